!> Modified Euler (thesis 2.6.3): Euler's one iteration per step on a new tangent, with the
!! unbalanced force carried into the next step (eq. 2.6.4). Only an unbalanced force larger
!! than the load itself is divergence.
module feps_method_modified_euler
  use feps_kinds, only: dp
  use feps_model, only: controls_t
  use feps_solution_method, only: solution_method_t
  implicit none
  private

  type, public, extends(solution_method_t) :: modified_euler_t
  contains
    procedure :: name
    procedure :: step_accepted
  end type modified_euler_t

contains

  pure function name(self) result(method_name)
    class(modified_euler_t), intent(in) :: self
    character(len=:), allocatable :: method_name
    method_name = 'modified-euler'
  end function name

  pure logical function step_accepted(self, rel, rnorm, c)
    class(modified_euler_t), intent(in) :: self
    real(dp), intent(in) :: rel, rnorm
    type(controls_t), intent(in) :: c
    step_accepted = rel < max(1.0_dp, c%divergence)
  end function step_accepted

end module feps_method_modified_euler
