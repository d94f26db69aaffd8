!> Linear static analysis: one assembly, one factorization, one solve.
module feps_linear_analysis
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_model, str
  use feps_model, only: model_t
  use feps_dof_map, only: dof_map_t, build_dof_map
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_assembly, only: group_kernel_t, stress_field_t, build_kernels, build_materials, build_pattern, &
                           assemble_stiffness, compute_stresses, internal_forces, check_jacobians
  use feps_loads, only: resolve_face_sets, nodal_load_vector, to_equations
  use feps_material, only: material_slot_t
  use feps_linear_solver, only: linear_solver_t
  use feps_solver_factory, only: new_linear_solver
  implicit none
  private

  !> What a linear run produces.
  type, public :: linear_result_t
    real(dp), allocatable :: displacement(:, :)   !! (3, nnode) global Cartesian
    real(dp), allocatable :: reaction(:, :)       !! (3, nnode) global Cartesian, at supports
    real(dp), allocatable :: external_force(:, :) !! (3, nnode) applied nodal forces
    type(stress_field_t), allocatable :: stresses(:)
    integer :: neq = 0
    integer :: unused_nodes = 0
    integer(i8) :: matrix_nnz = 0
    integer(i8) :: factor_nnz = 0
    real(dp) :: flops = 0.0_dp
    real(dp) :: min_pivot_ratio = 0.0_dp
    real(dp) :: max_pivot_ratio = 0.0_dp
    real(dp) :: min_detj = 0.0_dp
    real(dp) :: time_assembly = 0.0_dp
    real(dp) :: time_factorization = 0.0_dp
    real(dp) :: time_solve = 0.0_dp
    character(len=:), allocatable :: solver
  end type linear_result_t

  public :: run_linear, wall_clock

contains

  !> Seconds since an arbitrary origin.
  real(dp) function wall_clock()
    integer(i8) :: count, rate
    call system_clock(count, rate)
    wall_clock = real(count, dp) / real(rate, dp)
  end function wall_clock

  !> Solve the model's linear problem with the named solver.
  subroutine run_linear(model, solver_name, res, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: solver_name
    type(linear_result_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    type(group_kernel_t), allocatable :: kernels(:)
    type(material_slot_t), allocatable :: materials(:)
    type(dof_map_t) :: map
    type(csr_matrix_t) :: a
    class(linear_solver_t), allocatable :: solver
    real(dp), allocatable :: f_presc(:), b(:), fint(:, :)
    real(dp) :: t0, ul(3)
    integer :: n, d, ieq

    t0 = wall_clock()
    call build_kernels(model, kernels, error)
    if (allocated(error)) return
    call build_materials(model, materials, error)
    if (allocated(error)) return
    call check_jacobians(model, kernels, res%min_detj, error)
    if (allocated(error)) return
    call resolve_face_sets(model, kernels, error)
    if (allocated(error)) return
    call build_dof_map(model, map, error)
    if (allocated(error)) return
    res%neq = map%neq
    res%unused_nodes = map%unused_nodes
    call build_pattern(model, map, a)
    res%matrix_nnz = a%nnz()
    allocate (f_presc(map%neq), b(map%neq), res%external_force(3, model%nnode))
    call assemble_stiffness(model, map, kernels, materials, a, f_presc, error)
    if (allocated(error)) return
    call nodal_load_vector(model, kernels, res%external_force, error)
    if (allocated(error)) return
    call to_equations(map, res%external_force, b)
    b = b + f_presc
    res%time_assembly = wall_clock() - t0

    call new_linear_solver(solver_name, solver, error)
    if (allocated(error)) return
    res%solver = solver%name()
    t0 = wall_clock()
    call solver%analyze(a, error)
    if (allocated(error)) return
    call solver%factorize(a, error)
    if (allocated(error)) then
      ieq = error%item   ! fatal_error reallocates error: keep the item first
      if (ieq > 0 .and. ieq <= map%neq) then
        call fatal_error(error, err_model, model%deck_file // ': the stiffness matrix is singular at ' // map%dof_name(ieq) // &
                         ': that DOF is not held (an unconstrained rigid-body mode or a missing support)', item=ieq)
      end if
      return
    end if
    res%time_factorization = wall_clock() - t0
    res%factor_nnz = solver%factor_nnz
    res%flops = solver%flops
    res%min_pivot_ratio = solver%min_pivot_ratio
    res%max_pivot_ratio = solver%max_pivot_ratio
    t0 = wall_clock()
    call solver%solve(b, error)
    if (allocated(error)) return
    res%time_solve = wall_clock() - t0
    if (any(b /= b)) then
      call fatal_error(error, err_model, 'the solution holds NaN: the stiffness matrix is singular')
      return
    end if

    ! Nodal-system unknowns and prescribed values back to global Cartesian components.
    allocate (res%displacement(3, model%nnode))
    do n = 1, model%nnode
      do d = 1, 3
        if (map%eq(d, n) > 0) then
          ul(d) = b(map%eq(d, n))
        else if (map%constrained(d, n)) then
          ul(d) = map%prescribed(d, n)
        else
          ul(d) = 0.0_dp
        end if
      end do
      res%displacement(:, n) = matmul(map%basis(:, :, n), ul)
    end do
    call compute_stresses(model, kernels, materials, res%displacement, res%stresses)
    allocate (fint(3, model%nnode), res%reaction(3, model%nnode))
    call internal_forces(model, kernels, materials, res%displacement, fint)
    res%reaction = 0.0_dp
    do n = 1, model%nnode
      if (any(map%constrained(:, n))) res%reaction(:, n) = fint(:, n) - res%external_force(:, n)
    end do
  end subroutine run_linear

end module feps_linear_analysis
