!> The 20-node serendipity hexahedron, 3x3x3 Gauss or (with `reduced`) 2x2x2; faces are
!! 8-node serendipity quadrilaterals with 3x3 Gauss.
!!
!! Nodes (Abaqus C3D20 / VTK order): corners 1-8 as hex8, then the mid-edge nodes
!! 9-12 on edges 1-2, 2-3, 3-4, 4-1; 13-16 on edges 5-6, 6-7, 7-8, 8-5; 17-20 on edges 1-5, 2-6,
!! 3-7, 4-8. Faces as hex8 (1: zeta = -1, 2: zeta = +1, 3: eta = -1, 4: xi = +1, 5: eta = +1,
!! 6: xi = -1), each listed as its 4 corners counter-clockwise seen from outside, then the
!! mid-edge nodes of face edges 1-2, 2-3, 3-4, 4-1.
module feps_hex20
  use feps_kinds, only: dp
  use feps_gauss, only: cube_rule, square_rule
  use feps_solid_element, only: solid_element_t
  use feps_face_shapes, only: quad8_face_shape
  implicit none
  private

  !> Natural coordinates of the nodes, one column per node.
  real(dp), parameter :: node_xi(3, 20) = reshape([ &
    -1.0_dp, -1.0_dp, -1.0_dp,   1.0_dp, -1.0_dp, -1.0_dp,   1.0_dp, 1.0_dp, -1.0_dp,  -1.0_dp, 1.0_dp, -1.0_dp, &
    -1.0_dp, -1.0_dp, 1.0_dp,    1.0_dp, -1.0_dp, 1.0_dp,    1.0_dp, 1.0_dp, 1.0_dp,   -1.0_dp, 1.0_dp, 1.0_dp, &
    0.0_dp, -1.0_dp, -1.0_dp,    1.0_dp, 0.0_dp, -1.0_dp,    0.0_dp, 1.0_dp, -1.0_dp,  -1.0_dp, 0.0_dp, -1.0_dp, &
    0.0_dp, -1.0_dp, 1.0_dp,     1.0_dp, 0.0_dp, 1.0_dp,     0.0_dp, 1.0_dp, 1.0_dp,   -1.0_dp, 0.0_dp, 1.0_dp, &
    -1.0_dp, -1.0_dp, 0.0_dp,    1.0_dp, -1.0_dp, 0.0_dp,    1.0_dp, 1.0_dp, 0.0_dp,   -1.0_dp, 1.0_dp, 0.0_dp], &
    [3, 20])

  !> Nodes of each face (columns): corners counter-clockwise seen from outside, then mid-edges.
  integer, parameter :: hex20_faces(8, 6) = reshape([ &
    1, 4, 3, 2, 12, 11, 10, 9, &
    5, 6, 7, 8, 13, 14, 15, 16, &
    1, 2, 6, 5, 9, 18, 13, 17, &
    2, 3, 7, 6, 10, 19, 14, 18, &
    3, 4, 8, 7, 11, 20, 15, 19, &
    1, 5, 8, 4, 17, 16, 20, 12], [8, 6])

  !> Direction (1: xi, 2: eta, 3: zeta) of the edge that holds each mid-edge node 9-20.
  integer, parameter :: edge_direction(9:20) = [1, 2, 1, 2, 1, 2, 1, 2, 3, 3, 3, 3]

  type, extends(solid_element_t), public :: hex20_t
    logical :: reduced = .false.   !! .true.: 2x2x2 reduced integration instead of 3x3x3
  contains
    procedure :: nnodes => hex20_nnodes
    procedure :: ngauss => hex20_ngauss
    procedure :: shape => hex20_shape
    procedure :: gauss_rule => hex20_gauss_rule
    procedure :: natural_coordinates => hex20_natural_coordinates
    procedure :: nfaces => hex20_nfaces
    procedure :: nface_nodes => hex20_nface_nodes
    procedure :: face_nodes => hex20_face_nodes
    procedure :: face_shape => hex20_face_shape
    procedure :: nface_gauss => hex20_nface_gauss
    procedure :: face_gauss_rule => hex20_face_gauss_rule
    procedure :: element_type => hex20_element_type
  end type hex20_t

contains

  pure integer function hex20_nnodes(self)
    class(hex20_t), intent(in) :: self
    hex20_nnodes = 20
  end function hex20_nnodes

  pure integer function hex20_ngauss(self)
    class(hex20_t), intent(in) :: self
    hex20_ngauss = merge(8, 27, self%reduced)
  end function hex20_ngauss

  pure integer function hex20_nfaces(self)
    class(hex20_t), intent(in) :: self
    hex20_nfaces = 6
  end function hex20_nfaces

  pure integer function hex20_nface_nodes(self, face)
    class(hex20_t), intent(in) :: self
    integer, intent(in) :: face
    hex20_nface_nodes = 8
  end function hex20_nface_nodes

  pure integer function hex20_nface_gauss(self, face)
    class(hex20_t), intent(in) :: self
    integer, intent(in) :: face
    hex20_nface_gauss = 9
  end function hex20_nface_gauss

  !> The catalog's name: 'hex20' (3x3x3 Gauss) or 'hex20r' (2x2x2, reduced).
  pure function hex20_element_type(self) result(name)
    class(hex20_t), intent(in) :: self
    character(len=:), allocatable :: name
    if (self%reduced) then
      name = 'hex20r'
    else
      name = 'hex20'
    end if
  end function hex20_element_type

  !> Serendipity shape functions: corners N = f1 f2 f3 (xi.xi_a - 2) / 8 with f_i = 1 + xi_i xi_a,i;
  !! mid-edge nodes (xi_a,k = 0) N = (1 - xi_k^2) f_p f_q / 4.
  pure subroutine hex20_shape(self, xi, n, dn)
    class(hex20_t), intent(in) :: self
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: f(3), g, bubble
    integer :: a, k, p, q
    do a = 1, 8
      f = 1.0_dp + xi * node_xi(:, a)
      g = dot_product(xi, node_xi(:, a)) - 2.0_dp
      n(a) = 0.125_dp * f(1) * f(2) * f(3) * g
      dn(1, a) = 0.125_dp * node_xi(1, a) * f(2) * f(3) * (g + f(1))
      dn(2, a) = 0.125_dp * node_xi(2, a) * f(1) * f(3) * (g + f(2))
      dn(3, a) = 0.125_dp * node_xi(3, a) * f(1) * f(2) * (g + f(3))
    end do
    do a = 9, 20
      ! k: the direction along the node's edge; p, q: the other two
      k = edge_direction(a)
      p = modulo(k, 3) + 1
      q = modulo(k + 1, 3) + 1
      f = 1.0_dp + xi * node_xi(:, a)
      bubble = 1.0_dp - xi(k)**2
      n(a) = 0.25_dp * bubble * f(p) * f(q)
      dn(k, a) = -0.5_dp * xi(k) * f(p) * f(q)
      dn(p, a) = 0.25_dp * bubble * node_xi(p, a) * f(q)
      dn(q, a) = 0.25_dp * bubble * node_xi(q, a) * f(p)
    end do
  end subroutine hex20_shape

  pure subroutine hex20_gauss_rule(self, xi, w)
    class(hex20_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :), w(:)
    call cube_rule(merge(2, 3, self%reduced), xi, w)
  end subroutine hex20_gauss_rule

  pure subroutine hex20_natural_coordinates(self, xi)
    class(hex20_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :)
    xi(:, 1:20) = node_xi
  end subroutine hex20_natural_coordinates

  pure function hex20_face_nodes(self, face) result(nodes)
    class(hex20_t), intent(in) :: self
    integer, intent(in) :: face
    integer, allocatable :: nodes(:)
    nodes = hex20_faces(:, face)
  end function hex20_face_nodes

  !> 8-node serendipity quadrilateral (feps_face_shapes).
  pure subroutine hex20_face_shape(self, face, s, n, dn)
    class(hex20_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    call quad8_face_shape(s, n, dn)
  end subroutine hex20_face_shape

  pure subroutine hex20_face_gauss_rule(self, face, s, w)
    class(hex20_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(out) :: s(:, :), w(:)
    call square_rule(3, s, w)
  end subroutine hex20_face_gauss_rule

end module feps_hex20
