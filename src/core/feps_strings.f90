!> Small string helpers shared by the readers and factories.
module feps_strings
  use feps_kinds, only: dp, i8
  implicit none
  private

  public :: to_upper, to_lower, sci, utf8_text_length, shown, gib_text

contains

  !> ASCII upper case.
  pure function to_upper(text) result(res)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: res
    integer :: i, code
    res = text
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code >= iachar('a') .and. code <= iachar('z')) res(i:i) = achar(code - 32)
    end do
  end function to_upper

  !> ASCII lower case.
  pure function to_lower(text) result(res)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: res
    integer :: i, code
    res = text
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code >= iachar('A') .and. code <= iachar('Z')) res(i:i) = achar(code + 32)
    end do
  end function to_lower

  !> `x` in scientific notation with `digits` digits after the point, right-adjusted in at
  !! least `width` characters: `es<width>.<digits>`, except that an exponent of three digits
  !! keeps its `E` (`1.08628E+303`, where `es12.5` prints `1.08628+303`, which other programs
  !! do not read as a number). NaN and Inf as the compiler writes them.
  pure function sci(x, digits, width) result(res)
    real(dp), intent(in) :: x
    integer, intent(in) :: digits, width
    character(len=:), allocatable :: res
    character(len=64) :: buf
    character(len=32) :: fmt
    ! below 1e-99 or from 9.99e99 on, the mantissa may round into a three-digit exponent
    if (abs(x) >= 1.0e-99_dp .and. abs(x) < 9.99e99_dp .or. x == 0.0_dp) then
      write (fmt, '(a,i0,a,i0,a)') '(es', digits + 8, '.', digits, ')'
    else
      write (fmt, '(a,i0,a,i0,a)') '(es', digits + 9, '.', digits, 'e3)'
    end if
    write (buf, fmt) x
    res = trim(adjustl(buf))
    if (len(res) < width) res = repeat(' ', width - len(res)) // res
  end function sci

  !> How many bytes of `text` from the start are printable text: valid UTF-8 (no overlong form,
  !! no surrogate, nothing beyond U+10FFFF) without control characters (bytes 0-31 and 127; the
  !! C1 controls U+0080-U+009F). len(text) when all of it is; otherwise the offset of the first
  !! bad byte minus one. Names written into the XDMF (XML) file and the HDF5 file must be such
  !! text: XML 1.0 has no way to write a control character, and a parser stops at invalid UTF-8.
  pure integer function utf8_text_length(text) result(good)
    character(len=*), intent(in) :: text
    integer :: i, b, n, k, cp, lowest
    i = 1
    good = 0
    do while (i <= len(text))
      b = iachar(text(i:i))
      if (b < 32 .or. b == 127) return
      if (b < 128) then
        n = 0
        cp = b
        lowest = 0
      else if (b >= 194 .and. b <= 223) then
        n = 1
        cp = b - 192
        lowest = 128
      else if (b >= 224 .and. b <= 239) then
        n = 2
        cp = b - 224
        lowest = 2048
      else if (b >= 240 .and. b <= 244) then
        n = 3
        cp = b - 240
        lowest = 65536
      else
        return
      end if
      if (i + n > len(text)) return
      do k = 1, n
        b = iachar(text(i + k:i + k))
        if (b < 128 .or. b > 191) return
        cp = 64 * cp + (b - 128)
      end do
      if (cp < lowest .or. cp > 1114111 .or. (cp >= 55296 .and. cp <= 57343) .or. (cp >= 128 .and. cp <= 159)) return
      i = i + n + 1
      good = i - 1
    end do
  end function utf8_text_length

  !> `text` for a message: bytes that are not printable text (utf8_text_length) as \xNN.
  pure function shown(text) result(res)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: res
    character(len=*), parameter :: hex = '0123456789abcdef'
    integer :: i, good, b
    res = ''
    i = 1
    do while (i <= len(text))
      good = utf8_text_length(text(i:))
      res = res // text(i:i + good - 1)
      i = i + good
      if (i > len(text)) exit
      b = iachar(text(i:i))
      res = res // '\x' // hex(b / 16 + 1:b / 16 + 1) // hex(mod(b, 16) + 1:mod(b, 16) + 1)
      i = i + 1
    end do
  end function shown

  !> `bytes` in GiB with one decimal, for messages about memory.
  pure function gib_text(bytes) result(text)
    integer(i8), intent(in) :: bytes
    character(len=:), allocatable :: text
    character(len=32) :: buf
    write (buf, '(f0.1)') real(bytes, dp) / 1024.0_dp**3
    buf = adjustl(buf)
    if (buf(1:1) == '.') buf = '0' // buf
    text = trim(buf)
  end function gib_text

end module feps_strings
