!> The cracking concrete material (CONCRETE, feps_concrete_damage): the softening law of one
!! point against the fracture energy it must dissipate, a prism pulled apart on three meshes
!! (the crack band makes the dissipated energy G_f x area whatever the mesh), and its bad
!! parameters.
module test_concrete
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_material_testing, only: expect_material_rejected
  use feps_material, only: material_t, state_elastic, state_plastic, state_cracked
  use feps_material_testing, only: material_spec
  use feps_material_factory, only: new_material
  use feps_kinds, only: deg2rad
  use feps_concrete_damage, only: concrete_damage_t, softening_linear, softening_exponential
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  implicit none
  private

  public :: collect_concrete

contains

  subroutine collect_concrete(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('one point dissipates GF / h per volume, linear and exponential softening', test_point_energy), &
      new_unittest('a prism pulled apart dissipates GF x area on 1, 3 and 5 elements along, nu = 0 and 0.2', &
                   test_bar_energy), &
      new_unittest('FC: uniaxial compression reaches -FC and stays on the plateau, plastic strain', &
                   test_uniaxial_compression), &
      new_unittest('FC: triaxial compression reaches the Mohr-Coulomb strength of the compression meridian', &
                   test_triaxial_compression), &
      new_unittest('FC leaves uniaxial tension as it was: cracks at FT, bit for bit', test_tension_with_fc), &
      new_unittest('FC: a cracked point is elastic-damaged in compression (no Matsuoka-Nakai cap)', &
                   test_cracked_in_compression), &
      new_unittest('FC: a prism crushed by displacement carries FC x area (full Newton)', test_crush_prism), &
      new_unittest('DAMAGE=TENSILE: uniaxial tension as isotropic damage, to rounding', test_tensile_uniaxial), &
      new_unittest('DAMAGE=TENSILE: a cracked point keeps its stiffness in compression along and across the crack', &
                   test_tensile_compression_kept), &
      new_unittest('DAMAGE=TENSILE: the tangent against central differences of the update', test_tensile_tangent), &
      new_unittest('bad CONCRETE parameters name their field', test_bad_parameters) &
    ]
  end subroutine collect_concrete

  !> One point in uniaxial strain (nu = 0, so uniaxial stress too) stretched in 20000 steps
  !! to 20 times the strain at which a linear law is fully cracked: the area under sigma-eps
  !! (trapezoids) less the energy the residual stiffness (max_damage) would give back on
  !! unloading is G_f / h to 5e-4 for both laws (the residual stiffness also takes the work
  !! 1e-6 E eps_c^2 / 2 from where it caps the law, eps_c: 1e-5 of G_f / h for the linear law,
  !! 3e-4 for the exponential one, whose tail meets the cap at about 6e-3), the peak is f_t to 1e-3, the stress after
  !! the peak follows the law's closed form (1e-12) and the point is flagged cracked.
  subroutine test_point_energy(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: nsteps = 20000
    real(dp), parameter :: e = 30000.0_dp, ft = 3.0_dp, gf = 0.1_dp, h = 50.0_dp
    type(concrete_damage_t) :: mat
    real(dp) :: sig0(6), sig(6), eps(6), deps(6), dtan(6, 6), var0(2), var(2), w, peak, epsu, expected
    integer :: law, k, state
    do law = softening_linear, softening_exponential
      mat = concrete_damage_t(name='c', e=e, nu=0.0_dp, ft=ft, gf=gf, softening=law)
      epsu = 2.0_dp * gf / (h * ft)
      deps = 0.0_dp
      deps(1) = 20.0_dp * epsu / nsteps
      sig0 = 0.0_dp
      eps = 0.0_dp
      var0 = [0.0_dp, h]
      w = 0.0_dp
      peak = 0.0_dp
      do k = 1, nsteps
        call mat%update(sig0, eps, deps, state_elastic, sig, state, dtan, var0, var)
        w = w + 0.5_dp * (sig0(1) + sig(1)) * deps(1)
        peak = max(peak, sig(1))
        if (k == nsteps / 40) then   ! at eps = epsu / 2
          expected = ft * (epsu - 0.5_dp * epsu) / (epsu - ft / e)
          if (law == softening_exponential) &
            expected = ft * exp(-(0.5_dp * epsu - ft / e) / (gf / (h * ft) - 0.5_dp * ft / e))
          call check(error, sig(1), expected, 'law ' // str(law) // ': stress at eps_u / 2', rel=1.0e-12_dp)
          if (allocated(error)) return
          call check(error, state == state_cracked, 'law ' // str(law) // ': cracked after the peak')
          if (allocated(error)) return
        end if
        sig0 = sig
        eps = eps + deps
        var0 = var
      end do
      w = w - 0.5_dp * sig(1) * eps(1)   ! what the residual stiffness would give back
      call check(error, w, gf / h, 'law ' // str(law) // ': energy per volume', rel=5.0e-4_dp)
      if (allocated(error)) return
      call check(error, peak, ft, 'law ' // str(law) // ': peak stress', rel=1.0e-3_dp)
      if (allocated(error)) return
    end do
  end subroutine test_point_energy

  !> test/data/crack_bar_{1,3,5}.dat: a 100 mm cube of concrete (E = 30000, nu = 0, f_t = 3,
  !! G_f = 0.1 N/mm) on rollers, its top pulled 0.08 mm in 80 steps, its middle layer of
  !! elements 1 % weaker so that the crack forms there; the crack band is the element length
  !! 100 / n. The area under the top reaction against the top displacement is G_f x area
  !! = 1000 N mm to 2 % on each mesh (the last step's force is ~0: the bar has separated), and
  !! the peak force is 2.97 x 100^2 N to 1 % (the steps straddle the peak). crack_bar_3_exp.dat
  !! is the 3-element mesh with exponential softening pulled 0.3 mm in 150 steps (the force
  !! left at the end is exp(-10) of the peak). crack_bar_{1,3,5}_nu.dat are the three meshes
  !! with nu = 0.2, where the uncracked layers hold the band's lateral strain (the Rankine
  !! equivalent strain dissipated 906 and 904 N mm on 3 and 5 elements there: -9 %).
  subroutine test_bar_energy(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: decks(7) = [character(len=12) :: '1', '3', '5', '3_exp', '1_nu', '3_nu', '5_nu']
    integer, parameter :: nsteps(7) = [80, 80, 80, 150, 80, 80, 80]
    real(dp), parameter :: area = 100.0_dp**2, energy = 0.1_dp * area, peak_force = 2.97_dp * area
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: w, f, f0, u, u0, peak
    integer :: m, k, n
    character(len=:), allocatable :: mesh
    do m = 1, size(decks)
      mesh = 'crack_bar_' // trim(decks(m))
      call read_deck('test/data/' // mesh // '.dat', model, error)
      if (allocated(error)) return
      if (allocated(obs%steps)) deallocate (obs%steps)
      call run_analysis(model, 'cholmod', obs, summary, error)
      if (allocated(error)) return
      call check(error, summary%unconverged_steps, 0, mesh // ': steps left unconverged')
      if (allocated(error)) return
      call check(error, size(obs%steps), nsteps(m), 'every step written')
      if (allocated(error)) return
      w = 0.0_dp
      f0 = 0.0_dp
      u0 = 0.0_dp
      peak = 0.0_dp
      do k = 1, size(obs%steps)
        f = 0.0_dp
        u = 0.0_dp
        do n = 1, size(model%coords, 2)
          if (abs(model%coords(3, n) - 100.0_dp) > 1.0e-6_dp) cycle
          f = f + obs%steps(k)%reaction(3, n)
          u = obs%steps(k)%displacement(3, n)
        end do
        w = w + 0.5_dp * (f0 + f) * (u - u0)
        peak = max(peak, f)
        f0 = f
        u0 = u
      end do
      call check(error, w, energy, mesh // ': dissipated energy', rel=0.02_dp)
      if (allocated(error)) return
      call check(error, peak, peak_force, mesh // ': peak force', rel=0.01_dp)
      if (allocated(error)) return
      call check(error, abs(f0) < 1.0e-3_dp * peak_force, mesh // ': separated at the end ' // &
                 '(force ' // str(f0) // ' N)')
      if (allocated(error)) return
    end do
  end subroutine test_bar_energy

  !> A CONCRETE material from a hand-built record (keys and values as on a MATERIAL record).
  subroutine make_concrete(keys, values, mat, error)
    character(len=*), intent(in) :: keys(:)
    real(dp), intent(in) :: values(:)
    type(concrete_damage_t), intent(out) :: mat
    type(error_t), allocatable, intent(out) :: error
    class(material_t), allocatable :: m
    call new_material(material_spec('c', 'concrete', keys, values), m, error)
    if (allocated(error)) return
    select type (m)
    type is (concrete_damage_t)
      mat = m
    class default
      call test_failed(error, 'CONCRETE did not make a concrete_damage_t')
    end select
  end subroutine make_concrete

  !> n equal strain increments deps from the state (sig, eps, var), which each step replaces with
  !! its update's; state and dtan are the last step's.
  subroutine strain_steps(mat, deps, n, sig, eps, var, state, dtan)
    type(concrete_damage_t), intent(in) :: mat
    real(dp), intent(in) :: deps(6)
    integer, intent(in) :: n
    real(dp), intent(inout) :: sig(6), eps(6), var(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(6, 6)
    real(dp) :: sig_new(6), var_new(size(var))
    integer :: k
    do k = 1, n
      call mat%update(sig, eps, deps, state_elastic, sig_new, state, dtan, var, var_new)
      sig = sig_new
      eps = eps + deps
      var = var_new
    end do
  end subroutine strain_steps

  !> One step of a point strained by dz along z with its x and y stresses held at `lateral`
  !! and no shear: Newton's method on the x and y strains with the point's own tangent
  !! (quadratic with a consistent tangent), to 1e-12 of the axial stress.
  subroutine axial_step(mat, sig0, eps0, var0, dz, lateral, sig, state, var, deps, iterations)
    type(concrete_damage_t), intent(in) :: mat
    real(dp), intent(in) :: sig0(6), eps0(6), var0(:), dz, lateral
    real(dp), intent(out) :: sig(6), var(:), deps(6)
    integer, intent(out) :: state, iterations
    real(dp) :: dtan(6, 6), r(2), a(2, 2), det
    deps = 0.0_dp
    deps(3) = dz
    do iterations = 1, 50
      call mat%update(sig0, eps0, deps, state_elastic, sig, state, dtan, var0, var)
      r = sig(1:2) - lateral
      if (maxval(abs(r)) <= 1.0e-12_dp * max(abs(sig(3)), 1.0_dp)) return
      a = dtan(1:2, 1:2)
      det = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)
      deps(1) = deps(1) - (a(2, 2) * r(1) - a(1, 2) * r(2)) / det
      deps(2) = deps(2) - (a(1, 1) * r(2) - a(2, 1) * r(1)) / det
    end do
  end subroutine axial_step

  !> Uniaxial compression (x and y stress free) of a point with FC = 30, FT = 3 (PHI and PSI
  !! by default, 54.9 deg), and with PHI = 40, PSI = 10 (non-associated): strained in 45
  !! steps to 4.5 times FC / E. The stress is E eps until -FC, then -FC to 1e-9 on every later
  !! step (perfect plasticity; the surface passes through -FC whatever PHI), the point is
  !! plastic there and never cracks (kappa stays 0), its plastic strain along z is
  !! eps_z + FC / E (the elastic strain of uniaxial stress is sigma / E) to 1e-9, and the
  !! lateral Newton iterations take at most 5 (the consistent tangent).
  subroutine test_uniaxial_compression(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, fc = 30.0_dp
    type(concrete_damage_t) :: mat
    real(dp) :: sig0(6), sig(6), eps(6), deps(6), var0(8), var(8), dz
    integer :: k, state, iterations, variant
    do variant = 1, 2
      if (variant == 1) then
        call make_concrete(['e ', 'nu', 'ft', 'gf', 'fc'], [e, 0.2_dp, 3.0_dp, 0.1_dp, fc], mat, error)
      else
        call make_concrete(['e  ', 'nu ', 'ft ', 'gf ', 'fc ', 'phi', 'psi'], &
                           [e, 0.2_dp, 3.0_dp, 0.1_dp, fc, 40.0_dp, 10.0_dp], mat, error)
      end if
      if (allocated(error)) return
      call check(error, mat%state_size(), 8, 'state size with FC')
      if (allocated(error)) return
      sig0 = 0.0_dp
      eps = 0.0_dp
      var0 = 0.0_dp
      var0(2) = 50.0_dp
      dz = -0.1_dp * fc / e
      do k = 1, 45
        call axial_step(mat, sig0, eps, var0, dz, 0.0_dp, sig, state, var, deps, iterations)
        call check(error, iterations <= 5, 'variant ' // str(variant) // ' step ' // str(k) // ': ' // &
                   str(iterations) // ' lateral iterations')
        if (allocated(error)) return
        eps = eps + deps
        if (k < 10) then
          call check(error, sig(3), e * eps(3), 'elastic before -FC', rel=1.0e-12_dp)
          if (allocated(error)) return
          call check(error, state == state_elastic, 'elastic before -FC')
        else if (k > 10) then
          call check(error, sig(3), -fc, 'variant ' // str(variant) // ' step ' // str(k) // ': on the plateau', &
                     rel=1.0e-9_dp)
          if (allocated(error)) return
          call check(error, state == state_plastic, 'plastic on the plateau')
          if (allocated(error)) return
          call check(error, var(5), eps(3) - sig(3) / e, 'plastic strain along z', rel=1.0e-9_dp)
        end if
        if (allocated(error)) return
        call check(error, var(1), 0.0_dp, 'no cracking in uniaxial compression', abs=1.0e-12_dp)
        if (allocated(error)) return
        sig0 = sig
        var0 = var
      end do
    end do
  end subroutine test_uniaxial_compression

  !> Triaxial compression: a point under hydrostatic -q (imposed as its initial stress), then
  !! shortened along z with x and y held at -q. On the compression meridian the surface is
  !! the Mohr-Coulomb one, sigma_1 = q (1 + sin phi) / (1 - sin phi) + FC (compression
  !! positive; 2 c cos phi / (1 - sin phi) = FC); with the default PHI, (1 + sin) / (1 - sin)
  !! = FC / FT = 10, so q = 10 gives 130 MPa, and PHI = 40 gives 10 x 4.599 + 30. The axial
  !! stress reaches that to 1e-9 and stays.
  subroutine test_triaxial_compression(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, fc = 30.0_dp, q = 10.0_dp
    type(concrete_damage_t) :: mat
    real(dp) :: sig0(6), sig(6), eps(6), deps(6), var0(8), var(8), expected, sn
    integer :: k, state, iterations, variant
    do variant = 1, 2
      if (variant == 1) then
        call make_concrete(['e ', 'nu', 'ft', 'gf', 'fc'], [e, 0.2_dp, 3.0_dp, 0.1_dp, fc], mat, error)
        expected = 10.0_dp * q + fc
      else
        call make_concrete(['e  ', 'nu ', 'ft ', 'gf ', 'fc ', 'phi', 'psi'], &
                           [e, 0.2_dp, 3.0_dp, 0.1_dp, fc, 40.0_dp, 10.0_dp], mat, error)
        sn = sin(40.0_dp * deg2rad)
        expected = q * (1.0_dp + sn) / (1.0_dp - sn) + fc
      end if
      if (allocated(error)) return
      sig0 = 0.0_dp
      sig0(1:3) = -q
      eps = 0.0_dp
      var0 = 0.0_dp
      var0(2) = 50.0_dp
      do k = 1, 60
        call axial_step(mat, sig0, eps, var0, -0.05_dp * expected / e, -q, sig, state, var, deps, iterations)
        call check(error, iterations <= 5, 'variant ' // str(variant) // ' step ' // str(k) // ': ' // &
                   str(iterations) // ' lateral iterations')
        if (allocated(error)) return
        eps = eps + deps
        sig0 = sig
        var0 = var
      end do
      call check(error, -sig(3), expected, 'variant ' // str(variant) // ': triaxial strength at q = 10', &
                 rel=1.0e-9_dp)
      if (allocated(error)) return
      call check(error, state == state_plastic, 'plastic at the end')
      if (allocated(error)) return
    end do
  end subroutine test_triaxial_compression

  !> Uniaxial tension (x and y stress free, nu = 0.2) with and without FC: the mean stress is
  !! tensile, so the compression side never acts and the stresses are the same bit for bit;
  !! the peak is FT to 1e-3 and the point ends cracked.
  subroutine test_tension_with_fc(error)
    type(error_t), allocatable, intent(out) :: error
    type(concrete_damage_t) :: plain, crush
    real(dp) :: sig0(6), sig(6), eps(6), deps(6), var0(8), var(8), sig_p(6), var_p(8), peak, dtan_p(6, 6)
    integer :: k, state, state_p, iterations
    call make_concrete(['e ', 'nu', 'ft', 'gf'], [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp], plain, error)
    if (allocated(error)) return
    call make_concrete(['e ', 'nu', 'ft', 'gf', 'fc'], [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 30.0_dp], crush, error)
    if (allocated(error)) return
    sig0 = 0.0_dp
    eps = 0.0_dp
    var0 = 0.0_dp
    var0(2) = 50.0_dp
    peak = 0.0_dp
    do k = 1, 400
      call axial_step(crush, sig0, eps, var0, 5.0e-7_dp, 0.0_dp, sig, state, var, deps, iterations)
      call plain%update(sig0, eps, deps, state_elastic, sig_p, state_p, dtan_p, var0(1:2), var_p(1:2))
      call check(error, all(sig == sig_p) .and. state == state_p .and. all(var(1:2) == var_p(1:2)), &
                 'step ' // str(k) // ': the same update with and without FC')
      if (allocated(error)) return
      peak = max(peak, sig(3))
      eps = eps + deps
      sig0 = sig
      var0 = var
    end do
    call check(error, peak, 3.0_dp, 'tensile peak', rel=1.0e-3_dp)
    if (allocated(error)) return
    call check(error, state == state_cracked, 'cracked at the end')
  end subroutine test_tension_with_fc

  !> A point with FC = 30 (nu = 0, uniaxial strain = stress) pulled past its peak to kappa =
  !! 2 FT / E, then pushed back to -3 FC / E: once cracked its compression side is off (the
  !! design choice: its effective stress may lie far outside the surface), so the stress is
  !! (1 - d) E eps with the damage d of kappa = 2 FT / E, to 1e-12, beyond -FC (1 - d), and the
  !! point stays cracked.
  subroutine test_cracked_in_compression(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, ft = 3.0_dp, fc = 30.0_dp, h = 50.0_dp
    type(concrete_damage_t) :: mat
    real(dp) :: sig(6), eps(6), deps(6), dtan(6, 6), var(8), dmg
    integer :: state
    call make_concrete(['e ', 'nu', 'ft', 'gf', 'fc'], [e, 0.0_dp, ft, 0.1_dp, fc], mat, error)
    if (allocated(error)) return
    sig = 0.0_dp
    eps = 0.0_dp
    var = 0.0_dp
    var(2) = h
    deps = 0.0_dp
    deps(1) = 0.1_dp * ft / e
    call strain_steps(mat, deps, 20, sig, eps, var, state, dtan)
    dmg = mat%damage(2.0_dp * ft / e, h)
    call check(error, var(1), 2.0_dp * ft / e, 'kappa after the pull', rel=1.0e-12_dp)
    if (allocated(error)) return
    deps(1) = -(2.0_dp * ft + 3.0_dp * fc) / e / 50.0_dp
    call strain_steps(mat, deps, 50, sig, eps, var, state, dtan)
    call check(error, sig(1), (1.0_dp - dmg) * e * eps(1), 'compressed cracked point: (1 - d) E eps', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, sig(1) < -(1.0_dp - dmg) * fc .and. state == state_cracked, 'beyond -FC (1 - d), cracked')
  end subroutine test_cracked_in_compression

  !> test/data/crush_prism.dat: a 100 mm cube (one hex8) on rollers with FC = 30 MPa, its top
  !! pushed down 0.3 mm in 30 steps by full Newton. The top reaction is E A u / L until
  !! -FC x area = -300 000 N at step 10 and stays there to 1e-9 (homogeneous uniaxial stress),
  !! every point is plastic from step 11, every step converges to DELTA1 = 1e-10 without a
  !! cut-back and a step takes at most 3 iterations (the consistent tangent).
  subroutine test_crush_prism(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: area = 100.0_dp**2, force = -30.0_dp * area
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: f
    integer :: k, n
    call read_deck('test/data/crush_prism.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, summary%unconverged_steps == 0 .and. summary%cutbacks == 0, &
               'every step converged without a cut-back')
    if (allocated(error)) return
    call check(error, size(obs%steps), 30, 'every step written')
    if (allocated(error)) return
    do k = 1, size(obs%steps)
      f = 0.0_dp
      do n = 1, size(model%coords, 2)
        if (abs(model%coords(3, n) - 100.0_dp) < 1.0e-6_dp) f = f + obs%steps(k)%reaction(3, n)
      end do
      call check(error, obs%steps(k)%iterations <= 3, 'step ' // str(k) // ': ' // str(obs%steps(k)%iterations) // &
                 ' iterations')
      if (allocated(error)) return
      if (k <= 10) then
        call check(error, f, 30000.0_dp * area * (-0.01_dp * k) / 100.0_dp, 'step ' // str(k) // ': elastic', &
                   rel=1.0e-9_dp)
      else
        call check(error, f, force, 'step ' // str(k) // ': FC x area', rel=1.0e-9_dp)
        if (allocated(error)) return
        call check(error, all(obs%steps(k)%groups(1)%state == state_plastic), 'step ' // str(k) // ': plastic')
      end if
      if (allocated(error)) return
    end do
  end subroutine test_crush_prism

  !> DAMAGE=TENSILE in uniaxial stress (nu = 0, x pulled to 20 times the linear law's ultimate
  !! strain in 2000 steps): the tensile part is the whole effective stress, so every stress
  !! equals the isotropic damage's to 1e-13 of f_t (the two forms round differently).
  subroutine test_tensile_uniaxial(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, ft = 3.0_dp, gf = 0.1_dp, h = 50.0_dp
    type(concrete_damage_t) :: iso, split
    real(dp) :: sig0(6), sig(6), sig_i(6), eps(6), deps(6), dtan(6, 6), var0(2), var(2), var_i(2), worst
    integer :: k, state
    iso = concrete_damage_t(name='c', e=e, nu=0.0_dp, ft=ft, gf=gf)
    split = concrete_damage_t(name='c', e=e, nu=0.0_dp, ft=ft, gf=gf, tensile_only=.true.)
    deps = 0.0_dp
    deps(1) = 20.0_dp * 2.0_dp * gf / (h * ft) / 2000.0_dp
    sig0 = 0.0_dp
    eps = 0.0_dp
    var0 = [0.0_dp, h]
    worst = 0.0_dp
    do k = 1, 2000
      call split%update(sig0, eps, deps, state_elastic, sig, state, dtan, var0, var)
      call iso%update(sig0, eps, deps, state_elastic, sig_i, state, dtan, var0, var_i)
      worst = max(worst, maxval(abs(sig - sig_i)))
      sig0 = sig
      eps = eps + deps
      var0 = var
    end do
    call check(error, worst <= 1.0e-13_dp * ft, 'largest difference from isotropic damage ' // str(worst) // ' MPa')
    if (allocated(error)) return
    call check(error, state == state_cracked, 'cracked at the end')
  end subroutine test_tensile_uniaxial

  !> A point (nu = 0) pulled along x to kappa = 2 f_t / E (damage d), then, with x held,
  !! compressed along y to -10 f_t / E: DAMAGE=TENSILE keeps the full stiffness along the crack,
  !! sigma_y = E eps_y (isotropic damage: (1 - d) E eps_y), while sigma_x stays (1 - d) E eps_x;
  !! then x pushed back to -3 f_t / E: the crack closes and sigma_x = E eps_x (the isotropic
  !! damage's (1 - d) E eps_x), every one to 1e-12; the point stays cracked.
  subroutine test_tensile_compression_kept(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, ft = 3.0_dp, gf = 0.1_dp, h = 50.0_dp
    type(concrete_damage_t) :: mat
    real(dp) :: sig(6), eps(6), deps(6), dtan(6, 6), var(2), dmg
    integer :: state
    mat = concrete_damage_t(name='c', e=e, nu=0.0_dp, ft=ft, gf=gf, tensile_only=.true.)
    sig = 0.0_dp
    eps = 0.0_dp
    var = [0.0_dp, h]
    deps = 0.0_dp
    deps(1) = 0.1_dp * ft / e
    call strain_steps(mat, deps, 20, sig, eps, var, state, dtan)
    dmg = mat%damage(2.0_dp * ft / e, h)
    call check(error, var(1), 2.0_dp * ft / e, 'kappa after the pull', rel=1.0e-12_dp)
    if (allocated(error)) return
    deps = 0.0_dp
    deps(2) = -0.5_dp * ft / e
    call strain_steps(mat, deps, 20, sig, eps, var, state, dtan)
    call check(error, sig(2), e * eps(2), 'compressed along the crack: E eps_y', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, sig(1), (1.0_dp - dmg) * e * eps(1), 'across the crack: (1 - d) E eps_x', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, dtan(2, 2), e, 'tangent along the crack: E', rel=1.0e-9_dp)
    if (allocated(error)) return
    deps = 0.0_dp
    deps(1) = -(2.0_dp * ft + 3.0_dp * ft) / e / 50.0_dp
    call strain_steps(mat, deps, 50, sig, eps, var, state, dtan)
    call check(error, sig(1), e * eps(1), 'the crack closed: E eps_x', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, var(1), 2.0_dp * ft / e, 'kappa unchanged by compression', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, state == state_cracked, 'still cracked')
  end subroutine test_tensile_compression_kept

  !> DAMAGE=TENSILE (nu = 0.2, FC = 30): a point pulled along a general direction (shears
  !! too) past its peak, then compressed along y while still opening (a principal stress of
  !! about -3 f_t, which makes d <sig_eff>+ / d sig_eff far from the identity), then the
  !! tangent of a further step checked against central differences of the update's stress by
  !! the strain increment (step 1e-9 of a strain ~1e-4), while the damage grows (loading) and
  !! while it does not (unloading), to 1e-5 of the largest entry (the tangent's own derivatives
  !! are central differences of the stress).
  subroutine test_tensile_tangent(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: e = 30000.0_dp, ft = 3.0_dp, gf = 0.1_dp, h = 50.0_dp, step = 1.0e-9_dp
    type(concrete_damage_t) :: mat
    real(dp) :: sig0(6), sig(6), eps(6), dir(6), deps(6), dtan(6, 6), var0(8), var(8), sp(6), sm(6), fd(6, 6), dp_(6)
    integer :: j, state, probe
    character(len=*), parameter :: what(2) = ['loading  ', 'unloading']
    call make_concrete(['e ', 'nu', 'ft', 'gf', 'fc'], [e, 0.2_dp, ft, gf, 30.0_dp], mat, error)
    if (allocated(error)) return
    mat%tensile_only = .true.
    dir = [1.0_dp, -0.3_dp, 0.2_dp, 0.15_dp, -0.25_dp, 0.4_dp] * (0.05_dp * ft / e)
    sig = 0.0_dp
    eps = 0.0_dp
    var = 0.0_dp
    var(2) = h
    ! pulled, then (cracked: the compression side is off) compressed along y, still opening x
    call strain_steps(mat, dir, 30, sig, eps, var, state, dtan)
    dir = [1.0_dp, -6.0_dp, 0.3_dp, 0.1_dp, -0.1_dp, 0.2_dp] * (0.05_dp * ft / e)
    call strain_steps(mat, dir, 10, sig, eps, var, state, dtan)
    sig0 = sig
    var0 = var
    call check(error, state == state_cracked .and. var(1) > 1.2_dp * ft / e, 'cracked past the peak')
    if (allocated(error)) return
    do probe = 1, 2
      ! along x: the crack opens further (the damage grows) or closes a little (it does not)
      deps = 0.0_dp
      deps(1) = 0.5_dp * ft / e
      if (probe == 2) deps(1) = -0.01_dp * ft / e
      call mat%update(sig0, eps, deps, state_elastic, sig, state, dtan, var0, var)
      call check(error, (var(1) > var0(1)) .eqv. (probe == 1), trim(what(probe)) // ': kappa ' // str(var0(1)) // &
                 ' -> ' // str(var(1)))
      if (allocated(error)) return
      do j = 1, 6
        dp_ = 0.0_dp
        dp_(j) = step
        call mat%update(sig0, eps, deps + dp_, state_elastic, sp, state, fd, var0, var)
        call mat%update(sig0, eps, deps - dp_, state_elastic, sm, state, fd, var0, var)
        fd(:, j) = 0.0_dp
        fd(:, j) = (sp - sm) / (2.0_dp * step)
      end do
      call mat%update(sig0, eps, deps, state_elastic, sig, state, dtan, var0, var)
      call check(error, maxval(abs(dtan - fd)) <= 1.0e-5_dp * maxval(abs(fd)), trim(what(probe)) // &
                 ': tangent against differences, largest gap ' // str(maxval(abs(dtan - fd))) // ' of ' // &
                 str(maxval(abs(fd))))
      if (allocated(error)) return
    end do
  end subroutine test_tensile_tangent

  !> Every CONCRETE parameter out of range (FC at or below FT, PHI and PSI of the compression
  !! side too), PHI or PSI without FC, a softening law feps does not know and an unknown key
  !! are refused at their field.
  subroutine test_bad_parameters(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_material_rejected(error, 'c', 'concrete', ['e ', 'nu', 'ft', 'gf'], &
                                  [30000.0_dp, 0.2_dp, 0.0_dp, 0.1_dp], 'FT', 6)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e ', 'nu', 'ft', 'gf'], &
                                  [30000.0_dp, 0.2_dp, 3.0_dp, -0.1_dp], 'GF', 7)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e ', 'nu', 'ft'], [30000.0_dp, 0.2_dp, 3.0_dp], &
                                  'GF is missing', 0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e ', 'nu', 'gf'], [30000.0_dp, 0.2_dp, 0.1_dp], &
                                  'FT is missing', 0)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e ', 'nu', 'ft', 'gf'], &
                                  [30000.0_dp, 0.5_dp, 3.0_dp, 0.1_dp], 'NU', 5)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e  ', 'nu ', 'ft ', 'gf ', 'phi'], &
                                  [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 30.0_dp], 'PHI needs FC', 8)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e  ', 'nu ', 'ft ', 'gf ', 'psi'], &
                                  [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 30.0_dp], 'PSI needs FC', 8)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e ', 'nu', 'ft', 'gf', 'fc'], &
                                  [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 3.0_dp], 'FC = 3.00000 must exceed FT', 8)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e  ', 'nu ', 'ft ', 'gf ', 'fc ', 'phi'], &
                                  [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 30.0_dp, 0.0_dp], 'PHI', 9)
    if (allocated(error)) return
    call expect_material_rejected(error, 'c', 'concrete', ['e  ', 'nu ', 'ft ', 'gf ', 'fc ', 'psi'], &
                                  [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 30.0_dp, -1.0_dp], 'PSI', 9)
    if (allocated(error)) return
    ! the cohesion follows from FC and PHI: C is not a CONCRETE key
    call expect_material_rejected(error, 'c', 'concrete', ['e ', 'nu', 'ft', 'gf', 'fc', 'c '], &
                                  [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 30.0_dp, 5.0_dp], 'unknown parameter C', 9)
  end subroutine test_bad_parameters

end module test_concrete
