!> What the `feps` command does, as library procedures the tests can call: read a deck,
!! run it, write the HDF5 results (temporary name, renamed on success; nothing left behind
!! on error) and return a summary for the program to print.
module feps_program
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_input, str
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_assembly, only: group_kernel_t, build_kernels, check_jacobians
  use feps_linear_analysis, only: linear_result_t, run_linear, wall_clock
  use feps_results_file, only: results_file_t
  use feps_principal, only: principal_values
  implicit none
  private

  character(len=*), parameter, public :: feps_version = '0.1.0'

  !> Options from the command line; empty strings mean "as the deck says".
  type, public :: run_options_t
    character(len=:), allocatable :: deck
    character(len=:), allocatable :: output
    character(len=:), allocatable :: solver
    logical :: quiet = .false.
  end type run_options_t

  !> What the program reports after a run.
  type, public :: run_summary_t
    character(len=:), allocatable :: title
    character(len=:), allocatable :: output
    character(len=:), allocatable :: solver
    logical :: mesh_only = .false.
    integer :: nodes = 0
    integer :: elements = 0
    integer :: dofs = 0
    integer :: unused_nodes = 0
    integer(i8) :: factor_nnz = 0
    real(dp) :: flops = 0.0_dp
    real(dp) :: wall_time = 0.0_dp
    real(dp) :: time_assembly = 0.0_dp
    real(dp) :: time_factorization = 0.0_dp
    real(dp) :: time_solve = 0.0_dp
    integer(i8) :: matrix_nnz = 0
    real(dp) :: max_displacement = 0.0_dp
    integer :: max_displacement_node = 0
    real(dp) :: bbox(3, 2) = 0.0_dp
    real(dp) :: min_jacobian = 0.0_dp
    real(dp) :: min_pivot_ratio = 0.0_dp
    real(dp) :: max_pivot_ratio = 0.0_dp
    real(dp) :: applied_force(3) = 0.0_dp
    real(dp) :: reaction_force(3) = 0.0_dp
  end type run_summary_t

  public :: run_feps

contains

  !> Read, check, solve and write one deck.
  subroutine run_feps(options, summary, error)
    type(run_options_t), intent(in) :: options
    type(run_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(linear_result_t) :: res
    type(group_kernel_t), allocatable :: kernels(:)
    character(len=:), allocatable :: solver, output
    real(dp) :: t0, dnorm
    integer :: n

    t0 = wall_clock()
    call read_deck(options%deck, model, error)
    if (allocated(error)) return
    summary%title = model%title
    summary%mesh_only = model%mesh_only
    summary%nodes = model%nnode
    summary%elements = model%nelem()
    summary%bbox(:, 1) = minval(model%coords, dim=2)
    summary%bbox(:, 2) = maxval(model%coords, dim=2)

    output = model%output_file
    if (allocated(options%output)) then
      if (len(options%output) > 0) output = options%output
    end if
    if (len(output) == 0 .and. .not. model%mesh_only) output = default_output(options%deck)
    summary%output = output

    if (model%mesh_only) then
      call build_kernels(model, kernels, error)
      if (allocated(error)) return
      call check_jacobians(model, kernels, summary%min_jacobian, error)
      if (allocated(error)) return
      if (len(output) > 0) call write_mesh_only(output, model, error)
      summary%wall_time = wall_clock() - t0
      return
    end if

    solver = model%solver
    if (allocated(options%solver)) then
      if (len(options%solver) > 0) solver = options%solver
    end if
    call run_linear(model, solver, res, error)
    if (allocated(error)) return
    summary%solver = res%solver
    summary%dofs = res%neq
    summary%unused_nodes = res%unused_nodes
    summary%factor_nnz = res%factor_nnz
    summary%matrix_nnz = res%matrix_nnz
    summary%time_assembly = res%time_assembly
    summary%time_factorization = res%time_factorization
    summary%time_solve = res%time_solve
    summary%flops = res%flops
    summary%min_pivot_ratio = res%min_pivot_ratio
    summary%max_pivot_ratio = res%max_pivot_ratio
    summary%min_jacobian = res%min_detj
    summary%applied_force = sum(res%external_force, dim=2)
    summary%reaction_force = sum(res%reaction, dim=2)
    do n = 1, model%nnode
      dnorm = norm2(res%displacement(:, n))
      if (dnorm > summary%max_displacement) then
        summary%max_displacement = dnorm
        summary%max_displacement_node = n
      end if
    end do
    summary%wall_time = wall_clock() - t0
    if (len(output) > 0) call write_linear_results(output, model, res, summary, error)
  end subroutine run_feps

  !> The deck's name without folder and extension, with .h5, in the working directory.
  pure function default_output(deck) result(path)
    character(len=*), intent(in) :: deck
    character(len=:), allocatable :: path
    integer :: slash, dot
    slash = index(deck, '/', back=.true.)
    dot = index(deck(slash + 1:), '.', back=.true.)
    if (dot > 1) then
      path = deck(slash + 1:slash + dot - 1) // '.h5'
    else
      path = deck(slash + 1:) // '.h5'
    end if
  end function default_output

  subroutine write_mesh_only(path, model, error)
    character(len=*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    type(results_file_t) :: h5
    call h5%create(path, error)
    if (allocated(error)) return
    call write_mesh(h5, model, error)
    if (.not. allocated(error)) call h5%write_summary_string('program', 'feps ' // feps_version, error)
    if (.not. allocated(error)) call h5%write_summary_string('input_file', model%deck_file, error)
    if (.not. allocated(error)) call h5%close(error)
    if (allocated(error)) call h5%discard()
  end subroutine write_mesh_only

  subroutine write_mesh(h5, model, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: g
    call h5%write_mesh(model%coords, error)
    if (allocated(error)) return
    do g = 1, size(model%groups)
      call h5%write_group(model%groups(g)%name, model%groups(g)%element_type, model%groups(g)%connectivity, error)
      if (allocated(error)) return
    end do
  end subroutine write_mesh

  !> The one step of a linear run: displacement, reactions, Gauss-point stresses and the most
  !! tensile and most compressive principal stresses.
  subroutine write_linear_results(path, model, res, summary, error)
    character(len=*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(linear_result_t), intent(in) :: res
    type(run_summary_t), intent(in) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(results_file_t) :: h5
    real(dp), allocatable :: principal(:, :)
    real(dp) :: p(3)
    integer :: g, q

    call h5%create(path, error)
    if (allocated(error)) return
    call write_mesh(h5, model, error)
    if (allocated(error)) then
      call h5%discard()
      return
    end if
    call h5%begin_step(1, 1.0_dp, 1, 0.0_dp, error)
    if (.not. allocated(error)) call h5%write_nodal(1, 'displacement', res%displacement, 'ux uy uz', error)
    if (.not. allocated(error)) call h5%write_nodal(1, 'reaction', res%reaction, 'fx fy fz', error)
    do g = 1, size(model%groups)
      if (allocated(error)) exit
      associate (s => res%stresses(g))
        call h5%write_gauss(1, 'stress', model%groups(g)%name, s%sig, 'sxx syy szz syz sxz sxy', &
                            s%points_per_element, error)
        if (allocated(error)) exit
        allocate (principal(2, size(s%sig, 2)))
        do q = 1, size(s%sig, 2)
          p = principal_values(s%sig(:, q))
          principal(:, q) = [p(1), p(3)]
        end do
        call h5%write_gauss(1, 'principal', model%groups(g)%name, principal, 'most_tensile most_compressive', &
                            s%points_per_element, error)
        deallocate (principal)
      end associate
    end do
    if (.not. allocated(error)) call h5%write_summary_string('program', 'feps ' // feps_version, error)
    if (.not. allocated(error)) call h5%write_summary_string('input_file', model%deck_file, error)
    if (.not. allocated(error)) call h5%write_summary_string('solver', summary%solver, error)
    if (.not. allocated(error)) call h5%write_summary_real('wall_time', summary%wall_time, error)
    if (.not. allocated(error)) call h5%write_summary_int('dofs', int(summary%dofs, i8), error)
    if (.not. allocated(error)) call h5%write_summary_int('factor_nonzeros', summary%factor_nnz, error)
    if (.not. allocated(error)) call h5%write_summary_real('factor_flops', summary%flops, error)
    if (.not. allocated(error)) call h5%write_summary_int('matrix_nonzeros', summary%matrix_nnz, error)
    if (.not. allocated(error)) call h5%write_summary_real('time_assembly', summary%time_assembly, error)
    if (.not. allocated(error)) call h5%write_summary_real('time_factorization', summary%time_factorization, error)
    if (.not. allocated(error)) call h5%write_summary_real('time_solve', summary%time_solve, error)
    if (.not. allocated(error)) call h5%write_summary_real('max_displacement', summary%max_displacement, error)
    if (.not. allocated(error)) call h5%close(error)
    if (allocated(error)) call h5%discard()
  end subroutine write_linear_results

end module feps_program
