program tester
  use feps_testing, only: testsuite_t, new_testsuite, run_testsuites
  implicit none
  type(testsuite_t), allocatable :: suites(:)
  character(len=256) :: only
  integer :: nfail
  only = ''
  if (command_argument_count() > 0) call get_command_argument(1, only)
  suites = [testsuite_t ::]
  nfail = run_testsuites(suites, trim(only))
  if (nfail > 0) error stop 1
end program tester
