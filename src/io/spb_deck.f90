!> The namelist deck (INTERFACE.md): types with defaults, reading, validation, echo.
!>
!> Reading never stops the program: every problem comes back as one error naming the
!> group and the variable. Real inputs are tested for being finite before any comparison
!> (a NaN compared under -ffpe-trap=invalid would trap).
module spb_deck
   use, intrinsic :: iso_fortran_env, only: iostat_end
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp, max_segments, max_profiles, name_len, path_len, max_sweep_values, &
      max_realizations
   use spb_error, only: spb_error_t, make_error
   use spb_strings, only: itoa, rtoa, lower, ltoa
   use spb_prescan, only: deck_scan_t, scan_deck, has_group, has_var, assignment_text
   use spb_sys, only: fp_traps_off, fp_traps_restore
   use spb_mesh, only: mesh_fault_t, max_cells, max_steps, fault_cells, fault_segment_cells, &
      fault_not_whole, fault_short_segment, fault_mesh_cells, fault_short_run, fault_long_run
   use spb_problem, only: problem_t, end_free, end_fixed, end_transmit, end_base, load_none, &
      load_power, load_table, load_exponential, face_top, face_bottom, timing_accelerate, &
      timing_delay, timing_min, shift_above, shift_fragment, events_admissible, events_paper
   implicit none
   private
   public :: deck_t
   public :: read_deck, validate_deck, write_echo, known_groups, set_deck_value, &
      problem_from_deck, deck_record_t, deck_record, mesh_fault_message

   real(wp), parameter :: unset = -huge(1.0_wp)   !! marks a real the deck did not give

   character(len=16), parameter :: known_groups(8) = [character(len=16) :: 'run', 'mesh', &
      'segments', 'ends', 'load', 'initial', 'strength_field', 'sweep']

   !> One echoed deck value (write_echo, and the attributes of PREFIX.h5).
   type :: echo_item_t
      character(len=:), allocatable :: group, name, value, unit
      logical :: given = .false.                        !! set in the deck (else default)
   end type echo_item_t

   type :: run_cfg
      character(len=path_len) :: title = ''             !! echoed in every output header
      real(wp) :: t_end = unset                         !! end time [s], required
      real(wp) :: gravity = 0.0_wp                      !! acceleration along +x [m/s^2]
      character(len=name_len) :: timing = 'accelerate'  !! collision timing rule
      character(len=name_len) :: shift = 'above'        !! collision shift policy
      character(len=name_len) :: events = 'admissible' !! event rules: 'admissible' (they never
                                                        !! create wave energy) | 'paper' (literal)
      real(wp) :: eps_rel = 1.0e-9_wp                   !! round-off guard of the fracture test [-]
      integer :: history_every = 1                      !! steps between history rows
      integer :: field_every = 0                        !! steps between x-t field rows in
                                                        !! PREFIX.h5 (0: none)
      real(wp) :: profile_times(max_profiles) = unset   !! profile snapshot times [s]
      integer :: n_profiles = 0                         !! how many profile_times were given
      logical :: hdf5 = .false.                         !! also write PREFIX.h5
      character(len=name_len) :: model = 'half-mass'    !! 'half-mass' | 'full-mass' (naive)
      real(wp) :: energy_guard = 0.5_wp                 !! stop (exit 3) when mechanical energy
                                                        !! exceeds initial + work by this share
      character(len=path_len) :: checkpoint = ''        !! restart file written at t_end ('': none)
      integer :: checkpoint_every = 0                   !! and every so many steps (0: at the end)
   end type run_cfg

   type :: mesh_cfg
      integer :: cells = 0                              !! cells in the reference segment
      integer :: ref_segment = 1                        !! segment that sets dt from cells
      real(wp) :: dt = 0.0_wp                           !! time step [s] when > 0
      character(len=name_len) :: fit = 'strict'         !! 'strict' | 'stretch'
   end type mesh_cfg

   type :: segments_cfg
      integer :: n = 1                                  !! number of segments
      real(wp) :: length(max_segments) = unset          !! [m]
      real(wp) :: young(max_segments) = unset           !! [Pa]
      real(wp) :: density(max_segments) = unset         !! [kg/m^3]
      real(wp) :: strength(max_segments) = unset        !! tensile strength [Pa]; < 0 unbreakable
      character(len=name_len) :: interface(max_segments) = ''   !! 'bonded' | 'dry'
      real(wp) :: velocity(max_segments) = unset        !! initial rigid velocity [m/s]
      real(wp) :: gap(max_segments) = unset             !! initial gap at a dry interface [m]
   end type segments_cfg

   type :: ends_cfg
      character(len=name_len) :: top = 'free'          !! 'free' | 'fixed' | 'transmit'
      character(len=name_len) :: bottom = 'free'       !! 'free' | 'fixed' | 'base' | 'transmit'
      real(wp) :: base_gap = 0.0_wp                    !! gap to the base [m]
   end type ends_cfg

   type :: load_cfg
      character(len=name_len) :: kind = 'none'         !! 'none' | 'power' | 'exponential' | 'table'
      character(len=name_len) :: face = 'top'          !! 'top' | 'bottom'
      real(wp) :: p0 = unset                           !! pressure scale [Pa]; required by
                                                       !! 'power' and 'exponential'
      real(wp) :: t_k = unset                          !! decay time [s]
      real(wp) :: exponent = 0.0_wp                    !! power-law exponent [-]
      real(wp) :: t_cut = unset                        !! p = 0 after t_cut [s]
      character(len=path_len) :: table = ''            !! two-column file t [s], p [Pa]
   end type load_cfg

   type :: initial_cfg
      character(len=name_len) :: state = 'unstressed'  !! 'unstressed' | 'static'
      real(wp) :: strain_rate = 0.0_wp                 !! uniform stretching: v += rate (x - x_c),
                                                       !! x_c the centre of mass [1/s]
   end type initial_cfg

   !> &strength_field: random strength per cell (issue 8).
   type :: strength_field_cfg
      character(len=name_len) :: kind = 'uniform'      !! 'uniform' (segment strengths) | 'weibull'
      real(wp) :: modulus = unset                      !! Weibull modulus m [-]
      real(wp) :: scale = unset                        !! Weibull scale [Pa]
      integer :: seed = 1                              !! generator seed (spb_random)
   end type strength_field_cfg

   !> &sweep (only read with --sweep): Monte-Carlo realizations of the strength field, a
   !> parameter sweep over values of one deck variable, or both (every value x every
   !> realization).
   type :: sweep_cfg
      integer :: realizations = 0                      !! per value; 0: the deck's own field
      integer :: seed = 1                              !! realization i: realization_seed(seed, i)
      character(len=name_len) :: vary = ''             !! deck variable, e.g. 'p0', 'velocity(1)'
      real(wp) :: values(max_sweep_values) = unset     !! its values
      integer :: n_values = 0                          !! how many values were given
      character(len=name_len) :: distribution = 'static'  !! 'static' | 'dynamic' over ranks
      integer :: bins = 50                             !! fragment-length histogram bins
   end type sweep_cfg

   !> What the outputs and the checkpoints say of a deck (and need of it): where it came
   !> from, its title, every value as echoed, and the settings that shape the files.
   type :: deck_record_t
      character(len=:), allocatable :: path           !! the deck file
      character(len=:), allocatable :: title          !! &run title
      character(len=:), allocatable :: table          !! &load table ('' : none)
      type(echo_item_t), allocatable :: items(:)      !! every value, given or default
      logical :: hdf5 = .false.                       !! &run hdf5
      integer :: field_every = 0                      !! &run field_every [steps]
      real(wp) :: t_end = 0.0_wp                      !! &run t_end [s]
      real(wp), allocatable :: profile_times(:)       !! &run profile_times given [s]
   end type deck_record_t

   type :: deck_t
      character(len=path_len) :: path = '(built in memory)'   !! where the deck came from
      type(run_cfg) :: run
      type(mesh_cfg) :: mesh
      type(segments_cfg) :: seg
      type(ends_cfg) :: ends
      type(load_cfg) :: load
      type(initial_cfg) :: init
      type(strength_field_cfg) :: field
      type(sweep_cfg) :: sweep
      logical :: is_sweep = .false.   !! read for --sweep: &sweep is required and echoed
      type(deck_scan_t) :: scan   !! what the file assigned (marks echo lines as input)
   end type deck_t

contains

   !> The problem a validated deck describes: the keywords become codes, the "not given"
   !> markers defaults or logicals (a load table's rows are read by spb_load_table).
   function problem_from_deck(deck) result(prob)
      type(deck_t), intent(in) :: deck     !! the deck
      type(problem_t) :: prob
      integer :: n, j
      n = deck%seg%n
      prob%nseg = n
      allocate(prob%length(n), prob%young(n), prob%density(n), prob%strength(n), &
               prob%velocity(n), prob%dry(n), prob%gap(n))
      prob%length(:) = deck%seg%length(1:n)
      prob%young(:) = deck%seg%young(1:n)
      prob%density(:) = deck%seg%density(1:n)
      prob%strength(:) = deck%seg%strength(1:n)
      prob%velocity(:) = deck%seg%velocity(1:n)
      prob%dry = .false.
      prob%gap = 0.0_wp
      do j = 1, n - 1
         prob%dry(j) = deck%seg%interface(j) == 'dry'
         if (is_set(deck%seg%gap(j))) prob%gap(j) = deck%seg%gap(j)
      end do
      prob%cells = deck%mesh%cells
      prob%ref_segment = deck%mesh%ref_segment
      prob%dt = deck%mesh%dt
      prob%stretch = deck%mesh%fit == 'stretch'
      prob%t_end = deck%run%t_end
      prob%top = end_of(deck%ends%top)
      prob%bottom = end_of(deck%ends%bottom)
      prob%base_gap = deck%ends%base_gap
      select case (deck%load%kind)
      case ('power')
         prob%load_kind = load_power
      case ('exponential')
         prob%load_kind = load_exponential
      case ('table')
         prob%load_kind = load_table
      case default
         prob%load_kind = load_none
      end select
      prob%load_face = merge(face_bottom, face_top, deck%load%face == 'bottom')
      if (is_set(deck%load%p0)) prob%p0 = deck%load%p0
      prob%has_t_k = is_set(deck%load%t_k)
      if (prob%has_t_k) prob%t_k = deck%load%t_k
      prob%exponent = deck%load%exponent
      prob%has_t_cut = is_set(deck%load%t_cut)
      if (prob%has_t_cut) prob%t_cut = deck%load%t_cut
      prob%static_start = deck%init%state == 'static'
      prob%strain_rate = deck%init%strain_rate
      prob%weibull = deck%field%kind == 'weibull'
      if (is_set(deck%field%modulus)) prob%weibull_modulus = deck%field%modulus
      if (is_set(deck%field%scale)) prob%weibull_scale = deck%field%scale
      prob%seed = deck%field%seed
      prob%gravity = deck%run%gravity
      prob%full_mass = deck%run%model == 'full-mass'
      select case (deck%run%timing)
      case ('delay')
         prob%timing = timing_delay
      case ('min')
         prob%timing = timing_min
      case default
         prob%timing = timing_accelerate
      end select
      prob%shift = merge(shift_fragment, shift_above, deck%run%shift == 'fragment')
      prob%events = merge(events_paper, events_admissible, deck%run%events == 'paper')
      prob%eps_rel = deck%run%eps_rel
   contains
      !> The end code of an end keyword.
      integer function end_of(word)
         character(len=*), intent(in) :: word
         select case (word)
         case ('fixed')
            end_of = end_fixed
         case ('transmit')
            end_of = end_transmit
         case ('base')
            end_of = end_base
         case default
            end_of = end_free
         end select
      end function end_of
   end function problem_from_deck

   !> Whether a real was given (not the "not given" marker).
   logical elemental function is_set(x)
      real(wp), intent(in) :: x
      is_set = .true.
      if (ieee_is_finite(x)) is_set = x > 0.5_wp * unset
   end function is_set

   !> Read and validate a deck file.
   subroutine read_deck(path, deck, err, sweep)
      character(len=*), intent(in) :: path       !! deck file
      type(deck_t), intent(out) :: deck    !! the deck
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      logical, intent(in), optional :: sweep     !! a sweep deck (--sweep): &sweep required
      integer :: u, ios
      character(len=256) :: msg
      logical :: traps(3)

      call scan_deck(path, known_groups, deck%scan, err)
      if (allocated(err)) return
      deck%path = path
      if (.not. has_group(deck%scan, 'run')) then
         call make_error(err, '&run: required group is missing (it must give t_end)')
         return
      end if
      if (present(sweep)) deck%is_sweep = sweep
      if (has_group(deck%scan, 'sweep') .and. .not. deck%is_sweep) then
         call make_error(err, '&sweep: this deck is a sweep; run it with spallbar --sweep ' // &
                         trim(path) // ' (under mpirun for several ranks)')
         return
      end if
      if (deck%is_sweep .and. .not. has_group(deck%scan, 'sweep')) then
         call make_error(err, '&sweep: required group is missing (--sweep needs realizations ' &
                         // 'or vary and values)')
         return
      end if
      open(newunit=u, file=path, status='old', action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, 'deck: cannot open ''' // trim(path) // ''': ' // trim(msg))
         return
      end if
      call fp_traps_off(traps)
      call read_run(u, deck, err)
      if (.not. allocated(err)) call read_mesh(u, deck, err)
      if (.not. allocated(err)) call read_segments(u, deck, err)
      if (.not. allocated(err)) call read_ends(u, deck, err)
      if (.not. allocated(err)) call read_load(u, deck, err)
      if (.not. allocated(err)) call read_initial(u, deck, err)
      if (.not. allocated(err)) call read_strength_field(u, deck, err)
      if (.not. allocated(err) .and. deck%is_sweep) call read_sweep(u, deck, err)
      close(u)
      ! validation compares values the user gave, NaN and Inf among them, before it rejects
      ! them: the traps stay off until it is done
      if (.not. allocated(err)) call validate_deck(deck, err)
      if (.not. allocated(err) .and. deck%is_sweep) call validate_sweep(deck, err)
      call fp_traps_restore(traps)
   end subroutine read_deck

   !> A keyword value longer than any keyword is an error here (the deck keeps name_len
   !> characters, and a cut value could look like a valid one).
   subroutine check_word(err, group, var, value)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: var   !! variable name
      character(len=*), intent(in) :: value   !! its value text
      if (allocated(err)) return
      if (len_trim(value) > name_len) call make_error(err, '&' // group // ': ' // var // &
         ': ''' // value(1:20) // '...'' is longer than any choice (' // itoa(name_len) // &
         ' characters at most)')
   end subroutine check_word

   !> The error for the one assignment (record, '&group var = value /') that does not read.
   subroutine blame(err, group, var, record, msg)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: var   !! variable name
      character(len=*), intent(in) :: record
      character(len=*), intent(in) :: msg
      character(len=*), parameter :: nomatch = 'Cannot match namelist object name '
      character(len=:), allocatable :: value, name
      integer :: k
      k = index(msg, nomatch)
      if (k > 0) then
         ! the reader could not match a name: the variable itself, or a word in its value
         name = lower(trim(adjustl(msg(k + len(nomatch):))))
         k = scan(name, '(')
         if (k > 1) name = name(:k - 1)
         if (name == var .or. name == '''' // var // '''') then
            call make_error(err, '&' // group // ': ' // var // ': unknown variable in this group')
            return
         end if
      end if
      k = index(record, '=')
      value = record(k + 1:len(record) - 2)
      do k = 1, len(value)
         if (iachar(value(k:k)) < 32) value(k:k) = ' '
      end do
      value = trim(adjustl(value))
      if (len(value) > 0) then
         if (value(len(value):) == ',') value = trim(value(:len(value) - 1))
      end if
      if (len(value) > 40) value = value(1:37) // '...'
      if (len(value) > 0) then
         if (value(1:1) /= '''' .and. value(1:1) /= '"') value = '''' // value // ''''
      end if
      call make_error(err, '&' // group // ': ' // var // ': cannot read the value ' // &
                      value // ' (wrong type, unquoted text, or more values than it holds?)')
   end subroutine blame

   !> Turn a namelist read status into an error naming the group (and the variable).
   subroutine read_status(deck, group, ios, msg, err)
      type(deck_t), intent(in) :: deck     !! the deck
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: msg
      integer, intent(in) :: ios
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), parameter :: nomatch = 'Cannot match namelist object name '
      character(len=:), allocatable :: name
      integer :: k
      if (ios == 0 .or. allocated(err)) return
      if (ios == iostat_end) then
         if (has_group(deck%scan, group)) call make_error(err, '&' // group // &
            ': the group could not be read to its end (unbalanced quotes or a missing ''/''?)')
         return
      end if
      k = index(msg, nomatch)
      if (k > 0) then
         name = lower(trim(adjustl(msg(k + len(nomatch):))))
         if (len(name) >= 2) then
            if (scan(name(1:1), '''"') > 0 .and. name(len(name):len(name)) == name(1:1)) then
               name = name(2:len(name)-1)
            end if
         end if
         k = scan(name, '(')
         if (k > 1) name = name(:k-1)
         if (has_var(deck%scan, group, name)) then
            call make_error(err, '&' // group // ': ' // name // ': unknown variable in this group')
         else
            call make_error(err, '&' // group // ': cannot read the value ''' // name // &
                            ''' (wrong type, unquoted text or too many values?)')
         end if
      else
         call make_error(err, '&' // group // ': cannot read the group: ' // trim(msg))
      end if
   end subroutine read_status

   !> Read &run (defaults kept for what the deck leaves out).
   subroutine read_run(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=path_len) :: title
      real(wp) :: t_end, gravity, eps_rel, profile_times(max_profiles)
      character(len=path_len) :: timing, shift, model, events
      integer :: history_every, field_every, ios
      logical :: hdf5
      real(wp) :: energy_guard
      character(len=path_len) :: checkpoint
      integer :: checkpoint_every
      character(len=256) :: msg
      character(len=256) :: msg2
      character(len=:), allocatable :: record, var
      integer :: k, ios2
      namelist /run/ title, t_end, gravity, timing, shift, eps_rel, history_every, &
         profile_times, hdf5, model, energy_guard, field_every, checkpoint, checkpoint_every, &
         events
      title = deck%run%title
      checkpoint = deck%run%checkpoint
      checkpoint_every = deck%run%checkpoint_every
      t_end = deck%run%t_end
      gravity = deck%run%gravity
      timing = deck%run%timing
      shift = deck%run%shift
      events = deck%run%events
      eps_rel = deck%run%eps_rel
      history_every = deck%run%history_every
      field_every = deck%run%field_every
      profile_times = deck%run%profile_times
      hdf5 = deck%run%hdf5
      model = deck%run%model
      energy_guard = deck%run%energy_guard
      rewind(u)
      read(u, nml=run, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'run', k, var)
            if (len(record) == 0) cycle
            read(record, nml=run, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'run', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'run', ios, msg, err)
      call check_word(err, 'run', 'timing', timing)
      call check_word(err, 'run', 'shift', shift)
      call check_word(err, 'run', 'events', events)
      call check_word(err, 'run', 'model', model)
      if (allocated(err)) return
      if (len_trim(title) == len(title)) then
         call make_error(err, '&run: title: longer than ' // itoa(len(title) - 1) // ' characters')
         return
      end if
      if (len_trim(checkpoint) == len(checkpoint)) then
         call make_error(err, '&run: checkpoint: longer than ' // itoa(len(checkpoint) - 1) // &
                         ' characters')
         return
      end if
      deck%run%title = title
      deck%run%checkpoint = checkpoint
      deck%run%checkpoint_every = checkpoint_every
      deck%run%t_end = t_end
      deck%run%gravity = gravity
      deck%run%timing = lower(timing)
      deck%run%shift = lower(shift)
      deck%run%events = lower(events)
      deck%run%eps_rel = eps_rel
      deck%run%history_every = history_every
      deck%run%field_every = field_every
      deck%run%profile_times = profile_times
      deck%run%hdf5 = hdf5
      deck%run%model = lower(model)
      deck%run%energy_guard = energy_guard
   end subroutine read_run

   !> Read &mesh.
   subroutine read_mesh(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: cells, ref_segment, ios
      real(wp) :: dt
      character(len=path_len) :: fit
      character(len=256) :: msg
      character(len=256) :: msg2
      character(len=:), allocatable :: record, var
      integer :: k, ios2
      namelist /mesh/ cells, ref_segment, dt, fit
      cells = deck%mesh%cells
      ref_segment = deck%mesh%ref_segment
      dt = deck%mesh%dt
      fit = deck%mesh%fit
      rewind(u)
      read(u, nml=mesh, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'mesh', k, var)
            if (len(record) == 0) cycle
            read(record, nml=mesh, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'mesh', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'mesh', ios, msg, err)
      call check_word(err, 'mesh', 'fit', fit)
      if (allocated(err)) return
      deck%mesh%cells = cells
      deck%mesh%ref_segment = ref_segment
      deck%mesh%dt = dt
      deck%mesh%fit = lower(fit)
   end subroutine read_mesh

   !> Read &segments.
   subroutine read_segments(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: n, ios, j
      real(wp), dimension(max_segments) :: length, young, density, strength, velocity, gap
      character(len=path_len) :: interface(max_segments)
      character(len=256) :: msg
      character(len=256) :: msg2
      character(len=:), allocatable :: record, var
      integer :: k, ios2
      namelist /segments/ n, length, young, density, strength, interface, velocity, gap
      n = deck%seg%n
      length = deck%seg%length
      young = deck%seg%young
      density = deck%seg%density
      strength = deck%seg%strength
      interface = deck%seg%interface
      velocity = deck%seg%velocity
      gap = deck%seg%gap
      rewind(u)
      read(u, nml=segments, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'segments', k, var)
            if (len(record) == 0) cycle
            read(record, nml=segments, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'segments', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'segments', ios, msg, err)
      do j = 1, max_segments
         call check_word(err, 'segments', 'interface(' // itoa(j) // ')', interface(j))
      end do
      if (allocated(err)) return
      deck%seg%n = n
      deck%seg%length = length
      deck%seg%young = young
      deck%seg%density = density
      deck%seg%strength = strength
      do j = 1, max_segments
         deck%seg%interface(j) = lower(interface(j))
      end do
      deck%seg%velocity = velocity
      deck%seg%gap = gap
   end subroutine read_segments

   !> Read &ends.
   subroutine read_ends(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=path_len) :: top, bottom
      real(wp) :: base_gap
      integer :: ios
      character(len=256) :: msg
      character(len=256) :: msg2
      character(len=:), allocatable :: record, var
      integer :: k, ios2
      namelist /ends/ top, bottom, base_gap
      top = deck%ends%top
      bottom = deck%ends%bottom
      base_gap = deck%ends%base_gap
      rewind(u)
      read(u, nml=ends, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'ends', k, var)
            if (len(record) == 0) cycle
            read(record, nml=ends, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'ends', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'ends', ios, msg, err)
      call check_word(err, 'ends', 'top', top)
      call check_word(err, 'ends', 'bottom', bottom)
      if (allocated(err)) return
      deck%ends%top = lower(top)
      deck%ends%bottom = lower(bottom)
      deck%ends%base_gap = base_gap
   end subroutine read_ends

   !> Read &load.
   subroutine read_load(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=path_len) :: kind, face
      real(wp) :: p0, t_k, exponent, t_cut
      character(len=path_len) :: table
      integer :: ios
      character(len=256) :: msg
      character(len=256) :: msg2
      character(len=:), allocatable :: record, var
      integer :: k, ios2
      namelist /load/ kind, face, p0, t_k, exponent, t_cut, table
      kind = deck%load%kind
      face = deck%load%face
      p0 = deck%load%p0
      t_k = deck%load%t_k
      exponent = deck%load%exponent
      t_cut = deck%load%t_cut
      table = deck%load%table
      rewind(u)
      read(u, nml=load, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'load', k, var)
            if (len(record) == 0) cycle
            read(record, nml=load, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'load', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'load', ios, msg, err)
      call check_word(err, 'load', 'kind', kind)
      call check_word(err, 'load', 'face', face)
      if (allocated(err)) return
      deck%load%kind = lower(kind)
      deck%load%face = lower(face)
      deck%load%p0 = p0
      deck%load%t_k = t_k
      deck%load%exponent = exponent
      deck%load%t_cut = t_cut
      if (len_trim(table) == len(table)) then
         call make_error(err, '&load: table: the path is longer than ' // itoa(len(table) - 1) &
                         // ' characters')
         return
      end if
      deck%load%table = table
   end subroutine read_load

   !> Read &initial.
   subroutine read_initial(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=path_len) :: state
      integer :: ios
      character(len=256) :: msg
      character(len=256) :: msg2
      character(len=:), allocatable :: record, var
      integer :: k, ios2
      real(wp) :: strain_rate
      namelist /initial/ state, strain_rate
      state = deck%init%state
      strain_rate = deck%init%strain_rate
      rewind(u)
      read(u, nml=initial, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'initial', k, var)
            if (len(record) == 0) cycle
            read(record, nml=initial, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'initial', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'initial', ios, msg, err)
      call check_word(err, 'initial', 'state', state)
      if (allocated(err)) return
      deck%init%state = lower(state)
      deck%init%strain_rate = strain_rate
   end subroutine read_initial

   !> Read &strength_field.
   subroutine read_strength_field(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=path_len) :: kind
      real(wp) :: modulus, scale
      integer :: seed, ios
      character(len=256) :: msg
      character(len=256) :: msg2
      character(len=:), allocatable :: record, var
      integer :: k, ios2
      namelist /strength_field/ kind, modulus, scale, seed
      kind = deck%field%kind
      modulus = deck%field%modulus
      scale = deck%field%scale
      seed = deck%field%seed
      rewind(u)
      read(u, nml=strength_field, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'strength_field', k, var)
            if (len(record) == 0) cycle
            read(record, nml=strength_field, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'strength_field', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'strength_field', ios, msg, err)
      call check_word(err, 'strength_field', 'kind', kind)
      if (allocated(err)) return
      deck%field%kind = lower(kind)
      deck%field%modulus = modulus
      deck%field%scale = scale
      deck%field%seed = seed
   end subroutine read_strength_field

   !> Read &sweep (with --sweep only).
   subroutine read_sweep(u, deck, err)
      integer, intent(in) :: u             !! open unit of the deck
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=path_len) :: vary, distribution
      real(wp) :: values(max_sweep_values)
      integer :: realizations, seed, bins, ios, k, ios2
      character(len=256) :: msg, msg2
      character(len=:), allocatable :: record, var
      namelist /sweep/ realizations, seed, vary, values, distribution, bins
      realizations = deck%sweep%realizations
      seed = deck%sweep%seed
      vary = deck%sweep%vary
      values = deck%sweep%values
      distribution = deck%sweep%distribution
      bins = deck%sweep%bins
      rewind(u)
      read(u, nml=sweep, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         ! find the assignment that fails by reading them one at a time
         do k = 1, size(deck%scan%keys)
            record = assignment_text(deck%scan, 'sweep', k, var)
            if (len(record) == 0) cycle
            read(record, nml=sweep, iostat=ios2, iomsg=msg2)
            if (ios2 /= 0) then
               call blame(err, 'sweep', var, record, msg2)
               exit
            end if
         end do
      end if
      call read_status(deck, 'sweep', ios, msg, err)
      call check_word(err, 'sweep', 'vary', vary)
      call check_word(err, 'sweep', 'distribution', distribution)
      if (allocated(err)) return
      deck%sweep%realizations = realizations
      deck%sweep%seed = seed
      deck%sweep%vary = lower(vary)
      deck%sweep%values = values
      deck%sweep%distribution = lower(distribution)
      deck%sweep%bins = bins
      deck%sweep%n_values = 0
      do k = 1, max_sweep_values
         if (.not. is_set(values(k))) exit
         deck%sweep%n_values = k
      end do
   end subroutine read_sweep

   !> &sweep: what to vary and how often; every case's deck must itself be valid.
   subroutine validate_sweep(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(deck_t) :: trial
      integer :: k
      associate (sw => deck%sweep)
         if (sw%realizations < 0 .or. sw%realizations > max_realizations) then
            call make_error(err, '&sweep: realizations must be 0 .. ' // itoa(max_realizations) &
                            // ', got ' // itoa(sw%realizations))
            return
         end if
         if (sw%bins < 1 .or. sw%bins > 100000) then
            call make_error(err, '&sweep: bins must be 1 .. 100000, got ' // itoa(sw%bins))
            return
         end if
         call need_choice(err, 'sweep', 'distribution', sw%distribution, [character(len=8) :: &
                          'static', 'dynamic'])
         if (allocated(err)) return
         if (len_trim(deck%run%checkpoint) > 0) then
            call make_error(err, '&run: checkpoint = ''' // trim(deck%run%checkpoint) // &
                            ''' is not used by --sweep (a sweep''s cases write no files); ' // &
                            'remove it from the sweep deck')
            return
         end if
         if (len_trim(sw%vary) == 0) then
            if (sw%realizations == 0) then
               call make_error(err, '&sweep: nothing to sweep: give realizations > 0, or vary ' &
                               // 'and values')
               return
            end if
            if (sw%n_values > 0) then
               call make_error(err, '&sweep: values are given but vary is not')
               return
            end if
         else
            if (sw%n_values == 0) then
               call make_error(err, '&sweep: vary = ''' // trim(sw%vary) // ''' needs values')
               return
            end if
            do k = sw%n_values + 1, max_sweep_values
               if (is_set(sw%values(k))) then
                  call make_error(err, '&sweep: values(' // itoa(k) // ') is given but values(' &
                                  // itoa(sw%n_values + 1) // ') is not')
                  return
               end if
            end do
            do k = 1, sw%n_values
               call need_finite(err, 'sweep', 'values(' // itoa(k) // ')', sw%values(k))
            end do
            if (allocated(err)) return
         end if
         if (sw%realizations > 0 .and. deck%field%kind /= 'weibull') then
            call make_error(err, '&sweep: realizations need &strength_field kind = ''weibull'' ' &
                            // '(else every realization is the same run)')
            return
         end if
         ! every value must make a valid deck
         do k = 1, sw%n_values
            trial = deck
            call set_deck_value(trial, sw%vary, sw%values(k), err)
            if (allocated(err)) return
            call validate_deck(trial, err)
            if (allocated(err)) then
               err%message = '&sweep: values(' // itoa(k) // ') = ' // rtoa(sw%values(k)) // &
                             ' for ' // trim(sw%vary) // ': ' // err%message
               return
            end if
         end do
      end associate
   end subroutine validate_sweep

   !> Set the deck variable a sweep varies: name as in the deck, 'p0' or 'velocity(2)'.
   subroutine set_deck_value(deck, name, value, err)
      type(deck_t), intent(inout) :: deck   !! the deck
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(in) :: value        !! the value to set
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=:), allocatable :: base
      integer :: j, p, ios
      base = trim(name)
      j = 0
      p = index(base, '(')
      if (p > 0) then
         if (base(len(base):) /= ')') then
            call make_error(err, '&sweep: vary = ''' // base // ''' is not a deck variable')
            return
         end if
         read(base(p + 1:len(base) - 1), *, iostat=ios) j
         if (ios /= 0 .or. j < 1 .or. j > deck%seg%n) then
            call make_error(err, '&sweep: vary = ''' // base // ''': the index must be a ' // &
                            'segment 1 .. ' // itoa(deck%seg%n))
            return
         end if
         base = base(:p - 1)
      end if
      select case (base)
      case ('velocity', 'strength', 'young', 'density', 'length', 'gap')
         if (j == 0) then
            call make_error(err, '&sweep: vary = ''' // base // ''' needs a segment index, ' // &
                            'e.g. ''' // base // '(1)''')
            return
         end if
      case default
         if (j /= 0) then
            call make_error(err, '&sweep: vary = ''' // trim(name) // ''': ' // base // &
                            ' takes no index')
            return
         end if
      end select
      select case (base)
      case ('velocity')
         deck%seg%velocity(j) = value
      case ('strength')
         deck%seg%strength(j) = value
      case ('young')
         deck%seg%young(j) = value
      case ('density')
         deck%seg%density(j) = value
      case ('length')
         deck%seg%length(j) = value
      case ('gap')
         deck%seg%gap(j) = value
      case ('p0')
         deck%load%p0 = value
      case ('t_k')
         deck%load%t_k = value
      case ('t_cut')
         deck%load%t_cut = value
      case ('exponent')
         deck%load%exponent = value
      case ('gravity')
         deck%run%gravity = value
      case ('t_end')
         deck%run%t_end = value
      case ('eps_rel')
         deck%run%eps_rel = value
      case ('base_gap')
         deck%ends%base_gap = value
      case ('modulus')
         deck%field%modulus = value
      case ('scale')
         deck%field%scale = value
      case ('strain_rate')
         deck%init%strain_rate = value
      case default
         call make_error(err, '&sweep: vary = ''' // trim(name) // ''' is not a variable a ' &
            // 'sweep can vary (p0, t_k, t_cut, exponent, gravity, t_end, eps_rel, base_gap, ' &
            // 'modulus, scale, strain_rate, velocity(j), strength(j), young(j), density(j), ' &
            // 'length(j), gap(j))')
      end select
   end subroutine set_deck_value

   ! ---------------------------------------------------------------- validation

   !> Check every value; the first violation becomes the error. Fills derived counts.
   subroutine validate_deck(deck, err)
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      call validate_run(deck%run, err)
      if (.not. allocated(err)) call validate_segments(deck%seg, err)
      if (.not. allocated(err)) call validate_mesh(deck%mesh, deck%seg%n, err)
      if (.not. allocated(err)) call validate_ends(deck%ends, err)
      if (.not. allocated(err)) call validate_load(deck%load, deck%ends, err)
      if (.not. allocated(err)) call validate_initial(deck, err)
      if (.not. allocated(err)) call validate_field(deck, err)
   end subroutine validate_deck

   !> Error unless x is a finite number; name is the variable as the user writes it.
   subroutine need_finite(err, group, name, x)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(in) :: x
      if (allocated(err)) return
      if (.not. ieee_is_finite(x)) call make_error(err, '&' // group // ': ' // name // &
         ' must be a finite number, got ' // rtoa(x))
   end subroutine need_finite

   !> Error unless x was given, is finite and > 0 (or >= 0 when zero_ok).
   subroutine need_positive(err, group, name, x, zero_ok)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(in) :: x
      logical, intent(in), optional :: zero_ok
      logical :: zok
      if (allocated(err)) return
      zok = .false.
      if (present(zero_ok)) zok = zero_ok
      if (.not. is_set(x)) then
         call make_error(err, '&' // group // ': ' // name // ' is required')
         return
      end if
      call need_finite(err, group, name, x)
      if (allocated(err)) return
      if (zok) then
         if (x < 0.0_wp) call make_error(err, '&' // group // ': ' // name // &
            ' must be >= 0, got ' // rtoa(x))
      else
         if (x <= 0.0_wp) call make_error(err, '&' // group // ': ' // name // &
            ' must be > 0, got ' // rtoa(x))
      end if
   end subroutine need_positive

   !> Error unless value is one of choices.
   subroutine need_choice(err, group, name, value, choices)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: name   !! variable name
      character(len=*), intent(in) :: value   !! its value text
      character(len=*), intent(in) :: choices(:)
      character(len=:), allocatable :: list
      integer :: k
      if (allocated(err)) return
      if (any(choices == value)) return
      list = ''
      do k = 1, size(choices)
         if (k > 1) list = list // ' | '
         list = list // '''' // trim(choices(k)) // ''''
      end do
      call make_error(err, '&' // group // ': ' // name // ' must be ' // list // ', got ''' &
                      // trim(value) // '''')
   end subroutine need_choice


   !> Check &run's values.
   subroutine validate_run(run, err)
      type(run_cfg), intent(inout) :: run   !! &run values
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: k
      call need_positive(err, 'run', 't_end', run%t_end)
      call need_finite(err, 'run', 'gravity', run%gravity)
      call need_choice(err, 'run', 'timing', run%timing, [character(len=10) :: 'accelerate', &
                       'delay', 'min'])
      call need_choice(err, 'run', 'shift', run%shift, [character(len=8) :: 'above', 'fragment'])
      call need_choice(err, 'run', 'events', run%events, [character(len=10) :: 'admissible', &
                       'paper'])
      call need_choice(err, 'run', 'model', run%model, [character(len=9) :: 'half-mass', 'full-mass'])
      call need_finite(err, 'run', 'eps_rel', run%eps_rel)
      if (allocated(err)) return
      if (run%eps_rel < 0.0_wp .or. run%eps_rel > 1.0e-3_wp) then
         call make_error(err, '&run: eps_rel must be in [0, 1e-3], got ' // rtoa(run%eps_rel))
         return
      end if
      call need_finite(err, 'run', 'energy_guard', run%energy_guard)
      if (allocated(err)) return
      if (run%energy_guard < 0.0_wp) then
         call make_error(err, '&run: energy_guard must be >= 0 (0: off), got ' // rtoa(run%energy_guard))
         return
      end if
      if (run%history_every < 1) then
         call make_error(err, '&run: history_every must be >= 1, got ' // itoa(run%history_every))
         return
      end if
      if (run%field_every < 0) then
         call make_error(err, '&run: field_every must be >= 0 (0: no x-t fields), got ' // &
                         itoa(run%field_every))
         return
      end if
      if (run%checkpoint_every < 0) then
         call make_error(err, '&run: checkpoint_every must be >= 0 (0: at t_end only), got ' // &
                         itoa(run%checkpoint_every))
         return
      end if
      if (run%checkpoint_every > 0 .and. len_trim(run%checkpoint) == 0) then
         call make_error(err, '&run: checkpoint_every = ' // itoa(run%checkpoint_every) // &
                         ' needs checkpoint = ''file.h5'' (the restart file to write)')
         return
      end if
      if (run%field_every > 0 .and. .not. run%hdf5) then
         call make_error(err, '&run: field_every = ' // itoa(run%field_every) // &
                         ' needs hdf5 = .true. (the x-t fields are written to PREFIX.h5 only)')
         return
      end if
      run%n_profiles = 0
      do k = 1, max_profiles
         if (.not. is_set(run%profile_times(k))) exit
         run%n_profiles = k
      end do
      do k = 1, max_profiles
         associate (name => 'profile_times(' // itoa(k) // ')')
            if (k > run%n_profiles) then
               if (is_set(run%profile_times(k))) call make_error(err, '&run: ' // name // &
                  ' is given but profile_times(' // itoa(run%n_profiles + 1) // ') is not')
            else
               call need_positive(err, 'run', name, run%profile_times(k), zero_ok=.true.)
               if (allocated(err)) return
               if (run%profile_times(k) > run%t_end) call make_error(err, '&run: ' // name // &
                  ' = ' // rtoa(run%profile_times(k)) // ' is after t_end = ' // rtoa(run%t_end))
               if (k > 1 .and. .not. allocated(err)) call need_order(k)
            end if
         end associate
         if (allocated(err)) return
      end do
   contains
      !> profile_times must not decrease: check entry k against entry k - 1.
      subroutine need_order(k)
         integer, intent(in) :: k
         if (run%profile_times(k) < run%profile_times(k - 1)) call make_error(err, &
            '&run: profile_times(' // itoa(k) // ') must not be earlier than profile_times(' &
            // itoa(k - 1) // ')')
      end subroutine need_order
   end subroutine validate_run

   !> Check &mesh's values.
   subroutine validate_mesh(mesh, nseg, err)
      type(mesh_cfg), intent(in) :: mesh   !! &mesh values
      integer, intent(in) :: nseg
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      if (allocated(err)) return
      call need_finite(err, 'mesh', 'dt', mesh%dt)
      if (allocated(err)) return
      if (mesh%dt < 0.0_wp) then
         call make_error(err, '&mesh: dt must be >= 0 (0: set by cells), got ' // rtoa(mesh%dt))
      else if (mesh%cells < 0) then
         call make_error(err, '&mesh: cells must be >= 0, got ' // itoa(mesh%cells))
      else if (mesh%dt > 0.0_wp .and. mesh%cells > 0) then
         call make_error(err, '&mesh: cells: give either cells or dt, not both')
      else if (mesh%dt <= 0.0_wp .and. mesh%cells == 0) then
         call make_error(err, '&mesh: cells is required (cells in segment ref_segment), or give dt > 0')
      else if (mesh%ref_segment < 1 .or. mesh%ref_segment > nseg) then
         call make_error(err, '&mesh: ref_segment must be in 1..' // itoa(nseg) // ', got ' // &
                         itoa(mesh%ref_segment))
      end if
      call need_choice(err, 'mesh', 'fit', mesh%fit, [character(len=8) :: 'strict', 'stretch'])
   end subroutine validate_mesh

   !> Check &segments' values and fill the defaults of the segments given.
   subroutine validate_segments(seg, err)
      type(segments_cfg), intent(inout) :: seg
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: j
      character(len=:), allocatable :: sj
      if (allocated(err)) return
      if (seg%n < 1 .or. seg%n > max_segments) then
         call make_error(err, '&segments: n must be in 1..' // itoa(max_segments) // ', got ' &
                         // itoa(seg%n))
         return
      end if
      do j = 1, max_segments
         sj = '(' // itoa(j) // ')'
         if (j <= seg%n) then
            call need_positive(err, 'segments', 'length' // sj, seg%length(j))
            call need_positive(err, 'segments', 'young' // sj, seg%young(j))
            call need_positive(err, 'segments', 'density' // sj, seg%density(j))
            if (is_set(seg%strength(j))) then
               call need_finite(err, 'segments', 'strength' // sj, seg%strength(j))
            else
               seg%strength(j) = -1.0_wp
            end if
            if (is_set(seg%velocity(j))) then
               call need_finite(err, 'segments', 'velocity' // sj, seg%velocity(j))
            else
               seg%velocity(j) = 0.0_wp
            end if
            if (j < seg%n) then
               if (len_trim(seg%interface(j)) == 0) seg%interface(j) = 'bonded'
               call need_choice(err, 'segments', 'interface' // sj, seg%interface(j), &
                                [character(len=8) :: 'bonded', 'dry'])
               if (is_set(seg%gap(j))) then
                  call need_positive(err, 'segments', 'gap' // sj, seg%gap(j), zero_ok=.true.)
                  if (.not. allocated(err) .and. seg%gap(j) > 0.0_wp .and. &
                      seg%interface(j) /= 'dry') call make_error(err, '&segments: gap' // sj // &
                      ' > 0 needs interface' // sj // ' = ''dry''')
               else
                  seg%gap(j) = 0.0_wp
               end if
            else
               if (len_trim(seg%interface(j)) > 0) call make_error(err, '&segments: interface' // &
                  sj // ' is given but there are only ' // itoa(seg%n - 1) // ' interfaces (n = ' &
                  // itoa(seg%n) // ')')
               if (is_set(seg%gap(j)) .and. .not. allocated(err)) call make_error(err, &
                  '&segments: gap' // sj // ' is given but there are only ' // itoa(seg%n - 1) &
                  // ' interfaces (n = ' // itoa(seg%n) // ')')
            end if
         else
            call beyond_n('length', seg%length(j))
            call beyond_n('young', seg%young(j))
            call beyond_n('density', seg%density(j))
            call beyond_n('strength', seg%strength(j))
            call beyond_n('velocity', seg%velocity(j))
            if (j >= seg%n) call beyond_n('gap', seg%gap(j))
            if (len_trim(seg%interface(j)) > 0 .and. .not. allocated(err)) then
               call make_error(err, '&segments: interface' // sj // ' is given but n = ' // itoa(seg%n))
            end if
         end if
         if (allocated(err)) return
      end do
   contains
      !> A value given for a segment beyond n is an error.
      subroutine beyond_n(name, x)
         character(len=*), intent(in) :: name   !! variable name
         real(wp), intent(in) :: x
         if (allocated(err)) return
         if (is_set(x)) call make_error(err, '&segments: ' // name // sj // ' is given but n = ' &
                                        // itoa(seg%n) // ' (set n to the number of segments)')
      end subroutine beyond_n
   end subroutine validate_segments

   !> Check &ends' values.
   subroutine validate_ends(ends, err)
      type(ends_cfg), intent(in) :: ends
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      call need_choice(err, 'ends', 'top', ends%top, [character(len=8) :: 'free', 'fixed', 'transmit'])
      call need_choice(err, 'ends', 'bottom', ends%bottom, [character(len=8) :: 'free', 'fixed', &
                       'base', 'transmit'])
      call need_finite(err, 'ends', 'base_gap', ends%base_gap)
      if (allocated(err)) return
      if (ends%base_gap < 0.0_wp) then
         call make_error(err, '&ends: base_gap must be >= 0, got ' // rtoa(ends%base_gap))
      else if (ends%base_gap > 0.0_wp .and. ends%bottom /= 'base') then
         call make_error(err, '&ends: base_gap is given but bottom = ''' // trim(ends%bottom) // '''')
      end if
   end subroutine validate_ends

   !> Check &load's values against the ends.
   subroutine validate_load(load, ends, err)
      type(load_cfg), intent(in) :: load   !! &load values
      type(ends_cfg), intent(in) :: ends
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=name_len) :: face_end
      call need_choice(err, 'load', 'kind', load%kind, [character(len=11) :: 'none', 'power', &
                       'exponential', 'table'])
      call need_choice(err, 'load', 'face', load%face, [character(len=8) :: 'top', 'bottom'])
      if (allocated(err) .or. load%kind == 'none') return
      if (load%face == 'top') then
         face_end = ends%top
      else
         face_end = ends%bottom
      end if
      if (face_end /= 'free' .and. face_end /= 'transmit') then
         call make_error(err, '&load: face = ''' // trim(load%face) // ''' is a ''' // &
                         trim(face_end) // ''' end (&ends); a load acts on a free face ' // &
                         '(or enters as an incident wave through a transmitting one)')
         return
      end if
      if ((load%kind == 'power' .or. load%kind == 'exponential') .and. .not. is_set(load%p0)) then
         call make_error(err, '&load: p0 is required for kind = ''' // trim(load%kind) // '''')
         return
      end if
      if (load%kind == 'power') then
         call need_finite(err, 'load', 'p0', load%p0)
         call need_finite(err, 'load', 'exponent', load%exponent)
         if (allocated(err)) return
         if (load%exponent < 0.0_wp) then
            call make_error(err, '&load: exponent must be >= 0, got ' // rtoa(load%exponent))
            return
         end if
         if (is_set(load%t_k)) then
            call need_positive(err, 'load', 't_k', load%t_k)
         else if (load%exponent > 0.0_wp) then
            call make_error(err, '&load: t_k is required when exponent > 0')
         end if
         if (allocated(err)) return
         if (is_set(load%t_cut)) then
            call need_positive(err, 'load', 't_cut', load%t_cut)
            if (allocated(err)) return
            if (is_set(load%t_k)) then
               if (load%t_cut > load%t_k) call make_error(err, '&load: t_cut = ' // &
                  rtoa(load%t_cut) // ' is after t_k = ' // rtoa(load%t_k) // &
                  ' (p = p0 (1 - t/t_k)**exponent is defined up to t_k)')
            end if
         end if
      else if (load%kind == 'exponential') then
         call need_finite(err, 'load', 'p0', load%p0)
         if (.not. is_set(load%t_k) .and. .not. allocated(err)) then
            call make_error(err, '&load: t_k (decay time) is required for kind = ''exponential''')
            return
         end if
         call need_positive(err, 'load', 't_k', load%t_k)
         if (is_set(load%t_cut)) call need_positive(err, 'load', 't_cut', load%t_cut)
      else if (load%kind == 'table') then
         if (len_trim(load%table) == 0) call make_error(err, &
            '&load: table (file of two columns t p) is required for kind = ''table''')
      end if
   end subroutine validate_load

   !> &strength_field: a Weibull field needs its modulus and scale and a breakable segment
   !> (it replaces the strength of the segments whose strength is >= 0).
   subroutine validate_field(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      call need_choice(err, 'strength_field', 'kind', deck%field%kind, [character(len=8) :: &
                       'uniform', 'weibull'])
      if (allocated(err) .or. deck%field%kind /= 'weibull') return
      call need_positive(err, 'strength_field', 'modulus', deck%field%modulus)
      call need_positive(err, 'strength_field', 'scale', deck%field%scale)
      if (allocated(err)) return
      if (.not. any(deck%seg%strength(1:deck%seg%n) >= 0.0_wp)) call make_error(err, &
         '&strength_field: kind = ''weibull'' applies to segments with strength >= 0 ' // &
         '(&segments strength), and there is none')
   end subroutine validate_field

   !> Check &initial's values.
   subroutine validate_initial(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      if (deck%run%model == 'full-mass' .and. any(deck%seg%interface(1:deck%seg%n - 1) == 'dry')) then
         call make_error(err, '&segments: interface = ''dry'' needs &run model = ''half-mass'' ' &
                         // '(the full-mass model breaks springs, not nodes)')
         return
      end if
      call need_choice(err, 'initial', 'state', deck%init%state, [character(len=10) :: &
                       'unstressed', 'static'])
      call need_finite(err, 'initial', 'strain_rate', deck%init%strain_rate)
      if (allocated(err)) return
      if (abs(deck%init%strain_rate) > 0.0_wp .and. (deck%ends%top == 'fixed' .or. &
          deck%ends%bottom == 'fixed' .or. deck%ends%bottom == 'base')) then
         call make_error(err, '&initial: strain_rate = ' // rtoa(deck%init%strain_rate) // &
            ' needs ends that let the bar stretch about its centre of mass (&ends top, ' // &
            'bottom = ''free'' or ''transmit'')')
         return
      end if
      if (deck%init%state == 'static' .and. abs(deck%run%gravity) > 0.0_wp) then
         if (any(deck%seg%gap(1:deck%seg%n - 1) > 0.0_wp)) then
            call make_error(err, '&initial: state = ''static'' with a gap in &segments gap: ' &
                            // 'separated pieces are not in equilibrium')
            return
         end if
         if (deck%ends%bottom == 'base' .and. deck%ends%base_gap > 0.0_wp) then
            call make_error(err, '&initial: state = ''static'' with &ends base_gap > 0: a bar ' &
                            // 'above the base is not in equilibrium')
            return
         end if
         if (deck%ends%top == 'free' .and. deck%ends%bottom == 'free') call make_error(err, &
            '&initial: state = ''static'' with gravity needs a supported end (&ends top or ' &
            // 'bottom = ''fixed'', ''transmit'' or ''base''); both ends are free')
      end if
   end subroutine validate_initial

   ! ---------------------------------------------------------------------- echo

   !> Every deck value, defaults included, in echo order: group, name, value as namelist
   !> text, unit, and whether the deck gave it.
   subroutine deck_items(deck, items)
      type(deck_t), intent(in) :: deck     !! the deck
      type(echo_item_t), allocatable, intent(out) :: items(:)   !! the deck values as echoed
      integer :: j, n
      character(len=:), allocatable :: v
      allocate(items(0))
      call item('run', 'title', quote(deck%run%title), '')
      call item('run', 't_end', rtoa(deck%run%t_end), 's')
      call item('run', 'gravity', rtoa(deck%run%gravity), 'm/s^2')
      call item('run', 'timing', quote(deck%run%timing), '')
      call item('run', 'shift', quote(deck%run%shift), '')
      call item('run', 'events', quote(deck%run%events), '')
      call item('run', 'eps_rel', rtoa(deck%run%eps_rel), '-')
      call item('run', 'history_every', itoa(deck%run%history_every), 'steps')
      v = ''
      do j = 1, deck%run%n_profiles
         if (j > 1) v = v // ', '
         v = v // rtoa(deck%run%profile_times(j))
      end do
      call item('run', 'profile_times', v, 's')
      call item('run', 'hdf5', ltoa(deck%run%hdf5), '')
      call item('run', 'field_every', itoa(deck%run%field_every), 'steps (0: none)')
      call item('run', 'model', quote(deck%run%model), '')
      call item('run', 'energy_guard', rtoa(deck%run%energy_guard), '- (0: off)')
      call item('run', 'checkpoint', quote(deck%run%checkpoint), '(restart file; '''': none)')
      call item('run', 'checkpoint_every', itoa(deck%run%checkpoint_every), 'steps (0: at t_end)')

      call item('mesh', 'cells', itoa(deck%mesh%cells), '')
      call item('mesh', 'ref_segment', itoa(deck%mesh%ref_segment), '')
      call item('mesh', 'dt', rtoa(deck%mesh%dt), 's')
      call item('mesh', 'fit', quote(deck%mesh%fit), '')

      n = deck%seg%n
      call item('segments', 'n', itoa(n), '')
      call item('segments', 'length', rlist(deck%seg%length(1:n)), 'm')
      call item('segments', 'young', rlist(deck%seg%young(1:n)), 'Pa')
      call item('segments', 'density', rlist(deck%seg%density(1:n)), 'kg/m^3')
      call item('segments', 'strength', rlist(deck%seg%strength(1:n)), 'Pa (< 0: unbreakable)')
      v = ''
      do j = 1, n - 1
         if (j > 1) v = v // ', '
         v = v // quote(deck%seg%interface(j))
      end do
      call item('segments', 'interface', v, '')
      call item('segments', 'velocity', rlist(deck%seg%velocity(1:n)), 'm/s')
      call item('segments', 'gap', rlist(deck%seg%gap(1:n-1)), 'm')

      call item('ends', 'top', quote(deck%ends%top), '')
      call item('ends', 'bottom', quote(deck%ends%bottom), '')
      call item('ends', 'base_gap', rtoa(deck%ends%base_gap), 'm')

      call item('load', 'kind', quote(deck%load%kind), '')
      call item('load', 'face', quote(deck%load%face), '')
      call item('load', 'p0', opt(deck%load%p0), 'Pa')
      call item('load', 't_k', opt(deck%load%t_k), 's')
      call item('load', 'exponent', rtoa(deck%load%exponent), '-')
      call item('load', 't_cut', opt(deck%load%t_cut), 's')
      call item('load', 'table', quote(deck%load%table), '')

      call item('initial', 'state', quote(deck%init%state), '')
      call item('initial', 'strain_rate', rtoa(deck%init%strain_rate), '1/s')
      call item('strength_field', 'kind', quote(deck%field%kind), '')
      call item('strength_field', 'modulus', opt(deck%field%modulus), '-')
      call item('strength_field', 'scale', opt(deck%field%scale), 'Pa')
      call item('strength_field', 'seed', itoa(deck%field%seed), '')
      if (deck%is_sweep) then
         call item('sweep', 'realizations', itoa(deck%sweep%realizations), '')
         call item('sweep', 'seed', itoa(deck%sweep%seed), '')
         call item('sweep', 'vary', quote(deck%sweep%vary), '')
         if (deck%sweep%n_values > 0) then
            call item('sweep', 'values', rlist(deck%sweep%values(1:deck%sweep%n_values)), '')
         else
            call item('sweep', 'values', '(none)', '')
         end if
         call item('sweep', 'distribution', quote(deck%sweep%distribution), '')
         call item('sweep', 'bins', itoa(deck%sweep%bins), '')
      end if
   contains
      !> Append one echoed value.
      subroutine item(g, name, value, unit)
         character(len=*), intent(in) :: g   !! group name
         character(len=*), intent(in) :: name   !! variable name
         character(len=*), intent(in) :: value   !! its value text
         character(len=*), intent(in) :: unit
         items = [items, echo_item_t(g, name, value, unit, has_var(deck%scan, g, name))]
      end subroutine item
   end subroutine deck_items

   !> A mesh fault (spb_mesh) in the deck's terms: the one-line message of the bad input.
   function mesh_fault_message(fault, prob) result(msg)
      type(mesh_fault_t), intent(in) :: fault   !! why no mesh (fault_none: built)
      type(problem_t), intent(in) :: prob   !! the problem
      character(len=:), allocatable :: msg
      character(len=:), allocatable :: sj
      sj = itoa(fault%segment)
      select case (fault%kind)
      case (fault_cells)
         msg = '&mesh: cells = ' // itoa(prob%cells) // '; the limit is ' // itoa(max_cells)
      case (fault_segment_cells)
         msg = '&segments: length(' // sj // ') would need ' // rtoa(fault%cells) // &
               ' cells; the limit is ' // itoa(max_cells)
      case (fault_not_whole)
         msg = '&segments: length(' // sj // ') = ' // rtoa(prob%length(fault%segment)) // &
               ' m is ' // rtoa(fault%cells) // ' cells of dx = a dt = ' // rtoa(fault%dx) // &
               ' m, not a whole number (&mesh fit = ''strict''; use fit = ''stretch'' or ' // &
               'change the length)'
      case (fault_short_segment)
         msg = '&segments: length(' // sj // ') = ' // rtoa(prob%length(fault%segment)) // &
               ' m is less than half a cell of dx = a dt = ' // rtoa(fault%dx) // &
               ' m (&mesh fit = ''stretch'' would make it a whole cell; use a smaller dt or ' // &
               'more cells)'
      case (fault_mesh_cells)
         msg = '&mesh: cells: the mesh would have ' // rtoa(fault%cells) // &
               ' cells; the limit is ' // itoa(max_cells)
      case (fault_short_run)
         msg = '&run: t_end = ' // rtoa(prob%t_end) // ' s is shorter than half a step of ' // &
               'dt = ' // rtoa(fault%dt) // ' s'
      case (fault_long_run)
         msg = '&run: t_end = ' // rtoa(prob%t_end) // ' s needs ' // rtoa(fault%steps) // &
               ' steps of dt = ' // rtoa(fault%dt) // ' s; the limit is ' // itoa(max_steps)
      case default
         msg = ''
      end select
   end function mesh_fault_message

   !> The record of a validated deck for the outputs and checkpoints.
   function deck_record(deck) result(rec)
      type(deck_t), intent(in) :: deck     !! the deck
      type(deck_record_t) :: rec
      rec%path = trim(deck%path)
      rec%title = trim(deck%run%title)
      rec%table = trim(deck%load%table)
      call deck_items(deck, rec%items)
      rec%hdf5 = deck%run%hdf5
      rec%field_every = deck%run%field_every
      rec%t_end = deck%run%t_end
      allocate(rec%profile_times(deck%run%n_profiles))
      rec%profile_times(:) = deck%run%profile_times(1:deck%run%n_profiles)
   end function deck_record

   !> Write every deck value, defaults included, as namelist text behind prefix.
   subroutine write_echo(u, rec, prefix)
      integer, intent(in) :: u                    !! open formatted unit
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      character(len=*), intent(in) :: prefix      !! e.g. '# '
      character(len=40) :: lhs
      character(len=:), allocatable :: note
      integer :: k
      write(u, '(a)') prefix // 'deck: ' // rec%path // &
         '   (every value; "input" = given in the deck, "default" = not given)'
      associate (items => rec%items)
      do k = 1, size(items)
         if (k == 1) then
            write(u, '(a)') prefix // '&' // items(k)%group
         else if (items(k)%group /= items(k - 1)%group) then
            write(u, '(a)') prefix // '/'
            write(u, '(a)') prefix // '&' // items(k)%group
         end if
         lhs = '   ' // items(k)%name
         note = merge('input  ', 'default', items(k)%given)
         note = trim(note)
         if (len_trim(items(k)%unit) > 0) note = '[' // items(k)%unit // '] ' // note
         write(u, '(a)') prefix // lhs(1:18) // '= ' // pad(items(k)%value, 30) // ' ! ' // note
      end do
      if (size(items) > 0) write(u, '(a)') prefix // '/'
      end associate
   end subroutine write_echo

   !> s padded with blanks to at least n characters.
   pure function pad(s, n) result(r)
      character(len=*), intent(in) :: s
      integer, intent(in) :: n
      character(len=max(len(s), n)) :: r
      r = s
   end function pad

   !> s in single quotes (a quote inside doubled).
   pure function quote(s) result(r)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: r
      r = '''' // trim(s) // ''''
   end function quote

   !> A real as echoed: its value, or '(not set)' when not given.
   function opt(x) result(r)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: r
      if (is_set(x)) then
         r = rtoa(x)
      else
         r = '(not set)'
      end if
   end function opt

   !> A list of reals as echoed.
   function rlist(x) result(r)
      real(wp), intent(in) :: x(:)
      character(len=:), allocatable :: r
      integer :: k
      r = ''
      do k = 1, size(x)
         if (k > 1) r = r // ', '
         r = r // rtoa(x(k))
      end do
   end function rlist
end module spb_deck
