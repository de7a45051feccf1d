!> Naive Fortran reference of the compact scheme (2.3) for bench/run.py's intact bar: the
!> loop anyone would write first. Half-node model of one material (E = 2e11 Pa,
!> rho = 8000 kg/m^3, dt = 1e-6 s, dx = a dt = 5 mm), free ends, the power-law load
!> p0 (1 - t/t_k) on the top face in its stepwise form (doc/method.md, "Loads in the stepwise
!> form"), no gravity; two loops over the bar per step, no blocking. bench/run.py compiles it
!> with spallbar's Release flags.
!>
!>     P^n      = (1/(2 dt)) integral of p over [t^(n-1), t^(n+1)]
!>     du^(n+1) = du^n + (s_i - s_(i+1)) dt^2 / m_i      (s_0 = P^n, s_(N+1) = 0)
!>     u^(n+1)  = u^n + du^(n+1)
!>     s^(n+1)  = s^n + (E/dx) (du_(k-1) - du_k)         (cells k = 1..N)
!>
!> usage: naive_ref CELLS STEPS [OUT]: prints the loop's wall time and node-steps/s; OUT gets
!> the final state as a stream of 8-byte integer N, then u(0:N) [m], v(0:N) [m/s] and
!> s(1:N) [Pa] as 8-byte reals (bench/references.py reads it).
program naive_ref
   use, intrinsic :: iso_fortran_env, only: real64, int64, error_unit
   implicit none
   integer, parameter :: wp = real64
   real(wp), parameter :: young = 2.0e11_wp   !! Young's modulus [Pa]
   real(wp), parameter :: rho = 8000.0_wp     !! density [kg/m^3]
   real(wp), parameter :: dt = 1.0e-6_wp      !! time step [s]
   real(wp), parameter :: p0 = 1.0e8_wp       !! load at t = 0 [Pa]
   real(wp), parameter :: t_k = 1.0e-4_wp     !! p = p0 (1 - t/t_k) [s]
   real(wp), parameter :: t_cut = 1.0e-4_wp   !! p = 0 after [s]
   real(wp), allocatable :: u(:)      !! displacement of node 0..N [m]
   real(wp), allocatable :: du(:)     !! its increment over the last step [m]
   real(wp), allocatable :: c(:)      !! dt^2 / m of node 0..N [m^2 s^2/kg]
   real(wp), allocatable :: s(:)      !! stress of cell 1..N; s(0), s(N+1) the faces [Pa]
   real(wp) :: a, dx, dm, stiff, wall
   integer :: n, steps, step, i, k, ios, unit
   integer(int64) :: t0, t1, rate
   character(len=512) :: arg

   if (command_argument_count() < 2) then
      write(error_unit, '(a)') 'usage: naive_ref CELLS STEPS [OUT]'
      error stop 2
   end if
   call get_command_argument(1, arg)
   read(arg, *, iostat=ios) n
   if (ios /= 0 .or. n < 1) error stop 2
   call get_command_argument(2, arg)
   read(arg, *, iostat=ios) steps
   if (ios /= 0 .or. steps < 1) error stop 2

   a = sqrt(young / rho)
   dx = a * dt
   dm = rho * dx
   stiff = young / dx
   allocate(u(0:n), du(0:n), c(0:n), s(0:n + 1))
   u = 0.0_wp
   du = 0.0_wp
   s = 0.0_wp
   c = dt * dt / dm
   c(0) = dt * dt / (0.5_wp * dm)     ! half masses at the free ends
   c(n) = c(0)

   call system_clock(t0, rate)
   do step = 0, steps - 1
      s(0) = stepwise_load(step)
      do i = 0, n
         du(i) = du(i) + (s(i) - s(i + 1)) * c(i)
         u(i) = u(i) + du(i)
      end do
      do k = 1, n
         s(k) = s(k) + stiff * (du(k - 1) - du(k))
      end do
   end do
   call system_clock(t1)
   wall = real(t1 - t0, wp) / real(rate, wp)
   write(*, '(a,i0,a,i0,a,f8.3,a,es9.3,a)') 'naive: ', n, ' cells, ', steps, ' steps, loop', &
      wall, ' s, ', real(n + 1, wp) * real(steps, wp) / max(wall, tiny(1.0_wp)), ' node-steps/s'

   if (command_argument_count() >= 3) then
      call get_command_argument(3, arg)
      open(newunit=unit, file=trim(arg), access='stream', form='unformatted', &
           status='replace', action='write')
      write(unit) int(n, int64), u, du / dt, s(1:n)
      close(unit)
   end if

contains

   !> P^n: the mean of p0 (1 - t/t_k) over [t^(n-1), t^(n+1)], p = 0 outside [0, t_cut] [Pa].
   pure real(wp) function stepwise_load(m) result(p)
      integer, intent(in) :: m   !! step index n
      real(wp) :: lo, hi
      lo = max(real(m - 1, wp) * dt, 0.0_wp)
      hi = min(real(m + 1, wp) * dt, t_cut)
      p = 0.0_wp
      if (hi > lo) p = p0 * (hi - lo) * (1.0_wp - (hi + lo) / (2.0_wp * t_k)) / (2.0_wp * dt)
   end function stepwise_load
end program naive_ref
