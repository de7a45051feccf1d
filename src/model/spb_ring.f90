!> Characteristic stepping of an intact homogeneous bar (doc/method.md, "Characteristic
!> stepping of intact stretches (issue 36)").
!>
!> With dx = a dt the compact update (2.3) of a stretch of equal cells is an exact shift:
!> du_i^n = F(n - i) + G(n + i) and s_k^n = K (F(n - k + 1) - G(n + k)), K = E A / dx. A
!> step writes one new F at the top face and one new G at the bottom face, found by the
!> lattice's own end-node update (loads, supports, the ledger: spb_step); every other value
!> only moves. The section stresses (3.1)-(3.2) of a homogeneous stretch without gravity
!> obey S_i^{n+1/2} + S_i^{n-1/2} = s_i^n + s_{i+1}^n, which the same shift carries:
!> S_i^{n+1/2} = Ra(n - i) + Rb(n + i + 1) + (-1)^n C_i, two more characteristic sequences
!> and one constant per node. The fracture test is bounded by block extrema of Ra and Rb
!> (blocks of 64 values, levels of 8 blocks) and each block's weakest section (C and the
!> strengths, found once), and evaluated node by node only where that bound reaches the
!> strength; advance_rings stops before any step in which a node could break, with the
!> lattice arrays rebuilt, so that the whole step (spb_sim sim_step) takes it as always.
module spb_ring
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_load, only: load_t
   use spb_state, only: state_t
   use spb_ends, only: face_step_t, face_top, face_bottom, has_base, is_striker
   use spb_problem, only: end_free, end_fixed
   use spb_step, only: end_stresses, step_load_integral, hold_end, book_end_nodes
   implicit none
   private
   public :: ring_qualifies, advance_rings, ring_span_max

   integer, parameter :: leaf = 64   !! values per finest block
   integer, parameter :: fan = 8     !! blocks of one level per block of the next
   !> A node whose section stress from the characteristic sequences comes within this share
   !> of the stress scale of its strength stops the characteristic steps: the lattice's own
   !> section stress differs from it by round-off only (~1e-13 of the scale) [-]
   real(wp), parameter :: guard_share = 1.0e-9_wp
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
      real(wp), allocatable :: v(:)             !! (lo:lo+capacity-1)
      type(level_t), allocatable :: lev(:)      !! the levels of blocks
   end type seq_t

   !> The characteristic state of the bar between the conversions.
   type :: ring_t
      integer :: n = 0                !! cells
      integer :: n0 = 0               !! step of the conversion
      real(wp) :: k = 0.0_wp          !! E A / dx of the cells [Pa/m A]
      type(seq_t) :: f                !! F: du_i^n = F(n - i) + G(n + i) [m]
      type(seq_t) :: g                !! G [m]
      type(seq_t) :: ra               !! Ra: S_i^{n+1/2} = Ra(n - i) + Rb(n + i + 1) + ... [Pa]
      type(seq_t) :: rb               !! Rb [Pa]
      real(wp), allocatable :: c(:)   !! (1:n-1) C_i of the sections [Pa]
      type(seq_t) :: w_even           !! (1:n-1) C_i + R_i (a step from an even n) [Pa]
      type(seq_t) :: w_odd            !! (1:n-1) -C_i + R_i [Pa]
      real(wp) :: scale = 0.0_wp      !! largest |Ra|, |Rb|, |C| seen [Pa]
   end type ring_t

contains

   !> Whether advance_rings may stand in for whole steps (advance, contact_step,
   !> fracture_step) of this bar: one material and cross-section (every cell's mass, impedance
   !> and stiffness the same), no gravity, free or fixed ends with no base, striking mass or
   !> landing, every node joined, some breakable, none by a cohesive crack or a damage
   !> integral, the half-mass model. Breakable nodes are allowed: the steps stop before one
   !> could break.
   pure logical function ring_qualifies(mesh, st, g)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer :: j, k
      ring_qualifies = .false.
      if (mesh%n < 2 .or. abs(g) > 0.0_wp .or. mesh%full_mass) return
      if (st%n_split /= 0 .or. st%n_breakable == 0 .or. st%fm%n_cut /= 0 .or. st%n_skip /= 0) return
      if (st%coh%on .or. st%dmg%on) return
      if (any(has_base(st%ends) .or. is_striker(st%ends)) .or. any(st%ends%landing)) return
      if (.not. all(st%ends%kind == end_free .or. st%ends%kind == end_fixed)) return
      do j = 1, mesh%nseg
         k = mesh%first(j)
         if (abs(mesh%dm(k) - mesh%dm(1)) > 0.0_wp .or. abs(mesh%z(k) - mesh%z(1)) > 0.0_wp .or. &
             abs(mesh%stiff(k) - mesh%stiff(1)) > 0.0_wp) return
      end do
      ring_qualifies = .true.
   end function ring_qualifies

   !> The most steps one call of advance_rings takes for a bar of n cells: its arrays hold
   !> n + steps values per sequence.
   pure integer function ring_span_max(n)
      integer, intent(in) :: n             !! cells
      ring_span_max = n + 4096
   end function ring_span_max

   !> Up to nsteps whole steps of a bar that ring_qualifies, in characteristic form: the
   !> lattice arrays are converted once (O(n)), each step costs O(1) at the faces and in the
   !> bounded fracture test, and the arrays are rebuilt at the end (O(n)). It stops before a
   !> step in which some node could break (taken < nsteps). The end nodes' bookkeeping
   !> (book_end_nodes: ledger, support sections) is made step by step as advance makes it.
   !> s_old is not kept (as advance_joined): the caller ends with an ordinary step.
   pure subroutine advance_rings(mesh, load, g, st, nsteps, taken, max_sec_bottom, face_du)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2] (0)
      type(state_t), intent(inout) :: st   !! the state
      integer, intent(in) :: nsteps        !! steps to take at most (<= ring_span_max)
      integer, intent(out) :: taken        !! steps taken
      real(wp), intent(out) :: max_sec_bottom   !! largest sec(n) of these steps [Pa]
      real(wp), intent(out) :: face_du(2, nsteps)   !! increments of the face halves (B_0,
                                                    !! A_n) of each step [m]
      type(ring_t) :: r
      type(face_step_t) :: fs(2)
      real(wp) :: du0, dun, s1, sn, dt2, guard, best, a, b, thr
      integer :: n, nc, t, lv
      logical :: stop_now

      nc = mesh%n
      dt2 = mesh%dt * mesh%dt
      taken = 0
      max_sec_bottom = -huge(1.0_wp)
      face_du = 0.0_wp
      call to_rings(mesh, st, nsteps, r)
      lv = size(r%w_even%lev)
      do t = 1, nsteps
         n = r%n0 + t - 1
         ! the sequences' values S^{n+1/2} needs: Ra(n - 1), Rb(n + nc)
         a = r%k * (r%f%v(n) + r%f%v(n - 1))
         call push(r%ra, a - r%ra%v(n - 2))
         b = -r%k * (r%g%v(n + nc - 1) + r%g%v(n + nc))
         call push(r%rb, b - r%rb%v(n + nc - 1))
         r%scale = max(r%scale, abs(r%ra%v(n - 1)), abs(r%rb%v(n + nc)))
         ! (3.3) bounded: could some node's S^{n+1/2} < -R - eps? Then the lattice takes it.
         guard = guard_share * max(r%scale, st%s_scale)
         best = no_break
         if (modulo(n, 2) == 0) then
            call descend(r%ra, 1.0_wp, 0, r%rb, 1.0_wp, 1, n, lv, 1, nc - 1, guard, best, r%w_even)
         else
            call descend(r%ra, 1.0_wp, 0, r%rb, 1.0_wp, 1, n, lv, 1, nc - 1, guard, best, r%w_odd)
         end if
         stop_now = best < guard
         if (stop_now) exit
         ! the end nodes, as advance takes them: end stresses, (2.3)1-2, supports, booking
         du0 = r%f%v(n) + r%g%v(n)
         dun = r%f%v(n - nc) + r%g%v(n + nc)
         s1 = r%k * (r%f%v(n) - r%g%v(n + 1))
         sn = r%k * (r%f%v(n - nc + 1) - r%g%v(n + nc))
         st%dua(0) = du0
         st%dub(0) = du0
         st%dua(nc) = dun
         st%dub(nc) = dun
         call end_stresses(mesh, load, st, fs(face_top)%s, fs(face_bottom)%s, step=n)
         fs(face_top)%q = step_load_integral(load, n, mesh%dt, face_top)
         fs(face_bottom)%q = step_load_integral(load, n, mesh%dt, face_bottom)
         fs%rho = 0.0_wp
         fs(face_top)%du_old = du0
         fs(face_bottom)%du_old = dun
         st%s(0) = fs(face_top)%s
         st%s(nc + 1) = fs(face_bottom)%s
         st%dua(0) = du0 + (st%s(0) - s1) * mesh%inv_m(0) * dt2
         st%dub(0) = st%dua(0)
         st%dua(nc) = dun + (sn - st%s(nc + 1)) * mesh%inv_m(nc) * dt2
         st%dub(nc) = st%dua(nc)
         call hold_end(mesh, st, face_top, fs(face_top))
         call hold_end(mesh, st, face_bottom, fs(face_bottom))
         fs(face_top)%s_cell = s1
         fs(face_bottom)%s_cell = sn
         call book_end_nodes(mesh, g, st, fs)
         max_sec_bottom = max(max_sec_bottom, st%section(nc))
         face_du(:, t) = fs%du
         ! the new values at the faces: du_0^{n+1} = F(n+1) + G(n+1), du_n^{n+1} = ...
         call push(r%f, st%dub(0) - r%g%v(n + 1))
         call push(r%g, st%dua(nc) - r%f%v(n + 1 - nc))
         ! fracture_step's largest stress magnitude, |s^{n+1}| and the bottom support's
         st%s_scale = max(st%s_scale, abs(st%section(nc)))
         thr = -(st%s_scale / r%k) * (1.0_wp + scale_share)
         best = no_break
         call descend(r%f, 1.0_wp, 1, r%g, -1.0_wp, 0, n + 1, size(r%f%lev), 1, nc, thr, best)
         call descend(r%f, -1.0_wp, 1, r%g, 1.0_wp, 0, n + 1, size(r%f%lev), 1, nc, thr, best)
         if (best < no_break) st%s_scale = max(st%s_scale, -r%k * best)
         taken = t
      end do
      if (taken > 0) call from_rings(r, taken, st)
   end subroutine advance_rings

   !> The characteristic state of the lattice arrays at t^n0 (O(n)), with room for nsteps.
   pure subroutine to_rings(mesh, st, nsteps, r)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state (intact, joined)
      integer, intent(in) :: nsteps        !! steps to make room for
      type(ring_t), intent(out) :: r       !! its characteristic form
      real(wp) :: fv(0:mesh%n), gv(0:mesh%n), c, sgn
      integer :: n0, nc, i, cap
      nc = mesh%n
      n0 = st%step
      r%n = nc
      r%n0 = n0
      r%k = mesh%stiff(1)
      cap = nc + nsteps + 2
      ! F(n0 - i) = fv(i), G(n0 + i) = gv(i): du_i = fv(i) + gv(i), s_k / K = fv(k-1) - gv(k).
      ! The split of du_0 is free (an alternating pair F += c (-1)^m, G -= c (-1)^m changes
      ! neither du nor s): it is chosen to leave no alternating part in F (tighter bounds).
      fv(0) = 0.5_wp * st%dua(0)
      gv(0) = st%dua(0) - fv(0)
      do i = 1, nc
         gv(i) = fv(i - 1) - st%s(i) / r%k
         fv(i) = st%dua(i) - gv(i)
      end do
      ! (F(m) -= c (-1)^m, G(m) += c (-1)^m; m = n0 -+ i have the parity of n0 + i)
      c = alternating_part(fv)
      do i = 0, nc
         sgn = sign_of(i)
         fv(i) = fv(i) - c * sgn
         gv(i) = gv(i) + c * sgn
      end do
      call start_seq(r%f, n0 - nc, cap, nc + nsteps + 1)
      do i = nc, 0, -1
         call push(r%f, fv(i))
      end do
      call start_seq(r%g, n0, cap, nc + nsteps + 1)
      do i = 0, nc
         call push(r%g, gv(i))
      end do
      call start_sections(st, r, nsteps)
   end subroutine to_rings

   !> Ra, Rb and C of the sections at t^n0 from st%section = S^{n0-1/2}, and the blocks'
   !> weakest sections C + R, -C + R.
   pure subroutine start_sections(st, r, nsteps)
      type(state_t), intent(in) :: st      !! the state
      type(ring_t), intent(inout) :: r     !! the rings (F and G set)
      integer, intent(in) :: nsteps        !! steps to make room for
      real(wp) :: ra(r%n0 - r%n:r%n0 - 2), rb(r%n0 + 1:r%n0 + r%n - 1), c, w
      integer :: n0, nc, j, i, cap
      n0 = r%n0
      nc = r%n
      cap = nc + nsteps + 2
      ! Ra(j) + Ra(j - 1) = K (F(j + 1) + F(j)); Rb(j) + Rb(j - 1) = -K (G(j - 1) + G(j)):
      ! each from its first value, its alternating part then removed (C takes what is left)
      ra(n0 - nc) = 0.5_wp * r%k * (r%f%v(n0 - nc + 1) + r%f%v(n0 - nc))
      do j = n0 - nc + 1, n0 - 2
         ra(j) = r%k * (r%f%v(j + 1) + r%f%v(j)) - ra(j - 1)
      end do
      c = alternating_part(ra)
      do j = n0 - nc, n0 - 2
         ra(j) = ra(j) - c * sign_of(j - (n0 - nc))
      end do
      rb(n0 + 1) = -0.5_wp * r%k * (r%g%v(n0) + r%g%v(n0 + 1))
      do j = n0 + 2, n0 + nc - 1
         rb(j) = -r%k * (r%g%v(j - 1) + r%g%v(j)) - rb(j - 1)
      end do
      c = alternating_part(rb)
      do j = n0 + 1, n0 + nc - 1
         rb(j) = rb(j) - c * sign_of(j - (n0 + 1))
      end do
      call start_seq(r%ra, n0 - nc, cap, nc + nsteps + 1)
      do j = n0 - nc, n0 - 2
         call push(r%ra, ra(j))
      end do
      call start_seq(r%rb, n0 + 1, cap, nc + nsteps + 1)
      do j = n0 + 1, n0 + nc - 1
         call push(r%rb, rb(j))
      end do
      ! C_i = (-1)^(n0-1) (S_i^{n0-1/2} - Ra(n0 - 1 - i) - Rb(n0 + i))
      allocate(r%c(nc - 1))
      call start_seq(r%w_even, 1, nc - 1, nc - 1)
      call start_seq(r%w_odd, 1, nc - 1, nc - 1)
      r%scale = max(maxval(abs(ra)), maxval(abs(rb)), 0.0_wp)
      do i = 1, nc - 1
         r%c(i) = sign_of(n0 - 1) * (st%section(i) - ra(n0 - 1 - i) - rb(n0 + i))
         r%scale = max(r%scale, abs(r%c(i)))
         w = no_break
         if (st%strength(i) >= 0.0_wp) w = st%strength(i)
         call push(r%w_even, merge(w + r%c(i), w, w < no_break))
         call push(r%w_odd, merge(w - r%c(i), w, w < no_break))
      end do
   end subroutine start_sections

   !> The lattice arrays at t^(n0 + taken) from the characteristic state (O(n)): increments,
   !> cell stresses, displacements (u^n0 plus the sums of the increments), the section
   !> stresses S^{n-1/2} (every interior node: the bar has breakable ones).
   pure subroutine from_rings(r, taken, st)
      type(ring_t), intent(in) :: r        !! the characteristic state
      integer, intent(in) :: taken         !! steps taken since the conversion
      type(state_t), intent(inout) :: st   !! the state (its end nodes already set)
      real(wp), allocatable :: cf(:), cg(:)
      real(wp) :: d
      integer :: n, n0, nc, i, j
      nc = r%n
      n0 = r%n0
      n = n0 + taken
      ! running sums of F and G: u_i^n - u_i^n0 = sum over m = n0+1..n of F(m - i) + G(m + i)
      allocate(cf(n0 - nc:n), cg(n0:n + nc))
      cf(n0 - nc) = r%f%v(n0 - nc)
      do j = n0 - nc + 1, n
         cf(j) = cf(j - 1) + r%f%v(j)
      end do
      cg(n0) = r%g%v(n0)
      do j = n0 + 1, n + nc
         cg(j) = cg(j - 1) + r%g%v(j)
      end do
      do i = 0, nc
         d = (cf(n - i) - cf(n0 - i)) + (cg(n + i) - cg(n0 + i))
         st%ua(i) = st%ua(i) + d
         st%ub(i) = st%ub(i) + d
      end do
      do i = 1, nc - 1
         st%dua(i) = r%f%v(n - i) + r%g%v(n + i)
         st%dub(i) = st%dua(i)
      end do
      do i = 1, nc
         st%s(i) = r%k * (r%f%v(n - i + 1) - r%g%v(n + i))
      end do
      do i = 1, nc - 1
         st%section(i) = r%ra%v(n - 1 - i) + r%rb%v(n + i) + sign_of(n - 1) * r%c(i)
      end do
      st%step = n
      st%n_skip = 0
   end subroutine from_rings

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
      bs = leaf * fan**(l - 1)
      if (.not. present(b)) then
         nb = (p1 - 1) / bs + 1
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
      integer :: bs, ba, bb
      bs = leaf * fan**(min(l, size(x%lev)) - 1)
      ba = (ja - x%lo) / bs
      bb = (jb - x%lo) / bs
      associate (lv => x%lev(min(l, size(x%lev))))
         if (s > 0.0_wp) then
            m = minval(lv%mn(ba:bb))
         else
            m = -maxval(lv%mx(ba:bb))
         end if
      end associate
   end function extremum

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
      nl = 1
      bs = leaf
      do while (bs * fan < span)
         nl = nl + 1
         bs = bs * fan
      end do
      allocate(x%lev(nl))
      bs = leaf
      do l = 1, nl
         allocate(x%lev(l)%mn(0:cap / bs + 1), x%lev(l)%mx(0:cap / bs + 1))
         bs = bs * fan
      end do
   end subroutine start_seq

   !> Append v(hi + 1) = val, keeping the extrema of the blocks that hold it.
   pure subroutine push(x, val)
      type(seq_t), intent(inout) :: x      !! the sequence
      real(wp), intent(in) :: val          !! the value
      integer :: l, o, bs, b
      x%hi = x%hi + 1
      x%v(x%hi) = val
      o = x%hi - x%lo
      bs = leaf
      do l = 1, size(x%lev)
         b = o / bs
         if (o - b * bs == 0) then
            x%lev(l)%mn(b) = val
            x%lev(l)%mx(b) = val
         else
            x%lev(l)%mn(b) = min(x%lev(l)%mn(b), val)
            x%lev(l)%mx(b) = max(x%lev(l)%mx(b), val)
         end if
         bs = bs * fan
      end do
   end subroutine push

   !> The alternating part c of a sequence v(j) (c (-1)^j), estimated as the mean of
   !> (-1)^j (v(j) - v(j + 1)) / 2: a sequence with a smooth part keeps it, c is removed.
   pure real(wp) function alternating_part(v) result(c)
      real(wp), intent(in) :: v(:)         !! the sequence (its first value at an index of
                                           !! the parity its caller applies c with)
      integer :: j, m
      m = size(v) - 1
      c = 0.0_wp
      if (m < 1) return
      do j = 1, m
         c = c + sign_of(j - 1) * (v(j) - v(j + 1))
      end do
      c = 0.5_wp * c / real(m, wp)
   end function alternating_part

   !> (-1)^m for any integer m.
   pure real(wp) function sign_of(m)
      integer, intent(in) :: m             !! the exponent
      sign_of = merge(1.0_wp, -1.0_wp, modulo(m, 2) == 0)
   end function sign_of
end module spb_ring
