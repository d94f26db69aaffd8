!> The `feps` command: parse arguments, run the library, print a summary, choose the exit code.
program feps_main
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use, intrinsic :: iso_c_binding, only: c_int
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, err_input, err_input_file, err_model, str
  use feps_program, only: run_options_t, run_summary_t, run_feps, feps_version, unbalanced_text
  use feps_strings, only: sci
  use feps_paths, only: is_xdmf_name
  use feps_model, only: max_iterations_limit, max_total_steps
  use feps_files, only: report_file_size_limit
  use feps_mumps_solver, only: mpi_built, mpi_start, mpi_stop
  use feps_cholmod_solver, only: mixed_tolerance
  use feps_parallel, only: silence_output
  use feps_blas, only: blas_description, choose_blas_kernels, factorization_threads, set_blas_threads
  use feps_joint_command, only: joint_request_t, set_joint_option, run_joint_command, joint_usage
  use feps_element_table, only: element_table_lines
  use omp_lib, only: omp_set_num_threads, omp_get_num_procs, omp_get_max_threads
  use feps_cores, only: idle_cores
  implicit none

  interface
    subroutine c_exit(status) bind(C, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

  type(run_options_t) :: options
  type(run_summary_t) :: summary
  type(error_t), allocatable :: error
  integer :: status
  integer :: threads = 0           !! --threads N: element-loop threads (0: not given)
  integer :: rank, ranks           !! this process's MPI rank and the number of ranks (0 and 1 without MPI)

  call choose_blas_kernels()
  call set_threads(probe=.false.)
  ! MPI build: every rank runs the same analysis, each on its own elements (feps_parallel);
  ! the ranks above 0 print nothing and write no file, and all of them end with one status
  call mpi_start(rank, ranks)
  call silence_output()
  call report_file_size_limit()
  if (command_argument_count() >= 1) then
    if (argument(1) == 'joint') call leave(joint_command())
    if (argument(1) == 'elements') call leave(elements_command())
  end if
  call parse_arguments(options, status)
  if (status >= 0) call leave(status)
  call set_threads(probe=.true.)

  if (options%quiet) then
    call run_feps(options, summary, error)
  else
    call run_feps(options, summary, error, print_line, print_warning)
  end if
  if (allocated(error)) then
    write (error_unit, '(a)') 'feps: error: ' // error%message
    ! 2: what the user fixes in the input (the deck, an included file, a file that cannot be
    ! read, a model that cannot be solved as given); 1: a run that failed (no convergence,
    ! results beyond double precision) or results that cannot be written.
    select case (error%code)
    case (err_input, err_input_file, err_model)
      call leave(2)
    case default
      call leave(1)
    end select
  end if
  if (.not. options%quiet) call print_summary(summary)
  call mpi_stop(0)

contains

  !> End the program with exit status `status` (every MPI rank ends with the same).
  subroutine leave(status)
    integer, intent(in) :: status
    call mpi_stop(status)
    call c_exit(int(status, c_int))
  end subroutine leave

  subroutine print_warning(line)
    character(len=*), intent(in) :: line
    write (error_unit, '(a)') 'feps: warning: ' // line
    flush (error_unit)
  end subroutine print_warning

  subroutine print_line(line)
    character(len=*), intent(in) :: line
    write (output_unit, '(a)') line
    flush (output_unit)
  end subroutine print_line

  !> `feps elements` (feps_element_table): the element catalog as JSON; returns the exit status.
  integer function elements_command() result(status)
    type(error_t), allocatable :: error
    status = 2
    if (command_argument_count() > 1) then
      write (error_unit, '(a)') 'feps: error: elements takes no argument (given: "' // argument(2) // '")'
      return
    end if
    call element_table_lines(print_line, error)
    if (allocated(error)) then
      write (error_unit, '(a)') 'feps: error: ' // error%message
      status = 1
      return
    end if
    status = 0
  end function elements_command

  !> `feps joint ...` (feps_joint_command): the analytical joint models; returns the exit status.
  integer function joint_command() result(status)
    type(joint_request_t) :: request
    type(error_t), allocatable :: error
    character(len=:), allocatable :: name
    integer :: i
    status = 2
    i = 1
    do while (i < command_argument_count())
      i = i + 1
      name = argument(i)
      if (name == '--json') then
        call set_joint_option(request, name, '', error)
      else if (name == '-h' .or. name == '--help') then
        write (output_unit, '(a)') joint_usage
        status = 0
        return
      else if (i == command_argument_count() .or. len(name) < 3 .or. name(1:min(2, len(name))) /= '--') then
        write (error_unit, '(a)') 'feps: error: joint: "' // name // '" is not an option with a value (' // &
          joint_usage // ')'
        return
      else
        i = i + 1
        call set_joint_option(request, name, argument(i), error)
      end if
      if (allocated(error)) exit
    end do
    if (.not. allocated(error)) call run_joint_command(request, print_line, error)
    if (allocated(error)) then
      write (error_unit, '(a)') 'feps: error: ' // error%message
      return
    end if
    status = 0
  end function joint_command

  !> Fill options; status = -1 to go on, or the exit status to stop with. Each option is given
  !! at most once and takes no empty value: a second one, or '', would be silently ignored or
  !! override the first (exit 2, as for a bad value).
  subroutine parse_arguments(options, status)
    type(run_options_t), intent(out) :: options
    integer, intent(out) :: status
    integer :: i, n
    character(len=:), allocatable :: arg, name, value, seen
    status = -1
    options%output = ''
    options%solver = ''
    options%method = ''
    options%fields = ''
    options%restart = ''
    options%tolerance = ''
    seen = ' '
    n = command_argument_count()
    i = 0
    do while (i < n)
      i = i + 1
      arg = argument(i)
      select case (arg)
      case ('-h', '--help')
        call print_help()
        status = 0
        return
      case ('-V', '--version')
        write (output_unit, '(a)') 'feps ' // feps_version, 'blas ' // blas_description()
        status = 0
        return
      case ('-q', '--quiet', '--check', '--strict', '--out-of-core', '--mixed-precision', '-o', '--output', &
            '--solver', '--method', '--maxit', '--steps', '--tolerance', '--fields', &
            '--restart', '--step', '--restart-every', '--stop-after-step', '--threads')
        name = arg
        if (arg == '-q') name = '--quiet'
        if (arg == '-o') name = '--output'
        if (index(seen, ' ' // name // ' ') > 0) then
          write (error_unit, '(a)') 'feps: error: ' // name // ' is given twice (each option at most once; ' // &
            'see feps --help)'
          status = 2
          return
        end if
        seen = seen // name // ' '
        if (name == '--quiet') then
          options%quiet = .true.
          cycle
        else if (name == '--check') then
          options%check_only = .true.
          cycle
        else if (name == '--strict') then
          options%strict = .true.
          cycle
        else if (name == '--out-of-core') then
          options%out_of_core = .true.
          cycle
        else if (name == '--mixed-precision') then
          options%mixed_precision = .true.
          cycle
        end if
        if (i == n) then
          write (error_unit, '(a)') 'feps: error: ' // arg // ' needs a value (see feps --help)'
          status = 2
          return
        end if
        i = i + 1
        value = argument(i)
        if (len_trim(value) == 0) then
          write (error_unit, '(a)') 'feps: error: ' // arg // ' takes ' // value_kind(name) // ', not an empty value'
          status = 2
          return
        end if
        select case (name)
        case ('--method')
          options%method = value
        case ('--fields')
          options%fields = value
        case ('--tolerance')
          options%tolerance = value       ! read and checked with the deck's rule (feps_program)
        case ('--restart')
          options%restart = value
        case ('--step', '--restart-every', '--stop-after-step', '--steps')
          ! a step count: whole_number gives 0 for anything else
          if (whole_number(value) < 1 .or. whole_number(value) > max_total_steps) then
            write (error_unit, '(a)') 'feps: error: ' // name // ' takes a whole number from 1 to ' // &
              str(max_total_steps) // ', not "' // value // '"'
            status = 2
            return
          end if
          if (name == '--step') options%restart_step = whole_number(value)
          if (name == '--restart-every') options%restart_every = whole_number(value)
          if (name == '--stop-after-step') options%stop_after_step = whole_number(value)
          if (name == '--steps') options%steps = whole_number(value)
        case ('--threads')
          threads = whole_number(value)
          if (threads < 1 .or. threads > 4096) then
            write (error_unit, '(a)') 'feps: error: --threads takes a whole number from 1 to 4096, not "' // &
              value // '"'
            status = 2
            return
          end if
        case ('--maxit')
          options%max_iterations = whole_number(value)
          if (options%max_iterations < 1 .or. options%max_iterations > max_iterations_limit) then
            write (error_unit, '(a)') 'feps: error: --maxit takes a whole number from 1 to ' // &
              str(max_iterations_limit) // ', not "' // value // '"'
            status = 2
            return
          end if
        case ('--solver')
          options%solver = value
          if (options%solver /= 'skyline' .and. options%solver /= 'cholmod' .and. options%solver /= 'mumps') then
            write (error_unit, '(a)') 'feps: error: --solver takes skyline, cholmod or mumps, not "' // options%solver // '"'
            status = 2
            return
          end if
          if (options%solver == 'mumps' .and. .not. mpi_built()) then
            write (error_unit, '(a)') 'feps: error: --solver mumps needs the MPI build of feps (README, "MUMPS over MPI")'
            status = 2
            return
          end if
        case default
          options%output = value
          if (is_xdmf_name(options%output)) then
            write (error_unit, '(a)') 'feps: error: ' // arg // ' "' // options%output // &
              '": the results file must not end in .xmf (the XDMF file beside it takes that name)'
            status = 2
            return
          end if
        end select
      case default
        if (len(arg) > 0 .and. arg(1:1) == '-') then
          write (error_unit, '(a)') 'feps: error: unknown option "' // arg // '" (see feps --help)'
          status = 2
          return
        end if
        if (allocated(options%deck)) then
          write (error_unit, '(a)') 'feps: error: one input deck at a time ("' // options%deck // '" and "' // &
            arg // '")'
          status = 2
          return
        end if
        if (len_trim(arg) == 0) then
          write (error_unit, '(a)') 'feps: error: the input deck is an empty name'
          status = 2
          return
        end if
        options%deck = arg
      end select
    end do
    if (.not. allocated(options%deck)) then
      write (error_unit, '(a)') 'feps: error: no input deck given (see feps --help)'
      status = 2
    else if (options%restart_step > 0 .and. len(options%restart) == 0) then
      write (error_unit, '(a)') 'feps: error: --step ' // str(options%restart_step) // ' names a restart point: ' // &
        'it needs --restart FILE'
      status = 2
    end if
  end subroutine parse_arguments

  !> What an option takes, for the message about an empty value.
  pure function value_kind(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    select case (name)
    case ('--output')
      text = 'a results file name'
    case ('--solver')
      text = 'skyline or cholmod'
    case ('--method')
      text = 'a method name (euler, modified-euler, newton-raphson, modified-newton-raphson, ' // &
             'initial-stiffness, full-newton-raphson)'
    case ('--maxit')
      text = 'a whole number from 1 to ' // str(max_iterations_limit)
    case ('--restart')
      text = 'a checkpoint file name'
    case ('--step', '--restart-every', '--stop-after-step', '--steps')
      text = 'a whole number of steps'
    case ('--tolerance')
      text = 'a number from 0 up (DELTA1)'
    case ('--threads')
      text = 'a whole number of threads'
    case default
      text = 'a list of result fields, e.g. all,nodal_principal'
    end select
  end function value_kind

  !> Threads of the element loops and CHOLMOD's solves (OpenMP) and of the factorization (OpenBLAS).
  !! Element loops and solves: --threads N; else OMP_NUM_THREADS when set; else the cores that
  !! no other process is running on at start (idle_cores), at least one: a waiting OpenMP thread
  !! whose core another process holds slowed FE1 twofold on a 2-core machine
  !! (docs/performance.md); and no more than the factorization's share of a large machine (on
  !! 16 cores FE1 was slower on 16 element threads than on 8). The results are the same for
  !! any number.
  !! Factorization: at most factorization_threads(cores) (three quarters of a machine above 4
  !! cores: all 16 of 16 measured 10x slower than 12), and no more than --threads N or
  !! OMP_NUM_THREADS; OPENBLAS_NUM_THREADS or GOTO_NUM_THREADS, when set, stand as set. The
  !! BLAS threads change the factorization at round-off; the element threads change nothing.
  !! Without `probe` (before the command line is read: --version, the joint and elements
  !! commands) the default is one thread, without the 40 ms of looking at the machine's load.
  subroutine set_threads(probe)
    logical, intent(in) :: probe
    integer :: blas
    blas = factorization_threads(omp_get_num_procs())
    if (threads > 0) then
      call omp_set_num_threads(threads)
      blas = min(blas, threads)
    else if (is_set('OMP_NUM_THREADS')) then
      blas = min(blas, omp_get_max_threads())
    else if (probe) then
      call omp_set_num_threads(min(idle_cores(omp_get_num_procs()), blas))
    else
      call omp_set_num_threads(1)
    end if
    if (.not. (is_set('OPENBLAS_NUM_THREADS') .or. is_set('GOTO_NUM_THREADS'))) call set_blas_threads(blas)
  end subroutine set_threads

  !> Whether an environment variable is set to something.
  logical function is_set(name)
    character(len=*), intent(in) :: name
    integer :: length
    call get_environment_variable(name, length=length)
    is_set = length > 0
  end function is_set

  !> The value of a whole number argument, or 0 when it is not one.
  integer function whole_number(text)
    character(len=*), intent(in) :: text
    integer :: ios
    whole_number = 0
    if (len(text) == 0 .or. verify(text, '0123456789') /= 0 .or. len(text) > 9) return
    read (text, *, iostat=ios) whole_number
    if (ios /= 0) whole_number = 0
  end function whole_number

  function argument(i) result(arg)
    integer, intent(in) :: i
    character(len=:), allocatable :: arg
    integer :: length
    call get_command_argument(i, length=length)
    allocate (character(len=length) :: arg)
    if (length > 0) call get_command_argument(i, arg)
  end function argument

  subroutine print_help()
    write (output_unit, '(a)') &
      'feps ' // feps_version // ' - finite elements for concrete jacking pipes, joints and soil', &
      '', &
      'usage: feps DECK [--output FILE] [--solver skyline|cholmod|mumps [--out-of-core]] [--mixed-precision]', &
      '                 [--method NAME] [--maxit N] [--steps N] [--tolerance X] [--fields LIST] [--check]', &
      '                 [--strict] [--quiet] [--restart-every N] [--restart FILE [--step N]] [--threads N]', &
      '       feps joint --beta DEG | --Z MM  --a MM --Ep MPa [--P N] [--json] ...', &
      '       feps elements', &
      '       feps --help | --version', &
      '', &
      '  DECK                 input deck (docs/input-format.md) or a file holding only a DATAIN mesh', &
      '  -o, --output FILE    HDF5 results file (overrides the deck''s OUTPUT record);', &
      '                       an XDMF file for ParaView is written beside it (FILE with .xmf', &
      '                       for its extension, so FILE must not end in .xmf)', &
      '      --solver NAME    linear solver: cholmod (supernodal, METIS), skyline (LDL^T, RCM) or', &
      '                       mumps (multifrontal, over MPI: mpirun -np N feps ..., in the MPI build)', &
      '      --out-of-core    with mumps: the factors on disk, in MUMPS_OOC_TMPDIR (else TMPDIR, else', &
      '                       /tmp), for models whose factor does not fit in memory', &
      '      --mixed-precision  with cholmod: the solves of a nonlinear run read a single-precision', &
      '                       copy of the factor (half the bytes); each step''s iterations correct', &
      '                       the solves against their double-precision residual, so steps converge', &
      '                       as before (docs/tradeoff.md). A linear model stays in double precision', &
      '      --method NAME    solve every stage by one method: euler, modified-euler, newton-raphson,', &
      '                       modified-newton-raphson, initial-stiffness, full-newton-raphson', &
      '                       (overrides the deck)', &
      '      --maxit N        at most N iterations per step in every stage, 1 to ' // str(max_iterations_limit) // &
      ' (overrides', &
      '                       the deck''s MAXIT; euler and modified-euler keep their one iteration)', &
      '      --steps N        N equal steps in every stage under load or displacement control', &
      '                       (overrides the deck''s STEPS; arc-length stages keep theirs)', &
      '      --tolerance X    the relative residual every step must reach, a number from 0 up', &
      '                       (overrides the deck''s DELTA1). The converged answer fast:', &
      '                       --method full-newton-raphson --steps 1 --tolerance 1e-6', &
      '      --fields LIST    the result fields to write, comma-separated as the FIELDS record names', &
      '                       them (overrides the deck''s FIELDS), e.g. all,nodal_principal', &
      '      --check          check the deck and the model: everything a run checks before its', &
      '                       first step, every stage''s loads, and one factorization of the', &
      '                       elastic stiffness per stage (missing supports); take no step,', &
      '                       write no file', &
      '      --strict         a run whose last step of some stage ends out of balance (relative', &
      '                       residual above DELTA1) fails: exit 1, no results file', &
      '      --restart-every N  write restart data every N steps to the checkpoint file beside', &
      '                       the results (NAME.restart.h5; overrides the deck''s RESTART)', &
      '      --restart FILE   continue the deck''s run from the restart data in FILE (a checkpoint', &
      '                       file of the same model) instead of from zero', &
      '      --step N         the restart point of step N (default: the last one in FILE)', &
      '      --stop-after-step K  a test aid: stop after step K as a run that dies would (exit 1)', &
      '      --threads N      threads of the element loops (OpenMP; default OMP_NUM_THREADS, else 1);', &
      '                       the results are bit-identical for any N', &
      '  -q, --quiet          print nothing but errors (no progress lines, no summary)', &
      '  -h, --help           this text', &
      '  -V, --version        the version', &
      '  joint                the analytical joint models of thesis chapter 7 (feps joint --help)', &
      '  elements             the element catalog as JSON (names in Abaqus and meshio, faces)', &
      '', &
      'Each option is given at most once, and none takes an empty value.', &
      '', &
      'Exit status: 0 success; 2 bad input (including a deck that cannot be read) or an unsolvable', &
      'model; 1 a run that failed (no convergence, results beyond double precision) or results', &
      'that cannot be written.'
  end subroutine print_help

  subroutine print_summary(s)
    type(run_summary_t), intent(in) :: s
    character(len=32) :: buf
    integer :: i
    if (len(s%title) > 0) write (output_unit, '(a)') 'title            ' // s%title
    write (output_unit, '(a)') 'nodes            ' // str(s%nodes)
    write (output_unit, '(a)') 'elements         ' // str(s%elements)
    if (s%checked_only) then
      call print_check(s)
      return
    end if
    if (s%mesh_only) then
      write (output_unit, '(a)') 'bounding box min' // vec3(s%bbox(:, 1))
      write (output_unit, '(a)') 'bounding box max' // vec3(s%bbox(:, 2))
      write (output_unit, '(a)') 'min Jacobian     ' // jacobian_text(s%min_jacobian)
    else
      write (output_unit, '(a)') 'dofs             ' // str(s%dofs)
      if (s%unused_nodes > 0) write (output_unit, '(a)') 'unused nodes     ' // str(s%unused_nodes) // &
        ' (in no element; no DOFs)'
      write (output_unit, '(a)') 'solver           ' // s%solver
      if (s%solver == 'cholmod-mixed') call print_mixed_precision(s)
      if (allocated(s%rank_memory_mb)) call print_ranks(s)
      write (output_unit, '(a)') 'blas             ' // s%blas
      write (output_unit, '(a)') 'threads          ' // str(omp_get_max_threads()) // ' of ' // &
        str(omp_get_num_procs()) // ' cores (element loops, solves)'
      if (s%linear) then
        write (output_unit, '(a)') 'analysis         linear: ' // str(s%factorizations) // ' factorization(s)'
      else
        write (output_unit, '(a)') 'analysis         nonlinear: ' // str(s%steps) // ' steps, ' // &
          str(s%iterations) // ' iterations, ' // str(s%factorizations) // ' factorizations, ' // &
          str(s%cutbacks) // ' cut-backs, ' // str(s%unconverged_steps) // &
          ' steps not converged (residual carried on)'
        if (s%lu_factorizations > 0) then
          write (buf, '(es9.2)') s%lu_min_rcond
          write (output_unit, '(a)') 'unsymmetric LU   ' // str(s%lu_factorizations) // &
            ' of the factorizations (UMFPACK: exact non-symmetric tangents; smallest rcond ' // &
            trim(adjustl(buf)) // ')'
        end if
        if (s%line_search) write (output_unit, '(a)') 'line search      ' // str(s%line_searches) // &
          ' of the iterations scaled (LINESEARCH=energy), ' // str(s%line_search_evaluations) // &
          ' residual evaluations added'
      end if
      write (buf, '(i0)') s%matrix_nnz
      write (output_unit, '(a)') 'matrix nonzeros  ' // trim(buf) // ' (lower triangle)'
      write (buf, '(i0)') s%factor_nnz
      write (output_unit, '(a)') 'factor nonzeros  ' // trim(buf)
      write (output_unit, '(a,es10.3)') 'factor flops     ', s%flops
      write (output_unit, '(a,es10.3,a,es10.3)') 'pivot ratio      ', s%min_pivot_ratio, ' .. ', s%max_pivot_ratio
      if (s%min_pivot_ratio > 0.0_dp) write (output_unit, '(a,es10.3,a)') 'condition est.   ', &
        s%max_pivot_ratio / s%min_pivot_ratio, ' (max/min pivot ratio)'
      if (s%condition_warning) write (error_unit, '(a)') 'feps: warning: the max/min pivot ratio exceeded 1e12: ' // &
        'the stiffness is ill-conditioned (stiffness contrast or a nearly free part); results may have lost digits'
      write (output_unit, '(a)') 'applied force   ' // vec3(s%applied_force)
      write (output_unit, '(a)') 'reaction force  ' // vec3(s%reaction_force)
      if (s%max_displacement_node > 0) then
        write (output_unit, '(a)') 'max displacement ' // sci(s%max_displacement, 5, 12) // ' at node ' // &
          str(s%max_displacement_node)
      else
        write (output_unit, '(a)') 'max displacement ' // sci(0.0_dp, 5, 12) // ' (no node moves)'
      end if
    end if
    if (allocated(s%state_bytes)) call print_state_memory(s)
    if (.not. s%mesh_only .and. .not. s%converged) write (output_unit, '(a)') 'warning: ' // unbalanced_text(s)
    if (.not. s%mesh_only) write (output_unit, '(a,3(f0.3,a))') 'times            assembly ', s%time_assembly, &
      ' s, factorization ', s%time_factorization, ' s, solve ', s%time_solve, ' s'
    write (output_unit, '(a,f0.3,a)') 'wall time        ', s%wall_time, ' s'
    if (allocated(s%reports)) then
      do i = 1, size(s%reports)
        write (output_unit, '(a)') trim(s%reports(i))
      end do
    end if
    if (len(s%output) > 0) write (output_unit, '(a)') 'results          ' // s%output
    if (allocated(s%restart_from)) write (output_unit, '(a)') 'continued from   ' // s%restart_from // &
      ' after step ' // str(s%restart_step) // ' (the results hold the later steps)'
    if (allocated(s%restart_file)) write (output_unit, '(a)') 'restart data     ' // s%restart_file
  end subroutine print_summary

  !> A 3-vector as the summary prints it: each component after a blank, in 12 characters.
  pure function vec3(v) result(line)
    real(dp), intent(in) :: v(3)
    character(len=:), allocatable :: line
    line = ' ' // sci(v(1), 5, 12) // ' ' // sci(v(2), 5, 12) // ' ' // sci(v(3), 5, 12)
  end function vec3

  !> The smallest Jacobian determinant of the solid elements for the summary; a model without
  !! solids (bars only) has none.
  function jacobian_text(j) result(text)
    real(dp), intent(in) :: j
    character(len=:), allocatable :: text
    if (j >= huge(1.0_dp)) then
      text = 'none (no solid element)'
    else
      text = sci(j, 5, 12)
    end if
  end function jacobian_text

  !> How the mixed-precision solves went: the largest test-solve error of the factors solved in
  !! single precision, and the factors solved in double precision instead.
  subroutine print_mixed_precision(s)
    type(run_summary_t), intent(in) :: s
    character(len=:), allocatable :: line
    line = 'mixed precision  ' // str(s%single_precision_factors) // ' of ' // str(s%factorizations) // &
      ' factors solved in single precision from their third solve on'
    if (s%single_precision_factors > 0) line = line // ' (test solves within ' // &
      trim(adjustl(sci(s%test_solve_error, 2, 9))) // ' relative)'
    if (s%precision_fallbacks > 0) line = line // '; ' // str(s%precision_fallbacks) // &
      ' kept in double precision (test solve above ' // trim(adjustl(sci(mixed_tolerance, 1, 8))) // ')'
    write (output_unit, '(a)') line
  end subroutine print_mixed_precision

  !> MUMPS over MPI: each rank's factorization memory (the largest of the run) and time (summed).
  subroutine print_ranks(s)
    type(run_summary_t), intent(in) :: s
    write (output_unit, '(a)') 'ranks            ' // str(size(s%rank_memory_mb)) // &
      '; factorization memory per rank (MB):' // whole_numbers(s%rank_memory_mb) // &
      '; factorization time per rank (s):' // seconds(s%rank_factor_seconds)
    if (.not. allocated(s%rank_elements)) return
    write (output_unit, '(a)') 'rank elements   ' // whole_numbers(s%rank_elements) // &
      '; set-up, assembly and update time per rank (s):' // seconds(s%rank_element_seconds)
    write (output_unit, '(a)') 'rank memory      peak resident per rank (MB):' // whole_numbers(s%rank_peak_memory_mb)
  end subroutine print_ranks

  !> ' v1 v2 ...', each rounded to a whole number.
  function whole_numbers(v) result(text)
    real(dp), intent(in) :: v(:)
    character(len=:), allocatable :: text
    integer :: r
    text = ''
    do r = 1, size(v)
      text = text // ' ' // str(nint(v(r)))
    end do
  end function whole_numbers

  !> ' t1 t2 ...' in seconds to two decimals.
  function seconds(v) result(text)
    real(dp), intent(in) :: v(:)
    character(len=:), allocatable :: text
    character(len=32) :: buf
    integer :: r
    text = ''
    do r = 1, size(v)
      write (buf, '(f0.2)') v(r)
      if (buf(1:1) == '.') buf = '0' // buf
      text = text // ' ' // trim(buf)
    end do
  end function seconds

  !> The summary of `feps --check`: the model's size and the solver's predictions.
  subroutine print_check(s)
    type(run_summary_t), intent(in) :: s
    character(len=32) :: buf
    write (output_unit, '(a)') 'dofs             ' // str(s%dofs)
    if (s%unused_nodes > 0) write (output_unit, '(a)') 'unused nodes     ' // str(s%unused_nodes) // &
      ' (in no element; no DOFs)'
    write (output_unit, '(a)') 'min Jacobian     ' // jacobian_text(s%min_jacobian)
    write (output_unit, '(a)') 'analysis         ' // trim(merge('linear   ', 'nonlinear', s%linear)) // ': ' // &
      str(s%stages) // ' stage(s), ' // str(s%steps) // ' steps'
    write (output_unit, '(a)') 'applied force   ' // vec3(s%applied_force)
    write (output_unit, '(a)') 'solver           ' // s%solver
    write (output_unit, '(a)') 'blas             ' // s%blas
    write (buf, '(i0)') s%matrix_nnz
    write (output_unit, '(a)') 'matrix nonzeros  ' // trim(buf) // ' (lower triangle)'
    write (buf, '(i0)') s%factor_nnz
    write (output_unit, '(a,f0.1,a)') 'factor nonzeros  ' // trim(buf) // ' (', &
      8.0_dp * real(s%factor_nnz, dp) / 1024.0_dp**2, ' MiB)'
    write (output_unit, '(a,es10.3,a)') 'factor flops     ', s%flops, ' (one factorization)'
    write (output_unit, '(a,es10.3,a,es10.3)') 'pivot ratio      ', s%min_pivot_ratio, ' .. ', s%max_pivot_ratio
    if (s%condition_warning) write (error_unit, '(a)') 'feps: warning: the max/min pivot ratio exceeded 1e12: ' // &
      'the stiffness is ill-conditioned (stiffness contrast or a nearly free part); results may have lost digits'
    write (output_unit, '(a,3(f0.3,a))') 'times            assembly ', s%time_assembly, &
      ' s, factorization ', s%time_factorization, ' s'
    write (output_unit, '(a,f0.3,a)') 'wall time        ', s%wall_time, ' s'
    write (output_unit, '(a)') 'checked          the elastic stiffness of every stage factorizes; ' // &
      'no step taken, no result file written (--check)'
  end subroutine print_check

  !> Memory kept for point states: nonlinear groups only (elastic groups keep none).
  subroutine print_state_memory(s)
    type(run_summary_t), intent(in) :: s
    character(len=:), allocatable :: line
    integer :: g
    line = 'point state      ' // str(sum(s%state_bytes)) // ' bytes'
    do g = 1, size(s%state_bytes)
      line = line // merge(' (', ', ', g == 1) // trim(s%group_names(g)) // ' ' // &
             str(s%state_bytes(g) / max(1_i8, int(s%group_elements(g), i8))) // ' per element'
    end do
    write (output_unit, '(a)') line // ')'
  end subroutine print_state_memory

end program feps_main
