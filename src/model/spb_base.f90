!> The rigid base (doc/method.md, "Rigid base and dry interfaces"): the bottom face lands on
!> it and lifts off it again. Landing is a collision with a partner of infinite impedance
!> (alpha -> oo in (5.6)) put on the grid by the timing rule; lift-off is a break of the
!> face's section against the base. Both are here, called where the collisions (spb_contact) and the
!> breaks (spb_fracture) of the step are made, so the events keep their order.
module spb_base
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_bottom, has_base
   use spb_state, only: state_t
   use spb_section, only: section_stress_a
   use spb_events, only: event_t, event_list_t, push_event, ev_base_collision, ev_separation
   use spb_wave, only: fragment_characteristics, region_wave, held_odd, vertex_offset
   use spb_fragments, only: node_energy, anchored, fragment_span, span_mass, shift_span, &
      choose_time, du_before_a, path_speed, shift_late, shift_part, extend_up, finish_event, &
      book_shift_work, skip_next, keep_credit
   use spb_problem, only: events_admissible, shift_above
   implicit none
   private
   public :: touch_base, lift_off

contains

   !> After the trial step: a bottom face off the base that has passed it lands (land), its
   !> region's wave measure before and after booked in e_lost_wave.
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
      real(wp) :: e_wave0, tol
      integer :: r_top, r_bot
      if (has_base(st%ends(face_bottom)) .and. .not. st%ends(face_bottom)%contact) then
         tol = 0.0_wp
         if (rules == events_admissible) tol = eps_rel * mesh%dx(mesh%n)
         if (st%ua(mesh%n) - st%ends(face_bottom)%u_contact > tol) then
            if (rules == events_admissible) then
               call fragment_span(mesh, st, mesh%n, r_top, r_bot)
               r_bot = mesh%n
            else
               call landing_region(mesh, st, policy, r_top, r_bot)
            end if
            e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
            call land(mesh, st, g, timing, policy, events, rules, i_top, tol)
            if (rules == events_admissible) call keep_credit(mesh, st, g, i_top, i_bot, e_wave0)
            st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - &
                             region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
         end if
      end if
   end subroutine touch_base

   !> Fragment boundaries around everything a landing can change under the paper's rules:
   !> the fragment on the base and whatever either correction (5.2) shifts; the whole bar
   !> for 'above'.
   pure subroutine landing_region(mesh, st, policy, r_top, r_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(out) :: r_top        !! top node of the region the event can change
      integer, intent(out) :: r_bot        !! bottom node of that region
      real(wp) :: d_acc, d_del, amount
      integer :: j, k, top, bot
      r_top = 0
      r_bot = mesh%n
      if (policy == shift_above) return
      call fragment_span(mesh, st, mesh%n, j, k)
      d_acc = (st%ua(mesh%n) - st%dua(mesh%n)) - st%ends(face_bottom)%u_contact
      d_del = st%ua(mesh%n) - st%ends(face_bottom)%u_contact
      call land_side(mesh, st, policy, d_acc, top, amount)
      call land_side(mesh, st, policy, d_del, bot, amount)
      r_top = min(j, top, bot)
   end subroutine landing_region

   !> The correction (5.2) that closes the gap to the base at t^n, u_A^n - u_base, where an
   !> overlap at t^n within the contact tolerance counts as touching: the face met it then
   !> (to round-off), and moving the bar by that much would only lift it.
   pure real(wp) function gap_at_n(st, n, tol) result(d_acc)
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: n             !! the bottom node
      real(wp), intent(in) :: tol          !! contact tolerance [m] (0: the paper's rules)
      d_acc = (st%ua(n) - st%dua(n)) - st%ends(face_bottom)%u_contact
      if (d_acc > 0.0_wp .and. d_acc <= tol) d_acc = 0.0_wp
   end function gap_at_n

   !> The region a landing's correction moves: the fragment on the base's side (all of the
   !> bar for 'above'), unless it is anchored; top node j.
   pure subroutine land_side(mesh, st, policy, corr, j, shift_amount)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: policy        !! shift policy (shift_*)
      real(wp), intent(in) :: corr         !! the chosen correction (5.2) [m]
      integer, intent(out) :: j            !! top node of the region
      real(wp), intent(out) :: shift_amount    !! its shift along x [m] (0: none)
      integer :: k
      call fragment_span(mesh, st, mesh%n, j, k)
      if (policy == shift_above) j = 0
      shift_amount = 0.0_wp
      if (.not. anchored(mesh, st, j, mesh%n)) then
         shift_amount = -corr
         call extend_up(mesh, st, j, shift_amount)
         ! taking along what it is pushed into can reach a held top: then nothing moves
         if (anchored(mesh, st, j, mesh%n)) shift_amount = 0.0_wp
      end if
   end subroutine land_side

   !> The bottom face meets the rigid base (alpha -> infinity: the bottom half stops).
   pure subroutine land(mesh, st, g, timing, policy, events, rules, i_top, tol)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: tol              !! contact tolerance [m] (0: the paper's rules)
      integer, intent(in) :: timing        !! collision timing rule (timing_*)
      integer, intent(in) :: policy        !! shift policy (shift_*)
      integer, intent(in) :: rules         !! event rules (events_*)
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp) :: d_acc, d_del, corr, e0, de, du_trial, dua0, shift_amount, w, bias, other
      integer :: n, j, j_near, k
      logical :: at_n, ok
      type(event_t) :: ev
      n = mesh%n
      dua0 = du_before_a(mesh, st, g, n)
      d_acc = gap_at_n(st, n, tol)
      d_del = st%ua(n) - st%ends(face_bottom)%u_contact
      call choose_time(timing, d_acc, d_del, at_n, corr)
      call land_side(mesh, st, policy, corr, j, shift_amount)
      if (rules == events_admissible) then
         ! the base does not move: the bar's side takes the whole correction, rigidly; where
         ! that would move it against gravity and a load on its top face the other time is
         ! taken (closing the gap at t^n moves it down, removing the overlap at t^{n+1} up)
         bias = g * span_mass(mesh, j, n) * mesh%dt
         if (j == 0) bias = bias + i_top
         ! the bar side moves by -corr: against the bias, take the other time's correction
         ! if it moves along it, or the smaller one where both go against
         other = merge(d_del, d_acc, at_n)
         if (-bias * corr < 0.0_wp .and. (.not. -bias * other < 0.0_wp .or. &
                                          abs(other) < abs(corr))) then
            at_n = .not. at_n
            corr = other
            call land_side(mesh, st, policy, corr, j, shift_amount)
         end if
         ! a bar side that cannot move (held by a fixed top) lands at t^n: the face keeps the
         ! small gap it had then, never an overlap
         if (.not. abs(shift_amount) > 0.0_wp .and. .not. at_n) then
            at_n = .true.
            corr = d_acc
         end if
         if (abs(shift_amount) > 0.0_wp) then
            call fragment_span(mesh, st, n, j_near, k)
            if (j < j_near) call shift_part(mesh, st, g, j, j_near, shift_amount, .true.)
            call shift_part(mesh, st, g, max(j, j_near), n, shift_amount, .false.)
            if (j == 0) call book_shift_work(st, i_top / mesh%dt * shift_amount)
         end if
      else if (.not. at_n) then
         ! as for a collision: on its path, and never creating energy, else at t^n
         call path_speed(mesh, st, g, j, n, shift_amount, w, ok)
         du_trial = st%dua(n) + w * mesh%dt
         if (.not. ok .or. -0.5_wp * mesh%ma(n) * ((du_trial / mesh%dt)**2 + g * du_trial) &
             - 0.5_wp * st%s(n) * du_trial > 0.0_wp) then
            at_n = .true.
            corr = d_acc
            call land_side(mesh, st, policy, corr, j, shift_amount)
         end if
      end if
      if (abs(shift_amount) > 0.0_wp .and. rules /= events_admissible) then
         if (at_n) then
            call shift_span(mesh, st, g, j, n, shift_amount, de)
            st%ledger%e_shift = st%ledger%e_shift - de
         else
            call shift_late(mesh, st, g, j, n, shift_amount, w)
         end if
      end if
      ev%kind = ev_base_collision
      if (at_n) then
         ev%stress = 2.0_wp * st%s_old(n) + mesh%z(n) * dua0 / mesh%dt
      else
         ev%stress = 2.0_wp * st%s(n) + mesh%z(n) * st%dua(n) / mesh%dt
      end if
      ev%stress_bound = abs(2.0_wp * st%s(n))                      ! (6.3), alpha -> infinity
      e0 = node_energy(mesh, st, g, n)
      du_trial = st%dua(n)
      st%ends(face_bottom)%contact = .true.
      st%ledger%i_support = st%ledger%i_support - mesh%ma(n) * du_trial / mesh%dt
      st%dua(n) = 0.0_wp
      st%dub(n) = 0.0_wp
      if (at_n) then
         st%ua(n) = st%ua(n) - du_trial
         st%ub(n) = st%ua(n)
         st%s(n) = st%s(n) + mesh%stiff(n) * du_trial
         st%section(n) = section_stress_a(st%s_old(n), 0.0_wp, dua0 / mesh%dt, 0.0_wp, mesh%z(n), &
                                      mesh%dm(n), g)
      else
         ! joined at t^{n+1}: as for a collision between fragments, s_old follows the
         ! increment so that the ledger's telescoping stays exact; the next step's base
         ! section stress starts from the bottom half's own velocity with S^{n+1/2} = 0, the
         ! collision stress (5.6), alpha -> infinity
         st%s_old(n) = st%s_old(n) - mesh%stiff(n) * du_trial
         st%section(n) = 0.0_wp
         st%ends(face_bottom)%landing = .true.
         st%ends(face_bottom)%v_land = du_trial / mesh%dt
         call skip_next(st, n)
      end if
      st%ledger%e_join = st%ledger%e_join + (e0 - node_energy(mesh, st, g, n))
      call finish_event(mesh, st, ev, n, at_n, corr, shift_amount, st%gen%frag_id(j), 0, events)
   end subroutine land

   !> The bar leaves the rigid base when the base section stress falls below -eps (the
   !> base has no tensile strength): 'paper', stage 1 and 2 on the bar side only;
   !> 'admissible', as a break: the bar left at t^n, and its bottom face moves over the step
   !> by 2 f_n of the continuum state at t^n (the base's impulse of the step is given back).
   !> A bar held by a fixed top with an odd cell count, under gravity: its bottom face moves
   !> by 2 f_n + d*/2 (d* = g dt^2 / (Z_n C)), where the free bar's measure has its vertex,
   !> K lower (vertex_offset), which pays the credit of its landing (K - credit >= 0 is
   !> removed); it leaves only where that step is still off the base, 2 f_n + d*/2 < 0: for
   !> g > 0 the base holds a pull of up to Z_n d* / (2 dt) (doc/method.md, "A landing
   !> credit").
   pure subroutine lift_off(mesh, st, g, eps, events, rules, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: eps          !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      integer, intent(in) :: rules         !! event rules (events_*)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp) :: s_base, d_a, e0, de, e_wave0, vertex
      real(wp), allocatable :: f(:), gw(:)
      integer :: n, j, k
      type(event_t) :: ev
      n = mesh%n
      if (any(st%skip_test(1:st%n_skip) == n)) return
      if (.not. (st%section(n) < -eps)) return
      s_base = st%section(n)
      call fragment_span(mesh, st, n, j, k)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, j, n)
      if (rules == events_admissible .and. .not. mesh%full_mass) then
         allocate(f(j+1:n), gw(j+1:n))
         call fragment_characteristics(mesh, st, g, j, n, i_top, i_bot, .true., f, gw)
         vertex = 0.0_wp
         if (held_odd(mesh, st, j, n)) vertex = vertex_offset(mesh, g, j, n, n)
         ! the base lets go where the continuum reading's base stress pulls too (as breaks),
         ! beyond the pull it holds for the held bar's vertex
         if (.not. (mesh%z(n) / mesh%dt * (2.0_wp * f(n) + vertex) < -eps)) then
            st%section(n) = 2.0_wp * mesh%z(n) / mesh%dt * f(n)
            return
         end if
         ! the step redone from t^n for the bottom face: it moves by 2 f_n (+ the vertex's
         ! offset)
         d_a = st%dua(n) - (2.0_wp * f(n) + vertex)
      else
         ! stage 1 on the bar side; the full-mass model lets go without corrections (it has
         ! no section stresses)
         d_a = merge(0.0_wp, -s_base * mesh%dt**2 / mesh%dm(n), mesh%full_mass)
      end if
      e0 = node_energy(mesh, st, g, n)
      st%ua(n) = st%ua(n) - d_a
      st%dua(n) = st%dua(n) - d_a
      st%ledger%i_support = st%ledger%i_support - mesh%ma(n) * d_a / mesh%dt
      st%ub(n) = st%ua(n)
      st%dub(n) = st%dua(n)
      if (rules == events_admissible) then
         st%s(n) = st%s(n) + mesh%stiff(n) * d_a    ! the cell above follows the redone step
      else if (.not. mesh%full_mass) then
         st%s(n) = st%s(n) - s_base                 ! stage 1 releases the base stress
      end if
      st%ends(face_bottom)%contact = .false.
      st%u_credit = 0.0_wp
      st%section(n) = 0.0_wp
      st%ledger%e_fracture = st%ledger%e_fracture + (e0 - node_energy(mesh, st, g, n))
      if (rules /= events_admissible .and. .not. anchored(mesh, st, j, n)) then
         ! stage 2
         call shift_span(mesh, st, g, j, n, 0.5_wp * d_a, de)
         st%ledger%e_fracture = st%ledger%e_fracture - de
      end if
      ev%kind = ev_separation
      ev%step = st%step
      ev%node = n
      ev%t = real(st%step, wp) * mesh%dt
      ev%x = mesh%x(n)
      ev%stress = s_base
      ev%dt_bound = mesh%dt
      ev%dx_bound = 0.0_wp
      ev%opening = st%ends(face_bottom)%u_contact - st%ua(n)
      ev%frag_above = st%gen%frag_id(j)
      call push_event(events, ev)
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - region_wave(mesh, st, g, i_top, i_bot, j, n)
   end subroutine lift_off
end module spb_base
