!> The running balances of a run: the work done on the bar, the energy that events removed
!> or changed, and the impulses of the momentum balance (the history's ledger columns;
!> doc/outputs.md). The state carries one (state_t%ledger); every stage books into it.
module spb_ledger
   use spb_kinds, only: wp
   use spb_columns, only: column_set_t, add_column
   implicit none
   private
   public :: ledger_t, ledger_columns_t, register_ledger_columns, post_ledger_columns

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
      real(wp) :: m_drift = 0.0_wp            !! mass times displacement that corrections moved
                                              !! without momentum: rigid shifts (shift_span),
                                              !! regions set on their path (shift_late), landings
                                              !! at t^{n+1} (spb_base join_base); / the bar's
                                              !! mass, the history's x_drift [kg/m A]
   end type ledger_t

   !> The ledger's history columns (PREFIX.his, /history): their ids (spb_columns).
   type :: ledger_columns_t
      integer :: w_load = 0, w_transmit = 0, e_fracture = 0, e_join = 0, e_shift = 0
      integer :: e_contact = 0, i_ends = 0, i_support = 0, p_shift = 0, w_cohesive = 0
   end type ledger_columns_t

contains

   !> Register the ledger's history columns (their meaning: doc/outputs.md).
   pure subroutine register_ledger_columns(set, id)
      type(column_set_t), intent(inout) :: set   !! the history's columns
      type(ledger_columns_t), intent(out) :: id   !! their ids
      call add_column(set, id%w_load, 'w_load', 'J/m^2')
      call add_column(set, id%w_transmit, 'w_transmit', 'J/m^2')
      call add_column(set, id%e_fracture, 'e_fracture', 'J/m^2')
      call add_column(set, id%e_join, 'e_join', 'J/m^2')
      call add_column(set, id%e_shift, 'e_shift', 'J/m^2')
      call add_column(set, id%e_contact, 'e_contact', 'J/m^2')
      call add_column(set, id%i_ends, 'i_ends', 'kg/(m s)')
      call add_column(set, id%i_support, 'i_support', 'kg/(m s)')
      call add_column(set, id%p_shift, 'p_shift', 'kg/(m s)')
      call add_column(set, id%w_cohesive, 'w_cohesive', 'J/m^2')
   end subroutine register_ledger_columns

   !> Post the ledger's values into a history row.
   pure subroutine post_ledger_columns(id, ledger, row)
      type(ledger_columns_t), intent(in) :: id   !! the columns' ids
      type(ledger_t), intent(in) :: ledger       !! the running balances
      real(wp), intent(inout) :: row(:)          !! the row
      row(id%w_load) = ledger%w_load
      row(id%w_transmit) = ledger%w_transmit
      row(id%e_fracture) = ledger%e_fracture
      row(id%e_join) = ledger%e_join
      row(id%e_shift) = ledger%e_shift
      row(id%e_contact) = ledger%e_contact
      row(id%i_ends) = ledger%i_ends
      row(id%i_support) = ledger%i_support
      row(id%p_shift) = ledger%p_shift
      row(id%w_cohesive) = ledger%w_cohesive
   end subroutine post_ledger_columns
end module spb_ledger
