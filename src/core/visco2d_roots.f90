!> The root of an increasing function by bracketing and bisection: what the
!> mesh generators use to give a section the volume it must have.
module visco2d_roots
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: increasing_root, scalar_function

  abstract interface
    !> A real function of one real variable (it may change its host's state).
    real(dp) function scalar_function(x)
      import :: dp
      real(dp), intent(in) :: x
    end function scalar_function
  end interface

contains

  !> x with f(x) = target for an increasing f: the bracket [0, 1] is widened
  !> (low stepped down by 2, 4, 8, ..., high doubled; up to 60 times each)
  !> until it holds the target, then halved until it cannot be split (round-off).
  real(dp) function increasing_root(f, target) result(middle)
    procedure(scalar_function) :: f
    real(dp), intent(in) :: target
    real(dp) :: low, high
    integer :: iteration
    low = 0.0_dp
    high = 1.0_dp
    do iteration = 1, 60
      if (f(low) <= target) exit
      high = low
      low = low - 2.0_dp**iteration
    end do
    do iteration = 1, 60
      if (f(high) >= target) exit
      low = high
      high = 2.0_dp*high
    end do
    middle = 0.5_dp*(low + high)
    do iteration = 1, 200
      middle = 0.5_dp*(low + high)
      if (middle <= low .or. middle >= high) exit
      if (f(middle) < target) then
        low = middle
      else
        high = middle
      end if
    end do
  end function increasing_root
end module visco2d_roots
