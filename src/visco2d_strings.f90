!> Small text helpers: numbers to strings for messages and listings.
module visco2d_strings
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: itoa, rtoa, gtoa, short_real, to_upper, to_lower

contains

  !> Integer as text without blanks.
  pure function itoa(value) result(text)
    integer, intent(in) :: value
    character(:), allocatable :: text
    character(len=16) :: buffer
    write(buffer, '(i0)') value
    text = trim(buffer)
  end function itoa

  !> Real as text with 4 significant decimals (for messages).
  pure function rtoa(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es12.4)') value
    text = trim(adjustl(buffer))
  end function rtoa

  !> Real as text with 10 significant digits (for summaries and tables).
  pure function gtoa(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buffer
    if (value == 0.0_dp) then
      text = '0'
      return
    end if
    write(buffer, '(es17.9e3)') value
    text = trim(adjustl(buffer))
  end function gtoa

  !> Shortest text (up to 15 significant digits) that reads back as the value:
  !> 0.7 -> '0.7', 18.11e6 -> '18110000.0', 1e-7 -> '0.1E-06'.
  function short_real(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=40) :: buffer, form
    real(dp) :: back
    integer :: digits, ios
    do digits = 1, 15
      write(form, '(a, i0, a)') '(g0.', digits, ')'
      write(buffer, form) value
      read(buffer, *, iostat=ios) back
      if (ios == 0 .and. back == value) exit
    end do
    text = trim(adjustl(buffer))
    if (text(len(text):) == '.') text = text//'0'     ! '1.' -> '1.0'
  end function short_real

  !> Upper-case copy of a string.
  pure function to_upper(text) result(upper)
    character(*), intent(in) :: text
    character(len(text)) :: upper
    integer :: i, code
    upper = text
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code >= iachar('a') .and. code <= iachar('z')) upper(i:i) = achar(code - 32)
    end do
  end function to_upper

  !> Lower-case copy of a string.
  pure function to_lower(text) result(lower)
    character(*), intent(in) :: text
    character(len(text)) :: lower
    integer :: i, code
    lower = text
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code >= iachar('A') .and. code <= iachar('Z')) lower(i:i) = achar(code + 32)
    end do
  end function to_lower
end module visco2d_strings
