!> The catalog of solution methods: METHOD='s code (feps_model's method_names) to the type
!! that makes its decisions. A new method is one file extending solution_method_t, one name
!! in method_names and one line here.
module feps_solution_methods
  use feps_model, only: method_euler, method_modified_euler, method_newton_raphson, &
                        method_modified_newton_raphson, method_initial_stiffness, method_full_newton_raphson
  use feps_error, only: error_t, fatal_error, err_internal, str
  use feps_solution_method, only: solution_method_t
  use feps_method_euler, only: euler_t
  use feps_method_modified_euler, only: modified_euler_t
  use feps_method_newton_raphson, only: newton_raphson_t
  use feps_method_modified_newton_raphson, only: modified_newton_raphson_t
  use feps_method_initial_stiffness, only: initial_stiffness_t
  use feps_method_full_newton_raphson, only: full_newton_raphson_t
  implicit none
  private

  public :: new_solution_method

contains

  !> The method of code `code` (the deck reader accepts only known names, so every code it
  !! stores has a type here: another is an internal error).
  subroutine new_solution_method(code, method, error)
    integer, intent(in) :: code
    class(solution_method_t), allocatable, intent(out) :: method
    type(error_t), allocatable, intent(out) :: error
    select case (code)
    case (method_euler)
      allocate (euler_t :: method)
    case (method_modified_euler)
      allocate (modified_euler_t :: method)
    case (method_newton_raphson)
      allocate (newton_raphson_t :: method)
    case (method_initial_stiffness)
      allocate (initial_stiffness_t :: method)
    case (method_full_newton_raphson)
      allocate (full_newton_raphson_t :: method)
    case (method_modified_newton_raphson)
      allocate (modified_newton_raphson_t :: method)
    case default
      call fatal_error(error, err_internal, 'new_solution_method: no solution method has code ' // str(code))
    end select
  end subroutine new_solution_method

end module feps_solution_methods
