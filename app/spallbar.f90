!> spallbar: stress waves, spall and multiple collisions in layered elastic-brittle bars.
!>
!> The main program only sequences the phases of the 1988 EMC workflow: read the command
!> line (spb_cli), read the deck, set up the mesh and the state, restart or start, run,
!> report (spb_driver), exit. Exit status 2: bad input; 3: a run that went wrong; 128 +
!> signal: stopped by SIGTERM/SIGINT (outputs complete to that step); 0: success.
program spallbar
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use spb_error, only: spb_error_t
   use spb_cli, only: cli_t, parse_command_line, write_request, request_none
   use spb_deck, only: deck_t, read_deck
   use spb_sim, only: sim_t, sim_setup, sim_run, checkpoint_t
   use spb_checkpoint, only: read_checkpoint
   use spb_summary, only: run_summary_t
   use spb_driver, only: announce_run, write_report, sweep_main
   use spb_sys, only: sys_exit, catch_stop_signals, heap_for_large_arrays
   implicit none

   type(cli_t) :: cli
   type(deck_t) :: deck
   type(sim_t) :: sim
   type(checkpoint_t), allocatable :: ck   ! allocated: the run restarts from it
   type(run_summary_t) :: summary
   type(spb_error_t), allocatable :: err
   character(len=:), allocatable :: notes(:)   ! said on stderr once the run starts
   integer :: status

   call heap_for_large_arrays()
   call parse_command_line(cli, err)
   if (allocated(err)) call fail(err)
   if (cli%request /= request_none) then      ! --help, --version, --deck-help
      call write_request(output_unit, cli%request)
      call sys_exit(0)
   end if
   if (cli%sweep) then                        ! --sweep: every rank, its own exit status
      call sweep_main(cli, status)
      call sys_exit(status)
   end if
   call read_deck(cli%deck, deck, err)
   if (allocated(err)) call fail(err)
   call sim_setup(deck, sim, err, restart=len(cli%restart) > 0, rings=.not. cli%lattice)
   if (allocated(err)) call fail(err)
   if (len(cli%restart) > 0) then
      allocate(ck)
      call read_checkpoint(cli%restart, sim%record, sim%mesh, sim%load, ck, err, &
                           any_version=cli%any_version)
      if (allocated(err)) call fail(err)
   end if
   call announce_run(output_unit, cli, deck, sim, notes, ck)
   call catch_stop_signals()
   call sim_run(sim, cli%prefix, cli%progress, summary, err, resume=ck, &
                batch_seconds=cli%batch, notes=notes)
   if (allocated(err)) call fail(err)
   if (.not. cli%quiet) call write_report(output_unit, sim, summary, cli%prefix)

contains

   !> Write the error's message to standard error and exit with its code.
   subroutine fail(e)
      type(spb_error_t), intent(in) :: e   !! the error (its code is the exit status)
      write(error_unit, '(a)') 'spallbar: ' // e%message
      flush(error_unit)
      flush(output_unit)
      call sys_exit(e%code)
   end subroutine fail
end program spallbar
