!> Curved bar elements with 2, 3, 4 and 5 nodes (thesis section 2.5.2): 'bar2', 'bar3', 'bar4',
!! 'bar5'. Isoparametric 3D lines carrying only an axial force.
!!
!! Nodes in their natural order along the bar: node 1 at s = -1, node n at s = +1, the others
!! equally spaced between them in order, s_i = -1 + 2 (i - 1) / (n - 1) (so bar3 is end, middle,
!! end). Shape functions are the Lagrange polynomials on these points (thesis eq. 2.5.2, there
!! written on [0, 1]).
!!
!! Integration: n - 1 Gauss-Legendre points (thesis), listed in ascending s. This integrates
!! B^T B J exactly for a straight bar with equally spaced nodes.
!!
!! Kinematics (eqs. 2.5.4-2.5.9): tangent dx/ds, Jacobian J = |dx/ds|, unit tangent
!! t = (dx/ds) / J, one strain component, the axial strain eps = t . du/dl = t . (du/ds) / J, so
!! B(1, 3 n) = [dN_1/ds t^T, ..., dN_n/ds t^T] / J with DOFs node by node (u1x, u1y, u1z, u2x, ...).
!! The "stress" of a bar is its axial force N (tension positive) and its "material matrix" is
!! d(1, 1) = E A (eq. 2.5.10); integration weights are w J, i.e. along the arc length.
module feps_bar_element
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_input, str
  use feps_gauss, only: gauss_legendre
  use feps_element, only: element_t
  implicit none
  private

  public :: bar_element_t, new_bar_element, is_bar_type

  integer, parameter, public :: min_bar_nodes = 2   !! fewest nodes of a bar element
  integer, parameter, public :: max_bar_nodes = 5   !! most nodes of a bar element
  integer, parameter, public :: bar_ndim = 3        !! coordinates and DOFs per node

  !> A curved bar with `nodes` nodes.
  type, extends(element_t) :: bar_element_t
    integer :: nodes = 2
  contains
    ! the element contract
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
    procedure :: jacobian_message => bar_jacobian_message
    ! the bar family
    procedure :: ngauss
    procedure :: natural_coordinates
    procedure :: shape
    procedure :: integration_rule
    procedure :: point_b
    procedure :: length
    procedure :: body_force => bar_body_force
  end type bar_element_t

contains

  !> Make a bar element from its name 'bar2' .. 'bar5' (case-insensitive, surrounding blanks
  !! ignored). An unknown name returns an err_input error naming it and the known names.
  pure subroutine new_bar_element(type_name, element, error)
    character(len=*), intent(in) :: type_name
    type(bar_element_t), intent(out) :: element
    type(error_t), allocatable, intent(out) :: error
    integer :: n
    n = nodes_of_name(type_name)
    if (n == 0) then
      call fatal_error(error, err_input, "unknown bar element type '" // trim(adjustl(type_name)) // &
                       "' (known: bar2, bar3, bar4, bar5)")
      return
    end if
    element%nodes = n
  end subroutine new_bar_element

  !> True if `name` (case-insensitive) names a bar element type.
  pure logical function is_bar_type(name)
    character(len=*), intent(in) :: name
    is_bar_type = nodes_of_name(name) /= 0
  end function is_bar_type

  !> Number of nodes named by 'barN' (N = 2..5), 0 for any other name.
  pure integer function nodes_of_name(name) result(n)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: base
    integer :: code
    n = 0
    base = trim(adjustl(name))
    if (len(base) /= 4) return
    if (lower(base(1:3)) /= 'bar') return
    code = iachar(base(4:4)) - iachar('0')
    if (code >= min_bar_nodes .and. code <= max_bar_nodes) n = code
  end function nodes_of_name

  pure function lower(text) result(low)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: low
    integer :: i, code
    low = text
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code >= iachar('A') .and. code <= iachar('Z')) low(i:i) = achar(code + 32)
    end do
  end function lower

  ! ------------------------------------------------------------------ sizes and names

  !> Number of nodes.
  pure integer function nnodes(self)
    class(bar_element_t), intent(in) :: self
    nnodes = self%nodes
  end function nnodes

  !> Coordinates and DOFs per node: 3.
  pure integer function ndim(self)
    class(bar_element_t), intent(in) :: self
    ndim = bar_ndim
  end function ndim

  !> Strain/stress components: 1 (axial strain, axial force).
  pure integer function ncomp(self)
    class(bar_element_t), intent(in) :: self
    ncomp = 1
  end function ncomp

  !> Number of Gauss points: nodes - 1.
  pure integer function ngauss(self)
    class(bar_element_t), intent(in) :: self
    ngauss = self%nodes - 1
  end function ngauss

  !> Type name, e.g. 'bar3'.
  pure function element_type(self) result(name)
    class(bar_element_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'bar' // achar(iachar('0') + self%nodes)
  end function element_type

  ! ------------------------------------------------------------------ shape functions and rule

  !> Natural coordinates `s(nnodes)` of the nodes: -1 + 2 (i - 1) / (n - 1).
  pure subroutine natural_coordinates(self, s)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(out) :: s(:)
    integer :: i
    do i = 1, self%nodes
      s(i) = -1.0_dp + 2.0_dp * real(i - 1, dp) / real(self%nodes - 1, dp)
    end do
  end subroutine natural_coordinates

  !> Lagrange shape functions `n(nnodes)` and derivatives `dn(nnodes)` = dN/ds at `s`.
  pure subroutine shape(self, s, n, dn)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: s
    real(dp), intent(out) :: n(:), dn(:)
    real(dp) :: sn(max_bar_nodes), term
    integer :: i, j, k, p
    p = self%nodes
    call self%natural_coordinates(sn)
    do i = 1, p
      n(i) = 1.0_dp
      dn(i) = 0.0_dp
      do j = 1, p
        if (j /= i) n(i) = n(i) * (s - sn(j)) / (sn(i) - sn(j))
      end do
      ! product rule: one factor differentiated at a time (no division by s - s_j)
      do k = 1, p
        if (k == i) cycle
        term = 1.0_dp / (sn(i) - sn(k))
        do j = 1, p
          if (j /= i .and. j /= k) term = term * (s - sn(j)) / (sn(i) - sn(j))
        end do
        dn(i) = dn(i) + term
      end do
    end do
  end subroutine shape

  !> Gauss points `s(ngauss)` (ascending) and weights `w(ngauss)` on [-1, 1].
  pure subroutine integration_rule(self, s, w)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(out) :: s(:), w(:)
    call gauss_legendre(self%nodes - 1, s, w)
  end subroutine integration_rule

  ! ------------------------------------------------------------------ geometry

  !> Tangent dx/ds `tangent(3)` and Jacobian |dx/ds| from `xe(3, n)` and `dn(n)`.
  pure subroutine tangent_vector(p, xe, dn, tangent, jac)
    integer, intent(in) :: p
    real(dp), intent(in) :: xe(:, :), dn(:)
    real(dp), intent(out) :: tangent(bar_ndim), jac
    integer :: a
    tangent = 0.0_dp
    do a = 1, p
      tangent = tangent + dn(a) * xe(1:bar_ndim, a)
    end do
    jac = norm2(tangent)
  end subroutine tangent_vector

  !> Unit tangent `t(3)`, its Jacobian `jac`, dN/ds `dn` and weight `w` at Gauss point `g`.
  !! A degenerate point (zero tangent) gives t = 0, so that its B and stiffness vanish.
  pure subroutine gauss_point(self, xe, g, t, jac, dn, w)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)
    integer, intent(in) :: g
    real(dp), intent(out) :: t(bar_ndim), jac, dn(max_bar_nodes), w
    real(dp) :: s(max_bar_nodes), ws(max_bar_nodes), n(max_bar_nodes)
    call self%integration_rule(s, ws)
    call self%shape(s(g), n, dn)
    call tangent_vector(self%nodes, xe, dn, t, jac)
    if (jac > tiny(jac)) then
      t = t / jac
    else
      t = 0.0_dp
    end if
    w = ws(g)
  end subroutine gauss_point

  !> Strain-displacement row `b(1, 3 nnodes)` at Gauss point `g` (axial strain = b ue), and
  !! `wdet` = weight times |dx/ds|; optionally the unit tangent `tangent(3)` there.
  pure subroutine point_b(self, xe, g, b, wdet, tangent)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)      !! (3, nnodes)
    integer, intent(in) :: g
    real(dp), intent(out) :: b(:, :)      !! (1, 3 nnodes)
    real(dp), intent(out) :: wdet
    real(dp), intent(out), optional :: tangent(:)  !! (3)
    real(dp) :: t(bar_ndim), jac, dn(max_bar_nodes), w
    integer :: a, la
    call gauss_point(self, xe, g, t, jac, dn, w)
    wdet = w * jac
    b = 0.0_dp
    if (jac > tiny(jac)) then
      do a = 1, self%nodes
        la = bar_ndim * (a - 1)
        b(1, la + 1:la + bar_ndim) = (dn(a) / jac) * t
      end do
    end if
    if (present(tangent)) tangent(1:bar_ndim) = t
  end subroutine point_b

  !> Element stiffness `ke(3 nnodes, 3 nnodes)` = sum over the Gauss points of B^T d B wdet with
  !! the axial stiffness `d(1, 1, g)` = E A of each point.
  pure subroutine stiffness(self, xe, d, ke)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: d(:, :, :)   !! (1, 1, ngauss)
    real(dp), intent(out) :: ke(:, :)    !! (3 nnodes, 3 nnodes)
    real(dp) :: b(1, bar_ndim * max_bar_nodes), wdet
    integer :: g, i, j, ndof
    ndof = bar_ndim * self%nodes
    ke(1:ndof, 1:ndof) = 0.0_dp
    do g = 1, self%ngauss()
      call self%point_b(xe, g, b(:, 1:ndof), wdet)
      do j = 1, ndof
        do i = 1, j
          ke(i, j) = ke(i, j) + b(1, i) * (d(1, 1, g) * wdet) * b(1, j)
        end do
      end do
    end do
    ! exactly symmetric: the lower triangle is a copy of the upper one
    do j = 1, ndof
      ke(j + 1:ndof, j) = ke(j, j + 1:ndof)
    end do
  end subroutine stiffness

  !> Internal nodal forces `fe(3 nnodes)` = sum over the Gauss points of B^T N wdet with the
  !! axial forces `sig(1, ngauss)`.
  pure subroutine internal_force(self, xe, sig, fe)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: sig(:, :)    !! (1, ngauss)
    real(dp), intent(out) :: fe(:)       !! (3 nnodes)
    real(dp) :: b(1, bar_ndim * max_bar_nodes), wdet
    integer :: g, ndof
    ndof = bar_ndim * self%nodes
    fe(1:ndof) = 0.0_dp
    do g = 1, self%ngauss()
      call self%point_b(xe, g, b(:, 1:ndof), wdet)
      fe(1:ndof) = fe(1:ndof) + b(1, 1:ndof) * (sig(1, g) * wdet)
    end do
  end subroutine internal_force

  !> Axial strains `eps(1, ngauss)` = B ue at the Gauss points (ue node by node).
  pure subroutine strains(self, xe, ue, eps)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: ue(:)        !! (3 nnodes)
    real(dp), intent(out) :: eps(:, :)   !! (1, ngauss)
    real(dp) :: b(1, bar_ndim * max_bar_nodes), wdet
    integer :: g, ndof
    ndof = bar_ndim * self%nodes
    do g = 1, self%ngauss()
      call self%point_b(xe, g, b(:, 1:ndof), wdet)
      eps(1, g) = dot_product(b(1, 1:ndof), ue(1:ndof))
    end do
  end subroutine strains

  !> Global coordinates `xg(3, ngauss)` of the Gauss points.
  pure subroutine point_coordinates(self, xe, xg)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(out) :: xg(:, :)    !! (3, ngauss)
    real(dp) :: s(max_bar_nodes), w(max_bar_nodes), n(max_bar_nodes), dn(max_bar_nodes)
    integer :: g, a
    call self%integration_rule(s, w)
    do g = 1, self%ngauss()
      call self%shape(s(g), n, dn)
      xg(1:bar_ndim, g) = 0.0_dp
      do a = 1, self%nodes
        xg(1:bar_ndim, g) = xg(1:bar_ndim, g) + n(a) * xe(1:bar_ndim, a)
      end do
    end do
  end subroutine point_coordinates

  !> w |dx/ds| at each Gauss point: the length it stands for.
  pure subroutine point_weights(self, xe, w)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(out) :: w(:)        !! (ngauss)
    real(dp) :: t(bar_ndim), jac, dn(max_bar_nodes), wg
    integer :: g
    do g = 1, self%ngauss()
      call gauss_point(self, xe, g, t, jac, dn, wg)
      w(g) = wg * jac
    end do
  end subroutine point_weights

  !> Length of the bar by the element's own rule: the sum of wdet over the Gauss points, i.e.
  !! the length the stiffness and internal forces integrate over (exact for a straight bar).
  pure real(dp) function length(self, xe)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp) :: w(self%ngauss())
    integer :: g
    call self%point_weights(xe, w)
    length = 0.0_dp
    do g = 1, size(w)
      length = length + w(g)
    end do
  end function length

  !> Smallest Jacobian at the Gauss points, signed: dx/ds projected on the unit tangent at the
  !! element centre (s = 0), so that a bar folded back on itself gives a value <= 0. For a
  !! straight bar it equals |dx/ds| = length / 2. (A valid bar whose tangent turns by more than
  !! 90 degrees between its centre and a Gauss point, i.e. spanning well over a half circle,
  !! would also give <= 0; such a bar must be subdivided.) The caller rejects values <= 0.
  pure real(dp) function min_jacobian(self, xe)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp) :: s(max_bar_nodes), w(max_bar_nodes), n(max_bar_nodes), dn(max_bar_nodes)
    real(dp) :: reference(bar_ndim), tangent(bar_ndim), jac
    integer :: g
    call self%shape(0.0_dp, n, dn)
    call tangent_vector(self%nodes, xe, dn, reference, jac)
    if (jac <= tiny(jac)) then
      min_jacobian = 0.0_dp
      return
    end if
    reference = reference / jac
    call self%integration_rule(s, w)
    min_jacobian = huge(1.0_dp)
    do g = 1, self%ngauss()
      call self%shape(s(g), n, dn)
      call tangent_vector(self%nodes, xe, dn, tangent, jac)
      min_jacobian = min(min_jacobian, dot_product(tangent, reference))
    end do
  end function min_jacobian

  !> The rejection of a bar by its line Jacobian `jac` <= 0.
  pure function bar_jacobian_message(self, label, jac) result(message)
    class(bar_element_t), intent(in) :: self
    character(len=*), intent(in) :: label
    real(dp), intent(in) :: jac
    character(len=:), allocatable :: message
    message = 'bar element ' // label // ' is folded or has coincident nodes (Jacobian ' // str(jac) // ')'
  end function bar_jacobian_message

  !> Consistent nodal forces of the uniform force `b(3)` per unit length (a bar's weight: its
  !! unit weight times its area): the sum over the Gauss points of N_a b |dx/ds| w.
  pure subroutine bar_body_force(self, xe, b, fe)
    class(bar_element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: b(3)
    real(dp), intent(out) :: fe(:)       !! (3 nnodes)
    real(dp) :: s(max_bar_nodes), w(max_bar_nodes), n(max_bar_nodes), dn(max_bar_nodes), t(bar_ndim), jac
    integer :: g, a
    call self%integration_rule(s, w)
    fe = 0.0_dp
    do g = 1, self%ngauss()
      call self%shape(s(g), n, dn)
      call tangent_vector(self%nodes, xe, dn, t, jac)
      do a = 1, self%nodes
        fe(3 * a - 2:3 * a) = fe(3 * a - 2:3 * a) + n(a) * jac * w(g) * b
      end do
    end do
  end subroutine bar_body_force

end module feps_bar_element
