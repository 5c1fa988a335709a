!> Mesh input (legacy NODE/ELEMENT cards with generation, or a MESH generator
!> card), checks (duplicates, undefined or unused nodes, non-positive
!> Jacobians), boundary edge sets and bandwidth-reducing renumbering.
module visco2d_mesh
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_tolerance
  use visco2d_error, only: error_t, set_error
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_integer, named_word, &
                           positional_real, positional_integer, positional_word, check_fields_used
  use visco2d_element, only: element_min_jacobian
  use visco2d_mesh_generator, only: sphere_grid, rectangle_grid, ring_grid, sphere_default_grade, sphere_default_core, &
                                    edge_set_none, edge_set_axis, edge_set_inner, edge_set_outer, &
                                    edge_set_bottom, edge_set_top, edge_set_name
  use visco2d_renumber, only: reverse_cuthill_mckee, half_bandwidth, sort_integers
  use visco2d_strings, only: itoa, rtoa
  implicit none
  private

  public :: mesh_t, mesh_input_t, read_node_card, read_element_card, read_mesh_card, build_mesh
  public :: node_set, edge_set_code, node_index, side_nodes
  public :: edge_set_none, edge_set_axis, edge_set_inner, edge_set_outer, edge_set_bottom, edge_set_top
  public :: edge_set_name

  integer, parameter :: name_length = 32

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
    integer :: generator_line = 0
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
      call card_error(error, deck, card, 'node number must be positive, got '//itoa(id)); return
    end if
    if (count < 0 .or. increment <= 0) then
      call card_error(error, deck, card, 'GEN must be >= 0 and INC > 0'); return
    end if
    if (count > 0 .and. dr == 0.0_dp .and. dz == 0.0_dp) then
      call card_error(error, deck, card, 'GEN needs a step DR= or DZ= (generated nodes would coincide)'); return
    end if
    call reserve_nodes(input, count + 1)
    do i = 0, count
      input%nnode = input%nnode + 1
      input%node_id(input%nnode) = id + i*increment
      input%xy(:, input%nnode) = [r + i*dr, z + i*dz]
      input%node_line(input%nnode) = card%line
    end do
    input%source = 'CARDS'
  end subroutine read_node_card

  !> ELEMENT e n1 n2 n3 n4 MAT=id [GEN=k INC=de NINC=dn]: element e, then k more
  !> numbered e+i*de with nodes n_j + i*dn.
  subroutine read_element_card(input, deck, card, error)
    type(mesh_input_t), intent(inout) :: input
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    type(error_t), allocatable, intent(inout) :: error
    integer :: id, nodes(4), generate, increment, node_increment, i, j
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
      call card_error(error, deck, card, 'element number must be positive, got '//itoa(id)); return
    end if
    if (generate < 0 .or. increment <= 0) then
      call card_error(error, deck, card, 'GEN must be >= 0 and INC > 0'); return
    end if
    do j = 1, 4
      if (count(nodes == nodes(j)) > 1) then
        call card_error(error, deck, card, 'node '//itoa(nodes(j))// &
          ' appears twice: a quadrilateral needs 4 distinct nodes'); return
      end if
    end do
    if (len(material) > name_length) then
      call card_error(error, deck, card, 'MAT id longer than 32 characters'); return
    end if
    call reserve_elements(input, generate + 1)
    do i = 0, generate
      input%nelem = input%nelem + 1
      input%element_id(input%nelem) = id + i*increment
      input%nodes(:, input%nelem) = nodes + i*node_increment
      input%material(input%nelem) = material
      input%element_line(input%nelem) = card%line
    end do
    input%source = 'CARDS'
  end subroutine read_element_card

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
        call card_error(error, deck, card, 'R must be > 0'); return
      end if
      if (level < 1 .or. level > 7) then
        call card_error(error, deck, card, 'LEVEL must be in 1..7 (level 7 has 360,448 elements), got '//itoa(level))
        return
      end if
      if (grade < 0.0_dp .or. grade > 6.0_dp) then
        call card_error(error, deck, card, 'GRADE must be in [0, 6]'); return
      end if
      if (core <= 0.05_dp .or. core >= 0.95_dp) then
        call card_error(error, deck, card, 'CORE must be in (0.05, 0.95)'); return
      end if
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
        call card_error(error, deck, card, 'need R1 > R0 and Z1 > Z0'); return
      end if
      if (nr < 1 .or. nz < 1 .or. real(nr, dp)*nz > 5.0e6_dp) then
        call card_error(error, deck, card, 'NR and NZ must be >= 1 (and NR*NZ <= 5e6)'); return
      end if
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
        call card_error(error, deck, card, 'need 0 < R0 < R1'); return
      end if
      if (z0 <= 0.0_dp .or. z0 > 90.0_dp) then
        call card_error(error, deck, card, 'ANGLE must be in (0, 90] degrees'); return
      end if
      if (nr < 1 .or. nz < 1 .or. real(nr, dp)*nz > 5.0e6_dp) then
        call card_error(error, deck, card, 'NR and NT must be >= 1 (and NR*NT <= 5e6)'); return
      end if
      call ring_grid(r0, r1, z0, nr, nz, xy, connectivity, edge_element, edge_side, edge_set)
    case default
      call card_error(error, deck, card, 'mesh kind must be SPHERE, RECT or RING, got "'//kind//'"'); return
    end select
    if (len(material) > name_length) then
      call card_error(error, deck, card, 'MAT id longer than 32 characters'); return
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
  !> Jacobian check, boundary edges, renumbering for bandwidth.
  subroutine build_mesh(input, deck, geometry, mesh, error)
    type(mesh_input_t), intent(in) :: input
    type(card_deck_t), intent(in) :: deck
    integer, intent(in) :: geometry
    type(mesh_t), intent(out) :: mesh
    type(error_t), allocatable, intent(inout) :: error
    integer, allocatable :: order(:), element_order(:), used(:)
    integer :: i, j, e, node
    real(dp) :: lower(2), upper(2), jacobian

    if (input%nnode == 0 .or. input%nelem == 0) then
      call set_error(error, 'missing mesh: give NODE and ELEMENT cards or a MESH card', file=deck%file)
      return
    end if
    ! Nodes, sorted by number; duplicates are errors.
    call sort_integers(int(input%node_id(1:input%nnode), int64), order)
    mesh%nnode = input%nnode
    mesh%node_id = input%node_id(order)
    mesh%xy = input%xy(:, order)
    do i = 2, mesh%nnode
      if (mesh%node_id(i) == mesh%node_id(i - 1)) then
        call set_error(error, 'node '//itoa(mesh%node_id(i))//' defined twice (also on line '// &
          itoa(min(input%node_line(order(i)), input%node_line(order(i - 1))))//')', file=deck%file, &
          line=max(input%node_line(order(i)), input%node_line(order(i - 1))), card='NODE')
        return
      end if
    end do
    ! Elements, sorted by number.
    call sort_integers(int(input%element_id(1:input%nelem), int64), element_order)
    mesh%nelem = input%nelem
    mesh%element_id = input%element_id(element_order)
    mesh%element_line = input%element_line(element_order)
    mesh%element_material_name = input%material(element_order)
    allocate(mesh%connectivity(4, mesh%nelem), mesh%element_material(mesh%nelem))
    mesh%element_material = 0
    do e = 2, mesh%nelem
      if (mesh%element_id(e) == mesh%element_id(e - 1)) then
        call set_error(error, 'element '//itoa(mesh%element_id(e))//' defined twice (also on line '// &
          itoa(min(mesh%element_line(e), mesh%element_line(e - 1)))//')', file=deck%file, &
          line=max(mesh%element_line(e), mesh%element_line(e - 1)), card='ELEMENT')
        return
      end if
    end do
    do e = 1, mesh%nelem
      do j = 1, 4
        node = node_index(mesh, input%nodes(j, element_order(e)))
        if (node == 0) then
          call set_error(error, 'element '//itoa(mesh%element_id(e))//' uses node '// &
            itoa(input%nodes(j, element_order(e)))//', which is not defined', file=deck%file, &
            line=mesh%element_line(e), card='ELEMENT')
          return
        end if
        mesh%connectivity(j, e) = node
      end do
    end do
    allocate(used(mesh%nnode))
    used = 0
    do e = 1, mesh%nelem
      used(mesh%connectivity(:, e)) = 1
    end do
    do i = 1, mesh%nnode
      if (used(i) == 0) then
        call set_error(error, 'node '//itoa(mesh%node_id(i))//' is not connected to any element', &
          file=deck%file, line=input%node_line(order(i)), card='NODE')
        return
      end if
    end do

    lower = minval(mesh%xy, dim=2)
    upper = maxval(mesh%xy, dim=2)
    mesh%size = max(norm2(upper - lower), tiny(1.0_dp))
    if (geometry == geometry_axisymmetric .and. lower(1) < -geometry_tolerance*mesh%size) then
      i = minloc(mesh%xy(1, :), dim=1)
      call set_error(error, 'node '//itoa(mesh%node_id(i))//' has r < 0; axisymmetric meshes need r >= 0', &
        file=deck%file, line=input%node_line(order(i)), card='NODE')
      return
    end if
    ! Snap r to exactly 0 on the axis.
    where (abs(mesh%xy(1, :)) <= geometry_tolerance*mesh%size) mesh%xy(1, :) = 0.0_dp

    do e = 1, mesh%nelem
      jacobian = element_min_jacobian(mesh%xy(:, mesh%connectivity(:, e)))
      if (jacobian <= 1.0e-12_dp*mesh%size**2) then
        call set_error(error, 'element '//itoa(mesh%element_id(e))//' has a non-positive Jacobian ('// &
          rtoa(jacobian)//'): number its nodes counter-clockwise and keep it convex', &
          file=deck%file, line=mesh%element_line(e), card=trim(merge('ELEMENT', 'MESH   ', input%generator_line == 0)))
        return
      end if
    end do

    if (allocated(input%edge_set)) then
      ! Generated meshes tag their edges; map element numbers through the sort.
      mesh%edge_element = input%edge_element
      mesh%edge_side = input%edge_side
      mesh%edge_set = input%edge_set
    else
      call find_boundary_edges(mesh)
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

  !> Boundary edges (used by one element only), tagged by the bounding box:
  !> r = rmin -> INNER (AXIS if rmin = 0), r = rmax -> OUTER, z = zmin -> BOTTOM, z = zmax -> TOP.
  subroutine find_boundary_edges(mesh)
    type(mesh_t), intent(inout) :: mesh
    integer(int64), allocatable :: keys(:)
    integer, allocatable :: order(:)
    integer :: e, side, k, count, a, b, i, nedge
    real(dp) :: lower(2), upper(2), tol
    allocate(keys(4*mesh%nelem))
    do e = 1, mesh%nelem
      do side = 1, 4
        call side_nodes(mesh, e, side, a, b)
        keys(4*(e - 1) + side) = int(min(a, b) - 1, int64)*mesh%nnode + max(a, b) - 1
      end do
    end do
    call sort_integers(keys, order)
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
