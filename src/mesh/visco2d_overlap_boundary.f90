!> Tests 3 and 4 of visco2d_overlap, on the boundary sides (those of one
!> element) only, with a grid of bins over them:
!>  3. boundary: the boundary sides neither cross nor touch except at common
!>     nodes (two distinct nodes at one point are a crack, a node inside
!>     another's boundary side a hanging node, boundary sides along each
!>     other with the elements on one side an overlap);
!>  4. covering: the boundary winds once around a point inside one element
!>     of each boundary loop.
module visco2d_overlap_boundary
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_overlap_finding, only: overlap_t, overlap_none, overlap_area, overlap_coincident_nodes, &
                                     overlap_hanging_node
  implicit none
  private

  public :: check_boundary, check_covering

contains

  !> Test 3: boundary sides neither cross nor touch but at common nodes.
  subroutine check_boundary(xy, boundary, tolerance, finding, tests)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: boundary(:, :)
    real(dp), intent(in) :: tolerance
    type(overlap_t), intent(inout) :: finding
    integer(int64), intent(inout) :: tests
    real(dp), allocatable :: lower(:, :), upper(:, :)
    integer, allocatable :: start(:), items(:)
    integer :: m, c, p, q, owner, nx, ny
    real(dp) :: origin(2), cell
    m = size(boundary, 2)
    if (m < 2) return
    allocate(lower(2, m), upper(2, m))
    do p = 1, m
      lower(:, p) = min(xy(:, boundary(1, p)), xy(:, boundary(2, p))) - tolerance
      upper(:, p) = max(xy(:, boundary(1, p)), xy(:, boundary(2, p))) + tolerance
    end do
    call bin_boxes(lower, upper, origin, cell, nx, ny, start, items)
    do c = 1, size(start) - 1
      do p = start(c), start(c + 1) - 1
        do q = p + 1, start(c + 1) - 1
          associate (i => items(p), j => items(q))
          if (any(lower(:, i) > upper(:, j)) .or. any(lower(:, j) > upper(:, i))) cycle
          ! Test the pair once: in the bin of the lower-left corner of the boxes' intersection.
          owner = bin_of(max(lower(2, i), lower(2, j)), origin(2), cell, ny)*nx &
                  + bin_of(max(lower(1, i), lower(1, j)), origin(1), cell, nx) + 1
          if (owner /= c) cycle
          tests = tests + 1
          call test_sides(xy, boundary, tolerance, min(i, j), max(i, j), finding)
          end associate
          if (finding%kind /= overlap_none) return
        end do
      end do
    end do
  end subroutine check_boundary

  !> Two boundary sides s = a -> b and t = c -> d (of elements E and F).
  subroutine test_sides(xy, boundary, tolerance, s, t, finding)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: boundary(:, :)
    real(dp), intent(in) :: tolerance
    type(overlap_t), intent(inout) :: finding
    integer, intent(in) :: s, t
    integer :: a, b, c, d
    a = boundary(1, s); b = boundary(2, s)
    c = boundary(1, t); d = boundary(2, t)
    if (a == c .or. a == d .or. b == c .or. b == d) then
      call common_node(xy, boundary, tolerance, s, t, finding)
      return
    end if
    if (collinear_overlap(xy, tolerance, a, b, c, d)) then
      if (dot_product(xy(:, b) - xy(:, a), xy(:, d) - xy(:, c)) > 0.0_dp) then
        call found(boundary, finding, overlap_area, s, t)      ! along each other, both elements on one side
      else
        call touching(xy, boundary, tolerance, s, t, finding)  ! face to face: a crack or a hanging node
        if (finding%kind == overlap_none) call found(boundary, finding, overlap_coincident_nodes, s, t, a, c)
      end if
      return
    end if
    if (crossing(xy, tolerance, a, b, c, d)) then
      call found(boundary, finding, overlap_area, s, t)
      return
    end if
    call touching(xy, boundary, tolerance, s, t, finding)
  end subroutine test_sides

  !> Sides with a node in common: their other ends on one ray from it are a
  !> crack (at one point) or a hanging node (the nearer on the other side).
  subroutine common_node(xy, boundary, tolerance, s, t, finding)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: boundary(:, :)
    real(dp), intent(in) :: tolerance
    type(overlap_t), intent(inout) :: finding
    integer, intent(in) :: s, t
    integer :: v, a, b
    real(dp) :: da(2), db(2)
    if (boundary(1, s) == boundary(1, t) .or. boundary(1, s) == boundary(2, t)) then
      v = boundary(1, s); a = boundary(2, s)
    else
      v = boundary(2, s); a = boundary(1, s)
    end if
    b = merge(boundary(2, t), boundary(1, t), boundary(1, t) == v)
    if (a == b) return
    da = xy(:, a) - xy(:, v)
    db = xy(:, b) - xy(:, v)
    if (abs(da(1)*db(2) - da(2)*db(1)) > tolerance*max(norm2(da), norm2(db))) return
    if (dot_product(da, db) <= 0.0_dp) return
    if (norm2(xy(:, a) - xy(:, b)) <= tolerance) then
      call found(boundary, finding, overlap_coincident_nodes, s, t, a, b)
    else if (norm2(da) < norm2(db)) then
      call found(boundary, finding, overlap_hanging_node, s, t, a)
    else
      call found(boundary, finding, overlap_hanging_node, t, s, b)
    end if
  end subroutine common_node

  !> An end of one side at an end of the other (a crack) or inside it (a hanging node).
  subroutine touching(xy, boundary, tolerance, s, t, finding)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: boundary(:, :)
    real(dp), intent(in) :: tolerance
    type(overlap_t), intent(inout) :: finding
    integer, intent(in) :: s, t
    integer :: k, l
    do k = 1, 2
      do l = 1, 2
        if (norm2(xy(:, boundary(k, s)) - xy(:, boundary(l, t))) <= tolerance) then
          call found(boundary, finding, overlap_coincident_nodes, s, t, boundary(k, s), boundary(l, t))
          return
        end if
      end do
    end do
    do k = 1, 2
      if (inside_side(xy, boundary, tolerance, boundary(k, s), t)) then
        call found(boundary, finding, overlap_hanging_node, s, t, boundary(k, s))
        return
      end if
      if (inside_side(xy, boundary, tolerance, boundary(k, t), s)) then
        call found(boundary, finding, overlap_hanging_node, t, s, boundary(k, t))
        return
      end if
    end do
  end subroutine touching

  !> Node m lies on side s, strictly between its ends.
  logical function inside_side(xy, boundary, tolerance, m, s)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: boundary(:, :)
    real(dp), intent(in) :: tolerance
    integer, intent(in) :: m, s
    real(dp) :: d(2), w(2), length, along
    d = xy(:, boundary(2, s)) - xy(:, boundary(1, s))
    w = xy(:, m) - xy(:, boundary(1, s))
    length = norm2(d)
    inside_side = .false.
    if (abs(d(1)*w(2) - d(2)*w(1)) > tolerance*length) return
    along = dot_product(w, d)/length
    inside_side = along > tolerance .and. along < length - tolerance
  end function inside_side

  !> a-b and c-d on one line (within the tolerance) and overlapping over more than it.
  logical function collinear_overlap(xy, tolerance, a, b, c, d)
    real(dp), intent(in) :: xy(:, :)
    real(dp), intent(in) :: tolerance
    integer, intent(in) :: a, b, c, d
    real(dp) :: u(2), length, tc, td
    u = xy(:, b) - xy(:, a)
    length = norm2(u)
    collinear_overlap = .false.
    if (abs(cross(u, xy(:, c) - xy(:, a))) > tolerance*length) return
    if (abs(cross(u, xy(:, d) - xy(:, a))) > tolerance*length) return
    tc = dot_product(xy(:, c) - xy(:, a), u)/length
    td = dot_product(xy(:, d) - xy(:, a), u)/length
    collinear_overlap = min(length, max(tc, td)) - max(0.0_dp, min(tc, td)) > tolerance
  end function collinear_overlap

  !> a-b and c-d cross at a point inside both (each pair of ends strictly on either side).
  logical function crossing(xy, tolerance, a, b, c, d)
    real(dp), intent(in) :: xy(:, :)
    real(dp), intent(in) :: tolerance
    integer, intent(in) :: a, b, c, d
    real(dp) :: u(2), v(2), lu, lv
    u = xy(:, b) - xy(:, a)
    v = xy(:, d) - xy(:, c)
    lu = norm2(u)
    lv = norm2(v)
    crossing = sides_apart(cross(u, xy(:, c) - xy(:, a))/lu, cross(u, xy(:, d) - xy(:, a))/lu, tolerance) .and. &
               sides_apart(cross(v, xy(:, a) - xy(:, c))/lv, cross(v, xy(:, b) - xy(:, c))/lv, tolerance)
  end function crossing

  !> f and g of opposite signs, each beyond the tolerance.
  logical function sides_apart(f, g, tolerance)
    real(dp), intent(in) :: tolerance
    real(dp), intent(in) :: f, g
    sides_apart = (f > tolerance .and. g < -tolerance) .or. (f < -tolerance .and. g > tolerance)
  end function sides_apart

  !> Record a finding of this kind between boundary sides s and t (nodes m, n).
  subroutine found(boundary, finding, kind, s, t, m, n)
    integer, intent(in) :: boundary(:, :)
    type(overlap_t), intent(inout) :: finding
    integer, intent(in) :: kind, s, t
    integer, intent(in), optional :: m, n
    finding%kind = kind
    finding%elements = [boundary(3, s), boundary(3, t), 0]
    finding%nodes = 0
    if (present(m)) finding%nodes(1) = m
    if (present(n)) finding%nodes = [min(m, n), max(m, n)]
  end subroutine found

  pure real(dp) function cross(u, v)
    real(dp), intent(in) :: u(2), v(2)
    cross = u(1)*v(2) - u(2)*v(1)
  end function cross

  !> Test 4: the boundary winds once around a point inside an element of each
  !> boundary loop (followed from side to side by their nodes).
  subroutine check_covering(xy, connectivity, boundary, finding, tests)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: connectivity(:, :)
    integer, intent(in) :: boundary(:, :)
    type(overlap_t), intent(inout) :: finding
    integer(int64), intent(inout) :: tests
    integer, allocatable :: leaving(:), next_free(:), slab_start(:), slab_items(:)
    logical, allocatable :: visited(:)
    real(dp), allocatable :: low(:, :), high(:, :)
    real(dp) :: origin(2), cell, point(2)
    integer :: m, p, s, node, nnode, nslab, one, other
    m = size(boundary, 2)
    if (m == 0) return
    nnode = size(xy, 2)
    ! Sides leaving each node (compressed rows), and horizontal slabs of sides.
    allocate(leaving(nnode + 1), next_free(nnode), visited(m), low(2, m), high(2, m))
    leaving = 0
    do s = 1, m
      leaving(boundary(1, s)) = leaving(boundary(1, s)) + 1
    end do
    next_free(1) = 1
    do node = 2, nnode
      next_free(node) = next_free(node - 1) + leaving(node - 1)
    end do
    leaving(1:nnode) = next_free
    leaving(nnode + 1) = m + 1
    block
      integer :: sorted(m)
      do s = 1, m
        sorted(next_free(boundary(1, s))) = s
        next_free(boundary(1, s)) = next_free(boundary(1, s)) + 1
      end do
      next_free = leaving(1:nnode)
      do s = 1, m
        low(:, s) = [-huge(1.0_dp), min(xy(2, boundary(1, s)), xy(2, boundary(2, s)))]
        high(:, s) = [huge(1.0_dp), max(xy(2, boundary(1, s)), xy(2, boundary(2, s)))]
      end do
      call bin_slabs(low(2, :), high(2, :), origin(2), cell, nslab, slab_start, slab_items)
      visited = .false.
      do s = 1, m
        if (visited(s)) cycle
        ! One point per loop: the centroid of the element of its first side.
        point = 0.25_dp*sum(xy(:, connectivity(:, boundary(3, s))), dim=2)
        if (winding(point) /= 1) then
          one = boundary(3, s)
          other = covering_element(point, one)     ! 0 if none (then the message names one element)
          finding%kind = overlap_area
          finding%elements = [one, other, 0]
          if (other > 0) finding%elements(1:2) = [min(one, other), max(one, other)]
          return
        end if
        p = s
        do while (p > 0)                          ! mark the loop
          visited(p) = .true.
          node = boundary(2, p)
          p = 0
          do while (next_free(node) < leaving(node + 1))
            p = sorted(next_free(node))
            next_free(node) = next_free(node) + 1
            if (.not. visited(p)) exit
            p = 0
          end do
        end do
      end do
    end block
  contains

    !> Winding number of the boundary around a point (Sunday's crossing rule).
    integer function winding(at) result(turns)
      real(dp), intent(in) :: at(2)
      integer :: k, slab, s
      turns = 0
      slab = bin_of(at(2), origin(2), cell, nslab) + 1
      do k = slab_start(slab), slab_start(slab + 1) - 1
        s = slab_items(k)
        tests = tests + 1
        associate (a => xy(:, boundary(1, s)), b => xy(:, boundary(2, s)))
        if (a(2) <= at(2)) then
          if (b(2) > at(2) .and. cross(b - a, at - a) > 0.0_dp) turns = turns + 1
        else
          if (b(2) <= at(2) .and. cross(b - a, at - a) < 0.0_dp) turns = turns - 1
        end if
        end associate
      end do
    end function winding

    !> An element other than `except` with the point inside (0 if none).
    integer function covering_element(at, except) result(element)
      real(dp), intent(in) :: at(2)
      integer, intent(in) :: except
      integer :: e, k
      do e = 1, size(connectivity, 2)
        if (e == except) cycle
        element = e
        do k = 1, 4
          if (cross(xy(:, connectivity(mod(k, 4) + 1, e)) - xy(:, connectivity(k, e)), &
                    at - xy(:, connectivity(k, e))) < 0.0_dp) element = 0
        end do
        if (element > 0) return
      end do
      element = 0
    end function covering_element
  end subroutine check_covering

  !> Bins of a uniform grid over boxes (cell: the geometric mean of the boxes'
  !> sizes, grown until the bins and the box-bin pairs are O(n)); bin c holds
  !> items(start(c):start(c + 1) - 1). Bins are numbered row after row from 1.
  subroutine bin_boxes(lower, upper, origin, cell, nx, ny, start, items)
    real(dp), intent(in) :: lower(:, :), upper(:, :)
    real(dp), intent(out) :: origin(2), cell
    integer, intent(out) :: nx, ny
    integer, allocatable, intent(out) :: start(:), items(:)
    integer, allocatable :: range(:, :), fill(:)
    real(dp) :: extent(2), log_sum
    integer(int64) :: cells, insertions
    integer :: n, k, ix, iy, c
    n = size(lower, 2)
    origin = minval(lower, dim=2)
    extent = maxval(upper, dim=2) - origin
    log_sum = 0.0_dp
    do k = 1, n
      log_sum = log_sum + log(max(maxval(upper(:, k) - lower(:, k)), tiny(1.0_dp)))
    end do
    cell = max(exp(log_sum/n), maxval(extent)/2.0e4_dp, tiny(1.0_dp))
    allocate(range(4, n))
    do
      nx = int(extent(1)/cell) + 1
      ny = int(extent(2)/cell) + 1
      cells = int(nx, int64)*ny
      insertions = 0
      do k = 1, n
        range(:, k) = [bin_of(lower(1, k), origin(1), cell, nx), bin_of(upper(1, k), origin(1), cell, nx), &
                       bin_of(lower(2, k), origin(2), cell, ny), bin_of(upper(2, k), origin(2), cell, ny)]
        insertions = insertions + int(range(2, k) - range(1, k) + 1, int64)*(range(4, k) - range(3, k) + 1)
      end do
      if (cells <= 4_int64*n + 16 .and. insertions <= 16_int64*n + 1024) exit
      cell = 2.0_dp*cell
    end do
    allocate(start(cells + 1), fill(cells), items(insertions))
    start = 0
    do k = 1, n
      do iy = range(3, k), range(4, k)
        do ix = range(1, k), range(2, k)
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
    do k = 1, n
      do iy = range(3, k), range(4, k)
        do ix = range(1, k), range(2, k)
          c = iy*nx + ix + 1
          items(fill(c)) = k
          fill(c) = fill(c) + 1
        end do
      end do
    end do
  end subroutine bin_boxes

  !> Horizontal slabs over intervals [low, high] (the same rule as bin_boxes, in one dimension).
  subroutine bin_slabs(low, high, origin, cell, nslab, start, items)
    real(dp), intent(in) :: low(:), high(:)
    real(dp), intent(out) :: origin, cell
    integer, intent(out) :: nslab
    integer, allocatable, intent(out) :: start(:), items(:)
    real(dp), allocatable :: lower(:, :), upper(:, :)
    real(dp) :: origin2(2)
    integer :: nx
    allocate(lower(2, size(low)), upper(2, size(low)))
    lower(1, :) = 0.0_dp
    upper(1, :) = 0.0_dp
    lower(2, :) = low
    upper(2, :) = high
    call bin_boxes(lower, upper, origin2, cell, nx, nslab, start, items)
    origin = origin2(2)
  end subroutine bin_slabs

  !> Bin (0-based) of coordinate x in n bins of size cell from origin (clamped).
  pure integer function bin_of(x, origin, cell, n) result(index)
    real(dp), intent(in) :: x, origin, cell
    integer, intent(in) :: n
    index = min(n - 1, max(0, int((x - origin)/cell)))
  end function bin_of
end module visco2d_overlap_boundary
