!> Full Newton-Raphson: the exact (consistent) tangent of every iterate, refactorized every
!! iteration and factorized as it is when non-symmetric (LU); a step must converge. BFGS pairs
!! built on an earlier factor would not describe the new one, so ACCELERATION=bfgs does not
!! apply.
module feps_method_full_newton_raphson
  use feps_kinds, only: dp
  use feps_model, only: controls_t
  use feps_solution_method, only: solution_method_t, factor_state_t
  implicit none
  private

  type, public, extends(solution_method_t) :: full_newton_raphson_t
  contains
    procedure :: name
    procedure :: exact_tangent
    procedure :: takes_bfgs
    procedure :: step_accepted
  end type full_newton_raphson_t

contains

  pure function name(self) result(method_name)
    class(full_newton_raphson_t), intent(in) :: self
    character(len=:), allocatable :: method_name
    method_name = 'full-newton-raphson'
  end function name

  pure logical function exact_tangent(self)
    class(full_newton_raphson_t), intent(in) :: self
    exact_tangent = .true.
  end function exact_tangent

  pure logical function takes_bfgs(self, c)
    class(full_newton_raphson_t), intent(in) :: self
    type(controls_t), intent(in) :: c
    takes_bfgs = .false.
  end function takes_bfgs

  !> A step must converge.
  pure logical function step_accepted(self, rel, rnorm, c)
    class(full_newton_raphson_t), intent(in) :: self
    real(dp), intent(in) :: rel, rnorm
    type(controls_t), intent(in) :: c
    step_accepted = rel < c%delta1 .or. rnorm < c%delta2
  end function step_accepted

end module feps_method_full_newton_raphson
