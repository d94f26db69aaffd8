!> Small string helpers shared by the readers and factories.
module feps_strings
  use feps_kinds, only: dp
  implicit none
  private

  public :: to_upper, to_lower, sci

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

end module feps_strings
