!> MUMPS over MPI (issue 29): the linear solver of `--solver mumps` in the MPI build. Every rank
!! makes each call together (feps_mumps_shim.c). On more than one rank each rank gives the
!! entries of its own elements (`set_local_entries`, MUMPS's distributed input, which it sums),
!! on one rank the whole matrix; the right-hand sides are rank 0's and every rank gets the
!! solution. LDL' of the symmetric
!! stiffness (MUMPS SYM = 2: its null-pivot detection names the equation of a singular stiffness,
!! which SYM = 1, the positive definite mode, did not do), or LU of the exact non-symmetric
!! tangent (SYM = 0, `unsymmetric`); the factors in memory or on disk (`out_of_core`, MUMPS's
!! ICNTL(22), `--out-of-core`). Each factorization records every rank's memory and time.
module feps_mumps_solver
  use, intrinsic :: iso_c_binding, only: c_int, c_int32_t, c_int64_t, c_double
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_input, err_model, err_solver, err_memory, err_internal, str
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_linear_solver, only: linear_solver_t
  implicit none
  private

  public :: mumps_solver_t, mpi_built, mpi_start, mpi_stop

  !> Codes of feps_mumps_shim.c.
  integer(c_int), parameter :: mumps_ok = 0, mumps_no_mpi = 1, mumps_no_memory = 4, mumps_singular = 5

  type, extends(linear_solver_t) :: mumps_solver_t
    logical :: out_of_core = .false.    !! the factors on disk (MUMPS_OOC_TMPDIR, else TMPDIR, else /tmp)
    logical :: unsymmetric = .false.    !! LU of the full matrix (both triangles) instead of LDL' of the lower
    integer(c_int), private :: instance = -1     !! the shim's MUMPS instance, -1 before analyze
    integer, private :: n = 0
    logical, private :: factorized = .false.
    integer, private :: det_sign = 0             !! the sign of the factor's determinant (ICNTL(33))
    real(dp), private :: memory_estimate_mb = 0.0_dp   !! MUMPS's, after the analysis (all ranks)
    integer(c_int32_t), allocatable, private :: local(:)  !! 1 where this rank gives the entry (distributed)
  contains
    procedure :: takes_distributed_matrix => mumps_takes_distributed_matrix
    procedure :: set_local_entries => mumps_set_local_entries
    procedure :: memory_need_bytes => mumps_memory_need_bytes
    procedure :: analyze => mumps_analyze
    procedure :: factorize => mumps_factorize
    procedure :: solve => mumps_solve
    procedure :: name => mumps_name
    procedure :: zero_pivot_rule => mumps_zero_pivot_rule
    procedure :: determinant_sign => mumps_determinant_sign
    final :: mumps_finalize
  end type mumps_solver_t

  interface
    integer(c_int) function feps_mpi_built() bind(C, name='feps_mpi_built')
      import :: c_int
    end function feps_mpi_built
    integer(c_int) function feps_mpi_start(rank, ranks) bind(C, name='feps_mpi_start')
      import :: c_int
      integer(c_int), intent(out) :: rank, ranks
    end function feps_mpi_start
    subroutine feps_mpi_stop(status) bind(C, name='feps_mpi_stop')
      import :: c_int
      integer(c_int), value :: status
    end subroutine feps_mpi_stop
    integer(c_int) function feps_mumps_create(sym, out_of_core) bind(C, name='feps_mumps_create')
      import :: c_int
      integer(c_int), value :: sym, out_of_core
    end function feps_mumps_create
    integer(c_int) function feps_mumps_ranks() bind(C, name='feps_mumps_ranks')
      import :: c_int
    end function feps_mumps_ranks
    real(c_double) function feps_mumps_rank_stat(instance, rank, k) bind(C, name='feps_mumps_rank_stat')
      import :: c_int, c_double
      integer(c_int), value :: instance, rank, k
    end function feps_mumps_rank_stat
    real(c_double) function feps_mumps_memory_estimate(instance) bind(C, name='feps_mumps_memory_estimate')
      import :: c_int, c_double
      integer(c_int), value :: instance
    end function feps_mumps_memory_estimate
    subroutine feps_mumps_free(instance) bind(C, name='feps_mumps_free')
      import :: c_int
      integer(c_int), value :: instance
    end subroutine feps_mumps_free
    integer(c_int) function feps_mumps_analyze(instance, n, row_ptr, col, distributed, local) &
        bind(C, name='feps_mumps_analyze')
      import :: c_int, c_int32_t, c_int64_t
      integer(c_int), value :: instance
      integer(c_int64_t), value :: n
      integer(c_int64_t), intent(in) :: row_ptr(*)
      integer(c_int32_t), intent(in) :: col(*)
      integer(c_int), value :: distributed
      integer(c_int32_t), intent(in) :: local(*)
    end function feps_mumps_analyze
    integer(c_int) function feps_mumps_factorize(instance, val) bind(C, name='feps_mumps_factorize')
      import :: c_int, c_double
      integer(c_int), value :: instance
      real(c_double), intent(in) :: val(*)
    end function feps_mumps_factorize
    integer(c_int64_t) function feps_mumps_null_pivot(instance) bind(C, name='feps_mumps_null_pivot')
      import :: c_int, c_int64_t
      integer(c_int), value :: instance
    end function feps_mumps_null_pivot
    integer(c_int64_t) function feps_mumps_factor_entries(instance) bind(C, name='feps_mumps_factor_entries')
      import :: c_int, c_int64_t
      integer(c_int), value :: instance
    end function feps_mumps_factor_entries
    real(c_double) function feps_mumps_flops(instance) bind(C, name='feps_mumps_flops')
      import :: c_int, c_double
      integer(c_int), value :: instance
    end function feps_mumps_flops
    integer(c_int) function feps_mumps_solve(instance, n, nrhs, b) bind(C, name='feps_mumps_solve')
      import :: c_int, c_int64_t, c_double
      integer(c_int), value :: instance
      integer(c_int64_t), value :: n, nrhs
      real(c_double), intent(inout) :: b(*)
    end function feps_mumps_solve
    integer(c_int) function feps_mumps_determinant_sign(instance) bind(C, name='feps_mumps_determinant_sign')
      import :: c_int
      integer(c_int), value :: instance
    end function feps_mumps_determinant_sign
    integer(c_int) function feps_mumps_infog(instance, k) bind(C, name='feps_mumps_infog')
      import :: c_int
      integer(c_int), value :: instance, k
    end function feps_mumps_infog
  end interface

contains

  !> Whether this build has MPI and MUMPS (the MPI build, README).
  logical function mpi_built()
    mpi_built = feps_mpi_built() /= 0
  end function mpi_built

  !> Start MPI (in the MPI build): this process's rank and the number of ranks; rank 0 and one
  !! rank without MPI.
  subroutine mpi_start(rank, ranks)
    integer, intent(out) :: rank, ranks
    integer(c_int) :: r, s, code
    code = feps_mpi_start(r, s)
    rank = int(r)
    ranks = int(s)
    if (code /= mumps_ok) then
      rank = 0
      ranks = 1
    end if
  end subroutine mpi_start

  !> End MPI: rank 0 tells the other ranks to end with `status`. Nothing without MPI.
  subroutine mpi_stop(status)
    integer, intent(in) :: status
    call feps_mpi_stop(int(status, c_int))
  end subroutine mpi_stop

  !> On more than one rank, each rank gives MUMPS its own elements' entries (MUMPS sums them).
  logical function mumps_takes_distributed_matrix(self)
    class(mumps_solver_t), intent(in) :: self
    mumps_takes_distributed_matrix = mpi_built() .and. feps_mumps_ranks() > 1
  end function mumps_takes_distributed_matrix

  !> The entries this rank gives of the next pattern analysed (its elements').
  subroutine mumps_set_local_entries(self, local)
    class(mumps_solver_t), intent(inout) :: self
    logical, intent(in) :: local(:)
    self%local = merge(1_c_int32_t, 0_c_int32_t, local)
  end subroutine mumps_set_local_entries

  !> Ordering and symbolic analysis of the pattern of `a` (on every rank).
  subroutine mumps_analyze(self, a, error)
    class(mumps_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code
    self%factorized = .false.
    if (.not. mpi_built()) then
      call fatal_error(error, err_input, '--solver mumps needs the MPI build of feps (README, "MUMPS over MPI")')
      return
    end if
    if (.not. allocated(a%row_ptr) .or. .not. allocated(a%col)) then
      call fatal_error(error, err_internal, 'mumps: analyze called without a pattern')
      return
    end if
    ! a new pattern (supports that change) gets a new instance: MUMPS 5.5 analysing a second
    ! centralised pattern on the same instance found it structurally singular
    if (self%instance >= 0) call feps_mumps_free(self%instance)
    self%instance = -1
    if (self%instance < 0) self%instance = feps_mumps_create(merge(0_c_int, 2_c_int, self%unsymmetric), &
                                                            merge(1_c_int, 0_c_int, self%out_of_core))
    if (self%instance < 0) then
      call fatal_error(error, err_solver, 'mumps: cannot start MUMPS (MPI not started, or out of memory)')
      return
    end if
    if (.not. allocated(self%local)) allocate (self%local(0))
    if (size(self%local) /= 0 .and. size(self%local) /= size(a%col)) then
      call fatal_error(error, err_internal, 'mumps: the local entries do not fit the pattern')
      return
    end if
    code = feps_mumps_analyze(self%instance, int(a%n, c_int64_t), a%row_ptr, a%col, &
                              merge(1_c_int, 0_c_int, size(self%local) > 0), self%local)
    deallocate (self%local)   ! each pattern is given its own
    if (code /= mumps_ok) then
      call failed(self, code, 'the ordering and analysis of ' // str(a%n) // ' equations', error)
      return
    end if
    self%n = a%n
    self%factor_nnz = feps_mumps_factor_entries(self%instance)
    self%flops = feps_mumps_flops(self%instance)
    self%memory_estimate_mb = real(feps_mumps_memory_estimate(self%instance), dp)
  end subroutine mumps_analyze

  !> Numerical LDL' factorization (on every rank). A null pivot fails with err_model naming the
  !! equation in error%item when MUMPS names it.
  subroutine mumps_factorize(self, a, error)
    class(mumps_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code
    integer :: equation
    self%factorized = .false.
    if (self%instance < 0 .or. self%n == 0 .or. a%n /= self%n .or. .not. allocated(a%val)) then
      call fatal_error(error, err_internal, 'mumps: factorize called before analyze')
      return
    end if
    code = feps_mumps_factorize(self%instance, a%val)
    if (code == mumps_singular) then
      equation = int(feps_mumps_null_pivot(self%instance))
      call fatal_error(error, err_model, 'mumps: stiffness matrix singular or not positive definite at equation ' // &
                       str(equation) // ' (unconstrained, mechanism or negative stiffness)', equation)
      return
    end if
    if (code /= mumps_ok) then
      call failed(self, code, 'the factor', error)
      return
    end if
    self%flops = feps_mumps_flops(self%instance)
    self%factor_nnz = feps_mumps_factor_entries(self%instance)
    self%det_sign = int(feps_mumps_determinant_sign(self%instance))
    self%factorized = .true.
    self%factorizations = self%factorizations + 1
    call record_ranks(self)
  end subroutine mumps_factorize

  !> Every rank's memory in this factorization (the largest of the run kept) and its time (summed
  !! over the run's factorizations), from feps_mumps_shim.c.
  subroutine record_ranks(self)
    class(mumps_solver_t), intent(inout) :: self
    integer :: ranks, r
    ranks = int(feps_mumps_ranks())
    if (ranks < 1) return
    if (.not. allocated(self%rank_memory_mb)) then
      allocate (self%rank_memory_mb(ranks), self%rank_factor_seconds(ranks))
      self%rank_memory_mb = 0.0_dp
      self%rank_factor_seconds = 0.0_dp
    end if
    do r = 1, ranks
      self%rank_memory_mb(r) = max(self%rank_memory_mb(r), &
                                   real(feps_mumps_rank_stat(self%instance, int(r - 1, c_int), 0_c_int), dp))
      self%rank_factor_seconds(r) = self%rank_factor_seconds(r) + &
                                    real(feps_mumps_rank_stat(self%instance, int(r - 1, c_int), 1_c_int), dp)
    end do
  end subroutine record_ranks

  !> MUMPS's own estimate, after the analysis, of the memory its factorization needs on all
  !! ranks together: in core, or with the factors on disk (then far less than the factor).
  pure function mumps_memory_need_bytes(self) result(bytes)
    class(mumps_solver_t), intent(in) :: self
    integer(i8) :: bytes
    bytes = int(self%memory_estimate_mb, i8) * 1000000_i8
  end function mumps_memory_need_bytes

  !> Solve A x = b in place; size(b) = n * nrhs.
  subroutine mumps_solve(self, b, error)
    class(mumps_solver_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code
    integer(i8) :: nrhs
    if (.not. self%factorized) then
      call fatal_error(error, err_internal, 'mumps: solve called without a valid factorization')
      return
    end if
    nrhs = size(b, kind=i8) / self%n
    if (nrhs < 1 .or. nrhs * self%n /= size(b, kind=i8)) then
      call fatal_error(error, err_internal, 'mumps: right-hand side size is not a multiple of ' // str(self%n))
      return
    end if
    code = feps_mumps_solve(self%instance, int(self%n, c_int64_t), int(nrhs, c_int64_t), b)
    if (code /= mumps_ok) call failed(self, code, 'the solve', error)
  end subroutine mumps_solve

  !> The error of a MUMPS call that failed: out of memory, or MUMPS's own code.
  subroutine failed(self, code, what, error)
    type(mumps_solver_t), intent(in) :: self
    integer(c_int), intent(in) :: code
    character(len=*), intent(in) :: what
    type(error_t), allocatable, intent(out) :: error
    if (code == mumps_no_memory) then
      call fatal_error(error, err_memory, 'mumps: ' // what // ' does not fit in the memory the ranks may use ' // &
                       '(MUMPS INFOG(1) = ' // str(int(feps_mumps_infog(self%instance, 1_c_int))) // ')')
    else if (code == mumps_no_mpi) then
      call fatal_error(error, err_input, '--solver mumps needs the MPI build of feps (README, "MUMPS over MPI")')
    else
      call fatal_error(error, err_solver, 'mumps: ' // what // ' failed (MUMPS INFOG(1) = ' // &
                       str(int(feps_mumps_infog(self%instance, 1_c_int))) // ', INFOG(2) = ' // &
                       str(int(feps_mumps_infog(self%instance, 2_c_int))) // ')')
    end if
  end subroutine failed

  pure function mumps_name(self) result(name)
    class(mumps_solver_t), intent(in) :: self
    character(len=:), allocatable :: name
    if (self%unsymmetric) then
      name = 'mumps-lu'
    else if (self%out_of_core) then
      name = 'mumps-ooc'
    else
      name = 'mumps'
    end if
  end function mumps_name

  !> MUMPS's null pivots (ICNTL(24), CNTL(3) = 1e-11, feps_mumps_shim.c).
  pure function mumps_zero_pivot_rule(self) result(text)
    class(mumps_solver_t), intent(in) :: self
    character(len=:), allocatable :: text
    text = 'MUMPS''s null pivot: its row below 1e-11 of the matrix''s norm'
  end function mumps_zero_pivot_rule

  !> The sign of the last factorized matrix's determinant (MUMPS's RINFOG(12), ICNTL(33)): -1 past
  !! a limit point or bifurcation of an exact tangent; 0 before a factorization.
  pure integer function mumps_determinant_sign(self)
    class(mumps_solver_t), intent(in) :: self
    mumps_determinant_sign = 0
    if (self%factorized) mumps_determinant_sign = self%det_sign
  end function mumps_determinant_sign

  !> Release the MUMPS instance on every rank.
  subroutine mumps_finalize(self)
    type(mumps_solver_t), intent(inout) :: self
    if (self%instance >= 0) call feps_mumps_free(self%instance)
    self%instance = -1
    self%factorized = .false.
  end subroutine mumps_finalize

end module feps_mumps_solver
