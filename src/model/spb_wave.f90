!> The continuum energy a lattice state represents, and its zig-zag Jordan amplitude
!> (doc/method.md, "Wave energy" and "The zig-zag Jordan block at dx = a dt").
!>
!> At dx = a dt the lattice reproduces at its nodes every solution u = F(t - x/a) + G(t + x/a)
!> of each cell (plus g t^2/2 under gravity). A lattice state at t^{n+1} (cell stresses
!> s^{n+1}, increments du^{n+1}) is read as the characteristic intervals of every cell: f_k
!> (the down-going wave's rise over one step) and g_k (the up-going one's), with
!>    cell k:         Z_k (f_k - g_k) = s_k dt
!>    joined node i:  m_i du_i / dt   = Z_{i+1} f_{i+1} + Z_i g_i
!>    free top face:  m du / dt       = Z f - I/2      (I: integral of the face load over the step)
!>    free bottom:    m du / dt       = Z g + I/2
!> (a held end gives no equation; a transmitting one gives the interval of the wave that came
!> in through it, plus g dt^2/4 under gravity). The energy of that continuum state,
!>    E = sum_k Z_k (f_k^2 + g_k^2) / dt  =  integral of rho v^2/2 + sigma^2/(2E),
!> is non-negative, zero only at rest or in rigid motion, and conserved exactly by the intact
!> scheme (g = 0, no load). A fragment with two free faces has one equation more than
!> unknowns: their compatibility residual
!>    J = sum_i (-1)^(i - top) (m_i du_i / dt + s_i dt)   (s_i: the cell above node i)
!> minus the load terms is the amplitude along the Jordan partner of the zig-zag mode (it
!> grows linearly when not zero) and must stay at round-off. A fragment held at both ends
!> has one unknown more than equations (the zig-zag standing wave with nodes at every node):
!> the smallest energy is taken. Under gravity E + e_pot - (g dt / 2) sum_f J'_f (J' the same
!> alternating sum with the loads; with a transmitting end and an odd cell count, the outgoing
!> wave's interval there) is the exactly conserved total (checked for every combination of
!> held, free and transmitting ends, homogeneous and layered; bench/transmit_gravity.py).
module spb_wave
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, face_bottom, has_free_face, transmits, is_velocity_end, &
      has_base, on_base, holds, gives_equation
   use spb_state, only: state_t
   use spb_columns, only: column_set_t, add_column
   implicit none
   private
   public :: wave_t, wave_energy, fragment_wave, fragment_characteristics, region_wave, &
      transmit_residuals, start_without_zigzag, start_zigzag, held_odd, credit_bound, &
      vertex_offset, credit_position
   public :: wave_columns_t, register_wave_columns, post_wave_columns

   !> The whole bar's wave energy and the largest Jordan amplitude of its fragments.
   type :: wave_t
      real(wp) :: e_wave = 0.0_wp      !! sum of the fragments' continuum energies [J/m^2]
      real(wp) :: e_gravity = 0.0_wp   !! -(g dt/2) sum_f J'_f: with e_pot the exact gravity
                                       !! energy of the lattice [J/m^2]
      real(wp) :: jordan = 0.0_wp      !! largest |J| over the fragments / the bar's momentum
                                       !! scale (sum of |m du/dt| and |s dt| over the nodes) [-]
      real(wp) :: jordan_abs = 0.0_wp  !! largest |J| [kg/(m s)]
      real(wp) :: momentum_scale = 0.0_wp  !! the bar's momentum scale (the sum above) [kg/(m s)]
      real(wp) :: w_support = 0.0_wp   !! sum over the constant-velocity ends of V Z f_end, f_end
                                       !! the interval the end sends into the bar (top: f_1,
                                       !! bottom: g_n) at t^{n+1}: the part of their work on
                                       !! the continuum state that is a function of it [J/m^2]
   end type wave_t

   !> The wave measure's history columns (PREFIX.his, /history): their ids (spb_columns).
   type :: wave_columns_t
      integer :: e_wave = 0, e_wave_g = 0, jordan = 0
   end type wave_columns_t

   !> What a fragment's two faces give its reading (face_equations).
   type :: faces_t
      logical :: eq_top = .false.     !! the top face gives an equation (tr_top included)
      logical :: eq_bot = .false.     !! the bottom face gives an equation (tr_bot included)
      logical :: tr_top = .false.     !! the top face is a transmitting end that is used
      logical :: tr_bot = .false.     !! the bottom face is a transmitting end that is used
      real(wp) :: load_top = 0.0_wp   !! load term of the top face, I_top/2 or 0 [kg/(m s)]
      real(wp) :: load_bot = 0.0_wp   !! load term of the bottom face, I_bot/2 or 0 [kg/(m s)]
      real(wp) :: eta_top = 0.0_wp    !! at a transmitting top, Z_1 f_1 its equation gives at
                                      !! t^{n+1}: Z_1 (w_in + g dt^2/4) [kg/(m s)]
      real(wp) :: eta_bot = 0.0_wp    !! at a transmitting bottom, Z_n g_n: Z_n (w_in + g dt^2/4)
                                      !! [kg/(m s)]
   end type faces_t

contains

   !> Register the wave measure's history columns (their meaning: doc/outputs.md).
   pure subroutine register_wave_columns(set, id)
      type(column_set_t), intent(inout) :: set   !! the history's columns
      type(wave_columns_t), intent(out) :: id    !! their ids
      call add_column(set, id%e_wave, 'e_wave', 'J/m^2')
      call add_column(set, id%e_wave_g, 'e_wave_g', 'J/m^2')
      call add_column(set, id%jordan, 'jordan', '-')
   end subroutine register_wave_columns

   !> Post the wave measure into a history row.
   pure subroutine post_wave_columns(id, w, row)
      type(wave_columns_t), intent(in) :: id   !! the columns' ids
      type(wave_t), intent(in) :: w            !! the wave measure
      real(wp), intent(inout) :: row(:)        !! the row
      row(id%e_wave) = w%e_wave
      row(id%e_wave_g) = w%e_gravity
      row(id%jordan) = w%jordan
   end subroutine post_wave_columns

   !> Wave energy of the bar at t^{n+1} = st%step dt. i_top, i_bot: integrals of the load on the
   !> top and bottom faces over the step just taken [Pa s] (0 where no load acts there).
   pure function wave_energy(mesh, st, g, i_top, i_bot) result(w)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g        !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      type(wave_t) :: w
      real(wp) :: e, jp, jr, ja, total, ws
      integer :: c, top, bot
      total = 0.0_wp
      top = 0
      do c = 1, st%n_split + 1
         if (c <= st%n_split) then
            bot = st%split(c)
         else
            bot = mesh%n
         end if
         if (top > 0 .and. bot < mesh%n .and. bot > top .and. .not. loaded(st, top, bot)) then
            ! between two split nodes (no transmitting end, no load): the short path
            call inner_wave(mesh, st, top, bot, .true., e, jp, jr, ja)
         else
            call fragment_wave(mesh, st, g, top, bot, i_top, i_bot, e, jp, jr, ja, w_sup=ws)
            w%w_support = w%w_support + ws
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

   !> Wave energy with its gravity terms, e_wave - (g dt/2) J' + e_pot, less the reading's part
   !> of the constant-velocity ends' work (wave_t%w_support), of the fragments between the
   !> fragment boundaries top and bot (0 or a split node, n or a split node) [J/m^2]: what an
   !> event that acts there (breaks, joins, shifts) changes.
   pure real(wp) function region_wave(mesh, st, g, i_top, i_bot, top, bot) result(e_sum)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      integer, intent(in) :: top           !! top node of the region (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the region (n or a split node)
      real(wp) :: e, jp, jr, ja, ws
      integer :: t, b
      ! gravity potential at mid-step, -g m (u^n + u^{n+1})/2, of the halves the region owns
      e_sum = region_potential(bot - top, g, top == 0, bot == mesh%n, mesh%ma(top:bot), &
                               mesh%mb(top:bot), st%ua(top:bot), st%ub(top:bot), &
                               st%dua(top:bot), st%dub(top:bot))
      t = top
      do while (t < bot)
         b = t + 1
         do while (b < bot)
            if (.not. st%joined(b)) exit
            b = b + 1
         end do
         if (t > 0 .and. b < mesh%n .and. .not. loaded(st, t, b)) then
            call inner_wave(mesh, st, t, b, .false., e, jp, jr, ja)
         else
            call fragment_wave(mesh, st, g, t, b, i_top, i_bot, e, jp, jr, ja, w_sup=ws, &
                               scale=.false.)
            e_sum = e_sum - ws
         end if
         e_sum = e_sum + e - 0.5_wp * g * mesh%dt * jp
         t = b
      end do
   end function region_wave

   !> The gravity potential at mid-step, -g m (u^n + u^{n+1})/2, of the halves a region of
   !> nodes 0..m (top..bot) owns [J/m^2]: every node's but the top node's upper half (unless
   !> the top is the bar's end, first_a) and the bottom node's lower half (unless it is the
   !> bar's end, last_b); summed node by node, upper half before lower (region_wave's order:
   !> the ends peeled off the loop, on the region's slices of the arrays).
   pure real(wp) function region_potential(m, g, first_a, last_b, ma, mb, ua, ub, dua, dub) &
      result(e)
      integer, intent(in) :: m             !! cells of the region (nodes 0..m)
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      logical, intent(in) :: first_a       !! the top node's upper half is the region's
      logical, intent(in) :: last_b        !! the bottom node's lower half is the region's
      real(wp), intent(in) :: ma(0:m)      !! upper half masses [kg/m^2 A]
      real(wp), intent(in) :: mb(0:m)      !! lower half masses [kg/m^2 A]
      real(wp), intent(in) :: ua(0:m)      !! upper half displacements at t^{n+1} [m]
      real(wp), intent(in) :: ub(0:m)      !! lower half displacements at t^{n+1} [m]
      real(wp), intent(in) :: dua(0:m)     !! their increments over the step [m]
      real(wp), intent(in) :: dub(0:m)     !! [m]
      integer :: j
      e = 0.0_wp
      ! without gravity every term is a zero (of either sign): the sum is 0 exactly
      if (.not. abs(g) > 0.0_wp) return
      if (first_a) e = e - g * ma(0) * (ua(0) - 0.5_wp * dua(0))
      if (m > 0 .or. last_b) e = e - g * mb(0) * (ub(0) - 0.5_wp * dub(0))
      do j = 1, m - 1
         e = e - g * ma(j) * (ua(j) - 0.5_wp * dua(j))
         e = e - g * mb(j) * (ub(j) - 0.5_wp * dub(j))
      end do
      if (m > 0) then
         e = e - g * ma(m) * (ua(m) - 0.5_wp * dua(m))
         if (last_b) e = e - g * mb(m) * (ub(m) - 0.5_wp * dub(m))
      end if
   end function region_potential

   !> Whether a face of the fragment top..bot is a cohesive crack's (it carries a traction).
   pure logical function loaded(st, top, bot)
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment
      integer, intent(in) :: bot           !! bottom node of the fragment
      loaded = .false.
      if (st%coh%on) loaded = st%coh%active(top) .or. st%coh%active(bot)
   end function loaded

   !> The continuum reading of one fragment, nodes top..bot (top: 0 or a split node whose
   !> lower half it owns; bot: n or a split node whose upper half it owns), at t^{n+1}.
   !> One pass without arrays (the reading of fragment_h, which tests/test_wave_energy.pf
   !> checks this against): every solution of the node equations from the top down is
   !> h_k = hd_k + beta (-1)^(bot-k), hd_k the one that starts from the top face's equation
   !> (or from 0 where the top is held); beta follows from the bottom face's equation (half
   !> of it, sharing the residual, when both faces are free; 0 when only the top is free) or,
   !> held at both ends, from the smallest energy. With A = sum (hd^2 + (hd + s dt)^2)/Z,
   !> B = sum (-1)^(bot-k) (2 hd + s dt)/Z and C = sum 1/Z the energy is
   !> (A + 2 beta B + 2 beta^2 C)/dt. rho: at a transmitting end, the reading's incoming
   !> interval minus the one its equation gives (the fragment's zig-zag content, not zero where
   !> the other face gives an equation too; transmit_residuals). scale = .false.: the
   !> momentum scale is not summed (jordan 0; the other results the same).
   pure subroutine fragment_wave(mesh, st, g, top, bot, i_top, i_bot, e, jprime, jordan, &
                                 jordan_abs, rho, w_sup, scale)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top          !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot          !! bottom face-load integral over the step [Pa s]
      real(wp), intent(out) :: e             !! continuum energy [J/m^2]
      real(wp), intent(out) :: jprime        !! alternating sum J' with the load terms [kg/(m s)]
      real(wp), intent(out) :: jordan        !! the fragment's momentum scale, sum of |m du/dt|
                                             !! and |s dt| [kg/(m s)]
      real(wp), intent(out) :: jordan_abs    !! |J| (0 unless two free faces) [kg/(m s)]
      real(wp), intent(out), optional :: rho(2)  !! rho at a transmitting top and bottom (else
                                                 !! 0) [m]
      real(wp), intent(out), optional :: w_sup   !! V Z f_end summed over the fragment's
                                                 !! constant-velocity ends (wave_t) [J/m^2]
      logical, intent(in), optional :: scale     !! sum the momentum scale (default .true.)
      real(wp) :: dt, r, hd, hd_1, a, b, c, d, beta
      logical :: with_scale
      type(faces_t) :: fc
      with_scale = .true.
      if (present(scale)) with_scale = scale
      dt = mesh%dt
      fc = face_equations(mesh, st, g, top, bot, i_top, i_bot)
      r = node_momentum(mesh, st, top, bot, top)
      jprime = r
      jordan = abs(r)
      hd = 0.0_wp
      if (fc%eq_top .and. bot > top) hd = r + fc%load_top - st%s(top + 1) * dt
      if (fc%tr_top .and. bot > top) hd = fc%eta_top - st%s(top + 1) * dt
      hd_1 = hd
      a = 0.0_wp
      b = 0.0_wp
      c = 0.0_wp
      ! the pass over the cells (node_momentum of each node below top written out there)
      if (bot > top) call cell_sums(bot - top, merge(bot - top, bot - top - 1, bot == mesh%n), &
         dt, mesh%ma(top + 1:bot), mesh%mb(top + 1:bot), st%dua(top + 1:bot), &
         st%dub(top + 1:bot), st%s(top + 1:bot), mesh%z(top + 1:bot), with_scale, &
         merge(1.0_wp, -1.0_wp, mod(bot - top - 1, 2) == 0), hd, r, jprime, jordan, a, b, c)
      if (.not. with_scale) jordan = 0.0_wp
      call face_terms(mesh, st, top, bot, fc, jprime)
      jordan_abs = 0.0_wp
      e = 0.0_wp
      if (present(rho)) rho = 0.0_wp
      if (present(w_sup)) w_sup = 0.0_wp
      if (bot == top) return
      ! hd now holds hd_bot; d = h_bot from the bottom face's equation minus hd_bot
      d = r - fc%load_bot - hd
      if (fc%tr_bot) d = fc%eta_bot - hd
      if (fc%eq_top .and. fc%eq_bot) then
         ! with two transmitting ends the residual is not a Jordan amplitude but the content of
         ! the neutral zig-zag mode (no Jordan block: it changes sign in every step and never
         ! grows; an unstressed start under gravity holds some); reported as before where
         ! g = 0 (round-off there)
         if (.not. ((fc%tr_top .or. fc%tr_bot) .and. abs(g) > 0.0_wp)) jordan_abs = abs(d)
         beta = 0.5_wp * d
      else if (fc%eq_top) then
         beta = 0.0_wp
      else if (fc%eq_bot) then
         beta = d
      else
         beta = -b / (2.0_wp * c)
      end if
      e = max(0.0_wp, a + 2.0_wp * beta * (b + beta * c)) / dt
      if (present(w_sup)) then
         ! Z_1 f_1 = h_1 + s_1 dt at a constant-velocity top, Z_n g_n = h_bot at the bottom
         if (top == 0 .and. is_velocity_end(st%ends(face_top))) w_sup = st%ends(face_top)%v_end * &
            (hd_1 + beta * merge(1.0_wp, -1.0_wp, mod(bot - top - 1, 2) == 0) + st%s(1) * dt)
         if (bot == mesh%n .and. is_velocity_end(st%ends(face_bottom))) w_sup = w_sup + &
            st%ends(face_bottom)%v_end * (hd + beta)
      end if
      if (.not. present(rho)) return
      ! h of the end cells: h_1 = hd_1 + beta (-1)^(bot-top-1), h_bot = hd_bot + beta
      if (top == 0 .and. transmits(st%ends(face_top))) then
         rho(1) = (hd_1 + beta * merge(1.0_wp, -1.0_wp, mod(bot - top - 1, 2) == 0) + &
                   st%s(1) * dt - fc%eta_top) / mesh%z(1)
      end if
      if (bot == mesh%n .and. transmits(st%ends(face_bottom))) then
         rho(2) = (hd + beta - fc%eta_bot) / mesh%z(bot)
      end if
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
         call cell_sums(bot - top, bot - top - 1, dt, mesh%ma(top + 1:bot), &
            mesh%mb(top + 1:bot), st%dua(top + 1:bot), st%dub(top + 1:bot), &
            st%s(top + 1:bot), mesh%z(top + 1:bot), with_scale, &
            merge(1.0_wp, -1.0_wp, mod(bot - top - 1, 2) == 0), hd, r, jprime, jordan, a, b, c)
      end if
      if (mod(bot - top, 2) == 1) jprime = jprime + 2.0_wp * no_load
      d = r - no_load - hd
      jordan_abs = abs(d)
      beta = 0.5_wp * d
      e = max(0.0_wp, a + 2.0_wp * beta * (b + beta * c)) / dt
   end subroutine inner_wave

   !> The pass over the cells top+1..bot of a fragment (fragment_wave, inner_wave): the same
   !> operations in the same order as fragment_wave's one-pass loop (node_momentum written
   !> out), the sums in locals, on the fragment's own slices of the arrays (explicit shapes:
   !> the compiler keeps their addresses in registers). Node j (1..m) below the top is a
   !> whole node for j <= m_whole (m at the bar's end, else m - 1), else the upper half of a
   !> split node. On return hd is hd_bot and r the bottom node's momentum.
   pure subroutine cell_sums(m, m_whole, dt, ma, mb, dua, dub, s, z, with_scale, sgn_k0, hd, &
                             r, jp, jr, a, b, c)
      integer, intent(in) :: m             !! cells (nodes below the top node)
      integer, intent(in) :: m_whole       !! of them whole nodes (m or m - 1)
      real(wp), intent(in) :: dt           !! time step [s]
      real(wp), intent(in) :: ma(m)        !! upper half masses of the nodes [kg/m^2 A]
      real(wp), intent(in) :: mb(m)        !! lower half masses [kg/m^2 A]
      real(wp), intent(in) :: dua(m)       !! increments of the upper halves [m]
      real(wp), intent(in) :: dub(m)       !! increments of the lower halves [m]
      real(wp), intent(in) :: s(m)         !! stresses of the cells above the nodes [Pa A]
      real(wp), intent(in) :: z(m)         !! impedances of the cells [kg/(m^2 s) A]
      logical, intent(in) :: with_scale    !! sum the momentum scale (jr)
      real(wp), intent(in) :: sgn_k0       !! (-1)^(bot-top-1), B's sign at the first cell
      real(wp), intent(inout) :: hd        !! hd of the first cell in, hd_bot out [kg/(m s)]
      real(wp), intent(inout) :: r         !! m du/dt of the last node summed [kg/(m s)]
      real(wp), intent(inout) :: jp        !! J' so far [kg/(m s)]
      real(wp), intent(inout) :: jr        !! the momentum scale so far [kg/(m s)]
      real(wp), intent(inout) :: a         !! A so far [(kg/(m s))^2 m^2 s/kg]
      real(wp), intent(inout) :: b         !! B so far [kg/(m s) m^2 s/kg]
      real(wp), intent(inout) :: c         !! C so far [m^2 s/kg]
      real(wp) :: sd, sd_next, iz, sgn, sgn_k, h, p, q, u, v, w, rk
      integer :: j
      h = hd
      p = jp
      q = jr
      u = a
      v = b
      w = c
      rk = r
      sgn = 1.0_wp
      sgn_k = sgn_k0
      sd_next = s(1) * dt
      do j = 1, m
         sd = sd_next
         if (j <= m_whole) then
            rk = (ma(j) * dua(j) + mb(j) * dub(j)) / dt
         else
            rk = ma(j) * dua(j) / dt    ! the upper half of a split node
         end if
         iz = 1.0_wp / z(j)
         sgn = -sgn
         p = p + sgn * (rk + sd)
         if (with_scale) q = q + abs(rk) + abs(sd)
         u = u + (h**2 + (h + sd)**2) * iz
         v = v + sgn_k * (2.0_wp * h + sd) * iz
         w = w + iz
         sgn_k = -sgn_k
         if (j < m) then
            sd_next = s(j + 1) * dt
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

   !> The zig-zag content of the fragments at the transmitting ends, at t^{n+1} [m]: the
   !> reading's incoming interval there minus the one the end's equation gives,
   !> w_in + g dt^2/4. It is zero where the fragment's other end is held (the end's equation
   !> is its reading); where the other face gives an equation too (a free face, another
   !> transmitting end) a state can hold the neutral zig-zag mode of such a fragment (an
   !> unstressed start under gravity as init_state builds it holds g dt^2/4 of it), and the
   !> intact scheme takes rho to -rho in every step, loads or not. The start the program runs
   !> holds none (start_without_zigzag), so rho stays at round-off; the work through the end
   !> counts the incoming interval w_in + rho (spb_step, which does not ask without gravity:
   !> with g = 0 nothing but the start, which the projection clears, makes any).
   pure subroutine transmit_residuals(mesh, st, g, i_top, i_bot, rho_top, rho_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp), intent(out) :: rho_top     !! rho at a transmitting top (else 0) [m]
      real(wp), intent(out) :: rho_bot     !! rho at a transmitting bottom (else 0) [m]
      real(wp) :: e, jp, jr, ja, rho(2)
      type(faces_t) :: fc
      integer :: top, bot
      rho_top = 0.0_wp
      rho_bot = 0.0_wp
      if (transmits(st%ends(face_top))) then
         bot = mesh%n
         if (st%n_split > 0) bot = st%split(1)
         fc = face_equations(mesh, st, g, 0, bot, i_top, i_bot)
         if (fc%eq_bot) then
            call fragment_wave(mesh, st, g, 0, bot, i_top, i_bot, e, jp, jr, ja, rho, &
                               scale=.false.)
            rho_top = rho(1)
         end if
      end if
      if (transmits(st%ends(face_bottom))) then
         top = 0
         if (st%n_split > 0) top = st%split(st%n_split)
         fc = face_equations(mesh, st, g, top, mesh%n, i_top, i_bot)
         if (fc%eq_top) then
            call fragment_wave(mesh, st, g, top, mesh%n, i_top, i_bot, e, jp, jr, ja, rho, &
                               scale=.false.)
            rho_bot = rho(2)
         end if
      end if
   end subroutine transmit_residuals

   !> The start without the lattice's zig-zag content (issue 17): a fragment with a
   !> transmitting end whose other end gives an equation (a free face, the base out of contact,
   !> a split node, a second transmitting end) has the zig-zag mode u_i = A (-1)^(n+i) as a
   !> neutral mode, a lattice-only state the continuum cannot have, and a start can hold some
   !> (an unstressed one under gravity g dt^2/4: the bar moved over the step before t = 0 at
   !> its end's velocity while the continuation rests in equilibrium; a strain rate
   !> (strain_rate dx) dt/4). Its amplitude is read by rho (start_zigzag) and the mode is taken
   !> out: A = -rho at a transmitting top, -(-1)^n rho at a transmitting bottom (n the bottom
   !> node), -rho_top 2 Z_1/(Z_1 + Z_n) with two transmitting ends (the mode's own rho there,
   !> the two readings' residual shared half and half). rho flips its sign in every intact
   !> step, so its linear part is the left eigenvector of the mode: this is the spectral
   !> projection, and rho stays 0 (to round-off) until an event. At t^0 the mode adds
   !> u_i += A (-1)^i, du_i += 2 A (-1)^i, s_k += 2 A (E/dx)_k (-1)^(k-1) and the opposite
   !> to s^{-1}; the section stresses are left alone (the mode leaves (3.1)'s half velocity
   !> unchanged, so S keeps no part of it), and a base out of contact moves with the bottom
   !> face (the deck's gap is kept). Called once, after init_state (spb_sim).
   pure subroutine start_without_zigzag(mesh, g, st)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the initial state (st%step = 0)
      real(wp) :: rho_top, rho_bot, amp
      integer :: top, bot, n
      n = mesh%n
      call start_zigzag(mesh, g, st, rho_top, rho_bot)
      top = 0
      if (st%n_split > 0) top = st%split(st%n_split)
      bot = n
      if (st%n_split > 0) bot = st%split(1)
      if (transmits(st%ends(face_top)) .and. transmits(st%ends(face_bottom)) .and. top == 0) then
         amp = -rho_top * 2.0_wp * mesh%z(1) / (mesh%z(1) + mesh%z(n))
         call add_zigzag(mesh, st, 0, n, amp)
         return
      end if
      if (transmits(st%ends(face_top))) call add_zigzag(mesh, st, 0, bot, -rho_top)
      if (transmits(st%ends(face_bottom))) then
         amp = -rho_bot * merge(1.0_wp, -1.0_wp, mod(n, 2) == 0)
         call add_zigzag(mesh, st, top, n, amp)
      end if
   end subroutine start_without_zigzag

   !> The zig-zag content rho of the state at t^0 at a transmitting top and bottom [m]
   !> (transmit_residuals, with no load before t = 0, with and without gravity): 0 where the
   !> fragment's other end is held.
   pure subroutine start_zigzag(mesh, g, st, rho_top, rho_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(in) :: st      !! the state at t^0
      real(wp), intent(out) :: rho_top     !! rho at a transmitting top (else 0) [m]
      real(wp), intent(out) :: rho_bot     !! rho at a transmitting bottom (else 0) [m]
      real(wp), parameter :: no_load = 0.0_wp
      call transmit_residuals(mesh, st, g, no_load, no_load, rho_top, rho_bot)
   end subroutine start_zigzag

   !> Add the zig-zag mode u_i = amp (-1)^i (at t^0) to the fragment top..bot: the halves it
   !> owns, its cells' stresses s^0 and s^{-1}.
   pure subroutine add_zigzag(mesh, st, top, bot, amp)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state at t^0
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: amp          !! the mode's amplitude A [m]
      real(wp) :: a_i, ds
      integer :: i
      if (.not. abs(amp) > 0.0_wp) return
      do i = top, bot
         a_i = merge(amp, -amp, mod(i, 2) == 0)
         if (i > top .or. top == 0) then
            st%ua(i) = st%ua(i) + a_i
            st%dua(i) = st%dua(i) + 2.0_wp * a_i
         end if
         if (i < bot .or. bot == mesh%n) then
            st%ub(i) = st%ub(i) + a_i
            st%dub(i) = st%dub(i) + 2.0_wp * a_i
         end if
         if (i > top) then
            ds = -2.0_wp * mesh%stiff(i) * a_i       ! (E/dx)(du_{i-1} - du_i) of the mode
            st%s(i) = st%s(i) + ds
            st%s_old(i) = st%s_old(i) - ds
         end if
      end do
      if (top == 0 .and. has_base(st%ends(face_top)) .and. .not. st%ends(face_top)%contact) then
         st%ends(face_top)%u_contact = st%ends(face_top)%u_contact + amp
      end if
      if (bot == mesh%n .and. has_base(st%ends(face_bottom)) .and. &
          .not. st%ends(face_bottom)%contact) then
         st%ends(face_bottom)%u_contact = st%ends(face_bottom)%u_contact + &
                                          merge(amp, -amp, mod(bot, 2) == 0)
      end if
      st%s_scale = max(st%s_scale, maxval(abs(st%s(top+1:bot))))
   end subroutine add_zigzag

   !> The characteristic intervals of the fragment's cells at t^n (at_n: read from s^n and
   !> du^{n+1}; the waves that arrive at the nodes during the step) or at t^{n+1} (from
   !> s^{n+1} and du^{n+1}): f_k (down-going) and g_k (up-going) rise over one step [m].
   !> Over the step a joined node moves by 2 (Z_i f_i + Z_{i+1} g_{i+1}) / (Z_i + Z_{i+1})
   !> (t^n intervals), a free bottom face by 2 f_i, a free top face by 2 g_{i+1}.
   pure subroutine fragment_characteristics(mesh, st, gravity, top, bot, i_top, i_bot, at_n, f, g)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: gravity      !! gravity along +x [m/s^2]
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top          !! top face-load integral over the step [Pa s]
      real(wp), intent(in) :: i_bot          !! bottom face-load integral over the step [Pa s]
      logical, intent(in) :: at_n          !! the t^n intervals (else those at t^{n+1})
      real(wp), intent(out) :: f(top+1:)   !! down-going interval f_k of each cell [m]
      real(wp), intent(out) :: g(top+1:)   !! up-going interval g_k of each cell [m]
      real(wp) :: h(top+1:max(top+1, bot)), sdt(top+1:max(top+1, bot)), jp, jr, ja
      call fragment_h(mesh, st, gravity, top, bot, i_top, i_bot, at_n, h, sdt, jp, jr, ja)
      g(top+1:bot) = h(top+1:bot) / mesh%z(top+1:bot)
      f(top+1:bot) = (h(top+1:bot) + sdt(top+1:bot)) / mesh%z(top+1:bot)
   end subroutine fragment_characteristics

   !> h_k = Z_k g_k and s_k dt of the fragment's cells, J' and the Jordan amplitude; at_n:
   !> the t^n reading (s^n; a node's equation holds the cell above), else t^{n+1} (s^{n+1};
   !> the cell below).
   pure subroutine fragment_h(mesh, st, g, top, bot, i_top, i_bot, at_n, h, sdt, jprime, jordan, &
                              jordan_abs)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
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
      real(wp) :: r(top:bot), h_dn(top+1:max(top+1, bot)), h_up(top+1:max(top+1, bot))
      real(wp) :: dt, scale, sgn, alpha, num, den
      type(faces_t) :: fc
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
      fc = face_equations(mesh, st, g, top, bot, i_top, i_bot)
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
      call face_terms(mesh, st, top, bot, fc, jprime)
      jordan = scale
      jordan_abs = 0.0_wp
      if (bot == top) return
      ! h from the top face down and from the bottom face up
      h_dn(top + 1) = 0.0_wp
      if (fc%eq_top .and. .not. fc%tr_top) h_dn(top + 1) = merge(r(top) - fc%load_top, &
         r(top) + fc%load_top - sdt(top + 1), at_n)
      if (fc%tr_top) h_dn(top + 1) = merge(r(top) - fc%eta_top, fc%eta_top - sdt(top + 1), at_n)
      do k = top + 1, bot - 1
         h_dn(k + 1) = r(k) - sdt(k + o) - h_dn(k)
      end do
      if (fc%eq_bot) then
         if (fc%tr_bot) then
            h_up(bot) = merge(r(bot) - fc%eta_bot - sdt(bot), fc%eta_bot, at_n)
         else
            h_up(bot) = merge(r(bot) - sdt(bot) + fc%load_bot, r(bot) - fc%load_bot, at_n)
         end if
         do k = bot - 1, top + 1, -1
            h_up(k) = r(k) - sdt(k + o) - h_up(k + 1)
         end do
      end if
      if (fc%eq_top .and. fc%eq_bot) then
         ! two free faces: one equation too many; its residual is the Jordan amplitude,
         ! shared half and half between the two readings (with a transmitting end: the
         ! zig-zag content, fragment_wave)
         if (.not. ((fc%tr_top .or. fc%tr_bot) .and. abs(g) > 0.0_wp)) then
            jordan_abs = abs(h_dn(bot) - h_up(bot))
         end if
         h(top+1:bot) = 0.5_wp * (h_dn + h_up)
      else if (fc%eq_top) then
         h(top+1:bot) = h_dn
      else if (fc%eq_bot) then
         h(top+1:bot) = h_up
      else
         ! held at both ends: h + alpha (-1)^k solves the node equations for any alpha; the
         ! smallest energy drops the standing zig-zag wave that no node sees
         num = 0.0_wp
         den = 0.0_wp
         sgn = 1.0_wp
         do k = top + 1, bot
            num = num + sgn * (2.0_wp * h_dn(k) + sdt(k)) / mesh%z(k)
            den = den + 2.0_wp / mesh%z(k)
            sgn = -sgn
         end do
         alpha = -num / den
         sgn = 1.0_wp
         do k = top + 1, bot
            h(k) = h_dn(k) + sgn * alpha
            sgn = -sgn
         end do
      end if
   end subroutine fragment_h

   !> The face loads' terms of J', and the alternating sum counted from the held end: from
   !> the bottom where only the bottom is held (the top otherwise); with a transmitting end
   !> and an odd cell count, the continuation's part of the sum (below).
   pure subroutine face_terms(mesh, st, top, bot, fc, jprime)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      type(faces_t), intent(in) :: fc      !! what the two faces give (face_equations)
      real(wp), intent(inout) :: jprime    !! J' from the nodes [kg/(m s)]
      real(wp) :: out_top, out_bot
      ! Found by computing the
      ! conserved functional of the affine one-step map and checked exact (round-off) for
      ! free, top-held, bottom-held and both-held fragments of odd and even cell counts, with
      ! loads on either face (doc/method.md)
      if (mod(bot - top, 2) == 1) jprime = jprime + 2.0_wp * fc%load_bot
      if (fc%eq_top .and. .not. fc%eq_bot .and. mod(bot - top, 2) == 1) jprime = -jprime
      ! held at both ends (a fixed top, and a fixed bottom or the base) with an odd cell count:
      ! the conserved gravity term is -2 g sum w_i m_i (u_i^n + u_i^{n+1})/2 with weights
      ! w_i = (-1)^(i-top-1) (1/2 - C_i/C), C_i the compliance (sum of dt/Z) of the cells
      ! above node i (found from the affine one-step map; exact, layered included), plus the
      ! bottom node's elastic position over C (held_weights)
      if (held_odd(mesh, st, top, bot)) jprime = held_weights(mesh, st, top, bot)
      if (fc%eq_top .and. .not. fc%eq_bot .and. mod(bot - top, 2) == 1) then
         jprime = jprime - 2.0_wp * fc%load_top
      end if
      ! a transmitting end read by its equation, odd cell count: the alternating sum goes on
      ! through the continuation, where it telescopes to the interval of the wave that went out
      ! over the step, Z (du_end - w_in - g dt^2/4) = r_end - eta. Twice that with a held other
      ! end (the sum counted from it); with two transmitting ends the two halves' sum replaces
      ! J' (the bar's own part cancels). Found on the lattice model (bench/transmit_gravity.py,
      ! from the affine one-step map), exact intact and through breaks.
      if (mod(bot - top, 2) == 0 .or. .not. (fc%tr_top .or. fc%tr_bot)) return
      out_top = node_momentum(mesh, st, top, bot, top) - fc%eta_top
      out_bot = node_momentum(mesh, st, top, bot, bot) - fc%eta_bot
      if (fc%tr_top .and. fc%tr_bot) then
         jprime = out_top + out_bot
      else if (fc%tr_bot .and. .not. fc%eq_top) then
         jprime = jprime + 2.0_wp * out_bot
      else if (fc%tr_top .and. .not. fc%eq_bot) then
         jprime = jprime + 2.0_wp * out_top
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
   !> With a constant-velocity end the positions are taken relative to the supports' line
   !> U_top (1 - C_i/C) + U_bot C_i/C (U: a velocity end's mid-step position, else 0), the
   !> lattice's exact quasi-static motion of the supports (doc/method.md, "Ends").
   pure real(wp) function held_weights(mesh, st, top, bot) result(jp)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp) :: c_total, c_above, sgn, u_el, ref_top, ref_bot, ref
      integer :: i
      c_total = sum(1.0_wp / mesh%z(top+1:bot))
      c_above = 0.0_wp
      sgn = -1.0_wp
      jp = 0.0_wp
      ref_top = 0.0_wp
      ref_bot = 0.0_wp
      if (is_velocity_end(st%ends(face_top))) ref_top = st%ub(top) - 0.5_wp * st%dub(top)
      if (is_velocity_end(st%ends(face_bottom))) ref_bot = st%ua(bot) - 0.5_wp * st%dua(bot)
      u_el = st%ub(top)
      do i = top, bot
         if (i > top) then
            c_above = c_above + 1.0_wp / mesh%z(i)
            u_el = u_el - st%s(i) / mesh%stiff(i)
         end if
         ref = ref_top * (1.0_wp - c_above / c_total) + ref_bot * (c_above / c_total)
         jp = jp + sgn * (0.5_wp - c_above / c_total) * &
              (mesh%ma(i) * (u_el - 0.5_wp * st%dua(i) - ref) + &
               mesh%mb(i) * (u_el - 0.5_wp * st%dub(i) - ref))
         sgn = -sgn
      end do
      jp = 4.0_wp / mesh%dt * jp + (u_el - 0.5_wp * st%dua(bot) - ref_bot + st%u_credit) / &
           c_total
      ! a bar resting against a base above it: the top node's position where its landing
      ! left it, the mirror of the bottom's term (the positions are summed from the top, so
      ! the bottom's term of the mirrored bar is this one)
      if (top == 0 .and. on_base(st%ends(face_top))) jp = jp + &
         (st%ub(top) - 0.5_wp * st%dub(top)) / c_total
   end function held_weights

   !> Whether the fragment top..bot is held at both ends (a fixed or velocity top, and a fixed
   !> or velocity bottom or the base it rests on) with an odd cell count: the case of
   !> held_weights, and of the landing credit (doc/method.md, "A landing credit").
   pure logical function held_odd(mesh, st, top, bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      held_odd = mod(bot - top, 2) == 1 .and. top == 0 .and. holds(st%ends(face_top)) .and. &
                 bot == mesh%n .and. holds(st%ends(face_bottom))
   end function held_odd

   !> K = g^2 dt^3 / (8 C), C = sum 1/Z over the cells of the fragment top..bot: for a
   !> fragment with an odd cell count held at one end, how much lower its measure is where its
   !> free face's step over the last step is the vertex of the measure (g dt^2 / (2 Z_k C)
   !> beyond the g = 0 one, along gravity; vertex_offset) [J/m^2]; for one held at both ends,
   !> the most a landing or a join can add to the measure (doc/method.md, "A landing credit").
   pure real(wp) function credit_bound(mesh, g, top, bot) result(k)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      k = g**2 * mesh%dt**3 / (8.0_wp * sum(1.0_wp / mesh%z(top+1:bot)))
   end function credit_bound

   !> g dt^2 / (2 Z_k C): where the measure of a fragment (nodes top..bot, odd cell count, held
   !> at its other end) has its vertex in the step of its free face next to cell k, beyond the
   !> g = 0 one, along gravity [m] (doc/method.md, "A landing credit"). 0 for an even count.
   pure real(wp) function vertex_offset(mesh, g, top, bot, k) result(d)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      integer, intent(in) :: k             !! the cell next to the free face
      d = 0.0_wp
      if (mod(bot - top, 2) == 1) d = 0.5_wp * g * mesh%dt**2 / (mesh%z(k) * &
                                                            sum(1.0_wp / mesh%z(top+1:bot)))
   end function vertex_offset

   !> The credit gamma [J/m^2] of the bar held at both ends with an odd cell count as the
   !> position u_credit of held_weights (the measure is lower by g dt u_credit / (2C)) [m].
   pure real(wp) function credit_position(mesh, g, gamma) result(u)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2], not 0
      real(wp), intent(in) :: gamma        !! the credit [J/m^2]
      u = 2.0_wp * gamma * sum(1.0_wp / mesh%z(1:mesh%n)) / (g * mesh%dt)
   end function credit_position

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
   !> the wave that came in over the step is known: at t^{n+1} the end cell's incoming
   !> interval is w_in + g dt^2/4 (eta = Z times it); at t^n the end node moved by it plus the
   !> end cell's outgoing interval. w_in (st%ends) is the interval the static stress carried,
   !> the continuation's motion and the incident load bring; g dt^2/4 is gravity's: the virtual
   !> cell's s_static is the continuation's static stress half a cell beyond the end node, so
   !> at the node it is s_static -/+ rho g dx/2 (bottom/top), and the reading's intervals carry
   !> the common rise g dt t^{n+1/2}/2 of g t^2/2, which cancels the incoming wave's own
   !> growth (doc/method.md). A held end gives none. A transmitting end is used only where the
   !> other end is not a free face (the free face's reading is exact there too).
   pure type(faces_t) function face_equations(mesh, st, g, top, bot, i_top, i_bot) result(fc)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      integer, intent(in) :: top           !! top node of the fragment (0 or a split node)
      integer, intent(in) :: bot           !! bottom node of the fragment (n or a split node)
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step [Pa s]
      real(wp), intent(in) :: i_bot        !! load integral on the bottom face over the step [Pa s]
      real(wp) :: grav
      ! a cohesive crack's face is a loaded free face: the traction T pulls it towards the
      ! other face, a load p = -T on it (I^{n+1} = st%coh%q, doc/method.md "Cohesive cracks")
      if (top > 0) then
         fc%eq_top = .true.
         if (st%coh%on) then
            if (st%coh%active(top)) fc%load_top = -0.5_wp * st%coh%q(top)
         end if
      else
         fc%eq_top = gives_equation(st%ends(face_top))
         if (has_free_face(st%ends(face_top))) fc%load_top = 0.5_wp * i_top
      end if
      if (bot < mesh%n) then
         fc%eq_bot = .true.
         if (st%coh%on) then
            if (st%coh%active(bot)) fc%load_bot = -0.5_wp * st%coh%q(bot)
         end if
      else
         fc%eq_bot = gives_equation(st%ends(face_bottom))
         if (has_free_face(st%ends(face_bottom))) fc%load_bot = 0.5_wp * i_bot
      end if
      fc%tr_top = top == 0 .and. transmits(st%ends(face_top)) .and. .not. fc%eq_bot
      fc%tr_bot = bot == mesh%n .and. transmits(st%ends(face_bottom)) .and. .not. fc%eq_top
      fc%eq_top = fc%eq_top .or. fc%tr_top
      fc%eq_bot = fc%eq_bot .or. fc%tr_bot
      grav = 0.0_wp
      if (abs(g) > 0.0_wp) grav = 0.25_wp * g * mesh%dt**2
      if (top == 0 .and. transmits(st%ends(face_top))) then
         fc%eta_top = mesh%z(1) * (st%ends(face_top)%w_in + grav)
      end if
      if (bot == mesh%n .and. transmits(st%ends(face_bottom))) then
         fc%eta_bot = mesh%z(mesh%n) * (st%ends(face_bottom)%w_in + grav)
      end if
   end function face_equations
end module spb_wave
