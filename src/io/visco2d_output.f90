!> Output of one run into its case folder: `summary.txt` (`key = value`),
!> `history.csv`, `pressure.csv` and `results.h5` (the legacy-style
!> `listing.txt` is visco2d_listing). Names and keys here are an interface:
!> tools parse them. Every writer returns no error or an error_t (the file
!> it wrote and a message saying what failed): text files are written
!> through visco2d_text_file, whose every write and close is checked.
module visco2d_output
  use, intrinsic :: iso_fortran_env, only: int64
  use hdf5, only: hid_t
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, table_real
  use visco2d_deck, only: deck_t, analysis_name, geometry_name
  use visco2d_record, only: record_t, summary_item_t, summary_item_text, record_real, unit_of, summary_unit, &
                            summary_real, summary_integer
  use visco2d_hdf5, only: h5_writer_t, h5_open_file, h5_close_file, h5_group, h5_close_group, &
                          h5_write, h5_attribute
  use visco2d_text_file, only: text_file_t, text_open, text_put, text_close
  use visco2d_xdmf, only: write_xdmf_view, xdmf_view_bytes
  implicit none
  private

  public :: write_summary, write_history, write_results_h5, unit_of, summary_unit
  public :: write_pressure, time_first_contact

contains

  !> summary.txt: one `key = value` per line.
  subroutine write_summary(path, record, error)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(out) :: error
    type(text_file_t) :: out
    integer :: i
    call text_open(out, path)
    do i = 1, record%nsummary
      call text_put(out, trim(record%summary(i)%key)//' = '//summary_item_text(record%summary(i)))
    end do
    call text_close(out)
    if (len(out%message) > 0) call set_error(error, out%message, file=path)
  end subroutine write_summary

  !> history.csv: a header row of column names (units in the names), then one row per output step.
  subroutine write_history(path, record, error)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: message
    call write_csv(path, record%columns, record%history(:, 1:record%nrow), message)
    if (len(message) > 0) call set_error(error, message, file=path)
  end subroutine write_history

  !> pressure.csv: the contact pressure over radius (record%pressure, visco2d_impact's
  !> pressure_table), a header row of column names (units in the names), one row per node.
  subroutine write_pressure(path, record, error)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: message
    call write_csv(path, record%pressure%columns, record%pressure%values, message, integer_column='node')
    if (len(message) > 0) call set_error(error, message, file=path)
  end subroutine write_pressure

  !> A CSV table: the header row of the column names, then one row per column
  !> of values (ncolumn, nrow), each number by table_real (10 significant digits)
  !> but the column named `integer_column` (the deck's node numbers), written
  !> as an integer.
  subroutine write_csv(path, columns, values, message, integer_column)
    character(*), intent(in) :: path
    character(*), intent(in) :: columns(:)
    real(dp), intent(in) :: values(:, :)
    character(:), allocatable, intent(out) :: message
    character(*), intent(in), optional :: integer_column
    type(text_file_t) :: out
    logical :: whole(size(columns))
    integer :: i, j
    character(:), allocatable :: line
    whole = .false.
    if (present(integer_column)) whole = columns == integer_column
    call text_open(out, path)
    line = trim(columns(1))
    do j = 2, size(columns)
      line = line//','//trim(columns(j))
    end do
    call text_put(out, line)
    do i = 1, size(values, 2)
      line = ''
      do j = 1, size(columns)
        if (j > 1) line = line//','
        if (whole(j)) then
          line = line//integer_text(nint(values(j, i)))
        else
          line = line//table_real(values(j, i))
        end if
      end do
      call text_put(out, line)
    end do
    call text_close(out)
    message = out%message
  end subroutine write_csv

  !> The legacy-style printed listing.  !> About the size of results.h5: its arrays and 64 kB for groups and attributes.
  function h5_bytes(deck, record) result(bytes)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    integer(int64) :: bytes
    integer :: i
    bytes = 65536_int64 + 8_int64*size(deck%mesh%xy, kind=int64) + 8_int64*size(deck%mesh%connectivity, kind=int64) &
            + 12_int64*deck%mesh%nelem + 4_int64*deck%mesh%nnode + 512_int64*record%nsummary
    if (allocated(record%history)) bytes = bytes + 8_int64*size(record%history, 1, kind=int64)*record%nrow
    if (allocated(record%bruise_fields)) bytes = bytes + 8_int64*size(record%bruise_fields, kind=int64)* &
                                                 (4_int64*deck%mesh%nelem + deck%mesh%nnode)
    bytes = bytes + xdmf_view_bytes(record)
    if (.not. allocated(record%snapshots)) return
    do i = 1, size(record%snapshots)
      associate (s => record%snapshots(i))
      if (allocated(s%displacement)) bytes = bytes + 8_int64*size(s%displacement, kind=int64)
      if (allocated(s%velocity)) bytes = bytes + 8_int64*size(s%velocity, kind=int64)
      if (allocated(s%acceleration)) bytes = bytes + 8_int64*size(s%acceleration, kind=int64)
      if (allocated(s%stress)) bytes = bytes + 8_int64*size(s%stress, kind=int64)
      if (allocated(s%stress_gauss)) bytes = bytes + 8_int64*size(s%stress_gauss, kind=int64)
      if (allocated(s%max_shear)) bytes = bytes + 8_int64*size(s%max_shear, kind=int64)
      if (allocated(s%von_mises)) bytes = bytes + 8_int64*size(s%von_mises, kind=int64)
      end associate
    end do
  end function h5_bytes
  !> One summary item as a scalar dataset of /summary, by its kind: a real
  !> as a double in full precision, an integer as an integer (each with a
  !> `units` attribute), a text or a logical (yes / no, HDF5 has no boolean)
  !> as a string, the same words as summary.txt.
  subroutine write_summary_item(writer, group, item)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: group
    type(summary_item_t), intent(in) :: item
    select case (item%kind)
    case (summary_real)
      call h5_write(writer, group, trim(item%key), item%real_value, units=item%unit)
    case (summary_integer)
      call h5_write(writer, group, trim(item%key), item%integer_value, units=item%unit)
    case default
      call h5_write(writer, group, trim(item%key), summary_item_text(item))
    end select
  end subroutine write_summary_item

  !> The time of first contact (s, deck time) from the summary's
  !> `time_first_contact_s`, full precision; `found` is false in a run without contact.
  function time_first_contact(record, found) result(time)
    type(record_t), intent(in) :: record
    logical, intent(out) :: found
    real(dp) :: time
    call record_real(record, 'time_first_contact_s', time, found)
  end function time_first_contact

  !> results.h5: /mesh, /summary/<key>, /history/<column>, /fields/<snapshot>/..., /xdmf/<snapshot>/...
  !> HDF5 is closed (h5fclose, h5close) also after a failure; `error` says
  !> what failed first (not allocated if all went well).
  subroutine write_results_h5(path, case_name, deck, record, error)
    character(*), intent(in) :: path, case_name
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(out) :: error
    type(h5_writer_t) :: writer
    integer(hid_t) :: group, fields, snapshot
    integer :: i, k
    real(dp), allocatable :: column(:)
    real(dp) :: contact_time
    logical :: contact

    call h5_open_file(writer, path, h5_bytes(deck, record))
    call h5_attribute(writer, writer%file, 'case', case_name)
    call h5_attribute(writer, writer%file, 'title', deck%title)
    call h5_attribute(writer, writer%file, 'geometry', geometry_name(deck%settings%geometry))
    call h5_attribute(writer, writer%file, 'analysis', analysis_name(deck%analysis))

    group = h5_group(writer, writer%file, 'mesh')
    call h5_write(writer, group, 'nodes', deck%mesh%xy, units='m')
    call h5_write(writer, group, 'elements', deck%mesh%connectivity)
    call h5_write(writer, group, 'elements_0based', deck%mesh%connectivity - 1)
    call h5_write(writer, group, 'node_ids', deck%mesh%node_id)
    call h5_write(writer, group, 'element_ids', deck%mesh%element_id)
    call h5_write(writer, group, 'element_material', deck%mesh%element_material)
    if (deck%body%line > 0) then                   ! two bodies: which one each node and element belongs to
      call h5_write(writer, group, 'node_body', body_index(deck%mesh%nnode, deck%pad%first_node))
      call h5_write(writer, group, 'element_body', body_index(deck%mesh%nelem, deck%pad%first_element))
    end if
    call h5_close_group(writer, group)

    group = h5_group(writer, writer%file, 'summary')
    do i = 1, record%nsummary
      call write_summary_item(writer, group, record%summary(i))
    end do
    call h5_close_group(writer, group)
    contact_time = time_first_contact(record, contact)

    group = h5_group(writer, writer%file, 'history')
    do k = 1, size(record%columns)
      column = record%history(k, 1:record%nrow)
      call h5_write(writer, group, trim(record%columns(k)), column, units=unit_of(record%columns(k)))
    end do
    call h5_close_group(writer, group)

    if (allocated(record%pressure%columns)) then
      group = h5_group(writer, writer%file, 'pressure')
      do k = 1, size(record%pressure%columns)
        column = record%pressure%values(k, :)
        if (trim(record%pressure%columns(k)) == 'node') then     ! the deck's node numbers
          call h5_write(writer, group, 'node', nint(column))
        else
          call h5_write(writer, group, trim(record%pressure%columns(k)), column, &
                        units=unit_of(record%pressure%columns(k)))
        end if
      end do
      call h5_close_group(writer, group)
    end if

    fields = h5_group(writer, writer%file, 'fields')
    if (allocated(record%snapshots)) then
      do i = 1, size(record%snapshots)
        associate (s => record%snapshots(i))
        snapshot = h5_group(writer, fields, s%name)
        call h5_attribute(writer, snapshot, 'time', s%time)
        call h5_attribute(writer, snapshot, 'time_units', 's')
        if (contact) call h5_attribute(writer, snapshot, 'time_from_contact', s%time - contact_time)
        call h5_attribute(writer, snapshot, 'label', s%label)
        call h5_write(writer, snapshot, 'displacement', s%displacement, units='m')
        if (allocated(s%velocity)) call h5_write(writer, snapshot, 'velocity', s%velocity, units='m/s')
        if (allocated(s%acceleration)) call h5_write(writer, snapshot, 'acceleration', s%acceleration, units='m/s^2')
        call h5_write(writer, snapshot, 'stress', s%stress, units='Pa')
        call h5_write(writer, snapshot, 'stress_gauss', s%stress_gauss, units='Pa')
        call h5_write(writer, snapshot, 'max_shear', s%max_shear, units='Pa')
        call h5_write(writer, snapshot, 'von_mises', s%von_mises, units='Pa')
        call h5_close_group(writer, snapshot)
        end associate
      end do
    end if
    call h5_close_group(writer, fields)
    call write_xdmf_view(writer, record)                     ! what results.xmf shows (visco2d_xdmf)
    if (allocated(record%bruise_fields)) then                ! BRUISE envelopes (visco2d_bruise)
      group = h5_group(writer, writer%file, 'bruise')
      do i = 1, size(record%bruise_fields)
        associate (f => record%bruise_fields(i))
        call h5_write(writer, group, f%name, f%gauss, units=f%units)
        if (allocated(f%nodal)) call h5_write(writer, group, f%name//'_nodal', f%nodal, units=f%units)
        end associate
      end do
      call h5_close_group(writer, group)
    end if
    call h5_close_file(writer)
    if (len(writer%failed) > 0) call set_error(error, writer%failed, file=path)
  end subroutine write_results_h5

  !> 1 for the entities 1..first - 1 (the first body), 2 from `first` on (the second BODY).
  pure function body_index(count, first) result(body)
    integer, intent(in) :: count, first
    integer :: body(count)
    integer :: k
    body = [(merge(1, 2, k < first), k = 1, count)]
  end function body_index
end module visco2d_output
