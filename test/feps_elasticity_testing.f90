!> Closed forms of isotropic elasticity shared by the element suites, written independently of
!! the library's material kernels so that the element tests do not test feps against itself.
module feps_elasticity_testing
  use feps_kinds, only: dp
  implicit none
  private

  public :: isotropic_d, d_at_points

contains

  !> Isotropic elastic matrix, Voigt [xx, yy, zz, yz, xz, xy], engineering shears.
  pure function isotropic_d(e, nu) result(d)
    real(dp), intent(in) :: e, nu
    real(dp) :: d(6, 6), lambda, mu
    lambda = e * nu / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
    mu = e / (2.0_dp * (1.0_dp + nu))
    d = 0.0_dp
    d(1:3, 1:3) = lambda
    d(1, 1) = lambda + 2.0_dp * mu
    d(2, 2) = lambda + 2.0_dp * mu
    d(3, 3) = lambda + 2.0_dp * mu
    d(4, 4) = mu
    d(5, 5) = mu
    d(6, 6) = mu
  end function isotropic_d

  !> The same D at every Gauss point.
  pure function d_at_points(d, ng) result(dg)
    real(dp), intent(in) :: d(6, 6)
    integer, intent(in) :: ng
    real(dp) :: dg(6, 6, ng)
    integer :: g
    do g = 1, ng
      dg(:, :, g) = d
    end do
  end function d_at_points

end module feps_elasticity_testing
