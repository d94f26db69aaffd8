!> Shape functions of the element faces: the 3- and 6-node triangles in the area coordinates
!! (s1, s2) = (L2, L3) and the 4- and 8-node quadrilaterals on [-1, 1]^2, with the node orders
!! of element_t's face contract (triangles: corners 1, 2, 3, then mid-edges 4 (1-2), 5 (2-3),
!! 6 (3-1); quadrilaterals: corners (-1,-1), (1,-1), (1,1), (-1,1), then mid-edges 5 (1-2),
!! 6 (2-3), 7 (3-4), 8 (4-1)). Every solid's faces take them, tri6 its plane triangle, and the
!! interface elements their quad4, tri3 and tri6 layers (interface-quad8 keeps its own
!! arrangement of the serendipity functions: the same functions, other rounding).
module feps_face_shapes
  use feps_kinds, only: dp
  implicit none
  private

  public :: tri3_face_shape, tri6_face_shape, quad4_face_shape, quad8_face_shape

  !> Face-local coordinates of the 8 quadrilateral face nodes.
  real(dp), parameter :: quad8_s(2, 8) = reshape([ &
    -1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, &
    0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp], [2, 8])

  !> Face-local direction (1: s1, 2: s2) of the edge that holds each mid-edge node 5-8.
  integer, parameter :: quad8_edge_direction(5:8) = [1, 2, 1, 2]

contains

  !> Linear triangle: N = (L1, L2, L3) with L1 = 1 - s1 - s2; `n(3)`, `dn(2, 3)`.
  pure subroutine tri3_face_shape(s, n, dn)
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    n(1:3) = [1.0_dp - s(1) - s(2), s(1), s(2)]
    dn(1, 1:3) = [-1.0_dp, 1.0_dp, 0.0_dp]
    dn(2, 1:3) = [-1.0_dp, 0.0_dp, 1.0_dp]
  end subroutine tri3_face_shape

  !> Quadratic triangle: corners N = L (2L - 1), mid-edges N = 4 L_i L_j; `n(6)`, `dn(2, 6)`.
  pure subroutine tri6_face_shape(s, n, dn)
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: l1, l2, l3
    l2 = s(1)
    l3 = s(2)
    l1 = 1.0_dp - l2 - l3
    n(1:6) = [l1 * (2.0_dp * l1 - 1.0_dp), l2 * (2.0_dp * l2 - 1.0_dp), l3 * (2.0_dp * l3 - 1.0_dp), &
              4.0_dp * l1 * l2, 4.0_dp * l2 * l3, 4.0_dp * l3 * l1]
    ! d/ds1 = d/dL2 - d/dL1, d/ds2 = d/dL3 - d/dL1
    dn(1, 1:6) = [1.0_dp - 4.0_dp * l1, 4.0_dp * l2 - 1.0_dp, 0.0_dp, &
                  4.0_dp * (l1 - l2), 4.0_dp * l3, -4.0_dp * l3]
    dn(2, 1:6) = [1.0_dp - 4.0_dp * l1, 0.0_dp, 4.0_dp * l3 - 1.0_dp, &
                  -4.0_dp * l2, 4.0_dp * l2, 4.0_dp * (l1 - l3)]
  end subroutine tri6_face_shape

  !> Bilinear quadrilateral: N_a = (1 + s1 s1_a)(1 + s2 s2_a) / 4; `n(4)`, `dn(2, 4)`.
  pure subroutine quad4_face_shape(s, n, dn)
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: f(2)
    integer :: a
    do a = 1, 4
      f = 1.0_dp + s * quad8_s(:, a)
      n(a) = 0.25_dp * f(1) * f(2)
      dn(1, a) = 0.25_dp * quad8_s(1, a) * f(2)
      dn(2, a) = 0.25_dp * quad8_s(2, a) * f(1)
    end do
  end subroutine quad4_face_shape

  !> 8-node serendipity quadrilateral: corners N = (1 + s1 s1_a)(1 + s2 s2_a)(s.s_a - 1) / 4,
  !! mid-edge nodes N = (1 - s_k^2)(1 + s_l s_l,a) / 2; `n(8)`, `dn(2, 8)`.
  pure subroutine quad8_face_shape(s, n, dn)
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: f(2), g
    integer :: a, k, l
    do a = 1, 4
      f = 1.0_dp + s * quad8_s(:, a)
      g = dot_product(s, quad8_s(:, a)) - 1.0_dp
      n(a) = 0.25_dp * f(1) * f(2) * g
      dn(1, a) = 0.25_dp * quad8_s(1, a) * f(2) * (g + f(1))
      dn(2, a) = 0.25_dp * quad8_s(2, a) * f(1) * (g + f(2))
    end do
    do a = 5, 8
      ! k: the direction along the node's edge; l: across it
      k = quad8_edge_direction(a)
      l = 3 - k
      n(a) = 0.5_dp * (1.0_dp - s(k)**2) * (1.0_dp + s(l) * quad8_s(l, a))
      dn(k, a) = -s(k) * (1.0_dp + s(l) * quad8_s(l, a))
      dn(l, a) = 0.5_dp * (1.0_dp - s(k)**2) * quad8_s(l, a)
    end do
  end subroutine quad8_face_shape

end module feps_face_shapes
