!> Node renumbering that reduces the half-bandwidth of the banded system
!> (reverse Cuthill-McKee from a pseudo-peripheral start node, per component).
module visco2d_renumber
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_sorting, only: sorted_order
  implicit none
  private

  public :: reverse_cuthill_mckee, half_bandwidth

contains

  !> Half-bandwidth in equations (2 dofs per node, diagonal excluded) of the
  !> system whose node `i` has equation position `position(i)`.
  pure integer function half_bandwidth(connectivity, position) result(width)
    integer, intent(in) :: connectivity(:, :), position(:)
    integer :: e, spread
    width = 0
    do e = 1, size(connectivity, 2)
      spread = maxval(position(connectivity(:, e))) - minval(position(connectivity(:, e)))
      width = max(width, 2*spread + 1)
    end do
  end function half_bandwidth

  !> Reverse Cuthill-McKee: position(i) is the new place of node i (1..nnode).
  subroutine reverse_cuthill_mckee(nnode, connectivity, position)
    integer, intent(in) :: nnode, connectivity(:, :)
    integer, allocatable, intent(out) :: position(:)
    integer, allocatable :: start(:), neighbours(:), degree(:), order(:), level(:)
    integer :: placed, root

    allocate(position(nnode))
    call node_graph(nnode, connectivity, start, neighbours)
    degree = start(2:nnode + 1) - start(1:nnode)
    allocate(order(nnode), level(nnode))
    position = 0
    placed = 0
    do while (placed < nnode)
      root = minloc(degree, dim=1, mask=position == 0)
      root = pseudo_peripheral(root)
      call breadth_first(root, placed)
    end do
    ! Reverse the Cuthill-McKee order.
    order = order(nnode:1:-1)
    position(order) = [(placed, placed = 1, nnode)]

  contains

    !> Cuthill-McKee sweep from root; neighbours taken in increasing degree.
    subroutine breadth_first(first, count)
      integer, intent(in) :: first
      integer, intent(inout) :: count
      integer :: head, node, k, m, candidates(64), ncand
      count = count + 1
      order(count) = first
      position(first) = -1
      head = count
      do while (head <= count)
        node = order(head)
        head = head + 1
        ncand = 0
        do k = start(node), start(node + 1) - 1
          m = neighbours(k)
          if (position(m) /= 0) cycle
          position(m) = -1
          if (ncand < size(candidates)) then
            ncand = ncand + 1
            candidates(ncand) = m
          else
            count = count + 1
            order(count) = m
          end if
        end do
        ! by increasing degree, ties in the order found
        order(count + 1:count + ncand) = candidates(sorted_order(degree(candidates(1:ncand))))
        count = count + ncand
      end do
    end subroutine breadth_first

    !> George-Liu: walk to a node of (nearly) maximal eccentricity.
    integer function pseudo_peripheral(first) result(node)
      integer, intent(in) :: first
      integer :: depth, new_depth, pass, far, farther
      node = first
      depth = level_structure(node, far)
      do pass = 1, 8
        new_depth = level_structure(far, farther)
        if (new_depth <= depth) exit
        node = far
        depth = new_depth
        far = farther
      end do
    end function pseudo_peripheral

    !> Depth of the BFS level structure from origin, and a minimum-degree
    !> node of its last level.
    integer function level_structure(origin, far) result(depth)
      integer, intent(in) :: origin
      integer, intent(out) :: far
      integer, allocatable :: queue(:)
      integer :: head, tail, node, k, m
      allocate(queue(nnode))
      level = -1
      level(origin) = 0
      queue(1) = origin
      head = 1
      tail = 1
      do while (head <= tail)
        node = queue(head)
        head = head + 1
        do k = start(node), start(node + 1) - 1
          m = neighbours(k)
          if (level(m) >= 0) cycle
          level(m) = level(node) + 1
          tail = tail + 1
          queue(tail) = m
        end do
      end do
      depth = level(queue(tail))
      far = queue(tail)
      do k = tail, 1, -1
        if (level(queue(k)) /= depth) exit
        if (degree(queue(k)) < degree(far)) far = queue(k)
      end do
    end function level_structure
  end subroutine reverse_cuthill_mckee

  !> Node adjacency (compressed rows) from element connectivity.
  subroutine node_graph(nnode, connectivity, start, neighbours)
    integer, intent(in) :: nnode, connectivity(:, :)
    integer, allocatable, intent(out) :: start(:), neighbours(:)
    integer, allocatable :: pairs(:, :), order(:)
    integer(int64), allocatable :: keys(:)
    integer :: e, i, j, count, k, nper
    nper = size(connectivity, 1)
    allocate(pairs(2, size(connectivity, 2)*nper*(nper - 1)))
    count = 0
    do e = 1, size(connectivity, 2)
      do i = 1, nper
        do j = 1, nper
          if (i == j) cycle
          if (connectivity(i, e) == connectivity(j, e)) cycle
          count = count + 1
          pairs(:, count) = [connectivity(i, e), connectivity(j, e)]
        end do
      end do
    end do
    ! Sort pairs by (first, second) and drop duplicates.
    allocate(keys(count))
    keys = int(pairs(1, 1:count) - 1, int64)*nnode + pairs(2, 1:count) - 1
    order = sorted_order(keys)
    allocate(start(nnode + 1), neighbours(count))
    start = 0
    k = 0
    do i = 1, count
      if (i > 1) then
        if (keys(order(i)) == keys(order(i - 1))) cycle
      end if
      k = k + 1
      neighbours(k) = pairs(2, order(i))
      start(pairs(1, order(i))) = start(pairs(1, order(i))) + 1
    end do
    ! Counts -> offsets.
    j = 1
    do i = 1, nnode
      e = start(i)
      start(i) = j
      j = j + e
    end do
    start(nnode + 1) = j
    neighbours = neighbours(1:k)
  end subroutine node_graph

end module visco2d_renumber
