!> Spall: fracture of a section (3.3)-(3.6) (doc/method.md, "Fracture").
!>
!> After each step, a joined interior node breaks at t^{n+1} when its section stress
!> S^{n+1/2} < -R_i - eps, eps = eps_rel * (largest stress magnitude so far), and, where the
!> section has a damage integral K > 0, once its damage has reached K (spb_damage). How it breaks
!> is the rule set's, chosen here once per step: the paper's two-stage correction
!> (spb_rules_paper) or the admissible break from the continuum state at t^n
!> (spb_rules_admissible); every energy change is booked in e_fracture, so the ledger stays
!> closed. The full-mass comparison model breaks springs instead (spb_full_mass), also
!> chosen here. Before the breaks: the events of the cohesive cracks and the lift-off from
!> the base (spb_base).
module spb_fracture
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, on_base
   use spb_state, only: state_t, separates
   use spb_events, only: event_t, event_list_t, push_event, ev_crack
   use spb_wave, only: region_wave
   use spb_problem, only: events_admissible, events_paper
   use spb_fragments, only: fragment_span, record_break
   use spb_base, only: lift_off
   use spb_rules_paper, only: paper_breaks
   use spb_rules_admissible, only: admissible_breaks
   use spb_full_mass, only: full_mass_fracture
   use spb_damage, only: damage_reached
   implicit none
   private
   public :: fracture_step, events_admissible, events_paper, first_overlap

   !> Nodes the fracture test looks at together before it looks at them one by one.
   integer, parameter :: scan_block = 64

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
      real(wp) :: eps, s_max, du_max
      integer :: k
      real(wp), parameter :: velocity_floor = 1.0e-12_wp   !! round-off floor, share of Z|v|

      if (st%coh%n_pending > 0) call crack_events(mesh, st, events)
      if (st%coh%n_active > 0) call complete_cracks(mesh, st, events)
      if (st%n_breakable == 0 .and. .not. any(on_base(st%ends))) return
      ! the largest stress and increment in one pass over the nodes
      s_max = 0.0_wp
      du_max = abs(st%dua(0))
      do k = 1, mesh%n
         s_max = max(s_max, abs(st%s(k)))
         du_max = max(du_max, abs(st%dua(k)))
      end do
      st%s_scale = max(st%s_scale, s_max, abs(st%section(mesh%n)))
      if (on_base(st%ends(face_top))) st%s_scale = max(st%s_scale, abs(st%section(0)))
      ! the section stresses are formed from the nodes' velocities, so they round off at
      ! about epsilon Z |v| even in uniform motion, where no stress sets the scale: a floor
      ! of 1e-12 Z|v| (frame-dependent, but far below eps_rel s_scale wherever stresses act)
      eps = max(eps_rel * st%s_scale, velocity_floor * maxval(mesh%impedance * mesh%seg_area) * &
                du_max / mesh%dt)
      if (mesh%full_mass) then
         ! the full-mass model: its own lift-off, springs instead of sections
         call full_mass_fracture(mesh, st, g, eps, events, i_top, i_bot)
         return
      end if
      if (any(on_base(st%ends))) call lift_off(mesh, st, g, eps, events, &
                                                                       rules, i_top, i_bot)
      if (st%n_breakable == 0) return
      call break_nodes(mesh, st, g, eps, events, rules, i_top, i_bot)
   end subroutine fracture_step

   !> (3.3): all sections that break at this step, tested on the uncorrected step, broken by
   !> the rule set given; the wave energy of the fragments that break, before and after, is
   !> booked in e_lost_wave.
   pure subroutine break_nodes(mesh, st, g, eps, events, rules, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g          !! gravity [m/s^2]
      real(wp), intent(in) :: eps        !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      integer, intent(in) :: rules       !! events_admissible | events_paper
      real(wp), intent(in) :: i_top      !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot      !! load integral on the bottom face over the step [Pa s]
      integer :: cand(mesh%n)
      real(wp) :: e_wave0
      integer :: i, nb, j, k, r_top, r_bot, i0, i1
      logical :: ready
      nb = 0
      do i0 = 1, mesh%n - 1, scan_block
         ! a block none of whose nodes is joined, breakable and below -R - eps is passed over
         ! in one look (the same candidates, in the same order)
         i1 = min(i0 + scan_block - 1, mesh%n - 1)
         if (.not. any(st%section(i0:i1) < -st%strength(i0:i1) - eps .and. &
                       st%strength(i0:i1) >= 0.0_wp .and. st%joined(i0:i1))) cycle
         do i = i0, i1
            if (.not. st%joined(i)) cycle
            if (st%strength(i) < 0.0_wp) cycle
            if (.not. (st%section(i) < -st%strength(i) - eps)) cycle
            if (st%coh%on) then
               if (st%coh%gc(i) > 0.0_wp) cycle
            end if
            if (any(st%skip_test(1:st%n_skip) == i)) cycle
            ! time-dependent fracture: the section breaks once its damage reaches K
            ! (spb_damage)
            call damage_reached(mesh, st, i, ready)
            if (.not. ready) cycle
            nb = nb + 1
            cand(nb) = i
         end do
      end do
      if (nb == 0) return
      call fragment_span(mesh, st, cand(1), r_top, k)
      call fragment_span(mesh, st, cand(nb), j, r_bot)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
      select case (rules)
      case (events_admissible)
         call admissible_breaks(mesh, st, g, cand(1:nb), i_top, i_bot, eps, events)
      case default
         call paper_breaks(mesh, st, g, cand(1:nb), events)
      end select
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - region_wave(mesh, st, g, i_top, i_bot, &
                                                               r_top, r_bot)
   end subroutine break_nodes

   !> The events of the cohesive cracks the step opened (spb_crack): each holds from t^n.
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
