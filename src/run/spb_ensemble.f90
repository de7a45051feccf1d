!> The ensemble of a sweep (&sweep ensemble_columns; doc/sweeps.md, "Ensembles"): at every
!> history time the mean, standard deviation, minimum and maximum over the realizations of
!> each ensemble column, and each column's predictability horizon from its 1 ms window
!> means. What PREFIX.ens and /ensemble of PREFIX_sweep.h5 hold; spb_sweep gathers the
!> realizations' series and writes the files.
!>
!> Every sum runs over the realizations in realization order on one rank (rank 0, after the
!> series are gathered in case order), so the numbers do not depend on the ranks.
module spb_ensemble
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use spb_kinds, only: wp
   use spb_strings, only: itoa, rtoa
   use spb_columns, only: column_set_t
   use spb_history, only: history_set
   use spb_hdf5, only: h5file_t, h5_attr, h5_group, h5_write
   use spb_schedule, only: row_count
   implicit none
   private
   public :: ensemble_t, ensemble_setup, ensemble_reduce, ensemble_columns_line, &
      ensemble_row, ensemble_notes, ensemble_h5, horizon_text, ensemble_window

   !> The width of the windows the horizon compares: 1 ms [s].
   real(wp), parameter :: ensemble_window = 1.0e-3_wp
   !> Its inverse, exact: a horizon k / 1000 s prints as k ms [1/s].
   real(wp), parameter :: windows_per_second = 1000.0_wp
   !> The statistics of a column, in the order of PREFIX.ens: C_mean, C_std, C_min, C_max.
   character(len=*), parameter :: stat_names(4) = [character(len=5) :: '_mean', '_std', &
      '_min', '_max']
   integer, parameter :: n_stats = size(stat_names)

   !> The ensemble: its columns, its history times, and (ensemble_reduce) its statistics.
   type :: ensemble_t
      integer :: n_cols = 0                          !! ensemble columns
      integer :: n_rows = 0                          !! history rows of every realization
      character(len=24), allocatable :: names(:)     !! the columns' names
      character(len=16), allocatable :: units(:)     !! their units
      integer, allocatable :: ids(:)                 !! their places in history_set
      integer :: every = 1                           !! &run history_every [steps]
      integer :: nsteps = 0                          !! steps of every realization
      real(wp) :: dt = 0.0_wp                        !! their step [s]
      real(wp) :: tol = 0.01_wp                      !! &sweep horizon_tol [-]
      integer :: members = 0                         !! realizations done (status 0), counted
      integer :: realizations = 0                    !! realizations of the sweep
      real(wp), allocatable :: t(:)                  !! the rows' times [s]
      real(wp), allocatable :: stats(:, :, :)        !! (statistic, column, row): mean, std,
                                                     !! min, max [the column's unit]
      integer :: windows = 0                         !! whole 1 ms windows before t_end
      real(wp), allocatable :: horizon(:)            !! per column: the start of the first
                                                     !! window past the tolerance [s]; -1 not
                                                     !! reached; NaN no window with a row
      real(wp), allocatable :: scale(:)              !! per column: largest |ensemble mean of
                                                     !! a window mean| [the column's unit]
      real(wp), allocatable :: spread_at(:)          !! per column: the window std at the
                                                     !! horizon, or the largest [unit]
   end type ensemble_t

contains

   !> The ensemble of the history columns names (validated by the deck reader), with units
   !> (as the history's, per unit area or not), for realizations sharing nsteps steps of dt
   !> and rows every `every` steps.
   pure subroutine ensemble_setup(ens, names, units, every, nsteps, dt, tol, realizations)
      type(ensemble_t), intent(out) :: ens   !! the ensemble
      character(len=*), intent(in) :: names(:)   !! the columns
      character(len=*), intent(in) :: units(:)   !! their units
      integer, intent(in) :: every         !! steps between history rows
      integer, intent(in) :: nsteps        !! steps of the realizations
      real(wp), intent(in) :: dt           !! their step [s]
      real(wp), intent(in) :: tol          !! the horizon's share [-]
      integer, intent(in) :: realizations  !! realizations
      type(column_set_t) :: his
      integer :: j, k
      his = history_set()
      ens%n_cols = size(names)
      allocate(ens%names(ens%n_cols), ens%units(ens%n_cols), ens%ids(ens%n_cols))
      ens%ids = 0
      do j = 1, ens%n_cols
         ens%names(j) = names(j)
         ens%units(j) = units(j)
         do k = 1, size(his%col)
            if (his%col(k)%name == names(j)) ens%ids(j) = k
         end do
      end do
      ens%every = max(every, 1)
      ens%nsteps = nsteps
      ens%dt = dt
      ens%tol = tol
      ens%realizations = realizations
      ens%n_rows = row_count(ens%every, nsteps)
      allocate(ens%t(ens%n_rows))
      do k = 1, ens%n_rows
         ens%t(k) = real(min((k - 1) * ens%every, nsteps), wp) * dt
      end do
      ! the whole windows up to t_end (one ending within 1e-9 of a window's width counts)
      ens%windows = int(real(nsteps, wp) * dt / ensemble_window + 1.0e-9_wp)
   end subroutine ensemble_setup

   !> The statistics over the realizations whose member flag is set, series(:, c) being
   !> realization c's columns at its rows ((column, row) in column order); and the horizons.
   !> Mean and standard deviation are the population's (divided by the number of members),
   !> in two passes; a column whose members all agree has exactly that mean and std 0.
   pure subroutine ensemble_reduce(ens, series, member)
      type(ensemble_t), intent(inout) :: ens   !! the ensemble
      real(wp), intent(in) :: series(:, :)     !! (column + n_cols (row - 1), realization)
      logical, intent(in) :: member(:)         !! realization c counts
      real(wp), allocatable :: wmean(:, :, :)  ! (window, column, member): window means
      real(wp) :: x(count(member))
      integer, allocatable :: wcount(:)        ! samples per window
      integer :: j, k, r, m, w
      ens%members = count(member)
      allocate(ens%stats(n_stats, ens%n_cols, ens%n_rows), source=0.0_wp)
      allocate(ens%horizon(ens%n_cols), ens%scale(ens%n_cols), ens%spread_at(ens%n_cols))
      do k = 1, ens%n_rows
         do j = 1, ens%n_cols
            x = pack(series(j + ens%n_cols * (k - 1), :), member)
            if (size(x) > 0) call describe(x, ens%stats(:, j, k))
         end do
      end do
      ! each member's window means: the mean of its rows with floor(t / 1 ms) = w
      allocate(wmean(ens%windows, ens%n_cols, ens%members), source=0.0_wp)
      allocate(wcount(ens%windows), source=0)
      do k = 1, ens%n_rows
         w = int(ens%t(k) / ensemble_window) + 1
         if (w <= ens%windows) wcount(w) = wcount(w) + 1
      end do
      m = 0
      do r = 1, size(member)
         if (.not. member(r)) cycle
         m = m + 1
         do k = 1, ens%n_rows
            w = int(ens%t(k) / ensemble_window) + 1
            if (w > ens%windows) cycle
            wmean(w, :, m) = wmean(w, :, m) + series(ens%n_cols * (k - 1) + 1: &
                                                     ens%n_cols * k, r)
         end do
         do w = 1, ens%windows
            if (wcount(w) > 0) wmean(w, :, m) = wmean(w, :, m) / real(wcount(w), wp)
         end do
      end do
      do j = 1, ens%n_cols
         call horizon(wmean(:, j, :), wcount, ens%tol, ens%horizon(j), ens%scale(j), &
                      ens%spread_at(j))
      end do
   end subroutine ensemble_reduce

   !> Mean, standard deviation (population), minimum, maximum of x (at least one value).
   pure subroutine describe(x, s)
      real(wp), intent(in) :: x(:)         !! the values, in realization order
      real(wp), intent(out) :: s(n_stats)  !! mean, std, min, max
      real(wp) :: mean
      s(3) = minval(x)
      s(4) = maxval(x)
      if (.not. (s(4) > s(3))) then
         s(1) = s(3)
         s(2) = 0.0_wp
         return
      end if
      mean = sum(x) / real(size(x), wp)
      s(1) = mean
      s(2) = sqrt(sum((x - mean)**2) / real(size(x), wp))
   end subroutine describe

   !> The horizon of one column from its members' window means wm(window, member): the
   !> start of the first window (with rows) whose std over the members exceeds tol times
   !> the largest |mean over the members| of any window (-1: none; NaN: no window has a row).
   pure subroutine horizon(wm, wcount, tol, t_h, scale, spread)
      real(wp), intent(in) :: wm(:, :)     !! (window, member) window means
      integer, intent(in) :: wcount(:)     !! rows per window
      real(wp), intent(in) :: tol          !! the share [-]
      real(wp), intent(out) :: t_h         !! the horizon [s]
      real(wp), intent(out) :: scale       !! the largest |window mean| [unit]
      real(wp), intent(out) :: spread      !! the window std at the horizon, else the largest
      real(wp) :: s(n_stats, size(wm, 1))
      integer :: w
      t_h = -1.0_wp
      scale = 0.0_wp
      spread = 0.0_wp
      if (.not. any(wcount > 0) .or. size(wm, 2) == 0) then
         t_h = ieee_nan()
         return
      end if
      do w = 1, size(wm, 1)
         if (wcount(w) > 0) call describe(wm(w, :), s(:, w))
         if (wcount(w) > 0) scale = max(scale, abs(s(1, w)))
      end do
      do w = 1, size(wm, 1)
         if (wcount(w) == 0) cycle
         spread = max(spread, s(2, w))
         if (s(2, w) > tol * scale) then
            spread = s(2, w)
            t_h = real(w - 1, wp) / windows_per_second
            return
         end if
      end do
   end subroutine horizon

   !> A quiet NaN (the horizon of a column without a window).
   pure real(wp) function ieee_nan()
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
      ieee_nan = ieee_value(ieee_nan, ieee_quiet_nan)
   end function ieee_nan

   !> PREFIX.ens's column names, blank-separated: t, then C_mean C_std C_min C_max per column.
   pure function ensemble_columns_line(ens) result(line)
      type(ensemble_t), intent(in) :: ens  !! the ensemble
      character(len=:), allocatable :: line
      integer :: j, s
      line = 't'
      do j = 1, ens%n_cols
         do s = 1, n_stats
            line = line // ' ' // trim(ens%names(j)) // trim(stat_names(s))
         end do
      end do
   end function ensemble_columns_line

   !> Row k of PREFIX.ens: t and the statistics, each a blank and es20.12e3 (as PREFIX.sweep).
   function ensemble_row(ens, k) result(line)
      type(ensemble_t), intent(in) :: ens  !! the ensemble (reduced)
      integer, intent(in) :: k             !! the row
      character(len=:), allocatable :: line
      character(len=21) :: cell
      integer :: j, s
      write(cell, '(1x,es20.12e3)') ens%t(k)
      line = cell
      do j = 1, ens%n_cols
         do s = 1, n_stats
            write(cell, '(1x,es20.12e3)') ens%stats(s, j, k)
            line = line // ' ' // cell
         end do
      end do
   end function ensemble_row

   !> The horizon of column j as the header and the summary say it.
   function horizon_text(ens, j) result(text)
      type(ensemble_t), intent(in) :: ens  !! the ensemble (reduced)
      integer, intent(in) :: j             !! the column
      character(len=:), allocatable :: text
      character(len=12) :: a, b
      write(a, '(es12.4e3)') ens%spread_at(j)
      write(b, '(es12.4e3)') ens%tol * ens%scale(j)
      if (ieee_is_nan(ens%horizon(j))) then
         text = 'none (no 1 ms window with a history row before t_end = ' // &
                six_digits(real(ens%nsteps, wp) * ens%dt) // ' s)'
      else if (ens%horizon(j) < 0.0_wp) then
         text = 'not reached before t_end = ' // six_digits(real(ens%nsteps, wp) * ens%dt) // &
                ' s (largest std of a window mean ' // trim(adjustl(a)) // ' <= ' // &
                trim(adjustl(b)) // ' ' // trim(ens%units(j)) // ')'
      else
         text = rtoa(ens%horizon(j)) // ' s (window [' // rtoa(ens%horizon(j)) // ', ' // &
                rtoa(real(nint(ens%horizon(j) * windows_per_second) + 1, wp) / &
                windows_per_second) // ') s: std of the window means ' // &
                trim(adjustl(a)) // ' > ' // trim(adjustl(b)) // ' ' // trim(ens%units(j)) // ')'
      end if
   end function horizon_text

   !> x to six significant digits, as rtoa writes numbers (0.0502701 for 0.05027007584).
   function six_digits(x) result(text)
      real(wp), intent(in) :: x            !! the number
      character(len=:), allocatable :: text
      character(len=16) :: buf
      real(wp) :: y
      write(buf, '(es16.5e3)') x
      read(buf, *) y
      text = rtoa(y)
   end function six_digits

   !> PREFIX.ens's header lines after the deck's echo (without '# '): the ensemble, the
   !> rules, each column's horizon, the units.
   function ensemble_notes(ens, perturb, spread) result(lines)
      type(ensemble_t), intent(in) :: ens  !! the ensemble (reduced)
      character(len=*), intent(in) :: perturb   !! &sweep perturb ('': a Weibull field)
      real(wp), intent(in) :: spread       !! &sweep spread [-]
      character(len=400), allocatable :: lines(:)
      character(len=:), allocatable :: what, units
      integer :: j
      if (len_trim(perturb) > 0) then
         what = trim(perturb) // ' x (1 + ' // rtoa(spread) // ' u_i), u_i uniform in ' // &
                '(-1, 1) from (seed, i) (the value column of PREFIX.sweep)'
      else
         what = 'the Weibull strength field of seed realization_seed(seed, i)'
      end if
      units = 't [s]'
      do j = 1, ens%n_cols
         units = units // '; ' // trim(ens%names(j)) // '_* [' // trim(ens%units(j)) // ']'
      end do
      lines = [character(len=400) :: &
         'ensemble: ' // itoa(ens%members) // ' of ' // itoa(ens%realizations) // &
         ' realizations (those done, status 0), realization i: ' // what, &
         'rows: the history times (&run history_every = ' // itoa(ens%every) // &
         ' steps and t_end), shared by every realization', &
         'C_mean, C_std: mean and standard deviation over the realizations (population: ' // &
         'sum / N, sqrt(sum (x - mean)^2 / N)); C_min, C_max: the extremes', &
         'horizon: the start of the first 1 ms window [k ms, (k+1) ms) (the whole ones ' // &
         'before t_end) whose std over the realizations of the window mean of C exceeds ' // &
         'horizon_tol = ' // rtoa(ens%tol) // ' x the largest |mean window mean| of C']
      do j = 1, ens%n_cols
         lines = [character(len=400) :: lines, 'horizon ' // trim(ens%names(j)) // ': ' // &
                  horizon_text(ens, j)]
      end do
      lines = [character(len=400) :: lines, 'units: ' // units]
   end function ensemble_notes

   !> /ensemble of PREFIX_sweep.h5: t [s], C_mean, C_std, C_min, C_max per column (its unit),
   !> horizon [s] per column (-1 not reached, NaN no window); attributes columns,
   !> horizon_tol, window [s], members, realizations.
   subroutine ensemble_h5(h5, ens)
      type(h5file_t), intent(inout) :: h5  !! the sweep's HDF5 file
      type(ensemble_t), intent(in) :: ens  !! the ensemble (reduced)
      real(wp) :: col(ens%n_rows)
      integer :: j, s
      call h5_group(h5, '/ensemble')
      call h5_attr(h5, '/ensemble', 'columns', ens%names)
      call h5_attr(h5, '/ensemble', 'horizon_tol', ens%tol)
      call h5_attr(h5, '/ensemble', 'window', ensemble_window)
      call h5_attr(h5, '/ensemble', 'members', ens%members)
      call h5_attr(h5, '/ensemble', 'realizations', ens%realizations)
      call h5_write(h5, '/ensemble/t', ens%t, 's')
      do j = 1, ens%n_cols
         do s = 1, n_stats
            col = ens%stats(s, j, :)    ! contiguous
            call h5_write(h5, '/ensemble/' // trim(ens%names(j)) // trim(stat_names(s)), col, &
                          trim(ens%units(j)))
         end do
      end do
      call h5_write(h5, '/ensemble/horizon', ens%horizon, 's')
   end subroutine ensemble_h5
end module spb_ensemble
