!> The running balances of a run: the work done on the bar, the energy that events removed
!> or changed, and the impulses of the momentum balance (the history's ledger columns;
!> doc/outputs.md). The state carries one (state_t%ledger); every stage books into it.
module spb_ledger
   use spb_kinds, only: wp
   implicit none
   private
   public :: ledger_t

   !> The running balances: work done on the bar, energy that events removed or changed,
   !> and the impulses of the momentum balance (the history's ledger columns).
   type :: ledger_t
      real(wp) :: w_load = 0.0_wp             !! work of the end loads so far [J/m^2]
      real(wp) :: w_transmit = 0.0_wp         !! work of transmitting ends so far [J/m^2]
      real(wp) :: w_support = 0.0_wp          !! work of constant-velocity ends so far [J/m^2]
      real(wp) :: e_fracture = 0.0_wp         !! energy removed by fracture corrections [J/m^2]
      real(wp) :: e_join = 0.0_wp             !! energy removed by joins (collisions) [J/m^2]
      real(wp) :: e_shift = 0.0_wp            !! gravity energy changed by collision shifts [J/m^2]
      real(wp) :: e_contact = 0.0_wp          !! energy the cut springs' non-linear force
                                              !! removed from the scheme's invariant [J/m^2]
      real(wp) :: w_wave = 0.0_wp             !! work of the loads and transmitting ends on the
                                              !! continuum state (spb_wave) [J/m^2]
      real(wp) :: e_lost_wave = 0.0_wp        !! wave energy (with its gravity term) that events
                                              !! removed [J/m^2]
      real(wp) :: p_shift = 0.0_wp            !! momentum collision shifts gave the shifted
                                              !! masses, moving them along their path [kg/(m s)]
      real(wp) :: i_ends = 0.0_wp             !! impulse of the end stresses (loads and
                                              !! transmitting ends) on the end nodes [kg/(m s)]
      real(wp) :: i_support = 0.0_wp          !! impulse of the supports (fixed and
                                              !! constant-velocity ends, the base): the
                                              !! momentum they took [kg/(m s)]
      real(wp) :: w_cohesive = 0.0_wp         !! work the cohesive tractions took from the
                                              !! waves, sum of I (delta^{n+1} - delta^n)/dt:
                                              !! dissipated plus held by the cracks (spb_cohesive;
                                              !! in w_wave with the other sign) [J/m^2]
      real(wp) :: e_closing = 0.0_wp          !! of w_cohesive, what closing faces' contact took
                                              !! beyond the law's integral (>= 0) [J/m^2]
      real(wp) :: e_impactor = 0.0_wp         !! energy a striking mass's contact removed from
                                              !! the scheme's invariant: what the mass lost
                                              !! beyond the work F^n (u^{n+1} - u^{n-1})/2 the
                                              !! face stress did on the bar (spb_ends) [J/m^2]
      real(wp) :: e_traction = 0.0_wp         !! the same work in the scheme's own measure,
                                              !! P^n (delta^{n+1} - delta^{n-1})/2 (in e_lost) [J/m^2]
   end type ledger_t
end module spb_ledger
