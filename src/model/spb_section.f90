!> Section stress at a node at half steps, (3.1)-(3.2) (METHOD.md §4).
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

   !> (3.1)1 and (3.2)1: from the cell above (stress s_above, impedance z_above, mass dm_above).
   pure elemental real(wp) function section_stress_a(s_above, s_prev, v_n, v_np1, z_above, &
                                                     dm_above, g) result(s_new)
      real(wp), intent(in) :: s_above    !! stress of the cell above at t^n [Pa]
      real(wp), intent(in) :: s_prev     !! section stress S^{n-1/2} [Pa]
      real(wp), intent(in) :: v_n        !! node velocity v^n (mean over the step ending at t^n) [m/s]
      real(wp), intent(in) :: v_np1      !! node velocity v^{n+1} [m/s]
      real(wp), intent(in) :: z_above    !! impedance of the cell above [kg/(m^2 s)]
      real(wp), intent(in) :: dm_above   !! mass of the cell above [kg/m^2]
      real(wp), intent(in) :: g          !! gravity along +x [m/s^2]
      real(wp) :: v_a
      v_a = v_n + (s_above - s_prev + 0.5_wp * dm_above * g) / z_above        ! (3.1)1
      s_new = s_above + z_above * (v_a - v_np1) + 0.5_wp * dm_above * g       ! (3.2)1
   end function section_stress_a

   !> (3.1)2 and (3.2)2: from the cell below.
   pure elemental real(wp) function section_stress_b(s_below, s_prev, v_n, v_np1, z_below, &
                                                     dm_below, g) result(s_new)
      real(wp), intent(in) :: s_below    !! stress of the cell below at t^n [Pa]
      real(wp), intent(in) :: s_prev     !! section stress S^{n-1/2} [Pa]
      real(wp), intent(in) :: v_n        !! node velocity v^n [m/s]
      real(wp), intent(in) :: v_np1      !! node velocity v^{n+1} [m/s]
      real(wp), intent(in) :: z_below    !! impedance of the cell below [kg/(m^2 s)]
      real(wp), intent(in) :: dm_below   !! mass of the cell below [kg/m^2]
      real(wp), intent(in) :: g          !! gravity along +x [m/s^2]
      real(wp) :: v_b
      v_b = v_n + (s_prev - s_below + 0.5_wp * dm_below * g) / z_below        ! (3.1)2
      s_new = s_below - z_below * (v_b - v_np1) - 0.5_wp * dm_below * g       ! (3.2)2
   end function section_stress_b
end module spb_section
