!> The history (PREFIX.his, /history in PREFIX.h5; doc/outputs.md): one row every
!> history_every steps, its columns registered by the modules that own the quantities
!> (spb_columns): the state (time, step, reactions, fragments), the energies (spb_diag),
!> the ledger, the ends (end stresses, a striking mass), the wave measure (spb_wave), the
!> cohesive cracks (spb_crack), and here the run's own: gravity's impulse, the wave
!> measure's work, loss and ledger, the largest overlap. history_order is the file's column
!> order, a format archived results depend on; a column registered beyond it follows it.
module spb_history
   use spb_kinds, only: wp
   use spb_columns, only: column_set_t, column_set, add_column
   use spb_mesh, only: mesh_t
   use spb_load, only: load_t
   use spb_state, only: state_t, state_columns_t, register_state_columns, post_state_columns
   use spb_ledger, only: ledger_columns_t, register_ledger_columns, post_ledger_columns
   use spb_ends, only: face_top, face_bottom, has_base, is_striker, striker_energy, end_columns_t, &
      register_end_columns, post_end_columns
   use spb_diag, only: energies_t, energies_columns_t, register_energies_columns, &
      post_energies_columns
   use spb_wave, only: wave_t, wave_energy, wave_columns_t, register_wave_columns, &
      post_wave_columns
   use spb_step, only: face_load_integrals, end_stresses
   use spb_full_mass, only: full_mass_measure
   use spb_crack, only: crack_columns_t, register_crack_columns, post_crack_columns
   implicit none
   private
   public :: history_ids_t, history_order, register_history, history_set, post_history, measure, &
      length_defect

   !> The columns of PREFIX.his and /history in file order (doc/outputs.md): the format of
   !> the files written so far. A new column is registered by its owner and follows these.
   character(len=*), parameter :: history_order(*) = [character(len=16) :: &
      't', 'reaction_bottom', 'reaction_top', 'fragments', 'e_kin', 'e_strain', 'e_pot', &
      'w_ext', 'e_lost', 'momentum', 'step', 's_end_top', 's_end_bottom', 'w_load', &
      'w_transmit', 'ledger', 'e_fracture', 'e_join', 'e_shift', 'e_contact', 'i_gravity', &
      'i_ends', 'i_support', 'p_shift', 'e_wave', 'e_wave_g', 'jordan', 'w_wave', 'e_lost_w', &
      'ledger_w', 'overlap', 'e_cohesive', 'w_cohesive', 'cracks_open', 'x_impactor', &
      'v_impactor', 'f_impactor', 'x_cm', 'x_drift', 'l_defect']

   !> The ids of the history's columns, each owner's in its own type.
   type :: history_ids_t
      type(state_columns_t) :: state
      type(energies_columns_t) :: energies
      type(ledger_columns_t) :: ledger
      type(end_columns_t) :: ends
      type(wave_columns_t) :: wave
      type(crack_columns_t) :: cracks
      integer :: i_gravity = 0, w_wave = 0, e_lost_w = 0, ledger_w = 0, overlap = 0
      integer :: x_cm = 0, x_drift = 0, l_defect = 0
   end type history_ids_t

contains

   !> The history's columns, each registered by its owner, and their ids.
   pure subroutine register_history(set, id)
      type(column_set_t), intent(out) :: set   !! the history's columns, in file order
      type(history_ids_t), intent(out) :: id   !! their ids
      set = column_set(history_order)
      call register_state_columns(set, id%state)
      call register_energies_columns(set, id%energies)
      call register_ledger_columns(set, id%ledger)
      call register_end_columns(set, id%ends)
      call register_wave_columns(set, id%wave)
      call register_crack_columns(set, id%cracks)
      ! the run's own (post_history)
      call add_column(set, id%i_gravity, 'i_gravity', 'kg/(m s)')
      call add_column(set, id%w_wave, 'w_wave', 'J/m^2')
      call add_column(set, id%e_lost_w, 'e_lost_w', 'J/m^2')
      call add_column(set, id%ledger_w, 'ledger_w', 'J/m^2')
      call add_column(set, id%overlap, 'overlap', '-')
      call add_column(set, id%x_cm, 'x_cm', 'm')
      call add_column(set, id%x_drift, 'x_drift', 'm')
      call add_column(set, id%l_defect, 'l_defect', 'm')
   end subroutine register_history

   !> The history's columns, in file order.
   pure function history_set() result(set)
      type(column_set_t) :: set
      type(history_ids_t) :: id
      call register_history(set, id)
   end function history_set

   !> One history row at the state's time: each owner posts its values. e, wv, w_wave,
   !> e_lost_w: the energies and the wave measure of the state (measure).
   pure subroutine post_history(id, mesh, load, st, g, e, wv, w_wave, e_lost_w, row)
      type(history_ids_t), intent(in) :: id   !! the columns' ids (register_history)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(energies_t), intent(in) :: e    !! the scheme's energies (spb_diag)
      type(wave_t), intent(in) :: wv       !! the wave measure
      real(wp), intent(in) :: w_wave       !! work in that measure [J/m^2]
      real(wp), intent(in) :: e_lost_w     !! energy events removed, in that measure [J/m^2]
      real(wp), intent(inout) :: row(:)    !! the row (the set's columns)
      real(wp) :: s_top, s_bot, m_a, m_b, mu_a, mu_b
      call end_stresses(mesh, load, st, s_top, s_bot)
      call mass_sums(mesh, st, m_a, m_b, mu_a, mu_b)
      call post_state_columns(id%state, mesh, st, row)
      call post_energies_columns(id%energies, e, row)
      call post_ledger_columns(id%ledger, st%ledger, row)
      call post_end_columns(id%ends, st%ends, mesh, st%step, s_top, s_bot, row)
      call post_wave_columns(id%wave, wv, row)
      call post_crack_columns(id%cracks, st, row)
      row(id%i_gravity) = g * bar_mass(st, m_a + m_b) * real(st%step, wp) * mesh%dt
      row(id%w_wave) = w_wave
      row(id%e_lost_w) = e_lost_w
      row(id%ledger_w) = wv%e_wave + e%e_pot + wv%e_gravity - w_wave + e_lost_w
      row(id%overlap) = largest_overlap(mesh, st)
      row(id%x_cm) = (mu_a + mu_b) / (m_a + m_b)
      row(id%x_drift) = st%ledger%m_drift / (m_a + m_b)
      row(id%l_defect) = length_defect(mesh, st, e)
   end subroutine post_history

   !> The energy measure of the outputs and the guard: the wave measure (spb_wave) of the
   !> half-mass model; the full-mass comparison model has no continuum reading and keeps the
   !> scheme's own (e_wave = e_kin + e_strain, w_wave = w_ext, e_lost_w = e_lost).
   pure subroutine measure(mesh, load, st, g, e, wv, w_wave, e_lost_w, scale)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(energies_t), intent(in) :: e    !! the scheme's energies (spb_diag)
      type(wave_t), intent(out) :: wv      !! the wave measure (full mass: only e_wave)
      real(wp), intent(out) :: w_wave      !! work in that measure [J/m^2]
      real(wp), intent(out) :: e_lost_w    !! energy events removed, in that measure [J/m^2]
      real(wp), intent(out), optional :: scale   !! the energy guard's scale [J/m^2]
      real(wp) :: q_top, q_bot, e_scale
      if (mesh%full_mass) then
         call full_mass_measure(e, wv, w_wave, e_lost_w, e_scale)
         if (present(scale)) scale = e_scale
         return
      end if
      call face_load_integrals(mesh, load, st%step, st, q_top, q_bot)
      wv = wave_energy(mesh, st, g, q_top, q_bot)
      ! a striking mass's kinetic and cushion energy (its gravity energy is in e_pot)
      if (any(is_striker(st%ends))) wv%e_wave = wv%e_wave + sum(striker_energy(st%ends, 0.0_wp))
      w_wave = st%ledger%w_wave + wv%w_support
      e_lost_w = st%ledger%e_lost_wave
      if (present(scale)) scale = wv%e_wave
   end subroutine measure

   !> The sums of one pass over the half nodes that the centre of mass and the masses take,
   !> each in sum()'s order (the bits of sum(mesh%ma) and the others): the half masses
   !> m_a = sum m_A, m_b = sum m_B and their moments mu_a = sum m_A u_A, mu_b = sum m_B u_B.
   !> The displacement of the bar's centre of mass is (mu_a + mu_b) / (m_a + m_b) [m]: with
   !> the momentum's sum over the steps, the centre-of-mass theorem's
   !> M (X(t) - X(0)) = dt sum p + M x_drift (doc/outputs.md).
   pure subroutine mass_sums(mesh, st, m_a, m_b, mu_a, mu_b)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(out) :: m_a         !! sum of the upper half masses [kg/m^2 A]
      real(wp), intent(out) :: m_b         !! sum of the lower half masses [kg/m^2 A]
      real(wp), intent(out) :: mu_a        !! sum of m_A u_A [kg/m A]
      real(wp), intent(out) :: mu_b        !! sum of m_B u_B [kg/m A]
      integer :: i
      m_a = 0.0_wp
      m_b = 0.0_wp
      mu_a = 0.0_wp
      mu_b = 0.0_wp
      do i = 0, mesh%n
         m_a = m_a + mesh%ma(i)
         m_b = m_b + mesh%mb(i)
         mu_a = mu_a + mesh%ma(i) * st%ua(i)
         mu_b = mu_b + mesh%mb(i) * st%ub(i)
      end do
   end subroutine mass_sums

   !> The cells' length that no stress explains, sum over the cells k of (u_A(k) - u_B(k-1)) +
   !> s_k dx_k / E_k [m]: 0 while every displacement change came with its increment and stress
   !> (the scheme, rigid shifts, redone steps); a correction that moves a face alone (shift =
   !> 'face', a join with both sides held) leaves its amount here (doc/outputs.md). The
   !> full-mass model's cut cells are left out (their length change is an opening). With e,
   !> the energies of this state: the half-mass model's defect summed in their pass.
   pure real(wp) function length_defect(mesh, st, e) result(d)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      type(energies_t), intent(in), optional :: e   !! the state's energies (spb_diag energies)
      integer :: k
      real(wp) :: d_u, d_s
      if (.not. mesh%full_mass .and. present(e)) then
         d = e%defect
         return
      end if
      if (.not. mesh%full_mass) then
         ! the two sums of one pass, each in sum()'s order: the same bits, in half the time
         d_u = 0.0_wp
         d_s = 0.0_wp
         do k = 1, mesh%n
            d_u = d_u + (st%ua(k) - st%ub(k - 1))
            d_s = d_s + st%s(k) / mesh%stiff(k)
         end do
         d = d_u + d_s
         return
      end if
      ! the full-mass model breaks cells, not nodes: a cut cell's length change is its opening
      d = 0.0_wp
      do k = 1, mesh%n
         if (st%fm%is_cut(k)) cycle
         d = d + (st%ua(k) - st%ub(k - 1)) + st%s(k) / mesh%stiff(k)
      end do
   end function length_defect

   !> The mass gravity acts on: the bar's (m_bar) and a striking mass's [kg/m^2 A].
   pure real(wp) function bar_mass(st, m_bar) result(m)
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: m_bar        !! the bar's mass, sum of the half masses [kg/m^2 A]
      m = m_bar
      if (any(is_striker(st%ends))) m = m + sum(st%ends%mass, is_striker(st%ends))
   end function bar_mass

   !> The overlap of the two faces of split node i: at an open cohesive crack minus its own
   !> opening (spb_state cohesive_t: rigid shifts are none), elsewhere ua - ub [m].
   pure real(wp) function face_overlap(st, i) result(d)
      type(state_t), intent(in) :: st      !! the state
      integer, intent(in) :: i             !! split node
      d = st%ua(i) - st%ub(i)
      if (st%coh%on) then
         if (st%coh%active(i)) d = -st%coh%opening(i)
      end if
   end function face_overlap

   !> The largest overlap of two faces at a split node (at an open cohesive crack, of its own
   !> opening below 0), or of an end face and its base, in cells of that node (-1 when
   !> every open face is a cell or more apart, or none is open) [-].
   pure real(wp) function largest_overlap(mesh, st) result(ov)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      integer :: c, i
      ov = -huge(1.0_wp)
      do c = 1, st%n_split
         i = st%split(c)
         ov = max(ov, face_overlap(st, i) / min(mesh%dx(i), mesh%dx(i + 1)))
      end do
      if (has_base(st%ends(face_bottom))) ov = max(ov, (st%ua(mesh%n) - &
         st%ends(face_bottom)%u_contact) / mesh%dx(mesh%n))
      if (has_base(st%ends(face_top))) ov = max(ov, (st%ends(face_top)%u_contact - st%ub(0)) / &
                                                mesh%dx(1))
      ov = max(ov, -1.0_wp)
   end function largest_overlap
end module spb_history
