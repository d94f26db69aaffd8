!> The 15-node quadratic wedge (pentahedron, triangular prism), 18-point rule: the 6-point
!! triangle rule (degree 4) times 3-point Gauss in zeta (degree 5), exact for the stiffness of an
!! undistorted (affine) element, whose integrand is of degree 4 in the triangle and in zeta, as
!! hex20's 3x3x3 is for an undistorted brick. (CalculiX's C3D15 uses 9 points, the 3-point
!! triangle rule times 3 Gauss: of degree 2 in the triangle, it leaves no spurious zero-energy
!! mode but misses the exact stiffness of an affine element by about 0.6% of its largest entry,
!! test_solid_elements found; feps results on wedge15 meshes differ from CalculiX's by that.)
!! Faces: triangles of 6 nodes with the 6-point rule (degree 4, exact for a pressure on a curved
!! face, as hex20's 3x3), quadrilaterals of 8 nodes (serendipity, as hex20's faces) with 3x3 Gauss.
!!
!! Nodes (Abaqus/CalculiX C3D15, gmsh order): corners 1-6 as wedge6 (bottom 1, 2, 3 at
!! zeta = -1, counter-clockwise seen from the top; top 4, 5, 6 at zeta = +1, node 3 + k above
!! node k), then the mid-edge nodes 7 (1-2), 8 (2-3), 9 (3-1), 10 (4-5), 11 (5-6), 12 (6-4),
!! 13 (1-4), 14 (2-5), 15 (3-6). Natural coordinates xi = (L2, L3, zeta), L1 = 1 - xi - eta.
!! Faces as wedge6 (the Abaqus S1-S5 numbering, each listed in the opposite sense of Abaqus's
!! for an outward normal), corners then the mid-edge nodes of the face edges in order:
!! 1: (1 3 2 9 8 7), 2: (4 5 6 10 11 12) triangles with (s1, s2) = (L2, L3) of the face;
!! 3: (1 2 5 4 7 14 10 13), 4: (2 3 6 5 8 15 11 14), 5: (3 1 4 6 9 13 12 15) quadrilaterals
!! with s1 from face node 1 towards 2, s2 from 1 towards 4.
module feps_wedge15
  use feps_kinds, only: dp
  use feps_gauss, only: wedge_rule, triangle_rule, square_rule
  use feps_face_shapes, only: tri6_face_shape, quad8_face_shape
  use feps_solid_element, only: solid_element_t
  implicit none
  private

  !> Natural coordinates of the nodes, one column per node.
  real(dp), parameter :: node_xi(3, 15) = reshape([ &
    0.0_dp, 0.0_dp, -1.0_dp,  1.0_dp, 0.0_dp, -1.0_dp,  0.0_dp, 1.0_dp, -1.0_dp, &
    0.0_dp, 0.0_dp, 1.0_dp,   1.0_dp, 0.0_dp, 1.0_dp,   0.0_dp, 1.0_dp, 1.0_dp, &
    0.5_dp, 0.0_dp, -1.0_dp,  0.5_dp, 0.5_dp, -1.0_dp,  0.0_dp, 0.5_dp, -1.0_dp, &
    0.5_dp, 0.0_dp, 1.0_dp,   0.5_dp, 0.5_dp, 1.0_dp,   0.0_dp, 0.5_dp, 1.0_dp, &
    0.0_dp, 0.0_dp, 0.0_dp,   1.0_dp, 0.0_dp, 0.0_dp,   0.0_dp, 1.0_dp, 0.0_dp], [3, 15])

  !> Triangle corners (1-3: L1, L2, L3) of the edge that holds each mid-edge node 7-12.
  integer, parameter :: triangle_edges(2, 7:12) = reshape([1, 2,  2, 3,  3, 1,  1, 2,  2, 3,  3, 1], [2, 6])

  !> Nodes of each face (columns): corners counter-clockwise seen from outside, then mid-edges;
  !! a triangle's 7th and 8th are 0.
  integer, parameter :: wedge15_faces(8, 5) = reshape([ &
    1, 3, 2, 9, 8, 7, 0, 0, &
    4, 5, 6, 10, 11, 12, 0, 0, &
    1, 2, 5, 4, 7, 14, 10, 13, &
    2, 3, 6, 5, 8, 15, 11, 14, &
    3, 1, 4, 6, 9, 13, 12, 15], [8, 5])

  !> Faces 1 and 2 are triangles, 3 to 5 quadrilaterals.
  integer, parameter :: ntriangles = 2

  type, extends(solid_element_t), public :: wedge15_t
  contains
    procedure :: nnodes => wedge15_nnodes
    procedure :: ngauss => wedge15_ngauss
    procedure :: shape => wedge15_shape
    procedure :: gauss_rule => wedge15_gauss_rule
    procedure :: natural_coordinates => wedge15_natural_coordinates
    procedure :: nfaces => wedge15_nfaces
    procedure :: nface_nodes => wedge15_nface_nodes
    procedure :: face_nodes => wedge15_face_nodes
    procedure :: face_shape => wedge15_face_shape
    procedure :: nface_gauss => wedge15_nface_gauss
    procedure :: face_gauss_rule => wedge15_face_gauss_rule
    procedure :: element_type => wedge15_element_type
  end type wedge15_t

contains

  pure integer function wedge15_nnodes(self)
    class(wedge15_t), intent(in) :: self
    wedge15_nnodes = 15
  end function wedge15_nnodes

  pure integer function wedge15_ngauss(self)
    class(wedge15_t), intent(in) :: self
    wedge15_ngauss = 18
  end function wedge15_ngauss

  pure integer function wedge15_nfaces(self)
    class(wedge15_t), intent(in) :: self
    wedge15_nfaces = 5
  end function wedge15_nfaces

  !> 6 on the triangles (faces 1, 2), 8 on the quadrilaterals.
  pure integer function wedge15_nface_nodes(self, face)
    class(wedge15_t), intent(in) :: self
    integer, intent(in) :: face
    wedge15_nface_nodes = merge(6, 8, face <= ntriangles)
  end function wedge15_nface_nodes

  !> 6 on the triangles (faces 1, 2), 3x3 = 9 on the quadrilaterals.
  pure integer function wedge15_nface_gauss(self, face)
    class(wedge15_t), intent(in) :: self
    integer, intent(in) :: face
    wedge15_nface_gauss = merge(6, 9, face <= ntriangles)
  end function wedge15_nface_gauss

  pure function wedge15_element_type(self) result(name)
    class(wedge15_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'wedge15'
  end function wedge15_element_type

  !> With L = (1 - xi - eta, xi, eta) and z = zeta zeta_a: corners
  !! N = L_c (1 + z)(2 L_c + z - 2) / 2; mid-edge nodes of the end triangles
  !! N = 2 L_i L_j (1 + z); mid-edge nodes of the vertical edges N = L_c (1 - zeta^2).
  pure subroutine wedge15_shape(self, xi, n, dn)
    class(wedge15_t), intent(in) :: self
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: l(3), dndl(3, 15), za, z
    integer :: a, c, i, j
    l = [1.0_dp - xi(1) - xi(2), xi(1), xi(2)]
    ! dndl(k, a) = dN_a / dL_k, the three L taken as independent; dn(3, :) directly
    dndl = 0.0_dp
    do a = 1, 6
      c = modulo(a - 1, 3) + 1
      za = node_xi(3, a)
      z = xi(3) * za
      n(a) = 0.5_dp * l(c) * (1.0_dp + z) * (2.0_dp * l(c) + z - 2.0_dp)
      dndl(c, a) = 0.5_dp * (1.0_dp + z) * (4.0_dp * l(c) + z - 2.0_dp)
      dn(3, a) = 0.5_dp * l(c) * za * (2.0_dp * l(c) + 2.0_dp * z - 1.0_dp)
    end do
    do a = 7, 12
      i = triangle_edges(1, a)
      j = triangle_edges(2, a)
      za = node_xi(3, a)
      n(a) = 2.0_dp * l(i) * l(j) * (1.0_dp + xi(3) * za)
      dndl(i, a) = 2.0_dp * l(j) * (1.0_dp + xi(3) * za)
      dndl(j, a) = 2.0_dp * l(i) * (1.0_dp + xi(3) * za)
      dn(3, a) = 2.0_dp * l(i) * l(j) * za
    end do
    do a = 13, 15
      c = a - 12
      n(a) = l(c) * (1.0_dp - xi(3)**2)
      dndl(c, a) = 1.0_dp - xi(3)**2
      dn(3, a) = -2.0_dp * l(c) * xi(3)
    end do
    ! d/dxi = d/dL2 - d/dL1, d/deta = d/dL3 - d/dL1
    dn(1, 1:15) = dndl(2, :) - dndl(1, :)
    dn(2, 1:15) = dndl(3, :) - dndl(1, :)
  end subroutine wedge15_shape

  pure subroutine wedge15_gauss_rule(self, xi, w)
    class(wedge15_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :), w(:)
    call wedge_rule(6, 3, xi, w)
  end subroutine wedge15_gauss_rule

  pure subroutine wedge15_natural_coordinates(self, xi)
    class(wedge15_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :)
    xi(:, 1:15) = node_xi
  end subroutine wedge15_natural_coordinates

  pure function wedge15_face_nodes(self, face) result(nodes)
    class(wedge15_t), intent(in) :: self
    integer, intent(in) :: face
    integer, allocatable :: nodes(:)
    nodes = wedge15_faces(1:self%nface_nodes(face), face)
  end function wedge15_face_nodes

  !> Quadratic triangle on faces 1, 2; 8-node serendipity quadrilateral on faces 3-5.
  pure subroutine wedge15_face_shape(self, face, s, n, dn)
    class(wedge15_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    if (face <= ntriangles) then
      call tri6_face_shape(s, n, dn)
    else
      call quad8_face_shape(s, n, dn)
    end if
  end subroutine wedge15_face_shape

  pure subroutine wedge15_face_gauss_rule(self, face, s, w)
    class(wedge15_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(out) :: s(:, :), w(:)
    if (face <= ntriangles) then
      call triangle_rule(6, s, w)
    else
      call square_rule(3, s, w)
    end if
  end subroutine wedge15_face_gauss_rule

end module feps_wedge15
