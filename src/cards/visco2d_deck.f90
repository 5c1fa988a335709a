!> A deck: the cards of one input file interpreted as a model (title,
!> analysis, geometry, materials, mesh, supports, loads, time histories,
!> time stages, probes), with every reference checked. Errors name the
!> file, line, column and card. read_deck reads each card, checks that the
!> deck is complete, builds the mesh, resolves the pending targets
!> (visco2d_deck_targets) and runs the cross-card checks
!> (visco2d_deck_checks). The deck types and queries live in
!> visco2d_deck_types and are re-exported here, so a user of a deck
!> imports this module only.
module visco2d_deck
  use visco2d_kinds, only: geometry_axisymmetric, geometry_plane_strain, kinematics_small, kinematics_large
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, short_real, nearest_word
  use visco2d_cards, only: card_deck_t, read_cards, card_error, positional_word, check_fields_used, field_column, &
                           named_integer, named_word, has_field
  use visco2d_material_cards, only: read_material, read_prony, finish_material, read_plastic, read_hardening, &
                                    read_ogden
  use visco2d_curve_cards, only: read_curve
  use visco2d_time, only: time_stage_t, read_time
  use visco2d_dynamic_cards, only: dynamic_settings_t, output_request_t, read_wilson, read_initial, read_drop, &
                                   read_gravity, read_output, read_formulation, theta_unconditional, &
                                   read_integrator
  use visco2d_contact_cards, only: plate_t, pad_t, body_t, read_plate, read_pad, read_body, read_stop, stop_name, &
                                   stop_at_tend, &
                                   stop_at_max_deformation, stop_at_separation
  use visco2d_bruise_cards, only: read_bruise, check_bruise_cards, criterion_plastic
  use visco2d_mesh_cards, only: mesh_input_t, read_node_card, read_element_card, read_mesh_card
  use visco2d_mesh_build, only: build_mesh
  use visco2d_pad_mesh, only: append_pad
  use visco2d_body_mesh, only: append_body
  use visco2d_deck_types, only: deck_t, settings_t, loads_t, source_t, fix_t, pressure_t, force_t, probe_t, &
                                expect_t, warning_t, &
                                analysis_static, analysis_quasistatic, analysis_dynamic, analysis_name, &
                                geometry_name, total_steps, formulation_name, initial_velocity, add_warning, &
                                solver_card_names, card_at_line
  use visco2d_deck_targets, only: pending_t, read_fix, read_pressure, read_force, read_probe, read_expect, &
                                  resolve_materials, resolve_fixes, resolve_forces, resolve_probes, curve_index
  use visco2d_deck_meaning, only: check_meaning
  use visco2d_deck_checks, only: check_time_stages, check_dynamic_cards, check_contact_cards, &
                                 check_plate_position, check_plate_supports, check_mass, check_locking, &
                                 check_memory_needs_time, check_load_sizes, check_pressures, check_kinematics
  implicit none
  private

  public :: deck_t, settings_t, loads_t, source_t, fix_t, pressure_t, force_t, probe_t, expect_t, time_stage_t, &
            warning_t, read_deck
  public :: dynamic_settings_t, output_request_t
  public :: analysis_static, analysis_quasistatic, analysis_dynamic, analysis_name, geometry_name, total_steps
  public :: formulation_name, initial_velocity
  public :: plate_t, pad_t, body_t, stop_at_tend, stop_at_max_deformation, stop_at_separation, stop_name

  !> Every card keyword a deck may use.
  character(len=11), parameter :: card_keywords(33) = [character(len=11) :: 'TITLE', 'ANALYSIS', 'GEOMETRY', &
    'FORMULATION', 'KINEMATICS', 'SOLVER', 'MATERIAL', 'PRONY', 'OGDEN', 'PLASTIC', 'HARDENING', 'NODE', 'ELEMENT', &
    'MESH', 'FIX', 'PRESSURE', 'FORCE', 'GRAVITY', &
    'CURVE', 'TIME', 'WILSON', 'INTEGRATOR', 'INITIAL', 'DROP', 'OUTPUT', 'PLATE', 'PAD', 'STOP', 'PROBE', 'EXPECT', &
    'BRUISE', 'BODY', 'END']

  !> What read_deck keeps while it reads the cards: the mesh cards, the
  !> targets still to resolve and the lines of the once-only cards.
  type :: reading_t
    type(mesh_input_t) :: mesh_input
    type(pending_t), allocatable :: fixes(:), forces(:), probes(:)
    character(len=32), allocatable :: pressure_curves(:)  !< CURVE= of each PRESSURE card, '' if none
    integer, allocatable :: pressure_cards(:)             !< card index of each PRESSURE card
    integer :: title_line = 0, analysis_line = 0, geometry_line = 0, formulation_line = 0, kinematics_line = 0
    integer :: material_card = 0                          !< index of the last MATERIAL card, 0 if none
    logical :: increments_given = .false.                 !< ANALYSIS STATIC has INCREMENTS= or ITERATIONS=
  end type reading_t

  !> The largest INCREMENTS= and ITERATIONS= of ANALYSIS STATIC.
  integer, parameter :: max_increments = 100000, max_iterations = 1000

contains

  !> Read and check a deck file: each card, then the deck as a whole.
  subroutine read_deck(file, deck, error)
    character(*), intent(in) :: file
    type(deck_t), intent(out) :: deck
    type(error_t), allocatable, intent(out) :: error
    type(reading_t) :: reading
    integer :: i

    call read_cards(file, deck%cards, error, card_keywords)
    if (allocated(error)) return
    deck%source = card_source(deck%cards)
    deck%title = ''
    allocate(deck%materials(0), deck%loads%pressures(0), deck%expects(0), deck%loads%curves(0), deck%stages(0))
    allocate(deck%warnings(0), deck%output%field_times(0), deck%bruises(0))
    allocate(reading%fixes(0), reading%forces(0), reading%probes(0), reading%pressure_curves(0))
    allocate(reading%pressure_cards(0))
    do i = 1, deck%cards%count
      call read_card(deck, reading, i, error); if (allocated(error)) return
    end do
    call check_complete(file, deck, error); if (allocated(error)) return
    if (reading%analysis_line == 0) then
      call card_error(error, deck%cards, deck%cards%cards(deck%cards%count), 'missing ANALYSIS card (ANALYSIS '// &
                      'STATIC, QUASISTATIC or DYNAMIC) before END'); return
    end if
    call finish_deck(deck, reading, error)
  end subroutine read_deck

  !> Where a deck was read from (the located errors of a failed solve): its
  !> file, and the line and keyword of each card.
  pure function card_source(cards) result(source)
    type(card_deck_t), intent(in) :: cards
    type(source_t) :: source
    integer :: k
    source%file = cards%file
    allocate(source%lines(cards%count), source%keywords(cards%count))
    do k = 1, cards%count
      source%lines(k) = cards%cards(k)%line
      source%keywords(k) = cards%cards(k)%keyword
    end do
  end function card_source

  !> Read card i into the deck (or into `reading` until the mesh exists).
  subroutine read_card(deck, reading, i, error)
    type(deck_t), intent(inout) :: deck
    type(reading_t), intent(inout) :: reading
    integer, intent(in) :: i
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word

    associate (cards => deck%cards, card => deck%cards%cards(i))
    select case (card%keyword)
    case ('TITLE', 'ANALYSIS', 'GEOMETRY', 'FORMULATION', 'KINEMATICS', 'SOLVER')
      call read_model_card(deck, reading, i, error)
    case ('WILSON', 'INTEGRATOR', 'INITIAL', 'DROP', 'GRAVITY', 'OUTPUT', 'PLATE', 'PAD', 'BODY', 'STOP')
      call read_motion_card(deck, i, error)
    case ('MATERIAL')
      call read_material(cards, card, deck%materials, error); if (allocated(error)) return
      reading%material_card = i
    case ('PRONY')
      if (.not. follows_material(deck, reading, i)) then
        call card_error(error, cards, card, 'PRONY must follow its MATERIAL card (or another PRONY card)')
        return
      end if
      call read_prony(cards, card, deck%materials(size(deck%materials)), error)
    case ('OGDEN')
      if (.not. follows(deck, reading, i, ['MATERIAL', 'OGDEN   '])) then
        call card_error(error, cards, card, 'OGDEN must follow its MATERIAL id HYPERFOAM card (or another OGDEN card)')
        return
      end if
      call read_ogden(cards, card, deck%materials(size(deck%materials)), error)
    case ('PLASTIC')
      if (.not. follows(deck, reading, i, ['MATERIAL ', 'PRONY    ', 'PLASTIC  ', 'HARDENING'])) then
        call card_error(error, cards, card, 'PLASTIC must follow its MATERIAL card (or that material''s PRONY cards)')
        return
      end if
      call read_plastic(cards, card, deck%materials(size(deck%materials)), error)
    case ('HARDENING')
      if (.not. follows(deck, reading, i, ['PLASTIC  ', 'HARDENING'])) then
        call card_error(error, cards, card, 'HARDENING must follow its PLASTIC TABLE card (or another HARDENING card)')
        return
      end if
      call read_hardening(cards, card, deck%materials(size(deck%materials)), error)
    case ('CURVE')
      call read_curve(cards, card, deck%loads%curves, error)
    case ('TIME')
      call read_time(cards, card, deck%stages, error)
    case ('NODE')
      call read_node_card(reading%mesh_input, cards, card, error)
    case ('ELEMENT')
      call read_element_card(reading%mesh_input, cards, card, error)
    case ('MESH')
      call read_mesh_card(reading%mesh_input, cards, card, error)
    case ('FIX')
      call read_fix(cards, card, i, reading%fixes, error)
    case ('PRESSURE')
      call read_pressure(cards, card, deck%loads%pressures, word, error); if (allocated(error)) return
      reading%pressure_curves = [character(len=32) :: reading%pressure_curves, word]
      reading%pressure_cards = [reading%pressure_cards, i]
      call check_repeated_pressure(deck, reading, i, error)
    case ('FORCE')
      call read_force(cards, card, i, reading%forces, error); if (allocated(error)) return
      call check_repeated_force(deck, reading, i, error)
    case ('PROBE')
      call read_probe(cards, card, i, reading%probes, error)
    case ('EXPECT')
      call read_expect(cards, card, deck%expects, error)
    case ('BRUISE')
      call read_bruise(cards, card, deck%bruises, error)
    case ('END')
      call check_fields_used(cards, card, error, 'END')
    case default
      call card_error(error, cards, card, 'unknown card "'//card%keyword//'"'// &
        suggestion(nearest_word(card%keyword, card_keywords))//' (known: TITLE ANALYSIS '// &
        'GEOMETRY FORMULATION KINEMATICS MATERIAL PRONY OGDEN PLASTIC HARDENING NODE ELEMENT MESH FIX PRESSURE FORCE '// &
        'GRAVITY CURVE TIME '// &
        'WILSON INTEGRATOR INITIAL DROP OUTPUT PLATE PAD BODY STOP PROBE EXPECT BRUISE END)')
    end select
    end associate
  end subroutine read_card

  !> TITLE, ANALYSIS, GEOMETRY and FORMULATION: once each.
  subroutine read_model_card(deck, reading, i, error)
    type(deck_t), intent(inout) :: deck
    type(reading_t), intent(inout) :: reading
    integer, intent(in) :: i
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: word, word_newton
    integer :: k

    associate (cards => deck%cards, card => deck%cards%cards(i))
    select case (card%keyword)
    case ('TITLE')
      call once(deck, i, reading%title_line, error); if (allocated(error)) return
      reading%title_line = card%line
      deck%title = card%rest
    case ('ANALYSIS')
      call once(deck, i, reading%analysis_line, error); if (allocated(error)) return
      reading%analysis_line = card%line
      call positional_word(cards, card, 1, 'analysis kind (STATIC, QUASISTATIC or DYNAMIC)', word, error)
      if (allocated(error)) return
      if (word == 'STATIC') then                   ! the load increments of a plastic solve
        reading%increments_given = has_field(card, 'INCREMENTS')
        call named_integer(cards, card, 'INCREMENTS', deck%settings%increments, error, default=10)
        if (allocated(error)) return
        if (deck%settings%increments < 1 .or. deck%settings%increments > max_increments) then
          call card_error(error, cards, card, 'INCREMENTS must be in [1, '//integer_text(max_increments)//'], got '// &
                          integer_text(deck%settings%increments), field_column(card, 'INCREMENTS')); return
        end if
      end if
      if (word == 'STATIC' .or. word == 'QUASISTATIC' .or. word == 'DYNAMIC') then   ! Newton iterations of an increment or a step
        reading%increments_given = reading%increments_given .or. has_field(card, 'ITERATIONS')
        call named_integer(cards, card, 'ITERATIONS', deck%settings%iterations, error, &
                           default=merge(50, 30, word == 'DYNAMIC'))
        if (allocated(error)) return
        if (deck%settings%iterations < 1 .or. deck%settings%iterations > max_iterations) then
          call card_error(error, cards, card, 'ITERATIONS must be in [1, '//integer_text(max_iterations)//'], got '// &
                          integer_text(deck%settings%iterations), field_column(card, 'ITERATIONS')); return
        end if
      end if
      if (word == 'DYNAMIC' .and. has_field(card, 'NEWTON')) then   ! the plastic step's Newton method
        reading%increments_given = .true.
        call named_word(cards, card, 'NEWTON', word_newton, error)
        if (allocated(error)) return
        if (word_newton /= 'MODIFIED' .and. word_newton /= 'FULL') then
          call card_error(error, cards, card, 'NEWTON must be MODIFIED (the factored S~, the default) or FULL (the '// &
                          'consistent tangent factored at each iteration), got '//word_newton, &
                          field_column(card, 'NEWTON')); return
        end if
        deck%settings%full_newton = word_newton == 'FULL'
      end if
      call check_fields_used(cards, card, error, &
        'ANALYSIS STATIC [INCREMENTS=n] [ITERATIONS=n] | QUASISTATIC [ITERATIONS=n] | DYNAMIC [ITERATIONS=n] '// &
        '[NEWTON=MODIFIED|FULL]')
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
      end select
    case ('GEOMETRY')
      call once(deck, i, reading%geometry_line, error); if (allocated(error)) return
      reading%geometry_line = card%line
      call positional_word(cards, card, 1, 'geometry (AXISYMMETRIC or PLANESTRAIN)', word, error)
      if (allocated(error)) return
      call check_fields_used(cards, card, error, 'GEOMETRY AXISYMMETRIC | PLANESTRAIN'); if (allocated(error)) return
      select case (word)
      case ('AXISYMMETRIC')
        deck%settings%geometry = geometry_axisymmetric
      case ('PLANESTRAIN')
        deck%settings%geometry = geometry_plane_strain
      case default
        call card_error(error, cards, card, 'geometry must be AXISYMMETRIC or PLANESTRAIN, got "'//word//'"', &
                        field_column(card, '1'))
      end select
    case ('FORMULATION')
      call once(deck, i, reading%formulation_line, error); if (allocated(error)) return
      call read_formulation(cards, card, deck%settings%formulation, error); if (allocated(error)) return
      reading%formulation_line = card%line
    case ('KINEMATICS')
      call once(deck, i, reading%kinematics_line, error); if (allocated(error)) return
      reading%kinematics_line = card%line
      deck%kinematics_line = card%line
      call positional_word(cards, card, 1, 'kinematics (SMALL or LARGE)', word, error); if (allocated(error)) return
      call check_fields_used(cards, card, error, 'KINEMATICS SMALL | LARGE'); if (allocated(error)) return
      select case (word)
      case ('SMALL')
        deck%settings%kinematics = kinematics_small
      case ('LARGE')
        deck%settings%kinematics = kinematics_large
      case default
        call card_error(error, cards, card, 'kinematics must be SMALL (small strain, the default) or LARGE (finite '// &
                        'deformation), got "'//word//'"', field_column(card, '1'))
      end select
    case ('SOLVER')
      call once(deck, i, deck%solver_line, error); if (allocated(error)) return
      deck%solver_line = card%line
      call positional_word(cards, card, 1, 'solver (BAND, PROFILE or CHOLMOD)', word, error)
      if (allocated(error)) return
      call check_fields_used(cards, card, error, 'SOLVER BAND | PROFILE | CHOLMOD'); if (allocated(error)) return
      deck%settings%solver = 0
      do k = 1, size(solver_card_names)
        if (word == trim(solver_card_names(k))) deck%settings%solver = k
      end do
      if (deck%settings%solver == 0) call card_error(error, cards, card, 'solver must be BAND (the legacy '// &
        'band storage and LAPACK), PROFILE (envelope storage) or CHOLMOD (sparse, the default), got "'//word//'"', &
        field_column(card, '1'))
    end select
    end associate
  end subroutine read_model_card

  !> The cards of the motion, once each: WILSON or INTEGRATOR, INITIAL, DROP,
  !> GRAVITY, OUTPUT, PLATE and STOP.
  subroutine read_motion_card(deck, i, error)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: i
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: warning

    associate (cards => deck%cards, card => deck%cards%cards(i))
    select case (card%keyword)
    case ('WILSON')
      call once(deck, i, deck%dynamics%wilson_line, error); if (allocated(error)) return
      call read_wilson(cards, card, deck%dynamics, error); if (allocated(error)) return
      if (deck%dynamics%theta < theta_unconditional) call add_warning(deck, card%line, 'WILSON', &
        'THETA = '//short_real(deck%dynamics%theta)//' < 1.37: Wilson-theta is then only conditionally stable;'// &
        ' a large DT may blow up (1.4 is the usual value)')
    case ('INTEGRATOR')
      call once(deck, i, deck%dynamics%wilson_line, error); if (allocated(error)) return
      call read_integrator(cards, card, deck%dynamics, error, warning); if (allocated(error)) return
      if (allocated(warning)) call add_warning(deck, card%line, 'INTEGRATOR', warning)
    case ('INITIAL')
      call once(deck, i, deck%dynamics%initial_line, error); if (allocated(error)) return
      call read_initial(cards, card, deck%dynamics, error)
    case ('DROP')
      call once(deck, i, deck%dynamics%drop_line, error); if (allocated(error)) return
      call read_drop(cards, card, deck%dynamics, error)
    case ('GRAVITY')
      call once(deck, i, deck%gravity_line, error); if (allocated(error)) return
      call read_gravity(cards, card, deck%loads%gravity, error); if (allocated(error)) return
      deck%gravity_line = card%line
    case ('OUTPUT')
      call once(deck, i, deck%output%line, error); if (allocated(error)) return
      call read_output(cards, card, deck%output, error)
    case ('PLATE')
      call once(deck, i, deck%plate%line, error); if (allocated(error)) return
      call read_plate(cards, card, deck%plate, error)
    case ('PAD')
      call once(deck, i, deck%pad%line, error); if (allocated(error)) return
      call read_pad(cards, card, deck%pad, error)
    case ('BODY')
      call once(deck, i, deck%body%line, error); if (allocated(error)) return
      call read_body(cards, card, deck%body, error)
    case ('STOP')
      call once(deck, i, deck%stop_line, error); if (allocated(error)) return
      call read_stop(cards, card, deck%stop_at, error); if (allocated(error)) return
      deck%stop_line = card%line
    end select
    end associate
  end subroutine read_motion_card

  !> An error if card i may appear once and already did (on first_line > 0).
  subroutine once(deck, i, first_line, error)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: i, first_line
    type(error_t), allocatable, intent(inout) :: error
    if (first_line == 0) return
    call card_error(error, deck%cards, deck%cards%cards(i), 'only one '//deck%cards%cards(i)%keyword// &
      ' card is allowed (first on line '//integer_text(first_line)//')')
  end subroutine once

  !> The same pressure twice (same set, value and curve) is a duplicated
  !> line, not a load meant to be doubled (card i is the last PRESSURE read).
  subroutine check_repeated_pressure(deck, reading, i, error)
    type(deck_t), intent(in) :: deck
    type(reading_t), intent(in) :: reading
    integer, intent(in) :: i
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, n
    n = size(deck%loads%pressures)
    do k = 1, n - 1
      if (deck%loads%pressures(k)%edge_set /= deck%loads%pressures(n)%edge_set) cycle
      if (deck%loads%pressures(k)%value /= deck%loads%pressures(n)%value .or. &
          reading%pressure_curves(k) /= reading%pressure_curves(n)) cycle
      call card_error(error, deck%cards, deck%cards%cards(i), 'the same pressure as on line '// &
        integer_text(deck%loads%pressures(k)%line)//' (a duplicated line?): give the total on one card', &
        field_column(deck%cards%cards(i), 'P'))
      return
    end do
  end subroutine check_repeated_pressure

  !> The same point load twice (same node, values and curve): a duplicated
  !> line (card i is the last FORCE read).
  subroutine check_repeated_force(deck, reading, i, error)
    type(deck_t), intent(in) :: deck
    type(reading_t), intent(in) :: reading
    integer, intent(in) :: i
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, n
    associate (forces => reading%forces)
    n = size(forces)
    do k = 1, n - 1
      if (forces(k)%target /= forces(n)%target .or. forces(k)%curve /= forces(n)%curve) cycle
      if (any(forces(k)%values /= forces(n)%values)) cycle
      call card_error(error, deck%cards, deck%cards%cards(i), 'the same force as on line '// &
        integer_text(deck%cards%cards(forces(k)%card)%line)//' (a duplicated line?): give the total on one card', &
        forces(n)%column)
      return
    end do
    end associate
  end subroutine check_repeated_force

  !> True if card k directly follows a card of one of these keywords, after a MATERIAL card.
  logical function follows(deck, reading, k, keywords)
    type(deck_t), intent(in) :: deck
    type(reading_t), intent(in) :: reading
    integer, intent(in) :: k
    character(*), intent(in) :: keywords(:)
    follows = .false.
    if (reading%material_card == 0 .or. k < 2) return
    follows = any(deck%cards%cards(k - 1)%keyword == keywords)
  end function follows

  !> Plasticity is solved by ANALYSIS STATIC (alone or on the rigid PLATE
  !> with SLIP, not on a PAD), by ANALYSIS QUASISTATIC (which has no contact:
  !> a PLATE or PAD there is refused by check_contact_cards) and by ANALYSIS
  !> DYNAMIC (with or without the rigid PLATE, on a PAD whose own materials
  !> are not plastic) so far: elsewhere a PLASTIC card is an error (not an
  !> elastic run). An
  !> INCREMENTS= or ITERATIONS= on a deck without plasticity is a warning.
  subroutine check_plastic_analysis(deck, reading, error)
    type(deck_t), intent(inout) :: deck
    type(reading_t), intent(in) :: reading
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, m, j
    m = 0
    do k = 1, size(deck%materials)
      if (deck%materials(k)%plastic) then
        m = k
        exit
      end if
    end do
    call check_plastic_bruise(deck, m, error)
    if (allocated(error)) return
    if (m == 0) then
      if (reading%increments_given .and. deck%analysis == analysis_static .and. &
          deck%settings%kinematics /= kinematics_large) call add_warning(deck, &
        reading%analysis_line, 'ANALYSIS', 'INCREMENTS= and ITERATIONS= are for plastic materials (a PLASTIC card); '// &
        'this deck has none and is solved in one linear step')
      if (reading%increments_given .and. deck%analysis == analysis_dynamic .and. &
          deck%settings%kinematics /= kinematics_large) call add_warning(deck, &
        reading%analysis_line, 'ANALYSIS', 'ITERATIONS= and NEWTON= are for plastic materials (a PLASTIC card) or '// &
        'KINEMATICS LARGE; '// &
        'this deck has none and each step is one linear solve')
      if (reading%increments_given .and. deck%analysis == analysis_quasistatic) call add_warning(deck, &
        reading%analysis_line, 'ANALYSIS', 'ITERATIONS= is for plastic materials (a PLASTIC card); '// &
        'this deck has none and each step is one linear solve')
      return
    end if
    k = card_at_line(deck, deck%materials(m)%plastic_line)
    if (deck%analysis == analysis_static) then
      if (deck%pad%line > 0) then
        call card_error(error, deck%cards, deck%cards%cards(k), 'plasticity (PLASTIC, material '// &
          deck%materials(m)%id//') in ANALYSIS STATIC is not available on a PAD yet (line '// &
          integer_text(deck%pad%line)//'); it is on the rigid PLATE with SLIP'); return
      end if
      if (deck%plate%line > 0 .and. deck%plate%stick) then
        call card_error(error, deck%cards, deck%cards%cards(k), 'plasticity (PLASTIC, material '// &
          deck%materials(m)%id//') in ANALYSIS STATIC takes frictionless contact only so far: give the PLATE '// &
          'card (line '//integer_text(deck%plate%line)//') SLIP'); return
      end if
    else if (deck%body%line > 0) then
      call card_error(error, deck%cards, deck%cards%cards(k), 'plasticity (PLASTIC, material '// &
        deck%materials(m)%id//') with a second BODY (line '//integer_text(deck%body%line)//') is not available '// &
        'yet: the two bodies are elastic or viscoelastic'); return
    else if (deck%analysis == analysis_dynamic .and. deck%pad%line > 0) then
      do j = 1, size(deck%materials)
        if (.not. (deck%materials(j)%plastic .and. pad_material(deck, deck%materials(j)%id))) cycle
        call card_error(error, deck%cards, deck%cards%cards(card_at_line(deck, deck%materials(j)%plastic_line)), &
          'plasticity of a PAD''s material (PLASTIC, material '//deck%materials(j)%id//', of the PAD on line '// &
          integer_text(deck%pad%line)//') is not available yet; a plastic body on an elastic or viscoelastic pad is')
        return
      end do
    end if
  end subroutine check_plastic_analysis

  !> True if material `id` is the PAD's (MAT=) or its cover's (COVERMAT=).
  pure logical function pad_material(deck, id)
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: id
    pad_material = .false.
    if (allocated(deck%pad%material)) pad_material = deck%pad%material == id
    if (allocated(deck%pad%cover_material)) pad_material = pad_material .or. &
      (len(deck%pad%cover_material) > 0 .and. deck%pad%cover_material == id)
  end function pad_material

  !> A BRUISE CRITERION=PLASTIC card reads the equivalent plastic strain of
  !> an ANALYSIS DYNAMIC run: it needs that analysis and a PLASTIC material
  !> (the one of its MAT=, if given); otherwise it would report no bruise
  !> where nothing can yield, so it is an error at the card. `plastic`: the
  !> first plastic material, 0 if none.
  subroutine check_plastic_bruise(deck, plastic, error)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: plastic
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, j
    if (.not. allocated(deck%bruises)) return
    do k = 1, size(deck%bruises)
      associate (b => deck%bruises(k))
      if (b%criterion /= criterion_plastic) cycle
      if (plastic == 0) then
        call set_error(error, 'CRITERION=PLASTIC reads the equivalent plastic strain, and no material of this deck '// &
          'has a PLASTIC card', file=deck%cards%file, line=b%line, column=b%column, card='BRUISE'); return
      end if
      if (deck%analysis /= analysis_dynamic) then
        call set_error(error, 'CRITERION=PLASTIC is available in ANALYSIS DYNAMIC only so far; this deck is ANALYSIS '// &
          analysis_name(deck%analysis), file=deck%cards%file, line=b%line, column=b%column, card='BRUISE'); return
      end if
      if (len(b%material) == 0) cycle
      do j = 1, size(deck%materials)
        if (deck%materials(j)%id == b%material .and. .not. deck%materials(j)%plastic) then
          call set_error(error, 'CRITERION=PLASTIC for material '//b%material//', which has no PLASTIC card', &
            file=deck%cards%file, line=b%line, column=b%material_column, card='BRUISE'); return
        end if
      end do
      end associate
    end do
  end subroutine check_plastic_bruise

  !> True if card k (a PRONY) directly follows a MATERIAL or PRONY card.
  logical function follows_material(deck, reading, k)
    type(deck_t), intent(in) :: deck
    type(reading_t), intent(in) :: reading
    integer, intent(in) :: k
    follows_material = .false.
    if (reading%material_card == 0 .or. k < 2) return
    follows_material = deck%cards%cards(k - 1)%keyword == 'MATERIAL' .or. &
                       deck%cards%cards(k - 1)%keyword == 'PRONY'
  end function follows_material

  !> The deck read has cards, an END card, a material and a mesh.
  subroutine check_complete(file, deck, error)
    character(*), intent(in) :: file
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    associate (cards => deck%cards)
    if (cards%count == 0) then
      if (cards%lines == 0) then
        call set_error(error, 'the deck has no cards: it is an empty file', file=file, line=1)
      else
        call set_error(error, 'the deck has no cards: its '//integer_text(cards%lines)//' lines are blank or comments', &
                       file=file, line=cards%lines)
      end if
      return
    end if
    if (.not. cards%has_end) then
      call card_error(error, cards, cards%cards(cards%count), 'missing END card: the deck ends after this card '// &
                      '(is it truncated?)'); return
    end if
    end associate
  end subroutine check_complete

  !> Materials and mesh after every card is read: the cross-card checks,
  !> the mesh, the resolved targets and the checks that need the mesh.
  subroutine finish_deck(deck, reading, error)
    type(deck_t), intent(inout) :: deck
    type(reading_t), intent(inout) :: reading
    type(error_t), allocatable, intent(inout) :: error
    integer :: i
    associate (cards => deck%cards)
    if (size(deck%materials) == 0) then
      call card_error(error, cards, cards%cards(first_card(cards, ['ELEMENT', 'MESH   ', 'END    '])), &
                      'missing MATERIAL card: the elements need one (MATERIAL id ELASTIC E=.. NU=..)'); return
    end if
    if (.not. any([(cards%cards(i)%keyword == 'NODE' .or. cards%cards(i)%keyword == 'ELEMENT' .or. &
                    cards%cards(i)%keyword == 'MESH', i = 1, cards%count)])) then
      call card_error(error, cards, cards%cards(cards%count), 'missing mesh: give NODE and ELEMENT cards or a '// &
                      'MESH card before END'); return
    end if
    if (.not. any([(cards%cards(i)%keyword == 'ELEMENT' .or. cards%cards(i)%keyword == 'MESH', &
                    i = 1, cards%count)])) then
      call card_error(error, cards, cards%cards(first_card(cards, ['NODE'])), 'missing elements: NODE cards '// &
                      'need ELEMENT cards to make a mesh (or give a MESH card instead)'); return
    end if
    do i = 1, size(deck%materials)
      call finish_material(cards, deck%materials(i), error); if (allocated(error)) return
    end do
    call check_plastic_analysis(deck, reading, error); if (allocated(error)) return
    call check_kinematics(deck, error); if (allocated(error)) return
    call check_time_stages(deck, reading%analysis_line, error); if (allocated(error)) return
    call check_dynamic_cards(deck, error); if (allocated(error)) return
    call check_contact_cards(deck, error); if (allocated(error)) return
    call check_bruise_cards(cards, deck%bruises, deck%materials, deck%analysis == analysis_quasistatic, error)
    if (allocated(error)) return

    call build_mesh(reading%mesh_input, cards, deck%settings%geometry, deck%mesh, error); if (allocated(error)) return
    call resolve_materials(deck, error); if (allocated(error)) return
    call resolve_fixes(deck, reading%fixes, error); if (allocated(error)) return
    call resolve_forces(deck, reading%forces, error); if (allocated(error)) return
    call resolve_probes(deck, reading%probes, error); if (allocated(error)) return
    call check_pressures(deck, error); if (allocated(error)) return
    do i = 1, size(deck%loads%pressures)
      deck%loads%pressures(i)%curve = curve_index(deck, reading%pressure_cards(i), &
                                                  trim(reading%pressure_curves(i)), error)
      if (allocated(error)) return
    end do
    call check_load_sizes(deck, error); if (allocated(error)) return
    call check_memory_needs_time(deck, reading%analysis_line, error); if (allocated(error)) return
    call check_mass(deck, error); if (allocated(error)) return
    call check_plate_position(deck, error); if (allocated(error)) return
    call check_plate_supports(deck, error); if (allocated(error)) return
    if (deck%pad%line > 0) then                       ! the pad's mesh after the body's (its checks need the body)
      call append_pad(deck, error); if (allocated(error)) return
    end if
    if (deck%body%line > 0) then                      ! the second body after the first (placed under it)
      call append_body(deck, error); if (allocated(error)) return
    end if
    call check_locking(deck)
    call check_meaning(deck, reading%analysis_line)
    end associate
  end subroutine finish_deck

  !> Index of the first card with one of these keywords (the last card if none).
  integer function first_card(cards, keywords) result(found)
    type(card_deck_t), intent(in) :: cards
    character(*), intent(in) :: keywords(:)
    integer :: k
    found = cards%count
    do k = 1, cards%count
      if (any(keywords == cards%cards(k)%keyword)) then
        found = k
        return
      end if
    end do
  end function first_card

  !> ' (did you mean X?)' for a near-miss word, '' if none.
  pure function suggestion(word) result(text)
    character(*), intent(in) :: word
    character(:), allocatable :: text
    text = ''
    if (len_trim(word) > 0) text = ' (did you mean '//trim(word)//'?)'
  end function suggestion

end module visco2d_deck
