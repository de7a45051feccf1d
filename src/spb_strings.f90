!> Formatting helpers shared by messages, the deck echo and the outputs.
module spb_strings
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use spb_kinds, only: wp
   implicit none
   private
   public :: itoa, rtoa, lower, ltoa

   interface itoa
      module procedure itoa_default, itoa_int64
   end interface itoa

contains

   !> Integer as text, no blanks.
   pure function itoa_default(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') k
      s = trim(buf)
   end function itoa_default

   pure function itoa_int64(k) result(s)
      integer(int64), intent(in) :: k
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') k
      s = trim(buf)
   end function itoa_int64

   !> Logical as Fortran namelist text.
   pure function ltoa(b) result(s)
      logical, intent(in) :: b
      character(len=:), allocatable :: s
      if (b) then
         s = '.true.'
      else
         s = '.false.'
      end if
   end function ltoa

   !> Shortest decimal text that reads back as exactly the same real (up to 17 digits).
   function rtoa(x) result(s)
      real(wp), intent(in) :: x
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
      character(len=:), allocatable, intent(inout) :: s
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
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: k, ic
      r = s
      do k = 1, len(s)
         ic = iachar(s(k:k))
         if (ic >= iachar('A') .and. ic <= iachar('Z')) r(k:k) = achar(ic + 32)
      end do
   end function lower
end module spb_strings
