!> The command line of spallbar: what it asks for (cli_t, parse_command_line) and the texts
!> of --help and --version. Nothing here exits: the main program does, with the status
!> these return.
module spb_cli
   use, intrinsic :: iso_fortran_env, only: compiler_version, compiler_options
   use spb_kinds, only: wp, path_len
   use spb_identity, only: program_identity, build_revision
   use spb_error, only: spb_error_t, make_error, exit_input
   use spb_strings, only: itoa
   use spb_sys, only: stderr_is_terminal
   use spb_deck, only: write_deck_help
   use spb_hdf5, only: h5_library_version
   use spb_par, only: par_kind
   implicit none
   private
   public :: cli_t, parse_command_line, write_request, build_options
   public :: request_none, request_help, request_version, request_deck_help

   !> What the command line asks for besides a run (answered on stdout, exit 0).
   integer, parameter :: request_none = 0        !! a run or a sweep
   integer, parameter :: request_help = 1        !! --help, -h: the usage lines
   integer, parameter :: request_version = 2     !! --version: the program and its build
   integer, parameter :: request_deck_help = 3   !! --deck-help: every deck variable

   !> The command line, read.
   type :: cli_t
      integer :: request = request_none    !! --help, --version, --deck-help (request_*)
      character(len=:), allocatable :: deck      !! the deck path
      character(len=:), allocatable :: prefix    !! output path prefix (default: the deck
                                                 !! path without .nml)
      character(len=:), allocatable :: restart   !! --restart FILE ('' none)
      logical :: quiet = .false.           !! --quiet
      logical :: sweep = .false.           !! --sweep
      logical :: any_version = .false.     !! --restart-any-version: a checkpoint of another
                                           !! program restarts
      logical :: progress = .false.        !! a progress line updated in place on stderr (a
                                           !! terminal, not --quiet)
      real(wp) :: batch = 30.0_wp          !! seconds between progress lines when stderr is
                                           !! not a terminal (--progress; 0: none) [s]
      logical :: lattice = .false.         !! SPALLBAR_STEPPING=lattice: every step on the
                                           !! lattice arrays, never in characteristic form
                                           !! (spb_ring; doc/method.md), single runs and sweeps
   end type cli_t

contains

   !> Read the command line: the deck, --output, --quiet, --sweep, --restart, --progress;
   !> --help, --version and --deck-help end the reading there (cli%request); the prefix
   !> defaults to the deck path without .nml.
   subroutine parse_command_line(cli, e)
      type(cli_t), intent(out) :: cli      !! what the command line asks for
      type(spb_error_t), allocatable, intent(out) :: e   !! the error (allocated: it failed)
      call parse_arguments(cli%deck, cli%prefix, cli%quiet, cli%sweep, cli%restart, &
                           cli%any_version, cli%batch, cli%request, e)
      if (cli%quiet .or. stderr_is_terminal()) cli%batch = 0.0_wp
      cli%progress = (.not. cli%quiet) .and. stderr_is_terminal()
      cli%lattice = lattice_only()
   end subroutine parse_command_line

   !> SPALLBAR_STEPPING=lattice in the environment: the equality tests' reference
   !> (tests/cli_rings.py).
   logical function lattice_only()
      character(len=16) :: text
      integer :: length, status
      call get_environment_variable('SPALLBAR_STEPPING', text, length, status)
      lattice_only = status == 0 .and. trim(text) == 'lattice'
   end function lattice_only

   !> The arguments, one by one (see parse_command_line); request: the first of --help,
   !> --version, --deck-help (the arguments after it are not read).
   subroutine parse_arguments(path, pre, q, sw, rst, any_ver, every, request, e)
      character(len=:), allocatable, intent(out) :: path   !! the deck path
      character(len=:), allocatable, intent(out) :: pre    !! output path prefix
      logical, intent(out) :: q                !! --quiet
      logical, intent(out) :: sw               !! --sweep
      character(len=:), allocatable, intent(out) :: rst   !! --restart FILE ('' none)
      logical, intent(out) :: any_ver          !! --restart-any-version
      real(wp), intent(out) :: every           !! --progress SECONDS (default 30)
      integer, intent(out) :: request          !! --help, --version, --deck-help (request_*)
      type(spb_error_t), allocatable, intent(out) :: e   !! the error (allocated: it failed)
      integer :: k, nargs, lenarg
      character(len=path_len) :: arg
      q = .false.
      sw = .false.
      any_ver = .false.
      every = 30.0_wp
      request = request_none
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
            request = request_help
            return
         case ('--version')
            request = request_version
            return
         case ('--deck-help')
            request = request_deck_help
            return
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
   end subroutine parse_arguments

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

   !> The answer to --help, --version or --deck-help, on unit.
   subroutine write_request(unit, request)
      integer, intent(in) :: unit          !! where (standard output)
      integer, intent(in) :: request       !! request_help, request_version, request_deck_help
      select case (request)
      case (request_help)
         call usage(unit)
      case (request_version)
         call print_version(unit)
      case (request_deck_help)
         call write_deck_help(unit)
      case default
         continue   ! request_none: nothing asked
      end select
   end subroutine write_request

   !> The usage lines of --help.
   subroutine usage(unit)
      integer, intent(in) :: unit          !! where (standard output)
      write(unit, '(a)') 'usage: spallbar DECK.nml [--output PREFIX] [--quiet] ' // &
         '[--progress SECONDS] [--restart CHECKPOINT.h5 [--restart-any-version]]'
      write(unit, '(a)') '       (--progress: when stderr is not a terminal, a ' // &
         'progress line every SECONDS, default 30, 0 none, the first after 5 s at most; ' // &
         'on a terminal it updates in place)'
      write(unit, '(a)') '       [mpirun -np K] spallbar --sweep SWEEP.nml [--output ' // &
         'PREFIX] [--quiet] [--progress SECONDS]   (PREFIX.sweep, PREFIX_sweep.h5; ' // &
         par_kind // ')'
      write(unit, '(a)') '       spallbar --version | --help | --deck-help   (--deck-help: ' // &
         'every deck variable, its default, unit and meaning)'
      write(unit, '(a)') 'Reads the namelist deck, writes PREFIX.his, .prf, .evt, .frg ' // &
         '(.gau with &gauges; .h5 and .xmf with &run hdf5) (PREFIX: the deck path without .nml).'
      write(unit, '(a)') 'Exit status: 0 done, 2 bad input, 3 the run went wrong, ' // &
         '128 + N stopped by signal N (SIGTERM: 143; outputs and checkpoint written to there).'
   end subroutine usage

   !> --version: the program and how it was built (compiler and its options, sweeps on MPI or
   !> serial, the HDF5 library), so that a result can name the build that made it.
   subroutine print_version(unit)
      integer, intent(in) :: unit          !! where (standard output)
      write(unit, '(a)') program_identity()
      write(unit, '(a)') '  sources:  ' // build_revision()
      write(unit, '(a)') '  compiler: ' // compiler_version()
      write(unit, '(a)') '  options:  ' // build_options(compiler_options())
      write(unit, '(a)') '  sweeps:   ' // par_kind
      write(unit, '(a)') '  HDF5:     ' // h5_library_version()
   end subroutine print_version

   !> The compiler options that decide the numbers: every word of all, once, but include
   !> paths (-I and the path after it), the module folder (-J and the path after it: the
   !> library's, whose options these are, has one), the machine's instruction-set switches
   !> (-m..., --param, which -march=native expands to: its -march= word stays) and the
   !> pre-include.
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
         if (word == '-I' .or. word == '-J') then
            skip_next = .true.
            cycle
         end if
         if (index(word, '-I') == 1 .or. index(word, '-J') == 1 .or. &
             index(word, '--param') == 1 .or. index(word, '-fpre-include') == 1) cycle
         if (index(word, '-m') == 1 .and. index(word, '-march=') /= 1) cycle
         if (index(text // ' ', ' ' // word // ' ') > 0) cycle   ! CMake repeats -O3, -g
         text = text // ' ' // word
      end do
      text = trim(adjustl(text))
   end function build_options
end module spb_cli
