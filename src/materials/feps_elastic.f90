!> Isotropic linear elasticity.
module feps_elastic
  use feps_kinds, only: dp
  implicit none
  private

  public :: elastic_matrix

contains

  !> Isotropic elasticity matrix in Voigt order [xx yy zz yz xz xy], engineering shear strains.
  pure function elastic_matrix(e, nu) result(d)
    real(dp), intent(in) :: e, nu
    real(dp) :: d(6, 6)
    real(dp) :: lam, mu
    lam = e * nu / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
    mu = e / (2.0_dp * (1.0_dp + nu))
    d = 0.0_dp
    d(1:3, 1:3) = lam
    d(1, 1) = lam + 2.0_dp * mu
    d(2, 2) = lam + 2.0_dp * mu
    d(3, 3) = lam + 2.0_dp * mu
    d(4, 4) = mu
    d(5, 5) = mu
    d(6, 6) = mu
  end function elastic_matrix

end module feps_elastic
