!> One element's response at finite deformation: its hyperelastic law at
!> the Gauss points (visco2d_hyperelastic), pointwise or with the mean
!> dilatation (FORMULATION BBAR), through the current-configuration element
!> of visco2d_finite_element: internal force, tangent stiffness, Cauchy
!> stresses, logarithmic strains and the stored energy.
!>
!> A HYPERFOAM material is visco2d_hyperfoam's law, pointwise (a foam is
!> compressible: the mean dilatation is for the nearly incompressible flesh).
!> An ELASTIC material under KINEMATICS LARGE is the neo-Hookean law of its
!> own G and K (C10 = G / 2, D1 = 2 / K): the same small-strain limit, and
!> unlike the St Venant-Kirchhoff extension of Hooke's law it does not
!> soften in compression.
module visco2d_finite_solid
  use visco2d_kinds, only: dp, formulation_bbar
  use visco2d_material, only: material_t, hyperelastic_none, hyperelastic_neo_hooke, hyperelastic_mooney_rivlin, &
                              hyperelastic_foam
  use visco2d_quadrilateral, only: gauss_count
  use visco2d_hyperelastic, only: hyperelastic_t, hyperelastic_from_moduli, isochoric_response, volumetric_response, &
                                  hyperelastic_response, pressure_tangent, volume_change
  use visco2d_finite_element, only: finite_point_t, finite_kinematics, finite_force, finite_tangent, element_volumes
  use visco2d_hyperfoam, only: hyperfoam_t, hyperfoam_response
  use visco2d_finite_viscoelastic, only: finite_viscoelastic_t, viscoelastic_point_t, viscoelastic_response, &
                                         viscoelastic_isochoric_response
  implicit none
  private

  public :: element_response, law_of_material, logarithmic_strain, viscoelastic_element

contains

  !> The neo-Hookean or Mooney-Rivlin constants of a material (module comment for ELASTIC).
  pure function law_of_material(material) result(law)
    type(material_t), intent(in) :: material
    type(hyperelastic_t) :: law
    select case (material%hyperelastic)
    case (hyperelastic_neo_hooke, hyperelastic_mooney_rivlin)
      law%c10 = material%c10
      law%c01 = material%c01
      law%d1 = material%d1
    case default
      law = hyperelastic_from_moduli(material%shear, material%bulk)
    end select
  end function law_of_material

  !> The element at displacement u (u_r1, u_z1, ...) of its reference
  !> coordinates xy: internal force f (8), tangent K (8 x 8, when
  !> `with_stiffness`), Cauchy stresses and logarithmic strains at the Gauss
  !> points (rr, zz, tt, rz; engineering shear), and W integrated over the
  !> reference volume (J, per radian in axisymmetry). `valid` false: an
  !> element inverted or through the axis, nothing else is set.
  pure subroutine element_response(geometry, formulation, material, xy, displacement, with_stiffness, &
                                   force, stiffness, stress, strain, energy, valid)
    integer, intent(in) :: geometry, formulation
    type(material_t), intent(in) :: material
    real(dp), intent(in) :: xy(2, 4), displacement(8)
    logical, intent(in) :: with_stiffness
    real(dp), intent(out) :: force(8), stiffness(8, 8), stress(4, gauss_count), strain(4, gauss_count), energy
    logical, intent(out) :: valid
    type(finite_point_t) :: points(gauss_count)
    type(hyperelastic_t) :: law
    real(dp) :: tangent(4, 4, gauss_count), point_energy, reference, gradient(8), pressure, slope
    integer :: gp
    logical :: mean_dilatation
    force = 0.0_dp
    stiffness = 0.0_dp
    stress = 0.0_dp
    strain = 0.0_dp
    energy = 0.0_dp
    call finite_kinematics(geometry, xy, displacement, points, valid)
    if (.not. valid) return
    if (material%hyperelastic == hyperelastic_foam) then     ! compressible: pointwise, whatever FORMULATION says
      call foam_element(geometry, material, points, with_stiffness, force, stiffness, stress, strain, energy, valid)
      return
    end if
    law = law_of_material(material)
    mean_dilatation = formulation == formulation_bbar
    slope = 0.0_dp                                  ! (used with the mean dilatation only)
    reference = 1.0_dp
    gradient = 0.0_dp
    if (mean_dilatation) call mean_pressure(law, points, pressure, slope, energy, reference, gradient)
    do gp = 1, gauss_count
      if (mean_dilatation) then
        call isochoric_response(law, points(gp)%deformation, stress(:, gp), tangent(:, :, gp), point_energy, &
                                points(gp)%gradient)
        stress(1:3, gp) = stress(1:3, gp) + pressure
        tangent(:, :, gp) = tangent(:, :, gp) + pressure_tangent(pressure)
      else
        call hyperelastic_response(law, points(gp)%deformation, stress(:, gp), tangent(:, :, gp), point_energy, &
                                   points(gp)%gradient)
      end if
      energy = energy + points(gp)%reference_volume*point_energy
      strain(:, gp) = logarithmic_strain(points(gp)%deformation)
    end do
    call element_forces(geometry, points, stress, tangent, with_stiffness, mean_dilatation, slope, reference, gradient, &
                        force, stiffness)
  end subroutine element_response

  !> The mean dilatation's pressure of an element (FORMULATION BBAR): the
  !> volumetric law at the element's volume ratio theta = v / V, with
  !> theta - 1 = sum (J - 1) dV / V (J - 1 from H keeps small strains' digits);
  !> its slope, the volumetric energy (J, per radian), V and d v / d u.
  pure subroutine mean_pressure(law, points, pressure, slope, energy, reference, gradient)
    type(hyperelastic_t), intent(in) :: law
    type(finite_point_t), intent(in) :: points(gauss_count)
    real(dp), intent(out) :: pressure, slope, energy, reference, gradient(8)
    real(dp) :: current, change, volumetric_energy
    integer :: gp
    call element_volumes(points, current, reference, gradient)
    change = 0.0_dp
    do gp = 1, gauss_count
      change = change + volume_change(points(gp)%gradient)*points(gp)%reference_volume
    end do
    call volumetric_response(law, current/reference, pressure, slope, volumetric_energy, change/reference)
    energy = reference*volumetric_energy
  end subroutine mean_pressure

  !> The element's force from the points' stresses and, when wanted, its
  !> tangent stiffness (with the mean dilatation's term slope / V dv/du dv/du).
  pure subroutine element_forces(geometry, points, stress, tangent, with_stiffness, mean_dilatation, slope, reference, &
                                 gradient, force, stiffness)
    integer, intent(in) :: geometry
    type(finite_point_t), intent(in) :: points(gauss_count)
    real(dp), intent(in) :: stress(4, gauss_count), tangent(4, 4, gauss_count), slope, reference, gradient(8)
    logical, intent(in) :: with_stiffness, mean_dilatation
    real(dp), intent(inout) :: force(8), stiffness(8, 8)
    force = finite_force(points, stress)
    if (.not. with_stiffness) return
    stiffness = finite_tangent(geometry, points, stress, tangent)
    if (mean_dilatation) stiffness = stiffness + slope/reference*spread(gradient, 2, 8)*spread(gradient, 1, 8)
  end subroutine element_forces

  !> element_response for a material with memory (VISCOELASTIC with PRONY
  !> terms) over a step dt from the points' histories `history_in`: Simo's
  !> finite-strain viscoelasticity (visco2d_finite_viscoelastic), pointwise
  !> or with the mean dilatation (the isochoric part at the points, the
  !> elastic pressure of the element's volume ratio); the histories at the
  !> end of the step into `history_out`. The energy is the law's stored
  !> energy at the step's end.
  pure subroutine viscoelastic_element(geometry, formulation, law, xy, displacement, dt, history_in, with_stiffness, &
                                       force, stiffness, stress, strain, energy, history_out, valid)
    integer, intent(in) :: geometry, formulation
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: xy(2, 4), displacement(8), dt
    type(viscoelastic_point_t), intent(in) :: history_in(gauss_count)
    logical, intent(in) :: with_stiffness
    real(dp), intent(out) :: force(8), stiffness(8, 8), stress(4, gauss_count), strain(4, gauss_count), energy
    type(viscoelastic_point_t), intent(inout) :: history_out(gauss_count)
    logical, intent(out) :: valid
    type(finite_point_t) :: points(gauss_count)
    real(dp) :: tangent(4, 4, gauss_count), point_energy, reference, gradient(8), pressure, slope
    integer :: gp
    logical :: mean_dilatation
    force = 0.0_dp
    stiffness = 0.0_dp
    stress = 0.0_dp
    strain = 0.0_dp
    energy = 0.0_dp
    call finite_kinematics(geometry, xy, displacement, points, valid)
    if (.not. valid) return
    mean_dilatation = formulation == formulation_bbar
    slope = 0.0_dp                                  ! (used with the mean dilatation only)
    reference = 1.0_dp
    gradient = 0.0_dp
    if (mean_dilatation) call mean_pressure(law%instantaneous, points, pressure, slope, energy, reference, gradient)
    do gp = 1, gauss_count
      if (mean_dilatation) then
        call viscoelastic_isochoric_response(law, dt, points(gp)%deformation, history_in(gp), stress(:, gp), &
                                             tangent(:, :, gp), history_out(gp), point_energy, points(gp)%gradient)
        stress(1:3, gp) = stress(1:3, gp) + pressure
        tangent(:, :, gp) = tangent(:, :, gp) + pressure_tangent(pressure)
      else
        call viscoelastic_response(law, dt, points(gp)%deformation, history_in(gp), stress(:, gp), tangent(:, :, gp), &
                                   history_out(gp), point_energy, points(gp)%gradient)
      end if
      energy = energy + points(gp)%reference_volume*point_energy
      strain(:, gp) = logarithmic_strain(points(gp)%deformation)
    end do
    call element_forces(geometry, points, stress, tangent, with_stiffness, mean_dilatation, slope, reference, gradient, &
                        force, stiffness)
  end subroutine viscoelastic_element

  !> element_response for a HYPERFOAM material: visco2d_hyperfoam's law at
  !> every point; a point it cannot take (an overflow at an extreme
  !> compression) makes the element invalid.
  pure subroutine foam_element(geometry, material, points, with_stiffness, force, stiffness, stress, strain, energy, &
                               valid)
    integer, intent(in) :: geometry
    type(material_t), intent(in) :: material
    type(finite_point_t), intent(in) :: points(gauss_count)
    logical, intent(in) :: with_stiffness
    real(dp), intent(inout) :: force(8), stiffness(8, 8), stress(4, gauss_count), strain(4, gauss_count), energy
    logical, intent(out) :: valid
    type(hyperfoam_t) :: foam
    real(dp) :: tangent(4, 4, gauss_count), point_energy
    integer :: gp
    logical :: admissible
    foam%mu = material%foam_mu
    foam%alpha = material%foam_alpha
    foam%nu = material%foam_nu
    valid = .true.
    do gp = 1, gauss_count
      if (with_stiffness) then
        call hyperfoam_response(foam, points(gp)%deformation, stress(:, gp), tangent(:, :, gp), point_energy, &
                                admissible)
      else                                          ! the stress alone: no tangent to compute
        call hyperfoam_response(foam, points(gp)%deformation, stress(:, gp), energy=point_energy, &
                                admissible=admissible)
      end if
      if (.not. admissible) then
        valid = .false.
        return
      end if
      energy = energy + points(gp)%reference_volume*point_energy
      strain(:, gp) = logarithmic_strain(points(gp)%deformation)
    end do
    force = finite_force(points, stress)
    if (with_stiffness) stiffness = finite_tangent(geometry, points, stress, tangent)
  end subroutine foam_element

  !> The logarithmic (Hencky) strain ln V = 1/2 ln(F F^T) of an in-plane F
  !> with a hoop stretch, as (rr, zz, tt, 2 rz): the in-plane block from the
  !> eigenvalues and vectors of its 2 x 2 left Cauchy-Green tensor.
  pure function logarithmic_strain(deformation) result(strain)
    real(dp), intent(in) :: deformation(3, 3)
    real(dp) :: strain(4)
    real(dp) :: b(2, 2), mean, radius, lambda1, lambda2, c, s, angle, h1, h2
    b = matmul(deformation(1:2, 1:2), transpose(deformation(1:2, 1:2)))
    mean = 0.5_dp*(b(1, 1) + b(2, 2))
    radius = hypot(0.5_dp*(b(1, 1) - b(2, 2)), b(1, 2))
    lambda1 = mean + radius
    lambda2 = mean - radius
    angle = 0.5_dp*atan2(2.0_dp*b(1, 2), b(1, 1) - b(2, 2))
    c = cos(angle)
    s = sin(angle)
    h1 = 0.5_dp*log(lambda1)
    h2 = 0.5_dp*log(lambda2)
    strain(1) = h1*c*c + h2*s*s
    strain(2) = h1*s*s + h2*c*c
    strain(3) = log(deformation(3, 3))
    strain(4) = 2.0_dp*(h1 - h2)*c*s
  end function logarithmic_strain
end module visco2d_finite_solid
