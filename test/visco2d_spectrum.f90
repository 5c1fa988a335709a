!> The spectrum of a 3 x 3 amplification matrix in quadruple precision, for
!> the integrator tests (test_wilson, test_integrators): the roots of its
!> characteristic cubic, the principal pair r e^{+-i phi} and the spectral
!> radius.
module visco2d_spectrum
  implicit none
  private

  public :: qp, pi_qp, spectrum_t, spectrum_of, cubic

  integer, parameter :: qp = selected_real_kind(30)
  real(qp), parameter :: pi_qp = 3.14159265358979323846264338327950288_qp

  !> The roots of the characteristic polynomial of an amplification matrix.
  type :: spectrum_t
    complex(qp) :: root(3) = (0.0_qp, 0.0_qp)  !< oscillating: root(1), root(2) the principal pair
                                               !< (Im root(1) > 0), root(3) the spurious root;
                                               !< else the real roots by decreasing modulus
    logical :: oscillating = .false.           !< the principal roots are a complex pair
    real(qp) :: radius = 0.0_qp                !< spectral radius rho(A)
    real(qp) :: modulus = 0.0_qp               !< r of the pair r e^{+-i phi}
    real(qp) :: phase = 0.0_qp                 !< phi of the pair, radians per step
    real(qp) :: coefficients(0:2) = 0.0_qp     !< lambda^3 + c2 lambda^2 + c1 lambda + c0
  end type spectrum_t

contains

  !> p(z) = z^3 + c2 z^2 + c1 z + c0.
  pure complex(qp) function cubic(c, z)
    real(qp), intent(in) :: c(0:2)
    complex(qp), intent(in) :: z
    cubic = ((z + c(2))*z + c(1))*z + c(0)
  end function cubic

  !> The roots of det(lambda I - A) = lambda^3 + c2 lambda^2 + c1 lambda + c0:
  !> one real root by bisection on the Cauchy bound interval (p(-B) < 0 < p(B)),
  !> to the last bit; the other two from the deflated quadratic (complex pair,
  !> or the cancellation-free real formula); each root then polished by Newton
  !> on the full cubic (a step kept only if it lowers |p|), so the order of
  !> deflation does not matter.
  function spectrum_of(a) result(s)
    real(qp), intent(in) :: a(3, 3)
    type(spectrum_t) :: s
    real(qp) :: c(0:2), bound, low, high, middle, real_root, b1, b0, discriminant, q
    complex(qp) :: z, trial, slope, swap
    integer :: iteration, j
    c(2) = -(a(1, 1) + a(2, 2) + a(3, 3))
    c(1) = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1) + a(1, 1)*a(3, 3) - a(1, 3)*a(3, 1) + a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)
    c(0) = -(a(1, 1)*(a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)) - a(1, 2)*(a(2, 1)*a(3, 3) - a(2, 3)*a(3, 1)) &
             + a(1, 3)*(a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1)))
    s%coefficients = c
    bound = 1.0_qp + max(abs(c(0)), abs(c(1)), abs(c(2)))
    low = -bound
    high = bound
    do iteration = 1, 1000
      middle = 0.5_qp*(low + high)
      if (middle <= low .or. middle >= high) exit
      if (real(cubic(c, cmplx(middle, 0.0_qp, qp)), qp) < 0.0_qp) then
        low = middle
      else
        high = middle
      end if
    end do
    real_root = 0.5_qp*(low + high)
    b1 = c(2) + real_root
    b0 = c(1) + real_root*b1
    discriminant = b1**2 - 4.0_qp*b0
    s%oscillating = discriminant < 0.0_qp
    if (s%oscillating) then
      s%root(1) = cmplx(-0.5_qp*b1, 0.5_qp*sqrt(-discriminant), qp)
      s%root(2) = conjg(s%root(1))
    else
      q = -0.5_qp*(b1 + sign(sqrt(discriminant), b1))
      s%root(1) = cmplx(q, 0.0_qp, qp)
      s%root(2) = cmplx(0.0_qp, 0.0_qp, qp)
      if (q /= 0.0_qp) s%root(2) = cmplx(b0/q, 0.0_qp, qp)
    end if
    s%root(3) = cmplx(real_root, 0.0_qp, qp)
    do j = 1, 3
      z = s%root(j)
      do iteration = 1, 5
        slope = (3.0_qp*z + 2.0_qp*c(2))*z + c(1)
        if (slope == (0.0_qp, 0.0_qp)) exit
        trial = z - cubic(c, z)/slope
        if (abs(cubic(c, trial)) >= abs(cubic(c, z))) exit
        z = trial
      end do
      s%root(j) = z
    end do
    if (s%oscillating) then
      s%root(2) = conjg(s%root(1))
      if (aimag(s%root(1)) < 0.0_qp) s%root(1:2) = s%root([2, 1])
      s%modulus = abs(s%root(1))
      s%phase = atan2(aimag(s%root(1)), real(s%root(1), qp))
    else
      ! all real: sort by decreasing modulus
      do j = 1, 2
        do iteration = 1, 3 - j
          if (abs(s%root(iteration)) < abs(s%root(iteration + 1))) then
            swap = s%root(iteration)
            s%root(iteration) = s%root(iteration + 1)
            s%root(iteration + 1) = swap
          end if
        end do
      end do
    end if
    s%radius = maxval(abs(s%root))
  end function spectrum_of
end module visco2d_spectrum
