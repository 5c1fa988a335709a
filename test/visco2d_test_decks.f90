!> Small valid decks shared by the tests, and the checks of a refused deck
!> (the tests of the card reader: test_bad_decks, test_input_guards,
!> test_mesh_guards; the static contact tests: pressed_sphere).
!> A deck is an array of lines: line k of the file is element k (the number
!> beside each card), so a test replaces or splices cards by their line.
module visco2d_test_decks
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_text_contains, write_deck, exact_text
  implicit none
  private

  public :: deck_line_length, square, creep, dynamic, impact, impact_in_gravity, press, pressed_sphere
  public :: try_read_deck, check_error_location

  !> The length of a deck line in these tests (room for every card they write).
  integer, parameter :: deck_line_length = 120

contains

  !> A valid one-element plane-strain static deck: the unit square.
  function square() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: &
      'TITLE unit square', &                         ! 1
      'ANALYSIS STATIC', &                           ! 2
      'GEOMETRY PLANESTRAIN', &                      ! 3
      'MATERIAL steel ELASTIC E=200e9 NU=0.3', &     ! 4
      'NODE 1 0 0', &                                ! 5
      'NODE 2 1 0', &                                ! 6
      'NODE 3 1 1', &                                ! 7
      'NODE 4 0 1', &                                ! 8
      'ELEMENT 1 1 2 3 4 MAT=steel', &               ! 9
      'FIX 1 RZ', &                                  ! 10
      'FIX 2 Z', &                                   ! 11
      'END']                                         ! 12
  end function square

  !> A valid quasi-static viscoelastic deck: a creeping block under a ramped pressure.
  function creep() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: &
      'TITLE creep block', &                              ! 1
      'ANALYSIS QUASISTATIC', &                           ! 2
      'GEOMETRY AXISYMMETRIC', &                          ! 3
      'MATERIAL flesh VISCOELASTIC K=2e6', &              ! 4
      'PRONY G=1e6 BETA=10', &                            ! 5
      'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', &  ! 6
      'FIX BOTTOM Z', &                                   ! 7
      'PRESSURE TOP P=1e4 CURVE=load', &                  ! 8
      'CURVE load 0 0 1 1', &                             ! 9
      'TIME DT=0.1 TEND=1', &                             ! 10
      'END']                                              ! 11
  end function creep

  !> A valid dynamic deck: an axisymmetric block in free flight.
  function dynamic() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: &
      'TITLE flying block', &                             ! 1
      'ANALYSIS DYNAMIC', &                               ! 2
      'GEOMETRY AXISYMMETRIC', &                          ! 3
      'MATERIAL flesh ELASTIC E=1e6 NU=0.3 RHO=800', &    ! 4
      'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', &  ! 5
      'INITIAL VZ=-1', &                                  ! 6
      'WILSON THETA=1.4', &                               ! 7
      'GRAVITY G=9.8', &                                  ! 8
      'TIME DT=1e-5 TEND=1e-3', &                         ! 9
      'OUTPUT EVERY=10 FIELDS=1e-4,5e-4', &               ! 10
      'END']                                              ! 11
  end function dynamic

  !> A valid dynamic contact deck: a sphere (pole at z = 0) dropped onto a plate at z = 0.
  function impact() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: &
      'TITLE dropped sphere', &                           ! 1
      'ANALYSIS DYNAMIC', &                               ! 2
      'GEOMETRY AXISYMMETRIC', &                          ! 3
      'MATERIAL apple ELASTIC E=6e6 NU=0.3 RHO=800', &    ! 4
      'MESH SPHERE R=0.0381 LEVEL=1', &                   ! 5
      'INITIAL VZ=-1', &                                  ! 6
      'PLATE Z=0', &                                      ! 7
      'STOP AT=MAXDEFORMATION', &                         ! 8
      'TIME DT=1e-5 TEND=2e-3', &                         ! 9
      'END']                                              ! 10
  end function impact

  !> The impact deck in gravity, with field output: line 8 `GRAVITY G=9.8`
  !> (in place of the STOP card), line 10 `OUTPUT EVERY=10 FIELDS=1e-4`,
  !> line 11 `END`; lines 1-7 and 9 as in impact().
  function impact_in_gravity() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = impact()
    deck_lines(8) = 'GRAVITY G=9.8'
    deck_lines = [character(len=deck_line_length) :: deck_lines(1:9), 'OUTPUT EVERY=10 FIELDS=1e-4', deck_lines(10)]
  end function impact_in_gravity

  !> A valid static contact deck: the sphere pressed onto the plate by its weight.
  function press() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: &
      'TITLE pressed sphere', &                           ! 1
      'ANALYSIS STATIC', &                                ! 2
      'GEOMETRY AXISYMMETRIC', &                          ! 3
      'MATERIAL apple ELASTIC E=6e6 NU=0.3 RHO=800', &    ! 4
      'MESH SPHERE R=0.0381 LEVEL=1', &                   ! 5
      'GRAVITY G=1000', &                                 ! 6
      'PLATE Z=0 SLIP', &                                 ! 7
      'END']                                              ! 8
  end function press

  !> The Table-1 sphere (E = 18.11 MPa, nu = 0.219, rho = 756.85 kg/m^3,
  !> R = 36.6 mm; MESH SPHERE at `level`, the default contact grid) on PLATE Z=0 `mode` (STICK or
  !> SLIP), pressed onto it by GRAVITY G = `g`: a STATIC deck titled `title`.
  function pressed_sphere(title, level, mode, g) result(deck_lines)
    character(*), intent(in) :: title, mode
    integer, intent(in) :: level
    real(dp), intent(in) :: g
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: 'TITLE '//title, &     ! 1
      'ANALYSIS STATIC', &                                                   ! 2
      'GEOMETRY AXISYMMETRIC', &                                             ! 3
      'MATERIAL fruit ELASTIC E=18.11e6 NU=0.219 RHO=756.85', &              ! 4
      'MESH SPHERE R=0.0366 LEVEL='//integer_text(level), &   ! 5
      'PLATE Z=0 '//mode, &                                                  ! 6
      'GRAVITY G='//exact_text(g), &                                         ! 7
      'END']                                                                 ! 8
  end function pressed_sphere

  !> Read the deck at `path` (written from `deck_lines` first, if given):
  !> `refused` if read_deck returned an error, `message` its text ('' if none).
  subroutine try_read_deck(path, refused, message, deck_lines)
    character(*), intent(in) :: path
    logical, intent(out) :: refused
    character(:), allocatable, intent(out) :: message
    character(*), intent(in), optional :: deck_lines(:)
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    if (present(deck_lines)) call write_deck(path, deck_lines)
    call read_deck(path, deck, error)
    refused = allocated(error)
    message = ''
    if (refused) message = error_text(error)
  end subroutine try_read_deck

  !> The error `text` is `path:line:column: CARD: ...fragment...`. Checks
  !> <name>_file (the text starts with `path:`), <name>_line (if line > 0),
  !> <name>_column (if column > 0: `path:line:column: `, or `:column: ` alone
  !> when line is 0), <name>_card (if card is not empty) and <name>_message.
  subroutine check_error_location(name, text, path, line, column, card, fragment)
    character(*), intent(in) :: name, text, path
    integer, intent(in) :: line, column
    character(*), intent(in) :: card, fragment
    call check(name//'_file', index(text, path//':') == 1, 'expected "'//path//':" at the start of "'//text//'"')
    if (line > 0) call check_text_contains(name//'_line', text, path//':'//integer_text(line)//':')
    if (line > 0 .and. column > 0) call check_text_contains(name//'_column', text, &
                                                           path//':'//integer_text(line)//':'//integer_text(column)//': ')
    if (line == 0 .and. column > 0) call check_text_contains(name//'_column', text, ':'//integer_text(column)//': ')
    if (len(card) > 0) call check_text_contains(name//'_card', text, ': '//card//': ')
    call check_text_contains(name//'_message', text, fragment)
  end subroutine check_error_location
end module visco2d_test_decks
