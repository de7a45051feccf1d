!> The compact update (2.3) of the half-node model (doc/method.md, "The compact update") for
!> one step, and the section stresses (3.1)-(3.2) (doc/method.md, "Section stresses at every
!> node") it evaluates at every breakable node.
module spb_step
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_load, only: load_t, load_none, step_load, load_integral
   use spb_state, only: state_t
   use spb_ends, only: face_step_t, face_top, face_bottom, face_stress, face_integral, &
      hold_face, book_ends, transmits, has_base, is_striker, strike
   use spb_wave, only: transmit_residuals
   use spb_crack, only: start_cracks, cohesive_step
   use spb_full_mass, only: cut_closing, cut_spring_forces, full_mass_supports
   implicit none
   private
   public :: section_stress_a, section_stress_b, advance, advance_joined, joined_only, &
      end_stresses, face_load_integrals, step_load_integral, hold_end, book_end_nodes

   integer, parameter :: block_default = 2048   !! nodes per block of advance_joined

contains

   !> Stresses acting on the end faces at t^n (spb_ends face_stress): s_top pushes node 0
   !> like a cell above it; s_bot pushes node n like a cell below it.
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
      ! the load is evaluated once for both faces
      p = stepwise_load(mesh, load, m)
      s_top = side_stress(mesh, load, st, face_top, p)
      s_bot = side_stress(mesh, load, st, face_bottom, p)
   end subroutine end_stresses

   !> The stress on one end face at t^step (spb_ends face_stress) [Pa].
   pure real(wp) function end_stress(mesh, load, st, side, step) result(s)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: side          !! face_top | face_bottom
      integer, intent(in) :: step          !! the step index n
      s = side_stress(mesh, load, st, side, stepwise_load(mesh, load, step))
   end function end_stress

   !> The stepwise load P^step (0 without a load) [Pa].
   pure real(wp) function stepwise_load(mesh, load, step) result(p)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      integer, intent(in) :: step          !! the step index n
      p = 0.0_wp
      if (load%kind /= load_none) p = step_load(load, step, mesh%dt)
   end function stepwise_load

   !> The stress on one end face under the stepwise load p (spb_ends face_stress) [Pa].
   pure real(wp) function side_stress(mesh, load, st, side, p) result(s)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: side          !! face_top | face_bottom
      real(wp), intent(in) :: p            !! the stepwise load P^n [Pa]
      if (side == face_top) then
         s = face_stress(st%ends(side), side, p, load%face == side, mesh%stiff(1), st%dub(0), &
                         mesh%dt)
      else
         s = face_stress(st%ends(side), side, p, load%face == side, mesh%stiff(mesh%n), &
                         st%dua(mesh%n), mesh%dt)
      end if
   end function side_stress

   !> Integrals of the load over the step that ends at t^step, on a free top and a free bottom
   !> face [Pa s] (0 where the load acts elsewhere or the face is not free), and of a striking
   !> mass's contact stress on its face: the exact work of the load on the continuum state
   !> is I du / dt (spb_wave).
   pure subroutine face_load_integrals(mesh, load, step, st, i_top, i_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      integer, intent(in) :: step          !! step index: the step ends at t^step
      type(state_t), intent(in) :: st      !! the state (its ends)
      real(wp), intent(out) :: i_top       !! load integral on the top face over the step [Pa s]
      real(wp), intent(out) :: i_bot       !! load integral on the bottom face over the step [Pa s]
      real(wp) :: q
      i_top = 0.0_wp
      i_bot = 0.0_wp
      if (step < 1) return
      q = 0.0_wp
      if (load%kind /= load_none) q = load_integral(load, real(step - 1, wp) * mesh%dt, &
                                                    real(step, wp) * mesh%dt)
      if (load%kind /= load_none .or. is_striker(st%ends(face_top))) then
         i_top = face_integral(st%ends(face_top), q, load%face == face_top, step)
      end if
      if (load%kind /= load_none .or. is_striker(st%ends(face_bottom))) then
         i_bot = face_integral(st%ends(face_bottom), q, load%face == face_bottom, step)
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
      if (.not. (transmits(st%ends(face_top)) .or. transmits(st%ends(face_bottom)))) return
      call face_load_integrals(mesh, load, st%step, st, i_top, i_bot)
      call transmit_residuals(mesh, st, g, i_top, i_bot, rho_top, rho_bot)
      rho_top = -rho_top
      rho_bot = -rho_bot
   end subroutine zigzag_after_step

   !> Integral of the load over the step from t^n to t^{n+1} on the face it acts on (0 on the
   !> other) [Pa s].
   pure real(wp) function step_load_integral(load, n, dt, side) result(q)
      type(load_t), intent(in) :: load     !! the end load
      integer, intent(in) :: n             !! step index: the step from t^n to t^{n+1}
      real(wp), intent(in) :: dt           !! time step [s]
      integer, intent(in) :: side          !! face_top | face_bottom
      q = 0.0_wp
      if (load%kind == load_none .or. load%face /= side) return
      q = load_integral(load, real(n, wp) * dt, real(n + 1, wp) * dt)
   end function step_load_integral

   !> Advance the state from t^n to t^{n+1}.
   pure subroutine advance(mesh, load, g, st)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state
      real(wp), allocatable :: swap(:), du_cut_old(:)
      real(wp) :: old_a(st%n_split), old_b(st%n_split), old_sec(st%n_split)
      real(wp) :: dt, dt2, d
      integer :: split(st%n_split)
      integer :: i, n, c, n_split, n_new
      integer :: new_cracks(mesh%n)
      type(face_step_t) :: r(2)

      n = mesh%n
      dt = mesh%dt
      dt2 = dt * dt
      ! a striking mass's step comes first: its contact integral makes its face's stress
      if (is_striker(st%ends(face_top))) call strike(st%ends(face_top), face_top, st%step, &
         st%ub(0), st%dub(0), st%s(1), mesh%z(1), g, dt)
      if (is_striker(st%ends(face_bottom))) call strike(st%ends(face_bottom), face_bottom, &
         st%step, st%ua(n), st%dua(n), st%s(n), mesh%z(n), g, dt)
      call end_stresses(mesh, load, st, r(face_top)%s, r(face_bottom)%s)
      r(face_top)%q = step_load_integral(load, st%step, mesh%dt, face_top)
      r(face_bottom)%q = step_load_integral(load, st%step, mesh%dt, face_bottom)
      call zigzag_after_step(mesh, load, g, st, r(face_top)%rho, r(face_bottom)%rho)
      st%s(0) = r(face_top)%s
      st%s(n + 1) = r(face_bottom)%s
      r(face_top)%du_old = st%dub(0)
      r(face_bottom)%du_old = st%dua(n)
      ! the full-mass model's cut springs (spb_full_mass): their closing before the step
      if (st%fm%n_cut > 0) du_cut_old = cut_closing(st)

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
      call hold_end(mesh, st, face_top, r(face_top))
      call hold_end(mesh, st, face_bottom, r(face_bottom))
      r(face_top)%s_cell = st%s(1)
      r(face_bottom)%s_cell = st%s(n)
      call book_end_nodes(mesh, g, st, r)

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
      ! the full-mass model's cut springs push only in compression (spb_full_mass)
      if (st%fm%n_cut > 0) call cut_spring_forces(mesh, st, du_cut_old)
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
      call face_load_integrals(mesh, load, st%step, st, i_top, i_bot)
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
   !> base to land on or leave, no striking mass, no support is being hit, and no gauge reads
   !> a node's section stress (mesh%watch: the blocked steps do not keep it).
   pure logical function joined_only(mesh, st)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      joined_only = st%n_split == 0 .and. st%n_breakable == 0 .and. st%fm%n_cut == 0 .and. &
                    .not. any(has_base(st%ends) .or. is_striker(st%ends)) .and. &
                    .not. any(st%ends%landing) .and. mesh%n_watch == 0
   end function joined_only

   !> nsteps steps of a bar that is joined_only, bit-identical to as many calls of advance,
   !> but cache-blocked in space and time: the nodes are cut into blocks of block_nodes, and
   !> each block is taken through all nsteps steps before the next, its range sliding one
   !> node towards the top per step (a node at step t needs only its neighbours at step
   !> t - 1, and the block above has already taken them there). The end nodes' bookkeeping
   !> is recorded per step and booked in step order at the end. s_old is not kept: the
   !> caller ends with an ordinary step (a history row reads s^{n-1}).
   pure subroutine advance_joined(mesh, load, g, st, nsteps, block_nodes, max_sec_bottom, &
                                  face_du)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g                     !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: nsteps                 !! steps to take
      integer, intent(in), optional :: block_nodes  !! nodes per block (default 2048)
      real(wp), intent(out), optional :: max_sec_bottom  !! largest sec(n) of these steps [Pa]
      real(wp), intent(out), optional :: face_du(2, nsteps)   !! increments of the face halves
                                                              !! (B_0, A_n) of each step [m]
      type(face_step_t) :: r(2, nsteps)
      real(wp) :: rho_top, rho_bot
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
         r(face_top, t)%rho = rho_top
         r(face_bottom, t)%rho = rho_bot
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
               r(face_top, t)%s = end_stress(mesh, load, st, face_top, n0 + t - 1)
               r(face_top, t)%q = step_load_integral(load, n0 + t - 1, mesh%dt, face_top)
               st%s(0) = r(face_top, t)%s
               r(face_top, t)%du_old = st%dub(0)
            end if
            if (e == n + 1) then
               r(face_bottom, t)%s = end_stress(mesh, load, st, face_bottom, n0 + t - 1)
               r(face_bottom, t)%q = step_load_integral(load, n0 + t - 1, mesh%dt, face_bottom)
               st%s(n + 1) = r(face_bottom, t)%s
               r(face_bottom, t)%du_old = st%dua(n)
            end if
            call joined_increments(mesh, g, st%s, st%dua, a, e - 1)
            if (a == 0) then
               st%dub(0) = st%dua(0)
               call hold_end(mesh, st, face_top, r(face_top, t))
               r(face_top, t)%s_cell = st%s(1)
            end if
            if (e == n + 1) then
               st%dub(n) = st%dua(n)
               call hold_end(mesh, st, face_bottom, r(face_bottom, t))
               r(face_bottom, t)%s_cell = st%s(n)
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
         call book_end_nodes(mesh, g, st, r(:, t))
         if (present(max_sec_bottom)) max_sec_bottom = max(max_sec_bottom, st%section(n))
         if (present(face_du)) face_du(:, t) = r(:, t)%du
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

   !> A holding support at one end stops its node or moves it by V dt (spb_ends hold_face);
   !> f records what it took and the face half's increment after the step.
   pure subroutine hold_end(mesh, st, side, f)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: side          !! face_top | face_bottom
      type(face_step_t), intent(inout) :: f   !! the step's record of that end
      integer :: k
      k = merge(0, mesh%n, side == face_top)
      call hold_face(st%ends(side), mesh%ma(k), mesh%mb(k), mesh%dt, st%dua(k), st%dub(k), f)
      if (side == face_top) then
         f%du = st%dub(0)
      else
         f%du = st%dua(mesh%n)
      end if
   end subroutine hold_end

   !> The end nodes' part of one step (spb_ends book_ends), with the end cells' numbers; the
   !> full-mass model's supports take the force on their node instead (spb_full_mass).
   pure subroutine book_end_nodes(mesh, g, st, f)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state
      type(face_step_t), intent(in) :: f(2)   !! what the step did at the end nodes
      real(wp) :: section(2)
      integer :: n
      n = mesh%n
      section = [st%section(0), st%section(n)]
      call book_ends(st%ends, f, [mesh%z(1), mesh%z(n)], [mesh%dm(1), mesh%dm(n)], g, mesh%dt, &
                     st%ledger, section)
      if (mesh%full_mass) call full_mass_supports(st%ends, f, [mesh%mb(0), mesh%ma(n)], g, &
                                                  section)
      st%section(0) = section(1)
      st%section(n) = section(2)
   end subroutine book_end_nodes

   include 'spb_section_form_a.inc'
   include 'spb_section_form_b.inc'
end module spb_step
