!> The 4-node quadrilateral at finite deformation (KINEMATICS LARGE),
!> axisymmetric (one radian) or plane strain, 2 x 2 Gauss points, written on
!> the current configuration from the total displacement (an updated-
!> Lagrangian form of the total-Lagrangian state: nothing is carried from
!> step to step but u).
!>
!> At a Gauss point, with X the reference and x = X + u the current nodal
!> coordinates, the in-plane deformation gradient is F = (dx/dxi)(dX/dxi)^-1
!> and the hoop stretch F_33 = r / R (the current over the reference radius;
!> 1 in plane strain). The current gradients dN/dx give the B matrix of the
!> small-strain element evaluated at x (rows d/dr, d/dz, N/r, the
!> engineering shear), dv = det(dx/dxi) r the current volume element (one
!> radian) and dV = det(dX/dxi) R the reference one. The internal force and
!> the tangent stiffness (Bonet and Wood 2008, Nonlinear Continuum Mechanics
!> for Finite Element Analysis, ch. 9, written for the axisymmetric case):
!>
!>   f   = sum_gp B^T sigma dv
!>   K   = sum_gp B^T c B dv  +  K_sigma,
!>   K_sigma(a, b) = sum_gp [ (grad N_a . sigma grad N_b) I_2  +  sigma_tt N_a N_b / r^2 e_r e_r ] dv,
!>
!> sigma the Cauchy stress and c the spatial tangent of the law
!> (visco2d_hyperelastic); the hoop term of K_sigma is the axisymmetric
!> one (the hoop strain u_r / r). With the mean dilatation (FORMULATION
!> BBAR; Nagtegaal, Parks and Rice 1974, Simo, Taylor and Pister 1985) the
!> pressure is that of the element's volume ratio theta = v / V, constant
!> over the element, and the tangent gains U''(theta) / V g g^T with
!> g = dv/dx = sum_gp b_vol dv (b_vol the rows 1 + 2 + 3 of B).
!> test/test_finite.f90 checks K against differences of f and the patch
!> of a homogeneous deformation.
module visco2d_finite_element
  use visco2d_kinds, only: dp, geometry_axisymmetric
  use visco2d_quadrilateral, only: gauss_count, gauss_xi, gauss_eta, shape_functions
  implicit none
  private

  public :: finite_point_t, finite_kinematics, finite_force, finite_tangent, element_volumes

  !> The kinematics of one Gauss point in the current configuration.
  type :: finite_point_t
    real(dp) :: deformation(3, 3) = 0.0_dp  !< F: the in-plane block and the hoop stretch F(3, 3)
    real(dp) :: gradient(3, 3) = 0.0_dp     !< H = F - I from u itself (no cancellation: small strains keep their digits)
    real(dp) :: b(4, 8) = 0.0_dp            !< B at x (d/dr, d/dz, N/r, engineering shear)
    real(dp) :: gradients(2, 4) = 0.0_dp    !< dN_a/dx (row 1: d/dr, row 2: d/dz)
    real(dp) :: shape(4) = 0.0_dp           !< N_a
    real(dp) :: radius = 0.0_dp             !< current r (1 in plane strain, for the hoop term's sake unused)
    real(dp) :: volume = 0.0_dp             !< dv = det(dx/dxi) r, current (per radian in axisymmetry)
    real(dp) :: reference_volume = 0.0_dp   !< dV = det(dX/dxi) R
  end type finite_point_t

contains

  !> The four Gauss points of an element with reference coordinates xy and
  !> nodal displacements (u_r1, u_z1, ...). `valid` is false when the element
  !> is inverted or degenerate in either configuration (det <= 0, or a
  !> current radius <= 0 at a Gauss point): the caller stops with a located
  !> error (or cuts the step), never a stress from it.
  pure subroutine finite_kinematics(geometry, xy, displacement, points, valid)
    integer, intent(in) :: geometry
    real(dp), intent(in) :: xy(2, 4), displacement(8)
    type(finite_point_t), intent(out) :: points(gauss_count)
    logical, intent(out) :: valid
    real(dp) :: current(2, 4), n(4), dn(2, 4), reference_jacobian(2, 2), current_jacobian(2, 2)
    real(dp) :: reference_det, current_det, inverse(2, 2), reference_radius
    integer :: gp, a
    current = xy + reshape(displacement, [2, 4])
    valid = .true.
    do gp = 1, gauss_count
      call shape_functions(gauss_xi(gp), gauss_eta(gp), n, dn)
      reference_jacobian = matmul(dn, transpose(xy))        ! (i, j) = d X_j / d xi_i
      current_jacobian = matmul(dn, transpose(current))     ! (i, j) = d x_j / d xi_i
      reference_det = determinant2(reference_jacobian)
      current_det = determinant2(current_jacobian)
      if (reference_det <= 0.0_dp .or. current_det <= 0.0_dp) then
        valid = .false.
        return
      end if
      associate (p => points(gp))
      p%shape = n
      ! F_ij = d x_i / d X_j = sum_a x_ia dN_a/dX_j: dN/dX = (dX/dxi)^-T dN/dxi
      inverse = inverse2(reference_jacobian, reference_det)
      p%gradient = 0.0_dp
      p%gradient(1:2, 1:2) = matmul(reshape(displacement, [2, 4]), transpose(matmul(inverse, dn)))
      p%deformation = 0.0_dp
      p%deformation(1:2, 1:2) = matmul(current, transpose(matmul(inverse, dn)))
      inverse = inverse2(current_jacobian, current_det)
      p%gradients = matmul(inverse, dn)
      p%b = 0.0_dp
      do a = 1, 4
        p%b(1, 2*a - 1) = p%gradients(1, a)
        p%b(2, 2*a) = p%gradients(2, a)
        p%b(4, 2*a - 1) = p%gradients(2, a)
        p%b(4, 2*a) = p%gradients(1, a)
      end do
      if (geometry == geometry_axisymmetric) then
        reference_radius = dot_product(n, xy(1, :))
        p%radius = dot_product(n, current(1, :))
        if (reference_radius <= 0.0_dp .or. p%radius <= 0.0_dp) then
          valid = .false.
          return
        end if
        p%deformation(3, 3) = p%radius/reference_radius
        p%gradient(3, 3) = dot_product(n, displacement(1:7:2))/reference_radius
        p%b(3, 1:7:2) = n/p%radius
        p%volume = current_det*p%radius
        p%reference_volume = reference_det*reference_radius
      else
        p%radius = 1.0_dp
        p%deformation(3, 3) = 1.0_dp
        p%volume = current_det
        p%reference_volume = reference_det
      end if
      end associate
    end do
  end subroutine finite_kinematics

  !> f = sum_gp B^T sigma dv for the Cauchy stresses (rr, zz, tt, rz) of the points.
  pure function finite_force(points, stress) result(force)
    type(finite_point_t), intent(in) :: points(gauss_count)
    real(dp), intent(in) :: stress(4, gauss_count)
    real(dp) :: force(8)
    integer :: gp
    force = 0.0_dp
    do gp = 1, gauss_count
      force = force + points(gp)%volume*matmul(transpose(points(gp)%b), stress(:, gp))
    end do
  end function finite_force

  !> K = sum_gp (B^T c B + the stress term) dv for the points' Cauchy
  !> stresses and spatial tangents (module comment).
  pure function finite_tangent(geometry, points, stress, tangent) result(stiffness)
    integer, intent(in) :: geometry
    type(finite_point_t), intent(in) :: points(gauss_count)
    real(dp), intent(in) :: stress(4, gauss_count), tangent(4, 4, gauss_count)
    real(dp) :: stiffness(8, 8)
    real(dp) :: in_plane(2, 2), g
    integer :: gp, a, c
    stiffness = 0.0_dp
    do gp = 1, gauss_count
      associate (p => points(gp), s => stress(:, gp))
      stiffness = stiffness + p%volume*matmul(transpose(p%b), matmul(tangent(:, :, gp), p%b))
      in_plane = reshape([s(1), s(4), s(4), s(2)], [2, 2])
      do c = 1, 4
        do a = 1, 4
          g = p%volume*dot_product(p%gradients(:, a), matmul(in_plane, p%gradients(:, c)))
          stiffness(2*a - 1, 2*c - 1) = stiffness(2*a - 1, 2*c - 1) + g
          stiffness(2*a, 2*c) = stiffness(2*a, 2*c) + g
          if (geometry == geometry_axisymmetric) stiffness(2*a - 1, 2*c - 1) = stiffness(2*a - 1, 2*c - 1) + &
            p%volume*s(3)*p%shape(a)*p%shape(c)/p%radius**2
        end do
      end do
      end associate
    end do
  end function finite_tangent

  !> The element's current and reference volumes v = sum dv, V = sum dV and
  !> g = dv/dx = sum_gp b_vol dv (the mean dilatation's volume ratio v / V and its gradient).
  pure subroutine element_volumes(points, current, reference, gradient)
    type(finite_point_t), intent(in) :: points(gauss_count)
    real(dp), intent(out) :: current, reference, gradient(8)
    integer :: gp
    current = 0.0_dp
    reference = 0.0_dp
    gradient = 0.0_dp
    do gp = 1, gauss_count
      current = current + points(gp)%volume
      reference = reference + points(gp)%reference_volume
      gradient = gradient + points(gp)%volume*(points(gp)%b(1, :) + points(gp)%b(2, :) + points(gp)%b(3, :))
    end do
  end subroutine element_volumes

  pure real(dp) function determinant2(a)
    real(dp), intent(in) :: a(2, 2)
    determinant2 = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
  end function determinant2

  pure function inverse2(a, det) result(inverse)
    real(dp), intent(in) :: a(2, 2), det
    real(dp) :: inverse(2, 2)
    inverse(1, 1) = a(2, 2)/det
    inverse(1, 2) = -a(1, 2)/det
    inverse(2, 1) = -a(2, 1)/det
    inverse(2, 2) = a(1, 1)/det
  end function inverse2
end module visco2d_finite_element
