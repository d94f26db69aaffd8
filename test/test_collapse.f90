!> Collapse is called collapse, and a run that ends out of balance says so (issue 24):
!! test/data/block_collapse.dat pulls a block off its base with 1.2 times the capacity of the
!! Mohr-Coulomb interface between them, (c + sigma_n tan phi) A = 250.94 N, so that no
!! equilibrium exists beyond load factor 1 + 1 / 1.2 = 1.8333.
module test_collapse
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: err_solver
  use feps_model, only: model_t, method_names, method_euler, method_modified_euler, method_newton_raphson, &
                        method_modified_newton_raphson, method_initial_stiffness, method_full_newton_raphson
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  use feps_program, only: run_options_t, run_summary_t, run_feps
  implicit none
  private

  public :: collect_collapse

  character(len=*), parameter :: deck = 'test/data/block_collapse.dat'
  !> The load factor beyond which no equilibrium exists: stage 2 carries 1.2 times the capacity.
  real(dp), parameter :: lf_capacity = 1.0_dp + 1.0_dp / 1.2_dp

contains

  subroutine collect_collapse(testsuite)
    type(unittest_t), allocatable, intent(out) :: testsuite(:)
    testsuite = [ &
      new_unittest('below its capacity (0.96) the block converges in every step, full Newton', test_below_capacity), &
      new_unittest('beyond its capacity full Newton stops as a collapse (exit 1) between 1.75 and 1.8333', &
                   test_full_newton_collapse), &
      new_unittest('every method stops beyond capacity with exit 1 and the last load factor', test_every_method), &
      new_unittest('a run that ends out of balance says so; --strict fails it and writes nothing', &
                   test_out_of_balance), &
      new_unittest('a converged run is marked converged', test_converged_run) &
      ]
  end subroutine collect_collapse

  !> The deck with every stage solved by method `method` (its code in feps_model) and stage 2
  !! pulling with `fraction` of the interface's capacity.
  subroutine load_deck(method, fraction, model, error)
    integer, intent(in) :: method
    real(dp), intent(in) :: fraction
    type(model_t), intent(out) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: s, l
    call read_deck(deck, model, error)
    if (allocated(error)) return
    do s = 1, size(model%stages)
      model%stages(s)%controls%method = method
      model%stages(s)%controls%max_iterations = merge(1, 50, method == method_euler .or. &
                                                       method == method_modified_euler)
    end do
    do l = 1, size(model%face_loads)
      associate (load => model%face_loads(l))
        if (load%stage == 2) load%total = load%total * fraction / 1.2_dp
      end associate
    end do
  end subroutine load_deck

  !> The load factor a stop names after `key`.
  real(dp) function factor_after(msg, key) result(lf)
    character(len=*), intent(in) :: msg, key
    integer :: at, length, ios
    lf = -1.0_dp
    at = index(msg, key)
    if (at == 0) return
    at = at + len(key)
    length = scan(msg(at:), ' ,;:)') - 1
    if (length < 0) length = len(msg) - at + 1
    read (msg(at:at + length - 1), *, iostat=ios) lf
    if (ios /= 0) lf = -1.0_dp
  end function factor_after

  !> 0.96 of the capacity: full Newton converges in all 11 steps (the lower bound of the next
  !! test's stop is not a false collapse).
  subroutine test_below_capacity(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    call load_deck(method_full_newton_raphson, 0.96_dp, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%converged .and. summary%unconverged_steps == 0 .and. summary%cutbacks == 0, &
               'converged without a cut-back')
  end subroutine test_below_capacity

  subroutine test_full_newton_collapse(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    type(error_t), allocatable :: run_error
    real(dp) :: lf
    call load_deck(method_full_newton_raphson, 1.2_dp, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, run_error)
    if (.not. allocated(run_error)) then
      call test_failed(error, 'a pull beyond the capacity ran to the end')
      return
    end if
    call check(error, run_error%code, err_solver, 'a collapse is a run that failed (exit 1): ' // run_error%message)
    if (allocated(error)) return
    call check(error, index(run_error%message, 'collapse in stage shear, step ') > 0 .and. &
               index(run_error%message, 'node ') > 0 .and. index(run_error%message, 'DOF u') > 0 .and. &
               index(run_error%message, 'no support is missing') > 0, &
               'names the collapse, the stage, step, node and DOF: ' // run_error%message)
    if (allocated(error)) return
    lf = factor_after(run_error%message, 'beyond load factor ')
    call check(error, lf >= 1.75_dp .and. lf <= lf_capacity + 1.0e-9_dp, &
               'the last load factor in equilibrium lies below the capacity 1.8333 (and above 1.75): ' // &
               run_error%message)
  end subroutine test_full_newton_collapse

  !> Whatever the method, the pull beyond the capacity stops with exit 1 (never exit 2 as a
  !! missing support, never a finished run) and names the last load factor accepted, which
  !! the methods that converge every step hold below the capacity.
  subroutine test_every_method(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    type(error_t), allocatable :: run_error
    integer, parameter :: methods(4) = [method_newton_raphson, method_modified_newton_raphson, &
                                        method_initial_stiffness, method_full_newton_raphson]
    integer :: i, method
    real(dp) :: lf
    ! the Euler methods take one iteration a step and carry on: test_out_of_balance
    do i = 1, size(methods)
      method = methods(i)
      call load_deck(method, 1.2_dp, model, error)
      if (allocated(error)) return
      call run_analysis(model, 'cholmod', obs, summary, run_error)
      if (.not. allocated(run_error)) then
        call test_failed(error, trim(method_names(method)) // ': a pull beyond the capacity ran to the end')
        return
      end if
      call check(error, run_error%code, err_solver, trim(method_names(method)) // ': ' // run_error%message)
      if (allocated(error)) return
      lf = max(factor_after(run_error%message, 'beyond load factor '), &
               factor_after(run_error%message, '(carried): load factor '), &
               factor_after(run_error%message, 'the last state in equilibrium: load factor '))
      call check(error, lf > 1.0_dp, trim(method_names(method)) // ' names the last load factor: ' // &
                 run_error%message)
      if (allocated(error)) return
      ! a carried residual is the last accepted state's (cut-backs reset the method's own
      ! record of it to force a factorization; the message once showed that reset, 1.8e308)
      if (index(run_error%message, '(carried)') > 0) then
        call check(error, factor_after(run_error%message, 'relative residual of ') < 1.0_dp, &
                   trim(method_names(method)) // ': the carried residual of the last state accepted: ' // &
                   run_error%message)
        if (allocated(error)) return
      end if
      if (index(run_error%message, '(carried)') == 0) then
        call check(error, lf <= lf_capacity + 1.0e-9_dp, trim(method_names(method)) // &
                   ': in equilibrium only below the capacity: ' // run_error%message)
        if (allocated(error)) return
      end if
      deallocate (run_error)
    end do
  end subroutine test_every_method

  !> Euler takes one iteration a step and carries on: beyond the capacity it ends out of
  !! balance. The summary says so (converged false, the residual and where); with --strict the
  !! run fails (err_solver: exit 1) naming the stage, step and load factor, and leaves no file.
  subroutine test_out_of_balance(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: out = 'build/test_collapse_strict.h5'
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    type(run_options_t) :: options
    type(run_summary_t) :: run
    logical :: exists
    call load_deck(method_euler, 1.2_dp, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, .not. summary%converged .and. summary%unbalanced > 1.0e-6_dp .and. &
               summary%unbalanced_stage == 'shear' .and. index(summary%unbalanced_at, 'DOF u') > 0, &
               'the summary says the run ends out of balance, where and by how much')
    if (allocated(error)) return
    options%deck = deck
    options%output = out
    options%method = 'euler'
    options%strict = .true.
    call run_feps(options, run, error)
    if (.not. allocated(error)) then
      call test_failed(error, '--strict accepted a run that ends out of balance')
      return
    end if
    if (error%code /= err_solver .or. index(error%message, 'stage shear, step 10, load factor 2') == 0 .or. &
        index(error%message, '--strict') == 0) then
      error%message = '--strict: ' // error%message
      return
    end if
    deallocate (error)
    inquire (file=out, exist=exists)
    call check(error, .not. exists, '--strict leaves no results file')
    if (allocated(error)) return
    inquire (file=out // '.part', exist=exists)
    call check(error, .not. exists, '--strict leaves no partial file')
  end subroutine test_out_of_balance

  !> The deck's own method (modified Newton-Raphson) at 0.5 of the capacity converges every
  !! stage: converged, and --strict changes nothing.
  subroutine test_converged_run(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    call load_deck(method_modified_newton_raphson, 0.5_dp, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%converged .and. summary%unbalanced == 0.0_dp, 'a converged run is marked converged')
  end subroutine test_converged_run

end module test_collapse
