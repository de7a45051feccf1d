!> A rigid striking mass against an end face over one step, integrated exactly
!> (doc/method.md, "Striking mass").
!>
!> Over a step the face, left alone, would move at a constant velocity w: what the lattice
!> brings to it (spb_ends). A contact stress p(t) >= 0 (compression) on the face adds
!> sigma p / Z to its velocity (sigma = +1 at the top, where compression pushes the face
!> along +x, -1 at the bottom), Z = rho c A the end cell's impedance: the face of an
!> elastic bar is a dashpot against what arrives at it. The mass M moves under gravity g
!> (along +x) and -sigma p. With a rigid contact the face moves with the mass, so
!> p = sigma Z (V - w) and M V' = M g - Z (V - w): V relaxes exponentially to
!> w + M g / Z at the rate beta = Z / M. With a cushion of stiffness k (a linear spring
!> between mass and face, zero length) p = k c, c >= 0 its compression, and
!> (c, u = sigma (V - w)) solve the linear system c' = u - (k/Z) c, u' = sigma g - (k/M) c:
!> a mass-spring-dashpot, under-, critically or over-damped. Both are linear with constant
!> coefficients over the step, so the step is integrated in closed form, with the times at
!> which the mass strikes (the gap closes) and lets go (p would become tensile: it pushes
!> only) solved inside it. The step returns the contact impulse q = integral of p over the
!> step, which the lattice applies as the face's load (its stepwise form, spb_ends).
module spb_impactor
   use spb_kinds, only: wp
   implicit none
   private
   public :: mass_state_t, mass_step_t, strike_step, mass_energy

   !> The striking mass at a grid time.
   type :: mass_state_t
      real(wp) :: x = 0.0_wp          !! displacement of the mass from its start [m]
      real(wp) :: v = 0.0_wp          !! velocity along +x [m/s]
      real(wp) :: gap = 0.0_wp        !! distance between the mass and the face; < 0: the
                                      !! cushion's compression (0 while in rigid contact) [m]
      logical :: touching = .false.   !! in contact (rigid) or compressing the cushion
   end type mass_state_t

   !> What a step did.
   type :: mass_step_t
      real(wp) :: q = 0.0_wp          !! integral of the contact stress over the step
                                      !! (compression > 0) [Pa s A]
      real(wp) :: p_end = 0.0_wp      !! contact stress at the end of the step [Pa A]
      real(wp) :: t_impact = -1.0_wp  !! time into the step of its first impact (< 0: none) [s]
      real(wp) :: v_impact = 0.0_wp   !! approach speed sigma (V - w) at that impact [m/s]
      real(wp) :: t_release = -1.0_wp !! time into the step of its first release (< 0: none) [s]
      integer :: impacts = 0          !! impacts within the step
      integer :: releases = 0         !! releases within the step
   end type mass_step_t

   integer, parameter :: max_phases = 64       !! contact changes within one step at most
   !> Round-off guard of the contact decisions, relative to the largest contact stress at
   !> stake so far (p_ref): a contact lets go only when it would pull by more than this, a
   !> mass at the face strikes only when it approaches faster than this over Z
   !> (doc/method.md, "Tolerances") [-]
   real(wp), parameter :: contact_tol = 1.0e-9_wp
   integer, parameter :: root_samples = 8      !! subintervals searched for a cushion's release

contains

   !> Kinetic, gravity and cushion energy of the mass (potential 0 at its start) [J/m^2 A].
   pure real(wp) function mass_energy(st, m, k, g) result(e)
      type(mass_state_t), intent(in) :: st     !! the mass
      real(wp), intent(in) :: m                !! its mass [kg/m^2 A]
      real(wp), intent(in) :: k                !! cushion stiffness (0: rigid) [Pa/m A]
      real(wp), intent(in) :: g                !! gravity along +x [m/s^2]
      e = 0.5_wp * m * st%v**2 - m * g * st%x
      if (k > 0.0_wp .and. st%gap < 0.0_wp) e = e + 0.5_wp * k * st%gap**2
   end function mass_energy

   !> One step of length dt from st: the face moves at w where no contact stress acts.
   pure subroutine strike_step(st, m, k, z, g, sigma, w, dt, p_ref, r)
      type(mass_state_t), intent(inout) :: st  !! the mass at t^n, then at t^{n+1}
      real(wp), intent(in) :: m               !! the mass [kg/m^2 A]
      real(wp), intent(in) :: k               !! cushion stiffness (0: rigid contact) [Pa/m A]
      real(wp), intent(in) :: z               !! impedance of the end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: g               !! gravity along +x [m/s^2]
      real(wp), intent(in) :: sigma           !! +1: the mass is above the top face; -1: below
                                              !! the bottom face
      real(wp), intent(in) :: w               !! the face's velocity without contact [m/s]
      real(wp), intent(in) :: dt              !! time step [s]
      real(wp), intent(in) :: p_ref           !! the scale of the contact stresses: the
                                              !! largest so far, Z |V|, M |g| [Pa A]
      type(mass_step_t), intent(out) :: r     !! the step's contact impulse and events
      real(wp) :: t, s, dq
      integer :: phase
      t = 0.0_wp
      do phase = 1, max_phases
         if (.not. (t < dt)) exit
         if (st%touching) then
            if (k > 0.0_wp) then
               call cushion_phase(st, m, k, z, g, sigma, w, dt - t, contact_tol * p_ref / z, &
                                  contact_tol * p_ref / k, s, dq, r%p_end)
            else
               call rigid_phase(st, m, z, g, sigma, w, dt - t, contact_tol * p_ref, s, dq, &
                                r%p_end)
            end if
            r%q = r%q + dq
            if (.not. st%touching) then
               r%releases = r%releases + 1
               if (r%t_release < 0.0_wp) r%t_release = t + s
            end if
         else
            call free_phase(st, g, sigma, w, dt - t, contact_tol * p_ref / z, s)
            r%p_end = 0.0_wp
            if (st%touching) then
               r%impacts = r%impacts + 1
               if (r%t_impact < 0.0_wp) then
                  r%t_impact = t + s
                  r%v_impact = sigma * (st%v - w)
               end if
            end if
         end if
         t = t + s
         ! a phase that ends in a contact change takes the rest of the step to the next one;
         ! otherwise it ran to the step's end
      end do
   end subroutine strike_step

   !> Flight: the mass under gravity, the face at w, until the gap closes (the mass is
   !> moving onto the face; time s into the rest of the step) or the rest ends.
   pure subroutine free_phase(st, g, sigma, w, rest, v_tol, s)
      type(mass_state_t), intent(inout) :: st  !! the mass
      real(wp), intent(in) :: g                !! gravity along +x [m/s^2]
      real(wp), intent(in) :: sigma            !! side (+1 top, -1 bottom)
      real(wp), intent(in) :: w                !! the face's velocity [m/s]
      real(wp), intent(in) :: rest             !! what is left of the step [s]
      real(wp), intent(in) :: v_tol            !! an approach slower than this is none [m/s]
      real(wp), intent(out) :: s               !! the phase's length [s]
      real(wp) :: a2, a1, a0
      ! gap(s) = gap + sigma ((w - V) s - g s^2 / 2)
      a2 = -0.5_wp * sigma * g
      a1 = sigma * (w - st%v)
      a0 = max(st%gap, 0.0_wp)
      ! at the face: an approach within round-off of none is none
      if (.not. (a0 > 0.0_wp) .and. abs(a1) <= v_tol) a1 = 0.0_wp
      s = first_closing(a2, a1, a0, rest)
      st%x = st%x + st%v * s + 0.5_wp * g * s**2
      st%v = st%v + g * s
      if (s < rest) then
         st%gap = 0.0_wp
         st%touching = .true.
      else
         st%gap = a0 + (a1 + a2 * s) * s
         if (st%gap < 0.0_wp) st%gap = 0.0_wp   ! round-off of a closing at the step's end
      end if
   end subroutine free_phase

   !> The first s in [0, rest) at which a0 + a1 s + a2 s^2 (a0 >= 0) reaches 0 while
   !> falling; rest where it does not.
   pure real(wp) function first_closing(a2, a1, a0, rest) result(s)
      real(wp), intent(in) :: a2               !! quadratic coefficient [m/s^2]
      real(wp), intent(in) :: a1               !! linear coefficient [m/s]
      real(wp), intent(in) :: a0               !! the gap now, >= 0 [m]
      real(wp), intent(in) :: rest             !! the interval's length [s]
      real(wp) :: disc, r1, r2, qq
      s = rest
      if (.not. (a0 > 0.0_wp)) then
         ! touching: it strikes now when moving onto the face (or pushed onto it at rest)
         if (a1 < 0.0_wp .or. (.not. (a1 > 0.0_wp) .and. a2 < 0.0_wp)) s = 0.0_wp
         return
      end if
      if (.not. (abs(a2) > 0.0_wp)) then
         if (a1 < 0.0_wp) s = min(rest, -a0 / a1)
         return
      end if
      disc = a1**2 - 4.0_wp * a2 * a0
      if (disc < 0.0_wp) return
      ! the stable roots of a2 s^2 + a1 s + a0
      qq = -0.5_wp * (a1 + sign(sqrt(disc), a1))
      if (.not. (abs(qq) > 0.0_wp)) return
      r1 = qq / a2
      r2 = a0 / qq
      if (r1 > 0.0_wp) s = min(s, r1)
      if (r2 > 0.0_wp) s = min(s, r2)
   end function first_closing

   !> Rigid contact: V relaxes to w + M g / Z at beta = Z / M, p = sigma Z (V - w), until p
   !> would become tensile (released) or the rest ends.
   pure subroutine rigid_phase(st, m, z, g, sigma, w, rest, p_tol, s, dq, p_end)
      type(mass_state_t), intent(inout) :: st  !! the mass
      real(wp), intent(in) :: m                !! its mass [kg/m^2 A]
      real(wp), intent(in) :: z                !! impedance of the end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: g                !! gravity along +x [m/s^2]
      real(wp), intent(in) :: sigma            !! side (+1 top, -1 bottom)
      real(wp), intent(in) :: w                !! the face's velocity without contact [m/s]
      real(wp), intent(in) :: rest             !! what is left of the step [s]
      real(wp), intent(in) :: p_tol            !! a pull within this is none [Pa A]
      real(wp), intent(out) :: s               !! the phase's length [s]
      real(wp), intent(out) :: dq              !! integral of p over it [Pa s A]
      real(wp), intent(out) :: p_end           !! p at its end [Pa A]
      real(wp) :: beta, d0, e, h, ratio, p0
      beta = z / m
      ! p(s) = sigma (M g + Z d0 e^{-beta s}), d0 = V - w - M g / Z
      d0 = st%v - w - m * g / z
      p0 = sigma * (m * g + z * d0)
      s = rest
      if (p0 < -p_tol) then
         ! it pulls: released before p acts
         s = 0.0_wp
      else if (sigma * (m * g + z * d0 * exp(-beta * rest)) < -p_tol) then
         ! released within the rest: e^{-beta s} = -M g / (Z d0), in (e^{-beta rest}, 1)
         ratio = -m * g / (z * d0)
         s = min(rest, max(0.0_wp, -log(ratio) / beta))
      end if
      e = exp(-beta * s)
      h = relax_time(beta, s)                 ! (1 - e^{-beta s}) / beta
      st%v = (w + m * g / z) + d0 * e
      st%x = st%x + (w + m * g / z) * s + d0 * h
      ! M (V - V0) = M g s - sigma q, V - V0 = -d0 beta h, M beta = Z
      dq = sigma * (m * g * s + z * d0 * h)
      p_end = sigma * (m * g + z * d0 * e)
      st%gap = 0.0_wp
      if (s < rest) then
         st%touching = .false.
         p_end = 0.0_wp
      end if
   end subroutine rigid_phase

   !> (1 - e^{-beta s}) / beta without cancellation where beta s is small [s].
   pure real(wp) function relax_time(beta, s) result(h)
      real(wp), intent(in) :: beta             !! rate [1/s]
      real(wp), intent(in) :: s                !! time [s]
      real(wp) :: x
      x = beta * s
      if (abs(x) < 1.0e-3_wp) then
         h = s * (1.0_wp - x / 2.0_wp * (1.0_wp - x / 3.0_wp * (1.0_wp - x / 4.0_wp * &
             (1.0_wp - x / 5.0_wp))))
      else
         h = (1.0_wp - exp(-x)) / beta
      end if
   end function relax_time

   !> Cushion: c' = u - a c, u' = h - b c (a = k/Z, b = k/M, h = sigma g, u = sigma (V - w))
   !> from c = -gap, until c returns to 0 (released) or the rest ends.
   pure subroutine cushion_phase(st, m, k, z, g, sigma, w, rest, v_tol, c_tol, s, dq, p_end)
      type(mass_state_t), intent(inout) :: st  !! the mass
      real(wp), intent(in) :: m                !! its mass [kg/m^2 A]
      real(wp), intent(in) :: k                !! cushion stiffness [Pa/m A]
      real(wp), intent(in) :: z                !! impedance of the end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: g                !! gravity along +x [m/s^2]
      real(wp), intent(in) :: sigma            !! side (+1 top, -1 bottom)
      real(wp), intent(in) :: w                !! the face's velocity without contact [m/s]
      real(wp), intent(in) :: rest             !! what is left of the step [s]
      real(wp), intent(in) :: v_tol            !! a speed within this of 0 is none [m/s]
      real(wp), intent(in) :: c_tol            !! the cushion lets go when its compression
                                               !! falls below -c_tol: a force within round-off
                                               !! of the contact stresses is none [m]
      real(wp), intent(out) :: s               !! the phase's length [s]
      real(wp), intent(out) :: dq              !! integral of p over it [Pa s A]
      real(wp), intent(out) :: p_end           !! p at its end [Pa A]
      real(wp) :: a, b, cs, us, y(2), yi(2), c_end, lo, hi, mid, c_lo, c_hi, ds
      integer :: j, it, samples
      logical :: found
      a = k / z
      b = k / m
      cs = sigma * g / b          ! equilibrium compression c* = h / b
      us = a * cs                 ! and u* = a c*
      y = [max(-st%gap, 0.0_wp) - cs, sigma * (st%v - w) - us]
      ! released at once: no compression, and the mass moving away or at rest with gravity
      ! not pressing it into the cushion
      if (.not. (y(1) + cs > 0.0_wp) .and. (y(2) + us < -v_tol .or. &
          (.not. (y(2) + us > v_tol) .and. .not. (sigma * g > 0.0_wp)))) then
         s = 0.0_wp
         dq = 0.0_wp
         p_end = 0.0_wp
         st%gap = 0.0_wp
         st%touching = .false.
         return
      end if
      ! the first return of c to 0 within the rest: sampled, then bisected
      s = rest
      found = .false.
      lo = 0.0_wp
      c_lo = y(1) + cs
      ! a few samples per cushion period and damping time, so no return is stepped over
      samples = int(min(4096.0_wp, max(real(root_samples, wp), 4.0_wp * rest * (sqrt(b) + a))))
      ds = rest / real(samples, wp)
      do j = 1, samples
         hi = ds * real(j, wp)
         c_hi = cs + propagate(y, a, b, hi, 1)
         if (c_hi < -c_tol .and. hi > 0.0_wp) then
            found = .true.
            exit
         end if
         lo = hi
         c_lo = c_hi
      end do
      if (found) then
         ! c_lo >= 0 > c_hi (c_lo may be 0 at lo = 0: the mass starts leaving the cushion)
         do it = 1, 200
            mid = 0.5_wp * (lo + hi)
            if (.not. (mid > lo .and. mid < hi)) exit
            if (cs + propagate(y, a, b, mid, 1) < 0.0_wp) then
               hi = mid
            else
               lo = mid
            end if
         end do
         s = hi
         if (.not. (c_lo > 0.0_wp) .and. lo <= 0.0_wp) s = 0.0_wp
      end if
      ! the state and the integrals at s
      yi = integral(y, a, b, s)
      c_end = cs + propagate(y, a, b, s, 1)
      dq = k * (cs * s + yi(1))
      st%x = st%x + w * s + sigma * (us * s + yi(2))
      st%v = w + sigma * (us + propagate(y, a, b, s, 2))
      if (found) then
         st%gap = 0.0_wp
         st%touching = .false.
         p_end = 0.0_wp
      else
         st%gap = -max(c_end, 0.0_wp)
         p_end = k * max(c_end, 0.0_wp)
      end if
   end subroutine cushion_phase

   !> Component i of e^{A s} y, A = [[-a, 1], [-b, 0]].
   pure real(wp) function propagate(y, a, b, s, i) result(yi)
      real(wp), intent(in) :: y(2)             !! the deviation at 0
      real(wp), intent(in) :: a                !! k/Z [1/s]
      real(wp), intent(in) :: b                !! k/M [1/s^2]
      real(wp), intent(in) :: s                !! time [s]
      integer, intent(in) :: i                 !! component
      real(wp) :: ec, es, v(2)
      call exp_parts(a, b, s, ec, es)
      ! e^{A s} = EC I + ES (A + a/2 I), A + a/2 I = [[-a/2, 1], [-b, a/2]]
      v(1) = ec * y(1) + es * (-0.5_wp * a * y(1) + y(2))
      v(2) = ec * y(2) + es * (-b * y(1) + 0.5_wp * a * y(2))
      yi = v(i)
   end function propagate

   !> The integral over [0, s] of e^{A s'} y: A^{-1} (e^{A s} - I) y, A^{-1} = [[0, -1],
   !> [b, -a]] / b.
   pure function integral(y, a, b, s) result(yi)
      real(wp), intent(in) :: y(2)             !! the deviation at 0
      real(wp), intent(in) :: a                !! k/Z [1/s]
      real(wp), intent(in) :: b                !! k/M [1/s^2]
      real(wp), intent(in) :: s                !! time [s]
      real(wp) :: yi(2)
      real(wp) :: d(2)
      d(1) = propagate(y, a, b, s, 1) - y(1)
      d(2) = propagate(y, a, b, s, 2) - y(2)
      yi(1) = -d(2) / b
      yi(2) = (b * d(1) - a * d(2)) / b
   end function integral

   !> e^{-a s/2} C(s) and e^{-a s/2} S(s) of e^{A s} = e^{-a s/2} [C I + S (A + a/2 I)]:
   !> C = cosh(mu s), S = sinh(mu s)/mu with mu^2 = a^2/4 - b (cos and sin for mu^2 < 0;
   !> a series where mu^2 s^2 is small, critical damping included), the exponentials
   !> combined so that a stiff overdamped cushion does not overflow.
   pure subroutine exp_parts(a, b, s, ec, es)
      real(wp), intent(in) :: a                !! k/Z [1/s]
      real(wp), intent(in) :: b                !! k/M [1/s^2]
      real(wp), intent(in) :: s                !! time [s]
      real(wp), intent(out) :: ec              !! e^{-a s/2} C [-]
      real(wp), intent(out) :: es              !! e^{-a s/2} S [s]
      real(wp) :: m2, x, mu, ep, em, damp
      m2 = 0.25_wp * a**2 - b
      x = m2 * s**2
      if (abs(x) < 1.0e-2_wp) then
         damp = exp(-0.5_wp * a * s)
         ec = damp * (1.0_wp + x / 2.0_wp * (1.0_wp + x / 12.0_wp * (1.0_wp + x / 30.0_wp * &
              (1.0_wp + x / 56.0_wp * (1.0_wp + x / 90.0_wp)))))
         es = damp * s * (1.0_wp + x / 6.0_wp * (1.0_wp + x / 20.0_wp * (1.0_wp + x / 42.0_wp * &
              (1.0_wp + x / 72.0_wp * (1.0_wp + x / 110.0_wp)))))
      else if (m2 > 0.0_wp) then
         mu = sqrt(m2)
         ep = exp((mu - 0.5_wp * a) * s)
         em = exp(-(mu + 0.5_wp * a) * s)
         ec = 0.5_wp * (ep + em)
         es = 0.5_wp * (ep - em) / mu
      else
         mu = sqrt(-m2)
         damp = exp(-0.5_wp * a * s)
         ec = damp * cos(mu * s)
         es = damp * sin(mu * s) / mu
      end if
   end subroutine exp_parts
end module spb_impactor
