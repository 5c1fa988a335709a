!> `results.xmf`: an XDMF 3 description of `results.h5` beside it, so that
!> ParaView and meshio open the mesh and every snapshot directly. The file
!> holds no numbers of its own: every DataItem points into `results.h5`
!> (`results.h5:/fields/step_000123/displacement`), so the two must stay
!> together. One Temporal collection of Uniform grids, one grid per snapshot
!> (Time = the deck time in s), each with the mesh (Quadrilateral topology
!> from `/mesh/elements_0based`, XY geometry from `/mesh/nodes`), the
!> material index per element (Center="Cell") and the nodal fields of the
!> snapshot (Center="Node"). The Gauss-point stresses stay in results.h5 only.
module visco2d_xdmf
  use visco2d_kinds, only: dp
  use visco2d_strings, only: itoa
  use visco2d_deck, only: deck_t
  use visco2d_record, only: record_t, snapshot_t
  use visco2d_text_file, only: text_file_t, text_open, text_put, text_close
  implicit none
  private

  public :: write_results_xdmf

  !> The HDF5 file the XDMF file points into (same folder).
  character(len=*), parameter :: h5_name = 'results.h5'

contains

  !> Write the XDMF file at `path` for the results.h5 written from the same
  !> deck and record; `message` is '' or what failed.
  subroutine write_results_xdmf(path, deck, record, message)
    character(*), intent(in) :: path
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    character(:), allocatable, intent(out) :: message
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
    message = out%message
  end subroutine write_results_xdmf

  !> One snapshot: a Uniform grid with its time, the mesh and its fields.
  subroutine put_snapshot(out, deck, record, snapshot)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(snapshot_t), intent(in) :: snapshot
    character(:), allocatable :: group, nodes, elements
    integer :: k
    nodes = itoa(deck%mesh%nnode)
    elements = itoa(deck%mesh%nelem)
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
    call put_attribute(out, 'displacement', 'Vector', 'Node', nodes//' 2', 'Float', '8', group//'/displacement')
    if (allocated(snapshot%velocity)) &
      call put_attribute(out, 'velocity', 'Vector', 'Node', nodes//' 2', 'Float', '8', group//'/velocity')
    if (allocated(snapshot%acceleration)) &
      call put_attribute(out, 'acceleration', 'Vector', 'Node', nodes//' 2', 'Float', '8', group//'/acceleration')
    ! A 4-component "Vector": VTK's XDMF reader (ParaView) then reads one 4-component tuple per
    ! node; as "Matrix" it read the whole array as a single tuple.
    call put_attribute(out, 'stress', 'Vector', 'Node', nodes//' 4', 'Float', '8', group//'/stress')
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
