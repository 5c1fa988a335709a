!> Card reader: one card per line, keyword first, then free-format fields,
!> either `NAME=value` pairs or positional values. `#` or `!` starts a comment.
!> Keywords and field names are case-insensitive. Every token remembers its
!> column, so errors can point at the offending field.
module visco2d_cards
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: to_upper
  implicit none
  private

  public :: token_t, card_t, card_deck_t
  public :: read_cards
  public :: card_error, named_real, named_integer, named_word, has_field
  public :: positional_count, positional_real, positional_integer, positional_word
  public :: check_fields_used, field_column, parse_real

  !> One field of a card.
  type :: token_t
    character(:), allocatable :: name   !< upper-case field name; '' for a positional value
    character(:), allocatable :: value  !< the value as written
    integer :: column = 0               !< column of the first character of the field
    logical :: used = .false.           !< set when an accessor consumed the field
  end type token_t

  !> One card: a non-blank, non-comment line.
  type :: card_t
    character(:), allocatable :: keyword   !< upper-case keyword
    character(:), allocatable :: text      !< the line as written (comment stripped)
    character(:), allocatable :: rest      !< text after the keyword (for TITLE)
    integer :: line = 0                    !< line number in the deck file
    integer :: column = 0                  !< column of the keyword
    type(token_t), allocatable :: tokens(:)
  end type card_t

  !> All cards of one deck file, up to and including END.
  type :: card_deck_t
    character(:), allocatable :: file
    type(card_t), allocatable :: cards(:)
    integer :: count = 0
    logical :: has_end = .false.
  end type card_deck_t

contains

  !> Read a deck file into cards. Reading stops after the END card.
  subroutine read_cards(file, deck, error)
    character(*), intent(in) :: file
    type(card_deck_t), intent(out) :: deck
    type(error_t), allocatable, intent(out) :: error
    integer :: unit, ios, line_number
    character(len=4096) :: buffer
    character(len=256) :: message
    type(card_t) :: card
    logical :: exists

    deck%file = file
    allocate(deck%cards(64))
    inquire(file=file, exist=exists)
    if (.not. exists) then
      call set_error(error, 'cannot open deck: file does not exist', file=file)
      return
    end if
    open(newunit=unit, file=file, status='old', action='read', iostat=ios, iomsg=message)
    if (ios /= 0) then
      call set_error(error, 'cannot open deck: '//trim(message), file=file)
      return
    end if
    line_number = 0
    do
      read(unit, '(a)', iostat=ios) buffer
      if (ios /= 0) exit
      line_number = line_number + 1
      if (len_trim(buffer) >= len(buffer) - 1) then
        call set_error(error, 'line longer than 4094 characters', file=file, line=line_number)
        close(unit)
        return
      end if
      call split_line(buffer, line_number, card, error)
      if (allocated(error)) then
        error%file = file
        close(unit)
        return
      end if
      if (.not. allocated(card%keyword)) cycle
      if (deck%count == size(deck%cards)) call grow(deck%cards)
      deck%count = deck%count + 1
      deck%cards(deck%count) = card
      if (card%keyword == 'END') then
        deck%has_end = .true.
        exit
      end if
    end do
    close(unit)
  end subroutine read_cards

  subroutine grow(cards)
    type(card_t), allocatable, intent(inout) :: cards(:)
    type(card_t), allocatable :: bigger(:)
    allocate(bigger(2*size(cards)))
    bigger(1:size(cards)) = cards
    call move_alloc(bigger, cards)
  end subroutine grow

  !> Split one line into keyword and fields; an empty/comment line gives no keyword.
  subroutine split_line(raw, line_number, card, error)
    character(*), intent(in) :: raw
    integer, intent(in) :: line_number
    type(card_t), intent(out) :: card
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: line
    integer :: i, n, start, count, equals
    integer :: starts(512), ends(512)

    line = raw
    do i = 1, len(line)
      if (line(i:i) == achar(9)) line(i:i) = ' '
      if (line(i:i) == '#' .or. line(i:i) == '!') then
        line = line(1:i-1)
        exit
      end if
    end do
    n = len_trim(line)
    if (n == 0) return

    ! Whitespace-separated words.
    count = 0
    i = 1
    do while (i <= n)
      if (line(i:i) == ' ') then
        i = i + 1
        cycle
      end if
      start = i
      do while (i <= n)
        if (line(i:i) == ' ') exit
        i = i + 1
      end do
      if (count == size(starts)) then
        call set_error(error, 'too many fields on one card (512 at most)', line=line_number)
        return
      end if
      count = count + 1
      starts(count) = start
      ends(count) = i - 1
    end do

    card%line = line_number
    card%column = starts(1)
    card%keyword = to_upper(line(starts(1):ends(1)))
    card%text = line(1:n)
    if (count > 1) then
      card%rest = line(starts(2):n)
    else
      card%rest = ''
    end if

    ! Fields; `NAME = value`, `NAME= value` and `NAME =value` are joined.
    allocate(card%tokens(0))
    i = 2
    do while (i <= count)
      block
        type(token_t) :: token
        character(:), allocatable :: word
        word = line(starts(i):ends(i))
        token%column = starts(i)
        if (i < count) then
          if (line(starts(i+1):starts(i+1)) == '=' .and. index(word, '=') == 0) then
            word = word//line(starts(i+1):ends(i+1))
            i = i + 1
          end if
        end if
        if (word(len(word):len(word)) == '=' .and. i < count) then
          if (index(line(starts(i+1):ends(i+1)), '=') == 0) then  ! not the next NAME=value
            word = word//line(starts(i+1):ends(i+1))
            i = i + 1
          end if
        end if
        equals = index(word, '=')
        if (equals == 0) then
          token%name = ''
          token%value = word
        else if (equals == 1) then
          call set_error(error, 'field "'//word//'" has no name before "="', &
                         line=line_number, column=token%column, card=card%keyword)
          return
        else
          token%name = to_upper(word(1:equals-1))
          token%value = word(equals+1:)
          if (len(token%value) == 0) then
            call set_error(error, 'field '//token%name//' has no value after "="', &
                           line=line_number, column=token%column, card=card%keyword)
            return
          end if
        end if
        if (len(token%name) > 0) then
          if (any([(card%tokens(equals)%name == token%name, equals = 1, size(card%tokens))])) then
            call set_error(error, 'field '//token%name//' given twice', &
                           line=line_number, column=token%column, card=card%keyword)
            return
          end if
        end if
        card%tokens = [card%tokens, token]
      end block
      i = i + 1
    end do
  end subroutine split_line

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
  !> mantissa, finite. Shared by the card reader and the command line.
  subroutine parse_real(text, value, ok)
    character(*), intent(in) :: text
    real(dp), intent(out) :: value
    logical, intent(out) :: ok
    integer :: i, mantissa_digits, exponent_digits, ios
    logical :: in_exponent, seen_point
    value = 0.0_dp
    mantissa_digits = 0
    exponent_digits = 0
    in_exponent = .false.
    seen_point = .false.
    ok = len(text) > 0
    do i = 1, len(text)
      select case (text(i:i))
      case ('0':'9')
        if (in_exponent) then
          exponent_digits = exponent_digits + 1
        else
          mantissa_digits = mantissa_digits + 1
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
    if (.not. ok) return
    read(text, *, iostat=ios) value
    ok = ios == 0
    if (ok) ok = ieee_is_finite(value)
  end subroutine parse_real

  subroutine parse_integer(text, value, ok)
    character(*), intent(in) :: text
    integer, intent(out) :: value
    logical, intent(out) :: ok
    integer :: ios
    value = 0
    ok = len(text) > 0 .and. len(text) <= 9 .and. verify(text, '0123456789+-') == 0 &
         .and. scan(text, '0123456789') > 0 .and. scan(text(2:), '+-') == 0
    if (.not. ok) return
    read(text, *, iostat=ios) value
    ok = ios == 0
  end subroutine parse_integer

  !> Real value of field NAME=. Absent: `default` if given, else an error.
  subroutine named_real(deck, card, name, value, error, default)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    character(*), intent(in) :: name
    real(dp), intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    real(dp), intent(in), optional :: default
    integer :: i
    logical :: ok
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
    call parse_real(card%tokens(i)%value, value, ok)
    if (.not. ok) call card_error(error, deck, card, name//' must be a number, got "'// &
                                  card%tokens(i)%value//'"', card%tokens(i)%column)
  end subroutine named_real

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
    call parse_integer(card%tokens(i)%value, value, ok)
    if (.not. ok) call card_error(error, deck, card, name//' must be an integer, got "'// &
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
    positional_count = 0
    do i = 1, size(card%tokens)
      if (len(card%tokens(i)%name) == 0) positional_count = positional_count + 1
    end do
  end function positional_count

  integer function find_positional(card, position) result(found)
    type(card_t), intent(in) :: card
    integer, intent(in) :: position
    integer :: i, seen
    found = 0
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
  subroutine positional_real(deck, card, position, what, value, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    integer, intent(in) :: position
    character(*), intent(in) :: what
    real(dp), intent(out) :: value
    type(error_t), allocatable, intent(inout) :: error
    integer :: i
    logical :: ok
    value = 0.0_dp
    i = find_positional(card, position)
    if (i == 0) then
      call card_error(error, deck, card, 'missing '//what//' (a number)')
      return
    end if
    card%tokens(i)%used = .true.
    call parse_real(card%tokens(i)%value, value, ok)
    if (.not. ok) call card_error(error, deck, card, what//' must be a number, got "'// &
                                  card%tokens(i)%value//'"', card%tokens(i)%column)
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
    value = 0
    i = find_positional(card, position)
    if (i == 0) then
      call card_error(error, deck, card, 'missing '//what//' (an integer)')
      return
    end if
    card%tokens(i)%used = .true.
    call parse_integer(card%tokens(i)%value, value, ok)
    if (.not. ok) call card_error(error, deck, card, what//' must be an integer, got "'// &
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
    character(:), allocatable :: hint
    hint = ''
    if (present(allowed)) hint = ' (expected: '//allowed//')'
    do i = 1, size(card%tokens)
      if (card%tokens(i)%used) cycle
      if (len(card%tokens(i)%name) > 0) then
        call card_error(error, deck, card, 'unknown field '//card%tokens(i)%name//hint, &
                        card%tokens(i)%column)
      else
        call card_error(error, deck, card, 'unexpected value "'//card%tokens(i)%value//'"'//hint, &
                        card%tokens(i)%column)
      end if
      return
    end do
  end subroutine check_fields_used
end module visco2d_cards
