!> Time histories of loads and prescribed displacements (the CURVE card):
!> a step (value 1 from t = 0 on) or a piecewise-linear table of (t, value)
!> points, held constant before the first and after the last point.
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
  pure real(dp) function curve_value(curve, t) result(factor)
    type(curve_t), intent(in) :: curve
    real(dp), intent(in) :: t
    integer :: k, n
    n = size(curve%time)
    if (t <= curve%time(1)) then
      factor = curve%value(1)
      return
    end if
    do k = 2, n
      if (t <= curve%time(k)) then
        factor = curve%value(k - 1) + (curve%value(k) - curve%value(k - 1))* &
                 (t - curve%time(k - 1))/(curve%time(k) - curve%time(k - 1))
        return
      end if
    end do
    factor = curve%value(n)
  end function curve_value
end module visco2d_curve
