!> Staged incremental analysis by the thesis's modified Newton-Raphson family (section 2.6):
!! Euler, modified Euler, Newton-Raphson (tangent each step), modified Newton-Raphson
!! (refactorize when the residual at the end of a step exceeds delta3/delta4) and initial
!! stiffness. Residual formulation: R = P - F_int with stresses updated from the start of the
!! step (eq. 2.3.21), so the unbalanced force of a step is carried into the next (eq. 2.6.4)
!! except by Euler, which drops it. Steps that diverge are cut back (halved) up to a bound; a
!! model that is linear (all materials elastic, no interfaces) is solved with one
!! factorization and one solve per stage whatever the deck asks.
!!
!! The state and its operations are in feps_analysis_state, the progress lines, step results
!! and stop messages in feps_step_report; this module holds the decisions: which stiffness to
!! factorize, when a step has converged, diverged or is carried, and when to cut back.
module feps_incremental_analysis
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, input_error, err_solver, err_model, err_input, str
  use feps_clock, only: wall_clock
  use feps_strings, only: to_upper
  use feps_model, only: model_t, stage_t, controls_t, method_names, path_load, path_arc_length, path_names, &
                        method_euler, method_modified_euler
  use feps_loads, only: nodal_load_vector
  use feps_observer, only: observer_t
  use feps_analysis_summary, only: analysis_summary_t, condition_warning
  use feps_geostatic, only: in_situ_field_t, build_in_situ_field, set_in_situ_stress, end_geostatic_stage
  use feps_analysis_state, only: analysis_t, is_linear_model, set_up, &
                                 init_states, set_crack_bands, state_bytes, change_supports, activate_groups, check_born_nodes, &
                                 stage_increments, set_trial, add_free, update_points, residual, &
                                 committed_residual, commit, restore, factorize_tangent, support_reaction, &
                                 save_state, restore_state
  use feps_restart_data, only: restart_data_t, model_fingerprint, set_summary_scalars, summary_reals, summary_ints
  use feps_solution_method, only: solution_method_t, factor_state_t
  use feps_solution_methods, only: new_solution_method
  use feps_path_following, only: path_t, start_path, path_substep, constrain_arc, constrain_displacement, &
                                 constrain_load
  use feps_bfgs, only: bfgs_t
  use feps_line_search, only: line_search_t, line_search_begin, line_search_next, line_search_eta, &
                              line_search_s_min, line_search_max_evaluations
  use feps_step_report, only: progress_line, time_text, collapse_error, report_step, report_open_interfaces, &
                              writes_step, name_step, newly_open_points, collect_point_notes, stop_error
  use feps_parallel, only: share_root_error, sum_over_ranks, peak_memory_mb
  implicit none
  private

  public :: analysis_summary_t, condition_warning
  public :: run_analysis, check_analysis, is_linear_model

contains

  !> Run every stage of the model; report progress and the steps to write to `observer`.
  !! A nonlinear run hands restart data to `observer%checkpoint` every model%restart_every
  !! steps; with `resume` it continues from such data (of the same model: its fingerprint is
  !! checked) instead of starting from zero.
  subroutine run_analysis(model, solver_name, observer, summary, error, resume, stop_after)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: solver_name
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(restart_data_t), intent(in), optional :: resume
    integer, intent(in), optional :: stop_after   !! a test aid: fail (exit 1) after this step
    type(analysis_t) :: an
    real(dp) :: t0, length
    integer :: n
    integer(i8) :: fingerprint

    t0 = wall_clock()
    call set_up(model, solver_name, an, summary, error)
    if (allocated(error)) return
    fingerprint = model_fingerprint(model, summary%solver)
    if (present(resume)) then
      if (resume%fingerprint /= fingerprint) then
        call fatal_error(error, err_input, resume%source // ': restart data of another model (its mesh, ' // &
                         'materials, loads, stages, controls or solver differ from ' // model%deck_file // ')')
        return
      end if
      if (resume%step >= sum(model%stages%steps)) then
        call fatal_error(error, err_input, resume%source // ': its restart point is step ' // str(resume%step) // &
                         ', the last of the run of ' // model%deck_file // ': nothing to continue')
        return
      end if
    end if
    call check_path_restart(model, present(resume), error)
    if (allocated(error)) return
    call init_states(model, an)
    summary%state_bytes = state_bytes(an%states)
    call set_crack_bands(model, an, error)
    if (allocated(error)) return
    call check_in_situ_field(model, an, error)
    if (allocated(error)) return
    allocate (an%path%f_ref(3, model%nnode), an%path%f_applied(3, model%nnode))
    call nodal_load_vector(model, an%kernels, an%path%f_ref, error, stage=0)
    if (allocated(error)) return
    an%path%f_applied = 0.0_dp
    summary%time_assembly = wall_clock() - t0

    if (summary%linear) then
      if (present(resume)) then
        call fatal_error(error, err_input, resume%source // ': a linear model is solved in one solve per ' // &
                         'stage and continues from no restart data')
        return
      end if
      call observer%progress('linear model (all materials elastic, no interfaces): one factorization, ' // &
                             'one solve per stage')
      if (solver_name == 'cholmod-mixed') call observer%progress('note: mixed precision is for nonlinear ' // &
        'runs, whose iterations correct each solve: a linear model is solved once, in double precision')
      if (model%restart_every > 0) call observer%progress('note: no restart data: a linear model is solved ' // &
                                                          'in one solve per stage')
      call run_linear_stages(model, an, observer, summary, error)
    else
      if (present(resume)) then
        call restore_state(model, an, resume, resume%stage, summary, error)
        if (allocated(error)) return
        call set_summary_scalars(summary, summary_reals_of(resume), summary_ints_of(resume))
        summary%unbalanced_stage = resume%summary%unbalanced_stage
        summary%unbalanced_at = resume%summary%unbalanced_at
      end if
      call run_nonlinear_stages(model, an, observer, summary, fingerprint, error, resume, stop_after)
    end if
    if (allocated(error)) return

    summary%factor_nnz = an%eq%solver%factor_nnz
    summary%flops = an%eq%solver%flops
    summary%single_precision_factors = an%eq%solver%lower_precision_factors
    summary%test_solve_error = an%eq%solver%test_solve_error
    summary%precision_fallbacks = an%eq%solver%precision_fallbacks
    if (allocated(an%eq%solver%rank_memory_mb)) then
      summary%rank_memory_mb = an%eq%solver%rank_memory_mb
      summary%rank_factor_seconds = an%eq%solver%rank_factor_seconds
    end if
    if (allocated(an%eq%lu)) then
      ! MUMPS's LU of the non-symmetric tangents: its own instance on the same ranks
      if (allocated(an%eq%lu%rank_memory_mb) .and. allocated(summary%rank_memory_mb)) then
        summary%rank_memory_mb = max(summary%rank_memory_mb, an%eq%lu%rank_memory_mb)
        summary%rank_factor_seconds = summary%rank_factor_seconds + an%eq%lu%rank_factor_seconds
      end if
    end if
    if (an%part%distributed .or. allocated(summary%rank_memory_mb)) call summarise_ranks(an, summary)
    summary%min_pivot_ratio = an%eq%solver%min_pivot_ratio
    summary%max_pivot_ratio = an%eq%solver%max_pivot_ratio
    summary%applied_force = sum(an%path%f_applied, dim=2)
    summary%reaction_force = 0.0_dp
    do n = 1, model%nnode
      if (any(an%eq%map%constrained(:, n))) summary%reaction_force = summary%reaction_force + support_reaction(an, n)
      length = magnitude(an%path%u(:, n))
      if (length > summary%max_displacement) then
        summary%max_displacement = length
        summary%max_displacement_node = n
      end if
    end do
  end subroutine run_analysis

  !> Each rank's elements, its time assembling and updating them and its largest resident
  !! memory so far, on every rank.
  subroutine summarise_ranks(an, summary)
    type(analysis_t), intent(in) :: an
    type(analysis_summary_t), intent(inout) :: summary
    integer :: r
    allocate (summary%rank_elements(an%part%ranks), summary%rank_element_seconds(an%part%ranks), &
              summary%rank_peak_memory_mb(an%part%ranks))
    do r = 0, an%part%ranks - 1
      summary%rank_elements(r + 1) = real(an%part%elements_of_rank(r), dp)
    end do
    summary%rank_element_seconds = 0.0_dp
    summary%rank_element_seconds(an%part%rank + 1) = summary%time_assembly + summary%time_update
    call sum_over_ranks(summary%rank_element_seconds, size(summary%rank_element_seconds, kind=i8))
    summary%rank_peak_memory_mb = 0.0_dp
    summary%rank_peak_memory_mb(an%part%rank + 1) = peak_memory_mb()
    call sum_over_ranks(summary%rank_peak_memory_mb, size(summary%rank_peak_memory_mb, kind=i8))
  end subroutine summarise_ranks

  !> The summary totals restart data carry (feps_restart_data's order).
  pure function summary_reals_of(data) result(x)
    type(restart_data_t), intent(in) :: data
    real(dp), allocatable :: x(:)
    x = summary_reals(data%summary)
  end function summary_reals_of

  pure function summary_ints_of(data) result(k)
    type(restart_data_t), intent(in) :: data
    integer, allocatable :: k(:)
    k = summary_ints(data%summary)
  end function summary_ints_of

  !> Euclidean length without the under- or overflow of the squares that norm2 has in
  !! gfortran (a displacement of 1e-297 mm stays 1e-297, one of 1e200 stays finite).
  pure real(dp) function magnitude(v)
    real(dp), intent(in) :: v(:)
    real(dp) :: scale
    scale = maxval(abs(v))
    magnitude = 0.0_dp
    if (scale > 0.0_dp) magnitude = scale * norm2(v / scale)
  end function magnitude

  !> A run with restart data (RESTART, --restart-every, or continued from them) takes no
  !! path-following stage: the arc length and the previous increment that steer its steps are
  !! not in the restart data. An input error naming the first such STAGE record.
  subroutine check_path_restart(model, resuming, error)
    type(model_t), intent(in) :: model
    logical, intent(in) :: resuming
    type(error_t), allocatable, intent(out) :: error
    integer :: s
    if (model%restart_every == 0 .and. .not. resuming) return
    do s = 1, size(model%stages)
      associate (st => model%stages(s))
        if (st%path == path_load) cycle
        call input_error(error, st%file, st%line, 'PATH=' // to_upper(trim(path_names(st%path))) // ' (stage ' // st%name // &
                         ') steers its steps by an arc length and the previous increment, which restart data do ' // &
                         'not carry: run it without restart data (RESTART, --restart-every, --restart)', st%path_field)
        return
      end associate
    end do
  end subroutine check_path_restart

  !> Everything a run checks before it takes a step, without taking one: elements and their
  !! Jacobians, materials, face sets, DOF numbering, the sparse pattern, the solver's analysis,
  !! and, stage by stage, the loads, the prescribed displacements, the nodes of elements born
  !! later and the factorization of the elastic stiffness of the elements active in the stage
  !! (a missing support or rigid-body mode is found there, as in a run; summary%factor_nnz,
  !! %flops and the pivot ratios are those of the factorization). The same errors as
  !! run_analysis up to that point.
  subroutine check_analysis(model, solver_name, summary, error, observer)
    type(model_t), intent(inout) :: model     !! face sets are resolved into it
    character(len=*), intent(in) :: solver_name
    type(analysis_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    class(observer_t), intent(inout), optional :: observer   !! gets one line per stage
    type(analysis_t) :: an
    real(dp), allocatable :: df(:, :), duc(:, :), dps(:), post(:)
    real(dp) :: t0, f(3)
    integer :: s, g
    logical :: changed
    character(len=:), allocatable :: line
    character(len=40) :: buf
    type(path_t) :: pt

    t0 = wall_clock()
    call set_up(model, solver_name, an, summary, error)
    if (allocated(error)) return
    call check_path_restart(model, .false., error)
    if (allocated(error)) return
    call init_states(model, an)
    summary%state_bytes = state_bytes(an%states)
    call set_crack_bands(model, an, error)
    if (allocated(error)) return
    call check_in_situ_field(model, an, error)
    if (allocated(error)) return
    allocate (an%path%f_ref(3, model%nnode), df(3, model%nnode), duc(3, model%nnode), dps(size(model%groups)))
    call nodal_load_vector(model, an%kernels, an%path%f_ref, error, stage=0)
    if (allocated(error)) return
    summary%time_assembly = wall_clock() - t0
    allocate (an%path%f_applied(3, model%nnode))
    an%path%f_applied = 0.0_dp
    do s = 1, size(model%stages)
      ! as a run reports a failed factorization: a nonlinear run factorizes in the stage's first step
      call start_elastic_stage(model, an, s, summary, changed, error, observer=observer, &
                               name_failed_step=.not. summary%linear)
      if (allocated(error)) return
      call stage_increments(model, an, s, df, duc, dps, error)
      if (allocated(error)) return
      if (model%stages(s)%path /= path_load) then
        ! the path's own checks (loads only, the followed DOF free), as a run makes them
        call start_path(model, an, model%stages(s), df, duc, dps, pt, error)
        if (allocated(error)) return
      end if
      summary%steps = summary%steps + model%stages(s)%steps
      f = sum(df, dim=2)
      summary%applied_force = summary%applied_force + f
      if (.not. present(observer)) cycle
      associate (st => model%stages(s), c => model%stages(s)%controls)
        line = 'stage ' // st%name // ': ' // str(st%steps) // ' steps, ' // &
               trim(merge('linear (one solve)     ', method_names(c%method), summary%linear))
        if (.not. summary%linear) line = line // ', at most ' // str(c%max_iterations) // &
                                         ' iterations per step' // residual_target(c)
        write (buf, '(3(1x,es10.3))') f
        line = line // '; load increment' // trim(buf) // ' N; ' // str(count(duc /= 0.0_dp)) // ' DOFs moved'
        do g = 1, size(model%groups)
          if (model%groups(g)%activate_stage == s .and. s > 1) line = line // '; born: ' // model%groups(g)%name
        end do
        do g = 1, size(model%groups)
          if (dps(g) == 0.0_dp) cycle
          write (buf, '(es10.3)') dps(g)
          line = line // '; prestress ' // model%groups(g)%name // ' ' // trim(adjustl(buf)) // ' N'
        end do
        post = model%stage_prestress(s, after=.true.)
        do g = 1, size(model%groups)
          if (post(g) == 0.0_dp) cycle
          write (buf, '(es10.3)') post(g)
          line = line // '; post-tension ' // model%groups(g)%name // ' ' // trim(adjustl(buf)) // ' N (bonded next stage)'
        end do
      end associate
      call observer%progress(line)
    end do
    summary%factor_nnz = an%eq%solver%factor_nnz
    summary%flops = an%eq%solver%flops
    summary%min_pivot_ratio = an%eq%solver%min_pivot_ratio
    summary%max_pivot_ratio = an%eq%solver%max_pivot_ratio
  end subroutine check_analysis

  !> The start of a stage on the elastic stiffness (the linear driver, feps --check): the
  !! stage's supports and born groups, then a factorization when either changed (and in the
  !! first stage). With name_failed_step a failed factorization names stage, step 1 and load
  !! factor, as the nonlinear driver reports it.
  subroutine start_elastic_stage(model, an, s, summary, changed, error, observer, name_failed_step)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer, intent(in) :: s
    type(analysis_summary_t), intent(inout) :: summary
    logical, intent(out) :: changed
    type(error_t), allocatable, intent(out) :: error
    class(observer_t), intent(inout), optional :: observer
    logical, intent(in), optional :: name_failed_step
    logical :: born
    call change_supports(model, an, s, changed, summary, error, observer)
    if (allocated(error)) return
    call activate_groups(model, an, s, born)
    if (.not. (s == 1 .or. born .or. changed)) return
    call check_born_nodes(model, an, s, error)
    if (allocated(error)) return
    call factorize_tangent(model, an, .true., summary, error)
    if (.not. allocated(error) .or. .not. present(name_failed_step)) return
    if (name_failed_step) call name_step(error, model%stages(s), 1, real(s - 1, dp))
  end subroutine start_elastic_stage

  ! ---------------------------------------------------------------------------------------
  ! Linear models
  ! ---------------------------------------------------------------------------------------

  !> Each stage of a linear model in one solve, whatever its steps and method. All a stage
  !! adds (loads, prescribed displacements, prestress, released support forces) enters linearly,
  !! so its step k of n is exactly the stage's start plus k/n of that solve: the steps its
  !! OUTPUT=k asks for, and its last, are written from that scaling, each with the reactions,
  !! stresses and residual of its own state.
  subroutine run_linear_stages(model, an, observer, summary, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: df(:, :), duc(:, :), dps(:), r(:)
    real(dp), allocatable :: u0(:, :), f0(:, :), uc0(:, :), u_end(:, :)   !! the stage's start and its solution
    real(dp) :: t0, rnorm, pnorm, r_scale, t, t_done
    integer :: s, k, n, step
    logical :: changed

    allocate (df(3, model%nnode), duc(3, model%nnode), dps(size(model%groups)), r(an%eq%map%neq))
    step = 0
    do s = 1, size(model%stages)
      n = model%stages(s)%steps
      call start_elastic_stage(model, an, s, summary, changed, error, observer=observer)
      if (allocated(error)) return
      if (changed) then
        deallocate (r)
        allocate (r(an%eq%map%neq))
      end if
      call stage_increments(model, an, s, df, duc, dps, error)
      if (allocated(error)) return
      u0 = an%path%u
      f0 = an%path%f_applied
      uc0 = an%path%uc
      an%path%f_applied = f0 + df
      an%path%uc = uc0 + duc
      ! Move the constrained DOFs, then one solve for the free ones.
      call set_trial(model, an)
      call update_points(model, an, dps)
      call residual(an, r, rnorm, pnorm)
      r_scale = rnorm
      t0 = wall_clock()
      call an%eq%solver%solve(r, error)
      if (allocated(error)) return
      summary%time_solve = summary%time_solve + wall_clock() - t0
      call check_finite_solution(model, an, s, r, 'the solution', error)
      if (allocated(error)) return
      call add_free(an, r, an%path%u_t)
      u_end = an%path%u_t
      summary%iterations = summary%iterations + 1
      ! The steps written: each state from the last one committed (point states carry the
      ! groups born in a stage and the prestressed ones) with its share of the prestress.
      t_done = 0.0_dp
      do k = 1, n
        if (.not. writes_step(model%stages(s), k)) cycle
        t = real(k, dp) / n
        if (k < n) then
          an%path%u_t = u0 + t * (u_end - u0)
          an%path%f_applied = f0 + t * df
          an%path%uc = uc0 + t * duc
        else
          an%path%u_t = u_end
          an%path%f_applied = f0 + df
          an%path%uc = uc0 + duc
        end if
        call update_points(model, an, dps * (t - t_done))
        call residual(an, r, rnorm, pnorm)
        call check_finite_solution(model, an, s, r, 'the residual', error)
        if (allocated(error)) return
        ! A stage loaded only by a prestress (a band on a free pipe) has no load and no
        ! reaction: its initial out-of-balance force is the scale, as in substep.
        if (pnorm <= 1.0e-8_dp * t * r_scale) pnorm = t * r_scale
        call commit(an)
        t_done = t
        call observer%progress(progress_line(s, k, n, s - 1 + t, 1, rnorm / pnorm, summary%factorizations, 0))
        call report_step(model, an, observer, step + k, s, k, s - 1 + t, 1, rnorm / pnorm, error)
        if (allocated(error)) return
      end do
      step = step + n
      summary%steps = step
    end do
  end subroutine run_linear_stages

  !> The linear driver has no cut-back to catch a solve that left double precision (the loads
  !! are finite, but too large for the stiffness, or a degenerate nodal system brought NaN in):
  !! stop, naming the stage and the first DOF where `x` (a solution, or a residual) is not finite.
  subroutine check_finite_solution(model, an, s, x, what, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: s
    real(dp), intent(in) :: x(:)
    character(len=*), intent(in) :: what
    type(error_t), allocatable, intent(out) :: error
    integer :: ieq
    if (all(ieee_is_finite(x))) return
    ieq = findloc(ieee_is_finite(x), .false., dim=1)
    call fatal_error(error, err_solver, model%deck_file // ': stage ' // model%stages(s)%name // ': ' // what // &
                     ' is not finite at ' // an%eq%map%dof_name(ieq) // ' (' // str(x(ieq)) // '): the loads or ' // &
                     'prescribed displacements are too large for the stiffness (beyond double precision), or ' // &
                     'a nodal system (FIX ..., CSYS=) gives no direction')
  end subroutine check_finite_solution

  ! ---------------------------------------------------------------------------------------
  ! Nonlinear models
  ! ---------------------------------------------------------------------------------------

  !> The stages of a nonlinear model step by step: the stiffness the method asks for, the
  !! iterations of each (sub)step, cut-backs, and the steps carried unconverged.
  subroutine run_nonlinear_stages(model, an, observer, summary, fingerprint, error, resume, stop_after)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(inout) :: summary
    integer(i8), intent(in) :: fingerprint           !! the model's, for the restart data written
    type(error_t), allocatable, intent(out) :: error
    type(restart_data_t), intent(in), optional :: resume   !! continue after its step
    integer, intent(in), optional :: stop_after            !! a test aid: fail after this step
    real(dp), allocatable :: df(:, :), duc(:, :), dps(:), r(:)
    real(dp) :: h, done, rnorm, pnorm, t_start
    integer :: s, k, step, iters, cut, nfact0, iters_step, opened, mechanism, total_steps
    character(len=:), allocatable :: step_notes, run_notes
    logical :: ok, step_unconverged, born, changed
    type(factor_state_t) :: f              !! the factor held, carried from stage to stage
    class(solution_method_t), allocatable :: method
    logical, allocatable :: fully_open(:)
    integer :: s_first, k_first, k_start
    logical :: mid_stage, stage_done
    real(dp) :: lf
    type(path_t) :: pt

    allocate (df(3, model%nnode), duc(3, model%nnode), dps(size(model%groups)), r(an%eq%map%neq), &
              fully_open(size(model%groups)))
    fully_open = .false.
    step = 0
    s_first = 1
    k_first = 1
    if (present(resume)) then
      ! Continue after the step of the restart data: its counters, factor state and notes.
      step = resume%step
      s_first = resume%stage
      k_first = resume%step_in_stage + 1
      f = resume%factor
      fully_open = resume%fully_open
      run_notes = resume%run_notes
      if (k_first > model%stages(s_first)%steps) then
        s_first = s_first + 1
        k_first = 1
      end if
      call observer%progress('continued from ' // resume%source // ' after step ' // str(resume%step) // &
                             ' (stage ' // model%stages(resume%stage)%name // ', step ' // &
                             str(resume%step_in_stage) // ')')
    end if
    total_steps = sum(model%stages%steps)
    t_start = wall_clock()
    do s = s_first, size(model%stages)
      associate (st => model%stages(s), c => model%stages(s)%controls)
        call new_solution_method(c%method, method, error)
        if (allocated(error)) return
        ! A run continued within a stage: the stage has started (supports, births, factor state
        ! restored); only its increments are computed again.
        mid_stage = s == s_first .and. k_first > 1
        k_start = 1
        if (mid_stage) k_start = k_first
        if (.not. mid_stage) then
          call change_supports(model, an, s, changed, summary, error, observer)
          if (allocated(error)) return
          if (changed) then
            deallocate (r)
            allocate (r(an%eq%map%neq))
            f%have_factor = .false.     ! a new set of equations: factorize again, whatever the method
          end if
          call activate_groups(model, an, s, born)
          if (s == 1 .or. born .or. changed) then
            call check_born_nodes(model, an, s, error)
            if (allocated(error)) return
            ! New elements change the stiffness: refactorize (the tangent, or the initial
            ! stiffness for that method) before the stage's first step.
            if (s > 1 .and. method%refactors_for_new_elements()) f%have_factor = .false.
            if (s > 1) f%rel_prev = huge(1.0_dp)
          end if
        end if
        if (s == model%geostatic_stage) then
          call set_in_situ_stress(model, an, error)
          if (allocated(error)) return
        end if
        call stage_increments(model, an, s, df, duc, dps, error)
        if (allocated(error)) return
        call observer%progress('stage ' // st%name // ': ' // str(st%steps) // ' steps, method ' // &
                               trim(method_names(c%method)) // ', at most ' // str(c%max_iterations) // &
                               ' iterations per step' // residual_target(c))
        if (st%path /= path_load) then
          call observer%progress('stage ' // st%name // ': PATH=' // trim(path_names(st%path)) // &
                                 ', the load factor of the stage''s loads follows the path')
          call start_path(model, an, st, df, duc, dps, pt, error)
          if (allocated(error)) return
        end if
        stage_done = .false.
        do k = k_start, st%steps
          step = step + 1
          done = 0.0_dp
          h = 1.0_dp
          cut = 0
          iters_step = 0
          nfact0 = summary%factorizations
          step_unconverged = .false.
          step_notes = ''
          if (st%path /= path_load) then
            call path_step(model, an, method, observer, st, s, k, f, pt, r, rnorm, pnorm, iters_step, summary, &
                           step_notes, run_notes, stage_done, error)
            if (allocated(error)) return
            done = 1.0_dp
          end if
          do while (done < 1.0_dp - 1.0e-12_dp)
            h = min(h, 1.0_dp - done)
            ! Which stiffness: the method decides (thesis 2.6.3).
            if (method%needs_factor(f, c)) then
              ! The tangent of the committed state (the elastic stiffness before the first step),
              ! also when new supports renumber the equations, unless the method asks for the
              ! elastic one (initial stiffness; modified Newton-Raphson's retry after a cut-back).
              f%factor_elastic = method%factorizes_elastic(f)
              call factorize_tangent(model, an, f%factor_elastic, summary, error, exact=method%exact_tangent())
              if (allocated(error)) then
                call explain_failed_factorization(model, an, st, k, s - 1 + (k - 1 + done) / st%steps, &
                                                  s - 1 + (k - 1 + done + h) / st%steps, last_state(f, c), &
                                                  summary, error)
                return
              end if
              f%have_factor = .true.
              f%elastic_retry = .false.
            end if
            call substep(model, an, method, c, df * (h / st%steps), duc * (h / st%steps), dps * (h / st%steps), &
                         r, rnorm, pnorm, iters, ok, summary, error, step_notes)
            if (allocated(error)) then
              ! full Newton-Raphson refactorizes within the step
              call explain_failed_factorization(model, an, st, k, s - 1 + (k - 1 + done) / st%steps, &
                                                s - 1 + (k - 1 + done + h) / st%steps, last_state(f, c), summary, &
                                                error)
              return
            end if
            iters_step = iters_step + iters
            if (ok) then
              done = done + h
              f%rel_prev = rnorm / pnorm
              f%rel_accepted = f%rel_prev
              f%abs_prev = rnorm
              if (.not. (f%rel_prev < c%delta1 .or. rnorm < c%delta2)) step_unconverged = .true.
              call commit(an)
              call collect_point_notes(model, an, .false., run_notes)
              an%path%f_applied = an%path%f_applied + df * (h / st%steps)
              an%path%uc = an%path%uc + duc * (h / st%steps)
            else
              cut = cut + 1
              summary%cutbacks = summary%cutbacks + 1
              opened = newly_open_points(an)
              if (cut > c%max_cutbacks) then
                ! Where the last try's tangent is singular (its elastic counterpart is not), the
                ! load has formed a mechanism: the stop is a collapse.
                if (rnorm <= huge(rnorm)) call find_mechanism(model, an, .true., summary, mechanism)
                call restore(an)
                call stop_error(model, an, r, st, k, s - 1 + (k - 1 + done + h) / st%steps, &
                                s - 1 + (k - 1 + done) / st%steps, last_state(f, c), rnorm / pnorm, &
                                cut > c%max_cutbacks, opened, step_notes, error, mechanism)
                return
              end if
              call restore(an)
              h = h / 2.0_dp
              ! After a cut-back, start again from a new factorization, of the stiffness the
              ! method says (modified Newton-Raphson: the elastic one).
              call method%after_cutback(f)
              call observer%progress('  step ' // str(k) // ' diverged: cut back to ' // str(h) // ' of a step')
            end if
          end do
          summary%steps = step
          summary%iterations = summary%iterations + iters_step
          lf = s - 1 + real(k, dp) / st%steps
          if (st%path /= path_load) lf = s - 1 + pt%lam
          if (step_unconverged) summary%unconverged_steps = summary%unconverged_steps + 1
          ! A stage that ends out of balance: the run says so (and --strict refuses it).
          if (k == st%steps .and. .not. (f%rel_prev < c%delta1 .or. f%abs_prev < c%delta2)) &
            call note_unbalanced(an, st, real(s, dp), r, f%rel_prev, summary)
          call observer%progress(progress_line(s, k, st%steps, lf, iters_step, &
                                               f%rel_prev, summary%factorizations, summary%factorizations - nfact0) &
                                 // trim(merge('  (not converged: carried) ', '                           ', &
                                                step_unconverged)) // &
                                 time_text(wall_clock() - t_start, step, total_steps))
          call report_open_interfaces(model, an, observer, fully_open)
          if (writes_step(st, k) .or. stage_done) then
            call report_step(model, an, observer, step, s, k, lf, iters_step, f%rel_prev, error)
            if (allocated(error)) return
          end if
          if (s == model%geostatic_stage .and. k == st%steps) then
            call end_geostatic_stage(an)
            call observer%progress('stage ' // st%name // ': in-situ stress set (GEOSTATIC); displacements ' // &
                                   'count from zero from here on')
          end if
          if (model%restart_every > 0) then
            if (mod(step, model%restart_every) == 0) then
              call checkpoint(an, observer, summary, f, fingerprint, step, s, k, fully_open, run_notes, error)
              if (allocated(error)) return
            end if
          end if
          if (present(stop_after)) then
            if (step == stop_after) then
              call fatal_error(error, err_solver, model%deck_file // ': stopped after step ' // str(step) // &
                               ' (--stop-after-step, a test aid that stands for a run that dies)')
              return
            end if
          end if
          if (stage_done) exit
        end do
        if (st%path == path_arc_length) then
          if (stage_done) then
            call observer%progress('stage ' // st%name // ': PATH=arc-length reached the stage''s full load ' // &
                                   '(load factor ' // str(real(s, dp)) // ') in ' // str(k) // ' steps')
          else
            call observer%progress('stage ' // st%name // ': PATH=arc-length ended after its ' // str(st%steps) // &
                                   ' steps at load factor ' // str(s - 1 + pt%lam) // ' (' // str(pt%lam) // &
                                   ' of the stage''s load; its full load not reached)')
          end if
        end if
      end associate
    end do
    if (summary%lu_factorizations > 0) call observer%progress('note: ' // str(summary%lu_factorizations) // &
      ' tangents were non-symmetric (non-associated flow, psi /= phi, or a gap closing within a step): ' // &
      'factorized as they are by UMFPACK (LU)')
    if (an%eq%lu_singular > 0) call observer%progress('note: ' // str(an%eq%lu_singular) // ' exact non-symmetric ' // &
      'tangents were singular (a body held only by faces sliding without dilation): their nearest symmetric ' // &
      'positive semi-definite stand-ins were factorized')
    if (allocated(run_notes)) then
      if (len(run_notes) > 0) call observer%progress('note: ' // run_notes)
    end if
    if (an%eq%symmetrized) call observer%progress('note: the tangent was non-symmetric at some points (non-' // &
                                               'associated flow, psi /= phi, or a gap closing within a step); ' // &
                                               'each material''s symmetric stand-in was factorized (by ' // &
                                               'default the nearest positive semi-definite matrix) and the ' // &
                                               'exact residual iterated on')
  end subroutine run_nonlinear_stages

  !> The layers of a GEOSTATIC stage's in-situ stress, checked before anything is solved (an
  !! input error names the record).
  subroutine check_in_situ_field(model, an, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    type(error_t), allocatable, intent(out) :: error
    type(in_situ_field_t) :: field
    if (model%geostatic_stage > 0) call build_in_situ_field(model, an, field, error)
  end subroutine check_in_situ_field

  !> Hand the restart data of the end of step `step` (step k of stage s) to the observer:
  !! the analysis state, the factor state, the totals so far and the run's notes.
  subroutine checkpoint(an, observer, summary, f, fingerprint, step, s, k, fully_open, run_notes, error)
    type(analysis_t), intent(in) :: an
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(in) :: summary
    type(factor_state_t), intent(in) :: f
    integer(i8), intent(in) :: fingerprint
    integer, intent(in) :: step, s, k
    logical, intent(in) :: fully_open(:)
    character(len=:), allocatable, intent(in) :: run_notes
    type(error_t), allocatable, intent(out) :: error
    type(restart_data_t) :: data
    data%fingerprint = fingerprint
    data%step = step
    data%stage = s
    data%step_in_stage = k
    call save_state(an, data)
    data%factor = f
    data%summary = summary
    data%fully_open = fully_open
    data%run_notes = ''
    if (allocated(run_notes)) data%run_notes = run_notes
    call observer%checkpoint(data, error)
    call share_root_error(error)   ! rank 0 writes: every rank stops where it fails
  end subroutine checkpoint

  !> Record that stage `st` ended with the unbalanced force r (|R| / |P| = rel) above its
  !! tolerance: the run is not converged, and the largest such residual is kept with where.
  subroutine note_unbalanced(an, st, lf, r, rel, summary)
    type(analysis_t), intent(in) :: an
    type(stage_t), intent(in) :: st
    real(dp), intent(in) :: lf             !! the load factor at the stage's end
    real(dp), intent(in) :: r(:)
    real(dp), intent(in) :: rel
    type(analysis_summary_t), intent(inout) :: summary
    integer :: imax
    if (.not. summary%converged .and. .not. (rel > summary%unbalanced)) return
    summary%converged = .false.
    summary%unbalanced = rel
    imax = maxloc(abs(r), dim=1, mask=r == r)
    summary%unbalanced_stage = st%name
    summary%unbalanced_step = st%steps
    summary%unbalanced_load_factor = lf
    summary%unbalanced_at = ''
    if (imax >= 1) summary%unbalanced_at = an%eq%map%dof_name(imax)
    summary%unbalanced_tolerance = st%controls%delta1
  end subroutine note_unbalanced

  !> What a step iterates to, for the stage lines: `, to a relative residual of 1.00E-04` (DELTA1,
  !! which --tolerance sets; `or 5.00E-01 N` with DELTA2). Nothing for the Euler methods, which
  !! take one iteration whatever the residual.
  pure function residual_target(c) result(text)
    type(controls_t), intent(in) :: c
    character(len=:), allocatable :: text
    character(len=12) :: buf
    text = ''
    if (c%method == method_euler .or. c%method == method_modified_euler) return
    write (buf, '(es9.2)') c%delta1
    text = ', to a relative residual of ' // trim(adjustl(buf))
    if (c%delta2 <= 0.0_dp) return
    write (buf, '(es9.2)') c%delta2
    text = text // ' or ' // trim(adjustl(buf)) // ' N'
  end function residual_target

  !> What the last accepted state was, for a stop's message: in equilibrium (within the
  !! stage's tolerance), or accepted out of balance (the unbalanced force carried).
  function last_state(f, c) result(text)
    type(factor_state_t), intent(in) :: f
    type(controls_t), intent(in) :: c
    character(len=:), allocatable :: text
    if (f%rel_accepted < c%delta1 .or. f%abs_prev < c%delta2) then
      text = 'the last state in equilibrium'
    else
      text = 'the last state accepted, out of balance by a relative residual of ' // str(f%rel_accepted) // &
             ' (carried)'
    end if
  end function last_state

  !> A factorization that failed during the steps. A singular stiffness whose elastic
  !! counterpart (the same supports and elements, every point elastic) factorizes is a
  !! mechanism that the load has formed, not a missing support: collapse (a run failure, exit
  !! status 1), naming the stage, the step, the last load factor in equilibrium and the node
  !! and DOF where the mechanism runs, whatever the method. Where the elastic stiffness is
  !! singular too, the model lacks a support (the model error as the first factorization gives
  !! it); any other failure is named with the step and passed on.
  subroutine explain_failed_factorization(model, an, st, k, lf_equilibrium, lf_try, last, summary, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k
    real(dp), intent(in) :: lf_equilibrium   !! the load factor of the last state in equilibrium
    real(dp), intent(in) :: lf_try           !! the load factor the (sub)step was going to
    character(len=*), intent(in) :: last     !! what the last accepted state was (last_state)
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(inout) :: error
    integer :: ieq
    ieq = error%item
    if (error%code /= err_model .or. ieq < 1 .or. ieq > an%eq%map%neq) then
      call name_step(error, st, k, lf_try)
      return
    end if
    if (.not. elastic_factorizes(model, an, summary)) then
      call name_step(error, st, k, lf_try)
      return
    end if
    call collapse_error(model, an, st, k, lf_equilibrium, last, 'the step went to ' // str(lf_try), 'there', &
                        ieq, error)
  end subroutine explain_failed_factorization

  !> Whether the elastic stiffness of the model as it stands (supports, active groups)
  !! factorizes: a singular tangent is then a mechanism of the load, not a missing support.
  !! Replaces the factor held.
  logical function elastic_factorizes(model, an, summary) result(ok)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable :: elastic_error
    call factorize_tangent(model, an, .true., summary, elastic_error)
    ok = .not. allocated(elastic_error)
  end function elastic_factorizes

  !> The equation where the tangent of the current trial state (`trial`) or of the committed
  !! one is singular while the elastic stiffness of the same model is not: where a mechanism
  !! runs (0 where none is found). Replaces the factor held.
  subroutine find_mechanism(model, an, trial, summary, ieq)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    logical, intent(in) :: trial
    type(analysis_summary_t), intent(inout) :: summary
    integer, intent(out) :: ieq
    type(error_t), allocatable :: probe_error
    ieq = 0
    call factorize_tangent(model, an, .false., summary, probe_error, trial=trial, exact=.true.)
    if (.not. allocated(probe_error)) return
    if (probe_error%code /= err_model .or. probe_error%item < 1 .or. probe_error%item > an%eq%map%neq) return
    ieq = probe_error%item
    if (.not. elastic_factorizes(model, an, summary)) ieq = 0
  end subroutine find_mechanism

  !> One (sub)step: move the constrained DOFs by duc, apply df, iterate on the residual.
  !! ok is false when the step diverges (non-finite or growing residual, or iterations run out
  !! far from convergence).
  subroutine substep(model, an, method, c, df, duc, dps, r, rnorm, pnorm, iters, ok, summary, error, notes)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    class(solution_method_t), intent(in) :: method
    type(controls_t), intent(in) :: c
    real(dp), intent(in) :: df(:, :), duc(:, :)
    real(dp), intent(in) :: dps(:)          !! prestress force added to each group's bars
    real(dp), intent(inout) :: r(:)
    real(dp), intent(out) :: rnorm, pnorm
    integer, intent(out) :: iters
    logical, intent(out) :: ok
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    !> materials' notes about the states of every iterate (collect_point_notes)
    character(len=:), allocatable, intent(inout) :: notes
    real(dp), allocatable :: r_carry(:)
    real(dp) :: t0, r_first, rel, r_scale
    integer :: m
    logical :: use_bfgs
    type(bfgs_t) :: bfgs
    real(dp), allocatable :: du(:), r0(:), u_base(:, :)   !! line search: correction, R and u before it
    real(dp) :: g0

    if (.not. method%carries_residual()) then
      ! Euler drops the unbalanced force of the previous step (eq. 2.6.4 not applied).
      allocate (r_carry(size(r)))
      call committed_residual(model, an, r_carry)
    end if
    an%path%f_applied = an%path%f_applied + df
    an%path%uc = an%path%uc + duc
    call set_trial(model, an)
    call update_points(model, an, dps)
    call collect_point_notes(model, an, .true., notes)
    call residual(an, r, rnorm, pnorm)
    if (allocated(r_carry)) r = r - r_carry
    r_scale = rnorm
    ok = .true.
    r_first = -1.0_dp
    iters = 0
    use_bfgs = method%takes_bfgs(c)
    if (use_bfgs) call bfgs%start(size(r), c%max_iterations)
    if (c%line_search) then
      allocate (du(size(r)), r0(size(r)), u_base(3, size(an%path%u_t, 2)))
      summary%line_search = .true.
    end if
    do m = 1, c%max_iterations
      if (method%exact_tangent() .and. m > 1) then
        ! Full Newton: the consistent tangent of the current iterate, refactorized every iteration
        ! (factorize_tangent times its assembly and factorization itself).
        call factorize_tangent(model, an, .false., summary, error, trial=.true., exact=.true.)
        if (allocated(error)) exit
      end if
      t0 = wall_clock()
      if (c%line_search) r0 = r
      if (use_bfgs) then
        call bfgs%direction(an%eq%solver, r, error)
      else
        call an%eq%solve(r, error)
      end if
      if (allocated(error)) exit
      summary%time_solve = summary%time_solve + wall_clock() - t0
      if (c%line_search) then
        g0 = dot_product(r, r0)     ! du . R(u)
        du = r
        u_base = an%path%u_t
      end if
      call add_free(an, r, an%path%u_t)
      if (use_bfgs) call bfgs%record_correction(r)
      t0 = wall_clock()
      call update_points(model, an, dps)
      call collect_point_notes(model, an, .true., notes)
      summary%time_update = summary%time_update + wall_clock() - t0
      call residual(an, r, rnorm, pnorm)
      if (use_bfgs) call bfgs%add_pair(r)
      ! The step's initial out-of-balance force is the scale only when load and reactions
      ! vanish (a block lifted off: no load, no reaction, no stress).
      if (pnorm <= 1.0e-8_dp * r_scale) pnorm = r_scale
      ! LINESEARCH=energy: a converged iterate is kept as it is
      if (c%line_search .and. .not. (rnorm / pnorm < c%delta1 .or. rnorm < c%delta2)) then
        call search_line(model, an, dps, u_base, du, g0, r, rnorm, pnorm, summary, notes)
        if (pnorm <= 1.0e-8_dp * r_scale) pnorm = r_scale
      end if
      iters = m
      rel = rnorm / pnorm
      if (.not. (rnorm <= huge(rnorm))) then
        ok = .false.
        exit
      end if
      if (r_first < 0.0_dp) r_first = rnorm
      if (rel < c%delta1 .or. rnorm < c%delta2) exit
      if (m > 1 .and. rnorm > 1.0e4_dp * r_first) then
        ok = .false.
        exit
      end if
    end do
    ! Undo the step's load and constraint increments; the caller applies them on success.
    an%path%f_applied = an%path%f_applied - df
    an%path%uc = an%path%uc - duc
    if (allocated(error)) return
    if (.not. ok) return
    rel = rnorm / pnorm
    ! Newton-Raphson must converge; the other methods may end a step unconverged and carry the
    ! unbalanced force (thesis 2.6.3), unless it exceeds the divergence limit.
    ok = method%step_accepted(rel, rnorm, c)
  end subroutine substep

  !> One step of a path-following stage (PATH=ARC-LENGTH or DISPLACEMENT, feps_path_following)
  !! from the committed state, with cut-backs: a step that does not converge is tried again
  !! with half the arc length (arc-length) or half the displacement (displacement control, the
  !! rest of the step following in further substeps). An arc that would pass the stage's full
  !! load is replaced by a step to exactly that load (stage_done). The stiffness is the
  !! method's; where its tangent is singular (at a limit point, on a plateau) the elastic
  !! stiffness is factorized instead, the constraint equation keeping the system regular.
  subroutine path_step(model, an, method, observer, st, s, k, f, pt, r, rnorm, pnorm, iters_step, summary, &
                       notes, run_notes, stage_done, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    class(solution_method_t), intent(in) :: method
    class(observer_t), intent(inout) :: observer
    type(stage_t), intent(in) :: st
    integer, intent(in) :: s, k
    type(factor_state_t), intent(inout) :: f
    type(path_t), intent(inout) :: pt
    real(dp), intent(inout) :: r(:)
    real(dp), intent(out) :: rnorm, pnorm
    integer, intent(out) :: iters_step
    type(analysis_summary_t), intent(inout) :: summary
    character(len=:), allocatable, intent(inout) :: notes, run_notes
    logical, intent(out) :: stage_done
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: du(:)
    real(dp) :: h, done, target, dlam
    integer :: cut, iters, mode, mechanism
    logical :: ok
    stage_done = .false.
    iters_step = 0
    h = 1.0_dp
    done = 0.0_dp
    cut = 0
    mode = constrain_displacement
    if (st%path == path_arc_length) mode = constrain_arc
    associate (c => st%controls)
      do while (done < 1.0_dp - 1.0e-12_dp)
        h = min(h, 1.0_dp - done)
        if (method%needs_factor(f, c)) then
          f%factor_elastic = method%factorizes_elastic(f)
          call factorize_tangent(model, an, f%factor_elastic, summary, error, exact=method%exact_tangent())
          if (allocated(error) .and. .not. f%factor_elastic) then
            deallocate (error)
            f%factor_elastic = .true.
            call factorize_tangent(model, an, .true., summary, error)
          end if
          if (allocated(error)) then
            call explain_failed_factorization(model, an, st, k, s - 1 + pt%lam, s - 1 + pt%lam, last_state(f, c), &
                                              summary, error)
            return
          end if
          f%have_factor = .true.
          f%elastic_retry = .false.
        end if
        select case (mode)
        case (constrain_arc)
          target = pt%arc
        case (constrain_displacement)
          target = h * st%path_value / st%steps
        case default
          target = 1.0_dp - pt%lam
        end select
        call path_substep(model, an, c, method%exact_tangent(), pt, mode, target, dlam, du, r, rnorm, pnorm, iters, &
                          ok, summary, error, notes)
        if (allocated(error)) then
          call explain_failed_factorization(model, an, st, k, s - 1 + pt%lam, s - 1 + pt%lam + dlam, &
                                            last_state(f, c), summary, error)
          return
        end if
        iters_step = iters_step + iters
        if (ok .and. mode == constrain_arc .and. pt%lam < 1.0_dp .and. pt%lam + dlam > 1.0_dp - 1.0e-9_dp) then
          ! the arc passes (or all but reaches) the stage's full load: a step to exactly that load instead
          call restore(an)
          mode = constrain_load
          cycle
        end if
        if (ok) then
          call commit(an)
          call collect_point_notes(model, an, .false., run_notes)
          pt%lam = pt%lam + dlam
          an%path%f_applied = pt%f0 + pt%lam * pt%df
          pt%du_prev = du
          f%rel_prev = rnorm / pnorm
          f%rel_accepted = f%rel_prev
          f%abs_prev = rnorm
          if (mode == constrain_displacement) then
            done = done + h
          else
            done = 1.0_dp
          end if
          stage_done = mode == constrain_load
          ! an arc cut back grows again (doubling) after steps that converge easily
          if (mode == constrain_arc .and. cut == 0 .and. 2 * iters <= c%max_iterations) &
            pt%arc = min(pt%arc0, 2.0_dp * pt%arc)
        else
          cut = cut + 1
          summary%cutbacks = summary%cutbacks + 1
          if (cut > c%max_cutbacks) then
            mechanism = 0
            if (rnorm <= huge(rnorm)) call find_mechanism(model, an, .true., summary, mechanism)
            call restore(an)
            if (.not. abs(dlam) < huge(dlam)) dlam = 0.0_dp
            call stop_error(model, an, r, st, k, s - 1 + pt%lam + dlam, s - 1 + pt%lam, last_state(f, c), &
                            rnorm / pnorm, .true., newly_open_points(an), notes, error, mechanism)
            return
          end if
          call restore(an)
          if (mode == constrain_displacement) then
            h = h / 2.0_dp
            call observer%progress('  step ' // str(k) // ' diverged: cut back to ' // str(h) // ' of a step')
          else
            mode = constrain_arc
            pt%arc = pt%arc / 2.0_dp
            call observer%progress('  step ' // str(k) // ' diverged: arc length halved to ' // str(pt%arc))
          end if
          call method%after_cutback(f)
        end if
      end do
    end associate
  end subroutine path_step

  !> LINESEARCH=energy after an iteration whose full correction du (from u_base) left the
  !! residual r: where the correction overshoots (feps_line_search), the residual is evaluated
  !! again at u_base + s du for the factors the search asks for, and the last is kept (u_t,
  !! the points' trial states and tangents, r, |R|, |P|). Each evaluation updates every point
  !! from the committed state (path-independent within a step), as an iteration does.
  subroutine search_line(model, an, dps, u_base, du, g0, r, rnorm, pnorm, summary, notes)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    real(dp), intent(in) :: dps(:)
    real(dp), intent(in) :: u_base(:, :)
    real(dp), intent(in) :: du(:)
    real(dp), intent(in) :: g0                 !! du . R(u_base)
    real(dp), intent(inout) :: r(:)
    real(dp), intent(inout) :: rnorm, pnorm
    type(analysis_summary_t), intent(inout) :: summary
    character(len=:), allocatable, intent(inout) :: notes
    type(line_search_t) :: ls
    real(dp) :: t0
    call line_search_begin(ls, g0, dot_product(du, r), line_search_eta, line_search_s_min)
    if (ls%done) return
    summary%line_searches = summary%line_searches + 1
    do
      t0 = wall_clock()
      an%path%u_t = u_base
      call add_free(an, ls%s * du, an%path%u_t)
      call update_points(model, an, dps)
      call collect_point_notes(model, an, .true., notes)
      summary%time_update = summary%time_update + wall_clock() - t0
      call residual(an, r, rnorm, pnorm)
      summary%line_search_evaluations = summary%line_search_evaluations + 1
      call line_search_next(ls, dot_product(du, r), line_search_eta, line_search_s_min, &
                            line_search_max_evaluations)
      if (ls%done) exit
    end do
  end subroutine search_line

end module feps_incremental_analysis
