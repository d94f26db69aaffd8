!> The 8-node trilinear hexahedron, 2x2x2 Gauss; faces are 4-node bilinear quadrilaterals with
!! 2x2 Gauss.
!!
!! Nodes: bottom face (zeta = -1) counter-clockwise seen from +zeta, then the top face in the
!! same order: (-1,-1,-1), (1,-1,-1), (1,1,-1), (-1,1,-1), (-1,-1,1), (1,-1,1), (1,1,1), (-1,1,1).
!! Faces (the numbering of Abaqus S1-S6, nodes ordered for an outward normal):
!! 1: zeta = -1 (1 4 3 2), 2: zeta = +1 (5 6 7 8), 3: eta = -1 (1 2 6 5),
!! 4: xi = +1 (2 3 7 6), 5: eta = +1 (3 4 8 7), 6: xi = -1 (1 5 8 4).
module feps_hex8
  use feps_kinds, only: dp
  use feps_gauss, only: cube_rule, square_rule
  use feps_solid_element, only: solid_element_t
  use feps_face_shapes, only: quad4_face_shape
  implicit none
  private

  !> Natural coordinates of the nodes, one column per node.
  real(dp), parameter :: node_xi(3, 8) = reshape([ &
    -1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, &
    -1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp], [3, 8])

  !> Nodes of each face (columns), counter-clockwise seen from outside.
  integer, parameter :: hex8_faces(4, 6) = reshape([ &
    1, 4, 3, 2,  5, 6, 7, 8,  1, 2, 6, 5,  2, 3, 7, 6,  3, 4, 8, 7,  1, 5, 8, 4], [4, 6])


  type, extends(solid_element_t), public :: hex8_t
  contains
    procedure :: nnodes => hex8_nnodes
    procedure :: ngauss => hex8_ngauss
    procedure :: shape => hex8_shape
    procedure :: gauss_rule => hex8_gauss_rule
    procedure :: natural_coordinates => hex8_natural_coordinates
    procedure :: nfaces => hex8_nfaces
    procedure :: nface_nodes => hex8_nface_nodes
    procedure :: face_nodes => hex8_face_nodes
    procedure :: face_shape => hex8_face_shape
    procedure :: nface_gauss => hex8_nface_gauss
    procedure :: face_gauss_rule => hex8_face_gauss_rule
    procedure :: element_type => hex8_element_type
  end type hex8_t

contains

  pure integer function hex8_nnodes(self)
    class(hex8_t), intent(in) :: self
    hex8_nnodes = 8
  end function hex8_nnodes

  pure integer function hex8_ngauss(self)
    class(hex8_t), intent(in) :: self
    hex8_ngauss = 8
  end function hex8_ngauss

  pure integer function hex8_nfaces(self)
    class(hex8_t), intent(in) :: self
    hex8_nfaces = 6
  end function hex8_nfaces

  pure integer function hex8_nface_nodes(self, face)
    class(hex8_t), intent(in) :: self
    integer, intent(in) :: face
    hex8_nface_nodes = 4
  end function hex8_nface_nodes

  pure integer function hex8_nface_gauss(self, face)
    class(hex8_t), intent(in) :: self
    integer, intent(in) :: face
    hex8_nface_gauss = 4
  end function hex8_nface_gauss

  pure function hex8_element_type(self) result(name)
    class(hex8_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'hex8'
  end function hex8_element_type

  !> N_a = (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a) / 8 and its derivatives.
  pure subroutine hex8_shape(self, xi, n, dn)
    class(hex8_t), intent(in) :: self
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: f(3)
    integer :: a
    do a = 1, 8
      f = 1.0_dp + xi * node_xi(:, a)
      n(a) = 0.125_dp * f(1) * f(2) * f(3)
      dn(1, a) = 0.125_dp * node_xi(1, a) * f(2) * f(3)
      dn(2, a) = 0.125_dp * node_xi(2, a) * f(1) * f(3)
      dn(3, a) = 0.125_dp * node_xi(3, a) * f(1) * f(2)
    end do
  end subroutine hex8_shape

  pure subroutine hex8_gauss_rule(self, xi, w)
    class(hex8_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :), w(:)
    call cube_rule(2, xi, w)
  end subroutine hex8_gauss_rule

  pure subroutine hex8_natural_coordinates(self, xi)
    class(hex8_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :)
    xi(:, 1:8) = node_xi
  end subroutine hex8_natural_coordinates

  pure function hex8_face_nodes(self, face) result(nodes)
    class(hex8_t), intent(in) :: self
    integer, intent(in) :: face
    integer, allocatable :: nodes(:)
    nodes = hex8_faces(:, face)
  end function hex8_face_nodes

  !> Bilinear quadrilateral (feps_face_shapes).
  pure subroutine hex8_face_shape(self, face, s, n, dn)
    class(hex8_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    call quad4_face_shape(s, n, dn)
  end subroutine hex8_face_shape

  pure subroutine hex8_face_gauss_rule(self, face, s, w)
    class(hex8_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(out) :: s(:, :), w(:)
    call square_rule(2, s, w)
  end subroutine hex8_face_gauss_rule

end module feps_hex8
