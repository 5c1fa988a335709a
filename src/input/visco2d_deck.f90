!> A deck: the cards of one input file interpreted as a model (title,
!> analysis, geometry, materials, mesh, supports, loads, time histories,
!> time stages, probes), with every reference checked. Errors name the
!> file, line, column and card.
module visco2d_deck
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_plane_strain, formulation_standard, formulation_bbar
  use visco2d_error, only: error_t, set_error
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_strings, only: itoa, rtoa, short_real, to_lower, nearest_word
  use visco2d_ranges, only: length_range, pressure_range, force_range, speed_range, &
                            expected_value_range, tolerance_range, range_t, in_range, range_text
  use visco2d_cards, only: card_t, card_deck_t, read_cards, card_error, named_real, named_integer, &
                           named_word, positional_word, positional_real, &
                           check_fields_used, has_field, field_column
  use visco2d_material, only: material_t, has_memory
  use visco2d_material_cards, only: read_material, read_prony, finish_material
  use visco2d_curve, only: curve_t, read_curve
  use visco2d_time, only: time_stage_t, read_time
  use visco2d_dynamic_cards, only: dynamics_t, output_request_t, read_wilson, read_initial, read_drop, &
                                   read_gravity, read_output, read_formulation, standard_gravity, theta_unconditional, &
                                   read_integrator
  use visco2d_contact_cards, only: plate_t, read_plate, read_stop, stop_name, stop_at_tend, &
                                   stop_at_max_deformation, stop_at_separation
  use visco2d_bruise_cards, only: bruise_card_t, read_bruise, check_bruise_cards
  use visco2d_mesh, only: mesh_t, mesh_input_t, read_node_card, read_element_card, read_mesh_card, &
                          build_mesh, node_set, node_index, edge_set_code, edge_set_name, &
                          edge_set_none, edge_set_axis
  implicit none
  private

  public :: deck_t, fix_t, pressure_t, force_t, probe_t, expect_t, time_stage_t, warning_t, read_deck
  public :: dynamics_t, output_request_t
  public :: analysis_static, analysis_quasistatic, analysis_dynamic, analysis_name, geometry_name, total_steps
  public :: formulation_name, initial_velocity
  public :: plate_t, stop_at_tend, stop_at_max_deformation, stop_at_separation, stop_name

  integer, parameter :: analysis_static = 1       !< S U = R once
  integer, parameter :: analysis_quasistatic = 2  !< incremental in time, no inertia (the legacy program)
  integer, parameter :: analysis_dynamic = 3      !< incremental in time with inertia (Wilson-theta, the extension)

  !> Every card keyword a deck may use.
  character(len=11), parameter :: card_keywords(26) = [character(len=11) :: 'TITLE', 'ANALYSIS', 'GEOMETRY', &
    'FORMULATION', 'MATERIAL', 'PRONY', 'NODE', 'ELEMENT', 'MESH', 'FIX', 'PRESSURE', 'FORCE', 'GRAVITY', &
    'CURVE', 'TIME', 'WILSON', 'INTEGRATOR', 'INITIAL', 'DROP', 'OUTPUT', 'PLATE', 'STOP', 'PROBE', 'EXPECT', 'BRUISE', 'END']

  !> A warning about a deck that still runs (file:line: CARD: text).
  type :: warning_t
    character(:), allocatable :: text
  end type warning_t

  !> A support: components prescribed at a set of nodes, u = value * curve(t)
  !> (value 0, no curve: a fixed support).
  type :: fix_t
    integer, allocatable :: nodes(:)
    logical :: fix_r = .false., fix_z = .false.
    real(dp) :: value(2) = 0.0_dp  !< prescribed (u_r, u_z), m
    integer :: curve = 0           !< index into deck%curves; 0 = constant
    integer :: line = 0
  end type fix_t

  !> A uniform normal pressure on a boundary edge set (positive = compressive), p * curve(t).
  type :: pressure_t
    integer :: edge_set = edge_set_none
    real(dp) :: value = 0.0_dp     !< Pa
    integer :: curve = 0           !< index into deck%curves; 0 = constant
    integer :: line = 0
  end type pressure_t

  !> A point load at a node (per radian in axisymmetry), N, times curve(t).
  type :: force_t
    integer :: node = 0
    real(dp) :: value(2) = 0.0_dp
    integer :: curve = 0           !< index into deck%curves; 0 = constant
    integer :: line = 0
  end type force_t

  !> A node whose displacement and stress are reported in the summary and history.
  type :: probe_t
    character(:), allocatable :: name
    integer :: node = 0
  end type probe_t

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
    character(:), allocatable :: title
    integer :: analysis = 0
    integer :: geometry = geometry_axisymmetric
    type(material_t), allocatable :: materials(:)
    type(mesh_t) :: mesh
    type(fix_t), allocatable :: fixes(:)
    type(pressure_t), allocatable :: pressures(:)
    type(force_t), allocatable :: forces(:)
    type(probe_t), allocatable :: probes(:)
    type(expect_t), allocatable :: expects(:)
    type(curve_t), allocatable :: curves(:)
    type(time_stage_t), allocatable :: stages(:)  !< TIME cards, in order (QUASISTATIC, DYNAMIC)
    type(dynamics_t) :: dynamics                  !< WILSON, INITIAL, DROP (DYNAMIC)
    real(dp) :: gravity = 0.0_dp                  !< GRAVITY G=, m/s^2 in -z; 0: no gravity
    integer :: gravity_line = 0
    type(output_request_t) :: output              !< OUTPUT EVERY= FIELDS=
    integer :: formulation = formulation_standard !< FORMULATION STANDARD | BBAR
    type(plate_t) :: plate                        !< PLATE (contact extension); plate%line = 0: none
    integer :: stop_at = stop_at_tend             !< STOP AT= (MAXDEFORMATION by default with a PLATE in DYNAMIC)
    integer :: stop_line = 0
    type(bruise_card_t), allocatable :: bruises(:) !< BRUISE cards (visco2d_bruise); none: no envelopes kept
    type(warning_t), allocatable :: warnings(:)
  end type deck_t

  !> A target of FIX or FORCE or PROBE, kept until the mesh exists.
  type :: pending_t
    integer :: card = 0
    integer :: column = 0               !< column of the target field
    character(:), allocatable :: target
    character(:), allocatable :: components
    real(dp) :: values(2) = 0.0_dp
    character(:), allocatable :: curve  !< CURVE= name, '' if none
  end type pending_t

contains

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
      if (deck%gravity_line > 0) g = deck%gravity
      velocity(2) = -sqrt(2.0_dp*g*deck%dynamics%drop_height)
    end if
  end function initial_velocity

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
    integer(int64) :: steps
    integer :: k
    steps = 0
    if (allocated(deck%stages)) then
      do k = 1, size(deck%stages)
        steps = steps + int(deck%stages(k)%steps, int64)
      end do
    end if
    total_steps = int(min(steps, int(huge(total_steps), int64)))
  end function total_steps

  !> Read and check a deck file.
  subroutine read_deck(file, deck, error)
    character(*), intent(in) :: file
    type(deck_t), intent(out) :: deck
    type(error_t), allocatable, intent(out) :: error
    type(mesh_input_t) :: mesh_input
    type(pending_t), allocatable :: fixes(:), forces(:), probes(:)
    character(len=32), allocatable :: pressure_curves(:)
    integer, allocatable :: pressure_cards(:)
    integer :: i, title_line, analysis_line, geometry_line, material_card, formulation_line
    character(:), allocatable :: word, warning

    call read_cards(file, deck%cards, error, card_keywords)
    if (allocated(error)) return
    deck%title = ''
    allocate(deck%materials(0), deck%pressures(0), deck%expects(0), fixes(0), forces(0), probes(0))
    allocate(deck%curves(0), deck%stages(0), pressure_curves(0), pressure_cards(0), deck%warnings(0))
    allocate(deck%output%field_times(0), deck%bruises(0))
    formulation_line = 0
    title_line = 0
    analysis_line = 0
    geometry_line = 0
    material_card = 0

    associate (cards => deck%cards)
    do i = 1, cards%count
      associate (card => cards%cards(i))
      select case (card%keyword)
      case ('TITLE')
        if (title_line > 0) then
          call duplicate_card(title_line); return
        end if
        title_line = card%line
        deck%title = card%rest
      case ('ANALYSIS')
        if (analysis_line > 0) then
          call duplicate_card(analysis_line); return
        end if
        analysis_line = card%line
        call positional_word(cards, card, 1, 'analysis kind (STATIC, QUASISTATIC or DYNAMIC)', word, error)
        if (allocated(error)) return
        call check_fields_used(cards, card, error, 'ANALYSIS STATIC | QUASISTATIC | DYNAMIC')
        if (allocated(error)) return
        select case (word)
        case ('STATIC')
          deck%analysis = analysis_static
        case ('QUASISTATIC')
          deck%analysis = analysis_quasistatic
        case ('DYNAMIC')
          deck%analysis = analysis_dynamic
        case default
          call card_error(error, cards, card, 'analysis kind must be STATIC, QUASISTATIC or DYNAMIC, got "'// &
                          word//'"', field_column(card, '1'))
          return
        end select
      case ('GEOMETRY')
        if (geometry_line > 0) then
          call duplicate_card(geometry_line); return
        end if
        geometry_line = card%line
        call positional_word(cards, card, 1, 'geometry (AXISYMMETRIC or PLANESTRAIN)', word, error)
        if (allocated(error)) return
        call check_fields_used(cards, card, error, 'GEOMETRY AXISYMMETRIC | PLANESTRAIN'); if (allocated(error)) return
        select case (word)
        case ('AXISYMMETRIC')
          deck%geometry = geometry_axisymmetric
        case ('PLANESTRAIN')
          deck%geometry = geometry_plane_strain
        case default
          call card_error(error, cards, card, 'geometry must be AXISYMMETRIC or PLANESTRAIN, got "'//word//'"', &
                          field_column(card, '1'))
          return
        end select
      case ('MATERIAL')
        call read_material(cards, card, deck%materials, error); if (allocated(error)) return
        material_card = i
      case ('PRONY')
        if (.not. follows_material(i)) then
          call card_error(error, cards, card, 'PRONY must follow its MATERIAL card (or another PRONY card)')
          return
        end if
        call read_prony(cards, card, deck%materials(size(deck%materials)), error); if (allocated(error)) return
      case ('CURVE')
        call read_curve(cards, card, deck%curves, error); if (allocated(error)) return
      case ('TIME')
        call read_time(cards, card, deck%stages, error); if (allocated(error)) return
      case ('WILSON')
        if (deck%dynamics%wilson_line > 0) then
          call duplicate_card(deck%dynamics%wilson_line); return
        end if
        call read_wilson(cards, card, deck%dynamics, error); if (allocated(error)) return
        if (deck%dynamics%theta < theta_unconditional) call add_warning(deck, card%line, 'WILSON', &
          'THETA = '//short_real(deck%dynamics%theta)//' < 1.37: Wilson-theta is then only conditionally stable;'// &
          ' a large DT may blow up (1.4 is the usual value)')
      case ('INTEGRATOR')
        if (deck%dynamics%wilson_line > 0) then
          call duplicate_card(deck%dynamics%wilson_line); return
        end if
        call read_integrator(cards, card, deck%dynamics, error, warning); if (allocated(error)) return
        if (allocated(warning)) call add_warning(deck, card%line, 'INTEGRATOR', warning)
      case ('INITIAL')
        if (deck%dynamics%initial_line > 0) then
          call duplicate_card(deck%dynamics%initial_line); return
        end if
        call read_initial(cards, card, deck%dynamics, error); if (allocated(error)) return
      case ('DROP')
        if (deck%dynamics%drop_line > 0) then
          call duplicate_card(deck%dynamics%drop_line); return
        end if
        call read_drop(cards, card, deck%dynamics, error); if (allocated(error)) return
      case ('GRAVITY')
        if (deck%gravity_line > 0) then
          call duplicate_card(deck%gravity_line); return
        end if
        call read_gravity(cards, card, deck%gravity, error); if (allocated(error)) return
        deck%gravity_line = card%line
      case ('OUTPUT')
        if (deck%output%line > 0) then
          call duplicate_card(deck%output%line); return
        end if
        call read_output(cards, card, deck%output, error); if (allocated(error)) return
      case ('FORMULATION')
        if (formulation_line > 0) then
          call duplicate_card(formulation_line); return
        end if
        call read_formulation(cards, card, deck%formulation, error); if (allocated(error)) return
        formulation_line = card%line
      case ('PLATE')
        if (deck%plate%line > 0) then
          call duplicate_card(deck%plate%line); return
        end if
        call read_plate(cards, card, deck%plate, error); if (allocated(error)) return
      case ('STOP')
        if (deck%stop_line > 0) then
          call duplicate_card(deck%stop_line); return
        end if
        call read_stop(cards, card, deck%stop_at, error); if (allocated(error)) return
        deck%stop_line = card%line
      case ('NODE')
        call read_node_card(mesh_input, cards, card, error); if (allocated(error)) return
      case ('ELEMENT')
        call read_element_card(mesh_input, cards, card, error); if (allocated(error)) return
      case ('MESH')
        call read_mesh_card(mesh_input, cards, card, error); if (allocated(error)) return
      case ('FIX')
        call read_fix(cards, card, i, fixes, error); if (allocated(error)) return
      case ('PRESSURE')
        call read_pressure(cards, card, deck%pressures, word, error); if (allocated(error)) return
        pressure_curves = [character(len=32) :: pressure_curves, word]
        pressure_cards = [pressure_cards, i]
        call check_repeated_pressure(); if (allocated(error)) return
      case ('FORCE')
        call read_force(cards, card, i, forces, error); if (allocated(error)) return
        call check_repeated_force(); if (allocated(error)) return
      case ('PROBE')
        call read_probe(cards, card, i, probes, error); if (allocated(error)) return
      case ('EXPECT')
        call read_expect(cards, card, deck%expects, error); if (allocated(error)) return
      case ('BRUISE')
        call read_bruise(cards, card, deck%bruises, error); if (allocated(error)) return
      case ('END')
        call check_fields_used(cards, card, error, 'END'); if (allocated(error)) return
      case default
        call card_error(error, cards, card, 'unknown card "'//card%keyword//'"'// &
          suggestion(nearest_word(card%keyword, card_keywords))//' (known: TITLE ANALYSIS '// &
          'GEOMETRY FORMULATION MATERIAL PRONY NODE ELEMENT MESH FIX PRESSURE FORCE GRAVITY CURVE TIME '// &
          'WILSON INTEGRATOR INITIAL DROP OUTPUT PLATE STOP PROBE EXPECT BRUISE END)')
        return
      end select
      end associate
    end do

    if (cards%count == 0) then
      if (cards%lines == 0) then
        call set_error(error, 'the deck has no cards: it is an empty file', file=file, line=1)
      else
        call set_error(error, 'the deck has no cards: its '//itoa(cards%lines)//' lines are blank or comments', &
                       file=file, line=cards%lines)
      end if
      return
    end if
    if (.not. cards%has_end) then
      call card_error(error, cards, cards%cards(cards%count), 'missing END card: the deck ends after this card '// &
                      '(is it truncated?)'); return
    end if
    if (analysis_line == 0) then
      call card_error(error, cards, cards%cards(cards%count), 'missing ANALYSIS card (ANALYSIS STATIC, '// &
                      'QUASISTATIC or DYNAMIC) before END'); return
    end if
    if (size(deck%materials) == 0) then
      call card_error(error, cards, cards%cards(first_card(['ELEMENT', 'MESH   ', 'END    '])), &
                      'missing MATERIAL card: the elements need one (MATERIAL id ELASTIC E=.. NU=..)'); return
    end if
    if (.not. any([(cards%cards(i)%keyword == 'NODE' .or. cards%cards(i)%keyword == 'ELEMENT' .or. &
                    cards%cards(i)%keyword == 'MESH', i = 1, cards%count)])) then
      call card_error(error, cards, cards%cards(cards%count), 'missing mesh: give NODE and ELEMENT cards or a '// &
                      'MESH card before END'); return
    end if
    if (.not. any([(cards%cards(i)%keyword == 'ELEMENT' .or. cards%cards(i)%keyword == 'MESH', &
                    i = 1, cards%count)])) then
      call card_error(error, cards, cards%cards(first_card(['NODE'])), 'missing elements: NODE cards need '// &
                      'ELEMENT cards to make a mesh (or give a MESH card instead)'); return
    end if
    do i = 1, size(deck%materials)
      call finish_material(cards, deck%materials(i), error); if (allocated(error)) return
    end do
    call check_time_stages(deck, analysis_line, error); if (allocated(error)) return
    call check_dynamic_cards(deck, error); if (allocated(error)) return
    call check_contact_cards(deck, error); if (allocated(error)) return
    call check_bruise_cards(cards, deck%bruises, deck%materials, deck%analysis == analysis_quasistatic, error)
    if (allocated(error)) return

    call build_mesh(mesh_input, cards, deck%geometry, deck%mesh, error); if (allocated(error)) return
    call resolve_materials(deck, error); if (allocated(error)) return
    call resolve_fixes(deck, fixes, error); if (allocated(error)) return
    call resolve_forces(deck, forces, error); if (allocated(error)) return
    call resolve_probes(deck, probes, error); if (allocated(error)) return
    call check_pressures(deck, error); if (allocated(error)) return
    do i = 1, size(deck%pressures)
      deck%pressures(i)%curve = curve_index(deck, pressure_cards(i), trim(pressure_curves(i)), error)
      if (allocated(error)) return
    end do
    call check_load_sizes(deck, error); if (allocated(error)) return
    call check_memory_needs_time(deck, analysis_line, error); if (allocated(error)) return
    call check_mass(deck, error); if (allocated(error)) return
    call check_plate_position(deck, error); if (allocated(error)) return
    call check_locking(deck)
    end associate

  contains

    subroutine duplicate_card(first_line)
      integer, intent(in) :: first_line
      call card_error(error, deck%cards, deck%cards%cards(i), 'only one '//deck%cards%cards(i)%keyword// &
        ' card is allowed (first on line '//itoa(first_line)//')')
    end subroutine duplicate_card

    !> The same pressure twice (same set, value and curve) is a duplicated
    !> line, not a load meant to be doubled.
    subroutine check_repeated_pressure()
      integer :: k, n
      n = size(deck%pressures)
      do k = 1, n - 1
        if (deck%pressures(k)%edge_set /= deck%pressures(n)%edge_set) cycle
        if (deck%pressures(k)%value /= deck%pressures(n)%value .or. pressure_curves(k) /= pressure_curves(n)) cycle
        call card_error(error, deck%cards, deck%cards%cards(i), 'the same pressure as on line '// &
          itoa(deck%pressures(k)%line)//' (a duplicated line?): give the total on one card', &
          field_column(deck%cards%cards(i), 'P'))
        return
      end do
    end subroutine check_repeated_pressure

    !> The same point load twice (same node, values and curve): a duplicated line.
    subroutine check_repeated_force()
      integer :: k, n
      n = size(forces)
      do k = 1, n - 1
        if (forces(k)%target /= forces(n)%target .or. forces(k)%curve /= forces(n)%curve) cycle
        if (any(forces(k)%values /= forces(n)%values)) cycle
        call card_error(error, deck%cards, deck%cards%cards(i), 'the same force as on line '// &
          itoa(deck%cards%cards(forces(k)%card)%line)//' (a duplicated line?): give the total on one card', &
          forces(n)%column)
        return
      end do
    end subroutine check_repeated_force

    !> True if card k (a PRONY) directly follows a MATERIAL or PRONY card.
    logical function follows_material(k)
      integer, intent(in) :: k
      follows_material = .false.
      if (material_card == 0 .or. k < 2) return
      follows_material = deck%cards%cards(k - 1)%keyword == 'MATERIAL' .or. &
                         deck%cards%cards(k - 1)%keyword == 'PRONY'
    end function follows_material

    !> Index of the first card with one of these keywords (the last card if none).
    integer function first_card(keywords) result(found)
      character(*), intent(in) :: keywords(:)
      integer :: k
      found = deck%cards%count
      do k = 1, deck%cards%count
        if (any(keywords == deck%cards%cards(k)%keyword)) then
          found = k
          return
        end if
      end do
    end function first_card
  end subroutine read_deck

  !> FIX target R|Z|RZ [UR=..] [UZ=..] [CURVE=name]  (target: node number, AXIS, BOTTOM, TOP,
  !> INNER or OUTER); UR/UZ prescribe a displacement (default 0), scaled by the curve.
  subroutine read_fix(cards, card, index, fixes, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    integer, intent(in) :: index
    type(pending_t), allocatable, intent(inout) :: fixes(:)
    type(error_t), allocatable, intent(inout) :: error
    type(pending_t) :: fix
    fix%card = index
    call positional_word(cards, card, 1, 'target (node number, AXIS, BOTTOM, TOP, INNER or OUTER)', &
                         fix%target, error); if (allocated(error)) return
    fix%column = field_column(card, '1')
    call positional_word(cards, card, 2, 'components (R, Z or RZ)', fix%components, error); if (allocated(error)) return
    call named_real(cards, card, 'UR', fix%values(1), error, default=0.0_dp, range=length_range)
    if (allocated(error)) return
    call named_real(cards, card, 'UZ', fix%values(2), error, default=0.0_dp, range=length_range)
    if (allocated(error)) return
    call named_word(cards, card, 'CURVE', fix%curve, error, default=''); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'FIX target R|Z|RZ [UR=..] [UZ=..] [CURVE=name]')
    if (allocated(error)) return
    if (fix%components /= 'R' .and. fix%components /= 'Z' .and. fix%components /= 'RZ' &
        .and. fix%components /= 'ZR') then
      call card_error(error, cards, card, 'components must be R, Z or RZ, got "'//fix%components//'"', &
                      field_column(card, '2')); return
    end if
    if (has_field(card, 'UR') .and. scan(fix%components, 'R') == 0) then
      call card_error(error, cards, card, 'UR= prescribes u_r, so the components must include R', &
                      field_column(card, 'UR')); return
    end if
    if (has_field(card, 'UZ') .and. scan(fix%components, 'Z') == 0) then
      call card_error(error, cards, card, 'UZ= prescribes u_z, so the components must include Z', &
                      field_column(card, 'UZ')); return
    end if
    if (len(fix%curve) > 0 .and. all(fix%values == 0.0_dp)) then
      call card_error(error, cards, card, 'CURVE= scales the prescribed UR=/UZ=, which are zero here', &
                      field_column(card, 'CURVE')); return
    end if
    fixes = [fixes, fix]
  end subroutine read_fix

  !> PRESSURE edge-set P=.. [CURVE=name]
  subroutine read_pressure(cards, card, pressures, curve, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(pressure_t), allocatable, intent(inout) :: pressures(:)
    character(:), allocatable, intent(out) :: curve
    type(error_t), allocatable, intent(inout) :: error
    type(pressure_t) :: pressure
    character(:), allocatable :: set
    call positional_word(cards, card, 1, 'edge set (INNER, OUTER, TOP or BOTTOM)', set, error)
    if (allocated(error)) return
    call named_real(cards, card, 'P', pressure%value, error, range=pressure_range); if (allocated(error)) return
    call named_word(cards, card, 'CURVE', curve, error, default=''); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'PRESSURE INNER|OUTER|TOP|BOTTOM P=.. [CURVE=name]')
    if (allocated(error)) return
    pressure%edge_set = edge_set_code(set)
    if (pressure%edge_set == edge_set_none .or. pressure%edge_set == edge_set_axis) then
      call card_error(error, cards, card, 'edge set must be INNER, OUTER, TOP or BOTTOM, got "'//set//'"', &
                      field_column(card, '1')); return
    end if
    pressure%line = card%line
    pressures = [pressures, pressure]
  end subroutine read_pressure

  !> FORCE n FR=.. FZ=.. [CURVE=name]  (N per radian in axisymmetry, N per metre in plane strain)
  subroutine read_force(cards, card, index, forces, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    integer, intent(in) :: index
    type(pending_t), allocatable, intent(inout) :: forces(:)
    type(error_t), allocatable, intent(inout) :: error
    type(pending_t) :: force
    force%card = index
    call positional_word(cards, card, 1, 'node number', force%target, error); if (allocated(error)) return
    force%column = field_column(card, '1')
    call named_real(cards, card, 'FR', force%values(1), error, default=0.0_dp, range=force_range)
    if (allocated(error)) return
    call named_real(cards, card, 'FZ', force%values(2), error, default=0.0_dp, range=force_range)
    if (allocated(error)) return
    call named_word(cards, card, 'CURVE', force%curve, error, default=''); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'FORCE n FR=.. FZ=.. [CURVE=name]'); if (allocated(error)) return
    forces = [forces, force]
  end subroutine read_force

  !> PROBE name NODE=n   or   PROBE name R=.. Z=..  (the nearest node)
  subroutine read_probe(cards, card, index, probes, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    integer, intent(in) :: index
    type(pending_t), allocatable, intent(inout) :: probes(:)
    type(error_t), allocatable, intent(inout) :: error
    type(pending_t) :: probe
    integer :: node, k
    probe%card = index
    call positional_word(cards, card, 1, 'probe name', probe%components, error); if (allocated(error)) return
    if (verify(probe%components, 'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0 .or. len(probe%components) > 24) then
      call card_error(error, cards, card, 'probe name must be letters, digits or _ (24 at most), got "'// &
                      probe%components//'"', field_column(card, '1')); return
    end if
    do k = 1, size(probes)
      if (probes(k)%components == probe%components) then
        call card_error(error, cards, card, 'probe '//probe%components//' defined twice (first on line '// &
                        itoa(cards%cards(probes(k)%card)%line)//')', field_column(card, '1')); return
      end if
    end do
    if (has_field(card, 'NODE')) then
      call named_integer(cards, card, 'NODE', node, error); if (allocated(error)) return
      probe%target = itoa(node)
      probe%column = field_column(card, 'NODE')
    else
      call named_real(cards, card, 'R', probe%values(1), error, range=length_range); if (allocated(error)) return
      call named_real(cards, card, 'Z', probe%values(2), error, range=length_range); if (allocated(error)) return
      probe%target = ''
    end if
    call check_fields_used(cards, card, error, 'PROBE name NODE=n | R=.. Z=..'); if (allocated(error)) return
    probes = [probes, probe]
  end subroutine read_probe

  !> EXPECT key value [RTOL=0.01]: the value a summary key should have.
  !> The value is nonzero (the relative error divides by it); a key is expected once.
  subroutine read_expect(cards, card, expects, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(expect_t), allocatable, intent(inout) :: expects(:)
    type(error_t), allocatable, intent(inout) :: error
    type(expect_t) :: expect
    integer :: k
    call positional_word(cards, card, 1, 'summary key', expect%key, error); if (allocated(error)) return
    call positional_real(cards, card, 2, 'expected value', expect%value, error, range=expected_value_range)
    if (allocated(error)) return
    call named_real(cards, card, 'RTOL', expect%tolerance, error, default=1.0e-2_dp, range=tolerance_range)
    if (allocated(error)) return
    call check_fields_used(cards, card, error, 'EXPECT key value [RTOL=..]'); if (allocated(error)) return
    do k = 1, size(expects)
      if (expects(k)%key == expect%key) then
        call card_error(error, cards, card, 'key '//to_lower(expect%key)//' is already expected on line '// &
                        itoa(expects(k)%line), field_column(card, '1')); return
      end if
    end do
    expect%line = card%line
    expect%column = field_column(card, '1')
    expects = [expects, expect]
  end subroutine read_expect

  subroutine resolve_materials(deck, error)
    type(deck_t), intent(inout) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: e, k
    do e = 1, deck%mesh%nelem
      associate (name => deck%mesh%element_material_name(e))
      if (len_trim(name) == 0) then
        if (size(deck%materials) == 1) then
          deck%mesh%element_material(e) = 1
          cycle
        end if
        call line_error(error, deck, deck%mesh%element_line(e), 'element '//itoa(deck%mesh%element_id(e))// &
          ' needs MAT=<id>: the deck defines several materials')
        return
      end if
      do k = 1, size(deck%materials)
        if (deck%materials(k)%id == trim(name)) deck%mesh%element_material(e) = k
      end do
      if (deck%mesh%element_material(e) == 0) then
        call line_error(error, deck, deck%mesh%element_line(e), 'element '//itoa(deck%mesh%element_id(e))// &
          ' uses material '//trim(name)//', which is not defined by a MATERIAL card', 'MAT')
        return
      end if
      end associate
    end do
  end subroutine resolve_materials

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

  !> ' (did you mean X?)' for a near-miss word, '' if none.
  pure function suggestion(word) result(text)
    character(*), intent(in) :: word
    character(:), allocatable :: text
    text = ''
    if (len_trim(word) > 0) text = ' (did you mean '//trim(word)//'?)'
  end function suggestion

  !> Node index of a target written as a node number; error if undefined.
  integer function target_node(deck, pending, error) result(node)
    type(deck_t), intent(in) :: deck
    type(pending_t), intent(in) :: pending
    type(error_t), allocatable, intent(inout) :: error
    integer :: id, ios
    node = 0
    read(pending%target, *, iostat=ios) id
    if (ios /= 0 .or. verify(pending%target, '0123456789') /= 0) then
      call card_error(error, deck%cards, deck%cards%cards(pending%card), 'target must be a node number'// &
        ' or a set name (AXIS, BOTTOM, TOP, INNER, OUTER), got "'//pending%target//'"', pending%column)
      return
    end if
    node = node_index(deck%mesh, id)
    if (node == 0) call card_error(error, deck%cards, deck%cards%cards(pending%card), 'node '// &
      pending%target//' is not defined', pending%column)
  end function target_node

  !> FIX targets to nodes. A component prescribed twice must be prescribed
  !> alike (same value and curve); the axis condition u_r = 0 counts as one.
  subroutine resolve_fixes(deck, pending, error)
    type(deck_t), intent(inout) :: deck
    type(pending_t), intent(in) :: pending(:)
    type(error_t), allocatable, intent(inout) :: error
    integer, allocatable :: owner(:, :)
    integer :: k, i, c, code, node, other
    logical :: fixed(2)
    allocate(deck%fixes(size(pending)), owner(2, deck%mesh%nnode))
    owner = 0
    do k = 1, size(pending)
      associate (fix => deck%fixes(k), card => deck%cards%cards(pending(k)%card))
      fix%line = card%line
      fix%fix_r = index(pending(k)%components, 'R') > 0
      fix%fix_z = index(pending(k)%components, 'Z') > 0
      fix%value = pending(k)%values
      fix%curve = curve_index(deck, pending(k)%card, pending(k)%curve, error)
      if (allocated(error)) return
      code = edge_set_code(pending(k)%target)
      if (code /= edge_set_none) then
        call node_set(deck%mesh, code, fix%nodes)
        if (size(fix%nodes) == 0) then
          call card_error(error, deck%cards, card, 'set '//pending(k)%target//' has no nodes in this mesh', &
                          pending(k)%column); return
        end if
      else
        fix%nodes = [target_node(deck, pending(k), error)]
        if (allocated(error)) return
      end if
      fixed = [fix%fix_r, fix%fix_z]
      do i = 1, size(fix%nodes)
        node = fix%nodes(i)
        if (deck%geometry == geometry_axisymmetric .and. deck%mesh%xy(1, node) == 0.0_dp .and. &
            fix%fix_r .and. fix%value(1) /= 0.0_dp) then
          call card_error(error, deck%cards, card, 'node '//itoa(deck%mesh%node_id(node))// &
            ' is on the axis, where u_r = 0 always; it cannot have UR='//short_real(fix%value(1)), &
            field_column(card, 'UR'))
          return
        end if
        do c = 1, 2
          if (.not. fixed(c)) cycle
          other = owner(c, node)
          if (other > 0) then
            if (deck%fixes(other)%value(c) /= fix%value(c) .or. deck%fixes(other)%curve /= fix%curve) then
              call card_error(error, deck%cards, card, 'node '//itoa(deck%mesh%node_id(node))//' gets a '// &
                'different prescribed '//trim(merge('u_r', 'u_z', c == 1))//' from the FIX card on line '// &
                itoa(deck%fixes(other)%line)//' (a node may be prescribed twice only alike)', pending(k)%column)
              return
            end if
          end if
          owner(c, node) = k
        end do
      end do
      end associate
    end do
  end subroutine resolve_fixes

  subroutine resolve_forces(deck, pending, error)
    type(deck_t), intent(inout) :: deck
    type(pending_t), intent(in) :: pending(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    allocate(deck%forces(size(pending)))
    do k = 1, size(pending)
      deck%forces(k)%node = target_node(deck, pending(k), error)
      if (allocated(error)) return
      deck%forces(k)%value = pending(k)%values
      deck%forces(k)%line = deck%cards%cards(pending(k)%card)%line
      deck%forces(k)%curve = curve_index(deck, pending(k)%card, pending(k)%curve, error)
      if (allocated(error)) return
    end do
  end subroutine resolve_forces

  !> Index of the curve named on card `card` (0 for ''); error if undefined or
  !> if the analysis has no time axis.
  integer function curve_index(deck, card, name, error) result(found)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: card
    character(*), intent(in) :: name
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    found = 0
    if (len(name) == 0) return
    associate (the_card => deck%cards%cards(card))
    if (deck%analysis == analysis_static) then
      call card_error(error, deck%cards, the_card, 'CURVE= needs a time axis: use ANALYSIS QUASISTATIC '// &
                      'or DYNAMIC with TIME cards (STATIC applies every load once, in full)', &
                      field_column(the_card, 'CURVE'))
      return
    end if
    do k = 1, size(deck%curves)
      if (deck%curves(k)%name == name) found = k
    end do
    if (found == 0) call card_error(error, deck%cards, the_card, 'curve '//name// &
      ' is not defined by a CURVE card', field_column(the_card, 'CURVE'))
    end associate
  end function curve_index

  !> TIME belongs to QUASISTATIC and DYNAMIC (required there), not to STATIC.
  subroutine check_time_stages(deck, analysis_line, error)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: analysis_line
    type(error_t), allocatable, intent(inout) :: error
    if (deck%analysis /= analysis_static .and. size(deck%stages) == 0) then
      call line_error(error, deck, analysis_line, analysis_name(deck%analysis)// &
                      ' analysis needs a TIME DT=.. TEND=.. card', '1')
    else if (deck%analysis == analysis_static .and. size(deck%stages) > 0) then
      call line_error(error, deck, deck%stages(1)%line, &
                      'TIME cards need ANALYSIS QUASISTATIC or DYNAMIC (STATIC has no time axis)')
    end if
  end subroutine check_time_stages

  !> WILSON, INITIAL and DROP belong to DYNAMIC; INITIAL VZ= and DROP exclude
  !> each other; OUTPUT needs a time axis and its FIELDS times must lie on it.
  subroutine check_dynamic_cards(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, lines(3)
    real(dp) :: speed(2)
    character(len=10), parameter :: names(3) = ['WILSON    ', 'INITIAL   ', 'DROP      ']
    associate (d => deck%dynamics)
    lines = [d%wilson_line, d%initial_line, d%drop_line]
    if (deck%analysis /= analysis_dynamic) then
      do k = 1, size(lines)
        if (lines(k) == 0) cycle
        call line_error(error, deck, lines(k), trim(card_keyword_at(deck, lines(k), names(k)))// &
                        ' needs ANALYSIS DYNAMIC (this deck is '// &
                        analysis_name(deck%analysis)//')')
        return
      end do
    end if
    if (d%drop_line > 0) then
      speed = initial_velocity(deck)
      if (.not. in_range(speed(2), speed_range)) then
        call line_error(error, deck, d%drop_line, 'DROP HEIGHT = '//short_real(d%drop_height)//' m with g = '// &
          short_real(merge(deck%gravity, standard_gravity, deck%gravity_line > 0))//' m/s^2 gives VZ = '// &
          short_real(speed(2))//' m/s; the speed must be '//range_text(speed_range), 'HEIGHT')
        return
      end if
    end if
    if (d%drop_line > 0 .and. d%initial_line > 0) then
      if (d%velocity(2) /= 0.0_dp) then
        call line_error(error, deck, d%drop_line, 'DROP sets the initial VZ = -sqrt(2 g h); the INITIAL card '// &
                        'on line '//itoa(d%initial_line)//' sets VZ too: give one of them', 'HEIGHT')
        return
      end if
    end if
    end associate
    if (deck%output%line > 0) then
      if (deck%analysis /= analysis_dynamic) then
        call line_error(error, deck, deck%output%line, 'OUTPUT applies to ANALYSIS DYNAMIC (this deck is '// &
                        analysis_name(deck%analysis)//'; QUASISTATIC records every step)')
        return
      end if
      if (size(deck%output%field_times) > 0 .and. size(deck%stages) > 0) then
        if (deck%output%field_times(size(deck%output%field_times)) > deck%stages(size(deck%stages))%end_time) then
          call line_error(error, deck, deck%output%line, 'FIELDS time '// &
            short_real(deck%output%field_times(size(deck%output%field_times)))// &
            ' s is after the end of the run (TEND = '//short_real(deck%stages(size(deck%stages))%end_time)//' s)', &
            'FIELDS')
          return
        end if
      end if
    end if
  end subroutine check_dynamic_cards

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

  !> PLATE belongs to STATIC (the body pressed onto the plate) and DYNAMIC
  !> (impact); STOP to DYNAMIC. MAXDEFORMATION and SEPARATION need a plate,
  !> SEPARATION one that lets go (RELEASE=YES). A dynamic run with a plate
  !> stops at maximum deformation unless a STOP card says otherwise.
  subroutine check_contact_cards(deck, error)
    type(deck_t), intent(inout) :: deck
    type(error_t), allocatable, intent(inout) :: error
    if (deck%plate%line > 0 .and. deck%analysis == analysis_quasistatic) then
      call line_error(error, deck, deck%plate%line, &
                      'PLATE needs ANALYSIS STATIC or DYNAMIC (QUASISTATIC has no contact search)'); return
    end if
    if (deck%stop_line == 0) then
      if (deck%plate%line > 0 .and. deck%analysis == analysis_dynamic) deck%stop_at = stop_at_max_deformation
      return
    end if
    if (deck%analysis /= analysis_dynamic) then
      call line_error(error, deck, deck%stop_line, 'STOP needs ANALYSIS DYNAMIC (this deck is '// &
                      analysis_name(deck%analysis)//')'); return
    end if
    if (deck%stop_at /= stop_at_tend .and. deck%plate%line == 0) then
      call line_error(error, deck, deck%stop_line, 'STOP AT='//stop_name(deck%stop_at)// &
                      ' needs a PLATE card (or use STOP AT=TEND)', 'AT'); return
    end if
    if (deck%stop_at == stop_at_separation .and. .not. deck%plate%release) then
      call line_error(error, deck, deck%stop_line, 'STOP AT=SEPARATION needs PLATE ... RELEASE=YES (line '// &
                      itoa(deck%plate%line)//'): without it contact nodes are held for good and the body never '// &
                      'leaves the plate', 'AT'); return
    end if
  end subroutine check_contact_cards

  !> The body starts on or above the plate: no node below z = Z.
  subroutine check_plate_position(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: lowest
    if (deck%plate%line == 0) return
    lowest = minloc(deck%mesh%xy(2, :), dim=1)
    if (deck%mesh%xy(2, lowest) < deck%plate%z - 1.0e-9_dp*deck%mesh%size) then
      call line_error(error, deck, deck%plate%line, 'node '//itoa(deck%mesh%node_id(lowest))//' (r = '// &
        rtoa(deck%mesh%xy(1, lowest))//', z = '//rtoa(deck%mesh%xy(2, lowest))//') lies below the plate z = '// &
        rtoa(deck%plate%z)//': the body must start on or above the plate', 'Z')
    end if
  end subroutine check_plate_position

  !> Inertia and gravity need mass: every material in use needs RHO > 0.
  subroutine check_mass(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    if (deck%analysis /= analysis_dynamic .and. deck%gravity_line == 0) return
    do k = 1, size(deck%materials)
      if (deck%materials(k)%density > 0.0_dp) cycle
      if (.not. any(deck%mesh%element_material == k)) cycle
      call line_error(error, deck, deck%materials(k)%line, 'material '//deck%materials(k)%id//' has no density: '// &
        trim(merge('ANALYSIS DYNAMIC', 'GRAVITY         ', deck%analysis == analysis_dynamic))// &
        ' needs RHO= > 0 (kg/m^3)', 'RHO')
      return
    end do
  end subroutine check_mass

  !> A warning for a nearly incompressible material (K/G > 1000, nu > 0.4995)
  !> in the standard element, which locks: FORMULATION BBAR does not.
  subroutine check_locking(deck)
    type(deck_t), intent(inout) :: deck
    integer :: k
    real(dp) :: ratio
    if (deck%formulation /= formulation_standard) return
    do k = 1, size(deck%materials)
      if (.not. any(deck%mesh%element_material == k)) cycle
      ratio = deck%materials(k)%bulk/max(deck%materials(k)%shear, tiny(1.0_dp))   ! instantaneous G(0)
      if (ratio > 1000.0_dp) call add_warning(deck, deck%materials(k)%line, 'MATERIAL', 'material '// &
        deck%materials(k)%id//' is nearly incompressible (K/G = '//rtoa(ratio)//'): the standard '// &
        'element locks (too stiff); FORMULATION BBAR avoids that')
    end do
  end subroutine check_locking

  !> Add a located warning to the deck.
  subroutine add_warning(deck, line, card, message)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: line
    character(*), intent(in) :: card, message
    type(warning_t) :: warning
    warning%text = deck%cards%file//':'//itoa(line)//': '//card//': '//message
    deck%warnings = [deck%warnings, warning]
  end subroutine add_warning

  !> A material with memory needs time: STATIC cannot say which modulus to use.
  subroutine check_memory_needs_time(deck, analysis_line, error)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: analysis_line
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    if (deck%analysis /= analysis_static) return
    do k = 1, size(deck%materials)
      if (.not. has_memory(deck%materials(k))) cycle
      if (.not. any(deck%mesh%element_material == k)) cycle
      call line_error(error, deck, analysis_line, 'material '//deck%materials(k)%id//' relaxes in time '// &
        '(PRONY terms with BETA > 0): use ANALYSIS QUASISTATIC or DYNAMIC with TIME cards', '1')
      return
    end do
  end subroutine check_memory_needs_time

  subroutine resolve_probes(deck, pending, error)
    type(deck_t), intent(inout) :: deck
    type(pending_t), intent(in) :: pending(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    real(dp), allocatable :: distance(:)
    allocate(deck%probes(size(pending)))
    do k = 1, size(pending)
      deck%probes(k)%name = to_lower(pending(k)%components)
      if (len(pending(k)%target) > 0) then
        deck%probes(k)%node = target_node(deck, pending(k), error)
        if (allocated(error)) return
      else
        distance = (deck%mesh%xy(1, :) - pending(k)%values(1))**2 + (deck%mesh%xy(2, :) - pending(k)%values(2))**2
        deck%probes(k)%node = minloc(distance, dim=1)
      end if
    end do
  end subroutine resolve_probes

  !> A load or prescribed displacement times its curve stays in its range
  !> (each within its own, the product too: P = 1e12 Pa with a curve up to
  !> 1e6 would reach 1e18 Pa).
  subroutine check_load_sizes(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    do k = 1, size(deck%pressures)
      call check_product(deck%pressures(k)%line, [deck%pressures(k)%value], deck%pressures(k)%curve, 'P', pressure_range)
      if (allocated(error)) return
    end do
    do k = 1, size(deck%forces)
      call check_product(deck%forces(k)%line, deck%forces(k)%value, deck%forces(k)%curve, 'FR, FZ', force_range)
      if (allocated(error)) return
    end do
    do k = 1, size(deck%fixes)
      call check_product(deck%fixes(k)%line, deck%fixes(k)%value, deck%fixes(k)%curve, 'UR, UZ', length_range)
      if (allocated(error)) return
    end do
  contains
    subroutine check_product(line, values, curve, names, range)
      integer, intent(in) :: line
      real(dp), intent(in) :: values(:)
      integer, intent(in) :: curve
      character(*), intent(in) :: names
      type(range_t), intent(in) :: range
      real(dp) :: largest
      if (curve == 0) return
      largest = maxval(abs(values))*maxval(abs(deck%curves(curve)%value))
      if (largest <= range%upper) return
      call line_error(error, deck, line, names//' times curve '//deck%curves(curve)%name//' (line '// &
        itoa(deck%curves(curve)%line)//') reaches '//rtoa(largest)//': it must stay '//range_text(range), 'CURVE')
    end subroutine check_product
  end subroutine check_load_sizes

  subroutine check_pressures(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    do k = 1, size(deck%pressures)
      if (.not. any(deck%mesh%edge_set == deck%pressures(k)%edge_set)) then
        call line_error(error, deck, deck%pressures(k)%line, 'edge set '//edge_set_name(deck%pressures(k)%edge_set)// &
          ' has no boundary edges in this mesh', '1')
        return
      end if
    end do
  end subroutine check_pressures

end module visco2d_deck
