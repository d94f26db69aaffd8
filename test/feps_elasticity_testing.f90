!> Closed forms of isotropic elasticity shared by the element suites, written independently of
!! the library's material kernels so that the element tests do not test feps against itself.
module feps_elasticity_testing
  use feps_kinds, only: dp
  implicit none
  private

  public :: isotropic_d, d_at_points, lame_bore_displacement, mean_radial_displacement

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

  !> Radial displacement of the bore r = a of the plane-strain Lame cylinder a < r < b under
  !! internal pressure p: u(a) = a ((1 - nu^2) s_t - nu (1 + nu) s_r) / E with
  !! s_t, s_r = A +- B / a^2, A = p a^2 / (b^2 - a^2), B = A b^2.
  pure real(dp) function lame_bore_displacement(a, b, p, young, nu) result(u)
    real(dp), intent(in) :: a, b, p, young, nu
    real(dp) :: ca, cb
    ca = p * a**2 / (b**2 - a**2)
    cb = p * a**2 * b**2 / (b**2 - a**2)
    u = a * ((1.0_dp - nu**2) * (ca + cb / a**2) - nu * (1.0_dp + nu) * (ca - cb / a**2)) / young
  end function lame_bore_displacement

  !> Mean radial displacement (about the z axis) of the nodes on r = `r` that moved, and how many
  !! there are (the lattices' unused nodes on the circle stay at zero and are left out).
  pure subroutine mean_radial_displacement(coords, u, r, mean, count)
    real(dp), intent(in) :: coords(:, :), u(:, :), r
    real(dp), intent(out) :: mean
    integer, intent(out) :: count
    integer :: n
    mean = 0.0_dp
    count = 0
    do n = 1, size(coords, 2)
      if (abs(hypot(coords(1, n), coords(2, n)) - r) > 1.0e-6_dp .or. all(u(:, n) == 0.0_dp)) cycle
      mean = mean + dot_product(u(1:2, n), coords(1:2, n)) / r
      count = count + 1
    end do
    if (count > 0) mean = mean / count
  end subroutine mean_radial_displacement

end module feps_elasticity_testing
