!> Records of comma-separated fields, shared by the input-deck reader and the DATAIN reader.
!!
!! Lexical rules (SPEC section 2):
!! - fields are separated by commas and trimmed; tabs and carriage returns count as blanks;
!! - `!` starts a comment that runs to the end of the line; blank lines are ignored;
!! - one trailing comma on a line is allowed and does not make an empty last field;
!!   any other empty field (`a,,b`, `,a`, `a,,`) is the error "empty field";
!! - a line whose first field begins with a digit, `+`, `-` or `.` continues the previous
!!   record (Table 2.1 continues an element record on the next line); any other line starts
!!   a new record. A continuation line before any record is an error.
!!
!! Every field remembers its line, so errors name file, line and field number (the field
!! number counts from 1 over the whole record, continuation lines included). A missing
!! field is reported on the record's last line, where it should have been.
module feps_records
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use feps_strings, only: to_upper
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, input_error, str, err_input_file, err_input
  use feps_files, only: file_kind, file_kind_text, file_regular
  implicit none
  private

  public :: field_t, record_t
  public :: read_records, records_from_text
  public :: keyword, nfields, field_text, field_line, field_real, field_int, get_option
  public :: record_error, is_integer_text, is_real_text, real_from_text, int_in_range

  !> The longest line feps reads (characters, the end of line not counted): a record longer
  !! than that continues on the next line. A longer line is an input error naming it, read
  !! no further (docs/input-format.md).
  integer, parameter, public :: max_line_length = 100000

  !> One field of a record: its trimmed text and the line it is on.
  type :: field_t
    character(len=:), allocatable :: text
    integer :: line = 0
  end type field_t

  !> One record: file name, line of its first line, and its fields (keyword first).
  type :: record_t
    character(len=:), allocatable :: file
    integer :: line = 0
    type(field_t), allocatable :: fields(:)
  end type record_t

  !> Records being collected from the lines of one file. The fields of the last record grow in
  !! `open` (doubling its size), so that a record continued over many lines is built in linear
  !! time; they move to the record when the next record starts or the file ends.
  type :: record_builder_t
    type(record_t), allocatable :: records(:)
    integer :: nrec = 0
    type(field_t), allocatable :: open(:)
    integer :: nopen = 0
  end type record_builder_t

  character(len=*), parameter :: continuation_start = '0123456789+-.'

contains

  !> Read a text file into records (rules in the module header).
  !! Errors: err_input_file if the file cannot be opened or read; err_input for an empty field,
  !! a continuation line before any record, or a file without records.
  subroutine read_records(path, records, error)
    character(len=*), intent(in) :: path
    type(record_t), allocatable, intent(out) :: records(:)
    type(error_t), allocatable, intent(out) :: error
    type(record_builder_t) :: builder
    character(len=:), allocatable :: buffer
    character(len=256) :: iomsg
    integer :: unit, iostat, lineno, length, kind
    logical :: eof, too_long

    ! Only a regular file is read: a FIFO would block at open, a device such as /dev/zero
    ! never ends, and a directory opens and reads as an empty file.
    kind = file_kind(path)
    if (kind /= file_regular) then
      call fatal_error(error, err_input_file, path // ': cannot open file: ' // file_kind_text(kind))
      return
    end if
    open (newunit=unit, file=path, status='old', action='read', form='formatted', &
          access='sequential', iostat=iostat, iomsg=iomsg)
    if (iostat /= 0) then
      call fatal_error(error, err_input_file, path // ': cannot open file: ' // trim(iomsg))
      return
    end if
    allocate (character(len=max_line_length) :: buffer)
    lineno = 0
    do
      call read_line(unit, buffer, length, eof, too_long, iostat, iomsg)
      if (iostat /= 0) then
        call fatal_error(error, err_input_file, path // ':' // str(lineno + 1) // ': cannot read: ' // trim(iomsg))
        exit
      end if
      if (eof) exit
      lineno = lineno + 1
      if (too_long) then
        call input_error(error, path, lineno, 'line longer than ' // str(max_line_length) // &
                         ' characters, the most feps reads in one line (continue a record on the next line)')
        exit
      end if
      if (lineno == huge(lineno)) then
        call input_error(error, path, lineno, 'more lines than feps reads in one file (' // str(huge(lineno)) // ')')
        exit
      end if
      call add_line(builder, path, buffer(:length), lineno, error)
      if (allocated(error)) exit
    end do
    close (unit)
    if (allocated(error)) return
    call finish_records(builder, path, records, error)
  end subroutine read_records

  !> Build records from lines held in memory, as if they were the file `name`
  !! (line numbers are the array indices). Same rules and errors as `read_records`.
  subroutine records_from_text(name, lines, records, error)
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: lines(:)
    type(record_t), allocatable, intent(out) :: records(:)
    type(error_t), allocatable, intent(out) :: error
    type(record_builder_t) :: builder
    integer :: i
    do i = 1, size(lines)
      call add_line(builder, name, lines(i), i, error)
      if (allocated(error)) return
    end do
    call finish_records(builder, name, records, error)
  end subroutine records_from_text

  !> First field upper-cased ('' for a record without fields).
  pure function keyword(rec) result(key)
    type(record_t), intent(in) :: rec
    character(len=:), allocatable :: key
    if (nfields(rec) > 0) then
      key = to_upper(rec%fields(1)%text)
    else
      key = ''
    end if
  end function keyword

  !> Number of fields, keyword included.
  pure integer function nfields(rec)
    type(record_t), intent(in) :: rec
    if (allocated(rec%fields)) then
      nfields = size(rec%fields)
    else
      nfields = 0
    end if
  end function nfields

  !> Text of field i ('' if the record has fewer fields).
  pure function field_text(rec, i) result(text)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    character(len=:), allocatable :: text
    if (i >= 1 .and. i <= nfields(rec)) then
      text = rec%fields(i)%text
    else
      text = ''
    end if
  end function field_text

  !> Line of field i; for a missing field, the record's last line.
  pure integer function field_line(rec, i)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    integer :: n
    n = nfields(rec)
    if (i >= 1 .and. i <= n) then
      field_line = rec%fields(i)%line
    else if (n > 0) then
      field_line = rec%fields(n)%line
    else
      field_line = rec%line
    end if
  end function field_line

  !> Input error at a record: "FILE:LINE: field I: MESSAGE" when `field` is given (the line
  !! is that field's), else "FILE:LINE: MESSAGE" with the record's first line.
  pure subroutine record_error(error, rec, message, field)
    type(error_t), allocatable, intent(out) :: error
    type(record_t), intent(in) :: rec
    character(len=*), intent(in) :: message
    integer, intent(in), optional :: field
    if (present(field)) then
      call input_error(error, rec%file, field_line(rec, field), message, field)
    else
      call input_error(error, rec%file, rec%line, message)
    end if
  end subroutine record_error

  !> Field i as a real number; error if it is missing or not a number.
  pure subroutine field_real(rec, i, value, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    real(dp), intent(out) :: value
    type(error_t), allocatable, intent(out) :: error
    logical :: ok
    value = 0.0_dp
    if (i > nfields(rec)) then
      call record_error(error, rec, 'missing field: expected a real number', i)
      return
    end if
    if (.not. is_real_text(rec%fields(i)%text)) then
      call record_error(error, rec, "expected a real number, got '" // rec%fields(i)%text // "'", i)
      return
    end if
    call real_from_text(rec%fields(i)%text, value, ok)
    if (.not. ok) call record_error(error, rec, "real number out of range: '" // &
                                    rec%fields(i)%text // "' (zero or a magnitude from 2.2e-308 to 1.8e308)", i)
  end subroutine field_real

  !> Field i as an integer in lo..hi; error if it is missing, not an integer or outside that
  !! range (`what` names it in the message, default 'integer'). Every integer of a deck is read
  !! with its range, so that no later arithmetic on it (a count negated, multiplied, added up)
  !! can overflow.
  pure subroutine field_int(rec, i, value, error, lo, hi, what)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    integer, intent(out) :: value
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in) :: lo, hi
    character(len=*), intent(in), optional :: what
    type(error_t), allocatable :: range
    if (i > nfields(rec)) then
      value = 0
      call record_error(error, rec, 'missing field: expected an integer', i)
      return
    end if
    if (.not. is_integer_text(rec%fields(i)%text)) then
      value = 0
      call record_error(error, rec, "expected an integer, got '" // rec%fields(i)%text // "'", i)
      return
    end if
    call int_in_range(rec%fields(i)%text, lo, hi, value, range, what)
    if (allocated(range)) call record_error(error, rec, range%message, i)
  end subroutine field_int

  !> `text` (integer syntax: is_integer_text) as an integer in lo..hi; otherwise `value` = 0
  !! and an error whose message (no place: the caller adds it) names the range.
  pure subroutine int_in_range(text, lo, hi, value, error, what)
    character(len=*), intent(in) :: text
    integer, intent(in) :: lo, hi
    integer, intent(out) :: value
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: what
    integer(i8) :: wide
    integer :: iostat, first
    character(len=:), allocatable :: name
    value = 0
    name = 'integer'
    if (present(what)) name = what
    ! leading zeros aside, more than 18 digits cannot be in range (and could overflow i8)
    first = verify(text, '+-0')
    iostat = 1
    if (first == 0) then
      wide = 0
      iostat = 0
    else if (len(text) - first + 1 <= 18) then
      read (text, *, iostat=iostat) wide
    end if
    if (iostat == 0) then
      if (wide >= lo .and. wide <= hi) then
        value = int(wide)
        return
      end if
    end if
    call fatal_error(error, err_input, name // ' ' // trim(adjustl(text)) // ' is outside the allowed range ' // &
                     str(lo) // '..' // str(hi))
  end subroutine int_in_range

  !> Look for a field `key=value` (key case-insensitive, blanks around `=` allowed);
  !! `value_text` is the trimmed text after `=` ('' if not found), `index` the field number
  !! (0 if not found). The first matching field wins.
  pure subroutine get_option(rec, key, value_text, found, index)
    type(record_t), intent(in) :: rec
    character(len=*), intent(in) :: key
    character(len=:), allocatable, intent(out) :: value_text
    logical, intent(out) :: found
    integer, intent(out), optional :: index
    integer :: i, eq
    found = .false.
    value_text = ''
    if (present(index)) index = 0
    do i = 1, nfields(rec)
      eq = scan(rec%fields(i)%text, '=')
      if (eq == 0) cycle
      if (to_upper(trim(adjustl(rec%fields(i)%text(:eq - 1)))) /= to_upper(trim(adjustl(key)))) cycle
      found = .true.
      value_text = trim(adjustl(rec%fields(i)%text(eq + 1:)))
      if (present(index)) index = i
      return
    end do
  end subroutine get_option

  !> Upper-case copy of a string (ASCII letters only).

  !> True for [sign] digits.
  pure logical function is_integer_text(text)
    character(len=*), intent(in) :: text
    integer :: first
    is_integer_text = .false.
    if (len(text) == 0) return
    first = 1
    if (text(1:1) == '+' .or. text(1:1) == '-') first = 2
    if (first > len(text)) return
    is_integer_text = verify(text(first:), '0123456789') == 0
  end function is_integer_text

  !> The number `text` holds (blanks around it aside): `ok` when it has the syntax of
  !! is_real_text and is zero or a normal double (magnitude 2.2e-308 .. 1.8e308); otherwise
  !! `v` = 0. The syntax comes first: a list-directed read alone takes '100-1' as 100e-1. A
  !! subnormal number (1e-320) is refused as out of range: it has lost digits, and arithmetic on
  !! it runs at a fraction of the normal speed (an E = 1e-320 took 15 s to be refused).
  pure subroutine real_from_text(text, v, ok)
    character(len=*), intent(in) :: text
    real(dp), intent(out) :: v
    logical, intent(out) :: ok
    integer :: ios
    v = 0.0_dp
    ok = .false.
    if (.not. is_real_text(trim(adjustl(text)))) return
    read (text, *, iostat=ios) v
    if (ios == 0) ok = ieee_is_finite(v)
    if (ok .and. v /= 0.0_dp) ok = abs(v) >= tiny(v)
    if (.not. ok) v = 0.0_dp
  end subroutine real_from_text

  !> True for [sign] mantissa [exponent]: the mantissa has digits with at most one '.',
  !! the exponent is e, E, d or D, an optional sign and digits.
  pure logical function is_real_text(text)
    character(len=*), intent(in) :: text
    integer :: pos, ndigits, n
    is_real_text = .false.
    n = len(text)
    pos = 1
    if (n == 0) return
    if (text(1:1) == '+' .or. text(1:1) == '-') pos = 2
    ndigits = 0
    do while (pos <= n)
      if (verify(text(pos:pos), '0123456789') /= 0) exit
      ndigits = ndigits + 1
      pos = pos + 1
    end do
    if (pos <= n) then
      if (text(pos:pos) == '.') then
        pos = pos + 1
        do while (pos <= n)
          if (verify(text(pos:pos), '0123456789') /= 0) exit
          ndigits = ndigits + 1
          pos = pos + 1
        end do
      end if
    end if
    if (ndigits == 0) return
    if (pos <= n) then
      if (scan(text(pos:pos), 'eEdD') == 0) return
      pos = pos + 1
      if (pos <= n) then
        if (text(pos:pos) == '+' .or. text(pos:pos) == '-') pos = pos + 1
      end if
      if (pos > n) return
      if (verify(text(pos:), '0123456789') /= 0) return
    end if
    is_real_text = .true.
  end function is_real_text

  ! ---- private ----

  !> Split one line into fields and add them as a new record or as a continuation.
  subroutine add_line(builder, name, raw, lineno, error)
    type(record_builder_t), intent(inout) :: builder
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: raw
    integer, intent(in) :: lineno
    type(error_t), allocatable, intent(out) :: error
    character(len=len(raw)) :: line
    type(field_t), allocatable :: parts(:)
    integer :: i, nparts, first_field, bang, start, comma
    logical :: continues

    line = raw
    do i = 1, len(line)
      if (line(i:i) == achar(9) .or. line(i:i) == achar(13)) line(i:i) = ' '
    end do
    bang = index(line, '!')
    if (bang > 0) line(bang:) = ' '
    if (len_trim(line) == 0) return

    ! count fields first, then cut them out
    nparts = 1
    do i = 1, len_trim(line)
      if (line(i:i) == ',') nparts = nparts + 1
    end do
    allocate (parts(nparts))
    start = 1
    do i = 1, nparts
      comma = index(line(start:), ',')
      if (comma == 0) then
        parts(i)%text = trim(adjustl(line(start:len_trim(line))))
      else
        parts(i)%text = trim(adjustl(line(start:start + comma - 2)))
        start = start + comma
      end if
      parts(i)%line = lineno
    end do
    ! one trailing comma is allowed
    if (nparts > 1 .and. len(parts(nparts)%text) == 0) nparts = nparts - 1

    continues = .false.
    if (len(parts(1)%text) > 0) continues = scan(parts(1)%text(1:1), continuation_start) == 1
    if (continues .and. builder%nrec == 0) then
      call input_error(error, name, lineno, 'continuation line (it begins with a number) before any record')
      return
    end if
    first_field = 0
    if (continues) first_field = builder%nopen
    do i = 1, nparts
      if (len(parts(i)%text) == 0) then
        call input_error(error, name, lineno, 'empty field', first_field + i)
        return
      end if
    end do

    if (.not. continues) call push_record(builder, name, lineno)
    call append_fields(builder, parts(1:nparts))
  end subroutine add_line

  !> Add fields to the last record's growing list.
  subroutine append_fields(builder, parts)
    type(record_builder_t), intent(inout) :: builder
    type(field_t), intent(inout) :: parts(:)
    type(field_t), allocatable :: bigger(:)
    integer :: i
    if (.not. allocated(builder%open)) allocate (builder%open(16))
    if (builder%nopen + size(parts) > size(builder%open)) then
      allocate (bigger(max(2 * size(builder%open), builder%nopen + size(parts))))
      do i = 1, builder%nopen
        call move_alloc(builder%open(i)%text, bigger(i)%text)
        bigger(i)%line = builder%open(i)%line
      end do
      call move_alloc(bigger, builder%open)
    end if
    do i = 1, size(parts)
      call move_alloc(parts(i)%text, builder%open(builder%nopen + i)%text)
      builder%open(builder%nopen + i)%line = parts(i)%line
    end do
    builder%nopen = builder%nopen + size(parts)
  end subroutine append_fields

  !> The last record takes the fields collected for it.
  subroutine close_record(builder)
    type(record_builder_t), intent(inout) :: builder
    integer :: i
    if (builder%nrec == 0) return
    associate (rec => builder%records(builder%nrec))
      if (allocated(rec%fields)) return
      allocate (rec%fields(builder%nopen))
      do i = 1, builder%nopen
        call move_alloc(builder%open(i)%text, rec%fields(i)%text)
        rec%fields(i)%line = builder%open(i)%line
      end do
    end associate
    builder%nopen = 0
  end subroutine close_record

  !> Start a new record (its fields follow by append_fields).
  subroutine push_record(builder, name, lineno)
    type(record_builder_t), intent(inout) :: builder
    character(len=*), intent(in) :: name
    integer, intent(in) :: lineno
    type(record_t), allocatable :: bigger(:)
    integer :: i
    call close_record(builder)
    if (.not. allocated(builder%records)) allocate (builder%records(64))
    if (builder%nrec == size(builder%records)) then
      allocate (bigger(2 * size(builder%records)))
      do i = 1, builder%nrec
        call move_record(builder%records(i), bigger(i))
      end do
      call move_alloc(bigger, builder%records)
    end if
    builder%nrec = builder%nrec + 1
    associate (rec => builder%records(builder%nrec))
      rec%file = name
      rec%line = lineno
    end associate
  end subroutine push_record

  !> Move a record's allocatable parts without copying the fields.
  subroutine move_record(from, to)
    type(record_t), intent(inout) :: from
    type(record_t), intent(inout) :: to
    call move_alloc(from%file, to%file)
    to%line = from%line
    call move_alloc(from%fields, to%fields)
  end subroutine move_record

  subroutine finish_records(builder, name, records, error)
    type(record_builder_t), intent(inout) :: builder
    character(len=*), intent(in) :: name
    type(record_t), allocatable, intent(out) :: records(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: i
    call close_record(builder)
    if (builder%nrec == 0) then
      call fatal_error(error, err_input, name // ': empty file (no records)')
      allocate (records(0))
      return
    end if
    allocate (records(builder%nrec))
    do i = 1, builder%nrec
      call move_record(builder%records(i), records(i))
    end do
  end subroutine finish_records

  !> Read one line into `buffer(:length)` in pieces of 512 characters, in time linear in its
  !! length; `eof` at the end of the file; `too_long` when it has more than len(buffer)
  !! characters (the rest of it is not read: the caller stops there).
  subroutine read_line(unit, buffer, length, eof, too_long, iostat, iomsg)
    integer, intent(in) :: unit
    character(len=*), intent(inout) :: buffer
    integer, intent(out) :: length
    logical, intent(out) :: eof, too_long
    integer, intent(out) :: iostat
    character(len=*), intent(inout) :: iomsg
    character(len=512) :: chunk
    integer :: nread
    length = 0
    eof = .false.
    too_long = .false.
    do
      read (unit, '(a)', advance='no', iostat=iostat, iomsg=iomsg, size=nread) chunk
      if (length + nread > len(buffer)) then
        too_long = .true.
        iostat = 0
        return
      end if
      buffer(length + 1:length + nread) = chunk(:nread)
      length = length + nread
      if (is_iostat_eor(iostat)) then
        iostat = 0
        return
      else if (is_iostat_end(iostat)) then
        ! a last line without a newline still counts; the next call reports the end
        eof = length == 0
        iostat = 0
        return
      else if (iostat /= 0) then
        return
      end if
    end do
  end subroutine read_line

end module feps_records
