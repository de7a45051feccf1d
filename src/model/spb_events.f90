!> Events (fracture, collision, separation) as data: produced by the physics modules,
!> written by the output module, inspected by tests.
module spb_events
   use spb_kinds, only: wp
   use spb_columns, only: column_set_t, column_set, add_column
   implicit none
   private
   public :: event_t, event_list_t, push_event, ev_fracture, ev_collision, ev_separation
   public :: ev_base_collision, ev_impact, ev_release, ev_crack, event_kind_t, event_kinds, &
      n_event_kinds
   public :: event_columns_t, register_event_columns, post_event_columns

   integer, parameter :: ev_fracture = 1, ev_collision = 2, ev_separation = 3
   integer, parameter :: ev_base_collision = 4
   !> A striking mass comes into contact with its face, and leaves it (spb_impactor)
   integer, parameter :: ev_impact = 5, ev_release = 6
   !> A cohesive crack starts (its end, the full opening, is a fracture)
   integer, parameter :: ev_crack = 7

   !> What the writers need to know of an event kind (entry code of event_kinds).
   type :: event_kind_t
      character(len=14) :: name = ''      !! the .evt 'kind' column, HDF5 /events kind_codes
      character(len=16) :: plural = ''    !! its count in the run summary's events line ('':
                                          !! not there)
      character(len=24) :: column = ''    !! its count's column in the sweep table ('': none)
      !> one of the kinds from the first format on: its count is in the run summary's events
      !> line and the checkpoint even when 0, and its sweep column after status; the others'
      !> counts only when some occurred (outputs without them stay as they were), their
      !> columns after e_fracture
      logical :: core = .false.
   end type event_kind_t

   !> The event kinds, in code order: the one list the outputs, the run summary, the
   !> checkpoint and the sweep table follow (a new kind is a line here and its physics).
   type(event_kind_t), parameter :: event_kinds(7) = [ &
      event_kind_t('fracture', 'fractures', 'fractures', .true.), &
      event_kind_t('collision', 'collisions', 'collisions', .true.), &
      event_kind_t('separation', 'separations', 'separations', .true.), &
      event_kind_t('base-collision', 'base collisions', 'base_collisions', .true.), &
      event_kind_t('impact', 'impacts', 'impacts', .false.), &
      event_kind_t('release', 'releases', '', .false.), &
      event_kind_t('crack', '', 'cracks', .false.)]
   integer, parameter :: n_event_kinds = size(event_kinds)   !! codes 1 .. n_event_kinds

   type :: event_t
      integer :: kind = ev_fracture     !! ev_* constant
      integer :: step = 0               !! the event holds from t^step on
      integer :: node = 0               !! node whose section the event concerns
      real(wp) :: t = 0.0_wp            !! [s]
      real(wp) :: x = 0.0_wp            !! reference position of the section [m]
      real(wp) :: stress = 0.0_wp       !! section stress that caused it [Pa]
      real(wp) :: dt_bound = 0.0_wp     !! (4.1): the true time is at most this earlier [s]
      real(wp) :: dx_bound = 0.0_wp     !! (4.2): the true place is at most this far [m]
      real(wp) :: opening = 0.0_wp      !! fracture: initial opening of the faces; collision:
                                        !! the correction (5.2) of the chosen rule [m]
      real(wp) :: stress_bound = 0.0_wp !! (6.2): bound of the collision stress error [Pa]
      real(wp) :: shift = 0.0_wp        !! rigid shift applied to one side [m]
      integer :: frag_above = 0         !! fragment ids on either side after the event
      integer :: frag_below = 0
   end type event_t

   type :: event_list_t
      type(event_t), allocatable :: e(:)
      integer :: n = 0
   end type event_list_t

   !> The columns of PREFIX.evt and /events: their ids (spb_columns).
   type :: event_columns_t
      integer :: t = 0, step = 0, kind = 0, node = 0, x = 0, stress = 0, dt_bound = 0
      integer :: dx_bound = 0, opening = 0, frag_above = 0, frag_below = 0, stress_bound = 0
      integer :: shift = 0
   end type event_columns_t

contains

   !> The columns of PREFIX.evt and /events (their meaning: doc/outputs.md), one owner's:
   !> the file's order is the registration order here. Whole numbers in 12 characters, the
   !> kind's name in 16.
   pure subroutine register_event_columns(set, id)
      type(column_set_t), intent(out) :: set    !! the events' columns, in file order
      type(event_columns_t), intent(out) :: id  !! their ids
      set = column_set([character(len=24) ::])
      call add_column(set, id%t, 't', 's')
      call add_column(set, id%step, 'step', '-', whole=.true., width=12)
      call add_column(set, id%kind, 'kind', '-', whole=.true., width=16, kind=.true.)
      call add_column(set, id%node, 'node', '-', whole=.true., width=12)
      call add_column(set, id%x, 'x', 'm')
      call add_column(set, id%stress, 'stress', 'Pa')
      call add_column(set, id%dt_bound, 'dt_bound', 's')
      call add_column(set, id%dx_bound, 'dx_bound', 'm')
      call add_column(set, id%opening, 'opening', 'm')
      call add_column(set, id%frag_above, 'frag_above', '-', whole=.true., width=12)
      call add_column(set, id%frag_below, 'frag_below', '-', whole=.true., width=12)
      call add_column(set, id%stress_bound, 'stress_bound', 'Pa')
      call add_column(set, id%shift, 'shift', 'm')
   end subroutine register_event_columns

   !> Post an event into a row of the events' columns.
   pure subroutine post_event_columns(id, e, row)
      type(event_columns_t), intent(in) :: id   !! the columns' ids
      type(event_t), intent(in) :: e            !! the event
      real(wp), intent(inout) :: row(:)         !! the row
      row(id%t) = e%t
      row(id%step) = real(e%step, wp)
      row(id%kind) = real(e%kind, wp)
      row(id%node) = real(e%node, wp)
      row(id%x) = e%x
      row(id%stress) = e%stress
      row(id%dt_bound) = e%dt_bound
      row(id%dx_bound) = e%dx_bound
      row(id%opening) = e%opening
      row(id%frag_above) = real(e%frag_above, wp)
      row(id%frag_below) = real(e%frag_below, wp)
      row(id%stress_bound) = e%stress_bound
      row(id%shift) = e%shift
   end subroutine post_event_columns

   !> Append an event to the list (grown by doubling).
   pure subroutine push_event(list, ev)
      type(event_list_t), intent(inout) :: list   !! the list (grown as needed)
      type(event_t), intent(in) :: ev             !! the event to append
      type(event_t), allocatable :: grown(:)
      if (.not. allocated(list%e)) allocate(list%e(8))
      if (list%n == size(list%e)) then
         allocate(grown(2 * size(list%e)))
         grown(1:list%n) = list%e(1:list%n)
         call move_alloc(grown, list%e)
      end if
      list%n = list%n + 1
      list%e(list%n) = ev
   end subroutine push_event
end module spb_events
