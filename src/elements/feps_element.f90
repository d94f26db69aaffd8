!> The element contract: what assembly, loads, the analysis and the results ask of an element of
!! any family (solids, interfaces, bars, and any future one). The element catalog
!! (feps_element_catalog) makes an element of every type it knows as a `class(element_t)`.
!!
!! Conventions, the same for every family:
!! - Node coordinates `xe(3, nnodes)` and element DOFs node by node with 3 DOFs per node
!!   (u1x, u1y, u1z, u2x, ...), global Cartesian. A plane-strain type (ndim() = 2) keeps the
!!   three DOFs: its matrices have zero z rows and columns and it ignores uz (the analysis holds
!!   uz in 2D models).
!! - Each element has `npoints()` integration points and `ncomp()` strain (stress) components
!!   per point, in the family's own order and frame: solids the Voigt strains
!!   [xx yy zz yz xz xy] (engineering shears) and stresses; interfaces the relative
!!   displacements and tractions in their local frame; bars the axial strain and axial force.
!!   The material matrix of a point, `d(ncomp, ncomp)`, maps the one to the other.
!!
!! What a family adds of its own (a solid's shape functions, B-matrix and faces; an interface's
!! layers and local frame; a bar's tangent) stays in the family's abstract or concrete type.
module feps_element
  use feps_kinds, only: dp
  use feps_error, only: str
  implicit none
  private

  !> An element of any family, seen through what every family provides.
  type, abstract, public :: element_t
  contains
    procedure(count_interface), deferred :: nnodes          !! nodes per element (an interface: both layers)
    procedure(count_interface), deferred :: npoints         !! integration points per element
    procedure(count_interface), deferred :: ncomp           !! strain (stress) components per point
    procedure(count_interface), deferred :: ndim            !! spatial dimension: 3, or 2 for plane strain
    procedure(name_interface), deferred :: element_type     !! the catalog's type name: 'hex8', 'bar3', ...
    procedure(stiffness_interface), deferred :: stiffness   !! sum of B^T D B over the points
    procedure(force_interface), deferred :: internal_force  !! sum of B^T sig over the points
    procedure(strains_interface), deferred :: strains       !! B ue at the points
    procedure(coordinates_interface), deferred :: point_coordinates  !! global positions of the points
    procedure(weights_interface), deferred :: point_weights  !! the measure each point stands for
    procedure(jacobian_interface), deferred :: min_jacobian !! mesh check: <= 0 rejects the element
    procedure :: jacobian_message
    procedure :: body_force => element_body_force   !! consistent nodal forces of a uniform body force
    procedure :: stresses_of_tensors => element_stresses_of_tensors  !! point stresses of a given stress field
  end type element_t

  abstract interface
    pure integer function count_interface(self)
      import :: element_t
      class(element_t), intent(in) :: self
    end function count_interface

    pure function name_interface(self) result(name)
      import :: element_t
      class(element_t), intent(in) :: self
      character(len=:), allocatable :: name
    end function name_interface

    !> Element stiffness `ke(3 nnodes, 3 nnodes)` from the material matrices `d(ncomp, ncomp,
    !! npoints)` of its points (need not be symmetric).
    pure subroutine stiffness_interface(self, xe, d, ke)
      import :: element_t, dp
      class(element_t), intent(in) :: self
      real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
      real(dp), intent(in) :: d(:, :, :)   !! (ncomp, ncomp, npoints)
      real(dp), intent(out) :: ke(:, :)    !! (3 nnodes, 3 nnodes)
    end subroutine stiffness_interface

    !> Internal nodal forces `fe(3 nnodes)` from the stresses `sig(ncomp, npoints)` of its points.
    pure subroutine force_interface(self, xe, sig, fe)
      import :: element_t, dp
      class(element_t), intent(in) :: self
      real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
      real(dp), intent(in) :: sig(:, :)    !! (ncomp, npoints)
      real(dp), intent(out) :: fe(:)       !! (3 nnodes)
    end subroutine force_interface

    !> Strains `eps(ncomp, npoints)` at the points from the displacements `ue(3 nnodes)`.
    pure subroutine strains_interface(self, xe, ue, eps)
      import :: element_t, dp
      class(element_t), intent(in) :: self
      real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
      real(dp), intent(in) :: ue(:)        !! (3 nnodes)
      real(dp), intent(out) :: eps(:, :)   !! (ncomp, npoints)
    end subroutine strains_interface

    !> Global coordinates `xg(3, npoints)` of the points, in the order of their results.
    pure subroutine coordinates_interface(self, xe, xg)
      import :: element_t, dp
      class(element_t), intent(in) :: self
      real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
      real(dp), intent(out) :: xg(:, :)    !! (3, npoints)
    end subroutine coordinates_interface

    !> The weight times the Jacobian of each point, `w(npoints)` in the order of its results: the
    !! share of the element's measure the point stands for (a solid: volume, mm3, or the area of a
    !! unit-thick plane-strain slice; an interface: area, or length per unit thickness in 2D; a
    !! bar: length). They add up to the measure its stiffness integrates over.
    pure subroutine weights_interface(self, xe, w)
      import :: element_t, dp
      class(element_t), intent(in) :: self
      real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
      real(dp), intent(out) :: w(:)        !! (npoints)
    end subroutine weights_interface

    !> The smallest Jacobian of the element's mapping (a solid: the determinant; an interface or
    !! a bar: its signed surface or line Jacobian); the caller rejects values <= 0.
    pure real(dp) function jacobian_interface(self, xe)
      import :: element_t, dp
      class(element_t), intent(in) :: self
      real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    end function jacobian_interface
  end interface

contains

  !> The error message for an element rejected by its smallest Jacobian `jac` (<= 0): `label`
  !! names the element ('<k> of group <name> (nodes ...)'). A family whose Jacobian means
  !! something else (a surface, a line) overrides it to say so.
  pure function jacobian_message(self, label, jac) result(message)
    class(element_t), intent(in) :: self
    character(len=*), intent(in) :: label
    real(dp), intent(in) :: jac
    character(len=:), allocatable :: message
    message = 'element ' // label // ' has a non-positive Jacobian (' // str(jac) // &
              '): check its node order or coordinates'
  end function jacobian_message

  !> Consistent nodal forces `fe(3 nnodes)` of the uniform force `b(3)` per unit of the element's
  !! measure (a solid: per volume, N/mm3, or per area of a unit-thick plane-strain slice; a bar:
  !! per length, N/mm): the sum over the points of N_a b times the point's weight. The default,
  !! for a family with no volume or length (the zero-thickness interfaces), is no force: such an
  !! element carries no weight.
  pure subroutine element_body_force(self, xe, b, fe)
    class(element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)     !! (3, nnodes)
    real(dp), intent(in) :: b(3)
    real(dp), intent(out) :: fe(:)       !! (3 nnodes)
    fe = 0.0_dp
  end subroutine element_body_force

  !> The point stresses `sig(ncomp, npoints)` (the family's own components and frame) of the
  !! Cartesian stress tensors `tensors(3, 3, npoints)` given at its points (an in-situ stress
  !! field); `taken` is false, and sig zero, for a family whose stress is not a continuum's (a
  !! bar's axial force): such an element starts unstressed. This default is that case.
  pure subroutine element_stresses_of_tensors(self, xe, tensors, sig, taken)
    class(element_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)          !! (3, nnodes)
    real(dp), intent(in) :: tensors(:, :, :)  !! (3, 3, npoints)
    real(dp), intent(out) :: sig(:, :)        !! (ncomp, npoints)
    logical, intent(out) :: taken
    sig = 0.0_dp
    taken = .false.
  end subroutine element_stresses_of_tensors

end module feps_element
