!> The cross-card checks of a deck, run once every card is read (and, for
!> those that need nodes and elements, once the mesh is built): cards that
!> belong to one analysis kind, the plate, STOP, masses, memory materials,
!> pressure edge sets, load sizes; and the warning for a locking material.
module visco2d_deck_checks
  use visco2d_kinds, only: dp, formulation_standard, kinematics_large
  use visco2d_error, only: error_t
  use visco2d_strings, only: integer_text, message_real, short_real
  use visco2d_ranges, only: length_range, pressure_range, force_range, speed_range, range_t, in_range, range_text
  use visco2d_material, only: has_memory, hyperelastic_none, hyperelastic_name, material_kind_viscoelastic, &
                              material_kind_name
  use visco2d_dynamic_cards, only: standard_gravity
  use visco2d_contact_cards, only: stop_name, stop_at_tend, stop_at_max_deformation, stop_at_separation
  use visco2d_mesh, only: edge_set_name
  use visco2d_deck_types, only: deck_t, analysis_static, analysis_quasistatic, analysis_dynamic, analysis_name, &
                                initial_velocity, line_error, card_keyword_at, add_warning
  implicit none
  private

  public :: check_time_stages, check_dynamic_cards, check_contact_cards, check_plate_position, check_mass
  public :: check_plate_supports
  public :: check_locking, check_memory_needs_time, check_load_sizes, check_pressures, check_kinematics

contains

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
          short_real(merge(deck%loads%gravity, standard_gravity, deck%gravity_line > 0))//' m/s^2 gives VZ = '// &
          short_real(speed(2))//' m/s; the speed must be '//range_text(speed_range), 'HEIGHT')
        return
      end if
    end if
    if (d%drop_line > 0 .and. d%initial_line > 0) then
      if (d%velocity(2) /= 0.0_dp) then
        call line_error(error, deck, d%drop_line, 'DROP sets the initial VZ = -sqrt(2 g h); the INITIAL card '// &
                        'on line '//integer_text(d%initial_line)//' sets VZ too: give one of them', 'HEIGHT')
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
    if (deck%pad%line > 0 .and. deck%plate%line == 0) then
      call line_error(error, deck, deck%pad%line, 'PAD needs a PLATE card: the pad lies on the rigid plate, '// &
                      'its top surface at the PLATE card''s Z'); return
    end if
    if (deck%pad%line > 0 .and. deck%analysis == analysis_quasistatic) then
      call line_error(error, deck, deck%pad%line, 'PAD needs ANALYSIS STATIC or DYNAMIC (QUASISTATIC has no '// &
                      'contact search)'); return
    end if
    call check_body_card(deck, error); if (allocated(error)) return
    if (deck%stop_line == 0) then
      if (deck%plate%line > 0 .and. deck%analysis == analysis_dynamic) deck%stop_at = stop_at_max_deformation
      if (deck%body%line > 0 .and. deck%body%release) deck%stop_at = stop_at_separation
      return
    end if
    if (deck%analysis /= analysis_dynamic) then
      call line_error(error, deck, deck%stop_line, 'STOP needs ANALYSIS DYNAMIC (this deck is '// &
                      analysis_name(deck%analysis)//')'); return
    end if
    if (deck%body%line > 0) then
      if (deck%stop_at == stop_at_max_deformation) then
        call line_error(error, deck, deck%stop_line, 'STOP AT=MAXDEFORMATION needs a PLATE (the paper''s criterion '// &
                        'of a body on the plate); two bodies (BODY, line '//integer_text(deck%body%line)//') stop '// &
                        'at SEPARATION or TEND', 'AT'); return
      end if
      if (deck%stop_at == stop_at_separation .and. .not. deck%body%release) then
        call line_error(error, deck, deck%stop_line, 'STOP AT=SEPARATION needs BODY ... RELEASE=YES (line '// &
                        integer_text(deck%body%line)//'): without it the bodies are held together for good', 'AT')
        return
      end if
      return
    end if
    if (deck%stop_at /= stop_at_tend .and. deck%plate%line == 0) then
      call line_error(error, deck, deck%stop_line, 'STOP AT='//stop_name(deck%stop_at)// &
                      ' needs a PLATE card (or use STOP AT=TEND)', 'AT'); return
    end if
    if (deck%stop_at == stop_at_separation .and. .not. deck%plate%release) then
      call line_error(error, deck, deck%stop_line, 'STOP AT=SEPARATION needs PLATE ... RELEASE=YES (line '// &
                      integer_text(deck%plate%line)//'): without it contact nodes are held for good and the body never '// &
                      'leaves the plate', 'AT'); return
    end if
  end subroutine check_contact_cards

  !> A second BODY: two free bodies head on, so far in ANALYSIS DYNAMIC,
  !> without a PLATE, a PAD or GRAVITY (each refused at the BODY card).
  subroutine check_body_card(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    if (deck%body%line == 0) return
    if (deck%analysis /= analysis_dynamic) then
      call line_error(error, deck, deck%body%line, 'BODY needs ANALYSIS DYNAMIC (this deck is '// &
                      analysis_name(deck%analysis)//'; two bodies pressed together statically are not available yet)')
      return
    end if
    if (deck%plate%line > 0) then
      call line_error(error, deck, deck%body%line, 'BODY with a PLATE (line '//integer_text(deck%plate%line)// &
                      ') is not available yet: the two bodies are free (head on, no plate); leave out the PLATE card')
      return
    end if
    if (deck%pad%line > 0) then
      call line_error(error, deck, deck%body%line, 'BODY with a PAD (line '//integer_text(deck%pad%line)// &
                      ') is not available yet: the two bodies are free (head on, no plate or pad)'); return
    end if
    if (deck%gravity_line > 0) then
      call line_error(error, deck, deck%body%line, 'BODY with GRAVITY (line '//integer_text(deck%gravity_line)// &
                      ') is not available yet: the two free bodies fly without it (DROP gives the first body its '// &
                      'speed)'); return
    end if
  end subroutine check_body_card

  !> The body starts on or above the plate: no node below z = Z.
  subroutine check_plate_position(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: lowest
    if (deck%plate%line == 0) return
    lowest = minloc(deck%mesh%xy(2, :), dim=1)
    if (deck%mesh%xy(2, lowest) < deck%plate%z - 1.0e-9_dp*deck%mesh%size) then
      call line_error(error, deck, deck%plate%line, 'node '//integer_text(deck%mesh%node_id(lowest))//' (r = '// &
        message_real(deck%mesh%xy(1, lowest))//', z = '//message_real(deck%mesh%xy(2, lowest))//') lies below the plate z = '// &
        message_real(deck%plate%z)//': the body must start on or above the plate', 'Z')
    end if
  end subroutine check_plate_position

  !> No FIX of u_z on a node that starts on the plate: the support, not the
  !> plate, would take the contact force there (the pressure at the pole read
  !> 0 while the plate force was 196 N), and the plate already holds the body
  !> in z. Refused at the FIX card.
  subroutine check_plate_supports(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, i, node
    if (deck%plate%line == 0) return
    do k = 1, size(deck%loads%fixes)
      if (.not. deck%loads%fixes(k)%fix_z) cycle
      do i = 1, size(deck%loads%fixes(k)%nodes)
        node = deck%loads%fixes(k)%nodes(i)
        if (deck%mesh%xy(2, node) > deck%plate%z + 1.0e-9_dp*deck%mesh%size) cycle
        call line_error(error, deck, deck%loads%fixes(k)%line, 'node '//integer_text(deck%mesh%node_id(node))//' (r = '// &
          message_real(deck%mesh%xy(1, node))//', z = '//message_real(deck%mesh%xy(2, node))//') lies on the plate (PLATE Z = '// &
          message_real(deck%plate%z)//', line '//integer_text(deck%plate%line)//'): a FIX of its u_z would take the contact '// &
          'force there instead of the plate (the pressure q would read 0); the plate already holds the body '// &
          'in z: fix R only, or fix a node off the plate')
        return
      end do
    end do
  end subroutine check_plate_supports

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
    if (deck%settings%formulation /= formulation_standard) return
    do k = 1, size(deck%materials)
      if (.not. any(deck%mesh%element_material == k)) cycle
      ratio = deck%materials(k)%bulk/max(deck%materials(k)%shear, tiny(1.0_dp))   ! instantaneous G(0)
      if (ratio > 1000.0_dp) call add_warning(deck, deck%materials(k)%line, 'MATERIAL', 'material '// &
        deck%materials(k)%id//' is nearly incompressible (K/G = '//message_real(ratio)//'): the standard '// &
        'element locks (too stiff); FORMULATION BBAR avoids that')
    end do
  end subroutine check_locking

  !> KINEMATICS LARGE runs what src/finite/ solves so far: elastic or
  !> hyperelastic (NEOHOOKE, MOONEY, HYPERFOAM) bodies under point loads,
  !> gravity and prescribed displacements, ANALYSIS STATIC, or ANALYSIS
  !> DYNAMIC with or without the rigid PLATE and a PAD (STATIC: the PLATE, not a PAD), VISCOELASTIC flesh
  !> by Simo's finite-strain law (PRONY terms; DYNAMIC only: STATIC refuses
  !> memory anyway). Anything else is refused at its
  !> card, with what to do; a hyperelastic material in a small-strain run
  !> warns (it is linearised).
  subroutine check_kinematics(deck, error)
    type(deck_t), intent(inout) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    if (deck%settings%kinematics /= kinematics_large) then
      do k = 1, size(deck%materials)
        if (deck%materials(k)%hyperelastic == hyperelastic_none) cycle
        call add_warning(deck, deck%materials(k)%line, 'MATERIAL', 'material '//deck%materials(k)%id//' is '// &
          hyperelastic_name(deck%materials(k)%hyperelastic)//', and this deck is small-strain (no KINEMATICS '// &
          'LARGE): it runs as its linearisation, G = '//short_real(deck%materials(k)%shear)//' Pa, K = '// &
          short_real(deck%materials(k)%bulk)//' Pa')
      end do
      return
    end if
    if (deck%analysis /= analysis_static .and. deck%analysis /= analysis_dynamic) then
      call line_error(error, deck, deck%kinematics_line, 'KINEMATICS LARGE solves ANALYSIS STATIC and DYNAMIC; '// &
        analysis_name(deck%analysis)//' is small-strain only (remove the card, or make the deck STATIC or DYNAMIC)', '1')
      return
    end if
    do k = 1, size(deck%materials)
      if (deck%materials(k)%plastic) then
        call line_error(error, deck, deck%materials(k)%plastic_line, 'plasticity (PLASTIC) is small-strain only; '// &
          'KINEMATICS LARGE takes elastic and hyperelastic (NEOHOOKE, MOONEY, HYPERFOAM) materials')
        return
      end if
      if (has_memory(deck%materials(k)) .and. deck%materials(k)%kind /= material_kind_viscoelastic) then
        call line_error(error, deck, deck%materials(k)%line, 'material '//deck%materials(k)%id//' is '// &
          material_kind_name(deck%materials(k)%kind)//' (a uniaxial relaxation modulus): at finite strain the '// &
          'Prony law is that of the shear modulus; give it as VISCOELASTIC K= with PRONY G= BETA= cards', '2')
        return
      end if
    end do
    if (size(deck%loads%pressures) > 0) then
      call line_error(error, deck, deck%loads%pressures(1)%line, 'a PRESSURE on the undeformed edge is not the '// &
        'follower load a finite deformation needs, and that load is not in this version: with KINEMATICS LARGE '// &
        'load by FORCE, GRAVITY or a prescribed displacement (FIX ... UZ=)')
      return
    end if
    if (deck%pad%line > 0 .and. deck%analysis == analysis_static) then
      call line_error(error, deck, deck%pad%line, 'a static PAD at finite deformation is not in this version '// &
        '(KINEMATICS LARGE runs the PAD in ANALYSIS DYNAMIC)')
      return
    end if
  end subroutine check_kinematics

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
  !> A load or prescribed displacement times its curve stays in its range
  !> (each within its own, the product too: P = 1e12 Pa with a curve up to
  !> 1e6 would reach 1e18 Pa).
  subroutine check_load_sizes(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    do k = 1, size(deck%loads%pressures)
      call check_product(deck%loads%pressures(k)%line, [deck%loads%pressures(k)%value], &
        deck%loads%pressures(k)%curve, 'P', pressure_range)
      if (allocated(error)) return
    end do
    do k = 1, size(deck%loads%forces)
      call check_product(deck%loads%forces(k)%line, deck%loads%forces(k)%value, deck%loads%forces(k)%curve, &
        'FR, FZ', force_range)
      if (allocated(error)) return
    end do
    do k = 1, size(deck%loads%fixes)
      call check_product(deck%loads%fixes(k)%line, deck%loads%fixes(k)%value, deck%loads%fixes(k)%curve, 'UR, UZ', &
        length_range)
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
      largest = maxval(abs(values))*maxval(abs(deck%loads%curves(curve)%value))
      if (largest <= range%upper) return
      call line_error(error, deck, line, names//' times curve '//deck%loads%curves(curve)%name//' (line '// &
        integer_text(deck%loads%curves(curve)%line)//') reaches '//message_real(largest)//': it must stay ' &
          //range_text(range), 'CURVE')
    end subroutine check_product
  end subroutine check_load_sizes

  !> Each PRESSURE edge set has boundary edges in the mesh.
  subroutine check_pressures(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    do k = 1, size(deck%loads%pressures)
      if (.not. any(deck%mesh%edge_set == deck%loads%pressures(k)%edge_set)) then
        call line_error(error, deck, deck%loads%pressures(k)%line, &
          'edge set '//edge_set_name(deck%loads%pressures(k)%edge_set)// &
          ' has no boundary edges in this mesh', '1')
        return
      end if
    end do
  end subroutine check_pressures

end module visco2d_deck_checks
