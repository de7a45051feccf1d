!> End loads in the "stepwise form" (doc/method.md, "Loads in the stepwise form"): the
!> pressure applied at t^n is the mean of p(t) over the two steps around t^n, integrated
!> analytically.
module spb_load
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp
   use spb_problem, only: problem_t, load_none, load_power, load_table, load_exponential, &
      face_top, face_bottom
   implicit none
   private
   public :: load_t, load_none, load_power, load_table, load_exponential, face_top, face_bottom
   public :: build_load, load_integral, step_load


   type :: load_t
      integer :: kind = load_none         !! load_none | load_power | load_table
      integer :: face = face_top          !! face_top | face_bottom
      real(wp) :: p0 = 0.0_wp             !! [Pa A]: the force on the face (spb_mesh)
      real(wp) :: t_k = 0.0_wp            !! [s]; 0: constant pressure (exponent 0)
      real(wp) :: exponent = 0.0_wp       !! [-]
      real(wp) :: t_cut = huge(1.0_wp)    !! [s] p = 0 after
      real(wp), allocatable :: t(:)       !! table times [s], non-decreasing
      real(wp), allocatable :: p(:)       !! table pressures times the face's area [Pa A]
   end type load_t

contains

   !> The end load of the problem (a table's rows come with it, read by spb_load_table), as
   !> the force on the loaded face: the pressure times its cell's cross-section (spb_mesh:
   !> the model's stresses are forces).
   pure subroutine build_load(prob, load)
      type(problem_t), intent(in) :: prob   !! the problem
      type(load_t), intent(out) :: load    !! the end load
      real(wp) :: area
      area = 1.0_wp
      if (allocated(prob%area)) then
         area = prob%area(1)
         if (prob%load_face == face_bottom) area = prob%area(prob%nseg)
      end if
      load%face = prob%load_face
      select case (prob%load_kind)
      case (load_power)
         load%kind = load_power
         load%p0 = prob%p0 * area
         load%exponent = prob%exponent
         if (prob%has_t_k) load%t_k = prob%t_k
         if (prob%has_t_cut) then
            load%t_cut = prob%t_cut
         else if (prob%has_t_k) then
            load%t_cut = prob%t_k
         end if
      case (load_exponential)
         load%kind = load_exponential
         load%p0 = prob%p0 * area
         load%t_k = prob%t_k
         if (prob%has_t_cut) load%t_cut = prob%t_cut
      case (load_table)
         load%kind = load_table
         load%t = prob%table_t
         load%p = prob%table_p * area
      case default
         load%kind = load_none
      end select
   end subroutine build_load

   !> log(1 + x) accurate for small x (Goldberg's correction; F2008 has no log1p).
   pure elemental real(wp) function log1p_acc(x) result(r)
      real(wp), intent(in) :: x   !! argument, > -1 [-]
      real(wp) :: w, d
      w = 1.0_wp + x
      d = w - 1.0_wp
      if (.not. (abs(d) > 0.0_wp)) then
         r = x
      else
         r = log(w) * (x / d)
      end if
   end function log1p_acc

   !> exp(x) - 1 accurate for small x (Kahan's correction; F2008 has no expm1).
   pure elemental real(wp) function expm1_acc(x) result(r)
      real(wp), intent(in) :: x   !! exponent [-]
      real(wp) :: w, d
      w = exp(x)
      d = w - 1.0_wp
      if (.not. (abs(d) > 0.0_wp)) then
         r = x
      else if (.not. (d > -1.0_wp)) then
         r = -1.0_wp
      else
         r = d * (x / log(w))
      end if
   end function expm1_acc

   !> Integral of p(t) over [a, b] (b >= a), exact for both load forms.
   pure real(wp) function load_integral(load, a, b) result(q)
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: a   !! start of the window [s]
      real(wp), intent(in) :: b   !! end of the window [s]
      select case (load%kind)
      case (load_power)
         q = power_integral(load, a, b)
      case (load_table)
         q = table_integral(load%t, load%p, a, b)
      case (load_exponential)
         q = exponential_integral(load, a, b)
      case default
         q = 0.0_wp
      end select
   end function load_integral

   !> Integral of the power-law load over [a, b] [Pa s].
   pure real(wp) function power_integral(load, a, b) result(q)
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: a   !! start of the window [s]
      real(wp), intent(in) :: b   !! end of the window [s]
      real(wp) :: lo, hi, ca, cb, k
      lo = max(a, 0.0_wp)
      hi = min(b, load%t_cut)
      q = 0.0_wp
      if (.not. (hi > lo)) return
      if (load%t_k <= 0.0_wp .or. .not. (load%exponent > 0.0_wp)) then
         q = load%p0 * (hi - lo)
         return
      end if
      ! p0 t_k/(k) [(1 - lo/t_k)**k - (1 - hi/t_k)**k], k = exponent + 1, written as
      ! ca**k * (1 - (cb/ca)**k) with expm1/log1p so that short windows keep all digits.
      k = load%exponent + 1.0_wp
      ca = 1.0_wp - lo / load%t_k
      cb = 1.0_wp - hi / load%t_k
      if (ca <= 0.0_wp) return
      if (cb <= 0.0_wp) then
         q = load%p0 * load%t_k / k * ca**k
      else
         q = -load%p0 * load%t_k / k * ca**k * expm1_acc(k * log1p_acc(-(hi - lo) / (load%t_k * ca)))
      end if
   end function power_integral

   !> p0 exp(-t/t_k) on [0, t_cut]: p0 t_k exp(-lo/t_k) (1 - exp(-(hi - lo)/t_k)).
   pure real(wp) function exponential_integral(load, a, b) result(q)
      type(load_t), intent(in) :: load     !! the end load
      real(wp), intent(in) :: a   !! start of the window [s]
      real(wp), intent(in) :: b   !! end of the window [s]
      real(wp) :: lo, hi
      lo = max(a, 0.0_wp)
      hi = min(b, load%t_cut)
      q = 0.0_wp
      if (.not. (hi > lo)) return
      q = -load%p0 * load%t_k * exp(-lo / load%t_k) * expm1_acc(-(hi - lo) / load%t_k)
   end function exponential_integral

   !> Integral of the piecewise-linear table over [a, b]; p = 0 outside the table.
   pure real(wp) function table_integral(t, p, a, b) result(q)
      real(wp), intent(in) :: t(:)   !! table times [s], non-decreasing
      real(wp), intent(in) :: p(:)   !! table pressures [Pa]
      real(wp), intent(in) :: a      !! start of the window [s]
      real(wp), intent(in) :: b      !! end of the window [s]
      integer :: i, lo_i, hi_i, mid
      real(wp) :: x0, x1, slope, p_at0, p_at1
      q = 0.0_wp
      if (.not. (b > a)) return
      if (b <= t(1) .or. a >= t(size(t))) return
      ! first interval i with t(i+1) > a
      lo_i = 1
      hi_i = size(t) - 1
      do while (lo_i < hi_i)
         mid = (lo_i + hi_i) / 2
         if (t(mid + 1) > a) then
            hi_i = mid
         else
            lo_i = mid + 1
         end if
      end do
      do i = lo_i, size(t) - 1
         if (t(i) >= b) exit
         if (.not. (t(i + 1) > t(i))) cycle       ! a jump: no width
         x0 = max(a, t(i))
         x1 = min(b, t(i + 1))
         if (.not. (x1 > x0)) cycle
         slope = (p(i + 1) - p(i)) / (t(i + 1) - t(i))
         p_at0 = p(i) + slope * (x0 - t(i))
         p_at1 = p(i) + slope * (x1 - t(i))
         q = q + 0.5_wp * (p_at0 + p_at1) * (x1 - x0)
      end do
   end function table_integral

   !> The stepwise load P^n = (1/(2 dt)) * integral of p from t^(n-1) to t^(n+1)  (ref [5]).
   pure real(wp) function step_load(load, n, dt) result(pn)
      type(load_t), intent(in) :: load     !! the end load
      integer, intent(in) :: n         !! step index
      real(wp), intent(in) :: dt       !! time step [s]
      pn = load_integral(load, real(n - 1, wp) * dt, real(n + 1, wp) * dt) / (2.0_wp * dt)
   end function step_load
end module spb_load
