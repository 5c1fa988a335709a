!> The model a deck describes (deck_t and the records it holds: the model's
!> settings, supports, loads, probes and time stages of visco2d_model, the
!> expected values, warnings), the analysis
!> kinds, the small queries on a deck (names, total steps, initial velocity)
!> and the located errors and warnings on its cards. visco2d_deck reads a
!> deck into these types and re-exports them.
module visco2d_deck_types
  use visco2d_kinds, only: dp, geometry_axisymmetric, formulation_bbar
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text
  use visco2d_cards, only: card_deck_t, card_error, field_column
  use visco2d_material, only: material_t
  use visco2d_model, only: settings_t, fix_t, pressure_t, force_t, loads_t, probe_t, time_stage_t, source_t, &
                           stage_total_steps
  use visco2d_dynamic_cards, only: dynamic_settings_t, output_request_t, standard_gravity
  use visco2d_contact_cards, only: plate_t, pad_t, body_t, stop_at_tend
  use visco2d_bruise_cards, only: bruise_card_t
  use visco2d_mesh, only: mesh_t
  implicit none
  private

  public :: deck_t, settings_t, loads_t, source_t, fix_t, pressure_t, force_t, probe_t, expect_t, warning_t
  public :: analysis_static, analysis_quasistatic, analysis_dynamic, analysis_name, geometry_name, total_steps
  public :: formulation_name, initial_velocity
  public :: solver_card_default, solver_card_band, solver_card_profile, solver_card_cholmod, solver_card_names
  public :: card_at_line, line_error, card_keyword_at, add_warning

  integer, parameter :: analysis_static = 1       !< S U = R once
  integer, parameter :: analysis_quasistatic = 2  !< incremental in time, no inertia (the legacy program)
  integer, parameter :: analysis_dynamic = 3      !< incremental in time with inertia (Wilson-theta, the extension)

  !> SOLVER BAND | PROFILE | CHOLMOD: the storage of the Cholesky factor
  !> (visco2d_factor numbers its solvers the same way; 0: its default).
  integer, parameter :: solver_card_default = 0
  integer, parameter :: solver_card_band = 1      !< band storage, LAPACK dpbtrf/dpbtrs (the legacy program's)
  integer, parameter :: solver_card_profile = 2   !< envelope (skyline) storage
  integer, parameter :: solver_card_cholmod = 3   !< CHOLMOD, sparse with a fill-reducing order
  character(len=7), parameter :: solver_card_names(3) = ['BAND   ', 'PROFILE', 'CHOLMOD']

  !> A warning about a deck that still runs (file:line: CARD: text).
  type :: warning_t
    character(:), allocatable :: text
  end type warning_t

  !> An expected value of a summary key (an analytic answer the deck documents).
  type :: expect_t
    character(:), allocatable :: key   !< summary key, upper case
    real(dp) :: value = 0.0_dp
    real(dp) :: tolerance = 1.0e-2_dp  !< relative
    integer :: line = 0
    integer :: column = 0              !< column of the key on the EXPECT card
  end type expect_t

  !> The model a deck describes.
  type :: deck_t
    type(card_deck_t) :: cards                     !< the cards as read (for the listing echo)
    type(source_t) :: source                       !< the file and its cards' lines and keywords (located errors)
    character(:), allocatable :: title
    integer :: analysis = 0
    type(settings_t) :: settings                   !< GEOMETRY, FORMULATION, SOLVER
    type(material_t), allocatable :: materials(:)
    type(mesh_t) :: mesh
    type(loads_t) :: loads                         !< FIX, PRESSURE, FORCE, CURVE, GRAVITY G=
    type(probe_t), allocatable :: probes(:)
    type(expect_t), allocatable :: expects(:)
    type(time_stage_t), allocatable :: stages(:)  !< TIME cards, in order (QUASISTATIC, DYNAMIC)
    type(dynamic_settings_t) :: dynamics                  !< WILSON, INITIAL, DROP (DYNAMIC)
    integer :: gravity_line = 0                   !< the GRAVITY card (loads%gravity: its G=)
    type(output_request_t) :: output              !< OUTPUT EVERY= FIELDS=
    integer :: solver_line = 0
    integer :: kinematics_line = 0                 !< line of the KINEMATICS card (0: none)
    type(plate_t) :: plate                        !< PLATE (contact extension); plate%line = 0: none
    type(pad_t) :: pad                            !< PAD on the plate (visco2d_pad_mesh); pad%line = 0: none
    !> BODY, a second deformable body (visco2d_body_mesh); body%line = 0: none. Its mesh part is
    !> marked by pad%first_node, pad%first_element and pad%surface (with pad%line = 0): the
    !> pad's machinery (node-to-segment contact, the inelastic projection) serves it
    type(body_t) :: body
    integer :: stop_at = stop_at_tend             !< STOP AT= (MAXDEFORMATION by default with a PLATE in DYNAMIC)
    integer :: stop_line = 0
    type(bruise_card_t), allocatable :: bruises(:) !< BRUISE cards (visco2d_bruise); none: no envelopes kept
    type(warning_t), allocatable :: warnings(:)
  end type deck_t

contains

  !> The analysis kind's name as on the ANALYSIS card ('NONE' for none).
  pure function analysis_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    select case (code)
    case (analysis_static); name = 'STATIC'
    case (analysis_quasistatic); name = 'QUASISTATIC'
    case (analysis_dynamic); name = 'DYNAMIC'
    case default; name = 'NONE'
    end select
  end function analysis_name

  !> The element formulation's name as on the FORMULATION card.
  pure function formulation_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    name = merge('BBAR    ', 'STANDARD', code == formulation_bbar)
    name = trim(name)
  end function formulation_name

  !> Initial (v_r, v_z) of the free nodes, m/s: INITIAL VR=/VZ=, or VZ = -sqrt(2 g h) of DROP HEIGHT=h
  !> (g of the GRAVITY card, 9.8 m/s^2 without one).
  pure function initial_velocity(deck) result(velocity)
    type(deck_t), intent(in) :: deck
    real(dp) :: velocity(2)
    real(dp) :: g
    velocity = deck%dynamics%velocity
    if (deck%dynamics%drop_line > 0) then
      g = standard_gravity
      if (deck%gravity_line > 0) g = deck%loads%gravity
      velocity(2) = -sqrt(2.0_dp*g*deck%dynamics%drop_height)
    end if
  end function initial_velocity

  !> The geometry's name as on the GEOMETRY card.
  pure function geometry_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    name = merge('AXISYMMETRIC', 'PLANESTRAIN ', code == geometry_axisymmetric)
    name = trim(name)
  end function geometry_name

  !> Total number of time steps of the deck's TIME stages (read_time keeps
  !> it at most max_steps; summed in 64 bits all the same).
  pure integer function total_steps(deck)
    type(deck_t), intent(in) :: deck
    total_steps = 0
    if (allocated(deck%stages)) total_steps = stage_total_steps(deck%stages)
  end function total_steps

  !> Index of the card on a line (0 if none: a line is always a card's here).
  integer function card_at_line(deck, line) result(found)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    integer :: low, high, middle
    found = 0
    low = 1
    high = deck%cards%count
    do while (low <= high)                  ! cards are in line order
      middle = (low + high)/2
      if (deck%cards%cards(middle)%line == line) then
        found = middle
        return
      else if (deck%cards%cards(middle)%line < line) then
        low = middle + 1
      else
        high = middle - 1
      end if
    end do
  end function card_at_line

  !> An error at the card on `line`, at the column of its field `field` (a
  !> name, or a position as '1') if it has one, else at its keyword.
  subroutine line_error(error, deck, line, message, field)
    type(error_t), allocatable, intent(inout) :: error
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    character(*), intent(in) :: message
    character(*), intent(in), optional :: field
    integer :: k
    k = card_at_line(deck, line)
    if (k == 0) then
      call set_error(error, message, file=deck%cards%file, line=line)
    else if (present(field)) then
      call card_error(error, deck%cards, deck%cards%cards(k), message, field_column(deck%cards%cards(k), field))
    else
      call card_error(error, deck%cards, deck%cards%cards(k), message)
    end if
  end subroutine line_error

  !> The keyword of the card on `line` (`fallback` if no card starts there).
  function card_keyword_at(deck, line, fallback) result(keyword)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    character(*), intent(in) :: fallback
    character(:), allocatable :: keyword
    integer :: k
    keyword = trim(fallback)
    do k = 1, deck%cards%count
      if (deck%cards%cards(k)%line == line) then
        keyword = trim(deck%cards%cards(k)%keyword)
        return
      end if
    end do
  end function card_keyword_at

  !> Add a located warning to the deck.
  subroutine add_warning(deck, line, card, message)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: line
    character(*), intent(in) :: card, message
    type(warning_t) :: warning
    warning%text = deck%cards%file//':'//integer_text(line)//': '//card//': '//message
    deck%warnings = [deck%warnings, warning]
  end subroutine add_warning
end module visco2d_deck_types
