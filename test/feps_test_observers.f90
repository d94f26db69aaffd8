!> Observers the test suites share: they keep what an analysis hands over, for the checks.
module feps_test_observers
  use feps_error, only: error_t
  use feps_observer, only: observer_t, step_result_t
  implicit none
  private

  !> Keeps every step written (the last step of each stage by default) and ignores progress.
  type, extends(observer_t), public :: all_steps_t
    type(step_result_t), allocatable :: steps(:)
  contains
    procedure :: progress => ignore_progress
    procedure :: write_step => keep_step
  end type all_steps_t

contains

  subroutine ignore_progress(self, line)
    class(all_steps_t), intent(inout) :: self
    character(len=*), intent(in) :: line
  end subroutine ignore_progress

  subroutine keep_step(self, res, error)
    class(all_steps_t), intent(inout) :: self
    type(step_result_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    if (.not. allocated(self%steps)) allocate (self%steps(0))
    self%steps = [self%steps, res]
  end subroutine keep_step

end module feps_test_observers
