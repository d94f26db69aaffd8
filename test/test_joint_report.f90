!> REPORT, JOINT (issue 26 item 5): the design summary of a pipe joint against closed forms on
!! test/data/joint_closed.dat and joint_gap.dat: two rings 1e10 times stiffer than the interface
!! between them, the top one given a small rigid rotation t about the joint's centre and a
!! closure d0, so that eps_n = -d0 - t x and sigma_n = Kn eps_n where closed, 0 where open.
!! Then Z = R + d0 / t, the opening is largest at the point of least x, the compression at the
!! point of largest x, the faces turn by atan(t), and with no gap the load is Kn d0 times the
!! (polygonal) annulus, and both models reduce to closed forms (M = sigma_max I / Z). The pipes'
!! hoop and axial stresses against Lame on test/data/joint_lame.dat.
module test_joint_report
  use feps_kinds, only: dp, pi, rad2deg, deg2rad
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  use feps_joint_report, only: joint_summary_t, joint_summary
  implicit none
  private

  public :: collect_joint_report

  real(dp), parameter :: kn = 1.0e-6_dp, t = 1.0e-4_dp, outer = 715.0_dp, inner = 600.0_dp
  !> the rings' compliance leaves ~1e-8 of eps_n; the tolerance keeps a margin
  real(dp), parameter :: tol = 1.0e-6_dp

contains

  !> Collect the suite.
  subroutine collect_joint_report(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [new_unittest('closed joint: Z, load, compression, opening, angle, models', test_closed), &
             new_unittest('joint with a gap: Z from the gap front, opening, angle', test_gap), &
             new_unittest('pressurised pipe joint: hoop and axial stresses against Lame', test_lame)]
  end subroutine collect_joint_report

  subroutine solve(deck, js, error)
    character(len=*), intent(in) :: deck
    type(joint_summary_t), intent(out) :: js
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    call read_deck(deck, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    associate (res => obs%steps(size(obs%steps)))
      call joint_summary(model, model%reports(1), res%displacement, res%groups, js, error)
    end associate
  end subroutine solve

  !> The checks both decks share: compression and opening at the extreme points, the angle.
  subroutine check_common(js, d0, error)
    type(joint_summary_t), intent(in) :: js
    real(dp), intent(in) :: d0
    type(error_t), allocatable, intent(out) :: error
    call check(error, js%sigma_max, kn * (d0 + t * maxval(js%geometry%along)), &
               'largest compression Kn (d0 + t x_max)', rel=tol)
    if (allocated(error)) return
    call check(error, js%sigma_max_at(1) * cos(js%sigma_max_at(2) * deg2rad), maxval(js%geometry%along), &
               'largest compression at x_max', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%opening, -d0 - t * minval(js%geometry%along), 'largest opening -d0 - t x_min', &
               abs=tol * d0)
    if (allocated(error)) return
    call check(error, js%opening_at(1) * cos(js%opening_at(2) * deg2rad), minval(js%geometry%along), &
               'largest opening at x_min', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%has_deflection, 'two pipes: a deflection angle')
    if (allocated(error)) return
    call check(error, js%deflection, atan(t) * rad2deg, 'the faces turn by atan(t)', rel=tol)
    if (allocated(error)) return
    call check(error, js%geometry%rings, 4, 'two elements through the wall: 4 rings of Gauss points')
    if (allocated(error)) return
    call check(error, js%geometry%copies, 2, 'a half model')
  end subroutine check_common

  subroutine test_closed(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: d0 = 0.1_dp, a = 15.0_dp, length = 2500.0_dp, ec = 40000.0_dp, ep = 660.0_dp
    type(joint_summary_t) :: js
    real(dp) :: polygon, z, sigma, area
    call solve('test/data/joint_closed.dat', js, error)
    if (allocated(error)) return
    call check_common(js, d0, error)
    if (allocated(error)) return
    z = outer + d0 / t
    call check(error, js%contact_width, z, 'no gap: the zero of the line through each ring', rel=tol)
    if (allocated(error)) return
    ! 12 straight-sided 15 deg segments of the half annulus; sum of x dA = 0 by its symmetry
    polygon = 0.5_dp * (outer**2 - inner**2) * 12.0_dp * sin(15.0_dp * deg2rad)
    call check(error, js%geometry%area, polygon, 'interface area: the half annulus polygon', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%load, 2.0_dp * kn * d0 * polygon, 'load: 2 Kn d0 A', rel=tol)
    if (allocated(error)) return
    call check(error, js%geometry%concrete_modulus, ec, 'E_c from the pipe''s elastic tangent', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%geometry%packing_modulus, ep, 'E_p = 2 G (1 + nu) from the tangent', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%has_models, 'models evaluated')
    if (allocated(error)) return
    ! Z > 2R: over the whole annulus P = sigma_max (Z - R) A / Z, M = sigma_max I / Z
    area = pi * (outer**2 - inner**2)
    sigma = js%load * js%contact_width / ((js%contact_width - outer) * area)
    call check(error, js%australian%sigma_max, sigma, 'australian sigma_max = P Z / ((Z - R) A)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%haslem%sigma_max, sigma, 'haslem sigma_max (the same stress law)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%australian%beta, atan(sigma * (a / ep + length / ec) / js%contact_width) * rad2deg, &
               'australian tan(beta) = sigma_max (a/E_p + L/E_c) / Z', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, js%haslem%beta, sigma * (a / ep + length / ec) / js%contact_width * rad2deg, &
               'haslem beta = sigma_max a/(Z E_p) + (sigma_max I/Z) L/(E_c I)', rel=1.0e-12_dp)
  end subroutine test_closed

  subroutine test_gap(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: d0 = 0.02_dp
    type(joint_summary_t) :: js
    call solve('test/data/joint_gap.dat', js, error)
    if (allocated(error)) return
    call check_common(js, d0, error)
    if (allocated(error)) return
    call check(error, js%contact_width, outer + d0 / t, 'gap front at x = -d0 / t: Z = R + d0 / t', rel=tol)
    if (allocated(error)) return
    call check(error, js%opening > 0.0_dp, 'the far side is open')
  end subroutine test_gap

  !> test/data/joint_lame.dat: generalized plane strain of a thick cylinder under internal
  !! pressure p and an axial strain eps_z, across a stiff elastic joint.
  subroutine test_lame(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: p = 10.0_dp, e = 40000.0_dp, nu = 0.2_dp, eps_z = -0.05_dp / 100.0_dp
    type(joint_summary_t) :: js
    real(dp) :: lame_a, szz, polygon
    call solve('test/data/joint_lame.dat', js, error)
    if (allocated(error)) return
    lame_a = p * inner**2 / (outer**2 - inner**2)
    call check(error, js%hoop_at(1) < inner + 0.5_dp * 14.375_dp, 'largest hoop tension in the bore''s elements')
    if (allocated(error)) return
    call check(error, js%hoop_max, lame_a * (1.0_dp + outer**2 / js%hoop_at(1)**2), &
               'hoop tension: Lame at the point''s radius', rel=1.0e-2_dp)
    if (allocated(error)) return
    szz = e * eps_z + 2.0_dp * nu * lame_a
    call check(error, js%axial_min, szz, 'axial stress min: E eps_z + 2 nu p a^2 / (b^2 - a^2)', rel=2.0e-2_dp)
    if (allocated(error)) return
    ! 36 straight-sided 5 deg segments of the half annulus, twice: the whole joint
    polygon = 0.5_dp * (outer**2 - inner**2) * 36.0_dp * sin(5.0_dp * deg2rad)
    call check(error, js%load, -2.0_dp * szz * polygon, 'load: the axial stress over the whole annulus', &
               rel=1.0e-3_dp)
    if (allocated(error)) return
    call check(error, js%deflection, 0.0_dp, 'no relative rotation', abs=1.0e-9_dp)
    if (allocated(error)) return
    call check(error, .not. js%has_models, 'no PACKING=: no models')
  end subroutine test_lame

end module test_joint_report
