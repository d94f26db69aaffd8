!> What the `feps` command does, as library procedures the tests can call: read a deck,
!! run it, write the HDF5 results (temporary name, renamed on success; nothing left behind
!! on error) and return a summary for the program to print.
module feps_program
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use feps_kinds, only: dp, i8
  use feps_blas, only: blas_description
  use feps_error, only: error_t, fatal_error, input_error, err_input, err_input_file, err_model, err_internal, &
                        err_solver, err_memory, str
  use feps_model, only: model_t, report_t, method_names, method_euler, method_modified_euler, method_newton_raphson, &
                        method_full_newton_raphson, line_search_refusal, known_fields, path_arc_length, &
                        max_total_steps
  use feps_deck, only: read_deck
  use feps_strings, only: to_lower, shown, utf8_text_length, gib_text
  use feps_files, only: file_kind, file_kind_text, folder_of, folder_writable, file_missing, file_regular, &
                        file_directory, memory_limit_bytes
  use feps_paths, only: xdmf_file_name, restart_file_name, meshio_file_name
  use feps_restart_data, only: restart_data_t
  use feps_restart_file, only: read_restart_point
  use feps_records, only: real_from_text
  use feps_clock, only: wall_clock
  use feps_incremental_analysis, only: analysis_summary_t, run_analysis, check_analysis
  use feps_results_file, only: results_file_t
  use feps_results_observer, only: results_observer_t, line_sink
  use feps_reports, only: section_rotation, axis_tilt, section_forces
  use feps_joint_report, only: joint_geometry_t, joint_summary_t, joint_geometry, joint_summary
  use feps_observer, only: group_result_t
  use feps_version, only: feps_release
  use feps_parallel, only: parallel_rank, share_root_error
  use feps_mesh_only, only: mesh_jacobians, write_mesh_only, write_mesh
  implicit none
  private

  character(len=*), parameter, public :: feps_version = feps_release   !! re-exported for app/

  !> Options from the command line; empty strings mean "as the deck says".
  type, public :: run_options_t
    character(len=:), allocatable :: deck
    character(len=:), allocatable :: output
    character(len=:), allocatable :: solver
    character(len=:), allocatable :: method     !! overrides every stage's METHOD when not empty
    integer :: max_iterations = 0               !! overrides every stage's MAXIT when positive
    integer :: steps = 0                        !! overrides STEPS of every stage not under arc length when positive
    character(len=:), allocatable :: tolerance  !! overrides every stage's DELTA1 when not empty (a number >= 0)
    character(len=:), allocatable :: fields     !! overrides the deck's FIELDS when not empty: names, comma-separated
    logical :: quiet = .false.
    logical :: check_only = .false.             !! check the deck and the model, solve nothing, write nothing
    logical :: strict = .false.                 !! a run that ends out of balance fails (exit 1, no results)
    logical :: out_of_core = .false.            !! --out-of-core: MUMPS's factors on disk (solver mumps only)
    logical :: mixed_precision = .false.        !! --mixed-precision: CHOLMOD's solves in single precision
    character(len=:), allocatable :: restart    !! --restart FILE: continue from its restart data when not empty
    integer :: restart_step = 0                 !! --step N: the restart point (0: the last in the file)
    integer :: restart_every = 0                !! --restart-every N: overrides the deck's RESTART when positive
    integer :: stop_after_step = 0              !! --stop-after-step K (a test aid): fail after step K when positive
  end type run_options_t

  !> What the program reports after a run: the analysis's totals (the parent type, filled by
  !! the analysis itself) and what the program knows of the run.
  type, public, extends(analysis_summary_t) :: run_summary_t
    character(len=:), allocatable :: title
    character(len=:), allocatable :: output
    character(len=:), allocatable :: blas          !! the BLAS, its kernels and threads (feps_blas)
    logical :: mesh_only = .false.
    logical :: checked_only = .false.               !! --check: nothing solved, no file written
    integer :: stages = 0
    integer :: nodes = 0
    integer :: elements = 0
    real(dp) :: wall_time = 0.0_dp
    real(dp) :: bbox(3, 2) = 0.0_dp
    character(len=200), allocatable :: reports(:)   !! post-processing lines (REPORT records)
    character(len=:), allocatable :: fields         !! result fields written (FIELDS)
    character(len=32), allocatable :: group_names(:)
    integer, allocatable :: group_elements(:)
    character(len=:), allocatable :: restart_from   !! --restart: the checkpoint file continued from
    integer :: restart_step = 0                     !! and the step after which the run continued
    character(len=:), allocatable :: restart_file   !! the checkpoint file written (RESTART), if any
  end type run_summary_t

  public :: run_feps, unbalanced_text, line_sink




contains

  !> Read, check, solve and write one deck; progress lines go to `sink` when given, and the
  !! deck's warnings (a value far outside the physical range: a unit slip?) to `warn`, as soon
  !! as the deck is read.
  subroutine run_feps(options, summary, error, sink, warn)
    type(run_options_t), intent(in) :: options
    type(run_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    procedure(line_sink), optional :: sink, warn
    type(model_t), target :: model
    type(results_observer_t) :: obs
    character(len=:), allocatable :: solver, output
    real(dp) :: t0
    integer :: g
    type(restart_data_t) :: resume
    logical :: resuming

    t0 = wall_clock()
    call read_deck(options%deck, model, error)
    if (allocated(error)) return
    call check_coordinates(model, error)
    if (allocated(error)) return
    if (allocated(model%warnings) .and. present(warn)) then
      do g = 1, size(model%warnings)
        call warn(trim(model%warnings(g)))
      end do
    end if
    summary%title = model%title
    summary%blas = blas_description()
    summary%mesh_only = model%mesh_only
    summary%nodes = model%nnode
    summary%elements = model%nelem()
    summary%bbox(:, 1) = minval(model%coords, dim=2)
    summary%bbox(:, 2) = maxval(model%coords, dim=2)

    output = model%output_file
    if (given(options%output)) output = options%output
    if (len(output) == 0 .and. .not. model%mesh_only) output = default_output(options%deck)
    summary%output = output
    ! The memory the model will need, before any of it is taken (a mesh near the size limit
    ! used to die in an allocation with a backtrace, leaving a .h5.part behind).
    call check_memory(model, error)
    if (allocated(error)) return
    ! The result paths are checked before any work (a directory of that name used to be found
    ! when the run ended, and then removed); --check writes nothing and checks none.
    if (len(output) > 0 .and. .not. options%check_only) then
      call check_result_paths(output, error)
      if (allocated(error)) return
    end if

    if (model%mesh_only) then
      call mesh_jacobians(model, summary%min_jacobian, error)
      if (allocated(error)) return
      if (len(output) > 0 .and. parallel_rank() == 0) call write_mesh_only(output, model, error)
      call share_root_error(error)
      summary%wall_time = wall_clock() - t0
      return
    end if

    solver = model%solver
    if (given(options%solver)) solver = options%solver
    if (options%out_of_core) then
      if (solver /= 'mumps') then
        call fatal_error(error, err_input, '--out-of-core keeps MUMPS''s factors on disk: it needs the mumps ' // &
                         'solver (--solver mumps), not ' // solver)
        return
      end if
      solver = 'mumps-ooc'
    end if
    if (options%mixed_precision) then
      if (solver /= 'cholmod') then
        call fatal_error(error, err_input, '--mixed-precision solves with a single-precision copy of CHOLMOD''s ' // &
                         'factor: it needs the cholmod solver, not ' // solver)
        return
      end if
      solver = 'cholmod-mixed'
    end if
    if (given(options%method)) then
      call override_method(model, options%method, error)
      if (allocated(error)) return
    end if
    if (options%max_iterations > 0) call override_max_iterations(model, options%max_iterations)
    if (options%steps > 0) then
      call override_steps(model, options%steps, error)
      if (allocated(error)) return
    end if
    if (given(options%tolerance)) then
      call override_tolerance(model, options%tolerance, error)
      if (allocated(error)) return
    end if
    if (given(options%fields)) then
      call override_fields(model, options%fields, error)
      if (allocated(error)) return
    end if
    call check_reports(model, error)
    if (allocated(error)) return
    if (options%restart_every > 0) model%restart_every = options%restart_every
    resuming = given(options%restart)
    if (resuming .and. .not. options%check_only) then
      ! The restart data are read (and their step checked) before the results are started.
      call read_restart_point(options%restart, options%restart_step, resume, error)
      if (allocated(error)) return
      summary%restart_from = options%restart
      summary%restart_step = resume%step
    end if
    if (options%check_only) then
      if (present(sink)) obs%sink => sink
      call check_only(model, solver, obs, summary, error)
      summary%wall_time = wall_clock() - t0
      return
    end if
    obs%model => model
    if (present(sink)) obs%sink => sink
    ! an MPI run's ranks above 0 compute all rank 0 does and write nothing (feps_parallel)
    if (parallel_rank() > 0) call obs%h5%keep_silent()
    call obs%h5%create(output, error)
    call share_root_error(error)
    if (allocated(error)) return
    obs%writing = .true.
    if (model%restart_every > 0 .and. parallel_rank() == 0) then
      obs%restart_path = restart_file_name(output)
      summary%restart_file = obs%restart_path
    end if
    call write_mesh(obs%h5, model, error)
    call share_root_error(error)
    if (.not. allocated(error)) then
      if (resuming .and. options%stop_after_step > 0) then
        call run_analysis(model, solver, obs, summary%analysis_summary_t, error, resume=resume, &
                          stop_after=options%stop_after_step)
      else if (resuming) then
        call run_analysis(model, solver, obs, summary%analysis_summary_t, error, resume=resume)
      else if (options%stop_after_step > 0) then
        call run_analysis(model, solver, obs, summary%analysis_summary_t, error, stop_after=options%stop_after_step)
      else
        call run_analysis(model, solver, obs, summary%analysis_summary_t, error)
      end if
    end if
    if (.not. allocated(error) .and. options%strict .and. .not. summary%converged) &
      call fatal_error(error, err_solver, options%deck // ': ' // unbalanced_text(summary) // &
                       ' (--strict: a run that ends out of balance fails)')
    if (allocated(error)) then
      ! A deck refused before its first step (exit status 2: what --check finds too) leaves the
      ! results of an earlier run alone; a run that failed removes them (they would pass for its).
      call obs%h5%discard(keep_earlier=obs%steps_written == 0 .and. &
                          any(error%code == [err_input, err_input_file, err_model]))
      return
    end if
    ! no restart point written: a linear model, or fewer steps than RESTART's EVERY
    if (allocated(summary%restart_file) .and. (summary%linear .or. summary%steps < model%restart_every)) &
      deallocate (summary%restart_file)
    summary%fields = model%fields%names()
    allocate (summary%group_names(size(model%groups)), summary%group_elements(size(model%groups)))
    do g = 1, size(model%groups)
      summary%group_names(g) = model%groups(g)%name
      summary%group_elements(g) = size(model%groups(g)%connectivity, 2)
    end do
    call post_process(model, obs%last_displacement, obs%last_reaction, obs%last_groups, obs%h5, summary, error)
    call share_root_error(error)
    if (allocated(error)) then
      call obs%h5%discard()
      return
    end if
    call write_sets(obs%h5, model, error)
    call share_root_error(error)
    if (allocated(error)) then
      call obs%h5%discard()
      return
    end if
    summary%wall_time = wall_clock() - t0
    call write_summary(obs%h5, model, summary, error)
    if (.not. allocated(error)) call obs%h5%close(error)
    call share_root_error(error)
    if (allocated(error)) call obs%h5%discard()
  end subroutine run_feps

  !> What a run that ends out of balance says: the largest relative residual a stage ended
  !! with, where, and what to do.
  function unbalanced_text(summary) result(text)
    class(run_summary_t), intent(in) :: summary
    character(len=:), allocatable :: text
    text = 'the run ends out of balance: stage ' // summary%unbalanced_stage // ', step ' // &
           str(summary%unbalanced_step) // ', load factor ' // str(summary%unbalanced_load_factor) // &
           ' ended with a relative residual of ' // str(summary%unbalanced) // ' (DELTA1 = ' // &
           str(summary%unbalanced_tolerance) // &
           '), largest at ' // summary%unbalanced_at // ': its results are not in equilibrium; give the stage ' // &
           'more steps or iterations (STEPS=, MAXIT=), or METHOD=full-newton-raphson'
  end function unbalanced_text

  !> `feps --check`: every check a run makes before its first step (check_analysis), one
  !! elastic factorization per stage whose elements change, and no result file.
  subroutine check_only(model, solver, obs, summary, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: solver
    type(results_observer_t), intent(inout) :: obs     !! forwards the stage lines (writes nothing)
    type(run_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    if (associated(obs%sink)) then
      call check_analysis(model, solver, summary%analysis_summary_t, error, obs)
    else
      call check_analysis(model, solver, summary%analysis_summary_t, error)
    end if
    if (allocated(error)) return
    summary%checked_only = .true.
    summary%output = ''
    summary%stages = size(model%stages)
  end subroutine check_only

  !> Every stage solved by one method (its preset iteration limits as in the deck reader).
  subroutine override_method(model, name, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: name
    type(error_t), allocatable, intent(out) :: error
    integer :: m, s, method
    method = 0
    do m = 1, size(method_names)
      if (name == trim(method_names(m))) method = m
    end do
    if (method == 0) then
      call fatal_error(error, err_input, 'unknown method "' // name // '" (euler, modified-euler, ' // &
                       'newton-raphson, modified-newton-raphson, initial-stiffness, full-newton-raphson)')
      return
    end if
    do s = 1, size(model%stages)
      associate (c => model%stages(s)%controls)
        c%method = method
        select case (method)
        case (method_euler, method_modified_euler)
          c%max_iterations = 1
        case (method_newton_raphson, method_full_newton_raphson)
          c%max_iterations = max(c%max_iterations, 50)
        case default
          if (c%max_iterations == 1) c%max_iterations = 10
        end select
        ! a LINESEARCH=energy of the deck that the new method cannot take is bad input too
        if (len(line_search_refusal(c)) > 0) then
          call fatal_error(error, err_input, '--method ' // name // ': ' // line_search_refusal(c) // &
                           ' (LINESEARCH=energy at ' // c%line_search_file // ':' // str(c%line_search_line) // &
                           ', stage ' // model%stages(s)%name // ')')
          return
        end if
      end associate
    end do
  end subroutine override_method

  !> --fields LIST: the result fields to write, as a FIELDS record would name them (comma-
  !! separated; `all` for the schema's default fields), in place of the deck's FIELDS.
  subroutine override_fields(model, list, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: list
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: rest, name
    logical :: found
    integer :: comma
    call model%fields%clear()
    rest = list
    do while (len(rest) > 0)
      comma = index(rest, ',')
      if (comma == 0) comma = len(rest) + 1
      name = trim(adjustl(rest(:comma - 1)))
      rest = rest(min(comma + 1, len(rest) + 1):)
      call model%fields%select(to_lower(name), found)
      if (.not. found) then
        call fatal_error(error, err_input, '--fields: unknown field "' // name // '" (' // known_fields() // ')')
        return
      end if
    end do
  end subroutine override_fields

  !> Every stage's iteration limit per step (MAXIT), after any --method override. The Euler
  !! methods keep their single iteration: that is what they are.
  subroutine override_max_iterations(model, max_iterations)
    type(model_t), intent(inout) :: model
    integer, intent(in) :: max_iterations
    integer :: s
    do s = 1, size(model%stages)
      associate (c => model%stages(s)%controls)
        if (c%method == method_euler .or. c%method == method_modified_euler) cycle
        c%max_iterations = max_iterations
        c%max_iterations_set = .true.
      end associate
    end do
  end subroutine override_max_iterations

  !> Whether a string option was given (set and not empty: empty means "as the deck says").
  pure logical function given(option)
    character(len=:), allocatable, intent(in) :: option
    given = .false.
    if (allocated(option)) given = len(option) > 0
  end function given

  !> --steps N: every stage under load or displacement control takes N equal steps in place of
  !! its STEPS (the speed-accuracy trade without editing the deck, docs/tradeoff.md). An
  !! arc-length stage keeps its STEPS: there they count arcs of length ARC, which would cut the
  !! path short. All stages' steps together stay within max_total_steps.
  subroutine override_steps(model, steps, error)
    type(model_t), intent(inout) :: model
    integer, intent(in) :: steps
    type(error_t), allocatable, intent(out) :: error
    integer :: s, total
    total = 0
    do s = 1, size(model%stages)
      if (model%stages(s)%path /= path_arc_length) model%stages(s)%steps = steps
      if (model%stages(s)%steps > max_total_steps - total) then
        call fatal_error(error, err_input, '--steps ' // str(steps) // ': the stages would take more than ' // &
                         str(max_total_steps) // ' steps together')
        return
      end if
      total = total + model%stages(s)%steps
    end do
  end subroutine override_steps

  !> --tolerance X: every stage's DELTA1 (the relative residual a step must reach), a number
  !! from 0 up as the deck's DELTA1 takes it.
  subroutine override_tolerance(model, text, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: text
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: value
    logical :: ok
    integer :: s
    call real_from_text(text, value, ok)
    if (.not. ok .or. value < 0.0_dp) then
      call fatal_error(error, err_input, '--tolerance takes a number from 0 up (every stage''s DELTA1), not "' // &
                       shown(text) // '"')
      return
    end if
    do s = 1, size(model%stages)
      model%stages(s)%controls%delta1 = value
    end do
  end subroutine override_tolerance

  !> Nodes beyond double precision (a DATAIN increment or a coordinate system that overflows or
  !! gives no direction) are bad input: name the first, before anything is computed or
  !! written, so that a run and --check stop alike (the results writer would refuse the mesh).
  subroutine check_coordinates(model, error)
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    character(len=1), parameter :: axes(3) = ['x', 'y', 'z']
    integer :: at(2)
    if (all(ieee_is_finite(model%coords))) return
    at = findloc(ieee_is_finite(model%coords), .false.)
    call fatal_error(error, err_input, model%deck_file // ': node ' // str(at(2)) // ': its coordinate ' // &
                     axes(at(1)) // ' is not finite (' // str(model%coords(at(1), at(2))) // '): the DATAIN ' // &
                     'block or NODE record that gives it, or its coordinate system, is beyond double precision')
  end subroutine check_coordinates

  !> The sections and rings of the REPORT records depend on the mesh only: find their errors
  !! before the first step, in a run and in --check alike (not after the whole analysis, whose
  !! results would be lost), by evaluating each report on zero displacements, with the very
  !! procedures post_process uses.
  subroutine check_reports(model, error)
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: u(:, :)
    type(group_result_t) :: no_stress(0)
    type(joint_geometry_t) :: joint
    real(dp) :: angle, force(3), moment(3)
    integer :: k, count
    allocate (u(3, model%nnode))
    u = 0.0_dp
    do k = 1, size(model%reports)
      if (model%reports(k)%kind == 'reaction') cycle      ! its node set was checked when read
      if (model%reports(k)%kind == 'joint') then
        call joint_geometry(model, model%reports(k), joint, error)
      else if (model%reports(k)%kind == 'section') then
        call section_forces(model, model%reports(k), no_stress, force, moment, count, error)
      else if (model%reports(k)%kind == 'tilt') then
        call axis_tilt(model, model%reports(k), u, angle, error)
      else
        call section_rotation(model, model%reports(k), u, angle, error)
      end if
      if (allocated(error)) return
    end do
  end subroutine check_reports

  !> REPORT records: rotations of pipe sections (thesis 7.3) from the final displacements,
  !! resultants of the final support reactions on node sets, forces through sections from the
  !! final stresses.
  subroutine post_process(model, u, reaction, groups, h5, summary, error)
    type(model_t), intent(in) :: model
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(in) :: reaction(:, :)     !! (3, nnode) global Cartesian, the last step's
    type(group_result_t), intent(in) :: groups(:)  !! the last step's point results
    type(results_file_t), intent(inout) :: h5
    type(run_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    integer :: k
    real(dp) :: angle
    character(len=200) :: line
    character(len=200), allocatable :: block(:)
    allocate (summary%reports(0))
    do k = 1, size(model%reports)
      associate (r => model%reports(k))
        if (r%kind == 'reaction') then
          call reaction_resultant(model, r, reaction, line, h5, error)
          if (allocated(error)) return
          summary%reports = [character(len=200) :: summary%reports, line]
          cycle
        end if
        if (r%kind == 'section') then
          call section_report(model, r, groups, line, h5, error)
          if (allocated(error)) return
          summary%reports = [character(len=200) :: summary%reports, line]
          cycle
        end if
        if (r%kind == 'joint') then
          call joint_report(model, r, u, groups, block, h5, error)
          if (allocated(error)) return
          summary%reports = [character(len=200) :: summary%reports, block]
          cycle
        end if
        if (r%kind == 'tilt') then
          call axis_tilt(model, r, u, angle, error)
          if (allocated(error)) return
          write (line, '(a,f0.1,a,f0.1,a,f10.6,a)') 'tilt ' // r%name // ' (axis from z = ', r%x_from, ' to z = ', &
            r%x_to, '): ', angle, ' deg'
        else
          call section_rotation(model, r, u, angle, error)
          if (allocated(error)) return
          write (line, '(a,f0.1,a,f0.1,a,f10.6,a)') 'rotation ' // r%name // ' (section z = ', r%z, ', r = ', &
            r%r, '): ', angle, ' deg'
        end if
        if (r%has_reference) write (line, '(a,a,f10.6,a,f0.1,a)') trim(line), '; thesis ', r%reference, &
          ' deg (', 100.0_dp * (angle - r%reference) / r%reference, '%)'
        summary%reports = [character(len=200) :: summary%reports, line]
        call h5%write_summary_real('rotation_' // r%name // '_deg', angle, error)
        if (allocated(error)) return
      end associate
    end do
  end subroutine post_process

  !> REPORT, SECTION: the forces and moments through the section (feps_reports' section_forces),
  !! printed as one line and written to /summary as section_<name>_N, _Vx, _Vy (N) and _Mx,
  !! _My, _T (N mm).
  subroutine section_report(model, r, groups, line, h5, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    type(group_result_t), intent(in) :: groups(:)
    character(len=200), intent(out) :: line
    type(results_file_t), intent(inout) :: h5
    type(error_t), allocatable, intent(out) :: error
    character(len=2), parameter :: names(6) = ['N ', 'Vx', 'Vy', 'Mx', 'My', 'T ']
    real(dp) :: force(3), moment(3), values(6)
    integer :: count, d
    call section_forces(model, r, groups, force, moment, count, error)
    if (allocated(error)) return
    values = [force(3), force(1), force(2), moment]
    write (line, '(a,f0.1,a,i0,3(a,es13.5),a,3(a,es13.5),a)') 'section ' // r%name // ' (z = ', r%z, ', ', &
      count, ' elements): N', values(1), ', Vx', values(2), ', Vy', values(3), ' N;', ' Mx', values(4), &
      ', My', values(5), ', T', values(6), ' N mm'
    do d = 1, 6
      call h5%write_summary_real('section_' // r%name // '_' // trim(names(d)), values(d), error)
      if (allocated(error)) return
    end do
  end subroutine section_report

  !> REPORT, JOINT: the design summary of a pipe joint (feps_joint_report's joint_summary),
  !! printed as a block of lines and written to /summary as joint_<name>_<quantity>
  !! (docs/output-format.md).
  subroutine joint_report(model, r, u, groups, block, h5, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    real(dp), intent(in) :: u(:, :)
    type(group_result_t), intent(in) :: groups(:)
    character(len=200), allocatable, intent(out) :: block(:)
    type(results_file_t), intent(inout) :: h5
    type(error_t), allocatable, intent(out) :: error
    type(joint_summary_t) :: js
    character(len=200) :: line
    character(len=:), allocatable :: pipes
    integer :: k
    call joint_summary(model, r, u, groups, js, error)
    if (allocated(error)) return
    pipes = model%groups(r%pipe_groups(1))%name
    do k = 2, size(r%pipe_groups)
      pipes = pipes // ', ' // model%groups(r%pipe_groups(k))%name
    end do
    associate (geo => js%geometry)
      allocate (block(0))
      write (line, '(a,f0.1,a,f0.1,a)') 'joint ' // r%name // ' (interface ' // model%groups(r%interface_group)%name // &
        ', pipes ' // pipes // '; R = ', geo%outer_radius, ', r = ', geo%inner_radius, ' mm):'
      call add(line)
      if (js%hoop_group /= 0) then
        write (line, '(a,es12.4,a,3(a,f0.1),a)') '  hoop tension max      ', js%hoop_max, ' MPa', ' at r = ', &
          js%hoop_at(1), ', theta = ', js%hoop_at(2), ', z = ', js%hoop_at(3), ' (' // &
          model%groups(js%hoop_group)%name // ', points within ' // str(js%reach) // ' mm of the joint)'
        call add(line)
        write (line, '(a,es12.4,a,3(a,f0.1),a)') '  axial stress min      ', js%axial_min, ' MPa', ' at r = ', &
          js%axial_at(1), ', theta = ', js%axial_at(2), ', z = ', js%axial_at(3), ' (' // &
          model%groups(js%axial_group)%name // ')'
        call add(line)
      end if
      write (line, '(a,es12.4,a,2(a,f0.1))') '  joint compression max ', js%sigma_max, ' MPa', ' at r = ', &
        js%sigma_max_at(1), ', theta = ', js%sigma_max_at(2)
      call add(line)
      if (abs(js%contact_width) < 1.0e7_dp) then
        write (line, '(a,f12.1,a,i0,a)') '  contact width Z       ', js%contact_width, ' mm (mean over ', geo%rings, &
          ' rings of points)'
      else
        ! no gap and sigma_n nearly uniform: the fitted lines' zeros lie far away
        write (line, '(a,es12.4,a,i0,a)') '  contact width Z       ', js%contact_width, ' mm (mean over ', geo%rings, &
          ' rings of points: no gap, nearly uniform compression)'
      end if
      call add(line)
      write (line, '(a,es12.4,a,2(a,f0.1))') '  joint opening max     ', js%opening, ' mm', ' at r = ', &
        js%opening_at(1), ', theta = ', js%opening_at(2)
      call add(line)
      if (js%has_deflection) then
        write (line, '(a,es12.4,a,2(f0.1,a))') '  deflection angle      ', js%deflection, ' deg (end faces z = ', &
          js%face_z(1), ' and ', js%face_z(2), ')'
        call add(line)
      end if
      if (r%has_p) then
        write (line, '(a,es12.4,a)') '  joint load P          ', js%load, ' N (P=)'
      else
        write (line, '(a,es12.4,a,i0,a)') '  joint load P          ', js%load, ' N (', geo%copies, &
          ' x the interface''s normal force)'
      end if
      call add(line)
      if (js%has_models) then
        write (line, '(a,f0.2,a,f0.1,a,f0.1,a,f0.1,a)') '  models at this P and Z (a = ', geo%packing_thickness, &
          ', L = ', geo%pipe_length, ' mm, E_c = ', geo%concrete_modulus, ', E_p = ', geo%packing_modulus, ' MPa):'
        call add(line)
        write (line, '(a,es12.4,a,es12.4,a)') '  australian sigma_max  ', js%australian%sigma_max, ' MPa, beta ', &
          js%australian%beta, ' deg'
        call add(line)
        write (line, '(a,es12.4,a,es12.4,a)') '  haslem     sigma_max  ', js%haslem%sigma_max, ' MPa, beta ', &
          js%haslem%beta, ' deg'
        call add(line)
      else
        call add('  models not evaluated: ' // js%models_note)
      end if
    end associate
    call write_joint_values(h5, 'joint_' // r%name // '_', js, error)
  contains
    subroutine add(text)
      character(len=*), intent(in) :: text
      block = [character(len=200) :: block, text]
    end subroutine add

  end subroutine joint_report

  !> The /summary attributes of REPORT, JOINT, each named `prefix` // quantity.
  subroutine write_joint_values(h5, prefix, js, error)
    type(results_file_t), intent(inout) :: h5
    character(len=*), intent(in) :: prefix
    type(joint_summary_t), intent(in) :: js
    type(error_t), allocatable, intent(out) :: error
    associate (geo => js%geometry)
      if (js%hoop_group /= 0) then
        call put('hoop_max', js%hoop_max)
        call put_at('hoop', js%hoop_at)
        call put('axial_min', js%axial_min)
        call put_at('axial', js%axial_at)
      end if
      call put('sigma_max', js%sigma_max)
      call put_at('sigma_max', js%sigma_max_at(1:2))
      call put('contact_width', js%contact_width)
      call put('opening', js%opening)
      call put_at('opening', js%opening_at(1:2))
      if (js%has_deflection) call put('deflection_deg', js%deflection)
      call put('load', js%load)
      call put('outer_radius', geo%outer_radius)
      call put('inner_radius', geo%inner_radius)
      if (js%has_models) then
        call put('packing_thickness', geo%packing_thickness)
        call put('pipe_length', geo%pipe_length)
        call put('concrete_modulus', geo%concrete_modulus)
        call put('packing_modulus', geo%packing_modulus)
        call put('australian_sigma_max', js%australian%sigma_max)
        call put('australian_beta_deg', js%australian%beta)
        call put('haslem_sigma_max', js%haslem%sigma_max)
        call put('haslem_beta_deg', js%haslem%beta)
      end if
    end associate
  contains
    subroutine put(name, value)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: value
      if (allocated(error)) return
      call h5%write_summary_real(prefix // name, value, error)
    end subroutine put

    subroutine put_at(name, at)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: at(:)
      character(len=5), parameter :: coordinate(3) = ['r    ', 'theta', 'z    ']
      integer :: d
      do d = 1, size(at)
        call put(name // '_' // trim(coordinate(d)), at(d))
      end do
    end subroutine put_at
  end subroutine write_joint_values

  !> REPORT, REACTION: the sum of the support reactions (global x, y, z) over the nodes of the
  !! report's node set, printed as one line and written to /summary as reaction_<name>_fx, _fy
  !! and _fz (N). A node without a support in a direction contributes zero there.
  subroutine reaction_resultant(model, r, reaction, line, h5, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    real(dp), intent(in) :: reaction(:, :)
    character(len=200), intent(out) :: line
    type(results_file_t), intent(inout) :: h5
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: f(3)
    integer :: d
    character(len=2), parameter :: axes(3) = ['fx', 'fy', 'fz']
    associate (nodes => model%node_sets(r%node_set)%nodes)
      do d = 1, 3
        f(d) = sum(reaction(d, nodes))
      end do
      write (line, '(a,i0,a,3(a,es14.6),a)') 'reaction ' // r%name // ' (set ' // &
        model%node_sets(r%node_set)%name // ', ', size(nodes), trim(merge(' node): ', ' nodes):', size(nodes) == 1)), &
        ' fx', f(1), ', fy', f(2), ', fz', f(3), ' N'
    end associate
    do d = 1, 3
      call h5%write_summary_real('reaction_' // r%name // '_' // axes(d), f(d), error)
      if (allocated(error)) return
    end do
  end subroutine reaction_resultant






  !> The deck's selections as the run resolved them, `/sets/nodes/<name>` and
  !! `/sets/faces/<name>` (the nodes and faces that supports, loads and REPORTs act on), and its
  !! support records, `/constraints/<kkkk>`, so that a script or an exporter needs no second
  !! reading of the deck.
  subroutine write_sets(h5, model, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: members(:, :)
    integer :: k
    do k = 1, size(model%node_sets)
      if (model%node_sets(k)%listed) cycle
      associate (set => model%node_sets(k))
        members = reshape(set%nodes, [1, size(set%nodes)])
        call h5%write_set('nodes', set%name, members, error)
      end associate
      if (allocated(error)) return
    end do
    do k = 1, size(model%face_sets)
      associate (set => model%face_sets(k))
        if (.not. allocated(set%element)) cycle
        if (allocated(members)) deallocate (members)
        allocate (members(2, size(set%face)))
        members(1, :) = set%element
        members(2, :) = set%face
        call h5%write_set('faces', set%name, members, error, group=model%groups(set%group)%name)
      end associate
      if (allocated(error)) return
    end do
    if (.not. allocated(model%constraints)) return
    do k = 1, size(model%constraints)
      associate (c => model%constraints(k), set => model%node_sets(model%constraints(k)%node_set))
        if (set%listed) then
          call h5%write_constraint(k, c, '', error, node=set%nodes(1))
        else
          call h5%write_constraint(k, c, set%name, error)
        end if
      end associate
      if (allocated(error)) return
    end do
  end subroutine write_sets

  subroutine write_summary(h5, model, summary, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    type(run_summary_t), intent(in) :: summary
    type(error_t), allocatable, intent(out) :: error
    integer :: g
    call h5%write_summary_string('program', 'feps ' // feps_version, error)
    if (.not. allocated(error)) call h5%write_summary_string('input_file', model%deck_file, error)
    if (.not. allocated(error)) call h5%write_summary_string('solver', summary%solver, error)
    if (.not. allocated(error)) call h5%write_summary_string('blas', summary%blas, error)
    if (.not. allocated(error) .and. summary%solver == 'cholmod-mixed') then
      call h5%write_summary_int('single_precision_factors', int(summary%single_precision_factors, i8), error)
      if (.not. allocated(error)) call h5%write_summary_real('test_solve_error', summary%test_solve_error, error)
      if (.not. allocated(error)) call h5%write_summary_int('precision_fallbacks', &
                                                            int(summary%precision_fallbacks, i8), error)
    end if
    if (.not. allocated(error)) call h5%write_summary_real('wall_time', summary%wall_time, error)
    if (.not. allocated(error)) call h5%write_summary_int('dofs', int(summary%dofs, i8), error)
    if (.not. allocated(error)) call h5%write_summary_int('factor_nonzeros', summary%factor_nnz, error)
    if (.not. allocated(error)) call h5%write_summary_real('factor_flops', summary%flops, error)
    if (.not. allocated(error) .and. allocated(summary%rank_memory_mb)) then
      call h5%write_summary_int('ranks', size(summary%rank_memory_mb, kind=i8), error)
      if (.not. allocated(error)) call h5%write_summary_reals('rank_memory_mb', summary%rank_memory_mb, error)
      if (.not. allocated(error)) call h5%write_summary_reals('rank_factorization_time', &
                                                              summary%rank_factor_seconds, error)
    end if
    if (.not. allocated(error) .and. allocated(summary%rank_elements)) then
      call h5%write_summary_reals('rank_elements', summary%rank_elements, error)
      if (.not. allocated(error)) call h5%write_summary_reals('rank_element_time', summary%rank_element_seconds, error)
      if (.not. allocated(error)) call h5%write_summary_reals('rank_peak_memory_mb', summary%rank_peak_memory_mb, error)
    end if
    if (.not. allocated(error)) call h5%write_summary_int('matrix_nonzeros', summary%matrix_nnz, error)
    if (.not. allocated(error)) call h5%write_summary_real('time_assembly', summary%time_assembly, error)
    if (.not. allocated(error)) call h5%write_summary_real('time_factorization', summary%time_factorization, error)
    if (.not. allocated(error)) call h5%write_summary_real('time_solve', summary%time_solve, error)
    if (.not. allocated(error)) call h5%write_summary_real('max_displacement', summary%max_displacement, error)
    if (.not. allocated(error) .and. summary%min_pivot_ratio > 0.0_dp) call h5%write_summary_real( &
      'condition_estimate', summary%max_pivot_ratio / summary%min_pivot_ratio, error)
    if (allocated(summary%restart_from) .and. .not. allocated(error)) then
      call h5%write_summary_string('restart_from', summary%restart_from, error)
      if (.not. allocated(error)) call h5%write_summary_int('restart_step', int(summary%restart_step, i8), error)
    end if
    if (.not. allocated(error)) call h5%write_summary_int('steps', int(summary%steps, i8), error)
    if (.not. allocated(error)) call h5%write_summary_int('iterations', int(summary%iterations, i8), error)
    if (.not. allocated(error)) call h5%write_summary_int('factorizations', int(summary%factorizations, i8), error)
    if (.not. allocated(error)) call h5%write_summary_int('lu_factorizations', int(summary%lu_factorizations, i8), error)
    if (.not. allocated(error) .and. summary%lu_factorizations > 0) &
      call h5%write_summary_real('lu_min_rcond', summary%lu_min_rcond, error)
    if (.not. allocated(error)) call h5%write_summary_int('cutbacks', int(summary%cutbacks, i8), error)
    if (.not. allocated(error)) call h5%write_summary_int('unconverged_steps', int(summary%unconverged_steps, i8), &
                                                          error)
    if (.not. allocated(error)) call h5%write_summary_int('converged', merge(1_i8, 0_i8, summary%converged), error)
    if (.not. allocated(error)) call h5%write_summary_real('unbalanced', summary%unbalanced, error)
    if (.not. allocated(error) .and. summary%line_search) call h5%write_summary_int('line_searches', &
      int(summary%line_searches, i8), error)
    if (.not. allocated(error) .and. summary%line_search) call h5%write_summary_int('line_search_evaluations', &
      int(summary%line_search_evaluations, i8), error)
    ! trim: merge pads 'linear' to the length of 'nonlinear'
    if (.not. allocated(error)) call h5%write_summary_string('analysis', trim(merge('linear   ', 'nonlinear', &
                                                                                      summary%linear)), error)
    if (.not. allocated(error)) call h5%write_summary_string('fields', summary%fields, error)
    if (.not. allocated(error)) call h5%write_summary_int('point_state_bytes', sum(summary%state_bytes), error)
    if (.not. allocated(error)) call write_parameters(h5, model, error)
    if (.not. allocated(error)) call write_materials(h5, model, error)
    do g = 1, size(summary%state_bytes)
      if (allocated(error)) return
      call h5%write_group_int(model%groups(g)%name, 'point_state_bytes', summary%state_bytes(g), error)
      if (.not. allocated(error)) call h5%write_group_int(model%groups(g)%name, 'point_state_bytes_per_element', &
        summary%state_bytes(g) / max(1_i8, int(summary%group_elements(g), i8)), error)
      if (.not. allocated(error) .and. model%is_prestressed(g)) &
        call h5%write_group_real(model%groups(g)%name, 'prestress', total_prestress(model, g), error)
    end do
  end subroutine write_summary

  !> The axial force the PRESTRESS records add to group g's bars over all stages (bonded
  !! before or after).
  pure real(dp) function total_prestress(model, g)
    type(model_t), intent(in) :: model
    integer, intent(in) :: g
    integer :: s
    real(dp) :: f(size(model%groups))
    total_prestress = 0.0_dp
    do s = 1, size(model%stages)
      f = model%stage_prestress(s) + model%stage_prestress(s, after=.true.)
      total_prestress = total_prestress + f(g)
    end do
  end function total_prestress

  !> Each MATERIAL record as /materials/<name>: its kind and its parameters as given.
  subroutine write_materials(h5, model, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: m
    character(len=1), parameter :: no_texts(0) = [character(len=1) ::]
    if (.not. allocated(model%materials)) return
    do m = 1, size(model%materials)
      associate (spec => model%materials(m))
        if (allocated(spec%texts)) then
          call h5%write_material(spec%name, spec%kind, spec%keys, spec%values, spec%texts, error)
        else
          call h5%write_material(spec%name, spec%kind, spec%keys, spec%values, no_texts, error)
        end if
      end associate
      if (allocated(error)) return
    end do
  end subroutine write_materials

  !> PARAMETERS records as /summary attributes parameter_<name>: a number as a real, anything
  !! else as a string.
  subroutine write_parameters(h5, model, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: v
    integer :: i
    logical :: number
    if (.not. allocated(model%parameter_names)) return
    do i = 1, size(model%parameter_names)
      call real_from_text(model%parameter_values(i), v, number)
      if (number) then
        call h5%write_summary_real('parameter_' // trim(model%parameter_names(i)), v, error)
      else
        call h5%write_summary_string('parameter_' // trim(model%parameter_names(i)), &
                                     trim(model%parameter_values(i)), error)
      end if
      if (allocated(error)) return
    end do
  end subroutine write_parameters

  !> A failed run (err_memory, exit status 1) when the memory the model will take is beyond what
  !! this process may use (memory_limit_bytes: its address-space limit, ulimit -v, or the
  !! machine's memory). The estimate counts only arrays every run allocates, so it is a lower
  !! bound: for a mesh, its coordinates (three copies: the reader's, the model's and the
  !! results'), its connectivity and its integration points' positions; for an analysis also ten
  !! vectors of the DOFs, two stress states per integration point and the lower triangle of the
  !! stiffness matrix, at least (9 k + 3) / 2 entries of 12 bytes per node for the smallest
  !! element of k nodes (each of a node's 3 rows couples the 3 DOFs of every node of an element
  !! that holds it). The factor comes on top (feps --check reports its size).
  subroutine check_memory(model, error)
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: need, limit, points
    integer :: g, kmin
    limit = memory_limit_bytes()
    if (limit <= 0) return
    points = 0
    kmin = huge(1)
    need = 3_i8 * 24_i8 * model%nnode
    do g = 1, size(model%groups)
      associate (gr => model%groups(g))
        kmin = min(kmin, size(gr%connectivity, 1))
        need = need + 4_i8 * size(gr%connectivity, kind=i8)
        points = points + int(max(gr%element%npoints, 0), i8) * size(gr%connectivity, 2, kind=i8)
      end associate
    end do
    need = need + 24_i8 * points
    if (.not. model%mesh_only .and. size(model%groups) > 0) need = need + 10_i8 * 24_i8 * model%nnode + &
      2_i8 * 48_i8 * points + 12_i8 * ((9_i8 * kmin + 3_i8) * model%nnode / 2_i8)
    if (need <= limit) return
    call fatal_error(error, err_memory, model%deck_file // ': the model (' // str(model%nnode) // ' nodes, ' // &
                     str(model%nelem()) // ' elements) needs about ' // gib_text(need) // ' GiB at least, ' // &
                     'more than the ' // gib_text(limit) // ' GiB this process may use (its address-space ' // &
                     'limit, ulimit -v, or the machine''s memory)')
  end subroutine check_memory

  !> Bad input (exit status 2) when the results file `path` cannot be written where it is to
  !! go: its folder missing or not writable, or the results file, the XDMF file beside it or the
  !! temporary names of either (`.part`) an existing directory, FIFO or device: feps replaces
  !! regular files of these names only, and never removes anything else. The file's name is
  !! written into the XDMF (XML) file, so it must be printable UTF-8.
  subroutine check_result_paths(path, error)
    character(len=*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: folder, name, names(:), what
    integer :: kind, i
    folder = folder_of(path)
    name = path(len(folder) + 1:)
    if (len(name) > 0) then
      if (name(1:1) == '/') name = name(2:)
    end if
    if (len(name) == 0) then
      call fatal_error(error, err_input, 'results file "' // shown(path) // '": no file name (it ends in /)')
      return
    end if
    if (len(folder) > 0) then
      kind = file_kind(folder)
      if (kind == file_missing) then
        call fatal_error(error, err_input, 'results file "' // shown(path) // '": cannot create it: no folder "' // &
                         shown(folder) // '"')
        return
      else if (kind /= file_directory) then
        call fatal_error(error, err_input, 'results file "' // shown(path) // '": cannot create it: "' // &
                         shown(folder) // '" is not a folder')
        return
      end if
    end if
    if (.not. folder_writable(folder)) then
      what = '.'
      if (len(folder) > 0) what = shown(folder)
      call fatal_error(error, err_input, 'results file "' // shown(path) // '": cannot create it: the folder "' // &
                       what // '" is not writable')
      return
    end if
    names = [character(len=len(path) + 20) :: path, path // '.part', xdmf_file_name(path), &
                                                 xdmf_file_name(path) // '.part', meshio_file_name(path), &
                                                 meshio_file_name(path) // '.part']
    do i = 1, size(names)
      kind = file_kind(trim(names(i)))
      if (kind /= file_missing .and. kind /= file_regular) then
        what = file_kind_text(kind) // ': feps writes a file of that name and removes nothing it did not create'
        if (i > 1) what = '"' // shown(trim(names(i))) // '": ' // what
        call fatal_error(error, err_input, 'results file "' // shown(path) // '": ' // what)
        return
      end if
    end do
    if (utf8_text_length(name) < len(name)) then
      call fatal_error(error, err_input, 'results file "' // shown(path) // '": its name has a byte that is ' // &
                       'no printable text (a control character, or not UTF-8), and the XDMF (XML) file names it')
    end if
  end subroutine check_result_paths

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

end module feps_program
