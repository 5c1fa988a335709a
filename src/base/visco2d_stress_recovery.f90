!> Stress recovery at the nodes: each element's Gauss-point stresses
!> extrapolated bilinearly to its corners and averaged over the elements
!> that meet at a node (as nodal_average of visco2d_assembly does for all
!> nodes at once).
module visco2d_stress_recovery
  use visco2d_kinds, only: dp
  use visco2d_mesh, only: mesh_t
  use visco2d_element, only: gauss_to_node_extrapolation
  implicit none
  private

  public :: node_stress, node_corners, corner_stress

contains

  !> Nodal stress at one node: Gauss values extrapolated in each element that
  !> has the node, then averaged (the same recovery as nodal_average).
  function node_stress(mesh, stress, node) result(value)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: stress(:, :, :)
    integer, intent(in) :: node
    real(dp) :: value(4)
    value = corner_stress(stress, node_corners(mesh, node))
  end function node_stress

  !> The (corner, element) pairs of the elements that meet at a node: a
  !> search over the mesh, done once so that corner_stress is O(1) per step.
  pure function node_corners(mesh, node) result(corners)
    type(mesh_t), intent(in) :: mesh
    integer, intent(in) :: node
    integer, allocatable :: corners(:, :)
    integer :: e, a, number
    number = count(mesh%connectivity == node)
    allocate(corners(2, number))
    number = 0
    do e = 1, mesh%nelem
      do a = 1, 4
        if (mesh%connectivity(a, e) /= node) cycle
        number = number + 1
        corners(:, number) = [a, e]
      end do
    end do
  end function node_corners

  !> The nodal stress at a node from its corners (node_corners): the bilinear
  !> extrapolation of each element's Gauss stresses, averaged over the elements.
  pure function corner_stress(stress, corners) result(value)
    real(dp), intent(in) :: stress(:, :, :)
    integer, intent(in) :: corners(:, :)
    real(dp) :: value(4)
    real(dp) :: extrapolation(4, 4)
    integer :: k
    extrapolation = gauss_to_node_extrapolation()
    value = 0.0_dp
    do k = 1, size(corners, 2)
      value = value + matmul(stress(:, :, corners(2, k)), extrapolation(:, corners(1, k)))
    end do
    value = value/max(size(corners, 2), 1)
  end function corner_stress
end module visco2d_stress_recovery
