!> A checked, numbered mesh from the mesh cards: node and element numbers
!> (duplicates, undefined or unused nodes), the extent, non-positive
!> Jacobians, overlapping or uncovered elements (visco2d_overlap), the
!> boundary edge sets and the bandwidth-reducing renumbering.
module visco2d_mesh_build
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_tolerance
  use visco2d_error, only: error_t, set_error
  use visco2d_cards, only: card_deck_t, field_column
  use visco2d_quadrilateral, only: element_min_jacobian
  use visco2d_mesh_generator, only: edge_set_none, edge_set_axis, edge_set_inner, edge_set_outer, &
                                    edge_set_bottom, edge_set_top
  use visco2d_renumber, only: reverse_cuthill_mckee, half_bandwidth
  use visco2d_sorting, only: sorted_order
  use visco2d_overlap, only: overlap_t, check_edges, check_overlaps, edge_keys, overlap_none, overlap_same_nodes, &
                             overlap_shared_edge, overlap_same_side, overlap_area, overlap_coincident_nodes, &
                             overlap_hanging_node
  use visco2d_strings, only: integer_text, message_real
  use visco2d_mesh, only: mesh_t, node_index, side_nodes
  use visco2d_mesh_cards, only: mesh_input_t
  implicit none
  private

  public :: build_mesh, bandwidth_numbering

  !> Smallest size (bounding-box diagonal) of a mesh, m: lengths are in metres.
  real(dp), parameter :: min_mesh_size = 1.0e-9_dp

contains

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
    edge_order = sorted_order(keys)
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

    call bandwidth_numbering(mesh)
  end subroutine build_mesh

  !> Bandwidth: input order against reverse Cuthill-McKee; keep the better
  !> (mesh%equation, mesh%half_bandwidth and the input order's half_bandwidth_before).
  subroutine bandwidth_numbering(mesh)
    type(mesh_t), intent(inout) :: mesh
    integer, allocatable :: order(:)
    integer :: i
    mesh%equation = [(i, i = 1, mesh%nnode)]
    mesh%half_bandwidth_before = half_bandwidth(mesh%connectivity, mesh%equation)
    call reverse_cuthill_mckee(mesh%nnode, mesh%connectivity, order)
    mesh%half_bandwidth = half_bandwidth(mesh%connectivity, order)
    if (mesh%half_bandwidth < mesh%half_bandwidth_before) then
      mesh%equation = order
    else
      mesh%half_bandwidth = mesh%half_bandwidth_before
    end if
  end subroutine bandwidth_numbering

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
    order = sorted_order(input%node_id(1:input%nnode))
    mesh%nnode = input%nnode
    mesh%node_id = input%node_id(order)
    mesh%xy = input%xy(:, order)
    do i = 2, mesh%nnode
      if (mesh%node_id(i) == mesh%node_id(i - 1)) then
        line = max(input%node_line(order(i)), input%node_line(order(i - 1)))
        call set_error(error, 'node '//integer_text(mesh%node_id(i))//' defined twice (also on line '// &
          integer_text(min(input%node_line(order(i)), input%node_line(order(i - 1))))//')', file=deck%file, &
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
    element_order = sorted_order(input%element_id(1:input%nelem))
    mesh%nelem = input%nelem
    mesh%element_id = input%element_id(element_order)
    mesh%element_line = input%element_line(element_order)
    mesh%element_material_name = input%material(element_order)
    allocate(mesh%connectivity(4, mesh%nelem), mesh%element_material(mesh%nelem))
    mesh%element_material = 0
    do e = 2, mesh%nelem
      if (mesh%element_id(e) == mesh%element_id(e - 1)) then
        line = max(mesh%element_line(e), mesh%element_line(e - 1))
        call set_error(error, 'element '//integer_text(mesh%element_id(e))//' defined twice (also on line '// &
          integer_text(min(mesh%element_line(e), mesh%element_line(e - 1)))//')', file=deck%file, &
          line=line, column=column_at(deck, line, '1'), card='ELEMENT')
        return
      end if
    end do
    do e = 1, mesh%nelem
      do j = 1, 4
        node = node_index(mesh, input%nodes(j, element_order(e)))
        if (node == 0) then
          call set_error(error, 'element '//integer_text(mesh%element_id(e))//' uses node '// &
            integer_text(input%nodes(j, element_order(e)))//', which is not defined', file=deck%file, &
            line=mesh%element_line(e), column=column_at(deck, mesh%element_line(e), integer_text(1 + j)), card='ELEMENT')
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
        call set_error(error, 'node '//integer_text(mesh%node_id(i))//' is not connected to any element', &
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
      call set_error(error, 'the mesh is '//message_real(mesh%size)//' m across: lengths are in metres and a mesh must be '// &
        'at least '//message_real(min_mesh_size)//' m across', file=deck%file, line=mesh%line, column=mesh%column, &
        card=mesh%card)
      return
    end if
    if (geometry == geometry_axisymmetric .and. lower(1) < -geometry_tolerance*mesh%size) then
      i = minloc(mesh%xy(1, :), dim=1)
      call set_error(error, 'node '//integer_text(mesh%node_id(i))//' has r < 0; axisymmetric meshes need r >= 0', &
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
    integer :: e, column
    character(:), allocatable :: why
    floor = 1.0e-12_dp*mesh%size**2
    do e = 1, mesh%nelem
      jacobian = element_min_jacobian(mesh%xy(:, mesh%connectivity(:, e)))
      if (jacobian > floor) cycle
      if (jacobian > 0.0_dp) then
        why = ' is nearly flat: its smallest Jacobian, '//message_real(jacobian)//' m^2, is below 1e-12 of the mesh''s '// &
              'size squared; give it a reasonable shape'
      else if (mesh%card == 'MESH' .and. column_at(deck, mesh%line, 'CORE') + column_at(deck, mesh%line, 'GRADE') > 0) then
        ! A generated grid whose CORE/GRADE leave its layers no room at this LEVEL (CORE=0.94 on GRID=LEGACY,
        ! level 1): the user numbered no node, so "number its nodes counter-clockwise" would mislead.
        column = column_at(deck, mesh%line, 'CORE')
        if (column == 0) column = column_at(deck, mesh%line, 'GRADE')
        call set_error(error, 'the grid folds: element '//integer_text(mesh%element_id(e))//' is inverted (Jacobian '// &
          message_real(jacobian)//' m^2): its CORE and GRADE leave the layers no room at this LEVEL; a smaller '// &
          'CORE or GRADE (or a higher LEVEL) keeps it valid', file=deck%file, line=mesh%line, column=column, &
          card=mesh%card)
        return
      else if (mesh%card == 'MESH') then
        why = ' of the generated grid has a non-positive Jacobian ('//message_real(jacobian)//'): the MESH card''s '// &
              'dimensions fold it'
      else
        why = ' has a non-positive Jacobian ('//message_real(jacobian)//'): number its nodes counter-clockwise and keep it convex'
      end if
      call set_error(error, 'element '//integer_text(mesh%element_id(e))//why, file=deck%file, line=mesh%element_line(e), &
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
      message = 'elements '//named(first)//' and '//integer_text(mesh%element_id(second))//' have the same four nodes ('// &
        node_list(mesh%connectivity(:, second))//'): a coincident element doubles the stiffness there'
    case (overlap_shared_edge)
      message = 'the side '//node_pair(finding%nodes)//' is shared by elements '//named(finding%elements(1))//', '// &
        named(finding%elements(2))//' and '//integer_text(mesh%element_id(finding%elements(3)))// &
        ': a side joins at most two elements, so elements overlap there'
      second = maxloc(mesh%element_line(finding%elements), dim=1)
      second = finding%elements(second)
    case (overlap_same_side)
      message = 'elements '//named(first)//' and '//integer_text(mesh%element_id(second))//' lie on the same side of '// &
        'their common side '//node_pair(finding%nodes)//': they overlap'
    case (overlap_area)
      if (second == 0) then
        second = first
        message = 'element '//integer_text(mesh%element_id(first))//' lies where the mesh covers the body twice '// &
          '(each part of the body must be meshed once)'
      else
        message = 'element '//integer_text(mesh%element_id(second))//' overlaps element '//named(first)// &
          ': their areas intersect (each part of the body must be meshed once)'
      end if
    case (overlap_coincident_nodes)
      message = 'nodes '//integer_text(mesh%node_id(finding%nodes(1)))//' and '//integer_text(mesh%node_id(finding%nodes(2)))// &
        ' are at the same point (r = '// &
        message_real(mesh%xy(1, finding%nodes(1)))//', z = '//message_real(mesh%xy(2, finding%nodes(1)))//') but are two '// &
        'nodes: elements '//named(first)//' and '//named(second)//' are not joined there (a crack, whose '// &
        'faces would pass through each other unseen); give both elements one node'
      line = max(input%node_line(order(finding%nodes(1))), input%node_line(order(finding%nodes(2))))
      call set_error(error, message, file=deck%file, line=line, column=column_at(deck, line, '1'), card='NODE')
      return
    case (overlap_hanging_node)
      first = finding%elements(2)              ! the element whose side holds the node
      second = finding%elements(1)
      message = 'node '//integer_text(mesh%node_id(finding%nodes(1)))//' of element '//integer_text(mesh%element_id(second))// &
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
      text = integer_text(mesh%element_id(e))//' (line '//integer_text(mesh%element_line(e))//')'
    end function named

    function node_pair(nodes) result(text)
      integer, intent(in) :: nodes(2)
      character(:), allocatable :: text
      text = integer_text(mesh%node_id(nodes(1)))//'-'//integer_text(mesh%node_id(nodes(2)))
    end function node_pair

    function node_list(nodes) result(text)
      integer, intent(in) :: nodes(4)
      character(:), allocatable :: text
      integer :: k
      text = integer_text(mesh%node_id(nodes(1)))
      do k = 2, 4
        text = text//' '//integer_text(mesh%node_id(nodes(k)))
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

end module visco2d_mesh_build
