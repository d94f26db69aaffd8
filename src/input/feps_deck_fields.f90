!> Field helpers of the input deck's readers: required fields, numbers and ranges with the
!! file, line and field of a bad one, KEY=value options, coordinate names, coordinate-system
!! options, result names and the element and material families.
module feps_deck_fields
  use feps_strings, only: to_upper, shown, utf8_text_length
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_records, only: record_t, keyword, nfields, field_text, field_line, is_integer_text, is_real_text, &
                          real_from_text, int_in_range
  use feps_coordinate_system, only: csys_cylindrical
  use feps_model, only: model_t
  use feps_element_catalog, only: family_solid, family_interface, family_bar
  implicit none
  private

  public :: require_fields, forbid_extra_fields, get_real, get_int, parse_real, parse_int, parse_range_real, parse_range_int
  public :: key_value, check_option_keys, option_text, option_real, get_csys_option, dof_index, dof_names, check_result_name
  public :: resolve_path, material_family

contains

  !> A record with fewer than `n` fields (keyword included) is an error naming the first
  !! missing field.
  subroutine require_fields(rec, n, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: n
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: least
    if (nfields(rec) >= n) return
    least = str(n - 1) // ' fields'
    if (n == 2) least = '1 field'
    call input_error(error, rec%file, field_line(rec, nfields(rec) + 1), &
                     keyword(rec) // ' needs at least ' // least // &
                     ' after the keyword; field ' // str(nfields(rec) + 1) // ' is missing', nfields(rec) + 1)
  end subroutine require_fields

  !> A record with more than `n` fields (keyword included) is an error naming the first extra
  !! one: a field feps would otherwise ignore is a mistake the user should see.
  subroutine forbid_extra_fields(rec, n, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: n
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: most
    if (nfields(rec) <= n) return
    most = 'at most ' // str(n - 1) // ' fields'
    if (n == 2) most = 'at most 1 field'
    if (n == 1) most = 'no field'
    call input_error(error, rec%file, field_line(rec, n + 1), &
                     keyword(rec) // ' takes ' // most // ' after the keyword; "' // &
                     field_text(rec, n + 1) // '" is one too many', n + 1)
  end subroutine forbid_extra_fields

  !> Field `i` of `rec` as a finite real number; an error naming the field otherwise.
  subroutine get_real(rec, i, v, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    real(dp), intent(out) :: v
    type(error_t), allocatable, intent(out) :: error
    call parse_real(field_text(rec, i), v, error, rec, i)
  end subroutine get_real

  !> Field `i` of `rec` as an integer in lo..hi; an error naming the field otherwise.
  subroutine get_int(rec, i, lo, hi, v, error, what)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i, lo, hi
    integer, intent(out) :: v
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: what   !! its name in the message (default 'integer')
    call parse_int(field_text(rec, i), lo, hi, v, error, rec, i, what)
  end subroutine get_int

  !> `text` (field `i` of `rec`, for the message) as a finite real number.
  subroutine parse_real(text, v, error, rec, i)
    character(len=*), intent(in) :: text
    real(dp), intent(out) :: v
    type(error_t), allocatable, intent(out) :: error
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    logical :: ok
    call real_from_text(text, v, ok)
    if (ok) return
    if (is_real_text(trim(adjustl(text)))) then
      call input_error(error, rec%file, field_line(rec, i), 'number "' // trim(text) // '" is out of range ' // &
                       '(zero or a magnitude from 2.2e-308 to 1.8e308)', i)
    else
      call input_error(error, rec%file, field_line(rec, i), 'expected a number, got "' // trim(text) // '"', i)
    end if
  end subroutine parse_real

  !> `text` (field `i` of `rec`, for the message) as an integer in lo..hi (0 on error). Every
  !! integer of a deck is read with its range, before any arithmetic on it.
  subroutine parse_int(text, lo, hi, v, error, rec, i, what)
    character(len=*), intent(in) :: text
    integer, intent(in) :: lo, hi
    integer, intent(out) :: v
    type(error_t), allocatable, intent(out) :: error
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    character(len=*), intent(in), optional :: what   !! its name in the message (default 'integer')
    type(error_t), allocatable :: range
    v = 0
    if (.not. is_integer_text(trim(adjustl(text)))) then
      call input_error(error, rec%file, field_line(rec, i), 'expected an integer, got "' // trim(text) // '"', i)
      return
    end if
    call int_in_range(trim(adjustl(text)), lo, hi, v, range, what)
    if (allocated(range)) call input_error(error, rec%file, field_line(rec, i), range%message, i)
  end subroutine parse_int

  !> `text` as a real number or a range LO:HI with LO <= HI (a number: `lo` = `hi`).
  subroutine parse_range_real(text, lo, hi, error, rec, i)
    character(len=*), intent(in) :: text
    real(dp), intent(out) :: lo, hi
    type(error_t), allocatable, intent(out) :: error
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    integer :: c
    c = index(text, ':')
    if (c == 0) then
      call parse_real(text, lo, error, rec, i)
      hi = lo
      return
    end if
    call parse_real(text(:c - 1), lo, error, rec, i)
    if (allocated(error)) return
    call parse_real(text(c + 1:), hi, error, rec, i)
    if (allocated(error)) return
    if (hi < lo) call input_error(error, rec%file, field_line(rec, i), 'empty range "' // text // '" (from > to)', i)
  end subroutine parse_range_real

  !> `text` as an integer or a range LO:HI (an integer: `lo` = `hi`), each in first..last.
  subroutine parse_range_int(text, first, last, lo, hi, error, rec, i)
    character(len=*), intent(in) :: text
    integer, intent(in) :: first, last
    integer, intent(out) :: lo, hi
    type(error_t), allocatable, intent(out) :: error
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    integer :: c
    c = index(text, ':')
    if (c == 0) then
      call parse_int(text, first, last, lo, error, rec, i)
      hi = lo
      return
    end if
    call parse_int(text(:c - 1), first, last, lo, error, rec, i)
    if (allocated(error)) return
    call parse_int(text(c + 1:), first, last, hi, error, rec, i)
  end subroutine parse_range_int

  !> Field `i` of `rec` as KEY=value: `key` upper-cased, `value` as written. A field without
  !! '=' or with nothing before it is an error naming the field: 'expected <expected>, got ...'.
  subroutine key_value(rec, i, expected, key, value, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    character(len=*), intent(in) :: expected   !! what the field should look like, e.g. 'KEY=value'
    character(len=:), allocatable, intent(out) :: key, value
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: f
    integer :: eq
    f = field_text(rec, i)
    eq = index(f, '=')
    if (eq < 2) then
      call input_error(error, rec%file, field_line(rec, i), 'expected ' // expected // ', got "' // f // '"', i)
      return
    end if
    key = to_upper(f(:eq - 1))
    value = f(eq + 1:)
  end subroutine key_value

  !> Fields `first`.. of `rec` must be KEY=value options, each given once (but for the keys in
  !! `repeatable`) and, when `allowed` is given, one of those keys (upper case). A reader that
  !! looks its options up by name would otherwise ignore a misspelt or repeated one.
  subroutine check_option_keys(rec, first, error, allowed, repeatable, expected)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: first
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: allowed(:)
    character(len=*), intent(in), optional :: repeatable(:)
    character(len=*), intent(in), optional :: expected   !! the form of a field (default 'KEY=value')
    character(len=:), allocatable :: key, value, other, list, form
    integer :: i, j
    form = 'KEY=value'
    if (present(expected)) form = expected
    do i = first, nfields(rec)
      call key_value(rec, i, form, key, value, error)
      if (allocated(error)) return
      if (present(allowed)) then
        if (.not. any(allowed == key)) then
          list = trim(allowed(1))
          do j = 2, size(allowed)
            list = list // ', ' // trim(allowed(j))
          end do
          call input_error(error, rec%file, field_line(rec, i), 'unknown ' // keyword(rec) // ' option "' // key // &
                           '" (' // list // ')', i)
          return
        end if
      end if
      if (present(repeatable)) then
        if (any(repeatable == key)) cycle
      end if
      do j = first, i - 1
        call key_value(rec, j, 'KEY=value', other, value, error)
        if (other == key) then
          call input_error(error, rec%file, field_line(rec, i), &
                           key // ' is given twice (fields ' // str(j) // ' and ' // &
                           str(i) // ')', i)
          return
        end if
      end do
    end do
  end subroutine check_option_keys

  !> The text after KEY= in the first field of that key (case-insensitive).
  subroutine option_text(rec, key, text, ifield, found)
    type(record_t), intent(in) :: rec
    character(len=*), intent(in) :: key
    character(len=:), allocatable, intent(out) :: text
    integer, intent(out) :: ifield
    logical, intent(out) :: found
    integer :: i, eq
    character(len=:), allocatable :: f
    found = .false.
    ifield = 0
    text = ''
    do i = 2, nfields(rec)
      f = field_text(rec, i)
      eq = index(f, '=')
      if (eq < 2) cycle
      if (to_upper(f(:eq - 1)) == key) then
        text = f(eq + 1:)
        ifield = i
        found = .true.
        return
      end if
    end do
  end subroutine option_text

  !> The real value of option KEY=value of `rec`; `value` unchanged when the option is absent.
  subroutine option_real(rec, key, value, found, error)
    type(record_t), intent(in) :: rec
    character(len=*), intent(in) :: key
    real(dp), intent(inout) :: value
    logical, intent(out) :: found
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: ifield
    call option_text(rec, key, text, ifield, found)
    if (found) call parse_real(text, value, error, rec, ifield)
  end subroutine option_real

  !> The coordinate system named by option KEY=n of `rec` (`default` when absent); an error
  !! for a system the model does not define.
  subroutine get_csys_option(rec, model, key, default, cs, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    character(len=*), intent(in) :: key
    integer, intent(in) :: default
    integer, intent(out) :: cs
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: ifield
    logical :: found
    cs = default
    call option_text(rec, key, text, ifield, found)
    if (.not. found) return
    call parse_int(text, -huge(1), huge(1), cs, error, rec, ifield)
    if (allocated(error)) return
    if (cs < 1 .or. cs > size(model%systems)) then
      call input_error(error, rec%file, field_line(rec, ifield), 'undefined coordinate system ' // str(cs), ifield)
    end if
  end subroutine get_csys_option

  !> Direction or coordinate index from its name in a system of kind `kind`; 0 if unknown.
  pure subroutine dof_index(name, kind, dof)
    character(len=*), intent(in) :: name
    integer, intent(in) :: kind
    integer, intent(out) :: dof
    dof = 0
    select case (name)
    case ('1', 'U1')
      dof = 1
    case ('2', 'U2')
      dof = 2
    case ('3', 'U3')
      dof = 3
    end select
    if (dof /= 0) return
    if (kind == csys_cylindrical) then
      select case (name)
      case ('R', 'UR')
        dof = 1
      case ('T', 'THETA', 'UT')
        dof = 2
      case ('Z', 'UZ')
        dof = 3
      end select
    else
      select case (name)
      case ('X', 'UX')
        dof = 1
      case ('Y', 'UY')
        dof = 2
      case ('Z', 'UZ')
        dof = 3
      end select
    end if
  end subroutine dof_index

  !> The direction names `dof_index` knows in a system of kind `kind`, for messages.
  pure function dof_names(kind) result(s)
    integer, intent(in) :: kind
    character(len=:), allocatable :: s
    if (kind == csys_cylindrical) then
      s = 'R, THETA, Z'
    else
      s = 'X, Y, Z'
    end if
  end function dof_names

  !> Group, material and set names become HDF5 paths (/mesh/groups/<name>, /materials/<name>,
  !! /sets/nodes/<name>) and XDMF (XML) text: no '/', no XML markup characters, not '.' or
  !! '..', and printable text: valid UTF-8 without control characters (XML cannot hold them,
  !! and a parser stops at invalid UTF-8), shown as \xNN in the message.
  subroutine check_result_name(rec, what, name, error, field)
    type(record_t), intent(in) :: rec
    character(len=*), intent(in) :: what, name
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: field   !! the field that holds the name (default 2)
    integer :: f
    f = 2
    if (present(field)) f = field
    if (scan(name, '/<>&"''') > 0 .or. name == '.' .or. name == '..') then
      call input_error(error, rec%file, field_line(rec, f), 'the ' // what // ' name "' // shown(name) // &
                       '" may not contain / < > & " or '' nor be . or .. (it names a group in the results file)', f)
    else if (utf8_text_length(name) < len(name)) then
      call input_error(error, rec%file, field_line(rec, f), 'the ' // what // ' name "' // shown(name) // &
                       '" has a byte that is no printable text at byte ' // str(utf8_text_length(name) + 1) // &
                       ' (a control character, or not UTF-8): it names a group in the results file and ' // &
                       'the XDMF (XML) file', f)
    end if
  end subroutine check_result_name

  !> A path relative to the directory of the file that names it.
  pure function resolve_path(base, path) result(full)
    character(len=*), intent(in) :: base, path
    character(len=:), allocatable :: full
    integer :: slash
    if (len(path) > 0) then
      if (path(1:1) == '/') then
        full = path
        return
      end if
    end if
    slash = index(base, '/', back=.true.)
    full = base(:slash) // path
  end function resolve_path

  !> The element family (the element catalog's code) whose groups take a material of `kind`.
  pure integer function material_family(kind) result(family)
    character(len=*), intent(in) :: kind
    select case (kind)
    case ('interface')
      family = family_interface
    case ('bar')
      family = family_bar
    case default
      family = family_solid
    end select
  end function material_family

end module feps_deck_fields
