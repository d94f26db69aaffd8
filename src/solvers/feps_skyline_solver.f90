!> Skyline (profile, variable-band) LDL^T solver for symmetric positive definite matrices.
!!
!! The equations are renumbered by reverse Cuthill-McKee. The upper triangle is stored by
!! columns ("active columns"): column j holds rows first(j) .. j contiguously, diagonal last,
!! starting at col_ptr(j); pointers are 64-bit because profiles of 1e9+ entries occur.
!! After factorization column j holds l(j, first(j):j-1) followed by the pivot d(j), so that
!! A = L D L^T in the permuted numbering (Crout / active-column algorithm, inner products).
!!
!! Flop convention (self%flops): every multiply-add counts 2, every division 1. A column of
!! height h costs 2 * (sum of its inner-product lengths) + 3 * h.
module feps_skyline_solver
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_model, err_solver, err_internal, str
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_linear_solver, only: linear_solver_t, pivot_tolerance
  use feps_ordering, only: reverse_cuthill_mckee, skyline_first_rows
  implicit none
  private

  !> Columns factorized together: each finished column read from memory serves this many.
  integer, parameter :: column_block = 16

  !> Skyline LDL^T solver with reverse Cuthill-McKee ordering.
  type, extends(linear_solver_t), public :: skyline_solver_t
    private
    integer :: n = 0                        !! number of equations analysed
    integer(i8) :: matrix_nnz = 0           !! stored entries of the analysed pattern
    logical :: analyzed = .false.
    logical :: factorized = .false.
    integer :: negative_pivots = 0          !! negative d_i of the last factorization (its negative eigenvalues)
    integer, allocatable :: perm(:)         !! perm(new) = old
    integer, allocatable :: iperm(:)        !! iperm(old) = new
    integer, allocatable :: first(:)        !! first row of each column (new numbering)
    integer(i8), allocatable :: col_ptr(:)  !! (n+1) start of each column in `profile`
    real(dp), allocatable :: profile(:)     !! the skyline: A before, L and D after factorizing
  contains
    procedure :: analyze => skyline_analyze
    procedure :: factorize => skyline_factorize
    procedure :: solve => skyline_solve
    procedure :: name => skyline_name
    procedure :: determinant_sign => skyline_determinant_sign
  end type skyline_solver_t

contains

  !> Reverse Cuthill-McKee ordering, column heights and 64-bit column pointers; allocates the
  !! profile (an allocation failure returns err_solver). Sets self%factor_nnz.
  subroutine skyline_analyze(self, a, error)
    class(skyline_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer :: j, stat

    self%analyzed = .false.
    self%factorized = .false.
    ! Release the old profile before asking for a new one.
    if (allocated(self%profile)) deallocate (self%profile)
    if (a%n < 0 .or. (a%n > 0 .and. .not. allocated(a%row_ptr))) then
      call fatal_error(error, err_internal, 'skyline: analyze called with an unassembled matrix')
      return
    end if

    self%n = a%n
    self%matrix_nnz = a%nnz()
    call reverse_cuthill_mckee(a, self%perm, self%iperm)
    self%first = skyline_first_rows(a, self%iperm)

    if (allocated(self%col_ptr)) deallocate (self%col_ptr)
    allocate (self%col_ptr(self%n + 1))
    self%col_ptr(1) = 1
    do j = 1, self%n
      self%col_ptr(j + 1) = self%col_ptr(j) + int(j - self%first(j) + 1, i8)
    end do
    self%factor_nnz = self%col_ptr(self%n + 1) - 1

    allocate (self%profile(self%factor_nnz), stat=stat)
    if (stat /= 0) then
      call fatal_error(error, err_solver, 'skyline: cannot allocate the profile of ' // &
                       str(real(self%factor_nnz, dp)) // ' entries (' // &
                       str(8.0_dp * real(self%factor_nnz, dp) / 1024.0_dp**3) // &
                       ' GiB) for ' // str(self%n) // ' equations; use a sparse direct solver')
      return
    end if
    self%analyzed = .true.
  end subroutine skyline_analyze

  !> Scatter `a` into the permuted profile and factorize A = L D L^T. A pivot d_i that is not
  !! finite or is <= pivot_tolerance * a_ii fails with err_model and error%item = i (original
  !! numbering). Sets flops, pivot ratios d_i / a_ii and counts successful factorizations.
  subroutine skyline_factorize(self, a, error)
    class(skyline_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: diagonal(:), pivot(:)
    integer(i8) :: dot_terms
    integer :: n, j, block_start, block_end
    real(dp) :: d, ratio

    self%factorized = .false.
    if (.not. self%analyzed) then
      call fatal_error(error, err_internal, 'skyline: factorize called before analyze')
      return
    end if
    if (a%n /= self%n .or. a%nnz() /= self%matrix_nnz) then
      call fatal_error(error, err_internal, 'skyline: matrix pattern differs from the analysed one')
      return
    end if
    n = self%n

    call scatter_matrix(self, a, error)
    if (allocated(error)) return

    allocate (diagonal(n), pivot(n))
    do j = 1, n
      diagonal(j) = self%profile(self%col_ptr(j + 1) - 1)
    end do

    dot_terms = 0
    self%min_pivot_ratio = huge(1.0_dp)
    self%max_pivot_ratio = -huge(1.0_dp)
    ! Columns go in blocks so that each finished column read from memory serves the whole block.
    do block_start = 1, n, column_block
      block_end = min(block_start + column_block - 1, n)
      call update_from_finished_columns(self%profile, self%col_ptr, self%first, block_start, block_end, &
                                        dot_terms)
      do j = block_start, block_end
        call complete_column(self%profile, self%col_ptr, self%first, pivot, block_start, j, dot_terms)
        d = pivot(j)
        if (diagonal(j) /= 0.0_dp) then
          ratio = d / diagonal(j)
          if (ieee_is_finite(ratio)) then
            self%min_pivot_ratio = min(self%min_pivot_ratio, ratio)
            self%max_pivot_ratio = max(self%max_pivot_ratio, ratio)
          end if
        end if
        if (.not. ieee_is_finite(d) .or. d <= pivot_tolerance * diagonal(j)) then
          self%flops = flops_of(dot_terms, self%col_ptr(j + 1) - 1 - j)
          if (self%min_pivot_ratio > self%max_pivot_ratio) then
            self%min_pivot_ratio = 0.0_dp
            self%max_pivot_ratio = 0.0_dp
          end if
          call pivot_error(error, self%perm(j), d, diagonal(j))
          return
        end if
      end do
    end do

    self%flops = flops_of(dot_terms, self%factor_nnz - n)
    if (n == 0) then
      self%min_pivot_ratio = 1.0_dp
      self%max_pivot_ratio = 1.0_dp
    end if
    self%negative_pivots = count(pivot < 0.0_dp)
    self%factorizations = self%factorizations + 1
    self%factorized = .true.
  end subroutine skyline_factorize

  !> Solve A x = b in place: permute, forward substitution with L, scaling by D, back
  !! substitution with L^T, permute back.
  subroutine skyline_solve(self, b, error)
    class(skyline_solver_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: y(:)
    integer :: n, j, first_j, length
    integer(i8) :: column
    real(dp) :: x_j

    if (.not. self%factorized) then
      call fatal_error(error, err_internal, 'skyline: solve called without a successful factorization')
      return
    end if
    n = self%n
    if (size(b) /= n) then
      call fatal_error(error, err_internal, 'skyline: right-hand side has ' // str(size(b)) // &
                       ' entries, the matrix ' // str(n) // ' equations')
      return
    end if

    allocate (y(n))
    y = b(self%perm)
    associate (profile => self%profile, col_ptr => self%col_ptr, first => self%first)
      ! L z = b: column j of the profile is row j of L.
      do j = 2, n
        first_j = first(j)
        length = j - first_j
        if (length > 0) y(j) = y(j) - dot_contiguous(length, profile(col_ptr(j)), y(first_j))
      end do
      do j = 1, n
        y(j) = y(j) / profile(col_ptr(j + 1) - 1)
      end do
      ! L^T x = z, column by column: once x(j) is known, remove it from the rows above.
      do j = n, 2, -1
        first_j = first(j)
        length = j - first_j
        if (length > 0) then
          column = col_ptr(j)
          x_j = y(j)
          y(first_j:j - 1) = y(first_j:j - 1) - profile(column:column + length - 1) * x_j
        end if
      end do
    end associate
    b(self%perm) = y
  end subroutine skyline_solve

  pure function skyline_name(self) result(name)
    class(skyline_solver_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'skyline'
  end function skyline_name

  !> The sign of det D = det A after a factorization, from the pivots' signs (Sylvester: as many
  !! negative pivots as negative eigenvalues); only a matrix with a negative diagonal entry
  !! passes pivot_tolerance with a negative pivot. 0 without a factor.
  pure integer function skyline_determinant_sign(self)
    class(skyline_solver_t), intent(in) :: self
    skyline_determinant_sign = 0
    if (self%factorized) skyline_determinant_sign = merge(-1, 1, mod(self%negative_pivots, 2) == 1)
  end function skyline_determinant_sign

  !> Zero the profile and add the entries of `a` at their permuted positions.
  subroutine scatter_matrix(self, a, error)
    type(skyline_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer :: i, new_i, new_j, row, column
    integer(i8) :: k, pos

    self%profile(:) = 0.0_dp
    do i = 1, a%n
      new_i = self%iperm(i)
      do k = a%row_ptr(i), a%row_ptr(i + 1) - 1
        new_j = self%iperm(a%col(k))
        column = max(new_i, new_j)
        row = min(new_i, new_j)
        if (row < self%first(column)) then
          call fatal_error(error, err_internal, 'skyline: entry (' // str(i) // ', ' // &
                           str(a%col(k)) // ') lies outside the analysed profile')
          return
        end if
        pos = self%col_ptr(column + 1) - 1 - (column - row)
        self%profile(pos) = self%profile(pos) + a%val(k)
      end do
    end do
  end subroutine scatter_matrix

  !> Error for a bad pivot of original equation `equation`.
  pure subroutine pivot_error(error, equation, pivot, diagonal)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in) :: equation
    real(dp), intent(in) :: pivot, diagonal

    if (.not. ieee_is_finite(pivot)) then
      call fatal_error(error, err_model, 'skyline: pivot of equation ' // str(equation) // &
                       ' is not finite (diagonal entry ' // str(diagonal) // ')', item=equation)
    else
      call fatal_error(error, err_model, 'skyline: pivot of equation ' // str(equation) // ' is ' // &
                       str(pivot) // ', not above ' // str(pivot_tolerance) // ' times its diagonal entry ' // &
                       str(diagonal) // ': the stiffness is singular or not positive definite ' // &
                       '(missing support or mechanism?)', item=equation)
    end if
  end subroutine pivot_error

  !> Flops of the factorization: 2 per inner-product term, 1 division and 1 multiply-add per
  !! off-diagonal profile entry.
  pure real(dp) function flops_of(dot_terms, offdiagonal_entries)
    integer(i8), intent(in) :: dot_terms, offdiagonal_entries
    flops_of = 2.0_dp * real(dot_terms, dp) + 3.0_dp * real(offdiagonal_entries, dp)
  end function flops_of

  !> First half of the Crout step for the columns block_start..block_end: subtract from each
  !! g(i, j) = a(i, j) - sum_k l(i, k) g(k, j) the contributions of the rows i < block_start,
  !! whose columns are finished. Row i is the outer loop so that column i, once in cache,
  !! serves every column of the block.
  pure subroutine update_from_finished_columns(profile, col_ptr, first, block_start, block_end, dot_terms)
    real(dp), intent(inout) :: profile(*)  ! assumed size: columns are passed by their first element
    integer(i8), intent(in) :: col_ptr(:)
    integer, intent(in) :: first(:)
    integer, intent(in) :: block_start, block_end
    integer(i8), intent(inout) :: dot_terms
    integer(i8) :: base_i
    integer :: i, j

    ! The top row of a column needs no correction.
    do i = minval(first(block_start:block_end)) + 1, block_start - 1
      base_i = col_ptr(i) - first(i)
      do j = block_start, block_end
        if (first(j) < i) call subtract_dot(profile, base_i, col_ptr(j) - first(j), max(first(i), first(j)), &
                                            i, dot_terms)
      end do
    end do
  end subroutine update_from_finished_columns

  !> Second half of the Crout step for column j: the rows block_start <= i < j (columns
  !! finished earlier in this block), then l(j, i) = g(i) / d(i) and
  !! d(j) = a(j, j) - sum_i l(j, i) g(i), stored in pivot(j) and on the diagonal.
  pure subroutine complete_column(profile, col_ptr, first, pivot, block_start, j, dot_terms)
    real(dp), intent(inout) :: profile(*)  ! assumed size: columns are passed by their first element
    integer(i8), intent(in) :: col_ptr(:)
    integer, intent(in) :: first(:)
    real(dp), intent(inout) :: pivot(:)
    integer, intent(in) :: block_start, j
    integer(i8), intent(inout) :: dot_terms
    integer(i8) :: base_j
    integer :: i, first_j
    real(dp) :: g, l, d

    first_j = first(j)
    base_j = col_ptr(j) - first_j
    do i = max(block_start, first_j + 1), j - 1
      call subtract_dot(profile, col_ptr(i) - first(i), base_j, max(first(i), first_j), i, dot_terms)
    end do
    d = profile(base_j + j)
    do i = first_j, j - 1
      g = profile(base_j + i)
      l = g / pivot(i)
      profile(base_j + i) = l
      d = d - l * g
    end do
    pivot(j) = d
    profile(base_j + j) = d
  end subroutine complete_column

  !> profile(base_j + i) -= sum over rows start .. i-1 of column i times column j, where row
  !! r of column i is at base_i + r and of column j at base_j + r.
  pure subroutine subtract_dot(profile, base_i, base_j, start, i, dot_terms)
    real(dp), intent(inout) :: profile(*)  ! assumed size: columns are passed by their first element
    integer(i8), intent(in) :: base_i, base_j
    integer, intent(in) :: start, i
    integer(i8), intent(inout) :: dot_terms
    if (start >= i) return
    profile(base_j + i) = profile(base_j + i) &
                          - dot_contiguous(i - start, profile(base_i + start), profile(base_j + start))
    dot_terms = dot_terms + (i - start)
  end subroutine subtract_dot

  !> Inner product of two contiguous vectors. Eight independent partial sums let the compiler
  !! vectorise without reassociating a single reduction.
  pure real(dp) function dot_contiguous(length, x, y) result(s)
    integer, intent(in) :: length
    real(dp), intent(in) :: x(length), y(length)
    real(dp) :: partial(8)
    integer :: k, blocked

    partial = 0.0_dp
    blocked = length - mod(length, 8)
    do k = 1, blocked, 8
      partial = partial + x(k:k + 7) * y(k:k + 7)
    end do
    s = ((partial(1) + partial(5)) + (partial(2) + partial(6))) + &
        ((partial(3) + partial(7)) + (partial(4) + partial(8)))
    do k = blocked + 1, length
      s = s + x(k) * y(k)
    end do
  end function dot_contiguous

end module feps_skyline_solver
