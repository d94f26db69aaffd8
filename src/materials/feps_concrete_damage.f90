!> Cracking concrete: an isotropic damage model driven by the tensile effective stress (the
!! Rankine measure where one principal stress is tensile), with linear or exponential tension
!! softening regularised by the fracture energy G_f over the crack band h of the point's
!! element (Bazant and Oh 1983; the Rankine damage model of Jirasek and Bazant, Inelastic
!! Analysis of Structures, 2002, section 25.1).
!!
!! Components: 6 Voigt stresses [xx yy zz yz xz xy] and strains with engineering shears,
!! tension positive. sigma = (1 - d) sigma_eff, sigma_eff = D eps (E, nu isotropic).
!!
!! Why isotropic damage and not a fixed or rotating smeared crack: one scalar history variable
!! (kappa) and exactly the crack band energy, which is what the crack band theory regularises.
!! What it does not do: it softens the compressive and shear stiffness of a cracked point with
!! the tensile one (a smeared crack would keep them). DAMAGE=TENSILE (`tensile_only`) keeps the
!! compression: sigma = sig_eff - d <sig_eff>+, the damage on the tensile principal part of the
!! effective stress only (its inverse divides the tensile principal values of a stored stress by
!! 1 - d; the tangent (I - d P) D - d' <sig_eff>+ (D grad kappa)^T, P = d <sig_eff>+ / d sig_eff
!! by central differences). The same kappa and law, so uniaxial tension is unchanged.
!!
!! Compression (optional, MATERIAL key FC and with it PHI and PSI): the modified Matsuoka-Nakai
!! surface of feps_matsuoka_nakai (perfectly plastic) bounds the effective stress of a point
!! that has not cracked, where the return lands at a compressive mean stress (p < 0); its
!! return mapping and consistent tangent are the MATSUOKA material's own (a component,
!! `crush`, called, not copied), with its continuous closest-point rule (its apex lies on the
!! tensile side, where the damage governs). The surface passes through -FC in uniaxial
!! compression: apex M = FC/2 (1/sin(phi) - 1), i.e. cohesion c = FC (1 - sin phi) /
!! (2 cos phi); PHI defaults to asin((FC - FT) / (FC + FT)), which puts it through FT in
!! uniaxial tension too (thesis chapter 9's concrete: FC = 50, FT = 5 give its 54.9 deg), and
!! PSI to PHI. Why only where the return lands at p < 0: the surface also caps the uniaxial
!! tensile effective stress at its own tensile strength (FT with the default PHI), so the
!! damage would never start; elsewhere the damage alone governs. Why by where the return
!! lands and not by the elastic trial: full Newton's first iterate after yield predicts the
!! plastic dilation, whose elastic trial is tensile, though its return lands back on the
!! compressive side (the trial choice cycled; docs/verification.md). Why not once cracked:
!! a cracked point's effective stress may lie far outside the surface, and a return from
!! there jumps by as much (chapter 9's CR did not converge with it); a cracked point is
!! elastic-damaged in compression. The price: where the landing point's mean stress changes
!! sign (near pure shear) the update of an uncracked point jumps between the two surfaces, by
!! at most their distance there.
!!
!! History: kappa, the largest equivalent strain reached (`equivalent_strain`: the energy norm
!! of the tensile part of the effective stress, which is the Rankine measure
!! max(sigma_eff_1, 0) / E when one principal stress is tensile, and keeps the dissipation
!! G_f / h when the lateral strain of a crack band is held, at any nu); damage starts at
!! kappa = eps_0 = f_t / E. Softening of the uniaxial stress after the peak:
!!  - LINEAR: sigma = f_t (eps_u - kappa) / (eps_u - eps_0), eps_u = 2 G_f / (h f_t);
!!  - EXPONENTIAL: sigma = f_t exp(-(kappa - eps_0) / eps_f), eps_f = G_f / (h f_t) - eps_0 / 2;
!! both dissipate G_f / h per unit volume, G_f per unit crack area over a band h. Both need
!! h < 2 E G_f / f_t^2 (twice Hillerborg's characteristic length), else the band snaps back.
!! The damage is capped at max_damage so a fully cracked point keeps a tiny stiffness and the
!! stiffness matrix stays regular.
!!
!! The update is incremental in the effective stress, sigma_eff = sig0 / (1 - d(kappa0)) +
!! D deps, so a stress imposed at the start of a step (prestress, in-situ) enters it. Internal
!! variables: 1 kappa, 2 h (the crack band, set once per point by the analysis from its
!! element: `band_slot`); with FC, 3-8 the plastic strain of the compression side (Voigt,
!! engineering shears: for the record; the update is incremental in the effective stress and
!! does not need it). Tangent: unloading or below the peak the secant (1 - d) D; while
!! the damage grows the consistent tangent (1 - d) D - d'(kappa) sigma_eff (D grad kappa)^T,
!! non-symmetric in general (full Newton factorizes it by LU; the other methods take its
!! nearest symmetric positive semi-definite part). Where the compression side yields, D is
!! the Matsuoka-Nakai consistent tangent D_ep in both terms (D_ep^T grad kappa in the
!! second). The secant alone converged linearly, at a rate near 0.97 per iteration, once a
!! laterally held band softened (nu > 0).
module feps_concrete_damage
  use feps_kinds, only: dp, deg2rad
  use feps_error, only: error_t, str
  use feps_model, only: material_spec_t
  use feps_material_params, only: check_known_keys, get_parameter, material_error, get_unit_weight, get_k0
  use feps_material, only: material_t, state_elastic, state_cracked, modulus_warning
  use feps_matsuoka_nakai, only: matsuoka_nakai_t, tension_closest_point
  use feps_elastic, only: elastic_matrix
  use feps_principal, only: principal_values, principal_frame
  implicit none
  private

  public :: new_concrete_damage

  !> Softening laws (MATERIAL key SOFTENING=LINEAR | EXPONENTIAL).
  integer, parameter, public :: softening_linear = 1, softening_exponential = 2

  !> The largest damage: a fully cracked point keeps 1e-6 of its stiffness.
  real(dp), parameter, public :: max_damage = 1.0_dp - 1.0e-6_dp

  integer, parameter :: var_kappa = 1, var_band = 2, var_plastic = 3

  !> Cracking concrete (isotropic Rankine damage): E, nu, tensile strength ft (MPa), fracture
  !! energy gf (N/mm) and the softening law; with a compressive strength fc, the
  !! Matsuoka-Nakai surface `crush` in compression.
  type, extends(material_t), public :: concrete_damage_t
    real(dp) :: e = 0.0_dp
    real(dp) :: nu = 0.0_dp
    real(dp) :: ft = 0.0_dp
    real(dp) :: gf = 0.0_dp
    integer :: softening = softening_linear
    !> DAMAGE=TENSILE: the damage acts on the tensile principal part of the effective stress
    !! only (compression kept along a crack and across a closed one); .false.: isotropic
    logical :: tensile_only = .false.
    real(dp) :: fc = 0.0_dp    !! uniaxial compressive strength (MPa); 0: elastic in compression
    !> The Matsuoka-Nakai surface on the compression side (allocated with fc > 0)
    type(matsuoka_nakai_t), allocatable :: crush
  contains
    procedure :: elastic_tangent => cd_elastic_tangent
    procedure :: update => cd_update
    procedure :: is_linear => cd_is_linear
    procedure :: state_size => cd_state_size
    procedure :: band_slot => cd_band_slot
    procedure :: max_band => cd_max_band
    procedure :: damage => cd_damage
    procedure :: damage_rate => cd_damage_rate
    procedure :: unit_warning => cd_unit_warning
  end type concrete_damage_t

contains

  pure subroutine cd_elastic_tangent(self, d)
    class(concrete_damage_t), intent(in) :: self
    real(dp), intent(out) :: d(:, :)
    d = elastic_matrix(self%e, self%nu)
  end subroutine cd_elastic_tangent

  pure logical function cd_is_linear(self)
    class(concrete_damage_t), intent(in) :: self
    cd_is_linear = .false.
  end function cd_is_linear

  !> kappa and the crack band h; with the compression side, its plastic strain (6) too.
  pure integer function cd_state_size(self) result(n)
    class(concrete_damage_t), intent(in) :: self
    n = 2
    if (allocated(self%crush)) n = 8
  end function cd_state_size

  !> The internal variable that holds the point's crack band.
  pure integer function cd_band_slot(self) result(slot)
    class(concrete_damage_t), intent(in) :: self
    slot = var_band
  end function cd_band_slot

  !> The largest crack band without snap-back of the band: 2 E G_f / f_t^2.
  pure real(dp) function cd_max_band(self) result(h)
    class(concrete_damage_t), intent(in) :: self
    h = 2.0_dp * self%e * self%gf / self%ft**2
  end function cd_max_band

  !> The damage at history kappa in a band h (0 before the peak, at most max_damage).
  pure real(dp) function cd_damage(self, kappa, h) result(d)
    class(concrete_damage_t), intent(in) :: self
    real(dp), intent(in) :: kappa, h
    real(dp) :: eps0, epsu, epsf
    eps0 = self%ft / self%e
    d = 0.0_dp
    if (.not. (kappa > eps0)) return
    select case (self%softening)
    case (softening_exponential)
      epsf = self%gf / (h * self%ft) - 0.5_dp * eps0
      d = 1.0_dp - eps0 / kappa * exp(-(kappa - eps0) / epsf)
    case default
      epsu = 2.0_dp * self%gf / (h * self%ft)
      if (kappa >= epsu) then
        d = 1.0_dp
      else
        d = 1.0_dp - eps0 * (epsu - kappa) / (kappa * (epsu - eps0))
      end if
    end select
    d = min(d, max_damage)
  end function cd_damage

  !> d'(kappa), the damage's rate of growth with the history kappa while it grows (0 before
  !! the peak and where the damage is capped).
  pure real(dp) function cd_damage_rate(self, kappa, h) result(rate)
    class(concrete_damage_t), intent(in) :: self
    real(dp), intent(in) :: kappa, h
    real(dp) :: eps0, epsu, epsf, ex
    eps0 = self%ft / self%e
    rate = 0.0_dp
    if (.not. (kappa > eps0) .or. .not. (self%damage(kappa, h) < max_damage)) return
    select case (self%softening)
    case (softening_exponential)
      epsf = self%gf / (h * self%ft) - 0.5_dp * eps0
      ex = exp(-(kappa - eps0) / epsf)
      rate = eps0 / kappa * ex * (1.0_dp / kappa + 1.0_dp / epsf)
    case default
      epsu = 2.0_dp * self%gf / (h * self%ft)
      rate = eps0 * epsu / (kappa**2 * (epsu - eps0))
    end select
  end function cd_damage_rate

  !> Stress update over a step (see the module description); state_cracked once the point has
  !! damaged, state_plastic in a step in which its compression side yields (only before it
  !! has cracked; over state_cracked should it crack in that step). Without a crack band
  !! (h = 0: not set) the point does not crack.
  pure subroutine cd_update(self, sig0, eps0, deps, state0, sig, state, dtan, var0, var)
    class(concrete_damage_t), intent(in) :: self
    real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
    integer, intent(in) :: state0
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(:, :)
    real(dp), intent(in), optional :: var0(:)
    real(dp), intent(out), optional :: var(:)
    real(dp) :: d(6, 6), kappa0, kappa, h, dmg0, dmg, sig_eff(6), eq, rate, dk(6), sig_tr(6), sig_ret(6), dep(6, 6)
    real(dp) :: sig_damaging(6)
    integer :: j, crush_state
    logical :: crushing
    d = elastic_matrix(self%e, self%nu)
    kappa0 = 0.0_dp
    h = 0.0_dp
    if (present(var0)) then
      kappa0 = var0(var_kappa)
      h = var0(var_band)
    end if
    dmg0 = 0.0_dp
    if (h > 0.0_dp) dmg0 = self%damage(kappa0, h)
    if (self%tensile_only) then
      sig_eff = undamaged_stress(sig0(1:6), dmg0) + matmul(d, deps(1:6))
    else
      sig_eff = sig0(1:6) / (1.0_dp - dmg0) + matmul(d, deps(1:6))
    end if
    crushing = .false.
    if (allocated(self%crush) .and. .not. (dmg0 > 0.0_dp)) then
      ! The Matsuoka-Nakai return of the same trial (formed there), kept where it lands on the
      ! compressive side of the surface (mean stress < 0); elsewhere, and once the point has
      ! cracked (its effective stress may lie far outside the surface), the damage governs.
      call self%crush%update(sig0(1:6), eps0, deps, state0, sig_ret, crush_state, dep)
      crushing = crush_state /= state_elastic .and. sig_ret(1) + sig_ret(2) + sig_ret(3) < 0.0_dp
      if (crushing) then
        sig_tr = sig_eff
        sig_eff = sig_ret
      end if
    end if
    eq = equivalent_strain(sig_eff, self%e, self%nu)
    kappa = max(kappa0, eq)
    dmg = 0.0_dp
    if (h > 0.0_dp) dmg = self%damage(kappa, h)
    if (crushing) d = dep
    rate = 0.0_dp
    if (h > 0.0_dp .and. eq > kappa0) rate = self%damage_rate(kappa, h)
    if (self%tensile_only) then
      ! sigma = sig_eff - d <sig_eff>+: d sigma / d eps = (I - d P) D, P = d <sig_eff>+ / d sig_eff
      ! (an undamaged point, most of them, needs neither the principal frame nor P)
      sig_damaging = 0.0_dp
      if (dmg > 0.0_dp .or. rate > 0.0_dp) sig_damaging = tensile_part(sig_eff)
      sig(1:6) = sig_eff - dmg * sig_damaging
      dtan(1:6, 1:6) = d
      if (dmg > 0.0_dp) dtan(1:6, 1:6) = d - dmg * matmul(tensile_part_derivative(sig_eff), d)
    else
      sig_damaging = sig_eff
      sig(1:6) = (1.0_dp - dmg) * sig_eff
      dtan(1:6, 1:6) = (1.0_dp - dmg) * d
    end if
    if (rate > 0.0_dp) then
      ! loading: minus d'(kappa) times the damaged stress (sig_eff, or its tensile part) times
      ! (D grad kappa)^T (D the compression side's D_ep where it yields: D_ep^T grad kappa)
      if (crushing) then
        dk = matmul(equivalent_strain_gradient(sig_eff, self%e, self%nu), d)
      else
        dk = matmul(d, equivalent_strain_gradient(sig_eff, self%e, self%nu))
      end if
      do j = 1, 6
        dtan(1:6, j) = dtan(1:6, j) - rate * sig_damaging * dk(j)
      end do
    end if
    state = state_elastic
    if (dmg > 0.0_dp) state = state_cracked
    if (crushing) state = crush_state
    if (present(var)) then
      var(var_kappa) = kappa
      var(var_band) = h
      if (allocated(self%crush)) then
        var(var_plastic:var_plastic + 5) = 0.0_dp
        if (present(var0)) var(var_plastic:var_plastic + 5) = var0(var_plastic:var_plastic + 5)
        if (crushing) var(var_plastic:var_plastic + 5) = var(var_plastic:var_plastic + 5) + &
                                                         compliance_times(sig_tr - sig_eff, self%e, self%nu)
      end if
    end if
  end subroutine cd_update

  !> The tensile principal part <s>+ = sum over the principal stresses s_k > 0 of s_k n_k n_k^T
  !! of a Voigt stress.
  pure function tensile_part(s) result(t)
    real(dp), intent(in) :: s(6)
    real(dp) :: t(6)
    real(dp) :: values(3), vectors(3, 3)
    integer :: k
    call principal_frame(s, values, vectors)
    t = 0.0_dp
    do k = 1, 3
      if (values(k) > 0.0_dp) t = t + values(k) * voigt_dyad(vectors(:, k))
    end do
  end function tensile_part

  !> The effective stress of a stress s damaged on its tensile part by d (DAMAGE=TENSILE):
  !! s and sig_eff share principal directions; the tensile principal values are divided by
  !! 1 - d, the compressive ones are s's own.
  pure function undamaged_stress(s, dmg) result(sig_eff)
    real(dp), intent(in) :: s(6), dmg
    real(dp) :: sig_eff(6)
    if (.not. (dmg > 0.0_dp)) then
      sig_eff = s
      return
    end if
    sig_eff = s + dmg / (1.0_dp - dmg) * tensile_part(s)
  end function undamaged_stress

  !> The derivative of `tensile_part` with respect to the six Voigt stresses (column k: by
  !! s_k), by central differences with a step of 1e-6 of the largest component, as
  !! `equivalent_strain_gradient` (where a principal stress passes zero the differences
  !! average the two sides of the kink).
  pure function tensile_part_derivative(s) result(p)
    real(dp), intent(in) :: s(6)
    real(dp) :: p(6, 6)
    real(dp) :: step, sp(6), sm(6)
    integer :: k
    step = 1.0e-6_dp * maxval(abs(s))
    p = 0.0_dp
    if (.not. (step > 0.0_dp)) return
    do k = 1, 6
      sp = s
      sm = s
      sp(k) = sp(k) + step
      sm(k) = sm(k) - step
      p(:, k) = (tensile_part(sp) - tensile_part(sm)) / (2.0_dp * step)
    end do
  end function tensile_part_derivative

  !> n n^T of a unit vector in Voigt order [xx yy zz yz xz xy].
  pure function voigt_dyad(n) result(v)
    real(dp), intent(in) :: n(3)
    real(dp) :: v(6)
    v = [n(1) * n(1), n(2) * n(2), n(3) * n(3), n(2) * n(3), n(1) * n(3), n(1) * n(2)]
  end function voigt_dyad

  !> The elastic strain (engineering shears) of a Voigt stress: D^-1 s.
  pure function compliance_times(s, e, nu) result(eps)
    real(dp), intent(in) :: s(6), e, nu
    real(dp) :: eps(6)
    eps(1) = (s(1) - nu * (s(2) + s(3))) / e
    eps(2) = (s(2) - nu * (s(1) + s(3))) / e
    eps(3) = (s(3) - nu * (s(1) + s(2))) / e
    eps(4:6) = 2.0_dp * (1.0_dp + nu) / e * s(4:6)
  end function compliance_times

  !> The equivalent strain that drives the damage: the energy norm of the tensile part of the
  !! effective stress, sqrt(<sigma>+ : C : <sigma>+) / sqrt(E) (C the elastic compliance), i.e.
  !! sqrt(sum t_i^2 - 2 nu sum_{i<j} t_i t_j) / E over t_i = max(s_i, 0), s_i the principal
  !! effective stresses. With one tensile principal stress it is the Rankine measure s_1 / E.
  !! Where none is compressive it is sqrt(2 Y / E), Y = eps : D : eps / 2 the energy release
  !! rate of the isotropic damage, so that the dissipation int Y dd = int E kappa^2 / 2
  !! d'(kappa) dkappa is the uniaxial one, G_f / h, whatever the lateral strain: in uniaxial
  !! stress and in a crack band held laterally by uncracked neighbours (near uniaxial strain)
  !! alike. The Rankine measure alone dissipates 1 / 1.11 of G_f / h in that band at
  !! nu = 0.2: its effective stress reaches (1 - nu) / ((1 + nu)(1 - 2 nu)) E eps there.
  !! Compressive principal stresses do not enter (they neither crack nor delay cracking).
  pure real(dp) function equivalent_strain(sig_eff, e, nu) result(eq)
    real(dp), intent(in) :: sig_eff(6), e, nu
    real(dp) :: t(3), q
    t = max(principal_values(sig_eff), 0.0_dp)
    q = t(1)**2 + t(2)**2 + t(3)**2 - 2.0_dp * nu * (t(1) * t(2) + t(2) * t(3) + t(1) * t(3))
    eq = sqrt(max(q, 0.0_dp)) / e
  end function equivalent_strain

  !> The gradient of `equivalent_strain` with respect to the six Voigt effective stresses
  !! (strain-like: the shear entries are derivatives by the shear stress), by central
  !! differences with a step of 1e-6 of the largest component (rounding leaves about 1e-10
  !! of the gradient; where a principal stress passes zero the measure has a kink and the
  !! differences average its two sides). Differences spare the principal directions that the
  !! analytic form would need.
  pure function equivalent_strain_gradient(sig_eff, e, nu) result(g)
    real(dp), intent(in) :: sig_eff(6), e, nu
    real(dp) :: g(6)
    real(dp) :: step, sp(6), sm(6)
    integer :: k
    step = 1.0e-6_dp * maxval(abs(sig_eff))
    g = 0.0_dp
    if (.not. (step > 0.0_dp)) return
    do k = 1, 6
      sp = sig_eff
      sm = sig_eff
      sp(k) = sp(k) + step
      sm(k) = sm(k) - step
      g(k) = (equivalent_strain(sp, e, nu) - equivalent_strain(sm, e, nu)) / (2.0_dp * step)
    end do
  end function equivalent_strain_gradient

  !> A Young's modulus far outside the physical range in N, mm and MPa.
  pure subroutine cd_unit_warning(self, warning, key)
    class(concrete_damage_t), intent(in) :: self
    character(len=:), allocatable, intent(out) :: warning, key
    key = 'e'
    warning = modulus_warning(self%e)
  end subroutine cd_unit_warning

  !> A cracking concrete material from MATERIAL parameters E, NU, FT (tensile strength, MPa),
  !! GF (fracture energy, N/mm), SOFTENING (LINEAR, the default, or EXPONENTIAL), GAMMA, K0,
  !! and optionally FC (compressive strength, MPa) with PHI and PSI (degrees) for the
  !! Matsuoka-Nakai surface in compression. Checks E > 0, -1 < nu < 0.5, FT > 0, GF > 0,
  !! FT < FC < huge, 0 < PHI < 90, 0 <= PSI <= PHI, PHI and PSI only with FC, and rejects
  !! unknown keys and laws; errors name the record's file and line and the parameter's field.
  subroutine new_concrete_damage(spec, material, error)
    type(material_spec_t), intent(in) :: spec
    class(material_t), allocatable, intent(out) :: material
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: known(11) = ['e        ', 'nu       ', 'ft       ', 'gf       ', &
                                                'softening', 'gamma    ', 'k0       ', 'fc       ', &
                                                'phi      ', 'psi      ', 'damage   ']
    real(dp) :: e, nu, ft, gf, gamma, k0, fc
    character(len=:), allocatable :: law, kind
    logical :: has_law, has_kind, tensile_only
    integer :: softening
    type(matsuoka_nakai_t), allocatable :: crush
    call check_known_keys(spec, known, error)
    if (.not. allocated(error)) call get_parameter(spec, 'e', e, error, positive=.true.)
    if (.not. allocated(error)) call get_parameter(spec, 'nu', nu, error)
    if (allocated(error)) return
    if (.not. (nu > -1.0_dp .and. nu < 0.5_dp)) then
      call material_error(error, spec, 'NU = ' // str(nu) // &
                          ' is outside (-1, 0.5): the material would not be positive definite', 'nu')
      return
    end if
    call get_parameter(spec, 'ft', ft, error, positive=.true.)
    if (.not. allocated(error)) call get_parameter(spec, 'gf', gf, error, positive=.true.)
    if (allocated(error)) return
    softening = softening_linear
    call spec%get_text('softening', law, has_law)
    if (has_law) then
      select case (law)
      case ('linear')
        softening = softening_linear
      case ('exponential')
        softening = softening_exponential
      case default
        call material_error(error, spec, 'SOFTENING = "' // law // '": it must be LINEAR (the default) or ' // &
                            'EXPONENTIAL', 'softening')
        return
      end select
    end if
    tensile_only = .false.
    call spec%get_text('damage', kind, has_kind)
    if (has_kind) then
      select case (kind)
      case ('isotropic')
        tensile_only = .false.
      case ('tensile')
        tensile_only = .true.
      case default
        call material_error(error, spec, 'DAMAGE = "' // kind // '": it must be ISOTROPIC (the default) or ' // &
                            'TENSILE', 'damage')
        return
      end select
    end if
    call get_compression_side(spec, e, nu, ft, fc, crush, error)
    if (allocated(error)) return
    call get_unit_weight(spec, gamma, error)
    if (.not. allocated(error)) call get_k0(spec, k0, error)
    if (allocated(error)) return
    allocate (material, source=concrete_damage_t(name=spec%name, e=e, nu=nu, ft=ft, gf=gf, softening=softening, &
                                                 tensile_only=tensile_only, unit_weight=gamma, k0=k0, fc=fc))
    ! moved in, not through the constructor (gfortran 12 freed a constructor's allocatable
    ! component twice)
    select type (material)
    type is (concrete_damage_t)
      if (allocated(crush)) call move_alloc(crush, material%crush)
    end select
  end subroutine new_concrete_damage

  !> The compression side from FC, PHI and PSI (none given: fc = 0 and no `crush`, elastic in
  !! compression): the Matsuoka-Nakai surface through -FC in uniaxial compression, PHI by
  !! default through FT in uniaxial tension too, PSI by default PHI.
  subroutine get_compression_side(spec, e, nu, ft, fc, crush, error)
    type(material_spec_t), intent(in) :: spec
    real(dp), intent(in) :: e, nu, ft
    real(dp), intent(out) :: fc
    type(matsuoka_nakai_t), allocatable, intent(out) :: crush
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: phi, psi
    logical :: has_fc, has_phi, has_psi
    call spec%get('fc', fc, has_fc)
    call spec%get('phi', phi, has_phi)
    call spec%get('psi', psi, has_psi)
    if (.not. has_fc) then
      fc = 0.0_dp
      if (has_phi) call material_error(error, spec, 'PHI needs FC (the compressive strength, which switches on ' // &
                                       'the Matsuoka-Nakai surface in compression)', 'phi')
      if (has_psi .and. .not. has_phi) call material_error(error, spec, 'PSI needs FC (the compressive ' // &
                                       'strength, which switches on the Matsuoka-Nakai surface in compression)', 'psi')
      return
    end if
    if (.not. (fc > 0.0_dp .and. fc <= huge(fc))) then
      call material_error(error, spec, 'FC = ' // str(fc) // ' must be positive and finite (the uniaxial ' // &
                          'compressive strength, MPa)', 'fc')
      return
    end if
    if (.not. (fc > ft)) then
      call material_error(error, spec, 'FC = ' // str(fc) // ' must exceed FT = ' // str(ft) // &
                          ' (the compressive strength is the larger)', 'fc')
      return
    end if
    if (has_phi) then
      if (.not. (phi > 0.0_dp .and. phi < 90.0_dp)) then
        call material_error(error, spec, 'PHI = ' // str(phi) // ' must lie in (0, 90) degrees', 'phi')
        return
      end if
    else
      phi = asin((fc - ft) / (fc + ft)) / deg2rad
    end if
    if (has_psi) then
      if (.not. (psi >= 0.0_dp .and. psi <= phi)) then
        call material_error(error, spec, 'PSI = ' // str(psi) // ' must lie in [0, PHI] = [0, ' // str(phi) // &
                            '] degrees', 'psi')
        return
      end if
    else
      psi = phi
    end if
    allocate (crush, source=matsuoka_nakai_t(name=spec%name, e=e, nu=nu, phi=phi, psi=psi, &
                                             apex=0.5_dp * fc * (1.0_dp / sin(phi * deg2rad) - 1.0_dp), &
                                             tension=tension_closest_point))
  end subroutine get_compression_side

end module feps_concrete_damage
