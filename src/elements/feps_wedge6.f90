!> The 6-node linear wedge (pentahedron, triangular prism), 6-point rule: the 3-point triangle
!! rule (degree 2) times 2-point Gauss in zeta (degree 3), exact for the stiffness of an
!! undistorted (affine) prism, whose integrand is of degree 2 in the triangle and in zeta,
!! as hex8's 2x2x2 is for an undistorted brick. (CalculiX's C3D6 uses 2 points, the triangle
!! centroid times 2 Gauss: not exact, and a single free element then has a 7th zero-energy mode,
!! test_solid_elements found; feps results on wedge6 meshes differ from CalculiX's by that.)
!! Faces: triangles of 3 nodes with the 3-point rule (degree 2: exact for the face shape
!! functions times a linear traction), quadrilaterals of 4 nodes with 2x2 Gauss as hex8's.
!!
!! Nodes (Abaqus/CalculiX C3D6, gmsh order): the bottom triangle 1, 2, 3 (zeta = -1),
!! counter-clockwise seen from the top, then the top triangle 4, 5, 6 (zeta = +1), node 3 + k
!! above node k. Natural coordinates xi = (L2, L3, zeta): N_a = L_a (1 + zeta zeta_a) / 2 with
!! (L1, L2, L3) = (1 - xi - eta, xi, eta).
!! Faces (the numbering of Abaqus S1-S5, whose node sets are 1-2-3, 4-6-5, 1-4-5-2, 2-5-6-3,
!! 3-6-4-1): each listed from the same first node in the opposite sense, since the Abaqus
!! listing has the right-hand normal pointing into the element (as for hex8 and tet4):
!! 1: (1 3 2), 2: (4 5 6) triangles with (s1, s2) = (L2, L3) of the face;
!! 3: (1 2 5 4), 4: (2 3 6 5), 5: (3 1 4 6) quadrilaterals with s1 from face node 1 towards 2,
!! s2 from 1 towards 4; dx/ds1 x dx/ds2 points out on every face.
module feps_wedge6
  use feps_kinds, only: dp
  use feps_gauss, only: wedge_rule, triangle_rule, square_rule
  use feps_face_shapes, only: tri3_face_shape, quad4_face_shape
  use feps_solid_element, only: solid_element_t
  implicit none
  private

  !> Natural coordinates of the nodes, one column per node.
  real(dp), parameter :: node_xi(3, 6) = reshape([ &
    0.0_dp, 0.0_dp, -1.0_dp,  1.0_dp, 0.0_dp, -1.0_dp,  0.0_dp, 1.0_dp, -1.0_dp, &
    0.0_dp, 0.0_dp, 1.0_dp,   1.0_dp, 0.0_dp, 1.0_dp,   0.0_dp, 1.0_dp, 1.0_dp], [3, 6])

  !> Nodes of each face (columns), counter-clockwise seen from outside; a triangle's 4th is 0.
  integer, parameter :: wedge6_faces(4, 5) = reshape([ &
    1, 3, 2, 0,  4, 5, 6, 0,  1, 2, 5, 4,  2, 3, 6, 5,  3, 1, 4, 6], [4, 5])

  !> Faces 1 and 2 are triangles, 3 to 5 quadrilaterals.
  integer, parameter :: ntriangles = 2

  type, extends(solid_element_t), public :: wedge6_t
  contains
    procedure :: nnodes => wedge6_nnodes
    procedure :: ngauss => wedge6_ngauss
    procedure :: shape => wedge6_shape
    procedure :: gauss_rule => wedge6_gauss_rule
    procedure :: natural_coordinates => wedge6_natural_coordinates
    procedure :: nfaces => wedge6_nfaces
    procedure :: nface_nodes => wedge6_nface_nodes
    procedure :: face_nodes => wedge6_face_nodes
    procedure :: face_shape => wedge6_face_shape
    procedure :: nface_gauss => wedge6_nface_gauss
    procedure :: face_gauss_rule => wedge6_face_gauss_rule
    procedure :: element_type => wedge6_element_type
  end type wedge6_t

contains

  pure integer function wedge6_nnodes(self)
    class(wedge6_t), intent(in) :: self
    wedge6_nnodes = 6
  end function wedge6_nnodes

  pure integer function wedge6_ngauss(self)
    class(wedge6_t), intent(in) :: self
    wedge6_ngauss = 6
  end function wedge6_ngauss

  pure integer function wedge6_nfaces(self)
    class(wedge6_t), intent(in) :: self
    wedge6_nfaces = 5
  end function wedge6_nfaces

  !> 3 on the triangles (faces 1, 2), 4 on the quadrilaterals.
  pure integer function wedge6_nface_nodes(self, face)
    class(wedge6_t), intent(in) :: self
    integer, intent(in) :: face
    wedge6_nface_nodes = merge(3, 4, face <= ntriangles)
  end function wedge6_nface_nodes

  !> 3 on the triangles (faces 1, 2), 2x2 = 4 on the quadrilaterals.
  pure integer function wedge6_nface_gauss(self, face)
    class(wedge6_t), intent(in) :: self
    integer, intent(in) :: face
    wedge6_nface_gauss = merge(3, 4, face <= ntriangles)
  end function wedge6_nface_gauss

  pure function wedge6_element_type(self) result(name)
    class(wedge6_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'wedge6'
  end function wedge6_element_type

  !> N_a = L_a (1 + zeta zeta_a) / 2, L = (1 - xi - eta, xi, eta) of the node's corner.
  pure subroutine wedge6_shape(self, xi, n, dn)
    class(wedge6_t), intent(in) :: self
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:), dn(:, :)
    ! dl(k, c) = dL_c / dxi_k
    real(dp), parameter :: dl(2, 3) = reshape([-1.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 3])
    real(dp) :: l(3), f
    integer :: a, c
    l = [1.0_dp - xi(1) - xi(2), xi(1), xi(2)]
    do a = 1, 6
      c = modulo(a - 1, 3) + 1
      f = 0.5_dp * (1.0_dp + xi(3) * node_xi(3, a))
      n(a) = l(c) * f
      dn(1:2, a) = dl(:, c) * f
      dn(3, a) = 0.5_dp * l(c) * node_xi(3, a)
    end do
  end subroutine wedge6_shape

  pure subroutine wedge6_gauss_rule(self, xi, w)
    class(wedge6_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :), w(:)
    call wedge_rule(3, 2, xi, w)
  end subroutine wedge6_gauss_rule

  pure subroutine wedge6_natural_coordinates(self, xi)
    class(wedge6_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :)
    xi(:, 1:6) = node_xi
  end subroutine wedge6_natural_coordinates

  pure function wedge6_face_nodes(self, face) result(nodes)
    class(wedge6_t), intent(in) :: self
    integer, intent(in) :: face
    integer, allocatable :: nodes(:)
    nodes = wedge6_faces(1:self%nface_nodes(face), face)
  end function wedge6_face_nodes

  !> Linear triangle on faces 1, 2; bilinear quadrilateral on faces 3-5.
  pure subroutine wedge6_face_shape(self, face, s, n, dn)
    class(wedge6_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    if (face <= ntriangles) then
      call tri3_face_shape(s, n, dn)
    else
      call quad4_face_shape(s, n, dn)
    end if
  end subroutine wedge6_face_shape

  pure subroutine wedge6_face_gauss_rule(self, face, s, w)
    class(wedge6_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(out) :: s(:, :), w(:)
    if (face <= ntriangles) then
      call triangle_rule(3, s, w)
    else
      call square_rule(2, s, w)
    end if
  end subroutine wedge6_face_gauss_rule

end module feps_wedge6
