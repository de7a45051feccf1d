!> Diagnostics: the scheme's own energy invariant, momentum and the energy ledger.
!>
!> With v^{n+1} = du^{n+1}/dt, the discrete energy at t^{n+1/2},
!>   e_kin + e_strain = sum 0.5 m (v^{n+1})^2 + sum 0.5 (dx/E) s^n s^{n+1},
!> changes over a step by exactly the work F^n (u^{n+1} - u^{n-1})/2 of the nodal forces.
!> Gravity's part is -(change of e_pot) with e_pot = -g sum m (u^n + u^{n+1})/2; the end
!> stresses' part is w_ext. So e_kin + e_strain + e_pot - w_ext + e_lost is constant to
!> round-off (METHOD.md §3).
module spb_diag
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t
   implicit none
   private
   public :: energies_t, energies

   type :: energies_t
      real(wp) :: e_kin = 0.0_wp      !! [J/m^2]
      real(wp) :: e_strain = 0.0_wp   !! [J/m^2]
      real(wp) :: e_pot = 0.0_wp      !! gravity potential, zero at u = 0 [J/m^2]
      real(wp) :: w_ext = 0.0_wp      !! work of loads and transmitting ends [J/m^2]
      real(wp) :: e_lost = 0.0_wp     !! removed by events [J/m^2]
      real(wp) :: ledger = 0.0_wp     !! e_kin + e_strain + e_pot - w_ext + e_lost [J/m^2]
      real(wp) :: momentum = 0.0_wp   !! [kg/(m s)]
   end type energies_t

contains

   pure function energies(mesh, st, g) result(e)
      type(mesh_t), intent(in) :: mesh
      type(state_t), intent(in) :: st
      real(wp), intent(in) :: g       !! gravity [m/s^2]
      type(energies_t) :: e
      integer :: n
      real(wp) :: dt
      n = mesh%n
      dt = mesh%dt
      e%e_kin = 0.5_wp * sum(mesh%ma * st%dua**2 + mesh%mb * st%dub**2) / dt**2
      e%e_strain = 0.5_wp * sum(st%s_old(1:n) * st%s(1:n) / mesh%stiff)
      e%e_pot = 0.0_wp - g * sum(mesh%ma * (st%ua - 0.5_wp * st%dua) + mesh%mb * (st%ub - 0.5_wp * st%dub))
      e%w_ext = st%w_load + st%w_transmit
      e%e_lost = st%e_lost
      e%ledger = e%e_kin + e%e_strain + e%e_pot - e%w_ext + e%e_lost
      e%momentum = sum(mesh%ma * st%dua + mesh%mb * st%dub) / dt
   end function energies
end module spb_diag
