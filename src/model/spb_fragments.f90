!> Fragments and the moves events make of them, what both rule sets (spb_rules_paper,
!> spb_rules_admissible), the rigid base (spb_base) and the full-mass model (spb_full_mass)
!> share: a fragment's span, mass, momentum and node energies; the rigid shifts of the
!> corrections (5.2) and their booking; the timing rule (5.2)-(5.3); the start and the join
!> of a collision (5.4)-(5.6); the opening of a section and the record of a break; fragment
!> ids; an event's time, place and correction; the landing credit of a bar held at both ends.
module spb_fragments
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, face_bottom, has_free_face, holds
   use spb_state, only: state_t, close_node, open_node
   use spb_section, only: section_stress_a
   use spb_events, only: event_t, event_list_t, push_event, ev_collision, ev_fracture, &
      ev_separation
   use spb_arrays, only: append
   use spb_wave, only: region_wave, held_odd, credit_bound, credit_position
   use spb_problem, only: timing_accelerate, timing_delay, timing_within
   implicit none
   private
   public :: node_energy, anchored, fragment_span, span_mass, shift_span, new_fragment_id
   public :: choose_time, du_before_a, du_before_b, span_momentum, end_force, path_speed, &
      shift_late, shift_part, extend_up, extend_down, finish_event, book_shift_work, skip_next, &
      keep_credit
   public :: cohesive_open, gap_at_n, start_collision, join_node, open_section, record_break
   public :: join_stress, move_faces, strain_faces

contains

   !> Energy terms that live at node i: kinetic and potential energy of its two halves and
   !> the strain energy of the cells on either side (the scheme's own forms, spb_diag).
   pure real(wp) function node_energy(mesh, st, g, i) result(e)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! node
      real(wp) :: dt
      dt = mesh%dt
      e = 0.5_wp * (mesh%ma(i) * st%dua(i)**2 + mesh%mb(i) * st%dub(i)**2) / dt**2 &
          - g * (mesh%ma(i) * (st%ua(i) - 0.5_wp * st%dua(i)) + mesh%mb(i) * (st%ub(i) - 0.5_wp * st%dub(i)))
      if (i >= 1) e = e + 0.5_wp * st%s_old(i) * st%s(i) / mesh%stiff(i)
      if (i <= mesh%n - 1) e = e + 0.5_wp * st%s_old(i + 1) * st%s(i + 1) / mesh%stiff(i + 1)
   end function node_energy

   !> Whether the region of nodes top..bot (its end halves as in shift_span) holds a
   !> support that a rigid shift cannot move: a fixed end, a constant-velocity end (its
   !> position is V t), or the base the bar rests on.
   pure logical function anchored(mesh, st, top, bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      anchored = (top == 0 .and. holds(st%ends(face_top))) .or. &
                 (bot == mesh%n .and. holds(st%ends(face_bottom)))
   end function anchored

   !> Nodes of the fragment above split node i (top = j) or below it (bottom = k).
   pure subroutine fragment_span(mesh, st, i, j, k)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! node
      integer, intent(out) :: j   !! top node of the fragment ending at A_i (0 or a split node)
      integer, intent(out) :: k   !! bottom node of the fragment starting at B_i (n or split)
      integer :: lo, hi, mid
      ! the split nodes are st%split(1:n_split), ascending (the interior nodes not joined):
      ! lo = how many lie below i, by bisection (O(log n_split), not a walk over the nodes)
      lo = 0
      hi = st%n_split
      do while (lo < hi)
         mid = (lo + hi + 1) / 2
         if (st%split(mid) < i) then
            lo = mid
         else
            hi = mid - 1
         end if
      end do
      ! (none: the bar's end, or the node beyond i where i is an end itself, as a walk from
      ! i would stop)
      j = min(0, i - 1)
      if (lo > 0) j = st%split(lo)
      k = max(mesh%n, i + 1)
      do mid = lo + 1, min(lo + 2, st%n_split)
         if (st%split(mid) > i) then
            k = st%split(mid)
            exit
         end if
      end do
   end subroutine fragment_span

   !> Mass of the region from B_top to A_bot (as moved by shift_span) [kg/m^2]: its cells,
   !> and the outer half mass of an end node (a transmitting or full-mass end).
   pure real(wp) function span_mass(mesh, top, bot) result(mass)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      mass = mesh%m_above(bot) - mesh%m_above(top)
      if (top == 0) mass = mass + mesh%ma(0)
      if (bot == mesh%n) mass = mass + mesh%mb(mesh%n)
   end function span_mass

   !> Shift the displacements (not the increments) of the fragment from B_top to A_bot
   !> rigidly by delta; returns the change of gravity potential energy. A cohesive crack at an
   !> end keeps its opening, which is its own (spb_state cohesive_t): a shift is no opening.
   pure subroutine shift_span(mesh, st, g, top, bot, delta, de_pot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: delta        !! rigid shift along x [m]
      integer, intent(in) :: top           !! top node: its lower half B_top moves (all of it if 0)
      integer, intent(in) :: bot           !! bottom node: its upper half A_bot moves (all if n)
      real(wp), intent(out) :: de_pot      !! [J/m^2]
      integer :: i
      do i = top, bot
         if (i > top .or. top == 0) st%ua(i) = st%ua(i) + delta
         if (i < bot .or. bot == mesh%n) st%ub(i) = st%ub(i) + delta
      end do
      de_pot = -g * span_mass(mesh, top, bot) * delta
      ! the centre of mass moves with no momentum behind it (x_drift, doc/outputs.md)
      st%ledger%m_drift = st%ledger%m_drift + span_mass(mesh, top, bot) * delta
   end subroutine shift_span

   !> Issue a new fragment id for the fragment whose top node is `node`, with its parent and
   !> birth step (kept per node like the id: memory does not grow with the events).
   pure subroutine new_fragment_id(st, parent, node)
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: parent        !! id of the parent fragment (0: none)
      integer, intent(in) :: node          !! top node of the new fragment
      st%gen%n_frag_ids = st%gen%n_frag_ids + 1
      st%gen%frag_id(node) = st%gen%n_frag_ids
      st%gen%frag_parent(node) = parent
      st%gen%frag_birth(node) = st%step
   end subroutine new_fragment_id

   !> The timing rule: join at t^n (accelerate), at t^{n+1} (delay; within, whose overlap
   !> strain_faces then keeps as strain), or where the correction is smaller (min, (5.3));
   !> corr is the chosen correction (5.2).
   pure subroutine choose_time(timing, d_acc, d_del, at_n, corr)
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      real(wp), intent(in) :: d_acc          !! correction (5.2) for a join at t^n [m]
      real(wp), intent(in) :: d_del          !! correction (5.2) for a join at t^{n+1} [m]
      logical, intent(out) :: at_n           !! join at t^n (else at t^{n+1})
      real(wp), intent(out) :: corr          !! the correction of the chosen time [m]
      select case (timing)
      case (timing_accelerate)
         at_n = .true.
      case (timing_delay, timing_within)
         at_n = .false.
      case default
         at_n = abs(d_acc) <= abs(d_del)
      end select
      corr = merge(d_acc, d_del, at_n)
   end subroutine choose_time

   !> Trial increment of a split half over the step just taken, and its increment before.
   pure real(wp) function du_before_a(mesh, st, g, i) result(d)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! split node
      d = st%dua(i) - (st%s_old(i) + mesh%ma(i) * g) / mesh%ma(i) * mesh%dt**2
   end function du_before_a

   !> Trial increment of the lower half of split node i over the step before.
   pure real(wp) function du_before_b(mesh, st, g, i) result(d)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! split node
      d = st%dub(i) - (mesh%mb(i) * g - st%s_old(i + 1)) / mesh%mb(i) * mesh%dt**2
   end function du_before_b

   !> Momentum of the region from B_top to A_bot over the last step [kg/(m s)].
   pure real(wp) function span_momentum(mesh, st, top, bot) result(mom)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      integer :: i
      mom = 0.0_wp
      do i = top, bot
         if (i > top .or. top == 0) mom = mom + mesh%ma(i) * st%dua(i)
         if (i < bot .or. bot == mesh%n) mom = mom + mesh%mb(i) * st%dub(i)
      end do
      mom = mom / mesh%dt
   end function span_momentum

   !> Load on a free end face that belongs to the region top..bot, along +x [N/m^2].
   pure real(wp) function end_force(mesh, st, top, bot) result(f)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      f = 0.0_wp
      if (top == 0 .and. has_free_face(st%ends(face_top))) f = f + st%s(0)
      if (bot == mesh%n .and. has_free_face(st%ends(face_bottom))) f = f - st%s(mesh%n + 1)
   end function end_force

   !> Velocity change w of a region shifted on its path (see shift_late): the real root
   !> of M w^2/2 + (P + F dt/2) w - F shift = 0 on the side of the region's motion, with
   !> P its momentum over the step and F = M g + end loads the constant force on it (the
   !> ledger measures potential and work at mid-step); ok = .false. where there is none
   !> (the region is too slow to have come that far) or where it would set the region
   !> back by more than the step.
   pure subroutine path_speed(mesh, st, g, top, bot, shift, w, ok)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: shift        !! its shift along x [m]
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      real(wp), intent(out) :: w               !! [m/s]
      logical, intent(out) :: ok               !! w exists and sets the region back by at most dt
      real(wp) :: mass, force, vm, disc
      w = 0.0_wp
      ok = .true.
      mass = span_mass(mesh, top, bot)
      force = g * mass + end_force(mesh, st, top, bot)
      if (.not. (abs(force) > 0.0_wp .and. abs(shift) > 0.0_wp .and. mass > 0.0_wp)) return
      vm = (span_momentum(mesh, st, top, bot) + 0.5_wp * force * mesh%dt) / mass
      disc = vm**2 + 2.0_wp * force / mass * shift
      ok = disc >= 0.0_wp
      if (ok) w = sign(sqrt(disc), vm) - vm
      ! the velocity change is the force's over the time the region is set back; the
      ! contact happened within the step, so that time is at most dt
      ok = ok .and. abs(w) <= abs(force / mass) * mesh%dt
   end subroutine path_speed

   !> The correction of a join at t^{n+1} moves the shifted region along its path: besides
   !> the rigid shift (5.2) that removes the overlap, its increments change by a uniform
   !> w dt (path_speed) so that kinetic plus potential energy change by exactly the work
   !> the end loads do on the region's move (booked in w_load). A rigid shift alone would
   !> lift the region against gravity and the loads for nothing: the paper's "fragments
   !> keep being pushed apart". The momentum w gives the region is booked in p_shift.
   pure subroutine shift_late(mesh, st, g, top, bot, shift, w)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: shift        !! its shift along x [m]
      real(wp), intent(in) :: w            !! its velocity change (path_speed) [m/s]
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      real(wp) :: de, mass, mom, f_end, work
      integer :: i
      mass = span_mass(mesh, top, bot)
      mom = span_momentum(mesh, st, top, bot)
      f_end = end_force(mesh, st, top, bot)
      call shift_span(mesh, st, g, top, bot, shift, de)
      do i = top, bot
         if (i > top .or. top == 0) st%dua(i) = st%dua(i) + w * mesh%dt
         if (i < bot .or. bot == mesh%n) st%dub(i) = st%dub(i) + w * mesh%dt
      end do
      work = f_end * (shift - 0.5_wp * w * mesh%dt)
      st%ledger%w_load = st%ledger%w_load + work
      ! kinetic + potential change minus that work: zero but for the root's rounding
      st%ledger%e_shift = st%ledger%e_shift - (mom * w + mass * (0.5_wp * w**2 + 0.5_wp * g * mesh%dt * w) &
                                 + de - work)
      st%ledger%p_shift = st%ledger%p_shift + mass * w
      ! the step's increments gained w dt that no displacement followed (x_drift)
      st%ledger%m_drift = st%ledger%m_drift - mass * w * mesh%dt
   end subroutine shift_late

   !> Shift the nodes a..b rigidly by delta (shift_span), booking the gravity energy in
   !> e_shift; far: the part lies beyond the fragments whose wave measure the event takes
   !> before and after, so the change is booked in e_lost_wave here too.
   pure subroutine shift_part(mesh, st, g, a, b, delta, far)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: delta        !! the shift along x [m]
      integer, intent(in) :: a             !! top node of the part (as top in shift_span)
      integer, intent(in) :: b             !! bottom node of the part (as bot in shift_span)
      logical, intent(in) :: far           !! the part lies beyond the two fragments
      real(wp) :: de
      call shift_span(mesh, st, g, a, b, delta, de)
      st%ledger%e_shift = st%ledger%e_shift - de
      if (far) st%ledger%e_lost_wave = st%ledger%e_lost_wave - de
   end subroutine shift_part

   !> A shifted fragment must not be pushed into its neighbour: while the shift would make
   !> the faces at the region's top node overlap, the fragment above moves with it.
   pure subroutine extend_up(mesh, st, top, shift)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(inout) :: top        !! top node of the region (0 or a split node)
      real(wp), intent(in) :: shift        !! its shift along x [m]
      do while (top > 0)
         if (st%joined(top)) exit
         if (.not. ((st%ub(top) + shift) - st%ua(top) < 0.0_wp)) exit
         top = top - 1
         do while (top > 0)
            if (.not. st%joined(top)) exit
            top = top - 1
         end do
         if (anchored(mesh, st, top, mesh%n - 1)) exit
      end do
   end subroutine extend_up

   !> The same downward, for a shift of the lower side.
   pure subroutine extend_down(mesh, st, bot, shift)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(inout) :: bot        !! bottom node of the region (n or a split node)
      real(wp), intent(in) :: shift        !! its shift along x [m]
      do while (bot < mesh%n)
         if (st%joined(bot)) exit
         if (.not. (st%ub(bot) - (st%ua(bot) + shift) < 0.0_wp)) exit
         bot = bot + 1
         do while (bot < mesh%n)
            if (.not. st%joined(bot)) exit
            bot = bot + 1
         end do
         if (anchored(mesh, st, 1, bot)) exit
      end do
   end subroutine extend_down

   !> Fill the time, place and correction of a collision event and append it.
   pure subroutine finish_event(mesh, st, ev, node, at_n, corr, shift, above, below, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(event_t), intent(inout) :: ev       !! kind, stress and stress_bound already set
      integer, intent(in) :: node              !! node of the section (n: the base)
      integer, intent(in) :: above             !! fragment id for frag_above (collision: the
                                               !! merged fragment)
      integer, intent(in) :: below             !! fragment id for frag_below (collision: the
                                               !! lower one merged; base: 0)
      logical, intent(in) :: at_n              !! joined at t^n (else t^{n+1})
      real(wp), intent(in) :: corr             !! correction (5.2) of the chosen time [m]
      real(wp), intent(in) :: shift            !! the shift applied [m]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      ev%step = st%step
      if (at_n) ev%step = st%step - 1
      ev%node = node
      ev%t = real(ev%step, wp) * mesh%dt
      ev%x = mesh%x(node)
      ev%dt_bound = mesh%dt
      ev%dx_bound = 0.0_wp
      ev%opening = corr
      ev%shift = shift
      ev%frag_above = above
      ev%frag_below = below
      call push_event(events, ev)
   end subroutine finish_event

   !> Work a face load does on a rigid shift of its face [J/m^2]: booked as work and, since no
   !> wave energy follows, as what the event removed.
   pure subroutine book_shift_work(st, work)
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: work         !! work of the face load on the shift [J/m^2]
      st%ledger%w_wave = st%ledger%w_wave + work
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + work
   end subroutine book_shift_work

   !> Node i was joined at t^{n+1}: its section is not tested for breaking this step.
   pure subroutine skip_next(st, i)
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: i             !! split node
      call append(st%skip_test, st%n_skip, i)
   end subroutine skip_next

   !> A landing or a join that leaves the bar one fragment held at both ends with an odd cell
   !> count changes its measure by c d^2 - g mu d (d the faces' trial step beyond what a
   !> lift-off or a break would redo), which adds up to K = g^2 dt^3 / (8C) for small d: no
   !> landing rule avoids it within the penetration allowance (doc/method.md, "A landing
   !> credit"). That gain, up to K, is kept as the held bar's credit (its measure lower by
   !> as much, constant while it is held) instead of being created; the lift-off or break
   !> that ends the hold pays it (spb_fracture). e_wave0: the region's measure before the
   !> event. Anything beyond K stays booked, where the ledger shows it.
   pure subroutine keep_credit(mesh, st, g, i_top, i_bot, e_wave0)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(in) :: e_wave0      !! region_wave of the event's region before it [J/m^2]
      real(wp) :: gain
      if (.not. abs(g) > 0.0_wp .or. st%n_split > 0 .or. mesh%full_mass) return
      if (.not. held_odd(mesh, st, 0, mesh%n)) return
      gain = region_wave(mesh, st, g, i_top, i_bot, 0, mesh%n) - e_wave0
      if (.not. gain > 0.0_wp) return
      st%u_credit = st%u_credit + &
                         credit_position(mesh, g, min(gain, credit_bound(mesh, g, 0, mesh%n)))
   end subroutine keep_credit

   !> Whether split node i is a cohesive crack that still carries traction (its faces'
   !> contact is the crack's own, spb_cohesive).
   pure logical function cohesive_open(st, i)
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! split node
      cohesive_open = .false.
      if (st%coh%on) cohesive_open = st%coh%active(i)
   end function cohesive_open

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

   !> The start of a collision at split node i, before either rule set's correction: the
   !> halves' increments of the step before (for the collision stress of a join at t^n), the
   !> corrections (5.2) that close the gap at t^n (gap_at_n) or remove the overlap at
   !> t^{n+1}, and the timing rule's choice between them.
   pure subroutine start_collision(mesh, st, g, timing, i, tol, du0, d_acc, d_del, at_n, corr)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: i             !! split node
      real(wp), intent(in) :: tol          !! contact tolerance [m] (0: the paper's rules)
      real(wp), intent(out) :: du0(2)      !! the upper and the lower half's increment of the
                                           !! step before (du_before_a, du_before_b) [m]
      real(wp), intent(out) :: d_acc       !! correction for a join at t^n (< 0: a gap) [m]
      real(wp), intent(out) :: d_del       !! correction for a join at t^{n+1} (> 0) [m]
      logical, intent(out) :: at_n         !! the rule joins at t^n (else at t^{n+1})
      real(wp), intent(out) :: corr        !! the correction of the chosen time [m]
      du0(1) = du_before_a(mesh, st, g, i)
      du0(2) = du_before_b(mesh, st, g, i)
      ! (5.2): corrections that close the gap at t^n or remove the overlap at t^{n+1}
      d_acc = gap_at_n(st, i, tol)                          ! u_A^n - u_B^n (< 0: a gap)
      d_del = st%ua(i) - st%ub(i)                                 ! u_A^{n+1} - u_B^{n+1} > 0
      call choose_time(timing, d_acc, d_del, at_n, corr)
   end subroutine start_collision

   !> The collision stress (5.6) in the section of split node i if its halves joined at t^n
   !> (at_n: from the cells' stresses s^n and the halves' increments du0 of the step before)
   !> or at t^{n+1} (from s^{n+1} and the increments just taken) [Pa, + compression].
   pure real(wp) function join_stress(mesh, st, i, at_n, du0) result(sz)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! split node
      logical, intent(in) :: at_n          !! joined at t^n (else t^{n+1})
      real(wp), intent(in) :: du0(2)       !! the halves' increments of the step before [m]
      if (at_n) then
         sz = collision_stress(st%s_old(i), st%s_old(i + 1), du0(1) / mesh%dt, du0(2) / mesh%dt, &
                               mesh%z(i), mesh%z(i + 1))
      else
         sz = collision_stress(st%s(i), st%s(i + 1), st%dua(i) / mesh%dt, st%dub(i) / mesh%dt, &
                               mesh%z(i), mesh%z(i + 1))
      end if
   end function join_stress

   !> Move the two faces of split node i towards each other by d (apart for d < 0): the upper
   !> half by -d m_B/(m_A + m_B), the lower by +d m_A/(m_A + m_B), their displacements only.
   !> Their common centre of mass stays (x_drift books + and - that cancel), so gravity does
   !> no work on the move; the cells next to the node keep their stresses, so the two cells'
   !> lengths take the correction as a length defect; nothing beyond the node moves (the
   !> 'face' policy's correction, causal: doc/method.md, "The 'face' correction").
   pure subroutine move_faces(mesh, st, g, i, d)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! split node
      real(wp), intent(in) :: d            !! the faces' overlap to remove [m]
      real(wp) :: x, y, de_pot
      x = d * mesh%mb(i) / (mesh%ma(i) + mesh%mb(i))
      y = d - x
      st%ua(i) = st%ua(i) - x
      st%ub(i) = st%ub(i) + y
      de_pot = -g * (mesh%mb(i) * y - mesh%ma(i) * x)
      st%ledger%e_shift = st%ledger%e_shift - de_pot
      st%ledger%m_drift = st%ledger%m_drift + (mesh%mb(i) * y - mesh%ma(i) * x)
   end subroutine move_faces

   !> A collision timed within the step ('within', doc/method.md "Collisions timed within the
   !> step"), after the join at t^{n+1} of split node i (join_node): the overlap d the trial
   !> step left is kept as strain. The two halves, now one node, go to their common centre of
   !> mass (the upper half by -d m_B/(m_A + m_B), the lower by +d m_A/(m_A + m_B), as
   !> move_faces), and the two cells take the change of their lengths in their stresses. With
   !> constant velocities over the step a contact at t^n + theta dt leaves d = (1 - theta) dv dt,
   !> and the cells' added stress is the contact stress (5.6) times the share of the step after
   !> the contact. s_old follows s: the step in effect started from the compressed cells, which
   !> keeps s^{n+1} - s^n = E/dx (du_{k-1} - du_k) and the ledger's telescoping exact. The
   !> section stress S^{n+1/2} takes 2 ds of the cell above, so that the next step's (3.1)-(3.2)
   !> give the collision stress (5.6) of the join, not it plus the added strain. Nothing moves
   !> the centre of mass and no length is left unexplained (x_drift, l_defect: 0).
   pure subroutine strain_faces(mesh, st, g, i, d)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state (node i joined at t^{n+1})
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! the node
      real(wp), intent(in) :: d            !! the faces' overlap at t^{n+1} [m]
      real(wp) :: x, y, e0, ds_a, ds_b
      e0 = node_energy(mesh, st, g, i)
      x = d * mesh%mb(i) / (mesh%ma(i) + mesh%mb(i))
      y = d - x
      ds_a = mesh%stiff(i) * x
      ds_b = mesh%stiff(i + 1) * y
      st%ua(i) = st%ua(i) - x
      st%ub(i) = st%ub(i) + y
      st%s(i) = st%s(i) + ds_a
      st%s(i + 1) = st%s(i + 1) + ds_b
      st%s_old(i) = st%s_old(i) + ds_a
      st%s_old(i + 1) = st%s_old(i + 1) + ds_b
      st%section(i) = st%section(i) + 2.0_wp * ds_a
      ! gravity: the common centre of mass stays (0 to round-off), booked as a shift's
      st%ledger%e_shift = st%ledger%e_shift + g * (mesh%mb(i) * y - mesh%ma(i) * x)
      st%ledger%m_drift = st%ledger%m_drift + (mesh%mb(i) * y - mesh%ma(i) * x)
      st%ledger%e_join = st%ledger%e_join + (e0 - node_energy(mesh, st, g, i))
   end subroutine strain_faces

   !> The join of a collision at split node i once a rule set has corrected the positions
   !> (moved by shift, at the time at_n with the correction corr): the collision stress (5.6)
   !> at the joining time and its error bound (6.2), the join with conserved momentum (5.4),
   !> the genealogy (the merged fragment is new, its parent the upper one) and the event.
   pure subroutine join_node(mesh, st, g, i, at_n, corr, shift, du0, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! split node
      logical, intent(in) :: at_n          !! joined at t^n (else t^{n+1})
      real(wp), intent(in) :: corr         !! the correction (5.2) used [m]
      real(wp), intent(in) :: shift        !! the shift applied (event's shift) [m]
      real(wp), intent(in) :: du0(2)       !! the halves' increments of the step before [m]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp) :: mass_a, mass_b, du_join, e0, sz, du_a_trial, du_b_trial
      integer :: j, k, parent_up, parent_dn
      type(event_t) :: ev
      ! collision stress (5.6) at the joining time, and its error bound (6.2)
      sz = join_stress(mesh, st, i, at_n, du0)
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
         st%section(i) = section_stress_a(st%s_old(i), 0.0_wp, du0(1) / mesh%dt, &
                                          du_join / mesh%dt, mesh%z(i), mesh%dm(i), g)
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
      call finish_event(mesh, st, ev, i, at_n, corr, shift, st%gen%frag_id(j), parent_dn, events)
   end subroutine join_node

   !> Open the joined section i: its halves' u and du change by dd_a (upper) and dd_b
   !> (lower), the cells above and below by ds_a and ds_b; the section has no strength from
   !> now on, and the change of the scheme's measure is booked in e_fracture.
   pure subroutine open_section(mesh, st, g, i, dd_a, dd_b, ds_a, ds_b)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! node
      real(wp), intent(in) :: dd_a         !! change of the upper half's u and du [m]
      real(wp), intent(in) :: dd_b         !! change of the lower half's u and du [m]
      real(wp), intent(in) :: ds_a         !! stress change of the cell above [Pa]
      real(wp), intent(in) :: ds_b         !! stress change of the cell below [Pa]
      real(wp) :: e0
      e0 = node_energy(mesh, st, g, i)
      st%ua(i) = st%ua(i) + dd_a
      st%dua(i) = st%dua(i) + dd_a
      st%ub(i) = st%ub(i) + dd_b
      st%dub(i) = st%dub(i) + dd_b
      st%s(i) = st%s(i) + ds_a
      st%s(i + 1) = st%s(i + 1) + ds_b
      call open_node(st, i)
      st%strength(i) = 0.0_wp
      st%section(i) = 0.0_wp
      st%n_breakable = st%n_breakable - 1
      st%ledger%e_fracture = st%ledger%e_fracture + (e0 - node_energy(mesh, st, g, i))
   end subroutine open_section

   !> The genealogy and the event of a break at node i, now split, of the fragment whose top
   !> node was j: both pieces are new fragments born of the one that broke; a section that had
   !> been open before (a crack, a dry contact) separates rather than fractures.
   pure subroutine record_break(mesh, st, i, j, stress, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: i             !! node
      integer, intent(in) :: j             !! top node of the fragment that broke
      real(wp), intent(in) :: stress          !! the section stress that broke it [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      type(event_t) :: ev
      integer :: parent
      parent = st%gen%frag_id(j)
      call new_fragment_id(st, parent, j)
      call new_fragment_id(st, parent, i)
      ev%kind = ev_fracture
      if (st%cracked(i)) ev%kind = ev_separation
      st%cracked(i) = .true.
      ev%step = st%step
      ev%node = i
      ev%t = real(st%step, wp) * mesh%dt
      ev%x = mesh%x(i)
      ev%stress = stress
      ev%dt_bound = mesh%dt
      ev%dx_bound = max(mesh%dx(i), mesh%dx(i + 1))
      ev%opening = st%ub(i) - st%ua(i)
      ev%frag_above = st%gen%frag_id(j)
      ev%frag_below = st%gen%frag_id(i)
      call push_event(events, ev)
   end subroutine record_break

end module spb_fragments
