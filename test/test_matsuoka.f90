!> Tests of the modified Matsuoka-Nakai model (thesis 2.4.2-2.4.3, SPEC section 5): the
!! surface against Mohr-Coulomb on the meridians, the uniaxial strengths (15.71 / 6 MPa,
!! ft/fc = 1/10 at 54.9 deg), returns onto the surface with the flow rule, the apex and the
!! tension zone, the consistent tangent against finite differences, rotation invariance,
!! the uniaxial strain-driven block example, the elastic range of nu, huge steps for a range
!! of angles and the parameter checks; both tension-zone rules (the thesis's proportional
!! return, discontinuous, and the continuous closest-point return with its apex).
module test_matsuoka
  use feps_kinds, only: dp, deg2rad
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_material_testing, only: material_spec, record_fields, expect_material_rejected
  use feps_model, only: material_spec_t, name_len
  use feps_material, only: material_t, state_elastic, state_plastic, state_tension
  use feps_matsuoka_nakai, only: matsuoka_nakai_t, new_matsuoka_nakai, apex_from_tensile_strength, &
                                 apex_from_cohesion, apex_stiffness_factor, tension_proportional, &
                                 tension_closest_point
  implicit none
  private

  public :: collect_matsuoka

  real(dp), parameter :: e_block = 10000.0_dp, nu_block = 0.2_dp, phi_block = 26.57_dp, ft_block = 6.0_dp
  real(dp), parameter :: zero6(6) = 0.0_dp

contains

  subroutine collect_matsuoka(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("mohr_coulomb_meridians", test_meridians), &
      new_unittest("uniaxial_strengths", test_uniaxial_strengths), &
      new_unittest("elastic_step_and_nu_range", test_elastic_nu), &
      new_unittest("random_returns_on_surface", test_random_returns), &
      new_unittest("apex_and_tension_zone", test_apex_tension), &
      new_unittest("tension_rules_continuity", test_tension_continuity), &
      new_unittest("closest_point_tension_returns", test_closest_point_returns), &
      new_unittest("tangent_finite_difference", test_tangent_fd), &
      new_unittest("rotation_invariance", test_rotation), &
      new_unittest("uniaxial_block_path_2_4_3", test_block_path), &
      new_unittest("angles_and_huge_steps", test_huge_steps), &
      new_unittest("numpy_reference_returns", test_numpy_reference), &
      new_unittest("flow_along_thesis_potential_2_4_12", test_thesis_potential_flow), &
      new_unittest("closest_point_apex_region", test_apex_region), &
      new_unittest("validator", test_validator) &
      ]
  end subroutine collect_matsuoka

  ! ---------------------------------------------------------------- helpers

  pure function make(phi, psi, ft, e, nu, tension) result(m)
    real(dp), intent(in) :: phi, psi, ft
    real(dp), intent(in), optional :: e, nu
    integer, intent(in), optional :: tension
    type(matsuoka_nakai_t) :: m
    m = matsuoka_nakai_t(name='concrete', e=e_block, nu=nu_block, phi=phi, psi=psi, &
                         apex=apex_from_tensile_strength(ft, phi))
    if (present(e)) m%e = e
    if (present(nu)) m%nu = nu
    if (present(tension)) m%tension = tension
  end function make

  pure logical function finite(x)
    real(dp), intent(in) :: x(:)
    finite = all(x == x) .and. all(abs(x) <= huge(x))
  end function finite

  !> Independent isotropic elasticity (Lame form) and its inverse (engineering shears).
  pure function d_matrix(e, nu) result(d)
    real(dp), intent(in) :: e, nu
    real(dp) :: d(6, 6)
    real(dp) :: c
    integer :: i
    c = e / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
    d = 0.0_dp
    d(1:3, 1:3) = c * nu
    do i = 1, 3
      d(i, i) = c * (1.0_dp - nu)
      d(i + 3, i + 3) = 0.5_dp * c * (1.0_dp - 2.0_dp * nu)
    end do
  end function d_matrix

  pure function compliance(e, nu, sig) result(eps)
    real(dp), intent(in) :: e, nu, sig(6)
    real(dp) :: eps(6)
    eps(1) = (sig(1) - nu * (sig(2) + sig(3))) / e
    eps(2) = (sig(2) - nu * (sig(1) + sig(3))) / e
    eps(3) = (sig(3) - nu * (sig(1) + sig(2))) / e
    eps(4:6) = 2.0_dp * (1.0_dp + nu) / e * sig(4:6)
  end function compliance

  !> The thesis cubic in compression-positive sigma* = M I - sigma, computed here from the
  !! invariants (independent of the module), relative to |I1 I2| + zeta |I3|.
  pure real(dp) function relative_cubic(m, sig) result(rel)
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp), intent(in) :: sig(6)
    real(dp) :: a(3, 3), i1, i2, i3, zeta
    a = -reshape([sig(1), sig(6), sig(5), sig(6), sig(2), sig(4), sig(5), sig(4), sig(3)], [3, 3])
    a(1, 1) = a(1, 1) + m%apex
    a(2, 2) = a(2, 2) + m%apex
    a(3, 3) = a(3, 3) + m%apex
    zeta = 9.0_dp + 8.0_dp * tan(m%phi * deg2rad)**2
    i1 = a(1, 1) + a(2, 2) + a(3, 3)
    i2 = a(1, 1) * a(2, 2) - a(1, 2)**2 + a(2, 2) * a(3, 3) - a(2, 3)**2 + a(1, 1) * a(3, 3) - a(1, 3)**2
    i3 = a(1, 1) * (a(2, 2) * a(3, 3) - a(2, 3)**2) - a(1, 2) * (a(1, 2) * a(3, 3) - a(2, 3) * a(1, 3)) &
         + a(1, 3) * (a(1, 2) * a(2, 3) - a(2, 2) * a(1, 3))
    rel = 0.0_dp
    if (abs(i1 * i2) + zeta * abs(i3) > 0.0_dp) rel = (i1 * i2 - zeta * i3) / (abs(i1 * i2) + zeta * abs(i3))
  end function relative_cubic

  !> Scale of the yield value of a stress (to make |F| relative).
  pure real(dp) function stress_scale(m, sig)
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp), intent(in) :: sig(6)
    stress_scale = maxval(abs(sig)) + m%apex
  end function stress_scale

  !> The t in [lo, hi] with F(base + t dir) = 0 by bisection (F(lo) < 0 < F(hi)).
  real(dp) function surface_along(m, base, dir, lo, hi) result(t)
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp), intent(in) :: base(6), dir(6), lo, hi
    real(dp) :: a, b
    integer :: i
    a = lo
    b = hi
    do i = 1, 200
      t = 0.5_dp * (a + b)
      if (m%yield_value(base + t * dir) > 0.0_dp) then
        b = t
      else
        a = t
      end if
      if (b - a <= 1.0e-15_dp * max(abs(a), abs(b))) exit
    end do
    t = 0.5_dp * (a + b)
  end function surface_along

  !> A deterministic uniform number in (0, 1) (Park-Miller minimal standard generator).
  real(dp) function next_uniform(seed) result(u)
    integer(kind=8), intent(inout) :: seed
    seed = modulo(16807_8 * seed, 2147483647_8)
    u = real(seed, dp) / 2147483647.0_dp
  end function next_uniform

  !> Voigt stress of R S R^T for S given in Voigt form.
  pure function rotate_stress(r, sig) result(out)
    real(dp), intent(in) :: r(3, 3), sig(6)
    real(dp) :: out(6), s(3, 3)
    s = reshape([sig(1), sig(6), sig(5), sig(6), sig(2), sig(4), sig(5), sig(4), sig(3)], [3, 3])
    s = matmul(r, matmul(s, transpose(r)))
    out = [s(1, 1), s(2, 2), s(3, 3), s(2, 3), s(1, 3), s(1, 2)]
  end function rotate_stress

  pure function rotation(a, b, c) result(r)
    real(dp), intent(in) :: a, b, c
    real(dp) :: r(3, 3), rx(3, 3), ry(3, 3), rz(3, 3)
    rz = reshape([cos(a), sin(a), 0.0_dp, -sin(a), cos(a), 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
    ry = reshape([cos(b), 0.0_dp, -sin(b), 0.0_dp, 1.0_dp, 0.0_dp, sin(b), 0.0_dp, cos(b)], [3, 3])
    rx = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, cos(c), sin(c), 0.0_dp, -sin(c), cos(c)], [3, 3])
    r = matmul(rz, matmul(ry, rx))
  end function rotation

  !> Update from a trial stress: sig0 = trial, no strain increment.
  subroutine return_of(m, sig_tr, sig, state, dtan)
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp), intent(in) :: sig_tr(6)
    real(dp), intent(out) :: sig(6)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(6, 6)
    call m%update(sig_tr, zero6, zero6, state_elastic, sig, state, dtan)
  end subroutine return_of

  !> Central finite-difference gradient of the yield value of m at sig.
  function fd_gradient(m, sig) result(g)
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp), intent(in) :: sig(6)
    real(dp) :: g(6), e(6), h
    integer :: j
    h = 1.0e-6_dp * stress_scale(m, sig)
    do j = 1, 6
      e = 0.0_dp
      e(j) = h
      g(j) = (m%yield_value(sig + e) - m%yield_value(sig - e)) / (2.0_dp * h)
    end do
  end function fd_gradient

  !> Central finite-difference derivative of the update from sig0 with respect to the strain
  !! increment at deps (step 1e-6 of its largest component).
  function fd_tangent(m, sig0, deps) result(dfd)
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp), intent(in) :: sig0(6), deps(6)
    real(dp) :: dfd(6, 6), e(6), h, sp(6), sm(6), dd(6, 6)
    integer :: j, stp, stm
    h = 1.0e-6_dp * maxval(abs(deps))
    do j = 1, 6
      e = 0.0_dp
      e(j) = h
      call m%update(sig0, zero6, deps + e, state_elastic, sp, stp, dd)
      call m%update(sig0, zero6, deps - e, state_elastic, sm, stm, dd)
      dfd(:, j) = (sp - sm) / (2.0_dp * h)
    end do
  end function fd_tangent

  !> Checks for one returned stress: finite; on the surface for plastic and tension states
  !! (|F| <= 1e-12 scale, thesis cubic <= 1e-10 relative); elastic: unchanged and inside;
  !! plastic: plastic strain D^-1 (sig_tr - sig) along the potential gradient with a positive
  !! multiplier (potential: the cone with angle psi, FD gradient; psi = 0: the deviator);
  !! tension: sig = alpha sig_tr with 0 < alpha <= 1 (proportional rule) or the apex M I with
  !! the small residual tangent (closest-point rule).
  subroutine check_returned(error, m, sig_tr, sig, state, dtan, what)
    type(error_t), allocatable, intent(out) :: error
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp), intent(in) :: sig_tr(6), sig(6), dtan(6, 6)
    integer, intent(in) :: state
    character(len=*), intent(in) :: what
    type(matsuoka_nakai_t) :: pot
    real(dp) :: ep(6), ng(6), proj, alpha, scale
    scale = stress_scale(m, sig_tr)
    if (.not. (finite(sig) .and. finite(reshape(dtan, [36])))) then
      call test_failed(error, what // ': not finite')
      return
    end if
    select case (state)
    case (state_elastic)
      call check(error, maxval(abs(sig - sig_tr)) == 0.0_dp .and. m%yield_value(sig_tr) < 0.0_dp, &
                 what // ': elastic point unchanged and inside')
    case (state_plastic, state_tension)
      call check(error, m%yield_value(sig), 0.0_dp, what // ': F on the surface', abs=1.0e-12_dp * scale)
      if (allocated(error)) return
      ! (the relative cubic is rounding noise at the apex itself, sigma* = 0)
      if (maxval(abs(sig - m%apex * [1, 1, 1, 0, 0, 0])) > 1.0e-10_dp * m%apex) then
        call check(error, relative_cubic(m, sig), 0.0_dp, what // ': cubic f on the surface', abs=1.0e-10_dp)
        if (allocated(error)) return
      end if
      if (state == state_plastic) then
        ep = compliance(m%e, m%nu, sig_tr - sig)
        if (m%psi > 0.0_dp) then
          pot = m
          pot%phi = m%psi
          ng = fd_gradient(pot, sig)
        else
          ng = sig - sum(sig(1:3)) / 3.0_dp * [1, 1, 1, 0, 0, 0]
          ng(4:6) = 2.0_dp * ng(4:6)
        end if
        proj = dot_product(ep, ng) / dot_product(ng, ng)
        call check(error, proj > 0.0_dp, what // ': positive plastic multiplier')
        if (allocated(error)) return
        call check(error, norm2(ep - proj * ng), 0.0_dp, what // ': plastic strain along dg/dsigma', &
                   abs=1.0e-7_dp * norm2(ep))
      else if (m%tension == tension_closest_point) then
        call check(error, maxval(abs(sig - m%apex * [1, 1, 1, 0, 0, 0])), 0.0_dp, what // ': the apex', abs=0.0_dp)
        if (allocated(error)) return
        call check(error, maxval(abs(dtan - apex_stiffness_factor * d_matrix(m%e, m%nu))), 0.0_dp, &
                   what // ': apex residual tangent', abs=1.0e-12_dp * m%e)
      else
        alpha = dot_product(sig, sig_tr) / dot_product(sig_tr, sig_tr)
        call check(error, alpha > 0.0_dp .and. alpha <= 1.0_dp + 1.0e-14_dp, what // ': 0 < alpha <= 1')
        if (allocated(error)) return
        call check(error, maxval(abs(sig - alpha * sig_tr)), 0.0_dp, what // ': proportional', abs=1.0e-12_dp * scale)
      end if
    case default
      call test_failed(error, what // ': unexpected state ' // str(state))
    end select
  end subroutine check_returned

  ! ---------------------------------------------------------------- tests

  !> On the triaxial compression (sigma_2 = sigma_3) and extension (sigma_1 = sigma_2)
  !! meridians the surface is the Mohr-Coulomb one, sigma_1 = sigma_3 (1+sin)/(1-sin) +
  !! 2 c cos/(1-sin) (compression positive, sigma_1 major), for three angles and several
  !! confinements; the surface point is found by bisection on F and checked on the cubic.
  subroutine test_meridians(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: angles(3) = [15.0_dp, 26.57_dp, 54.9_dp], confinement(4) = [0.0_dp, 1.0_dp, 5.0_dp, 40.0_dp]
    type(matsuoka_nakai_t) :: m
    real(dp) :: sn, c, s3, expected, t, sig(6)
    integer :: i, k
    do i = 1, size(angles)
      m = make(angles(i), angles(i), 2.0_dp)
      sn = sin(angles(i) * deg2rad)
      c = m%apex * tan(angles(i) * deg2rad)
      call check(error, apex_from_cohesion(c, angles(i)), m%apex, 'apex from c and from ft', rel=1.0e-13_dp)
      if (allocated(error)) return
      do k = 1, size(confinement)
        s3 = confinement(k) * c
        expected = s3 * (1.0_dp + sn) / (1.0_dp - sn) + 2.0_dp * c * cos(angles(i) * deg2rad) / (1.0_dp - sn)
        ! compression meridian: (sigma_1, sigma_3, sigma_3) compression positive, sigma_1 in z
        t = surface_along(m, -s3 * [1, 1, 0, 0, 0, 0] * 1.0_dp, [0, 0, -1, 0, 0, 0] * 1.0_dp, s3, 100.0_dp * expected)
        call check(error, t, expected, 'compression meridian phi ' // str(angles(i)) // ' s3 ' // str(s3), &
                   rel=1.0e-8_dp)
        if (allocated(error)) return
        sig = -[s3, s3, expected, 0.0_dp, 0.0_dp, 0.0_dp]
        call check(error, relative_cubic(m, sig), 0.0_dp, 'cubic zero on the compression meridian', abs=1.0e-10_dp)
        if (allocated(error)) return
        ! extension meridian: (sigma_1, sigma_1, sigma_3)
        t = surface_along(m, -s3 * [0, 0, 1, 0, 0, 0] * 1.0_dp, [-1, -1, 0, 0, 0, 0] * 1.0_dp, s3, 100.0_dp * expected)
        call check(error, t, expected, 'extension meridian phi ' // str(angles(i)) // ' s3 ' // str(s3), &
                   rel=1.0e-8_dp)
        if (allocated(error)) return
        sig = -[expected, expected, s3, 0.0_dp, 0.0_dp, 0.0_dp]
        call check(error, relative_cubic(m, sig), 0.0_dp, 'cubic zero on the extension meridian', abs=1.0e-10_dp)
        if (allocated(error)) return
        ! off the meridians (Lode angle between) the surface lies outside Mohr-Coulomb
        t = surface_along(m, -[s3, 0.5_dp * (s3 + expected), 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], &
                          [0, 0, -1, 0, 0, 0] * 1.0_dp, 0.5_dp * (s3 + expected), 100.0_dp * expected)
        call check(error, t > expected * (1.0_dp + 1.0e-6_dp), 'between the meridians outside Mohr-Coulomb')
        if (allocated(error)) return
      end do
    end do
  end subroutine test_meridians

  !> Thesis 2.4.3: E = 10000, nu = 0.2, phi = psi = 26.57, ft = 6: fc = 15.71 (0.1%), uniaxial
  !! tension strength 6 on the surface; chapter 9: phi = 54.9 gives ft/fc = 1/10 (1%).
  subroutine test_uniaxial_strengths(error)
    type(error_t), allocatable, intent(out) :: error
    type(matsuoka_nakai_t) :: m
    real(dp) :: fc, ft, sn
    m = make(phi_block, phi_block, ft_block)
    fc = surface_along(m, zero6, [-1, 0, 0, 0, 0, 0] * 1.0_dp, 0.0_dp, 1000.0_dp)
    call check(error, fc, 15.71_dp, 'uniaxial compression strength fc', rel=1.0e-3_dp)
    if (allocated(error)) return
    sn = sin(phi_block * deg2rad)
    call check(error, fc, ft_block * (1.0_dp + sn) / (1.0_dp - sn), 'fc = ft (1+sin)/(1-sin)', rel=1.0e-10_dp)
    if (allocated(error)) return
    ft = surface_along(m, zero6, [0, 1, 0, 0, 0, 0] * 1.0_dp, 0.0_dp, 1000.0_dp)
    call check(error, ft, ft_block, 'uniaxial tension strength ft', rel=1.0e-10_dp)
    if (allocated(error)) return
    call check(error, m%yield_value([0.0_dp, 0.0_dp, ft_block, 0.0_dp, 0.0_dp, 0.0_dp]), 0.0_dp, &
               'F(ft on z) = 0', abs=1.0e-12_dp * ft_block)
    if (allocated(error)) return
    m = make(54.9_dp, 54.9_dp, 1.0_dp)
    fc = surface_along(m, zero6, [0, 0, -1, 0, 0, 0] * 1.0_dp, 0.0_dp, 1000.0_dp)
    ft = surface_along(m, zero6, [0, 0, 1, 0, 0, 0] * 1.0_dp, 0.0_dp, 1000.0_dp)
    call check(error, ft / fc, 0.1_dp, 'ft/fc at phi = 54.9', rel=1.0e-2_dp)
  end subroutine test_uniaxial_strengths

  !> Elastic steps for nu in [-0.9, 0.499]: sig = sig0 + D deps with D the isotropic matrix
  !! (checked against the compliance: D^-1 D = I), tangent D, state elastic; and
  !! elastic_tangent, is_linear, symmetric_tangent.
  subroutine test_elastic_nu(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: nus(7) = [-0.9_dp, -0.5_dp, 0.0_dp, 0.2_dp, 0.3_dp, 0.45_dp, 0.499_dp]
    type(matsuoka_nakai_t) :: m
    real(dp) :: d(6, 6), dt(6, 6), sig(6), sig0(6), deps(6), col(6), eye(6)
    integer :: i, j, st
    sig0 = [-5.0_dp, -4.0_dp, -6.0_dp, 0.3_dp, -0.2_dp, 0.1_dp]
    do i = 1, size(nus)
      m = make(30.0_dp, 10.0_dp, 3.0_dp, e=20000.0_dp, nu=nus(i))
      call m%elastic_tangent(d)
      do j = 1, 6
        col = compliance(m%e, m%nu, d(:, j))
        eye = 0.0_dp
        eye(j) = 1.0_dp
        call check(error, maxval(abs(col - eye)), 0.0_dp, 'D^-1 D = I, nu = ' // str(nus(i)), abs=1.0e-10_dp)
        if (allocated(error)) return
      end do
      call check(error, maxval(abs(d - d_matrix(m%e, m%nu))), 0.0_dp, 'D', abs=1.0e-9_dp * maxval(abs(d)))
      if (allocated(error)) return
      deps = 1.0e-6_dp * [1.0_dp, -2.0_dp, 0.5_dp, 3.0_dp, -1.0_dp, 2.0_dp]
      call m%update(sig0, zero6, deps, state_elastic, sig, st, dt)
      call check(error, st, state_elastic, 'elastic state')
      if (allocated(error)) return
      call check(error, maxval(abs(sig - sig0 - matmul(d_matrix(m%e, m%nu), deps))), 0.0_dp, 'elastic stress', &
                 abs=1.0e-12_dp * maxval(abs(sig0)))
      if (allocated(error)) return
      call check(error, maxval(abs(dt - d)), 0.0_dp, 'elastic tangent', abs=0.0_dp)
      if (allocated(error)) return
    end do
    call check(error, .not. m%is_linear(), 'not linear')
    if (allocated(error)) return
    call check(error, .not. m%symmetric_tangent(), 'psi < phi: non-symmetric tangent')
    if (allocated(error)) return
    m%psi = m%phi
    call check(error, m%symmetric_tangent(), 'psi = phi: symmetric tangent')
  end subroutine test_elastic_nu

  !> 300 random trial stresses (fixed seed) for phi = 15, 26.57, 40, 54.9 (nu = 0.2, -0.9,
  !! 0.499, 0) and psi = 0, phi/2, phi, under both tension rules: every result passes
  !! check_returned; each kind of result occurs.
  subroutine test_random_returns(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: angles(4) = [15.0_dp, 26.57_dp, 40.0_dp, 54.9_dp]
    real(dp), parameter :: nus(4) = [0.2_dp, -0.9_dp, 0.499_dp, 0.0_dp]
    type(matsuoka_nakai_t) :: m
    real(dp) :: sig_tr(6), sig(6), dt(6, 6), psi
    integer(kind=8) :: seed
    integer :: i, j, k, n, st, counts(0:3), rule
    do rule = tension_proportional, tension_closest_point
    seed = 20240917_8
    counts = 0
    do i = 1, size(angles)
      do j = 0, 2
        psi = 0.5_dp * j * angles(i)
        m = make(angles(i), psi, 4.0_dp, nu=nus(i), tension=rule)
        do n = 1, 300
          do k = 1, 6
            sig_tr(k) = m%apex * (6.0_dp * next_uniform(seed) - 4.5_dp)
          end do
          sig_tr(4:6) = 0.5_dp * sig_tr(4:6)
          call return_of(m, sig_tr, sig, st, dt)
          call check_returned(error, m, sig_tr, sig, st, dt, 'phi ' // str(angles(i)) // ' psi ' // str(psi) // &
                              ' trial ' // str(n))
          if (allocated(error)) return
          counts(st) = counts(st) + 1
        end do
      end do
    end do
    ! (the closest-point rule's apex region is a narrow cone round the hydrostatic axis)
    call check(error, counts(state_elastic) > 100 .and. counts(state_plastic) > 1000 .and. &
               counts(state_tension) > merge(100, 0, rule == tension_proportional), &
               'elastic, plastic and tension results all occur (rule ' // &
               str(rule) // '): ' // str(counts(0)) // ' ' // str(counts(1)) // ' ' // str(counts(3)))
    if (allocated(error)) return
    end do
  end subroutine test_random_returns

  !> Trial stresses swept in steps of 0.005 MPa across the tension zone's border sigma_1 = M
  !! (phi = 54.9 deg, ft = 5 MPa, chapter 9's concrete; sigma_2 = 0, -10, -30, sigma_3 =
  !! sigma_2 - 5; psi = phi and 0). The closest-point rule is continuous: no returned component
  !! moves by more than twice the trial's step. The thesis's proportional rule jumps at the
  !! border, by more than 1 MPa at sigma_2 = -10 and -30 (measured: up to 16 MPa).
  subroutine test_tension_continuity(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: lateral(3) = [0.0_dp, -10.0_dp, -30.0_dp], step = 0.005_dp
    type(matsuoka_nakai_t) :: m
    real(dp) :: trial(6), sig(6), prev(6), dt(6, 6), biggest
    integer :: i, j, k, st, rule
    do k = 0, 1
      do rule = tension_proportional, tension_closest_point
        m = make(54.9_dp, k * 54.9_dp, 5.0_dp, e=31700.0_dp, nu=0.22_dp, tension=rule)
        do j = 1, size(lateral)
          biggest = 0.0_dp
          do i = 0, 4000
            trial = [-5.0_dp + i * step, lateral(j), lateral(j) - 5.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
            call return_of(m, trial, sig, st, dt)
            if (i > 0) biggest = max(biggest, maxval(abs(sig - prev)))
            prev = sig
          end do
          if (rule == tension_closest_point) then
            call check(error, biggest <= 2.0_dp * step, 'closest point: continuous at sigma_2 = ' // &
                       str(lateral(j)) // ', psi = ' // str(m%psi) // ' (largest change ' // str(biggest) // ')')
          else if (j > 1) then
            call check(error, biggest > 1.0_dp, 'proportional (thesis): jumps at sigma_2 = ' // str(lateral(j)) // &
                       ', psi = ' // str(m%psi) // ' (largest change ' // str(biggest) // ')')
          end if
          if (allocated(error)) return
        end do
      end do
    end do
  end subroutine test_tension_continuity

  !> The closest-point rule: a hydrostatic trial beyond the apex returns to M I (state
  !! tension) for psi = phi and psi = 0; a trial whose sigma_1 exceeds M but whose return
  !! stays on the cone is a plastic point with the consistent tangent, checked against central
  !! finite differences (1e-5 relative); uniaxial tension far beyond ft lands on the cone, not
  !! proportionally at (ft, 0, 0).
  subroutine test_closest_point_returns(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: psis(2) = [54.9_dp, 0.0_dp]
    type(matsuoka_nakai_t) :: m
    real(dp) :: sig0(6), deps(6), sig(6), dt(6, 6), dfd(6, 6)
    integer :: i, st
    do i = 1, size(psis)
      m = make(54.9_dp, psis(i), 5.0_dp, e=31700.0_dp, nu=0.22_dp, tension=tension_closest_point)
      call return_of(m, 2.0_dp * m%apex * [1, 1, 1, 0, 0, 0], sig, st, dt)
      call check_returned(error, m, 2.0_dp * m%apex * [1, 1, 1, 0, 0, 0], sig, st, dt, 'hydrostatic 2 M')
      if (allocated(error)) return
      call check(error, st, state_tension, 'hydrostatic 2 M: the apex, state tension')
      if (allocated(error)) return
      ! sigma_1 = M + 1 with lateral compression: the old tension zone, now a return to the cone
      sig0 = [m%apex + 1.0_dp, -10.0_dp, -15.0_dp, 0.3_dp, -0.2_dp, 0.1_dp]
      deps = 1.0e-5_dp * [1.0_dp, -0.5_dp, 0.2_dp, 0.3_dp, 0.1_dp, -0.2_dp]
      call m%update(sig0, zero6, deps, state_elastic, sig, st, dt)
      call check_returned(error, m, sig0 + matmul(d_matrix(m%e, m%nu), deps), sig, st, dt, &
                          'sigma_1 beyond M, psi ' // str(psis(i)))
      if (allocated(error)) return
      call check(error, st, state_plastic, 'sigma_1 beyond M: a plastic point on the cone')
      if (allocated(error)) return
      dfd = fd_tangent(m, sig0, deps)
      call check(error, maxval(abs(dt - dfd)), 0.0_dp, 'closest point: tangent vs FD, psi ' // str(psis(i)), &
                 abs=1.0e-5_dp * maxval(abs(dfd)))
      if (allocated(error)) return
      ! uniaxial tension 2 ft: on the cone, and not the proportional (ft, 0, 0)
      call return_of(m, [10.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], sig, st, dt)
      call check_returned(error, m, [10.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], sig, st, dt, &
                          'uniaxial 2 ft, psi ' // str(psis(i)))
      if (allocated(error)) return
      call check(error, maxval(abs(sig - [5.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])) > 0.1_dp, &
                 'uniaxial 2 ft: not the proportional return')
      if (allocated(error)) return
      call check_random_tension_tangents(error, m)
      if (allocated(error)) return
    end do
  end subroutine test_closest_point_returns

  !> 200 random trials with the most tensile principal stress near or beyond the apex (fixed
  !! seed): where the trial and its perturbations return to the cone, the tangent equals the
  !! central finite difference (1e-5 relative); at the apex it is the residual 1e-6 D. At least
  !! 50 of each must occur.
  subroutine check_random_tension_tangents(error, m)
    type(error_t), allocatable, intent(out) :: error
    type(matsuoka_nakai_t), intent(in) :: m
    real(dp) :: trial(6), sig(6), dt(6, 6), dfd(6, 6), sp(6), sm(6), dd(6, 6), e(6), h, dev(6)
    integer(kind=8) :: seed
    integer :: n, k, j, st, stp, stm, on_cone, at_apex
    logical :: same_side
    seed = 4242_8
    on_cone = 0
    at_apex = 0
    do n = 1, 200
      do k = 1, 3
        trial(k) = m%apex * (2.5_dp * next_uniform(seed) - 1.0_dp)
      end do
      do k = 4, 6
        trial(k) = m%apex * (next_uniform(seed) - 0.5_dp)
      end do
      ! every other trial near the hydrostatic axis beyond the apex
      if (modulo(n, 2) == 0) trial = 0.05_dp * trial + m%apex * (1.0_dp + next_uniform(seed)) * [1, 1, 1, 0, 0, 0]
      call return_of(m, trial, sig, st, dt)
      dev = sig - sum(sig(1:3)) / 3.0_dp * [1, 1, 1, 0, 0, 0]
      if (st == state_plastic .and. sqrt(sum(dev(1:3)**2) + 2.0_dp * sum(dev(4:6)**2)) < 2.0e-2_dp * m%apex) then
        ! near the apex check_returned's finite-difference gradient of the cone misses the flow
        ! direction by 1e-5 (trial 50: |s| = 3.6e-3 M; its return meets the flow rule to 1e-14
        ! in 50-digit arithmetic): check only that the stress is on the surface; the tangent
        ! check below covers these points
        call check(error, m%yield_value(sig), 0.0_dp, 'random tension trial ' // str(n) // ': on the surface', &
                   abs=1.0e-12_dp * m%apex)
      else
        call check_returned(error, m, trial, sig, st, dt, 'random tension trial ' // str(n))
      end if
      if (allocated(error)) return
      if (st == state_tension) at_apex = at_apex + 1
      if (st /= state_plastic) cycle
      h = 1.0e-7_dp * m%apex
      same_side = .true.
      do j = 1, 6
        e = 0.0_dp
        e(j) = h
        call return_of(m, trial + e, sp, stp, dd)
        call return_of(m, trial - e, sm, stm, dd)
        same_side = same_side .and. stp == state_plastic .and. stm == state_plastic
        dfd(:, j) = (sp - sm) / (2.0_dp * h)
      end do
      if (.not. same_side) cycle
      ! d sig / d sig_tr = dt D^-1
      do j = 1, 6
        e = 0.0_dp
        e(j) = 1.0_dp
        dd(:, j) = matmul(dt, compliance(m%e, m%nu, e))
      end do
      call check(error, maxval(abs(dd - dfd)), 0.0_dp, 'random tension trial ' // str(n) // ': tangent vs FD', &
                 abs=1.0e-5_dp * max(1.0_dp, maxval(abs(dfd))))
      if (allocated(error)) return
      on_cone = on_cone + 1
    end do
    call check(error, on_cone >= 50 .and. at_apex >= 50, 'random tension trials: ' // str(on_cone) // &
               ' on the cone checked, ' // str(at_apex) // ' at the apex')
  end subroutine check_random_tension_tangents

  !> The apex M I for hydrostatic tension beyond it and for a trial exactly at it; uniaxial
  !! tension beyond M returns proportionally to (ft, 0, 0); uniaxial tension below M (but
  !! beyond ft) by the closest-point return; points exactly on the surface stay; trial paths
  !! through the apex and along the hydrostatic axis give finite stresses on or inside the
  !! surface.
  subroutine test_apex_tension(error)
    type(error_t), allocatable, intent(out) :: error
    type(matsuoka_nakai_t) :: m
    real(dp) :: sig(6), dt(6, 6), apex(6), trial(6), dir(6), t, k
    integer :: st, i, j
    do j = 0, 1
      m = make(phi_block, j * phi_block, ft_block)
      apex = m%apex * [1, 1, 1, 0, 0, 0]
      k = m%e / (3.0_dp * (1.0_dp - 2.0_dp * m%nu))
      ! hydrostatic tension twice the apex
      call return_of(m, 2.0_dp * apex, sig, st, dt)
      call check(error, st, state_tension, 'hydrostatic beyond apex: tension state')
      if (allocated(error)) return
      call check(error, maxval(abs(sig - apex)), 0.0_dp, 'hydrostatic beyond apex: the apex', abs=1.0e-12_dp * m%apex)
      if (allocated(error)) return
      call check(error, dt(1, 1) + 2.0_dp * dt(1, 2), 3.0_dp * apex_stiffness_factor * k, &
                 'apex: volumetric residual stiffness', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, dt(4, 4), 0.25_dp * m%e / (1.0_dp + m%nu), 'apex: shear stiffness alpha G, alpha = 1/2', &
                 rel=1.0e-10_dp)
      if (allocated(error)) return
      ! exactly at the apex
      call return_of(m, apex, sig, st, dt)
      call check(error, maxval(abs(sig - apex)) == 0.0_dp .and. finite(reshape(dt, [36])), 'trial at the apex stays')
      if (allocated(error)) return
      ! uniaxial tension 2 ft > M: proportional return to ft
      call check(error, 2.0_dp * ft_block > m%apex, 'test premise: 2 ft beyond the apex')
      if (allocated(error)) return
      call return_of(m, [0.0_dp, 2.0_dp * ft_block, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], sig, st, dt)
      call check(error, st, state_tension, 'uniaxial 2 ft: tension state')
      if (allocated(error)) return
      call check(error, maxval(abs(sig - [0.0_dp, ft_block, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])), 0.0_dp, &
                 'uniaxial 2 ft: back to ft', abs=1.0e-12_dp * ft_block)
      if (allocated(error)) return
      ! uniaxial tension 1.2 ft < M: closest point
      trial = [0.0_dp, 0.0_dp, 1.2_dp * ft_block, 0.0_dp, 0.0_dp, 0.0_dp]
      call return_of(m, trial, sig, st, dt)
      call check(error, st, state_plastic, 'uniaxial 1.2 ft: closest-point return')
      if (allocated(error)) return
      call check_returned(error, m, trial, sig, st, dt, 'uniaxial 1.2 ft')
      if (allocated(error)) return
      ! a point on the surface (uniaxial ft) stays, plastic
      trial = [ft_block, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
      call return_of(m, trial, sig, st, dt)
      call check(error, st == state_plastic .and. all(sig == trial) .and. finite(reshape(dt, [36])), &
                 'on the surface: unchanged, plastic')
      if (allocated(error)) return
      ! paths through the apex in several directions
      do i = 1, 3
        select case (i)
        case (1)
          dir = [1.0_dp, -0.5_dp, -0.5_dp, 0.0_dp, 0.0_dp, 0.0_dp]
        case (2)
          dir = [0.3_dp, 0.2_dp, -0.1_dp, 0.4_dp, -0.2_dp, 0.1_dp]
        case default
          dir = [1.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
        end select
        t = -2.0_dp
        do while (t <= 2.0_dp + 1.0e-12_dp)
          trial = apex + t * m%apex * dir
          call return_of(m, trial, sig, st, dt)
          call check_returned(error, m, trial, sig, st, dt, 'path ' // str(i) // ' t ' // str(t))
          if (allocated(error)) return
          if (abs(t) < 1.0e-12_dp) then
            call check(error, maxval(abs(sig - apex)), 0.0_dp, 'path at the apex', abs=1.0e-12_dp * m%apex)
            if (allocated(error)) return
          end if
          t = t + 0.125_dp
        end do
      end do
    end do
  end subroutine test_apex_tension

  !> The consistent tangent against a central finite-difference derivative of the update
  !! (1e-5 relative to the largest entry) for associated and non-associated flow at several
  !! trial stresses outside the surface (generic Lode angles, near the meridians, near the
  !! apex); associated tangents are symmetric.
  subroutine test_tangent_fd(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: psis(4) = [26.57_dp, 15.0_dp, 5.0_dp, 0.0_dp]
    type(matsuoka_nakai_t) :: m
    real(dp) :: sig0(6), deps(6), sig(6), dt(6, 6), dfd(6, 6)
    integer :: i, k, st
    do i = 1, size(psis)
      m = make(26.57_dp, psis(i), ft_block, nu=0.25_dp)
      do k = 1, 5
        sig0 = [-8.0_dp, -4.0_dp, -2.0_dp, 0.5_dp, -0.3_dp, 0.2_dp]
        select case (k)
        case (1)
          deps = 3.0e-3_dp * [0.3_dp, -0.5_dp, 0.1_dp, 0.8_dp, -0.4_dp, 0.6_dp]
        case (2)
          deps = 1.0e-3_dp * [-3.0_dp, 0.4_dp, 0.3_dp, 0.1_dp, 0.0_dp, 0.05_dp]
        case (3)
          sig0 = [-3.0_dp, -3.0_dp, -12.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
          deps = 1.0e-3_dp * [0.5_dp, 0.5_dp, -2.0_dp, 0.01_dp, 0.0_dp, 0.0_dp]
        case (4)
          sig0 = m%apex * [0.8_dp, 0.8_dp, 0.8_dp, 0.0_dp, 0.0_dp, 0.0_dp]
          deps = 2.0e-3_dp * [-0.3_dp, 0.1_dp, -0.1_dp, 0.25_dp, 0.1_dp, -0.15_dp]
        case default
          sig0 = [-30.0_dp, -10.0_dp, -20.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
          deps = 1.0e-2_dp * [-2.0_dp, -1.0_dp, 0.5_dp, 1.5_dp, -1.0_dp, 1.0_dp]
        end select
        call m%update(sig0, zero6, deps, state_elastic, sig, st, dt)
        call check(error, st, state_plastic, 'tangent psi ' // str(psis(i)) // ' case ' // str(k) // ' plastic')
        if (allocated(error)) return
        dfd = fd_tangent(m, sig0, deps)
        call check(error, maxval(abs(dt - dfd)), 0.0_dp, 'tangent vs FD, psi ' // str(psis(i)) // ' case ' // &
                   str(k), abs=1.0e-5_dp * maxval(abs(dfd)))
        if (allocated(error)) return
        if (m%symmetric_tangent()) then
          call check(error, maxval(abs(dt - transpose(dt))), 0.0_dp, 'associated: symmetric', abs=0.0_dp)
          if (allocated(error)) return
        else
          call check(error, maxval(abs(dt - transpose(dt))) > 1.0e-6_dp * maxval(abs(dt)), &
                     'non-associated: not symmetric')
          if (allocated(error)) return
        end if
      end do
    end do
  end subroutine test_tangent_fd

  !> Rotating the trial stress, updating and rotating back gives the same stress (1e-10
  !! relative) for elastic, plastic and tension-zone trials.
  subroutine test_rotation(error)
    type(error_t), allocatable, intent(out) :: error
    type(matsuoka_nakai_t) :: m
    real(dp) :: r(3, 3), rt(3, 3), trial(6), sig(6), sig_r(6), dt(6, 6), back(6)
    integer(kind=8) :: seed
    integer :: i, j, k, st, st_r
    seed = 77_8
    do j = 0, 1
      m = make(35.0_dp, j * 35.0_dp, 3.0_dp)
      do i = 1, 60
        do k = 1, 6
          trial(k) = m%apex * (6.0_dp * next_uniform(seed) - 4.5_dp)
        end do
        if (i == 1) trial = [2.0_dp * m%apex, -1.0_dp, 0.5_dp, 0.0_dp, 0.0_dp, 0.0_dp]   ! on a principal frame
        if (i == 2) trial = [-40.0_dp, -1.0_dp, -1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]          ! on a meridian
        r = rotation(0.3_dp * i, 0.7_dp - 0.05_dp * i, 1.1_dp + 0.2_dp * i)
        call return_of(m, trial, sig, st, dt)
        call return_of(m, rotate_stress(r, trial), sig_r, st_r, dt)
        rt = transpose(r)
        back = rotate_stress(rt, sig_r)
        call check(error, st_r, st, 'rotated: same state, trial ' // str(i))
        if (allocated(error)) return
        call check(error, maxval(abs(back - sig)), 0.0_dp, 'rotated back: same stress, trial ' // str(i), &
                   abs=1.0e-10_dp * stress_scale(m, trial))
        if (allocated(error)) return
      end do
    end do
  end subroutine test_rotation

  !> The block example of thesis 2.4.3 at one material point: eps_z imposed in 200 equal
  !! steps, the lateral stresses kept zero by Newton iteration on the lateral strains with the
  !! tangent. sigma_z rises with slope E and stays at -15.71 in compression and +6 in tension
  !! (0.2%), never beyond; with either tension rule (the path stays on the cone).
  subroutine test_block_path(error)
    type(error_t), allocatable, intent(out) :: error
    type(matsuoka_nakai_t) :: m
    real(dp) :: sig0(6), eps0(6), deps(6), sig(6), dt(6, 6), target, ezmax, a(2, 2), r(2), det, peak
    integer :: dir, step, iter, st, st0, rule
    do rule = tension_proportional, tension_closest_point
    m = make(phi_block, phi_block, ft_block, tension=rule)
    do dir = -1, 1, 2
      if (dir < 0) then
        target = -15.71_dp
      else
        target = ft_block
      end if
      ezmax = 3.0_dp * target / m%e
      sig0 = 0.0_dp
      eps0 = 0.0_dp
      st0 = state_elastic
      peak = 0.0_dp
      do step = 1, 200
        deps = 0.0_dp
        deps(3) = ezmax / 200.0_dp
        deps(1:2) = -m%nu * deps(3)
        do iter = 1, 50
          call m%update(sig0, eps0, deps, st0, sig, st, dt)
          r = sig(1:2)
          if (maxval(abs(r)) <= 1.0e-10_dp * abs(target)) exit
          a = dt(1:2, 1:2)
          det = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
          deps(1) = deps(1) - (a(2, 2) * r(1) - a(1, 2) * r(2)) / det
          deps(2) = deps(2) - (a(1, 1) * r(2) - a(2, 1) * r(1)) / det
        end do
        call check(error, maxval(abs(sig(1:2))) <= 1.0e-10_dp * abs(target), 'lateral stress free, step ' // str(step))
        if (allocated(error)) return
        if (step == 10) then
          call check(error, sig(3), m%e * 10.0_dp * ezmax / 200.0_dp, 'elastic slope E', rel=1.0e-12_dp)
          if (allocated(error)) return
        end if
        peak = max(peak, abs(sig(3)))
        sig0 = sig
        eps0 = eps0 + deps
        st0 = st
      end do
      call check(error, st0, state_plastic, 'plateau reached')
      if (allocated(error)) return
      call check(error, sig0(3), target, 'plateau sigma_z', rel=2.0e-3_dp)
      if (allocated(error)) return
      call check(error, peak, abs(target), 'no overshoot', rel=2.0e-3_dp)
      if (allocated(error)) return
    end do
    end do
  end subroutine test_block_path

  !> phi = 5..60 deg (and the extremes 1 and 80 deg) with psi = 0 and psi = phi: single
  !! steps from zero stress reaching 100 and 1e6 times the elastic limit in shear, uniaxial
  !! compression, mixed, uniaxial-strain tension and volumetric expansion directions give
  !! finite stresses on the surface (check_returned).
  subroutine test_huge_steps(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: factors(2) = [100.0_dp, 1.0e6_dp]
    type(matsuoka_nakai_t) :: m
    real(dp) :: dirs(6, 5), d(6, 6), sig(6), dt(6, 6), t, phi, angles(14)
    integer :: i, j, k, n, st
    dirs(:, 1) = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]
    dirs(:, 2) = [0.3_dp, 0.3_dp, -1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]   ! uniaxial compression stress (nu = 0.3)
    dirs(:, 3) = [-0.3_dp, 0.6_dp, -0.3_dp, 0.5_dp, -0.4_dp, 0.2_dp]
    dirs(:, 4) = [0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
    dirs(:, 5) = [1.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
    angles(1:12) = [(5.0_dp * i, i = 1, 12)]
    angles(13:14) = [1.0_dp, 80.0_dp]
    do i = 1, size(angles)
      phi = angles(i)
      do j = 0, 1
        m = make(phi, j * phi, 2.0_dp, nu=0.3_dp)
        d = d_matrix(m%e, m%nu)
        do k = 1, size(dirs, 2)
          t = surface_along(m, zero6, matmul(d, dirs(:, k)), 0.0_dp, 1.0e3_dp * m%apex / m%e)
          call check(error, t < 0.99_dp * 1.0e3_dp * m%apex / m%e, 'test premise: direction ' // str(k) // ' yields')
          if (allocated(error)) return
          do n = 1, size(factors)
            call m%update(zero6, zero6, factors(n) * t * dirs(:, k), state_elastic, sig, st, dt)
            call check_returned(error, m, matmul(d, factors(n) * t * dirs(:, k)), sig, st, dt, &
                                'huge step phi ' // str(phi) // ' psi ' // str(m%psi) // ' dir ' // str(k) // &
                                ' factor ' // str(factors(n)))
            if (allocated(error)) return
            call check(error, st /= state_elastic, 'huge step yields')
            if (allocated(error)) return
          end do
        end do
      end do
    end do
  end subroutine test_huge_steps

  !> Eight trials (generic, psi = 0, nu = -0.9 and 0.45, the closest-point rule beyond sigma_1 =
  !! M, near the apex, huge, the proportional tension zone) against an independent numpy
  !! implementation, test/reference/matsuoka_reference.py (principal stresses, the thesis's cubic f and
  !! potential g with M* from g = 0, backward Euler by Newton from several starts; not feps's
  !! Lode-angle reduction); its printed values are pasted here. Tolerance 1e-10 of
  !! max|sigma_tr| + M (the two agree to 7e-16 on the audit's machine).
  subroutine test_numpy_reference(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp
    real(dp), parameter :: par(5, 8) = reshape([ &   ! phi, psi, nu, tension rule, ft
      26.57_dp, 26.57_dp, 0.2_dp, 1.0_dp, 6.0_dp, 26.57_dp, 0.0_dp, 0.2_dp, 1.0_dp, 6.0_dp, &
      26.57_dp, 13.0_dp, -0.9_dp, 1.0_dp, 6.0_dp, 54.9_dp, 54.9_dp, 0.45_dp, 1.0_dp, 5.0_dp, &
      54.9_dp, 20.0_dp, 0.22_dp, 2.0_dp, 5.0_dp, 15.0_dp, 15.0_dp, 0.3_dp, 2.0_dp, 0.2_dp, &
      40.0_dp, 10.0_dp, 0.0_dp, 1.0_dp, 3.0_dp, 35.0_dp, 35.0_dp, 0.2_dp, 1.0_dp, 3.0_dp], [5, 8])
    real(dp), parameter :: trials(6, 8) = reshape([ &
      -30.0_dp, -5.0_dp, 2.0_dp, 4.0_dp, -3.0_dp, 6.0_dp, -30.0_dp, -5.0_dp, 2.0_dp, 4.0_dp, -3.0_dp, 6.0_dp, &
      -12.0_dp, -20.0_dp, -3.0_dp, 7.0_dp, 1.0_dp, -2.0_dp, -150.0_dp, 5.0_dp, -10.0_dp, 0.0_dp, 15.0_dp, 0.0_dp, &
      12.0_dp, -25.0_dp, -30.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, 0.5_dp, 0.45_dp, 0.4_dp, 0.02_dp, 0.0_dp, 0.01_dp, &
      -1.0e4_dp, 2.0e3_dp, -5.0e3_dp, 3.0e3_dp, -1.0e3_dp, 4.0e3_dp, 9.0_dp, -4.0_dp, -6.0_dp, 1.0_dp, 2.0_dp, -1.0_dp], &
      [6, 8])
    real(dp), parameter :: expected(6, 8) = reshape([ &
      -2.9065430430028290e+01_dp, -8.9651496658228922e+00_dp, -5.1086898343848706e+00_dp, 2.2270485469503680e+00_dp, &
      -2.4469137989900847e+00_dp, 4.9483277656136631e+00_dp, &
      -2.3056571995210263e+01_dp, -7.1926614751967479e+00_dp, -2.7507665295929682e+00_dp, 2.5382256832021604e+00_dp, &
      -1.9036692624016216e+00_dp, 3.8073385248032428e+00_dp, &
      -1.1880145568868926e+01_dp, -1.9702532653546033e+01_dp, -3.4260482782796018e+00_dp, 6.7031320224803244e+00_dp, &
      9.6543809345347986e-01_dp, -1.9487299422075199e+00_dp, &
      -1.6017819445159893e+02_dp, -7.5205674833276710e+00_dp, -2.0807660921491411e+01_dp, 0.0000000000000000e+00_dp, &
      1.4932557163940087e+01_dp, 0.0000000000000000e+00_dp, &
      2.2578877266949458e+00_dp, -2.4907912146704085e+01_dp, -2.9398992824043539e+01_dp, 1.7980057694808127e+00_dp, &
      -7.8674927251562200e-03_dp, 7.3378553751212727e-01_dp, &
      4.4144180157544732e-01_dp, 4.2869440064839054e-01_dp, 4.0806887348164372e-01_dp, 8.3202386554958960e-03_dp, &
      -3.5013894398620962e-04_dp, 2.4094246078168809e-03_dp, &
      -5.0885397070007903e+00_dp, 1.0177079414001580e+00_dp, -2.5442698535003951e+00_dp, 1.5265619121002370e+00_dp, &
      -5.0885397070007898e-01_dp, 2.0354158828003159e+00_dp, &
      2.5142405494141595e+00_dp, -1.1174402441840710e+00_dp, -1.6761603662761064e+00_dp, 2.7936006104601774e-01_dp, &
      5.5872012209203548e-01_dp, -2.7936006104601774e-01_dp], [6, 8])
    type(matsuoka_nakai_t) :: m
    real(dp) :: sig(6), dt(6, 6)
    integer :: i, st
    do i = 1, 8
      m = make(par(1, i), par(2, i), par(5, i), e=e, nu=par(3, i), tension=nint(par(4, i)))
      call return_of(m, trials(:, i), sig, st, dt)
      call check(error, maxval(abs(sig - expected(:, i))), 0.0_dp, 'numpy reference, trial ' // str(i), &
                 abs=1.0e-10_dp * (maxval(abs(trials(:, i))) + m%apex))
      if (allocated(error)) return
      call check(error, st, merge(state_tension, state_plastic, i >= 7), 'numpy reference, trial ' // str(i) // ': state')
      if (allocated(error)) return
    end do
  end subroutine test_numpy_reference

  !> TENSION=closest-point: a trial returns to the apex exactly where sigma_tr - M I = dlambda D n
  !! for some n in the subdifferential of the potential cone at its apex, derived here without
  !! the module: with the cone written |s| = k(theta) (M* - p) (k from the thesis's cubic J1 J2 -
  !! zeta* J3 = 0 by bisection at 720 Lode angles), D n = 2 G y + K I with y in the dual unit
  !! ball of |s| / k(theta), so the apex is reached iff p_tr > M and max_theta <y, s_hat(theta)>
  !! k(theta) <= 1 for y = K s_tr / (2 G (p_tr - M)); for psi = 0 (no volume change) iff p_tr >=
  !! M. 2400 random trials beyond the apex (fixed seed; phi = 26.57 and 54.9 deg, psi = 0,
  !! phi/2, phi, nu = 0.2, -0.9, 0.49, generic axes) must be classified alike (state tension
  !! against plastic), except within 1e-3 of the border (the sampled maximum's accuracy).
  subroutine test_apex_region(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: nt = 720
    real(dp), parameter :: angles(2) = [26.57_dp, 54.9_dp], nus(3) = [0.2_dp, -0.9_dp, 0.49_dp]
    real(dp), parameter :: e1(3) = [2.0_dp, -1.0_dp, -1.0_dp] / sqrt(6.0_dp), e2(3) = [0.0_dp, 1.0_dp, -1.0_dp] / sqrt(2.0_dp)
    type(matsuoka_nakai_t) :: m
    real(dp) :: kt(nt), dirs(3, nt), th, sp(3), y(3), p, val, bulk, shear, trial(6), sig(6), dt(6, 6), r(3, 3)
    integer(kind=8) :: seed
    integer :: i, j, k, n, it, st, counts(2)
    seed = 1618033_8
    counts = 0
    do it = 1, nt
      th = 2.0_dp * 3.141592653589793238_dp * (it - 1) / nt
      dirs(:, it) = cos(th) * e1 + sin(th) * e2
    end do
    do i = 1, size(angles)
      do j = 0, 2
        do it = 1, nt
          kt(it) = cone_radius_thesis(0.5_dp * j * angles(i), dirs(:, it))
        end do
        do k = 1, size(nus)
          m = make(angles(i), 0.5_dp * j * angles(i), 4.0_dp, nu=nus(k), tension=tension_closest_point)
          bulk = m%e / (3.0_dp * (1.0_dp - 2.0_dp * m%nu))
          shear = m%e / (2.0_dp * (1.0_dp + m%nu))
          do n = 1, 400 / 3
            ! beyond the apex: p_tr > M, a deviator of 0.03 .. 3 M
            p = m%apex * (1.0_dp + 2.0_dp * next_uniform(seed))
            sp = m%apex * 10.0_dp**(2.0_dp * next_uniform(seed) - 1.5_dp) * &
                 [next_uniform(seed) - 0.5_dp, next_uniform(seed) - 0.5_dp, next_uniform(seed) - 0.5_dp]
            sp = p + sp - sum(sp) / 3.0_dp
            r = rotation(6.0_dp * next_uniform(seed), 6.0_dp * next_uniform(seed), 6.0_dp * next_uniform(seed))
            trial = rotate_stress(r, [sp(1), sp(2), sp(3), 0.0_dp, 0.0_dp, 0.0_dp])
            call return_of(m, trial, sig, st, dt)
            if (j == 0) then
              if (abs(p - m%apex) < 1.0e-9_dp * m%apex) cycle
              val = merge(0.0_dp, 2.0_dp, p > m%apex)
            else
              y = bulk * (sp - p) / (2.0_dp * shear * (p - m%apex))
              val = maxval(matmul(y, dirs) * kt)
              if (abs(val - 1.0_dp) < 1.0e-3_dp) cycle
            end if
            call check(error, st, merge(state_tension, state_plastic, val < 1.0_dp), 'apex region: phi ' // &
                       str(m%phi) // ' psi ' // str(m%psi) // ' nu ' // str(m%nu) // ' trial ' // str(n) // &
                       ' (dual-norm value ' // str(val) // ')')
            if (allocated(error)) return
            if (val < 1.0_dp) then
              counts(1) = counts(1) + 1
            else
              counts(2) = counts(2) + 1
            end if
          end do
        end do
      end do
    end do
    call check(error, all(counts > 300), 'apex region: both sides occur (' // str(counts(1)) // ' at the apex, ' // &
               str(counts(2)) // ' on the cone)')
  end subroutine test_apex_region

  !> k with J1 J2 - zeta* J3 = 0 at b = 1 - k s_hat (principal sigma-bar = M* - sigma with
  !! M* - p = 1), zeta* = 9 + 8 tan^2(psi): the cone's radius per unit depth along the unit
  !! deviator s_hat; bisection from the axis (inside) to the octant's face.
  pure real(dp) function cone_radius_thesis(psi, s_hat) result(k)
    real(dp), intent(in) :: psi, s_hat(3)
    real(dp) :: zs, lo, hi, b(3)
    integer :: i
    zs = 9.0_dp + 8.0_dp * tan(psi * deg2rad)**2
    lo = 0.0_dp
    hi = 1.0_dp / maxval(s_hat)
    do i = 1, 100
      k = 0.5_dp * (lo + hi)
      b = 1.0_dp - k * s_hat
      if (sum(b) * (b(1) * b(2) + b(2) * b(3) + b(1) * b(3)) - zs * product(b) < 0.0_dp) then
        lo = k
      else
        hi = k
      end if
    end do
    k = 0.5_dp * (lo + hi)
  end function cone_radius_thesis

  !> The flow rule against the thesis's own potential (eq. 2.4.6-2.4.8, zeta* = 9 + 8 tan^2 psi)
  !! written out here in Cartesian components: M* by bisection so that g = 0 at the returned
  !! stress (on the branch M* > sigma_1), the gradient by eq. 2.4.12 (with the I2 of eq. 2.4.4
  !! taken with -tau^2, as eq. 2.4.12 itself implies). The plastic strain D^-1 (sigma_tr -
  !! sigma) of every plastic return must be parallel to it (misfit 1e-8 of its size) with a
  !! positive multiplier: 1200 random trials (fixed seed), phi = 15, 26.57, 54.9 deg, psi =
  !! phi/3, 2 phi/3, phi (psi = 0 is the deviator, checked by check_returned), nu = 0.2, -0.9,
  !! 0.49, both tension rules, returns with |s| > 0.02 M (nearer the apex the stress carries too
  !! few digits of sigma - M).
  subroutine test_thesis_potential_flow(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: angles(3) = [15.0_dp, 26.57_dp, 54.9_dp], nus(3) = [0.2_dp, -0.9_dp, 0.49_dp]
    type(matsuoka_nakai_t) :: m
    real(dp) :: sig_tr(6), sig(6), dt(6, 6), ep(6), ng(6), proj, dev(6)
    integer(kind=8) :: seed
    integer :: i, j, k, n, st, rule, checked
    seed = 31337_8
    checked = 0
    do rule = tension_proportional, tension_closest_point
      do i = 1, size(angles)
        do j = 1, 3
          do k = 1, size(nus)
            m = make(angles(i), j * angles(i) / 3.0_dp, 4.0_dp, nu=nus(k), tension=rule)
            do n = 1, 23
              sig_tr(1:3) = m%apex * (8.0_dp * next_uniform(seed) - 6.5_dp)
              sig_tr(4:6) = m%apex * (4.0_dp * [next_uniform(seed), next_uniform(seed), next_uniform(seed)] - 2.0_dp)
              sig_tr(2) = m%apex * (8.0_dp * next_uniform(seed) - 6.5_dp)
              sig_tr(3) = m%apex * (8.0_dp * next_uniform(seed) - 6.5_dp)
              call return_of(m, sig_tr, sig, st, dt)
              if (st /= state_plastic) cycle
              dev = sig - sum(sig(1:3)) / 3.0_dp * [1, 1, 1, 0, 0, 0]
              if (sqrt(sum(dev(1:3)**2) + 2.0_dp * sum(dev(4:6)**2)) < 0.02_dp * m%apex) cycle
              ep = compliance(m%e, m%nu, sig_tr - sig)
              ng = thesis_potential_gradient(m%psi, sig)
              proj = dot_product(ep, ng) / dot_product(ng, ng)
              call check(error, proj > 0.0_dp, 'thesis potential: positive multiplier, phi ' // str(m%phi) // &
                         ' psi ' // str(m%psi) // ' trial ' // str(n))
              if (allocated(error)) return
              call check(error, norm2(ep - proj * ng), 0.0_dp, 'thesis potential: plastic strain along eq. 2.4.12, phi ' // &
                         str(m%phi) // ' psi ' // str(m%psi) // ' nu ' // str(m%nu) // ' trial ' // str(n), &
                         abs=1.0e-8_dp * norm2(ep))
              if (allocated(error)) return
              checked = checked + 1
            end do
          end do
        end do
      end do
    end do
    call check(error, checked >= 300, 'thesis potential: enough plastic returns checked (' // str(checked) // ')')
  end subroutine test_thesis_potential_flow

  !> The outward gradient (tension positive, engineering shears) of the thesis's potential
  !! through sig: eq. 2.4.12 with sigma-bar = M* - sigma and tau-bar = -tau (compression
  !! positive), M* the root > sigma_1 of J1 J2 - zeta* J3 = 0 by bisection, and the sign turned
  !! (the thesis's g = zeta* J3 - J1 J2 is negative outside).
  function thesis_potential_gradient(psi, sig) result(ng)
    real(dp), intent(in) :: psi, sig(6)
    real(dp) :: ng(6)
    real(dp) :: zs, lo, hi, mid, b(6), j1, j2
    integer :: i
    zs = 9.0_dp + 8.0_dp * tan(psi * deg2rad)**2
    lo = largest_principal(sig)
    hi = lo + maxval(abs(sig)) + 1.0_dp
    do while (potential_value(zs, hi, sig) > 0.0_dp)
      hi = lo + 2.0_dp * (hi - lo)
    end do
    do i = 1, 200
      mid = 0.5_dp * (lo + hi)
      if (potential_value(zs, mid, sig) > 0.0_dp) then
        lo = mid
      else
        hi = mid
      end if
    end do
    b(1:3) = 0.5_dp * (lo + hi) - sig(1:3)
    b(4:6) = -sig(4:6)
    j1 = b(1) + b(2) + b(3)
    j2 = b(1) * b(2) + b(2) * b(3) + b(1) * b(3) - b(4)**2 - b(5)**2 - b(6)**2
    ! eq. 2.4.12 (derivatives by the compression-positive stress), then d/dsigma = -d/dsigma-bar
    ng(1) = zs * (b(2) * b(3) - b(4)**2) - j1 * (b(2) + b(3)) - j2
    ng(2) = zs * (b(1) * b(3) - b(5)**2) - j1 * (b(1) + b(3)) - j2
    ng(3) = zs * (b(1) * b(2) - b(6)**2) - j1 * (b(1) + b(2)) - j2
    ng(4) = 2.0_dp * zs * (b(5) * b(6) - b(1) * b(4)) + 2.0_dp * b(4) * j1
    ng(5) = 2.0_dp * zs * (b(6) * b(4) - b(2) * b(5)) + 2.0_dp * b(5) * j1
    ng(6) = 2.0_dp * zs * (b(4) * b(5) - b(3) * b(6)) + 2.0_dp * b(6) * j1
    ! this is d g_thesis / d sigma-bar; g_thesis = zeta* J3 - J1 J2 decreases outwards and
    ! sigma-bar = M* I - sigma (every component), so the outward d/dsigma is ng itself
  end function thesis_potential_gradient

  !> J1 J2 - zeta* J3 of sigma-bar = x I - sig (tau-bar = -tau): positive between sigma_1
  !! and the potential's apex x = M*, negative beyond.
  pure real(dp) function potential_value(zs, x, sig) result(v)
    real(dp), intent(in) :: zs, x, sig(6)
    real(dp) :: b(6), j1, j2, j3
    b(1:3) = x - sig(1:3)
    b(4:6) = -sig(4:6)
    j1 = b(1) + b(2) + b(3)
    j2 = b(1) * b(2) + b(2) * b(3) + b(1) * b(3) - b(4)**2 - b(5)**2 - b(6)**2
    j3 = b(1) * b(2) * b(3) + 2.0_dp * b(4) * b(5) * b(6) - b(1) * b(4)**2 - b(2) * b(5)**2 - b(3) * b(6)**2
    v = j1 * j2 - zs * j3
  end function potential_value

  !> The largest principal stress (trigonometric solution of the characteristic cubic).
  pure real(dp) function largest_principal(sig) result(s1)
    real(dp), intent(in) :: sig(6)
    real(dp) :: q, p, b(6), r
    q = (sig(1) + sig(2) + sig(3)) / 3.0_dp
    b = sig
    b(1:3) = b(1:3) - q
    p = sqrt((b(1)**2 + b(2)**2 + b(3)**2 + 2.0_dp * (b(4)**2 + b(5)**2 + b(6)**2)) / 6.0_dp)
    s1 = q
    if (.not. (p > 0.0_dp)) return
    b = b / p
    r = 0.5_dp * (b(1) * b(2) * b(3) + 2.0_dp * b(4) * b(5) * b(6) - b(1) * b(4)**2 - b(2) * b(5)**2 - b(3) * b(6)**2)
    s1 = q + 2.0_dp * p * cos(acos(max(-1.0_dp, min(1.0_dp, r))) / 3.0_dp)
  end function largest_principal

  !> Accepts E, NU, PHI, PSI with FT or C (apex eq. 2.4.5); rejects missing, out-of-range,
  !! doubly given and unknown parameters, naming them.
  subroutine test_validator(error)
    type(error_t), allocatable, intent(out) :: error
    class(material_t), allocatable :: mat
    type(error_t), allocatable :: err
    character(len=name_len), parameter :: kft(5) = [character(len=name_len) :: 'e', 'nu', 'phi', 'psi', 'ft']
    character(len=name_len), parameter :: kc(5) = [character(len=name_len) :: 'e', 'nu', 'phi', 'psi', 'c']
    character(len=name_len), parameter :: k6(6) = [character(len=name_len) :: 'e', 'nu', 'phi', 'psi', 'ft', 'c']
    real(dp) :: sn
    call new_matsuoka_nakai(material_spec('concrete', 'matsuoka', kft, [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp]), mat, err)
    if (allocated(err)) then
      call test_failed(error, 'valid parameters rejected: ' // err%message)
      return
    end if
    select type (mat)
    type is (matsuoka_nakai_t)
      sn = 0.5_dp
      call check(error, mat%e == 1.0e4_dp .and. mat%nu == 0.2_dp .and. mat%phi == 30.0_dp .and. &
                 mat%psi == 10.0_dp .and. mat%name == 'concrete', 'parameters stored')
      if (allocated(error)) return
      call check(error, mat%apex, 3.0_dp * (1.0_dp + 1.0_dp / sn), 'apex from ft', rel=1.0e-14_dp)
    class default
      call test_failed(error, 'wrong material type')
    end select
    if (allocated(error)) return
    call new_matsuoka_nakai(material_spec('concrete', 'matsuoka', kc, [1.0e4_dp, 0.2_dp, 45.0_dp, 0.0_dp, 5.0_dp]), mat, err)
    if (allocated(err)) then
      call test_failed(error, 'valid parameters (C) rejected: ' // err%message)
      return
    end if
    select type (mat)
    type is (matsuoka_nakai_t)
      call check(error, mat%apex, 5.0_dp, 'apex from c', rel=1.0e-14_dp)
    class default
      call test_failed(error, 'wrong material type')
    end select
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [0.0_dp, 0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp], 'E = ', &
                                  field=4)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft(2:5), [0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp], 'E is missing', &
                                  field=0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, 0.5_dp, 30.0_dp, 10.0_dp, 6.0_dp], 'NU = ', &
                                  field=5)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, -1.0_dp, 30.0_dp, 10.0_dp, 6.0_dp], 'NU = ', &
                                  field=5)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, 0.2_dp, 0.0_dp, 0.0_dp, 6.0_dp], 'PHI = ', &
                                  field=6)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, 0.2_dp, 90.0_dp, 10.0_dp, 6.0_dp], 'PHI = ', &
                                  field=6)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, 0.2_dp, 30.0_dp, 31.0_dp, 6.0_dp], 'PSI = ', &
                                  field=7)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, 0.2_dp, 30.0_dp, -1.0_dp, 6.0_dp], 'PSI = ', &
                                  field=7)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', [kft(1:3), kft(5)], &
                                  [1.0e4_dp, 0.2_dp, 30.0_dp, 6.0_dp], 'PSI is missing', field=0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, 0.0_dp], 'FT = ', &
                                  field=8)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kc, [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, -2.0_dp], 'C = ', &
                                  field=8)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', k6, &
                                  [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp, 3.0_dp], 'only one of FT and C', field=9)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft(1:4), &
                                  [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp], 'FT or C is missing', field=0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', [character(len=name_len) :: 'e', 'nu', 'phi', 'psi', 'ft', 'kn'], &
                         [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp, 1.0_dp], 'unknown parameter KN', field=9)
    if (allocated(error)) return
    ! FT and C together: the second of the two is named, whichever it is.
    call expect_material_rejected(error, 'concrete', 'matsuoka', [character(len=name_len) :: 'e', 'ft', 'nu', 'c', 'phi', 'psi'], &
                                  [1.0e4_dp, 6.0_dp, 0.2_dp, 3.0_dp, 30.0_dp, 10.0_dp], 'only one of FT and C', field=7)
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', [character(len=name_len) :: 'e', 'c', 'nu', 'ft', 'phi', 'psi'], &
                                  [1.0e4_dp, 3.0_dp, 0.2_dp, 6.0_dp, 30.0_dp, 10.0_dp], 'only one of FT and C', field=7)
    if (allocated(error)) return
    ! A record built without field numbers: the same errors, naming no field.
    call expect_material_rejected(error, 'concrete', 'matsuoka', kft, [1.0e4_dp, 0.2_dp, 30.0_dp, 31.0_dp, 6.0_dp], 'PSI = ')
    if (allocated(error)) return
    call expect_material_rejected(error, 'concrete', 'matsuoka', k6, &
                                  [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp, 3.0_dp], 'only one of FT and C')
    if (allocated(error)) return
    ! TENSION: a rule's name, the default the thesis's
    call check(error, tension_of(''), tension_proportional, 'no TENSION: proportional')
    if (allocated(error)) return
    call check(error, tension_of('proportional'), tension_proportional, 'TENSION=proportional')
    if (allocated(error)) return
    call check(error, tension_of('closest-point'), tension_closest_point, 'TENSION=closest-point')
    if (allocated(error)) return
    call expect_tension_rejected(error, 'sideways')
    if (allocated(error)) return
    call expect_tension_rejected(error, '')   ! given as a number (TENSION=1)
  end subroutine test_validator

  !> E, NU, PHI, PSI, FT and TENSION given as `word` ('' as if a number had been given).
  function spec_with_tension(word) result(spec)
    character(len=*), intent(in) :: word
    type(material_spec_t) :: spec
    spec = material_spec('concrete', 'matsuoka', [character(len=name_len) :: 'e', 'nu', 'phi', 'psi', 'ft', 'tension'], &
                   [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp, 1.0_dp], record_fields(6))
    spec%texts = [character(len=name_len) :: '', '', '', '', '', word]
  end function spec_with_tension

  !> The tension rule the validator stores for TENSION=`word` (`word` = '': TENSION left out).
  integer function tension_of(word) result(rule)
    character(len=*), intent(in) :: word
    class(material_t), allocatable :: mat
    type(error_t), allocatable :: err
    rule = -1
    if (word == '') then
      call new_matsuoka_nakai(material_spec('concrete', 'matsuoka', [character(len=name_len) :: 'e', 'nu', 'phi', 'psi', 'ft'], &
                                      [1.0e4_dp, 0.2_dp, 30.0_dp, 10.0_dp, 6.0_dp]), mat, err)
    else
      call new_matsuoka_nakai(spec_with_tension(word), mat, err)
    end if
    if (allocated(err)) return
    select type (mat)
    type is (matsuoka_nakai_t)
      rule = mat%tension
    end select
  end function tension_of

  subroutine expect_tension_rejected(error, word)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in) :: word
    class(material_t), allocatable :: mat
    type(error_t), allocatable :: err
    call new_matsuoka_nakai(spec_with_tension(word), mat, err)
    if (.not. allocated(err)) then
      call test_failed(error, 'TENSION="' // word // '" accepted')
      return
    end if
    call check(error, index(err%message, 'deck.inp:23: field 9: material concrete: ') == 1 .and. &
               index(err%message, 'TENSION = "' // word // '": it must be') > 0 &
               .and. index(err%message, 'CLOSEST-POINT') > 0, 'message "' // err%message // '" names TENSION')
  end subroutine expect_tension_rejected

end module test_matsuoka
