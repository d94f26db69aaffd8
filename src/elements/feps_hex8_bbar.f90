!> The 8-node hexahedron with the B-bar method (Hughes 1980): the volumetric part of the strain
!! is replaced by its average over the element, so the element does not lock as nu -> 0.5.
!! It keeps the shape functions, faces and 2x2x2 Gauss rule of hex8 and overrides only the
!! strain-displacement relation (B-bar matrix, stiffness, Gauss-point strains).
module feps_hex8_bbar
  use feps_kinds, only: dp
  use feps_hex8, only: hex8_t
  use feps_solid_element, only: fill_b
  implicit none
  private

  integer, parameter :: nen = 8, ng = 8

  type, extends(hex8_t), public :: hex8_bbar_t
  contains
    procedure :: element_type => hex8_bbar_element_type
    procedure :: b_matrix => hex8_bbar_b_matrix
    procedure :: stiffness => hex8_bbar_stiffness
    procedure :: strains => hex8_bbar_strains
  end type hex8_bbar_t

contains

  pure function hex8_bbar_element_type(self) result(name)
    class(hex8_bbar_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = 'hex8b'
  end function hex8_bbar_element_type

  !> Volume-averaged shape-function gradients (1/V) int dN_a/dx dV, (3, nen).
  pure subroutine mean_gradients(self, xe, dbar)
    class(hex8_bbar_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)
    real(dp), intent(out) :: dbar(3, nen)
    real(dp) :: xi(3, ng), w(ng), n(nen), dndx(3, nen), detj, vol
    integer :: g
    call self%gauss_rule(xi, w)
    dbar = 0.0_dp
    vol = 0.0_dp
    do g = 1, ng
      call self%shape_gradients(xe, xi(:, g), n, dndx, detj)
      dbar = dbar + dndx * (w(g) * detj)
      vol = vol + w(g) * detj
    end do
    if (vol > 0.0_dp) dbar = dbar / vol
  end subroutine mean_gradients

  !> B-bar at xi: the standard B with the dilatational part of its normal rows replaced by the
  !! element average: B(i, (a,j)) += (dbar_aj - dN_a/dx_j) / 3 for the normal rows i = 1..3.
  pure subroutine bbar_from(dndx, dbar, b)
    real(dp), intent(in) :: dndx(3, nen), dbar(3, nen)
    real(dp), intent(out) :: b(6, 3 * nen)
    integer :: a, c
    call fill_b(dndx, b)
    do a = 1, nen
      c = 3 * (a - 1)
      b(1:3, c + 1) = b(1:3, c + 1) + (dbar(1, a) - dndx(1, a)) / 3.0_dp
      b(1:3, c + 2) = b(1:3, c + 2) + (dbar(2, a) - dndx(2, a)) / 3.0_dp
      b(1:3, c + 3) = b(1:3, c + 3) + (dbar(3, a) - dndx(3, a)) / 3.0_dp
    end do
  end subroutine bbar_from

  pure subroutine hex8_bbar_b_matrix(self, xe, xi, b, detj)
    class(hex8_bbar_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)
    real(dp), intent(in) :: xi(3)
    real(dp), intent(out) :: b(:, :)
    real(dp), intent(out) :: detj
    real(dp) :: n(nen), dndx(3, nen), dbar(3, nen)
    call mean_gradients(self, xe, dbar)
    call self%shape_gradients(xe, xi, n, dndx, detj)
    call bbar_from(dndx, dbar, b)
  end subroutine hex8_bbar_b_matrix

  pure subroutine hex8_bbar_stiffness(self, xe, d, ke)
    class(hex8_bbar_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)
    real(dp), intent(in) :: d(:, :, :)
    real(dp), intent(out) :: ke(:, :)
    real(dp) :: xi(3, ng), w(ng), n(nen), dndx(3, nen), dbar(3, nen), b(6, 3 * nen), detj
    integer :: g
    call self%gauss_rule(xi, w)
    call mean_gradients(self, xe, dbar)
    ke = 0.0_dp
    do g = 1, ng
      call self%shape_gradients(xe, xi(:, g), n, dndx, detj)
      call bbar_from(dndx, dbar, b)
      ke = ke + matmul(transpose(b), matmul(d(:, :, g), b)) * (w(g) * detj)
    end do
  end subroutine hex8_bbar_stiffness

  pure subroutine hex8_bbar_strains(self, xe, ue, eps)
    class(hex8_bbar_t), intent(in) :: self
    real(dp), intent(in) :: xe(:, :)
    real(dp), intent(in) :: ue(:)
    real(dp), intent(out) :: eps(:, :)
    real(dp) :: xi(3, ng), w(ng), n(nen), dndx(3, nen), dbar(3, nen), b(6, 3 * nen), detj
    integer :: g
    call self%gauss_rule(xi, w)
    call mean_gradients(self, xe, dbar)
    do g = 1, ng
      call self%shape_gradients(xe, xi(:, g), n, dndx, detj)
      call bbar_from(dndx, dbar, b)
      eps(:, g) = matmul(b, ue)
    end do
  end subroutine hex8_bbar_strains

end module feps_hex8_bbar
