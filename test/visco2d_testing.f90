!> A small assertion module shared by the test programs. Each check prints
!> one line, `PASS name` or `FAIL name: detail`; the test runner counts them.
module visco2d_testing
  use visco2d_kinds, only: dp
  use visco2d_record, only: record_t, record_column
  implicit none
  private

  public :: check, check_close, check_text_contains, test_summary, failures, write_deck
  public :: history_index, history_column, history_last

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
end module visco2d_testing
