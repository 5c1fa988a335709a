!> The mesh cards: legacy NODE and ELEMENT cards with generation, or a MESH
!> generator card (SPHERE, SPHEROID, OUTLINE, RECT, RING; its fields are read
!> by visco2d_generator_cards), read into a mesh_input_t with the size of the
!> mesh checked against the limits before it is generated.
!> visco2d_mesh_build turns the input into a checked, numbered mesh_t.
module visco2d_mesh_cards
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_integer, named_word, &
                           positional_real, positional_integer, positional_word, positional_count, check_fields_used, &
                           field_column, has_field
  use visco2d_mesh_generator, only: sphere_element_layer, sphere_layer_count
  use visco2d_generator_cards, only: read_sphere_mesh, read_rect_mesh, read_ring_mesh
  use visco2d_budget, only: run_size_t, mesh_run_size, memory_limit, bytes_text, count_text, max_mesh_entities, &
                            raise_hint
  use visco2d_ranges, only: max_coordinate
  use visco2d_strings, only: integer_text, message_real
  use visco2d_mesh, only: name_length
  implicit none
  private

  public :: mesh_input_t, read_node_card, read_element_card, read_mesh_card

  !> Largest node or element number, given or generated: what a card field
  !> can hold (9 digits), so every number can be named on a card.
  integer, parameter :: max_id = 999999999

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
      call card_error(error, deck, card, 'node number must be positive, got '//integer_text(id), field_column(card, '1'))
      return
    end if
    if (count < 0) then
      call card_error(error, deck, card, 'GEN must be >= 0, got '//integer_text(count), field_column(card, 'GEN')); return
    end if
    if (increment <= 0) then
      call card_error(error, deck, card, 'INC must be > 0, got '//integer_text(increment), field_column(card, 'INC')); return
    end if
    if (count > 0 .and. dr == 0.0_dp .and. dz == 0.0_dp) then
      call card_error(error, deck, card, 'GEN needs a step DR= or DZ= (generated nodes would coincide)', &
                      field_column(card, 'GEN')); return
    end if
    last = int(id, int64) + int(count, int64)*increment
    if (last > max_id) then
      call card_error(error, deck, card, 'GEN='//integer_text(count)//' INC='//integer_text(increment)//' from node ' &
        //integer_text(id)// &
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
      call card_error(error, deck, card, what//' = '//message_real(value)//' m is out of range: coordinates must be in [-'// &
        message_real(max_coordinate)//', '//message_real(max_coordinate)//'] m', field_column(card, field))
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
      call positional_integer(deck, card, 1 + j, 'node '//integer_text(j)//' of 4', nodes(j), error)
      if (allocated(error)) return
    end do
    call named_word(deck, card, 'MAT', material, error, default=''); if (allocated(error)) return
    call named_integer(deck, card, 'GEN', generate, error, default=0); if (allocated(error)) return
    call named_integer(deck, card, 'INC', increment, error, default=1); if (allocated(error)) return
    call named_integer(deck, card, 'NINC', node_increment, error, default=1); if (allocated(error)) return
    call check_fields_used(deck, card, error, 'ELEMENT e n1 n2 n3 n4 MAT=id [GEN=k INC=de NINC=dn]')
    if (allocated(error)) return
    if (id <= 0) then
      call card_error(error, deck, card, 'element number must be positive, got '//integer_text(id), field_column(card, '1'))
      return
    end if
    do j = 1, 4
      if (nodes(j) <= 0) then
        call card_error(error, deck, card, 'node numbers must be positive, got '//integer_text(nodes(j)), &
                        field_column(card, integer_text(1 + j))); return
      end if
    end do
    if (generate < 0) then
      call card_error(error, deck, card, 'GEN must be >= 0, got '//integer_text(generate), field_column(card, 'GEN')); return
    end if
    if (increment <= 0) then
      call card_error(error, deck, card, 'INC must be > 0, got '//integer_text(increment), field_column(card, 'INC')); return
    end if
    do j = 1, 4
      if (count(nodes == nodes(j)) > 1) then
        call card_error(error, deck, card, 'node '//integer_text(nodes(j))// &
          ' appears twice: a quadrilateral needs 4 distinct nodes', field_column(card, integer_text(1 + j))); return
      end if
    end do
    if (len(material) > name_length) then
      call card_error(error, deck, card, 'MAT id longer than 32 characters', field_column(card, 'MAT')); return
    end if
    last = int(id, int64) + int(generate, int64)*increment
    if (last > max_id) then
      call card_error(error, deck, card, 'GEN='//integer_text(generate)//' INC='//integer_text(increment)//' from element '// &
        integer_text(id)//' would number the last element '//count_text(last)//', past the largest element number '// &
        count_text(int(max_id, int64)), field_column(card, merge('GEN', 'INC', generate > increment))); return
    end if
    do j = 1, 4                                   ! node numbers are linear in i: check the last element's
      extreme = int(nodes(j), int64) + int(generate, int64)*node_increment
      if (extreme < 1 .or. extreme > max_id) then
        call card_error(error, deck, card, 'GEN='//integer_text(generate)//' NINC='//integer_text(node_increment)// &
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

  !> MESH SPHERE R=.. [LEVEL=1] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c]
  !>   [SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id]
  !> (MAT= may be omitted when the deck has one material; GRADE and CORE
  !> default to 4.5 and 0.15 on the contact grid, 2.35 and 0.35 on the legacy grid;
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

  logical function input_is_generated(input, deck, card, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    type(error_t), allocatable, intent(inout) :: error
    input_is_generated = input%generator_line > 0
    if (input_is_generated) call card_error(error, deck, card, card%keyword// &
      ' cards cannot be combined with the MESH card on line '//integer_text(input%generator_line))
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
