!> Reading and checking a material's MATERIAL-record parameters: one place for the messages
!! (naming the record's file and line, the field at fault, the material and the parameter).
module feps_material_params
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: material_spec_t
  use feps_strings, only: to_upper
  implicit none
  private

  public :: check_known_keys, get_parameter, get_unit_weight, get_k0, material_error, material_conflict, material_error_at

contains

  !> Error "material NAME: MESSAGE" at the MATERIAL record; with `key`, at the field that
  !! gave it (when the record's field numbers are known and the key was given).
  subroutine material_error(error, spec, message, key)
    type(error_t), allocatable, intent(out) :: error
    type(material_spec_t), intent(in) :: spec
    character(len=*), intent(in) :: message
    character(len=*), intent(in), optional :: key
    integer :: field
    field = 0
    if (present(key)) field = spec%field_of(key)
    call material_error_at(error, spec, message, field)
  end subroutine material_error

  !> Error about two keys that may not be given together, at the field of the later one
  !! (the first is fine on its own: the second is what breaks the record).
  subroutine material_conflict(error, spec, message, key1, key2)
    type(error_t), allocatable, intent(out) :: error
    type(material_spec_t), intent(in) :: spec
    character(len=*), intent(in) :: message, key1, key2
    call material_error_at(error, spec, message, max(spec%field_of(key1), spec%field_of(key2)))
  end subroutine material_conflict

  !> Error "material NAME: MESSAGE" at field `field` of the MATERIAL record (0: no field).
  subroutine material_error_at(error, spec, message, field)
    type(error_t), allocatable, intent(out) :: error
    type(material_spec_t), intent(in) :: spec
    character(len=*), intent(in) :: message
    integer, intent(in) :: field
    if (field > 0) then
      call input_error(error, spec%file, spec%line, 'material ' // spec%name // ': ' // message, field)
    else
      call input_error(error, spec%file, spec%line, 'material ' // spec%name // ': ' // message)
    end if
  end subroutine material_error_at

  !> Every given key must be one of `known` (lower case), so a misspelt key is not ignored;
  !! the error names the first unknown key's field.
  subroutine check_known_keys(spec, known, error)
    type(material_spec_t), intent(in) :: spec
    character(len=*), intent(in) :: known(:)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: expected
    integer :: i, field
    if (.not. allocated(spec%keys)) return
    expected = to_upper(trim(known(1)))
    do i = 2, size(known)
      expected = expected // ', ' // to_upper(trim(known(i)))
    end do
    do i = 1, size(spec%keys)
      if (all(trim(spec%keys(i)) /= known)) then
        field = 0
        if (allocated(spec%fields)) then
          if (i <= size(spec%fields)) field = spec%fields(i)
        end if
        call material_error_at(error, spec, 'unknown parameter ' // to_upper(trim(spec%keys(i))) // &
                               ' (expected ' // expected // ')', field)
        return
      end if
    end do
  end subroutine check_known_keys

  !> A parameter's value: an error if it is missing (unless `default` is given; no field is at
  !! fault) or, with `positive`, not positive and finite (naming the key's field).
  subroutine get_parameter(spec, key, value, error, default, positive)
    type(material_spec_t), intent(in) :: spec
    character(len=*), intent(in) :: key
    real(dp), intent(out) :: value
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in), optional :: default
    logical, intent(in), optional :: positive
    logical :: found
    call spec%get(key, value, found)
    if (.not. found) then
      if (present(default)) then
        value = default
      else
        call material_error(error, spec, to_upper(key) // ' is missing')
      end if
      return
    end if
    if (present(positive)) then
      if (positive .and. .not. (value > 0.0_dp .and. value <= huge(value))) then
        call material_error(error, spec, to_upper(key) // ' = ' // str(value) // ' must be positive and finite', key)
      end if
    end if
  end subroutine get_parameter

  !> GAMMA, the unit weight (N/mm3; 0 when not given: a weightless material, as the thesis's):
  !! zero or positive and finite, else an error naming its field.
  subroutine get_unit_weight(spec, gamma, error)
    type(material_spec_t), intent(in) :: spec
    real(dp), intent(out) :: gamma
    type(error_t), allocatable, intent(out) :: error
    call get_parameter(spec, 'gamma', gamma, error, default=0.0_dp)
    if (allocated(error)) return
    if (.not. (gamma >= 0.0_dp .and. gamma <= huge(gamma))) &
      call material_error(error, spec, 'GAMMA = ' // str(gamma) // ' must be zero or positive and finite ' // &
                          '(a unit weight, N/mm3)', 'gamma')
  end subroutine get_unit_weight

  !> K0, the ratio of horizontal to vertical in-situ stress of a ground material (-1 when not
  !! given: not ground); positive and at most `max_k0`, else an error naming its field.
  subroutine get_k0(spec, k0, error)
    type(material_spec_t), intent(in) :: spec
    real(dp), intent(out) :: k0
    type(error_t), allocatable, intent(out) :: error
    ! Heavily overconsolidated clays reach K0 of 3 at most; beyond 10 it is a slip of the pen.
    real(dp), parameter :: max_k0 = 10.0_dp
    logical :: found
    call spec%get('k0', k0, found)
    if (.not. found) then
      k0 = -1.0_dp
      return
    end if
    if (.not. (k0 > 0.0_dp .and. k0 <= max_k0)) &
      call material_error(error, spec, 'K0 = ' // str(k0) // ' must lie in (0, 10] (the ratio of horizontal ' // &
                          'to vertical in-situ stress)', 'k0')
  end subroutine get_k0

end module feps_material_params
