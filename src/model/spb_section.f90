!> Section stress at a node at half steps, (3.1)-(3.2) (doc/method.md, "Section stresses at
!> every node" and "Section stress at a support").
!>
!> S^{n+1/2} is the stress that holds in the node's characteristic section from
!> t^{n+1/2} to t^{n+3/2}. Both forms give the same value for a joined node; the A form
!> sees the cell above, the B form the cell below. A support (fixed end, rigid base) is
!> the A or B form with the support side at rest.
module spb_section
   use spb_step, only: section_stress_a, section_stress_b
   implicit none
   private
   public :: section_stress_a, section_stress_b
   ! The two forms live in spb_step, with the step that evaluates them for every breakable
   ! node each step: a call within one module is inlined (from another one it is not, and
   ! that step took 1.66 times as long: measured on input/long/expanding_bar_4m_2ms.nml).
end module spb_section
