!> The finite-strain viscoelastic law (visco2d_finite_viscoelastic) at one
!> material point and in one element, against the laws it must reduce to,
!> closed forms and differences:
!>  1. No Prony terms: the hyperelastic law (visco2d_hyperelastic) to the bit,
!>     for an ELASTIC, a NEOHOOKE and a MOONEY material, whatever dt; dt = 0
!>     from an unstressed history: the instantaneous law (G0) to round-off.
!>  2. Small-strain limit: a ramp, a hold, a partial unloading and a hold of a
!>     general strain of 1e-6 (dilatation, normal and shear parts, a rotation)
!>     against visco2d's small-strain incremental law (visco2d_viscoelastic's
!>     step_coefficients, history_stress, update_history, eqs. [13]-[24]) at
!>     every step: stress and stored energy.
!>  3. Step and hold at finite strain (uniaxial strain lambda = 0.7, isochoric
!>     simple shear gamma = 0.8): the isochoric stress is sigma0_iso g(t) in
!>     closed form (a jump by a step dt = 0) and sigma0_iso (gamma_inf +
!>     sum gamma_i J(beta_i dt1) exp(-beta_i (t - dt1))) after a ramp over one
!>     step dt1, the pressure elastic, over holding steps of growing length.
!>  4. The tangent: J c : H = d tau/ds - H tau - tau H^T (the Oldroyd rate of
!>     tau, central differences along F(s) = (1 + s H) F, as test_finite.f90)
!>     at random finite deformations with a history of random earlier steps,
!>     for the whole law and its isochoric part; the element's tangent
!>     (visco2d_finite_element's finite_tangent with this law's stresses and
!>     tangents, pointwise and with the mean dilatation's pressure) against
!>     central differences of its force.
!>  5. Objectivity: a superposed in-plane rotation, a different one at every
!>     step, rotates the Cauchy stress and the tangent and leaves the history.
!>  6. Long-time limit: after a loading path and 40 of the slowest relaxation
!>     times of hold, the stress is the hyperelastic law's with G_inf; one
!>     step of dt -> infinity from an unstressed history too.
!> Each check states its tolerance and why; the largest errors are printed.
program test_finite_viscoelastic
  use visco2d_kinds, only: dp, geometry_axisymmetric, geometry_plane_strain
  use visco2d_material, only: material_t, material_kind_viscoelastic, hyperelastic_neo_hooke, &
                              hyperelastic_mooney_rivlin, elastic_matrix
  use visco2d_viscoelastic, only: step_coefficients_t, step_coefficients, deviatoric_part, deviatoric_stress, &
                                  history_stress, update_history, stored_energy_density, relaxation_integral
  use visco2d_hyperelastic, only: hyperelastic_t, hyperelastic_from_moduli, hyperelastic_response, isochoric_response, &
                                  volumetric_response, identity3, pressure_tangent, volume_change
  use visco2d_quadrilateral, only: gauss_count
  use visco2d_finite_element, only: finite_point_t, finite_kinematics, finite_force, finite_tangent, element_volumes
  use visco2d_finite_viscoelastic, only: finite_viscoelastic_t, viscoelastic_point_t, finite_viscoelastic_from_material, &
                                         viscoelastic_point_create, viscoelastic_response, &
                                         viscoelastic_isochoric_response, viscoelastic_energy, step_shear_ratio, &
                                         relaxation_ratio, term_count
  use visco2d_testing, only: check, test_summary
  implicit none

  real(dp), parameter :: shear_inf = 0.2e6_dp, bulk = 5.0e6_dp
  ! A flesh of three Prony terms from 0.5 ms to 50 ms (the impact's and the hold's time scales), G0 = 1.25 MPa
  real(dp), parameter :: prony_shear(3) = [0.5e6_dp, 0.3e6_dp, 0.25e6_dp], prony_rate(3) = [2000.0_dp, 200.0_dp, 20.0_dp]
  integer :: seed_state = 20261204
  character(len=48) :: measure_names(24) = ''
  real(dp) :: measure_worst(24) = 0.0_dp
  integer :: measures = 0

  call no_prony_terms()
  call small_strain_limit()
  call step_and_hold()
  call tangent_from_stress()
  call element_tangent()
  call objectivity()
  call long_time_limit()
  call print_measures()
  call test_summary('test_finite_viscoelastic')

contains

  !> Keep the largest relative error of a kind of check.
  subroutine note(name, relative_error)
    character(*), intent(in) :: name
    real(dp), intent(in) :: relative_error
    integer :: k
    do k = 1, measures
      if (measure_names(k) == name) then
        measure_worst(k) = max(measure_worst(k), relative_error)
        return
      end if
    end do
    measures = measures + 1
    measure_names(measures) = name
    measure_worst(measures) = relative_error
  end subroutine note

  subroutine print_measures()
    integer :: k
    do k = 1, measures
      print '(a, a48, es10.2)', 'measured largest relative error: ', measure_names(k), measure_worst(k)
    end do
  end subroutine print_measures

  !> A uniform number in [0, 1) from a fixed linear congruential sequence (the same every run).
  real(dp) function uniform()
    seed_state = int(modulo(1103515245_8*int(seed_state, 8) + 12345_8, 2147483648_8))
    uniform = real(seed_state, dp)/2147483648.0_dp
  end function uniform

  !> The viscoelastic flesh: neo-Hookean (kind 0: a VISCOELASTIC card) or MOONEY instantaneous law.
  function flesh(kind) result(material)
    integer, intent(in) :: kind
    type(material_t) :: material
    material%kind = material_kind_viscoelastic
    material%long_term_shear = shear_inf
    material%prony_shear = prony_shear
    material%prony_rate = prony_rate
    material%shear = shear_inf + sum(prony_shear)
    material%bulk = bulk
    material%hyperelastic = kind
    if (kind == hyperelastic_mooney_rivlin) then
      material%c10 = 0.7_dp*0.5_dp*shear_inf      ! any C10 : C01 = 7 : 3; scaled to G0 by the law
      material%c01 = 0.3_dp*0.5_dp*shear_inf
      material%d1 = 2.0_dp/bulk
    end if
  end function flesh

  !> A deformation gradient: rotation by angle, stretches l1, l2 in a frame at angle2, hoop l3.
  pure function gradient_of(angle, angle2, l1, l2, l3) result(f)
    real(dp), intent(in) :: angle, angle2, l1, l2, l3
    real(dp) :: f(3, 3), q(2, 2), p(2, 2), u(2, 2)
    q = reshape([cos(angle), sin(angle), -sin(angle), cos(angle)], [2, 2])
    p = reshape([cos(angle2), sin(angle2), -sin(angle2), cos(angle2)], [2, 2])
    u = matmul(p, matmul(reshape([l1, 0.0_dp, 0.0_dp, l2], [2, 2]), transpose(p)))
    f = 0.0_dp
    f(1:2, 1:2) = matmul(q, u)
    f(3, 3) = l3
  end function gradient_of

  !> A random finite deformation: any in-plane rotation, stretches in [0.55, 1.6], hoop in [0.7, 1.35].
  function random_gradient() result(f)
    real(dp) :: f(3, 3), angle, angle2, l1, l2, l3
    angle = 6.0_dp*uniform() - 3.0_dp
    angle2 = 3.0_dp*uniform()
    l1 = 0.55_dp + 1.05_dp*uniform()
    l2 = 0.55_dp + 1.05_dp*uniform()
    l3 = 0.7_dp + 0.65_dp*uniform()
    f = gradient_of(angle, angle2, l1, l2, l3)
  end function random_gradient

  pure function rotation(angle) result(q)
    real(dp), intent(in) :: angle
    real(dp) :: q(3, 3)
    q = gradient_of(angle, 0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp)
  end function rotation

  pure real(dp) function determinant(a)
    real(dp), intent(in) :: a(3, 3)
    determinant = a(3, 3)*(a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1))
  end function determinant

  pure function tensor_of(v) result(a)
    real(dp), intent(in) :: v(4)
    real(dp) :: a(3, 3)
    a = 0.0_dp
    a(1, 1) = v(1); a(2, 2) = v(2); a(3, 3) = v(3); a(1, 2) = v(4); a(2, 1) = v(4)
  end function tensor_of

  pure function voigt_of(a) result(v)
    real(dp), intent(in) :: a(3, 3)
    real(dp) :: v(4)
    v = [a(1, 1), a(2, 2), a(3, 3), a(1, 2)]
  end function voigt_of

  !> The relative size of a difference: max |a - b| / max |b| (b the reference).
  pure real(dp) function relative(a, b)
    real(dp), intent(in) :: a(:), b(:)
    relative = maxval(abs(a - b))/maxval(abs(b))
  end function relative

  ! ---------------------------------------------------------------------------------------------------------------
  !> 1. No Prony terms: visco2d_hyperelastic to the bit; dt = 0 from rest: the instantaneous law.
  subroutine no_prony_terms()
    type(material_t) :: elastic, neo, mooney
    type(finite_viscoelastic_t) :: law
    type(hyperelastic_t) :: reference
    type(viscoelastic_point_t) :: history, updated
    real(dp) :: f(3, 3), stress(4), tangent(4, 4), energy, expected(4), expected_tangent(4, 4), expected_energy
    real(dp), parameter :: steps(6) = [0.0_dp, 1.0e-4_dp, 3.0e-2_dp, 1.0_dp, 1.0e20_dp, 5.0e-3_dp]
    real(dp) :: dt, worst, worst_bits
    integer :: kind, step
    elastic%shear = 1.1e6_dp
    elastic%long_term_shear = 1.1e6_dp
    elastic%bulk = bulk
    neo = elastic
    neo%hyperelastic = hyperelastic_neo_hooke
    neo%c10 = 0.5_dp*1.1e6_dp
    neo%d1 = 1.7_dp/bulk                       ! its own D1, not 2/K
    mooney = neo
    mooney%hyperelastic = hyperelastic_mooney_rivlin
    mooney%c10 = 0.4e6_dp
    mooney%c01 = 0.15e6_dp
    worst_bits = 0.0_dp
    do kind = 1, 3
      select case (kind)
      case (1); law = finite_viscoelastic_from_material(elastic); reference = hyperelastic_from_moduli(1.1e6_dp, bulk)
      case (2); law = finite_viscoelastic_from_material(neo); reference = hyperelastic_t(c10=neo%c10, c01=0.0_dp, d1=neo%d1)
      case default
        law = finite_viscoelastic_from_material(mooney)
        reference = hyperelastic_t(c10=mooney%c10, c01=mooney%c01, d1=mooney%d1)
      end select
      history = viscoelastic_point_create(law)
      do step = 1, 6
        f = random_gradient()
        dt = steps(step)
        call viscoelastic_response(law, dt, f, history, stress, tangent, updated, energy)
        call hyperelastic_response(reference, f, expected, expected_tangent, expected_energy)
        worst_bits = max(worst_bits, maxval(abs(stress - expected)), maxval(abs(tangent - expected_tangent)), &
                         abs(energy - expected_energy))
        call isochoric_response(reference, f, expected, expected_tangent, expected_energy)
        call viscoelastic_isochoric_response(law, dt, f, history, stress, tangent, updated, energy)
        worst_bits = max(worst_bits, maxval(abs(stress - expected)), maxval(abs(tangent - expected_tangent)), &
                         abs(energy - expected_energy))
        history = updated
      end do
    end do
    call note('1. no Prony terms = hyperelastic (absolute, Pa)', worst_bits)
    call check('no Prony terms: stress, tangent and energy are visco2d_hyperelastic''s to the bit (ELASTIC, '// &
               'NEOHOOKE, MOONEY; 6 steps, dt 0 ... 1e20 s)', worst_bits == 0.0_dp)
    ! dt = 0 from rest: mu_hat = (G_inf + sum G_i)/G0 = 1 to round-off
    worst = 0.0_dp
    do kind = 1, 2
      law = finite_viscoelastic_from_material(flesh(merge(0, hyperelastic_mooney_rivlin, kind == 1)))
      history = viscoelastic_point_create(law)
      f = random_gradient()
      call viscoelastic_response(law, 0.0_dp, f, history, stress, tangent, updated)
      call hyperelastic_response(law%instantaneous, f, expected, expected_tangent)
      worst = max(worst, relative(stress, expected), relative(reshape(tangent, [16]), reshape(expected_tangent, [16])))
    end do
    call note('1. dt = 0 from rest = instantaneous law', worst)
    call check('dt = 0 from rest: the instantaneous law G0 = G_inf + sum G_i (to 1e-14: mu_hat''s round-off)', &
               worst <= 1.0e-14_dp)
    law = finite_viscoelastic_from_material(flesh(hyperelastic_mooney_rivlin))
    call check('MOONEY with Prony terms: 2 (C10 + C01) = G0, C10 : C01 kept, D1 kept', &
               abs(2.0_dp*(law%instantaneous%c10 + law%instantaneous%c01) - (shear_inf + sum(prony_shear))) <= &
               1.0e-9_dp .and. abs(law%instantaneous%c10/law%instantaneous%c01 - 7.0_dp/3.0_dp) <= 1.0e-14_dp .and. &
               law%instantaneous%d1 == 2.0_dp/bulk .and. term_count(law) == 3)
  end subroutine no_prony_terms

  ! ---------------------------------------------------------------------------------------------------------------
  !> 2. Strains of 1e-6: the finite-strain law against visco2d's small-strain incremental law at every step.
  subroutine small_strain_limit()
    real(dp), parameter :: eps = 1.0e-6_dp
    type(material_t) :: material
    type(finite_viscoelastic_t) :: law
    type(viscoelastic_point_t) :: history, updated
    type(step_coefficients_t) :: coefficients
    real(dp) :: direction(3, 3), h(3, 3), amplitude, dt, t, stress(4), tangent(4, 4), energy
    real(dp) :: small(4), deviatoric(4), deviatoric_old(4), volumetric, strain(4), s(4), c(4, 3), worst, worst_energy
    real(dp) :: worst_tangent, expected_energy
    integer :: step
    material = flesh(0)
    law = finite_viscoelastic_from_material(material)
    history = viscoelastic_point_create(law)
    direction = 0.0_dp
    direction(1, 1) = 0.3_dp; direction(2, 2) = -0.7_dp; direction(3, 3) = 0.2_dp
    direction(1, 2) = 0.4_dp; direction(2, 1) = 0.1_dp      ! shear and a rotation
    s = 0.0_dp
    c = 0.0_dp
    deviatoric_old = 0.0_dp
    worst = 0.0_dp
    worst_energy = 0.0_dp
    worst_tangent = 0.0_dp
    t = 0.0_dp
    dt = 1.0e-4_dp
    do step = 1, 80
      ! ramp over 1 ms (10 steps), hold (growing steps), unload to 40 % over 5 ms, hold again
      if (step <= 10) then
        amplitude = eps*real(step, dp)/10.0_dp
        dt = 1.0e-4_dp
      else if (step <= 40) then
        amplitude = eps
        dt = 1.0e-4_dp*1.25_dp**(step - 10)
      else if (step <= 45) then
        amplitude = eps*(1.0_dp - 0.12_dp*real(step - 40, dp))
        dt = 1.0e-3_dp
      else
        amplitude = 0.4_dp*eps
        dt = 2.0e-4_dp*1.2_dp**(step - 45)
      end if
      t = t + dt
      h = amplitude*direction
      ! visco2d's small-strain law: ds = 2 mu de + s0, C_m <- exp(-x) C_m + J_m de (eqs. [13], [21]-[24])
      coefficients = step_coefficients(material, dt)
      strain = [h(1, 1), h(2, 2), h(3, 3), h(1, 2) + h(2, 1)]
      call deviatoric_part(strain, deviatoric, volumetric)
      s = s + deviatoric_stress(coefficients%shear, deviatoric - deviatoric_old) + history_stress(material, coefficients, c)
      call update_history(coefficients, deviatoric - deviatoric_old, c)
      deviatoric_old = deviatoric
      small = s
      small(1:3) = small(1:3) + material%bulk*volumetric
      ! the finite-strain law at F = I + H
      call viscoelastic_response(law, dt, identity3 + h, history, stress, tangent, updated, energy, gradient=h)
      history = updated
      worst = max(worst, relative(stress, small))
      expected_energy = stored_energy_density(material, strain, c)
      worst_energy = max(worst_energy, abs(energy - expected_energy)/expected_energy)
      worst_tangent = max(worst_tangent, maxval(abs(tangent - elastic_matrix(coefficients%shear, material%bulk)))/ &
                                         maxval(abs(elastic_matrix(coefficients%shear, material%bulk))))
    end do
    call note('2. small strain: stress vs eqs. [13]-[24]', worst)
    call note('2. small strain: stored energy', worst_energy)
    call note('2. small strain: tangent vs D(mu_n, K)', worst_tangent)
    ! the O(strain) = 1e-6 remainder of the kinematics (rotation, J^(-2/3), the pull-back) times a few
    call check('small strain (1e-6): stress = visco2d''s incremental law at each of 80 steps (ramp, hold, unload, '// &
               'hold; to 1e-5)', worst <= 1.0e-5_dp)
    call check('small strain: stored energy = stored_energy_density at each step (to 1e-5)', worst_energy <= 1.0e-5_dp)
    call check('small strain: tangent = the elasticity matrix of mu_n (eq. [21]) and K at each step (to 1e-5)', &
               worst_tangent <= 1.0e-5_dp)
    call check('small strain: the history covers 6 times the slowest relaxation time (t > 0.3 s)', t > 0.3_dp)
  end subroutine small_strain_limit

  ! ---------------------------------------------------------------------------------------------------------------
  !> 3. A finite deformation applied in one step and held: sigma_iso = sigma0_iso g(t) in closed form.
  subroutine step_and_hold()
    type(finite_viscoelastic_t) :: law
    type(viscoelastic_point_t) :: history, updated
    real(dp) :: f(3, 3), stress(4), tangent(4, 4), iso0(4), tangent0(4, 4), pressure, slope, expected(4), t, dt
    real(dp) :: ramp, ratio, worst_jump, worst_ramp, worst_iso, iso(4), first_dt
    integer :: case, step, kind, start
    worst_jump = 0.0_dp
    worst_ramp = 0.0_dp
    worst_iso = 0.0_dp
    do case = 1, 2
      if (case == 1) then
        f = 0.0_dp
        f(1, 1) = 1.0_dp; f(2, 2) = 0.7_dp; f(3, 3) = 1.0_dp        ! uniaxial strain, 30 % compression
        kind = 0
      else
        f = identity3
        f(1, 2) = 0.8_dp                                            ! isochoric simple shear
        kind = hyperelastic_mooney_rivlin
      end if
      law = finite_viscoelastic_from_material(flesh(kind))
      call isochoric_response(law%instantaneous, f, iso0, tangent0)
      call volumetric_response(law%instantaneous, determinant(f), pressure, slope)
      do start = 1, 2        ! 1: a jump (a step of dt = 0); 2: a ramp over one step of 0.5 ms
        first_dt = merge(0.0_dp, 5.0e-4_dp, start == 1)
        history = viscoelastic_point_create(law)
        t = 0.0_dp
        do step = 0, 45
          dt = merge(first_dt, 1.0e-4_dp*1.3_dp**(step - 1), step == 0)
          t = t + dt
          call viscoelastic_response(law, dt, f, history, stress, tangent, updated)
          call viscoelastic_isochoric_response(law, dt, f, history, iso, tangent, updated)
          history = updated
          if (start == 1) then
            ratio = relaxation_ratio(law, t)
          else
            ramp = law%long_term_ratio + sum(law%ratio*relaxation_integral(law%rate*first_dt)* &
                                             exp(-law%rate*(t - first_dt)))
            ratio = ramp
          end if
          expected = ratio*iso0
          expected(1:3) = expected(1:3) + pressure
          if (start == 1) then
            worst_jump = max(worst_jump, relative(stress, expected))
          else
            worst_ramp = max(worst_ramp, relative(stress, expected))
          end if
          worst_iso = max(worst_iso, maxval(abs(iso - ratio*iso0))/maxval(abs(iso0)))
        end do
      end do
    end do
    call note('3. step and hold: jump, g(t)', worst_jump)
    call note('3. step and hold: ramp over one step', worst_ramp)
    call note('3. step and hold: isochoric part', worst_iso)
    ! 46 steps of exp products against exp of the sum, the pull-back and push-forward: a few 1e-15
    call check('step and hold (uniaxial strain 0.7, simple shear 0.8): sigma = p 1 + sigma0_iso g(t) after a jump '// &
               '(46 steps, t to 44 s; to 1e-12)', worst_jump <= 1.0e-12_dp)
    call check('step and hold: after a ramp over one step dt1, sigma0_iso (gamma_inf + sum gamma_i J(x1) '// &
               'exp(-beta_i (t - dt1))) (to 1e-12)', worst_ramp <= 1.0e-12_dp)
    call check('step and hold: the isochoric part alone relaxes as sigma0_iso g(t) (to 1e-12)', worst_iso <= 1.0e-12_dp)
    call check('step and hold: the hold reached 30 of the slowest relaxation times', &
               relaxation_ratio(law, t) - law%long_term_ratio <= 1.0e-12_dp)
  end subroutine step_and_hold

  ! ---------------------------------------------------------------------------------------------------------------
  !> A history of `steps` random deformations at random steps from rest (dt 0.1 ... 3 ms).
  function random_history(law, steps) result(history)
    type(finite_viscoelastic_t), intent(in) :: law
    integer, intent(in) :: steps
    type(viscoelastic_point_t) :: history, updated
    real(dp) :: stress(4), tangent(4, 4)
    integer :: k
    history = viscoelastic_point_create(law)
    do k = 1, steps
      call viscoelastic_response(law, 1.0e-4_dp + 3.0e-3_dp*uniform(), random_gradient(), history, stress, tangent, &
                                 updated)
      history = updated
    end do
  end function random_history

  !> tau (Voigt) of the whole law (whole = true) or its isochoric part at F over dt from history.
  function kirchhoff(law, dt, f, history, whole) result(tau)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: dt, f(3, 3)
    type(viscoelastic_point_t), intent(in) :: history
    logical, intent(in) :: whole
    real(dp) :: tau(4), tangent(4, 4)
    type(viscoelastic_point_t) :: updated
    if (whole) then
      call viscoelastic_response(law, dt, f, history, tau, tangent, updated)
    else
      call viscoelastic_isochoric_response(law, dt, f, history, tau, tangent, updated)
    end if
    tau = determinant(f)*tau
  end function kirchhoff

  !> 4. J c : H = d tau/ds - H tau - tau H^T, central differences (step 1e-6: truncation ~1e-12, round-off ~1e-10).
  subroutine tangent_from_stress()
    real(dp), parameter :: step = 1.0e-6_dp
    type(finite_viscoelastic_t) :: law
    type(viscoelastic_point_t) :: history, updated
    real(dp) :: f(3, 3), h(3, 3), stress(4), tangent(4, 4), tau(3, 3), rate(3, 3), hv(4), expected(4), worst, dt
    real(dp) :: worst_symmetry, scale
    integer :: case, component, part
    logical :: whole
    worst = 0.0_dp
    worst_symmetry = 0.0_dp
    do case = 1, 12
      law = finite_viscoelastic_from_material(flesh(merge(0, hyperelastic_mooney_rivlin, mod(case, 2) == 1)))
      history = random_history(law, 3)
      f = random_gradient()
      dt = 1.0e-4_dp + 3.0e-3_dp*uniform()
      do part = 1, 2
        whole = part == 1
        if (whole) then
          call viscoelastic_response(law, dt, f, history, stress, tangent, updated)
        else
          call viscoelastic_isochoric_response(law, dt, f, history, stress, tangent, updated)
        end if
        scale = maxval(abs(determinant(f)*tangent))
        worst_symmetry = max(worst_symmetry, maxval(abs(tangent - transpose(tangent)))*determinant(f)/scale)
        tau = determinant(f)*tensor_of(stress)
        do component = 1, 4
          h = 0.0_dp
          select case (component)
          case (1); h(1, 1) = 1.0_dp
          case (2); h(2, 2) = 1.0_dp
          case (3); h(3, 3) = 1.0_dp
          case default; h(1, 2) = 0.5_dp; h(2, 1) = 0.5_dp
          end select
          hv = [h(1, 1), h(2, 2), h(3, 3), 2.0_dp*h(1, 2)]
          rate = matmul(h, tau) + matmul(tau, transpose(h))
          expected = (kirchhoff(law, dt, matmul(identity3 + step*h, f), history, whole) - &
                      kirchhoff(law, dt, matmul(identity3 - step*h, f), history, whole))/(2.0_dp*step) - voigt_of(rate)
          worst = max(worst, maxval(abs(determinant(f)*matmul(tangent, hv) - expected))/scale)
        end do
      end do
    end do
    call note('4. tangent vs Oldroyd rate of tau', worst)
    call check('tangent = Oldroyd rate of tau with a history (12 random F, neo-Hookean and Mooney, whole law and '// &
               'isochoric part; to 1e-6)', worst <= 1.0e-6_dp)
    call check('tangent is symmetric (to 1e-14)', worst_symmetry <= 1.0e-14_dp)
  end subroutine tangent_from_stress

  !> The element's force and tangent with this law at its Gauss points, each with its own history: pointwise
  !> (viscoelastic_response) or with the mean dilatation (viscoelastic_isochoric_response and the pressure of the
  !> element's volume ratio, as visco2d_finite_solid assembles the hyperelastic law).
  subroutine element_state(geometry, mean_dilatation, law, xy, u, dt, histories, force, stiffness, valid)
    integer, intent(in) :: geometry
    logical, intent(in) :: mean_dilatation
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: xy(2, 4), u(8), dt
    type(viscoelastic_point_t), intent(in) :: histories(gauss_count)
    real(dp), intent(out) :: force(8), stiffness(8, 8)
    logical, intent(out) :: valid
    type(finite_point_t) :: points(gauss_count)
    type(viscoelastic_point_t) :: updated
    real(dp) :: stress(4, gauss_count), tangent(4, 4, gauss_count), current, reference, gradient(8), change
    real(dp) :: pressure, slope
    integer :: gp
    call finite_kinematics(geometry, xy, u, points, valid)
    if (.not. valid) return
    if (mean_dilatation) then
      call element_volumes(points, current, reference, gradient)
      change = 0.0_dp
      do gp = 1, gauss_count
        change = change + volume_change(points(gp)%gradient)*points(gp)%reference_volume
      end do
      call volumetric_response(law%instantaneous, current/reference, pressure, slope, change=change/reference)
    end if
    do gp = 1, gauss_count
      if (mean_dilatation) then
        call viscoelastic_isochoric_response(law, dt, points(gp)%deformation, histories(gp), stress(:, gp), &
                                             tangent(:, :, gp), updated, gradient=points(gp)%gradient)
        stress(1:3, gp) = stress(1:3, gp) + pressure
        tangent(:, :, gp) = tangent(:, :, gp) + pressure_tangent(pressure)
      else
        call viscoelastic_response(law, dt, points(gp)%deformation, histories(gp), stress(:, gp), tangent(:, :, gp), &
                                   updated, gradient=points(gp)%gradient)
      end if
    end do
    force = finite_force(points, stress)
    stiffness = finite_tangent(geometry, points, stress, tangent)
    if (mean_dilatation) stiffness = stiffness + slope/reference*spread(gradient, 2, 8)*spread(gradient, 1, 8)
  end subroutine element_state

  !> The element: K = df/du by central differences (step 1e-9 of a 1 cm element, as test_finite.f90: to 1e-6).
  subroutine element_tangent()
    real(dp), parameter :: xy(2, 4) = reshape([0.01_dp, 0.0_dp, 0.022_dp, 0.001_dp, 0.025_dp, 0.013_dp, &
                                               0.008_dp, 0.011_dp], [2, 4])
    real(dp), parameter :: u1(8) = [0.001_dp, -0.001_dp, -0.0005_dp, -0.002_dp, 0.0015_dp, -0.003_dp, 0.0005_dp, &
                                    -0.001_dp]
    real(dp), parameter :: u2(8) = [0.002_dp, -0.003_dp, -0.001_dp, -0.004_dp, 0.003_dp, -0.006_dp, 0.001_dp, -0.002_dp]
    real(dp), parameter :: step = 1.0e-9_dp
    type(finite_viscoelastic_t) :: law
    type(viscoelastic_point_t) :: histories(gauss_count), scratch_histories(gauss_count)
    type(finite_point_t) :: points(gauss_count)
    real(dp) :: force(8), stiffness(8, 8), plus(8), minus(8), scratch(8, 8), numeric(8, 8), stress(4), tangent(4, 4)
    real(dp) :: worst, worst_symmetry
    integer :: trial, geometry, column, gp
    logical :: valid, all_valid, mean_dilatation
    type(viscoelastic_point_t) :: updated
    worst = 0.0_dp
    worst_symmetry = 0.0_dp
    all_valid = .true.
    do trial = 1, 8
      geometry = merge(geometry_axisymmetric, geometry_plane_strain, mod(trial - 1, 4) < 2)
      mean_dilatation = trial > 4
      law = finite_viscoelastic_from_material(flesh(merge(0, hyperelastic_mooney_rivlin, mod(trial, 2) == 1)))
      ! a history: one step of 2 ms to u1, the Gauss points' own
      call finite_kinematics(geometry, xy, u1, points, valid)
      all_valid = all_valid .and. valid
      do gp = 1, gauss_count
        histories(gp) = viscoelastic_point_create(law)
        call viscoelastic_response(law, 2.0e-3_dp, points(gp)%deformation, histories(gp), stress, tangent, updated, &
                                   gradient=points(gp)%gradient)
        histories(gp) = updated
      end do
      scratch_histories = histories
      call element_state(geometry, mean_dilatation, law, xy, u2, 1.0e-3_dp, scratch_histories, force, stiffness, valid)
      all_valid = all_valid .and. valid
      do column = 1, 8
        call element_state(geometry, mean_dilatation, law, xy, u2 + step*unit(column), 1.0e-3_dp, scratch_histories, &
                           plus, scratch, valid)
        call element_state(geometry, mean_dilatation, law, xy, u2 - step*unit(column), 1.0e-3_dp, scratch_histories, &
                           minus, scratch, valid)
        all_valid = all_valid .and. valid
        numeric(:, column) = (plus - minus)/(2.0_dp*step)
      end do
      worst = max(worst, maxval(abs(stiffness - numeric))/maxval(abs(stiffness)))
      worst_symmetry = max(worst_symmetry, maxval(abs(stiffness - transpose(stiffness)))/maxval(abs(stiffness)))
    end do
    call note('4. element tangent vs df/du', worst)
    call check('element tangent = df/du with the law''s history (axisymmetric and plane strain, pointwise and '// &
               'mean dilatation, neo-Hookean and Mooney; to 1e-6)', all_valid .and. worst <= 1.0e-6_dp)
    call check('element tangent is symmetric (to 1e-12)', worst_symmetry <= 1.0e-12_dp)
  end subroutine element_tangent

  pure function unit(k) result(e)
    integer, intent(in) :: k
    real(dp) :: e(8)
    e = 0.0_dp
    e(k) = 1.0_dp
  end function unit

  ! ---------------------------------------------------------------------------------------------------------------
  !> 5. A superposed rotation Q_k (another at every step): sigma -> Q sigma Q^T, c -> Q Q Q Q c, same history.
  subroutine objectivity()
    type(finite_viscoelastic_t) :: law
    type(viscoelastic_point_t) :: plain, rotated, updated_plain, updated_rotated
    real(dp) :: f(3, 3), q(3, 3), s(4), sq(4), t(4, 4), tq(4, 4), h(3, 3), hv(4), hq(3, 3), hqv(4), dt
    real(dp) :: worst_stress, worst_history, worst_tangent
    integer :: step, component
    law = finite_viscoelastic_from_material(flesh(hyperelastic_mooney_rivlin))
    plain = viscoelastic_point_create(law)
    rotated = viscoelastic_point_create(law)
    worst_stress = 0.0_dp
    worst_history = 0.0_dp
    worst_tangent = 0.0_dp
    do step = 1, 8
      f = random_gradient()
      q = rotation(6.0_dp*uniform() - 3.0_dp)
      dt = 1.0e-4_dp + 3.0e-3_dp*uniform()
      call viscoelastic_response(law, dt, f, plain, s, t, updated_plain)
      call viscoelastic_response(law, dt, matmul(q, f), rotated, sq, tq, updated_rotated)
      plain = updated_plain
      rotated = updated_rotated
      worst_stress = max(worst_stress, relative(sq, voigt_of(matmul(q, matmul(tensor_of(s), transpose(q))))))
      worst_history = max(worst_history, relative(reshape(rotated%internal, [12]), reshape(plain%internal, [12])), &
                          relative(rotated%instantaneous, plain%instantaneous))
      do component = 1, 4
        h = 0.0_dp
        select case (component)
        case (1); h(1, 1) = 1.0_dp
        case (2); h(2, 2) = 1.0_dp
        case (3); h(3, 3) = 1.0_dp
        case default; h(1, 2) = 0.5_dp; h(2, 1) = 0.5_dp
        end select
        hv = [h(1, 1), h(2, 2), h(3, 3), 2.0_dp*h(1, 2)]
        hq = matmul(q, matmul(h, transpose(q)))
        hqv = [hq(1, 1), hq(2, 2), hq(3, 3), 2.0_dp*hq(1, 2)]
        ! c(QF) : (Q H Q^T) = Q (c(F) : H) Q^T
        worst_tangent = max(worst_tangent, maxval(abs(matmul(tq, hqv) - &
                            voigt_of(matmul(q, matmul(tensor_of(matmul(t, hv)), transpose(q))))))/maxval(abs(t)))
      end do
    end do
    call note('5. objectivity: stress', worst_stress)
    call note('5. objectivity: history', worst_history)
    call note('5. objectivity: tangent', worst_tangent)
    call check('objectivity: sigma(Q_k F_k) = Q_k sigma(F_k) Q_k^T over 8 steps of changing rotations (to 1e-12)', &
               worst_stress <= 1.0e-12_dp)
    call check('objectivity: the reference-configuration history does not see the rotations (to 1e-12)', &
               worst_history <= 1.0e-12_dp)
    call check('objectivity: c(Q F) : Q H Q^T = Q (c(F) : H) Q^T (to 1e-12)', worst_tangent <= 1.0e-12_dp)
  end subroutine objectivity

  ! ---------------------------------------------------------------------------------------------------------------
  !> 6. After many relaxation times the stress is the hyperelastic law's with G_inf.
  subroutine long_time_limit()
    type(finite_viscoelastic_t) :: law
    type(viscoelastic_point_t) :: history, updated
    type(hyperelastic_t) :: relaxed
    real(dp) :: f(3, 3), stress(4), tangent(4, 4), expected(4), expected_tangent(4, 4), t, worst, worst_tangent
    real(dp) :: worst_jump, dt, energy, expected_energy, worst_energy
    integer :: case, step
    worst = 0.0_dp
    worst_tangent = 0.0_dp
    worst_jump = 0.0_dp
    worst_energy = 0.0_dp
    do case = 1, 4
      law = finite_viscoelastic_from_material(flesh(merge(0, hyperelastic_mooney_rivlin, mod(case, 2) == 1)))
      relaxed = hyperelastic_t(c10=law%long_term_ratio*law%instantaneous%c10, &
                               c01=law%long_term_ratio*law%instantaneous%c01, d1=law%instantaneous%d1)
      history = random_history(law, 6)
      f = random_gradient()
      t = 0.0_dp
      do step = 1, 40                    ! hold f for 40 of the slowest relaxation times (2 s)
        dt = 2.0_dp/40.0_dp
        t = t + dt
        call viscoelastic_response(law, dt, f, history, stress, tangent, updated, energy)
        history = updated
      end do
      call hyperelastic_response(relaxed, f, expected, expected_tangent, expected_energy)
      worst = max(worst, relative(stress, expected))
      worst_energy = max(worst_energy, abs(energy - expected_energy)/expected_energy)
      ! the tangent of a step of 50 ms is mu_hat = gamma_inf + sum gamma_i J(x): only the relaxed law's as dt -> infinity
      call viscoelastic_response(law, 1.0e20_dp, f, history, stress, tangent, updated)
      worst_tangent = max(worst_tangent, relative(reshape(tangent, [16]), reshape(expected_tangent, [16])))
      ! one step of dt -> infinity from rest: the relaxed law at once
      call viscoelastic_response(law, 1.0e20_dp, f, viscoelastic_point_create(law), stress, tangent, updated)
      worst_jump = max(worst_jump, relative(stress, expected), relative(reshape(tangent, [16]), &
                                                                        reshape(expected_tangent, [16])))
    end do
    call note('6. long time: stress vs G_inf law', worst)
    call note('6. long time: energy vs G_inf law', worst_energy)
    call note('6. long time: tangent (dt -> inf) vs G_inf law', worst_tangent)
    call note('6. dt -> infinity from rest vs G_inf law', worst_jump)
    ! exp(-beta_min 2 s) = exp(-40) = 4e-18 of the history left, round-off beyond
    call check('long time: after a loading path and 40 relaxation times of hold, sigma = the neo-Hookean / Mooney '// &
               'law of G_inf (to 1e-12)', worst <= 1.0e-12_dp .and. t >= 0.999_dp*40.0_dp/minval(prony_rate))
    call check('long time: the stored energy is the G_inf law''s W (to 1e-12)', worst_energy <= 1.0e-12_dp)
    call check('long time: the tangent of a step dt -> infinity is the G_inf law''s (to 1e-12)', &
               worst_tangent <= 1.0e-12_dp)
    call check('one step of dt -> infinity from rest: the G_inf law (to 1e-12)', worst_jump <= 1.0e-12_dp)
    call check('step_shear_ratio: 1 at dt = 0, gamma_inf as dt -> infinity', &
               abs(step_shear_ratio(law, 0.0_dp) - 1.0_dp) <= 1.0e-15_dp .and. &
               abs(step_shear_ratio(law, 1.0e20_dp) - shear_inf/(shear_inf + sum(prony_shear))) <= 1.0e-15_dp)
  end subroutine long_time_limit
end program test_finite_viscoelastic
