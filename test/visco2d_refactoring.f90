!> Tests only: the plate's held equations imposed by refactoring S~ with
!> them eliminated at every contact change, instead of the program's
!> capacitance system on one factor with the supports. test_capacitance runs
!> the Table 1 impact both ways (solve_dynamic's `hold`) and checks that they
!> agree. An extension of visco2d_time_step's contact_hold_t: the time step
!> calls its three bindings and nothing else of it. (Rigid plate only: with
!> a PAD the stepper uses the capacitance system whatever it is given.)
module visco2d_refactoring
  use visco2d_error, only: error_t, set_error
  use visco2d_banded, only: band_constrain_rhs
  use visco2d_factor, only: factor_compute, factor_solve, solve_failure_text
  use visco2d_time_step, only: stepper_t, contact_hold_t
  implicit none
  private

  public :: refactoring_hold_t

  !> Held equations eliminated from S~, refactored at every contact change.
  type, extends(contact_hold_t) :: refactoring_hold_t
  contains
    procedure, nopass :: factor => refactor_row
    procedure, nopass :: hold => refactor_rows
    procedure, nopass :: solve => solve_refactored
  end type refactoring_hold_t

contains

  !> S~ of row r factored with the supports and the held equations imposed.
  subroutine refactor_row(stepper, r, info, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    associate (point => stepper%points(r))
    call factor_compute(point%factor, point%effective, stepper%fixed, info, stepper%solver)
    end associate
    stepper%factorizations = stepper%factorizations + 1
  end subroutine refactor_row

  !> The contact set has changed: every row's S~ refactored.
  subroutine refactor_rows(stepper, info, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(out) :: info
    type(error_t), allocatable, intent(inout) :: error
    integer :: r
    info = 0
    do r = 1, size(stepper%points)
      call refactor_row(stepper, r, info, error)
      if (info /= 0 .or. allocated(error)) return
    end do
  end subroutine refactor_rows

  !> dU of eq. [34] with the held equations: a solve with the refactored S~.
  subroutine solve_refactored(stepper, r, error)
    type(stepper_t), intent(inout) :: stepper
    integer, intent(in) :: r
    type(error_t), allocatable, intent(inout) :: error
    integer :: status
    associate (point => stepper%points(r))
    stepper%solution = stepper%effective_load
    call band_constrain_rhs(point%effective, stepper%fixed, stepper%prescribed, stepper%solution)
    call factor_solve(point%factor, stepper%solution, status)
    end associate
    if (status /= 0) call set_error(error, solve_failure_text(status))
  end subroutine solve_refactored
end module visco2d_refactoring
