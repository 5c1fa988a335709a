!> Small text helpers: numbers to strings for messages and listings.
module visco2d_strings
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: integer_text, message_real, table_real, es_field, short_real, compact_real, to_upper, to_lower, nearest_word

  !> Integer (default or 64-bit) as text without blanks.
  interface integer_text
    module procedure integer_text_default, integer_text_int64
  end interface integer_text

contains

  !> Integer as text without blanks.
  pure function integer_text_default(value) result(text)
    integer, intent(in) :: value
    character(:), allocatable :: text
    character(len=16) :: buffer
    write(buffer, '(i0)') value
    text = trim(buffer)
  end function integer_text_default

  !> 64-bit integer as text without blanks.
  pure function integer_text_int64(value) result(text)
    integer(int64), intent(in) :: value
    character(:), allocatable :: text
    character(len=24) :: buffer
    write(buffer, '(i0)') value
    text = trim(buffer)
  end function integer_text_int64

  !> Real as text with 4 significant decimals (for messages): 1.8110E+07,
  !> and a three-digit exponent where one is needed (1.0000E-300, never the
  !> E-less 1.0000-300 of a two-digit exponent field).
  pure function message_real(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es13.4e3)') value
    text = two_digit_exponent(trim(adjustl(buffer)))
  end function message_real

  !> A real right-aligned in exactly `width` characters like the edit
  !> descriptor ES<width>.<digits> (1.00000000E+07 for width 16, digits 8),
  !> but with the E kept for a three-digit exponent (one digit fewer:
  !> 1.0000000E-300), where ES<w>.<d> would print 1.00000000-300. For tables.
  pure function es_field(value, width, digits) result(text)
    real(dp), intent(in) :: value
    integer, intent(in) :: width, digits
    character(len=width) :: text
    character(len=64) :: buffer
    write(buffer, '(es64.'//digit_text(digits)//'e3)') value
    buffer = adjustl(buffer)
    if (index(buffer, 'E') > 0 .and. buffer(index(buffer, 'E') + 2:index(buffer, 'E') + 2) == '0') then
      buffer = two_digit_exponent(trim(buffer))                      ! the usual E+07: as ES<w>.<d>
    else if (index(buffer, 'E') > 0) then
      write(buffer, '(es64.'//digit_text(digits - 1)//'e3)') value   ! E+100 and beyond: one digit fewer
      buffer = adjustl(buffer)
    end if
    text = adjustr(buffer(1:width))
    if (len_trim(buffer) > width) text = repeat('*', width)
  end function es_field

  !> Real as text with 10 significant digits (for summaries and tables).
  pure function table_real(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buffer
    if (value == 0.0_dp) then
      text = '0'
      return
    end if
    write(buffer, '(es17.9e3)') value
    text = trim(adjustl(buffer))
  end function table_real

  !> Shortest text (up to 17 significant digits) that reads back as the value:
  !> plain decimals for 1e-4 <= |value| < 1e15 (0.7 -> '0.7', 0.002 -> '0.002',
  !> 18.11e6 -> '18110000.0'), else scientific with the E always written
  !> (1e-7 -> '1.0E-07', 1e308 -> '1.0E+308', 4.9e-324 -> '4.9E-324').
  pure function short_real(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=48) :: buffer
    real(dp) :: back
    integer :: digits, ios
    if (value == 0.0_dp) then
      text = '0.0'
      return
    end if
    if (value /= value .or. abs(value) > huge(value)) then
      write(buffer, '(g0)') value                  ! NaN, Infinity, -Infinity
      text = trim(adjustl(buffer))
      return
    end if
    do digits = 1, 17
      if (abs(value) >= 1.0e-4_dp .and. abs(value) < 1.0e15_dp) then
        write(buffer, '(f0.'//digit_text(digits)//')') value
      else
        write(buffer, '(es30.'//digit_text(digits - 1)//'e3)') value
      end if
      read(buffer, *, iostat=ios) back
      if (ios == 0 .and. back == value) exit
    end do
    text = trim(adjustl(buffer))
    if (index(text, 'E') > 0) then
      text = two_digit_exponent(text)
      if (index(text, '.E') > 0) text = text(1:index(text, '.E'))//'0'//text(index(text, '.E') + 1:)   ! '1.E+308' -> '1.0E+308'
    else
      text = trailing_zeros_removed(text)
    end if
  end function short_real

  !> A number as compact as a person writes it, for ranges in messages:
  !> 1e14 -> '1e14', 1e-3 -> '0.001', 0.5 -> '0.5', 1000 -> '1000', -1e4 -> '-1e4'
  !> (plain decimals for 1e-3 <= |value| < 1e4, else mantissa e exponent).
  pure function compact_real(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    integer :: at, exponent, ios
    if (value /= 0.0_dp .and. (abs(value) < 1.0e-3_dp .or. abs(value) >= 1.0e4_dp)) then
      text = scientific(value)
    else
      text = short_real(value)
    end if
    at = index(text, 'E')
    if (at == 0) then
      if (len(text) > 2) then
        if (text(len(text) - 1:) == '.0') text = text(1:len(text) - 2)
      end if
      return
    end if
    read(text(at + 1:), *, iostat=ios) exponent
    if (ios /= 0) return
    text = text(1:at - 1)
    if (len(text) > 2) then
      if (text(len(text) - 1:) == '.0') text = text(1:len(text) - 2)
    end if
    text = text//'e'//integer_text(exponent)
  end function compact_real

  !> Shortest scientific text that reads back as the value ('1.0E+14').
  pure function scientific(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=48) :: buffer
    real(dp) :: back
    integer :: digits, ios
    do digits = 1, 17
      write(buffer, '(es30.'//digit_text(digits)//'e3)') value
      read(buffer, *, iostat=ios) back
      if (ios == 0 .and. back == value) exit
    end do
    text = trim(adjustl(buffer))
  end function scientific

  !> Digits as text for a format ('0' ... '17').
  pure function digit_text(digits) result(text)
    integer, intent(in) :: digits
    character(:), allocatable :: text
    text = integer_text(max(digits, 0))
  end function digit_text

  !> 'E+007' -> 'E+07', 'E-300' kept: an exponent printed with three digits
  !> keeps two when the first is 0, so ordinary numbers read as before.
  pure function two_digit_exponent(text) result(shorter)
    character(*), intent(in) :: text
    character(:), allocatable :: shorter
    integer :: at
    shorter = text
    at = index(text, 'E', back=.true.)
    if (at == 0 .or. len(text) < at + 4) return
    if (text(at + 2:at + 2) == '0' .and. len(text) == at + 4) shorter = text(1:at + 1)//text(at + 3:)
  end function two_digit_exponent

  !> '0.0020000' -> '0.002', '18110000.000' -> '18110000.0', '.5' -> '0.5'.
  pure function trailing_zeros_removed(text) result(shorter)
    character(*), intent(in) :: text
    character(:), allocatable :: shorter
    integer :: last
    shorter = text
    if (index(shorter, '.') == 0) return
    last = len(shorter)
    do while (last > index(shorter, '.') + 1)
      if (shorter(last:last) /= '0') exit
      last = last - 1
    end do
    shorter = shorter(1:last)
    if (shorter(1:1) == '.') shorter = '0'//shorter
    if (len(shorter) > 1) then
      if (shorter(1:2) == '-.') shorter = '-0'//shorter(2:)
    end if
  end function trailing_zeros_removed

  !> The candidate nearest to a mistyped word (at most 2 edits: a letter
  !> dropped, added, changed or two swapped; fewer than half its letters), '' if none.
  pure function nearest_word(word, candidates) result(nearest)
    character(*), intent(in) :: word
    character(*), intent(in) :: candidates(:)
    character(:), allocatable :: nearest
    integer :: k, distance, best
    nearest = ''
    best = 3
    do k = 1, size(candidates)
      if (trim(candidates(k)) == trim(word)) cycle
      distance = edit_distance(trim(word), trim(candidates(k)))
      if (distance < best .and. 2*distance < len_trim(word)) then
        best = distance
        nearest = trim(candidates(k))
      end if
    end do
  end function nearest_word

  !> Optimal string alignment distance (insertions, deletions, substitutions,
  !> adjacent transpositions), capped at 3 for words too far apart in length.
  pure integer function edit_distance(a, b) result(distance)
    character(*), intent(in) :: a, b
    integer :: d(0:len(a), 0:len(b))
    integer :: i, j, cost
    if (abs(len(a) - len(b)) > 2 .or. len(a) > 64 .or. len(b) > 64) then
      distance = 3
      return
    end if
    do i = 0, len(a)
      d(i, 0) = i
    end do
    do j = 0, len(b)
      d(0, j) = j
    end do
    do i = 1, len(a)
      do j = 1, len(b)
        cost = merge(0, 1, a(i:i) == b(j:j))
        d(i, j) = min(d(i - 1, j) + 1, d(i, j - 1) + 1, d(i - 1, j - 1) + cost)
        if (i > 1 .and. j > 1) then
          if (a(i:i) == b(j - 1:j - 1) .and. a(i - 1:i - 1) == b(j:j)) d(i, j) = min(d(i, j), d(i - 2, j - 2) + 1)
        end if
      end do
    end do
    distance = d(len(a), len(b))
  end function edit_distance

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
