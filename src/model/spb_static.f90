!> Self-weight equilibrium (2.4) of the lumped-mass bar for the given supports.
!>
!> Supported ends are 'fixed', 'velocity' (a support that moves: the equilibrium is the
!> same in its frame), 'transmit' (a transmitting end continues the bar, so
!> it carries the weight like a support) and the base where the bar starts on it (not where
!> its face moves at t = 0: the base does not touch it then), at either end. With one support the cell stresses follow from
!> the weight carried and the displacements by summing strains from the support; with two
!> the tridiagonal stiffness system is solved.
!>
!> A bar that starts split at dry interfaces (their sides move differently at t = 0, or a
!> static state would pull them) is several bodies, each in the equilibrium of its own
!> supports: a body without one (a hammer touching a pile it moves onto) is in free fall,
!> unstressed. The bodies are placed so that their faces touch (doc/method.md, "Static state").
module spb_static
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_ends, only: end_t, face_top, face_bottom, has_free_face, has_base
   implicit none
   private
   public :: static_state

contains

   !> Static displacements u(0:n), cell stresses s(1:n) and end stresses [Pa] that the
   !> supports exert (s_top acts on node 0 like a cell above it, s_bot like a cell below),
   !> body by body: the bar split at the nodes split (in: where it starts open; out: also the
   !> dry interfaces, nodes dry, whose contact the static state would pull, opened one at a
   !> time, the most pulled first). supported: the node's body has a support (its state is
   !> an equilibrium; else it is unstressed, in free fall).
   pure subroutine static_state(mesh, ends, g, base_holds, dry, stretching, split, u, s, s_top, &
                                s_bot, supported)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(end_t), intent(in) :: ends(2)   !! the ends (their kinds)
      real(wp), intent(in) :: g                   !! gravity [m/s^2]
      logical, intent(in) :: base_holds(2)        !! a base end holds the bar at t = 0
                                                  !! (face_top, face_bottom)
      logical, intent(in) :: dry(0:mesh%n)        !! a dry interface that starts closed
                                                  !! (contact without tensile strength)
      logical, intent(in) :: stretching           !! &initial strain_rate > 0: the bar's
                                                  !! stretching pulls a contact at t = 0 that
                                                  !! the weight does not press
      logical, intent(inout) :: split(0:mesh%n)   !! the bar starts split at the node
      real(wp), intent(out) :: u(0:mesh%n)        !! [m]
      real(wp), intent(out) :: s(1:mesh%n)        !! [Pa], compression positive
      real(wp), intent(out) :: s_top              !! top end stress, as a cell above node 0 [Pa]
      real(wp), intent(out) :: s_bot              !! bottom end stress, as a cell below node n [Pa]
      logical, intent(out) :: supported(0:mesh%n) !! the node's body has a support
      logical :: top_held, bot_held
      real(wp) :: pull, c
      integer :: i, n, worst

      n = mesh%n
      top_held = .not. has_free_face(ends(face_top)) .and. &
                 (.not. has_base(ends(face_top)) .or. base_holds(face_top))
      bot_held = .not. has_free_face(ends(face_bottom)) .and. &
                 (.not. has_base(ends(face_bottom)) .or. base_holds(face_bottom))
      do
         call bodies_static(mesh, g, top_held, bot_held, split, u, s, supported)
         ! the contact force of a closed dry interface, C = s_i + m_a g (the upper half's
         ! equilibrium) where its body is in equilibrium, 0 in free fall; C < 0 pulls, and
         ! C = 0 where the bar is stretched
         worst = 0
         pull = 0.0_wp
         do i = 1, n - 1
            if (.not. dry(i) .or. split(i)) cycle
            c = 0.0_wp
            if (supported(i)) c = s(i) + mesh%ma(i) * g
            if (c < pull .or. (worst == 0 .and. stretching .and. .not. c > 0.0_wp)) then
               pull = min(c, 0.0_wp)
               worst = i
            end if
         end do
         if (worst == 0) exit
         split(worst) = .true.
      end do
      ! what the supports must exert for node 0 and node n to be in equilibrium
      s_top = s(1) - (mesh%ma(0) + mesh%mb(0)) * g
      s_bot = s(n) + (mesh%ma(n) + mesh%mb(n)) * g
      if (.not. top_held) s_top = 0.0_wp
      if (.not. bot_held) s_bot = 0.0_wp
   end subroutine static_state

   !> The static state of every body (the runs of nodes between split nodes), placed so that
   !> the faces at each split node touch: from the top body down, each body moved rigidly to
   !> the face above it, unless only the bottom end supports the bar (then from the bottom
   !> body up), so that a supported body keeps the position its support gives it.
   pure subroutine bodies_static(mesh, g, top_held, bot_held, split, u, s, supported)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity [m/s^2]
      logical, intent(in) :: top_held      !! the top end supports the bar
      logical, intent(in) :: bot_held      !! the bottom end supports the bar
      logical, intent(in) :: split(0:mesh%n)  !! the bar is split at the node
      real(wp), intent(out) :: u(0:mesh%n)    !! [m]
      real(wp), intent(out) :: s(1:mesh%n)    !! [Pa]
      logical, intent(out) :: supported(0:mesh%n)  !! the node's body has a support
      real(wp) :: w(0:mesh%n), shift
      integer :: tops(mesh%n + 1)
      integer :: t, b, n, nb, k, j
      logical :: up

      n = mesh%n
      nb = 0
      do t = 0, n - 1
         if (t == 0 .or. split(t)) then
            nb = nb + 1
            tops(nb) = t
         end if
      end do
      tops(nb + 1) = n
      if (nb == 1) then
         call body_static(mesh, g, 0, n, top_held, bot_held, u, s)
         supported = top_held .or. bot_held
         return
      end if
      up = bot_held .and. .not. top_held
      do j = 1, nb
         k = merge(nb + 1 - j, j, up)
         t = tops(k)
         b = tops(k + 1)
         call body_static(mesh, g, t, b, t == 0 .and. top_held, b == n .and. bot_held, w, s)
         supported(t:b) = (t == 0 .and. top_held) .or. (b == n .and. bot_held)
         if (j == 1) then
            u(t:b) = w(t:b)
         else if (up) then
            shift = u(b) - w(b)
            u(t:b - 1) = w(t:b - 1) + shift
         else
            shift = u(t) - w(t)
            u(t + 1:b) = w(t + 1:b) + shift
         end if
      end do
   end subroutine bodies_static

   !> The static state of one body, nodes top..bot (0 or a split node, n or a split node):
   !> u(top:bot), s(top+1:bot). Held at one end: stresses from the weight carried, positions
   !> summed from the support (0 there); at both: the tridiagonal system (Thomas); at none:
   !> unstressed at rest (a body in free fall).
   pure subroutine body_static(mesh, g, top, bot, top_held, bot_held, u, s)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity [m/s^2]
      integer, intent(in) :: top           !! the body's top node
      integer, intent(in) :: bot           !! the body's bottom node
      logical, intent(in) :: top_held      !! its top end is supported
      logical, intent(in) :: bot_held      !! its bottom end is supported
      real(wp), intent(inout) :: u(0:mesh%n)  !! [m], nodes top..bot set
      real(wp), intent(inout) :: s(1:mesh%n)  !! [Pa], cells top+1..bot set
      real(wp) :: m(0:mesh%n), c(mesh%n), d(mesh%n), w
      integer :: i

      m(top:bot) = mesh%ma(top:bot) + mesh%mb(top:bot)
      if (top > 0) m(top) = mesh%mb(top)
      if (bot < mesh%n) m(bot) = mesh%ma(bot)
      if (top_held .and. .not. bot_held) then
         ! node equilibrium s_i - s_{i+1} + m_i g = 0 from the free bottom (s_{bot+1} = 0)
         s(bot) = -m(bot) * g
         do i = bot - 1, top + 1, -1
            s(i) = s(i + 1) - m(i) * g
         end do
         u(top) = 0.0_wp
         do i = top + 1, bot
            u(i) = u(i - 1) - s(i) / mesh%stiff(i)
         end do
      else if (bot_held .and. .not. top_held) then
         s(top + 1) = m(top) * g
         do i = top + 1, bot - 1
            s(i + 1) = s(i) + m(i) * g
         end do
         u(bot) = 0.0_wp
         do i = bot, top + 1, -1
            u(i - 1) = u(i) + s(i) / mesh%stiff(i)
         end do
      else if (top_held .and. bot_held) then
         ! -k_i u_{i-1} + (k_i + k_{i+1}) u_i - k_{i+1} u_{i+1} = m_i g, u_0 = u_n = 0 (Thomas)
         u(top:bot) = 0.0_wp
         if (bot - top >= 2) then
            d(top + 1) = mesh%stiff(top + 1) + mesh%stiff(top + 2)
            c(top + 1) = m(top + 1) * g
         end if
         do i = top + 2, bot - 1
            w = mesh%stiff(i) / d(i - 1)
            d(i) = mesh%stiff(i) + mesh%stiff(i + 1) - w * mesh%stiff(i)
            c(i) = m(i) * g + w * c(i - 1)
         end do
         do i = bot - 1, top + 1, -1
            u(i) = (c(i) + mesh%stiff(i + 1) * u(i + 1)) / d(i)
         end do
         do i = top + 1, bot
            s(i) = mesh%stiff(i) * (u(i - 1) - u(i))
         end do
      else
         u(top:bot) = 0.0_wp
         s(top + 1:bot) = 0.0_wp
      end if
   end subroutine body_static
end module spb_static
