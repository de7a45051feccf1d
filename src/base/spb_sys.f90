!> The few operating-system services Fortran 2008 lacks, through C interoperability.
module spb_sys
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_funptr, c_funloc
   use, intrinsic :: ieee_exceptions, only: ieee_flag_type, ieee_overflow, ieee_invalid, &
      ieee_divide_by_zero, ieee_get_halting_mode, ieee_set_halting_mode, ieee_set_flag
   implicit none
   private
   public :: sys_exit, stderr_is_terminal, sys_rename, catch_stop_signals, stop_signal
   public :: fp_traps_off, fp_traps_restore, heap_for_large_arrays

   type(ieee_flag_type), parameter :: read_traps(3) = [ieee_overflow, ieee_invalid, &
      ieee_divide_by_zero]

   integer(c_int), parameter :: sigint = 2_c_int, sigterm = 15_c_int   ! Linux numbers

   !> The signal that asked the run to stop (0: none). The one piece of module state in
   !> spallbar: a signal handler can reach nothing else. Written by the handler only.
   integer(c_int), volatile :: caught = 0_c_int

   interface
      !> C exit(3): ends the process from a signal handler's context.
      subroutine c_exit(status) bind(c, name='exit')
         import :: c_int
         implicit none
         integer(c_int), value :: status
      end subroutine c_exit
      !> C isatty(3).
      function c_isatty(fd) bind(c, name='isatty') result(r)
         import :: c_int
         implicit none
         integer(c_int), value :: fd
         integer(c_int) :: r
      end function c_isatty
      !> C rename(2) on NUL-terminated names.
      function c_rename(old, new) bind(c, name='rename') result(r)
         import :: c_int, c_char
         implicit none
         ! C strings (char *), NUL-terminated by the caller
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: old(*), new(*)
         integer(c_int) :: r
      end function c_rename
      !> C mallopt(3).
      function c_mallopt(param, value) bind(c, name='mallopt') result(r)
         import :: c_int
         implicit none
         integer(c_int), value :: param, value
         integer(c_int) :: r
      end function c_mallopt
      !> C signal(2): install a handler.
      function c_signal(signum, handler) bind(c, name='signal') result(previous)
         import :: c_int, c_funptr
         implicit none
         integer(c_int), value :: signum
         type(c_funptr), value :: handler
         type(c_funptr) :: previous
      end function c_signal
   end interface

contains

   !> Large arrays from the heap, not each from its own mmap (glibc: M_MMAP_THRESHOLD = -3,
   !> raised to its largest, 32 MiB). Every mmap starts at the same offset of a 4 KiB page,
   !> so the state's arrays would share their addresses modulo 4 KiB, and a load from one
   !> stalls behind a store to another at the same index (4K aliasing): measured 20% of the
   !> stepping time of a 1e5-node bar (doc/benchmarks.md). Heap arrays lie one after the
   !> other at staggered offsets. A performance hint only: ignored where it fails.
   subroutine heap_for_large_arrays()
      integer(c_int) :: rc
      rc = c_mallopt(-3_c_int, 33554432_c_int)
   end subroutine heap_for_large_arrays

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

   !> Hold off floating-point traps (the debug build's -ffpe-trap) while text is read: a
   !> value like 1e999 reads as +Inf, which validation then rejects with a message, instead
   !> of stopping the program inside the runtime library.
   subroutine fp_traps_off(saved)
      logical, intent(out) :: saved(3)   !! the halting modes to restore
      call ieee_get_halting_mode(read_traps, saved)
      call ieee_set_halting_mode(read_traps, .false.)
   end subroutine fp_traps_off

   !> Clear what reading raised and restore the halting modes fp_traps_off saved.
   subroutine fp_traps_restore(saved)
      logical, intent(in) :: saved(3)
      call ieee_set_flag(read_traps, .false.)
      call ieee_set_halting_mode(read_traps, saved)
   end subroutine fp_traps_restore

   !> From now on SIGTERM and SIGINT only set a flag (stop_signal reads it): the run ends
   !> its step, writes and closes its outputs, and exits with 128 + the signal number.
   subroutine catch_stop_signals()
      type(c_funptr) :: previous
      previous = c_signal(sigterm, c_funloc(on_signal))
      previous = c_signal(sigint, c_funloc(on_signal))
   end subroutine catch_stop_signals

   !> The signal caught since catch_stop_signals (0: none).
   integer function stop_signal()
      stop_signal = int(caught)
   end function stop_signal

   !> The handler of SIGTERM/SIGINT: remembers the signal (the run stops at the next step).
   subroutine on_signal(signum) bind(c)
      integer(c_int), value :: signum
      caught = signum
   end subroutine on_signal
end module spb_sys
