!> Gauss-Legendre quadrature on [-1, 1] with 1 to 5 points, and its tensor products on the
!! square [-1, 1]^2 and the cube [-1, 1]^3. An n-point rule integrates polynomials of degree
!! 2n - 1 exactly in each coordinate. Also the symmetric rules of the reference triangle
!! (s1, s2 >= 0, s1 + s2 <= 1) and tetrahedron (xi_i >= 0, xi_1 + xi_2 + xi_3 <= 1), in the area
!! or volume coordinates (L2, L3[, L4]) of the simplex elements, and their product with
!! Gauss-Legendre on the wedge (triangle times [-1, 1]).
module feps_gauss
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_internal, str
  implicit none
  private

  integer, parameter, public :: max_gauss_points = 5  !! largest 1D rule available

  public :: gauss_legendre, square_rule, cube_rule, triangle_rule, tetrahedron_rule, wedge_rule

  ! Symmetric 6-point triangle rule of degree 4 (Dunavant 1985): points (a, a), (1 - 2a, a),
  ! (a, 1 - 2a) for two orbits; weights are for a triangle of unit area (multiplied by 1/2 below).
  real(dp), parameter :: orbit1_a = 0.445948490915964886318329253883_dp
  real(dp), parameter :: orbit1_w = 0.223381589678011465944827736195_dp
  real(dp), parameter :: orbit2_a = 0.091576213509770743459571463402_dp
  real(dp), parameter :: orbit2_w = 0.109951743655321867388505597138_dp

contains

  !> Points `x(1:n)` (ascending) and weights `w(1:n)` of the n-point Gauss-Legendre rule on [-1, 1].
  !! `n` must be 1..max_gauss_points; otherwise x and w are zero and `error` (if present) says so.
  pure subroutine gauss_legendre(n, x, w, error)
    integer, intent(in) :: n
    real(dp), intent(out) :: x(:), w(:)
    type(error_t), allocatable, intent(out), optional :: error
    real(dp) :: a, b
    x = 0.0_dp
    w = 0.0_dp
    if (n < 1 .or. n > max_gauss_points .or. size(x) < n .or. size(w) < n) then
      if (present(error)) call fatal_error(error, err_internal, 'Gauss-Legendre rule with ' // str(n) // &
                                           ' points is not available (1 to ' // str(max_gauss_points) // ')')
      return
    end if
    select case (n)
    case (1)
      x(1) = 0.0_dp
      w(1) = 2.0_dp
    case (2)
      x(1:2) = [-1.0_dp, 1.0_dp] / sqrt(3.0_dp)
      w(1:2) = 1.0_dp
    case (3)
      x(1:3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
      w(1:3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
    case (4)
      a = sqrt(3.0_dp / 7.0_dp - 2.0_dp / 7.0_dp * sqrt(1.2_dp))
      b = sqrt(3.0_dp / 7.0_dp + 2.0_dp / 7.0_dp * sqrt(1.2_dp))
      x(1:4) = [-b, -a, a, b]
      w(1:4) = [18.0_dp - sqrt(30.0_dp), 18.0_dp + sqrt(30.0_dp), 18.0_dp + sqrt(30.0_dp), &
                18.0_dp - sqrt(30.0_dp)] / 36.0_dp
    case (5)
      a = sqrt(5.0_dp - 2.0_dp * sqrt(10.0_dp / 7.0_dp)) / 3.0_dp
      b = sqrt(5.0_dp + 2.0_dp * sqrt(10.0_dp / 7.0_dp)) / 3.0_dp
      x(1:5) = [-b, -a, 0.0_dp, a, b]
      w(1:5) = [322.0_dp - 13.0_dp * sqrt(70.0_dp), 322.0_dp + 13.0_dp * sqrt(70.0_dp), 512.0_dp, &
                322.0_dp + 13.0_dp * sqrt(70.0_dp), 322.0_dp - 13.0_dp * sqrt(70.0_dp)] / 900.0_dp
    end select
  end subroutine gauss_legendre

  !> n x n tensor-product rule on the square: point k = i + n (j - 1) is (x_i, x_j), the first
  !! coordinate varying fastest. `s` is (2, n**2), `w` is (n**2).
  pure subroutine square_rule(n, s, w, error)
    integer, intent(in) :: n
    real(dp), intent(out) :: s(:, :), w(:)
    type(error_t), allocatable, intent(out), optional :: error
    real(dp) :: x(max_gauss_points), wx(max_gauss_points)
    type(error_t), allocatable :: rule_error
    integer :: i, j, k
    s = 0.0_dp
    w = 0.0_dp
    call gauss_legendre(n, x, wx, rule_error)
    if (.not. allocated(rule_error) .and. (size(s, 1) < 2 .or. size(s, 2) < n**2 .or. size(w) < n**2)) &
      call fatal_error(rule_error, err_internal, 'square_rule: arrays too small for ' // str(n**2) // ' points')
    if (allocated(rule_error)) then
      if (present(error)) call move_alloc(rule_error, error)
      return
    end if
    k = 0
    do j = 1, n
      do i = 1, n
        k = k + 1
        s(1:2, k) = [x(i), x(j)]
        w(k) = wx(i) * wx(j)
      end do
    end do
  end subroutine square_rule

  !> n x n x n tensor-product rule on the cube: point k = i + n (j - 1) + n**2 (l - 1) is
  !! (x_i, x_j, x_l), the first coordinate varying fastest. `xi` is (3, n**3), `w` is (n**3).
  pure subroutine cube_rule(n, xi, w, error)
    integer, intent(in) :: n
    real(dp), intent(out) :: xi(:, :), w(:)
    type(error_t), allocatable, intent(out), optional :: error
    real(dp) :: x(max_gauss_points), wx(max_gauss_points)
    type(error_t), allocatable :: rule_error
    integer :: i, j, l, k
    xi = 0.0_dp
    w = 0.0_dp
    call gauss_legendre(n, x, wx, rule_error)
    if (.not. allocated(rule_error) .and. (size(xi, 1) < 3 .or. size(xi, 2) < n**3 .or. size(w) < n**3)) &
      call fatal_error(rule_error, err_internal, 'cube_rule: arrays too small for ' // str(n**3) // ' points')
    if (allocated(rule_error)) then
      if (present(error)) call move_alloc(rule_error, error)
      return
    end if
    k = 0
    do l = 1, n
      do j = 1, n
        do i = 1, n
          k = k + 1
          xi(1:3, k) = [x(i), x(j), x(l)]
          w(k) = wx(i) * wx(j) * wx(l)
        end do
      end do
    end do
  end subroutine cube_rule

  !> Symmetric rule on the reference triangle with `n` = 1 (degree 1: the centroid), 3 (degree 2:
  !! the interior points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3)) or 6 points (degree 4, Dunavant 1985):
  !! points `s(2, n)` in the area coordinates (L2, L3) and weights `w(n)` summing to 1/2, the
  !! reference area. Another `n` gives zero arrays and `error` (if present) says so.
  pure subroutine triangle_rule(n, s, w, error)
    integer, intent(in) :: n
    real(dp), intent(out) :: s(:, :), w(:)
    type(error_t), allocatable, intent(out), optional :: error
    s = 0.0_dp
    w = 0.0_dp
    if (all(n /= [1, 3, 6]) .or. size(s, 1) < 2 .or. size(s, 2) < n .or. size(w) < n) then
      if (present(error)) call fatal_error(error, err_internal, 'triangle rule with ' // str(n) // &
                                           ' points is not available (1, 3 or 6), or the arrays are too small')
      return
    end if
    select case (n)
    case (1)
      s(1:2, 1) = 1.0_dp / 3.0_dp
      w(1) = 0.5_dp
    case (3)
      call triangle_orbit(1.0_dp / 6.0_dp, 0, s)
      w(1:3) = 1.0_dp / 6.0_dp
    case (6)
      call triangle_orbit(orbit1_a, 0, s)
      call triangle_orbit(orbit2_a, 3, s)
      w(1:3) = 0.5_dp * orbit1_w
      w(4:6) = 0.5_dp * orbit2_w
    end select
  end subroutine triangle_rule

  !> The three points (a, a), (1 - 2a, a), (a, 1 - 2a) of a symmetric orbit into
  !! `pts(1:2, offset + 1:offset + 3)`.
  pure subroutine triangle_orbit(a, offset, pts)
    real(dp), intent(in) :: a
    integer, intent(in) :: offset
    real(dp), intent(inout) :: pts(:, :)
    pts(1:2, offset + 1) = [a, a]
    pts(1:2, offset + 2) = [1.0_dp - 2.0_dp * a, a]
    pts(1:2, offset + 3) = [a, 1.0_dp - 2.0_dp * a]
  end subroutine triangle_orbit

  !> Symmetric rule on the reference tetrahedron with `n` = 1 (degree 1: the centroid) or 4 points
  !! (degree 2: L_k = (5 + 3 sqrt 5)/20 at point k, the other three (5 - sqrt 5)/20): points
  !! `xi(3, n)` in the volume coordinates (L2, L3, L4) and weights `w(n)` summing to 1/6, the
  !! reference volume. Another `n` gives zero arrays and `error` (if present) says so.
  pure subroutine tetrahedron_rule(n, xi, w, error)
    integer, intent(in) :: n
    real(dp), intent(out) :: xi(:, :), w(:)
    type(error_t), allocatable, intent(out), optional :: error
    real(dp) :: a, b
    integer :: k
    xi = 0.0_dp
    w = 0.0_dp
    if (all(n /= [1, 4]) .or. size(xi, 1) < 3 .or. size(xi, 2) < n .or. size(w) < n) then
      if (present(error)) call fatal_error(error, err_internal, 'tetrahedron rule with ' // str(n) // &
                                           ' points is not available (1 or 4), or the arrays are too small')
      return
    end if
    select case (n)
    case (1)
      xi(1:3, 1) = 0.25_dp
      w(1) = 1.0_dp / 6.0_dp
    case (4)
      a = (5.0_dp - sqrt(5.0_dp)) / 20.0_dp
      b = (5.0_dp + 3.0_dp * sqrt(5.0_dp)) / 20.0_dp
      ! point 1 near corner 1 (L1 = b), point k near corner k (L_k = b)
      xi(1:3, 1:4) = a
      do k = 2, 4
        xi(k - 1, k) = b
      end do
      w(1:4) = 1.0_dp / 24.0_dp
    end select
  end subroutine tetrahedron_rule

  !> Product rule on the reference wedge (triangle times zeta in [-1, 1]): the `ntri`-point
  !! triangle rule times the `nz`-point Gauss-Legendre rule; point k = i + ntri (j - 1) is
  !! (s_i, zeta_j), the triangle point varying fastest. `xi` is (3, ntri nz), `w` (ntri nz),
  !! the weights summing to 1, the reference volume. A rule not available gives zero arrays and
  !! `error` (if present) says so.
  pure subroutine wedge_rule(ntri, nz, xi, w, error)
    integer, intent(in) :: ntri, nz
    real(dp), intent(out) :: xi(:, :), w(:)
    type(error_t), allocatable, intent(out), optional :: error
    real(dp) :: s(2, 6), ws(6), z(max_gauss_points), wz(max_gauss_points)
    type(error_t), allocatable :: rule_error
    integer :: i, j, k
    xi = 0.0_dp
    w = 0.0_dp
    call triangle_rule(ntri, s, ws, rule_error)
    if (.not. allocated(rule_error)) call gauss_legendre(nz, z, wz, rule_error)
    if (.not. allocated(rule_error) .and. (size(xi, 1) < 3 .or. size(xi, 2) < ntri * nz .or. size(w) < ntri * nz)) &
      call fatal_error(rule_error, err_internal, 'wedge_rule: arrays too small for ' // str(ntri * nz) // ' points')
    if (allocated(rule_error)) then
      if (present(error)) call move_alloc(rule_error, error)
      return
    end if
    k = 0
    do j = 1, nz
      do i = 1, ntri
        k = k + 1
        xi(1:3, k) = [s(1, i), s(2, i), z(j)]
        w(k) = ws(i) * wz(j)
      end do
    end do
  end subroutine wedge_rule

end module feps_gauss
