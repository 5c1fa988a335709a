!> The hyperfoam (visco2d_hyperfoam) at one material point, against closed
!> forms and independent computations:
!>  1. Small strain: at F = I + eps h (eps = 1e-7) the stress is the linear
!>     law sigma = 2 mu0 e + (K0 - 2 mu0/3) tr(e) I, the tangent the linear
!>     moduli; at F = I exactly (three equal stretches, the limits of the
!>     divided differences) the tangent is the linear one to round-off.
!>  2. Homogeneous states, lam from 1 to 0.2 (80 % compression) and in
!>     tension to 2: uniaxial stress (lateral stretches free): one term with
!>     nu = 0 gives lateral stretch 1 and sigma = 2 mu/alpha (lam^alpha - 1)/lam;
!>     one term with nu /= 0 the ABAQUS closed form lam_T = lam^(-nu) and the
!>     nominal stress T = (2/lam) mu/alpha (lam^alpha - J^(-alpha beta)); several
!>     terms the lateral stretch of a bisection on the test's own sum, and
!>     Newton on the code's stress and tangent to the same root; equibiaxial
!>     (lam_T = lam^(-2 nu/(1 - nu)) for one term) and volumetric closed
!>     forms; simple shear: sigma_12 = dW/dgamma (differences of W) and the
!>     universal relation sigma_11 - sigma_22 = gamma sigma_12.
!>  3. Stress = derivative of W: S = 2 dW/dC by differences of the energy,
!>     pushed forward, sigma = J^-1 F S F^T; and P = dW/dF = J sigma F^-T.
!>  4. Tangent = derivative of stress: CC = 2 dS/dC by differences of the
!>     code's own S (from its sigma), pushed forward, against the tangent, at
!>     random F (in-plane rotation times stretches), equal stretches (two
!>     and three), lam = 0.2 and tension, for foams of 1, 2, 3 and 6 terms.
!>  5. Objectivity: sigma(R F) = R sigma(F) R^T, c(R F) = R R R R c(F), W(R F) = W(F).
!>  6. hyperfoam_check: its message for each bad parameter; an inverted F is
!>     not admissible and gives zeros, never NaN.
!> Differences are the 4-point central formula f' = [8 (f(h) - f(-h)) -
!> (f(2h) - f(-2h))]/(12 h), truncation h^4 f^(5)/30; the steps are relative
!> to the smallest eigenvalue of C; each test states the tolerance and why.
program test_hyperfoam
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
  use visco2d_kinds, only: dp, pi
  use visco2d_hyperfoam, only: hyperfoam_t, hyperfoam_response, hyperfoam_initial_moduli, hyperfoam_check
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary
  implicit none
  type(hyperfoam_t) :: foams(5)
  character(len=12) :: foam_names(5)
  integer :: seed_state = 20261204
  ! The largest relative error each kind of check measured (printed at the end, quoted in doc/hyperfoam.md).
  character(len=40) :: measure_names(16) = ''
  real(dp) :: measure_worst(16) = 0.0_dp
  integer :: measures = 0

  ! 1: one term, nu = 0 (the ABAQUS benchmark's foam has nu = 0); 2: one term, nu = 0.3;
  ! 3: two terms of opposite alpha (a Storakers-type fit); 4: three terms, a negative nu;
  ! 5: six terms (the most ABAQUS allows), one mu_i < 0. Moduli of a soft packing foam (mu0 ~ 0.1-0.5 MPa).
  foams(1) = foam([0.2e6_dp], [8.0_dp], [0.0_dp])
  foams(2) = foam([0.15e6_dp], [5.0_dp], [0.3_dp])
  foams(3) = foam([0.16e6_dp, 0.02e6_dp], [12.0_dp, -3.0_dp], [0.05_dp, 0.2_dp])
  foams(4) = foam([0.1e6_dp, 0.05e6_dp, 0.03e6_dp], [2.0_dp, 9.0_dp, -1.5_dp], [-0.2_dp, 0.1_dp, 0.0_dp])
  foams(5) = foam([0.1e6_dp, 0.05e6_dp, 0.04e6_dp, -0.01e6_dp, 0.02e6_dp, 0.03e6_dp], &
                  [1.0_dp, 4.0_dp, 10.0_dp, 6.0_dp, -2.0_dp, -6.0_dp], [0.0_dp, 0.1_dp, 0.2_dp, 0.05_dp, 0.3_dp, 0.15_dp])
  foam_names = [character(len=12) :: 'one_nu0', 'one_nu03', 'two_terms', 'three_terms', 'six_terms']

  call small_strain_limit()
  call uniaxial_compression()
  call equibiaxial_compression()
  call volumetric_compression()
  call simple_shear()
  call stress_is_energy_derivative()
  call tangent_is_stress_derivative()
  call objectivity()
  call parameter_checks()
  call inadmissible_deformation()
  call example_sets()
  call print_measures()
  call test_summary('test_hyperfoam')

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
      print '(a, a40, es10.2)', 'measured largest relative error: ', measure_names(k), measure_worst(k)
    end do
  end subroutine print_measures

  function foam(mu, alpha, nu) result(law)
    real(dp), intent(in) :: mu(:), alpha(:), nu(:)
    type(hyperfoam_t) :: law
    law%mu = mu
    law%alpha = alpha
    law%nu = nu
  end function foam

  !> A uniform number in [0, 1) from a fixed linear congruential sequence (the same every run).
  real(dp) function uniform()
    seed_state = modulo(1103515245_8*int(seed_state, 8) + 12345_8, 2147483648_8)
    uniform = real(seed_state, dp)/2147483648.0_dp
  end function uniform

  pure function rotation(angle) result(r)
    real(dp), intent(in) :: angle
    real(dp) :: r(3, 3)
    r = 0.0_dp
    r(1, :) = [cos(angle), -sin(angle), 0.0_dp]
    r(2, :) = [sin(angle), cos(angle), 0.0_dp]
    r(3, 3) = 1.0_dp
  end function rotation

  pure function diagonal(values) result(m)
    real(dp), intent(in) :: values(3)
    real(dp) :: m(3, 3)
    integer :: i
    m = 0.0_dp
    do i = 1, 3
      m(i, i) = values(i)
    end do
  end function diagonal

  !> Voigt (rr, zz, thetatheta, rz) to the 3x3 tensor and back.
  pure function tensor_of(v) result(t)
    real(dp), intent(in) :: v(4)
    real(dp) :: t(3, 3)
    t = 0.0_dp
    t(1, 1) = v(1); t(2, 2) = v(2); t(3, 3) = v(3); t(1, 2) = v(4); t(2, 1) = v(4)
  end function tensor_of

  pure function voigt_of(t) result(v)
    real(dp), intent(in) :: t(3, 3)
    real(dp) :: v(4)
    v = [t(1, 1), t(2, 2), t(3, 3), 0.5_dp*(t(1, 2) + t(2, 1))]
  end function voigt_of

  !> The fourth-order tensor of a 4x4 Voigt matrix (minor symmetries), and back.
  pure function fourth_of(d) result(c)
    real(dp), intent(in) :: d(4, 4)
    real(dp) :: c(3, 3, 3, 3)
    integer, parameter :: vi(4) = [1, 2, 3, 1], vj(4) = [1, 2, 3, 2]
    integer :: p, q
    c = 0.0_dp
    do q = 1, 4
      do p = 1, 4
        c(vi(p), vj(p), vi(q), vj(q)) = d(p, q)
        c(vj(p), vi(p), vi(q), vj(q)) = d(p, q)
        c(vi(p), vj(p), vj(q), vi(q)) = d(p, q)
        c(vj(p), vi(p), vj(q), vi(q)) = d(p, q)
      end do
    end do
  end function fourth_of

  pure function voigt_fourth(c) result(d)
    real(dp), intent(in) :: c(3, 3, 3, 3)
    real(dp) :: d(4, 4)
    integer, parameter :: vi(4) = [1, 2, 3, 1], vj(4) = [1, 2, 3, 2]
    integer :: p, q
    do q = 1, 4
      do p = 1, 4
        d(p, q) = c(vi(p), vj(p), vi(q), vj(q))
      end do
    end do
  end function voigt_fourth

  !> a_iI a_jJ a_kK a_lL c_IJKL.
  pure function transform_fourth(a, c) result(t)
    real(dp), intent(in) :: a(3, 3), c(3, 3, 3, 3)
    real(dp) :: t(3, 3, 3, 3), u(3, 3, 3, 3)
    integer :: i, j, k, l, m
    t = c
    ! one index at a time: t_..i.. = a_im t_..m..
    u = 0.0_dp
    do m = 1, 3
      do i = 1, 3
        u(i, :, :, :) = u(i, :, :, :) + a(i, m)*t(m, :, :, :)
      end do
    end do
    t = 0.0_dp
    do m = 1, 3
      do j = 1, 3
        t(:, j, :, :) = t(:, j, :, :) + a(j, m)*u(:, m, :, :)
      end do
    end do
    u = 0.0_dp
    do m = 1, 3
      do k = 1, 3
        u(:, :, k, :) = u(:, :, k, :) + a(k, m)*t(:, :, m, :)
      end do
    end do
    t = 0.0_dp
    do m = 1, 3
      do l = 1, 3
        t(:, :, :, l) = t(:, :, :, l) + a(l, m)*u(:, :, :, m)
      end do
    end do
  end function transform_fourth

  !> The symmetric positive square root U of C (block diagonal: 2x2 in-plane
  !> block by the closed form sqrt(M) = (M + sqrt(det M) I)/sqrt(tr M + 2 sqrt(det M)),
  !> the hoop entry by sqrt).
  pure function square_root(c) result(u)
    real(dp), intent(in) :: c(3, 3)
    real(dp) :: u(3, 3), s, t
    u = 0.0_dp
    s = sqrt(c(1, 1)*c(2, 2) - c(1, 2)*c(2, 1))
    t = sqrt(c(1, 1) + c(2, 2) + 2.0_dp*s)
    u(1:2, 1:2) = c(1:2, 1:2)/t
    u(1, 1) = u(1, 1) + s/t
    u(2, 2) = u(2, 2) + s/t
    u(3, 3) = sqrt(c(3, 3))
  end function square_root

  !> Inverse of a block-diagonal F (2x2 in-plane block and the hoop entry).
  pure function inverse(f) result(g)
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: g(3, 3), area
    g = 0.0_dp
    area = f(1, 1)*f(2, 2) - f(1, 2)*f(2, 1)
    g(1, :) = [f(2, 2), -f(1, 2), 0.0_dp]/area
    g(2, :) = [-f(2, 1), f(1, 1), 0.0_dp]/area
    g(3, 3) = 1.0_dp/f(3, 3)
  end function inverse

  pure real(dp) function volume_of(f)
    real(dp), intent(in) :: f(3, 3)
    volume_of = (f(1, 1)*f(2, 2) - f(1, 2)*f(2, 1))*f(3, 3)
  end function volume_of

  !> W at the right stretch tensor sqrt(C).
  real(dp) function energy_of_c(law, c) result(w)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: c(3, 3)
    real(dp) :: s(4), d(4, 4)
    call hyperfoam_response(law, square_root(c), s, d, w)
  end function energy_of_c

  real(dp) function energy_of_f(law, f) result(w)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: s(4), d(4, 4)
    call hyperfoam_response(law, f, s, d, w)
  end function energy_of_f

  !> The second Piola-Kirchhoff stress of the code at C: S = J U^-1 sigma(U) U^-1, U = sqrt(C).
  function pk2_of_c(law, c) result(s)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: c(3, 3)
    real(dp) :: s(3, 3), u(3, 3), g(3, 3), sigma(4), d(4, 4)
    u = square_root(c)
    call hyperfoam_response(law, u, sigma, d)
    g = inverse(u)
    s = volume_of(u)*matmul(g, matmul(tensor_of(sigma), transpose(g)))
  end function pk2_of_c

  !> Smallest eigenvalue of the block-diagonal C (for the relative steps).
  pure real(dp) function smallest_eigenvalue(c)
    real(dp), intent(in) :: c(3, 3)
    real(dp) :: mean, radius
    mean = 0.5_dp*(c(1, 1) + c(2, 2))
    radius = hypot(0.5_dp*(c(1, 1) - c(2, 2)), c(1, 2))
    smallest_eigenvalue = min(c(3, 3), (c(1, 1)*c(2, 2) - c(1, 2)**2)/(mean + radius))
  end function smallest_eigenvalue

  !> The linear law's stress and moduli for mu0, K0.
  pure subroutine linear_law(shear, bulk, strain, stress, moduli)
    real(dp), intent(in) :: shear, bulk, strain(4)
    real(dp), intent(out) :: stress(4), moduli(4, 4)
    real(dp) :: lame
    lame = bulk - 2.0_dp*shear/3.0_dp
    stress(1:3) = 2.0_dp*shear*strain(1:3) + lame*sum(strain(1:3))
    stress(4) = 2.0_dp*shear*strain(4)
    moduli = 0.0_dp
    moduli(1:3, 1:3) = lame
    moduli(1, 1) = lame + 2.0_dp*shear
    moduli(2, 2) = lame + 2.0_dp*shear
    moduli(3, 3) = lame + 2.0_dp*shear
    moduli(4, 4) = shear
  end subroutine linear_law

  ! ---------------------------------------------------------------------------------------------------------
  !> 1. At F = I + eps h the stress is linear in eps h: the neglected terms are O(|alpha| eps) relative
  !> (|alpha| <= 12, eps = 1e-7: < 2e-6 with the factor of the second-order terms), the round-off in
  !> lam^alpha - J^(-alpha beta) is eps_machine/eps ~ 1e-9 relative: tolerance 1e-5 of the largest
  !> component. The tangent at I + eps h differs from the linear moduli by O(|alpha|^2 eps) ~ 1e-5 relative
  !> (tolerance 1e-4); at F = I exactly the tangent is the linear one to round-off (1e-12).
  subroutine small_strain_limit()
    real(dp), parameter :: eps = 1.0e-7_dp
    real(dp) :: h(3, 3), f(3, 3), strain(4), stress(4), tangent(4, 4), expected(4), moduli(4, 4)
    real(dp) :: shear, bulk
    integer :: n, trial
    do n = 1, size(foams)
      call hyperfoam_initial_moduli(foams(n), shear, bulk)
      do trial = 1, 3
        h = 0.0_dp
        h(1:2, 1:2) = reshape([uniform(), uniform(), uniform(), uniform()], [2, 2]) - 0.5_dp
        h(3, 3) = uniform() - 0.5_dp
        f = diagonal([1.0_dp, 1.0_dp, 1.0_dp]) + eps*h
        strain = voigt_of(0.5_dp*(h + transpose(h)))*eps     ! tensor components (e_rz, not gamma_rz)
        call linear_law(shear, bulk, strain, expected, moduli)
        call hyperfoam_response(foams(n), f, stress, tangent)
        call check_close('small_strain_stress_'//trim(foam_names(n))//'_'//digit(trial), &
                         maxval(abs(stress - expected)), 0.0_dp, rtol=0.0_dp, atol=1.0e-5_dp*maxval(abs(expected)))
        call note('small-strain stress', maxval(abs(stress - expected))/maxval(abs(expected)))
        call check_close('small_strain_tangent_'//trim(foam_names(n))//'_'//digit(trial), &
                         maxval(abs(tangent - moduli)), 0.0_dp, rtol=0.0_dp, atol=1.0e-4_dp*maxval(abs(moduli)))
        call note('small-strain tangent', maxval(abs(tangent - moduli))/maxval(abs(moduli)))
      end do
      f = diagonal([1.0_dp, 1.0_dp, 1.0_dp])
      call hyperfoam_response(foams(n), f, stress, tangent)
      call linear_law(shear, bulk, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], expected, moduli)
      call check_close('identity_tangent_'//trim(foam_names(n)), maxval(abs(tangent - moduli)), 0.0_dp, &
                       rtol=0.0_dp, atol=1.0e-12_dp*maxval(abs(moduli)))
      call note('tangent at F = I', maxval(abs(tangent - moduli))/maxval(abs(moduli)))
      call check_close('identity_stress_zero_'//trim(foam_names(n)), maxval(abs(stress)), 0.0_dp, &
                       rtol=0.0_dp, atol=1.0e-9_dp)
      call check_close('identity_moduli_'//trim(foam_names(n)), tangent(4, 4), shear, rtol=1.0e-12_dp)
    end do
  end subroutine small_strain_limit

  pure function digit(i) result(text)
    integer, intent(in) :: i
    character(:), allocatable :: text
    character(len=12) :: buffer
    write(buffer, '(i0)') i
    text = trim(buffer)
  end function digit

  ! ---------------------------------------------------------------------------------------------------------
  !> The test's own sum: the principal Kirchhoff stress of a stretch lam_a at a volume ratio J,
  !> sum 2 mu_i/alpha_i (lam_a^alpha_i - J^(-alpha_i beta_i)).
  pure real(dp) function principal_kirchhoff(law, stretch, volume) result(tau)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: stretch, volume
    real(dp) :: beta
    integer :: i
    tau = 0.0_dp
    do i = 1, size(law%mu)
      beta = law%nu(i)/(1.0_dp - 2.0_dp*law%nu(i))
      tau = tau + 2.0_dp*law%mu(i)/law%alpha(i)*(stretch**law%alpha(i) - volume**(-law%alpha(i)*beta))
    end do
  end function principal_kirchhoff

  !> The lateral stretch t with zero lateral stress when `count` directions (1: uniaxial, 2: the
  !> two free ones of uniaxial stress are r and theta; see callers) carry t and the others the imposed
  !> stretch: bisection on tau(t, J(t)) = 0 in log t over [1e-3, 1e3] to a relative 1e-15.
  real(dp) function lateral_by_bisection(law, imposed, imposed_count) result(t)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: imposed
    integer, intent(in) :: imposed_count   ! 1: uniaxial (J = lam t^2); 2: equibiaxial (J = lam^2 t)
    real(dp) :: low, high, middle, value_low
    integer :: k
    low = log(1.0e-3_dp)
    high = log(1.0e3_dp)
    value_low = lateral_residual(law, imposed, imposed_count, low)
    do k = 1, 200
      middle = 0.5_dp*(low + high)
      if (sign(1.0_dp, lateral_residual(law, imposed, imposed_count, middle)) == sign(1.0_dp, value_low)) then
        low = middle
      else
        high = middle
      end if
      if (high - low < 1.0e-15_dp) exit
    end do
    t = exp(0.5_dp*(low + high))
  end function lateral_by_bisection

  !> The lateral principal Kirchhoff stress at the lateral stretch exp(log_t).
  pure real(dp) function lateral_residual(law, imposed, imposed_count, log_t)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: imposed, log_t
    integer, intent(in) :: imposed_count
    real(dp) :: volume
    if (imposed_count == 1) then
      volume = imposed*exp(2.0_dp*log_t)
    else
      volume = imposed**2*exp(log_t)
    end if
    lateral_residual = principal_kirchhoff(law, exp(log_t), volume)
  end function lateral_residual

  !> 2a. Uniaxial stress along z (the lateral r and theta free): F = diag(t, lam, t). For every foam the
  !> lateral stretch t by Newton on the code's sigma_rr with the code's tangent (at a diagonal F with
  !> l = d = diag(dt/t, 0, dt/t), the Truesdell rate gives d sigma_rr/d ln t = c_1111 + c_1133 + (2 - 2)
  !> sigma_rr), against the bisection on the test's own sum (both to round-off: tolerance 1e-12), the
  !> axial Cauchy stress against the test's sum tau/J (1e-10: the two differ by the round-off of t, times
  !> dtau/dln t / tau <~ alpha), the lateral stress zero to 1e-10 of the axial one; one term: t = lam^(-nu)
  !> (nu = 0: t = 1) and the ABAQUS nominal stress T = (2/lam) mu/alpha (lam^alpha - J^(-alpha beta)).
  !> Newton converging in < 12 iterations from t = 1 down to lam = 0.2 (steps of 0.05 from the previous t)
  !> is itself a check of the tangent (quadratic convergence).
  subroutine uniaxial_compression()
    real(dp) :: lam, t, t_bisection, f(3, 3), stress(4), tangent(4, 4), volume, expected, nominal, beta, correction
    real(dp) :: stretches(21)
    integer :: n, k, iteration, most
    logical :: converged
    do k = 1, 17
      stretches(k) = 1.0_dp - 0.05_dp*(k - 1)            ! 1 to 0.2
    end do
    stretches(18:21) = [1.25_dp, 1.5_dp, 1.75_dp, 2.0_dp]     ! tension
    do n = 1, size(foams)
      most = 0
      converged = .true.
      t = 1.0_dp
      do k = 1, size(stretches)
        lam = stretches(k)
        if (k == 18) t = 1.0_dp
        do iteration = 1, 30
          f = diagonal([t, lam, t])
          call hyperfoam_response(foams(n), f, stress, tangent)
          correction = -stress(1)/(tangent(1, 1) + tangent(1, 3))     ! d ln t
          if (abs(correction) <= 1.0e-14_dp) exit                     ! quadratic: the next is below round-off
          t = t*exp(correction)
        end do
        most = max(most, iteration)
        converged = converged .and. iteration < 30
        t_bisection = lateral_by_bisection(foams(n), lam, 1)
        call check_close('uniaxial_lateral_newton_vs_bisection_'//trim(foam_names(n))//'_'//digit(k), &
                         t, t_bisection, rtol=1.0e-12_dp)
        call note('uniaxial lateral stretch (Newton/bisect)', abs(t - t_bisection)/t_bisection)
        volume = lam*t**2
        expected = principal_kirchhoff(foams(n), lam, volume)/volume
        call check_close('uniaxial_axial_stress_'//trim(foam_names(n))//'_'//digit(k), stress(2), expected, &
                         rtol=1.0e-10_dp, atol=1.0e-10_dp*foams(n)%mu(1))
        call note('uniaxial axial stress', abs(stress(2) - expected)/max(abs(expected), foams(n)%mu(1)))
        call check_close('uniaxial_lateral_stress_zero_'//trim(foam_names(n))//'_'//digit(k), &
                         max(abs(stress(1)), abs(stress(3)), abs(stress(4))), 0.0_dp, rtol=0.0_dp, &
                         atol=1.0e-10_dp*abs(stress(2)) + 1.0e-300_dp)
        if (size(foams(n)%mu) == 1) then
          call check_close('uniaxial_lateral_abaqus_'//trim(foam_names(n))//'_'//digit(k), t, &
                           lam**(-foams(n)%nu(1)), rtol=1.0e-12_dp)
          call note('uniaxial lam_T = lam^(-nu)', abs(t - lam**(-foams(n)%nu(1)))/t)
          beta = foams(n)%nu(1)/(1.0_dp - 2.0_dp*foams(n)%nu(1))
          nominal = 2.0_dp/lam*foams(n)%mu(1)/foams(n)%alpha(1)*(lam**foams(n)%alpha(1) &
                    - (lam*lam**(-2.0_dp*foams(n)%nu(1)))**(-foams(n)%alpha(1)*beta))
          ! nominal stress = force / reference area = sigma_zz t^2
          call check_close('uniaxial_nominal_abaqus_'//trim(foam_names(n))//'_'//digit(k), stress(2)*t**2, &
                           nominal, rtol=1.0e-10_dp, atol=1.0e-10_dp*foams(n)%mu(1))
          call note('uniaxial ABAQUS nominal stress', abs(stress(2)*t**2 - nominal)/max(abs(nominal), foams(n)%mu(1)))
        end if
        if (foams(n)%nu(1) == 0.0_dp .and. size(foams(n)%mu) == 1) then
          call check_close('uniaxial_nu0_closed_form_'//digit(k), stress(2), &
                           2.0_dp*foams(n)%mu(1)/foams(n)%alpha(1)*(lam**foams(n)%alpha(1) - 1.0_dp)/lam, &
                           rtol=1.0e-12_dp, atol=1.0e-10_dp*foams(n)%mu(1))
        end if
      end do
      call check('uniaxial_newton_converges_'//trim(foam_names(n)), converged .and. most <= 12, &
                 'most iterations '//digit(most))
    end do
  end subroutine uniaxial_compression

  !> 2b. Equibiaxial stress in r and theta (z free): F = diag(lam, t, lam), t from the bisection on the test's
  !> own sum (J = lam^2 t); the code's sigma_zz is zero to 1e-10 of sigma_rr (t carries the bisection's
  !> 1e-15 times |dtau/dln t| <~ alpha tau), sigma_rr = sigma_thetatheta = tau(lam, J)/J to 1e-10; one term:
  !> t = lam^(-2 nu/(1 - nu)) to 1e-12.
  subroutine equibiaxial_compression()
    real(dp) :: lam, t, f(3, 3), stress(4), tangent(4, 4), volume, expected, nu
    integer :: n, k
    do n = 1, size(foams)
      do k = 1, 21
        if (k <= 17) then
          lam = 1.0_dp - 0.05_dp*(k - 1)
        else
          lam = 1.0_dp + 0.25_dp*(k - 17)
        end if
        t = lateral_by_bisection(foams(n), lam, 2)
        f = diagonal([lam, t, lam])
        call hyperfoam_response(foams(n), f, stress, tangent)
        volume = lam**2*t
        expected = principal_kirchhoff(foams(n), lam, volume)/volume
        call check_close('equibiaxial_stress_'//trim(foam_names(n))//'_'//digit(k), stress(1), expected, &
                         rtol=1.0e-10_dp, atol=1.0e-10_dp*foams(n)%mu(1))
        call note('equibiaxial stress', abs(stress(1) - expected)/max(abs(expected), foams(n)%mu(1)))
        call check_close('equibiaxial_hoop_equals_radial_'//trim(foam_names(n))//'_'//digit(k), stress(3), &
                         stress(1), rtol=1.0e-13_dp, atol=1.0e-13_dp*foams(n)%mu(1))
        ! t carries the bisection's relative 1e-15 (a few ulps), which moves sigma_zz by up to
        ! |c| 1e-15 (at lam = 1, where sigma_rr = 0 too, this is all there is): + 1e-13 max|c|.
        call check_close('equibiaxial_free_zero_'//trim(foam_names(n))//'_'//digit(k), abs(stress(2)), 0.0_dp, &
                         rtol=0.0_dp, atol=1.0e-10_dp*abs(stress(1)) + 1.0e-13_dp*maxval(abs(tangent)))
        if (size(foams(n)%mu) == 1) then
          nu = foams(n)%nu(1)
          call check_close('equibiaxial_lateral_closed_form_'//trim(foam_names(n))//'_'//digit(k), t, &
                           lam**(-2.0_dp*nu/(1.0_dp - nu)), rtol=1.0e-12_dp)
        end if
      end do
    end do
  end subroutine equibiaxial_compression

  !> 2c. Volumetric (hydrostatic) compression F = lam I, lam from 1 to 0.2: the pressure is
  !> -sum 2 mu_i/alpha_i (lam^alpha_i - lam^(-3 alpha_i beta_i))/lam^3 in every direction, no shear
  !> (1e-12: the same sum in another order); the tangent at three equal stretches is isotropic:
  !> D(1,1) = D(2,2) = D(3,3), D(1,2) = D(1,3) = D(2,3), D(4,4) = (D(1,1) - D(1,2))/2 (1e-10 of D(1,1)).
  subroutine volumetric_compression()
    real(dp) :: lam, stress(4), tangent(4, 4), expected, scale
    integer :: n, k
    do n = 1, size(foams)
      do k = 1, 17
        lam = 1.0_dp - 0.05_dp*(k - 1)
        call hyperfoam_response(foams(n), diagonal([lam, lam, lam]), stress, tangent)
        expected = principal_kirchhoff(foams(n), lam, lam**3)/lam**3
        call check_close('volumetric_stress_'//trim(foam_names(n))//'_'//digit(k), &
                         maxval(abs(stress(1:3) - expected)) + abs(stress(4)), 0.0_dp, rtol=0.0_dp, &
                         atol=1.0e-12_dp*abs(expected) + 1.0e-12_dp*foams(n)%mu(1))
        call note('volumetric stress', &
                  (maxval(abs(stress(1:3) - expected)) + abs(stress(4)))/max(abs(expected), foams(n)%mu(1)))
        scale = abs(tangent(1, 1))
        call check_close('volumetric_tangent_isotropic_'//trim(foam_names(n))//'_'//digit(k), &
                         max(abs(tangent(2, 2) - tangent(1, 1)), abs(tangent(3, 3) - tangent(1, 1)), &
                             abs(tangent(1, 3) - tangent(1, 2)), abs(tangent(2, 3) - tangent(1, 2)), &
                             abs(tangent(4, 4) - 0.5_dp*(tangent(1, 1) - tangent(1, 2)))), 0.0_dp, &
                         rtol=0.0_dp, atol=1.0e-10_dp*scale)
      end do
    end do
  end subroutine volumetric_compression

  !> 2d. Simple shear F = I + gamma e_r e_z (plane strain, J = 1): P_rz = dW/dgamma and sigma_rz = P_rz
  !> (sigma = P F^T, F_zr = 0, F_zz = 1); dW/dgamma by the 4-point formula with h = 1e-3 (truncation
  !> h^4 |W^(5)|/30 ~ 1e-12 |alpha|^4 relative, round-off eps |W|/h ~ 1e-13: tolerance 1e-8 relative
  !> to the shear stress, plus 1e-8 mu0 where it vanishes). The universal relation of isotropic
  !> elasticity in simple shear, sigma_11 - sigma_22 = gamma sigma_12 (Rivlin 1948; Truesdell & Noll 1965,
  !> "The non-linear field theories of mechanics"), to 1e-10.
  subroutine simple_shear()
    real(dp), parameter :: h = 1.0e-3_dp
    real(dp) :: gamma, f(3, 3), stress(4), tangent(4, 4), derivative, shear, bulk
    integer :: n, k
    do n = 1, size(foams)
      call hyperfoam_initial_moduli(foams(n), shear, bulk)
      do k = 1, 8
        gamma = 0.25_dp*k                      ! to gamma = 2 (stretches 2.41 and 0.41)
        f = diagonal([1.0_dp, 1.0_dp, 1.0_dp])
        f(1, 2) = gamma
        call hyperfoam_response(foams(n), f, stress, tangent)
        derivative = (8.0_dp*(shear_energy(foams(n), gamma + h) - shear_energy(foams(n), gamma - h)) &
                      - (shear_energy(foams(n), gamma + 2.0_dp*h) - shear_energy(foams(n), gamma - 2.0_dp*h)))/(12.0_dp*h)
        call check_close('simple_shear_stress_is_dW_dgamma_'//trim(foam_names(n))//'_'//digit(k), stress(4), &
                         derivative, rtol=1.0e-8_dp, atol=1.0e-8_dp*shear)
        call note('simple shear sigma_12 vs dW/dgamma', abs(stress(4) - derivative)/max(abs(derivative), shear))
        call check_close('simple_shear_universal_relation_'//trim(foam_names(n))//'_'//digit(k), &
                         stress(1) - stress(2), gamma*stress(4), rtol=1.0e-10_dp, atol=1.0e-10_dp*shear)
        call note('simple shear s11 - s22 = gamma s12', &
                  abs(stress(1) - stress(2) - gamma*stress(4))/max(abs(gamma*stress(4)), shear))
      end do
    end do
  end subroutine simple_shear

  !> W in simple shear of amount g.
  real(dp) function shear_energy(law, g)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: g
    real(dp) :: m(3, 3)
    m = diagonal([1.0_dp, 1.0_dp, 1.0_dp])
    m(1, 2) = g
    shear_energy = energy_of_f(law, m)
  end function shear_energy

  !> A random deformation of the kinds the tests need: F = R(angle) U with U = Q diag(l1, l2) Q^T
  !> in-plane (Q another rotation) and l3 the hoop stretch.
  function deformation_of(angle, frame, l1, l2, l3) result(f)
    real(dp), intent(in) :: angle, frame, l1, l2, l3
    real(dp) :: f(3, 3), q(3, 3)
    q = rotation(frame)
    f = matmul(rotation(angle), matmul(q, matmul(diagonal([l1, l2, l3]), transpose(q))))
  end function deformation_of

  !> The deformations of tests 3 and 4: random stretches in [0.2, 1.8], two equal in-plane stretches,
  !> three equal, uniaxial 80 % compression (0.2, 1, 1), a plane of 0.2 x 0.2 with hoop 1, tension.
  subroutine deformation_set(set)
    real(dp), intent(out) :: set(3, 3, 10)
    integer :: k
    do k = 1, 4
      set(:, :, k) = deformation_of(2.0_dp*pi*uniform(), 2.0_dp*pi*uniform(), 0.2_dp + 1.6_dp*uniform(), &
                                    0.2_dp + 1.6_dp*uniform(), 0.2_dp + 1.6_dp*uniform())
    end do
    set(:, :, 5) = deformation_of(0.7_dp, 0.3_dp, 0.6_dp, 0.6_dp, 1.1_dp)       ! lam1 = lam2
    set(:, :, 6) = deformation_of(-1.2_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.5_dp)      ! all equal
    set(:, :, 7) = deformation_of(0.4_dp, 1.0_dp, 1.0_dp, 0.2_dp, 1.0_dp)       ! 80 % compression, lam1 = lam3
    set(:, :, 8) = deformation_of(2.1_dp, 0.5_dp, 0.2_dp, 0.2_dp, 1.0_dp)       ! 0.2 x 0.2 in plane
    set(:, :, 9) = deformation_of(0.9_dp, -0.4_dp, 1.8_dp, 1.3_dp, 1.5_dp)      ! tension
    set(:, :, 10) = deformation_of(0.2_dp, 0.8_dp, 0.9_dp, 0.9_dp + 1.0e-6_dp, 1.0_dp) ! nearly equal
  end subroutine deformation_set

  !> 3. S = 2 dW/dC: W(C) = W(sqrt(C)) (W is objective), S_IJ = 2 dW/dC_IJ as the derivative along
  !> E = e_I e_I or (e_1 e_2 + e_2 e_1)/2 (dW(C + t E)/dt = S : E/2 = S_II/2 or S_12/2),
  !> pushed forward: sigma = J^-1 F S F^T, against the code's sigma. The 4-point formula with a step
  !> 1e-3 times the smallest eigenvalue of C: truncation (1e-3)^4 |alpha|^4/30 ~ 1e-10 relative, round-off
  !> eps |W| / (h |S|) ~ 1e-12; tolerance 1e-7 of the largest stress component. And the first
  !> Piola-Kirchhoff P = dW/dF (differences over the five entries of F) against J sigma F^-T, same tolerance.
  subroutine stress_is_energy_derivative()
    real(dp) :: set(3, 3, 10), f(3, 3), c(3, 3), e(3, 3), s(3, 3), sigma(3, 3), stress(4), tangent(4, 4)
    real(dp) :: step, p(3, 3), expected(3, 3)
    integer :: n, k, q, i, j
    integer, parameter :: vi(4) = [1, 2, 3, 1], vj(4) = [1, 2, 3, 2]
    call deformation_set(set)
    do n = 1, size(foams)
      do k = 1, size(set, 3)
        f = set(:, :, k)
        c = matmul(transpose(f), f)
        step = 1.0e-3_dp*smallest_eigenvalue(c)
        s = 0.0_dp
        do q = 1, 4
          e = 0.0_dp
          e(vi(q), vj(q)) = 0.5_dp
          e(vj(q), vi(q)) = e(vj(q), vi(q)) + 0.5_dp
          ! d W(C + t E)/dt = dW/dC : E = S : E / 2, and S : E = S_qq for q = 1..3, S_12 for the shear pair.
          s(vi(q), vj(q)) = 2.0_dp*difference_c(foams(n), c, step, e)
          s(vj(q), vi(q)) = s(vi(q), vj(q))
        end do
        sigma = matmul(f, matmul(s, transpose(f)))/volume_of(f)
        call hyperfoam_response(foams(n), f, stress, tangent)
        call check_close('stress_from_energy_'//trim(foam_names(n))//'_'//digit(k), &
                         maxval(abs(voigt_of(sigma) - stress)), 0.0_dp, rtol=0.0_dp, &
                         atol=1.0e-7_dp*maxval(abs(stress)))
        call note('sigma vs 2 dW/dC pushed forward', maxval(abs(voigt_of(sigma) - stress))/maxval(abs(stress)))
        ! P = dW/dF over the entries of the in-plane block and the hoop stretch.
        p = 0.0_dp
        step = 1.0e-3_dp*sqrt(smallest_eigenvalue(c))
        do j = 1, 3
          do i = 1, 3
            if ((i == 3 .or. j == 3) .and. i /= j) cycle
            p(i, j) = difference_f(foams(n), f, step, i, j)
          end do
        end do
        expected = volume_of(f)*matmul(tensor_of(stress), transpose(inverse(f)))
        call check_close('first_piola_from_energy_'//trim(foam_names(n))//'_'//digit(k), &
                         maxval(abs(p - expected)), 0.0_dp, rtol=0.0_dp, atol=1.0e-7_dp*maxval(abs(expected)))
        call note('P vs dW/dF', maxval(abs(p - expected))/maxval(abs(expected)))
      end do
    end do
  end subroutine stress_is_energy_derivative

  !> dW(C + t E)/dt at t = 0 by the 4-point formula.
  real(dp) function difference_c(law, c, h, direction)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: c(3, 3), h, direction(3, 3)
    difference_c = (8.0_dp*(energy_of_c(law, c + h*direction) - energy_of_c(law, c - h*direction)) &
                    - (energy_of_c(law, c + 2.0_dp*h*direction) - energy_of_c(law, c - 2.0_dp*h*direction))) &
                   /(12.0_dp*h)
  end function difference_c

  !> dW/dF_ij by the 4-point formula.
  real(dp) function difference_f(law, f, h, i, j)
    type(hyperfoam_t), intent(in) :: law
    real(dp), intent(in) :: f(3, 3), h
    integer, intent(in) :: i, j
    real(dp) :: d(3, 3)
    d = 0.0_dp
    d(i, j) = 1.0_dp
    difference_f = (8.0_dp*(energy_of_f(law, f + h*d) - energy_of_f(law, f - h*d)) &
                    - (energy_of_f(law, f + 2.0_dp*h*d) - energy_of_f(law, f - 2.0_dp*h*d)))/(12.0_dp*h)
  end function difference_f

  !> 4. CC = 2 dS/dC and c = J^-1 F F F F CC: the code's S(C) = J U^-1 sigma(U) U^-1 at U = sqrt(C)
  !> differentiated along the four directions E_q (as in test 3: CC_IJKL E_KL = CC_IJq), then pushed
  !> forward with the F of the state (R U, so the rotation is in the test), against the code's tangent
  !> at F. The 4-point formula with a step 1e-4 times the smallest eigenvalue of C: truncation
  !> (1e-4)^4 |alpha|^5/30 ~ 1e-12 relative, round-off eps/1e-4 ~ 1e-12 times the condition of the
  !> push-forward (lam_max/lam_min)^4 <= 9^4 ~ 1e4: tolerance 1e-6 of the largest tangent component.
  subroutine tangent_is_stress_derivative()
    real(dp) :: set(3, 3, 10), f(3, 3), c(3, 3), e(3, 3), stress(4), tangent(4, 4), material(4, 4)
    real(dp) :: step, plus(3, 3), minus(3, 3), derivative(3, 3), spatial(4, 4)
    integer :: n, k, q
    integer, parameter :: vi(4) = [1, 2, 3, 1], vj(4) = [1, 2, 3, 2]
    call deformation_set(set)
    do n = 1, size(foams)
      do k = 1, size(set, 3)
        f = set(:, :, k)
        c = matmul(transpose(f), f)
        step = 1.0e-4_dp*smallest_eigenvalue(c)
        do q = 1, 4
          e = 0.0_dp
          e(vi(q), vj(q)) = 0.5_dp
          e(vj(q), vi(q)) = e(vj(q), vi(q)) + 0.5_dp
          plus = pk2_of_c(foams(n), c + step*e) - pk2_of_c(foams(n), c - step*e)
          minus = pk2_of_c(foams(n), c + 2.0_dp*step*e) - pk2_of_c(foams(n), c - 2.0_dp*step*e)
          derivative = (8.0_dp*plus - minus)/(12.0_dp*step)
          material(:, q) = 2.0_dp*voigt_of(derivative)
        end do
        spatial = voigt_fourth(transform_fourth(f, fourth_of(material)))/volume_of(f)
        call hyperfoam_response(foams(n), f, stress, tangent)
        call check_close('tangent_from_stress_'//trim(foam_names(n))//'_'//digit(k), &
                         maxval(abs(spatial - tangent)), 0.0_dp, rtol=0.0_dp, atol=1.0e-6_dp*maxval(abs(tangent)))
        call note('tangent vs 2 dS/dC pushed forward', maxval(abs(spatial - tangent))/maxval(abs(tangent)))
        call check_close('tangent_major_symmetry_'//trim(foam_names(n))//'_'//digit(k), &
                         maxval(abs(tangent - transpose(tangent))), 0.0_dp, rtol=0.0_dp, &
                         atol=1.0e-13_dp*maxval(abs(tangent)))
      end do
    end do
  end subroutine tangent_is_stress_derivative

  !> 5. sigma(R F) = R sigma(F) R^T, c(R F) = R R R R c(F) and W(R F) = W(F) for in-plane rotations R:
  !> the principal frames differ by R only, so to round-off (1e-12 of the largest component).
  subroutine objectivity()
    real(dp) :: set(3, 3, 10), f(3, 3), r(3, 3), stress(4), tangent(4, 4), rotated(4), rotated_tangent(4, 4)
    real(dp) :: w, w_rotated
    integer :: n, k
    call deformation_set(set)
    do n = 1, size(foams)
      do k = 1, size(set, 3)
        f = set(:, :, k)
        r = rotation(2.0_dp*pi*uniform())
        call hyperfoam_response(foams(n), f, stress, tangent, w)
        call hyperfoam_response(foams(n), matmul(r, f), rotated, rotated_tangent, w_rotated)
        call check_close('objective_stress_'//trim(foam_names(n))//'_'//digit(k), &
                         maxval(abs(rotated - voigt_of(matmul(r, matmul(tensor_of(stress), transpose(r)))))), &
                         0.0_dp, rtol=0.0_dp, atol=1.0e-12_dp*maxval(abs(stress)))
        call note('objectivity of sigma', &
                  maxval(abs(rotated - voigt_of(matmul(r, matmul(tensor_of(stress), transpose(r))))))/maxval(abs(stress)))
        call check_close('objective_tangent_'//trim(foam_names(n))//'_'//digit(k), &
                         maxval(abs(rotated_tangent - voigt_fourth(transform_fourth(r, fourth_of(tangent))))), &
                         0.0_dp, rtol=0.0_dp, atol=1.0e-12_dp*maxval(abs(tangent)))
        call note('objectivity of the tangent', &
                  maxval(abs(rotated_tangent - voigt_fourth(transform_fourth(r, fourth_of(tangent)))))/maxval(abs(tangent)))
        call check_close('objective_energy_'//trim(foam_names(n))//'_'//digit(k), w_rotated, w, &
                         rtol=1.0e-12_dp, atol=1.0e-14_dp*foams(n)%mu(1))
      end do
    end do
  end subroutine objectivity

  !> 6. The parameter check: every good foam passes; each bad parameter gives its message.
  subroutine parameter_checks()
    type(hyperfoam_t) :: bad, empty
    real(dp) :: nan
    integer :: n
    do n = 1, size(foams)
      call check('check_accepts_'//trim(foam_names(n)), len(hyperfoam_check(foams(n))) == 0, hyperfoam_check(foams(n)))
    end do
    nan = ieee_value(nan, ieee_quiet_nan)
    call check_text_contains('check_not_given', hyperfoam_check(empty), 'no terms')
    bad = foam([1.0e5_dp], [0.0_dp], [0.1_dp])
    call check_text_contains('check_alpha_zero', hyperfoam_check(bad), 'alpha_1 of the hyperfoam must not be 0')
    bad = foam([1.0e5_dp, 1.0e4_dp], [2.0_dp, 4.0_dp], [0.1_dp, 0.5_dp])
    call check_text_contains('check_nu_half', hyperfoam_check(bad), 'nu_2 of the hyperfoam must be in (-1, 0.5)')
    bad = foam([1.0e5_dp], [2.0_dp], [-1.0_dp])
    call check_text_contains('check_nu_minus_one', hyperfoam_check(bad), 'nu_1 of the hyperfoam must be in (-1, 0.5)')
    bad = foam([1.0e5_dp, -2.0e5_dp], [2.0_dp, 4.0_dp], [0.1_dp, 0.1_dp])
    call check_text_contains('check_shear_positive', hyperfoam_check(bad), 'mu0 = sum mu_i of the hyperfoam must be > 0')
    bad = foam([1.0e5_dp, -0.5e5_dp], [2.0_dp, 4.0_dp], [0.0_dp, 0.45_dp])   ! K0 = 2e5/3 - 1e5 (1/3 + 4.5) < 0
    call check_text_contains('check_bulk_positive', hyperfoam_check(bad), 'K0 = sum 2 mu_i (1/3 + beta_i)')
    bad = foam([1.0e5_dp, 1.0e4_dp], [2.0_dp], [0.1_dp, 0.1_dp])
    call check_text_contains('check_lengths', hyperfoam_check(bad), 'as many alpha_i and nu_i as mu_i')
    bad = foam([(1.0e4_dp, n = 1, 7)], [(2.0_dp, n = 1, 7)], [(0.1_dp, n = 1, 7)])
    call check_text_contains('check_seven_terms', hyperfoam_check(bad), '1 to 6 terms, found 7')
    bad = foam([real(dp) ::], [real(dp) ::], [real(dp) ::])
    call check_text_contains('check_zero_terms', hyperfoam_check(bad), '1 to 6 terms, found 0')
    bad = foam([1.0e5_dp], [nan], [0.1_dp])
    call check_text_contains('check_not_finite', hyperfoam_check(bad), 'not finite')
  end subroutine parameter_checks

  !> An inverted or degenerate F is not admissible: zeros, never NaN or Infinity.
  subroutine inadmissible_deformation()
    real(dp) :: f(3, 3), stress(4), tangent(4, 4), w
    logical :: admissible
    f = diagonal([1.0_dp, -0.5_dp, 1.0_dp])
    call hyperfoam_response(foams(3), f, stress, tangent, w, admissible)
    call check('inverted_not_admissible', .not. admissible .and. all(stress == 0.0_dp) .and. &
               all(tangent == 0.0_dp) .and. w == 0.0_dp)
    f = diagonal([1.0_dp, 1.0_dp, 0.0_dp])
    call hyperfoam_response(foams(3), f, stress, tangent, w, admissible)
    call check('zero_hoop_not_admissible', .not. admissible .and. all(ieee_is_finite(stress)) .and. &
               all(ieee_is_finite(tangent)))
    ! A foam without terms or with arrays of unequal length (the caller skipped hyperfoam_check): zeros.
    call hyperfoam_response(hyperfoam_t(), diagonal([0.9_dp, 0.8_dp, 1.0_dp]), stress, tangent, w, admissible)
    call check('no_terms_not_admissible', .not. admissible .and. all(stress == 0.0_dp) .and. w == 0.0_dp)
    call hyperfoam_response(foam([1.0e5_dp, 1.0e4_dp], [2.0_dp], [0.0_dp, 0.0_dp]), diagonal([0.9_dp, 0.8_dp, 1.0_dp]), &
                            stress, tangent, w, admissible)
    call check('unequal_lengths_not_admissible', .not. admissible .and. all(tangent == 0.0_dp))
    ! Overflow: lam^alpha = 1e-3^(-200) = 1e600 is not a double: zeros, never Infinity.
    call hyperfoam_response(foam([1.0e5_dp], [-200.0_dp], [0.0_dp]), diagonal([1.0e-3_dp, 1.0_dp, 1.0_dp]), &
                            stress, tangent, w, admissible)
    call check('overflow_not_admissible', .not. admissible .and. all(stress == 0.0_dp) .and. &
               all(tangent == 0.0_dp) .and. w == 0.0_dp)
    f = diagonal([0.2_dp, 0.2_dp, 0.2_dp])    ! 99.2 % volume loss: still admissible and finite
    call hyperfoam_response(foams(5), f, stress, tangent, w, admissible)
    call check('strong_compression_finite', admissible .and. all(ieee_is_finite(stress)) .and. &
               all(ieee_is_finite(tangent)) .and. ieee_is_finite(w))
  end subroutine inadmissible_deformation

  !> The three pad foams of doc/hyperfoam.md: the two illustrative sets A and B and the *HYPERFOAM, N=2
  !> example of the CalculiX manual (C, read as MPa) (nu = 0, so the lateral stretch is 1 and the
  !> nominal stress of uniaxial compression is sum 2 mu_i/alpha_i (lam^alpha_i - 1)/lam): the check accepts
  !> them, E0 = 2 mu0 (nu0 = 0), and the code's nominal stress sigma_zz (lateral stretch 1, so the
  !> nominal stress is sigma_zz itself) equals the closed form to 1e-12 at the strains the doc tabulates
  !> (printed for the doc).
  subroutine example_sets()
    type(hyperfoam_t) :: sets(3)
    character(len=1), parameter :: names(3) = ['A', 'B', 'C']
    real(dp), parameter :: strains(5) = [0.05_dp, 0.2_dp, 0.4_dp, 0.6_dp, 0.8_dp]
    real(dp) :: stress(4), tangent(4, 4), lam, expected, shear, bulk
    integer :: n, k, i
    character(len=120) :: line
    sets(1) = foam([0.245e6_dp, 0.005e6_dp], [10.0_dp, -2.0_dp], [0.0_dp, 0.0_dp])
    sets(2) = foam([0.74e6_dp, 0.01e6_dp], [12.0_dp, -2.0_dp], [0.0_dp, 0.0_dp])
    sets(3) = foam([0.164861e6_dp, 2.302e-5_dp*1.0e6_dp], [8.88413_dp, -4.81798_dp], [0.0_dp, 0.0_dp])
    do n = 1, size(sets)
      call check('example_set_accepted_'//names(n), len(hyperfoam_check(sets(n))) == 0)
      call hyperfoam_initial_moduli(sets(n), shear, bulk)
      write(line, '(a, es10.3, a, es10.3, a, es10.3)') 'example set '//names(n)//': mu0 ', shear, ' K0 ', bulk, &
        ' E0 ', 9.0_dp*bulk*shear/(3.0_dp*bulk + shear)
      print '(a)', trim(line)
      do k = 1, size(strains)
        lam = 1.0_dp - strains(k)
        call hyperfoam_response(sets(n), diagonal([1.0_dp, lam, 1.0_dp]), stress, tangent)
        expected = 0.0_dp
        do i = 1, size(sets(n)%mu)
          expected = expected + 2.0_dp*sets(n)%mu(i)/sets(n)%alpha(i)*(lam**sets(n)%alpha(i) - 1.0_dp)/lam
        end do
        call check_close('example_set_nominal_'//names(n)//'_'//digit(k), stress(2), expected, rtol=1.0e-12_dp)
        call check_close('example_set_lateral_free_'//names(n)//'_'//digit(k), abs(stress(1)) + abs(stress(3)), &
                         0.0_dp, rtol=0.0_dp, atol=1.0e-12_dp*abs(expected))
        write(line, '(a, f5.2, a, es11.4, a, es11.4, a)') 'example set '//names(n)//': compression ', strains(k), &
          ' nominal stress ', stress(2), ' Pa, tangent D(2,2) ', tangent(2, 2), ' Pa'
        print '(a)', trim(line)
      end do
    end do
  end subroutine example_sets

end program test_hyperfoam
