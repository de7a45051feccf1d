!> Outputs (doc/outputs.md): the column text files PREFIX.his, .prf, .evt, .frg, .imp (and .gau
!> with &gauges), PREFIX.spl at the end and, with
!> &run hdf5 = .true., PREFIX.h5 holding the same (layout in doc/outputs.md).
!>
!> Each text file starts with '#' header lines (version, title, the full echoed deck, the
!> mesh, units); the last header line names the columns. Every writer here writes both.
module spb_output
   use, intrinsic :: iso_fortran_env, only: int64
   use spb_kinds, only: wp
   use spb_identity, only: program_identity, build_revision
   use spb_error, only: spb_error_t, make_error, exit_runtime
   use spb_strings, only: itoa, rtoa, es20_12, es_into, int_right, int_into
   use spb_deck, only: deck_record_t, write_echo
   use spb_deck_types, only: echo_item_t
   use spb_hdf5, only: h5file_t, h5_create, h5_close, h5_flush, h5_attr, h5_group, h5_write, &
      h5_table, h5_append, h5_xt, h5_append_xt, h5_open_read, h5_get, h5_get_columns, h5_copy, &
      h5_table_rows, h5_xt_rows, h5_read_size, xt_gauges, block_name, buffer_rows
   use spb_xdmf, only: write_xdmf, xdmf_path
   use spb_sys, only: sys_rename, sys_file_size, sys_lock, sys_real_path, sys_is_directory, &
      sys_same_file, sys_lock_held, sys_write_trouble, &
      sys_file_kind, file_other
   use spb_mesh, only: mesh_t
   use spb_state, only: state_t
   use spb_events, only: event_list_t, event_kinds, event_columns_t, register_event_columns, &
      post_event_columns
   use spb_diag, only: frag_info_t
   use spb_gauge, only: gauge_t, locate_gauges
   use spb_columns, only: column_t, column_set_t, column_fault, column_names
   use spb_history, only: history_ids_t, register_history, history_set
   use spb_diagnostics, only: diag_t, spall_row, impact_row, spall_columns, impact_columns, &
      spall_units, impact_units, end_names, imp_kind_names, pick_fraction, impact_t
   implicit none
   private
   public :: write_diag_text, write_diag_h5, diag_unit, write_impacts
   public :: outputs_t, open_outputs, close_outputs, write_history_row, write_profile
   public :: history_columns, write_mesh_summary, write_events, write_fragments
   public :: write_field, flush_outputs, h5_deck_header, column_t, column_names
   public :: write_gauge_row, gauge_columns, text_count, claim_sweep_outputs, bar_units
   public :: program_line, publish_outputs, where_outputs, out_path, is_temporary, remove_file
   public :: output_marks_t, mark_outputs, text_extensions, tail_len, claim_outputs, &
      check_written
   ! for spb_restart, which continues the outputs of a checkpointed run
   public :: event_columns, impact_table_columns, find_header, column_line, text_unit, set_text_unit, no_unit, &
      block_name, split

   character(len=*), parameter :: history_units = 't [s]; reaction_*, s_end_* [Pa] ' &
      // '(compression > 0); fragments, step [-]; e_*, w_*, ledger [J/m^2]; momentum, i_*, ' &
      // 'p_shift [kg/(m s)] along +x (down); jordan [-]; x_impactor [m], v_impactor [m/s] ' &
      // 'along +x, f_impactor [N/m^2] (compression > 0); x_cm, x_drift [m] along +x'
   character(len=*), parameter :: fragment_columns = 'id parent birth_t x_top x_bottom mass ' &
      // 'velocity e_vib top_node bottom_node t'
   character(len=*), parameter :: profile_columns = 'x u v stress t'
   ! The rows' formats, written by the fast formatters (es20_12, int_right), which give the
   ! same characters: .evt and .his (1x,es20.12e3 | 1x,i12 | 1x,a16 per column: table_line;
   ! .evt then 1x,i9 kind_code), .frg (2(1x,i12),6(1x,es20.12e3),2(1x,i12),1x,es20.12e3),
   ! .prf (5(1x,es20.12e3)), .gau (1x,es20.12e3 per column).

   !> Bytes of rows collected per text file before they are written: one write statement
   !> per buffer instead of one per row (the run-time library's cost per record is most of
   !> the writing otherwise); the bytes in the file are the same.
   integer, parameter :: row_buffer_len = 262144

   !> A table's last row as text, with the bits of the value each field was made from: a
   !> value repeated from the row before (a third of the event columns: t within a step, x,
   !> dt_bound, ...; most of the history's) is not formatted or copied again (a field's
   !> text depends on the value's bits alone), and the next row is written over this one.
   type :: row_cache_t
      character(len=:), allocatable :: line            !! the row: each column a blank and
                                                       !! its field (allocated at the first)
      integer(int64), allocatable :: bits(:)           !! each field's value's bits (transfer)
      logical, allocatable :: set(:)                   !! the field holds a value
   end type row_cache_t

   !> Rows of one text file not yet written: text(1:n), each row ended by a newline.
   type :: row_buffer_t
      character(len=:), allocatable :: text   !! the rows (allocated at the first row)
      integer :: n = 0                        !! bytes held
   end type row_buffer_t

   !> A closed file's unit: newunit= numbers are negative but never -1.
   integer, parameter :: no_unit = -1

   !> Text files a run may write (text_extensions).
   integer, parameter :: n_text = 6

   type :: outputs_t
      character(len=:), allocatable :: prefix
      character(len=:), allocatable :: part   !! '.part' while written as temporaries, else ''
      logical :: with_h5 = .false.                        !! PREFIX.h5 is one of them
      integer :: his = no_unit, prf = no_unit, evt = no_unit, frg = no_unit   !! units
      integer :: imp = no_unit                            !! PREFIX.imp's unit
      integer :: gau = no_unit                            !! PREFIX.gau's unit (no gauges: none)
      integer :: n_gauges = 0                             !! gauges (columns 3 n_gauges + 1)
      logical :: hdf5 = .false.                           !! PREFIX.h5 is written
      logical :: per_area = .true.                        !! every area 1: units per unit area
      type(h5file_t) :: h5
      integer :: h_his = 0, h_evt = 0, h_imp = 0          !! its table handles
      type(column_t), allocatable :: his_table(:)         !! the history's columns (spb_history)
      type(history_ids_t) :: his_id                       !! their ids: a row is posted under
                                                          !! them (spb_history post_history)
      type(column_t), allocatable :: evt_table(:)         !! the events' columns (spb_events)
      type(event_columns_t) :: evt_id                     !! their ids
      integer :: n_prof = 0, n_frg = 0                    !! profile, fragment blocks so far
      integer(int64) :: head(n_text) = 0                       !! header bytes of each text file
      type(row_buffer_t) :: rows(n_text)                       !! rows not yet written, per text
                                                          !! file (text_extensions order)
      type(row_cache_t) :: his_cache, evt_cache           !! the last row's texts
      type(row_cache_t) :: imp_cache                      !! .imp's last row's text
      integer(int64) :: n_his = 0, n_evt = 0, n_imp = 0   !! .his, .evt, .imp rows written here
      integer(int64) :: expect(n_text) = 0                     !! bytes each text file should
                                                          !! hold: check_written's measure
                                                          !! (a write the disk refuses is
                                                          !! not always in inquire's size)
      logical :: refused(n_text) = .false.                     !! a write of rows to it failed
   end type outputs_t

   !> The text files, in the order of outputs_t%head and output_marks_t (.gau: with &gauges).
   character(len=4), parameter :: text_extensions(n_text) = ['.his', '.prf', '.evt', '.frg', &
      '.imp', '.gau']

   integer, parameter :: tail_len = 240   !! bytes of each text file a mark remembers
   !> the suffix of an output written as a temporary until the run publishes it
   character(len=*), parameter :: part_suffix = '.part'

   !> How far the outputs reach at one step: what a restart keeps of them.
   type :: output_marks_t
      integer(int64) :: body(n_text) = 0   !! bytes after the header of each text file
      character(len=tail_len) :: tail(n_text) = ''   !! the last bytes of each body ...
      integer :: tail_n(n_text) = 0           !! ... so many of them (a restart checks them)
      integer :: rows_his = 0            !! rows of PREFIX.h5 /history
      integer :: rows_evt = 0            !! rows of /events
      integer :: rows_imp = 0            !! rows of /impacts
      integer :: rows_xt = 0             !! times of /fields/xt
      integer :: n_prof = 0              !! groups under /fields/profiles
      integer :: n_frg = 0               !! groups under /fragments
      integer :: rows_gau = 0            !! times of /gauges (with &gauges)
   end type output_marks_t

contains

   !> Open PREFIX.his, .prf, .evt, .frg, .imp (.gau, .h5) and write their headers. temporaries:
   !> write them as PREFIX.ext.part, which publish_outputs renames (a run that fails before
   !> leaves the previous outputs as they were; doc/outputs.md).
   subroutine open_outputs(prefix, rec, mesh, report, out, err, xt_rows, temporaries)
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      character(len=*), intent(in) :: report(:)     !! mesh fit report lines
      type(outputs_t), intent(out) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      integer, intent(in), optional :: xt_rows   !! x-t times buffered in memory (default 64)
      logical, intent(in), optional :: temporaries   !! as PREFIX.ext.part (default: no)
      type(column_set_t) :: his, evt
      out%prefix = prefix
      out%part = ''
      ! the tables' columns as their owners register them (spb_history, spb_events)
      call register_history(his, out%his_id)
      out%his_table = his%col
      call register_event_columns(evt, out%evt_id)
      out%evt_table = evt%col
      if (len(column_fault(his)) > 0) then
         call make_error(err, 'history: ' // column_fault(his), code=exit_runtime)
         return
      end if
      if (present(temporaries)) then
         if (temporaries) out%part = part_suffix
      end if
      out%per_area = per_unit_area(mesh)
      call open_one('.his', out%his)
      if (.not. allocated(err)) call open_one('.prf', out%prf)
      if (.not. allocated(err)) call open_one('.evt', out%evt)
      if (.not. allocated(err)) call open_one('.frg', out%frg)
      if (.not. allocated(err)) call open_one('.imp', out%imp)
      out%n_gauges = size(rec%gauge_x)
      if (.not. allocated(err) .and. out%n_gauges > 0) call open_one('.gau', out%gau)
      if (allocated(err)) then
         call close_outputs(out)
         return
      end if
      call header(out%his, 'history: one row every history_every steps', 1)
      write(out%his, '(a)') '# energies at row time t^{n+1}: e_kin from v^{n+1}, e_strain from' &
         // ' s^n s^{n+1}, e_pot from (u^n+u^{n+1})/2 (the scheme''s invariant, doc/method.md' &
         // ' "Energy ledger")'
      write(out%his, '(a)') '# ledger = e_kin + e_strain + e_pot - w_ext + e_lost is constant; ' &
         // 'w_ext = w_load + w_transmit; e_lost = e_fracture'
      write(out%his, '(a)') '# momentum balance: momentum - momentum(t=0) = i_gravity + i_ends ' &
         // '+ i_support + p_shift (gravity, end stresses, supports/base, collision shifts)'
      write(out%his, '(a)') '# units: ' // bar_units(history_units, mesh)
      write(out%his, '(a)') column_line(1)
      call header(out%prf, 'stress profiles: one block per profile time', 2)
      write(out%prf, '(a)') '# rows per half node, top to bottom: node 0 lower half only, ' &
         // 'node n upper half only, others upper then lower half at the same x'
      write(out%prf, '(a)') '# stress is that of the cell the half belongs to; v = du/dt over ' &
         // 'the step ending at t'
      write(out%prf, '(a)') '# t: the block''s time, also on its "# t = " line'
      write(out%prf, '(a)') '# units: x [m] (reference position), u [m], v [m/s], stress [Pa] ' &
         // '(compression > 0), t [s]'
      write(out%prf, '(a)') column_line(2)
      call header(out%evt, 'events: one row per fracture, collision, separation', 3)
      write(out%evt, '(a)') '# t is the grid time the event takes effect; the true time lies in ' &
         // '[t - dt_bound, t] (4.1), the true place within dx_bound of x (4.2)'
      write(out%evt, '(a)') '# frag_above, frag_below: fragment ids on either side after the event ' &
         // '(collision: the merged one and the lower parent)'
      write(out%evt, '(a)') '# opening: fracture: (dA+dB)/2 of the new faces; collision: the ' &
         // 'correction (5.2) of the rule used; stress_bound: (6.2) bound of the collision ' &
         // 'stress error; shift: rigid shift given to one side'
      write(out%evt, '(a)') '# kind_code: the kind as a number (' // kind_codes() // ')'
      write(out%evt, '(a)') '# units: t, dt_bound [s]; step, node, frag_*, kind_code [-]; x, ' &
         // 'dx_bound, opening, shift [m] (x reference); stress, stress_bound [Pa] ' &
         // '(compression > 0)'
      write(out%evt, '(a)') column_line(3)
      call header(out%frg, 'fragments: one block per profile time', 4)
      write(out%frg, '(a)') '# x_top, x_bottom: current positions x + u of the faces; e_vib: ' &
         // 'kinetic energy about the mean motion + strain energy; birth_t: time of the ' &
         // 'fracture that made it'
      write(out%frg, '(a)') '# t: the block''s time, also on its "# t = " line'
      write(out%frg, '(a)') '# units: ' // bar_units('birth_t, t [s]; x_* [m]; mass [kg/m^2]; ' &
         // 'velocity [m/s]; e_vib [J/m^2]; ids and nodes [-]', mesh)
      write(out%frg, '(a)') column_line(4)
      call header(out%imp, 'impacts: one row per contact episode (fragments, base, ' // &
                  'impactor), in the order they end', 5)
      write(out%imp, '(a)') '# t_start, t_end: the events that begin and end it (PREFIX.evt); ' &
         // 'peak_force, impulse: of the contact force (compression > 0) over its steps'
      write(out%imp, '(a)') '# v_*: centre-of-mass velocities of the two sides along +x ' // &
         '(down); the base is at rest; an episode open at t_end has NaN for t_end, duration, ' &
         // 'v_*_after'
      write(out%imp, '(a)') '# units: t_start, t_end, duration [s]; kind [-]; x [m] ' // &
         '(reference); peak_force [' // diag_unit('N', mesh) // ']; impulse [' // &
         diag_unit('N s', mesh) // ']; v_* [m/s]'
      write(out%imp, '(a)') column_line(5)
      if (out%gau /= no_unit) then
         call header(out%gau, 'gauges: one row every &gauges every steps', 6)
         call gauge_header(out%gau, rec, mesh)
      end if
      call text_sizes(out, out%head)
      out%expect = out%head
      if (rec%hdf5) call open_h5(prefix, rec, mesh, report, out, err, xt_rows)
   contains
      !> Open PREFIX.ext for writing (unit u).
      subroutine open_one(ext, u)
         character(len=*), intent(in) :: ext   !! file extension, e.g. '.his'
         integer, intent(out) :: u         !! open formatted unit
         integer :: ios
         character(len=256) :: msg
         open(newunit=u, file=prefix // ext // out%part, status='replace', action='write', &
              iostat=ios, iomsg=msg)
         if (ios /= 0) then
            u = no_unit
            call make_error(err, '--output: cannot write ''' // prefix // ext // out%part // &
                            ''': ' // trim(msg))
         end if
      end subroutine open_one
      !> The header lines every text file starts with: with &run header = 'names' a first
      !> line naming the columns without '#' (numpy's genfromtxt(names=True), pandas'
      !> read_csv(comment='#')), then the '#' lines; the last '#' line names them again.
      subroutine header(u, what, k)
         integer, intent(in) :: u          !! open formatted unit
         character(len=*), intent(in) :: what   !! what the file holds (its first line)
         integer, intent(in) :: k          !! text file (text_extensions)
         if (rec%names_first) write(u, '(a)') text_columns(k, size(rec%gauge_x))
         call header_lines(u, rec, mesh, report, what)
      end subroutine header
   end subroutine open_outputs

   !> The '#' lines every text output starts with after its column-name first line: the
   !> program and what the file holds, the title, the echoed deck, the mesh as built.
   subroutine header_lines(u, rec, mesh, report, what)
      integer, intent(in) :: u             !! open formatted unit
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      character(len=*), intent(in) :: report(:)     !! mesh fit report lines
      character(len=*), intent(in) :: what   !! what the file holds (its first '#' line)
      write(u, '(a)') '# ' // program_line() // ' -- ' // what
      if (len(foreign(rec)) > 0) write(u, '(a)') '# ' // foreign(rec)
      write(u, '(a)') '# title: ' // rec%title
      call write_echo(u, rec, '# ')
      call write_mesh_summary(u, mesh, report, '# ')
   end subroutine header_lines

   !> The program as every header's first line names it: its identity and where its sources
   !> came from, 'spallbar 0.3.0 (source 1a2b3c4d5e6f) built from git b82964e1a2b3'.
   function program_line() result(text)
      character(len=:), allocatable :: text   !! the line, without '# '
      text = program_identity() // ' built from ' // build_revision()
   end function program_line

   !> The header line of a run restarted with --restart-any-version from another program's
   !> checkpoint ('' for any other run).
   function foreign(rec) result(text)
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      character(len=:), allocatable :: text   !! the line, without '# '
      text = ''
      if (allocated(rec%restarted_from)) then
         if (len(rec%restarted_from) > 0) text = 'restarted (--restart-any-version) from a ' // &
            'checkpoint of ' // rec%restarted_from // ': not one uninterrupted run of one program'
      end if
   end function foreign

   !> The header lines of PREFIX.gau after the common ones: where each gauge is, what it
   !> reads, units, the column line.
   subroutine gauge_header(u, rec, mesh)
      integer, intent(in) :: u             !! open formatted unit
      type(deck_record_t), intent(in) :: rec   !! the deck's record (its gauges)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(gauge_t) :: g(size(rec%gauge_x))
      character(len=:), allocatable :: where
      integer :: k
      call locate_gauges(mesh, rec%gauge_x, g, rec%gauge_below)
      do k = 1, size(g)
         where = '# gauge ' // itoa(k) // ' at x = ' // rtoa(g(k)%x) // ' m '
         if (g(k)%node == 0) then
            write(u, '(a)') where // 'is on node 0, the top end: the support''s section ' // &
               'stress (a free face: the load on it, its mean over the step)'
         else if (g(k)%node == mesh%n) then
            write(u, '(a)') where // 'is on node ' // itoa(mesh%n) // ', the bottom end: the ' &
               // 'support''s section stress (a free face: the load on it, its mean over the step)'
         else if (g(k)%node > 0) then
            write(u, '(a)') where // 'is on node ' // itoa(g(k)%node) // ': its section ' // &
               'stress; where the node splits, the face ' // trim(merge('below', 'above', &
               g(k)%below)) // ' it (side = ''' // trim(merge('below', 'above', g(k)%below)) // &
               '''): its velocity and u, the stress on it (0 free, a cohesive crack''s traction)'
         else
            write(u, '(a)') where // 'is inside cell ' // itoa(g(k)%cell) // ': its stress; ' // &
               'velocity and u interpolated linearly between nodes ' // itoa(g(k)%cell - 1) // &
               ' and ' // itoa(g(k)%cell) // ' (their halves in this cell)'
         end if
      end do
      write(u, '(a)') '# stress_k: at a node the section stress S (3.1)-(3.2) that holds over ' // &
         'the step ending at t, on a split node''s face what acts on it; inside a cell the ' // &
         'cell''s stress at t'
      write(u, '(a)') '# velocity_k: du/dt over the step ending at t; u_k: displacement at t'
      write(u, '(a)') '# units: t [s]; stress_k [Pa] (compression > 0); velocity_k [m/s] ' // &
         'along +x (down); u_k [m]'
      write(u, '(a)') column_line(6, size(g))
   end subroutine gauge_header

   !> The column names of PREFIX.gau: t, then stress_k velocity_k u_k for k = 1..n.
   pure function gauge_columns(n) result(line)
      integer, intent(in) :: n             !! gauges
      character(len=:), allocatable :: line
      integer :: k
      line = 't'
      do k = 1, n
         line = line // ' stress_' // itoa(k) // ' velocity_' // itoa(k) // ' u_' // itoa(k)
      end do
   end function gauge_columns

   !> One row of PREFIX.gau (and /gauges): the gauges' readings at time t.
   subroutine write_gauge_row(out, t, stress, velocity, u)
      type(outputs_t), intent(inout) :: out   !! the outputs
      real(wp), intent(in) :: t            !! time of the row [s]
      real(wp), intent(in) :: stress(:)    !! stress of each gauge [Pa]
      real(wp), intent(in) :: velocity(:)  !! velocity of each gauge [m/s]
      real(wp), intent(in) :: u(:)         !! displacement of each gauge [m]
      character(len=21 * (3 * size(stress) + 1)) :: line
      integer :: k, at
      if (out%gau == no_unit) return
      line = ' '
      line(2:21) = es20_12(t)
      at = 21
      do k = 1, size(stress)
         line(at + 2:at + 21) = es20_12(stress(k))
         line(at + 23:at + 42) = es20_12(velocity(k))
         line(at + 44:at + 63) = es20_12(u(k))
         at = at + 63
      end do
      call put_row(out, 6, line)
      if (out%hdf5) call h5_append_xt(out%h5, t, stress, velocity, u, xt_gauges)
   end subroutine write_gauge_row

   !> How many text files a run writes (PREFIX.gau with gauges): the first so many of
   !> text_extensions.
   pure integer function text_count(rec)
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      text_count = n_text - 1
      if (size(rec%gauge_x) > 0) text_count = n_text
   end function text_count

   !> The mesh as built: dt, cells, steps, and each segment's cells and lengths.
   subroutine write_mesh_summary(u, mesh, report, prefix)
      integer, intent(in) :: u             !! open formatted unit
      type(mesh_t), intent(in) :: mesh     !! the mesh
      character(len=*), intent(in) :: report(:)   !! the mesh fit report (stretched segments)
      character(len=*), intent(in) :: prefix   !! what each line starts with, e.g. '# '
      integer :: j
      write(u, '(a)') prefix // 'mesh: dt = ' // rtoa(mesh%dt) // ' s, ' // itoa(mesh%n) // &
         ' cells, ' // itoa(mesh%nsteps) // ' steps to t = ' // &
         rtoa(real(mesh%nsteps, wp) * mesh%dt) // ' s'
      do j = 1, mesh%nseg
         write(u, '(a)') prefix // 'segment ' // itoa(j) // ': cells ' // &
            itoa(mesh%first(j)) // '..' // itoa(mesh%last(j)) // ', dx = a dt = ' // &
            rtoa(mesh%dx(mesh%first(j))) // ' m, a = ' // rtoa(mesh%wave_speed(j)) // &
            ' m/s, Z = ' // rtoa(mesh%impedance(j)) // ' kg/(m^2 s), length ' // &
            rtoa(mesh%length(j)) // ' m (asked ' // rtoa(mesh%length_req(j)) // ')' // &
            area_note(j)
      end do
      do j = 1, size(report)
         write(u, '(a)') prefix // 'fit = ''stretch'': ' // trim(report(j))
      end do
   contains
      !> ', area A = ... m^2' where the bar is not per unit area.
      function area_note(j) result(note)
         integer, intent(in) :: j   !! the segment
         character(len=:), allocatable :: note
         note = ''
         if (.not. per_unit_area(mesh)) note = ', area A = ' // rtoa(mesh%seg_area(j)) // ' m^2'
      end function area_note
   end subroutine write_mesh_summary

   !> Whether every cross-section is 1 m^2: the outputs are per unit area, as before areas.
   pure logical function per_unit_area(mesh)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      per_unit_area = maxval(abs(mesh%seg_area - 1.0_wp)) <= 0.0_wp   ! every area exactly 1
   end function per_unit_area

   !> Units text for this bar: as written (per unit area) when every area is 1, else the
   !> whole bar's: J/m^2 -> J, kg/(m s) -> kg m/s, kg/m^2 -> kg, kg/(m^2 s) -> kg/s, Pa/m ->
   !> N/m (stresses stay Pa).
   pure function bar_units(text, mesh) result(out)
      character(len=*), intent(in) :: text   !! units as per unit area
      type(mesh_t), intent(in) :: mesh       !! the mesh
      character(len=:), allocatable :: out
      out = unit_text(text, per_unit_area(mesh))
   end function bar_units

   !> bar_units for a bar that is (per_area) or is not per unit area.
   pure function unit_text(text, per_area) result(out)
      character(len=*), intent(in) :: text   !! units as per unit area
      logical, intent(in) :: per_area        !! every area is 1
      character(len=:), allocatable :: out
      character(len=10), parameter :: per(6) = [character(len=10) :: 'J/m^2', 'kg/(m s)', &
         'kg/(m^2 s)', 'kg/m^2', 'Pa/m', 'N/m^2']
      character(len=6), parameter :: whole(6) = [character(len=6) :: 'J', 'kg m/s', 'kg/s', &
         'kg', 'N/m', 'N']
      integer :: k, i
      out = text
      if (per_area) return
      do k = 1, size(per)
         do
            i = index(out, trim(per(k)))
            if (i == 0) exit
            out = out(:i - 1) // trim(whole(k)) // out(i + len_trim(per(k)):)
         end do
      end do
   end function unit_text

   !> Before any output is created or truncated: check that every file of the run (its
   !> outputs, the temporaries they are written as, PREFIX.xmf) can be written without
   !> touching it, that none is the deck or its load table, that the checkpoint ('' : none)
   !> is none of them and can be written; then hold PREFIX.lock and the checkpoint's lock
   !> (CHECKPOINT.lock) and refuse when another run holds the lock of a file this run would
   !> write (its checkpoint among this run's outputs, or this run's checkpoint among its
   !> outputs). A refusal leaves no file; the locks are taken before the last test, so of two
   !> runs started together at least one sees the other.
   subroutine claim_outputs(prefix, rec, checkpoint, err)
      character(len=*), intent(in) :: prefix       !! output path prefix
      type(deck_record_t), intent(in) :: rec       !! the deck's record (its path, hdf5)
      character(len=*), intent(in) :: checkpoint   !! the checkpoint file ('': none)
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: refused)
      character(len=len(prefix) + 10) :: files(2 * n_text + 5)
      integer :: k, n, nt
      logical :: made(2), lockless(2)
      if (sys_is_directory(prefix)) then
         call make_error(err, '--output: ''' // prefix // ''' is a folder; give a prefix ' // &
                         'such as ''' // prefix // '/run''')
         return
      end if
      ! the text files, PREFIX.h5 and PREFIX.xmf when written, each as itself and as the
      ! temporary it is written as first; then the lock
      nt = text_count(rec)
      n = 0
      do k = 1, nt
         files(n + 1) = prefix // text_extensions(k)
         files(n + 2) = prefix // trim(text_extensions(k)) // part_suffix
         n = n + 2
      end do
      if (rec%hdf5) then
         files(n + 1) = prefix // '.h5'
         files(n + 2) = prefix // '.h5' // part_suffix
         files(n + 3) = xdmf_path(prefix)
         files(n + 4) = xdmf_path(prefix) // part_suffix
         n = n + 4
      end if
      files(n + 1) = prefix // '.lock'
      ! no output (nor the lock, which is truncated) may be one of the run's inputs: by name,
      ! by a symbolic link or by a hard link (issue 32)
      do k = 1, n + 1
         call not_an_input('--output: ''' // trim(files(k)) // '''', trim(files(k)), rec, err)
         if (allocated(err)) return
      end do
      call claim_checkpoint(checkpoint, rec, files(1:n + 1), err)
      if (allocated(err)) return
      ! the locks before any file is probed: a run refused below never touches a file that
      ! a running one writes (its probe of a temporary would delete that run's)
      made = .false.
      lockless = .false.
      call hold_lock(prefix // '.lock', '--output: ''' // prefix // '''', made(1), lockless(1), &
                     err)
      if (len(checkpoint) > 0 .and. .not. allocated(err)) call hold_lock(checkpoint // &
         '.lock', '&run: checkpoint = ''' // checkpoint // '''', made(2), lockless(2), err)
      if (.not. allocated(err)) call others_writing(prefix, files(1:n + 1), checkpoint, err)
      do k = 1, n
         if (allocated(err)) exit
         call check_writable('--output', trim(files(k)), err)
      end do
      if (len(checkpoint) > 0 .and. .not. allocated(err)) call check_writable('&run: ' // &
         'checkpoint = ''' // checkpoint // '''', checkpoint // '.part', err)
      ! a lock file that cannot be made where every output can: said after the probes, which
      ! name the cause (a missing folder) when there is one
      if (lockless(1) .and. .not. allocated(err)) call make_error(err, '--output: cannot ' // &
         'make the lock file ''' // prefix // '.lock''')
      if (lockless(2) .and. .not. allocated(err)) call make_error(err, '&run: checkpoint = ''' // &
         checkpoint // ''': cannot make the lock file ''' // checkpoint // '.lock''')
      if (allocated(err)) then
         ! leave no file: the lock files this run made go again
         if (made(1)) call remove_file(prefix // '.lock')
         if (made(2)) call remove_file(checkpoint // '.lock')
      end if
   end subroutine claim_outputs

   !> Refuse (err) when another run holds the lock of a file this one writes: another run's
   !> checkpoint (CHECKPOINT.lock) that is one of files (the lock among them), or this run's
   !> checkpoint that is an output, temporary or the lock of another run's prefix (PREFIX.lock
   !> of the prefix it belongs to).
   subroutine others_writing(prefix, files, checkpoint, err)
      character(len=*), intent(in) :: prefix       !! output path prefix
      character(len=*), intent(in) :: files(:)     !! the run's outputs and temporaries
      character(len=*), intent(in) :: checkpoint   !! the checkpoint file ('': none)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: refused)
      character(len=10) :: tails(2 * n_text + 5)
      integer :: k, m
      ! every file a prefix may have: the text files, PREFIX.h5 and .xmf, each as itself and
      ! as its temporary, and the lock (from the lists that name them, never a copy)
      tails(1:n_text + 2) = [character(len=10) :: text_extensions, '.h5', '.xmf']
      do k = 1, n_text + 2
         tails(n_text + 2 + k) = trim(tails(k)) // part_suffix
      end do
      tails(2 * n_text + 5) = '.lock'
      do k = 1, size(files)
         if (sys_lock_held(trim(files(k)) // '.lock')) then
            call make_error(err, '--output: ''' // trim(files(k)) // ''' is the checkpoint ' // &
               'of another spallbar run (' // trim(files(k)) // '.lock is locked); wait for ' // &
               'it or give another --output than ''' // prefix // '''')
            return
         end if
      end do
      if (len(checkpoint) == 0) return
      do k = 1, size(tails)
         m = len(checkpoint) - len_trim(tails(k))
         if (m < 1) cycle
         if (checkpoint(m + 1:) /= trim(tails(k))) cycle
         ! this run's own prefix holds its lock here (its outputs were checked before)
         if (sys_real_path(checkpoint(:m)) == sys_real_path(prefix)) cycle
         if (sys_lock_held(checkpoint(:m) // '.lock')) then
            call make_error(err, '&run: checkpoint = ''' // checkpoint // ''' is an output ' // &
               'of another spallbar run on the prefix ''' // checkpoint(:m) // ''' (' // &
               checkpoint(:m) // '.lock is locked); give the checkpoint a file of its own')
            return
         end if
      end do
   end subroutine others_writing

   !> The checkpoint's part of claim_outputs: not a file of the run (files: its outputs and
   !> lock), the deck, its load table, a folder or a FIFO/device (its .part is probed by
   !> claim_outputs once the locks are held).
   subroutine claim_checkpoint(checkpoint, rec, files, err)
      character(len=*), intent(in) :: checkpoint   !! the checkpoint file ('': none)
      type(deck_record_t), intent(in) :: rec       !! the deck's record (its path, hdf5)
      character(len=*), intent(in) :: files(:)     !! the run's text files, .h5, .lock
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: refused)
      character(len=:), allocatable :: ck
      integer :: k
      if (len(checkpoint) == 0) return
      ck = sys_real_path(checkpoint)
      do k = 1, size(files)
         if (ck == sys_real_path(trim(files(k)))) then
            call make_error(err, '&run: checkpoint = ''' // checkpoint // ''' is an ' // &
               'output of this run (''' // trim(files(k)) // '''); give the checkpoint a ' // &
               'file of its own')
            return
         end if
      end do
      call not_an_input('&run: checkpoint = ''' // checkpoint // '''', checkpoint, rec, err)
      if (allocated(err)) return
      ! it is written as checkpoint.part and renamed: that may not be an input either
      call not_an_input('&run: checkpoint = ''' // checkpoint // ''' (written as ''' // &
                        checkpoint // '.part'')', checkpoint // '.part', rec, err)
      if (allocated(err)) return
      ! a lock file's name: a later run on that prefix would truncate it as its lock
      if (len(checkpoint) >= 5) then
         if (checkpoint(len(checkpoint) - 4:) == '.lock') then
            call make_error(err, '&run: checkpoint = ''' // checkpoint // ''' is named like ' // &
               'a lock file (spallbar truncates PREFIX.lock and CHECKPOINT.lock to lock them); ' // &
               'give the checkpoint another name')
            return
         end if
      end if
      ! nor its lock file
      call not_an_input('&run: checkpoint = ''' // checkpoint // ''' (its lock ''' // &
                        checkpoint // '.lock'')', checkpoint // '.lock', rec, err)
      if (allocated(err)) return
      if (sys_is_directory(checkpoint)) then
         call make_error(err, '&run: checkpoint = ''' // checkpoint // ''' is a folder; ' // &
                         'give a file such as ''' // checkpoint // '/run.h5''')
      else if (sys_file_kind(checkpoint) == file_other) then
         call make_error(err, '&run: checkpoint = ''' // checkpoint // ''' is not a ' // &
                         'regular file (a FIFO, a device or a socket); give a file of its own')
      end if
   end subroutine claim_checkpoint

   !> Refuse (err) a file the run writes that is one of its inputs, the deck or its load
   !> table: the same path, or the same file through a symbolic or a hard link.
   subroutine not_an_input(what, path, rec, err)
      character(len=*), intent(in) :: what         !! the file as the message names it
      character(len=*), intent(in) :: path         !! the file the run would write
      type(deck_record_t), intent(in) :: rec       !! the deck's record (its path, table)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: refused)
      character(len=:), allocatable :: real
      real = sys_real_path(path)
      if (real == sys_real_path(rec%path) .or. sys_same_file(path, rec%path)) then
         call make_error(err, what // ' is the deck itself; give the run''s files other names')
      else if (len(rec%table) > 0) then
         if (real == sys_real_path(rec%table) .or. sys_same_file(path, rec%table)) then
            call make_error(err, what // ' is the load table of this deck (' // rec%table // &
                            '); give the run''s files other names')
         end if
      end if
   end subroutine not_an_input

   !> Hold the lock file path for the life of the process: a second run that would write
   !> the same files is refused (what: how the message names them). made: the file did not
   !> exist before; lockless: it cannot be made (the caller says why).
   subroutine hold_lock(path, what, made, lockless, err)
      character(len=*), intent(in) :: path         !! the lock file
      character(len=*), intent(in) :: what         !! --output PREFIX or the checkpoint
      logical, intent(out) :: made                 !! the lock file is new
      logical, intent(out) :: lockless             !! the lock file cannot be made
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: refused)
      integer :: state
      inquire(file=path, exist=made)
      made = .not. made
      call sys_lock(path, state)
      lockless = state == 1
      if (state == 1) then
         made = .false.
      else if (state /= 0) then
         call make_error(err, what // ' is in use by another spallbar run (' // path // &
            ' is locked); wait for it or give other names')
      end if
   end subroutine hold_lock

   !> Remove a file (missing: nothing to do).
   subroutine remove_file(path)
      character(len=*), intent(in) :: path   !! the file
      integer :: u, ios
      open(newunit=u, file=path, status='old', iostat=ios)
      if (ios == 0) close(u, status='delete')
   end subroutine remove_file

   !> A sweep's claim_outputs, before any case runs: PREFIX.sweep, PREFIX_sweep.h5 (and
   !> with an ensemble PREFIX.ens) and the .part files they are written as can be written (none is a folder, none an input of the
   !> sweep), PREFIX.lock held.
   subroutine claim_sweep_outputs(prefix, rec, err, ensemble)
      character(len=*), intent(in) :: prefix       !! output path prefix
      type(deck_record_t), intent(in) :: rec       !! the deck's record (its path, table)
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: refused)
      logical, intent(in), optional :: ensemble    !! PREFIX.ens is written too
      character(len=*), parameter :: tails(6) = [character(len=14) :: '.sweep', &
         '.sweep.part', '_sweep.h5', '_sweep.h5.part', '.ens', '.ens.part']
      integer :: k, n
      n = 4   ! the files written: without an ensemble the first four
      if (present(ensemble)) then
         if (ensemble) n = 6
      end if
      if (sys_is_directory(prefix)) then
         call make_error(err, '--output: ''' // prefix // ''' is a folder; give a prefix ' // &
                         'such as ''' // prefix // '/run''')
         return
      end if
      ! none of them (nor the lock) may be the deck or its load table (issue 32)
      do k = 1, n
         call not_an_input('--output: ''' // prefix // trim(tails(k)) // '''', &
                           prefix // trim(tails(k)), rec, err)
         if (allocated(err)) return
      end do
      call not_an_input('--output: ''' // prefix // '.lock''', prefix // '.lock', rec, err)
      if (allocated(err)) return
      ! the lock first, then the probes (see claim_outputs)
      block
         logical :: made, lockless
         call hold_lock(prefix // '.lock', '--output: ''' // prefix // '''', made, lockless, err)
         do k = 1, n
            if (allocated(err)) exit
            call check_writable('--output', prefix // trim(tails(k)), err)
         end do
         if (lockless .and. .not. allocated(err)) call make_error(err, '--output: cannot ' // &
            'make the lock file ''' // prefix // '.lock''')
         if (allocated(err) .and. made) call remove_file(prefix // '.lock')
      end block
   end subroutine claim_sweep_outputs

   !> Error unless path can be written: an existing file is opened for appending and closed
   !> untouched, a missing one is created and removed again.
   subroutine check_writable(what, path, err)
      character(len=*), intent(in) :: what   !! who names it ('--output', '&run: checkpoint')
      character(len=*), intent(in) :: path   !! the file
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      logical :: exists
      integer :: u, ios
      character(len=256) :: msg
      if (sys_is_directory(path)) then
         call make_error(err, what // ': cannot write ''' // path // ''': it is a folder')
         return
      end if
      inquire(file=path, exist=exists)
      if (exists) then
         open(newunit=u, file=path, status='old', action='write', position='append', &
              iostat=ios, iomsg=msg)
         if (ios == 0) close(u)
      else
         open(newunit=u, file=path, status='new', action='write', iostat=ios, iomsg=msg)
         if (ios == 0) close(u, status='delete', iostat=ios, iomsg=msg)
      end if
      if (ios /= 0) call make_error(err, what // ': cannot write ''' // path // ''': ' // &
                                    trim(msg))
   end subroutine check_writable

   !> Whether every byte written to the text files reached them: gfortran reports no error
   !> when a disk is full, so the size the system has is compared with what was written
   !> (after a flush). A shortfall is err (exit 3), naming the file and the bytes.
   subroutine check_written(out, err)
      type(outputs_t), intent(inout) :: out   !! the outputs (collected rows written first)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer(int64) :: wrote, have
      integer :: k, u
      call drain_rows(out)
      if (allocated(err)) return
      do k = 1, size(text_extensions)
         u = text_unit(out, k)
         if (u == no_unit) cycle
         flush(u)
         inquire(unit=u, size=wrote)
         wrote = max(wrote, out%expect(k))
         have = sys_file_size(out_path(out, k))
         if (have < wrote .or. out%refused(k)) then
            call make_error(err, 'run: cannot write ''' // out_path(out, k) // &
               ''': ' // itoa(max(have, 0_int64)) // ' of ' // itoa(wrote) // ' bytes reached ' // &
               'the disk (' // sys_write_trouble(out_path(out, k)) // '); the outputs end there', &
               code=exit_runtime)
            return
         end if
      end do
      if (out%hdf5) then
         if (allocated(out%h5%error)) call make_error(err, out%h5%error, code=exit_runtime)
      end if
   end subroutine check_written

   !> Close every file; a file that did not receive all it was written, or a failure of the
   !> HDF5 file (its first error), comes back in err.
   subroutine close_outputs(out, err)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(out), optional :: err   !! allocated: it failed
      type(spb_error_t), allocatable :: short, xdmf_err
      call check_written(out, short)
      if (out%his /= no_unit) close(out%his)
      if (out%prf /= no_unit) close(out%prf)
      if (out%evt /= no_unit) close(out%evt)
      if (out%frg /= no_unit) close(out%frg)
      if (out%imp /= no_unit) close(out%imp)
      if (out%gau /= no_unit) close(out%gau)
      out%frg = no_unit
      out%imp = no_unit
      out%gau = no_unit
      out%his = no_unit
      out%prf = no_unit
      out%evt = no_unit
      if (out%hdf5) then
         call h5_close(out%h5)
         out%hdf5 = .false.
         if (allocated(out%h5%error)) then
            if (present(err)) call make_error(err, out%h5%error, code=exit_runtime)
         else if (.not. is_temporary(out)) then
            ! PREFIX.xmf describes the file as it is now, complete (temporaries: once they
            ! are published)
            call write_xdmf(out%prefix, xdmf_err)
            if (allocated(xdmf_err) .and. present(err)) call move_alloc(xdmf_err, err)
         end if
      end if
      if (allocated(short) .and. present(err)) call move_alloc(short, err)
   end subroutine close_outputs

   !> Push what is written so far to disk (text and HDF5): a killed run reads up to here.
   subroutine flush_outputs(out)
      type(outputs_t), intent(inout) :: out   !! the outputs
      call drain_rows(out)
      if (out%his /= no_unit) flush(out%his)
      if (out%evt /= no_unit) flush(out%evt)
      if (out%imp /= no_unit) flush(out%imp)
      if (out%gau /= no_unit) flush(out%gau)
      if (out%hdf5) call h5_flush(out%h5)
   end subroutine flush_outputs

   !> Bytes in each text file now (written through to the file first).
   subroutine text_sizes(out, bytes)
      type(outputs_t), intent(inout) :: out   !! the outputs (collected rows written first)
      integer(int64), intent(out) :: bytes(n_text)   !! each text file (text_extensions; 0:
                                                      !! not open)
      integer :: k, u
      call drain_rows(out)
      bytes = 0
      do k = 1, n_text
         u = text_unit(out, k)
         if (u == no_unit) cycle
         flush(u)
         inquire(unit=u, size=bytes(k))
      end do
   end subroutine text_sizes

   !> Whether the outputs are still the temporaries PREFIX.ext.part.
   pure logical function is_temporary(out)
      type(outputs_t), intent(in) :: out   !! the outputs
      is_temporary = .false.
      if (allocated(out%part)) is_temporary = len(out%part) > 0
   end function is_temporary

   !> The file text file k (text_extensions) is written to now: PREFIX.ext, or PREFIX.ext.part
   !> while the outputs are temporaries.
   pure function out_path(out, k) result(path)
      type(outputs_t), intent(in) :: out   !! the outputs
      integer, intent(in) :: k             !! text file (text_extensions)
      character(len=:), allocatable :: path
      path = out%prefix // trim(text_extensions(k))
      if (is_temporary(out)) path = path // out%part
   end function out_path

   !> Give the temporaries their names: rename each PREFIX.ext.part over PREFIX.ext (each
   !> rename atomic; a reader holding the previous file keeps reading it), PREFIX.h5 too; the
   !> open files go on being written under the new names. Once the HDF5 file is closed,
   !> PREFIX.xmf is written for it. Nothing to do when they are not temporaries.
   subroutine publish_outputs(out, err)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: failed)
      integer :: k
      logical :: ok
      if (.not. is_temporary(out)) return
      do k = 1, n_text - merge(0, 1, out%n_gauges > 0)
         call sys_rename(out_path(out, k), out%prefix // trim(text_extensions(k)), ok)
         if (.not. ok) then
            call make_error(err, 'run: cannot rename ''' // out_path(out, k) // ''' to ''' // &
               out%prefix // trim(text_extensions(k)) // '''', code=exit_runtime)
            return
         end if
      end do
      if (out%with_h5) then
         call sys_rename(out%prefix // '.h5' // out%part, out%prefix // '.h5', ok)
         if (.not. ok) then
            call make_error(err, 'run: cannot rename ''' // out%prefix // '.h5' // out%part // &
               ''' to ''' // out%prefix // '.h5''', code=exit_runtime)
            return
         end if
      end if
      out%part = ''
      if (out%with_h5 .and. .not. out%hdf5) call write_xdmf(out%prefix, err)
   end subroutine publish_outputs

   !> Where the outputs of a run that stopped before publishing them are, for its message:
   !> '; this run's outputs are PREFIX.*.part, the previous PREFIX.* are as they
   !> were', or '' when they are published.
   function where_outputs(out) result(text)
      type(outputs_t), intent(in) :: out   !! the outputs
      character(len=:), allocatable :: text
      text = ''
      if (is_temporary(out)) text = '; this run''s outputs are ' // out%prefix // &
         '.*' // out%part // ', the previous ' // out%prefix // '.* are as they were'
   end function where_outputs

   !> Where the outputs stand now (everything written through to the files): the body
   !> length of each text file and its last bytes, the rows of each PREFIX.h5 table.
   subroutine mark_outputs(out, marks)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(output_marks_t), intent(out) :: marks   !! how far the outputs reach
      integer(int64) :: bytes(n_text)
      integer :: k, u, r, ios
      call flush_outputs(out)
      call text_sizes(out, bytes)
      marks%body = bytes - out%head
      do k = 1, size(text_extensions)
         ! the tail is read back through a second connection: close, read, reopen
         u = text_unit(out, k)
         if (u == no_unit) cycle
         close(u)
         marks%tail_n(k) = int(min(int(tail_len, int64), marks%body(k)))
         open(newunit=r, file=out_path(out, k), access='stream', &
              form='unformatted', status='old', action='read', iostat=ios)
         if (ios == 0 .and. marks%tail_n(k) > 0) then
            read(r, pos=bytes(k) - marks%tail_n(k) + 1, iostat=ios) marks%tail(k)(1:marks%tail_n(k))
         end if
         if (ios == 0) close(r)
         if (ios /= 0) marks%tail_n(k) = -1     ! a restart from this mark will refuse
         open(newunit=u, file=out_path(out, k), status='old', action='write', &
              position='append', iostat=ios)
         if (ios /= 0) u = no_unit
         call set_text_unit(out, k, u)
      end do
      if (.not. out%hdf5) return
      marks%rows_his = h5_table_rows(out%h5, out%h_his)
      marks%rows_evt = h5_table_rows(out%h5, out%h_evt)
      marks%rows_imp = h5_table_rows(out%h5, out%h_imp)
      marks%rows_xt = h5_xt_rows(out%h5)
      marks%n_prof = out%n_prof
      marks%n_frg = out%n_frg
      marks%rows_gau = h5_xt_rows(out%h5, xt_gauges)
   end subroutine mark_outputs

   !> The unit of text file k (text_extensions order).
   pure integer function text_unit(out, k) result(u)
      type(outputs_t), intent(in) :: out   !! the outputs
      integer, intent(in) :: k             !! text file (text_extensions)
      integer :: units(n_text)
      units = [out%his, out%prf, out%evt, out%frg, out%imp, out%gau]
      u = units(k)
   end function text_unit

   !> Set the unit of text file k.
   subroutine set_text_unit(out, k, u)
      type(outputs_t), intent(inout) :: out   !! the outputs
      integer, intent(in) :: k             !! text file (text_extensions)
      integer, intent(in) :: u             !! open formatted unit
      integer(int64) :: bytes
      if (u /= no_unit) then
         ! what the file holds now counts as written (a restart's copied body); what was
         ! written and refused before stays counted (a mark's reopening)
         inquire(unit=u, size=bytes)
         out%expect(k) = max(out%expect(k), bytes)
      end if
      select case (k)
      case (1)
         out%his = u
      case (2)
         out%prf = u
      case (3)
         out%evt = u
      case (4)
         out%frg = u
      case (5)
         out%imp = u
      case default
         out%gau = u
      end select
   end subroutine set_text_unit

   !> The column line that ends the header of text file k.
   pure function column_line(k, n_gauges) result(line)
      integer, intent(in) :: k             !! text file (text_extensions)
      integer, intent(in), optional :: n_gauges   !! PREFIX.gau: its gauges
      character(len=:), allocatable :: line
      if (present(n_gauges)) then
         line = '# ' // text_columns(k, n_gauges)
      else
         line = '# ' // text_columns(k, 0)
      end if
   end function column_line

   !> The names of the columns of text file k, blank-separated.
   pure function text_columns(k, n_gauges) result(line)
      integer, intent(in) :: k             !! text file (text_extensions)
      integer, intent(in) :: n_gauges      !! PREFIX.gau: its gauges
      character(len=:), allocatable :: line
      select case (k)
      case (1)
         line = history_columns()
      case (2)
         line = profile_columns
      case (3)
         line = event_columns() // ' kind_code'
      case (4)
         line = fragment_columns
      case (5)
         line = impact_table_columns()
      case default
         line = gauge_columns(n_gauges)
      end select
   end function text_columns

   !> The event kinds' codes for the header of PREFIX.evt: "1 fracture, 2 collision, ...".
   pure function kind_codes() result(line)
      character(len=:), allocatable :: line
      integer :: k
      line = ''
      do k = 1, size(event_kinds)
         if (k > 1) line = line // ', '
         line = line // itoa(k) // ' ' // trim(event_kinds(k)%name)
      end do
   end function kind_codes

   !> Bytes of the header of a text output (up to its column line), -1 if there is none in
   !> its first MiBs, and the file's size.
   subroutine find_header(path, k, head, size_bytes, n_gauges)
      character(len=*), intent(in) :: path   !! file path
      integer, intent(in) :: k             !! text file (text_extensions)
      integer(int64), intent(out) :: head         !! bytes of the header (-1: not found)
      integer(int64), intent(out) :: size_bytes   !! bytes of the file
      integer, intent(in), optional :: n_gauges   !! PREFIX.gau: its gauges
      integer, parameter :: scan_max = 4194304
      character(len=:), allocatable :: buf
      character(len=:), allocatable :: line
      integer :: u, ios, m, at
      head = -1
      inquire(file=path, size=size_bytes)
      m = int(min(int(scan_max, int64), size_bytes))
      if (m <= 0) return
      open(newunit=u, file=path, access='stream', form='unformatted', status='old', &
           action='read', iostat=ios)
      if (ios /= 0) return
      allocate(character(len=m) :: buf)
      read(u, pos=1, iostat=ios) buf
      close(u)
      if (ios /= 0) return
      line = column_line(k, n_gauges) // new_line('a')
      if (len(buf) >= len(line)) then
         if (buf(1:len(line)) == line) then
            head = len(line)
            return
         end if
      end if
      at = index(buf, new_line('a') // line)
      if (at > 0) head = at + len(line)
   end subroutine find_header

   !> Root attributes (program, title, deck path, layout, conventions) and /deck: one group
   !> per namelist group, one string attribute per variable (the echoed value), with
   !> name:units and name:from ('input' or 'default'). PREFIX.h5 and PREFIX_sweep.h5 share it.
   subroutine h5_deck_header(h5, rec)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      integer :: k
      call h5_attr(h5, '/', 'program', program_identity())
      call h5_attr(h5, '/', 'revision', build_revision())
      if (len(foreign(rec)) > 0) call h5_attr(h5, '/', 'restarted_from', rec%restarted_from)
      call h5_attr(h5, '/', 'title', rec%title)
      call h5_attr(h5, '/', 'deck_path', rec%path)
      call h5_attr(h5, '/', 'layout', 'doc/outputs.md; h5py shows a Fortran a(nx, nt) ' // &
                   'as (nt, nx)')
      call h5_attr(h5, '/', 'conventions', 'SI units; x down from the top end; ' // &
                   'stress > 0 in compression')
      call h5_group(h5, '/deck')
      associate (items => rec%items)
      do k = 1, size(items)
         if (k == 1) then
            call h5_group(h5, '/deck/' // items(k)%group)
         else if (items(k)%group /= items(k - 1)%group) then
            call h5_group(h5, '/deck/' // items(k)%group)
         end if
         associate (g => '/deck/' // items(k)%group, nm => items(k)%name)
            call h5_deck_value(h5, g, items(k))
            if (len_trim(items(k)%unit) > 0) call h5_attr(h5, g, nm // ':units', items(k)%unit)
            call h5_attr(h5, g, nm // ':from', trim(merge('input  ', 'default', items(k)%given)))
         end associate
      end do
      end associate
   end subroutine h5_deck_header

   !> One deck value as an attribute of its type (doc/outputs.md, "/deck"): a real as
   !> float64 (not set: no attribute), an integer as int32, a logical as the FALSE/TRUE
   !> enumeration h5py reads as bool, a text as a string; an array variable as a 1-D array
   !> of them.
   subroutine h5_deck_value(h5, group, item)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: group   !! '/deck/GROUP'
      type(echo_item_t), intent(in) :: item   !! the value
      select case (item%type)
      case ('r')
         if (item%list) then
            call h5_attr(h5, group, item%name, item%reals)
         else if (size(item%reals) == 1) then
            call h5_attr(h5, group, item%name, item%reals(1))
         end if
      case ('i')
         call h5_attr(h5, group, item%name, item%ints(1))
      case ('l')
         call h5_attr(h5, group, item%name, item%flags(1))
      case default
         if (item%list) then
            call h5_attr(h5, group, item%name, item%words)
         else
            call h5_attr(h5, group, item%name, unquote(item%value))
         end if
      end select
   end subroutine h5_deck_value

   !> PREFIX.h5: root attributes, /deck, /mesh, the /history and /events tables, /fields
   !> (profiles, and x-t rows when field_every > 0), /fragments.
   subroutine open_h5(prefix, rec, mesh, report, out, err, xt_rows)
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      character(len=*), intent(in) :: report(:)   !! the mesh fit report (stretched segments)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer, intent(in), optional :: xt_rows   !! x-t times buffered in memory (default 64)
      character(len=32), allocatable :: names(:), units(:)
      logical, allocatable :: whole(:)
      integer :: k, n
      call h5_create(out%h5, prefix // '.h5' // out%part)
      out%hdf5 = .true.
      out%with_h5 = .true.
      call h5_deck_header(out%h5, rec)
      ! the mesh
      n = mesh%n
      call h5_group(out%h5, '/mesh')
      call h5_attr(out%h5, '/mesh', 'dt', mesh%dt)
      call h5_attr(out%h5, '/mesh', 'cells', n)
      call h5_attr(out%h5, '/mesh', 'steps', mesh%nsteps)
      call h5_attr(out%h5, '/mesh', 'segments', mesh%nseg)
      do k = 1, size(report)
         call h5_attr(out%h5, '/mesh', 'fit_report_' // itoa(k), trim(report(k)))
      end do
      call h5_write(out%h5, '/mesh/x', mesh%x, 'm')
      call h5_write(out%h5, '/mesh/m_upper', mesh%ma, bar_units('kg/m^2', mesh))
      call h5_write(out%h5, '/mesh/m_lower', mesh%mb, bar_units('kg/m^2', mesh))
      call h5_write(out%h5, '/mesh/dx', mesh%dx, 'm')
      call h5_write(out%h5, '/mesh/dm', mesh%dm, bar_units('kg/m^2', mesh))
      call h5_write(out%h5, '/mesh/impedance', mesh%z, bar_units('kg/(m^2 s)', mesh))
      call h5_write(out%h5, '/mesh/stiffness', mesh%stiff, bar_units('Pa/m', mesh))
      if (.not. per_unit_area(mesh)) call h5_write(out%h5, '/mesh/area', mesh%area, 'm^2')
      call h5_write(out%h5, '/mesh/segment', mesh%seg, '-')
      call h5_write(out%h5, '/mesh/x_half', half_x(mesh), 'm')
      ! tables
      names = out%his_table%name
      units = out%his_table%unit
      do k = 1, size(units)
         units(k) = bar_units(trim(units(k)), mesh)
      end do
      whole = out%his_table%whole
      call h5_table(out%h5, '/history', names, units, whole, out%h_his)
      call h5_attr(out%h5, '/history', 'columns', history_columns())
      names = out%evt_table%name
      units = out%evt_table%unit
      whole = out%evt_table%whole
      call h5_table(out%h5, '/events', names, units, whole, out%h_evt)
      call h5_attr(out%h5, '/events', 'kind_codes', kind_codes())
      ! /impacts: a row as each contact episode ends (write_impacts)
      names = impact_columns()
      units = impact_units()
      units(6) = diag_unit('N', mesh)
      units(7) = diag_unit('N s', mesh)
      whole = spread(.false., 1, size(names))
      whole(4) = .true.
      call h5_table(out%h5, '/impacts', names, units, whole, out%h_imp)
      call h5_group(out%h5, '/fields')
      call h5_group(out%h5, '/fields/profiles')
      call h5_attr(out%h5, '/fields', 'rows', 'half nodes top to bottom, as PREFIX.prf: ' // &
                   'node 0 lower half, then upper and lower half of each interior node, ' // &
                   'node n upper half; x at /mesh/x_half')
      if (rec%field_every > 0) then
         k = 64
         if (present(xt_rows)) k = xt_rows
         call h5_xt(out%h5, '/fields/xt', 2 * n, rows=k)
         call h5_attr(out%h5, '/fields/xt', 'every', rec%field_every)
      end if
      call h5_group(out%h5, '/fragments')
      if (size(rec%gauge_x) > 0) then
         call h5_xt(out%h5, '/gauges', size(rec%gauge_x), xt_gauges, &
                    [character(len=8) :: 'stress', 'velocity', 'u'], &
                    [character(len=8) :: 'Pa', 'm/s', 'm'])
         call h5_attr(out%h5, '/gauges', 'x', rec%gauge_x)
         call h5_attr(out%h5, '/gauges', 'every', rec%gauge_every)
         call h5_attr(out%h5, '/gauges', 'layout', 'as PREFIX.gau: Fortran (gauges, rows); ' // &
                      'h5py/numpy see (rows, gauges); x [m] the gauges'' reference positions')
      end if
      call h5_flush(out%h5)
      if (allocated(out%h5%error)) call make_error(err, '--output: ' // out%h5%error, &
                                                   code=exit_runtime)
   end subroutine open_h5

   !> Reference position of every half-node row (the .prf layout).
   pure function half_x(mesh) result(x)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      real(wp) :: x(2 * mesh%n)
      integer :: i, r
      r = 0
      do i = 0, mesh%n
         if (i > 0) then
            r = r + 1
            x(r) = mesh%x(i)
         end if
         if (i < mesh%n) then
            r = r + 1
            x(r) = mesh%x(i)
         end if
      end do
   end function half_x

   !> u, v and stress of every half-node row at the state's time.
   pure subroutine half_rows(mesh, st, u, v, s)
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(out) :: u(:)        !! displacement of each half-node row [m]
      real(wp), intent(out) :: v(:)        !! velocity of each row over the last step [m/s]
      real(wp), intent(out) :: s(:)        !! stress of each row's cell [Pa]
      integer :: i, r
      r = 0
      do i = 0, mesh%n
         if (i > 0) then
            r = r + 1
            u(r) = st%ua(i)
            v(r) = st%dua(i) / mesh%dt
            s(r) = st%s(i) / mesh%area(i)
         end if
         if (i < mesh%n) then
            r = r + 1
            u(r) = st%ub(i)
            v(r) = st%dub(i) / mesh%dt
            s(r) = st%s(i + 1) / mesh%area(i + 1)
         end if
      end do
   end subroutine half_rows

   !> One row of the x-t fields (PREFIX.h5 only).
   subroutine write_field(out, mesh, st)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp) :: u(2 * mesh%n), v(2 * mesh%n), s(2 * mesh%n)
      if (.not. out%hdf5) return
      call half_rows(mesh, st, u, v, s)
      call h5_append_xt(out%h5, real(st%step, wp) * mesh%dt, u, v, s)
   end subroutine write_field

   !> The history's column names, blank-separated (the column line of PREFIX.his).
   pure function history_columns() result(line)
      character(len=:), allocatable :: line
      type(column_set_t) :: his
      his = history_set()
      line = column_names(his%col)
   end function history_columns

   !> The event columns' names, blank-separated (the column line of PREFIX.evt).
   pure function event_columns() result(line)
      character(len=:), allocatable :: line
      type(column_set_t) :: evt
      type(event_columns_t) :: id
      call register_event_columns(evt, id)
      line = column_names(evt%col)
   end function event_columns

   !> The contact episodes' column names, blank-separated (the column line of PREFIX.imp).
   pure function impact_table_columns() result(line)
      character(len=:), allocatable :: line
      line = joined_names(impact_columns())
   end function impact_table_columns

   !> The blank-separated words of s.
   pure subroutine split(s, words)
      character(len=*), intent(in) :: s   !! the text
      character(len=32), allocatable, intent(out) :: words(:)   !! its words, in order
      integer :: i, j, n
      allocate(words(0))
      i = 1
      n = len_trim(s)
      do while (i <= n)
         if (s(i:i) == ' ') then
            i = i + 1
            cycle
         end if
         j = i
         do while (j < n)
            if (s(j + 1:j + 1) == ' ') exit
            j = j + 1
         end do
         words = [character(len=32) :: words, s(i:j)]
         i = j + 1
      end do
   end subroutine split

   !> One history row: the values of out%his_table's columns, each posted under its id
   !> (spb_history post_history; whole numbers as float64).
   subroutine write_history_row(out, v)
      type(outputs_t), intent(inout) :: out    !! the outputs
      real(wp), intent(in) :: v(:)             !! the row
      call table_line(out%his_table, v, out%his_cache)
      call put_row(out, 1, out%his_cache%line)
      out%n_his = out%n_his + 1
      ! the text reaches the file before PREFIX.h5 writes a block of rows: a killed run's
      ! text never holds fewer rows than its HDF5 tables
      if (out%hdf5 .and. mod(out%n_his, int(buffer_rows, int64)) == 0) call drain_one(out, 1)
      if (out%hdf5) call h5_append(out%h5, out%h_his, v)
   end subroutine write_history_row

   !> Rows for the events of the list.
   subroutine write_events(out, events)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(event_list_t), intent(in) :: events   !! events of the step (appended)
      real(wp) :: v(size(out%evt_table))
      character(len=10) :: code   ! the row's kind_code (1x,i9)
      integer :: k
      code(1:1) = ' '
      do k = 1, events%n
         associate (e => events%e(k))
            call post_event_columns(out%evt_id, e, v)
            call table_line(out%evt_table, v, out%evt_cache)
            call int_into(e%kind, code(2:10))
            call put_row(out, 3, out%evt_cache%line, code)
            out%n_evt = out%n_evt + 1
            if (out%hdf5 .and. mod(out%n_evt, int(buffer_rows, int64)) == 0) then
               call drain_one(out, 3)
            end if
            if (out%hdf5) call h5_append(out%h5, out%h_evt, v)
         end associate
      end do
   end subroutine write_events

   !> Collect one row of text file k (text_extensions order); the rows are written when the
   !> buffer is full and by drain_rows. With tail: the row is line // tail (copied once).
   subroutine put_row(out, k, line, tail)
      type(outputs_t), intent(inout) :: out   !! the outputs
      integer, intent(in) :: k                !! text file (text_extensions)
      character(len=*), intent(in) :: line    !! the row, without its newline
      character(len=*), intent(in), optional :: tail   !! the rest of the row
      integer :: u, ios, n
      u = text_unit(out, k)
      if (u == no_unit) return
      n = len(line)
      if (present(tail)) n = n + len(tail)
      out%expect(k) = out%expect(k) + n + 1
      associate (b => out%rows(k))
         if (.not. allocated(b%text)) allocate(character(len=row_buffer_len) :: b%text)
         if (b%n + n + 1 > row_buffer_len) call drain_one(out, k)
         if (n + 1 > row_buffer_len) then
            if (present(tail)) then
               write(u, '(2a)', iostat=ios) line, tail
            else
               write(u, '(a)', iostat=ios) line
            end if
            if (ios /= 0) out%refused(k) = .true.    ! check_written tells
         else
            b%text(b%n + 1:b%n + len(line)) = line
            if (present(tail)) b%text(b%n + len(line) + 1:b%n + n) = tail
            b%text(b%n + n + 1:b%n + n + 1) = new_line('a')
            b%n = b%n + n + 1
         end if
      end associate
   end subroutine put_row

   !> Write the collected rows of every text file.
   subroutine drain_rows(out)
      type(outputs_t), intent(inout) :: out   !! the outputs
      integer :: k
      do k = 1, size(out%rows)
         call drain_one(out, k)
      end do
   end subroutine drain_rows

   !> Write the collected rows of text file k as one record: the rows with their newlines,
   !> the last newline left to the record's end (the bytes of one write per row).
   subroutine drain_one(out, k)
      type(outputs_t), intent(inout) :: out   !! the outputs
      integer, intent(in) :: k                !! text file (text_extensions)
      integer :: u, ios
      associate (b => out%rows(k))
         if (b%n == 0) return
         u = text_unit(out, k)
         ! a refused write (a full disk) is found by check_written (out%expect)
         if (u /= no_unit) then
            write(u, '(a)', iostat=ios) b%text(1:b%n - 1)
            if (ios /= 0) out%refused(k) = .true.
         end if
         b%n = 0
      end associate
   end subroutine drain_one

   !> One text row of a table into cache%line: each column a blank and its field, by the
   !> fast formatters (the same characters as es20.12e3 and iW edit descriptors,
   !> tests/test_format.pf); a field whose value has the bits of the row before keeps its text.
   pure subroutine table_line(table, v, cache)
      type(column_t), intent(in) :: table(:)   !! the columns
      real(wp), intent(in) :: v(:)             !! the row's values (whole numbers as float64)
      type(row_cache_t), intent(inout) :: cache   !! the table's last row, then this one
      integer :: k, at
      integer(int64) :: bits
      if (.not. allocated(cache%line)) then
         cache%line = repeat(' ', sum(table%width + 1))
         allocate(cache%bits(size(table)), cache%set(size(table)))
         cache%set = .false.
      end if
      at = 1
      do k = 1, size(table)
         associate (c => table(k))
            bits = transfer(v(k), 0_int64)
            if (.not. cache%set(k) .or. cache%bits(k) /= bits) then
               if (c%kind) then
                  cache%line(at + 1:at + c%width) = kind_field(whole(v(k)))
               else if (c%whole) then
                  call int_into(whole(v(k)), cache%line(at + 1:at + c%width))
               else if (c%width == 20) then
                  call es_into(v(k), cache%line(at + 1:at + 20))
               else
                  cache%line(at + 1:at + c%width) = es20_12(v(k))
               end if
               cache%bits(k) = bits
               cache%set(k) = .true.
            end if
            at = at + c%width + 1
         end associate
      end do
   end subroutine table_line

   !> nint(x) for a whole number held as float64 (exact below 2^53), without the library call
   !> where x is whole.
   pure integer function whole(x) result(k)
      real(wp), intent(in) :: x            !! the value
      k = int(x)
      if (abs(x - real(k, wp)) > 0.0_wp) k = nint(x)
   end function whole

   !> One block of fragments at time t.
   subroutine write_fragments(out, t, dt, list)
      type(outputs_t), intent(inout) :: out   !! the outputs
      real(wp), intent(in) :: t            !! time of the row [s]
      real(wp), intent(in) :: dt           !! time step [s]
      type(frag_info_t), intent(in) :: list(:)   !! the fragments, top to bottom
      integer :: f
      character(len=:), allocatable :: g
      character(len=2 * 13 + 6 * 21 + 2 * 13 + 21) :: line
      call put_row(out, 4, '# t = ' // rtoa(t))
      do f = 1, size(list)
         ! (2(1x,i12),6(1x,es20.12e3),2(1x,i12),1x,es20.12e3): ... top_node bottom_node t
         line = ' ' // int_right(list(f)%id, 12) // ' ' // int_right(list(f)%parent, 12) // &
            ' ' // es20_12(real(list(f)%birth_step, wp) * dt) // ' ' // es20_12(list(f)%x_top) // &
            ' ' // es20_12(list(f)%x_bot) // ' ' // es20_12(list(f)%mass) // &
            ' ' // es20_12(list(f)%velocity) // ' ' // es20_12(list(f)%e_vib) // &
            ' ' // int_right(list(f)%top, 12) // ' ' // int_right(list(f)%bot, 12) // &
            ' ' // es20_12(t)
         call put_row(out, 4, line)
      end do
      if (.not. out%hdf5) return
      out%n_frg = out%n_frg + 1
      g = '/fragments/' // block_name(out%n_frg)
      call h5_group(out%h5, g)
      call h5_attr(out%h5, g, 't', t)
      block
         integer :: ic(size(list))
         real(wp) :: rc(size(list))
         ic = list%id
         call h5_write(out%h5, g // '/id', ic, '-')
         ic = list%parent
         call h5_write(out%h5, g // '/parent', ic, '-')
         rc = real(list%birth_step, wp) * dt
         call h5_write(out%h5, g // '/birth_t', rc, 's')
         rc = list%x_top
         call h5_write(out%h5, g // '/x_top', rc, 'm')
         rc = list%x_bot
         call h5_write(out%h5, g // '/x_bottom', rc, 'm')
         rc = list%mass
         call h5_write(out%h5, g // '/mass', rc, unit_text('kg/m^2', out%per_area))
         rc = list%velocity
         call h5_write(out%h5, g // '/velocity', rc, 'm/s')
         rc = list%e_vib
         call h5_write(out%h5, g // '/e_vib', rc, unit_text('J/m^2', out%per_area))
         ic = list%top
         call h5_write(out%h5, g // '/top_node', ic, '-')
         ic = list%bot
         call h5_write(out%h5, g // '/bottom_node', ic, '-')
      end block
   end subroutine write_fragments

   !> One profile block at the state's time.
   subroutine write_profile(out, mesh, st, t_requested)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(state_t), intent(in) :: st      !! the state
      real(wp), intent(in) :: t_requested   !! the profile_times entry [s]
      integer :: i, n
      real(wp) :: dt
      real(wp) :: u(2 * mesh%n), v(2 * mesh%n), s(2 * mesh%n)
      character(len=:), allocatable :: g
      character(len=20) :: tt
      n = mesh%n
      dt = mesh%dt
      call put_row(out, 2, '# t = ' // rtoa(real(st%step, wp) * dt))
      call put_row(out, 2, '# step ' // itoa(st%step) // ', requested t = ' // rtoa(t_requested))
      ! (5(1x,es20.12e3)): x u v stress t
      tt = es20_12(real(st%step, wp) * dt)
      do i = 0, n
         if (i > 0) call put_row(out, 2, ' ' // es20_12(mesh%x(i)) // ' ' // es20_12(st%ua(i)) // &
            ' ' // es20_12(st%dua(i) / dt) // ' ' // es20_12(st%s(i) / mesh%area(i)) // ' ' // tt)
         if (i < n) call put_row(out, 2, ' ' // es20_12(mesh%x(i)) // ' ' // es20_12(st%ub(i)) // &
            ' ' // es20_12(st%dub(i) / dt) // ' ' // es20_12(st%s(i + 1) / mesh%area(i + 1)) // &
            ' ' // tt)
      end do
      if (.not. out%hdf5) return
      out%n_prof = out%n_prof + 1
      g = '/fields/profiles/' // block_name(out%n_prof)
      call half_rows(mesh, st, u, v, s)
      call h5_group(out%h5, g)
      call h5_attr(out%h5, g, 't', real(st%step, wp) * dt)
      call h5_attr(out%h5, g, 't_requested', t_requested)
      call h5_attr(out%h5, g, 'step', st%step)
      call h5_write(out%h5, g // '/u', u, 'm')
      call h5_write(out%h5, g // '/v', v, 'm/s')
      call h5_write(out%h5, g // '/stress', s, 'Pa')
   end subroutine write_profile
   !> An event kind's name right-justified in 16 characters (the A16 field of the .evt rows),
   !> without a temporary per event.
   pure function kind_field(kind) result(f)
      integer, intent(in) :: kind   !! event kind (ev_*)
      character(len=16) :: f
      character(len=16), parameter :: fields(size(event_kinds)) = &
         adjustr('  ' // event_kinds%name)
      f = fields(max(1, min(size(event_kinds), kind)))
   end function kind_field

   !> A namelist string value without its quotes ('a' -> a); lists are left as they are.
   pure function unquote(v) result(r)
      character(len=*), intent(in) :: v   !! the value text
      character(len=:), allocatable :: r
      integer :: n
      n = len(v)
      r = v
      if (n >= 2) then
         if (v(1:1) == '''' .and. v(n:n) == '''' .and. index(v(2:n - 1), '''') == 0) r = v(2:n - 1)
      end if
   end function unquote

   !> The unit of a column of PREFIX.spl or .imp for this bar: forces in Pa and impulses in
   !> Pa s when every area is 1 (per unit area), else N and N s.
   pure function diag_unit(unit, mesh) result(out)
      character(len=*), intent(in) :: unit   !! the unit of the whole bar ('N', 'N s', ...)
      type(mesh_t), intent(in) :: mesh       !! the mesh
      character(len=:), allocatable :: out
      out = trim(unit)
      if (.not. per_unit_area(mesh)) return
      if (out == 'N') out = 'Pa'
      if (out == 'N s') out = 'Pa s'
   end function diag_unit

   !> The words of a column list, blank-separated.
   pure function joined_names(names) result(line)
      character(len=*), intent(in) :: names(:)   !! the names
      character(len=:), allocatable :: line
      integer :: k
      line = trim(names(1))
      do k = 2, size(names)
         line = line // ' ' // trim(names(k))
      end do
   end function joined_names

   !> PREFIX.spl (one row per free end), written once at the end of a run (doc/outputs.md),
   !> with the header every text output has.
   subroutine write_diag_text(prefix, rec, mesh, report, d, err)
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      character(len=*), intent(in) :: report(:)     !! mesh fit report lines
      type(diag_t), intent(in) :: d        !! the record
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      integer :: u, k, side
      real(wp) :: v(11)
      character(len=:), allocatable :: line, cols
      character(len=10) :: frac
      write(frac, '(f10.2)') pick_fraction
      ! PREFIX.spl
      cols = 'end ' // joined_names(spall_columns())
      call open_text('.spl', u)
      if (allocated(err)) return
      if (rec%names_first) write(u, '(a)') cols
      call header_lines(u, rec, mesh, report, 'spall: one row per free end of the bar (top, ' &
                        // 'bottom)')
      write(u, '(a)') '# v_*: the end''s velocity along its outward normal (up at the top, ' &
         // 'down at the bottom); the peak is the first maximum confirmed by a fall of ' // &
         trim(adjustl(frac)) // ' of its rise, the pull-back the minimum after it confirmed ' // &
         'by a rise of ' // trim(adjustl(frac)) // ' of the drop (doc/outputs.md)'
      write(u, '(a)') '# sigma_novikov = rho c dv_pullback / 2 of the end cell; spall_x: ' // &
         'reference position of the fracture nearest the end (m from the top); ' // &
         'scab_*: the piece between it and the end when it broke (velocity outward)'
      write(u, '(a)') '# NaN: no value (no peak, no pull-back, no fracture)'
      write(u, '(a)') '# units: t_* [s]; v_*, dv_pullback, scab_velocity [m/s]; sigma_novikov ' &
         // '[Pa]; spall_x, scab_thickness [m]'
      write(u, '(a)') '# ' // cols
      do side = 1, 2
         if (.not. d%ends(side)%on) cycle
         v(1:10) = spall_row(d%ends(side))
         line = ' ' // end_names(side)
         do k = 1, 10
            line = line // ' ' // num(v(k))
         end do
         write(u, '(a)') line
      end do
      close(u)
   contains
      !> A value in 1x,es20.12e3 (NaN as 'NaN', right-aligned).
      function num(x) result(text)
         real(wp), intent(in) :: x         !! the value
         character(len=20) :: text
         write(text, '(es20.12e3)') x
      end function num
      !> Open PREFIX.ext for writing.
      subroutine open_text(ext, unit)
         character(len=*), intent(in) :: ext   !! the extension
         integer, intent(out) :: unit      !! its unit
         integer :: ios
         character(len=256) :: msg
         open(newunit=unit, file=prefix // ext, status='replace', action='write', iostat=ios, &
              iomsg=msg)
         if (ios /= 0) call make_error(err, 'run: cannot write ''' // prefix // ext // ''': ' &
                                       // trim(msg), code=exit_runtime)
      end subroutine open_text
   end subroutine write_diag_text

   !> The same as /spall of PREFIX.h5 (before it is closed): columns as in the text file,
   !> end as a code (1 top, 2 bottom).
   subroutine write_diag_h5(out, d)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(diag_t), intent(in) :: d        !! the record
      character(len=14) :: names(11)
      character(len=8) :: units(11)
      logical :: whole(11)
      real(wp) :: v(11)
      integer :: h, side
      if (.not. out%hdf5) return
      names = [character(len=14) :: 'end', spall_columns()]
      units = [character(len=8) :: '-', spall_units()]
      whole = .false.
      whole(1) = .true.
      call h5_table(out%h5, '/spall', names, units, whole, h)
      do side = 1, 2
         if (.not. d%ends(side)%on) cycle
         v(1) = real(side, wp)
         v(2:11) = spall_row(d%ends(side))
         call h5_append(out%h5, h, v)
      end do
   end subroutine write_diag_h5

   !> Rows of PREFIX.imp and /impacts for the contact episodes (spb_diagnostics) that ended
   !> since the last call, in the order they ended: the columns of impact_columns, kind as
   !> its word in the text (/impacts: its code), NaN where there is no value.
   subroutine write_impacts(out, ended)
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(impact_t), intent(in) :: ended(:)   !! the episodes that ended
      real(wp) :: v(11)
      integer :: k
      do k = 1, size(ended)
         v = impact_row(ended(k))
         call impact_line(v, ended(k)%kind, out%imp_cache)
         call put_row(out, 5, out%imp_cache%line)
         out%n_imp = out%n_imp + 1
         if (.not. out%hdf5) cycle
         ! the text reaches the file before PREFIX.h5 writes a block of rows (write_events)
         if (mod(out%n_imp, int(buffer_rows, int64)) == 0) call drain_one(out, 5)
         call h5_append(out%h5, out%h_imp, v)
      end do
   end subroutine write_impacts

   !> One row of PREFIX.imp into cache%line: 1x,es20.12e3 per column, the kind's word
   !> right-aligned in 1x,a16 (the fourth); a value with the bits of the row before keeps its
   !> text (table_line: consecutive episodes often share their times).
   pure subroutine impact_line(v, kind, cache)
      real(wp), intent(in) :: v(11)        !! the row's values (impact_row; v(4) unused)
      integer, intent(in) :: kind          !! the episode's kind (imp_* constant)
      type(row_cache_t), intent(inout) :: cache   !! the last row, then this one
      integer :: c, at
      integer(int64) :: bits
      if (.not. allocated(cache%line)) then
         cache%line = repeat(' ', 10 * 21 + 17)
         allocate(cache%bits(11), cache%set(11))
         cache%set = .false.
      end if
      at = 0
      do c = 1, 11
         if (c == 4) then
            cache%line(at + 1:at + 17) = ' ' // adjustr(imp_kind_names(kind) // '       ')
            at = at + 17
         else
            bits = transfer(v(c), 0_int64)
            if (.not. cache%set(c) .or. cache%bits(c) /= bits) then
               call es_into(v(c), cache%line(at + 2:at + 21))
               cache%bits(c) = bits
               cache%set(c) = .true.
            end if
            at = at + 21
         end if
      end do
   end subroutine impact_line
end module spb_output
