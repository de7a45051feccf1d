!> The problem the model solves: the bar, its ends, the load, the initial state and the
!> event rules, as numbers and integer codes.
!>
!> Only the deck module builds it (problem_from_deck); mesh, load, state and the stepping
!> take it and know nothing of the deck's keywords. No strings and no "not given" markers:
!> what the deck left out is either a default here or a logical saying so.
module spb_problem
   use spb_kinds, only: wp
   implicit none
   private
   public :: problem_t
   public :: end_free, end_fixed, end_transmit, end_base, end_velocity, end_impactor
   public :: load_none, load_power, load_table, load_exponential, face_top, face_bottom
   public :: timing_accelerate, timing_delay, timing_min, timing_within, shift_above, shift_fragment, &
      shift_face
   public :: events_admissible, events_paper

   !> End conditions of the bar.
   integer, parameter :: end_free = 1, end_fixed = 2, end_transmit = 3, end_base = 4, &
      end_velocity = 5, end_impactor = 6
   !> Kinds of end load, and the face it acts on.
   integer, parameter :: load_none = 0, load_power = 1, load_table = 2, load_exponential = 3
   integer, parameter :: face_top = 1, face_bottom = 2
   !> Collision timing rules (5.2)-(5.3) and shift policies (doc/method.md, "Collisions");
   !> 'within' keeps the overlap at t^{n+1} as strain (doc/method.md, "Collisions timed within
   !> the step").
   integer, parameter :: timing_accelerate = 1, timing_delay = 2, timing_min = 3, &
      timing_within = 4
   integer, parameter :: shift_above = 1, shift_fragment = 2, shift_face = 3
   !> Event rules: 'admissible' keeps the continuum state a break or a lift-off acts on (no
   !> wave energy is created, no Jordan component is left); 'paper' is the paper's literal
   !> stage-1/stage-2 correction (doc/method.md, "Admissible events").
   integer, parameter :: events_admissible = 1, events_paper = 2

   type :: problem_t
      ! the bar, per segment j = 1..nseg (top to bottom)
      integer :: nseg = 0                          !! segments
      real(wp), allocatable :: length(:)           !! asked length [m]
      real(wp), allocatable :: young(:)            !! Young's modulus [Pa]
      real(wp), allocatable :: density(:)          !! [kg/m^3]
      real(wp), allocatable :: area(:)             !! cross-section area [m^2] (1: the
                                                   !! model per unit area, as before)
      real(wp), allocatable :: strength(:)         !! tensile strength [Pa]; < 0 unbreakable
      real(wp), allocatable :: fracture_energy(:)  !! cohesive fracture energy Gc [J/m^2]; 0:
                                                   !! brittle (the paper's fracture)
      real(wp), allocatable :: damage_integral(:)  !! Tuler-Butcher damage integral K
                                                   !! [Pa^lambda s]; 0: none (at once at R)
      real(wp), allocatable :: damage_exponent(:)  !! Tuler-Butcher exponent lambda [-]
      real(wp), allocatable :: velocity(:)         !! initial rigid velocity [m/s]
      logical, allocatable :: dry(:)               !! interface below segment j is dry
      real(wp), allocatable :: gap(:)              !! initial gap at that dry interface [m]
      ! the mesh
      integer :: cells = 0                         !! cells of the reference segment
      integer :: ref_segment = 1                   !! the segment whose cells set dt
      real(wp) :: dt = 0.0_wp                      !! time step [s]; 0: from cells
      logical :: stretch = .false.                 !! fit each segment's length to whole cells
      real(wp) :: t_end = 0.0_wp                   !! end time [s]
      ! ends and the rigid base
      integer :: top = end_free                    !! end_* code of node 0
      integer :: bottom = end_free                 !! end_* code of node n
      ! the striking mass (end_impactor at impactor_face)
      integer :: impactor_face = face_top          !! face_* code of the end it strikes
      real(wp) :: impactor_mass = 0.0_wp           !! [kg/m^2 A]
      real(wp) :: impactor_velocity = 0.0_wp       !! along +x at t = 0 [m/s]
      real(wp) :: impactor_gap = 0.0_wp            !! between the mass and the face at t = 0 [m]
      real(wp) :: impactor_cushion = 0.0_wp        !! spring stiffness (0: rigid) [Pa/m A]
      real(wp) :: base_gap = 0.0_wp                !! gap between bottom face and base [m]
      real(wp) :: base_gap_top = 0.0_wp            !! gap between top face and a base above [m]
      ! the end load
      integer :: load_kind = load_none             !! load_* code
      integer :: load_face = face_top              !! face_* code
      real(wp) :: p0 = 0.0_wp                      !! pressure scale [Pa]
      logical :: has_t_k = .false.                 !! the deck gave t_k
      real(wp) :: t_k = 0.0_wp                     !! decay time [s] (when has_t_k)
      real(wp) :: exponent = 0.0_wp                !! power-law exponent [-]
      logical :: has_t_cut = .false.               !! the deck gave t_cut
      real(wp) :: t_cut = 0.0_wp                   !! p = 0 after t_cut [s] (when has_t_cut)
      real(wp), allocatable :: table_t(:)          !! load_table: times [s], non-decreasing
      real(wp), allocatable :: table_p(:)          !! load_table: pressures [Pa]
      ! the initial state
      logical :: static_start = .false.            !! start in self-weight equilibrium
      real(wp) :: strain_rate = 0.0_wp             !! uniform stretching about the centre of
                                                   !! mass [1/s]
      ! strength per cell
      logical :: weibull = .false.                 !! Weibull strengths (else the segment's)
      real(wp) :: weibull_modulus = 0.0_wp         !! Weibull modulus m [-]
      real(wp) :: weibull_scale = 0.0_wp           !! Weibull scale [Pa]
      integer :: seed = 1                          !! generator seed (spb_random)
      ! the physics and the event rules
      real(wp) :: gravity = 0.0_wp                 !! acceleration along +x [m/s^2]
      logical :: full_mass = .false.               !! the paper's naive comparison model
      integer :: timing = timing_accelerate        !! timing_* code
      integer :: shift = shift_above               !! shift_* code
      integer :: events = events_admissible        !! events_* code
      real(wp) :: eps_rel = 1.0e-9_wp              !! round-off guard of the event tests [-]
   end type problem_t
end module spb_problem
