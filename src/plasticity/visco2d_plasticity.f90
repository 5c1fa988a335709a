!> Von Mises (J2) plasticity with isotropic hardening at one Gauss point: the
!> return mapping of the deviatoric stress and its consistent tangent, for
!> a plastic slider in series with the viscoelastic deviatoric response of
!> eqs. [13]-[24] (the bulk stays elastic, eq. [14]).
!>
!> Over a step the viscoelastic law gives the deviatoric trial stress
!>   s_trial = s_n + s0 + 2 mu_n de            (eqs. [13], [21], [23])
!> with mu_n the step's shear modulus (eq. [21]; G for an elastic material).
!> With the plastic strain increment de_p = dgamma n, n = s_trial/|s_trial|
!> (radial return: the flow is normal to the von Mises cylinder),
!>   s = s_trial - 2 mu_n dgamma n,
!>   |s_trial| - 2 mu_n dgamma = sqrt(2/3) sigma_y(ebar_n + sqrt(2/3) dgamma),
!> ebar the equivalent plastic strain and sigma_y(ebar) the uniaxial yield
!> stress of the hardening curve. The viscoelastic histories then take the
!> elastic part de - de_p of the increment (eq. [24]), so the springs and
!> dashpots see only the strain the slider did not take.
!>
!> Vectors are the project's (r, z, theta, rz) with engineering shear:
!> strains (e_r, e_z, e_theta, gamma_rz), stresses (s_r, s_z, s_theta, s_rz);
!> the norm of a deviatoric stress is |s| = (s_r^2 + s_z^2 + s_theta^2 +
!> 2 s_rz^2)^(1/2), and de_p's shear component is 2 dgamma n_rz.
!>
!> The hardening curve is piecewise linear in ebar: points (ebar_k,
!> sigma_k) from ebar_1 = 0 (the initial yield stress), with the slope
!> `final_slope` beyond the last point (0: perfectly plastic there). The
!> bilinear curve of a yield stress Y and a tangent modulus E_t is the one
!> point (0, Y) with the plastic modulus H = E E_t / (E - E_t) beyond it
!> (bilinear_hardening). The curve's type and the bilinear one live with the
!> material (visco2d_material) and are re-exported here. The consistent tangent is Simo and Hughes's
!> (Computational Inelasticity, 1998, Box 3.2) with mu_n in place of G.
module visco2d_plasticity
  use visco2d_kinds, only: dp
  use visco2d_material, only: material_t, hardening_t, bilinear_hardening
  use visco2d_viscoelastic, only: step_coefficients_t, deviatoric_part, history_stress, update_history
  implicit none
  private

  public :: hardening_t, bilinear_hardening, yield_stress, hardening_slope
  public :: return_result_t, radial_return, consistent_tangent, deviatoric_norm, viscoplastic_update, point_return

  !> What the return mapping of one Gauss point gives.
  type :: return_result_t
    real(dp) :: stress(4) = 0.0_dp             !< the deviatoric stress s, Pa
    real(dp) :: plastic_increment(4) = 0.0_dp  !< de_p, engineering shear
    real(dp) :: equivalent_plastic = 0.0_dp    !< ebar after the step
    real(dp) :: multiplier = 0.0_dp            !< dgamma (0: an elastic step)
    real(dp) :: dissipation = 0.0_dp           !< s : de_p, the plastic work per unit volume of the step, J/m^3
    logical :: yielded = .false.               !< the trial stress was outside the yield surface
    real(dp) :: theta = 1.0_dp                 !< 1 - 2 mu dgamma / |s_trial| (Box 3.2)
    real(dp) :: theta_bar = 0.0_dp             !< 1 / (1 + H / (3 mu)) - (1 - theta)
    real(dp) :: normal(4) = 0.0_dp             !< n = s_trial / |s_trial| (tensor components)
  end type return_result_t

  !> Newton iterations of the return mapping on a curved (tabulated) hardening:
  !> the scalar equation is piecewise linear, so it ends once dgamma lies in its segment.
  integer, parameter :: max_return_iterations = 50

contains

  !> sigma_y(ebar), Pa.
  pure real(dp) function yield_stress(hardening, ebar) result(stress)
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: ebar
    integer :: k
    k = segment(hardening, ebar)
    if (k == size(hardening%stress)) then
      stress = hardening%stress(k) + hardening%final_slope*(ebar - hardening%plastic_strain(k))
    else
      stress = hardening%stress(k) + (hardening%stress(k + 1) - hardening%stress(k)) &
               *(ebar - hardening%plastic_strain(k))/(hardening%plastic_strain(k + 1) - hardening%plastic_strain(k))
    end if
  end function yield_stress

  !> d sigma_y / d ebar at ebar (the slope of the segment ebar lies in, to the right at a point), Pa.
  pure real(dp) function hardening_slope(hardening, ebar) result(slope)
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: ebar
    integer :: k
    k = segment(hardening, ebar)
    if (k == size(hardening%stress)) then
      slope = hardening%final_slope
    else
      slope = (hardening%stress(k + 1) - hardening%stress(k))/(hardening%plastic_strain(k + 1) - hardening%plastic_strain(k))
    end if
  end function hardening_slope

  !> The point k with ebar_k <= ebar < ebar_(k+1) (the last one beyond the table).
  pure integer function segment(hardening, ebar) result(k)
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: ebar
    k = size(hardening%plastic_strain)
    do while (k > 1)
      if (hardening%plastic_strain(k) <= ebar) exit
      k = k - 1
    end do
  end function segment

  !> |s| of a deviatoric stress (r, z, theta, rz): (s:s)^(1/2).
  pure real(dp) function deviatoric_norm(s) result(norm)
    real(dp), intent(in) :: s(4)
    norm = sqrt(s(1)**2 + s(2)**2 + s(3)**2 + 2.0_dp*s(4)**2)
  end function deviatoric_norm

  !> The radial return of the deviatoric trial stress `trial` (Pa) with the
  !> step's shear modulus `shear` (mu_n, Pa) from the equivalent plastic
  !> strain `ebar` of the step's start. A trial stress inside the yield
  !> surface (or on it) is the stress: an elastic step.
  pure function radial_return(hardening, shear, trial, ebar) result(state)
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: shear, trial(4), ebar
    type(return_result_t) :: state
    real(dp), parameter :: root_two_thirds = sqrt(2.0_dp/3.0_dp)
    real(dp) :: norm, excess, slope, dgamma, residual
    integer :: iteration
    norm = deviatoric_norm(trial)
    state%stress = trial
    state%equivalent_plastic = ebar
    excess = norm - root_two_thirds*yield_stress(hardening, ebar)
    if (excess <= 0.0_dp) return
    state%yielded = .true.
    state%normal = trial/norm
    ! Newton on g(dgamma) = |s_trial| - 2 mu dgamma - sqrt(2/3) sigma_y(ebar + sqrt(2/3) dgamma),
    ! piecewise linear in dgamma: each iterate is the root of one segment's line, and the
    ! iteration ends when the root lies in its own segment (the bilinear curve's one line is
    ! solved at once: dgamma = excess / (2 mu + 2/3 H)).
    if (size(hardening%stress) == 1) then           ! bilinear: g is one line, its root in one step
      slope = hardening%final_slope
      dgamma = excess/(2.0_dp*shear + 2.0_dp/3.0_dp*slope)
    else
      dgamma = 0.0_dp
      do iteration = 1, max_return_iterations
        slope = hardening_slope(hardening, ebar + root_two_thirds*dgamma)
        residual = norm - 2.0_dp*shear*dgamma - root_two_thirds*yield_stress(hardening, ebar + root_two_thirds*dgamma)
        if (iteration > 1 .and. abs(residual) <= 1.0e-14_dp*norm) exit
        dgamma = dgamma + residual/(2.0_dp*shear + 2.0_dp/3.0_dp*slope)
        dgamma = max(dgamma, 0.0_dp)
      end do
      slope = hardening_slope(hardening, ebar + root_two_thirds*dgamma)
    end if
    state%multiplier = dgamma
    state%stress = trial - 2.0_dp*shear*dgamma*state%normal
    state%plastic_increment(1:3) = dgamma*state%normal(1:3)
    state%plastic_increment(4) = 2.0_dp*dgamma*state%normal(4)
    state%equivalent_plastic = ebar + root_two_thirds*dgamma
    state%dissipation = dot_product(state%stress(1:3), state%plastic_increment(1:3)) &
                        + state%stress(4)*state%plastic_increment(4)
    state%theta = 1.0_dp - 2.0_dp*shear*dgamma/norm
    state%theta_bar = 1.0_dp/(1.0_dp + slope/(3.0_dp*shear)) - (1.0_dp - state%theta)
  end function radial_return

  !> The consistent tangent d sigma / d epsilon (4 x 4, engineering shear in
  !> strain: d s_rz / d gamma_rz = mu in the elastic case) of a step with
  !> bulk modulus K, shear modulus mu_n and the return's theta, theta_bar and n:
  !>   C = K 1 x 1 + 2 mu theta I_dev - 2 mu theta_bar n x n      (Box 3.2)
  !> An elastic step (theta = 1, theta_bar = 0) gives the elastic matrix.
  pure function consistent_tangent(bulk, shear, state) result(tangent)
    real(dp), intent(in) :: bulk, shear
    type(return_result_t), intent(in) :: state
    real(dp) :: tangent(4, 4)
    real(dp) :: n_strain(4)
    integer :: i
    tangent = 0.0_dp
    tangent(1:3, 1:3) = bulk - 2.0_dp/3.0_dp*shear*state%theta
    do i = 1, 3
      tangent(i, i) = tangent(i, i) + 2.0_dp*shear*state%theta
    end do
    tangent(4, 4) = shear*state%theta              ! d s_rz / d gamma_rz = (1/2) 2 mu theta
    ! - 2 mu theta_bar n (n : d eps): n : d eps = n_r de_r + n_z de_z + n_t de_t + n_rz dgamma_rz
    n_strain = state%normal
    do i = 1, 4
      tangent(i, :) = tangent(i, :) - 2.0_dp*shear*state%theta_bar*state%normal(i)*n_strain
    end do
  end function consistent_tangent

  !> One Gauss point of the visco-elastoplastic flesh over a step: from the
  !> total stress `stress` (in: the step's start, out: its end, Pa) and the
  !> strain increment `increment` (engineering shear), with the step's
  !> coefficients of the material (mu_n, K, eqs. [21], [22]), its Prony
  !> histories `history` (4, nterm; updated with the elastic part of the
  !> deviatoric increment, eq. [24]) and the equivalent plastic strain
  !> `ebar` (updated): point_return with the history stress of eq. [23].
  pure subroutine viscoplastic_update(material, coefficients, hardening, increment, stress, history, ebar, state)
    type(material_t), intent(in) :: material
    type(step_coefficients_t), intent(in) :: coefficients
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: increment(4)
    real(dp), intent(inout) :: stress(4), history(:, :), ebar
    type(return_result_t), intent(out) :: state
    real(dp) :: deviatoric(4), volumetric, s0(4), start(4)
    s0 = 0.0_dp
    if (size(history, 2) > 0) s0 = history_stress(material, coefficients, history)
    start = stress
    call point_return(hardening, coefficients%shear, coefficients%bulk, start, increment, s0, &
                      2.0_dp/3.0_dp*yield_stress(hardening, ebar)**2, ebar, stress, state)
    call deviatoric_part(increment, deviatoric, volumetric)
    if (size(history, 2) > 0) call update_history(coefficients, deviatoric - state%plastic_increment, history)
    ebar = state%equivalent_plastic
  end subroutine viscoplastic_update

  !> The stress at the end of a step at one Gauss point: the mean stress
  !> p_n + K tr(de) (eq. [14]) and the deviatoric trial
  !> s_trial = dev(stress) + 2 mu dev(de) + s0 (eqs. [13], [21], [23]; s0 the
  !> history stress of the step) returned to the yield surface
  !> (radial_return) when |s_trial|^2 exceeds `limit` = (2/3) sigma_y(ebar)^2;
  !> `state` the return's result (an elastic one inside the surface).
  pure subroutine point_return(hardening, shear, bulk, stress, increment, s0, limit, ebar, sigma, state)
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: shear, bulk, stress(4), increment(4), s0(4), limit, ebar
    real(dp), intent(out) :: sigma(4)
    type(return_result_t), intent(out) :: state
    real(dp) :: mean, volumetric, trial(4)
    volumetric = increment(1) + increment(2) + increment(3)
    mean = sum(stress(1:3))/3.0_dp
    trial(1:3) = stress(1:3) - mean + 2.0_dp*shear*(increment(1:3) - volumetric/3.0_dp)
    trial(4) = stress(4) + shear*increment(4)
    trial = trial + s0
    if (trial(1)**2 + trial(2)**2 + trial(3)**2 + 2.0_dp*trial(4)**2 <= limit) then
      sigma = trial                                 ! inside the yield surface: elastic (radial_return's first test)
      state%stress = trial
      state%equivalent_plastic = ebar
    else
      state = radial_return(hardening, shear, trial, ebar)
      sigma = state%stress
    end if
    sigma(1:3) = sigma(1:3) + mean + bulk*volumetric
  end subroutine point_return
end module visco2d_plasticity
