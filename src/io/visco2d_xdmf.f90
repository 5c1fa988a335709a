!> `results.xmf`: an XDMF 3 description of `results.h5` beside it, so that
!> ParaView and meshio open the mesh and every snapshot directly. The file
!> holds no numbers of its own: every DataItem points into `results.h5`
!> (`results.h5:/xdmf/step_000123/displacement`), so the two must stay
!> together. One Temporal collection of Uniform grids, one grid per snapshot
!> (Time = the deck time in s), each with the mesh (Quadrilateral topology
!> from `/mesh/elements_0based`, XY geometry from `/mesh/nodes`), the
!> material index per element (Center="Cell") and the nodal fields of the
!> snapshot (Center="Node"). The Gauss-point stresses stay in results.h5 only.
!>
!> ParaView's readers differ on 2- and 4-component arrays (the legacy XDMF
!> reader of ParaView 5.11 reads a 4-component "Vector" as 3-component
!> tuples; a 2-component vector read by its XDMF3 readers cannot be warped
!> by, Warp By Vector asserts 3 components), so the vectors and the stress
!> the XDMF file shows are the view copies of `/xdmf/<snapshot>/` in
!> results.h5 (write_xdmf_view): vectors with 3 components (u_r, u_z, 0) and
!> the stress as the full symmetric 3x3 tensor of 9 components
!> (AttributeType "Tensor", row by row, r z theta as x y z): sigma_r,
!> tau_rz, 0, tau_rz, sigma_z, 0, 0, 0, sigma_theta. Every reader tried
!> reads that alike; a 6-component "Tensor6" is not: the legacy reader
!> expands it in XDMF's order (xx, xy, xz, yy, yz, zz), the XDMF3 readers
!> pass it on as VTK's (xx, yy, zz, xy, yz, xz).
!> `/fields/<snapshot>/` keeps its own (2- and 4-component) layout.
module visco2d_xdmf
  use, intrinsic :: iso_fortran_env, only: int64
  use hdf5, only: hid_t
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text
  use visco2d_deck, only: deck_t
  use visco2d_record, only: record_t, snapshot_t
  use visco2d_hdf5, only: h5_writer_t, h5_group, h5_close_group, h5_write
  use visco2d_text_file, only: text_file_t, text_open, text_put, text_close
  implicit none
  private

  public :: write_results_xdmf, write_xdmf_view, xdmf_view_bytes

  !> The HDF5 file the XDMF file points into (same folder).
  character(len=*), parameter :: h5_name = 'results.h5'

  !> The group of results.h5 holding the view copies (one subgroup per snapshot).
  character(len=*), parameter :: view_group = 'xdmf'

contains

  !> Write the XDMF file at `path` for the results.h5 written from the same
  !> deck and record; `error` (the file and what failed) if a write or the
  !> close failed.
  subroutine write_results_xdmf(path, deck, record, error)
    character(*), intent(in) :: path
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(out) :: error
    type(text_file_t) :: out
    integer :: i
    call text_open(out, path)
    call text_put(out, '<?xml version="1.0" ?>')
    call text_put(out, '<Xdmf Version="3.0">')
    call text_put(out, '  <Domain>')
    call text_put(out, '    <Grid Name="snapshots" GridType="Collection" CollectionType="Temporal">')
    if (allocated(record%snapshots)) then
      do i = 1, size(record%snapshots)
        call put_snapshot(out, deck, record, record%snapshots(i))
      end do
    end if
    call text_put(out, '    </Grid>')
    call text_put(out, '  </Domain>')
    call text_put(out, '</Xdmf>')
    call text_close(out)
    if (len(out%message) > 0) call set_error(error, out%message, file=path)
  end subroutine write_results_xdmf

  !> The view copies results.xmf points at, one group `/xdmf/<snapshot>` per
  !> snapshot in the open file of `writer`: `displacement`, `velocity`,
  !> `acceleration` as (nnode, 3) (u_r, u_z, 0) in h5py and `stress` as
  !> (nnode, 9), the 3x3 tensor row by row (stress_tensor), Pa.
  subroutine write_xdmf_view(writer, record)
    type(h5_writer_t), intent(inout) :: writer
    type(record_t), intent(in) :: record
    integer(hid_t) :: view, group
    integer :: i
    view = h5_group(writer, writer%file, view_group)
    if (allocated(record%snapshots)) then
      do i = 1, size(record%snapshots)
        associate (s => record%snapshots(i))
        group = h5_group(writer, view, s%name)
        call h5_write(writer, group, 'displacement', padded(s%displacement, 3), units='m')
        if (allocated(s%velocity)) call h5_write(writer, group, 'velocity', padded(s%velocity, 3), units='m/s')
        if (allocated(s%acceleration)) &
          call h5_write(writer, group, 'acceleration', padded(s%acceleration, 3), units='m/s^2')
        call h5_write(writer, group, 'stress', stress_tensor(s%stress), units='Pa')
        call h5_close_group(writer, group)
        end associate
      end do
    end if
    call h5_close_group(writer, view)
  end subroutine write_xdmf_view

  !> About the bytes write_xdmf_view adds to results.h5 (its arrays; the memory
  !> estimate counts the same 18 doubles per node, h5_xdmf_node_bytes of visco2d_budget).
  pure function xdmf_view_bytes(record) result(bytes)
    type(record_t), intent(in) :: record
    integer(int64) :: bytes
    integer :: i, components
    bytes = 0
    if (.not. allocated(record%snapshots)) return
    do i = 1, size(record%snapshots)
      associate (s => record%snapshots(i))
      components = 3 + 9
      if (allocated(s%velocity)) components = components + 3
      if (allocated(s%acceleration)) components = components + 3
      if (allocated(s%displacement)) bytes = bytes + 8_int64*components*size(s%displacement, 2, kind=int64)
      end associate
    end do
  end function xdmf_view_bytes

  !> `values` (m, n) with rows m+1 .. `rows` of zeros: (u_r, u_z) -> (u_r, u_z, 0).
  pure function padded(values, rows) result(full)
    real(dp), intent(in) :: values(:, :)
    integer, intent(in) :: rows
    real(dp), allocatable :: full(:, :)
    allocate(full(rows, size(values, 2)), source=0.0_dp)
    full(1:size(values, 1), :) = values
  end function padded

  !> The nodal stress (sigma_r, sigma_z, sigma_theta, tau_rz) (4, nnode) as
  !> the 3x3 tensor in (r, z, theta), row by row (9, nnode).
  pure function stress_tensor(stress) result(tensor)
    real(dp), intent(in) :: stress(:, :)
    real(dp), allocatable :: tensor(:, :)
    allocate(tensor(9, size(stress, 2)), source=0.0_dp)
    tensor(1, :) = stress(1, :)   ! rr
    tensor(2, :) = stress(4, :)   ! rz
    tensor(4, :) = stress(4, :)   ! zr
    tensor(5, :) = stress(2, :)   ! zz
    tensor(9, :) = stress(3, :)   ! theta theta
  end function stress_tensor

  !> One snapshot: a Uniform grid with its time, the mesh and its fields.
  subroutine put_snapshot(out, deck, record, snapshot)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(snapshot_t), intent(in) :: snapshot
    character(:), allocatable :: group, view, nodes, elements
    integer :: k
    nodes = integer_text(deck%mesh%nnode)
    elements = integer_text(deck%mesh%nelem)
    group = '/fields/'//snapshot%name
    call text_put(out, '      <Grid Name="'//snapshot%name//'" GridType="Uniform">')
    call text_put(out, '        <Time Value="'//time_text(snapshot%time)//'"/>')
    call text_put(out, '        <Topology TopologyType="Quadrilateral" NumberOfElements="'//elements//'">')
    call put_item(out, elements//' 4', 'Int', '4', '/mesh/elements_0based')
    call text_put(out, '        </Topology>')
    call text_put(out, '        <Geometry GeometryType="XY">')
    call put_item(out, nodes//' 2', 'Float', '8', '/mesh/nodes')
    call text_put(out, '        </Geometry>')
    call put_attribute(out, 'material', 'Scalar', 'Cell', elements, 'Int', '4', '/mesh/element_material')
    if (deck%body%line > 0) then                   ! two bodies: 1 the first, 2 the BODY card's
      call put_attribute(out, 'body', 'Scalar', 'Cell', elements, 'Int', '4', '/mesh/element_body')
      call put_attribute(out, 'node_body', 'Scalar', 'Node', nodes, 'Int', '4', '/mesh/node_body')
    end if
    view = '/'//view_group//'/'//snapshot%name
    call put_attribute(out, 'displacement', 'Vector', 'Node', nodes//' 3', 'Float', '8', view//'/displacement')
    if (allocated(snapshot%velocity)) &
      call put_attribute(out, 'velocity', 'Vector', 'Node', nodes//' 3', 'Float', '8', view//'/velocity')
    if (allocated(snapshot%acceleration)) &
      call put_attribute(out, 'acceleration', 'Vector', 'Node', nodes//' 3', 'Float', '8', view//'/acceleration')
    call put_attribute(out, 'stress', 'Tensor', 'Node', nodes//' 9', 'Float', '8', view//'/stress')
    call put_attribute(out, 'max_shear', 'Scalar', 'Node', nodes, 'Float', '8', group//'/max_shear')
    call put_attribute(out, 'von_mises', 'Scalar', 'Node', nodes, 'Float', '8', group//'/von_mises')
    ! The BRUISE envelopes (maxima over the whole run, so the same in every
    ! grid): their nodal versions, /bruise/<name>_nodal.
    if (allocated(record%bruise_fields)) then
      do k = 1, size(record%bruise_fields)
        associate (field => record%bruise_fields(k))
        if (allocated(field%nodal)) call put_attribute(out, field%name, 'Scalar', 'Node', nodes, 'Float', '8', &
                                                       '/bruise/'//field%name//'_nodal')
        end associate
      end do
    end if
    call text_put(out, '      </Grid>')
  end subroutine put_snapshot

  !> An Attribute element holding one HDF DataItem.
  subroutine put_attribute(out, name, kind, center, dimensions, number_type, precision, dataset)
    type(text_file_t), intent(inout) :: out
    character(*), intent(in) :: name, kind, center, dimensions, number_type, precision, dataset
    call text_put(out, '        <Attribute Name="'//name//'" AttributeType="'//kind//'" Center="'//center//'">')
    call put_item(out, dimensions, number_type, precision, dataset)
    call text_put(out, '        </Attribute>')
  end subroutine put_attribute

  !> A DataItem pointing at a dataset of results.h5 (dimensions in C order, as h5py shows them).
  subroutine put_item(out, dimensions, number_type, precision, dataset)
    type(text_file_t), intent(inout) :: out
    character(*), intent(in) :: dimensions, number_type, precision, dataset
    call text_put(out, '          <DataItem Dimensions="'//dimensions//'" NumberType="'//number_type// &
      '" Precision="'//precision//'" Format="HDF">'//h5_name//':'//dataset//'</DataItem>')
  end subroutine put_item

  !> A time in s with 17 significant digits (the double read back exactly).
  function time_text(time) result(text)
    real(dp), intent(in) :: time
    character(:), allocatable :: text
    character(len=40) :: buffer
    write(buffer, '(es24.16e3)') time
    text = trim(adjustl(buffer))
  end function time_text
end module visco2d_xdmf
