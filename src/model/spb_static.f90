!> Self-weight equilibrium (2.4) of the lumped-mass bar for the given supports.
!>
!> Supported ends are 'fixed', 'velocity' (a support that moves: the equilibrium is the
!> same in its frame), 'transmit' (a transmitting end continues the bar, so
!> it carries the weight like a support) and the base where the bar starts on it (not where
!> its face moves at t = 0: the base does not touch it then), at either end. With one support the cell stresses follow from
!> the weight carried and the displacements by summing strains from the support; with two
!> the tridiagonal stiffness system is solved.
module spb_static
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: end_t, face_top, face_bottom, has_free_face, has_base
   implicit none
   private
   public :: static_state

contains

   !> Static displacements u(0:n), cell stresses s(1:n) and end stresses [Pa] that the
   !> supports exert (s_top acts on node 0 like a cell above it, s_bot like a cell below).
   pure subroutine static_state(mesh, ends, g, base_holds, u, s, s_top, s_bot)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(end_t), intent(in) :: ends(2)   !! the ends (their kinds)
      real(wp), intent(in) :: g                   !! gravity [m/s^2]
      logical, intent(in) :: base_holds(2)        !! a base end holds the bar at t = 0
                                                  !! (face_top, face_bottom)
      real(wp), intent(out) :: u(0:mesh%n)        !! [m]
      real(wp), intent(out) :: s(1:mesh%n)        !! [Pa], compression positive
      real(wp), intent(out) :: s_top              !! top end stress, as a cell above node 0 [Pa]
      real(wp), intent(out) :: s_bot              !! bottom end stress, as a cell below node n [Pa]
      real(wp) :: m(0:mesh%n), c(mesh%n), d(mesh%n), w
      logical :: top_held, bot_held
      integer :: i, n

      n = mesh%n
      m = mesh%ma + mesh%mb
      top_held = .not. has_free_face(ends(face_top)) .and. &
                 (.not. has_base(ends(face_top)) .or. base_holds(face_top))
      bot_held = .not. has_free_face(ends(face_bottom)) .and. &
                 (.not. has_base(ends(face_bottom)) .or. base_holds(face_bottom))
      if (top_held .and. .not. bot_held) then
         ! node equilibrium s_i - s_{i+1} + m_i g = 0 from the free bottom (s_{n+1} = 0)
         s(n) = -m(n) * g
         do i = n - 1, 1, -1
            s(i) = s(i + 1) - m(i) * g
         end do
         u(0) = 0.0_wp
         do i = 1, n
            u(i) = u(i - 1) - s(i) / mesh%stiff(i)
         end do
      else if (bot_held .and. .not. top_held) then
         s(1) = m(0) * g
         do i = 1, n - 1
            s(i + 1) = s(i) + m(i) * g
         end do
         u(n) = 0.0_wp
         do i = n, 1, -1
            u(i - 1) = u(i) + s(i) / mesh%stiff(i)
         end do
      else if (top_held .and. bot_held) then
         ! -k_i u_{i-1} + (k_i + k_{i+1}) u_i - k_{i+1} u_{i+1} = m_i g, u_0 = u_n = 0 (Thomas)
         u = 0.0_wp
         if (n >= 2) then
            d(1) = mesh%stiff(1) + mesh%stiff(2)
            c(1) = m(1) * g
         end if
         do i = 2, n - 1
            w = mesh%stiff(i) / d(i - 1)
            d(i) = mesh%stiff(i) + mesh%stiff(i + 1) - w * mesh%stiff(i)
            c(i) = m(i) * g + w * c(i - 1)
         end do
         do i = n - 1, 1, -1
            u(i) = (c(i) + mesh%stiff(i + 1) * u(i + 1)) / d(i)
         end do
         do i = 1, n
            s(i) = mesh%stiff(i) * (u(i - 1) - u(i))
         end do
      else
         u = 0.0_wp
         s = 0.0_wp
      end if
      ! what the supports must exert for node 0 and node n to be in equilibrium
      s_top = s(1) - m(0) * g
      s_bot = s(n) + m(n) * g
      if (.not. top_held) s_top = 0.0_wp
      if (.not. bot_held) s_bot = 0.0_wp
   end subroutine static_state
end module spb_static
