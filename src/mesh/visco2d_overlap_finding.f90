!> What the overlap tests of a mesh find (visco2d_overlap): the kind of a
!> finding and the elements and nodes concerned.
module visco2d_overlap_finding
  implicit none
  private

  public :: overlap_t
  public :: overlap_none, overlap_same_nodes, overlap_shared_edge, overlap_same_side, overlap_area, &
            overlap_coincident_nodes, overlap_hanging_node

  !> What was found.
  integer, parameter :: overlap_none = 0
  integer, parameter :: overlap_same_nodes = 1        !< two elements with the same four nodes
  integer, parameter :: overlap_shared_edge = 2       !< a side of three or more elements
  integer, parameter :: overlap_same_side = 3         !< two elements on the same side of their common side
  integer, parameter :: overlap_area = 4              !< two elements whose areas intersect
  integer, parameter :: overlap_coincident_nodes = 5  !< two distinct nodes at one point (a crack)
  integer, parameter :: overlap_hanging_node = 6      !< a node inside another element's side

  !> A finding: its kind, the elements (indices) and nodes (indices) concerned.
  !> overlap_hanging_node: elements(1) holds nodes(1), elements(2) the side.
  type :: overlap_t
    integer :: kind = overlap_none
    integer :: elements(3) = 0   !< two elements (three for overlap_shared_edge)
    integer :: nodes(2) = 0      !< the side; the coincident nodes; the hanging node and 0
  end type overlap_t
end module visco2d_overlap_finding
