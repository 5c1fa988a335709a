!> The whole mesh at finite deformation (KINEMATICS LARGE): every element's
!> response at a displacement U (visco2d_finite_solid) gathered into the
!> internal force f(U), the tangent stiffness K_t(U) (band storage), the
!> Cauchy stresses and logarithmic strains at the Gauss points and the
!> stored energy W; and the extremes of the deformation read from the
!> logarithmic strains. The static solve (visco2d_finite_static) and the
!> dynamic step (visco2d_time_step) both evaluate the bodies through it.
module visco2d_finite_assembly
  use visco2d_kinds, only: dp
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: material_t
  use visco2d_model, only: settings_t
  use visco2d_banded, only: band_matrix_t, band_create, band_add_element
  use visco2d_assembly, only: element_dofs, scatter_add
  use visco2d_finite_solid, only: element_response
  implicit none
  private

  public :: finite_assemble, strain_extremes

contains

  !> f(U), the stresses, the logarithmic strains and W (J, per radian in
  !> axisymmetry) at the displacement U (equation order); with `stiffness`
  !> also K_t(U), created here with the mesh's half-bandwidth. `inverted`:
  !> the first element (its index) inverted or through the axis at U, 0 if
  !> none; when it is not 0 the outputs are incomplete and must not be used.
  subroutine finite_assemble(mesh, materials, settings, displacement, force, stress, strain, energy, inverted, &
                             stiffness)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    real(dp), intent(in) :: displacement(:)
    real(dp), intent(out) :: force(:), stress(:, :, :), strain(:, :, :), energy
    integer, intent(out) :: inverted
    type(band_matrix_t), intent(inout), optional :: stiffness
    real(dp) :: element_force(8), element_stiffness(8, 8), element_energy
    integer :: e
    logical :: valid
    inverted = 0
    force = 0.0_dp
    energy = 0.0_dp
    if (present(stiffness)) call band_create(stiffness, 2*mesh%nnode, mesh%half_bandwidth)
    do e = 1, mesh%nelem
      call element_response(settings%geometry, settings%formulation, materials(mesh%element_material(e)), &
                            mesh%xy(:, mesh%connectivity(:, e)), displacement(element_dofs(mesh, e)), &
                            present(stiffness), element_force, element_stiffness, stress(:, :, e), strain(:, :, e), &
                            element_energy, valid)
      if (.not. valid) then
        inverted = e
        return
      end if
      call scatter_add(mesh, e, element_force, force)
      if (present(stiffness)) call band_add_element(stiffness, element_dofs(mesh, e), element_stiffness)
      energy = energy + element_energy
    end do
  end subroutine finite_assemble

  !> The least and largest volume ratio J and the least principal stretch
  !> over the Gauss points, from the logarithmic strains (rr, zz, tt, rz with
  !> engineering shear): J = exp(tr ln V) exactly, the stretches exp of the
  !> principal logarithmic strains (the in-plane pair and the hoop one).
  pure subroutine strain_extremes(strain, volume_ratio_min, volume_ratio_max, stretch_min)
    real(dp), intent(in) :: strain(:, :, :)
    real(dp), intent(out) :: volume_ratio_min, volume_ratio_max, stretch_min
    real(dp) :: mean, radius, volume_ratio
    integer :: e, g
    volume_ratio_min = huge(1.0_dp)
    volume_ratio_max = -huge(1.0_dp)
    stretch_min = huge(1.0_dp)
    do e = 1, size(strain, 3)
      do g = 1, size(strain, 2)
        associate (eps => strain(:, g, e))
        volume_ratio = exp(eps(1) + eps(2) + eps(3))
        volume_ratio_min = min(volume_ratio_min, volume_ratio)
        volume_ratio_max = max(volume_ratio_max, volume_ratio)
        mean = 0.5_dp*(eps(1) + eps(2))
        radius = hypot(0.5_dp*(eps(1) - eps(2)), 0.5_dp*eps(4))
        stretch_min = min(stretch_min, exp(mean - radius), exp(eps(3)))
        end associate
      end do
    end do
  end subroutine strain_extremes

end module visco2d_finite_assembly
