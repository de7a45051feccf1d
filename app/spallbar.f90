!> spallbar: stress waves, spall and multiple collisions in layered elastic-brittle bars.
!>
!> The main program only sequences the phases of the 1988 EMC workflow: read the deck,
!> echo it, build the mesh, initialise, step, write columns. Exit status 2: bad input;
!> 3: a run that went wrong; 128 + signal: stopped by SIGTERM/SIGINT (outputs complete to
!> that step); 0: success.
program spallbar
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit, compiler_version, compiler_options
   use spb_kinds, only: wp, path_len
   use spb_identity, only: program_identity, build_revision
   use spb_error, only: spb_error_t, make_error, exit_input
   use spb_strings, only: itoa
   use spb_deck, only: deck_t, read_deck, write_deck_help, deck_warnings
   use spb_sim, only: sim_t, sim_setup, sim_run, checkpoint_t
   use spb_summary, only: run_summary_t, write_summary
   use spb_checkpoint, only: read_checkpoint
   use spb_output, only: write_mesh_summary
   use spb_hdf5, only: h5_library_version
   use spb_diag, only: frag_info_t, fragment_list
   use spb_sys, only: sys_exit, stderr_is_terminal, catch_stop_signals, heap_for_large_arrays
   use spb_sweep, only: run_sweep, sweep_summary_t
   use spb_estimate, only: estimate_t, estimate_run, estimate_line, estimate_warnings
   use spb_par, only: par_init, par_finalize, par_barrier, par_rank, par_kind
   implicit none

   type(deck_t) :: deck
   type(sim_t) :: sim
   type(run_summary_t) :: summary
   type(estimate_t) :: est   ! the work and the outputs of the run, before it starts
   type(spb_error_t), allocatable :: err
   character(len=:), allocatable :: deck_path, prefix, restart_path
   logical :: quiet, sweep
   logical :: any_version   ! --restart-any-version: a checkpoint of another program restarts
   character(len=:), allocatable :: note   ! what a restart of another program's checkpoint says
   real(wp) :: batch   ! seconds between progress lines when stderr is not a terminal (0: none)

   call heap_for_large_arrays()
   call parse_command_line(deck_path, prefix, quiet, sweep, restart_path, any_version, batch, err)
   if (quiet .or. stderr_is_terminal()) batch = 0.0_wp
   if (allocated(err)) call fail(err)
   if (sweep) call sweep_main()
   call read_deck(deck_path, deck, err)
   if (allocated(err)) call fail(err)
   call sim_setup(deck, sim, err, restart=len(restart_path) > 0)
   if (allocated(err)) call fail(err)
   if (len(restart_path) > 0) then
      block
         type(checkpoint_t) :: ck
         call read_checkpoint(restart_path, sim%record, sim%mesh, sim%load, ck, err, &
                              any_version=any_version)
         if (allocated(err)) call fail(err)
         ! another program's checkpoint (--restart-any-version): said once the run starts
         note = ''
         if (ck%program /= program_identity()) then
            sim%record%restarted_from = ck%program
            note = 'spallbar: --restart-any-version: ''' // restart_path // ''' was written by ' &
               // ck%program // ', this is ' // program_identity() // '; the outputs are ' // &
               'not one uninterrupted run of one program (every header says so)'
         end if
         est = estimate_run(deck, sim%mesh%n, sim%mesh%nsteps, sim%mesh%dt, ck%st%step, .true.)
         if (.not. quiet) then
            write(output_unit, '(a)') program_identity() // ': ' // trim(deck%run%title)
            call write_mesh_summary(output_unit, sim%mesh, sim%report, '  ')
            write(output_unit, '(a,i0,a,es12.5,a)') '  restart from ' // restart_path // &
               ' at step ', ck%st%step, ' (t = ', real(ck%st%step, wp) * sim%mesh%dt, ' s)'
            write(output_unit, '(a)') '  ' // estimate_line(est)
         end if
         flush(output_unit)   ! a log of stdout and stderr together: the header first
         call catch_stop_signals()
         call sim_run(sim, prefix, (.not. quiet) .and. stderr_is_terminal(), summary, err, &
                      resume=ck, batch_seconds=batch, &
                      notes=noted(note, warnings(deck, sim%mesh%nsteps, est)))
      end block
   else
      est = estimate_run(deck, sim%mesh%n, sim%mesh%nsteps, sim%mesh%dt, 0, .true.)
      if (.not. quiet) then
         write(output_unit, '(a)') program_identity() // ': ' // trim(deck%run%title)
         call write_mesh_summary(output_unit, sim%mesh, sim%report, '  ')
         write(output_unit, '(a)') '  ' // estimate_line(est)
      end if
      flush(output_unit)   ! a log of stdout and stderr together: the header first
      call catch_stop_signals()
      call sim_run(sim, prefix, (.not. quiet) .and. stderr_is_terminal(), summary, err, &
                   batch_seconds=batch, notes=warnings(deck, sim%mesh%nsteps, est))
   end if
   if (allocated(err)) call fail(err)
   if (.not. quiet) call write_outcome()

contains

   !> The end-of-run text (spb_summary), with the fragments at the end and every file the
   !> run wrote.
   subroutine write_outcome()
      type(frag_info_t), allocatable :: list(:)
      character(len=:), allocatable :: files
      call fragment_list(sim%mesh, sim%st, list)
      files = prefix // '.his, ' // prefix // '.prf, ' // prefix // '.evt, ' // prefix // '.frg'
      if (allocated(sim%record%gauge_x)) then
         if (size(sim%record%gauge_x) > 0) files = files // ', ' // prefix // '.gau'
      end if
      if (sim%record%hdf5) files = files // ', ' // prefix // '.h5, ' // prefix // '.xmf'
      if (summary%checkpoints > 0) files = files // ', checkpoint ' // sim%opt%checkpoint // &
         ' (step ' // itoa(summary%steps) // ')'
      call write_summary(output_unit, summary, list, prefix, files)
   end subroutine write_outcome

   !> Write the error's message to standard error and exit with its code.
   subroutine fail(e)
      type(spb_error_t), intent(in) :: e   !! the error (its code is the exit status)
      write(error_unit, '(a)') 'spallbar: ' // e%message
      flush(error_unit)
      flush(output_unit)
      call sys_exit(e%code)
   end subroutine fail

   !> --sweep: every rank reads and checks the deck (the same answer everywhere), runs its
   !> cases; rank 0 reports and writes the outputs. Exits: 0, 2 bad input, 3 some case went
   !> wrong, 128 + signal.
   subroutine sweep_main()
      type(sweep_summary_t) :: ssum
      integer :: rank
      call par_init()
      rank = par_rank()
      call read_deck(deck_path, deck, err, sweep=.true.)
      if (.not. allocated(err)) then
         if (rank == 0 .and. .not. quiet) write(output_unit, '(a)') program_identity() // &
            ' sweep: ' // trim(deck%run%title)
         flush(output_unit)
         if (rank == 0) call warn(warnings(deck, 0))
         call catch_stop_signals()
         call run_sweep(deck, prefix, rank == 0 .and. (.not. quiet) .and. stderr_is_terminal(), &
                        ssum, err, batch_seconds=merge(batch, 0.0_wp, rank == 0), &
                        echo=rank == 0 .and. .not. quiet)
      end if
      if (rank == 0 .and. .not. quiet .and. ssum%cases > 0) then
         write(output_unit, '(a,i0,a,i0,a,a,a,a,a,f0.3,a)') '  done: ', ssum%cases, ' cases on ', &
            ssum%ranks, ' rank(s) (', trim(ssum%distribution), ', ', par_kind, ') in ', &
            ssum%wall, ' s wall'
         write(output_unit, '(a,i0,a,i0,a,i0,a)') '  cases done: ', ssum%done, ', went wrong: ', &
            ssum%failed, ', not run: ', ssum%not_run, '; wrote ' // prefix // '.sweep, ' // &
            prefix // '_sweep.h5'
      end if
      flush(output_unit)
      ! stopped by a signal: rank 0 writes the table and its message, then every rank exits
      ! 128 + signal at once, without MPI_Finalize: mpirun, when it got the signal itself,
      ! is ending the job, never completes a finalize and SIGKILLs the ranks 1 s after
      ! forwarding the signal (odls_base_sigkill_timeout; doc/sweeps.md)
      if (ssum%signal /= 0) then
         if (rank == 0 .and. allocated(err)) then
            write(error_unit, '(a)') 'spallbar: ' // err%message
            flush(error_unit)
         end if
         call par_barrier()
         if (allocated(err)) call sys_exit(err%code)
         call sys_exit(128 + ssum%signal)
      end if
      call par_finalize()
      if (allocated(err)) then
         if (rank == 0) call fail(err)
         call sys_exit(err%code)
      end if
      call sys_exit(0)
   end subroutine sweep_main

   !> The usage lines of --help, on standard output.
   subroutine usage()
      write(output_unit, '(a)') 'usage: spallbar DECK.nml [--output PREFIX] [--quiet] ' // &
         '[--progress SECONDS] [--restart CHECKPOINT.h5 [--restart-any-version]]'
      write(output_unit, '(a)') '       (--progress: when stderr is not a terminal, a ' // &
         'progress line every SECONDS, default 30, 0 none, the first after 5 s at most; ' // &
         'on a terminal it updates in place)'
      write(output_unit, '(a)') '       [mpirun -np K] spallbar --sweep SWEEP.nml [--output ' // &
         'PREFIX] [--quiet] [--progress SECONDS]   (PREFIX.sweep, PREFIX_sweep.h5; ' // &
         par_kind // ')'
      write(output_unit, '(a)') '       spallbar --version | --help | --deck-help   (--deck-help: ' // &
         'every deck variable, its default, unit and meaning)'
      write(output_unit, '(a)') 'Reads the namelist deck, writes PREFIX.his, .prf, .evt, .frg ' // &
         '(.gau with &gauges; .h5 and .xmf with &run hdf5) (PREFIX: the deck path without .nml).'
      write(output_unit, '(a)') 'Exit status: 0 done, 2 bad input, 3 the run went wrong, ' // &
         '128 + N stopped by signal N (SIGTERM: 143; outputs and checkpoint written to there).'
   end subroutine usage

   !> Plausibility warnings on stderr (--quiet keeps them; &run warnings = .false. has none).
   subroutine warn(lines)
      character(len=*), intent(in) :: lines(:)   !! the warnings, as warnings() gives them
      integer :: k
      do k = 1, size(lines)
         write(error_unit, '(a)') trim(lines(k))
      end do
   end subroutine warn

   !> The lines a run says on stderr once it starts: note (when not empty), then lines. (An
   !> array constructor with a type-spec over trim(note) and a function result corrupts the
   !> heap under gfortran 12: built element by element here.)
   function noted(note, lines) result(all)
      character(len=*), intent(in) :: note       !! a line first ('': none)
      character(len=*), intent(in) :: lines(:)   !! the other lines
      character(len=max(len(note), len(lines))), allocatable :: all(:)
      integer :: k0
      k0 = merge(1, 0, len_trim(note) > 0)
      allocate(all(size(lines) + k0))
      if (k0 == 1) all(1) = note
      all(k0 + 1:) = lines
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

   !> --version: the program and how it was built (compiler and its options, sweeps on MPI or
   !> serial, the HDF5 library), so that a result can name the build that made it.
   subroutine print_version()
      write(output_unit, '(a)') program_identity()
      write(output_unit, '(a)') '  sources:  ' // build_revision()
      write(output_unit, '(a)') '  compiler: ' // compiler_version()
      write(output_unit, '(a)') '  options:  ' // build_options(compiler_options())
      write(output_unit, '(a)') '  sweeps:   ' // par_kind
      write(output_unit, '(a)') '  HDF5:     ' // h5_library_version()
   end subroutine print_version

   !> The compiler options that decide the numbers: every word of all, once, but include
   !> paths (-I and the path after it), the machine's instruction-set switches (-m...,
   !> --param, which -march=native expands to: its -march= word stays) and the pre-include.
   function build_options(all) result(text)
      character(len=*), intent(in) :: all   !! compiler_options()
      character(len=:), allocatable :: text
      character(len=:), allocatable :: word
      integer :: i, j
      logical :: skip_next
      text = ''
      skip_next = .false.
      i = 1
      do while (i <= len_trim(all))
         j = index(all(i:), ' ')
         if (j == 0) then
            j = len_trim(all) + 1
         else
            j = i + j - 1
         end if
         word = all(i:j - 1)
         i = j + 1
         if (len(word) == 0) cycle
         if (skip_next) then
            skip_next = .false.
            cycle
         end if
         if (word == '-I') then
            skip_next = .true.
            cycle
         end if
         if (index(word, '-I') == 1 .or. index(word, '--param') == 1 .or. &
             index(word, '-fpre-include') == 1) cycle
         if (index(word, '-m') == 1 .and. index(word, '-march=') /= 1) cycle
         if (index(text // ' ', ' ' // word // ' ') > 0) cycle   ! CMake repeats -O3, -g
         text = text // ' ' // word
      end do
      text = trim(adjustl(text))
   end function build_options

   !> Read the command line: the deck, --output, --quiet, --sweep and --restart (--help,
   !> --version and --deck-help print and exit 0); the prefix defaults to the deck path
   !> without .nml.
   subroutine parse_command_line(path, pre, q, sw, rst, any_ver, every, e)
      character(len=:), allocatable, intent(out) :: path   !! the deck path
      character(len=:), allocatable, intent(out) :: pre    !! output path prefix
      character(len=:), allocatable, intent(out) :: rst   !! --restart FILE ('' none)
      logical, intent(out) :: q                !! --quiet
      logical, intent(out) :: sw               !! --sweep
      logical, intent(out) :: any_ver          !! --restart-any-version
      real(wp), intent(out) :: every           !! --progress SECONDS (default 30)
      type(spb_error_t), allocatable, intent(out) :: e   !! the error (allocated: it failed)
      integer :: k, nargs, lenarg
      character(len=path_len) :: arg
      q = .false.
      sw = .false.
      any_ver = .false.
      every = 30.0_wp
      path = ''
      pre = ''
      rst = ''
      nargs = command_argument_count()
      k = 1
      do while (k <= nargs)
         call get_command_argument(k, arg, lenarg)
         if (lenarg > path_len) then
            call make_error(e, 'command line: argument ' // itoa(k) // ' is longer than ' // &
                            itoa(path_len) // ' characters')
            return
         end if
         select case (trim(arg))
         case ('--help', '-h')
            call usage()
            call sys_exit(0)
         case ('--version')
            call print_version()
            call sys_exit(0)
         case ('--deck-help')
            call write_deck_help(output_unit)
            call sys_exit(0)
         case ('--quiet', '-q')
            q = .true.
         case ('--output', '-o')
            call option_value(k, nargs, arg, e, '--output needs a PREFIX')
            if (allocated(e)) return
            pre = trim(arg)
         case ('--sweep')
            sw = .true.
         case ('--restart-any-version')
            any_ver = .true.
         case ('--progress')
            call option_value(k, nargs, arg, e, '--progress needs SECONDS (0: no lines)')
            if (allocated(e)) return
            block
               integer :: ios
               read(arg, *, iostat=ios) every
               if (ios /= 0 .or. .not. (every >= 0.0_wp .and. every <= 1.0e6_wp)) then
                  call make_error(e, 'command line: --progress needs SECONDS in 0 .. 1e6, ' // &
                                  'got ''' // trim(arg) // '''')
                  return
               end if
            end block
         case ('--restart')
            call option_value(k, nargs, arg, e, '--restart needs a CHECKPOINT file')
            if (allocated(e)) return
            rst = trim(arg)
         case default
            if (arg(1:1) == '-') then
               call make_error(e, 'command line: unknown option ''' // trim(arg) // &
                               ''' (see spallbar --help)')
               return
            end if
            if (len(path) > 0) then
               call make_error(e, 'command line: more than one deck given (''' // path // &
                               ''' and ''' // trim(arg) // ''')')
               return
            end if
            path = trim(arg)
         end select
         k = k + 1
      end do
      if (len(path) == 0) then
         call make_error(e, 'command line: no deck given (usage: spallbar DECK.nml ' // &
                         '[--output PREFIX] [--quiet])', code=exit_input)
         return
      end if
      if (any_ver .and. len(rst) == 0) then
         call make_error(e, 'command line: --restart-any-version goes with --restart CHECKPOINT')
         return
      end if
      if (sw .and. len(rst) > 0) then
         call make_error(e, 'command line: --restart is for one run, not with --sweep')
         return
      end if
      if (len(pre) == 0) then
         pre = path
         if (len(pre) > 4) then
            if (pre(len(pre)-3:) == '.nml') pre = pre(:len(pre)-4)
         end if
      end if
   end subroutine parse_command_line

   !> The value after the option at argument k into arg (k moves on to it); the error
   !> 'command line: missing' when there is none.
   subroutine option_value(k, nargs, arg, e, missing)
      integer, intent(inout) :: k          !! index of the option; moved on to its value
      integer, intent(in) :: nargs         !! number of command-line arguments
      ! the caller's buffer receives the argument
      ! allow(assumed-size-character-intent)
      character(len=*), intent(inout) :: arg   !! the option's value
      type(spb_error_t), allocatable, intent(inout) :: e   !! the error (allocated: it failed)
      character(len=*), intent(in) :: missing   !! what the error says when there is no value
      if (k >= nargs) then
         call make_error(e, 'command line: ' // missing)
         return
      end if
      k = k + 1
      call get_command_argument(k, arg)
   end subroutine option_value
end program spallbar
