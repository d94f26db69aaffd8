!> Linear solver by name.
module feps_solver_factory
  use feps_error, only: error_t, fatal_error, err_input
  use feps_linear_solver, only: linear_solver_t
  use feps_skyline_solver, only: skyline_solver_t
  use feps_cholmod_solver, only: cholmod_solver_t
  use feps_mumps_solver, only: mumps_solver_t
  implicit none
  private

  public :: new_linear_solver

contains

  !> 'skyline' (LDL^T with reverse Cuthill-McKee), 'cholmod' (supernodal, METIS) or 'mumps'
  !! (multifrontal over MPI, in the MPI build).
  subroutine new_linear_solver(name, solver, error)
    character(len=*), intent(in) :: name
    class(linear_solver_t), allocatable, intent(out) :: solver
    type(error_t), allocatable, intent(out) :: error
    select case (name)
    case ('skyline')
      allocate (skyline_solver_t :: solver)
    case ('cholmod')
      allocate (cholmod_solver_t :: solver)
    case ('mumps')
      allocate (mumps_solver_t :: solver)
    case default
      call fatal_error(error, err_input, 'unknown linear solver "' // name // '" (skyline, cholmod or mumps)')
    end select
  end subroutine new_linear_solver

end module feps_solver_factory
