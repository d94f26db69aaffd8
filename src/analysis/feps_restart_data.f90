!> Restart data: everything a nonlinear run needs to continue from the end of a step so that
!! every later step is bit-identical to the uninterrupted run's. The state along the load
!! path, every group's point states (committed and trial), the values of the matrices the
!! factors held were formed from (refactorized on restart, not reassembled), the solver's
!! counters, the method's factor state, the summary's totals and the run's notes; and a
!! fingerprint of the resolved model that a continued run must match.
module feps_restart_data
  use, intrinsic :: iso_fortran_env, only: int8
  use feps_kinds, only: dp, i8
  use feps_model, only: model_t
  use feps_point_state_store, only: point_state_store_t
  use feps_solution_method, only: factor_state_t
  use feps_analysis_summary, only: analysis_summary_t
  implicit none
  private

  public :: model_fingerprint, summary_reals, summary_ints, set_summary_scalars

  !> The restart data of the end of one step.
  type, public :: restart_data_t
    character(len=:), allocatable :: source              !! the file it was read from (messages)
    integer(i8) :: fingerprint = 0                       !! model_fingerprint of the model it belongs to
    integer :: step = 0                                  !! step counter over all stages
    integer :: stage = 0
    integer :: step_in_stage = 0
    real(dp), allocatable :: u(:, :), u_t(:, :), fint(:, :), f_applied(:, :), uc(:, :), release_force(:, :)
    logical, allocatable :: active(:)                    !! groups active
    logical, allocatable :: fully_open(:)                !! groups reported fully open
    type(point_state_store_t), allocatable :: states(:)  !! every group's (unallocated arrays: none kept)
    real(dp), allocatable :: a_val(:)                    !! values of the symmetric matrix last factorized
    real(dp), allocatable :: a_full_val(:)               !! values of the full matrix last given to LU (if any)
    logical :: use_lu = .false.
    logical :: symmetrized = .false.
    logical :: warned_condition = .false.
    integer :: lu_singular = 0
    integer :: solver_factorizations = 0
    !> the symmetric solver's mixed-precision counters (linear_solver_t's)
    integer :: solves_with_factor = 0
    integer :: lower_precision_factors = 0
    integer :: precision_fallbacks = 0
    real(dp) :: test_solve_error = 0.0_dp
    integer :: lu_factorizations = 0
    real(dp) :: lu_min_rcond = huge(1.0_dp)
    type(factor_state_t) :: factor
    type(analysis_summary_t) :: summary
    character(len=:), allocatable :: run_notes
  end type restart_data_t

  !> Two 31-bit multiplicative hashes side by side: no integer overflow, ~62 bits.
  integer(i8), parameter :: p1 = 2147483647_i8, p2 = 2147483629_i8, m1 = 48271_i8, m2 = 69621_i8

  type :: hash_t
    integer(i8) :: a = 1, b = 7
  end type hash_t

  interface mix
    module procedure mix_reals, mix_real, mix_ints, mix_int, mix_text
  end interface mix

contains

  !> A fingerprint of the resolved model that decides the results: nodes, coordinate systems,
  !! groups (type, material, connectivity, birth), materials (kind and parameters), sets,
  !! supports, prescribed displacements, loads, prestress, stages (steps, LOAD=, controls,
  !! births) and the linear solver. Output choices (FIELDS, OUTPUT, RESTART) are left out.
  function model_fingerprint(model, solver) result(fp)
    type(model_t), intent(in) :: model
    character(len=*), intent(in) :: solver
    integer(i8) :: fp
    type(hash_t) :: h
    integer :: i, j
    call mix(h, model%nnode)
    call mix(h, reshape(model%coords, [size(model%coords)]))
    call mix(h, merge(1, 0, model%plane_strain))
    do i = 1, size(model%systems)
      call mix(h, model%systems(i)%kind)
      call mix(h, model%systems(i)%origin)
      call mix(h, reshape(model%systems(i)%axes, [9]))
    end do
    do i = 1, size(model%groups)
      associate (g => model%groups(i))
        call mix(h, g%element_type)
        call mix(h, [g%material, g%activate_stage])
        call mix(h, reshape(g%connectivity, [size(g%connectivity)]))
      end associate
    end do
    do i = 1, size(model%materials)
      associate (m => model%materials(i))
        call mix(h, m%kind)
        do j = 1, size(m%keys)
          call mix(h, trim(m%keys(j)))
          call mix(h, m%values(j))
        end do
        if (allocated(m%texts)) then
          do j = 1, size(m%texts)
            call mix(h, trim(m%texts(j)))
          end do
        end if
      end associate
    end do
    if (allocated(model%node_sets)) then
      do i = 1, size(model%node_sets)
        call mix(h, model%node_sets(i)%nodes)
      end do
    end if
    if (allocated(model%face_sets)) then
      do i = 1, size(model%face_sets)
        call mix(h, model%face_sets(i)%group)
        if (allocated(model%face_sets(i)%element)) call mix(h, model%face_sets(i)%element)
        if (allocated(model%face_sets(i)%face)) call mix(h, model%face_sets(i)%face)
      end do
    end if
    if (allocated(model%constraints)) then
      do i = 1, size(model%constraints)
        associate (c => model%constraints(i))
          call mix(h, [c%node_set, c%csys, c%dof, c%stage, c%active_from, merge(1, 0, c%release), &
                       merge(1, 0, c%prescribed)])
          call mix(h, c%value)
        end associate
      end do
    end if
    if (allocated(model%nodal_loads)) then
      do i = 1, size(model%nodal_loads)
        call mix(h, [model%nodal_loads(i)%stage, model%nodal_loads(i)%node_set, model%nodal_loads(i)%csys])
        call mix(h, model%nodal_loads(i)%components)
      end do
    end if
    if (allocated(model%face_loads)) then
      do i = 1, size(model%face_loads)
        associate (l => model%face_loads(i))
          call mix(h, [l%stage, l%face_set, l%kind, l%csys, merge(1, 0, l%use_total), l%vary_csys, l%vary_coord, &
                       l%vary2_csys, l%vary2_coord])
          call mix(h, [l%components, l%value, l%total, l%zero, l%peak_at, l%zero2, l%peak2_at])
        end associate
      end do
    end if
    if (allocated(model%prestresses)) then
      do i = 1, size(model%prestresses)
        associate (p => model%prestresses(i))
          call mix(h, [p%stage, p%group, merge(1, 0, p%bond_after)])
          call mix(h, p%force)
        end associate
      end do
    end if
    do i = 1, size(model%stages)
      associate (st => model%stages(i), c => model%stages(i)%controls)
        call mix(h, [st%steps, c%method, c%max_iterations, c%max_cutbacks, merge(1, 0, c%bfgs), &
                     merge(1, 0, c%line_search)])
        call mix(h, [st%load_fraction, c%delta1, c%delta2, c%delta3, c%delta4, c%divergence])
        if (allocated(st%activate)) then
          do j = 1, size(st%activate)
            call mix(h, trim(st%activate(j)))
          end do
        end if
      end associate
    end do
    call mix(h, solver)
    fp = ior(ishft(h%a, 31), h%b)
  end function model_fingerprint

  subroutine mix_bytes(h, bytes)
    type(hash_t), intent(inout) :: h
    integer(int8), intent(in) :: bytes(:)
    integer :: i
    integer(i8) :: v
    do i = 1, size(bytes)
      v = iand(int(bytes(i), i8), 255_i8)
      h%a = modulo(h%a * m1 + v + 1, p1)
      h%b = modulo(h%b * m2 + v + 3, p2)
    end do
    ! the length too, so that [1, 2] and [1], [2] differ
    h%a = modulo(h%a * m1 + size(bytes), p1)
  end subroutine mix_bytes

  subroutine mix_reals(h, x)
    type(hash_t), intent(inout) :: h
    real(dp), intent(in) :: x(:)
    if (size(x) == 0) then
      call mix_bytes(h, [integer(int8) ::])
    else
      call mix_bytes(h, transfer(x, [0_int8]))
    end if
  end subroutine mix_reals

  subroutine mix_real(h, x)
    type(hash_t), intent(inout) :: h
    real(dp), intent(in) :: x
    call mix_reals(h, [x])
  end subroutine mix_real

  subroutine mix_ints(h, x)
    type(hash_t), intent(inout) :: h
    integer, intent(in) :: x(:)
    if (size(x) == 0) then
      call mix_bytes(h, [integer(int8) ::])
    else
      call mix_bytes(h, transfer(x, [0_int8]))
    end if
  end subroutine mix_ints

  subroutine mix_int(h, x)
    type(hash_t), intent(inout) :: h
    integer, intent(in) :: x
    call mix_ints(h, [x])
  end subroutine mix_int

  subroutine mix_text(h, text)
    type(hash_t), intent(inout) :: h
    character(len=*), intent(in) :: text
    integer :: i
    call mix_ints(h, [(ichar(text(i:i)), i = 1, len(text))])
  end subroutine mix_text

  !> The summary's real totals that a continued run carries on from, in a fixed order
  !! (set_summary_scalars reads them back).
  pure function summary_reals(s) result(x)
    type(analysis_summary_t), intent(in) :: s
    real(dp) :: x(11)
    x = [s%lu_min_rcond, s%unbalanced, s%unbalanced_tolerance, s%unbalanced_load_factor, s%min_pivot_ratio, &
         s%max_pivot_ratio, s%flops, s%time_assembly, s%time_factorization, s%time_solve, s%time_update]
  end function summary_reals

  !> The summary's integer and logical totals, in a fixed order.
  pure function summary_ints(s) result(k)
    type(analysis_summary_t), intent(in) :: s
    integer :: k(12)
    k = [s%steps, s%iterations, s%factorizations, s%lu_factorizations, s%cutbacks, s%unconverged_steps, &
         merge(1, 0, s%converged), s%unbalanced_step, merge(1, 0, s%line_search), s%line_searches, &
         s%line_search_evaluations, merge(1, 0, s%condition_warning)]
  end function summary_ints

  !> The totals of summary_reals and summary_ints back into `s`.
  pure subroutine set_summary_scalars(s, x, k)
    type(analysis_summary_t), intent(inout) :: s
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: k(:)
    s%lu_min_rcond = x(1)
    s%unbalanced = x(2)
    s%unbalanced_tolerance = x(3)
    s%unbalanced_load_factor = x(4)
    s%min_pivot_ratio = x(5)
    s%max_pivot_ratio = x(6)
    s%flops = x(7)
    s%time_assembly = x(8)
    s%time_factorization = x(9)
    s%time_solve = x(10)
    s%time_update = x(11)
    s%steps = k(1)
    s%iterations = k(2)
    s%factorizations = k(3)
    s%lu_factorizations = k(4)
    s%cutbacks = k(5)
    s%unconverged_steps = k(6)
    s%converged = k(7) == 1
    s%unbalanced_step = k(8)
    s%line_search = k(9) == 1
    s%line_searches = k(10)
    s%line_search_evaluations = k(11)
    s%condition_warning = k(12) == 1
  end subroutine set_summary_scalars

end module feps_restart_data
