!> Linear solver by name.
module feps_solver_factory
  use feps_error, only: error_t, fatal_error, err_input
  use feps_linear_solver, only: linear_solver_t
  use feps_skyline_solver, only: skyline_solver_t
  use feps_cholmod_solver, only: cholmod_solver_t
  use feps_mumps_solver, only: mumps_solver_t
  use feps_umfpack_solver, only: umfpack_solver_t
  implicit none
  private

  public :: new_linear_solver, new_lu_solver

contains

  !> 'skyline' (LDL^T with reverse Cuthill-McKee), 'cholmod' (supernodal, METIS),
  !! 'cholmod-mixed' (the same, its solves in single precision), 'mumps' (multifrontal over MPI,
  !! in the MPI build) or 'mumps-ooc' (the same, its factors on disk).
  subroutine new_linear_solver(name, solver, error)
    character(len=*), intent(in) :: name
    class(linear_solver_t), allocatable, intent(out) :: solver
    type(error_t), allocatable, intent(out) :: error
    select case (name)
    case ('skyline')
      allocate (skyline_solver_t :: solver)
    case ('cholmod')
      allocate (cholmod_solver_t :: solver)
    case ('cholmod-mixed')
      allocate (solver, source=cholmod_solver_t(mixed=.true.))
    case ('mumps')
      allocate (mumps_solver_t :: solver)
    case ('mumps-ooc')
      allocate (solver, source=mumps_solver_t(out_of_core=.true.))
    case default
      call fatal_error(error, err_input, 'unknown linear solver "' // name // '" (skyline, cholmod or mumps)')
    end select
  end subroutine new_linear_solver

  !> The LU solver for the exact non-symmetric tangents that goes with the linear solver `name`:
  !! MUMPS's LU (over the same ranks, its factors where the run keeps them) with 'mumps' and
  !! 'mumps-ooc', else UMFPACK.
  subroutine new_lu_solver(name, solver)
    character(len=*), intent(in) :: name
    class(linear_solver_t), allocatable, intent(out) :: solver
    select case (name)
    case ('mumps')
      allocate (solver, source=mumps_solver_t(unsymmetric=.true.))
    case ('mumps-ooc')
      allocate (solver, source=mumps_solver_t(unsymmetric=.true., out_of_core=.true.))
    case default
      allocate (umfpack_solver_t :: solver)
    end select
  end subroutine new_lu_solver

end module feps_solver_factory
