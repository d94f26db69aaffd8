!> The incremental driver: linear scenes stay linear, contact through interfaces at extreme
!! stiffness ratios, a fully open interface, huge steps, and the clear stop.
module test_nonlinear
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: err_solver, str
  use feps_material, only: state_plastic, state_open
  use feps_model, only: model_t, method_newton_raphson, method_modified_euler, method_initial_stiffness, &
                        method_modified_newton_raphson, method_full_newton_raphson, load_traction
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_observer, only: observer_t, step_result_t
  use feps_test_observers, only: all_steps_t
  use feps_gauss, only: square_rule
  implicit none
  private

  public :: collect_nonlinear

  !> Keeps the last step written and the progress lines.
  type, extends(observer_t) :: keep_last_t
    type(step_result_t) :: last
    integer :: nwritten = 0
    character(len=200), allocatable :: lines(:)
  contains
    procedure :: progress => keep_progress
    procedure :: write_step => keep_step
  end type keep_last_t

contains

  subroutine collect_nonlinear(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('a linear scene does one factorization whatever the deck asks', test_linear_scene), &
      new_unittest('contact stress equals a uniform traction, Kn 8..8e5, E 1..1e6', test_contact_uniform), &
      new_unittest('contact stress equals a linearly varying traction', test_contact_linear), &
      new_unittest('a fully open interface is held by its residual stiffness and reported', test_fully_open), &
      new_unittest('one huge sliding step equals 100 small ones', test_huge_step), &
      new_unittest('an impossible load stops with the clear message, never NaN', test_clear_stop), &
      new_unittest('plane strain: contact through line3 interfaces, Gauss and nodal', test_contact_2d), &
      new_unittest('Matsuoka block: one step 100 times past yield, every preset', test_matsuoka_huge_step), &
      new_unittest('stiffness contrast 1e11 : 1.44 in one model, condition warning', test_stiffness_contrast), &
      new_unittest('initial stiffness factorizes once; elastic groups carry no point state', test_initial_stiffness_once), &
      new_unittest('BFGS: a stiff interface sliding on soft blocks converges in 10 iterations', test_bfgs_sliding), &
      new_unittest('cohesionless dilatant joint from zero: full Newton converges, solution scales with load', &
                   test_cohesionless_from_zero), &
      new_unittest('a block pulled past the tensile strength stops where the joint opens, and says so', &
                   test_brittle_pull), &
      new_unittest('full Newton follows an unzipping cascade to equilibrium, given the iterations', &
                   test_unzipping_cascade), &
      new_unittest('non-dilatant joint (psi = 0): full Newton with the LU tangent converges as BFGS does', &
                   test_non_dilatant_joint), &
      new_unittest('concrete at its tensile cap: the closest-point tension rule under full Newton', &
                   test_tension_cap_beam), &
      new_unittest('modified Newton-Raphson past a birth on yielded concrete: the elastic retry', &
                   test_birth_on_yielded), &
      new_unittest('a block pulled over a block: full Newton with the line search, no cut-back, mu N', &
                   test_line_search_friction), &
      new_unittest('the line search changes the way to a step''s solution, not the solution', &
                   test_line_search_same_solution) &
      ]
  end subroutine collect_nonlinear

  subroutine keep_progress(self, line)
    class(keep_last_t), intent(inout) :: self
    character(len=*), intent(in) :: line
    character(len=200), allocatable :: tmp(:)
    if (.not. allocated(self%lines)) allocate (self%lines(0))
    tmp = [character(len=200) :: self%lines, line]
    call move_alloc(tmp, self%lines)
  end subroutine keep_progress

  subroutine keep_step(self, res, error)
    class(keep_last_t), intent(inout) :: self
    type(step_result_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    self%last = res
    self%nwritten = self%nwritten + 1
  end subroutine keep_step

  !> The load factor a clear stop names ("..., load factor 0.5776: ...").
  real(dp) function stop_load_factor(msg) result(lf)
    character(len=*), intent(in) :: msg
    integer :: at
    at = index(msg, 'load factor ') + len('load factor ')
    read (msg(at:at + index(msg(at:), ':') - 2), *) lf
  end function stop_load_factor

  logical function said(obs, piece)
    type(keep_last_t), intent(in) :: obs
    character(len=*), intent(in) :: piece
    integer :: i
    said = .false.
    if (.not. allocated(obs%lines)) return
    do i = 1, size(obs%lines)
      if (index(obs%lines(i), piece) > 0) said = .true.
    end do
  end function said

  !> The cube deck asked for 50 Newton-Raphson steps: still one factorization, exact answer.
  subroutine test_linear_scene(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    call read_deck('test/data/cube.dat', model, error)
    if (allocated(error)) return
    model%stages(1)%steps = 50
    model%stages(1)%controls%method = method_newton_raphson
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%linear, 'detected as linear')
    if (allocated(error)) return
    call check(error, summary%factorizations, 1, 'factorizations')
    if (allocated(error)) return
    call check(error, summary%iterations, 1, 'solves')
    if (allocated(error)) return
    call check(error, said(obs, 'linear model'), 'the detection is reported')
    if (allocated(error)) return
    call check(error, obs%last%groups(1)%stress(3, 1), -100.0_dp, 'szz', rel=1.0e-10_dp)
  end subroutine test_linear_scene

  !> Uniform pressure p on the upper block: every interface point carries sigma_n = -p.
  subroutine test_contact_uniform(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: kns(5) = [8.0_dp, 80.0_dp, 800.0_dp, 8.0e3_dp, 8.0e5_dp]
    real(dp), parameter :: es(4) = [1.0_dp, 1.0e2_dp, 1.0e4_dp, 1.0e6_dp]
    integer :: i, j
    do i = 1, size(kns)
      do j = 1, size(es)
        call contact_case(kns(i), es(j), .false., error)
        if (allocated(error)) return
      end do
    end do
  end subroutine test_contact_uniform

  subroutine test_contact_linear(error)
    type(error_t), allocatable, intent(out) :: error
    call contact_case(8.0_dp, 1.0_dp, .true., error)
    if (allocated(error)) return
    call contact_case(8.0e5_dp, 1.0e6_dp, .true., error)
    if (allocated(error)) return
    call contact_case(8.0e5_dp, 1.0_dp, .true., error)
  end subroutine test_contact_linear

  !> p = 1 MPa uniform, or p = 0.5 + x / 20 (linear in x from 0.5 to 1.5): the linear stress
  !! field is exact, so each interface point must carry sigma_n = -p(x) (1%), tau = 0.
  subroutine contact_case(kn, e, linear, error)
    real(dp), intent(in) :: kn, e
    logical, intent(in) :: linear
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: x, p, sn, tau
    integer :: q, g
    character(len=64) :: what
    call read_deck('test/data/block_contact.dat', model, error)
    if (allocated(error)) return
    call model%materials(1)%set('e', e)            ! block: E
    call model%materials(2)%set('kn', kn)          ! contact: KN
    call model%materials(2)%set('ks', kn / 2.0_dp) ! contact: KS
    if (linear) then
      ! pressure 0.5 at x = -10 rising to 1.5 at x = 20 ... as an intensity linear in x with
      ! zero at x = -10 and peak 1.5 at x = 20: p(x) = 1.5 (x + 10) / 30
      model%face_loads(1)%vary_coord = 1
      model%face_loads(1)%vary_csys = 2
      model%face_loads(1)%zero = -10.0_dp
      model%face_loads(1)%peak_at = 20.0_dp
      model%face_loads(1)%value = 1.5_dp
    end if
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    write (what, '(a,es8.1,a,es8.1)') 'Kn = ', kn, ', E = ', e
    g = 3
    do q = 1, size(obs%last%groups(g)%state)
      sn = obs%last%groups(g)%stress(3, q)
      tau = hypot(obs%last%groups(g)%stress(1, q), obs%last%groups(g)%stress(2, q))
      x = interface_point_x(q)
      p = 1.0_dp
      if (linear) p = 1.5_dp * (x + 10.0_dp) / 30.0_dp
      call check(error, sn, -p, trim(what) // ': sigma_n at a contact point', rel=0.01_dp)
      if (allocated(error)) return
      call check(error, tau, 0.0_dp, trim(what) // ': tau at a contact point', abs=0.01_dp * p)
      if (allocated(error)) return
    end do
  end subroutine contact_case

  !> x of interface point q (2x2 Gauss in each of the 2x2 elements of 10 mm, first direction
  !! fastest, elements numbered x fastest).
  pure real(dp) function interface_point_x(q)
    integer, intent(in) :: q
    integer :: e, g
    real(dp), parameter :: a = 1.0_dp / sqrt(3.0_dp)
    e = (q - 1) / 4 + 1
    g = mod(q - 1, 4) + 1
    interface_point_x = 10.0_dp * mod(e - 1, 2) + 5.0_dp + 5.0_dp * merge(-a, a, mod(g, 2) == 1)
  end function interface_point_x

  !> The upper block lifted 0.1 mm: every point open, zero stress, a regular system.
  subroutine test_fully_open(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: s
    call read_deck('test/data/sec2_3_4_lift.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, all(obs%last%groups(3)%state == 2), 'every interface point open')
    if (allocated(error)) return
    call check(error, maxval(abs(obs%last%groups(3)%stress)), 0.0_dp, 'zero tractions', abs=0.0_dp)
    if (allocated(error)) return
    call check(error, said(obs, 'fully open'), 'the open interface is reported')
    if (allocated(error)) return
    do s = 1, 3
      call check(error, all(obs%last%displacement(s, :) == obs%last%displacement(s, :)), 'no NaN')
      if (allocated(error)) return
    end do
    call check(error, maxval(obs%last%displacement(3, 9:16)), 0.1_dp, 'upper block lifted', rel=1.0e-9_dp)
  end subroutine test_fully_open

  !> sec2.3.4a with its 0.2 mm of sliding in one step: the closed-form return is exact for any
  !! step, so tau = 133.33 and sigma_n = -266.67 as with 100 steps (0.1%).
  subroutine test_huge_step(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: m
    integer, parameter :: methods(3) = [method_modified_euler, method_newton_raphson, method_initial_stiffness]
    do m = 1, size(methods)
      call read_deck('input/verification/sec2_3_4a.dat', model, error)
      if (allocated(error)) return
      model%stages(2)%steps = 1
      model%stages(2)%controls%method = methods(m)
      model%stages(2)%controls%max_iterations = merge(1, 50, methods(m) == method_modified_euler)
      call run_analysis(model, 'cholmod', obs, summary, error)
      if (allocated(error)) return
      call check(error, hypot(obs%last%groups(3)%stress(1, 1), obs%last%groups(3)%stress(2, 1)), &
                 100.0_dp + (1000.0_dp / 3.0_dp) * 0.1_dp, 'tau after one step', rel=1.0e-3_dp)
      if (allocated(error)) return
      call check(error, obs%last%groups(3)%stress(3, 1), -2.0_dp * (100.0_dp + (1000.0_dp / 3.0_dp) * 0.1_dp), &
                 'sigma_n after one step', rel=1.0e-3_dp)
      if (allocated(error)) return
    end do
  end subroutine test_huge_step

  !> A sideways traction beyond the friction capacity: no equilibrium exists. The run must
  !! stop with the clear message (stage, step, load factor, largest residual DOF).
  subroutine test_clear_stop(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: code
    call read_deck('test/data/block_contact.dat', model, error)
    if (allocated(error)) return
    ! pressure 1 MPa and a shear traction of 2 MPa (friction can carry tan 30 = 0.58 MPa)
    model%face_loads = [model%face_loads, model%face_loads(1)]
    model%face_loads(2)%kind = load_traction
    model%face_loads(2)%components = [2.0_dp, 0.0_dp, 0.0_dp]
    model%stages(1)%controls%max_cutbacks = 4
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (.not. allocated(error)) then
      call test_failed(error, 'an impossible load did not stop the run')
      return
    end if
    code = error%code   ! check_stop reallocates error
    call check_stop(code, err_solver, 'error category', error)
    if (allocated(error)) return
  contains
    subroutine check_stop(actual, expected, what, run_error)
      integer, intent(in) :: actual, expected
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(inout) :: run_error
      character(len=:), allocatable :: msg
      msg = run_error%message
      deallocate (run_error)
      if (actual /= expected) then
        call test_failed(run_error, what // ': ' // msg)
      else if (index(msg, 'step 1') == 0 .or. index(msg, 'load factor') == 0 .or. index(msg, 'cut-backs') == 0 &
               .or. index(msg, 'node ') == 0 .or. index(msg, 'DOF') == 0) then
        call test_failed(run_error, 'the stop message lacks step, load factor, cut-backs or DOF: ' // msg)
      end if
    end subroutine check_stop
  end subroutine test_clear_stop

  !> Two tri6 blocks pressed together through line3 interfaces: sigma_n = -p, tau = 0 at
  !! every interface point, with Gauss and with nodal integration.
  subroutine test_contact_2d(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    character(len=21), parameter :: types(2) = ['interface-line3      ', 'interface-line3-nodal']
    integer :: t, q
    do t = 1, 2
      call read_deck('test/data/contact_2d.dat', model, error)
      if (allocated(error)) return
      model%groups(3)%element_type = trim(types(t))
      call run_analysis(model, 'cholmod', obs, summary, error)
      if (allocated(error)) return
      call check(error, size(obs%last%groups(3)%stress, 1), 2, 'two interface components in 2D')
      if (allocated(error)) return
      do q = 1, size(obs%last%groups(3)%state)
        call check(error, obs%last%groups(3)%stress(2, q), -1.0_dp, trim(types(t)) // ': sigma_n', rel=1.0e-9_dp)
        if (allocated(error)) return
        call check(error, obs%last%groups(3)%stress(1, q), 0.0_dp, trim(types(t)) // ': tau', abs=1.0e-9_dp)
        if (allocated(error)) return
      end do
    end do
  end subroutine test_contact_2d

  !> The sec2.4.3 compression block driven to 100 times its yield displacement in one step:
  !! each iterative preset ends on the plateau (or stops with the clear message), never with
  !! NaN; modified Euler (one iteration, nothing to carry the residual into) must stay finite.
  subroutine test_matsuoka_huge_step(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: m
    integer, parameter :: methods(4) = [method_modified_euler, method_newton_raphson, &
                                        method_modified_newton_raphson, method_initial_stiffness]
    do m = 1, size(methods)
      call read_deck('input/verification/sec2_4_3_compression.dat', model, error)
      if (allocated(error)) return
      model%stages(1)%steps = 1
      model%stages(1)%controls%method = methods(m)
      model%stages(1)%controls%max_iterations = merge(1, 100, methods(m) == method_modified_euler)
      model%constraints(size(model%constraints))%value = -100.0_dp * 15.71_dp / 10000.0_dp * 10.0_dp
      call run_analysis(model, 'cholmod', obs, summary, error)
      if (allocated(error)) then
        ! the clear stop is acceptable; NaN never is
        if (index(error%message, 'NaN') > 0 .or. index(error%message, 'step 1') == 0) return
        deallocate (error)
        cycle
      end if
      call check(error, all(obs%last%groups(1)%stress == obs%last%groups(1)%stress), 'no NaN')
      if (allocated(error)) return
      if (methods(m) == method_modified_euler) cycle
      call check(error, maxval(abs(obs%last%groups(1)%stress(3, :) + 15.7112_dp)), 0.0_dp, &
                 'sigma_z on the plateau after one huge step', abs=0.02_dp)
      if (allocated(error)) return
    end do
  end subroutine test_matsuoka_huge_step

  !> The contact test with the upper block at E = 1e11 and the lower one at 1.44 MPa (and
  !! Kn = 8e5). The stiff block's sideways motion is held only through the soft one, so the
  !! system is singular to within double precision (pivot ratios ~1e-11, like those roundoff
  !! leaves in a truly singular model). Either it converges with the exact linear stress field
  !! (1%) and the condition estimate shows the contrast, or it stops with the clear message
  !! naming the node and DOF; never NaN.
  subroutine test_stiffness_contrast(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: q
    call read_deck('test/data/block_contact.dat', model, error)
    if (allocated(error)) return
    model%materials = [model%materials, model%materials(1)]
    model%materials(3)%name = 'stiff'
    call model%materials(1)%set('e', 1.44_dp)       ! lower block
    call model%materials(3)%set('e', 1.0e11_dp)     ! upper block
    model%groups(2)%material = 3
    call model%materials(2)%set('kn', 8.0e5_dp)
    call model%materials(2)%set('ks', 4.0e5_dp)
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) then
      if (index(error%message, 'singular at node') > 0 .and. index(error%message, 'DOF') > 0 .and. &
          index(error%message, 'double precision') > 0) deallocate (error)
      return
    end if
    do q = 1, size(obs%last%groups(3)%state)
      call check(error, obs%last%groups(3)%stress(3, q), -1.0_dp, 'sigma_n with a contrast of 7e10', rel=0.01_dp)
      if (allocated(error)) return
    end do
    call check(error, summary%max_pivot_ratio / summary%min_pivot_ratio > 1.0e9_dp, &
               'the condition estimate shows the contrast')
    if (allocated(error)) return
    call check(error, summary%condition_warning .eqv. &
               (summary%max_pivot_ratio / summary%min_pivot_ratio > 1.0e12_dp), 'warning exactly above 1e12')
  end subroutine test_stiffness_contrast

  !> Sliding through interfaces by initial stiffness: one factorization for all steps.
  subroutine test_initial_stiffness_once(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    call read_deck('input/verification/sec2_3_4a.dat', model, error)
    if (allocated(error)) return
    model%stages(1)%controls%method = method_initial_stiffness
    model%stages(2)%controls%method = method_initial_stiffness
    model%stages(2)%controls%max_iterations = 50
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%factorizations, 1, 'factorizations in 101 steps')
    if (allocated(error)) return
    call check(error, summary%iterations > summary%steps, 'it iterates instead')
    if (allocated(error)) return
    call check(error, hypot(obs%last%groups(3)%stress(1, 1), obs%last%groups(3)%stress(2, 1)), &
               100.0_dp + (1000.0_dp / 3.0_dp) * 0.1_dp, 'tau at u = 0.2', rel=1.0e-3_dp)
  end subroutine test_initial_stiffness_once

  !> A stiff interface (Ks = 400) sliding between soft blocks (G / h = 0.5), the model B FD
  !! situation: plain initial stiffness converges at about 0.999 per iteration and stops after
  !! its cut-backs; with ACCELERATION=bfgs the step converges within MAXIT = 10, and the base
  !! reactions satisfy the friction law of every sliding point summed: Rx / Rz = tan 30.
  subroutine test_bfgs_sliding(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: rx, rz
    integer :: n
    call read_deck('test/data/block_shear.dat', model, error)
    if (allocated(error)) return
    call check(error, model%stages(2)%controls%bfgs, 'ACCELERATION=bfgs read')
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%unconverged_steps, 0, 'steps left unconverged')
    if (allocated(error)) return
    call check(error, summary%cutbacks, 0, 'cut-backs')
    if (allocated(error)) return
    call check(error, all(obs%last%groups(3)%state == 1), 'every interface point slides')
    if (allocated(error)) return
    rx = 0.0_dp
    rz = 0.0_dp
    do n = 1, size(model%coords, 2)
      if (abs(model%coords(3, n)) > 1.0e-9_dp) cycle
      rx = rx + obs%last%reaction(1, n)
      rz = rz + obs%last%reaction(3, n)
    end do
    call check(error, rx / rz, tan(30.0_dp * atan(1.0_dp) / 45.0_dp), 'base Rx / Rz = tan phi', rel=1.0e-8_dp)
    if (allocated(error)) return
    ! The same step without the updates: the residual is still above DIVERGENCE after 10
    ! iterations at every cut-back, and the run stops.
    call read_deck('test/data/block_shear.dat', model, error)
    if (allocated(error)) return
    model%stages(2)%controls%bfgs = .false.
    model%stages(2)%controls%max_cutbacks = 2
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (.not. allocated(error)) then
      call test_failed(error, 'plain initial stiffness converged: the test no longer shows slow convergence')
      return
    end if
    deallocate (error)
  end subroutine test_bfgs_sliding

  !> The chapter 3 joint with a cohesionless (c = 0), dilatant (psi = phi = 20) interface,
  !! pressure and shear displacement applied together from zero (test/data/joint_c0.dat). No
  !! strength at zero load makes every step as nonlinear as the whole run; it used to stop in
  !! every method (the gap test on the trial stress made the update jump, Newton cycled).
  !! Full Newton must converge every step, in one iteration once the sliding set has settled,
  !! and since the problem is homogeneous of degree one the step 2 stresses must be half those
  !! of step 4 (1e-9); modified Euler in 40 steps must end on the same stresses (1e-6).
  subroutine test_cohesionless_from_zero(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: newton, euler
    type(analysis_summary_t) :: summary
    integer, parameter :: g = 5   ! if_up
    real(dp) :: scale
    call read_deck('test/data/joint_c0.dat', model, error)
    if (allocated(error)) return
    call check(error, trim(model%groups(g)%name) == 'if_up', 'group 5 is the upper interface')
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', newton, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks == 0 .and. summary%unconverged_steps == 0, &
               'full Newton: no cut-back, every step converged')
    if (allocated(error)) return
    call check(error, summary%iterations <= 10 + 3, 'full Newton: ' // str(summary%iterations) // &
               ' iterations in 4 steps (at most 10 in the first, then 1 each)')
    if (allocated(error)) return
    call check(error, size(newton%steps) == 4, 'four steps written')
    if (allocated(error)) return
    associate (s2 => newton%steps(2)%groups(g), s4 => newton%steps(4)%groups(g))
      call check(error, any(s4%state == state_plastic), 'points sliding')
      if (allocated(error)) return
      scale = maxval(abs(s4%stress(1:2, :)))
      call check(error, maxval(abs(2.0_dp * s2%stress(1:2, :) - s4%stress(1:2, :))) <= 1.0e-9_dp * scale, &
                 'step 2 stresses are half those of step 4')
      if (allocated(error)) return
      call read_deck('test/data/joint_c0.dat', model, error)
      if (allocated(error)) return
      model%stages(1)%steps = 40
      model%stages(1)%output_every = 40
      model%stages(1)%controls%method = method_modified_euler
      model%stages(1)%controls%max_iterations = 1
      call run_analysis(model, 'cholmod', euler, summary, error)
      if (allocated(error)) return
      call check(error, maxval(abs(euler%steps(1)%groups(g)%stress(1:2, :) - s4%stress(1:2, :))) <= 1.0e-6_dp * scale, &
                 'modified Euler, 40 steps: the same stresses')
    end associate
  end subroutine test_cohesionless_from_zero

  !> test/data/joint_psi0.dat, the cohesionless joint with psi = 0, whose sliding points have
  !! non-symmetric tangents. Full Newton factorizes the exact tangent (UMFPACK LU) and converges
  !! quadratically: at most 6 iterations in the first step, 1 in each later one (with c = 0 the
  !! solution is homogeneous in the load), to 1e-10. An independent method, the elastic
  !! stiffness with BFGS updates (MAXIT = 400; it never factorizes a tangent), reaches the same
  !! interface stresses (to 1e-5 of the largest; both converged to DELTA1). Modified
  !! Newton-Raphson factorizes the interface's symmetric stand-in and carries the run through
  !! within its DIVERGENCE without a cut-back.
  subroutine test_non_dilatant_joint(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: newton, bfgs, mnr
    integer :: k
    type(analysis_summary_t) :: summary
    integer, parameter :: g = 5   ! if_up
    real(dp) :: scale
    call read_deck('test/data/joint_psi0.dat', model, error)
    if (allocated(error)) return
    model%stages(1)%controls%delta1 = 1.0e-10_dp
    call run_analysis(model, 'cholmod', newton, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks == 0 .and. summary%unconverged_steps == 0 .and. &
               summary%iterations <= 6 + 3 .and. summary%lu_factorizations >= 1, &
               'full Newton with the LU tangent: ' // str(summary%iterations) // ' iterations, ' // &
               str(summary%lu_factorizations) // ' LU factorizations, every step converged')
    if (allocated(error)) return

    call run_elastic_bfgs('test/data/joint_psi0.dat', bfgs, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks == 0 .and. summary%unconverged_steps == 0 .and. summary%factorizations == 1, &
               'BFGS on the elastic stiffness: one factorization, every step converged')
    if (allocated(error)) return
    associate (s2 => newton%steps(2)%groups(g), s4 => newton%steps(4)%groups(g), b4 => bfgs%steps(4)%groups(g))
      call check(error, any(s4%state == state_plastic), 'points sliding')
      if (allocated(error)) return
      scale = maxval(abs(s4%stress(1:2, :)))
      call check(error, maxval(abs(2.0_dp * s2%stress(1:2, :) - s4%stress(1:2, :))) <= 1.0e-9_dp * scale, &
                 'step 2 stresses are half those of step 4')
      if (allocated(error)) return
      call check(error, maxval(abs(b4%stress(1:2, :) - s4%stress(1:2, :))) <= 1.0e-5_dp * scale, &
                 'full Newton and BFGS reach the same interface stresses')
      if (allocated(error)) return
    end associate

    ! Modified Newton-Raphson factorizes the interface's symmetric stand-in (the nearest positive
    ! semi-definite matrix without its shear-normal blocks) and iterates through without a
    ! cut-back, each step's unbalance within the method's DIVERGENCE = 1e-2, so the stresses are
    ! within 1% of full Newton's (0.35% in step 1, 3e-6 later, measured). With the nearest
    ! matrix itself it failed in step 2 and needed a cut-back to the elastic stiffness.
    call read_deck('test/data/joint_psi0.dat', model, error)
    if (allocated(error)) return
    model%stages(1)%controls%method = method_modified_newton_raphson
    call run_analysis(model, 'cholmod', mnr, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks == 0, 'modified Newton-Raphson on the interface''s stand-in: ' // &
               str(summary%cutbacks) // ' cut-backs')
    if (allocated(error)) return
    do k = 1, 4
      associate (sm => mnr%steps(k)%groups(g), sn => newton%steps(k)%groups(g))
        call check(error, maxval(abs(sm%stress(1:2, :) - sn%stress(1:2, :))) <= &
                   1.0e-2_dp * maxval(abs(sn%stress(1:2, :))), 'modified Newton-Raphson: the stresses within ' // &
                   'its carried unbalance (DIVERGENCE = 1e-2) of full Newton''s, step ' // str(k))
        if (allocated(error)) return
      end associate
    end do

  end subroutine test_non_dilatant_joint

  !> test/data/beam_tension_cap.dat: a plain-concrete cantilever pushed to 5 times its first
  !! yield in 5 steps, the top fibres near the clamp at the tensile cap. With TENSION =
  !! closest-point (a continuous stress update) full Newton converges in every step without a
  !! cut-back (at most 8 iterations a step; 34 measured), to the same stresses as the elastic
  !! stiffness with BFGS updates (1e-6 of the largest; both to DELTA1 = 1e-9), and its tip force
  !! is within 0.2% of a 50-step run's (0.12% measured). (The thesis's proportional rule, whose
  !! update jumps where sigma_1 reaches M, needs 4-5 times the iterations and a cut-back here,
  !! and its 5-step answer moves with DELTA1: docs/verification.md; the run then ends with a
  !! note naming TENSION=closest-point, which this test checks.)
  subroutine test_tension_cap_beam(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'test/data/beam_tension_cap.dat'
    type(model_t) :: model
    type(all_steps_t) :: newton, bfgs
    type(keep_last_t) :: fine
    type(analysis_summary_t) :: summary
    real(dp) :: scale, f5, f50
    character(len=:), allocatable :: msg
    call read_deck(deck, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', newton, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks == 0 .and. summary%unconverged_steps == 0 .and. summary%iterations <= 40, &
               'closest point, full Newton: every step converged without a cut-back, ' // &
               str(summary%iterations) // ' iterations')
    if (allocated(error)) return
    associate (s5 => newton%steps(size(newton%steps)))
      call check(error, count(s5%groups(1)%state == state_plastic) >= 8, 'test premise: points at the cap')
      if (allocated(error)) return
      f5 = tip_force(model, s5%reaction)
    end associate

    call run_elastic_bfgs(deck, bfgs, summary, error)
    if (allocated(error)) return
    call check(error, summary%unconverged_steps == 0 .and. summary%factorizations == 1, &
               'BFGS on the elastic stiffness: one factorization, every step converged')
    if (allocated(error)) return
    associate (sn => newton%steps(size(newton%steps))%groups(1)%stress, &
               sb => bfgs%steps(size(bfgs%steps))%groups(1)%stress)
      scale = maxval(abs(sn))
      call check(error, maxval(abs(sb - sn)), 0.0_dp, 'full Newton and BFGS reach the same stresses', &
                 abs=1.0e-6_dp * scale)
    end associate
    if (allocated(error)) return

    call read_deck(deck, model, error)
    if (allocated(error)) return
    model%stages(1)%steps = 50
    call run_analysis(model, 'cholmod', fine, summary, error)
    if (allocated(error)) return
    f50 = tip_force(model, fine%last%reaction)
    call check(error, f5, f50, 'closest point: 5 steps give the tip force of 50', rel=2.0e-3_dp)
    if (allocated(error)) return
    call check(error, .not. any(index(fine%lines, 'reached the tension zone') > 0), &
               'closest point: no note about the tension zone')
    if (allocated(error)) return

    ! The thesis's rule: the run ends, and says that points reached its discontinuous tension zone.
    call read_deck(deck, model, error)
    if (allocated(error)) return
    call model%materials(1)%set('tension', 0.0_dp, text='proportional')
    deallocate (fine%lines)
    call run_analysis(model, 'cholmod', fine, summary, error)
    if (allocated(error)) return
    call check(error, any(index(fine%lines, 'note: material concrete: points reached the tension zone') > 0), &
               'proportional: the run notes the tension zone')
    if (allocated(error)) return

    ! ... and a run that stops after its cut-backs says so in its stop message.
    call read_deck(deck, model, error)
    if (allocated(error)) return
    call model%materials(1)%set('tension', 0.0_dp, text='proportional')
    model%stages(1)%controls%max_iterations = 4
    model%stages(1)%controls%max_cutbacks = 1
    call expect_clear_stop(model, fine, 'proportional, 4 iterations, 1 cut-back: expected the clear stop', msg, error)
    if (allocated(error)) return
    call check(error, index(msg, 'does not converge after 1 cut-backs') > 0 .and. &
               index(msg, 'points reached the tension zone') > 0 .and. index(msg, 'TENSION=closest-point') > 0, &
               'the stop names the tension zone and the continuous rule: ' // msg)
  contains
    real(dp) function tip_force(model, reaction) result(f)
      type(model_t), intent(in) :: model
      real(dp), intent(in) :: reaction(:, :)
      f = sum(reaction(2, :), mask=abs(model%coords(1, :) - 200.0_dp) < 1.0e-9_dp)
    end function tip_force
  end subroutine test_tension_cap_beam

  !> test/data/friction_pull.dat (scripts/bench_calculix_friction.py's model reduced to 10 joint
  !! elements and 10 pull steps): a block pressed with N = 1000 N onto another and pulled through
  !! a cohesionless joint (phi = 30, psi = 0) from partial slip to full sliding. Full Newton
  !! without a line search cycles at the slip front (points switching between sticking and
  !! sliding) and needs cut-backs (12 measured, 719 iterations); with LINESEARCH=energy no step
  !! is cut back (83 iterations measured, 39 corrections scaled). Both end fully sliding, where
  !! the pull force is the closed form mu N = tan(30) 1000 N (1e-6; 8e-11 measured) and the
  !! state does not depend on the path: the two runs took different sub-steps through partial
  !! slip (2e-4 of max |u| apart there), a difference each sliding step shrinks five- to
  !! six-fold, to 2.3e-8 of max |u| at the last step: equal to 1e-6 of max |u|.
  subroutine test_line_search_friction(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'test/data/friction_pull.dat'
    real(dp), parameter :: mu_n = 1000.0_dp / sqrt(3.0_dp)
    type(model_t) :: model
    type(all_steps_t) :: searched, plain
    type(analysis_summary_t) :: summary
    real(dp) :: scale
    integer :: s
    call read_deck(deck, model, error)
    if (allocated(error)) return
    call check(error, model%stages(2)%controls%line_search, 'LINESEARCH=energy read')
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', searched, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks, 0, 'with the line search: cut-backs')
    if (allocated(error)) return
    call check(error, summary%unconverged_steps == 0 .and. summary%line_searches > 0 .and. &
               summary%line_search_evaluations >= summary%line_searches, 'with the line search: every step ' // &
               'converged, ' // str(summary%line_searches) // ' corrections scaled, ' // &
               str(summary%line_search_evaluations) // ' residual evaluations added')
    if (allocated(error)) return
    call check(error, pull_force(model, searched), mu_n, 'with the line search: pull force at full sliding = mu N', &
               rel=1.0e-6_dp)
    if (allocated(error)) return

    call read_deck(deck, model, error)
    if (allocated(error)) return
    do s = 1, size(model%stages)
      model%stages(s)%controls%line_search = .false.
    end do
    call run_analysis(model, 'cholmod', plain, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks > 0 .and. summary%unconverged_steps == 0 .and. summary%line_searches == 0, &
               'test premise: without the line search full Newton cycles and is cut back (' // &
               str(summary%cutbacks) // ' cut-backs)')
    if (allocated(error)) return
    call check(error, pull_force(model, plain), mu_n, 'without the line search: pull force = mu N', rel=1.0e-6_dp)
    if (allocated(error)) return
    associate (us => searched%steps(size(searched%steps))%displacement, up => plain%steps(size(plain%steps))%displacement)
      scale = maxval(abs(up))
      call check(error, maxval(abs(us - up)), 0.0_dp, 'with and without the line search: the same displacements ' // &
                 'at full sliding', abs=1.0e-6_dp * scale)
    end associate
  contains
    !> The x reaction of the pulled end face (x = 100 of the upper block, z >= 20) at the last step.
    real(dp) function pull_force(model, obs) result(f)
      type(model_t), intent(in) :: model
      type(all_steps_t), intent(in) :: obs
      f = sum(obs%steps(size(obs%steps))%reaction(1, :), mask=abs(model%coords(1, :) - 100.0_dp) < 1.0e-9_dp .and. &
              model%coords(3, :) > 20.0_dp - 1.0e-9_dp)
    end function pull_force
  end subroutine test_line_search_friction

  !> test/data/beam_tension_cap.dat (see test_tension_cap_beam) converges by full Newton with and
  !! without LINESEARCH=energy without a cut-back, so both runs take the same steps; the search
  !! scales some corrections (10 measured, 29 iterations against 34) and must reach the same
  !! solution: each run ends its steps at |R| / |P| < DELTA1 = 1e-9, so the stresses agree to
  !! 1e-8 of the largest (DELTA1 and a factor 10 for the conditioning; 1.1e-11 measured).
  subroutine test_line_search_same_solution(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'test/data/beam_tension_cap.dat'
    type(model_t) :: model
    type(all_steps_t) :: plain, searched
    type(analysis_summary_t) :: summary
    integer :: k
    call read_deck(deck, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', plain, summary, error)
    if (allocated(error)) return
    call read_deck(deck, model, error)
    if (allocated(error)) return
    model%stages(1)%controls%line_search = .true.
    call run_analysis(model, 'cholmod', searched, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks == 0 .and. summary%unconverged_steps == 0 .and. summary%line_searches > 0, &
               'test premise: the search scaled corrections (' // str(summary%line_searches) // &
               '), every step converged without a cut-back')
    if (allocated(error)) return
    call check(error, size(searched%steps), size(plain%steps), 'steps written')
    if (allocated(error)) return
    do k = 1, size(plain%steps)
      associate (sp => plain%steps(k)%groups(1)%stress, ss => searched%steps(k)%groups(1)%stress)
        call check(error, maxval(abs(ss - sp)), 0.0_dp, 'with and without the line search: the same stresses ' // &
                   'at step ' // str(plain%steps(k)%step), abs=1.0e-8_dp * maxval(abs(sp)))
      end associate
      if (allocated(error)) return
    end do
  end subroutine test_line_search_same_solution

  !> Run a model that must stop with the clear message (a solver error): `msg` gets it; the test
  !! fails with `what` if the run ended well, or with the message if it failed otherwise.
  subroutine expect_clear_stop(model, observer, what, msg, error)
    type(model_t), intent(inout) :: model
    class(observer_t), intent(inout) :: observer
    character(len=*), intent(in) :: what
    character(len=:), allocatable, intent(out) :: msg
    type(error_t), allocatable, intent(out) :: error
    type(analysis_summary_t) :: summary
    type(error_t), allocatable :: run_error
    msg = ''
    call run_analysis(model, 'cholmod', observer, summary, run_error)
    if (.not. allocated(run_error)) then
      call test_failed(error, what)
      return
    end if
    msg = run_error%message
    call check(error, run_error%code, err_solver, 'error category of "' // msg // '"')
  end subroutine expect_clear_stop

  !> Run a deck with an independent iteration: the elastic stiffness (one factorization) with
  !! BFGS updates and up to 400 iterations a step, the reference for full Newton's solutions.
  subroutine run_elastic_bfgs(path, observer, summary, error)
    character(len=*), intent(in) :: path
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    call read_deck(path, model, error)
    if (allocated(error)) return
    model%stages(1)%controls%method = method_initial_stiffness
    model%stages(1)%controls%bfgs = .true.
    model%stages(1)%controls%max_iterations = 400
    call run_analysis(model, 'cholmod', observer, summary, error)
  end subroutine run_elastic_bfgs

  !> test/data/block_pull.dat: a 3 MPa pull on an interface whose tensile strength is
  !! c / tan(phi) = 1.732 MPa. The joint opens at load factor 1.732 / 3 = 0.577 and nothing but
  !! the residual gap stiffness is left: the run must stop there (within the last cut-back,
  !! 1/1024 of the step) with the clear message, which must say that interface points opened.
  subroutine test_brittle_pull(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: obs
    character(len=:), allocatable :: msg
    real(dp) :: lf
    call read_deck('test/data/block_pull.dat', model, error)
    if (allocated(error)) return
    call expect_clear_stop(model, obs, 'a pull beyond the tensile strength did not stop the run', msg, error)
    if (allocated(error)) return
    call check(error, index(msg, 'interface points opened') > 0 .and. index(msg, 'limit point') > 0, &
               'the message says interface points opened: ' // msg)
    if (allocated(error)) return
    lf = stop_load_factor(msg)
    call check(error, lf > 1.0_dp / tan(30.0_dp * acos(-1.0_dp) / 180.0_dp) / 3.0_dp .and. &
               lf < 1.0_dp / tan(30.0_dp * acos(-1.0_dp) / 180.0_dp) / 3.0_dp + 1.0_dp / 1024.0_dp, &
               'stops just past load factor c / tan(phi) / 3 = 0.5774: ' // msg)
  end subroutine test_brittle_pull

  !> test/data/unzip.dat: a block pressed on a base (2 MPa) through 40 x 1 interface quads
  !! (tensile strength c / tan(phi) = 0.346 MPa), then bent by a moment M = 266667 N mm about
  !! x = 100. Where the first point opens (load factor 1.55-1.60) the opening spreads at that
  !! load: full Newton with MAXIT=200 must converge every step, and its interface stresses must
  !! balance the load (sum of sigma_n dA = -N = -4000 N, of sigma_n (x - 100) dA = -M, 1e-5),
  !! the open points must lie on the tension side of every closed one, and 4 steps must end
  !! where 20 do (1e-5 of the peak stress: the unzipping is monotonic). With MAXIT=3 the run
  !! must stop in that load window and say that more iterations may follow the opening.
  subroutine test_unzipping_cascade(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: four, twenty
    type(keep_last_t) :: stopped
    type(analysis_summary_t) :: summary
    real(dp), parameter :: m_applied = 0.4_dp * 100.0_dp**3 / 3.0_dp * 2.0_dp, n_applied = 4000.0_dp
    real(dp) :: s(2, 4), w(4), x, fz, my, xopen, xclosed, lf, peak
    character(len=:), allocatable :: msg
    integer :: g, e, k
    call square_rule(2, s, w)
    call read_deck('test/data/unzip.dat', model, error)
    if (allocated(error)) return
    g = 3
    call check(error, trim(model%groups(g)%name) == 'joint', 'group 3 is the joint')
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', four, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks == 0 .and. summary%unconverged_steps == 0, &
               'MAXIT=200: every step converged without a cut-back')
    if (allocated(error)) return
    associate (last => four%steps(size(four%steps))%groups(g))
      fz = 0.0_dp
      my = 0.0_dp
      xopen = -huge(1.0_dp)
      xclosed = huge(1.0_dp)
      do e = 1, size(model%groups(g)%connectivity, 2)
        do k = 1, 4
          ! 5 x 10 mm quads along x: the point's x from its natural coordinate, weight 50 / 4.
          x = model%coords(1, model%groups(g)%connectivity(1, e)) + 2.5_dp * (1.0_dp + s(1, k))
          associate (p => 4 * (e - 1) + k)
            fz = fz + 12.5_dp * last%stress(3, p)
            my = my + 12.5_dp * last%stress(3, p) * (x - 100.0_dp)
            if (last%state(p) == state_open) then
              xopen = max(xopen, x)
            else
              xclosed = min(xclosed, x)
            end if
          end associate
        end do
      end do
      call check(error, abs(fz + n_applied) <= 1.0e-5_dp * n_applied, 'sum of sigma_n dA = ' // str(fz))
      if (allocated(error)) return
      call check(error, abs(my + m_applied) <= 1.0e-5_dp * m_applied, 'moment of sigma_n = ' // str(my))
      if (allocated(error)) return
      call check(error, xopen > 50.0_dp .and. xopen < xclosed, 'open up to x = ' // str(xopen) // &
                 ', in contact from x = ' // str(xclosed))
      if (allocated(error)) return
      call read_deck('test/data/unzip.dat', model, error)
      if (allocated(error)) return
      model%stages(2)%steps = 20
      call run_analysis(model, 'cholmod', twenty, summary, error)
      if (allocated(error)) return
      peak = maxval(abs(last%stress(3, :)))
      call check(error, maxval(abs(twenty%steps(size(twenty%steps))%groups(g)%stress(3, :) - last%stress(3, :))) &
                 <= 1.0e-5_dp * peak, '20 steps end where 4 do')
      if (allocated(error)) return
    end associate
    call read_deck('test/data/unzip.dat', model, error)
    if (allocated(error)) return
    model%stages(2)%controls%max_iterations = 3
    call expect_clear_stop(model, stopped, 'MAXIT=3 followed the unzipping: the test no longer needs the ' // &
                           'iterations', msg, error)
    if (allocated(error)) return
    call check(error, index(msg, 'interface points opened') > 0 .and. index(msg, 'MAXIT=') > 0, &
               'the message suggests more iterations: ' // msg)
    if (allocated(error)) return
    lf = stop_load_factor(msg)
    call check(error, lf > 1.55_dp .and. lf < 1.6_dp, 'stops where the first point opens: ' // msg)
  end subroutine test_unzipping_cascade

  !> test/data/band_birth_yielded.dat: a 6 MPa band pressure yields the pipe end (stage 1), then
  !! the band is born and 1/400 of the end load applied in one step. Modified Newton-Raphson
  !! refactorizes at the birth with the committed tangent, too soft for the yielded points that
  !! now unload, and used to stop after ten cut-backs with the same residual each time. Its
  !! cut-back now retries with the elastic stiffness: the run must end, and agree with full
  !! Newton (every step converged) within the unbalance that modified Newton-Raphson carries
  !! from stage 1 (up to 2e-4 of the load): displacements within 1e-3 of the largest, every
  !! stress component within 0.01 MPa of stresses up to 16 MPa (1.7e-5 and 0.0014 MPa measured).
  subroutine test_birth_on_yielded(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(keep_last_t) :: mnr, newton
    type(analysis_summary_t) :: summary
    call read_deck('test/data/band_birth_yielded.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', mnr, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks >= 1, 'the birth step still fails once with the committed tangent (' // &
               str(summary%cutbacks) // ' cut-backs): the test shows the retry')
    if (allocated(error)) return
    call read_deck('test/data/band_birth_yielded.dat', model, error)
    if (allocated(error)) return
    model%stages(:)%controls%method = method_full_newton_raphson
    model%stages(:)%controls%max_iterations = 50
    call run_analysis(model, 'cholmod', newton, summary, error)
    if (allocated(error)) return
    call check(error, summary%unconverged_steps == 0, 'full Newton: every step converged')
    if (allocated(error)) return
    call check(error, maxval(abs(mnr%last%displacement - newton%last%displacement)) <= &
               1.0e-3_dp * maxval(abs(newton%last%displacement)), 'displacements as full Newton''s')
    if (allocated(error)) return
    call check(error, maxval(abs(mnr%last%groups(1)%stress - newton%last%groups(1)%stress)) <= 0.01_dp, &
               'the concrete''s stresses as full Newton''s')
  end subroutine test_birth_on_yielded

end module test_nonlinear
