!> Full Newton-Raphson: the exact (consistent) tangent of every iterate, refactorized every
!! iteration and factorized as it is when non-symmetric (LU); a step must converge, as under
!! Newton-Raphson, whose decisions it extends. BFGS pairs built on an earlier factor would not
!! describe the new one, so ACCELERATION=bfgs does not apply.
module feps_method_full_newton_raphson
  use feps_model, only: controls_t
  use feps_method_newton_raphson, only: newton_raphson_t
  implicit none
  private

  type, public, extends(newton_raphson_t) :: full_newton_raphson_t
  contains
    procedure :: name
    procedure :: exact_tangent
    procedure :: takes_bfgs
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

end module feps_method_full_newton_raphson
