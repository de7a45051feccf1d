!> The two ends of the bar (doc/method.md, "Ends"): one record per end, its kind and what it
!> keeps from step to step, and everything the step, the wave measure and the events ask of
!> an end: the face's stress, the hold of a support, the booking of the end's work and
!> impulse, the support's section stress, and the questions "is it held", "does its face
!> give an equation of the wave measure". The kinds are told apart here and nowhere else
!> in the stepping.
!>
!> Sides are face_top (node 0, end cell 1 below it) and face_bottom (node n, end cell n
!> above it). The kernels take the end node's own numbers (masses, increments, the end
!> cell's impedance), so top and bottom share their code: where a formula differs it is by
!> the side's orientation (the top's face stress pushes node 0 like a cell above it, the
!> bottom's pushes node n like a cell below it).
module spb_ends
   use spb_kinds, only: wp
   use spb_problem, only: face_top, face_bottom, end_free, end_fixed, end_transmit, end_base, &
      end_velocity, end_impactor
   use spb_mesh, only: mesh_t
   use spb_ledger, only: ledger_t
   use spb_section, only: section_stress_a, section_stress_b
   use spb_impactor, only: mass_state_t, mass_step_t, strike_step, mass_energy
   use spb_events, only: event_t, event_list_t, push_event, ev_impact, ev_release
   use spb_field_io, only: field_io_t
   use spb_columns, only: column_set_t, add_column
   implicit none
   private
   public :: end_t, face_step_t, face_top, face_bottom
   public :: transmits, is_velocity_end, is_fixed_end, has_base, on_base, &
      holds, gives_equation, moves_with_bar, support_du, is_striker, has_free_face
   public :: face_stress, face_load_share, hold_face, book_ends, start_end, place_on_base, &
      define_ends, strike, striker_energy, striker_momentum, face_integral, strike_events, &
      striker_fields
   public :: end_columns_t, register_end_columns, post_end_columns

   !> One end of the bar: its kind (end_* of spb_problem) and what the kind keeps from step to
   !> step. The fields a kind does not use stay at their defaults.
   type :: end_t
      integer :: kind = end_free              !! end_free | end_fixed | end_transmit | end_base
                                              !! | end_velocity
      real(wp) :: s_static = 0.0_wp           !! static stress a transmitting end carries [Pa]
      real(wp) :: v_far = 0.0_wp              !! velocity of the bar's continuation beyond a
                                              !! transmitting end: the end's at t = 0 [m/s]
      real(wp) :: v_end = 0.0_wp              !! velocity of a constant-velocity end: its
                                              !! node's at t = 0, kept for the whole run [m/s]
      real(wp) :: w_in = 0.0_wp               !! interval of the wave that came in through a
                                              !! transmitting end over the last step [m]
      logical :: contact = .false.            !! the face rests on the base
      real(wp) :: u_contact = 0.0_wp          !! displacement of the end node at which its face
                                              !! touches the base [m]
      logical :: landing = .false.            !! the next support section stress starts from
      real(wp) :: v_land = 0.0_wp             !! a moving bar half (collision with a support):
                                              !! (3.1) then uses this velocity for v^n and
                                              !! S^{n-1/2} = 0 [m/s]
      ! a striking mass (end_impactor): what it is (define_ends), then its state
      real(wp) :: mass = 0.0_wp               !! its mass M [kg/m^2 A]
      real(wp) :: cushion = 0.0_wp            !! its cushion's stiffness k (0: rigid) [Pa/m A]
      real(wp) :: gap0 = 0.0_wp               !! its gap to the face at t = 0 [m]
      real(wp) :: u_face0 = 0.0_wp            !! the face's displacement at t = 0 (a static
                                              !! start's is not 0) [m]
      real(wp) :: p_ref = 0.0_wp              !! the largest contact stress at stake so far
                                              !! (Z |V|, Z |w|, M |g|, the step means) [Pa A]
      type(mass_state_t) :: striker           !! the mass at t^n: displacement, velocity,
                                              !! contact (spb_impactor)
      real(wp) :: q = 0.0_wp                  !! integral of the contact stress over the step
                                              !! that ends at t^q_step, I [Pa s A]
      real(wp) :: q_before = 0.0_wp           !! the same over the step before it [Pa s A]
      integer :: q_step = 0                   !! that step's end index
      real(wp) :: de_mass = 0.0_wp            !! change of the mass's energy (kinetic, gravity,
                                              !! cushion) over the last step [J/m^2 A]
      type(mass_step_t) :: struck             !! what the last step did (impacts, releases)
   end type end_t

   !> What one step did at one end node: what its end stress's impulse and work, the
   !> support's impulse and the support section stress of the step are booked from.
   type :: face_step_t
      real(wp) :: s = 0.0_wp                  !! end stress of the step, as the cell beyond the
                                              !! end node [Pa]
      real(wp) :: du_old = 0.0_wp             !! increment of the face half (B_0 at the top,
                                              !! A_n at the bottom) before the step [m]
      real(wp) :: du = 0.0_wp                 !! the same after it [m]
      logical :: held = .false.               !! a support held the end node
      real(wp) :: p = 0.0_wp                  !! ma du_A + mb du_B it stopped, relative to the
                                              !! support's V dt (0 at a fixed end) [kg/m]
      real(wp) :: s_cell = 0.0_wp             !! s^n of the end cell [Pa]
      real(wp) :: q = 0.0_wp                  !! integral of the load over the step on that
                                              !! face [Pa s]
      real(wp) :: rho = 0.0_wp                !! zig-zag content at a transmitting end after the
                                              !! step (spb_wave) [m]
   end type face_step_t

   !> The ends' history columns (PREFIX.his, /history): their ids (spb_columns).
   type :: end_columns_t
      integer :: s_end_top = 0, s_end_bottom = 0, x_impactor = 0, v_impactor = 0
      integer :: f_impactor = 0
   end type end_columns_t

contains

   !> A transmitting end: the bar continues beyond it without end.
   elemental logical function transmits(e)
      type(end_t), intent(in) :: e         !! the end
      transmits = e%kind == end_transmit
   end function transmits

   !> A constant-velocity end (Saint-Venant's struck end).
   elemental logical function is_velocity_end(e)
      type(end_t), intent(in) :: e         !! the end
      is_velocity_end = e%kind == end_velocity
   end function is_velocity_end

   !> A fixed end.
   elemental logical function is_fixed_end(e)
      type(end_t), intent(in) :: e         !! the end
      is_fixed_end = e%kind == end_fixed
   end function is_fixed_end

   !> A rigid base the face can rest on, leave and land on again.
   elemental logical function has_base(e)
      type(end_t), intent(in) :: e         !! the end
      has_base = e%kind == end_base
   end function has_base

   !> The face rests on the base.
   elemental logical function on_base(e)
      type(end_t), intent(in) :: e         !! the end
      on_base = e%kind == end_base .and. e%contact
   end function on_base

   !> A support holds the end node (a rigid shift cannot move it): a fixed end, a
   !> constant-velocity end (its position is V t), the base the face rests on.
   elemental logical function holds(e)
      type(end_t), intent(in) :: e         !! the end
      holds = e%kind == end_fixed .or. e%kind == end_velocity .or. on_base(e)
   end function holds

   !> The end face gives an equation of the wave measure (spb_wave): a free face (a striking
   !> mass's contact stress is a load on it), or one off the base (a transmitting end gives
   !> one where spb_wave says so).
   elemental logical function gives_equation(e)
      type(end_t), intent(in) :: e         !! the end
      gives_equation = e%kind == end_free .or. e%kind == end_impactor .or. &
                       (e%kind == end_base .and. .not. e%contact)
   end function gives_equation

   !> The end node moves with the bar next to it from t = 0 (no collision with its support
   !> at t^0): a transmitting or a constant-velocity end.
   elemental logical function moves_with_bar(e)
      type(end_t), intent(in) :: e         !! the end
      moves_with_bar = e%kind == end_transmit .or. e%kind == end_velocity
   end function moves_with_bar

   !> A striking mass acts on the face (spb_impactor).
   elemental logical function is_striker(e)
      type(end_t), intent(in) :: e         !! the end
      is_striker = e%kind == end_impactor
   end function is_striker

   !> The bar's end face is free of any support: a free face, or one a striking mass acts on
   !> through a contact stress (it moves with the bar; its statics is a free end's).
   elemental logical function has_free_face(e)
      type(end_t), intent(in) :: e         !! the end
      has_free_face = e%kind == end_free .or. e%kind == end_impactor
   end function has_free_face

   !> The ends' kinds and what a striking mass is, from the mesh: at the start and when a
   !> checkpoint is read (which holds what the ends keep, not what they are).
   pure subroutine define_ends(ends, mesh)
      type(end_t), intent(inout) :: ends(2)   !! the two ends
      type(mesh_t), intent(in) :: mesh        !! the mesh
      ends%kind = mesh%end_kind
      where (ends%kind == end_impactor)
         ends%mass = mesh%impactor_mass
         ends%cushion = mesh%impactor_cushion
         ends%gap0 = mesh%impactor_gap
      end where
   end subroutine define_ends

   !> The increment a holding support gives its node over a step: V dt at a constant-velocity
   !> end, 0 at a fixed end and on the base [m].
   pure real(wp) function support_du(e, dt) result(du)
      type(end_t), intent(in) :: e         !! the end
      real(wp), intent(in) :: dt           !! time step [s]
      du = 0.0_wp
      if (e%kind == end_velocity) du = e%v_end * dt
   end function support_du

   !> The end's state at t = 0, once its node's velocity v and the static stress s_static it
   !> carries (spb_static) are known: a transmitting end continues the bar without end, and
   !> beyond it the bar keeps the motion its end had at t = 0 (as it keeps the static
   !> stress), so a bar in uniform motion stays in it and no end depends on the frame of
   !> reference; a constant-velocity end keeps the velocity its node starts with. w_in: what
   !> comes in through a transmitting end before any load, the continuation's static stress
   !> and motion.
   pure subroutine start_end(e, side, v, s_static, z, dt)
      type(end_t), intent(inout) :: e      !! the end (its kind set)
      integer, intent(in) :: side          !! face_top | face_bottom
      real(wp), intent(in) :: v            !! the end node's velocity at t = 0 [m/s]
      real(wp), intent(in) :: s_static     !! static stress at the end (spb_static) [Pa]
      real(wp), intent(in) :: z            !! impedance of the end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: dt           !! time step [s]
      e%s_static = s_static
      if (e%kind == end_transmit) e%v_far = v
      if (e%kind == end_velocity) e%v_end = v
      if (side == face_top) then
         e%w_in = 0.5_wp * (e%s_static / z + e%v_far) * dt
      else
         e%w_in = 0.5_wp * (-e%s_static / z + e%v_far) * dt
      end if
   end subroutine start_end

   !> The base beyond an end face at t = 0 (below the bottom, above the top), gap away from
   !> it: touching and at rest, the face rests on it; moving onto it, the first step lands by
   !> the timing rule (and logs the event); moving away from it, not in contact. A face at
   !> rest on it has no increment.
   pure subroutine place_on_base(e, side, u_face, gap, du_face)
      type(end_t), intent(inout) :: e      !! the end (a base)
      integer, intent(in) :: side          !! face_top | face_bottom
      real(wp), intent(in) :: u_face       !! the face half's displacement at t = 0 [m]
      real(wp), intent(in) :: gap          !! the gap between the face and the base [m]
      real(wp), intent(inout) :: du_face   !! the face half's increment du^0 [m]
      e%u_contact = u_face + merge(-gap, gap, side == face_top)
      e%contact = gap <= 0.0_wp .and. .not. (abs(du_face) > 0.0_wp)
      if (e%contact) du_face = 0.0_wp
   end subroutine place_on_base

   !> The stress acting on the end face at t^n, as the cell beyond the end node: the stepwise
   !> load P^n on a loaded free face; at a transmitting end the static stress it carries, the
   !> radiation stress of the outgoing wave and, when the load acts on that end, 2 P^n for
   !> the incident wave of stress p(t) arriving through it; 0 otherwise. At Courant 1,
   !> u = F(t - x/a) + G(t + x/a): the virtual cell beyond node 0 has s_0 = -(E/dx) du_0^n
   !> (outgoing G) + (E/dx) [F(n+1) - F(n-1)] = 2 P^n (incident F); the bottom is its mirror.
   pure real(wp) function face_stress(e, side, p, loaded, stiff, du_face, dt) result(s)
      type(end_t), intent(in) :: e         !! the end
      integer, intent(in) :: side          !! face_top | face_bottom
      real(wp), intent(in) :: p            !! the stepwise load P^n [Pa]
      logical, intent(in) :: loaded        !! the load acts on this face
      real(wp), intent(in) :: stiff        !! stiffness E A / dx of the end cell [Pa/m A]
      real(wp), intent(in) :: du_face      !! the face half's increment du^n [m]
      real(wp), intent(in) :: dt           !! time step [s]
      s = 0.0_wp
      select case (e%kind)
      case (end_free)
         if (loaded) s = p
      case (end_transmit)
         if (side == face_top) then
            s = e%s_static - stiff * (du_face - e%v_far * dt)
         else
            s = e%s_static + stiff * (du_face - e%v_far * dt)
         end if
         if (loaded) s = s + 2.0_wp * p
      case (end_impactor)
         ! the stepwise form of the contact stress over the last two steps (strike)
         s = 0.5_wp * (e%q_before + e%q) / dt
      case default
         ! the other ends take no part here
      end select
   end function face_stress

   !> The integral of the face stress over the step that ends at t^step on a face whose
   !> load works on the continuum state: a loaded free face's load integral q, a striking
   !> mass's contact stress [Pa s].
   pure real(wp) function face_integral(e, q, loaded, step) result(i_face)
      type(end_t), intent(in) :: e         !! the end
      real(wp), intent(in) :: q            !! the load's integral over that step [Pa s]
      logical, intent(in) :: loaded        !! the load acts on this face
      integer, intent(in) :: step          !! the step's end index
      if (e%kind == end_impactor) then
         i_face = 0.0_wp
         if (step == e%q_step) then
            i_face = e%q
         else if (step == e%q_step - 1) then
            i_face = e%q_before
         end if
      else
         i_face = face_load_share(e, q, loaded)
      end if
   end function face_integral

   !> The striking mass's step (spb_impactor strike_step) from t^n, before the lattice's: the
   !> face, left alone, would move at w over it, the rate of the lattice's free update (what
   !> the step brings to the face: its increment du^n, the end cell's stress s^n, the
   !> contact integral of the step before, gravity); the contact integral I^{n+1} found
   !> makes the face's stress (I^n + I^{n+1}) / (2 dt) (face_stress), with which the
   !> lattice's update moves the face by w dt + sigma I^{n+1} / Z: the mass's own motion
   !> (doc/impactor.md). u_face: the face's displacement at t^n (the gap follows from it).
   pure subroutine strike(e, side, step, u_face, du_face, s_cell, z, g, dt)
      type(end_t), intent(inout) :: e      !! the end (a striking mass)
      integer, intent(in) :: side          !! face_top | face_bottom
      integer, intent(in) :: step          !! the step index n (the step from t^n)
      real(wp), intent(in) :: u_face       !! the face half's displacement u^n [m]
      real(wp), intent(in) :: du_face      !! its increment du^n [m]
      real(wp), intent(in) :: s_cell       !! stress of the end cell s^n [Pa A]
      real(wp), intent(in) :: z            !! impedance of the end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      real(wp), intent(in) :: dt           !! time step [s]
      real(wp) :: sigma, w, e0
      sigma = merge(1.0_wp, -1.0_wp, side == face_top)
      ! the gap is measured from where the face is at t = 0, as the first step finds it
      if (step == 0) e%u_face0 = u_face
      w = (du_face + sigma * (e%q - 2.0_wp * s_cell * dt) / z + g * dt**2) / dt
      if (.not. (e%striker%touching .and. .not. (e%cushion > 0.0_wp))) then
         e%striker%gap = e%gap0 + sigma * ((u_face - e%u_face0) - e%striker%x)
      end if
      e0 = mass_energy(e%striker, e%mass, e%cushion, g)
      e%p_ref = max(e%p_ref, z * abs(e%striker%v), z * abs(w), e%mass * abs(g))
      call strike_step(e%striker, e%mass, e%cushion, z, g, sigma, w, dt, e%p_ref, e%struck)
      e%p_ref = max(e%p_ref, abs(e%struck%q) / dt)
      e%de_mass = mass_energy(e%striker, e%mass, e%cushion, g) - e0
      e%q_before = e%q
      e%q = e%struck%q
      e%q_step = step + 1
   end subroutine strike

   !> The events of a striking mass's last step (strike), in time order: its first impact
   !> and its first release within the step, at their exact times (dt_bound 0); stress: the
   !> contact stress Z v an impact starts with (rigid contact; 0 through a cushion).
   pure subroutine strike_events(e, step, node, x, z, dt, frag, events)
      type(end_t), intent(in) :: e         !! the end (a striking mass after its step)
      integer, intent(in) :: step          !! the step index n (the step from t^n)
      integer, intent(in) :: node          !! the face's node
      real(wp), intent(in) :: x            !! its reference position [m]
      real(wp), intent(in) :: z            !! impedance of the end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: dt           !! time step [s]
      integer, intent(in) :: frag          !! id of the fragment struck
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      type(event_t) :: ev(2)
      integer :: k, m
      if (e%kind /= end_impactor) return
      m = 0
      if (e%struck%t_impact >= 0.0_wp) then
         m = m + 1
         ev(m)%kind = ev_impact
         ev(m)%t = e%struck%t_impact
         if (.not. (e%cushion > 0.0_wp)) ev(m)%stress = z * e%struck%v_impact
      end if
      if (e%struck%t_release >= 0.0_wp) then
         m = m + 1
         ev(m)%kind = ev_release
         ev(m)%t = e%struck%t_release
      end if
      ! in time order (an impact and a release at the same instant: the impact first)
      if (m == 2) then
         if (ev(2)%t < ev(1)%t) ev = ev(2:1:-1)
      end if
      do k = 1, m
         ev(k)%step = step
         ev(k)%node = node
         ev(k)%t = real(step, wp) * dt + ev(k)%t
         ev(k)%x = x
         ev(k)%frag_above = frag
         call push_event(events, ev(k))
      end do
   end subroutine strike_events

   !> Register the ends' history columns: the stresses on the end faces, a striking mass's
   !> displacement, velocity and contact force (their meaning: doc/outputs.md).
   pure subroutine register_end_columns(set, id)
      type(column_set_t), intent(inout) :: set   !! the history's columns
      type(end_columns_t), intent(out) :: id     !! their ids
      call add_column(set, id%s_end_top, 's_end_top', 'Pa')
      call add_column(set, id%s_end_bottom, 's_end_bottom', 'Pa')
      call add_column(set, id%x_impactor, 'x_impactor', 'm')
      call add_column(set, id%v_impactor, 'v_impactor', 'm/s')
      call add_column(set, id%f_impactor, 'f_impactor', 'N/m^2')
   end subroutine register_end_columns

   !> Post the ends' values into a history row at step: the end faces' stresses, and a
   !> striking mass's displacement from its start, its velocity, and the contact force's
   !> mean over the last step (N, or Pa when every area is 1); 0 without one.
   pure subroutine post_end_columns(id, ends, mesh, step, s_top, s_bot, row)
      type(end_columns_t), intent(in) :: id   !! the columns' ids
      type(end_t), intent(in) :: ends(2)      !! the top and the bottom end
      type(mesh_t), intent(in) :: mesh        !! the mesh
      integer, intent(in) :: step             !! the row's step
      real(wp), intent(in) :: s_top           !! stress on the top face at the row's time [Pa A]
      real(wp), intent(in) :: s_bot           !! the same on the bottom face [Pa A]
      real(wp), intent(inout) :: row(:)       !! the row
      integer :: side
      row(id%s_end_top) = s_top / mesh%area(1)
      row(id%s_end_bottom) = s_bot / mesh%area(mesh%n)
      row(id%x_impactor) = 0.0_wp
      row(id%v_impactor) = 0.0_wp
      row(id%f_impactor) = 0.0_wp
      do side = face_top, face_bottom
         if (.not. is_striker(ends(side))) cycle
         row(id%x_impactor) = ends(side)%striker%x
         row(id%v_impactor) = ends(side)%striker%v
         if (ends(side)%q_step == step) row(id%f_impactor) = ends(side)%q / mesh%dt
      end do
   end subroutine post_end_columns

   !> What a striking mass keeps from step to step, as checkpoint fields (the one list, for
   !> writing and reading back; a run without a striking mass has none of them).
   subroutine striker_fields(e, side, io)
      type(end_t), intent(inout) :: e      !! the end (a striking mass)
      integer, intent(in) :: side          !! face_top | face_bottom
      class(field_io_t), intent(inout) :: io   !! the checkpoint file
      character(len=:), allocatable :: at
      integer :: touching
      at = merge('striker_top', 'striker_bot', side == face_top) // '_'
      call io%field('/state', at // 'x', e%striker%x)
      call io%field('/state', at // 'v', e%striker%v)
      call io%field('/state', at // 'gap', e%striker%gap)
      touching = merge(1, 0, e%striker%touching)
      call io%field('/state', at // 'touching', touching)
      e%striker%touching = touching == 1
      call io%field('/state', at // 'q', e%q)
      call io%field('/state', at // 'q_before', e%q_before)
      call io%field('/state', at // 'q_step', e%q_step)
      call io%field('/state', at // 'u_face0', e%u_face0)
      call io%field('/state', at // 'p_ref', e%p_ref)
   end subroutine striker_fields

   !> Kinetic, gravity and cushion energy of a striking mass (0 for another end) [J/m^2 A].
   elemental real(wp) function striker_energy(e, g) result(en)
      type(end_t), intent(in) :: e         !! the end
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      en = 0.0_wp
      if (e%kind == end_impactor) en = mass_energy(e%striker, e%mass, e%cushion, g)
   end function striker_energy

   !> A striking mass's momentum on the lattice's footing: M V + sigma I/2 with I the
   !> contact integral of the last step (sigma = +1 at the top, -1 at the bottom), so that
   !> with the bar's momentum (the mean over the last step) it changes by the external
   !> impulses only (doc/impactor.md) [kg/(m s) A].
   elemental real(wp) function striker_momentum(e, side) result(p)
      type(end_t), intent(in) :: e         !! the end
      integer, intent(in) :: side          !! face_top | face_bottom
      p = 0.0_wp
      if (e%kind == end_impactor) p = e%mass * e%striker%v + &
                                      merge(0.5_wp, -0.5_wp, side == face_top) * e%q
   end function striker_momentum

   !> The load integral q over a step as it works on the face's continuum state: all of it
   !> on a loaded free face, none elsewhere [Pa s].
   pure real(wp) function face_load_share(e, q, loaded) result(i_face)
      type(end_t), intent(in) :: e         !! the end
      real(wp), intent(in) :: q            !! the load's integral over the step [Pa s]
      logical, intent(in) :: loaded        !! the load acts on this face
      i_face = 0.0_wp
      if (loaded .and. e%kind == end_free) i_face = q
   end function face_load_share

   !> A holding support stops the end node (a fixed end, the base it rests on) or moves it by
   !> V dt (a constant-velocity end); the momentum it takes, what the node would have had
   !> beyond m V, is recorded in f.
   pure subroutine hold_face(e, ma, mb, dt, dua, dub, f)
      type(end_t), intent(in) :: e         !! the end
      real(wp), intent(in) :: ma           !! the end node's upper half mass [kg/m^2 A]
      real(wp), intent(in) :: mb           !! its lower half mass [kg/m^2 A]
      real(wp), intent(in) :: dt           !! time step [s]
      real(wp), intent(inout) :: dua       !! its upper half's increment of the step [m]
      real(wp), intent(inout) :: dub       !! its lower half's [m]
      type(face_step_t), intent(inout) :: f   !! the step's record of this end (held, p)
      real(wp) :: du
      f%held = holds(e)
      if (f%held) then
         du = support_du(e, dt)
         f%p = ma * (dua - du) + mb * (dub - du)
         dua = du
         dub = du
      end if
   end subroutine hold_face

   !> The end nodes' part of one step, in the order the step makes it: impulse of the end
   !> stresses and of the supports, work of the end stresses (on the scheme's and on the
   !> continuum state), section stresses at the supports. z, dm: the end cells' impedance
   !> and mass.
   pure subroutine book_ends(ends, f, z, dm, g, dt, ledger, section)
      type(end_t), intent(inout) :: ends(2)     !! the two ends
      type(face_step_t), intent(in) :: f(2)     !! what the step did at each end node
      real(wp), intent(in) :: z(2)              !! impedance of each end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: dm(2)             !! mass of each end cell [kg/m^2 A]
      real(wp), intent(in) :: g                 !! gravity along +x [m/s^2]
      real(wp), intent(in) :: dt                !! time step [s]
      type(ledger_t), intent(inout) :: ledger   !! the run's balances
      real(wp), intent(inout) :: section(2)     !! section stress of each end node [Pa]
      real(wp) :: w, s_ext(2)
      integer :: side
      ! momentum balance: the end stresses act on the end nodes, supports take what reaches
      ! them; a striking mass's contact stress is internal (the mass's momentum is counted,
      ! striker_momentum)
      s_ext = f%s
      where (ends%kind == end_impactor) s_ext = 0.0_wp
      ledger%i_ends = ledger%i_ends + (s_ext(face_top) - s_ext(face_bottom)) * dt
      do side = face_top, face_bottom
         if (f(side)%held) ledger%i_support = ledger%i_support - f(side)%p / dt
      end do
      ! work of the end stresses over the step: F^n (u^{n+1} - u^{n-1}) / 2, which keeps
      ! the discrete energy ledger exact
      do side = face_top, face_bottom
         if (side == face_top) then
            w = f(side)%s * 0.5_wp * (f(side)%du + f(side)%du_old)
         else
            w = -f(side)%s * 0.5_wp * (f(side)%du + f(side)%du_old)
         end if
         if (ends(side)%kind == end_transmit) then
            ledger%w_transmit = ledger%w_transmit + w
         else if (ends(side)%kind == end_impactor) then
            ! a striking mass: no external work; what the mass lost (-de_mass, exact) beyond
            ! what the bar gained (w, the scheme's product) is removed in the scheme's measure
            ledger%e_impactor = ledger%e_impactor - (w + ends(side)%de_mass)
         else
            ledger%w_load = ledger%w_load + w
         end if
      end do
      ! a constant-velocity end's support force -p/dt^2 does the same product (its node moves
      ! by V dt in both steps); in the continuum reading its work over the step is V times
      ! the impulse the continuum's end section takes, -p/dt + Z (f^{n+1} - f^n) (f the
      ! interval the support sends into the bar): the first part is booked here, the second
      ! is a function of the reading at t^{n+1} (spb_wave, wave_t%w_support; doc/method.md)
      do side = face_top, face_bottom
         if (ends(side)%kind /= end_velocity) cycle
         ledger%w_support = ledger%w_support - f(side)%p / dt**2 * 0.5_wp * &
                            (f(side)%du + f(side)%du_old)
         ledger%w_wave = ledger%w_wave - ends(side)%v_end * f(side)%p / dt
      end do
      ! the same work on the continuum state (spb_wave): I du / dt at a free loaded face; at a
      ! transmitting end the energy the incoming wave (the static stress carried and the
      ! incident load) brings minus what the outgoing one takes, Z du (2 w - du) / dt, w the
      ! incoming interval: w_in, plus under gravity the fragment's zig-zag content rho
      do side = face_top, face_bottom
         select case (ends(side)%kind)
         case (end_free)
            if (side == face_top) then
               ledger%w_wave = ledger%w_wave + f(side)%q * f(side)%du / dt
            else
               ledger%w_wave = ledger%w_wave - f(side)%q * f(side)%du / dt
            end if
         case (end_transmit)
            if (side == face_top) then
               ends(side)%w_in = (0.5_wp * ends(side)%s_static * dt + f(side)%q) / z(side) + &
                                 0.5_wp * ends(side)%v_far * dt
            else
               ends(side)%w_in = -(0.5_wp * ends(side)%s_static * dt + f(side)%q) / z(side) + &
                                 0.5_wp * ends(side)%v_far * dt
            end if
            ledger%w_wave = ledger%w_wave + z(side) * f(side)%du * &
                            (2.0_wp * (ends(side)%w_in + f(side)%rho) - f(side)%du) / dt
         case (end_impactor)
            ! the bar's continuum state gains I du / dt from the contact stress (as from a
            ! load, I = the step's contact integral); the mass lost -de_mass (exact): the
            ! difference, the contact stress's variance over the step times dt / Z >= 0, is
            ! what the step's piecewise-constant reading cannot carry (doc/impactor.md)
            if (side == face_top) then
               w = ends(side)%q * f(side)%du / dt
            else
               w = -ends(side)%q * f(side)%du / dt
            end if
            ledger%e_lost_wave = ledger%e_lost_wave - (w + ends(side)%de_mass)
         case default
            ! the other ends take no part here
         end select
      end do
      call support_sections(ends, f, z, dm, g, dt, section)
   end subroutine book_ends

   !> Section stresses at the supports, (3.1)-(3.2) with s^n and v^n, v^{n+1}: the end of
   !> book_ends. A support just hit by a moving half starts from that half's velocity. (The
   !> full-mass model has no section stresses: spb_full_mass full_mass_supports.)
   pure subroutine support_sections(ends, f, z, dm, g, dt, section)
      type(end_t), intent(inout) :: ends(2)     !! the two ends
      type(face_step_t), intent(in) :: f(2)     !! what the step did at each end node
      real(wp), intent(in) :: z(2)              !! impedance of each end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: dm(2)             !! mass of each end cell [kg/m^2 A]
      real(wp), intent(in) :: g                 !! gravity along +x [m/s^2]
      real(wp), intent(in) :: dt                !! time step [s]
      real(wp), intent(inout) :: section(2)     !! section stress of each end node [Pa]
      real(wp) :: du_old(2)
      integer :: side
      do side = face_top, face_bottom
         du_old(side) = f(side)%du_old
         if (ends(side)%landing) du_old(side) = ends(side)%v_land * dt
      end do
      ends%landing = .false.
      do side = face_top, face_bottom
         select case (ends(side)%kind)
         case (end_fixed)
            section(side) = support_form(side, f(side)%s_cell, section(side), du_old(side) / dt, &
                                         0.0_wp, z(side), dm(side), g)
         case (end_transmit, end_velocity)
            section(side) = support_form(side, f(side)%s_cell, section(side), du_old(side) / dt, &
                                         f(side)%du / dt, z(side), dm(side), g)
         case (end_base)
            ! resting on the rigid base: the base side does not move; v^n is the face half's
            ! velocity before the step (0 while it rests)
            if (ends(side)%contact) then
               section(side) = support_form(side, f(side)%s_cell, section(side), &
                                            du_old(side) / dt, 0.0_wp, z(side), dm(side), g)
            else
               section(side) = 0.0_wp
            end if
         case default
            ! the other ends take no part here
         end select
      end do
   end subroutine support_sections

   !> The section stress (3.1)-(3.2) at an end node from its end cell: the B form (the cell
   !> below) at the top, the A form (the cell above) at the bottom.
   pure real(wp) function support_form(side, s_cell, s_prev, v_n, v_np1, z, dm, g) result(s_new)
      integer, intent(in) :: side          !! face_top | face_bottom
      real(wp), intent(in) :: s_cell       !! stress of the end cell at t^n [Pa]
      real(wp), intent(in) :: s_prev       !! section stress S^{n-1/2} [Pa]
      real(wp), intent(in) :: v_n          !! the face half's velocity v^n [m/s]
      real(wp), intent(in) :: v_np1        !! the node's velocity v^{n+1} [m/s]
      real(wp), intent(in) :: z            !! impedance of the end cell [kg/(m^2 s) A]
      real(wp), intent(in) :: dm           !! mass of the end cell [kg/m^2 A]
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      if (side == face_top) then
         s_new = section_stress_b(s_cell, s_prev, v_n, v_np1, z, dm, g)
      else
         s_new = section_stress_a(s_cell, s_prev, v_n, v_np1, z, dm, g)
      end if
   end function support_form
end module spb_ends
