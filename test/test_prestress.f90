!> Prestressed bars (PRESTRESS, group, FORCE= | STRESS=): the prestress is added to the bars'
!! axial force in equal parts over the stage's steps, and the bars stay bonded afterwards.
!! Checked against closed forms of springs in series and in parallel, on the linear path (bars
!! only) and on the nonlinear path (tendons born in the stage that prestresses them, on a
!! Matsuoka-Nakai block that stays elastic), under every solution method.
module test_prestress
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: err_solver
  use feps_model, only: model_t, method_euler, method_modified_euler, method_newton_raphson, &
                        method_modified_newton_raphson, method_initial_stiffness, method_full_newton_raphson, &
                        method_names
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  implicit none
  private

  public :: collect_prestress

contains

  subroutine collect_prestress(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("tendon_in_series_with_a_spring", test_series), &
      new_unittest("block_with_tendons_born_prestressed_every_method", test_block), &
      new_unittest("deck_records_prestress_forces", test_deck), &
      new_unittest("forces_near_huge_stop_clearly", test_overflow) &
      ]
  end subroutine collect_prestress

  !> Tendon k1 = 100 N/mm prestressed by N0 = 90 N in series with a spring k2 = 200 N/mm
  !! between fixed ends (test/data/prestress_series.dat): u2 = -N0 / (k1 + k2) = -0.3 and
  !! N = N0 k2 / (k1 + k2) = 60 N in both, the reactions -60 and +60. Then F = 30 N on the
  !! middle node: du = 0.1, tendon 60 + k1 du = 70 N, spring 60 - k2 du = 40 N.
  subroutine test_series(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    call read_deck('test/data/prestress_series.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%linear, 'bars only: the linear path')
    if (allocated(error)) return
    call check(error, size(obs%steps), 2, 'one written step per stage on the linear path')
    if (allocated(error)) return
    call check(error, obs%steps(1)%displacement(1, 2), -0.3_dp, 'stage 1: u2 = -N0 / (k1 + k2)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(1)%groups(1)%stress(1, 1), 60.0_dp, 'stage 1: tendon N0 k2 / (k1 + k2)', &
               rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(1)%groups(2)%stress(1, 1), 60.0_dp, 'stage 1: spring N0 k2 / (k1 + k2)', &
               rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(1)%reaction(1, 1), -60.0_dp, 'stage 1: reaction at the tendon end', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(1)%reaction(1, 3), 60.0_dp, 'stage 1: reaction at the spring end', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(2)%displacement(1, 2), -0.2_dp, 'stage 2: u2 + F / (k1 + k2)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(2)%groups(1)%stress(1, 1), 70.0_dp, 'stage 2: the bonded tendon gains k1 du', &
               rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(2)%groups(2)%stress(1, 1), 40.0_dp, 'stage 2: the spring loses k2 du', &
               rel=1.0e-12_dp)
  end subroutine test_series

  !> A 10 mm cube (E = 1000, k_b = E A / L = 10000 N/mm) under p1 = 1 MPa in stage 1; four
  !! edge tendons (k_t = 20 N/mm each) born in stage 2 and prestressed there by STRESS = 100
  !! (N0 = 10 N) over 5 steps (test/data/prestress_block.dat). After step k of stage 2 each
  !! tendon carries (k / 5) N0 k_b / (k_b + 4 k_t), the block sxx = -1 - 4 N / 100 and the
  !! loaded face moves by -p1 L / E - 4 N / k_b. Every method must land on it at every step.
  subroutine test_block(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: methods(6) = [method_euler, method_modified_euler, method_newton_raphson, &
                                        method_modified_newton_raphson, method_initial_stiffness, &
                                        method_full_newton_raphson]
    real(dp), parameter :: kb = 10000.0_dp, kt = 20.0_dp, n0 = 10.0_dp
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    real(dp) :: n, expected_u
    integer :: m, k, q
    character(len=:), allocatable :: what

    do m = 1, size(methods)
      call read_deck('test/data/prestress_block.dat', model, error)
      if (allocated(error)) return
      model%stages(:)%controls%method = methods(m)
      model%stages(:)%controls%max_iterations = merge(1, 50, methods(m) == method_euler .or. &
                                                             methods(m) == method_modified_euler)
      if (allocated(obs%steps)) deallocate (obs%steps)
      call run_analysis(model, 'cholmod', obs, summary, error)
      if (allocated(error)) return
      what = trim(method_names(methods(m))) // ': '
      call check(error, .not. summary%linear, what // 'a Matsuoka block: the nonlinear path')
      if (allocated(error)) return
      call check(error, size(obs%steps), 6, what // 'end of stage 1 and every step of stage 2')
      if (allocated(error)) return
      call check(error, obs%steps(1)%groups(2)%stress(1, 1), 0.0_dp, what // 'unborn tendons carry nothing', &
                 abs=1.0e-12_dp)
      if (allocated(error)) return
      do k = 1, 5
        n = k / 5.0_dp * n0 * kb / (kb + 4.0_dp * kt)
        do q = 1, size(obs%steps(k + 1)%groups(2)%stress, 2)
          call check(error, obs%steps(k + 1)%groups(2)%stress(1, q), n, what // 'tendon force after step ' // &
                     achar(48 + k) // ' of 5', rel=1.0e-9_dp)
          if (allocated(error)) return
        end do
        do q = 1, size(obs%steps(k + 1)%groups(1)%stress, 2)
          call check(error, obs%steps(k + 1)%groups(1)%stress(1, q), -1.0_dp - 4.0_dp * n / 100.0_dp, &
                     what // 'block sxx = -p1 - 4 N / A_b', rel=1.0e-9_dp)
          if (allocated(error)) return
        end do
        expected_u = -10.0_dp / 1000.0_dp - 4.0_dp * n / kb
        call check(error, obs%steps(k + 1)%displacement(1, 2), expected_u, what // 'loaded face ux', &
                   rel=1.0e-9_dp)
        if (allocated(error)) return
      end do
    end do
  end subroutine test_block

  !> STRESS= becomes a force (times A) when the deck is read, and each stage's prestress is its
  !! own records plus LOAD= times the reference ones.
  subroutine test_deck(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    real(dp), allocatable :: f(:)
    call read_deck('test/data/prestress_block.dat', model, error)
    if (allocated(error)) return
    call check(error, size(model%prestresses), 1, 'one PRESTRESS record')
    if (allocated(error)) return
    call check(error, model%prestresses(1)%force, 10.0_dp, 'STRESS=100 on A=0.1: 10 N', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, model%prestresses(1)%stage, 2, 'recorded for the stage it follows')
    if (allocated(error)) return
    f = model%stage_prestress(1)
    call check(error, maxval(abs(f)), 0.0_dp, 'nothing in stage 1')
    if (allocated(error)) return
    f = model%stage_prestress(2)
    call check(error, f(2), 10.0_dp, 'stage 2: the tendons get 10 N', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, f(1), 0.0_dp, 'stage 2: the block gets none')
    if (allocated(error)) return
    ! a reference record (before any STAGE) scales with LOAD=
    model%prestresses(1)%stage = 0
    model%stages(1)%load_fraction = 0.25_dp
    f = model%stage_prestress(1)
    call check(error, f(2), 2.5_dp, 'a reference prestress times LOAD=0.25', rel=1.0e-14_dp)
  end subroutine test_deck

  !> A prestress of 1e299 N crushes the block. The support reactions' sum of squares used to
  !! overflow, which made the reference force infinite and every relative residual zero: the
  !! run "converged" with the tendons at 1e298 N on a block at zero stress. It must stop with
  !! the clear message instead.
  subroutine test_overflow(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    type(error_t), allocatable :: run_error
    call read_deck('test/data/prestress_block.dat', model, error)
    if (allocated(error)) return
    model%prestresses(1)%force = 1.0e299_dp
    call run_analysis(model, 'cholmod', obs, summary, run_error)
    if (.not. allocated(run_error)) then
      call test_failed(error, 'a prestress of 1e299 N on a 10 mm block ran to the end')
      return
    end if
    call check(error, run_error%code, err_solver, 'a numerical stop: ' // run_error%message)
    if (allocated(error)) return
    call check(error, index(run_error%message, 'does not converge') > 0, 'the clear stop: ' // run_error%message)
  end subroutine test_overflow

end module test_prestress
