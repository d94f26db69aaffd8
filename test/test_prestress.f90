!> Prestressed bars (PRESTRESS, group, FORCE= | STRESS=): the prestress is added to the bars'
!! axial force in equal parts over the stage's steps, and the bars stay bonded afterwards.
!! Checked against closed forms: springs in series on the linear path (bars only); tendons born
!! in the stage that prestresses them on a Matsuoka-Nakai block, elastic under every solution
!! method and flowing at its compressive plateau through cut-backs; a band of hoop rings on a
!! Lame cylinder. Also: the deck's records, and forces near huge() stopping clearly.
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
      new_unittest("forces_near_huge_stop_clearly", test_overflow, nonfinite=.true.), &
      new_unittest("band_on_a_lame_cylinder", test_ring), &
      new_unittest("tendons_against_a_block_at_its_plateau", test_plateau), &
      new_unittest("post_tensioned_tendons_every_method", test_post), &
      new_unittest("post_tensioned_tendon_in_series_with_a_spring", test_series_post) &
      ]
  end subroutine collect_prestress

  !> Every stage of `model` solved by `method`, with the iterations the presets allow it
  !! (one for the Euler methods, 50 for the others).
  subroutine use_method(model, method)
    type(model_t), intent(inout) :: model
    integer, intent(in) :: method
    model%stages(:)%controls%method = method
    model%stages(:)%controls%max_iterations = merge(1, 50, method == method_euler .or. &
                                                           method == method_modified_euler)
  end subroutine use_method

  !> Tendon k1 = 100 N/mm prestressed by N0 = 90 N in series with a spring k2 = 200 N/mm
  !! between fixed ends (test/data/prestress_series.dat): u2 = -N0 / (k1 + k2) = -0.3 and
  !! N = N0 k2 / (k1 + k2) = 60 N in both, the reactions -60 and +60, reached in equal thirds
  !! over stage 1's three steps (OUTPUT=1: the linear path writes each, k/3 of its one solve).
  !! Then F = 30 N on the middle node: du = 0.1, tendon 60 + k1 du = 70 N, spring 60 - k2 du = 40 N.
  subroutine test_series(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    character(len=:), allocatable :: what
    real(dp) :: t
    integer :: k
    call read_deck('test/data/prestress_series.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%linear, 'bars only: the linear path')
    if (allocated(error)) return
    call check(error, size(obs%steps), 4, 'every step of stage 1 (OUTPUT=1) and the end of stage 2')
    if (allocated(error)) return
    do k = 1, 3
      t = k / 3.0_dp
      what = 'stage 1, step ' // achar(iachar('0') + k) // ' of 3: '
      call check(error, obs%steps(k)%step, k, what // 'step number')
      if (allocated(error)) return
      call check(error, obs%steps(k)%load_factor, t, what // 'load factor k / 3', rel=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%displacement(1, 2), -0.3_dp * t, what // 'u2 = -(k/3) N0 / (k1 + k2)', &
                 rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%groups(1)%stress(1, 1), 60.0_dp * t, what // 'tendon (k/3) N0 k2 / (k1 + k2)', &
                 rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%groups(2)%stress(1, 1), 60.0_dp * t, what // 'spring (k/3) N0 k2 / (k1 + k2)', &
                 rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%reaction(1, 1), -60.0_dp * t, what // 'reaction at the tendon end', &
                 rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%reaction(1, 3), 60.0_dp * t, what // 'reaction at the spring end', &
                 rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%residual, 0.0_dp, what // 'in balance', abs=1.0e-12_dp)
      if (allocated(error)) return
    end do
    call check(error, obs%steps(4)%step, 4, 'stage 2: step number')
    if (allocated(error)) return
    call check(error, obs%steps(4)%load_factor, 2.0_dp, 'stage 2: load factor', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, obs%steps(4)%displacement(1, 2), -0.2_dp, 'stage 2: u2 + F / (k1 + k2)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(4)%groups(1)%stress(1, 1), 70.0_dp, 'stage 2: the bonded tendon gains k1 du', &
               rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(4)%groups(2)%stress(1, 1), 40.0_dp, 'stage 2: the spring loses k2 du', &
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
      call use_method(model, methods(m))
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
    if (allocated(error)) return
    ! records on one group add up: the reference share plus a stage's own
    model%prestresses = [model%prestresses, model%prestresses(1)]
    model%prestresses(2)%stage = 1
    model%prestresses(2)%force = -4.0_dp
    f = model%stage_prestress(1)
    call check(error, f(2), 2.5_dp - 4.0_dp, 'two records on one group add up', rel=1.0e-14_dp)
    if (allocated(error)) return
    f = model%stage_prestress(2)
    call check(error, f(2), 10.0_dp * model%stages(2)%load_fraction, 'stage 2: only the reference share', &
               abs=1.0e-14_dp)
  end subroutine test_deck

  !> Two prestressed hoop rings of bar2 chords (E A = 8e6 N, N0 = 1e5 N each) on the outer
  !! nodes of a plane-strain Lame cylinder (test/data/prestress_ring.dat, a = 600, b = 715,
  !! h = 25, 8 x 11.25 deg). (1) A polygon ring in tension N pulls each node in by
  !! 2 N sin(dtheta / 2), which is exactly the nodal load of a pressure p0 = 2 N0 / (b h
  !! cos(dtheta / 2)) on the hex8 faces: the same mesh with stress-free bars and p0 must move
  !! identically (1e-10), its bars carrying N - N0. (2) Lame: u_r(b) = -C p with
  !! C = b (1 + nu) ((1 - 2 nu) b^2 + a^2) / (E (b^2 - a^2)), and the ring's compatibility
  !! N = N0 + E A u_r(b) / b give N = N0 / (1 + 2 E A C / (b^2 h cos(dtheta / 2))); 4 hex8
  !! through the wall are 0.2% stiffer than Lame (u_r 0.18% low), so the loss of force N0 - N
  !! and u_r(b) are checked within 0.5%.
  subroutine test_ring(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: a = 600.0_dp, b = 715.0_dp, e = 40000.0_dp, nu = 0.2_dp, h = 25.0_dp, &
                           ea = 8.0e6_dp, n0 = 1.0e5_dp, dtheta = 11.25_dp * acos(-1.0_dp) / 180.0_dp
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs_ps, obs_p
    real(dp) :: c, n_closed, ur_closed, r, ur
    integer :: n, q, nouter
    call read_deck('test/data/prestress_ring.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs_ps, summary, error)
    if (allocated(error)) return
    ! the same mesh: stress-free bars and the equivalent pressure
    call read_deck('test/data/prestress_ring.dat', model, error)
    if (allocated(error)) return
    model%prestresses(1)%force = 0.0_dp
    model%face_loads(1)%value = 2.0_dp * n0 / (b * h * cos(dtheta / 2.0_dp))
    call run_analysis(model, 'cholmod', obs_p, summary, error)
    if (allocated(error)) return
    associate (u_ps => obs_ps%steps(1)%displacement, u_p => obs_p%steps(1)%displacement, &
               bar_ps => obs_ps%steps(1)%groups(2)%stress, bar_p => obs_p%steps(1)%groups(2)%stress)
      call check(error, maxval(abs(u_ps - u_p)), 0.0_dp, 'prestressed rings = their equivalent pressure', &
                 abs=1.0e-10_dp * maxval(abs(u_p)))
      if (allocated(error)) return
      do q = 1, size(bar_ps, 2)
        call check(error, bar_ps(1, q) - n0, bar_p(1, q), 'bar force: N0 + that of the pressure', &
                   rel=1.0e-9_dp)
        if (allocated(error)) return
      end do
      c = b * (1.0_dp + nu) * ((1.0_dp - 2.0_dp * nu) * b**2 + a**2) / (e * (b**2 - a**2))
      n_closed = n0 / (1.0_dp + 2.0_dp * ea * c / (b**2 * h * cos(dtheta / 2.0_dp)))
      ur_closed = -c * 2.0_dp * n_closed / (b * h * cos(dtheta / 2.0_dp))
      do q = 1, size(bar_ps, 2)
        call check(error, n0 - bar_ps(1, q), n0 - n_closed, 'loss of force against Lame', rel=5.0e-3_dp)
        if (allocated(error)) return
      end do
      nouter = 0
      do n = 1, size(u_ps, 2)
        r = hypot(model%coords(1, n), model%coords(2, n))
        if (abs(r - b) > 1.0e-6_dp) cycle
        nouter = nouter + 1
        ur = (u_ps(1, n) * model%coords(1, n) + u_ps(2, n) * model%coords(2, n)) / r
        call check(error, ur, ur_closed, 'u_r(b) against Lame', rel=5.0e-3_dp)
        if (allocated(error)) return
      end do
      call check(error, nouter, 18, 'outer nodes checked')
    end associate
  end subroutine test_ring

  !> The block of test_block with 50 times the prestress (STRESS = 5000: N0 = 500 N per
  !! tendon): the concrete reaches its uniaxial compressive strength fc = 2 M sin(phi) /
  !! (1 - sin(phi)) = 15 MPa (M = ft / 2 (1 + 1 / sin(phi)) = 7.5, phi = 30) and flows at that
  !! plateau until the tendons, losing k_t = 20 N/mm each as it shortens, are in equilibrium
  !! with it: 4 N + p1 A = fc A gives N = 350 N, and the face moves by -p1 L / E - (N0 - N) / k_t
  !! = -7.51 mm. Steps cut back while the block flows, so this also checks that the prestress
  !! follows the cut-backs' fractions of a step.
  subroutine test_plateau(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: sin_phi = 0.5_dp, ft = 5.0_dp
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    real(dp) :: fc
    integer :: last, q
    call read_deck('test/data/prestress_block.dat', model, error)
    if (allocated(error)) return
    model%prestresses(1)%force = 500.0_dp
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%cutbacks > 0, 'the flow makes steps cut back')
    if (allocated(error)) return
    fc = 2.0_dp * (ft / 2.0_dp * (1.0_dp + 1.0_dp / sin_phi)) * sin_phi / (1.0_dp - sin_phi)
    last = size(obs%steps)
    do q = 1, size(obs%steps(last)%groups(1)%stress, 2)
      call check(error, obs%steps(last)%groups(1)%stress(1, q), -fc, 'block sxx at the plateau -fc', rel=1.0e-6_dp)
      if (allocated(error)) return
    end do
    do q = 1, size(obs%steps(last)%groups(2)%stress, 2)
      call check(error, obs%steps(last)%groups(2)%stress(1, q), (fc - 1.0_dp) * 100.0_dp / 4.0_dp, &
                 'tendon force (fc - p1) A / 4', rel=1.0e-6_dp)
      if (allocated(error)) return
    end do
    call check(error, obs%steps(last)%displacement(1, 2), -0.01_dp - (500.0_dp - 350.0_dp) / 20.0_dp, &
               'loaded face ux', rel=1.0e-6_dp)
  end subroutine test_plateau

  !> test/data/prestress_post.dat: the block's tendons post-tensioned (BOND=after) to N0 = 10 N
  !! in stage 2, bonded from stage 3. Stage 2, step k of 5: the tendons are not bonded, carry
  !! nothing themselves and pull the faces together with k / 5 of 4 N0: sxx = -1 - 4 (k / 5) N0 /
  !! A_b, ux = sxx L / E. Stage 3, p3 = 2 MPa more, shared with the now bonded tendons: du = -p3 A_b
  !! / (k_b + 4 k_t), each tendon N0 + k_t du, sxx = -1.4 - p3 k_b / (k_b + 4 k_t). Every method.
  subroutine test_post(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: methods(6) = [method_euler, method_modified_euler, method_newton_raphson, &
                                        method_modified_newton_raphson, method_initial_stiffness, &
                                        method_full_newton_raphson]
    real(dp), parameter :: kb = 10000.0_dp, kt = 20.0_dp, n0 = 10.0_dp, p3 = 2.0_dp
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    real(dp) :: sxx, du
    integer :: m, k, q, last
    character(len=:), allocatable :: what
    do m = 1, size(methods)
      call read_deck('test/data/prestress_post.dat', model, error)
      if (allocated(error)) return
      call check(error, model%groups(2)%activate_stage, 3, 'BOND=after in stage 2: the tendons are born in stage 3')
      if (allocated(error)) return
      call use_method(model, methods(m))
      if (allocated(obs%steps)) deallocate (obs%steps)
      call run_analysis(model, 'cholmod', obs, summary, error)
      if (allocated(error)) return
      what = trim(method_names(methods(m))) // ': '
      call check(error, size(obs%steps), 7, what // 'stage 1, every step of stage 2, stage 3')
      if (allocated(error)) return
      do k = 1, 5
        sxx = -1.0_dp - 4.0_dp * (k / 5.0_dp) * n0 / 100.0_dp
        call check(error, maxval(abs(obs%steps(k + 1)%groups(2)%stress)), 0.0_dp, &
                   what // 'unbonded tendons carry nothing themselves', abs=1.0e-12_dp)
        if (allocated(error)) return
        do q = 1, size(obs%steps(k + 1)%groups(1)%stress, 2)
          call check(error, obs%steps(k + 1)%groups(1)%stress(1, q), sxx, what // 'stage 2: sxx', rel=1.0e-9_dp)
          if (allocated(error)) return
        end do
        call check(error, obs%steps(k + 1)%displacement(1, 2), sxx * 10.0_dp / 1000.0_dp, what // 'stage 2: ux', &
                   rel=1.0e-9_dp)
        if (allocated(error)) return
      end do
      last = size(obs%steps)
      du = -p3 * 100.0_dp / (kb + 4.0_dp * kt)
      do q = 1, size(obs%steps(last)%groups(2)%stress, 2)
        call check(error, obs%steps(last)%groups(2)%stress(1, q), n0 + kt * du, &
                   what // 'stage 3: bonded tendons N0 + k_t du', rel=1.0e-9_dp)
        if (allocated(error)) return
      end do
      do q = 1, size(obs%steps(last)%groups(1)%stress, 2)
        call check(error, obs%steps(last)%groups(1)%stress(1, q), -1.4_dp - p3 * kb / (kb + 4.0_dp * kt), &
                   what // 'stage 3: sxx', rel=1.0e-9_dp)
        if (allocated(error)) return
      end do
      call check(error, obs%steps(last)%displacement(1, 2), -0.014_dp + du, what // 'stage 3: ux', rel=1.0e-9_dp)
      if (allocated(error)) return
    end do
  end subroutine test_post

  !> test/data/prestress_series_post.dat (the linear path): stage 1, the unbonded tendon's 90 N
  !! held by the spring alone, in thirds over its three steps (OUTPUT=1): u2 = -(k/3) 90 / k2,
  !! -0.45 at its end; stage 2, bonded carrying 90 N, F = 30 N: u2 = -0.35, tendon 100 N,
  !! spring 70 N (pretensioned, test_series: 60, 70 and 40 N).
  subroutine test_series_post(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    character(len=:), allocatable :: what
    real(dp) :: t
    integer :: k
    call read_deck('test/data/prestress_series_post.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%linear, 'bars only: the linear path')
    if (allocated(error)) return
    call check(error, size(obs%steps), 4, 'every step of stage 1 (OUTPUT=1) and the end of stage 2')
    if (allocated(error)) return
    do k = 1, 3
      t = k / 3.0_dp
      what = 'stage 1, step ' // achar(iachar('0') + k) // ' of 3: '
      call check(error, obs%steps(k)%displacement(1, 2), -0.45_dp * t, what // 'u2 = -(k/3) N0 / k2', &
                 rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%groups(1)%stress(1, 1), 0.0_dp, what // 'the unbonded tendon is not a bar yet')
      if (allocated(error)) return
      call check(error, obs%steps(k)%groups(2)%stress(1, 1), 90.0_dp * t, what // 'spring (k/3) N0', rel=1.0e-12_dp)
      if (allocated(error)) return
    end do
    call check(error, obs%steps(4)%displacement(1, 2), -0.35_dp, 'stage 2: u2 + F / (k1 + k2)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(4)%groups(1)%stress(1, 1), 100.0_dp, 'stage 2: tendon N0 + k1 du', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(4)%groups(2)%stress(1, 1), 70.0_dp, 'stage 2: spring N0 - k2 du', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, obs%steps(4)%reaction(1, 1), -100.0_dp, 'stage 2: the tendon''s anchor reaction', &
               rel=1.0e-12_dp)
  end subroutine test_series_post

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
