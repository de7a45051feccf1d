!> Every deck variable in one place: the get_param pattern of MOM6's MOM_file_parser.
!>
!> deck_params holds one call per variable: its group, its name, the component of deck_t
!> that holds it (whose initial value is its default), its unit and its meaning, and, for
!> a keyword, the values it accepts. A pass over that list does one job:
!>
!> * pass_read: read one assignment of the deck into its component (the one reader; a
!>   variable no call answers is unknown);
!> * pass_echo: every value as the outputs' headers echo it;
!> * pass_find, pass_set: the reals a sweep may vary, and setting one of them;
!> * pass_doc: every variable with its default, unit, choices and meaning.
!>
!> Adding a deck variable is a component in spb_deck_types and one call here; checks that
!> relate it to other variables go to spb_deck's validation.
module spb_deck_params
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
   use, intrinsic :: ieee_exceptions, only: ieee_underflow, ieee_get_flag, ieee_set_flag
   use spb_kinds, only: wp, path_len
   use spb_error, only: spb_error_t, make_error
   use spb_prescan, only: has_var
   use spb_strings, only: itoa, rtoa, ltoa, lower
   use spb_deck_types, only: deck_t, sweep_cfg, gauges_cfg, impactor_cfg, echo_item_t, is_set, timing_words, &
      shift_words, events_words, model_words, fit_words, top_words, bottom_words, &
      interface_words, kind_words, face_words, state_words, field_words, distribution_words, &
      header_words, side_words
   implicit none
   private
   public :: param_pass_t, deck_params, pass_read, pass_echo, pass_find, pass_set, pass_doc, &
      huge_real

   real(wp), parameter :: tiny_real = 1.0e-60_wp   !! smallest magnitude of a deck real (or 0)
   real(wp), parameter :: huge_real = 1.0e60_wp    !! largest magnitude of a deck real

   integer, parameter :: pass_read = 1   !! read the assignment pass%record
   integer, parameter :: pass_echo = 2   !! list every value as echoed
   integer, parameter :: pass_find = 3   !! is pass%name a real a sweep may vary?
   integer, parameter :: pass_set = 4    !! set that real (element pass%index) to pass%value
   integer, parameter :: pass_doc = 5    !! list every variable with its meaning

   !> One pass over the deck's variables: what it asks, and what it found.
   type :: param_pass_t
      integer :: mode = pass_echo                        !! pass_read .. pass_doc
      character(len=:), allocatable :: group             !! read: the assignment's group
      character(len=:), allocatable :: name              !! read, find, set: the variable
      character(len=:), allocatable :: record            !! read: '&group name... = value /'
      integer :: index = 0                               !! set: element (0: a scalar)
      real(wp) :: value = 0.0_wp                         !! set: the value; find: the value
                                                         !! the deck holds (element pass%index)
      logical :: found = .false.                         !! read, find, set: a call answered
      logical :: indexed = .false.                       !! find: the variable is an array
      character(len=:), allocatable :: sweepable         !! find: every name a sweep may vary
      type(spb_error_t), allocatable :: err              !! read: the assignment does not read
      type(echo_item_t), allocatable :: items(:)         !! echo, doc: one per variable
   end type param_pass_t

   !> One value of each type an assignment can give (read_value's namelist slots).
   type :: slots_t
      real(wp) :: real = 0.0_wp                               !! a real
      integer :: integer = 0                                  !! an integer
      logical :: logical = .false.                            !! a logical
      character(len=path_len) :: text = ''                    !! a text
      real(wp), allocatable :: reals(:)                       !! reals
      character(len=path_len), allocatable :: texts(:)        !! texts
   end type slots_t

contains

   !> The deck's variables, group by group, in the order the echo lists them: name, unit
   !> as echoed, meaning, and the component (r: real, i: integer, l: logical, t: text, ra:
   !> reals, ta: keywords) whose initial value in spb_deck_types is the default.
   subroutine deck_params(deck, pass)
      type(deck_t), intent(inout) :: deck        !! the deck (read, set: changed)
      type(param_pass_t), intent(inout) :: pass  !! what this pass does
      integer :: n
      n = deck%seg%n
      associate (p => pass, r => deck%run)
         call param(p, 'run', 'title', '', 'echoed in every output header', t=r%title)
         call param(p, 'run', 't_end', 's', 'end time (required)', r=r%t_end, sweep=.true.)
         call param(p, 'run', 'gravity', 'm/s^2', 'acceleration along +x (downwards)', &
                    r=r%gravity, sweep=.true.)
         call param(p, 'run', 'timing', '', 'collision timing rule', t=r%timing, &
                    choices=timing_words)
         call param(p, 'run', 'shift', '', 'collision shift policy', t=r%shift, &
                    choices=shift_words)
         call param(p, 'run', 'events', '', 'event rules: ''admissible'' never create wave ' &
                    // 'energy, ''paper'' are the paper''s own', t=r%events, choices=events_words)
         call param(p, 'run', 'eps_rel', '-', 'round-off guard of the fracture test and ' &
                    // 'the contact tolerance', r=r%eps_rel, sweep=.true.)
         call param(p, 'run', 'history_every', 'steps', 'steps between history rows', &
                    i=r%history_every)
         call param(p, 'run', 'profile_times', 's', 'profile snapshot times, increasing, ' &
                    // 'up to t_end', ra=r%profile_times, count=r%n_profiles)
         call param(p, 'run', 'hdf5', '', 'also write PREFIX.h5', l=r%hdf5)
         call param(p, 'run', 'field_every', 'steps (0: none)', 'steps between x-t field ' &
                    // 'rows in PREFIX.h5', i=r%field_every)
         call param(p, 'run', 'model', '', 'lumped-mass model (''full-mass'': the naive one, ' &
                    // 'for comparison)', t=r%model, choices=model_words)
         call param(p, 'run', 'energy_guard', '- (0: off)', 'stop (exit 3) when the wave ' &
                    // 'energy exceeds initial energy + work by this share', r=r%energy_guard)
         call param(p, 'run', 'checkpoint', '(restart file; '''': none)', 'restart file ' &
                    // 'written at t_end', t=r%checkpoint)
         call param(p, 'run', 'checkpoint_every', 'steps (0: at t_end)', 'also write the ' &
                    // 'checkpoint every so many steps', i=r%checkpoint_every)
         call param(p, 'run', 'warnings', '', 'warn on stderr of values outside the ranges ' &
                    // 'of engineering materials (a unit slip?)', l=r%warnings)
         call param(p, 'run', 'header', '', 'text outputs: ''names'': the first line names ' &
                    // 'the columns (numpy, pandas); ''comments'': every header line starts ' &
                    // 'with #', t=r%header, choices=header_words)
      end associate
      associate (p => pass, m => deck%mesh)
         call param(p, 'mesh', 'cells', '', 'cells in segment ref_segment (or dt)', i=m%cells)
         call param(p, 'mesh', 'ref_segment', '', 'the segment whose cells set dt', &
                    i=m%ref_segment)
         call param(p, 'mesh', 'dt', 's', 'time step when > 0 (or cells)', r=m%dt)
         call param(p, 'mesh', 'fit', '', 'segment lengths that are not whole cells: an ' &
                    // 'error, or stretched', t=m%fit, choices=fit_words)
      end associate
      associate (p => pass, s => deck%seg)
         call param(p, 'segments', 'n', '', 'number of segments, top to bottom', i=s%n)
         call param(p, 'segments', 'length', 'm', 'segment lengths (required)', ra=s%length, &
                    count=n, sweep=.true.)
         call param(p, 'segments', 'young', 'Pa', 'Young''s moduli (required)', ra=s%young, &
                    count=n, sweep=.true.)
         call param(p, 'segments', 'density', 'kg/m^3', 'densities (required)', &
                    ra=s%density, count=n, sweep=.true.)
         call param(p, 'segments', 'area', 'm^2', 'cross-section areas (default 1: outputs ' &
                    // 'per unit area)', ra=s%area, count=n, sweep=.true.)
         call param(p, 'segments', 'strength', 'Pa (< 0: unbreakable)', 'tensile ' &
                    // 'strengths (default -1)', ra=s%strength, count=n, sweep=.true.)
         call param(p, 'segments', 'fracture_energy', 'J/m^2', 'cohesive fracture ' &
                    // 'energies Gc (default 0: brittle)', ra=s%fracture_energy, count=n, &
                    sweep=.true.)
         call damage_params(deck, p)
         call param(p, 'segments', 'interface', '', 'interface j between segments j and ' &
                    // 'j+1 (default ''bonded'')', ta=s%interface, count=n - 1, &
                    choices=interface_words)
         call param(p, 'segments', 'velocity', 'm/s', 'initial rigid velocities (default 0)', &
                    ra=s%velocity, count=n, sweep=.true.)
         call param(p, 'segments', 'gap', 'm', 'initial gap at dry interface j (default 0)', &
                    ra=s%gap, count=n - 1, sweep=.true.)
      end associate
      associate (p => pass, e => deck%ends)
         call param(p, 'ends', 'top', '', 'the top end', t=e%top, choices=top_words)
         call param(p, 'ends', 'bottom', '', 'the bottom end', t=e%bottom, choices=bottom_words)
         call param(p, 'ends', 'base_gap', 'm', 'gap between the bottom and the rigid base', &
                    r=e%base_gap, sweep=.true.)
         ! echoed where the top is a base (a deck of before has none: its echo stays as it was)
         if (p%mode /= pass_echo .or. e%top == 'base' .or. abs(e%base_gap_top) > 0.0_wp) then
            call param(p, 'ends', 'base_gap_top', 'm', 'gap between the top and a rigid base ' &
                       // 'above it', r=e%base_gap_top, sweep=.true.)
         end if
      end associate
      associate (p => pass, l => deck%load)
         call param(p, 'load', 'kind', '', 'pressure history on the loaded face', t=l%kind, &
                    choices=kind_words)
         call param(p, 'load', 'face', '', 'the loaded face', t=l%face, choices=face_words)
         call param(p, 'load', 'p0', 'Pa', 'pressure scale (power, exponential)', r=l%p0, &
                    sweep=.true.)
         call param(p, 'load', 't_k', 's', 'duration (power) or decay time (exponential)', &
                    r=l%t_k, sweep=.true.)
         call param(p, 'load', 'exponent', '-', 'power-law exponent', r=l%exponent, &
                    sweep=.true.)
         call param(p, 'load', 't_cut', 's', 'p = 0 after t_cut', r=l%t_cut, sweep=.true.)
         call param(p, 'load', 'table', '', 'file of two columns t [s], p [Pa]', t=l%table)
      end associate
      associate (p => pass, i => deck%init)
         call param(p, 'initial', 'state', '', 'initial stresses', t=i%state, &
                    choices=state_words)
         call param(p, 'initial', 'strain_rate', '1/s', 'uniform stretching about the centre ' &
                    // 'of mass', r=i%strain_rate, sweep=.true.)
      end associate
      associate (p => pass, f => deck%field)
         call param(p, 'strength_field', 'kind', '', 'strength per cell', t=f%kind, &
                    choices=field_words)
         call param(p, 'strength_field', 'modulus', '-', 'Weibull modulus m', r=f%modulus, &
                    sweep=.true.)
         call param(p, 'strength_field', 'scale', 'Pa', 'Weibull scale', r=f%scale, &
                    sweep=.true.)
         call param(p, 'strength_field', 'seed', '', 'generator seed', i=f%seed)
      end associate
      if (deck%is_sweep .or. pass%mode == pass_doc) call sweep_params(deck%sweep, pass)
      ! echoed only by a deck that has gauges: the outputs of every other deck stay as they were
      if (pass%mode /= pass_echo .or. deck%gauges%n > 0) call gauge_params(deck%gauges, pass)
      ! the same for a striking mass
      if (pass%mode /= pass_echo .or. deck%impactor%on) call impactor_params(deck%impactor, pass)
   end subroutine deck_params

   !> &segments damage_integral and damage_exponent (time-dependent fracture): listed by
   !> every pass but the echo, and echoed by a deck that gives one of them or a K > 0 (a
   !> deck of before has none: its echo stays as it was).
   subroutine damage_params(deck, p)
      type(deck_t), intent(inout) :: deck     !! the deck
      type(param_pass_t), intent(inout) :: p  !! what this pass does
      logical :: show
      integer :: n
      n = deck%seg%n
      show = p%mode /= pass_echo
      if (.not. show) show = has_var(deck%scan, 'segments', 'damage_integral') .or. &
                             has_var(deck%scan, 'segments', 'damage_exponent')
      if (.not. show .and. n >= 1 .and. n <= size(deck%seg%damage_integral)) then
         show = any(deck%seg%damage_integral(1:n) > 0.0_wp)
      end if
      if (.not. show) return
      call param(p, 'segments', 'damage_integral', 'Pa^lambda s', 'Tuler-Butcher damage ' &
                 // 'integral K: a section breaks when the integral of (S - R)^lambda dt ' &
                 // 'over its tension S beyond its strength R reaches K (default 0: at once)', &
                 ra=deck%seg%damage_integral, count=n, sweep=.true.)
      call param(p, 'segments', 'damage_exponent', '-', 'Tuler-Butcher exponent lambda ' &
                 // '(default 2)', ra=deck%seg%damage_exponent, count=n, sweep=.true.)
   end subroutine damage_params

   !> &impactor's variables (optional group: a striking mass, doc/impactor.md).
   subroutine impactor_params(m, p)
      type(impactor_cfg), intent(inout) :: m  !! &impactor values
      type(param_pass_t), intent(inout) :: p  !! what this pass does
      call param(p, 'impactor', 'face', '', 'the end of the bar the mass strikes', t=m%face, &
                 choices=face_words)
      ! a sweep varies them as impactor_mass, ... (&segments has a velocity and a gap too)
      call param(p, 'impactor', 'mass', 'kg', 'the striking mass (per m^2 when every area ' &
                 // 'is 1; required)', r=m%mass, sweep=.true., sweep_as='impactor_mass')
      call param(p, 'impactor', 'velocity', 'm/s', 'its velocity along +x (down) at t = 0', &
                 r=m%velocity, sweep=.true., sweep_as='impactor_velocity')
      call param(p, 'impactor', 'gap', 'm', 'distance between the mass and the face at t = 0', &
                 r=m%gap, sweep=.true., sweep_as='impactor_gap')
      call param(p, 'impactor', 'cushion', 'N/m', 'stiffness of a linear spring between the ' &
                 // 'mass and the face (per m^2 when every area is 1; 0: rigid contact)', &
                 r=m%cushion, sweep=.true., sweep_as='impactor_cushion')
   end subroutine impactor_params

   !> &gauges' variables (optional group: PREFIX.gau).
   subroutine gauge_params(g, p)
      type(gauges_cfg), intent(inout) :: g    !! &gauges values
      type(param_pass_t), intent(inout) :: p  !! what this pass does
      call param(p, 'gauges', 'x', 'm', 'reference positions of the gauges in [0, length], ' &
                 // 'up to 100', ra=g%x, count=g%n, empty='(none)')
      call param(p, 'gauges', 'every', 'steps', 'steps between rows of PREFIX.gau (not ' &
                 // 'given: &run history_every)', i=g%every)
      call param(p, 'gauges', 'side', '', 'at a node that splits, the side whose face a ' &
                 // 'gauge reads: one value for all gauges or one per gauge (default ' &
                 // '''above'')', ta=g%side, count=g%n_side, choices=side_words)
   end subroutine gauge_params

   !> &sweep's variables (a sweep deck only: read with --sweep).
   subroutine sweep_params(sw, p)
      type(sweep_cfg), intent(inout) :: sw    !! &sweep values
      type(param_pass_t), intent(inout) :: p  !! what this pass does
      call param(p, 'sweep', 'realizations', '', 'strength-field realizations per value ' &
                 // '(0: the deck''s own field)', i=sw%realizations)
      call param(p, 'sweep', 'seed', '', 'realization i draws with realization_seed(seed, i)', &
                 i=sw%seed)
      call param(p, 'sweep', 'vary', '', 'the deck variable to vary, e.g. ''p0'', ' &
                 // '''velocity(1)''', t=sw%vary)
      call param(p, 'sweep', 'values', '', 'its values', ra=sw%values, count=sw%n_values, &
                 empty='(none)')
      call param(p, 'sweep', 'distribution', '', 'cases over MPI ranks', t=sw%distribution, &
                 choices=distribution_words)
      call param(p, 'sweep', 'bins', '', 'fragment-length histogram bins', i=sw%bins)
      ! echoed only by an ensemble's deck: the tables of every other sweep stay as they were
      if (p%mode /= pass_echo .or. len_trim(sw%perturb) > 0 .or. sw%n_ensemble > 0) then
         call param(p, 'sweep', 'perturb', '', 'the deck variable realization i multiplies ' &
                    // 'by 1 + spread u_i, u_i uniform in [-1, 1] (a name vary accepts)', &
                    t=sw%perturb)
         call param(p, 'sweep', 'spread', '-', 'the perturbation''s relative half-width, ' &
                    // 'in [0, 1)', r=sw%spread)
         call param(p, 'sweep', 'ensemble_columns', '', 'history columns whose mean, std, ' &
                    // 'min, max over the realizations PREFIX.ens holds, up to 16', &
                    ta=sw%ensemble_columns, count=sw%n_ensemble, empty='(none)')
         call param(p, 'sweep', 'horizon_tol', '-', 'predictability horizon: the std of ' &
                    // 'the 1 ms window means above this share of their largest |mean|', &
                    r=sw%horizon_tol)
      end if
   end subroutine sweep_params

   !> One deck variable: the one call that reads, echoes, sets (a sweep) and documents it.
   !> Exactly one of r, i, l, t, ra, ta is given: its component of deck_t.
   subroutine param(p, group, name, unit, doc, r, i, l, t, ra, ta, count, choices, sweep, &
                    empty, sweep_as)
      type(param_pass_t), intent(inout) :: p   !! what this pass does
      character(len=*), intent(in) :: group    !! group name
      character(len=*), intent(in) :: name     !! variable name
      character(len=*), intent(in) :: unit     !! unit as echoed
      character(len=*), intent(in) :: doc      !! what it means
      real(wp), intent(inout), optional :: r   !! a real
      integer, intent(inout), optional :: i    !! an integer
      logical, intent(inout), optional :: l    !! a logical
      ! allow(assumed-size-character-intent)
      character(len=*), intent(inout), optional :: t      !! a text (name_len or path_len)
      real(wp), intent(inout), optional :: ra(:)          !! reals
      ! allow(assumed-size-character-intent)
      character(len=*), intent(inout), optional :: ta(:)  !! keywords
      integer, intent(in), optional :: count   !! elements echoed: ra or ta(1:count)
      character(len=*), intent(in), optional :: choices(:)   !! a keyword's values
      logical, intent(in), optional :: sweep   !! a sweep may vary it (r, or ra by element)
      character(len=*), intent(in), optional :: empty   !! echoed for count = 0 (else '')
      character(len=*), intent(in), optional :: sweep_as   !! the name a sweep varies it by
                                                            !! (default name)
      logical :: sweepable
      select case (p%mode)
      case (pass_read)
         if (p%group /= group .or. p%name /= name) return
         p%found = .true.
         call read_value(p, present(choices), r, i, l, t, ra, ta)
      case (pass_find, pass_set)
         sweepable = .false.
         if (present(sweep)) sweepable = sweep
         if (.not. sweepable) return
         if (present(r) .and. present(sweep_as)) then
            call sweep_target(p, sweep_as, .false., r)
         else if (present(r)) then
            call sweep_target(p, name, .false., r)
         end if
         if (present(ra)) call sweep_target(p, name, .true., ra(max(1, p%index)))
      case default
         call add_item(p, group, name, echo_text(r, i, l, t, ra, ta, count, empty), unit, &
                       doc // choice_list(choices))
         call type_item(p%items(size(p%items)), r, i, l, ra, ta, count)
      end select
   end subroutine param

   !> A text as read (the slot holds path_len characters), before it goes into its
   !> component of len characters: a keyword longer than any keyword, or a text that fills
   !> the slot, is an error (a cut value could look like a valid one).
   subroutine check_length(p, text, len, keyword, k)
      type(param_pass_t), intent(inout) :: p   !! the read pass
      character(len=*), intent(in) :: text     !! as read
      integer, intent(in) :: len               !! characters its component holds
      logical, intent(in) :: keyword           !! a keyword (else free text)
      integer, intent(in), optional :: k       !! the element of an array
      character(len=:), allocatable :: var
      if (allocated(p%err)) return
      var = p%name
      if (present(k)) var = var // '(' // itoa(k) // ')'
      if (keyword .and. len_trim(text) > len) then
         call make_error(p%err, '&' // p%group // ': ' // var // ': ''' // text(1:20) // &
                         '...'' is longer than any choice (' // itoa(len) // ' characters at most)')
      else if (len_trim(text) >= len) then
         call make_error(p%err, '&' // p%group // ': ' // var // ': longer than ' // &
                         itoa(len - 1) // ' characters')
      end if
   end subroutine check_length

   !> A value as the echo shows it: a real or '(not set)', an integer, a logical, a quoted
   !> text, or the first count elements of an array separated by ', ' (empty when none).
   function echo_text(r, i, l, t, ra, ta, count, empty) result(text)
      real(wp), intent(in), optional :: r      !! a real
      integer, intent(in), optional :: i       !! an integer
      logical, intent(in), optional :: l       !! a logical
      character(len=*), intent(in), optional :: t       !! a text
      real(wp), intent(in), optional :: ra(:)           !! reals
      character(len=*), intent(in), optional :: ta(:)   !! keywords
      integer, intent(in), optional :: count   !! elements shown
      character(len=*), intent(in), optional :: empty   !! shown when count = 0
      character(len=:), allocatable :: text
      integer :: k
      text = ''
      if (present(r)) text = opt(r)
      if (present(i)) text = itoa(i)
      if (present(l)) text = ltoa(l)
      if (present(t)) text = quote(t)
      if (.not. present(count)) return
      do k = 1, count
         if (k > 1) text = text // ', '
         if (present(ra)) text = text // opt(ra(k))
         if (present(ta)) text = text // quote(ta(k))
      end do
      if (count < 1 .and. present(empty)) text = empty
   end function echo_text

   ! ------------------------------------------------------------------- the reader

   !> The one namelist read of the deck: one assignment, its value read by gfortran's
   !> namelist rules (subscripts, repeat counts, null values, quotes as in any namelist)
   !> into the slot of its type, which starts from the current value (the one of r .. ta
   !> given). A value that does not read becomes p%err and leaves the variable as it was.
   subroutine read_value(p, keyword, r, i, l, t, ra, ta)
      type(param_pass_t), intent(inout) :: p   !! the read pass (its record)
      logical, intent(in) :: keyword           !! t, ta: keywords (kept lower-case)
      real(wp), intent(inout), optional :: r   !! a real
      integer, intent(inout), optional :: i    !! an integer
      logical, intent(inout), optional :: l    !! a logical
      ! allow(assumed-size-character-intent)
      character(len=*), intent(inout), optional :: t      !! a text
      real(wp), intent(inout), optional :: ra(:)          !! reals
      ! allow(assumed-size-character-intent)
      character(len=*), intent(inout), optional :: ta(:)  !! keywords
      type(slots_t) :: v
      character(len=:), allocatable :: record
      integer :: ios, k
      logical :: underflow
      if (present(ra)) then
         allocate(v%reals, source=ra)
      else
         allocate(v%reals(0))
      end if
      if (present(ta)) then
         allocate(v%texts(size(ta)))
         v%texts(:) = ta
      else
         allocate(v%texts(0))
      end if
      if (present(r)) v%real = r
      if (present(i)) v%integer = i
      if (present(l)) v%logical = l
      if (present(t)) v%text = t
      record = slot_record(p%record, p%group, p%name, &
                           slot_name(present(r), present(i), present(l), present(t), present(ra)))
      call read_slots(record, v, ios, underflow)
      if (ios /= 0) then
         call blame(p%err, p%group, p%name, p%record)
         return
      end if

      if (present(t)) call check_length(p, v%text, len(t), keyword)
      do k = 1, size(v%texts)
         call check_length(p, v%texts(k), len(ta), keyword, k)
      end do
      if (present(r) .or. present(ra)) call check_reals(p, record, v%real, v%reals, present(ra))
      if (allocated(p%err)) return
      if (underflow .and. (present(r) .or. present(ra))) then
         ! a denormal is refused above by its value; 1e-400 reads as an exact 0
         call make_error(p%err, '&' // p%group // ': ' // p%name // ': a value below ' // &
                         '1e-308 in magnitude reads as 0, which is not what was written: a ' // &
                         'deck real is 0 or between 1e-60 and 1e60 in magnitude')
         return
      end if
      if (keyword) v%text = lower(v%text)
      do k = 1, size(v%texts)
         v%texts(k) = lower(v%texts(k))
      end do
      if (present(r)) r = v%real
      if (present(i)) i = v%integer
      if (present(l)) l = v%logical
      if (present(t)) t = v%text
      if (present(ra)) ra(:) = v%reals
      if (present(ta)) ta(:) = v%texts
   end subroutine read_value

   !> The reals an assignment gave (read: as read_value read them): each must be finite and
   !> 0 or between tiny_real and huge_real in magnitude, so that no derived quantity (a
   !> wave speed, a cell count, an energy: products of up to five deck values) overflows or
   !> underflows, and no value is taken for the "not given" marker. Which elements the
   !> assignment gave is found by reading it again into a slot filled otherwise: an element
   !> the record sets reads the same bits both times.
   subroutine check_reals(p, record, r, ra, array)
      type(param_pass_t), intent(inout) :: p   !! the read pass
      character(len=*), intent(in) :: record   !! the assignment, renamed to its slot
      real(wp), intent(in) :: r                !! a scalar as read
      real(wp), intent(in) :: ra(:)            !! an array as read
      logical, intent(in) :: array             !! ra is the variable (else r)
      type(slots_t) :: v
      integer :: ios, k
      v%real = other_than(r)
      allocate(v%reals(size(ra)), v%texts(0))
      do k = 1, size(ra)
         v%reals(k) = other_than(ra(k))
      end do
      call read_slots(record, v, ios)
      if (ios /= 0) return   ! read once already: cannot happen
      if (.not. array) then
         if (same_bits(r, v%real)) call check_real(p, p%name, r)
         return
      end if
      do k = 1, size(ra)
         if (same_bits(ra(k), v%reals(k))) call check_real(p, p%name // '(' // itoa(k) &
                                                              // ')', ra(k))
      end do
   end subroutine check_reals

   !> The namelist slots of one assignment, one of each type; the record (renamed by
   !> slot_record) reads into the one of its variable's type.
   subroutine read_slots(record, v, ios, underflow)
      character(len=*), intent(in) :: record   !! '&spb_value slot... = value /'
      type(slots_t), intent(inout) :: v        !! the slots: current values in, as read out
      integer, intent(out) :: ios              !! the read's status
      logical, intent(out), optional :: underflow   !! a number read underflowed (1e-400 -> 0)
      logical :: flag
      real(wp) :: spb_real
      integer :: spb_integer
      logical :: spb_logical
      character(len=path_len) :: spb_text
      real(wp), allocatable :: spb_reals(:)
      character(len=path_len), allocatable :: spb_texts(:)
      namelist /spb_value/ spb_real, spb_integer, spb_logical, spb_text, spb_reals, spb_texts
      spb_real = v%real
      spb_integer = v%integer
      spb_logical = v%logical
      spb_text = v%text
      allocate(spb_reals, source=v%reals)
      allocate(spb_texts, source=v%texts)
      call ieee_set_flag(ieee_underflow, .false.)
      read(record, nml=spb_value, iostat=ios)
      call ieee_get_flag(ieee_underflow, flag)
      call ieee_set_flag(ieee_underflow, .false.)
      if (present(underflow)) underflow = flag
      if (ios /= 0) return   ! the slots keep what they had
      v%real = spb_real
      v%integer = spb_integer
      v%logical = spb_logical
      v%text = spb_text
      v%reals = spb_reals
      v%texts = spb_texts
   end subroutine read_slots

   !> One real a deck gave: finite, and 0 or tiny_real <= |x| <= huge_real.
   subroutine check_real(p, name, x)
      type(param_pass_t), intent(inout) :: p   !! the read pass
      character(len=*), intent(in) :: name     !! the variable (with its element)
      real(wp), intent(in) :: x                !! the value given
      if (allocated(p%err)) return
      if (.not. ieee_is_finite(x)) then
         call make_error(p%err, '&' // p%group // ': ' // name // ' must be a finite number, ' &
                         // 'got ' // rtoa(x))
      else if ((abs(x) > 0.0_wp .and. abs(x) < tiny_real) .or. abs(x) > huge_real) then
         call make_error(p%err, '&' // p%group // ': ' // name // ' = ' // rtoa(x) // &
                         ' is out of range: a deck real is 0 or between 1e-60 and 1e60 in ' // &
                         'magnitude')
      end if
   end subroutine check_real

   !> A real whose bits differ from x's.
   pure real(wp) function other_than(x)
      real(wp), intent(in) :: x   !! a value
      other_than = 1.0_wp
      if (same_bits(x, 1.0_wp)) other_than = 2.0_wp
   end function other_than

   !> Whether a and b have the same bits (NaN included).
   pure logical function same_bits(a, b)
      real(wp), intent(in) :: a   !! a value
      real(wp), intent(in) :: b   !! another
      same_bits = transfer(a, 0_int64) == transfer(b, 0_int64)
   end function same_bits

   !> The namelist slot of read_value for a variable of the type given (else keywords).
   pure function slot_name(r, i, l, t, ra) result(slot)
      logical, intent(in) :: r    !! a real
      logical, intent(in) :: i    !! an integer
      logical, intent(in) :: l    !! a logical
      logical, intent(in) :: t    !! a text
      logical, intent(in) :: ra   !! reals
      character(len=:), allocatable :: slot
      slot = 'spb_texts'
      if (r) slot = 'spb_real'
      if (i) slot = 'spb_integer'
      if (l) slot = 'spb_logical'
      if (t) slot = 'spb_text'
      if (ra) slot = 'spb_reals'
   end function slot_name

   !> The assignment record with its variable renamed to the slot of its type:
   !> '&group Name(2) = 5 /' becomes '&spb_value spb_reals(2) = 5 /'.
   function slot_record(record, group, name, slot) result(text)
      character(len=*), intent(in) :: record   !! '&group name... = value /'
      character(len=*), intent(in) :: group    !! group name
      character(len=*), intent(in) :: name     !! the variable as the deck names it
      character(len=*), intent(in) :: slot     !! the slot's name
      character(len=:), allocatable :: text
      text = '&spb_value ' // trim(slot) // record(len(group) + 3 + len(name):)
   end function slot_record

   !> The error for an assignment (record, '&group var = value /') whose value does not
   !> read: the value as written, cut to 40 characters.
   subroutine blame(err, group, var, record)
      type(spb_error_t), allocatable, intent(inout) :: err   !! receives the error
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: var     !! variable name
      character(len=*), intent(in) :: record  !! the assignment
      character(len=:), allocatable :: value
      integer :: k
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


   ! ------------------------------------------------------------- sweeps, echo, doc

   !> Find and set pass over a real a sweep may vary (an array: by element): a find pass
   !> collects every such name and tells whether pass%name is one; a set pass sets it.
   subroutine sweep_target(p, name, indexed, x)
      type(param_pass_t), intent(inout) :: p   !! a find or set pass
      character(len=*), intent(in) :: name     !! variable name
      logical, intent(in) :: indexed           !! an array (swept by element)
      real(wp), intent(inout) :: x             !! the real (the element pass%index)
      if (p%mode == pass_find) then
         if (.not. allocated(p%sweepable)) p%sweepable = ''
         if (len(p%sweepable) > 0) p%sweepable = p%sweepable // ', '
         p%sweepable = p%sweepable // name // trim(merge('(j)', '   ', indexed))
      end if
      if (p%name /= name) return
      p%found = .true.
      p%indexed = indexed
      if (p%mode == pass_find) p%value = x
      if (p%mode == pass_set) x = p%value
   end subroutine sweep_target

   !> Append one variable to an echo or doc pass.
   subroutine add_item(p, group, name, value, unit, doc)
      type(param_pass_t), intent(inout) :: p   !! an echo or doc pass
      character(len=*), intent(in) :: group    !! group name
      character(len=*), intent(in) :: name     !! variable name
      character(len=*), intent(in) :: value    !! its value as echoed
      character(len=*), intent(in) :: unit     !! unit as echoed
      character(len=*), intent(in) :: doc      !! what it means
      type(echo_item_t) :: item
      if (.not. allocated(p%items)) allocate(p%items(0))
      item%group = group
      item%name = name
      item%value = value
      item%unit = unit
      if (p%mode == pass_doc) item%doc = doc
      p%items = [p%items, item]
   end subroutine add_item

   !> The value of an echoed variable with its type (the one of r, i, l, ra, ta given;
   !> none: a text, whose value is the echo's): a real not set has no value (reals empty),
   !> an element not set of an array is NaN; an array variable is a list of its first
   !> count elements.
   subroutine type_item(item, r, i, l, ra, ta, count)
      type(echo_item_t), intent(inout) :: item   !! the item just added
      real(wp), intent(in), optional :: r      !! a real
      integer, intent(in), optional :: i       !! an integer
      logical, intent(in), optional :: l       !! a logical
      real(wp), intent(in), optional :: ra(:)           !! reals
      character(len=*), intent(in), optional :: ta(:)   !! keywords
      integer, intent(in), optional :: count   !! elements of ra or ta
      integer :: k, n
      n = 0
      if (present(count)) n = max(0, count)
      item%list = present(ra) .or. present(ta)
      if (present(r)) then
         item%type = 'r'
         allocate(item%reals(merge(1, 0, is_set(r))))
         if (is_set(r)) item%reals(1) = r
      else if (present(ra)) then
         item%type = 'r'
         allocate(item%reals(n))
         do k = 1, size(item%reals)
            item%reals(k) = not_set_nan(ra(k))
         end do
      else if (present(i)) then
         item%type = 'i'
         item%ints = [i]
      else if (present(l)) then
         item%type = 'l'
         item%flags = [l]
      else if (present(ta)) then
         allocate(item%words(n))
         do k = 1, size(item%words)
            item%words(k) = ta(k)
         end do
      end if
   end subroutine type_item

   !> x, or NaN for a real the deck did not set.
   function not_set_nan(x) result(y)
      real(wp), intent(in) :: x   !! a deck real
      real(wp) :: y
      if (is_set(x)) then
         y = x
      else
         y = ieee_value(y, ieee_quiet_nan)
      end if
   end function not_set_nan

   !> ' (''a'' | ''b'')' for a keyword's documentation ('' without choices).
   function choice_list(choices) result(s)
      character(len=*), intent(in), optional :: choices(:)   !! a keyword's values
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      if (.not. present(choices)) return
      do k = 1, size(choices)
         if (k == 1) then
            s = s // ' ('
         else
            s = s // ' | '
         end if
         s = s // '''' // trim(choices(k)) // ''''
      end do
      s = s // ')'
   end function choice_list

   !> s in single quotes.
   pure function quote(s) result(r)
      character(len=*), intent(in) :: s   !! a string value
      character(len=:), allocatable :: r
      r = '''' // trim(s) // ''''
   end function quote

   !> A real as echoed: its value, or '(not set)' when not given.
   function opt(x) result(r)
      real(wp), intent(in) :: x   !! a deck real
      character(len=:), allocatable :: r
      if (is_set(x)) then
         r = rtoa(x)
      else
         r = '(not set)'
      end if
   end function opt
end module spb_deck_params
