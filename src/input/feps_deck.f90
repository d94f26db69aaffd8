!> The input deck: legacy-style keyword records, with DATAIN blocks inline or included.
!! Keywords and their fields are documented in docs/input-format.md. Every error names the
!! file, the line and, where one is at fault, the field. The reader fills the model's plain
!! data; face sets are resolved later by the assembly layer, which knows element faces.
module feps_deck
  use feps_strings, only: to_upper, to_lower
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, err_input, str
  use feps_records, only: record_t, read_records, keyword, nfields, field_text, field_line
  use feps_paths, only: is_xdmf_name
  use feps_datain, only: datain_mesh_t, datain_read_block, is_datain_record, datain_check, max_mesh_nodes, &
                       max_mesh_elements
  use feps_coordinate_system, only: coordinate_system_t, default_coordinate_systems, cylindrical_about, csys_cartesian, &
                                    csys_cylindrical
  use feps_model, only: model_t, max_total_steps, element_group_t, material_spec_t, text_material_keys, node_set_t, face_set_t, &
                        nodal_load_t, constraint_t, &
                        region_t, in_region, name_len, method_euler, method_modified_euler, method_newton_raphson, &
                        method_full_newton_raphson, known_fields, line_search_refusal
  use feps_deck_fields, only: require_fields, forbid_extra_fields, get_real, get_int, parse_real, parse_int, parse_range_real, &
                              parse_range_int, key_value, check_option_keys, option_text, get_csys_option, dof_index, dof_names, &
                              check_result_name, resolve_path, material_family
  use feps_element_catalog, only: element_info, known_element_types, family_solid, family_interface, &
                                  family_bar, bare_mesh_type
  use feps_material, only: material_t
  use feps_material_factory, only: new_material, material_of
  use feps_deck_loads, only: read_fix, read_displace, read_force, read_prestress, read_face_load, read_gravity, read_geostatic, &
                             read_mode
  use feps_deck_stages, only: read_stage, read_controls_record, read_report
  use feps_deck_tables, only: first_row_field, read_nodes_table, read_elements_table, read_id_list
  implicit none
  private

  public :: read_deck, resolve_node_sets

  !> The rows of one ELEMENTS table (checked against the nodes once all are read).
  type :: element_rows_t
    integer :: group = 0
    integer, allocatable :: ids(:)
    integer, allocatable :: connectivity(:, :)
    integer, allocatable :: id_field(:)          !! each row's id field (node i is field id_field + i)
    type(record_t) :: rec
  end type element_rows_t

  !> ELSET, name, LIST, GROUP=g: element ids of a group, as its tables (or its DATAIN blocks'
  !! order) number them, with the line and field of each for messages; an FSET ELSET=
  !! takes them with a face number.
  type :: element_set_t
    character(len=:), allocatable :: name
    character(len=:), allocatable :: group
    integer, allocatable :: ids(:), lines(:), fields(:)
  end type element_set_t

  !> What the reader keeps while it walks the records.
  type :: deck_state_t
    type(datain_mesh_t) :: mesh
    type(element_set_t), allocatable :: element_sets(:)
    integer, allocatable :: block_group(:)      !! group that took each element block
    integer :: current_group = 0                !! group taking the inline blocks that follow
    integer :: explicit_nodes = 0
    real(dp), allocatable :: explicit_coords(:, :)
    integer, allocatable :: explicit_ids(:)
    integer, allocatable :: explicit_line(:)
    integer, allocatable :: explicit_field(:)    !! the field of each explicit node's number
    character(len=:), allocatable :: explicit_file
    type(region_t), allocatable :: set_regions(:)
    integer, allocatable :: set_node(:)          !! NSET by a single node number (0: by region)
    character(len=name_len), allocatable :: set_group(:)  !! NSET restricted to a group's nodes ('' if not)
    type(record_t), allocatable :: set_records(:)
    integer, allocatable :: set_field(:)         !! a LIST row's node field (set_node -2), else 0
    type(element_rows_t), allocatable :: element_tables(:)
    integer :: current_stage = 0                 !! stage that loads and displacements belong to
    logical :: fields_given = .false.            !! a FIELDS record came: only what it names
    integer :: solver_line = 0                   !! line of the SOLVER record (0: none yet)
    integer :: output_line = 0                   !! line of the OUTPUT record (0: none yet)
    integer :: restart_line = 0                  !! line of the RESTART record (0: none yet)
  end type deck_state_t

contains

  !> Read a deck (or a file holding only a DATAIN mesh) into `model`.
  subroutine read_deck(path, model, error)
    character(len=*), intent(in) :: path
    type(model_t), intent(out) :: model
    type(error_t), allocatable, intent(out) :: error
    type(record_t), allocatable :: records(:)
    type(deck_state_t) :: st
    integer :: pos

    call read_records(path, records, error)
    if (allocated(error)) return
    model%deck_file = path
    model%title = ''
    model%solver = 'cholmod'
    model%output_file = ''
    model%systems = default_coordinate_systems()
    allocate (model%groups(0), model%materials(0), model%node_sets(0), model%face_sets(0))
    allocate (model%constraints(0), model%nodal_loads(0), model%face_loads(0), model%stages(0), model%reports(0))
    allocate (model%prestresses(0))
    allocate (st%block_group(0), st%set_regions(0), st%set_node(0), st%set_records(0), st%set_group(0), st%set_field(0))
    allocate (st%explicit_coords(3, 0), st%explicit_ids(0), st%explicit_line(0), st%element_tables(0), &
              st%explicit_field(0))
    st%mesh%nnode = 0
    allocate (st%mesh%coords(3, 0), st%mesh%blocks(0))

    ! A file of DATAIN records only is a bare mesh to check and report.
    model%mesh_only = .true.
    do pos = 1, size(records)
      if (.not. is_datain_record(records(pos))) model%mesh_only = .false.
    end do
    pos = 1
    do while (pos <= size(records))
      call read_record(records, pos, model, st, error)
      if (allocated(error)) return
    end do
    call finish_model(path, model, st, error)
  end subroutine read_deck

  !> Dispatch one record (or a whole DATAIN block) and advance pos.
  subroutine read_record(records, pos, model, st, error)
    type(record_t), intent(in) :: records(:)
    integer, intent(inout) :: pos
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: key
    integer :: nb_before, b

    key = keyword(records(pos))
    if (key == 'A') then
      nb_before = size(st%mesh%blocks)
      call datain_read_block(records, pos, model%systems, st%mesh, error)
      if (allocated(error)) return
      do b = nb_before + 1, size(st%mesh%blocks)
        st%block_group = [st%block_group, st%current_group]
      end do
      return
    end if
    if (key == 'E') then
      ! The closing E of a DATAIN mesh: nothing more to do, and nothing may follow it.
      call forbid_extra_fields(records(pos), 1, error)
      if (allocated(error)) return
      pos = pos + 1
      return
    end if
    if (model%mesh_only) then
      call input_error(error, records(pos)%file, records(pos)%line, &
                       'a DATAIN mesh file holds only A, % and E records, not "' // key // '"', 1)
      return
    end if

    select case (key)
    case ('TITLE')
      call read_title(records(pos), model)
    case ('PARAMETERS')
      call read_parameters(records(pos), model, error)
    case ('CSYS')
      call read_csys(records(pos), model, error)
    case ('INCLUDE')
      call read_include(records(pos), model, st, error)
    case ('NODE')
      call read_node(records(pos), model, st, error)
    case ('NODES')
      call read_nodes(records(pos), model, st, error)
    case ('ELEMENTS')
      call read_elements(records(pos), model, st, error)
    case ('MATERIAL')
      call read_material(records(pos), model, error)
    case ('GROUP')
      call read_group(records(pos), model, st, error)
    case ('NSET')
      call read_nset(records(pos), model, st, error)
    case ('FSET')
      call read_fset(records(pos), model, st, error)
    case ('ELSET')
      call read_elset(records(pos), st, error)
    case ('FIX')
      call read_fix(records(pos), model, st%current_stage, .false., error)
    case ('RELEASE')
      call read_fix(records(pos), model, st%current_stage, .true., error)
    case ('DISPLACE', 'FORCE')
      if (nfields(records(pos)) >= 2) then
        if (to_upper(field_text(records(pos), 2)) == 'LIST') then
          call read_listed_values(records(pos), model, st, error)
          pos = pos + 1
          return
        end if
      end if
      if (key == 'FORCE') then
        call read_force(records(pos), model, st%current_stage, error)
      else
        call read_displace(records(pos), model, st%current_stage, error)
      end if
    case ('GRAVITY')
      call read_gravity(records(pos), model, st%current_stage, error)
    case ('GEOSTATIC')
      call read_geostatic(records(pos), model, st%current_stage, error)
    case ('PRESSURE', 'TRACTION')
      call read_face_load(records(pos), model, st%current_stage, error)
    case ('PRESTRESS')
      call read_prestress(records(pos), model, st%current_stage, error)
    case ('CONTROLS')
      call read_controls_record(records(pos), model, error)
    case ('REPORT')
      call read_report(records(pos), model, error)
    case ('STAGE')
      call read_stage(records(pos), model, error)
      st%current_stage = size(model%stages)
    case ('SOLVER')
      if (st%solver_line > 0) then
        call input_error(error, records(pos)%file, records(pos)%line, 'SOLVER is given twice (first at line ' // &
                         str(st%solver_line) // ')', 1)
        return
      end if
      st%solver_line = records(pos)%line
      call read_solver(records(pos), model, error)
    case ('FIELDS')
      call read_fields(records(pos), model, st, error)
    case ('OUTPUT')
      call read_output(records(pos), model, st, error)
    case ('RESTART')
      call read_restart(records(pos), model, st, error)
    case ('%')
      call input_error(error, records(pos)%file, records(pos)%line, &
                       'a % record outside a DATAIN block (no A record opened one)', 1)
    case default
      call input_error(error, records(pos)%file, records(pos)%line, 'unknown keyword "' // key // '"', 1)
    end select
    pos = pos + 1
  end subroutine read_record

  ! ---------------------------------------------------------------------------------------
  ! Keyword readers
  ! ---------------------------------------------------------------------------------------

  subroutine read_title(rec, model)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer :: i
    model%title = ''
    do i = 2, nfields(rec)
      if (i > 2) model%title = model%title // ', '
      model%title = model%title // field_text(rec, i)
    end do
  end subroutine read_title

  !> PARAMETERS, NAME=value [, NAME=value ...]: labels of the case (a campaign's parameters),
  !! written to the results file as /summary attributes parameter_<name> (a number as a real,
  !! anything else as a string). Names: letters, digits and underscores, not starting with a
  !! digit, each given once in the deck.
  subroutine read_parameters(rec, model, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: f, name, value
    character(len=name_len), allocatable :: names(:), values(:)
    integer :: i, eq, n
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    if (.not. allocated(model%parameter_names)) allocate (model%parameter_names(0), model%parameter_values(0))
    do i = 2, nfields(rec)
      f = field_text(rec, i)
      eq = index(f, '=')
      name = trim(adjustl(f(:max(eq - 1, 0))))
      value = trim(adjustl(f(eq + 1:)))
      if (eq == 0 .or. len(name) == 0 .or. len(value) == 0) then
        call input_error(error, rec%file, field_line(rec, i), 'expected NAME=value, got "' // f // '"', i)
        return
      end if
      if (verify(name, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0 .or. &
          scan(name(1:1), '0123456789') /= 0 .or. len(name) > name_len - 10 .or. len(value) > name_len) then
        call input_error(error, rec%file, field_line(rec, i), &
                         'parameter "' // name // '": a name is letters, digits and ' // &
                         'underscores, not starting with a digit, at most ' // str(name_len - 10) // &
                         ' characters; a value at most ' // str(name_len), i)
        return
      end if
      if (any(model%parameter_names == name)) then
        call input_error(error, rec%file, field_line(rec, i), 'parameter "' // name // '" is given twice', i)
        return
      end if
      n = size(model%parameter_names)
      allocate (names(n + 1), values(n + 1))
      names(:n) = model%parameter_names
      values(:n) = model%parameter_values
      names(n + 1) = name
      values(n + 1) = value
      call move_alloc(names, model%parameter_names)
      call move_alloc(values, model%parameter_values)
    end do
  end subroutine read_parameters

  !> CSYS, id, CYLINDRICAL, x0, y0, z0, ax, ay, az [, rx, ry, rz]   or
  !! CSYS, id, CARTESIAN, x0, y0, z0 [, ax, ay, az, bx, by, bz]
  subroutine read_csys(rec, model, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: id, i
    real(dp) :: v(9), ref(3)
    type(coordinate_system_t) :: cs
    type(coordinate_system_t), allocatable :: tmp(:)
    character(len=:), allocatable :: kind

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    call get_int(rec, 2, -huge(1), huge(1), id, error)
    if (allocated(error)) return
    if (id /= size(model%systems) + 1) then
      call input_error(error, rec%file, field_line(rec, 2), 'coordinate systems are numbered in order: expected ' // &
                       str(size(model%systems) + 1) // ', got ' // str(id), 2)
      return
    end if
    kind = to_upper(field_text(rec, 3))
    select case (kind)
    case ('CYLINDRICAL')
      call require_fields(rec, 9, error)
      if (allocated(error)) return
      do i = 1, 6
        call get_real(rec, 3 + i, v(i), error)
        if (allocated(error)) return
      end do
      if (norm2(v(4:6)) == 0.0_dp) then
        call input_error(error, rec%file, field_line(rec, 7), 'the cylinder axis has zero length', 7)
        return
      end if
      ref = [1.0_dp, 0.0_dp, 0.0_dp]
      if (nfields(rec) > 9) then
        ! all three components or none: two would silently leave the default in place
        if (nfields(rec) < 12) then
          call input_error(error, rec%file, field_line(rec, nfields(rec) + 1), &
                           'the theta reference takes all three of rx, ry, rz ' // &
                           '(fields 10 to 12) or none; field ' // str(nfields(rec) + 1) // ' is missing', &
                           nfields(rec) + 1)
          return
        end if
        call forbid_extra_fields(rec, 12, error)
        if (allocated(error)) return
        do i = 1, 3
          call get_real(rec, 9 + i, ref(i), error)
          if (allocated(error)) return
        end do
        ! theta = 0 is the part of the reference normal to the axis: it must have one
        if (norm2(ref - dot_product(ref, v(4:6)) / dot_product(v(4:6), v(4:6)) * v(4:6)) <= &
            1.0e-9_dp * norm2(ref) .or. norm2(ref) == 0.0_dp) then
          call input_error(error, rec%file, field_line(rec, 10), &
                           'the theta reference (rx, ry, rz) is zero or parallel ' // &
                           'to the axis, so it gives no direction for theta = 0', 10)
          return
        end if
      else if (abs(v(4)) > 0.9_dp * norm2(v(4:6))) then
        ref = [0.0_dp, 1.0_dp, 0.0_dp]
      end if
      cs = cylindrical_about(v(1:3), v(4:6), ref)
    case ('CARTESIAN')
      call require_fields(rec, 6, error)
      if (allocated(error)) return
      call forbid_extra_fields(rec, 12, error)
      if (allocated(error)) return
      do i = 1, 3
        call get_real(rec, 3 + i, v(i), error)
        if (allocated(error)) return
      end do
      cs%kind = csys_cartesian
      cs%origin = v(1:3)
      if (nfields(rec) > 6) then
        ! a rotated system (Abaqus *TRANSFORM, TYPE=R): all six components or none
        if (nfields(rec) < 12) then
          call input_error(error, rec%file, field_line(rec, nfields(rec) + 1), &
                           'the axes take all six of ax, ay, az, bx, by, bz (fields 7 to 12) or none; field ' // &
                           str(nfields(rec) + 1) // ' is missing', nfields(rec) + 1)
          return
        end if
        do i = 1, 6
          call get_real(rec, 6 + i, v(3 + i), error)
          if (allocated(error)) return
        end do
        call cartesian_axes(rec, v(4:6), v(7:9), cs%axes, error)
        if (allocated(error)) return
      end if
    case default
      call input_error(error, rec%file, field_line(rec, 3), 'unknown coordinate system kind "' // kind // &
                       '" (CARTESIAN or CYLINDRICAL)', 3)
      return
    end select
    tmp = [model%systems, cs]
    call move_alloc(tmp, model%systems)
  end subroutine read_csys

  !> The axes of a rotated Cartesian system: x along `ax`, y the part of `bx` normal to it,
  !! z = x cross y; a zero `ax` names field 7, a zero `bx` or one parallel to `ax` field 10.
  subroutine cartesian_axes(rec, ax, bx, axes, error)
    type(record_t), intent(in) :: rec
    real(dp), intent(in) :: ax(3), bx(3)
    real(dp), intent(out) :: axes(3, 3)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: e1(3), e2(3)
    axes = 0.0_dp
    if (norm2(ax) == 0.0_dp) then
      call input_error(error, rec%file, field_line(rec, 7), 'the x axis (ax, ay, az) has zero length', 7)
      return
    end if
    e1 = ax / norm2(ax)
    e2 = bx - dot_product(bx, e1) * e1
    ! the same test as the cylindrical theta reference's
    if (norm2(bx) == 0.0_dp .or. norm2(e2) <= 1.0e-9_dp * norm2(bx)) then
      call input_error(error, rec%file, field_line(rec, 10), 'the x-y plane''s vector (bx, by, bz) is zero or ' // &
                       'parallel to the x axis, so it gives no y axis', 10)
      return
    end if
    e2 = e2 / norm2(e2)
    axes(:, 1) = e1
    axes(:, 2) = e2
    axes(:, 3) = [e1(2) * e2(3) - e1(3) * e2(2), e1(3) * e2(1) - e1(1) * e2(3), e1(1) * e2(2) - e1(2) * e2(1)]
  end subroutine cartesian_axes

  !> INCLUDE, file: a DATAIN file (blocks and the closing E), path relative to the deck.
  subroutine read_include(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    type(record_t), allocatable :: inc(:)
    character(len=:), allocatable :: path, key
    integer :: pos, nb_before, b
    logical :: closed

    call require_fields(rec, 2, error)
    if (allocated(error)) return
    path = resolve_path(rec%file, field_text(rec, 2))
    call read_records(path, inc, error)
    if (allocated(error)) then
      error%message = rec%file // ':' // str(rec%line) // ': INCLUDE: ' // error%message
      error%code = err_input
      return
    end if
    pos = 1
    closed = .false.
    do while (pos <= size(inc))
      key = keyword(inc(pos))
      if (closed) then
        call input_error(error, inc(pos)%file, inc(pos)%line, 'record after the closing E of the mesh', 1)
        return
      end if
      select case (key)
      case ('A')
        nb_before = size(st%mesh%blocks)
        call datain_read_block(inc, pos, model%systems, st%mesh, error)
        if (allocated(error)) return
        do b = nb_before + 1, size(st%mesh%blocks)
          st%block_group = [st%block_group, st%current_group]
        end do
      case ('E')
        closed = .true.
        pos = pos + 1
      case default
        call input_error(error, inc(pos)%file, inc(pos)%line, &
                         'an included DATAIN file holds only A, % and E records, not "' // key // '"', 1)
        return
      end select
    end do
    if (.not. closed) then
      call input_error(error, inc(size(inc))%file, inc(size(inc))%line, &
                       'truncated DATAIN file: the closing E record of the mesh is missing')
    end if
  end subroutine read_include

  !> NODE, id, c1, c2, c3 [, CSYS=n]: one node given explicitly.
  subroutine read_node(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    integer :: id, cs, i
    real(dp) :: c(3)
    call require_fields(rec, 5, error)
    if (allocated(error)) return
    call get_int(rec, 2, -huge(1), huge(1), id, error)
    if (allocated(error)) return
    if (id < 1) then
      call input_error(error, rec%file, field_line(rec, 2), 'node number ' // str(id) // ' must be positive', 2)
      return
    end if
    if (id > max_mesh_nodes) then
      call input_error(error, rec%file, field_line(rec, 2), &
                       'node number ' // str(id) // ' is larger than feps reads (' // &
                       str(max_mesh_nodes) // ')', 2)
      return
    end if
    do i = 1, 3
      call get_real(rec, 2 + i, c(i), error)
      if (allocated(error)) return
    end do
    call check_option_keys(rec, 6, error, allowed=['CSYS'], expected='CSYS=n after x, y, z')
    if (allocated(error)) return
    call get_csys_option(rec, model, 'CSYS', csys_cartesian, cs, error)
    if (allocated(error)) return
    if (any(st%explicit_ids(1:st%explicit_nodes) == id)) then
      call input_error(error, rec%file, field_line(rec, 2), 'duplicate node ' // str(id) // ' (defined before)', 2)
      return
    end if
    st%explicit_ids = [st%explicit_ids, id]
    st%explicit_line = [st%explicit_line, rec%line]
    st%explicit_field = [st%explicit_field, 2]
    st%explicit_file = rec%file
    st%explicit_coords = reshape([st%explicit_coords, model%systems(cs)%to_global(c)], &
                                 [3, st%explicit_nodes + 1])
    st%explicit_nodes = st%explicit_nodes + 1
  end subroutine read_node

  !> NODES [, CSYS=n] and its rows: nodes given explicitly, as NODE records are (a number
  !! given twice is found once all nodes are read, naming both lines).
  subroutine read_nodes(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: ids(:), lines(:), fields(:)
    real(dp), allocatable :: coords(:, :)
    call read_nodes_table(rec, model, ids, coords, lines, fields, error)
    if (allocated(error)) return
    st%explicit_field = [st%explicit_field, fields]
    st%explicit_ids = [st%explicit_ids, ids]
    st%explicit_line = [st%explicit_line, lines]
    st%explicit_file = rec%file
    st%explicit_coords = reshape([st%explicit_coords, coords], [3, st%explicit_nodes + size(ids)])
    st%explicit_nodes = st%explicit_nodes + size(ids)
  end subroutine read_nodes

  !> ELEMENTS, group and its rows: the group's elements, with their ids.
  subroutine read_elements(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    type(element_rows_t) :: rows
    type(element_rows_t), allocatable :: tmp(:)
    integer :: g
    call read_elements_table(rec, model, g, rows%ids, rows%connectivity, rows%id_field, error)
    if (allocated(error)) return
    if (size(model%groups(g)%blocks) > 0) then
      call input_error(error, rec%file, rec%line, 'group ' // model%groups(g)%name // ' takes DATAIN element ' // &
                       'blocks (BLOCKS=); its elements come from blocks or from ELEMENTS tables, not both', 2)
      return
    end if
    rows%group = g
    rows%rec = rec
    tmp = [st%element_tables, rows]
    call move_alloc(tmp, st%element_tables)
  end subroutine read_elements

  !> FORCE, LIST [, CSYS=n] and DISPLACE, LIST [, CSYS=n], then rows `node, dof, value` (Abaqus
  !! *CLOAD and *BOUNDARY): each row a force or a prescribed value on one node, in the stage of
  !! the record (a reference before any STAGE), adding up as the records on sets do. A row's
  !! node is a set of its own, not written to /sets (one a node, shared by all rows on it).
  subroutine read_listed_values(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    type(record_t) :: head
    type(node_set_t), allocatable :: new_sets(:)
    type(record_t), allocatable :: new_records(:)
    type(region_t), allocatable :: new_regions(:)
    type(nodal_load_t), allocatable :: loads(:)
    type(constraint_t), allocatable :: constraints(:)
    integer, allocatable :: nodes(:), dofs(:), set_of(:), new_fields(:)
    real(dp), allocatable :: values(:)
    integer :: first, cs, nrow, j, i, dof, nnew, iset
    logical :: force, total

    force = keyword(rec) == 'FORCE'
    first = first_row_field(rec)
    head%file = rec%file
    head%line = rec%line
    head%fields = rec%fields(1:first - 1)
    call check_option_keys(head, 3, error, allowed=['CSYS', 'MODE'], &
                           expected='CSYS=n or MODE= (the rows follow on lines of their own)')
    if (allocated(error)) return
    call get_csys_option(head, model, 'CSYS', csys_cartesian, cs, error)
    if (allocated(error)) return
    call read_mode(head, st%current_stage, total, error)
    if (allocated(error)) return
    nrow = (nfields(rec) - first + 1) / 3
    if (nfields(rec) < first) then
      call input_error(error, rec%file, rec%line, keyword(rec) // ', LIST has no row (rows "node, dof, value" ' // &
                       'follow on lines of their own)')
      return
    end if
    if (mod(nfields(rec) - first + 1, 3) /= 0) then
      call input_error(error, rec%file, field_line(rec, nfields(rec)), 'a ' // keyword(rec) // ' row is "node, ' // &
                       'dof, value": the last row is short of a field', nfields(rec) + 1)
      return
    end if
    ! Every row is read first and the model grows once per record: appending row by row
    ! copied the arrays each time, n^2 in the rows (minutes for the supports of an imported
    ! model).
    allocate (nodes(nrow), dofs(nrow), values(nrow))
    do j = 1, nrow
      i = first + 3 * (j - 1)
      call get_int(rec, i, 1, max_mesh_nodes, nodes(j), error, 'node number')
      if (allocated(error)) return
      call dof_index(to_upper(field_text(rec, i + 1)), model%systems(cs)%kind, dof)
      if (dof == 0) then
        call input_error(error, rec%file, field_line(rec, i + 1), 'unknown degree of freedom "' // &
                         field_text(rec, i + 1) // '" for this system (' // dof_names(model%systems(cs)%kind) // ')', &
                         i + 1)
        return
      end if
      dofs(j) = dof
      call get_real(rec, i + 2, values(j), error)
      if (allocated(error)) return
    end do
    ! each node's own one-node set ('LIST/node n': '/' is in no name a deck gives), shared by
    ! every LIST row on that node: the last such set of an earlier record, else a new one
    allocate (set_of(maxval(nodes)))
    set_of = 0
    do iset = 1, size(model%node_sets)
      associate (set => model%node_sets(iset))
        if (set%listed) then
          if (set%nodes(1) <= size(set_of)) set_of(set%nodes(1)) = iset
        end if
      end associate
    end do
    allocate (new_sets(nrow), new_records(nrow), new_regions(nrow), new_fields(nrow))
    nnew = 0
    iset = size(model%node_sets)
    do j = 1, nrow
      if (set_of(nodes(j)) /= 0) cycle
      i = first + 3 * (j - 1)
      nnew = nnew + 1
      set_of(nodes(j)) = iset + nnew
      new_sets(nnew)%name = 'LIST/node ' // str(nodes(j))
      new_sets(nnew)%nodes = [nodes(j)]
      new_sets(nnew)%listed = .true.
      new_fields(nnew) = i
      ! only what a message about this node needs: its keyword, and its field's line, which
      ! field_line gives for field i
      new_records(nnew)%file = rec%file
      new_records(nnew)%line = rec%line
      new_records(nnew)%fields = [rec%fields(1), rec%fields(i)]
    end do
    model%node_sets = [model%node_sets, new_sets(1:nnew)]
    st%set_group = [character(len=name_len) :: st%set_group, [(repeat(' ', name_len), j = 1, nnew)]]
    st%set_regions = [st%set_regions, new_regions(1:nnew)]
    st%set_node = [st%set_node, [(-2, j = 1, nnew)]]
    st%set_field = [st%set_field, new_fields(1:nnew)]
    st%set_records = [st%set_records, new_records(1:nnew)]
    if (force) then
      allocate (loads(nrow))
      do j = 1, nrow
        i = first + 3 * (j - 1)
        loads(j)%stage = st%current_stage
        loads(j)%file = rec%file
        loads(j)%line = field_line(rec, i)
        loads(j)%field = i
        loads(j)%node_set = set_of(nodes(j))
        loads(j)%csys = cs
        loads(j)%components = 0.0_dp
        loads(j)%components(dofs(j)) = values(j)
        loads(j)%given = .false.
        loads(j)%given(dofs(j)) = .true.
        loads(j)%total = total
      end do
      model%nodal_loads = [model%nodal_loads, loads]
    else
      allocate (constraints(nrow))
      do j = 1, nrow
        i = first + 3 * (j - 1)
        constraints(j)%node_set = set_of(nodes(j))
        constraints(j)%csys = cs
        constraints(j)%dof = dofs(j)
        constraints(j)%value = values(j)
        constraints(j)%stage = st%current_stage
        constraints(j)%prescribed = .true.
        constraints(j)%total = total
        constraints(j)%file = rec%file
        constraints(j)%line = field_line(rec, i)
      end do
      model%constraints = [model%constraints, constraints]
    end if
  end subroutine read_listed_values

  !> The rows `element, face` of FSET, name, LIST, GROUP=g: element ids as the group numbers
  !! them (finish_model maps them to the group's rows; the assembly checks the face numbers).
  subroutine read_face_rows(rec, s, error)
    type(record_t), intent(in) :: rec
    type(face_set_t), intent(inout) :: s
    type(error_t), allocatable, intent(out) :: error
    type(record_t) :: head
    integer :: first, nrow, j, i
    first = first_row_field(rec)
    head%file = rec%file
    head%line = rec%line
    head%fields = rec%fields(1:first - 1)
    call check_option_keys(head, 4, error, allowed=['GROUP'], expected='GROUP=g (the rows follow on lines of their own)')
    if (allocated(error)) return
    if (nfields(rec) < first) then
      call input_error(error, rec%file, rec%line, 'FSET, LIST has no row (rows "element, face" follow on lines ' // &
                       'of their own)')
      return
    end if
    if (mod(nfields(rec) - first + 1, 2) /= 0) then
      call input_error(error, rec%file, field_line(rec, nfields(rec)), 'an FSET row is "element, face": the ' // &
                       'last row is short of a field', nfields(rec) + 1)
      return
    end if
    nrow = (nfields(rec) - first + 1) / 2
    allocate (s%element(nrow), s%face(nrow), s%row_line(nrow), s%row_field(nrow))
    do j = 1, nrow
      i = first + 2 * (j - 1)
      call get_int(rec, i, 1, max_mesh_elements, s%element(j), error, 'element number')
      if (allocated(error)) return
      call get_int(rec, i + 1, 1, 1000, s%face(j), error, 'face number')
      if (allocated(error)) return
      s%row_line(j) = field_line(rec, i)
      s%row_field(j) = i + 1
    end do
    s%listed = .true.
  end subroutine read_face_rows

  !> The element ids of FSET LIST rows become rows of their group's connectivity: the ids of
  !! its ELEMENTS tables, or 1, 2, ... in the order of its DATAIN blocks.
  subroutine map_face_rows(model, error)
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: row_of(:)
    integer :: s, j, g, e, nel
    do s = 1, size(model%face_sets)
      associate (fs => model%face_sets(s))
        if (.not. fs%listed) cycle
        g = fs%group
        nel = size(model%groups(g)%connectivity, 2)
        if (allocated(model%groups(g)%element_ids)) then
          allocate (row_of(max(maxval(model%groups(g)%element_ids), maxval(fs%element))), source=0)
          do e = 1, nel
            row_of(model%groups(g)%element_ids(e)) = e
          end do
        else
          allocate (row_of(max(nel, maxval(fs%element))), source=0)
          row_of(1:nel) = [(e, e = 1, nel)]
        end if
        do j = 1, size(fs%element)
          if (row_of(fs%element(j)) == 0) then
            call input_error(error, fs%file, fs%row_line(j), 'face set ' // fs%name // ': group ' // &
                             model%groups(g)%name // ' has no element ' // str(fs%element(j)), fs%row_field(j) - 1)
            return
          end if
          fs%element(j) = row_of(fs%element(j))
        end do
        deallocate (row_of)
      end associate
    end do
  end subroutine map_face_rows

  !> MATERIAL, name, kind, KEY=value, ...
  subroutine read_material(rec, model, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    type(material_spec_t) :: m
    type(material_spec_t), allocatable :: tmp(:)
    integer :: i
    character(len=:), allocatable :: key, text, word
    real(dp) :: v

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    m%name = field_text(rec, 2)
    call check_result_name(rec, 'material', m%name, error)
    if (allocated(error)) return
    if (model%find_material(m%name) > 0) then
      call input_error(error, rec%file, field_line(rec, 2), 'material "' // m%name // '" is defined twice', 2)
      return
    end if
    m%kind = to_lower(field_text(rec, 3))
    m%kind_field = 3
    m%file = rec%file
    m%line = rec%line
    ! Field numbers kept with the keys, so the material checks can name the field at fault.
    allocate (m%keys(0), m%values(0), m%texts(0), m%fields(0))
    do i = 4, nfields(rec)
      call key_value(rec, i, 'KEY=value', key, text, error)
      if (allocated(error)) return
      key = to_lower(key)
      if (any(m%keys == key)) then
        call input_error(error, rec%file, field_line(rec, i), 'material ' // m%name // ': ' // to_upper(key) // &
                         ' is given twice (fields ' // str(m%fields(maxloc(merge(1, 0, m%keys == key), dim=1))) // ' and ' // &
                         str(i) // ')', i)
        return
      end if
      word = ''
      v = 0.0_dp
      if (any(key == text_material_keys)) then
        word = to_lower(text)   ! a word (the material checks it)
      else
        call parse_real(text, v, error, rec, i)
        if (allocated(error)) return
      end if
      m%keys = [character(len=name_len) :: m%keys, key]
      m%values = [m%values, v]
      m%texts = [character(len=name_len) :: m%texts, word]
      m%fields = [m%fields, i]
    end do
    tmp = [model%materials, m]
    call move_alloc(tmp, model%materials)
  end subroutine read_material

  !> GROUP, name, TYPE=hex8, MATERIAL=name [, BLOCKS=i or i:j]
  subroutine read_group(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    type(element_group_t) :: g
    type(element_group_t), allocatable :: tmp(:)
    character(len=:), allocatable :: text
    type(error_t), allocatable :: unknown
    integer :: ifield, lo, hi, b
    logical :: found

    call require_fields(rec, 2, error)
    if (allocated(error)) return
    g%name = field_text(rec, 2)
    call check_result_name(rec, 'group', g%name, error)
    if (allocated(error)) return
    if (model%find_group(g%name) > 0) then
      call input_error(error, rec%file, field_line(rec, 2), 'group "' // g%name // '" is defined twice', 2)
      return
    end if
    call check_option_keys(rec, 3, error, allowed=[character(len=8) :: 'TYPE', 'MATERIAL', 'BLOCKS'])
    if (allocated(error)) return
    call option_text(rec, 'TYPE', text, ifield, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'GROUP needs TYPE=<element type>')
      return
    end if
    call element_info(text, g%element, unknown)
    if (allocated(unknown)) then
      call input_error(error, rec%file, field_line(rec, ifield), 'unknown element type "' // text // '" (solids: ' // &
                       known_element_types(family_solid) // '; interfaces: ' // &
                       known_element_types(family_interface) // '; bars: ' // known_element_types(family_bar) // &
                       '; of them 2D (plane strain): ' // known_element_types(dimension=2) // ')', ifield)
      return
    end if
    g%element_type = g%element%name
    call option_text(rec, 'MATERIAL', text, ifield, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'GROUP needs MATERIAL=<name>')
      return
    end if
    g%material_name = text
    g%material_field = ifield
    g%file = rec%file
    g%line = rec%line
    allocate (g%blocks(0))
    call option_text(rec, 'BLOCKS', text, ifield, found)
    tmp = [model%groups, g]
    call move_alloc(tmp, model%groups)
    if (found) then
      call parse_range_int(text, -huge(1), max_mesh_elements, lo, hi, error, rec, ifield)
      if (allocated(error)) return
      if (lo < 1 .or. hi < lo) then
        call input_error(error, rec%file, field_line(rec, ifield), &
                         'BLOCKS range "' // text // '" is empty or not positive', &
                         ifield)
        return
      end if
      model%groups(size(model%groups))%blocks = [(b, b = lo, hi)]
      st%current_group = 0
    else
      st%current_group = size(model%groups)
    end if
  end subroutine read_group

  !> NSET, name, [CSYS=n,] <coordinate>=a[:b] ..., [TOL=t]   or   NSET, name, NODE=n   or
  !! NSET, name, LIST and lines of node ids (ranges a:b allowed)
  subroutine read_nset(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    type(node_set_t) :: s
    type(node_set_t), allocatable :: tmp(:)
    type(record_t), allocatable :: rtmp(:)
    type(region_t) :: r
    character(len=:), allocatable :: text
    integer :: ifield, node
    integer, allocatable :: fields(:)
    logical :: found

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    s%name = field_text(rec, 2)
    call check_result_name(rec, 'node set', s%name, error)
    if (allocated(error)) return
    if (model%find_node_set(s%name) > 0) then
      call input_error(error, rec%file, field_line(rec, 2), 'node set "' // s%name // '" is defined twice', 2)
      return
    end if
    node = 0
    call option_text(rec, 'NODE', text, ifield, found)
    if (to_upper(field_text(rec, 3)) == 'LIST') then
      ! the ids are checked against the nodes once all are read (resolve_node_sets)
      if (first_row_field(rec) /= 4) then
        call input_error(error, rec%file, rec%line, 'NSET, name, LIST takes no option; its ids follow on ' // &
                         'lines of their own', 4)
        return
      end if
      call read_id_list(rec, 4, max_mesh_nodes, s%nodes, fields, error)
      if (allocated(error)) return
      if (size(s%nodes) == 0) then
        call input_error(error, rec%file, rec%line, 'node set ' // s%name // ' lists no node')
        return
      end if
      node = -1
    else if (found) then
      if (nfields(rec) > 3) then
        call input_error(error, rec%file, field_line(rec, merge(4, 3, ifield == 3)), &
                         'NODE= selects one node and takes no other option', &
                         merge(4, 3, ifield == 3))
        return
      end if
      call parse_int(text, -huge(1), huge(1), node, error, rec, ifield)
      if (allocated(error)) return
      if (node < 1) then
        call input_error(error, rec%file, field_line(rec, ifield), &
                         'node number ' // str(node) // ' must be positive', ifield)
        return
      end if
    else
      call read_region(rec, model, r, error)
      if (allocated(error)) return
    end if
    if (.not. allocated(s%nodes)) allocate (s%nodes(0))
    tmp = [model%node_sets, s]
    call move_alloc(tmp, model%node_sets)
    call option_text(rec, 'GROUP', text, ifield, found)
    if (.not. found) text = ''
    st%set_group = [character(len=name_len) :: st%set_group, text]
    st%set_regions = [st%set_regions, r]
    st%set_node = [st%set_node, node]
    st%set_field = [st%set_field, 0]
    rtmp = [st%set_records, rec]
    call move_alloc(rtmp, st%set_records)
  end subroutine read_nset

  !> FSET, name, GROUP=g, [CSYS=n,] <coordinate>=a[:b] ..., [TOL=t]
  subroutine read_fset(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(in) :: st
    type(error_t), allocatable, intent(out) :: error
    type(face_set_t) :: s
    type(face_set_t), allocatable :: tmp(:)
    character(len=:), allocatable :: text, elset
    integer :: ifield, efield, k, face
    logical :: found, by_elset

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    s%name = field_text(rec, 2)
    call check_result_name(rec, 'face set', s%name, error)
    if (allocated(error)) return
    if (model%find_face_set(s%name) > 0) then
      call input_error(error, rec%file, field_line(rec, 2), 'face set "' // s%name // '" is defined twice', 2)
      return
    end if
    call option_text(rec, 'ELSET', elset, efield, by_elset)
    call option_text(rec, 'GROUP', text, ifield, found)
    if (by_elset) then
      ! FSET, name, ELSET=e, FACE=k: face k of every element of the set (Abaqus *SURFACE's
      ! "elset, Sk"); the group is the set's
      call check_option_keys(rec, 3, error, allowed=[character(len=5) :: 'ELSET', 'FACE', 'GROUP'])
      if (allocated(error)) return
      k = 0
      if (allocated(st%element_sets)) then
        do k = size(st%element_sets), 1, -1
          if (st%element_sets(k)%name == elset) exit
        end do
      end if
      if (k == 0) then
        call input_error(error, rec%file, field_line(rec, efield), 'undefined element set "' // elset // &
                         '" (an ELSET record before this one defines it)', efield)
        return
      end if
      if (found .and. text /= st%element_sets(k)%group) then
        call input_error(error, rec%file, field_line(rec, ifield), 'GROUP=' // text // ': element set ' // &
                         elset // ' is of group ' // st%element_sets(k)%group, ifield)
        return
      end if
      text = st%element_sets(k)%group
      ifield = efield
      call option_face(rec, face, error)
      if (allocated(error)) return
      associate (es => st%element_sets(k))
        s%element = es%ids
        s%face = [(face, k = 1, size(es%ids))]
        s%row_line = es%lines
        s%row_field = es%fields + 1        ! map_face_rows names field - 1: the element's
      end associate
      s%listed = .true.
    else if (.not. found) then
      call input_error(error, rec%file, rec%line, 'FSET needs GROUP=<element group> (or ELSET=<element set>)')
      return
    end if
    if (.not. by_elset .and. to_upper(field_text(rec, 3)) == 'LIST') then
      call read_face_rows(rec, s, error)
      if (allocated(error)) return
    end if
    s%group = model%find_group(text)
    if (s%group == 0) then
      call input_error(error, rec%file, field_line(rec, ifield), 'undefined element group "' // text // '"', ifield)
      return
    end if
    if (model%groups(s%group)%element%family == family_interface) then
      call input_error(error, rec%file, field_line(rec, ifield), &
                       'face sets take faces of solid elements; group "' // text // &
                       '" holds interface elements', ifield)
      return
    end if
    if (.not. s%listed) then
      call read_region(rec, model, s%region, error)
      if (allocated(error)) return
      allocate (s%element(0), s%face(0))
    end if
    s%file = rec%file
    s%line = rec%line
    tmp = [model%face_sets, s]
    call move_alloc(tmp, model%face_sets)
  end subroutine read_fset

  !> FACE=k of an FSET ELSET= record: the face number, 1 to 6 (the element catalog's, which are
  !! CalculiX's and Abaqus's; a face the element type lacks is refused when the faces are made).
  subroutine option_face(rec, face, error)
    type(record_t), intent(in) :: rec
    integer, intent(out) :: face
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: ifield
    logical :: found
    face = 0
    call option_text(rec, 'FACE', text, ifield, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'FSET, ELSET= needs FACE=<face number>')
      return
    end if
    call parse_int(text, 1, 6, face, error, rec, ifield, 'face number')
  end subroutine option_face

  !> ELSET, name, LIST, GROUP=g, then lines of element ids (several a line, `a:b` ranges), as
  !! the group's ELEMENTS tables number its elements (1, 2, ... in the order of its DATAIN
  !! blocks): for FSET, name, ELSET=, FACE=. The ids are checked against the group when the
  !! face set is made.
  subroutine read_elset(rec, st, error)
    type(record_t), intent(in) :: rec
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    type(record_t) :: head
    type(element_set_t) :: es
    type(element_set_t), allocatable :: tmp(:)
    character(len=:), allocatable :: text
    integer :: first, ifield, k
    logical :: found
    call require_fields(rec, 3, error)
    if (allocated(error)) return
    es%name = field_text(rec, 2)
    call check_result_name(rec, 'element set', es%name, error)
    if (allocated(error)) return
    if (allocated(st%element_sets)) then
      if (any([(st%element_sets(k)%name == es%name, k = 1, size(st%element_sets))])) then
        call input_error(error, rec%file, field_line(rec, 2), 'element set "' // es%name // '" is defined twice', 2)
        return
      end if
    end if
    if (to_upper(field_text(rec, 3)) /= 'LIST') then
      call input_error(error, rec%file, field_line(rec, 3), 'ELSET takes LIST, GROUP=g and lines of element ' // &
                       'numbers, not "' // field_text(rec, 3) // '"', 3)
      return
    end if
    first = first_row_field(rec)
    head%file = rec%file
    head%line = rec%line
    head%fields = rec%fields(1:first - 1)
    call check_option_keys(head, 4, error, allowed=['GROUP'], expected='GROUP=g (the element numbers follow on ' // &
                           'lines of their own)')
    if (allocated(error)) return
    call option_text(head, 'GROUP', text, ifield, found)
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'ELSET needs GROUP=<element group> (element numbers are a group''s)')
      return
    end if
    es%group = text
    if (nfields(rec) < first) then
      call input_error(error, rec%file, rec%line, 'ELSET, LIST has no element number (they follow on lines of ' // &
                       'their own)')
      return
    end if
    call read_id_list(rec, first, max_mesh_elements, es%ids, es%fields, error)
    if (allocated(error)) return
    es%lines = [(field_line(rec, es%fields(k)), k = 1, size(es%fields))]
    if (.not. allocated(st%element_sets)) allocate (st%element_sets(0))
    tmp = [st%element_sets, es]
    call move_alloc(tmp, st%element_sets)
  end subroutine read_elset

  subroutine read_solver(rec, model, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    call forbid_extra_fields(rec, 2, error)
    if (allocated(error)) return
    model%solver = to_lower(field_text(rec, 2))
    if (model%solver /= 'cholmod' .and. model%solver /= 'skyline') then
      call input_error(error, rec%file, field_line(rec, 2), 'unknown solver "' // field_text(rec, 2) // &
                       '" (skyline or cholmod)', 2)
    end if
  end subroutine read_solver

  !> OUTPUT, file.h5: the results file, relative to the working directory; given once.
  subroutine read_output(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    if (st%output_line > 0) then
      call input_error(error, rec%file, field_line(rec, 1), 'OUTPUT is given twice (first at line ' // &
                       str(st%output_line) // ')', 1)
      return
    end if
    st%output_line = rec%line
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    call forbid_extra_fields(rec, 2, error)
    if (allocated(error)) return
    model%output_file = field_text(rec, 2)
    if (is_xdmf_name(model%output_file)) &
      call input_error(error, rec%file, field_line(rec, 2), 'results file "' // &
                       model%output_file // '" must not end in .xmf (the XDMF file beside it takes that name)', 2)
  end subroutine read_output

  !> RESTART, EVERY=n: write restart data (the checkpoint file beside the results) every n
  !! steps, counted over all stages, so that a run that dies can be continued (feps --restart).
  subroutine read_restart(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: key, value
    if (st%restart_line > 0) then
      call input_error(error, rec%file, field_line(rec, 1), 'RESTART is given twice (first at line ' // &
                       str(st%restart_line) // ')', 1)
      return
    end if
    st%restart_line = rec%line
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    call forbid_extra_fields(rec, 2, error)
    if (allocated(error)) return
    call key_value(rec, 2, 'EVERY=n', key, value, error)
    if (allocated(error)) return
    if (key /= 'EVERY') then
      call input_error(error, rec%file, field_line(rec, 2), 'unknown RESTART option "' // field_text(rec, 2) // &
                       '" (RESTART takes EVERY=n: restart data every n steps)', 2)
      return
    end if
    call parse_int(value, 1, max_total_steps, model%restart_every, error, rec, 2, 'EVERY')
  end subroutine read_restart

  !> FIELDS, name [, name ...] [, CSYS=n]: write only the named result fields (several records
  !! add up); CSYS names the cylindrical system of stress_cyl (default 3, about the global z).
  subroutine read_fields(rec, model, st, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    integer :: i
    logical :: known, csys_given
    character(len=:), allocatable :: key, value
    csys_given = .false.
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    if (.not. st%fields_given) then
      call model%fields%clear()
      st%fields_given = .true.
    end if
    do i = 2, nfields(rec)
      if (index(field_text(rec, i), '=') > 0) then    ! CSYS=n: the frame of stress_cyl
        call key_value(rec, i, 'CSYS=n', key, value, error)
        if (allocated(error)) return
        if (key /= 'CSYS') then
          call input_error(error, rec%file, field_line(rec, i), 'unknown FIELDS option "' // field_text(rec, i) // &
                           '" (FIELDS takes field names, and CSYS=n for stress_cyl)', i)
          return
        else if (csys_given) then
          call input_error(error, rec%file, field_line(rec, i), 'CSYS is given twice', i)
          return
        end if
        csys_given = .true.
        call get_csys_option(rec, model, 'CSYS', 3, model%fields%csys, error)
        if (allocated(error)) return
        if (model%systems(model%fields%csys)%kind /= csys_cylindrical) then
          call input_error(error, rec%file, field_line(rec, i), 'CSYS=' // str(model%fields%csys) // ' is not a ' // &
                           'cylindrical system (stress_cyl takes the radial, hoop and axial directions of one)', i)
          return
        end if
        cycle
      end if
      call model%fields%select(to_lower(field_text(rec, i)), known)
      if (.not. known) then
        call input_error(error, rec%file, field_line(rec, i), 'unknown field "' // field_text(rec, i) // '" (' // &
                         known_fields() // ')', i)
        return
      end if
    end do
  end subroutine read_fields

  ! ---------------------------------------------------------------------------------------
  ! After the last record: nodes, groups, node sets
  ! ---------------------------------------------------------------------------------------

  subroutine finish_model(path, model, st, error)
    character(len=*), intent(in) :: path
    type(model_t), intent(inout) :: model
    type(deck_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: defined(:)
    integer, allocatable :: node_line(:)
    type(error_t), allocatable :: unknown
    class(material_t), allocatable :: material
    integer :: nnode, i, g, b, nel, k, first, m, ntab, t

    ! Nodes: DATAIN blocks first, explicit NODE records at their numbers.
    nnode = st%mesh%nnode
    if (st%explicit_nodes > 0) nnode = max(nnode, maxval(st%explicit_ids))
    ! a gap in the numbering is no node, at the origin (never read as garbage)
    allocate (model%coords(3, nnode), source=0.0_dp)
    allocate (defined(nnode), source=.false.)
    model%coords(:, 1:st%mesh%nnode) = st%mesh%coords(:, 1:st%mesh%nnode)
    defined(1:st%mesh%nnode) = .true.
    allocate (node_line(nnode), source=0)
    do i = 1, st%explicit_nodes
      if (node_line(st%explicit_ids(i)) > 0) then
        call input_error(error, st%explicit_file, st%explicit_line(i), 'duplicate node ' // &
                         str(st%explicit_ids(i)) // ' (defined before, at line ' // &
                         str(node_line(st%explicit_ids(i))) // ')', st%explicit_field(i))
        return
      end if
      if (defined(st%explicit_ids(i))) then
        call input_error(error, st%explicit_file, st%explicit_line(i), 'duplicate node ' // &
                         str(st%explicit_ids(i)) // ' (already generated by a DATAIN block)', st%explicit_field(i))
        return
      end if
      model%coords(:, st%explicit_ids(i)) = st%explicit_coords(:, i)
      defined(st%explicit_ids(i)) = .true.
      node_line(st%explicit_ids(i)) = st%explicit_line(i)
    end do
    model%nnode = nnode
    if (nnode == 0) then
      call input_error(error, path, 1, 'the model has no nodes')
      return
    end if
    st%mesh%nnode = nnode
    call datain_check(st%mesh, error)
    if (allocated(error)) return

    if (model%mesh_only) then
      ! A bare DATAIN mesh: one group per element block, typed by its node count.
      deallocate (model%groups)
      allocate (model%groups(size(st%mesh%blocks)))
      do b = 1, size(st%mesh%blocks)
        model%groups(b)%name = 'block' // str(b)
        model%groups(b)%element_type = bare_mesh_type(st%mesh%blocks(b)%nodes_per_element)
        if (len(model%groups(b)%element_type) > 0) then
          call element_info(model%groups(b)%element_type, model%groups(b)%element, unknown)
        else
          model%groups(b)%element_type = 'nodes' // str(st%mesh%blocks(b)%nodes_per_element)
        end if
        model%groups(b)%material_name = ''
        model%groups(b)%connectivity = st%mesh%blocks(b)%connectivity
        model%groups(b)%blocks = [b]
        model%groups(b)%file = st%mesh%blocks(b)%file
        model%groups(b)%line = st%mesh%blocks(b)%line
      end do
    else
      ! Blocks to groups: explicit BLOCKS= lists, else the group that preceded them.
      do g = 1, size(model%groups)
        do k = 1, size(model%groups(g)%blocks)
          b = model%groups(g)%blocks(k)
          if (b > size(st%mesh%blocks)) then
            call input_error(error, model%groups(g)%file, model%groups(g)%line, 'group ' // model%groups(g)%name &
                             // ' names element block ' // str(b) // ' but the mesh has ' // &
                             str(size(st%mesh%blocks)) // ' blocks')
            return
          end if
          if (st%block_group(b) /= 0 .and. st%block_group(b) /= g) then
            call input_error(error, model%groups(g)%file, model%groups(g)%line, 'element block ' // str(b) // &
                             ' already belongs to group ' // model%groups(st%block_group(b))%name)
            return
          end if
          st%block_group(b) = g
        end do
      end do
      do b = 1, size(st%mesh%blocks)
        if (st%block_group(b) == 0) then
          call input_error(error, st%mesh%blocks(b)%file, st%mesh%blocks(b)%line, 'element block ' // str(b) // &
                           ' belongs to no GROUP (give GROUP before it or BLOCKS= in a GROUP)')
          return
        end if
      end do
      do g = 1, size(model%groups)
        model%groups(g)%blocks = pack([(b, b = 1, size(st%mesh%blocks))], st%block_group == g)
        nel = 0
        do k = 1, size(model%groups(g)%blocks)
          b = model%groups(g)%blocks(k)
          nel = nel + size(st%mesh%blocks(b)%connectivity, 2)
          if (st%mesh%blocks(b)%nodes_per_element /= model%groups(g)%element%nnodes) then
            call input_error(error, st%mesh%blocks(b)%file, st%mesh%blocks(b)%line, 'element block ' // str(b) &
                             // ' has ' // str(st%mesh%blocks(b)%nodes_per_element) // ' nodes per element, but ' &
                             // 'group ' // model%groups(g)%name // ' is ' // model%groups(g)%element_type // &
                             ' (' // str(model%groups(g)%element%nnodes) // ' nodes)')
            return
          end if
        end do
        ntab = 0
        do t = 1, size(st%element_tables)
          if (st%element_tables(t)%group == g) ntab = ntab + size(st%element_tables(t)%ids)
        end do
        if (nel > 0 .and. ntab > 0) then
          call input_error(error, model%groups(g)%file, model%groups(g)%line, 'group ' // model%groups(g)%name // &
                           ' takes DATAIN element blocks and ELEMENTS rows; its elements come from one or the other')
          return
        end if
        if (nel == 0 .and. ntab == 0) then
          call input_error(error, model%groups(g)%file, model%groups(g)%line, 'group ' // model%groups(g)%name // &
                           ' has no elements')
          return
        end if
        if (ntab > 0) then
          call gather_element_tables(st%element_tables, g, model%groups(g))
        else
          allocate (model%groups(g)%connectivity(model%groups(g)%element%nnodes, nel))
          first = 0
          do k = 1, size(model%groups(g)%blocks)
            b = model%groups(g)%blocks(k)
            nel = size(st%mesh%blocks(b)%connectivity, 2)
            model%groups(g)%connectivity(:, first + 1:first + nel) = st%mesh%blocks(b)%connectivity
            first = first + nel
          end do
        end if
        model%groups(g)%material = model%find_material(model%groups(g)%material_name)
        if (model%groups(g)%material == 0) then
          call input_error(error, model%groups(g)%file, model%groups(g)%line, 'undefined material "' // &
                           model%groups(g)%material_name // '"', model%groups(g)%material_field)
          return
        end if
        if (material_family(model%materials(model%groups(g)%material)%kind) /= model%groups(g)%element%family) then
          call input_error(error, model%groups(g)%file, model%groups(g)%line, 'group ' // model%groups(g)%name // &
                           ' (' // model%groups(g)%element_type // ') cannot use material ' // &
                           model%groups(g)%material_name // ' (' // model%materials(model%groups(g)%material)%kind // &
                           '): interface elements take INTERFACE materials, bars BAR, solids ELASTIC, MATSUOKA or CONCRETE')
          return
        end if
      end do
      ! Every material's parameters are parsed into its typed record and checked as its object
      ! is built, now, before anything is written; the record is kept for the analysis.
      do m = 1, size(model%materials)
        call new_material(model%materials(m), material, error)
        if (allocated(error)) return
        call note_unit_warning(model, model%materials(m), material)
        call move_alloc(material, model%materials(m)%params)
      end do
      call check_element_tables(st%element_tables, model, defined, error)
      if (allocated(error)) return
      do g = 1, size(model%groups)
        do k = 1, size(model%groups(g)%connectivity, 2)
          do i = 1, size(model%groups(g)%connectivity, 1)
            if (.not. defined(model%groups(g)%connectivity(i, k))) then
              call input_error(error, model%groups(g)%file, model%groups(g)%line, 'element ' // str(k) // &
                               ' of group ' // model%groups(g)%name // ' uses node ' // &
                               str(model%groups(g)%connectivity(i, k)) // ', which is not defined')
              return
            end if
          end do
        end do
      end do
    end if
    if (size(model%groups) == 0) then
      call input_error(error, path, 1, 'the model has no elements')
      return
    end if
    ! A model is plane strain when its groups are 2D types; 2D and 3D do not mix.
    model%plane_strain = model%groups(1)%element%dimension == 2
    do g = 2, size(model%groups)
      if ((model%groups(g)%element%dimension == 2) .neqv. model%plane_strain) then
        call input_error(error, model%groups(g)%file, model%groups(g)%line, 'group ' // model%groups(g)%name // &
                         ' (' // model%groups(g)%element_type // ') mixes 2D (plane strain) and 3D element types')
        return
      end if
    end do
    call resolve_node_sets(model, defined, st%set_regions, st%set_node, st%set_records, error, st%set_group, &
                           st%set_field)
    if (allocated(error)) return
    call map_face_rows(model, error)
    if (allocated(error)) return
    call check_loaded_nodes(model, error)
    if (allocated(error)) return
    call finish_stages(model)
    call check_line_search(model, error)
    if (allocated(error)) return
    call resolve_activations(model, error)
    if (.not. allocated(error)) call resolve_prestresses(model, error)
    if (.not. allocated(error)) call check_geostatic(model, error)
  end subroutine finish_model

  !> A GEOSTATIC stage needs gravity acting in it: the in-situ stress is the weight's, and the
  !! stage applies that weight while the stress is set, so the two stay in balance.
  subroutine check_geostatic(model, error)
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    if (model%geostatic_stage == 0) return
    if (model%gravity_stage /= model%geostatic_stage) &
      call input_error(error, model%geostatic_file, model%geostatic_line, 'GEOSTATIC needs GRAVITY in ' // &
                       'the same stage (the in-situ stress is the weight of the ground, applied with it)', 1)
  end subroutine check_geostatic

  !> A group's elements from its ELEMENTS tables, in reading order, with their ids.
  subroutine gather_element_tables(tables, g, group)
    type(element_rows_t), intent(in) :: tables(:)
    integer, intent(in) :: g
    type(element_group_t), intent(inout) :: group
    integer :: t, n, first
    n = 0
    do t = 1, size(tables)
      if (tables(t)%group == g) n = n + size(tables(t)%ids)
    end do
    allocate (group%connectivity(group%element%nnodes, n), group%element_ids(n))
    first = 0
    do t = 1, size(tables)
      if (tables(t)%group /= g) cycle
      n = size(tables(t)%ids)
      group%connectivity(:, first + 1:first + n) = tables(t)%connectivity
      group%element_ids(first + 1:first + n) = tables(t)%ids
      first = first + n
    end do
  end subroutine gather_element_tables

  !> Every node of an ELEMENTS row must be defined (the error names its line and field), and
  !! an element id is given once over all tables.
  subroutine check_element_tables(tables, model, defined, error)
    type(element_rows_t), intent(in) :: tables(:)
    type(model_t), intent(in) :: model
    logical, intent(in) :: defined(:)
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: first_line(:)
    integer :: t, j, i, node, id, f
    id = 0
    do t = 1, size(tables)
      if (size(tables(t)%ids) > 0) id = max(id, maxval(tables(t)%ids))
    end do
    allocate (first_line(id), source=0)
    do t = 1, size(tables)
      associate (rec => tables(t)%rec)
        do j = 1, size(tables(t)%ids)
          id = tables(t)%ids(j)
          f = tables(t)%id_field(j)
          if (first_line(id) > 0) then
            call input_error(error, rec%file, field_line(rec, f), 'duplicate element ' // str(id) // &
                             ' (defined before, at line ' // str(first_line(id)) // ')', f)
            return
          end if
          first_line(id) = field_line(rec, f)
          do i = 1, size(tables(t)%connectivity, 1)
            node = tables(t)%connectivity(i, j)
            if (node > size(defined)) then
              call input_error(error, rec%file, field_line(rec, f + i), 'element ' // str(id) // ' of group ' // &
                               model%groups(tables(t)%group)%name // ' uses node ' // str(node) // &
                               ', which is not defined', f + i)
              return
            end if
            if (.not. defined(node)) then
              call input_error(error, rec%file, field_line(rec, f + i), 'element ' // str(id) // ' of group ' // &
                               model%groups(tables(t)%group)%name // ' uses node ' // str(node) // &
                               ', which is not defined', f + i)
              return
            end if
          end do
        end do
      end associate
    end do
  end subroutine check_element_tables

  !> The ids of an NSET LIST must be defined nodes (the error names the field of the first
  !! that is not); a node listed twice is kept once.
  subroutine check_listed_nodes(set, rec, defined, error)
    type(node_set_t), intent(inout) :: set
    type(record_t), intent(in) :: rec
    logical, intent(in) :: defined(:)
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: ids(:), fields(:)
    logical, allocatable :: seen(:)
    integer :: i
    call read_id_list(rec, 4, max_mesh_nodes, ids, fields, error)
    if (allocated(error)) return
    allocate (seen(size(defined)), source=.false.)
    do i = 1, size(ids)
      if (ids(i) > size(defined)) then
        call input_error(error, rec%file, field_line(rec, fields(i)), 'node set ' // set%name // ': node ' // &
                         str(ids(i)) // ' is not defined', fields(i))
        return
      end if
      if (.not. defined(ids(i))) then
        call input_error(error, rec%file, field_line(rec, fields(i)), 'node set ' // set%name // ': node ' // &
                         str(ids(i)) // ' is not defined', fields(i))
        return
      end if
      seen(ids(i)) = .true.
    end do
    set%nodes = pack([(i, i = 1, size(defined))], seen)
  end subroutine check_listed_nodes

  !> STRESS= values become forces (times the bar material's area A). A post-tensioned
  !! (BOND=after) group is born at the start of the stage after its record's, which must exist.
  !! Every stage a bonded prestress acts in must have the group's elements: a prestress before
  !! its group is born (ACTIVATE) would have nothing to act on.
  subroutine resolve_prestresses(model, error)
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: i, s, born
    real(dp) :: area
    class(material_t), allocatable :: material
    do i = 1, size(model%prestresses)
      if (.not. model%prestresses(i)%bond_after) cycle
      associate (p => model%prestresses(i), g => model%groups(model%prestresses(i)%group))
        if (p%stage == 0 .or. p%stage == size(model%stages)) then
          call input_error(error, p%file, p%line, 'PRESTRESS with BOND=AFTER tensions group "' // g%name // &
                           '" in a stage and bonds it at the start of the next: it belongs after a STAGE ' // &
                           'record that another STAGE follows', p%bond_field)
          return
        end if
        if (g%activate_stage /= 0 .and. g%activate_stage /= p%stage + 1) then
          call input_error(error, p%file, p%line, 'PRESTRESS with BOND=AFTER bonds group "' // g%name // &
                           '" at the start of stage ' // model%stages(p%stage + 1)%name // ', but it is ' // &
                           'born in stage ' // model%stages(max(1, g%activate_stage))%name // ' (ACTIVATE or ' // &
                           'another BOND=AFTER)', p%bond_field)
          return
        end if
        g%activate_stage = p%stage + 1
      end associate
    end do
    do i = 1, size(model%prestresses)
      associate (p => model%prestresses(i), g => model%groups(model%prestresses(i)%group))
        if (p%per_area) then
          ! the area the bar material declares (its checked record: A is there, positive)
          call material_of(model%materials(g%material), material, error)
          if (allocated(error)) return
          area = material%section_area()
          if (area > 0.0_dp) then
            ! tested before the product, which would overflow (and trap under -ffpe-trap); an
            ! |A| below 1 cannot make it overflow, and huge / |A| would
            if (abs(p%force) > huge(1.0_dp) / max(1.0_dp, abs(area))) then
              call input_error(error, p%file, p%line, 'PRESTRESS of group "' // g%name // '": STRESS times ' // &
                               'the area A of material ' // g%material_name // ' overflows', 3)
              return
            end if
            p%force = p%force * area
          end if
          p%per_area = .false.
        end if
        if (p%bond_after) cycle
        born = max(1, g%activate_stage)
        do s = 1, born - 1
          if (p%stage == s .or. (p%stage == 0 .and. model%stages(s)%load_fraction /= 0.0_dp)) then
            call input_error(error, p%file, p%line, 'PRESTRESS of group "' // g%name // '" acts in stage ' // &
                             model%stages(s)%name // ', before the group is born (in stage ' // &
                             model%stages(born)%name // ': ACTIVATE or BOND=AFTER)', 2)
            return
          end if
        end do
      end associate
    end do
  end subroutine resolve_prestresses

  !> Each group named by a stage's ACTIVATE is born in that stage: it must exist and be
  !! activated once only.
  subroutine resolve_activations(model, error)
    type(model_t), intent(inout) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: s, i, g
    do s = 1, size(model%stages)
      if (.not. allocated(model%stages(s)%activate)) cycle
      associate (stg => model%stages(s))
        do i = 1, size(stg%activate)
          g = model%find_group(trim(stg%activate(i)))
          if (g == 0) then
            call input_error(error, stg%file, stg%line, 'ACTIVATE: undefined element group "' // &
                             trim(stg%activate(i)) // '"', stg%activate_field(i))
            return
          end if
          if (model%groups(g)%activate_stage /= 0) then
            call input_error(error, stg%file, stg%line, 'ACTIVATE: group "' // trim(stg%activate(i)) // &
                             '" is activated twice (already in stage ' // &
                             model%stages(model%groups(g)%activate_stage)%name // ')', stg%activate_field(i))
            return
          end if
          model%groups(g)%activate_stage = s
        end do
      end associate
    end do
  end subroutine resolve_activations

  !> Without STAGE records the deck is one stage of one step applying everything; with them,
  !! LOAD= defaults to 1 for a single stage and 0 otherwise. Method presets fix the iteration
  !! limits the thesis gives them (2.6.3).
  subroutine finish_stages(model)
    type(model_t), intent(inout) :: model
    integer :: s
    if (size(model%stages) == 0) then
      deallocate (model%stages)
      allocate (model%stages(1))
      model%stages(1)%name = 'stage1'
      model%stages(1)%steps = 1
      model%stages(1)%load_fraction = 1.0_dp
      model%stages(1)%controls = model%controls
      model%stages(1)%file = model%deck_file
      model%stages(1)%line = 0
    end if
    do s = 1, size(model%stages)
      if (.not. model%stages(s)%load_given) model%stages(s)%load_fraction = &
        merge(1.0_dp, 0.0_dp, size(model%stages) == 1)
      associate (c => model%stages(s)%controls)
        select case (c%method)
        case (method_euler, method_modified_euler)
          c%max_iterations = 1
        case (method_newton_raphson, method_full_newton_raphson)
          if (.not. c%max_iterations_set) c%max_iterations = 50
        end select
      end associate
    end do
  end subroutine finish_stages

  !> LINESEARCH=energy where a stage's method cannot take it (feps_model's line_search_refusal):
  !! an input error naming the record and field that asked for it (CONTROLS or STAGE) and the stage.
  subroutine check_line_search(model, error)
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: s
    character(len=:), allocatable :: why
    do s = 1, size(model%stages)
      associate (c => model%stages(s)%controls)
        why = line_search_refusal(c)
        if (len(why) == 0) cycle
        call input_error(error, c%line_search_file, c%line_search_line, why // ' (stage ' // &
                         model%stages(s)%name // ')', c%line_search_field)
        return
      end associate
    end do
  end subroutine check_line_search

  !> A FORCE on a node that belongs to no element would act on nothing (its DOFs are not in the
  !! system) and yet count in the applied force: an error naming the FORCE record.
  subroutine check_loaded_nodes(model, error)
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: used(:)
    integer :: g, i, k, n
    allocate (used(model%nnode))
    used = .false.
    do g = 1, size(model%groups)
      used(pack(model%groups(g)%connectivity, .true.)) = .true.
    end do
    do i = 1, size(model%nodal_loads)
      associate (l => model%nodal_loads(i))
        do k = 1, size(model%node_sets(l%node_set)%nodes)
          n = model%node_sets(l%node_set)%nodes(k)
          if (used(n)) cycle
          call input_error(error, l%file, l%line, 'FORCE on node set ' // model%node_sets(l%node_set)%name // &
                           ': node ' // str(n) // ' belongs to no element, so the force would act on nothing', l%field)
          return
        end do
      end associate
    end do
  end subroutine check_loaded_nodes

  !> Fill each node set with the nodes in its region (or its one node); an empty set is an error.
  !! Only defined nodes are selected: NODE records may leave gaps in the numbering.
  subroutine resolve_node_sets(model, defined, regions, single, records, error, groups, fields)
    type(model_t), intent(inout) :: model
    logical, intent(in) :: defined(:)   !! given by a DATAIN block or a NODE record
    type(region_t), intent(in) :: regions(:)
    integer, intent(in) :: single(:)   !! NSET NODE=n: n; NSET LIST: -1 (nodes listed); a LIST row's node:
                                       !! -2 (the node in the set, its field in `fields`); else 0
    type(record_t), intent(in) :: records(:)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: groups(:)   !! restrict to the nodes of a group
    integer, intent(in), optional :: fields(:)            !! the field of a LIST row's node (single -2)
    integer :: s, n, g, ifield
    logical, allocatable :: inside(:), in_group(:)
    character(len=:), allocatable :: text
    logical :: found
    allocate (inside(model%nnode), in_group(model%nnode))
    do s = 1, size(model%node_sets)
      if (single(s) == -1) then
        call check_listed_nodes(model%node_sets(s), records(s), defined, error)
        if (allocated(error)) return
        cycle
      end if
      if (single(s) == -2) then
        n = model%node_sets(s)%nodes(1)
        ifield = 0
        if (present(fields)) ifield = fields(s)
        if (n > model%nnode) then
          call input_error(error, records(s)%file, field_line(records(s), ifield), 'node ' // str(n) // &
                           ' is not defined', ifield)
          return
        end if
        if (.not. defined(n)) then
          call input_error(error, records(s)%file, field_line(records(s), ifield), 'node ' // str(n) // &
                           ' is not defined', ifield)
          return
        end if
        cycle
      end if
      if (single(s) > 0) then
        call option_text(records(s), 'NODE', text, ifield, found)   ! the field to name
        if (single(s) > model%nnode) then
          call input_error(error, records(s)%file, records(s)%line, 'node ' // str(single(s)) // &
                           ' is out of range (the mesh has ' // str(model%nnode) // ' nodes)', ifield)
          return
        end if
        if (.not. defined(single(s))) then
          call input_error(error, records(s)%file, records(s)%line, 'node ' // str(single(s)) // &
                           ' is not defined (no DATAIN block or NODE record gives it)', ifield)
          return
        end if
        model%node_sets(s)%nodes = [single(s)]
        cycle
      end if
      in_group = .true.
      if (present(groups)) then
        if (len_trim(groups(s)) > 0) then
          g = model%find_group(trim(groups(s)))
          if (g == 0) then
            call input_error(error, records(s)%file, records(s)%line, 'undefined element group "' // &
                             trim(groups(s)) // '"')
            return
          end if
          in_group = .false.
          in_group(pack(model%groups(g)%connectivity, .true.)) = .true.
        end if
      end if
      do n = 1, model%nnode
        inside(n) = in_group(n) .and. defined(n)
        if (inside(n)) inside(n) = in_region(regions(s), model%systems(regions(s)%csys), model%coords(:, n))
      end do
      model%node_sets(s)%nodes = pack([(n, n = 1, model%nnode)], inside)
      if (size(model%node_sets(s)%nodes) == 0) then
        call input_error(error, records(s)%file, records(s)%line, 'node set ' // model%node_sets(s)%name // &
                         ' selects no node')
        return
      end if
    end do
  end subroutine resolve_node_sets

  !> Region options of a NSET/FSET record: CSYS=, TOL= and coordinate=a[:b] fields.
  subroutine read_region(rec, model, r, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    type(region_t), intent(out) :: r
    type(error_t), allocatable, intent(out) :: error
    integer :: i, k
    character(len=:), allocatable :: f, key

    call get_csys_option(rec, model, 'CSYS', csys_cartesian, r%csys, error)
    if (allocated(error)) return
    call check_option_keys(rec, 3, error)
    if (allocated(error)) return
    do i = 3, nfields(rec)
      call key_value(rec, i, 'COORDINATE=value or =from:to', key, f, error)
      if (allocated(error)) return
      select case (key)
      case ('CSYS', 'GROUP')
        cycle
      case ('TOL')
        call parse_real(f, r%tol, error, rec, i)
        if (allocated(error)) return
        cycle
      end select
      call dof_index(key, model%systems(r%csys)%kind, k)
      if (k == 0) then
        call input_error(error, rec%file, field_line(rec, i), &
                         'unknown coordinate "' // key // '" for this system (' // &
                         dof_names(model%systems(r%csys)%kind) // ')', i)
        return
      end if
      if (r%active(k)) then
        call input_error(error, rec%file, field_line(rec, i), &
                         'coordinate ' // key // ' names the same coordinate as ' // &
                         'another field of the selection', i)
        return
      end if
      call parse_range_real(f, r%lo(k), r%hi(k), error, rec, i)
      if (allocated(error)) return
      r%active(k) = .true.
    end do
    if (.not. any(r%active)) then
      call input_error(error, rec%file, rec%line, 'the selection gives no coordinate range')
    end if
  end subroutine read_region

  !> Keep the material's unit warning, if it has one, naming the MATERIAL record's file, line
  !! and the field of the parameter (E, or G where E was not given).
  subroutine note_unit_warning(model, spec, material)
    type(model_t), intent(inout) :: model
    type(material_spec_t), intent(in) :: spec
    class(material_t), intent(in) :: material
    character(len=:), allocatable :: warning, key, where
    character(len=600), allocatable :: kept(:)
    integer :: field, n
    call material%unit_warning(warning, key)
    if (len(warning) == 0) return
    field = spec%field_of(key)
    if (field == 0 .and. key == 'e') field = spec%field_of('g')
    where = spec%file // ':' // str(spec%line) // ': '
    if (field > 0) where = where // 'field ' // str(field) // ': '
    n = 0
    if (allocated(model%warnings)) n = size(model%warnings)
    allocate (kept(n + 1))
    if (n > 0) kept(:n) = model%warnings
    kept(n + 1) = where // 'material ' // spec%name // ': ' // warning
    call move_alloc(kept, model%warnings)
  end subroutine note_unit_warning

end module feps_deck
