!> Modified Newton-Raphson (thesis 2.6.3): the factor is kept from step to step and renewed
!! (the tangent of the committed state) when the residual at the end of the last step exceeds
!! DELTA3 (relative) or DELTA4 (N). After a cut-back it retries with the elastic stiffness:
!! the committed tangent may be what failed (points at the yield surface or in the tension
!! zone that unload have their elastic stiffness, far stiffer than their tangent, and a fixed
!! tangent softer than the response overshoots by the same ratio at every iteration whatever
!! the step size: chapter 9's PR with a 6 MPa band); the elastic stiffness, the thesis's
!! initial one, is never softer.
module feps_method_modified_newton_raphson
  use feps_kinds, only: dp
  use feps_model, only: controls_t
  use feps_solution_method, only: solution_method_t, factor_state_t
  implicit none
  private

  type, public, extends(solution_method_t) :: modified_newton_raphson_t
  contains
    procedure :: name
    procedure :: needs_factor
    procedure :: after_cutback
  end type modified_newton_raphson_t

contains

  pure function name(self) result(method_name)
    class(modified_newton_raphson_t), intent(in) :: self
    character(len=:), allocatable :: method_name
    method_name = 'modified-newton-raphson'
  end function name

  pure logical function needs_factor(self, f, c)
    class(modified_newton_raphson_t), intent(in) :: self
    type(factor_state_t), intent(in) :: f
    type(controls_t), intent(in) :: c
    needs_factor = .not. f%have_factor .or. f%rel_prev > c%delta3 .or. f%abs_prev > c%delta4
  end function needs_factor

  pure subroutine after_cutback(self, f)
    class(modified_newton_raphson_t), intent(in) :: self
    type(factor_state_t), intent(inout) :: f
    f%rel_prev = huge(1.0_dp)
    f%elastic_retry = .true.
  end subroutine after_cutback

end module feps_method_modified_newton_raphson
