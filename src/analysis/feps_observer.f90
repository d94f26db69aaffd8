!> What an analysis reports while it runs: progress lines and the results of the steps that
!! are to be written. The program layer implements an observer (printing, HDF5); the
!! analysis layer never prints or writes files itself.
module feps_observer
  use feps_kinds, only: dp
  use feps_error, only: error_t
  use feps_restart_data, only: restart_data_t
  implicit none
  private

  !> Results of one point (Gauss or interface point) field of a group.
  type, public :: group_result_t
    real(dp), allocatable :: stress(:, :)    !! (ncomp, npoints): Voigt stresses or interface tractions
    real(dp), allocatable :: strain(:, :)    !! (ncomp, npoints)
    integer, allocatable :: state(:)         !! point states (feps_material state_*)
    integer :: points_per_element = 0
    integer :: family = 0                    !! the element catalog's family of the group's type
  end type group_result_t

  !> One step's results.
  type, public :: step_result_t
    integer :: step = 0                      !! step counter over all stages
    integer :: stage = 0
    integer :: step_in_stage = 0
    real(dp) :: load_factor = 0.0_dp         !! stage - 1 + fraction of the stage applied
    integer :: iterations = 0
    real(dp) :: residual = 0.0_dp            !! relative residual |R| / |P| at the end of the step
    !> the sign of the determinant of the exact tangent last factorized in the step (full
    !! Newton-Raphson): +1, -1 (an odd number of its eigenvalues below zero), 0 not known
    integer :: tangent_sign = 0
    real(dp), allocatable :: displacement(:, :)  !! (3, nnode) global Cartesian
    real(dp), allocatable :: reaction(:, :)      !! (3, nnode) global Cartesian
    real(dp), allocatable :: applied_force(:, :) !! (3, nnode) external nodal forces applied so far
    real(dp), allocatable :: reaction_nodal(:, :) !! (3, nnode) reactions in each node's nodal system
    logical :: has_nodal_systems = .false.       !! some node has a nodal (e.g. cylindrical) system
    type(group_result_t), allocatable :: groups(:)
  end type step_result_t

  type, abstract, public :: observer_t
  contains
    procedure(progress_interface), deferred :: progress
    procedure(step_interface), deferred :: write_step
    procedure :: checkpoint
  end type observer_t

  abstract interface
    !> One line of progress (step, load factor, iterations, residual, ...).
    subroutine progress_interface(self, line)
      import :: observer_t
      class(observer_t), intent(inout) :: self
      character(len=*), intent(in) :: line
    end subroutine progress_interface
    !> A step whose results are to be kept.
    subroutine step_interface(self, res, error)
      import :: observer_t, step_result_t, error_t
      class(observer_t), intent(inout) :: self
      type(step_result_t), intent(in) :: res
      type(error_t), allocatable, intent(out) :: error
    end subroutine step_interface
  end interface

contains

  !> Restart data of the end of a step (RESTART, --restart-every) to keep. Default: none kept.
  subroutine checkpoint(self, data, error)
    class(observer_t), intent(inout) :: self
    type(restart_data_t), intent(in) :: data
    type(error_t), allocatable, intent(out) :: error
  end subroutine checkpoint

end module feps_observer
