!> Euler (thesis 2.6.3): one iteration per step on a new tangent, and the unbalanced force of
!! the previous step dropped (eq. 2.6.4 not applied). Transitions (a gap opening, yield) are
!! left unbalanced by design: only an unbalanced force larger than the load itself is
!! divergence.
module feps_method_euler
  use feps_kinds, only: dp
  use feps_model, only: controls_t
  use feps_solution_method, only: solution_method_t, factor_state_t
  implicit none
  private

  type, public, extends(solution_method_t) :: euler_t
  contains
    procedure :: name
    procedure :: carries_residual
    procedure :: step_accepted
  end type euler_t

contains

  pure function name(self) result(method_name)
    class(euler_t), intent(in) :: self
    character(len=:), allocatable :: method_name
    method_name = 'euler'
  end function name

  pure logical function carries_residual(self)
    class(euler_t), intent(in) :: self
    carries_residual = .false.
  end function carries_residual

  pure logical function step_accepted(self, rel, rnorm, c)
    class(euler_t), intent(in) :: self
    real(dp), intent(in) :: rel, rnorm
    type(controls_t), intent(in) :: c
    step_accepted = rel < max(1.0_dp, c%divergence)
  end function step_accepted

end module feps_method_euler
