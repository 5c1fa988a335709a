!> Exact conversion between the uniaxial relaxation function
!> E(t) = sum_i E_i exp(-alpha_i t) (eqs. [47], [50]) and the shear relaxation
!> function G(t) = phi1(t) = sum_m G_m exp(-beta_m t) (eqs. [12], [49]) of a
!> material that is viscoelastic in shear and elastic in bulk (modulus K).
!>
!> With S(s) = sum_i E_i/(s + alpha_i), the Laplace transform of E(t), eq. [48]
!> reads Gbar(s) = 3K S(s)/(9K - s S(s)): the elastic relation G = 3KE/(9K - E)
!> with E and G replaced by their Carson transforms s Ebar and s Gbar. This is a
!> proper rational function of s, so G(t) is exactly a finite Prony series; the
!> paper inverted eq. [48] numerically and refitted a Maxwell model (Table 3),
!> here it is inverted exactly by partial fractions.
!>
!> Both directions have the form F(s) = N S(s)/(T - h(s)), h(s) = s S(s), with
!> S(s) = sum_k c_k/(s + a_k), c_k > 0, a_k >= 0 distinct:
!>   uniaxial -> shear:  c = E, a = alpha, N = 3K,  T = 9K   (eq. [48]);
!>   shear -> uniaxial:  c = G, a = beta,  N = -9K, T = -3K  (Ebar = 9K Gbar/(3K + s Gbar)).
!> h(s) = sum_k c_k s/(s + a_k) = sum_k c_k - sum_k c_k a_k/(s + a_k) is
!> increasing between its poles -a_k (h' = sum c_k a_k/(s + a_k)^2 > 0) and runs
!> from -inf to +inf between consecutive poles, so the poles of F (roots of
!> h = T) are real, negative and interlaced with the -a_k: one in each interval
!> between consecutive poles, one in (-inf, -a_max) if T > sum c_k, one in
!> (-a_min, 0) if T < c_0 (c_0: the coefficient of an a = 0 term, else 0). An
!> a = 0 term gives the pole s = 0 with residue lim s F(s) = N c_0/(T - c_0).
!> At a root p /= 0, S(p) = T/p and the residue is
!>   N S(p)/(-h'(p)) = N T/(beta h'(p)),   beta = -p,   N T = 27 K^2 > 0.
!> Roots are found by bisection of h(s) - T inside each interval, written in the
!> offset d = s + a_o from the nearer end point pole -a_o so that s + a_k =
!> d + (a_k - a_o) keeps full relative precision; no polynomial is formed.
module visco2d_relaxation
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, short_real
  use visco2d_sorting, only: sorted_order
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  implicit none
  private

  public :: uniaxial_to_shear, uniaxial_to_shear_with_bulk, shear_to_uniaxial

  !> Bisection steps per root: enough to reach adjacent doubles from any bracket.
  integer, parameter :: max_bisections = 4000

  !> The state of one partial-fraction inversion (find_poles): the scaled
  !> series c_k, a_k, the numerator N and target T, and the poles found so far.
  type :: pole_search_t
    integer :: n = 0                              !< terms (and poles to find)
    integer :: count = 0                          !< poles found
    real(dp) :: scale = 1.0_dp                    !< sum of the moduli: c_k = modulus_k/scale
    real(dp) :: numerator = 0.0_dp, target = 0.0_dp, total = 0.0_dp  !< N, T, sum c
    real(dp), allocatable :: coefficient(:), rate(:)
    real(dp), allocatable :: residue(:), pole_rate(:)
    character(:), allocatable :: message          !< '' while all is well
  end type pole_search_t

contains

  !> Uniaxial Prony series (E_i, alpha_i) (eq. [47]) and Poisson's ratio nu at
  !> t = 0 -> bulk modulus K = sum E_i/(3(1 - 2 nu)) (Table 3 footnote) and the
  !> exact shear series (G_m, beta_m) of eq. [49], sorted by increasing beta.
  !> On failure `error` says what is wrong (the caller locates it), `bulk` is 0
  !> and the series are empty.
  subroutine uniaxial_to_shear(young, alpha, poisson, bulk, shear, beta, error)
    real(dp), intent(in) :: young(:)          !< E_i, Pa (> 0)
    real(dp), intent(in) :: alpha(:)          !< alpha_i, 1/s (>= 0)
    real(dp), intent(in) :: poisson           !< nu at t = 0, in (-1, 0.5)
    real(dp), intent(out) :: bulk             !< K, Pa
    real(dp), allocatable, intent(out) :: shear(:)  !< G_m, Pa
    real(dp), allocatable, intent(out) :: beta(:)   !< beta_m, 1/s
    type(error_t), allocatable, intent(out) :: error  !< not allocated on success
    character(:), allocatable :: message
    real(dp) :: bulk_at_zero
    bulk = 0.0_dp
    allocate(shear(0), beta(0))
    call check_series(young, alpha, 'uniaxial', 'E', 'alpha', message)
    if (len(message) > 0) then
      call set_error(error, message)
      return
    end if
    if (.not. ieee_is_finite(poisson)) then
      call set_error(error, "Poisson's ratio nu is not a finite number")
      return
    end if
    if (poisson <= -1.0_dp .or. poisson >= 0.5_dp) then
      call set_error(error, "Poisson's ratio nu must be in (-1, 0.5), got "//short_real(poisson))
      return
    end if
    bulk_at_zero = sum(young)/(3.0_dp*(1.0_dp - 2.0_dp*poisson))      ! Table 3 footnote
    call uniaxial_to_shear_with_bulk(young, alpha, bulk_at_zero, shear, beta, error)
    if (.not. allocated(error)) bulk = bulk_at_zero
  end subroutine uniaxial_to_shear

  !> Uniaxial Prony series (E_i, alpha_i) and the elastic bulk modulus K ->
  !> exact shear series (G_m, beta_m), sorted by increasing beta (eq. [48]).
  !> Needs 9K > sum E_i (i.e. nu(0) > -1). On failure `error` says what is
  !> wrong and the series are empty.
  subroutine uniaxial_to_shear_with_bulk(young, alpha, bulk, shear, beta, error)
    real(dp), intent(in) :: young(:)          !< E_i, Pa (> 0)
    real(dp), intent(in) :: alpha(:)          !< alpha_i, 1/s (>= 0)
    real(dp), intent(in) :: bulk              !< K, Pa
    real(dp), allocatable, intent(out) :: shear(:)  !< G_m, Pa
    real(dp), allocatable, intent(out) :: beta(:)   !< beta_m, 1/s
    type(error_t), allocatable, intent(out) :: error  !< not allocated on success
    character(:), allocatable :: message
    real(dp), allocatable :: coefficient(:), rate(:)
    call check_series(young, alpha, 'uniaxial', 'E', 'alpha', message)
    if (len(message) == 0) call check_bulk(bulk, message)
    if (len(message) == 0) then
      if (.not. 9.0_dp*bulk > sum(young)) message = 'the bulk modulus K = '//short_real(bulk)// &
        ' must exceed sum(E)/9 = '//short_real(sum(young)/9.0_dp)//' (that is, nu(0) > -1)'
    end if
    if (len(message) > 0) then
      allocate(shear(0), beta(0))
      call set_error(error, message)
      return
    end if
    call merge_equal_rates(young, alpha, coefficient, rate)
    ! eq. [48]: Gbar = 3K S/(9K - s S)
    call invert_rational(coefficient, rate, 3.0_dp*bulk, 9.0_dp*bulk, shear, beta, message)
    if (len(message) > 0) call set_error(error, message)
  end subroutine uniaxial_to_shear_with_bulk

  !> Inverse of eq. [48]: shear series (G_m, beta_m) and the bulk modulus K ->
  !> uniaxial series (E_i, alpha_i), sorted by increasing alpha, from
  !> Ebar = 9K Gbar/(3K + s Gbar). On failure `error` says what is wrong and
  !> the series are empty.
  subroutine shear_to_uniaxial(shear, beta, bulk, young, alpha, error)
    real(dp), intent(in) :: shear(:)          !< G_m, Pa (> 0)
    real(dp), intent(in) :: beta(:)           !< beta_m, 1/s (>= 0)
    real(dp), intent(in) :: bulk              !< K, Pa (> 0)
    real(dp), allocatable, intent(out) :: young(:)  !< E_i, Pa
    real(dp), allocatable, intent(out) :: alpha(:)  !< alpha_i, 1/s
    type(error_t), allocatable, intent(out) :: error  !< not allocated on success
    character(:), allocatable :: message
    real(dp), allocatable :: coefficient(:), rate(:)
    call check_series(shear, beta, 'shear', 'G', 'beta', message)
    if (len(message) == 0) call check_bulk(bulk, message)
    if (len(message) > 0) then
      allocate(young(0), alpha(0))
      call set_error(error, message)
      return
    end if
    call merge_equal_rates(shear, beta, coefficient, rate)
    ! Ebar = 9K Gbar/(3K + s Gbar) = (-9K) Gbar/((-3K) - s Gbar)
    call invert_rational(coefficient, rate, -9.0_dp*bulk, -3.0_dp*bulk, young, alpha, message)
    if (len(message) > 0) call set_error(error, message)
  end subroutine shear_to_uniaxial

  !> Checks of a Prony series: terms present, sizes equal, finite values,
  !> moduli > 0, rates >= 0. `series` names it in messages ('uniaxial', 'shear').
  subroutine check_series(modulus, rate, series, modulus_name, rate_name, message)
    real(dp), intent(in) :: modulus(:), rate(:)
    character(*), intent(in) :: series, modulus_name, rate_name
    character(:), allocatable, intent(out) :: message
    integer :: i
    message = ''
    if (size(modulus) == 0) then
      message = 'the '//series//' relaxation series has no terms'
      return
    end if
    if (size(rate) /= size(modulus)) then
      message = 'the '//series//' relaxation series has '//integer_text(size(modulus))//' '//modulus_name// &
                ' values but '//integer_text(size(rate))//' '//rate_name//' values'
      return
    end if
    do i = 1, size(modulus)
      if (.not. ieee_is_finite(modulus(i))) then
        message = series//' term '//integer_text(i)//': '//modulus_name//' is not a finite number'
      else if (.not. ieee_is_finite(rate(i))) then
        message = series//' term '//integer_text(i)//': '//rate_name//' is not a finite number'
      else if (modulus(i) <= 0.0_dp) then
        message = series//' term '//integer_text(i)//': '//modulus_name//' must be > 0, got '//short_real(modulus(i))
      else if (rate(i) < 0.0_dp) then
        message = series//' term '//integer_text(i)//': '//rate_name//' must be >= 0, got '//short_real(rate(i))
      end if
      if (len(message) > 0) return
    end do
    if (.not. ieee_is_finite(sum(modulus))) message = 'the sum of the '//series//' moduli overflows'
  end subroutine check_series

  !> The bulk modulus must be finite and positive.
  subroutine check_bulk(bulk, message)
    real(dp), intent(in) :: bulk
    character(:), allocatable, intent(out) :: message
    message = ''
    if (.not. ieee_is_finite(bulk)) then
      message = 'the bulk modulus K is not a finite number'
    else if (bulk <= 0.0_dp) then
      message = 'the bulk modulus K must be > 0, got '//short_real(bulk)
    end if
  end subroutine check_bulk

  !> Terms sorted by increasing rate, terms with equal rates merged (moduli summed).
  pure subroutine merge_equal_rates(modulus, rate, merged_modulus, merged_rate)
    real(dp), intent(in) :: modulus(:), rate(:)
    real(dp), allocatable, intent(out) :: merged_modulus(:), merged_rate(:)
    real(dp) :: sorted_modulus(size(modulus)), sorted_rate(size(rate))
    integer :: i, count
    sorted_modulus = modulus
    sorted_rate = rate
    call sort_by_rate(sorted_modulus, sorted_rate)
    count = 0
    do i = 1, size(sorted_rate)
      if (count > 0) then
        if (sorted_rate(i) == sorted_rate(count)) then
          sorted_modulus(count) = sorted_modulus(count) + sorted_modulus(i)
          cycle
        end if
      end if
      count = count + 1
      sorted_modulus(count) = sorted_modulus(i)
      sorted_rate(count) = sorted_rate(i)
    end do
    merged_modulus = sorted_modulus(1:count)
    merged_rate = sorted_rate(1:count)
  end subroutine merge_equal_rates

  !> Sort (modulus, rate) pairs by increasing rate.
  pure subroutine sort_by_rate(modulus, rate)
    real(dp), intent(inout) :: modulus(:), rate(:)
    integer, allocatable :: order(:)
    order = sorted_order(rate)
    modulus = modulus(order)
    rate = rate(order)
  end subroutine sort_by_rate

  !> Partial fractions of F(s) = numerator S(s)/(target - s S(s)),
  !> S(s) = sum_k c_k/(s + a_k), as F(s) = sum_m residue_m/(s + pole_rate_m):
  !> the time function is sum_m residue_m exp(-pole_rate_m t). Needs c_k > 0 and
  !> distinct a_k >= 0 sorted increasingly (see the module header for the root
  !> intervals and the residue formula). On failure the results are empty.
  subroutine invert_rational(modulus, rate, modulus_numerator, modulus_target, residue, pole_rate, message)
    real(dp), intent(in) :: modulus(:), rate(:), modulus_numerator, modulus_target
    real(dp), allocatable, intent(out) :: residue(:), pole_rate(:)
    character(:), allocatable, intent(out) :: message
    call find_poles(modulus, rate, modulus_numerator, modulus_target, residue, pole_rate, message)
    if (len(message) > 0) then
      residue = [real(dp) ::]
      pole_rate = [real(dp) ::]
    end if
  end subroutine invert_rational

  !> The work of invert_rational, on moduli scaled by their sum (the residues,
  !> which scale like a modulus, are scaled back): no overflow of 27 K^2
  !> whatever the unit. Stops at the first failure with `message` set.
  subroutine find_poles(modulus, rate, modulus_numerator, modulus_target, residue, pole_rate, message)
    real(dp), intent(in) :: modulus(:), rate(:), modulus_numerator, modulus_target
    real(dp), allocatable, intent(out) :: residue(:), pole_rate(:)
    character(:), allocatable, intent(out) :: message
    type(pole_search_t) :: search
    real(dp) :: zero_rate_coefficient, root_rate, root_residue
    integer :: first_positive, k

    search%n = size(rate)
    allocate(search%residue(search%n), search%pole_rate(search%n))
    search%message = ''
    search%count = 0
    search%rate = rate
    search%scale = sum(modulus)
    search%coefficient = modulus/search%scale
    search%numerator = modulus_numerator/search%scale
    search%target = modulus_target/search%scale
    search%total = sum(search%coefficient)
    call find_poles_scaled(search, modulus, first_positive, zero_rate_coefficient)
    if (len(search%message) == 0 .and. first_positive <= search%n) then
      ! one root between consecutive poles, -a_(k+1) < s < -a_k
      do k = first_positive, search%n - 1
        call root_between(search, rate(k + 1), rate(k), root_rate, root_residue)
        if (len(search%message) == 0) call add_pole(search, root_rate, root_residue)
        if (len(search%message) > 0) exit
      end do
      ! one root in (-inf, -a_max) if T > sum c (there h runs from sum c to +inf)
      if (len(search%message) == 0 .and. search%target > search%total) then
        call root_below(search, root_rate, root_residue)
        if (len(search%message) == 0) call add_pole(search, root_rate, root_residue)
      end if
      ! one root in (-a_min, 0) if T < c_0 (there h runs from -inf to c_0)
      if (len(search%message) == 0 .and. search%target < zero_rate_coefficient) then
        call root_between(search, rate(first_positive), 0.0_dp, root_rate, root_residue)
        if (len(search%message) == 0) call add_pole(search, root_rate, root_residue)
      end if
    end if
    if (len(search%message) == 0 .and. search%count /= search%n) &
      search%message = 'conversion failed: found '//integer_text(search%count)//' poles for '//integer_text(search%n)// &
                       ' distinct rates'
    message = search%message
    residue = search%residue*search%scale
    pole_rate = search%pole_rate
    if (len(message) == 0) call sort_by_rate(residue, pole_rate)
  end subroutine find_poles

  !> The checks before the roots are sought (moduli not negligible, no pole at
  !> s > 0, no lost pole) and the pole s = 0 of an a = 0 term (the long-term
  !> modulus), with residue lim s F(s) = N c_0/(T - c_0). Returns the first
  !> term with a positive rate and c_0 (0 without an a = 0 term).
  subroutine find_poles_scaled(search, modulus, first_positive, zero_rate_coefficient)
    type(pole_search_t), intent(inout) :: search
    real(dp), intent(in) :: modulus(:)
    integer, intent(out) :: first_positive
    real(dp), intent(out) :: zero_rate_coefficient
    integer :: k
    zero_rate_coefficient = 0.0_dp
    first_positive = 1
    if (any(search%coefficient < tiny(1.0_dp))) then
      k = minloc(search%coefficient, dim=1)
      search%message = 'conversion failed: the modulus '//short_real(modulus(k))//' of the term with rate '// &
                       short_real(search%rate(k))//' 1/s is negligible against their sum '//short_real(search%scale)
      return
    end if
    if (search%rate(1) == 0.0_dp) then
      zero_rate_coefficient = search%coefficient(1)
      first_positive = 2
    end if
    ! c_0 < T < sum c would put a root of h = T at s > 0 (a growing mode);
    ! T = c_0 or T = sum c would lose a pole (a double pole at 0, or one at -inf)
    if (search%target > zero_rate_coefficient .and. search%target < search%total) then
      search%message = 'no stable conversion: the transform has a pole at s > 0'
    else if (search%target == zero_rate_coefficient .or. &
             (search%target == search%total .and. first_positive <= search%n)) then
      search%message = 'degenerate series: the transform has fewer poles than the series has terms'
    end if
    if (len(search%message) > 0) return
    if (first_positive == 2) call add_pole(search, 0.0_dp, &
      search%numerator*zero_rate_coefficient/(search%target - zero_rate_coefficient))
  end subroutine find_poles_scaled

  !> Store one pole after checking that it is usable.
  subroutine add_pole(search, value_rate, value_residue)
    type(pole_search_t), intent(inout) :: search
    real(dp), intent(in) :: value_rate, value_residue
    if (search%count >= search%n) then
      search%message = 'conversion failed: more poles than terms'
    else if (.not. (ieee_is_finite(value_residue) .and. value_residue > 0.0_dp)) then
      search%message = 'conversion failed: the term with rate '//short_real(value_rate)// &
                ' 1/s gets a modulus that is not positive and finite ('//short_real(value_residue*search%scale)// &
                '); moduli or rates too far apart, or rates too close, for double precision'
    else if (.not. (ieee_is_finite(value_rate) .and. value_rate >= 0.0_dp)) then
      search%message = 'conversion failed: a rate that is not finite and >= 0 ('//short_real(value_rate)//')'
    else
      search%count = search%count + 1
      search%residue(search%count) = value_residue
      search%pole_rate(search%count) = value_rate
    end if
  end subroutine add_pole

  !> The root in (-left_rate, -right_rate), left_rate > right_rate >= 0 (the
  !> right end is a pole of h, or s = 0 where h = c_0 > T).
  subroutine root_between(search, left_rate, right_rate, root_rate, root_residue)
    type(pole_search_t), intent(inout) :: search
    real(dp), intent(in) :: left_rate, right_rate
    real(dp), intent(out) :: root_rate, root_residue
    real(dp) :: middle, origin, low, high
    ! which half holds the root? (h increases: h(middle) > T -> left half)
    middle = -0.5_dp*(left_rate + right_rate)
    if (shifted_h(search, middle, 0.0_dp) - search%target > 0.0_dp) then
      origin = left_rate                  ! d = s + a_left in (0, a_left - a_right)
      low = 0.0_dp
      high = left_rate - right_rate
    else
      origin = right_rate                 ! d = s + a_right in (a_right - a_left, 0)
      low = right_rate - left_rate
      high = 0.0_dp
    end if
    call bisect(search, origin, low, high, root_rate, root_residue)
  end subroutine root_between

  !> The root in (-inf, -a_max) when T > sum c. There every |s + a_k| >=
  !> |s + a_max|, so h - T <= (sum c - T) + sum(c a)/|d|, d = s + a_max:
  !> at d = -2 sum(c a)/(T - sum c) h - T <= -(T - sum c)/2 < 0.
  subroutine root_below(search, root_rate, root_residue)
    type(pole_search_t), intent(inout) :: search
    real(dp), intent(out) :: root_rate, root_residue
    real(dp) :: low
    low = -2.0_dp*sum(search%coefficient*search%rate)/(search%target - search%total)
    call bisect(search, search%rate(search%n), low, 0.0_dp, root_rate, root_residue)
  end subroutine root_below

  !> Bisection in d = s + origin on (low, high), where h - T < 0 at low and > 0
  !> at high (end points are not evaluated: they may be poles), to adjacent
  !> doubles; then the rate beta = -s = origin - d and the residue
  !> N T/(beta h'(s)).
  subroutine bisect(search, origin, low, high, root_rate, root_residue)
    type(pole_search_t), intent(inout) :: search
    real(dp), intent(in) :: origin, low, high
    real(dp), intent(out) :: root_rate, root_residue
    real(dp) :: lower, upper, middle, value, lower_value, upper_value, root
    integer :: iteration
    lower = low
    upper = high
    lower_value = -huge(1.0_dp)
    upper_value = huge(1.0_dp)
    do iteration = 1, max_bisections
      middle = lower + 0.5_dp*(upper - lower)
      if (middle <= lower .or. middle >= upper) exit
      value = shifted_h(search, middle, origin) - search%target
      if (ieee_is_nan(value)) then
        search%message = 'conversion failed: the transform is not finite near rate '//short_real(origin)//' 1/s'
        return
      end if
      if (value < 0.0_dp) then
        lower = middle
        lower_value = value
      else if (value > 0.0_dp) then
        upper = middle
        upper_value = value
      else
        lower = middle
        upper = middle
        lower_value = 0.0_dp
        exit
      end if
    end do
    if (abs(lower_value) <= abs(upper_value)) then
      root = lower
    else
      root = upper
    end if
    root_rate = origin - root
    root_residue = search%numerator*search%target/(root_rate*shifted_h_derivative(search, root, origin))
  end subroutine bisect

  !> h(s) = sum_k c_k s/(s + a_k) at s = d - origin, with s + a_k = d + (a_k - origin).
  pure real(dp) function shifted_h(search, d, origin) result(value)
    type(pole_search_t), intent(in) :: search
    real(dp), intent(in) :: d, origin
    real(dp) :: s
    integer :: j
    s = d - origin
    value = 0.0_dp
    do j = 1, search%n
      if (search%rate(j) == 0.0_dp) then
        value = value + search%coefficient(j)
      else
        value = value + search%coefficient(j)*s/(d + (search%rate(j) - origin))
      end if
    end do
  end function shifted_h

  !> h'(s) = sum_k c_k a_k/(s + a_k)^2 at s = d - origin (all terms positive).
  pure real(dp) function shifted_h_derivative(search, d, origin) result(value)
    type(pole_search_t), intent(in) :: search
    real(dp), intent(in) :: d, origin
    integer :: j
    value = 0.0_dp
    do j = 1, search%n
      if (search%rate(j) > 0.0_dp) value = value + search%coefficient(j)*search%rate(j)/(d + (search%rate(j) - origin))**2
    end do
  end function shifted_h_derivative
end module visco2d_relaxation
