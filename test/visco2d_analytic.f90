!> Closed-form and exact reference solutions of linear viscoelasticity, for
!> comparison with finite-element results; and Hertz's stresses on the axis
!> under a sphere's contact (hertz_axis_shear, hertz_axis_maximum).
!>
!> The material is elastic in bulk and viscoelastic in shear:
!>
!>   s_ij(t) = 2 int_0^t phi1(t - tau) de_ij/dtau dtau,   sigma = K theta,
!>
!> with the Prony (generalized Maxwell) relaxation modulus
!>
!>   phi1(t) = G(t) = sum_m G_m exp(-beta_m t),   G_m > 0 (Pa), beta_m >= 0 (1/s).
!>
!> A term with beta_m = 0 is a long-term (equilibrium) modulus. Without one the
!> material is a fluid in shear: under a sustained shear stress it flows.
!>
!> In the Laplace domain (f(t) -> fbar(s)), with the Carson transform
!> fhat(s) = s fbar(s), the law reads s_ij-hat = 2 Ghat e_ij-hat, with
!>
!>   Ghat(s) = s Gbar(s) = sum_m G_m s/(s + beta_m),
!>
!> so by the correspondence principle a quasi-static elastic solution becomes
!> the viscoelastic one when G is replaced by Ghat(s) and every load by its
!> Carson transform (a step of height p: p/s becomes p in Carson form, i.e. the
!> Laplace transform of the response is (elastic formula with G -> Ghat)/s).
!>
!> This module depends on visco2d_kinds only: it is independent of the
!> library's viscoelastic code on purpose. Nothing here stops the program:
!> invalid input gives a quiet NaN result, which every comparison rejects.
module visco2d_analytic
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: shear_relaxation, shear_ramp_response, uniaxial_creep_compliance_one_term
  public :: cylinder_bore_displacement, cylinder_bore_displacement_elastic
  public :: hertz_axis_shear, hertz_axis_maximum

  !> Which function of s a root search is for (see find_root).
  integer, parameter :: function_gbar = 1, function_bulk_shear = 2

  !> f(t) = constant + slope t + sum_k residue(k) exp(pole(k) t): the inverse
  !> Laplace transform of a proper rational function with (at most) a double
  !> pole at s = 0 and simple real negative poles.
  type :: pole_expansion_t
    real(dp) :: constant = 0.0_dp
    real(dp) :: slope = 0.0_dp
    integer :: count = 0
    real(dp), allocatable :: pole(:), residue(:)
  end type pole_expansion_t

contains

  !> The shear relaxation modulus phi1(t) = G(t) = sum_m G_m exp(-beta_m t), Pa.
  !> `shear` (G_m, Pa) and `beta` (beta_m, 1/s) have the same size; t in s.
  !> No check of the signs is made (any real Prony series is evaluated).
  pure real(dp) function shear_relaxation(shear, beta, t)
    real(dp), intent(in) :: shear(:)   !< G_m, Pa
    real(dp), intent(in) :: beta(:)    !< beta_m, 1/s
    real(dp), intent(in) :: t          !< time, s
    shear_relaxation = sum(shear*exp(-beta*t))
  end function shear_relaxation

  !> Deviatoric stress of a deviatoric strain component growing at a constant
  !> `rate` (1/s) from t = 0 (zero before):
  !>
  !>   s(t) = 2 int_0^t phi1(t - tau) rate dtau = 2 rate sum_m G_m t (1 - exp(-beta_m t))/(beta_m t),
  !>
  !> the beta_m t -> 0 limit 2 rate G_m t being included without cancellation:
  !> (1 - exp(-x))/x is evaluated as -expm1(-x)/x with a series for small x.
  !> Requires beta_m >= 0 (returns NaN otherwise). Returns 0 for t <= 0.
  pure real(dp) function shear_ramp_response(shear, beta, rate, t)
    real(dp), intent(in) :: shear(:)   !< G_m, Pa
    real(dp), intent(in) :: beta(:)    !< beta_m >= 0, 1/s
    real(dp), intent(in) :: rate       !< strain rate de/dt, 1/s
    real(dp), intent(in) :: t          !< time, s
    integer :: m
    if (size(shear) /= size(beta) .or. any(beta < 0.0_dp)) then
      shear_ramp_response = ieee_value(1.0_dp, ieee_quiet_nan)
      return
    end if
    shear_ramp_response = 0.0_dp
    if (t <= 0.0_dp) return
    do m = 1, size(shear)
      shear_ramp_response = shear_ramp_response + shear(m)*relative_decay(beta(m)*t)
    end do
    shear_ramp_response = 2.0_dp*rate*t*shear_ramp_response
  end function shear_ramp_response

  !> Uniaxial creep compliance of the one-term Maxwell shear law
  !> G(t) = G exp(-beta t) with elastic bulk modulus K: the axial strain per unit
  !> axial stress applied as a step at t = 0 (1/Pa, t in s).
  !>
  !> Derivation (Laplace domain, Carson transforms fhat = s fbar):
  !>   Ghat = s Gbar = G s/(s + beta).
  !> The elastic Young modulus is E = 9 K G/(3 K + G), so by correspondence
  !>   Ehat = 9 K Ghat/(3 K + Ghat),
  !>   1/Ehat = (3 K + Ghat)/(9 K Ghat) = 1/(3 Ghat) + 1/(9 K).
  !> A unit stress step has the Carson transform 1, so the strain has the Carson
  !> transform Dhat = 1/Ehat and the Laplace transform
  !>   Dbar = Dhat/s = (s + beta)/(3 G s^2) + 1/(9 K s)
  !>        = 1/(3 G s) + beta/(3 G s^2) + 1/(9 K s),
  !> whose inverse is
  !>   D(t) = (1 + beta t)/(3 G) + 1/(9 K).
  !> (D(0) = (3 K + G)/(9 K G) = 1/E0, the instantaneous elastic compliance;
  !> the shear part creeps linearly, the bulk part is instantaneous.)
  !> Requires G > 0, K > 0, beta >= 0 (returns NaN otherwise); returns 0 for t < 0.
  pure real(dp) function uniaxial_creep_compliance_one_term(shear, beta, bulk, t)
    real(dp), intent(in) :: shear   !< G, Pa
    real(dp), intent(in) :: beta    !< beta, 1/s
    real(dp), intent(in) :: bulk    !< K, Pa
    real(dp), intent(in) :: t       !< time, s
    if (.not. (shear > 0.0_dp .and. bulk > 0.0_dp .and. beta >= 0.0_dp)) then
      uniaxial_creep_compliance_one_term = ieee_value(1.0_dp, ieee_quiet_nan)
    else if (t < 0.0_dp) then
      uniaxial_creep_compliance_one_term = 0.0_dp
    else
      uniaxial_creep_compliance_one_term = (1.0_dp + beta*t)/(3.0_dp*shear) + 1.0_dp/(9.0_dp*bulk)
    end if
  end function uniaxial_creep_compliance_one_term

  !> Radial displacement of the bore, u(a), of an elastic thick-walled cylinder
  !> in plane strain (axial strain zero) under internal pressure p, outer
  !> surface free. With u = A r + B/r, lambda = K - 2G/3,
  !>   sigma_r = 2 (K + G/3) A - 2 G B/r^2,  sigma_r(a) = -p,  sigma_r(b) = 0
  !> give B = p a^2 b^2/(2 G (b^2 - a^2)), A = p a^2/(2 (K + G/3)(b^2 - a^2)), so
  !>   u(a) = p a/(b^2 - a^2) [a^2/(2 (K + G/3)) + b^2/(2 G)].
  !> SI units (Pa, m). No check of the input.
  pure real(dp) function cylinder_bore_displacement_elastic(shear_modulus, bulk, inner, outer, pressure)
    real(dp), intent(in) :: shear_modulus   !< G, Pa
    real(dp), intent(in) :: bulk            !< K, Pa
    real(dp), intent(in) :: inner           !< bore radius a, m
    real(dp), intent(in) :: outer           !< outer radius b, m
    real(dp), intent(in) :: pressure        !< internal pressure p (positive = pushing outward), Pa
    cylinder_bore_displacement_elastic = pressure*inner/(outer**2 - inner**2) &
      *(inner**2/(2.0_dp*(bulk + shear_modulus/3.0_dp)) + outer**2/(2.0_dp*shear_modulus))
  end function cylinder_bore_displacement_elastic

  !> Radial displacement of the bore, u(a, t), of a viscoelastic thick-walled
  !> cylinder in plane strain (axial strain zero), inner radius a, outer radius
  !> b (free), under an internal pressure p0 applied as a step at t = 0 and held.
  !>
  !> Correspondence principle (G -> Ghat(s) = sum_m G_m s/(s + beta_m), p -> p0/s):
  !>
  !>   ubar(a, s) = p0 a/(b^2 - a^2) [ a^2/2 F2(s) + b^2/2 F1(s) ],
  !>   F1(s) = 1/(s Ghat(s)) = 1/(s^2 Gbar(s)),   Gbar(s) = sum_m G_m/(s + beta_m),
  !>   F2(s) = 1/(s (K + Ghat(s)/3)) = 1/(s J(s)),
  !>   J(s)  = K + Ghat(s)/3 = K + G0/3 - (1/3) sum_m G_m beta_m/(s + beta_m),  G0 = sum_m G_m.
  !>
  !> Both are proper rational functions (the zeros of Gbar and J are the poles;
  !> the -beta_m are zeros of F1 and F2, not poles). Let beta_(1) < ... < beta_(n)
  !> be the distinct rates (equal rates are merged by adding their moduli).
  !>
  !> F1. Gbar is a sum of simple poles with positive residues G_m, so on each
  !> interval (-beta_(k+1), -beta_(k)) it decreases strictly (Gbar' = -sum
  !> G_m/(s + beta_m)^2 < 0) from +inf to -inf: exactly one zero z_k in each, and
  !> none outside (Gbar > 0 for s > -beta_(1), < 0 for s < -beta_(n)). The n - 1
  !> zeros interlace with the -beta_m. Residue at z_k: 1/(z_k^2 Gbar'(z_k)) < 0.
  !> At s = 0:
  !>  * no beta = 0 (a fluid in shear): Gbar(0) = sum G_m/beta_m = H0 is finite,
  !>    so F1 has a DOUBLE pole at 0: F1 = 1/(s^2 Gbar) with Gbar = H0 + H1 s + ...,
  !>    H1 = Gbar'(0) = -sum G_m/beta_m^2, contributing t/H0 - H1/H0^2 (creep flow,
  !>    growing like t; for one term (1 + beta t)/G);
  !>  * a term beta = 0 (modulus G_inf): Gbar = G_inf/s + R(s), s^2 Gbar = s (G_inf + s R),
  !>    a SIMPLE pole with residue 1/G_inf (bounded creep to the long-term state).
  !>
  !> F2. J increases strictly (J' = (1/3) sum G_m beta_m/(s + beta_m)^2 > 0) from -inf
  !> to +inf between consecutive distinct positive -beta_m, from -inf to
  !> J(0) = K + G_inf/3 > 0 on (-beta_min, 0) (beta_min the least positive rate),
  !> and stays >= K + G0/3 > 0 for s < -beta_max: exactly one zero in each of
  !> those intervals, one per distinct positive rate, again interlacing with the
  !> -beta_m. Residue at a zero w: 1/(w J'(w)) < 0. The simple pole at s = 0 has
  !> residue 1/J(0) = 1/(K + G_inf/3).
  !>
  !> Hence u(a, t) = p0 a/(b^2 - a^2) [ a^2/2 f2(t) + b^2/2 f1(t) ] with
  !>   f1(t) = (pole at 0) + sum_k exp(z_k t)/(z_k^2 Gbar'(z_k)),
  !>   f2(t) = 1/(K + G_inf/3) + sum_k exp(w_k t)/(w_k J'(w_k)).
  !> Each zero is bracketed between consecutive poles and found by bisection to
  !> full double precision, evaluating Gbar and J directly (no polynomial
  !> expansion). To keep full relative accuracy when a root lies very close to
  !> a pole (e.g. nearly incompressible K >> G), the unknown is the offset d
  !> from the nearer bracketing pole -c, s = -c +- d, and each s + beta_m is formed
  !> as (beta_m - c) +- d without cancellation.
  !>
  !> Checks: f1(0) = 1/G0 and f2(0) = 1/(K + G0/3) (instantaneous elastic response
  !> with G0 = sum G_m); with G_inf > 0, u -> the elastic value with G_inf as t -> inf.
  !>
  !> Units SI (Pa, 1/s, m, s). Any number of terms >= 1. Requires size(shear) =
  !> size(beta) >= 1, every G_m >= 0 with sum > 0, beta_m >= 0, K > 0,
  !> 0 < inner < outer and size(times) = size(displacement); otherwise every
  !> displacement is a quiet NaN. Terms with G_m = 0 are ignored. For t < 0
  !> (before the step) the displacement is 0.
  pure subroutine cylinder_bore_displacement(shear, beta, bulk, inner, outer, pressure, times, displacement)
    real(dp), intent(in) :: shear(:)          !< G_m, Pa
    real(dp), intent(in) :: beta(:)           !< beta_m >= 0, 1/s
    real(dp), intent(in) :: bulk              !< K, Pa
    real(dp), intent(in) :: inner             !< bore radius a, m
    real(dp), intent(in) :: outer             !< outer radius b, m
    real(dp), intent(in) :: pressure          !< internal pressure p0 of the step, Pa
    real(dp), intent(in) :: times(:)          !< times t, s
    real(dp), intent(out) :: displacement(:)  !< u(a, t), m
    real(dp), allocatable :: moduli(:), rates(:)
    type(pole_expansion_t) :: shear_part, bulk_part
    real(dp) :: factor
    integer :: i

    if (size(shear) /= size(beta) .or. size(shear) < 1 .or. size(times) /= size(displacement) &
        .or. any(shear < 0.0_dp) .or. any(beta < 0.0_dp) .or. .not. sum(shear) > 0.0_dp &
        .or. .not. bulk > 0.0_dp .or. .not. inner > 0.0_dp .or. .not. outer > inner) then
      displacement = ieee_value(1.0_dp, ieee_quiet_nan)
      return
    end if

    call merge_terms(shear, beta, moduli, rates)
    call shear_compliance_expansion(moduli, rates, shear_part)
    call bulk_shear_expansion(moduli, rates, bulk, bulk_part)

    factor = pressure*inner/(outer**2 - inner**2)
    do i = 1, size(times)
      if (times(i) < 0.0_dp) then
        displacement(i) = 0.0_dp
      else
        displacement(i) = factor*(0.5_dp*inner**2*evaluate(bulk_part, times(i)) &
                                  + 0.5_dp*outer**2*evaluate(shear_part, times(i)))
      end if
    end do
  end subroutine cylinder_bore_displacement

  ! ---------------------------------------------------------------------------
  ! Private helpers.

  !> exp(x) - 1 without cancellation for small |x| (Fortran has no expm1).
  !> |x| < 0.5: the Taylor series x (1 + x/2! + x^2/3! + ...) to 18 terms
  !> (truncation < 0.5^18/19! ~ 3e-23 relative); otherwise exp(x) - 1 loses at
  !> most ~1.5 bits (|exp(x)| / |exp(x) - 1| <= 1/(1 - exp(-0.5)) ~ 2.5).
  pure real(dp) function exp_minus_one(x)
    real(dp), intent(in) :: x
    integer, parameter :: terms = 18
    integer :: n
    real(dp) :: series
    if (abs(x) < 0.5_dp) then
      ! Horner form of 1 + x/2 + x^2/6 + ... + x^(terms-1)/terms!
      series = 1.0_dp
      do n = terms, 2, -1
        series = 1.0_dp + series*x/real(n, dp)
      end do
      exp_minus_one = x*series
    else
      exp_minus_one = exp(x) - 1.0_dp
    end if
  end function exp_minus_one

  !> (1 - exp(-x))/x for x >= 0, = 1 at x = 0, accurate to a few ulps.
  pure real(dp) function relative_decay(x)
    real(dp), intent(in) :: x
    if (x == 0.0_dp) then
      relative_decay = 1.0_dp
    else
      relative_decay = -exp_minus_one(-x)/x
    end if
  end function relative_decay

  !> Sort the rates ascending, merge equal rates (adding their moduli) and drop
  !> zero moduli. Input already validated (moduli >= 0, rates >= 0, sum > 0).
  pure subroutine merge_terms(shear, beta, moduli, rates)
    real(dp), intent(in) :: shear(:), beta(:)
    real(dp), allocatable, intent(out) :: moduli(:), rates(:)
    real(dp) :: work_moduli(size(shear)), work_rates(size(shear))
    integer :: count, m, j
    count = 0
    do m = 1, size(shear)
      if (shear(m) == 0.0_dp) cycle
      ! insertion into the sorted list, merging an equal rate
      j = count
      do while (j >= 1)
        if (work_rates(j) <= beta(m)) exit
        j = j - 1
      end do
      if (j >= 1) then
        if (work_rates(j) == beta(m)) then
          work_moduli(j) = work_moduli(j) + shear(m)
          cycle
        end if
      end if
      work_rates(j + 2:count + 1) = work_rates(j + 1:count)
      work_moduli(j + 2:count + 1) = work_moduli(j + 1:count)
      work_rates(j + 1) = beta(m)
      work_moduli(j + 1) = shear(m)
      count = count + 1
    end do
    moduli = work_moduli(1:count)
    rates = work_rates(1:count)
  end subroutine merge_terms

  !> The pole expansion of F1(s) = 1/(s Ghat(s)) = 1/(s^2 Gbar(s)), for sorted,
  !> distinct rates (see cylinder_bore_displacement).
  pure subroutine shear_compliance_expansion(moduli, rates, expansion)
    real(dp), intent(in) :: moduli(:), rates(:)
    type(pole_expansion_t), intent(out) :: expansion
    real(dp) :: root, shifts(size(rates)), h0, h1
    integer :: n, k

    n = size(rates)
    if (rates(1) == 0.0_dp) then
      expansion%constant = 1.0_dp/moduli(1)
      expansion%slope = 0.0_dp
    else
      h0 = sum(moduli/rates)
      h1 = -sum(moduli/rates**2)
      expansion%slope = 1.0_dp/h0
      expansion%constant = -h1/h0**2
    end if
    expansion%count = n - 1
    allocate(expansion%pole(n - 1), expansion%residue(n - 1))
    do k = 1, n - 1
      call find_root(function_gbar, moduli, rates, 0.0_dp, rates(k), rates(k + 1), root, shifts)
      expansion%pole(k) = root
      ! residue of 1/(s^2 Gbar) at a simple zero of Gbar: 1/(z^2 Gbar'(z))
      expansion%residue(k) = 1.0_dp/(root**2*(-sum(moduli/shifts**2)))
    end do
  end subroutine shear_compliance_expansion

  !> The pole expansion of F2(s) = 1/(s (K + Ghat(s)/3)) = 1/(s J(s)), for sorted,
  !> distinct rates (see cylinder_bore_displacement).
  pure subroutine bulk_shear_expansion(moduli, rates, bulk, expansion)
    real(dp), intent(in) :: moduli(:), rates(:)
    real(dp), intent(in) :: bulk
    type(pole_expansion_t), intent(out) :: expansion
    real(dp) :: root, shifts(size(rates)), long_term, brackets(size(rates) + 1)
    integer :: n, k, count

    n = size(rates)
    long_term = 0.0_dp
    if (rates(1) == 0.0_dp) long_term = moduli(1)
    expansion%constant = 1.0_dp/(bulk + long_term/3.0_dp)
    expansion%slope = 0.0_dp
    ! bracket ends 0 = c_0 < c_1 < ... : the zero rate and every positive rate
    if (rates(1) == 0.0_dp) then
      brackets(1:n) = rates
      count = n - 1
    else
      brackets(1) = 0.0_dp
      brackets(2:n + 1) = rates
      count = n
    end if
    expansion%count = count
    allocate(expansion%pole(count), expansion%residue(count))
    do k = 1, count
      call find_root(function_bulk_shear, moduli, rates, bulk, brackets(k), brackets(k + 1), root, shifts)
      expansion%pole(k) = root
      ! residue of 1/(s J) at a simple zero of J: 1/(w J'(w))
      expansion%residue(k) = 1.0_dp/(root*sum(moduli*rates/shifts**2, mask=rates > 0.0_dp)/3.0_dp)
    end do
  end subroutine bulk_shear_expansion

  !> Gbar(s) = sum G_m/(s + beta_m) or J(s) = K + G0/3 - (1/3) sum G_m beta_m/(s + beta_m),
  !> from the shifts s + beta_m.
  pure real(dp) function laplace_function(which, moduli, rates, bulk, shifts)
    integer, intent(in) :: which
    real(dp), intent(in) :: moduli(:), rates(:), bulk, shifts(:)
    if (which == function_gbar) then
      laplace_function = sum(moduli/shifts)
    else
      laplace_function = bulk + (sum(moduli) - sum(moduli*rates/shifts, mask=rates > 0.0_dp))/3.0_dp
    end if
  end function laplace_function

  !> The zero of Gbar (which = function_gbar, decreasing in s) or of J
  !> (function_bulk_shear, increasing) in the open interval (-right, -left),
  !> 0 <= left < right, where the function runs from -/+inf to +/-inf (or to J(0) > 0).
  !> Bisection to full precision on the offset d from the nearer end -c:
  !> s = -c + direction d, shifts(m) = s + beta_m = (beta_m - c) + direction d.
  pure subroutine find_root(which, moduli, rates, bulk, left, right, root, shifts)
    integer, intent(in) :: which
    real(dp), intent(in) :: moduli(:), rates(:), bulk, left, right
    real(dp), intent(out) :: root, shifts(:)
    integer, parameter :: max_iterations = 2200
    real(dp) :: gap, anchor, direction, slope, value, low, high, middle
    integer :: iteration

    gap = right - left
    if (which == function_gbar) then
      slope = -1.0_dp
    else
      slope = 1.0_dp
    end if
    ! which half? evaluate at the midpoint s = -left - gap/2
    shifts = (rates - left) - 0.5_dp*gap
    value = laplace_function(which, moduli, rates, bulk, shifts)
    if (slope*value < 0.0_dp) then
      ! the root is to the right of the midpoint (larger s): near s = -left
      anchor = left
      direction = -1.0_dp
    else
      anchor = right
      direction = 1.0_dp
    end if
    ! g(d) = f(-anchor + direction d) has the sign of slope*direction for its derivative
    low = 0.0_dp
    high = gap
    do iteration = 1, max_iterations
      middle = low + 0.5_dp*(high - low)
      if (middle <= low .or. middle >= high) exit
      shifts = (rates - anchor) + direction*middle
      value = laplace_function(which, moduli, rates, bulk, shifts)
      if (value == 0.0_dp) then
        low = middle
        high = middle
        exit
      end if
      if (value*slope*direction > 0.0_dp) then
        high = middle
      else
        low = middle
      end if
    end do
    middle = low + 0.5_dp*(high - low)
    shifts = (rates - anchor) + direction*middle
    root = -anchor + direction*middle
  end subroutine find_root

  !> constant + slope t + sum residue exp(pole t), t >= 0.
  pure real(dp) function evaluate(expansion, t)
    type(pole_expansion_t), intent(in) :: expansion
    real(dp), intent(in) :: t
    integer :: k
    real(dp) :: exponent
    evaluate = expansion%constant + expansion%slope*t
    do k = 1, expansion%count
      exponent = expansion%pole(k)*t
      if (exponent > -745.0_dp) evaluate = evaluate + expansion%residue(k)*exp(exponent)
    end do
  end function evaluate
  !> Hertz's (sigma_r - sigma_z)/(2 p0) on the axis of a sphere's contact at
  !> zeta = z/a (Johnson, Contact Mechanics, eq. 3.45): the largest shear
  !> stress there, over the peak pressure p0.
  pure real(dp) function hertz_axis_shear(zeta, nu)
    real(dp), intent(in) :: zeta, nu
    real(dp) :: radial, axial
    axial = -1.0_dp/(1.0_dp + zeta**2)
    radial = -(1.0_dp + nu)*(1.0_dp - zeta*atan(1.0_dp/zeta)) + 0.5_dp/(1.0_dp + zeta**2)
    hertz_axis_shear = 0.5_dp*(radial - axial)
  end function hertz_axis_shear

  !> The maximum of hertz_axis_shear over zeta (value, over p0, and its zeta),
  !> by golden-section search on [0.1, 2], where it is unimodal (its maximum
  !> is near zeta = 0.48 for every nu in [0, 0.5]).
  pure subroutine hertz_axis_maximum(nu, value, zeta)
    real(dp), intent(in) :: nu
    real(dp), intent(out) :: value, zeta
    real(dp), parameter :: golden = 0.5_dp*(sqrt(5.0_dp) - 1.0_dp)
    real(dp) :: low, high, x1, x2
    integer :: i
    low = 0.1_dp
    high = 2.0_dp
    do i = 1, 200
      x1 = high - golden*(high - low)
      x2 = low + golden*(high - low)
      if (hertz_axis_shear(x1, nu) > hertz_axis_shear(x2, nu)) then
        high = x2
      else
        low = x1
      end if
    end do
    zeta = 0.5_dp*(low + high)
    value = hertz_axis_shear(zeta, nu)
  end subroutine hertz_axis_maximum

end module visco2d_analytic
