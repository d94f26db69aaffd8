!> A small test-drive-like harness: unit tests are subroutines that return an allocated
!! error on failure; `check` compares values with stated tolerances.
module feps_testing
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: ieee_exceptions, only: ieee_usual, ieee_get_halting_mode, ieee_set_halting_mode
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_internal, str
  implicit none
  private

  public :: error_t, unittest_t, testsuite_t, new_unittest, new_testsuite, check, test_failed
  public :: run_testsuites


  abstract interface
    subroutine test_procedure(error)
      import :: error_t
      type(error_t), allocatable, intent(out) :: error
    end subroutine test_procedure
  end interface

  type :: unittest_t
    character(len=:), allocatable :: name
    procedure(test_procedure), pointer, nopass :: run => null()
    !> The test makes non-finite numbers on purpose (an overflow, a NaN input that a guard must
    !! refuse): it runs with floating-point halting off, so that a build with -ffpe-trap
    !! (test/cli/check_runtime.sh) runs it to its checks instead of stopping at the trap.
    logical :: nonfinite = .false.
  end type unittest_t

  abstract interface
    subroutine collect_procedure(tests)
      import :: unittest_t
      type(unittest_t), allocatable, intent(out) :: tests(:)
    end subroutine collect_procedure
  end interface
  public :: test_procedure, collect_procedure

  type :: testsuite_t
    character(len=:), allocatable :: name
    procedure(collect_procedure), pointer, nopass :: collect => null()
  end type testsuite_t

  interface check
    module procedure check_logical, check_real, check_int
  end interface check

contains

  !> A unit test; `nonfinite`: it makes non-finite numbers on purpose (see unittest_t).
  function new_unittest(name, run, nonfinite) result(test)
    character(len=*), intent(in) :: name
    procedure(test_procedure) :: run
    logical, intent(in), optional :: nonfinite
    type(unittest_t) :: test
    test%name = name
    test%run => run
    if (present(nonfinite)) test%nonfinite = nonfinite
  end function new_unittest

  function new_testsuite(name, collect) result(suite)
    character(len=*), intent(in) :: name
    procedure(collect_procedure) :: collect
    type(testsuite_t) :: suite
    suite%name = name
    suite%collect => collect
  end function new_testsuite

  subroutine test_failed(error, message)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in) :: message
    call fatal_error(error, err_internal, message)
  end subroutine test_failed

  subroutine check_logical(error, condition, message)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in) :: condition
    character(len=*), intent(in) :: message
    if (.not. condition) call test_failed(error, message)
  end subroutine check_logical

  !> Pass when |actual - expected| <= max(abs, rel*|expected|); NaN always fails.
  subroutine check_real(error, actual, expected, message, rel, abs)
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in) :: actual, expected
    character(len=*), intent(in) :: message
    real(dp), intent(in), optional :: rel, abs
    real(dp) :: tol
    tol = 0.0_dp
    if (present(rel)) tol = max(tol, rel * max(0.0_dp, sign(expected, 1.0_dp)))
    if (present(abs)) tol = max(tol, abs)
    if (.not. present(rel) .and. .not. present(abs)) tol = 1.0e-12_dp * sign(expected, 1.0_dp)
    if (actual /= actual .or. .not. (sign(actual - expected, 1.0_dp) <= tol)) then
      call test_failed(error, message // ': got ' // str(actual) // ', expected ' // str(expected) // &
                       ' (tolerance ' // str(tol) // ')')
    end if
  end subroutine check_real

  subroutine check_int(error, actual, expected, message)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in) :: actual, expected
    character(len=*), intent(in) :: message
    if (actual /= expected) call test_failed(error, message // ': got ' // str(actual) // &
                                             ', expected ' // str(expected))
  end subroutine check_int

  !> Run every suite (or only those named in `only`, separated by blanks), print a line per test
  !! and the closing line 'N passed, N failed'; return the number of failures. A name in `only`
  !! that is no suite's runs nothing: one line on error_unit lists the suites, and the result is -1.
  function run_testsuites(suites, only) result(nfail)
    type(testsuite_t), intent(in) :: suites(:)
    character(len=*), intent(in) :: only
    integer :: nfail
    type(unittest_t), allocatable :: tests(:)
    type(error_t), allocatable :: error
    character(len=:), allocatable :: names
    integer :: i, j, npass, first, last
    logical :: halting(size(ieee_usual))
    npass = 0
    nfail = 0
    first = 1
    do while (first <= len(only))
      if (only(first:first) == ' ') then
        first = first + 1
        cycle
      end if
      last = index(only(first:), ' ')
      last = merge(len(only), first + last - 2, last == 0)
      if (.not. any([(suites(i)%name == only(first:last), i = 1, size(suites))])) then
        names = ''
        do i = 1, size(suites)
          names = names // merge(', ', '  ', i > 1) // suites(i)%name
        end do
        write (error_unit, '(a)') 'tester: no test suite "' // only(first:last) // '" (the suites:' // &
          names(2:) // ')'
        nfail = -1
        return
      end if
      first = last + 2
    end do
    do i = 1, size(suites)
      if (len_trim(only) > 0 .and. index(' ' // only // ' ', ' ' // suites(i)%name // ' ') == 0) cycle
      call suites(i)%collect(tests)
      do j = 1, size(tests)
        ! Halting is set and restored here: a procedure using the IEEE modules restores it on return.
        if (tests(j)%nonfinite) then
          call ieee_get_halting_mode(ieee_usual, halting)
          call ieee_set_halting_mode(ieee_usual, .false.)
        end if
        call tests(j)%run(error)
        if (tests(j)%nonfinite) call ieee_set_halting_mode(ieee_usual, halting)
        if (allocated(error)) then
          nfail = nfail + 1
          write (*, '(a)') '  FAIL ' // suites(i)%name // ': ' // tests(j)%name // ': ' // error%message
          deallocate (error)
        else
          npass = npass + 1
          write (*, '(a)') '  ok   ' // suites(i)%name // ': ' // tests(j)%name
        end if
      end do
    end do
    write (*, '(a)') str(npass) // ' passed, ' // str(nfail) // ' failed'
  end function run_testsuites

end module feps_testing
