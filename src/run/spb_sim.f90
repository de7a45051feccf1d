!> A simulation: deck -> mesh, load, state; the stepping loop with its outputs.
!>
!> sim_setup works on an in-memory deck (tests use it without files); sim_run writes the
!> column outputs and reports progress.
module spb_sim
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit, int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t, make_error, exit_runtime
   use spb_sys, only: stop_signal, sys_memory_limit
   use spb_strings, only: itoa, rtoa
   use spb_deck, only: deck_t, problem_from_deck, deck_record_t, deck_record, mesh_fault_message, &
      deck_file
   use spb_problem, only: problem_t, load_table
   use spb_load_table, only: read_table
   use spb_mesh, only: mesh_t, build_mesh, mesh_size, mesh_fault_t, &
      fault_none, node_area
   use spb_load, only: load_t, build_load
   use spb_state, only: state_t, init_state
   use spb_full_mass, only: init_full_mass
   use spb_step, only: advance, advance_joined, joined_only, face_load_integrals
   use spb_ring, only: ring_qualifies, ring_layout_t, ring_layout, ring_hybrid_t, start_rings, &
      advance_rings, end_rings, ring_span_max
   use spb_ends, only: face_top, face_bottom, is_velocity_end, is_striker, strike_events
   use spb_fragments, only: fragment_span
   use spb_wave, only: wave_t, wave_energy, start_without_zigzag
   use spb_diag, only: energies_t, energies, frag_info_t, fragment_list
   use spb_history, only: measure, post_history, length_defect, history_ids_t, register_history
   use spb_columns, only: column_set_t
   use spb_events, only: event_list_t
   use spb_summary, only: run_summary_t, summary_start, summary_row, summary_guard, &
      summary_reaction, summary_events, summary_checkpoint, summary_end
   use spb_fracture, only: fracture_step
   use spb_contact, only: contact_step
   use spb_gauge, only: gauge_t, locate_gauges, watch_gauges, read_gauges
   use spb_output, only: outputs_t, open_outputs, close_outputs, write_history_row, write_profile, &
      bar_units, &
      write_events, write_fragments, write_field, flush_outputs, output_marks_t, mark_outputs, &
      claim_outputs, check_written, write_gauge_row, publish_outputs, where_outputs, &
      write_diag_text, write_diag_h5, write_impacts
   use spb_restart, only: resume_outputs, drop_set_aside
   use spb_checkpoint, only: checkpoint_t, write_checkpoint, check_checkpoint_path
   use spb_estimate, only: progress_period
   use spb_diagnostics, only: diag_t, diag_start, diag_step, diag_end_samples, diag_close, &
      diag_taken, contact_nodes, diag_contact_samples, contacts_by_sections
   use spb_schedule, only: schedule_t, schedule_every, schedule_at, is_due, next_due, act_row, &
      act_check, act_field, act_checkpoint, act_progress, act_gauge, row_count, row_index, &
      check_every, keeps_rows
   implicit none
   private
   public :: sim_t, sim_setup, sim_run, sim_step, checkpoint_t, setup_model, &
      run_options_t, memory_text, run_base_bytes, run_cell_bytes, ring_span_at_start, &
      ring_retry, ring_memory_note

   !> The characteristic steps (spb_ring) stand in for the lattice's over a span of at least
   !> ring_min_steps steps of a bar of at least ring_min_cells cells: below either the
   !> lattice is faster (doc/method.md, "Characteristic stepping of intact stretches").
   integer, parameter :: ring_min_steps = 40
   integer, parameter :: ring_min_cells = 16
   !> The shortest stretch a ring holds [cells]: a short ring's step (one block of 64 values
   !> to bound) costs about what the update of 6 to 8 junction nodes does, so a shorter
   !> fragment stays in the junctions (the Weibull spall sweep's scabs of 9 to 15 cells: 8 %
   !> fewer instructions as rings, doc/benchmarks.md, seventh round); whether the rings serve
   !> the bar at all is spb_ring ring_layout's cost test (a long ring near its strength).
   integer, parameter :: ring_min_stretch = 8
   !> A try of the characteristic steps that stops within ring_min_steps steps makes the next
   !> wait (take_steps: twice as long after each such try, at most this many steps): a bar
   !> whose tests come near their thresholds in nearly every step (zero strength), or whose
   !> events come a few steps apart, keeps the lattice's cost.
   integer, parameter :: ring_wait_max = 4096
   !> In a batch log the first progress line comes after this at the latest, whatever
   !> --progress asks for the lines after it: with the set-up (4 s for 5e6 cells) and a look
   !> at the clock every 2^24 cell-steps, within 10 s of the start (issue 32) [s].
   real(wp), parameter :: first_batch_seconds = 5.0_wp

   !> Memory of a run, resident bytes (Release, /usr/bin/time -f %M): 204 MB with 1e6 cells,
   !> 395 MB with 2e6, 778 MB with 4e6: 196 bytes per cell over about 13 MB. Counted: mesh
   !> 76 (seg; dx, dm, z, stiff; x, ma, mb, inv_m, m_above), state 100 (ua, ub, dua, dub,
   !> s, s_old, section, strength, cell_strength; joined, cracked, is_cut; the genealogy's
   !> three integers; split), init_state's u, s, v 24: 200 per cell; the cells' areas (issue
   !> 20) 8 more (measured 809 MB with 4e6 cells: 204 per cell).
   real(wp), parameter :: run_base_bytes = 16.0e6_wp      !! program, libraries [bytes]
   real(wp), parameter :: run_cell_bytes = 208.0_wp       !! per cell [bytes]
   !> The characteristic steps' arrays per cell while they last (spb_ring: the sequences,
   !> their blocks, one ring's running sums of F and G at the conversion back) [bytes]:
   !> measured 75 at 1e6 cells in one ring, 99 in four rings that can break (their sections'
   !> sequences; the same in 0.6.4, which counted 80)
   real(wp), parameter :: ring_cell_bytes = 104.0_wp
   !> With gauges, the running sums of every ring a gauge reads, kept through a span (their
   !> readings inside it, spb_ring read_ring_gauges) [bytes per cell]: measured 34 (1e6 cells,
   !> four rings, a gauge in each)
   real(wp), parameter :: ring_gauge_bytes = 40.0_wp
   !> The gauges' readings kept for one call of advance_rings (ring_steps), at most [values]
   !> (8 MiB: 3495 steps of 100 gauges)
   integer, parameter :: ring_gauge_values = 2**20
   !> --restart reads the checkpoint's state beside the run's: measured 372 bytes per cell
   !> (4e5 and 8e5 cells), 176 more than a run.
   real(wp), parameter :: restart_cell_bytes = 200.0_wp   !! per cell [bytes]
   !> hdf5 with field_every: per cell, write_field's u, v, s and /mesh/x_half (2 half nodes,
   !> 8 bytes: 64), and per buffered time 64 (the buffer's u, v, stress: 48; write_xt's copy
   !> of one of them: 16). Measured with 64 times (2e5 and 4e5 cells): 4130 bytes per cell
   !> more than a run; counted 64 + 64 x 64 = 4160. A restart replays the old file's x-t
   !> rows as many times at once: 48 more per time.
   real(wp), parameter :: xt_cell_bytes = 64.0_wp          !! per cell [bytes]
   real(wp), parameter :: xt_time_bytes = 64.0_wp          !! per cell and time [bytes]
   real(wp), parameter :: replay_time_bytes = 48.0_wp      !! per cell and time [bytes]
   integer, parameter :: xt_rows_max = 64                  !! x-t times buffered at most

   !> Columns of the history kept in memory at its history_every rows (a sweep's ensemble,
   !> spb_sweep: its cases write no files): samples(:, k) holds the columns ids at the k-th
   !> row (spb_schedule row_index), whether or not PREFIX.his is written.
   type :: sampler_t
      logical :: on = .false.                        !! columns are kept
      integer, allocatable :: ids(:)                 !! the columns (places in history_set)
      type(history_ids_t) :: his_id                  !! the history's ids (post_history)
      integer :: width = 0                           !! the history's columns
      real(wp), allocatable :: samples(:, :)         !! (column, row)
   end type sampler_t

   !> What a run carries from step to step besides the simulation: its outputs, the
   !> events of the step, the schedule, and the clock.
   type :: run_t
      type(outputs_t) :: out
      type(event_list_t) :: events
      type(schedule_t) :: sched
      logical :: to_files = .true.                   !! write the outputs
      logical :: progress = .false.                  !! show a progress line on stderr
      real(wp) :: batch_seconds = 0.0_wp             !! a progress line every so many seconds
                                                     !! (stderr not a terminal; 0: none)
      integer(int64) :: c_batch = 0                  !! system_clock at the last batch line
      logical :: batch_shown = .false.               !! a batch line was written
      logical :: ck_on = .false.                     !! write checkpoints
      integer :: next_profile = 1                    !! index of the next profile in sched%at
      integer(int64) :: c0 = 0, c_last = 0, rate = 1 !! system_clock at the start, at the
                                                     !! last progress line; ticks per second
      type(sampler_t) :: sampler                     !! history columns kept at the rows
      logical :: span_ended = .false.                !! this step ended a span of
                                                     !! characteristic steps (its check)
   end type run_t

   !> What the run loop does besides stepping (the deck's &run settings).
   type :: run_options_t
      integer :: history_every = 1                   !! steps between history rows
      integer :: field_every = 0                     !! steps between x-t field rows (0: none)
      real(wp), allocatable :: profile_times(:)      !! profile times [s]
      character(len=:), allocatable :: checkpoint    !! checkpoint file ('': none)
      integer :: checkpoint_every = 0                !! steps between checkpoints (0: at the end)
      real(wp) :: energy_guard = 0.5_wp              !! the energy guard's share (0: off) [-]
      integer :: xt_rows = xt_rows_max               !! x-t times buffered (fewer when memory
                                                     !! is short)
      integer :: gauge_every = 1                     !! steps between gauge rows
      logical :: rings = .true.                      !! characteristic steps where a bar
                                                     !! qualifies (spb_ring); .false.: the
                                                     !! lattice always (SPALLBAR_STEPPING)
      logical :: rings_dropped = .false.             !! asked for, but their arrays did not
                                                     !! fit (sim_setup): the lattice always
   end type run_options_t

   type :: sim_t
      type(problem_t) :: prob                        !! what the model solves
      type(run_options_t) :: opt                     !! what the run loop does besides
      type(deck_record_t) :: record                  !! what the outputs and checkpoints say
                                                     !! of the deck
      type(mesh_t) :: mesh
      type(load_t) :: load
      type(state_t) :: st
      type(gauge_t), allocatable :: gauges(:)        !! &gauges (none: no PREFIX.gau)
      character(len=200), allocatable :: report(:)   !! mesh fit report
   end type sim_t


contains

   !> A striking mass's energy at stake, for the energy guard's scale: its kinetic energy
   !> and its weight over its gap to the face, M |g| gap (0 without one) [J/m^2 A].
   pure real(wp) function striker_scale(sim) result(e)
      type(sim_t), intent(in) :: sim       !! the simulation
      integer :: side
      e = 0.0_wp
      do side = face_top, face_bottom
         if (.not. is_striker(sim%st%ends(side))) cycle
         associate (m => sim%st%ends(side))
            e = e + 0.5_wp * m%mass * m%striker%v**2 + m%mass * abs(sim%prob%gravity) * m%gap0
         end associate
      end do
   end function striker_scale

   !> Build mesh, load and initial state from a validated deck, once the memory they need
   !> (and the outputs', a restart's) is known to fit.
   subroutine sim_setup(deck, sim, err, restart, files, rings, limit, extra)
      type(deck_t), intent(in) :: deck     !! the deck
      type(sim_t), intent(out) :: sim      !! the simulation
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      logical, intent(in), optional :: restart   !! it goes on from a checkpoint
      logical, intent(in), optional :: files     !! it writes its outputs (default .true.)
      logical, intent(in), optional :: rings     !! characteristic steps where they serve
                                                 !! (default; .false.: the lattice always)
      real(wp), intent(in), optional :: limit    !! the memory this process may use, when the
                                                 !! caller knows it (default sys_memory_limit)
                                                 !! [bytes]
      real(wp), intent(in), optional :: extra    !! memory needed besides (a sweep's tables)
                                                 !! [bytes]
      type(wave_t) :: w0
      real(wp) :: beside, lim
      logical :: with_files, restarted, may_serve
      with_files = .true.
      if (present(files)) with_files = files
      if (present(rings)) sim%opt%rings = rings
      ! the echo only where files show it
      sim%record = deck_record(deck, echo=with_files)
      sim%opt%history_every = deck%run%history_every
      sim%opt%field_every = deck%run%field_every
      sim%opt%profile_times = deck%run%profile_times(1:deck%run%n_profiles)
      sim%opt%checkpoint = deck_file(deck, deck%run%checkpoint)
      sim%opt%checkpoint_every = deck%run%checkpoint_every
      sim%opt%energy_guard = deck%run%energy_guard
      sim%opt%gauge_every = sim%record%gauge_every
      beside = 0.0_wp
      if (present(extra)) beside = extra
      ! the limit asked once for both checks (it reads the cgroup's files)
      if (present(limit)) then
         lim = limit
      else
         lim = real(sys_memory_limit(), wp)
      end if
      call setup_model(deck, sim%prob, sim%mesh, sim%load, sim%report, err, files=files, &
                       restart=restart, extra=beside, xt_rows=sim%opt%xt_rows, limit=lim)
      if (allocated(err)) return
      allocate(sim%gauges(size(sim%record%gauge_x)))
      call locate_gauges(sim%mesh, sim%record%gauge_x, sim%gauges, sim%record%gauge_below)
      call watch_gauges(sim%mesh, sim%gauges)
      ! the model, chosen once: the half-mass model, or the full-mass comparison model, which
      ! sets up its own masses and state (spb_full_mass)
      if (sim%prob%full_mass) then
         call init_full_mass(sim%prob, sim%mesh, sim%st)
      else
         call init_state(sim%prob, sim%mesh, sim%st)
      end if
      ! the start holds none of the lattice's zig-zag mode (spb_wave; issue 17)
      call start_without_zigzag(sim%mesh, sim%prob%gravity, sim%st)
      ! the work of constant-velocity ends on the continuum state counts from t = 0: its part
      ! that is a function of the reading (wave_t%w_support) starts from its value then
      if (any(is_velocity_end(sim%st%ends))) then
         w0 = wave_energy(sim%mesh, sim%st, sim%prob%gravity, 0.0_wp, 0.0_wp)
         sim%st%ledger%w_wave = -w0%w_support
      end if
      ! a bar the characteristic steps may serve, from its start or later, in a run (whose
      ! outputs' periods let a span last ring_min_steps steps) or a sweep's case (no
      ! outputs), needs their arrays too (ring_bytes while they last): where
      ! they do not fit beside the run in the memory this process may use, every step is
      ! the lattice's, the same results to round-off (doc/method.md, "Memory"; the run says
      ! so, ring_memory_note); where they fit, the x-t buffer is sized with them counted
      may_serve = sim%opt%rings .and. sim%mesh%n >= ring_min_cells
      if (may_serve .and. with_files) may_serve = ring_period(sim) > 0
      if (may_serve) then
         restarted = .false.
         if (present(restart)) restarted = restart
         block
            type(spb_error_t), allocatable :: no_fit
            integer :: rows
            call plan_memory(deck, sim%mesh%n, with_files, restarted, &
                             beside + ring_bytes(sim), rows, no_fit, lim)
            if (allocated(no_fit)) then
               sim%opt%rings = .false.
               sim%opt%rings_dropped = .true.
            else
               sim%opt%xt_rows = rows
            end if
         end block
      end if
   end subroutine sim_setup

   !> The memory the characteristic steps may take besides the run's (sim_setup) [bytes]:
   !> their arrays, and with gauges every ring's running sums and a block's readings.
   pure real(wp) function ring_bytes(sim) result(bytes)
      type(sim_t), intent(in) :: sim       !! the simulation, set up
      bytes = real(sim%mesh%n, wp) * ring_cell_bytes
      if (size(sim%gauges) > 0) bytes = bytes + real(sim%mesh%n, wp) * ring_gauge_bytes + &
                                        8.0_wp * real(ring_gauge_values, wp)
   end function ring_bytes

   !> What a run says when the characteristic steps' arrays did not fit (sim_setup): a
   !> line for stderr, '' when they fit or were not asked for.
   function ring_memory_note(sim, restarted) result(note)
      type(sim_t), intent(in) :: sim       !! the simulation, set up
      logical, intent(in) :: restarted     !! it goes on from a checkpoint
      character(len=:), allocatable :: note
      note = ''
      if (.not. sim%opt%rings_dropped) return
      note = 'spallbar: note: the arrays of the characteristic steps (doc/method.md, ' // &
         '"Memory"; about ' // memory_text(ring_bytes(sim)) // &
         ' for ' // itoa(sim%mesh%n) // ' cells) do not fit beside the run in the ' // &
         'memory this process may use (' // memory_text(real(sys_memory_limit(), wp)) // &
         '): every step is the lattice''s, slower, with the same results to round-off'
      if (restarted) note = note // '; a restart is then bit-identical only to a run that ' // &
         'took its steps on the lattice too'
   end function ring_memory_note

   !> The problem of a validated deck, its mesh and its load (the load table read here, after
   !> the mesh: a deck with faults in both reports the mesh's first). Before the mesh is
   !> built, the memory of the run is checked against the limit (plan_memory).
   subroutine setup_model(deck, prob, mesh, load, report, err, files, restart, extra, xt_rows, &
                          limit)
      type(deck_t), intent(in) :: deck     !! the deck
      type(problem_t), intent(out) :: prob   !! the problem
      type(mesh_t), intent(out) :: mesh    !! the mesh
      type(load_t), intent(out) :: load    !! the end load
      character(len=200), allocatable, intent(out) :: report(:)   !! mesh fit report
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      logical, intent(in), optional :: files     !! the run writes its outputs (default .true.)
      logical, intent(in), optional :: restart   !! it goes on from a checkpoint
      real(wp), intent(in), optional :: extra    !! memory needed besides (a sweep's tables)
                                                 !! [bytes]
      integer, intent(out), optional :: xt_rows  !! x-t times the run may buffer
      real(wp), intent(in), optional :: limit    !! the memory this process may use, when the
                                                 !! caller knows it (default sys_memory_limit)
                                                 !! [bytes]
      type(mesh_fault_t) :: fault
      integer :: n, rows
      logical :: with_files, restarted
      real(wp) :: beside
      with_files = .true.
      if (present(files)) with_files = files
      restarted = .false.
      if (present(restart)) restarted = restart
      beside = 0.0_wp
      if (present(extra)) beside = extra
      prob = problem_from_deck(deck)
      call mesh_size(prob, n, fault)
      if (fault%kind == fault_none) then
         call plan_memory(deck, n, with_files, restarted, beside, rows, err, limit)
         if (allocated(err)) return
         if (present(xt_rows)) xt_rows = rows
      end if
      call build_mesh(prob, mesh, report, fault)
      if (fault%kind /= fault_none) then
         call make_error(err, mesh_fault_message(fault, prob))
         return
      end if
      if (prob%load_kind == load_table) then
         call read_table(deck_file(deck, deck%load%table), prob%table_t, prob%table_p, err)
         if (allocated(err)) return
      else if (len_trim(deck%load%table) > 0) then
         ! a table given with another kind is not used, but a missing or malformed one is a
         ! mistake in the deck all the same (doc/deck.md)
         block
            real(wp), allocatable :: t_unused(:), p_unused(:)
            call read_table(deck_file(deck, deck%load%table), t_unused, p_unused, err)
            if (allocated(err)) return
         end block
      end if
      call build_load(prob, load)
   end subroutine setup_model

   !> Whether a run of n cells fits in the memory this process may use (sys_memory_limit),
   !> before anything of its size is allocated: the mesh and state (refused naming &mesh
   !> cells or dt), then with hdf5 and field_every the x-t buffer, which holds 64 times or
   !> as many as fit, at least one (refused naming field_every).
   subroutine plan_memory(deck, n, files, restart, extra, xt_rows, err, limit_in)
      type(deck_t), intent(in) :: deck     !! the deck
      integer, intent(in) :: n             !! cells of the mesh
      logical, intent(in) :: files         !! the run writes its outputs
      logical, intent(in) :: restart       !! it goes on from a checkpoint
      real(wp), intent(in) :: extra        !! memory needed besides [bytes]
      integer, intent(out) :: xt_rows      !! x-t times it may buffer
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      real(wp), intent(in), optional :: limit_in   !! the memory this process may use, when
                                                   !! the caller knows it (default
                                                   !! sys_memory_limit, which reads the
                                                   !! cgroup's files: a sweep asks once)
                                                   !! [bytes]
      real(wp) :: limit, need, per_time, one
      character(len=:), allocatable :: what
      if (present(limit_in)) then
         limit = limit_in
      else
         limit = real(sys_memory_limit(), wp)
      end if
      need = extra + run_base_bytes + real(n, wp) * run_cell_bytes
      if (restart) need = need + real(n, wp) * restart_cell_bytes
      xt_rows = xt_rows_max
      if (need > limit) then
         ! (the message made only here: a sweep checks every case, twice)
         if (deck%mesh%cells > 0) then
            what = '&mesh: cells = ' // itoa(deck%mesh%cells)
         else
            what = '&mesh: dt = ' // rtoa(deck%mesh%dt) // ' s gives ' // itoa(n) // &
                   ' cells, which'
         end if
         call make_error(err, what // ' needs about ' // memory_text(need) // &
                         ' of memory; the limit here is ' // memory_text(limit))
         return
      end if
      if (.not. (files .and. deck%run%hdf5 .and. deck%run%field_every > 0)) return
      per_time = real(n, wp) * xt_time_bytes
      if (restart) per_time = per_time + real(n, wp) * replay_time_bytes
      need = need + real(n, wp) * xt_cell_bytes
      one = need + per_time
      if (one > limit) then
         call make_error(err, '&run: field_every = ' // itoa(deck%run%field_every) // &
            ' (hdf5 x-t rows of ' // itoa(n) // ' cells) needs about ' // memory_text(one) // &
            ' of memory with one row buffered; the limit here is ' // memory_text(limit))
         return
      end if
      xt_rows = int(min(real(xt_rows_max, wp), (limit - need) / per_time))
   end subroutine plan_memory

   !> An amount of memory for a message: '9.6 GB', '50.0 MB'.
   function memory_text(bytes) result(text)
      real(wp), intent(in) :: bytes        !! the amount [bytes]
      character(len=:), allocatable :: text
      character(len=24) :: buf
      if (bytes >= 1.0e9_wp) then
         write(buf, '(f24.1)') bytes / 1.0e9_wp
         text = trim(adjustl(buf)) // ' GB'
      else
         write(buf, '(f24.1)') bytes / 1.0e6_wp
         text = trim(adjustl(buf)) // ' MB'
      end if
   end function memory_text

   !> One step of the whole method: the trial update, collisions by the timing rule, then
   !> fracture and separation at t^{n+1}.
   pure subroutine sim_step(sim, events)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(event_list_t), intent(inout) :: events   !! events of this step are appended
      real(wp) :: i_top, i_bot
      associate (p => sim%prob)
         call advance(sim%mesh, sim%load, p%gravity, sim%st)
         if (any(is_striker(sim%st%ends))) call striker_events(sim%mesh, sim%st, events)
         call face_load_integrals(sim%mesh, sim%load, sim%st%step, sim%st, i_top, i_bot)
         call contact_step(sim%mesh, sim%st, p%gravity, p%timing, p%shift, events, i_top, &
                           i_bot, p%events, p%eps_rel)
         call fracture_step(sim%mesh, sim%st, p%gravity, p%eps_rel, events, p%events, i_top, &
                            i_bot)
      end associate
   end subroutine sim_step

   !> The impacts and releases of the step just taken (spb_ends strike_events), before the
   !> events the step's state makes at t^{n+1}.
   pure subroutine striker_events(mesh, st, events)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state after the step
      type(event_list_t), intent(inout) :: events   !! events of this step are appended
      integer :: top, bot
      call fragment_span(mesh, st, mesh%n, top, bot)
      call strike_events(st%ends(face_top), st%step - 1, 0, mesh%x(0), mesh%z(1), mesh%dt, &
                         st%gen%frag_id(0), events)
      call strike_events(st%ends(face_bottom), st%step - 1, mesh%n, mesh%x(mesh%n), &
                         mesh%z(mesh%n), mesh%dt, st%gen%frag_id(top), events)
   end subroutine striker_events

   !> Run to t_end writing PREFIX.his, .prf, .evt, .frg, .imp (with files = .false.: no files,
   !> only the summary, as a sweep's cases do). With resume: go on from a checkpoint, the
   !> outputs continuing those of the run that wrote it (bit-identical to one run).
   !> With &run checkpoint: write it every checkpoint_every steps, at t_end and when a
   !> signal stops the run. What happens between steps is the schedule's (spb_schedule).
   subroutine sim_run(sim, prefix, progress, summary, err, files, resume, batch_seconds, notes, &
                      sample_ids, samples)
      type(sim_t), intent(inout) :: sim    !! the simulation
      character(len=*), intent(in) :: prefix   !! output path prefix
      logical, intent(in) :: progress          !! show a progress line on stderr (a terminal)
      type(run_summary_t), intent(out) :: summary   !! the run's summary
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      logical, intent(in), optional :: files   !! write the outputs (default .true.)
      type(checkpoint_t), intent(in), optional :: resume   !! continue from this checkpoint
      real(wp), intent(in), optional :: batch_seconds   !! a progress line every so many
                                                        !! seconds, each on its own line (a
                                                        !! batch log; 0 or absent: none)
      character(len=*), intent(in), optional :: notes(:)   !! lines for stderr once the run
                                                           !! is sure to start (warnings): a
                                                           !! refusal stays one line
      integer, intent(in), optional :: sample_ids(:)   !! history columns to keep (their places
                                                       !! in spb_history history_set)
      real(wp), allocatable, intent(out), optional :: samples(:, :)   !! with sample_ids: those
                                                       !! columns at the history_every rows,
                                                       !! (column, row: spb_schedule row_index);
                                                       !! a row the run did not reach is 0
      type(run_t) :: run
      integer(int64) :: c_now
      logical :: stop_now

      run%to_files = .true.
      if (present(files)) run%to_files = files
      run%progress = progress
      if (present(batch_seconds)) run%batch_seconds = batch_seconds
      if (present(sample_ids)) call start_sampler(run%sampler, sample_ids, &
         row_count(max(sim%opt%history_every, 1), sim%mesh%nsteps))
      call start_run(sim, run, summary, prefix, err, resume)
      if (allocated(err)) return
      if (present(notes)) then
         block
            integer :: k
            do k = 1, size(notes)
               if (len_trim(notes(k)) > 0) write(error_unit, '(a)') trim(notes(k))
            end do
         end block
      end if
      if (.not. present(resume)) call first_rows(sim, run, summary, err)
      do while (sim%st%step < sim%mesh%nsteps)
         call take_steps(sim, run, summary)
         call after_step(sim, run, summary, err, stop_now)
         if (stop_now) exit
      end do
      ! the last row at t_end when it is not a history_every row (written after the
      ! checkpoint: a run extended from there does not have it)
      if (.not. allocated(err) .and. sim%st%step == sim%mesh%nsteps .and. &
          .not. is_due(run%sched, act_row, sim%mesh%nsteps)) call row(sim, run, summary, err)
      if (.not. allocated(err) .and. sim%st%step == sim%mesh%nsteps .and. size(sim%gauges) > 0 &
          .and. .not. is_due(run%sched, act_gauge, sim%mesh%nsteps)) call gauge_row(sim, run)
      call system_clock(c_now)
      if (progress) write(error_unit, '(a)') ''
      ! the episodes still open at the end of a complete run (doc/outputs.md, PREFIX.imp)
      if (.not. allocated(err) .and. sim%st%step == sim%mesh%nsteps) then
         call diag_close(summary%diag)
         call take_impacts(run, summary%diag)
      end if
      if (run%to_files) then
         block
            type(spb_error_t), allocatable :: err_close
            if (.not. allocated(err)) call write_diag_h5(run%out, summary%diag)
            call close_outputs(run%out, err_close)
            if (allocated(err_close) .and. .not. allocated(err)) call move_alloc(err_close, err)
            ! the outputs of a complete run replace the previous ones; a run that failed
            ! leaves them as they were and says where its own are (doc/outputs.md)
            if (.not. allocated(err)) call publish_outputs(run%out, err)
            if (allocated(err)) err%message = err%message // where_outputs(run%out)
            ! PREFIX.spl: written once the others are published
            if (.not. allocated(err)) call write_diag_text(prefix, sim%record, sim%mesh, &
                                                           sim%report, summary%diag, err)
         end block
      end if
      call summary_end(summary, sim%st%step, &
                       real(c_now - run%c0, wp) / real(max(run%rate, 1_int64), wp))
      if (present(samples) .and. run%sampler%on) call move_alloc(run%sampler%samples, samples)
   end subroutine sim_run

   !> Keep the history columns ids at each of rows rows.
   pure subroutine start_sampler(sampler, ids, rows)
      type(sampler_t), intent(out) :: sampler   !! the columns kept
      integer, intent(in) :: ids(:)        !! the columns (places in history_set)
      integer, intent(in) :: rows          !! the rows (spb_schedule row_count)
      type(column_set_t) :: set
      sampler%on = .true.
      sampler%ids = ids
      call register_history(set, sampler%his_id)
      sampler%width = size(set%col)
      allocate(sampler%samples(size(ids), rows), source=0.0_wp)
   end subroutine start_sampler

   !> Open (or resume) the outputs, check the checkpoint path, and lay out the schedule.
   subroutine start_run(sim, run, summary, prefix, err, resume)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      type(checkpoint_t), intent(in), optional :: resume   !! checkpoint to resume from
      associate (opt => sim%opt)
         run%ck_on = run%to_files .and. len(opt%checkpoint) > 0
         if (run%to_files) call claim_outputs(prefix, sim%record, opt%checkpoint, err)
         if (allocated(err)) return
         if (run%ck_on) call check_checkpoint_path(opt%checkpoint, err)
         if (allocated(err)) return
         if (present(resume)) then
            call resume_outputs(prefix, sim%record, sim%mesh, sim%report, resume%marks, run%out, &
                                err, xt_rows=opt%xt_rows)
            if (allocated(err)) return
            sim%st = resume%st
            ! what a checkpoint does not keep of the cohesive cracks: the deck's guard and
            ! the list of cracks a step opens (empty between steps)
            if (sim%st%coh%on) then
               sim%st%coh%eps_rel = sim%prob%eps_rel
               allocate(sim%st%coh%pending(max(1, sim%mesh%n)), source=0)
               allocate(sim%st%coh%pending_stress(max(1, sim%mesh%n)), source=0.0_wp)
               sim%st%coh%n_pending = 0
            end if
            summary = resume%summary
         else if (run%to_files) then
            call drop_set_aside(prefix)
            call open_outputs(prefix, sim%record, sim%mesh, sim%report, run%out, err, &
                              xt_rows=opt%xt_rows, temporaries=.true.)
            if (allocated(err)) return
         end if
         run%sched%n_end = sim%mesh%nsteps
         ! rows where they are written or kept (a sweep's case without ensemble columns
         ! keeps none: its running values are taken at the checks, doc/sweeps.md)
         if (keeps_rows(run%to_files, run%sampler%on)) then
            call schedule_every(run%sched, act_row, opt%history_every)
         else
            call schedule_every(run%sched, act_row, 0)
         end if
         call schedule_every(run%sched, act_check, check_every)
         ! x-t field rows and profiles only where they are written (they end the spans of
         ! characteristic steps)
         if (run%to_files) call schedule_every(run%sched, act_field, opt%field_every)
         if (run%ck_on) call schedule_every(run%sched, act_checkpoint, opt%checkpoint_every)
         if (size(sim%gauges) > 0 .and. run%to_files) call schedule_every(run%sched, act_gauge, &
                                                                          opt%gauge_every)
         call schedule_every(run%sched, act_progress, progress_period(sim%mesh%n))
         if (run%to_files) then
            call schedule_at(run%sched, nint(opt%profile_times / sim%mesh%dt))
         else
            call schedule_at(run%sched, [integer ::])
         end if
      end associate
      ! the first profile still to write
      run%next_profile = 1
      if (present(resume)) then
         do while (run%next_profile <= size(run%sched%at))
            if (run%sched%at(run%next_profile) > sim%st%step) exit
            run%next_profile = run%next_profile + 1
         end do
      end if
      call system_clock(run%c0, run%rate)
      run%c_last = run%c0
      run%c_batch = run%c0
   end subroutine start_run

   !> The energy references and the rows, profiles and fields of t = 0.
   subroutine first_rows(sim, run, summary, err)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(energies_t) :: e0
      type(wave_t) :: w0
      real(wp) :: w_w, e_l, scale
      e0 = energies(sim%mesh, sim%st, sim%prob%gravity)
      call diag_start(summary%diag, sim%mesh, sim%st)
      call measure(sim%mesh, sim%load, sim%st, sim%prob%gravity, e0, w0, w_w, e_l, scale)
      call summary_start(summary, e0, w0, w_w, e_l, scale, &
                         sim%st%section(sim%mesh%n) / sim%mesh%area(sim%mesh%n))
      call row(sim, run, summary, err)
      if (run%sched%every(act_gauge) > 0) call gauge_row(sim, run)
      call profiles(sim, run)
      if (run%sched%every(act_field) > 0 .and. run%to_files) then
         call write_field(run%out, sim%mesh, sim%st)
      end if
   end subroutine first_rows

   !> The steps up to the next one at which an action is due: those before it in one
   !> cache-blocked call where the bar is joined and nothing can break, or in characteristic
   !> form where most of it lies in intact homogeneous stretches (spb_ring: they stop before a
   !> step in which a node could break or two faces could touch), then that step with its
   !> events (written and counted).
   subroutine take_steps(sim, run, summary)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(ring_layout_t) :: lay
      integer :: k, kr, j, n0, short
      real(wp) :: sec_max
      real(wp), allocatable :: face_du(:, :)
      ! (k: to the next due action, the checks every 64 steps and the progress lines
      ! included, for the lattice; kr: a span of characteristic steps passes over those)
      k = next_due(run%sched, sim%st%step, run%next_profile) - sim%st%step
      short = -1
      if (use_rings(sim, summary)) then
         kr = ring_span(sim, run)
         if (kr - 1 >= ring_min_steps) then
            lay = ring_layout(sim%mesh, sim%st, ring_min_stretch)
            if (lay%worth) then
               call ring_steps(sim, run, summary, lay, kr - 1, short)
               run%span_ended = .true.
               k = 0
            else
               ! the lattice serves this bar: its layout is looked at again ring_min_steps
               ! steps on (not at every step: it costs about a microsecond)
               sim%st%ring_next = sim%st%step + ring_min_steps
            end if
         end if
      end if
      if (k > 1 .and. joined_only(sim%mesh, sim%st)) then
         allocate(face_du(2, k - 1))
         n0 = sim%st%step
         call advance_joined(sim%mesh, sim%load, sim%prob%gravity, sim%st, k - 1, &
                             max_sec_bottom=sec_max, face_du=face_du)
         call summary_reaction(summary, sec_max / sim%mesh%area(sim%mesh%n))
         call diag_end_samples(summary%diag, sim%mesh, n0, face_du)
      end if
      run%events%n = 0
      call sim_step(sim, run%events)
      call ring_retry(short, run%events%n > 0, sim%st%step, sim%st%ring_wait, sim%st%ring_next)
      call summary_reaction(summary, sim%st%section(sim%mesh%n) / sim%mesh%area(sim%mesh%n))
      call diag_step(summary%diag, sim%mesh, sim%st, run%events)
      call take_impacts(run, summary%diag)
      if (run%events%n == 0) return
      ! the events' section forces as stresses over their sections (spb_mesh)
      do j = 1, run%events%n
         associate (ev => run%events%e(j))
            ev%stress = ev%stress / node_area(sim%mesh, ev%node)
            ev%stress_bound = ev%stress_bound / node_area(sim%mesh, ev%node)
         end associate
      end do
      if (run%to_files) call write_events(run%out, run%events)
      call summary_events(summary, run%events)
   end subroutine take_steps

   !> The characteristic steps may serve this bar now (spb_ring ring_qualifies), the last
   !> try's wait is over, and every contact episode under way is one a section carries
   !> (spb_diagnostics: its force is sampled step by step).
   pure logical function use_rings(sim, summary)
      type(sim_t), intent(in) :: sim       !! the simulation
      type(run_summary_t), intent(in) :: summary   !! the run's summary (its episodes)
      use_rings = sim%opt%rings .and. sim%mesh%n >= ring_min_cells .and. &
                  sim%st%step >= sim%st%ring_next
      if (use_rings) use_rings = ring_qualifies(sim%mesh, sim%st)
      if (use_rings) use_rings = contacts_by_sections(summary%diag)
   end function use_rings

   !> For the estimate before a run: the steps between the conversions where the
   !> characteristic steps serve the bar at its state now (use_rings, the rings holding three
   !> quarters of it), from the periods of the outputs that end a span (history rows, x-t
   !> fields, checkpoints); 0 where they do not serve it or the spans are too short.
   pure integer function ring_span_at_start(sim) result(span)
      type(sim_t), intent(in) :: sim       !! the simulation, set up
      type(ring_layout_t) :: lay
      type(run_summary_t) :: none
      span = 0
      if (.not. use_rings(sim, none)) return
      lay = ring_layout(sim%mesh, sim%st, ring_min_stretch)
      if (.not. lay%worth) return
      span = ring_period(sim)
   end function ring_span_at_start

   !> The steps between the conversions that the periods of a run's outputs allow (history
   !> rows, x-t rows, checkpoints; at most ring_span_max; gauge rows are read from the rings,
   !> ring_steps), 0 when a span could not last ring_min_steps steps: then the characteristic
   !> steps never serve the run.
   pure integer function ring_period(sim) result(span)
      type(sim_t), intent(in) :: sim       !! the simulation, set up
      span = min(max(sim%opt%history_every, 1), ring_span_max(sim%mesh%n))
      if (sim%opt%field_every > 0) span = min(span, sim%opt%field_every)
      if (sim%opt%checkpoint_every > 0) span = min(span, sim%opt%checkpoint_every)
      if (span - 1 < ring_min_steps) span = 0
   end function ring_period

   !> Steps to the next due action but the check between rows, the progress line and the
   !> gauge rows: the characteristic steps keep no lattice arrays to check, so that check
   !> (finiteness, the energy guard) is made at the rows and at the end of each span
   !> (doc/method.md); the gauge rows inside a span are read from the rings (ring_steps).
   pure integer function ring_span(sim, run) result(k)
      type(sim_t), intent(in) :: sim       !! the simulation
      type(run_t), intent(in) :: run       !! the run's context (its schedule)
      type(schedule_t) :: sched
      sched = run%sched
      sched%every(act_check) = 0
      sched%every(act_progress) = 0
      sched%every(act_gauge) = 0
      k = next_due(sched, sim%st%step, run%next_profile) - sim%st%step
   end function ring_span

   !> When the characteristic steps are tried next (doc/method.md, "When"), after a try that
   !> stopped early (short = 1: within ring_min_steps steps), did not (0) or was not made
   !> (-1; nothing changes): the wait doubles after each try that stopped early, at most
   !> ring_wait_max steps; ring_min_steps at once when the step had no event (a false alarm);
   !> when it had, a quarter of that marks the first such try without delaying the next
   !> (events a few steps apart: a fragmenting bar), and the waits after it double from
   !> there; a try that did not stop early ends the wait.
   pure subroutine ring_retry(short, events, step, wait, next)
      integer, intent(in) :: short         !! 1 stopped early, 0 did not, -1 no try
      logical, intent(in) :: events        !! the step that ended the try had events
      integer, intent(in) :: step          !! the step the state is at
      integer, intent(inout) :: wait       !! steps waited after the last try (0: none)
      integer, intent(inout) :: next       !! no try before this step
      if (short == 1) then
         if (.not. events) then
            wait = max(2 * wait, ring_min_steps)
         else if (wait == 0) then
            wait = ring_min_steps / 4
         else
            wait = 2 * wait
         end if
         wait = min(wait, ring_wait_max)
         next = step
         if (wait > ring_min_steps / 4) next = step + wait
      else if (short == 0) then
         wait = 0
      end if
   end subroutine ring_retry

   !> Up to nsteps characteristic steps (spb_ring: each conversion for at most ring_span_max
   !> steps), with what the run books of each: the bottom reaction, the ends' samples, the
   !> contact episodes' forces, the gauge rows due (read from the rings); the progress line
   !> where it is due. They stop early before a
   !> step in which a node could break or two faces could touch (short = 1: within
   !> ring_min_steps steps, else 0).
   subroutine ring_steps(sim, run, summary, lay, nsteps, short)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (its schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(ring_layout_t), intent(in) :: lay   !! the rings (ring_layout of this state)
      integer, intent(in) :: nsteps        !! steps to take at most
      integer, intent(out) :: short        !! 1: they stopped within ring_min_steps steps
      type(ring_hybrid_t) :: h
      real(wp), allocatable :: face_du(:, :), samples(:, :), readings(:, :, :)
      integer, allocatable :: nodes(:)
      real(wp) :: sec_max
      integer :: left, m, k, taken, n0, total, period, g_every, t
      logical :: stopped
      ! the gauge rows due inside the span, read from the rings (read_ring_gauges)
      g_every = 0
      if (run%to_files) g_every = run%sched%every(act_gauge)
      left = nsteps
      total = 0
      stopped = .false.
      call contact_nodes(summary%diag, nodes)
      period = run%sched%every(act_progress)
      do while (left > 0 .and. .not. stopped)
         m = min(left, ring_span_max(sim%mesh%n))
         call start_rings(sim%mesh, sim%st, lay, m, sim%prob%eps_rel, sim%prob%events, nodes, h)
         ! the conversion's steps in blocks that end where the progress line is due (and, with
         ! gauge rows, after at most ring_gauge_values of their values)
         do while (m > 0)
            k = m
            if (period > 0) k = min(m, period - modulo(sim%st%step, period))
            ! (the gauges' readings of a block at most ring_gauge_values values)
            if (g_every > 0) k = min(k, max(1, ring_gauge_values / (3 * size(sim%gauges))))
            if (allocated(face_du)) deallocate(face_du, samples, readings)
            allocate(face_du(2, k), samples(size(nodes), k), &
                     readings(3, size(sim%gauges), merge(k, 0, g_every > 0)))
            n0 = sim%st%step
            call advance_rings(sim%mesh, sim%load, sim%prob%gravity, sim%prob%eps_rel, sim%st, &
                               h, k, taken, sec_max, face_du, samples, sim%gauges, g_every, &
                               readings)
            if (taken > 0) then
               call summary_reaction(summary, sec_max / sim%mesh%area(sim%mesh%n))
               call diag_end_samples(summary%diag, sim%mesh, n0, face_du(:, 1:taken))
               call diag_contact_samples(summary%diag, samples(:, 1:taken), sim%mesh%dt)
            end if
            if (g_every > 0) then
               do t = 1, taken
                  if (mod(n0 + t, g_every) == 0) call write_gauge_row(run%out, &
                     real(n0 + t, wp) * sim%mesh%dt, readings(1, :, t), readings(2, :, t), &
                     readings(3, :, t))
               end do
            end if
            m = m - taken
            left = left - taken
            total = total + taken
            if (taken < k) then
               stopped = .true.
               exit
            end if
            if (period > 0 .and. m > 0) then
               if (modulo(sim%st%step, period) == 0) call progress_lines(sim, run, sim%st%step)
            end if
         end do
         call end_rings(sim%mesh, sim%prob%gravity, sim%st, h)
      end do
      short = merge(1, 0, stopped .and. total < ring_min_steps)
   end subroutine ring_steps

   !> The contact episodes that ended: their rows written (PREFIX.imp, /impacts), then gone
   !> from memory (a run without files drops them).
   subroutine take_impacts(run, d)
      type(run_t), intent(inout) :: run    !! the run's context (outputs)
      type(diag_t), intent(inout) :: d     !! the experiment diagnostics
      if (d%n_ended == 0) return
      if (run%to_files) call write_impacts(run%out, d%ended(1:d%n_ended))
      call diag_taken(d)
   end subroutine take_impacts

   !> What is due after step n: the row or the check between rows, profiles, the field row,
   !> a checkpoint, the end on a stop signal, the progress line. stop_now: the run ends here.
   subroutine after_step(sim, run, summary, err, stop_now)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      logical, intent(out) :: stop_now     !! the run ends here
      integer :: n, sig
      logical :: wrote_row
      integer(int64) :: c_now
      n = sim%st%step
      stop_now = .true.
      wrote_row = .false.
      if (is_due(run%sched, act_row, n)) then
         call row(sim, run, summary, err)
         wrote_row = .true.
         if (allocated(err)) return
      else if (is_due(run%sched, act_check, n) .or. run%span_ended) then
         ! (every 64 steps, and after a span of characteristic steps, which passes over
         ! the checks due inside it)
         call check_between_rows(sim, run, summary, err)
         if (allocated(err)) return
      end if
      run%span_ended = .false.
      if (is_due(run%sched, act_gauge, n)) call gauge_row(sim, run)
      call profiles(sim, run)
      if (is_due(run%sched, act_field, n) .and. run%to_files) then
         call write_field(run%out, sim%mesh, sim%st)
      end if
      sig = stop_signal()
      if (run%ck_on) then
         ! the state after everything of step n that an uninterrupted run writes too
         if (n == sim%mesh%nsteps .or. sig /= 0 .or. is_due(run%sched, act_checkpoint, n)) then
            call checkpoint(sim, run, summary, err)
         end if
         if (allocated(err)) return
      end if
      if (sig /= 0) then
         ! SIGTERM/SIGINT: end here with the outputs complete up to this step
         if (.not. wrote_row) call row(sim, run, summary, err)
         if (run%sched%every(act_gauge) > 0 .and. .not. is_due(run%sched, act_gauge, n)) then
            call gauge_row(sim, run)
         end if
         call make_error(err, 'run: stopped by signal ' // itoa(sig) // &
            ' at step ' // itoa(sim%st%step) // ' (t = ' // &
            rtoa(real(sim%st%step, wp) * sim%mesh%dt) // ' s); outputs up to here are ' // &
            'written and closed' // trim(merge(' (and the checkpoint)', '                     ', &
            run%ck_on)), code=128 + sig)
         ! (sim_run adds where they are when they are still the temporaries)
         return
      end if
      if (is_due(run%sched, act_progress, n)) then
         call system_clock(c_now)
         if (real(c_now - run%c_last, wp) > 0.5_wp * real(run%rate, wp)) then
            if (run%to_files) call flush_outputs(run%out)
            if (run%to_files) call check_written(run%out, err)
            if (allocated(err)) return
         end if
         call progress_lines(sim, run, n)
      end if
      stop_now = .false.
   end subroutine after_step

   !> At step n, where the progress line is due: the line on a terminal if half a second has
   !> passed since the last, a batch log's line if its interval has (the outputs' flush is
   !> after_step's, at the end of a span of characteristic steps).
   subroutine progress_lines(sim, run, n)
      type(sim_t), intent(in) :: sim       !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (its clock)
      integer, intent(in) :: n             !! the step
      integer(int64) :: c_now
      call system_clock(c_now)
      if (real(c_now - run%c_last, wp) > 0.5_wp * real(run%rate, wp)) then
         run%c_last = c_now
         if (run%progress) call show_progress(sim, n, real(c_now - run%c0, wp) / &
                                              real(run%rate, wp))
      end if
      if (run%batch_seconds > 0.0_wp .and. real(c_now - run%c_batch, wp) >= &
          batch_interval(run) * real(run%rate, wp)) then
         run%c_batch = c_now
         run%batch_shown = .true.
         call show_progress(sim, n, real(c_now - run%c0, wp) / real(run%rate, wp), batch=.true.)
      end if
   end subroutine progress_lines

   !> Seconds between batch progress lines: --progress SECONDS, but the first comes after
   !> first_batch_seconds at the latest [s].
   pure real(wp) function batch_interval(run) result(seconds)
      type(run_t), intent(in) :: run       !! the run's context (its clock)
      seconds = run%batch_seconds
      if (.not. run%batch_shown) seconds = min(seconds, first_batch_seconds)
   end function batch_interval

   !> Between rows: the state's finiteness and the energy guard (a failing one writes its row).
   subroutine check_between_rows(sim, run, summary, err)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(energies_t) :: e
      type(wave_t) :: wv
      real(wp) :: w_w, e_l
      e = energies(sim%mesh, sim%st, sim%prob%gravity)
      if (ieee_is_finite(e%ledger)) then
         call measure(sim%mesh, sim%load, sim%st, sim%prob%gravity, e, wv, w_w, e_l)
         ! a run without rows takes the summary's running values here
         if (.not. keeps_rows(run%to_files, run%sampler%on)) call summary_row(summary, &
            sim%st%step, e, wv, w_w, e_l)
         call guard(sim, summary, e, wv, w_w, err)
         if (allocated(err)) call row(sim, run, summary, err)
      else
         call row(sim, run, summary, err)
      end if
   end subroutine check_between_rows

   !> Write the checkpoint of step n (its outputs written through first).
   subroutine checkpoint(sim, run, summary, err)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(output_marks_t) :: marks
      call mark_outputs(run%out, marks)
      call check_written(run%out, err)
      if (allocated(err)) return
      call summary_checkpoint(summary, sim%st%step)
      call write_checkpoint(sim%opt%checkpoint, sim%record, sim%mesh, sim%load, &
                            sim%st, summary, marks, err)
      ! a checkpoint continues these outputs: from here on they are the run's (doc/outputs.md)
      if (.not. allocated(err)) call publish_outputs(run%out, err)
   end subroutine checkpoint

   !> One history row (and the run summary's running values); a state that is not finite
   !> ends the run here (exit 3), naming the first bad node.
   subroutine row(sim, run, summary, err)
      type(sim_t), intent(inout) :: sim    !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(energies_t) :: e
      type(wave_t) :: wv
      real(wp) :: w_w, e_l, g
      integer :: i
      g = sim%prob%gravity
      e = energies(sim%mesh, sim%st, g)
      if (.not. ieee_is_finite(e%ledger)) then
         ! the first node whose displacements, increments or cell stress above are bad
         do i = 0, sim%mesh%n
            if (.not. (ieee_is_finite(sim%st%ua(i)) .and. ieee_is_finite(sim%st%ub(i)) .and. &
                       ieee_is_finite(sim%st%dua(i)) .and. ieee_is_finite(sim%st%dub(i)) &
                       .and. ieee_is_finite(sim%st%s(i)))) exit
         end do
         call make_error(err, 'run: the state is not finite at step ' // itoa(sim%st%step) // &
            ' (t = ' // rtoa(real(sim%st%step, wp) * sim%mesh%dt) // ' s), node ' // &
            itoa(min(i, sim%mesh%n)), code=exit_runtime)
         if (run%to_files) call flush_outputs(run%out)
         return
      end if
      call measure(sim%mesh, sim%load, sim%st, sim%prob%gravity, e, wv, w_w, e_l)
      ! the summary's running values (wv%jordan made relative to the largest momentum scale)
      call summary_row(summary, sim%st%step, e, wv, w_w, e_l)
      if (run%to_files) then
         block
            real(wp) :: v(size(run%out%his_table))   ! the row: each owner posts its columns
            v = 0.0_wp
            call post_history(run%out%his_id, sim%mesh, sim%load, sim%st, g, e, wv, w_w, e_l, v)
            call write_history_row(run%out, v)
         end block
      end if
      i = 0
      if (run%sampler%on) i = row_index(max(sim%opt%history_every, 1), sim%mesh%nsteps, &
                                        sim%st%step)
      if (i > 0) then
         block
            real(wp) :: v(run%sampler%width)   ! the row, as PREFIX.his would have it
            v = 0.0_wp
            call post_history(run%sampler%his_id, sim%mesh, sim%load, sim%st, g, e, wv, w_w, &
                              e_l, v)
            run%sampler%samples(:, i) = v(run%sampler%ids)
         end block
      end if
      call guard(sim, summary, e, wv, w_w, err)
   end subroutine row

   !> Stop when the mechanical energy exceeds the initial energy plus the work of the
   !> loads (gravity's work is in e_pot) by more than energy_guard times the scale. The
   !> energy is the wave measure (spb_wave), which no zig-zag growth can hide from.
   subroutine guard(sim, summary, e, wv, w_w, err)
      type(sim_t), intent(in) :: sim       !! the simulation
      type(run_summary_t), intent(inout) :: summary   !! the run's summary
      type(energies_t), intent(in) :: e    !! the scheme's energies (e_pot is used)
      type(wave_t), intent(in) :: wv       !! the wave measure
      real(wp), intent(in) :: w_w      !! work in that measure [J/m^2]
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      real(wp) :: excess
      character(len=16) :: b1, b2
      if (allocated(err)) return
      call summary_guard(summary, e, wv, w_w, excess, striker_scale(sim))
      associate (limit => sim%opt%energy_guard)
         if (limit > 0.0_wp .and. excess > limit * summary%guard_scale .and. &
             summary%guard_scale > 0.0_wp) then
            ! three exponent digits: es10.3 drops the E of an exponent beyond 99 (1.661+152)
            write(b1, '(es12.3e3)') excess
            write(b2, '(es12.3e3)') excess / summary%guard_scale
            call make_error(err, 'run: mechanical energy exceeds the initial energy plus the ' // &
               'work of the loads by ' // trim(adjustl(b1)) // ' ' // bar_units('J/m^2', sim%mesh) &
               // ' (' // &
               trim(adjustl(b2)) // ' of the energy scale, above ' // &
               '&run energy_guard = ' // rtoa(limit) // ') at step ' // &
               itoa(sim%st%step) // ' (t = ' // rtoa(real(sim%st%step, wp) * sim%mesh%dt) // &
               ' s); outputs up to here are written', code=exit_runtime)
            return
         end if
         ! the positions the event corrections moved with no momentum (x_drift) or left in the
         ! cells' lengths (l_defect): beyond position_guard of the bar's length the positions
         ! (gauges' u, gaps, profiles) mean nothing (doc/method.md, "Chatter")
         if (limit > 0.0_wp) call position_guard(sim, e, err)
      end associate
   end subroutine guard

   !> Stop when the event corrections have left more than position_share of the bar's length
   !> in the cells' lengths (|l_defect|, doc/outputs.md), with the energy guard. (x_drift is not
   !> guarded: a long run of many events, repeated blows, drifts by a share that grows with
   !> its length; doc/method.md, "Chatter".)
   subroutine position_guard(sim, e, err)
      type(sim_t), intent(in) :: sim       !! the simulation
      type(energies_t), intent(in) :: e    !! the state's energies (their pass sums l_defect)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      real(wp), parameter :: position_share = 0.05_wp
      real(wp) :: moved, length
      length = sim%mesh%x(sim%mesh%n) - sim%mesh%x(0)
      moved = abs(length_defect(sim%mesh, sim%st, e))
      if (moved > position_share * length) then
         call make_error(err, 'run: the event corrections have left ' // rtoa(moved) // &
            ' m in the cells'' lengths (l_defect), more than ' // rtoa(position_share) // &
            ' of the bar''s length, at step ' // itoa(sim%st%step) // ' (t = ' // &
            rtoa(real(sim%st%step, wp) * sim%mesh%dt) // ' s): the positions mean nothing ' // &
            'beyond it (a pair that joins and parts on alternate steps does this, as under ' // &
            'timing = ''delay''; doc/method.md, "Chatter"); outputs up to here are written', &
            code=exit_runtime)
      end if
   end subroutine position_guard

   !> One row of the gauges (PREFIX.gau, /gauges) at the state's time.
   subroutine gauge_row(sim, run)
      type(sim_t), intent(in) :: sim       !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      real(wp), dimension(size(sim%gauges)) :: stress, velocity, u
      if (.not. run%to_files) return
      call read_gauges(sim%mesh, sim%load, sim%st, sim%gauges, stress, velocity, u)
      call write_gauge_row(run%out, real(sim%st%step, wp) * sim%mesh%dt, stress, velocity, u)
   end subroutine gauge_row

   !> The profiles (and fragment lists) due at this step.
   subroutine profiles(sim, run)
      type(sim_t), intent(in) :: sim       !! the simulation
      type(run_t), intent(inout) :: run    !! the run's context (outputs, schedule, clock)
      type(frag_info_t), allocatable :: list(:)
      do while (run%next_profile <= size(run%sched%at))
         if (run%sched%at(run%next_profile) /= sim%st%step) exit
         if (run%to_files) then
            call write_profile(run%out, sim%mesh, sim%st, &
                               sim%opt%profile_times(run%next_profile))
            call fragment_list(sim%mesh, sim%st, list)
            call write_fragments(run%out, real(sim%st%step, wp) * sim%mesh%dt, sim%mesh%dt, list)
         end if
         run%next_profile = run%next_profile + 1
      end do
   end subroutine profiles

   !> The progress line on stderr: share done, speed, time to go; on a terminal it rewrites
   !> itself, in a batch log (batch) it is a line of its own with the step and the time.
   subroutine show_progress(sim, n_done, elapsed, batch)
      type(sim_t), intent(in) :: sim       !! the simulation
      integer, intent(in) :: n_done            !! steps done
      real(wp), intent(in) :: elapsed          !! wall time so far [s]
      logical, intent(in), optional :: batch   !! a line of its own (stderr is not a terminal)
      character(len=16) :: wall
      real(wp) :: frac, speed
      character(len=120) :: line
      frac = real(n_done, wp) / real(sim%mesh%nsteps, wp)
      speed = real(n_done, wp) / max(elapsed, 1.0e-9_wp)
      write(line, '(a,f6.1,a,es9.2,a,f9.1,a)') 'spallbar: ', 100.0_wp * frac, '%  ', speed, &
         ' steps/s  ETA ', real(sim%mesh%nsteps - n_done, wp) / speed, ' s'
      if (present(batch)) then
         write(wall, '(f16.1)') elapsed
         write(error_unit, '(a,i0,a,i0,a,es10.3,a)') trim(line) // '  (step ', n_done, &
            ' of ', sim%mesh%nsteps, ', t = ', real(n_done, wp) * sim%mesh%dt, ' s, ' // &
            trim(adjustl(wall)) // ' s wall)'
      else
         write(error_unit, '(a)', advance='no') achar(13) // trim(line)
      end if
      flush(error_unit)
   end subroutine show_progress
end module spb_sim
