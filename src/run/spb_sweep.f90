!> Sweeps (spallbar --sweep DECK, under mpirun for several ranks): the cases of &sweep —
!> Monte-Carlo realizations of the strength field, values of one deck variable, or both —
!> run without per-case files, distributed over the ranks; rank 0 writes one table
!> PREFIX.sweep and PREFIX_sweep.h5 (per-case summaries, fragment-length histograms).
!>
!> Case c (1-based) is value iv = (c - 1) / R + 1 and realization ir = mod(c - 1, R) + 1,
!> R = max(1, realizations). Every case is computed by one rank from its own deck, start to
!> end, and its row does not depend on which rank or how many there are: the table is the
!> same for any number of ranks and either distribution.
module spb_sweep
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit, int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t, make_error, exit_runtime
   use spb_strings, only: itoa, rtoa, es_into, int_into
   use spb_sys, only: stop_signal, sys_rename, sys_file_size, sys_memory_limit, sys_write_trouble
   use spb_deck, only: deck_t, validate_deck, set_deck_value, deck_value, write_echo, deck_record
   use spb_mesh, only: mesh_t
   use spb_load, only: load_t
   use spb_problem, only: problem_t
   use spb_random, only: realization_seed, realization_draw
   use spb_estimate, only: estimate_t, estimate_run, estimate_line, estimate_warnings, &
      sweep_estimate
   use spb_sim, only: sim_t, sim_setup, sim_run, setup_model, memory_text, run_base_bytes
   use spb_summary, only: run_summary_t
   use spb_diag, only: frag_info_t, fragment_list
   use spb_events, only: ev_fracture, event_kinds
   use spb_cohesive, only: dissipated
   use spb_diagnostics, only: diag_t, spall_row
   use spb_hdf5, only: h5file_t, h5_create, h5_close, h5_attr, h5_group, h5_write
   use spb_output, only: h5_deck_header, column_t, column_names, claim_sweep_outputs, program_line, &
      bar_units
   use spb_columns, only: column_set_t
   use spb_history, only: history_set
   use spb_ensemble, only: ensemble_t, ensemble_setup, ensemble_reduce, ensemble_columns_line, &
      ensemble_row, ensemble_notes, ensemble_h5, horizon_text
   use spb_par, only: par_rank, par_size, par_send, par_recv, par_wtime, par_max, par_any, &
      par_kind
   implicit none
   private
   public :: run_sweep, sweep_case_count, case_deck, run_case, sweep_summary_t

   character(len=*), parameter :: sweep_units = 'id, fragments, realization, seed, status, ' // &
      'fractures .. base_collisions, steps [-]; mean_fragment_length [m] (reference length); ' // &
      'max_reaction_bottom [Pa] (compression > 0); first_fracture_t [s] (-1: none); value: ' // &
      'the varied variable''s (0 without vary); e_kin_end, w_ext_end, ledger_drift [J/m^2]; ' // &
      'max_excess [-] (of the energy scale); e_vib_end (fragments'' vibration energy at t_end), ' // &
      'e_fracture (the fracture corrections'' energy) [J/m^2]; mean_fracture_stress [Pa] ' // &
      '(mean |section stress| at the fractures, 0: none); cracks [-] (cohesive cracks opened), ' // &
      'e_cohesive [J/m^2] (energy they dissipated); sigma_novikov_* [Pa], spall_x_*, ' // &
      'scab_thickness_* [m] (PREFIX.spl of the top and bottom end; -1: none)'
   !> PREFIX.sweep and /cases: the one list of the sweep table's columns, in order
   !> (sweep_table), but the event kinds' counts: those follow spb_events event_kinds, each
   !> under its column name, the core kinds' after status, the others' after e_fracture.
   type(column_t), parameter :: case_columns(9) = [ &
      column_t('id', '-', .true.), &
      column_t('fragments', '-', .true.), &
      column_t('mean_fragment_length', 'm', .false.), &
      column_t('max_reaction_bottom', 'Pa', .false.), &
      column_t('first_fracture_t', 's', .false.), &
      column_t('value', '-', .false.), &
      column_t('realization', '-', .true.), &
      column_t('seed', '-', .true.), &
      column_t('status', '-', .true.)]
   type(column_t), parameter :: run_columns(8) = [ &
      column_t('e_kin_end', 'J/m^2', .false.), &
      column_t('w_ext_end', 'J/m^2', .false.), &
      column_t('max_excess', '-', .false.), &
      column_t('ledger_drift', 'J/m^2', .false.), &
      column_t('steps', '-', .true.), &
      column_t('e_vib_end', 'J/m^2', .false.), &
      column_t('mean_fracture_stress', 'Pa', .false.), &
      column_t('e_fracture', 'J/m^2', .false.)]
   type(column_t), parameter :: cohesive_columns(1) = [ &
      column_t('e_cohesive', 'J/m^2', .false.)]
   !> the experiment diagnostics of each end (spb_diagnostics; PREFIX.spl), last
   type(column_t), parameter :: spall_columns(6) = [ &
      column_t('sigma_novikov_top', 'Pa', .false.), &
      column_t('spall_x_top', 'm', .false.), &
      column_t('scab_thickness_top', 'm', .false.), &
      column_t('sigma_novikov_bottom', 'Pa', .false.), &
      column_t('spall_x_bottom', 'm', .false.), &
      column_t('scab_thickness_bottom', 'm', .false.)]
   !> the event kinds with a column: core, and the others
   integer, parameter :: n_core_kinds = count(event_kinds%core .and. event_kinds%column /= '')
   integer, parameter :: n_other_kinds = count(.not. event_kinds%core .and. &
                                               event_kinds%column /= '')
   integer, parameter :: n_columns = size(case_columns) + size(run_columns) + &
      size(cohesive_columns) + n_core_kinds + n_other_kinds + size(spall_columns)
   integer, parameter :: col_id = 1, col_fragments = 2, col_mean_length = 3, col_max_reaction = 4, &
      col_first_fracture = 5, col_value = 6, col_realization = 7, col_seed = 8, col_status = 9, &
      col_e_kin = n_core_kinds + 10, col_w_ext = n_core_kinds + 11, &
      col_excess = n_core_kinds + 12, col_drift = n_core_kinds + 13, &
      col_steps = n_core_kinds + 14, col_e_vib = n_core_kinds + 15, &
      col_fracture_stress = n_core_kinds + 16, col_e_fracture = n_core_kinds + 17, &
      col_e_cohesive = n_core_kinds + n_other_kinds + 18, &
      col_spall = n_core_kinds + n_other_kinds + 19
   integer, parameter :: status_not_run = -1
   integer, parameter :: tag_request = 1000000001, tag_work = 1000000002, tag_check = 1000000003
   !> Memory of the sweep's tables per case, besides its runs [bytes]: a row (n_columns
   !> reals) in run_sweep, and write_h5's column and its whole numbers (8 + 4); per case
   !> and bin, a histogram count (default integer: 4 bytes).
   real(wp), parameter :: case_bytes = 8.0_wp * real(n_columns, wp) + 12.0_wp
   real(wp), parameter :: bin_bytes = real(storage_size(1) / 8, wp)

   !> What a sweep did (printed by the main program; the closing note's wall times).
   type :: sweep_summary_t
      integer :: cases = 0, ranks = 1
      integer :: done = 0, failed = 0, not_run = 0
      !> the signal (SIGTERM, SIGINT) that stopped the sweep on some rank, 0: none; the same
      !> on every rank
      integer :: signal = 0
      real(wp) :: wall = 0.0_wp          !! [s]
      character(len=16) :: distribution = ''
      !> with &sweep ensemble_columns: PREFIX.ens is written, and each column's horizon
      !> ('column: horizon', doc/sweeps.md "Ensembles")
      logical :: ensemble = .false.
      character(len=400), allocatable :: horizons(:)
   end type sweep_summary_t


   !> The sweep's progress lines on rank 0 (show): on a terminal, or in batch every so often.
   type :: meter_t
      logical :: terminal = .false.     !! stderr is a terminal: one line updated in place
      real(wp) :: every = 0.0_wp        !! batch: seconds between lines (0: none) [s]
      real(wp) :: t0 = 0.0_wp           !! par_wtime at the start [s]
      real(wp) :: last = 0.0_wp         !! par_wtime of the last batch line [s]
   end type meter_t

contains

   !> Number of cases: values x realizations (at least one of each).
   pure integer function sweep_case_count(deck) result(nc)
      type(deck_t), intent(in) :: deck     !! the deck
      nc = max(1, deck%sweep%n_values) * max(1, deck%sweep%realizations)
   end function sweep_case_count

   !> The deck of case c: the varied variable set to its value, the realization's seed.
   subroutine case_deck(deck, c, cdeck, value, realization, err)
      type(deck_t), intent(in) :: deck     !! the deck
      integer, intent(in) :: c                 !! case number (1..sweep_case_count)
      type(deck_t), intent(out) :: cdeck       !! the case's deck
      real(wp), intent(out) :: value           !! value of the varied variable (0: none varied)
      integer, intent(out) :: realization      !! the case's realization (0: none)
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      integer :: nrep, iv
      nrep = max(1, deck%sweep%realizations)
      iv = (c - 1) / nrep + 1
      cdeck = deck
      cdeck%is_sweep = .false.
      value = 0.0_wp
      if (deck%sweep%n_values > 0) then
         value = deck%sweep%values(iv)
         call set_deck_value(cdeck, deck%sweep%vary, value, err)
         if (allocated(err)) return
      end if
      realization = 0
      if (deck%sweep%realizations > 0) then
         realization = mod(c - 1, nrep) + 1
         cdeck%field%seed = realization_seed(deck%sweep%seed, realization)
      end if
      if (len_trim(deck%sweep%perturb) > 0) then
         ! (doc/sweeps.md, "Ensembles") the deck's value x (1 + spread u_i)
         call deck_value(deck, deck%sweep%perturb, value, err)
         if (allocated(err)) return
         value = value * (1.0_wp + deck%sweep%spread * &
                          realization_draw(deck%sweep%seed, realization))
         call set_deck_value(cdeck, deck%sweep%perturb, value, err)
         if (allocated(err)) return
      end if
      call validate_deck(cdeck, err)
   end subroutine case_deck

   !> Run case c without files: its table row and fragment-length histogram over
   !> (0, l_hist] in nbins bins (a fragment at least l_hist long counts in the last bin),
   !> and the ensemble's history columns at its rows (series: (column, row) in column order).
   subroutine run_case(deck, c, nbins, l_hist, ids, rings, row, hist, series, limit, beside)
      type(deck_t), intent(in) :: deck     !! the deck
      integer, intent(in) :: c               !! case number
      integer, intent(in) :: nbins           !! histogram bins
      real(wp), intent(in) :: l_hist         !! histogram range [m]
      integer, intent(in) :: ids(:)          !! the ensemble's columns (history_set places;
                                             !! none: no ensemble)
      logical, intent(in) :: rings           !! characteristic steps where they serve
                                             !! (spb_ring; .false.: the lattice always)
      real(wp), intent(out) :: row(n_columns)   !! the case's table row (sweep_table columns)
      integer, intent(out) :: hist(nbins)    !! fragments per length bin
      real(wp), intent(out) :: series(:)     !! the ensemble's columns at the history rows
      real(wp), intent(in), optional :: limit   !! the memory this process may use (default:
                                                !! sys_memory_limit, asked again) [bytes]
      real(wp), intent(in), optional :: beside  !! memory the sweep holds besides the case
                                                !! (its tables, the ensemble) [bytes]
      real(wp), allocatable :: samples(:, :)
      type(deck_t) :: cdeck
      type(sim_t) :: sim
      type(run_summary_t) :: summary
      type(spb_error_t), allocatable :: err
      type(frag_info_t), allocatable :: list(:)
      real(wp) :: value, length
      integer :: realization, f, b, k
      row = 0.0_wp
      hist = 0
      series = 0.0_wp
      row(col_id) = real(c, wp)
      row(col_status) = real(status_not_run, wp)
      call case_deck(deck, c, cdeck, value, realization, err)
      row(col_value) = value
      row(col_realization) = real(realization, wp)
      row(col_seed) = real(cdeck%field%seed, wp)
      if (allocated(err)) return              ! checked before any case runs
      call sim_setup(cdeck, sim, err, files=.false., rings=rings, limit=limit, extra=beside)
      if (allocated(err)) return
      if (size(ids) > 0) then
         call sim_run(sim, '', .false., summary, err, files=.false., sample_ids=ids, &
                      samples=samples)
         if (allocated(samples)) then
            if (size(samples) == size(series)) series = reshape(samples, [size(series)])
         end if
      else
         call sim_run(sim, '', .false., summary, err, files=.false.)
      end if
      row(col_status) = 0.0_wp
      if (allocated(err)) row(col_status) = real(err%code, wp)
      call fragment_list(sim%mesh, sim%st, list)
      row(col_fragments) = real(size(list), wp)
      do f = 1, size(list)
         length = sim%mesh%x(list(f)%bot) - sim%mesh%x(list(f)%top)
         row(col_mean_length) = row(col_mean_length) + length
         row(col_e_vib) = row(col_e_vib) + list(f)%e_vib
         b = min(nbins, max(1, int(length / l_hist * real(nbins, wp)) + 1))
         hist(b) = hist(b) + 1
      end do
      row(col_mean_length) = row(col_mean_length) / real(max(1, size(list)), wp)
      row(col_max_reaction) = summary%max_reaction_bottom
      row(col_first_fracture) = summary%first_fracture_t
      do k = 1, size(event_kinds)
         if (kind_column(k) > 0) row(kind_column(k)) = real(summary%n_kind(k), wp)
      end do
      row(col_e_kin) = summary%e_kin_end
      row(col_w_ext) = summary%w_ext_end
      row(col_excess) = summary%max_excess
      row(col_drift) = summary%ledger_drift
      row(col_steps) = real(summary%steps, wp)
      if (summary%n_kind(ev_fracture) > 0) row(col_fracture_stress) = &
         summary%fracture_stress_sum / real(summary%n_kind(ev_fracture), wp)
      row(col_e_fracture) = sim%st%ledger%e_fracture
      if (sim%st%coh%on) row(col_e_cohesive) = sum(dissipated(sim%st%coh%dmax, sim%st%coh%r, &
                                                              sim%st%coh%dc))
      row(col_spall:) = spall_cells(summary%diag)
   end subroutine run_case

   !> The spall columns of a case: sigma_novikov, spall_x, scab_thickness of the top and the
   !> bottom end (spb_diagnostics spall_row); -1 where an end has none (PREFIX.spl's NaN: the
   !> table stays finite for spallbar-compare, as first_fracture_t's -1; none of the three is
   !> ever negative).
   pure function spall_cells(d) result(v)
      type(diag_t), intent(in) :: d        !! the case's record
      real(wp) :: v(size(spall_columns))
      real(wp) :: r(10)
      integer :: side
      do side = 1, 2
         r = spall_row(d%ends(side))
         v(3 * side - 2:3 * side) = [r(6), r(7), r(9)]
         if (.not. d%ends(side)%on) v(3 * side - 2:3 * side) = -1.0_wp
      end do
      where (ieee_is_nan(v)) v = -1.0_wp
   end function spall_cells

   !> Check every case's deck and mesh (every rank, the same answer), then run the cases
   !> over the ranks; rank 0 writes PREFIX.sweep and PREFIX_sweep.h5.
   subroutine run_sweep(deck, prefix, progress, summary, err, batch_seconds, echo, rings)
      type(deck_t), intent(in) :: deck     !! the deck
      character(len=*), intent(in) :: prefix   !! output path prefix
      logical, intent(in) :: progress          !! progress line on stderr (rank 0)
      type(sweep_summary_t), intent(out) :: summary   !! the sweep's summary
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      real(wp), intent(in), optional :: batch_seconds   !! rank 0: a progress line every so
                                                        !! many seconds (stderr not a terminal)
      logical, intent(in), optional :: echo    !! rank 0: the estimate on stdout (its
                                               !! warnings go to stderr all the same)
      logical, intent(in), optional :: rings   !! characteristic steps where they serve
                                               !! (default; .false.: the lattice always)
      type(estimate_t), allocatable :: est_values(:)
      type(ensemble_t) :: ens
      real(wp), allocatable :: rows(:, :), series(:, :)
      integer, allocatable :: hists(:, :)
      real(wp) :: l_hist, t0, tables, beside
      integer :: nc, nbins, rank, nranks, c, sig
      type(meter_t) :: meter
      logical :: on
      real(wp) :: limit

      t0 = par_wtime()
      on = .true.
      if (present(rings)) on = rings
      meter%terminal = progress
      if (present(batch_seconds)) meter%every = batch_seconds
      meter%t0 = t0
      meter%last = t0
      nc = sweep_case_count(deck)
      nbins = deck%sweep%bins
      rank = par_rank()
      nranks = par_size()
      ! the memory this process may use, asked once (sys_memory_limit reads the cgroup's
      ! files: 0.25 ms, about half of a case's run here)
      limit = real(sys_memory_limit(), wp)
      call check_tables(deck, limit, tables, err)
      if (.not. allocated(err)) call check_cases(deck, limit, tables, l_hist, est_values, ens, &
                                                 beside, err)
      if (nranks > 1) call agree(rank, nranks, err)
      if (allocated(err)) return
      ! a signal while the cases were checked (a perturbed sweep builds every realization's
      ! mesh first): nothing ran, nothing is written (every rank asks: a collective)
      sig = par_max(int(stop_signal()))
      if (sig /= 0) then
         summary%signal = sig
         call make_error(err, 'sweep: stopped by signal ' // itoa(sig) // ' while its ' // &
            'cases were checked, before any ran; nothing written', code=128 + sig)
         return
      end if
      if (rank == 0) call tell_estimate(deck, sweep_estimate(est_values, &
                                        deck%sweep%realizations, nranks), echo)
      ! the outputs once every rank can run the cases (PREFIX.lock is made last)
      if (rank == 0) call claim_sweep_outputs(prefix, deck_record(deck), err, &
                                              ensemble=ens%n_cols > 0)
      if (nranks > 1) call agree(rank, nranks, err)
      if (allocated(err)) return
      allocate(rows(n_columns, nc), hists(nbins, nc), &
               series(ens%n_cols * ens%n_rows, nc))
      do c = 1, nc
         rows(:, c) = 0.0_wp
         rows(col_id, c) = real(c, wp)
         rows(col_status, c) = real(status_not_run, wp)
      end do
      hists = 0
      summary%cases = nc
      summary%ranks = nranks
      summary%distribution = trim(deck%sweep%distribution(1:16))
      if (nranks == 1) then
         summary%distribution = 'serial'
         call run_static(deck, 1, 0, l_hist, ens%ids, on, [limit, beside], meter, rows, hists, &
                         series)
      else if (deck%sweep%distribution == 'dynamic') then
         call run_dynamic(deck, rank, nranks, l_hist, ens%ids, on, [limit, beside], meter, rows, &
                          hists, series)
      else
         call run_static(deck, nranks, rank, l_hist, ens%ids, on, [limit, beside], meter, rows, &
                         hists, series)
      end if
      summary%wall = par_wtime() - t0
      ! every rank learns whether one was stopped (and waits here until all are done)
      summary%signal = par_max(int(stop_signal()))
      if (rank /= 0) return
      summary%done = count(nint(rows(col_status, :)) == 0)
      summary%not_run = count(nint(rows(col_status, :)) == status_not_run)
      summary%failed = nc - summary%done - summary%not_run
      summary%ensemble = ens%n_cols > 0
      if (summary%ensemble) then
         ! the realizations done, in realization order, on this rank alone (spb_ensemble)
         call ensemble_reduce(ens, series, nint(rows(col_status, :)) == 0)
         allocate(summary%horizons(ens%n_cols))
         do c = 1, ens%n_cols
            summary%horizons(c) = trim(ens%names(c)) // ': ' // horizon_text(ens, c)
         end do
      end if
      call write_table(deck, prefix, rows, err)
      if (.not. allocated(err)) call write_h5(deck, prefix, rows, hists, l_hist, ens, err)
      if (.not. allocated(err) .and. summary%ensemble) call write_ensemble(deck, prefix, ens, err)
      if (allocated(err)) return
      if (summary%signal /= 0) then
         call make_error(err, 'sweep: stopped by signal ' // itoa(summary%signal) // ' with ' // &
            itoa(summary%not_run) // ' of ' // itoa(nc) // ' cases not run (status -1); ' // &
            prefix // '.sweep and ' // prefix // '_sweep.h5 are written' // &
            trim(merge(' (and ' // prefix // '.ens)', repeat(' ', len(prefix) + 11), &
                       summary%ensemble)), code=128 + summary%signal)
      else if (summary%failed > 0) then
         call make_error(err, 'sweep: ' // itoa(summary%failed) // ' of ' // itoa(nc) // &
            ' cases went wrong (status column); ' // prefix // '.sweep and ' // prefix // &
            '_sweep.h5 are written' // trim(merge(' (and ' // prefix // '.ens)', &
            repeat(' ', len(prefix) + 11), summary%ensemble)), code=exit_runtime)
      end if
   end subroutine run_sweep

   !> Case c on rank mod(c - 1, k); the others send their rows to rank 0 at the end, in
   !> case order (rank 0 receives in the same order: no deadlock).
   subroutine run_static(deck, k, me, l_hist, ids, rings, memory, meter, rows, hists, series)
      type(deck_t), intent(in) :: deck     !! the deck
      integer, intent(in) :: k                 !! ranks
      integer, intent(in) :: me                !! this rank
      real(wp), intent(in) :: l_hist           !! histogram range [m]
      integer, intent(in) :: ids(:)            !! the ensemble's columns (none: no ensemble)
      logical, intent(in) :: rings             !! characteristic steps where they serve
      real(wp), intent(in) :: memory(2)        !! the memory this process may use, and what
                                               !! the sweep holds besides a case [bytes]
      type(meter_t), intent(inout) :: meter    !! the progress lines (rank 0)
      real(wp), intent(inout) :: rows(:, :)    !! (column, case)
      integer, intent(inout) :: hists(:, :)    !! (bin, case)
      real(wp), intent(inout) :: series(:, :)  !! (the ensemble's columns at the rows, case)
      integer :: c, done, nc, nbins
      real(wp), allocatable :: buf(:)
      nc = size(rows, 2)
      nbins = size(hists, 1)
      done = 0
      do c = me + 1, nc, k
         if (stop_signal() /= 0) exit
         call run_case(deck, c, nbins, l_hist, ids, rings, rows(:, c), hists(:, c), &
                          series(:, c), memory(1), memory(2))
         done = done + 1
         if (me == 0) call show(meter, done * k, nc)
      end do
      if (k == 1) return
      allocate(buf(n_columns + nbins + size(series, 1)))
      if (me /= 0) then
         do c = me + 1, nc, k
            call pack_case(rows(:, c), hists(:, c), series(:, c), buf)
            call par_send(buf, 0, c)
         end do
      else
         do c = 1, nc
            if (mod(c - 1, k) == 0) cycle
            call par_recv(buf, mod(c - 1, k), c)
            call unpack_case(buf, rows(:, c), hists(:, c), series(:, c))
         end do
      end if
   end subroutine run_static

   !> A case's row, histogram and ensemble series in one message to rank 0.
   pure subroutine pack_case(row, hist, series, buf)
      real(wp), intent(in) :: row(:)       !! its row
      integer, intent(in) :: hist(:)       !! its histogram
      real(wp), intent(in) :: series(:)    !! its ensemble columns
      real(wp), intent(out) :: buf(:)      !! the message
      buf(1:size(row)) = row
      buf(size(row) + 1:size(row) + size(hist)) = real(hist, wp)
      buf(size(row) + size(hist) + 1:) = series
   end subroutine pack_case

   !> The row, histogram and ensemble series of a message (pack_case).
   pure subroutine unpack_case(buf, row, hist, series)
      real(wp), intent(in) :: buf(:)       !! the message
      real(wp), intent(out) :: row(:)      !! its row
      integer, intent(out) :: hist(:)      !! its histogram
      real(wp), intent(out) :: series(:)   !! its ensemble columns
      row = buf(1:size(row))
      hist = nint(buf(size(row) + 1:size(row) + size(hist)))
      series = buf(size(row) + size(hist) + 1:)
   end subroutine unpack_case

   !> Rank 0 hands out one case at a time to whichever rank asks and collects the rows;
   !> the other ranks compute. Case 0 means stop.
   subroutine run_dynamic(deck, rank, nranks, l_hist, ids, rings, memory, meter, rows, hists, &
                          series)
      type(deck_t), intent(in) :: deck     !! the deck
      integer, intent(in) :: rank              !! this rank
      integer, intent(in) :: nranks            !! ranks
      real(wp), intent(in) :: l_hist           !! histogram range [m]
      integer, intent(in) :: ids(:)            !! the ensemble's columns (none: no ensemble)
      logical, intent(in) :: rings             !! characteristic steps where they serve
      real(wp), intent(in) :: memory(2)        !! the memory this process may use, and what
                                               !! the sweep holds besides a case [bytes]
      type(meter_t), intent(inout) :: meter    !! the progress lines (rank 0)
      real(wp), intent(inout) :: rows(:, :)    !! (column, case)
      integer, intent(inout) :: hists(:, :)    !! (bin, case)
      real(wp), intent(inout) :: series(:, :)  !! (the ensemble's columns at the rows, case)
      integer :: c, next, active, worker, finished, nc, nbins
      real(wp), allocatable :: buf(:)
      nc = size(rows, 2)
      nbins = size(hists, 1)
      allocate(buf(n_columns + nbins + size(series, 1)))
      if (rank == 0) then
         next = 1
         active = nranks - 1
         finished = 0
         do while (active > 0)
            call par_recv(c, par_any, tag_request, got_source=worker)
            if (c > 0) then
               call par_recv(buf, worker, c)
               call unpack_case(buf, rows(:, c), hists(:, c), series(:, c))
               finished = finished + 1
               call show(meter, finished, nc)
            end if
            if (next <= nc .and. stop_signal() == 0) then
               call par_send(next, worker, tag_work)
               next = next + 1
            else
               call par_send(0, worker, tag_work)
               active = active - 1
            end if
         end do
      else
         c = 0
         do
            call par_send(c, 0, tag_request)
            if (c > 0) then
               call pack_case(rows(:, c), hists(:, c), series(:, c), buf)
               call par_send(buf, 0, c)
            end if
            call par_recv(c, 0, tag_work)
            if (c == 0) exit
            call run_case(deck, c, nbins, l_hist, ids, rings, rows(:, c), hists(:, c), &
                          series(:, c), memory(1), memory(2))
         end do
      end if
   end subroutine run_dynamic

   !> The sweep's progress on stderr: on a terminal one line updated in place after every
   !> case; in batch (meter%every > 0) a line every meter%every seconds and at the end.
   subroutine show(meter, n_done, n_all)
      type(meter_t), intent(inout) :: meter   !! the progress lines
      integer, intent(in) :: n_done            !! cases done
      integer, intent(in) :: n_all             !! all cases
      character(len=100) :: line
      real(wp) :: now
      if (.not. meter%terminal .and. meter%every <= 0.0_wp) return
      now = par_wtime()
      write(line, '(a,i0,a,i0,a,f8.1,a)') 'spallbar sweep: ', min(n_done, n_all), ' of ', &
         n_all, ' cases, ', now - meter%t0, ' s'
      if (meter%terminal) then
         write(error_unit, '(a)', advance='no') achar(13) // trim(line)
         if (n_done >= n_all) write(error_unit, '(a)') ''
      else if (now - meter%last >= meter%every .or. n_done >= n_all) then
         meter%last = now
         write(error_unit, '(a)') trim(line)
      end if
      flush(error_unit)
   end subroutine show

   !> Every value's deck and mesh must build (bad input: exit 2 before anything runs), and
   !> with perturb every realization's; the histogram range is the longest bar of the cases.
   !> With ensemble_columns: the ensemble (its rows: every realization's history times,
   !> which must be the same), and its memory beside the tables'.
   subroutine check_cases(deck, limit, tables, l_hist, est_values, ens, extra, err)
      type(deck_t), intent(in) :: deck     !! the deck
      real(wp), intent(in) :: limit        !! the memory this process may use [bytes]
      real(wp), intent(in) :: tables       !! memory of the sweep's tables [bytes]
      real(wp), intent(out) :: l_hist      !! histogram range: the longest bar of the cases [m]
      type(estimate_t), allocatable, intent(out) :: est_values(:)   !! the work of a case of
                                                                    !! each value
      type(ensemble_t), intent(out) :: ens !! the ensemble (none: n_cols = 0, no ids)
      real(wp), intent(out) :: extra       !! memory the sweep holds besides a case: its
                                           !! tables and the ensemble [bytes]
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      type(deck_t) :: cdeck
      type(mesh_t) :: mesh
      type(load_t) :: load
      type(problem_t) :: prob
      character(len=200), allocatable :: report(:)
      real(wp) :: value
      integer :: c, iv, realization, nrep, n_cases
      nrep = max(1, deck%sweep%realizations)
      l_hist = 0.0_wp
      extra = tables
      allocate(est_values(max(1, deck%sweep%n_values)), ens%ids(0))
      ! the cases whose decks differ: the first realization of each value, or (perturb)
      ! every realization of the one value
      n_cases = max(1, deck%sweep%n_values)
      if (len_trim(deck%sweep%perturb) > 0) n_cases = nrep
      do iv = 1, n_cases
         if (stop_signal() /= 0) exit          ! the sweep ends before any case (run_sweep)
         c = (iv - 1) * nrep + 1
         if (len_trim(deck%sweep%perturb) > 0) c = iv
         call case_deck(deck, c, cdeck, value, realization, err)
         if (.not. allocated(err)) call setup_model(cdeck, prob, mesh, load, report, err, &
                                                    files=.false., extra=extra, limit=limit)
         if (allocated(err)) then
            if (deck%sweep%n_values > 0) err%message = '&sweep: values(' // itoa(iv) // ') = ' &
               // rtoa(value) // ' for ' // trim(deck%sweep%vary) // ': ' // err%message
            if (len_trim(deck%sweep%perturb) > 0) err%message = '&sweep: perturb = ''' // &
               trim(deck%sweep%perturb) // ''': realization ' // itoa(iv) // ' gives ' // &
               rtoa(value) // ': ' // err%message
            return
         end if
         l_hist = max(l_hist, mesh%x(mesh%n) - mesh%x(0))
         if (iv <= size(est_values)) est_values(iv) = estimate_run(cdeck, mesh%n, mesh%nsteps, &
                                                                  mesh%dt, 0, .false.)
         if (deck%sweep%n_ensemble == 0) cycle
         if (iv == 1) then
            call start_ensemble(deck, mesh, limit, tables, ens, extra, err)
         else if (mesh%nsteps /= ens%nsteps .or. abs(mesh%dt - ens%dt) > 0.0_wp) then
            call make_error(err, '&sweep: perturb = ''' // trim(deck%sweep%perturb) // &
               ''': realization ' // itoa(iv) // ' has other history times (dt = ' // &
               rtoa(mesh%dt) // ' s, ' // itoa(mesh%nsteps) // ' steps) than realization 1 ' // &
               '(dt = ' // rtoa(ens%dt) // ' s, ' // itoa(ens%nsteps) // ' steps); the ' // &
               'ensemble''s realizations share them: perturb a variable that leaves the ' // &
               'time step alone')
         end if
         if (allocated(err)) return
      end do
   end subroutine check_cases

   !> The ensemble of a sweep with ensemble_columns, its realizations on mesh (the first
   !> realization's): refused when its memory, beside the tables' (and the runs' checked
   !> with them), is more than this process may use. extra: the memory both need [bytes].
   subroutine start_ensemble(deck, mesh, limit, tables, ens, extra, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(mesh_t), intent(in) :: mesh     !! the first realization's mesh
      real(wp), intent(in) :: limit        !! the memory this process may use [bytes]
      real(wp), intent(in) :: tables       !! memory of the sweep's tables [bytes]
      type(ensemble_t), intent(out) :: ens !! the ensemble
      real(wp), intent(out) :: extra       !! memory of the tables and the ensemble [bytes]
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(column_set_t) :: his
      character(len=16) :: units(deck%sweep%n_ensemble)
      integer :: j, k
      his = history_set()
      do j = 1, size(units)
         do k = 1, size(his%col)
            if (his%col(k)%name == deck%sweep%ensemble_columns(j)) units(j) = &
               bar_units(trim(his%col(k)%unit), mesh)
         end do
      end do
      call ensemble_setup(ens, deck%sweep%ensemble_columns(1:size(units)), units, &
                          deck%run%history_every, mesh%nsteps, mesh%dt, deck%sweep%horizon_tol, &
                          deck%sweep%realizations)
      extra = tables + ensemble_bytes(ens%n_cols, ens%n_rows, sweep_case_count(deck))
      if (run_base_bytes + extra > limit) call make_error(err, '&sweep: realizations = ' // &
         itoa(deck%sweep%realizations) // ' and ensemble_columns (' // itoa(ens%n_cols) // &
         ' at ' // itoa(ens%n_rows) // ' history rows: &run history_every = ' // &
         itoa(deck%run%history_every) // ') need about ' // memory_text(run_base_bytes + extra) &
         // ' of memory; the limit here is ' // memory_text(limit))
   end subroutine start_ensemble

   !> Memory of an ensemble of n_cols columns at n_rows rows over cases realizations
   !> [bytes]: every rank holds each case's series (8 bytes a value, as the table's rows),
   !> and besides them a case's samples, its message and rank 0's statistics (4 a value).
   pure real(wp) function ensemble_bytes(n_cols, n_rows, cases) result(bytes)
      integer, intent(in) :: n_cols        !! ensemble columns
      integer, intent(in) :: n_rows        !! history rows
      integer, intent(in) :: cases         !! realizations
      bytes = 8.0_wp * real(n_cols, wp) * real(n_rows, wp) * (real(cases, wp) + 6.0_wp)
   end function ensemble_bytes

   !> The sweep's estimate: its line on stdout (echo), its warnings on stderr.
   subroutine tell_estimate(deck, est, echo)
      type(deck_t), intent(in) :: deck     !! the deck
      type(estimate_t), intent(in) :: est  !! the whole sweep's estimate
      logical, intent(in), optional :: echo   !! the line on stdout
      integer :: k
      if (present(echo)) then
         if (echo) write(output_unit, '(a)') '  ' // estimate_line(est)
         flush(output_unit)
      end if
      associate (w => estimate_warnings(deck, est))
         do k = 1, size(w)
            write(error_unit, '(a)') 'spallbar: warning: ' // trim(w(k))
         end do
      end associate
   end subroutine tell_estimate

   !> The memory of the sweep's tables (a row and a histogram per case) against the limit
   !> of this process, before they are allocated; the cases' runs are checked beside them
   !> (check_cases).
   subroutine check_tables(deck, limit, tables, err)
      type(deck_t), intent(in) :: deck     !! the deck
      real(wp), intent(in) :: limit        !! the memory this process may use [bytes]
      real(wp), intent(out) :: tables      !! memory of the tables [bytes]
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      real(wp) :: cases
      cases = real(max(1, deck%sweep%n_values), wp) * real(max(1, deck%sweep%realizations), wp)
      tables = cases * (case_bytes + bin_bytes * real(deck%sweep%bins, wp))
      if (run_base_bytes + tables > limit) call make_error(err, '&sweep: realizations = ' // &
         itoa(deck%sweep%realizations) // ' and bins = ' // itoa(deck%sweep%bins) // &
         ' need about ' // memory_text(run_base_bytes + tables) // ' of memory (a row and ' // &
         'a histogram for each of ' // itoa(sweep_case_count(deck)) // ' cases); the ' // &
         'limit here is ' // memory_text(limit))
   end subroutine check_tables

   !> Every rank's checks must agree before any case runs (a rank that stopped alone would
   !> leave the others waiting): the ranks send rank 0 their status, rank 0 answers with its
   !> own or, when only another rank refused (its memory limit is lower), that one's.
   subroutine agree(rank, nranks, err)
      integer, intent(in) :: rank          !! this rank
      integer, intent(in) :: nranks        !! ranks
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: k, code, other
      code = 0
      if (allocated(err)) code = err%code
      if (rank /= 0) then
         call par_send(code, 0, tag_check)
         call par_recv(code, 0, tag_check)
         if (code /= 0 .and. .not. allocated(err)) call make_error(err, &
            'sweep: refused (rank 0 says why)', code=code)
         return
      end if
      do k = 1, nranks - 1
         call par_recv(other, k, tag_check)
         if (other /= 0 .and. code == 0) then
            code = other
            call make_error(err, 'sweep: rank ' // itoa(k) // ' of ' // itoa(nranks) // &
               ' refused the cases: they need more memory than its limit (&mesh cells, ' // &
               '&sweep realizations and bins; run it alone to see the numbers)', code=other)
         end if
      end do
      do k = 1, nranks - 1
         call par_send(code, k, tag_check)
      end do
   end subroutine agree

   !> The sweep table's column of the count of event kind k (0: none): a core kind's after
   !> status, another's after e_fracture, each in code order.
   pure integer function kind_column(k) result(c)
      integer, intent(in) :: k             !! event kind code
      c = 0
      if (len_trim(event_kinds(k)%column) == 0) return
      if (event_kinds(k)%core) then
         c = col_status + count(event_kinds(:k)%core .and. event_kinds(:k)%column /= '')
      else
         c = col_e_fracture + count(.not. event_kinds(:k)%core .and. event_kinds(:k)%column /= '')
      end if
   end function kind_column

   !> The sweep table's columns, in order: its own and the event kinds' counts (kind_column).
   pure function sweep_table() result(table)
      type(column_t) :: table(n_columns)
      integer :: k
      table(:col_status) = case_columns
      table(col_e_kin:col_e_fracture) = run_columns
      table(col_e_cohesive:col_spall - 1) = cohesive_columns
      table(col_spall:) = spall_columns
      do k = 1, size(event_kinds)
         if (kind_column(k) > 0) table(kind_column(k)) = column_t(event_kinds(k)%column, '-', &
                                                                  .true.)
      end do
   end function sweep_table

   !> The sweep table's column names, blank-separated (the column line of PREFIX.sweep).
   pure function sweep_columns() result(line)
      character(len=:), allocatable :: line
      line = column_names(sweep_table())
   end function sweep_columns

   !> PREFIX.sweep: header (deck echo with &sweep, columns, units), one row per case, in
   !> case order; written to PREFIX.sweep.part and renamed when complete.
   subroutine write_table(deck, prefix, rows, err)
      type(deck_t), intent(in) :: deck     !! the deck
      character(len=*), intent(in) :: prefix   !! output path prefix
      real(wp), intent(in) :: rows(:, :)       !! (column, case)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=22 * n_columns) :: line
      type(column_t) :: table(n_columns)
      integer :: u, c, k, at
      call open_part(prefix // '.sweep', u, err)
      if (allocated(err)) return
      if (deck%run%header == 'names') write(u, '(a)') sweep_columns()
      write(u, '(a)') '# ' // program_line() // ' -- sweep: one row per case, in case order'
      write(u, '(a)') '# title: ' // trim(deck%run%title)
      call write_echo(u, deck_record(deck), '# ')
      write(u, '(a)') '# cases: ' // itoa(size(rows, 2)) // ' = ' // &
         itoa(max(1, deck%sweep%n_values)) // ' value(s) x ' // &
         itoa(max(1, deck%sweep%realizations)) // ' realization(s); case c is value ' // &
         '(c-1)/R+1 and realization mod(c-1,R)+1 (R = realizations)'
      write(u, '(a)') '# seed: the &strength_field seed of the case (re-run one case alone ' // &
         'with it); status: 0 done, 3 the run went wrong, 128+s stopped by signal s, -1 not run'
      write(u, '(a)') '# fragments at t_end; mean_fragment_length = mean reference length ' // &
         'of those fragments; max_reaction_bottom over every step'
      write(u, '(a)') '# units: ' // sweep_units
      if (len_trim(deck%sweep%perturb) > 0) write(u, '(a)') '# value: the perturbed ' // &
         trim(deck%sweep%perturb) // ' x (1 + spread u_i) of realization i (PREFIX.ens)'
      write(u, '(a)') '# ' // sweep_columns()
      table = sweep_table()
      ! each field as (1x,i12) or (1x,es20.12e3) would write it, the fields a blank apart
      ! (es_into, int_into: the text without the run-time library's formatted I/O)
      do c = 1, size(rows, 2)
         at = 0
         do k = 1, n_columns
            if (k > 1) then
               line(at + 1:at + 1) = ' '
               at = at + 1
            end if
            line(at + 1:at + 1) = ' '
            if (table(k)%whole) then
               call int_into(nint(rows(k, c)), line(at + 2:at + 13))
               at = at + 13
            else
               call es_into(rows(k, c), line(at + 2:at + 21))
               at = at + 21
            end if
         end do
         write(u, '(a)') line(1:at)
      end do
      call close_part(prefix // '.sweep', u, err)
   end subroutine write_table

   !> PREFIX.ens (doc/sweeps.md, "Ensembles"): header (deck echo, the ensemble, the
   !> horizons, units, columns), one row per history time; written to PREFIX.ens.part and
   !> renamed when complete. No rows when no realization was done.
   subroutine write_ensemble(deck, prefix, ens, err)
      type(deck_t), intent(in) :: deck     !! the deck
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(ensemble_t), intent(in) :: ens  !! the ensemble (reduced)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: u, k
      call open_part(prefix // '.ens', u, err)
      if (allocated(err)) return
      if (deck%run%header == 'names') write(u, '(a)') ensemble_columns_line(ens)
      write(u, '(a)') '# ' // program_line() // ' -- ensemble: one row per history time, ' // &
         'statistics over the realizations'
      write(u, '(a)') '# title: ' // trim(deck%run%title)
      call write_echo(u, deck_record(deck), '# ')
      associate (notes => ensemble_notes(ens, deck%sweep%perturb, deck%sweep%spread))
         do k = 1, size(notes)
            write(u, '(a)') '# ' // trim(notes(k))
         end do
      end associate
      write(u, '(a)') '# ' // ensemble_columns_line(ens)
      if (ens%members > 0) then
         do k = 1, ens%n_rows
            write(u, '(a)') ensemble_row(ens, k)
         end do
      end if
      call close_part(prefix // '.ens', u, err)
   end subroutine write_ensemble

   !> Open path.part for a table (replacing one there).
   subroutine open_part(path, u, err)
      character(len=*), intent(in) :: path   !! the table (PREFIX.sweep, PREFIX.ens)
      integer, intent(out) :: u            !! its unit
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: ios
      character(len=256) :: msg
      open(newunit=u, file=path // '.part', status='replace', action='write', &
           iostat=ios, iomsg=msg)
      if (ios /= 0) call make_error(err, '--output: cannot write ''' // path // ''': ' // &
                                    trim(msg), code=exit_runtime)
   end subroutine open_part

   !> Close a table's path.part and rename it path, once all of it reached the disk (else it
   !> is left as path.part).
   subroutine close_part(path, u, err)
      character(len=*), intent(in) :: path   !! the table (PREFIX.sweep, PREFIX.ens)
      integer, intent(in) :: u             !! its unit (open_part)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer(int64) :: wrote, have
      integer :: ios
      logical :: ok
      ! gfortran reports no error on a full disk: compare what reached it before renaming
      flush(u)
      inquire(unit=u, size=wrote)
      have = sys_file_size(path // '.part')
      close(u, iostat=ios)
      if (have < wrote) then
         call make_error(err, '--output: cannot write ''' // path // ''': ' // &
            itoa(max(have, 0_int64)) // ' of ' // itoa(wrote) // ' bytes reached the disk ' // &
            '(' // sys_write_trouble(path // '.part') // '); the cut table is left as ' // &
            path // '.part', &
            code=exit_runtime)
         return
      end if
      call sys_rename(path // '.part', path, ok)
      if (ios /= 0 .or. .not. ok) call make_error(err, code=exit_runtime, message= &
         '--output: cannot write ''' // path // '''')
   end subroutine close_part

   !> PREFIX_sweep.h5: the deck (attributes), /cases/<column> (one dataset per column of
   !> the table), /histogram/edges [m] and /histogram/counts (bins x cases; h5py: cases x
   !> bins). Written to PREFIX_sweep.h5.part and renamed when complete.
   subroutine write_h5(deck, prefix, rows, hists, l_hist, ens, err)
      type(deck_t), intent(in) :: deck     !! the deck
      character(len=*), intent(in) :: prefix   !! output path prefix
      real(wp), intent(in) :: rows(:, :)       !! (column, case)
      integer, intent(in) :: hists(:, :)       !! (bin, case)
      real(wp), intent(in) :: l_hist           !! histogram range [m]
      type(ensemble_t), intent(in) :: ens      !! the ensemble (n_cols = 0: none)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(h5file_t) :: h5
      real(wp) :: col(size(rows, 2))
      type(column_t) :: table(n_columns)
      integer :: k, nb
      logical :: ok
      call h5_create(h5, prefix // '_sweep.h5.part')
      call h5_deck_header(h5, deck_record(deck))
      call h5_group(h5, '/cases')
      call h5_attr(h5, '/cases', 'count', size(rows, 2))
      call h5_attr(h5, '/cases', 'vary', trim(deck%sweep%vary))
      call h5_attr(h5, '/cases', 'units', sweep_units)
      table = sweep_table()
      do k = 1, n_columns
         if (table(k)%whole) then
            call h5_write(h5, '/cases/' // trim(table(k)%name), nint(rows(k, :)), &
                          trim(table(k)%unit))
         else
            col = rows(k, :)    ! contiguous
            call h5_write(h5, '/cases/' // trim(table(k)%name), col, &
                          trim(table(k)%unit))
         end if
      end do
      nb = size(hists, 1)
      call h5_group(h5, '/histogram')
      call h5_attr(h5, '/histogram', 'quantity', 'reference lengths of the fragments at ' // &
                   't_end, bins of equal width on (0, l_hist]; the last bin also holds longer ones')
      call h5_write(h5, '/histogram/edges', [(l_hist * real(k, wp) / real(nb, wp), k = 0, nb)], 'm')
      call h5_write(h5, '/histogram/counts', hists, '-')
      if (ens%n_cols > 0) call ensemble_h5(h5, ens)
      call h5_close(h5)
      if (allocated(h5%error)) then
         call make_error(err, h5%error, code=exit_runtime)
         return
      end if
      call sys_rename(prefix // '_sweep.h5.part', prefix // '_sweep.h5', ok)
      if (.not. ok) call make_error(err, '--output: cannot write ''' // prefix // '_sweep.h5''', &
                                    code=exit_runtime)
   end subroutine write_h5
end module spb_sweep
