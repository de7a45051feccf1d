!> PREFIX.h5 (layout in doc/outputs.md): the only module that uses HDF5.
!>
!> An opaque file type with open / write / flush / close. Tables (the history, the events)
!> are groups of one extendible 1-D dataset per column, chunked and deflated, appended
!> through a row buffer; the x-t fields are extendible 2-D datasets (rows of the half-node
!> layout x snapshots; the gauges: gauges x rows). flush writes the buffers and calls H5Fflush: a run killed after a
!> flush leaves a file that reads up to it. Every hdferr goes through check(), which names
!> the operation, the file and the object. h5py sees a Fortran a(nx, nt) as (nt, nx).
module spb_hdf5
   use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5fcreate_f, h5fopen_f, h5fclose_f, h5fflush_f, &
      h5gcreate_f, h5gopen_f, h5gclose_f, h5screate_f, h5screate_simple_f, h5sclose_f, &
      h5sselect_hyperslab_f, h5pcreate_f, h5pset_chunk_f, h5pset_deflate_f, h5pclose_f, &
      h5dcreate_f, h5dopen_f, h5dclose_f, h5dwrite_f, h5dread_f, h5dget_space_f, &
      h5dset_extent_f, h5sget_simple_extent_dims_f, h5acreate_f, h5awrite_f, h5aclose_f, &
      h5tcopy_f, h5tset_size_f, h5tclose_f, h5tenum_create_f, h5tenum_insert_f, h5lexists_f, h5oopen_f, h5oclose_f, h5eset_auto_f, &
      h5aopen_f, h5aread_f, h5aget_type_f, h5tget_size_f, h5aexists_f, h5ocopy_f, &
      h5tget_class_f, h5tis_variable_str_f, H5T_STRING_F, h5aget_space_f, &
      h5sget_simple_extent_npoints_f, &
      h5get_libversion_f, H5F_ACC_TRUNC_F, H5F_ACC_RDONLY_F, H5F_SCOPE_GLOBAL_F, H5S_SCALAR_F, H5S_UNLIMITED_F, &
      H5S_SELECT_SET_F, H5P_DATASET_CREATE_F, H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, &
      H5T_NATIVE_CHARACTER, H5P_FILE_CREATE_F
   use, intrinsic :: iso_c_binding, only: c_int, c_bool, c_int64_t, c_long_long
   use spb_kinds, only: wp
   use spb_strings, only: itoa
   use spb_sys, only: sys_lock_held
   implicit none
   private
   public :: h5_library_version
   public :: h5file_t, h5_create, h5_close, h5_flush, h5_attr, h5_group, h5_write, h5_table, &
      h5_append, h5_xt, h5_append_xt, h5_read, h5_read_size
   public :: h5_open_read, h5_get, h5_get_attr, h5_get_columns, h5_copy, h5_table_rows, &
      h5_xt_rows, xt_fields, xt_gauges, h5_exists, h5_has_attr, block_name, buffer_rows

   integer, parameter :: buffer_rows = 1024     !! rows held before a table is written
   integer, parameter :: xt_fields = 1          !! the x-t fields (/fields/xt)
   integer, parameter :: xt_gauges = 2          !! the gauges (/gauges)
   integer, parameter :: deflate_level = 4
   integer(c_int), parameter :: fspace_strategy_none = 3   !! H5F_FSPACE_STRATEGY_NONE

   interface
      !> C API (the 1.10 Fortran API lacks it): how the file reuses freed space.
      function h5pset_file_space_strategy(fcpl, strategy, persist, threshold) &
            bind(c, name='H5Pset_file_space_strategy') result(status)
         import :: c_int, c_bool, c_int64_t, c_long_long
         implicit none
         integer(c_int64_t), value :: fcpl           !! file creation property list (hid_t)
         integer(c_int), value :: strategy           !! H5F_fspace_strategy_t (3: none)
         logical(c_bool), value :: persist           !! keep free-space information in the file
         integer(c_long_long), value :: threshold    !! hsize_t: smallest section tracked [bytes]
         integer(c_int) :: status
      end function h5pset_file_space_strategy
   end interface

   !> One table: a group with one extendible dataset per column.
   type :: table_t
      character(len=:), allocatable :: path     !! e.g. '/history'
      integer(hid_t), allocatable :: dset(:)
      logical, allocatable :: is_int(:)
      real(wp), allocatable :: buf(:, :)        !! (columns, buffer_rows)
      integer :: nbuf = 0
      integer(hsize_t) :: rows = 0              !! rows in the file
   end type table_t

   !> Rows of a quantity at each time: datasets t(nt) and three (nrow, nt) ones (the x-t
   !> fields u, v, stress; the gauges' stress, velocity, u).
   type :: xt_t
      integer(hid_t) :: dset(4) = -1
      integer :: nrow = 0                       !! rows per time (0: not created)
      real(wp), allocatable :: buf(:, :, :)     !! (nrow, 3, buffer) for u, v, stress
      real(wp), allocatable :: tbuf(:)
      integer :: nbuf = 0
      integer(hsize_t) :: rows = 0
   end type xt_t

   type :: h5file_t
      character(len=:), allocatable :: path
      integer(hid_t) :: file = -1
      type(table_t), allocatable :: tables(:)
      type(xt_t) :: xt(2)                       !! xt_fields, xt_gauges
      logical :: read_only = .false.            !! opened by h5_open_read
      character(len=:), allocatable :: error    !! first failure, if any
   end type h5file_t

   !> An attribute being written: the object it belongs to, its dataspace and itself.
   type :: attr_t
      integer(hid_t) :: obj = -1                !! the group or dataset
      integer(hid_t) :: space = -1              !! its dataspace
      integer(hid_t) :: attr = -1               !! the attribute (< 0: not created)
      integer(hsize_t) :: dims(1) = 1           !! its elements (1 for a scalar)
      character(len=:), allocatable :: what     !! 'path:name', for messages
   end type attr_t

   interface h5_attr
      module procedure attr_string, attr_real, attr_int, attr_reals, attr_strings, attr_ints, &
         attr_logical, attr_logicals
   end interface h5_attr

   interface h5_write
      module procedure write_real_1d, write_int_1d, write_int_2d
   end interface h5_write

   interface h5_get
      module procedure get_real_1d
   end interface h5_get

   interface h5_get_attr
      module procedure get_attr_real, get_attr_int, get_attr_string
   end interface h5_get_attr

contains

   !> Record the first failure of an HDF5 call.
   subroutine check(h5, hdferr, what)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      integer, intent(in) :: hdferr             !! status of the HDF5 call (< 0: it failed)
      character(len=*), intent(in) :: what      !! operation and object
      if (hdferr < 0 .and. .not. allocated(h5%error)) then
         h5%error = 'HDF5: ' // what // ' failed in ''' // h5%path // ''''
      end if
   end subroutine check

   !> Create (truncate) the file.
   subroutine h5_create(h5, path)
      type(h5file_t), intent(out) :: h5    !! the HDF5 file
      character(len=*), intent(in) :: path   !! the file
      integer :: hdferr
      integer(hid_t) :: fcpl
      h5%path = path
      allocate(h5%tables(0))
      call h5open_f(hdferr)
      call check(h5, hdferr, 'h5open_f')
      ! failures are reported once, through check(), not by the library's own printing
      call h5eset_auto_f(0, hdferr)
      ! Freed file space is never reused: a table chunk that grows on rewrite moves, and its
      ! old copy stays intact, so the index written at the last flush still points at valid
      ! data when the run is killed (SIGKILL) before the next one. Costs a little file size.
      call h5pcreate_f(H5P_FILE_CREATE_F, fcpl, hdferr)
      call check(h5, hdferr, 'h5pcreate_f (file creation)')
      if (h5pset_file_space_strategy(int(fcpl, c_int64_t), fspace_strategy_none, &
                                     .false._c_bool, 1_c_long_long) < 0) call check(h5, -1, &
                                     'H5Pset_file_space_strategy')
      call h5fcreate_f(path, H5F_ACC_TRUNC_F, h5%file, hdferr, creation_prp=fcpl)
      ! HDF5 locks a file it opens (flock): a reader that holds this one is the likely cause
      if (hdferr < 0 .and. sys_lock_held(path)) call check(h5, hdferr, 'h5fcreate_f (another ' // &
         'process holds the file open, e.g. h5py, a notebook or ParaView: close it)')
      call check(h5, hdferr, 'h5fcreate_f')
      call h5pclose_f(fcpl, hdferr)
      if (hdferr < 0) h5%file = -1
   end subroutine h5_create

   !> Create the group path (its parent must exist).
   subroutine h5_group(h5, path)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer(hid_t) :: g
      integer :: hdferr
      if (h5%file < 0) return
      call h5gcreate_f(h5%file, path, g, hdferr)
      call check(h5, hdferr, 'h5gcreate_f ' // path)
      if (hdferr >= 0) call h5gclose_f(g, hdferr)
   end subroutine h5_group

   !> Open a group or dataset path for attributes.
   subroutine open_obj(h5, path, obj, is_dset)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer(hid_t), intent(out) :: obj   !! an open group or dataset
      logical, intent(out) :: is_dset      !! always .false. (h5oopen_f opens either kind)
      integer :: hdferr
      is_dset = .false.
      call h5oopen_f(h5%file, path, obj, hdferr)
      call check(h5, hdferr, 'h5oopen_f ' // path)
   end subroutine open_obj

   !> Close a group or dataset opened by open_obj.
   subroutine close_obj(obj)
      integer(hid_t), intent(in) :: obj        !! a group or dataset opened by open_obj
      integer :: hdferr
      call h5oclose_f(obj, hdferr)
   end subroutine close_obj

   !> Open the object at path and create its attribute name of type atype, a scalar
   !> (n < 0) or a 1-D array of n elements (n = 0: an empty one); a%attr < 0 when that
   !> failed (recorded by check) or the file is not open.
   subroutine attr_begin(h5, path, name, atype, n, a)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      integer(hid_t), intent(in) :: atype    !! its datatype
      integer, intent(in) :: n               !! elements (< 0: a scalar)
      type(attr_t), intent(out) :: a         !! the attribute
      integer :: hdferr
      a%what = path // ':' // name
      if (h5%file < 0) return
      call h5oopen_f(h5%file, path, a%obj, hdferr)
      call check(h5, hdferr, 'h5oopen_f ' // path)
      if (hdferr < 0) a%obj = -1
      if (allocated(h5%error)) return
      if (n < 0) then
         call h5screate_f(H5S_SCALAR_F, a%space, hdferr)
      else
         a%dims = int(n, hsize_t)
         call h5screate_simple_f(1, a%dims, a%space, hdferr)
      end if
      call check(h5, hdferr, 'h5screate_f ' // a%what)
      if (hdferr < 0) return
      call h5acreate_f(a%obj, name, atype, a%space, a%attr, hdferr)
      call check(h5, hdferr, 'h5acreate_f ' // a%what)
      if (hdferr < 0) a%attr = -1
   end subroutine attr_begin

   !> Check the write of an attribute begun by attr_begin, then close what it opened.
   subroutine attr_end(h5, a, hdferr)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      type(attr_t), intent(inout) :: a      !! the attribute
      integer, intent(in) :: hdferr         !! status of its h5awrite_f
      integer :: ignored
      if (a%attr >= 0) then
         call check(h5, hdferr, 'h5awrite_f ' // a%what)
         call h5aclose_f(a%attr, ignored)
      end if
      if (a%space >= 0) call h5sclose_f(a%space, ignored)
      if (a%obj >= 0) call close_obj(a%obj)
   end subroutine attr_end

   !> A string attribute of the object at path.
   subroutine attr_string(h5, path, name, value)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      character(len=*), intent(in) :: value   !! its value
      character(len=max(1, len(value))) :: text   ! an empty value is stored as one blank
      text = value
      call attr_texts(h5, path, name, [text], -1)
   end subroutine attr_string

   !> A 1-D string attribute of the object at path (every element as long as the longest,
   !> at least one character).
   subroutine attr_strings(h5, path, name, values)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      character(len=*), intent(in) :: values(:)   !! its values
      character(len=max(1, maxval([0, len_trim(values)]))) :: texts(size(values))
      texts = values
      call attr_texts(h5, path, name, texts, size(values))
   end subroutine attr_strings

   !> Strings of one length as a scalar (n < 0: texts(1)) or 1-D attribute.
   subroutine attr_texts(h5, path, name, texts, n)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      character(len=*), intent(in) :: texts(:)   !! the values, of length >= 1
      integer, intent(in) :: n               !! elements (< 0: a scalar)
      type(attr_t) :: a
      integer(hid_t) :: atype
      integer :: hdferr, ignored
      if (h5%file < 0) return
      call h5tcopy_f(H5T_NATIVE_CHARACTER, atype, hdferr)
      call h5tset_size_f(atype, int(len(texts), size_t), hdferr)
      call attr_begin(h5, path, name, atype, n, a)
      hdferr = 0
      if (a%attr >= 0) call h5awrite_f(a%attr, atype, texts, a%dims, hdferr)
      call attr_end(h5, a, hdferr)
      call h5tclose_f(atype, ignored)
   end subroutine attr_texts

   !> A real attribute of the object at path.
   subroutine attr_real(h5, path, name, value)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      real(wp), intent(in) :: value        !! its value
      type(attr_t) :: a
      integer :: hdferr
      call attr_begin(h5, path, name, H5T_NATIVE_DOUBLE, -1, a)
      hdferr = 0
      if (a%attr >= 0) call h5awrite_f(a%attr, H5T_NATIVE_DOUBLE, value, a%dims, hdferr)
      call attr_end(h5, a, hdferr)
   end subroutine attr_real

   !> A 1-D real attribute of the object at path.
   subroutine attr_reals(h5, path, name, values)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      real(wp), intent(in) :: values(:)    !! its values
      type(attr_t) :: a
      integer :: hdferr
      call attr_begin(h5, path, name, H5T_NATIVE_DOUBLE, size(values), a)
      hdferr = 0
      if (a%attr >= 0) call h5awrite_f(a%attr, H5T_NATIVE_DOUBLE, values, a%dims, hdferr)
      call attr_end(h5, a, hdferr)
   end subroutine attr_reals

   !> An integer attribute of the object at path.
   subroutine attr_int(h5, path, name, value)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      integer, intent(in) :: value         !! its value
      call attr_int_as(h5, path, name, [value], -1, H5T_NATIVE_INTEGER)
   end subroutine attr_int

   !> A 1-D integer attribute of the object at path.
   subroutine attr_ints(h5, path, name, values)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      integer, intent(in) :: values(:)     !! its values
      call attr_int_as(h5, path, name, values, size(values), H5T_NATIVE_INTEGER)
   end subroutine attr_ints

   !> A logical attribute of the object at path: the enumeration FALSE = 0, TRUE = 1 over a
   !> native integer, which h5py reads as numpy.bool_ (h5dump shows FALSE or TRUE).
   subroutine attr_logical(h5, path, name, value)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      logical, intent(in) :: value         !! its value
      call attr_bools(h5, path, name, [value], -1)
   end subroutine attr_logical

   !> A 1-D logical attribute of the object at path (the enumeration of attr_logical).
   subroutine attr_logicals(h5, path, name, values)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      logical, intent(in) :: values(:)     !! its values
      call attr_bools(h5, path, name, values, size(values))
   end subroutine attr_logicals

   !> Logicals as the FALSE/TRUE enumeration, a scalar (n < 0: values(1)) or 1-D.
   subroutine attr_bools(h5, path, name, values, n)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      logical, intent(in) :: values(:)     !! the values
      integer, intent(in) :: n             !! elements (< 0: a scalar)
      integer(hid_t) :: atype
      integer :: hdferr, ignored
      if (h5%file < 0) return
      call h5tenum_create_f(H5T_NATIVE_INTEGER, atype, hdferr)
      call check(h5, hdferr, 'h5tenum_create_f ' // path // ':' // name)
      if (hdferr < 0) return
      call h5tenum_insert_f(atype, 'FALSE', 0, hdferr)
      call check(h5, hdferr, 'h5tenum_insert_f FALSE ' // path // ':' // name)
      call h5tenum_insert_f(atype, 'TRUE', 1, hdferr)
      call check(h5, hdferr, 'h5tenum_insert_f TRUE ' // path // ':' // name)
      call attr_int_as(h5, path, name, merge(1, 0, values), n, atype)
      call h5tclose_f(atype, ignored)
   end subroutine attr_bools

   !> Integers as an attribute of type atype (native integers or an enumeration over them),
   !> a scalar (n < 0: values(1)) or 1-D.
   subroutine attr_int_as(h5, path, name, values, n, atype)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      integer, intent(in) :: values(:)     !! the values
      integer, intent(in) :: n             !! elements (< 0: a scalar)
      integer(hid_t), intent(in) :: atype  !! the datatype in the file and in memory
      type(attr_t) :: a
      integer :: hdferr
      call attr_begin(h5, path, name, atype, n, a)
      hdferr = 0
      if (a%attr >= 0) call h5awrite_f(a%attr, atype, values, a%dims, hdferr)
      call attr_end(h5, a, hdferr)
   end subroutine attr_int_as

   !> A fixed 1-D dataset with a units attribute.
   subroutine write_real_1d(h5, path, values, units)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: units   !! unit of the data
      real(wp), intent(in) :: values(:)    !! the data
      integer(hid_t) :: space, dset
      integer(hsize_t) :: dims(1)
      integer :: hdferr
      if (h5%file < 0) return
      dims = size(values)
      call h5screate_simple_f(1, dims, space, hdferr)
      call h5dcreate_f(h5%file, path, H5T_NATIVE_DOUBLE, space, dset, hdferr)
      call check(h5, hdferr, 'h5dcreate_f ' // path)
      if (hdferr >= 0) then
         call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, values, dims, hdferr)
         call check(h5, hdferr, 'h5dwrite_f ' // path)
         call h5dclose_f(dset, hdferr)
      end if
      call h5sclose_f(space, hdferr)
      call attr_string(h5, path, 'units', units)
   end subroutine write_real_1d

   !> A 1-D integer dataset with its units attribute.
   subroutine write_int_1d(h5, path, values, units)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: units   !! unit of the data
      integer, intent(in) :: values(:)     !! the data
      call write_int_shaped(h5, path, values, [size(values, kind=hsize_t)], units)
   end subroutine write_int_1d

   !> A fixed 2-D integer dataset values(nx, ny) (h5py: shape (ny, nx)) with units.
   subroutine write_int_2d(h5, path, values, units)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: units   !! unit of the data
      integer, intent(in) :: values(:, :)   !! the data
      call write_int_shaped(h5, path, reshape(values, [size(values)]), &
                            shape(values, kind=hsize_t), units)
   end subroutine write_int_2d

   !> An integer dataset of the given dims from its values in Fortran (column-major) order.
   subroutine write_int_shaped(h5, path, values, dims, units)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: units   !! unit of the data
      integer, intent(in) :: values(:)     !! the data
      integer(hsize_t), intent(in) :: dims(:)   !! the dataset's dimensions (Fortran order)
      integer(hid_t) :: space, dset
      integer :: hdferr
      if (h5%file < 0) return
      call h5screate_simple_f(size(dims), dims, space, hdferr)
      call h5dcreate_f(h5%file, path, H5T_NATIVE_INTEGER, space, dset, hdferr)
      call check(h5, hdferr, 'h5dcreate_f ' // path)
      if (hdferr >= 0) then
         call h5dwrite_f(dset, H5T_NATIVE_INTEGER, values, dims, hdferr)
         call check(h5, hdferr, 'h5dwrite_f ' // path)
         call h5dclose_f(dset, hdferr)
      end if
      call h5sclose_f(space, hdferr)
      call attr_string(h5, path, 'units', units)
   end subroutine write_int_shaped

   !> An extendible, chunked, deflated dataset of rank 1 (nrow = 0) or 2 (nrow rows).
   subroutine create_extendible(h5, path, dtype, nrow, dset)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer(hid_t), intent(in) :: dtype  !! HDF5 type of the elements
      integer, intent(in) :: nrow          !! rows of a 2-D dataset (0: 1-D)
      integer(hid_t), intent(out) :: dset  !! the open dataset (-1: not created)
      integer(hid_t) :: space, plist
      integer(hsize_t) :: dims(2), maxdims(2), chunk(2)
      integer :: hdferr, rank
      dset = -1
      if (nrow == 0) then
         rank = 1
         dims = [0_hsize_t, 0_hsize_t]
         maxdims = [H5S_UNLIMITED_F, 0_hsize_t]
         chunk = [int(buffer_rows, hsize_t), 1_hsize_t]
      else
         rank = 2
         dims = [int(nrow, hsize_t), 0_hsize_t]
         maxdims = [int(nrow, hsize_t), H5S_UNLIMITED_F]
         chunk = [int(nrow, hsize_t), int(max(1, min(64, 262144 / max(nrow, 1))), hsize_t)]
      end if
      call h5screate_simple_f(rank, dims(1:rank), space, hdferr, maxdims(1:rank))
      call h5pcreate_f(H5P_DATASET_CREATE_F, plist, hdferr)
      call h5pset_chunk_f(plist, rank, chunk(1:rank), hdferr)
      call h5pset_deflate_f(plist, deflate_level, hdferr)
      call h5dcreate_f(h5%file, path, dtype, space, dset, hdferr, plist)
      call check(h5, hdferr, 'h5dcreate_f ' // path)
      call h5pclose_f(plist, hdferr)
      call h5sclose_f(space, hdferr)
   end subroutine create_extendible

   !> A table: group path with one extendible column per name; returns its handle.
   subroutine h5_table(h5, path, names, units, is_int, handle)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: names(:)   !! column names
      character(len=*), intent(in) :: units(:)   !! unit of the data
      logical, intent(in) :: is_int(:)     !! the column is stored as integers
      integer, intent(out) :: handle       !! table handle (h5_table)
      type(table_t) :: tab
      integer :: k
      handle = 0
      if (h5%file < 0) return
      call h5_group(h5, path)
      tab%path = path
      allocate(tab%dset(size(names)), tab%is_int(size(names)))
      allocate(tab%buf(size(names), buffer_rows))
      tab%is_int = is_int
      do k = 1, size(names)
         if (is_int(k)) then
            call create_extendible(h5, path // '/' // trim(names(k)), H5T_NATIVE_INTEGER, 0, tab%dset(k))
         else
            call create_extendible(h5, path // '/' // trim(names(k)), H5T_NATIVE_DOUBLE, 0, tab%dset(k))
         end if
         call attr_string(h5, path // '/' // trim(names(k)), 'units', trim(units(k)))
      end do
      h5%tables = [h5%tables, tab]
      handle = size(h5%tables)
   end subroutine h5_table

   !> Append one row to a table (buffered).
   subroutine h5_append(h5, handle, row)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      integer, intent(in) :: handle        !! table handle (h5_table)
      real(wp), intent(in) :: row(:)       !! one value per column
      if (h5%file < 0 .or. handle < 1) return
      associate (tab => h5%tables(handle))
         tab%nbuf = tab%nbuf + 1
         tab%buf(:, tab%nbuf) = row
      end associate
      if (h5%tables(handle)%nbuf == buffer_rows) call write_table(h5, handle)
   end subroutine h5_append

   !> Write the buffered rows of table handle to its datasets.
   subroutine write_table(h5, handle)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      integer, intent(in) :: handle        !! table handle (h5_table)
      integer(hid_t) :: fspace, mspace
      integer(hsize_t) :: off(1), cnt(1), newsize(1)
      integer :: k, hdferr
      real(wp) :: col(h5%tables(handle)%nbuf)
      integer :: icol(h5%tables(handle)%nbuf)
      associate (tab => h5%tables(handle))
         if (tab%nbuf == 0) return
         cnt = tab%nbuf
         off = tab%rows
         newsize = tab%rows + cnt
         do k = 1, size(tab%dset)
            call h5dset_extent_f(tab%dset(k), newsize, hdferr)
            call check(h5, hdferr, 'h5dset_extent_f ' // tab%path)
            call h5dget_space_f(tab%dset(k), fspace, hdferr)
            call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, off, cnt, hdferr)
            call h5screate_simple_f(1, cnt, mspace, hdferr)
            if (tab%is_int(k)) then
               icol = nint(tab%buf(k, 1:tab%nbuf))
               call h5dwrite_f(tab%dset(k), H5T_NATIVE_INTEGER, icol, cnt, hdferr, &
                               mem_space_id=mspace, file_space_id=fspace)
            else
               col = tab%buf(k, 1:tab%nbuf)
               call h5dwrite_f(tab%dset(k), H5T_NATIVE_DOUBLE, col, cnt, hdferr, &
                               mem_space_id=mspace, file_space_id=fspace)
            end if
            call check(h5, hdferr, 'h5dwrite_f ' // tab%path)
            call h5sclose_f(mspace, hdferr)
            call h5sclose_f(fspace, hdferr)
         end do
         tab%rows = newsize(1)
         tab%nbuf = 0
      end associate
   end subroutine write_table

   !> Rows per time under path: t(nt) and three (nrow, nt) datasets, with units: the x-t
   !> fields (which = xt_fields: u, v, stress by default) or the gauges (xt_gauges); rows
   !> times are buffered before they are written (64 unless memory is short; spb_sim).
   subroutine h5_xt(h5, path, nrow, which, names, units, rows)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer, intent(in) :: nrow          !! rows per time (half nodes, gauges)
      integer, intent(in), optional :: which   !! xt_fields (default) or xt_gauges
      character(len=*), intent(in), optional :: names(3)   !! the datasets' names
      character(len=*), intent(in), optional :: units(3)   !! their units
      integer, intent(in), optional :: rows    !! times buffered (>= 1; default 64)
      character(len=8) :: nm(3), un(3)
      integer :: k, w, nb
      if (h5%file < 0) return
      w = xt_fields
      if (present(which)) w = which
      nm = [character(len=8) :: 'u', 'v', 'stress']
      un = [character(len=8) :: 'm', 'm/s', 'Pa']
      if (present(names)) nm = names
      if (present(units)) un = units
      call h5_group(h5, path)
      nb = 64
      if (present(rows)) nb = max(1, rows)
      associate (xt => h5%xt(w))
         xt%nrow = nrow
         allocate(xt%buf(nrow, 3, nb), xt%tbuf(nb))
         call create_extendible(h5, path // '/t', H5T_NATIVE_DOUBLE, 0, xt%dset(4))
         call attr_string(h5, path // '/t', 'units', 's')
         do k = 1, 3
            call create_extendible(h5, path // '/' // trim(nm(k)), H5T_NATIVE_DOUBLE, nrow, &
                                   xt%dset(k))
            call attr_string(h5, path // '/' // trim(nm(k)), 'units', trim(un(k)))
         end do
      end associate
   end subroutine h5_xt

   !> Append one row of times (time, and the three quantities of every row).
   subroutine h5_append_xt(h5, t, u, v, s, which)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      real(wp), intent(in) :: t                !! [s]
      real(wp), intent(in) :: u(:)             !! displacement per half-node row [m] (gauges:
                                               !! stress [Pa])
      real(wp), intent(in) :: v(:)             !! velocity per row [m/s]
      real(wp), intent(in) :: s(:)             !! stress per half-node row [Pa] (gauges:
                                               !! displacement [m])
      integer, intent(in), optional :: which   !! xt_fields (default) or xt_gauges
      integer :: w
      w = xt_fields
      if (present(which)) w = which
      if (h5%file < 0 .or. h5%xt(w)%nrow == 0) return
      associate (xt => h5%xt(w))
         xt%nbuf = xt%nbuf + 1
         xt%tbuf(xt%nbuf) = t
         xt%buf(:, 1, xt%nbuf) = u
         xt%buf(:, 2, xt%nbuf) = v
         xt%buf(:, 3, xt%nbuf) = s
      end associate
      if (h5%xt(w)%nbuf == size(h5%xt(w)%tbuf)) call write_xt(h5, w)
   end subroutine h5_append_xt

   !> Write the buffered rows of one set of x-t datasets.
   subroutine write_xt(h5, w)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      integer, intent(in) :: w             !! xt_fields or xt_gauges
      integer(hid_t) :: fspace, mspace
      integer(hsize_t) :: off2(2), cnt2(2), size2(2), off1(1), cnt1(1)
      integer :: k, hdferr, nb
      real(wp) :: block(h5%xt(w)%nrow, h5%xt(w)%nbuf), tcol(h5%xt(w)%nbuf)
      associate (xt => h5%xt(w))
         nb = xt%nbuf
         if (nb == 0) return
         size2 = [int(xt%nrow, hsize_t), xt%rows + nb]
         off2 = [0_hsize_t, xt%rows]
         cnt2 = [int(xt%nrow, hsize_t), int(nb, hsize_t)]
         do k = 1, 3
            call h5dset_extent_f(xt%dset(k), size2, hdferr)
            call check(h5, hdferr, 'h5dset_extent_f x-t field')
            call h5dget_space_f(xt%dset(k), fspace, hdferr)
            call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, off2, cnt2, hdferr)
            call h5screate_simple_f(2, cnt2, mspace, hdferr)
            block = xt%buf(:, k, 1:nb)
            call h5dwrite_f(xt%dset(k), H5T_NATIVE_DOUBLE, block, cnt2, hdferr, &
                            mem_space_id=mspace, file_space_id=fspace)
            call check(h5, hdferr, 'h5dwrite_f x-t field')
            call h5sclose_f(mspace, hdferr)
            call h5sclose_f(fspace, hdferr)
         end do
         off1 = xt%rows
         cnt1 = nb
         call h5dset_extent_f(xt%dset(4), [xt%rows + nb], hdferr)
         call h5dget_space_f(xt%dset(4), fspace, hdferr)
         call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, off1, cnt1, hdferr)
         call h5screate_simple_f(1, cnt1, mspace, hdferr)
         tcol = xt%tbuf(1:nb)
         call h5dwrite_f(xt%dset(4), H5T_NATIVE_DOUBLE, tcol, cnt1, hdferr, &
                         mem_space_id=mspace, file_space_id=fspace)
         call check(h5, hdferr, 'h5dwrite_f x-t times')
         call h5sclose_f(mspace, hdferr)
         call h5sclose_f(fspace, hdferr)
         xt%rows = xt%rows + nb
         xt%nbuf = 0
      end associate
   end subroutine write_xt

   !> Write every buffer and flush the file: it then reads up to here if the run dies.
   subroutine h5_flush(h5)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      integer :: k, hdferr
      if (h5%file < 0 .or. h5%read_only) return
      do k = 1, size(h5%tables)
         call write_table(h5, k)
      end do
      do k = 1, size(h5%xt)
         if (h5%xt(k)%nrow > 0) call write_xt(h5, k)
      end do
      call h5fflush_f(h5%file, H5F_SCOPE_GLOBAL_F, hdferr)
      call check(h5, hdferr, 'h5fflush_f')
   end subroutine h5_flush

   !> Write what is buffered and close the file (errors stay in h5%error).
   subroutine h5_close(h5)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      integer :: k, j, hdferr
      if (h5%file < 0) return
      call h5_flush(h5)
      do k = 1, size(h5%tables)
         do j = 1, size(h5%tables(k)%dset)
            if (h5%tables(k)%dset(j) >= 0) call h5dclose_f(h5%tables(k)%dset(j), hdferr)
         end do
      end do
      do j = 1, size(h5%xt)
         do k = 1, 4
            if (h5%xt(j)%dset(k) >= 0) call h5dclose_f(h5%xt(j)%dset(k), hdferr)
         end do
      end do
      call h5fclose_f(h5%file, hdferr)
      call check(h5, hdferr, 'h5fclose_f')
      h5%file = -1
   end subroutine h5_close

   !> Open an existing file read-only (the h5_get* readers, h5_copy's source; h5_close).
   subroutine h5_open_read(h5, path)
      type(h5file_t), intent(out) :: h5    !! the HDF5 file
      character(len=*), intent(in) :: path   !! the file
      integer :: hdferr
      h5%path = path
      h5%read_only = .true.
      allocate(h5%tables(0))
      call h5open_f(hdferr)
      call check(h5, hdferr, 'h5open_f')
      call h5eset_auto_f(0, hdferr)
      call h5fopen_f(path, H5F_ACC_RDONLY_F, h5%file, hdferr)
      call check(h5, hdferr, 'h5fopen_f (read)')
      if (hdferr < 0) h5%file = -1
   end subroutine h5_open_read

   !> True when the object path (absolute) exists; parents are checked first, as
   !> h5lexists_f needs them.
   logical function h5_exists(h5, path)
      type(h5file_t), intent(in) :: h5     !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer :: j, k, hdferr
      logical :: ok
      h5_exists = .false.
      if (h5%file < 0) return
      j = 1
      do
         k = index(path(j+1:), '/')
         if (k == 0) exit
         j = j + k
         call h5lexists_f(h5%file, path(:j-1), ok, hdferr)
         if (.not. ok .or. hdferr < 0) return
      end do
      call h5lexists_f(h5%file, path, ok, hdferr)
      h5_exists = ok .and. hdferr >= 0
   end function h5_exists

   !> Dimensions of a dataset (Fortran order; rank <= 2); rank = -1 when it is absent.
   subroutine h5_dims(h5, path, dims, rank)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer(hsize_t), intent(out) :: dims(2)   !! its dimensions, Fortran order
      integer, intent(out) :: rank         !! its rank (-1: absent)
      integer(hid_t) :: dset, space
      integer(hsize_t) :: maxdims(2)
      integer :: hdferr
      dims = 0
      rank = -1
      if (.not. h5_exists(h5, path)) return
      call h5dopen_f(h5%file, path, dset, hdferr)
      call check(h5, hdferr, 'h5dopen_f ' // path)
      if (hdferr < 0) return
      call h5dget_space_f(dset, space, hdferr)
      call h5sget_simple_extent_dims_f(space, dims, maxdims, rank)
      call h5sclose_f(space, hdferr)
      call h5dclose_f(dset, hdferr)
   end subroutine h5_dims

   !> Open a 1-D dataset for reading: its handle and length (false if absent).
   logical function open_1d(h5, path, dset, n)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer(hid_t), intent(out) :: dset  !! the open dataset (-1: not opened)
      integer(hsize_t), intent(out) :: n   !! its length
      integer(hsize_t) :: dims(2)
      integer :: hdferr, rank
      n = 0
      dset = -1
      call h5_dims(h5, path, dims, rank)
      open_1d = rank == 1
      if (.not. open_1d) return
      n = dims(1)
      call h5dopen_f(h5%file, path, dset, hdferr)
      call check(h5, hdferr, 'h5dopen_f ' // path)
      open_1d = hdferr >= 0
   end function open_1d

   !> A whole 1-D dataset as float64 (HDF5 converts integer ones), allocated to its length
   !> (unallocated if absent).
   subroutine get_real_1d(h5, path, values)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      real(wp), allocatable, intent(out) :: values(:)   !! the data
      integer(hid_t) :: dset
      integer(hsize_t) :: n
      integer :: hdferr
      if (.not. open_1d(h5, path, dset, n)) return
      allocate(values(n))
      call h5dread_f(dset, H5T_NATIVE_DOUBLE, values, [n], hdferr)
      call check(h5, hdferr, 'h5dread_f ' // path)
      call h5dclose_f(dset, hdferr)
   end subroutine get_real_1d

   !> Columns c0+1 .. c0+size(values, 2) of a 2-D float64 dataset (rows = size(values, 1)).
   subroutine h5_get_columns(h5, path, c0, values)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      integer, intent(in) :: c0            !! columns before the first one read
      real(wp), intent(out) :: values(:, :)   !! the data
      integer(hid_t) :: dset, fspace, mspace
      integer(hsize_t) :: off(2), cnt(2)
      integer :: hdferr
      values = 0.0_wp
      if (h5%file < 0) return
      off = [0_hsize_t, int(c0, hsize_t)]
      cnt = shape(values, kind=hsize_t)
      call h5dopen_f(h5%file, path, dset, hdferr)
      call check(h5, hdferr, 'h5dopen_f ' // path)
      if (hdferr < 0) return
      call h5dget_space_f(dset, fspace, hdferr)
      call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, off, cnt, hdferr)
      call check(h5, hdferr, 'h5sselect_hyperslab_f ' // path)
      call h5screate_simple_f(2, cnt, mspace, hdferr)
      call h5dread_f(dset, H5T_NATIVE_DOUBLE, values, cnt, hdferr, mem_space_id=mspace, &
                     file_space_id=fspace)
      call check(h5, hdferr, 'h5dread_f ' // path)
      call h5sclose_f(mspace, hdferr)
      call h5sclose_f(fspace, hdferr)
      call h5dclose_f(dset, hdferr)
   end subroutine h5_get_columns

   !> Whether the object at path exists and has the attribute name.
   logical function h5_has_attr(h5, path, name)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      integer(hid_t) :: obj
      integer :: hdferr
      logical :: is_dset
      h5_has_attr = .false.
      if (h5%file < 0) return
      if (.not. h5_exists(h5, path)) return
      call open_obj(h5, path, obj, is_dset)
      if (allocated(h5%error)) return
      call h5aexists_f(obj, name, h5_has_attr, hdferr)
      if (hdferr < 0) h5_has_attr = .false.
      call close_obj(obj)
   end function h5_has_attr

   !> Open the attribute name of the object path (attr < 0 and an error if absent or not
   !> a single value).
   subroutine open_attr(h5, path, name, obj, attr)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      integer(hid_t), intent(out) :: obj   !! an open group or dataset
      integer(hid_t), intent(out) :: attr  !! the open attribute (< 0: absent, not one value)
      integer(hid_t) :: space
      integer(hsize_t) :: npoints
      integer :: hdferr
      logical :: is_dset, exists
      attr = -1
      obj = -1
      if (h5%file < 0) return
      if (.not. h5_exists(h5, path)) then
         call check(h5, -1, 'finding ' // path)
         return
      end if
      call open_obj(h5, path, obj, is_dset)
      if (allocated(h5%error)) return
      call h5aexists_f(obj, name, exists, hdferr)
      if (.not. exists) then
         call check(h5, -1, 'finding attribute ' // path // ':' // name)
         call close_obj(obj)
         obj = -1
         return
      end if
      call h5aopen_f(obj, name, attr, hdferr)
      call check(h5, hdferr, 'h5aopen_f ' // path // ':' // name)
      if (hdferr < 0) return
      ! every attribute read here is one value: another shape would be read past its end
      call h5aget_space_f(attr, space, hdferr)
      npoints = -1
      if (hdferr >= 0) call h5sget_simple_extent_npoints_f(space, npoints, hdferr)
      if (hdferr >= 0) call h5sclose_f(space, hdferr)
      if (npoints /= 1) then
         call check(h5, -1, 'reading ' // path // ':' // name // ' (not a single value)')
         call h5aclose_f(attr, hdferr)
         attr = -1
      end if
   end subroutine open_attr

   !> Close an attribute and its object.
   subroutine close_attr(obj, attr)
      integer(hid_t), intent(in) :: obj    !! an open group or dataset
      integer(hid_t), intent(in) :: attr   !! an attribute opened by open_attr (< 0: none)
      integer :: hdferr
      if (attr >= 0) call h5aclose_f(attr, hdferr)
      if (obj >= 0) call h5oclose_f(obj, hdferr)
   end subroutine close_attr

   !> Read a real attribute of the object at path.
   subroutine get_attr_real(h5, path, name, value)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      real(wp), intent(out) :: value       !! its value
      integer(hid_t) :: obj, attr
      integer :: hdferr
      value = 0.0_wp
      call open_attr(h5, path, name, obj, attr)
      if (attr >= 0) then
         call h5aread_f(attr, H5T_NATIVE_DOUBLE, value, [1_hsize_t], hdferr)
         call check(h5, hdferr, 'h5aread_f ' // path // ':' // name)
      end if
      call close_attr(obj, attr)
   end subroutine get_attr_real

   !> Read an integer attribute of the object at path.
   subroutine get_attr_int(h5, path, name, value)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      integer, intent(out) :: value        !! its value
      integer(hid_t) :: obj, attr
      integer :: hdferr
      value = 0
      call open_attr(h5, path, name, obj, attr)
      if (attr >= 0) then
         call h5aread_f(attr, H5T_NATIVE_INTEGER, value, [1_hsize_t], hdferr)
         call check(h5, hdferr, 'h5aread_f ' // path // ':' // name)
      end if
      call close_attr(obj, attr)
   end subroutine get_attr_int

   !> A fixed-length string attribute as written by h5_attr (trailing blanks dropped).
   subroutine get_attr_string(h5, path, name, value)
      type(h5file_t), intent(inout) :: h5   !! the HDF5 file
      character(len=*), intent(in) :: path   !! object path in the file (a group or dataset)
      character(len=*), intent(in) :: name   !! attribute name
      character(len=:), allocatable, intent(out) :: value   !! its value
      integer(hid_t) :: obj, attr, atype
      integer(size_t) :: n
      integer :: hdferr, tclass
      logical :: vlen
      value = ''
      call open_attr(h5, path, name, obj, attr)
      if (attr >= 0) then
         call h5aget_type_f(attr, atype, hdferr)
         call h5tget_size_f(atype, n, hdferr)
         call h5tget_class_f(atype, tclass, hdferr)
         vlen = .false.
         if (tclass == H5T_STRING_F) call h5tis_variable_str_f(atype, vlen, hdferr)
         if (tclass /= H5T_STRING_F .or. vlen) then
            ! another writer's attribute (h5py writes variable-length strings): not read
            call check(h5, -1, 'reading ' // path // ':' // name // ' (not a fixed-length string)')
            n = 0
         end if
         if (n > 0) then
         block
            character(len=n) :: text
            call h5aread_f(attr, atype, text, [1_hsize_t], hdferr)
            call check(h5, hdferr, 'h5aread_f ' // path // ':' // name)
            value = trim(text)
         end block
         end if
         call h5tclose_f(atype, hdferr)
      end if
      call close_attr(obj, attr)
   end subroutine get_attr_string

   !> Copy an object (a group with everything under it, or a dataset) from src to dst.
   subroutine h5_copy(src, src_path, dst, dst_path)
      type(h5file_t), intent(inout) :: src   !! the file copied from
      type(h5file_t), intent(inout) :: dst   !! the file copied into
      character(len=*), intent(in) :: src_path   !! object path in src
      character(len=*), intent(in) :: dst_path   !! its path in dst
      integer :: hdferr
      if (src%file < 0 .or. dst%file < 0) return
      call h5ocopy_f(src%file, src_path, dst%file, dst_path, hdferr)
      call check(dst, hdferr, 'h5ocopy_f ' // src%path // ':' // src_path // ' to ' // dst_path)
   end subroutine h5_copy

   !> Rows a table holds, buffered ones included.
   integer function h5_table_rows(h5, handle) result(rows)
      type(h5file_t), intent(in) :: h5     !! the HDF5 file
      integer, intent(in) :: handle        !! table handle (h5_table)
      rows = 0
      if (handle < 1 .or. handle > size(h5%tables)) return
      rows = int(h5%tables(handle)%rows) + h5%tables(handle)%nbuf
   end function h5_table_rows

   !> Rows (times) of the x-t fields or the gauges, buffered ones included.
   integer function h5_xt_rows(h5, which) result(rows)
      type(h5file_t), intent(in) :: h5     !! the HDF5 file
      integer, intent(in), optional :: which   !! xt_fields (default) or xt_gauges
      integer :: w
      w = xt_fields
      if (present(which)) w = which
      rows = 0
      if (h5%xt(w)%nrow > 0) rows = int(h5%xt(w)%rows) + h5%xt(w)%nbuf
   end function h5_xt_rows

   !> Length of a 1-D dataset (or the last dimension) in an existing file; -1 if absent.
   subroutine h5_read_size(path, dset_path, n)
      character(len=*), intent(in) :: path   !! the file
      character(len=*), intent(in) :: dset_path   !! dataset path in the file
      integer, intent(out) :: n                   !! its length (last dimension; -1: absent)
      integer(hid_t) :: file, dset, space
      integer(hsize_t) :: dims(2), maxdims(2)
      integer :: hdferr, rank
      logical :: exists
      n = -1
      call h5open_f(hdferr)
      call h5fopen_f(path, H5F_ACC_RDONLY_F, file, hdferr)
      if (hdferr < 0) return
      call h5lexists_f(file, dset_path, exists, hdferr)
      if (exists) then
         call h5dopen_f(file, dset_path, dset, hdferr)
         call h5dget_space_f(dset, space, hdferr)
         call h5sget_simple_extent_dims_f(space, dims, maxdims, rank)
         if (rank >= 1) n = int(dims(rank))
         call h5sclose_f(space, hdferr)
         call h5dclose_f(dset, hdferr)
      end if
      call h5fclose_f(file, hdferr)
   end subroutine h5_read_size

   !> Read a 1-D float64 dataset of an existing file into values (size from h5_read_size).
   subroutine h5_read(path, dset_path, values, ok)
      character(len=*), intent(in) :: path   !! the file
      character(len=*), intent(in) :: dset_path   !! dataset path in the file
      real(wp), intent(out) :: values(:)   !! the data
      logical, intent(out) :: ok           !! the dataset was read
      integer(hid_t) :: file, dset
      integer(hsize_t) :: dims(1)
      integer :: hdferr
      ok = .false.
      call h5open_f(hdferr)
      call h5fopen_f(path, H5F_ACC_RDONLY_F, file, hdferr)
      if (hdferr < 0) return
      call h5dopen_f(file, dset_path, dset, hdferr)
      if (hdferr >= 0) then
         dims = size(values)
         call h5dread_f(dset, H5T_NATIVE_DOUBLE, values, dims, hdferr)
         ok = hdferr >= 0
         call h5dclose_f(dset, hdferr)
      end if
      call h5fclose_f(file, hdferr)
   end subroutine h5_read

   !> The HDF5 library's version, 'major.minor.release' (h5get_libversion_f).
   function h5_library_version() result(text)
      character(len=:), allocatable :: text
      integer :: major, minor, release, hdferr
      call h5get_libversion_f(major, minor, release, hdferr)
      if (hdferr /= 0) then
         text = 'unknown'
      else
         text = itoa(major) // '.' // itoa(minor) // '.' // itoa(release)
      end if
   end function h5_library_version

   !> Name of the k-th block group: 'p000', 'p001', ... (sorts in time order).
   pure function block_name(k) result(name)
      integer, intent(in) :: k             !! block number, from 1
      character(len=:), allocatable :: name
      character(len=12) :: buf
      write(buf, '(a,i3.3)') 'p', k - 1
      name = trim(buf)
   end function block_name
end module spb_hdf5
