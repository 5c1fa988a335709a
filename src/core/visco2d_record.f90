!> What a run produces, independent of how it is written: summary
!> `key = value` lines, the history table (one row per output step) and
!> field snapshots. Solvers fill a record; `visco2d_output` writes it.
module visco2d_record
  use visco2d_kinds, only: dp
  use visco2d_strings, only: table_real, integer_text
  implicit none
  private

  public :: record_t, snapshot_t, summary_item_t, table_t
  public :: record_put, record_put_real, record_put_integer
  public :: history_define, history_append, record_add_snapshot, record_insert_snapshot, record_column
  public :: run_warning_t, record_warn, gauss_field_t

  !> One `key = value` line of summary.txt. The key is kept whole, however
  !> long (expect_probe_<name>_..._within_rtol keys are long).
  type :: summary_item_t
    character(:), allocatable :: key
    character(:), allocatable :: value
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

  !> Set (or replace) a summary value given as text.
  subroutine record_put(record, key, value)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key, value
    type(summary_item_t), allocatable :: bigger(:)
    integer :: i
    if (.not. allocated(record%summary)) allocate(record%summary(32))
    do i = 1, record%nsummary
      if (record%summary(i)%key == key) then
        record%summary(i)%value = value
        return
      end if
    end do
    if (record%nsummary == size(record%summary)) then
      allocate(bigger(2*size(record%summary)))
      bigger(1:record%nsummary) = record%summary(1:record%nsummary)
      call move_alloc(bigger, record%summary)
    end if
    record%nsummary = record%nsummary + 1
    record%summary(record%nsummary)%key = key
    record%summary(record%nsummary)%value = value
  end subroutine record_put

  !> Set a real summary value (10 significant digits).
  subroutine record_put_real(record, key, value)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key
    real(dp), intent(in) :: value
    call record_put(record, key, table_real(value))
  end subroutine record_put_real

  subroutine record_put_integer(record, key, value)
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: key
    integer, intent(in) :: value
    call record_put(record, key, integer_text(value))
  end subroutine record_put_integer

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
