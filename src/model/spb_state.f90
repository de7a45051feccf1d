!> The evolving state of the half-node model and its initialisation.
!>
!> Every node i = 0..n has an upper half A_i (cell i above) and a lower half B_i (cell
!> i+1 below). A joined node moves as one mass; a split node's halves move apart. Node
!> arrays hold u and the last increment du = u^n - u^{n-1}; v^n = du/dt is the mean
!> velocity over the step that ends at t^n.
module spb_state
   use spb_kinds, only: wp
   use spb_problem, only: problem_t
   use spb_mesh, only: mesh_t
   use spb_ledger, only: ledger_t
   use spb_ends, only: end_t, face_top, face_bottom, start_end, has_free_face, is_fixed_end, &
      define_ends, has_base, moves_with_bar, place_on_base, is_striker
   use spb_static, only: static_state
   use spb_random, only: rng_t, rng_seed, rng_uniform, weibull
   use spb_columns, only: column_set_t, add_column
   implicit none
   private
   public :: state_t, damage_t, init_state, fragment_count, open_node, close_node, cell_strengths, &
      separates
   public :: state_columns_t, register_state_columns, post_state_columns

   !> The fragments' genealogy, kept per node (memory does not grow with the events).
   type :: genealogy_t
      integer, allocatable :: frag_id(:)      !! (0:n) id of the fragment whose top node is i,
                                              !! 0 at joined interior nodes
      integer, allocatable :: frag_parent(:)  !! (0:n) parent id of the fragment whose top node
                                              !! is i (0: none)
      integer, allocatable :: frag_birth(:)   !! (0:n) step at which that fragment was born
      integer :: n_frag_ids = 0               !! fragment ids issued
   end type genealogy_t

   !> The full-mass (naive) model's cut springs (spb_full_mass): springs break instead of
   !> nodes; a cut spring carries compression only.
   type :: full_mass_t
      integer, allocatable :: cut(:)          !! indices of cut cells, first n_cut used
      logical, allocatable :: is_cut(:)       !! (1:n)
      integer :: n_cut = 0                    !! cut cells
      real(wp) :: strain_cut = 0.0_wp         !! strain energy measure of cut cells [J/m^2]
   end type full_mass_t

   !> Cohesive cracks (spb_cohesive; doc/method.md, "Cohesive cracks"): per node, allocated
   !> only where some segment has a fracture energy (on).
   type :: cohesive_t
      logical :: on = .false.                 !! some section has Gc > 0 (the arrays exist)
      real(wp), allocatable :: gc(:)          !! (0:n) fracture energy of the section; 0 once
                                              !! a crack there has opened fully [J/m^2]
      real(wp), allocatable :: r(:)           !! (0:n) traction of the crack at zero opening
                                              !! (the section's strength when it started) [Pa]
      real(wp), allocatable :: dc(:)          !! (0:n) critical opening 2 Gc / r [m]
      real(wp), allocatable :: dmax(:)        !! (0:n) largest opening so far [m]
      real(wp), allocatable :: opening(:)     !! (0:n) the crack's opening, kept by its faces'
                                              !! increments: ub - ua less what rigid shifts of
                                              !! one side added (a shift is no opening), not
                                              !! taken from ub - ua, whose round-off is that
                                              !! of the positions (of the frame) [m]
      real(wp), allocatable :: q(:)           !! (0:n) integral of the traction over the last
                                              !! step, I^n (tension > 0) [Pa s]
      logical, allocatable :: active(:)       !! (0:n) a split node whose faces carry traction
      integer :: n_active = 0                 !! such nodes
      real(wp) :: eps_rel = 1.0e-9_wp         !! round-off guard of the opening test (as
                                              !! fracture's) [-]
      integer, allocatable :: pending(:)      !! cracks the step opened, for their events
      real(wp), allocatable :: pending_stress(:)  !! their section stresses S^{n+1/2} [Pa]
      integer :: n_pending = 0                !! such cracks
   end type cohesive_t

   !> Time-dependent fracture (Tuler-Butcher; doc/method.md, "Time-dependent fracture"): per
   !> node, allocated only where some segment has a damage integral K > 0 (on). A section
   !> whose K > 0 breaks when D = integral of (S - R)^lambda dt over the time its tension S
   !> exceeds its strength R reaches K; the state keeps D/K.
   type :: damage_t
      logical :: on = .false.                 !! some section has K > 0 (the arrays exist)
      real(wp), allocatable :: k(:)           !! (0:n) damage integral K of the section
                                              !! [Pa^lambda s]; 0: breaks at once (brittle)
      real(wp), allocatable :: lambda(:)      !! (0:n) its exponent lambda [-]
      real(wp), allocatable :: d(:)           !! (0:n) damage so far, D/K [-]; the section
                                              !! breaks in the step that takes it to 1
   end type damage_t

   type :: state_t
      integer :: step = 0                     !! step index n: the state is at t^n = n dt
      real(wp), allocatable :: ua(:), ub(:)   !! displacements of the halves (0:n) [m]
      real(wp), allocatable :: dua(:), dub(:) !! last increments (0:n) [m]
      real(wp), allocatable :: s(:)           !! cell stresses s^n (0:n+1); 0 and n+1 hold the
                                              !! end stresses (load, transmitting end) [Pa]
      real(wp), allocatable :: s_old(:)       !! s^{n-1}, same layout [Pa]
      logical, allocatable :: joined(:)       !! node halves move together (0:n)
      real(wp), allocatable :: section(:)     !! section stress S^{n-1/2} at each node (0:n); at
                                              !! nodes 0 and n the support's [Pa]; 0 when split
      real(wp), allocatable :: strength(:)    !! tensile strength R_i of each node's section
                                              !! (0:n) [Pa]; < 0 unbreakable, 0 once broken
      real(wp), allocatable :: cell_strength(:) !! (1:n) [Pa]; < 0 unbreakable, 0 once cut
      integer :: n_breakable = 0              !! joined interior nodes with strength >= 0
      integer :: n_split = 0                  !! split interior nodes (not joined)
      integer, allocatable :: split(:)        !! those nodes in ascending order, first n_split
                                              !! used; kept by open_node and close_node
      real(wp) :: s_scale = 0.0_wp            !! largest stress magnitude so far [Pa]
      logical, allocatable :: cracked(:)      !! (0:n) the section has been open once (a crack
                                              !! or a dry contact): re-openings are separations
      integer, allocatable :: skip_test(:)    !! nodes joined at t^{n+1} this step (delay rule):
      integer :: n_skip = 0                   !! their section stress starts next step
      type(ledger_t) :: ledger                !! work, event energies, impulses
      type(end_t) :: ends(2)                  !! the top and the bottom end (face_top,
                                              !! face_bottom): spb_ends
      real(wp) :: u_credit = 0.0_wp           !! the landing credit of a bar held at both ends
                                              !! with an odd cell count, as a position: its
                                              !! gravity term is lower by g dt u_credit/(2C)
                                              !! (spb_wave, held_weights); 0 otherwise [m]
      type(genealogy_t) :: gen                !! the fragments' ids and parents
      type(full_mass_t) :: fm                 !! the full-mass model's cut springs
      type(cohesive_t) :: coh                 !! cohesive cracks
      type(damage_t) :: dmg                   !! time-dependent fracture (Tuler-Butcher)
      integer :: ring_next = 0                !! the characteristic steps (spb_ring) are not
                                              !! tried before this step: the last try stopped
                                              !! early (its state, that a restart repeats it)
      integer :: ring_wait = 0                !! steps waited after that try (doubles while
                                              !! tries stop early, 0 after one that did not;
                                              !! 10: one stopped early by events, no wait)
   end type state_t

   !> The state's history columns (PREFIX.his, /history): their ids (spb_columns).
   type :: state_columns_t
      integer :: t = 0, step = 0, reaction_bottom = 0, reaction_top = 0, fragments = 0
   end type state_columns_t

contains

   !> Initial state (2.4): unstressed or in self-weight equilibrium, plus segment velocities.
   subroutine init_state(prob, mesh, st)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(out) :: st     !! the state
      integer :: n, i
      real(wp) :: g, dt, u(0:mesh%n), s(1:mesh%n), v(0:mesh%n), s_top, s_bot
      logical :: split(0:mesh%n), dry(0:mesh%n), supported(0:mesh%n)

      n = mesh%n
      g = prob%gravity
      dt = mesh%dt
      allocate(st%ua(0:n), st%ub(0:n), st%dua(0:n), st%dub(0:n))
      allocate(st%s(0:n+1), st%s_old(0:n+1), st%joined(0:n), st%section(0:n), st%strength(0:n))
      st%joined = .true.
      allocate(st%cracked(0:n))
      allocate(st%skip_test(8), source=0)
      st%cracked = .false.
      ! the cells' strengths (a Weibull field is drawn once), then the nodes'
      allocate(st%cell_strength(n), st%fm%is_cut(n))
      st%cell_strength = cell_strengths(prob, mesh)
      call init_strength(mesh, st)
      call init_cohesive(prob, mesh, st)
      call init_damage(prob, mesh, st)
      allocate(st%fm%cut(16), source=0)
      st%fm%is_cut = .false.
      allocate(st%gen%frag_id(0:n), st%gen%frag_parent(0:n), st%gen%frag_birth(0:n))
      st%gen%frag_parent = 0
      st%gen%frag_birth = 0
      st%gen%frag_id = 0
      st%gen%frag_id(0) = 1
      st%gen%n_frag_ids = 1
      call define_ends(st%ends, mesh)
      v = initial_velocities(prob, mesh, st%ends)
      call dry_starts(prob, mesh, split, dry)
      s_top = 0.0_wp
      s_bot = 0.0_wp
      supported = .false.
      if (prob%static_start) then
         ! the base carries weight only where the bar starts resting on it (in contact); a
         ! face moving at t = 0 is not touched by it (issue 17); a dry interface only where
         ! it starts closed and pressed, so each body is in the equilibrium of its own
         ! supports, one without any in free fall (issue 34)
         call static_state(mesh, st%ends, g, [prob%base_gap_top <= 0.0_wp .and. &
                           .not. (abs(v(0) * dt) > 0.0_wp), prob%base_gap <= 0.0_wp .and. &
                           .not. (abs(v(n) * dt) > 0.0_wp)], dry, prob%strain_rate > 0.0_wp, &
                           split, u, s, s_top, s_bot, supported)
      else
         u = 0.0_wp
         s = 0.0_wp
      end if
      call start_end(st%ends(face_top), face_top, v(0), s_top, mesh%z(1), dt)
      call start_end(st%ends(face_bottom), face_bottom, v(n), s_bot, mesh%z(n), dt)
      ! a striking mass starts at its gap with its velocity
      where (is_striker(st%ends))
         st%ends%striker%v = mesh%impactor_velocity
         st%ends%striker%gap = st%ends%gap0
      end where
      st%ua = u
      st%ub = u
      st%dua = v * dt
      st%dub = v * dt
      call open_dry(prob, mesh, split, st)
      st%n_breakable = count(st%strength(1:n-1) >= 0.0_wp .and. st%joined(1:n-1))
      ! defined beyond n_split too: a checkpoint writes (and counts in its checksum) the whole list
      allocate(st%split(max(1, n - 1)), source=0)
      st%n_split = 0
      do i = 1, n - 1
         if (st%joined(i)) cycle
         st%n_split = st%n_split + 1
         st%split(st%n_split) = i
      end do
      if (has_base(st%ends(face_bottom))) call place_on_base(st%ends(face_bottom), face_bottom, &
                                                            st%ua(n), prob%base_gap, st%dua(n))
      if (has_base(st%ends(face_top))) call place_on_base(st%ends(face_top), face_top, st%ub(0), &
                                                         prob%base_gap_top, st%dub(0))
      ! a face that gravity pulls away from the base it touches at rest is not pressed onto it:
      ! it starts out of contact and leaves with no event (a static start is refused there)
      if (g < 0.0_wp .and. has_base(st%ends(face_bottom))) st%ends(face_bottom)%contact = .false.
      if (g > 0.0_wp .and. has_base(st%ends(face_top))) st%ends(face_top)%contact = .false.
      st%s = 0.0_wp
      st%s(1:n) = s
      ! s^{-1} = s^0 - E (du_{k-1} - du_k)/dx, for the strain-energy product at the first row
      st%s_old = 0.0_wp
      st%s_old(1:n) = st%s(1:n) - mesh%stiff * (st%dub(0:n-1) - st%dua(1:n))
      call init_sections(prob, mesh, s, supported, st)
      st%s_scale = maxval(abs(s))
   end subroutine init_state

   !> How the dry interfaces start: open (split) where a gap parts their sides, the sides
   !> move differently (they touch at most: the contact starts at t = 0) or, in an unstressed
   !> start, a strain rate > 0 stretches the bar (it pulls every contact); else closed (dry),
   !> and a static start may still open those its static state pulls (spb_static).
   pure subroutine dry_starts(prob, mesh, split, dry)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      logical, intent(out) :: split(0:mesh%n)  !! (0:n) the node starts open
      logical, intent(out) :: dry(0:mesh%n)    !! (0:n) a dry interface that starts closed
      integer :: i, j
      split = .false.
      dry = .false.
      do j = 1, mesh%nseg - 1
         if (.not. prob%dry(j)) cycle
         i = mesh%last(j)
         split(i) = prob%gap(j) > 0.0_wp .or. abs(prob%velocity(j) - prob%velocity(j + 1)) > 0.0_wp
         if (.not. prob%static_start) split(i) = split(i) .or. prob%strain_rate > 0.0_wp
         dry(i) = .not. split(i)
      end do
   end subroutine dry_starts

   !> The dry interfaces in the state: no strength; those that start open (split) with their
   !> halves' own velocities and the lower side moved down by the gap (O(n) per gapped
   !> interface only). With a strain rate each face moves with the mean velocity of its
   !> cell, as a free end face does (initial_velocities): no zig-zag Jordan component in
   !> either piece.
   pure subroutine open_dry(prob, mesh, split, st)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      logical, intent(in) :: split(0:mesh%n)   !! (0:n) the node starts open
      type(state_t), intent(inout) :: st   !! the state
      real(wp) :: va, vb, gap, xc, dt
      integer :: i, j, n
      n = mesh%n
      dt = mesh%dt
      xc = mass_centre(mesh)
      do j = 1, mesh%nseg - 1
         i = mesh%last(j)
         if (.not. prob%dry(j)) cycle
         st%cracked(i) = .true.
         st%strength(i) = 0.0_wp
         if (st%coh%on) st%coh%gc(i) = 0.0_wp
         if (st%dmg%on) st%dmg%k(i) = 0.0_wp
         if (.not. split(i)) cycle
         va = prob%velocity(j)
         vb = prob%velocity(j + 1)
         st%joined(i) = .false.
         if (abs(prob%strain_rate) > 0.0_wp) then
            va = va + prob%strain_rate * (mesh%x(i) - 0.5_wp * mesh%dx(i) - xc)
            vb = vb + prob%strain_rate * (mesh%x(i) + 0.5_wp * mesh%dx(i + 1) - xc)
         end if
         st%dua(i) = va * dt
         st%dub(i) = vb * dt
         gap = prob%gap(j)
         if (gap > 0.0_wp) then
            st%ub(i) = st%ub(i) + gap
            st%ua(i+1:n) = st%ua(i+1:n) + gap
            st%ub(i+1:n) = st%ub(i+1:n) + gap
         end if
      end do
   end subroutine open_dry

   !> Node velocities at t = 0: the segment's, at an interface the momentum-weighted mean;
   !> with a strain rate the uniform stretching about the centre of mass; held ends at rest.
   pure function initial_velocities(prob, mesh, ends) result(v)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(end_t), intent(in) :: ends(2)   !! the ends (their kinds)
      real(wp) :: v(0:mesh%n)                  !! [m/s]
      integer :: i, j, k, n
      real(wp) :: va, vb, xc
      n = mesh%n
      do j = 1, mesh%nseg
         do k = mesh%first(j), mesh%last(j)
            v(k) = prob%velocity(j)
         end do
      end do
      v(0) = prob%velocity(1)
      do j = 1, mesh%nseg - 1
         i = mesh%last(j)
         va = prob%velocity(j)
         vb = prob%velocity(j + 1)
         v(i) = (mesh%ma(i) * va + mesh%mb(i) * vb) * mesh%inv_m(i)
      end do
      if (abs(prob%strain_rate) > 0.0_wp) then
         ! uniform stretching about the centre of mass (free, transmitting or constant-velocity
         ! ends; a constant-velocity end node takes its own v(x) exactly, so that with two of
         ! them every cell stretches alike, s = -E strain_rate t, whatever the centre)
         associate (m => mesh%ma + mesh%mb)
            xc = mass_centre(mesh)
            v = v + prob%strain_rate * (mesh%x - xc)
            ! a node between cells that differ (materials, areas) moves with the mass-weighted
            ! mean of its two cells' centre velocities: the lattice state of v(x) with no
            ! zig-zag Jordan component (between equal cells that is v(x_i) itself; issue 34)
            do i = 1, n - 1
               if (.not. (abs(mesh%dm(i) - mesh%dm(i + 1)) > 0.0_wp .or. &
                          abs(mesh%dx(i) - mesh%dx(i + 1)) > 0.0_wp)) cycle
               v(i) = v(i) + prob%strain_rate * 0.5_wp * (mesh%mb(i) * mesh%dx(i + 1) - &
                                                          mesh%ma(i) * mesh%dx(i)) * mesh%inv_m(i)
            end do
            ! a free face moves in the first step with the mean velocity of its cell: that is
            ! the lattice state of the continuum field v(x) with no zig-zag Jordan component
            ! (spb_wave); the face's own v(x) would start one that grows linearly
            if (has_free_face(ends(face_top)) .or. has_base(ends(face_top))) then
               v(0) = v(0) + prob%strain_rate * 0.5_wp * mesh%dx(1)
            end if
            if (has_free_face(ends(face_bottom)) .or. has_base(ends(face_bottom))) then
               v(n) = v(n) - prob%strain_rate * 0.5_wp * mesh%dx(n)
            end if
         end associate
      end if
      if (is_fixed_end(ends(face_top))) v(0) = 0.0_wp
      if (is_fixed_end(ends(face_bottom))) v(n) = 0.0_wp
   end function initial_velocities

   !> The bar's centre of mass in the reference configuration [m].
   pure real(wp) function mass_centre(mesh)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      associate (m => mesh%ma + mesh%mb)
         mass_centre = sum(m * mesh%x) / sum(m)
      end associate
   end function mass_centre

   !> Section stresses S^{-1/2} of the initial state, from its cell stresses s.
   pure subroutine init_sections(prob, mesh, s, supported, st)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: s(:)             !! cell stresses at t = 0, cells 1..n [Pa]
      logical, intent(in) :: supported(0:)     !! (0:n) in a static start, the node's body has
                                               !! a support (spb_static)
      type(state_t), intent(inout) :: st   !! the state
      integer :: i, n
      real(wp) :: g
      n = mesh%n
      g = prob%gravity
      ! Section stresses S^{-1/2}. A bar in self-weight equilibrium starts at the fixed point
      ! of (3.1)-(3.2), S = s_above + dm_above g / 2 (= s_below - dm_below g / 2). An
      ! 'unstressed' bar had no stress before t = 0: S = s (a free-falling bar then keeps
      ! S = 0 exactly). A support that a moving bar presses on at t = 0 is a collision at t^0:
      ! (3.1) starts from the bar half's own velocity with S^{-1/2} = 0; since the support
      ! half's increment is 0, that is the value that makes the step's (3.1) do so.
      st%section = 0.0_wp
      if (prob%static_start) then
         ! a body without a support is in free fall: S = s, as unstressed
         do i = 1, n - 1
            if (supported(i)) then
               st%section(i) = s(i) + 0.5_wp * mesh%dm(i) * g
            else
               st%section(i) = s(i)
            end if
         end do
         if (.not. has_free_face(st%ends(face_top))) then
            st%section(0) = s(1) - 0.5_wp * mesh%dm(1) * g
         end if
         if (.not. has_free_face(st%ends(face_bottom))) then
            st%section(n) = s(n) + 0.5_wp * mesh%dm(n) * g
         end if
      else
         do i = 1, n - 1
            st%section(i) = s(i)
         end do
         ! a bar moving against a fixed end at t = 0 collides with it at t^0
         if (is_fixed_end(st%ends(face_top))) then
            st%ends(face_top)%landing = .true.
            st%ends(face_top)%v_land = prob%velocity(1)
         end if
         if (is_fixed_end(st%ends(face_bottom))) then
            st%ends(face_bottom)%landing = .true.
            st%ends(face_bottom)%v_land = prob%velocity(mesh%nseg)
         end if
         ! a transmitting or a constant-velocity end moves with the bar next to it: no collision
         if (moves_with_bar(st%ends(face_top))) st%section(0) = s(1)
         if (moves_with_bar(st%ends(face_bottom))) st%section(n) = s(n)
      end if
      if (has_base(st%ends(face_bottom)) .and. .not. st%ends(face_bottom)%contact) then
         st%section(n) = 0.0_wp
      end if
      if (has_base(st%ends(face_top)) .and. .not. st%ends(face_top)%contact) st%section(0) = 0.0_wp
      do i = 1, n - 1
         if (.not. st%joined(i)) st%section(i) = 0.0_wp
      end do
   end subroutine init_sections

   !> Node strengths: the weaker of the two cells' strengths at each interior node (a
   !> segment's strength inside it, the weaker one at a bonded interface, seed section 2);
   !> one cell breakable: its strength; ends never break.
   subroutine init_strength(mesh, st)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state
      integer :: i
      real(wp) :: ra, rb
      st%strength = -1.0_wp
      do i = 1, mesh%n - 1
         ra = st%cell_strength(i)
         rb = st%cell_strength(i + 1)
         if (ra >= 0.0_wp .and. rb >= 0.0_wp) then
            st%strength(i) = min(ra, rb)
         else if (ra >= 0.0_wp) then
            st%strength(i) = ra
         else if (rb >= 0.0_wp) then
            st%strength(i) = rb
         end if
      end do
      st%n_breakable = count(st%strength(1:mesh%n-1) >= 0.0_wp)
   end subroutine init_strength

   !> The sections' fracture energies: each node takes the Gc of the cell whose strength it
   !> took (the weaker side of a bonded interface, the smaller Gc where both sides are as
   !> strong; with a strength field, its cell's segment).
   !> Only where some segment has Gc > 0; a dry interface stays brittle (it has no bond).
   subroutine init_cohesive(prob, mesh, st)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state (strengths set)
      integer :: i, n, k
      real(wp) :: ra, rb
      n = mesh%n
      st%coh%on = .false.
      if (.not. allocated(prob%fracture_energy)) return
      if (.not. any(prob%fracture_energy > 0.0_wp)) return
      st%coh%on = .true.
      allocate(st%coh%gc(0:n), st%coh%r(0:n), st%coh%dc(0:n), st%coh%dmax(0:n), st%coh%q(0:n), &
               st%coh%opening(0:n), source=0.0_wp)
      allocate(st%coh%active(0:n), source=.false.)
      allocate(st%coh%pending(max(1, n)), source=0)
      allocate(st%coh%pending_stress(max(1, n)), source=0.0_wp)
      st%coh%n_active = 0
      st%coh%eps_rel = prob%eps_rel
      do i = 1, n - 1
         ra = st%cell_strength(i)
         rb = st%cell_strength(i + 1)
         k = i
         if (ra < 0.0_wp .or. (rb >= 0.0_wp .and. rb < ra)) k = i + 1
         ! the model's energies are per unit area times the area (spb_mesh), as its forces
         st%coh%gc(i) = prob%fracture_energy(mesh%seg(k)) * mesh%area(k)
         ! two sides as strong: the smaller Gc, whichever side is up (mirror)
         if (ra >= 0.0_wp .and. .not. abs(ra - rb) > 0.0_wp) st%coh%gc(i) = min( &
            prob%fracture_energy(mesh%seg(i)) * mesh%area(i), &
            prob%fracture_energy(mesh%seg(i + 1)) * mesh%area(i + 1))
      end do
      ! a section with no strength opens no cohesive crack
      where (.not. st%strength > 0.0_wp) st%coh%gc = 0.0_wp
   end subroutine init_cohesive

   !> The sections' damage integrals K and exponents lambda (Tuler-Butcher): each node takes
   !> those of the cell whose strength it took (spb_state init_strength: the weaker side of
   !> a bonded interface; where both sides are as strong, the smaller K, then the smaller
   !> lambda, so that a mirrored bar is the same; with a strength field, its cell's
   !> segment). Only where some segment has K > 0; a dry interface has no bond.
   subroutine init_damage(prob, mesh, st)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state (strengths set)
      integer :: i, n, k, ja, jb
      real(wp) :: ra, rb
      n = mesh%n
      st%dmg%on = allocated(prob%damage_integral)
      if (st%dmg%on) st%dmg%on = any(prob%damage_integral > 0.0_wp)
      if (.not. st%dmg%on) return
      allocate(st%dmg%k(0:n), st%dmg%d(0:n), source=0.0_wp)
      allocate(st%dmg%lambda(0:n), source=2.0_wp)
      do i = 1, n - 1
         ra = st%cell_strength(i)
         rb = st%cell_strength(i + 1)
         k = i
         if (ra < 0.0_wp .or. (rb >= 0.0_wp .and. rb < ra)) k = i + 1
         ja = mesh%seg(i)
         jb = mesh%seg(i + 1)
         if (ra >= 0.0_wp .and. .not. abs(ra - rb) > 0.0_wp .and. ja /= jb) then
            ! two sides as strong: the smaller K, then the smaller lambda, whichever is up
            k = i
            if (prob%damage_integral(jb) < prob%damage_integral(ja) .or. &
                (.not. abs(prob%damage_integral(jb) - prob%damage_integral(ja)) > 0.0_wp &
                 .and. prob%damage_exponent(jb) < prob%damage_exponent(ja))) k = i + 1
         end if
         st%dmg%k(i) = prob%damage_integral(mesh%seg(k))
         st%dmg%lambda(i) = prob%damage_exponent(mesh%seg(k))
      end do
      ! an unbreakable section has no K (a dry interface's is cleared where it is set open)
      where (st%strength < 0.0_wp) st%dmg%k = 0.0_wp
   end subroutine init_damage

   !> Tensile strength of every cell [Pa] (< 0 unbreakable): its segment's, or with
   !> &strength_field kind = 'weibull' a Weibull sample (spb_random, the deck's seed) for
   !> every cell of a segment whose strength is >= 0, drawn from the top cell down.
   function cell_strengths(prob, mesh) result(cs)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp) :: cs(mesh%n)
      type(rng_t) :: g
      real(wp) :: u
      integer :: k
      cs = prob%strength(mesh%seg)
      if (prob%weibull) then
         g = rng_seed(prob%seed)
         do k = 1, mesh%n
            if (cs(k) < 0.0_wp) cycle
            call rng_uniform(g, u)
            cs(k) = weibull(u, prob%weibull_modulus, prob%weibull_scale)
         end do
      end if
      ! the model's stresses are forces A sigma (spb_mesh): so are its strengths
      where (cs >= 0.0_wp) cs = cs * mesh%area
   end function cell_strengths

   !> Number of fragments: pieces between split interior nodes.
   pure integer function fragment_count(st) result(nf)
      type(state_t), intent(in) :: st      !! the state
      nf = 1 + st%fm%n_cut + st%n_split - st%coh%n_active
   end function fragment_count

   !> Register the state's history columns: the row's time and step, the supports' section
   !> stresses, the fragments (their meaning: doc/outputs.md).
   pure subroutine register_state_columns(set, id)
      type(column_set_t), intent(inout) :: set   !! the history's columns
      type(state_columns_t), intent(out) :: id   !! their ids
      call add_column(set, id%t, 't', 's')
      call add_column(set, id%step, 'step', '-', whole=.true.)
      call add_column(set, id%reaction_bottom, 'reaction_bottom', 'Pa')
      call add_column(set, id%reaction_top, 'reaction_top', 'Pa')
      call add_column(set, id%fragments, 'fragments', '-', whole=.true.)
   end subroutine register_state_columns

   !> Post the state's values into a history row.
   pure subroutine post_state_columns(id, mesh, st, row)
      type(state_columns_t), intent(in) :: id   !! the columns' ids
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(inout) :: row(:)    !! the row
      row(id%t) = real(st%step, wp) * mesh%dt
      row(id%step) = real(st%step, wp)
      row(id%reaction_bottom) = st%section(mesh%n) / mesh%area(mesh%n)
      row(id%reaction_top) = st%section(0) / mesh%area(1)
      row(id%fragments) = real(fragment_count(st), wp)
   end subroutine post_state_columns

   !> Whether node i separates two fragments: split, and not a cohesive crack that still
   !> carries traction (its faces are held together by it).
   pure logical function separates(st, i)
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! node
      separates = .not. st%joined(i)
      if (separates .and. st%coh%on) separates = .not. st%coh%active(i)
   end function separates

   !> Split interior node i (it must be joined): its halves move apart from now on. O(n_split).
   pure subroutine open_node(st, i)
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: i             !! the interior node to split
      integer :: c
      c = st%n_split
      do while (c > 0)
         if (st%split(c) < i) exit
         st%split(c + 1) = st%split(c)
         c = c - 1
      end do
      st%split(c + 1) = i
      st%n_split = st%n_split + 1
      st%joined(i) = .false.
   end subroutine open_node

   !> Join split interior node i: its halves move together from now on. O(n_split).
   pure subroutine close_node(st, i)
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: i             !! the interior node to join
      integer :: c, k
      k = 0
      do c = 1, st%n_split
         if (st%split(c) == i) k = c
      end do
      if (k == 0) return
      st%split(k:st%n_split - 1) = st%split(k + 1:st%n_split)
      st%n_split = st%n_split - 1
      st%joined(i) = .true.
   end subroutine close_node
end module spb_state
