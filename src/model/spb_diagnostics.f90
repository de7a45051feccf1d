!> Experiment diagnostics (doc/outputs.md, "PREFIX.spl" and "PREFIX.imp"): what a spall
!> experiment reads at a free end of the bar (the velocity peak, the pull-back minimum, the
!> Novikov spall strength, the spall plane and the scab), and the table of contact episodes
!> (two fragments, a fragment and the base, the striking mass and its face).
!>
!> This module owns the recording: it watches the state and the events after each step
!> (spb_sim calls diag_step, and diag_end_samples for steps taken in a block); the physics
!> modules do not know of it. The picking of the peak and the pull-back is the pure kernel
!> pick_sample. What a checkpoint keeps of the record is the one list diag_fields.
module spb_diagnostics
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
   use spb_kinds, only: wp
   use spb_field_io, only: field_io_t
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t
   use spb_ends, only: face_top, face_bottom, has_free_face, has_base, is_striker
   use spb_events, only: event_list_t, ev_fracture, ev_collision, ev_separation, &
      ev_base_collision, ev_impact, ev_release
   use spb_fragments, only: fragment_span, span_momentum, span_mass
   implicit none
   private
   public :: pick_t, pick_sample, significant, spall_end_t, impact_t, diag_t, diag_start, diag_step, &
      diag_end_samples, diag_fields, diag_close, imp_kind_names, imp_fragments, imp_base, &
      imp_impactor, pick_fraction, diag_problem, end_names, spall_row, impact_row, spall_columns, &
      impact_columns, spall_units, impact_units, first_impacts, diag_taken, contact_nodes, &
      diag_contact_samples, contacts_by_sections

   !> The share of the swing that confirms a peak or a pull-back minimum (doc/outputs.md,
   !> "How the peak and the pull-back are picked"): a maximum is the peak once the velocity
   !> has fallen below it by this share of the peak's rise over the velocity at t = 0; a
   !> minimum after it is the pull-back once the velocity has risen above it by this share of
   !> the drop from the peak to it. 0.1: the lattice's ringing behind a front (below 1 % of
   !> the jump at Courant number 1) cannot confirm either, while a spall signal (the rise
   !> after the minimum is the whole drop 2 R / Z) does at once.
   real(wp), parameter :: pick_fraction = 0.1_wp

   !> A later sample replaces the peak's candidate only when it exceeds it by more than this
   !> share of the swing: round-off on a plateau does not move the peak's time.
   real(wp), parameter :: plateau_tol = 1.0e-9_wp

   !> The picking's phases: waiting for the peak, after the peak (looking for the minimum),
   !> done (the pull-back found).
   integer, parameter :: phase_rise = 0, phase_fall = 1, phase_done = 2

   integer, parameter :: imp_fragments = 1, imp_base = 2, imp_impactor = 3
   character(len=9), parameter :: imp_kind_names(3) = ['fragments', 'base     ', 'impactor ']
   character(len=6), parameter :: end_names(2) = ['top   ', 'bottom']
   integer, parameter :: first_impacts = 5   !! episodes the run summary lists
   integer, parameter :: hole = -1           !! the node of a slot of diag_t%open whose
                                             !! episode ended (no node is negative)

   !> The running peak and pull-back of one end's outward velocity (pick_sample).
   type :: pick_t
      integer :: phase = phase_rise
      real(wp) :: w0 = 0.0_wp              !! outward velocity at t = 0 [m/s]
      real(wp) :: w_max = 0.0_wp           !! largest outward velocity so far (rise), the
                                           !! peak (after) [m/s]
      real(wp) :: t_max = -1.0_wp          !! its time (-1: none) [s]
      real(wp) :: w_min = 0.0_wp           !! smallest since the peak [m/s]
      real(wp) :: t_min = -1.0_wp          !! its time (-1: none) [s]
      real(wp) :: swing = 0.0_wp           !! largest |w - w0| so far [m/s]
      real(wp) :: floor = 0.0_wp           !! the bar's velocity scale at the last sample:
                                           !! the largest |w0| and swing of either end [m/s]
   end type pick_t

   !> One end's record (a row of PREFIX.spl).
   type :: spall_end_t
      logical :: on = .false.              !! the end has a free face (a row)
      type(pick_t) :: pick                 !! its velocity peak and pull-back
      real(wp) :: z = 0.0_wp               !! impedance rho c of the end cell [kg/(m^2 s)]
      real(wp) :: x_end = 0.0_wp           !! reference position of the end [m]
      integer :: node = -1                 !! node of the fracture nearest the end (-1: none)
      real(wp) :: spall_x = 0.0_wp         !! its reference position [m]
      real(wp) :: spall_t = 0.0_wp         !! its time [s]
      real(wp) :: scab_v = 0.0_wp          !! the velocity of the piece it freed, outward [m/s]
   end type spall_end_t

   !> A contact episode (a row of PREFIX.imp).
   type :: impact_t
      integer :: kind = imp_fragments      !! imp_* constant
      integer :: node = 0                  !! the contact's node (the end node: base, impactor)
      real(wp) :: t_start = 0.0_wp         !! [s]
      real(wp) :: t_end = -1.0_wp          !! [s]; -1: open
      real(wp) :: x = 0.0_wp               !! reference position of the contact [m]
      real(wp) :: peak = 0.0_wp            !! largest contact force (compression > 0) [N A]
      real(wp) :: impulse = 0.0_wp         !! integral of the contact force [N s A]
      real(wp) :: v(4) = 0.0_wp            !! centre-of-mass velocities along +x: above and
                                           !! below before, above and below after [m/s]
   end type impact_t

   !> The whole record of a run.
   type :: diag_t
      type(spall_end_t) :: ends(2)         !! face_top, face_bottom
      real(wp) :: scale = 0.0_wp           !! the bar's velocity scale so far: the largest
                                           !! |w0| and |w - w0| of either end [m/s]
      type(impact_t), allocatable :: open(:)   !! episodes under way in the order they began,
                                               !! first n_open slots used; a slot whose
                                               !! episode ended is a hole (node = hole)
      integer :: n_open = 0
      integer :: n_holes = 0               !! holes among open(1:n_open): an episode's end
                                           !! leaves one instead of moving the slots after it
                                           !! (thousands when every cell is a contact); they
                                           !! are packed away once they are half (pack_open)
      integer :: n_done = 0                !! episodes ended so far
      type(impact_t) :: first(first_impacts)   !! the first min(n_done, first_impacts) of
                                               !! them (the run summary's)
      type(impact_t), allocatable :: ended(:)  !! episodes ended since the caller last took
                                               !! them (PREFIX.imp's rows; diag_taken),
                                               !! first n_ended used
      integer :: n_ended = 0
      !> open_at's index: the open episodes other than a striking mass's at each node 0..n,
      !> and the slot of one of them (where there is one, it is that one's): a separation
      !> finds its episode without a search (millions when every cell is a contact).
      !> Built at the first step that needs it (index_open; a checkpoint does not keep it).
      integer, allocatable :: n_at(:)
      integer, allocatable :: slot_at(:)
   end type diag_t

contains

   !> One sample w at time t of an end's outward velocity into its picking (doc/outputs.md,
   !> "How the peak and the pull-back are picked").
   elemental subroutine pick_sample(p, t, w, floor)
      type(pick_t), intent(inout) :: p     !! the picking
      real(wp), intent(in) :: t            !! the sample's time [s]
      real(wp), intent(in) :: w            !! the outward velocity then [m/s]
      real(wp), intent(in), optional :: floor   !! the bar's velocity scale (both ends' |w0|
                                                !! and swings) [m/s]
      ! a state that is not finite ends the run at its next check (spb_sim): no sample
      if (.not. ieee_is_finite(w)) return
      p%swing = max(p%swing, abs(w - p%w0))
      if (present(floor)) p%floor = max(p%floor, floor)
      select case (p%phase)
      case (phase_rise)
         if (w > p%w_max + plateau_tol * p%swing) then
            p%w_max = w
            p%t_max = t
         else if (significant(p) .and. p%w_max - w > pick_fraction * (p%w_max - p%w0)) then
            p%phase = phase_fall
            p%w_min = w
            p%t_min = t
         end if
      case (phase_fall)
         if (w < p%w_min) then
            p%w_min = w
            p%t_min = t
         else if (w - p%w_min > pick_fraction * (p%w_max - p%w_min)) then
            p%phase = phase_done
         end if
      case default
         ! phase_done: the row is fixed
      end select
   end subroutine pick_sample

   !> The largest outward velocity so far is a peak's candidate: it rose above the velocity
   !> at t = 0 by more than pick_fraction of the largest swing |w - w0| seen, and of the bar's
   !> velocity scale (floor: round-off at an end the waves have not reached yet, and ringing
   !> about a resting end, are not).
   elemental logical function significant(p)
      type(pick_t), intent(in) :: p        !! the picking
      significant = p%t_max >= 0.0_wp .and. p%w_max - p%w0 > pick_fraction * &
                    max(p%swing, p%floor)
   end function significant

   !> The record at t = 0: which ends have rows, their velocities then.
   pure subroutine diag_start(d, mesh, st)
      type(diag_t), intent(out) :: d       !! the record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state at t = 0
      integer :: side
      real(wp) :: w(2)
      w = outward(mesh, st%dub(0), st%dua(mesh%n))
      do side = face_top, face_bottom
         d%ends(side)%on = has_free_face(st%ends(side))
         d%ends(side)%pick%w0 = w(side)
         d%ends(side)%pick%w_max = w(side)
      end do
      d%ends(face_top)%z = mesh%z(1) / mesh%area(1)
      d%ends(face_bottom)%z = mesh%z(mesh%n) / mesh%area(mesh%n)
      d%ends(face_top)%x_end = mesh%x(0)
      d%ends(face_bottom)%x_end = mesh%x(mesh%n)
      allocate(d%open(4), d%ended(4))
   end subroutine diag_start

   !> The outward velocities of the two end faces from their halves' increments [m/s].
   pure function outward(mesh, du_top, du_bot) result(w)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: du_top       !! increment of B_0 over the step [m]
      real(wp), intent(in) :: du_bot       !! increment of A_n over the step [m]
      real(wp) :: w(2)
      w = [-du_top, du_bot] / mesh%dt
   end function outward

   !> Steps taken in a block (spb_step advance_joined): the end faces' increments of each,
   !> the first at step n0 + 1.
   pure subroutine diag_end_samples(d, mesh, n0, du)
      type(diag_t), intent(inout) :: d     !! the record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      integer, intent(in) :: n0            !! the step before the block
      real(wp), intent(in) :: du(:, :)     !! (face, step) increments of the face halves [m]
      integer :: t, side
      real(wp) :: w(2)
      do t = 1, size(du, 2)
         w = outward(mesh, du(face_top, t), du(face_bottom, t))
         ! the bar's velocity scale: both ends' velocities at t = 0 and swings since
         do side = face_top, face_bottom
            if (ieee_is_finite(w(side))) d%scale = max(d%scale, abs(d%ends(side)%pick%w0), &
                                                       abs(w(side) - d%ends(side)%pick%w0))
         end do
         do side = face_top, face_bottom
            if (d%ends(side)%on) call pick_sample(d%ends(side)%pick, &
                                                  real(n0 + t, wp) * mesh%dt, w(side), d%scale)
         end do
      end do
   end subroutine diag_end_samples

   !> Every episode under way is a contact of fragments (its force a section's stress), so
   !> that a block of steps without events may sample them (contact_nodes).
   pure logical function contacts_by_sections(d)
      type(diag_t), intent(in) :: d        !! the record
      integer :: k
      contacts_by_sections = .true.
      do k = 1, d%n_open
         if (d%open(k)%node == hole) cycle
         if (d%open(k)%kind /= imp_fragments) contacts_by_sections = .false.
      end do
   end function contacts_by_sections

   !> The nodes of the episodes under way (holes left out), in their order.
   pure subroutine contact_nodes(d, nodes)
      type(diag_t), intent(in) :: d        !! the record
      integer, allocatable, intent(out) :: nodes(:)   !! their nodes
      integer :: k, c
      c = 0
      do k = 1, d%n_open
         if (d%open(k)%node /= hole) c = c + 1
      end do
      allocate(nodes(c))
      c = 0
      do k = 1, d%n_open
         if (d%open(k)%node == hole) cycle
         c = c + 1
         nodes(c) = d%open(k)%node
      end do
   end subroutine contact_nodes

   !> The forces of a block of steps without events into the episodes under way: f(c, t) of
   !> the c-th of contact_nodes at the t-th step (as diag_step adds them step by step).
   pure subroutine diag_contact_samples(d, f, dt)
      type(diag_t), intent(inout) :: d     !! the record
      real(wp), intent(in) :: f(:, :)      !! (episode, step) their sections [Pa A]
      real(wp), intent(in) :: dt           !! the step [s]
      integer :: k, c, t
      c = 0
      do k = 1, d%n_open
         if (d%open(k)%node == hole) cycle
         c = c + 1
         do t = 1, size(f, 2)
            call add_force(d%open(k), f(c, t), dt)
         end do
      end do
   end subroutine diag_contact_samples

   !> After a step with its events: the ends' samples, the fractures nearest the ends, the
   !> episodes that begin, go on and end.
   pure subroutine diag_step(d, mesh, st, events)
      type(diag_t), intent(inout) :: d     !! the record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state after the step
      type(event_list_t), intent(in) :: events   !! the step's events
      real(wp) :: du(2, 1)
      integer :: j, k
      du(:, 1) = [st%dub(0), st%dua(mesh%n)]
      call diag_end_samples(d, mesh, st%step - 1, du)
      if (events%n > 0 .and. .not. allocated(d%n_at)) call index_open(d, mesh%n)
      do j = 1, events%n
         associate (ev => events%e(j))
            select case (ev%kind)
            case (ev_fracture)
               call fracture_seen(d, mesh, st, ev%node, ev%t)
            case (ev_collision)
               call begin(d, mesh, st, imp_fragments, ev%node, ev%t)
            case (ev_base_collision)
               call begin(d, mesh, st, imp_base, ev%node, ev%t)
            case (ev_impact)
               call begin(d, mesh, st, imp_impactor, ev%node, ev%t)
            case (ev_separation, ev_release)
               k = open_at(d, ev%node, ev%kind == ev_release)
               ! a striking mass's contact integral of the step covers its contact up to the
               ! release; a section's stress of the step it opens is the pull that opened it
               if (k > 0 .and. ev%kind == ev_release) call add_force(d%open(k), &
                  contact_force(mesh, st, d%open(k)), mesh%dt)
               if (k > 0) call finish(d, mesh, st, k, ev%t)
            case default
               ! cracks starting: no episode, no spall plane yet (their fracture is)
            end select
         end associate
      end do
      do k = 1, d%n_open
         if (d%open(k)%node == hole) cycle
         call add_force(d%open(k), contact_force(mesh, st, d%open(k)), mesh%dt)
      end do
   end subroutine diag_step

   !> A fracture at node i at time t: the nearest to an end so far is that end's spall plane,
   !> with the velocity of the piece between it and the end.
   pure subroutine fracture_seen(d, mesh, st, i, t)
      type(diag_t), intent(inout) :: d     !! the record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state after the step
      integer, intent(in) :: i             !! the broken node
      real(wp), intent(in) :: t            !! its time [s]
      if (i <= 0 .or. i >= mesh%n) return
      associate (e => d%ends(face_top))
         if (e%on .and. (e%node < 0 .or. i < e%node)) then
            e%node = i
            e%spall_x = mesh%x(i)
            e%spall_t = t
            e%scab_v = -span_momentum(mesh, st, 0, i) / span_mass(mesh, 0, i)
         end if
      end associate
      associate (e => d%ends(face_bottom))
         if (e%on .and. (e%node < 0 .or. i > e%node)) then
            e%node = i
            e%spall_x = mesh%x(i)
            e%spall_t = t
            e%scab_v = span_momentum(mesh, st, i, mesh%n) / span_mass(mesh, i, mesh%n)
         end if
      end associate
   end subroutine fracture_seen

   !> The open episode at node (a striking mass's: release), 0 if none; the first of them
   !> in the order they began.
   pure integer function open_at(d, node, release) result(k)
      type(diag_t), intent(in) :: d        !! the record
      integer, intent(in) :: node          !! the node of the event
      logical, intent(in) :: release       !! the event is a striking mass's release
      if (.not. release .and. allocated(d%n_at)) then
         if (node >= lbound(d%n_at, 1) .and. node <= ubound(d%n_at, 1)) then
            ! the index: none, or the only one (its slot checked), else the search
            k = 0
            if (d%n_at(node) == 0) return
            k = d%slot_at(node)
            if (d%n_at(node) == 1 .and. k >= 1 .and. k <= d%n_open) then
               if (d%open(k)%node == node .and. d%open(k)%kind /= imp_impactor) return
            end if
         end if
      end if
      do k = 1, d%n_open
         if (d%open(k)%node /= node) cycle
         if (release .eqv. (d%open(k)%kind == imp_impactor)) return
      end do
      k = 0
   end function open_at

   !> The two sides' centre-of-mass velocities at a contact (along +x) [m/s]: fragments, the
   !> base (at rest), the striking mass.
   pure function side_velocities(mesh, st, kind, node) result(v)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: kind          !! imp_* constant
      integer, intent(in) :: node          !! the contact's node
      real(wp) :: v(2)
      integer :: j, k, side
      v = 0.0_wp
      call fragment_span(mesh, st, node, j, k)
      if (kind == imp_fragments) then
         v(1) = span_momentum(mesh, st, j, node) / span_mass(mesh, j, node)
         v(2) = span_momentum(mesh, st, node, k) / span_mass(mesh, node, k)
         return
      end if
      side = merge(face_top, face_bottom, node == 0)
      if (side == face_top) then
         v(2) = span_momentum(mesh, st, 0, k) / span_mass(mesh, 0, k)
         if (kind == imp_impactor) v(1) = st%ends(side)%striker%v
      else
         v(1) = span_momentum(mesh, st, j, mesh%n) / span_mass(mesh, j, mesh%n)
         if (kind == imp_impactor) v(2) = st%ends(side)%striker%v
      end if
   end function side_velocities

   !> The contact force of an open episode over the step just taken (compression > 0) [N A]:
   !> the section stress of the node, a striking mass's contact integral over dt.
   pure real(wp) function contact_force(mesh, st, e) result(f)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state after the step
      type(impact_t), intent(in) :: e      !! the episode
      integer :: side
      if (e%kind == imp_impactor) then
         side = merge(face_top, face_bottom, e%node == 0)
         f = st%ends(side)%q / mesh%dt
      else
         f = st%section(e%node)
      end if
   end function contact_force

   !> One step's force into an episode's peak and impulse.
   pure subroutine add_force(e, f, dt)
      type(impact_t), intent(inout) :: e   !! the episode
      real(wp), intent(in) :: f            !! the step's contact force [N A]
      real(wp), intent(in) :: dt           !! the step [s]
      if (.not. ieee_is_finite(f)) return   ! the run ends at its next check (spb_sim)
      e%peak = max(e%peak, f)
      e%impulse = e%impulse + f * dt
   end subroutine add_force

   !> An episode begins: its sides' velocities before, as they are at the end of the step in
   !> which it begins (the step's share of the contact impulse, at most F dt / M, is in them).
   pure subroutine begin(d, mesh, st, kind, node, t)
      type(diag_t), intent(inout) :: d     !! the record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state after the step
      integer, intent(in) :: kind          !! imp_* constant
      integer, intent(in) :: node          !! the contact's node
      real(wp), intent(in) :: t            !! its time [s]
      type(impact_t) :: e
      e%kind = kind
      e%node = node
      e%t_start = t
      e%x = mesh%x(node)
      e%v(1:2) = side_velocities(mesh, st, kind, node)
      call push(d%open, d%n_open, e)
      if (kind /= imp_impactor .and. allocated(d%n_at)) then
         d%n_at(node) = d%n_at(node) + 1
         d%slot_at(node) = d%n_open
      end if
   end subroutine begin

   !> Episode k ends at t: its sides' velocities after, it moves to the ended ones.
   pure subroutine finish(d, mesh, st, k, t)
      type(diag_t), intent(inout) :: d     !! the record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state after the step
      integer, intent(in) :: k             !! the open episode
      real(wp), intent(in) :: t            !! its end [s]
      type(impact_t) :: e
      e = d%open(k)
      e%t_end = t
      e%v(3:4) = side_velocities(mesh, st, e%kind, e%node)
      call ended(d, e)
      if (e%kind /= imp_impactor .and. allocated(d%n_at)) d%n_at(e%node) = d%n_at(e%node) - 1
      d%open(k)%node = hole
      d%n_holes = d%n_holes + 1
      if (2 * d%n_holes >= d%n_open) call pack_open(d)
   end subroutine finish

   !> The open episodes packed to the front of d%open, in the order they began (the holes
   !> gone).
   pure subroutine pack_open(d)
      type(diag_t), intent(inout) :: d     !! the record
      integer :: k, m
      m = 0
      do k = 1, d%n_open
         if (d%open(k)%node == hole) cycle
         m = m + 1
         if (m < k) d%open(m) = d%open(k)
         if (allocated(d%n_at) .and. d%open(m)%kind /= imp_impactor) d%slot_at(d%open(m)%node) = m
      end do
      d%n_open = m
      d%n_holes = 0
   end subroutine pack_open

   !> open_at's index of the open episodes (diag_t n_at, slot_at) for nodes 0..n.
   pure subroutine index_open(d, n)
      type(diag_t), intent(inout) :: d     !! the record
      integer, intent(in) :: n             !! cells of the bar
      integer :: k, i
      if (allocated(d%n_at)) deallocate(d%n_at, d%slot_at)
      allocate(d%n_at(0:n), d%slot_at(0:n))
      d%n_at = 0
      d%slot_at = 0
      do k = d%n_open, 1, -1
         i = d%open(k)%node
         if (i == hole .or. d%open(k)%kind == imp_impactor) cycle
         d%n_at(i) = d%n_at(i) + 1
         d%slot_at(i) = k
      end do
   end subroutine index_open

   !> An episode ended (or open at the end of the run): counted, kept among the first ones
   !> while there are fewer than first_impacts, and among those the caller takes next.
   pure subroutine ended(d, e)
      type(diag_t), intent(inout) :: d     !! the record
      type(impact_t), intent(in) :: e      !! the episode
      d%n_done = d%n_done + 1
      if (d%n_done <= first_impacts) d%first(d%n_done) = e
      call push(d%ended, d%n_ended, e)
   end subroutine ended

   !> The caller has taken the ended episodes (written them to PREFIX.imp, or has no
   !> files): they are dropped, so that memory holds only the episodes open at once.
   pure subroutine diag_taken(d)
      type(diag_t), intent(inout) :: d     !! the record
      d%n_ended = 0
   end subroutine diag_taken

   !> Append an episode to a list (grown by doubling).
   pure subroutine push(list, n, e)
      type(impact_t), allocatable, intent(inout) :: list(:)   !! the list
      integer, intent(inout) :: n          !! entries used
      type(impact_t), intent(in) :: e      !! the episode
      type(impact_t), allocatable :: grown(:)
      if (.not. allocated(list)) allocate(list(4))
      if (n == size(list)) then
         allocate(grown(2 * size(list)))
         grown(1:n) = list(1:n)
         call move_alloc(grown, list)
      end if
      n = n + 1
      list(n) = e
   end subroutine push

   !> The end of the run: the episodes still open end with no end (their t_end, duration
   !> and velocities after empty), in the order they began.
   pure subroutine diag_close(d)
      type(diag_t), intent(inout) :: d     !! the record
      integer :: k
      call pack_open(d)
      do k = 1, d%n_open
         call ended(d, d%open(k))
      end do
      d%n_open = 0
      if (allocated(d%n_at)) deallocate(d%n_at, d%slot_at)
   end subroutine diag_close

   !> The columns of PREFIX.spl (after the word end) and their units.
   pure function spall_columns() result(names)
      character(len=14) :: names(10)
      names = [character(len=14) :: 't_peak', 'v_peak', 't_pullback', 'v_pullback', &
               'dv_pullback', 'sigma_novikov', 'spall_x', 'spall_t', 'scab_thickness', &
               'scab_velocity']
   end function spall_columns

   !> The units of spall_columns.
   pure function spall_units() result(units)
      character(len=5) :: units(10)
      units = [character(len=5) :: 's', 'm/s', 's', 'm/s', 'm/s', 'Pa', 'm', 's', 'm', 'm/s']
   end function spall_units

   !> The columns of PREFIX.imp (after kind, the fourth) and their units.
   pure function impact_columns() result(names)
      character(len=14) :: names(11)
      names = [character(len=14) :: 't_start', 't_end', 'duration', 'kind', 'x', &
               'peak_force', 'impulse', 'v_above_before', 'v_below_before', 'v_above_after', &
               'v_below_after']
   end function impact_columns

   !> The units of impact_columns (per unit area: the caller's).
   pure function impact_units() result(units)
      character(len=5) :: units(11)
      units = [character(len=5) :: 's', 's', 's', '-', 'm', 'N', 'N s', 'm/s', 'm/s', 'm/s', &
               'm/s']
   end function impact_units

   !> One end's row of PREFIX.spl (spall_columns); NaN where there is no value.
   pure function spall_row(e) result(v)
      type(spall_end_t), intent(in) :: e  !! the end's record
      real(wp) :: v(10)
      real(wp) :: nan
      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      v = nan
      ! a confirmed peak stays one when a later, larger swing (a pull the other way) would
      ! make it small
      if (e%pick%phase /= phase_rise .or. significant(e%pick)) then
         v(1) = e%pick%t_max
         v(2) = e%pick%w_max
      end if
      if (e%pick%phase == phase_done) then
         v(3) = e%pick%t_min
         v(4) = e%pick%w_min
         v(5) = e%pick%w_max - e%pick%w_min
         v(6) = 0.5_wp * e%z * v(5)
      end if
      if (e%node >= 0) then
         v(7) = e%spall_x
         v(8) = e%spall_t
         v(9) = abs(e%spall_x - e%x_end)
         v(10) = e%scab_v
      end if
   end function spall_row

   !> One episode's row of PREFIX.imp (impact_columns; kind as its code); NaN where there is
   !> no value (an episode open at the end).
   pure function impact_row(e) result(v)
      type(impact_t), intent(in) :: e     !! the episode
      real(wp) :: v(11)
      v = ieee_value(1.0_wp, ieee_quiet_nan)
      v(1) = e%t_start
      v(4) = real(e%kind, wp)
      v(5) = e%x
      v(6) = e%peak
      v(7) = e%impulse
      v(8:9) = e%v(1:2)
      if (e%t_end >= 0.0_wp) then
         v(2) = e%t_end
         v(3) = e%t_end - e%t_start
         v(10:11) = e%v(3:4)
      end if
   end function impact_row

   !> Why a record read back from a checkpoint cannot be continued on a mesh of n cells (''
   !> when it can): every node, kind and phase in range, every value finite but the NaN-free
   !> defaults.
   pure function diag_problem(d, n) result(why)
      type(diag_t), intent(in) :: d        !! the record read back
      integer, intent(in) :: n             !! cells of the mesh
      character(len=:), allocatable :: why
      integer :: side, k
      why = ''
      if (d%n_open < 0 .or. d%n_done < 0) then
         why = 'is damaged: its count of open or ended contact episodes is out of range'
         return
      end if
      do side = face_top, face_bottom
         associate (e => d%ends(side))
            if (e%pick%phase < phase_rise .or. e%pick%phase > phase_done .or. e%node < -1 &
                .or. e%node > n .or. .not. all(ieee_is_finite([e%pick%w0, e%pick%w_max, &
                e%pick%t_max, e%pick%w_min, e%pick%t_min, e%pick%swing, e%pick%floor, e%z, &
                e%x_end, &
                e%spall_x, e%spall_t, e%scab_v]))) then
               why = 'is damaged: its spall record of the ' // trim(end_names(side)) // &
                     ' end is out of range'
               return
            end if
         end associate
      end do
      do k = 1, d%n_open + min(d%n_done, first_impacts)
         if (k <= d%n_open) then
            if (bad(d%open(k))) why = 'is damaged: an open contact episode is out of range'
         else
            if (bad(d%first(k - d%n_open))) why = 'is damaged: a contact episode is out of range'
         end if
         if (len(why) > 0) return
      end do
   contains
      !> The episode's kind or node out of range.
      pure logical function bad(e)
         type(impact_t), intent(in) :: e   !! the episode
         bad = e%kind < imp_fragments .or. e%kind > imp_impactor .or. e%node < 0 .or. e%node > n
         if (e%kind /= imp_fragments) bad = bad .or. (e%node /= 0 .and. e%node /= n)
      end function bad
   end function diag_problem

   !> A whole number read back as a real: x when it is one within the integers' range, else
   !> -huge (what range checks then refuse).
   elemental integer function whole(x) result(i)
      real(wp), intent(in) :: x            !! the value
      i = -huge(1)
      if (ieee_is_finite(x)) then
         if (abs(x) < real(huge(1), wp)) i = nint(x)
      end if
   end function whole

   !> The one list of what a checkpoint keeps of the record (attributes of group, the
   !> episodes one array: those open, then the first ended ones the run summary lists; the
   !> others are in PREFIX.imp up to the checkpoint's mark), written or read back
   !> (io%writing); all of it added later: a checkpoint of a version without it restarts
   !> with the record as at t = 0 (diag_start).
   subroutine diag_fields(d, io, group)
      type(diag_t), intent(inout) :: d     !! the record
      class(field_io_t), intent(inout) :: io   !! the checkpoint file
      character(len=*), intent(in) :: group    !! its group ('/run')
      integer, parameter :: nf = 13        ! values per episode
      integer :: side, k, n_open, n_first
      real(wp) :: r
      real(wp), allocatable :: a(:)
      character(len=:), allocatable :: p
      do side = face_top, face_bottom
         p = 'spl_' // trim(end_names(side)) // '_'
         associate (e => d%ends(side))
            r = real(e%pick%phase, wp)
            call io%later(group, p // 'phase', r)
            e%pick%phase = whole(r)
            r = merge(1.0_wp, 0.0_wp, e%on)
            call io%later(group, p // 'on', r)
            e%on = r > 0.5_wp
            call io%later(group, p // 'z', e%z)
            call io%later(group, p // 'x_end', e%x_end)
            call io%later(group, p // 'w0', e%pick%w0)
            call io%later(group, p // 'w_max', e%pick%w_max)
            call io%later(group, p // 't_max', e%pick%t_max)
            call io%later(group, p // 'w_min', e%pick%w_min)
            call io%later(group, p // 't_min', e%pick%t_min)
            call io%later(group, p // 'swing', e%pick%swing)
            call io%later(group, p // 'floor', e%pick%floor)
            r = real(e%node, wp)
            call io%later(group, p // 'node', r)
            e%node = whole(r)
            call io%later(group, p // 'spall_x', e%spall_x)
            call io%later(group, p // 'spall_t', e%spall_t)
            call io%later(group, p // 'scab_v', e%scab_v)
         end associate
      end do
      call io%later(group, 'spl_scale', d%scale)
      r = real(d%n_done, wp)
      call io%later(group, 'imp_ended', r)
      d%n_done = whole(r)
      ! the episodes, open ones first: n_open, then nf values each
      n_first = min(max(d%n_done, 0), first_impacts)
      if (io%writing) then
         call pack_open(d)
         allocate(a(1 + nf * (d%n_open + n_first)))
         a(1) = real(d%n_open, wp)
         do k = 1, d%n_open
            a(2 + nf * (k - 1):1 + nf * k) = packed(d%open(k))
         end do
         do k = 1, n_first
            a(2 + nf * (d%n_open + k - 1):1 + nf * (d%n_open + k)) = packed(d%first(k))
         end do
      end if
      call io%later_reals('impacts', a)
      if (io%writing .or. .not. allocated(a)) return
      if (size(a) < 1) return
      if (allocated(d%n_at)) deallocate(d%n_at, d%slot_at)
      d%n_open = 0
      d%n_ended = 0
      n_open = whole(a(1))
      if (n_open < 0 .or. n_open + n_first /= (size(a) - 1) / nf) then
         d%n_open = -1                     ! damaged: diag_problem says so
         return
      end if
      do k = 1, n_open
         call push(d%open, d%n_open, unpacked(a(2 + nf * (k - 1):1 + nf * k)))
      end do
      do k = 1, n_first
         d%first(k) = unpacked(a(2 + nf * (n_open + k - 1):1 + nf * (n_open + k)))
      end do
   contains
      !> An episode as nf reals.
      pure function packed(e) result(v)
         type(impact_t), intent(in) :: e  !! the episode
         real(wp) :: v(nf)
         v = [real(e%kind, wp), real(e%node, wp), e%t_start, e%t_end, e%x, e%peak, e%impulse, &
              e%v, 0.0_wp, 0.0_wp]
      end function packed
      !> The episode of nf reals.
      pure function unpacked(v) result(e)
         real(wp), intent(in) :: v(nf)    !! the values
         type(impact_t) :: e
         e = impact_t(whole(v(1)), whole(v(2)), v(3), v(4), v(5), v(6), v(7), v(8:11))
      end function unpacked
   end subroutine diag_fields
end module spb_diagnostics
