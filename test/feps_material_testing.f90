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

  public :: material_spec, record_fields, expect_material_rejected

  !> The file and line every hand-built record claims to come from.
  character(len=*), parameter :: record_file = 'deck.inp'
  integer, parameter :: record_line = 23

contains

  !> A MATERIAL record `name` of kind `kind` (as the deck reader stores it) with numeric `keys`;
  !! with `fields`, each key's field number on the record (without, none is known and no
  !! error may name a field).
  function material_spec(name, kind, keys, values, fields) result(spec)
    character(len=*), intent(in) :: name, kind
    character(len=*), intent(in) :: keys(:)
    real(dp), intent(in) :: values(:)
    integer, intent(in), optional :: fields(:)
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
    if (present(fields)) then
      spec%fields = fields
      spec%kind_field = 3
    end if
  end function material_spec

  !> The field numbers the deck reader gives `n` keys written in order after MATERIAL, name
  !! and kind: 4, 5, ..., n + 3.
  pure function record_fields(n) result(fields)
    integer, intent(in) :: n
    integer :: fields(n)
    integer :: i
    fields = [(i + 3, i = 1, n)]
  end function record_fields

  !> The factory must refuse the record with an input error that starts with its file:line and
  !! names the material and `what` (the parameter or the fault). Without `field` the record
  !! carries no field numbers and the message must name none; with it the record carries
  !! them as the deck reader would (record_fields) and the message must name field `field`
  !! (none if `field` is 0: no one field is at fault, e.g. a missing key).
  subroutine expect_material_rejected(error, name, kind, keys, values, what, field)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in) :: name, kind, what
    character(len=*), intent(in) :: keys(:)
    real(dp), intent(in) :: values(:)
    integer, intent(in), optional :: field
    class(material_t), allocatable :: mat
    type(error_t), allocatable :: err
    character(len=:), allocatable :: place
    place = record_file // ':' // str(record_line) // ': '
    if (present(field)) then
      call new_material(material_spec(name, kind, keys, values, record_fields(size(keys))), mat, err)
      if (field > 0) place = place // 'field ' // str(field) // ': '
    else
      call new_material(material_spec(name, kind, keys, values), mat, err)
    end if
    if (.not. allocated(err)) then
      call test_failed(error, 'material ' // name // ': bad parameters accepted (expected an error about ' // &
                       what // ')')
      return
    end if
    ! The place is followed at once by the material: a field is named exactly when expected.
    call check(error, err%code == err_input .and. &
               index(err%message, place // 'material ' // name // ': ') == 1 .and. index(err%message, what) > 0, &
               'message "' // err%message // '" starts "' // place // 'material ' // name // ': " and names ' // what)
  end subroutine expect_material_rejected

end module feps_material_testing
