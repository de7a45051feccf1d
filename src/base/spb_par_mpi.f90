!> The few message-passing operations a sweep needs, on MPI (use mpi_f08). The serial build
!> compiles spb_par_serial.f90 instead: the same module, one rank, no messages.
!>
!> MPI is started only by a sweep (par_init), and only in a process an MPI launcher started
!> (mpirun, mpiexec, srun: launched); a single run never touches it. Without MPI started,
!> every operation is the serial build's (one rank, no messages), asking MPI_Initialized,
!> which MPI allows before MPI_Init, instead of keeping a flag.
module spb_par
   use mpi_f08, only: MPI_Init, MPI_Initialized, MPI_Finalize, MPI_Finalized, MPI_Comm_rank, &
      MPI_Comm_size, MPI_Send, MPI_Recv, MPI_Status, MPI_COMM_WORLD, MPI_DOUBLE_PRECISION, &
      MPI_INTEGER, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_Wtime, MPI_Barrier, MPI_Allreduce, MPI_MAX
   use, intrinsic :: iso_fortran_env, only: int64
   use spb_kinds, only: wp
   use spb_sys, only: fp_traps_off, fp_traps_restore
   implicit none
   private
   public :: par_init, par_finalize, par_rank, par_size, par_send, par_recv, &
      par_wtime, par_max, par_barrier, par_any, par_kind, par_started

   integer, parameter :: par_any = -1               !! any source (par_recv)
   character(len=*), parameter :: par_kind = 'MPI'  !! what this build runs sweeps on

   interface par_send
      module procedure send_real, send_int
   end interface par_send
   interface par_recv
      module procedure recv_real, recv_int
   end interface par_recv

contains

   !> Start the parallel run (MPI_Init). Floating-point traps (the debug build's
   !> -ffpe-trap) are held off meanwhile: under `srun --mpi=pmix` OpenMPI's start-up raises
   !> a floating-point exception inside MPI_Init, and the trap stopped every rank there
   !> (SIGFPE; OpenMPI 4.1.4, Slurm 22.05). Flags it raised are cleared.
   !> A process no launcher started runs alone: MPI is not started (its singleton start
   !> forks a daemon, 0.3 s of wall clock and 0.05-0.1 s of CPU time, as much as 150 cases
   !> of input/sweeps/weibull_spall.nml; doc/sweeps.md).
   subroutine par_init()
      logical :: started
      logical :: saved(3)   ! the halting modes to restore
      call MPI_Initialized(started)
      if (started) return
      if (.not. launched()) return
      call fp_traps_off(saved)
      call MPI_Init()
      call fp_traps_restore(saved)
   end subroutine par_init

   !> Whether an MPI launcher started this process: one of the variables OpenMPI's mpirun
   !> (OMPI_COMM_WORLD_SIZE), PMIx (PMIX_RANK: srun --mpi=pmix, OpenMPI 4/5), PMI-1/2
   !> (PMI_RANK, PMI_SIZE: MPICH's hydra, Intel MPI, srun --mpi=pmi2) or MVAPICH2
   !> (MV2_COMM_WORLD_SIZE) set in every rank, or SPALLBAR_MPI_INIT (set to anything, for
   !> another launcher).
   logical function launched()
      character(len=*), parameter :: names(6) = [character(len=20) :: 'OMPI_COMM_WORLD_SIZE', &
         'PMIX_RANK', 'PMI_RANK', 'PMI_SIZE', 'MV2_COMM_WORLD_SIZE', 'SPALLBAR_MPI_INIT']
      integer :: k, length, status
      launched = .false.
      do k = 1, size(names)
         call get_environment_variable(trim(names(k)), length=length, status=status)
         if (status == 0) launched = .true.
      end do
   end function launched

   !> Whether MPI runs this process's sweep (par_init started it).
   logical function par_started()
      call MPI_Initialized(par_started)
   end function par_started

   !> End the parallel run.
   subroutine par_finalize()
      logical :: started, done
      call MPI_Initialized(started)
      if (.not. started) return
      call MPI_Finalized(done)
      if (.not. done) call MPI_Finalize()
   end subroutine par_finalize

   !> This rank (0 .. ranks - 1).
   integer function par_rank()
      par_rank = 0
      if (par_started()) call MPI_Comm_rank(MPI_COMM_WORLD, par_rank)
   end function par_rank

   !> The number of ranks.
   integer function par_size()
      par_size = 1
      if (par_started()) call MPI_Comm_size(MPI_COMM_WORLD, par_size)
   end function par_size

   !> Wall time [s] (a common clock for differences).
   real(wp) function par_wtime()
      integer(int64) :: c, rate
      if (par_started()) then
         par_wtime = real(MPI_Wtime(), wp)
      else
         call system_clock(c, rate)
         par_wtime = real(c, wp) / real(max(rate, 1_int64), wp)
      end if
   end function par_wtime

   !> The largest of i over the ranks (every rank calls it; a barrier too).
   integer function par_max(i)
      integer, intent(in) :: i             !! this rank's value
      par_max = i
      if (par_started()) call MPI_Allreduce(i, par_max, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD)
   end function par_max

   !> Wait until every rank is here.
   subroutine par_barrier()
      if (par_started()) call MPI_Barrier(MPI_COMM_WORLD)
   end subroutine par_barrier

   !> Send a message of reals to rank dest with tag.
   subroutine send_real(buf, dest, tag)
      real(wp), intent(in) :: buf(:)       !! the message
      integer, intent(in) :: dest          !! rank to send to
      integer, intent(in) :: tag           !! message tag
      call MPI_Send(buf, size(buf), MPI_DOUBLE_PRECISION, dest, tag, MPI_COMM_WORLD)
   end subroutine send_real

   !> Send one integer to rank dest with tag.
   subroutine send_int(i, dest, tag)
      integer, intent(in) :: i             !! the integer
      integer, intent(in) :: dest          !! rank to send to
      integer, intent(in) :: tag           !! message tag
      call MPI_Send(i, 1, MPI_INTEGER, dest, tag, MPI_COMM_WORLD)
   end subroutine send_int

   !> Receive buf from source (par_any: any rank) with tag (par_any: any tag); who and what
   !> tag it came with.
   subroutine recv_real(buf, source, tag, got_source, got_tag)
      real(wp), intent(out) :: buf(:)      !! the message
      integer, intent(in) :: source        !! rank to receive from
      integer, intent(in) :: tag           !! message tag
      integer, intent(out), optional :: got_source   !! the rank it came from
      integer, intent(out), optional :: got_tag   !! its tag
      type(MPI_Status) :: status
      call MPI_Recv(buf, size(buf), MPI_DOUBLE_PRECISION, mpi_source(source), mpi_tag(tag), &
                    MPI_COMM_WORLD, status)
      if (present(got_source)) got_source = status%MPI_SOURCE
      if (present(got_tag)) got_tag = status%MPI_TAG
   end subroutine recv_real

   !> Receive one integer from rank source with tag (par_any: any of either).
   subroutine recv_int(i, source, tag, got_source, got_tag)
      integer, intent(out) :: i            !! the integer
      integer, intent(in) :: source        !! rank to receive from
      integer, intent(in) :: tag           !! message tag
      integer, intent(out), optional :: got_source   !! the rank it came from
      integer, intent(out), optional :: got_tag   !! its tag
      type(MPI_Status) :: status
      call MPI_Recv(i, 1, MPI_INTEGER, mpi_source(source), mpi_tag(tag), MPI_COMM_WORLD, status)
      if (present(got_source)) got_source = status%MPI_SOURCE
      if (present(got_tag)) got_tag = status%MPI_TAG
   end subroutine recv_int

   !> The MPI source for a rank or par_any.
   integer function mpi_source(source)
      integer, intent(in) :: source        !! rank to receive from
      mpi_source = source
      if (source == par_any) mpi_source = MPI_ANY_SOURCE
   end function mpi_source

   !> The MPI tag for a tag or par_any.
   integer function mpi_tag(tag)
      integer, intent(in) :: tag           !! message tag
      mpi_tag = tag
      if (tag == par_any) mpi_tag = MPI_ANY_TAG
   end function mpi_tag
end module spb_par
