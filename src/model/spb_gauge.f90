!> Gauges (&gauges, PREFIX.gau): what a strain gauge and a velocity probe at a reference
!> position x of the bar read.
!>
!> At a node (x equal to the node's position to within 1e-9 of its cells' length) the
!> stress is the section stress S of the node ((3.1)-(3.2), doc/method.md, "Section stresses
!> at every node"): the stress a gauge on the section reads; at an end node the support's
!> section stress, or on a free face the load on it (its mean over the step). Strictly
!> inside a cell the stress is the cell's. Velocity and displacement are interpolated
!> linearly between the cell's two nodes, each node by its half on the cell's side.
!>
!> An interior node is read on one side, the gauge's `side` (&gauges side, doc/gauges.md):
!> its upper half A_i ('above') or its lower half B_i ('below'). While the node is joined
!> the two halves move as one and the side changes nothing (but a displacement a gap or a
!> shift put between the halves); once split the gauge reads that side's face: its velocity,
!> its displacement and the stress on it, 0 on a free face and the traction's mean over
!> the step on the faces of an open cohesive crack (the same on both faces).
!>
!> The section stress of an interior node is kept by the step only where a node can break:
!> the nodes gauges read are listed in mesh%watch, which the step keeps as well.
module spb_gauge
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t, node_area
   use spb_ends, only: face_top, face_bottom, has_free_face
   use spb_load, only: load_t
   use spb_state, only: state_t
   use spb_step, only: face_load_integrals
   implicit none
   private
   public :: gauge_t, locate_gauges, watch_gauges, read_gauges

   !> A node is where a gauge is when x is this close to it, in cells.
   real(wp), parameter :: node_tolerance = 1.0e-9_wp

   !> Where one gauge sits in the mesh.
   type :: gauge_t
      real(wp) :: x = 0.0_wp        !! reference position [m]
      integer :: node = -1          !! the node it is on (-1: inside a cell)
      integer :: cell = 0           !! the cell it is in (node gauges: 0)
      real(wp) :: w = 0.0_wp        !! (x - x_{cell-1}) / dx of the cell [-]
      logical :: below = .false.    !! at an interior node: reads the lower half B_i (else
                                    !! the upper half A_i)
   end type gauge_t

contains

   !> The place of each position in the mesh. A position beyond the modelled bar (its
   !> length stretched by fit = 'stretch') reads the end node.
   pure subroutine locate_gauges(mesh, x, gauges, below)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: x(:)         !! reference positions [m]
      type(gauge_t), intent(out) :: gauges(size(x))   !! where they are
      logical, intent(in), optional :: below(:)   !! the side each reads at a node that
                                                  !! splits (not given: above)
      integer :: k, lo, hi, mid, n
      real(wp) :: xk
      n = mesh%n
      do k = 1, size(x)
         xk = min(max(x(k), 0.0_wp), mesh%x(n))
         gauges(k)%x = x(k)
         if (present(below)) gauges(k)%below = below(k)
         ! the cell k with x(k-1) <= xk <= x(k): bisection over the nodes
         lo = 0
         hi = n
         do while (hi - lo > 1)
            mid = (lo + hi) / 2
            if (mesh%x(mid) <= xk) then
               lo = mid
            else
               hi = mid
            end if
         end do
         if (abs(xk - mesh%x(lo)) <= node_tolerance * mesh%dx(lo + 1)) then
            gauges(k)%node = lo
         else if (abs(mesh%x(hi) - xk) <= node_tolerance * mesh%dx(hi)) then
            gauges(k)%node = hi
         else
            gauges(k)%cell = hi
            gauges(k)%w = (xk - mesh%x(lo)) / (mesh%x(hi) - mesh%x(lo))
         end if
      end do
   end subroutine locate_gauges

   !> List the interior nodes the gauges are on in mesh%watch: the step keeps their
   !> section stress (and steps node by node while there are any).
   pure subroutine watch_gauges(mesh, gauges)
      type(mesh_t), intent(inout) :: mesh   !! the mesh (watch list set)
      type(gauge_t), intent(in) :: gauges(:)   !! the gauges
      integer :: k
      allocate(mesh%watch(size(gauges)))
      mesh%n_watch = 0
      do k = 1, size(gauges)
         associate (i => gauges(k)%node)
            if (i <= 0 .or. i >= mesh%n) cycle
            if (any(mesh%watch(1:mesh%n_watch) == i)) cycle
            mesh%n_watch = mesh%n_watch + 1
            mesh%watch(mesh%n_watch) = i
         end associate
      end do
   end subroutine watch_gauges

   !> What the gauges read at the state's time: stress [Pa] (compression > 0), velocity
   !> [m/s] over the step ending there (along +x) and displacement [m] of each.
   pure subroutine read_gauges(mesh, load, st, gauges, stress, velocity, u)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load (a loaded free face)
      type(state_t), intent(in) :: st      !! the state
      type(gauge_t), intent(in) :: gauges(:)   !! the gauges
      real(wp), intent(out) :: stress(:)   !! stress of each gauge [Pa]
      real(wp), intent(out) :: velocity(:) !! velocity of each gauge [m/s]
      real(wp), intent(out) :: u(:)        !! displacement of each gauge [m]
      real(wp) :: q_top, q_bot
      integer :: k, i, c, n
      n = mesh%n
      call face_load_integrals(mesh, load, st%step, st, q_top, q_bot)
      do k = 1, size(gauges)
         i = gauges(k)%node
         c = gauges(k)%cell
         if (i == 0) then
            stress(k) = st%section(0)
            if (has_free_face(st%ends(face_top))) stress(k) = q_top / mesh%dt
            velocity(k) = st%dub(0) / mesh%dt
            u(k) = st%ub(0)
         else if (i == n) then
            stress(k) = st%section(n)
            if (has_free_face(st%ends(face_bottom))) stress(k) = q_bot / mesh%dt
            velocity(k) = st%dua(n) / mesh%dt
            u(k) = st%ua(n)
         else if (i > 0) then
            stress(k) = face_stress(mesh, st, i)
            if (gauges(k)%below) then
               velocity(k) = st%dub(i) / mesh%dt
               u(k) = st%ub(i)
            else
               velocity(k) = st%dua(i) / mesh%dt
               u(k) = st%ua(i)
            end if
         else
            associate (w => gauges(k)%w)
               stress(k) = st%s(c) / mesh%area(c)
               velocity(k) = ((1.0_wp - w) * st%dub(c - 1) + w * st%dua(c)) / mesh%dt
               u(k) = (1.0_wp - w) * st%ub(c - 1) + w * st%ua(c)
            end associate
         end if
         ! the model's stresses are forces A sigma (spb_mesh): over the section's area
         if (i >= 0) stress(k) = stress(k) / node_area(mesh, i)
      end do
   end subroutine read_gauges

   !> The stress on interior node i's section as a gauge on either side reads it (a force,
   !> as the model's stresses): joined, its section stress; split, what acts on its faces:
   !> an open cohesive crack's traction, its mean over the step ending at t (tension < 0),
   !> else nothing (free faces).
   pure real(wp) function face_stress(mesh, st, i) result(s)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! interior node
      s = 0.0_wp
      if (st%joined(i)) then
         s = st%section(i)
      else if (st%coh%on) then
         if (st%coh%active(i)) s = -st%coh%q(i) / mesh%dt
      end if
   end function face_stress
end module spb_gauge
