!> A rigid base end in its own numbers (doc/method.md, "A base at either end"): what lets one
!> code serve a base below the bar and one above it. The end node e (0 or n), its end cell c
!> (1 or n), the face half (B_0 at the top, A_n at the bottom) and the sense sgn of the base's
!> side (+1: below the face, along +x; -1: above it). A face penetrates the base by
!> sgn (u_face - u_contact); the region an event moves is the fragment on the base and what it
!> takes along away from it (nodes a..b). Used by the landing and lift-off rules (spb_base)
!> and by the full-mass model's lift-off (spb_full_mass).
module spb_base_face
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: face_top, face_bottom
   use spb_state, only: state_t
   use spb_events, only: event_t, event_list_t, push_event, ev_separation
   use spb_fragments, only: fragment_span
   use spb_problem, only: shift_above
   implicit none
   private
   public :: base_face_t, base_face, face_u, face_du, face_mass, move_base_face, base_fragment, &
      base_ids, lift_off_event, end_order

   !> A base end in its own numbers.
   type :: base_face_t
      integer :: side = face_bottom        !! face_top | face_bottom
      integer :: e = 0                     !! the end node (0 or n)
      integer :: c = 1                     !! the end cell (1 or n)
      real(wp) :: sgn = 1.0_wp             !! +1: the base below the face; -1: above it
   end type base_face_t

contains

   !> The base end of side `side` in its own numbers.
   pure type(base_face_t) function base_face(mesh, side) result(bf)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      integer, intent(in) :: side          !! face_top | face_bottom
      bf%side = side
      if (side == face_top) then
         bf%e = 0
         bf%c = 1
         bf%sgn = -1.0_wp
      else
         bf%e = mesh%n
         bf%c = mesh%n
         bf%sgn = 1.0_wp
      end if
   end function base_face

   !> The face half's displacement (B_0 at the top, A_n at the bottom) [m].
   pure real(wp) function face_u(st, bf)
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      face_u = merge(st%ub(bf%e), st%ua(bf%e), bf%side == face_top)
   end function face_u

   !> The face half's increment over the step [m].
   pure real(wp) function face_du(st, bf)
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      face_du = merge(st%dub(bf%e), st%dua(bf%e), bf%side == face_top)
   end function face_du

   !> The face half's mass [kg/m^2 A].
   pure real(wp) function face_mass(mesh, bf)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(base_face_t), intent(in) :: bf  !! the base end
      face_mass = merge(mesh%mb(bf%e), mesh%ma(bf%e), bf%side == face_top)
   end function face_mass

   !> Move the face half by -d_u and change its increment by -d_du; the other half of the end
   !> node (massless at a base end but in the full-mass model) follows it.
   pure subroutine move_base_face(st, bf, d_u, d_du)
      type(state_t), intent(inout) :: st   !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      real(wp), intent(in) :: d_u          !! taken from the displacement [m]
      real(wp), intent(in) :: d_du         !! taken from the increment [m]
      if (bf%side == face_top) then
         st%ub(bf%e) = st%ub(bf%e) - d_u
         st%dub(bf%e) = st%dub(bf%e) - d_du
         st%ua(bf%e) = st%ub(bf%e)
         st%dua(bf%e) = st%dub(bf%e)
      else
         st%ua(bf%e) = st%ua(bf%e) - d_u
         st%dua(bf%e) = st%dua(bf%e) - d_du
         st%ub(bf%e) = st%ua(bf%e)
         st%dub(bf%e) = st%dua(bf%e)
      end if
   end subroutine move_base_face

   !> The nodes a..b of the fragment resting against the base (all of the bar for 'above').
   pure subroutine base_fragment(mesh, st, bf, policy, a, b)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      integer, intent(in) :: policy        !! shift policy (shift_*); -1: the fragment alone
      integer, intent(out) :: a            !! top node of the region (0 or a split node)
      integer, intent(out) :: b            !! bottom node of the region (n or a split node)
      integer :: j, k
      call fragment_span(mesh, st, bf%e, j, k)
      if (bf%side == face_top) then
         a = 0
         b = k
         if (policy == shift_above) b = mesh%n
      else
         a = j
         b = mesh%n
         if (policy == shift_above) a = 0
      end if
   end subroutine base_fragment

   !> The fragment id of the piece on the base, for an event's frag_above (a base below) or
   !> frag_below (a base above).
   pure subroutine base_ids(st, bf, a, above, below)
      type(state_t), intent(in) :: st      !! the state
      type(base_face_t), intent(in) :: bf  !! the base end
      integer, intent(in) :: a             !! top node of the region the event moved
      integer, intent(out) :: above        !! frag_above
      integer, intent(out) :: below        !! frag_below
      if (bf%side == face_top) then
         above = 0
         below = st%gen%frag_id(0)
      else
         above = st%gen%frag_id(a)
         below = 0
      end if
   end subroutine base_ids

   !> The order in which the two ends are taken when both may act in one step (two bases): the
   !> larger key first (an overlap in cells, a pull), so that a mirrored bar takes them in the
   !> mirrored order; on a tie the bottom first. key(face_top), key(face_bottom).
   pure function end_order(key) result(order)
      real(wp), intent(in) :: key(2)       !! each end's key (-huge: it does not act)
      integer :: order(2)                  !! the sides in the order taken
      order = [face_bottom, face_top]
      if (key(face_top) > key(face_bottom)) order = [face_top, face_bottom]
   end function end_order

   !> The separation event of a face that left its base (after the state has been updated).
   pure subroutine lift_off_event(mesh, st, bf, a, stress, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state after the lift-off
      type(base_face_t), intent(in) :: bf  !! the base end
      integer, intent(in) :: a             !! top node of the fragment that left the base
      real(wp), intent(in) :: stress       !! the base section stress that let it go [Pa]
      type(event_list_t), intent(inout) :: events   !! events of the step (appended)
      type(event_t) :: ev
      ev%kind = ev_separation
      ev%step = st%step
      ev%node = bf%e
      ev%t = real(st%step, wp) * mesh%dt
      ev%x = mesh%x(bf%e)
      ev%stress = stress
      ev%dt_bound = mesh%dt
      ev%dx_bound = 0.0_wp
      ev%opening = bf%sgn * (st%ends(bf%side)%u_contact - face_u(st, bf))
      call base_ids(st, bf, a, ev%frag_above, ev%frag_below)
      call push_event(events, ev)
   end subroutine lift_off_event
end module spb_base_face
