!> The element operators of a time-stepping run, computed once: B (or B-bar)
!> at the four Gauss points of every element (eq. [4] through
!> visco2d_element), the integration factors |J| r and the element equation
!> numbers, stored element after element so the step loop streams through
!> them. The geometry does not change (small displacements), so B is the same
!> at every step; this trades 128 reals per element for recomputing the
!> Jacobians twice per element per step.
module visco2d_operators
  use visco2d_kinds, only: dp
  use visco2d_deck, only: deck_t
  use visco2d_element, only: element_b_matrices, gauss_count
  use visco2d_assembly, only: element_dofs
  implicit none
  private

  public :: operators_t, operators_create, operators_element_force, operators_trial_stress

  !> B, |J| r and equation numbers of every element.
  type :: operators_t
    integer :: nelem = 0
    real(dp), allocatable :: b(:, :, :, :)   !< (4, 8, gauss_count, nelem)
    real(dp), allocatable :: weight(:, :)    !< (gauss_count, nelem): |J| r (|J| in plane strain)
    integer, allocatable :: dofs(:, :)       !< (8, nelem): (r1, z1, ..., r4, z4) in band order
  end type operators_t

contains

  !> The operators of the deck's mesh, geometry and formulation.
  subroutine operators_create(deck, operators)
    type(deck_t), intent(in) :: deck
    type(operators_t), intent(out) :: operators
    integer :: e
    associate (mesh => deck%mesh)
    operators%nelem = mesh%nelem
    allocate(operators%b(4, 8, gauss_count, mesh%nelem), operators%weight(gauss_count, mesh%nelem), &
             operators%dofs(8, mesh%nelem))
    do e = 1, mesh%nelem
      call element_b_matrices(deck%settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), operators%b(:, :, :, e), &
                              operators%weight(:, e), deck%settings%formulation)
      operators%dofs(:, e) = element_dofs(mesh, e)
    end do
    end associate
  end subroutine operators_create

  !> Internal nodal forces of one element, sum_g B^T sigma |J| r.
  pure function operators_element_force(operators, e, stress) result(force)
    type(operators_t), intent(in) :: operators
    integer, intent(in) :: e
    real(dp), intent(in) :: stress(4, gauss_count)
    real(dp) :: force(8)
    integer :: g, j
    force = 0.0_dp
    do g = 1, gauss_count
      do j = 1, 8
        force(j) = force(j) + operators%weight(g, e)*dot_product(operators%b(:, j, g, e), stress(:, g))
      end do
    end do
  end function operators_element_force

  !> The step's constitutive pass in one sweep over the elements (each
  !> element's B used while it is in cache): strain increments B du (eq. [4]), trial
  !> stresses stress + D(G, K) increments (eqs. [13], [14]) + history (the
  !> Prony part of eq. [23] over dt, precomputed; absent for elastic
  !> materials), and their internal forces F = sum B^T trial |J| r.
  pure subroutine operators_trial_stress(operators, du, shear, bulk, stress, increments, trial, force, history)
    type(operators_t), intent(in) :: operators
    real(dp), intent(in) :: du(:)
    real(dp), intent(in) :: shear(:), bulk(:)                 !< (nelem) moduli over dt
    real(dp), intent(in) :: stress(:, :, :)                   !< (4, gauss_count, nelem) at t
    real(dp), intent(out) :: increments(:, :, :), trial(:, :, :)
    real(dp), intent(out) :: force(:)
    real(dp), intent(in), optional :: history(:, :, :)       !< (4, gauss_count, nelem)
    real(dp) :: local(8), increment(4), sigma(4), volumetric, element_force(8)
    integer :: e, g, j
    force = 0.0_dp
    do e = 1, operators%nelem
      do j = 1, 8                                   ! not du(dofs(:, e)): that vector subscript allocates a copy
        local(j) = du(operators%dofs(j, e))
      end do
      do g = 1, gauss_count
        increment = operators%b(:, 1, g, e)*local(1)   ! B du (eq. [4]); from the first term: no zeroing call
        do j = 2, 8
          increment = increment + operators%b(:, j, g, e)*local(j)
        end do
        volumetric = increment(1) + increment(2) + increment(3)     ! stress_from_strain, inlined: eqs. [1], [2], [8], [9]
        sigma(1:3) = stress(1:3, g, e) + bulk(e)*volumetric + 2.0_dp*shear(e)*(increment(1:3) - volumetric/3.0_dp)
        sigma(4) = stress(4, g, e) + shear(e)*increment(4)
        if (present(history)) sigma = sigma + history(:, g, e)
        increments(:, g, e) = increment
        trial(:, g, e) = sigma
      end do
      element_force = operators_element_force(operators, e, trial(:, :, e))
      do j = 1, 8                                   ! a loop, not force(dofs) = force(dofs) + ...: no temporary
        force(operators%dofs(j, e)) = force(operators%dofs(j, e)) + element_force(j)
      end do
    end do
  end subroutine operators_trial_stress
end module visco2d_operators
