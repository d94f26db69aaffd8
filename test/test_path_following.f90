!> Path following (issue 27, STAGE PATH=): arc-length and displacement control against closed
!! forms. A block on a Mohr-Coulomb interface (test/data/block_arc.dat, block_displacement.dat)
!! pushed past its capacity (c + sigma_n tan phi) A = 250.940108 N: load control stops at that
!! limit load (test_collapse); both paths go through it and along the plateau beyond. A linear
!! bar (test/data/path_bar.dat) gives the load factor read back and the arc's steps exactly. A
!! softening bar of cracking concrete (test/data/crack_bar_arc.dat) under a force: arc-length
!! follows its falling branch, F = A f_t (uu - u) / (uu - u0), where load control must stop. A
!! column of ten cubes, one weaker (test/data/snap_back_bar.dat), snaps back; displacement control
!! of the crack's opening (NSET= less FROM=) follows it on its closed form.
module test_path_following
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  implicit none
  private

  public :: collect_path_following

  !> The block's capacity: c A + tan(phi) N with c = 0.05, A = 400 mm^2, N = 400 N, phi = 30 deg.
  real(dp), parameter :: capacity = 0.05_dp * 400.0_dp + 400.0_dp * 0.57735026918962576_dp
  real(dp), parameter :: push = 360.0_dp       !! the stage's load: 9 nodes x 40 N

contains

  subroutine collect_path_following(testsuite)
    type(unittest_t), allocatable, intent(out) :: testsuite(:)
    testsuite = [ &
      new_unittest('arc-length: the block''s peak is (c + sigma_n tan phi) A to 1e-6, then a plateau', &
                   test_arc_peak), &
      new_unittest('displacement control: the set follows VALUE, the load read back reaches the capacity', &
                   test_displacement_peak), &
      new_unittest('linear bar: load factor read back k u / F; arc-length in equal steps to the full load', &
                   test_bar), &
      new_unittest('softening bar: arc-length through the peak and down the closed-form softening line', &
                   test_softening_bar), &
      new_unittest('snap-back: the crack''s opening (NSET less FROM) followed, the top back on the closed form', &
                   test_snap_back), &
      new_unittest('softening bar: the tangent''s determinant positive up to the peak, negative past it', &
                   test_softening_bar_stability) &
      ]
  end subroutine collect_path_following

  !> Run deck `deck`, keeping every step written (CHOLMOD, or the solver named).
  subroutine run_deck(deck, model, obs, summary, error, solver)
    character(len=*), intent(in) :: deck
    type(model_t), intent(out) :: model
    type(all_steps_t), intent(out) :: obs
    type(analysis_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: solver
    call read_deck(deck, model, error)
    if (allocated(error)) return
    if (present(solver)) then
      call run_analysis(model, solver, obs, summary, error)
    else
      call run_analysis(model, 'cholmod', obs, summary, error)
    end if
  end subroutine run_deck

  !> The mean displacement in direction `dof` (1..3) of node set `name` at step i of obs.
  real(dp) function mean_u(model, obs, name, i, dof)
    type(model_t), intent(in) :: model
    type(all_steps_t), intent(in) :: obs
    character(len=*), intent(in) :: name
    integer, intent(in) :: i, dof
    associate (nodes => model%node_sets(model%find_node_set(name))%nodes)
      mean_u = sum(obs%steps(i)%displacement(dof, nodes)) / size(nodes)
    end associate
  end function mean_u

  !> The block under PATH=ARC-LENGTH: the largest load of the path is the capacity to 1e-6;
  !! at least 10 steps lie on the plateau (the load within 1e-6 of it) with the block sliding
  !! further at each; the load applied equals the load factor times the stage's load, and the
  !! reactions balance it.
  subroutine test_arc_peak(error)
    type(error_t), allocatable, intent(out) :: error
    call check_peak('test/data/block_arc.dat', 30, error)
  end subroutine test_arc_peak

  !> The block under PATH=DISPLACEMENT (0.5 mm in 20 steps): the set's mean displacement is
  !! k / 20 of 0.5 at step k, and the load read back reaches the capacity to 1e-6 and stays.
  subroutine test_displacement_peak(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: k
    call check_peak('test/data/block_displacement.dat', 20, error)
    if (allocated(error)) return
    call run_deck('test/data/block_displacement.dat', model, obs, summary, error)
    if (allocated(error)) return
    do k = 1, 20
      call check(error, mean_u(model, obs, 'push', k + 1, 1), 0.5_dp * k / 20, 'the set''s mean ux at step ' // &
                 str(k), abs=1.0e-9_dp)
      if (allocated(error)) return
    end do
  end subroutine test_displacement_peak

  !> The checks of the block's path common to both controls (`n` steps in stage 2).
  subroutine check_peak(deck, n, error)
    character(len=*), intent(in) :: deck
    integer, intent(in) :: n
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: lam(n), peak, ux_prev
    integer :: k, on_plateau
    call run_deck(deck, model, obs, summary, error)
    if (allocated(error)) return
    call check(error, size(obs%steps), n + 1, deck // ': every step written')
    if (allocated(error)) return
    do k = 1, n
      lam(k) = obs%steps(k + 1)%load_factor - 1.0_dp
      associate (st => obs%steps(k + 1))
        call check(error, sum(st%applied_force(1, :)), lam(k) * push, deck // ': the load applied is the ' // &
                   'load factor times the stage''s load, step ' // str(k), rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, sum(st%reaction(1, :)), -lam(k) * push, deck // ': the reactions balance it, step ' // &
                   str(k), rel=1.0e-8_dp)
        if (allocated(error)) return
      end associate
    end do
    peak = maxval(lam) * push
    call check(error, peak, capacity, deck // ': the peak load is (c + sigma_n tan phi) A', rel=1.0e-6_dp)
    if (allocated(error)) return
    on_plateau = 0
    ux_prev = -huge(1.0_dp)
    do k = 1, n
      if (abs(lam(k) * push - capacity) > 1.0e-6_dp * capacity) cycle
      on_plateau = on_plateau + 1
      if (.not. mean_u(model, obs, 'push', k + 1, 1) > ux_prev) then
        call test_failed(error, deck // ': on the plateau the block slides further at each step (step ' // &
                         str(k) // ')')
        return
      end if
      ux_prev = mean_u(model, obs, 'push', k + 1, 1)
    end do
    call check(error, on_plateau >= 10, deck // ': at least 10 steps on the plateau, got ' // str(on_plateau))
  end subroutine check_peak

  !> test/data/path_bar.dat: displacement control reads back the load factor 2 u (k = 100 N/mm,
  !! F = 50 N) at u = 0.25, 0.5, 0.75, 1; the arc-length stage takes ten steps of 0.1 of its
  !! load (a linear path: every arc the same) and ends on its full load at u = -2 mm.
  subroutine test_bar(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: k
    call run_deck('test/data/path_bar.dat', model, obs, summary, error)
    if (allocated(error)) return
    call check(error, size(obs%steps), 14, 'every step written')
    if (allocated(error)) return
    do k = 1, 4
      call check(error, obs%steps(k)%displacement(1, 2), 0.25_dp * k, 'u at step ' // str(k), abs=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, obs%steps(k)%load_factor, 2.0_dp * 0.25_dp * k, 'the load factor read back k u / F, ' // &
                 'step ' // str(k), rel=1.0e-12_dp)
      if (allocated(error)) return
    end do
    do k = 1, 10
      call check(error, obs%steps(4 + k)%load_factor, 1.0_dp + 0.1_dp * k, 'arc-length: step ' // str(k) // &
                 ' is 0.1 of the load', rel=1.0e-12_dp)
      if (allocated(error)) return
    end do
    call check(error, obs%steps(14)%displacement(1, 2), -2.0_dp, 'u at the end, (100 - 300) / k', rel=1.0e-12_dp)
  end subroutine test_bar

  !> test/data/crack_bar_arc.dat: every step's (u, F) on the closed form, the elastic line up to
  !! the peak A f_t and the linear softening line beyond it (to 1e-9 of the peak), most steps past
  !! the peak, and the load falling.
  subroutine test_softening_bar(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, area = 1.0e4_dp, length = 100.0_dp, ft = 2.97_dp, gf = 0.1_dp, &
                           reference = 4.0_dp * 10000.0_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: u0, uu, u, force, expected, worst
    integer :: i, past
    call run_deck('test/data/crack_bar_arc.dat', model, obs, summary, error)
    if (allocated(error)) return
    u0 = ft * length / e
    uu = 2.0_dp * gf / ft
    worst = 0.0_dp
    past = 0
    associate (nodes => model%node_sets(model%find_node_set('top'))%nodes)
      do i = 1, size(obs%steps)
        u = sum(obs%steps(i)%displacement(3, nodes)) / size(nodes)
        force = obs%steps(i)%load_factor * reference
        if (u <= u0) then
          expected = e * area * u / length
        else
          expected = area * ft * (uu - u) / (uu - u0)
          past = past + 1
        end if
        worst = max(worst, abs(force - expected) / (area * ft))
      end do
    end associate
    call check(error, worst, 0.0_dp, 'every step on the closed-form path', abs=1.0e-9_dp)
    if (allocated(error)) return
    call check(error, past >= 20, 'at least 20 steps down the softening branch (' // str(past) // ')')
    if (allocated(error)) return
    call check(error, obs%steps(size(obs%steps))%load_factor * reference < 0.2_dp * area * ft, &
               'the load falls below a fifth of the peak')
  end subroutine test_softening_bar

  !> test/data/crack_bar_arc.dat with the skyline solver, whose LDL^T factorizes the indefinite
  !! tangent of the softening band (CHOLMOD's LL^T refuses it, and the path then takes the
  !! elastic stiffness, whose sign says nothing). While the bar is elastic (u < u0) the tangent
  !! is positive definite: every step's `tangent_sign` +1. Past the peak the load falls as u
  !! grows, so the stretching mode's stiffness, E_t A / L with E_t = -f_t / (eps_u - eps_0), is
  !! negative; the other modes of the cube shear it, and keep a positive stiffness while the
  !! damaged shear modulus (1 - d) G = f_t (eps_u - eps) / (2 (eps_u - eps_0) eps) (nu = 0)
  !! exceeds |E_t|, that is up to eps = eps_u / 3: there exactly one eigenvalue is negative, and
  !! `tangent_sign` is -1. (Further down, more of the cube's modes soften and the parity may
  !! change: feps writes the sign, not the count.) The same bar at nu = 0.2
  !! (crack_bar_arc_nu.dat) has a non-symmetric softening tangent, factorized by UMFPACK's LU.
  subroutine test_softening_bar_stability(error)
    type(error_t), allocatable, intent(out) :: error
    call check_bar_signs('test/data/crack_bar_arc.dat', 'skyline', 0.0_dp, error)
    if (allocated(error)) return
    call check_bar_signs('test/data/crack_bar_arc_nu.dat', 'cholmod', 0.2_dp, error)
  end subroutine test_softening_bar_stability

  !> One softening bar's signs (test_softening_bar_stability) with `solver`: the damaged shear
  !! modulus (1 - d) E / (2 (1 + nu)) exceeds |E_t| up to eps = eps_u / (2 (1 + nu) + 1).
  subroutine check_bar_signs(deck, solver, nu, error)
    character(len=*), intent(in) :: deck, solver
    real(dp), intent(in) :: nu
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, length = 100.0_dp, ft = 2.97_dp, gf = 0.1_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: u0, uu, u
    integer :: i, before, past
    call run_deck(deck, model, obs, summary, error, solver=solver)
    if (allocated(error)) return
    u0 = ft * length / e
    uu = 2.0_dp * gf / ft
    before = 0
    past = 0
    associate (nodes => model%node_sets(model%find_node_set('top'))%nodes)
      do i = 1, size(obs%steps)
        u = sum(obs%steps(i)%displacement(3, nodes)) / size(nodes)
        if (u < 0.999_dp * u0) then
          call check(error, obs%steps(i)%tangent_sign, 1, deck // ' step ' // str(i) // ' (elastic, u = ' // &
                     str(u) // '): the tangent''s determinant positive')
          before = before + 1
        else if (u > 1.001_dp * u0 .and. u < uu / (2.0_dp * (1.0_dp + nu) + 1.0_dp)) then
          call check(error, obs%steps(i)%tangent_sign, -1, deck // ' step ' // str(i) // ' (softening, u = ' // &
                     str(u) // '): one negative eigenvalue, the determinant negative')
          past = past + 1
        end if
        if (allocated(error)) return
      end do
    end associate
    call check(error, before >= 3 .and. past >= 4, deck // ': steps on both sides of the peak (' // str(before) // &
               ', ' // str(past) // ')')
    if (allocated(error) .or. nu == 0.0_dp) return
    call check(error, summary%lu_factorizations > 0, deck // ': the non-symmetric tangent factorized by LU')
  end subroutine check_bar_signs

  !> test/data/snap_back_bar.dat: the column's top displacement u at every step on the closed
  !! form against the load (to 1e-9 of the peak's u, L f_t / E), the crack's opening at each step
  !! VALUE / STEPS more than at the last (to 1e-12), at least 80 steps in which the top moves back
  !! (the snap-back), and the load down to a quarter of the peak.
  subroutine test_snap_back(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, area = 1.0e4_dp, length = 1000.0_dp, h = 100.0_dp, ft = 2.7_dp, &
                           gf = 0.1_dp, reference = 4.0_dp * 10000.0_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: e0, eu, s, u, w, u_last, expected, worst, worst_w
    integer :: i, back
    call run_deck('test/data/snap_back_bar.dat', model, obs, summary, error)
    if (allocated(error)) return
    e0 = ft / e
    eu = 2.0_dp * gf / (ft * h)
    worst = 0.0_dp
    worst_w = 0.0_dp
    back = 0
    u_last = 0.0_dp
    do i = 1, size(obs%steps)
      s = obs%steps(i)%load_factor * reference / area
      u = mean_u(model, obs, 'top', i, 3)
      w = mean_u(model, obs, 'crack_top', i, 3) - mean_u(model, obs, 'crack_bottom', i, 3)
      if (w <= h * e0) then
        expected = length * s / e
      else
        expected = (length - h) * s / e + h * (eu - (eu - e0) * s / ft)
      end if
      worst = max(worst, abs(u - expected) / (length * ft / e))
      worst_w = max(worst_w, abs(w - 0.06_dp * i / size(obs%steps)))
      if (u < u_last) back = back + 1
      u_last = u
    end do
    call check(error, worst, 0.0_dp, 'the top displacement on the closed form at every step', abs=1.0e-9_dp)
    if (allocated(error)) return
    call check(error, worst_w, 0.0_dp, 'the crack''s opening follows VALUE in equal steps', abs=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, back >= 80, 'the top moves back in at least 80 steps (' // str(back) // ')')
    if (allocated(error)) return
    call check(error, s < 0.25_dp * ft, 'the load falls below a quarter of the peak')
  end subroutine test_snap_back

end module test_path_following
