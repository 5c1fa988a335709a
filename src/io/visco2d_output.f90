!> Output of one run into its case folder: `summary.txt` (`key = value`),
!> `history.csv`, `pressure.csv` and `results.h5` (the legacy-style
!> `listing.txt` is visco2d_listing). Names and keys here are an interface:
!> tools parse them. Every writer returns '' or a message saying what
!> failed: text files are written through visco2d_text_file, whose every
!> write and close is checked.
module visco2d_output
  use, intrinsic :: iso_fortran_env, only: int64
  use hdf5, only: hid_t
  use visco2d_kinds, only: dp
  use visco2d_strings, only: integer_text, table_real
  use visco2d_deck, only: deck_t, analysis_name, geometry_name
  use visco2d_record, only: record_t, summary_item_t
  use visco2d_hdf5, only: h5_writer_t, h5_open_file, h5_close_file, h5_group, h5_close_group, &
                          h5_write, h5_attribute
  use visco2d_text_file, only: text_file_t, text_open, text_put, text_close
  use visco2d_xdmf, only: write_xdmf_view, xdmf_view_bytes
  implicit none
  private

  public :: write_summary, write_history, write_results_h5, unit_of, summary_unit
  public :: write_pressure, time_first_contact

  !> What number_kind finds in a summary value.
  integer, parameter :: number_none = 0, number_integer = 1, number_real = 2

contains

  !> Unit of a history column or summary key, from its suffix ('t_ms' -> 'ms').
  pure function unit_of(name) result(unit)
    character(*), intent(in) :: name
    character(:), allocatable :: unit
    integer :: last
    last = index(trim(name), '_', back=.true.)
    unit = '1'
    if (last == 0) return
    if (len_trim(name) > 5) then
      if (name(len_trim(name) - 4:len_trim(name)) == '_m_s2') then
        unit = 'm/s^2'; return
      end if
    end if
    if (len_trim(name) > 4) then
      if (name(len_trim(name) - 3:len_trim(name)) == '_m_s') then
        unit = 'm/s'; return
      end if
    end if
    select case (trim(name(last + 1:)))
    case ('s', 'ms', 'm', 'mm', 'Pa', 'MPa', 'N', 'J', 'g', 'kg')
      unit = trim(name(last + 1:))
    case ('m/s')
      unit = 'm/s'
    end select
  end function unit_of

  !> Unit of a summary key: unit_of the key, and for an EXPECT key
  !> (`expect_<key>_value`) the unit of <key>; a relative error is '1'.
  pure function summary_unit(key) result(unit)
    character(*), intent(in) :: key
    character(:), allocatable :: unit
    character(len=*), parameter :: prefix = 'expect_', suffix = '_value'
    integer :: n
    n = len_trim(key)
    if (n > len(prefix) + len(suffix)) then
      if (key(1:len(prefix)) == prefix .and. key(n - len(suffix) + 1:n) == suffix) then
        unit = unit_of(key(len(prefix) + 1:n - len(suffix)))
        return
      end if
    end if
    unit = unit_of(key)
  end function summary_unit

  !> summary.txt: one `key = value` per line.
  subroutine write_summary(path, record, message)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    character(:), allocatable, intent(out) :: message
    type(text_file_t) :: out
    integer :: i
    call text_open(out, path)
    do i = 1, record%nsummary
      call text_put(out, trim(record%summary(i)%key)//' = '//record%summary(i)%value)
    end do
    call text_close(out)
    message = out%message
  end subroutine write_summary

  !> history.csv: a header row of column names (units in the names), then one row per output step.
  subroutine write_history(path, record, message)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    character(:), allocatable, intent(out) :: message
    type(text_file_t) :: out
    integer :: i, j
    character(:), allocatable :: line
    call text_open(out, path)
    line = trim(record%columns(1))
    do j = 2, size(record%columns)
      line = line//','//trim(record%columns(j))
    end do
    call text_put(out, line)
    do i = 1, record%nrow
      line = table_real(record%history(1, i))
      do j = 2, size(record%columns)
        line = line//','//table_real(record%history(j, i))
      end do
      call text_put(out, line)
    end do
    call text_close(out)
    message = out%message
  end subroutine write_history

  !> pressure.csv: the contact pressure over radius (record%pressure, visco2d_impact's
  !> pressure_table), a header row of column names (units in the names), one row per node.
  subroutine write_pressure(path, record, message)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    character(:), allocatable, intent(out) :: message
    type(text_file_t) :: out
    integer :: i, j
    character(:), allocatable :: line
    call text_open(out, path)
    associate (table => record%pressure)
    line = trim(table%columns(1))
    do j = 2, size(table%columns)
      line = line//','//trim(table%columns(j))
    end do
    call text_put(out, line)
    do i = 1, size(table%values, 2)
      line = ''
      do j = 1, size(table%columns)
        if (j > 1) line = line//','
        if (trim(table%columns(j)) == 'node') then          ! the deck's node number
          line = line//integer_text(nint(table%values(j, i)))
        else
          line = line//table_real(table%values(j, i))
        end if
      end do
      call text_put(out, line)
    end do
    end associate
    call text_close(out)
    message = out%message
  end subroutine write_pressure

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
  !> One summary item as a scalar dataset of /summary: an integer or a real
  !> (with a `units` attribute) when the whole value is a number, else text.
  subroutine write_summary_item(writer, group, item)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: group
    type(summary_item_t), intent(in) :: item
    integer :: integer_value, status
    real(dp) :: real_value
    status = 1
    select case (number_kind(item%value))
    case (number_integer)
      read(item%value, *, iostat=status) integer_value
      if (status == 0) call h5_write(writer, group, trim(item%key), integer_value, units=summary_unit(item%key))
    case (number_real)
      read(item%value, *, iostat=status) real_value
      if (status == 0) call h5_write(writer, group, trim(item%key), real_value, units=summary_unit(item%key))
    end select
    if (status /= 0) call h5_write(writer, group, trim(item%key), item%value)
  end subroutine write_summary_item

  !> What a summary value is: number_integer (digits with an optional sign,
  !> at most 9 digits), number_real (a Fortran real literal: sign, digits
  !> with at most one point, an optional exponent e/E/d/D with digits) or
  !> number_none (anything else, blanks inside included).
  pure integer function number_kind(text) result(kind)
    character(*), intent(in) :: text
    integer :: i, n, digits, exponent_digits
    logical :: point, exponent
    kind = number_none
    n = len_trim(text)
    i = 1
    if (n == 0) return
    if (scan(text(1:1), '+-') == 1) i = 2
    digits = 0; exponent_digits = 0
    point = .false.; exponent = .false.
    do while (i <= n)
      select case (text(i:i))
      case ('0':'9')
        if (exponent) then
          exponent_digits = exponent_digits + 1
        else
          digits = digits + 1
        end if
      case ('.')
        if (point .or. exponent) return
        point = .true.
      case ('e', 'E', 'd', 'D')
        if (exponent .or. digits == 0) return
        exponent = .true.
        if (i < n) then
          if (scan(text(i + 1:i + 1), '+-') == 1) i = i + 1
        end if
      case default
        return
      end select
      i = i + 1
    end do
    if (digits == 0 .or. (exponent .and. exponent_digits == 0)) return
    if (point .or. exponent .or. digits > 9) then
      kind = number_real
    else
      kind = number_integer
    end if
  end function number_kind

  !> The time of first contact (s, deck time) from the summary's
  !> `time_first_contact_s`; `found` is false in a run without contact.
  function time_first_contact(record, found) result(time)
    type(record_t), intent(in) :: record
    logical, intent(out) :: found
    real(dp) :: time
    integer :: i, status
    time = 0.0_dp
    found = .false.
    do i = 1, record%nsummary
      if (record%summary(i)%key /= 'time_first_contact_s') cycle
      if (number_kind(record%summary(i)%value) == number_none) return
      read(record%summary(i)%value, *, iostat=status) time
      found = status == 0
      if (.not. found) time = 0.0_dp
      return
    end do
  end function time_first_contact

  !> results.h5: /mesh, /summary/<key>, /history/<column>, /fields/<snapshot>/..., /xdmf/<snapshot>/...
  !> HDF5 is closed (h5fclose, h5close) also after a failure; `message` says
  !> what failed first ('' if all went well).
  subroutine write_results_h5(path, case_name, deck, record, message)
    character(*), intent(in) :: path, case_name
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    character(:), allocatable, intent(out) :: message
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
    message = writer%failed
  end subroutine write_results_h5
end module visco2d_output
