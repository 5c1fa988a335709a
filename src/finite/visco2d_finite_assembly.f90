!> The whole mesh at finite deformation (KINEMATICS LARGE): every element's
!> response at a displacement U (visco2d_finite_solid) gathered into the
!> internal force f(U), the tangent stiffness K_t(U) (band storage), the
!> Cauchy stresses and logarithmic strains at the Gauss points and the
!> stored energy W; and the extremes of the deformation read from the
!> logarithmic strains. The static solve (visco2d_finite_static) and the
!> dynamic step (visco2d_time_step) both evaluate the bodies through it; in
!> the dynamic step the materials that relax (PRONY terms) evaluate Simo's
!> viscoelasticity over the step's interval (finite_memory_t).
module visco2d_finite_assembly
  use visco2d_kinds, only: dp
  use visco2d_mesh, only: mesh_t
  use visco2d_material, only: material_t, has_memory
  use visco2d_model, only: settings_t
  use visco2d_quadrilateral, only: gauss_count
  use visco2d_banded, only: band_matrix_t, band_create, band_add_element
  use visco2d_assembly, only: element_dofs, scatter_add
  use visco2d_finite_solid, only: element_response, viscoelastic_element
  use visco2d_finite_viscoelastic, only: finite_viscoelastic_t, viscoelastic_point_t, finite_viscoelastic_from_material, &
                                         viscoelastic_point_create
  implicit none
  private

  public :: finite_assemble, strain_extremes, general_element
  public :: finite_memory_t, finite_memory_create, memory_points_create

  !> The materials that relax in time (VISCOELASTIC with PRONY terms) at
  !> finite deformation: their laws (visco2d_finite_viscoelastic) and the
  !> interval over which an evaluation advances the histories.
  type :: finite_memory_t
    logical, allocatable :: relaxes(:)                       !< per material
    type(finite_viscoelastic_t), allocatable :: laws(:)      !< per material (used where relaxes)
    real(dp) :: dt = 0.0_dp                                  !< the interval, s
  end type finite_memory_t

contains

  !> The laws of the materials with memory; `any_memory` false when none of
  !> the mesh's materials relaxes (then no history is kept).
  pure subroutine finite_memory_create(mesh, materials, memory, any_memory)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(finite_memory_t), intent(out) :: memory
    logical, intent(out) :: any_memory
    integer :: k
    allocate(memory%relaxes(size(materials)), memory%laws(size(materials)))
    do k = 1, size(materials)
      memory%relaxes(k) = has_memory(materials(k)) .and. any(mesh%element_material == k)
      if (memory%relaxes(k)) memory%laws(k) = finite_viscoelastic_from_material(materials(k))
    end do
    any_memory = any(memory%relaxes)
  end subroutine finite_memory_create

  !> The histories of every Gauss point at rest (no stress has ever acted):
  !> (gauss, nelem), with the terms of its material's law.
  pure function memory_points_create(mesh, memory) result(points)
    type(mesh_t), intent(in) :: mesh
    type(finite_memory_t), intent(in) :: memory
    type(viscoelastic_point_t), allocatable :: points(:, :)
    integer :: e, g
    allocate(points(gauss_count, mesh%nelem))
    do e = 1, mesh%nelem
      if (.not. memory%relaxes(mesh%element_material(e))) cycle
      do g = 1, gauss_count
        points(g, e) = viscoelastic_point_create(memory%laws(mesh%element_material(e)))
      end do
    end do
  end function memory_points_create

  !> Element e's response at the displacement U (element_response), or,
  !> with `memory` and a material that relaxes, its viscoelastic response
  !> over memory%dt from the points' histories `history` into `next`.
  pure subroutine general_element(mesh, materials, settings, e, displacement, with_stiffness, force, stiffness, stress, &
                                  strain, energy, valid, memory, history, next)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    integer, intent(in) :: e
    real(dp), intent(in) :: displacement(:)
    logical, intent(in) :: with_stiffness
    real(dp), intent(out) :: force(8), stiffness(8, 8), stress(4, gauss_count), strain(4, gauss_count), energy
    logical, intent(out) :: valid
    type(finite_memory_t), intent(in), optional :: memory
    type(viscoelastic_point_t), intent(in), optional :: history(:, :)
    type(viscoelastic_point_t), intent(inout), optional :: next(:, :)
    integer :: m
    m = mesh%element_material(e)
    if (present(memory)) then
      if (memory%relaxes(m)) then
        call viscoelastic_element(settings%geometry, settings%formulation, memory%laws(m), &
                                  mesh%xy(:, mesh%connectivity(:, e)), displacement(element_dofs(mesh, e)), memory%dt, &
                                  history(:, e), with_stiffness, force, stiffness, stress, strain, energy, next(:, e), valid)
        return
      end if
    end if
    call element_response(settings%geometry, settings%formulation, materials(m), mesh%xy(:, mesh%connectivity(:, e)), &
                          displacement(element_dofs(mesh, e)), with_stiffness, force, stiffness, stress, strain, energy, &
                          valid)
  end subroutine general_element

  !> f(U), the stresses, the logarithmic strains and W (J, per radian in
  !> axisymmetry) at the displacement U (equation order); with `stiffness`
  !> also K_t(U), created here with the mesh's half-bandwidth. `inverted`:
  !> the first element (its index) inverted or through the axis at U, 0 if
  !> none; when it is not 0 the outputs are incomplete and must not be used.
  subroutine finite_assemble(mesh, materials, settings, displacement, force, stress, strain, energy, inverted, &
                             stiffness, memory, history, next)
    type(mesh_t), intent(in) :: mesh
    type(material_t), intent(in) :: materials(:)
    type(settings_t), intent(in) :: settings
    real(dp), intent(in) :: displacement(:)
    real(dp), intent(out) :: force(:), stress(:, :, :), strain(:, :, :), energy
    integer, intent(out) :: inverted
    type(band_matrix_t), intent(inout), optional :: stiffness
    type(finite_memory_t), intent(in), optional :: memory           !< materials with memory (general_element)
    type(viscoelastic_point_t), intent(in), optional :: history(:, :)
    type(viscoelastic_point_t), intent(inout), optional :: next(:, :)
    real(dp) :: element_force(8), element_stiffness(8, 8), element_energy
    integer :: e
    logical :: valid
    inverted = 0
    force = 0.0_dp
    energy = 0.0_dp
    if (present(stiffness)) call band_create(stiffness, 2*mesh%nnode, mesh%half_bandwidth)
    do e = 1, mesh%nelem
      ! the histories passed on only when given: an absent assumed-shape array of a type with allocatable
      ! components passed on to another optional dummy makes gfortran read its empty descriptor
      if (present(memory) .and. present(history) .and. present(next)) then
        call general_element(mesh, materials, settings, e, displacement, present(stiffness), element_force, &
                             element_stiffness, stress(:, :, e), strain(:, :, e), element_energy, valid, memory, history, &
                             next)
      else
        call general_element(mesh, materials, settings, e, displacement, present(stiffness), element_force, &
                             element_stiffness, stress(:, :, e), strain(:, :, e), element_energy, valid)
      end if
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
    real(dp) :: mean, radius, volumetric, low, high, least
    integer :: e, g
    low = huge(1.0_dp)                              ! the extremes of the logarithms; exp once at the end
    high = -huge(1.0_dp)
    least = huge(1.0_dp)
    do e = 1, size(strain, 3)
      do g = 1, size(strain, 2)
        associate (eps => strain(:, g, e))
        volumetric = eps(1) + eps(2) + eps(3)
        low = min(low, volumetric)
        high = max(high, volumetric)
        mean = 0.5_dp*(eps(1) + eps(2))
        radius = hypot(0.5_dp*(eps(1) - eps(2)), 0.5_dp*eps(4))
        least = min(least, mean - radius, eps(3))
        end associate
      end do
    end do
    volume_ratio_min = exp(low)
    volume_ratio_max = exp(high)
    stretch_min = exp(least)
  end subroutine strain_extremes

end module visco2d_finite_assembly
