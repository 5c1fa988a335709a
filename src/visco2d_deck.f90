!> A deck: the cards of one input file interpreted as a model (title,
!> analysis, geometry, materials, mesh, supports, loads, probes), with every
!> reference checked. Errors name the file, line, column and card.
module visco2d_deck
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_plane_strain
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: itoa, short_real, to_lower
  use visco2d_cards, only: card_t, card_deck_t, read_cards, card_error, named_real, named_integer, &
                           named_word, positional_word, positional_real, check_fields_used, has_field, &
                           field_column
  use visco2d_material, only: material_t, material_kind_elastic, elastic_constants_from_e_nu
  use visco2d_mesh, only: mesh_t, mesh_input_t, read_node_card, read_element_card, read_mesh_card, &
                          build_mesh, node_set, node_index, edge_set_code, edge_set_name, &
                          edge_set_none, edge_set_axis
  implicit none
  private

  public :: deck_t, fix_t, pressure_t, force_t, probe_t, expect_t, read_deck
  public :: analysis_static, analysis_name, geometry_name

  integer, parameter :: analysis_static = 1

  !> A support: components fixed at a set of nodes.
  type :: fix_t
    integer, allocatable :: nodes(:)
    logical :: fix_r = .false., fix_z = .false.
    integer :: line = 0
  end type fix_t

  !> A uniform normal pressure on a boundary edge set (positive = compressive).
  type :: pressure_t
    integer :: edge_set = edge_set_none
    real(dp) :: value = 0.0_dp     !< Pa
    integer :: line = 0
  end type pressure_t

  !> A point load at a node (per radian in axisymmetry), N.
  type :: force_t
    integer :: node = 0
    real(dp) :: value(2) = 0.0_dp
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
  end type deck_t

  !> A target of FIX or FORCE or PROBE, kept until the mesh exists.
  type :: pending_t
    integer :: card = 0
    integer :: column = 0               !< column of the target field
    character(:), allocatable :: target
    character(:), allocatable :: components
    real(dp) :: values(2) = 0.0_dp
  end type pending_t

contains

  pure function analysis_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    select case (code)
    case (analysis_static); name = 'STATIC'
    case default; name = 'NONE'
    end select
  end function analysis_name

  pure function geometry_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    name = merge('AXISYMMETRIC', 'PLANESTRAIN ', code == geometry_axisymmetric)
    name = trim(name)
  end function geometry_name

  !> Read and check a deck file.
  subroutine read_deck(file, deck, error)
    character(*), intent(in) :: file
    type(deck_t), intent(out) :: deck
    type(error_t), allocatable, intent(out) :: error
    type(mesh_input_t) :: mesh_input
    type(pending_t), allocatable :: fixes(:), forces(:), probes(:)
    integer :: i, title_line, analysis_line, geometry_line
    character(:), allocatable :: word

    call read_cards(file, deck%cards, error)
    if (allocated(error)) return
    deck%title = ''
    allocate(deck%materials(0), deck%pressures(0), deck%expects(0), fixes(0), forces(0), probes(0))
    title_line = 0
    analysis_line = 0
    geometry_line = 0

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
        call positional_word(cards, card, 1, 'analysis kind (STATIC)', word, error); if (allocated(error)) return
        call check_fields_used(cards, card, error, 'ANALYSIS STATIC'); if (allocated(error)) return
        select case (word)
        case ('STATIC')
          deck%analysis = analysis_static
        case ('QUASISTATIC', 'DYNAMIC')
          call card_error(error, cards, card, word//' analysis is not available in this version (STATIC only)')
          return
        case default
          call card_error(error, cards, card, 'analysis kind must be STATIC, got "'//word//'"'); return
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
          call card_error(error, cards, card, 'geometry must be AXISYMMETRIC or PLANESTRAIN, got "'//word//'"')
          return
        end select
      case ('MATERIAL')
        call read_material(cards, card, deck%materials, error); if (allocated(error)) return
      case ('NODE')
        call read_node_card(mesh_input, cards, card, error); if (allocated(error)) return
      case ('ELEMENT')
        call read_element_card(mesh_input, cards, card, error); if (allocated(error)) return
      case ('MESH')
        call read_mesh_card(mesh_input, cards, card, error); if (allocated(error)) return
      case ('FIX')
        call read_fix(cards, card, i, fixes, error); if (allocated(error)) return
      case ('PRESSURE')
        call read_pressure(cards, card, deck%pressures, error); if (allocated(error)) return
      case ('FORCE')
        call read_force(cards, card, i, forces, error); if (allocated(error)) return
      case ('PROBE')
        call read_probe(cards, card, i, probes, error); if (allocated(error)) return
      case ('EXPECT')
        call read_expect(cards, card, deck%expects, error); if (allocated(error)) return
      case ('END')
        call check_fields_used(cards, card, error, 'END'); if (allocated(error)) return
      case default
        call card_error(error, cards, card, 'unknown card "'//card%keyword//'" (known: TITLE ANALYSIS '// &
          'GEOMETRY MATERIAL NODE ELEMENT MESH FIX PRESSURE FORCE PROBE EXPECT END)')
        return
      end select
      end associate
    end do

    if (cards%count == 0) then
      call set_error(error, 'the deck has no cards (an empty file?)', file=file); return
    end if
    if (.not. cards%has_end) then
      call set_error(error, 'missing END card (is the deck truncated?)', file=file); return
    end if
    if (analysis_line == 0) then
      call set_error(error, 'missing ANALYSIS card (ANALYSIS STATIC)', file=file); return
    end if
    if (size(deck%materials) == 0) then
      call set_error(error, 'missing MATERIAL card', file=file); return
    end if

    call build_mesh(mesh_input, cards, deck%geometry, deck%mesh, error); if (allocated(error)) return
    call resolve_materials(deck, error); if (allocated(error)) return
    call resolve_fixes(deck, fixes, error); if (allocated(error)) return
    call resolve_forces(deck, forces, error); if (allocated(error)) return
    call resolve_probes(deck, probes, error); if (allocated(error)) return
    call check_pressures(deck, error); if (allocated(error)) return
    end associate

  contains

    subroutine duplicate_card(first_line)
      integer, intent(in) :: first_line
      call card_error(error, deck%cards, deck%cards%cards(i), 'only one '//deck%cards%cards(i)%keyword// &
        ' card is allowed (first on line '//itoa(first_line)//')')
    end subroutine duplicate_card
  end subroutine read_deck

  !> MATERIAL id ELASTIC E=.. NU=.. [RHO=..]   or   MATERIAL id ELASTIC G=.. K=.. [RHO=..]
  subroutine read_material(cards, card, materials, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(material_t), allocatable, intent(inout) :: materials(:)
    type(error_t), allocatable, intent(inout) :: error
    type(material_t) :: material
    character(:), allocatable :: kind
    integer :: k
    call positional_word(cards, card, 1, 'material id', material%id, error); if (allocated(error)) return
    call positional_word(cards, card, 2, 'material kind (ELASTIC)', kind, error); if (allocated(error)) return
    do k = 1, size(materials)
      if (materials(k)%id == material%id) then
        call card_error(error, cards, card, 'material '//material%id//' defined twice'); return
      end if
    end do
    select case (kind)
    case ('ELASTIC')
      material%kind = material_kind_elastic
      if (has_field(card, 'E') .or. has_field(card, 'NU')) then
        call named_real(cards, card, 'E', material%young, error); if (allocated(error)) return
        call named_real(cards, card, 'NU', material%poisson, error); if (allocated(error)) return
        if (material%young <= 0.0_dp) then
          call field_error('E must be > 0, got '//short_real(material%young), 'E'); return
        end if
        if (material%poisson <= -1.0_dp .or. material%poisson >= 0.5_dp) then
          call field_error('NU must be in (-1, 0.5), got '//short_real(material%poisson), 'NU'); return
        end if
        call elastic_constants_from_e_nu(material%young, material%poisson, material%shear, material%bulk)
      else
        call named_real(cards, card, 'G', material%shear, error); if (allocated(error)) return
        call named_real(cards, card, 'K', material%bulk, error); if (allocated(error)) return
        if (material%shear <= 0.0_dp) then
          call field_error('G must be > 0, got '//short_real(material%shear), 'G'); return
        end if
        if (material%bulk <= 0.0_dp) then
          call field_error('K must be > 0, got '//short_real(material%bulk), 'K'); return
        end if
        material%young = 9.0_dp*material%bulk*material%shear/(3.0_dp*material%bulk + material%shear)
        material%poisson = (3.0_dp*material%bulk - 2.0_dp*material%shear)/ &
                           (2.0_dp*(3.0_dp*material%bulk + material%shear))
      end if
      call named_real(cards, card, 'RHO', material%density, error, default=0.0_dp); if (allocated(error)) return
      if (material%density < 0.0_dp) then
        call field_error('RHO must be >= 0', 'RHO'); return
      end if
      call check_fields_used(cards, card, error, 'MATERIAL id ELASTIC E=.. NU=.. [RHO=..] or G=.. K=.. [RHO=..]')
      if (allocated(error)) return
    case ('VISCOELASTIC', 'UNIAXIAL')
      call card_error(error, cards, card, kind//' materials are not available in this version (ELASTIC only)')
      return
    case default
      call card_error(error, cards, card, 'material kind must be ELASTIC, got "'//kind//'"'); return
    end select
    materials = [materials, material]
  contains
    subroutine field_error(message, name)
      character(*), intent(in) :: message
      character(*), intent(in), optional :: name
      integer :: column
      column = card%column
      if (present(name)) column = field_column(card, name)
      call card_error(error, cards, card, message, column)
    end subroutine field_error
  end subroutine read_material

  !> FIX target R|Z|RZ  (target: node number, AXIS, BOTTOM, TOP, INNER or OUTER)
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
    call check_fields_used(cards, card, error, 'FIX target R|Z|RZ'); if (allocated(error)) return
    if (fix%components /= 'R' .and. fix%components /= 'Z' .and. fix%components /= 'RZ' &
        .and. fix%components /= 'ZR') then
      call card_error(error, cards, card, 'components must be R, Z or RZ, got "'//fix%components//'"', &
                      field_column(card, '2')); return
    end if
    fixes = [fixes, fix]
  end subroutine read_fix

  !> PRESSURE edge-set P=..
  subroutine read_pressure(cards, card, pressures, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(pressure_t), allocatable, intent(inout) :: pressures(:)
    type(error_t), allocatable, intent(inout) :: error
    type(pressure_t) :: pressure
    character(:), allocatable :: set
    call positional_word(cards, card, 1, 'edge set (INNER, OUTER, TOP or BOTTOM)', set, error)
    if (allocated(error)) return
    call named_real(cards, card, 'P', pressure%value, error); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'PRESSURE INNER|OUTER|TOP|BOTTOM P=..'); if (allocated(error)) return
    pressure%edge_set = edge_set_code(set)
    if (pressure%edge_set == edge_set_none .or. pressure%edge_set == edge_set_axis) then
      call card_error(error, cards, card, 'edge set must be INNER, OUTER, TOP or BOTTOM, got "'//set//'"', &
                      field_column(card, '1')); return
    end if
    pressure%line = card%line
    pressures = [pressures, pressure]
  end subroutine read_pressure

  !> FORCE n FR=.. FZ=..   (N per radian in axisymmetry, N per metre in plane strain)
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
    call named_real(cards, card, 'FR', force%values(1), error, default=0.0_dp); if (allocated(error)) return
    call named_real(cards, card, 'FZ', force%values(2), error, default=0.0_dp); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'FORCE n FR=.. FZ=..'); if (allocated(error)) return
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
                      probe%components//'"'); return
    end if
    do k = 1, size(probes)
      if (probes(k)%components == probe%components) then
        call card_error(error, cards, card, 'probe '//probe%components//' defined twice'); return
      end if
    end do
    if (has_field(card, 'NODE')) then
      call named_integer(cards, card, 'NODE', node, error); if (allocated(error)) return
      probe%target = itoa(node)
      probe%column = field_column(card, 'NODE')
    else
      call named_real(cards, card, 'R', probe%values(1), error); if (allocated(error)) return
      call named_real(cards, card, 'Z', probe%values(2), error); if (allocated(error)) return
      probe%target = ''
    end if
    call check_fields_used(cards, card, error, 'PROBE name NODE=n | R=.. Z=..'); if (allocated(error)) return
    probes = [probes, probe]
  end subroutine read_probe

  !> EXPECT key value [RTOL=0.01]: the value a summary key should have.
  subroutine read_expect(cards, card, expects, error)
    type(card_deck_t), intent(in) :: cards
    type(card_t), intent(inout) :: card
    type(expect_t), allocatable, intent(inout) :: expects(:)
    type(error_t), allocatable, intent(inout) :: error
    type(expect_t) :: expect
    call positional_word(cards, card, 1, 'summary key', expect%key, error); if (allocated(error)) return
    call positional_real(cards, card, 2, 'expected value', expect%value, error); if (allocated(error)) return
    call named_real(cards, card, 'RTOL', expect%tolerance, error, default=1.0e-2_dp); if (allocated(error)) return
    call check_fields_used(cards, card, error, 'EXPECT key value [RTOL=..]'); if (allocated(error)) return
    if (expect%tolerance <= 0.0_dp) then
      call card_error(error, cards, card, 'RTOL must be > 0'); return
    end if
    expect%line = card%line
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
        call set_error(error, 'element '//itoa(deck%mesh%element_id(e))// &
          ' needs MAT=<id>: the deck defines several materials', file=deck%cards%file, &
          line=deck%mesh%element_line(e), card=trim(card_of_line(deck, deck%mesh%element_line(e))))
        return
      end if
      do k = 1, size(deck%materials)
        if (deck%materials(k)%id == trim(name)) deck%mesh%element_material(e) = k
      end do
      if (deck%mesh%element_material(e) == 0) then
        call set_error(error, 'element '//itoa(deck%mesh%element_id(e))//' uses material '//trim(name)// &
          ', which is not defined by a MATERIAL card', file=deck%cards%file, &
          line=deck%mesh%element_line(e), card=trim(card_of_line(deck, deck%mesh%element_line(e))))
        return
      end if
      end associate
    end do
  end subroutine resolve_materials

  function card_of_line(deck, line) result(keyword)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: line
    character(len=16) :: keyword
    integer :: i
    keyword = ''
    do i = 1, deck%cards%count
      if (deck%cards%cards(i)%line == line) keyword = deck%cards%cards(i)%keyword
    end do
  end function card_of_line

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

  subroutine resolve_fixes(deck, pending, error)
    type(deck_t), intent(inout) :: deck
    type(pending_t), intent(in) :: pending(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: k, code
    allocate(deck%fixes(size(pending)))
    do k = 1, size(pending)
      associate (fix => deck%fixes(k), card => deck%cards%cards(pending(k)%card))
      fix%line = card%line
      fix%fix_r = index(pending(k)%components, 'R') > 0
      fix%fix_z = index(pending(k)%components, 'Z') > 0
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
    end do
  end subroutine resolve_forces

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

  subroutine check_pressures(deck, error)
    type(deck_t), intent(in) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    do k = 1, size(deck%pressures)
      if (.not. any(deck%mesh%edge_set == deck%pressures(k)%edge_set)) then
        call set_error(error, 'edge set '//edge_set_name(deck%pressures(k)%edge_set)// &
          ' has no boundary edges in this mesh', file=deck%cards%file, line=deck%pressures(k)%line, card='PRESSURE')
        return
      end if
    end do
  end subroutine check_pressures

end module visco2d_deck
