!> Restart: the outputs of a run continued from a checkpoint are the previous run's up to
!> the checkpoint's marks, then this run's (bit-identical to one uninterrupted run).
module spb_restart
   use, intrinsic :: iso_fortran_env, only: int64
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t, make_error, exit_runtime
   use spb_strings, only: itoa
   use spb_deck, only: deck_record_t
   use spb_hdf5, only: h5file_t, h5_close, h5_flush, h5_open_read, h5_get, h5_get_columns, &
      h5_copy, h5_append, h5_append_xt, h5_read_size, xt_gauges, xt_fields
   use spb_sys, only: sys_rename
   use spb_mesh, only: mesh_t
   use spb_output, only: outputs_t, output_marks_t, open_outputs, text_extensions, tail_len, &
      history_columns, event_columns, impact_table_columns, find_header, column_line, text_unit, set_text_unit, &
      no_unit, block_name, split, text_count, remove_file
   implicit none
   private
   public :: resume_outputs, drop_set_aside

   character(len=*), parameter :: aside = '.restart'   !! suffix of the set-aside outputs
   character(len=*), parameter :: hint = ' (a restart continues the outputs of the run ' // &
      'that wrote the checkpoint: same directory and --output PREFIX)'

contains

   !> Outputs of a restarted run: fresh headers for this deck, then the body of the previous
   !> run's files up to the marks (rows written after them are dropped), open for appending.
   !> The previous files are set aside as PREFIX.ext.restart while this is done and removed
   !> after; nothing is touched when they do not hold what the marks count.
   !>
   !> A restart killed on the way (SIGKILL, a node that died) is resumed by the next one: a
   !> PREFIX.ext.restart that exists is the previous output (the rename happened; PREFIX.ext
   !> is then a cut copy or one rebuilt up to the marks, and is rebuilt again from it), else
   !> PREFIX.ext is. Renames are atomic and the set-aside files are removed only once every
   !> output is rebuilt, so at every instant one complete copy of each file exists.
   subroutine resume_outputs(prefix, rec, mesh, report, marks, out, err, xt_rows)
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      character(len=*), intent(in) :: report(:)   !! the mesh fit report (stretched segments)
      type(output_marks_t), intent(in) :: marks   !! how far the outputs reach
      type(outputs_t), intent(out) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      integer, intent(in), optional :: xt_rows   !! x-t times buffered in memory (default 64)
      integer(int64) :: head(size(text_extensions))
      integer :: k, nrows, nt, ng
      logical :: aside_there(size(text_extensions) + 1), ok
      character(len=:), allocatable :: f   !! one output's path
      character(len=len(prefix) + 12) :: prev(size(text_extensions) + 1)   !! the previous outputs (PREFIX.ext[.restart])
      ! the previous outputs (set aside by a restart that did not finish, or not yet): a
      ! header, then at least the body the checkpoint counts, ending in the bytes it remembers
      nt = text_count(rec)            ! 5, or 6 with gauges (.gau)
      ng = size(rec%gauge_x)
      do k = 1, nt + 1
         f = output_file(prefix, k, nt)
         inquire(file=f // aside, exist=aside_there(k))
         if (aside_there(k)) f = f // aside
         prev(k) = f
      end do
      do k = 1, nt
         call check_text(trim(prev(k)), k, ng, marks, head(k), err)
         if (allocated(err)) return
      end do
      if (rec%hdf5) then
         call h5_read_size(trim(prev(nt + 1)), '/history/t', nrows)
         if (nrows < marks%rows_his) then
            call make_error(err, '--restart: ''' // trim(prev(nt + 1)) // ''' holds ' // &
               itoa(max(nrows, 0)) // ' history rows, the checkpoint counts ' // &
               itoa(marks%rows_his) // hint)
            return
         end if
      end if
      do k = 1, nt + 1
         if (k == nt + 1 .and. .not. rec%hdf5) exit
         if (aside_there(k)) cycle
         f = output_file(prefix, k, nt)
         call sys_rename(f, f // aside, ok)
         if (.not. ok) then
            call make_error(err, '--restart: cannot rename ''' // f // ''' to ''' // f // &
                            aside // '''')
            return
         end if
      end do
      call open_outputs(prefix, rec, mesh, report, out, err, xt_rows)
      if (allocated(err)) return
      do k = 1, nt
         call copy_body(prefix, k, head(k), marks%body(k), out, err)
         if (allocated(err)) return
      end do
      if (rec%hdf5) then
         call replay_h5(prefix, mesh, marks, out, err)
         if (allocated(err)) return
      end if
      call drop_set_aside(prefix)
   end subroutine resume_outputs

   !> Refuse a previous text output k that lacks the header, the body the checkpoint counts
   !> or the bytes it remembers at the end of that body.
   subroutine check_text(f, k, ng, marks, head, err)
      character(len=*), intent(in) :: f   !! the previous output
      integer, intent(in) :: k            !! text file (text_extensions)
      integer, intent(in) :: ng           !! gauges of the deck (the .gau columns)
      type(output_marks_t), intent(in) :: marks   !! how far the outputs reach
      integer(int64), intent(out) :: head   !! its header bytes
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: refused)
      integer(int64) :: sz
      integer :: u, ios
      logical :: there
      character(len=tail_len) :: tail
      head = -1
      inquire(file=f, exist=there)
      if (.not. there) then
         call make_error(err, '--restart: ''' // f // ''' is missing' // hint)
         return
      end if
      call find_header(f, k, head, sz, ng)
      if (head < 0) then
         call make_error(err, '--restart: ''' // f // ''' has no header line ''' // &
            column_line(k, ng) // ''': not a spallbar output' // hint)
      else if (sz - head < marks%body(k)) then
         call make_error(err, '--restart: ''' // f // ''' holds ' // &
            itoa(sz - head) // ' bytes after its header, the checkpoint counts ' // &
            itoa(marks%body(k)) // hint)
      else if (marks%tail_n(k) < 0) then
         call make_error(err, '--restart: the checkpoint could not read the end of ''' // &
            f // ''' when it was written')
      else if (marks%tail_n(k) > 0) then
         open(newunit=u, file=f, access='stream', form='unformatted', status='old', &
              action='read', iostat=ios)
         if (ios == 0) read(u, pos=head + marks%body(k) - marks%tail_n(k) + 1, &
                            iostat=ios) tail(1:marks%tail_n(k))
         if (ios == 0) close(u)
         if (ios /= 0) then
            call make_error(err, '--restart: cannot read ''' // f // '''')
         else if (tail(1:marks%tail_n(k)) /= marks%tail(k)(1:marks%tail_n(k))) then
            call make_error(err, '--restart: ''' // f // ''' is not the output of the ' // &
               'run that wrote the checkpoint (its rows differ at the checkpoint)' // hint)
         end if
      end if
   end subroutine check_text

   !> Remove the set-aside outputs PREFIX.ext.restart: at the end of a restart (the outputs
   !> are rebuilt), and before a run that starts afresh on PREFIX (left by a restart that
   !> was killed, they would be taken for that run's outputs by its next --restart).
   subroutine drop_set_aside(prefix)
      character(len=*), intent(in) :: prefix   !! output path prefix
      integer :: k
      do k = 1, size(text_extensions) + 1
         call remove_file(output_file(prefix, k, size(text_extensions)) // aside)
      end do
   end subroutine drop_set_aside

   !> PREFIX.ext of output k of a run with nt text files (text_extensions(k), nt + 1:
   !> PREFIX.h5).
   pure function output_file(prefix, k, nt) result(f)
      character(len=*), intent(in) :: prefix   !! output path prefix
      integer, intent(in) :: k   !! file (text_extensions, nt + 1: PREFIX.h5)
      integer, intent(in) :: nt  !! text files of the run (text_count)
      character(len=:), allocatable :: f
      f = prefix // trim(merge(text_extensions(min(k, nt)), '.h5 ', k <= nt))
   end function output_file

   !> Append the body up to the mark of the set-aside file k to the fresh one.
   subroutine copy_body(prefix, k, head, body, out, err)
      character(len=*), intent(in) :: prefix   !! output path prefix
      integer, intent(in) :: k                 !! text file (text_extensions)
      integer(int64), intent(in) :: head       !! header bytes of the set-aside file
      integer(int64), intent(in) :: body       !! body bytes the checkpoint counts
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer, parameter :: chunk = 1048576
      character(len=:), allocatable :: buf
      integer(int64) :: pos, m
      integer :: src, dst, ios
      character(len=256) :: msg
      associate (f => prefix // text_extensions(k))
         close(text_unit(out, k))
         allocate(character(len=chunk) :: buf)
         open(newunit=src, file=f // aside, access='stream', form='unformatted', &
              status='old', action='read', iostat=ios, iomsg=msg)
         if (ios == 0) open(newunit=dst, file=f, access='stream', form='unformatted', &
              status='old', action='write', position='append', iostat=ios, iomsg=msg)
         pos = head + 1
         do while (ios == 0 .and. pos <= head + body)
            m = min(int(chunk, int64), head + body - pos + 1)
            read(src, pos=pos, iostat=ios, iomsg=msg) buf(1:m)
            if (ios == 0) write(dst, iostat=ios, iomsg=msg) buf(1:m)
            pos = pos + m
         end do
         close(src)
         close(dst)
         if (ios == 0) then
            open(newunit=dst, file=f, status='old', action='write', position='append', &
                 iostat=ios, iomsg=msg)
         end if
         if (ios /= 0) then
            call make_error(err, '--restart: copying ''' // f // aside // ''' to ''' // f // &
                            ''': ' // trim(msg), code=exit_runtime)
            dst = no_unit
         end if
         call set_text_unit(out, k, dst)
      end associate
   end subroutine copy_body
   !> PREFIX.h5: table rows and x-t times up to the marks, profile and fragment groups.
   subroutine replay_h5(prefix, mesh, marks, out, err)
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(output_marks_t), intent(in) :: marks   !! how far the outputs reach
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(h5file_t) :: old     !! the previous PREFIX.h5, read while it is replayed
      integer :: k
      call h5_open_read(old, prefix // '.h5' // aside)
      call replay_table(prefix, old, '/history', history_columns(), out, out%h_his, &
                        marks%rows_his, err)
      call replay_table(prefix, old, '/events', event_columns(), out, out%h_evt, marks%rows_evt, &
                        err)
      call replay_table(prefix, old, '/impacts', impact_table_columns(), out, out%h_imp, &
                        marks%rows_imp, err)
      if (marks%rows_xt > 0) call replay_xt(prefix, old, mesh, marks%rows_xt, out, err)
      if (marks%rows_gau > 0) call replay_gauges(prefix, old, out%n_gauges, marks%rows_gau, &
                                                 out, err)
      do k = 1, marks%n_prof
         if (allocated(out%h5%error)) exit   ! a group missing: no use trying the others
         call h5_copy(old, '/fields/profiles/' // block_name(k), out%h5, &
                      '/fields/profiles/' // block_name(k))
      end do
      out%n_prof = marks%n_prof
      do k = 1, marks%n_frg
         if (allocated(out%h5%error)) exit
         call h5_copy(old, '/fragments/' // block_name(k), out%h5, &
                      '/fragments/' // block_name(k))
      end do
      out%n_frg = marks%n_frg
      call h5_flush(out%h5)
      if (allocated(old%error)) then
         call make_error(err, '--restart: ' // old%error, code=exit_runtime)
      else if (allocated(out%h5%error)) then
         call make_error(err, '--restart: ' // out%h5%error, code=exit_runtime)
      end if
      call h5_close(old)
   end subroutine replay_h5
   !> The first rows of every column of a table (integer columns read as float64).
   subroutine replay_table(prefix, old, path, columns, out, handle, rows, err)
      character(len=*), intent(in) :: prefix   !! output path prefix
      character(len=*), intent(in) :: path   !! table path in the file
      character(len=*), intent(in) :: columns   !! its column names, blank-separated
      type(h5file_t), intent(inout) :: old     !! the previous PREFIX.h5
      type(outputs_t), intent(inout) :: out   !! the outputs
      integer, intent(in) :: handle            !! table handle in out%h5
      integer, intent(in) :: rows              !! rows to copy
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=32), allocatable :: names(:)
      real(wp), allocatable :: col(:), table(:, :)
      integer :: c, r
      if (rows == 0) return
      call split(columns, names)
      do c = 1, size(names)
         call h5_get(old, path // '/' // trim(names(c)), col)
         if (.not. allocated(col)) then
            call make_error(err, '--restart: ''' // prefix // '.h5'' has no ' // path // &
                            '/' // trim(names(c)), code=exit_runtime)
            return
         end if
         if (size(col) < rows) then
            call make_error(err, '--restart: ''' // prefix // '.h5'' ' // path // '/' // &
               trim(names(c)) // ' holds ' // itoa(size(col)) // ' rows, the ' // &
               'checkpoint counts ' // itoa(rows), code=exit_runtime)
            return
         end if
         ! allocated once the first column shows the file holds the rows counted
         if (.not. allocated(table)) allocate(table(size(names), rows))
         table(c, :) = col(1:rows)
      end do
      do r = 1, rows
         call h5_append(out%h5, handle, table(:, r))
      end do
   end subroutine replay_table
   !> The first times of the x-t field, in blocks of columns.
   subroutine replay_xt(prefix, old, mesh, rows_xt, out, err)
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(h5file_t), intent(inout) :: old     !! the previous PREFIX.h5
      type(mesh_t), intent(in) :: mesh     !! the mesh
      integer, intent(in) :: rows_xt           !! times to copy
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      real(wp), allocatable :: t(:), u(:, :), v(:, :), s(:, :)
      integer :: c0, m, j, width
      ! as many times at once as the new file buffers (fewer when memory is short; spb_sim)
      width = 64
      if (allocated(out%h5%xt(xt_fields)%tbuf)) width = size(out%h5%xt(xt_fields)%tbuf)
      call h5_get(old, '/fields/xt/t', t)
      if (.not. allocated(t)) then
         call make_error(err, '--restart: ''' // prefix // '.h5'' has no /fields/xt', &
                         code=exit_runtime)
         return
      end if
      if (size(t) < rows_xt) then
         call make_error(err, '--restart: ''' // prefix // '.h5'' /fields/xt holds ' // &
            itoa(size(t)) // ' times, the checkpoint counts ' // itoa(rows_xt), &
            code=exit_runtime)
         return
      end if
      allocate(u(2 * mesh%n, width), v(2 * mesh%n, width), s(2 * mesh%n, width))
      do c0 = 0, rows_xt - 1, width
         m = min(width, rows_xt - c0)
         call h5_get_columns(old, '/fields/xt/u', c0, u(:, 1:m))
         call h5_get_columns(old, '/fields/xt/v', c0, v(:, 1:m))
         call h5_get_columns(old, '/fields/xt/stress', c0, s(:, 1:m))
         do j = 1, m
            call h5_append_xt(out%h5, t(c0 + j), u(:, j), v(:, j), s(:, j))
         end do
      end do
   end subroutine replay_xt

   !> The first rows of the gauges (/gauges), in blocks of rows.
   subroutine replay_gauges(prefix, old, n_gauges, rows, out, err)
      character(len=*), intent(in) :: prefix   !! output path prefix
      type(h5file_t), intent(inout) :: old     !! the previous PREFIX.h5
      integer, intent(in) :: n_gauges          !! gauges
      integer, intent(in) :: rows              !! rows to copy
      type(outputs_t), intent(inout) :: out   !! the outputs
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer, parameter :: width = 64
      real(wp), allocatable :: t(:), s(:, :), v(:, :), u(:, :)
      integer :: c0, m, j
      call h5_get(old, '/gauges/t', t)
      if (.not. allocated(t)) then
         call make_error(err, '--restart: ''' // prefix // '.h5'' has no /gauges', &
                         code=exit_runtime)
         return
      end if
      if (size(t) < rows) then
         call make_error(err, '--restart: ''' // prefix // '.h5'' /gauges holds ' // &
            itoa(size(t)) // ' rows, the checkpoint counts ' // itoa(rows), code=exit_runtime)
         return
      end if
      allocate(s(n_gauges, width), v(n_gauges, width), u(n_gauges, width))
      do c0 = 0, rows - 1, width
         m = min(width, rows - c0)
         call h5_get_columns(old, '/gauges/stress', c0, s(:, 1:m))
         call h5_get_columns(old, '/gauges/velocity', c0, v(:, 1:m))
         call h5_get_columns(old, '/gauges/u', c0, u(:, 1:m))
         do j = 1, m
            call h5_append_xt(out%h5, t(c0 + j), s(:, j), v(:, j), u(:, j), xt_gauges)
         end do
      end do
   end subroutine replay_gauges
end module spb_restart
