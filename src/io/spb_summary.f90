!> The run summary: what a run reports at its end and carries from step to step (the
!> energy guard's reference and scale among it). This module owns all of it: the type, its
!> updates (called by the run loop, spb_sim, where the values are known), the one list of
!> what a checkpoint keeps of it (summary_fields, written and read back through a
!> field_io_t, the checkpoint's file: doc/outputs.md `/run`) and the end-of-run text.
module spb_summary
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use spb_kinds, only: wp
   use spb_strings, only: itoa
   use spb_field_io, only: field_io_t
   use spb_diag, only: energies_t, frag_info_t
   use spb_wave, only: wave_t
   use spb_events, only: event_list_t, ev_fracture, event_kinds, n_event_kinds
   use spb_diagnostics, only: diag_t, diag_fields, spall_row, impact_row, end_names, &
      imp_kind_names, first_impacts
   implicit none
   private
   public :: run_summary_t, first_fractures, summary_start, summary_row, summary_guard
   public :: summary_reaction, summary_events, summary_checkpoint, summary_end
   public :: summary_fields, summary_problem, write_summary

   integer, parameter :: first_fractures = 5   !! fractures the run summary keeps

   !> What a run reports and carries from step to step (a restart file keeps it).
   type :: run_summary_t
      integer :: steps = 0
      integer :: events = 0                !! events written
      real(wp) :: wall = 0.0_wp            !! [s]
      real(wp) :: ledger0 = 0.0_wp         !! ledger at t = 0 [J/m^2]
      real(wp) :: ledger_drift = 0.0_wp    !! largest |ledger - ledger0| over rows [J/m^2]
      real(wp) :: energy_scale = 0.0_wp    !! largest energy term seen [J/m^2]
      real(wp) :: max_excess = 0.0_wp      !! largest (E - E0) - w_ext, relative to the guard's
                                           !! scale [-]
      integer :: n_kind(n_event_kinds) = 0 !! events by kind (spb_events event_kinds)
      real(wp) :: first_fracture_t = -1.0_wp   !! time of the first fracture; -1: none [s]
      real(wp) :: max_reaction_bottom = 0.0_wp !! largest section stress at the bottom node
                                               !! over all steps (compression > 0) [Pa]
      real(wp) :: e_kin_end = 0.0_wp       !! kinetic energy at the end [J/m^2]
      real(wp) :: w_ext_end = 0.0_wp       !! work of the loads and ends at the end [J/m^2]
      integer :: checkpoints = 0           !! checkpoints written
      real(wp) :: fracture_stress_sum = 0.0_wp !! sum of |section stress| at the fractures [Pa]
      real(wp) :: e_mech0 = 0.0_wp         !! the energy guard's reference: mechanical energy
                                           !! at t = 0, e_wave + e_pot + e_wave_g [J/m^2]
      real(wp) :: guard_scale = 0.0_wp     !! the guard's scale: e_wave at t = 0, then the
                                           !! largest |w_wave| [J/m^2]
      real(wp) :: ledger_w0 = 0.0_wp       !! wave ledger at t = 0 [J/m^2]
      real(wp) :: wave_drift = 0.0_wp      !! largest |ledger_w - ledger_w0| over rows [J/m^2]
      real(wp) :: max_jordan = 0.0_wp      !! largest relative Jordan amplitude over rows [-]
      real(wp) :: jordan_scale = 0.0_wp    !! largest momentum scale of the bar over rows, what
                                           !! the Jordan amplitude is relative to [kg/(m s)]
      real(wp) :: fracture_t(first_fractures) = 0.0_wp    !! the first fractures: time [s],
      real(wp) :: fracture_x(first_fractures) = 0.0_wp    !! reference position [m],
      real(wp) :: fracture_s(first_fractures) = 0.0_wp    !! section stress [Pa]
      type(diag_t) :: diag                 !! the experiment diagnostics (spb_diagnostics:
                                           !! PREFIX.spl, .imp)
   end type run_summary_t

contains

   !> The references of t = 0 (a run that does not resume): the energy guard's reference
   !> and scale, the wave ledger's start and the first bottom reaction.
   pure subroutine summary_start(summary, e0, w0, w_w, e_l, scale, reaction)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(energies_t), intent(in) :: e0   !! the scheme's energies at t = 0
      type(wave_t), intent(in) :: w0       !! the wave measure at t = 0
      real(wp), intent(in) :: w_w          !! work in that measure [J/m^2]
      real(wp), intent(in) :: e_l          !! energy events removed, in that measure [J/m^2]
      real(wp), intent(in) :: scale        !! the guard's scale at t = 0: the measure's energy
                                           !! (the full-mass model's: e_kin + |e_strain|)
                                           !! [J/m^2]
      real(wp), intent(in) :: reaction     !! section stress at the bottom node [Pa]
      summary%e_mech0 = w0%e_wave + e0%e_pot + w0%e_gravity
      summary%guard_scale = scale
      summary%ledger_w0 = summary%e_mech0 - w_w + e_l
      summary%max_reaction_bottom = reaction
   end subroutine summary_start

   !> The running values of a history row: the Jordan amplitude made relative to the largest
   !> momentum scale so far (in wv, for the row: the current scale vanishes once a bar has
   !> come to rest or radiated its waves away), the energies at the end, the ledgers' drifts
   !> and the largest energy term. step: the row's step (0: the ledger's reference).
   pure subroutine summary_row(summary, step, e, wv, w_w, e_l)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      integer, intent(in) :: step          !! the row's step
      type(energies_t), intent(in) :: e    !! the scheme's energies
      type(wave_t), intent(inout) :: wv    !! the wave measure (its jordan made relative)
      real(wp), intent(in) :: w_w          !! work in that measure [J/m^2]
      real(wp), intent(in) :: e_l          !! energy events removed, in that measure [J/m^2]
      summary%jordan_scale = max(summary%jordan_scale, wv%momentum_scale)
      if (summary%jordan_scale > 0.0_wp) wv%jordan = wv%jordan_abs / summary%jordan_scale
      summary%e_kin_end = e%e_kin
      summary%w_ext_end = e%w_ext
      if (step == 0) summary%ledger0 = e%ledger
      summary%ledger_drift = max(summary%ledger_drift, abs(e%ledger - summary%ledger0))
      summary%wave_drift = max(summary%wave_drift, abs(wv%e_wave + e%e_pot + wv%e_gravity - &
         w_w + e_l - summary%ledger_w0))
      summary%max_jordan = max(summary%max_jordan, wv%jordan)
      summary%energy_scale = max(summary%energy_scale, abs(e%e_kin), abs(e%e_strain), &
                                 abs(e%e_pot), abs(e%w_ext))
   end subroutine summary_row

   !> The energy guard's running values: its scale (the largest |work| in the wave measure,
   !> and a striking mass's energy at stake) and the largest relative excess; excess, the
   !> mechanical energy's excess over the initial energy plus the work, is what the guard
   !> compares with its limit.
   pure subroutine summary_guard(summary, e, wv, w_w, excess, striker_scale)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(energies_t), intent(in) :: e    !! the scheme's energies (e_pot is used)
      type(wave_t), intent(in) :: wv       !! the wave measure
      real(wp), intent(in) :: w_w          !! work in that measure [J/m^2]
      real(wp), intent(out) :: excess      !! (E - E0) - w_w [J/m^2]
      real(wp), intent(in) :: striker_scale   !! a striking mass's energy at stake: its kinetic
                                              !! energy and its weight over its gap (0
                                              !! without one) [J/m^2]
      summary%guard_scale = max(summary%guard_scale, abs(w_w), striker_scale)
      excess = (wv%e_wave + e%e_pot + wv%e_gravity - summary%e_mech0) - w_w
      if (summary%guard_scale > 0.0_wp) summary%max_excess = max(summary%max_excess, &
         excess / summary%guard_scale)
   end subroutine summary_guard

   !> The largest section stress at the bottom node so far.
   pure subroutine summary_reaction(summary, reaction)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      real(wp), intent(in) :: reaction     !! a section stress at the bottom node [Pa]
      summary%max_reaction_bottom = max(summary%max_reaction_bottom, reaction)
   end subroutine summary_reaction

   !> The events of a step: counted by kind; the first fractures kept (time, place, stress).
   pure subroutine summary_events(summary, events)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(event_list_t), intent(in) :: events   !! the step's events (stresses per area)
      integer :: j, k
      summary%events = summary%events + events%n
      do j = 1, events%n
         associate (ev => events%e(j))
            summary%n_kind(ev%kind) = summary%n_kind(ev%kind) + 1
            if (ev%kind == ev_fracture) then
               if (summary%first_fracture_t < 0.0_wp) summary%first_fracture_t = ev%t
               k = summary%n_kind(ev_fracture)
               if (k <= first_fractures) then
                  summary%fracture_t(k) = ev%t
                  summary%fracture_x(k) = ev%x
                  summary%fracture_s(k) = ev%stress
               end if
               summary%fracture_stress_sum = summary%fracture_stress_sum + abs(ev%stress)
            end if
         end associate
      end do
   end subroutine summary_events

   !> A checkpoint of step is being written (the summary it keeps counts it).
   pure subroutine summary_checkpoint(summary, step)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      integer, intent(in) :: step          !! the checkpoint's step
      summary%checkpoints = summary%checkpoints + 1
      summary%steps = step
   end subroutine summary_checkpoint

   !> The end of the run: its steps and wall time.
   pure subroutine summary_end(summary, step, wall)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      integer, intent(in) :: step          !! the last step
      real(wp), intent(in) :: wall         !! the run's wall time [s]
      summary%steps = step
      summary%wall = wall
   end subroutine summary_end

   !> The one list of what a checkpoint keeps of the run summary (attributes of group),
   !> written or read back (io%writing); adding a field is one line here.
   subroutine summary_fields(summary, io, group)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      class(field_io_t), intent(inout) :: io   !! the checkpoint file
      character(len=*), intent(in) :: group    !! its group ('/run')
      integer :: k
      call io%field(group, 'steps', summary%steps)
      call io%field(group, 'events', summary%events)
      ! the counts by kind: a core kind's always, another's only where there were some (a
      ! checkpoint of a run without them, or of a version before them, has none)
      do k = 1, size(event_kinds)
         if (event_kinds(k)%core) then
            call io%field(group, 'n_kind_' // itoa(k), summary%n_kind(k))
         else if (io%writing) then
            if (summary%n_kind(k) > 0) call io%field(group, 'n_kind_' // itoa(k), &
                                                     summary%n_kind(k))
         else if (io%has(group, 'n_kind_' // itoa(k))) then
            call io%field(group, 'n_kind_' // itoa(k), summary%n_kind(k))
         end if
      end do
      call io%field(group, 'checkpoints', summary%checkpoints)
      call io%field(group, 'ledger0', summary%ledger0)
      call io%field(group, 'ledger_drift', summary%ledger_drift)
      call io%field(group, 'energy_scale', summary%energy_scale)
      call io%field(group, 'max_excess', summary%max_excess)
      call io%field(group, 'first_fracture_t', summary%first_fracture_t)
      call io%field(group, 'max_reaction_bottom', summary%max_reaction_bottom)
      call io%field(group, 'e_kin_end', summary%e_kin_end)
      call io%field(group, 'w_ext_end', summary%w_ext_end)
      call io%field(group, 'e_mech0', summary%e_mech0)
      call io%field(group, 'guard_scale', summary%guard_scale)
      call io%field(group, 'ledger_w0', summary%ledger_w0)
      call io%field(group, 'wave_drift', summary%wave_drift)
      call io%field(group, 'max_jordan', summary%max_jordan)
      call io%field(group, 'jordan_scale', summary%jordan_scale)
      call io%field(group, 'fracture_stress_sum', summary%fracture_stress_sum)
      ! added later (a checkpoint without them restarts; its summary lists fewer fractures)
      do k = 1, first_fractures
         call io%later(group, 'fracture_t_' // itoa(k), summary%fracture_t(k))
         call io%later(group, 'fracture_x_' // itoa(k), summary%fracture_x(k))
         call io%later(group, 'fracture_stress_' // itoa(k), summary%fracture_s(k))
      end do
      call diag_fields(summary%diag, io, group)
   end subroutine summary_fields

   !> Why the run summary read back cannot be continued ('' when it can): its counts not
   !> negative.
   function summary_problem(summary) result(why)
      type(run_summary_t), intent(in) :: summary   !! the run's summary read back
      character(len=:), allocatable :: why
      why = ''
      if (min(summary%steps, summary%events, summary%checkpoints, minval(summary%n_kind)) < 0) then
         why = 'is damaged: a count of its run summary is negative'
      end if
   end function summary_problem

   !> The end-of-run text: steps, wall time and the energy ledgers' drifts, the events by
   !> kind, the first fractures, the fragments at the end (the first few: where, how long,
   !> how fast), and every file the run wrote.
   subroutine write_summary(unit, summary, list, prefix, files)
      integer, intent(in) :: unit          !! where (standard output)
      type(run_summary_t), intent(in) :: summary   !! the run's summary
      type(frag_info_t), intent(in) :: list(:)   !! the fragments at the end, top to bottom
      character(len=*), intent(in) :: prefix   !! output path prefix
      character(len=*), intent(in) :: files    !! the files the run wrote, in words
      integer :: k, nf
      character(len=200) :: line
      write(unit, '(a,i0,a,es9.2,a,es9.2,a,es9.2,a)') '  done: ', summary%steps, &
         ' steps in ', summary%wall, ' s; energy ledger drift ', summary%ledger_drift, &
         ' J/m^2 (', summary%ledger_drift / max(summary%energy_scale, tiny(1.0_wp)), &
         ' of the largest energy term)'
      write(unit, '(a,es9.2,a)') '  largest excess of mechanical energy (wave measure) ' // &
         'over initial + work: ', summary%max_excess, ' of the energy scale'
      write(unit, '(a,es9.2,a,es9.2,a)') '  wave energy ledger drift ', summary%wave_drift, &
         ' J/m^2; largest Jordan amplitude ', summary%max_jordan, ' (events must leave none: round-off)'
      write(unit, '(a)') '  events: ' // itoa(summary%events) // ' (' // by_kind(summary) // ')'
      nf = summary%n_kind(ev_fracture)
      if (nf > 0) write(unit, '(a)') '  fractures: ' // itoa(nf) // ' (time, place, ' // &
         'section stress; compression > 0):'
      do k = 1, min(nf, first_fractures)
         write(line, '(a,es11.4,a,es11.4,a,es11.4,a)') '    t = ', summary%fracture_t(k), &
            ' s at x = ', summary%fracture_x(k), ' m, stress ', summary%fracture_s(k), ' Pa'
         write(unit, '(a)') trim(line)
      end do
      if (nf > first_fractures) write(unit, '(a)') '    ... and ' // &
         itoa(nf - first_fractures) // ' more (' // prefix // '.evt)'
      write(unit, '(a)') '  fragments at the end: ' // itoa(size(list)) // &
         ' (x of the faces now, length, mean velocity):'
      do k = 1, min(size(list), 5)
         write(line, '(a,i0,a,es11.4,a,es11.4,a,es10.3,a,es10.3,a)') '    ', list(k)%id, ': x = ', &
            list(k)%x_top, ' .. ', list(k)%x_bot, ' m, length ', list(k)%x_bot - list(k)%x_top, &
            ' m, velocity ', list(k)%velocity, ' m/s'
         write(unit, '(a)') trim(line)
      end do
      if (size(list) > 5) write(unit, '(a)') '    ... and ' // itoa(size(list) - 5) // &
         ' more (' // prefix // '.frg lists them all at a profile time equal to t_end)'
      call write_diag_summary(unit, summary%diag, prefix)
      write(unit, '(a)') '  wrote ' // files
   end subroutine write_summary

   !> The experiment diagnostics' lines of the run summary: each free end's peak, pull-back,
   !> Novikov strength and spall plane (PREFIX.spl), the first contact episodes (PREFIX.imp).
   subroutine write_diag_summary(unit, d, prefix)
      integer, intent(in) :: unit          !! where (standard output)
      type(diag_t), intent(in) :: d        !! the record
      character(len=*), intent(in) :: prefix   !! output path prefix
      integer :: side, k
      real(wp) :: v(11)
      character(len=240) :: line
      do side = 1, 2
         if (.not. d%ends(side)%on) cycle
         v(1:10) = spall_row(d%ends(side))
         ! an end with neither a peak nor a fracture has no line (PREFIX.spl has its row)
         if (ieee_is_nan(v(2)) .and. d%ends(side)%node < 0) cycle
         write(line, '(a,es11.4,a,es11.4,a,es11.4,a,es11.4,a,es11.4,a)') '  spall, ' // &
            trim(end_names(side)) // ' end: peak ', v(2), ' m/s at ', v(1), ' s, pull-back ', &
            v(4), ' m/s at ', v(3), ' s, sigma_novikov ', v(6), ' Pa'
         write(unit, '(a)') trim(line)
         if (d%ends(side)%node >= 0) then
            write(line, '(a,es11.4,a,es11.4,a,es11.4,a,es11.4,a)') '    spall plane x = ', &
               v(7), ' m at ', v(8), ' s; scab ', v(9), ' m thick, ', v(10), ' m/s outward'
            write(unit, '(a)') trim(line)
         end if
      end do
      if (d%n_done == 0) return
      write(unit, '(a)') '  contact episodes: ' // itoa(d%n_done) // ' (start, duration, ' // &
         'kind, peak force, impulse; ' // prefix // '.imp):'
      do k = 1, min(d%n_done, first_impacts)
         v = impact_row(d%first(k))
         write(line, '(a,es11.4,a,es11.4,a,es11.4,a,es11.4)') '    from t = ', v(1), ' s for ', &
            v(3), ' s, ' // trim(imp_kind_names(d%first(k)%kind)) // ', peak ', v(6), &
            ', impulse ', v(7)
         write(unit, '(a)') trim(line)
      end do
      if (d%n_done > first_impacts) write(unit, '(a)') '    ... and ' // &
         itoa(d%n_done - first_impacts) // ' more episodes'
   end subroutine write_diag_summary

   !> The events by kind for the summary's events line, 'fractures 3, collisions 1, ...':
   !> every kind with a plural in event_kinds, a core kind's even when 0.
   function by_kind(summary) result(text)
      type(run_summary_t), intent(in) :: summary   !! the run's summary
      character(len=:), allocatable :: text
      integer :: k
      text = ''
      do k = 1, size(event_kinds)
         if (len_trim(event_kinds(k)%plural) == 0) cycle
         if (.not. event_kinds(k)%core .and. summary%n_kind(k) == 0) cycle
         if (len(text) > 0) text = text // ', '
         text = text // trim(event_kinds(k)%plural) // ' ' // itoa(summary%n_kind(k))
      end do
   end function by_kind
end module spb_summary
