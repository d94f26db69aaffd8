!> Reading and checking a material's MATERIAL-record parameters: one place for the messages
!! (naming the record's file and line, the material and the parameter).
module feps_material_params
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: material_spec_t
  use feps_strings, only: to_upper
  implicit none
  private

  public :: check_known_keys, get_parameter, material_error

contains

  !> Error "material NAME: MESSAGE" at the MATERIAL record.
  subroutine material_error(error, spec, message)
    type(error_t), allocatable, intent(out) :: error
    type(material_spec_t), intent(in) :: spec
    character(len=*), intent(in) :: message
    call input_error(error, spec%file, spec%line, 'material ' // spec%name // ': ' // message)
  end subroutine material_error

  !> Every given key must be one of `known` (lower case), so a misspelt key is not ignored.
  subroutine check_known_keys(spec, known, error)
    type(material_spec_t), intent(in) :: spec
    character(len=*), intent(in) :: known(:)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: expected
    integer :: i
    if (.not. allocated(spec%keys)) return
    expected = to_upper(trim(known(1)))
    do i = 2, size(known)
      expected = expected // ', ' // to_upper(trim(known(i)))
    end do
    do i = 1, size(spec%keys)
      if (all(trim(spec%keys(i)) /= known)) then
        call material_error(error, spec, 'unknown parameter ' // to_upper(trim(spec%keys(i))) // &
                            ' (expected ' // expected // ')')
        return
      end if
    end do
  end subroutine check_known_keys

  !> A parameter's value: an error if it is missing (unless `default` is given) or, with
  !! `positive`, not positive and finite.
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
        call material_error(error, spec, to_upper(key) // ' = ' // str(value) // ' must be positive and finite')
      end if
    end if
  end subroutine get_parameter

end module feps_material_params
