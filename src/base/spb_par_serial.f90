!> spb_par for a build without MPI: one rank, nothing to send. A sweep then runs its cases
!> one after the other in this process (spb_par_mpi.f90 is the MPI version).
module spb_par
   use, intrinsic :: iso_fortran_env, only: int64
   use spb_kinds, only: wp
   implicit none
   private
   public :: par_init, par_finalize, par_rank, par_size, par_send, par_recv, &
      par_wtime, par_max, par_barrier, par_any, par_kind, par_started

   integer, parameter :: par_any = -1
   character(len=*), parameter :: par_kind = 'serial (built without MPI)'

   interface par_send
      module procedure send_real, send_int
   end interface par_send
   interface par_recv
      module procedure recv_real, recv_int
   end interface par_recv

contains

   !> Start the parallel run (MPI_Init).
   subroutine par_init()
   end subroutine par_init

   !> Whether MPI runs this process's sweep: never in this build.
   logical function par_started()
      par_started = .false.
   end function par_started

   !> End the parallel run.
   subroutine par_finalize()
   end subroutine par_finalize

   !> This rank (0 .. ranks - 1).
   integer function par_rank()
      par_rank = 0
   end function par_rank

   !> The largest of i over the ranks: i.
   integer function par_max(i)
      integer, intent(in) :: i             !! this rank's value
      par_max = i
   end function par_max

   !> Wait until every rank is here: one rank, no wait.
   subroutine par_barrier()
   end subroutine par_barrier

   !> The number of ranks.
   integer function par_size()
      par_size = 1
   end function par_size

   !> Wall time [s] (a common clock for differences).
   real(wp) function par_wtime()
      integer(int64) :: c, rate
      call system_clock(c, rate)
      par_wtime = real(c, wp) / real(max(rate, 1_int64), wp)
   end function par_wtime

   ! One rank never sends or receives: the sweep driver does not call these with size 1.
   !> Send a message of reals to rank dest with tag.
   subroutine send_real(buf, dest, tag)
      real(wp), intent(in) :: buf(:)       !! the message
      integer, intent(in) :: dest          !! rank to send to
      integer, intent(in) :: tag           !! message tag
      error stop 'spb_par: no messages in a serial build'
   end subroutine send_real

   !> Send one integer to rank dest with tag.
   subroutine send_int(i, dest, tag)
      integer, intent(in) :: i             !! the integer
      integer, intent(in) :: dest          !! rank to send to
      integer, intent(in) :: tag           !! message tag
      error stop 'spb_par: no messages in a serial build'
   end subroutine send_int

   !> Receive a message of reals from rank source with tag (par_any: any of either).
   subroutine recv_real(buf, source, tag, got_source, got_tag)
      real(wp), intent(out) :: buf(:)      !! the message
      integer, intent(in) :: source        !! rank to receive from
      integer, intent(in) :: tag           !! message tag
      integer, intent(out), optional :: got_source   !! the rank it came from
      integer, intent(out), optional :: got_tag   !! its tag
      buf = 0.0_wp
      error stop 'spb_par: no messages in a serial build'
   end subroutine recv_real

   !> Receive one integer from rank source with tag (par_any: any of either).
   subroutine recv_int(i, source, tag, got_source, got_tag)
      integer, intent(out) :: i            !! the integer
      integer, intent(in) :: source        !! rank to receive from
      integer, intent(in) :: tag           !! message tag
      integer, intent(out), optional :: got_source   !! the rank it came from
      integer, intent(out), optional :: got_tag   !! its tag
      i = 0
      error stop 'spb_par: no messages in a serial build'
   end subroutine recv_int
end module spb_par
