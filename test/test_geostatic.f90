!> The GEOSTATIC stage (issue 26 item 2): in-situ stresses from the weight and K0, against
!! closed forms.
!! - test/data/k0_layers.dat, two layers (clay K0 0.7 under sand K0 0.5), 2 m of overburden
!!   above the mesh as a top pressure, and cohesionless interfaces between the columns (normal
!!   +x) and across one of them (normal +z): sv = the weight above, szz = -sv and
!!   sxx = syy = -K0 sv at every Gauss point, the interfaces' normal stress -K0 sv and -sv with no
!!   shear, the base's reaction the weight, and no displacement (the field is in balance).
!! - test/data/k0_reset.dat, a column loaded on top in the GEOSTATIC stage and in the next:
!!   each stage settles 0.1 H / M, because the displacements count from zero after the first,
!!   while the stresses keep both loads.
module test_geostatic
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  use feps_element_catalog, only: point_coordinates
  implicit none
  private

  public :: collect_geostatic

  real(dp), parameter :: gamma_sand = 1.8e-5_dp, gamma_clay = 2.0e-5_dp
  real(dp), parameter :: k0_sand = 0.5_dp, k0_clay = 0.7_dp
  real(dp), parameter :: surface = 12000.0_dp, layer_top = 5000.0_dp

contains

  !> Collect the suite.
  subroutine collect_geostatic(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('K0 layers: stresses and interface tractions exact, no displacement', test_k0_layers), &
      new_unittest('the GEOSTATIC stage''s settlement is reset, its stresses kept', test_k0_reset)]
  end subroutine collect_geostatic

  !> The vertical stress at height z of k0_layers.dat (positive: the weight above).
  elemental real(dp) function vertical_stress(z) result(sv)
    real(dp), intent(in) :: z
    if (z >= layer_top) then
      sv = gamma_sand * (surface - z)
    else
      sv = gamma_sand * (surface - layer_top) + gamma_clay * (layer_top - z)
    end if
  end function vertical_stress

  elemental real(dp) function k0_at(z)
    real(dp), intent(in) :: z
    k0_at = merge(k0_sand, k0_clay, z >= layer_top)
  end function k0_at

  subroutine test_k0_layers(error)
    type(error_t), allocatable, intent(out) :: error
    ! the weight of both columns (500 x 500 mm each) and of the 2 m of sand above them
    real(dp), parameter :: weight = 2 * 500.0_dp**2 * (gamma_clay * 5000.0_dp + gamma_sand * 5000.0_dp + 0.036_dp)
    real(dp), parameter :: tol = 1.0e-12_dp * 0.236_dp    ! of the largest stress, at the base
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp), allocatable :: xg(:, :)
    real(dp) :: worst, worst_shear, sv
    integer :: g, q
    call read_deck('test/data/k0_layers.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    associate (res => obs%steps(size(obs%steps)))
      call check(error, sum(res%reaction(3, :)), weight, 'the base carries the weight', rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(res%displacement)), 0.0_dp, 'the ground in balance does not move', &
                 abs=1.0e-9_dp)
      if (allocated(error)) return
      worst = 0.0_dp
      worst_shear = 0.0_dp
      do g = 1, size(model%groups)
        call point_coordinates(model%groups(g)%element_type, model%coords, model%groups(g)%connectivity, xg, error)
        if (allocated(error)) return
        do q = 1, size(xg, 2)
          sv = vertical_stress(xg(3, q))
          select case (model%groups(g)%name)
          case ('vertical')      ! normal +x: sigma_n = sxx
            worst = max(worst, abs(res%groups(g)%stress(3, q) + k0_at(xg(3, q)) * sv))
            worst_shear = max(worst_shear, maxval(abs(res%groups(g)%stress(1:2, q))))
          case ('horizontal')    ! normal +z: sigma_n = szz
            worst = max(worst, abs(res%groups(g)%stress(3, q) + sv))
            worst_shear = max(worst_shear, maxval(abs(res%groups(g)%stress(1:2, q))))
          case default
            worst = max(worst, abs(res%groups(g)%stress(3, q) + sv), &
                        maxval(abs(res%groups(g)%stress(1:2, q) + k0_at(xg(3, q)) * sv)))
            worst_shear = max(worst_shear, maxval(abs(res%groups(g)%stress(4:6, q))))
          end select
        end do
      end do
      call check(error, worst, 0.0_dp, 'sv = the weight above, sh = K0 sv at every point', abs=tol)
      if (allocated(error)) return
      call check(error, worst_shear, 0.0_dp, 'no shear stress anywhere', abs=tol)
    end associate
  end subroutine test_k0_layers

  subroutine test_k0_reset(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: gamma = 2.0e-5_dp, height = 10000.0_dp, e = 50.0_dp, nu = 0.3_dp, q_top = 0.1_dp, &
                           k0 = 0.5_dp
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp), allocatable :: xg(:, :)
    real(dp) :: m, worst
    integer :: q
    call read_deck('test/data/k0_reset.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, size(obs%steps), 2, 'a step per stage written')
    if (allocated(error)) return
    m = e * (1.0_dp - nu) / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
    call check(error, minval(obs%steps(1)%displacement(3, :)), -q_top * height / m, &
               'the GEOSTATIC stage settles under its top load', rel=1.0e-9_dp)
    if (allocated(error)) return
    call check(error, minval(obs%steps(2)%displacement(3, :)), -q_top * height / m, &
               'the next stage''s settlement counts from zero', rel=1.0e-9_dp)
    if (allocated(error)) return
    call point_coordinates('hex20', model%coords, model%groups(1)%connectivity, xg, error)
    if (allocated(error)) return
    worst = 0.0_dp
    associate (sig => obs%steps(2)%groups(1)%stress)
      do q = 1, size(xg, 2)
        worst = max(worst, abs(sig(3, q) + gamma * (height - xg(3, q)) + 2 * q_top), &
                    maxval(abs(sig(1:2, q) + k0 * gamma * (height - xg(3, q)) + nu / (1.0_dp - nu) * 2 * q_top)))
      end do
    end associate
    call check(error, worst, 0.0_dp, 'the stresses keep the in-situ field and both loads', abs=1.0e-12_dp)
  end subroutine test_k0_reset

end module test_geostatic
