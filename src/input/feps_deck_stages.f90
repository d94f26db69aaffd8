!> The deck's solution records: CONTROLS (the methods and their tolerances), STAGE and
!! REPORT (the quantities printed beside the thesis's values).
module feps_deck_stages
  use feps_strings, only: to_upper, to_lower
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, input_error, str
  use feps_records, only: record_t, nfields, field_text, field_line
  use feps_model, only: model_t, name_len, stage_t, controls_t, method_names, report_t, max_total_steps, &
                        max_iterations_limit, max_cutbacks_limit, path_load, path_arc_length, path_displacement, &
                        path_names, method_euler, method_modified_euler
  use feps_deck_fields, only: key_value, check_option_keys, option_real, option_text, require_fields, parse_real, &
                              parse_int, get_csys_option
  use feps_element_catalog, only: family_solid, family_interface
  use feps_coordinate_system, only: csys_cylindrical
  implicit none
  private

  public :: read_stage, read_controls, read_controls_record, read_report

contains

  !> STAGE, name, STEPS=n, LOAD=fraction, OUTPUT=k, ACTIVATE=g1[:g2...], and any CONTROLS
  !! option. ACTIVATE may be repeated; the group names are resolved once all groups are known.
  subroutine read_stage(rec, model, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    type(stage_t) :: st
    type(stage_t), allocatable :: tmp(:)
    integer :: i, colon
    character(len=:), allocatable :: k, v, names
    logical :: found
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    st%name = field_text(rec, 2)
    ! Messages, progress lines and /steps name a stage by its name: two alike would be ambiguous.
    do i = 1, size(model%stages)
      if (model%stages(i)%name == st%name) then
        call input_error(error, rec%file, field_line(rec, 2), &
                         'STAGE "' // st%name // '" is defined twice (first at line ' // &
                         str(model%stages(i)%line) // ')', 2)
        return
      end if
    end do
    st%file = rec%file
    st%line = rec%line
    st%controls = model%controls
    allocate (st%activate(0), st%activate_field(0))
    call check_option_keys(rec, 3, error, repeatable=['ACTIVATE'])
    if (allocated(error)) return
    call option_text(rec, 'STEPS', v, i, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'STAGE ' // st%name // ' needs STEPS=n')
      return
    end if
    do i = 3, nfields(rec)
      call key_value(rec, i, 'KEY=value', k, v, error)
      if (allocated(error)) return
      select case (k)
      case ('STEPS')
        call parse_int(v, 1, max_total_steps, st%steps, error, rec, i, 'STEPS')
        if (allocated(error)) return
        ! steps are numbered over all stages: their sum must stay countable (i8 for the sum)
        if (sum(int([model%stages%steps], i8)) + st%steps > max_total_steps) then
          call input_error(error, rec%file, field_line(rec, i), 'the stages'' steps add up to ' // &
                           str(sum(int([model%stages%steps], i8)) + st%steps) // ', more than feps numbers in one run (' // &
                           str(max_total_steps) // ')', i)
          return
        end if
      case ('LOAD')
        call parse_real(v, st%load_fraction, error, rec, i)
        if (allocated(error)) return
        st%load_given = .true.   ! else the default, decided once all stages are known
      case ('OUTPUT')
        call parse_int(v, 0, max_total_steps, st%output_every, error, rec, i, 'OUTPUT (every k steps)')
        if (allocated(error)) return
      case ('ACTIVATE')
        names = v
        do
          colon = index(names, ':')
          if (colon == 0) colon = len(names) + 1
          if (len_trim(names(:colon - 1)) == 0 .or. colon - 1 > name_len) then
            call input_error(error, rec%file, field_line(rec, i), &
                             'ACTIVATE takes group names separated by ":", got "' // &
                             v // '"', i)
            return
          end if
          st%activate = [character(len=name_len) :: st%activate, names(:colon - 1)]
          st%activate_field = [st%activate_field, i]
          if (colon > len(names)) exit
          names = names(colon + 1:)
        end do
      case ('PATH', 'ARC', 'NSET', 'FROM', 'DOF', 'VALUE')
        call read_path_option(rec, i, k, v, model, st, error)
        if (allocated(error)) return
      case ('METHOD', 'MAXIT', 'CUTBACKS', 'DELTA1', 'DELTA2', 'DELTA3', 'DELTA4', 'DIVERGENCE', 'ACCELERATION', &
            'LINESEARCH')
      case default
        call input_error(error, rec%file, field_line(rec, i), &
                         'unknown STAGE option "' // k // '" (STEPS, LOAD, OUTPUT, ' // &
                         'ACTIVATE, PATH, ARC, NSET, DOF, VALUE, METHOD, MAXIT, DELTA1, DELTA2, DELTA3, DELTA4, ' // &
                         'DIVERGENCE, CUTBACKS, ACCELERATION, LINESEARCH)', i)
        return
      end select
    end do
    call read_controls(rec, 3, st%controls, error)
    if (allocated(error)) return
    call check_path_options(rec, model, st, error)
    if (allocated(error)) return
    tmp = [model%stages, st]
    call move_alloc(tmp, model%stages)
  end subroutine read_stage

  !> One of the path-following options of a STAGE record (field i, key k, value v): PATH=
  !! (LOAD, ARC-LENGTH, DISPLACEMENT), ARC= (> 0), NSET= and FROM= (node sets defined before the
  !! STAGE), DOF= (X, Y or Z) and VALUE= (not zero). Which keys go with which PATH is check_path_options'.
  subroutine read_path_option(rec, i, k, v, model, st, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i
    character(len=*), intent(in) :: k, v
    type(model_t), intent(in) :: model
    type(stage_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    integer :: p
    select case (k)
    case ('PATH')
      st%path = -1
      do p = lbound(path_names, 1), ubound(path_names, 1)
        if (to_lower(v) == trim(path_names(p))) st%path = p
      end do
      st%path_field = i
      if (st%path < 0) call input_error(error, rec%file, field_line(rec, i), 'unknown PATH "' // v // &
                                        '" (LOAD, ARC-LENGTH, DISPLACEMENT)', i)
    case ('ARC')
      call parse_real(v, st%arc, error, rec, i)
      if (allocated(error)) return
      if (.not. (st%arc > 0.0_dp)) call input_error(error, rec%file, field_line(rec, i), &
                                                    'ARC (the arc length) must be positive', i)
    case ('NSET')
      st%path_set = model%find_node_set(v)
      if (st%path_set == 0) call input_error(error, rec%file, field_line(rec, i), 'undefined node set "' // v // &
                                             '" (PATH=DISPLACEMENT follows a set defined before its STAGE)', i)
    case ('FROM')
      st%path_from_set = model%find_node_set(v)
      if (st%path_from_set == 0) call input_error(error, rec%file, field_line(rec, i), 'undefined node set "' // &
                                                  v // '" (FROM= of PATH=DISPLACEMENT names a set defined before ' // &
                                                  'its STAGE)', i)
    case ('DOF')
      st%path_dof = index('XYZ', to_upper(v))
      if (len(v) /= 1 .or. st%path_dof == 0) then
        st%path_dof = 0
        call input_error(error, rec%file, field_line(rec, i), 'DOF takes X, Y or Z, got "' // v // '"', i)
      end if
    case ('VALUE')
      call parse_real(v, st%path_value, error, rec, i)
      if (allocated(error)) return
      if (st%path_value == 0.0_dp) call input_error(error, rec%file, field_line(rec, i), &
                                                    'VALUE (the displacement increment of the stage) must not be zero', i)
    end select
  end subroutine read_path_option

  !> The path-following keys of a STAGE record fit together: ARC= only with PATH=ARC-LENGTH;
  !! NSET=, DOF= and VALUE= all three with PATH=DISPLACEMENT and only there; a path that
  !! iterates to equilibrium takes no Euler method (one pass per step).
  subroutine check_path_options(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(stage_t), intent(in) :: st
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: v
    integer :: i
    logical :: found
    call option_text(rec, 'ARC', v, i, found)
    if (found .and. st%path /= path_arc_length) then
      call input_error(error, rec%file, field_line(rec, i), 'ARC is the arc length of PATH=ARC-LENGTH; ' // &
                       'this stage follows PATH=' // to_upper(trim(path_names(st%path))), i)
      return
    end if
    if (st%path == path_displacement) then
      if (st%path_set == 0 .or. st%path_dof == 0 .or. st%path_value == 0.0_dp) then
        call input_error(error, rec%file, field_line(rec, st%path_field), 'PATH=DISPLACEMENT needs NSET=<set>, ' // &
                         'DOF=<X, Y or Z> and VALUE=<the displacement increment of the stage>', st%path_field)
        return
      end if
      if (st%path_from_set == st%path_set) then
        call option_text(rec, 'FROM', v, i, found)
        call input_error(error, rec%file, field_line(rec, i), 'FROM= names the set NSET= names: their ' // &
                         'relative displacement is zero', i)
        return
      end if
    else
      do i = 3, nfields(rec)
        v = to_upper(field_text(rec, i))
        if (index(v, 'NSET=') == 1 .or. index(v, 'DOF=') == 1 .or. index(v, 'VALUE=') == 1 .or. &
            index(v, 'FROM=') == 1) then
          call input_error(error, rec%file, field_line(rec, i), v(:index(v, '=') - 1) // ' goes with ' // &
                           'PATH=DISPLACEMENT (the DOF it follows); this stage follows PATH=' // &
                           to_upper(trim(path_names(st%path))), i)
          return
        end if
      end do
    end if
    if (st%path /= path_load .and. (st%controls%method == method_euler .or. &
                                    st%controls%method == method_modified_euler)) then
      call input_error(error, rec%file, field_line(rec, st%path_field), 'PATH=' // to_upper(trim(path_names(st%path))) // &
                       ' iterates each step to equilibrium; METHOD=' // trim(method_names(st%controls%method)) // &
                       ' takes one pass per step (use newton-raphson, modified-newton-raphson, initial-stiffness ' // &
                       'or full-newton-raphson)', st%path_field)
      return
    end if
  end subroutine check_path_options

  !> The CONTROLS record: the default controls of the STAGE records after it. Each stage takes
  !! its copy when its STAGE record is read, so a CONTROLS after a STAGE would change nothing
  !! for the stages before it: an error rather than a silent no-op.
  subroutine read_controls_record(rec, model, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    if (size(model%stages) > 0) then
      call input_error(error, rec%file, field_line(rec, 1), 'CONTROLS after STAGE ' // model%stages(1)%name // &
                       ' would not apply to it: put CONTROLS before the first STAGE, or give the options ' // &
                       'on the STAGE records', 1)
      return
    end if
    call check_option_keys(rec, 2, error)
    if (allocated(error)) return
    call read_controls(rec, 2, model%controls, error)
  end subroutine read_controls_record

  !> CONTROLS, METHOD=name, MAXIT=n, DELTA1..DELTA4=value, CUTBACKS=n, ACCELERATION=..,
  !! LINESEARCH=.. (also inside STAGE).
  subroutine read_controls(rec, first, c, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: first
    type(controls_t), intent(inout) :: c
    type(error_t), allocatable, intent(out) :: error
    integer :: i, m
    character(len=:), allocatable :: k, v
    real(dp) :: x
    do i = first, nfields(rec)
      call key_value(rec, i, 'KEY=value', k, v, error)
      if (allocated(error)) return
      select case (k)
      case ('METHOD')
        c%method = 0
        do m = 1, size(method_names)
          if (to_lower(v) == trim(method_names(m))) c%method = m
        end do
        if (c%method == 0) then
          call input_error(error, rec%file, field_line(rec, i), &
                           'unknown METHOD "' // v // '" (euler, modified-euler, ' // &
                           'newton-raphson, modified-newton-raphson, initial-stiffness, full-newton-raphson)', i)
          return
        end if
      case ('MAXIT', 'CUTBACKS')
        if (k == 'MAXIT') then
          call parse_int(v, 1, max_iterations_limit, m, error, rec, i, k)
        else
          call parse_int(v, 0, max_cutbacks_limit, m, error, rec, i, k)
        end if
        if (allocated(error)) return
        if (k == 'MAXIT') then
          c%max_iterations = m
          c%max_iterations_set = .true.
        else
          c%max_cutbacks = m
        end if
      case ('ACCELERATION')
        select case (to_lower(v))
        case ('bfgs')
          c%bfgs = .true.
        case ('none')
          c%bfgs = .false.
        case default
          call input_error(error, rec%file, field_line(rec, i), 'unknown ACCELERATION "' // v // '" (none, bfgs)', i)
          return
        end select
      case ('LINESEARCH')
        select case (to_lower(v))
        case ('energy')
          c%line_search = .true.
        case ('none')
          c%line_search = .false.
        case default
          call input_error(error, rec%file, field_line(rec, i), 'unknown LINESEARCH "' // v // '" (none, energy)', i)
          return
        end select
        c%line_search_file = rec%file
        c%line_search_line = rec%line
        c%line_search_field = i
      case ('DELTA1', 'DELTA2', 'DELTA3', 'DELTA4', 'DIVERGENCE')
        call parse_real(v, x, error, rec, i)
        if (allocated(error)) return
        if (x < 0.0_dp) then
          call input_error(error, rec%file, field_line(rec, i), k // ' must not be negative', i)
          return
        end if
        select case (k)
        case ('DELTA1')
          c%delta1 = x
        case ('DELTA2')
          c%delta2 = x
        case ('DELTA3')
          c%delta3 = x
        case ('DELTA4')
          c%delta4 = x
        case ('DIVERGENCE')
          c%divergence = x
        end select
      case default
        if (first == 2) then
          call input_error(error, rec%file, field_line(rec, i), 'unknown CONTROLS option "' // k // &
                           '" (METHOD, MAXIT, DELTA1, DELTA2, DELTA3, DELTA4, DIVERGENCE, CUTBACKS, ACCELERATION, ' // &
                           'LINESEARCH)', i)
          return
        end if
      end select
    end do
  end subroutine read_controls

  !> REPORT, ROTATION, NAME=n, GROUP=g, R=radius, Z=section [, FROM=x0, TO=x1]
  !! [, REFERENCE=value in degrees], or REPORT, TILT, NAME=n, GROUP=g, FROM=z0, TO=z1
  !! [, REFERENCE=...]: the tilt of the group's axis between two sections (thesis Table 7.2),
  !! or REPORT, REACTION, NAME=n, NSET=s: the resultant of the support reactions on a node set.
  subroutine read_report(rec, model, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    type(report_t) :: r
    type(report_t), allocatable :: tmp(:)
    character(len=:), allocatable :: text, kind
    integer :: ifield
    logical :: found, has_to
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    r%kind = to_lower(field_text(rec, 2))
    if (r%kind /= 'rotation' .and. r%kind /= 'tilt' .and. r%kind /= 'reaction' .and. r%kind /= 'section' .and. &
        r%kind /= 'joint') then
      call input_error(error, rec%file, field_line(rec, 2), 'unknown REPORT "' // field_text(rec, 2) // &
                       '" (ROTATION, TILT, REACTION, SECTION, JOINT)', 2)
      return
    end if
    kind = to_upper(r%kind)
    ! the kinds with a reader of their own
    if (r%kind == 'joint' .or. r%kind == 'section' .or. r%kind == 'reaction') then
      select case (r%kind)
      case ('joint')
        call read_joint_report(rec, model, r, error)
      case ('section')
        call read_section_report(rec, model, r, error)
      case default
        call read_reaction_report(rec, model, r, error)
      end select
      if (allocated(error)) return
      tmp = [model%reports, r]
      call move_alloc(tmp, model%reports)
      return
    end if
    if (r%kind == 'tilt') then
      call check_option_keys(rec, 3, error, allowed=[character(len=9) :: 'NAME', 'GROUP', 'FROM', 'TO', 'REFERENCE'])
    else
      call check_option_keys(rec, 3, error, &
                             allowed=[character(len=9) :: 'NAME', 'GROUP', 'R', 'Z', 'FROM', 'TO', 'REFERENCE'])
    end if
    if (allocated(error)) return
    call name_report(rec, model, r, error)
    if (allocated(error)) return
    call option_text(rec, 'GROUP', text, ifield, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'REPORT, ' // kind // ' needs GROUP=<the pipe group>')
      return
    end if
    r%group = model%find_group(text)
    if (r%group == 0) then
      call input_error(error, rec%file, field_line(rec, ifield), 'undefined element group "' // text // '"', ifield)
      return
    end if
    call option_real(rec, 'REFERENCE', r%reference, r%has_reference, error)
    if (allocated(error)) return
    call option_real(rec, 'FROM', r%x_from, r%has_span, error)
    if (allocated(error)) return
    call option_real(rec, 'TO', r%x_to, has_to, error)
    if (allocated(error)) return

    if (r%kind == 'tilt') then
      ! FROM= and TO= are the two sections z whose mean ux give the axis tilt.
      if (.not. (r%has_span .and. has_to) .or. r%x_from == r%x_to) then
        call input_error(error, rec%file, rec%line, 'REPORT, TILT needs FROM= and TO= (two different sections z)')
        return
      end if
    else
      call option_real(rec, 'R', r%r, found, error)
      if (allocated(error)) return
      if (.not. found) then
        call input_error(error, rec%file, rec%line, 'REPORT, ROTATION needs R=<radius>')
        return
      end if
      call option_real(rec, 'Z', r%z, found, error)
      if (allocated(error)) return
      if (.not. found) then
        call input_error(error, rec%file, rec%line, 'REPORT, ROTATION needs Z=<section>')
        return
      end if
      if (r%has_span .neqv. has_to .or. (has_to .and. r%x_from == r%x_to)) then
        call input_error(error, rec%file, rec%line, 'REPORT, ROTATION takes both FROM= and TO= (different x), ' // &
                         'or neither')
        return
      end if
    end if
    tmp = [model%reports, r]
    call move_alloc(tmp, model%reports)
  end subroutine read_report

  !> A REPORT's record (for its messages) and name: NAME= or, by default, its kind; a name an
  !! earlier REPORT took is an error (refuse_duplicate_name).
  subroutine name_report(rec, model, r, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(report_t), intent(inout) :: r
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: ifield
    logical :: found
    r%file = rec%file
    r%line = rec%line
    call option_text(rec, 'NAME', text, ifield, found)
    r%name = r%kind
    if (found) r%name = text
    call refuse_duplicate_name(rec, model, r%name, merge(ifield, 2, found), error)
  end subroutine name_report

  !> The options of REPORT, SECTION: NAME= (default 'section'), Z= (the section plane, required),
  !! GROUP= (default: every group) and X0=, Y0= (the point on the plane moments are taken about,
  !! default the z axis).
  subroutine read_section_report(rec, model, r, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(report_t), intent(inout) :: r
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: ifield
    logical :: found
    call check_option_keys(rec, 3, error, allowed=[character(len=5) :: 'NAME', 'GROUP', 'Z', 'X0', 'Y0'])
    if (allocated(error)) return
    call name_report(rec, model, r, error)
    if (allocated(error)) return
    call option_text(rec, 'GROUP', text, ifield, found)
    if (found) then
      r%group = model%find_group(text)
      if (r%group == 0) then
        call input_error(error, rec%file, field_line(rec, ifield), 'undefined element group "' // text // '"', ifield)
        return
      end if
    end if
    call option_real(rec, 'Z', r%z, found, error)
    if (allocated(error)) return
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'REPORT, SECTION needs Z=<the section plane>')
      return
    end if
    call option_real(rec, 'X0', r%about(1), found, error)
    if (.not. allocated(error)) call option_real(rec, 'Y0', r%about(2), found, error)
  end subroutine read_section_report

  !> The options of REPORT, JOINT: NAME= (default 'joint'), INTERFACE= (the joint's interface
  !! group), PIPE=g1[:g2] (the pipes beside it, solid groups), PACKING= (a solid group, for the
  !! analytical models), CSYS= (a cylindrical system about the pipe axis; default FIELDS CSYS=),
  !! EDGE= (theta of the loaded edge, deg), A=, L= and P= (packing thickness, pipe length and
  !! joint load in place of what the model gives), NEAR= (how far from the joint the pipes'
  !! points count).
  subroutine read_joint_report(rec, model, r, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(report_t), intent(inout) :: r
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text, names
    integer :: ifield, g, colon
    logical :: found
    call check_option_keys(rec, 3, error, allowed=[character(len=9) :: 'NAME', 'INTERFACE', 'PIPE', 'PACKING', &
                                                    'CSYS', 'EDGE', 'A', 'L', 'P', 'NEAR'])
    if (allocated(error)) return
    call name_report(rec, model, r, error)
    if (allocated(error)) return
    call joint_group('INTERFACE', family_interface, 'an interface group', r%interface_group)
    if (allocated(error)) return
    if (model%groups(r%interface_group)%element%dimension /= 3) then
      call input_error(error, rec%file, field_line(rec, ifield), 'REPORT, JOINT: group "' // text // &
                       '" is a 2D (plane strain) interface; the joint is an annulus in 3D', ifield)
      return
    end if
    call option_text(rec, 'PIPE', names, ifield, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'REPORT, JOINT needs PIPE=<the pipe group>[:<the other pipe>]')
      return
    end if
    allocate (r%pipe_groups(0))
    do
      colon = index(names, ':')
      if (colon == 0) colon = len(names) + 1
      text = names(:colon - 1)
      g = model%find_group(text)
      if (g == 0) then
        call input_error(error, rec%file, field_line(rec, ifield), 'undefined element group "' // text // '"', ifield)
        return
      end if
      if (model%groups(g)%element%family /= family_solid) then
        call input_error(error, rec%file, field_line(rec, ifield), 'REPORT, JOINT: PIPE= group "' // text // &
                         '" is not a solid group (its type is ' // model%groups(g)%element_type // ')', ifield)
        return
      end if
      if (any(r%pipe_groups == g)) then
        call input_error(error, rec%file, field_line(rec, ifield), 'REPORT, JOINT: PIPE= names group "' // text // &
                         '" twice', ifield)
        return
      end if
      r%pipe_groups = [r%pipe_groups, g]
      if (colon > len(names)) exit
      names = names(colon + 1:)
    end do
    if (size(r%pipe_groups) > 2) then
      call input_error(error, rec%file, field_line(rec, ifield), 'REPORT, JOINT: PIPE= takes one or two groups ' // &
                       '(the pipes on either side of the joint)', ifield)
      return
    end if
    call option_text(rec, 'PACKING', text, ifield, found)
    if (found) then
      call joint_group('PACKING', family_solid, 'a solid group', r%packing_group)
      if (allocated(error)) return
    end if
    call get_csys_option(rec, model, 'CSYS', 0, r%csys, error)
    if (allocated(error)) return
    if (r%csys /= 0) then
      if (model%systems(r%csys)%kind /= csys_cylindrical) then
        call option_text(rec, 'CSYS', text, ifield, found)
        call input_error(error, rec%file, field_line(rec, ifield), 'REPORT, JOINT: coordinate system ' // &
                         str(r%csys) // ' is not cylindrical (the joint''s hoop stress and radii are about its axis)', &
                         ifield)
        return
      end if
    end if
    call option_real(rec, 'EDGE', r%edge, found, error)
    if (.not. allocated(error)) call positive_option('A', r%packing_thickness, r%has_a)
    if (.not. allocated(error)) call positive_option('L', r%pipe_length, r%has_l)
    if (.not. allocated(error)) call positive_option('P', r%load, r%has_p)
    if (.not. allocated(error)) call positive_option('NEAR', r%near, found)
  contains
    !> The group named by KEY=, which must be of `family`.
    subroutine joint_group(key, family, what, g)
      character(len=*), intent(in) :: key, what
      integer, intent(in) :: family
      integer, intent(out) :: g
      call option_text(rec, key, text, ifield, found)
      g = 0
      if (.not. found) then
        call input_error(error, rec%file, rec%line, 'REPORT, JOINT needs ' // key // '=<' // what // '>')
        return
      end if
      g = model%find_group(text)
      if (g == 0) then
        call input_error(error, rec%file, field_line(rec, ifield), 'undefined element group "' // text // '"', ifield)
        return
      end if
      if (model%groups(g)%element%family /= family) then
        call input_error(error, rec%file, field_line(rec, ifield), 'REPORT, JOINT: ' // key // '= group "' // &
                         text // '" is not ' // what // ' (its type is ' // model%groups(g)%element_type // ')', ifield)
        g = 0
      end if
    end subroutine joint_group

    !> KEY=value, which must be positive when given.
    subroutine positive_option(key, value, given)
      character(len=*), intent(in) :: key
      real(dp), intent(inout) :: value
      logical, intent(out) :: given
      call option_real(rec, key, value, given, error)
      if (allocated(error) .or. .not. given) return
      if (.not. value > 0.0_dp) then
        call option_text(rec, key, text, ifield, found)
        call input_error(error, rec%file, field_line(rec, ifield), 'REPORT, JOINT: ' // key // '= must be ' // &
                         'positive, got ' // text, ifield)
      end if
    end subroutine positive_option
  end subroutine read_joint_report

  !> The options of REPORT, REACTION: NAME= (default 'reaction') and NSET=, a node set defined
  !! before the record.
  subroutine read_reaction_report(rec, model, r, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(report_t), intent(inout) :: r
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: ifield
    logical :: found
    call check_option_keys(rec, 3, error, allowed=[character(len=4) :: 'NAME', 'NSET'])
    if (allocated(error)) return
    call name_report(rec, model, r, error)
    if (allocated(error)) return
    call option_text(rec, 'NSET', text, ifield, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'REPORT, REACTION needs NSET=<a node set>')
      return
    end if
    r%node_set = model%find_node_set(text)
    if (r%node_set == 0) call input_error(error, rec%file, field_line(rec, ifield), &
                                          'undefined node set "' // text // '"', ifield)
  end subroutine read_reaction_report

  !> Each REPORT's values are written under its name (rotation_<name>_deg, reaction_<name>_fx):
  !! two REPORTs of one name would write one value over the other.
  subroutine refuse_duplicate_name(rec, model, name, ifield, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    character(len=*), intent(in) :: name
    integer, intent(in) :: ifield
    type(error_t), allocatable, intent(out) :: error
    integer :: i
    do i = 1, size(model%reports)
      if (model%reports(i)%name == name) then
        call input_error(error, rec%file, field_line(rec, ifield), &
                         'REPORT name "' // name // '" is used twice (first at line ' // &
                         str(model%reports(i)%line) // ')', ifield)
        return
      end if
    end do
  end subroutine refuse_duplicate_name

end module feps_deck_stages
