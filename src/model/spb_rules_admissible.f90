!> The admissible event rules (`&run events = 'admissible'`, the default; doc/method.md,
!> "Admissible events"): each keeps the continuum reading of the state, so no event creates
!> wave energy. Collisions are taken largest overlap first, those joined at t^n before those
!> at t^{n+1}; both sides move rigidly about their common centre of mass; faces collide when
!> they overlap by more than eps_rel dx; a join that leaves the bar held at both ends keeps
!> its landing credit. A break redoes the step of the two new faces from the continuum state
!> at t^n and pays that credit. Chosen in one place: spb_contact contact_step and
!> spb_fracture fracture_step; what both rule sets share is in spb_fragments.
module spb_rules_admissible
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, face_bottom, has_base
   use spb_state, only: state_t
   use spb_events, only: event_list_t
   use spb_fragments, only: node_energy, fragment_span, span_mass, anchored, choose_time, &
      shift_part, extend_up, extend_down, book_shift_work, keep_credit, cohesive_open, &
      gap_at_n, start_collision, join_node, open_section, record_break, move_faces, &
      join_stress, strain_faces
   use spb_wave, only: fragment_characteristics, region_wave, credit_position
   use spb_problem, only: shift_above, shift_face, timing_within
   implicit none
   private
   public :: admissible_collisions, admissible_breaks, pay_credit

contains

   !> The collisions of the step by the admissible rules: the overlapping open sections,
   !> largest overlap first (an order that a mirrored bar sees the same way; a correction can
   !> close or open the next one's overlap), the joins at t^n first, then those at t^{n+1} (a
   !> fragment joined at t^{n+1} has no state at t^n for a later join of the step at t^n).
   !> The wave measure of the two fragments, before and after, is booked in e_lost_wave.
   pure subroutine admissible_collisions(mesh, st, g, timing, policy, events, i_top, i_bot, &
                                         eps_rel)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g                !! gravity [m/s^2]
      integer, intent(in) :: timing            !! timing_* rule
      integer, intent(in) :: policy            !! shift_* policy
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top            !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot            !! bottom face-load integral over the step [Pa s]
      real(wp), intent(in) :: eps_rel          !! faces collide when they overlap by more than
                                               !! eps_rel dx (round-off) [-]
      real(wp) :: e_wave0, tol
      integer :: r_top, r_bot
      integer :: open_nodes(st%n_split)
      integer :: c, i, pass
      open_nodes = overlapping(mesh, st, eps_rel)
      do pass = 1, 2
      do c = 1, size(open_nodes)
         if (open_nodes(c) == 0) exit
         i = open_nodes(c)
         ! a cohesive crack's faces keep themselves apart (spb_cohesive): no collision
         if (cohesive_open(st, i)) cycle
         tol = eps_rel * min(mesh%dx(i), mesh%dx(i + 1))
         if (pass == 1 .and. st%ua(i) - st%ub(i) > tol) then
            if (.not. joins_at_n(mesh, st, g, timing, policy, i, i_top, i_bot, tol)) cycle
         end if
         if (st%ua(i) - st%ub(i) > tol) then
            ! the two fragments; what is shifted beyond them moves rigidly and books its
            ! gravity energy itself (shift_both_sides)
            call fragment_span(mesh, st, i, r_top, r_bot)
            e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
            call collide(mesh, st, g, timing, policy, i, events, i_top, i_bot, tol)
            call keep_credit(mesh, st, g, i_top, i_bot, e_wave0)
            st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                             region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
         end if
      end do
      end do
   end subroutine admissible_collisions

   !> The open sections whose faces overlap by more than eps_rel dx (dx the smaller cell at
   !> the node), largest overlap first, the rest of the list 0; open cohesive cracks left out.
   pure function overlapping(mesh, st, eps_rel) result(open_nodes)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: eps_rel      !! the round-off guard [-]
      integer :: open_nodes(st%n_split)
      real(wp) :: overlap(st%n_split)
      integer :: c, i, m, nc
      open_nodes = st%split(1:st%n_split)
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
   end function overlapping

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
      at_n = .false.
      if (timing == timing_within) return
      d_acc = gap_at_n(st, i, tol)
      d_del = st%ua(i) - st%ub(i)
      call choose_time(timing, d_acc, d_del, at_n, corr)
      call hold_late_join(mesh, st, i, d_acc, at_n, corr)
      call plan_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, top, bot, x, y, &
                           i_top, i_bot)
   end function joins_at_n

   !> Choose the rule's time, move both sides, join node i.
   pure subroutine collide(mesh, st, g, timing, policy, i, events, i_top, i_bot, tol)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: i             !! split node
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(in) :: tol          !! contact tolerance [m]
      real(wp) :: du0(2), d_acc, d_del, corr, shift_amount, d_pre
      logical :: at_n
      call start_collision(mesh, st, g, timing, i, tol, du0, d_acc, d_del, at_n, corr)
      if (timing == timing_within) then
         ! joined at t^{n+1}, the overlap the step's motion made kept as strain; no side moves
         ! (no shift policy). An overlap the faces already had at t^n (d_acc > 0) is no
         ! contact within this step: straining it would create energy (the loss (1 - theta)
         ! theta ... of strain_faces turns negative for theta < 0), so the faces take it as
         ! 'face' does, as a length defect
         ! (even one within the contact tolerance, which gap_at_n reads as touching)
         d_pre = max(0.0_wp, (st%ua(i) - st%dua(i)) - (st%ub(i) - st%dub(i)))
         if (d_pre > 0.0_wp) call move_faces(mesh, st, g, i, d_pre)
         call join_node(mesh, st, g, i, .false., corr, &
                        -corr * mesh%mb(i) / (mesh%ma(i) + mesh%mb(i)), du0, events)
         call strain_faces(mesh, st, g, i, corr - d_pre)
         return
      end if
      call hold_late_join(mesh, st, i, d_acc, at_n, corr)
      call shift_both_sides(mesh, st, g, policy, i, d_acc, d_del, at_n, corr, shift_amount, &
                            i_top, i_bot)
      call join_node(mesh, st, g, i, at_n, corr, shift_amount, du0, events)
   end subroutine collide

   !> A join at t^{n+1} is a contact only if its collision stress (5.6) there compresses: a
   !> tensile one would part the faces in the next step, whose break redoes that step from
   !> the continuum state at t^n and so undoes the join's exchange of momentum (the 'delay'
   !> chatter, doc/method.md "Chatter"). Such a collision is joined at t^n, as accelerate
   !> would: the contact began within the step just taken.
   pure subroutine hold_late_join(mesh, st, i, d_acc, at_n, corr)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state (trial step taken)
      integer, intent(in) :: i             !! split node
      real(wp), intent(in) :: d_acc        !! correction (5.2) for a join at t^n [m]
      logical, intent(inout) :: at_n       !! join at t^n (else t^{n+1})
      real(wp), intent(inout) :: corr      !! the correction of the chosen time [m]
      real(wp), parameter :: unused(2) = 0.0_wp
      real(wp) :: scale
      if (at_n) return
      ! tensile beyond round-off (a frame change or a mirror must not flip the choice)
      scale = abs(st%s(i)) + abs(st%s(i + 1)) + &
              mesh%z(i + 1) * (abs(st%dua(i)) + abs(st%dub(i))) / mesh%dt
      if (.not. join_stress(mesh, st, i, .false., unused) < -1.0e-9_wp * scale) return
      at_n = .true.
      corr = d_acc
   end subroutine hold_late_join

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
      moved = -x
      if (policy == shift_face) then
         call move_faces(mesh, st, g, i, corr)
         return
      end if
      call fragment_span(mesh, st, i, j, k)
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
      if (policy == shift_face) then
         ! only the two faces move (move_faces), at the timing rule's time: nothing is anchored,
         ! their common centre of mass stays, so gravity and the end loads do no work on it
         top = i
         bot = i
         x = corr * mesh%mb(i) / (mesh%ma(i) + mesh%mb(i))
         y = corr - x
         return
      end if
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

   !> The admissible break of the sections cand (ascending). A section found at t^{n+1} with
   !> S^{n+1/2} < -R carried that tension over the step just taken: the crack opened at t^n
   !> (the method's bound (4.1)). So the step is redone for the new faces from the continuum
   !> state at t^n, which the break leaves as it is: over the step the upper face moves by
   !> 2 f_i, the lower by 2 g_{i+1} (the t^n intervals of the cells above and below, read
   !> from the fragment before any of this step's breaks; spb_wave), and the two cells'
   !> stresses follow. The wave energy is conserved, momentum too (m_A 2 f_i + m_B 2 g_{i+1}
   !> = m_i du_i), both new fragments are free of the Jordan component; for a homogeneous
   !> bar this is the paper's stage 1 with S the continuum section stress of the step. The
   !> faces open by what the continuum opens them in one step (no stage 2). The scheme's
   !> own measure changes by what e_fracture books.
   pure subroutine admissible_breaks(mesh, st, g, cand, i_top, i_bot, eps, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: cand(:)           !! sections whose S^{n+1/2} < -R - eps
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(in) :: eps          !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp) :: du_a(size(cand)), du_b(size(cand)), s_brk(size(cand)), sig
      real(wp), allocatable :: f(:), gw(:)
      integer :: brk(size(cand))
      integer :: m, i, j, k, nb
      ! each candidate breaks where the continuum reading's own section stress over the step,
      ! (Z_i/dt)(2 f_i - du_i), is beyond its strength too (after a join the (3.1)-(3.2)
      ! recursion can differ from it; its value is kept where the section holds)
      if (size(cand) == 0) return
      ! f and gw over the fragments of all candidates at once (the spans do not change here)
      call fragment_span(mesh, st, cand(1), j, k)
      i = j
      call fragment_span(mesh, st, cand(size(cand)), j, k)
      allocate(f(i+1:k), gw(i+1:k))
      m = 1
      nb = 0
      do while (m <= size(cand))
         call fragment_span(mesh, st, cand(m), j, k)
         call fragment_characteristics(mesh, st, g, j, k, i_top, i_bot, .true., f(j+1:k), &
                                       gw(j+1:k))
         do while (m <= size(cand))
            if (cand(m) >= k) exit
            i = cand(m)
            sig = mesh%z(i) / mesh%dt * (2.0_wp * f(i) - st%dua(i))
            if (sig < -st%strength(i) - eps) then
               nb = nb + 1
               brk(nb) = i
               du_a(nb) = 2.0_wp * f(i)
               du_b(nb) = 2.0_wp * gw(i + 1)
            else
               st%section(i) = sig
            end if
            m = m + 1
         end do
      end do
      do m = 1, nb
         i = brk(m)
         s_brk(m) = st%section(i)
         ! the step redone from t^n for the two faces: u, du and the two cells' s^{n+1}
         call open_section(mesh, st, g, i, du_a(m) - st%dua(i), du_b(m) - st%dub(i), &
                           -mesh%stiff(i) * (du_a(m) - st%dua(i)), &
                           mesh%stiff(i + 1) * (du_b(m) - st%dub(i)))
      end do
      if (nb > 0 .and. abs(st%u_credit) > 0.0_wp) then
         call pay_credit(mesh, st, g, brk(1), brk(nb), i_top, i_bot)
      end if
      do m = 1, nb
         call fragment_span(mesh, st, brk(m), j, k)
         call record_break(mesh, st, brk(m), j, s_brk(m), events)
      end do
   end subroutine admissible_breaks

   !> The break of a bar held at both ends whose measure holds a landing's credit gamma
   !> (spb_fragments, keep_credit): the credit leaves the measure with the hold, so the break
   !> would add gamma. The new end fragments pay it: the measure of a fragment held at one end
   !> is a parabola in the step of its free face, whose vertex is not in general the step the
   !> break redid (its alternating sum is not zero there, as the held bar's was); the face's
   !> step moves towards the vertex by what lowers that fragment's measure by gamma (to the
   !> vertex where that is not enough), first the lower fragment's (nodes i_low..n, held by
   !> the base or a fixed bottom) top face, then the upper one's (0..i_up, fixed top) bottom
   !> face, neither so far that the faces overlap at t^{n+1}. What is not paid stays booked in
   !> e_lost_wave (doc/method.md, "A landing credit"); the upper face pays only what the lower
   !> could not, beyond 1e-6 of the credit (not the round-off of a full payment). The faces'
   !> momentum change is the supports' (i_support), which hold the bar.
   pure subroutine pay_credit(mesh, st, g, i_up, i_low, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i_up          !! the uppermost section that broke
      integer, intent(in) :: i_low         !! the lowest section that broke
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp) :: gamma, gamma0
      gamma = st%u_credit / credit_position(mesh, g, 1.0_wp)
      st%u_credit = 0.0_wp
      if (.not. gamma > 0.0_wp) return
      gamma0 = gamma
      call pay_from_face(mesh, st, g, i_low, .false., i_low, mesh%n, i_top, i_bot, gamma)
      ! the upper face pays what the lower could not (not the round-off of a full payment)
      if (gamma > 1.0e-6_wp * gamma0) call pay_from_face(mesh, st, g, i_up, .true., 0, i_up, &
                                                         i_top, i_bot, gamma)
   end subroutine pay_credit

   !> Lower the measure of the fragment top..bot by up to credit (what remains is returned)
   !> by moving the step of its face at split node i (the upper half's with upper) towards
   !> the vertex of its measure, as little as that needs and no further than the other face
   !> at node i allows (no overlap). The measure is quadratic in the step: its two
   !> coefficients are taken from three evaluations, h = d* = g dt^2 / (Z C) apart. Where K
   !> is below the measure's round-off the coefficients are noise: the move is kept within
   !> 10 h (the vertex lay within 3 h in every case measured) and undone if the measure rose.
   pure subroutine pay_from_face(mesh, st, g, i, upper, top, bot, i_top, i_bot, credit)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! the split node of the face
      logical, intent(in) :: upper         !! the upper half's face (else the lower's)
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(inout) :: credit    !! the credit still to pay [J/m^2]
      type(state_t) :: trial
      real(wp) :: p0, p_plus, p_minus, p1, h, a, b, disc, delta
      h = abs(g) * mesh%dt**2 / (mesh%z(merge(i, i + 1, upper)) * sum(1.0_wp / mesh%z(top+1:bot)))
      p0 = region_wave(mesh, st, g, i_top, i_bot, top, bot)
      trial = st
      call move_face(mesh, trial, g, i, upper, h)
      p_plus = region_wave(mesh, trial, g, i_top, i_bot, top, bot)
      trial = st
      call move_face(mesh, trial, g, i, upper, -h)
      p_minus = region_wave(mesh, trial, g, i_top, i_bot, top, bot)
      a = (p_plus + p_minus - 2.0_wp * p0) / (2.0_wp * h**2)
      b = (p_plus - p_minus) / (2.0_wp * h)
      if (.not. a > 0.0_wp) return
      disc = b**2 - 4.0_wp * a * credit
      if (disc > 0.0_wp) then
         delta = -2.0_wp * credit / (b + sign(sqrt(disc), b))
      else
         delta = -b / (2.0_wp * a)
      end if
      delta = max(-10.0_wp * h, min(10.0_wp * h, delta))
      if (upper) then
         delta = min(delta, st%ub(i) - st%ua(i))
      else
         delta = max(delta, st%ua(i) - st%ub(i))
      end if
      trial = st
      call move_face(mesh, trial, g, i, upper, delta)
      p1 = region_wave(mesh, trial, g, i_top, i_bot, top, bot)
      if (.not. p1 < p0) return
      st = trial
      credit = credit - (p0 - p1)
   end subroutine pay_from_face

   !> Move the step of one face of split node i by delta (the upper half's with upper, else
   !> the lower's): its u and du, the stress of its cell, e_fracture (the scheme's measure)
   !> and i_support.
   pure subroutine move_face(mesh, st, g, i, upper, delta)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: i             !! split node
      logical, intent(in) :: upper         !! the upper half's face (else the lower's)
      real(wp), intent(in) :: delta        !! change of its step [m]
      real(wp) :: e0
      e0 = node_energy(mesh, st, g, i)
      if (upper) then
         st%ua(i) = st%ua(i) + delta
         st%dua(i) = st%dua(i) + delta
         st%s(i) = st%s(i) - mesh%stiff(i) * delta
         st%ledger%i_support = st%ledger%i_support + mesh%ma(i) * delta / mesh%dt
      else
         st%ub(i) = st%ub(i) + delta
         st%dub(i) = st%dub(i) + delta
         st%s(i + 1) = st%s(i + 1) + mesh%stiff(i + 1) * delta
         st%ledger%i_support = st%ledger%i_support + mesh%mb(i) * delta / mesh%dt
      end if
      st%ledger%e_fracture = st%ledger%e_fracture + (e0 - node_energy(mesh, st, g, i))
   end subroutine move_face
end module spb_rules_admissible
