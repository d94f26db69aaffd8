!> What the incremental analysis tells its observer and its user: progress lines, the
!! results of the steps written, interface groups that open and close, the materials' notes
!! about point states, and the clear stop of a step that cannot be brought into balance.
module feps_step_report
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_solver, str
  use feps_result_schema, only: result_fields
  use feps_element_catalog, only: family_interface
  use feps_model, only: model_t, stage_t, output_fields_t, method_initial_stiffness, method_full_newton_raphson, &
                        method_newton_raphson
  use feps_assembly, only: group_kernel_t, element_strains
  use feps_material, only: state_open, state_elastic, state_tension
  use feps_observer, only: observer_t, step_result_t, group_result_t
  use feps_analysis_state, only: analysis_t, support_reaction, support_reaction_nodal
  use feps_parallel, only: share_root_error
  implicit none
  private

  public :: progress_line, time_text, collapse_error, report_step, report_open_interfaces, writes_step
  public :: name_step, newly_open_points, collect_point_notes, stop_error

contains

  !> Say when an interface group opens completely (only the residual gap stiffness then holds
  !! what it joined) and when it closes again.
  subroutine report_open_interfaces(model, an, observer, fully_open)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    class(observer_t), intent(inout) :: observer
    logical, intent(inout) :: fully_open(:)
    integer :: g
    logical :: now
    do g = 1, size(model%groups)
      if (an%kernels(g)%family /= family_interface) cycle
      now = all(an%states(g)%state == state_open)
      if (now .and. .not. fully_open(g)) then
        call observer%progress('note: interface group ' // model%groups(g)%name // ' is fully open (' // &
                               str(size(an%states(g)%state)) // ' points): only the residual gap stiffness ' // &
                               'holds what it joined')
      else if (fully_open(g) .and. .not. now) then
        call observer%progress('note: interface group ' // model%groups(g)%name // ' is in contact again')
      end if
      fully_open(g) = now
    end do
  end subroutine report_open_interfaces

  !> Is step k of the stage written (every OUTPUT=k-th step, and always its last)?
  pure logical function writes_step(st, k)
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k
    if (st%output_every > 0) then
      writes_step = mod(k, st%output_every) == 0 .or. k == st%steps
    else
      writes_step = k == st%steps
    end if
  end function writes_step

  !> Append stage, step and load factor to an error found during a step.
  subroutine name_step(error, st, k, lf)
    type(error_t), intent(inout) :: error
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k
    real(dp), intent(in) :: lf
    error%message = error%message // ' (stage ' // st%name // ', step ' // str(k) // ', load factor ' // str(lf) // ')'
  end subroutine name_step

  !> Interface points open in the trial state that were not open at the start of the step.
  pure integer function newly_open_points(an) result(n)
    type(analysis_t), intent(in) :: an
    integer :: g
    n = 0
    do g = 1, size(an%states)
      if (an%kernels(g)%family /= family_interface .or. .not. an%states(g)%nonlinear) cycle
      n = n + count(an%states(g)%state_t == state_open .and. an%states(g)%state /= state_open)
    end do
  end function newly_open_points

  !> Add to `notes` (separated by '; ') each material's note about a point state present in
  !! the trial (`trial`) or committed states of the active nonlinear groups, once.
  subroutine collect_point_notes(model, an, trial, notes)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    logical, intent(in) :: trial
    character(len=:), allocatable, intent(inout) :: notes
    character(len=:), allocatable :: note
    integer :: g, state
    logical :: present_
    if (.not. allocated(notes)) notes = ''
    do g = 1, size(an%states)
      if (.not. an%path%active(g) .or. .not. an%states(g)%nonlinear) cycle
      do state = state_elastic, state_tension
        if (trial) then
          present_ = any(an%states(g)%state_t == state)
        else
          present_ = any(an%states(g)%state == state)
        end if
        if (.not. present_) cycle
        call an%materials(model%groups(g)%material)%m%state_note(state, note)
        if (len(note) == 0 .or. index(notes, note) > 0) cycle
        if (len(notes) > 0) notes = notes // '; '
        notes = notes // note
      end do
    end do
  end subroutine collect_point_notes

  !> The clear stop: step, load factor, residual and the DOF where it is largest, and the last
  !! load factor in equilibrium; when interface points opened in the last try, a hint that the
  !! load may have passed a limit point.
  subroutine stop_error(model, an, r, st, k, lf, lf_equilibrium, last, rel, cutbacks_exhausted, opened, notes, &
                        error, mechanism)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    real(dp), intent(in) :: r(:)
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k
    real(dp), intent(in) :: lf, rel
    real(dp), intent(in) :: lf_equilibrium   !! the load factor of the last state accepted
    character(len=*), intent(in) :: last     !! what that state was: in equilibrium, or out of balance (carried)
    logical, intent(in) :: cutbacks_exhausted
    integer, intent(in) :: opened   !! interface points that opened in the last try
    character(len=*), intent(in) :: notes   !! materials' notes about the states the step's iterates reached
    type(error_t), allocatable, intent(out) :: error
    !> the equation where the last try's tangent is singular while the elastic stiffness is
    !! not (0: none found): a mechanism, and the stop a collapse
    integer, intent(in) :: mechanism
    integer :: imax
    character(len=:), allocatable :: why, hint
    imax = maxloc(abs(r), dim=1, mask=r == r)
    if (imax < 1) imax = 1
    if (cutbacks_exhausted) then
      why = 'the step does not converge after ' // str(st%controls%max_cutbacks) // ' cut-backs'
    else
      why = 'the residual is not finite'
    end if
    hint = ''
    if (opened > 0) then
      hint = '; ' // str(opened) // ' interface points opened in the last try, each dropping ' // &
        'its tensile strength c / tan(phi) at once: '
      if (st%controls%method == method_full_newton_raphson) then
        ! Each opening sheds its force onto its neighbours, which may open in turn: the
        ! iterations follow that cascade point by point (model B FD2 needs 75 at its unzipping).
        hint = hint // 'the opening may spread further than ' // str(st%controls%max_iterations) // &
          ' iterations can follow (STAGE ..., MAXIT=400 or feps --maxit 400), or the load passed a limit point'
      else
        hint = hint // 'the load may have passed a limit point (the thesis carries the unbalanced ' // &
          'force: STAGE ..., DIVERGENCE=1)'
      end if
    end if
    if (an%eq%symmetrized .and. st%controls%method /= method_initial_stiffness .and. cutbacks_exhausted) then
      ! Non-associated flow: outside full Newton (which factorizes the exact tangent by LU) the
      ! factorized matrix is only a symmetric stand-in for the tangent, and as psi -> 0 the
      ! iterations stall (the 2D joint with psi = 0; docs/input-format.md, CONTROLS).
      hint = hint // '; the tangent was non-symmetric (psi /= phi, or a gap closing) and only a symmetric ' // &
        'stand-in was factorized: try STAGE ..., METHOD=full-newton-raphson (exact tangent, LU) or ' // &
        'METHOD=initial-stiffness, ACCELERATION=bfgs, MAXIT=400'
    end if
    if (st%controls%method == method_newton_raphson .and. .not. an%eq%symmetrized .and. cutbacks_exhausted) then
      ! The thesis's Newton-Raphson iterates on the tangent of the step's start (elastic in the
      ! first step), so cut-backs do not help where the path bends within every step.
      hint = hint // '; newton-raphson keeps the tangent of the step''s start through its iterations: ' // &
        'try STAGE ..., METHOD=full-newton-raphson (the tangent of every iterate)'
      ! A tangent softer than the response (sliding, when it unloads) overshoots: the search
      ! scales it (the one-DOF slide unloads in one iteration a step with s = 0.2).
      if (.not. st%controls%line_search) hint = hint // ' or LINESEARCH=energy (scales corrections that overshoot)'
    end if
    if (st%controls%method == method_full_newton_raphson .and. .not. st%controls%line_search .and. &
        opened == 0 .and. cutbacks_exhausted) then
      ! Undamped Newton cycles over the kinks of a non-smooth law whatever the step size (the
      ! block pulled over a block of scripts/bench_calculix_friction.py: 10 cut-backs).
      hint = hint // '; full Newton may cycle where points switch between sticking and sliding (or ' // &
        'loading and unloading): try STAGE ..., LINESEARCH=energy'
    end if
    if (len(notes) > 0 .and. cutbacks_exhausted) hint = hint // '; ' // notes
    if (mechanism > 0) then
      call collapse_error(model, an, st, k, lf_equilibrium, last, 'the last try went to ' // str(lf) // &
                          ', relative residual ' // str(rel) // ' after ' // str(st%controls%max_cutbacks) // &
                          ' cut-backs', 'of the last try', mechanism, error)
      return
    end if
    call fatal_error(error, err_solver, model%deck_file // ': stage ' // st%name // ', step ' // str(k) // &
                     ', load factor ' // str(lf) // ': ' // why // ' (relative residual ' // str(rel) // &
                     ', largest at ' // an%eq%map%dof_name(imax) // '); ' // last // ': load factor ' // &
                     str(lf_equilibrium) // hint)
  end subroutine stop_error

  !> The stop of a collapse: no equilibrium beyond `lf_equilibrium` (the last state accepted,
  !! as `last` says; `tried`: what the step tried), the tangent stiffness (`whose`) singular at
  !! equation `ieq` while the elastic one of the same model is not.
  subroutine collapse_error(model, an, st, k, lf_equilibrium, last, tried, whose, ieq, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k, ieq
    real(dp), intent(in) :: lf_equilibrium
    character(len=*), intent(in) :: last, tried, whose
    type(error_t), allocatable, intent(inout) :: error
    call fatal_error(error, err_solver, model%deck_file // ': collapse in stage ' // st%name // ', step ' // &
                     str(k) // ': no equilibrium found beyond load factor ' // str(lf_equilibrium) // ' (' // &
                     last // '; ' // tried // '): the tangent stiffness ' // whose // ' is singular at ' // &
                     an%eq%map%dof_name(ieq) // ' while the elastic stiffness of the same model is not: the ' // &
                     'load has formed a mechanism or reached a limit point (the structure or its interfaces ' // &
                     'have no more capacity), no support is missing', item=ieq)
  end subroutine collapse_error

  !> The progress line of a step: stage, step, load factor, iterations, relative residual and
  !! refactorizations (in all, and in this step).
  function progress_line(s, k, n, lf, iters, rel, nfact, nfact_step) result(line)
    integer, intent(in) :: s, k, n, iters, nfact, nfact_step
    real(dp), intent(in) :: lf, rel
    character(len=:), allocatable :: line
    character(len=160) :: buf
    write (buf, '(a,i0,a,i0,a,i0,a,f9.5,a,i4,a,es9.2,a,i0,a,i0,a)') 'stage ', s, '  step ', k, '/', n, &
      '  load ', lf, '  iterations ', iters, '  residual ', rel, '  refactorizations ', nfact, ' (+', nfact_step, ')'
    line = trim(buf)
  end function progress_line

  !> The time a run has taken after `done` of its `total` steps, and an estimate of the time
  !! left at the mean rate so far: '  elapsed 12.3 s, about 45 s left'.
  function time_text(elapsed, done, total) result(text)
    real(dp), intent(in) :: elapsed        !! seconds since the first step began
    integer, intent(in) :: done, total
    character(len=:), allocatable :: text
    character(len=32) :: buf
    write (buf, '(f0.1)') elapsed
    buf = adjustl(buf)
    if (buf(1:1) == '.') buf = '0' // buf      ! f0.1 writes 0.3 as .3
    text = '  elapsed ' // trim(buf) // ' s'
    if (done < 1 .or. done >= total) return
    write (buf, '(i0)') nint(elapsed / done * (total - done))
    text = text // ', about ' // trim(buf) // ' s left'
  end function time_text

  !> Hand the step's results to the observer.
  subroutine report_step(model, an, observer, step, s, k, lf, iters, rel, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    class(observer_t), intent(inout) :: observer
    integer, intent(in) :: step, s, k, iters
    real(dp), intent(in) :: lf, rel
    type(error_t), allocatable, intent(out) :: error
    type(step_result_t) :: res
    integer :: g, n
    res%step = step
    res%stage = s
    res%step_in_stage = k
    res%load_factor = lf
    res%iterations = iters
    res%residual = rel
    res%tangent_sign = an%eq%tangent_sign
    res%displacement = an%path%u
    res%applied_force = an%path%f_applied
    allocate (res%reaction(3, model%nnode), res%reaction_nodal(3, model%nnode))
    res%reaction = 0.0_dp
    res%reaction_nodal = 0.0_dp
    do n = 1, model%nnode
      if (.not. any(an%eq%map%constrained(:, n))) cycle
      res%reaction(:, n) = support_reaction(an, n)
      res%reaction_nodal(:, n) = support_reaction_nodal(an, n)
    end do
    res%has_nodal_systems = an%eq%map%has_rotations()
    allocate (res%groups(size(model%groups)))
    do g = 1, size(model%groups)
      res%groups(g)%points_per_element = an%kernels(g)%npoints
      res%groups(g)%family = an%kernels(g)%family
      ! Fields not asked for are not computed (stress recovery is most of a linear step's output cost).
      if (.not. group_output_wanted(model%fields, an%kernels(g))) cycle
      if (an%states(g)%nonlinear) then
        res%groups(g)%stress = an%states(g)%sig
        res%groups(g)%strain = an%states(g)%eps
        res%groups(g)%state = an%states(g)%state
      else
        call linear_group_results(model, an, g, res%groups(g))
      end if
    end do
    call check_finite_results(model, res, error)
    if (allocated(error)) return
    call observer%write_step(res, error)
    call share_root_error(error)   ! rank 0 writes: every rank stops where it fails
  end subroutine report_step

  !> Never hand over a step with a result that left double precision (NaN or Infinity in a
  !! displacement, a reaction or a point's stress or strain): a numerical error naming the
  !! stage, the step and where, instead of a results file of NaN.
  subroutine check_finite_results(model, res, error)
    type(model_t), intent(in) :: model
    type(step_result_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    character(len=2), parameter :: dofs(3) = ['ux', 'uy', 'uz']
    character(len=:), allocatable :: where
    integer :: at(2), g
    where = ''
    if (.not. all(ieee_is_finite(res%displacement))) then
      at = findloc(ieee_is_finite(res%displacement), .false.)
      where = 'the displacement at node ' // str(at(2)) // ', ' // dofs(at(1))
    else if (.not. all(ieee_is_finite(res%reaction))) then
      at = findloc(ieee_is_finite(res%reaction), .false.)
      where = 'the reaction at node ' // str(at(2)) // ', ' // dofs(at(1))
    else if (.not. all(ieee_is_finite(res%reaction_nodal))) then
      at = findloc(ieee_is_finite(res%reaction_nodal), .false.)
      where = 'the reaction in the nodal system of node ' // str(at(2)) // ', component ' // str(at(1))
    else
      do g = 1, size(res%groups)
        associate (gr => res%groups(g))
          if (.not. allocated(gr%stress)) cycle
          if (all(ieee_is_finite(gr%stress)) .and. all(ieee_is_finite(gr%strain))) cycle
          if (.not. all(ieee_is_finite(gr%stress))) then
            at = findloc(ieee_is_finite(gr%stress), .false.)
            where = 'the stress'
          else
            at = findloc(ieee_is_finite(gr%strain), .false.)
            where = 'the strain'
          end if
          where = where // ' of group ' // model%groups(g)%name // ' at point ' // &
                  str(mod(at(2) - 1, gr%points_per_element) + 1) // ' of element ' // &
                  str((at(2) - 1) / gr%points_per_element + 1)
          exit
        end associate
      end do
    end if
    if (len(where) == 0) return
    call fatal_error(error, err_solver, model%deck_file // ': stage ' // model%stages(res%stage)%name // &
                     ', step ' // str(res%step_in_stage) // ': ' // where // ' is not finite (beyond double ' // &
                     'precision); no results are written')
  end subroutine check_finite_results

  !> Does any requested field need the point results of a group of this kernel's family? Every
  !! field of the result schema that belongs to the group's element family does (the nodal
  !! averages are made from the points).
  pure logical function group_output_wanted(fields, kernel)
    type(output_fields_t), intent(in) :: fields
    type(group_kernel_t), intent(in) :: kernel
    group_output_wanted = any(fields%on .and. result_fields%family == kernel%family)
  end function group_output_wanted

  !> Strains and stresses of a linear group from the total displacements (sigma = D eps).
  subroutine linear_group_results(model, an, g, gr)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: g
    type(group_result_t), intent(inout) :: gr
    integer :: e, np, nc
    real(dp), allocatable :: d(:, :)
    np = an%kernels(g)%npoints
    nc = an%kernels(g)%ncomp
    allocate (gr%stress(nc, np * size(model%groups(g)%connectivity, 2)), gr%strain(nc, size(gr%stress, 2)))
    allocate (gr%state(size(gr%stress, 2)), d(nc, nc))
    gr%state = 0
    call an%materials(model%groups(g)%material)%m%elastic_tangent(d)
    ! each element writes its own points: threads (OpenMP) give the same bits as one
    !$omp parallel do schedule(static)
    do e = 1, size(model%groups(g)%connectivity, 2)
      call element_results(e)
    end do
    !$omp end parallel do
  contains
    !> Strains and stresses of element e's points.
    subroutine element_results(e)
      integer, intent(in) :: e
      real(dp) :: ue(3 * an%kernels(g)%nnodes)
      integer :: q, q0
      q0 = (e - 1) * np
      ue = reshape(an%path%u(:, model%groups(g)%connectivity(:, e)), [size(ue)])
      call element_strains(an%kernels(g), model%coords(:, model%groups(g)%connectivity(:, e)), ue, &
                           gr%strain(:, q0 + 1:q0 + np))
      do q = 1, np
        gr%stress(:, q0 + q) = matmul(d, gr%strain(:, q0 + q))
      end do
    end subroutine element_results
  end subroutine linear_group_results

end module feps_step_report
