!> The full-mass comparison model (`&run model = 'full-mass'`; doc/method.md, "The full-mass
!> comparison model"): the paper's Fig. 12 model "without boundary half masses, whose
!> elementary fragment is a full mass with a one-sided spring". Free end nodes carry full
!> masses; a spring whose own stress falls below -R - eps is cut and carries compression
!> only from then on; no section stresses, no corrections: its supports take the force on
!> the node and the base lets go of the bar without one. It has no continuum reading: its
!> energy measure and the guard's scale are the scheme's own.
!>
!> Everything the model does differently is here, chosen where each phase starts: the set-up
!> (init_full_mass, by spb_sim), the step's cut springs (spb_step advance, which they
!> concern once one is cut), the supports' section stresses (spb_step), the breaks and the
!> lift-off (spb_fracture fracture_step) and the energy measure (spb_sim).
module spb_full_mass
   use spb_kinds, only: wp
   use spb_problem, only: problem_t, end_free
   use spb_mesh, only: mesh_t
   use spb_ends, only: end_t, face_step_t, face_top, face_bottom, on_base
   use spb_state, only: state_t, init_state
   use spb_events, only: event_t, event_list_t, push_event, ev_fracture
   use spb_arrays, only: append
   use spb_wave, only: wave_t, region_wave
   use spb_diag, only: energies_t
   use spb_fragments, only: node_energy, fragment_span, new_fragment_id
   use spb_base_face, only: base_face_t, base_face, move_base_face, base_fragment, lift_off_event, &
      end_order
   implicit none
   private
   public :: init_full_mass, full_mass_fracture, cut_closing, cut_spring_forces, &
      full_mass_supports, full_mass_measure

contains

   !> The model's set-up, in place of init_state: the mesh's free end nodes carry full masses
   !> (the mesh marks the model: mesh%full_mass), then the initial state (2.4) of that mesh,
   !> whose breaking happens in springs: no node ever splits.
   subroutine init_full_mass(prob, mesh, st)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(inout) :: mesh  !! the mesh (half masses at its ends)
      type(state_t), intent(out) :: st     !! the state
      integer :: n
      n = mesh%n
      mesh%full_mass = .true.
      ! the naive model has no half masses at free faces: a free end node is a full mass
      if (prob%top == end_free) mesh%ma(0) = 0.5_wp * mesh%dm(1)
      if (prob%bottom == end_free) mesh%mb(n) = 0.5_wp * mesh%dm(n)
      mesh%inv_m(0) = 1.0_wp / (mesh%ma(0) + mesh%mb(0))
      mesh%inv_m(n) = 1.0_wp / (mesh%ma(n) + mesh%mb(n))
      call init_state(prob, mesh, st)
      st%strength = -1.0_wp
      st%n_breakable = count(st%cell_strength >= 0.0_wp)
      ! no cohesive cracks either (they open at nodes; the deck refuses them, spb_deck)
      st%coh%on = .false.
   end subroutine init_full_mass

   !> The model's part of fracture_step at t^{n+1}: a base lets go of a face it pulls
   !> (full_mass_lift_off; with two bases the stronger pull first), then the springs beyond their
   !> strength are cut.
   pure subroutine full_mass_fracture(mesh, st, g, eps, events, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: eps          !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      integer :: k, order(2)
      ! with two bases, the stronger pull lets go first (spb_base_face end_order)
      order = end_order(merge(-st%section([0, mesh%n]), -huge(1.0_wp), on_base(st%ends)))
      do k = 1, 2
         if (on_base(st%ends(order(k)))) call full_mass_lift_off(mesh, st, &
            base_face(mesh, order(k)), g, eps, events, i_top, i_bot)
      end do
      if (st%n_breakable == 0) return
      call cut_springs(mesh, st, eps, events)
   end subroutine full_mass_fracture

   !> The bar leaves a rigid base when the force on its end node, the base section stress,
   !> falls below -eps (the base has no tensile strength): the model lets go without
   !> corrections (it has no section stresses), the end node's halves move on together.
   !> The wave measure of the fragment on the base, before and after, is booked in
   !> e_lost_wave as for the half-mass model (the model's measure does not read it).
   pure subroutine full_mass_lift_off(mesh, st, bf, g, eps, events, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: eps          !! round-off guard [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp) :: s_base, e0, e_wave0
      integer :: a, b
      if (any(st%skip_test(1:st%n_skip) == bf%e)) return
      if (.not. (st%section(bf%e) < -eps)) return
      s_base = st%section(bf%e)
      call base_fragment(mesh, st, bf, -1, a, b)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, a, b)
      e0 = node_energy(mesh, st, g, bf%e)
      ! the other half follows the face half (zero changes: move_base_face by 0)
      call move_base_face(st, bf, 0.0_wp, 0.0_wp)
      st%ends(bf%side)%contact = .false.
      st%u_credit = 0.0_wp
      st%section(bf%e) = 0.0_wp
      st%ledger%e_fracture = st%ledger%e_fracture + (e0 - node_energy(mesh, st, g, bf%e))
      call lift_off_event(mesh, st, bf, a, s_base, events)
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - region_wave(mesh, st, g, i_top, &
                                                                            i_bot, a, b)
   end subroutine full_mass_lift_off

   !> A spring whose own stress falls below -R - eps is cut; from then on it carries
   !> compression only. No half masses, no corrections; the strain energy it held is booked
   !> in e_fracture.
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

   !> Before a step: each cut cell's closing increment of the step before, du_A(k) - du_B(k-1)
   !> (cut_spring_forces takes the work of its force over both steps) [m].
   pure function cut_closing(st) result(du)
      type(state_t), intent(in) :: st      !! the state at t^n
      real(wp) :: du(st%fm%n_cut)
      integer :: c, k
      do c = 1, st%fm%n_cut
         k = st%fm%cut(c)
         du(c) = st%dua(k) - st%dub(k - 1)
      end do
   end function cut_closing

   !> After the update of a step: a cut spring pushes only in compression,
   !> s = max(0, E/dx (u_{k-1} - u_k)); its force is not part of the linear invariant, so its
   !> work W (the F^n (u^{n+1} - u^{n-1})/2 product) and its strain measure go to e_contact,
   !> keeping the ledger exact.
   pure subroutine cut_spring_forces(mesh, st, du_old)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state at t^{n+1} (s_old: s^n)
      real(wp), intent(in) :: du_old(:)    !! cut_closing before the step [m]
      real(wp) :: w_cut, strain_cut
      integer :: c, k
      w_cut = 0.0_wp
      strain_cut = 0.0_wp
      do c = 1, st%fm%n_cut
         k = st%fm%cut(c)
         w_cut = w_cut + st%s_old(k) * 0.5_wp * ((st%dua(k) - st%dub(k - 1)) + du_old(c))
         st%s(k) = max(0.0_wp, mesh%stiff(k) * (st%ub(k - 1) - st%ua(k)))
         strain_cut = strain_cut + 0.5_wp * st%s_old(k) * st%s(k) / mesh%stiff(k)
      end do
      st%ledger%e_contact = st%ledger%e_contact - w_cut - (strain_cut - st%fm%strain_cut)
      st%fm%strain_cut = strain_cut
   end subroutine cut_spring_forces

   !> The section stresses of the supports the bar rests on, after spb_ends book_ends: the
   !> model has no section stresses, the base takes the force on its node, s_cell + m_in g
   !> (the top's: s_cell - m_in g). The other supports keep book_ends' values.
   pure subroutine full_mass_supports(ends, f, m_in, g, section)
      type(end_t), intent(in) :: ends(2)        !! the two ends
      type(face_step_t), intent(in) :: f(2)     !! what the step did at each end node (s_cell:
                                                !! s^n of the end cell)
      real(wp), intent(in) :: m_in(2)           !! the end node's half mass inside [kg/m^2 A]
      real(wp), intent(in) :: g                 !! gravity along +x [m/s^2]
      real(wp), intent(inout) :: section(2)     !! section stress of each end node [Pa]
      integer :: side
      do side = face_top, face_bottom
         if (.not. on_base(ends(side))) cycle
         if (side == face_top) then
            section(side) = f(side)%s_cell - m_in(side) * g
         else
            section(side) = f(side)%s_cell + m_in(side) * g
         end if
      end do
   end subroutine full_mass_supports

   !> The model's energy measure for the outputs and the guard: the scheme's own (e_wave =
   !> e_kin + e_strain, w_wave = w_ext, e_lost_w = e_lost), and the guard's scale at t = 0,
   !> e_kin + |e_strain|.
   pure subroutine full_mass_measure(e, wv, w_wave, e_lost_w, scale)
      type(energies_t), intent(in) :: e    !! the scheme's energies (spb_diag)
      type(wave_t), intent(out) :: wv      !! the measure (only e_wave)
      real(wp), intent(out) :: w_wave      !! work in that measure [J/m^2]
      real(wp), intent(out) :: e_lost_w    !! energy events removed, in that measure [J/m^2]
      real(wp), intent(out) :: scale       !! the energy guard's scale, read at t = 0 [J/m^2]
      wv%e_wave = e%e_kin + e%e_strain
      w_wave = e%w_ext
      e_lost_w = e%e_lost
      scale = e%e_kin + abs(e%e_strain)
   end subroutine full_mass_measure
end module spb_full_mass
