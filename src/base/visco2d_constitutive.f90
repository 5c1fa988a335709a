!> The constitutive update shared by the quasi-static and the dynamic step
!> loops: the history stress s0 of eq. [23] at every Gauss point, and the
!> history update of eq. [24] once a step's strain increments stand. The
!> trial stress sigma_t + D(mu, K) de + s0 (eqs. [13], [14]) is formed by
!> each loop where it also forms the internal force (element_internal_force
!> in the quasi-static loop, operators_trial_stress in the dynamic one).
module visco2d_constitutive
  use visco2d_kinds, only: dp
  use visco2d_material, only: material_t
  use visco2d_element, only: gauss_count
  use visco2d_viscoelastic, only: step_coefficients_t, viscoelastic_state_t, element_terms, deviatoric_part, &
                                  history_stress, update_history
  implicit none
  private

  public :: history_stresses, commit_history

contains

  !> s0 of eq. [23] at every Gauss point over the step of `coefficients`
  !> (one per material), 0 in the elements without memory.
  subroutine history_stresses(materials, element_material, state, coefficients, s0)
    type(material_t), intent(in) :: materials(:)
    integer, intent(in) :: element_material(:)
    type(viscoelastic_state_t), intent(in) :: state
    type(step_coefficients_t), intent(in) :: coefficients(:)
    real(dp), intent(out) :: s0(:, :, :)                     !< (4, gauss_count, nelem)
    integer :: e, g, nterm, slot
    s0 = 0.0_dp
    do e = 1, size(element_material)
      nterm = element_terms(state, e)
      if (nterm == 0) cycle
      associate (material => materials(element_material(e)), c => coefficients(element_material(e)))
      do g = 1, gauss_count
        slot = state%first(e) + (g - 1)*nterm
        s0(:, g, e) = history_stress(material, c, state%history(:, slot:slot + nterm - 1))
      end do
      end associate
    end do
  end subroutine history_stresses

  !> Eq. [24]: every history after the strain increments of the step of
  !> `coefficients` (one per material).
  subroutine commit_history(element_material, state, coefficients, increments)
    integer, intent(in) :: element_material(:)
    type(viscoelastic_state_t), intent(inout) :: state
    type(step_coefficients_t), intent(in) :: coefficients(:)
    real(dp), intent(in) :: increments(:, :, :)              !< (4, gauss_count, nelem) strain increments
    real(dp) :: deviatoric(4), volumetric
    integer :: e, g, nterm, slot
    do e = 1, size(element_material)
      nterm = element_terms(state, e)
      if (nterm == 0) cycle
      do g = 1, gauss_count
        slot = state%first(e) + (g - 1)*nterm
        call deviatoric_part(increments(:, g, e), deviatoric, volumetric)
        call update_history(coefficients(element_material(e)), deviatoric, state%history(:, slot:slot + nterm - 1))
      end do
    end do
  end subroutine commit_history
end module visco2d_constitutive
