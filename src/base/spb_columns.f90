!> The columns of an output table, registered by the modules that own their quantities (the
!> MOM6 register_diag_field / post_data pattern; doc/build.md, "Output columns"): an owner
!> registers each quantity once (name, unit, whole numbers or not) and keeps the id it gets
!> in a type of its own; each row it posts the value under that id, row(id) = value. The id
!> is the column's place in the file, given by the name: a set starts from the list of names
!> whose order the file format fixes, and a column registered beyond that list follows it in
!> registration order. No value is placed by counting.
module spb_columns
   implicit none
   private
   public :: column_t, column_set_t, column_set, add_column, column_fault, column_names

   !> A column of a table: its name, its unit, and whether it holds whole numbers (text: an
   !> integer field; HDF5: int64). Rows carry every value as float64 (exact below 2^53).
   type :: column_t
      character(len=24) :: name = ''
      character(len=8) :: unit = ''
      logical :: whole = .false.
      integer :: width = 20              !! text field width; a whole number right-aligned
      logical :: kind = .false.          !! the event kind: its name in the text (the code in HDF5)
   end type column_t

   !> The columns of a table as their owners registered them, in file order.
   type :: column_set_t
      type(column_t), allocatable :: col(:)        !! the columns (a listed one not registered
                                                   !! yet: name '')
      character(len=24), allocatable :: order(:)   !! the names whose places the format fixes
      character(len=24) :: twice = ''              !! a name registered twice (a fault)
   end type column_set_t

contains

   !> An empty set whose first columns are the names of order, in that order (the file
   !> format); their owners register them.
   pure function column_set(order) result(set)
      character(len=*), intent(in) :: order(:)   !! names in file order
      type(column_set_t) :: set
      integer :: k
      allocate(set%order(size(order)), set%col(size(order)))
      do k = 1, size(order)
         set%order(k) = order(k)
      end do
   end function column_set

   !> Register a column: id becomes its place, the one to post its values under (rows hold
   !> whole numbers as float64; width: of the text field, default 20; kind: the event kind).
   pure subroutine add_column(set, id, name, unit, whole, width, kind)
      type(column_set_t), intent(inout) :: set   !! the table's columns
      integer, intent(out) :: id              !! the column's id: its place in a row
      character(len=*), intent(in) :: name    !! column name
      character(len=*), intent(in) :: unit    !! its unit ('-': none)
      logical, intent(in), optional :: whole  !! whole numbers (default: no)
      integer, intent(in), optional :: width  !! text field width (default 20)
      logical, intent(in), optional :: kind   !! the event kind column (default: no)
      type(column_t), allocatable :: grown(:)
      type(column_t) :: c
      integer :: k
      c%name = name
      c%unit = unit
      if (present(whole)) c%whole = whole
      if (present(width)) c%width = width
      if (present(kind)) c%kind = kind
      id = 0
      do k = 1, size(set%order)
         if (set%order(k) == name) id = k
      end do
      if (id == 0) then
         do k = size(set%order) + 1, size(set%col)
            if (set%col(k)%name == name) id = k
         end do
      end if
      if (id == 0) then
         allocate(grown(size(set%col) + 1))
         grown(1:size(set%col)) = set%col
         call move_alloc(grown, set%col)
         id = size(set%col)
      end if
      if (len_trim(set%col(id)%name) > 0) set%twice = name
      set%col(id) = c
   end subroutine add_column

   !> What is wrong with a set ('' when nothing): a name of its order no owner registered,
   !> or one registered twice.
   pure function column_fault(set) result(why)
      type(column_set_t), intent(in) :: set   !! the table's columns
      character(len=:), allocatable :: why
      integer :: k
      why = ''
      if (len_trim(set%twice) > 0) why = 'column ' // trim(set%twice) // ' registered twice'
      do k = 1, size(set%order)
         if (len_trim(set%col(k)%name) == 0) why = 'column ' // trim(set%order(k)) // &
            ' not registered'
      end do
   end function column_fault

   !> The names of a table's columns, blank-separated.
   pure function column_names(table) result(line)
      type(column_t), intent(in) :: table(:)   !! the table's columns
      character(len=:), allocatable :: line
      integer :: k
      line = trim(table(1)%name)
      do k = 2, size(table)
         line = line // ' ' // trim(table(k)%name)
      end do
   end function column_names
end module spb_columns
