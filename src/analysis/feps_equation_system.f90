!> The equation system of an analysis: the numbering of the free equations, the matrix (its
!! lower triangle for the symmetric solvers, both triangles for the exact non-symmetric
!! tangent), and the factors, all behind linear_solver_t: the symmetric solver the run chose
!! (CHOLMOD, skyline or MUMPS) and an LU for the exact non-symmetric tangents of full Newton
!! (UMFPACK; MUMPS's LU when the run's solver is MUMPS).
!! `solve` uses the factor the last factorization made.
module feps_equation_system
  use feps_kinds, only: dp
  use feps_error, only: error_t
  use feps_dof_map, only: dof_map_t
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_linear_solver, only: linear_solver_t
  use feps_umfpack_solver, only: umfpack_solver_t
  implicit none
  private

  type, public :: equation_system_t
    type(dof_map_t) :: map
    type(csr_matrix_t) :: a                            !! lower triangle: the symmetric (stand-in) tangent
    class(linear_solver_t), allocatable :: solver      !! its factor (CHOLMOD or skyline)
    type(csr_matrix_t) :: a_full                       !! both triangles: the exact non-symmetric tangent
    class(linear_solver_t), allocatable :: lu          !! its LU factors (full Newton, psi /= phi)
    logical :: use_lu = .false.                        !! the last factorization was lu's (set by factorize_tangent)
    logical :: symmetrized = .false.                   !! some tangent was replaced by its symmetric stand-in
    logical :: warned_condition = .false.
    integer :: lu_singular = 0                         !! exact tangents found singular (the stand-in was used)
    !> The sign of the determinant of the last matrix factorized when that was a state's exact
    !! tangent (full Newton-Raphson's; set by factorize_tangent): +1, -1, or 0 when it was the
    !! elastic stiffness, a symmetric stand-in, or its solver does not know the sign.
    integer :: tangent_sign = 0
  contains
    procedure :: solve
    procedure :: lu_min_rcond
    procedure :: set_lu_min_rcond
  end type equation_system_t

contains

  !> x = A^-1 b in place, by the factor the last factorization made (LU or the symmetric one).
  subroutine solve(self, b, error)
    class(equation_system_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    type(error_t), allocatable, intent(out) :: error
    if (self%use_lu) then
      call self%lu%solve(b, error)
    else
      call self%solver%solve(b, error)
    end if
  end subroutine solve


  !> The smallest reciprocal condition estimate of the LU factors kept (UMFPACK's; 0 where the
  !! LU solver gives none: MUMPS flags a singular tangent by its null pivots instead).
  pure real(dp) function lu_min_rcond(self)
    class(equation_system_t), intent(in) :: self
    lu_min_rcond = 0.0_dp
    if (.not. allocated(self%lu)) return
    select type (lu => self%lu)
    type is (umfpack_solver_t)
      lu_min_rcond = lu%min_rcond
    end select
  end function lu_min_rcond

  !> Restore the smallest reciprocal condition estimate (a restart), where the LU solver keeps one.
  subroutine set_lu_min_rcond(self, rcond)
    class(equation_system_t), intent(inout) :: self
    real(dp), intent(in) :: rcond
    if (.not. allocated(self%lu)) return
    select type (lu => self%lu)
    type is (umfpack_solver_t)
      lu%min_rcond = rcond
    end select
  end subroutine set_lu_min_rcond

end module feps_equation_system
