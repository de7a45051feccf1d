!> PREFIX.xmf: an XDMF 2 description of the fields in a finished PREFIX.h5, so that ParaView
!> (and VisIt, or any reader of XDMF) opens them without the project's reader
!> (doc/outputs.md, "PREFIX.xmf"). The data stay in PREFIX.h5; the XML only points at them.
!>
!> Three grids, each where the file has its data:
!>  * `xt`: the x-t plane as one rectilinear grid, x (the half-node rows of /mesh/x_half)
!>    along X and the times of /fields/xt/t along Y, with u, v and stress on its points;
!>  * `bar`: the same rows as a time series of the bar (one line of points per x-t time);
!>  * `profiles`: the profile snapshots of /fields/profiles as a time series.
module spb_xdmf
   use spb_kinds, only: wp
   use spb_error, only: spb_error_t, make_error, exit_runtime
   use spb_strings, only: itoa, rtoa
   use spb_hdf5, only: h5file_t, h5_open_read, h5_close, h5_get, h5_get_attr, h5_exists, &
      block_name
   use spb_sys, only: sys_rename
   implicit none
   private
   public :: write_xdmf, xdmf_path

   character(len=*), parameter :: fields(3) = [character(len=6) :: 'u', 'v', 'stress']
   character(len=*), parameter :: units(3) = [character(len=3) :: 'm', 'm/s', 'Pa']

contains

   !> The XDMF file that goes with the output prefix.
   pure function xdmf_path(prefix) result(path)
      character(len=*), intent(in) :: prefix   !! output path prefix
      character(len=:), allocatable :: path
      path = prefix // '.xmf'
   end function xdmf_path

   !> Read what PREFIX.h5 holds (closed, complete) and write PREFIX.xmf beside it (through
   !> PREFIX.xmf.part, renamed when whole).
   subroutine write_xdmf(prefix, err)
      character(len=*), intent(in) :: prefix   !! output path prefix (PREFIX.h5 exists)
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      type(h5file_t) :: h5
      real(wp), allocatable :: x(:), t_xt(:), t_prf(:)
      character(len=:), allocatable :: h5name, part
      integer :: u, ios, k, n_prf
      logical :: ok
      character(len=256) :: msg
      call h5_open_read(h5, prefix // '.h5')
      call h5_get(h5, '/mesh/x_half', x)
      call h5_get(h5, '/fields/xt/t', t_xt)
      n_prf = 0
      do while (h5_exists(h5, '/fields/profiles/' // block_name(n_prf + 1)))
         n_prf = n_prf + 1
      end do
      allocate(t_prf(n_prf))
      do k = 1, n_prf
         call h5_get_attr(h5, '/fields/profiles/' // block_name(k), 't', t_prf(k))
      end do
      if (allocated(h5%error)) then
         call make_error(err, 'HDF5: ' // h5%error // ' (reading ''' // prefix // '.h5'' for ' // &
                         'its XDMF file)', code=exit_runtime)
         call h5_close(h5)
         return
      end if
      call h5_close(h5)
      if (.not. allocated(x)) allocate(x(0))
      if (.not. allocated(t_xt)) allocate(t_xt(0))
      h5name = base_name(prefix) // '.h5'
      part = xdmf_path(prefix) // '.part'
      open(newunit=u, file=part, status='replace', action='write', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, '--output: cannot write ''' // part // ''': ' // trim(msg), &
                         code=exit_runtime)
         return
      end if
      write(u, '(a)') '<?xml version="1.0" ?>'
      write(u, '(a)') '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>'
      write(u, '(a)') '<!-- spallbar: the fields of ' // h5name // ' (doc/outputs.md); x [m], ' // &
         't [s], u [m], v [m/s] along +x (down), stress [Pa] (compression > 0) -->'
      write(u, '(a)') '<Xdmf Version="2.0">'
      write(u, '(a)') ' <Domain>'
      if (size(t_xt) > 0 .and. size(x) > 0) then
         call xt_plane(u, h5name, size(x), size(t_xt))
         call line_series(u, h5name, size(x), t_xt, .true.)
      end if
      if (n_prf > 0 .and. size(x) > 0) call line_series(u, h5name, size(x), t_prf, .false.)
      write(u, '(a)') ' </Domain>'
      write(u, '(a)') '</Xdmf>'
      close(u, iostat=ios)
      if (ios == 0) call sys_rename(part, xdmf_path(prefix), ok)
      if (ios /= 0 .or. .not. ok) call make_error(err, '--output: cannot write ''' // &
         xdmf_path(prefix) // '''', code=exit_runtime)
   end subroutine write_xdmf

   !> The grid `xt`: x along X, t along Y, the fields on its points.
   subroutine xt_plane(u, h5name, nx, nt)
      integer, intent(in) :: u             !! open formatted unit
      character(len=*), intent(in) :: h5name   !! the HDF5 file, relative to the XML
      integer, intent(in) :: nx            !! half-node rows
      integer, intent(in) :: nt            !! x-t times
      integer :: k
      write(u, '(a)') '  <Grid Name="xt" GridType="Uniform">'
      write(u, '(a)') '   <Topology TopologyType="2DRectMesh" Dimensions="' // itoa(nt) // ' ' // &
         itoa(nx) // '"/>'
      write(u, '(a)') '   <Geometry GeometryType="VXVY">'
      call item(u, itoa(nx), h5name // ':/mesh/x_half')
      call item(u, itoa(nt), h5name // ':/fields/xt/t')
      write(u, '(a)') '   </Geometry>'
      do k = 1, size(fields)
         write(u, '(a)') '   <Attribute Name="' // trim(fields(k)) // ' [' // trim(units(k)) // &
            ']" AttributeType="Scalar" Center="Node">'
         call item(u, itoa(nt) // ' ' // itoa(nx), h5name // ':/fields/xt/' // trim(fields(k)))
         write(u, '(a)') '   </Attribute>'
      end do
      write(u, '(a)') '  </Grid>'
   end subroutine xt_plane

   !> A time series of the bar as lines of points: `bar` (from_xt: at each x-t time, row k of
   !> /fields/xt through a hyperslab) or `profiles` (each profile snapshot; its 1-D datasets
   !> given as 1 x nx, the shape of the grid: what VTK's XDMF reader needs).
   subroutine line_series(u, h5name, nx, t, from_xt)
      integer, intent(in) :: u             !! open formatted unit
      character(len=*), intent(in) :: h5name   !! the HDF5 file, relative to the XML
      integer, intent(in) :: nx            !! half-node rows
      real(wp), intent(in) :: t(:)         !! the members' times [s]
      logical, intent(in) :: from_xt       !! the x-t rows (else the profiles)
      integer :: k, j
      character(len=:), allocatable :: name, member, path
      if (from_xt) then
         name = 'bar'
         member = 'bar'
      else
         name = 'profiles'
         member = 'profile'
      end if
      write(u, '(a)') '  <Grid Name="' // name // '" GridType="Collection" ' // &
         'CollectionType="Temporal">'
      do k = 1, size(t)
         call line_grid_start(u, member, h5name, nx, t(k))
         do j = 1, size(fields)
            write(u, '(a)') '    <Attribute Name="' // trim(fields(j)) // ' [' // &
               trim(units(j)) // ']" AttributeType="Scalar" Center="Node">'
            if (from_xt) then
               path = h5name // ':/fields/xt/' // trim(fields(j))
               write(u, '(a)') '     <DataItem ItemType="HyperSlab" Dimensions="1 ' // &
                  itoa(nx) // '">'
               write(u, '(a)') '      <DataItem Dimensions="3 2" Format="XML">' // &
                  itoa(k - 1) // ' 0 1 1 1 ' // itoa(nx) // '</DataItem>'
               call item(u, itoa(size(t)) // ' ' // itoa(nx), path)
               write(u, '(a)') '     </DataItem>'
            else
               path = h5name // ':/fields/profiles/' // block_name(k) // '/' // trim(fields(j))
               call item(u, '1 ' // itoa(nx), path)
            end if
            write(u, '(a)') '    </Attribute>'
         end do
         write(u, '(a)') '   </Grid>'
      end do
      write(u, '(a)') '  </Grid>'
   end subroutine line_series

   !> The opening of a time series' member: its time, a 1 x nx rectilinear grid on x.
   subroutine line_grid_start(u, name, h5name, nx, t)
      integer, intent(in) :: u             !! open formatted unit
      character(len=*), intent(in) :: name   !! the member's name
      character(len=*), intent(in) :: h5name   !! the HDF5 file, relative to the XML
      integer, intent(in) :: nx            !! half-node rows
      real(wp), intent(in) :: t            !! the member's time [s]
      write(u, '(a)') '   <Grid Name="' // name // '" GridType="Uniform">'
      write(u, '(a)') '    <Time Value="' // rtoa(t) // '"/>'
      write(u, '(a)') '    <Topology TopologyType="2DRectMesh" Dimensions="1 ' // itoa(nx) // '"/>'
      write(u, '(a)') '    <Geometry GeometryType="VXVY">'
      call item(u, itoa(nx), h5name // ':/mesh/x_half')
      write(u, '(a)') '     <DataItem Dimensions="1" NumberType="Float" Precision="8" ' // &
         'Format="XML">0</DataItem>'
      write(u, '(a)') '    </Geometry>'
   end subroutine line_grid_start

   !> A float64 DataItem pointing at a dataset of the HDF5 file.
   subroutine item(u, dims, where)
      integer, intent(in) :: u             !! open formatted unit
      character(len=*), intent(in) :: dims   !! its dimensions, slowest first ("nt nx")
      character(len=*), intent(in) :: where   !! FILE:/path of the dataset
      write(u, '(a)') '     <DataItem Dimensions="' // dims // '" NumberType="Float" ' // &
         'Precision="8" Format="HDF">' // where // '</DataItem>'
   end subroutine item

   !> The file name of a path (what follows its last '/').
   pure function base_name(path) result(name)
      character(len=*), intent(in) :: path   !! a path
      character(len=:), allocatable :: name
      name = path(index(path, '/', back=.true.) + 1:)
   end function base_name
end module spb_xdmf
