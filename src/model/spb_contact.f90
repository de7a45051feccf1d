!> Collisions (5.1)-(5.7) and the rigid base (doc/method.md, "Collisions" and "Rigid base and
!> dry interfaces").
!>
!> After the trial step every open section is tested for passing faces (5.1). The
!> collision is put on the grid by the timing rule: 'accelerate' joins at t^n, 'delay' at
!> t^{n+1}, 'min' takes the one with the smaller displacement correction (5.3). The paper's
!> rules shift one side rigidly by the correction (5.2) - the whole bar above the section
!> ('above') or only the colliding fragment ('fragment'); the lower side where the upper one
!> is anchored -, the admissible ones both sides about their common centre of mass; then the
!> node's halves join with conserved momentum (5.4).
!>
!> Joining at t^n and stepping is linear in the increments: the joined node's increment is
!> the mass-weighted mean of its halves' trial increments. So 'accelerate' is applied to
!> the trial step locally (the shifted fragment, the node, its two cells), never by redoing
!> the step for the whole bar.
!>
!> The rule set is chosen here, once per step: the paper's (spb_rules_paper) or the
!> admissible one (spb_rules_admissible); the join both end with is spb_fragments join_node.
module spb_contact
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t
   use spb_events, only: event_list_t
   use spb_base, only: touch_base
   use spb_rules_paper, only: paper_collisions
   use spb_rules_admissible, only: admissible_collisions
   use spb_problem, only: events_admissible, timing_accelerate, timing_delay, timing_min, &
      shift_above, shift_fragment
   implicit none
   private
   public :: contact_step, timing_accelerate, timing_delay, timing_min, shift_above, &
      shift_fragment

contains

   !> Test every open section (and the base) after the trial step; join what collides by the
   !> rule set given; an open cohesive crack is no collision (its faces' contact is the
   !> crack's own).
   pure subroutine contact_step(mesh, st, g, timing, policy, events, i_top, i_bot, rules, eps_rel)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g                !! gravity [m/s^2]
      integer, intent(in) :: timing            !! timing_* rule
      integer, intent(in) :: policy            !! shift_* policy
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top            !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot            !! bottom face-load integral over the step [Pa s]
      integer, intent(in) :: rules             !! events_admissible | events_paper
      real(wp), intent(in) :: eps_rel          !! admissible: faces collide when they overlap
                                               !! by more than eps_rel dx (round-off) [-]
      st%n_skip = 0
      select case (rules)
      case (events_admissible)
         call admissible_collisions(mesh, st, g, timing, policy, events, i_top, i_bot, eps_rel)
      case default
         call paper_collisions(mesh, st, g, timing, policy, events, i_top, i_bot)
      end select
      ! the rigid base an end face may land on (spb_base)
      call touch_base(mesh, st, g, timing, policy, events, i_top, i_bot, rules, eps_rel)
   end subroutine contact_step
end module spb_contact
