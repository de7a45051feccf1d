!> A simulation: deck -> mesh, load, state; the stepping loop with its outputs.
!>
!> sim_setup works on an in-memory deck (tests use it without files); sim_run writes the
!> column outputs and reports progress.
module spb_sim
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit, int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t, make_error, exit_runtime
   use spb_sys, only: stop_signal
   use spb_strings, only: itoa, rtoa
   use spb_deck, only: deck_t, problem_from_deck
   use spb_problem, only: problem_t, load_table
   use spb_load_table, only: read_table
   use spb_mesh, only: mesh_t, build_mesh, end_base
   use spb_load, only: load_t, build_load
   use spb_state, only: state_t, init_state, fragment_count
   use spb_step, only: advance, advance_joined, joined_only, end_stresses, face_load_integrals
   use spb_wave, only: wave_t, wave_energy
   use spb_diag, only: energies_t, energies, frag_info_t, fragment_list, run_summary_t
   use spb_events, only: event_list_t, ev_fracture
   use spb_fracture, only: fracture_step
   use spb_contact, only: contact_step
   use spb_output, only: outputs_t, open_outputs, close_outputs, write_history_row, write_profile, &
      write_events, write_fragments, write_field, flush_outputs, output_marks_t, mark_outputs, &
      resume_outputs
   use spb_checkpoint, only: checkpoint_t, write_checkpoint, check_checkpoint_path
   implicit none
   private
   public :: sim_t, sim_setup, sim_run, run_summary_t, sim_step, checkpoint_t, setup_model

   type :: sim_t
      type(deck_t) :: deck                           !! for the outputs' echo and checkpoints
      type(problem_t) :: prob                        !! what the model solves
      type(mesh_t) :: mesh
      type(load_t) :: load
      type(state_t) :: st
      character(len=200), allocatable :: report(:)   !! mesh fit report
   end type sim_t


contains

   !> The energy measure of the outputs and the guard: the wave measure (spb_wave) of the
   !> half-mass model; the full-mass comparison model has no continuum reading and keeps the
   !> scheme's own (e_wave = e_kin + e_strain, w_wave = w_ext, e_lost_w = e_lost).
   pure subroutine measure(sim, e, wv, w_wave, e_lost_w)
      type(sim_t), intent(in) :: sim
      type(energies_t), intent(in) :: e
      type(wave_t), intent(out) :: wv
      real(wp), intent(out) :: w_wave, e_lost_w     !! [J/m^2]
      real(wp) :: q_top, q_bot
      if (sim%mesh%full_mass) then
         wv%e_wave = e%e_kin + e%e_strain
         w_wave = e%w_ext
         e_lost_w = e%e_lost
         return
      end if
      call face_load_integrals(sim%mesh, sim%load, sim%st%n, q_top, q_bot)
      wv = wave_energy(sim%mesh, sim%st, sim%prob%gravity, q_top, q_bot)
      w_wave = sim%st%w_wave
      e_lost_w = sim%st%e_lost_wave
   end subroutine measure

   !> The largest overlap of two faces at a split node, or of the bottom face and the base,
   !> in cells of that node (<= 0: none; -huge with no open face) [-].
   pure real(wp) function largest_overlap(sim) result(ov)
      type(sim_t), intent(in) :: sim
      integer :: c, i
      ov = -huge(1.0_wp)
      do c = 1, sim%st%n_split
         i = sim%st%split(c)
         ov = max(ov, (sim%st%ua(i) - sim%st%ub(i)) / min(sim%mesh%dx(i), sim%mesh%dx(i + 1)))
      end do
      if (sim%mesh%bottom == end_base) ov = max(ov, (sim%st%ua(sim%mesh%n) - sim%st%u_base) / &
                                                sim%mesh%dx(sim%mesh%n))
      ov = max(ov, -1.0_wp)
   end function largest_overlap

   !> Build mesh, load and initial state from a validated deck.
   subroutine sim_setup(deck, sim, err)
      type(deck_t), intent(in) :: deck
      type(sim_t), intent(out) :: sim
      type(spb_error_t), allocatable, intent(out) :: err
      sim%deck = deck
      call setup_model(deck, sim%prob, sim%mesh, sim%load, sim%report, err)
      if (allocated(err)) return
      call init_state(sim%prob, sim%mesh, sim%st)
   end subroutine sim_setup

   !> The problem of a validated deck, its mesh and its load (the load table read here, after
   !> the mesh: a deck with faults in both reports the mesh's first).
   subroutine setup_model(deck, prob, mesh, load, report, err)
      type(deck_t), intent(in) :: deck
      type(problem_t), intent(out) :: prob
      type(mesh_t), intent(out) :: mesh
      type(load_t), intent(out) :: load
      character(len=200), allocatable, intent(out) :: report(:)   !! mesh fit report
      type(spb_error_t), allocatable, intent(out) :: err
      prob = problem_from_deck(deck)
      call build_mesh(prob, mesh, report, err)
      if (allocated(err)) return
      if (prob%load_kind == load_table) then
         call read_table(deck%load%table, prob%table_t, prob%table_p, err)
         if (allocated(err)) return
      end if
      call build_load(prob, load)
   end subroutine setup_model

   !> One step of the whole method: the trial update, collisions by the timing rule, then
   !> fracture and separation at t^{n+1}.
   pure subroutine sim_step(sim, events)
      type(sim_t), intent(inout) :: sim
      type(event_list_t), intent(inout) :: events   !! events of this step are appended
      real(wp) :: i_top, i_bot
      associate (p => sim%prob)
         call advance(sim%mesh, sim%load, p%gravity, sim%st)
         call face_load_integrals(sim%mesh, sim%load, sim%st%n, i_top, i_bot)
         call contact_step(sim%mesh, sim%st, p%gravity, p%timing, p%shift, events, i_top, &
                           i_bot, p%events, p%eps_rel)
         call fracture_step(sim%mesh, sim%st, p%gravity, p%eps_rel, events, p%events, i_top, &
                            i_bot)
      end associate
   end subroutine sim_step

   !> Run to t_end writing PREFIX.his, .prf, .evt, .frg (with files = .false.: no files,
   !> only the summary, as a sweep's cases do). With resume: go on from a checkpoint, the
   !> outputs continuing those of the run that wrote it (bit-identical to one run).
   !> With &run checkpoint: write it every checkpoint_every steps, at t_end and when a
   !> signal stops the run.
   subroutine sim_run(sim, prefix, progress, summary, err, files, resume)
      type(sim_t), intent(inout) :: sim
      character(len=*), intent(in) :: prefix
      logical, intent(in) :: progress          !! show a progress line on stderr
      type(run_summary_t), intent(out) :: summary
      type(spb_error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: files   !! write the outputs (default .true.)
      type(checkpoint_t), intent(in), optional :: resume   !! continue from this checkpoint
      type(outputs_t) :: out
      type(event_list_t) :: events
      integer :: ip, nprof, every, n, k, j, ck_every, sig
      integer, allocatable :: prof_step(:)
      integer(int64) :: c0, c_last, c_now, rate
      real(wp) :: g, sec_max
      logical :: wrote_row, to_files, ck_on

      to_files = .true.
      if (present(files)) to_files = files
      ck_on = to_files .and. len_trim(sim%deck%run%checkpoint) > 0
      ck_every = sim%deck%run%checkpoint_every
      if (ck_on) call check_checkpoint_path(trim(sim%deck%run%checkpoint), err)
      if (allocated(err)) return
      if (present(resume)) then
         call resume_outputs(prefix, sim%deck, sim%mesh, sim%report, resume%marks, out, err)
         if (allocated(err)) return
         sim%st = resume%st
         summary = resume%summary
      else if (to_files) then
         call open_outputs(prefix, sim%deck, sim%mesh, sim%report, out, err)
         if (allocated(err)) return
      end if
      g = sim%prob%gravity
      every = sim%deck%run%history_every
      nprof = sim%deck%run%n_profiles
      allocate(prof_step(nprof))
      prof_step = nint(sim%deck%run%profile_times(1:nprof) / sim%mesh%dt)
      ! the first profile still to write
      ip = 1
      if (present(resume)) then
         do while (ip <= nprof)
            if (prof_step(ip) > sim%st%n) exit
            ip = ip + 1
         end do
      end if
      call system_clock(c0, rate)
      c_last = c0
      if (.not. present(resume)) then
         block
            type(energies_t) :: e0
            type(wave_t) :: w0
            real(wp) :: w_w, e_l
            e0 = energies(sim%mesh, sim%st, g)
            call measure(sim, e0, w0, w_w, e_l)
            summary%e_mech0 = w0%e_wave + e0%e_pot + w0%e_gravity
            summary%guard_scale = w0%e_wave
            if (sim%mesh%full_mass) summary%guard_scale = e0%e_kin + abs(e0%e_strain)
            summary%ledger_w0 = summary%e_mech0 - w_w + e_l
         end block
         summary%max_reaction_bottom = sim%st%sec(sim%mesh%n)
         call row()
         call profiles()
         if (sim%deck%run%field_every > 0 .and. to_files) call write_field(out, sim%mesh, sim%st)
      end if
      n = sim%st%n
      sig = 0
      do while (n < sim%mesh%nsteps)
         ! steps with nothing to write, check or break are taken in one cache-blocked call,
         ! up to the step before the next one that has work of its own
         k = next_stop(n) - n
         if (k > 1 .and. joined_only(sim%mesh, sim%st)) then
            call advance_joined(sim%mesh, sim%load, g, sim%st, k - 1, max_sec_bottom=sec_max)
            summary%max_reaction_bottom = max(summary%max_reaction_bottom, sec_max)
            n = n + k - 1
         end if
         n = n + 1
         events%n = 0
         call sim_step(sim, events)
         summary%max_reaction_bottom = max(summary%max_reaction_bottom, sim%st%sec(sim%mesh%n))
         if (events%n > 0) then
            if (to_files) call write_events(out, events)
            summary%events = summary%events + events%n
            do j = 1, events%n
               associate (ev => events%e(j))
                  summary%n_kind(ev%kind) = summary%n_kind(ev%kind) + 1
                  if (ev%kind == ev_fracture) then
                     if (summary%first_fracture_t < 0.0_wp) summary%first_fracture_t = ev%t
                     summary%fracture_stress_sum = summary%fracture_stress_sum + abs(ev%stress)
                  end if
               end associate
            end do
         end if
         wrote_row = .false.
         if (mod(n, every) == 0) then
            call row()
            wrote_row = .true.
            if (allocated(err)) exit
         else if (mod(n, 64) == 0) then
            ! between rows: the state's finiteness and the energy guard every 64 steps
            block
               type(energies_t) :: e
               type(wave_t) :: wv
               real(wp) :: w_w, e_l
               e = energies(sim%mesh, sim%st, g)
               if (ieee_is_finite(e%ledger)) then
                  call measure(sim, e, wv, w_w, e_l)
                  call guard(e, wv, w_w)
                  if (allocated(err)) call row()
               else
                  call row()
               end if
            end block
            if (allocated(err)) exit
         end if
         call profiles()
         if (sim%deck%run%field_every > 0) then
            if (mod(n, sim%deck%run%field_every) == 0 .and. to_files) &
               call write_field(out, sim%mesh, sim%st)
         end if
         sig = stop_signal()
         if (ck_on) then
            ! the state after everything of step n that an uninterrupted run writes too
            ! (max: Fortran may evaluate mod before the test of ck_every)
            if (n == sim%mesh%nsteps .or. sig /= 0 .or. &
                (ck_every > 0 .and. mod(n, max(ck_every, 1)) == 0)) call checkpoint()
            if (allocated(err)) exit
         end if
         if (sig /= 0) then
            ! SIGTERM/SIGINT: end here with the outputs complete up to this step
            if (.not. wrote_row) call row()
            call make_error(err, 'run: stopped by signal ' // itoa(sig) // &
               ' at step ' // itoa(sim%st%n) // ' (t = ' // &
               rtoa(real(sim%st%n, wp) * sim%mesh%dt) // ' s); outputs up to here are ' // &
               'written and closed' // trim(merge(' (and the checkpoint)', '                     ', &
               ck_on)), code=128 + sig)
            exit
         end if
         if (mod(n, 1024) == 0) then
            call system_clock(c_now)
            if (real(c_now - c_last, wp) > 0.5_wp * real(rate, wp)) then
               c_last = c_now
               if (to_files) call flush_outputs(out)
               if (progress) call show_progress(n, real(c_now - c0, wp) / real(rate, wp))
            end if
         end if
      end do
      ! the last row at t_end when it is not a history_every row (written after the
      ! checkpoint: a run extended from there does not have it)
      if (.not. allocated(err) .and. sim%st%n == sim%mesh%nsteps .and. &
          mod(sim%mesh%nsteps, every) /= 0) call row()
      call system_clock(c_now)
      if (progress) write(error_unit, '(a)') ''
      if (to_files) then
         block
            type(spb_error_t), allocatable :: err_close
            call close_outputs(out, err_close)
            if (allocated(err_close) .and. .not. allocated(err)) call move_alloc(err_close, err)
         end block
      end if
      summary%steps = sim%st%n
      summary%wall = real(c_now - c0, wp) / real(max(rate, 1_int64), wp)
   contains
      !> The first step after n that writes, checks or reports something (a multiple of 64
      !> for the guard and the progress line, a history row, a profile, a field row, the end).
      integer function next_stop(n_now) result(m)
         integer, intent(in) :: n_now
         integer(int64) :: m8
         m8 = min(int(sim%mesh%nsteps, int64), (n_now / 64 + 1) * 64_int64, &
                  (n_now / every + 1) * int(every, int64))
         if (ip <= nprof) then
            if (prof_step(ip) > n_now) m8 = min(m8, int(prof_step(ip), int64))
         end if
         associate (fe => sim%deck%run%field_every)
            if (fe > 0) m8 = min(m8, (n_now / fe + 1) * int(fe, int64))
         end associate
         if (ck_on .and. ck_every > 0) m8 = min(m8, (n_now / ck_every + 1) * int(ck_every, int64))
         m = int(m8)
      end function next_stop
      !> Write the checkpoint of step n (its outputs written through first).
      subroutine checkpoint()
         type(output_marks_t) :: marks
         call mark_outputs(out, marks)
         summary%checkpoints = summary%checkpoints + 1
         summary%steps = sim%st%n
         call write_checkpoint(trim(sim%deck%run%checkpoint), sim%deck, sim%mesh, sim%load, &
                               sim%st, summary, marks, err)
      end subroutine checkpoint
      subroutine row()
         type(energies_t) :: e
         type(wave_t) :: wv
         real(wp) :: s_top, s_bot, w_w, e_l
         integer :: i
         e = energies(sim%mesh, sim%st, g)
         call end_stresses(sim%mesh, sim%load, sim%st, s_top, s_bot)
         if (.not. ieee_is_finite(e%ledger)) then
            ! the first node whose displacements, increments or cell stress above are bad
            do i = 0, sim%mesh%n
               if (.not. (ieee_is_finite(sim%st%ua(i)) .and. ieee_is_finite(sim%st%ub(i)) .and. &
                          ieee_is_finite(sim%st%dua(i)) .and. ieee_is_finite(sim%st%dub(i)) &
                          .and. ieee_is_finite(sim%st%s(i)))) exit
            end do
            call make_error(err, 'run: the state is not finite at step ' // itoa(sim%st%n) // &
               ' (t = ' // rtoa(real(sim%st%n, wp) * sim%mesh%dt) // ' s), node ' // &
               itoa(min(i, sim%mesh%n)), code=exit_runtime)
            if (to_files) call flush_outputs(out)
            return
         end if
         call measure(sim, e, wv, w_w, e_l)
         ! the Jordan amplitude relative to the largest momentum scale so far (the current one
         ! vanishes once a bar has come to rest or radiated its waves away)
         summary%jordan_scale = max(summary%jordan_scale, wv%momentum_scale)
         if (summary%jordan_scale > 0.0_wp) wv%jordan = wv%jordan_abs / summary%jordan_scale
         summary%e_kin_end = e%e_kin
         summary%w_ext_end = e%w_ext
         if (to_files) call write_history_row(out, real(sim%st%n, wp) * sim%mesh%dt, sim%st%sec(sim%mesh%n), &
            sim%st%sec(0), fragment_count(sim%st), e%e_kin, e%e_strain, e%e_pot, e%w_ext, &
            e%e_lost, e%momentum, sim%st%n, s_top, s_bot, sim%st%w_load, sim%st%w_transmit, &
            e%ledger, sim%st%e_fracture, sim%st%e_join, sim%st%e_shift, sim%st%e_contact, &
            g * (sum(sim%mesh%ma) + sum(sim%mesh%mb)) * real(sim%st%n, wp) * sim%mesh%dt, &
            sim%st%i_ends, sim%st%i_support, sim%st%p_shift, wv%e_wave, wv%e_gravity, wv%jordan, &
            w_w, e_l, wv%e_wave + e%e_pot + wv%e_gravity - w_w + e_l, largest_overlap(sim))
         if (sim%st%n == 0) summary%ledger0 = e%ledger
         call guard(e, wv, w_w)
         summary%ledger_drift = max(summary%ledger_drift, abs(e%ledger - summary%ledger0))
         summary%wave_drift = max(summary%wave_drift, abs(wv%e_wave + e%e_pot + wv%e_gravity - &
            w_w + e_l - summary%ledger_w0))
         summary%max_jordan = max(summary%max_jordan, wv%jordan)
         summary%energy_scale = max(summary%energy_scale, abs(e%e_kin), abs(e%e_strain), &
                                    abs(e%e_pot), abs(e%w_ext))
      end subroutine row
      !> Stop when the mechanical energy exceeds the initial energy plus the work of the
      !> loads (gravity's work is in e_pot) by more than energy_guard times the scale. The
      !> energy is the wave measure (spb_wave), which no zig-zag growth can hide from.
      subroutine guard(e, wv, w_w)
         type(energies_t), intent(in) :: e
         type(wave_t), intent(in) :: wv
         real(wp), intent(in) :: w_w      !! work in that measure [J/m^2]
         real(wp) :: excess
         character(len=16) :: b1, b2
         if (allocated(err)) return
         summary%guard_scale = max(summary%guard_scale, abs(w_w))
         excess = (wv%e_wave + e%e_pot + wv%e_gravity - summary%e_mech0) - w_w
         if (summary%guard_scale > 0.0_wp) summary%max_excess = max(summary%max_excess, &
            excess / summary%guard_scale)
         if (sim%deck%run%energy_guard > 0.0_wp .and. &
             excess > sim%deck%run%energy_guard * summary%guard_scale .and. &
             summary%guard_scale > 0.0_wp) then
            write(b1, '(es10.3)') excess
            write(b2, '(es10.3)') excess / summary%guard_scale
            call make_error(err, 'run: mechanical energy exceeds the initial energy plus the ' // &
               'work of the loads by ' // trim(adjustl(b1)) // ' J/m^2 (' // &
               trim(adjustl(b2)) // ' of the energy scale, above ' // &
               '&run energy_guard = ' // rtoa(sim%deck%run%energy_guard) // ') at step ' // &
               itoa(sim%st%n) // ' (t = ' // rtoa(real(sim%st%n, wp) * sim%mesh%dt) // &
               ' s); outputs up to here are written', code=exit_runtime)
         end if
      end subroutine guard
      subroutine profiles()
         type(frag_info_t), allocatable :: list(:)
         do while (ip <= nprof)
            if (prof_step(ip) /= sim%st%n) exit
            if (.not. to_files) then
               ip = ip + 1
               cycle
            end if
            call write_profile(out, sim%mesh, sim%st, sim%deck%run%profile_times(ip))
            call fragment_list(sim%mesh, sim%st, list)
            call write_fragments(out, real(sim%st%n, wp) * sim%mesh%dt, sim%mesh%dt, list)
            ip = ip + 1
         end do
      end subroutine profiles
      subroutine show_progress(n_done, elapsed)
         integer, intent(in) :: n_done
         real(wp), intent(in) :: elapsed
         real(wp) :: frac, speed
         character(len=120) :: line
         frac = real(n_done, wp) / real(sim%mesh%nsteps, wp)
         speed = real(n_done, wp) / max(elapsed, 1.0e-9_wp)
         write(line, '(a,f6.1,a,es9.2,a,f9.1,a)') 'spallbar: ', 100.0_wp * frac, '%  ', speed, &
            ' steps/s  ETA ', real(sim%mesh%nsteps - n_done, wp) / speed, ' s'
         write(error_unit, '(a)', advance='no') achar(13) // trim(line)
         flush(error_unit)
      end subroutine show_progress
   end subroutine sim_run
end module spb_sim
