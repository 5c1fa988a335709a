!> A small assertion module shared by the test programs, with the few helpers
!> they share. Each check prints one line, `PASS name` or `FAIL name: detail`;
!> the test runner counts them.
module visco2d_testing
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_record, only: record_t, record_column, record_real
  use visco2d_expect, only: summary_value
  implicit none
  private

  public :: check, check_close, check_text_contains, test_summary, failures, write_deck
  public :: history_index, history_column, history_last, summary_real, message_of, exact_text, read_lines

  integer, save :: passes = 0, failures = 0

contains

  !> A boolean check.
  subroutine check(name, condition, detail)
    character(*), intent(in) :: name
    logical, intent(in) :: condition
    character(*), intent(in), optional :: detail
    if (condition) then
      passes = passes + 1
      print '(a)', 'PASS '//name
    else
      failures = failures + 1
      if (present(detail)) then
        print '(a)', 'FAIL '//name//': '//detail
      else
        print '(a)', 'FAIL '//name
      end if
    end if
  end subroutine check

  !> |actual - expected| <= rtol |expected| + atol.
  subroutine check_close(name, actual, expected, rtol, atol)
    character(*), intent(in) :: name
    real(dp), intent(in) :: actual, expected, rtol
    real(dp), intent(in), optional :: atol
    real(dp) :: tolerance
    character(len=160) :: detail
    tolerance = rtol*abs(expected)
    if (present(atol)) tolerance = tolerance + atol
    write(detail, '(a, es23.15, a, es23.15, a, es10.3, a, es10.3)') 'got ', actual, ', expected ', expected, &
      ', |error| ', abs(actual - expected), ' > tolerance ', tolerance
    call check(name, abs(actual - expected) <= tolerance .and. actual == actual, trim(detail))
  end subroutine check_close

  !> The text contains the fragment.
  subroutine check_text_contains(name, text, fragment)
    character(*), intent(in) :: name, text, fragment
    call check(name, index(text, fragment) > 0, 'expected "'//fragment//'" in "'//text//'"')
  end subroutine check_text_contains

  !> Print this program's count; stop with status 1 if a check failed.
  subroutine test_summary(program_name)
    character(*), intent(in) :: program_name
    print '(a, ": ", i0, " passed, ", i0, " failed")', program_name, passes, failures
    if (failures > 0) error stop 1, quiet=.true.
  end subroutine test_summary

  !> Write the lines of a test deck to a file (trailing blanks trimmed).
  subroutine write_deck(path, deck_lines)
    character(*), intent(in) :: path
    character(*), intent(in) :: deck_lines(:)
    integer :: unit, i
    open(newunit=unit, file=path, status='replace', action='write')
    do i = 1, size(deck_lines)
      write(unit, '(a)') trim(deck_lines(i))
    end do
    close(unit)
  end subroutine write_deck

  !> Index of a history column of a record (0 if absent).
  integer function history_index(record, name) result(index)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: name
    index = record_column(record, name)
  end function history_index

  !> A history column over the rows (empty, and a failed check, if absent).
  function history_column(record, name) result(values)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: name
    real(dp), allocatable :: values(:)
    integer :: k
    k = history_index(record, name)
    if (k == 0) then
      allocate(values(0))
      call check('column_'//name, .false., 'no history column '//name)
    else
      values = record%history(k, 1:record%nrow)
    end if
  end function history_column

  !> The last row of a history column (huge, and a failed check, if absent).
  real(dp) function history_last(record, name) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: name
    real(dp), allocatable :: values(:)
    values = history_column(record, name)
    value = huge(1.0_dp)
    if (size(values) > 0) value = values(size(values))
  end function history_last

  !> A real summary value of a record; if the key is absent or not a number,
  !> a failed check and `missing` (default NaN).
  real(dp) function summary_real(record, key, missing) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    real(dp), intent(in), optional :: missing
    character(:), allocatable :: text
    logical :: found
    value = ieee_value(1.0_dp, ieee_quiet_nan)
    if (present(missing)) value = missing
    text = summary_value(record, key)
    if (len(text) == 0) then
      call check('summary key '//key, .false., 'absent')
      return
    end if
    call record_real(record, key, value, found)       ! full precision
    if (.not. found) then
      value = ieee_value(1.0_dp, ieee_quiet_nan)
      if (present(missing)) value = missing
      call check('summary key '//key, .false., 'not a number: '//text)
    end if
  end function summary_real

  !> The text of an error ('' if there is none).
  function message_of(error) result(text)
    type(error_t), allocatable, intent(in) :: error
    character(:), allocatable :: text
    text = ''
    if (allocated(error)) text = error_text(error)
  end function message_of

  !> A real as text with 17 significant digits (ES24.16, leading blanks
  !> removed), which reads back as the same double: for deck cards and details.
  function exact_text(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es24.16)') value
    text = trim(adjustl(buffer))
  end function exact_text

  !> The lines of a text file (of at most 4096 characters each), all as long
  !> as the longest; `found` is false, and there are no lines, if the file
  !> cannot be opened. `delete`: remove the file once read.
  subroutine read_lines(path, lines, found, delete)
    character(*), intent(in) :: path
    character(:), allocatable, intent(out) :: lines(:)
    logical, intent(out) :: found
    logical, intent(in), optional :: delete
    character(len=4096) :: buffer
    integer :: unit, status, count, width, k
    allocate(character(len=0) :: lines(0))
    open(newunit=unit, file=path, status='old', action='read', iostat=status)
    found = status == 0
    if (.not. found) return
    count = 0
    width = 0
    do
      read(unit, '(a)', iostat=status) buffer
      if (status /= 0) exit
      count = count + 1
      width = max(width, len_trim(buffer))
    end do
    rewind(unit)
    deallocate(lines)
    allocate(character(len=width) :: lines(count))
    do k = 1, count
      read(unit, '(a)') lines(k)
    end do
    close(unit, status=merge('delete', 'keep  ', present_and_true(delete)))
  end subroutine read_lines

  !> An optional flag that is present and true.
  pure logical function present_and_true(flag)
    logical, intent(in), optional :: flag
    present_and_true = .false.
    if (present(flag)) present_and_true = flag
  end function present_and_true
end module visco2d_testing
