!> Fallback for the part of pFUnit's `funit` module that spallbar's .pf tests use.
!>
!> Semantics follow pFUnit 4.14's (doc/build.md, "What pFUnit 4.14 requires of a .pf file"):
!> tolerances are absolute and inclusive, expected comes first, a test stops at its first
!> failing assertion (the translator adds `if (anyExceptions()) return` after each one). The bookkeeping below is the test
!> harness's own state, as in pFUnit; the library under test has none.
module funit
   use, intrinsic :: iso_fortran_env, only: real64, output_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_class, &
      ieee_positive_inf, ieee_negative_inf, ieee_positive_zero, ieee_negative_zero, &
      operator(==)
   implicit none
   private
   public :: assertEqual, assertNotEqual, assertRelativelyEqual, assertTrue, assertFalse
   public :: assertLessThan, assertLessThanOrEqual, assertGreaterThan, assertGreaterThanOrEqual
   public :: assertIsFinite, assertIsNaN, assertFail
   public :: anyExceptions, start_test, end_test, finish_run

   integer, parameter :: dp = real64
   logical :: failed = .false.
   integer :: n_run = 0, n_failed = 0
   character(len=256) :: current = ''
   character(len=*), parameter :: nonfinite_array = 'non-finite array element in ' // &
      'AssertEqual (pFUnit 4.14 stops with SIGFPE here under the Debug traps)'

   interface assertEqual
      module procedure eq_r_r, eq_r_r1, eq_r1_r1, eq_i_i, eq_i1_i1, eq_c_c, eq_l_l
   end interface assertEqual
   interface assertNotEqual
      module procedure ne_i_i
   end interface assertNotEqual
   interface assertRelativelyEqual
      module procedure rel_r_r, rel_r1_r1
   end interface assertRelativelyEqual
   interface assertLessThan
      module procedure lt_r, lt_i
   end interface assertLessThan
   interface assertLessThanOrEqual
      module procedure le_r, le_i
   end interface assertLessThanOrEqual
   interface assertGreaterThan
      module procedure gt_r, gt_i
   end interface assertGreaterThan
   interface assertGreaterThanOrEqual
      module procedure ge_r, ge_i
   end interface assertGreaterThanOrEqual
   interface assertIsFinite
      module procedure finite_r, finite_r1
   end interface assertIsFinite
   interface assertIsNaN
      module procedure nan_r
   end interface assertIsNaN

contains

   logical function anyExceptions()
      anyExceptions = failed
   end function anyExceptions

   subroutine start_test(name)
      character(len=*), intent(in) :: name
      current = name
      failed = .false.
      n_run = n_run + 1
   end subroutine start_test

   subroutine end_test()
      if (failed) then
         n_failed = n_failed + 1
         write(output_unit, '(a)') 'FAILED: ' // trim(current)
      else
         write(output_unit, '(a)') 'passed: ' // trim(current)
      end if
   end subroutine end_test

   subroutine finish_run(only)
      character(len=*), intent(in) :: only
      write(output_unit, '(a,i0,a,i0,a)') 'Tests run: ', n_run, ', Failures: ', n_failed, &
         ', Errors: 0'
      if (len(only) > 0 .and. n_run == 0) then
         write(output_unit, '(a)') 'no test named ''' // only // ''''
         error stop 2
      end if
      if (n_failed > 0) then
         write(output_unit, '(a)') '*** Encountered 1 or more failures/errors during testing ***'
         error stop 2
      end if
   end subroutine finish_run

   subroutine fail(what, message, location)
      character(len=*), intent(in) :: what
      character(len=*), intent(in), optional :: message, location
      character(len=:), allocatable :: text
      failed = .true.
      text = 'Failure'
      if (present(location)) text = text // ' at ' // location
      text = text // ' in ' // trim(current) // ': ' // what
      if (present(message)) text = text // '; ' // message
      write(output_unit, '(a)') text
   end subroutine fail

   function r2s(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write(buf, '(es24.16e3)') x
      s = trim(adjustl(buf))
   end function r2s

   function i2s(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write(buf, '(i0)') k
      s = trim(buf)
   end function i2s

   ! ------------------------------------------------------------------ equality
   subroutine eq_r_r(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected, actual
      real(dp), intent(in), optional :: tolerance
      character(len=*), intent(in), optional :: message, location
      real(dp) :: tol
      tol = 0.0_dp
      if (present(tolerance)) tol = tolerance
      ! pFUnit 4.14 passes equal infinities (Inf = Inf) and fails Inf against anything
      ! else; it never forms Inf - Inf, which the Debug traps would turn into SIGFPE.
      if (.not. (ieee_is_finite(expected) .and. ieee_is_finite(actual))) then
         if (.not. same_infinity(expected, actual)) call fail('expected ' // r2s(expected) // &
            ' but found ' // r2s(actual), message, location)
         return
      end if
      if (.not. (abs(actual - expected) <= tol)) call fail('expected ' // r2s(expected) // &
         ' but found ' // r2s(actual) // ' (difference ' // r2s(abs(actual - expected)) // &
         ' > tolerance ' // r2s(tol) // ')', message, location)
   end subroutine eq_r_r

   !> Both values are the same infinity (no NaN): what pFUnit's scalar assertEqual accepts.
   logical function same_infinity(a, b)
      real(dp), intent(in) :: a, b
      same_infinity = ieee_class(a) == ieee_class(b) .and. &
         (ieee_class(a) == ieee_positive_inf .or. ieee_class(a) == ieee_negative_inf)
   end function same_infinity

   subroutine eq_r_r1(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected, actual(:)
      real(dp), intent(in), optional :: tolerance
      character(len=*), intent(in), optional :: message, location
      real(dp) :: e(size(actual))
      e = expected
      call eq_r1_r1(e, actual, tolerance, message, location)
   end subroutine eq_r_r1

   subroutine eq_r1_r1(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected(:), actual(:)
      real(dp), intent(in), optional :: tolerance
      character(len=*), intent(in), optional :: message, location
      real(dp) :: tol
      integer :: k
      tol = 0.0_dp
      if (present(tolerance)) tol = tolerance
      if (size(expected) /= size(actual)) then
         call fail('arrays differ in size: expected ' // i2s(size(expected)) // ', found ' // &
                   i2s(size(actual)), message, location)
         return
      end if
      if (.not. (all(ieee_is_finite(expected)) .and. all(ieee_is_finite(actual)))) then
         call fail(nonfinite_array, message, location)
         return
      end if
      do k = 1, size(actual)
         if (.not. (abs(actual(k) - expected(k)) <= tol)) then
            call fail('element ' // i2s(k) // ': expected ' // r2s(expected(k)) // &
               ' but found ' // r2s(actual(k)) // ' (largest difference ' // &
               r2s(maxval(abs(actual - expected))) // ' > tolerance ' // r2s(tol) // ')', &
               message, location)
            return
         end if
      end do
   end subroutine eq_r1_r1

   subroutine eq_i_i(expected, actual, message, location)
      integer, intent(in) :: expected, actual
      character(len=*), intent(in), optional :: message, location
      if (expected /= actual) call fail('expected ' // i2s(expected) // ' but found ' // &
                                        i2s(actual), message, location)
   end subroutine eq_i_i

   subroutine eq_i1_i1(expected, actual, message, location)
      integer, intent(in) :: expected(:), actual(:)
      character(len=*), intent(in), optional :: message, location
      integer :: k
      if (size(expected) /= size(actual)) then
         call fail('arrays differ in size', message, location)
         return
      end if
      do k = 1, size(actual)
         if (expected(k) /= actual(k)) then
            call fail('element ' // i2s(k) // ': expected ' // i2s(expected(k)) // &
                      ' but found ' // i2s(actual(k)), message, location)
            return
         end if
      end do
   end subroutine eq_i1_i1

   subroutine eq_c_c(expected, actual, message, location)
      character(len=*), intent(in) :: expected, actual
      character(len=*), intent(in), optional :: message, location
      ! pFUnit 4.14's default: leading and trailing blanks are ignored, inner ones count
      ! (Fortran's == already pads the shorter string with trailing blanks).
      if (adjustl(expected) /= adjustl(actual)) call fail('expected ''' // expected // &
         ''' but found ''' // actual // '''', message, location)
   end subroutine eq_c_c

   subroutine eq_l_l(expected, actual, message, location)
      logical, intent(in) :: expected, actual
      character(len=*), intent(in), optional :: message, location
      if (expected .neqv. actual) call fail('logical values differ', message, location)
   end subroutine eq_l_l

   subroutine ne_i_i(expected, actual, message, location)
      integer, intent(in) :: expected, actual
      character(len=*), intent(in), optional :: message, location
      if (expected == actual) call fail('values are equal: ' // i2s(actual), message, location)
   end subroutine ne_i_i

   subroutine rel_r_r(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected, actual, tolerance
      character(len=*), intent(in), optional :: message, location
      ! pFUnit 4.14 fails expected = 0 whatever actual is; it dies of SIGFPE on a non-finite
      ! value under the Debug traps (a failing verdict too).
      if (.not. (ieee_is_finite(expected) .and. ieee_is_finite(actual))) then
         call fail('non-finite value in AssertRelativelyEqual (pFUnit 4.14 stops with ' // &
                   'SIGFPE here under the Debug traps)', message, location)
         return
      end if
      if (ieee_class(expected) == ieee_positive_zero .or. &
          ieee_class(expected) == ieee_negative_zero) then
         call fail('Zero denominator detected in AssertRelativelyEqual.', message, location)
         return
      end if
      if (.not. (abs(actual - expected) <= tolerance * abs(expected))) call fail('expected ' &
         // r2s(expected) // ' but found ' // r2s(actual) // ' (relative difference ' // &
         r2s(abs(actual - expected) / abs(expected)) // ' > ' // r2s(tolerance) // ')', &
         message, location)
   end subroutine rel_r_r

   subroutine rel_r1_r1(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected(:), actual(:), tolerance
      character(len=*), intent(in), optional :: message, location
      integer :: k
      if (size(expected) /= size(actual)) then
         call fail('arrays differ in size', message, location)
         return
      end if
      do k = 1, size(actual)
         call rel_r_r(expected(k), actual(k), tolerance, message, location)
         if (failed) return
      end do
   end subroutine rel_r1_r1

   ! ---------------------------------------------------------------- ordering
   subroutine lt_r(lhs, rhs, tolerance, message, location)
      real(dp), intent(in) :: lhs, rhs
      real(dp), intent(in), optional :: tolerance
      character(len=*), intent(in), optional :: message, location
      real(dp) :: tol
      tol = 0.0_dp
      if (present(tolerance)) tol = tolerance
      if (.not. (lhs < rhs + tol)) call fail(r2s(lhs) // ' is not less than ' // r2s(rhs), &
                                             message, location)
   end subroutine lt_r

   subroutine lt_i(lhs, rhs, message, location)
      integer, intent(in) :: lhs, rhs
      character(len=*), intent(in), optional :: message, location
      if (.not. (lhs < rhs)) call fail(i2s(lhs) // ' is not less than ' // i2s(rhs), message, &
                                       location)
   end subroutine lt_i

   subroutine le_r(lhs, rhs, tolerance, message, location)
      real(dp), intent(in) :: lhs, rhs
      real(dp), intent(in), optional :: tolerance
      character(len=*), intent(in), optional :: message, location
      real(dp) :: tol
      tol = 0.0_dp
      if (present(tolerance)) tol = tolerance
      if (.not. (lhs <= rhs + tol)) call fail(r2s(lhs) // ' is not <= ' // r2s(rhs), message, &
                                              location)
   end subroutine le_r

   subroutine le_i(lhs, rhs, message, location)
      integer, intent(in) :: lhs, rhs
      character(len=*), intent(in), optional :: message, location
      if (.not. (lhs <= rhs)) call fail(i2s(lhs) // ' is not <= ' // i2s(rhs), message, location)
   end subroutine le_i

   subroutine gt_r(lhs, rhs, tolerance, message, location)
      real(dp), intent(in) :: lhs, rhs
      real(dp), intent(in), optional :: tolerance
      character(len=*), intent(in), optional :: message, location
      real(dp) :: tol
      tol = 0.0_dp
      if (present(tolerance)) tol = tolerance
      if (.not. (lhs > rhs - tol)) call fail(r2s(lhs) // ' is not greater than ' // r2s(rhs), &
                                             message, location)
   end subroutine gt_r

   subroutine gt_i(lhs, rhs, message, location)
      integer, intent(in) :: lhs, rhs
      character(len=*), intent(in), optional :: message, location
      if (.not. (lhs > rhs)) call fail(i2s(lhs) // ' is not greater than ' // i2s(rhs), message, &
                                       location)
   end subroutine gt_i

   subroutine ge_r(lhs, rhs, tolerance, message, location)
      real(dp), intent(in) :: lhs, rhs
      real(dp), intent(in), optional :: tolerance
      character(len=*), intent(in), optional :: message, location
      real(dp) :: tol
      tol = 0.0_dp
      if (present(tolerance)) tol = tolerance
      if (.not. (lhs >= rhs - tol)) call fail(r2s(lhs) // ' is not >= ' // r2s(rhs), message, &
                                              location)
   end subroutine ge_r

   subroutine ge_i(lhs, rhs, message, location)
      integer, intent(in) :: lhs, rhs
      character(len=*), intent(in), optional :: message, location
      if (.not. (lhs >= rhs)) call fail(i2s(lhs) // ' is not >= ' // i2s(rhs), message, location)
   end subroutine ge_i

   ! ----------------------------------------------------------------- others

   subroutine assertTrue(condition, message, location)
      logical, intent(in) :: condition
      character(len=*), intent(in), optional :: message, location
      if (.not. condition) call fail('condition is false', message, location)
   end subroutine assertTrue

   subroutine assertFalse(condition, message, location)
      logical, intent(in) :: condition
      character(len=*), intent(in), optional :: message, location
      if (condition) call fail('condition is true', message, location)
   end subroutine assertFalse

   subroutine finite_r(x, message, location)
      real(dp), intent(in) :: x
      character(len=*), intent(in), optional :: message, location
      if (.not. ieee_is_finite(x)) call fail('value is not finite', message, location)
   end subroutine finite_r

   subroutine finite_r1(x, message, location)
      real(dp), intent(in) :: x(:)
      character(len=*), intent(in), optional :: message, location
      if (.not. all(ieee_is_finite(x))) call fail('array has non-finite values', message, location)
   end subroutine finite_r1

   subroutine nan_r(x, message, location)
      real(dp), intent(in) :: x
      character(len=*), intent(in), optional :: message, location
      if (.not. ieee_is_nan(x)) call fail('value is not NaN', message, location)
   end subroutine nan_r

   subroutine assertFail(message, location)
      character(len=*), intent(in) :: message
      character(len=*), intent(in), optional :: location
      call fail('assertFail', message, location)
   end subroutine assertFail
end module funit
