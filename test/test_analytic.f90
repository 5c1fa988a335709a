!> Proves the reference solutions of visco2d_analytic right by independent means.
!>
!>  * shear_ramp_response: against composite Gauss-Legendre quadrature of the
!>    hereditary integral 2 rate int_0^t G(u) du in quadruple precision, on a
!>    geometrically graded mesh (ratio 2 from 1e-3/beta_max), 20 points a panel.
!>    The quadrature error is far below double precision (the relative panel
!>    error of exp(-beta u) is roughly c^40/40! 4^-20 exp(-2c), c = beta u/2,
!>    at most ~1e-25 over all c), so the
!>    comparison measures the double-precision closed form only.
!>  * uniaxial_creep_compliance_one_term: D(0) = 1/E0 and the Laplace transform
!>    int_0^inf D(t) exp(-s t) dt (the same quadrature, on [0, 100/s]) equals
!>    1/(s Ehat(s)), Ehat = 9 K Ghat/(3 K + Ghat), Ghat = G s/(s + beta).
!>  * cylinder_bore_displacement: the instantaneous elastic response (t = 0,
!>    G = sum G_m), the long-term elastic response (G = G_inf), the hand-derived
!>    one-term closed form, and, for 2, 4 and 8 terms, a numerical inversion of
!>    the Laplace-domain expression ubar(a, s) (evaluated directly from Ghat(s),
!>    no poles or residues) by the fixed Talbot method (Abate and Valko 2004)
!>    in quadruple precision. The Talbot method with M nodes gives about 0.6 M
!>    significant digits when the arithmetic carries about M digits; with
!>    M = 40 in quad precision (~33 digits) the inversion error is ~1e-25,
!>    confirmed here by the difference between M = 40 and M = 56 and by the
!>    one-term closed form. The comparison therefore measures the error of the
!>    double-precision pole/residue sum only.
program test_analytic
  use visco2d_kinds, only: dp
  use visco2d_analytic, only: shear_relaxation, shear_ramp_response, uniaxial_creep_compliance_one_term, &
    cylinder_bore_displacement, cylinder_bore_displacement_elastic
  use visco2d_testing, only: check, check_close, test_summary
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  implicit none

  integer, parameter :: qp = selected_real_kind(30)
  integer, parameter :: gauss_points = 20
  real(qp), parameter :: pi_qp = 3.14159265358979323846264338327950288419716939937510582_qp
  real(qp) :: gauss_node(gauss_points), gauss_weight(gauss_points)

  ! geometry and load of the thick cylinder (SI)
  real(dp), parameter :: inner = 0.01_dp, outer = 0.03_dp, pressure = 1.0e5_dp

  call gauss_legendre(gauss_node, gauss_weight)

  call test_relaxation()
  call test_ramp()
  call test_compliance()
  call test_talbot_itself()
  call test_cylinder_one_term()
  call test_cylinder_limits()
  call test_cylinder_multi_term()
  call test_cylinder_input()

  call test_summary('test_analytic')

contains

  ! --------------------------------------------------------------------------
  ! shear_relaxation

  subroutine test_relaxation()
    real(dp), parameter :: g(3) = [1.0e6_dp, 2.0e6_dp, 3.0e6_dp], b(3) = [0.0_dp, 1.0_dp, 10.0_dp]
    ! exact arithmetic apart from exp: round-off 1e-15
    call check_close('relaxation: G(0) = sum G_m', shear_relaxation(g, b, 0.0_dp), 6.0e6_dp, 1.0e-15_dp)
    call check_close('relaxation: G(0.1)', shear_relaxation(g, b, 0.1_dp), &
      1.0e6_dp + 2.0e6_dp*0.904837418035959573_dp + 3.0e6_dp*0.367879441171442322_dp, 1.0e-15_dp)
    call check_close('relaxation: G(inf) = G_inf', shear_relaxation(g, b, 1.0e4_dp), 1.0e6_dp, 1.0e-15_dp)
  end subroutine test_relaxation

  ! --------------------------------------------------------------------------
  ! shear_ramp_response against quadrature

  subroutine test_ramp()
    real(dp), parameter :: products(13) = [1.0e-12_dp, 1.0e-9_dp, 1.0e-6_dp, 1.0e-4_dp, 1.0e-2_dp, 0.3_dp, &
      0.5_dp, 0.7_dp, 1.0_dp, 10.0_dp, 1.0e2_dp, 1.0e4_dp, 1.0e6_dp]
    real(dp), parameter :: rate = 2.5e-3_dp, beta_one = 4.0_dp
    real(dp), parameter :: g4(4) = [0.1e6_dp, 0.2e6_dp, 0.3e6_dp, 0.4e6_dp], b4(4) = [0.0_dp, 1.0e-3_dp, 1.0_dp, 1.0e3_dp]
    real(dp) :: t, actual, expected, worst
    character(len=80) :: name
    integer :: i

    ! One term, beta t from 1e-12 to 1e6. The closed form is a few ulps
    ! (relative_decay: series or 1 - exp(-x) with <= 1.5 bits lost); measured
    ! worst 2.3e-16; tolerance 1e-15.
    worst = 0.0_dp
    do i = 1, size(products)
      t = products(i)/beta_one
      actual = shear_ramp_response([3.0e6_dp], [beta_one], rate, t)
      expected = real(ramp_quadrature([3.0e6_qp], [real(beta_one, qp)], real(rate, qp), real(t, qp)), dp)
      worst = max(worst, abs(actual - expected)/abs(expected))
      write(name, '(a, es8.1)') 'ramp one term: beta t =', products(i)
      call check_close(trim(name), actual, expected, 1.0e-15_dp)
    end do
    print '(a, es9.2)', '  ramp one term: worst relative error ', worst

    ! beta = 0: exactly 2 rate G t
    call check_close('ramp: beta = 0 gives 2 rate G t', shear_ramp_response([3.0e6_dp], [0.0_dp], rate, 7.0_dp), &
      2.0_dp*rate*3.0e6_dp*7.0_dp, 1.0e-15_dp)
    ! zero before the ramp starts
    call check('ramp: zero at t <= 0', shear_ramp_response([3.0e6_dp], [beta_one], rate, 0.0_dp) == 0.0_dp &
      .and. shear_ramp_response([3.0e6_dp], [beta_one], rate, -1.0_dp) == 0.0_dp)

    ! Four terms (rates 0, 1e-3, 1, 1e3) over t from 1e-9 to 1e9 s: a sum of
    ! positive terms, so the same few-ulp accuracy; measured 2.2e-16; tolerance 2e-15.
    worst = 0.0_dp
    do i = -9, 9, 2
      t = 10.0_dp**i
      actual = shear_ramp_response(g4, b4, rate, t)
      expected = real(ramp_quadrature(real(g4, qp), real(b4, qp), real(rate, qp), real(t, qp)), dp)
      worst = max(worst, abs(actual - expected)/abs(expected))
      write(name, '(a, es8.1)') 'ramp four terms: t =', t
      call check_close(trim(name), actual, expected, 2.0e-15_dp)
    end do
    print '(a, es9.2)', '  ramp four terms: worst relative error ', worst

    call check('ramp: negative beta rejected (NaN)', ieee_is_nan(shear_ramp_response([1.0_dp], [-1.0_dp], rate, 1.0_dp)))
  end subroutine test_ramp

  !> 2 rate int_0^t G(u) du by composite Gauss-Legendre on panels [0, h0],
  !> [h0, 2 h0], [2 h0, 4 h0], ..., the last one clipped at t.
  function ramp_quadrature(g, b, rate, t) result(integral)
    real(qp), intent(in) :: g(:), b(:), rate, t
    real(qp) :: integral
    real(qp) :: low, high
    integral = 0.0_qp
    low = 0.0_qp
    high = t
    if (maxval(b) > 0.0_qp) high = min(t, 1.0e-3_qp/maxval(b))
    do
      integral = integral + relaxation_panel(g, b, low, high)
      if (high >= t) exit
      low = high
      high = min(2.0_qp*high, t)
    end do
    integral = 2.0_qp*rate*integral
  end function ramp_quadrature

  !> int_x0^x1 G(u) du by the Gauss-Legendre rule.
  function relaxation_panel(g, b, x0, x1) result(value)
    real(qp), intent(in) :: g(:), b(:), x0, x1
    real(qp) :: value, u
    integer :: j
    value = 0.0_qp
    do j = 1, gauss_points
      u = 0.5_qp*(x0 + x1) + 0.5_qp*(x1 - x0)*gauss_node(j)
      value = value + gauss_weight(j)*sum(g*exp(-b*u))
    end do
    value = 0.5_qp*(x1 - x0)*value
  end function relaxation_panel

  ! --------------------------------------------------------------------------
  ! uniaxial_creep_compliance_one_term

  subroutine test_compliance()
    real(dp), parameter :: g = 1.2e6_dp, k = 9.0e6_dp, beta = 0.7_dp
    real(dp), parameter :: s_values(4) = [1.0e-3_dp, 0.1_dp, 2.0_dp, 50.0_dp]
    real(qp) :: s, transform, expected, ghat, ehat
    real(dp) :: young0, worst
    character(len=80) :: name
    integer :: i

    ! D(0) = 1/E0, E0 = 9 K G/(3 K + G): a few roundings, tolerance 1e-15
    young0 = 9.0_dp*k*g/(3.0_dp*k + g)
    call check_close('compliance: D(0) = 1/E0', uniaxial_creep_compliance_one_term(g, beta, k, 0.0_dp), &
      1.0_dp/young0, 1.0e-15_dp)
    ! Laplace transform against 1/(s Ehat): quadrature error < 1e-25; the
    ! difference measures only the rounding of D in double precision
    ! (integrand D(t) e^-st in qp from a dp D). Measured 3.5e-17; tolerance 1e-14.
    worst = 0.0_dp
    do i = 1, size(s_values)
      s = real(s_values(i), qp)
      transform = compliance_transform(g, beta, k, s)
      ghat = real(g, qp)*s/(s + real(beta, qp))
      ehat = 9.0_qp*real(k, qp)*ghat/(3.0_qp*real(k, qp) + ghat)
      expected = 1.0_qp/(s*ehat)
      worst = max(worst, real(abs(transform - expected)/expected, dp))
      write(name, '(a, es8.1)') 'compliance: Laplace transform = 1/(s Ehat) at s =', s_values(i)
      call check_close(trim(name), real(transform, dp), real(expected, dp), 1.0e-14_dp)
    end do
    print '(a, es9.2)', '  compliance transform: worst relative error ', worst
    call check('compliance: invalid input rejected (NaN)', &
      ieee_is_nan(uniaxial_creep_compliance_one_term(-1.0_dp, beta, k, 1.0_dp)))
  end subroutine test_compliance

  !> int_0^inf D(t) exp(-s t) dt, graded panels from 1e-3/s to 100/s (tail < e^-100).
  function compliance_transform(g, beta, k, s) result(integral)
    real(dp), intent(in) :: g, beta, k
    real(qp), intent(in) :: s
    real(qp) :: integral, low, high, t, last
    integer :: j
    integral = 0.0_qp
    low = 0.0_qp
    high = 1.0e-3_qp/s
    last = 100.0_qp/s
    do
      do j = 1, gauss_points
        t = 0.5_qp*(low + high) + 0.5_qp*(high - low)*gauss_node(j)
        integral = integral + 0.5_qp*(high - low)*gauss_weight(j) &
          *real(uniaxial_creep_compliance_one_term(g, beta, k, real(t, dp)), qp)*exp(-s*t)
      end do
      if (high >= last) exit
      low = high
      high = min(2.0_qp*high, last)
    end do
  end function compliance_transform

  ! --------------------------------------------------------------------------
  ! Talbot inversion of ubar(a, s)

  !> ubar(a, s) = p a/(b^2 - a^2) [a^2/(2 s (K + Ghat/3)) + b^2/(2 s Ghat)], Ghat = sum G_m s/(s + beta_m).
  function bore_transform(g, b, k, s) result(value)
    real(dp), intent(in) :: g(:), b(:), k
    complex(qp), intent(in) :: s
    complex(qp) :: value, ghat
    real(qp) :: a2, b2
    integer :: m
    ghat = (0.0_qp, 0.0_qp)
    do m = 1, size(g)
      ghat = ghat + real(g(m), qp)*s/(s + real(b(m), qp))
    end do
    a2 = real(inner, qp)**2
    b2 = real(outer, qp)**2
    value = real(pressure, qp)*real(inner, qp)/(b2 - a2) &
      *(a2/(2.0_qp*s*(real(k, qp) + ghat/3.0_qp)) + b2/(2.0_qp*s*ghat))
  end function bore_transform

  !> Fixed Talbot inversion (Abate and Valko 2004) of bore_transform at t > 0
  !> with `nodes` = M nodes:
  !>   f(t) = r/M [ F(r) e^{rt}/2 + sum_{k=1}^{M-1} Re( e^{t s_k} F(s_k) (1 + i sigma_k) ) ],
  !>   r = 2M/(5t), s_k = r theta_k (cot theta_k + i), theta_k = k pi/M,
  !>   sigma_k = theta_k + (theta_k cot theta_k - 1) cot theta_k.
  function talbot_bore(g, b, k, t, nodes) result(value)
    real(dp), intent(in) :: g(:), b(:), k, t
    integer, intent(in) :: nodes
    real(qp) :: value, r, theta, cot, sigma, tq
    complex(qp) :: s
    integer :: j
    tq = real(t, qp)
    r = 2.0_qp*nodes/(5.0_qp*tq)
    value = 0.5_qp*exp(r*tq)*real(bore_transform(g, b, k, cmplx(r, 0.0_qp, qp)), qp)
    do j = 1, nodes - 1
      theta = j*pi_qp/nodes
      cot = cos(theta)/sin(theta)
      s = r*theta*cmplx(cot, 1.0_qp, qp)
      sigma = theta + (theta*cot - 1.0_qp)*cot
      value = value + real(exp(tq*s)*bore_transform(g, b, k, s)*cmplx(1.0_qp, sigma, qp), qp)
    end do
    value = r/nodes*value
  end function talbot_bore

  !> The one-term closed form (hand-derived; see test_cylinder_one_term).
  real(dp) function one_term_bore(g, beta, k, t)
    real(dp), intent(in) :: g, beta, k, t
    real(dp) :: gamma, f1, f2
    gamma = k*beta/(k + g/3.0_dp)
    f1 = (1.0_dp + beta*t)/g
    f2 = 1.0_dp/k - (g/3.0_dp)/(k*(k + g/3.0_dp))*exp(-gamma*t)
    one_term_bore = pressure*inner/(outer**2 - inner**2)*(0.5_dp*inner**2*f2 + 0.5_dp*outer**2*f1)
  end function one_term_bore

  !> The Talbot inversion itself: M = 40 against the one-term closed form and
  !> against M = 56 for a four-term law. Measured 1.6e-25 and 4.0e-25 relative,
  !> far beyond double precision; tolerance 1e-20.
  subroutine test_talbot_itself()
    real(dp), parameter :: g4(4) = [0.1e6_dp, 0.2e6_dp, 0.3e6_dp, 0.4e6_dp], b4(4) = [1.0e-3_dp, 0.1_dp, 10.0_dp, 1.0e3_dp]
    real(dp), parameter :: g1 = 1.0e6_dp, beta1 = 2.0_dp, k = 1.0e7_dp
    real(qp) :: coarse, fine, exact, worst_exact, worst_nodes
    real(dp) :: t
    integer :: i
    worst_exact = 0.0_qp
    worst_nodes = 0.0_qp
    do i = -4, 4
      t = 10.0_dp**i
      ! one-term closed form in quad precision
      exact = one_term_bore_qp(real(g1, qp), real(beta1, qp), real(k, qp), real(t, qp))
      coarse = talbot_bore([g1], [beta1], k, t, 40)
      worst_exact = max(worst_exact, abs(coarse - exact)/abs(exact))
      coarse = talbot_bore(g4, b4, k, t, 40)
      fine = talbot_bore(g4, b4, k, t, 56)
      worst_nodes = max(worst_nodes, abs(coarse - fine)/abs(fine))
    end do
    print '(a, es9.2, a, es9.2)', '  Talbot M = 40: vs one-term closed form ', real(worst_exact, dp), &
      ', vs M = 56 (four terms) ', real(worst_nodes, dp)
    call check('Talbot M = 40 agrees with the one-term closed form to 1e-20', worst_exact < 1.0e-20_qp)
    call check('Talbot M = 40 agrees with M = 56 to 1e-20', worst_nodes < 1.0e-20_qp)
  end subroutine test_talbot_itself

  real(qp) function one_term_bore_qp(g, beta, k, t)
    real(qp), intent(in) :: g, beta, k, t
    real(qp) :: gamma, f1, f2, a, b
    a = real(inner, qp)
    b = real(outer, qp)
    gamma = k*beta/(k + g/3.0_qp)
    f1 = (1.0_qp + beta*t)/g
    f2 = 1.0_qp/k - (g/3.0_qp)/(k*(k + g/3.0_qp))*exp(-gamma*t)
    one_term_bore_qp = real(pressure, qp)*a/(b**2 - a**2)*(0.5_qp*a**2*f2 + 0.5_qp*b**2*f1)
  end function one_term_bore_qp

  ! --------------------------------------------------------------------------
  ! Thick cylinder

  !> One Maxwell term: 1/(s Ghat) = (s + beta)/(G s^2) -> (1 + beta t)/G and
  !> 1/(s (K + Ghat/3)) = (s + beta)/(s ((K + G/3) s + K beta))
  !>   = 1/(K s) - (G/3)/(K (K + G/3)) /(s + gamma) -> 1/K - (G/3)/(K (K + G/3)) e^{-gamma t},
  !> gamma = K beta/(K + G/3). The module finds gamma by bisection; the two
  !> agree to round-off (measured <= 2.5e-16 relative, K = 1e6 .. 1e10 Pa);
  !> tolerance 1e-12 (brief).
  subroutine test_cylinder_one_term()
    real(dp), parameter :: g = 1.0e6_dp, beta = 2.0_dp
    real(dp), parameter :: bulks(3) = [1.0e6_dp, 1.0e7_dp, 1.0e10_dp]
    real(dp) :: times(12), actual(12), worst
    integer :: i, j
    character(len=80) :: name
    times = [0.0_dp, (10.0_dp**i, i = -5, 5)]
    do j = 1, size(bulks)
      call cylinder_bore_displacement([g], [beta], bulks(j), inner, outer, pressure, times, actual)
      worst = 0.0_dp
      do i = 1, size(times)
        worst = max(worst, abs(actual(i) - one_term_bore(g, beta, bulks(j), times(i))) &
          /abs(one_term_bore(g, beta, bulks(j), times(i))))
      end do
      print '(a, es8.1, a, es9.2)', '  one term, K =', bulks(j), ': worst relative error ', worst
      write(name, '(a, es8.1)') 'cylinder one term = closed form (1e-12), K =', bulks(j)
      call check(trim(name), worst <= 1.0e-12_dp)
    end do
  end subroutine test_cylinder_one_term

  !> Instantaneous and long-term elastic limits.
  subroutine test_cylinder_limits()
    real(dp), parameter :: k = 1.0e7_dp
    real(dp) :: u(2), lame_value
    ! t = 0: elastic with G0 = sum G_m (the residue sums reproduce 1/G0 and
    ! 1/(K + G0/3)). The residues are as large as 1/G_inf, so the sum loses
    ! ~eps G0/G_inf: measured <= 1.3e-15, and 2.4e-14 for G0/G_inf = 1e3
    ! ('small G_inf'); tolerance 1e-13. t = 1e12 s: every exponential has
    ! underflowed; measured <= 2.2e-16 against G_inf; tolerance 1e-10 (brief).
    call limits('2 terms, fluid', [0.6e6_dp, 0.4e6_dp], [1.0e-3_dp, 1.0e3_dp])
    call limits('2 terms, solid', [0.3e6_dp, 0.7e6_dp], [0.0_dp, 1.0_dp])
    call limits('4 terms, fluid', [0.1e6_dp, 0.2e6_dp, 0.3e6_dp, 0.4e6_dp], [1.0e-3_dp, 0.1_dp, 10.0_dp, 1.0e3_dp])
    call limits('4 terms, solid', [0.25e6_dp, 0.25e6_dp, 0.25e6_dp, 0.25e6_dp], [0.0_dp, 1.0e-3_dp, 1.0_dp, 1.0e3_dp])
    call limits('3 terms, small G_inf', [1.0e3_dp, 0.5e6_dp, 0.5e6_dp], [0.0_dp, 1.0e-3_dp, 1.0e3_dp])
    ! a single beta = 0 term: purely elastic at all times
    call cylinder_bore_displacement([0.8e6_dp], [0.0_dp], k, inner, outer, pressure, [0.0_dp, 1.0e3_dp], u)
    call check_close('cylinder elastic only: t = 0', u(1), &
      cylinder_bore_displacement_elastic(0.8e6_dp, k, inner, outer, pressure), 1.0e-15_dp)
    call check_close('cylinder elastic only: t = 1e3', u(2), &
      cylinder_bore_displacement_elastic(0.8e6_dp, k, inner, outer, pressure), 1.0e-15_dp)
    ! elastic formula against the Lame form u = (1 + nu)/E A ((1 - 2 nu) a + b^2/a)
    lame_value = lame_bore(0.8e6_dp, k)
    call check_close('cylinder elastic formula = Lame form', &
      cylinder_bore_displacement_elastic(0.8e6_dp, k, inner, outer, pressure), lame_value, 1.0e-14_dp)
  end subroutine test_cylinder_limits

  !> t = 0 and t -> inf limits of one law, K = 1e7 Pa.
  subroutine limits(label, g, b)
    character(*), intent(in) :: label
    real(dp), intent(in) :: g(:), b(:)
    real(dp), parameter :: k = 1.0e7_dp
    real(dp) :: v(2), g_inf
    call cylinder_bore_displacement(g, b, k, inner, outer, pressure, [0.0_dp, 1.0e12_dp], v)
    call check_close('cylinder t = 0 = elastic with sum G_m: '//label, v(1), &
      cylinder_bore_displacement_elastic(sum(g), k, inner, outer, pressure), 1.0e-13_dp)
    g_inf = sum(g, mask=b == 0.0_dp)
    if (g_inf > 0.0_dp) then
      call check_close('cylinder t -> inf = elastic with G_inf: '//label, v(2), &
        cylinder_bore_displacement_elastic(g_inf, k, inner, outer, pressure), 1.0e-10_dp)
    end if
  end subroutine limits

  !> Lame: u(a) = (1 + nu)/E A ((1 - 2 nu) a + b^2/a), A = p a^2/(b^2 - a^2).
  real(dp) function lame_bore(g, k)
    real(dp), intent(in) :: g, k
    real(dp) :: young, poisson, big_a
    young = 9.0_dp*k*g/(3.0_dp*k + g)
    poisson = (3.0_dp*k - 2.0_dp*g)/(2.0_dp*(3.0_dp*k + g))
    big_a = pressure*inner**2/(outer**2 - inner**2)
    lame_bore = (1.0_dp + poisson)/young*big_a*((1.0_dp - 2.0_dp*poisson)*inner + outer**2/inner)
  end function lame_bore

  !> Multi-term laws against Talbot inversion, t = 1e-4 .. 1e4 s.
  subroutine test_cylinder_multi_term()
    call against_talbot('2 terms, fluid', [0.6e6_dp, 0.4e6_dp], [1.0e-3_dp, 1.0e3_dp], 1.0e7_dp)
    call against_talbot('2 terms, solid', [0.3e6_dp, 0.7e6_dp], [0.0_dp, 1.0_dp], 1.0e7_dp)
    call against_talbot('4 terms, fluid', [0.1e6_dp, 0.2e6_dp, 0.3e6_dp, 0.4e6_dp], &
      [1.0e-3_dp, 0.1_dp, 10.0_dp, 1.0e3_dp], 1.0e7_dp)
    call against_talbot('4 terms, solid', [0.25e6_dp, 0.25e6_dp, 0.25e6_dp, 0.25e6_dp], &
      [0.0_dp, 1.0e-3_dp, 1.0_dp, 1.0e3_dp], 1.0e7_dp)
    ! unsorted input with a repeated rate, nearly incompressible (K = 1e4 G0):
    ! the J roots lie within ~2e-5 relative of the poles -beta_m
    call against_talbot('4 terms unsorted, repeated rate, K = 1e4 G0', [0.3e6_dp, 0.2e6_dp, 0.1e6_dp, 0.4e6_dp], &
      [1.0e2_dp, 0.0_dp, 1.0e-2_dp, 1.0e2_dp], 1.0e10_dp)
    ! compressible (K = G0/3)
    call against_talbot('4 terms, fluid, K = G0/3', [0.1e6_dp, 0.2e6_dp, 0.3e6_dp, 0.4e6_dp], &
      [1.0e-3_dp, 0.1_dp, 10.0_dp, 1.0e3_dp], 1.0e6_dp/3.0_dp)
    ! eight terms, rates 1e-4 .. 1e4 with a long-term modulus
    call against_talbot('8 terms, solid', [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp, 6.0_dp, 7.0_dp, 8.0_dp]*1.0e5_dp, &
      [0.0_dp, 1.0e-4_dp, 1.0e-3_dp, 1.0e-2_dp, 1.0_dp, 1.0e2_dp, 1.0e3_dp, 1.0e4_dp], 1.0e7_dp)
    ! eight terms, fluid, K = 2.8e7 G0: the J roots lie ~1e-9 relative from the poles
    call against_talbot('8 terms, fluid, K = 1e14', [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp, 6.0_dp, 7.0_dp, 8.0_dp]*1.0e5_dp, &
      [1.0e-5_dp, 1.0e-4_dp, 1.0e-3_dp, 1.0e-2_dp, 1.0_dp, 1.0e2_dp, 1.0e3_dp, 1.0e4_dp], 1.0e14_dp)
    ! two nearly equal rates (1 and 1 + 1e-9): a root squeezed into a 1e-9 bracket
    call against_talbot('2 terms, rates 1 and 1 + 1e-9', [0.5e6_dp, 0.5e6_dp], [1.0_dp, 1.0_dp + 1.0e-9_dp], 1.0e7_dp)
  end subroutine test_cylinder_multi_term

  !> Tolerance 1e-13 relative: the pole/residue sum adds O(n) terms of the size
  !> of 1/G0 .. 1/G_inf with some cancellation; measured worst 6.6e-15 (8 terms,
  !> see the printed values; 2.6e-15 for 4 terms), so 1e-13 leaves room for other
  !> compilers while any wrong root or residue (an error of O(1) in one term) is
  !> caught by ~10 orders of magnitude.
  subroutine against_talbot(label, g, b, k)
    character(*), intent(in) :: label
    real(dp), intent(in) :: g(:), b(:), k
    integer, parameter :: count = 17
    real(dp) :: times(count), actual(count), expected, worst
    integer :: i
    times = [(10.0_dp**(0.5_dp*i), i = -8, 8)]
    call cylinder_bore_displacement(g, b, k, inner, outer, pressure, times, actual)
    worst = 0.0_dp
    do i = 1, count
      expected = real(talbot_bore(g, b, k, times(i), 40), dp)
      worst = max(worst, abs(actual(i) - expected)/abs(expected))
    end do
    print '(a, a, a, es9.2)', '  cylinder ', label, ': worst relative error vs Talbot ', worst
    call check('cylinder = Talbot inversion (1e-13), t = 1e-4..1e4: '//label, worst <= 1.0e-13_dp)
  end subroutine against_talbot

  subroutine test_cylinder_input()
    real(dp) :: u(2)
    call cylinder_bore_displacement([1.0e6_dp], [-1.0_dp], 1.0e7_dp, inner, outer, pressure, [0.0_dp, 1.0_dp], u)
    call check('cylinder: negative beta rejected (NaN)', all(ieee_is_nan(u)))
    call cylinder_bore_displacement([1.0e6_dp], [1.0_dp], 1.0e7_dp, outer, inner, pressure, [0.0_dp, 1.0_dp], u)
    call check('cylinder: inner >= outer rejected (NaN)', all(ieee_is_nan(u)))
    call cylinder_bore_displacement([1.0e6_dp], [1.0_dp], 1.0e7_dp, inner, outer, pressure, [-1.0_dp, 1.0_dp], u)
    call check('cylinder: zero before the step', u(1) == 0.0_dp .and. u(2) > 0.0_dp)
  end subroutine test_cylinder_input

  ! --------------------------------------------------------------------------

  !> Gauss-Legendre nodes and weights on [-1, 1] in quad precision (Newton on P_n).
  subroutine gauss_legendre(x, w)
    real(qp), intent(out) :: x(:), w(:)
    integer :: n, i, j, iteration
    real(qp) :: z, p0, p1, p2, dp_dz, step
    n = size(x)
    do i = 1, n
      z = cos(pi_qp*(i - 0.25_qp)/(n + 0.5_qp))
      do iteration = 1, 100
        p0 = 1.0_qp
        p1 = z
        do j = 2, n
          p2 = ((2*j - 1)*z*p1 - (j - 1)*p0)/j
          p0 = p1
          p1 = p2
        end do
        dp_dz = n*(z*p1 - p0)/(z*z - 1.0_qp)
        step = p1/dp_dz
        z = z - step
        if (abs(step) < 1.0e-32_qp) exit
      end do
      ! recompute at the converged z
      p0 = 1.0_qp
      p1 = z
      do j = 2, n
        p2 = ((2*j - 1)*z*p1 - (j - 1)*p0)/j
        p0 = p1
        p1 = p2
      end do
      dp_dz = n*(z*p1 - p0)/(z*z - 1.0_qp)
      x(i) = z
      w(i) = 2.0_qp/((1.0_qp - z*z)*dp_dz**2)
    end do
  end subroutine gauss_legendre
end program test_analytic
