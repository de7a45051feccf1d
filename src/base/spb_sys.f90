!> The few operating-system services Fortran 2008 lacks, through C interoperability.
module spb_sys
   use, intrinsic :: iso_c_binding, only: c_int, c_long, c_char, c_null_char, c_funptr, &
      c_funloc, c_ptr, c_associated
   use, intrinsic :: iso_fortran_env, only: int64, output_unit, error_unit
   use, intrinsic :: ieee_exceptions, only: ieee_flag_type, ieee_overflow, ieee_invalid, &
      ieee_divide_by_zero, ieee_get_halting_mode, ieee_set_halting_mode, ieee_set_flag
   implicit none
   private
   public :: sys_exit, stderr_is_terminal, sys_rename, catch_stop_signals, stop_signal
   public :: fp_traps_off, fp_traps_restore, heap_for_large_arrays
   public :: sys_lock_held, sys_write_trouble
   public :: sys_file_size, sys_lock, sys_real_path, sys_is_directory, sys_file_kind, &
      sys_same_file
   public :: file_missing, file_regular, file_folder, file_other
   integer, parameter :: file_missing = -1   !! sys_file_kind: nothing there
   integer, parameter :: file_regular = 0    !! sys_file_kind: a regular file
   integer, parameter :: file_folder = 1     !! sys_file_kind: a folder
   integer, parameter :: file_other = 2      !! sys_file_kind: a FIFO, device or socket

   type(ieee_flag_type), parameter :: read_traps(3) = [ieee_overflow, ieee_invalid, &
      ieee_divide_by_zero]

   integer(c_int), parameter :: sigint = 2_c_int, sigterm = 15_c_int   ! Linux numbers

   !> The signal that asked the run to stop (0: none). The one piece of module state in
   !> spallbar: a signal handler can reach nothing else. Written by the handler only.
   integer(c_int), volatile :: caught = 0_c_int

   public :: sys_memory_limit

   interface
      !> C _exit(2): ends the process at once, without exit handlers.
      subroutine c_exit_now(status) bind(c, name='_exit')
         import :: c_int
         implicit none
         integer(c_int), value :: status   !! exit status of the process
      end subroutine c_exit_now
      !> spb_path_query (spb_sys_c.c): a question about a path through the system (what:
      !> 0 its kind by stat(2), 1 whether another open file holds a flock on it, 2 whether its
      !> file system is read-only or full by statvfs(3)).
      function c_path_query(path, what) bind(c, name='spb_path_query') result(r)
         import :: c_char, c_int
         implicit none
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: path(*)   !! NUL-terminated path
         integer(c_int), value :: what   !! the question: 0 kind, 1 lock held, 2 file system
         integer(c_int) :: r
      end function c_path_query

      !> spb_same_file (spb_sys_c.c): whether two paths name one file, through stat(2).
      function c_same_file(a, b) bind(c, name='spb_same_file') result(r)
         import :: c_char, c_int
         implicit none
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: a(*)   !! NUL-terminated path
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: b(*)   !! NUL-terminated path
         integer(c_int) :: r
      end function c_same_file

      !> C isatty(3).
      function c_isatty(fd) bind(c, name='isatty') result(r)
         import :: c_int
         implicit none
         integer(c_int), value :: fd   !! file descriptor
         integer(c_int) :: r
      end function c_isatty
      !> C rename(2) on NUL-terminated names.
      function c_rename(old, new) bind(c, name='rename') result(r)
         import :: c_int, c_char
         implicit none
         ! C strings (char *), NUL-terminated by the caller
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: old(*)   !! existing path, NUL-terminated
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: new(*)   !! new path, NUL-terminated
         integer(c_int) :: r
      end function c_rename
      !> C mallopt(3).
      function c_mallopt(param, value) bind(c, name='mallopt') result(r)
         import :: c_int
         implicit none
         integer(c_int), value :: param   !! the parameter to set (M_*)
         integer(c_int), value :: value   !! its new value
         integer(c_int) :: r
      end function c_mallopt
      !> C fopen(3).
      function c_fopen(path, mode) bind(c, name='fopen') result(f)
         import :: c_char, c_ptr
         implicit none
         ! C strings (char *), NUL-terminated by the caller
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: path(*)   !! the file's path, NUL-terminated
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: mode(*)   !! open mode ('rb', ...), NUL-terminated
         type(c_ptr) :: f
      end function c_fopen
      !> C fseek(3).
      function c_fseek(f, offset, whence) bind(c, name='fseek') result(r)
         import :: c_ptr, c_long, c_int
         implicit none
         type(c_ptr), value :: f               !! the stream (FILE *)
         integer(c_long), value :: offset      !! offset from whence [bytes]
         integer(c_int), value :: whence       !! SEEK_SET 0, SEEK_CUR 1, SEEK_END 2
         integer(c_int) :: r
      end function c_fseek
      !> C ftell(3).
      function c_ftell(f) bind(c, name='ftell') result(r)
         import :: c_ptr, c_long
         implicit none
         type(c_ptr), value :: f   !! the stream (FILE *)
         integer(c_long) :: r
      end function c_ftell
      !> C fclose(3).
      function c_fclose(f) bind(c, name='fclose') result(r)
         import :: c_ptr, c_int
         implicit none
         type(c_ptr), value :: f   !! the stream (FILE *)
         integer(c_int) :: r
      end function c_fclose
      !> C creat(2): open (create, empty) a file for writing.
      function c_creat(path, mode) bind(c, name='creat') result(fd)
         import :: c_char, c_int
         implicit none
         ! C string (char *), NUL-terminated by the caller
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: path(*)   !! the file's path, NUL-terminated
         integer(c_int), value :: mode   !! permission bits of a new file
         integer(c_int) :: fd
      end function c_creat
      !> C flock(2).
      function c_flock(fd, operation) bind(c, name='flock') result(r)
         import :: c_int
         implicit none
         integer(c_int), value :: fd          !! file descriptor
         integer(c_int), value :: operation   !! LOCK_* flags (LOCK_EX | LOCK_NB = 6)
         integer(c_int) :: r
      end function c_flock
      !> C realpath(3) into a caller's buffer of PATH_MAX characters.
      function c_realpath(path, resolved) bind(c, name='realpath') result(r)
         import :: c_char, c_ptr
         implicit none
         ! C strings (char *): the path NUL-terminated, the buffer PATH_MAX long
         ! allow(assumed-size)
         character(kind=c_char), intent(in) :: path(*)   !! the path, NUL-terminated
         ! allow(assumed-size, assumed-size-character-intent)
         character(kind=c_char), intent(inout) :: resolved(*)   !! PATH_MAX buffer for the result
         type(c_ptr) :: r
      end function c_realpath
      !> C signal(2): install a handler.
      function c_signal(signum, handler) bind(c, name='signal') result(previous)
         import :: c_int, c_funptr
         implicit none
         integer(c_int), value :: signum     !! the signal number
         type(c_funptr), value :: handler    !! the handler (c_funloc of a bind(c) procedure)
         type(c_funptr) :: previous
      end function c_signal
   end interface

contains

   !> Large arrays from the heap, not each from its own mmap (glibc: M_MMAP_THRESHOLD = -3,
   !> raised to its largest, 32 MiB). Every mmap starts at the same offset of a 4 KiB page,
   !> so the state's arrays would share their addresses modulo 4 KiB, and a load from one
   !> stalls behind a store to another at the same index (4K aliasing): measured 20% of the
   !> stepping time of a 1e5-node bar (doc/benchmarks.md). Heap arrays lie one after the
   !> other at staggered offsets. Freed heap memory is kept for reuse up to 1 GiB
   !> (M_TRIM_THRESHOLD = -1), not handed back at each free: the characteristic steps
   !> (spb_ring) allocate and free their sequences at each event, and pages handed back
   !> fault again when they are touched anew (measured: a third of a layered bar's run,
   !> doc/benchmarks.md). A performance hint only: ignored where it fails.
   subroutine heap_for_large_arrays()
      integer(c_int) :: rc
      rc = c_mallopt(-3_c_int, 33554432_c_int)
      rc = c_mallopt(-1_c_int, 1073741824_c_int)
   end subroutine heap_for_large_arrays

   !> Terminate with an exit status and no runtime banner (error stop prints one). Every
   !> output is closed by then; standard output and error are flushed, and the process
   !> ends without the exit handlers of the libraries (_exit(2)): HDF5 1.10's handler
   !> crashes (SIGSEGV) on a file whose close failed, e.g. on a full disk.
   subroutine sys_exit(status)
      integer, intent(in) :: status   !! process exit status
      flush(output_unit)
      flush(error_unit)
      call c_exit_now(int(status, c_int))
   end subroutine sys_exit

   !> True when standard error is a terminal (progress lines go there only then).
   logical function stderr_is_terminal()
      stderr_is_terminal = c_isatty(2_c_int) == 1_c_int
   end function stderr_is_terminal

   !> Rename a file (atomic within one file system); ok is false on failure.
   subroutine sys_rename(old, new, ok)
      character(len=*), intent(in) :: old   !! existing path
      character(len=*), intent(in) :: new   !! new path (replaced if it exists)
      logical, intent(out) :: ok            !! true on success
      ok = c_rename(old // c_null_char, new // c_null_char) == 0_c_int
   end subroutine sys_rename

   !> The size of a file as the operating system has it (-1: it cannot be opened). For a
   !> file this program writes, the bytes that reached the disk: gfortran's own view of
   !> an open unit (inquire size=) counts what a full disk silently refused.
   function sys_file_size(path) result(bytes)
      character(len=*), intent(in) :: path   !! the file
      integer(int64) :: bytes
      type(c_ptr) :: f
      integer(c_int) :: rc
      bytes = -1
      f = c_fopen(path // c_null_char, 'rb' // c_null_char)
      if (.not. c_associated(f)) return
      if (c_fseek(f, 0_c_long, 2_c_int) == 0_c_int) bytes = int(c_ftell(f), int64)
      rc = c_fclose(f)
   end function sys_file_size

   !> Take an exclusive lock on path (created empty if missing) for the life of the process
   !> (flock(2), LOCK_EX | LOCK_NB). state: 0 held, 1 the file cannot be made, 2 another
   !> process holds it. The file stays; removing it would let two later runs both lock.
   subroutine sys_lock(path, state)
      character(len=*), intent(in) :: path   !! the lock file
      integer, intent(out) :: state          !! 0 held, 1 cannot be made, 2 held elsewhere
      integer(c_int) :: fd
      fd = c_creat(path // c_null_char, int(o'644', c_int))
      state = 1
      if (fd < 0_c_int) return
      state = 2
      if (c_flock(fd, 6_c_int) == 0_c_int) state = 0
   end subroutine sys_lock

   !> Whether another process (or another open file of this one) holds a flock(2) lock on
   !> path, shared or exclusive: an HDF5 reader (h5py, ParaView) or a spallbar run's lock.
   !> .false. when path is missing.
   logical function sys_lock_held(path)
      character(len=*), intent(in) :: path   !! the file
      sys_lock_held = c_path_query(path // c_null_char, 1_c_int) /= 0_c_int
   end function sys_lock_held

   !> Why the file system of path refuses writes, as words for a message: 'the file system
   !> is read-only', 'the disk is full (or over quota)', or 'full, or over quota?' when
   !> statvfs(3) shows neither.
   function sys_write_trouble(path) result(text)
      character(len=*), intent(in) :: path   !! a file on that file system
      character(len=:), allocatable :: text
      select case (c_path_query(path // c_null_char, 2_c_int))
      case (1)
         text = 'the file system is read-only'
      case (2)
         text = 'the disk is full (or over quota)'
      case default
         text = 'full, or over quota?'
      end select
   end function sys_write_trouble

   !> The absolute path with links and '..' resolved (realpath(3)) of a file that may not
   !> exist yet: its folder resolved, its name kept; path itself when the folder is missing.
   function sys_real_path(path) result(real_path)
      character(len=*), intent(in) :: path   !! a file
      character(len=:), allocatable :: real_path
      character(kind=c_char, len=4096) :: buffer
      character(len=:), allocatable :: folder, name
      integer :: k
      type(c_ptr) :: r
      k = index(path, '/', back=.true.)
      folder = '.'
      if (k == 1) folder = '/'
      if (k > 1) folder = path(:k - 1)
      name = path(k + 1:)
      real_path = path
      buffer = ''
      r = c_realpath(folder // c_null_char, buffer)
      if (.not. c_associated(r)) return
      k = index(buffer, c_null_char)
      if (k <= 1) return
      real_path = buffer(:k - 1) // '/' // name
      if (buffer(:k - 1) == '/') real_path = '/' // name
   end function sys_real_path

   !> What path names (following links): file_missing, file_regular, file_folder or
   !> file_other (a FIFO, a device, a socket: never a deck, an input or an output).
   integer function sys_file_kind(path)
      character(len=*), intent(in) :: path   !! a path
      sys_file_kind = int(c_path_query(trim(path) // c_null_char, 0_c_int))
   end function sys_file_kind

   !> Whether two paths name the same existing file (a hard link, a symbolic link or another
   !> spelling of it); false where either is missing.
   logical function sys_same_file(a, b)
      character(len=*), intent(in) :: a   !! a path
      character(len=*), intent(in) :: b   !! another path
      sys_same_file = c_same_file(trim(a) // c_null_char, trim(b) // c_null_char) /= 0
   end function sys_same_file

   !> Whether path names a folder.
   logical function sys_is_directory(path)
      character(len=*), intent(in) :: path   !! a path
      inquire(file=path // '/.', exist=sys_is_directory)
   end function sys_is_directory

   !> Hold off floating-point traps (the debug build's -ffpe-trap) while text is read: a
   !> value like 1e999 reads as +Inf, which validation then rejects with a message, instead
   !> of stopping the program inside the runtime library.
   subroutine fp_traps_off(saved)
      logical, intent(out) :: saved(3)   !! the halting modes to restore
      call ieee_get_halting_mode(read_traps, saved)
      call ieee_set_halting_mode(read_traps, .false.)
   end subroutine fp_traps_off

   !> Clear what reading raised and restore the halting modes fp_traps_off saved.
   subroutine fp_traps_restore(saved)
      logical, intent(in) :: saved(3)   !! the halting modes fp_traps_off saved
      call ieee_set_flag(read_traps, .false.)
      call ieee_set_halting_mode(read_traps, saved)
   end subroutine fp_traps_restore

   !> From now on SIGTERM and SIGINT only set a flag (stop_signal reads it): the run ends
   !> its step, writes and closes its outputs, and exits with 128 + the signal number.
   subroutine catch_stop_signals()
      type(c_funptr) :: previous
      previous = c_signal(sigterm, c_funloc(on_signal))
      previous = c_signal(sigint, c_funloc(on_signal))
   end subroutine catch_stop_signals

   !> The signal caught since catch_stop_signals (0: none).
   integer function stop_signal()
      stop_signal = int(caught)
   end function stop_signal

   !> The handler of SIGTERM/SIGINT: remembers the signal (the run stops at the next step).
   subroutine on_signal(signum) bind(c)
      integer(c_int), value :: signum   !! the signal number
      caught = signum
   end subroutine on_signal

   !> The memory this process may use [bytes]: the physical memory (sysconf(3)
   !> _SC_PHYS_PAGES x _SC_PAGESIZE), or the address-space limit (getrlimit(2) RLIMIT_AS,
   !> the soft limit `ulimit -v` sets), or the memory limit of its cgroup (Slurm's --mem, a
   !> container's: cgroup_memory_limit) when that is smaller; the environment variable
   !> SPALLBAR_MEMORY_LIMIT (bytes, digits only; tests) lowers it further. Linux numbers:
   !> _SC_PAGESIZE 30, _SC_PHYS_PAGES 85, RLIMIT_AS 9, RLIM_INFINITY all bits set (-1 here).
   !> huge(1_int64) when nothing is known.
   function sys_memory_limit() result(bytes)
      integer(int64) :: bytes
      interface
         !> C sysconf(3).
         function c_sysconf(name) bind(c, name='sysconf') result(r)
            import :: c_int, c_long
            implicit none
            integer(c_int), value :: name   !! the setting (_SC_*)
            integer(c_long) :: r
         end function c_sysconf
         !> C getrlimit(2): struct rlimit {rlim_t rlim_cur, rlim_max} (two unsigned longs).
         function c_getrlimit(resource, rlim) bind(c, name='getrlimit') result(r)
            import :: c_int, c_long
            implicit none
            integer(c_int), value :: resource          !! the limit (RLIMIT_*)
            integer(c_long), intent(out) :: rlim(2)    !! soft and hard limit [bytes]
            integer(c_int) :: r
         end function c_getrlimit
      end interface
      integer(c_long) :: pages, page_size, rlim(2)
      character(len=32) :: text
      integer :: length, status
      bytes = huge(1_int64)
      pages = c_sysconf(85_c_int)
      page_size = c_sysconf(30_c_int)
      if (pages > 0 .and. page_size > 0) then
         if (pages < huge(1_int64) / page_size) bytes = int(pages, int64) * int(page_size, int64)
      end if
      if (c_getrlimit(9_c_int, rlim) == 0_c_int) then
         if (rlim(1) > 0) bytes = min(bytes, int(rlim(1), int64))
      end if
      bytes = min(bytes, cgroup_memory_limit())
      call get_environment_variable('SPALLBAR_MEMORY_LIMIT', text, length, status)
      if (status == 0) bytes = min(bytes, bytes_of(text))
   end function sys_memory_limit

   !> The bytes a text of digits says (at most 18 of them, blanks around), huge(1_int64) for
   !> any other text: blank, 'max', a sign, 19 digits or more (cgroup v1's "no limit" is
   !> 9223372036854771712), 0.
   pure function bytes_of(text) result(bytes)
      character(len=*), intent(in) :: text   !! the text
      integer(int64) :: bytes
      integer(int64) :: value
      integer :: ios
      bytes = huge(1_int64)
      if (len_trim(adjustl(text)) < 1 .or. len_trim(adjustl(text)) > 18) return
      if (verify(trim(adjustl(text)), '0123456789') /= 0) return
      read(text, *, iostat=ios) value
      if (ios == 0 .and. value > 0) bytes = value
   end function bytes_of

   !> The memory limit of the cgroup this process is in [bytes], huge(1_int64) when there is
   !> none or nothing can be read: the smallest of its cgroup's and every cgroup's above it
   !> up to the mount's root, memory.max (cgroup v2; 'max': none) or memory.limit_in_bytes
   !> (v1), as Slurm (--mem, ConstrainRAMSpace) and container runtimes set them, and beyond
   !> which the kernel kills the process without a word. The cgroup's path
   !> (/proc/self/cgroup: '0::PATH' for v2, 'N:...,memory,...:PATH' for v1) is taken relative
   !> to the root of the mount that holds the hierarchy (/proc/self/mountinfo: fstype
   !> cgroup2, or cgroup with the memory option), as inside a container whose view starts at
   !> its own cgroup. Both versions are read (a hybrid system mounts both; the one without
   !> the memory controller has no such files).
   function cgroup_memory_limit() result(bytes)
      integer(int64) :: bytes
      character(len=4096) :: mount(2), root(2), path(2)   ! v1 memory (1), v2 (2)
      character(len=4096), allocatable :: lines(:)
      character(len=:), allocatable :: rel
      integer :: v, k
      character(len=*), parameter :: files(2) = [character(len=21) :: 'memory.limit_in_bytes', &
                                                 'memory.max']
      bytes = huge(1_int64)
      mount = ''
      root = ''
      path = ''
      ! the process's cgroup in each hierarchy; the mount of each that holds it: of several,
      ! the one whose root is the longest prefix of the process's path (a mount of another
      ! part of the hierarchy holds other cgroups' files)
      if (.not. text_lines('/proc/self/cgroup', lines)) return
      do k = 1, size(lines)
         call cgroup_line(lines(k))
      end do
      if (.not. text_lines('/proc/self/mountinfo', lines)) return
      do k = 1, size(lines)
         call mount_line(lines(k))
      end do
      do v = 1, 2
         if (len_trim(mount(v)) == 0 .or. len_trim(path(v)) == 0) cycle
         rel = trim(path(v))
         if (trim(root(v)) /= '/') rel = rel(len_trim(root(v)) + 1:)
         ! the cgroup and each one above it, up to the mount's root
         do
            if (len(rel) > 0) then
               if (rel(len(rel):len(rel)) == '/') rel = rel(:len(rel) - 1)
            end if
            bytes = min(bytes, limit_file(trim(mount(v)) // rel // '/' // trim(files(v))))
            if (len(rel) == 0) exit
            k = index(rel, '/', back=.true.)
            rel = rel(:max(k - 1, 0))
         end do
      end do
   contains
      !> One line of /proc/self/mountinfo: 'ID PARENT MAJ:MIN ROOT MOUNTPOINT OPTIONS... -
      !> FSTYPE SOURCE SUPEROPTIONS': a mount of hierarchy v whose root holds the process's
      !> path, kept when its root is longer than the one kept before.
      subroutine mount_line(text)
         character(len=*), intent(in) :: text   !! the line
         character(len=:), allocatable :: fstype, super, r
         integer :: dash, v
         dash = index(text, ' - ')
         if (dash == 0) return
         fstype = word(text(dash + 3:), 1)
         super = word(text(dash + 3:), 3)
         if (fstype == 'cgroup2') then
            v = 2
         else if (fstype == 'cgroup' .and. index(',' // super // ',', ',memory,') > 0) then
            v = 1
         else
            return
         end if
         if (len_trim(path(v)) == 0) return
         r = word(text(:dash), 4)
         if (r /= '/' .and. index(trim(path(v)) // '/', r // '/') /= 1) return
         if (len_trim(mount(v)) > 0 .and. len(r) <= len_trim(root(v))) return
         mount(v) = word(text(:dash), 5)
         root(v) = r
      end subroutine mount_line
      !> One line of /proc/self/cgroup: 'ID:CONTROLLERS:PATH'.
      subroutine cgroup_line(text)
         character(len=*), intent(in) :: text   !! the line
         integer :: c1, c2
         c1 = index(text, ':')
         if (c1 == 0) return
         c2 = c1 + index(text(c1 + 1:), ':')
         if (c2 == c1) return
         if (text(:c1 - 1) == '0' .and. c2 == c1 + 1) then
            path(2) = text(c2 + 1:)
         else if (index(',' // text(c1 + 1:c2 - 1) // ',', ',memory,') > 0) then
            path(1) = text(c2 + 1:)
         end if
      end subroutine cgroup_line
   end function cgroup_memory_limit

   !> Whether the text file name could be read, and its lines (up to 4096 characters each;
   !> at most 4096 lines: /proc/self's files hold a few dozen).
   logical function text_lines(name, lines) result(ok)
      character(len=*), intent(in) :: name   !! the file
      character(len=4096), allocatable, intent(out) :: lines(:)   !! its lines
      character(len=4096) :: line
      integer :: u, ios, n, k
      allocate(lines(0))
      open(newunit=u, file=name, action='read', status='old', iostat=ios)
      ok = ios == 0
      if (.not. ok) return
      ! counted first, then read again into their array
      n = 0
      do while (n < 4096)
         read(u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         n = n + 1
      end do
      deallocate(lines)
      allocate(lines(n))
      rewind(u)
      do k = 1, n
         read(u, '(a)', iostat=ios) lines(k)
         if (ios /= 0) lines(k) = ''
      end do
      close(u)
   end function text_lines

   !> The n-th word of a line of words separated by blanks ('' when it has fewer).
   pure function word(text, n) result(w)
      character(len=*), intent(in) :: text   !! the line
      integer, intent(in) :: n               !! which word, from 1
      character(len=:), allocatable :: w
      integer :: k, first, found
      w = ''
      found = 0
      k = 1
      do while (k <= len(text))
         if (text(k:k) == ' ') then
            k = k + 1
            cycle
         end if
         first = k
         do while (k <= len(text))
            if (text(k:k) == ' ') exit
            k = k + 1
         end do
         found = found + 1
         if (found == n) then
            w = text(first:k - 1)
            return
         end if
      end do
   end function word

   !> The limit a cgroup file holds [bytes]: a number of bytes, or huge(1_int64) for 'max',
   !> nothing, or a file that cannot be read.
   function limit_file(name) result(bytes)
      character(len=*), intent(in) :: name   !! the file
      integer(int64) :: bytes
      character(len=64) :: text
      integer :: u, ios
      bytes = huge(1_int64)
      open(newunit=u, file=name, action='read', status='old', iostat=ios)
      if (ios /= 0) return
      read(u, '(a)', iostat=ios) text
      close(u)
      if (ios == 0) bytes = bytes_of(text)
   end function limit_file
end module spb_sys
