!> Materials: isotropic elasticity split into deviatoric and volumetric
!> parts (eqs. [1]-[4], [8]-[9]). The viscoelastic-in-shear law of
!> eqs. [10]-[24] extends this type with Prony terms (later module).
module visco2d_material
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: material_t, material_kind_elastic, elastic_matrix, stress_from_strain
  public :: von_mises, max_shear, elastic_constants_from_e_nu

  integer, parameter :: material_kind_elastic = 1

  !> One material of the deck.
  type :: material_t
    character(:), allocatable :: id      !< the id used by MAT= (upper case)
    integer :: kind = material_kind_elastic
    real(dp) :: young = 0.0_dp           !< E, Pa
    real(dp) :: poisson = 0.0_dp         !< nu
    real(dp) :: shear = 0.0_dp           !< G = mu, Pa   (eq. [8])
    real(dp) :: bulk = 0.0_dp            !< K = k, Pa    (eq. [9])
    real(dp) :: density = 0.0_dp         !< rho, kg/m^3
  end type material_t

contains

  !> G and K from E and nu.
  pure subroutine elastic_constants_from_e_nu(young, poisson, shear, bulk)
    real(dp), intent(in) :: young, poisson
    real(dp), intent(out) :: shear, bulk
    shear = young / (2.0_dp*(1.0_dp + poisson))
    bulk = young / (3.0_dp*(1.0_dp - 2.0_dp*poisson))
  end subroutine elastic_constants_from_e_nu

  !> Stress-strain matrix for strain (e_r, e_z, e_theta, gamma_rz) from the split
  !> s_ij = 2 G e_ij (eq. [8]) and sigma = K theta (eq. [9]).
  pure function elastic_matrix(shear, bulk) result(d)
    real(dp), intent(in) :: shear, bulk
    real(dp) :: d(4, 4)
    real(dp) :: diagonal, off_diagonal
    diagonal = bulk + 4.0_dp*shear/3.0_dp
    off_diagonal = bulk - 2.0_dp*shear/3.0_dp
    d = 0.0_dp
    d(1:3, 1:3) = off_diagonal
    d(1, 1) = diagonal
    d(2, 2) = diagonal
    d(3, 3) = diagonal
    d(4, 4) = shear
  end function elastic_matrix

  !> Stress (sigma_r, sigma_z, sigma_theta, tau_rz) from strain, eqs. [1]-[4], [8]-[9].
  pure function stress_from_strain(shear, bulk, strain) result(stress)
    real(dp), intent(in) :: shear, bulk, strain(4)
    real(dp) :: stress(4)
    real(dp) :: volumetric, mean
    volumetric = strain(1) + strain(2) + strain(3)              ! eq. [4]
    mean = bulk*volumetric                                       ! eq. [9]
    stress(1:3) = mean + 2.0_dp*shear*(strain(1:3) - volumetric/3.0_dp)  ! eqs. [1], [2], [8]
    stress(4) = shear*strain(4)                                  ! s_rz = 2 G e_rz, gamma = 2 e_rz
  end function stress_from_strain

  !> von Mises equivalent stress of (sigma_r, sigma_z, sigma_theta, tau_rz).
  pure elemental function von_mises(sr, sz, st, trz) result(value)
    real(dp), intent(in) :: sr, sz, st, trz
    real(dp) :: value
    value = sqrt(0.5_dp*((sr - sz)**2 + (sz - st)**2 + (st - sr)**2) + 3.0_dp*trz**2)
  end function von_mises

  !> Maximum shear stress (sigma_1 - sigma_3)/2 over the three principal stresses.
  pure elemental function max_shear(sr, sz, st, trz) result(value)
    real(dp), intent(in) :: sr, sz, st, trz
    real(dp) :: value, centre, radius, p1, p2
    centre = 0.5_dp*(sr + sz)
    radius = sqrt((0.5_dp*(sr - sz))**2 + trz**2)
    p1 = centre + radius
    p2 = centre - radius
    value = 0.5_dp*(max(p1, p2, st) - min(p1, p2, st))
  end function max_shear
end module visco2d_material
