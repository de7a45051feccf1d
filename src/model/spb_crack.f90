!> Cohesive cracks in the state (doc/method.md, "Cohesive cracks"): where a section with a
!> fracture energy opens a crack, and the crack's force in each step. The law and its
!> exact integrals are spb_cohesive's.
module spb_crack
   use spb_kinds, only: wp
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t, open_node
   use spb_wave, only: fragment_characteristics, region_wave
   use spb_cohesive, only: cohesive_force, law_integral, dissipated
   use spb_fragments, only: fragment_span
   use spb_damage, only: damage_reached
   use spb_columns, only: column_set_t, add_column
   implicit none
   private
   public :: start_cracks, cohesive_step
   public :: crack_columns_t, register_crack_columns, post_crack_columns

   !> The cohesive cracks' history columns (PREFIX.his, /history): their ids (spb_columns).
   type :: crack_columns_t
      integer :: e_cohesive = 0, cracks_open = 0
   end type crack_columns_t

contains

   !> Register the cohesive cracks' history columns: the energy they have dissipated, the
   !> cracks still open (their meaning: doc/outputs.md).
   pure subroutine register_crack_columns(set, id)
      type(column_set_t), intent(inout) :: set   !! the history's columns
      type(crack_columns_t), intent(out) :: id   !! their ids
      call add_column(set, id%e_cohesive, 'e_cohesive', 'J/m^2')
      call add_column(set, id%cracks_open, 'cracks_open', '-', whole=.true.)
   end subroutine register_crack_columns

   !> Post the cohesive cracks' values into a history row: the energy they have dissipated
   !> so far, open and completed (spb_cohesive), and the cracks that carry traction.
   pure subroutine post_crack_columns(id, st, row)
      type(crack_columns_t), intent(in) :: id   !! the columns' ids
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(inout) :: row(:)    !! the row
      row(id%e_cohesive) = 0.0_wp
      if (st%coh%on) row(id%e_cohesive) = sum(dissipated(st%coh%dmax, st%coh%r, st%coh%dc))
      row(id%cracks_open) = real(st%coh%n_active, wp)
   end subroutine post_crack_columns

   !> Open a cohesive crack at t^n at every joined section with a fracture energy whose
   !> section stress over the coming step, S^{n+1/2} (just computed), is beyond its strength
   !> (and, with a damage integral K > 0, whose damage reaches K in this step, spb_damage):
   !> the tension a section carries over a step is what the step would transmit, so the crack
   !> must carry the step already (opened after it, a crack lets the step's excess through,
   !> which breaks the next section one step later, and so on down the bar). Nothing of the
   !> state moves: the node splits with its halves where they are, and its faces take the
   !> step under the law's traction, which starts at the strength. The traction integral of
   !> the step that ended at t^n, I^n, is what the continuum reading of the joined fragment
   !> at t^n gives the section, (m_B du/dt - Z_{i+1} f_{i+1}) + (Z_i g_i - m_A du/dt): with
   !> it each face's equation holds with the joined reading's intervals, so the wave energy
   !> is unchanged (what the reading changes is booked in e_lost_wave all the same). The
   !> events are written by spb_fracture (st%coh%pending).
   pure subroutine start_cracks(mesh, g, st, i_top, i_bot, new, n_new)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp), intent(in) :: g            !! gravity along +x [m/s^2]
      type(state_t), intent(inout) :: st   !! the state at t^n, S^{n+1/2} in st%section
      real(wp), intent(in) :: i_top        !! load integral on the top face over the step that
                                           !! ended at t^n [Pa s]
      real(wp), intent(in) :: i_bot        !! the same on the bottom face [Pa s]
      integer, intent(out) :: new(:)       !! the nodes opened, ascending (first n_new)
      integer, intent(out) :: n_new        !! how many
      real(wp), allocatable :: f(:), gw(:)
      real(wp) :: q(mesh%n), e_wave0, dt, eps
      integer :: m, i, j, k, r_top, r_bot
      logical :: ready
      n_new = 0
      dt = mesh%dt
      eps = st%coh%eps_rel * st%s_scale
      do i = 1, mesh%n - 1
         if (.not. st%joined(i)) cycle
         if (.not. st%coh%gc(i) > 0.0_wp .or. st%strength(i) < 0.0_wp) cycle
         if (.not. (st%section(i) < -st%strength(i) - eps)) cycle
         if (any(st%skip_test(1:st%n_skip) == i)) cycle
         ! with a damage integral K > 0 the crack opens once the damage reaches K (spb_damage)
         call damage_reached(mesh, st, i, ready)
         if (.not. ready) cycle
         n_new = n_new + 1
         new(n_new) = i
      end do
      if (n_new == 0) return
      call fragment_span(mesh, st, new(1), r_top, k)
      call fragment_span(mesh, st, new(n_new), j, r_bot)
      e_wave0 = region_wave(mesh, st, g, i_top, i_bot, r_top, r_bot)
      allocate(f(r_top+1:r_bot), gw(r_top+1:r_bot))
      ! the readings of the fragments at t^n, before any of them splits
      m = 1
      do while (m <= n_new)
         call fragment_span(mesh, st, new(m), j, k)
         call fragment_characteristics(mesh, st, g, j, k, i_top, i_bot, .false., f(j+1:k), &
                                       gw(j+1:k))
         do while (m <= n_new)
            if (new(m) >= k) exit
            i = new(m)
            q(m) = (mesh%mb(i) * st%dub(i) / dt - mesh%z(i + 1) * f(i + 1)) + &
                   (mesh%z(i) * gw(i) - mesh%ma(i) * st%dua(i) / dt)
            m = m + 1
         end do
      end do
      do m = 1, n_new
         i = new(m)
         call open_node(st, i)
         st%n_breakable = st%n_breakable - 1
         st%coh%r(i) = st%strength(i)
         st%coh%dc(i) = 2.0_wp * st%coh%gc(i) / st%strength(i)
         st%coh%q(i) = q(m)
         st%coh%opening(i) = 0.0_wp
         st%coh%active(i) = .true.
         st%coh%n_active = st%coh%n_active + 1
         st%coh%n_pending = st%coh%n_pending + 1
         st%coh%pending(st%coh%n_pending) = i
         st%coh%pending_stress(st%coh%n_pending) = st%section(i)
         st%strength(i) = 0.0_wp
         st%section(i) = 0.0_wp
      end do
      st%ledger%e_lost_wave = st%ledger%e_lost_wave + e_wave0 - region_wave(mesh, st, g, i_top, &
                                                                           i_bot, r_top, r_bot)
   end subroutine start_cracks

   !> The cohesive cracks' forces of the step (spb_cohesive): each open crack's faces, whose
   !> increments the step has set as free faces', take the force P^n that the stepwise form
   !> and the law give; the traction integral I^{n+1}, the largest opening and the work in both
   !> measures are booked. A crack open beyond its critical opening that carried nothing over
   !> the step has applied its last force: it is a plain split node from now on.
   pure subroutine cohesive_step(mesh, st, split, old_a, old_b)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(inout) :: st   !! the state (increments of the step set)
      integer, intent(in) :: split(:)      !! the split nodes
      real(wp), intent(in) :: old_a(:)     !! their upper halves' increments du^n [m]
      real(wp), intent(in) :: old_b(:)     !! their lower halves' increments du^n [m]
      real(wp) :: dt, dt2, a, dstar, p, q_next, d1, w
      integer :: c, i
      logical :: contact
      dt = mesh%dt
      dt2 = dt * dt
      do c = 1, size(split)
         i = split(c)
         if (.not. st%coh%active(i)) cycle
         ! the crack's own opening (spb_state cohesive_t): the faces' distance less what rigid
         ! shifts added, kept by the increments (not ub - ua: the positions' round-off, which
         ! is the frame's, is large beside a small opening: doc/method.md, "Cohesive cracks")
         a = st%coh%opening(i)
         dstar = a + (st%dub(i) - st%dua(i))
         call cohesive_force(a, dstar, dt2 * (1.0_wp / mesh%ma(i) + 1.0_wp / mesh%mb(i)), dt, &
                             st%coh%q(i), st%coh%dmax(i), st%coh%r(i), st%coh%dc(i), p, q_next, &
                             contact)
         ! the traction pulls the upper half down and the lower one up
         st%dua(i) = st%dua(i) + p / mesh%ma(i) * dt2
         st%dub(i) = st%dub(i) - p / mesh%mb(i) * dt2
         d1 = a + (st%dub(i) - st%dua(i))
         w = q_next * (d1 - a) / dt
         st%ledger%w_cohesive = st%ledger%w_cohesive + w
         ! what a step that ends in contact took beyond the law's integral (elsewhere the law's
         ! root makes the two equal, to round-off)
         if (contact) st%ledger%e_closing = st%ledger%e_closing + (w - law_integral(a, d1, &
                                            st%coh%dmax(i), st%coh%r(i), st%coh%dc(i)))
         st%ledger%w_wave = st%ledger%w_wave - w
         st%ledger%e_traction = st%ledger%e_traction + &
                                p * 0.5_wp * ((d1 - a) + (old_b(c) - old_a(c)))
         st%coh%dmax(i) = max(st%coh%dmax(i), d1)
         st%coh%opening(i) = d1
         st%coh%q(i) = q_next
         if (.not. abs(q_next) > 0.0_wp .and. st%coh%dmax(i) >= st%coh%dc(i)) then
            ! a plain split node from now on: its faces' contact is the collisions'
            st%coh%active(i) = .false.
            st%coh%n_active = st%coh%n_active - 1
            st%coh%opening(i) = 0.0_wp
         end if
      end do
   end subroutine cohesive_step

end module spb_crack
