!> Errors as values: library routines return an allocated spb_error_t and never stop.
module spb_error
   implicit none
   private
   public :: spb_error_t, make_error, exit_input, exit_runtime

   integer, parameter :: exit_input = 2     !! exit status for bad input
   integer, parameter :: exit_runtime = 3   !! exit status for a run that went wrong

   type :: spb_error_t
      character(len=:), allocatable :: message   !! one line: '&group: variable ...'
      integer :: code = exit_input               !! exit status the program should use
   end type spb_error_t

contains

   !> Allocate err with a message and an exit code (default: input error).
   subroutine make_error(err, message, code)
      type(spb_error_t), allocatable, intent(inout) :: err   !! receives the error
      character(len=*), intent(in) :: message                !! one-line description
      integer, intent(in), optional :: code                  !! exit status
      if (allocated(err)) deallocate(err)
      allocate(err)
      err%message = message
      if (present(code)) err%code = code
   end subroutine make_error
end module spb_error
