!> The cracking concrete material (CONCRETE, feps_concrete_damage): the softening law of one
!! point against the fracture energy it must dissipate, a prism pulled apart on three meshes
!! (the crack band makes the dissipated energy G_f x area whatever the mesh), and its bad
!! parameters.
module test_concrete
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_material_testing, only: expect_material_rejected
  use feps_material, only: state_elastic, state_cracked
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

  !> Every CONCRETE parameter out of range, a softening law feps does not know and an unknown
  !! key are refused at their field.
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
                                  [30000.0_dp, 0.2_dp, 3.0_dp, 0.1_dp, 30.0_dp], 'PHI', 8)
  end subroutine test_bad_parameters

end module test_concrete
