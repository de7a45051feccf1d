!> Formatting helpers shared by messages, the deck echo and the outputs.
module spb_strings
   use, intrinsic :: iso_fortran_env, only: int64, real128
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use spb_kinds, only: wp
   implicit none
   private
   public :: itoa, rtoa, lower, ltoa, es20_12, es_into, int_right, int_into

   interface itoa
      module procedure itoa_default, itoa_int64
   end interface itoa

   integer, parameter :: qp = real128   !! es20_12's wide arithmetic (113-bit significand)
   !> '00', '01', ..., '99': pair p at 2 p + 1
   character(len=200), parameter :: digit_pairs = &
      '00010203040506070809101112131415161718192021222324252627282930313233343536373839' // &
      '40414243444546474849505152535455565758596061626364656667686970717273747576777879' // &
      '8081828384858687888990919293949596979899'

contains

   !> x as Fortran's ES20.12E3 edit would write it (gfortran: correctly rounded to 13
   !> significant digits, ties to even), without the run-time library's formatted I/O: the
   !> output columns are most of a run's cost otherwise. The 13 digits come from es_digits;
   !> only a value that is not finite, or one whose rounding es_digits cannot decide (within
   !> 1e-18 of a tie after a 10^k that is not exact, never met in practice), goes through
   !> write(es20.12e3). tests/test_format.pf compares both on random bit patterns, decades'
   !> edges, ties and subnormals.
   pure function es20_12(x) result(out)
      real(wp), intent(in) :: x            !! the number
      character(len=20) :: out
      call es_into(x, out)
   end function es20_12

   !> es20_12 written in place into a row's field of 20 characters (no function result to
   !> copy: a run's rows hold millions of them).
   pure subroutine es_into(x, out)
      real(wp), intent(in) :: x            !! the number
      ! the caller's part of a row receives the text
      ! allow(assumed-size-character-intent)
      character(len=*), intent(out) :: out   !! the field (20 characters)
      integer(int64) :: m, hi7
      integer :: e, k, lo6, hi6
      logical :: ok
      if (.not. ieee_is_finite(x)) then
         write(out, '(es20.12e3)') x
         return
      end if
      if (.not. (abs(x) > 0.0_wp)) then
         out = merge('-0.000000000000E+000', ' 0.000000000000E+000', sign(1.0_wp, x) < 0.0_wp)
         return
      end if
      call es_digits(abs(x), m, e, ok)
      if (.not. ok) then
         write(out, '(es20.12e3)') x
         return
      end if
      ! m has 13 digits: d.dddddddddddd, the last 12 as two groups of 6 in pairs
      out(1:1) = merge('-', ' ', x < 0.0_wp)
      hi7 = m / 1000000_int64
      lo6 = int(m - hi7 * 1000000_int64)
      k = int(hi7 / 1000000_int64)
      hi6 = int(hi7) - 1000000 * k
      out(2:2) = achar(48 + k)
      out(3:3) = '.'
      out(4:9) = six_digits(hi6)
      out(10:15) = six_digits(lo6)
      out(16:16) = 'E'
      out(17:17) = merge('-', '+', e < 0)
      k = abs(e)
      out(18:18) = achar(48 + k / 100)
      out(19:20) = pair(mod(k, 100))
   end subroutine es_into

   !> The six decimal digits of 0 <= v < 10^6, leading zeros kept.
   pure function six_digits(v) result(d)
      integer, intent(in) :: v   !! the value
      character(len=6) :: d
      integer :: p, q
      p = v / 10000
      q = v - 10000 * p
      d(1:2) = pair(p)
      d(3:4) = pair(q / 100)
      d(5:6) = pair(mod(q, 100))
   end function six_digits

   !> The two decimal digits of 0 <= p < 100.
   pure function pair(p) result(d)
      integer, intent(in) :: p   !! the value
      character(len=2) :: d
      d = digit_pairs(2 * p + 1:2 * p + 2)
   end function pair

   !> a > 0 (finite) as m 10^(e-12) with 10^12 <= m < 10^13, m the correctly rounded
   !> (ties to even) 13-digit mantissa. With 0 <= k = 12 - e <= 22 (1e-10 <= a < 1e13) 10^k
   !> is exact and a 10^k = hi + lo exactly (Dekker's product), which decides the decade and
   !> the rounding exactly (es_scaled). Otherwise a 10^k is formed in 113-bit arithmetic
   !> from 10^k rounded to 113 bits (relative error below 2^-112, 2e-21 at 10^13): the
   !> rounding is decided unless the scaled value lies within 1e-18 of a tie (ok false).
   pure subroutine es_digits(a, m, e, ok)
      real(wp), intent(in) :: a            !! the magnitude, > 0 and finite
      integer(int64), intent(out) :: m     !! the 13 digits
      integer, intent(out) :: e            !! the decimal exponent
      logical, intent(out) :: ok           !! m and e are decided
      integer :: j, k, step, be
      real(qp) :: q, r
      !> 10^k correctly rounded to 113 bits (compile time; checked against exact fractions)
      !> for every k that ES20.12 of a double needs: 12 - e, e = -324 (subnormals) .. 308
      real(qp), parameter :: pow10_q(-300:340) = [(10.0_qp**k, k = -300, 340)]
      ! the decade from the binary exponent (within one; corrected below): exponent(a) - 1,
      ! read from the bits where a is normal (exponent() is a library call)
      be = int(ibits(transfer(a, 0_int64), 52, 11))
      if (be == 0) be = exponent(a) + 1022
      e = floor(real(be - 1023, wp) * 0.30102999566398120_wp)
      ok = .false.
      m = 0
      do j = 1, 3
         k = 12 - e
         if (k >= 0 .and. k <= 22) then
            call es_scaled(a, k, m, step)
         else if (k >= lbound(pow10_q, 1) .and. k <= ubound(pow10_q, 1)) then
            q = real(a, qp) * pow10_q(k)
            step = 0
            if (q >= 1.0e13_qp) then
               step = 1
            else if (q < 1.0e12_qp) then
               step = -1
            else
               r = anint(q)
               if (abs(q - r) > 0.5_qp - 1.0e-18_qp) return
               m = int(r, int64)
            end if
         else
            return
         end if
         if (step == 0) then
            if (m >= 10000000000000_int64) then         ! rounded up into the next decade
               m = 1000000000000_int64
               e = e + 1
            end if
            ok = .true.
            return
         end if
         e = e + step
      end do
   end subroutine es_digits

   !> a 10^k (0 <= k <= 22, so 10^k exact) rounded to an integer, ties to even, when it lies
   !> in [10^12, 10^13) (step 0); step +1 above, -1 below. hi = fl(a 10^k) and, where it
   !> matters, lo = a 10^k - hi exactly (Dekker's product); hi - anint(hi) is exact.
   pure subroutine es_scaled(a, k, m, step)
      real(wp), intent(in) :: a            !! the magnitude, > 0
      integer, intent(in) :: k             !! the power of ten, 0..22
      integer(int64), intent(out) :: m     !! the rounded value (step 0)
      integer, intent(out) :: step         !! 0: in the decade; +1: above it; -1: below it
      real(wp), parameter :: splitter = 134217729.0_wp          ! 2^27 + 1
      real(wp) :: p, hi, lo, r, f, ah, al, ph, pl, t
      integer(int64) :: m0
      integer :: j
      real(wp), parameter :: pow10(0:22) = [(10.0_wp**j, j = 0, 22)]   ! exact
      p = pow10(k)
      hi = a * p
      step = 0
      m = 0
      ! lo is below half an ulp of hi (< 1e-3 here): only the decade's edges and ties need it.
      ! hi < 1e15 (the decade is known within one): its integer part m0 and fraction t are
      ! exact, and anint(hi) is m0 or m0 + 1 (without the library's round)
      if (hi >= 1.0e13_wp + 1.0_wp) then
         step = 1                    ! clearly above the decade (the estimate was one low)
         return
      else if (hi < 1.0e12_wp - 1.0_wp) then
         step = -1
         return
      else if (hi > 1.0e12_wp + 1.0_wp .and. hi < 1.0e13_wp - 1.0_wp) then
         m0 = int(hi, int64)
         t = hi - real(m0, wp)
         if (t < 0.499_wp) then
            m = m0
            return
         else if (t > 0.501_wp) then
            m = m0 + 1
            return
         end if
      end if
      r = anint(hi)
      f = hi - r
      call split(a, ah, al)
      call split(p, ph, pl)
      lo = ((ah * ph - hi) + ah * pl + al * ph) + al * pl
      ! the decade: 10^12 <= hi + lo < 10^13 (the signs of these sums are exact)
      if ((hi - 1.0e13_wp) + lo >= 0.0_wp) then
         step = 1
         return
      else if ((hi - 1.0e12_wp) + lo < 0.0_wp) then
         step = -1
         return
      end if
      ! f and lo are multiples of, and below half of, ulp(hi): hi + lo rounds to r unless
      ! f = -1/2 (anint took the half up); there lo decides, and lo = 0 is a tie
      m = int(r, int64)
      if (f <= -0.5_wp) then
         if (lo < 0.0_wp .or. (.not. (lo > 0.0_wp) .and. mod(m, 2_int64) == 1_int64)) m = m - 1
      end if
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
   end subroutine es_scaled

   !> k right-justified in w characters, as the I<w> edit writes it (w <= 20).
   pure function int_right(k, w) result(out)
      integer, intent(in) :: k   !! the integer
      integer, intent(in) :: w   !! field width in characters (<= 20)
      character(len=w) :: out
      call int_into(k, out)
   end function int_right

   !> k right-justified in the field, as the I<w> edit writes it with w = len(field) (<= 20),
   !> written in place (no temporary of run-time length).
   pure subroutine int_into(k, field)
      integer, intent(in) :: k   !! the integer
      ! the caller's part of a row receives the digits
      ! allow(assumed-size-character-intent)
      character(len=*), intent(out) :: field   !! the field
      integer(int64) :: m, q
      integer :: j, r
      m = abs(int(k, int64))
      field = ' '
      j = len(field)
      ! two digits per division while two are left and fit
      do while (m >= 10_int64 .and. j >= 2)
         q = m / 100_int64
         r = int(m - 100_int64 * q)
         field(j - 1:j) = pair(r)
         j = j - 2
         m = q
      end do
      ! the last digit (0 for k = 0; the lowest digit left where the field is too narrow)
      if ((m > 0 .or. j == len(field)) .and. j >= 1) then
         field(j:j) = achar(48 + int(mod(m, 10_int64)))
         j = j - 1
      end if
      if (k < 0 .and. j >= 1) field(j:j) = '-'
   end subroutine int_into

   !> Integer as text, no blanks (the I0 edit's text, without the run-time library's
   !> formatted I/O: a deck's checks and echo format hundreds of them).
   pure function itoa_default(k) result(s)
      integer, intent(in) :: k   !! the integer
      character(len=:), allocatable :: s
      character(len=24) :: buf
      call int_into(k, buf)
      s = trim(adjustl(buf))
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

   !> Shortest decimal text that reads back as exactly the same real (up to 17 digits): the
   !> fewest significant digits d whose correctly rounded ES form reads back as x, tidied.
   !> Where the reals that read back as x lie symmetrically about it (every x but a power of
   !> two, whose lower neighbour is half as far as its upper one), a form with more digits
   !> reads back as x whenever one with fewer does (the nearest (d+1)-digit decimal is at
   !> least as near as the nearest d-digit one), so d is found by bisection, in 5 trials
   !> instead of up to 17; a power of two tries d = 1, 2, ... in turn, as every x did before.
   !> tests/test_format.pf compares both searches on random bit patterns, powers of two,
   !> decimals and subnormals.
   function rtoa(x) result(s)
      real(wp), intent(in) :: x            !! the number
      character(len=:), allocatable :: s
      character(len=40) :: buf, found
      integer :: d, lo, hi
      logical :: same
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
      if (ibits(transfer(x, 0_int64), 0, 52) == 0_int64) then   ! a power of two (or zero)
         do d = 1, 17
            call try(d, buf, same)
            if (same) exit
         end do
         found = buf
      else
         lo = 1
         hi = 17
         found = ''
         do while (lo < hi)
            d = (lo + hi) / 2
            call try(d, buf, same)
            if (same) then
               hi = d
               found = buf
            else
               lo = d + 1
            end if
         end do
         ! found holds the form of d = hi, unless no trial read back: then hi = 17, written
         ! here (17 digits always read back)
         if (len_trim(found) == 0) call try(hi, found, same)
      end if
      s = trim(adjustl(found))
      call tidy(s)
   contains
      !> buf: x in ES form with d significant digits; same: it reads back as x.
      subroutine try(d, buf, same)
         integer, intent(in) :: d              !! significant digits, 1..17
         character(len=40), intent(out) :: buf   !! the ES form
         logical, intent(out) :: same          !! buf reads back as x, bit for bit
         real(wp) :: back
         write(buf, es_format(d)) x
         read(buf, *) back
         same = transfer(back, 0_int64) == transfer(x, 0_int64)
      end subroutine try
   end function rtoa

   !> The ES edit with d significant digits, '(es9.0e3)' ... '(es25.16e3)'.
   pure function es_format(d) result(fmt)
      integer, intent(in) :: d             !! significant digits, 1..17
      character(len=12) :: fmt
      character(len=12), parameter :: formats(17) = [character(len=12) :: '(es9.0e3)', &
         '(es10.1e3)', '(es11.2e3)', '(es12.3e3)', '(es13.4e3)', '(es14.5e3)', '(es15.6e3)', &
         '(es16.7e3)', '(es17.8e3)', '(es18.9e3)', '(es19.10e3)', '(es20.11e3)', &
         '(es21.12e3)', '(es22.13e3)', '(es23.14e3)', '(es24.15e3)', '(es25.16e3)']
      fmt = formats(d)
   end function es_format

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
