!> Helpers shared by the material suites: a MATERIAL record built by hand, and the check that
!! the material factory rejects a bad one with a message that names its place and the fault.
module feps_material_testing
  use feps_kinds, only: dp
  use feps_testing, only: error_t, check, test_failed
  use feps_error, only: err_input, str
  use feps_model, only: material_spec_t
  use feps_material, only: material_t
  use feps_material_factory, only: new_material
  implicit none
  private

  public :: material_spec, expect_material_rejected

  !> The file and line every hand-built record claims to come from.
  character(len=*), parameter :: record_file = 'deck.inp'
  integer, parameter :: record_line = 23

contains

  !> A MATERIAL record `name` of kind `kind` (as the deck reader stores it) with numeric `keys`.
  function material_spec(name, kind, keys, values) result(spec)
    character(len=*), intent(in) :: name, kind
    character(len=*), intent(in) :: keys(:)
    real(dp), intent(in) :: values(:)
    type(material_spec_t) :: spec
    integer :: i
    spec%name = name
    spec%kind = kind
    spec%file = record_file
    spec%line = record_line
    allocate (spec%keys(size(keys)))
    do i = 1, size(keys)
      spec%keys(i) = keys(i)
    end do
    spec%values = values
  end function material_spec

  !> The factory must refuse the record with an input error that starts with its file:line and
  !! names the material and `what` (the parameter or the fault).
  subroutine expect_material_rejected(error, name, kind, keys, values, what)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in) :: name, kind, what
    character(len=*), intent(in) :: keys(:)
    real(dp), intent(in) :: values(:)
    class(material_t), allocatable :: mat
    type(error_t), allocatable :: err
    call new_material(material_spec(name, kind, keys, values), mat, err)
    if (.not. allocated(err)) then
      call test_failed(error, 'material ' // name // ': bad parameters accepted (expected an error about ' // &
                       what // ')')
      return
    end if
    call check(error, err%code == err_input .and. &
               index(err%message, record_file // ':' // str(record_line) // ':') == 1 .and. &
               index(err%message, name) > 0 .and. index(err%message, what) > 0, &
               'message "' // err%message // '" names file:line, material ' // name // ' and ' // what)
  end subroutine expect_material_rejected

end module feps_material_testing
