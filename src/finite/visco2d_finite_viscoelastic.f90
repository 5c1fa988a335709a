!> Finite-strain viscoelastic flesh: the Prony relaxation of the deck's
!> VISCOELASTIC material (the paper's eqs. [10]-[12], shear modulus
!> phi1(t) = G_inf + sum_i G_i exp(-beta_i t), elastic bulk K) carried over to
!> finite deformation in the way of Simo (1987, "On a fully three-dimensional
!> finite-strain viscoelastic damage model: formulation and computational
!> aspects", CMAME 60, 153-173), Simo and Hughes (1998, Computational
!> Inelasticity, ch. 10) and Holzapfel (2000, Nonlinear Solid Mechanics,
!> sec. 6.10), on top of the neo-Hookean / Mooney-Rivlin law of
!> visco2d_hyperelastic.
!>
!> The law. The instantaneous (glassy) response is visco2d_hyperelastic's
!> W0 = C10 (I1bar - 3) + C01 (I2bar - 3) + (J - 1)^2 / D1 with
!> 2 (C10 + C01) = G0 = G_inf + sum_i G_i (neo-Hookean C10 = G0 / 2 unless the
!> material is MOONEY, whose C10 and C01 are scaled to that sum) and D1 = 2 / K.
!> The volumetric stress is elastic, J p 1 with p = U'(J). The isochoric second
!> Piola-Kirchhoff stress is the hereditary integral of the instantaneous one,
!> S0(t) = F^-1 tau0_iso F^-T (tau0_iso the isochoric Kirchhoff stress of W0),
!> with the normalised kernel g(t) = gamma_inf + sum_i gamma_i exp(-beta_i t),
!> gamma_i = G_i / G0, gamma_inf = G_inf / G0:
!>
!>   S_iso(t) = int_0^t g(t - s) dS0/ds ds = gamma_inf S0(t) + sum_i Q_i(t),
!>   dQ_i/dt + beta_i Q_i = gamma_i dS0/dt,
!>
!> the internal (non-equilibrium) stresses Q_i living in the reference
!> configuration (so the law is objective for any superposed rotation,
!> also a time-varying one). This is Holzapfel's form (the Q_i driven by the
!> isochoric stress itself, not Simo's fictitious stress with a DEV
!> projection afterwards); the history part F Q_i F^T / J of the Cauchy
!> stress is then not traceless in a non-proportional history, and goes with
!> the isochoric part here (a held deformation keeps it traceless).
!>
!> The recursion. Over a step dt, S0 is taken linear in time between S0_n and
!> S0_n+1, as visco2d's small-strain law (visco2d_viscoelastic, eqs. [13]-[24])
!> takes the deviatoric strain; the convolution is then exact:
!>
!>   Q_i,n+1 = exp(-x_i) Q_i,n + gamma_i J(x_i) (S0_n+1 - S0_n),   x_i = beta_i dt,
!>   J(x) = (1 - exp(-x)) / x   (eq. [22], visco2d_viscoelastic's relaxation_integral).
!>
!> Simo and Hughes and Holzapfel use the midpoint factor exp(-x/2) instead of
!> J(x) (equal to O(x^2)); J(x) is taken here because with it the small-strain
!> limit (S0 -> 2 G0 e, Q_i -> 2 G_i C_i) is visco2d's eqs. [21]-[24] term by
!> term, so that at strains of 1e-6 the two agree to the O(strain) remainder of
!> the kinematics over any history (test/test_finite_viscoelastic.f90), and a
!> held deformation relaxes exactly as S0 g(t) whatever the steps. dt = 0 is
!> the instantaneous response (J(0) = 1); a huge dt the relaxed one.
!>
!> Stress and tangent of a step: with mu_hat = gamma_inf + sum_i gamma_i J(x_i)
!> (= mu_n / G0 of eq. [21]) and the history stress of the step
!> H_n = sum_i (exp(-x_i) Q_i,n - gamma_i J(x_i) S0_n), fixed in the reference
!> configuration,
!>
!>   S_iso,n+1 = mu_hat S0_n+1 + H_n,
!>   sigma_iso = mu_hat sigma0_iso + F H_n F^T / J,   c_iso = mu_hat c0_iso,
!>
!> since a stress fixed in the reference configuration has no Oldroyd rate:
!> the spatial tangent (the Oldroyd rate of tau over J, visco2d_hyperelastic's
!> convention, which visco2d_finite_element's finite_tangent takes) is that of
!> the instantaneous law scaled by mu_hat, plus the volumetric one; it is
!> symmetric. Stresses and tangents are in the element's Voigt order (rr, zz,
!> theta theta, rz), the tangent's shear row and column those of the (1, 2)
!> pair (engineering shear in B); the 2nd Piola-Kirchhoff histories are stored
!> as tensor components (rr, zz, tt, rz).
!>
!> The stored energy (viscoelastic_energy): U(J) + gamma_inf W0_iso +
!> sum_i Q_i : Q_i / (4 G_i), the energy of the springs of the generalised
!> Maxwell model; at small strain it is visco2d_viscoelastic's
!> stored_energy_density (K theta^2/2 + G_inf e:e + sum G_i C_i:C_i) exactly
!> in form, at finite strain the internal springs' part is that quadratic
!> measure of the Q_i (the law defines no unique free energy of them).
!>
!> What is not here: the deck wiring (a VISCOELASTIC material under
!> KINEMATICS LARGE, the history per Gauss point in a time loop); the
!> module is the material point only (doc/finite_viscoelastic.md).
module visco2d_finite_viscoelastic
  use visco2d_kinds, only: dp
  use visco2d_material, only: material_t, has_memory, hyperelastic_neo_hooke, hyperelastic_mooney_rivlin
  use visco2d_viscoelastic, only: relaxation_integral
  use visco2d_hyperelastic, only: hyperelastic_t, isochoric_response, volumetric_response, pressure_tangent, &
                                  voigt_stress, identity3, volume_change
  implicit none
  private

  public :: finite_viscoelastic_t, viscoelastic_point_t
  public :: finite_viscoelastic_from_material, viscoelastic_point_create, term_count
  public :: viscoelastic_isochoric_response, viscoelastic_response, viscoelastic_energy
  public :: step_shear_ratio, relaxation_ratio, internal_energy

  !> The constants of the law: the instantaneous hyperelastic law (G0, K) and
  !> the normalised Prony series g(t) = gamma_inf + sum gamma_i exp(-beta_i t).
  type :: finite_viscoelastic_t
    type(hyperelastic_t) :: instantaneous          !< W0: 2 (C10 + C01) = G0, D1 = 2 / K
    real(dp) :: long_term_ratio = 1.0_dp           !< gamma_inf = G_inf / G0
    real(dp), allocatable :: ratio(:)              !< gamma_i = G_i / G0
    real(dp), allocatable :: rate(:)               !< beta_i, 1/s (> 0)
  end type finite_viscoelastic_t

  !> The history of one material point (Gauss point) at the end of a step.
  type :: viscoelastic_point_t
    real(dp) :: instantaneous(4) = 0.0_dp          !< S0_iso,n (rr, zz, tt, rz), Pa: 2nd Piola-Kirchhoff
    real(dp), allocatable :: internal(:, :)        !< Q_i,n (4, terms), Pa: 2nd Piola-Kirchhoff
  end type viscoelastic_point_t

contains

  !> The law of a material: its Prony series (G_inf, G_i, beta_i; none for an
  !> elastic material) and bulk K. The instantaneous law is the neo-Hookean
  !> C10 = G0 / 2, D1 = 2 / K, or, for a MOONEY material, its C10 and C01
  !> scaled so that 2 (C10 + C01) = G0 (and its D1). A NEOHOOKE or MOONEY
  !> material without Prony terms keeps its own constants, so that the law
  !> is visco2d_finite_solid's law_of_material exactly.
  pure function finite_viscoelastic_from_material(material) result(law)
    type(material_t), intent(in) :: material
    type(finite_viscoelastic_t) :: law
    real(dp) :: g0, scale
    logical :: hyperelastic
    hyperelastic = (material%hyperelastic == hyperelastic_neo_hooke .or. &
                    material%hyperelastic == hyperelastic_mooney_rivlin) .and. material%d1 > 0.0_dp .and. &
                   material%c10 + material%c01 > 0.0_dp
    if (.not. has_memory(material)) then
      allocate(law%ratio(0), law%rate(0))
      law%long_term_ratio = 1.0_dp
      if (hyperelastic) then
        law%instantaneous = hyperelastic_t(c10=material%c10, c01=material%c01, d1=material%d1)
      else
        law%instantaneous = hyperelastic_t(c10=0.5_dp*material%shear, c01=0.0_dp, d1=2.0_dp/material%bulk)
      end if
      return
    end if
    g0 = material%long_term_shear + sum(material%prony_shear)
    law%long_term_ratio = material%long_term_shear/g0
    law%ratio = material%prony_shear/g0
    law%rate = material%prony_rate
    if (hyperelastic .and. material%hyperelastic == hyperelastic_mooney_rivlin) then
      scale = g0/(2.0_dp*(material%c10 + material%c01))
      law%instantaneous = hyperelastic_t(c10=scale*material%c10, c01=scale*material%c01, d1=material%d1)
    else if (hyperelastic) then
      law%instantaneous = hyperelastic_t(c10=0.5_dp*g0, c01=0.0_dp, d1=material%d1)
    else
      law%instantaneous = hyperelastic_t(c10=0.5_dp*g0, c01=0.0_dp, d1=2.0_dp/material%bulk)
    end if
  end function finite_viscoelastic_from_material

  !> The number of Prony terms of the law.
  pure integer function term_count(law)
    type(finite_viscoelastic_t), intent(in) :: law
    term_count = 0
    if (allocated(law%ratio)) term_count = size(law%ratio)
  end function term_count

  !> The history of an undeformed, unstressed point.
  pure function viscoelastic_point_create(law) result(point)
    type(finite_viscoelastic_t), intent(in) :: law
    type(viscoelastic_point_t) :: point
    point%instantaneous = 0.0_dp
    allocate(point%internal(4, term_count(law)))
    point%internal = 0.0_dp
  end function viscoelastic_point_create

  !> mu_hat = gamma_inf + sum gamma_i J(beta_i dt): the factor of the
  !> instantaneous isochoric stress and tangent over a step dt (mu_n / G0,
  !> eq. [21]); 1 at dt = 0, gamma_inf as dt -> infinity.
  pure real(dp) function step_shear_ratio(law, dt) result(ratio)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: dt
    ratio = law%long_term_ratio
    if (term_count(law) > 0) ratio = ratio + sum(law%ratio*relaxation_integral(law%rate*dt))
  end function step_shear_ratio

  !> The normalised relaxation function g(t) = gamma_inf + sum gamma_i exp(-beta_i t).
  pure real(dp) function relaxation_ratio(law, t) result(ratio)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: t
    ratio = law%long_term_ratio
    if (term_count(law) > 0) ratio = ratio + sum(law%ratio*exp(-law%rate*t))
  end function relaxation_ratio

  !> The isochoric (hereditary) part over a step dt >= 0 (s) to the deformation
  !> gradient F (3 x 3: the in-plane block and the hoop stretch) from the
  !> history at the start of the step: the Cauchy stress sigma_iso (Voigt, Pa,
  !> the history part included: module comment), its spatial tangent c_iso
  !> (Voigt, Pa) and the history at the end of the step. `energy`: the
  !> isochoric and internal parts of viscoelastic_energy at the end of the
  !> step (J/m^3 of reference volume). `gradient`: H = F - I computed without
  !> cancellation (as visco2d_hyperelastic's isochoric_response takes it).
  pure subroutine viscoelastic_isochoric_response(law, dt, deformation, history_in, stress, tangent, history_out, &
                                                  energy, gradient)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: dt, deformation(3, 3)
    type(viscoelastic_point_t), intent(in) :: history_in
    real(dp), intent(out) :: stress(4), tangent(4, 4)
    type(viscoelastic_point_t), intent(out) :: history_out
    real(dp), intent(out), optional :: energy
    real(dp), intent(in), optional :: gradient(3, 3)
    real(dp) :: h(3, 3), jacobian, stress0(4), tangent0(4, 4), energy0, s0(4), previous(4), held(4), mu_hat
    real(dp) :: decay, integral, inverse(3, 3), old(4)
    integer :: i, n
    if (present(gradient)) then
      h = gradient
    else
      h = deformation - identity3
    end if
    call isochoric_response(law%instantaneous, deformation, stress0, tangent0, energy0, h)
    jacobian = 1.0_dp + volume_change(h)
    inverse = inverse_gradient(deformation)
    ! S0 = F^-1 tau0 F^-T, tau0 = J sigma0
    s0 = voigt_stress(matmul(inverse, matmul(jacobian*tensor_of(stress0), transpose(inverse))))
    n = term_count(law)
    previous = history_in%instantaneous
    allocate(history_out%internal(4, n))
    history_out%instantaneous = s0
    mu_hat = law%long_term_ratio
    held = 0.0_dp
    do i = 1, n
      old = 0.0_dp
      if (allocated(history_in%internal)) then
        if (size(history_in%internal, 2) >= i) old = history_in%internal(:, i)
      end if
      integral = relaxation_integral(law%rate(i)*dt)                    ! J(x), eq. [22]
      decay = exp(-law%rate(i)*dt)
      history_out%internal(:, i) = decay*old + law%ratio(i)*integral*(s0 - previous)
      mu_hat = mu_hat + law%ratio(i)*integral
      held = held + decay*old - law%ratio(i)*integral*previous          ! H_n
    end do
    stress = mu_hat*stress0
    tangent = mu_hat*tangent0
    if (n > 0) stress = stress + voigt_stress(matmul(deformation, matmul(tensor_of(held), transpose(deformation))))/jacobian
    if (present(energy)) energy = law%long_term_ratio*energy0 + internal_energy(law, history_out)
  end subroutine viscoelastic_isochoric_response

  !> The whole law over a step dt, the pressure from the point's own J:
  !> Cauchy stress (Voigt, Pa), spatial tangent (Voigt, Pa), the history at
  !> the end of the step, and viscoelastic_energy there (J/m^3 of reference
  !> volume). The volumetric part is visco2d_hyperelastic's volumetric_response
  !> of the instantaneous law (elastic in bulk), added as hyperelastic_response
  !> adds it; the mean-dilatation element takes viscoelastic_isochoric_response
  !> and the pressure of its volume ratio instead.
  pure subroutine viscoelastic_response(law, dt, deformation, history_in, stress, tangent, history_out, energy, gradient)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: dt, deformation(3, 3)
    type(viscoelastic_point_t), intent(in) :: history_in
    real(dp), intent(out) :: stress(4), tangent(4, 4)
    type(viscoelastic_point_t), intent(out) :: history_out
    real(dp), intent(out), optional :: energy
    real(dp), intent(in), optional :: gradient(3, 3)
    real(dp) :: h(3, 3), change, jacobian, pressure, slope, isochoric_energy, volumetric_energy
    if (present(gradient)) then
      h = gradient
    else
      h = deformation - identity3
    end if
    call viscoelastic_isochoric_response(law, dt, deformation, history_in, stress, tangent, history_out, &
                                         isochoric_energy, h)
    change = volume_change(h)
    jacobian = 1.0_dp + change
    call volumetric_response(law%instantaneous, jacobian, pressure, slope, volumetric_energy, change)
    stress(1:3) = stress(1:3) + pressure
    tangent = tangent + pressure_tangent(pressure) + jacobian*slope*spread(voigt_stress(identity3), 2, 4)* &
              spread(voigt_stress(identity3), 1, 4)
    if (present(energy)) energy = isochoric_energy + volumetric_energy
  end subroutine viscoelastic_response

  !> The stored energy at F with the history of the end of the step that
  !> reached F (J/m^3 of reference volume): U(J) + gamma_inf W0_iso(F) +
  !> sum_i Q_i : Q_i / (4 G_i), G_i = gamma_i G0 (module comment).
  pure real(dp) function viscoelastic_energy(law, deformation, history, gradient) result(energy)
    type(finite_viscoelastic_t), intent(in) :: law
    real(dp), intent(in) :: deformation(3, 3)
    type(viscoelastic_point_t), intent(in) :: history
    real(dp), intent(in), optional :: gradient(3, 3)
    real(dp) :: h(3, 3), stress(4), tangent(4, 4), energy0, pressure, slope, volumetric_energy, change
    if (present(gradient)) then
      h = gradient
    else
      h = deformation - identity3
    end if
    call isochoric_response(law%instantaneous, deformation, stress, tangent, energy0, h)
    change = volume_change(h)
    call volumetric_response(law%instantaneous, 1.0_dp + change, pressure, slope, volumetric_energy, change)
    energy = volumetric_energy + law%long_term_ratio*energy0 + internal_energy(law, history)
  end function viscoelastic_energy

  !> sum_i Q_i : Q_i / (4 gamma_i G0) (a term with gamma_i = 0 stores nothing).
  pure real(dp) function internal_energy(law, history) result(energy)
    type(finite_viscoelastic_t), intent(in) :: law
    type(viscoelastic_point_t), intent(in) :: history
    real(dp) :: g0
    integer :: i
    energy = 0.0_dp
    if (.not. allocated(history%internal)) return
    g0 = 2.0_dp*(law%instantaneous%c10 + law%instantaneous%c01)
    do i = 1, min(term_count(law), size(history%internal, 2))
      if (law%ratio(i) <= 0.0_dp) cycle
      associate (q => history%internal(:, i))
        energy = energy + (q(1)**2 + q(2)**2 + q(3)**2 + 2.0_dp*q(4)**2)/(4.0_dp*law%ratio(i)*g0)
      end associate
    end do
  end function internal_energy

  !> The symmetric 3 x 3 tensor of Voigt components (rr, zz, tt, rz).
  pure function tensor_of(v) result(a)
    real(dp), intent(in) :: v(4)
    real(dp) :: a(3, 3)
    a = 0.0_dp
    a(1, 1) = v(1)
    a(2, 2) = v(2)
    a(3, 3) = v(3)
    a(1, 2) = v(4)
    a(2, 1) = v(4)
  end function tensor_of

  !> F^-1 of F = (in-plane block, hoop stretch).
  pure function inverse_gradient(f) result(inverse)
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: inverse(3, 3), det
    det = f(1, 1)*f(2, 2) - f(1, 2)*f(2, 1)
    inverse = 0.0_dp
    inverse(1, 1) = f(2, 2)/det
    inverse(2, 2) = f(1, 1)/det
    inverse(1, 2) = -f(1, 2)/det
    inverse(2, 1) = -f(2, 1)/det
    inverse(3, 3) = 1.0_dp/f(3, 3)
  end function inverse_gradient
end module visco2d_finite_viscoelastic
