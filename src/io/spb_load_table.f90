!> The load table of a deck (&load kind = 'table'): a two-column file t [s], p [Pa].
module spb_load_table
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t, make_error
   use spb_strings, only: itoa, rtoa
   use spb_sys, only: fp_traps_off, fp_traps_restore, sys_file_kind, file_other
   implicit none
   private
   public :: read_table

   integer, parameter :: max_table_rows = 1000000

contains

   !> Read a two-column table t [s], p [Pa]; '#' and '!' start comments.
   subroutine read_table(path, t, p, err)
      character(len=*), intent(in) :: path   !! the table file
      real(wp), allocatable, intent(out) :: t(:)   !! times [s], non-decreasing
      real(wp), allocatable, intent(out) :: p(:)   !! pressures [Pa]
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      integer :: u, ios, nrow, line, k, nchar
      logical :: ok
      character(len=1025) :: buf
      character(len=256) :: msg
      real(wp) :: tt, pp
      real(wp), allocatable :: tw(:), pw(:)
      logical :: traps(3)

      if (sys_file_kind(path) == file_other) then
         call make_error(err, '&load: table = ''' // trim(path) // ''': not a regular file ' // &
                         '(a FIFO, a device or a socket)')
         return
      end if
      open(newunit=u, file=path, status='old', action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, '&load: table = ''' // trim(path) // ''': cannot open: ' // trim(msg))
         return
      end if
      allocate(tw(64), pw(64))
      nrow = 0
      line = 0
      call fp_traps_off(traps)
      do
         read(u, '(a)', advance='no', size=nchar, iostat=ios) buf
         if (is_iostat_end(ios)) exit
         line = line + 1
         if (ios == 0) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': longer than ' // itoa(len(buf) - 1) // ' characters')
            exit
         end if
         if (.not. is_iostat_eor(ios)) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': cannot be read')
            exit
         end if
         buf(nchar + 1:) = ' '
         ! a UTF-8 byte-order mark on the first line is nothing; tabs and carriage returns
         ! are blanks (a line of only a tab is as blank as an empty one)
         if (line == 1 .and. nchar >= 3) then
            if (buf(1:3) == achar(239) // achar(187) // achar(191)) buf(1:3) = ' '
         end if
         do k = 1, nchar
            if (buf(k:k) == achar(9) .or. buf(k:k) == achar(13)) buf(k:k) = ' '
         end do
         k = scan(buf, '#!')
         if (k > 0) buf(k:) = ' '
         if (len_trim(buf) == 0) cycle
         call two_numbers(buf, tt, pp, ok)
         if (.not. ok) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': expected two numbers t p (and nothing else)')
            exit
         end if
         if (.not. (ieee_is_finite(tt) .and. ieee_is_finite(pp))) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': values must be finite')
            exit
         end if
         if (out_of_range(tt) .or. out_of_range(pp)) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': values must be 0 or between 1e-60 and 1e60 in magnitude')
            exit
         end if
         if (tt < 0.0_wp) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': time must be >= 0, got ' // rtoa(tt))
            exit
         end if
         if (nrow >= 1) then
            if (tt < tw(nrow)) then
               call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // &
                  itoa(line) // ': times must not decrease (' // rtoa(tt) // ' after ' // &
                  rtoa(tw(nrow)) // ')')
               exit
            end if
         end if
         if (nrow >= 2) then
            if (.not. (tt > tw(nrow - 1))) then
               call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // &
                  itoa(line) // ': a time may repeat once (a jump), not three times')
               exit
            end if
         end if
         if (nrow >= max_table_rows) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' has more than ' // &
                            itoa(max_table_rows) // ' rows')
            exit
         end if
         if (nrow == size(tw)) then
            tw = [tw, tw]
            pw = [pw, pw]
         end if
         nrow = nrow + 1
         tw(nrow) = tt
         pw(nrow) = pp
      end do
      call fp_traps_restore(traps)
      close(u)
      if (allocated(err)) return
      if (nrow < 2) then
         call make_error(err, '&load: table = ''' // trim(path) // ''' needs at least two rows')
         return
      end if
      t = tw(1:nrow)
      p = pw(1:nrow)
   end subroutine read_table

   !> The two numbers of a table row: exactly two words, separated by blanks, tabs or a
   !> comma, each a decimal number ([sign] digits [. digits] [exponent]); ok is false for
   !> anything else (a '/' or a repeat count, which a list-directed read would take).
   subroutine two_numbers(text, a, b, ok)
      character(len=*), intent(in) :: text   !! the row, comments removed
      real(wp), intent(out) :: a             !! first number (t [s])
      real(wp), intent(out) :: b             !! second number (p [Pa])
      logical, intent(out) :: ok             !! both read, nothing else on the row
      integer :: i, n, first(3), last(3), ios
      real(wp) :: x(2)
      n = 0
      i = 1
      a = 0.0_wp
      b = 0.0_wp
      ok = .false.
      do while (i <= len_trim(text))
         if (index(' ,' // achar(9) // achar(13), text(i:i)) > 0) then
            i = i + 1
            cycle
         end if
         n = n + 1
         if (n > 2) return
         first(n) = i
         do while (i <= len_trim(text))
            if (index(' ,' // achar(9) // achar(13), text(i:i)) > 0) exit
            i = i + 1
         end do
         last(n) = i - 1
      end do
      if (n /= 2) return
      do i = 1, 2
         if (.not. is_number(text(first(i):last(i)))) return
         read(text(first(i):last(i)), *, iostat=ios) x(i)
         if (ios /= 0) return
      end do
      a = x(1)
      b = x(2)
      ok = .true.
   end subroutine two_numbers

   !> Whether word is a decimal number: [sign] (digits [. [digits]] | . digits)
   !> [(e|d) [sign] digits].
   pure logical function is_number(word)
      character(len=*), intent(in) :: word   !! one word of a row
      integer :: i, mantissa, exponent
      is_number = .false.
      i = 1
      if (i <= len(word)) then
         if (word(i:i) == '+' .or. word(i:i) == '-') i = i + 1
      end if
      mantissa = 0
      do while (i <= len(word))
         if (.not. is_digit(word(i:i))) exit
         mantissa = mantissa + 1
         i = i + 1
      end do
      if (i <= len(word)) then
         if (word(i:i) == '.') then
            i = i + 1
            do while (i <= len(word))
               if (.not. is_digit(word(i:i))) exit
               mantissa = mantissa + 1
               i = i + 1
            end do
         end if
      end if
      if (mantissa == 0) return
      if (i <= len(word)) then
         if (index('eEdD', word(i:i)) == 0) return
         i = i + 1
         if (i <= len(word)) then
            if (word(i:i) == '+' .or. word(i:i) == '-') i = i + 1
         end if
         exponent = 0
         do while (i <= len(word))
            if (.not. is_digit(word(i:i))) return
            exponent = exponent + 1
            i = i + 1
         end do
         if (exponent == 0) return
      end if
      is_number = .true.
   end function is_number

   !> Whether x lies outside the magnitudes a deck's reals may take (0, or 1e-60 .. 1e60).
   pure logical function out_of_range(x)
      real(wp), intent(in) :: x   !! a table value
      out_of_range = (abs(x) > 0.0_wp .and. abs(x) < 1.0e-60_wp) .or. abs(x) > 1.0e60_wp
   end function out_of_range

   !> Whether c is a decimal digit.
   pure logical function is_digit(c)
      character, intent(in) :: c   !! one character
      is_digit = c >= '0' .and. c <= '9'
   end function is_digit
end module spb_load_table
