!> Mohr-Coulomb interface material with a gap zone (thesis sections 2.3.2-2.3.3).
!!
!! Components: 3 [gamma1 gamma2 eps_n] (3D interface) or 2 [gamma eps_n] (2D interface)
!! relative displacements (upper minus lower layer, eps_n > 0 opening) and the matching
!! stresses [tau1 tau2 sigma_n] or [tau sigma_n] (tension positive). The component count
!! is taken from the size of the arrays passed in.
!!
!! Elastic: D = diag(ks, ks, kn) (eq. 2.3.13); ks = 0 is full slip (no shear stress ever).
!! Yield f = tau^2 - (c - sigma_n tan phi)^2
!! (eq. 2.3.14), plastic potential g with dilation angle psi (eq. 2.3.16). On the yield
!! surface f and g have the same gradients as the cones F = tau - c + sigma_n tan phi and
!! G = tau + sigma_n tan psi, so the closest-point return along D dG/dsigma is closed form
!! for this perfectly plastic model with isotropic shear stiffness:
!!   dlambda = F(trial) / (ks + kn tan phi tan psi),
!!   tau = tau_tr - ks dlambda (same shear direction), sigma_n = sigma_n_tr - kn tan psi dlambda.
!!
!! Gap zone: c - sigma_n tan phi <= 0 (at or beyond the apex). A point opens where the return
!! reaches the apex (a trial stress in the gap zone with little shear; with psi = 0 every trial
!! stress there): the stress is exactly zero and the tangent is `gap_factor` * D (a small residual
!! stiffness for numerical stability; default 1e-6). The update is then continuous in the trial
!! stress but for the loss of the tensile strength c / tan phi on opening. An open point stays
!! open while eps_n > 0; when eps_n <= 0 at the end of a step the gap closes inside the step and
!! the stress restarts from zero by eq. 2.3.22. The restart is at eps_n = 0, so the normal
!! dilation a point gathered while sliding before it opened is lost when it closes again (an
!! eps_n that gave -150 MPa before opening gives -50 after; thesis rule, SPEC 5).
module feps_interface_mohr_coulomb
  use feps_kinds, only: dp, deg2rad
  use feps_error, only: error_t, input_error, str
  use feps_model, only: material_spec_t
  use feps_material_params, only: check_known_keys, get_parameter, material_error
  use feps_material, only: material_t, state_elastic, state_plastic, state_open
  use feps_tangent_symmetry, only: nearest_symmetric_psd
  implicit none
  private

  public :: new_interface_mohr_coulomb

  !> Residual stiffness factor of an open gap: tangent = default_gap_factor * D.
  real(dp), parameter, public :: default_gap_factor = 1.0e-6_dp

  !> Relative tolerance of the yield check: a trial stress within it of the surface is taken
  !! as on the surface (plastic state, elastic-plastic tangent, no return needed), so that a
  !! returned point is recognised as yielding in the next step despite rounding.
  real(dp), parameter :: yield_tolerance = 1.0e-10_dp

  !> Mohr-Coulomb interface: stiffnesses kn, ks (stress per relative displacement), cohesion c,
  !! friction angle phi and dilation angle psi in degrees (0 <= psi <= phi < 90).
  type, extends(material_t), public :: interface_mohr_coulomb_t
    real(dp) :: kn = 0.0_dp
    real(dp) :: ks = 0.0_dp
    real(dp) :: c = 0.0_dp
    real(dp) :: phi = 0.0_dp
    real(dp) :: psi = 0.0_dp
    real(dp) :: gap_factor = default_gap_factor   !! open gap: tangent = gap_factor * D, stress 0
  contains
    procedure :: elastic_tangent => mc_elastic_tangent
    procedure :: update => mc_update
    procedure :: is_linear => mc_is_linear
    procedure :: symmetric_tangent => mc_symmetric_tangent
    procedure :: symmetric_stand_in => mc_symmetric_stand_in
  end type interface_mohr_coulomb_t

contains

  !> Elastic interface stiffness: diag(ks, ks, kn) for 3 components, diag(ks, kn) for 2.
  pure subroutine mc_elastic_tangent(self, d)
    class(interface_mohr_coulomb_t), intent(in) :: self
    real(dp), intent(out) :: d(:, :)
    integer :: i, n
    n = size(d, 1)
    d = 0.0_dp
    do i = 1, n - 1
      d(i, i) = self%ks
    end do
    d(n, n) = self%kn
  end subroutine mc_elastic_tangent

  !> Stress update over a step (eq. 2.3.21) from the state at its start, with the consistent
  !! tangent of the return map. States: state_elastic (stuck), state_plastic (sliding),
  !! state_open (gap). For a point open at the start of the step that closes inside it, the
  !! trial stress is that of eq. 2.3.22: sigma_n = kn eps_n (= t kn deps_n) and
  !! tau = t ks dgamma with t = eps_n / deps_n the fraction of the step in contact (t = 1 when
  !! eps_n was already <= 0 at the start); the tangent is then the exact derivative of this.
  pure subroutine mc_update(self, sig0, eps0, deps, state0, sig, state, dtan, var0, var)
    class(interface_mohr_coulomb_t), intent(in) :: self
    real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
    integer, intent(in) :: state0
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(:, :)
    real(dp), intent(in), optional :: var0(:)   !! no internal variables (state_size 0)
    real(dp), intent(out), optional :: var(:)
    ! fixed-size locals (an interface has at most 3 components): arrays sized by size(sig0)
    ! would be taken from the heap and given back at every point of every iteration
    real(dp) :: d(3, 3), jac(3, 3), amat(3, 3), sig_tr(3), eps_n, t, dt_ddeps_n
    integer :: i, n, ns

    n = size(sig0)
    ns = n - 1
    call self%elastic_tangent(d(1:n, 1:n))

    if (state0 == state_open) then
      eps_n = eps0(n) + deps(n)
      if (eps_n > 0.0_dp) then
        call set_open(self, d(1:n, 1:n), sig, state, dtan)
        return
      end if
      ! Closure inside the step (eq. 2.3.22): stress restarts from zero at the contact instant.
      t = 1.0_dp
      dt_ddeps_n = 0.0_dp
      if (deps(n) < 0.0_dp) then
        if (eps_n > deps(n)) then   ! eps0_n > 0: contact during the step, t = eps_n/deps_n in [0,1)
          t = eps_n / deps(n)
          dt_ddeps_n = -eps0(n) / deps(n)**2
        end if
      end if
      sig_tr(1:ns) = t * self%ks * deps(1:ns)
      sig_tr(n) = self%kn * eps_n
      jac(1:n, 1:n) = d(1:n, 1:n)
      do i = 1, ns
        jac(i, i) = t * self%ks
        jac(i, n) = self%ks * deps(i) * dt_ddeps_n
      end do
    else
      sig_tr(1:n) = sig0 + matmul(d(1:n, 1:n), deps)
      jac(1:n, 1:n) = d(1:n, 1:n)
    end if

    call return_map(self, sig_tr(1:n), sig, state, amat(1:n, 1:n))
    if (state == state_open) then
      call set_open(self, d(1:n, 1:n), sig, state, dtan)
    else
      dtan = matmul(amat(1:n, 1:n), jac(1:n, 1:n))
    end if
  end subroutine mc_update

  !> An open gap: zero stress and the residual tangent.
  pure subroutine set_open(self, d, sig, state, dtan)
    class(interface_mohr_coulomb_t), intent(in) :: self
    real(dp), intent(in) :: d(:, :)
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(:, :)
    sig = 0.0_dp
    state = state_open
    dtan = self%gap_factor * d
  end subroutine set_open

  !> Closest-point return of a trial stress: the stress, the state and the algorithmic
  !! derivative amat = d sig / d sig_tr (the consistent tangent is amat times the trial's
  !! derivative, D in an ordinary step). amat is not defined (left zero) for an open point.
  pure subroutine return_map(self, sig_tr, sig, state, amat)
    class(interface_mohr_coulomb_t), intent(in) :: self
    real(dp), intent(in) :: sig_tr(:)
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: amat(:, :)
    real(dp) :: tan_phi, tan_psi, tau_tr, sn_tr, strength, f_lin, h, dlambda, tau, ratio
    real(dp) :: m(2)   !! the slip direction (ns components; fixed size: no heap)
    integer :: i, j, n, ns

    n = size(sig_tr)
    ns = n - 1
    tan_phi = tan(self%phi * deg2rad)
    tan_psi = tan(self%psi * deg2rad)
    tau_tr = norm2(sig_tr(1:ns))
    sn_tr = sig_tr(n)
    amat = 0.0_dp

    ! Gap: the return along D dG/dsigma reaches the apex (tau <= 0 after it), i.e.
    ! ks (sigma_n_tr tan phi - c) >= tau_tr kn tan phi tan psi. This is where the thesis's
    ! integration along the strain path enters the gap zone c - sigma_n tan phi <= 0: a trial
    ! stress in that zone whose shear is large enough slides along the cone instead, its
    ! dilation keeping it in contact; with psi = 0 the two tests are the same. Testing the
    ! trial stress itself against the gap zone would make the stress jump from the cone to
    ! zero across sigma_n_tr = c / tan phi (Newton iterations then cycle). The extra
    ! sigma_n >= 0 keeps a frictionless, cohesionless interface (phi = c = 0) in contact under
    ! compression instead of treating every state as open. The trial in the gap zone
    ! (sigma_n tan phi >= c) follows from the apex test when ks > 0; with ks = 0 the apex test
    ! holds everywhere, and this one alone decides.
    if (sn_tr >= 0.0_dp .and. sn_tr * tan_phi - self%c >= 0.0_dp .and. &
        self%ks * (sn_tr * tan_phi - self%c) >= tau_tr * self%kn * tan_phi * tan_psi) then
      sig = 0.0_dp
      state = state_open
      return
    end if

    strength = self%c - sn_tr * tan_phi
    f_lin = tau_tr - strength
    ! Without shear stiffness (ks = 0: full slip) there is no shear stress to slide: a point in
    ! contact is elastic.
    if (self%ks == 0.0_dp .or. f_lin < -yield_tolerance * (tau_tr + abs(sn_tr) * tan_phi + self%c)) then
      sig = sig_tr
      state = state_elastic
      do i = 1, n
        amat(i, i) = 1.0_dp
      end do
      return
    end if

    h = self%ks + self%kn * tan_phi * tan_psi
    dlambda = max(f_lin, 0.0_dp) / h
    tau = max(tau_tr - self%ks * dlambda, 0.0_dp)
    if (tau_tr > 0.0_dp) then
      m(1:ns) = sig_tr(1:ns) / tau_tr
      ratio = tau / tau_tr
    else
      ! Only at a zero-strength point (the apex, or phi = c = 0): no slip direction, zero shear.
      m(1:ns) = 0.0_dp
      ratio = 0.0_dp
    end if
    sig(1:ns) = tau * m(1:ns)
    sig(n) = sn_tr - self%kn * tan_psi * dlambda
    state = state_plastic

    ! d sig / d sig_tr: the shear magnitude follows the return, the direction rotates with the
    ! trial shear scaled by tau / tau_tr (3D only: in 2D, I - m m^T = 0).
    do j = 1, ns
      do i = 1, ns
        amat(i, j) = (1.0_dp - self%ks / h - ratio) * m(i) * m(j)
      end do
      amat(j, j) = amat(j, j) + ratio
      amat(j, n) = -self%ks * tan_phi / h * m(j)
      amat(n, j) = -self%kn * tan_psi / h * m(j)
    end do
    amat(n, n) = 1.0_dp - self%kn * tan_psi * tan_phi / h
  end subroutine return_map

  pure logical function mc_is_linear(self)
    class(interface_mohr_coulomb_t), intent(in) :: self
    mc_is_linear = .false.
  end function mc_is_linear

  !> The tangent is symmetric only for associated flow (psi = phi).
  pure logical function mc_symmetric_tangent(self)
    class(interface_mohr_coulomb_t), intent(in) :: self
    mc_symmetric_tangent = self%psi == self%phi
  end function mc_symmetric_tangent

  !> The symmetric stand-in of a non-associated (psi /= phi) tangent: the nearest symmetric
  !! positive semi-definite matrix (the default) without its shear-normal couplings. That
  !! matrix spreads the indefinite coupling of the friction to sigma_n (and of the dilation)
  !! into both off-diagonal blocks; with them modified Euler diverged on cohesionless
  !! interfaces under in-situ stress (docs/verification.md). Its diagonal blocks are positive
  !! semi-definite, and so is the block-diagonal matrix; it keeps the small stiffness along the
  !! slip (0.035 ks at phi = 15, psi = 0, kn = 2 ks) that holds a body held only by sliding
  !! faces. Associated flow keeps the default (only a closing gap makes its tangent
  !! non-symmetric).
  subroutine mc_symmetric_stand_in(self, d)
    class(interface_mohr_coulomb_t), intent(in) :: self
    real(dp), intent(inout) :: d(:, :)
    integer :: n
    call nearest_symmetric_psd(d)
    if (self%psi /= self%phi) then
      n = size(d, 1)
      d(1:n - 1, n) = 0.0_dp
      d(n, 1:n - 1) = 0.0_dp
    end if
  end subroutine mc_symmetric_stand_in

  !> A Mohr-Coulomb interface from MATERIAL parameters KN, KS, PHI (required), C and PSI
  !! (default 0), angles in degrees. Checks kn > 0, ks >= 0 (0: full slip), c >= 0, 0 <= phi < 90 and
  !! 0 <= psi <= phi, and rejects unknown keys; errors name the record's file and line and,
  !! where one parameter is at fault, its field.
  subroutine new_interface_mohr_coulomb(spec, material, error)
    type(material_spec_t), intent(in) :: spec
    class(material_t), allocatable, intent(out) :: material
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: known(5) = ['kn ', 'ks ', 'c  ', 'phi', 'psi']
    real(dp) :: kn, ks, c, phi, psi

    call check_known_keys(spec, known, error)
    if (.not. allocated(error)) call get_parameter(spec, 'kn', kn, error, positive=.true.)
    if (.not. allocated(error)) call get_parameter(spec, 'ks', ks, error)
    if (.not. allocated(error)) call get_parameter(spec, 'c', c, error, default=0.0_dp)
    if (.not. allocated(error)) call get_parameter(spec, 'phi', phi, error)
    if (.not. allocated(error)) call get_parameter(spec, 'psi', psi, error, default=0.0_dp)
    if (allocated(error)) return
    if (.not. (ks >= 0.0_dp .and. ks <= huge(ks))) then
      call material_error(error, spec, 'KS = ' // str(ks) // ' must be non-negative and finite', 'ks')
    else if (.not. (c >= 0.0_dp .and. c <= huge(c))) then
      call material_error(error, spec, 'C = ' // str(c) // ' must be non-negative and finite', 'c')
    else if (.not. (phi >= 0.0_dp .and. phi < 90.0_dp)) then
      call material_error(error, spec, 'PHI = ' // str(phi) // ' must lie in [0, 90) degrees', 'phi')
    else if (.not. (psi >= 0.0_dp .and. psi <= phi)) then
      call material_error(error, spec, 'PSI = ' // str(psi) // ' must lie in [0, PHI] = [0, ' // str(phi) // &
                          '] degrees', 'psi')
    else
      allocate (material, source=interface_mohr_coulomb_t(name=spec%name, kn=kn, ks=ks, c=c, phi=phi, psi=psi))
    end if
  end subroutine new_interface_mohr_coulomb


end module feps_interface_mohr_coulomb
