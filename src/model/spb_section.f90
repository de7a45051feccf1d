!> Section stress at a node at half steps, (3.1)-(3.2) (doc/method.md, "Section stresses at
!> every node" and "Section stress at a support").
!>
!> S^{n+1/2} is the stress that holds in the node's characteristic section from
!> t^{n+1/2} to t^{n+3/2}. Both forms give the same value for a joined node; the A form
!> sees the cell above, the B form the cell below. A support (fixed end, rigid base) is
!> the A or B form with the support side at rest.
module spb_section
   use spb_kinds, only: wp
   implicit none
   private
   public :: section_stress_a, section_stress_b
contains
   include 'spb_section_form_a.inc'
   include 'spb_section_form_b.inc'
end module spb_section
