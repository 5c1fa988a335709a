!> Overlap tests of a mesh of convex counter-clockwise quadrilaterals (every
!> element that passed the Jacobian check is one: a positive Jacobian at the
!> four corners is a positive turn at each of them).
!>
!> A conforming mesh covers its domain once. The tests, each linear or
!> n log n in the number of elements whatever their shapes:
!>  1. sides (`check_edges`, from the sorted side keys): a side joins at most
!>     two elements, which run along it in opposite directions (so lie on either
!>     side of it), and no two elements have the same four nodes;
!>  2. corners (`check_overlaps`): around each node, the angular wedges of the
!>     elements that meet there do not overlap. With 1, the mesh is then a
!>     local one-to-one map of the plane everywhere except along its boundary;
!>  3. boundary: the boundary sides (those of one element) neither cross nor
!>     touch except at common nodes: two distinct nodes at one point are a
!>     crack, a node inside another's boundary side a hanging node, boundary
!>     sides along each other with the elements on one side an overlap;
!>  4. covering: with 1-3, the number of elements over a point is the winding
!>     number of the boundary around it, the same all along the inner side of a
!>     boundary loop; it must be 1 at a point inside one element of each loop
!>     (an element inside another element, or a part of the mesh lying on another,
!>     gives 2).
!> Tests 3 and 4 (visco2d_overlap_boundary) use a grid of bins over the
!> boundary sides only; the findings are visco2d_overlap_finding's
!> (re-exported here).
module visco2d_overlap
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, pi
  use visco2d_sorting, only: sorted_order
  use visco2d_overlap_finding, only: overlap_t, overlap_none, overlap_same_nodes, overlap_shared_edge, &
                                     overlap_same_side, overlap_area, overlap_coincident_nodes, overlap_hanging_node
  use visco2d_overlap_boundary, only: check_boundary, check_covering
  implicit none
  private

  public :: overlap_t, check_edges, check_overlaps, edge_keys, wedges_overlap
  public :: overlap_none, overlap_same_nodes, overlap_shared_edge, overlap_same_side, overlap_area, &
            overlap_coincident_nodes, overlap_hanging_node

  !> Angles (rad) within this are equal (round-off of atan2 is ~1e-16).
  real(dp), parameter :: angle_tolerance = 1.0e-9_dp

contains

  !> One key per element side: (min node - 1) nnode + (max node - 1), side k
  !> of element e at position 4 (e - 1) + k.
  pure function edge_keys(connectivity, nnode) result(keys)
    integer, intent(in) :: connectivity(:, :), nnode
    integer(int64), allocatable :: keys(:)
    integer :: e, side, a, b
    allocate(keys(4*size(connectivity, 2)))
    do e = 1, size(connectivity, 2)
      do side = 1, 4
        a = connectivity(side, e)
        b = connectivity(mod(side, 4) + 1, e)
        keys(4*(e - 1) + side) = int(min(a, b) - 1, int64)*nnode + max(a, b) - 1
      end do
    end do
  end function edge_keys

  !> Sides of more than two elements, and pairs of elements that have the same
  !> nodes or lie on the same side of their common side. keys and order: the
  !> side keys and their ascending order (sorted_order). Reports the finding
  !> whose later element comes first, same nodes before the others.
  pure subroutine check_edges(connectivity, keys, order, finding)
    integer, intent(in) :: connectivity(:, :)
    integer(int64), intent(in) :: keys(:)
    integer, intent(in) :: order(:)
    type(overlap_t), intent(out) :: finding
    type(overlap_t) :: candidate
    integer :: first, last, e1, e2, s1, s2
    first = 1
    do while (first <= size(order))
      last = first
      do while (last < size(order))
        if (keys(order(last + 1)) /= keys(order(first))) exit
        last = last + 1
      end do
      candidate%kind = overlap_none
      if (last > first) then
        e1 = (order(first) - 1)/4 + 1
        s1 = order(first) - 4*(e1 - 1)
        e2 = (order(first + 1) - 1)/4 + 1
        s2 = order(first + 1) - 4*(e2 - 1)
        candidate%elements = [e1, e2, 0]
        candidate%nodes = [connectivity(s1, e1), connectivity(mod(s1, 4) + 1, e1)]
        if (same_nodes(connectivity(:, e1), connectivity(:, e2))) then
          candidate%kind = overlap_same_nodes
        else if (last > first + 1) then
          candidate%kind = overlap_shared_edge
          candidate%elements(3) = (order(first + 2) - 1)/4 + 1
        else if (connectivity(s2, e2) == candidate%nodes(1)) then
          candidate%kind = overlap_same_side            ! both run a -> b: both lie to its left
        end if
      end if
      if (candidate%kind /= overlap_none) then
        if (finding%kind == overlap_none .or. better(candidate, finding)) finding = candidate
      end if
      first = last + 1
    end do
  contains
    pure logical function better(new, old)
      type(overlap_t), intent(in) :: new, old
      if ((new%kind == overlap_same_nodes) .neqv. (old%kind == overlap_same_nodes)) then
        better = new%kind == overlap_same_nodes
      else
        better = maxval(new%elements(1:2)) < maxval(old%elements(1:2))
      end if
    end function better
  end subroutine check_edges

  !> True if two elements have the same set of nodes.
  pure logical function same_nodes(a, b)
    integer, intent(in) :: a(4), b(4)
    integer :: k
    same_nodes = .true.
    do k = 1, 4
      if (.not. any(b == a(k))) same_nodes = .false.
    end do
  end function same_nodes

  !> Tests 2-4 of the module (call after check_edges found nothing).
  !> keys, order: the sorted side keys; tolerance (m): what counts as touching;
  !> work: the candidate tests made (pairs of wedges, of boundary sides and of
  !> sides against test points), a measure of the cost.
  subroutine check_overlaps(xy, connectivity, keys, order, tolerance, finding, work)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: connectivity(:, :)
    integer(int64), intent(in) :: keys(:)
    integer, intent(in) :: order(:)
    real(dp), intent(in) :: tolerance
    type(overlap_t), intent(out) :: finding
    integer(int64), intent(out), optional :: work
    integer, allocatable :: boundary(:, :)   ! (3, m): start node, end node, element
    integer(int64) :: tests
    tests = 0
    call check_corners(xy, connectivity, finding, tests)
    if (finding%kind == overlap_none) then
      call boundary_sides(connectivity, keys, order, boundary)
      call check_boundary(xy, boundary, tolerance, finding, tests)
      if (finding%kind == overlap_none) call check_covering(xy, connectivity, boundary, finding, tests)
    end if
    if (present(work)) work = tests
  end subroutine check_overlaps

  !> Test 2: around each node, the wedges of the elements there are disjoint.
  subroutine check_corners(xy, connectivity, finding, tests)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: connectivity(:, :)
    type(overlap_t), intent(inout) :: finding
    integer(int64), intent(inout) :: tests
    integer, allocatable :: start(:), fill(:), corner(:)
    real(dp), allocatable :: from(:), width(:)
    integer :: nnode, nelem, e, k, node, first, last, a, b
    nnode = size(xy, 2)
    nelem = size(connectivity, 2)
    ! The corners at each node (compressed rows): corner = 4 (e - 1) + k.
    allocate(start(nnode + 1), fill(nnode), corner(4*nelem), from(4*nelem), width(4*nelem))
    start = 0
    do e = 1, nelem
      do k = 1, 4
        start(connectivity(k, e)) = start(connectivity(k, e)) + 1
      end do
    end do
    fill(1) = 1
    do node = 2, nnode
      fill(node) = fill(node - 1) + start(node - 1)
    end do
    start(1:nnode) = fill
    start(nnode + 1) = 4*nelem + 1
    do e = 1, nelem
      do k = 1, 4
        node = connectivity(k, e)
        corner(fill(node)) = 4*(e - 1) + k
        call wedge(e, k, from(fill(node)), width(fill(node)))
        fill(node) = fill(node) + 1
      end do
    end do
    do node = 1, nnode
      first = start(node)
      last = start(node + 1) - 1
      if (last <= first) cycle
      tests = tests + (last - first + 1)
      call wedges_overlap(from(first:last), width(first:last), a, b)
      if (a > 0) then
        finding%kind = overlap_area
        finding%elements = [(corner(first + a - 1) - 1)/4 + 1, (corner(first + b - 1) - 1)/4 + 1, 0]
        return
      end if
    end do
  contains
    !> The wedge of element e at its corner k: from the direction of the next
    !> node, counter-clockwise over the interior angle to the previous node.
    subroutine wedge(e, k, angle, span)
      integer, intent(in) :: e, k
      real(dp), intent(out) :: angle, span
      real(dp) :: next(2), previous(2)
      next = xy(:, connectivity(mod(k, 4) + 1, e)) - xy(:, connectivity(k, e))
      previous = xy(:, connectivity(mod(k + 2, 4) + 1, e)) - xy(:, connectivity(k, e))
      angle = atan2(next(2), next(1))
      if (angle < 0.0_dp) angle = angle + 2.0_dp*pi
      span = atan2(next(1)*previous(2) - next(2)*previous(1), dot_product(next, previous))
    end subroutine wedge
  end subroutine check_corners

  !> Wedges [from, from + width] (rad, counter-clockwise, from in [0, 2 pi))
  !> around one point: a, b are two that overlap (positions in the arrays), 0 if none.
  subroutine wedges_overlap(from, width, a, b)
    real(dp), intent(in) :: from(:), width(:)
    integer, intent(out) :: a, b
    integer, allocatable :: order(:)
    integer :: i, j, n
    a = 0
    b = 0
    n = size(from)
    order = sorted_order(from)
    do i = 1, n
      j = mod(i, n) + 1
      if (from(order(i)) + width(order(i)) > from(order(j)) + merge(2.0_dp*pi, 0.0_dp, j == 1) + angle_tolerance) then
        a = order(i)
        b = order(j)
        return
      end if
    end do
  end subroutine wedges_overlap

  !> The sides of one element only, each as (start node, end node, element),
  !> counter-clockwise around the element.
  subroutine boundary_sides(connectivity, keys, order, boundary)
    integer, intent(in) :: connectivity(:, :)
    integer(int64), intent(in) :: keys(:)
    integer, intent(in) :: order(:)
    integer, allocatable, intent(out) :: boundary(:, :)
    integer :: i, n, m, e, side
    n = size(order)
    allocate(boundary(3, n))
    m = 0
    i = 1
    do while (i <= n)
      if (i < n) then
        if (keys(order(i + 1)) == keys(order(i))) then
          i = i + 2
          cycle
        end if
      end if
      e = (order(i) - 1)/4 + 1
      side = order(i) - 4*(e - 1)
      m = m + 1
      boundary(:, m) = [connectivity(side, e), connectivity(mod(side, 4) + 1, e), e]
      i = i + 1
    end do
    boundary = boundary(:, 1:m)
  end subroutine boundary_sides
end module visco2d_overlap
