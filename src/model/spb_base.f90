!> The rigid base (doc/method.md, "Rigid base and dry interfaces"): an end face lands on
!> it and lifts off it again, at the bottom (a bar standing on the ground) or at the top (its
!> mirror: a bar pressed up against a ceiling). Landing is a collision with a partner of
!> infinite impedance (alpha -> oo in (5.6)) put on the grid by the timing rule; lift-off is a
!> break of the face's section against the base. Both are here, called where the collisions
!> (spb_contact) and the breaks (spb_fracture) of the step are made, so the events keep their
!> order; the full-mass model's lift-off is its own (spb_full_mass).
!>
!> One code serves both ends, written in the end's own numbers (spb_base_face): a face
!> penetrates the base by sgn (u_face - u_contact); the bar side of a landing moves by
!> -sgn corr; the face half's stop changes the end cell's stress by sgn (E/dx) du.
!>
!> The two rule sets (&run events) differ in how a landing is corrected and how a lift-off
!> redoes the step: each has its own procedures here (land_admissible, lift_admissible;
!> land_paper, lift_paper), chosen once at each entry (touch_base, lift_off); what both do
!> (the join with the base, the release from it) is shared (join_base, leave_base).
module spb_base
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, face_bottom, has_base, on_base
   use spb_state, only: state_t
   use spb_section, only: section_stress_a, section_stress_b
   use spb_events, only: event_t, event_list_t, ev_base_collision
   use spb_wave, only: fragment_characteristics, region_wave, held_odd, vertex_offset
   use spb_fragments, only: node_energy, anchored, fragment_span, span_mass, shift_span, &
      choose_time, du_before_a, du_before_b, path_speed, shift_late, shift_part, extend_up, &
      extend_down, finish_event, book_shift_work, skip_next, keep_credit
   use spb_base_face, only: base_face_t, base_face, face_u, face_du, face_mass, move_base_face, &
      base_fragment, base_ids, lift_off_event, end_order
   use spb_problem, only: events_paper, shift_above, shift_face, timing_within
   implicit none
   private
   public :: touch_base, lift_off

contains

   !> After the trial step: a face off its base that has passed it lands, by the rule set's
   !> landing (land_admissible, land_paper: chosen here), the region's wave measure before and
   !> after booked in e_lost_wave; with two bases the deeper overlap first (end_order).
   pure subroutine touch_base(mesh, st, g, timing, policy, events, i_top, i_bot, rules, eps_rel)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g                !! gravity [m/s^2]
      integer, intent(in) :: timing            !! timing_* rule
      integer, intent(in) :: policy            !! shift_* policy
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top            !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot            !! bottom face-load integral over the step [Pa s]
      integer, intent(in) :: rules             !! events_admissible | events_paper
      real(wp), intent(in) :: eps_rel          !! admissible: the face lands when it overlaps
                                               !! the base by more than eps_rel dx [-]
      integer :: side, k, order(2)
      real(wp) :: key(2)
      type(base_face_t) :: bf
      ! with two bases, the deeper overlap (in cells) lands first
      key = -huge(1.0_wp)
      do side = face_top, face_bottom
         if (.not. has_base(st%ends(side)) .or. st%ends(side)%contact) cycle
         bf = base_face(mesh, side)
         key(side) = bf%sgn * (face_u(st, bf) - st%ends(side)%u_contact) / mesh%dx(bf%c)
      end do
      order = end_order(key)
      do k = 1, 2
         side = order(k)
         if (.not. has_base(st%ends(side)) .or. st%ends(side)%contact) cycle
         bf = base_face(mesh, side)
         select case (rules)
         case (events_paper)
            call land_paper(mesh, st, bf, g, timing, policy, events, i_top, i_bot)
         case default
            call land_admissible(mesh, st, bf, g, timing, policy, events, i_top, i_bot, eps_rel)
         end select
      end do
   end subroutine touch_base

   !> Fragment boundaries around everything a landing can change under the paper's rules:
   !> the fragment on the base and whatever either correction (5.2) shifts; the whole bar
   !> for 'above'.
   pure subroutine landing_region(mesh, st, bf, policy, r_top, r_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(out) :: r_top        !! top node of the region the event can change
      integer, intent(out) :: r_bot        !! bottom node of that region
      real(wp) :: d_acc, d_del, amount, u_c
      integer :: a(3), b(3)
      r_top = 0
      r_bot = mesh%n
      if (policy == shift_above) return
      call base_fragment(mesh, st, bf, -1, a(1), b(1))
      u_c = st%ends(bf%side)%u_contact
      d_acc = bf%sgn * ((face_u(st, bf) - face_du(st, bf)) - u_c)
      d_del = bf%sgn * (face_u(st, bf) - u_c)
      call land_side(mesh, st, bf, policy, d_acc, a(2), b(2), amount)
      call land_side(mesh, st, bf, policy, d_del, a(3), b(3), amount)
      r_top = minval(a)
      r_bot = maxval(b)
   end subroutine landing_region

   !> The correction (5.2) that closes the gap to the base at t^n, sgn (u_face^n - u_base),
   !> where an overlap at t^n within the contact tolerance counts as touching: the face met
   !> it then (to round-off), and moving the bar by that much would only lift it.
   pure real(wp) function gap_at_n(st, bf, tol) result(d_acc)
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: tol          !! contact tolerance [m] (0: the paper's rules)
      d_acc = bf%sgn * ((face_u(st, bf) - face_du(st, bf)) - st%ends(bf%side)%u_contact)
      if (d_acc > 0.0_wp .and. d_acc <= tol) d_acc = 0.0_wp
   end function gap_at_n

   !> The region a landing's correction moves: the fragment on the base's side (all of the
   !> bar for 'above'), unless it is anchored, with what it is pushed into; nodes a..b.
   pure subroutine land_side(mesh, st, bf, policy, corr, a, b, shift_amount)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      integer, intent(in) :: policy        !! shift policy (shift_*)
      real(wp), intent(in) :: corr         !! the chosen correction (5.2) [m]
      integer, intent(out) :: a            !! top node of the region
      integer, intent(out) :: b            !! bottom node of the region
      real(wp), intent(out) :: shift_amount    !! its shift along x [m] (0: none)
      call base_fragment(mesh, st, bf, policy, a, b)
      shift_amount = 0.0_wp
      if (policy == shift_face) then
         ! only the face half moves (correct_admissible): it is never held
         shift_amount = -bf%sgn * corr
      else if (.not. anchored(mesh, st, a, b)) then
         shift_amount = -bf%sgn * corr
         if (bf%side == face_top) then
            call extend_down(mesh, st, b, shift_amount)
         else
            call extend_up(mesh, st, a, shift_amount)
         end if
         ! taking along what it is pushed into can reach a held end: then nothing moves
         if (anchored(mesh, st, a, b)) shift_amount = 0.0_wp
      end if
   end subroutine land_side

   !> The admissible rules' landing: the face lands when it overlaps the base by more than
   !> eps_rel dx; the base does not move, so the bar's side takes the whole correction,
   !> rigidly (correct_admissible); a gain of the held bar's measure is kept as its credit.
   pure subroutine land_admissible(mesh, st, bf, g, timing, policy, events, i_top, i_bot, eps_rel)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(in) :: eps_rel      !! the contact tolerance, of a cell [-]
      real(wp) :: e_wave0, tol, du0, d_acc, d_del, corr, shift_amount, d_pre
      integer :: r_top, r_bot, a, b
      logical :: at_n
      tol = eps_rel * mesh%dx(bf%c)
      if (.not. bf%sgn * (face_u(st, bf) - st%ends(bf%side)%u_contact) > tol) return
      call base_fragment(mesh, st, bf, -1, r_top, r_bot)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
      call landing_start(mesh, st, bf, g, timing, policy, tol, du0, d_acc, d_del, at_n, corr, &
                         a, b, shift_amount)
      if (timing == timing_within) then
         ! at t^{n+1}, the overlap the step's motion made kept as strain of the end cell
         ! (strain_base); one the face already had at t^n is moved away as a length defect
         ! (even one within the contact tolerance, which gap_at_n reads as touching)
         d_pre = max(0.0_wp, bf%sgn * ((face_u(st, bf) - face_du(st, bf)) - &
                                       st%ends(bf%side)%u_contact))
         if (d_pre > 0.0_wp) then
            call move_base_face(st, bf, bf%sgn * d_pre, 0.0_wp)
            st%ledger%e_shift = st%ledger%e_shift - g * face_mass(mesh, bf) * bf%sgn * d_pre
            st%ledger%m_drift = st%ledger%m_drift - face_mass(mesh, bf) * bf%sgn * d_pre
         end if
         call join_base(mesh, st, bf, g, .false., d_del, a, -bf%sgn * d_del, du0, events)
         call strain_base(mesh, st, bf, g, d_del - d_pre)
         call keep_credit(mesh, st, g, i_top, i_bot, e_wave0)
         st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                                 region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
         return
      end if
      call correct_admissible(mesh, st, bf, g, policy, i_top, i_bot, d_acc, d_del, at_n, corr, &
                              a, b, shift_amount)
      call join_base(mesh, st, bf, g, at_n, corr, a, shift_amount, du0, events)
      call keep_credit(mesh, st, g, i_top, i_bot, e_wave0)
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                              region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
   end subroutine land_admissible

   !> The paper's landing: the face lands when it overlaps the base at all; the region is
   !> shifted rigidly at t^n, or on its path at t^{n+1} (correct_paper).
   pure subroutine land_paper(mesh, st, bf, g, timing, policy, events, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), parameter :: tol = 0.0_wp
      real(wp) :: e_wave0, du0, d_acc, d_del, corr, shift_amount
      integer :: r_top, r_bot, a, b
      logical :: at_n
      if (.not. bf%sgn * (face_u(st, bf) - st%ends(bf%side)%u_contact) > tol) return
      call landing_region(mesh, st, bf, policy, r_top, r_bot)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
      call landing_start(mesh, st, bf, g, timing, policy, tol, du0, d_acc, d_del, at_n, corr, &
                         a, b, shift_amount)
      call correct_paper(mesh, st, bf, g, policy, d_acc, at_n, corr, a, b, shift_amount)
      call join_base(mesh, st, bf, g, at_n, corr, a, shift_amount, du0, events)
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                              region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
   end subroutine land_paper

   !> What a landing starts from: the face half's increment of the step before, the
   !> corrections (5.2) at t^n and t^{n+1}, the timing rule's choice and the region it moves.
   pure subroutine landing_start(mesh, st, bf, g, timing, policy, tol, du0, d_acc, d_del, at_n, &
                                 corr, a, b, shift_amount)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      real(wp), intent(in) :: tol          !! contact tolerance [m] (0: the paper's rules)
      real(wp), intent(out) :: du0         !! the face half's increment over the step before [m]
      real(wp), intent(out) :: d_acc       !! correction (5.2) for a landing at t^n [m]
      real(wp), intent(out) :: d_del       !! correction (5.2) for a landing at t^{n+1} [m]
      logical, intent(out) :: at_n         !! land at t^n (else t^{n+1})
      real(wp), intent(out) :: corr        !! the chosen correction [m]
      integer, intent(out) :: a            !! top node of the region moved
      integer, intent(out) :: b            !! bottom node of the region moved
      real(wp), intent(out) :: shift_amount   !! its shift along x [m]
      if (bf%side == face_top) then
         du0 = du_before_b(mesh, st, g, bf%e)
      else
         du0 = du_before_a(mesh, st, g, bf%e)
      end if
      d_acc = gap_at_n(st, bf, tol)
      d_del = bf%sgn * (face_u(st, bf) - st%ends(bf%side)%u_contact)
      call choose_time(timing, d_acc, d_del, at_n, corr)
      call land_side(mesh, st, bf, policy, corr, a, b, shift_amount)
   end subroutine landing_start

   !> The face meets the rigid base (alpha -> infinity: the face half stops) at the time and
   !> with the correction the rule set settled on: the event, the node's join with the base.
   pure subroutine join_base(mesh, st, bf, g, at_n, corr, a, shift_amount, du0, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      logical, intent(in) :: at_n          !! it landed at t^n (else t^{n+1})
      real(wp), intent(in) :: corr         !! the correction (5.2) of that time [m]
      integer, intent(in) :: a             !! top node of the region moved
      real(wp), intent(in) :: shift_amount !! its shift along x [m]
      real(wp), intent(in) :: du0          !! the face half's increment over the step before [m]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp) :: e0, du_trial
      integer :: above, below
      type(event_t) :: ev
      ev%kind = ev_base_collision
      ! the collision stress (5.6), alpha -> infinity, with the face's velocity into the base
      if (at_n) then
         ev%stress = 2.0_wp * st%s_old(bf%c) + bf%sgn * mesh%z(bf%c) * du0 / mesh%dt
      else
         ev%stress = 2.0_wp * st%s(bf%c) + bf%sgn * mesh%z(bf%c) * face_du(st, bf) / mesh%dt
      end if
      ev%stress_bound = abs(2.0_wp * st%s(bf%c))                   ! (6.3), alpha -> infinity
      e0 = node_energy(mesh, st, g, bf%e)
      du_trial = face_du(st, bf)
      st%ends(bf%side)%contact = .true.
      st%ledger%i_support = st%ledger%i_support - face_mass(mesh, bf) * du_trial / mesh%dt
      st%dua(bf%e) = 0.0_wp
      st%dub(bf%e) = 0.0_wp
      if (at_n) then
         call move_base_face(st, bf, du_trial, 0.0_wp)
         st%s(bf%c) = st%s(bf%c) + bf%sgn * mesh%stiff(bf%c) * du_trial
         if (bf%side == face_top) then
            st%section(bf%e) = section_stress_b(st%s_old(bf%c), 0.0_wp, du0 / mesh%dt, 0.0_wp, &
                                                mesh%z(bf%c), mesh%dm(bf%c), g)
         else
            st%section(bf%e) = section_stress_a(st%s_old(bf%c), 0.0_wp, du0 / mesh%dt, 0.0_wp, &
                                                mesh%z(bf%c), mesh%dm(bf%c), g)
         end if
      else
         ! joined at t^{n+1}: as for a collision between fragments, s_old follows the
         ! increment so that the ledger's telescoping stays exact; the next step's base
         ! section stress starts from the face half's own velocity with S^{n+1/2} = 0, the
         ! collision stress (5.6), alpha -> infinity
         st%s_old(bf%c) = st%s_old(bf%c) - bf%sgn * mesh%stiff(bf%c) * du_trial
         ! the face keeps the step it took, the base takes its momentum: that step moved the
         ! mass with no momentum left behind it (x_drift)
         st%ledger%m_drift = st%ledger%m_drift + face_mass(mesh, bf) * du_trial
         st%section(bf%e) = 0.0_wp
         st%ends(bf%side)%landing = .true.
         st%ends(bf%side)%v_land = du_trial / mesh%dt
         call skip_next(st, bf%e)
      end if
      st%ledger%e_join = st%ledger%e_join + (e0 - node_energy(mesh, st, g, bf%e))
      call base_ids(st, bf, a, above, below)
      call finish_event(mesh, st, ev, bf%e, at_n, corr, shift_amount, above, below, events)
   end subroutine join_base

   !> A landing timed within the step ('within'), after the face's join with the base at
   !> t^{n+1} (join_base): the face goes back onto the base by d, the overlap the trial step
   !> left, and the end cell takes that change of its length as compression (the base does not
   !> move, so the cell takes all of it), s_old with it (strain_faces, the same for a collision
   !> between fragments). The base section stress S^{n+1/2} takes 2 ds, so that the next
   !> step's (3.1)-(3.2) give the collision stress of the landing. The face's move has no
   !> momentum behind it (x_drift: its mass times d, O(dt^2) per landing).
   pure subroutine strain_base(mesh, st, bf, g, d)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state (the face joined with the base)
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: d            !! the face's overlap with the base [m]
      real(wp) :: e0, ds
      e0 = node_energy(mesh, st, g, bf%e)
      ds = mesh%stiff(bf%c) * d
      call move_base_face(st, bf, bf%sgn * d, 0.0_wp)
      st%s(bf%c) = st%s(bf%c) + ds
      st%s_old(bf%c) = st%s_old(bf%c) + ds
      st%section(bf%e) = st%section(bf%e) + 2.0_wp * ds
      st%ledger%e_shift = st%ledger%e_shift - g * face_mass(mesh, bf) * bf%sgn * d
      st%ledger%m_drift = st%ledger%m_drift - face_mass(mesh, bf) * bf%sgn * d
      st%ledger%e_join = st%ledger%e_join + (e0 - node_energy(mesh, st, g, bf%e))
   end subroutine strain_base

   !> The admissible rules' landing correction: the base does not move, so the bar's side
   !> takes the whole correction, rigidly; where that would move it against gravity and a
   !> load on its far face the other time is taken (closing the gap at t^n moves it into the
   !> base's direction, removing the overlap at t^{n+1} away from it).
   pure subroutine correct_admissible(mesh, st, bf, g, policy, i_top, i_bot, d_acc, d_del, at_n, &
                                   corr, a, b, shift_amount)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: policy        !! shift policy (shift_*)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(in) :: d_acc        !! correction (5.2) for a landing at t^n [m]
      real(wp), intent(in) :: d_del        !! correction (5.2) for a landing at t^{n+1} [m]
      logical, intent(inout) :: at_n       !! land at t^n (else t^{n+1}); updated
      real(wp), intent(inout) :: corr      !! the chosen correction; updated [m]
      integer, intent(inout) :: a          !! top node of the region moved
      integer, intent(inout) :: b          !! bottom node of the region moved
      real(wp), intent(inout) :: shift_amount   !! its shift along x [m]; updated
      real(wp) :: bias, other
      integer :: j_near, k_near
      ! bias: the push of gravity and the far face's load along +x; the bar side moves by
      ! -sgn corr: against the bias, take the other time's correction if it moves along it,
      ! or the smaller one where both go against
      if (policy == shift_face) then
         bias = g * face_mass(mesh, bf) * mesh%dt
      else
         bias = g * span_mass(mesh, a, b) * mesh%dt
         if (bf%side == face_bottom .and. a == 0) bias = bias + i_top
         if (bf%side == face_top .and. b == mesh%n) bias = bias - i_bot
      end if
      other = merge(d_del, d_acc, at_n)
      if (bias * (-bf%sgn * corr) < 0.0_wp .and. (.not. bias * (-bf%sgn * other) < 0.0_wp .or. &
                                                 abs(other) < abs(corr))) then
         at_n = .not. at_n
         corr = other
         call land_side(mesh, st, bf, policy, corr, a, b, shift_amount)
      end if
      ! a bar side that cannot move (held at its other end) lands at t^n: the face keeps the
      ! small gap it had then, never an overlap
      if (.not. abs(shift_amount) > 0.0_wp .and. .not. at_n) then
         at_n = .true.
         corr = d_acc
      end if
      if (.not. abs(shift_amount) > 0.0_wp) return
      if (policy == shift_face) then
         ! the 'face' policy: the face half alone moves onto the base (a length defect of its
         ! end cell; nothing beyond the end node moves)
         call move_base_face(st, bf, -shift_amount, 0.0_wp)
         st%ledger%e_shift = st%ledger%e_shift + g * face_mass(mesh, bf) * shift_amount
         st%ledger%m_drift = st%ledger%m_drift + face_mass(mesh, bf) * shift_amount
      else if (bf%side == face_top) then
         call fragment_span(mesh, st, 0, j_near, k_near)
         call shift_part(mesh, st, g, 0, min(b, k_near), shift_amount, .false.)
         if (b > k_near) call shift_part(mesh, st, g, k_near, b, shift_amount, .true.)
         if (b == mesh%n) call book_shift_work(st, -i_bot / mesh%dt * shift_amount)
      else
         call fragment_span(mesh, st, mesh%n, j_near, k_near)
         if (a < j_near) call shift_part(mesh, st, g, a, j_near, shift_amount, .true.)
         call shift_part(mesh, st, g, max(a, j_near), mesh%n, shift_amount, .false.)
         if (a == 0) call book_shift_work(st, i_top / mesh%dt * shift_amount)
      end if
   end subroutine correct_admissible

   !> The paper's rules' landing correction: the region shifted rigidly at t^n; at t^{n+1} on
   !> its path (shift_late), and where no path leads there or the landing would create energy,
   !> at t^n.
   pure subroutine correct_paper(mesh, st, bf, g, policy, d_acc, at_n, corr, a, b, shift_amount)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: policy        !! shift policy (shift_*)
      real(wp), intent(in) :: d_acc        !! correction (5.2) for a landing at t^n [m]
      logical, intent(inout) :: at_n       !! land at t^n (else t^{n+1}); updated
      real(wp), intent(inout) :: corr      !! the chosen correction; updated [m]
      integer, intent(inout) :: a          !! top node of the region moved
      integer, intent(inout) :: b          !! bottom node of the region moved
      real(wp), intent(inout) :: shift_amount   !! its shift along x [m]; updated
      real(wp) :: w, du_trial, de
      logical :: ok
      if (.not. at_n) then
         call path_speed(mesh, st, g, a, b, shift_amount, w, ok)
         du_trial = face_du(st, bf) + w * mesh%dt
         if (.not. ok .or. -0.5_wp * face_mass(mesh, bf) * ((du_trial / mesh%dt)**2 + &
             g * du_trial) - bf%sgn * 0.5_wp * st%s(bf%c) * du_trial > 0.0_wp) then
            at_n = .true.
            corr = d_acc
            call land_side(mesh, st, bf, policy, corr, a, b, shift_amount)
         end if
      end if
      if (.not. abs(shift_amount) > 0.0_wp) return
      if (at_n) then
         call shift_span(mesh, st, g, a, b, shift_amount, de)
         st%ledger%e_shift = st%ledger%e_shift - de
      else
         call shift_late(mesh, st, g, a, b, shift_amount, w)
      end if
   end subroutine correct_paper

   !> Each face resting on its base leaves it when the base section stress falls below -eps
   !> (the base has no tensile strength), by the rule set's lift-off (lift_admissible,
   !> lift_paper: chosen here); with two bases the stronger pull first (end_order).
   pure subroutine lift_off(mesh, st, g, eps, events, rules, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: eps          !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      integer, intent(in) :: rules         !! event rules (events_*)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      integer :: side, k, order(2)
      type(base_face_t) :: bf
      ! with two bases, the stronger pull lets go first
      order = end_order(merge(-st%section([0, mesh%n]), -huge(1.0_wp), on_base(st%ends)))
      do k = 1, 2
         side = order(k)
         if (.not. on_base(st%ends(side))) cycle
         bf = base_face(mesh, side)
         if (any(st%skip_test(1:st%n_skip) == bf%e)) cycle
         if (.not. (st%section(bf%e) < -eps)) cycle
         select case (rules)
         case (events_paper)
            call lift_paper(mesh, st, bf, g, events, i_top, i_bot)
         case default
            call lift_admissible(mesh, st, bf, g, eps, events, i_top, i_bot)
         end select
      end do
   end subroutine lift_off

   !> The admissible lift-off, as a break: the bar left at t^n, and its face moves over the
   !> step by twice the characteristic interval coming in to it at t^n (2 f_n at the bottom,
   !> 2 g_1 at the top; the base's impulse of the step is given back). A bar held at its other
   !> end with an odd cell count, under gravity: its face moves by that plus d*/2
   !> (d* = g dt^2 / (Z C)), where the free bar's measure has its vertex, K lower
   !> (vertex_offset), which pays the credit of its landing (K - credit >= 0 is removed); it
   !> leaves only where that step is still off the base: the base holds a pull of up to
   !> Z d* / (2 dt) when gravity presses the bar onto it (doc/method.md, "A landing credit").
   pure subroutine lift_admissible(mesh, st, bf, g, eps, events, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: eps          !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp) :: s_base, d_a, e_wave0, vertex, w_in
      real(wp), allocatable :: f(:), gw(:)
      integer :: a, b
      s_base = st%section(bf%e)
      call base_fragment(mesh, st, bf, -1, a, b)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, a, b)
      allocate(f(a+1:b), gw(a+1:b))
      call fragment_characteristics(mesh, st, g, a, b, i_top, i_bot, .true., f, gw)
      vertex = 0.0_wp
      if (held_odd(mesh, st, a, b)) vertex = vertex_offset(mesh, g, a, b, bf%c)
      ! the interval coming in to the face (f_n down at the bottom, g_1 up at the top)
      w_in = merge(gw(a+1), f(b), bf%side == face_top)
      ! the base lets go where the continuum reading's base stress pulls too (as breaks),
      ! beyond the pull it holds for the held bar's vertex
      if (.not. bf%sgn * (mesh%z(bf%c) / mesh%dt * (2.0_wp * w_in + vertex)) < -eps) then
         st%section(bf%e) = bf%sgn * (2.0_wp * mesh%z(bf%c) / mesh%dt * w_in)
         return
      end if
      ! the step redone from t^n for the face: it moves by 2 w_in (+ the vertex's offset), the
      ! end cell follows
      d_a = face_du(st, bf) - (2.0_wp * w_in + vertex)
      call leave_base(mesh, st, bf, g, d_a, bf%sgn * mesh%stiff(bf%c) * d_a)
      call lift_off_event(mesh, st, bf, a, s_base, events)
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                              region_wave(mesh, st, g, i_top, i_bot, a, b)
   end subroutine lift_admissible

   !> The paper's lift-off: stage 1 on the bar side only (the face moves back by the base
   !> stress's step, the end cell's stress releases it), stage 2 (the fragment shifted by
   !> half of that) where it is not anchored.
   pure subroutine lift_paper(mesh, st, bf, g, events, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp) :: s_base, d_a, de, e_wave0
      integer :: a, b
      s_base = st%section(bf%e)
      call base_fragment(mesh, st, bf, -1, a, b)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, a, b)
      d_a = -bf%sgn * s_base * mesh%dt**2 / mesh%dm(bf%c)
      call leave_base(mesh, st, bf, g, d_a, -s_base)
      if (.not. anchored(mesh, st, a, b)) then
         call shift_span(mesh, st, g, a, b, 0.5_wp * d_a, de)
         st%ledger%e_fracture = st%ledger%e_fracture - de
      end if
      call lift_off_event(mesh, st, bf, a, s_base, events)
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                              region_wave(mesh, st, g, i_top, i_bot, a, b)
   end subroutine lift_paper

   !> The face leaves its base: its step redone by -d_a (the base's impulse of it given back),
   !> the end cell's stress changed by ds, the contact and the landing credit ended, the change
   !> of the scheme's measure booked in e_fracture.
   pure subroutine leave_base(mesh, st, bf, g, d_a, ds)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: d_a          !! taken from the face half's u and du [m]
      real(wp), intent(in) :: ds           !! stress change of the end cell [Pa]
      real(wp) :: e0
      e0 = node_energy(mesh, st, g, bf%e)
      call move_base_face(st, bf, d_a, d_a)
      st%ledger%i_support = st%ledger%i_support - face_mass(mesh, bf) * d_a / mesh%dt
      st%s(bf%c) = st%s(bf%c) + ds
      st%ends(bf%side)%contact = .false.
      st%u_credit = 0.0_wp
      st%section(bf%e) = 0.0_wp
      st%ledger%e_fracture = st%ledger%e_fracture + (e0 - node_energy(mesh, st, g, bf%e))
   end subroutine leave_base
end module spb_base
