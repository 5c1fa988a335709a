!> The finite-element mesh (mesh_t) and its queries: nodes by number or by
!> boundary edge set, the nodes of an element side. The mesh is read by
!> visco2d_mesh_cards (NODE/ELEMENT cards with generation, or a MESH
!> generator card) and checked, numbered and renumbered by
!> visco2d_mesh_build.
module visco2d_mesh
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, geometry_tolerance
  use visco2d_sorting, only: sorted_order
  implicit none
  private

  public :: mesh_t, name_length
  public :: node_set, edge_set_code, node_index, side_nodes, boundary_sides, pole_curvature_radius
  public :: generated_round_body
  public :: edge_set_none, edge_set_axis, edge_set_inner, edge_set_outer, edge_set_bottom, edge_set_top
  public :: edge_set_name

  !> Boundary edge sets: the generators tag the edges they make, the cards name them (edge_set_name).
  integer, parameter :: edge_set_none = 0, edge_set_axis = 1, edge_set_inner = 2, &
                        edge_set_outer = 3, edge_set_bottom = 4, edge_set_top = 5

  !> Length of a material name on an element.
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
    character(:), allocatable :: source               !< 'CARDS', 'SPHERE', 'SPHEROID', 'OUTLINE' or 'RECT'
    real(dp) :: size = 1.0_dp                         !< bounding-box diagonal, m
    integer :: line = 0, column = 0                   !< the MESH card, or the first ELEMENT card
    character(:), allocatable :: card                 !< 'MESH' or 'ELEMENT'
  end type mesh_t

contains

  !> Name of an edge-set code, as written on cards.
  pure function edge_set_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    select case (code)
    case (edge_set_axis); name = 'AXIS'
    case (edge_set_inner); name = 'INNER'
    case (edge_set_outer); name = 'OUTER'
    case (edge_set_bottom); name = 'BOTTOM'
    case (edge_set_top); name = 'TOP'
    case default; name = 'NONE'
    end select
  end function edge_set_name

  !> The two nodes (counter-clockwise) of side `side` (1..4) of element e.
  pure subroutine side_nodes(mesh, e, side, a, b)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: e, side
    integer, intent(out) :: a, b
    a = mesh%connectivity(side, e)
    b = mesh%connectivity(mod(side, 4) + 1, e)
  end subroutine side_nodes

  !> The boundary sides of elements 1..last: the sides that belong to one of
  !> those elements only, as node pairs (smaller index first), in the order
  !> of their sort key.
  function boundary_sides(mesh, last) result(edges)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: last
    integer, allocatable :: edges(:, :)
    integer(int64), allocatable :: keys(:)
    integer, allocatable :: order(:), pairs(:, :)
    integer :: e, side, a, b, i, count, nedge
    allocate(keys(4*last), pairs(2, 4*last))
    count = 0
    do e = 1, last
      do side = 1, 4
        call side_nodes(mesh, e, side, a, b)
        count = count + 1
        pairs(:, count) = [min(a, b), max(a, b)]
        keys(count) = int(pairs(1, count), int64)*int(mesh%nnode + 1, int64) + int(pairs(2, count), int64)
      end do
    end do
    order = sorted_order(keys)
    allocate(edges(2, count))
    nedge = 0
    do i = 1, count
      if (i > 1) then
        if (keys(order(i)) == keys(order(i - 1))) cycle
      end if
      if (i < count) then
        if (keys(order(i)) == keys(order(i + 1))) cycle
      end if
      nedge = nedge + 1
      edges(:, nedge) = pairs(:, order(i))
    end do
    edges = edges(:, 1:nedge)
  end function boundary_sides

  !> The radius of curvature, m, of the boundary of elements 1..last (a body
  !> of revolution) at its contact pole, the lowest boundary node on the axis:
  !> the circle centred on the axis through the pole and its neighbour along
  !> the boundary, R = (r^2 + dz^2)/(2 dz). This is the R of Hertz's contact,
  !> eqs. [43]-[45]: for a generated sphere its radius on both grids and
  !> every level (the pole nodes lie on the sphere: +0.005 % at level 1 of the
  !> contact grid), for a spheroid A^2/C to O(theta^2) (theta the first
  !> segment's angle, 1.15 deg at level 1), for an outline its spline's
  !> (measured on inputs/outline_apple.inp: -0.50 % at level 1, -0.04 % at
  !> level 4). Not half the body's height, nor the radius of its volume: the
  !> contact grid moves its far-pole nodes out to restore the volume (6.8 mm
  !> on a 36.6 mm sphere at level 1), and a spheroid's pole curvature is not
  !> its mean radius. 0 when there is no pole node or the boundary is not
  !> convex there (dz <= 0: no Hertz contact).
  !> Whether the mesh is a generated round body (`MESH SPHERE`, `SPHEROID` or
  !> `OUTLINE`): a convex contact pole on the axis that touches a plate like
  !> a sphere of the pole's radius of curvature, the body Hertz's reference
  !> and the Hertz advice are computed for.
  pure logical function generated_round_body(mesh)
    type(mesh_t), intent(in) :: mesh
    generated_round_body = .false.
    if (.not. allocated(mesh%source)) return
    generated_round_body = mesh%source == 'SPHERE' .or. mesh%source == 'SPHEROID' .or. mesh%source == 'OUTLINE'
  end function generated_round_body

  function pole_curvature_radius(mesh, last) result(radius)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: last
    real(dp) :: radius
    integer, allocatable :: edges(:, :)
    real(dp) :: tol, rise, run
    integer :: k, pole, side
    radius = 0.0_dp
    edges = boundary_sides(mesh, last)
    tol = geometry_tolerance*mesh%size
    pole = 0
    do k = 1, size(edges, 2)
      do side = 1, 2
        associate (node => edges(side, k))
        if (abs(mesh%xy(1, node)) > tol) cycle
        if (pole == 0) then
          pole = node
        else if (mesh%xy(2, node) < mesh%xy(2, pole)) then
          pole = node
        end if
        end associate
      end do
    end do
    if (pole == 0) return
    do k = 1, size(edges, 2)
      if (all(edges(:, k) /= pole)) cycle
      associate (other => sum(edges(:, k)) - pole)
      run = abs(mesh%xy(1, other))
      rise = mesh%xy(2, other) - mesh%xy(2, pole)
      end associate
      if (run <= tol .or. rise <= tol) cycle     ! the side along the axis, or not convex
      radius = (run**2 + rise**2)/(2.0_dp*rise)
      return
    end do
  end function pole_curvature_radius

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
