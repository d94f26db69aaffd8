!> Symmetric sparse matrix in compressed rows, lower triangle only (column <= row),
!! columns sorted ascending in each row, so the diagonal is the last entry of its row.
!! The same arrays read as compressed columns are the upper triangle (CHOLMOD stype = +1).
module feps_sparse_matrix
  use feps_kinds, only: dp, i8
  implicit none
  private

  type, public :: csr_matrix_t
    integer :: n = 0                        !! number of equations
    integer(i8), allocatable :: row_ptr(:)  !! (n+1), 1-based: row i is row_ptr(i) .. row_ptr(i+1)-1
    integer, allocatable :: col(:)          !! column of each entry, 1-based
    real(dp), allocatable :: val(:)         !! values
  contains
    procedure :: nnz => csr_nnz
    procedure :: find => csr_find           !! position of (i, j), j <= i, or 0
    procedure :: multiply => csr_multiply   !! y = A x with the full symmetric matrix
    procedure :: diagonal => csr_diagonal
  end type csr_matrix_t

contains

  pure integer(i8) function csr_nnz(self)
    class(csr_matrix_t), intent(in) :: self
    csr_nnz = 0
    if (allocated(self%row_ptr)) csr_nnz = self%row_ptr(self%n + 1) - 1
  end function csr_nnz

  !> Binary search of column j in row i (j <= i).
  pure integer(i8) function csr_find(self, i, j) result(pos)
    class(csr_matrix_t), intent(in) :: self
    integer, intent(in) :: i, j
    integer(i8) :: lo, hi, mid
    lo = self%row_ptr(i)
    hi = self%row_ptr(i + 1) - 1
    pos = 0
    do while (lo <= hi)
      mid = (lo + hi) / 2
      if (self%col(mid) == j) then
        pos = mid
        return
      else if (self%col(mid) < j) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function csr_find

  pure subroutine csr_multiply(self, x, y)
    class(csr_matrix_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    integer :: i, j
    integer(i8) :: k
    y = 0.0_dp
    do i = 1, self%n
      do k = self%row_ptr(i), self%row_ptr(i + 1) - 1
        j = self%col(k)
        y(i) = y(i) + self%val(k) * x(j)
        if (j /= i) y(j) = y(j) + self%val(k) * x(i)
      end do
    end do
  end subroutine csr_multiply

  pure function csr_diagonal(self) result(d)
    class(csr_matrix_t), intent(in) :: self
    real(dp) :: d(self%n)
    integer :: i
    do i = 1, self%n
      d(i) = self%val(self%row_ptr(i + 1) - 1)
    end do
  end function csr_diagonal

end module feps_sparse_matrix
