!> Zero-thickness interface elements (thesis section 2.3.1): two layers of nodes, the LOWER layer
!! first (nodes 1..p), then the UPPER layer in the same order (nodes p+1..2p); pair i is (i, p+i).
!! Geometry (shape, local frame, Jacobian) comes from the lower layer only; for a zero-thickness
!! element the layers coincide.
!!
!! Shapes (natural coordinates s):
!! - 'interface-quad4': 4 pairs, bilinear (thesis eq. 2.3.2), s in [-1, 1]^2, corners
!!   (-1,-1), (1,-1), (1,1), (-1,1).
!! - 'interface-quad8': 8 pairs, serendipity: the 4 corners as quad4, then the mid-edges of edges
!!   1-2, 2-3, 3-4, 4-1.
!! - 'interface-tri3': 3 pairs, linear; s = (L2, L3), L1 = 1 - s1 - s2; corners (0,0), (1,0), (0,1).
!! - 'interface-tri6': 6 pairs: 3 corners, then the mid-edges of edges 1-2, 2-3, 3-1.
!! - 'interface-line2' (2D, plane strain): 2 pairs, linear, s1 in [-1, 1].
!! - 'interface-line3' (2D): 3 pairs: the two ends, then the middle; quadratic.
!!
!! Integration rules. Default (Gauss): exact for the pair stiffness B^T D B of a flat element
!! with an affine mapping and constant D (degree 2 per direction for linear shapes, 4 for
!! quadratic ones):
!! - quad4: 2x2 Gauss-Legendre; quad8: 3x3 Gauss-Legendre;
!! - tri3: 3 interior points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3), weights A/3 (degree 2);
!! - tri6: 6-point symmetric rule of degree 4 (Strang-Fix / Dunavant), points (a, a), (1-2a, a),
!!   (a, 1-2a) and the same with b;
!! - line2: 2-point Gauss-Legendre; line3: 3-point Gauss-Legendre.
!! Nodal ('-nodal' suffix; Newton-Cotes / Lobatto), points at the nodes of one layer, known to
!! avoid spurious oscillation of the tractions at stiff interfaces:
!! - quad4: 2x2 Lobatto (the 4 corners, weights A/4 for a parallelogram);
!! - quad8: 3x3 Lobatto (Simpson): the 8 nodes in node order, then the centre (weights 1/9,
!!   4/9 and 16/9 of the reference area 4). The centre point couples all pairs.
!! - tri3: the 3 vertices, weights A/3; tri6: the 3 mid-edge points, weights A/3 (exact for
!!   quadratics; the corner pairs get no stiffness from this element);
!! - line2: the 2 ends (2-point Lobatto); line3: Simpson, ends then middle (weights L/6, L/6, 2L/3).
!! Integration points of the nodal rules are listed in node order.
!!
!! Local frame (thesis eq. 2.3.4), rows of `frame`:
!! - 3D: e1 = dx/ds1 normalised, n = (dx/ds1 x dx/ds2) normalised, e2 = n x e1. With the lower
!!   layer numbered counter-clockwise seen from the upper side, n points from lower to upper.
!! - 2D: e1 = dx/ds1 normalised (x-y plane), n = e1 turned +90 degrees = (-e1y, e1x).
!! Strains are relative displacements UPPER minus LOWER in the local frame:
!! 3D [gamma1, gamma2, eps_n], 2D [gamma, eps_n]; eps_n > 0 is opening. B = C [-F  F]
!! (eqs. 2.3.8-2.3.10) with C = frame and F the shape functions; DOFs node by node
!! (u1x, u1y[, u1z], u2x, ...). Stresses are tractions in the same frame and order.
!!
!! The element contract (`element_t`) works with 3 DOFs per node: `stiffness`, `internal_force`,
!! `strains`, `point_coordinates` and `min_jacobian` take `xe(3, nnodes)` and `ue(3 nnodes)`. A
!! 2D (line) element embeds its x-y kernels there: zero z rows and columns, uz ignored, z = 0 at
!! its points. The kernels in the element's own dimension (ndim coordinates and DOFs per node)
!! are the `*_nd` procedures.
module feps_interface_element
  use feps_strings, only: to_lower
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_input, str
  use feps_gauss, only: gauss_legendre, square_rule
  use feps_face_shapes, only: quad4_face_shape, tri3_face_shape, tri6_face_shape
  use feps_element, only: element_t
  implicit none
  private

  public :: interface_element_t, new_interface_element, is_interface_type

  integer, parameter, public :: max_interface_pairs = 8   !! largest number of node pairs
  integer, parameter, public :: max_interface_points = 9  !! largest number of integration points

  !> Shape kinds.
  integer, parameter, public :: interface_quad4 = 1, interface_quad8 = 2, interface_tri3 = 3, &
                                interface_tri6 = 4, interface_line2 = 5, interface_line3 = 6

  integer, parameter :: nshapes = 6
  character(len=15), parameter :: shape_names(nshapes) = [character(len=15) :: &
    'interface-quad4', 'interface-quad8', 'interface-tri3', 'interface-tri6', &
    'interface-line2', 'interface-line3']
  integer, parameter :: shape_pairs(nshapes) = [4, 8, 3, 6, 2, 3]
  integer, parameter :: shape_dims(nshapes) = [3, 3, 3, 3, 2, 2]
  integer, parameter :: gauss_points(nshapes) = [4, 9, 3, 6, 2, 3]
  integer, parameter :: nodal_points(nshapes) = [4, 9, 3, 3, 2, 3]
  character(len=*), parameter :: nodal_suffix = '-nodal'

  !> Natural coordinates of the quad8 nodes (the first 4 are the quad4 nodes).
  real(dp), parameter :: quad_s(2, 8) = reshape([ &
    -1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, &
    0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp], [2, 8])

  ! 6-point degree-4 triangle rule (weights for the reference area 1/2)
  real(dp), parameter :: tri_a = 0.44594849091596488631832925388305_dp
  real(dp), parameter :: tri_b = 0.091576213509770743459571463402202_dp
  real(dp), parameter :: tri_wa = 0.11169079483900573284750350421656_dp
  real(dp), parameter :: tri_wb = 0.054975871827660933819163162450105_dp

  !> A zero-thickness interface element: its shape and its integration choice.
  type, extends(element_t) :: interface_element_t
    integer :: shape_kind = interface_quad4      !! one of the interface_* kinds
    logical :: nodal_integration = .false.       !! nodal (Newton-Cotes/Lobatto) instead of Gauss
    !> The rule's weights and the shape functions and derivatives at its points, computed once
    !! by new_interface_element: the element loops ask for them at every point of every
    !! iteration (an element made otherwise computes them each time).
    logical :: tabulated = .false.
    real(dp) :: table_w(max_interface_points) = 0.0_dp
    real(dp) :: table_n(max_interface_pairs, max_interface_points) = 0.0_dp
    real(dp) :: table_dn(2, max_interface_pairs, max_interface_points) = 0.0_dp
  contains
    ! the element contract (3 DOFs per node)
    procedure :: nnodes
    procedure :: npoints => ngauss
    procedure :: ncomp
    procedure :: ndim
    procedure :: element_type
    procedure :: stiffness
    procedure :: internal_force
    procedure :: strains
    procedure :: point_coordinates
    procedure :: point_weights
    procedure :: min_jacobian
    procedure :: jacobian_message => interface_jacobian_message
    procedure :: stresses_of_tensors => interface_stresses_of_tensors
    ! the interface family, in the element's own dimension (ndim coordinates and DOFs per node)
    procedure :: npairs
    procedure :: ngauss
    procedure :: shape
    procedure :: integration_rule
    procedure :: node_coordinates
    procedure :: point_b
    procedure :: stiffness_nd
    procedure :: internal_force_nd
    procedure :: strains_nd
    procedure :: point_coordinates_nd
    procedure :: point_weights_nd
    procedure :: area
    procedure :: min_jacobian_nd
  end type interface_element_t

contains

  !> Make an interface element from its name (case-insensitive, surrounding blanks ignored):
  !! one of the shape names above, optionally followed by '-nodal'. An unknown name returns an
  !! err_input error naming it and the known names.
  pure subroutine new_interface_element(type_name, element, error)
    character(len=*), intent(in) :: type_name
    type(interface_element_t), intent(out) :: element
    type(error_t), allocatable, intent(out) :: error
    integer :: kind
    logical :: nodal
    character(len=:), allocatable :: known
    real(dp) :: s(2, max_interface_points)
    integer :: i, g
    call parse_name(type_name, kind, nodal)
    if (kind == 0) then
      known = ''
      do i = 1, nshapes
        known = known // trim(shape_names(i)) // ', '
      end do
      call fatal_error(error, err_input, "unknown interface element type '" // trim(adjustl(type_name)) // &
                       "' (known: " // known // "each optionally with the suffix '-nodal')")
      return
    end if
    element%shape_kind = kind
    element%nodal_integration = nodal
    call element%integration_rule(s, element%table_w)
    do g = 1, element%ngauss()
      call element%shape(s(:, g), element%table_n(:, g), element%table_dn(:, :, g))
    end do
    element%tabulated = .true.
  end subroutine new_interface_element

  !> True if `name` (case-insensitive) names an interface element type, with or without '-nodal'.
  pure logical function is_interface_type(name)
    character(len=*), intent(in) :: name
    integer :: kind
    logical :: nodal
    call parse_name(name, kind, nodal)
    is_interface_type = kind /= 0
  end function is_interface_type

  !> Shape kind (0 if unknown) and nodal flag of a type name.
  pure subroutine parse_name(name, kind, nodal)
    character(len=*), intent(in) :: name
    integer, intent(out) :: kind
    logical, intent(out) :: nodal
    character(len=:), allocatable :: base
    integer :: i, nb
    base = to_lower(trim(adjustl(name)))
    nb = len(base)
    nodal = .false.
    if (nb > len(nodal_suffix)) then
      if (base(nb - len(nodal_suffix) + 1:) == nodal_suffix) then
        nodal = .true.
        base = base(:nb - len(nodal_suffix))
      end if
    end if
    kind = 0
    do i = 1, nshapes
      if (base == trim(shape_names(i))) kind = i
    end do
  end subroutine parse_name


  ! ------------------------------------------------------------------ sizes and names

  !> Number of node pairs.
  pure integer function npairs(self)
    class(interface_element_t), intent(in) :: self
    npairs = shape_pairs(self%shape_kind)
  end function npairs

  !> Number of nodes (both layers).
  pure integer function nnodes(self)
    class(interface_element_t), intent(in) :: self
    nnodes = 2 * shape_pairs(self%shape_kind)
  end function nnodes

  !> Spatial dimension: 3 for surface elements, 2 for line elements (plane strain).
  pure integer function ndim(self)
    class(interface_element_t), intent(in) :: self
    ndim = shape_dims(self%shape_kind)
  end function ndim

  !> Strain/stress components: 3 ([gamma1, gamma2, eps_n]) in 3D, 2 ([gamma, eps_n]) in 2D.
  pure integer function ncomp(self)
    class(interface_element_t), intent(in) :: self
    ncomp = shape_dims(self%shape_kind)
  end function ncomp

  !> Number of integration points of the chosen rule.
  pure integer function ngauss(self)
    class(interface_element_t), intent(in) :: self
    if (self%nodal_integration) then
      ngauss = nodal_points(self%shape_kind)
    else
      ngauss = gauss_points(self%shape_kind)
    end if
  end function ngauss

  !> The catalog's type name: the shape name, with the '-nodal' suffix for nodal integration,
  !! e.g. 'interface-quad4', 'interface-line3-nodal'.
  pure function element_type(self) result(name)
    class(interface_element_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = trim(shape_names(self%shape_kind))
    if (self%nodal_integration) name = name // nodal_suffix
  end function element_type

  ! ------------------------------------------------------------------ shape functions and rules

  !> Shape functions `n(npairs)` of one layer and their derivatives `dn(2, npairs)` (d/ds1, d/ds2;
  !! the second row is zero for line elements) at natural point `s(2)` (s(2) unused for lines).
  pure subroutine shape(self, s, n, dn)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: s(2)
    real(dp), intent(out) :: n(:), dn(:, :)
    real(dp) :: f(2), x, y
    integer :: a
    select case (self%shape_kind)
    case (interface_quad4)
      call quad4_face_shape(s, n, dn)
    case (interface_quad8)
      x = s(1)
      y = s(2)
      do a = 1, 4
        f = 1.0_dp + s * quad_s(:, a)
        n(a) = 0.25_dp * f(1) * f(2) * (f(1) + f(2) - 3.0_dp)
        dn(1, a) = 0.25_dp * quad_s(1, a) * f(2) * (2.0_dp * f(1) + f(2) - 3.0_dp)
        dn(2, a) = 0.25_dp * quad_s(2, a) * f(1) * (f(1) + 2.0_dp * f(2) - 3.0_dp)
      end do
      ! mid-edges on eta = -1 and eta = +1 (nodes 5, 7), then on xi = +1 and xi = -1 (6, 8)
      do a = 5, 7, 2
        n(a) = 0.5_dp * (1.0_dp - x * x) * (1.0_dp + y * quad_s(2, a))
        dn(1, a) = -x * (1.0_dp + y * quad_s(2, a))
        dn(2, a) = 0.5_dp * (1.0_dp - x * x) * quad_s(2, a)
      end do
      do a = 6, 8, 2
        n(a) = 0.5_dp * (1.0_dp - y * y) * (1.0_dp + x * quad_s(1, a))
        dn(1, a) = 0.5_dp * (1.0_dp - y * y) * quad_s(1, a)
        dn(2, a) = -y * (1.0_dp + x * quad_s(1, a))
      end do
    case (interface_tri3)
      call tri3_face_shape(s, n, dn)
    case (interface_tri6)
      call tri6_face_shape(s, n, dn)
    case (interface_line2)
      n(1:2) = [0.5_dp * (1.0_dp - s(1)), 0.5_dp * (1.0_dp + s(1))]
      dn(1, 1:2) = [-0.5_dp, 0.5_dp]
      dn(2, 1:2) = 0.0_dp
    case (interface_line3)
      x = s(1)
      n(1:3) = [0.5_dp * x * (x - 1.0_dp), 0.5_dp * x * (x + 1.0_dp), 1.0_dp - x * x]
      dn(1, 1:3) = [x - 0.5_dp, x + 0.5_dp, -2.0_dp * x]
      dn(2, 1:3) = 0.0_dp
    end select
  end subroutine shape

  !> Integration points `s(2, ngauss)` (natural coordinates; s(2, :) = 0 for lines) and weights
  !! `w(ngauss)` of the chosen rule (reference areas: square 4, triangle 1/2, line 2).
  pure subroutine integration_rule(self, s, w)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(out) :: s(:, :), w(:)
    real(dp) :: x(3), wx(3)
    s = 0.0_dp
    w = 0.0_dp
    if (self%nodal_integration) then
      select case (self%shape_kind)
      case (interface_quad4)
        s(:, 1:4) = quad_s(:, 1:4)
        w(1:4) = 1.0_dp
      case (interface_quad8)
        s(:, 1:8) = quad_s
        s(:, 9) = 0.0_dp
        w(1:9) = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 4.0_dp, 4.0_dp, 4.0_dp, 4.0_dp, 16.0_dp] / 9.0_dp
      case (interface_tri3)
        s(:, 1:3) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 3])
        w(1:3) = 1.0_dp / 6.0_dp
      case (interface_tri6)
        s(:, 1:3) = reshape([0.5_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp, 0.5_dp], [2, 3])
        w(1:3) = 1.0_dp / 6.0_dp
      case (interface_line2)
        s(1, 1:2) = [-1.0_dp, 1.0_dp]
        w(1:2) = 1.0_dp
      case (interface_line3)
        s(1, 1:3) = [-1.0_dp, 1.0_dp, 0.0_dp]
        w(1:3) = [1.0_dp, 1.0_dp, 4.0_dp] / 3.0_dp
      end select
    else
      select case (self%shape_kind)
      case (interface_quad4)
        call square_rule(2, s, w)
      case (interface_quad8)
        call square_rule(3, s, w)
      case (interface_tri3)
        s(:, 1:3) = reshape([1.0_dp, 1.0_dp, 4.0_dp, 1.0_dp, 1.0_dp, 4.0_dp], [2, 3]) / 6.0_dp
        w(1:3) = 1.0_dp / 6.0_dp
      case (interface_tri6)
        s(:, 1:6) = reshape([tri_a, tri_a, 1.0_dp - 2.0_dp * tri_a, tri_a, tri_a, 1.0_dp - 2.0_dp * tri_a, &
                             tri_b, tri_b, 1.0_dp - 2.0_dp * tri_b, tri_b, tri_b, 1.0_dp - 2.0_dp * tri_b], [2, 6])
        w(1:6) = [tri_wa, tri_wa, tri_wa, tri_wb, tri_wb, tri_wb]
      case (interface_line2)
        call gauss_legendre(2, x, wx)
        s(1, 1:2) = x(1:2)
        w(1:2) = wx(1:2)
      case (interface_line3)
        call gauss_legendre(3, x, wx)
        s(1, 1:3) = x
        w(1:3) = wx
      end select
    end if
  end subroutine integration_rule

  !> Shape functions `n`, derivatives `dn` (as `shape`) and weight `wg` at integration point g,
  !! from the element's table when it has one.
  pure subroutine point_shape(self, g, n, dn, wg)
    class(interface_element_t), intent(in) :: self
    integer, intent(in) :: g
    real(dp), intent(out) :: n(:), dn(:, :), wg
    real(dp) :: s(2, max_interface_points), w(max_interface_points)
    integer :: p
    if (self%tabulated) then
      p = shape_pairs(self%shape_kind)
      n(1:p) = self%table_n(1:p, g)
      dn(:, 1:p) = self%table_dn(:, 1:p, g)
      wg = self%table_w(g)
      return
    end if
    call self%integration_rule(s, w)
    call self%shape(s(:, g), n, dn)
    wg = w(g)
  end subroutine point_shape

  !> Natural coordinates `s(2, npairs)` of the nodes of one layer, in connectivity order
  !! (s(2, :) = 0 for lines).
  pure subroutine node_coordinates(self, s)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(out) :: s(:, :)
    s = 0.0_dp
    select case (self%shape_kind)
    case (interface_quad4)
      s(:, 1:4) = quad_s(:, 1:4)
    case (interface_quad8)
      s(:, 1:8) = quad_s
    case (interface_tri3)
      s(:, 1:3) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 3])
    case (interface_tri6)
      s(:, 1:6) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
                           0.5_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp, 0.5_dp], [2, 6])
    case (interface_line2)
      s(1, 1:2) = [-1.0_dp, 1.0_dp]
    case (interface_line3)
      s(1, 1:3) = [-1.0_dp, 1.0_dp, 0.0_dp]
    end select
  end subroutine node_coordinates

  ! ------------------------------------------------------------------ geometry

  !> Tangent dx/ds1 `t1`, normal vector `nstar` (3D: dx/ds1 x dx/ds2; 2D: t1 turned +90 deg),
  !! local frame `frame(nd, nd)` (rows e1[, e2], n) and Jacobian |nstar| from the lower-layer
  !! coordinates `xe` and derivatives `dn(2, p)`. A degenerate point gives a zero frame.
  pure subroutine local_frame(nd, p, xe, dn, frame, jac, nstar)
    integer, intent(in) :: nd, p
    real(dp), intent(in) :: xe(:, :)
    real(dp), intent(in) :: dn(:, :)
    real(dp), intent(out) :: frame(:, :)
    real(dp), intent(out) :: jac
    real(dp), intent(out) :: nstar(3)
    real(dp) :: t1(3), t2(3), len1
    integer :: a
    t1 = 0.0_dp
    t2 = 0.0_dp
    do a = 1, p
      t1(1:nd) = t1(1:nd) + dn(1, a) * xe(1:nd, a)
      t2(1:nd) = t2(1:nd) + dn(2, a) * xe(1:nd, a)
    end do
    frame(1:nd, 1:nd) = 0.0_dp
    if (nd == 3) then
      nstar = cross(t1, t2)
      jac = norm2(nstar)
      len1 = norm2(t1)
      if (jac <= tiny(jac) .or. len1 <= tiny(len1)) return
      t1 = t1 / len1
      t2 = nstar / jac
      frame(1, 1:3) = t1
      frame(2, 1:3) = cross(t2, t1)
      frame(3, 1:3) = t2
    else
      nstar = [-t1(2), t1(1), 0.0_dp]
      jac = norm2(t1(1:2))
      if (jac <= tiny(jac)) return
      frame(1, 1:2) = t1(1:2) / jac
      frame(2, 1:2) = [-frame(1, 2), frame(1, 1)]
    end if
  end subroutine local_frame

  pure function cross(u, v) result(w)
    real(dp), intent(in) :: u(3), v(3)
    real(dp) :: w(3)
    w = [u(2) * v(3) - u(3) * v(2), u(3) * v(1) - u(1) * v(3), u(1) * v(2) - u(2) * v(1)]
  end function cross

  !> Strain-displacement matrix `b(ncomp, ndim nnodes)` at integration point `g`
  !! (strain = b ue, upper minus lower in the local frame), `wdet` = weight times surface (line)
  !! Jacobian, and the local frame `frame(ndim, ndim)` (rows e1, e2, n in 3D; e1, n in 2D).
  pure subroutine point_b(self, xe, g, b, wdet, frame)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)      !! (ndim, nnodes) both layers
    integer, intent(in) :: g
    real(dp), intent(out) :: b(:, :)      !! (ncomp, ndim nnodes)
    real(dp), intent(out) :: wdet
    real(dp), intent(out) :: frame(:, :)  !! (ndim, ndim)
    real(dp) :: wg
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs), nstar(3), jac
    integer :: p, nd, a, lo, up
    p = self%npairs()
    nd = self%ndim()
    call point_shape(self, g, n, dn, wg)
    call local_frame(nd, p, xe, dn, frame, jac, nstar)
    wdet = wg * jac
    b = 0.0_dp
    do a = 1, p
      lo = nd * (a - 1)
      up = nd * (p + a - 1)
      b(1:nd, lo + 1:lo + nd) = -n(a) * frame(1:nd, 1:nd)
      b(1:nd, up + 1:up + nd) = n(a) * frame(1:nd, 1:nd)
    end do
  end subroutine point_b

  !> Element stiffness `ke(ndim nnodes, ndim nnodes)` in the element's own dimension = sum over
  !! the points of B^T D B wdet with the material matrix `d(ncomp, ncomp, ngauss)` of each point
  !! (need not be symmetric).
  pure subroutine stiffness_nd(self, xe, d, ke)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (ndim, nnodes)
    real(dp), intent(in) :: d(:, :, :)   !! (ncomp, ncomp, ngauss)
    real(dp), intent(out) :: ke(:, :)    !! (ndim nnodes, ndim nnodes)
    real(dp) :: wg
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs), nstar(3), jac
    real(dp) :: frame(3, 3), dglobal(3, 3), blk(3, 3)
    integer :: p, nd, g, a, c, la, ua, lc, uc
    p = self%npairs()
    nd = self%ndim()
    ke = 0.0_dp
    do g = 1, self%ngauss()
      call point_shape(self, g, n, dn, wg)
      call local_frame(nd, p, xe, dn, frame, jac, nstar)
      ! B^T D B = [-F F]^T (C^T D C) [-F F]: one global pair matrix, scaled by N_a N_c
      dglobal(1:nd, 1:nd) = matmul(transpose(frame(1:nd, 1:nd)), matmul(d(1:nd, 1:nd, g), frame(1:nd, 1:nd))) &
                            * (wg * jac)
      do c = 1, p
        lc = nd * (c - 1)
        uc = nd * (p + c - 1)
        do a = 1, p
          la = nd * (a - 1)
          ua = nd * (p + a - 1)
          blk(1:nd, 1:nd) = (n(a) * n(c)) * dglobal(1:nd, 1:nd)
          ke(la + 1:la + nd, lc + 1:lc + nd) = ke(la + 1:la + nd, lc + 1:lc + nd) + blk(1:nd, 1:nd)
          ke(la + 1:la + nd, uc + 1:uc + nd) = ke(la + 1:la + nd, uc + 1:uc + nd) - blk(1:nd, 1:nd)
          ke(ua + 1:ua + nd, lc + 1:lc + nd) = ke(ua + 1:ua + nd, lc + 1:lc + nd) - blk(1:nd, 1:nd)
          ke(ua + 1:ua + nd, uc + 1:uc + nd) = ke(ua + 1:ua + nd, uc + 1:uc + nd) + blk(1:nd, 1:nd)
        end do
      end do
    end do
  end subroutine stiffness_nd

  !> Internal nodal forces `fe(ndim nnodes)` in the element's own dimension = sum over the
  !! points of B^T sig wdet, with the local tractions `sig(ncomp, ngauss)`.
  pure subroutine internal_force_nd(self, xe, sig, fe)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (ndim, nnodes)
    real(dp), intent(in) :: sig(:, :)    !! (ncomp, ngauss)
    real(dp), intent(out) :: fe(:)       !! (ndim nnodes)
    real(dp) :: wg
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs), nstar(3), jac
    real(dp) :: frame(3, 3), traction(3)
    integer :: p, nd, g, a, la, ua
    p = self%npairs()
    nd = self%ndim()
    fe = 0.0_dp
    do g = 1, self%ngauss()
      call point_shape(self, g, n, dn, wg)
      call local_frame(nd, p, xe, dn, frame, jac, nstar)
      ! global traction C^T sig acts on the upper layer, its opposite on the lower one
      traction(1:nd) = matmul(sig(1:nd, g), frame(1:nd, 1:nd)) * (wg * jac)
      do a = 1, p
        la = nd * (a - 1)
        ua = nd * (p + a - 1)
        fe(la + 1:la + nd) = fe(la + 1:la + nd) - n(a) * traction(1:nd)
        fe(ua + 1:ua + nd) = fe(ua + 1:ua + nd) + n(a) * traction(1:nd)
      end do
    end do
  end subroutine internal_force_nd

  !> Strains `eps(ncomp, ngauss)` = B ue at the integration points, from `ue(ndim nnodes)` in
  !! the element's own dimension (node by node).
  pure subroutine strains_nd(self, xe, ue, eps)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (ndim, nnodes)
    real(dp), intent(in) :: ue(:)        !! (ndim nnodes)
    real(dp), intent(out) :: eps(:, :)   !! (ncomp, ngauss)
    real(dp) :: wg
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs), nstar(3), jac
    real(dp) :: frame(3, 3), jump(3)
    integer :: p, nd, g, a, la, ua
    p = self%npairs()
    nd = self%ndim()
    do g = 1, self%ngauss()
      call point_shape(self, g, n, dn, wg)
      call local_frame(nd, p, xe, dn, frame, jac, nstar)
      ! displacement jump (upper minus lower) in global axes, then in the local frame
      jump = 0.0_dp
      do a = 1, p
        la = nd * (a - 1)
        ua = nd * (p + a - 1)
        jump(1:nd) = jump(1:nd) + n(a) * (ue(ua + 1:ua + nd) - ue(la + 1:la + nd))
      end do
      eps(1:nd, g) = matmul(frame(1:nd, 1:nd), jump(1:nd))
    end do
  end subroutine strains_nd

  !> Global coordinates `xg(ndim, ngauss)` of the integration points (on the lower layer), in
  !! the element's own dimension.
  pure subroutine point_coordinates_nd(self, xe, xg)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (ndim, nnodes)
    real(dp), intent(out) :: xg(:, :)    !! (ndim, ngauss)
    real(dp) :: s(2, max_interface_points), w(max_interface_points)
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs)
    integer :: p, nd, g, a
    p = self%npairs()
    nd = self%ndim()
    call self%integration_rule(s, w)
    do g = 1, self%ngauss()
      call self%shape(s(:, g), n, dn)
      xg(1:nd, g) = 0.0_dp
      do a = 1, p
        xg(1:nd, g) = xg(1:nd, g) + n(a) * xe(1:nd, a)
      end do
    end do
  end subroutine point_coordinates_nd

  !> wdet at each point of the chosen rule, from `xe(ndim, nnodes)`: the area of the lower layer
  !! it stands for (length per unit thickness in 2D).
  pure subroutine point_weights_nd(self, xe, wts)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (ndim, nnodes)
    real(dp), intent(out) :: wts(:)      !! (ngauss)
    real(dp) :: s(2, max_interface_points), w(max_interface_points)
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs), nstar(3), jac, frame(3, 3)
    integer :: p, nd, g
    p = self%npairs()
    nd = self%ndim()
    call self%integration_rule(s, w)
    do g = 1, self%ngauss()
      call self%shape(s(:, g), n, dn)
      call local_frame(nd, p, xe, dn, frame, jac, nstar)
      wts(g) = w(g) * jac
    end do
  end subroutine point_weights_nd

  !> Area of the lower layer (length in 2D): sum of wdet over the chosen rule.
  pure real(dp) function area(self, xe)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (ndim, nnodes)
    real(dp) :: wts(max_interface_points)
    integer :: g
    call self%point_weights_nd(xe, wts(1:self%ngauss()))
    area = 0.0_dp
    do g = 1, self%ngauss()
      area = area + wts(g)
    end do
  end function area

  !> Smallest surface (line) Jacobian at the integration points, from `xe(ndim, nnodes)`, signed: the normal vector
  !! dx/ds1 x dx/ds2 (2D: the tangent) projected on the unit normal (tangent) at the element
  !! centre, so that a folded or inverted element gives a value <= 0. For a flat element it
  !! equals |dx/ds1 x dx/ds2|. The caller rejects values <= 0.
  pure real(dp) function min_jacobian_nd(self, xe)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (ndim, nnodes)
    real(dp) :: s(2, max_interface_points), w(max_interface_points), centre(2)
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs), nstar(3), jac, frame(3, 3)
    real(dp) :: reference(3)
    integer :: p, nd, g
    p = self%npairs()
    nd = self%ndim()
    select case (self%shape_kind)
    case (interface_tri3, interface_tri6)
      centre = 1.0_dp / 3.0_dp
    case default
      centre = 0.0_dp
    end select
    call self%shape(centre, n, dn)
    call local_frame(nd, p, xe, dn, frame, jac, reference)
    if (jac <= tiny(jac)) then
      min_jacobian_nd = 0.0_dp
      return
    end if
    reference = reference / jac
    call self%integration_rule(s, w)
    min_jacobian_nd = huge(1.0_dp)
    do g = 1, self%ngauss()
      call self%shape(s(:, g), n, dn)
      call local_frame(nd, p, xe, dn, frame, jac, nstar)
      min_jacobian_nd = min(min_jacobian_nd, dot_product(nstar, reference))
    end do
  end function min_jacobian_nd

  ! ------------------------------------------------------------------ the element contract

  !> Element stiffness `ke(3 nnodes, 3 nnodes)` (3 DOFs per node) from `xe(3, nnodes)`: that of
  !! stiffness_nd, a 2D element's x-y matrix embedded with zero z rows and columns.
  pure subroutine stiffness(self, xe, d, ke)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: d(:, :, :)   !! (ncomp, ncomp, ngauss)
    real(dp), intent(out) :: ke(:, :)    !! (3 nnodes, 3 nnodes)
    real(dp), allocatable :: k2(:, :)
    integer, allocatable :: map2(:)
    if (self%ndim() == 3) then
      call stiffness_nd(self, xe, d, ke)
      return
    end if
    map2 = xy_dofs(self%nnodes())
    allocate (k2(2 * self%nnodes(), 2 * self%nnodes()))
    call stiffness_nd(self, xe(1:2, :), d, k2)
    ke = 0.0_dp
    ke(map2, map2) = k2
  end subroutine stiffness

  !> Internal nodal forces `fe(3 nnodes)` (3 DOFs per node) from `xe(3, nnodes)` and the local
  !! tractions `sig(ncomp, ngauss)`: those of internal_force_nd, a 2D element's with zero z forces.
  pure subroutine internal_force(self, xe, sig, fe)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: sig(:, :)    !! (ncomp, ngauss)
    real(dp), intent(out) :: fe(:)       !! (3 nnodes)
    real(dp) :: f2(2 * self%nnodes())
    if (self%ndim() == 3) then
      call internal_force_nd(self, xe, sig, fe)
      return
    end if
    fe = 0.0_dp
    call internal_force_nd(self, xe(1:2, :), sig, f2)
    fe(xy_dofs(self%nnodes())) = f2
  end subroutine internal_force

  !> Strains `eps(ncomp, ngauss)` (relative displacements in the local frame) from `xe(3, nnodes)`
  !! and `ue(3 nnodes)`: those of strains_nd, a 2D element's from the x-y displacements.
  pure subroutine strains(self, xe, ue, eps)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: ue(:)        !! (3 nnodes)
    real(dp), intent(out) :: eps(:, :)   !! (ncomp, ngauss)
    if (self%ndim() == 3) then
      call strains_nd(self, xe, ue, eps)
    else
      call strains_nd(self, xe(1:2, :), ue(xy_dofs(self%nnodes())), eps)
    end if
  end subroutine strains

  !> Global coordinates `xg(3, ngauss)` of the integration points (on the lower layer) from
  !! `xe(3, nnodes)`; a 2D element's points have z = 0.
  pure subroutine point_coordinates(self, xe, xg)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(out) :: xg(:, :)    !! (3, ngauss)
    if (self%ndim() == 3) then
      call point_coordinates_nd(self, xe, xg)
    else
      xg(3, :) = 0.0_dp
      call point_coordinates_nd(self, xe(1:2, :), xg(1:2, :))
    end if
  end subroutine point_coordinates

  !> The area each point stands for (`point_weights_nd`) from `xe(3, nnodes)`.
  pure subroutine point_weights(self, xe, w)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(out) :: w(:)        !! (ngauss)
    call self%point_weights_nd(xe(1:self%ndim(), :), w)
  end subroutine point_weights

  !> The tractions of the Cartesian stress tensors `tensors(3, 3, ngauss)` given at the points on
  !! the interface's plane, in its local frame: e_i . sigma . n for every row e_i of the frame
  !! (3D [tau1, tau2, sigma_n], 2D [tau, sigma_n]; tension positive, as the tractions).
  pure subroutine interface_stresses_of_tensors(self, xe, tensors, sig, taken)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)          !! (3, nnodes)
    real(dp), intent(in) :: tensors(:, :, :)  !! (3, 3, ngauss)
    real(dp), intent(out) :: sig(:, :)        !! (ncomp, ngauss)
    logical, intent(out) :: taken
    real(dp) :: s(2, max_interface_points), w(max_interface_points)
    real(dp) :: n(max_interface_pairs), dn(2, max_interface_pairs), nstar(3), jac, frame(3, 3)
    integer :: p, nd, g
    p = self%npairs()
    nd = self%ndim()
    call self%integration_rule(s, w)
    do g = 1, self%ngauss()
      call self%shape(s(:, g), n, dn)
      call local_frame(nd, p, xe(1:nd, :), dn, frame, jac, nstar)
      sig(1:nd, g) = matmul(frame(1:nd, 1:nd), matmul(tensors(1:nd, 1:nd, g), frame(nd, 1:nd)))
    end do
    taken = .true.
  end subroutine interface_stresses_of_tensors

  !> min_jacobian_nd from `xe(3, nnodes)` (a 2D element: from its x-y coordinates).
  pure real(dp) function min_jacobian(self, xe)
    class(interface_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    if (self%ndim() == 3) then
      min_jacobian = min_jacobian_nd(self, xe)
    else
      min_jacobian = min_jacobian_nd(self, xe(1:2, :))
    end if
  end function min_jacobian

  !> The rejection of an interface element by its surface (line) Jacobian `jac` <= 0.
  pure function interface_jacobian_message(self, label, jac) result(message)
    class(interface_element_t), intent(in) :: self
    character(len=*), intent(in) :: label
    real(dp), intent(in) :: jac
    character(len=:), allocatable :: message
    message = 'interface element ' // label // ' has a degenerate or folded lower face (surface Jacobian ' // &
              str(jac) // ')'
  end function interface_jacobian_message

  !> Positions of the x and y DOFs of n nodes among 3 DOFs per node.
  pure function xy_dofs(n) result(idx)
    integer, intent(in) :: n
    integer :: idx(2 * n)
    integer :: k
    do k = 1, n
      idx(2 * k - 1) = 3 * k - 2
      idx(2 * k) = 3 * k - 1
    end do
  end function xy_dofs

end module feps_interface_element
