!> Explicit interfaces of the BLAS and LAPACK routines visco2d calls (and its
!> tests), in one place, so that every call is checked against the same
!> argument list. The BLAS kernels are declared pure (they touch only their
!> arguments), so pure procedures may call them.
module visco2d_lapack
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: ddot, daxpy, dgemv, dger
  public :: dpbtrf, dpbtrs, dpotrf, dpotrs, dsyev, dgels

  interface
    !> x . y (BLAS 1).
    pure function ddot(n, x, incx, y, incy)
      import :: dp
      integer, intent(in) :: n, incx, incy
      real(dp), intent(in) :: x(*), y(*)
      real(dp) :: ddot
    end function ddot
    !> y <- alpha x + y (BLAS 1).
    pure subroutine daxpy(n, alpha, x, incx, y, incy)
      import :: dp
      integer, intent(in) :: n, incx, incy
      real(dp), intent(in) :: alpha, x(*)
      real(dp), intent(inout) :: y(*)
    end subroutine daxpy
    !> y <- alpha op(A) x + beta y (BLAS 2).
    pure subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
      import :: dp
      character, intent(in) :: trans
      integer, intent(in) :: m, n, lda, incx, incy
      real(dp), intent(in) :: alpha, a(lda, *), x(*), beta
      real(dp), intent(inout) :: y(*)
    end subroutine dgemv
    !> A <- alpha x y^T + A (BLAS 2).
    pure subroutine dger(m, n, alpha, x, incx, y, incy, a, lda)
      import :: dp
      integer, intent(in) :: m, n, incx, incy, lda
      real(dp), intent(in) :: alpha, x(*), y(*)
      real(dp), intent(inout) :: a(lda, *)
    end subroutine dger
    !> Cholesky factor of a symmetric positive definite band matrix.
    subroutine dpbtrf(uplo, n, kd, ab, ldab, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, kd, ldab
      real(dp), intent(inout) :: ab(ldab, *)
      integer, intent(out) :: info
    end subroutine dpbtrf
    !> Solve with the band Cholesky factor of dpbtrf.
    subroutine dpbtrs(uplo, n, kd, nrhs, ab, ldab, b, ldb, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, kd, nrhs, ldab, ldb
      real(dp), intent(in) :: ab(ldab, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dpbtrs
    !> Cholesky factor of a dense symmetric positive definite matrix.
    subroutine dpotrf(uplo, n, a, lda, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotrf
    !> Solve with the dense Cholesky factor of dpotrf.
    subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dpotrs
    !> Eigenvalues (and vectors) of a dense symmetric matrix.
    subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
      import :: dp
      character, intent(in) :: jobz, uplo
      integer, intent(in) :: n, lda, lwork
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: w(*), work(*)
      integer, intent(out) :: info
    end subroutine dsyev
    !> Least-squares solution of an over-determined system (QR).
    subroutine dgels(trans, m, n, nrhs, a, lda, b, ldb, work, lwork, info)
      import :: dp
      character, intent(in) :: trans
      integer, intent(in) :: m, n, nrhs, lda, ldb, lwork
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      real(dp), intent(out) :: work(*)
      integer, intent(out) :: info
    end subroutine dgels
  end interface
end module visco2d_lapack
