!> The lumped-mass mesh (doc/method.md, "Mesh"): one dt, dx_j = a_j dt, half-node masses.
module spb_mesh
   use spb_kinds, only: wp
   use spb_strings, only: itoa, rtoa
   use spb_problem, only: problem_t, end_free, end_fixed, end_transmit, end_base, end_velocity
   implicit none
   private
   public :: mesh_t, build_mesh, mesh_size, end_free, end_fixed, end_transmit, end_base, &
      end_velocity, node_area
   public :: mesh_fault_t, max_cells, max_steps, fault_none, fault_cells, fault_segment_cells, &
      fault_not_whole, fault_short_segment, fault_mesh_cells, fault_short_run, fault_long_run

   integer, parameter :: max_cells = 50000000   !! refuse meshes larger than this
   integer, parameter :: max_steps = 2000000000 !! refuse runs longer than this
   !> 'strict' accepts a segment when L_j/(a_j dt) is within this relative distance of a
   !> whole number: the representable-length noise of a user's decimal inputs, far below
   !> any physical length change.
   real(wp), parameter :: fit_tolerance = 1.0e-9_wp

   !> Why no mesh serves a problem (fault_none: it was built), with the numbers that say it.
   integer, parameter :: fault_none = 0, fault_cells = 1, fault_segment_cells = 2, &
      fault_not_whole = 3, fault_short_segment = 4, fault_mesh_cells = 5, fault_short_run = 6, &
      fault_long_run = 7
   type :: mesh_fault_t
      integer :: kind = fault_none         !! fault_*
      integer :: segment = 0               !! the segment concerned (0: none)
      real(wp) :: cells = 0.0_wp           !! its cells (continuous), or the mesh's [-]
      real(wp) :: dx = 0.0_wp              !! its a dt [m]
      real(wp) :: dt = 0.0_wp              !! the time step [s]
      real(wp) :: steps = 0.0_wp           !! t_end / dt [-]
   end type mesh_fault_t

   type :: mesh_t
      integer :: nseg = 0                    !! segments
      integer :: n = 0                       !! cells; nodes are 0..n
      real(wp) :: dt = 0.0_wp                !! time step [s]
      integer :: nsteps = 0                  !! steps to reach t_end
      integer :: end_kind(2) = end_free      !! end condition (end_*) of the top and the bottom
                                             !! (face_top, face_bottom): the state's end
                                             !! records take it (spb_ends define_ends)
      real(wp) :: impactor_mass = 0.0_wp     !! a striking mass's M [kg/m^2 A]
      real(wp) :: impactor_cushion = 0.0_wp  !! its cushion's stiffness (0: rigid) [Pa/m A]
      real(wp) :: impactor_gap = 0.0_wp      !! its gap to the face at t = 0 [m]
      real(wp) :: impactor_velocity = 0.0_wp !! its velocity at t = 0 [m/s]
      logical :: full_mass = .false.         !! the paper's naive comparison model (Fig. 12),
                                             !! set with its masses by spb_full_mass
      ! per segment
      integer, allocatable :: first(:), last(:)        !! cell range of each segment
      real(wp), allocatable :: length_req(:)           !! length asked for [m]
      real(wp), allocatable :: length(:)               !! length modelled = cells a dt [m]
      real(wp), allocatable :: wave_speed(:)           !! a_j [m/s]
      real(wp), allocatable :: impedance(:)            !! Z_j = rho_j a_j [kg/(m^2 s)]
      real(wp), allocatable :: seg_area(:)             !! A_j, cross-section area [m^2]
      ! per cell k = 1..n
      integer, allocatable :: seg(:)         !! segment of the cell
      real(wp), allocatable :: dx(:)         !! a_j dt [m]
      real(wp), allocatable :: dm(:)         !! rho_j A_j dx_j = Z_j A_j dt [kg/m^2 A]
      real(wp), allocatable :: z(:)          !! axial impedance Z_j A_j [kg/(m^2 s) A]
      real(wp), allocatable :: stiff(:)      !! axial stiffness E_j A_j / dx_j [Pa/m A]
      real(wp), allocatable :: area(:)       !! A_j of the cell [m^2]: the model's stresses
                                             !! are forces A sigma ('A' in the units above:
                                             !! per unit area when every A_j = 1)
      ! per node i = 0..n
      real(wp), allocatable :: x(:)          !! reference position [m]
      real(wp), allocatable :: ma(:)         !! upper half mass (cell above) [kg/m^2]
      real(wp), allocatable :: mb(:)         !! lower half mass (cell below) [kg/m^2]
      real(wp), allocatable :: inv_m(:)      !! 1/(ma + mb) [m^2/kg]
      real(wp), allocatable :: m_above(:)    !! mass of cells 1..i, sum of dm [kg/m^2]
      ! observation
      integer :: n_watch = 0                 !! interior nodes whose section stress every step
      integer, allocatable :: watch(:)       !! keeps although they cannot break (gauges on
                                             !! them; spb_gauge), first n_watch used
   end type mesh_t

contains

   !> The number of cells of the problem's mesh (0 with a fault), found as build_mesh finds
   !> it but without building anything: what a run needs can be checked before it allocates.
   pure subroutine mesh_size(prob, n, fault)
      type(problem_t), intent(in) :: prob   !! the problem
      integer, intent(out) :: n            !! cells of the mesh (0: fault)
      type(mesh_fault_t), intent(out) :: fault   !! why no mesh (fault_none: it can be built)
      integer, allocatable :: cells(:)
      real(wp) :: dt, steps_real
      call plan_mesh(prob, dt, cells, steps_real, fault)
      n = 0
      if (fault%kind == fault_none) n = sum(cells)
   end subroutine mesh_size

   !> dt, the cells of each segment and t_end / dt of the problem, or its fault.
   pure subroutine plan_mesh(prob, dt, cells, steps_real, fault)
      type(problem_t), intent(in) :: prob   !! the problem
      real(wp), intent(out) :: dt          !! the time step [s]
      integer, allocatable, intent(out) :: cells(:)   !! cells of each segment
      real(wp), intent(out) :: steps_real  !! t_end / dt [-]
      type(mesh_fault_t), intent(out) :: fault   !! why no mesh (fault_none: it can be built)
      integer :: j, nseg, r
      real(wp) :: a(prob%nseg), ncont(prob%nseg)
      nseg = prob%nseg
      allocate(cells(nseg), source=0)
      dt = 0.0_wp
      steps_real = 0.0_wp
      a = sqrt(prob%young / prob%density)
      r = prob%ref_segment
      if (.not. (prob%dt > 0.0_wp) .and. prob%cells > max_cells) then
         fault%kind = fault_cells
         return
      end if
      if (prob%dt > 0.0_wp) then
         dt = prob%dt
      else
         dt = prob%length(r) / (a(r) * real(prob%cells, wp))
      end if
      fault%dt = dt
      ncont = prob%length / (a * dt)
      do j = 1, nseg
         fault%segment = j
         fault%cells = ncont(j)
         fault%dx = a(j) * dt
         if (ncont(j) > real(max_cells, wp)) then
            fault%kind = fault_segment_cells
            return
         end if
         cells(j) = nint(ncont(j))
         if (.not. prob%stretch) then
            if (cells(j) < 1 .or. abs(ncont(j) - real(cells(j), wp)) > &
                fit_tolerance * max(1.0_wp, ncont(j))) then
               fault%kind = fault_not_whole
               return
            end if
         else if (cells(j) < 1) then
            fault%kind = fault_short_segment
            return
         end if
      end do
      fault%segment = 0
      if (sum(int(cells, kind=8)) > max_cells) then
         fault%kind = fault_mesh_cells
         fault%cells = sum(real(cells, wp))
         return
      end if
      steps_real = prob%t_end / dt
      fault%steps = steps_real
      if (steps_real < 0.5_wp) then
         fault%kind = fault_short_run
      else if (steps_real > real(max_steps, wp)) then
         fault%kind = fault_long_run
      end if
   end subroutine plan_mesh

   !> Build the mesh of the problem; report holds one line per stretched segment. A problem
   !> that no mesh can serve comes back as a fault (what and the numbers; the deck module
   !> words it in the deck's terms) and no mesh.
   subroutine build_mesh(prob, mesh, report, fault)
      type(problem_t), intent(in) :: prob   !! the problem
      type(mesh_t), intent(out) :: mesh    !! the mesh
      character(len=200), allocatable, intent(out) :: report(:)   !! length changes (stretch)
      type(mesh_fault_t), intent(out) :: fault   !! why no mesh (fault_none: built)
      integer :: j, nseg, k
      integer, allocatable :: cells(:)
      real(wp), allocatable :: a(:), zz(:)
      real(wp) :: dt, steps_real

      nseg = prob%nseg
      mesh%nseg = nseg
      allocate(report(0))
      a = sqrt(prob%young / prob%density)
      zz = prob%density * a
      if (.not. allocated(prob%area)) then
         mesh%seg_area = [(1.0_wp, j = 1, nseg)]
      else
         mesh%seg_area = prob%area
      end if
      call plan_mesh(prob, dt, cells, steps_real, fault)
      if (fault%kind /= fault_none) return
      mesh%dt = dt
      ! a t_end within round-off of a grid time is that grid time
      mesh%nsteps = max(1, ceiling(steps_real - 1.0e-9_wp))
      mesh%end_kind = [prob%top, prob%bottom]
      mesh%impactor_mass = prob%impactor_mass
      mesh%impactor_cushion = prob%impactor_cushion
      mesh%impactor_gap = prob%impactor_gap
      mesh%impactor_velocity = prob%impactor_velocity
      mesh%n = sum(cells)
      mesh%wave_speed = a
      mesh%impedance = zz
      mesh%length_req = prob%length
      allocate(mesh%first(nseg), mesh%last(nseg), mesh%length(nseg))
      k = 0
      do j = 1, nseg
         mesh%first(j) = k + 1
         k = k + cells(j)
         mesh%last(j) = k
         mesh%length(j) = real(cells(j), wp) * (a(j) * dt)
         if (prob%stretch) then
            report = [character(len=200) :: report, 'segment ' // itoa(j) // ': ' // &
               itoa(cells(j)) // ' cells, length ' // rtoa(mesh%length_req(j)) // ' -> ' // &
               rtoa(mesh%length(j)) // ' m (relative change ' // &
               rtoa(mesh%length(j) / mesh%length_req(j) - 1.0_wp) // ')']
         end if
      end do
      call fill_cells(prob, a, zz, mesh)
   end subroutine build_mesh

   !> The per-cell and per-node arrays of a mesh whose segments' cell ranges and dt are set:
   !> dx = a dt, masses Z A dt, stiffness E A/dx, positions, half masses, cumulative mass.
   !> A bar of cross-sections A_j is the unit-area bar of density rho_j A_j and modulus
   !> E_j A_j (the same wave speed, the axial impedance Z_j A_j): its stresses are the forces
   !> A sigma, its strengths R A and its face loads p A (doc/areas.md).
   pure subroutine fill_cells(prob, a, zz, mesh)
      type(problem_t), intent(in) :: prob   !! the problem
      real(wp), intent(in) :: a(:)            !! wave speed per segment [m/s]
      real(wp), intent(in) :: zz(:)           !! impedance per segment [kg/(m^2 s)]
      type(mesh_t), intent(inout) :: mesh   !! the mesh
      integer :: i, j, k
      real(wp) :: dt
      dt = mesh%dt
      associate (n => mesh%n)
         allocate(mesh%seg(n), mesh%dx(n), mesh%dm(n), mesh%z(n), mesh%stiff(n), mesh%area(n))
         allocate(mesh%x(0:n), mesh%ma(0:n), mesh%mb(0:n), mesh%inv_m(0:n))
         do j = 1, mesh%nseg
            do k = mesh%first(j), mesh%last(j)
               mesh%seg(k) = j
               mesh%dx(k) = a(j) * dt
               mesh%area(k) = mesh%seg_area(j)
               mesh%dm(k) = (zz(j) * mesh%area(k)) * dt
               mesh%z(k) = zz(j) * mesh%area(k)
               mesh%stiff(k) = (prob%young(j) * mesh%area(k)) / mesh%dx(k)
            end do
         end do
         mesh%x(0) = 0.0_wp
         do j = 1, mesh%nseg
            do k = mesh%first(j), mesh%last(j)
               ! positions from the segment start, so each interface sits at its sum of lengths
               mesh%x(k) = mesh%x(mesh%first(j) - 1) + real(k - mesh%first(j) + 1, wp) * mesh%dx(k)
            end do
         end do
         mesh%ma(0) = 0.0_wp
         mesh%mb(n) = 0.0_wp
         do i = 1, n
            mesh%ma(i) = 0.5_wp * mesh%dm(i)
            mesh%mb(i - 1) = 0.5_wp * mesh%dm(i)
         end do
         ! a transmitting end continues the bar: its node carries the half mass of the
         ! virtual cell beyond, so that it moves like an interior node
         if (prob%top == end_transmit) mesh%ma(0) = 0.5_wp * mesh%dm(1)
         if (prob%bottom == end_transmit) mesh%mb(n) = 0.5_wp * mesh%dm(n)
         mesh%inv_m = 1.0_wp / (mesh%ma + mesh%mb)
         allocate(mesh%m_above(0:n))
         mesh%m_above(0) = 0.0_wp
         do k = 1, n
            mesh%m_above(k) = mesh%m_above(k - 1) + mesh%dm(k)
         end do
      end associate
   end subroutine fill_cells

   !> The area of node i's section [m^2]: the narrower of its two cells (an end node: its
   !> cell). A section force over it is the stress there that a break or a gauge reads.
   pure real(wp) function node_area(mesh, i) result(a)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      integer, intent(in) :: i             !! node 0..n
      if (i <= 0) then
         a = mesh%area(1)
      else if (i >= mesh%n) then
         a = mesh%area(mesh%n)
      else
         a = min(mesh%area(i), mesh%area(i + 1))
      end if
   end function node_area
end module spb_mesh
