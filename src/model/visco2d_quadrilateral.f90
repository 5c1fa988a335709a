!> The geometry of the 4-node quadrilateral shared by the mesh input and the
!> element: the corner and Gauss-point coordinates of the parent square, the
!> bilinear shape functions of eq. [33] and the Jacobian check the mesh input
!> makes on every element. The element itself (stiffness, mass, strains) is
!> visco2d_element in the base.
module visco2d_quadrilateral
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: gauss_count, gauss_xi, gauss_eta, node_xi, node_eta, shape_functions, element_min_jacobian

  integer, parameter :: gauss_count = 4
  real(dp), parameter :: g = 0.577350269189625764509148780501957456_dp  ! 1/sqrt(3)
  !> Gauss points ordered like the nodes: (-,-), (+,-), (+,+), (-,+). Weights are 1.
  real(dp), parameter :: gauss_xi(4) = [-g, g, g, -g]
  real(dp), parameter :: gauss_eta(4) = [-g, -g, g, g]
  real(dp), parameter :: node_xi(4) = [-1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp]
  real(dp), parameter :: node_eta(4) = [-1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp]

contains

  !> Bilinear shape functions N_i = (1 + xi_i xi)(1 + eta_i eta)/4, eq. [33],
  !> and their derivatives dN/dxi (row 1) and dN/deta (row 2).
  pure subroutine shape_functions(xi, eta, n, dn)
    real(dp), intent(in) :: xi, eta
    real(dp), intent(out) :: n(4), dn(2, 4)
    n = 0.25_dp*(1.0_dp + node_xi*xi)*(1.0_dp + node_eta*eta)
    dn(1, :) = 0.25_dp*node_xi*(1.0_dp + node_eta*eta)
    dn(2, :) = 0.25_dp*node_eta*(1.0_dp + node_xi*xi)
  end subroutine shape_functions

  !> Smallest Jacobian determinant over the corners and the Gauss points
  !> (a non-positive value means a distorted or clockwise element).
  pure function element_min_jacobian(xy) result(minimum)
    real(dp), intent(in) :: xy(2, 4)
    real(dp) :: minimum
    real(dp) :: n(4), dn(2, 4), jac(2, 2)
    integer :: i
    minimum = huge(1.0_dp)
    do i = 1, 4
      call shape_functions(node_xi(i), node_eta(i), n, dn)
      jac = matmul(dn, transpose(xy))
      minimum = min(minimum, jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1))
      call shape_functions(gauss_xi(i), gauss_eta(i), n, dn)
      jac = matmul(dn, transpose(xy))
      minimum = min(minimum, jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1))
    end do
  end function element_min_jacobian
end module visco2d_quadrilateral
