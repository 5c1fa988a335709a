!> Time histories of loads and prescribed displacements (the CURVE card):
!> a step (value 1 from t = 0 on) or a piecewise-linear table of (t, value)
!> points, held constant before the first and after the last point. The card
!> is read by visco2d_curve_cards.
module visco2d_curve
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: curve_t, curve_value

  !> One named time history. A load without a curve is constant in time (a step at t = 0).
  type :: curve_t
    character(:), allocatable :: name
    real(dp), allocatable :: time(:)    !< s, strictly increasing; a step has time = [0]
    real(dp), allocatable :: value(:)   !< dimensionless factor on the card's value
    integer :: line = 0                 !< line of the CURVE card
  end type curve_t

contains

  !> Factor of a curve at time t (s): linear between points, constant outside.
  !> The interval is found by bisection (a curve may have many points).
  pure real(dp) function curve_value(curve, t) result(factor)
    type(curve_t), intent(in) :: curve
    real(dp), intent(in) :: t
    integer :: low, high, middle, n
    n = size(curve%time)
    if (t <= curve%time(1)) then
      factor = curve%value(1)
      return
    end if
    if (t > curve%time(n)) then
      factor = curve%value(n)
      return
    end if
    low = 1                                   ! time(low) < t <= time(high)
    high = n
    do while (high - low > 1)
      middle = (low + high)/2
      if (t <= curve%time(middle)) then
        high = middle
      else
        low = middle
      end if
    end do
    factor = curve%value(low) + (curve%value(high) - curve%value(low))* &
             (t - curve%time(low))/(curve%time(high) - curve%time(low))
  end function curve_value
end module visco2d_curve
