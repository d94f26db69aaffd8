!> Modified Matsuoka-Nakai elastic-perfectly-plastic model for concrete and soil (thesis
!! section 2.4.2, with zeta = 9 + 8 tan^2(phi), SPEC section 5).
!!
!! Components: 6 Voigt stresses [xx yy zz yz xz xy] and strains with engineering shears,
!! tension positive. Elasticity is isotropic (E, nu).
!!
!! Yield function. The thesis writes f for compression-positive stress; with tension-positive
!! sigma the shifted stress is sigma* = M I - sigma (apex at hydrostatic tension M) and
!!   f = I1* I2* - zeta I3*,  zeta = 9 + 8 tan^2(phi),  M = c / tan(phi) = ft/2 (1 + 1/sin(phi))
!! (the thesis's expression with the opposite sign, so that f > 0 is outside near the surface).
!! In terms of the mean stress p = tr(sigma)/3 and the deviator s, f = 0 is equivalent to
!!   F(sigma) = r(s) + beta (p - M) = 0,
!! with beta = tan(phi) sqrt(6 / (3 + 4 tan^2 phi)) and r >= 0 the largest root of
!!   r^3 - 3/2 J2 r - 3/2 gamma J3 = 0,  gamma = zeta beta / (zeta - 3),
!! J2 = s:s/2, J3 = det(s). Explicitly r = rho cos(acos(h cos 3 theta)/3), rho = |s|,
!! cos 3 theta = 3 sqrt(6) J3 / rho^3, h = gamma sqrt(2/3) with |h| < 1 for every phi.
!! F (stress units, positive outside) is a convex, positively homogeneous function of
!! sigma - M I, smooth except on the hydrostatic axis; it is the function used in the return,
!! and the cubic f is available as `yield_cubic` (its other branches lie outside the positive
!! octant of sigma*, so it is only meaningful near the surface).
!!
!! Plastic potential g (eq. 2.4.6-2.4.8): the same cone with zeta* = 9 + 8 tan^2(psi) and an
!! apex M* chosen so that g passes through the current stress. The gradient of g at frozen M*
!! is then parallel to the gradient of G(sigma) = r*(s) + beta* p (M* does not enter it), so
!! the flow direction is n_g = dG/dsigma. For psi = 0 it is the von Mises direction
!! sqrt(3)/2 s/|s| (no volume change).
!!
!! Stress update (backward Euler, closest-point return along D n_g at the end point):
!!  - elastic trial sigma_tr = sig0 + D deps; F(sigma_tr) < -1e-12 scale: elastic;
!!  - tension zone (rule `tension_proportional`, the thesis's and the default): the most
!!    tensile principal trial stress sigma_1 >= M (sigma*_min <= 0).
!!    "Proportionally put back" is implemented as a scaling about the origin (zero stress,
!!    which lies inside the surface since M > 0): sigma = alpha sigma_tr with the unique
!!    alpha in (0, 1] that puts it on the surface, alpha = beta M / (r(s_tr) + beta p_tr)
!!    (closed form: F is linear along the ray). Hydrostatic tension beyond the apex gives the
!!    apex M I exactly; uniaxial tension sigma > M gives (ft, 0, 0). State state_tension.
!!    This rule makes the update discontinuous where sigma_1 crosses M (the closest-point
!!    return just below M lands elsewhere on the surface; jumps of up to 16 MPa for chapter
!!    9's concrete), so Newton iterations that cross it may cycle;
!!  - rule `tension_closest_point` (MATERIAL key TENSION=closest-point, not in the thesis): no
!!    tension zone; every trial outside the surface takes the closest-point return below, and
!!    where that return passes the apex (rho <= 0) the stress is the apex M I, state
!!    state_tension, tangent apex_stiffness_factor D (the exact derivative there is zero). The
!!    update is continuous;
!!  - within 1e-12 of the surface: sigma = sigma_tr, state_plastic (no return);
!!  - otherwise the closest-point return, state_plastic. Because D, F and G are isotropic the
!!    return keeps the principal axes of the trial, and the return equations reduce exactly to
!!    one scalar equation for the Lode angle theta of the end point (theta in [0, pi/3], cos
!!    3 theta = 3 sqrt(6) det(s)/|s|^3): with omega(theta) = r/rho and delta = theta_tr - theta,
!!      R(theta) = rho_tr sin(delta) (K beta beta* + 2 mu omega omega*)
!!                 - 2 mu omega*'(theta) (rho_tr omega cos(delta) - beta (M - p_tr)) = 0,
!!    R(0) >= 0 >= R(pi/3); it is solved by Newton's method with a bisection safeguard on
!!    this bracket to machine precision, then dlambda = (rho_tr omega cos(delta) - beta
!!    (M - p_tr)) / (K beta beta* + 2 mu omega omega*), p = p_tr - K beta* dlambda,
!!    rho = beta (M - p) / omega (so F = 0 exactly), and the end deviator is rebuilt from the
!!    trial by a rotation in the deviatoric plane, s = rho (cos(delta) s_tr/|s_tr| + sin(delta)
!!    w), w the unit coaxial deviator orthogonal to s_tr (from dev(s_tr^2)). No eigenvectors are
!!    needed and the result is covariant under rotations of the axes. Outside the tension zone
!!    p_tr < M, so under the proportional rule this return always has a solution on the
!!    smooth part of the surface (R's bracket holds for any p_tr).
!!
!! Tangents: normal return: the consistent (algorithmic) tangent
!!   dtan = Xi - Xi n_g n_f^T Xi / (n_f^T Xi n_g),  Xi = (D^-1 + dlambda d2G/dsigma2)^-1,
!! with the gradients and Hessians of r from the cubic by implicit differentiation (exact
!! derivative of the update; non-symmetric unless psi = phi). Tension zone: the continuum
!! elastic-plastic tangent D - D n_g n_f^T D / (n_f^T D n_g) at the returned stress
!! (symmetric for psi = phi, of the right size; the exact derivative of the proportional
!! return is not symmetric even for psi = phi); at the apex itself (hydrostatic trial) it is
!! alpha (D - K m m^T) + apex_stiffness_factor K m m^T (m = [1 1 1 0 0 0]): the deviatoric
!! response of the proportional return plus a small volumetric residual stiffness.
module feps_matsuoka_nakai
  use feps_kinds, only: dp, deg2rad, pi
  use feps_error, only: error_t, input_error, str
  use feps_model, only: material_spec_t
  use feps_material_params, only: check_known_keys, get_parameter, material_error, material_conflict, &
                                  get_unit_weight, get_k0
  use feps_material, only: material_t, state_elastic, state_plastic, state_tension, modulus_warning
  use feps_elastic, only: elastic_matrix
  use feps_strings, only: sci
  implicit none
  private

  public :: new_matsuoka_nakai, apex_from_tensile_strength, apex_from_cohesion

  !> Tension-zone rules (MATERIAL key TENSION=proportional | closest-point).
  integer, parameter, public :: tension_proportional = 1, tension_closest_point = 2

  !> Volumetric residual stiffness at the apex (tension zone, hydrostatic trial): K times this.
  real(dp), parameter, public :: apex_stiffness_factor = 1.0e-6_dp

  !> Relative band around the surface taken as on it (no return needed).
  real(dp), parameter :: yield_tolerance = 1.0e-12_dp

  real(dp), parameter :: sqrt6 = 2.449489742783178098197284074705891391965947480656670128432692567_dp
  real(dp), parameter :: sqrt2_3 = 0.816496580927726032732428024901963797321982493552223376144230855_dp

  !> Modified Matsuoka-Nakai material: E, nu, friction angle phi and dilation angle psi in
  !! degrees (0 < phi < 90, 0 <= psi <= phi) and the apex M (hydrostatic tension, > 0).
  type, extends(material_t), public :: matsuoka_nakai_t
    real(dp) :: e = 0.0_dp
    real(dp) :: nu = 0.0_dp
    real(dp) :: phi = 0.0_dp
    real(dp) :: psi = 0.0_dp
    real(dp) :: apex = 0.0_dp    !! M = c / tan(phi) = ft/2 (1 + 1/sin(phi))
    !> The return of trials in the tension zone: tension_proportional (thesis 2.4.2, the
    !! default) or tension_closest_point (continuous; the apex for trials beyond it)
    integer :: tension = tension_proportional
  contains
    procedure :: elastic_tangent => mn_elastic_tangent
    procedure :: update => mn_update
    procedure :: is_linear => mn_is_linear
    procedure :: symmetric_tangent => mn_symmetric_tangent
    procedure :: state_note => mn_state_note
    procedure :: yield_value => mn_yield_value
    procedure :: yield_cubic => mn_yield_cubic
    procedure :: unit_warning => mn_unit_warning
  end type matsuoka_nakai_t

  !> Constants of one Matsuoka-Nakai cone (yield: angle phi; potential: angle psi).
  type :: cone_t
    real(dp) :: beta = 0.0_dp    !! slope of the mean stress term
    real(dp) :: gam = 0.0_dp     !! J3 coefficient of the cubic for r
    real(dp) :: h = 0.0_dp       !! gam sqrt(2/3), |h| < 1
  end type cone_t

contains

  ! ------------------------------------------------------------------ parameters

  !> Apex M from the uniaxial tensile strength (eq. 2.4.5): M = ft/2 (1 + 1/sin(phi)).
  pure real(dp) function apex_from_tensile_strength(ft, phi) result(m)
    real(dp), intent(in) :: ft    !! uniaxial tensile strength
    real(dp), intent(in) :: phi   !! friction angle, degrees
    m = 0.5_dp * ft * (1.0_dp + 1.0_dp / sin(phi * deg2rad))
  end function apex_from_tensile_strength

  !> Apex M from the cohesion (eq. 2.4.5): M = c / tan(phi).
  pure real(dp) function apex_from_cohesion(c, phi) result(m)
    real(dp), intent(in) :: c     !! cohesion
    real(dp), intent(in) :: phi   !! friction angle, degrees
    m = c / tan(phi * deg2rad)
  end function apex_from_cohesion

  pure function make_cone(angle_deg) result(cone)
    real(dp), intent(in) :: angle_deg
    type(cone_t) :: cone
    real(dp) :: t2
    t2 = tan(angle_deg * deg2rad)**2
    cone%beta = sqrt(6.0_dp * t2 / (3.0_dp + 4.0_dp * t2))
    cone%gam = (9.0_dp + 8.0_dp * t2) * cone%beta / (6.0_dp + 8.0_dp * t2)
    ! 1 - h^2 = 216 (1 + t2) / (6 + 8 t2)^3 > 0; keep it representable for phi -> 90 deg so
    ! that acos(h cos 3 theta) stays differentiable (changes nothing below phi = 89.99 deg).
    cone%h = min(cone%gam * sqrt2_3, 1.0_dp - 1.0e-12_dp)
    cone%gam = cone%h / sqrt2_3
  end function make_cone

  ! ------------------------------------------------------------------ material interface

  !> Isotropic elastic matrix (eq. 2.4.10).
  pure subroutine mn_elastic_tangent(self, d)
    class(matsuoka_nakai_t), intent(in) :: self
    real(dp), intent(out) :: d(:, :)
    d = elastic_matrix(self%e, self%nu)
  end subroutine mn_elastic_tangent

  pure logical function mn_is_linear(self)
    class(matsuoka_nakai_t), intent(in) :: self
    mn_is_linear = .false.
  end function mn_is_linear

  !> The consistent tangent is symmetric only for associated flow (psi = phi).
  pure logical function mn_symmetric_tangent(self)
    class(matsuoka_nakai_t), intent(in) :: self
    mn_symmetric_tangent = self%psi == self%phi
  end function mn_symmetric_tangent

  !> Under the thesis's tension rule a point in the tension zone was returned proportionally,
  !! across the jump of the update at sigma_1 = M: say so and name the continuous rule.
  pure subroutine mn_state_note(self, state, note)
    class(matsuoka_nakai_t), intent(in) :: self
    integer, intent(in) :: state
    character(len=:), allocatable, intent(out) :: note
    note = ''
    if (self%tension == tension_proportional .and. state == state_tension) note = 'material ' // self%name // &
      ': points reached the tension zone, whose proportional return (thesis 2.4.2) makes the stress jump ' // &
      'where sigma_1 reaches the apex, so the result may depend on the step size; TENSION=closest-point is ' // &
      'continuous (docs/input-format.md)'
  end subroutine mn_state_note

  !> Yield value F(sigma) = r(s) + beta (p - M) in stress units: negative inside, zero on the
  !! surface, positive outside (a convex function, scaled like a stress distance).
  pure real(dp) function mn_yield_value(self, sig) result(f)
    class(matsuoka_nakai_t), intent(in) :: self
    real(dp), intent(in) :: sig(6)
    type(cone_t) :: cone
    real(dp) :: p, s(6)
    cone = make_cone(self%phi)
    call split(sig, p, s)
    f = cone_radius(s, cone) + cone%beta * (p - self%apex)
  end function mn_yield_value

  !> The thesis's cubic yield function with the sign turned, f = I1* I2* - zeta I3*,
  !! sigma* = M I - sigma, zeta = 9 + 8 tan^2(phi): zero on the surface, positive just outside.
  pure real(dp) function mn_yield_cubic(self, sig) result(f)
    class(matsuoka_nakai_t), intent(in) :: self
    real(dp), intent(in) :: sig(6)
    real(dp) :: a(6), i1, i2, i3, zeta
    zeta = 9.0_dp + 8.0_dp * tan(self%phi * deg2rad)**2
    a = -sig
    a(1:3) = a(1:3) + self%apex
    i1 = a(1) + a(2) + a(3)
    i2 = a(1) * a(2) + a(2) * a(3) + a(1) * a(3) - a(4)**2 - a(5)**2 - a(6)**2
    i3 = det_voigt(a)
    f = i1 * i2 - zeta * i3
  end function mn_yield_cubic

  !> Stress update over a step from sig0 (eps0 and state0 are not needed: the model is
  !! perfectly plastic and has no internal variables). See the module description.
  pure subroutine mn_update(self, sig0, eps0, deps, state0, sig, state, dtan, var0, var)
    class(matsuoka_nakai_t), intent(in) :: self
    real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
    integer, intent(in) :: state0
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(:, :)
    real(dp), intent(in), optional :: var0(:)   !! no internal variables (state_size 0)
    real(dp), intent(out), optional :: var(:)
    real(dp) :: d(6, 6), sig_tr(6), sig_new(6), dnew(6, 6)
    d = elastic_matrix(self%e, self%nu)
    sig_tr = sig0(1:6) + matmul(d, deps(1:6))
    call return_map(self, d, sig_tr, sig_new, state, dnew)
    sig = sig_new
    dtan = dnew
  end subroutine mn_update

  ! ------------------------------------------------------------------ return map

  !> Stress, state and tangent d sig / d eps for a trial stress (D the elastic matrix).
  pure subroutine return_map(self, d, sig_tr, sig, state, dtan)
    class(matsuoka_nakai_t), intent(in) :: self
    real(dp), intent(in) :: d(6, 6), sig_tr(6)
    real(dp), intent(out) :: sig(6)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(6, 6)
    type(cone_t) :: yc, pc
    real(dp) :: p_tr, s_tr(6), rho_tr, s_hat(6), w_hat(6), theta_tr, omega_tr, f_tr, scale
    real(dp) :: sigma_1, bulk, shear, theta, delta, wf, dwf, d2wf, wg, dwg, d2wg, b, dlambda, p, rho
    real(dp) :: alpha, mm(6, 6), m

    m = self%apex
    yc = make_cone(self%phi)
    pc = make_cone(self%psi)
    bulk = self%e / (3.0_dp * (1.0_dp - 2.0_dp * self%nu))
    shear = self%e / (2.0_dp * (1.0_dp + self%nu))

    call split(sig_tr, p_tr, s_tr)
    call lode_frame(s_tr, rho_tr, s_hat, w_hat, theta_tr)
    call lode_shape(yc%h, theta_tr, omega_tr, dwf, d2wf)
    f_tr = rho_tr * omega_tr + yc%beta * (p_tr - m)
    scale = rho_tr + yc%beta * (abs(p_tr) + m)

    if (f_tr < -yield_tolerance * scale) then
      sig = sig_tr
      state = state_elastic
      dtan = d
      return
    end if

    ! Tension zone (thesis rule): most tensile principal stress at or beyond the apex.
    sigma_1 = p_tr + rho_tr * sqrt2_3 * cos(theta_tr)
    if (self%tension == tension_proportional .and. sigma_1 >= m) then
      alpha = min(1.0_dp, yc%beta * m / max(f_tr + yc%beta * m, tiny(1.0_dp)))
      sig = alpha * sig_tr
      state = state_tension
      if (rho_tr > 1.0e-12_dp * (abs(p_tr) + m)) then
        call consistent_tangent(self, d, sig, 0.0_dp, dtan)
      else
        mm = 0.0_dp
        mm(1:3, 1:3) = bulk
        dtan = alpha * (d - mm) + apex_stiffness_factor * mm
      end if
      return
    end if

    state = state_plastic
    if (f_tr <= yield_tolerance * scale) then
      sig = sig_tr
      call consistent_tangent(self, d, sig, 0.0_dp, dtan)
      return
    end if

    call solve_lode_angle(theta_tr, rho_tr, p_tr, m, yc, pc, bulk, shear, theta)
    call lode_shape(yc%h, theta, wf, dwf, d2wf)
    call lode_shape(pc%h, theta, wg, dwg, d2wg)
    delta = theta_tr - theta
    b = bulk * yc%beta * pc%beta + 2.0_dp * shear * wf * wg
    dlambda = (rho_tr * wf * cos(delta) - yc%beta * (m - p_tr)) / b
    p = p_tr - bulk * pc%beta * dlambda
    rho = yc%beta * (m - p) / wf
    if (self%tension == tension_closest_point .and. .not. (rho > 0.0_dp)) then
      ! The return passes the apex: the stress is the apex itself, the same for every trial
      ! of this region (zero derivative; a small residual stiffness keeps the matrix regular).
      ! Continuous with the return to the cone, where rho -> 0 at the region's border.
      sig = 0.0_dp
      sig(1:3) = m
      state = state_tension
      dtan = apex_stiffness_factor * d
      return
    end if
    if (.not. (dlambda > 0.0_dp .and. rho > 0.0_dp)) then
      ! Not expected for a trial outside the surface with p_tr < M (a safeguard only):
      ! put the stress back proportionally as in the tension zone.
      alpha = min(1.0_dp, yc%beta * m / max(f_tr + yc%beta * m, tiny(1.0_dp)))
      sig = alpha * sig_tr
      call consistent_tangent(self, d, sig, 0.0_dp, dtan)
      return
    end if
    sig = rho * (cos(delta) * s_hat + sin(delta) * w_hat)
    sig(1:3) = sig(1:3) + p
    call consistent_tangent(self, d, sig, dlambda, dtan)
  end subroutine return_map

  !> The Lode angle theta of the returned stress: root of the reduced return equation R(theta)
  !! on [0, pi/3] (R(0) >= 0 >= R(pi/3)) by Newton's method kept inside a shrinking bracket
  !! (bisection when a Newton step leaves it), started from the trial's angle.
  pure subroutine solve_lode_angle(theta_tr, rho_tr, p_tr, m, yc, pc, bulk, shear, theta)
    real(dp), intent(in) :: theta_tr, rho_tr, p_tr, m, bulk, shear
    type(cone_t), intent(in) :: yc, pc
    real(dp), intent(out) :: theta
    real(dp) :: lo, hi, r, dr, theta_new, delta, wf, dwf, d2wf, wg, dwg, d2wg, b, db, c, dc
    integer :: iter

    lo = 0.0_dp
    hi = pi / 3.0_dp
    theta = min(max(theta_tr, lo), hi)
    do iter = 1, 200
      call lode_shape(yc%h, theta, wf, dwf, d2wf)
      call lode_shape(pc%h, theta, wg, dwg, d2wg)
      delta = theta_tr - theta
      b = bulk * yc%beta * pc%beta + 2.0_dp * shear * wf * wg
      db = 2.0_dp * shear * (dwf * wg + wf * dwg)
      c = rho_tr * wf * cos(delta) - yc%beta * (m - p_tr)
      dc = rho_tr * (dwf * cos(delta) + wf * sin(delta))
      r = rho_tr * sin(delta) * b - 2.0_dp * shear * dwg * c
      dr = -rho_tr * cos(delta) * b + rho_tr * sin(delta) * db - 2.0_dp * shear * (d2wg * c + dwg * dc)
      if (r == 0.0_dp) return
      if (r > 0.0_dp) then
        lo = theta
      else
        hi = theta
      end if
      theta_new = 0.5_dp * (lo + hi)
      if (dr /= 0.0_dp) then
        if (theta - r / dr > lo .and. theta - r / dr < hi) theta_new = theta - r / dr
      end if
      if (abs(theta_new - theta) <= 4.0_dp * epsilon(1.0_dp) .or. hi - lo <= 4.0_dp * epsilon(1.0_dp)) then
        theta = theta_new
        return
      end if
      theta = theta_new
    end do
  end subroutine solve_lode_angle

  !> Consistent tangent of the return with multiplier dlambda at the returned stress sig
  !! (dlambda = 0: the continuum elastic-plastic tangent).
  pure subroutine consistent_tangent(self, d, sig, dlambda, dtan)
    class(matsuoka_nakai_t), intent(in) :: self
    real(dp), intent(in) :: d(6, 6), sig(6), dlambda
    real(dp), intent(out) :: dtan(6, 6)
    type(cone_t) :: yc, pc
    real(dp) :: p, s(6), r, nf(6), ng(6), hg(6, 6), a(6, 6), xi(6, 6), xng(6), nfx(6), den
    integer :: i, j
    logical :: ok
    yc = make_cone(self%phi)
    pc = make_cone(self%psi)
    call split(sig, p, s)
    call cone_derivatives(s, yc, r, nf)
    call cone_derivatives(s, pc, r, ng, hg)
    nf(1:3) = nf(1:3) + yc%beta / 3.0_dp
    ng(1:3) = ng(1:3) + pc%beta / 3.0_dp
    if (dlambda > 0.0_dp) then
      a = dlambda * matmul(d, hg)
      do i = 1, 6
        a(i, i) = a(i, i) + 1.0_dp
      end do
      xi = d
      call solve_dense(a, xi, ok)
      if (.not. ok) xi = d
    else
      xi = d
    end if
    xng = matmul(xi, ng)
    nfx = matmul(nf, xi)
    den = dot_product(nf, xng)
    if (.not. (abs(den) > tiny(1.0_dp))) then
      dtan = xi
      return
    end if
    do j = 1, 6
      do i = 1, 6
        dtan(i, j) = xi(i, j) - xng(i) * nfx(j) / den
      end do
    end do
    if (self%psi == self%phi) then
      ! symmetric in exact arithmetic; remove the rounding so a symmetric solver sees it so
      do j = 1, 6
        do i = j + 1, 6
          dtan(i, j) = 0.5_dp * (dtan(i, j) + dtan(j, i))
          dtan(j, i) = dtan(i, j)
        end do
      end do
    end if
  end subroutine consistent_tangent

  ! ------------------------------------------------------------------ cone geometry

  !> omega(theta) = cos(acos(h cos 3 theta) / 3) and its first two derivatives.
  pure subroutine lode_shape(h, theta, w, dw, d2w)
    real(dp), intent(in) :: h, theta
    real(dp), intent(out) :: w, dw, d2w
    real(dp) :: x, a, sq, da, d2a, c3, s3
    c3 = cos(3.0_dp * theta)
    s3 = sin(3.0_dp * theta)
    x = h * c3
    a = acos(x)
    sq = sqrt(1.0_dp - x * x)   ! > 0: |h| < 1
    da = 3.0_dp * h * s3 / sq
    d2a = 9.0_dp * h * c3 / sq - 9.0_dp * h * h * s3 * s3 * x / sq**3
    w = cos(a / 3.0_dp)
    dw = -sin(a / 3.0_dp) * da / 3.0_dp
    d2w = -cos(a / 3.0_dp) * (da / 3.0_dp)**2 - sin(a / 3.0_dp) * d2a / 3.0_dp
  end subroutine lode_shape

  !> |s|, the unit deviator s/|s|, the unit coaxial deviator w orthogonal to it pointing to
  !! decreasing Lode angle (zero on a meridian), and the Lode angle theta in [0, pi/3]
  !! (theta = 0: uniaxial-tension-like deviator, pi/3: uniaxial-compression-like).
  !! theta comes from atan2 of sin 3 theta (from |w|) and cos 3 theta, accurate near the
  !! meridians where acos would not be.
  pure subroutine lode_frame(s, rho, s_hat, w_hat, theta)
    real(dp), intent(in) :: s(6)
    real(dp), intent(out) :: rho, s_hat(6), w_hat(6), theta
    real(dp) :: q(6), c3, wn
    rho = sqrt(inner(s, s))
    s_hat = 0.0_dp
    w_hat = 0.0_dp
    theta = 0.0_dp
    if (.not. (rho > 0.0_dp)) return
    s_hat = s / rho
    q = square_voigt(s_hat)
    q(1:3) = q(1:3) - (q(1) + q(2) + q(3)) / 3.0_dp
    c3 = sqrt6 * inner(q, s_hat)
    w_hat = q - inner(q, s_hat) * s_hat
    wn = sqrt(inner(w_hat, w_hat))
    if (wn > 0.0_dp) then
      w_hat = w_hat / wn
    else
      w_hat = 0.0_dp
    end if
    theta = atan2(sqrt6 * wn, c3) / 3.0_dp
  end subroutine lode_frame

  !> r(s) = |s| omega(theta) for the cone.
  pure real(dp) function cone_radius(s, cone) result(r)
    real(dp), intent(in) :: s(6)
    type(cone_t), intent(in) :: cone
    real(dp) :: rho, s_hat(6), c3
    rho = sqrt(inner(s, s))
    r = 0.0_dp
    if (.not. (rho > 0.0_dp)) return
    s_hat = s / rho
    c3 = max(-1.0_dp, min(1.0_dp, 3.0_dp * sqrt6 * det_voigt(s_hat)))
    r = rho * cos(acos(cone%h * c3) / 3.0_dp)
  end function cone_radius

  !> r(s) and its gradient (and optionally Hessian) with respect to the Voigt stress, by
  !! implicit differentiation of r^3 - 3/2 J2 r - 3/2 gamma J3 = 0. Gradients are
  !! strain-like (shear entries are derivatives by the shear stress, i.e. engineering).
  !! Zero on the hydrostatic axis (s = 0), where r is not differentiable.
  pure subroutine cone_derivatives(s, cone, r, grad, hess)
    real(dp), intent(in) :: s(6)
    type(cone_t), intent(in) :: cone
    real(dp), intent(out) :: r, grad(6)
    real(dp), intent(out), optional :: hess(6, 6)
    real(dp) :: j2, rr, gj2(6), gj3(6), a(6), hs(6, 6), t(6, 6), hj2(6, 6), hj3(6, 6)
    integer :: i, j
    r = cone_radius(s, cone)
    grad = 0.0_dp
    if (present(hess)) hess = 0.0_dp
    j2 = 0.5_dp * inner(s, s)
    rr = 3.0_dp * r * r - 1.5_dp * j2
    if (.not. (r > 0.0_dp .and. rr > 0.0_dp)) return

    gj2 = [s(1), s(2), s(3), 2.0_dp * s(4), 2.0_dp * s(5), 2.0_dp * s(6)]
    a = [s(2) * s(3) - s(4)**2, s(1) * s(3) - s(5)**2, s(1) * s(2) - s(6)**2, &
         2.0_dp * (s(5) * s(6) - s(1) * s(4)), 2.0_dp * (s(4) * s(6) - s(2) * s(5)), &
         2.0_dp * (s(4) * s(5) - s(3) * s(6))]
    gj3 = a
    gj3(1:3) = a(1:3) - (a(1) + a(2) + a(3)) / 3.0_dp
    grad = 1.5_dp * (r * gj2 + cone%gam * gj3) / rr
    if (.not. present(hess)) return

    ! d2 J3 / ds2 with s1..s6 independent, then through s = T sigma (T: deviator).
    hs = 0.0_dp
    hs(1, 2) = s(3)
    hs(1, 3) = s(2)
    hs(2, 3) = s(1)
    hs(1, 4) = -2.0_dp * s(4)
    hs(2, 5) = -2.0_dp * s(5)
    hs(3, 6) = -2.0_dp * s(6)
    hs(4, 5) = 2.0_dp * s(6)
    hs(4, 6) = 2.0_dp * s(5)
    hs(5, 6) = 2.0_dp * s(4)
    hs(4, 4) = -2.0_dp * s(1)
    hs(5, 5) = -2.0_dp * s(2)
    hs(6, 6) = -2.0_dp * s(3)
    do j = 1, 6
      do i = j + 1, 6
        hs(i, j) = hs(j, i)
      end do
    end do
    t = 0.0_dp
    t(1:3, 1:3) = -1.0_dp / 3.0_dp
    do i = 1, 3
      t(i, i) = 2.0_dp / 3.0_dp
      t(i + 3, i + 3) = 1.0_dp
    end do
    hj3 = matmul(t, matmul(hs, t))
    hj2 = 0.0_dp
    hj2(1:3, 1:3) = t(1:3, 1:3)
    do i = 4, 6
      hj2(i, i) = 2.0_dp
    end do
    do j = 1, 6
      do i = 1, 6
        hess(i, j) = (1.5_dp * r * hj2(i, j) + 1.5_dp * cone%gam * hj3(i, j) &
                      + 1.5_dp * (gj2(i) * grad(j) + grad(i) * gj2(j)) - 6.0_dp * r * grad(i) * grad(j)) / rr
      end do
    end do
  end subroutine cone_derivatives

  ! ------------------------------------------------------------------ tensor helpers

  !> Mean stress and deviator of a Voigt stress.
  pure subroutine split(sig, p, s)
    real(dp), intent(in) :: sig(6)
    real(dp), intent(out) :: p, s(6)
    p = (sig(1) + sig(2) + sig(3)) / 3.0_dp
    s = sig
    s(1:3) = s(1:3) - p
  end subroutine split

  !> Tensor inner product a:b of two Voigt stress-like vectors.
  pure real(dp) function inner(a, b)
    real(dp), intent(in) :: a(6), b(6)
    inner = a(1) * b(1) + a(2) * b(2) + a(3) * b(3) + 2.0_dp * (a(4) * b(4) + a(5) * b(5) + a(6) * b(6))
  end function inner

  !> s.s of a symmetric tensor in Voigt order [xx yy zz yz xz xy].
  pure function square_voigt(s) result(q)
    real(dp), intent(in) :: s(6)
    real(dp) :: q(6)
    q(1) = s(1)**2 + s(6)**2 + s(5)**2
    q(2) = s(6)**2 + s(2)**2 + s(4)**2
    q(3) = s(5)**2 + s(4)**2 + s(3)**2
    q(4) = s(6) * s(5) + s(2) * s(4) + s(4) * s(3)
    q(5) = s(1) * s(5) + s(6) * s(4) + s(5) * s(3)
    q(6) = s(1) * s(6) + s(6) * s(2) + s(5) * s(4)
  end function square_voigt

  pure real(dp) function det_voigt(a)
    real(dp), intent(in) :: a(6)
    det_voigt = a(1) * a(2) * a(3) + 2.0_dp * a(4) * a(5) * a(6) - a(1) * a(4)**2 - a(2) * a(5)**2 - a(3) * a(6)**2
  end function det_voigt

  !> Solve a x = b in place (b becomes x) by Gaussian elimination with partial pivoting.
  pure subroutine solve_dense(a, b, ok)
    real(dp), intent(in) :: a(:, :)
    real(dp), intent(inout) :: b(:, :)
    logical, intent(out) :: ok
    real(dp) :: lu(size(a, 1), size(a, 2)), rowtmp(size(a, 2)), btmp(size(b, 2)), factor
    integer :: n, k, i, piv
    n = size(a, 1)
    lu = a
    ok = .false.
    do k = 1, n
      piv = k - 1 + maxloc(abs(lu(k:n, k)), 1)
      if (.not. (abs(lu(piv, k)) > 0.0_dp)) return
      if (piv /= k) then
        rowtmp = lu(k, :)
        lu(k, :) = lu(piv, :)
        lu(piv, :) = rowtmp
        btmp = b(k, :)
        b(k, :) = b(piv, :)
        b(piv, :) = btmp
      end if
      do i = k + 1, n
        factor = lu(i, k) / lu(k, k)
        lu(i, k:n) = lu(i, k:n) - factor * lu(k, k:n)
        b(i, :) = b(i, :) - factor * b(k, :)
      end do
    end do
    do k = n, 1, -1
      b(k, :) = (b(k, :) - matmul(lu(k, k + 1:n), b(k + 1:n, :))) / lu(k, k)
    end do
    ok = all(b == b)
  end subroutine solve_dense

  ! ------------------------------------------------------------------ input

  !> A modified Matsuoka-Nakai material from MATERIAL parameters E, NU, PHI, PSI (degrees)
  !! and exactly one of FT (uniaxial tensile strength) or C (cohesion). Checks E > 0,
  !! -1 < nu < 0.5, 0 < phi < 90, 0 <= psi <= phi, ft > 0 or c > 0, and rejects unknown
  !! keys; errors name the record's file and line and the parameter (and its field, when
  !! one parameter is at fault: the second of FT and C when both are given).
  subroutine new_matsuoka_nakai(spec, material, error)
    type(material_spec_t), intent(in) :: spec
    class(material_t), allocatable, intent(out) :: material
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: known(9) = ['e      ', 'nu     ', 'phi    ', 'psi    ', 'ft     ', &
                                               'c      ', 'tension', 'gamma  ', 'k0     ']
    real(dp) :: e, nu, phi, psi, ft, c, m, gamma, k0
    logical :: has_ft, has_c, has_tension
    character(len=:), allocatable :: rule
    integer :: tension

    call check_known_keys(spec, known, error)
    if (.not. allocated(error)) call get_parameter(spec, 'e', e, error, positive=.true.)
    if (allocated(error)) return
    call get_parameter(spec, 'nu', nu, error)
    if (allocated(error)) return
    if (.not. (nu > -1.0_dp .and. nu < 0.5_dp)) then
      call material_error(error, spec, 'NU = ' // str(nu) // &
                          ' is outside (-1, 0.5): the material would not be positive definite', 'nu')
      return
    end if
    call get_parameter(spec, 'phi', phi, error)
    if (allocated(error)) return
    if (.not. (phi > 0.0_dp .and. phi < 90.0_dp)) then
      call material_error(error, spec, 'PHI = ' // str(phi) // ' must lie in (0, 90) degrees', 'phi')
      return
    end if
    call get_parameter(spec, 'psi', psi, error)
    if (allocated(error)) return
    if (.not. (psi >= 0.0_dp .and. psi <= phi)) then
      call material_error(error, spec, 'PSI = ' // str(psi) // ' must lie in [0, PHI] = [0, ' // str(phi) // '] degrees', &
                          'psi')
      return
    end if
    call spec%get('ft', ft, has_ft)
    call spec%get('c', c, has_c)
    if (has_ft .and. has_c) then
      call material_conflict(error, spec, 'give only one of FT and C (they determine the same apex M)', 'ft', 'c')
      return
    end if
    if (has_ft) then
      if (.not. (ft > 0.0_dp .and. ft <= huge(ft))) then
        call material_error(error, spec, 'FT = ' // str(ft) // ' must be positive and finite', 'ft')
        return
      end if
      m = apex_from_tensile_strength(ft, phi)
    else if (has_c) then
      if (.not. (c > 0.0_dp .and. c <= huge(c))) then
        call material_error(error, spec, 'C = ' // str(c) // ' must be positive and finite', 'c')
        return
      end if
      m = apex_from_cohesion(c, phi)
    else
      call material_error(error, spec, 'FT or C is missing')
      return
    end if
    tension = tension_proportional
    call spec%get_text('tension', rule, has_tension)
    if (has_tension) then
      select case (rule)
      case ('proportional')
        tension = tension_proportional
      case ('closest-point')
        tension = tension_closest_point
      case default
        call material_error(error, spec, 'TENSION = "' // rule // '": it must be PROPORTIONAL (the thesis''s ' // &
                            'rule, the default) or CLOSEST-POINT', 'tension')
        return
      end select
    end if
    call get_unit_weight(spec, gamma, error)
    if (.not. allocated(error)) call get_k0(spec, k0, error)
    if (allocated(error)) return
    allocate (material, source=matsuoka_nakai_t(name=spec%name, e=e, nu=nu, phi=phi, psi=psi, apex=m, &
                                                tension=tension, unit_weight=gamma, k0=k0))


  end subroutine new_matsuoka_nakai


  !> A Young's modulus far outside the physical range in N, mm and MPa, or one so small beside
  !! the strength that the material would reach its tensile strength only at a strain above
  !! max_cracking_strain (E = 40 for 40 GPa, with f_t = 3.5 MPa: 9 %).
  pure subroutine mn_unit_warning(self, warning, key)
    class(matsuoka_nakai_t), intent(in) :: self
    character(len=:), allocatable, intent(out) :: warning, key
    real(dp), parameter :: max_cracking_strain = 0.05_dp
    real(dp) :: ft
    key = 'e'
    warning = modulus_warning(self%e)
    if (len(warning) > 0) return
    ft = 2.0_dp * self%apex / (1.0_dp + 1.0_dp / sin(self%phi * deg2rad))   ! eq. 2.4.5 inverted
    if (ft > max_cracking_strain * self%e) warning = 'E = ' // sci(self%e, 3, 0) // ' MPa is only ' // &
      sci(self%e / ft, 3, 0) // ' times the tensile strength ' // sci(ft, 3, 0) // &
      ' MPa (the material reaches f_t at a strain of ' // sci(ft / self%e, 3, 0) // &
      '): feps works in N, mm and MPa (E given in GPa?)'
  end subroutine mn_unit_warning

end module feps_matsuoka_nakai
