!> Overlap tests of a mesh of convex counter-clockwise quadrilaterals (every
!> element that passed the Jacobian check is one: a positive Jacobian at the
!> four corners is a positive turn at each of them).
!>
!> A conforming mesh covers its domain once: each interior edge joins exactly
!> two elements, which lie on either side of it (they run along it in opposite
!> directions), no two elements share area, and elements meet only at common
!> nodes. `check_edges` tests the first two from the sorted edge keys, in
!> O(n log n); `check_overlaps` the others with a uniform grid of bins (cell
!> size: the geometric mean of the elements' extents), testing only the pairs
!> of elements whose boxes meet, each pair once, in O(n) for a mesh whose
!> element sizes vary smoothly.
module visco2d_overlap
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_renumber, only: sort_integers
  implicit none
  private

  public :: overlap_t, check_edges, check_overlaps, quads_overlap, edge_keys
  public :: overlap_none, overlap_same_nodes, overlap_shared_edge, overlap_same_side, overlap_area, &
            overlap_coincident_nodes, overlap_hanging_node

  !> What was found.
  integer, parameter :: overlap_none = 0
  integer, parameter :: overlap_same_nodes = 1        !< two elements with the same four nodes
  integer, parameter :: overlap_shared_edge = 2       !< an edge of three or more elements
  integer, parameter :: overlap_same_side = 3         !< two elements on the same side of their common edge
  integer, parameter :: overlap_area = 4              !< two elements whose areas intersect
  integer, parameter :: overlap_coincident_nodes = 5  !< two distinct nodes at one point (a crack)
  integer, parameter :: overlap_hanging_node = 6      !< a node on another element's edge, not one of its nodes

  !> A finding: its kind, the elements (indices) and nodes (indices) concerned.
  type :: overlap_t
    integer :: kind = overlap_none
    integer :: elements(3) = 0   !< two elements (three for overlap_shared_edge)
    integer :: nodes(2) = 0      !< the edge; the coincident nodes; the hanging node and 0
  end type overlap_t

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

  !> Edges of more than two elements, and pairs of elements that have the same
  !> nodes or lie on the same side of their common edge. keys and order: the
  !> edge keys and their ascending order (sort_integers). Reports the first
  !> finding in element order, same nodes before the others.
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

  !> Elements whose areas intersect, distinct nodes at one point, and nodes on
  !> an edge of an element they do not belong to; tolerance (m): what counts as
  !> touching. Call after check_edges (elements that share an edge are then on
  !> either side of it and are not tested again). Reports an area overlap
  !> before the others.
  subroutine check_overlaps(xy, connectivity, tolerance, finding, pairs)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: connectivity(:, :)
    real(dp), intent(in) :: tolerance
    type(overlap_t), intent(out) :: finding
    integer(int64), intent(out), optional :: pairs   !< pairs of elements tested (boxes meet)
    real(dp), allocatable :: lower(:, :), upper(:, :)
    integer, allocatable :: range(:, :), start(:), items(:), fill(:)
    real(dp) :: origin(2), extent(2), cell, log_sum
    integer :: nelem, e, nx, ny, c, a, b, ix, iy, owner
    integer(int64) :: cells, insertions
    type(overlap_t) :: other, pair
    integer(int64) :: tested

    tested = 0
    if (present(pairs)) pairs = 0
    nelem = size(connectivity, 2)
    if (nelem < 2) return
    allocate(lower(2, nelem), upper(2, nelem), range(4, nelem))
    log_sum = 0.0_dp
    do e = 1, nelem
      lower(:, e) = minval(xy(:, connectivity(:, e)), dim=2)
      upper(:, e) = maxval(xy(:, connectivity(:, e)), dim=2)
      log_sum = log_sum + log(max(maxval(upper(:, e) - lower(:, e)), tiny(1.0_dp)))
    end do
    origin = minval(lower, dim=2) - tolerance
    extent = maxval(upper, dim=2) + tolerance - origin
    cell = max(exp(log_sum/nelem), maxval(extent)/2.0e4_dp)   ! at most 2e4 cells a side
    do                                       ! grow the cells until their number and the insertions are O(n)
      nx = int(extent(1)/cell) + 1
      ny = int(extent(2)/cell) + 1
      cells = int(nx, int64)*ny
      insertions = 0
      do e = 1, nelem
        range(:, e) = [cell_of(lower(1, e) - tolerance, 1, nx), cell_of(upper(1, e) + tolerance, 1, nx), &
                       cell_of(lower(2, e) - tolerance, 2, ny), cell_of(upper(2, e) + tolerance, 2, ny)]
        insertions = insertions + int(range(2, e) - range(1, e) + 1, int64)*(range(4, e) - range(3, e) + 1)
      end do
      if (cells <= 4_int64*nelem + 16 .and. insertions <= 32_int64*nelem + 1024) exit
      cell = 2.0_dp*cell
    end do

    allocate(start(cells + 1), fill(cells), items(insertions))
    start = 0
    do e = 1, nelem
      do iy = range(3, e), range(4, e)
        do ix = range(1, e), range(2, e)
          c = iy*nx + ix + 1
          start(c) = start(c) + 1
        end do
      end do
    end do
    fill(1) = 1
    do c = 2, int(cells)
      fill(c) = fill(c - 1) + start(c - 1)
    end do
    start(1:cells) = fill
    start(cells + 1) = int(insertions) + 1
    do e = 1, nelem
      do iy = range(3, e), range(4, e)
        do ix = range(1, e), range(2, e)
          c = iy*nx + ix + 1
          items(fill(c)) = e
          fill(c) = fill(c) + 1
        end do
      end do
    end do

    other%kind = overlap_none
    do c = 1, int(cells)
      do a = start(c), start(c + 1) - 1
        do b = a + 1, start(c + 1) - 1
          associate (i => items(a), j => items(b))
          if (any(lower(:, i) > upper(:, j) + tolerance) .or. any(lower(:, j) > upper(:, i) + tolerance)) cycle
          ! Test the pair once: in the cell of the lower-left corner of the boxes' intersection.
          owner = cell_of(max(lower(2, i), lower(2, j)), 2, ny)*nx + cell_of(max(lower(1, i), lower(1, j)), 1, nx) + 1
          if (owner /= c) cycle
          tested = tested + 1
          call test_pair(min(i, j), max(i, j), pair)
          end associate
          if (pair%kind == overlap_area) then
            finding = pair
            if (present(pairs)) pairs = tested
            return
          end if
          if (pair%kind /= overlap_none .and. other%kind == overlap_none) other = pair
        end do
      end do
    end do
    finding = other
    if (present(pairs)) pairs = tested

  contains

    pure integer function cell_of(x, axis, n) result(index)
      real(dp), intent(in) :: x
      integer, intent(in) :: axis, n
      index = min(n - 1, max(0, int((x - origin(axis))/cell)))
    end function cell_of

    !> The tests of one pair of elements whose boxes meet.
    subroutine test_pair(i, j, pair)
      integer, intent(in) :: i, j
      type(overlap_t), intent(out) :: pair
      integer :: shared, p
      shared = 0
      do p = 1, 4
        if (any(connectivity(:, j) == connectivity(p, i))) shared = shared + 1
      end do
      if (shared >= 2) return                    ! a common side: on either side of it (check_edges)
      if (quads_overlap(xy(:, connectivity(:, i)), xy(:, connectivity(:, j)), tolerance)) then
        pair%kind = overlap_area
        pair%elements = [i, j, 0]
        return
      end if
      call node_on_boundary(i, j, pair)
      if (pair%kind == overlap_none) call node_on_boundary(j, i, pair)
    end subroutine test_pair

    !> A node of element `other` at a node of `element` (not the same node: a
    !> crack) or inside one of its sides (a hanging node). Only nodes inside
    !> the element's box can be.
    subroutine node_on_boundary(element, other, pair)
      integer, intent(in) :: element, other
      type(overlap_t), intent(inout) :: pair
      integer :: q, k, m
      do q = 1, 4
        m = connectivity(q, other)
        if (any(xy(:, m) < lower(:, element) - tolerance) .or. any(xy(:, m) > upper(:, element) + tolerance)) cycle
        if (any(connectivity(:, element) == m)) cycle
        do k = 1, 4
          associate (n => connectivity(k, element))
          if (all(abs(xy(:, m) - xy(:, n)) <= tolerance)) then
            pair%kind = overlap_coincident_nodes
            pair%elements = [min(element, other), max(element, other), 0]
            pair%nodes = [min(m, n), max(m, n)]
            return
          end if
          end associate
        end do
        do k = 1, 4
          if (on_side(connectivity(:, element), k, m)) then
            pair%kind = overlap_hanging_node
            pair%elements = [other, element, 0]
            pair%nodes = [m, 0]
            return
          end if
        end do
      end do
    end subroutine node_on_boundary

    !> True if node m (not one of the element's) lies on side `side` of the
    !> element with nodes `element`, strictly between its ends.
    pure logical function on_side(element, side, m)
      integer, intent(in) :: element(4), side, m
      real(dp) :: d(2), w(2), length, along
      on_side = .false.
      d = xy(:, element(mod(side, 4) + 1)) - xy(:, element(side))
      w = xy(:, m) - xy(:, element(side))
      length = sqrt(d(1)**2 + d(2)**2)
      if (abs(d(1)*w(2) - d(2)*w(1)) > tolerance*length) return
      along = (w(1)*d(1) + w(2)*d(2))/length
      on_side = along > tolerance .and. along < length - tolerance
    end function on_side
  end subroutine check_overlaps

  !> True if two convex counter-clockwise quadrilaterals share area: no edge
  !> of either separates them (separating axis test; touching within
  !> `tolerance` is not an overlap).
  pure logical function quads_overlap(p, q, tolerance)
    real(dp), intent(in) :: p(2, 4), q(2, 4), tolerance
    quads_overlap = .not. (separates(p, q) .or. separates(q, p))
  contains
    !> An edge of a whose outward side holds all of b (within the tolerance).
    pure logical function separates(a, b)
      real(dp), intent(in) :: a(2, 4), b(2, 4)
      real(dp) :: normal(2), length, nearest
      integer :: k, l
      separates = .false.
      do k = 1, 4
        l = mod(k, 4) + 1
        normal = [a(2, l) - a(2, k), a(1, k) - a(1, l)]             ! outward for counter-clockwise
        length = sqrt(normal(1)**2 + normal(2)**2)
        if (length == 0.0_dp) cycle
        nearest = minval(normal(1)*(b(1, :) - a(1, k)) + normal(2)*(b(2, :) - a(2, k)))
        if (nearest >= -tolerance*length) then
          separates = .true.
          return
        end if
      end do
    end function separates
  end function quads_overlap
end module visco2d_overlap
