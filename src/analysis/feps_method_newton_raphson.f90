!> Newton-Raphson (thesis 2.6.3): the tangent of the committed state factorized every step,
!! iterated until the step converges (to DELTA1 or DELTA2); a step that does not is cut back.
module feps_method_newton_raphson
  use feps_kinds, only: dp
  use feps_model, only: controls_t
  use feps_solution_method, only: solution_method_t
  implicit none
  private

  type, public, extends(solution_method_t) :: newton_raphson_t
  contains
    procedure :: name
    procedure :: step_accepted
  end type newton_raphson_t

contains

  pure function name(self) result(method_name)
    class(newton_raphson_t), intent(in) :: self
    character(len=:), allocatable :: method_name
    method_name = 'newton-raphson'
  end function name

  !> A step must converge.
  pure logical function step_accepted(self, rel, rnorm, c)
    class(newton_raphson_t), intent(in) :: self
    real(dp), intent(in) :: rel, rnorm
    type(controls_t), intent(in) :: c
    step_accepted = rel < c%delta1 .or. rnorm < c%delta2
  end function step_accepted

end module feps_method_newton_raphson
