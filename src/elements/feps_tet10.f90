!> The 10-node quadratic tetrahedron, 4-point rule (degree 2: exact for the stiffness of a
!! straight-edged element, whose strains are linear; CalculiX's C3D10 rule too);
!! faces are 6-node quadratic triangles with the 6-point rule (degree 4: exact for a pressure
!! on a curved face, N_a times the degree-2 normal dx/ds1 x dx/ds2, as hex20's 3x3 faces are).
!!
!! Nodes (Abaqus/CalculiX C3D10, gmsh order): corners 1-4 as tet4 (1, 2, 3 counter-clockwise
!! seen from node 4), then the mid-edge nodes 5 (1-2), 6 (2-3), 7 (3-1), 8 (1-4), 9 (2-4),
!! 10 (3-4). Natural coordinates xi = (L2, L3, L4), L1 = 1 - xi - eta - zeta.
!! Faces as tet4 (the Abaqus S1-S4 numbering, each listed in the opposite sense of Abaqus's for an
!! outward normal), corners then the mid-edge nodes of face edges 1-2, 2-3, 3-1:
!! 1: (1 3 2 7 6 5), 2: (1 2 4 5 9 8), 3: (2 3 4 6 10 9), 4: (3 1 4 7 8 10).
module feps_tet10
  use feps_kinds, only: dp
  use feps_gauss, only: tetrahedron_rule, triangle_rule
  use feps_face_shapes, only: tri6_face_shape
  use feps_solid_element, only: solid_element_t
  implicit none
  private

  !> Natural coordinates of the nodes, one column per node.
  real(dp), parameter :: node_xi(3, 10) = reshape([ &
    0.0_dp, 0.0_dp, 0.0_dp,  1.0_dp, 0.0_dp, 0.0_dp,  0.0_dp, 1.0_dp, 0.0_dp,  0.0_dp, 0.0_dp, 1.0_dp, &
    0.5_dp, 0.0_dp, 0.0_dp,  0.5_dp, 0.5_dp, 0.0_dp,  0.0_dp, 0.5_dp, 0.0_dp, &
    0.0_dp, 0.0_dp, 0.5_dp,  0.5_dp, 0.0_dp, 0.5_dp,  0.0_dp, 0.5_dp, 0.5_dp], [3, 10])

  !> Corners (columns) of the edge that holds each mid-edge node 5-10.
  integer, parameter :: tet10_edges(2, 5:10) = reshape([1, 2,  2, 3,  3, 1,  1, 4,  2, 4,  3, 4], [2, 6])

  !> Nodes of each face (columns): corners counter-clockwise seen from outside, then mid-edges.
  integer, parameter :: tet10_faces(6, 4) = reshape([ &
    1, 3, 2, 7, 6, 5, &
    1, 2, 4, 5, 9, 8, &
    2, 3, 4, 6, 10, 9, &
    3, 1, 4, 7, 8, 10], [6, 4])

  type, extends(solid_element_t), public :: tet10_t
  contains
    procedure :: nnodes => tet10_nnodes
    procedure :: ngauss => tet10_ngauss
    procedure :: shape => tet10_shape
    procedure :: gauss_rule => tet10_gauss_rule
    procedure :: natural_coordinates => tet10_natural_coordinates
    procedure :: nfaces => tet10_nfaces
    procedure :: nface_nodes => tet10_nface_nodes
    procedure :: face_nodes => tet10_face_nodes
    procedure :: face_shape => tet10_face_shape
    procedure :: nface_gauss => tet10_nface_gauss
    procedure :: face_gauss_rule => tet10_face_gauss_rule
    procedure :: element_type => tet10_element_type
  end type tet10_t

contains

  pure integer function tet10_nnodes(self)
    class(tet10_t), intent(in) :: self
    tet10_nnodes = 10
  end function tet10_nnodes

  pure integer function tet10_ngauss(self)
    class(tet10_t), intent(in) :: self
    tet10_ngauss = 4
  end function tet10_ngauss

  pure integer function tet10_nfaces(self)
    class(tet10_t), intent(in) :: self
    tet10_nfaces = 4
  end function tet10_nfaces

  pure integer function tet10_nface_nodes(self, face)
    class(tet10_t), intent(in) :: self
    integer, intent(in) :: face
    tet10_nface_nodes = 6
  end function tet10_nface_nodes

  pure integer function tet10_nface_gauss(self, face)
    class(tet10_t), intent(in) :: self
    integer, intent(in) :: face
    tet10_nface_gauss = 6
  end function tet10_nface_gauss

  pure function tet10_element_type(self) result(name)
    class(tet10_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'tet10'
  end function tet10_element_type

  !> Corners N = L (2L - 1), mid-edge nodes N = 4 L_i L_j, with L = (1 - xi - eta - zeta, xi,
  !! eta, zeta).
  pure subroutine tet10_shape(self, xi, n, dn)
    class(tet10_t), intent(in) :: self
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: l(4), dndl(4, 10)
    integer :: a, i, j, k
    l = [1.0_dp - xi(1) - xi(2) - xi(3), xi(1), xi(2), xi(3)]
    ! dndl(k, a) = dN_a / dL_k, the four L taken as independent
    dndl = 0.0_dp
    do a = 1, 4
      n(a) = l(a) * (2.0_dp * l(a) - 1.0_dp)
      dndl(a, a) = 4.0_dp * l(a) - 1.0_dp
    end do
    do a = 5, 10
      i = tet10_edges(1, a)
      j = tet10_edges(2, a)
      n(a) = 4.0_dp * l(i) * l(j)
      dndl(i, a) = 4.0_dp * l(j)
      dndl(j, a) = 4.0_dp * l(i)
    end do
    ! d/dxi_k = d/dL_(k+1) - d/dL_1
    do k = 1, 3
      dn(k, 1:10) = dndl(k + 1, :) - dndl(1, :)
    end do
  end subroutine tet10_shape

  pure subroutine tet10_gauss_rule(self, xi, w)
    class(tet10_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :), w(:)
    call tetrahedron_rule(4, xi, w)
  end subroutine tet10_gauss_rule

  pure subroutine tet10_natural_coordinates(self, xi)
    class(tet10_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :)
    xi(:, 1:10) = node_xi
  end subroutine tet10_natural_coordinates

  pure function tet10_face_nodes(self, face) result(nodes)
    class(tet10_t), intent(in) :: self
    integer, intent(in) :: face
    integer, allocatable :: nodes(:)
    nodes = tet10_faces(:, face)
  end function tet10_face_nodes

  pure subroutine tet10_face_shape(self, face, s, n, dn)
    class(tet10_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    call tri6_face_shape(s, n, dn)
  end subroutine tet10_face_shape

  pure subroutine tet10_face_gauss_rule(self, face, s, w)
    class(tet10_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(out) :: s(:, :), w(:)
    call triangle_rule(6, s, w)
  end subroutine tet10_face_gauss_rule

end module feps_tet10
