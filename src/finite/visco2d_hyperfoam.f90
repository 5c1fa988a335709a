!> The hyperfoam of ABAQUS (*HYPERFOAM): the compressible Ogden-Hill law of
!> elastomeric foams (Ogden 1972, "Large deformation isotropic elasticity: on
!> the correlation of theory and experiment for compressible rubberlike
!> solids", Proc. R. Soc. Lond. A 328; Hill 1978, "Aspects of invariance in
!> solid mechanics", Adv. Appl. Mech. 18; Storakers 1986, "On material
!> representation and constitutive branching in finite compressible
!> elasticity", J. Mech. Phys. Solids 34), at one material point:
!>
!>   W = sum_i 2 mu_i/alpha_i^2 [lam1^a_i + lam2^a_i + lam3^a_i - 3 + (J^(-a_i b_i) - 1)/b_i],
!>   b_i = nu_i/(1 - 2 nu_i),
!>
!> with the principal stretches lam_a and J = lam1 lam2 lam3; mu0 = sum mu_i,
!> K0 = sum 2 mu_i (1/3 + b_i). The principal Kirchhoff stresses are
!> tau_a = lam_a dW/dlam_a = sum_i 2 mu_i/a_i (lam_a^a_i - J^(-a_i b_i)), the
!> Cauchy stresses sigma_a = tau_a/J. The spatial tangent is the principal
!> form (Bonet & Wood 2008, "Nonlinear Continuum Mechanics for Finite Element
!> Analysis", 2nd ed., ch. 6; Simo & Taylor 1991, CMAME 85, 273-310):
!>
!>   J c = sum_ab (dtau_a/dln lam_b - 2 tau_a delta_ab) n_a n_a n_b n_b
!>       + sum_(a/=b) g_ab (n_a n_b n_a n_b + n_a n_b n_b n_a),
!>   g_ab = (tau_a lam_b^2 - tau_b lam_a^2)/(lam_a^2 - lam_b^2),
!>
!> where g_ab is evaluated as C_a C_b times the divided difference of the
!> principal second Piola-Kirchhoff stress S(C_a) at a fixed J (for this law
!> S_a depends on its own C_a = lam_a^2 and on J only), which has a finite
!> limit at equal stretches (the derivative) and is computed without
!> cancellation near it. The law, its parameters and its verification:
!> doc/hyperfoam.md.
module visco2d_hyperfoam
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp
  use visco2d_strings, only: integer_text, message_real
  implicit none
  private

  public :: hyperfoam_response, hyperfoam_initial_moduli, hyperfoam_check
  public :: hyperfoam_principal, hyperfoam_energy_principal, hyperfoam_max_terms

  !> The most terms a hyperfoam has (as in ABAQUS: N <= 6).
  integer, parameter :: hyperfoam_max_terms = 6

  !> The hyperfoam's terms, as an ABAQUS *HYPERFOAM card gives them.
  type, public :: hyperfoam_t
    real(dp), allocatable :: mu(:)      !< mu_i, Pa (sum > 0)
    real(dp), allocatable :: alpha(:)   !< alpha_i (nonzero)
    real(dp), allocatable :: nu(:)      !< nu_i, the effective Poisson ratio of term i (-1 < nu < 0.5); beta_i = nu_i/(1-2nu_i)
  end type hyperfoam_t

contains

  !> Cauchy stress and spatial tangent of the hyperfoam at deformation gradient F.
  !> F(1:2,1:2) is the in-plane (r, z) block, F(3,3) the hoop stretch (1 in
  !> plane strain), F(1:2,3) = F(3,1:2) = 0 (not read). The stress is in Voigt
  !> order (rr, zz, thetatheta, rz); the tangent is the spatial elasticity
  !> tensor c_ijkl = J^-1 F_iI F_jJ F_kK F_lL CC_IJKL, CC = 4 d2W/dCdC, in the
  !> same order, the fourth row and column for the pair (1,2) with no factor
  !> 2 (D(4,4) = c_1212). A deformation with det F(1:2,1:2) <= 0, F(3,3) <= 0
  !> or a value not finite is not admissible, and so is a foam without terms
  !> or with arrays of unequal length (hyperfoam_check tells why) and a result
  !> that overflows: stress, tangent and energy are then zero and
  !> `admissible` (if present) is false, never NaN or Infinity.
  pure subroutine hyperfoam_response(foam, deformation, stress, tangent, energy, admissible)
    type(hyperfoam_t), intent(in) :: foam
    real(dp), intent(in) :: deformation(3, 3)
    real(dp), intent(out) :: stress(4)
    real(dp), intent(out), optional :: tangent(4, 4)   !< absent: the stress alone (the force of an iteration)
    real(dp), intent(out), optional :: energy
    logical, intent(out), optional :: admissible
    real(dp) :: stretch(3), direction(3, 3), volume, kirchhoff(3), modulus(3, 3), shear(3, 3)
    real(dp) :: c(3, 3, 3, 3)
    integer :: a, b, p, q
    integer, parameter :: voigt_i(4) = [1, 2, 3, 1], voigt_j(4) = [1, 2, 3, 2]
    logical :: fine

    stress = 0.0_dp
    if (present(tangent)) tangent = 0.0_dp
    if (present(energy)) energy = 0.0_dp
    if (present(admissible)) admissible = .false.
    if (.not. (allocated(foam%mu) .and. allocated(foam%alpha) .and. allocated(foam%nu))) return
    if (size(foam%mu) < 1 .or. size(foam%alpha) /= size(foam%mu) .or. size(foam%nu) /= size(foam%mu)) return
    call principal_frame(deformation, stretch, direction, fine)
    if (.not. fine) return
    volume = product(stretch)
    if (present(tangent)) then
      call hyperfoam_principal(foam, stretch, kirchhoff, modulus, shear)
    else
      kirchhoff = principal_kirchhoff(foam, stretch)
    end if
    if (present(energy)) energy = hyperfoam_energy_principal(foam, stretch)

    do a = 1, 3
      stress = stress + kirchhoff(a)/volume*[direction(1, a)**2, direction(2, a)**2, direction(3, a)**2, &
                                             direction(1, a)*direction(2, a)]
    end do
    if (.not. present(tangent)) then
      fine = all(ieee_is_finite(stress))
      if (present(energy)) fine = fine .and. ieee_is_finite(energy)
      if (.not. fine) stress = 0.0_dp
      if (.not. fine .and. present(energy)) energy = 0.0_dp
      if (present(admissible)) admissible = fine
      return
    end if

    ! The spatial tensor J c from its principal components, then divided by J.
    c = 0.0_dp
    do a = 1, 3
      do b = 1, 3
        call add_dyad(c, modulus(a, b), direction(:, a), direction(:, a), direction(:, b), direction(:, b))
        if (a /= b) then
          call add_dyad(c, shear(a, b), direction(:, a), direction(:, b), direction(:, a), direction(:, b))
          call add_dyad(c, shear(a, b), direction(:, a), direction(:, b), direction(:, b), direction(:, a))
        end if
      end do
    end do
    do q = 1, 4
      do p = 1, 4
        tangent(p, q) = c(voigt_i(p), voigt_j(p), voigt_i(q), voigt_j(q))/volume
      end do
    end do
    fine = all(ieee_is_finite(stress)) .and. all(ieee_is_finite(tangent))
    if (present(energy)) fine = fine .and. ieee_is_finite(energy)
    if (.not. fine) then
      stress = 0.0_dp
      tangent = 0.0_dp
      if (present(energy)) energy = 0.0_dp
    end if
    if (present(admissible)) admissible = fine
  end subroutine hyperfoam_response

  !> The principal Kirchhoff stresses alone, tau_a = sum_i 2 mu_i/alpha_i
  !> (lam_a^alpha_i - J^(-alpha_i beta_i)): hyperfoam_principal's first output.
  pure function principal_kirchhoff(foam, stretch) result(kirchhoff)
    type(hyperfoam_t), intent(in) :: foam
    real(dp), intent(in) :: stretch(3)
    real(dp) :: kirchhoff(3)
    real(dp) :: volumetric, alpha
    integer :: i
    kirchhoff = 0.0_dp
    do i = 1, size(foam%mu)
      alpha = foam%alpha(i)
      volumetric = product(stretch)**(-alpha*poisson_beta(foam%nu(i)))
      kirchhoff = kirchhoff + 2.0_dp*foam%mu(i)/alpha*(stretch**alpha - volumetric)
    end do
  end function principal_kirchhoff

  !> The principal Kirchhoff stresses tau_a at the principal stretches, and
  !> the principal parts of J c: modulus(a, b) = dtau_a/dln lam_b - 2 tau_a
  !> delta_ab and shear(a, b) = g_ab (the coefficient of n_a n_b n_a n_b, its
  !> limit at lam_a = lam_b; shear(a, a) = 0). The stretches must be > 0.
  pure subroutine hyperfoam_principal(foam, stretch, kirchhoff, modulus, shear)
    type(hyperfoam_t), intent(in) :: foam
    real(dp), intent(in) :: stretch(3)
    real(dp), intent(out) :: kirchhoff(3), modulus(3, 3), shear(3, 3)
    real(dp) :: volume, beta, alpha, coefficient, volumetric, squares(3)
    integer :: i, a, b

    volume = product(stretch)
    squares = stretch**2
    kirchhoff = 0.0_dp
    modulus = 0.0_dp
    shear = 0.0_dp
    do i = 1, size(foam%mu)
      alpha = foam%alpha(i)
      beta = poisson_beta(foam%nu(i))
      coefficient = 2.0_dp*foam%mu(i)/alpha
      volumetric = volume**(-alpha*beta)
      do a = 1, 3
        kirchhoff(a) = kirchhoff(a) + coefficient*(stretch(a)**alpha - volumetric)
        ! dtau_a/dln lam_b = sum_i 2 mu_i (lam_a^alpha_i delta_ab + beta_i J^(-alpha_i beta_i)).
        modulus(a, :) = modulus(a, :) + 2.0_dp*foam%mu(i)*beta*volumetric
        modulus(a, a) = modulus(a, a) + 2.0_dp*foam%mu(i)*stretch(a)**alpha
        do b = 1, 3
          if (b == a) cycle
          ! C_a C_b [S_b - S_a]/(C_b - C_a) with S(x) = 2 mu/alpha (x^(alpha/2-1) - J^(-alpha beta)/x):
          ! the divided difference of -1/x is 1/(C_a C_b) exactly.
          shear(a, b) = shear(a, b) + coefficient*(squares(a)*squares(b) &
            *power_divided_difference(squares(a), squares(b), 0.5_dp*alpha - 1.0_dp) + volumetric)
        end do
      end do
    end do
    do a = 1, 3
      modulus(a, a) = modulus(a, a) - 2.0_dp*kirchhoff(a)
    end do
  end subroutine hyperfoam_principal

  !> W per unit reference volume at the principal stretches (> 0), J/m^3.
  !> The volumetric part (J^(-alpha beta) - 1)/beta is evaluated as
  !> -alpha ln J (e^x - 1)/x, x = -alpha beta ln J, so that nu = 0 (beta = 0)
  !> gives its limit -alpha ln J.
  pure real(dp) function hyperfoam_energy_principal(foam, stretch) result(energy)
    type(hyperfoam_t), intent(in) :: foam
    real(dp), intent(in) :: stretch(3)
    real(dp) :: log_volume, alpha, beta
    integer :: i
    log_volume = sum(log(stretch))
    energy = 0.0_dp
    do i = 1, size(foam%mu)
      alpha = foam%alpha(i)
      beta = poisson_beta(foam%nu(i))
      energy = energy + 2.0_dp*foam%mu(i)/alpha**2*(sum(stretch**alpha) - 3.0_dp &
        - alpha*log_volume*exponential_ratio(-alpha*beta*log_volume))
    end do
  end function hyperfoam_energy_principal

  !> Small-strain moduli of the law: mu0 = sum mu_i, K0 = sum 2 mu_i (1/3 + beta_i).
  pure subroutine hyperfoam_initial_moduli(foam, shear, bulk)
    type(hyperfoam_t), intent(in) :: foam
    real(dp), intent(out) :: shear, bulk
    integer :: i
    shear = sum(foam%mu)
    bulk = 0.0_dp
    do i = 1, size(foam%mu)
      bulk = bulk + 2.0_dp*foam%mu(i)*(1.0_dp/3.0_dp + poisson_beta(foam%nu(i)))
    end do
  end subroutine hyperfoam_initial_moduli

  !> Validity check of the parameters: an empty message if fine, else what is
  !> wrong. Checked: 1 to 6 terms, mu, alpha and nu of the same length, every
  !> value finite, every alpha_i /= 0, every nu_i in (-1, 0.5), mu0 = sum mu_i
  !> > 0 and K0 = sum 2 mu_i (1/3 + beta_i) > 0. Not checked: Drucker
  !> stability at finite strain (a fit with negative mu_i may lose it at a
  !> large strain; doc/hyperfoam.md).
  pure function hyperfoam_check(foam) result(message)
    type(hyperfoam_t), intent(in) :: foam
    character(:), allocatable :: message
    real(dp) :: shear, bulk
    integer :: i, terms
    message = ''
    if (.not. (allocated(foam%mu) .and. allocated(foam%alpha) .and. allocated(foam%nu))) then
      message = 'the hyperfoam has no terms (mu_i, alpha_i and nu_i not given)'
      return
    end if
    terms = size(foam%mu)
    if (size(foam%alpha) /= terms .or. size(foam%nu) /= terms) then
      message = 'the hyperfoam needs as many alpha_i and nu_i as mu_i: '//integer_text(terms)//' mu, ' &
        //integer_text(size(foam%alpha))//' alpha, '//integer_text(size(foam%nu))//' nu'
      return
    end if
    if (terms < 1 .or. terms > hyperfoam_max_terms) then
      message = 'a hyperfoam has 1 to '//integer_text(hyperfoam_max_terms)//' terms, found '//integer_text(terms)
      return
    end if
    do i = 1, terms
      if (.not. (ieee_is_finite(foam%mu(i)) .and. ieee_is_finite(foam%alpha(i)) .and. ieee_is_finite(foam%nu(i)))) then
        message = 'term '//integer_text(i)//' of the hyperfoam has a value that is not finite'
        return
      end if
      if (foam%alpha(i) == 0.0_dp) then
        message = 'alpha_'//integer_text(i)//' of the hyperfoam must not be 0'
        return
      end if
      if (.not. (foam%nu(i) > -1.0_dp .and. foam%nu(i) < 0.5_dp)) then
        message = 'nu_'//integer_text(i)//' of the hyperfoam must be in (-1, 0.5), found '//message_real(foam%nu(i))
        return
      end if
    end do
    call hyperfoam_initial_moduli(foam, shear, bulk)
    if (.not. shear > 0.0_dp) then
      message = 'the initial shear modulus mu0 = sum mu_i of the hyperfoam must be > 0, found ' &
        //message_real(shear)//' Pa'
      return
    end if
    if (.not. bulk > 0.0_dp) then
      message = 'the initial bulk modulus K0 = sum 2 mu_i (1/3 + beta_i) of the hyperfoam must be > 0, found ' &
        //message_real(bulk)//' Pa'
      return
    end if
  end function hyperfoam_check

  !> beta = nu/(1 - 2 nu).
  elemental real(dp) function poisson_beta(nu) result(beta)
    real(dp), intent(in) :: nu
    beta = nu/(1.0_dp - 2.0_dp*nu)
  end function poisson_beta

  !> (e^x - 1)/x, its series near 0 (error below x^5/720 for |x| < 1e-3).
  elemental real(dp) function exponential_ratio(x) result(ratio)
    real(dp), intent(in) :: x
    if (abs(x) < 1.0e-3_dp) then
      ratio = 1.0_dp + x/2.0_dp*(1.0_dp + x/3.0_dp*(1.0_dp + x/4.0_dp*(1.0_dp + x/5.0_dp)))
    else
      ratio = (exp(x) - 1.0_dp)/x
    end if
  end function exponential_ratio

  !> (y^p - x^p)/(y - x) for x, y > 0, and its limit p x^(p-1) at x = y.
  !> Within a relative distance 1e-3 it is the central-difference expansion
  !> about the mean m, p m^(p-1) + p(p-1)(p-2) m^(p-3) e^2/6 (e half the
  !> distance; the next term, of relative size p^4 (e/m)^4/120, is below 1e-13
  !> for |p| < 20); outside, the quotient loses at most eps/1e-3 to round-off.
  elemental real(dp) function power_divided_difference(x, y, p) result(difference)
    real(dp), intent(in) :: x, y, p
    real(dp) :: mean, half
    mean = 0.5_dp*(x + y)
    half = 0.5_dp*(y - x)
    if (abs(half) <= 0.5e-3_dp*mean) then
      difference = p*mean**(p - 1.0_dp) + p*(p - 1.0_dp)*(p - 2.0_dp)*mean**(p - 3.0_dp)*half**2/6.0_dp
    else
      difference = (y**p - x**p)/(y - x)
    end if
  end function power_divided_difference

  !> The principal stretches and directions (columns) of F: the in-plane
  !> 2x2 block of b = F F^T in closed form (the smaller eigenvalue as det/the
  !> larger, free of cancellation), the hoop direction principal.
  pure subroutine principal_frame(deformation, stretch, direction, fine)
    real(dp), intent(in) :: deformation(3, 3)
    real(dp), intent(out) :: stretch(3), direction(3, 3)
    logical, intent(out) :: fine
    real(dp) :: b11, b22, b12, mean, radius, larger, area, angle
    stretch = 1.0_dp
    direction = 0.0_dp
    direction(1, 1) = 1.0_dp
    direction(2, 2) = 1.0_dp
    direction(3, 3) = 1.0_dp
    fine = all(ieee_is_finite(deformation(1:2, 1:2))) .and. ieee_is_finite(deformation(3, 3))
    if (.not. fine) return
    area = deformation(1, 1)*deformation(2, 2) - deformation(1, 2)*deformation(2, 1)
    fine = area > 0.0_dp .and. deformation(3, 3) > 0.0_dp
    if (.not. fine) return
    b11 = deformation(1, 1)**2 + deformation(1, 2)**2
    b22 = deformation(2, 1)**2 + deformation(2, 2)**2
    b12 = deformation(1, 1)*deformation(2, 1) + deformation(1, 2)*deformation(2, 2)
    mean = 0.5_dp*(b11 + b22)
    radius = hypot(0.5_dp*(b11 - b22), b12)
    larger = mean + radius
    stretch(1) = sqrt(larger)
    stretch(2) = area/stretch(1)
    stretch(3) = deformation(3, 3)
    if (radius > 0.0_dp) then
      angle = 0.5_dp*atan2(2.0_dp*b12, b11 - b22)
    else
      angle = 0.0_dp
    end if
    direction(1:2, 1) = [cos(angle), sin(angle)]
    direction(1:2, 2) = [-sin(angle), cos(angle)]
  end subroutine principal_frame

  !> c = c + s u v w x (the dyadic product of four vectors).
  pure subroutine add_dyad(c, s, u, v, w, x)
    real(dp), intent(inout) :: c(3, 3, 3, 3)
    real(dp), intent(in) :: s, u(3), v(3), w(3), x(3)
    integer :: i, j, k, l
    if (s == 0.0_dp) return
    do l = 1, 3
      do k = 1, 3
        do j = 1, 3
          do i = 1, 3
            c(i, j, k, l) = c(i, j, k, l) + s*u(i)*v(j)*w(k)*x(l)
          end do
        end do
      end do
    end do
  end subroutine add_dyad

end module visco2d_hyperfoam
