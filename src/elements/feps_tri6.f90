!> The 6-node quadratic plane-strain triangle (unit thickness), for 2D models inside feps's 3D
!! machinery: coordinates `xe(3, 6)` with z = 0, three DOFs per node (u1x, u1y, u1z, u2x, ...)
!! whose z DOFs get zero columns in B (the analysis holds uz = 0), and the six Voigt components
!! [xx yy zz yz xz xy] with eps_zz = gamma_yz = gamma_xz = 0. The material is the ordinary 3D one,
!! so sigma_zz comes out of D. Stiffness, internal forces, area and edge weights are per unit
!! thickness.
!!
!! Nodes: corners 1, 2, 3 counter-clockwise seen from +z, then the mid-side nodes 4 (1-2),
!! 5 (2-3), 6 (3-1). Natural coordinates (s1, s2) = (L2, L3), L1 = 1 - s1 - s2; xi(3) is
!! ignored on input and zero on output.
!! Rules (triangle_rule of feps_gauss): 3-point (degree 2, the default) or 6-point (degree 4,
!! `six_point = .true.`).
!! "Faces" are the edges 1: (1 2 4), 2: (2 3 5), 3: (3 1 6) (corner, corner, mid-side), each a
!! 3-node quadratic line with face coordinate s1 in [-1, 1] (s2 ignored) and 3-point Gauss;
!! the normal is the outward in-plane one of a counter-clockwise element.
module feps_tri6
  use feps_kinds, only: dp
  use feps_gauss, only: gauss_legendre, triangle_rule
  use feps_solid_element, only: solid_element_t
  use feps_face_shapes, only: quadratic_triangle => tri6_face_shape
  implicit none
  private

  !> Natural coordinates (s1, s2, 0) of the nodes, one column per node.
  real(dp), parameter :: node_xi(3, 6) = reshape([ &
    0.0_dp, 0.0_dp, 0.0_dp,  1.0_dp, 0.0_dp, 0.0_dp,  0.0_dp, 1.0_dp, 0.0_dp, &
    0.5_dp, 0.0_dp, 0.0_dp,  0.5_dp, 0.5_dp, 0.0_dp,  0.0_dp, 0.5_dp, 0.0_dp], [3, 6])

  !> Nodes of each edge (columns): start corner, end corner (counter-clockwise), mid-side node.
  integer, parameter :: tri6_edges(3, 3) = reshape([1, 2, 4,  2, 3, 5,  3, 1, 6], [3, 3])

  !> Plane-strain 6-node triangle; `six_point` selects the 6-point rule instead of 3 points.
  type, extends(solid_element_t), public :: tri6_t
    logical :: six_point = .false.
  contains
    procedure :: nnodes => tri6_nnodes
    procedure :: ngauss => tri6_ngauss
    procedure :: shape => tri6_shape
    procedure :: gauss_rule => tri6_gauss_rule
    procedure :: natural_coordinates => tri6_natural_coordinates
    procedure :: nfaces => tri6_nfaces
    procedure :: nface_nodes => tri6_nface_nodes
    procedure :: face_nodes => tri6_face_nodes
    procedure :: face_shape => tri6_face_shape
    procedure :: nface_gauss => tri6_nface_gauss
    procedure :: face_gauss_rule => tri6_face_gauss_rule
    procedure :: element_type => tri6_element_type
    ! the 3D versions of solid_element_t replaced by their plane-strain forms; jacobian_range,
    ! min_jacobian, volume, internal_force, gauss_stresses and point_coordinates of
    ! solid_element_t work through these
    procedure :: ndim => tri6_ndim
    procedure :: shape_gradients => tri6_shape_gradients
    procedure :: b_matrix => tri6_b_matrix
    procedure :: stiffness => tri6_stiffness
    procedure :: strains => tri6_strains
    procedure :: face_integration => tri6_face_integration
  end type tri6_t

contains

  pure integer function tri6_nnodes(self)
    class(tri6_t), intent(in) :: self
    tri6_nnodes = 6
  end function tri6_nnodes

  !> 2: a plane-strain type (its element contract still has 3 DOFs per node, uz held).
  pure integer function tri6_ndim(self)
    class(tri6_t), intent(in) :: self
    tri6_ndim = 2
  end function tri6_ndim

  pure integer function tri6_ngauss(self)
    class(tri6_t), intent(in) :: self
    tri6_ngauss = merge(6, 3, self%six_point)
  end function tri6_ngauss

  pure integer function tri6_nfaces(self)
    class(tri6_t), intent(in) :: self
    tri6_nfaces = 3
  end function tri6_nfaces

  pure integer function tri6_nface_nodes(self, face)
    class(tri6_t), intent(in) :: self
    integer, intent(in) :: face
    tri6_nface_nodes = 3
  end function tri6_nface_nodes

  pure integer function tri6_nface_gauss(self, face)
    class(tri6_t), intent(in) :: self
    integer, intent(in) :: face
    tri6_nface_gauss = 3
  end function tri6_nface_gauss

  pure function tri6_element_type(self) result(name)
    class(tri6_t), intent(in) :: self
    character(len=:), allocatable :: name
    if (self%six_point) then
      name = 'tri6-6'
    else
      name = 'tri6'
    end if
  end function tri6_element_type

  !> Quadratic triangle (feps_face_shapes' 6-node triangle in the plane); dn(3, :) = 0.
  pure subroutine tri6_shape(self, xi, n, dn)
    class(tri6_t), intent(in) :: self
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:), dn(:, :)
    call quadratic_triangle(xi(1:2), n, dn(1:2, :))
    dn(3, 1:6) = 0.0_dp
  end subroutine tri6_shape

  !> Points `xi(3, ngauss)` (xi(3, :) = 0) and weights summing to 1/2, the reference area.
  pure subroutine tri6_gauss_rule(self, xi, w)
    class(tri6_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :), w(:)
    xi = 0.0_dp
    call triangle_rule(merge(6, 3, self%six_point), xi(1:2, :), w)
  end subroutine tri6_gauss_rule

  pure subroutine tri6_natural_coordinates(self, xi)
    class(tri6_t), intent(in) :: self
    real(dp), intent(out) :: xi(:, :)
    xi(:, 1:6) = node_xi
  end subroutine tri6_natural_coordinates

  pure function tri6_face_nodes(self, face) result(nodes)
    class(tri6_t), intent(in) :: self
    integer, intent(in) :: face
    integer, allocatable :: nodes(:)
    nodes = tri6_edges(:, face)
  end function tri6_face_nodes

  !> Quadratic line on s1 in [-1, 1]: ends at -1 and +1, mid-side node at 0; dn(2, :) = 0.
  pure subroutine tri6_face_shape(self, face, s, n, dn)
    class(tri6_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    n(1:3) = [0.5_dp * s(1) * (s(1) - 1.0_dp), 0.5_dp * s(1) * (s(1) + 1.0_dp), 1.0_dp - s(1)**2]
    dn(1, 1:3) = [s(1) - 0.5_dp, s(1) + 0.5_dp, -2.0_dp * s(1)]
    dn(2, 1:3) = 0.0_dp
  end subroutine tri6_face_shape

  !> 3-point Gauss-Legendre along the edge: `s(1, :)` the points, `s(2, :)` = 0.
  pure subroutine tri6_face_gauss_rule(self, face, s, w)
    class(tri6_t), intent(in) :: self
    integer, intent(in) :: face
    real(dp), intent(out) :: s(:, :), w(:)
    s = 0.0_dp
    call gauss_legendre(3, s(1, :), w)
  end subroutine tri6_face_gauss_rule

  !> Shape functions, global derivatives `dndx(3, 6)` (row 3, d/dz, is zero) and the in-plane
  !! Jacobian determinant (positive for a counter-clockwise element) at `xi`; with detj = 0 the
  !! derivatives are zero.
  pure subroutine tri6_shape_gradients(self, xe, xi, n, dndx, detj)
    class(tri6_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, 6) node coordinates, z ignored
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:)        !! (6)
    real(dp), intent(out) :: dndx(:, :)  !! (3, 6)
    real(dp), intent(out) :: detj
    real(dp) :: dn(3, size(xe, 2)), jac(2, 2)
    integer :: a
    call self%shape(xi, n, dn)
    ! jac(i, j) = d x_j / d s_i
    jac(:, 1) = matmul(dn(1:2, :), xe(1, :))
    jac(:, 2) = matmul(dn(1:2, :), xe(2, :))
    detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    dndx = 0.0_dp
    if (abs(detj) <= tiny(detj)) return
    do a = 1, size(xe, 2)
      dndx(1, a) = (jac(2, 2) * dn(1, a) - jac(1, 2) * dn(2, a)) / detj
      dndx(2, a) = (jac(1, 1) * dn(2, a) - jac(2, 1) * dn(1, a)) / detj
    end do
  end subroutine tri6_shape_gradients

  !> Plane-strain B `b(6, 18)`: rows xx, yy and xy only; the z-DOF columns are zero.
  pure subroutine tri6_b_matrix(self, xe, xi, b, detj)
    class(tri6_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)   !! (3, 6)
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: b(:, :)   !! (6, 18)
    real(dp), intent(out) :: detj
    real(dp) :: n(size(xe, 2)), dndx(3, size(xe, 2))
    integer :: a, c
    call self%shape_gradients(xe, xi, n, dndx, detj)
    b = 0.0_dp
    do a = 1, size(xe, 2)
      c = 3 * (a - 1)
      b(1, c + 1) = dndx(1, a)
      b(2, c + 2) = dndx(2, a)
      b(6, c + 1) = dndx(2, a)
      b(6, c + 2) = dndx(1, a)
    end do
  end subroutine tri6_b_matrix

  !> Stiffness per unit thickness `ke(18, 18)` = sum B^T D B detJ w with the plane-strain B, so
  !! only D(xx|yy|xy, xx|yy|xy) enters and the z rows and columns are zero; size(d, 3) must be
  !! ngauss().
  pure subroutine tri6_stiffness(self, xe, d, ke)
    class(tri6_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)      !! (3, 6)
    real(dp), intent(in) :: d(:, :, :)    !! (6, 6, ngauss)
    real(dp), intent(out) :: ke(:, :)     !! (18, 18)
    integer, parameter :: plane(3) = [1, 2, 6]   ! Voigt rows of B that are not zero
    real(dp) :: xi(3, size(d, 3)), w(size(d, 3)), b(6, 3 * size(xe, 2)), db(3, 3 * size(xe, 2))
    real(dp) :: detj
    integer :: g
    call self%gauss_rule(xi, w)
    ke = 0.0_dp
    do g = 1, size(w)
      call self%b_matrix(xe, xi(:, g), b, detj)
      db = matmul(d(plane, plane, g), b(plane, :)) * (detj * w(g))
      ke = ke + matmul(transpose(b(plane, :)), db)
    end do
  end subroutine tri6_stiffness

  !> Plane-strain strains `eps(6, ngauss)` = B ue: eps_zz = gamma_yz = gamma_xz = 0.
  pure subroutine tri6_strains(self, xe, ue, eps)
    class(tri6_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, 6)
    real(dp), intent(in) :: ue(:)        !! (18)
    real(dp), intent(out) :: eps(:, :)   !! (6, ngauss)
    real(dp) :: xi(3, size(eps, 2)), w(size(eps, 2)), b(6, 3 * size(xe, 2)), detj
    integer :: g
    call self%gauss_rule(xi, w)
    do g = 1, size(w)
      call self%b_matrix(xe, xi(:, g), b, detj)
      eps(:, g) = matmul(b, ue)
    end do
  end subroutine tri6_strains

  !> For every Gauss point of edge `face`: position `xg(3, 3)`, unit outward in-plane normal
  !! `normal(3, 3)` (z component 0), `wda` = weight * |dx/ds| * unit thickness and the edge
  !! shape functions `nf(3, 3)` (order of face_nodes(face)).
  pure subroutine tri6_face_integration(self, xe, face, xg, normal, wda, nf)
    class(tri6_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)       !! (3, 6)
    integer, intent(in) :: face
    real(dp), intent(out) :: xg(:, :)      !! (3, 3)
    real(dp), intent(out) :: normal(:, :)  !! (3, 3)
    real(dp), intent(out) :: wda(:)        !! (3)
    real(dp), intent(out) :: nf(:, :)      !! (3, 3)
    real(dp) :: s(2, size(wda)), w(size(wda)), dnf(2, size(nf, 1)), xf(3, size(nf, 1)), t(3), dl
    integer :: g
    xf = xe(:, tri6_edges(:, face))
    call self%face_gauss_rule(face, s, w)
    do g = 1, size(w)
      call self%face_shape(face, s(:, g), nf(:, g), dnf)
      xg(:, g) = matmul(xf, nf(:, g))
      t = matmul(xf, dnf(1, :))
      dl = hypot(t(1), t(2))
      ! the interior lies left of a counter-clockwise edge: the outward normal is t turned clockwise
      if (dl > 0.0_dp) then
        normal(:, g) = [t(2), -t(1), 0.0_dp] / dl
      else
        normal(:, g) = 0.0_dp
      end if
      wda(g) = w(g) * dl
    end do
  end subroutine tri6_face_integration

end module feps_tri6
