!> The incremental viscoelastic constitutive update of the legacy program,
!> eqs. [13]-[24]: viscoelastic in shear, elastic in bulk.
!>
!> Over a step of length dt the deviatoric strain is taken linear in time.
!> Then, exactly for each Prony term m (G_m, beta_m, x_m = beta_m dt):
!>   J_m   = (1 - exp(-x_m))/x_m                               eq. [22]
!>   mu    = G_inf + sum_m G_m J_m                               eq. [21]
!>   s0    = 2 sum_m G_m (exp(-x_m) - 1) C_m                     eq. [23], corrected
!>   ds    = 2 mu de + s0,   dsigma = K dtheta                   eqs. [13], [14]
!>   C_m  <- exp(-x_m) C_m + J_m de                              eq. [24]
!> As printed, eq. [23] has lost the "- 1" (doc/equations.md, errata): without it a
!> step strain would not relax. C_m is the history of term m, one vector
!> (e_r, e_z, e_theta, gamma_rz) per Gauss point, stored only for elements
!> whose material has memory (beta > 0). Shear components carry the
!> engineering strain gamma_rz = 2 e_rz, so s_rz = mu gamma_rz.
module visco2d_viscoelastic
  use visco2d_kinds, only: dp
  use visco2d_material, only: material_t, has_memory
  implicit none
  private

  public :: relaxation_integral, exp_minus_one
  public :: step_coefficients_t, step_coefficients
  public :: viscoelastic_state_t, viscoelastic_state_create, element_terms
  public :: deviatoric_part, deviatoric_stress, history_stress, update_history, stored_energy_density

  !> The per-step constants of one material for a step length dt.
  type :: step_coefficients_t
    real(dp) :: dt = -1.0_dp                 !< s, the step they were computed for
    real(dp) :: shear = 0.0_dp               !< mu_n, eq. [21], Pa
    real(dp) :: bulk = 0.0_dp                !< K, Pa
    real(dp), allocatable :: decay_minus_one(:)  !< exp(-beta_m dt) - 1, computed without cancellation
    real(dp), allocatable :: integral(:)     !< J_m, eq. [22]
  end type step_coefficients_t

  !> History C_m of every Gauss point of every element with memory.
  !> Element e owns slots first(e) .. first(e+1)-1: 4 Gauss points x its terms,
  !> slot = first(e) + (gauss - 1) nterm(e) + m - 1. Elastic elements own none.
  type :: viscoelastic_state_t
    integer, allocatable :: first(:)          !< (nelem + 1)
    real(dp), allocatable :: history(:, :)    !< (4, nslot): (e_r, e_z, e_theta, gamma_rz) per slot
  end type viscoelastic_state_t

contains

  !> exp(y) - 1 without cancellation for small |y| (Kahan's trick, with a
  !> series below 1e-5; Fortran 2008 has no expm1 intrinsic).
  pure elemental real(dp) function exp_minus_one(y) result(value)
    real(dp), intent(in) :: y
    real(dp) :: u
    if (abs(y) < 1.0e-5_dp) then
      value = y*(1.0_dp + y/2.0_dp*(1.0_dp + y/3.0_dp*(1.0_dp + y/4.0_dp)))
      return
    end if
    u = exp(y)
    if (u == 0.0_dp) then
      value = -1.0_dp
    else if (u > huge(u)) then
      value = u
    else
      value = (u - 1.0_dp)*y/log(u)
    end if
  end function exp_minus_one

  !> J(x) = (1 - exp(-x))/x, eq. [22], for x = beta dt >= 0: 1 at x = 0,
  !> no cancellation for tiny x, 1/x (no overflow) for huge x.
  pure elemental real(dp) function relaxation_integral(x) result(value)
    real(dp), intent(in) :: x
    if (x == 0.0_dp) then
      value = 1.0_dp
    else
      value = -exp_minus_one(-x)/x
    end if
  end function relaxation_integral

  !> Constants of a material for a step dt (dt = 0: the instantaneous response, mu = G(0)).
  pure function step_coefficients(material, dt) result(coefficients)
    type(material_t), intent(in) :: material
    real(dp), intent(in) :: dt
    type(step_coefficients_t) :: coefficients
    real(dp), allocatable :: x(:)
    coefficients%dt = dt
    coefficients%bulk = material%bulk
    coefficients%shear = material%long_term_shear
    if (.not. has_memory(material)) then
      allocate(coefficients%decay_minus_one(0), coefficients%integral(0))
      return
    end if
    x = material%prony_rate*dt
    coefficients%integral = relaxation_integral(x)                      ! eq. [22]
    coefficients%decay_minus_one = -x*coefficients%integral              ! exp(-x) - 1
    coefficients%shear = coefficients%shear + sum(material%prony_shear*coefficients%integral)  ! eq. [21]
  end function step_coefficients

  !> Number of Prony terms with memory of element e's material.
  pure integer function element_terms(state, e)
    type(viscoelastic_state_t), intent(in) :: state
    integer, intent(in) :: e
    element_terms = (state%first(e + 1) - state%first(e))/4
  end function element_terms

  !> History storage for the elements whose material has memory; zero initial history.
  subroutine viscoelastic_state_create(materials, element_material, state)
    type(material_t), intent(in) :: materials(:)
    integer, intent(in) :: element_material(:)
    type(viscoelastic_state_t), intent(out) :: state
    integer :: e, nterm
    allocate(state%first(size(element_material) + 1))
    state%first(1) = 1
    do e = 1, size(element_material)
      nterm = 0
      if (has_memory(materials(element_material(e)))) nterm = size(materials(element_material(e))%prony_rate)
      state%first(e + 1) = state%first(e) + 4*nterm
    end do
    allocate(state%history(4, state%first(size(element_material) + 1) - 1))
    state%history = 0.0_dp
  end subroutine viscoelastic_state_create

  !> Deviatoric strain (e_r, e_z, e_theta, gamma_rz) and volumetric strain, eqs. [2], [4].
  pure subroutine deviatoric_part(strain, deviatoric, volumetric)
    real(dp), intent(in) :: strain(4)
    real(dp), intent(out) :: deviatoric(4), volumetric
    volumetric = strain(1) + strain(2) + strain(3)
    deviatoric(1:3) = strain(1:3) - volumetric/3.0_dp
    deviatoric(4) = strain(4)
  end subroutine deviatoric_part

  !> The strain energy stored in the springs per unit volume, J/m^3, at one
  !> Gauss point of strain `strain` and histories `history` (4, one column
  !> per Prony term; none for an elastic material):
  !>   K theta^2/2 + G_inf e:e + sum_m G_m C_m:C_m
  !> (C_m the history of term m, whose spring carries s_m = 2 G_m C_m; e:e in
  !> engineering form, gamma_rz = 2 e_rz). For an elastic material it is
  !> 1/2 sigma:epsilon.
  pure real(dp) function stored_energy_density(material, strain, history) result(density)
    type(material_t), intent(in) :: material
    real(dp), intent(in) :: strain(4), history(:, :)
    real(dp) :: deviatoric(4), volumetric
    integer :: m
    call deviatoric_part(strain, deviatoric, volumetric)
    density = 0.5_dp*material%bulk*volumetric**2 + material%long_term_shear*contracted(deviatoric)
    do m = 1, size(history, 2)
      density = density + material%prony_shear(m)*contracted(history(:, m))
    end do
  contains
    !> e:e of a deviatoric strain in engineering form.
    pure real(dp) function contracted(e)
      real(dp), intent(in) :: e(4)
      contracted = e(1)**2 + e(2)**2 + e(3)**2 + 0.5_dp*e(4)**2
    end function contracted
  end function stored_energy_density

  !> Deviatoric stress 2 mu e_ij of a deviatoric strain in engineering form.
  pure function deviatoric_stress(modulus, deviatoric) result(stress)
    real(dp), intent(in) :: modulus, deviatoric(4)
    real(dp) :: stress(4)
    stress(1:3) = 2.0_dp*modulus*deviatoric(1:3)
    stress(4) = modulus*deviatoric(4)
  end function deviatoric_stress

  !> History stress s0 of one Gauss point, eq. [23] (with the erratum's "- 1"):
  !> s0 = 2 sum_m G_m (exp(-beta_m dt) - 1) C_m.  history is (4, nterm).
  pure function history_stress(material, coefficients, history) result(stress)
    type(material_t), intent(in) :: material
    type(step_coefficients_t), intent(in) :: coefficients
    real(dp), intent(in) :: history(:, :)
    real(dp) :: stress(4)
    real(dp) :: weighted(4)
    integer :: m
    weighted = 0.0_dp
    do m = 1, size(history, 2)
      weighted = weighted + material%prony_shear(m)*coefficients%decay_minus_one(m)*history(:, m)
    end do
    stress = deviatoric_stress(1.0_dp, weighted)
  end function history_stress

  !> C_m <- exp(-beta_m dt) C_m + J_m de, eq. [24], after the step's deviatoric increment de.
  pure subroutine update_history(coefficients, deviatoric_increment, history)
    type(step_coefficients_t), intent(in) :: coefficients
    real(dp), intent(in) :: deviatoric_increment(4)
    real(dp), intent(inout) :: history(:, :)
    integer :: m
    do m = 1, size(history, 2)
      history(:, m) = history(:, m) + coefficients%decay_minus_one(m)*history(:, m) + &
                      coefficients%integral(m)*deviatoric_increment
    end do
  end subroutine update_history
end module visco2d_viscoelastic
