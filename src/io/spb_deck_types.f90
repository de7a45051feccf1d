!> The deck's types (doc/deck.md): one component per deck variable, with its default;
!> the keyword lists each keyword variable accepts; the record the outputs keep of a deck.
!>
!> What a variable means, its unit and how it is echoed are said once, in its call in
!> spb_deck_params; its checks against other variables in spb_deck.
module spb_deck_types
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp, max_segments, max_profiles, name_len, path_len, max_sweep_values, &
      max_gauges, max_ensemble_columns
   use spb_prescan, only: deck_scan_t
   implicit none
   private
   public :: deck_t, run_cfg, mesh_cfg, segments_cfg, ends_cfg, load_cfg, initial_cfg, &
      strength_field_cfg, sweep_cfg, gauges_cfg, impactor_cfg, deck_record_t, echo_item_t, known_groups, unset, is_set
   public :: timing_words, shift_words, events_words, model_words, fit_words, top_words, &
      bottom_words, interface_words, kind_words, face_words, state_words, field_words, &
      distribution_words, header_words, side_words

   real(wp), parameter :: unset = -huge(1.0_wp)   !! marks a real the deck did not give


   ! the values each keyword variable accepts (checked in spb_deck, documented with the
   ! variable in spb_deck_params, turned into codes by problem_from_deck in this order)
   character(len=*), parameter :: timing_words(4) = [character(len=10) :: 'accelerate', &
      'delay', 'min', 'within']
   character(len=*), parameter :: shift_words(3) = [character(len=8) :: 'above', 'fragment', 'face']
   character(len=*), parameter :: events_words(2) = [character(len=10) :: 'admissible', 'paper']
   character(len=*), parameter :: model_words(2) = [character(len=9) :: 'half-mass', 'full-mass']
   character(len=*), parameter :: fit_words(2) = [character(len=7) :: 'strict', 'stretch']
   character(len=*), parameter :: top_words(5) = [character(len=8) :: 'free', 'fixed', 'transmit', &
      'velocity', 'base']
   character(len=*), parameter :: bottom_words(5) = [character(len=8) :: 'free', 'fixed', &
      'base', 'transmit', 'velocity']
   character(len=*), parameter :: interface_words(2) = [character(len=6) :: 'bonded', 'dry']
   character(len=*), parameter :: kind_words(4) = [character(len=11) :: 'none', 'power', &
      'exponential', 'table']
   character(len=*), parameter :: face_words(2) = [character(len=6) :: 'top', 'bottom']
   character(len=*), parameter :: state_words(2) = [character(len=10) :: 'unstressed', 'static']
   character(len=*), parameter :: field_words(2) = [character(len=7) :: 'uniform', 'weibull']
   character(len=*), parameter :: distribution_words(2) = [character(len=7) :: 'static', &
      'dynamic']
   character(len=*), parameter :: header_words(2) = [character(len=8) :: 'names', 'comments']
   character(len=*), parameter :: side_words(2) = [character(len=5) :: 'above', 'below']

   character(len=16), parameter :: known_groups(10) = [character(len=16) :: 'run', 'mesh', &
      'segments', 'ends', 'load', 'initial', 'strength_field', 'sweep', 'gauges', 'impactor']

   !> One echoed deck value (write_echo, and the attributes of PREFIX.h5).
   type :: echo_item_t
      character(len=:), allocatable :: group, name, value, unit
      logical :: given = .false.                        !! set in the deck (else default)
      character(len=:), allocatable :: doc              !! what it means (documentation only)
      ! the value with its type, for the typed attributes of /deck (doc/outputs.md)
      character(len=1) :: type = 't'                    !! 'r' real, 'i' integer, 'l' logical,
                                                        !! 't' text (its value unquoted)
      logical :: list = .false.                         !! an array variable: a list of values
      real(wp), allocatable :: reals(:)                 !! 'r': the values [its unit]; a
                                                        !! scalar not set: none, an element
                                                        !! not set: NaN
      integer, allocatable :: ints(:)                   !! 'i': the values
      logical, allocatable :: flags(:)                  !! 'l': the values
      character(len=name_len), allocatable :: words(:)  !! 't' list: the keywords
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
      logical :: warnings = .true.                      !! plausibility warnings on stderr
      character(len=name_len) :: header = 'names'       !! text headers: 'names' (first line
                                                        !! names the columns, no '#') |
                                                        !! 'comments' (every line '#')
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
      real(wp) :: area(max_segments) = unset            !! cross-section area [m^2] (default 1)
      real(wp) :: strength(max_segments) = unset        !! tensile strength [Pa]; < 0 unbreakable
      real(wp) :: fracture_energy(max_segments) = unset !! cohesive fracture energy [J/m^2];
                                                        !! 0 (default): brittle
      real(wp) :: damage_integral(max_segments) = unset !! Tuler-Butcher damage integral K
                                                        !! [Pa^lambda s]; 0 (default): none
      real(wp) :: damage_exponent(max_segments) = unset !! its exponent lambda [-] (default 2)
      character(len=name_len) :: interface(max_segments) = ''   !! 'bonded' | 'dry'
      real(wp) :: velocity(max_segments) = unset        !! initial rigid velocity [m/s]
      real(wp) :: gap(max_segments) = unset             !! initial gap at a dry interface [m]
   end type segments_cfg

   type :: ends_cfg
      character(len=name_len) :: top = 'free'          !! 'free' | 'fixed' | 'transmit' | 'velocity'
                                                       !! | 'base'
      character(len=name_len) :: bottom = 'free'       !! 'free' | 'fixed' | 'base' | 'transmit' |
                                                       !! 'velocity'
      real(wp) :: base_gap = 0.0_wp                    !! gap between bottom face and base [m]
      real(wp) :: base_gap_top = 0.0_wp                !! gap between top face and a base above
                                                       !! it [m]
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
      !> ensembles (doc/sweeps.md, "Ensembles"): realization i multiplies perturb by
      !> 1 + spread u_i, u_i uniform in [-1, 1] from (seed, i)
      character(len=name_len) :: perturb = ''          !! deck variable to perturb ('': none)
      real(wp) :: spread = 1.0e-3_wp                   !! relative half-width of the perturbation [-]
      !> history columns of PREFIX.ens (one slot more than max_ensemble_columns, so that a
      !> deck giving too many is told so by name)
      character(len=name_len) :: ensemble_columns(max_ensemble_columns + 1) = ''
      integer :: n_ensemble = 0                        !! how many ensemble_columns were given
      real(wp) :: horizon_tol = 0.01_wp                !! predictability horizon's share [-]
   end type sweep_cfg

   !> &gauges (optional): stress, velocity and displacement at reference positions, written
   !> to PREFIX.gau (and /gauges of PREFIX.h5). One slot more than max_gauges, so that a
   !> deck giving too many is told so by name.
   type :: gauges_cfg
      real(wp) :: x(max_gauges + 1) = unset            !! reference positions [m]
      integer :: n = 0                                 !! how many x were given
      integer :: every = 0                             !! steps between rows (not given:
                                                       !! &run history_every)
      character(len=name_len) :: side(max_gauges + 1) = ''   !! at a node that splits, the
                                                       !! side read: 'above' | 'below'; one
                                                       !! for all gauges or one per gauge
      integer :: n_side = 0                            !! how many side were given (after
                                                       !! validation: 1 or n)
   end type gauges_cfg

   !> &impactor (optional): a rigid striking mass at one end (doc/impactor.md).
   type :: impactor_cfg
      logical :: on = .false.                          !! the deck has the group
      character(len=name_len) :: face = 'top'          !! 'top' | 'bottom': the end it strikes
      real(wp) :: mass = unset                         !! [kg] (per m^2 when every area is 1)
      real(wp) :: velocity = 0.0_wp                    !! along +x at t = 0 [m/s]
      real(wp) :: gap = 0.0_wp                         !! between the mass and the face at t = 0 [m]
      real(wp) :: cushion = 0.0_wp                     !! linear spring between mass and face
                                                       !! [N/m] (per m^2 when every area is 1;
                                                       !! 0: rigid contact)
   end type impactor_cfg

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
      real(wp), allocatable :: gauge_x(:)             !! &gauges x [m] (none: no PREFIX.gau)
      integer :: gauge_every = 1                      !! &gauges every [steps]
      logical, allocatable :: gauge_below(:)          !! &gauges side: each gauge reads the
                                                      !! side below a node that splits
      logical :: names_first = .true.                 !! &run header = 'names'
      character(len=:), allocatable :: restarted_from !! --restart-any-version: its program
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
      type(gauges_cfg) :: gauges
      type(impactor_cfg) :: impactor
      logical :: is_sweep = .false.   !! read for --sweep: &sweep is required and echoed
      type(deck_scan_t) :: scan   !! what the file assigned (marks echo lines as input)
   end type deck_t

contains

   !> Whether a real was given (not the "not given" marker).
   logical elemental function is_set(x)
      real(wp), intent(in) :: x   !! a deck real
      is_set = .true.
      if (ieee_is_finite(x)) is_set = x > 0.5_wp * unset
   end function is_set
end module spb_deck_types
