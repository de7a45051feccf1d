!> Collisions (5.1)-(5.7) and the rigid base (doc/method.md, "Collisions" and "Rigid base and
!> dry interfaces").
!>
!> After the trial step every open section is tested for passing faces (5.1). The
!> collision is put on the grid by the timing rule: 'accelerate' joins at t^n, 'delay' at
!> t^{n+1}, 'min' takes the one with the smaller displacement correction (5.3). One side
!> is shifted rigidly by the correction (5.2) - the whole bar above the section ('above')
!> or only the colliding fragment ('fragment'); the lower side where the upper one is
!> anchored - and the node's halves join with conserved momentum (5.4).
!>
!> Joining at t^n and stepping is linear in the increments: the joined node's increment is
!> the mass-weighted mean of its halves' trial increments. So 'accelerate' is applied to
!> the trial step locally (the shifted fragment, the node, its two cells), never by redoing
!> the step for the whole bar.
module spb_contact
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, face_bottom, has_base
   use spb_state, only: state_t, close_node
   use spb_section, only: section_stress_a
   use spb_events, only: event_t, event_list_t, ev_collision
   use spb_fragments, only: node_energy, fragment_span, shift_span, span_mass, new_fragment_id, &
      anchored, choose_time, du_before_a, du_before_b, path_speed, shift_late, shift_part, &
      extend_up, extend_down, finish_event, book_shift_work, skip_next, keep_credit
   use spb_base, only: touch_base
   use spb_wave, only: region_wave
   use spb_problem, only: events_admissible, timing_accelerate, timing_delay, timing_min, &
      shift_above, shift_fragment
   implicit none
   private
   public :: contact_step, timing_accelerate, timing_delay, timing_min, shift_above, &
      shift_fragment


contains

   !> (5.6): stress in the section of a collision between halves moving at v_a (above)
   !> and v_b (below), with alpha = Z_below / Z_above.
   pure real(wp) function collision_stress(s_above, s_below, v_a, v_b, z_above, z_below) result(sz)
      real(wp), intent(in) :: s_above      !! stress of the cell above the node [Pa]
      real(wp), intent(in) :: s_below      !! stress of the cell below the node [Pa]
      real(wp), intent(in) :: v_a          !! velocity of the upper half along +x [m/s]
      real(wp), intent(in) :: v_b          !! velocity of the lower half along +x [m/s]
      real(wp), intent(in) :: z_above      !! impedance of the cell above [kg/(m^2 s)]
      real(wp), intent(in) :: z_below      !! impedance of the cell below [kg/(m^2 s)]
      real(wp) :: alpha
      alpha = z_below / z_above
      sz = (2.0_wp * (alpha * s_above + s_below) + (v_a - v_b) * z_below) / (alpha + 1.0_wp)
   end function collision_stress

   !> Whether split node i is a cohesive crack that still carries traction (its faces'
   !> contact is the crack's own, spb_cohesive).
   pure logical function cohesive_open(st, i)
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! split node
      cohesive_open = .false.
      if (st%coh%on) cohesive_open = st%coh%active(i)
   end function cohesive_open

   !> Test every open section (and the base) after the trial step; join what collides; an
   !> open cohesive crack is no collision (its faces' contact is the crack's own).
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
      real(wp) :: e_wave0, tol
      integer :: r_top, r_bot
      integer :: open_nodes(st%n_split)
      real(wp) :: overlap(st%n_split)
      integer :: c, i, m, nc, pass
      st%n_skip = 0
      ! the open sections in ascending order; a join removes only its own node from the list
      open_nodes = st%split(1:st%n_split)
      if (rules == events_admissible) then
         ! admissible: the overlapping ones, largest overlap first (an order that a mirrored
         ! bar sees the same way; a correction can close or open the next one's overlap)
         nc = 0
         do c = 1, size(open_nodes)
            i = open_nodes(c)
            if (.not. (st%ua(i) - st%ub(i) > eps_rel * min(mesh%dx(i), mesh%dx(i + 1)))) cycle
            if (cohesive_open(st, i)) cycle
            nc = nc + 1
            m = nc
            do while (m > 1)
               if (overlap(m - 1) >= st%ua(i) - st%ub(i)) exit
               overlap(m) = overlap(m - 1)
               open_nodes(m) = open_nodes(m - 1)
               m = m - 1
            end do
            overlap(m) = st%ua(i) - st%ub(i)
            open_nodes(m) = i
         end do
         open_nodes(nc + 1:) = 0
      end if
      ! admissible: the joins at t^n first, then those at t^{n+1} (a fragment joined at
      ! t^{n+1} has no state at t^n for a later join of the step at t^n)
      do pass = 1, merge(2, 1, rules == events_admissible)
      do c = 1, size(open_nodes)
         if (open_nodes(c) == 0) exit
         i = open_nodes(c)
         ! a cohesive crack's faces keep themselves apart (spb_cohesive): no collision
         if (cohesive_open(st, i)) cycle
         tol = 0.0_wp
         if (rules == events_admissible) tol = eps_rel * min(mesh%dx(i), mesh%dx(i + 1))
         if (rules == events_admissible .and. pass == 1 .and. st%ua(i) - st%ub(i) > tol) then
            if (.not. joins_at_n(mesh, st, g, timing, policy, i, i_top, i_bot, tol)) cycle
         end if
         if (st%ua(i) - st%ub(i) > tol) then
            if (rules == events_admissible) then
               ! the two fragments; what is shifted beyond them moves rigidly and books its
               ! gravity energy itself (shift_both_sides)
               call fragment_span(mesh, st, i, r_top, r_bot)
            else
               call event_region(mesh, st, g, timing, policy, rules, i, r_top, r_bot, i_top, &
                                 i_bot)
            end if
            e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
            call collide(mesh, st, g, timing, policy, i, events, rules, i_top, i_bot, tol)
            if (rules == events_admissible) call keep_credit(mesh, st, g, i_top, i_bot, e_wave0)
            st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                             region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
         end if
      end do
      end do
      ! the rigid base the bottom face may land on (spb_base)
      call touch_base(mesh, st, g, timing, policy, events, i_top, i_bot, rules, eps_rel)
   end subroutine contact_step

   !> The correction (5.2) that closes the gap at t^n, u_A^n - u_B^n, where an overlap at t^n
   !> within the contact tolerance counts as touching: the faces met then (to round-off), and
   !> moving a side by that much would only lift it.
   pure real(wp) function gap_at_n(st, i, tol) result(d_acc)
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! split node
      real(wp), intent(in) :: tol              !! contact tolerance [m] (0: the paper's rules)
      d_acc = (st%ua(i) - st%dua(i)) - (st%ub(i) - st%dub(i))
      if (d_acc > 0.0_wp .and. d_acc <= tol) d_acc = 0.0_wp
   end function gap_at_n

   !> Whether the admissible rules join split node i at t^n (as collide would decide now).
   pure logical function joins_at_n(mesh, st, g, timing, policy, i, i_top, i_bot, tol) result(at_n)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      real(wp), intent(in) :: tol              !! contact tolerance [m]
      real(wp) :: d_acc, d_del, corr, x, y
      integer :: top, bot
      d_acc = gap_at_n(st, i, tol)
      d_del = st%ua(i) - st%ub(i)
      call choose_time(timing, d_acc, d_del, at_n, corr)
      call plan_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, top, bot, x, y, &
                           i_top, i_bot)
   end function joins_at_n

   !> Fragment boundaries around everything a collision at split node i (or a landing, i = n)
   !> can change: the two fragments and whatever either correction (5.2) shifts; the whole
   !> bar for 'above'.
   pure subroutine event_region(mesh, st, g, timing, policy, rules, i, r_top, r_bot, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: rules         !! event rules (events_*)
      integer, intent(in) :: i             !! split node
      integer, intent(out) :: r_top        !! top node of the region the event can change
      integer, intent(out) :: r_bot        !! bottom node of that region
      real(wp) :: d_acc, d_del, amount, corr, x, y
      integer :: j, k, top, bot
      logical :: at_n
      r_top = 0
      r_bot = mesh%n
      if (policy == shift_above) return
      if (rules == events_admissible .and. i < mesh%n) then
         call fragment_span(mesh, st, i, j, k)
         d_acc = (st%ua(i) - st%dua(i)) - (st%ub(i) - st%dub(i))
         d_del = st%ua(i) - st%ub(i)
         call choose_time(timing, d_acc, d_del, at_n, corr)
         call plan_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, top, bot, x, y, &
                              i_top, i_bot)
         r_top = min(j, top)
         r_bot = max(k, bot)
         return
      end if
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
   pure subroutine collide(mesh, st, g, timing, policy, i, events, rules, i_top, i_bot, tol)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(in) :: tol              !! contact tolerance [m] (0: the paper's rules)
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      integer, intent(in) :: rules         !! event rules (events_*)
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp) :: dua0, dub0, d_acc, d_del, corr, mass_a, mass_b, du_join, e0, de, sz, v_a, v_b
      real(wp) :: du_a_trial, du_b_trial, shift_amount, w, closing
      integer :: j, k, top, bot, parent_up, parent_dn
      logical :: at_n, ok
      type(event_t) :: ev

      dua0 = du_before_a(mesh, st, g, i)
      dub0 = du_before_b(mesh, st, g, i)
      ! (5.2): corrections that close the gap at t^n or remove the overlap at t^{n+1}
      d_acc = gap_at_n(st, i, tol)                          ! u_A^n - u_B^n (< 0: a gap)
      d_del = st%ua(i) - st%ub(i)                                 ! u_A^{n+1} - u_B^{n+1} > 0
      call choose_time(timing, d_acc, d_del, at_n, corr)
      if (rules == events_admissible) then
         call shift_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, shift_amount, &
                               i_top, i_bot)
      else
         call shift_side(mesh, st, policy, i, corr, top, bot, shift_amount)
      end if
      if (.not. at_n .and. rules /= events_admissible) then
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
      if (abs(shift_amount) > 0.0_wp .and. rules /= events_admissible) then
         if (at_n) then
            call shift_span(mesh, st, g, top, bot, shift_amount, de)
            st%ledger%e_shift = st%ledger%e_shift - de
         else
            call shift_late(mesh, st, g, top, bot, shift_amount, w)
         end if
      end if
      ! collision stress (5.6) at the joining time, and its error bound (6.2)
      if (at_n) then
         v_a = dua0 / mesh%dt
         v_b = dub0 / mesh%dt
         sz = collision_stress(st%s_old(i), st%s_old(i + 1), v_a, v_b, mesh%z(i), mesh%z(i + 1))
      else
         v_a = st%dua(i) / mesh%dt
         v_b = st%dub(i) / mesh%dt
         sz = collision_stress(st%s(i), st%s(i + 1), v_a, v_b, mesh%z(i), mesh%z(i + 1))
      end if
      ev%kind = ev_collision
      ev%stress = sz
      ev%stress_bound = abs(2.0_wp * (mesh%z(i + 1) / mesh%z(i) * st%s(i) + st%s(i + 1)) / &
                            (mesh%z(i + 1) / mesh%z(i) + 1.0_wp))
      ! (5.4): join with conserved momentum
      e0 = node_energy(mesh, st, g, i)
      mass_a = mesh%ma(i)
      mass_b = mesh%mb(i)
      du_a_trial = st%dua(i)
      du_b_trial = st%dub(i)
      du_join = (mass_a * du_a_trial + mass_b * du_b_trial) / (mass_a + mass_b)
      call close_node(st, i)
      st%dua(i) = du_join
      st%dub(i) = du_join
      if (at_n) then
         ! joined at t^n: the step just taken is the joined node's; its cells see the mean
         ! increment, its section the collision stress S^{n+1/2} ((3.2) with S^{n-1/2} = 0)
         st%ua(i) = st%ua(i) - du_a_trial + du_join
         st%ub(i) = st%ub(i) - du_b_trial + du_join
         st%s(i) = st%s(i) + mesh%stiff(i) * (du_a_trial - du_join)
         st%s(i + 1) = st%s(i + 1) + mesh%stiff(i + 1) * (du_join - du_b_trial)
         st%section(i) = section_stress_a(st%s_old(i), 0.0_wp, v_a, du_join / mesh%dt, mesh%z(i), &
                                      mesh%dm(i), g)
      else
         ! joined at t^{n+1}: positions and stresses at t^{n+1} stay, the increment becomes
         ! the mean, so the step in effect ended from other u^n, s^n: s_old follows (it only
         ! enters the energy measure), which keeps s^{n+1} - s^n = E/dx (du_{k-1} - du_k) and
         ! with it the ledger's telescoping exact.
         st%s_old(i) = st%s_old(i) + mesh%stiff(i) * (du_join - du_a_trial)
         st%s_old(i + 1) = st%s_old(i + 1) - mesh%stiff(i + 1) * (du_join - du_b_trial)
         ! the next step computes the collision stress; this S^{n-1/2} makes (3.1) start
         ! from the upper half's own velocity with zero section stress
         st%section(i) = mesh%z(i) * (du_join - du_a_trial) / mesh%dt
         call skip_next(st, i)
      end if
      ! the halves now share one position (a shift closed the gap; if both sides were
      ! anchored a length defect of |corr| stays in the displacements, not the stresses)
      st%ledger%e_join = st%ledger%e_join + (e0 - node_energy(mesh, st, g, i))
      st%n_breakable = st%n_breakable + 1
      ! genealogy: the merged fragment is new, its parent the upper one
      call fragment_span(mesh, st, i, j, k)
      parent_up = st%gen%frag_id(j)
      parent_dn = st%gen%frag_id(i)
      st%gen%frag_id(i) = 0
      call new_fragment_id(st, parent_up, j)
      call finish_event(mesh, st, ev, i, at_n, corr, shift_amount, st%gen%frag_id(j), parent_dn, events)
   end subroutine collide

   !> The admissible correction of a collision at split node i: both sides move rigidly so
   !> that their faces meet and their common centre of mass stays (upper by -d M_l/(M_u + M_l),
   !> lower by +d M_u/(M_u + M_l), d the chosen (5.2) correction): no direction is preferred
   !> (mirror), only relative displacements count (Galilean), gravity does no work on it (free
   !> fall). The sides are the two colliding fragments ('fragment') or all of the bar on each
   !> side ('above'), each taking along what it would be pushed into. An anchored side does
   !> not move and the other takes the whole correction, at the time (t^n or t^{n+1}) whose
   !> correction does not lift it against gravity; with both anchored nothing moves and the
   !> join is at t^n (the faces then keep the small gap they had: never an overlap).
   pure subroutine shift_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, moved, &
                                    i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: d_acc        !! correction (5.2) for a join at t^n [m]
      real(wp), intent(in) :: d_del        !! correction (5.2) for a join at t^{n+1} [m]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      logical, intent(inout) :: at_n       !! join at t^n (else t^{n+1}); updated to the time used
      real(wp), intent(inout) :: corr      !! chosen correction (5.2); updated to the one used [m]
      real(wp), intent(out) :: moved         !! shift of the upper side (of the lower one where the
                                             !! upper stays) [m]
      integer :: top, bot, j, k
      real(wp) :: x, y
      call plan_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, top, bot, x, y, &
                              i_top, i_bot)
      call fragment_span(mesh, st, i, j, k)
      moved = -x
      if (abs(x) > 0.0_wp) then
         if (top < j) call shift_part(mesh, st, g, top, j, -x, .true.)
         call shift_part(mesh, st, g, max(top, j), i, -x, .false.)
         ! the load on a face the shift moves does its work on the move; the bar's energy
         ! does not change, so that work is what the event removes
         if (top == 0) call book_shift_work(st, -i_top / mesh%dt * x)
      end if
      if (abs(y) > 0.0_wp) then
         call shift_part(mesh, st, g, i, min(bot, k), y, .false.)
         if (bot > k) call shift_part(mesh, st, g, k, bot, y, .true.)
         if (bot == mesh%n) call book_shift_work(st, -i_bot / mesh%dt * y)
         if (.not. abs(x) > 0.0_wp) moved = y
      end if
   end subroutine shift_both_sides

   !> What shift_both_sides moves: the upper side top..i by -x, the lower side i..bot by +y,
   !> at the time (at_n) and with the correction (corr) it settles on.
   pure subroutine plan_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, top, bot, &
                                   x, y, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: d_acc        !! correction (5.2) for a join at t^n [m]
      real(wp), intent(in) :: d_del        !! correction (5.2) for a join at t^{n+1} [m]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
                                           !! (a side holding a loaded face moves only along it)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      logical, intent(inout) :: at_n       !! join at t^n (else t^{n+1}); updated to the time used
      real(wp), intent(inout) :: corr      !! chosen correction (5.2); updated to the one used [m]
      integer, intent(out) :: top          !! top node of the upper side
      integer, intent(out) :: bot          !! bottom node of the lower side
      real(wp), intent(out) :: x           !! the upper side moves by -x [m]
      real(wp), intent(out) :: y           !! the lower side moves by +y [m]
      integer :: j, k, pass
      real(wp) :: m_u, m_l, bias, other
      logical :: anch_u, anch_l, blocked, blocked_u, lift
      call fragment_span(mesh, st, i, j, k)
      if (policy == shift_above) then
         j = 0
         k = mesh%n
      end if
      top = j
      bot = k
      x = 0.0_wp
      y = 0.0_wp
      blocked = .false.
      blocked_u = .false.
      ! until the sides take along nothing more (each pass adds at least a fragment)
      do pass = 1, mesh%n + 1
         anch_u = anchored(mesh, st, top, i) .or. blocked_u
         anch_l = anchored(mesh, st, i, bot) .or. blocked
         ! a side that a load pushes towards the other moves only along it (moved back against
         ! it, the load would do its work again): the faces meet at t^n, closing the gap
         if (.not. (anch_u .or. anch_l) .and. ((top == 0 .and. i_top > 0.0_wp) .or. &
             (bot == mesh%n .and. i_bot > 0.0_wp)) .and. .not. at_n) then
            at_n = .true.
            corr = d_acc
         end if
         if (anch_u .and. anch_l) then
            at_n = .true.
            corr = d_acc
            x = 0.0_wp
            y = 0.0_wp
         else if (anch_u .or. anch_l) then
            ! the free side moves by +corr (lower) or -corr (upper), down is +x; it must not
            ! move against gravity and a load on its face (bias: their push along +x)
            if (anch_u) then
               bias = g * span_mass(mesh, i, bot) * mesh%dt
               if (bot == mesh%n) bias = bias - i_bot
            else
               bias = -g * span_mass(mesh, top, i) * mesh%dt
               if (top == 0) bias = bias - i_top
            end if
            ! (bias now along the free side's move by +corr)
            lift = bias * corr < 0.0_wp
            other = merge(d_del, d_acc, at_n)
            if (lift .and. (.not. bias * other < 0.0_wp .or. abs(other) < abs(corr))) then
               ! its move would go against gravity and the load: the other time's correction
               ! moves it along them (or, if both go against, the smaller one)
               at_n = .not. at_n
               corr = other
            end if
            x = merge(0.0_wp, corr, anch_u)
            y = merge(corr, 0.0_wp, anch_u)
         else
            m_u = span_mass(mesh, top, i)
            m_l = span_mass(mesh, i, bot)
            x = corr * m_l / (m_u + m_l)
            y = corr - x
         end if
         ! a lower side that reaches the base and would be pushed into it stays, as if held
         if (.not. anch_l .and. bot == mesh%n .and. has_base(st%ends(face_bottom)) .and. &
             y > 0.0_wp) then
            if (st%ua(mesh%n) + y - st%ends(face_bottom)%u_contact > 0.0_wp) then
               blocked = .true.
               cycle
            end if
         end if
         ! the same for an upper side that reaches a base above the bar (moved up by x > 0)
         if (.not. anch_u .and. top == 0 .and. has_base(st%ends(face_top)) .and. &
             x > 0.0_wp) then
            if (st%ends(face_top)%u_contact - (st%ub(0) - x) > 0.0_wp) then
               blocked_u = .true.
               cycle
            end if
         end if
         ! a side pushed into its neighbour takes it along; then the masses change
         j = top
         k = bot
         if (.not. anch_u .and. top > 0) call extend_up(mesh, st, top, -x)
         if (.not. anch_l .and. bot < mesh%n) call extend_down(mesh, st, bot, y)
         if (top == j .and. bot == k) exit
      end do
   end subroutine plan_both_sides

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

end module spb_contact
