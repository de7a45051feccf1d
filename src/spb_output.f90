!> Column text outputs (INTERFACE.md): PREFIX.his, PREFIX.prf, PREFIX.evt.
!>
!> Each file starts with '#' header lines (version, title, the full echoed deck, the mesh,
!> units); the last header line names the columns.
module spb_output
   use spb_kinds, only: wp, version
   use spb_error, only: spb_error_t, make_error
   use spb_strings, only: itoa, rtoa
   use spb_deck, only: deck_t, write_echo
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t
   use spb_events, only: event_list_t, event_kind_name
   use spb_diag, only: frag_info_t
   implicit none
   private
   public :: outputs_t, open_outputs, close_outputs, write_history_row, write_profile
   public :: history_columns, write_mesh_summary, write_events, write_fragments

   character(len=*), parameter :: history_columns = 't reaction_bottom reaction_top fragments ' &
      // 'e_kin e_strain e_pot w_ext e_lost momentum step s_end_top s_end_bottom w_load ' &
      // 'w_transmit ledger e_fracture e_join e_shift e_contact i_gravity i_ends i_support p_shift'
   character(len=*), parameter :: history_units = 't [s]; reaction_*, s_end_* [Pa] ' &
      // '(compression > 0); fragments, step [-]; e_*, w_*, ledger [J/m^2]; momentum, i_*, ' &
      // 'p_shift [kg/(m s)] along +x (down)'
   character(len=*), parameter :: event_columns = 't step kind node x stress dt_bound ' &
      // 'dx_bound opening frag_above frag_below stress_bound shift'
   character(len=*), parameter :: fragment_columns = 'id parent birth_t x_top x_bottom mass ' &
      // 'velocity e_vib top_node bottom_node'
   character(len=*), parameter :: fmt_real = 'es20.12e3'
   character(len=*), parameter :: fmt_his = '(3(1x,' // fmt_real // '),1x,i20,6(1x,' // &
      fmt_real // '),1x,i20,13(1x,' // fmt_real // '))'
   character(len=*), parameter :: fmt_evt = '(1x,' // fmt_real // ',1x,i12,1x,a16,1x,i12,' // &
      '5(1x,' // fmt_real // '),2(1x,i12),2(1x,' // fmt_real // '))'
   character(len=*), parameter :: fmt_frg = '(2(1x,i12),6(1x,' // fmt_real // '),2(1x,i12))'
   character(len=*), parameter :: fmt_prf = '(4(1x,' // fmt_real // '))'

   type :: outputs_t
      character(len=:), allocatable :: prefix
      integer :: his = -1, prf = -1, evt = -1, frg = -1   !! units; -1 when closed
   end type outputs_t

contains

   !> Open PREFIX.his, .prf, .evt and write their headers.
   subroutine open_outputs(prefix, deck, mesh, report, out, err)
      character(len=*), intent(in) :: prefix
      type(deck_t), intent(in) :: deck
      type(mesh_t), intent(in) :: mesh
      character(len=*), intent(in) :: report(:)     !! mesh fit report lines
      type(outputs_t), intent(out) :: out
      type(spb_error_t), allocatable, intent(out) :: err
      out%prefix = prefix
      call open_one('.his', out%his)
      if (.not. allocated(err)) call open_one('.prf', out%prf)
      if (.not. allocated(err)) call open_one('.evt', out%evt)
      if (.not. allocated(err)) call open_one('.frg', out%frg)
      if (allocated(err)) then
         call close_outputs(out)
         return
      end if
      call header(out%his, 'history: one row every history_every steps')
      write(out%his, '(a)') '# energies at row time t^{n+1}: e_kin from v^{n+1}, e_strain from' &
         // ' s^n s^{n+1}, e_pot from (u^n+u^{n+1})/2 (the scheme''s invariant, METHOD.md 3)'
      write(out%his, '(a)') '# ledger = e_kin + e_strain + e_pot - w_ext + e_lost is constant; ' &
         // 'w_ext = w_load + w_transmit; e_lost = e_fracture'
      write(out%his, '(a)') '# momentum balance: momentum - momentum(t=0) = i_gravity + i_ends ' &
         // '+ i_support + p_shift (gravity, end stresses, supports/base, collision shifts)'
      write(out%his, '(a)') '# units: ' // history_units
      write(out%his, '(a)') '# ' // history_columns
      call header(out%prf, 'stress profiles: one block per profile time')
      write(out%prf, '(a)') '# rows per half node, top to bottom: node 0 lower half only, ' &
         // 'node n upper half only, others upper then lower half at the same x'
      write(out%prf, '(a)') '# stress is that of the cell the half belongs to; v = du/dt over ' &
         // 'the step ending at t'
      write(out%prf, '(a)') '# units: x [m] (reference position), u [m], v [m/s], stress [Pa] ' &
         // '(compression > 0)'
      write(out%prf, '(a)') '# x u v stress'
      call header(out%evt, 'events: one row per fracture, collision, separation')
      write(out%evt, '(a)') '# t is the grid time the event takes effect; the true time lies in ' &
         // '[t - dt_bound, t] (4.1), the true place within dx_bound of x (4.2)'
      write(out%evt, '(a)') '# frag_above, frag_below: fragment ids on either side after the event ' &
         // '(collision: the merged one and the lower parent)'
      write(out%evt, '(a)') '# opening: fracture: (dA+dB)/2 of the new faces; collision: the ' &
         // 'correction (5.2) of the rule used; stress_bound: (6.2) bound of the collision ' &
         // 'stress error; shift: rigid shift given to one side'
      write(out%evt, '(a)') '# units: t, dt_bound [s]; step, node, frag_* [-]; x, dx_bound, ' &
         // 'opening, shift [m] (x reference); stress, stress_bound [Pa] (compression > 0)'
      write(out%evt, '(a)') '# ' // event_columns
      call header(out%frg, 'fragments: one block per profile time')
      write(out%frg, '(a)') '# x_top, x_bottom: current positions x + u of the faces; e_vib: ' &
         // 'kinetic energy about the mean motion + strain energy; birth_t: time of the ' &
         // 'fracture that made it'
      write(out%frg, '(a)') '# units: birth_t [s]; x_* [m]; mass [kg/m^2]; velocity [m/s]; ' &
         // 'e_vib [J/m^2]; ids and nodes [-]'
      write(out%frg, '(a)') '# ' // fragment_columns
   contains
      subroutine open_one(ext, u)
         character(len=*), intent(in) :: ext
         integer, intent(out) :: u
         integer :: ios
         character(len=256) :: msg
         open(newunit=u, file=prefix // ext, status='replace', action='write', iostat=ios, &
              iomsg=msg)
         if (ios /= 0) then
            u = -1
            call make_error(err, '--output: cannot write ''' // prefix // ext // ''': ' // trim(msg))
         end if
      end subroutine open_one
      subroutine header(u, what)
         integer, intent(in) :: u
         character(len=*), intent(in) :: what
         write(u, '(a)') '# spallbar ' // version // ' -- ' // what
         write(u, '(a)') '# title: ' // trim(deck%run%title)
         call write_echo(u, deck, '# ')
         call write_mesh_summary(u, mesh, report, '# ')
      end subroutine header
   end subroutine open_outputs

   !> The mesh as built: dt, cells, steps, and each segment's cells and lengths.
   subroutine write_mesh_summary(u, mesh, report, prefix)
      integer, intent(in) :: u
      type(mesh_t), intent(in) :: mesh
      character(len=*), intent(in) :: report(:)
      character(len=*), intent(in) :: prefix
      integer :: j
      write(u, '(a)') prefix // 'mesh: dt = ' // rtoa(mesh%dt) // ' s, ' // itoa(mesh%n) // &
         ' cells, ' // itoa(mesh%nsteps) // ' steps to t = ' // &
         rtoa(real(mesh%nsteps, wp) * mesh%dt) // ' s'
      do j = 1, mesh%nseg
         write(u, '(a)') prefix // 'segment ' // itoa(j) // ': cells ' // &
            itoa(mesh%first(j)) // '..' // itoa(mesh%last(j)) // ', dx = a dt = ' // &
            rtoa(mesh%dx(mesh%first(j))) // ' m, a = ' // rtoa(mesh%wave_speed(j)) // &
            ' m/s, Z = ' // rtoa(mesh%impedance(j)) // ' kg/(m^2 s), length ' // &
            rtoa(mesh%length(j)) // ' m (asked ' // rtoa(mesh%length_req(j)) // ')'
      end do
      do j = 1, size(report)
         write(u, '(a)') prefix // 'fit = ''stretch'': ' // trim(report(j))
      end do
   end subroutine write_mesh_summary

   subroutine close_outputs(out)
      type(outputs_t), intent(inout) :: out
      if (out%his >= 0) close(out%his)
      if (out%prf >= 0) close(out%prf)
      if (out%evt >= 0) close(out%evt)
      if (out%frg >= 0) close(out%frg)
      out%frg = -1
      out%his = -1
      out%prf = -1
      out%evt = -1
   end subroutine close_outputs

   !> One history row; values in the order of history_columns.
   subroutine write_history_row(out, t, reaction_bottom, reaction_top, fragments, e_kin, &
                                e_strain, e_pot, w_ext, e_lost, momentum, step, s_end_top, &
                                s_end_bottom, w_load, w_transmit, ledger, e_fracture, e_join, &
                                e_shift, e_contact, i_gravity, i_ends, i_support, p_shift)
      type(outputs_t), intent(in) :: out
      real(wp), intent(in) :: t, reaction_bottom, reaction_top, e_kin, e_strain, e_pot, w_ext
      real(wp), intent(in) :: e_lost, momentum, s_end_top, s_end_bottom, w_load, w_transmit, ledger
      real(wp), intent(in) :: e_fracture, e_join, e_shift, e_contact
      real(wp), intent(in) :: i_gravity, i_ends, i_support, p_shift
      integer, intent(in) :: fragments, step
      write(out%his, fmt_his) t, reaction_bottom, reaction_top, fragments, e_kin, e_strain, &
         e_pot, w_ext, e_lost, momentum, step, s_end_top, s_end_bottom, w_load, w_transmit, &
         ledger, e_fracture, e_join, e_shift, e_contact, i_gravity, i_ends, i_support, p_shift
   end subroutine write_history_row

   !> Rows for the events of the list.
   subroutine write_events(out, events)
      type(outputs_t), intent(in) :: out
      type(event_list_t), intent(in) :: events
      integer :: k
      do k = 1, events%n
         associate (e => events%e(k))
            write(out%evt, fmt_evt) e%t, e%step, event_kind_name(e%kind), e%node, e%x, &
               e%stress, e%dt_bound, e%dx_bound, e%opening, e%frag_above, e%frag_below, &
               e%stress_bound, e%shift
         end associate
      end do
   end subroutine write_events

   !> One block of fragments at time t.
   subroutine write_fragments(out, t, dt, list)
      type(outputs_t), intent(in) :: out
      real(wp), intent(in) :: t, dt
      type(frag_info_t), intent(in) :: list(:)
      integer :: f
      write(out%frg, '(a)') '# t = ' // rtoa(t)
      do f = 1, size(list)
         write(out%frg, fmt_frg) list(f)%id, list(f)%parent, real(list(f)%birth_step, wp) * dt, &
            list(f)%x_top, list(f)%x_bot, list(f)%mass, list(f)%velocity, list(f)%e_vib, &
            list(f)%top, list(f)%bot
      end do
   end subroutine write_fragments

   !> One profile block at the state's time.
   subroutine write_profile(out, mesh, st, t_requested)
      type(outputs_t), intent(in) :: out
      type(mesh_t), intent(in) :: mesh
      type(state_t), intent(in) :: st
      real(wp), intent(in) :: t_requested   !! the profile_times entry [s]
      integer :: i, n
      real(wp) :: dt
      n = mesh%n
      dt = mesh%dt
      write(out%prf, '(a)') '# t = ' // rtoa(real(st%n, wp) * dt)
      write(out%prf, '(a)') '# step ' // itoa(st%n) // ', requested t = ' // rtoa(t_requested)
      do i = 0, n
         if (i > 0) write(out%prf, fmt_prf) mesh%x(i), st%ua(i), st%dua(i) / dt, st%s(i)
         if (i < n) write(out%prf, fmt_prf) mesh%x(i), st%ub(i), st%dub(i) / dt, st%s(i + 1)
      end do
   end subroutine write_profile
end module spb_output
