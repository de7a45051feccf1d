!> The run's schedule: every periodic action of the stepping loop in one list, which both
!> steppers obey (the single step takes each action when it is due; the cache-blocked stepper
!> stops before the next step at which any action is due).
!>
!> An action is due at the multiples of its period, or at the steps of its list; the end of
!> the run is always a stop.
module spb_schedule
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   private
   public :: schedule_t, schedule_every, schedule_at, is_due, next_due, row_count, row_index
   public :: act_row, act_check, act_field, act_checkpoint, act_progress, act_gauge
   public :: check_every, keeps_rows

   !> The actions: a history row; the finiteness and energy-guard check between rows; a
   !> profile; an x-t field row; a checkpoint; the progress line and the flush of the outputs;
   !> a row of the gauges.
   integer, parameter :: act_row = 1, act_check = 2, act_profile = 3, act_field = 4, &
                         act_checkpoint = 5, act_progress = 6, act_gauge = 7, n_actions = 7

   !> The check between rows (finiteness, energy guard) runs every check_every steps (and
   !> after each span of characteristic steps); a run that keeps no rows (keeps_rows) takes
   !> its summary's running values there too (doc/sweeps.md).
   integer, parameter :: check_every = 64

   type :: schedule_t
      integer :: n_end = 0                       !! the last step of the run
      integer :: every(n_actions) = 0            !! period of each action [steps]; 0: none
      integer, allocatable :: at(:)              !! act_profile: its steps, non-decreasing
   end type schedule_t

contains

   !> A run computes history rows only where it writes them (files) or keeps some of their
   !> columns (sampling: a sweep's case with ensemble columns); a sweep's case without an
   !> ensemble computes none (doc/sweeps.md, "What a case computes").
   pure logical function keeps_rows(files, sampling)
      logical, intent(in) :: files         !! the run writes its outputs
      logical, intent(in) :: sampling      !! it keeps history columns in memory
      keeps_rows = files .or. sampling
   end function keeps_rows

   !> Action act is due at every multiple of period (period <= 0: never by period).
   pure subroutine schedule_every(sched, act, period)
      type(schedule_t), intent(inout) :: sched   !! the schedule
      integer, intent(in) :: act           !! the action (act_*)
      integer, intent(in) :: period        !! its period [steps]
      sched%every(act) = max(period, 0)
   end subroutine schedule_every

   !> The profile action is due at these steps.
   pure subroutine schedule_at(sched, steps)
      type(schedule_t), intent(inout) :: sched   !! the schedule
      integer, intent(in) :: steps(:)      !! [steps], non-decreasing
      sched%at = steps
   end subroutine schedule_at

   !> Whether action act is due by its period at step n (list actions: see next_due).
   pure logical function is_due(sched, act, n)
      type(schedule_t), intent(in) :: sched   !! the schedule
      integer, intent(in) :: act           !! the action (act_*)
      integer, intent(in) :: n             !! the step
      is_due = .false.
      if (sched%every(act) > 0) is_due = mod(n, sched%every(act)) == 0
   end function is_due

   !> The first step after n at which an action is due or the run ends; next_at is the index
   !> into the profile list of the first profile not yet written (its step counts if > n).
   pure integer function next_due(sched, n, next_at) result(m)
      type(schedule_t), intent(in) :: sched   !! the schedule
      integer, intent(in) :: n         !! the step just taken
      integer, intent(in) :: next_at   !! index of the next profile in sched%at
      integer(int64) :: m8
      integer :: act
      m8 = int(sched%n_end, int64)
      do act = 1, n_actions
         if (sched%every(act) > 0) m8 = min(m8, (n / sched%every(act) + 1) * &
                                           int(sched%every(act), int64))
      end do
      if (allocated(sched%at)) then
         if (next_at <= size(sched%at)) then
            if (sched%at(next_at) > n) m8 = min(m8, int(sched%at(next_at), int64))
         end if
      end if
      m = int(m8)
   end function next_due

   !> Rows of an action due every `every` steps of a run of n_end steps, with the row at
   !> step 0 and the last step's (a history: spb_sim's rows) [-].
   pure integer function row_count(every, n_end) result(rows)
      integer, intent(in) :: every         !! steps between rows (>= 1)
      integer, intent(in) :: n_end         !! the last step
      rows = n_end / every + 1
      if (mod(n_end, every) /= 0) rows = rows + 1
   end function row_count

   !> The place of step n's row among those row_count counts (0: step n has none).
   pure integer function row_index(every, n_end, n) result(k)
      integer, intent(in) :: every         !! steps between rows (>= 1)
      integer, intent(in) :: n_end         !! the last step
      integer, intent(in) :: n             !! the step
      k = 0
      if (mod(n, every) == 0) then
         k = n / every + 1
      else if (n == n_end) then
         k = n_end / every + 2
      end if
   end function row_index
end module spb_schedule
