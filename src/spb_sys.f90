!> The few operating-system services Fortran 2008 lacks, through C interoperability.
module spb_sys
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   implicit none
   private
   public :: sys_exit, stderr_is_terminal, sys_rename

   interface
      subroutine c_exit(status) bind(c, name='exit')
         import :: c_int
         integer(c_int), value :: status
      end subroutine c_exit
      function c_isatty(fd) bind(c, name='isatty') result(r)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: r
      end function c_isatty
      function c_rename(old, new) bind(c, name='rename') result(r)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: old(*), new(*)
         integer(c_int) :: r
      end function c_rename
   end interface

contains

   !> Terminate with an exit status and no runtime banner (error stop prints one).
   subroutine sys_exit(status)
      integer, intent(in) :: status   !! process exit status
      call c_exit(int(status, c_int))
   end subroutine sys_exit

   !> True when standard error is a terminal (progress lines go there only then).
   logical function stderr_is_terminal()
      stderr_is_terminal = c_isatty(2_c_int) == 1_c_int
   end function stderr_is_terminal

   !> Rename a file (atomic within one file system); ok is false on failure.
   subroutine sys_rename(old, new, ok)
      character(len=*), intent(in) :: old   !! existing path
      character(len=*), intent(in) :: new   !! new path (replaced if it exists)
      logical, intent(out) :: ok            !! true on success
      ok = c_rename(old // c_null_char, new // c_null_char) == 0_c_int
   end subroutine sys_rename
end module spb_sys
