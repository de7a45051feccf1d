!> The work of a run and the volume of its outputs, known before it starts (issue 32): the
!> time step is exact (dt = dx/a), so the steps follow from the mesh and t_end, and the rows
!> of every output from history_every, profile_times, &gauges every and field_every.
!>
!> The time is a documented speed of this program (Release, measured on the machine of
!> doc/outputs.md, "The estimate"), not a calibration: the estimate is the same on every
!> run of a deck, and the progress line gives the speed measured on the run itself within
!> seconds. Text for the echo and the warnings (more than an hour, more than 10 GB) naming
!> the deck's variables are made here too; the main program prints them.
module spb_estimate
   use spb_kinds, only: wp
   use spb_strings, only: itoa
   use spb_deck_types, only: deck_t
   use spb_columns, only: column_set_t
   use spb_history, only: history_set
   use spb_schedule, only: check_every, keeps_rows
   implicit none
   private
   public :: estimate_t, estimate_run, estimate_line, estimate_warnings, progress_period, &
      sweep_estimate, limit_seconds, limit_bytes, n_outputs, out_his, out_prf, out_gau, out_h5

   !> Seconds per cell and step while the mesh's state fits in the 32 MB L3 cache (up to
   !> about 1.5e5 cells at 208 bytes each, spb_sim run_cell_bytes); measured 6.4 ns with 1e4
   !> cells, 7.6 ns with 1e5 (the bar joined, history_every = 1e5) [s].
   real(wp), parameter :: sec_cell_step_cached = 7.0e-9_wp
   !> The same beyond the cache: measured 20 to 31 ns with 1e6 cells and 30 to 58 ns with
   !> 5e6 on the machine shared with other jobs (load 4 to 9 on 2 cores), 4.4 ns with 1e6
   !> cells of an unbreakable bar under a lighter load [s].
   real(wp), parameter :: sec_cell_step_large = 25.0e-9_wp
   !> State bytes that fit in the cache: 32 MB of L3 [bytes].
   real(wp), parameter :: cache_bytes = 32.0e6_wp
   !> State bytes per cell (spb_sim run_cell_bytes) [bytes].
   real(wp), parameter :: cell_bytes = 208.0_wp
   !> Seconds per cell and history row (its energies over the bar, and the step it stops
   !> the cache-blocked stepper at): 1e4 cells, 2e4 steps took 6.4 s with history_every = 1
   !> and 1.3 s with 1e5 [s].
   real(wp), parameter :: sec_cell_row = 25.0e-9_wp
   !> A bar stepped in characteristic form from the start (spb_ring, doc/method.md
   !> "Characteristic stepping of intact stretches"): seconds per step (a ring's ends, its
   !> bounded fracture test; 0.87 us a step measured on a breakable 1e6-cell bar to its
   !> first fracture, bench/run.py target 1) [s]
   real(wp), parameter :: sec_ring_step = 1.0e-6_wp
   !> and seconds per cell and span (the conversion to the rings and back, about 30 ns a
   !> cell each, measured on the layered bar of bench/run.py target 2) [s]. Events cost more
   !> (each a lattice step and two conversions): the estimate does not know them.
   real(wp), parameter :: sec_cell_span = 60.0e-9_wp
   !> Seconds per history row besides (its 34 numbers formatted, the wave measure's sums
   !> over the fragments): example3_case1 (19 cells) wrote 2130 rows in 17 to 25 ms [s].
   real(wp), parameter :: sec_row = 10.0e-6_wp
   !> Seconds per byte written: 100 gauges every step on 100 cells wrote 140 MB in 0.75 s
   !> [s].
   real(wp), parameter :: sec_byte = 5.5e-9_wp
   !> A warning above these: an hour of work [s], 10 GB of outputs [bytes].
   real(wp), parameter :: limit_seconds = 3600.0_wp, limit_bytes = 10.0e9_wp
   !> Cell-steps between two looks at the clock (progress_period): 2^24, a quarter of a
   !> second at 15 ns per cell and step, a second at the slowest Release speed measured
   !> (58 ns), a few seconds in Debug [-].
   real(wp), parameter :: cell_steps_per_look = 16777216.0_wp
   !> Steps between two looks at the clock on a small mesh [steps].
   integer, parameter :: period_max = 1024
   !> Width of a real column in the text files: 1x, es20.12e3 [bytes].
   integer, parameter :: col_bytes = 21

   !> The outputs counted: PREFIX.his, .prf, .gau, .h5 (.evt and .frg depend on the events
   !> and are not counted).
   integer, parameter :: out_his = 1, out_prf = 2, out_gau = 3, out_h5 = 4, n_outputs = 4
   character(len=4), parameter :: out_ext(n_outputs) = ['.his', '.prf', '.gau', '.h5 ']

   !> The work of a run and what it writes.
   type :: estimate_t
      integer :: cells = 0                     !! cells of the mesh
      integer :: steps = 0                     !! steps still to take
      real(wp) :: cell_steps = 0.0_wp          !! cells x steps [-]
      real(wp) :: rows = 0.0_wp                !! history rows [-]
      real(wp) :: seconds = 0.0_wp             !! wall time at the documented speed [s]
      real(wp) :: row_seconds = 0.0_wp         !! of it, the history rows' [s]
      real(wp) :: bytes(n_outputs) = 0.0_wp    !! per output (out_*): its rows [bytes]
      integer :: cases = 1                     !! a sweep: its cases (1: one run)
      integer :: ranks = 1                     !! a sweep: the ranks sharing them
   end type estimate_t

contains

   !> The estimate of a run of a validated deck on a mesh of cells cells and nsteps steps of
   !> dt, from step first (0, or a restart's checkpoint step) on; files = .false.: no
   !> outputs (a sweep's case).
   pure function estimate_run(deck, cells, nsteps, dt, first, files, ring_span) result(est)
      type(deck_t), intent(in) :: deck     !! the deck (its &run, &gauges)
      integer, intent(in) :: cells         !! cells of the mesh
      integer, intent(in) :: nsteps        !! steps to t_end
      real(wp), intent(in) :: dt           !! the time step [s]
      integer, intent(in) :: first         !! the step it starts from
      logical, intent(in) :: files         !! it writes its outputs
      integer, intent(in), optional :: ring_span   !! > 0: the bar starts in characteristic
                                                   !! form, converted every so many steps
      type(estimate_t) :: est
      real(wp) :: his_row     ! bytes of a history row [bytes]
      real(wp) :: gau_rows    ! gauge rows [-]
      real(wp) :: xt_rows     ! x-t rows of PREFIX.h5 [-]
      real(wp) :: c_step      ! seconds per cell and step [s]
      real(wp) :: half_rows   ! rows of a profile block: the half nodes, 2 per cell [-]
      integer :: ng, np, g_every
      type(column_set_t) :: his   ! the history's columns
      est%cells = cells
      est%steps = max(nsteps - first, 0)
      est%cell_steps = real(cells, wp) * real(est%steps, wp)
      est%rows = rows_between(first, nsteps, deck%run%history_every)
      ! a sweep's case keeps rows only for its ensemble; else the checks take a row's work
      if (.not. keeps_rows(files, deck%sweep%n_ensemble > 0)) est%rows = &
         rows_between(first, nsteps, check_every)
      c_step = sec_cell_step_cached
      if (real(cells, wp) * cell_bytes > cache_bytes) c_step = sec_cell_step_large
      est%row_seconds = est%rows * (real(cells, wp) * sec_cell_row + sec_row)
      est%seconds = est%cell_steps * c_step + est%row_seconds
      if (present(ring_span)) then
         if (ring_span > 0) est%seconds = real(est%steps, wp) * sec_ring_step + &
            (real(est%steps / ring_span, wp) + 1.0_wp) * real(cells, wp) * sec_cell_span + &
            est%row_seconds
      end if
      if (.not. files) return
      ng = deck%gauges%n
      g_every = deck%gauges%every
      if (g_every <= 0) g_every = deck%run%history_every
      gau_rows = 0.0_wp
      if (ng > 0) gau_rows = rows_between(first, nsteps, g_every)
      ! the profiles still to come: all of them, or those after a restart's step (at their
      ! steps nint(t / dt), as spb_sim start_run has them)
      np = deck%run%n_profiles
      if (first > 0) np = count(nint(deck%run%profile_times(1:np) / dt) > first)
      half_rows = 2.0_wp * real(cells, wp)
      his = history_set()
      his_row = real(sum(his%col%width + 1) + 1, wp)   ! each field and its blank, the newline
      est%bytes(out_his) = est%rows * his_row
      ! a block: its two '#' lines, then a row per half node (5 columns)
      est%bytes(out_prf) = real(np, wp) * (100.0_wp + half_rows * real(5 * col_bytes + 1, wp))
      est%bytes(out_gau) = gau_rows * real((1 + 3 * ng) * col_bytes + 1, wp)
      if (deck%run%hdf5) then
         ! the same columns as 8-byte values (deflate makes them smaller), and the x-t rows
         xt_rows = 0.0_wp
         if (deck%run%field_every > 0) xt_rows = rows_between(first, nsteps, &
                                                              deck%run%field_every)
         est%bytes(out_h5) = 8.0_wp * (est%rows * real(size(his%col), wp) + &
            real(np, wp) * 3.0_wp * half_rows + gau_rows * real(1 + 3 * ng, wp) + &
            xt_rows * (1.0_wp + 3.0_wp * half_rows))
      end if
      est%seconds = est%seconds + sum(est%bytes) * sec_byte
   end function estimate_run

   !> Rows of an output written at step 0, every `every` steps and at the last step, that
   !> fall after step first [-].
   pure real(wp) function rows_between(first, nsteps, every) result(rows)
      integer, intent(in) :: first         !! the step the run starts from (0: with t = 0)
      integer, intent(in) :: nsteps        !! the last step
      integer, intent(in) :: every         !! steps between rows
      integer :: e
      e = max(every, 1)
      rows = real(nsteps / e - first / e, wp)
      if (first == 0) rows = rows + 1.0_wp
      if (mod(nsteps, e) /= 0 .and. nsteps > first) rows = rows + 1.0_wp
   end function rows_between

   !> A sweep: the cases' work added up (est_values holds a case of each value, each run
   !> realizations times), shared by ranks ranks.
   pure function sweep_estimate(est_values, realizations, ranks) result(est)
      type(estimate_t), intent(in) :: est_values(:)   !! a case of each value of the sweep
      integer, intent(in) :: realizations  !! cases per value
      integer, intent(in) :: ranks         !! ranks sharing the cases
      type(estimate_t) :: est
      integer :: k
      est%cases = size(est_values) * max(realizations, 1)
      est%ranks = max(ranks, 1)
      do k = 1, size(est_values)
         est%cells = max(est%cells, est_values(k)%cells)
         est%steps = max(est%steps, est_values(k)%steps)
         est%cell_steps = est%cell_steps + real(max(realizations, 1), wp) * est_values(k)%cell_steps
         est%rows = est%rows + real(max(realizations, 1), wp) * est_values(k)%rows
         est%row_seconds = est%row_seconds + real(max(realizations, 1), wp) * &
                           est_values(k)%row_seconds
         est%seconds = est%seconds + real(max(realizations, 1), wp) * est_values(k)%seconds
      end do
      ! the wall time: the cases shared out, but no rank does less than the largest case
      est%row_seconds = est%row_seconds / real(est%ranks, wp)
      est%seconds = max(est%seconds / real(est%ranks, wp), maxval([0.0_wp, est_values%seconds]))
   end function sweep_estimate

   !> Steps between two looks at the clock (the progress line, the flush of the outputs):
   !> 1024 on a small mesh, fewer on a large one, so that they are at most 2^24 cell-steps
   !> apart (a power of two, at least 1) [steps].
   pure integer function progress_period(cells) result(period)
      integer, intent(in) :: cells         !! cells of the mesh
      period = period_max
      do while (period > 1 .and. real(period, wp) * real(max(cells, 1), wp) > &
                cell_steps_per_look)
         period = period / 2
      end do
   end function progress_period

   !> The echo's line: 'estimate: 2.5e13 cell-steps (5000000 cells x 5047545 steps), about
   !> 7.3 days; outputs about 1.0 MB (.his 1.0 MB, ...)'.
   pure function estimate_line(est) result(line)
      type(estimate_t), intent(in) :: est   !! the estimate
      character(len=:), allocatable :: line
      integer :: k
      character(len=:), allocatable :: parts
      if (est%cases > 1) then
         line = 'estimate: ' // sig3(est%cell_steps) // ' cell-steps (' // itoa(est%cases) // &
            ' cases, up to ' // itoa(est%cells) // ' cells x ' // itoa(est%steps) // &
            ' steps), about ' // duration_text(est%seconds) // ' on ' // itoa(est%ranks) // &
            ' rank(s) at this program''s speed (doc/outputs.md)'
         return
      end if
      line = 'estimate: ' // sig3(est%cell_steps) // ' cell-steps (' // itoa(est%cells) // &
         ' cells x ' // itoa(est%steps) // ' steps), about ' // duration_text(est%seconds) // &
         ' at this program''s speed (doc/outputs.md); outputs about ' // &
         bytes_text(sum(est%bytes))
      parts = ''
      do k = 1, n_outputs
         if (est%bytes(k) > 0.0_wp) parts = parts // ', ' // trim(out_ext(k)) // ' ' // &
                                            bytes_text(est%bytes(k))
      end do
      if (len(parts) > 0) line = line // ' (' // parts(3:) // '; .evt, .frg besides)'
   end function estimate_line

   !> The warnings of the estimate (none when &run warnings = .false.): more than an hour
   !> naming &mesh cells (or dt) and &run t_end (and history_every when its rows are most
   !> of it); more than 10 GB naming the variable of each output that holds a tenth of it.
   pure function estimate_warnings(deck, est) result(lines)
      type(deck_t), intent(in) :: deck     !! the deck
      type(estimate_t), intent(in) :: est  !! its estimate
      character(len=400), allocatable :: lines(:)
      character(len=:), allocatable :: mesh_var, text, parts
      real(wp) :: total
      integer :: k
      allocate(lines(0))
      if (.not. deck%run%warnings) return
      if (deck%mesh%cells > 0) then
         mesh_var = '&mesh cells = ' // itoa(deck%mesh%cells)
      else
         mesh_var = '&mesh dt = ' // sig3(deck%mesh%dt) // ' s (' // itoa(est%cells) // &
                    ' cells)'
      end if
      if (est%seconds > limit_seconds) then
         text = mesh_var // ' and &run t_end = ' // sig3(deck%run%t_end) // ' s make ' // &
            sig3(est%cell_steps) // ' cell-steps'
         if (est%cases > 1) text = text // ' over ' // itoa(est%cases) // &
            ' cases (&sweep realizations, values)'
         text = text // ': about ' // duration_text(est%seconds) // ' at this program''s ' // &
            'speed, more than an hour'
         if (est%row_seconds > 0.5_wp * est%seconds) text = text // '; &run history_every = ' &
            // itoa(deck%run%history_every) // ' makes most of it (' // &
            sig3(est%rows) // ' history rows of every cell)'
         lines = [character(len=400) :: lines, text // '; fewer cells or a shorter t_end?']
      end if
      total = sum(est%bytes)
      if (total > limit_bytes) then
         parts = ''
         do k = 1, n_outputs
            if (est%bytes(k) >= 0.1_wp * total) parts = parts // '; ' // trim(out_ext(k)) // &
               ' ' // bytes_text(est%bytes(k)) // ' from ' // output_variable(deck, k)
         end do
         lines = [character(len=400) :: lines, 'the outputs would be about ' // &
                  bytes_text(total) // ', more than 10 GB' // parts]
      end if
   end function estimate_warnings

   !> The deck variable that decides the size of output k (out_*), with its value.
   pure function output_variable(deck, k) result(text)
      type(deck_t), intent(in) :: deck     !! the deck
      integer, intent(in) :: k             !! the output (out_*)
      character(len=:), allocatable :: text
      select case (k)
      case (out_his)
         text = '&run history_every = ' // itoa(deck%run%history_every)
      case (out_prf)
         text = '&run profile_times (' // itoa(deck%run%n_profiles) // ' of them)'
      case (out_gau)
         if (deck%gauges%every > 0) then
            text = '&gauges every = ' // itoa(deck%gauges%every)
         else
            text = '&gauges every (not given: &run history_every = ' // &
                   itoa(deck%run%history_every) // ')'
         end if
         text = text // ' with ' // itoa(deck%gauges%n) // ' gauges'
      case default
         text = '&run hdf5'
         if (deck%run%field_every > 0) text = text // ' and field_every = ' // &
            itoa(deck%run%field_every)
      end select
   end function output_variable

   !> A duration for a message: '12 s', '3.5 min', '2.1 h', '7.3 days'.
   pure function duration_text(seconds) result(text)
      real(wp), intent(in) :: seconds      !! the duration [s]
      character(len=:), allocatable :: text
      if (seconds < 60.0_wp) then
         text = sig3(seconds) // ' s'
      else if (seconds < 3600.0_wp) then
         text = sig3(seconds / 60.0_wp) // ' min'
      else if (seconds < 86400.0_wp) then
         text = sig3(seconds / 3600.0_wp) // ' h'
      else
         text = sig3(seconds / 86400.0_wp) // ' days'
      end if
   end function duration_text

   !> An amount of bytes for a message: '62.3 GB', '6.5 MB', '12 kB'.
   pure function bytes_text(bytes) result(text)
      real(wp), intent(in) :: bytes        !! the amount [bytes]
      character(len=:), allocatable :: text
      if (bytes >= 1.0e9_wp) then
         text = sig3(bytes / 1.0e9_wp) // ' GB'
      else if (bytes >= 1.0e6_wp) then
         text = sig3(bytes / 1.0e6_wp) // ' MB'
      else
         text = sig3(bytes / 1.0e3_wp) // ' kB'
      end if
   end function bytes_text

   !> x with about three significant digits: '0.0123', '3.54', '62.3', '741', '2.52e13'.
   pure function sig3(x) result(text)
      real(wp), intent(in) :: x            !! the number
      character(len=:), allocatable :: text
      character(len=24) :: buf
      integer :: e, ex
      if (x == 0.0_wp) then
         text = '0'
      else if (abs(x) >= 1.0e-3_wp .and. abs(x) < 1.0e4_wp) then
         e = floor(log10(abs(x)))
         if (e >= 2) then
            write(buf, '(i0)') nint(x)
         else
            write(buf, '(f24.' // achar(iachar('0') + 2 - e) // ')') x
         end if
         text = trim(adjustl(buf))
      else
         write(buf, '(es24.2e3)') x
         text = trim(adjustl(buf))
         ! 2.52E+013 -> 2.52e13
         e = index(text, 'E')
         read(text(e + 1:), *) ex
         write(buf, '(i0)') ex
         text = text(:e - 1) // 'e' // trim(buf)
      end if
   end function sig3
end module spb_estimate
