!> Euler (thesis 2.6.3): modified Euler's one iteration per step on a new tangent, with the
!! unbalanced force of the previous step dropped (eq. 2.6.4 not applied). Transitions (a gap
!! opening, yield) are left unbalanced by design: only an unbalanced force larger than the
!! load itself is divergence.
module feps_method_euler
  use feps_method_modified_euler, only: modified_euler_t
  implicit none
  private

  type, public, extends(modified_euler_t) :: euler_t
  contains
    procedure :: name
    procedure :: carries_residual
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

end module feps_method_euler
