!> Symmetric sparse matrix in compressed rows, lower triangle only (column <= row),
!! columns sorted ascending in each row, so the diagonal is the last entry of its row.
!! The same arrays read as compressed columns are the upper triangle (CHOLMOD stype = +1).
module feps_sparse_matrix
  use feps_kinds, only: dp, i8
  !$ use omp_lib, only: omp_get_max_threads
  implicit none
  private

  !> Matrices with fewer stored entries are multiplied on one thread (a parallel region costs
  !! more than it saves).
  integer(i8), parameter :: threaded_entries = 100000_i8

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
  !! On several OpenMP threads (a matrix of at least `threaded_entries`) each thread takes a
  !! block of rows and adds only into its own block's rows; the terms of later blocks' rows for
  !! earlier blocks' rows follow on one thread, block after block, so every y(j) still receives
  !! its terms in that order: the same bits on any number of threads.
  subroutine csr_multiply(self, x, y)
    class(csr_matrix_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    integer, allocatable :: first_row(:)
    integer :: parts, b
    y = 0.0_dp
    parts = 1
    !$ parts = omp_get_max_threads()
    if (parts <= 1 .or. self%nnz() < threaded_entries) then
      call multiply_rows(self, x, y, 1, self%n)
      return
    end if
    first_row = row_blocks(self, parts)
    !$omp parallel do schedule(static, 1) num_threads(parts)
    do b = 1, parts
      call multiply_rows(self, x, y, first_row(b), first_row(b + 1) - 1)
    end do
    !$omp end parallel do
    do b = 2, parts
      call add_earlier_block_terms(self, x, y, first_row(b), first_row(b + 1) - 1)
    end do
  end subroutine csr_multiply

  !> Rows lo..hi of y = A x, adding their transposed terms into rows lo..hi only.
  pure subroutine multiply_rows(self, x, y, lo, hi)
    class(csr_matrix_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(inout) :: y(:)
    integer, intent(in) :: lo, hi
    real(dp) :: s, xi
    integer :: i, j
    integer(i8) :: k
    do i = lo, hi
      xi = x(i)
      s = 0.0_dp
      do k = self%row_ptr(i), self%row_ptr(i + 1) - 1
        j = self%col(k)
        s = s + self%val(k) * x(j)
        if (j /= i .and. j >= lo) y(j) = y(j) + self%val(k) * xi
      end do
      ! y(i) is still 0 here (only later rows add to it), so this stores s exactly
      y(i) = y(i) + s
    end do
  end subroutine multiply_rows

  !> The transposed terms of rows lo..hi for the rows before lo (the leading entries of each
  !! row: columns are sorted), in row order.
  pure subroutine add_earlier_block_terms(self, x, y, lo, hi)
    class(csr_matrix_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(inout) :: y(:)
    integer, intent(in) :: lo, hi
    integer :: i, j
    integer(i8) :: k
    do i = lo, hi
      do k = self%row_ptr(i), self%row_ptr(i + 1) - 1
        j = self%col(k)
        if (j >= lo) exit
        y(j) = y(j) + self%val(k) * x(i)
      end do
    end do
  end subroutine add_earlier_block_terms

  !> First rows of `parts` blocks of about equal numbers of entries (and n + 1 last).
  pure function row_blocks(self, parts) result(first_row)
    class(csr_matrix_t), intent(in) :: self
    integer, intent(in) :: parts
    integer :: first_row(parts + 1)
    integer :: b, lo, hi, mid
    integer(i8) :: target
    first_row(1) = 1
    first_row(parts + 1) = self%n + 1
    do b = 2, parts
      target = 1 + (self%nnz() * (b - 1)) / parts
      lo = first_row(b - 1)
      hi = self%n + 1
      do while (lo < hi)          ! the first row that starts at or after target
        mid = (lo + hi) / 2
        if (self%row_ptr(mid) < target) then
          lo = mid + 1
        else
          hi = mid
        end if
      end do
      first_row(b) = lo
    end do
  end function row_blocks

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
