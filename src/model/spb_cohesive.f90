!> The cohesive law of a crack and its step (doc/method.md, "Cohesive cracks").
!>
!> A section that reaches its strength R with a fracture energy Gc > 0 opens a cohesive crack:
!> its faces carry a traction T >= 0 (tension, pulling them together) that falls linearly
!> with the opening delta from R at 0 to 0 at delta_c = 2 Gc / R; below the largest opening
!> so far, delta_max, it unloads and reloads on the line through the origin,
!> T = T(delta_max) delta / delta_max; a closed crack (delta <= 0) carries none.
!>
!> The scheme applies a face force as it applies an end load, in the stepwise form: the
!> force at t^n is P^n = (I^n + I^{n+1}) / (2 dt), I^{n+1} the integral of the traction over
!> the step that ends at t^{n+1}. The traction over a step is taken along the law's path
!> from delta^n to delta^{n+1} with the opening moving uniformly in time, so
!> I^{n+1} = dt mean_traction(delta^n, delta^{n+1}), the exact mean of the law over the step's
!> openings, and the work the crack takes from the waves, I^{n+1} (delta^{n+1} - delta^n)/dt,
!> is exactly the law's integral over the opening increment (to round-off): a crack opened
!> fully has taken exactly Gc. delta^{n+1} depends on P^n linearly (delta* - c P), so each
!> step solves one scalar equation per open crack (cohesive_force). The faces of a crack never
!> pass each other: a step that would close it ends with the faces touching (delta = 0) under
!> the force that takes, a compression where needed, as a joined node moves; the energy this
!> contact takes (the step's work less the law's integral, never negative) is booked apart.
module spb_cohesive
   use spb_kinds, only: wp
   implicit none
   private
   public :: traction, mean_traction, law_integral, dissipated, recoverable, cohesive_force, exact_root

contains

   !> The law's traction at opening delta [Pa]: r the traction at zero opening of a fresh
   !> crack (its strength), dc the critical opening, dmax the largest opening so far.
   pure elemental real(wp) function traction(delta, dmax, r, dc) result(t)
      real(wp), intent(in) :: delta     !! opening [m]
      real(wp), intent(in) :: dmax      !! largest opening so far [m]
      real(wp), intent(in) :: r         !! strength: the traction at delta = 0+ when dmax = 0 [Pa]
      real(wp), intent(in) :: dc        !! critical opening 2 Gc / r [m]
      t = branch_value(delta, delta, dmax, r, dc)
   end function traction

   !> The linear branch of the law that holds at opening m, evaluated at x (x on its closure):
   !> 0 where the crack is closed or fully open, the unloading line below dmax, the softening
   !> line above it.
   pure real(wp) function branch_value(x, m, dmax, r, dc) result(t)
      real(wp), intent(in) :: x         !! where the branch is evaluated [m]
      real(wp), intent(in) :: m         !! a point inside the branch [m]
      real(wp), intent(in) :: dmax      !! largest opening so far [m]
      real(wp), intent(in) :: r         !! strength [Pa]
      real(wp), intent(in) :: dc        !! critical opening [m]
      real(wp) :: tm
      if (.not. m > 0.0_wp .or. m >= dc) then
         t = 0.0_wp
      else if (m < dmax) then
         ! unloading and reloading on the line through the origin
         tm = max(0.0_wp, r * (1.0_wp - dmax / dc))
         t = tm * (x / dmax)
      else
         t = max(0.0_wp, r * (1.0_wp - x / dc))
      end if
   end function branch_value

   !> Integral of the traction over the openings from a to b along a monotone path with
   !> largest opening dmax before it [Pa m]: exact (the law is linear between 0, dmax and
   !> dc: the trapezoid of each piece). Negative when b < a.
   pure real(wp) function law_integral(a, b, dmax, r, dc) result(w)
      real(wp), intent(in) :: a         !! opening at the start [m]
      real(wp), intent(in) :: b         !! opening at the end [m]
      real(wp), intent(in) :: dmax      !! largest opening before the path [m]
      real(wp), intent(in) :: r         !! strength [Pa]
      real(wp), intent(in) :: dc        !! critical opening [m]
      real(wp) :: lo, hi, pts(5), cut(3), x0, x1, dm, m
      integer :: k, np
      w = 0.0_wp
      if (.not. abs(b - a) > 0.0_wp) return
      lo = min(a, b)
      hi = max(a, b)
      dm = max(dmax, 0.0_wp)
      if (a > dm) dm = a      ! a path cannot start beyond the largest opening reached
      ! the pieces: the law is linear between its corners 0, dm and dc (ascending)
      cut = [0.0_wp, dm, dc]
      np = 1
      pts(1) = lo
      do k = 1, 3
         if (cut(k) > lo .and. cut(k) < hi .and. cut(k) > pts(np)) then
            np = np + 1
            pts(np) = cut(k)
         end if
      end do
      np = np + 1
      pts(np) = hi
      do k = 1, np - 1
         x0 = pts(k)
         x1 = pts(k + 1)
         if (.not. x1 > x0) cycle
         m = 0.5_wp * (x0 + x1)
         w = w + (x1 - x0) * 0.5_wp * (branch_value(x0, m, dm, r, dc) + &
                                       branch_value(x1, m, dm, r, dc))
      end do
      if (b < a) w = -w
   end function law_integral

   !> Mean traction over the openings from a to b (the exact integral over b - a; the
   !> traction at a where b = a) [Pa].
   pure real(wp) function mean_traction(a, b, dmax, r, dc) result(t)
      real(wp), intent(in) :: a         !! opening at the start of the step [m]
      real(wp), intent(in) :: b         !! opening at its end [m]
      real(wp), intent(in) :: dmax      !! largest opening before the step [m]
      real(wp), intent(in) :: r         !! strength [Pa]
      real(wp), intent(in) :: dc        !! critical opening [m]
      if (abs(b - a) > 0.0_wp) then
         t = law_integral(a, b, dmax, r, dc) / (b - a)
      else
         t = traction(a, max(dmax, a), r, dc)
      end if
   end function mean_traction

   !> Energy the crack has dissipated: r dmax / 2, which is Gc once dmax >= dc [J/m^2].
   pure elemental real(wp) function dissipated(dmax, r, dc) result(e)
      real(wp), intent(in) :: dmax      !! largest opening so far [m]
      real(wp), intent(in) :: r         !! strength [Pa]
      real(wp), intent(in) :: dc        !! critical opening [m]
      e = 0.5_wp * r * min(max(dmax, 0.0_wp), dc)
   end function dissipated

   !> Energy the crack holds and gives back on closing: the triangle under the unloading
   !> line up to the present opening, T(dmax) delta^2 / (2 dmax) [J/m^2].
   pure elemental real(wp) function recoverable(delta, dmax, r, dc) result(e)
      real(wp), intent(in) :: delta     !! opening [m]
      real(wp), intent(in) :: dmax      !! largest opening so far (>= delta) [m]
      real(wp), intent(in) :: r         !! strength [Pa]
      real(wp), intent(in) :: dc        !! critical opening [m]
      e = 0.0_wp
      if (.not. (delta > 0.0_wp .and. dmax > 0.0_wp)) return
      e = 0.5_wp * max(0.0_wp, r * (1.0_wp - dmax / dc)) * min(delta, dmax)**2 / dmax
   end function recoverable

   !> The crack's force of the step, P^n = (i_prev + I^{n+1}) / (2 dt) with
   !> I^{n+1} = dt mean_traction(a, dstar - c P^n): the scalar equation
   !> phi(P) = 2 P - i_prev/dt - mean_traction(a, dstar - c P) = 0 has its roots in
   !> [i_prev/(2 dt), (i_prev/dt + r)/2] (0 <= mean <= r); found by regula falsi (Illinois)
   !> inside that bracket to round-off. i_next = 2 dt P - i_prev keeps the stepwise form exact.
   pure subroutine cohesive_force(a, dstar, c, dt, i_prev, dmax, r, dc, p, i_next, contact)
      real(wp), intent(in) :: a         !! opening at t^n [m]
      real(wp), intent(in) :: dstar     !! opening at t^{n+1} the step gives without the force [m]
      real(wp), intent(in) :: c         !! opening the unit force closes over the step,
                                        !! dt^2 (1/m_A + 1/m_B) [m/Pa]
      real(wp), intent(in) :: dt        !! time step [s]
      real(wp), intent(in) :: i_prev    !! traction integral over the step that ended at t^n [Pa s]
      real(wp), intent(in) :: dmax      !! largest opening so far [m]
      real(wp), intent(in) :: r         !! strength [Pa]
      real(wp), intent(in) :: dc        !! critical opening [m]
      real(wp), intent(out) :: p        !! the force P^n on each face (tension > 0) [Pa]
      real(wp), intent(out) :: i_next   !! traction integral over this step [Pa s]
      logical, intent(out) :: contact   !! the faces end the step touching under the force
                                        !! that takes (not the law's root)
      real(wp) :: lo, hi, f_lo, f_hi, x, fx
      integer :: it, side
      logical :: found
      contact = .false.
      if (dmax >= dc) then
         ! a crack opened fully carries nothing: the last half of its traction, I^n/(2 dt)
         p = 0.5_wp * i_prev / dt
         i_next = 0.0_wp
         return
      end if
      lo = 0.5_wp * i_prev / dt
      hi = 0.5_wp * (i_prev / dt + r)
      if (a <= 1.0e-12_wp * dc) then
         ! closed at t^n (to round-off: a step that ends in contact leaves delta^{n+1} = 0 to an
         ! ulp of the step's opening increment). At delta = 0+ the law's traction is r for a
         ! fresh crack (its jump: at 0 it takes any traction up to r) and 0 on a damaged crack's
         ! unloading line; in contact it takes any compression. The crack stays closed where
         ! the force that keeps it so, p_c = dstar / c, needs a traction
         ! I^{n+1}/dt = 2 p_c - I^n/dt of at most that; else it opens, and the root lies where
         ! delta^{n+1} > 0, below p_c, where phi is continuous
         p = dstar / c
         if (2.0_wp * p - i_prev / dt <= merge(r, 0.0_wp, .not. dmax > 0.0_wp)) then
            i_next = 2.0_wp * dt * p - i_prev
            contact = .true.
            return
         end if
         hi = min(hi, p)
      end if
      ! the law is linear between its corners: the root in closed form (exact_root); the
      ! bracketed search below is the fallback where that finds none in [lo, hi]
      call exact_root(a, dstar, c, dt, i_prev, dmax, r, dc, lo, hi, p, found)
      if (found) then
         contact = dstar - c * p < 0.0_wp
         if (contact) p = dstar / c
         i_next = 2.0_wp * dt * p - i_prev
         return
      end if
      f_lo = phi(lo)
      f_hi = phi(hi)
      if (.not. f_lo < 0.0_wp) then
         p = lo
      else if (.not. f_hi > 0.0_wp) then
         p = hi
      else
         side = 0
         p = lo
         do it = 1, 200
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
            if (.not. (x > lo .and. x < hi)) x = 0.5_wp * (lo + hi)
            fx = phi(x)
            p = x
            if (.not. abs(fx) > 0.0_wp) exit
            if (fx < 0.0_wp) then
               lo = x
               f_lo = fx
               if (side == -1) f_hi = 0.5_wp * f_hi
               side = -1
            else
               hi = x
               f_hi = fx
               if (side == 1) f_lo = 0.5_wp * f_lo
               side = 1
            end if
            if (hi - lo <= 4.0_wp * epsilon(1.0_wp) * max(abs(lo), abs(hi))) then
               p = merge(lo, hi, abs(f_lo) < abs(f_hi))
               exit
            end if
         end do
      end if
      ! (where a fresh crack stays closed the law's jump at 0 is crossed: the root sits on it,
      ! delta^{n+1} = 0 to round-off, with the traction between 0 and r that keeps it there)
      ! the faces do not pass each other: where they would, the crack is in contact and its
      ! faces end the step touching, delta^{n+1} = 0, with the smaller tension (a compression
      ! where it is negative) that this takes
      contact = dstar - c * p < 0.0_wp
      if (contact) p = dstar / c
      i_next = 2.0_wp * dt * p - i_prev
   contains
      !> The equation's left side at the force pp [Pa].
      pure real(wp) function phi(pp)
         real(wp), intent(in) :: pp   !! a trial force P^n [Pa]
         phi = 2.0_wp * pp - i_prev / dt - mean_traction(a, dstar - c * pp, dmax, r, dc)
      end function phi
   end subroutine cohesive_force

   !> The roots of cohesive_force's equation in closed form. With x = delta^{n+1} and
   !> P = (dstar - x)/c the equation is (K - 2x/c)(x - a) = L(x), K = 2 dstar/c - I^n/dt and
   !> L(x) the law's integral from a to x; on each piece of the law (T = alpha + beta y between
   !> its corners) L is quadratic, so each piece gives a quadratic in the increment v = x - a
   !> (a linear one on the piece that holds a, where the factor v is taken out; elsewhere the
   !> factor is kept apart, so that no root v = 0 of it comes out of round-off). Of the roots
   !> that lie on their piece and give P in [lo, hi], the one nearest to a is taken (the least
   !> change of the opening: the only one where the cohesive zone is resolved, doc/method.md).
   pure subroutine exact_root(a, dstar, c, dt, i_prev, dmax, r, dc, lo, hi, p, found)
      real(wp), intent(in) :: a         !! opening at t^n [m]
      real(wp), intent(in) :: dstar     !! opening at t^{n+1} without the force [m]
      real(wp), intent(in) :: c         !! opening the unit force closes over the step [m/Pa]
      real(wp), intent(in) :: dt        !! time step [s]
      real(wp), intent(in) :: i_prev    !! traction integral of the last step [Pa s]
      real(wp), intent(in) :: dmax      !! largest opening so far [m]
      real(wp), intent(in) :: r         !! strength [Pa]
      real(wp), intent(in) :: dc        !! critical opening [m]
      real(wp), intent(in) :: lo        !! smallest force a root can have [Pa]
      real(wp), intent(in) :: hi        !! largest [Pa]
      real(wp), intent(out) :: p        !! the force of the root taken [Pa]
      logical, intent(out) :: found     !! a root was found
      real(wp) :: corner(4), p0, p1, alpha, beta, y0, e, kk, qa, qb, q, disc, x, best, dm, tm
      real(wp) :: roots(2), span
      integer :: k, m, nr
      found = .false.
      p = lo
      best = huge(1.0_wp)
      dm = max(dmax, 0.0_wp)
      if (a > dm) dm = a
      tm = 0.0_wp
      if (dm > 0.0_wp) tm = max(0.0_wp, r * (1.0_wp - dm / dc))
      kk = 2.0_wp * dstar / c - i_prev / dt
      span = max(abs(a), abs(dstar), dc)
      ! the pieces: below 0 (closed), 0..dm (unloading line), dm..dc (softening), beyond dc
      corner = [-huge(1.0_wp), 0.0_wp, dm, min(max(dc, dm), huge(1.0_wp))]
      ! first the piece that holds a: its root is the nearest where it lies closer to a than
      ! the piece's ends (no other piece's root can then be nearer): the usual step
      do k = 1, 4
         call piece(k, corner, dm, tm, r, dc, p0, p1, alpha, beta)
         if (.not. (p1 > p0 .and. a >= p0 .and. a <= p1)) cycle
         x = (kk - alpha - 0.5_wp * beta * a) / (2.0_wp / c + 0.5_wp * beta)
         if (abs(x - a) <= min(a - p0, p1 - a) .and. (dstar - x) / c >= lo .and. &
             (dstar - x) / c <= hi) then
            p = (dstar - x) / c
            found = .true.
            return
         end if
         exit
      end do
      do k = 1, 4
         call piece(k, corner, dm, tm, r, dc, p0, p1, alpha, beta)
         if (.not. p1 > p0) cycle
         nr = 0
         if (a >= p0 .and. a <= p1) then
            ! (K - 2x/c) - (alpha + beta (a + x)/2) = 0: the mean of a linear piece
            x = (kk - alpha - 0.5_wp * beta * a) / (2.0_wp / c + 0.5_wp * beta)
            nr = 1
            roots(1) = x
         else
            ! in the step's opening increment v = x - a: L(x) = e + v (alpha + beta (a + x)/2),
            ! e = L(y0) less the piece's line integrated from a to y0 (0 where a is on the
            ! piece's closure), so the equation is qa v^2 + qb v - e = 0. The factor v is kept
            ! apart: written in x, the root v = 0 that it has where a is on a corner came out
            ! of the cancellation of terms of size K a at round-off of them, on the piece's
            ! side of a corner a lies an ulp below, and was taken as the nearest root (a
            ! frame-dependent choice: doc/method.md, "Cohesive cracks")
            y0 = merge(p0, p1, a < p0)
            e = law_integral(a, y0, dmax, r, dc) - (y0 - a) * (alpha + 0.5_wp * beta * (a + y0))
            qa = -2.0_wp / c - 0.5_wp * beta
            qb = kk - 2.0_wp * a / c - alpha - beta * a
            if (abs(qa) * span <= 1.0e-14_wp * abs(qb)) then
               if (abs(qb) > 0.0_wp) then
                  nr = 1
                  roots(1) = a + e / qb
               end if
            else
               disc = qb**2 + 4.0_wp * qa * e
               if (disc >= 0.0_wp) then
                  q = -0.5_wp * (qb + sign(sqrt(disc), qb))
                  nr = 1
                  roots(1) = a + q / qa
                  if (abs(q) > 0.0_wp) then
                     nr = 2
                     roots(2) = a - e / q
                  end if
               end if
            end if
         end if
         do m = 1, nr
            x = roots(m)
            if (.not. (x >= p0 .and. x <= p1)) cycle
            if (.not. ((dstar - x) / c >= lo .and. (dstar - x) / c <= hi)) cycle
            if (abs(x - a) < best) then
               best = abs(x - a)
               p = (dstar - x) / c
               found = .true.
            end if
         end do
      end do
   end subroutine exact_root

   !> Piece k of the law (1: closed, 2: unloading line, 3: softening, 4: fully open) with
   !> corners as exact_root sets them: its ends p0, p1 and its line T = alpha + beta y.
   pure subroutine piece(k, corner, dm, tm, r, dc, p0, p1, alpha, beta)
      integer, intent(in) :: k            !! the piece
      real(wp), intent(in) :: corner(4)   !! -huge, 0, dm, dc [m]
      real(wp), intent(in) :: dm          !! the largest opening the path knows [m]
      real(wp), intent(in) :: tm          !! the traction at dm [Pa]
      real(wp), intent(in) :: r           !! strength [Pa]
      real(wp), intent(in) :: dc          !! critical opening [m]
      real(wp), intent(out) :: p0         !! lower end [m]
      real(wp), intent(out) :: p1         !! upper end [m]
      real(wp), intent(out) :: alpha      !! the line's value at 0 [Pa]
      real(wp), intent(out) :: beta       !! its slope [Pa/m]
      p0 = corner(k)
      p1 = huge(1.0_wp)
      if (k < 4) p1 = corner(k + 1)
      alpha = 0.0_wp
      beta = 0.0_wp
      select case (k)
      case (2)
         if (dm > 0.0_wp) beta = tm / dm
      case (3)
         alpha = r
         beta = -r / dc
      case default
         ! closed, or fully open: no traction
      end select
   end subroutine piece
end module spb_cohesive
