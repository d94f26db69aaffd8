!> Tests of the Mohr-Coulomb interface material with a gap zone (thesis 2.3.2-2.3.4):
!! elastic steps, sliding with and without dilation, the held-normal example of section
!! 2.3.4 (SPEC sec2.3.4a), gap opening and closure (eq. 2.3.22), the apex, the consistent
!! tangent against finite differences and against eq. 2.3.18, and parameter checks.
module test_interface_mc
  use feps_kinds, only: dp, rad2deg, deg2rad
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_material_testing, only: material_spec, expect_material_rejected
  use feps_model, only: name_len
  use feps_material, only: material_t, state_elastic, state_plastic, state_open
  use feps_interface_mohr_coulomb, only: interface_mohr_coulomb_t, new_interface_mohr_coulomb, &
                                         default_gap_factor
  use feps_tangent_symmetry, only: nearest_symmetric_psd
  implicit none
  private

  public :: collect_interface_mc

  !> Friction angle with tan(phi) = 0.5 (the thesis's 26.57 degrees, to full precision).
  real(dp), parameter :: phi_half = 26.565051177077989_dp

contains

  subroutine collect_interface_mc(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("elastic_tangent_and_linearity", test_elastic_tangent), &
      new_unittest("elastic_step", test_elastic_step), &
      new_unittest("sliding_without_dilation", test_sliding_no_dilation), &
      new_unittest("held_normal_dilation_sec2_3_4a", test_held_normal_dilation), &
      new_unittest("held_normal_thesis_angle", test_held_normal_thesis_angle), &
      new_unittest("gap_opening", test_gap_opening), &
      new_unittest("closure_inside_step", test_closure), &
      new_unittest("cohesion", test_cohesion), &
      new_unittest("trial_on_yield_surface", test_trial_on_surface), &
      new_unittest("apex_and_zero_shear", test_apex), &
      new_unittest("update_continuous_across_gap_zone", test_gap_continuity), &
      new_unittest("oblique_slip_3d", test_oblique_slip), &
      new_unittest("no_shear_stiffness_full_slip", test_no_shear_stiffness), &
      new_unittest("tangent_finite_difference", test_tangent_fd), &
      new_unittest("tangent_eq_2_3_18", test_tangent_continuum), &
      new_unittest("symmetric_tangent", test_symmetric), &
      new_unittest("validator", test_validator), &
      new_unittest("huge_steps_finite", test_huge_steps), &
      new_unittest("sliding_tangent_psd_stand_in", test_psd_stand_in), &
      new_unittest("random_steps_thesis_conditions", test_random_conditions) &
      ]
  end subroutine collect_interface_mc

  ! ---------------------------------------------------------------- helpers

  pure function make(kn, ks, c, phi, psi) result(m)
    real(dp), intent(in) :: kn, ks, c, phi, psi
    type(interface_mohr_coulomb_t) :: m
    m = interface_mohr_coulomb_t(name='iface', kn=kn, ks=ks, c=c, phi=phi, psi=psi)
  end function make

  pure function diag_d(m, n) result(d)
    type(interface_mohr_coulomb_t), intent(in) :: m
    integer, intent(in) :: n
    real(dp) :: d(n, n)
    integer :: i
    d = 0.0_dp
    do i = 1, n - 1
      d(i, i) = m%ks
    end do
    d(n, n) = m%kn
  end function diag_d

  !> Every entry of a within tol (absolute) of b.
  subroutine check_matrix(error, a, b, what, tol)
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in) :: a(:, :), b(:, :)
    character(len=*), intent(in) :: what
    real(dp), intent(in) :: tol
    integer :: i, j
    do j = 1, size(a, 2)
      do i = 1, size(a, 1)
        call check(error, a(i, j), b(i, j), what // '(' // str(i) // ',' // str(j) // ')', abs=tol)
        if (allocated(error)) return
      end do
    end do
  end subroutine check_matrix

  subroutine check_vector(error, a, b, what, tol)
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in) :: a(:), b(:)
    character(len=*), intent(in) :: what
    real(dp), intent(in) :: tol
    integer :: i
    do i = 1, size(a)
      call check(error, a(i), b(i), what // '(' // str(i) // ')', abs=tol)
      if (allocated(error)) return
    end do
  end subroutine check_vector

  pure logical function finite(x)
    real(dp), intent(in) :: x(:)
    finite = all(x == x) .and. all(abs(x) <= huge(x))
  end function finite

  !> Central finite-difference derivative d sig / d deps of the update.
  subroutine fd_tangent(m, sig0, eps0, deps, state0, dfd)
    type(interface_mohr_coulomb_t), intent(in) :: m
    real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
    integer, intent(in) :: state0
    real(dp), intent(out) :: dfd(:, :)
    real(dp) :: sp(size(sig0)), sm(size(sig0)), dt(size(sig0), size(sig0)), e(size(sig0)), h
    integer :: j, st
    h = 1.0e-6_dp * maxval(abs(deps))
    do j = 1, size(sig0)
      e = 0.0_dp
      e(j) = h
      call m%update(sig0, eps0, deps + e, state0, sp, st, dt)
      call m%update(sig0, eps0, deps - e, state0, sm, st, dt)
      dfd(:, j) = (sp - sm) / (2.0_dp * h)
    end do
  end subroutine fd_tangent

  !> Thesis eq. 2.3.18 with the gradients 2.3.19-2.3.20 (c_I from f = g at sig).
  pure function continuum_dep(m, sig) result(dep)
    type(interface_mohr_coulomb_t), intent(in) :: m
    real(dp), intent(in) :: sig(:)
    real(dp) :: dep(size(sig), size(sig))
    real(dp) :: d(size(sig), size(sig)), df(size(sig)), dg(size(sig)), tphi, tpsi, ci, sn
    integer :: i, j, n
    n = size(sig)
    d = diag_d(m, n)
    tphi = tan(m%phi * deg2rad)
    tpsi = tan(m%psi * deg2rad)
    sn = sig(n)
    ci = m%c + sn * (tpsi - tphi)
    df(1:n - 1) = sig(1:n - 1)
    df(n) = (m%c - sn * tphi) * tphi
    dg(1:n - 1) = sig(1:n - 1)
    dg(n) = (ci - sn * tpsi) * tpsi
    do j = 1, n
      do i = 1, n
        dep(i, j) = d(i, j) - d(i, i) * dg(i) * df(j) * d(j, j) / dot_product(df, matmul(d, dg))
      end do
    end do
  end function continuum_dep

  ! ---------------------------------------------------------------- tests

  subroutine test_elastic_tangent(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: d3(3, 3), d2(2, 2)
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 0.0_dp)
    call m%elastic_tangent(d3)
    call check_matrix(error, d3, reshape([1000.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1000.0_dp, 0.0_dp, &
                                          0.0_dp, 0.0_dp, 2000.0_dp], [3, 3]), 'D 3D', 0.0_dp)
    if (allocated(error)) return
    call m%elastic_tangent(d2)
    call check_matrix(error, d2, reshape([1000.0_dp, 0.0_dp, 0.0_dp, 2000.0_dp], [2, 2]), 'D 2D', 0.0_dp)
    if (allocated(error)) return
    call check(error, .not. m%is_linear(), 'interface material is not linear')
    if (allocated(error)) return
    call check(error, m%gap_factor, 1.0e-6_dp, 'documented gap factor 1e-6')
  end subroutine test_elastic_tangent

  !> Inside the yield surface: sig = sig0 + D deps exactly, stuck, tangent D.
  subroutine test_elastic_step(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig3(3), dt3(3, 3), sig2(2), dt2(2, 2)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 10.0_dp, 30.0_dp, 10.0_dp)
    ! trial tau = |(6, -5)| = 7.8, sigma_n = -120: strength 10 + 120 tan 30 = 79.3
    call m%update([5.0_dp, -3.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [1.0e-3_dp, -2.0e-3_dp, -1.0e-2_dp], &
                  state_elastic, sig3, st, dt3)
    call check_vector(error, sig3, [6.0_dp, -5.0_dp, -120.0_dp], 'sig 3D', 1.0e-12_dp)
    if (allocated(error)) return
    call check(error, st, state_elastic, 'state 3D')
    if (allocated(error)) return
    call check_matrix(error, dt3, diag_d(m, 3), 'tangent 3D', 0.0_dp)
    if (allocated(error)) return
    call m%update([5.0_dp, -100.0_dp], [0.0_dp, -0.05_dp], [-1.0e-3_dp, 1.0e-2_dp], state_plastic, sig2, st, dt2)
    call check_vector(error, sig2, [4.0_dp, -80.0_dp], 'sig 2D', 1.0e-12_dp)
    if (allocated(error)) return
    call check(error, st, state_elastic, 'state 2D (unloading from sliding)')
    if (allocated(error)) return
    call check_matrix(error, dt2, diag_d(m, 2), 'tangent 2D', 0.0_dp)
  end subroutine test_elastic_step

  !> psi = 0: sigma_n is that of the trial, tau is returned onto tau = c - sigma_n tan phi.
  subroutine test_sliding_no_dilation(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(2), dt(2, 2), sig3(3), dt3(3, 3)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 0.0_dp)
    call m%update([0.0_dp, -100.0_dp], [0.0_dp, -0.05_dp], [0.2_dp, -0.01_dp], state_elastic, sig, st, dt)
    call check(error, st, state_plastic, 'state')
    if (allocated(error)) return
    call check(error, sig(2), -120.0_dp, 'sigma_n unchanged from trial', rel=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, sig(1), 120.0_dp * tan(30.0_dp * deg2rad), 'tau on the surface', rel=1.0e-13_dp)
    if (allocated(error)) return
    ! negative slip direction keeps its sign
    call m%update([0.0_dp, 0.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [0.0_dp, -0.2_dp, 0.0_dp], &
                  state_elastic, sig3, st, dt3)
    call check_vector(error, sig3, [0.0_dp, -100.0_dp * tan(30.0_dp * deg2rad), -100.0_dp], 'sig 3D', 1.0e-12_dp)
  end subroutine test_sliding_no_dilation

  !> The symmetric stand-in for a sliding point's tangent (psi = 0, kn = 2000, ks = 1000,
  !! phi = 30, the point of test_sliding_no_dilation). The consistent tangent is
  !! [[0, -t kn], [0, kn]] (t = tan phi): no shear stiffness, shear following the normal
  !! stress. Its symmetric part S = [[0, -a], [-a, kn]], a = t kn / 2, is indefinite (det = -a^2),
  !! and the nearest symmetric positive semi-definite matrix is S without its negative
  !! eigenvalue: l v v^T with l = (kn + sqrt(kn^2 + 4 a^2)) / 2, whose trace is l and whose
  !! determinant is 0. With psi = phi the tangent is symmetric and semi-definite and the
  !! stand-in is the tangent itself. The interface's own stand-in (`symmetric_stand_in`, what
  !! the analysis factorizes) is that matrix without its coupling. Tolerance 1e-12 relative.
  subroutine test_psd_stand_in(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(2), dt(2, 2), d(2, 2), psd(2, 2), kn, a, l
    integer :: st
    kn = 2000.0_dp
    m = make(kn, 1000.0_dp, 0.0_dp, 30.0_dp, 0.0_dp)
    call m%update([0.0_dp, -100.0_dp], [0.0_dp, -0.05_dp], [0.2_dp, -0.01_dp], state_elastic, sig, st, dt)
    call check(error, st, state_plastic, 'sliding')
    if (allocated(error)) return
    a = tan(30.0_dp * deg2rad) * kn / 2.0_dp
    call check_vector(error, reshape(dt, [4]), [0.0_dp, 0.0_dp, -2.0_dp * a, kn], 'consistent tangent', 1.0e-12_dp)
    if (allocated(error)) return
    d = dt
    call nearest_symmetric_psd(d)
    l = (kn + sqrt(kn**2 + 4.0_dp * a**2)) / 2.0_dp
    call check(error, d(1, 2), d(2, 1), 'stand-in symmetric', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, d(1, 1) + d(2, 2), l, 'trace = the positive eigenvalue of S', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, d(1, 1) * d(2, 2) - d(1, 2) * d(2, 1), 0.0_dp, 'determinant 0 (negative eigenvalue removed)', &
               abs=1.0e-12_dp * l**2)
    if (allocated(error)) return
    call check(error, d(1, 2) < 0.0_dp .and. d(1, 1) > 0.0_dp, 'coupling sign of S kept, shear stiffness gained')
    if (allocated(error)) return
    ! the interface's own stand-in (what the analysis factorizes): that matrix without its
    ! coupling, diag(l v1^2, l v2^2): trace l, a small shear stiffness along the slip
    psd = d
    d = dt
    call m%symmetric_stand_in(d)
    call check_vector(error, reshape(d, [4]), [psd(1, 1), 0.0_dp, 0.0_dp, psd(2, 2)], &
                      'the interface''s stand-in: the nearest PSD matrix without its coupling', 1.0e-12_dp)
    if (allocated(error)) return
    call check(error, d(1, 1) > 0.0_dp .and. d(1, 1) < 0.2_dp * 1000.0_dp .and. d(2, 2) > 0.9_dp * kn, &
               'a small shear stiffness along the slip (13% of ks at phi = 30), the normal nearly kn')
    if (allocated(error)) return
    ! associated flow: the tangent is symmetric and semi-definite, the stand-in is itself
    m = make(kn, 1000.0_dp, 0.0_dp, 30.0_dp, 30.0_dp)
    call m%update([0.0_dp, -100.0_dp], [0.0_dp, -0.05_dp], [0.2_dp, -0.01_dp], state_elastic, sig, st, dt)
    d = dt
    call nearest_symmetric_psd(d)
    call check_vector(error, reshape(d, [4]), reshape(dt, [4]), 'psi = phi: unchanged', 1.0e-12_dp)
    if (allocated(error)) return
    d = dt
    call m%symmetric_stand_in(d)
    call check_vector(error, reshape(d, [4]), reshape(dt, [4]), 'psi = phi: the material''s stand-in unchanged', &
                      1.0e-12_dp)
  end subroutine test_psd_stand_in

  !> SPEC sec2.3.4a on one point: kn = 2000, ks = 1000, tan phi = tan psi = 0.5, c = 0;
  !! eps_n = -0.1 then 100 steps of gamma1 += 0.002 with eps_n held. The closed form is
  !! tau = 1000 u (u <= 0.1), tau = 100 + (1000/3)(u - 0.1) after, sigma_n = -2 tau.
  !! The backward-Euler return reproduces it to rounding: on the straight cone generator
  !! with a fixed slip direction the continuum tangent 2.3.18 is constant (slope
  !! ks - ks^2/(ks + kn tan phi tan psi) = 1000/3), so the integral is linear in each step,
  !! and the yield point u = 0.1 falls on a step boundary. Tolerance 1e-10 relative.
  subroutine test_held_normal_dilation(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), eps(3), deps(3), dt(3, 3), u, tau_ref
    integer :: st, k
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, atan(0.5_dp) * rad2deg, atan(0.5_dp) * rad2deg)
    sig = 0.0_dp
    eps = 0.0_dp
    st = state_elastic
    deps = [0.0_dp, 0.0_dp, -0.1_dp]
    call m%update(sig, eps, deps, st, sig, st, dt)
    eps = eps + deps
    call check(error, sig(3), -200.0_dp, 'stage 1 sigma_n = Kn delta1', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, st, state_elastic, 'stage 1 elastic')
    if (allocated(error)) return
    deps = [0.002_dp, 0.0_dp, 0.0_dp]
    do k = 1, 100
      call m%update(sig, eps, deps, st, sig, st, dt)
      eps = eps + deps
      u = 0.002_dp * k
      if (k <= 50) then
        tau_ref = 1000.0_dp * u
        call check(error, sig(3), -200.0_dp, 'sigma_n before yield, step ' // str(k), rel=1.0e-10_dp)
      else
        tau_ref = 100.0_dp + 1000.0_dp / 3.0_dp * (u - 0.1_dp)
        call check(error, sig(3), -2.0_dp * tau_ref, 'sigma_n = -2 tau, step ' // str(k), rel=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, st, state_plastic, 'sliding, step ' // str(k))
      end if
      if (allocated(error)) return
      call check(error, sig(1), tau_ref, 'tau, step ' // str(k), rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, sig(2), 0.0_dp, 'tau2, step ' // str(k), abs=1.0e-12_dp)
      if (allocated(error)) return
    end do
    call check(error, sig(1), 400.0_dp / 3.0_dp, 'end of stage 2: tau = 133.3', rel=1.0e-10_dp)
    if (allocated(error)) return
    call check(error, sig(3), -800.0_dp / 3.0_dp, 'end of stage 2: sigma_n = -266.7', rel=1.0e-10_dp)
  end subroutine test_held_normal_dilation

  !> The same with the thesis's printed 26.57 degrees (tan = 0.50004): the thesis values
  !! tau = 133.3, sigma_n = -266.7 within 0.5 % (the SPEC tolerance).
  subroutine test_held_normal_thesis_angle(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(2), eps(2), deps(2), dt(2, 2)
    integer :: st, k
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 26.57_dp, 26.57_dp)
    sig = 0.0_dp
    eps = 0.0_dp
    st = state_elastic
    deps = [0.0_dp, -0.1_dp]
    call m%update(sig, eps, deps, st, sig, st, dt)
    eps = eps + deps
    deps = [0.002_dp, 0.0_dp]
    do k = 1, 100
      call m%update(sig, eps, deps, st, sig, st, dt)
      eps = eps + deps
    end do
    call check(error, sig(1), 133.3_dp, 'tau', rel=5.0e-3_dp)
    if (allocated(error)) return
    call check(error, sig(2), -266.7_dp, 'sigma_n', rel=5.0e-3_dp)
  end subroutine test_held_normal_thesis_angle

  !> Opening beyond the apex gives zero stress, state open, tangent gap_factor * D; an open
  !! point stays open while eps_n > 0. With cohesion the interface carries tension up to the
  !! apex sigma_n = c / tan phi.
  subroutine test_gap_opening(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), dt(3, 3)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 10.0_dp)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.01_dp, 0.02_dp, 0.05_dp], &
                  state_elastic, sig, st, dt)
    call check(error, st, state_open, 'opened')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, 0.0_dp], 'sig open', 0.0_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, default_gap_factor * diag_d(m, 3), 'open tangent', 0.0_dp)
    if (allocated(error)) return
    ! from compression to opening in one step
    call m%update([10.0_dp, 0.0_dp, -50.0_dp], [0.01_dp, 0.0_dp, -0.025_dp], [0.0_dp, 0.0_dp, 0.03_dp], &
                  state_plastic, sig, st, dt)
    call check(error, st, state_open, 'opened from compression')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, 0.0_dp], 'sig opened from compression', 0.0_dp)
    if (allocated(error)) return
    ! stays open: eps_n = 0.05 - 0.04 > 0 (sig0 of an open point is ignored)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.05_dp], [0.3_dp, 0.0_dp, -0.04_dp], &
                  state_open, sig, st, dt)
    call check(error, st, state_open, 'stays open')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, 0.0_dp], 'sig stays open', 0.0_dp)
    if (allocated(error)) return
    ! cohesion c = 10, phi = 30: apex at sigma_n = 17.32; 10 stays bonded, 20 opens
    m = make(2000.0_dp, 1000.0_dp, 10.0_dp, 30.0_dp, 0.0_dp)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.005_dp], &
                  state_elastic, sig, st, dt)
    call check(error, st, state_elastic, 'cohesive tension below the apex')
    if (allocated(error)) return
    call check(error, sig(3), 10.0_dp, 'cohesive tension', rel=1.0e-14_dp)
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.01_dp], &
                  state_elastic, sig, st, dt)
    call check(error, st, state_open, 'tension beyond the apex opens')
  end subroutine test_gap_opening

  !> KS = 0 is full slip: no shear stress in any state and a zero shear tangent, while the
  !! normal behaviour is the usual one: elastic in compression and in tension below the apex
  !! c / tan phi (phi = 30, c = 10: 17.32), open beyond it. With phi = 0 and c > 0 the gap zone
  !! is never reached, so the contact holds in tension too (bilateral full slip); with
  !! phi = c = 0 it opens at sigma_n >= 0 (unilateral). Nothing divides by the zero hardening
  !! ks + kn tan phi tan psi.
  subroutine test_no_shear_stiffness(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), dt(3, 3), zero(3), d_normal(3, 3)
    integer :: st
    zero = 0.0_dp
    d_normal = 0.0_dp
    d_normal(3, 3) = 2000.0_dp
    m = make(2000.0_dp, 0.0_dp, 10.0_dp, 30.0_dp, 10.0_dp)
    call m%update(zero, zero, [5.0_dp, -3.0_dp, -0.01_dp], state_elastic, sig, st, dt)
    call check(error, st, state_elastic, 'compression with shear: elastic')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, -20.0_dp], 'compression: no shear stress', 1.0e-13_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, d_normal, 'compression: tangent diag(0, 0, kn)', 0.0_dp)
    if (allocated(error)) return
    call m%update(zero, zero, [1.0_dp, 0.0_dp, 0.005_dp], state_elastic, sig, st, dt)
    call check(error, st, state_elastic, 'tension below the apex: elastic')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, 10.0_dp], 'tension below the apex', 1.0e-13_dp)
    if (allocated(error)) return
    call m%update(zero, zero, [1.0_dp, 0.0_dp, 0.01_dp], state_elastic, sig, st, dt)
    call check(error, st, state_open, 'tension beyond the apex (20 > 17.32) opens')
    if (allocated(error)) return
    call check_vector(error, sig, zero, 'open', 0.0_dp)
    if (allocated(error)) return
    ! bilateral: phi = 0, c = 1
    m = make(2000.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp)
    call m%update(zero, zero, [3.0_dp, 4.0_dp, 1.0_dp], state_elastic, sig, st, dt)
    call check(error, st, state_elastic, 'phi = 0, c > 0: tension held')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, 2000.0_dp], 'phi = 0, c > 0: sigma_n = kn eps_n', 1.0e-12_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, d_normal, 'phi = 0, c > 0: tangent diag(0, 0, kn)', 0.0_dp)
    if (allocated(error)) return
    ! unilateral: phi = c = 0, on the surface (f = 0) in compression, and in tension
    m = make(2000.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp)
    call m%update(zero, zero, [1.0_dp, 0.0_dp, -0.01_dp], state_elastic, sig, st, dt)
    call check(error, finite(sig) .and. finite(pack(dt, .true.)), 'phi = c = 0 in compression: finite')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, -20.0_dp], 'phi = c = 0 in compression', 1.0e-13_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, d_normal, 'phi = c = 0 in compression: tangent', 0.0_dp)
    if (allocated(error)) return
    call m%update(zero, zero, [1.0_dp, 0.0_dp, 0.01_dp], state_elastic, sig, st, dt)
    call check(error, st, state_open, 'phi = c = 0 in tension opens')
  end subroutine test_no_shear_stiffness

  !> Eq. 2.3.22: an open point with eps0_n = 0.02 and deps_n = -0.05 closes at t = 0.6:
  !! sig = t D deps, elastic; with a larger shear the restarted trial slides; an open point
  !! already at eps_n <= 0 (t = 1) restarts with D deps.
  subroutine test_closure(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), dt(3, 3), deps(3), t, dfd(3, 3)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 0.0_dp)
    deps = [0.01_dp, 0.004_dp, -0.05_dp]
    t = (0.02_dp - 0.05_dp) / (-0.05_dp)
    ! sig0 of an open point is ignored (it is zero in the gap); pass garbage to show it
    call m%update([7.0_dp, 7.0_dp, 7.0_dp], [0.1_dp, 0.0_dp, 0.02_dp], deps, state_open, sig, st, dt)
    call check(error, st, state_elastic, 'closed, stuck')
    if (allocated(error)) return
    call check_vector(error, sig, t * matmul(diag_d(m, 3), deps), 'sig = t D deps', 1.0e-12_dp)
    if (allocated(error)) return
    call check(error, sig(3), m%kn * (0.02_dp - 0.05_dp), 'sigma_n = kn eps_n', rel=1.0e-13_dp)
    if (allocated(error)) return
    call fd_tangent(m, [7.0_dp, 7.0_dp, 7.0_dp], [0.1_dp, 0.0_dp, 0.02_dp], deps, state_open, dfd)
    call check_matrix(error, dt, dfd, 'closure tangent vs finite differences', 1.0e-6_dp * maxval(abs(dt)))
    if (allocated(error)) return
    ! larger shear: trial tau = 0.6*1000*0.1 = 60 > strength 60 tan 30 = 34.6, slides (psi = 0)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.02_dp], [0.1_dp, 0.0_dp, -0.05_dp], &
                  state_open, sig, st, dt)
    call check(error, st, state_plastic, 'closed, sliding')
    if (allocated(error)) return
    call check_vector(error, sig, [60.0_dp * tan(30.0_dp * deg2rad), 0.0_dp, -60.0_dp], 'closed and returned', &
                      1.0e-12_dp)
    if (allocated(error)) return
    ! open state with eps0_n = 0 (e.g. opened at the apex): whole step in contact
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.001_dp, 0.0_dp, -0.01_dp], &
                  state_open, sig, st, dt)
    call check_vector(error, sig, [1.0_dp, 0.0_dp, -20.0_dp], 'closure with t = 1', 1.0e-12_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, diag_d(m, 3), 'closure with t = 1: tangent D', 0.0_dp)
    if (allocated(error)) return
    ! reaching exactly eps_n = 0 (c = 0): touching with zero stress remains open
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.01_dp], [0.0_dp, 0.0_dp, -0.01_dp], &
                  state_open, sig, st, dt)
    call check(error, st, state_open, 'eps_n = 0 exactly with c = 0: zero stress, open')
    if (allocated(error)) return
    call check(error, finite(sig) .and. finite(reshape(dt, [9])), 'eps_n = 0 exactly: finite')
  end subroutine test_closure

  !> c = 20, phi = 30, psi = 0: slides at tau = c - sigma_n tan phi, in compression and in
  !! tension below the apex.
  subroutine test_cohesion(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(2), dt(2, 2)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 20.0_dp, 30.0_dp, 0.0_dp)
    call m%update([0.0_dp, -50.0_dp], [0.0_dp, -0.025_dp], [0.5_dp, 0.0_dp], state_elastic, sig, st, dt)
    call check(error, st, state_plastic, 'sliding')
    if (allocated(error)) return
    call check(error, sig(1), 20.0_dp + 50.0_dp * tan(30.0_dp * deg2rad), 'tau = c - sigma_n tan phi', rel=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, sig(2), -50.0_dp, 'sigma_n', rel=1.0e-14_dp)
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], [-0.5_dp, 0.005_dp], state_elastic, sig, st, dt)
    call check(error, st, state_plastic, 'sliding in tension')
    if (allocated(error)) return
    call check(error, sig(1), -(20.0_dp - 10.0_dp * tan(30.0_dp * deg2rad)), 'tau in tension', rel=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, sig(2), 10.0_dp, 'sigma_n in tension', rel=1.0e-14_dp)
    if (allocated(error)) return
    ! just inside the cohesive surface: stuck
    call m%update([0.0_dp, -50.0_dp], [0.0_dp, -0.025_dp], [0.048_dp, 0.0_dp], state_elastic, sig, st, dt)
    call check(error, st, state_elastic, 'tau = 48 < 48.87 stuck')
  end subroutine test_cohesion

  !> A trial exactly on the surface (tau_tr = 100, sigma_n = -200, tan phi = 0.5): stress =
  !! trial, on the surface, sliding state with the elastic-plastic tangent.
  subroutine test_trial_on_surface(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(2), dt(2, 2)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, phi_half, phi_half)
    call m%update([0.0_dp, -200.0_dp], [0.0_dp, -0.1_dp], [0.1_dp, 0.0_dp], state_elastic, sig, st, dt)
    call check(error, st, state_plastic, 'on the surface: sliding state')
    if (allocated(error)) return
    call check_vector(error, sig, [100.0_dp, -200.0_dp], 'stress = trial', 1.0e-10_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, continuum_dep(m, sig), 'tangent = D_ep', 1.0e-9_dp)
  end subroutine test_trial_on_surface

  !> c = 0 at zero stress is the apex: no step produces NaN; a zero step or pure opening
  !! leaves the point open with zero stress; compression then closes it (t = 1). tau_tr = 0
  !! under compression is elastic; phi = c = 0 (frictionless) slides to tau = 0 in contact.
  subroutine test_apex(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), dt(3, 3)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 20.0_dp)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    call check(error, finite(sig) .and. finite(reshape(dt, [9])), 'apex, zero step: finite')
    if (allocated(error)) return
    call check(error, st, state_open, 'apex, zero step: open (zero strength)')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, 0.0_dp], 'apex, zero step: sig', 0.0_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, default_gap_factor * diag_d(m, 3), 'apex tangent', 0.0_dp)
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0e-3_dp], &
                  state_elastic, sig, st, dt)
    call check(error, st, state_open, 'apex, pure opening: open')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, 0.0_dp], 'apex, pure opening: sig', 0.0_dp)
    if (allocated(error)) return
    ! pure shear at zero normal stress with the normal displacement held: the dilatant slip
    ! (psi = 20) presses the layers together, tau = tau_tr kn tan phi tan psi / h and
    ! sigma_n = -kn tan psi tau_tr / h, on the cone tau = -sigma_n tan phi (constant normal
    ! displacement direct shear of a cohesionless joint)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [1.0e-3_dp, 0.0_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    block
      real(dp) :: tphi, tpsi, h
      tphi = tan(30.0_dp * deg2rad)
      tpsi = tan(20.0_dp * deg2rad)
      h = 1000.0_dp + 2000.0_dp * tphi * tpsi
      call check(error, st, state_plastic, 'apex, pure shear, psi = 20: slides in contact')
      if (allocated(error)) return
      call check_vector(error, sig, [2000.0_dp * tphi * tpsi / h, 0.0_dp, -2000.0_dp * tpsi / h], &
                        'apex, pure shear, psi = 20: sig', 1.0e-14_dp)
      if (allocated(error)) return
      call check(error, sig(1), -sig(3) * tphi, 'apex, pure shear, psi = 20: on the cone', rel=1.0e-13_dp)
      if (allocated(error)) return
    end block
    ! without dilation nothing holds the layers together: open
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 0.0_dp)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [1.0e-3_dp, 0.0_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    call check(error, st == state_open .and. all(sig == 0.0_dp), 'apex, pure shear, psi = 0: open, zero stress')
    if (allocated(error)) return
    ! closing from the apex state
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 20.0_dp)
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, -1.0e-3_dp], state_open, &
                  sig, st, dt)
    call check(error, st, state_elastic, 'closed from apex')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, -2.0_dp], 'closed from apex: sig', 1.0e-14_dp)
    if (allocated(error)) return
    ! tau_tr = 0 with compression
    call m%update([0.0_dp, 0.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [0.0_dp, 0.0_dp, 0.0_dp], &
                  state_plastic, sig, st, dt)
    call check(error, st, state_elastic, 'tau_tr = 0 in compression: stuck')
    if (allocated(error)) return
    call check_matrix(error, dt, diag_d(m, 3), 'tau_tr = 0: tangent D', 0.0_dp)
    if (allocated(error)) return
    ! frictionless, cohesionless: contact in compression, zero shear, finite
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, 0.0_dp, 0.0_dp)
    call m%update([0.0_dp, 0.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [0.0_dp, 0.0_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    call check(error, finite(sig) .and. finite(reshape(dt, [9])), 'frictionless, tau_tr = 0: finite')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, -100.0_dp], 'frictionless, tau_tr = 0: sig', 0.0_dp)
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [0.01_dp, 0.02_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    call check(error, st, state_plastic, 'frictionless slides')
    if (allocated(error)) return
    call check_vector(error, sig, [0.0_dp, 0.0_dp, -100.0_dp], 'frictionless: zero shear', 1.0e-12_dp)
    if (allocated(error)) return
    call check(error, dt(3, 3), m%kn, 'frictionless: normal stiffness kept')
  end subroutine test_apex

  !> The stress update is continuous in the trial stress, but for the brittle loss of the
  !! tensile strength c / tan phi where a point opens: along sigma_n_tr from -10 to +10 at fixed
  !! tau_tr = 4 (phi = 30; c = 0 and 0.5; psi = 20 and 0; 2001 points, spacing 0.01) no two
  !! neighbouring results differ by more than the Lipschitz bound 2 x spacing x (1 + kn/ks) plus,
  !! for c > 0, c / tan phi. Testing the trial stress itself against the gap zone
  !! c - sigma_n tan phi <= 0 made the stress jump from the cone to zero there, by about
  !! tau_tr kn tan phi tan psi / h (1.7 MPa here) when psi > 0; the thesis's integration along
  !! the strain path enters the gap only where the return reaches the apex.
  subroutine test_gap_continuity(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), prev(3), dt(3, 3), sn, worst, bound
    integer :: st, k, ipsi, ic, nopen
    real(dp), parameter :: psis(2) = [20.0_dp, 0.0_dp], cs(2) = [0.0_dp, 0.5_dp], spacing = 0.01_dp
    character(len=:), allocatable :: what
    do ic = 1, 2
      do ipsi = 1, 2
        m = make(2000.0_dp, 1000.0_dp, cs(ic), 30.0_dp, psis(ipsi))
        what = 'c = ' // str(cs(ic)) // ', psi = ' // str(psis(ipsi))
        bound = 2.0_dp * spacing * (1.0_dp + 2000.0_dp / 1000.0_dp) + cs(ic) / tan(30.0_dp * deg2rad)
        worst = 0.0_dp
        nopen = 0
        do k = 0, 2000
          sn = -10.0_dp + spacing * k
          call m%update([4.0_dp, 0.0_dp, sn], [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.0_dp], state_elastic, &
                        sig, st, dt)
          if (st == state_open) nopen = nopen + 1
          if (k > 0) worst = max(worst, norm2(sig - prev))
          prev = sig
        end do
        call check(error, nopen > 0 .and. nopen < 2000, what // ': the sweep crosses into the gap')
        if (allocated(error)) return
        call check(error, worst <= bound, what // ': largest jump between neighbours ' // str(worst) // &
                   ' MPa, bound ' // str(bound))
        if (allocated(error)) return
      end do
    end do
  end subroutine test_gap_continuity

  !> 3D slip along (0.6, 0.8) with c = 5, phi = 30, psi = 10: the shear keeps its direction,
  !! tau = tau_tr - ks dlambda and sigma_n = sigma_n_tr - kn tan psi dlambda land on the surface.
  subroutine test_oblique_slip(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), dt(3, 3), tphi, tpsi, dl, tau, sn
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 5.0_dp, 30.0_dp, 10.0_dp)
    tphi = tan(30.0_dp * deg2rad)
    tpsi = tan(10.0_dp * deg2rad)
    call m%update([0.0_dp, 0.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [0.3_dp, 0.4_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    ! F(sig) = 0 with tau = 500 - ks dl, sn = -100 - kn tpsi dl (linear in dl)
    dl = (500.0_dp - 5.0_dp - 100.0_dp * tphi) / (1000.0_dp + 2000.0_dp * tphi * tpsi)
    tau = 500.0_dp - 1000.0_dp * dl
    sn = -100.0_dp - 2000.0_dp * tpsi * dl
    call check(error, st, state_plastic, 'sliding')
    if (allocated(error)) return
    call check(error, sig(2) / sig(1), 0.8_dp / 0.6_dp, 'slip direction kept', rel=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, norm2(sig(1:2)), tau, 'tau', rel=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, sig(3), sn, 'sigma_n (dilation against the held normal)', rel=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, norm2(sig(1:2)), 5.0_dp - sig(3) * tphi, 'on the yield surface', rel=1.0e-13_dp)
  end subroutine test_oblique_slip

  !> dtan against central differences of the update, 1e-6 relative to the largest entry.
  subroutine test_tangent_fd(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: mats(3)
    real(dp) :: sig3(3), dt3(3, 3), fd3(3, 3), sig2(2), dt2(2, 2), fd2(2, 2)
    real(dp), parameter :: sig0_3(3) = [3.0_dp, -4.0_dp, -100.0_dp], eps0_3(3) = [0.0_dp, 0.0_dp, -0.05_dp]
    real(dp), parameter :: sig0_2(2) = [3.0_dp, -100.0_dp], eps0_2(2) = [0.0_dp, -0.05_dp]
    real(dp) :: deps3(3), deps2(2)
    integer :: st, k, icase, expected
    character(len=:), allocatable :: what
    mats(1) = make(2000.0_dp, 1000.0_dp, 5.0_dp, 30.0_dp, 0.0_dp)
    mats(2) = make(2000.0_dp, 1000.0_dp, 5.0_dp, 30.0_dp, 30.0_dp)
    mats(3) = make(3000.0_dp, 800.0_dp, 5.0_dp, 35.0_dp, 12.0_dp)
    do k = 1, size(mats)
      do icase = 1, 2
        if (icase == 1) then   ! elastic
          deps3 = [0.004_dp, 0.003_dp, -0.01_dp]
          deps2 = [-0.004_dp, -0.01_dp]
          expected = state_elastic
        else                   ! sliding, oblique in 3D
          deps3 = [0.2_dp, -0.1_dp, 0.005_dp]
          deps2 = [-0.2_dp, 0.005_dp]
          expected = state_plastic
        end if
        what = 'material ' // str(k) // ' case ' // str(icase)
        call mats(k)%update(sig0_3, eps0_3, deps3, state_elastic, sig3, st, dt3)
        call check(error, st, expected, what // ' 3D state')
        if (allocated(error)) return
        call fd_tangent(mats(k), sig0_3, eps0_3, deps3, state_elastic, fd3)
        call check_matrix(error, dt3, fd3, what // ' 3D tangent', 1.0e-6_dp * maxval(abs(dt3)))
        if (allocated(error)) return
        call mats(k)%update(sig0_2, eps0_2, deps2, state_elastic, sig2, st, dt2)
        call check(error, st, expected, what // ' 2D state')
        if (allocated(error)) return
        call fd_tangent(mats(k), sig0_2, eps0_2, deps2, state_elastic, fd2)
        call check_matrix(error, dt2, fd2, what // ' 2D tangent', 1.0e-6_dp * maxval(abs(dt2)))
        if (allocated(error)) return
      end do
    end do
    ! the 3D sliding tangent differs from the continuum one by the factor tau/tau_tr
    call mats(3)%update(sig0_3, eps0_3, [0.2_dp, -0.1_dp, 0.005_dp], state_elastic, sig3, st, dt3)
    call check(error, maxval(abs(dt3 - continuum_dep(mats(3), sig3))) > 1.0e-2_dp * maxval(abs(dt3)), &
               'finite 3D step: algorithmic tangent differs from D_ep')
  end subroutine test_tangent_fd

  !> A vanishing step from a point on the yield surface: dtan = eq. 2.3.18 evaluated there.
  subroutine test_tangent_continuum(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig0(3), sig(3), dt(3, 3), tau, sig2(2), dt2(2, 2)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 10.0_dp, 30.0_dp, 15.0_dp)
    tau = 10.0_dp + 80.0_dp * tan(30.0_dp * deg2rad)
    sig0 = [0.6_dp * tau, -0.8_dp * tau, -80.0_dp]
    call m%update(sig0, [0.0_dp, 0.0_dp, -0.04_dp], [0.0_dp, 0.0_dp, 0.0_dp], state_plastic, sig, st, dt)
    call check(error, st, state_plastic, '3D sliding')
    if (allocated(error)) return
    call check_vector(error, sig, sig0, '3D stress unchanged', 1.0e-12_dp)
    if (allocated(error)) return
    call check_matrix(error, dt, continuum_dep(m, sig0), '3D tangent = eq. 2.3.18', 1.0e-10_dp * maxval(abs(dt)))
    if (allocated(error)) return
    call m%update([-tau, -80.0_dp], [0.0_dp, -0.04_dp], [0.0_dp, 0.0_dp], state_plastic, sig2, st, dt2)
    call check(error, st, state_plastic, '2D sliding')
    if (allocated(error)) return
    call check_matrix(error, dt2, continuum_dep(m, [-tau, -80.0_dp]), '2D tangent = eq. 2.3.18', &
                      1.0e-10_dp * maxval(abs(dt2)))
  end subroutine test_tangent_continuum

  !> symmetric_tangent is psi == phi, and the sliding tangent is symmetric exactly then.
  subroutine test_symmetric(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), dt(3, 3)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 5.0_dp, 30.0_dp, 30.0_dp)
    call check(error, m%symmetric_tangent(), 'psi = phi: symmetric')
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [0.3_dp, 0.1_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    call check(error, maxval(abs(dt - transpose(dt))), 0.0_dp, 'psi = phi: dtan symmetric', &
               abs=1.0e-12_dp * maxval(abs(dt)))
    if (allocated(error)) return
    m = make(2000.0_dp, 1000.0_dp, 5.0_dp, 30.0_dp, 10.0_dp)
    call check(error, .not. m%symmetric_tangent(), 'psi < phi: not symmetric')
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, -100.0_dp], [0.0_dp, 0.0_dp, -0.05_dp], [0.3_dp, 0.1_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    call check(error, maxval(abs(dt - transpose(dt))) > 1.0e-3_dp * maxval(abs(dt)), &
               'psi < phi: dtan non-symmetric')
  end subroutine test_symmetric


  subroutine test_validator(error)
    type(error_t), allocatable, intent(out) :: error
    class(material_t), allocatable :: mat
    type(error_t), allocatable :: err
    character(len=name_len), parameter :: k3(3) = [character(len=name_len) :: 'kn', 'ks', 'phi']
    character(len=name_len), parameter :: k5(5) = [character(len=name_len) :: 'kn', 'ks', 'c', 'phi', 'psi']
    call new_interface_mohr_coulomb(material_spec('joint', 'interface', k5, &
                                  [2000.0_dp, 1000.0_dp, 5.0_dp, 30.0_dp, 10.0_dp]), mat, err)
    if (allocated(err)) then
      call test_failed(error, 'valid parameters rejected: ' // err%message)
      return
    end if
    select type (mat)
    type is (interface_mohr_coulomb_t)
      call check(error, mat%kn == 2000.0_dp .and. mat%ks == 1000.0_dp .and. mat%c == 5.0_dp .and. &
                 mat%phi == 30.0_dp .and. mat%psi == 10.0_dp .and. mat%name == 'joint', 'parameters stored')
    class default
      call test_failed(error, 'wrong material type')
    end select
    if (allocated(error)) return
    call new_interface_mohr_coulomb(material_spec('joint', 'interface', k3, [2000.0_dp, 0.0_dp, 30.0_dp]), mat, err)
    if (allocated(err)) then
      call test_failed(error, 'KS = 0 (full slip) rejected: ' // err%message)
      return
    end if
    call new_interface_mohr_coulomb(material_spec('joint', 'interface', k3, [2000.0_dp, 1000.0_dp, 30.0_dp]), mat, err)
    if (allocated(err)) then
      call test_failed(error, 'c and psi should default: ' // err%message)
      return
    end if
    select type (mat)
    type is (interface_mohr_coulomb_t)
      call check(error, mat%c == 0.0_dp .and. mat%psi == 0.0_dp, 'c and psi default to 0')
    class default
      call test_failed(error, 'wrong material type')
    end select
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', ['ks ', 'phi'], [1000.0_dp, 30.0_dp], 'KN is missing', &
                                  field=0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', ['kn ', 'phi'], [1000.0_dp, 30.0_dp], 'KS is missing', &
                                  field=0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', ['kn', 'ks'], [1000.0_dp, 30.0_dp], 'PHI is missing', &
                                  field=0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [0.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 0.0_dp], 'KN = ', &
                                  field=4)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [2000.0_dp, -1.0_dp, 0.0_dp, 30.0_dp, 0.0_dp], 'KS = ', &
                                  field=5)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [2000.0_dp, 1000.0_dp, -1.0_dp, 30.0_dp, 0.0_dp], 'C = ', &
                                  field=6)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [2000.0_dp, 1000.0_dp, 0.0_dp, 90.0_dp, 0.0_dp], 'PHI = ', &
                                  field=7)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [2000.0_dp, 1000.0_dp, 0.0_dp, -5.0_dp, 0.0_dp], 'PHI = ', &
                                  field=7)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 31.0_dp], 'PSI = ', &
                                  field=8)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, -1.0_dp], 'PSI = ', &
                                  field=8)
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', ['kn ', 'ks ', 'phi', 'ps '], &
                                  [2000.0_dp, 1000.0_dp, 30.0_dp, 10.0_dp], 'unknown parameter PS ', field=7)
    if (allocated(error)) return
    ! A record built without field numbers: the same errors, naming no field.
    call expect_material_rejected(error, 'joint', 'interface', ['kn ', 'ks ', 'phi', 'ps '], &
                                  [2000.0_dp, 1000.0_dp, 30.0_dp, 10.0_dp], 'unknown parameter PS ')
    if (allocated(error)) return
    call expect_material_rejected(error, 'joint', 'interface', k5, [2000.0_dp, 1000.0_dp, 0.0_dp, 30.0_dp, 31.0_dp], 'PSI = ')
  end subroutine test_validator

  !> 7200 random steps (fixed seed) over phi = 0 .. 89.9 deg, psi = 0, phi/2, phi, c = 0 and 0.5,
  !! kn/ks = 2, 1e6 and 1e-6, 2D and 3D, from stuck and from open points (closing or not), each
  !! checked against the thesis's conditions computed here, not by the module: the trial (eq.
  !! 2.3.21; eq. 2.3.22 for a closing gap); a trial inside f < 0 (eq. 2.3.14) stays, unchanged;
  !! a point opens exactly where the return along D dg/dsigma reaches the apex, i.e. where
  !! sigma_tr - apex = dlambda D n for some n in the subdifferential {(y, tan psi): |y| <= 1} of
  !! the potential cone there (sigma_n >= c / tan phi and tau_tr kn tan psi <= ks (sigma_n_tr -
  !! c / tan phi)); a sliding point lies on f = 0 with c - sigma_n tan phi >= 0 (1e-12 of the
  !! stress scale) and sigma_tr - sigma = dlambda D dg/dsigma (eq. 2.3.20, c_I from f = g) with
  !! dlambda >= 0 (misfit 1e-9). Trials within 1e-9 of a border are not classified. Every kind
  !! of result must occur. (The audit of 2026-11-23 ran the same checks on 14 080 steps and 176
  !! paths of 60 steps against a numpy Newton solution of the thesis's equations.)
  subroutine test_random_conditions(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: angles(5) = [0.0_dp, 10.0_dp, 26.57_dp, 60.0_dp, 89.9_dp]
    real(dp), parameter :: kns(3) = [800.0_dp, 1.0e6_dp, 1.0_dp], kss(3) = [400.0_dp, 1.0_dp, 1.0e6_dp]
    type(interface_mohr_coulomb_t) :: m
    integer(kind=8) :: seed
    integer :: i, j, ic, ik, n, k, counts(0:2)
    seed = 8675309_8
    counts = 0
    do i = 1, size(angles)
      do j = 0, 2
        do ic = 0, 1
          do ik = 1, size(kns)
            m = make(kns(ik), kss(ik), 0.5_dp * ic, angles(i), 0.5_dp * j * angles(i))
            do n = 2, 3
              do k = 1, 40
                call check_random_step(error, m, n, seed, counts)
                if (allocated(error)) return
              end do
            end do
          end do
        end do
      end do
    end do
    call check(error, all(counts > 500), 'every kind of result occurs: stuck ' // str(counts(0)) // ', sliding ' // &
               str(counts(1)) // ', open ' // str(counts(2)))
  end subroutine test_random_conditions

  subroutine check_random_step(error, m, n, seed, counts)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t), intent(in) :: m
    integer, intent(in) :: n
    integer(kind=8), intent(inout) :: seed
    integer, intent(inout) :: counts(0:2)
    real(dp) :: sig0(n), eps0(n), deps(n), sig(n), dt(n, n), sig_tr(n), d(n, n), g(n), v(n), ret(n)
    real(dp) :: sc, tphi, tpsi, tau_tr, strength_tr, tau, strength, scale, t, dl, reach
    integer :: st, st0, i
    character(len=:), allocatable :: what
    sc = 10.0_dp**(4.0_dp * uniform(seed) - 2.0_dp)
    do i = 1, n
      sig0(i) = sc * (2.0_dp * uniform(seed) - 1.0_dp)
      eps0(i) = sc / m%kn * (2.0_dp * uniform(seed) - 1.0_dp)
      deps(i) = sc / min(m%kn, m%ks) * (2.0_dp * uniform(seed) - 1.0_dp)
    end do
    st0 = state_elastic
    if (uniform(seed) < 0.3_dp) then
      st0 = state_open
      sig0 = 0.0_dp
    end if
    call m%update(sig0, eps0, deps, st0, sig, st, dt)
    what = 'phi ' // str(m%phi) // ' psi ' // str(m%psi) // ' c ' // str(m%c) // ' kn ' // str(m%kn) // &
           ' n ' // str(n) // ' state0 ' // str(st0)
    call check(error, finite(sig) .and. finite(reshape(dt, [n * n])), what // ': finite')
    if (allocated(error)) return
    counts(st) = counts(st) + 1
    d = diag_d(m, n)
    tphi = tan(m%phi * deg2rad)
    tpsi = tan(m%psi * deg2rad)
    if (st0 == state_open) then
      if (eps0(n) + deps(n) > 0.0_dp) then
        call check(error, st == state_open .and. all(sig == 0.0_dp), what // ': stays open while eps_n > 0')
        return
      end if
      ! eq. 2.3.22: eps_n0 + (1 - t) deps_n = 0, or t = 1 when already closed at the start
      t = 1.0_dp
      if (eps0(n) > 0.0_dp) t = (eps0(n) + deps(n)) / deps(n)
      sig_tr = t * matmul(d, deps)
      sig_tr(n) = m%kn * (eps0(n) + deps(n))
    else
      sig_tr = sig0 + matmul(d, deps)
    end if
    tau_tr = norm2(sig_tr(1:n - 1))
    strength_tr = m%c - sig_tr(n) * tphi
    scale = maxval(abs(sig_tr)) + m%c
    ! the opening test multiplied by tan phi (no apex when phi = 0: phi = c = 0 opens under tension)
    reach = m%ks * (sig_tr(n) * tphi - m%c) - tau_tr * m%kn * tphi * tpsi
    if (tau_tr - strength_tr < -1.0e-9_dp * scale .and. strength_tr > 1.0e-9_dp * scale) then
      call check(error, st == state_elastic .and. maxval(abs(sig - sig_tr)) <= 1.0e-14_dp * scale, &
                 what // ': inside f < 0: stuck, the trial')
    else if (sig_tr(n) > 1.0e-9_dp * scale .and. reach > 1.0e-9_dp * scale * max(m%ks, m%kn) * max(tphi, 1.0_dp)) then
      call check(error, st == state_open .and. all(sig == 0.0_dp), what // ': the return reaches the apex: open')
    else if (reach < -1.0e-9_dp * scale * max(m%ks, m%kn) * max(tphi, 1.0_dp) .or. sig_tr(n) < -1.0e-9_dp * scale) then
      call check(error, st, state_plastic, what // ': sliding')
      if (allocated(error)) return
      tau = norm2(sig(1:n - 1))
      strength = m%c - sig(n) * tphi
      call check(error, tau, strength, what // ': on f = 0', abs=1.0e-12_dp * scale)
      if (allocated(error)) return
      call check(error, strength >= -1.0e-12_dp * scale, what // ': c - sigma_n tan phi >= 0')
      if (allocated(error)) return
      ret = sig_tr - sig
      if (tau > 0.0_dp) then
        g(1:n - 1) = sig(1:n - 1)   ! eq. 2.3.20 halved, (c_I - sigma_n tan psi) = c - sigma_n tan phi
        g(n) = strength * tpsi
        v = matmul(d, g)
        dl = dot_product(ret, v) / dot_product(v, v)
        call check(error, dl >= 0.0_dp, what // ': dlambda >= 0')
        if (allocated(error)) return
        call check(error, norm2(ret - dl * v), 0.0_dp, what // ': sigma_tr - sigma along D dg/dsigma', &
                   abs=1.0e-9_dp * max(norm2(ret), tiny(1.0_dp)))
      else
        ! a zero-strength point (phi = c = 0 in compression): no shear, sigma_n unchanged (psi <= phi = 0)
        call check(error, abs(sig(n) - sig_tr(n)) <= 1.0e-12_dp * scale, what // ': zero strength, sigma_n kept')
      end if
    end if
  end subroutine check_random_step

  !> A deterministic uniform number in (0, 1) (Park-Miller minimal standard generator).
  real(dp) function uniform(seed) result(u)
    integer(kind=8), intent(inout) :: seed
    seed = modulo(16807_8 * seed, 2147483647_8)
    u = real(seed, dp) / 2147483647.0_dp
  end function uniform

  !> Steps 1e6 times the elastic limit (u = 0.1 for sigma_n = -200, tan phi = 0.5) in shear,
  !! opening, closure and compression: finite results, sliding ones on the yield surface.
  subroutine test_huge_steps(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_mohr_coulomb_t) :: m
    real(dp) :: sig(3), dt(3, 3), sig2(2), dt2(2, 2)
    integer :: st
    m = make(2000.0_dp, 1000.0_dp, 0.0_dp, phi_half, 10.0_dp)
    call m%update([0.0_dp, 0.0_dp, -200.0_dp], [0.0_dp, 0.0_dp, -0.1_dp], [1.0e5_dp, -3.0e4_dp, 0.0_dp], &
                  state_elastic, sig, st, dt)
    call check(error, finite(sig) .and. finite(reshape(dt, [9])), 'huge shear: finite')
    if (allocated(error)) return
    call check(error, st, state_plastic, 'huge shear: sliding')
    if (allocated(error)) return
    call check(error, norm2(sig(1:2)), -0.5_dp * sig(3), 'huge shear: on the surface', rel=1.0e-10_dp)
    if (allocated(error)) return
    call m%update([0.0_dp, -200.0_dp], [0.0_dp, -0.1_dp], [-1.0e5_dp, 0.0_dp], state_elastic, sig2, st, dt2)
    call check(error, finite(sig2) .and. finite(reshape(dt2, [4])) .and. st == state_plastic, 'huge shear 2D')
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, -200.0_dp], [0.0_dp, 0.0_dp, -0.1_dp], [1.0e5_dp, 0.0_dp, 1.0e5_dp], &
                  state_elastic, sig, st, dt)
    call check(error, finite(sig) .and. st == state_open, 'huge opening: finite, open')
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 0.05_dp], [1.0e5_dp, 1.0e5_dp, -1.0e5_dp], &
                  state_open, sig, st, dt)
    call check(error, finite(sig) .and. finite(reshape(dt, [9])) .and. st == state_plastic, 'huge closure')
    if (allocated(error)) return
    call check(error, norm2(sig(1:2)), -0.5_dp * sig(3), 'huge closure: on the surface', rel=1.0e-10_dp)
    if (allocated(error)) return
    call m%update([0.0_dp, 0.0_dp, -200.0_dp], [0.0_dp, 0.0_dp, -0.1_dp], [0.0_dp, 0.0_dp, -1.0e5_dp], &
                  state_elastic, sig, st, dt)
    call check(error, finite(sig) .and. st == state_elastic, 'huge compression: finite, stuck')
  end subroutine test_huge_steps

end module test_interface_mc
