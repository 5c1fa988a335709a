!> The cards that name mesh targets (FIX, PRESSURE, FORCE, PROBE, EXPECT)
!> read into pending records while the deck is read, and resolved once the
!> mesh exists: targets to nodes, MAT= names to materials, CURVE= names to
!> curves, with every reference checked.
module visco2d_deck_targets
  use visco2d_kinds, only: dp, geometry_axisymmetric
  use visco2d_error, only: error_t
  use visco2d_strings, only: integer_text, message_real, short_real, to_lower, to_upper
  use visco2d_ranges, only: length_range, pressure_range, force_range, expected_value_range, tolerance_range
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_integer, &
                           named_word, positional_word, positional_real, &
                           check_fields_used, has_field, field_column
  use visco2d_mesh, only: node_set, node_index, edge_set_code, edge_set_none, edge_set_axis
  use visco2d_deck_types, only: deck_t, pressure_t, expect_t, analysis_static, analysis_dynamic, line_error, add_warning
  implicit none
  private

  public :: pending_t, read_fix, read_pressure, read_force, read_probe, read_expect
  public :: resolve_materials, resolve_fixes, resolve_forces, resolve_probes, curve_index

  !> A target of FIX or FORCE or PROBE, kept until the mesh exists.
  type :: pending_t
    integer :: card = 0
    integer :: column = 0               !< column of the target field
    character(:), allocatable :: target
    character(:), allocatable :: components
    real(dp) :: values(2) = 0.0_dp
    real(dp) :: radius = 0.0_dp         !< PROBE RADIUS= (m), 0 if none
    character(:), allocatable :: curve  !< CURVE= name, '' if none
  end type pending_t

contains

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

  !> PROBE name NODE=n   or   PROBE name R=.. Z=..  (the nearest node), [RADIUS=..]:
  !> with a radius (m, > 0) the probe is also a sensor, the mass-weighted mean
  !> acceleration of the nodes within RADIUS of the probe point (DYNAMIC only).
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
                        integer_text(cards%cards(probes(k)%card)%line)//')', field_column(card, '1')); return
      end if
    end do
    if (has_field(card, 'NODE')) then
      call named_integer(cards, card, 'NODE', node, error); if (allocated(error)) return
      probe%target = integer_text(node)
      probe%column = field_column(card, 'NODE')
    else
      call named_real(cards, card, 'R', probe%values(1), error, range=length_range); if (allocated(error)) return
      call named_real(cards, card, 'Z', probe%values(2), error, range=length_range); if (allocated(error)) return
      probe%target = ''
    end if
    if (has_field(card, 'RADIUS')) then
      call named_real(cards, card, 'RADIUS', probe%radius, error, range=length_range); if (allocated(error)) return
      if (.not. probe%radius > 0.0_dp) then
        call card_error(error, cards, card, 'RADIUS= is the sensor radius and must be positive, got '// &
                        short_real(probe%radius), field_column(card, 'RADIUS')); return
      end if
    end if
    call check_fields_used(cards, card, error, 'PROBE name NODE=n | R=.. Z=.. [RADIUS=..]')
    if (allocated(error)) return
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
                        integer_text(expects(k)%line), field_column(card, '1')); return
      end if
    end do
    expect%line = card%line
    expect%column = field_column(card, '1')
    expects = [expects, expect]
  end subroutine read_expect

  !> Each element's MAT= name to its material (the only one if none is named).
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
        call line_error(error, deck, deck%mesh%element_line(e), 'element '//integer_text(deck%mesh%element_id(e))// &
          ' needs MAT=<id>: the deck defines several materials')
        return
      end if
      do k = 1, size(deck%materials)
        if (deck%materials(k)%id == trim(name)) deck%mesh%element_material(e) = k
      end do
      if (deck%mesh%element_material(e) == 0) then
        call line_error(error, deck, deck%mesh%element_line(e), 'element '//integer_text(deck%mesh%element_id(e))// &
          ' uses material '//trim(name)//', which is not defined by a MATERIAL card', &
          material_field(deck, deck%mesh%element_line(e), name))
        return
      end if
      end associate
    end do
  end subroutine resolve_materials

  !> The field of the card on `line` that names material `name`: SKINMAT or
  !> COREMAT (the MESH SPHERE regions) when one of them does, else MAT.
  function material_field(deck, line, name) result(field)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    character(*), intent(in) :: name
    character(:), allocatable :: field
    integer :: k, i
    field = 'MAT'
    do k = 1, deck%cards%count
      if (deck%cards%cards(k)%line /= line) cycle
      do i = 1, size(deck%cards%cards(k)%tokens)
        associate (token => deck%cards%cards(k)%tokens(i))
        if ((token%name == 'SKINMAT' .or. token%name == 'COREMAT') .and. to_upper(token%value) == to_upper(trim(name))) &
          field = token%name
        end associate
      end do
    end do
  end function material_field

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
    allocate(deck%loads%fixes(size(pending)), owner(2, deck%mesh%nnode))
    owner = 0
    do k = 1, size(pending)
      associate (fix => deck%loads%fixes(k), card => deck%cards%cards(pending(k)%card))
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
        if (deck%settings%geometry == geometry_axisymmetric .and. deck%mesh%xy(1, node) == 0.0_dp .and. &
            fix%fix_r .and. fix%value(1) /= 0.0_dp) then
          call card_error(error, deck%cards, card, 'node '//integer_text(deck%mesh%node_id(node))// &
            ' is on the axis, where u_r = 0 always; it cannot have UR='//short_real(fix%value(1)), &
            field_column(card, 'UR'))
          return
        end if
        do c = 1, 2
          if (.not. fixed(c)) cycle
          other = owner(c, node)
          if (other > 0) then
            if (deck%loads%fixes(other)%value(c) /= fix%value(c) .or. deck%loads%fixes(other)%curve /= fix%curve) then
              call card_error(error, deck%cards, card, 'node '//integer_text(deck%mesh%node_id(node))//' gets a '// &
                'different prescribed '//trim(merge('u_r', 'u_z', c == 1))//' from the FIX card on line '// &
                integer_text(deck%loads%fixes(other)%line)//' (a node may be prescribed twice only alike)', pending(k)%column)
              return
            end if
          end if
          owner(c, node) = k
        end do
      end do
      end associate
    end do
  end subroutine resolve_fixes

  !> FORCE targets to nodes, CURVE= names to curves.
  subroutine resolve_forces(deck, pending, error)
    type(deck_t), intent(inout) :: deck
    type(pending_t), intent(in) :: pending(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    allocate(deck%loads%forces(size(pending)))
    do k = 1, size(pending)
      deck%loads%forces(k)%node = target_node(deck, pending(k), error)
      if (allocated(error)) return
      deck%loads%forces(k)%value = pending(k)%values
      deck%loads%forces(k)%line = deck%cards%cards(pending(k)%card)%line
      deck%loads%forces(k)%curve = curve_index(deck, pending(k)%card, pending(k)%curve, error)
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
    do k = 1, size(deck%loads%curves)
      if (deck%loads%curves(k)%name == name) found = k
    end do
    if (found == 0) call card_error(error, deck%cards, the_card, 'curve '//name// &
      ' is not defined by a CURVE card', field_column(the_card, 'CURVE'))
    end associate
  end function curve_index

  !> TIME belongs to QUASISTATIC and DYNAMIC (required there), not to STATIC.

  !> PROBE targets to nodes (NODE=, or the node nearest R=, Z=), and a
  !> sensor's region: the nodes within RADIUS of the probe point (R=, Z=, or
  !> the node of NODE=), the probe's node always among them.
  subroutine resolve_probes(deck, pending, error)
    type(deck_t), intent(inout) :: deck
    type(pending_t), intent(in) :: pending(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, i
    real(dp) :: point(2), size_there
    real(dp), allocatable :: distance(:)
    allocate(deck%probes(size(pending)))
    do k = 1, size(pending)
      associate (probe => deck%probes(k), card => deck%cards%cards(pending(k)%card))
      probe%name = to_lower(pending(k)%components)
      if (len(pending(k)%target) > 0) then
        probe%node = target_node(deck, pending(k), error)
        if (allocated(error)) return
        point = deck%mesh%xy(:, probe%node)
      else
        point = pending(k)%values
      end if
      distance = hypot(deck%mesh%xy(1, :) - point(1), deck%mesh%xy(2, :) - point(2))
      if (len(pending(k)%target) == 0) then
        probe%node = minloc(distance, dim=1)
        size_there = element_size_at(deck, probe%node)
        if (distance(probe%node) > size_there) call add_warning(deck, card%line, 'PROBE', &
          'the point (r = '//short_real(point(1))//', z = '//short_real(point(2))//') m is '// &
          message_real(distance(probe%node))//' m from its nearest node '//integer_text(deck%mesh%node_id(probe%node))// &
          ' (r = '//message_real(deck%mesh%xy(1, probe%node))//', z = '//message_real(deck%mesh%xy(2, probe%node))// &
          '), more than the size of the elements there ('//message_real(size_there)//' m): it lies outside the body, '// &
          'and probe '//probe%name//' reports that node (a unit slip? R= and Z= are in m)')
      end if
      probe%radius = pending(k)%radius
      if (probe%radius <= 0.0_dp) cycle
      if (deck%analysis /= analysis_dynamic) then
        call card_error(error, deck%cards, card, 'RADIUS= makes the probe a sensor (a mean acceleration), '// &
                        'which needs ANALYSIS DYNAMIC', field_column(card, 'RADIUS')); return
      end if
      distance(probe%node) = 0.0_dp
      probe%region = pack([(i, i = 1, deck%mesh%nnode)], distance <= probe%radius*(1.0_dp + 1.0e-9_dp))
      if (size(probe%region) == 1) call add_warning(deck, card%line, 'PROBE', 'sensor '//probe%name// &
        ' holds one node: RADIUS='//short_real(probe%radius)//' m is below the mesh spacing there, so it reads '// &
        'that node''s acceleration (a larger radius or a finer mesh averages)')
      end associate
    end do
  end subroutine resolve_probes

  !> The largest distance between two corners of an element holding `node`
  !> (its diameter): a point inside the body lies within the diameter of
  !> its element from one of its corners.
  pure real(dp) function element_size_at(deck, node) result(size_at)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: node
    integer :: e, i, j
    size_at = 0.0_dp
    associate (mesh => deck%mesh)
    do e = 1, mesh%nelem
      if (.not. any(mesh%connectivity(:, e) == node)) cycle
      do i = 1, 3
        do j = i + 1, 4
          size_at = max(size_at, norm2(mesh%xy(:, mesh%connectivity(i, e)) - mesh%xy(:, mesh%connectivity(j, e))))
        end do
      end do
    end do
    end associate
  end function element_size_at
end module visco2d_deck_targets
