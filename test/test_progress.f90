!> The progress lines of a long run carry the time taken and an estimate of the time left
!! (issue 25): at the mean rate of the steps so far.
module test_progress
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_step_report, only: time_text
  implicit none
  private

  public :: collect_progress

contains

  subroutine collect_progress(testsuite)
    type(unittest_t), allocatable, intent(out) :: testsuite(:)
    testsuite = [ &
      new_unittest('elapsed time and the time left at the mean rate so far', test_time_left), &
      new_unittest('the last step says only the elapsed time', test_last_step) &
      ]
  end subroutine collect_progress

  subroutine test_time_left(error)
    type(error_t), allocatable, intent(out) :: error
    ! 10 of 40 steps in 12.34 s: 30 more at 1.234 s each, 37.02 s
    call check(error, time_text(12.34_dp, 10, 40) == '  elapsed 12.3 s, about 37 s left', &
               '"' // time_text(12.34_dp, 10, 40) // '"')
    if (allocated(error)) return
    call check(error, time_text(0.34_dp, 1, 400) == '  elapsed 0.3 s, about 136 s left', &
               '"' // time_text(0.34_dp, 1, 400) // '"')
  end subroutine test_time_left

  subroutine test_last_step(error)
    type(error_t), allocatable, intent(out) :: error
    call check(error, time_text(122.24_dp, 400, 400) == '  elapsed 122.2 s', '"' // time_text(122.24_dp, 400, 400) // '"')
  end subroutine test_last_step

end module test_progress
