!> The fields of a card: `NAME=value` pairs and positional values read as
!> numbers or words with their ranges checked, the fields a card did not
!> use, and errors located at the card's file, line and column. The card
!> types and the reading of a deck file into cards are visco2d_card_reader
!> (re-exported here: a reader of cards imports this module only).
module visco2d_cards
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: to_upper, nearest_word
  use visco2d_ranges, only: range_t, in_range, range_text
  use visco2d_card_reader, only: token_t, card_t, card_deck_t, read_cards, max_line_length
  implicit none
  private

  public :: token_t, card_t, card_deck_t
  public :: read_cards
  public :: card_error, named_real, named_integer, named_word, has_field
  public :: positional_count, positional_real, positional_integer, positional_word
  public :: check_fields_used, field_column, parse_real, max_line_length

contains

  !> Error located at a card (and a column, if known).
  subroutine card_error(error, deck, card, message, column)
    type(error_t), allocatable, intent(inout) :: error
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    character(*), intent(in) :: message
    integer, intent(in), optional :: column
    integer :: col
    col = card%column
    if (present(column)) col = column
    call set_error(error, message, file=deck%file, line=card%line, column=col, card=card%keyword)
  end subroutine card_error

  !> True if the card has a field with this name.
  logical function has_field(card, name)
    type(card_t), intent(in) :: card
    character(*), intent(in) :: name
    has_field = find_named(card, name) > 0
  end function has_field

  integer function find_named(card, name) result(found)
    type(card_t), intent(in) :: card
    character(*), intent(in) :: name
    integer :: i
    found = 0
    do i = 1, size(card%tokens)
      if (card%tokens(i)%name == to_upper(name)) then
        found = i
        return
      end if
    end do
  end function find_named

  !> Strict real: [sign] digits [. digits] [e|d [sign] digits], a digit in the
  !> mantissa, finite and representable: text that overflows (1e999), NaN and
  !> Infinity are refused, and so is a nonzero number that underflows to 0
  !> (1e-999) or to a subnormal double (4.9e-324, below 2.2e-308). `reason`
  !> completes "<NAME> ..." in a message. Shared by the card reader and the
  !> command line.
  subroutine parse_real(text, value, ok, reason)
    character(*), intent(in) :: text
    real(dp), intent(out) :: value
    logical, intent(out) :: ok
    character(:), allocatable, intent(out), optional :: reason
    integer :: i, mantissa_digits, exponent_digits, ios
    logical :: in_exponent, seen_point, nonzero
    character(:), allocatable :: why
    value = 0.0_dp
    mantissa_digits = 0
    exponent_digits = 0
    in_exponent = .false.
    seen_point = .false.
    nonzero = .false.
    ok = len(text) > 0
    do i = 1, len(text)
      select case (text(i:i))
      case ('0':'9')
        if (in_exponent) then
          exponent_digits = exponent_digits + 1
        else
          mantissa_digits = mantissa_digits + 1
          if (text(i:i) /= '0') nonzero = .true.
        end if
      case ('+', '-')
        if (i > 1) ok = ok .and. scan(text(i - 1:i - 1), 'eEdD') > 0
      case ('.')
        ok = ok .and. .not. (seen_point .or. in_exponent)
        seen_point = .true.
      case ('e', 'E', 'd', 'D')
        ok = ok .and. .not. in_exponent .and. mantissa_digits > 0
        in_exponent = .true.
      case default
        ok = .false.
      end select
    end do
    ok = ok .and. mantissa_digits > 0 .and. (exponent_digits > 0 .or. .not. in_exponent)
    why = 'must be a number'
    if (.not. ok) then
      select case (to_upper(adjustl(text)))
      case ('NAN', '+NAN', '-NAN', 'INF', '+INF', '-INF', 'INFINITY', '+INFINITY', '-INFINITY')
        why = 'must be a finite number'
      end select
    else
      read(text, *, iostat=ios) value
      ok = ios == 0
      if (ok .and. .not. ieee_is_finite(value)) then
        ok = .false.
        why = 'must be a finite number (at most 1.8e308 in magnitude)'
      else if (ok .and. nonzero .and. abs(value) < tiny(1.0_dp)) then
        ok = .false.
        why = 'is too small to be a normal double (nonzero numbers must be at least 2.2e-308 in magnitude)'
      end if
      if (.not. ok) value = 0.0_dp
    end if
    if (present(reason)) then
      reason = ''
      if (.not. ok) reason = why
    end if
  end subroutine parse_real

  !> Strict integer: [sign] digits, at most 9 digits (|n| < 1e9, no overflow).
  subroutine parse_integer(text, value, ok, reason)
    character(*), intent(in) :: text
    integer, intent(out) :: value
    logical, intent(out) :: ok
    character(:), allocatable, intent(out) :: reason
    integer :: ios, first
    value = 0
    reason = 'must be an integer'
    first = 1
    if (len(text) > 0) then
      if (scan(text(1:1), '+-') > 0) first = 2
    end if
    ok = len(text) >= first .and. verify(text(first:), '0123456789') == 0
    if (.not. ok) return
    if (len(text) - first + 1 > 9) then
      ok = .false.
      reason = 'must be an integer of at most 9 digits'
      return
    end if
    read(text, *, iostat=ios) value
    ok = ios == 0
  end subroutine parse_integer

  !> Real value of field NAME=. Absent: `default` if given, else an error.
  !> With `range`, a value outside it is an error at the field.
  subroutine named_real(deck, card, name, value, error, default, range)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    character(*), intent(in) :: name
    real(dp), intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    real(dp), intent(in), optional :: default
    type(range_t), intent(in), optional :: range
    integer :: i
    i = find_named(card, name)
    if (i == 0) then
      if (present(default)) then
        value = default
      else
        value = 0.0_dp
        call card_error(error, deck, card, 'missing field '//name//'=<number>')
      end if
      return
    end if
    card%tokens(i)%used = .true.
    call real_field(deck, card, card%tokens(i), name, value, error, range)
  end subroutine named_real

  !> The value of a field as a real, checked: a number, finite, normal, and in `range` if given.
  subroutine real_field(deck, card, token, what, value, error, range)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    type(token_t), intent(in) :: token
    character(*), intent(in) :: what
    real(dp), intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    type(range_t), intent(in), optional :: range
    character(:), allocatable :: reason
    logical :: ok
    call parse_real(token%value, value, ok, reason)
    if (.not. ok) then
      call card_error(error, deck, card, what//' '//reason//', got "'//token%value//'"', token%column)
      return
    end if
    if (.not. present(range)) return
    if (.not. in_range(value, range)) call card_error(error, deck, card, what//' must be '//range_text(range)// &
                                                      ', got "'//token%value//'"', token%column)
  end subroutine real_field

  !> Integer value of field NAME=.
  subroutine named_integer(deck, card, name, value, error, default)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    character(*), intent(in) :: name
    integer, intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    integer, intent(in), optional :: default
    integer :: i
    logical :: ok
    character(:), allocatable :: reason
    i = find_named(card, name)
    if (i == 0) then
      if (present(default)) then
        value = default
      else
        value = 0
        call card_error(error, deck, card, 'missing field '//name//'=<integer>')
      end if
      return
    end if
    card%tokens(i)%used = .true.
    call parse_integer(card%tokens(i)%value, value, ok, reason)
    if (.not. ok) call card_error(error, deck, card, name//' '//reason//', got "'// &
                                  card%tokens(i)%value//'"', card%tokens(i)%column)
  end subroutine named_integer

  !> Upper-case word value of field NAME= (e.g. MAT=steel).
  subroutine named_word(deck, card, name, value, error, default)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    character(*), intent(in) :: name
    character(:), allocatable, intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    character(*), intent(in), optional :: default
    integer :: i
    i = find_named(card, name)
    if (i == 0) then
      if (present(default)) then
        value = default
      else
        value = ''
        call card_error(error, deck, card, 'missing field '//name//'=<value>')
      end if
      return
    end if
    card%tokens(i)%used = .true.
    value = to_upper(card%tokens(i)%value)
  end subroutine named_word

  !> Number of positional (unnamed) fields.
  integer function positional_count(card)
    type(card_t), intent(in) :: card
    integer :: i
    if (allocated(card%positions)) then
      positional_count = size(card%positions)
      return
    end if
    positional_count = 0
    do i = 1, size(card%tokens)
      if (len(card%tokens(i)%name) == 0) positional_count = positional_count + 1
    end do
  end function positional_count

  !> Index in card%tokens of the `position`-th positional field, 0 if none.
  integer function find_positional(card, position) result(found)
    type(card_t), intent(in) :: card
    integer, intent(in) :: position
    integer :: i, seen
    found = 0
    if (position < 1) return
    if (allocated(card%positions)) then
      if (position <= size(card%positions)) found = card%positions(position)
      return
    end if
    seen = 0
    do i = 1, size(card%tokens)
      if (len(card%tokens(i)%name) == 0) then
        seen = seen + 1
        if (seen == position) then
          found = i
          return
        end if
      end if
    end do
  end function find_positional

  !> The `position`-th positional field as a real; `what` names it in errors.
  !> With `range`, a value outside it is an error at the field.
  subroutine positional_real(deck, card, position, what, value, error, range)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    integer, intent(in) :: position
    character(*), intent(in) :: what
    real(dp), intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    type(range_t), intent(in), optional :: range
    integer :: i
    value = 0.0_dp
    i = find_positional(card, position)
    if (i == 0) then
      call card_error(error, deck, card, 'missing '//what//' (a number)')
      return
    end if
    card%tokens(i)%used = .true.
    call real_field(deck, card, card%tokens(i), what, value, error, range)
  end subroutine positional_real

  !> The `position`-th positional field as an integer.
  subroutine positional_integer(deck, card, position, what, value, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    integer, intent(in) :: position
    character(*), intent(in) :: what
    integer, intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    integer :: i
    logical :: ok
    character(:), allocatable :: reason
    value = 0
    i = find_positional(card, position)
    if (i == 0) then
      call card_error(error, deck, card, 'missing '//what//' (an integer)')
      return
    end if
    card%tokens(i)%used = .true.
    call parse_integer(card%tokens(i)%value, value, ok, reason)
    if (.not. ok) call card_error(error, deck, card, what//' '//reason//', got "'// &
                                  card%tokens(i)%value//'"', card%tokens(i)%column)
  end subroutine positional_integer

  !> The `position`-th positional field as an upper-case word ('' if absent and optional).
  subroutine positional_word(deck, card, position, what, value, error, optional_field)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    integer, intent(in) :: position
    character(*), intent(in) :: what
    character(:), allocatable, intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    logical, intent(in), optional :: optional_field
    integer :: i
    value = ''
    i = find_positional(card, position)
    if (i == 0) then
      if (present(optional_field)) then
        if (optional_field) return
      end if
      call card_error(error, deck, card, 'missing '//what)
      return
    end if
    card%tokens(i)%used = .true.
    value = to_upper(card%tokens(i)%value)
  end subroutine positional_word

  !> Column of field NAME= (a name) or of the n-th positional value (a number
  !> as text, e.g. '1'); the keyword's column if absent.
  integer function field_column(card, name) result(column)
    type(card_t), intent(in) :: card
    character(*), intent(in) :: name
    integer :: i, position, ios
    column = card%column
    read(name, *, iostat=ios) position
    if (ios == 0 .and. verify(name, '0123456789') == 0) then
      i = find_positional(card, position)
    else
      i = find_named(card, name)
    end if
    if (i > 0) column = card%tokens(i)%column
  end function field_column

  !> Error on the first field that no accessor consumed (unknown field name
  !> or surplus positional value).
  subroutine check_fields_used(deck, card, error, allowed)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    type(error_t), allocatable, intent(inout) :: error
    character(*), intent(in), optional :: allowed  !< text listing the accepted fields
    integer :: i
    character(:), allocatable :: hint, guess
    hint = ''
    if (present(allowed)) hint = ' (expected: '//allowed//')'
    do i = 1, size(card%tokens)
      if (card%tokens(i)%used) cycle
      if (len(card%tokens(i)%name) > 0) then
        guess = ''
        if (present(allowed)) guess = nearest_word(card%tokens(i)%name, field_names(allowed))
        if (len(guess) > 0) guess = ', did you mean '//guess//'?'
        call card_error(error, deck, card, 'unknown field '//card%tokens(i)%name//guess//hint, &
                        card%tokens(i)%column)
      else
        call card_error(error, deck, card, 'unexpected value "'//card%tokens(i)%value//'"'//hint, &
                        card%tokens(i)%column)
      end if
      return
    end do
  end subroutine check_fields_used

  !> The NAME of every NAME= in a card's form ('PLATE Z=.. [RELEASE=YES|NO]' -> Z, RELEASE).
  pure function field_names(form) result(names)
    character(*), intent(in) :: form
    character(len=16), allocatable :: names(:)
    integer :: i, first
    allocate(names(0))
    do i = 2, len(form)
      if (form(i:i) /= '=') cycle
      first = i
      do while (first > 1)
        if (verify(form(first - 1:first - 1), 'ABCDEFGHIJKLMNOPQRSTUVWXYZ') /= 0) exit
        first = first - 1
      end do
      if (first < i) names = [character(len=16) :: names, form(first:i - 1)]
    end do
  end function field_names
end module visco2d_cards
