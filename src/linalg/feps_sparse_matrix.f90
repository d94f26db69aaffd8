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

  public :: full_pattern

contains

  !> Number of stored entries (the lower triangle); 0 before the pattern is set.
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

  !> y = A x with the full symmetric matrix (each off-diagonal entry used twice).
  !! Row i's own sum is kept in a register and stored once, while its off-diagonal entries are
  !! added into the earlier rows. Every y(j) receives the same terms in the same order as the
  !! form that updates y(i) in memory entry by entry (row j's own entries, then one term from
  !! each later row in row order), so the results are bit-identical to it, 2.7x faster on
  !! FE1 (docs/performance.md, "The solve pair").
  pure subroutine csr_multiply(self, x, y)
    class(csr_matrix_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    real(dp) :: s, xi
    integer :: i, j
    integer(i8) :: k, first, last
    y = 0.0_dp
    do i = 1, self%n
      first = self%row_ptr(i)
      last = self%row_ptr(i + 1) - 1
      xi = x(i)
      s = 0.0_dp
      do k = first, last
        j = self%col(k)
        s = s + self%val(k) * x(j)
        if (j /= i) y(j) = y(j) + self%val(k) * xi
      end do
      ! y(i) is still 0 here (only later rows add to it), so this stores s exactly
      y(i) = y(i) + s
    end do
  end subroutine csr_multiply

  !> The diagonal entries, the last entry of each row.
  pure function csr_diagonal(self) result(d)
    class(csr_matrix_t), intent(in) :: self
    real(dp) :: d(self%n)
    integer :: i
    do i = 1, self%n
      d(i) = self%val(self%row_ptr(i + 1) - 1)
    end do
  end function csr_diagonal

  !> The pattern of both triangles of the symmetric `lower` (values zero), for a
  !! non-symmetric matrix with the same structure: columns sorted in each row, so `find`
  !! works on it for any (i, j) (multiply and diagonal do not: they assume the lower triangle).
  pure subroutine full_pattern(lower, full)
    type(csr_matrix_t), intent(in) :: lower
    type(csr_matrix_t), intent(out) :: full
    integer(i8), allocatable :: next(:)
    integer :: i, j
    integer(i8) :: k
    full%n = lower%n
    allocate (full%row_ptr(lower%n + 1), next(lower%n))
    ! row i holds its lower entries and, from the rows below, the transposes of theirs
    full%row_ptr = 0
    do i = 1, lower%n
      do k = lower%row_ptr(i), lower%row_ptr(i + 1) - 1
        j = lower%col(k)
        full%row_ptr(i + 1) = full%row_ptr(i + 1) + 1
        if (j /= i) full%row_ptr(j + 1) = full%row_ptr(j + 1) + 1
      end do
    end do
    full%row_ptr(1) = 1
    do i = 1, lower%n
      full%row_ptr(i + 1) = full%row_ptr(i + 1) + full%row_ptr(i)
    end do
    allocate (full%col(full%row_ptr(lower%n + 1) - 1))
    allocate (full%val(size(full%col)))
    full%val = 0.0_dp
    ! rows in order: row i's lower entries (columns <= i) come first, then the transposed ones
    ! from rows j > i arrive in increasing j, so every row ends up sorted
    next = full%row_ptr(1:lower%n)
    do i = 1, lower%n
      do k = lower%row_ptr(i), lower%row_ptr(i + 1) - 1
        j = lower%col(k)
        full%col(next(i)) = j
        next(i) = next(i) + 1
        if (j /= i) then
          full%col(next(j)) = i
          next(j) = next(j) + 1
        end if
      end do
    end do
  end subroutine full_pattern

end module feps_sparse_matrix
