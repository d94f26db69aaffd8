!> Linear elastic bar material (thesis eq. 2.5.10): Young's modulus E and cross-section area A.
!!
!! One component: the "strain" is the axial strain and the "stress" is the axial force
!! N = E A eps (tension positive), so the material matrix is d(1, 1) = E A. Units follow the
!! model (e.g. E in MPa = N/mm^2 and A in mm^2 give N in N).
module feps_elastic_bar
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: material_spec_t
  use feps_material_params, only: check_known_keys, get_parameter, get_unit_weight
  use feps_material, only: material_t, state_elastic, modulus_warning
  implicit none
  private

  public :: new_elastic_bar

  !> Elastic bar: Young's modulus `e` and cross-section area `a` (both positive).
  type, extends(material_t), public :: elastic_bar_t
    real(dp) :: e = 0.0_dp
    real(dp) :: a = 0.0_dp
  contains
    procedure :: elastic_tangent => elastic_bar_tangent
    procedure :: update => elastic_bar_update
    procedure :: is_linear => elastic_bar_is_linear
    procedure :: section_area => elastic_bar_section_area
    procedure :: unit_warning => elastic_bar_unit_warning
  end type elastic_bar_t

contains

  !> Axial stiffness: d(1, 1) = E A (any further entries of a larger `d` are zero).
  pure subroutine elastic_bar_tangent(self, d)
    class(elastic_bar_t), intent(in) :: self
    real(dp), intent(out) :: d(:, :)
    d = 0.0_dp
    d(1, 1) = self%e * self%a
  end subroutine elastic_bar_tangent

  !> Axial force N = N0 + E A deps, state elastic, tangent E A.
  pure subroutine elastic_bar_update(self, sig0, eps0, deps, state0, sig, state, dtan, var0, var)
    class(elastic_bar_t), intent(in) :: self
    real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
    integer, intent(in) :: state0
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(:, :)
    real(dp), intent(in), optional :: var0(:)   !! no internal variables (state_size 0)
    real(dp), intent(out), optional :: var(:)
    call self%elastic_tangent(dtan)
    sig = sig0 + matmul(dtan, deps)
    state = state_elastic
  end subroutine elastic_bar_update

  pure logical function elastic_bar_is_linear(self)
    class(elastic_bar_t), intent(in) :: self
    elastic_bar_is_linear = .true.
  end function elastic_bar_is_linear

  !> The bar's cross-section area A: its point stress is the axial force, A times the stress.
  pure real(dp) function elastic_bar_section_area(self) result(area)
    class(elastic_bar_t), intent(in) :: self
    area = self%a
  end function elastic_bar_section_area

  !> An elastic bar from MATERIAL parameters E and A (both required, positive and finite);
  !! unknown keys are rejected. Errors name the record's file and line and the parameter (and
  !! its field, when it was given).
  subroutine new_elastic_bar(spec, material, error)
    type(material_spec_t), intent(in) :: spec
    class(material_t), allocatable, intent(out) :: material
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: known(3) = ['e    ', 'a    ', 'gamma']
    real(dp) :: e, a, gamma
    call check_known_keys(spec, known, error)
    if (.not. allocated(error)) call get_parameter(spec, 'e', e, error, positive=.true.)
    if (.not. allocated(error)) call get_parameter(spec, 'a', a, error, positive=.true.)
    if (.not. allocated(error)) call get_unit_weight(spec, gamma, error)
    if (.not. allocated(error)) allocate (material, source=elastic_bar_t(name=spec%name, e=e, a=a, unit_weight=gamma))
  end subroutine new_elastic_bar


  !> A Young's modulus far outside the physical range in N, mm and MPa (a unit slip).
  pure subroutine elastic_bar_unit_warning(self, warning, key)
    class(elastic_bar_t), intent(in) :: self
    character(len=:), allocatable, intent(out) :: warning, key
    warning = modulus_warning(self%e)
    key = 'e'
  end subroutine elastic_bar_unit_warning

end module feps_elastic_bar
