!> The compact update (2.3) of the half-node model (doc/method.md, "The compact update") for
!> one step, and the section stresses (3.1)-(3.2) (doc/method.md, "Section stresses at every
!> node") it evaluates at every breakable node.
module spb_step
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t, end_free, end_fixed, end_transmit, end_base, end_velocity
   use spb_load, only: load_t, load_none, face_top, step_load, load_integral
   use spb_state, only: state_t
   use spb_wave, only: transmit_residuals
   use spb_crack, only: start_cracks, cohesive_step
   implicit none
   private
   public :: section_stress_a, section_stress_b, advance, advance_joined, joined_only, &
      end_stresses, face_load_integrals

   !> What one step did at the two end nodes: what the end stresses' impulse and work, the
   !> supports' impulse and the support section stresses of that step are booked from.
   type :: end_step_t
      real(wp) :: s_top = 0.0_wp, s_bot = 0.0_wp           !! end stresses of the step [Pa]
      real(wp) :: du_top_old = 0.0_wp, du_bot_old = 0.0_wp !! increments of B_0, A_n before it [m]
      real(wp) :: du_top = 0.0_wp, du_bot = 0.0_wp         !! the same after it [m]
      logical :: held_top = .false., held_bot = .false.    !! a support held the end node
      real(wp) :: p_top = 0.0_wp, p_bot = 0.0_wp           !! ma du_A + mb du_B it stopped,
                                                           !! relative to the support's V dt
                                                           !! (0 at a fixed end) [kg/m]
      real(wp) :: s_1 = 0.0_wp, s_n = 0.0_wp               !! s^n of the end cells [Pa]
      real(wp) :: q_top = 0.0_wp, q_bot = 0.0_wp           !! integral of the load over the
                                                           !! step on that face [Pa s]
      real(wp) :: rho_top = 0.0_wp, rho_bot = 0.0_wp       !! zig-zag content at a transmitting
                                                           !! end after the step (spb_wave) [m]
   end type end_step_t

   integer, parameter :: block_default = 2048   !! nodes per block of advance_joined

contains

   !> Stresses acting on the end faces at t^n: the stepwise load P^n on a loaded free face;
   !> at a transmitting end the static stress it carries, the radiation stress of the
   !> outgoing wave and, when the load acts on that end, 2 P^n for the incident wave of
   !> stress p(t) arriving through it; 0 otherwise. s_top pushes node 0 like a cell above
   !> it; s_bot pushes node n like a cell below it.
   pure subroutine end_stresses(mesh, load, st, s_top, s_bot, step)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(out) :: s_top          !! top face stress, as a cell above node 0 [Pa]
      real(wp), intent(out) :: s_bot          !! bottom face stress, as a cell below node n [Pa]
      integer, intent(in), optional :: step   !! the step index n (default st%step)
      real(wp) :: p
      integer :: m
      m = st%step
      if (present(step)) m = step
      p = 0.0_wp
      if (load%kind /= load_none) p = step_load(load, m, mesh%dt)
      s_top = 0.0_wp
      s_bot = 0.0_wp
      select case (mesh%top)
      case (end_free)
         if (load%face == face_top) s_top = p
      case (end_transmit)
         ! u = F(t - x/a) + G(t + x/a) at Courant 1: the virtual cell above node 0 has
         ! s_0 = -(E/dx) du_0^n (outgoing G) + (E/dx) [F(n+1) - F(n-1)] = 2 P^n (incident F)
         s_top = st%ends%s_static_top - mesh%stiff(1) * (st%dub(0) - st%ends%v_far_top * mesh%dt)
         if (load%face == face_top) s_top = s_top + 2.0_wp * p
      case default
         ! the other ends take no part here
      end select
      select case (mesh%bottom)
      case (end_free)
         if (load%face /= face_top) s_bot = p
      case (end_transmit)
         s_bot = st%ends%s_static_bot + mesh%stiff(mesh%n) * (st%dua(mesh%n) - st%ends%v_far_bot * mesh%dt)
         if (load%face /= face_top) s_bot = s_bot + 2.0_wp * p
      case default
         ! the other ends take no part here
      end select
   end subroutine end_stresses

   !> Integrals of the load over the step that ends at t^step, on a free top and a free bottom
   !> face [Pa s] (0 where the load acts elsewhere or the face is not free): the exact work
   !> of the load on the continuum state is I du / dt (spb_wave).
   pure subroutine face_load_integrals(mesh, load, step, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      integer, intent(in) :: step          !! step index: the step ends at t^step
      real(wp), intent(out) :: i_top       !! load integral on the top face over the step [Pa s]
      real(wp), intent(out) :: i_bot       !! load integral on the bottom face over the step [Pa s]
      real(wp) :: q
      i_top = 0.0_wp
      i_bot = 0.0_wp
      if (load%kind == load_none .or. step < 1) return
      q = load_integral(load, real(step - 1, wp) * mesh%dt, real(step, wp) * mesh%dt)
      if (load%face == face_top) then
         if (mesh%top == end_free) i_top = q
      else
         if (mesh%bottom == end_free) i_bot = q
      end if
   end subroutine face_load_integrals

   !> Under gravity, the zig-zag content rho (spb_wave, transmit_residuals) at each transmitting
   !> end after the step from the state at t^n: the intact step takes rho to -rho (found on
   !> the lattice model, loads included), so it is read once, before the step; 0 otherwise.
   pure subroutine zigzag_after_step(mesh, load, g, st, rho_top, rho_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(in) :: st      !! the state at t^n
      real(wp), intent(out) :: rho_top     !! rho at a transmitting top at t^{n+1} [m]
      real(wp), intent(out) :: rho_bot     !! rho at a transmitting bottom at t^{n+1} [m]
      real(wp) :: i_top, i_bot
      rho_top = 0.0_wp
      rho_bot = 0.0_wp
      if (.not. abs(g) > 0.0_wp) return
      if (.not. (mesh%top == end_transmit .or. mesh%bottom == end_transmit)) return
      call face_load_integrals(mesh, load, st%step, i_top, i_bot)
      call transmit_residuals(mesh, st, g, i_top, i_bot, rho_top, rho_bot)
      rho_top = -rho_top
      rho_bot = -rho_bot
   end subroutine zigzag_after_step

   !> Integral of the load over the step from t^n to t^{n+1} on the face it acts on [Pa s].
   pure subroutine step_load_integrals(load, n, dt, q_top, q_bot)
      type(load_t), intent(in) :: load     !! the end load
      integer, intent(in) :: n             !! step index: the step from t^n to t^{n+1}
      real(wp), intent(in) :: dt           !! time step [s]
      real(wp), intent(out) :: q_top       !! the integral if the top is loaded, else 0 [Pa s]
      real(wp), intent(out) :: q_bot       !! the integral if the bottom is loaded, else 0 [Pa s]
      real(wp) :: q
      q_top = 0.0_wp
      q_bot = 0.0_wp
      if (load%kind == load_none) return
      q = load_integral(load, real(n, wp) * dt, real(n + 1, wp) * dt)
      if (load%face == face_top) then
         q_top = q
      else
         q_bot = q
      end if
   end subroutine step_load_integrals

   !> Advance the state from t^n to t^{n+1}.
   pure subroutine advance(mesh, load, g, st)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state
      real(wp), allocatable :: swap(:), du_cut_old(:)
      real(wp) :: old_a(st%n_split), old_b(st%n_split), old_sec(st%n_split)
      real(wp) :: dt, dt2, d, w_cut, strain_cut
      integer :: split(st%n_split)
      integer :: i, n, c, k, n_split, n_new
      integer :: new_cracks(mesh%n)
      type(end_step_t) :: r

      n = mesh%n
      dt = mesh%dt
      dt2 = dt * dt
      call end_stresses(mesh, load, st, r%s_top, r%s_bot)
      call step_load_integrals(load, st%step, mesh%dt, r%q_top, r%q_bot)
      call zigzag_after_step(mesh, load, g, st, r%rho_top, r%rho_bot)
      st%s(0) = r%s_top
      st%s(n + 1) = r%s_bot
      r%du_top_old = st%dub(0)
      r%du_bot_old = st%dua(n)
      if (st%fm%n_cut > 0) then
         allocate(du_cut_old(st%fm%n_cut))
         do c = 1, st%fm%n_cut
            k = st%fm%cut(c)
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
         old_sec = st%section(split(1:n_split))
      end if
      if (st%n_breakable > 0) then
         ! (3.1)-(3.2): the section stress S^{n+1/2} of a joined interior node, needed where
         ! a node can break (an unbreakable node's is never read); d is the node's increment
         ! of this step as joined_increments takes it
         do i = 1, n - 1
            d = st%dua(i) + ((st%s(i) + mesh%ma(i) * g) + (mesh%mb(i) * g - st%s(i + 1))) &
                * mesh%inv_m(i) * dt2
            st%section(i) = section_stress_a(st%s(i), st%section(i), st%dua(i) / dt, d / dt, &
                                             mesh%z(i), mesh%dm(i), g)
         end do
      else if (mesh%n_watch > 0) then
         ! the same for the nodes gauges read (mesh%watch), breakable or not
         do c = 1, mesh%n_watch
            i = mesh%watch(c)
            d = st%dua(i) + ((st%s(i) + mesh%ma(i) * g) + (mesh%mb(i) * g - st%s(i + 1))) &
                * mesh%inv_m(i) * dt2
            st%section(i) = section_stress_a(st%s(i), st%section(i), st%dua(i) / dt, d / dt, &
                                             mesh%z(i), mesh%dm(i), g)
         end do
      end if
      ! cohesive sections beyond their strength open a crack at t^n, before the step, which
      ! its faces then take under the crack's traction (spb_crack)
      n_new = 0
      if (st%coh%on .and. st%n_breakable > 0) call open_cracks(mesh, load, g, st, new_cracks, n_new)
      call joined_increments(mesh, g, st%s, st%dua, 0, n)
      st%dub = st%dua
      do c = 1, n_split
         i = split(c)
         st%dua(i) = old_a(c) + (st%s(i) + mesh%ma(i) * g) / mesh%ma(i) * dt2
         st%dub(i) = old_b(c) + (mesh%mb(i) * g - st%s(i + 1)) / mesh%mb(i) * dt2
         st%section(i) = old_sec(c)
      end do
      if (st%coh%n_active > 0) call crack_forces(mesh, g, st, split, old_a, old_b, &
                                                 new_cracks(1:n_new))
      call hold_top(mesh, st, r)
      call hold_bottom(mesh, st, r)
      r%s_1 = st%s(1)
      r%s_n = st%s(n)
      call book_ends(mesh, g, st, r)

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
      if (st%fm%n_cut > 0) then
         w_cut = 0.0_wp
         strain_cut = 0.0_wp
         do c = 1, st%fm%n_cut
            k = st%fm%cut(c)
            w_cut = w_cut + st%s_old(k) * 0.5_wp * ((st%dua(k) - st%dub(k - 1)) + du_cut_old(c))
            st%s(k) = max(0.0_wp, mesh%stiff(k) * (st%ub(k - 1) - st%ua(k)))
            strain_cut = strain_cut + 0.5_wp * st%s_old(k) * st%s(k) / mesh%stiff(k)
         end do
         st%ledger%e_contact = st%ledger%e_contact - w_cut - (strain_cut - st%fm%strain_cut)
         st%fm%strain_cut = strain_cut
      end if
      st%step = st%step + 1
   end subroutine advance

   !> The cohesive sections that open a crack at t^n (spb_crack start_cracks, with the load
   !> integrals of the step that ended there); new: those nodes, ascending.
   pure subroutine open_cracks(mesh, load, g, st, new, n_new)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state at t^n, S^{n+1/2} in st%section
      integer, intent(out) :: new(:)       !! the nodes opened (first n_new)
      integer, intent(out) :: n_new        !! how many
      real(wp) :: i_top, i_bot
      call face_load_integrals(mesh, load, st%step, i_top, i_bot)
      call start_cracks(mesh, g, st, i_top, i_bot, new, n_new)
   end subroutine open_cracks

   !> The open cohesive cracks' part of the step (spb_crack cohesive_step): those open before
   !> it, whose halves the step has taken as free faces, and those opened now, whose halves
   !> the step took as one joined node (with the increment du^n of both), taken again as free
   !> faces first.
   pure subroutine crack_forces(mesh, g, st, split, old_a, old_b, new)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state (increments of the step set)
      integer, intent(in) :: split(:)      !! the nodes split before the step
      real(wp), intent(in) :: old_a(:)     !! their upper halves' increments du^n [m]
      real(wp), intent(in) :: old_b(:)     !! their lower halves' increments du^n [m]
      integer, intent(in) :: new(:)        !! the cracks opened at t^n
      real(wp) :: new_old(size(new)), dt2
      integer :: c, i
      dt2 = mesh%dt**2
      do c = 1, size(new)
         i = new(c)
         new_old(c) = st%dua(i) - ((st%s(i) + mesh%ma(i) * g) + (mesh%mb(i) * g - st%s(i + 1))) &
                      * mesh%inv_m(i) * dt2
         st%dua(i) = new_old(c) + (st%s(i) + mesh%ma(i) * g) / mesh%ma(i) * dt2
         st%dub(i) = new_old(c) + (mesh%mb(i) * g - st%s(i + 1)) / mesh%mb(i) * dt2
      end do
      call cohesive_step(mesh, st, split, old_a, old_b)
      if (size(new) > 0) call cohesive_step(mesh, st, new, new_old, new_old)
   end subroutine crack_forces

   !> advance_joined may stand in for nsteps calls of the whole step (advance, contact_step,
   !> fracture_step): every node is joined, none can break (no node, no spring), no rigid
   !> base to land on or leave, no support is being hit, and no gauge reads a node's section
   !> stress (mesh%watch: the blocked steps do not keep it).
   pure logical function joined_only(mesh, st)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      joined_only = st%n_split == 0 .and. st%n_breakable == 0 .and. st%fm%n_cut == 0 .and. &
                    mesh%bottom /= end_base .and. .not. (st%ends%landing_top .or. st%ends%landing_bot) &
                    .and. mesh%n_watch == 0
   end function joined_only

   !> nsteps steps of a bar that is joined_only, bit-identical to as many calls of advance,
   !> but cache-blocked in space and time: the nodes are cut into blocks of block_nodes, and
   !> each block is taken through all nsteps steps before the next, its range sliding one
   !> node towards the top per step (a node at step t needs only its neighbours at step
   !> t - 1, and the block above has already taken them there). The end nodes' bookkeeping
   !> is recorded per step and booked in step order at the end. s_old is not kept: the
   !> caller ends with an ordinary step (a history row reads s^{n-1}).
   pure subroutine advance_joined(mesh, load, g, st, nsteps, block_nodes, max_sec_bottom)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g                     !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: nsteps                 !! steps to take
      integer, intent(in), optional :: block_nodes  !! nodes per block (default 2048)
      real(wp), intent(out), optional :: max_sec_bottom  !! largest sec(n) of these steps [Pa]
      type(end_step_t) :: r(nsteps)
      real(wp) :: unused, rho_top, rho_bot
      integer :: n, n0, bw, nblk, kb, lo, hi, t, a, e, i, k
      logical :: same_u

      n = mesh%n
      n0 = st%step
      ! where both halves of every node sit at the same place to the bit (an intact bar), one
      ! displacement array is advanced and copied: the sums are the same
      same_u = .true.
      do i = 0, n
         if (abs(st%ua(i) - st%ub(i)) > 0.0_wp .or. &
             sign(1.0_wp, st%ua(i)) * sign(1.0_wp, st%ub(i)) < 0.0_wp) then
            same_u = .false.
            exit
         end if
      end do
      ! the zig-zag content at a transmitting end changes sign in every step
      call zigzag_after_step(mesh, load, g, st, rho_top, rho_bot)
      do t = 1, nsteps
         r(t)%rho_top = rho_top
         r(t)%rho_bot = rho_bot
         rho_top = -rho_top
         rho_bot = -rho_bot
      end do
      bw = block_default
      if (present(block_nodes)) bw = block_nodes
      bw = max(bw, nsteps + 2)     ! block 0 holds nodes 0 and 1 at every step
      nblk = n / bw + 1            ! the last block starts at or above node n
      do kb = 0, nblk - 1
         lo = kb * bw
         hi = lo + bw
         if (kb == nblk - 1) hi = n + 1 + nsteps
         do t = 1, nsteps
            a = max(0, lo - t + 1)
            e = min(n + 1, hi - t + 1)
            if (a >= e) cycle
            if (a == 0) then
               call end_stresses(mesh, load, st, r(t)%s_top, unused, step=n0 + t - 1)
               call step_load_integrals(load, n0 + t - 1, mesh%dt, r(t)%q_top, unused)
               st%s(0) = r(t)%s_top
               r(t)%du_top_old = st%dub(0)
            end if
            if (e == n + 1) then
               call end_stresses(mesh, load, st, unused, r(t)%s_bot, step=n0 + t - 1)
               call step_load_integrals(load, n0 + t - 1, mesh%dt, unused, r(t)%q_bot)
               st%s(n + 1) = r(t)%s_bot
               r(t)%du_bot_old = st%dua(n)
            end if
            call joined_increments(mesh, g, st%s, st%dua, a, e - 1)
            if (a == 0) then
               st%dub(0) = st%dua(0)
               call hold_top(mesh, st, r(t))
               r(t)%s_1 = st%s(1)
            end if
            if (e == n + 1) then
               st%dub(n) = st%dua(n)
               call hold_bottom(mesh, st, r(t))
               r(t)%s_n = st%s(n)
            end if
            ! (2.3)4 and (2.3)3 in one pass: cell k lies between nodes k - 1 and k
            if (a == 0) then
               st%ua(0) = st%ua(0) + st%dua(0)
               if (.not. same_u) st%ub(0) = st%ub(0) + st%dua(0)
            end if
            if (same_u) then
               do k = max(a, 1), e - 1
                  st%s(k) = st%s(k) + mesh%stiff(k) * (st%dua(k - 1) - st%dua(k))
                  st%ua(k) = st%ua(k) + st%dua(k)
               end do
            else
               do k = max(a, 1), e - 1
                  st%s(k) = st%s(k) + mesh%stiff(k) * (st%dua(k - 1) - st%dua(k))
                  st%ua(k) = st%ua(k) + st%dua(k)
                  st%ub(k) = st%ub(k) + st%dua(k)
               end do
            end if
         end do
      end do
      st%dub = st%dua
      if (same_u) st%ub = st%ua
      if (present(max_sec_bottom)) max_sec_bottom = -huge(1.0_wp)
      do t = 1, nsteps
         call book_ends(mesh, g, st, r(t))
         if (present(max_sec_bottom)) max_sec_bottom = max(max_sec_bottom, st%section(n))
      end do
      st%step = n0 + nsteps
      st%n_skip = 0
   end subroutine advance_joined

   !> (2.3)1-2 for joined nodes i0..i1: du += (forces of both halves) / (their mass) dt^2.
   pure subroutine joined_increments(mesh, g, s, du, i0, i1)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: s(0:)       !! cell stresses s^n, ends included [Pa]
      real(wp), intent(inout) :: du(0:)   !! increments [m]
      integer, intent(in) :: i0           !! first node to update
      integer, intent(in) :: i1           !! last node to update
      real(wp) :: dt2
      integer :: i
      dt2 = mesh%dt * mesh%dt
      if (abs(g) > 0.0_wp) then
         do i = i0, i1
            du(i) = du(i) + ((s(i) + mesh%ma(i) * g) + (mesh%mb(i) * g - s(i + 1))) &
                    * mesh%inv_m(i) * dt2
         end do
      else
         ! the same expression with g = 0 (x + 0 = x): two fewer arrays streamed
         do i = i0, i1
            du(i) = du(i) + (s(i) - s(i + 1)) * mesh%inv_m(i) * dt2
         end do
      end if
   end subroutine joined_increments

   !> A fixed top stops node 0, a constant-velocity top moves it by V dt; the momentum the
   !> support takes (what the node would have had beyond m V) is recorded.
   pure subroutine hold_top(mesh, st, r)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(end_step_t), intent(inout) :: r   !! the step's end-node record (top part set)
      real(wp) :: du
      r%held_top = mesh%top == end_fixed .or. mesh%top == end_velocity
      if (r%held_top) then
         du = 0.0_wp
         if (mesh%top == end_velocity) du = st%ends%v_end_top * mesh%dt
         r%p_top = mesh%ma(0) * (st%dua(0) - du) + mesh%mb(0) * (st%dub(0) - du)
         st%dua(0) = du
         st%dub(0) = du
      end if
      r%du_top = st%dub(0)
   end subroutine hold_top

   !> A fixed bottom, or the base the bar rests on, stops node n; a constant-velocity bottom
   !> moves it by V dt.
   pure subroutine hold_bottom(mesh, st, r)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      type(end_step_t), intent(inout) :: r   !! the step's end-node record (bottom part set)
      integer :: n
      real(wp) :: du
      n = mesh%n
      r%held_bot = mesh%bottom == end_fixed .or. mesh%bottom == end_velocity .or. &
                   (mesh%bottom == end_base .and. st%ends%base_contact)
      if (r%held_bot) then
         du = 0.0_wp
         if (mesh%bottom == end_velocity) du = st%ends%v_end_bot * mesh%dt
         r%p_bot = mesh%ma(n) * (st%dua(n) - du) + mesh%mb(n) * (st%dub(n) - du)
         st%dua(n) = du
         st%dub(n) = du
      end if
      r%du_bot = st%dua(n)
   end subroutine hold_bottom

   !> The end nodes' part of one step, in the order the step makes it: impulse of the end
   !> stresses and of the supports, work of the end stresses, section stresses at the supports.
   pure subroutine book_ends(mesh, g, st, r)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state
      type(end_step_t), intent(in) :: r    !! what the step did at the end nodes
      real(wp) :: dt, du_top_old, du_bot_old
      integer :: n
      n = mesh%n
      dt = mesh%dt
      ! momentum balance: the end stresses act on the end nodes, supports take what reaches
      ! them
      st%ledger%i_ends = st%ledger%i_ends + (r%s_top - r%s_bot) * dt
      if (r%held_top) st%ledger%i_support = st%ledger%i_support - r%p_top / dt
      if (r%held_bot) st%ledger%i_support = st%ledger%i_support - r%p_bot / dt
      ! work of the end stresses over the step: F^n (u^{n+1} - u^{n-1}) / 2, which keeps
      ! the discrete energy ledger exact
      associate (w_top => r%s_top * 0.5_wp * (r%du_top + r%du_top_old), &
                 w_bot => -r%s_bot * 0.5_wp * (r%du_bot + r%du_bot_old))
         if (mesh%top == end_transmit) then
            st%ledger%w_transmit = st%ledger%w_transmit + w_top
         else
            st%ledger%w_load = st%ledger%w_load + w_top
         end if
         if (mesh%bottom == end_transmit) then
            st%ledger%w_transmit = st%ledger%w_transmit + w_bot
         else
            st%ledger%w_load = st%ledger%w_load + w_bot
         end if
      end associate
      ! a constant-velocity end's support force -p/dt^2 does the same product (its node moves
      ! by V dt in both steps); in the continuum reading its work over the step is V times
      ! the impulse the continuum's end section takes, -p/dt + Z (f^{n+1} - f^n) (f the
      ! interval the support sends into the bar): the first part is booked here, the second
      ! is a function of the reading at t^{n+1} (spb_wave, wave_t%w_support; doc/method.md)
      if (mesh%top == end_velocity) then
         st%ledger%w_support = st%ledger%w_support - r%p_top / dt**2 * 0.5_wp * &
                               (r%du_top + r%du_top_old)
         st%ledger%w_wave = st%ledger%w_wave - st%ends%v_end_top * r%p_top / dt
      end if
      if (mesh%bottom == end_velocity) then
         st%ledger%w_support = st%ledger%w_support - r%p_bot / dt**2 * 0.5_wp * &
                               (r%du_bot + r%du_bot_old)
         st%ledger%w_wave = st%ledger%w_wave - st%ends%v_end_bot * r%p_bot / dt
      end if

      ! the same work on the continuum state (spb_wave): I du / dt at a free loaded face; at a
      ! transmitting end the energy the incoming wave (the static stress carried and the
      ! incident load) brings minus what the outgoing one takes, Z du (2 w - du) / dt, w the
      ! incoming interval: w_in, plus under gravity the fragment's zig-zag content rho
      select case (mesh%top)
      case (end_free)
         st%ledger%w_wave = st%ledger%w_wave + r%q_top * r%du_top / dt
      case (end_transmit)
         st%ends%w_in_top = (0.5_wp * st%ends%s_static_top * dt + r%q_top) / mesh%z(1) + &
                       0.5_wp * st%ends%v_far_top * dt
         st%ledger%w_wave = st%ledger%w_wave + mesh%z(1) * r%du_top * &
                            (2.0_wp * (st%ends%w_in_top + r%rho_top) - r%du_top) / dt
      case default
         ! the other ends take no part here
      end select
      select case (mesh%bottom)
      case (end_free)
         st%ledger%w_wave = st%ledger%w_wave - r%q_bot * r%du_bot / dt
      case (end_transmit)
         st%ends%w_in_bot = -(0.5_wp * st%ends%s_static_bot * dt + r%q_bot) / mesh%z(n) + &
                       0.5_wp * st%ends%v_far_bot * dt
         st%ledger%w_wave = st%ledger%w_wave + mesh%z(n) * r%du_bot * &
                            (2.0_wp * (st%ends%w_in_bot + r%rho_bot) - r%du_bot) / dt
      case default
         ! the other ends take no part here
      end select

      ! section stresses at the supports, (3.1)-(3.2) with s^n and v^n, v^{n+1}
      ! a support just hit by a moving half starts from that half's velocity
      du_top_old = r%du_top_old
      du_bot_old = r%du_bot_old
      if (st%ends%landing_top) du_top_old = st%ends%v_land_top * dt
      if (st%ends%landing_bot) du_bot_old = st%ends%v_land_bot * dt
      st%ends%landing_top = .false.
      st%ends%landing_bot = .false.
      select case (mesh%top)
      case (end_fixed)
         st%section(0) = section_stress_b(r%s_1, st%section(0), du_top_old / dt, 0.0_wp, mesh%z(1), &
                                       mesh%dm(1), g)
      case (end_transmit, end_velocity)
         st%section(0) = section_stress_b(r%s_1, st%section(0), du_top_old / dt, r%du_top / dt, &
                                       mesh%z(1), mesh%dm(1), g)
      case default
         ! the other ends take no part here
      end select
      select case (mesh%bottom)
      case (end_fixed)
         st%section(n) = section_stress_a(r%s_n, st%section(n), du_bot_old / dt, 0.0_wp, mesh%z(n), &
                                       mesh%dm(n), g)
      case (end_transmit, end_velocity)
         st%section(n) = section_stress_a(r%s_n, st%section(n), du_bot_old / dt, r%du_bot / dt, &
                                       mesh%z(n), mesh%dm(n), g)
      case (end_base)
         ! resting on the rigid base: the base side does not move; v^n is the bottom half's
         ! velocity before the step (0 while it rests)
         if (st%ends%base_contact .and. mesh%full_mass) then
            ! full-mass model: no section stresses; the base takes the force on the node
            st%section(n) = r%s_n + mesh%ma(n) * g
         else if (st%ends%base_contact) then
            st%section(n) = section_stress_a(r%s_n, st%section(n), du_bot_old / dt, 0.0_wp, &
                                          mesh%z(n), mesh%dm(n), g)
         else
            st%section(n) = 0.0_wp
         end if
      case default
         ! the other ends take no part here
      end select
   end subroutine book_ends

   !> (3.1)1 and (3.2)1: from the cell above (stress s_above, impedance z_above, mass dm_above).
   pure elemental real(wp) function section_stress_a(s_above, s_prev, v_n, v_np1, z_above, &
                                                     dm_above, g) result(s_new)
      real(wp), intent(in) :: s_above    !! stress of the cell above at t^n [Pa]
      real(wp), intent(in) :: s_prev     !! section stress S^{n-1/2} [Pa]
      real(wp), intent(in) :: v_n        !! node velocity v^n (mean over the step ending at t^n) [m/s]
      real(wp), intent(in) :: v_np1      !! node velocity v^{n+1} [m/s]
      real(wp), intent(in) :: z_above    !! impedance of the cell above [kg/(m^2 s)]
      real(wp), intent(in) :: dm_above   !! mass of the cell above [kg/m^2]
      real(wp), intent(in) :: g          !! gravity along +x [m/s^2]
      real(wp) :: v_a
      v_a = v_n + (s_above - s_prev + 0.5_wp * dm_above * g) / z_above        ! (3.1)1
      s_new = s_above + z_above * (v_a - v_np1) + 0.5_wp * dm_above * g       ! (3.2)1
   end function section_stress_a

   !> (3.1)2 and (3.2)2: from the cell below.
   pure elemental real(wp) function section_stress_b(s_below, s_prev, v_n, v_np1, z_below, &
                                                     dm_below, g) result(s_new)
      real(wp), intent(in) :: s_below    !! stress of the cell below at t^n [Pa]
      real(wp), intent(in) :: s_prev     !! section stress S^{n-1/2} [Pa]
      real(wp), intent(in) :: v_n        !! node velocity v^n [m/s]
      real(wp), intent(in) :: v_np1      !! node velocity v^{n+1} [m/s]
      real(wp), intent(in) :: z_below    !! impedance of the cell below [kg/(m^2 s)]
      real(wp), intent(in) :: dm_below   !! mass of the cell below [kg/m^2]
      real(wp), intent(in) :: g          !! gravity along +x [m/s^2]
      real(wp) :: v_b
      v_b = v_n + (s_prev - s_below + 0.5_wp * dm_below * g) / z_below        ! (3.1)2
      s_new = s_below - z_below * (v_b - v_np1) - 0.5_wp * dm_below * g       ! (3.2)2
   end function section_stress_b
end module spb_step
