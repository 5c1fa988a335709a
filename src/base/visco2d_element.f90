!> The 4-node isoparametric quadrilateral, axisymmetric (one radian, eq. [32])
!> or plane strain (unit thickness), with 2x2 Gauss integration.
!> Strain vector: (e_r, e_z, e_theta = u_r/r, gamma_rz); nodal dofs (u_r, u_z).
!> All kernels are pure: they see one element's coordinates and nothing else.
!> The optional `formulation` selects the legacy element (default) or B-bar:
!> the volumetric row sum of B replaced, at every Gauss point, by its
!> r-weighted element mean (mean dilatation), which removes volumetric
!> locking for nearly incompressible materials (Hughes 1980).
module visco2d_element
  use visco2d_kinds, only: dp, geometry_axisymmetric, formulation_bbar
  use visco2d_quadrilateral, only: gauss_count, gauss_xi, gauss_eta, node_xi, node_eta, shape_functions, &
                                   element_min_jacobian
  implicit none
  private

  public :: gauss_count, gauss_xi, gauss_eta
  public :: shape_functions, strain_displacement, element_b_matrices, element_stiffness, element_lumped_mass
  public :: element_strains, element_internal_force, edge_pressure_load
  public :: element_gauss_points, element_min_jacobian, gauss_to_node_extrapolation

contains

  !> Strain-displacement matrix B at (xi, eta), the Jacobian determinant,
  !> the radius r = sum R_i N_i and the integration factor |J| r (|J| in plane strain).
  pure subroutine strain_displacement(geometry, xy, xi, eta, b, detj, radius, factor)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xy(2, 4), xi, eta
    real(dp), intent(out) :: b(4, 8), detj, radius, factor
    real(dp) :: n(4), dn(2, 4), jac(2, 2), inverse(2, 2), dxy(2, 4)
    integer :: i
    call shape_functions(xi, eta, n, dn)
    jac = matmul(dn, transpose(xy))          ! jac(i,j) = d x_j / d xi_i
    detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
    radius = dot_product(n, xy(1, :))
    b = 0.0_dp
    if (detj <= 0.0_dp) then
      factor = 0.0_dp
      return
    end if
    inverse(1, 1) = jac(2, 2)/detj
    inverse(1, 2) = -jac(1, 2)/detj
    inverse(2, 1) = -jac(2, 1)/detj
    inverse(2, 2) = jac(1, 1)/detj
    dxy = matmul(inverse, dn)                ! row 1: dN/dr, row 2: dN/dz
    do i = 1, 4
      b(1, 2*i - 1) = dxy(1, i)
      b(2, 2*i) = dxy(2, i)
      b(4, 2*i - 1) = dxy(2, i)
      b(4, 2*i) = dxy(1, i)
    end do
    if (geometry == geometry_axisymmetric) then
      b(3, 1:7:2) = n/radius                 ! e_theta = u_r / r (r > 0 at Gauss points)
      factor = detj*radius                   ! one radian, eq. [32]
    else
      factor = detj
    end if
  end subroutine strain_displacement

  !> B at the four Gauss points and their integration factors |J| r. With
  !> formulation = formulation_bbar, B-bar: B + (1/3) m (bvol_mean - bvol),
  !> m = (1, 1, 1, 0), bvol = rows 1 + 2 + 3 of B, bvol_mean its mean weighted
  !> by |J| r, so the volumetric strain is constant in the element.
  pure subroutine element_b_matrices(geometry, xy, b, factor, formulation)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xy(2, 4)
    real(dp), intent(out) :: b(4, 8, gauss_count), factor(gauss_count)
    integer, intent(in), optional :: formulation
    real(dp) :: detj, radius, volumetric(8, gauss_count), mean(8)
    integer :: gp, row
    do gp = 1, gauss_count
      call strain_displacement(geometry, xy, gauss_xi(gp), gauss_eta(gp), b(:, :, gp), detj, radius, factor(gp))
    end do
    if (.not. present(formulation)) return
    if (formulation /= formulation_bbar .or. sum(factor) <= 0.0_dp) return
    mean = 0.0_dp
    do gp = 1, gauss_count
      volumetric(:, gp) = b(1, :, gp) + b(2, :, gp) + b(3, :, gp)
      mean = mean + factor(gp)*volumetric(:, gp)
    end do
    mean = mean/sum(factor)
    do gp = 1, gauss_count
      do row = 1, 3
        b(row, :, gp) = b(row, :, gp) + (mean - volumetric(:, gp))/3.0_dp
      end do
    end do
  end subroutine element_b_matrices

  !> Element stiffness k = sum_gp B^T D B |J| r for a constant D.
  pure function element_stiffness(geometry, xy, d, formulation) result(k)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xy(2, 4), d(4, 4)
    integer, intent(in), optional :: formulation
    real(dp) :: k(8, 8)
    real(dp) :: b(4, 8, gauss_count), factor(gauss_count)
    integer :: gp
    call element_b_matrices(geometry, xy, b, factor, formulation)
    k = 0.0_dp
    do gp = 1, gauss_count
      k = k + factor(gp)*matmul(transpose(b(:, :, gp)), matmul(d, b(:, :, gp)))
    end do
  end function element_stiffness

  !> Lumped mass per node: row sums of the consistent mass of eq. [32],
  !> m_i = rho * integral N_i r |J| dxi deta (the same for both dofs of the node).
  pure function element_lumped_mass(geometry, xy, density) result(m)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xy(2, 4), density
    real(dp) :: m(4)
    real(dp) :: b(4, 8), detj, radius, factor, n(4), dn(2, 4)
    integer :: gp
    m = 0.0_dp
    do gp = 1, gauss_count
      call strain_displacement(geometry, xy, gauss_xi(gp), gauss_eta(gp), b, detj, radius, factor)
      call shape_functions(gauss_xi(gp), gauss_eta(gp), n, dn)
      m = m + density*factor*n             ! sum_j N_i N_j = N_i
    end do
  end function element_lumped_mass

  !> Strains at the four Gauss points from the element displacements (u_r1, u_z1, ...).
  pure function element_strains(geometry, xy, displacement, formulation) result(strain)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xy(2, 4), displacement(8)
    integer, intent(in), optional :: formulation
    real(dp) :: strain(4, gauss_count)
    real(dp) :: b(4, 8, gauss_count), factor(gauss_count)
    integer :: gp
    call element_b_matrices(geometry, xy, b, factor, formulation)
    do gp = 1, gauss_count
      strain(:, gp) = matmul(b(:, :, gp), displacement)
    end do
  end function element_strains

  !> Internal nodal forces f = sum_gp B^T sigma |J| r.
  pure function element_internal_force(geometry, xy, stress, formulation) result(f)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xy(2, 4), stress(4, gauss_count)
    integer, intent(in), optional :: formulation
    real(dp) :: f(8)
    real(dp) :: b(4, 8, gauss_count), factor(gauss_count)
    integer :: gp
    call element_b_matrices(geometry, xy, b, factor, formulation)
    f = 0.0_dp
    do gp = 1, gauss_count
      f = f + factor(gp)*matmul(transpose(b(:, :, gp)), stress(:, gp))
    end do
  end function element_internal_force

  !> Consistent nodal forces (f_ra, f_za, f_rb, f_zb) of a uniform normal pressure p
  !> (positive = compressive, pushing into the body) on the straight edge a -> b
  !> of a counter-clockwise element. Two-point Gauss rule, r-weighted in axisymmetry.
  pure function edge_pressure_load(geometry, xa, xb, pressure) result(f)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xa(2), xb(2), pressure
    real(dp) :: f(4)
    real(dp) :: tangent(2), normal(2), length, s, na, nb, radius, weight
    integer :: gp
    tangent = xb - xa
    length = norm2(tangent)
    normal = [tangent(2), -tangent(1)]/length   ! outward for a counter-clockwise element
    f = 0.0_dp
    do gp = 1, 2
      s = merge(gauss_eta(1), gauss_eta(3), gp == 1)   ! -+1/sqrt(3)
      na = 0.5_dp*(1.0_dp - s)
      nb = 0.5_dp*(1.0_dp + s)
      radius = na*xa(1) + nb*xb(1)
      weight = 0.5_dp*length
      if (geometry == geometry_axisymmetric) weight = weight*radius
      f(1:2) = f(1:2) - pressure*normal*na*weight
      f(3:4) = f(3:4) - pressure*normal*nb*weight
    end do
  end function edge_pressure_load

  !> (r, z) of the four Gauss points.
  pure function element_gauss_points(xy) result(points)
    real(dp), intent(in) :: xy(2, 4)
    real(dp) :: points(2, gauss_count)
    real(dp) :: n(4), dn(2, 4)
    integer :: gp
    do gp = 1, gauss_count
      call shape_functions(gauss_xi(gp), gauss_eta(gp), n, dn)
      points(:, gp) = matmul(xy, n)
    end do
  end function element_gauss_points

  !> Matrix E with node_values = matmul(gauss_values, E): bilinear extrapolation
  !> from the Gauss points (at +-1/sqrt(3)) to the corner nodes.
  pure function gauss_to_node_extrapolation() result(e)
    real(dp) :: e(gauss_count, 4)
    real(dp) :: n(4), dn(2, 4)
    integer :: node
    do node = 1, 4
      ! A node sits at (xi, eta) = sqrt(3) * (+-1, +-1) in the Gauss-point frame.
      call shape_functions(node_xi(node)*sqrt(3.0_dp), node_eta(node)*sqrt(3.0_dp), n, dn)
      e(:, node) = n
    end do
  end function gauss_to_node_extrapolation
end module visco2d_element
