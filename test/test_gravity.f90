!> Body loads (issue 26): GRAVITY and the materials' unit weight GAMMA, against closed forms.
!! - test/data/soil_column.dat, a hex20 soil column on rollers: the vertical stress
!!   sv = -gamma (H - z) at every Gauss point and the horizontal nu / (1 - nu) sv (exact: hex20's
!!   quadratic uz carries the linear field), the top's settlement gamma H^2 / (2 M) with the
!!   constrained modulus M = E (1 - nu) / ((1 + nu) (1 - 2 nu)), and the base reaction equal to
!!   the weight gamma A H (to 1e-9).
!! - test/data/hanging_bar.dat, a bar3 tie hanging from its top: the axial force gamma A z at
!!   every Gauss point and the top's reaction gamma A L.
!! - gravity in a later stage, and a group born under gravity, bring their weight then.
module test_gravity
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  use feps_element_catalog, only: point_coordinates
  implicit none
  private

  public :: collect_gravity

contains

  !> Collect the suite.
  subroutine collect_gravity(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('soil column: sv = gamma depth at every Gauss point, reaction = weight', test_soil_column), &
      new_unittest('hanging bar: N = gamma A z at every Gauss point, reaction = weight', test_hanging_bar), &
      new_unittest('a group born under gravity brings its weight in its stage', test_lifts), &
      new_unittest('GRAVITY after a STAGE record weighs from that stage on', test_late_gravity)]
  end subroutine collect_gravity

  subroutine test_soil_column(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: gamma = 2.0e-5_dp, height = 10000.0_dp, area = 1.0e6_dp, e = 50.0_dp, nu = 0.3_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp), allocatable :: xg(:, :)
    real(dp) :: worst_v, worst_h, sv, m, settlement
    integer :: q
    call read_deck('test/data/soil_column.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    associate (res => obs%steps(size(obs%steps)))
      call check(error, sum(res%applied_force(3, :)), -gamma * area * height, 'the weight applied', rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, sum(res%reaction(3, :)), gamma * area * height, 'the base carries the weight', rel=1.0e-9_dp)
      if (allocated(error)) return
      call point_coordinates('hex20', model%coords, model%groups(1)%connectivity, xg, error)
      if (allocated(error)) return
      worst_v = 0.0_dp
      worst_h = 0.0_dp
      do q = 1, size(xg, 2)
        sv = -gamma * (height - xg(3, q))
        worst_v = max(worst_v, abs(res%groups(1)%stress(3, q) - sv))
        worst_h = max(worst_h, maxval(abs(res%groups(1)%stress(1:2, q) - nu / (1.0_dp - nu) * sv)))
      end do
      call check(error, worst_v, 0.0_dp, 'sv = -gamma (H - z) at every Gauss point', abs=1.0e-9_dp * gamma * height)
      if (allocated(error)) return
      call check(error, worst_h, 0.0_dp, 'sh = nu / (1 - nu) sv at every Gauss point', abs=1.0e-9_dp * gamma * height)
      if (allocated(error)) return
      m = e * (1.0_dp - nu) / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
      settlement = gamma * height**2 / (2.0_dp * m)
      call check(error, minval(res%displacement(3, :)), -settlement, 'the top settles gamma H^2 / (2 M)', rel=1.0e-9_dp)
    end associate
  end subroutine test_soil_column

  subroutine test_hanging_bar(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: gamma = 7.85e-5_dp, area = 100.0_dp, length = 1000.0_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp), allocatable :: xg(:, :)
    real(dp) :: worst
    integer :: q
    call read_deck('test/data/hanging_bar.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    associate (res => obs%steps(size(obs%steps)))
      call check(error, sum(res%reaction(3, :)), gamma * area * length, 'the top carries the weight', rel=1.0e-9_dp)
      if (allocated(error)) return
      call point_coordinates('bar3', model%coords, model%groups(1)%connectivity, xg, error)
      if (allocated(error)) return
      worst = 0.0_dp
      do q = 1, size(xg, 2)
        worst = max(worst, abs(res%groups(1)%stress(1, q) - gamma * area * xg(3, q)))
      end do
      call check(error, worst, 0.0_dp, 'N = gamma A z at every Gauss point', abs=1.0e-9_dp * gamma * area * length)
    end associate
  end subroutine test_hanging_bar

  !> test/data/soil_column_lifts.dat: the base carries the lower lift's weight after stage 1,
  !! the whole column's after stage 2, where the stresses are the one-lift column's.
  subroutine test_lifts(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: gamma = 2.0e-5_dp, height = 10000.0_dp, area = 1.0e6_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp), allocatable :: xg(:, :)
    real(dp) :: worst
    integer :: g, q, last
    call read_deck('test/data/soil_column_lifts.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, obs%steps(1)%stage, 1, 'the first step is stage 1''s')
    if (allocated(error)) return
    call check(error, sum(obs%steps(1)%reaction(3, :)), gamma * area * height / 2.0_dp, &
               'after stage 1 the base carries the lower lift', rel=1.0e-9_dp)
    if (allocated(error)) return
    last = size(obs%steps)
    call check(error, sum(obs%steps(last)%reaction(3, :)), gamma * area * height, &
               'after stage 2 the base carries both lifts', rel=1.0e-9_dp)
    if (allocated(error)) return
    worst = 0.0_dp
    do g = 1, 2
      call point_coordinates('hex20', model%coords, model%groups(g)%connectivity, xg, error)
      if (allocated(error)) return
      do q = 1, size(xg, 2)
        worst = max(worst, abs(obs%steps(last)%groups(g)%stress(3, q) + gamma * (height - xg(3, q))))
      end do
    end do
    call check(error, worst, 0.0_dp, 'sv = -gamma (H - z) in both lifts at the end', abs=1.0e-9_dp * gamma * height)
  end subroutine test_lifts

  !> test/data/soil_column_late_gravity.dat: nothing is applied in stage 1, the weight in stage 2.
  subroutine test_late_gravity(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: weight = 2.0e-5_dp * 1.0e6_dp * 10000.0_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    call read_deck('test/data/soil_column_late_gravity.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, maxval(abs(obs%steps(1)%applied_force)), 0.0_dp, 'no weight in stage 1', abs=0.0_dp)
    if (allocated(error)) return
    call check(error, sum(obs%steps(size(obs%steps))%reaction(3, :)), weight, 'the weight in stage 2', &
               rel=1.0e-9_dp)
  end subroutine test_late_gravity

end module test_gravity
