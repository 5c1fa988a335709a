!> Profile (envelope, "skyline") storage of a symmetric positive definite
!> matrix and its Cholesky factor S = L L^T (eq. [34]'s S~): row i keeps
!> L(i, first(i):i), from its first non-zero to the diagonal, one row after
!> the other. Cholesky creates no fill outside this envelope, so the factor
!> needs no more storage than the matrix; after the reverse Cuthill-McKee
!> numbering of visco2d_renumber the envelope of a sphere mesh is about a
!> third of the band (n (kd + 1)), and the substitutions, which stream
!> through the factor once forward and once back, read a third as much.
!> The arithmetic is the band Cholesky's (dpbtrf/dpbtrs) without the zeros
!> between the band's edge and each row's first non-zero.
module visco2d_profile
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_lapack, only: ddot, daxpy, dgemv, dger   ! the inner loops (see below)
  use visco2d_banded, only: band_matrix_t
  implicit none
  private

  public :: profile_matrix_t, profile_from_band, profile_factor, profile_solve, profile_solve_many

  !> profile_solve's info for a matrix profile_factor has not factored (a program error).
  integer, parameter, public :: profile_unfactored = -1

  ! The inner loops are BLAS calls: the optimized BLAS vectorizes the dot
  ! products, which the compiler may not (reordering a sum changes its
  ! round-off, so it keeps the sequential order without -ffast-math).

  !> Row i of the lower triangle, columns first(i) .. i, in
  !> values(start(i) : start(i) + i - first(i)) (the diagonal last).
  type :: profile_matrix_t
    integer :: n = 0                          !< order
    integer, allocatable :: first(:)          !< (n) column of row i's first non-zero
    integer(int64), allocatable :: start(:)       !< (n + 1) where row i starts in values
    real(dp), allocatable :: values(:)        !< the envelope, row after row
    logical :: factored = .false.             !< values hold the Cholesky factor L
  end type profile_matrix_t

contains

  !> The envelope of a symmetric band matrix (lower band storage) with the
  !> equations of `constrained` eliminated as band_constrain_matrix does
  !> (row and column zeroed, the diagonal kept, 1 if it was 0), with its
  !> values: each row from its first non-zero (exact zeros left of it are
  !> dropped) to the diagonal. `band` is left unchanged.
  subroutine profile_from_band(band, profile, constrained)
    type(band_matrix_t), intent(in) :: band
    type(profile_matrix_t), intent(inout) :: profile
    logical, intent(in) :: constrained(:)
    integer :: i, j, n
    integer(int64) :: at
    n = band%n
    profile%n = n
    profile%factored = .false.
    if (allocated(profile%first)) then
      if (size(profile%first) /= n) deallocate(profile%first, profile%start)
    end if
    if (.not. allocated(profile%first)) allocate(profile%first(n), profile%start(n + 1))
    profile%start(1) = 1
    do i = 1, n
      profile%first(i) = i
      if (.not. constrained(i)) then
        do j = max(1, i - band%kd), i - 1
          if (band%ab(1 + i - j, j) /= 0.0_dp .and. .not. constrained(j)) then
            profile%first(i) = j
            exit
          end if
        end do
      end if
      profile%start(i + 1) = profile%start(i) + (i - profile%first(i) + 1)
    end do
    if (allocated(profile%values)) then
      if (size(profile%values, kind=int64) /= profile%start(n + 1) - 1) deallocate(profile%values)
    end if
    if (.not. allocated(profile%values)) allocate(profile%values(profile%start(n + 1) - 1))
    do i = 1, n
      at = profile%start(i) - profile%first(i)
      do j = profile%first(i), i - 1
        profile%values(at + j) = merge(0.0_dp, band%ab(1 + i - j, j), constrained(j))
      end do
      profile%values(at + i) = band%ab(1, i)
      if (constrained(i) .and. band%ab(1, i) == 0.0_dp) profile%values(at + i) = 1.0_dp
    end do
  end subroutine profile_from_band

  !> Cholesky factorization in place, row by row (the "bordering" form: row
  !> i of L solves L(1:i-1, 1:i-1) l = S(i, 1:i-1) over its envelope, then
  !> L(i, i) = sqrt(S(i, i) - l . l)). info > 0: equation info has a
  !> non-positive pivot, or a pivot below 1e-13 of its original diagonal
  !> (numerically singular), as band_factor.
  subroutine profile_factor(profile, info)
    type(profile_matrix_t), intent(inout) :: profile
    integer, intent(out) :: info
    integer :: i, j, k0, small
    integer(int64) :: row_i, row_j
    real(dp) :: diagonal, pivot
    info = 0
    small = 0
    do i = 1, profile%n
      row_i = profile%start(i) - profile%first(i)          ! values(row_i + j) = L(i, j)
      do j = profile%first(i), i - 1
        row_j = profile%start(j) - profile%first(j)
        k0 = max(profile%first(i), profile%first(j))
        profile%values(row_i + j) = (profile%values(row_i + j) &
          - ddot(j - k0, profile%values(row_i + k0), 1, profile%values(row_j + k0), 1))/profile%values(row_j + j)
      end do
      diagonal = profile%values(row_i + i)
      pivot = diagonal - ddot(i - profile%first(i), profile%values(row_i + profile%first(i)), 1, &
                              profile%values(row_i + profile%first(i)), 1)
      if (.not. (pivot > 0.0_dp)) then                       ! dpbtrf stops here
        info = i
        exit
      end if
      if (pivot < 1.0e-13_dp*abs(diagonal) .and. small == 0) small = i
      profile%values(row_i + i) = sqrt(pivot)
    end do
    if (info == 0) info = small
    profile%factored = info == 0
  end subroutine profile_factor

  !> Solve S x = b in place with the factor: L y = b forward (a dot product
  !> per row), then L^T x = y backward (an axpy per row), each one pass over
  !> the envelope. info: 0 solved; profile_unfactored (b unchanged) if
  !> profile_factor has not factored the matrix (a program error the caller
  !> reports: factor_solve's solve_unfactored).
  subroutine profile_solve(profile, b, info)
    type(profile_matrix_t), intent(in) :: profile
    real(dp), intent(inout), contiguous :: b(:)
    integer, intent(out) :: info
    integer :: i, f
    integer(int64) :: row
    info = profile_unfactored
    if (.not. profile%factored) return
    info = 0
    do i = 1, profile%n
      f = profile%first(i)
      row = profile%start(i) - f
      b(i) = (b(i) - ddot(i - f, profile%values(row + f), 1, b(f:i - 1), 1))/profile%values(row + i)
    end do
    do i = profile%n, 1, -1
      f = profile%first(i)
      row = profile%start(i) - f
      b(i) = b(i)/profile%values(row + i)
      call daxpy(i - f, -b(i), profile%values(row + f), 1, b(f:i - 1), 1)
    end do
  end subroutine profile_solve

  !> Solve S X = B in place for several right-hand sides, one pass over the
  !> factor for all of them (B transposed into a work array so that every
  !> row of L is applied to all columns while it is in cache); info as
  !> profile_solve.
  subroutine profile_solve_many(profile, b, info)
    type(profile_matrix_t), intent(in) :: profile
    real(dp), intent(inout) :: b(:, :)
    integer, intent(out) :: info
    real(dp), allocatable :: x(:, :)
    integer :: i, f, m
    integer(int64) :: row
    info = profile_unfactored
    if (.not. profile%factored) return
    info = 0
    if (size(b, 2) == 0) return
    if (size(b, 2) == 1) then
      x = b
      call profile_solve(profile, x(:, 1), info)
      b = x
      return
    end if
    x = transpose(b)                                       ! x(:, i): row i of B
    m = size(x, 1)
    do i = 1, profile%n                                    ! L Y = B: x(:, i) -= X(:, f:i-1) L(i, f:i-1)^T
      f = profile%first(i)
      row = profile%start(i) - f
      if (i > f) call dgemv('N', m, i - f, -1.0_dp, x(1, f), m, profile%values(row + f), 1, 1.0_dp, x(1, i), 1)
      x(:, i) = x(:, i)/profile%values(row + i)
    end do
    do i = profile%n, 1, -1                                ! L^T X = Y: X(:, f:i-1) -= x(:, i) L(i, f:i-1)
      f = profile%first(i)
      row = profile%start(i) - f
      x(:, i) = x(:, i)/profile%values(row + i)
      if (i > f) call dger(m, i - f, -1.0_dp, x(1, i), 1, profile%values(row + f), 1, x(1, f), m)
    end do
    b = transpose(x)
  end subroutine profile_solve_many
end module visco2d_profile
