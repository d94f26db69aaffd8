!> The solution methods of thesis 2.6 against an independent re-implementation of what
!! docs/input-format.md (CONTROLS) says they do, on a problem with one effective DOF whose exact
!! path is known (test/data/slide_1dof*.dat; test/reference/solution_methods_1dof.py prints the
!! reference paths): every iterate-dependent number (displacement, iterations per step,
!! factorizations, cut-backs) must agree. Also: a cut-back restores the state exactly, a change
!! of supports or of method between stages keeps each method's stiffness, and the stages of a
!! linear model add their loads and prescribed displacements and balance them by reactions.
module test_solution_methods
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_model, only: model_t, method_euler, method_modified_euler, method_newton_raphson, &
                        method_modified_newton_raphson, method_initial_stiffness, method_full_newton_raphson, &
                        method_names
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  use feps_line_search, only: line_search_t, line_search_begin, line_search_next, line_search_eta, &
                              line_search_s_min, line_search_max_evaluations
  implicit none
  private

  public :: collect_solution_methods

  integer, parameter :: methods(6) = [method_euler, method_modified_euler, method_newton_raphson, &
                                      method_modified_newton_raphson, method_initial_stiffness, &
                                      method_full_newton_raphson]
  !> MAXIT of each method by default (docs/input-format.md, CONTROLS)
  integer, parameter :: default_maxit(6) = [1, 1, 50, 10, 10, 50]
  integer, parameter :: upper_node = 5   !! one of the four upper nodes (they move alike)

contains

  subroutine collect_solution_methods(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('one-DOF slide under load: every method''s path, iterations, factorizations, cut-backs', &
                   test_force_control), &
      new_unittest('one-DOF slide under displacement (|P| = 0, reactions the reference): every method', &
                   test_displacement_control), &
      new_unittest('a step cut back and finished equals the smaller steps taken directly, to the last bit', &
                   test_cutback_restores), &
      new_unittest('a change of supports between stages keeps every method''s stiffness', test_support_change), &
      new_unittest('initial stiffness after a Newton-Raphson stage factorizes the elastic stiffness', &
                   test_initial_stiffness_after_tangent), &
      new_unittest('linear stages: LOAD= share plus own loads and displacements, OUTPUT=k, equilibrium', &
                   test_staged_linear), &
      new_unittest('line search: the root of du . R(u + s du) on a line and across a kink', test_line_search_root), &
      new_unittest('line search: one-DOF unloading from sliding, the overshoot 5-fold, s = 0.2 exactly', &
                   test_line_search_unloading) &
      ]
  end subroutine collect_solution_methods

  !> Read `deck`, solve every stage by `method` with its default MAXIT, keep every step written.
  subroutine run_method(deck, method, obs, summary, error)
    character(len=*), intent(in) :: deck
    integer, intent(in) :: method
    type(all_steps_t), intent(out) :: obs
    type(analysis_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    integer :: s
    call read_deck(deck, model, error)
    if (allocated(error)) return
    do s = 1, size(model%stages)
      model%stages(s)%controls%method = method
      model%stages(s)%controls%max_iterations = default_maxit(findloc(methods, method, dim=1))
    end do
    call run_analysis(model, 'cholmod', obs, summary, error)
  end subroutine run_method

  !> Each step's displacement (1e-12 relative) and iterations, and the run's factorizations and
  !! cut-backs, against the reference path.
  subroutine check_path(obs, summary, label, u_ref, its_ref, nfact, ncut, error)
    type(all_steps_t), intent(in) :: obs
    type(analysis_summary_t), intent(in) :: summary
    character(len=*), intent(in) :: label
    real(dp), intent(in) :: u_ref(:)
    integer, intent(in) :: its_ref(:), nfact, ncut
    type(error_t), allocatable, intent(out) :: error
    integer :: k
    call check(error, size(obs%steps), size(u_ref), label // ': steps written')
    if (allocated(error)) return
    do k = 1, size(u_ref)
      call check(error, obs%steps(k)%displacement(1, upper_node), u_ref(k), label // ': u at step ' // str(k), &
                 rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%iterations, its_ref(k), label // ': iterations in step ' // str(k))
      if (allocated(error)) return
    end do
    call check(error, summary%factorizations, nfact, label // ': factorizations')
    if (allocated(error)) return
    call check(error, summary%cutbacks, ncut, label // ': cut-backs')
  end subroutine check_path

  !> test/data/slide_1dof.dat: 300 N in 10 steps, yield in step 5 (120 -> 150 N). Closed forms:
  !! Euler drops the unbalanced force, so after yield it adds F / kb = 1.2 per step from 1.2
  !! (7.2, not 8); modified Euler carries the 20 N its yield step leaves and is exact from step 6
  !! on; the Newton family is exact, u = 1 + (F - 125) / 25. Newton-Raphson keeps the elastic
  !! tangent of its step start through step 5 (error x 0.8 per iteration): 50 iterations do not
  !! reach 1e-6, the step is cut twice and its quarters take 148 in all; modified Newton-Raphson's
  !! step 5 ends above DIVERGENCE, is cut once and refactorized (elastic, then the sliding
  !! tangent); initial stiffness carries what 10 iterations at x 0.8 leave (cut back to reach
  !! DIVERGENCE). Iterations, factorizations and cut-backs: test/reference/solution_methods_1dof.py.
  subroutine test_force_control(error)
    type(error_t), allocatable, intent(out) :: error
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: u(10, 6), exact(10)
    integer :: its(10, 6), k, m
    integer, parameter :: nfact(6) = [10, 10, 15, 3, 1, 11], ncut(6) = [0, 0, 2, 1, 8, 0]
    do k = 1, 10
      exact(k) = merge(0.24_dp * k, 1.0_dp + (30.0_dp * k - 125.0_dp) / 25.0_dp, k <= 4)
    end do
    u(:, 1) = [0.24_dp, 0.48_dp, 0.72_dp, 0.96_dp, (1.2_dp * (k - 4), k = 5, 10)]
    u(:, 2) = [exact(1:4), 1.2_dp, exact(6:10)]
    u(:, 3) = exact
    u(:, 4) = exact
    u(:, 5) = [exact(1:4), 1.96383380475047_dp, 3.1639129146026_dp, 4.32824190576443_dp, 5.52783064703262_dp, &
               6.72782590554226_dp, 7.9278258508766_dp]
    u(:, 6) = exact
    its = 1
    its(5, 3) = 148
    its(5, 4) = 21
    its(5:10, 5) = [50, 60, 30, 30, 30, 30]
    its(5, 6) = 2
    do m = 1, 6
      call run_method('test/data/slide_1dof.dat', methods(m), obs, summary, error)
      if (allocated(error)) return
      call check_path(obs, summary, trim(method_names(methods(m))), u(:, m), its(:, m), nfact(m), ncut(m), error)
      if (allocated(error)) return
    end do
  end subroutine test_force_control

  !> test/data/slide_1dof_displaced.dat: the bars' ground ends move 1.05 per step and no free
  !! DOF is loaded, so the reference force of the convergence test is the reactions'. Exact:
  !! u = d / 5 up to d = 5, then d - 4. Euler drifts by the 0.2 its yield step leaves; the
  !! methods that converge end on the exact path with the reactions balancing each other (the
  !! ground's and the interface's: 1e-9 of the 100 N they carry).
  subroutine test_displacement_control(error)
    type(error_t), allocatable, intent(out) :: error
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: u(10, 6), exact(10)
    integer :: its(10, 6), k, m
    integer, parameter :: nfact(6) = [10, 10, 10, 2, 1, 11], ncut(6) = [0, 0, 0, 0, 10, 0]
    do k = 1, 10
      exact(k) = merge(0.21_dp * k, 1.05_dp * k - 4.0_dp, k <= 4)
    end do
    u(:, 1) = [exact(1:4), (1.05_dp * (k - 4), k = 5, 10)]
    u(:, 2) = [exact(1:4), 1.05_dp, exact(6:10)]
    u(:, 3) = [exact(1:4), 1.2499944248137_dp, exact(6:10)]
    u(:, 4) = [exact(1:4), 1.2231564544_dp, exact(6:10)]
    u(:, 5) = [exact(1:4), 1.2231564544_dp, 2.26842443855597_dp, 3.31842380956318_dp, 4.36842380947957_dp, &
               5.41842380947956_dp, 6.46842380947956_dp]
    u(:, 6) = exact
    its = 1
    its(5, 3) = 48
    its(5, 4) = 10
    its(5:10, 5) = [10, 60, 60, 60, 60, 60]
    its(5, 6) = 2
    do m = 1, 6
      call run_method('test/data/slide_1dof_displaced.dat', methods(m), obs, summary, error)
      if (allocated(error)) return
      call check_path(obs, summary, trim(method_names(methods(m))), u(:, m), its(:, m), nfact(m), ncut(m), error)
      if (allocated(error)) return
      if (any(methods(m) == [method_newton_raphson, method_full_newton_raphson, method_modified_newton_raphson, &
                             method_modified_euler])) then
        call check(error, obs%steps(10)%residual < 1.0e-6_dp, trim(method_names(methods(m))) // &
                   ': converged against the reactions, residual ' // str(obs%steps(10)%residual))
        if (allocated(error)) return
        call check(error, sum(obs%steps(10)%reaction(1, :)), 0.0_dp, trim(method_names(methods(m))) // &
                   ': the reactions balance', abs=1.0e-7_dp)
        if (allocated(error)) return
      end if
    end do
  end subroutine test_displacement_control

  !> The runs of slide_1dof.dat that cut steps back (Newton-Raphson: step 5 into quarters;
  !! initial stiffness: steps 5-6 into quarters, 7-10 into halves) end in the state of the same
  !! load applied directly in those steps (slide_1dof_direct_nr.dat, _is.dat): commit and restore
  !! leave nothing of a failed try behind. Displacements, reactions and interface stresses
  !! within 1e-14 (relative).
  subroutine test_cutback_restores(error)
    type(error_t), allocatable, intent(out) :: error
    type(all_steps_t) :: cut, direct
    type(analysis_summary_t) :: s_cut, s_direct
    character(len=*), parameter :: decks(2) = ['test/data/slide_1dof_direct_nr.dat', &
                                               'test/data/slide_1dof_direct_is.dat']
    integer, parameter :: which(2) = [method_newton_raphson, method_initial_stiffness]
    integer :: i, n1, n2
    do i = 1, 2
      call run_method('test/data/slide_1dof.dat', which(i), cut, s_cut, error)
      if (allocated(error)) return
      call run_method(decks(i), which(i), direct, s_direct, error)
      if (allocated(error)) return
      call check(error, s_cut%cutbacks > 0 .and. s_direct%cutbacks == 0, decks(i) // ': the cut run cut, the ' // &
                 'direct one did not')
      if (allocated(error)) return
      n1 = size(cut%steps)
      n2 = size(direct%steps)
      call check(error, maxval(abs(cut%steps(n1)%displacement - direct%steps(n2)%displacement)), 0.0_dp, &
                 decks(i) // ': displacements', abs=1.0e-14_dp * maxval(abs(direct%steps(n2)%displacement)))
      if (allocated(error)) return
      call check(error, maxval(abs(cut%steps(n1)%reaction - direct%steps(n2)%reaction)), 0.0_dp, &
                 decks(i) // ': reactions', abs=1.0e-14_dp * maxval(abs(direct%steps(n2)%reaction)))
      if (allocated(error)) return
      call check(error, maxval(abs(cut%steps(n1)%groups(1)%stress - direct%steps(n2)%groups(1)%stress)), 0.0_dp, &
                 decks(i) // ': interface stresses', abs=1.0e-14_dp * maxval(abs(direct%steps(n2)%groups(1)%stress)))
      if (allocated(error)) return
    end do
  end subroutine test_cutback_restores

  !> slide_1dof_support_change.dat holds a bar's free end from its second stage on, which does
  !! not touch the slide: every method must take slide_1dof.dat's steps (1e-12), with the same
  !! iterations. The new equations were factorized with the elastic stiffness instead of the
  !! committed tangent: Euler then ended at 6.24 instead of 7.2, modified Euler took one step
  !! to 1.6 instead of 3.2, Newton-Raphson needed 52 iterations instead of 1.
  subroutine test_support_change(error)
    type(error_t), allocatable, intent(out) :: error
    type(all_steps_t) :: obs, ref
    type(analysis_summary_t) :: summary, s_ref
    integer :: m, k
    do m = 1, 6
      call run_method('test/data/slide_1dof.dat', methods(m), ref, s_ref, error)
      if (allocated(error)) return
      call run_method('test/data/slide_1dof_support_change.dat', methods(m), obs, summary, error)
      if (allocated(error)) return
      call check(error, size(obs%steps), 10, 'steps written')
      if (allocated(error)) return
      do k = 1, 10
        call check(error, obs%steps(k)%displacement(1, upper_node), ref%steps(k)%displacement(1, upper_node), &
                   trim(method_names(methods(m))) // ': u at step ' // str(k), rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, obs%steps(k)%iterations, ref%steps(k)%iterations, &
                   trim(method_names(methods(m))) // ': iterations in step ' // str(k))
        if (allocated(error)) return
      end do
    end do
  end subroutine test_support_change

  !> slide_1dof_unload_is.dat: Newton-Raphson loads to 180 N (sliding, tangent kb = 25), then a
  !! stage by the initial-stiffness method takes 120 N off, an elastic unloading that the elastic
  !! stiffness solves exactly: u = 3.2 - 0.24 k, one iteration per step, one factorization more
  !! than the 11 of the first stage. It used to keep the last Newton-Raphson tangent, five times
  !! softer than the unloading response, and stopped after 10 cut-backs.
  subroutine test_initial_stiffness_after_tangent(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: k
    call read_deck('test/data/slide_1dof_unload_is.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, size(obs%steps), 5, 'steps written (the loading stage''s last, every unloading step)')
    if (allocated(error)) return
    do k = 0, 4
      call check(error, obs%steps(k + 1)%displacement(1, upper_node), 3.2_dp - 0.24_dp * k, 'u at unloading step ' // &
                 str(k), rel=1.0e-12_dp)
      if (allocated(error)) return
      if (k == 0) cycle
      call check(error, obs%steps(k + 1)%iterations, 1, 'iterations in unloading step ' // str(k))
      if (allocated(error)) return
    end do
    call check(error, summary%factorizations, 12, 'factorizations')
  end subroutine test_initial_stiffness_after_tangent

  !> test/data/staged_linear.dat (closed forms in the deck): the steps written (1-4 by OUTPUT=1,
  !! 6 and 7 by OUTPUT=2 of 3), the prescribed ux of the face x = 10 (the reference value times
  !! LOAD= plus the stage's own, and two records on one DOF adding up: 1e-12), the reactions
  !! balancing the applied force in every direction (1e-12 of the 7500 N applied), and skyline
  !! equal to CHOLMOD (1e-12). Before the fix a stage's own DISPLACE replaced the reference one
  !! and the last record on a DOF replaced the others (0.002 instead of 0.007 in stage one).
  subroutine test_staged_linear(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs(2)
    type(analysis_summary_t) :: summary
    character(len=*), parameter :: solvers(2) = ['cholmod', 'skyline']
    integer, parameter :: written(6) = [1, 2, 3, 4, 6, 7]
    real(dp) :: t, ux, ux_half, f(3), x(3)
    integer :: i, k, n
    do i = 1, 2
      call read_deck('test/data/staged_linear.dat', model, error)
      if (allocated(error)) return
      call run_analysis(model, solvers(i), obs(i), summary, error)
      if (allocated(error)) return
      call check(error, summary%linear, 'a linear model')
      if (allocated(error)) return
      call check(error, size(obs(i)%steps), size(written), solvers(i) // ': steps written')
      if (allocated(error)) return
      do k = 1, size(written)
        associate (st => obs(i)%steps(k))
          call check(error, st%step, written(k), solvers(i) // ': step written')
          if (allocated(error)) return
          if (st%stage == 1) then
            t = st%step_in_stage / 4.0_dp
            ux = 0.007_dp * t
            ux_half = ux
            f = [700.0_dp * t, 0.0_dp, -5000.0_dp * t]
          else
            t = st%step_in_stage / 3.0_dp
            ux = 0.007_dp + 0.009_dp * t
            ux_half = 0.007_dp + 0.010_dp * t
            f = [700.0_dp, 0.0_dp, -5000.0_dp - 2500.0_dp * t]
          end if
          do n = 1, size(model%coords, 2)
            x = model%coords(:, n)
            if (abs(x(1) - 10.0_dp) > 1.0e-9_dp) cycle
            call check(error, st%displacement(1, n), merge(ux_half, ux, x(2) <= 5.0_dp + 1.0e-9_dp), &
                       solvers(i) // ': ux on x = 10 at step ' // str(st%step), rel=1.0e-12_dp)
            if (allocated(error)) return
          end do
          call check(error, maxval(abs(sum(st%applied_force, dim=2) - f)), 0.0_dp, solvers(i) // &
                     ': applied force at step ' // str(st%step), abs=1.0e-12_dp * 7500.0_dp)
          if (allocated(error)) return
          call check(error, maxval(abs(sum(st%reaction, dim=2) + f)), 0.0_dp, solvers(i) // &
                     ': reactions balance the applied force at step ' // str(st%step), abs=1.0e-12_dp * 7500.0_dp)
          if (allocated(error)) return
        end associate
      end do
    end do
    do k = 1, size(written)
      call check(error, maxval(abs(obs(1)%steps(k)%displacement - obs(2)%steps(k)%displacement)), 0.0_dp, &
                 'skyline equals CHOLMOD at step ' // str(written(k)), &
                 abs=1.0e-12_dp * maxval(abs(obs(1)%steps(k)%displacement)))
      if (allocated(error)) return
    end do
  end subroutine test_staged_linear

  !> The search of feps_line_search on scalar functions g(s) = du . R(u + s du) whose root is
  !! known. A quadratic energy (linear g, the correction overshooting 5-fold: g = g0 (1 - 5 s))
  !! has its root s = 0.2 found by the first secant step, exactly (1e-15). Across a kink (a gap
  !! closing at s = 0.3, the stiffness 4 times higher beyond it: g = 1 - 2 s, then 0.4 - 8 (s -
  !! 0.3), root s = 0.35) the Illinois steps reach the root to 1e-12 when asked (eta = 1e-14),
  !! and with the defaults stop within line_search_max_evaluations at |g| <= eta g0. No search
  !! without an overshoot (g(1) >= 0, or g(0) <= 0: du points uphill); the shortest correction is
  !! line_search_s_min, where a search still beyond the root stops.
  subroutine test_line_search_root(error)
    type(error_t), allocatable, intent(out) :: error
    type(line_search_t) :: ls
    integer :: n
    call line_search_begin(ls, 3.0_dp, 3.0_dp * (1.0_dp - 5.0_dp), line_search_eta, line_search_s_min)
    call check(error, .not. ls%done, 'linear g: an overshoot is searched')
    if (allocated(error)) return
    call check(error, ls%s, 0.2_dp, 'linear g: the first secant step is the root', abs=1.0e-15_dp)
    if (allocated(error)) return
    call line_search_next(ls, g_linear(ls%s), line_search_eta, line_search_s_min, line_search_max_evaluations)
    call check(error, ls%done .and. ls%evaluations == 1, 'linear g: accepted after one evaluation')
    if (allocated(error)) return

    call line_search_begin(ls, g_kink(0.0_dp), g_kink(1.0_dp), 1.0e-14_dp, line_search_s_min)
    n = 0
    do while (.not. ls%done)
      n = n + 1
      call line_search_next(ls, g_kink(ls%s), 1.0e-14_dp, line_search_s_min, 100)
    end do
    call check(error, ls%s, 0.35_dp, 'kink: Illinois steps to the root', abs=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, n < 20, 'kink: Illinois converges superlinearly, ' // str(n) // ' evaluations')
    if (allocated(error)) return
    call line_search_begin(ls, g_kink(0.0_dp), g_kink(1.0_dp), line_search_eta, line_search_s_min)
    do while (.not. ls%done)
      call line_search_next(ls, g_kink(ls%s), line_search_eta, line_search_s_min, line_search_max_evaluations)
    end do
    call check(error, ls%evaluations <= line_search_max_evaluations .and. &
               abs(g_kink(ls%s)) <= line_search_eta * g_kink(0.0_dp), &
               'kink, defaults: |g(s)| <= eta g(0) within the evaluations allowed, s = ' // str(ls%s))
    if (allocated(error)) return

    call line_search_begin(ls, 1.0_dp, 0.2_dp, line_search_eta, line_search_s_min)
    call check(error, ls%done .and. ls%s == 1.0_dp, 'no overshoot (g(1) > 0): the full correction')
    if (allocated(error)) return
    call line_search_begin(ls, -1.0_dp, -3.0_dp, line_search_eta, line_search_s_min)
    call check(error, ls%done .and. ls%s == 1.0_dp, 'g(0) < 0: no search')
    if (allocated(error)) return
    call line_search_begin(ls, 0.3_dp, 0.3_dp - 0.3_dp / 0.05_dp, line_search_eta, line_search_s_min)
    call check(error, ls%s, line_search_s_min, 'root at s = 0.05: clamped to s_min')
    if (allocated(error)) return
    call line_search_next(ls, 0.3_dp * (1.0_dp - ls%s / 0.05_dp), line_search_eta, line_search_s_min, &
                          line_search_max_evaluations)
    call check(error, ls%done .and. ls%s == line_search_s_min, 'still beyond the root at s_min: stop there')
  contains
    pure real(dp) function g_linear(s)
      real(dp), intent(in) :: s
      g_linear = 3.0_dp * (1.0_dp - 5.0_dp * s)
    end function g_linear
    pure real(dp) function g_kink(s)
      real(dp), intent(in) :: s
      if (s < 0.3_dp) then
        g_kink = 1.0_dp - 2.0_dp * s
      else
        g_kink = 0.4_dp - 8.0_dp * (s - 0.3_dp)
      end if
    end function g_kink
  end subroutine test_line_search_root

  !> slide_1dof_unload_is.dat with its unloading stage by newton-raphson and by
  !! full-newton-raphson with LINESEARCH=energy. The first unloading step starts from the sliding
  !! tangent kb = 25, five times softer than the elastic unloading response 125: the correction
  !! overshoots 5-fold, g(s) = du . R(u + s du) is linear in s, and its root s = 25 / 125 = 0.2
  !! is found by one secant step. The step converges in one iteration with one residual
  !! evaluation added; the later steps start from the elastic tangent and need no search (u =
  !! 3.2 - 0.24 k, 1e-12, one iteration a step). Without it Newton-Raphson, whose tangent stays
  !! that of the step's start, overshoots at any step size and stops; full Newton takes two
  !! iterations.
  subroutine test_line_search_unloading(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: newton(2) = [method_newton_raphson, method_full_newton_raphson]
    type(model_t) :: model
    type(all_steps_t) :: searched(2), plain(2)   !! an observer keeps the steps of every run it sees
    type(analysis_summary_t) :: summary
    type(error_t), allocatable :: run_error
    integer :: i, k
    character(len=:), allocatable :: label
    do i = 1, 2
      label = trim(method_names(newton(i))) // ' with the line search'
      call read_deck('test/data/slide_1dof_unload_is.dat', model, error)
      if (allocated(error)) return
      model%stages(2)%controls%method = newton(i)
      model%stages(2)%controls%max_iterations = 50
      model%stages(2)%controls%line_search = .true.
      call run_analysis(model, 'cholmod', searched(i), summary, error)
      if (allocated(error)) return
      do k = 0, 4
        call check(error, searched(i)%steps(k + 1)%displacement(1, upper_node), 3.2_dp - 0.24_dp * k, label // &
                   ': u at unloading step ' // str(k), rel=1.0e-12_dp)
        if (allocated(error)) return
        if (k == 0) cycle
        call check(error, searched(i)%steps(k + 1)%iterations, 1, label // ': iterations in unloading step ' // str(k))
        if (allocated(error)) return
      end do
      ! the loading stage's Newton-Raphson cuts its step 5 into quarters (test_cutback_restores)
      call check(error, summary%line_searches == 1 .and. summary%line_search_evaluations == 1 .and. &
                 summary%cutbacks == 2, label // ': one correction scaled, one evaluation added, no cut-back ' // &
                 'but the loading stage''s 2: ' // str(summary%line_searches) // ', ' // &
                 str(summary%line_search_evaluations) // ', ' // str(summary%cutbacks))
      if (allocated(error)) return

      call read_deck('test/data/slide_1dof_unload_is.dat', model, error)
      if (allocated(error)) return
      model%stages(2)%controls%method = newton(i)
      model%stages(2)%controls%max_iterations = 50
      call run_analysis(model, 'cholmod', plain(i), summary, run_error)
      if (newton(i) == method_newton_raphson) then
        call check(error, allocated(run_error), 'newton-raphson without the line search: expected to stop')
        if (.not. allocated(error)) call check(error, index(run_error%message, 'LINESEARCH=energy') > 0, &
                                               'the stop names LINESEARCH=energy: ' // run_error%message)
      else if (allocated(run_error)) then
        call test_failed(error, 'full-newton-raphson without the line search: ' // run_error%message)
      else
        call check(error, plain(i)%steps(2)%iterations, 2, 'full-newton-raphson without the line search: ' // &
                   'iterations in unloading step 1')
      end if
      if (allocated(error)) return
    end do
  end subroutine test_line_search_unloading

end module test_solution_methods
