!> Error object carried from where a problem is found to the top level,
!> in the style of fpm's parse errors: `file:line:column: CARD: message`.
module visco2d_error
  implicit none
  private

  public :: error_t, set_error, error_text, locate_error

  !> A located error. `line`/`column` are 0 when unknown.
  type :: error_t
    character(:), allocatable :: file     !< deck file name ('' if none)
    integer :: line = 0                    !< 1-based line number in `file`
    integer :: column = 0                  !< 1-based column of the offending field
    character(:), allocatable :: card     !< card keyword, e.g. 'MATERIAL' ('' if none)
    character(:), allocatable :: message  !< what was expected and what was found
  end type error_t

contains

  !> Allocate `error` and fill it in.
  pure subroutine set_error(error, message, file, line, column, card)
    type(error_t), allocatable, intent(inout) :: error
    character(*), intent(in) :: message
    character(*), intent(in), optional :: file, card
    integer, intent(in), optional :: line, column
    if (allocated(error)) deallocate(error)
    allocate(error)
    error%message = message
    error%file = ''
    error%card = ''
    if (present(file)) error%file = file
    if (present(card)) error%card = card
    if (present(line)) error%line = line
    if (present(column)) error%column = column
  end subroutine set_error

  !> Locate an error found where the deck is not known (a failed solve of a
  !> factor): if it names no file, give it `file` (and `line`, `card`) and
  !> append `where` to its message (' at step 12 (t = ...)'). A located
  !> error is left as it is.
  pure subroutine locate_error(error, file, line, card, where)
    type(error_t), intent(inout) :: error
    character(*), intent(in) :: file
    integer, intent(in), optional :: line
    character(*), intent(in), optional :: card, where
    if (allocated(error%file)) then
      if (len(error%file) > 0) return
    end if
    error%file = file
    if (present(line)) error%line = line
    if (present(card)) error%card = card
    if (present(where)) error%message = error%message//where
  end subroutine locate_error

  !> One-line text of an error: `file:line:col: CARD: message`.
  pure function error_text(error) result(text)
    type(error_t), intent(in) :: error
    character(:), allocatable :: text
    character(len=16) :: buffer
    text = ''
    if (allocated(error%file)) then
      if (len(error%file) > 0) then
        text = error%file
        if (error%line > 0) then
          write(buffer, '(i0)') error%line
          text = text//':'//trim(buffer)
          if (error%column > 0) then
            write(buffer, '(i0)') error%column
            text = text//':'//trim(buffer)
          end if
        end if
        text = text//': '
      end if
    end if
    if (allocated(error%card)) then
      if (len(error%card) > 0) text = text//error%card//': '
    end if
    text = text//error%message
  end function error_text
end module visco2d_error
