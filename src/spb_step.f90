!> The compact update (2.3) of the half-node model (METHOD.md §3) for one step.
module spb_step
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t, end_free, end_fixed, end_transmit, end_base
   use spb_load, only: load_t, load_none, face_top, step_load
   use spb_state, only: state_t
   use spb_section, only: section_stress_a, section_stress_b
   implicit none
   private
   public :: advance, end_stresses

contains

   !> Stresses acting on the end faces at t^n: the stepwise load P^n on a loaded free face;
   !> at a transmitting end the static stress it carries, the radiation stress of the
   !> outgoing wave and, when the load acts on that end, 2 P^n for the incident wave of
   !> stress p(t) arriving through it; 0 otherwise. s_top pushes node 0 like a cell above
   !> it; s_bot pushes node n like a cell below it.
   pure subroutine end_stresses(mesh, load, st, s_top, s_bot)
      type(mesh_t), intent(in) :: mesh
      type(load_t), intent(in) :: load
      type(state_t), intent(in) :: st
      real(wp), intent(out) :: s_top, s_bot   !! [Pa]
      real(wp) :: p
      p = 0.0_wp
      if (load%kind /= load_none) p = step_load(load, st%n, mesh%dt)
      s_top = 0.0_wp
      s_bot = 0.0_wp
      select case (mesh%top)
      case (end_free)
         if (load%face == face_top) s_top = p
      case (end_transmit)
         ! u = F(t - x/a) + G(t + x/a) at Courant 1: the virtual cell above node 0 has
         ! s_0 = -(E/dx) du_0^n (outgoing G) + (E/dx) [F(n+1) - F(n-1)] = 2 P^n (incident F)
         s_top = st%s_static_top - mesh%stiff(1) * st%dub(0)
         if (load%face == face_top) s_top = s_top + 2.0_wp * p
      end select
      select case (mesh%bottom)
      case (end_free)
         if (load%face /= face_top) s_bot = p
      case (end_transmit)
         s_bot = st%s_static_bot + mesh%stiff(mesh%n) * st%dua(mesh%n)
         if (load%face /= face_top) s_bot = s_bot + 2.0_wp * p
      end select
   end subroutine end_stresses

   !> Advance the state from t^n to t^{n+1}.
   pure subroutine advance(mesh, load, g, st)
      type(mesh_t), intent(in) :: mesh
      type(load_t), intent(in) :: load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st
      real(wp), allocatable :: swap(:), du_cut_old(:)
      real(wp) :: old_a(st%n_split), old_b(st%n_split), old_sec(st%n_split)
      real(wp) :: dt, dt2, d, du_top_old, du_bot_old, s_top, s_bot, w_cut, strain_cut
      integer :: split(st%n_split)
      integer :: i, n, c, k, n_split

      n = mesh%n
      dt = mesh%dt
      dt2 = dt * dt
      call end_stresses(mesh, load, st, s_top, s_bot)
      st%s(0) = s_top
      st%s(n + 1) = s_bot
      du_top_old = st%dub(0)
      du_bot_old = st%dua(n)
      if (st%n_cut > 0) then
         allocate(du_cut_old(st%n_cut))
         do c = 1, st%n_cut
            k = st%cut(c)
            du_cut_old(c) = st%dua(k) - st%dub(k - 1)
         end do
      end if

      ! (2.3)1-2: a joined node takes the forces on both halves over both masses. Every
      ! node is first updated as joined (one branch-free, vectorisable pass), then the few
      ! split nodes are redone from their saved increments: each half takes its own force.
      n_split = st%n_split
      if (n_split > 0) then
         split = st%split(1:n_split)
         old_a = st%dua(split(1:n_split))
         old_b = st%dub(split(1:n_split))
         old_sec = st%sec(split(1:n_split))
      end if
      if (st%n_breakable > 0) then
         ! (3.1)-(3.2): the section stress S^{n+1/2} of a joined interior node, needed where
         ! a node can break (an unbreakable node's is never read)
         do i = 1, n - 1
            d = st%dua(i) + ((st%s(i) + mesh%ma(i) * g) + (mesh%mb(i) * g - st%s(i + 1))) &
                * mesh%inv_m(i) * dt2
            st%sec(i) = st%s(i) + mesh%z(i) * (st%dua(i) / dt + (st%s(i) - st%sec(i) + &
                        0.5_wp * mesh%dm(i) * g) / mesh%z(i) - d / dt) + 0.5_wp * mesh%dm(i) * g
         end do
      end if
      if (abs(g) > 0.0_wp) then
         do i = 0, n
            d = st%dua(i) + ((st%s(i) + mesh%ma(i) * g) + (mesh%mb(i) * g - st%s(i + 1))) &
                * mesh%inv_m(i) * dt2
            st%dua(i) = d
            st%dub(i) = d
         end do
      else
         ! the same expression with g = 0 (x + 0 = x): two fewer arrays streamed
         do i = 0, n
            d = st%dua(i) + (st%s(i) - st%s(i + 1)) * mesh%inv_m(i) * dt2
            st%dua(i) = d
            st%dub(i) = d
         end do
      end if
      do c = 1, n_split
         i = split(c)
         st%dua(i) = old_a(c) + (st%s(i) + mesh%ma(i) * g) / mesh%ma(i) * dt2
         st%dub(i) = old_b(c) + (mesh%mb(i) * g - st%s(i + 1)) / mesh%mb(i) * dt2
         st%sec(i) = old_sec(c)
      end do
      ! momentum balance: the end stresses act on the end nodes, supports take what reaches
      ! them
      st%i_ends = st%i_ends + (s_top - s_bot) * dt
      if (mesh%top == end_fixed) then
         st%i_support = st%i_support - (mesh%ma(0) * st%dua(0) + mesh%mb(0) * st%dub(0)) / dt
         st%dua(0) = 0.0_wp
         st%dub(0) = 0.0_wp
      end if
      if (mesh%bottom == end_fixed .or. (mesh%bottom == end_base .and. st%base_contact)) then
         st%i_support = st%i_support - (mesh%ma(n) * st%dua(n) + mesh%mb(n) * st%dub(n)) / dt
         st%dua(n) = 0.0_wp
         st%dub(n) = 0.0_wp
      end if
      ! work of the end stresses over the step: F^n (u^{n+1} - u^{n-1}) / 2, which keeps
      ! the discrete energy ledger exact
      associate (w_top => st%s(0) * 0.5_wp * (st%dub(0) + du_top_old), &
                 w_bot => -st%s(n + 1) * 0.5_wp * (st%dua(n) + du_bot_old))
         if (mesh%top == end_transmit) then
            st%w_transmit = st%w_transmit + w_top
         else
            st%w_load = st%w_load + w_top
         end if
         if (mesh%bottom == end_transmit) then
            st%w_transmit = st%w_transmit + w_bot
         else
            st%w_load = st%w_load + w_bot
         end if
      end associate

      ! section stresses at the supports, (3.1)-(3.2) with s^n and v^n, v^{n+1}
      ! a support just hit by a moving half starts from that half's velocity
      if (st%landing_top) du_top_old = st%v_land_top * dt
      if (st%landing_bot) du_bot_old = st%v_land_bot * dt
      st%landing_top = .false.
      st%landing_bot = .false.
      select case (mesh%top)
      case (end_fixed)
         st%sec(0) = section_stress_b(st%s(1), st%sec(0), du_top_old / dt, 0.0_wp, mesh%z(1), &
                                       mesh%dm(1), g)
      case (end_transmit)
         st%sec(0) = section_stress_b(st%s(1), st%sec(0), du_top_old / dt, st%dub(0) / dt, &
                                       mesh%z(1), mesh%dm(1), g)
      end select
      select case (mesh%bottom)
      case (end_fixed)
         st%sec(n) = section_stress_a(st%s(n), st%sec(n), du_bot_old / dt, 0.0_wp, mesh%z(n), &
                                       mesh%dm(n), g)
      case (end_transmit)
         st%sec(n) = section_stress_a(st%s(n), st%sec(n), du_bot_old / dt, st%dua(n) / dt, &
                                       mesh%z(n), mesh%dm(n), g)
      case (end_base)
         ! resting on the rigid base: the base side does not move; v^n is the bottom half's
         ! velocity before the step (0 while it rests)
         if (st%base_contact .and. mesh%full_mass) then
            ! full-mass model: no section stresses; the base takes the force on the node
            st%sec(n) = st%s(n) + mesh%ma(n) * g
         else if (st%base_contact) then
            st%sec(n) = section_stress_a(st%s(n), st%sec(n), du_bot_old / dt, 0.0_wp, &
                                          mesh%z(n), mesh%dm(n), g)
         else
            st%sec(n) = 0.0_wp
         end if
      end select

      ! (2.3)4: s^{n+1} = E (u_{k-1} - u_k)/dx, advanced by the increments of this step:
      ! algebraically the same, but it never subtracts two large displacements, so a bar
      ! that has moved far (or hangs in its static state) keeps all digits of its strains.
      ! s^n moves to s_old (buffers swapped, not copied).
      call move_alloc(st%s_old, swap)
      call move_alloc(st%s, st%s_old)
      call move_alloc(swap, st%s)
      st%s(0) = st%s_old(0)
      st%s(n + 1) = st%s_old(n + 1)
      st%s(1:n) = st%s_old(1:n) + mesh%stiff * (st%dub(0:n-1) - st%dua(1:n))
      ! (2.3)3: u^{n+1} = u^n + du^{n+1}
      st%ua = st%ua + st%dua
      st%ub = st%ub + st%dub
      ! full-mass model: a cut spring pushes only in compression, s = max(0, E/dx (u_{k-1} -
      ! u_k)); its force is not part of the linear invariant, so its work W (the F^n (u^{n+1}
      ! - u^{n-1})/2 product) and its strain measure go to e_contact, keeping the ledger exact
      if (st%n_cut > 0) then
         w_cut = 0.0_wp
         strain_cut = 0.0_wp
         do c = 1, st%n_cut
            k = st%cut(c)
            w_cut = w_cut + st%s_old(k) * 0.5_wp * ((st%dua(k) - st%dub(k - 1)) + du_cut_old(c))
            st%s(k) = max(0.0_wp, mesh%stiff(k) * (st%ub(k - 1) - st%ua(k)))
            strain_cut = strain_cut + 0.5_wp * st%s_old(k) * st%s(k) / mesh%stiff(k)
         end do
         st%e_contact = st%e_contact - w_cut - (strain_cut - st%strain_cut)
         st%strain_cut = strain_cut
      end if
      st%n = st%n + 1
   end subroutine advance
end module spb_step
