!> Builds material objects from the model's material parameters, checking them.
module feps_material_factory
  use feps_kinds, only: dp
  use feps_error, only: error_t, str
  use feps_model, only: material_spec_t
  use feps_material_params, only: check_known_keys, material_error, material_conflict, material_error_at, &
                                  get_unit_weight, get_k0
  use feps_material, only: material_t
  use feps_linear_elastic, only: linear_elastic_t
  use feps_interface_mohr_coulomb, only: new_interface_mohr_coulomb
  use feps_elastic_bar, only: new_elastic_bar
  use feps_matsuoka_nakai, only: new_matsuoka_nakai
  use feps_concrete_damage, only: new_concrete_damage
  implicit none
  private

  public :: new_material, material_of

contains

  !> A material from its parameters; errors name the MATERIAL record's file and line and,
  !! where one parameter is at fault, its field.
  subroutine new_material(spec, material, error)
    type(material_spec_t), intent(in) :: spec
    class(material_t), allocatable, intent(out) :: material
    type(error_t), allocatable, intent(out) :: error
    select case (spec%kind)
    case ('elastic')
      call new_linear_elastic(spec, material, error)
    case ('interface')
      call new_interface_mohr_coulomb(spec, material, error)
    case ('bar')
      call new_elastic_bar(spec, material, error)
    case ('matsuoka')
      call new_matsuoka_nakai(spec, material, error)
    case ('concrete')
      call new_concrete_damage(spec, material, error)
    case default
      call material_error_at(error, spec, 'unknown material kind "' // spec%kind // &
                             '" (ELASTIC, MATSUOKA, CONCRETE, INTERFACE, BAR)', spec%kind_field)
    end select
  end subroutine new_material

  !> The material of a MATERIAL record: a copy of the typed record the deck reader built and
  !! checked (spec%params), or, for a record built by hand or changed since (spec%set), one
  !! built and checked now by new_material.
  subroutine material_of(spec, material, error)
    type(material_spec_t), intent(in) :: spec
    class(material_t), allocatable, intent(out) :: material
    type(error_t), allocatable, intent(out) :: error
    if (allocated(spec%params)) then
      select type (params => spec%params)
      class is (material_t)
        allocate (material, source=params)
        return
      end select
    end if
    call new_material(spec, material, error)
  end subroutine material_of

  !> An isotropic elastic material from NU and one of E or G. A bad G is reported as given
  !! (not as the E derived from it), at G's field.
  subroutine new_linear_elastic(spec, material, error)
    type(material_spec_t), intent(in) :: spec
    class(material_t), allocatable, intent(out) :: material
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: e, nu, g, gamma, k0
    logical :: has_e, has_nu, has_g
    call check_known_keys(spec, ['e    ', 'nu   ', 'g    ', 'gamma', 'k0   '], error)
    if (allocated(error)) return
    call spec%get('e', e, has_e)
    call spec%get('nu', nu, has_nu)
    call spec%get('g', g, has_g)
    if (has_e .and. has_g) then
      call material_conflict(error, spec, 'give only one of E and G (with NU, either fixes the other)', 'e', 'g')
      return
    end if
    if (.not. has_nu) then
      call material_error(error, spec, 'nu is missing')
      return
    end if
    if (.not. (nu < 0.5_dp .and. nu > -1.0_dp)) then
      call material_error(error, spec, 'nu = ' // str(nu) // &
                          ' is outside (-1, 0.5): the material would not be positive definite', 'nu')
      return
    end if
    if (has_g) then
      if (.not. (g > 0.0_dp .and. g <= huge(g))) then
        call material_error(error, spec, 'G = ' // str(g) // ' must be positive and finite', 'g')
        return
      end if
      ! tested before the product, which would overflow (and trap under -ffpe-trap); a factor
      ! 2 (1 + nu) below 1 cannot make it overflow, and huge / factor would
      if (g > huge(g) / max(1.0_dp, 2.0_dp * (1.0_dp + nu))) then
        call material_error(error, spec, 'G = ' // str(g) // ' is too large: E = 2 G (1 + NU) overflows', 'g')
        return
      end if
      e = g * (2.0_dp * (1.0_dp + nu))   ! 2 G first would overflow where E does not
      has_e = .true.
    end if
    if (.not. has_e) then
      call material_error(error, spec, 'E (or G) is missing')
      return
    end if
    if (.not. (e > 0.0_dp) .or. e > huge(e)) then
      call material_error(error, spec, 'E = ' // str(e) // ' must be positive and finite', 'e')
      return
    end if
    call get_unit_weight(spec, gamma, error)
    if (.not. allocated(error)) call get_k0(spec, k0, error)
    if (allocated(error)) return
    allocate (material, source=linear_elastic_t(name=spec%name, e=e, nu=nu, unit_weight=gamma, k0=k0))
  end subroutine new_linear_elastic

end module feps_material_factory
