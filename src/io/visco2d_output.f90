!> Output of one run into its case folder: the legacy-style `listing.txt`,
!> `summary.txt` (`key = value`), `history.csv` and `results.h5`.
!> Names and keys here are an interface: tools parse them.
!> Every writer returns '' or a message saying what failed: files are written
!> through C stdio, whose every write and close is checked (the Fortran
!> runtime does not report a write that fails when its buffer is flushed, and
!> then keeps the unit), and a file's size is compared with the bytes meant for it.
module visco2d_output
  use, intrinsic :: iso_fortran_env, only: int64
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated
  use hdf5, only: hid_t
  use visco2d_kinds, only: dp
  use visco2d_strings, only: itoa, gtoa
  use visco2d_deck, only: deck_t, analysis_name, geometry_name, total_steps, analysis_dynamic, formulation_name, &
                          initial_velocity, stop_name
  use visco2d_material, only: material_kind_name, material_kind_elastic, material_kind_uniaxial, has_memory
  use visco2d_mesh, only: edge_set_name
  use visco2d_record, only: record_t, summary_item_t
  use visco2d_system, only: file_open_write, file_write, file_close
  use visco2d_hdf5, only: h5_writer_t, h5_open_file, h5_close_file, h5_group, h5_close_group, &
                          h5_write, h5_attribute
  implicit none
  private

  public :: write_summary, write_history, write_listing, write_results_h5, unit_of, summary_unit
  public :: write_pressure
  public :: text_file_t, text_open, text_put, text_close, time_first_contact
  public :: listing_row_limit

  !> What number_kind finds in a summary value.
  integer, parameter :: number_none = 0, number_integer = 1, number_real = 2

  !> Node and element tables in the listing stop after this many rows.
  integer, parameter :: listing_row_limit = 2000

  !> A text file written line by line (C stdio: every failed write is
  !> reported); the first failure is kept, later lines are dropped.
  type :: text_file_t
    character(:), allocatable :: path
    type(c_ptr) :: stream = c_null_ptr
    integer(int64) :: bytes = 0            !< bytes meant for the file so far (lines and newlines)
    character(:), allocatable :: message   !< '' or what failed
  end type text_file_t

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

  !> Create (replace) a text file.
  subroutine text_open(file, path)
    type(text_file_t), intent(out) :: file
    character(*), intent(in) :: path
    file%path = path
    file%message = ''
    file%stream = file_open_write(path)
    if (.not. c_associated(file%stream)) file%message = 'cannot create the file'//open_reason(path)
  end subroutine text_open

  !> ': <why>' of a file that cannot be created, from the Fortran runtime ('' if it can be after all).
  function open_reason(path) result(reason)
    character(*), intent(in) :: path
    character(:), allocatable :: reason
    character(len=256) :: text
    integer :: unit, status
    reason = ''
    open(newunit=unit, file=path, status='replace', action='write', iostat=status, iomsg=text)
    if (status /= 0) then
      reason = ': '//trim(text)
    else
      close(unit, status='delete', iostat=status)
    end if
  end function open_reason

  !> Write one line (nothing after a failure); for other modules' text files.
  subroutine text_put(file, line)
    type(text_file_t), intent(inout) :: file
    character(*), intent(in) :: line
    call put(file, line)
  end subroutine text_put

  !> Write one line (nothing after a failure).
  subroutine put(file, line)
    type(text_file_t), intent(inout) :: file
    character(*), intent(in) :: line
    if (len(file%message) > 0) return
    if (file_write(file%stream, line) /= 0 .or. file_write(file%stream, new_line('a')) /= 0) then
      file%message = 'writing failed after '//itoa(file%bytes)//' bytes (disk full or a file size limit?)'
      return
    end if
    file%bytes = file%bytes + len(line) + 1
  end subroutine put

  !> Close the file (a failure to write what was still buffered shows here);
  !> then its size must be the bytes written.
  subroutine text_close(file)
    type(text_file_t), intent(inout) :: file
    integer(int64) :: size
    integer :: status
    if (.not. c_associated(file%stream)) return
    status = file_close(file%stream)
    file%stream = c_null_ptr
    if (len(file%message) > 0) return
    if (status /= 0) then
      file%message = 'writing failed when the file was closed (disk full or a file size limit?)'
      return
    end if
    inquire(file=file%path, size=size, iostat=status)
    if (status /= 0 .or. size /= file%bytes) file%message = 'only '//itoa(max(size, 0_int64))//' of '// &
      itoa(file%bytes)//' bytes reached the disk (disk full or a file size limit?)'
  end subroutine text_close


  !> summary.txt: one `key = value` per line.
  subroutine write_summary(path, record, message)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    character(:), allocatable, intent(out) :: message
    type(text_file_t) :: out
    integer :: i
    call text_open(out, path)
    do i = 1, record%nsummary
      call put(out, trim(record%summary(i)%key)//' = '//record%summary(i)%value)
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
    call put(out, line)
    do i = 1, record%nrow
      line = gtoa(record%history(1, i))
      do j = 2, size(record%columns)
        line = line//','//gtoa(record%history(j, i))
      end do
      call put(out, line)
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
    call put(out, line)
    do i = 1, size(table%values, 2)
      line = ''
      do j = 1, size(table%columns)
        if (j > 1) line = line//','
        if (trim(table%columns(j)) == 'node') then          ! the deck's node number
          line = line//itoa(nint(table%values(j, i)))
        else
          line = line//gtoa(table%values(j, i))
        end if
      end do
      call put(out, line)
    end do
    end associate
    call text_close(out)
    message = out%message
  end subroutine write_pressure

  !> The legacy-style printed listing.
  subroutine write_listing(path, case_name, deck, effects, record, message)
    character(*), intent(in) :: path, case_name, effects
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    character(:), allocatable, intent(out) :: message
    type(text_file_t) :: out
    integer :: i, k
    character(len=*), parameter :: rule = repeat('-', 78)
    character(:), allocatable :: line
    call text_open(out, path)
    associate (mesh => deck%mesh)
    call put(out, rule)
    call put(out, ' visco2d  -  axisymmetric / plane-strain viscoelastic finite elements')
    call put(out, rule)
    call put(out, ' case:  '//case_name)
    call put(out, ' title: '//deck%title)
    call put(out, ' deck:  '//deck%cards%file)
    call put(out, '')
    call put(out, ' INPUT CARDS')
    do i = 1, deck%cards%count
      call put(out, integer_field(deck%cards%cards(i)%line, 6)//'  '//deck%cards%cards(i)%text)
    end do
    call put(out, '')
    call put(out, ' CONTROL')
    call put(out, '   analysis          '//analysis_name(deck%analysis))
    call put(out, '   geometry          '//geometry_name(deck%geometry))
    call put(out, '   effects           '//effects)
    call put(out, '   formulation       '//formulation_name(deck%formulation))
    if (deck%analysis == analysis_dynamic) then
      call put(out, '   Wilson theta      '//gtoa(deck%dynamics%theta))
      associate (velocity => initial_velocity(deck))
      call put(out, '   initial velocity  ('//gtoa(velocity(1))//', '//gtoa(velocity(2))//') m/s')
      end associate
      if (any(deck%dynamics%acceleration_given)) call put(out, '   initial accel.    ('// &
        gtoa(deck%dynamics%acceleration(1))//', '//gtoa(deck%dynamics%acceleration(2))//') m/s^2 (as given)')
      if (.not. all(deck%dynamics%acceleration_given)) call put(out, &
        '   initial accel.    from equilibrium M a = R(0) + gravity (components not given)')
      call put(out, '   output            history every '//itoa(deck%output%every)//' step(s), '// &
        itoa(size(deck%output%field_times))//' requested field time(s)')
    end if
    if (deck%gravity > 0.0_dp) call put(out, '   gravity           '//gtoa(deck%gravity)//' m/s^2 in -z')
    if (deck%plate%line > 0) then
      call put(out, '   plate             z = '//gtoa(deck%plate%z)//' m, '// &
        trim(merge('STICK (u_r, u_z held)', 'SLIP (u_z held)      ', deck%plate%stick))//', RELEASE='// &
        trim(merge('YES', 'NO ', deck%plate%release)))
      if (deck%analysis == analysis_dynamic) call put(out, '   stop at           '//stop_name(deck%stop_at))
    end if
    if (size(deck%warnings) + run_warnings(record) > 0) then
      call put(out, '')
      call put(out, ' WARNINGS')
      do k = 1, size(deck%warnings)
        call put(out, '   '//deck%warnings(k)%text)
      end do
      do k = 1, run_warnings(record)
        call put(out, '   '//record%warnings(k)%text)
      end do
    end if
    call put(out, '')
    call put(out, ' MESH')
    call put(out, '   source            '//mesh%source)
    call put(out, '   nodes             '//itoa(mesh%nnode))
    call put(out, '   elements          '//itoa(mesh%nelem))
    call put(out, '   equations         '//itoa(2*mesh%nnode))
    call put(out, '   half-bandwidth    '//itoa(mesh%half_bandwidth_before)//' as input, '// &
                  itoa(mesh%half_bandwidth)//' after reverse Cuthill-McKee')
    call put(out, '')
    call put(out, ' MATERIALS')
    call put(out, '   id           kind          E(0) (Pa)       nu(0)     G(0) (Pa)       K (Pa)          rho (kg/m3)')
    do k = 1, size(deck%materials)
      associate (m => deck%materials(k))
      call put(out, '   '//text_field(m%id, 12)//' '//text_field(material_kind_name(m%kind), 12)//' '// &
        real_field(m%young, 15, 7)//' '//real_field(m%poisson, 9, 2, fixed=6)//' '//real_field(m%shear, 15, 7)//' '// &
        real_field(m%bulk, 15, 7)//' '//real_field(m%density, 15, 7))
      if (m%kind == material_kind_uniaxial) then
        call put(out, '     uniaxial relaxation E(t) = sum E_i exp(-alpha_i t), eq. [47], as given:')
        do i = 1, size(m%uniaxial_young)
          call put(out, '       E_i = '//real_field(m%uniaxial_young(i), 16, 8)//' Pa   alpha_i = '// &
            real_field(m%uniaxial_rate(i), 16, 8)//' 1/s')
        end do
        call put(out, '     converted exactly (eq. [48], partial fractions) to the shear terms below')
      end if
      if (m%kind /= material_kind_elastic) then
        call put(out, '     shear relaxation phi1(t) = G_inf + sum G_m exp(-beta_m t), eq. [12]:')
        call put(out, '       G_inf = '//real_field(m%long_term_shear, 16, 8)//' Pa')
        if (has_memory(m)) then
          do i = 1, size(m%prony_shear)
            call put(out, '       G_m = '//real_field(m%prony_shear(i), 16, 8)//' Pa   beta_m = '// &
              real_field(m%prony_rate(i), 16, 8)//' 1/s')
          end do
        end if
      end if
      end associate
    end do
    if (size(deck%stages) > 0) then
      call put(out, '')
      call put(out, ' TIME STAGES  (line, steps, dt (s), end (s))')
      do k = 1, size(deck%stages)
        call put(out, integer_field(deck%stages(k)%line, 9)//integer_field(deck%stages(k)%steps, 9)//' '// &
          real_field(deck%stages(k)%dt, 16, 8)//' '//real_field(deck%stages(k)%end_time, 16, 8))
      end do
      if (deck%analysis == analysis_dynamic) then
        call put(out, '   '//itoa(total_steps(deck))//' Wilson-theta steps from the initial state at t = 0')
      else
        call put(out, '   '//itoa(total_steps(deck))//' steps after the instantaneous response at t = 0')
      end if
    end if
    if (size(deck%curves) > 0) then
      call put(out, '')
      call put(out, ' CURVES  (name: time (s) -> factor; constant outside the points)')
      do k = 1, size(deck%curves)
        call put(out, '   '//deck%curves(k)%name//':')
        do i = 1, size(deck%curves(k)%time)
          call put(out, '       '//real_field(deck%curves(k)%time(i), 16, 8)//' -> '// &
            real_field(deck%curves(k)%value(i), 16, 8))
        end do
      end do
    end if
    call put(out, '')
    call put(out, ' NODES  (number, r (m), z (m), band position)')
    do i = 1, min(mesh%nnode, listing_row_limit)
      call put(out, integer_field(mesh%node_id(i), 9)//' '//real_field(mesh%xy(1, i), 16, 8)//' '// &
        real_field(mesh%xy(2, i), 16, 8)//integer_field(mesh%equation(i), 9))
    end do
    if (mesh%nnode > listing_row_limit) call put(out, '   ... '//itoa(mesh%nnode - listing_row_limit)// &
      ' more nodes: see results.h5 /mesh/nodes')
    call put(out, '')
    call put(out, ' ELEMENTS  (number, nodes 1-4, material)')
    do i = 1, min(mesh%nelem, listing_row_limit)
      line = integer_field(mesh%element_id(i), 9)
      do k = 1, 4
        line = line//integer_field(mesh%node_id(mesh%connectivity(k, i)), 9)
      end do
      call put(out, line//'  '//trim(mesh%element_material_name(i)))
    end do
    if (mesh%nelem > listing_row_limit) call put(out, '   ... '//itoa(mesh%nelem - listing_row_limit)// &
      ' more elements: see results.h5 /mesh/elements')
    call put(out, '')
    call put(out, ' SUPPORTS AND LOADS')
    do k = 1, size(deck%fixes)
      call put(out, '   FIX      line '//itoa(deck%fixes(k)%line)//': '//itoa(size(deck%fixes(k)%nodes))// &
        ' node(s), '//merge('u_r ', '    ', deck%fixes(k)%fix_r)//merge('u_z', '   ', deck%fixes(k)%fix_z)// &
        trim(prescribed_text(deck, k)))
    end do
    do k = 1, size(deck%pressures)
      call put(out, '   PRESSURE line '//itoa(deck%pressures(k)%line)//': '// &
        edge_set_name(deck%pressures(k)%edge_set)//' p = '//gtoa(deck%pressures(k)%value)//' Pa'// &
        curve_text(deck, deck%pressures(k)%curve))
    end do
    do k = 1, size(deck%forces)
      call put(out, '   FORCE    line '//itoa(deck%forces(k)%line)//': node '// &
        itoa(mesh%node_id(deck%forces(k)%node))//' F = ('//gtoa(deck%forces(k)%value(1))//', '// &
        gtoa(deck%forces(k)%value(2))//') N'//curve_text(deck, deck%forces(k)%curve))
    end do
    call put(out, '')
    call put(out, ' RESULTS')
    do i = 1, record%nsummary
      call put(out, '   '//trim(record%summary(i)%key)//' = '//record%summary(i)%value)
    end do
    if (record%nrow > 0) then
      call put(out, '')
      call put(out, ' HISTORY (first and last rows; all rows in history.csv)')
      line = ''
      do k = 1, size(record%columns)
        line = line//text_field(record%columns(k)(1:min(16, len_trim(record%columns(k)))), 16, right=.true.)
        if (k < size(record%columns)) line = line//' '
      end do
      call put(out, line)
      do i = 1, record%nrow
        if (i > 20 .and. i < record%nrow - 20) cycle
        line = ''
        do k = 1, size(record%columns)
          line = line//real_field(record%history(k, i), 16, 8)
        if (k < size(record%columns)) line = line//' '
        end do
        call put(out, line)
      end do
    end if
    call put(out, rule)
    end associate
    call text_close(out)
    message = out%message
  end subroutine write_listing

  !> A real right-aligned in `width` characters: es format with `digits`
  !> decimals and a 3-digit exponent (with its letter: 1.0E+300, never
  !> 1.0+300), or f format with `fixed` decimals where that fits; never '*'.
  function real_field(value, width, digits, fixed) result(text)
    real(dp), intent(in) :: value
    integer, intent(in) :: width, digits
    integer, intent(in), optional :: fixed
    character(:), allocatable :: text
    character(len=64) :: buffer
    character(len=32) :: form
    if (present(fixed)) then
      write(form, '(a, i0, a, i0, a)') '(f', width, '.', fixed, ')'
      write(buffer, form) value
      if (index(buffer(1:width), '*') == 0) then
        text = buffer(1:width)
        return
      end if
    end if
    write(form, '(a, i0, a)') '(es32.', digits, 'e3)'
    write(buffer, form) value
    text = text_field(trim(adjustl(buffer)), width, right=.true.)
  end function real_field

  !> An integer right-aligned in `width` characters (wider if it needs more).
  function integer_field(value, width) result(text)
    integer, intent(in) :: value, width
    character(:), allocatable :: text
    text = text_field(itoa(value), width, right=.true.)
  end function integer_field

  !> Text padded with blanks to `width` (left-aligned, or right-aligned); longer text is kept whole.
  pure function text_field(text, width, right) result(field)
    character(*), intent(in) :: text
    integer, intent(in) :: width
    logical, intent(in), optional :: right
    character(:), allocatable :: field
    logical :: to_right
    to_right = .false.
    if (present(right)) to_right = right
    if (len(text) >= width) then
      field = text
    else if (to_right) then
      field = repeat(' ', width - len(text))//text
    else
      field = text//repeat(' ', width - len(text))
    end if
  end function text_field

  !> Number of run-time warnings in a record.
  pure integer function run_warnings(record)
    type(record_t), intent(in) :: record
    run_warnings = 0
    if (allocated(record%warnings)) run_warnings = size(record%warnings)
  end function run_warnings

  !> About the size of results.h5: its arrays and 64 kB for groups and attributes.
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

  !> ' x curve NAME' or '' (constant in time).
  function curve_text(deck, curve) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: curve
    character(:), allocatable :: text
    text = ''
    if (curve > 0) text = ' x curve '//deck%curves(curve)%name
  end function curve_text

  !> ', prescribed u_r = .., u_z = .. m [x curve]' for a FIX card with values.
  function prescribed_text(deck, k) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: k
    character(:), allocatable :: text
    text = ''
    associate (fix => deck%fixes(k))
    if (all(fix%value == 0.0_dp)) return
    text = ', prescribed'
    if (fix%fix_r) text = text//' u_r = '//gtoa(fix%value(1))//' m'
    if (fix%fix_z) text = text//' u_z = '//gtoa(fix%value(2))//' m'
    text = text//curve_text(deck, fix%curve)
    end associate
  end function prescribed_text

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

  !> results.h5: /mesh, /summary/<key>, /history/<column>, /fields/<snapshot>/...
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
    call h5_attribute(writer, writer%file, 'geometry', geometry_name(deck%geometry))
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
