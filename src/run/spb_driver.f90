!> The phases of the main program that say something: the header a run prints before it
!> starts (and the lines it says on stderr once it does), the report at its end, and the
!> whole of a sweep (--sweep) on every rank. The main program sequences them and is the
!> only one that exits.
module spb_driver
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use spb_kinds, only: wp
   use spb_identity, only: program_identity
   use spb_error, only: spb_error_t
   use spb_strings, only: itoa
   use spb_cli, only: cli_t
   use spb_deck, only: deck_t, read_deck, deck_warnings
   use spb_sim, only: sim_t, checkpoint_t, ring_span_at_start, ring_memory_note
   use spb_summary, only: run_summary_t, write_summary
   use spb_diag, only: frag_info_t, fragment_list
   use spb_output, only: write_mesh_summary
   use spb_sys, only: catch_stop_signals
   use spb_sweep, only: run_sweep, sweep_summary_t
   use spb_estimate, only: estimate_t, estimate_run, estimate_line, estimate_warnings
   use spb_par, only: par_init, par_finalize, par_barrier, par_rank, par_kind, par_started
   implicit none
   private
   public :: announce_run, write_report, sweep_main

contains

   !> Before a run starts: its header on unit (but with --quiet: the program and title, the
   !> mesh, the checkpoint it restarts from, the estimate) and the lines it says on stderr
   !> once it is sure to start (notes: the note of a restart from another program's
   !> checkpoint, the deck's and the estimate's warnings). ck: the checkpoint of a restart.
   subroutine announce_run(unit, cli, deck, sim, notes, ck)
      integer, intent(in) :: unit          !! where (standard output)
      type(cli_t), intent(in) :: cli       !! the command line
      type(deck_t), intent(in) :: deck     !! the deck
      type(sim_t), intent(inout) :: sim    !! the simulation (restarted_from of its record
                                           !! set for another program's checkpoint)
      character(len=:), allocatable, intent(out) :: notes(:)   !! the lines for stderr
      type(checkpoint_t), intent(in), optional :: ck   !! the checkpoint it restarts from
      type(estimate_t) :: est   ! the work and the outputs of the run, before it starts
      character(len=:), allocatable :: note   ! what a restart of another program's checkpoint says
      integer :: first
      note = ''
      first = 0
      if (present(ck)) then
         ! another program's checkpoint (--restart-any-version): said once the run starts
         if (ck%program /= program_identity()) then
            sim%record%restarted_from = ck%program
            note = 'spallbar: --restart-any-version: ''' // cli%restart // ''' was written by ' &
               // ck%program // ', this is ' // program_identity() // '; the outputs are ' // &
               'not one uninterrupted run of one program (every header says so)'
         end if
         first = ck%st%step
      end if
      est = estimate_run(deck, sim%mesh%n, sim%mesh%nsteps, sim%mesh%dt, first, .true., &
                         ring_span=ring_span_at_start(sim))
      if (.not. cli%quiet) then
         write(unit, '(a)') program_identity() // ': ' // trim(deck%run%title)
         call write_mesh_summary(unit, sim%mesh, sim%report, '  ')
         if (present(ck)) write(unit, '(a,i0,a,es12.5,a)') '  restart from ' // cli%restart // &
            ' at step ', ck%st%step, ' (t = ', real(ck%st%step, wp) * sim%mesh%dt, ' s)'
         write(unit, '(a)') '  ' // estimate_line(est)
      end if
      flush(unit)   ! a log of stdout and stderr together: the header first
      ! last, when the characteristic steps' arrays did not fit: every step on the lattice
      notes = noted(note, warnings(deck, sim%mesh%nsteps, est), &
                    ring_memory_note(sim, present(ck)))
   end subroutine announce_run

   !> After a run: the run summary's text (spb_summary) with the fragments at the end and
   !> every file the run wrote.
   subroutine write_report(unit, sim, summary, prefix)
      integer, intent(in) :: unit          !! where (standard output)
      type(sim_t), intent(in) :: sim       !! the simulation, at its end
      type(run_summary_t), intent(in) :: summary   !! the run's summary
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(frag_info_t), allocatable :: list(:)
      character(len=:), allocatable :: files
      call fragment_list(sim%mesh, sim%st, list)
      files = prefix // '.his, ' // prefix // '.prf, ' // prefix // '.evt, ' // prefix // '.frg'
      files = files // ', ' // prefix // '.spl, ' // prefix // '.imp'
      if (allocated(sim%record%gauge_x)) then
         if (size(sim%record%gauge_x) > 0) files = files // ', ' // prefix // '.gau'
      end if
      if (sim%record%hdf5) files = files // ', ' // prefix // '.h5, ' // prefix // '.xmf'
      if (summary%checkpoints > 0) files = files // ', checkpoint ' // sim%opt%checkpoint // &
         ' (step ' // itoa(summary%steps) // ')'
      call write_summary(unit, summary, list, prefix, files)
   end subroutine write_report

   !> --sweep: every rank reads and checks the deck (the same answer everywhere), runs its
   !> cases; rank 0 reports, writes the outputs and the error's message. status: what the
   !> program exits with, 0, 2 bad input, 3 some case went wrong, 128 + signal. Stopped by
   !> a signal, the ranks meet here and return without MPI_Finalize: mpirun, when it got the
   !> signal itself, is ending the job, never completes a finalize and SIGKILLs the ranks 1 s
   !> after forwarding the signal (odls_base_sigkill_timeout; doc/sweeps.md).
   subroutine sweep_main(cli, status)
      type(cli_t), intent(in) :: cli       !! the command line
      integer, intent(out) :: status       !! the exit status
      type(deck_t) :: deck
      type(sweep_summary_t) :: ssum
      type(spb_error_t), allocatable :: err
      integer :: rank, k
      call par_init()
      rank = par_rank()
      call read_deck(cli%deck, deck, err, sweep=.true.)
      if (.not. allocated(err)) then
         if (rank == 0 .and. .not. cli%quiet) write(output_unit, '(a)') program_identity() // &
            ' sweep: ' // trim(deck%run%title)
         flush(output_unit)
         if (rank == 0) call warn(warnings(deck, 0))
         call catch_stop_signals()
         call run_sweep(deck, cli%prefix, rank == 0 .and. cli%progress, ssum, err, &
                        batch_seconds=merge(cli%batch, 0.0_wp, rank == 0), &
                        echo=rank == 0 .and. .not. cli%quiet, rings=.not. cli%lattice)
      end if
      if (rank == 0 .and. .not. cli%quiet .and. ssum%cases > 0) then
         write(output_unit, '(a,i0,a,i0,a,a,a,a,a,f0.3,a)') '  done: ', ssum%cases, ' cases on ', &
            ssum%ranks, ' rank(s) (', trim(ssum%distribution), ', ', how_run(), ') in ', &
            ssum%wall, ' s wall'
         write(output_unit, '(a,i0,a,i0,a,i0,a)') '  cases done: ', ssum%done, ', went wrong: ', &
            ssum%failed, ', not run: ', ssum%not_run, '; wrote ' // cli%prefix // '.sweep, ' // &
            cli%prefix // '_sweep.h5' // trim(merge(', ' // cli%prefix // '.ens', &
            repeat(' ', len(cli%prefix) + 6), ssum%ensemble))
         if (allocated(ssum%horizons)) then
            do k = 1, size(ssum%horizons)
               write(output_unit, '(a)') '  horizon ' // trim(ssum%horizons(k))
            end do
         end if
      end if
      flush(output_unit)
      if (ssum%signal /= 0) then
         ! rank 0 writes the table and its message, then every rank exits 128 + signal at once
         if (rank == 0 .and. allocated(err)) then
            write(error_unit, '(a)') 'spallbar: ' // err%message
            flush(error_unit)
         end if
         call par_barrier()
         status = 128 + ssum%signal
         if (allocated(err)) status = err%code
         return
      end if
      call par_finalize()
      status = 0
      if (allocated(err)) then
         status = err%code
         if (rank == 0) then
            write(error_unit, '(a)') 'spallbar: ' // err%message
            flush(error_unit)
            flush(output_unit)
         end if
      end if
   end subroutine sweep_main

   !> What ran the sweep's cases: par_kind ('MPI'), or 'MPI not started: no launcher' for
   !> a process no MPI launcher started (spb_par par_init).
   function how_run() result(text)
      character(len=:), allocatable :: text
      text = par_kind
      if (par_kind == 'MPI' .and. .not. par_started()) text = 'MPI not started: no launcher'
   end function how_run

   !> Plausibility warnings on stderr (--quiet keeps them; &run warnings = .false. has none).
   subroutine warn(lines)
      character(len=*), intent(in) :: lines(:)   !! the warnings, as warnings() gives them
      integer :: k
      do k = 1, size(lines)
         write(error_unit, '(a)') trim(lines(k))
      end do
   end subroutine warn

   !> The lines a run says on stderr once it starts: note, then lines, then last (note and
   !> last when not empty). (An array constructor with a type-spec over trim(note) and a
   !> function result corrupts the heap under gfortran 12: built element by element here.)
   function noted(note, lines, last) result(all)
      character(len=*), intent(in) :: note       !! a line first ('': none)
      character(len=*), intent(in) :: lines(:)   !! the other lines
      character(len=*), intent(in) :: last       !! a line last ('': none)
      character(len=max(len(note), len(lines), len(last))), allocatable :: all(:)
      integer :: k0, k1
      k0 = merge(1, 0, len_trim(note) > 0)
      k1 = merge(1, 0, len_trim(last) > 0)
      allocate(all(size(lines) + k0 + k1))
      if (k0 == 1) all(1) = note
      all(k0 + 1:k0 + size(lines)) = lines
      if (k1 == 1) all(size(all)) = last
   end function noted

   !> The deck's plausibility warnings as stderr lines ('spallbar: warning: ...'); steps: the
   !> run's step count; with the run's estimate, its warnings too (an hour, 10 GB).
   function warnings(d, steps, e) result(lines)
      type(deck_t), intent(in) :: d        !! the deck
      integer, intent(in) :: steps         !! steps of the run
      type(estimate_t), intent(in), optional :: e   !! the run's estimate
      character(len=420), allocatable :: lines(:)
      integer :: k
      associate (w => deck_warnings(d, steps))
         allocate(lines(size(w)))
         do k = 1, size(w)
            lines(k) = 'spallbar: warning: ' // trim(w(k))
         end do
      end associate
      if (.not. present(e)) return
      associate (w => estimate_warnings(d, e))
         do k = 1, size(w)
            lines = [character(len=420) :: lines, 'spallbar: warning: ' // trim(w(k))]
         end do
      end associate
   end function warnings
end module spb_driver
