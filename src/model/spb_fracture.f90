!> Spall: fracture of a section (3.3)-(3.6) with the two-stage correction (doc/method.md,
!> "Fracture").
!>
!> After each step, a joined interior node breaks at t^{n+1} when its section stress
!> S^{n+1/2} < -R_i - eps, eps = eps_rel * (largest stress magnitude so far). Stage 1
!> releases S into the two adjacent cells (the halves receive opposite impulses -/+ S dt/2:
!> momentum conserved); stage 2 shifts the two new fragments rigidly so that the faces
!> open by (dA + dB)/2, the distance each half really moves under its impulse. Every
!> energy change is booked in e_fracture, so the ledger stays closed.
module spb_fracture
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, face_bottom, holds, on_base
   use spb_state, only: state_t, open_node, separates
   use spb_events, only: event_t, event_list_t, push_event, ev_fracture, ev_separation, ev_crack
   use spb_arrays, only: append
   use spb_wave, only: fragment_characteristics, region_wave, credit_position
   use spb_problem, only: events_admissible, events_paper
   use spb_fragments, only: node_energy, anchored, fragment_span, shift_span, new_fragment_id
   use spb_base, only: lift_off
   implicit none
   private
   public :: fracture_step, events_admissible, events_paper, first_overlap, pay_credit


contains

   !> Test every joined interior node at t^{n+1} = st%step dt and break those in tension
   !> beyond their strength; append one event per fracture.
   pure subroutine fracture_step(mesh, st, g, eps_rel, events, rules, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g          !! gravity [m/s^2]
      real(wp), intent(in) :: eps_rel    !! round-off guard, relative to the stress scale
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      integer, intent(in) :: rules       !! events_admissible | events_paper
      real(wp), intent(in) :: i_top      !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot      !! load integral on the bottom face over the step [Pa s]
      integer :: cand(mesh%n)
      real(wp) :: eps
      integer :: i, nb

      if (st%coh%n_pending > 0) call crack_events(mesh, st, events)
      if (st%coh%n_active > 0) call complete_cracks(mesh, st, events)
      if (st%n_breakable == 0 .and. .not. any(on_base(st%ends))) return
      st%s_scale = max(st%s_scale, maxval(abs(st%s(1:mesh%n))), abs(st%section(mesh%n)))
      if (on_base(st%ends(face_top))) st%s_scale = max(st%s_scale, abs(st%section(0)))
      eps = eps_rel * st%s_scale
      if (any(on_base(st%ends))) call lift_off(mesh, st, g, eps, events, &
                                                                       rules, i_top, i_bot)
      if (st%n_breakable == 0) return
      if (mesh%full_mass) then
         call cut_springs(mesh, st, eps, events)
         return
      end if
      ! (3.3): all sections that break at this step, tested on the uncorrected step
      nb = 0
      do i = 1, mesh%n - 1
         if (.not. st%joined(i)) cycle
         if (st%strength(i) < 0.0_wp) cycle
         if (.not. (st%section(i) < -st%strength(i) - eps)) cycle
         if (st%coh%on) then
            if (st%coh%gc(i) > 0.0_wp) cycle
         end if
         if (any(st%skip_test(1:st%n_skip) == i)) cycle
         nb = nb + 1
         cand(nb) = i
      end do
      if (nb > 0) call break_sections(mesh, st, g, cand(1:nb), eps, events, rules, i_top, i_bot)
   end subroutine fracture_step

   !> The events of the cohesive cracks the step opened (spb_crack): each holds from t^n.
   pure subroutine crack_events(mesh, st, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      type(event_t) :: ev
      integer :: m, i, j
      do m = 1, st%coh%n_pending
         i = st%coh%pending(m)
         ev%kind = ev_crack
         ev%step = st%step - 1
         ev%node = i
         ev%t = real(st%step - 1, wp) * mesh%dt
         ev%x = mesh%x(i)
         ev%stress = st%coh%pending_stress(m)
         ev%dt_bound = mesh%dt
         ev%dx_bound = max(mesh%dx(i), mesh%dx(i + 1))
         ev%opening = st%ub(i) - st%ua(i)
         j = i - 1
         do while (j > 0)
            if (separates(st, j)) exit
            j = j - 1
         end do
         ev%frag_above = st%gen%frag_id(j)
         ev%frag_below = st%gen%frag_id(j)
         call push_event(events, ev)
      end do
      st%coh%n_pending = 0
   end subroutine crack_events

   !> Break the sections brk (ascending, joined, beyond their strength) by the rules given.
   pure subroutine break_sections(mesh, st, g, cand, eps, events, rules, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g          !! gravity [m/s^2]
      integer, intent(in) :: cand(:)     !! the sections to break, ascending
      real(wp), intent(in) :: eps        !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      integer, intent(in) :: rules       !! events_admissible | events_paper
      real(wp), intent(in) :: i_top      !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot      !! load integral on the bottom face over the step [Pa s]
      integer, allocatable :: brk(:)
      real(wp), allocatable :: d_a(:), d_b(:), s_brk(:)
      real(wp) :: dt2, de, shift_up, shift_dn, e_wave0
      integer :: i, m, nb, j, k, r_top, r_bot
      logical :: anchored_up, anchored_dn
      nb = size(cand)
      allocate(brk(nb), d_a(nb), d_b(nb), s_brk(nb))
      brk = cand(1:nb)
      ! the wave energy of the fragments that break, before and after (e_lost_wave)
      call fragment_span(mesh, st, brk(1), r_top, k)
      call fragment_span(mesh, st, brk(nb), j, r_bot)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
      if (rules == events_admissible) then
         call break_admissible(mesh, st, g, brk, i_top, i_bot, eps, events)
         st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - region_wave(mesh, st, g, i_top, i_bot, &
                                                                  r_top, r_bot)
         return
      end if
      dt2 = mesh%dt**2
      ! stage 1, (3.4)-(3.6): each adjacent cell loses exactly S; the new faces are free
      do m = 1, nb
         i = brk(m)
         s_brk(m) = st%section(i)
         d_a(m) = -s_brk(m) * dt2 / mesh%dm(i)
         d_b(m) = -s_brk(m) * dt2 / mesh%dm(i + 1)
         call open_section(mesh, st, g, i, -d_a(m), d_b(m), -s_brk(m), -s_brk(m))
      end do
      ! stage 2: the opening becomes (dA + dB)/2; an anchored fragment (holding a fixed or
      ! a constant-velocity end) does not move and the other one takes the whole correction
      do m = 1, nb
         i = brk(m)
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
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - region_wave(mesh, st, g, i_top, i_bot, &
                                                               r_top, r_bot)
   end subroutine break_sections

   !> A cohesive crack whose largest opening reached the critical one has dissipated its Gc:
   !> it is a fracture now (new fragments, the event), and its section opens no crack again
   !> (Gc = 0: if it closes and parts again, that is a separation). Its faces still take the
   !> last half of the traction of the step that opened it fully (the stepwise form), then
   !> none (cohesive_step).
   pure subroutine complete_cracks(mesh, st, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      integer :: c, i, j
      do c = 1, st%n_split
         i = st%split(c)
         if (.not. (st%coh%gc(i) > 0.0_wp .and. st%coh%dmax(i) >= st%coh%dc(i))) cycle
         if (.not. st%coh%dc(i) > 0.0_wp) cycle
         st%coh%gc(i) = 0.0_wp
         ! the fragment that parts is the one the crack held together: up to the node above
         ! that separates
         j = i - 1
         do while (j > 0)
            if (separates(st, j)) exit
            j = j - 1
         end do
         call record_break(mesh, st, i, j, -st%coh%r(i), events)
      end do
   end subroutine complete_cracks


   !> The admissible break of the sections brk (ascending). A section found at t^{n+1} with
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
   pure subroutine break_admissible(mesh, st, g, cand, i_top, i_bot, eps, events)
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
   end subroutine break_admissible

   !> The break of a bar held at both ends whose measure holds a landing's credit gamma
   !> (spb_contact, keep_credit): the credit leaves the measure with the hold, so the break
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

   !> The naive full-mass model (the paper's Fig. 12 comparison): a spring whose own stress
   !> falls below -R - eps is cut; from then on it carries compression only. No half masses,
   !> no corrections; the strain energy it held is booked in e_fracture.
   pure subroutine cut_springs(mesh, st, eps, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: eps          !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      integer :: k, j, parent
      type(event_t) :: ev
      do k = 1, mesh%n
         if (st%fm%is_cut(k) .or. st%cell_strength(k) < 0.0_wp) cycle
         if (.not. (st%s(k) < -st%cell_strength(k) - eps)) cycle
         ev%stress = st%s(k)
         st%ledger%e_fracture = st%ledger%e_fracture + 0.5_wp * st%s_old(k) * st%s(k) / mesh%stiff(k)
         st%s(k) = 0.0_wp
         st%fm%is_cut(k) = .true.
         st%cell_strength(k) = 0.0_wp
         st%n_breakable = st%n_breakable - 1
         call append(st%fm%cut, st%fm%n_cut, k)
         ! the fragment that held cell k starts at node j (0 or just below a cut cell)
         j = k - 1
         do while (j > 0)
            if (st%fm%is_cut(j)) exit
            j = j - 1
         end do
         parent = st%gen%frag_id(j)
         call new_fragment_id(st, parent, j)
         call new_fragment_id(st, parent, k)
         ev%kind = ev_fracture
         ev%step = st%step
         ev%node = k - 1
         ev%t = real(st%step, wp) * mesh%dt
         ev%x = mesh%x(k) - 0.5_wp * mesh%dx(k)
         ev%dt_bound = mesh%dt
         ev%dx_bound = mesh%dx(k)
         ev%opening = 0.0_wp
         ev%frag_above = st%gen%frag_id(j)
         ev%frag_below = st%gen%frag_id(k)
         call push_event(events, ev)
      end do
   end subroutine cut_springs

   !> First split node whose faces have passed each other, u(A_i) - u(B_i) > tol (0: none).
   pure integer function first_overlap(mesh, st) result(node)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer :: i
      node = 0
      do i = 1, mesh%n - 1
         if (st%joined(i)) cycle
         if (st%ua(i) - st%ub(i) > 1.0e-9_wp * mesh%dx(i)) then
            node = i
            return
         end if
      end do
   end function first_overlap
end module spb_fracture
