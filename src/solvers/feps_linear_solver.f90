!> The abstract linear solver: analyse a pattern once, factorize as often as the stiffness
!! changes, solve as often as needed. Implementations: skyline LDL^T and CHOLMOD.
module feps_linear_solver
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t
  use feps_sparse_matrix, only: csr_matrix_t
  implicit none
  private

  !> Smallest accepted pivot relative to the matrix diagonal entry of its equation; below it
  !! (or negative) the factorization fails, naming that equation in error%item.
  real(dp), parameter, public :: pivot_tolerance = 1.0e-11_dp

  type, abstract, public :: linear_solver_t
    integer(i8) :: factor_nnz = 0         !! nonzeros in the factor (L or the skyline profile)
    real(dp) :: flops = 0.0_dp            !! floating-point operations of the last factorization
    real(dp) :: min_pivot_ratio = 0.0_dp  !! min over equations of pivot / diagonal entry
    real(dp) :: max_pivot_ratio = 0.0_dp  !! max over equations of pivot / diagonal entry
    integer :: factorizations = 0         !! how many factorizations so far
    !> Solvers that may solve in lower precision (CHOLMOD's mixed precision) test each factor
    !! they would so solve: how many factors were solved in lower precision, the largest
    !! relative error of their test solves, and how many went back to double precision (their
    !! test solve too inaccurate)
    integer :: lower_precision_factors = 0
    real(dp) :: test_solve_error = 0.0_dp
    integer :: precision_fallbacks = 0
    !> Solves since the last factorization, counted by the solvers that change precision after
    !! a few (restart data keep it, so that a continued run changes at the same solve)
    integer :: solves_with_factor = 0
    !> Set while a caller needs solves to the factor's own precision (BFGS's secant updates,
    !! which assume their H0 is K^-1 exactly): lower-precision solvers then solve with the factor
    logical :: exact_solves = .false.
    real(dp), allocatable :: rank_memory_mb(:)       !! solvers over MPI: each rank's largest factorization memory
    real(dp), allocatable :: rank_factor_seconds(:)  !! and its time in the factorizations, summed
  contains
    procedure :: memory_need_bytes  !! memory the factorization needs, known after the analysis
    procedure(analyze_interface), deferred :: analyze
    procedure(factorize_interface), deferred :: factorize
    procedure(solve_interface), deferred :: solve
    procedure(name_interface), deferred :: name
    procedure :: zero_pivot_rule    !! what the solver takes for a zero pivot, for messages
    procedure :: determinant_sign   !! the sign of the last factorized matrix's determinant, where known
    procedure :: takes_distributed_matrix  !! whether each rank may give only its elements' share of the matrix
    procedure :: set_local_entries  !! which entries of the pattern this rank gives (before analyze)
  end type linear_solver_t

  abstract interface
    !> Ordering and symbolic analysis of the pattern of `a`.
    subroutine analyze_interface(self, a, error)
      import :: linear_solver_t, csr_matrix_t, error_t
      class(linear_solver_t), intent(inout) :: self
      type(csr_matrix_t), intent(in) :: a
      type(error_t), allocatable, intent(out) :: error
    end subroutine analyze_interface
    !> Numerical factorization; a pivot <= pivot_tolerance * a(i,i) fails with error%item = i.
    subroutine factorize_interface(self, a, error)
      import :: linear_solver_t, csr_matrix_t, error_t
      class(linear_solver_t), intent(inout) :: self
      type(csr_matrix_t), intent(in) :: a
      type(error_t), allocatable, intent(out) :: error
    end subroutine factorize_interface
    !> Solve A x = b in place (b becomes x), with one or several right-hand sides.
    subroutine solve_interface(self, b, error)
      import :: linear_solver_t, dp, error_t
      class(linear_solver_t), intent(inout) :: self
      real(dp), intent(inout) :: b(:)
      type(error_t), allocatable, intent(out) :: error
    end subroutine solve_interface
    !> The solver's name as the summary and the results report it: 'cholmod' or 'skyline'.
    pure function name_interface(self) result(name)
      import :: linear_solver_t
      class(linear_solver_t), intent(in) :: self
      character(len=:), allocatable :: name
    end function name_interface
  end interface

contains

  !> The memory the factorization needs (a lower bound, 8 bytes a factor entry), known after the
  !! analysis; solvers that keep the factor elsewhere (out of core) or know better override it.
  pure function memory_need_bytes(self) result(bytes)
    class(linear_solver_t), intent(in) :: self
    integer(i8) :: bytes
    bytes = 8_i8 * self%factor_nnz
  end function memory_need_bytes

  !> The rule by which a pivot counts as zero (a singular stiffness), as messages say it:
  !! pivot_tolerance of the equation's own diagonal, as CHOLMOD, UMFPACK and skyline apply it.
  pure function zero_pivot_rule(self) result(text)
    class(linear_solver_t), intent(in) :: self
    character(len=:), allocatable :: text
    text = 'pivot below 1e-11 of its diagonal'
  end function zero_pivot_rule

  !> The sign of the determinant of the matrix last factorized: +1, -1, or 0 where the solver
  !! does not know it (the default). CHOLMOD's LL^T factorizes positive definite matrices only
  !! (+1); skyline counts its negative LDL^T pivots; UMFPACK asks its LU; MUMPS its determinant.
  pure integer function determinant_sign(self)
    class(linear_solver_t), intent(in) :: self
    determinant_sign = 0
  end function determinant_sign

  !> Whether the solver takes the matrix as the sum of every MPI rank's share, each rank giving
  !! the entries of its own elements (MUMPS on more than one rank): then the analysis
  !! partitions the elements over the ranks. The default: one whole matrix, on this process.
  logical function takes_distributed_matrix(self)
    class(linear_solver_t), intent(in) :: self
    takes_distributed_matrix = .false.
  end function takes_distributed_matrix

  !> Which entries of the next pattern to analyse this rank gives (`local`, one per entry of the
  !! matrix's values); the solvers that take one whole matrix ignore it.
  subroutine set_local_entries(self, local)
    class(linear_solver_t), intent(inout) :: self
    logical, intent(in) :: local(:)
  end subroutine set_local_entries

end module feps_linear_solver
