!> Explicit interfaces to the LAPACK and BLAS routines feps calls (double precision, and the
!! single-precision sgemv and strsv of mixed-precision solves; reference argument lists,
!! default-integer LP64 build).
module feps_lapack
  use feps_kinds, only: dp, sp
  implicit none
  private

  public :: dposv, dsyev, dgesv, dgemm, dpotrf, dgemv, dtrsv, sgemv, strsv

  interface
    !> Solve A X = B for symmetric positive definite A by Cholesky factorization.
    subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character(len=1), intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: info
    end subroutine dposv

    !> Eigenvalues (and optionally eigenvectors) of a symmetric matrix.
    subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
      import :: dp
      character(len=1), intent(in) :: jobz, uplo
      integer, intent(in) :: n, lda, lwork
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: w(*), work(*)
      integer, intent(out) :: info
    end subroutine dsyev

    !> Solve A X = B for a general A by LU factorization with partial pivoting.
    subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: dp
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgesv

    !> C = alpha op(A) op(B) + beta C.
    subroutine dgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
      import :: dp
      character(len=1), intent(in) :: transa, transb
      integer, intent(in) :: m, n, k, lda, ldb, ldc
      real(dp), intent(in) :: alpha, beta
      real(dp), intent(in) :: a(lda, *), b(ldb, *)
      real(dp), intent(inout) :: c(ldc, *)
    end subroutine dgemm

    !> y = alpha op(A) x + beta y.
    subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
      import :: dp
      character(len=1), intent(in) :: trans
      integer, intent(in) :: m, n, lda, incx, incy
      real(dp), intent(in) :: alpha, beta
      real(dp), intent(in) :: a(lda, *), x(*)
      real(dp), intent(inout) :: y(*)
    end subroutine dgemv

    !> x = op(A)^-1 x for a triangular A.
    subroutine dtrsv(uplo, trans, diag, n, a, lda, x, incx)
      import :: dp
      character(len=1), intent(in) :: uplo, trans, diag
      integer, intent(in) :: n, lda, incx
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: x(*)
    end subroutine dtrsv

    !> y = alpha op(A) x + beta y in single precision.
    subroutine sgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
      import :: sp
      character(len=1), intent(in) :: trans
      integer, intent(in) :: m, n, lda, incx, incy
      real(sp), intent(in) :: alpha, beta
      real(sp), intent(in) :: a(lda, *), x(*)
      real(sp), intent(inout) :: y(*)
    end subroutine sgemv

    !> x = op(A)^-1 x for a triangular A in single precision.
    subroutine strsv(uplo, trans, diag, n, a, lda, x, incx)
      import :: sp
      character(len=1), intent(in) :: uplo, trans, diag
      integer, intent(in) :: n, lda, incx
      real(sp), intent(in) :: a(lda, *)
      real(sp), intent(inout) :: x(*)
    end subroutine strsv

    !> Cholesky factorization of a symmetric positive definite matrix.
    subroutine dpotrf(uplo, n, a, lda, info)
      import :: dp
      character(len=1), intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotrf
  end interface

end module feps_lapack
