!> A list of named scalar fields, written or read back by one procedure (the MOM6
!> register_restart_field pattern): the module that owns a quantity lists its fields once,
!> in one routine taking a field_io_t; the file behind it (spb_checkpoint's HDF5 file and
!> checksum) extends this type. The same calls, in the same order, write and read.
module spb_field_io
   use spb_kinds, only: wp
   implicit none
   private
   public :: field_io_t

   !> Where a field list is written to or read back from.
   type, abstract :: field_io_t
      logical :: writing = .false.         !! write the fields (else read them back)
   contains
      procedure(int_field), deferred :: int_field     !! an integer field
      procedure(real_field), deferred :: real_field   !! a real field
      procedure(has_field), deferred :: has           !! the file holds the field
      procedure(reals_field), deferred :: later_reals !! a real array added later
      !> A field named name of group, written or read back into v.
      generic :: field => int_field, real_field
      procedure :: later => later_real
   end type field_io_t

   abstract interface
      !> An integer field of group, written or read back.
      subroutine int_field(io, group, name, v)
         import :: field_io_t
         implicit none
         class(field_io_t), intent(inout) :: io   !! the file
         character(len=*), intent(in) :: group    !! group path
         character(len=*), intent(in) :: name     !! field name
         integer, intent(inout) :: v              !! the value
      end subroutine int_field
      !> A real field of group, written or read back.
      subroutine real_field(io, group, name, v)
         import :: field_io_t, wp
         implicit none
         class(field_io_t), intent(inout) :: io   !! the file
         character(len=*), intent(in) :: group    !! group path
         character(len=*), intent(in) :: name     !! field name
         real(wp), intent(inout) :: v             !! the value
      end subroutine real_field
      !> A real array named name added after files existed: always written (when allocated);
      !> read back only where the file has it (a stays unallocated otherwise).
      subroutine reals_field(io, name, a)
         import :: field_io_t, wp
         implicit none
         class(field_io_t), intent(inout) :: io   !! the file
         character(len=*), intent(in) :: name     !! field name
         real(wp), allocatable, intent(inout) :: a(:)   !! the array
      end subroutine reals_field
      !> True when the file (being read) holds the field name of group.
      logical function has_field(io, group, name)
         import :: field_io_t
         implicit none
         class(field_io_t), intent(inout) :: io   !! the file
         character(len=*), intent(in) :: group    !! group path
         character(len=*), intent(in) :: name     !! field name
      end function has_field
   end interface

contains

   !> A real field added after files existed: always written; read back only where the
   !> file has it (v keeps its value otherwise), so that an older file still reads.
   subroutine later_real(io, group, name, v)
      class(field_io_t), intent(inout) :: io   !! the file
      character(len=*), intent(in) :: group    !! group path
      character(len=*), intent(in) :: name     !! field name
      real(wp), intent(inout) :: v             !! the value
      if (io%writing) then
         call io%real_field(group, name, v)
      else if (io%has(group, name)) then
         call io%real_field(group, name, v)
      end if
   end subroutine later_real
end module spb_field_io
