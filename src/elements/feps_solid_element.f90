!> The abstract solid element, the solid family of the element contract (`element_t`,
!! feps_element). A concrete solid (one file each) supplies its shape functions, Gauss rules and
!! faces; everything built on them (B-matrix, stiffness, internal force, Gauss-point strains,
!! stresses and coordinates, Jacobian checks, face integration, volume) lives here once.
!!
!! Conventions:
!! - Voigt order [xx, yy, zz, yz, xz, xy] with engineering shear strains (gamma = 2 eps);
!!   stress tension positive.
!! - Element DOF order u1x, u1y, u1z, u2x, ...; `xe(3, nen)` holds the node coordinates.
!! - Faces: `face_nodes(face)` lists the face's nodes counter-clockwise seen from outside, so that
!!   with the face-local coordinates the normal dx/ds1 x dx/ds2 points out of the element. A
!!   quadrilateral face has s1 from face node 1 towards 2 and s2 from 1 towards 4, both in
!!   [-1, 1]; a triangular face has the area coordinates (s1, s2) = (L2, L3), s1 from face node 1
!!   towards 2 and s2 from 1 towards 3. Faces of one element may differ (a wedge has triangles
!!   and quadrilaterals), so the face counts, shape functions and rules take the face number.
module feps_solid_element
  use feps_kinds, only: dp
  use feps_element, only: element_t
  implicit none
  private

  public :: voigt_size, fill_b

  integer, parameter :: voigt_size = 6   !! components of strain and stress

  !> A solid: 3 DOFs per node, the six Voigt components at each Gauss point.
  type, abstract, extends(element_t), public :: solid_element_t
  contains
    ! supplied by each solid (and nnodes, element_type of the element contract)
    procedure(count_interface), deferred :: ngauss          !! Gauss points of the volume rule
    procedure(shape_interface), deferred :: shape           !! N(xi) and dN/dxi
    procedure(rule_interface), deferred :: gauss_rule       !! volume Gauss points and weights
    procedure(nodes_xi_interface), deferred :: natural_coordinates  !! xi of every node
    procedure(count_interface), deferred :: nfaces          !! faces of the element
    procedure(face_count_interface), deferred :: nface_nodes  !! nodes of a face
    procedure(face_nodes_interface), deferred :: face_nodes !! local node numbers of a face (outward order)
    procedure(face_shape_interface), deferred :: face_shape !! a face's shape functions N(s), dN/ds
    procedure(face_count_interface), deferred :: nface_gauss  !! Gauss points of a face's rule
    procedure(face_rule_interface), deferred :: face_gauss_rule  !! a face's Gauss points and weights
    ! the element contract, common to every solid
    procedure :: npoints => solid_npoints
    procedure :: ncomp => solid_ncomp
    procedure :: ndim => solid_ndim
    procedure :: stiffness
    procedure :: internal_force
    procedure :: strains
    procedure :: point_coordinates
    procedure :: point_weights
    procedure :: min_jacobian
    ! common to every solid
    procedure :: shape_gradients
    procedure :: b_matrix
    procedure :: gauss_stresses
    procedure :: jacobian_range
    procedure :: face_integration
    procedure :: volume
    procedure :: body_force => solid_body_force
    procedure :: stresses_of_tensors => solid_stresses_of_tensors
  end type solid_element_t

  abstract interface
    pure integer function count_interface(self)
      import :: solid_element_t
      class(solid_element_t), intent(in) :: self
    end function count_interface

    !> A count (nodes, Gauss points) of face `face`.
    pure integer function face_count_interface(self, face)
      import :: solid_element_t
      class(solid_element_t), intent(in) :: self
      integer, intent(in) :: face
    end function face_count_interface

    !> Shape functions `n(nen)` and their derivatives `dn(3, nen)` (d/dxi_i) at `xi`.
    pure subroutine shape_interface(self, xi, n, dn)
      import :: solid_element_t, dp
      class(solid_element_t), intent(in) :: self
      real(dp), intent(in) :: xi(3)
      real(dp), intent(out) :: n(:), dn(:, :)
    end subroutine shape_interface

    !> Volume rule: points `xi(3, ngauss)` and weights `w(ngauss)`.
    pure subroutine rule_interface(self, xi, w)
      import :: solid_element_t, dp
      class(solid_element_t), intent(in) :: self
      real(dp), intent(out) :: xi(:, :), w(:)
    end subroutine rule_interface

    !> Natural coordinates `xi(3, nen)` of the nodes.
    pure subroutine nodes_xi_interface(self, xi)
      import :: solid_element_t, dp
      class(solid_element_t), intent(in) :: self
      real(dp), intent(out) :: xi(:, :)
    end subroutine nodes_xi_interface

    !> Local node numbers of face `face`, ordered so that the face normal points outwards.
    pure function face_nodes_interface(self, face) result(nodes)
      import :: solid_element_t
      class(solid_element_t), intent(in) :: self
      integer, intent(in) :: face
      integer, allocatable :: nodes(:)
    end function face_nodes_interface

    !> Shape functions `n(nface_nodes(face))` of face `face` and their derivatives
    !! `dn(2, nface_nodes(face))` at face point `s`.
    pure subroutine face_shape_interface(self, face, s, n, dn)
      import :: solid_element_t, dp
      class(solid_element_t), intent(in) :: self
      integer, intent(in) :: face
      real(dp), intent(in) :: s(2)
      real(dp), intent(out) :: n(:), dn(:, :)
    end subroutine face_shape_interface

    !> Rule of face `face`: points `s(2, nface_gauss(face))` and weights `w(nface_gauss(face))`.
    pure subroutine face_rule_interface(self, face, s, w)
      import :: solid_element_t, dp
      class(solid_element_t), intent(in) :: self
      integer, intent(in) :: face
      real(dp), intent(out) :: s(:, :), w(:)
    end subroutine face_rule_interface
  end interface

contains

  !> Integration points of a solid: the Gauss points of its volume rule.
  pure integer function solid_npoints(self)
    class(solid_element_t), intent(in) :: self
    solid_npoints = self%ngauss()
  end function solid_npoints

  !> Components of strain and stress per point: the six Voigt components.
  pure integer function solid_ncomp(self)
    class(solid_element_t), intent(in) :: self
    solid_ncomp = voigt_size
  end function solid_ncomp

  !> Spatial dimension: 3 (a plane-strain solid overrides it with 2).
  pure integer function solid_ndim(self)
    class(solid_element_t), intent(in) :: self
    solid_ndim = 3
  end function solid_ndim

  !> Shape functions `n(nen)`, their global derivatives `dndx(3, nen)` (d/dx, d/dy, d/dz) and the
  !! Jacobian determinant at natural point `xi`. With detj = 0 (singular mapping) the derivatives
  !! are returned as zero.
  pure subroutine shape_gradients(self, xe, xi, n, dndx, detj)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nen) node coordinates
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: n(:)        !! (nen)
    real(dp), intent(out) :: dndx(:, :)  !! (3, nen)
    real(dp), intent(out) :: detj
    real(dp) :: dn(3, size(xe, 2)), jac(3, 3), inv(3, 3)
    integer :: a
    call self%shape(xi, n, dn)
    ! jac(i, j) = d x_j / d xi_i
    jac = 0.0_dp
    do a = 1, size(xe, 2)
      jac(:, 1) = jac(:, 1) + dn(:, a) * xe(1, a)
      jac(:, 2) = jac(:, 2) + dn(:, a) * xe(2, a)
      jac(:, 3) = jac(:, 3) + dn(:, a) * xe(3, a)
    end do
    inv(1, 1) = jac(2, 2) * jac(3, 3) - jac(2, 3) * jac(3, 2)
    inv(2, 1) = jac(2, 3) * jac(3, 1) - jac(2, 1) * jac(3, 3)
    inv(3, 1) = jac(2, 1) * jac(3, 2) - jac(2, 2) * jac(3, 1)
    inv(1, 2) = jac(1, 3) * jac(3, 2) - jac(1, 2) * jac(3, 3)
    inv(2, 2) = jac(1, 1) * jac(3, 3) - jac(1, 3) * jac(3, 1)
    inv(3, 2) = jac(1, 2) * jac(3, 1) - jac(1, 1) * jac(3, 2)
    inv(1, 3) = jac(1, 2) * jac(2, 3) - jac(1, 3) * jac(2, 2)
    inv(2, 3) = jac(1, 3) * jac(2, 1) - jac(1, 1) * jac(2, 3)
    inv(3, 3) = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    detj = jac(1, 1) * inv(1, 1) + jac(1, 2) * inv(2, 1) + jac(1, 3) * inv(3, 1)
    if (abs(detj) <= tiny(detj)) then
      dndx = 0.0_dp
      return
    end if
    ! dN/dx = J^{-1} dN/dxi
    inv = inv / detj
    do a = 1, size(xe, 2)
      dndx(:, a) = inv(:, 1) * dn(1, a) + inv(:, 2) * dn(2, a) + inv(:, 3) * dn(3, a)
    end do
  end subroutine shape_gradients

  !> Fill the strain-displacement matrix `b(6, 3 nen)` from global derivatives `dndx(3, nen)`.
  pure subroutine fill_b(dndx, b)
    real(dp), intent(in) :: dndx(:, :)
    real(dp), intent(out) :: b(:, :)
    integer :: a, c
    b = 0.0_dp
    do a = 1, size(dndx, 2)
      c = 3 * (a - 1)
      b(1, c + 1) = dndx(1, a)
      b(2, c + 2) = dndx(2, a)
      b(3, c + 3) = dndx(3, a)
      b(4, c + 2) = dndx(3, a)
      b(4, c + 3) = dndx(2, a)
      b(5, c + 1) = dndx(3, a)
      b(5, c + 3) = dndx(1, a)
      b(6, c + 1) = dndx(2, a)
      b(6, c + 2) = dndx(1, a)
    end do
  end subroutine fill_b

  !> Strain-displacement matrix `b(6, 3 nen)` at `xi` (eps = B u, engineering shears) and the
  !! Jacobian determinant there.
  pure subroutine b_matrix(self, xe, xi, b, detj)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)   !! (3, nen)
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: b(:, :)   !! (6, 3 nen)
    real(dp), intent(out) :: detj
    real(dp) :: n(size(xe, 2)), dndx(3, size(xe, 2))
    call self%shape_gradients(xe, xi, n, dndx, detj)
    call fill_b(dndx, b)
  end subroutine b_matrix

  !> Element stiffness `ke(3 nen, 3 nen)` = sum over Gauss points of B^T D B detJ w, with the
  !! material matrix `d(6, 6, ngauss)` of each point (need not be symmetric). size(d, 3) must be
  !! ngauss() (it sizes the Gauss rule). A non-positive Jacobian is the caller's to reject
  !! (min_jacobian, before any stiffness).
  pure subroutine stiffness(self, xe, d, ke)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)      !! (3, nen)
    real(dp), intent(in) :: d(:, :, :)    !! (6, 6, ngauss)
    real(dp), intent(out) :: ke(:, :)     !! (3 nen, 3 nen)
    integer :: g, a, col, r
    real(dp) :: xi(3, size(d, 3)), w(size(d, 3))
    real(dp) :: n(size(xe, 2)), dndx(3, size(xe, 2)), db(6, 3 * size(xe, 2))
    real(dp) :: detj, dv, nx, ny, nz
    call self%gauss_rule(xi, w)
    ke = 0.0_dp
    do g = 1, size(w)
      call self%shape_gradients(xe, xi(:, g), n, dndx, detj)
      dv = detj * w(g)
      ! D B, using the sparsity of B (three nonzeros per column)
      do a = 1, size(xe, 2)
        nx = dndx(1, a)
        ny = dndx(2, a)
        nz = dndx(3, a)
        col = 3 * (a - 1)
        db(:, col + 1) = (d(:, 1, g) * nx + d(:, 6, g) * ny + d(:, 5, g) * nz) * dv
        db(:, col + 2) = (d(:, 2, g) * ny + d(:, 6, g) * nx + d(:, 4, g) * nz) * dv
        db(:, col + 3) = (d(:, 3, g) * nz + d(:, 4, g) * ny + d(:, 5, g) * nx) * dv
      end do
      ! B^T (D B), again three nonzeros per row of B^T
      do col = 1, size(db, 2)
        do a = 1, size(xe, 2)
          nx = dndx(1, a)
          ny = dndx(2, a)
          nz = dndx(3, a)
          r = 3 * (a - 1)
          ke(r + 1, col) = ke(r + 1, col) + nx * db(1, col) + ny * db(6, col) + nz * db(5, col)
          ke(r + 2, col) = ke(r + 2, col) + ny * db(2, col) + nx * db(6, col) + nz * db(4, col)
          ke(r + 3, col) = ke(r + 3, col) + nz * db(3, col) + ny * db(4, col) + nx * db(5, col)
        end do
      end do
    end do
  end subroutine stiffness

  !> Internal nodal forces `fe(3 nen)` = sum over the Gauss points of B^T sig detJ w, with the
  !! stresses `sig(6, ngauss)` of each point (size(sig, 2) sizes the Gauss rule).
  pure subroutine internal_force(self, xe, sig, fe)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nen)
    real(dp), intent(in) :: sig(:, :)    !! (6, ngauss)
    real(dp), intent(out) :: fe(:)       !! (3 nen)
    real(dp) :: xi(3, size(sig, 2)), w(size(sig, 2)), b(6, 3 * size(xe, 2)), detj
    integer :: q
    call self%gauss_rule(xi, w)
    fe = 0.0_dp
    do q = 1, size(sig, 2)
      call self%b_matrix(xe, xi(:, q), b, detj)
      fe = fe + matmul(sig(:, q), b) * (w(q) * detj)
    end do
  end subroutine internal_force

  !> Strains `eps(6, ngauss)` = B ue at the Gauss points (Voigt, engineering shears).
  pure subroutine strains(self, xe, ue, eps)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nen)
    real(dp), intent(in) :: ue(:)        !! (3 nen)
    real(dp), intent(out) :: eps(:, :)   !! (6, ngauss)
    integer :: g, a
    real(dp) :: xi(3, size(eps, 2)), w(size(eps, 2))
    real(dp) :: n(size(xe, 2)), dndx(3, size(xe, 2)), grad(3, 3), detj
    call self%gauss_rule(xi, w)
    do g = 1, size(w)
      call self%shape_gradients(xe, xi(:, g), n, dndx, detj)
      ! grad(i, j) = d u_i / d x_j
      grad = 0.0_dp
      do a = 1, size(xe, 2)
        grad(:, 1) = grad(:, 1) + ue(3 * a - 2:3 * a) * dndx(1, a)
        grad(:, 2) = grad(:, 2) + ue(3 * a - 2:3 * a) * dndx(2, a)
        grad(:, 3) = grad(:, 3) + ue(3 * a - 2:3 * a) * dndx(3, a)
      end do
      eps(1, g) = grad(1, 1)
      eps(2, g) = grad(2, 2)
      eps(3, g) = grad(3, 3)
      eps(4, g) = grad(2, 3) + grad(3, 2)
      eps(5, g) = grad(1, 3) + grad(3, 1)
      eps(6, g) = grad(1, 2) + grad(2, 1)
    end do
  end subroutine strains

  !> Linear elastic stresses `sig(6, ngauss)` = D B ue at the Gauss points.
  pure subroutine gauss_stresses(self, xe, ue, d, sig)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)      !! (3, nen)
    real(dp), intent(in) :: ue(:)         !! (3 nen)
    real(dp), intent(in) :: d(:, :, :)    !! (6, 6, ngauss)
    real(dp), intent(out) :: sig(:, :)    !! (6, ngauss)
    real(dp) :: eps(6, size(sig, 2))
    integer :: g, k
    call self%strains(xe, ue, eps)
    do g = 1, size(sig, 2)
      sig(:, g) = 0.0_dp
      do k = 1, 6
        sig(:, g) = sig(:, g) + d(:, k, g) * eps(k, g)
      end do
    end do
  end subroutine gauss_stresses

  !> Global coordinates `xg(3, ngauss)` of the Gauss points.
  pure subroutine point_coordinates(self, xe, xg)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)    !! (3, nen)
    real(dp), intent(out) :: xg(:, :)   !! (3, ngauss)
    integer :: g
    real(dp) :: xi(3, size(xg, 2)), w(size(xg, 2)), n(size(xe, 2)), dn(3, size(xe, 2))
    integer :: a
    call self%gauss_rule(xi, w)
    do g = 1, size(w)
      call self%shape(xi(:, g), n, dn)
      xg(:, g) = 0.0_dp
      do a = 1, size(xe, 2)
        xg(:, g) = xg(:, g) + xe(:, a) * n(a)
      end do
    end do
  end subroutine point_coordinates

  !> Smallest and largest Jacobian determinant over the Gauss points and the nodes (mesh check:
  !! a valid element has min_detj > 0).
  pure subroutine jacobian_range(self, xe, min_detj, max_detj)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)   !! (3, nen)
    real(dp), intent(out) :: min_detj, max_detj
    real(dp) :: xig(3, self%ngauss()), w(self%ngauss()), xin(3, size(xe, 2))
    real(dp) :: n(size(xe, 2)), dndx(3, size(xe, 2)), detj
    integer :: k
    call self%gauss_rule(xig, w)
    call self%natural_coordinates(xin)
    min_detj = huge(1.0_dp)
    max_detj = -huge(1.0_dp)
    do k = 1, size(w)
      call self%shape_gradients(xe, xig(:, k), n, dndx, detj)
      min_detj = min(min_detj, detj)
      max_detj = max(max_detj, detj)
    end do
    do k = 1, size(xe, 2)
      call self%shape_gradients(xe, xin(:, k), n, dndx, detj)
      min_detj = min(min_detj, detj)
      max_detj = max(max_detj, detj)
    end do
  end subroutine jacobian_range

  !> The smallest Jacobian determinant over the Gauss points and the nodes (jacobian_range's
  !! min_detj): the element contract's mesh check, <= 0 for an inverted or degenerate element.
  pure real(dp) function min_jacobian(self, xe)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)   !! (3, nen)
    real(dp) :: max_detj
    call self%jacobian_range(xe, min_jacobian, max_detj)
  end function min_jacobian

  !> For every Gauss point of face `face`: global position `xg(3, :)`, unit outward normal
  !! `normal(3, :)`, weight times surface Jacobian `wda(:)` and face shape functions
  !! `nf(nface_nodes(face), :)` (in the order of `face_nodes(face)`). Consistent nodal forces of a
  !! traction t(x) are then f_a = sum_g nf(a, g) t(xg(:, g)) wda(g).
  pure subroutine face_integration(self, xe, face, xg, normal, wda, nf)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)       !! (3, nen)
    integer, intent(in) :: face
    real(dp), intent(out) :: xg(:, :)      !! (3, nface_gauss(face))
    real(dp), intent(out) :: normal(:, :)  !! (3, nface_gauss(face))
    real(dp), intent(out) :: wda(:)        !! (nface_gauss(face))
    real(dp), intent(out) :: nf(:, :)      !! (nface_nodes(face), nface_gauss(face))
    real(dp) :: s(2, size(wda)), w(size(wda)), dnf(2, size(nf, 1)), xf(3, size(nf, 1))
    real(dp) :: t1(3), t2(3), c(3), da
    integer :: g, a
    xf = xe(:, self%face_nodes(face))
    call self%face_gauss_rule(face, s, w)
    do g = 1, size(w)
      call self%face_shape(face, s(:, g), nf(:, g), dnf)
      xg(:, g) = 0.0_dp
      t1 = 0.0_dp
      t2 = 0.0_dp
      do a = 1, size(xf, 2)
        xg(:, g) = xg(:, g) + xf(:, a) * nf(a, g)
        t1 = t1 + xf(:, a) * dnf(1, a)
        t2 = t2 + xf(:, a) * dnf(2, a)
      end do
      c(1) = t1(2) * t2(3) - t1(3) * t2(2)
      c(2) = t1(3) * t2(1) - t1(1) * t2(3)
      c(3) = t1(1) * t2(2) - t1(2) * t2(1)
      da = norm2(c)
      if (da > 0.0_dp) then
        normal(:, g) = c / da
      else
        normal(:, g) = 0.0_dp
      end if
      wda(g) = w(g) * da
    end do
  end subroutine face_integration

  !> detJ w at each Gauss point: the volume it stands for (a plane-strain solid: the area of a
  !! unit-thick slice, through its own shape_gradients).
  pure subroutine point_weights(self, xe, w)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)   !! (3, nen)
    real(dp), intent(out) :: w(:)      !! (ngauss)
    real(dp) :: xi(3, self%ngauss()), n(size(xe, 2)), dndx(3, size(xe, 2)), detj
    integer :: g
    call self%gauss_rule(xi, w)
    do g = 1, size(w)
      call self%shape_gradients(xe, xi(:, g), n, dndx, detj)
      w(g) = detj * w(g)
    end do
  end subroutine point_weights

  !> Volume of the element (sum of detJ w over the volume rule).
  pure real(dp) function volume(self, xe)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)   !! (3, nen)
    real(dp) :: w(self%ngauss())
    integer :: g
    call self%point_weights(xe, w)
    volume = 0.0_dp
    do g = 1, size(w)
      volume = volume + w(g)
    end do
  end function volume

  !> Consistent nodal forces of the uniform force `b(3)` per unit volume: the sum over the
  !! volume rule of N_a b detJ w (the rule of the stiffness, exact for a straight-sided element's
  !! polynomial N detJ).
  pure subroutine solid_body_force(self, xe, b, fe)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nen)
    real(dp), intent(in) :: b(3)
    real(dp), intent(out) :: fe(:)       !! (3 nen)
    real(dp) :: xi(3, self%ngauss()), w(self%ngauss()), n(size(xe, 2)), dndx(3, size(xe, 2)), detj
    integer :: g, a
    call self%gauss_rule(xi, w)
    fe = 0.0_dp
    do g = 1, size(w)
      call self%shape_gradients(xe, xi(:, g), n, dndx, detj)
      do a = 1, size(n)
        fe(3 * a - 2:3 * a) = fe(3 * a - 2:3 * a) + n(a) * detj * w(g) * b
      end do
    end do
    if (self%ndim() == 2) fe(3::3) = 0.0_dp   ! plane strain: uz is held
  end subroutine solid_body_force

  !> Voigt stresses [xx yy zz yz xz xy] of the Cartesian tensors given at the Gauss points.
  pure subroutine solid_stresses_of_tensors(self, xe, tensors, sig, taken)
    class(solid_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)          !! (3, nen)
    real(dp), intent(in) :: tensors(:, :, :)  !! (3, 3, ngauss)
    real(dp), intent(out) :: sig(:, :)        !! (6, ngauss)
    logical, intent(out) :: taken
    integer :: g
    do g = 1, size(sig, 2)
      sig(:, g) = [tensors(1, 1, g), tensors(2, 2, g), tensors(3, 3, g), tensors(2, 3, g), tensors(1, 3, g), &
                   tensors(1, 2, g)]
    end do
    taken = .true.
  end subroutine solid_stresses_of_tensors

end module feps_solid_element
