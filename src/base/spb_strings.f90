!> Formatting helpers shared by messages, the deck echo and the outputs.
module spb_strings
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use spb_kinds, only: wp
   implicit none
   private
   public :: itoa, rtoa, lower, ltoa, es20_12, int_right

   interface itoa
      module procedure itoa_default, itoa_int64
   end interface itoa

contains

   !> x as Fortran's ES20.12E3 edit would write it (correctly rounded, 13 significant
   !> digits), without the run-time library's formatted I/O: the output columns are most of
   !> a run's cost otherwise. x 10^k is formed exactly as hi + lo (Dekker's product; 10^k is
   !> exact for 0 <= k <= 22, so 1e-10 <= |x| < 1e13); a value whose rounding is not decided
   !> by hi alone (within 1e-4 of a tie), outside that range, or not finite, goes through
   !> write(es20.12e3).
   !> tests/test_format.pf compares both on a million values.
   pure function es20_12(x) result(out)
      real(wp), intent(in) :: x            !! the number
      character(len=20) :: out
      integer :: e, k, j
      real(wp), parameter :: pow10(0:22) = [(10.0_wp**k, k = 0, 22)]
      real(wp), parameter :: splitter = 134217729.0_wp          ! 2^27 + 1
      real(wp) :: a, p, hi, lo, r, ah, al, ph, pl
      integer(int64) :: m
      if (.not. ieee_is_finite(x)) then
         write(out, '(es20.12e3)') x
         return
      end if
      if (.not. (abs(x) > 0.0_wp)) then
         out = merge('-0.000000000000E+000', ' 0.000000000000E+000', sign(1.0_wp, x) < 0.0_wp)
         return
      end if
      a = abs(x)
      ! the decade from the binary exponent (within one; corrected below)
      e = floor(real(exponent(a) - 1, wp) * 0.30102999566398120_wp)
      do j = 1, 3
         k = 12 - e
         if (k < 0 .or. k > 22) exit
         ! hi + lo = a 10^k exactly; lo (at most half an ulp of hi, < 1e-3) only matters
         ! next to a decade edge or a rounding tie
         p = pow10(k)
         hi = a * p
         r = anint(hi)
         if (hi > 1.0e12_wp + 1.0_wp .and. hi < 1.0e13_wp - 1.0_wp .and. &
             abs(hi - r) < 0.499_wp) then
            lo = 0.0_wp
         else
            call split(a, ah, al)
            call split(p, ph, pl)
            lo = ((ah * ph - hi) + ah * pl + al * ph) + al * pl
            ! the decade: 10^12 <= hi + lo < 10^13 (compared exactly)
            if ((hi - 1.0e13_wp) + lo >= 0.0_wp) then
               e = e + 1
               cycle
            else if ((hi - 1.0e12_wp) + lo < 0.0_wp) then
               e = e - 1
               cycle
            end if
         end if
         if (abs(hi - r) + abs(lo) > 0.4999_wp) exit      ! too close to a tie
         if (r >= 1.0e13_wp) then                         ! rounded up into the next decade
            r = 1.0e12_wp
            e = e + 1
         end if
         m = int(r, int64)
         out(1:1) = merge('-', ' ', x < 0.0_wp)
         out(2:2) = achar(48 + int(m / 1000000000000_int64))
         out(3:3) = '.'
         do k = 15, 4, -1
            out(k:k) = achar(48 + int(mod(m, 10_int64)))
            m = m / 10_int64
         end do
         out(16:16) = 'E'
         out(17:17) = merge('-', '+', e < 0)
         k = abs(e)
         out(18:18) = achar(48 + k / 100)
         out(19:19) = achar(48 + mod(k / 10, 10))
         out(20:20) = achar(48 + mod(k, 10))
         return
      end do
      write(out, '(es20.12e3)') x
   contains
      !> Dekker's split of v into a high part vh and a low part vl = v - vh, exactly.
      pure subroutine split(v, vh, vl)
         real(wp), intent(in) :: v     !! the value to split
         real(wp), intent(out) :: vh   !! its high part
         real(wp), intent(out) :: vl   !! its low part, v - vh
         real(wp) :: c
         c = splitter * v
         vh = c - (c - v)
         vl = v - vh
      end subroutine split
   end function es20_12

   !> k right-justified in w characters, as the I<w> edit writes it (w <= 20).
   pure function int_right(k, w) result(out)
      integer, intent(in) :: k   !! the integer
      integer, intent(in) :: w   !! field width in characters (<= 20)
      character(len=w) :: out
      integer(int64) :: m
      integer :: j
      m = abs(int(k, int64))
      out = ' '
      j = w
      do
         out(j:j) = achar(48 + int(mod(m, 10_int64)))
         m = m / 10_int64
         j = j - 1
         if (m == 0 .or. j < 1) exit
      end do
      if (k < 0 .and. j >= 1) out(j:j) = '-'
   end function int_right

   !> Integer as text, no blanks.
   pure function itoa_default(k) result(s)
      integer, intent(in) :: k   !! the integer
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') k
      s = trim(buf)
   end function itoa_default

   !> The decimal text of a 64-bit integer.
   pure function itoa_int64(k) result(s)
      integer(int64), intent(in) :: k   !! the integer
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') k
      s = trim(buf)
   end function itoa_int64

   !> Logical as Fortran namelist text.
   pure function ltoa(b) result(s)
      logical, intent(in) :: b   !! the logical
      character(len=:), allocatable :: s
      if (b) then
         s = '.true.'
      else
         s = '.false.'
      end if
   end function ltoa

   !> Shortest decimal text that reads back as exactly the same real (up to 17 digits).
   function rtoa(x) result(s)
      real(wp), intent(in) :: x            !! the number
      character(len=:), allocatable :: s
      character(len=40) :: buf
      character(len=16) :: fmt
      real(wp) :: back
      integer :: d
      if (ieee_is_nan(x)) then
         s = 'NaN'
         return
      else if (.not. ieee_is_finite(x)) then
         if (x > 0) then
            s = 'Infinity'
         else
            s = '-Infinity'
         end if
         return
      end if
      do d = 1, 17
         write(fmt, '(a,i0,a,i0,a)') '(es', d + 8, '.', d - 1, 'e3)'
         write(buf, fmt) x
         read(buf, *) back
         if (transfer(back, 0_int64) == transfer(x, 0_int64)) exit
      end do
      s = trim(adjustl(buf))
      call tidy(s)
   end function rtoa

   !> Turn '1.5E+000' into '1.5', '2.5E-001' into '0.25', '1.25E+010' into '1.25e10'.
   !> Plain decimals for exponents -4..6, otherwise mantissa e exponent.
   subroutine tidy(s)
      character(len=:), allocatable, intent(inout) :: s   !! the string
      integer :: ie, k, ex
      character(len=:), allocatable :: mant, digits, sgn
      ie = scan(s, 'Ee')
      if (ie == 0) return
      read(s(ie+1:), *) ex
      mant = s(:ie-1)
      sgn = ''
      if (mant(1:1) == '-') then
         sgn = '-'
         mant = mant(2:)
      end if
      k = len(mant)
      if (mant(k:k) == '.') mant = mant(:k-1)
      if (ex >= -4 .and. ex <= 6) then
         digits = mant(1:1)
         if (len(mant) > 2) digits = digits // mant(3:)
         if (ex >= 0) then
            if (len(digits) < ex + 1) digits = digits // repeat('0', ex + 1 - len(digits))
            s = sgn // digits(:ex+1)
            if (len(digits) > ex + 1) s = s // '.' // digits(ex+2:)
         else
            s = sgn // '0.' // repeat('0', -ex - 1) // digits
         end if
      else if (ex == 0) then
         s = sgn // mant
      else
         s = sgn // mant // 'e' // itoa(ex)
      end if
   end subroutine tidy

   !> Lower-case copy of a string.
   pure function lower(s) result(r)
      character(len=*), intent(in) :: s    !! the string
      character(len=len(s)) :: r
      integer :: k, ic
      r = s
      do k = 1, len(s)
         ic = iachar(s(k:k))
         if (ic >= iachar('A') .and. ic <= iachar('Z')) r(k:k) = achar(ic + 32)
      end do
   end function lower
end module spb_strings
