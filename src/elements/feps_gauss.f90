!> Gauss-Legendre quadrature on [-1, 1] with 1 to 5 points, and its tensor products on the
!! square [-1, 1]^2 and the cube [-1, 1]^3. An n-point rule integrates polynomials of degree
!! 2n - 1 exactly in each coordinate.
module feps_gauss
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_internal, str
  implicit none
  private

  integer, parameter, public :: max_gauss_points = 5  !! largest 1D rule available

  public :: gauss_legendre, square_rule, cube_rule

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

end module feps_gauss
