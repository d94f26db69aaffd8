!> The totals of an analysis that the program reports and writes to `/summary`: one type,
!! filled where each total arises (the analysis, its solver) and extended by the program with
!! what it knows of the run (title, output, mesh), never copied field by field.
module feps_analysis_summary
  use feps_kinds, only: dp, i8
  implicit none
  private

  !> Totals of an analysis, for the summary.
  type, public :: analysis_summary_t
    logical :: linear = .false.
    integer :: dofs = 0                       !! free equations
    integer :: unused_nodes = 0
    integer :: steps = 0
    integer :: iterations = 0
    integer :: factorizations = 0
    integer :: lu_factorizations = 0        !! LU factorizations of exact non-symmetric tangents (full Newton)
    real(dp) :: lu_min_rcond = 0.0_dp        !! the smallest reciprocal condition estimate of those LU factors
    integer :: cutbacks = 0
    integer :: unconverged_steps = 0         !! steps accepted with |R| / |P| above delta1 (carried on)
    logical :: converged = .true.            !! every stage's last step ended within its tolerance
    real(dp) :: unbalanced = 0.0_dp          !! the largest |R| / |P| a stage ended with, above its tolerance
    real(dp) :: unbalanced_tolerance = 0.0_dp  !! that stage's DELTA1
    character(len=:), allocatable :: unbalanced_stage  !! that stage's name
    integer :: unbalanced_step = 0                     !! its last step
    real(dp) :: unbalanced_load_factor = 0.0_dp        !! and the load factor there
    character(len=:), allocatable :: unbalanced_at     !! the node and DOF of its largest unbalanced force
    logical :: line_search = .false.         !! some stage ran with LINESEARCH=energy
    integer :: line_searches = 0             !! iterations whose correction was searched (scaled)
    integer :: line_search_evaluations = 0   !! residual evaluations the searches added to the iterations'
    integer(i8) :: matrix_nnz = 0
    integer(i8) :: factor_nnz = 0
    real(dp) :: flops = 0.0_dp
    real(dp) :: min_pivot_ratio = 0.0_dp
    real(dp) :: max_pivot_ratio = 0.0_dp
    real(dp) :: min_jacobian = 0.0_dp        !! the smallest Jacobian determinant of the mesh
    real(dp) :: time_assembly = 0.0_dp
    real(dp) :: time_factorization = 0.0_dp
    real(dp) :: time_solve = 0.0_dp
    real(dp) :: time_update = 0.0_dp
    real(dp) :: max_displacement = 0.0_dp
    integer :: max_displacement_node = 0
    real(dp) :: applied_force(3) = 0.0_dp
    real(dp) :: reaction_force(3) = 0.0_dp
    character(len=:), allocatable :: solver
    integer :: single_precision_factors = 0  !! mixed precision: factors solved in single precision
    real(dp) :: test_solve_error = 0.0_dp    !! and the largest relative error of their test solves
    integer :: precision_fallbacks = 0       !! factors tested and solved in double precision instead
    logical :: condition_warning = .false.   !! max/min pivot ratio passed condition_warning
    integer(i8), allocatable :: state_bytes(:)  !! per group: bytes of point state (0: elastic, none kept)
    real(dp), allocatable :: rank_memory_mb(:)       !! MUMPS over MPI: each rank's largest factorization memory (MB)
    real(dp), allocatable :: rank_factor_seconds(:)  !! and its time in the factorizations (s)
    real(dp), allocatable :: rank_elements(:)        !! element-partitioned run: each rank's elements
    real(dp), allocatable :: rank_element_seconds(:) !! and its time setting up, assembling and updating (s)
    real(dp), allocatable :: rank_peak_memory_mb(:)  !! and its largest resident memory in the analysis (MB)
  end type analysis_summary_t

  !> Above this max/min pivot ratio the results may have lost digits: say so.
  real(dp), parameter, public :: condition_warning = 1.0e12_dp

end module feps_analysis_summary
