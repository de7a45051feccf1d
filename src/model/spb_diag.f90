!> Diagnostics: the scheme's own energy invariant, momentum and the energy ledger.
!>
!> With v^{n+1} = du^{n+1}/dt, the discrete energy at t^{n+1/2},
!>   e_kin + e_strain = sum 0.5 m (v^{n+1})^2 + sum 0.5 (dx/E) s^n s^{n+1},
!> changes over a step by exactly the work F^n (u^{n+1} - u^{n-1})/2 of the nodal forces.
!> Gravity's part is -(change of e_pot) with e_pot = -g sum m (u^n + u^{n+1})/2; the end
!> stresses' part is w_ext. So e_kin + e_strain + e_pot - w_ext + e_lost is constant to
!> round-off (doc/method.md, "Energy ledger").
module spb_diag
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t, separates
   use spb_ends, only: face_top, face_bottom, is_striker, striker_momentum
   use spb_columns, only: column_set_t, add_column
   implicit none
   private
   public :: energies_t, energies, frag_info_t, fragment_list
   public :: energies_columns_t, register_energies_columns, post_energies_columns

   type :: energies_t
      real(wp) :: e_kin = 0.0_wp      !! [J/m^2]
      real(wp) :: e_strain = 0.0_wp   !! [J/m^2]
      real(wp) :: e_pot = 0.0_wp      !! gravity potential, zero at u = 0 [J/m^2]
      real(wp) :: w_ext = 0.0_wp      !! work of loads, transmitting and constant-velocity ends
                                      !! [J/m^2]
      real(wp) :: e_lost = 0.0_wp     !! removed by events [J/m^2]
      real(wp) :: ledger = 0.0_wp     !! e_kin + e_strain + e_pot - w_ext + e_lost [J/m^2]
      real(wp) :: momentum = 0.0_wp   !! [kg/(m s)]
      real(wp) :: defect = 0.0_wp     !! the cells' length no stress explains, sum over the
                                      !! cells of (u_A(k) - u_B(k-1)) + s_k / stiff_k, in the
                                      !! same pass (the half-mass model's spb_history
                                      !! length_defect; not a history column of its own) [m]
   end type energies_t

   !> The energies' history columns (PREFIX.his, /history): their ids (spb_columns).
   type :: energies_columns_t
      integer :: e_kin = 0, e_strain = 0, e_pot = 0, w_ext = 0, e_lost = 0, ledger = 0
      integer :: momentum = 0
   end type energies_columns_t

   type :: frag_info_t
      integer :: id = 0, parent = 0, birth_step = 0
      integer :: top = 0, bot = 0          !! end nodes: B_top .. A_bot
      real(wp) :: x_top = 0.0_wp           !! current position of the top face x + u [m]
      real(wp) :: x_bot = 0.0_wp           !! current position of the bottom face [m]
      real(wp) :: mass = 0.0_wp            !! [kg/m^2]
      real(wp) :: velocity = 0.0_wp        !! mean velocity, momentum / mass [m/s]
      real(wp) :: e_vib = 0.0_wp           !! kinetic energy relative to the mean motion plus
                                           !! strain energy [J/m^2]
   end type frag_info_t

contains

   !> Register the energies' history columns (their meaning: doc/outputs.md).
   pure subroutine register_energies_columns(set, id)
      type(column_set_t), intent(inout) :: set   !! the history's columns
      type(energies_columns_t), intent(out) :: id   !! their ids
      call add_column(set, id%e_kin, 'e_kin', 'J/m^2')
      call add_column(set, id%e_strain, 'e_strain', 'J/m^2')
      call add_column(set, id%e_pot, 'e_pot', 'J/m^2')
      call add_column(set, id%w_ext, 'w_ext', 'J/m^2')
      call add_column(set, id%e_lost, 'e_lost', 'J/m^2')
      call add_column(set, id%momentum, 'momentum', 'kg/(m s)')
      call add_column(set, id%ledger, 'ledger', 'J/m^2')
   end subroutine register_energies_columns

   !> Post the energies into a history row.
   pure subroutine post_energies_columns(id, e, row)
      type(energies_columns_t), intent(in) :: id   !! the columns' ids
      type(energies_t), intent(in) :: e            !! the energies (energies)
      real(wp), intent(inout) :: row(:)            !! the row
      row(id%e_kin) = e%e_kin
      row(id%e_strain) = e%e_strain
      row(id%e_pot) = e%e_pot
      row(id%w_ext) = e%w_ext
      row(id%e_lost) = e%e_lost
      row(id%momentum) = e%momentum
      row(id%ledger) = e%ledger
   end subroutine post_energies_columns

   !> The energy terms of the state in the scheme's own measure, and its momentum.
   pure function energies(mesh, st, g) result(e)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g       !! gravity [m/s^2]
      type(energies_t) :: e
      integer :: n
      real(wp) :: dt, s_kin, s_strain, s_pot, s_mom, d_u, d_s
      n = mesh%n
      dt = mesh%dt
      call energy_sums(n, mesh%ma, mesh%mb, st%ua, st%ub, st%dua, st%dub, st%s_old(1:n), &
                       st%s(1:n), mesh%stiff, s_kin, s_pot, s_mom, s_strain, d_u, d_s)
      e%defect = d_u + d_s
      e%e_kin = 0.5_wp * s_kin / dt**2
      e%e_strain = 0.5_wp * s_strain
      e%e_pot = 0.0_wp - g * s_pot
      e%w_ext = st%ledger%w_load + st%ledger%w_transmit + st%ledger%w_support
      e%e_lost = st%ledger%e_fracture + st%ledger%e_join + st%ledger%e_shift + st%ledger%e_contact &
                 + st%ledger%e_traction
      if (any(is_striker(st%ends))) call add_striker(e)
      e%ledger = e%e_kin + e%e_strain + e%e_pot - e%w_ext + e%e_lost
      e%momentum = s_mom / dt
      if (any(is_striker(st%ends))) e%momentum = e%momentum + &
         sum(striker_momentum(st%ends, [face_top, face_bottom]))
   contains
      !> A striking mass's kinetic, gravity and cushion energy (doc/impactor.md), and what its
      !> contact removed from the invariant.
      pure subroutine add_striker(e)
         type(energies_t), intent(inout) :: e   !! the terms so far
         integer :: side
         do side = face_top, face_bottom
            if (.not. is_striker(st%ends(side))) cycle
            associate (m => st%ends(side)%striker, mass => st%ends(side)%mass, &
                       k => st%ends(side)%cushion)
               e%e_kin = e%e_kin + 0.5_wp * mass * m%v**2
               e%e_pot = e%e_pot - g * mass * m%x
               if (m%gap < 0.0_wp) e%e_strain = e%e_strain + 0.5_wp * k * m%gap**2
            end associate
         end do
         e%e_lost = e%e_lost + st%ledger%e_impactor
      end subroutine add_striker
   end function energies

   !> The sums of energies in one pass, each in the order sum() takes (i = 0, 1, ..., n;
   !> the strain's and the length defect's from 1): the same bits as six separate sums of the
   !> arrays, in less time (each sum is a chain of additions; one pass runs the six side by
   !> side, and explicit shapes let the compiler keep the arrays' addresses in registers).
   pure subroutine energy_sums(n, ma, mb, ua, ub, dua, dub, s_old, s, stiff, s_kin, s_pot, &
                               s_mom, s_strain, d_u, d_s)
      integer, intent(in) :: n                 !! cells
      real(wp), intent(in) :: ma(0:n)          !! upper half masses [kg/m^2 A]
      real(wp), intent(in) :: mb(0:n)          !! lower half masses [kg/m^2 A]
      real(wp), intent(in) :: ua(0:n)          !! upper half displacements [m]
      real(wp), intent(in) :: ub(0:n)          !! lower half displacements [m]
      real(wp), intent(in) :: dua(0:n)         !! their increments over the step [m]
      real(wp), intent(in) :: dub(0:n)         !! [m]
      real(wp), intent(in) :: s_old(n)         !! cell stresses at t^n [Pa A]
      real(wp), intent(in) :: s(n)             !! cell stresses at t^{n+1} [Pa A]
      real(wp), intent(in) :: stiff(n)         !! cell stiffnesses [Pa/m A]
      real(wp), intent(out) :: s_kin           !! sum m du^2 [kg m^2/m^2 A]
      real(wp), intent(out) :: s_pot           !! sum m (u - du/2) [kg m/m^2 A]
      real(wp), intent(out) :: s_mom           !! sum m du [kg m/m^2 A]
      real(wp), intent(out) :: s_strain        !! sum s_old s / stiff [J/m^2]
      real(wp), intent(out) :: d_u             !! sum over the cells of u_A(k) - u_B(k-1) [m]
      real(wp), intent(out) :: d_s             !! sum over the cells of s_k / stiff_k [m]
      integer :: i
      s_strain = 0.0_wp
      d_u = 0.0_wp
      d_s = 0.0_wp
      s_kin = 0.0_wp + (ma(0) * dua(0)**2 + mb(0) * dub(0)**2)
      s_pot = 0.0_wp + (ma(0) * (ua(0) - 0.5_wp * dua(0)) + mb(0) * (ub(0) - 0.5_wp * dub(0)))
      s_mom = 0.0_wp + (ma(0) * dua(0) + mb(0) * dub(0))
      do i = 1, n
         s_kin = s_kin + (ma(i) * dua(i)**2 + mb(i) * dub(i)**2)
         s_pot = s_pot + (ma(i) * (ua(i) - 0.5_wp * dua(i)) + mb(i) * (ub(i) - 0.5_wp * dub(i)))
         s_mom = s_mom + (ma(i) * dua(i) + mb(i) * dub(i))
         s_strain = s_strain + s_old(i) * s(i) / stiff(i)
         d_u = d_u + (ua(i) - ub(i - 1))
         d_s = d_s + s(i) / stiff(i)
      end do
   end subroutine energy_sums

   !> Every fragment, top to bottom, with its mass, mean velocity and vibration energy.
   !> Fragments end at a split node (half-node model) or before a cut cell (full-mass model).
   pure subroutine fragment_list(mesh, st, list)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(frag_info_t), allocatable, intent(out) :: list(:)   !! the fragments, top to bottom
      integer :: nf, top, bot, i, f
      logical :: whole_top, whole_bot
      real(wp) :: mom, ekin, estr, dt
      dt = mesh%dt
      nf = 1 + st%fm%n_cut
      do i = 1, mesh%n - 1
         if (separates(st, i)) nf = nf + 1
      end do
      allocate(list(nf))
      top = 0
      whole_top = .true.
      do f = 1, nf
         bot = top
         do
            if (bot == mesh%n) exit
            if (st%fm%is_cut(bot + 1)) exit
            bot = bot + 1
            if (bot == mesh%n) exit
            if (separates(st, bot)) exit
         end do
         whole_bot = bot == mesh%n .or. .not. separates(st, bot)
         list(f)%id = st%gen%frag_id(top)
         list(f)%parent = st%gen%frag_parent(top)
         list(f)%birth_step = st%gen%frag_birth(top)
         list(f)%top = top
         list(f)%bot = bot
         list(f)%x_top = mesh%x(top) + st%ub(top)
         list(f)%x_bot = mesh%x(bot) + st%ua(bot)
         list(f)%mass = 0.0_wp
         mom = 0.0_wp
         ekin = 0.0_wp
         estr = 0.0_wp
         do i = top, bot
            if (i > top .or. whole_top) then
               list(f)%mass = list(f)%mass + mesh%ma(i)
               mom = mom + mesh%ma(i) * st%dua(i) / dt
               ekin = ekin + 0.5_wp * mesh%ma(i) * (st%dua(i) / dt)**2
            end if
            if (i < bot .or. whole_bot) then
               list(f)%mass = list(f)%mass + mesh%mb(i)
               mom = mom + mesh%mb(i) * st%dub(i) / dt
               ekin = ekin + 0.5_wp * mesh%mb(i) * (st%dub(i) / dt)**2
            end if
            if (i > top) estr = estr + 0.5_wp * st%s_old(i) * st%s(i) / mesh%stiff(i)
         end do
         list(f)%velocity = mom / list(f)%mass
         list(f)%e_vib = ekin - 0.5_wp * mom**2 / list(f)%mass + estr
         if (whole_bot) then
            top = bot + 1
            whole_top = .true.
         else
            top = bot
            whole_top = .false.
         end if
      end do
   end subroutine fragment_list
end module spb_diag
