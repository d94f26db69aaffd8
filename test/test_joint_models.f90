!> Tests of the analytical joint models (thesis chapter 7) against quadrature, closed forms, thesis
!! Tables 7.1 and 7.4 and values printed by an independent Python implementation.
module test_joint_models
  use feps_kinds, only: dp, pi, rad2deg
  use feps_error, only: error_t, err_input
  use feps_testing, only: unittest_t, new_unittest, check
  use feps_joint_models, only: joint_t, joint_solution_t, australian, haslem, annulus_area, &
                               pipe_second_moment, joint_load_factor, joint_moment_factor, &
                               packing_youngs_modulus, thesis_joint_pressure
  implicit none
  private

  public :: collect_joint_models

  real(dp), parameter :: table_tolerance = 0.005_dp   ! SPEC section 9: 0.5 %

  !> Thesis Table 7.4, analytical columns: beta_bar (deg), Australian Z, sigma_max, Haslem Z, sigma_max,
  !! nu_p, G_p. Rows 1 and 3 (Z > 2R) and row 6's Haslem sigma_max are not reproduced by the stated
  !! equations (see docs, verification of chapter 7) and are left out of the checks below.
  real(dp), parameter :: table7_4(7, 12) = reshape([ &
    0.0662_dp, 1435.0_dp, 19.48_dp, 1435.0_dp, 19.48_dp, 0.1_dp, 300.0_dp, &
    0.0646_dp, 1428.5_dp, 20.02_dp, 1428.5_dp, 20.02_dp, 0.4_dp, 300.0_dp, &
    0.0687_dp, 1453.8_dp, 17.74_dp, 1453.8_dp, 17.74_dp, -0.3_dp, 300.0_dp, &
    0.0643_dp, 1335.7_dp, 21.39_dp, 1327.3_dp, 21.51_dp, 0.1_dp, 900.0_dp, &
    0.0637_dp, 1326.2_dp, 21.57_dp, 1315.5_dp, 21.71_dp, 0.4_dp, 900.0_dp, &
    0.0649_dp, 1370.3_dp, 20.87_dp, 1368.4_dp, 21.01_dp, -0.3_dp, 900.0_dp, &
    0.2061_dp, 768.0_dp, 32.4_dp, 505.0_dp, 43.69_dp, 0.1_dp, 300.0_dp, &
    0.1971_dp, 761.6_dp, 32.59_dp, 464.8_dp, 46.45_dp, 0.4_dp, 300.0_dp, &
    0.2123_dp, 820.1_dp, 30.95_dp, 621.8_dp, 37.62_dp, -0.3_dp, 300.0_dp, &
    0.1982_dp, 700.4_dp, 34.6_dp, 296.7_dp, 66.40_dp, 0.1_dp, 900.0_dp, &
    0.1951_dp, 696.8_dp, 34.71_dp, 267.4_dp, 72.75_dp, 0.4_dp, 900.0_dp, &
    0.1998_dp, 722.3_dp, 33.83_dp, 371.0_dp, 55.20_dp, -0.3_dp, 900.0_dp], [7, 12])
  integer, parameter :: reproduced_rows(*) = [2, 4, 5, 6, 7, 8, 9, 10, 11, 12]

contains

  !> Collect all exported unit tests.
  subroutine collect_joint_models(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("closed forms match quadrature of eq. 7.2.1", test_factors_quadrature), &
      new_unittest("full contact (Z > 2R) closed form", test_full_contact), &
      new_unittest("round trips beta -> Z -> beta, (beta, Z) -> P", test_round_trip), &
      new_unittest("table 7.1 edge load deflections", test_table7_1), &
      new_unittest("table 7.4 Australian columns", test_table7_4_australian), &
      new_unittest("table 7.4 Haslem columns", test_table7_4_haslem), &
      new_unittest("agrees with an independent Python implementation", test_python_agreement), &
      new_unittest("impossible inputs return errors", test_bad_input) &
      ]
  end subroutine collect_joint_models

  !> Midpoint rule over the chord lengths L_x of eq. 7.2.1: an independent evaluation of p and m.
  subroutine quadrature_factors(z, outer, inner, p, m)
    real(dp), intent(in) :: z, outer, inner
    real(dp), intent(out) :: p, m
    integer, parameter :: n = 200000
    real(dp) :: start, dx, x, chord, weight
    integer :: i
    start = max(outer - z, -outer)
    dx = (outer - start) / n
    p = 0.0_dp
    m = 0.0_dp
    do i = 1, n
      x = start + (i - 0.5_dp) * dx
      chord = 2.0_dp * sqrt(outer**2 - x**2)
      if (abs(x) < inner) chord = chord - 2.0_dp * sqrt(inner**2 - x**2)
      weight = (x - (outer - z)) / z * chord * dx
      p = p + weight
      m = m + weight * x
    end do
  end subroutine quadrature_factors

  subroutine test_factors_quadrature(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: widths(5) = [60.0_dp, 495.0_dp, 1000.0_dp, 1368.4_dp, 1700.0_dp]
    real(dp) :: p, m
    integer :: i
    do i = 1, size(widths)
      call quadrature_factors(widths(i), 715.0_dp, 600.0_dp, p, m)
      ! the sqrt end singularities limit the midpoint rule to about 1e-8 here
      call check(error, joint_load_factor(widths(i), 715.0_dp, 600.0_dp), p, "p(Z) at Z = 60..1700", rel=1.0e-6_dp)
      if (allocated(error)) return
      call check(error, joint_moment_factor(widths(i), 715.0_dp, 600.0_dp), m, "m(Z) at Z = 60..1700", rel=1.0e-6_dp)
      if (allocated(error)) return
    end do
  end subroutine test_factors_quadrature

  !> No gap: sigma = sigma_max (x - H) / Z everywhere, so P = sigma_max A (Z - R) / Z and M = sigma_max I_c / Z;
  !! then both models give the same angle, atan or not aside.
  subroutine test_full_contact(error)
    type(error_t), allocatable, intent(out) :: error
    type(joint_t) :: joint
    type(joint_solution_t) :: aus, has
    real(dp), parameter :: z = 1600.0_dp, load = 4.0e6_dp
    real(dp) :: sigma, area, inertia, compliance
    joint%packing_modulus = 660.0_dp
    area = annulus_area(715.0_dp, 600.0_dp)
    inertia = pipe_second_moment(715.0_dp, 600.0_dp)
    call check(error, area, pi * (715.0_dp**2 - 600.0_dp**2), "annulus area", rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, inertia, pi / 4.0_dp * (715.0_dp**4 - 600.0_dp**4), "I_c", rel=1.0e-14_dp)
    if (allocated(error)) return
    sigma = load * z / (area * (z - 715.0_dp))
    call australian(joint, aus, error, z=z, load=load)
    if (allocated(error)) return
    call haslem(joint, has, error, z=z, load=load)
    if (allocated(error)) return
    call check(error, aus%sigma_max, sigma, "sigma_max = P Z / (A (Z - R))", rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, aus%moment, sigma * inertia / z, "M = sigma_max I_c / Z", rel=1.0e-12_dp)
    if (allocated(error)) return
    compliance = 15.0_dp / 660.0_dp + 2500.0_dp / 40000.0_dp
    call check(error, aus%beta, atan(sigma * compliance / z) * rad2deg, "Australian beta", rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, has%beta, sigma * compliance / z * rad2deg, "Haslem beta", rel=1.0e-12_dp)
  end subroutine test_full_contact

  subroutine test_round_trip(error)
    type(error_t), allocatable, intent(out) :: error
    type(joint_t) :: joint
    type(joint_solution_t) :: first, second, third
    real(dp), parameter :: angles(4) = [0.01_dp, 0.0662_dp, 0.2_dp, 1.5_dp]
    integer :: i, model
    joint%packing_modulus = 1260.0_dp
    do model = 1, 2
      do i = 1, size(angles)
        call solve(model, first, error, beta=angles(i))
        if (allocated(error)) return
        call solve(model, second, error, z=first%contact_width)
        if (allocated(error)) return
        call check(error, second%beta, angles(i), "beta from the solved Z", rel=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, second%sigma_max, first%sigma_max, "sigma_max from the solved Z", rel=1.0e-10_dp)
        if (allocated(error)) return
        call solve(model, third, error, beta=angles(i), z=first%contact_width)
        if (allocated(error)) return
        call check(error, third%load, thesis_joint_pressure * annulus_area(715.0_dp, 600.0_dp), &
                   "P from beta and Z is the default load", rel=1.0e-10_dp)
        if (allocated(error)) return
      end do
    end do
  contains
    subroutine solve(which, solution, error, beta, z)
      integer, intent(in) :: which
      type(joint_solution_t), intent(out) :: solution
      type(error_t), allocatable, intent(out) :: error
      real(dp), intent(in), optional :: beta, z
      if (which == 1) then
        call australian(joint, solution, error, beta, z)
      else
        call haslem(joint, solution, error, beta, z)
      end if
    end subroutine solve
  end subroutine test_round_trip

  !> One pipe under the model B edge load: P = 2000 kN, Z = 495 mm (load from x = -220 to -715 mm), no
  !! packing (a = 0), L = 1250 (half the pipe: both ends are loaded, the mid-section does not rotate).
  subroutine test_table7_1(error)
    type(error_t), allocatable, intent(out) :: error
    type(joint_t) :: joint
    type(joint_solution_t) :: aus, has
    joint = joint_t(packing_thickness=0.0_dp, pipe_length=1250.0_dp, packing_modulus=1.0_dp)
    call australian(joint, aus, error, z=495.0_dp, load=2.0e6_dp)
    if (allocated(error)) return
    call haslem(joint, has, error, z=495.0_dp, load=2.0e6_dp)
    if (allocated(error)) return
    call check(error, aus%sigma_max, 18.66_dp, "edge load sigma_max (SPEC section 8)", rel=table_tolerance)
    if (allocated(error)) return
    call check(error, aus%beta, 0.0675_dp, "Australian deflection (deg)", rel=table_tolerance)
    if (allocated(error)) return
    call check(error, has%beta, 0.0198_dp, "Haslem deflection (deg)", rel=table_tolerance)
  end subroutine test_table7_1

  subroutine test_table7_4_australian(error)
    type(error_t), allocatable, intent(out) :: error
    call check_table7_4(1, error)
  end subroutine test_table7_4_australian

  subroutine test_table7_4_haslem(error)
    type(error_t), allocatable, intent(out) :: error
    call check_table7_4(2, error)
  end subroutine test_table7_4_haslem

  !> a = 15, L = 2500, E_c = 40000, P = 10 MPa on the annulus, E_p = 2 G_p (1 + nu_p).
  subroutine check_table7_4(model, error)
    integer, intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    type(joint_t) :: joint
    type(joint_solution_t) :: solution
    integer :: i, row, column
    character(len=8) :: label
    do i = 1, size(reproduced_rows)
      row = reproduced_rows(i)
      write (label, '(a,i0)') 'row ', row
      joint%packing_modulus = packing_youngs_modulus(table7_4(7, row), table7_4(6, row))
      if (model == 1) then
        call australian(joint, solution, error, beta=table7_4(1, row))
      else
        call haslem(joint, solution, error, beta=table7_4(1, row))
      end if
      if (allocated(error)) return
      column = 2 * model
      call check(error, solution%contact_width, table7_4(column, row), trim(label) // " Z", rel=table_tolerance)
      if (allocated(error)) return
      ! row 6, Haslem: thesis sigma_max 21.01 disagrees with its own Z = 1368.4 (20.90 at P = 10 MPa x A)
      if (model == 2 .and. row == 6) cycle
      call check(error, solution%sigma_max, table7_4(column + 1, row), trim(label) // " sigma_max", &
                 rel=table_tolerance)
      if (allocated(error)) return
    end do
  end subroutine check_table7_4

  !> Values printed by the separate Python implementation of the same equations that
  !! scripts/joint_models.py held until it became a front end of `feps joint` (commit b8b287f).
  subroutine test_python_agreement(error)
    type(error_t), allocatable, intent(out) :: error
    type(joint_t) :: joint
    type(joint_solution_t) :: s
    real(dp), parameter :: tol = 1.0e-9_dp

    joint%packing_modulus = 660.0_dp
    call australian(joint, s, error, beta=0.2061_dp)
    if (allocated(error)) return
    call check(error, s%contact_width, 767.8632154555078_dp, "australian beta 0.2061: Z", rel=tol)
    if (allocated(error)) return
    call check(error, s%sigma_max, 32.408766699089384_dp, "australian beta 0.2061: sigma_max", rel=tol)
    if (allocated(error)) return
    call check(error, s%moment, 2405869653.7617483_dp, "australian beta 0.2061: M", rel=tol)
    if (allocated(error)) return
    call haslem(joint, s, error, beta=0.2061_dp)
    if (allocated(error)) return
    call check(error, s%contact_width, 504.666987623762_dp, "haslem beta 0.2061: Z", rel=tol)
    if (allocated(error)) return
    call check(error, s%sigma_max, 43.70940224656189_dp, "haslem beta 0.2061: sigma_max", rel=tol)
    if (allocated(error)) return
    call haslem(joint, s, error, beta=0.0662_dp)
    if (allocated(error)) return
    call check(error, s%contact_width, 1452.6379194385408_dp, "haslem beta 0.0662: Z", rel=tol)
    if (allocated(error)) return

    joint%packing_modulus = 1980.0_dp
    call haslem(joint, s, error, beta=0.1_dp, z=800.0_dp)
    if (allocated(error)) return
    call check(error, s%load, 4795749.708497523_dp, "haslem beta 0.1, Z 800: P", rel=tol)
    if (allocated(error)) return

    joint = joint_t(packing_thickness=20.0_dp, pipe_length=3000.0_dp, concrete_modulus=30000.0_dp, &
                    packing_modulus=500.0_dp, outer_radius=500.0_dp, inner_radius=400.0_dp)
    call australian(joint, s, error, beta=0.5_dp, load=3.0e6_dp)
    if (allocated(error)) return
    call check(error, s%contact_width, 550.9355371280067_dp, "australian other joint: Z", rel=tol)
    if (allocated(error)) return
    call haslem(joint, s, error, beta=0.5_dp, load=3.0e6_dp)
    if (allocated(error)) return
    call check(error, s%contact_width, 380.98000051050644_dp, "haslem other joint: Z", rel=tol)
    if (allocated(error)) return
    call check(error, s%sigma_max, 45.236761068406764_dp, "haslem other joint: sigma_max", rel=tol)
  end subroutine test_python_agreement

  subroutine test_bad_input(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: failure
    type(joint_t) :: joint, bare
    type(joint_solution_t) :: s
    real(dp) :: largest
    joint%packing_modulus = 660.0_dp

    call australian(joint, s, failure, beta=0.0_dp)
    call expect_input_error("beta = 0")
    if (allocated(error)) return
    call haslem(joint, s, failure, beta=-0.1_dp)
    call expect_input_error("beta < 0")
    if (allocated(error)) return
    call australian(joint, s, failure, z=-5.0_dp)
    call expect_input_error("Z < 0")
    if (allocated(error)) return
    call australian(joint, s, failure)
    call expect_input_error("neither beta nor Z")
    if (allocated(error)) return
    call australian(joint, s, failure, beta=0.1_dp, z=500.0_dp, load=1.0e6_dp)
    call expect_input_error("beta, Z and P together")
    if (allocated(error)) return
    call australian(bare, s, failure, beta=0.1_dp)
    call expect_input_error("E_p not set")
    if (allocated(error)) return
    call haslem(joint_t(packing_modulus=660.0_dp, inner_radius=715.0_dp), s, failure, beta=0.1_dp)
    call expect_input_error("r = R")
    if (allocated(error)) return
    ! Without packing Haslem's angle is bounded by P R L / (E_c I_c) (resultant at the edge).
    largest = 2.0e6_dp * 715.0_dp * 2500.0_dp / (40000.0_dp * pipe_second_moment(715.0_dp, 600.0_dp)) * rad2deg
    call haslem(joint_t(packing_thickness=0.0_dp, packing_modulus=660.0_dp), s, failure, &
                beta=1.01_dp * largest, load=2.0e6_dp)
    call expect_input_error("Haslem beyond its largest angle")
    if (allocated(error)) return
    call haslem(joint_t(packing_thickness=0.0_dp, packing_modulus=660.0_dp), s, failure, &
                beta=0.9_dp * largest, load=2.0e6_dp)
    call check(error, .not. allocated(failure), "Haslem just below its largest angle solves")
  contains
    subroutine expect_input_error(what)
      character(len=*), intent(in) :: what
      call check(error, allocated(failure), what // ": no error returned")
      if (allocated(error)) return
      call check(error, failure%code, err_input, what // ": error code")
      deallocate (failure)
    end subroutine expect_input_error
  end subroutine test_bad_input

end module test_joint_models
