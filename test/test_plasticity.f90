!> The J2 return mapping of visco2d_plasticity at one material point,
!> against closed forms:
!>  1. Simple shear (gamma_rz driven) of an elastic-plastic material with
!>     linear hardening H: tau = G gamma up to tau_y = Y/sqrt(3), then
!>     tau = tau_y + G (H/3)/(G + H/3) (gamma - tau_y/G). The radial return
!>     is exact on a proportional path: equal to round-off for steps of any
!>     size (1, 10 and 1000 steps to the same strain).
!>  2. Uniaxial stress (e_z driven, e_r = e_theta found by Newton on the
!>     consistent tangent so that sigma_r = 0) with the bilinear curve of Y
!>     and E_t: sigma_z = E e up to Y, then Y + E_t (e - Y/E); and Newton
!>     exact after one update (the tangent is the consistent one).
!>  3. The consistent tangent against central differences of the update,
!>     at a plastic state on a general (non-proportional) increment.
!>  4. A tabulated curve (three points, perfectly plastic beyond) in simple
!>     shear: tau against the piecewise closed form, segment by segment.
!>  5. Unloading is elastic, reloading in reverse yields at the hardened
!>     stress (isotropic hardening), the stress stays on the yield surface,
!>     the plastic work is positive and equals sigma_y debar summed.
!>  6. The slider in series with a Prony material (viscoplastic_update): a
!>     shear step past the yield (dt = 0, mu = G(0)) returns to tau_y with
!>     gamma_e = tau_y/G(0); held, the stress relaxes as tau_y G(t)/G(0)
!>     with gamma_p frozen (the histories see only the elastic strain), to
!>     round-off over 200 steps of any length; with a yield stress no step
!>     reaches, the update is the viscoelastic one of eqs. [13]-[24] (the
!>     Table 3 material, a random strain path, equal to round-off).
program test_plasticity
  use visco2d_kinds, only: dp
  use visco2d_plasticity, only: hardening_t, bilinear_hardening, yield_stress, return_result_t, radial_return, &
                                consistent_tangent, deviatoric_norm, viscoplastic_update
  use visco2d_material, only: material_t, material_kind_viscoelastic, shear_relaxation_modulus
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients, deviatoric_part, deviatoric_stress, &
                                  history_stress, update_history
  use visco2d_testing, only: check, check_close, test_summary
  implicit none
  real(dp), parameter :: young = 4.07e6_dp, poisson = 0.32_dp         ! apple flesh (issue data)
  real(dp), parameter :: shear = young/(2.0_dp*(1.0_dp + poisson)), bulk = young/(3.0_dp*(1.0_dp - 2.0_dp*poisson))
  real(dp), parameter :: yield = 0.3e6_dp, tangent = 0.4e6_dp

  call simple_shear_bilinear()
  call uniaxial_bilinear()
  call tangent_by_differences()
  call simple_shear_table()
  call unload_and_reverse()
  call relaxation_after_yield()
  call viscoelastic_limit()
  call test_summary('test_plasticity')

contains

  !> Deviatoric part of a strain (engineering shear kept).
  pure function deviator(strain) result(e)
    real(dp), intent(in) :: strain(4)
    real(dp) :: e(4)
    e = strain
    e(1:3) = strain(1:3) - sum(strain(1:3))/3.0_dp
  end function deviator

  !> One step of an elastic-plastic point: the stress after the strain increment d from the deviatoric
  !> stress s (in: the step's start, out: its end) and ebar.
  subroutine point_step(hardening, d, strain, s, ebar, stress, state)
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: d(4)
    real(dp), intent(inout) :: strain(4), s(4), ebar
    real(dp), intent(out) :: stress(4)
    type(return_result_t), intent(out) :: state
    real(dp) :: de(4), trial(4)
    de = deviator(d)
    trial = s
    trial(1:3) = trial(1:3) + 2.0_dp*shear*de(1:3)
    trial(4) = trial(4) + shear*de(4)
    state = radial_return(hardening, shear, trial, ebar)
    strain = strain + d
    s = state%stress
    ebar = state%equivalent_plastic
    stress = s
    stress(1:3) = stress(1:3) + bulk*sum(strain(1:3))
  end subroutine point_step

  pure real(dp) function shear_closed_form(hardening_modulus, gamma) result(tau)
    real(dp), intent(in) :: hardening_modulus, gamma
    real(dp) :: tau_y
    tau_y = yield/sqrt(3.0_dp)
    if (shear*gamma <= tau_y) then
      tau = shear*gamma
    else
      tau = tau_y + shear*(hardening_modulus/3.0_dp)/(shear + hardening_modulus/3.0_dp)*(gamma - tau_y/shear)
    end if
  end function shear_closed_form

  subroutine simple_shear_bilinear()
    type(hardening_t) :: hardening
    type(return_result_t) :: state
    real(dp) :: strain(4), s(4), ebar, stress(4), gamma_end
    integer :: counts(3) = [1, 10, 1000], c, k
    character(len=8) :: tag
    hardening = bilinear_hardening(yield, tangent, young)
    gamma_end = 0.2_dp
    do c = 1, size(counts)
      strain = 0.0_dp; s = 0.0_dp; ebar = 0.0_dp
      do k = 1, counts(c)
        call point_step(hardening, [0.0_dp, 0.0_dp, 0.0_dp, gamma_end/counts(c)], strain, s, ebar, stress, state)
      end do
      write(tag, '(i0)') counts(c)
      call check_close('shear_tau_steps_'//trim(tag), stress(4), shear_closed_form(hardening%final_slope, gamma_end), &
                       rtol=1.0e-12_dp)
      call check_close('shear_normal_stresses_zero_steps_'//trim(tag), maxval(abs(stress(1:3))), 0.0_dp, &
                       rtol=0.0_dp, atol=1.0e-9_dp*yield)
      call check_close('shear_on_yield_surface_steps_'//trim(tag), sqrt(1.5_dp)*deviatoric_norm(s), &
                       yield_stress(hardening, ebar), rtol=1.0e-12_dp)
    end do
    ! below the yield: elastic, no plastic strain
    strain = 0.0_dp; s = 0.0_dp; ebar = 0.0_dp
    call point_step(hardening, [0.0_dp, 0.0_dp, 0.0_dp, 0.9_dp*yield/(sqrt(3.0_dp)*shear)], strain, s, ebar, stress, state)
    call check('shear_below_yield_elastic', .not. state%yielded .and. ebar == 0.0_dp)
  end subroutine simple_shear_bilinear

  !> Uniaxial stress by Newton on the lateral strain (sigma_r = sigma_theta = 0 by symmetry e_r = e_theta).
  subroutine uniaxial_bilinear()
    type(hardening_t) :: hardening
    type(return_result_t) :: state
    real(dp) :: strain(4), s(4), ebar, stress(4), trial_strain(4), s_try(4), ebar_try, d(4), c(4, 4)
    real(dp) :: expected, lateral, residual_history(8), slope
    integer :: step, iteration, nsteps, most_iterations
    hardening = bilinear_hardening(yield, tangent, young)
    strain = 0.0_dp; s = 0.0_dp; ebar = 0.0_dp
    nsteps = 40
    most_iterations = 0
    do step = 1, nsteps
      lateral = 0.0_dp
      residual_history = 0.0_dp
      do iteration = 1, 8
        trial_strain = strain; s_try = s; ebar_try = ebar
        d = [lateral, 5.0e-3_dp, lateral, 0.0_dp]
        call point_step(hardening, d, trial_strain, s_try, ebar_try, stress, state)
        residual_history(iteration) = abs(stress(1))
        if (abs(stress(1)) <= 1.0e-12_dp*yield) exit
        c = consistent_tangent(bulk, shear, state)
        slope = c(1, 1) + c(1, 3)                   ! d sigma_r / d e_lateral (e_r = e_theta)
        lateral = lateral - stress(1)/slope
      end do
      most_iterations = max(most_iterations, iteration)
      strain = trial_strain; s = s_try; ebar = ebar_try
    end do
    call check('uniaxial_newton_converged', abs(stress(1)) <= 1.0e-12_dp*yield)
    ! on a bilinear curve the lateral equation is piecewise linear in e_lateral: with the consistent
    ! tangent one Newton update is exact (a second evaluation confirms it; 3 where a step crosses the yield)
    call check('uniaxial_newton_consistent_tangent', most_iterations <= 3)
    if (strain(2)*young <= yield) then
      expected = young*strain(2)
    else
      expected = yield + tangent*(strain(2) - yield/young)
    end if
    call check_close('uniaxial_sigma_z_bilinear', stress(2), expected, rtol=1.0e-10_dp)
    call check_close('uniaxial_sigma_theta_zero', stress(3), 0.0_dp, rtol=0.0_dp, atol=1.0e-10_dp*yield)
  end subroutine uniaxial_bilinear

  subroutine tangent_by_differences()
    type(hardening_t) :: hardening
    type(return_result_t) :: state, base_state
    real(dp) :: strain0(4), s0(4), ebar0, strain(4), s(4), ebar, stress(4), plus(4), minus(4)
    real(dp) :: d(4), direction(4), c(4, 4), h, worst
    integer :: j
    hardening = bilinear_hardening(yield, tangent, young)
    ! a plastic start: simple shear past the yield
    strain0 = 0.0_dp; s0 = 0.0_dp; ebar0 = 0.0_dp
    call point_step(hardening, [0.0_dp, 0.0_dp, 0.0_dp, 0.15_dp], strain0, s0, ebar0, stress, state)
    d = [0.01_dp, -0.02_dp, 0.004_dp, 0.03_dp]                ! a non-proportional increment
    strain = strain0; s = s0; ebar = ebar0
    call point_step(hardening, d, strain, s, ebar, stress, base_state)
    call check('tangent_state_plastic', base_state%yielded)
    c = consistent_tangent(bulk, shear, base_state)
    worst = 0.0_dp
    h = 1.0e-6_dp
    do j = 1, 4
      direction = 0.0_dp
      direction(j) = h
      strain = strain0; s = s0; ebar = ebar0
      call point_step(hardening, d + direction, strain, s, ebar, plus, state)
      strain = strain0; s = s0; ebar = ebar0
      call point_step(hardening, d - direction, strain, s, ebar, minus, state)
      worst = max(worst, maxval(abs((plus - minus)/(2.0_dp*h) - c(:, j))))
    end do
    call check_close('tangent_central_differences', worst/maxval(abs(c)), 0.0_dp, rtol=0.0_dp, atol=1.0e-6_dp)
  end subroutine tangent_by_differences

  subroutine simple_shear_table()
    type(hardening_t) :: hardening
    type(return_result_t) :: state
    real(dp) :: strain(4), s(4), ebar, stress(4), tau_expected, gamma, gamma_p, tau
    integer :: k
    hardening%plastic_strain = [0.0_dp, 0.02_dp, 0.05_dp]
    hardening%stress = [0.2e6_dp, 0.3e6_dp, 0.33e6_dp]
    hardening%final_slope = 0.0_dp
    strain = 0.0_dp; s = 0.0_dp; ebar = 0.0_dp
    do k = 1, 300
      call point_step(hardening, [0.0_dp, 0.0_dp, 0.0_dp, 1.0e-3_dp], strain, s, ebar, stress, state)
    end do
    gamma = strain(4)
    ! closed form: tau = sigma_y(ebar)/sqrt(3), ebar = gamma_p/sqrt(3), gamma = tau/G + gamma_p
    ! solved segment by segment for gamma_p (sigma_y linear in each)
    gamma_p = table_plastic_shear(hardening, gamma)
    tau_expected = yield_stress(hardening, gamma_p/sqrt(3.0_dp))/sqrt(3.0_dp)
    tau = stress(4)
    call check_close('table_shear_tau', tau, tau_expected, rtol=1.0e-12_dp)
    call check_close('table_shear_ebar', ebar, gamma_p/sqrt(3.0_dp), rtol=1.0e-12_dp)
    call check('table_shear_past_last_point', ebar > 0.05_dp)
    call check_close('table_shear_perfectly_plastic_tau', tau, 0.33e6_dp/sqrt(3.0_dp), rtol=1.0e-12_dp)
  end subroutine simple_shear_table

  !> gamma_p of simple shear to total gamma on a tabulated curve: gamma = sigma_y(gamma_p/sqrt3)/(sqrt3 G) + gamma_p.
  real(dp) function table_plastic_shear(hardening, gamma) result(gamma_p)
    type(hardening_t), intent(in) :: hardening
    real(dp), intent(in) :: gamma
    real(dp) :: low, high, middle
    integer :: k
    low = 0.0_dp
    high = gamma
    do k = 1, 200                      ! bisection: the closed form is monotone in gamma_p
      middle = 0.5_dp*(low + high)
      if (yield_stress(hardening, middle/sqrt(3.0_dp))/(sqrt(3.0_dp)*shear) + middle > gamma) then
        high = middle
      else
        low = middle
      end if
    end do
    gamma_p = 0.5_dp*(low + high)
  end function table_plastic_shear

  subroutine unload_and_reverse()
    type(hardening_t) :: hardening
    type(return_result_t) :: state
    real(dp) :: strain(4), s(4), ebar, stress(4), work, expected_work, tau_peak, ebar_peak
    integer :: k
    hardening = bilinear_hardening(yield, tangent, young)
    strain = 0.0_dp; s = 0.0_dp; ebar = 0.0_dp; work = 0.0_dp; expected_work = 0.0_dp
    do k = 1, 100                                  ! to gamma = 0.3, about 2.7 times the yield strain
      call point_step(hardening, [0.0_dp, 0.0_dp, 0.0_dp, 3.0e-3_dp], strain, s, ebar, stress, state)
      work = work + state%dissipation
      expected_work = expected_work + yield_stress(hardening, state%equivalent_plastic)* &
                      (state%equivalent_plastic - (state%equivalent_plastic - sqrt(2.0_dp/3.0_dp)*state%multiplier))
    end do
    tau_peak = stress(4)
    ebar_peak = ebar
    call check('plastic_work_positive', work > 0.0_dp)
    call check_close('plastic_work_is_yield_times_debar', work, expected_work, rtol=1.0e-12_dp)
    ! unload by 2 tau_peak / G: elastic all the way to -tau_peak
    call point_step(hardening, [0.0_dp, 0.0_dp, 0.0_dp, -2.0_dp*tau_peak/shear*0.999_dp], strain, s, ebar, stress, state)
    call check('unload_elastic', .not. state%yielded .and. ebar == ebar_peak)
    call check_close('unload_reverse_stress', stress(4), -0.998_dp*tau_peak, rtol=1.0e-12_dp)
    ! a little more: yields in reverse at the hardened stress
    call point_step(hardening, [0.0_dp, 0.0_dp, 0.0_dp, -0.004_dp*tau_peak/shear], strain, s, ebar, stress, state)
    call check('reverse_yields', state%yielded .and. ebar > ebar_peak)
    call check_close('reverse_yield_at_hardened_stress', sqrt(3.0_dp)*abs(stress(4)), &
                     yield_stress(hardening, ebar), rtol=1.0e-12_dp)
    call check('reverse_yield_not_initial', sqrt(3.0_dp)*abs(stress(4)) > 1.01_dp*yield)
  end subroutine unload_and_reverse

  !> A viscoelastic material of two Prony terms (beta 50 and 2000 1/s) and G_inf.
  function prony_material() result(material)
    type(material_t) :: material
    material%kind = material_kind_viscoelastic
    material%long_term_shear = 0.6e6_dp
    material%prony_shear = [0.5e6_dp, 0.4e6_dp]
    material%prony_rate = [50.0_dp, 2000.0_dp]
    material%shear = material%long_term_shear + sum(material%prony_shear)
    material%bulk = 5.0e6_dp
  end function prony_material

  subroutine relaxation_after_yield()
    type(material_t) :: material
    type(hardening_t) :: hardening
    type(step_coefficients_t) :: instant, step
    type(return_result_t) :: state
    real(dp) :: stress(4), history(4, 2), ebar, gamma_p, tau_y, t, dt, worst
    integer :: k
    material = prony_material()
    hardening%plastic_strain = [0.0_dp]
    hardening%stress = [yield]
    hardening%final_slope = 0.0_dp                       ! perfectly plastic
    tau_y = yield/sqrt(3.0_dp)
    stress = 0.0_dp; history = 0.0_dp; ebar = 0.0_dp
    instant = step_coefficients(material, 0.0_dp)
    call viscoplastic_update(material, instant, hardening, [0.0_dp, 0.0_dp, 0.0_dp, 3.0_dp*tau_y/material%shear], &
                             stress, history, ebar, state)
    call check_close('relaxation_step_returns_to_yield', stress(4), tau_y, rtol=1.0e-13_dp)
    gamma_p = 3.0_dp*tau_y/material%shear - tau_y/material%shear
    call check_close('relaxation_step_plastic_strain', state%plastic_increment(4), gamma_p, rtol=1.0e-12_dp)
    t = 0.0_dp
    worst = 0.0_dp
    do k = 1, 200
      dt = 1.0e-5_dp*1.03_dp**k                           ! growing steps: 10 us to about 4 ms
      step = step_coefficients(material, dt)
      call viscoplastic_update(material, step, hardening, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], stress, history, ebar, state)
      t = t + dt
      worst = max(worst, abs(stress(4) - tau_y*shear_relaxation_modulus(material, t)/material%shear)/tau_y)
      if (state%yielded) exit
    end do
    call check('relaxation_hold_elastic', .not. state%yielded)
    call check_close('relaxation_hold_closed_form', worst, 0.0_dp, rtol=0.0_dp, atol=1.0e-12_dp)
    call check_close('relaxation_hold_plastic_frozen', ebar, gamma_p/sqrt(3.0_dp), rtol=1.0e-14_dp)
  end subroutine relaxation_after_yield

  subroutine viscoelastic_limit()
    type(material_t) :: material
    type(hardening_t) :: hardening
    type(step_coefficients_t) :: step
    type(return_result_t) :: state
    real(dp) :: stress(4), reference(4), history(4, 2), reference_history(4, 2), ebar, increment(4), draw(4)
    real(dp) :: deviatoric(4), volumetric, worst
    integer :: k
    material = prony_material()
    hardening = bilinear_hardening(1.0e12_dp, 0.0_dp, 1.0e13_dp)      ! never reached
    stress = 0.0_dp; reference = 0.0_dp; history = 0.0_dp; reference_history = 0.0_dp; ebar = 0.0_dp
    worst = 0.0_dp
    step = step_coefficients(material, 1.0e-4_dp)
    do k = 1, 100
      call random_number(draw)
      increment = 1.0e-3_dp*(draw - 0.5_dp)
      call viscoplastic_update(material, step, hardening, increment, stress, history, ebar, state)
      ! eqs. [13], [14], [23], [24] written out
      call deviatoric_part(increment, deviatoric, volumetric)
      reference = reference + deviatoric_stress(step%shear, deviatoric) + history_stress(material, step, reference_history)
      reference(1:3) = reference(1:3) + step%bulk*volumetric
      call update_history(step, deviatoric, reference_history)
      worst = max(worst, maxval(abs(stress - reference))/maxval(abs(reference)))
    end do
    call check('viscoelastic_limit_never_yields', ebar == 0.0_dp)
    call check_close('viscoelastic_limit_same_stress', worst, 0.0_dp, rtol=0.0_dp, atol=1.0e-13_dp)
    call check_close('viscoelastic_limit_same_history', maxval(abs(history - reference_history)), 0.0_dp, &
                     rtol=0.0_dp, atol=1.0e-16_dp)
  end subroutine viscoelastic_limit
end program test_plasticity
