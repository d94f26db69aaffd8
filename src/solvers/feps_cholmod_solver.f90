!> Sparse Cholesky solver using CHOLMOD (supernodal, METIS ordering) through the C shim.
!! METIS orders the graph of supervariables (equations with identical pattern, such as the
!! DOFs of one node), and CHOLMOD's own METIS ordering is the fallback.
!! The CHOLMOD state lives behind a C handle that the finalizer frees; do not copy a
!! cholmod_solver_t after analysis (the copy would share, and later free, the same handle).
module feps_cholmod_solver
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_int64_t
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_model, err_solver, err_internal, err_memory, str
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_linear_solver, only: linear_solver_t, pivot_tolerance
  use feps_strings, only: gib_text
  use feps_cholmod_bindings, only: feps_chol_create, feps_chol_free, feps_chol_analyze, &
    feps_chol_factorize, feps_chol_solve, feps_chol_flops, feps_chol_lnz, feps_chol_status, &
    feps_chol_failed_column, feps_chol_min_ratio, feps_chol_max_ratio, feps_chol_min_ratio_column, &
    feps_chol_supervariables, feps_chol_count_supervariables, feps_chol_supernodes, chol_ok, chol_bad_input, &
    chol_not_posdef, chol_not_ready, feps_chol_multiply
  use feps_supernodal_solve, only: supernodal_solve_t
  implicit none
  private

  public :: count_supervariables

  !> The largest relative error of a mixed-precision factor's test solve for which its solves
  !! go on in single precision. A step's iterations correct each solve against their
  !! double-precision residual, as they correct the initial stiffness's difference from the
  !! tangent; a copy much further off loses what they cannot restore: test/data's
  !! sec2_3_4_lift.dat (test solve off by 0.17) ended 1.8e-2 from its double-precision run. The
  !! thesis's models pass well below it (FE1 8.2e-5, PE1 1.6e-4, model C 1.8e-5;
  !! docs/tradeoff.md).
  real(dp), parameter, public :: mixed_tolerance = 1.0e-3_dp

  !> Mixed precision makes a factor's single-precision copy at its (mixed_after + 1)-th solve:
  !! the copy and its test cost about two solves, which a factor solved once or twice (full
  !! Newton's, one per iteration; an arc-length iteration's pair) would not repay, and whose
  !! quadratic convergence the inexact solves would slow (docs/tradeoff.md).
  integer, parameter :: mixed_after = 2

  !> CHOLMOD's status when it cannot allocate (CHOLMOD_OUT_OF_MEMORY in cholmod.h).
  integer, parameter :: cholmod_out_of_memory = -2

  !> CHOLMOD LL' solver: analyze once per pattern, factorize per set of values, solve many times.
  type, extends(linear_solver_t), public :: cholmod_solver_t
    private
    type(c_ptr) :: handle = c_null_ptr
    integer :: n = 0                 !! equations of the analysed pattern
    integer(i8) :: nnz = 0           !! stored entries of the analysed pattern
    logical :: factorized = .false.  !! a valid factor is available for solve
    integer(i8) :: graph_vertices = 0 !! supervariables METIS ordered; 0 for the fallback
    !> feps's own solves with a supernodal factor (threaded, the same bits for any number of
    !! threads); without a plan (no factor, or a simplicial one) CHOLMOD solves
    type(supernodal_solve_t) :: plan
    !> Mixed precision ('cholmod-mixed'): the factorization in double precision, the solves from
    !! a factor's third on with a single-precision copy of it, half the bytes each solve
    !! streams. A solve is then good to about kappa(A) 6e-8, which the iterations of a nonlinear
    !! step correct against their double-precision residual (docs/tradeoff.md)
    logical, public :: mixed = .false.
    !> With mixed precision: the relative error of the test solve of the last factor (see
    !! `start_single_solves`; the largest of those solved in single precision and the factors
    !! solved in double precision instead are linear_solver_t's test_solve_error and
    !! precision_fallbacks), and whether the current factor's copy was tried
    real(dp), public :: mixed_error = 0.0_dp
    logical :: copy_tried = .false.
  contains
    procedure :: analyze => cholmod_analyze
    procedure :: factorize => cholmod_factorize
    procedure :: solve => cholmod_solve
    procedure :: library_solve => cholmod_library_solve
    procedure :: solve_threads => cholmod_solve_threads
    procedure :: name => cholmod_name
    procedure :: determinant_sign => cholmod_determinant_sign
    procedure :: supervariables => cholmod_supervariables
    final :: cholmod_finalize
  end type cholmod_solver_t

contains

  !> METIS ordering and supernodal symbolic analysis of the pattern of `a`.
  subroutine cholmod_analyze(self, a, error)
    class(cholmod_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code

    self%factorized = .false.
    call self%plan%clear()
    self%n = 0
    self%nnz = 0
    self%graph_vertices = 0
    call check_arrays(a, 'analyze', error)
    if (allocated(error)) return
    if (.not. c_associated(self%handle)) self%handle = feps_chol_create()
    if (.not. c_associated(self%handle)) then
      call fatal_error(error, err_solver, 'cholmod: cannot start CHOLMOD (out of memory)')
      return
    end if

    code = feps_chol_analyze(self%handle, int(a%n, c_int64_t), a%row_ptr, a%col)
    select case (code)
    case (chol_ok)
    case (chol_bad_input)
      call fatal_error(error, err_internal, 'cholmod: pattern is not a sorted lower triangle ' // &
                       'with the diagonal last in each row')
      return
    case default
      if (feps_chol_status(self%handle) == cholmod_out_of_memory) then
        call fatal_error(error, err_memory, 'cholmod: the ordering and analysis of ' // str(a%n) // &
                         ' equations (' // str(real(a%nnz(), dp)) // ' matrix entries) do not fit in the ' // &
                         'memory this process may use (its address-space limit, ulimit -v, or the machine''s memory)')
        return
      end if
      call fatal_error(error, err_solver, 'cholmod: analysis failed (CHOLMOD status ' // &
                       str(int(feps_chol_status(self%handle))) // ')')
      return
    end select
    self%n = a%n
    self%nnz = a%nnz()
    self%factor_nnz = feps_chol_lnz(self%handle)
    self%flops = feps_chol_flops(self%handle)
    self%graph_vertices = feps_chol_supervariables(self%handle)
  end subroutine cholmod_analyze

  !> Numerical LL' factorization. Fails with err_model, naming the equation in error%item,
  !! when a pivot is not positive or pivot / diagonal <= pivot_tolerance.
  subroutine cholmod_factorize(self, a, error)
    class(cholmod_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code
    integer :: equation

    self%factorized = .false.
    call self%plan%clear()
    if (.not. c_associated(self%handle) .or. self%n == 0) then
      call fatal_error(error, err_internal, 'cholmod: factorize called before analyze')
      return
    end if
    if (a%n /= self%n .or. .not. allocated(a%val)) then
      call fatal_error(error, err_internal, 'cholmod: matrix does not match the analysed pattern')
      return
    end if
    if (size(a%val, kind=i8) < self%nnz) then
      call fatal_error(error, err_internal, 'cholmod: matrix does not match the analysed pattern')
      return
    end if

    code = feps_chol_factorize(self%handle, a%val)
    self%min_pivot_ratio = feps_chol_min_ratio(self%handle)
    self%max_pivot_ratio = feps_chol_max_ratio(self%handle)
    select case (code)
    case (chol_ok)
    case (chol_not_posdef)
      equation = int(feps_chol_failed_column(self%handle))
      call fatal_error(error, err_model, 'cholmod: stiffness matrix not positive definite at equation ' // &
                       str(equation) // ' (unconstrained, mechanism or negative stiffness)', equation)
      return
    case (chol_not_ready)
      call fatal_error(error, err_internal, 'cholmod: factorize called before analyze')
      return
    case default
      if (feps_chol_status(self%handle) == cholmod_out_of_memory) then
        call fatal_error(error, err_memory, 'cholmod: the factor (' // str(real(self%factor_nnz, dp)) // &
                         ' nonzeros, about ' // gib_text(8 * self%factor_nnz) // ' GiB) does not fit in the ' // &
                         'memory this process may use (its address-space limit, ulimit -v, or the machine''s memory)')
        return
      end if
      call fatal_error(error, err_solver, 'cholmod: factorization failed (CHOLMOD status ' // &
                       str(int(feps_chol_status(self%handle))) // ')')
      return
    end select

    if (.not. (self%min_pivot_ratio > pivot_tolerance)) then
      equation = int(feps_chol_min_ratio_column(self%handle))
      call fatal_error(error, err_model, 'cholmod: stiffness matrix singular at equation ' // &
                       str(equation) // ': pivot / diagonal = ' // str(self%min_pivot_ratio) // &
                       ' <= ' // str(pivot_tolerance) // ' (unconstrained or mechanism)', equation)
      return
    end if
    self%factorized = .true.
    self%factorizations = self%factorizations + 1
    call plan_solves(self)
    self%solves_with_factor = 0
    self%copy_tried = .false.
    self%mixed_error = 0.0_dp
  end subroutine cholmod_factorize

  !> Plan feps's own solves with the new factor, when it is supernodal.
  subroutine plan_solves(self)
    type(cholmod_solver_t), intent(inout) :: self
    type(c_ptr) :: super, pi, px, rows, x, perm
    integer(c_int64_t) :: nsuper
    call self%plan%clear()
    if (feps_chol_supernodes(self%handle, nsuper, super, pi, px, rows, x, perm) /= 1) return
    call self%plan%setup(self%n, nsuper, super, pi, px, rows, x, perm)
  end subroutine plan_solves

  !> Mixed precision, at a factor's (mixed_after + 1)-th solve: make its single-precision copy
  !! and measure what it gives. A test solve of A x = A x_true for a known x_true (every
  !! equation excited, no two alike) gives the relative error of x; a single-precision solve
  !! is good to about kappa(A) 6e-8, so an ill-conditioned stiffness (a stiff interface on a
  !! soft continuum) can lose most digits, and above mixed_tolerance the factor is solved in
  !! double precision instead. The copy and the check cost about two solves, once per factor.
  !! A run continued from restart data makes the copy again at its first solve, with the same
  !! outcome (the same factor, the same test), and counts nothing twice (`counted` false).
  subroutine start_single_solves(self, counted, error)
    type(cholmod_solver_t), intent(inout) :: self
    logical, intent(in) :: counted
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: x_true(:), x(:)
    integer :: k
    self%copy_tried = .true.
    call self%plan%add_single_copy()
    if (.not. self%plan%single_precision()) return
    x_true = [(1.0_dp + 0.5_dp * sin(0.37_dp * k), k = 1, self%n)]
    allocate (x(self%n))
    if (feps_chol_multiply(self%handle, int(self%n, c_int64_t), x_true, x) /= chol_ok) then
      call fatal_error(error, err_internal, 'cholmod: the product of the test solve failed')
      return
    end if
    call self%plan%solve(x)
    self%mixed_error = maxval(abs(x - x_true)) / maxval(abs(x_true))
    if (self%mixed_error <= mixed_tolerance) then
      if (counted) self%lower_precision_factors = self%lower_precision_factors + 1
      if (counted) self%test_solve_error = max(self%test_solve_error, self%mixed_error)
    else
      if (counted) self%precision_fallbacks = self%precision_fallbacks + 1
      call self%plan%drop_single_copy()
    end if
  end subroutine start_single_solves

  !> Solve A x = b in place; size(b) = n * nrhs holds nrhs right-hand sides one after another.
  subroutine cholmod_solve(self, b, error)
    class(cholmod_solver_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    call check_solve(self, b, error)
    if (allocated(error)) return
    if (self%plan%ready()) then
      if (self%mixed .and. .not. self%exact_solves) then
        self%solves_with_factor = self%solves_with_factor + 1
        if (self%solves_with_factor > mixed_after .and. .not. self%copy_tried) &
          call start_single_solves(self, self%solves_with_factor == mixed_after + 1, error)
        if (allocated(error)) return
      end if
      call self%plan%solve(b, exact=self%exact_solves)
    else
      call solve_with_cholmod(self, b, error)
    end if
  end subroutine cholmod_solve

  !> CHOLMOD's solve (`cholmod_l_solve`) with the current factor, in place: what solve does
  !! without a supernodal factor, and the reference feps's own solves are checked against.
  subroutine cholmod_library_solve(self, b, error)
    class(cholmod_solver_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    call check_solve(self, b, error)
    if (allocated(error)) return
    call solve_with_cholmod(self, b, error)
  end subroutine cholmod_library_solve

  !> A solve needs a factor and whole right-hand sides.
  subroutine check_solve(self, b, error)
    class(cholmod_solver_t), intent(in) :: self
    real(dp), intent(in) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: nrhs
    if (.not. self%factorized) then
      call fatal_error(error, err_internal, 'cholmod: solve called without a valid factorization')
      return
    end if
    nrhs = size(b, kind=i8) / self%n
    if (nrhs < 1 .or. nrhs * self%n /= size(b, kind=i8)) then
      call fatal_error(error, err_internal, 'cholmod: right-hand side size is not a multiple of ' // &
                       str(self%n))
    end if
  end subroutine check_solve

  !> cholmod_l_solve through the shim, in place.
  subroutine solve_with_cholmod(self, b, error)
    class(cholmod_solver_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code
    code = feps_chol_solve(self%handle, int(self%n, c_int64_t), size(b, kind=i8) / self%n, b)
    if (code /= chol_ok) then
      call fatal_error(error, err_solver, 'cholmod: solve failed (CHOLMOD status ' // &
                       str(int(feps_chol_status(self%handle))) // ')')
    end if
  end subroutine solve_with_cholmod

  !> Threads of feps's own supernodal solves with the current factor; 0 when CHOLMOD solves.
  pure integer function cholmod_solve_threads(self)
    class(cholmod_solver_t), intent(in) :: self
    cholmod_solve_threads = 0
    if (self%plan%ready()) cholmod_solve_threads = self%plan%thread_count()
  end function cholmod_solve_threads

  pure function cholmod_name(self) result(name)
    class(cholmod_solver_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'cholmod'
    if (self%mixed) name = 'cholmod-mixed'
  end function cholmod_name

  !> +1 after a factorization: LL^T, and a pivot not above pivot_tolerance fails it, so the
  !! matrices it factorizes are positive definite; 0 without a factor.
  pure integer function cholmod_determinant_sign(self)
    class(cholmod_solver_t), intent(in) :: self
    cholmod_determinant_sign = merge(1, 0, self%factorized)
  end function cholmod_determinant_sign

  !> Vertices of the graph METIS ordered in the last analysis: the supervariables (groups of
  !! equations with identical pattern), or 0 if CHOLMOD's own ordering of the full graph was used.
  pure function cholmod_supervariables(self) result(count)
    class(cholmod_solver_t), intent(in) :: self
    integer(i8) :: count
    count = self%graph_vertices
  end function cholmod_supervariables

  !> Number of supervariables of the pattern of `a`: groups of equations whose rows and columns
  !! (diagonal included) have the same pattern, such as the free DOFs of one node.
  subroutine count_supervariables(a, count, error)
    type(csr_matrix_t), intent(in) :: a
    integer(i8), intent(out) :: count
    type(error_t), allocatable, intent(out) :: error
    count = 0
    call check_arrays(a, 'count_supervariables', error)
    if (allocated(error)) return
    count = feps_chol_count_supervariables(int(a%n, c_int64_t), a%row_ptr, a%col)
    if (count == -1) then
      call fatal_error(error, err_internal, 'cholmod: pattern is not a sorted lower triangle ' // &
                       'with the diagonal last in each row')
    else if (count < 0) then
      call fatal_error(error, err_solver, 'cholmod: out of memory while grouping equations')
    end if
  end subroutine count_supervariables

  !> The pattern arrays the C shim reads must exist and match the matrix's size.
  subroutine check_arrays(a, caller, error)
    type(csr_matrix_t), intent(in) :: a
    character(len=*), intent(in) :: caller
    type(error_t), allocatable, intent(out) :: error
    if (a%n <= 0 .or. .not. allocated(a%row_ptr) .or. .not. allocated(a%col)) then
      call fatal_error(error, err_internal, 'cholmod: ' // caller // ' called with an empty matrix')
    else if (size(a%row_ptr, kind=i8) /= a%n + 1_i8 .or. size(a%col, kind=i8) < a%nnz()) then
      call fatal_error(error, err_internal, 'cholmod: ' // caller // ': matrix arrays do not match its size')
    end if
  end subroutine check_arrays

  !> Release the CHOLMOD handle and everything it holds.
  subroutine cholmod_finalize(self)
    type(cholmod_solver_t), intent(inout) :: self
    if (c_associated(self%handle)) call feps_chol_free(self%handle)
    self%handle = c_null_ptr
    self%factorized = .false.
    call self%plan%clear()
  end subroutine cholmod_finalize

end module feps_cholmod_solver
