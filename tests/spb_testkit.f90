!> Helpers the .pf tests share: decks built in memory, set-up that stops loudly.
module spb_testkit
   use, intrinsic :: iso_fortran_env, only: output_unit
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t
   use spb_deck, only: deck_t, validate_deck
   use spb_sim, only: sim_t, sim_setup
   implicit none
   private
   public :: layered_deck, setup_sim, write_lines, contains_text

contains

   !> A deck of segments whose lengths are whole cells of the given dt.
   function layered_deck(cells, young, density, dt, t_end, top, bottom) result(deck)
      integer, intent(in) :: cells(:)            !! cells per segment
      real(wp), intent(in) :: young(:), density(:)
      real(wp), intent(in) :: dt, t_end          !! [s]
      character(len=*), intent(in) :: top, bottom
      type(deck_t) :: deck
      integer :: j, n
      n = size(cells)
      deck%seg%n = n
      do j = 1, n
         deck%seg%young(j) = young(j)
         deck%seg%density(j) = density(j)
         deck%seg%length(j) = real(cells(j), wp) * sqrt(young(j) / density(j)) * dt
      end do
      deck%mesh%dt = dt
      deck%run%t_end = t_end
      deck%ends%top = top
      deck%ends%bottom = bottom
   end function layered_deck

   !> Validate the deck and build the simulation; any error stops the test program.
   subroutine setup_sim(deck, sim)
      type(deck_t), intent(inout) :: deck
      type(sim_t), intent(out) :: sim
      type(spb_error_t), allocatable :: err
      call validate_deck(deck, err)
      if (.not. allocated(err)) call sim_setup(deck, sim, err)
      if (allocated(err)) then
         write(output_unit, '(a)') 'test set-up failed: ' // err%message
         error stop 1
      end if
   end subroutine setup_sim

   !> Write lines to a text file (decks and tables for tests).
   subroutine write_lines(path, lines)
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: lines(:)
      integer :: u, k
      open(newunit=u, file=path, status='replace', action='write')
      do k = 1, size(lines)
         write(u, '(a)') trim(lines(k))
      end do
      close(u)
   end subroutine write_lines

   logical function contains_text(haystack, needle)
      character(len=*), intent(in) :: haystack, needle
      contains_text = index(haystack, needle) > 0
   end function contains_text
end module spb_testkit
