!> Growable integer lists: append with doubling, so that events stay O(1) amortised.
module spb_arrays
   implicit none
   private
   public :: append

contains

   !> Append value to list(1:n), growing the allocation by doubling; n is incremented.
   pure subroutine append(list, n, value)
      integer, allocatable, intent(inout) :: list(:)   !! the list (grown as needed)
      integer, intent(inout) :: n          !! entries in use
      integer, intent(in) :: value         !! the value to append
      integer, allocatable :: grown(:)
      if (.not. allocated(list)) allocate(list(8), source=0)
      if (n == size(list)) then
         ! the unused tail is 0: a checkpoint writes the whole list, the same bytes every run
         allocate(grown(max(8, 2 * size(list))), source=0)
         grown(1:n) = list(1:n)
         call move_alloc(grown, list)
      end if
      n = n + 1
      list(n) = value
   end subroutine append
end module spb_arrays
