!> Isotropic linear elastic material (E, nu or G, nu) for solids.
module feps_linear_elastic
  use feps_kinds, only: dp
  use feps_material, only: material_t, state_elastic, modulus_warning
  use feps_elastic, only: elastic_matrix
  implicit none
  private

  type, extends(material_t), public :: linear_elastic_t
    real(dp) :: e = 0.0_dp
    real(dp) :: nu = 0.0_dp
  contains
    procedure :: elastic_tangent => linear_elastic_tangent
    procedure :: update => linear_elastic_update
    procedure :: is_linear => linear_elastic_is_linear
    procedure :: unit_warning => linear_elastic_unit_warning
  end type linear_elastic_t

contains

  pure subroutine linear_elastic_tangent(self, d)
    class(linear_elastic_t), intent(in) :: self
    real(dp), intent(out) :: d(:, :)
    d = elastic_matrix(self%e, self%nu)
  end subroutine linear_elastic_tangent

  pure subroutine linear_elastic_update(self, sig0, eps0, deps, state0, sig, state, dtan, var0, var)
    class(linear_elastic_t), intent(in) :: self
    real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
    integer, intent(in) :: state0
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(:, :)
    real(dp), intent(in), optional :: var0(:)   !! no internal variables (state_size 0)
    real(dp), intent(out), optional :: var(:)
    dtan = elastic_matrix(self%e, self%nu)
    sig = sig0 + matmul(dtan, deps)
    state = state_elastic
  end subroutine linear_elastic_update

  pure logical function linear_elastic_is_linear(self)
    class(linear_elastic_t), intent(in) :: self
    linear_elastic_is_linear = .true.
  end function linear_elastic_is_linear

  !> A Young's modulus far outside the physical range in N, mm and MPa (a unit slip).
  pure subroutine linear_elastic_unit_warning(self, warning, key)
    class(linear_elastic_t), intent(in) :: self
    character(len=:), allocatable, intent(out) :: warning, key
    warning = modulus_warning(self%e)
    key = 'e'
  end subroutine linear_elastic_unit_warning

end module feps_linear_elastic
