!> Reproducible random numbers: L'Ecuyer's MRG32k3a combined multiple-recursive generator
!> (P. L'Ecuyer, "Good parameters and implementations for combined multiple recursive
!> random number generators", Operations Research 47 (1999) 159-164), in 64-bit integer
!> arithmetic (every product stays below 2^53), so a seed gives the same numbers with any
!> compiler and any optimisation; the intrinsic random_number is never used.
!>
!> Seeding: the six state words are drawn from the seed by a Lehmer generator modulo
!> m1 (multiplier 16807), offset so that no component is zero, and the generator is then
!> advanced 16 steps. Different seeds give unrelated streams in practice (not proven
!> independent substreams; for Monte-Carlo sweeps each realization gets its own seed).
module spb_random
   use, intrinsic :: iso_fortran_env, only: int64
   use spb_kinds, only: wp
   implicit none
   private
   public :: rng_t, rng_seed, rng_uniform, weibull, realization_seed, realization_draw, &
      weibull_log_min, weibull_log_max

   integer(int64), parameter :: m1 = 4294967087_int64, m2 = 4294944443_int64
   integer(int64), parameter :: a12 = 1403580_int64, a13n = 810728_int64
   integer(int64), parameter :: a21 = 527612_int64, a23n = 1370589_int64
   real(wp), parameter :: norm = 1.0_wp / (real(m1, wp) + 1.0_wp)
   !> The extremes of -ln(1 - u) over the numbers rng_uniform gives (u = z norm, z = 1 .. m1):
   !> a Weibull draw scale (-ln(1 - u))^(1/m) lies between scale weibull_log_min^(1/m)
   !> (about 2.3e-10) and scale weibull_log_max^(1/m) (about 22.18 = ln(m1 + 1)).
   real(wp), parameter :: weibull_log_min = -log(1.0_wp - norm)
   real(wp), parameter :: weibull_log_max = -log(1.0_wp - real(m1, wp) * norm)

   !> Generator state: (s10, s11, s12) modulo m1 and (s20, s21, s22) modulo m2.
   type :: rng_t
      integer(int64) :: s1(3) = [12345_int64, 12345_int64, 12345_int64]
      integer(int64) :: s2(3) = [12345_int64, 12345_int64, 12345_int64]
   end type rng_t

contains

   !> A generator started from an integer seed (any value; negative ones are folded).
   pure function rng_seed(seed) result(g)
      integer, intent(in) :: seed   !! the seed (any value)
      type(rng_t) :: g
      integer(int64) :: x
      real(wp) :: u
      integer :: k
      x = modulo(int(seed, int64), m1 - 1_int64) + 1_int64
      do k = 1, 3
         x = modulo(16807_int64 * x, 2147483647_int64)
         g%s1(k) = modulo(x + int(k, int64), m1)
         x = modulo(16807_int64 * x, 2147483647_int64)
         g%s2(k) = modulo(x + int(k, int64), m2)
      end do
      do k = 1, 16
         call rng_uniform(g, u)
      end do
   end function rng_seed

   !> Next number, uniform in (0, 1) (never 0 or 1).
   pure subroutine rng_uniform(g, u)
      type(rng_t), intent(inout) :: g      !! the generator
      real(wp), intent(out) :: u           !! the number, in (0, 1)
      integer(int64) :: p1, p2, z
      p1 = modulo(a12 * g%s1(2) - a13n * g%s1(1), m1)
      g%s1 = [g%s1(2), g%s1(3), p1]
      p2 = modulo(a21 * g%s2(3) - a23n * g%s2(1), m2)
      g%s2 = [g%s2(2), g%s2(3), p2]
      z = modulo(p1 - p2, m1)
      if (z == 0_int64) z = m1
      u = real(z, wp) * norm
   end subroutine rng_uniform

   !> A Weibull sample by inversion: scale (-ln(1 - u))^(1/modulus), for u in (0, 1).
   pure elemental real(wp) function weibull(u, modulus, scale) result(x)
      real(wp), intent(in) :: u         !! uniform number in (0, 1)
      real(wp), intent(in) :: modulus   !! Weibull modulus [-]
      real(wp), intent(in) :: scale     !! Weibull scale, in the sample's unit (strengths: Pa)
      x = scale * (-log(1.0_wp - u))**(1.0_wp / modulus)
   end function weibull

   !> Seed of realization i (1, 2, ...) of a sweep with base seed `seed`:
   !> 1 + mod(mod(seed, p) * 69621 + i * 48271, p - 1) with p = 2^31 - 1, in 64-bit integers
   !> (no overflow, no compiler dependence). 48271 is prime and does not divide p - 1, so for
   !> one base seed the realizations 1 .. p - 1 all get different seeds; rng_seed scrambles
   !> each further. The .sweep table prints it: any realization re-runs
   !> alone as an ordinary deck with &strength_field seed = that value.
   pure integer function realization_seed(seed, i) result(s)
      integer, intent(in) :: seed   !! base seed of the sweep
      integer, intent(in) :: i      !! realization (1, 2, ...)
      integer(int64), parameter :: p = 2147483647_int64
      s = int(1_int64 + modulo(modulo(int(seed, int64), p) * 69621_int64 + &
                               int(i, int64) * 48271_int64, p - 1_int64))
   end function realization_seed

   !> The perturbation of realization i (1, 2, ...) of a sweep with base seed `seed` (&sweep
   !> perturb): 2 u - 1 for the first number u of the generator seeded with
   !> realization_seed(seed, i), uniform in (-1, 1) and a function of (seed, i) alone [-].
   pure real(wp) function realization_draw(seed, i) result(x)
      integer, intent(in) :: seed   !! base seed of the sweep
      integer, intent(in) :: i      !! realization (1, 2, ...)
      type(rng_t) :: g
      real(wp) :: u
      g = rng_seed(realization_seed(seed, i))
      call rng_uniform(g, u)
      x = 2.0_wp * u - 1.0_wp
   end function realization_draw
end module spb_random
