!> Error reporting for the library: procedures never stop or print; they return an
!! allocated `error_t` (absent means success), and only the program decides exit codes.
module feps_error
  implicit none
  private

  !> Error categories; the program maps them to exit statuses.
  integer, parameter, public :: err_input = 2      !! bad input: file, line and field named
  integer, parameter, public :: err_model = 3      !! model cannot be solved (singular, unconstrained)
  integer, parameter, public :: err_solver = 4     !! numerical failure (divergence, no convergence)
  integer, parameter, public :: err_io = 5         !! files that cannot be written (results)
  integer, parameter, public :: err_internal = 6   !! a broken invariant: a bug in feps
  integer, parameter, public :: err_input_file = 7 !! an input file that cannot be opened or read (named)
  integer, parameter, public :: err_memory = 8     !! more memory than the process may use (a run that fails)

  !> An error: category, one-line message and an optional integer (e.g. the failing equation).
  type, public :: error_t
    integer :: code = err_internal
    character(len=:), allocatable :: message
    integer :: item = 0
  end type error_t

  public :: fatal_error, input_error, str

  !> Short text for numbers in messages.
  interface str
    module procedure str_int, str_int8, str_real
  end interface str

contains

  !> Allocate `error` with a category and a message.
  pure subroutine fatal_error(error, code, message, item)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in) :: code
    character(len=*), intent(in) :: message
    integer, intent(in), optional :: item
    allocate (error)
    error%code = code
    error%message = message
    if (present(item)) error%item = item
  end subroutine fatal_error

  !> Bad input at a place in a file: "FILE:LINE: field F: MESSAGE".
  pure subroutine input_error(error, file, line, message, field)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in) :: file
    integer, intent(in) :: line
    character(len=*), intent(in) :: message
    integer, intent(in), optional :: field
    if (present(field)) then
      call fatal_error(error, err_input, file // ':' // str(line) // ': field ' // str(field) // ': ' // message)
    else
      call fatal_error(error, err_input, file // ':' // str(line) // ': ' // message)
    end if
  end subroutine input_error

  pure function str_int(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write (buf, '(i0)') i
    s = trim(buf)
  end function str_int

  pure function str_int8(i) result(s)
    use feps_kinds, only: i8
    integer(i8), intent(in) :: i
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write (buf, '(i0)') i
    s = trim(buf)
  end function str_int8

  pure function str_real(x) result(s)
    use feps_kinds, only: dp
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    write (buf, '(g0.6)') x
    s = trim(adjustl(buf))
  end function str_real

end module feps_error
