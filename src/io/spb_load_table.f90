!> The load table of a deck (&load kind = 'table'): a two-column file t [s], p [Pa].
module spb_load_table
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t, make_error
   use spb_strings, only: itoa, rtoa
   use spb_sys, only: fp_traps_off, fp_traps_restore
   implicit none
   private
   public :: read_table

   integer, parameter :: max_table_rows = 1000000

contains

   !> Read a two-column table t [s], p [Pa]; '#' and '!' start comments.
   subroutine read_table(path, t, p, err)
      character(len=*), intent(in) :: path
      real(wp), allocatable, intent(out) :: t(:), p(:)
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      integer :: u, ios, nrow, line, k
      character(len=1024) :: buf
      character(len=256) :: msg
      real(wp) :: tt, pp
      real(wp), allocatable :: tw(:), pw(:)
      logical :: traps(3)

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
         read(u, '(a)', iostat=ios) buf
         if (ios /= 0) exit
         line = line + 1
         k = scan(buf, '#!')
         if (k > 0) buf(k:) = ' '
         if (len_trim(buf) == 0) cycle
         read(buf, *, iostat=ios) tt, pp
         if (ios /= 0) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': expected two numbers t p')
            exit
         end if
         if (.not. (ieee_is_finite(tt) .and. ieee_is_finite(pp))) then
            call make_error(err, '&load: table = ''' // trim(path) // ''' line ' // itoa(line) &
                            // ': values must be finite')
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
end module spb_load_table
