!> The 4-node linear tetrahedron (constant strain), 1-point rule (the centroid: exact, the
!! strains are constant); faces are 3-node linear triangles with the 3-point rule (degree 2:
!! exact for the face shape functions times a linear traction).
!!
!! Nodes (Abaqus/CalculiX C3D4, gmsh order): 1, 2, 3 counter-clockwise seen from node 4, so that
!! (x2 - x1) x (x3 - x1) . (x4 - x1) > 0. Natural coordinates xi = (L2, L3, L4):
!! N1 = 1 - xi - eta - zeta, N2 = xi, N3 = eta, N4 = zeta; nodes at (0,0,0), (1,0,0), (0,1,0),
!! (0,0,1).
!! Faces (the numbering of Abaqus S1-S4, whose node sets are 1-2-3, 1-4-2, 2-4-3, 3-4-1): each
!! listed from the same first node in the opposite sense, since the Abaqus listing has the
!! right-hand normal pointing into the element (hex8's faces are the Abaqus ones reversed alike):
!! 1: (1 3 2), 2: (1 2 4), 3: (2 3 4), 4: (3 1 4). Face coordinates (s1, s2) = (L2, L3) of the
!! face triangle, so dx/ds1 x dx/ds2 points out.
module feps_tet4
  use feps_kinds, only: dp
  use feps_gauss, only: tetrahedron_rule, triangle_rule
  use feps_face_shapes, only: tri3_face_shape
  use feps_solid_element, only: solid_element_t
  implicit none
  private

  !> Natural coordinates of the nodes, one column per node.
  real(dp), parameter :: node_xi(3, 4) = reshape([ &
    0.0_dp, 0.0_dp, 0.0_dp,  1.0_dp, 0.0_dp, 0.0_dp,  0.0_dp, 1.0_dp, 0.0_dp,  0.0_dp, 0.0_dp, 1.0_dp], [3, 4])

  !> Nodes of each face (columns), counter-clockwise seen from outside.
  integer, parameter :: tet4_faces(3, 4) = reshape([1, 3, 2,  1, 2, 4,  2, 3, 4,  3, 1, 4], [3, 4])

  type, extends(solid_element_t), public :: tet4_t
  contains
    procedure :: nnodes => tet4_nnodes
    procedure :: ngauss => tet4_ngauss
    procedure :: shape => tet4_shape
    procedure :: gauss_rule => tet4_gauss_rule
    procedure :: natural_coordinates => tet4_natural_coordinates
    procedure :: nfaces => tet4_nfaces
    procedure :: nface_nodes => tet4_nface_nodes
    procedure :: face_nodes => tet4_face_nodes
    procedure :: face_shape => tet4_face_shape
    procedure :: nface_gauss => tet4_nface_gauss
    procedure :: face_gauss_rule => tet4_face_gauss_rule
    procedure :: element_type => tet4_element_type
  end type tet4_t

contains

  pure integer function tet4_nnodes(self)
    class(tet4_t), intent(in) :: self
    tet4_nnodes = 4
  end function tet4_nnodes

  pure integer function tet4_ngauss(self)
    class(tet4_t), intent(in) :: self
    tet4_ngauss = 1
  end function tet4_ngauss

  pure integer function tet4_nfaces(self)
    class(tet4_t), intent(in) :: self
    tet4_nfaces = 4
  end function tet4_nfaces

  pure integer function tet4_nface_nodes(self, face)
    class(tet4_t), intent(in) :: self
    integer, intent(in) :: face
    tet4_nface_nodes = 3
  end function tet4_nface_nodes

  pure integer function tet4_nface_gauss(self, face)
    class(tet4_t), intent(in) :: self
    integer, intent(in) :: face
    tet4_nface_gauss = 3
  end function tet4_nface_gauss

  pure function tet4_element_type(self) result(name)
    class(tet4_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'tet4'
  end function tet4_element_type

  !> N = (1 - xi - eta - zeta, xi, eta, zeta); constant derivatives.
  pure subroutine tet4_shape(self, xi, n, dn)
    class(tet4_t), intent(in) :: self
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:), dn(:, :)
    n(1:4) = [1.0_dp - xi(1) - xi(2) - xi(3), xi(1), xi(2), xi(3)]
    dn(1, 1:4) = [-1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp]
    dn(2, 1:4) = [-1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp]
    dn(3, 1:4) = [-1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]
  end subroutine tet4_shape

  pure subroutine tet4_gauss_rule(self, xi, w)
    class(tet4_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :), w(:)
    call tetrahedron_rule(1, xi, w)
  end subroutine tet4_gauss_rule

  pure subroutine tet4_natural_coordinates(self, xi)
    class(tet4_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :)
    xi(:, 1:4) = node_xi
  end subroutine tet4_natural_coordinates

  pure function tet4_face_nodes(self, face) result(nodes)
    class(tet4_t), intent(in) :: self
    integer, intent(in) :: face
    integer, allocatable :: nodes(:)
    nodes = tet4_faces(:, face)
  end function tet4_face_nodes

  pure subroutine tet4_face_shape(self, face, s, n, dn)
    class(tet4_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    call tri3_face_shape(s, n, dn)
  end subroutine tet4_face_shape

  pure subroutine tet4_face_gauss_rule(self, face, s, w)
    class(tet4_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(out) :: s(:, :), w(:)
    call triangle_rule(3, s, w)
  end subroutine tet4_face_gauss_rule

end module feps_tet4
