!> Geometry for the tests' closed forms of surface loads: the cross product and the boundary
!! integrals of a face whose edges are quadratic curves (straight edges have the mid-point as
!! their middle node).
module feps_geometry_testing
  use feps_kinds, only: dp
  use feps_gauss, only: gauss_legendre
  implicit none
  private

  public :: cross, add_edge_integrals, linear_field, voigt_strain, rigid_mode

contains

  !> a x b
  pure function cross(a, b) result(c)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross

  !> Add the integrals along the quadratic edge from `xa` through `xm` to `xb` that give a face's
  !! vector area, 1/2 closed-integral of x cross dx, and its load moment, 1/2 closed-integral of
  !! |x|^2 dx (Stokes). The integrands are polynomials of degree 3 and 5: 4 Gauss points are exact.
  pure subroutine add_edge_integrals(xa, xb, xm, area, loop)
    real(dp), intent(in) :: xa(3), xb(3), xm(3)
    real(dp), intent(inout) :: area(3), loop(3)
    real(dp) :: s(4), ws(4), x(3), dx(3)
    integer :: g
    call gauss_legendre(4, s, ws)
    do g = 1, 4
      x = 0.5_dp * s(g) * (s(g) - 1.0_dp) * xa + 0.5_dp * s(g) * (s(g) + 1.0_dp) * xb + (1.0_dp - s(g)**2) * xm
      dx = (s(g) - 0.5_dp) * xa + (s(g) + 0.5_dp) * xb - 2.0_dp * s(g) * xm
      area = area + 0.5_dp * ws(g) * cross(x, dx)
      loop = loop + 0.5_dp * ws(g) * dot_product(x, x) * dx
    end do
  end subroutine add_edge_integrals

  !> Displacement vector of the field u = h x + c at the nodes `xe`.
  pure function linear_field(xe, h, c) result(u)
    real(dp), intent(in) :: xe(:, :), h(3, 3), c(3)
    real(dp) :: u(3 * size(xe, 2))
    integer :: a
    do a = 1, size(xe, 2)
      u(3 * a - 2:3 * a) = matmul(h, xe(:, a)) + c
    end do
  end function linear_field

  !> Engineering Voigt strain of the displacement gradient h.
  pure function voigt_strain(h) result(eps)
    real(dp), intent(in) :: h(3, 3)
    real(dp) :: eps(6)
    eps = [h(1, 1), h(2, 2), h(3, 3), h(2, 3) + h(3, 2), h(1, 3) + h(3, 1), h(1, 2) + h(2, 1)]
  end function voigt_strain

  !> Rigid-body mode `mode` (1-3: translation along x, y, z; 4-6: rotation about x, y, z) as the
  !! displacement field u = h x + c.
  pure subroutine rigid_mode(mode, h, c)
    integer, intent(in) :: mode
    real(dp), intent(out) :: h(3, 3), c(3)
    h = 0.0_dp
    c = 0.0_dp
    select case (mode)
    case (1:3)
      c(mode) = 1.0_dp
    case (4)   ! rotation about x
      h(2, 3) = -1.0_dp
      h(3, 2) = 1.0_dp
    case (5)   ! about y
      h(1, 3) = 1.0_dp
      h(3, 1) = -1.0_dp
    case (6)   ! about z
      h(1, 2) = -1.0_dp
      h(2, 1) = 1.0_dp
    end select
  end subroutine rigid_mode

end module feps_geometry_testing
