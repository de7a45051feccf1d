!> The continuum energy a lattice state represents, and its zig-zag Jordan amplitude
!> (METHOD.md §8; doc/method.md, "Wave energy").
!>
!> At dx = a dt the lattice reproduces at its nodes every solution u = F(t - x/a) + G(t + x/a)
!> of each cell (plus g t^2/2 under gravity). A lattice state at t^{n+1} (cell stresses
!> s^{n+1}, increments du^{n+1}) is read as the characteristic intervals of every cell: f_k
!> (the down-going wave's rise over one step) and g_k (the up-going one's), with
!>    cell k:         Z_k (f_k - g_k) = s_k dt
!>    joined node i:  m_i du_i / dt   = Z_{i+1} f_{i+1} + Z_i g_i
!>    free top face:  m du / dt       = Z f - I/2      (I: integral of the face load over the step)
!>    free bottom:    m du / dt       = Z g + I/2
!> (a held or transmitting end gives no equation). The energy of that continuum state,
!>    E = sum_k Z_k (f_k^2 + g_k^2) / dt  =  integral of rho v^2/2 + sigma^2/(2E),
!> is non-negative, zero only at rest or in rigid motion, and conserved exactly by the intact
!> scheme (g = 0, no load). A fragment with two free faces has one equation more than
!> unknowns: their compatibility residual
!>    J = sum_i (-1)^(i - top) (m_i du_i / dt + s_i dt)   (s_i: the cell above node i)
!> minus the load terms is the amplitude along the Jordan partner of the zig-zag mode (it
!> grows linearly when not zero) and must stay at round-off. A fragment held at both ends
!> has one unknown more than equations (the zig-zag standing wave with nodes at every node):
!> the smallest energy is taken. Under gravity E + e_pot - (g dt / 2) sum_f J'_f (J' the same
!> alternating sum with the loads) is the exactly conserved total (checked for every
!> combination of held and free ends, homogeneous and layered).
module spb_wave
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t, end_free, end_base, end_fixed, end_transmit
   use spb_state, only: state_t
   implicit none
   private
   public :: wave_t, wave_energy, fragment_wave, fragment_characteristics, region_wave

   !> The whole bar's wave energy and the largest Jordan amplitude of its fragments.
   type :: wave_t
      real(wp) :: e_wave = 0.0_wp      !! sum of the fragments' continuum energies [J/m^2]
      real(wp) :: e_gravity = 0.0_wp   !! -(g dt/2) sum_f J'_f: with e_pot the exact gravity
                                       !! energy of the lattice [J/m^2]
      real(wp) :: jordan = 0.0_wp      !! largest |J| over the fragments / the bar's momentum
                                       !! scale (sum of |m du/dt| and |s dt| over the nodes) [-]
      real(wp) :: jordan_abs = 0.0_wp  !! largest |J| [kg/(m s)]
      real(wp) :: momentum_scale = 0.0_wp  !! the bar's momentum scale (the sum above) [kg/(m s)]
   end type wave_t

contains

   !> Wave energy of the bar at t^{n+1} = st%step dt. i_top, i_bot: integrals of the load on the
   !> top and bottom faces over the step just taken [Pa s] (0 where no load acts there).
   pure function wave_energy(mesh, st, g, i_top, i_bot) result(w)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g        !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      type(wave_t) :: w
      real(wp) :: e, jp, jr, ja, total
      integer :: c, top, bot
      total = 0.0_wp
      top = 0
      do c = 1, st%n_split + 1
         if (c <= st%n_split) then
            bot = st%split(c)
         else
            bot = mesh%n
         end if
         if (top > 0 .and. bot < mesh%n .and. bot > top) then
            call inner_wave(mesh, st, top, bot, .true., e, jp, jr, ja)
         else
            call fragment_wave(mesh, st, top, bot, i_top, i_bot, e, jp, jr, ja)
         end if
         w%e_wave = w%e_wave + e
         w%e_gravity = w%e_gravity - 0.5_wp * g * mesh%dt * jp
         total = total + jr
         w%jordan_abs = max(w%jordan_abs, ja)
         top = bot
      end do
      w%momentum_scale = total
      if (total > 0.0_wp) w%jordan = w%jordan_abs / total
   end function wave_energy

   !> Wave energy with its gravity terms, e_wave - (g dt/2) J' + e_pot, of the fragments
   !> between the fragment boundaries top and bot (0 or a split node, n or a split node)
   !> [J/m^2]: what an event that acts there (breaks, joins, shifts) changes.
   pure real(wp) function region_wave(mesh, st, g, i_top, i_bot, top, bot) result(e_sum)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      real(wp) :: e, jp, jr, ja
      integer :: t, b, i
      ! gravity potential at mid-step, -g m (u^n + u^{n+1})/2, of the halves the region owns
      ! (node by node, upper half then lower half: the ends' halves only where the region
      ! owns them)
      e_sum = 0.0_wp
      if (top == 0) e_sum = e_sum - g * mesh%ma(top) * (st%ua(top) - 0.5_wp * st%dua(top))
      if (top < bot .or. bot == mesh%n) then
         e_sum = e_sum - g * mesh%mb(top) * (st%ub(top) - 0.5_wp * st%dub(top))
      end if
      do i = top + 1, bot - 1
         e_sum = e_sum - g * mesh%ma(i) * (st%ua(i) - 0.5_wp * st%dua(i))
         e_sum = e_sum - g * mesh%mb(i) * (st%ub(i) - 0.5_wp * st%dub(i))
      end do
      if (bot > top) then
         e_sum = e_sum - g * mesh%ma(bot) * (st%ua(bot) - 0.5_wp * st%dua(bot))
         if (bot == mesh%n) then
            e_sum = e_sum - g * mesh%mb(bot) * (st%ub(bot) - 0.5_wp * st%dub(bot))
         end if
      end if
      t = top
      do while (t < bot)
         b = t + 1
         do while (b < bot)
            if (.not. st%joined(b)) exit
            b = b + 1
         end do
         if (t > 0 .and. b < mesh%n) then
            call inner_wave(mesh, st, t, b, .false., e, jp, jr, ja)
         else
            call fragment_wave(mesh, st, t, b, i_top, i_bot, e, jp, jr, ja, scale=.false.)
         end if
         e_sum = e_sum + e - 0.5_wp * g * mesh%dt * jp
         t = b
      end do
   end function region_wave

   !> The continuum reading of one fragment, nodes top..bot (top: 0 or a split node whose
   !> lower half it owns; bot: n or a split node whose upper half it owns), at t^{n+1}.
   !> One pass without arrays (the reading of fragment_h, which tests/test_wave_energy.pf
   !> checks this against): every solution of the node equations from the top down is
   !> h_k = hd_k + beta (-1)^(bot-k), hd_k the one that starts from the top face's equation
   !> (or from 0 where the top is held); beta follows from the bottom face's equation (half
   !> of it, sharing the residual, when both faces are free; 0 when only the top is free) or,
   !> held at both ends, from the smallest energy. With A = sum (hd^2 + (hd + s dt)^2)/Z,
   !> B = sum (-1)^(bot-k) (2 hd + s dt)/Z and C = sum 1/Z the energy is
   !> (A + 2 beta B + 2 beta^2 C)/dt. B and C are summed only where beta can be other than 0,
   !> the momentum scale only when asked (scale, default .true.): the same operations in the
   !> same order otherwise (cell_sums), so the same bits.
   pure subroutine fragment_wave(mesh, st, top, bot, i_top, i_bot, e, jprime, jordan, jordan_abs, &
                                 scale)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top          !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot          !! bottom face-load integral over the step [Pa s]
      real(wp), intent(out) :: e             !! continuum energy [J/m^2]
      real(wp), intent(out) :: jprime        !! alternating sum J' with the load terms [kg/(m s)]
      real(wp), intent(out) :: jordan        !! the fragment's momentum scale, sum of |m du/dt|
                                             !! and |s dt| [kg/(m s)] (0 with scale = .false.)
      real(wp), intent(out) :: jordan_abs    !! |J| (0 unless two free faces) [kg/(m s)]
      logical, intent(in), optional :: scale   !! sum the momentum scale (default .true.)
      real(wp) :: dt, load_top, load_bot, r, hd, a, b, c, beta, d
      logical :: eq_top, eq_bot, tr_top, tr_bot, with_scale
      with_scale = .true.
      if (present(scale)) with_scale = scale
      if (top > 0 .and. bot < mesh%n .and. bot > top) then
         call inner_wave(mesh, st, top, bot, with_scale, e, jprime, jordan, jordan_abs)
         return
      end if
      dt = mesh%dt
      call face_equations(mesh, st, top, bot, i_top, i_bot, eq_top, eq_bot, load_top, load_bot, &
                          tr_top, tr_bot)
      r = node_momentum(mesh, st, top, bot, top)
      hd = 0.0_wp
      if (eq_top .and. bot > top) hd = r + load_top - st%s(top + 1) * dt
      if (tr_top .and. bot > top) hd = mesh%z(1) * st%ends%w_in_top - st%s(top + 1) * dt
      jprime = r
      jordan = 0.0_wp
      if (with_scale) jordan = abs(r)
      a = 0.0_wp
      b = 0.0_wp
      c = 0.0_wp
      ! B and C enter the energy unless beta = 0 (a free top over a held bottom)
      call cell_sums(mesh, st, top, bot, with_scale, .not. (eq_top .and. .not. eq_bot), hd, r, &
                     jprime, jordan, a, b, c)
      call face_terms(mesh, st, top, bot, eq_top, eq_bot, load_top, load_bot, jprime)
      jordan_abs = 0.0_wp
      e = 0.0_wp
      if (bot == top) return
      ! hd now holds hd_bot; d = h_bot from the bottom face's equation minus hd_bot
      d = r - load_bot - hd
      if (tr_bot) d = mesh%z(bot) * st%ends%w_in_bot - hd
      if (eq_top .and. eq_bot) then
         jordan_abs = abs(d)
         beta = 0.5_wp * d
      else if (eq_top) then
         beta = 0.0_wp
      else if (eq_bot) then
         beta = d
      else
         beta = -b / (2.0_wp * c)
      end if
      e = max(0.0_wp, a + 2.0_wp * beta * (b + beta * c)) / dt
   end subroutine fragment_wave

   !> fragment_wave of a fragment between two split nodes (0 < top < bot < n), the common
   !> case once a bar has broken up: both faces free and without load, so face_equations and
   !> face_terms reduce to what is written out here (the load terms 0 kept in the same
   !> operations: x + 0 is not x for x = -0).
   pure subroutine inner_wave(mesh, st, top, bot, with_scale, e, jprime, jordan, jordan_abs)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment, a split node
      integer, intent(in) :: bot           !! bottom node of the fragment, a split node > top
      logical, intent(in) :: with_scale    !! sum the momentum scale
      real(wp), intent(out) :: e             !! continuum energy [J/m^2]
      real(wp), intent(out) :: jprime        !! alternating sum J' [kg/(m s)]
      real(wp), intent(out) :: jordan        !! the momentum scale (0 without with_scale)
                                             !! [kg/(m s)]
      real(wp), intent(out) :: jordan_abs    !! |J| [kg/(m s)]
      real(wp), parameter :: no_load = 0.0_wp   ! load_top, load_bot of a split node's face
      real(wp) :: dt, r, hd, a, b, c, beta, d, sd, iz
      dt = mesh%dt
      ! node_momentum of the lower half of the split node top
      r = mesh%mb(top) * st%dub(top)
      r = r / dt
      hd = r + no_load - st%s(top + 1) * dt
      jprime = r
      jordan = 0.0_wp
      if (with_scale) jordan = abs(r)
      a = 0.0_wp
      b = 0.0_wp
      c = 0.0_wp
      if (bot == top + 1) then
         ! one cell (cell_sums' loop written out for it: sgn = -1, sgn_k = 1)
         sd = st%s(bot) * dt
         r = mesh%ma(bot) * st%dua(bot) / dt
         iz = 1.0_wp / mesh%z(bot)
         jprime = jprime + (-1.0_wp) * (r + sd)
         if (with_scale) jordan = jordan + abs(r) + abs(sd)
         a = a + (hd**2 + (hd + sd)**2) * iz
         b = b + 1.0_wp * (2.0_wp * hd + sd) * iz
         c = c + iz
      else
         call cell_sums(mesh, st, top, bot, with_scale, .true., hd, r, jprime, jordan, a, b, c)
      end if
      if (mod(bot - top, 2) == 1) jprime = jprime + 2.0_wp * no_load
      d = r - no_load - hd
      jordan_abs = abs(d)
      beta = 0.5_wp * d
      e = max(0.0_wp, a + 2.0_wp * beta * (b + beta * c)) / dt
   end subroutine inner_wave

   !> fragment_wave's pass over the cells top+1..bot: the same operations in the same order
   !> as the one-pass loop (node_momentum inlined), the sums in locals. On return hd is
   !> hd_bot and r the bottom node's momentum (the top node's when the fragment has no cell).
   pure subroutine cell_sums(mesh, st, top, bot, with_scale, with_bc, hd, r, jp, jr, a, b, c)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      logical, intent(in) :: with_scale    !! sum the momentum scale (jr)
      logical, intent(in) :: with_bc       !! sum B and C
      real(wp), intent(inout) :: hd        !! hd of the first cell in, hd_bot out [kg/(m s)]
      real(wp), intent(inout) :: r         !! m du/dt of the last node summed [kg/(m s)]
      real(wp), intent(inout) :: jp        !! J' so far [kg/(m s)]
      real(wp), intent(inout) :: jr        !! the momentum scale so far [kg/(m s)]
      real(wp), intent(inout) :: a         !! A so far [(kg/(m s))^2 m^2 s/kg]
      real(wp), intent(inout) :: b         !! B so far [kg/(m s) m^2 s/kg]
      real(wp), intent(inout) :: c         !! C so far [m^2 s/kg]
      real(wp) :: dt, sd, sd_next, iz, sgn, sgn_k, h, p, q, u, v, w, rk
      integer :: k, last
      dt = mesh%dt
      h = hd
      p = jp
      q = jr
      u = a
      v = b
      w = c
      rk = r
      sgn = 1.0_wp
      sgn_k = merge(1.0_wp, -1.0_wp, mod(bot - top - 1, 2) == 0)
      ! the bottom node is a whole node only at the bar's end
      last = bot
      if (bot < mesh%n) last = bot - 1
      sd_next = 0.0_wp
      if (bot > top) sd_next = st%s(top + 1) * dt
      do k = top + 1, bot
         sd = sd_next
         if (k <= last) then
            rk = (mesh%ma(k) * st%dua(k) + mesh%mb(k) * st%dub(k)) / dt
         else
            rk = mesh%ma(k) * st%dua(k) / dt    ! the upper half of a split node
         end if
         iz = 1.0_wp / mesh%z(k)
         sgn = -sgn
         p = p + sgn * (rk + sd)
         if (with_scale) q = q + abs(rk) + abs(sd)
         u = u + (h**2 + (h + sd)**2) * iz
         if (with_bc) then
            v = v + sgn_k * (2.0_wp * h + sd) * iz
            w = w + iz
         end if
         sgn_k = -sgn_k
         if (k < bot) then
            sd_next = st%s(k + 1) * dt
            h = rk - sd_next - h
         end if
      end do
      r = rk
      hd = h
      jp = p
      jr = q
      a = u
      b = v
      c = w
   end subroutine cell_sums

   !> The characteristic intervals of the fragment's cells at t^n (at_n: read from s^n and
   !> du^{n+1}; the waves that arrive at the nodes during the step) or at t^{n+1} (from
   !> s^{n+1} and du^{n+1}): f_k (down-going) and g_k (up-going) rise over one step [m].
   !> Over the step a joined node moves by 2 (Z_i f_i + Z_{i+1} g_{i+1}) / (Z_i + Z_{i+1})
   !> (t^n intervals), a free bottom face by 2 f_i, a free top face by 2 g_{i+1}.
   pure subroutine fragment_characteristics(mesh, st, top, bot, i_top, i_bot, at_n, f, g)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top          !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot          !! bottom face-load integral over the step [Pa s]
      logical, intent(in) :: at_n          !! the t^n intervals (else those at t^{n+1})
      real(wp), intent(out) :: f(top+1:)   !! down-going interval f_k of each cell [m]
      real(wp), intent(out) :: g(top+1:)   !! up-going interval g_k of each cell [m]
      real(wp) :: jp, jr, ja, h
      integer :: k
      ! h_k read into g, s_k dt into f (no temporaries), then g = h/Z, f = (h + s dt)/Z
      call fragment_h(mesh, st, top, bot, i_top, i_bot, at_n, g, f, jp, jr, ja)
      do k = top + 1, bot
         h = g(k)
         g(k) = h / mesh%z(k)
         f(k) = (h + f(k)) / mesh%z(k)
      end do
   end subroutine fragment_characteristics

   !> h_k = Z_k g_k and s_k dt of the fragment's cells, J' and the Jordan amplitude; at_n:
   !> the t^n reading (s^n; a node's equation holds the cell above), else t^{n+1} (s^{n+1};
   !> the cell below).
   pure subroutine fragment_h(mesh, st, top, bot, i_top, i_bot, at_n, h, sdt, jprime, jordan, &
                              jordan_abs)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      logical, intent(in) :: at_n          !! the t^n reading (s^n), else t^{n+1} (s^{n+1})
      real(wp), intent(out) :: h(top+1:)     !! h_k = Z_k g_k of each cell [kg/(m s)]
      real(wp), intent(out) :: sdt(top+1:)   !! s_k dt of each cell [kg/(m s)]
      real(wp), intent(out) :: jprime        !! alternating sum J' with the load terms [kg/(m s)]
      real(wp), intent(out) :: jordan        !! the fragment's momentum scale, sum of |m du/dt|
                                             !! and |s dt| [kg/(m s)]
      real(wp), intent(out) :: jordan_abs    !! |J| (0 unless two free faces) [kg/(m s)]
      real(wp) :: r(top:bot)
      real(wp) :: dt, load_top, load_bot, scale, sgn, res, alpha, num, den, h_up, h_up_bot
      logical :: eq_top, eq_bot, tr_top, tr_bot
      integer :: i, k, o

      dt = mesh%dt
      o = merge(0, 1, at_n)
      ! the fragment's node momenta over the step, m du / dt, and s dt of its cells
      do i = top, bot
         r(i) = node_momentum(mesh, st, top, bot, i)
      end do
      do k = top + 1, bot
         if (at_n) then
            sdt(k) = st%s_old(k) * dt
         else
            sdt(k) = st%s(k) * dt
         end if
      end do
      call face_equations(mesh, st, top, bot, i_top, i_bot, eq_top, eq_bot, load_top, load_bot, &
                          tr_top, tr_bot)
      ! J' = sum (-1)^(i-top) (r_i + s_i dt), s_i the cell above node i
      jprime = 0.0_wp
      scale = 0.0_wp
      sgn = 1.0_wp
      do i = top, bot
         if (i > top) then
            jprime = jprime + sgn * (r(i) + sdt(i))
            scale = scale + abs(r(i)) + abs(sdt(i))
         else
            jprime = jprime + sgn * r(i)
            scale = scale + abs(r(i))
         end if
         sgn = -sgn
      end do
      call face_terms(mesh, st, top, bot, eq_top, eq_bot, load_top, load_bot, jprime)
      jordan = scale
      jordan_abs = 0.0_wp
      if (bot == top) return
      ! h from the top face down (h_dn, held in h) and from the bottom face up (h_up, one
      ! value at a time, bottom first)
      h(top + 1) = 0.0_wp
      if (eq_top .and. at_n) h(top + 1) = r(top) - load_top
      if (eq_top .and. .not. at_n) h(top + 1) = r(top) + load_top - sdt(top + 1)
      if (tr_top .and. at_n) h(top + 1) = r(top) - mesh%z(1) * st%ends%w_in_top
      if (tr_top .and. .not. at_n) h(top + 1) = mesh%z(1) * st%ends%w_in_top - sdt(top + 1)
      do k = top + 1, bot - 1
         h(k + 1) = r(k) - sdt(k + o) - h(k)
      end do
      if (eq_bot) then
         if (tr_bot .and. at_n) then
            h_up_bot = r(bot) - mesh%z(bot) * st%ends%w_in_bot - sdt(bot)
         else if (tr_bot) then
            h_up_bot = mesh%z(bot) * st%ends%w_in_bot
         else if (at_n) then
            h_up_bot = r(bot) - sdt(bot) + load_bot
         else
            h_up_bot = r(bot) - load_bot
         end if
         if (eq_top) then
            ! two free faces: one equation too many; its residual is the Jordan amplitude,
            ! shared half and half between the two readings
            res = h(bot) - h_up_bot
            jordan_abs = abs(res)
         end if
         h_up = h_up_bot
         do k = bot, top + 1, -1
            if (k < bot) h_up = r(k) - sdt(k + o) - h_up
            if (eq_top) then
               h(k) = 0.5_wp * (h(k) + h_up)
            else
               h(k) = h_up
            end if
         end do
      else if (.not. eq_top) then
         ! held at both ends: h + alpha (-1)^k solves the node equations for any alpha; the
         ! smallest energy drops the standing zig-zag wave that no node sees
         num = 0.0_wp
         den = 0.0_wp
         sgn = 1.0_wp
         do k = top + 1, bot
            num = num + sgn * (2.0_wp * h(k) + sdt(k)) / mesh%z(k)
            den = den + 2.0_wp / mesh%z(k)
            sgn = -sgn
         end do
         alpha = -num / den
         sgn = 1.0_wp
         do k = top + 1, bot
            h(k) = h(k) + sgn * alpha
            sgn = -sgn
         end do
      end if
   end subroutine fragment_h

   !> The face loads' terms of J', and the alternating sum counted from the held end: from
   !> the bottom where only the bottom is held (the top otherwise).
   pure subroutine face_terms(mesh, st, top, bot, eq_top, eq_bot, load_top, load_bot, jprime)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      logical, intent(in) :: eq_top                  !! the top face gives an equation
      logical, intent(in) :: eq_bot                  !! the bottom face gives an equation
      real(wp), intent(in) :: load_top               !! load term of the top face [kg/(m s)]
      real(wp), intent(in) :: load_bot               !! load term of the bottom face [kg/(m s)]
      real(wp), intent(inout) :: jprime              !! J' from the nodes [kg/(m s)]
      ! Found by computing the
      ! conserved functional of the affine one-step map and checked exact (round-off) for
      ! free, top-held, bottom-held and both-held fragments of odd and even cell counts, with
      ! loads on either face; not for a transmitting end (doc/method.md)
      if (mod(bot - top, 2) == 1) jprime = jprime + 2.0_wp * load_bot
      if (eq_top .and. .not. eq_bot .and. mod(bot - top, 2) == 1) jprime = -jprime
      ! held at both ends (a fixed top, and a fixed bottom or the base) with an odd cell count:
      ! the conserved gravity term is -2 g sum w_i m_i (u_i^n + u_i^{n+1})/2 with weights
      ! w_i = (-1)^(i-top-1) (1/2 - C_i/C), C_i the compliance (sum of dt/Z) of the cells
      ! above node i (found from the affine one-step map; exact, layered included), plus the
      ! bottom node's elastic position over C (held_weights)
      if (.not. (eq_top .or. eq_bot) .and. mod(bot - top, 2) == 1 .and. top == 0 .and. &
          mesh%top == end_fixed .and. bot == mesh%n .and. (mesh%bottom == end_fixed .or. &
          (mesh%bottom == end_base .and. st%ends%base_contact))) jprime = held_weights(mesh, st, top, bot)
      if (eq_top .and. .not. eq_bot .and. mod(bot - top, 2) == 1) then
         jprime = jprime - 2.0_wp * load_top
      end if
   end subroutine face_terms

   !> (4/dt) sum_i w_i m_i (u_i - du_i/2) + (u_bot - du_bot/2)/C over the nodes of a fragment
   !> held at both ends, w_i = (-1)^(i-top-1) (1/2 - C_i/C) with C_i the compliance of the
   !> cells above node i, C = sum 1/Z of all: with -(g dt/2) in front, the exact gravity term
   !> of an odd cell count [kg/(m s)]. The positions u_i are the elastic ones, summed from the
   !> top down from the cell stresses (u_i = u_{i-1} - s_i dt/Z_i): they differ from the
   !> nodes' where a crack closed with a gap, which the dynamics does not see. The last term
   !> (the bottom node's elastic position, 0 for an intact bar on a fixed bottom; where the
   !> bar rests on the base, where its landing or the gaps it closed left it) keeps the term
   !> exact and is constant while the bar is held: it is what makes a lift-off or a break
   !> of a bar held at both ends change the measure by exactly what the g = 0 reading
   !> changes (0): without it they booked g dt u_bot / (2C), of either sign (doc/method.md).
   pure real(wp) function held_weights(mesh, st, top, bot) result(jp)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp) :: c_total, c_above, sgn, u_el
      integer :: i
      c_total = sum(1.0_wp / mesh%z(top+1:bot))
      c_above = 0.0_wp
      sgn = -1.0_wp
      jp = 0.0_wp
      u_el = st%ub(top)
      do i = top, bot
         if (i > top) then
            c_above = c_above + 1.0_wp / mesh%z(i)
            u_el = u_el - st%s(i) / mesh%stiff(i)
         end if
         jp = jp + sgn * (0.5_wp - c_above / c_total) * &
              (mesh%ma(i) * (u_el - 0.5_wp * st%dua(i)) + mesh%mb(i) * (u_el - 0.5_wp * st%dub(i)))
         sgn = -sgn
      end do
      jp = 4.0_wp / mesh%dt * jp + (u_el - 0.5_wp * st%dua(bot)) / c_total
   end function held_weights

   !> m du / dt of node i as the fragment top..bot owns it [kg/(m s)].
   pure real(wp) function node_momentum(mesh, st, top, bot, i) result(p)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      integer, intent(in) :: i             !! node
      if (i == top .and. top > 0) then
         p = mesh%mb(i) * st%dub(i)             ! the lower half of a split node
      else if (i == bot .and. bot < mesh%n) then
         p = mesh%ma(i) * st%dua(i)             ! the upper half of a split node
      else
         p = mesh%ma(i) * st%dua(i) + mesh%mb(i) * st%dub(i)
      end if
      p = p / mesh%dt
   end function node_momentum

   !> Which faces of the fragment give an equation: a free face, with the load terms -I/2 (top)
   !> and +I/2 (bottom) moved to the side of the unknowns, and a transmitting end (tr_*), where
   !> the wave that came in over the step is known (st%w_in_*): at t^{n+1} it is the interval
   !> of the end cell's incoming wave; at t^n the end node moved by it plus the end cell's
   !> outgoing interval. A held end gives none. A transmitting end is used only where the
   !> other end is not a free face: under gravity its equation lacks a term (not derived), and
   !> the free face's reading is exact there (Example 1's splinter under g).
   pure subroutine face_equations(mesh, st, top, bot, i_top, i_bot, eq_top, eq_bot, &
                                  load_top, load_bot, tr_top, tr_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      logical, intent(out) :: eq_top       !! the top face gives an equation (tr_top included)
      logical, intent(out) :: eq_bot       !! the bottom face gives an equation (tr_bot included)
      logical, intent(out) :: tr_top       !! the top face is a transmitting end that is used
      logical, intent(out) :: tr_bot       !! the bottom face is a transmitting end that is used
      real(wp), intent(out) :: load_top    !! load term of the top face, I_top/2 or 0 [kg/(m s)]
      real(wp), intent(out) :: load_bot    !! load term of the bottom face, I_bot/2 or 0 [kg/(m s)]
      load_top = 0.0_wp
      load_bot = 0.0_wp
      if (top > 0) then
         eq_top = .true.
      else
         eq_top = mesh%top == end_free
         if (eq_top) load_top = 0.5_wp * i_top
      end if
      if (bot < mesh%n) then
         eq_bot = .true.
      else
         eq_bot = mesh%bottom == end_free .or. (mesh%bottom == end_base .and. .not. st%ends%base_contact)
         if (mesh%bottom == end_free) load_bot = 0.5_wp * i_bot
      end if
      tr_top = top == 0 .and. mesh%top == end_transmit .and. .not. eq_bot
      tr_bot = bot == mesh%n .and. mesh%bottom == end_transmit .and. .not. eq_top
      eq_top = eq_top .or. tr_top
      eq_bot = eq_bot .or. tr_bot
   end subroutine face_equations
end module spb_wave
