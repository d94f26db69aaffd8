!> Runs every test suite (or those named as arguments: `fpm test -- SUITE [SUITE ...]`) and ends
!! with 'N passed, N failed'; exit status 1 if a test failed, 2 (and one line listing the suites)
!! for a name that is no suite's.
program tester
  use, intrinsic :: iso_c_binding, only: c_int
  use feps_testing, only: testsuite_t, new_testsuite, run_testsuites
  use test_datain, only: collect_datain
  use test_elements, only: collect_elements
  use test_cholmod, only: collect_cholmod
  use test_skyline, only: collect_skyline
  use test_results_file, only: collect_results_file
  use test_analysis, only: collect_analysis
  use test_bad_input, only: collect_bad_input
  use test_interface_element, only: collect_interface_element
  use test_interface_mc, only: collect_interface_mc
  use test_nonlinear, only: collect_nonlinear
  use test_tri6, only: collect_tri6
  use test_bars, only: collect_bars
  use test_matsuoka, only: collect_matsuoka
  use test_concrete, only: collect_concrete
  use test_joint_models, only: collect_joint_models
  use test_activation, only: collect_activation
  use test_prestress, only: collect_prestress
  use test_analysis_state, only: collect_analysis_state
  use test_principal, only: collect_principal
  use test_solution_methods, only: collect_solution_methods
  use test_stress_recovery, only: collect_stress_recovery
  use test_lined_hole, only: collect_lined_hole
  use test_lame_solids, only: collect_lame_solids
  use test_lists, only: collect_lists
  use test_result_schema, only: collect_result_schema
  use test_solid_elements, only: collect_solid_elements
  use test_collapse, only: collect_collapse
  use test_path_following, only: collect_path_following
  use test_interface_orientation, only: collect_interface_orientation
  use test_progress, only: collect_progress
  use test_element_contract, only: collect_element_contract
  use test_gravity, only: collect_gravity
  use test_geostatic, only: collect_geostatic
  use test_threads, only: collect_threads
  use test_section_report, only: collect_section_report
  use test_joint_report, only: collect_joint_report
  use test_restart, only: collect_restart
  implicit none

  interface
    subroutine c_exit(status) bind(C, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

  type(testsuite_t), allocatable :: suites(:)
  character(len=:), allocatable :: only
  character(len=256) :: arg
  integer :: nfail, i
  only = ''
  do i = 1, command_argument_count()
    call get_command_argument(i, arg)
    only = only // ' ' // trim(arg)
  end do
  suites = [ &
    new_testsuite('datain', collect_datain), &
    new_testsuite('elements', collect_elements), &
    new_testsuite('cholmod', collect_cholmod), &
    new_testsuite('skyline', collect_skyline), &
    new_testsuite('results_file', collect_results_file), &
    new_testsuite('analysis', collect_analysis), &
    new_testsuite('bad_input', collect_bad_input), &
    new_testsuite('interface_element', collect_interface_element), &
    new_testsuite('interface_mc', collect_interface_mc), &
    new_testsuite('nonlinear', collect_nonlinear), &
    new_testsuite('tri6', collect_tri6), &
    new_testsuite('bars', collect_bars), &
    new_testsuite('matsuoka', collect_matsuoka), &
    new_testsuite('concrete', collect_concrete), &
    new_testsuite('joint_models', collect_joint_models), &
    new_testsuite('activation', collect_activation), &
    new_testsuite('prestress', collect_prestress), &
    new_testsuite('analysis_state', collect_analysis_state), &
    new_testsuite('principal', collect_principal), &
    new_testsuite('solution_methods', collect_solution_methods), &
    new_testsuite('stress_recovery', collect_stress_recovery), &
    new_testsuite('lined_hole', collect_lined_hole), &
    new_testsuite('lame_solids', collect_lame_solids), &
    new_testsuite('lists', collect_lists), &
    new_testsuite('result_schema', collect_result_schema), &
    new_testsuite('solid_elements', collect_solid_elements), &
    new_testsuite('collapse', collect_collapse), &
    new_testsuite('path_following', collect_path_following), &
    new_testsuite('interface_orientation', collect_interface_orientation), &
    new_testsuite('progress', collect_progress), &
    new_testsuite('element_contract', collect_element_contract), &
    new_testsuite('gravity', collect_gravity), &
    new_testsuite('geostatic', collect_geostatic), &
    new_testsuite('threads', collect_threads), &
    new_testsuite('section_report', collect_section_report), &
    new_testsuite('joint_report', collect_joint_report), &
    new_testsuite('restart', collect_restart) &
    ]
  nfail = run_testsuites(suites, only)
  if (nfail < 0) call c_exit(2_c_int)      ! an unknown suite: the line is written, nothing ran
  if (nfail > 0) error stop 1
end program tester
