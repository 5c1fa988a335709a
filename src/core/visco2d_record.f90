!> What a run produces, independent of how it is written: summary
!> `key = value` lines, the history table (one row per output step) and
!> field snapshots. Solvers fill a record; `visco2d_output` writes it.
!> A summary value is kept as what it is (a real in full double precision,
!> an integer, a logical or a text) and becomes text only when it is written
!> (summary_item_text): summary.txt shows a real with 10 significant digits,
!> results.h5's /summary holds the double itself.
module visco2d_record
  use visco2d_kinds, only: dp
  use visco2d_strings, only: table_real, integer_text, message_real
  implicit none
  private

  public :: record_t, snapshot_t, summary_item_t, table_t
  public :: record_put, record_put_real, record_put_integer, record_put_logical
  public :: record_find, record_real, record_integer, record_text, summary_item_text, unit_of, summary_unit
  public :: history_define, history_append, record_add_snapshot, record_insert_snapshot, record_column
  public :: run_warning_t, record_warn, gauss_field_t

  !> The kinds of a summary value (summary_item_t%kind).
  integer, parameter, public :: summary_text = 0, summary_real = 1, summary_integer = 2, summary_logical = 3

  !> One `key = value` line of summary.txt, typed. The key is kept whole, however
  !> long (expect_probe_<name>_..._within_rtol keys are long).
  type :: summary_item_t
    character(:), allocatable :: key
    integer :: kind = summary_text                !< summary_text, _real, _integer or _logical
    character(:), allocatable :: text             !< the value of a text item
    real(dp) :: real_value = 0.0_dp               !< the value of a real item, full precision
    integer :: integer_value = 0                  !< the value of an integer item
    logical :: logical_value = .false.            !< the value of a logical item (written yes / no)
    integer :: digits = 10                        !< significant digits summary.txt shows of a real:
                                                  !< 10 (table_real) or 4 (message_real, the CPU time)
    character(:), allocatable :: unit             !< of a number, from the key's suffix (summary_unit)
  end type summary_item_t

  !> Fields at one instant. Nodal arrays are (components, nnode).
  type :: snapshot_t
    character(:), allocatable :: name          !< group name, sorts in time order
    character(:), allocatable :: label         !< why it was taken (e.g. 'final', 'max_deformation')
    real(dp) :: time = 0.0_dp                  !< s
    real(dp), allocatable :: displacement(:, :) !< (2, nnode) u_r, u_z in m
    real(dp), allocatable :: velocity(:, :)     !< (2, nnode) m/s (dynamic runs only)
    real(dp), allocatable :: acceleration(:, :) !< (2, nnode) m/s^2 (dynamic runs only)
    real(dp), allocatable :: stress(:, :)       !< (4, nnode) nodal average of sigma_r, sigma_z, sigma_theta, tau_rz in Pa
    real(dp), allocatable :: stress_gauss(:, :, :) !< (4, 4, nelem) at the Gauss points, Pa
    real(dp), allocatable :: max_shear(:)       !< (nnode) Pa
    real(dp), allocatable :: von_mises(:)       !< (nnode) Pa
  end type snapshot_t

  !> A table of numbers with named columns (units in the names, as history
  !> columns), e.g. the contact pressure over radius (pressure.csv).
  type :: table_t
    character(:), allocatable :: columns(:)    !< column names; unallocated: no table
    real(dp), allocatable :: values(:, :)      !< (ncolumn, nrow)
  end type table_t

  !> A field at the Gauss points and its nodal average (the BRUISE envelopes, /bruise in results.h5).
  type :: gauss_field_t
    character(:), allocatable :: name
    character(:), allocatable :: units
    real(dp), allocatable :: gauss(:, :)  !< (4, nelem): Gauss points ordered like the element's corners
    real(dp), allocatable :: nodal(:)     !< (nnode): mean over the node's elements of their nearest Gauss point
  end type gauss_field_t

  !> A warning found while solving (`file:line: CARD: text`, like a deck's warning).
  type :: run_warning_t
    character(:), allocatable :: text
  end type run_warning_t

  !> The results of one run.
  type :: record_t
    type(summary_item_t), allocatable :: summary(:)
    integer :: nsummary = 0
    character(:), allocatable :: columns(:)                !< history column names (with unit suffix), as long as given
    real(dp), allocatable :: history(:, :)                 !< (ncolumn, capacity)
    integer :: nrow = 0
    type(snapshot_t), allocatable :: snapshots(:)
    type(table_t) :: pressure                              !< contact pressure over radius at the impact's
                                                           !< maxima (visco2d_impact); no columns otherwise
    type(run_warning_t), allocatable :: warnings(:)        !< run-time warnings (record_warn); the driver prints
                                                           !< them and counts them in the summary's `warnings`
    type(gauss_field_t), allocatable :: bruise_fields(:)   !< envelopes of a deck with BRUISE cards (else unallocated)
  end type record_t

contains

  !> Unit of a history column or summary key, from its suffix ('t_ms' -> 'ms';
  !> '1' for none known).
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

  !> Index of a summary key in the record, 0 if absent.
  pure integer function record_find(record, key) result(index)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    do index = 1, record%nsummary
      if (record%summary(index)%key == key) return
    end do
    index = 0
  end function record_find

  !> The item of `key`, emptied of its old value (appended if the key is new).
  function summary_slot(record, key) result(i)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key
    integer :: i
    type(summary_item_t), allocatable :: bigger(:)
    if (.not. allocated(record%summary)) allocate(record%summary(32))
    i = record_find(record, key)
    if (i == 0) then
      if (record%nsummary == size(record%summary)) then
        allocate(bigger(2*size(record%summary)))
        bigger(1:record%nsummary) = record%summary(1:record%nsummary)
        call move_alloc(bigger, record%summary)
      end if
      record%nsummary = record%nsummary + 1
      i = record%nsummary
    end if
    record%summary(i) = summary_item_t(key=key)
  end function summary_slot

  !> Set (or replace) a text summary value.
  subroutine record_put(record, key, value)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key, value
    integer :: i
    i = summary_slot(record, key)
    record%summary(i)%text = value
  end subroutine record_put

  !> Set a real summary value, kept in full precision; summary.txt shows it
  !> with 10 significant digits (table_real), or 4 (message_real) if digits = 4.
  subroutine record_put_real(record, key, value, digits)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key
    real(dp), intent(in) :: value
    integer, intent(in), optional :: digits
    integer :: i
    i = summary_slot(record, key)
    record%summary(i)%kind = summary_real
    record%summary(i)%real_value = value
    record%summary(i)%unit = summary_unit(key)
    if (present(digits)) record%summary(i)%digits = digits
  end subroutine record_put_real

  !> Set an integer summary value.
  subroutine record_put_integer(record, key, value)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key
    integer, intent(in) :: value
    integer :: i
    i = summary_slot(record, key)
    record%summary(i)%kind = summary_integer
    record%summary(i)%integer_value = value
    record%summary(i)%unit = summary_unit(key)
  end subroutine record_put_integer

  !> Set a logical summary value (written yes / no).
  subroutine record_put_logical(record, key, value)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key
    logical, intent(in) :: value
    integer :: i
    i = summary_slot(record, key)
    record%summary(i)%kind = summary_logical
    record%summary(i)%logical_value = value
  end subroutine record_put_logical

  !> A summary value as summary.txt shows it: a real with table_real (10 significant
  !> digits; message_real for digits = 4), an integer with integer_text, a logical as yes / no.
  function summary_item_text(item) result(text)
    type(summary_item_t), intent(in) :: item
    character(:), allocatable :: text
    select case (item%kind)
    case (summary_real)
      if (item%digits == 4) then
        text = message_real(item%real_value)
      else
        text = table_real(item%real_value)
      end if
    case (summary_integer)
      text = integer_text(item%integer_value)
    case (summary_logical)
      text = trim(merge('yes', 'no ', item%logical_value))
    case default
      text = ''
      if (allocated(item%text)) text = item%text
    end select
  end function summary_item_text

  !> The summary value of `key` as summary.txt shows it ('' if absent).
  function record_text(record, key) result(text)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    character(:), allocatable :: text
    integer :: i
    text = ''
    i = record_find(record, key)
    if (i > 0) text = summary_item_text(record%summary(i))
  end function record_text

  !> The number of a real or integer summary key, in full precision, or with
  !> `as_shown` the number summary.txt shows (a real rounded to the digits
  !> summary_item_text writes); `found` is false (and value 0) if the key is
  !> absent or not a number.
  subroutine record_real(record, key, value, found, as_shown)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    real(dp), intent(out) :: value
    logical, intent(out) :: found
    logical, intent(in), optional :: as_shown
    character(:), allocatable :: text
    integer :: i, status
    value = 0.0_dp
    found = .false.
    i = record_find(record, key)
    if (i == 0) return
    select case (record%summary(i)%kind)
    case (summary_real)
      value = record%summary(i)%real_value
      found = .true.
      if (present(as_shown)) then
        if (as_shown) then
          text = summary_item_text(record%summary(i))
          read(text, *, iostat=status) value
          if (status /= 0) value = record%summary(i)%real_value     ! NaN, Infinity
        end if
      end if
    case (summary_integer)
      value = real(record%summary(i)%integer_value, dp)
      found = .true.
    end select
  end subroutine record_real

  !> The value of an integer summary key; `found` is false (and value 0)
  !> if the key is absent or not an integer.
  subroutine record_integer(record, key, value, found)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    integer, intent(out) :: value
    logical, intent(out) :: found
    integer :: i
    value = 0
    found = .false.
    i = record_find(record, key)
    if (i == 0) return
    if (record%summary(i)%kind /= summary_integer) return
    value = record%summary(i)%integer_value
    found = .true.
  end subroutine record_integer

  !> Add a run-time warning, located like an error (`file:line: CARD: message`;
  !> the parts not given are left out). The driver prints it on stderr after the
  !> solve, lists it in listing.txt and counts it in the summary's `warnings`.
  subroutine record_warn(record, message, file, line, card)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: message
    character(*), intent(in), optional :: file, card
    integer, intent(in), optional :: line
    type(run_warning_t) :: warning
    warning%text = ''
    if (present(file)) then
      if (len(file) > 0) then
        warning%text = file
        if (present(line)) then
          if (line > 0) warning%text = warning%text//':'//integer_text(line)
        end if
        warning%text = warning%text//': '
      end if
    end if
    if (present(card)) then
      if (len(card) > 0) warning%text = warning%text//card//': '
    end if
    warning%text = warning%text//message
    if (.not. allocated(record%warnings)) allocate(record%warnings(0))
    record%warnings = [record%warnings, warning]
  end subroutine record_warn

  !> Define the history columns (names carry their unit, e.g. 't_ms').
  subroutine history_define(record, columns, capacity)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: columns(:)
    integer, intent(in), optional :: capacity
    integer :: rows
    rows = 64
    if (present(capacity)) rows = max(capacity, 1)
    if (allocated(record%columns)) deallocate(record%columns)
    if (allocated(record%history)) deallocate(record%history)
    allocate(character(len=len(columns)) :: record%columns(size(columns)))
    record%columns = columns
    allocate(record%history(size(columns), rows))
    record%nrow = 0
  end subroutine history_define

  !> Index of a history column by name, 0 if absent.
  pure integer function record_column(record, name) result(index)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: name
    do index = 1, size(record%columns)
      if (record%columns(index) == name) return
    end do
    index = 0
  end function record_column

  !> Append one row to the history (grows geometrically: no per-step allocation).
  subroutine history_append(record, row)
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: row(:)
    real(dp), allocatable :: bigger(:, :)
    if (record%nrow == size(record%history, 2)) then
      allocate(bigger(size(record%history, 1), 2*size(record%history, 2)))
      bigger(:, 1:record%nrow) = record%history(:, 1:record%nrow)
      call move_alloc(bigger, record%history)
    end if
    record%nrow = record%nrow + 1
    record%history(:, record%nrow) = row
  end subroutine history_append

  !> Keep a snapshot, last. Its arrays are moved into the record (`snapshot`
  !> is left without them), and the snapshots already kept are moved, not
  !> copied, into the longer list: a deep copy of every kept snapshot at each
  !> append held the fields twice and left the freed copies resident, which
  !> doubled the memory of a run with 60 FIELDS= times.
  subroutine record_add_snapshot(record, snapshot)
    type(record_t), intent(inout) :: record
    type(snapshot_t), intent(inout) :: snapshot
    integer :: n
    n = 0
    if (allocated(record%snapshots)) n = size(record%snapshots)
    call place_snapshot(record, snapshot, n + 1)
  end subroutine record_add_snapshot

  !> Keep a snapshot in time order (moved, as record_add_snapshot); one taken
  !> at the time of a kept snapshot adds its label to that one ('final;
  !> maximum deformation').
  subroutine record_insert_snapshot(record, snapshot)
    type(record_t), intent(inout) :: record
    type(snapshot_t), intent(inout) :: snapshot
    integer :: k, position
    if (.not. allocated(record%snapshots)) allocate(record%snapshots(0))
    position = size(record%snapshots) + 1
    do k = 1, size(record%snapshots)
      if (record%snapshots(k)%time == snapshot%time) then
        record%snapshots(k)%label = record%snapshots(k)%label//'; '//snapshot%label
        return
      end if
      if (record%snapshots(k)%time > snapshot%time) then
        position = k
        exit
      end if
    end do
    call place_snapshot(record, snapshot, position)
  end subroutine record_insert_snapshot

  !> Put `snapshot` at `position` (1 to size + 1) of the record's list, moving
  !> it and the kept ones into a list one longer.
  subroutine place_snapshot(record, snapshot, position)
    type(record_t), intent(inout) :: record
    type(snapshot_t), intent(inout) :: snapshot
    integer, intent(in) :: position
    type(snapshot_t), allocatable :: kept(:)
    integer :: k, n
    n = 0
    if (allocated(record%snapshots)) then
      n = size(record%snapshots)
      call move_alloc(record%snapshots, kept)
    end if
    allocate(record%snapshots(n + 1))
    do k = 1, position - 1
      call move_snapshot(kept(k), record%snapshots(k))
    end do
    call move_snapshot(snapshot, record%snapshots(position))
    do k = position, n
      call move_snapshot(kept(k), record%snapshots(k + 1))
    end do
  end subroutine place_snapshot

  !> Move a snapshot's arrays from `from` to `to` (no copy of the fields).
  subroutine move_snapshot(from, to)
    type(snapshot_t), intent(inout) :: from, to
    if (allocated(from%name)) to%name = from%name
    if (allocated(from%label)) to%label = from%label
    to%time = from%time
    call move_alloc(from%displacement, to%displacement)
    call move_alloc(from%velocity, to%velocity)
    call move_alloc(from%acceleration, to%acceleration)
    call move_alloc(from%stress, to%stress)
    call move_alloc(from%stress_gauss, to%stress_gauss)
    call move_alloc(from%max_shear, to%max_shear)
    call move_alloc(from%von_mises, to%von_mises)
  end subroutine move_snapshot
end module visco2d_record
