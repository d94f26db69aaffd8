!> Direct solver for non-symmetric sparse matrices (UMFPACK, unsymmetric multifrontal LU),
!! for the full-Newton tangent where a material's tangent is non-symmetric (psi /= phi), behind
!! the same `linear_solver_t` contract as the symmetric solvers. It takes the full matrix, both
!! triangles, in compressed rows (`full_pattern` of feps_sparse_matrix), not the lower triangle
!! the symmetric solvers take, so it is not one of `--solver`'s choices.
!!
!! The UMFPACK state lives behind a C handle that the finalizer frees; do not copy a
!! umfpack_solver_t after a factorization (the copy would share, and later free, the handle).
module feps_umfpack_solver
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_int64_t
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_solver, err_model, str
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_linear_solver, only: linear_solver_t
  use feps_umfpack_bindings, only: feps_umf_create, feps_umf_free, feps_umf_factorize, feps_umf_solve, &
                                   feps_umf_status, feps_umf_flops, feps_umf_rcond, feps_umf_determinant_sign, &
                                   umf_ok, umf_singular
  implicit none
  private

  !> Below this reciprocal condition estimate the matrix is singular but for rounding: a body
  !! held only by faces sliding without dilation leaves about 1e-14 (test_analysis_state),
  !! where the model B, chapter 3 and test tangents give 3e-4 to 2e-2. UMFPACK itself flags only
  !! an exactly zero pivot, and the solve of such a factor is rounding noise amplified 1e14 times.
  real(dp), parameter, public :: lu_singular_rcond = 1.0e-12_dp

  !> UMFPACK's LU; `factorizations` counts the successful ones and `flops` is the last one's.
  type, extends(linear_solver_t), public :: umfpack_solver_t
    type(c_ptr) :: handle = c_null_ptr
    logical :: factorized = .false.    !! a valid factorization is held
    real(dp) :: rcond = 0.0_dp         !! UMFPACK's reciprocal condition estimate of the last factorization
    real(dp) :: min_rcond = huge(1.0_dp)   !! the smallest rcond of the factorizations kept
    integer :: det_sign = 0            !! the sign of the last factorization's determinant (0: not known)
  contains
    procedure :: analyze => umfpack_analyze
    procedure :: factorize => umfpack_factorize
    procedure :: solve => umfpack_solve
    procedure :: name => umfpack_name
    procedure :: determinant_sign => umfpack_determinant_sign
    final :: umfpack_finalize
  end type umfpack_solver_t

contains

  !> Nothing to do ahead: UMFPACK orders and analyses the pattern in each factorization (the
  !! non-symmetric tangents are rare and their pattern is the full one of the stiffness).
  subroutine umfpack_analyze(self, a, error)
    class(umfpack_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
  end subroutine umfpack_analyze

  !> 'umfpack'.
  pure function umfpack_name(self) result(name)
    class(umfpack_solver_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'umfpack'
  end function umfpack_name

  !> The sign of the determinant of the last factorization (UMFPACK's, from the LU factors and
  !! the row scaling): +1 or -1; 0 without a factor.
  pure integer function umfpack_determinant_sign(self)
    class(umfpack_solver_t), intent(in) :: self
    umfpack_determinant_sign = 0
    if (self%factorized) umfpack_determinant_sign = self%det_sign
  end function umfpack_determinant_sign

  !> LU factorization of the full matrix `a`; a singular matrix (a zero pivot, or a reciprocal
  !! condition estimate below lu_singular_rcond) fails with err_model.
  subroutine umfpack_factorize(self, a, error)
    !! `a` holds both triangles in compressed rows, 1-based.
    class(umfpack_solver_t), intent(inout) :: self
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code
    self%factorized = .false.
    if (.not. c_associated(self%handle)) self%handle = feps_umf_create()
    if (.not. c_associated(self%handle)) then
      call fatal_error(error, err_solver, 'UMFPACK: out of memory creating the solver')
      return
    end if
    code = feps_umf_factorize(self%handle, int(a%n, c_int64_t), a%row_ptr, a%col, a%val)
    self%flops = feps_umf_flops(self%handle)
    self%rcond = feps_umf_rcond(self%handle)
    if (code == umf_singular) then
      call fatal_error(error, err_model, 'UMFPACK: the non-symmetric tangent is singular')
      return
    else if (code == umf_ok .and. .not. self%rcond >= lu_singular_rcond) then
      call fatal_error(error, err_model, 'UMFPACK: the non-symmetric tangent is singular but for rounding ' // &
                       '(reciprocal condition estimate ' // str(self%rcond) // ')')
      return
    else if (code /= umf_ok) then
      call fatal_error(error, err_solver, 'UMFPACK failed to factorize (code ' // str(int(code)) // &
                       ', status ' // str(int(feps_umf_status(self%handle))) // ')')
      return
    end if
    self%factorized = .true.
    self%factorizations = self%factorizations + 1
    self%min_rcond = min(self%min_rcond, self%rcond)
    self%det_sign = int(feps_umf_determinant_sign(self%handle))
  end subroutine umfpack_factorize

  !> Solve A x = b in place with the last factorization.
  subroutine umfpack_solve(self, b, error)
    class(umfpack_solver_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: code
    if (.not. self%factorized) then
      call fatal_error(error, err_solver, 'UMFPACK: solve without a factorization')
      return
    end if
    code = feps_umf_solve(self%handle, b)
    if (code /= umf_ok) call fatal_error(error, err_solver, 'UMFPACK failed to solve (status ' // &
                                         str(int(feps_umf_status(self%handle))) // ')')
  end subroutine umfpack_solve

  subroutine umfpack_finalize(self)
    type(umfpack_solver_t), intent(inout) :: self
    if (c_associated(self%handle)) call feps_umf_free(self%handle)
    self%handle = c_null_ptr
  end subroutine umfpack_finalize

end module feps_umfpack_solver
