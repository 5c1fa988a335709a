!> Card reader: one card per line, keyword first, then free-format fields,
!> either `NAME=value` pairs or positional values. `#` or `!` starts a comment.
!> Keywords and field names are case-insensitive. Every token remembers its
!> column, so errors can point at the offending field. This module holds
!> the card types and reads a deck file into cards; visco2d_cards reads the
!> fields of a card (and re-exports the types and read_cards).
module visco2d_card_reader
  use visco2d_error, only: error_t, set_error
  use, intrinsic :: iso_fortran_env, only: iostat_end, iostat_eor
  use visco2d_strings, only: to_upper, integer_text
  implicit none
  private

  public :: token_t, card_t, card_deck_t
  public :: read_cards, max_line_length, read_line

  !> Longest line a deck may have (an error beyond, never a cut).
  integer, parameter :: max_line_length = 1000000
  !> Most NAME=value fields on one card (no card takes more than 8).
  integer, parameter :: max_named_fields = 64
  !> read_line's status for a line longer than max_line_length.
  integer, parameter :: line_too_long = -1000

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
    integer, allocatable :: positions(:)   !< tokens(positions(k)) is the k-th positional value
  end type card_t

  !> All cards of one deck file, up to and including END.
  type :: card_deck_t
    character(:), allocatable :: file
    type(card_t), allocatable :: cards(:)
    integer :: count = 0
    logical :: has_end = .false.
    integer :: lines = 0                   !< lines read (up to END)
  end type card_deck_t

contains

  !> Read a deck file into cards. The cards end at the END card; text after
  !> it is not read as cards, but a line there that starts with one of the
  !> `known` keywords is an error (a card moved past END would be lost).
  !> Lines of any length up to max_line_length are read whole (never cut); a
  !> missing file, a directory, an unreadable file and a binary file (control
  !> bytes) are located errors.
  subroutine read_cards(file, deck, error, known)
    character(*), intent(in) :: file
    type(card_deck_t), intent(out) :: deck
    type(error_t), allocatable, intent(out) :: error
    character(*), intent(in), optional :: known(:)   !< card keywords
    integer :: unit, ios, line_number
    character(len=512) :: message
    character(:), allocatable :: line
    type(card_t) :: card

    deck%file = file
    allocate(deck%cards(64))
    call open_deck(file, unit, error)
    if (allocated(error)) return
    line_number = 0
    do
      call read_line(unit, line, ios, message)
      if (ios == iostat_end) exit
      line_number = line_number + 1
      if (ios == line_too_long) then
        call set_error(error, 'line longer than '//integer_text(max_line_length)//' characters (is this a deck?)', &
                       file=file, line=line_number, column=max_line_length + 1)
      else if (ios /= 0) then
        call set_error(error, 'cannot read the deck: '//trim(message), file=file, line=line_number)
      else
        if (line_number == 1 .and. len(line) >= 3) then   ! a UTF-8 byte-order mark (some Windows editors)
          if (line(1:3) == achar(239)//achar(187)//achar(191)) line = line(4:)
        end if
        call check_text(line, line_number, error)
        if (.not. allocated(error)) call split_line(line, line_number, card, error)
      end if
      if (allocated(error)) then
        error%file = file
        close(unit)
        return
      end if
      if (.not. allocated(card%keyword)) cycle
      if (deck%count == size(deck%cards)) call grow(deck%cards)
      deck%count = deck%count + 1
      call move_card(card, deck%cards(deck%count))
      if (deck%cards(deck%count)%keyword == 'END') then
        deck%has_end = .true.
        exit
      end if
    end do
    deck%lines = line_number
    if (deck%has_end .and. present(known)) call check_after_end(unit, deck, line_number, known, error)
    close(unit)
  end subroutine read_cards

  !> After END: free text is allowed, a line that starts with a card keyword
  !> (a card moved or duplicated past END) is an error.
  subroutine check_after_end(unit, deck, line_number, known, error)
    integer, intent(in) :: unit
    type(card_deck_t), intent(in) :: deck
    integer, intent(in) :: line_number
    character(*), intent(in) :: known(:)
    type(error_t), allocatable, intent(inout) :: error
    character(len=512) :: message
    character(:), allocatable :: line
    type(card_t) :: card
    type(error_t), allocatable :: ignored
    integer :: ios, number
    number = line_number
    do
      call read_line(unit, line, ios, message)
      if (ios /= 0) exit
      number = number + 1
      call split_line(line, number, card, ignored)
      if (allocated(ignored)) deallocate(ignored)
      if (.not. allocated(card%keyword)) cycle
      if (.not. any(known == card%keyword) .or. card%keyword == 'END') cycle
      call set_error(error, 'this card comes after END (line '//integer_text(deck%cards(deck%count)%line)// &
                     ') and would be ignored: END must be the last card', file=deck%file, line=number, &
                     column=card%column, card=card%keyword)
      return
    end do
  end subroutine check_after_end

  !> Open a deck for reading; a missing file, a directory or an unreadable
  !> file is an error that says which.
  subroutine open_deck(file, unit, error)
    character(*), intent(in) :: file
    integer, intent(out) :: unit
    type(error_t), allocatable, intent(inout) :: error
    character(len=512) :: message
    logical :: exists, directory
    integer :: ios
    unit = -1
    if (len_trim(file) == 0) then
      call set_error(error, 'cannot open deck: the file name is empty', file='""')
      return
    end if
    inquire(file=file, exist=exists)
    if (.not. exists) then
      call set_error(error, 'cannot open deck: file does not exist', file=file)
      return
    end if
    inquire(file=file//'/.', exist=directory)
    if (directory) then
      call set_error(error, 'cannot read deck: this is a directory, not a deck file', file=file)
      return
    end if
    message = ''
    open(newunit=unit, file=file, status='old', action='read', form='formatted', access='sequential', &
         iostat=ios, iomsg=message)
    if (ios /= 0) then
      if (index(message, "Cannot open file '") == 1 .and. index(message, "': ", back=.true.) > 0) &
        message = message(index(message, "': ", back=.true.) + 3:)      ! the runtime's reason only
      call set_error(error, 'cannot open deck: '//trim(message), file=file)
      return
    end if
  end subroutine open_deck

  !> Read one line whole, however long (up to max_line_length characters):
  !> non-advancing reads of a chunk at a time into a buffer that doubles.
  !> ios: 0, iostat_end at the end of the file, line_too_long, or a read error.
  subroutine read_line(unit, line, ios, message)
    integer, intent(in) :: unit
    character(:), allocatable, intent(out) :: line
    integer, intent(out) :: ios
    character(*), intent(out) :: message
    character(len=4096) :: chunk
    character(:), allocatable :: buffer, bigger
    integer :: length, got
    allocate(character(len=len(chunk)) :: buffer)
    length = 0
    message = ''
    do
      got = 0
      read(unit, '(a)', advance='no', iostat=ios, iomsg=message, size=got) chunk
      if (got > 0) then
        if (length + got > max_line_length) then
          ios = line_too_long
          line = buffer(1:length)
          return
        end if
        if (length + got > len(buffer)) then
          allocate(character(len=max(2*len(buffer), length + got)) :: bigger)
          bigger(1:length) = buffer(1:length)
          call move_alloc(bigger, buffer)
        end if
        buffer(length + 1:length + got) = chunk(1:got)
        length = length + got
      end if
      if (ios == iostat_eor) then
        ios = 0
        exit
      end if
      if (ios == iostat_end .and. length > 0) then   ! a last line without a newline
        ios = 0
        exit
      end if
      if (ios /= 0) exit
    end do
    line = buffer(1:length)
  end subroutine read_line

  !> A deck is text: a control byte other than the tab (a NUL of a binary
  !> file) is an error at its column. (The runtime ends a line at LF, CR LF or CR.)
  subroutine check_text(line, line_number, error)
    character(*), intent(in) :: line
    integer, intent(in) :: line_number
    type(error_t), allocatable, intent(inout) :: error
    integer :: i, code
    do i = 1, len(line)
      code = iachar(line(i:i))
      if (code >= 32 .and. code /= 127) cycle
      if (code == 9) cycle
      call set_error(error, 'a control byte ('//integer_text(code)//') where text was expected: '// &
                     'a deck is a plain text file (is this a binary file?)', line=line_number, column=i)
      return
    end do
  end subroutine check_text

  subroutine grow(cards)
    type(card_t), allocatable, intent(inout) :: cards(:)
    type(card_t), allocatable :: bigger(:)
    integer :: i
    allocate(bigger(2*size(cards)))
    do i = 1, size(cards)
      call move_card(cards(i), bigger(i))
    end do
    call move_alloc(bigger, cards)
  end subroutine grow

  !> Move a card's contents without copying its text and fields.
  subroutine move_card(from, to)
    type(card_t), intent(inout) :: from
    type(card_t), intent(inout) :: to
    call move_alloc(from%keyword, to%keyword)
    call move_alloc(from%text, to%text)
    call move_alloc(from%rest, to%rest)
    call move_alloc(from%tokens, to%tokens)
    call move_alloc(from%positions, to%positions)
    to%line = from%line
    to%column = from%column
  end subroutine move_card

  !> Split one line into keyword and fields; an empty/comment line gives no keyword.
  subroutine split_line(raw, line_number, card, error)
    character(*), intent(in) :: raw
    integer, intent(in) :: line_number
    type(card_t), intent(out) :: card
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: line
    integer :: i, n, start, count, equals, ntoken, named
    integer, allocatable :: starts(:), ends(:)

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

    ! Whitespace-separated words (as many as the line holds).
    allocate(starts(16), ends(16))
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
        starts = [starts, starts]
        ends = [ends, ends]
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
    allocate(card%tokens(count - 1))
    ntoken = 0
    named = 0
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
          named = named + 1
          if (named > max_named_fields) then
            call set_error(error, 'more than '//integer_text(max_named_fields)//' NAME=value fields on one card', &
                           line=line_number, column=token%column, card=card%keyword)
            return
          end if
          do equals = 1, ntoken
            if (card%tokens(equals)%name /= token%name) cycle
            call set_error(error, 'field '//token%name//' given twice (first at column '// &
                           integer_text(card%tokens(equals)%column)//')', &
                           line=line_number, column=token%column, card=card%keyword)
            return
          end do
        end if
        ntoken = ntoken + 1
        card%tokens(ntoken) = token
      end block
      i = i + 1
    end do
    card%tokens = card%tokens(1:ntoken)
    card%positions = pack([(i, i = 1, ntoken)], [(len(card%tokens(i)%name) == 0, i = 1, ntoken)])
  end subroutine split_line
end module visco2d_card_reader
