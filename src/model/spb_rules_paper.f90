!> The paper's event rules (`&run events = 'paper'`; doc/method.md, "Fracture" and
!> "Collisions"): a collision shifts one side (the upper one, or the lower one where the
!> upper is anchored) by the timing rule's correction (5.2), a join at t^{n+1} moves it on
!> its path (shift_late); a break is stage 1 (the section stress released into the two
!> cells) and stage 2 (rigid shifts that open the faces by (dA + dB)/2). Chosen in one place:
!> spb_contact contact_step and spb_fracture fracture_step; what both rule sets share is in
!> spb_fragments. Exact contact: the faces collide when they overlap at all.
module spb_rules_paper
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t
   use spb_events, only: event_list_t
   use spb_fragments, only: fragment_span, shift_span, anchored, path_speed, shift_late, &
      extend_up, extend_down, cohesive_open, start_collision, join_node, open_section, &
      record_break
   use spb_wave, only: region_wave
   use spb_problem, only: shift_above
   implicit none
   private
   public :: paper_collisions, paper_breaks

contains

   !> The collisions of the step by the paper's rules: every open section, top to bottom, in
   !> one pass; the wave measure of the region each can change, before and after, booked in
   !> e_lost_wave.
   pure subroutine paper_collisions(mesh, st, g, timing, policy, events, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g                !! gravity [m/s^2]
      integer, intent(in) :: timing            !! timing_* rule
      integer, intent(in) :: policy            !! shift_* policy
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top            !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot            !! bottom face-load integral over the step [Pa s]
      real(wp) :: e_wave0
      integer :: r_top, r_bot
      integer :: open_nodes(st%n_split)
      integer :: c, i
      ! the open sections in ascending order; a join removes only its own node from the list
      open_nodes = st%split(1:st%n_split)
      do c = 1, size(open_nodes)
         if (open_nodes(c) == 0) exit
         i = open_nodes(c)
         ! a cohesive crack's faces keep themselves apart (spb_cohesive): no collision
         if (cohesive_open(st, i)) cycle
         if (st%ua(i) - st%ub(i) > 0.0_wp) then
            call event_region(mesh, st, policy, i, r_top, r_bot)
            e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
            call collide(mesh, st, g, timing, policy, i, events)
            st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                             region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
         end if
      end do
   end subroutine paper_collisions

   !> Fragment boundaries around everything a collision at split node i can change: the two
   !> fragments and whatever either correction (5.2) shifts; the whole bar for 'above'.
   pure subroutine event_region(mesh, st, policy, i, r_top, r_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      integer, intent(out) :: r_top        !! top node of the region the event can change
      integer, intent(out) :: r_bot        !! bottom node of that region
      real(wp) :: d_acc, d_del, amount
      integer :: j, k, top, bot
      r_top = 0
      r_bot = mesh%n
      if (policy == shift_above) return
      call fragment_span(mesh, st, i, j, k)
      d_acc = (st%ua(i) - st%dua(i)) - (st%ub(i) - st%dub(i))
      d_del = st%ua(i) - st%ub(i)
      r_top = j
      r_bot = k
      call shift_side(mesh, st, policy, i, d_acc, top, bot, amount)
      r_top = min(r_top, top)
      r_bot = max(r_bot, bot)
      call shift_side(mesh, st, policy, i, d_del, top, bot, amount)
      r_top = min(r_top, top)
      r_bot = max(r_bot, bot)
   end subroutine event_region

   !> Choose the rule's time, shift one side, join node i.
   pure subroutine collide(mesh, st, g, timing, policy, i, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp) :: du0(2), d_acc, d_del, corr, de, shift_amount, w, closing
      integer :: top, bot
      logical :: at_n, ok
      call start_collision(mesh, st, g, timing, i, 0.0_wp, du0, d_acc, d_del, at_n, corr)
      call shift_side(mesh, st, policy, i, corr, top, bot, shift_amount)
      if (.not. at_n) then
         ! a join at t^{n+1} moves the shifted region on its path (shift_late); where no
         ! path leads there, or the join would create energy, it is joined at t^n
         call path_speed(mesh, st, g, top, bot, shift_amount, w, ok)
         closing = st%dua(i) - st%dub(i)
         if (bot == i) closing = closing + w * mesh%dt
         if (top == i) closing = closing - w * mesh%dt
         if (.not. ok .or. late_join_energy(mesh, st, i, closing) > 0.0_wp) then
            at_n = .true.
            corr = d_acc
            call shift_side(mesh, st, policy, i, corr, top, bot, shift_amount)
         end if
      end if
      if (abs(shift_amount) > 0.0_wp) then
         if (at_n) then
            call shift_span(mesh, st, g, top, bot, shift_amount, de)
            st%ledger%e_shift = st%ledger%e_shift - de
         else
            call shift_late(mesh, st, g, top, bot, shift_amount, w)
         end if
      end if
      call join_node(mesh, st, g, i, at_n, corr, shift_amount, du0, events)
   end subroutine collide

   !> The side a correction corr (5.2) moves at split node i: the upper one (the fragment
   !> ending at A_i, or all above it for 'above'), the lower one where the upper is
   !> anchored, none if both are; a shifted side takes along what it would be pushed into.
   pure subroutine shift_side(mesh, st, policy, i, corr, top, bot, shift_amount)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      real(wp), intent(in) :: corr         !! the chosen correction (5.2) [m]
      integer, intent(out) :: top              !! top node of the region moved, as for shift_span
      integer, intent(out) :: bot              !! bottom node of the region moved
      real(wp), intent(out) :: shift_amount    !! its shift along x [m] (0: none)
      integer :: j, k
      call fragment_span(mesh, st, i, j, k)
      if (policy == shift_above) then
         j = 0
         k = mesh%n
      end if
      top = i
      bot = i
      shift_amount = 0.0_wp
      if (.not. anchored(mesh, st, j, i)) then
         top = j
         shift_amount = -corr
         call extend_up(mesh, st, top, shift_amount)
      else if (.not. anchored(mesh, st, i, k)) then
         bot = k
         shift_amount = corr
         call extend_down(mesh, st, bot, shift_amount)
      end if
   end subroutine shift_side

   !> Energy that joining split node i at t^{n+1} adds (negative: dissipates), as booked in
   !> e_join: the momentum join's kinetic loss and the strain measure, whose s^n follows
   !> the joined increment. [J/m^2]
   pure real(wp) function late_join_energy(mesh, st, i, closing) result(de)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! split node
      real(wp), intent(in) :: closing          !! du_A - du_B over the step [m]
      real(wp) :: ma, mb
      ma = mesh%ma(i)
      mb = mesh%mb(i)
      de = -0.5_wp * ma * mb / (ma + mb) * (closing / mesh%dt)**2 &
           - 0.5_wp * closing * (mb * st%s(i) + ma * st%s(i + 1)) / (ma + mb)
   end function late_join_energy

   !> The paper's break (3.4)-(3.6) of the sections cand (ascending, joined, beyond their
   !> strength). Stage 1: each adjacent cell loses exactly S, the new faces are free (the
   !> halves receive opposite impulses -/+ S dt/2). Stage 2: the two new fragments shift
   !> rigidly so that the opening becomes (dA + dB)/2; an anchored fragment (holding a fixed
   !> or a constant-velocity end) does not move and the other one takes the whole correction.
   pure subroutine paper_breaks(mesh, st, g, cand, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g          !! gravity [m/s^2]
      integer, intent(in) :: cand(:)     !! the sections to break, ascending
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp) :: d_a(size(cand)), d_b(size(cand)), s_brk(size(cand))
      real(wp) :: dt2, de, shift_up, shift_dn
      integer :: i, m, j, k
      logical :: anchored_up, anchored_dn
      dt2 = mesh%dt**2
      ! stage 1, (3.4)-(3.6): each adjacent cell loses exactly S; the new faces are free
      do m = 1, size(cand)
         i = cand(m)
         s_brk(m) = st%section(i)
         d_a(m) = -s_brk(m) * dt2 / mesh%dm(i)
         d_b(m) = -s_brk(m) * dt2 / mesh%dm(i + 1)
         call open_section(mesh, st, g, i, -d_a(m), d_b(m), -s_brk(m), -s_brk(m))
      end do
      ! stage 2: the opening becomes (dA + dB)/2; an anchored fragment (holding a fixed or
      ! a constant-velocity end) does not move and the other one takes the whole correction
      do m = 1, size(cand)
         i = cand(m)
         call fragment_span(mesh, st, i, j, k)
         anchored_up = anchored(mesh, st, j, i)
         anchored_dn = anchored(mesh, st, i, k)
         shift_up = 0.5_wp * d_a(m)
         shift_dn = -0.5_wp * d_b(m)
         if (anchored_up .and. .not. anchored_dn) then
            shift_dn = shift_dn - shift_up
            shift_up = 0.0_wp
         else if (anchored_dn .and. .not. anchored_up) then
            shift_up = shift_up - shift_dn
            shift_dn = 0.0_wp
         else if (anchored_up .and. anchored_dn) then
            shift_up = 0.0_wp
            shift_dn = 0.0_wp
         end if
         call shift_span(mesh, st, g, j, i, shift_up, de)
         st%ledger%e_fracture = st%ledger%e_fracture - de
         call shift_span(mesh, st, g, i, k, shift_dn, de)
         st%ledger%e_fracture = st%ledger%e_fracture - de
         call record_break(mesh, st, i, j, s_brk(m), events)
      end do
   end subroutine paper_breaks
end module spb_rules_paper
