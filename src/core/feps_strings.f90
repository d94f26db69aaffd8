!> Small string helpers shared by the readers and factories.
module feps_strings
  implicit none
  private

  public :: to_upper, to_lower

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

end module feps_strings
