!> Symmetric banded matrices (the legacy program's band storage, eq. [25]'s S
!> and later eq. [35]'s effective stiffness): assembly, symmetric
!> elimination of prescribed displacements, and LAPACK Cholesky
!> (dpbtrf once, dpbtrs per right-hand side).
module visco2d_banded
  use visco2d_kinds, only: dp
  use visco2d_lapack, only: dpbtrf, dpbtrs
  implicit none
  private

  public :: band_matrix_t, band_create, band_add_element, band_multiply, band_multiply_rows, band_constrain
  public :: band_constrain_matrix, band_constrain_rhs
  public :: band_factor, band_solve, band_solve_many

  !> band_solve's info for a matrix band_factor has not factored (a program error).
  integer, parameter, public :: band_unfactored = -1

  !> Lower band storage as LAPACK's 'L': ab(1 + i - j, j) = A(i, j) for j <= i <= j + kd.
  type :: band_matrix_t
    integer :: n = 0                    !< order
    integer :: kd = 0                   !< half-bandwidth (sub-diagonals)
    real(dp), allocatable :: ab(:, :)   !< (kd + 1, n)
    logical :: factored = .false.       !< ab holds the Cholesky factor
  end type band_matrix_t

contains

  !> A zero n x n matrix of half-bandwidth kd.
  subroutine band_create(matrix, n, kd)
    type(band_matrix_t), intent(out) :: matrix
    integer, intent(in) :: n, kd
    matrix%n = n
    matrix%kd = min(kd, max(n - 1, 0))
    allocate(matrix%ab(matrix%kd + 1, n))
    matrix%ab = 0.0_dp
  end subroutine band_create

  !> Add a symmetric element matrix with global equation numbers `dofs`.
  pure subroutine band_add_element(matrix, dofs, element)
    type(band_matrix_t), intent(inout) :: matrix
    integer, intent(in) :: dofs(:)
    real(dp), intent(in) :: element(:, :)
    integer :: a, b, i, j
    do b = 1, size(dofs)
      j = dofs(b)
      do a = 1, size(dofs)
        i = dofs(a)
        if (i >= j) matrix%ab(1 + i - j, j) = matrix%ab(1 + i - j, j) + element(a, b)
      end do
    end do
  end subroutine band_add_element

  !> y = A x for the (unfactored) symmetric band matrix.
  pure function band_multiply(matrix, x) result(y)
    type(band_matrix_t), intent(in) :: matrix
    real(dp), intent(in) :: x(:)
    real(dp) :: y(size(x))
    integer :: i, j, last
    y = 0.0_dp
    do j = 1, matrix%n
      last = min(matrix%n, j + matrix%kd)
      y(j) = y(j) + matrix%ab(1, j)*x(j)
      do i = j + 1, last
        y(i) = y(i) + matrix%ab(1 + i - j, j)*x(j)
        y(j) = y(j) + matrix%ab(1 + i - j, j)*x(i)
      end do
    end do
  end function band_multiply

  !> (A x)(p) for the listed rows p (y(k) for rows(k)), A the (unfactored)
  !> symmetric band matrix: O(kd) per row.
  pure function band_multiply_rows(matrix, x, rows) result(y)
    type(band_matrix_t), intent(in) :: matrix
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: rows(:)
    real(dp) :: y(size(rows))
    integer :: i, j, k, p
    do k = 1, size(rows)
      p = rows(k)
      y(k) = 0.0_dp
      do j = max(1, p - matrix%kd), p                      ! row p, left of and on the diagonal
        y(k) = y(k) + matrix%ab(1 + p - j, j)*x(j)
      end do
      do i = p + 1, min(matrix%n, p + matrix%kd)           ! row p, right of the diagonal (column p below it)
        y(k) = y(k) + matrix%ab(1 + i - p, p)*x(i)
      end do
    end do
  end function band_multiply_rows

  !> Impose u(p) = value(p) on the equations with constrained(p) without losing
  !> symmetry: move the columns to the right-hand side, zero row and column p,
  !> keep the diagonal, and set rhs(p) = A(p,p) value(p).
  subroutine band_constrain(matrix, constrained, values, rhs)
    type(band_matrix_t), intent(inout) :: matrix
    logical, intent(in) :: constrained(:)
    real(dp), intent(in) :: values(:)
    real(dp), intent(inout) :: rhs(:)
    call band_constrain_rhs(matrix, constrained, values, rhs)
    call band_constrain_matrix(matrix, constrained)
  end subroutine band_constrain

  !> The matrix part of band_constrain: zero row and column p of every
  !> constrained equation, keep its diagonal (1 if it was 0). Done once per
  !> factorization; each right-hand side then goes through band_constrain_rhs.
  pure subroutine band_constrain_matrix(matrix, constrained)
    type(band_matrix_t), intent(inout) :: matrix
    logical, intent(in) :: constrained(:)
    integer :: i, j, p
    do p = 1, matrix%n
      if (.not. constrained(p)) cycle
      do i = p + 1, min(matrix%n, p + matrix%kd)          ! column p below the diagonal
        matrix%ab(1 + i - p, p) = 0.0_dp
      end do
      do j = max(1, p - matrix%kd), p - 1                  ! row p left of the diagonal
        matrix%ab(1 + p - j, j) = 0.0_dp
      end do
      if (matrix%ab(1, p) == 0.0_dp) matrix%ab(1, p) = 1.0_dp
    end do
  end subroutine band_constrain_matrix

  !> The right-hand-side part of band_constrain, with `matrix` the original
  !> (unconstrained, unfactored) matrix: rhs <- rhs - A v on the free
  !> equations, rhs(p) = A(p,p) v(p) on the constrained ones.
  subroutine band_constrain_rhs(matrix, constrained, values, rhs)
    type(band_matrix_t), intent(in) :: matrix
    logical, intent(in) :: constrained(:)
    real(dp), intent(in) :: values(:)
    real(dp), intent(inout) :: rhs(:)
    integer :: p
    if (any(constrained .and. values /= 0.0_dp)) rhs = rhs - band_multiply(matrix, merge(values, 0.0_dp, constrained))
    do p = 1, matrix%n
      if (.not. constrained(p)) cycle
      if (matrix%ab(1, p) == 0.0_dp) then
        rhs(p) = values(p)
      else
        rhs(p) = matrix%ab(1, p)*values(p)
      end if
    end do
  end subroutine band_constrain_rhs

  !> Cholesky factorization in place (LAPACK dpbtrf). info > 0: equation info
  !> has a non-positive pivot, or a pivot below 1e-13 of its original diagonal
  !> (numerically singular: a mechanism, a missing support or a bad material).
  subroutine band_factor(matrix, info)
    type(band_matrix_t), intent(inout) :: matrix
    integer, intent(out) :: info
    real(dp), allocatable :: original(:)
    integer :: p
    original = matrix%ab(1, :)
    call dpbtrf('L', matrix%n, matrix%kd, matrix%ab, matrix%kd + 1, info)
    if (info == 0) then
      do p = 1, matrix%n
        if (matrix%ab(1, p)**2 < 1.0e-13_dp*abs(original(p))) then
          info = p
          exit
        end if
      end do
    end if
    matrix%factored = info == 0
  end subroutine band_factor

  !> Solve A x = b in place with the factor from band_factor (LAPACK dpbtrs).
  !> info: 0 solved; band_unfactored (b unchanged) if band_factor has not
  !> factored the matrix (a program error the caller reports: factor_solve's
  !> solve_unfactored); dpbtrs' info is non-zero only for illegal arguments,
  !> excluded by construction.
  subroutine band_solve(matrix, b, info)
    type(band_matrix_t), intent(in) :: matrix
    real(dp), intent(inout) :: b(:)
    integer, intent(out) :: info
    info = band_unfactored
    if (.not. matrix%factored) return
    call dpbtrs('L', matrix%n, matrix%kd, 1, matrix%ab, matrix%kd + 1, b, matrix%n, info)
  end subroutine band_solve

  !> Solve A X = B in place for several right-hand sides at once (one pass
  !> over the factor for all of them: dpbtrs reads it once per column block);
  !> info as band_solve.
  subroutine band_solve_many(matrix, b, info)
    type(band_matrix_t), intent(in) :: matrix
    real(dp), intent(inout) :: b(:, :)
    integer, intent(out) :: info
    info = band_unfactored
    if (.not. matrix%factored) return
    info = 0
    if (size(b, 2) == 0) return
    call dpbtrs('L', matrix%n, matrix%kd, size(b, 2), matrix%ab, matrix%kd + 1, b, size(b, 1), info)
  end subroutine band_solve_many
end module visco2d_banded
