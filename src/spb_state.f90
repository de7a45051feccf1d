!> The evolving state of the half-node model and its initialisation.
!>
!> Every node i = 0..n has an upper half A_i (cell i above) and a lower half B_i (cell
!> i+1 below). A joined node moves as one mass; a split node's halves move apart. Node
!> arrays hold u and the last increment du = u^n - u^{n-1}; v^n = du/dt is the mean
!> velocity over the step that ends at t^n.
module spb_state
   use spb_kinds, only: wp
   use spb_deck, only: deck_t
   use spb_mesh, only: mesh_t, end_fixed, end_free
   use spb_static, only: static_state
   implicit none
   private
   public :: state_t, init_state, fragment_count

   type :: state_t
      integer :: n = 0                        !! step index: the state is at t^n = n dt
      real(wp), allocatable :: ua(:), ub(:)   !! displacements of the halves (0:n) [m]
      real(wp), allocatable :: dua(:), dub(:) !! last increments (0:n) [m]
      real(wp), allocatable :: s(:)           !! cell stresses s^n (0:n+1); 0 and n+1 hold the
                                              !! end stresses (load, transmitting end) [Pa]
      real(wp), allocatable :: s_old(:)       !! s^{n-1}, same layout [Pa]
      logical, allocatable :: joined(:)       !! node halves move together (0:n)
      real(wp) :: sec_top = 0.0_wp            !! section stress at the top support S^{n-1/2} [Pa]
      real(wp) :: sec_bot = 0.0_wp            !! section stress at the bottom support [Pa]
      real(wp) :: s_static_top = 0.0_wp       !! static stress a transmitting top carries [Pa]
      real(wp) :: s_static_bot = 0.0_wp       !! static stress a transmitting bottom carries [Pa]
      real(wp) :: w_load = 0.0_wp             !! work of the end loads so far [J/m^2]
      real(wp) :: w_transmit = 0.0_wp         !! work of transmitting ends so far [J/m^2]
      real(wp) :: e_lost = 0.0_wp             !! energy removed by events so far [J/m^2]
   end type state_t

contains

   !> Initial state (2.4): unstressed or in self-weight equilibrium, plus segment velocities.
   subroutine init_state(deck, mesh, st)
      type(deck_t), intent(in) :: deck
      type(mesh_t), intent(in) :: mesh
      type(state_t), intent(out) :: st
      integer :: n, j, i, k
      real(wp) :: g, dt, u(0:mesh%n), s(1:mesh%n), v(0:mesh%n), va, vb

      n = mesh%n
      g = deck%run%gravity
      dt = mesh%dt
      allocate(st%ua(0:n), st%ub(0:n), st%dua(0:n), st%dub(0:n))
      allocate(st%s(0:n+1), st%s_old(0:n+1), st%joined(0:n))
      st%joined = .true.
      if (deck%init%state == 'static') then
         call static_state(mesh, g, u, s, st%s_static_top, st%s_static_bot)
      else
         u = 0.0_wp
         s = 0.0_wp
      end if
      ! node velocities: the segment's; at an interface the momentum-weighted mean
      do j = 1, mesh%nseg
         do k = mesh%first(j), mesh%last(j)
            v(k) = deck%seg%velocity(j)
         end do
      end do
      v(0) = deck%seg%velocity(1)
      do j = 1, mesh%nseg - 1
         i = mesh%last(j)
         va = deck%seg%velocity(j)
         vb = deck%seg%velocity(j + 1)
         v(i) = (mesh%ma(i) * va + mesh%mb(i) * vb) * mesh%inv_m(i)
      end do
      if (mesh%top == end_fixed) v(0) = 0.0_wp
      if (mesh%bottom == end_fixed) v(n) = 0.0_wp
      st%ua = u
      st%ub = u
      st%dua = v * dt
      st%dub = v * dt
      st%s = 0.0_wp
      st%s(1:n) = s
      ! s^{-1} = s^0 - E (du_{k-1} - du_k)/dx, for the strain-energy product at the first row
      st%s_old = 0.0_wp
      st%s_old(1:n) = st%s(1:n) - mesh%stiff * (st%dub(0:n-1) - st%dua(1:n))
      ! section stresses at supports start at their fixed point for the initial stresses
      st%sec_top = 0.0_wp
      st%sec_bot = 0.0_wp
      if (mesh%top /= end_free) st%sec_top = s(1) - 0.5_wp * mesh%dm(1) * g
      if (mesh%bottom /= end_free) st%sec_bot = s(n) + 0.5_wp * mesh%dm(n) * g
   end subroutine init_state

   !> Number of fragments: pieces between split interior nodes.
   pure integer function fragment_count(st) result(nf)
      type(state_t), intent(in) :: st
      integer :: n
      n = size(st%joined) - 1
      nf = 1
      if (n >= 2) nf = 1 + count(.not. st%joined(1:n-1))
   end function fragment_count
end module spb_state
