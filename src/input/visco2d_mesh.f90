!> Mesh input (legacy NODE/ELEMENT cards with generation, or a MESH generator
!> card), checks (duplicates, undefined or unused nodes, non-positive
!> Jacobians), boundary edge sets and bandwidth-reducing renumbering.
module visco2d_mesh
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_tolerance
  use visco2d_error, only: error_t, set_error
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_integer, named_word, &
                           positional_real, positional_integer, positional_word, check_fields_used, field_column
  use visco2d_quadrilateral, only: element_min_jacobian
  use visco2d_mesh_generator, only: sphere_grid, rectangle_grid, ring_grid, sphere_default_grade, sphere_default_core, &
                                    edge_set_none, edge_set_axis, edge_set_inner, edge_set_outer, &
                                    edge_set_bottom, edge_set_top, edge_set_name
  use visco2d_renumber, only: reverse_cuthill_mckee, half_bandwidth, sort_integers
  use visco2d_overlap, only: overlap_t, check_edges, check_overlaps, edge_keys, overlap_none, overlap_same_nodes, &
                             overlap_shared_edge, overlap_same_side, overlap_area, overlap_coincident_nodes, &
                             overlap_hanging_node
  use visco2d_budget, only: run_size_t, mesh_run_size, sphere_mesh_counts, grid_mesh_counts, memory_limit, &
                            bytes_text, count_text, max_mesh_entities
  use visco2d_strings, only: itoa, rtoa
  implicit none
  private

  public :: mesh_t, mesh_input_t, read_node_card, read_element_card, read_mesh_card, build_mesh
  public :: node_set, edge_set_code, node_index, side_nodes
  public :: edge_set_none, edge_set_axis, edge_set_inner, edge_set_outer, edge_set_bottom, edge_set_top
  public :: edge_set_name

  integer, parameter :: name_length = 32

  !> Largest node or element number, given or generated: what a card field
  !> can hold (9 digits), so every number can be named on a card.
  integer, parameter :: max_id = 999999999
  !> Largest |coordinate| of a node, m (lengths beyond the scale of any
  !> body keep every product of the solvers far from overflow).
  real(dp), parameter :: max_coordinate = 1.0e4_dp
  !> Smallest size (bounding-box diagonal) of a mesh, m: lengths are in metres.
  real(dp), parameter :: min_mesh_size = 1.0e-9_dp

  !> The finite-element mesh. Nodes and elements are stored in ascending
  !> user-number order; `equation` gives each node's place in the band order.
  type :: mesh_t
    integer :: nnode = 0, nelem = 0
    real(dp), allocatable :: xy(:, :)                 !< (2, nnode): r, z in m
    integer, allocatable :: node_id(:)                !< user node numbers
    integer, allocatable :: connectivity(:, :)        !< (4, nelem) node indices, counter-clockwise
    integer, allocatable :: element_id(:)             !< user element numbers
    integer, allocatable :: element_line(:)           !< deck line that defined the element
    integer, allocatable :: element_material(:)       !< index into the deck's materials
    character(len=name_length), allocatable :: element_material_name(:)
    integer, allocatable :: edge_element(:), edge_side(:), edge_set(:)  !< boundary edges
    integer, allocatable :: equation(:)               !< band position of each node (1..nnode)
    integer :: half_bandwidth = 0                     !< after renumbering (equations, diagonal excluded)
    integer :: half_bandwidth_before = 0              !< in input order
    character(:), allocatable :: source               !< 'CARDS', 'SPHERE' or 'RECT'
    real(dp) :: size = 1.0_dp                         !< bounding-box diagonal, m
    integer :: line = 0, column = 0                   !< the MESH card, or the first ELEMENT card
    character(:), allocatable :: card                 !< 'MESH' or 'ELEMENT'
  end type mesh_t

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

  !> MESH SPHERE R=.. [LEVEL=1] [MAT=id] [GRADE=2.35] [CORE=0.35]
  !> (MAT= may be omitted when the deck has one material)
  !> MESH RECT R0=.. R1=.. Z0=.. Z1=.. NR=.. NZ=.. [MAT=id]
  !> MESH RING R0=.. R1=.. NR=.. NT=.. [ANGLE=90] [MAT=id]   (plane-strain ring sector)
  subroutine read_mesh_card(input, deck, card, error)
    type(mesh_input_t), intent(inout) :: input
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    type(error_t), allocatable, intent(inout) :: error
    character(:), allocatable :: kind, material
    real(dp) :: radius, grade, core, r0, r1, z0, z1
    integer :: level, nr, nz, i
    integer(int64) :: nodes, elements, least_width
    real(dp), allocatable :: xy(:, :)
    integer, allocatable :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)

    if (input%nnode > 0 .or. input%nelem > 0) then
      call card_error(error, deck, card, 'a MESH card cannot be combined with NODE/ELEMENT cards or another MESH')
      return
    end if
    call positional_word(deck, card, 1, 'mesh kind (SPHERE, RECT or RING)', kind, error); if (allocated(error)) return
    call named_word(deck, card, 'MAT', material, error, default=''); if (allocated(error)) return
    select case (kind)
    case ('SPHERE')
      call named_real(deck, card, 'R', radius, error); if (allocated(error)) return
      call named_integer(deck, card, 'LEVEL', level, error, default=1); if (allocated(error)) return
      call named_real(deck, card, 'GRADE', grade, error, default=sphere_default_grade); if (allocated(error)) return
      call named_real(deck, card, 'CORE', core, error, default=sphere_default_core); if (allocated(error)) return
      call check_fields_used(deck, card, error, 'MESH SPHERE R=.. [LEVEL=L] [MAT=id] [GRADE=b] [CORE=c]')
      if (allocated(error)) return
      if (radius <= 0.0_dp) then
        call card_error(error, deck, card, 'R must be > 0 m, got '//rtoa(radius), field_column(card, 'R')); return
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
      if (radius > max_coordinate) then
        call card_error(error, deck, card, 'R must be <= '//rtoa(max_coordinate)//' m, got '//rtoa(radius), &
                        field_column(card, 'R')); return
      end if
      call sphere_mesh_counts(level, nodes, elements, least_width)
      call check_generated_size('LEVEL'); if (allocated(error)) return
      call sphere_grid(radius, level, grade, core, xy, connectivity, edge_element, edge_side, edge_set)
    case ('RECT')
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
      call check_generated_size(trim(merge('NR', 'NZ', nr >= nz))); if (allocated(error)) return
      call rectangle_grid(r0, r1, z0, z1, nr, nz, xy, connectivity, edge_element, edge_side, edge_set)
    case ('RING')
      call named_real(deck, card, 'R0', r0, error); if (allocated(error)) return
      call named_real(deck, card, 'R1', r1, error); if (allocated(error)) return
      call named_real(deck, card, 'ANGLE', z0, error, default=90.0_dp); if (allocated(error)) return
      call named_integer(deck, card, 'NR', nr, error); if (allocated(error)) return
      call named_integer(deck, card, 'NT', nz, error); if (allocated(error)) return
      call check_fields_used(deck, card, error, 'MESH RING R0=.. R1=.. NR=.. NT=.. [ANGLE=90] [MAT=id]')
      if (allocated(error)) return
      if (r0 <= 0.0_dp .or. r1 <= r0) then
        call card_error(error, deck, card, 'need 0 < R0 < R1', field_column(card, trim(merge('R0', 'R1', r0 <= 0.0_dp))))
        return
      end if
      if (z0 <= 0.0_dp .or. z0 > 90.0_dp) then
        call card_error(error, deck, card, 'ANGLE must be in (0, 90] degrees', field_column(card, 'ANGLE')); return
      end if
      if (r1 > max_coordinate) then
        call card_error(error, deck, card, 'R1 must be <= '//rtoa(max_coordinate)//' m, got '//rtoa(r1), &
                        field_column(card, 'R1')); return
      end if
      if (nr < 1) then
        call card_error(error, deck, card, 'NR must be >= 1, got '//itoa(nr), field_column(card, 'NR')); return
      end if
      if (nz < 1) then
        call card_error(error, deck, card, 'NT must be >= 1, got '//itoa(nz), field_column(card, 'NT')); return
      end if
      call grid_mesh_counts(nr, nz, nodes, elements, least_width)
      call check_generated_size(trim(merge('NR', 'NT', nr >= nz))); if (allocated(error)) return
      call ring_grid(r0, r1, z0, nr, nz, xy, connectivity, edge_element, edge_side, edge_set)
    case default
      call card_error(error, deck, card, 'mesh kind must be SPHERE, RECT or RING, got "'//kind//'"', &
                      field_column(card, '1')); return
    end select
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
    input%edge_element = edge_element
    input%edge_side = edge_side
    input%edge_set = edge_set
    input%source = kind
    input%generator_line = card%line
    input%generator_column = card%column

  contains

    !> Refuse, before generating it, a mesh larger than max_mesh_entities or
    !> on which even a STATIC run would need more memory than the limit
    !> (with the least half-bandwidth of the grid, so the refusal is sure).
    subroutine check_generated_size(field)
      character(*), intent(in) :: field
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
  end subroutine read_mesh_card

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

  !> Check the mesh cards and build the mesh: sorted numbering, node lookup,
  !> Jacobian check, overlap checks, boundary edges, renumbering for bandwidth.
  subroutine build_mesh(input, deck, geometry, mesh, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    integer, intent(in) :: geometry
    type(mesh_t), intent(out) :: mesh
    type(error_t), allocatable, intent(inout) :: error
    integer, allocatable :: order(:), element_order(:), edge_order(:)
    integer(int64), allocatable :: keys(:)
    integer :: i

    if (input%nnode == 0 .or. input%nelem == 0) then
      call set_error(error, 'missing mesh: give NODE and ELEMENT cards or a MESH card', file=deck%file)
      return
    end if
    if (input%generator_line > 0) then
      mesh%line = input%generator_line
      mesh%column = input%generator_column
      mesh%card = 'MESH'
    else
      mesh%line = input%first_element_line
      mesh%column = input%first_element_column
      mesh%card = 'ELEMENT'
    end if
    call number_nodes(input, deck, mesh, order, error); if (allocated(error)) return
    call number_elements(input, deck, mesh, element_order, error); if (allocated(error)) return
    call check_nodes_used(input, deck, mesh, order, error); if (allocated(error)) return
    call check_extent(input, deck, geometry, mesh, order, error); if (allocated(error)) return
    call check_jacobians(deck, mesh, error); if (allocated(error)) return
    keys = edge_keys(mesh%connectivity, mesh%nnode)
    call sort_integers(keys, edge_order)
    call check_covering(input, deck, mesh, order, keys, edge_order, error); if (allocated(error)) return

    if (allocated(input%edge_set)) then
      ! Generated meshes tag their edges; map element numbers through the sort.
      mesh%edge_element = input%edge_element
      mesh%edge_side = input%edge_side
      mesh%edge_set = input%edge_set
    else
      call find_boundary_edges(mesh, keys, edge_order)
    end if
    mesh%source = input%source

    ! Bandwidth: input order against reverse Cuthill-McKee; keep the better.
    mesh%equation = [(i, i = 1, mesh%nnode)]
    mesh%half_bandwidth_before = half_bandwidth(mesh%connectivity, mesh%equation)
    call reverse_cuthill_mckee(mesh%nnode, mesh%connectivity, order)
    mesh%half_bandwidth = half_bandwidth(mesh%connectivity, order)
    if (mesh%half_bandwidth < mesh%half_bandwidth_before) then
      mesh%equation = order
    else
      mesh%half_bandwidth = mesh%half_bandwidth_before
    end if
  end subroutine build_mesh

  !> Column of a field (see field_column) of the card on deck line `line`
  !> (cards are in line order); 0 if no card is on that line.
  integer function column_at(deck, line, field) result(column)
    type(card_deck_t), intent(in) :: deck
    integer, intent(in) :: line
    character(*), intent(in) :: field
    integer :: low, high, middle
    column = 0
    low = 1
    high = deck%count
    do while (low <= high)
      middle = (low + high)/2
      if (deck%cards(middle)%line == line) then
        column = field_column(deck%cards(middle), field)
        return
      else if (deck%cards(middle)%line < line) then
        low = middle + 1
      else
        high = middle - 1
      end if
    end do
  end function column_at

  !> Nodes in ascending number (order: input position of each); a number defined twice is an error.
  subroutine number_nodes(input, deck, mesh, order, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    type(mesh_t), intent(inout) :: mesh
    integer, allocatable, intent(out) :: order(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: i, line
    call sort_integers(int(input%node_id(1:input%nnode), int64), order)
    mesh%nnode = input%nnode
    mesh%node_id = input%node_id(order)
    mesh%xy = input%xy(:, order)
    do i = 2, mesh%nnode
      if (mesh%node_id(i) == mesh%node_id(i - 1)) then
        line = max(input%node_line(order(i)), input%node_line(order(i - 1)))
        call set_error(error, 'node '//itoa(mesh%node_id(i))//' defined twice (also on line '// &
          itoa(min(input%node_line(order(i)), input%node_line(order(i - 1))))//')', file=deck%file, &
          line=line, column=column_at(deck, line, '1'), card='NODE')
        return
      end if
    end do
  end subroutine number_nodes

  !> Elements in ascending number, their nodes as indices; a number defined
  !> twice or an undefined node is an error.
  subroutine number_elements(input, deck, mesh, element_order, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    type(mesh_t), intent(inout) :: mesh
    integer, allocatable, intent(out) :: element_order(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: e, j, node, line
    call sort_integers(int(input%element_id(1:input%nelem), int64), element_order)
    mesh%nelem = input%nelem
    mesh%element_id = input%element_id(element_order)
    mesh%element_line = input%element_line(element_order)
    mesh%element_material_name = input%material(element_order)
    allocate(mesh%connectivity(4, mesh%nelem), mesh%element_material(mesh%nelem))
    mesh%element_material = 0
    do e = 2, mesh%nelem
      if (mesh%element_id(e) == mesh%element_id(e - 1)) then
        line = max(mesh%element_line(e), mesh%element_line(e - 1))
        call set_error(error, 'element '//itoa(mesh%element_id(e))//' defined twice (also on line '// &
          itoa(min(mesh%element_line(e), mesh%element_line(e - 1)))//')', file=deck%file, &
          line=line, column=column_at(deck, line, '1'), card='ELEMENT')
        return
      end if
    end do
    do e = 1, mesh%nelem
      do j = 1, 4
        node = node_index(mesh, input%nodes(j, element_order(e)))
        if (node == 0) then
          call set_error(error, 'element '//itoa(mesh%element_id(e))//' uses node '// &
            itoa(input%nodes(j, element_order(e)))//', which is not defined', file=deck%file, &
            line=mesh%element_line(e), column=column_at(deck, mesh%element_line(e), itoa(1 + j)), card='ELEMENT')
          return
        end if
        mesh%connectivity(j, e) = node
      end do
    end do
  end subroutine number_elements

  !> Every node belongs to an element.
  subroutine check_nodes_used(input, deck, mesh, order, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: order(:)
    type(error_t), allocatable, intent(inout) :: error
    logical, allocatable :: used(:)
    integer :: e, i
    allocate(used(mesh%nnode))
    used = .false.
    do e = 1, mesh%nelem
      used(mesh%connectivity(:, e)) = .true.
    end do
    do i = 1, mesh%nnode
      if (.not. used(i)) then
        call set_error(error, 'node '//itoa(mesh%node_id(i))//' is not connected to any element', &
          file=deck%file, line=input%node_line(order(i)), column=column_at(deck, input%node_line(order(i)), '1'), &
          card='NODE')
        return
      end if
    end do
  end subroutine check_nodes_used

  !> The mesh's size (at least min_mesh_size: lengths are in metres) and,
  !> axisymmetric, r >= 0; nodes within the tolerance of the axis are put on it.
  subroutine check_extent(input, deck, geometry, mesh, order, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    integer, intent(in) :: geometry
    type(mesh_t), intent(inout) :: mesh
    integer, intent(in) :: order(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: lower(2), upper(2)
    integer :: i
    lower = minval(mesh%xy, dim=2)
    upper = maxval(mesh%xy, dim=2)
    mesh%size = norm2(upper - lower)
    if (mesh%size < min_mesh_size) then
      call set_error(error, 'the mesh is '//rtoa(mesh%size)//' m across: lengths are in metres and a mesh must be '// &
        'at least '//rtoa(min_mesh_size)//' m across', file=deck%file, line=mesh%line, column=mesh%column, &
        card=mesh%card)
      return
    end if
    if (geometry == geometry_axisymmetric .and. lower(1) < -geometry_tolerance*mesh%size) then
      i = minloc(mesh%xy(1, :), dim=1)
      call set_error(error, 'node '//itoa(mesh%node_id(i))//' has r < 0; axisymmetric meshes need r >= 0', &
        file=deck%file, line=input%node_line(order(i)), column=column_at(deck, input%node_line(order(i)), '2'), &
        card='NODE')
      return
    end if
    ! Snap r to exactly 0 on the axis.
    where (abs(mesh%xy(1, :)) <= geometry_tolerance*mesh%size) mesh%xy(1, :) = 0.0_dp
  end subroutine check_extent

  !> Every element convex and counter-clockwise: a Jacobian above a
  !> round-off floor at its corners and Gauss points.
  subroutine check_jacobians(deck, mesh, error)
    type(card_deck_t), intent(in) :: deck
    type(mesh_t), intent(in) :: mesh
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: jacobian, floor
    integer :: e
    character(:), allocatable :: why
    floor = 1.0e-12_dp*mesh%size**2
    do e = 1, mesh%nelem
      jacobian = element_min_jacobian(mesh%xy(:, mesh%connectivity(:, e)))
      if (jacobian > floor) cycle
      if (jacobian > 0.0_dp) then
        why = ' is nearly flat: its smallest Jacobian, '//rtoa(jacobian)//' m^2, is below 1e-12 of the mesh''s '// &
              'size squared; give it a reasonable shape'
      else
        why = ' has a non-positive Jacobian ('//rtoa(jacobian)//'): number its nodes counter-clockwise and keep it convex'
      end if
      call set_error(error, 'element '//itoa(mesh%element_id(e))//why, file=deck%file, line=mesh%element_line(e), &
        column=element_column(deck, mesh, e), card=mesh%card)
      return
    end do
  end subroutine check_jacobians

  !> Column of element e's number on its card (the MESH keyword for a generated mesh).
  integer function element_column(deck, mesh, e) result(column)
    type(card_deck_t), intent(in) :: deck
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e
    if (mesh%card == 'MESH') then
      column = mesh%column
    else
      column = column_at(deck, mesh%element_line(e), '1')
    end if
  end function element_column

  !> The elements cover the domain once: no two with the same nodes, no edge
  !> of three, no two on the same side of an edge, no overlapping areas, no
  !> distinct nodes at one point (a crack) and no node on another element's
  !> side (a hanging node). keys, edge_order: the sorted edge keys.
  subroutine check_covering(input, deck, mesh, order, keys, edge_order, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: order(:)
    integer(int64), intent(in) :: keys(:)
    integer, intent(in) :: edge_order(:)
    type(error_t), allocatable, intent(inout) :: error
    type(overlap_t) :: finding
    integer :: first, second, line
    character(:), allocatable :: message

    call check_edges(mesh%connectivity, keys, edge_order, finding)
    if (finding%kind == overlap_none) call check_overlaps(mesh%xy, mesh%connectivity, keys, edge_order, &
                                                          geometry_tolerance*mesh%size, finding)
    if (finding%kind == overlap_none) return
    ! The element defined last is the one in error; the other is named with its line.
    first = finding%elements(1)
    second = finding%elements(2)
    if (finding%kind /= overlap_hanging_node .and. second > 0) then
      if (mesh%element_line(first) > mesh%element_line(second)) then
        first = finding%elements(2)
        second = finding%elements(1)
      end if
    end if
    select case (finding%kind)
    case (overlap_same_nodes)
      message = 'elements '//named(first)//' and '//itoa(mesh%element_id(second))//' have the same four nodes ('// &
        node_list(mesh%connectivity(:, second))//'): a coincident element doubles the stiffness there'
    case (overlap_shared_edge)
      message = 'the side '//node_pair(finding%nodes)//' is shared by elements '//named(finding%elements(1))//', '// &
        named(finding%elements(2))//' and '//itoa(mesh%element_id(finding%elements(3)))// &
        ': a side joins at most two elements, so elements overlap there'
      second = maxloc(mesh%element_line(finding%elements), dim=1)
      second = finding%elements(second)
    case (overlap_same_side)
      message = 'elements '//named(first)//' and '//itoa(mesh%element_id(second))//' lie on the same side of '// &
        'their common side '//node_pair(finding%nodes)//': they overlap'
    case (overlap_area)
      if (second == 0) then
        second = first
        message = 'element '//itoa(mesh%element_id(first))//' lies where the mesh covers the body twice '// &
          '(each part of the body must be meshed once)'
      else
        message = 'element '//itoa(mesh%element_id(second))//' overlaps element '//named(first)// &
          ': their areas intersect (each part of the body must be meshed once)'
      end if
    case (overlap_coincident_nodes)
      message = 'nodes '//itoa(mesh%node_id(finding%nodes(1)))//' and '//itoa(mesh%node_id(finding%nodes(2)))// &
        ' are at the same point (r = '// &
        rtoa(mesh%xy(1, finding%nodes(1)))//', z = '//rtoa(mesh%xy(2, finding%nodes(1)))//') but are two '// &
        'nodes: elements '//named(first)//' and '//named(second)//' are not joined there (a crack, whose '// &
        'faces would pass through each other unseen); give both elements one node'
      line = max(input%node_line(order(finding%nodes(1))), input%node_line(order(finding%nodes(2))))
      call set_error(error, message, file=deck%file, line=line, column=column_at(deck, line, '1'), card='NODE')
      return
    case (overlap_hanging_node)
      first = finding%elements(2)              ! the element whose side holds the node
      second = finding%elements(1)
      message = 'node '//itoa(mesh%node_id(finding%nodes(1)))//' of element '//itoa(mesh%element_id(second))// &
        ' lies on a side of element '//named(first)//' but is not one of its nodes: the two are not joined '// &
        'along that side (a hanging node); split that side at the node'
    end select
    call set_error(error, message, file=deck%file, line=mesh%element_line(second), &
                   column=element_column(deck, mesh, second), card=mesh%card)

  contains

    !> "12 (line 30)": an element's number and the line of its card.
    function named(e) result(text)
      integer, intent(in) :: e
      character(:), allocatable :: text
      text = itoa(mesh%element_id(e))//' (line '//itoa(mesh%element_line(e))//')'
    end function named

    function node_pair(nodes) result(text)
      integer, intent(in) :: nodes(2)
      character(:), allocatable :: text
      text = itoa(mesh%node_id(nodes(1)))//'-'//itoa(mesh%node_id(nodes(2)))
    end function node_pair

    function node_list(nodes) result(text)
      integer, intent(in) :: nodes(4)
      character(:), allocatable :: text
      integer :: k
      text = itoa(mesh%node_id(nodes(1)))
      do k = 2, 4
        text = text//' '//itoa(mesh%node_id(nodes(k)))
      end do
    end function node_list
  end subroutine check_covering

  !> Boundary edges (used by one element only), tagged by the bounding box:
  !> r = rmin -> INNER (AXIS if rmin = 0), r = rmax -> OUTER, z = zmin -> BOTTOM, z = zmax -> TOP.
  !> keys, order: the edge keys (edge_keys) and their ascending order.
  subroutine find_boundary_edges(mesh, keys, order)
    type(mesh_t), intent(inout) :: mesh
    integer(int64), intent(in) :: keys(:)
    integer, intent(in) :: order(:)
    integer :: e, side, k, count, a, b, i, nedge
    real(dp) :: lower(2), upper(2), tol
    allocate(mesh%edge_element(size(keys)), mesh%edge_side(size(keys)), mesh%edge_set(size(keys)))
    nedge = 0
    lower = minval(mesh%xy, dim=2)
    upper = maxval(mesh%xy, dim=2)
    tol = geometry_tolerance*mesh%size
    count = size(keys)
    i = 1
    do while (i <= count)
      if (i < count) then
        if (keys(order(i + 1)) == keys(order(i))) then
          i = i + 2
          cycle
        end if
      end if
      k = order(i)
      e = (k - 1)/4 + 1
      side = k - 4*(e - 1)
      call side_nodes(mesh, e, side, a, b)
      nedge = nedge + 1
      mesh%edge_element(nedge) = e
      mesh%edge_side(nedge) = side
      mesh%edge_set(nedge) = classify(mesh%xy(:, a), mesh%xy(:, b))
      i = i + 1
    end do
    mesh%edge_element = mesh%edge_element(1:nedge)
    mesh%edge_side = mesh%edge_side(1:nedge)
    mesh%edge_set = mesh%edge_set(1:nedge)
  contains
    integer function classify(pa, pb) result(set)
      real(dp), intent(in) :: pa(2), pb(2)
      set = edge_set_none
      if (abs(pa(1) - lower(1)) <= tol .and. abs(pb(1) - lower(1)) <= tol) then
        set = edge_set_inner
        if (abs(lower(1)) <= tol) set = edge_set_axis   ! the axis, or in plane strain the plane x = 0
      else if (abs(pa(1) - upper(1)) <= tol .and. abs(pb(1) - upper(1)) <= tol) then
        set = edge_set_outer
      else if (abs(pa(2) - lower(2)) <= tol .and. abs(pb(2) - lower(2)) <= tol) then
        set = edge_set_bottom
      else if (abs(pa(2) - upper(2)) <= tol .and. abs(pb(2) - upper(2)) <= tol) then
        set = edge_set_top
      end if
    end function classify
  end subroutine find_boundary_edges

  !> The two nodes (counter-clockwise) of side `side` (1..4) of element e.
  pure subroutine side_nodes(mesh, e, side, a, b)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e, side
    integer, intent(out) :: a, b
    a = mesh%connectivity(side, e)
    b = mesh%connectivity(mod(side, 4) + 1, e)
  end subroutine side_nodes

  !> Edge-set code of a name (AXIS, INNER, OUTER, BOTTOM, TOP), 0 if unknown.
  pure integer function edge_set_code(name) result(code)
    character(*), intent(in) :: name
    select case (name)
    case ('AXIS'); code = edge_set_axis
    case ('INNER'); code = edge_set_inner
    case ('OUTER'); code = edge_set_outer
    case ('BOTTOM'); code = edge_set_bottom
    case ('TOP'); code = edge_set_top
    case default; code = edge_set_none
    end select
  end function edge_set_code

  !> Nodes of a named set: the nodes of its boundary edges. AXIS is every node
  !> at r = 0; BOTTOM/TOP with no tagged edges (a sphere) are the nodes at
  !> the lowest/highest z.
  subroutine node_set(mesh, code, nodes)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: code
    integer, allocatable, intent(out) :: nodes(:)
    logical, allocatable :: member(:)
    integer :: k, a, b, i
    real(dp) :: tol
    allocate(member(mesh%nnode))
    member = .false.
    tol = geometry_tolerance*mesh%size
    if (code == edge_set_axis) then
      member = mesh%xy(1, :) == 0.0_dp
    else
      do k = 1, size(mesh%edge_set)
        if (mesh%edge_set(k) /= code) cycle
        call side_nodes(mesh, mesh%edge_element(k), mesh%edge_side(k), a, b)
        member(a) = .true.
        member(b) = .true.
      end do
      if (.not. any(member)) then
        if (code == edge_set_bottom) member = mesh%xy(2, :) <= minval(mesh%xy(2, :)) + tol
        if (code == edge_set_top) member = mesh%xy(2, :) >= maxval(mesh%xy(2, :)) - tol
      end if
    end if
    nodes = pack([(i, i = 1, mesh%nnode)], member)
  end subroutine node_set

  !> Index of the node with user number id (binary search), 0 if absent.
  pure integer function node_index(mesh, id) result(index)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: id
    integer :: low, high, middle
    index = 0
    low = 1
    high = mesh%nnode
    do while (low <= high)
      middle = (low + high)/2
      if (mesh%node_id(middle) == id) then
        index = middle
        return
      else if (mesh%node_id(middle) < id) then
        low = middle + 1
      else
        high = middle - 1
      end if
    end do
  end function node_index

end module visco2d_mesh
