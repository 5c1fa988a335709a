!> The mesh cards: legacy NODE and ELEMENT cards with generation, or a MESH
!> generator card (SPHERE, SPHEROID, OUTLINE, RECT, RING), read into a mesh_input_t with the
!> size of the mesh checked against the limits before it is generated.
!> visco2d_mesh_build turns the input into a checked, numbered mesh_t.
module visco2d_mesh_cards
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_integer, named_word, &
                           positional_real, positional_integer, positional_word, positional_count, check_fields_used, &
                           field_column, has_field
  use visco2d_mesh_generator, only: spheroid_grid, rectangle_grid, ring_grid, sphere_default_grade, &
                                    sphere_default_core, sphere_grid_contact, sphere_grid_legacy, &
                                    spheroid_least_ratio, spheroid_largest_ratio, sphere_element_layer, &
                                    sphere_layer_count
  use visco2d_outline_grid, only: outline_t, outline_problem, make_outline, outline_grid, outline_max_points
  use visco2d_budget, only: run_size_t, mesh_run_size, sphere_mesh_counts, grid_mesh_counts, memory_limit, &
                            bytes_text, count_text, max_mesh_entities
  use visco2d_strings, only: itoa, rtoa, to_upper
  use visco2d_mesh, only: name_length
  implicit none
  private

  public :: mesh_input_t, read_node_card, read_element_card, read_mesh_card

  !> Largest node or element number, given or generated: what a card field
  !> can hold (9 digits), so every number can be named on a card.
  integer, parameter :: max_id = 999999999
  !> Largest |coordinate| of a node, m (lengths beyond the scale of any
  !> body keep every product of the solvers far from overflow).
  real(dp), parameter :: max_coordinate = 1.0e4_dp

  !> What the mesh cards said, before checking and numbering.
  type :: mesh_input_t
    integer :: nnode = 0, nelem = 0
    real(dp), allocatable :: xy(:, :)
    integer, allocatable :: node_id(:), node_line(:)
    integer, allocatable :: nodes(:, :), element_id(:), element_line(:)
    character(len=name_length), allocatable :: material(:)
    integer, allocatable :: edge_element(:), edge_side(:), edge_set(:)
    character(:), allocatable :: source
    integer :: generator_line = 0, generator_column = 0
    integer :: first_element_line = 0, first_element_column = 0
  end type mesh_input_t

contains

  !> NODE n r z [GEN=k INC=dn DR=.. DZ=..]: node n, then k more numbered n+dn, n+2dn, ...
  !> at (r + i DR, z + i DZ).
  subroutine read_node_card(input, deck, card, error)
    type(mesh_input_t), intent(inout) :: input
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    type(error_t), allocatable, intent(inout) :: error
    integer :: id, count, increment, i
    integer(int64) :: last
    real(dp) :: r, z, dr, dz
    if (input_is_generated(input, deck, card, error)) return
    call positional_integer(deck, card, 1, 'node number', id, error); if (allocated(error)) return
    call positional_real(deck, card, 2, 'r coordinate', r, error); if (allocated(error)) return
    call positional_real(deck, card, 3, 'z coordinate', z, error); if (allocated(error)) return
    call named_integer(deck, card, 'GEN', count, error, default=0); if (allocated(error)) return
    call named_integer(deck, card, 'INC', increment, error, default=1); if (allocated(error)) return
    call named_real(deck, card, 'DR', dr, error, default=0.0_dp); if (allocated(error)) return
    call named_real(deck, card, 'DZ', dz, error, default=0.0_dp); if (allocated(error)) return
    call check_fields_used(deck, card, error, 'NODE n r z [GEN=k INC=dn DR=.. DZ=..]'); if (allocated(error)) return
    if (id <= 0) then
      call card_error(error, deck, card, 'node number must be positive, got '//itoa(id), field_column(card, '1'))
      return
    end if
    if (count < 0) then
      call card_error(error, deck, card, 'GEN must be >= 0, got '//itoa(count), field_column(card, 'GEN')); return
    end if
    if (increment <= 0) then
      call card_error(error, deck, card, 'INC must be > 0, got '//itoa(increment), field_column(card, 'INC')); return
    end if
    if (count > 0 .and. dr == 0.0_dp .and. dz == 0.0_dp) then
      call card_error(error, deck, card, 'GEN needs a step DR= or DZ= (generated nodes would coincide)', &
                      field_column(card, 'GEN')); return
    end if
    last = int(id, int64) + int(count, int64)*increment
    if (last > max_id) then
      call card_error(error, deck, card, 'GEN='//itoa(count)//' INC='//itoa(increment)//' from node '//itoa(id)// &
        ' would number the last node '//count_text(last)//', past the largest node number '// &
        count_text(int(max_id, int64)), field_column(card, merge('GEN', 'INC', count > increment))); return
    end if
    call check_coordinate(r, '2', 'r'); if (allocated(error)) return
    call check_coordinate(z, '3', 'z'); if (allocated(error)) return
    call check_coordinate(dr, 'DR', 'DR'); if (allocated(error)) return
    call check_coordinate(dz, 'DZ', 'DZ'); if (allocated(error)) return
    call check_coordinate(r + count*dr, 'GEN', 'the last generated r'); if (allocated(error)) return
    call check_coordinate(z + count*dz, 'GEN', 'the last generated z'); if (allocated(error)) return
    call check_mesh_growth(input, int(count, int64) + 1, 0_int64, deck, card, 'GEN', error)
    if (allocated(error)) return
    call reserve_nodes(input, count + 1)
    do i = 0, count
      input%nnode = input%nnode + 1
      input%node_id(input%nnode) = id + i*increment
      input%xy(:, input%nnode) = [r + i*dr, z + i*dz]
      input%node_line(input%nnode) = card%line
    end do
    input%source = 'CARDS'
  contains
    subroutine check_coordinate(value, field, what)
      real(dp), intent(in) :: value
      character(*), intent(in) :: field, what
      if (abs(value) <= max_coordinate) return
      call card_error(error, deck, card, what//' = '//rtoa(value)//' m is out of range: coordinates must be in [-'// &
        rtoa(max_coordinate)//', '//rtoa(max_coordinate)//'] m', field_column(card, field))
    end subroutine check_coordinate
  end subroutine read_node_card

  !> ELEMENT e n1 n2 n3 n4 MAT=id [GEN=k INC=de NINC=dn]: element e, then k more
  !> numbered e+i*de with nodes n_j + i*dn.
  subroutine read_element_card(input, deck, card, error)
    type(mesh_input_t), intent(inout) :: input
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    type(error_t), allocatable, intent(inout) :: error
    integer :: id, nodes(4), generate, increment, node_increment, i, j
    integer(int64) :: last, extreme
    character(:), allocatable :: material
    if (input_is_generated(input, deck, card, error)) return
    call positional_integer(deck, card, 1, 'element number', id, error); if (allocated(error)) return
    do j = 1, 4
      call positional_integer(deck, card, 1 + j, 'node '//itoa(j)//' of 4', nodes(j), error)
      if (allocated(error)) return
    end do
    call named_word(deck, card, 'MAT', material, error, default=''); if (allocated(error)) return
    call named_integer(deck, card, 'GEN', generate, error, default=0); if (allocated(error)) return
    call named_integer(deck, card, 'INC', increment, error, default=1); if (allocated(error)) return
    call named_integer(deck, card, 'NINC', node_increment, error, default=1); if (allocated(error)) return
    call check_fields_used(deck, card, error, 'ELEMENT e n1 n2 n3 n4 MAT=id [GEN=k INC=de NINC=dn]')
    if (allocated(error)) return
    if (id <= 0) then
      call card_error(error, deck, card, 'element number must be positive, got '//itoa(id), field_column(card, '1'))
      return
    end if
    do j = 1, 4
      if (nodes(j) <= 0) then
        call card_error(error, deck, card, 'node numbers must be positive, got '//itoa(nodes(j)), &
                        field_column(card, itoa(1 + j))); return
      end if
    end do
    if (generate < 0) then
      call card_error(error, deck, card, 'GEN must be >= 0, got '//itoa(generate), field_column(card, 'GEN')); return
    end if
    if (increment <= 0) then
      call card_error(error, deck, card, 'INC must be > 0, got '//itoa(increment), field_column(card, 'INC')); return
    end if
    do j = 1, 4
      if (count(nodes == nodes(j)) > 1) then
        call card_error(error, deck, card, 'node '//itoa(nodes(j))// &
          ' appears twice: a quadrilateral needs 4 distinct nodes', field_column(card, itoa(1 + j))); return
      end if
    end do
    if (len(material) > name_length) then
      call card_error(error, deck, card, 'MAT id longer than 32 characters', field_column(card, 'MAT')); return
    end if
    last = int(id, int64) + int(generate, int64)*increment
    if (last > max_id) then
      call card_error(error, deck, card, 'GEN='//itoa(generate)//' INC='//itoa(increment)//' from element '// &
        itoa(id)//' would number the last element '//count_text(last)//', past the largest element number '// &
        count_text(int(max_id, int64)), field_column(card, merge('GEN', 'INC', generate > increment))); return
    end if
    do j = 1, 4                                   ! node numbers are linear in i: check the last element's
      extreme = int(nodes(j), int64) + int(generate, int64)*node_increment
      if (extreme < 1 .or. extreme > max_id) then
        call card_error(error, deck, card, 'GEN='//itoa(generate)//' NINC='//itoa(node_increment)// &
          ' would give element '//count_text(last)//' node '//count_text(extreme)//': node numbers must be in 1..'// &
          count_text(int(max_id, int64)), field_column(card, merge('NINC', 'GEN ', has_ninc()))); return
      end if
    end do
    call check_mesh_growth(input, 0_int64, int(generate, int64) + 1, deck, card, 'GEN', error)
    if (allocated(error)) return
    call reserve_elements(input, generate + 1)
    do i = 0, generate
      input%nelem = input%nelem + 1
      input%element_id(input%nelem) = id + i*increment
      input%nodes(:, input%nelem) = nodes + i*node_increment
      input%material(input%nelem) = material
      input%element_line(input%nelem) = card%line
    end do
    if (input%first_element_line == 0) then
      input%first_element_line = card%line
      input%first_element_column = card%column
    end if
    input%source = 'CARDS'
  contains
    logical function has_ninc()
      has_ninc = field_column(card, 'NINC') /= card%column
    end function has_ninc
  end subroutine read_element_card

  !> Refuse NODE or ELEMENT generation that would make the mesh larger than
  !> max_mesh_entities, or than the memory limit allows for even a STATIC run
  !> (the half-bandwidth is not known yet: the estimate takes the least, so
  !> the refusal is sure). Located at `field` of the card.
  subroutine check_mesh_growth(input, new_nodes, new_elements, deck, card, field, error)
    type(mesh_input_t), intent(in) :: input
    integer(int64), intent(in) :: new_nodes, new_elements
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    character(*), intent(in) :: field
    type(error_t), allocatable, intent(inout) :: error
    integer(int64) :: nodes, elements
    type(run_size_t) :: least
    real(dp) :: limit
    character(:), allocatable :: origin
    logical :: raisable
    nodes = input%nnode + new_nodes
    elements = input%nelem + new_elements
    if (max(nodes, elements) > max_mesh_entities) then
      call card_error(error, deck, card, 'the mesh would have '//count_text(nodes)//' nodes and '// &
        count_text(elements)//' elements, more than '//count_text(max_mesh_entities), field_column(card, field))
      return
    end if
    if (max(nodes, elements) < 100000) return          ! far below any limit: no need to ask
    least = mesh_run_size(nodes, elements, 1_int64)
    call memory_limit(limit, origin, raisable)
    if (least%total_bytes <= limit) return
    call card_error(error, deck, card, 'the mesh would have '//count_text(nodes)//' nodes and '// &
      count_text(elements)//' elements: a run on it needs at least '//bytes_text(least%total_bytes)// &
      ', more than '//origin//raise_hint(raisable), field_column(card, field))
  end subroutine check_mesh_growth

  !> How to lift a memory limit, for messages.
  pure function raise_hint(raisable) result(hint)
    logical, intent(in) :: raisable
    character(:), allocatable :: hint
    if (raisable) then
      hint = ' (a coarser mesh, or raise the limit with --max-memory SIZE or VISCO2D_MAX_MEMORY=SIZE)'
    else
      hint = ' (a coarser mesh)'
    end if
  end function raise_hint
  !> MESH SPHERE R=.. [LEVEL=1] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c]
  !>   [SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id]
  !> (MAT= may be omitted when the deck has one material; GRADE and CORE
  !> default to 2.5 and 0.2 on the contact grid, 2.35 and 0.35 on the legacy grid;
  !> SKINMAT= gives the outermost n of the 8 level-1 polar layers, n 2^(L-1)
  !> layers at level L, another material, COREMAT= the core block)
  !> MESH SPHEROID A=.. C=.. [LEVEL=1] [MAT=id] [GRID=..] [GRADE=b] [CORE=c]
  !> (the sphere grid stretched: equatorial semi-axis A, polar semi-axis C)
  !> MESH OUTLINE [LEVEL=1] [MAT=id] [GRID=..] [GRADE=b] [CORE=c] r1 z1 r2 z2 ... rn zn
  !> (the sphere grid mapped radially onto the outline through the points,
  !> from the contact pole (r1 = 0, the lowest point) to the far pole (rn = 0))
  !> MESH RECT R0=.. R1=.. Z0=.. Z1=.. NR=.. NZ=.. [MAT=id]
  !> MESH RING R0=.. R1=.. NR=.. NT=.. [ANGLE=90] [MAT=id]   (plane-strain ring sector)
  subroutine read_mesh_card(input, deck, card, error)
    type(mesh_input_t), intent(inout) :: input
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: kind, material, skin_material, core_material
    integer :: i, level, skin_layers
    real(dp), allocatable :: xy(:, :)
    integer, allocatable :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)

    if (input%nnode > 0 .or. input%nelem > 0) then
      call card_error(error, deck, card, 'a MESH card cannot be combined with NODE/ELEMENT cards or another MESH')
      return
    end if
    call positional_word(deck, card, 1, 'mesh kind (SPHERE, SPHEROID, OUTLINE, RECT or RING)', kind, error)
    if (allocated(error)) return
    call named_word(deck, card, 'MAT', material, error, default=''); if (allocated(error)) return
    select case (kind)
    case ('SPHERE', 'SPHEROID', 'OUTLINE')
      call read_sphere_mesh(deck, card, kind, xy, connectivity, edge_element, edge_side, edge_set, &
                            level, skin_material, skin_layers, core_material, error)
    case ('RECT')
      call read_rect_mesh(deck, card, xy, connectivity, edge_element, edge_side, edge_set, error)
    case ('RING')
      call read_ring_mesh(deck, card, xy, connectivity, edge_element, edge_side, edge_set, error)
    case default
      call card_error(error, deck, card, 'mesh kind must be SPHERE, SPHEROID, OUTLINE, RECT or RING, got "'//kind//'"', &
                      field_column(card, '1'))
    end select
    if (allocated(error)) return
    if (len(material) > name_length) then
      call card_error(error, deck, card, 'MAT id longer than 32 characters', field_column(card, 'MAT')); return
    end if
    input%nnode = size(xy, 2)
    input%nelem = size(connectivity, 2)
    input%xy = xy
    input%node_id = [(i, i = 1, input%nnode)]
    input%node_line = [(card%line, i = 1, input%nnode)]
    input%nodes = connectivity
    input%element_id = [(i, i = 1, input%nelem)]
    input%element_line = [(card%line, i = 1, input%nelem)]
    allocate(input%material(input%nelem))
    input%material = material
    if (kind == 'SPHERE' .or. kind == 'SPHEROID' .or. kind == 'OUTLINE') then
      do i = 1, input%nelem
        if (sphere_element_layer(level, i) == 0 .and. len(core_material) > 0) then
          input%material(i) = core_material
        else if (sphere_element_layer(level, i) > sphere_layer_count(level) - skin_layers*2**(level - 1) &
                 .and. len(skin_material) > 0) then
          input%material(i) = skin_material
        end if
      end do
    end if
    input%edge_element = edge_element
    input%edge_side = edge_side
    input%edge_set = edge_set
    input%source = kind
    input%generator_line = card%line
    input%generator_column = card%column
  end subroutine read_mesh_card

  !> MESH SPHERE, SPHEROID or OUTLINE (`kind`): the fields checked, the grid
  !> generated; its level and the material regions (SKINMAT=, SKIN_LAYERS=,
  !> COREMAT=; '' where the field is absent) returned for the caller to assign.
  subroutine read_sphere_mesh(deck, card, kind, xy, connectivity, edge_element, edge_side, edge_set, &
                              level, skin_material, skin_layers, core_material, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    character(*), intent(in) :: kind
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    integer, intent(out) :: level, skin_layers
    character(:), allocatable, intent(out) :: skin_material, core_material
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: equatorial, polar, grade, core
    integer :: grid
    integer(int64) :: nodes, elements, least_width
    character(:), allocatable :: grid_name, usage
    real(dp), allocatable :: r(:), z(:)
    type(outline_t) :: outline
    if (kind == 'SPHEROID') then
      usage = 'MESH SPHEROID A=.. C=.. [LEVEL=L] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c] '// &
              '[SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id]'
      call named_real(deck, card, 'A', equatorial, error); if (allocated(error)) return
      call named_real(deck, card, 'C', polar, error); if (allocated(error)) return
    else if (kind == 'OUTLINE') then
      usage = 'MESH OUTLINE [LEVEL=L] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c] '// &
              '[SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id] r1 z1 r2 z2 ... rn zn'
      call read_outline_points(deck, card, r, z, error); if (allocated(error)) return
    else
      usage = 'MESH SPHERE R=.. [LEVEL=L] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c] '// &
              '[SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id]'
      call named_real(deck, card, 'R', equatorial, error); if (allocated(error)) return
      polar = equatorial
    end if
    call named_integer(deck, card, 'LEVEL', level, error, default=1); if (allocated(error)) return
    call named_word(deck, card, 'GRID', grid_name, error, default='CONTACT'); if (allocated(error)) return
    select case (grid_name)
    case ('CONTACT'); grid = sphere_grid_contact
    case ('LEGACY'); grid = sphere_grid_legacy
    case default
      call card_error(error, deck, card, 'GRID must be CONTACT or LEGACY, got "'//grid_name//'"', &
                      field_column(card, 'GRID')); return
    end select
    call named_real(deck, card, 'GRADE', grade, error, default=sphere_default_grade(grid)); if (allocated(error)) return
    call named_real(deck, card, 'CORE', core, error, default=sphere_default_core(grid)); if (allocated(error)) return
    call named_word(deck, card, 'SKINMAT', skin_material, error, default=''); if (allocated(error)) return
    call named_integer(deck, card, 'SKIN_LAYERS', skin_layers, error, default=1); if (allocated(error)) return
    call named_word(deck, card, 'COREMAT', core_material, error, default=''); if (allocated(error)) return
    call check_fields_used(deck, card, error, usage)
    if (allocated(error)) return
    call check_regions(); if (allocated(error)) return
    if (kind == 'SPHEROID') then
      call check_semi_axis(equatorial, 'A'); if (allocated(error)) return
      call check_semi_axis(polar, 'C'); if (allocated(error)) return
      if (.not. (polar/equatorial >= spheroid_least_ratio .and. polar/equatorial <= spheroid_largest_ratio)) then
        call card_error(error, deck, card, 'C/A must be in ['//rtoa(spheroid_least_ratio)//', '// &
          rtoa(spheroid_largest_ratio)//'] (the range on which the stretched sphere grid is validated), got C/A = '// &
          rtoa(polar/equatorial), field_column(card, 'C')); return
      end if
    else if (kind == 'SPHERE') then
      call check_semi_axis(equatorial, 'R'); if (allocated(error)) return
    end if
    if (level < 1 .or. level > 7) then
      call card_error(error, deck, card, 'LEVEL must be in 1..7 (level 7 has 360,448 elements), got '//itoa(level), &
                      field_column(card, 'LEVEL')); return
    end if
    if (grade < 0.0_dp .or. grade > 6.0_dp) then
      call card_error(error, deck, card, 'GRADE must be in [0, 6], got '//rtoa(grade), field_column(card, 'GRADE'))
      return
    end if
    if (core <= 0.05_dp .or. core >= 0.95_dp) then
      call card_error(error, deck, card, 'CORE must be in (0.05, 0.95), got '//rtoa(core), field_column(card, 'CORE'))
      return
    end if
    if (grid == sphere_grid_contact .and. core > 0.7_dp) then   ! at 0.8 the map folds elements near the core
      call card_error(error, deck, card, 'CORE must be in (0.05, 0.7] on GRID=CONTACT, got '//rtoa(core), &
                      field_column(card, 'CORE')); return
    end if
    call sphere_mesh_counts(level, nodes, elements, least_width)
    call check_generated_size(deck, card, kind, nodes, elements, least_width, 'LEVEL', error)
    if (allocated(error)) return
    if (kind == 'OUTLINE') then
      call make_outline(r, z, outline)
      call outline_grid(outline, level, grade, core, grid, xy, connectivity, edge_element, edge_side, edge_set)
    else
      call spheroid_grid(equatorial, polar, level, grade, core, grid, xy, connectivity, edge_element, edge_side, &
                         edge_set)
    end if
  contains
    !> SKINMAT=, SKIN_LAYERS= and COREMAT=: ids of at most 32 characters; the
    !> skin 1 to 7 of the 8 level-1 layers (at least one layer of flesh).
    subroutine check_regions()
      if (len(skin_material) > name_length) then
        call card_error(error, deck, card, 'SKINMAT id longer than 32 characters', field_column(card, 'SKINMAT'))
      else if (len(core_material) > name_length) then
        call card_error(error, deck, card, 'COREMAT id longer than 32 characters', field_column(card, 'COREMAT'))
      else if (has_field(card, 'SKIN_LAYERS') .and. len(skin_material) == 0) then
        call card_error(error, deck, card, 'SKIN_LAYERS= needs SKINMAT=id (the skin''s material)', &
                        field_column(card, 'SKIN_LAYERS'))
      else if (skin_layers < 1 .or. skin_layers > 7) then
        call card_error(error, deck, card, 'SKIN_LAYERS must be in 1..7 (of the 8 polar layers at level 1; '// &
          'level L has 8*2^(L-1)), got '//itoa(skin_layers), field_column(card, 'SKIN_LAYERS'))
      end if
    end subroutine check_regions

    !> A radius or semi-axis: > 0 and at most max_coordinate (m).
    subroutine check_semi_axis(value, field)
      real(dp), intent(in) :: value
      character(*), intent(in) :: field
      if (value <= 0.0_dp) then
        call card_error(error, deck, card, field//' must be > 0 m, got '//rtoa(value), field_column(card, field))
      else if (value > max_coordinate) then
        call card_error(error, deck, card, field//' must be <= '//rtoa(max_coordinate)//' m, got '//rtoa(value), &
                        field_column(card, field))
      end if
    end subroutine check_semi_axis
  end subroutine read_sphere_mesh

  !> The points r1 z1 ... rn zn of MESH OUTLINE (the positional values after
  !> OUTLINE, in m): read, and checked as an outline (`outline_problem`),
  !> with an error at the point's r field (at its z field for a z problem);
  !> refused in a deck whose GEOMETRY is PLANESTRAIN (a body of revolution).
  subroutine read_outline_points(deck, card, r, z, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    real(dp), allocatable, intent(out) :: r(:), z(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: values, n, i, point
    logical :: at_z
    character(:), allocatable :: problem
    do i = 1, deck%count
      if (deck%cards(i)%keyword /= 'GEOMETRY' .or. positional_count(deck%cards(i)) < 1) cycle
      if (to_upper(deck%cards(i)%tokens(deck%cards(i)%positions(1))%value) /= 'PLANESTRAIN') cycle
      call card_error(error, deck, card, 'MESH OUTLINE is a body of revolution: it needs GEOMETRY AXISYMMETRIC '// &
        '(the GEOMETRY card on line '//itoa(deck%cards(i)%line)//' says PLANESTRAIN)', field_column(card, '1'))
      return
    end do
    values = positional_count(card) - 1
    if (mod(values, 2) /= 0) then
      call card_error(error, deck, card, 'the outline''s points come in pairs r z (m), got '//itoa(values)// &
        ' values: the last point has no z', field_column(card, itoa(values + 1))); return
    end if
    n = values/2
    if (n > outline_max_points) then
      call card_error(error, deck, card, 'the outline has '//itoa(n)//' points, more than '// &
        itoa(outline_max_points), field_column(card, '1')); return
    end if
    allocate(r(n), z(n))
    do i = 1, n
      call positional_real(deck, card, 2*i, 'r of point '//itoa(i)//' (m)', r(i), error); if (allocated(error)) return
      call positional_real(deck, card, 2*i + 1, 'z of point '//itoa(i)//' (m)', z(i), error)
      if (allocated(error)) return
      if (max(abs(r(i)), abs(z(i))) > max_coordinate) then
        call card_error(error, deck, card, 'point '//itoa(i)//' is out of range: coordinates must be in [-'// &
          rtoa(max_coordinate)//', '//rtoa(max_coordinate)//'] m', field_column(card, itoa(2*i))); return
      end if
    end do
    call outline_problem(r, z, problem, point, at_z)
    if (len(problem) == 0) return
    if (point == 0) then
      call card_error(error, deck, card, 'the outline '//problem, field_column(card, '1'))
    else
      call card_error(error, deck, card, problem, field_column(card, itoa(2*point + merge(1, 0, at_z))))
    end if
  end subroutine read_outline_points

  !> MESH RECT: the fields checked, the grid generated.
  subroutine read_rect_mesh(deck, card, xy, connectivity, edge_element, edge_side, edge_set, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: r0, r1, z0, z1
    integer :: nr, nz
    integer(int64) :: nodes, elements, least_width
    call named_real(deck, card, 'R0', r0, error); if (allocated(error)) return
    call named_real(deck, card, 'R1', r1, error); if (allocated(error)) return
    call named_real(deck, card, 'Z0', z0, error); if (allocated(error)) return
    call named_real(deck, card, 'Z1', z1, error); if (allocated(error)) return
    call named_integer(deck, card, 'NR', nr, error); if (allocated(error)) return
    call named_integer(deck, card, 'NZ', nz, error); if (allocated(error)) return
    call check_fields_used(deck, card, error, 'MESH RECT R0=.. R1=.. Z0=.. Z1=.. NR=.. NZ=.. [MAT=id]')
    if (allocated(error)) return
    if (r1 <= r0 .or. z1 <= z0) then
      call card_error(error, deck, card, 'need R1 > R0 and Z1 > Z0', field_column(card, trim(merge('R1', 'Z1', r1 <= r0))))
      return
    end if
    if (max(abs(r0), abs(r1), abs(z0), abs(z1)) > max_coordinate) then
      call card_error(error, deck, card, 'R0, R1, Z0 and Z1 must be in [-'//rtoa(max_coordinate)//', '// &
                      rtoa(max_coordinate)//'] m'); return
    end if
    if (nr < 1) then
      call card_error(error, deck, card, 'NR must be >= 1, got '//itoa(nr), field_column(card, 'NR')); return
    end if
    if (nz < 1) then
      call card_error(error, deck, card, 'NZ must be >= 1, got '//itoa(nz), field_column(card, 'NZ')); return
    end if
    call grid_mesh_counts(nr, nz, nodes, elements, least_width)
    call check_generated_size(deck, card, 'RECT', nodes, elements, least_width, trim(merge('NR', 'NZ', nr >= nz)), error)
    if (allocated(error)) return
    call rectangle_grid(r0, r1, z0, z1, nr, nz, xy, connectivity, edge_element, edge_side, edge_set)
  end subroutine read_rect_mesh

  !> MESH RING: the fields checked, the grid generated (ANGLE in degrees).
  subroutine read_ring_mesh(deck, card, xy, connectivity, edge_element, edge_side, edge_set, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: r0, r1, angle
    integer :: nr, nt
    integer(int64) :: nodes, elements, least_width
    call named_real(deck, card, 'R0', r0, error); if (allocated(error)) return
    call named_real(deck, card, 'R1', r1, error); if (allocated(error)) return
    call named_real(deck, card, 'ANGLE', angle, error, default=90.0_dp); if (allocated(error)) return
    call named_integer(deck, card, 'NR', nr, error); if (allocated(error)) return
    call named_integer(deck, card, 'NT', nt, error); if (allocated(error)) return
    call check_fields_used(deck, card, error, 'MESH RING R0=.. R1=.. NR=.. NT=.. [ANGLE=90] [MAT=id]')
    if (allocated(error)) return
    if (r0 <= 0.0_dp .or. r1 <= r0) then
      call card_error(error, deck, card, 'need 0 < R0 < R1', field_column(card, trim(merge('R0', 'R1', r0 <= 0.0_dp))))
      return
    end if
    if (angle <= 0.0_dp .or. angle > 90.0_dp) then
      call card_error(error, deck, card, 'ANGLE must be in (0, 90] degrees', field_column(card, 'ANGLE')); return
    end if
    if (r1 > max_coordinate) then
      call card_error(error, deck, card, 'R1 must be <= '//rtoa(max_coordinate)//' m, got '//rtoa(r1), &
                      field_column(card, 'R1')); return
    end if
    if (nr < 1) then
      call card_error(error, deck, card, 'NR must be >= 1, got '//itoa(nr), field_column(card, 'NR')); return
    end if
    if (nt < 1) then
      call card_error(error, deck, card, 'NT must be >= 1, got '//itoa(nt), field_column(card, 'NT')); return
    end if
    call grid_mesh_counts(nr, nt, nodes, elements, least_width)
    call check_generated_size(deck, card, 'RING', nodes, elements, least_width, trim(merge('NR', 'NT', nr >= nt)), error)
    if (allocated(error)) return
    call ring_grid(r0, r1, angle, nr, nt, xy, connectivity, edge_element, edge_side, edge_set)
  end subroutine read_ring_mesh

  !> Refuse, before generating it, a mesh larger than max_mesh_entities or
  !> on which even a STATIC run would need more memory than the limit
  !> (with the least half-bandwidth of the grid, so the refusal is sure).
  subroutine check_generated_size(deck, card, kind, nodes, elements, least_width, field, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    character(*), intent(in) :: kind, field
    integer(int64), intent(in) :: nodes, elements, least_width
    type(error_t), allocatable, intent(inout) :: error
    type(run_size_t) :: least
    real(dp) :: limit
    character(:), allocatable :: origin, what
    logical :: raisable
    what = 'MESH '//kind//' makes '//count_text(nodes)//' nodes and '//count_text(elements)//' elements'
    if (max(nodes, elements) > max_mesh_entities) then
      call card_error(error, deck, card, what//', more than '//count_text(max_mesh_entities), &
                      field_column(card, field)); return
    end if
    least = mesh_run_size(nodes, elements, least_width)
    call memory_limit(limit, origin, raisable)
    if (least%total_bytes <= limit) return
    call card_error(error, deck, card, what//': a run on it needs at least '//bytes_text(least%total_bytes)// &
      ' (the stiffness and its factor alone take '//bytes_text(least%band_bytes)//': '//count_text(2*nodes)// &
      ' equations, half-bandwidth at least '//count_text(least_width)//'), more than '//origin// &
      raise_hint(raisable), field_column(card, field))
  end subroutine check_generated_size

  logical function input_is_generated(input, deck, card, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    type(error_t), allocatable, intent(inout) :: error
    input_is_generated = input%generator_line > 0
    if (input_is_generated) call card_error(error, deck, card, card%keyword// &
      ' cards cannot be combined with the MESH card on line '//itoa(input%generator_line))
  end function input_is_generated

  subroutine reserve_nodes(input, extra)
    type(mesh_input_t), intent(inout) :: input
    integer, intent(in) :: extra
    integer :: capacity
    if (.not. allocated(input%xy)) allocate(input%xy(2, 0), input%node_id(0), input%node_line(0))
    if (input%nnode + extra <= size(input%node_id)) return
    capacity = max(2*size(input%node_id), input%nnode + extra, 64)
    call resize_real2(input%xy, capacity)
    call resize_int(input%node_id, capacity)
    call resize_int(input%node_line, capacity)
  end subroutine reserve_nodes

  subroutine reserve_elements(input, extra)
    type(mesh_input_t), intent(inout) :: input
    integer, intent(in) :: extra
    integer :: capacity
    character(len=name_length), allocatable :: material(:)
    integer, allocatable :: nodes(:, :)
    if (.not. allocated(input%nodes)) allocate(input%nodes(4, 0), input%element_id(0), &
                                               input%element_line(0), input%material(0))
    if (input%nelem + extra <= size(input%element_id)) return
    capacity = max(2*size(input%element_id), input%nelem + extra, 64)
    allocate(nodes(4, capacity), material(capacity))
    nodes(:, 1:input%nelem) = input%nodes(:, 1:input%nelem)
    material(1:input%nelem) = input%material(1:input%nelem)
    call move_alloc(nodes, input%nodes)
    call move_alloc(material, input%material)
    call resize_int(input%element_id, capacity)
    call resize_int(input%element_line, capacity)
  end subroutine reserve_elements

  subroutine resize_real2(array, capacity)
    real(dp), allocatable, intent(inout) :: array(:, :)
    integer, intent(in) :: capacity
    real(dp), allocatable :: bigger(:, :)
    allocate(bigger(size(array, 1), capacity))
    bigger = 0.0_dp
    bigger(:, 1:size(array, 2)) = array
    call move_alloc(bigger, array)
  end subroutine resize_real2

  subroutine resize_int(array, capacity)
    integer, allocatable, intent(inout) :: array(:)
    integer, intent(in) :: capacity
    integer, allocatable :: bigger(:)
    allocate(bigger(capacity))
    bigger = 0
    bigger(1:min(size(array), capacity)) = array(1:min(size(array), capacity))
    call move_alloc(bigger, array)
  end subroutine resize_int
end module visco2d_mesh_cards
