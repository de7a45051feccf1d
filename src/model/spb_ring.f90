!> Characteristic stepping of intact homogeneous stretches (doc/method.md, "Characteristic
!> stepping of intact stretches (issue 36)").
!>
!> With dx = a dt the compact update (2.3) of a stretch of equal cells is an exact shift:
!> du_j^n = F(n - j) + G(n + j) and s_k^n = K (F(n - k + 1) - G(n + k)), K = E A / dx, j and
!> k counted from the stretch's top node; gravity adds (n - n0) g dt^2 to every du (its
!> uniform part cancels in the strains) from the conversion at step n0. The bar is cut into rings, the stretches of at
!> least min_cells cells of one material whose interior nodes are all joined (cut at the
!> segments' interfaces and at split nodes), and the rest, the junction nodes (each ring's
!> two end nodes, the split nodes, the nodes of stretches too short to be a ring) and the
!> lattice cells (the cells of those short stretches). A step writes one new F at each
!> ring's top node and one new G at its bottom node, found by the lattice's own update of
!> those junction nodes (spb_step advance: the same expressions, loads, supports, the
!> ledger); every other ring value only moves. The section stresses (3.1)-(3.2) of a ring
!> obey S_i^{n+1/2} + S_i^{n-1/2} = s_i^n + s_{i+1}^n, which the same shift carries:
!> S_i^{n+1/2} = Ra(n - i) + Rb(n + i + 1) + (-1)^n C_i, two more characteristic sequences
!> and one constant per node. The fracture test is bounded by block extrema of Ra and Rb
!> (blocks of 64 values, levels of 8 blocks) and each block's weakest section (C and the
!> strengths, found once), and evaluated node by node only where that bound reaches the
!> strength; a junction node's section is the lattice's own. advance_rings stops before any
!> step in which a node could break or two split faces could touch, with the lattice arrays
!> rebuilt, so that the whole step (spb_sim sim_step) takes it as always.
module spb_ring
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_load, only: load_t
   use spb_state, only: state_t
   use spb_ends, only: face_step_t, face_top, face_bottom, has_base, is_striker
   use spb_problem, only: end_free, end_fixed, events_admissible
   use spb_step, only: end_stresses, step_load_integral, hold_end, book_end_nodes
   use spb_gauge, only: gauge_t, read_gauges
   implicit none
   private
   public :: ring_qualifies, ring_layout, start_rings, advance_rings, end_rings, ring_span_max

   integer, parameter :: leaf_bits = 6   !! log2 of leaf
   integer, parameter :: fan_bits = 3    !! log2 of fan
   integer, parameter :: leaf = 2**leaf_bits   !! values per finest block
   integer, parameter :: fan = 2**fan_bits     !! blocks of one level per block of the next
   !> A node whose section stress S from the characteristic sequences (or from the ring's
   !> end cells) comes below -R - eps_rel s_scale + margin_share scale stops the
   !> characteristic steps before the step: the lattice breaks it where S < -R - eps, eps >=
   !> eps_rel s_scale (spb_fracture), and its own S differs from this one by round-off only
   !> (~1e-13 of the scale), far below the margin [-]
   real(wp), parameter :: margin_share = 1.0e-11_wp
   !> Two split faces that would overlap by more than this share of the admissible rules'
   !> collision test (overlap > eps_rel dx) after a step stop the characteristic steps
   !> before it: their positions differ from the lattice's by round-off in the increments
   !> only, far below the rest of eps_rel dx [-]
   real(wp), parameter :: touch_part = 0.99_wp
   !> Under the paper's rules (overlap > 0), or with eps_rel = 0, faces that would come
   !> within this share of their cells' length of touching stop them [-]
   real(wp), parameter :: touch_share = 1.0e-9_wp
   !> An increase of the largest stress magnitude (st%s_scale) smaller than this share of it
   !> is not looked for (it scales only the fracture test's round-off guard) [-]
   real(wp), parameter :: scale_share = 1.0e-12_wp
   !> Stands for "cannot break" in the blocks' weakest sections (finite: sums of it with
   !> stresses must not overflow) [Pa]
   real(wp), parameter :: no_break = 0.25_wp * huge(1.0_wp)

   !> The extrema of one level of blocks.
   type :: level_t
      real(wp), allocatable :: mn(:)   !! smallest value of each block
      real(wp), allocatable :: mx(:)   !! largest value of each block
   end type level_t

   !> A characteristic sequence v(j), j = lo..hi written in increasing j, with the extrema
   !> of its blocks of leaf fan^(l-1) values (block b of level l holds j = lo + b bs ...).
   type :: seq_t
      integer :: lo = 0                         !! first index
      integer :: hi = -1                        !! last index written
      integer :: nl = 0                         !! levels of blocks (size of lev, kept:
                                                !! size() costs in the bounds' hot path)
      real(wp), allocatable :: v(:)             !! (lo:lo+capacity-1)
      real(wp), allocatable :: p(:)             !! F and G only: the running sums p(j) =
                                                !! v(lo) + ... + v(j), summed in increasing j
                                                !! as they are needed (u of the nodes inside:
                                                !! from_ring, node_now; sums_to), allocated
                                                !! at the first need
      integer :: p_hi = 0                       !! p holds lo..p_hi
      type(level_t), allocatable :: lev(:)      !! the levels of blocks
   end type seq_t

   !> The characteristic state of one ring between the conversions: cells c0..c0+n-1, its
   !> local node j the bar's node c0 - 1 + j (j = 0 and n: junction nodes).
   type :: ring_t
      integer :: c0 = 1               !! first cell
      integer :: n = 0                !! cells
      integer :: n0 = 0               !! step of the conversion
      real(wp) :: k = 0.0_wp          !! E A / dx of the cells [Pa/m A]
      logical :: sections = .false.   !! Ra, Rb and C are kept (sections are read)
      logical :: breaks = .false.     !! some interior node can break: the bounded test
      type(seq_t) :: f                !! F: du_j^n = F(n - j) + G(n + j) [m]
      type(seq_t) :: g                !! G [m]
      type(seq_t) :: ra               !! Ra: S_j^{n+1/2} = Ra(n - j) + Rb(n + j + 1) + ... [Pa]
      type(seq_t) :: rb               !! Rb [Pa]
      real(wp), allocatable :: c(:)   !! (1:n-1) C_j of the sections [Pa]
      type(seq_t) :: w_even           !! (1:n-1) C_j + R_j (a step from an even n) [Pa]
      type(seq_t) :: w_odd            !! (1:n-1) -C_j + R_j [Pa]
      real(wp) :: scale = 0.0_wp      !! largest |Ra|, |Rb|, |C| seen [Pa]
      real(wp) :: s_ends(2) = 0.0_wp  !! s^n0 of its first and last cell (restored when it
                                      !! takes no step) [Pa]
      logical :: finite = .true.      !! the state it was converted from is finite
   end type ring_t

   !> The rings and the junctions of a bar between start_rings and end_rings.
   type, public :: ring_hybrid_t
      private
      type(ring_t), allocatable :: r(:)       !! the rings
      integer, allocatable :: jn(:)           !! the junction nodes, ascending
      integer, allocatable :: lc(:)           !! the lattice cells, ascending
      logical, allocatable :: keep(:)         !! (0:n) the nodes whose sections are kept
      logical :: sections = .false.           !! some section is kept
      logical :: all_sections = .false.       !! every section is kept (some can break)
      logical :: finite = .true.              !! the converted state is finite
      real(wp) :: touch = 0.0_wp              !! faces that would overlap by more than this
                                              !! share of dx stop the steps [-]
      real(wp), allocatable :: nda(:), ndb(:) !! the junctions' trial increments [m]
      real(wp), allocatable :: nsec(:)        !! their trial sections [Pa]
      integer, allocatable :: samples(:)      !! the nodes whose sections are sampled
      !> the entries the gauges read that the rings hold, once each (read_ring_gauges, at
      !> its first call): (node or cell, its ring) of the nodes inside a ring, of the cells
      logical :: g_ready = .false.
      integer, allocatable :: g_node(:, :)
      integer, allocatable :: g_cell(:, :)
   end type ring_hybrid_t

   !> Where the rings lie: the stretches of at least min_cells equal cells joined inside.
   type, public :: ring_layout_t
      integer :: nr = 0                      !! rings
      integer, allocatable :: c0(:)          !! first cell of each
      integer, allocatable :: nc(:)          !! cells of each
      integer :: ring_cells = 0              !! cells in rings
      logical :: worth = .false.             !! the rings hold three quarters of the bar or
                                             !! more (below, the junctions' updates cost
                                             !! about what the lattice's step does), and
                                             !! their steps cost less than the lattice's
   end type ring_layout_t

   !> The costs of a step compared in ring_layout, in units of the lattice's update of one
   !> node of a breakable bar (about 18 instructions): measured with callgrind (Release) on
   !> free bars of 16-128 cells, 250 N steps, a lattice step costs about 3900 + 18 (N + 1)
   !> instructions and a one-ring step about 2700 whatever N; a ring (its four pushes, its
   !> bounded tests) about 1500, a junction node (the general path, node by node) about 135
   !> (doc/method.md, "When") [-]
   integer, parameter :: ring_step_nodes = 80       !! a ring's step
   integer, parameter :: junction_step_nodes = 7    !! a junction node's update
   integer, parameter :: lattice_step_nodes = 210   !! the lattice step's own cost

contains

   !> Whether advance_rings may stand in for whole steps (advance, contact_step,
   !> fracture_step) of this bar: free or fixed ends with no base, striking mass or
   !> landing, no cohesive crack or damage integral, the half-mass model, no node whose
   !> section test starts late (n_skip). Split nodes, interfaces and breakable nodes are
   !> allowed: the rings end at the first two, and the steps stop before one could break or
   !> two faces could touch.
   pure logical function ring_qualifies(mesh, st)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      ring_qualifies = .false.
      if (mesh%n < 2 .or. mesh%full_mass) return
      if (st%fm%n_cut /= 0 .or. st%n_skip /= 0) return
      if (st%coh%on .or. st%dmg%on) return
      if (any(has_base(st%ends) .or. is_striker(st%ends)) .or. any(st%ends%landing)) return
      if (.not. all(st%ends%kind == end_free .or. st%ends%kind == end_fixed)) return
      ring_qualifies = .true.
   end function ring_qualifies

   !> The rings of the bar now: the stretches of equal cells (mass, impedance, stiffness)
   !> cut at the split nodes, those of at least min_cells cells. O(segments + split nodes).
   pure function ring_layout(mesh, st, min_cells) result(lay)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state (st%split ascending)
      integer, intent(in) :: min_cells     !! the shortest ring [cells]
      type(ring_layout_t) :: lay
      integer :: cuts(mesh%nseg + st%n_split + 1), first(mesh%nseg + st%n_split + 1)
      integer :: cells(mesh%nseg + st%n_split + 1), nk, j, c, a, b, k, p
      ! the cuts: each node below which a new stretch starts (an interface between unequal
      ! segments, a split node), merged in ascending order, and the bottom node
      nk = 0
      c = 1
      do j = 1, mesh%nseg
         if (j < mesh%nseg) then
            k = mesh%last(j)
            if (same_cells(mesh, k, k + 1)) cycle
         else
            k = mesh%n
         end if
         do while (c <= st%n_split)
            if (st%split(c) >= k) exit
            nk = nk + 1
            cuts(nk) = st%split(c)
            c = c + 1
         end do
         if (c <= st%n_split) then
            if (st%split(c) == k) c = c + 1
         end if
         nk = nk + 1
         cuts(nk) = k
      end do
      a = 0
      do p = 1, nk
         b = cuts(p)
         if (b - a >= min_cells) then
            lay%nr = lay%nr + 1
            first(lay%nr) = a + 1
            cells(lay%nr) = b - a
         end if
         a = b
      end do
      allocate(lay%c0(lay%nr), lay%nc(lay%nr))
      lay%c0(:) = first(1:lay%nr)
      lay%nc(:) = cells(1:lay%nr)
      lay%ring_cells = sum(lay%nc)
      ! the rings' step against the lattice's (a bar of many short fragments, 70 rings of 28
      ! cells in 2000, stays on the lattice: 3.6 times its cost as rings; in real(wp), no
      ! overflow for any bar)
      lay%worth = 4 * lay%ring_cells >= 3 * mesh%n .and. &
                  real(ring_step_nodes, wp) * lay%nr + real(junction_step_nodes, wp) &
                  * (mesh%n + 1 - lay%ring_cells + lay%nr) < real(lattice_step_nodes, wp) + mesh%n + 1
   end function ring_layout

   !> Cells k and l are equal: mass, impedance, stiffness to the bit.
   pure logical function same_cells(mesh, k, l)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      integer, intent(in) :: k             !! one cell
      integer, intent(in) :: l             !! the other
      same_cells = .not. (abs(mesh%dm(k) - mesh%dm(l)) > 0.0_wp .or. &
                          abs(mesh%z(k) - mesh%z(l)) > 0.0_wp .or. &
                          abs(mesh%stiff(k) - mesh%stiff(l)) > 0.0_wp)
   end function same_cells

   !> The most steps one call of advance_rings takes for a bar of n cells: its arrays hold
   !> n + steps values per sequence.
   pure integer function ring_span_max(n)
      integer, intent(in) :: n             !! cells
      ring_span_max = n + 4096
   end function ring_span_max

   !> Up to nsteps whole steps of a bar in characteristic form (start_rings converted its
   !> rings, O(n); end_rings rebuilds the lattice arrays, O(n)): each step costs O(1) per ring
   !> at its ends and in the bounded fracture test plus the lattice's update of the junction
   !> nodes and lattice cells. It stops before a step in which some node could break or two
   !> split faces could touch, or whose state is not finite (taken < nsteps: the lattice
   !> takes that step after end_rings, and its check names the bad node). The end nodes'
   !> bookkeeping (book_end_nodes: ledger, support sections) is made step by step as advance
   !> makes it. s_old is not kept (as advance_joined): the caller ends with an ordinary step.
   !> samples: the section stresses S^{n+1/2} of every step taken at the nodes start_rings
   !> was given (an open contact episode's force).
   pure subroutine advance_rings(mesh, load, g, eps_rel, st, h, nsteps, taken, &
                                 max_sec_bottom, face_du, samples, gauges, gauge_every, readings)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: eps_rel      !! the event tests' round-off guard [-]
      type(state_t), intent(inout) :: st   !! the state
      type(ring_hybrid_t), intent(inout) :: h   !! the rings (start_rings)
      integer, intent(in) :: nsteps        !! steps to take at most (within start_rings's)
      integer, intent(out) :: taken        !! steps taken
      real(wp), intent(out) :: max_sec_bottom   !! largest sec(n) of these steps [Pa]
      real(wp), intent(out) :: face_du(2, nsteps)   !! increments of the face halves (B_0,
                                                    !! A_n) of each step [m]
      real(wp), intent(out) :: samples(size(h%samples), nsteps)   !! their S^{n+1/2} [Pa]
      type(gauge_t), intent(in), optional :: gauges(:)   !! the gauges (spb_gauge; these
                                                         !! three given together)
      integer, intent(in), optional :: gauge_every   !! a gauge row after each step that is a
                                                     !! multiple of this (0: none)
      real(wp), intent(inout), optional :: readings(:, :, :)   !! (3, gauges, nsteps) what
                                       !! the gauges read after those steps (stress, velocity,
                                       !! u: read_ring_gauges; the other steps' kept)
      type(face_step_t) :: fs(2)
      real(wp) :: guard, s_ends(2)
      integer :: t, c
      logical :: stop_now

      taken = 0
      max_sec_bottom = -huge(1.0_wp)
      face_du = 0.0_wp
      samples = 0.0_wp
      ! (which entries the gauges read that the rings hold: once a span)
      if (present(gauges) .and. .not. h%g_ready) call gauge_entries(h, gauges)
      do t = 1, nsteps
         if (.not. h%finite) exit
         ! the rings' sections S^{n+1/2} and their bounded test (3.3); could some node's
         ! S^{n+1/2} < -R - eps? Then the lattice takes this step.
         call rings_could_break(h, st, eps_rel, guard, stop_now)
         if (stop_now) exit
         ! the junction nodes on trial (a break, a touch, a value not finite stops here)
         s_ends = [st%s(0), st%s(mesh%n + 1)]
         call try_junctions(mesh, load, g, st, h, guard, fs, stop_now)
         if (stop_now) then
            st%s(0) = s_ends(1)
            st%s(mesh%n + 1) = s_ends(2)
            exit
         end if
         call take_junctions(mesh, load, g, st, h, fs)
         max_sec_bottom = max(max_sec_bottom, st%section(mesh%n))
         face_du(:, t) = fs%du
         ! fracture_step's largest stress magnitude, |s^{n+1}| and the bottom support's
         if (h%all_sections) call track_scale(st, h%r, h%lc)
         do c = 1, size(h%samples)
            samples(c, t) = section_of(st, h, h%samples(c))
         end do
         if (present(readings) .and. present(gauges) .and. present(gauge_every)) then
            if (gauge_every > 0) then
               if (mod(st%step, gauge_every) == 0) call read_ring_gauges(mesh, load, g, st, h, &
                  gauges, readings(1, :, t), readings(2, :, t), readings(3, :, t))
            end if
         end if
         taken = t
      end do
   end subroutine advance_rings

   !> The lattice arrays at the state's step from the rings (O(n)); the rings are gone.
   pure subroutine end_rings(mesh, g, st, h)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state (its junctions already at the step)
      type(ring_hybrid_t), intent(inout) :: h   !! the rings
      integer :: q
      do q = 1, size(h%r)
         call sums_to(h%r(q)%f, st%step)
         call sums_to(h%r(q)%g, st%step + h%r(q)%n)
         call from_ring(h%r(q), st, h%keep, g * mesh%dt**2)
         ! (one ring's sums at a time where no gauge reads the rings)
         deallocate(h%r(q)%f%p, h%r(q)%g%p)
      end do
      deallocate(h%r)
      st%n_skip = 0
   end subroutine end_rings

   !> The rings of a layout (ring_layout of this state) in characteristic form, with room
   !> for nsteps steps (at most ring_span_max): the sections advance keeps (every node's
   !> where some can break, else the gauges' (mesh%watch); and the sampled ones), the
   !> junction nodes and lattice cells, the rings converted (O(n)).
   pure subroutine start_rings(mesh, st, lay, nsteps, eps_rel, rules, sample_nodes, h)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(ring_layout_t), intent(in) :: lay   !! the rings
      integer, intent(in) :: nsteps        !! steps to make room for
      real(wp), intent(in) :: eps_rel      !! the event tests' round-off guard [-]
      integer, intent(in) :: rules         !! events_admissible | events_paper
      integer, intent(in) :: sample_nodes(:)   !! nodes whose sections are sampled (joined)
      type(ring_hybrid_t), intent(out) :: h     !! the hybrid state
      integer :: q
      h%samples = sample_nodes
      h%all_sections = st%n_breakable > 0
      allocate(h%keep(0:mesh%n))
      h%keep = h%all_sections
      h%keep(mesh%watch(1:mesh%n_watch)) = .true.
      h%keep(sample_nodes) = .true.
      h%sections = any(h%keep)
      call junctions(mesh%n, lay, h%jn, h%lc)
      allocate(h%nda(size(h%jn)), h%ndb(size(h%jn)), h%nsec(size(h%jn)))
      h%touch = -touch_share
      if (rules == events_admissible .and. eps_rel > 0.0_wp) h%touch = touch_part * eps_rel
      allocate(h%r(lay%nr))
      h%finite = .true.
      do q = 1, lay%nr
         call to_ring(mesh, st, lay%c0(q), lay%nc(q), nsteps, h%sections, h%r(q))
         h%finite = h%finite .and. h%r(q)%finite
      end do
   end subroutine start_rings

   !> The rings' sections S^{n+1/2} one value on (Ra(n - 1), Rb(n + m)), the threshold of
   !> the fracture test, and whether some ring's node could come below it (stop).
   pure subroutine rings_could_break(h, st, eps_rel, guard, stop)
      type(ring_hybrid_t), intent(inout) :: h   !! the hybrid state
      type(state_t), intent(in) :: st      !! the state at t^n
      real(wp), intent(in) :: eps_rel      !! the event tests' round-off guard [-]
      real(wp), intent(out) :: guard       !! the threshold of S + R [Pa]
      logical, intent(out) :: stop         !! some node could break in this step
      real(wp) :: scale, best
      integer :: q, n, m
      n = st%step
      scale = st%s_scale
      do q = 1, size(h%r)
         if (h%r(q)%sections) call push_sections(h%r(q), n)
         scale = max(scale, h%r(q)%scale)
      end do
      guard = -eps_rel * st%s_scale + margin_share * scale
      stop = .false.
      do q = 1, size(h%r)
         if (.not. h%r(q)%breaks) cycle
         best = no_break
         m = h%r(q)%n
         associate (r => h%r(q))
            if (modulo(n, 2) == 0) then
               call descend(r%ra, 1.0_wp, 0, r%rb, 1.0_wp, 1, n, size(r%w_even%lev), 1, m - 1, &
                            guard, best, r%w_even)
            else
               call descend(r%ra, 1.0_wp, 0, r%rb, 1.0_wp, 1, n, size(r%w_odd%lev), 1, m - 1, &
                            guard, best, r%w_odd)
            end if
         end associate
         if (best < guard) stop = .true.
      end do
   end subroutine rings_could_break

   !> The junction nodes' step on trial (nothing of the state changed but the rings' end
   !> cells' s^n, which they read, and the end stresses s(0), s(n+1)), as advance takes
   !> them: the end stresses, sections (3.1)-(3.2), (2.3)1-2 joined or by halves. stop: a
   !> node's section comes below the guard, two faces would touch, or a value is not
   !> finite.
   pure subroutine try_junctions(mesh, load, g, st, h, guard, fs, stop)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state at t^n
      type(ring_hybrid_t), intent(inout) :: h   !! the hybrid state (its trial values set)
      real(wp), intent(in) :: guard        !! the threshold of S + R [Pa]
      type(face_step_t), intent(out) :: fs(2)   !! the ends' record (their stresses)
      logical, intent(out) :: stop         !! the lattice must take this step
      real(wp) :: da, db, sec, dt, dt2, tol
      integer :: c, i, q, m, n, nc
      n = st%step
      nc = mesh%n
      dt = mesh%dt
      dt2 = dt * dt
      do q = 1, size(h%r)
         m = h%r(q)%n
         st%s(h%r(q)%c0) = cell_stress(h%r(q), n, 1)
         st%s(h%r(q)%c0 + m - 1) = cell_stress(h%r(q), n, m)
      end do
      call end_stresses(mesh, load, st, fs(face_top)%s, fs(face_bottom)%s, step=n)
      st%s(0) = fs(face_top)%s
      st%s(nc + 1) = fs(face_bottom)%s
      stop = .false.
      do c = 1, size(h%jn)
         i = h%jn(c)
         sec = st%section(i)
         if (st%joined(i)) then
            da = st%dua(i) + ((st%s(i) + mesh%ma(i) * g) + (mesh%mb(i) * g - st%s(i + 1))) &
                 * mesh%inv_m(i) * dt2
            db = da
            if (i > 0 .and. i < nc .and. h%keep(i)) then
               sec = section_stress_a(st%s(i), sec, st%dua(i) / dt, da / dt, mesh%z(i), &
                                      mesh%dm(i), g)
               if (st%strength(i) >= 0.0_wp) then
                  if (sec + st%strength(i) < guard) stop = .true.
               end if
            end if
         else
            da = st%dua(i) + (st%s(i) + mesh%ma(i) * g) / mesh%ma(i) * dt2
            db = st%dub(i) + (mesh%mb(i) * g - st%s(i + 1)) / mesh%mb(i) * dt2
            tol = h%touch * min(mesh%dx(i), mesh%dx(i + 1))
            if ((st%ua(i) + da) - (st%ub(i) + db) > tol) stop = .true.
         end if
         h%nda(c) = da
         h%ndb(c) = db
         h%nsec(c) = sec
         ! (a value not finite: the lattice's check after its step names the node)
         if (.not. (abs(da) <= huge(1.0_wp) .and. abs(db) <= huge(1.0_wp))) stop = .true.
      end do
   end subroutine try_junctions

   !> The step taken: the junction nodes' trial values, the supports, the ends' booking,
   !> (2.3)3-4 where the lattice holds them, the rings' new values at their ends.
   pure subroutine take_junctions(mesh, load, g, st, h, fs)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state: from t^n to t^{n+1}
      type(ring_hybrid_t), intent(inout) :: h   !! the hybrid state
      type(face_step_t), intent(inout) :: fs(2)   !! the ends' record
      real(wp) :: fall, dt2
      integer :: c, i, q, m, n, nc
      n = st%step
      nc = mesh%n
      dt2 = mesh%dt**2
      fs(face_top)%q = step_load_integral(load, n, mesh%dt, face_top)
      fs(face_bottom)%q = step_load_integral(load, n, mesh%dt, face_bottom)
      fs%rho = 0.0_wp
      fs(face_top)%du_old = st%dub(0)
      fs(face_bottom)%du_old = st%dua(nc)
      do c = 1, size(h%jn)
         i = h%jn(c)
         st%dua(i) = h%nda(c)
         st%dub(i) = h%ndb(c)
         st%section(i) = h%nsec(c)
      end do
      call hold_end(mesh, st, face_top, fs(face_top))
      call hold_end(mesh, st, face_bottom, fs(face_bottom))
      fs(face_top)%s_cell = st%s(1)
      fs(face_bottom)%s_cell = st%s(nc)
      call book_end_nodes(mesh, g, st, fs)
      do c = 1, size(h%jn)
         i = h%jn(c)
         st%ua(i) = st%ua(i) + st%dua(i)
         st%ub(i) = st%ub(i) + st%dub(i)
      end do
      do c = 1, size(h%lc)
         i = h%lc(c)
         st%s(i) = st%s(i) + mesh%stiff(i) * (st%dub(i - 1) - st%dua(i))
      end do
      ! du_0^{n+1} = F(n+1) + G(n+1) + (n+1-n0) g dt^2, du_m^{n+1} = F(n+1-m) + G(n+1+m) + ...
      do q = 1, size(h%r)
         m = h%r(q)%n
         fall = real(n + 1 - h%r(q)%n0, wp) * (g * dt2)
         call push(h%r(q)%f, (st%dub(h%r(q)%c0 - 1) - fall) - h%r(q)%g%v(n + 1))
         call push(h%r(q)%g, (st%dua(h%r(q)%c0 - 1 + m) - fall) - h%r(q)%f%v(n + 1 - m))
      end do
      st%step = n + 1
   end subroutine take_junctions

   !> The section stress S^{n+1/2} of node i after the step to t^{n+1} (st%step): a
   !> junction's as the step left it, a ring's from its sequences.
   pure real(wp) function section_of(st, h, i) result(sec)
      type(state_t), intent(in) :: st      !! the state at t^{n+1}
      type(ring_hybrid_t), intent(in) :: h      !! the hybrid state
      integer, intent(in) :: i             !! the node
      integer :: q, j, n
      n = st%step - 1
      q = ring_of(h, i)
      if (q == 0) then
         sec = st%section(i)
      else
         j = i - (h%r(q)%c0 - 1)
         sec = h%r(q)%ra%v(n - j) + h%r(q)%rb%v(n + j + 1) + sign_of(n) * h%r(q)%c(j)
      end if
   end function section_of

   !> The junction nodes (ascending) and the lattice cells (ascending) of a layout: the
   !> nodes no ring holds inside, the cells no ring holds (O(rings + their count)).
   pure subroutine junctions(nc, lay, jn, lc)
      integer, intent(in) :: nc            !! cells of the bar
      type(ring_layout_t), intent(in) :: lay   !! the rings (ascending, apart)
      integer, allocatable, intent(out) :: jn(:)   !! junction nodes
      integer, allocatable, intent(out) :: lc(:)   !! lattice cells
      integer :: q, i, nj, nl, node, cell
      ! ring q holds cells c0..c0+m-1 and, inside, nodes c0..c0+m-2
      allocate(jn(nc + 1 - sum(max(lay%nc(1:lay%nr) - 1, 0))), lc(nc - lay%ring_cells))
      nj = 0
      nl = 0
      node = 0
      cell = 1
      do q = 1, lay%nr
         do i = node, lay%c0(q) - 1
            nj = nj + 1
            jn(nj) = i
         end do
         do i = cell, lay%c0(q) - 1
            nl = nl + 1
            lc(nl) = i
         end do
         node = lay%c0(q) + lay%nc(q) - 1
         cell = lay%c0(q) + lay%nc(q)
      end do
      do i = node, nc
         nj = nj + 1
         jn(nj) = i
      end do
      do i = cell, nc
         nl = nl + 1
         lc(nl) = i
      end do
   end subroutine junctions

   !> The ring holding node i inside (0: a junction node), or with cell, cell i (0: a lattice
   !> cell): ring q holds cells c0..c0+m-1 and, inside, nodes c0..c0+m-2.
   pure integer function ring_of(h, i, cell) result(q)
      type(ring_hybrid_t), intent(in) :: h   !! the hybrid state
      integer, intent(in) :: i             !! the node (the cell)
      logical, intent(in), optional :: cell   !! i is a cell
      integer :: last
      last = 2
      if (present(cell)) then
         if (cell) last = 1
      end if
      do q = 1, size(h%r)
         if (i >= h%r(q)%c0 .and. i <= h%r(q)%c0 + h%r(q)%n - last) return
      end do
      q = 0
   end function ring_of

   !> What the gauges read (spb_gauge read_gauges) after a characteristic step: the entries
   !> of the lattice arrays they read that a ring holds (u, du and the section of a node
   !> inside it, the stress of a cell of it) made as end_rings would make them at this step,
   !> read, and put back: until end_rings, st%ua and ub of a ring's inside hold u at its
   !> conversion, to which from_ring adds (O(1) a gauge; which entries: gauge_entries, made
   !> before).
   pure subroutine read_ring_gauges(mesh, load, g, st, h, gauges, stress, velocity, u)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state at t^n (st%step), as it was on return
      type(ring_hybrid_t), intent(inout) :: h   !! the hybrid state (its running sums made on)
      type(gauge_t), intent(in) :: gauges(:)    !! the gauges (the same at every call of a span)
      real(wp), intent(out) :: stress(:)   !! stress of each gauge [Pa]
      real(wp), intent(out) :: velocity(:) !! velocity of each gauge [m/s]
      real(wp), intent(out) :: u(:)        !! displacement of each gauge [m]
      real(wp) :: saved(5, size(h%g_node, 2)), saved_s(size(h%g_cell, 2))
      integer :: k, q, n
      n = st%step
      do k = 1, size(h%g_node, 2)
         associate (i => h%g_node(1, k), r => h%r(h%g_node(2, k)))
            saved(:, k) = [st%ua(i), st%ub(i), st%dua(i), st%dub(i), st%section(i)]
            call sums_to(r%f, n)
            call sums_to(r%g, n + r%n)
            call node_now(r, st, i - (r%c0 - 1), g * mesh%dt**2)
         end associate
      end do
      do k = 1, size(h%g_cell, 2)
         q = h%g_cell(2, k)
         associate (c => h%g_cell(1, k))
            saved_s(k) = st%s(c)
            st%s(c) = cell_stress(h%r(q), n, c - (h%r(q)%c0 - 1))
         end associate
      end do
      call read_gauges(mesh, load, st, gauges, stress, velocity, u)
      do k = 1, size(h%g_node, 2)
         associate (i => h%g_node(1, k))
            st%ua(i) = saved(1, k)
            st%ub(i) = saved(2, k)
            st%dua(i) = saved(3, k)
            st%dub(i) = saved(4, k)
            st%section(i) = saved(5, k)
         end associate
      end do
      do k = 1, size(h%g_cell, 2)
         st%s(h%g_cell(1, k)) = saved_s(k)
      end do
   end subroutine read_ring_gauges

   !> The entries of the lattice arrays the gauges read that the rings hold, each once
   !> (read_ring_gauges: from_ring adds to u^n0, which a second patch would take for it): the
   !> nodes inside a ring (a node gauge's, a cell gauge's two) and the cells of a ring (a
   !> cell gauge's), each with its ring.
   pure subroutine gauge_entries(h, gauges)
      type(ring_hybrid_t), intent(inout) :: h   !! the hybrid state (g_node, g_cell set)
      type(gauge_t), intent(in) :: gauges(:)    !! the gauges
      integer :: want(2 * size(gauges)), nodes(2, 2 * size(gauges)), cells(2, size(gauges))
      integer :: k, nw, nn, nc, c, q
      ! the nodes they read (a node gauge's, a cell gauge's two) and the cells of the rings
      nw = 0
      nc = 0
      do k = 1, size(gauges)
         c = gauges(k)%cell
         if (gauges(k)%node >= 0) then
            nw = nw + 1
            want(nw) = gauges(k)%node
            cycle
         end if
         want(nw + 1:nw + 2) = [c - 1, c]
         nw = nw + 2
         q = ring_of(h, c, cell=.true.)
         if (q == 0) cycle
         if (any(cells(1, 1:nc) == c)) cycle
         nc = nc + 1
         cells(:, nc) = [c, q]
      end do
      ! of those nodes, the ones inside a ring, once each
      nn = 0
      do k = 1, nw
         q = ring_of(h, want(k))
         if (q == 0) cycle
         if (any(nodes(1, 1:nn) == want(k))) cycle
         nn = nn + 1
         nodes(:, nn) = [want(k), q]
      end do
      h%g_node = nodes(:, 1:nn)
      h%g_cell = cells(:, 1:nc)
      h%g_ready = .true.
   end subroutine gauge_entries

   !> The lattice arrays of the node j inside ring r (local: the bar's node c0 - 1 + j) at
   !> t^n (st%step > r%n0), as from_ring makes them: u, du and, where r keeps sections, the
   !> section S^{n-1/2} (the running sums made to n and n + m).
   pure subroutine node_now(r, st, j, gdt2)
      type(ring_t), intent(in) :: r        !! the ring
      type(state_t), intent(inout) :: st   !! the state (st%ua, ub of the node: u^n0)
      integer, intent(in) :: j             !! the node, 1..m-1 of the ring
      real(wp), intent(in) :: gdt2         !! g dt^2 [m]
      real(wp) :: d, fall, fallen
      integer :: n, n0, i
      n = st%step
      n0 = r%n0
      i = r%c0 - 1 + j
      fall = real(n - n0, wp) * gdt2
      fallen = 0.5_wp * real(n - n0, wp) * real(n - n0 + 1, wp) * gdt2
      d = (r%f%p(n - j) - r%f%p(n0 - j)) + (r%g%p(n + j) - r%g%p(n0 + j)) + fallen
      st%ua(i) = st%ua(i) + d
      st%ub(i) = st%ub(i) + d
      st%dua(i) = r%f%v(n - j) + r%g%v(n + j) + fall
      st%dub(i) = st%dua(i)
      if (r%sections) st%section(i) = r%ra%v(n - 1 - j) + r%rb%v(n + j) + sign_of(n - 1) * r%c(j)
   end subroutine node_now

   !> The stress s_k^n of ring r's cell k (1..m, local): K (F(n - k + 1) - G(n + k)), as
   !> from_ring's loop makes every cell's.
   pure real(wp) function cell_stress(r, n, k) result(s)
      type(ring_t), intent(in) :: r        !! the ring
      integer, intent(in) :: n             !! the step
      integer, intent(in) :: k             !! the cell, 1..m of the ring
      s = r%k * (r%f%v(n - k + 1) - r%g%v(n + k))
   end function cell_stress

   !> The sequences Ra, Rb of a ring one value on, with what S^{n+1/2} needs: Ra(n - 1),
   !> Rb(n + m).
   pure subroutine push_sections(r, n)
      type(ring_t), intent(inout) :: r     !! the ring
      integer, intent(in) :: n             !! the step index
      real(wp) :: a, b
      integer :: m
      m = r%n
      a = r%k * (r%f%v(n) + r%f%v(n - 1))
      call push(r%ra, a - r%ra%v(n - 2))
      b = -r%k * (r%g%v(n + m - 1) + r%g%v(n + m))
      call push(r%rb, b - r%rb%v(n + m - 1))
      r%scale = max(r%scale, abs(r%ra%v(n - 1)), abs(r%rb%v(n + m)))
   end subroutine push_sections

   !> st%s_scale after a step at t^n (st%step = n): the largest |s^n| of the lattice cells,
   !> of each ring's cells (bounded by its blocks), and the bottom support's section.
   pure subroutine track_scale(st, r, lc)
      type(state_t), intent(inout) :: st   !! the state
      type(ring_t), intent(in) :: r(:)     !! the rings
      integer, intent(in) :: lc(:)         !! the lattice cells
      real(wp) :: thr, best
      integer :: c, q, n
      n = st%step
      st%s_scale = max(st%s_scale, abs(st%section(size(st%section) - 1)))
      do c = 1, size(lc)
         st%s_scale = max(st%s_scale, abs(st%s(lc(c))))
      end do
      do q = 1, size(r)
         thr = -(st%s_scale / r(q)%k) * (1.0_wp + scale_share)
         best = no_break
         call descend(r(q)%f, 1.0_wp, 1, r(q)%g, -1.0_wp, 0, n, size(r(q)%f%lev), 1, r(q)%n, &
                      thr, best)
         call descend(r(q)%f, -1.0_wp, 1, r(q)%g, 1.0_wp, 0, n, size(r(q)%f%lev), 1, r(q)%n, &
                      thr, best)
         if (best < no_break) st%s_scale = max(st%s_scale, -r(q)%k * best)
      end do
   end subroutine track_scale

   !> The characteristic state of the ring of cells c0..c0+m-1 at t^n0 (O(m)), with room for
   !> nsteps; with sections, its Ra, Rb, C and the blocks' weakest sections too.
   pure subroutine to_ring(mesh, st, c0, m, nsteps, sections, r)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state (the ring's interior joined)
      integer, intent(in) :: c0            !! first cell
      integer, intent(in) :: m             !! cells
      integer, intent(in) :: nsteps        !! steps to make room for
      logical, intent(in) :: sections      !! the section sequences are kept
      type(ring_t), intent(out) :: r       !! its characteristic form
      real(wp) :: c, sgn
      integer :: n0, b, j, cap
      b = c0 - 1
      n0 = st%step
      r%c0 = c0
      r%n = m
      r%n0 = n0
      r%k = mesh%stiff(c0)
      cap = m + nsteps + 2
      call start_seq(r%f, n0 - m, cap, m + nsteps + 1)
      call start_seq(r%g, n0, cap, m + nsteps + 1)
      associate (f => r%f%v, g => r%g%v)
         ! F(n0 - j), G(n0 + j): du_j = F(n0 - j) + G(n0 + j), s_k / K = F(n0 - k + 1) - G(n0 + k);
         ! du_0 is the top node's lower half, du_m the bottom node's upper half. The split of
         ! du_0 is free (an alternating pair F += c (-1)^m, G -= c (-1)^m changes neither du
         ! nor s): it is chosen to leave no alternating part in F (tighter bounds): c the
         ! mean of (-1)^(j-1) (F(n0 - j + 1) - F(n0 - j)) / 2.
         f(n0) = 0.5_wp * st%dub(b)
         g(n0) = st%dub(b) - f(n0)
         c = 0.0_wp
         sgn = 1.0_wp
         do j = 1, m
            g(n0 + j) = f(n0 - j + 1) - st%s(b + j) / r%k
            f(n0 - j) = st%dua(b + j) - g(n0 + j)
            c = c + sgn * (f(n0 - j + 1) - f(n0 - j))
            sgn = -sgn
         end do
         c = 0.5_wp * c / real(m, wp)
         ! (F(i) -= c (-1)^i, G(i) += c (-1)^i; i = n0 -+ j have the parity of n0 + j)
         sgn = c
         do j = 0, m
            f(n0 - j) = f(n0 - j) - sgn
            g(n0 + j) = g(n0 + j) + sgn
            sgn = -sgn
         end do
      end associate
      call blocks(r%f, m + 1)
      call blocks(r%g, m + 1)
      ! (a value not finite makes its sum not finite; a sum that overflows only stops the
      ! characteristic steps: the lattice takes over)
      r%finite = abs(sum(r%f%v(n0 - m:n0))) <= huge(1.0_wp) .and. &
                 abs(sum(r%g%v(n0:n0 + m))) <= huge(1.0_wp)
      r%s_ends = [st%s(c0), st%s(b + m)]
      r%sections = sections
      if (.not. sections) return
      r%breaks = any(st%strength(c0:b + m - 1) >= 0.0_wp)
      call start_sections(st, r, nsteps)
   end subroutine to_ring

   !> Ra, Rb and C of a ring's sections at t^n0 from st%section = S^{n0-1/2}, and, where it
   !> can break, the blocks' weakest sections C + R, -C + R.
   pure subroutine start_sections(st, r, nsteps)
      type(state_t), intent(in) :: st      !! the state
      type(ring_t), intent(inout) :: r     !! the ring (F and G set)
      integer, intent(in) :: nsteps        !! steps to make room for
      real(wp) :: c, w
      integer :: n0, m, j, i, cap, b
      n0 = r%n0
      m = r%n
      b = r%c0 - 1
      cap = m + nsteps + 2
      call start_seq(r%ra, n0 - m, cap, m + nsteps + 1)
      call start_seq(r%rb, n0 + 1, cap, m + nsteps + 1)
      associate (ra => r%ra%v, rb => r%rb%v, f => r%f%v, g => r%g%v)
         ! Ra(j) + Ra(j - 1) = K (F(j + 1) + F(j)); Rb(j) + Rb(j - 1) = -K (G(j - 1) + G(j)):
         ! each from its first value, its alternating part then removed (C takes what is
         ! left)
         ra(n0 - m) = 0.5_wp * r%k * (f(n0 - m + 1) + f(n0 - m))
         do j = n0 - m + 1, n0 - 2
            ra(j) = r%k * (f(j + 1) + f(j)) - ra(j - 1)
         end do
         c = alternating_part(ra(n0 - m:n0 - 2))
         do j = n0 - m, n0 - 2
            ra(j) = ra(j) - c
            c = -c
         end do
         rb(n0 + 1) = -0.5_wp * r%k * (g(n0) + g(n0 + 1))
         do j = n0 + 2, n0 + m - 1
            rb(j) = -r%k * (g(j - 1) + g(j)) - rb(j - 1)
         end do
         c = alternating_part(rb(n0 + 1:n0 + m - 1))
         do j = n0 + 1, n0 + m - 1
            rb(j) = rb(j) - c
            c = -c
         end do
         ! C_i = (-1)^(n0-1) (S_i^{n0-1/2} - Ra(n0 - 1 - i) - Rb(n0 + i))
         allocate(r%c(m - 1))
         w = sign_of(n0 - 1)
         do i = 1, m - 1
            r%c(i) = w * (st%section(b + i) - ra(n0 - 1 - i) - rb(n0 + i))
         end do
         r%scale = max(largest_abs(ra(n0 - m:n0 - 2)), largest_abs(rb(n0 + 1:n0 + m - 1)), &
                       largest_abs(r%c))
      end associate
      call blocks(r%ra, m - 1)
      call blocks(r%rb, m - 1)
      if (.not. r%breaks) return
      call start_seq(r%w_even, 1, m - 1, m - 1)
      call start_seq(r%w_odd, 1, m - 1, m - 1)
      do i = 1, m - 1
         w = no_break
         if (st%strength(b + i) >= 0.0_wp) w = st%strength(b + i)
         r%w_even%v(i) = merge(w + r%c(i), w, w < no_break)
         r%w_odd%v(i) = merge(w - r%c(i), w, w < no_break)
      end do
      call blocks(r%w_even, m - 1)
      call blocks(r%w_odd, m - 1)
   end subroutine start_sections

   !> The lattice arrays of a ring's interior nodes and cells at t^n (st%step) from its
   !> characteristic state (O(m)): increments, cell stresses, displacements (u^n0 plus the
   !> sums of the increments), the section stresses S^{n-1/2} where keep (the nodes whose
   !> sections advance keeps). A ring that took no step leaves them as they were.
   pure subroutine from_ring(r, st, keep, gdt2)
      type(ring_t), intent(in) :: r        !! the characteristic state
      type(state_t), intent(inout) :: st   !! the state (its junction nodes already set)
      logical, intent(in) :: keep(0:)      !! the nodes whose sections are kept
      real(wp), intent(in) :: gdt2         !! g dt^2, each step's increment of every du by
                                           !! gravity [m]
      real(wp) :: d, fall, fallen
      integer :: n, n0, m, i, b
      m = r%n
      n0 = r%n0
      n = st%step
      b = r%c0 - 1
      if (n == n0) then
         st%s(r%c0) = r%s_ends(1)
         st%s(b + m) = r%s_ends(2)
         return
      end if
      ! the running sums of F and G (made to n and n + m: end_rings): u_j^n - u_j^n0 = sum
      ! over k = n0+1..n of F(k - j) + G(k + j); gravity's part (k - n0) g dt^2 in du^k, its
      ! sum over k = n0+1..n in u^n (node_now: the same expressions for one node)
      fall = real(n - n0, wp) * gdt2
      fallen = 0.5_wp * real(n - n0, wp) * real(n - n0 + 1, wp) * gdt2
      associate (cf => r%f%p, cg => r%g%p)
         do i = 1, m - 1
            d = (cf(n - i) - cf(n0 - i)) + (cg(n + i) - cg(n0 + i)) + fallen
            st%ua(b + i) = st%ua(b + i) + d
            st%ub(b + i) = st%ub(b + i) + d
            st%dua(b + i) = r%f%v(n - i) + r%g%v(n + i) + fall
            st%dub(b + i) = st%dua(b + i)
         end do
      end associate
      ! (cell_stress of every cell, written out: the loop vectorises)
      do i = 1, m
         st%s(b + i) = r%k * (r%f%v(n - i + 1) - r%g%v(n + i))
      end do
      if (.not. r%sections) return
      d = sign_of(n - 1)
      if (all(keep(b + 1:b + m - 1))) then
         ! (every section kept, as where some node can break: one pass without tests)
         do i = 1, m - 1
            st%section(b + i) = r%ra%v(n - 1 - i) + r%rb%v(n + i) + d * r%c(i)
         end do
         return
      end if
      do i = 1, m - 1
         if (keep(b + i)) st%section(b + i) = r%ra%v(n - 1 - i) + r%rb%v(n + i) + d * r%c(i)
      end do
   end subroutine from_ring

   !> The smallest value of sx X(n - p + cx) + sy Y(n + p + cy) + W(p) over positions p of
   !> block b of level l within p0..p1 that lies below thr (best: the smallest found, or
   !> kept), evaluated one by one only in the finest blocks whose bound lies below thr. At
   !> the top level (l = number of levels) every block is looked at.
   pure recursive subroutine descend(x, sx, cx, y, sy, cy, n, l, p0, p1, thr, best, w, b)
      type(seq_t), intent(in) :: x         !! the first sequence
      real(wp), intent(in) :: sx           !! its sign (1 or -1)
      integer, intent(in) :: cx            !! its index offset
      type(seq_t), intent(in) :: y         !! the second sequence
      real(wp), intent(in) :: sy           !! its sign (1 or -1)
      integer, intent(in) :: cy            !! its index offset
      integer, intent(in) :: n             !! the step index
      integer, intent(in) :: l             !! the level
      integer, intent(in) :: p0            !! first position
      integer, intent(in) :: p1            !! last position
      real(wp), intent(in) :: thr          !! the threshold
      real(wp), intent(inout) :: best      !! the smallest value below thr found
      type(seq_t), intent(in), optional :: w   !! the static part by position (absent: 0)
      integer, intent(in), optional :: b   !! the block (absent: all blocks of level l)
      integer :: bs, a, e, p, c, nb
      real(wp) :: bound, val
      bs = shiftl(leaf, fan_bits * (l - 1))
      if (.not. present(b)) then
         ! the whole range's bound first: most steps no value comes near thr
         bound = extremum(x, sx, l, n - p1 + cx, n - p0 + cx) + extremum(y, sy, l, n + p0 + cy, &
                                                                          n + p1 + cy)
         nb = (p1 - 1) / bs + 1
         if (present(w)) then
            ! (a plain loop, as in extremum: a helper procedure here cost 1.7 % of a sweep)
            val = w%lev(l)%mn(0)
            do c = 1, nb - 1
               val = min(val, w%lev(l)%mn(c))
            end do
            bound = bound + val
         end if
         if (.not. bound < thr) return
         do c = 0, nb - 1
            call descend(x, sx, cx, y, sy, cy, n, l, p0, p1, thr, best, w, c)
         end do
         return
      end if
      a = max(p0, 1 + b * bs)
      e = min(p1, (b + 1) * bs)
      if (a > e) return
      bound = extremum(x, sx, l, n - e + cx, n - a + cx) + extremum(y, sy, l, n + a + cy, &
                                                                     n + e + cy)
      if (present(w)) bound = bound + w%lev(l)%mn(b)
      if (.not. bound < thr) return
      if (l == 1) then
         do p = a, e
            val = sx * x%v(n - p + cx) + sy * y%v(n + p + cy)
            if (present(w)) val = val + w%v(p)
            if (val < thr) best = min(best, val)
         end do
      else
         do c = b * fan, b * fan + fan - 1
            call descend(x, sx, cx, y, sy, cy, n, l - 1, p0, p1, thr, best, w, c)
         end do
      end if
   end subroutine descend

   !> The smallest of s v(j) over j = ja..jb, bounded by the blocks of level l that hold them.
   pure real(wp) function extremum(x, s, l, ja, jb) result(m)
      type(seq_t), intent(in) :: x         !! the sequence
      real(wp), intent(in) :: s            !! its sign (1 or -1)
      integer, intent(in) :: l             !! the level
      integer, intent(in) :: ja            !! first index
      integer, intent(in) :: jb            !! last index
      integer :: sh, ba, bb, b, lx
      ! (ja >= lo: a shift divides by the block size)
      lx = min(l, x%nl)
      sh = leaf_bits + fan_bits * (lx - 1)
      ba = shiftr(ja - x%lo, sh)
      bb = shiftr(jb - x%lo, sh)
      ! a plain loop, not minval (whose NaN handling costs more than the few blocks' values:
      ! the sequences are finite, advance_rings stops before a value that is not)
      associate (lv => x%lev(lx))
         if (s > 0.0_wp) then
            m = lv%mn(ba)
            do b = ba + 1, bb
               m = min(m, lv%mn(b))
            end do
         else
            m = lv%mx(ba)
            do b = ba + 1, bb
               m = max(m, lv%mx(b))
            end do
            m = -m
         end if
      end associate
   end function extremum

   !> The largest |v| and 0 (a plain loop, which vectorises: maxval's handling of NaN does
   !> not, and a ring's values are finite where they are used).
   pure real(wp) function largest_abs(v) result(m)
      real(wp), intent(in) :: v(:)         !! the values
      integer :: j
      m = 0.0_wp
      do j = 1, size(v)
         m = max(m, abs(v(j)))
      end do
   end function largest_abs

   !> The levels of blocks (leaf, leaf fan, ...) up to the first whose block holds span
   !> positions.
   pure integer function levels(span) result(nl)
      integer, intent(in) :: span          !! positions
      integer :: bs
      nl = 1
      bs = leaf
      do while (bs * fan < span)
         nl = nl + 1
         bs = bs * fan
      end do
   end function levels

   !> An empty sequence from index lo with room for cap values, blocks over span values.
   pure subroutine start_seq(x, lo, cap, span)
      type(seq_t), intent(out) :: x        !! the sequence
      integer, intent(in) :: lo            !! its first index
      integer, intent(in) :: cap           !! values it may hold
      integer, intent(in) :: span          !! positions the blocks must cover
      integer :: nl, l, bs
      x%lo = lo
      x%hi = lo - 1
      allocate(x%v(lo:lo + cap - 1))
      nl = levels(span)
      allocate(x%lev(nl))
      x%nl = nl
      bs = leaf
      do l = 1, nl
         allocate(x%lev(l)%mn(0:cap / bs + 1), x%lev(l)%mx(0:cap / bs + 1))
         bs = bs * fan
      end do
   end subroutine start_seq

   !> Append v(hi + 1) = val, keeping the extrema of the blocks that hold it (block sizes
   !> are powers of two: leaf 2^6, fan 2^3).
   pure subroutine push(x, val)
      type(seq_t), intent(inout) :: x      !! the sequence
      real(wp), intent(in) :: val          !! the value
      integer :: l, o, b, sh
      x%hi = x%hi + 1
      x%v(x%hi) = val
      o = x%hi - x%lo
      sh = leaf_bits
      do l = 1, x%nl
         b = shiftr(o, sh)
         if (iand(o, shiftl(1, sh) - 1) == 0) then
            x%lev(l)%mn(b) = val
            x%lev(l)%mx(b) = val
         else if (val >= x%lev(l)%mn(b) .and. val <= x%lev(l)%mx(b)) then
            ! within this block's extrema, so within those of the blocks above that hold
            ! it (none of which starts here, since this one does not)
            exit
         else
            x%lev(l)%mn(b) = min(x%lev(l)%mn(b), val)
            x%lev(l)%mx(b) = max(x%lev(l)%mx(b), val)
         end if
         sh = sh + fan_bits
      end do
   end subroutine push

   !> The running sums of a sequence (F and G: seq_t p) up to index j (<= hi), those not yet
   !> made (their room made at the first call): the same additions in the same order
   !> whenever they are made.
   pure subroutine sums_to(x, j)
      type(seq_t), intent(inout) :: x      !! the sequence
      integer, intent(in) :: j             !! the last index wanted
      if (.not. allocated(x%p)) then
         allocate(x%p(lbound(x%v, 1):ubound(x%v, 1)))
         x%p(x%lo) = x%v(x%lo)
         x%p_hi = x%lo
      end if
      if (j <= x%p_hi) return
      call running_sums(j - x%p_hi, x%v(x%p_hi + 1:j), x%p(x%p_hi:j))
      x%p_hi = j
   end subroutine sums_to

   !> p(k) = p(k - 1) + v(k), k = 1..m, from p(0) (explicit shapes: the compiler keeps the
   !> arrays' addresses in registers, which it does not through the sequence's components).
   pure subroutine running_sums(m, v, p)
      integer, intent(in) :: m             !! values to add
      real(wp), intent(in) :: v(m)         !! the values
      real(wp), intent(inout) :: p(0:m)    !! p(0) given, p(1..m) made
      integer :: k
      do k = 1, m
         p(k) = p(k - 1) + v(k)
      end do
   end subroutine running_sums

   !> The first nv values of an empty sequence, written in x%v, taken in (as many pushes:
   !> the blocks' extrema made level by level from the one below, O(nv)).
   pure subroutine blocks(x, nv)
      type(seq_t), intent(inout) :: x      !! the sequence (its values written, hi not yet)
      integer, intent(in) :: nv            !! how many
      integer :: l, nb, b, a, e, j
      real(wp) :: mn, mx
      x%hi = x%lo + nv - 1
      if (nv <= 0) return
      nb = (nv - 1) / leaf + 1
      do b = 0, nb - 1
         a = x%lo + b * leaf
         e = min(x%hi, a + leaf - 1)
         ! both extrema in one pass (a bound's zero may take either sign: it is only
         ! compared and added)
         mn = x%v(a)
         mx = x%v(a)
         do j = a + 1, e
            mn = min(mn, x%v(j))
            mx = max(mx, x%v(j))
         end do
         x%lev(1)%mn(b) = mn
         x%lev(1)%mx(b) = mx
      end do
      do l = 2, size(x%lev)
         e = nb - 1
         nb = (nb - 1) / fan + 1
         do b = 0, nb - 1
            a = b * fan
            x%lev(l)%mn(b) = minval(x%lev(l - 1)%mn(a:min(e, a + fan - 1)))
            x%lev(l)%mx(b) = maxval(x%lev(l - 1)%mx(a:min(e, a + fan - 1)))
         end do
      end do
   end subroutine blocks

   !> The alternating part c of a sequence v(j) (c (-1)^j), estimated as the mean of
   !> (-1)^j (v(j) - v(j + 1)) / 2: a sequence with a smooth part keeps it, c is removed.
   pure real(wp) function alternating_part(v) result(c)
      real(wp), intent(in) :: v(:)         !! the sequence (its first value at an index of
                                           !! the parity its caller applies c with)
      integer :: j, m
      real(wp) :: sgn
      m = size(v) - 1
      c = 0.0_wp
      if (m < 1) return
      sgn = 1.0_wp
      do j = 1, m
         c = c + sgn * (v(j) - v(j + 1))
         sgn = -sgn
      end do
      c = 0.5_wp * c / real(m, wp)
   end function alternating_part

   !> (-1)^m for any integer m.
   pure real(wp) function sign_of(m)
      integer, intent(in) :: m             !! the exponent
      sign_of = 1.0_wp - 2.0_wp * real(iand(m, 1), wp)   ! (two's complement: odd m, low bit 1)
   end function sign_of
   include 'spb_section_form_a.inc'
end module spb_ring
