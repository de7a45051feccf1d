!> Time-dependent fracture, the Tuler-Butcher criterion (doc/method.md, "Time-dependent
!> fracture"): a section whose damage integral K > 0 breaks when
!>
!>     D = integral of (S - R)^lambda dt  >=  K
!>
!> over the time its tensile section stress S exceeds its strength R (S and R as tensile
!> magnitudes, in Pa). The section stress is constant over a step in the scheme (S^{n+1/2}
!> holds over the step it is tested for, doc/method.md "Section stresses at every node"), so
!> the integral of the step is exact for that piecewise-constant S: D += (S - R)^lambda dt,
!> the rectangle rule on the step, of first order in dt for a continuously varying S. The
!> state keeps D/K; a section breaks in the step that takes it to 1, when the brittle rule
!> would have broken it had its strength been reached then (the same test, the same timing).
module spb_damage
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t, node_area
   use spb_state, only: state_t
   implicit none
   private
   public :: damage_increment, damage_reached

   !> exp() of more than this would overflow: the step's damage is then beyond any K.
   real(wp), parameter :: log_huge = 700.0_wp

contains

   !> The damage of one step at a constant excess stress, as a share of K:
   !> excess^lambda dt / K [-], 0 where the excess is not > 0; computed in logarithms, so
   !> that no power of a stress overflows (it saturates at exp(700), far beyond 1).
   pure elemental real(wp) function damage_increment(excess, lambda, dt, k) result(dd)
      real(wp), intent(in) :: excess   !! S - R, the tension beyond the strength [Pa]
      real(wp), intent(in) :: lambda   !! the exponent lambda [-], > 0
      real(wp), intent(in) :: dt       !! the step [s]
      real(wp), intent(in) :: k        !! the damage integral K [Pa^lambda s], > 0
      dd = 0.0_wp
      if (.not. excess > 0.0_wp) return
      dd = exp(min(lambda * log(excess) + log(dt) - log(k), log_huge))
   end function damage_increment

   !> Whether section i, whose section stress S^{n+1/2} is beyond its strength (the brittle
   !> rule's test, passed), breaks in this step: at once where it has no damage integral (K
   !> = 0, and a section that has been open before: a separation); else its damage takes
   !> this step's share and it breaks once D/K reaches 1.
   pure subroutine damage_reached(mesh, st, i, ready)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state (the section's damage grows)
      integer, intent(in) :: i             !! the interior node
      logical, intent(out) :: ready        !! it breaks in this step
      real(wp) :: excess
      ready = .true.
      if (.not. st%dmg%on) return
      if (.not. st%dmg%k(i) > 0.0_wp .or. st%cracked(i)) return
      ! the model's stresses and strengths are forces A sigma (spb_mesh): over the section
      excess = (-st%section(i) - st%strength(i)) / node_area(mesh, i)
      st%dmg%d(i) = st%dmg%d(i) + damage_increment(excess, st%dmg%lambda(i), mesh%dt, &
                                                   st%dmg%k(i))
      ready = st%dmg%d(i) >= 1.0_wp
   end subroutine damage_reached
end module spb_damage
