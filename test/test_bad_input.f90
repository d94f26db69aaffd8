!> Every kind of bad input: a one-line error naming the file and line (or element, or node
!! and DOF), an input/model error code (exit status 2), and no result file left behind; and a
!! run whose numbers leave double precision: a numerical error (exit status 1), no result file.
module test_bad_input
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: err_input, err_input_file, err_model, err_solver, str
  use feps_program, only: run_options_t, run_summary_t, run_feps
  use feps_kinds, only: dp
  use feps_strings, only: utf8_text_length, shown
  use feps_records, only: max_line_length
  use feps_material, only: material_t
  use feps_material_factory, only: new_material
  use feps_linear_elastic, only: linear_elastic_t
  use feps_material_testing, only: material_spec
  implicit none
  private

  public :: collect_bad_input

  character(len=*), parameter :: out = 'build/test_bad_input.h5'

  integer :: steps_taken = 0   !! progress lines of steps that count_steps has seen

contains

  subroutine collect_bad_input(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('the valid cube deck runs and writes its file', test_valid), &
      new_unittest('unknown keyword', test_unknown_keyword), &
      new_unittest('RESTART, EVERY=0', test_restart_every_zero), &
      new_unittest('RESTART given twice', test_restart_twice), &
      new_unittest('RESTART with an unknown option', test_restart_unknown_option), &
      new_unittest('unknown record inside a DATAIN block', test_unknown_record), &
      new_unittest('missing field', test_missing_field), &
      new_unittest('non-numeric field', test_non_numeric), &
      new_unittest('zero repeat count', test_zero_repeat), &
      new_unittest('truncated file', test_truncated), &
      new_unittest('empty file', test_empty), &
      new_unittest('missing file', test_missing_file), &
      new_unittest('a directory given as the deck', test_deck_is_directory), &
      new_unittest('a device given as the deck', test_deck_is_device), &
      new_unittest('INCLUDE of a device', test_include_device), &
      new_unittest('INCLUDE of a FIFO: refused, not waited on', test_include_fifo), &
      new_unittest('a line longer than feps reads', test_line_too_long), &
      new_unittest('a record continued over 200 000 lines is read in linear time', test_long_record), &
      new_unittest('results named as an existing directory: refused before the run, kept', test_output_is_directory), &
      new_unittest('the XDMF name an existing directory: refused before the run, kept', test_xdmf_is_directory), &
      new_unittest('results in a missing folder: refused before the run', test_output_folder_missing), &
      new_unittest('two STAGE records with one name', test_stage_twice), &
      new_unittest('STAGE PATH= (arc-length, displacement control): each bad key or combination', test_path_keys), &
      new_unittest('node number out of range', test_node_out_of_range), &
      new_unittest('duplicate node', test_duplicate_node), &
      new_unittest('an FSET LIST row with a face number the type has not', test_fset_list_face_number), &
      new_unittest('an FSET LIST row naming an element of no group', test_fset_list_unknown_element), &
      new_unittest('MODE=TOTAL before any STAGE', test_mode_total_before_stage), &
      new_unittest('MODE= of an unknown word', test_mode_unknown), &
      new_unittest('a FORCE, LIST row with an unknown DOF', test_force_list_bad_dof), &
      new_unittest('a FORCE, LIST row on an undefined node', test_force_list_undefined_node), &
      new_unittest('a later FORCE, LIST row on an undefined node: its own line and field', &
                   test_force_list_undefined_node_later_row), &
      new_unittest('a DISPLACE, LIST row short of its value', test_displace_list_short_row), &
      new_unittest('a NODES table: a node number given twice', test_lists_duplicate_node), &
      new_unittest('ELEMENTS tables: an element id given twice', test_lists_duplicate_element), &
      new_unittest('an ELEMENTS row naming an undefined node', test_lists_undefined_node), &
      new_unittest('an ELEMENTS row a node short', test_lists_short_row), &
      new_unittest('a NODES row of five fields', test_lists_node_row_fields), &
      new_unittest('ELEMENTS before its GROUP', test_lists_elements_unknown_group), &
      new_unittest('an NSET LIST naming an undefined node', test_lists_nset_undefined_node), &
      new_unittest('a group of DATAIN blocks and ELEMENTS rows', test_lists_blocks_and_rows), &
      new_unittest('non-positive Jacobian names the element', test_negative_jacobian), &
      new_unittest('a face set on a group of bars: no faces', test_face_set_on_bars), &
      new_unittest('undefined material', test_undefined_material), &
      new_unittest('unknown element type: the message lists every type', test_element_type_unknown), &
      new_unittest('FIELDS CSYS= naming a Cartesian system', test_fields_csys_cartesian), &
      new_unittest('FIELDS with an option other than CSYS=', test_fields_option_unknown), &
      new_unittest('nu = 0.5 rejected', test_nu_half), &
      new_unittest('a modulus far outside N-mm-MPa warns, naming the parameter', test_unit_warnings), &
      new_unittest('nu = -1 rejected', test_nu_minus_one), &
      new_unittest('rigid-body mode names node and DOF', test_rigid_body_mode), &
      new_unittest('unknown result field name', test_unknown_field), &
      new_unittest('a DOF=value field without its DOF', test_option_without_key), &
      new_unittest('a number with an exponent but no E (200000-1)', test_exponent_without_e), &
      new_unittest('CSYS: theta reference along the axis', test_csys_reference_parallel), &
      new_unittest('CSYS: theta reference of two components', test_csys_reference_partial), &
      new_unittest('CSYS: a field too many', test_csys_extra_field), &
      new_unittest('a rotated Cartesian system given four of its six axis components', test_csys_axes_partial), &
      new_unittest('a rotated Cartesian system with a zero x axis', test_csys_axis_zero), &
      new_unittest('a rotated Cartesian system whose x-y vector is parallel to its x axis', test_csys_axes_parallel), &
      new_unittest('STAGE without STEPS=', test_stage_without_steps), &
      new_unittest('an option given twice in one record', test_option_given_twice), &
      new_unittest('a direction given twice under two names', test_direction_given_twice), &
      new_unittest('CONTROLS after a STAGE', test_controls_after_stage), &
      new_unittest('LINESEARCH=energy for a method it does not apply to names its field', test_linesearch_method), &
      new_unittest('an unknown LINESEARCH names its field', test_linesearch_unknown), &
      new_unittest('FIX with a KEY=value other than CSYS', test_fix_option), &
      new_unittest('FIX with CSYS= twice', test_fix_csys_twice), &
      new_unittest('REPORT with an unknown option', test_report_unknown_option), &
      new_unittest('REPORT, REACTION without NSET=', test_report_reaction_no_nset), &
      new_unittest('REPORT, REACTION with an undefined node set', test_report_reaction_unknown_nset), &
      new_unittest('two REPORTs of one name', test_report_name_twice), &
      new_unittest('two SOLVER records', test_solver_twice), &
      new_unittest('two OUTPUT records', test_output_twice), &
      new_unittest('an E record with a field', test_extra_field_on_e), &
      new_unittest('NSET by NODE= with a coordinate', test_nset_node_with_options), &
      new_unittest('GROUP with an unknown option', test_group_unknown_option), &
      new_unittest('NODE with a fourth coordinate', test_node_extra_field), &
      new_unittest('NSET of a node in a gap of the numbering', test_nset_undefined_node), &
      new_unittest('FORCE on a node that belongs to no element', test_force_on_orphan_node), &
      new_unittest('PRESSURE: VARY= without PEAK=', test_vary_without_peak), &
      new_unittest('PRESSURE: ZERO= and PEAK= without VARY=', test_zero_without_vary), &
      new_unittest('PRESSURE: VARY=X in a cylindrical system', test_vary_coordinate_of_other_system), &
      new_unittest('REPORT, TILT without two sections', test_tilt_no_span), &
      new_unittest('ACTIVATE of an undefined group', test_activate_unknown), &
      new_unittest('ACTIVATE of a group twice', test_activate_twice), &
      new_unittest('node carried only by an unborn group names node and DOF', test_activate_orphan), &
      new_unittest('RELEASE before any STAGE record', test_release_before_stage), &
      new_unittest('RELEASE of a DOF not held in the stage before names node and DOF', test_release_not_held), &
      new_unittest('RELEASE of a prescribed DOF names node, DOF and the DISPLACE line', test_release_prescribed), &
      new_unittest('PARAMETERS: a name given twice', test_parameter_twice), &
      new_unittest('PRESSURE with VARY2 but no VARY', test_vary2_alone), &
      new_unittest('FIX from a later stage of a prescribed DOF names node, DOF and the DISPLACE line', &
                   test_fix_prescribed), &
      new_unittest('PARAMETERS: a name starting with a digit', test_parameter_bad_name), &
      new_unittest('a node repeat count beyond the mesh size limit', test_repeat_too_large), &
      new_unittest('an element repeat count beyond the mesh size limit', test_element_repeat_too_large), &
      new_unittest('a NODE number beyond the mesh size limit', test_node_number_too_large), &
      new_unittest('STEPS beyond the integer range names its range', test_steps_out_of_range), &
      new_unittest('steps adding up past what one run numbers', test_steps_total_too_large), &
      new_unittest('MAXIT beyond what --maxit takes', test_maxit_out_of_range), &
      new_unittest('CUTBACKS beyond 50', test_cutbacks_out_of_range), &
      new_unittest('a subnormal number (E=1e-320) is refused at once', test_subnormal_number), &
      new_unittest('a bad field on a continuation line names that line', test_continuation_field_line), &
      new_unittest('MATSUOKA with an unknown TENSION rule', test_tension_rule_unknown), &
      new_unittest('ELASTIC with a parameter it does not have (TENSION)', test_tension_on_elastic), &
      new_unittest('ELASTIC with both E and G', test_elastic_e_and_g), &
      new_unittest('a MATERIAL parameter given twice', test_material_key_twice), &
      new_unittest('a material name with a slash', test_material_name_slash), &
      new_unittest('ELASTIC with a negative G names G and its field, not the derived E', test_elastic_g_negative), &
      new_unittest('ELASTIC with a G whose E overflows names G', test_elastic_g_overflow), &
      new_unittest('ELASTIC with G near huge() and NU near -1 is accepted (E does not overflow)', &
                   test_elastic_g_large_nu_negative), &
      new_unittest('ELASTIC with an unknown key names its field', test_elastic_unknown_key), &
      new_unittest('CONCRETE with a negative GF names its field', test_concrete_gf_negative), &
      new_unittest('CONCRETE with an unknown SOFTENING law names its field', test_concrete_softening_unknown), &
      new_unittest('CONCRETE with an unknown DAMAGE kind names its field', test_concrete_damage_unknown), &
      new_unittest('CONCRETE with FC below FT names the field of FC', test_concrete_fc_below_ft), &
      new_unittest('CONCRETE with a negative FC names its field', test_concrete_fc_negative), &
      new_unittest('CONCRETE with PHI out of range names its field', test_concrete_phi_out_of_range), &
      new_unittest('CONCRETE with PSI above PHI names its field', test_concrete_psi_above_phi), &
      new_unittest('CONCRETE with PHI but no FC names the field of PHI', test_concrete_phi_without_fc), &
      new_unittest('CONCRETE with FC given twice names the second', test_concrete_fc_twice), &
      new_unittest('CONCRETE in elements longer than its crack band allows (snap-back) names GF', &
                   test_concrete_band_too_large), &
      new_unittest('an unknown material kind names its field', test_material_kind_unknown), &
      new_unittest('MATSUOKA with FT and C names the second', test_matsuoka_ft_and_c), &
      new_unittest('MATSUOKA with PSI above PHI names PSI''s field', test_matsuoka_psi_above_phi), &
      new_unittest('INTERFACE with PSI above PHI names PSI''s field', test_interface_psi_above_phi), &
      new_unittest('BAR with a negative area names A''s field', test_bar_area_negative), &
      new_unittest('BAR without A names no field', test_bar_area_missing), &
      new_unittest('a group name with a slash', test_group_name_slash), &
      new_unittest('a group name with a control byte', test_group_name_control), &
      new_unittest('a group name that is not UTF-8', test_group_name_not_utf8), &
      new_unittest('printable UTF-8 text: control bytes, overlong forms, surrogates refused', test_utf8_text), &
      new_unittest('PRESTRESS on a group of solids', test_prestress_on_solid), &
      new_unittest('PRESTRESS before its group is born', test_prestress_before_birth), &
      new_unittest('PRESTRESS with FORCE= and STRESS=', test_prestress_force_and_stress), &
      new_unittest('PRESTRESS with a bare number', test_prestress_bare_value), &
      new_unittest('PRESTRESS whose STRESS times A overflows', test_prestress_overflow), &
      new_unittest('PRESTRESS, BOND=AFTER in the last stage', test_prestress_bond_last_stage), &
      new_unittest('PRESTRESS, BOND=AFTER on a group ACTIVATEd in another stage', test_prestress_bond_activate), &
      new_unittest('PRESTRESS, BOND= neither BEFORE nor AFTER', test_prestress_bond_word), &
      new_unittest('OUTPUT naming a .xmf file (the XDMF file would replace it)', test_output_xmf), &
      new_unittest('a load beyond double precision names the load', test_load_overflow, nonfinite=.true.), &
      new_unittest('stage loads adding up beyond double precision name the stage', test_stage_load_overflow, &
                   nonfinite=.true.), &
      new_unittest('a solution beyond double precision stops the run, no result file', test_solution_overflow, &
                   nonfinite=.true.), &
      new_unittest('a failed run removes the results an earlier run left under its name', test_failed_run_removes_stale, &
                   nonfinite=.true.), &
      new_unittest('a deck refused before its first step leaves the results an earlier run left', &
                   test_refused_deck_keeps_earlier), &
      new_unittest('REPORT, TILT on a section without nodes: before the first step, and by --check', &
                   test_report_no_section), &
      new_unittest('REPORT, ROTATION spanning beyond its ring: before the first step, and by --check', &
                   test_report_ring_span), &
      new_unittest('node coordinates beyond double precision, in a run and by --check', test_coordinates_overflow, &
                   nonfinite=.true.) &
      ]
  end subroutine collect_bad_input

  !> Run a deck that must fail; check the error code, the message's pieces (and that none of
  !! `absent` is in it) and that no result file (nor its temporary or XDMF) exists afterwards.
  !! With `check_only`, as `feps --check`; with `before_first_step`, the error must come before
  !! any step is taken.
  subroutine expect_failure(deck, code, pieces, error, absent, check_only, before_first_step)
    character(len=*), intent(in) :: deck
    integer, intent(in) :: code
    character(len=*), intent(in) :: pieces(:)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: absent(:)
    logical, intent(in), optional :: check_only, before_first_step
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    type(error_t), allocatable :: run_error
    integer :: i
    logical :: exists
    call remove_outputs()
    opt%deck = deck
    opt%output = out
    opt%solver = ''
    if (present(check_only)) opt%check_only = check_only
    steps_taken = 0
    call run_feps(opt, summary, run_error, count_steps)
    if (.not. allocated(run_error)) then
      call test_failed(error, deck // ': expected an error, the run succeeded')
      return
    end if
    if (present(before_first_step)) then
      if (before_first_step .and. steps_taken > 0) then
        call test_failed(error, deck // ': the error came after ' // str(steps_taken) // ' steps: ' // &
                         run_error%message)
        return
      end if
    end if
    call check(error, run_error%code, code, deck // ': error code (message: ' // run_error%message // ')')
    if (allocated(error)) return
    call check(error, index(run_error%message, new_line('a')) == 0, 'one-line message')
    if (allocated(error)) return
    do i = 1, size(pieces)
      if (index(run_error%message, trim(pieces(i))) == 0) then
        call test_failed(error, 'message "' // run_error%message // '" lacks "' // trim(pieces(i)) // '"')
        return
      end if
    end do
    if (present(absent)) then
      do i = 1, size(absent)
        if (index(run_error%message, trim(absent(i))) > 0) then
          call test_failed(error, 'message "' // run_error%message // '" has "' // trim(absent(i)) // '"')
          return
        end if
      end do
    end if
    inquire (file=out, exist=exists)
    call check(error, .not. exists, 'no result file left behind')
    if (allocated(error)) return
    inquire (file=out // '.part', exist=exists)
    call check(error, .not. exists, 'no temporary result file left behind')
    if (allocated(error)) return
    inquire (file='build/test_bad_input.xmf', exist=exists)
    call check(error, .not. exists, 'no XDMF file left behind')
  end subroutine expect_failure

  !> The progress sink of expect_failure: counts the lines of steps taken.
  subroutine count_steps(line)
    character(len=*), intent(in) :: line
    if (index(line, '  step ') > 0) steps_taken = steps_taken + 1
  end subroutine count_steps

  subroutine remove_outputs()
    integer :: u, ios
    character(len=*), parameter :: files(3) = [character(len=40) :: out, out // '.part', 'build/test_bad_input.xmf']
    integer :: i
    logical :: exists
    do i = 1, 3
      inquire (file=trim(files(i)), exist=exists)
      if (exists) then
        open (newunit=u, file=trim(files(i)), iostat=ios)
        if (ios == 0) close (u, status='delete')
      end if
    end do
  end subroutine remove_outputs

  !> Run `deck` as the feps command would, its results under `out`.
  subroutine run_deck(deck, error)
    character(len=*), intent(in) :: deck
    type(error_t), allocatable, intent(out) :: error
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    opt%deck = deck
    opt%output = out
    opt%solver = ''
    call run_feps(opt, summary, error)
  end subroutine run_deck

  subroutine test_valid(error)
    type(error_t), allocatable, intent(out) :: error
    logical :: exists
    call remove_outputs()
    call run_deck('test/data/cube.dat', error)
    if (allocated(error)) return
    inquire (file=out, exist=exists)
    call check(error, exists, 'result file written')
    if (allocated(error)) return
    inquire (file='build/test_bad_input.xmf', exist=exists)
    call check(error, exists, 'XDMF file written')
    call remove_outputs()
  end subroutine test_valid

  !> Issue 25's tables: a NODES table: a node number given twice.
  subroutine test_lists_duplicate_node(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_duplicate_node.dat', err_input, &
                        [character(len=60) :: 'lists_duplicate_node.dat:13:', &
                         'field 34', &
                         'duplicate node 3 (defined before, at line 7)'], error)
  end subroutine test_lists_duplicate_node

  !> Issue 25's tables: ELEMENTS tables: an element id given twice.
  subroutine test_lists_duplicate_element(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_duplicate_element.dat', err_input, &
                        [character(len=60) :: 'lists_duplicate_element.dat:16:', &
                         'field 3', &
                         'duplicate element 10 (defined before, at line 14)'], error)
  end subroutine test_lists_duplicate_element

  !> Issue 25's tables: an ELEMENTS row naming an undefined node.
  subroutine test_lists_undefined_node(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_undefined_node.dat', err_input, &
                        [character(len=60) :: 'lists_undefined_node.dat:14:', &
                         'field 11', &
                         'uses node 9, which is not defined'], error)
  end subroutine test_lists_undefined_node

  !> Issue 25's tables: an ELEMENTS row a node short.
  subroutine test_lists_short_row(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_short_row.dat', err_input, &
                        [character(len=60) :: 'lists_short_row.dat:15:', &
                         'field 11', &
                         'element 10 of group block has 7 nodes; its type hex8 has 8'], error)
  end subroutine test_lists_short_row

  !> Issue 25's tables: a NODES row of five fields.
  subroutine test_lists_node_row_fields(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_node_row_fields.dat', err_input, &
                        [character(len=60) :: 'lists_node_row_fields.dat:13:', &
                         'field 38', &
                         'this one has 5 fields'], error)
  end subroutine test_lists_node_row_fields

  !> Issue 25's tables: ELEMENTS before its GROUP.
  subroutine test_lists_elements_unknown_group(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_elements_unknown_group.dat', err_input, &
                        [character(len=60) :: 'lists_elements_unknown_group.dat:12:', &
                         'field 2', &
                         'undefined element group "block"'], error)
  end subroutine test_lists_elements_unknown_group

  !> Issue 25's tables: an NSET LIST naming an undefined node.
  subroutine test_lists_nset_undefined_node(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_nset_undefined_node.dat', err_input, &
                        [character(len=60) :: 'lists_nset_undefined_node.dat:16:', &
                         'field 7', &
                         'node set corners: node 12 is not defined'], error)
  end subroutine test_lists_nset_undefined_node

  !> Issue 25's tables: a group of DATAIN blocks and ELEMENTS rows.
  subroutine test_lists_blocks_and_rows(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/lists_blocks_and_rows.dat', err_input, &
                        [character(len=60) :: 'lists_blocks_and_rows.dat:3:', &
                         'takes DATAIN element blocks and ELEMENTS rows'], error)
  end subroutine test_lists_blocks_and_rows

  !> Issue 25's rotated Cartesian systems: a rotated Cartesian system given four of its six axis components.
  subroutine test_csys_axes_partial(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/csys_axes_partial.dat', err_input, &
                        [character(len=60) :: 'csys_axes_partial.dat:24:', &
                         'field 11', &
                         'the axes take all six of ax, ay, az, bx, by, bz'], error)
  end subroutine test_csys_axes_partial

  !> Issue 25's rotated Cartesian systems: a rotated Cartesian system with a zero x axis.
  subroutine test_csys_axis_zero(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/csys_axis_zero.dat', err_input, &
                        [character(len=60) :: 'csys_axis_zero.dat:24:', &
                         'field 7', &
                         'the x axis (ax, ay, az) has zero length'], error)
  end subroutine test_csys_axis_zero

  !> Issue 25's rotated Cartesian systems: a rotated Cartesian system whose x-y vector is parallel to its x axis.
  subroutine test_csys_axes_parallel(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/csys_axes_parallel.dat', err_input, &
                        [character(len=60) :: 'csys_axes_parallel.dat:24:', &
                         'field 10', &
                         'is zero or parallel to the x axis'], error)
  end subroutine test_csys_axes_parallel

  !> Issue 25's loads per node: a FORCE, LIST row with an unknown DOF.
  subroutine test_force_list_bad_dof(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/force_list_bad_dof.dat', err_input, &
                        [character(len=60) :: 'force_list_bad_dof.dat:23:', &
                         'field 4', &
                         'unknown degree of freedom "W"'], error)
  end subroutine test_force_list_bad_dof

  !> Issue 25's loads per node: a FORCE, LIST row on an undefined node.
  subroutine test_force_list_undefined_node(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/force_list_undefined_node.dat', err_input, &
                        [character(len=60) :: 'force_list_undefined_node.dat:23:', &
                         'field 3', &
                         'node 99 is not defined'], error)
  end subroutine test_force_list_undefined_node

  !> The third row of a FORCE, LIST, on line 25, names an undefined node: the message names
  !! that line and the row's node field (9), as it did when each row kept a copy of the whole
  !! record (a LIST of n rows now keeps two fields per row, not n records of 3n fields).
  subroutine test_force_list_undefined_node_later_row(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/force_list_undefined_node_later_row.dat', err_input, &
                        [character(len=60) :: 'force_list_undefined_node_later_row.dat:25:', &
                         'field 9', &
                         'node 99 is not defined'], error)
  end subroutine test_force_list_undefined_node_later_row

  !> Issue 25's loads per node: a DISPLACE, LIST row short of its value.
  subroutine test_displace_list_short_row(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/displace_list_short_row.dat', err_input, &
                        [character(len=60) :: 'displace_list_short_row.dat:23:', &
                         'field 8', &
                         'the last row is short of a field'], error)
  end subroutine test_displace_list_short_row

  !> Issue 27's STAGE PATH=: each bad key, value or combination (read from the record, or found
  !! when the stage starts, before its first step, and by --check alike) is named with its line.
  subroutine test_path_keys(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: dir = 'test/data/bad/'
    integer, parameter :: n = 17
    character(len=40), parameter :: decks(n) = [character(len=40) :: 'path_unknown', 'path_arc_zero', &
      'path_arc_without_arc_length', 'path_displacement_incomplete', 'path_nset_undefined', 'path_dof_unknown', &
      'path_value_zero', 'path_nset_without_displacement', 'path_euler', 'path_with_displace', 'path_no_load', &
      'path_dof_held', 'path_restart', 'path_from_undefined', 'path_from_without_displacement', &
      'path_from_same_set', 'path_from_same_nodes']
    character(len=60), parameter :: where(n) = [character(len=60) :: ':13: field 4:', ':13: field 5:', &
      ':13: field 4:', ':13: field 4:', ':13: field 5:', ':13: field 6:', ':13: field 7:', ':13: field 5:', &
      ':13: field 4:', ':13: PATH=ARC-LENGTH', ':13: PATH=ARC-LENGTH', ':13: PATH=DISPLACEMENT', ':14: field 4:', &
      ':13: field 6:', ':13: field 5:', ':13: field 6:', ':14: PATH=DISPLACEMENT']
    character(len=60), parameter :: what(n) = [character(len=60) :: 'unknown PATH "SPIRAL"', &
      'ARC (the arc length) must be positive', 'ARC is the arc length of PATH=ARC-LENGTH', &
      'PATH=DISPLACEMENT needs NSET=<set>, DOF=', 'undefined node set "tip"', 'DOF takes X, Y or Z, got "W"', &
      'VALUE (the displacement increment of the stage) must not be', 'NSET goes with PATH=DISPLACEMENT', &
      'METHOD=euler takes one pass per step', 'it moves no DOF by DISPLACE', 'has no load to scale', &
      'node 2 of set pulled is held in Y', 'which restart data do not carry', 'undefined node set "tip"', &
      'FROM goes with PATH=DISPLACEMENT', 'FROM= names the set NSET= names', 'the two sets move together']
    character(len=80) :: pieces(2)
    integer :: i, j
    ! each deck twice: a run, then --check (odd i, even i)
    do i = 1, 2 * n
      j = (i + 1) / 2
      pieces(1) = trim(decks(j)) // '.dat' // where(j)
      pieces(2) = what(j)
      call expect_failure(dir // trim(decks(j)) // '.dat', err_input, pieces, error, check_only=mod(i, 2) == 0, &
                          before_first_step=.true.)
      if (allocated(error)) return
    end do
  end subroutine test_path_keys

  !> Issue 25's MODE=: MODE=TOTAL before any STAGE.
  subroutine test_mode_total_before_stage(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/mode_total_before_stage.dat', err_input, &
                        [character(len=60) :: 'mode_total_before_stage.dat:24:', &
                         'field 4', &
                         'MODE=TOTAL needs a STAGE record before it'], error)
  end subroutine test_mode_total_before_stage

  !> Issue 25's MODE=: MODE= of an unknown word.
  subroutine test_mode_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/mode_unknown.dat', err_input, &
                        [character(len=60) :: 'mode_unknown.dat:29:', &
                         'field 3', &
                         'MODE takes INCREMENT or TOTAL, not "ABSOLUTE"'], error)
  end subroutine test_mode_unknown

  !> Issue 25's face sets by face number: an FSET LIST row with a face number the type has not.
  subroutine test_fset_list_face_number(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/fset_list_face_number.dat', err_input, &
                        [character(len=60) :: 'fset_list_face_number.dat:44:', &
                         'field 6', &
                         'element 1 (tet10) has faces 1 to 4, not 5'], error)
  end subroutine test_fset_list_face_number

  !> Issue 25's face sets by face number: an FSET LIST row naming an element of no group.
  subroutine test_fset_list_unknown_element(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/fset_list_unknown_element.dat', err_input, &
                        [character(len=60) :: 'fset_list_unknown_element.dat:45:', &
                         'field 7', &
                         'group wall has no element 999'], error)
  end subroutine test_fset_list_unknown_element

  subroutine test_unknown_keyword(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/unknown_keyword.dat', err_input, &
                        [character(len=40) :: 'unknown_keyword.dat:3:', 'FROB'], error)
  end subroutine test_unknown_keyword

  subroutine test_restart_every_zero(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/restart_every_zero.dat', err_input, &
                        [character(len=48) :: 'restart_every_zero.dat:25:', 'field 2', &
                         'EVERY 0 is outside the allowed range 1..'], error)
  end subroutine test_restart_every_zero

  subroutine test_restart_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/restart_twice.dat', err_input, &
                        [character(len=48) :: 'restart_twice.dat:26:', 'RESTART is given twice (first at line 25)'], &
                        error)
  end subroutine test_restart_twice

  subroutine test_restart_unknown_option(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/restart_unknown_option.dat', err_input, &
                        [character(len=48) :: 'restart_unknown_option.dat:25:', 'field 2', &
                         'unknown RESTART option "KEEP=3"'], error)
  end subroutine test_restart_unknown_option

  subroutine test_tilt_no_span(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/tilt_no_span.dat', err_input, &
                        [character(len=40) :: 'tilt_no_span.dat:21:', 'FROM= and TO='], error)
  end subroutine test_tilt_no_span

  subroutine test_unknown_field(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/unknown_field.dat', err_input, &
                        [character(len=40) :: 'unknown_field.dat:24:', 'field 3', 'stresses'], error)
  end subroutine test_unknown_field

  !> '=value' with nothing before the '=' is refused as such, not looked up as a DOF named ''.
  subroutine test_option_without_key(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/option_without_key.dat', err_input, &
                        [character(len=40) :: 'option_without_key.dat:25:', 'field 3', &
                         'expected DOF=value, got "=-100."'], error)
  end subroutine test_option_without_key

  !> Fortran's list-directed read takes '200000-1' as 2e4; feps checks the syntax first.
  subroutine test_exponent_without_e(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/number_exponent_without_e.dat', err_input, &
                        [character(len=40) :: 'number_exponent_without_e.dat:15:', 'field 4', &
                         'expected a number, got "200000-1"'], error)
  end subroutine test_exponent_without_e

  !> A reference along the axis has no part normal to it: theta = 0 would be NaN everywhere.
  subroutine test_csys_reference_parallel(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/csys_reference_parallel.dat', err_input, &
                        [character(len=40) :: 'csys_reference_parallel.dat:24:', 'field 10', 'parallel'], error)
  end subroutine test_csys_reference_parallel

  !> Two of rx, ry, rz used to leave the default reference in place without a word.
  subroutine test_csys_reference_partial(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/csys_reference_partial.dat', err_input, &
                        [character(len=40) :: 'csys_reference_partial.dat:24:', 'field 12', 'rx, ry, rz'], error)
  end subroutine test_csys_reference_partial

  subroutine test_csys_extra_field(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/csys_extra_field.dat', err_input, &
                        [character(len=40) :: 'csys_extra_field.dat:24:', 'field 13', 'one too many'], error)
  end subroutine test_csys_extra_field

  !> STEPS is in the syntax without brackets; it used to default to 1.
  subroutine test_stage_without_steps(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/stage_without_steps.dat', err_input, &
                        [character(len=40) :: 'stage_without_steps.dat:24:', 'needs STEPS=n'], error)
  end subroutine test_stage_without_steps

  !> The last of two Z= used to win without a word.
  subroutine test_option_given_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/option_given_twice.dat', err_input, &
                        [character(len=40) :: 'option_given_twice.dat:25:', 'field 4', 'Z is given twice'], error)
  end subroutine test_option_given_twice

  !> Z and UZ name the same DOF.
  subroutine test_direction_given_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/direction_given_twice.dat', err_input, &
                        [character(len=40) :: 'direction_given_twice.dat:25:', 'field 4', 'same direction'], error)
  end subroutine test_direction_given_twice

  !> Each stage copies the controls when it is read: a later CONTROLS changed nothing for it.
  subroutine test_controls_after_stage(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/controls_after_stage.dat', err_input, &
                        [character(len=40) :: 'controls_after_stage.dat:25:', 'would not apply'], error)
  end subroutine test_controls_after_stage

  !> LINESEARCH=energy given on CONTROLS reaches a stage of modified Newton-Raphson: the error
  !! names the CONTROLS record's field, the method and the stage, before any step.
  subroutine test_linesearch_method(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/linesearch_method.dat', err_input, &
                        [character(len=40) :: 'linesearch_method.dat:24:', 'field 3', 'LINESEARCH=energy', &
                         'modified-newton-raphson', 'stage s1'], error, before_first_step=.true.)
  end subroutine test_linesearch_method

  subroutine test_linesearch_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/linesearch_unknown.dat', err_input, &
                        [character(len=40) :: 'linesearch_unknown.dat:23:', 'field 5', 'LINESEARCH "armijo"', &
                         '(none, energy)'], error, before_first_step=.true.)
  end subroutine test_linesearch_unknown

  !> FIX used to skip every field with an '=' in it, a misspelt CSYS= too.
  subroutine test_fix_option(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/fix_option.dat', err_input, &
                        [character(len=40) :: 'fix_option.dat:25:', 'field 4', 'Y=0.5'], error)
  end subroutine test_fix_option

  subroutine test_fix_csys_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/fix_csys_twice.dat', err_input, &
                        [character(len=40) :: 'fix_csys_twice.dat:24:', 'field 5', 'CSYS is given twice'], error)
  end subroutine test_fix_csys_twice

  !> A misspelt REFERENCE= used to drop the reference from the summary silently.
  subroutine test_report_unknown_option(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/report_unknown_option.dat', err_input, &
                        [character(len=40) :: 'report_unknown_option.dat:24:', 'field 7', 'REFERNCE'], error)
  end subroutine test_report_unknown_option

  subroutine test_report_reaction_no_nset(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/report_reaction_no_nset.dat', err_input, &
                        [character(len=40) :: 'report_reaction_no_nset.dat:25:', 'needs NSET='], error)
  end subroutine test_report_reaction_no_nset

  subroutine test_report_reaction_unknown_nset(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/report_reaction_unknown_nset.dat', err_input, &
                        [character(len=40) :: 'report_reaction_unknown_nset.dat:25:', 'field 4', &
                         'undefined node set "bottm"'], error)
  end subroutine test_report_reaction_unknown_nset

  !> Each REPORT writes its values under its name: the second of one name used to overwrite the
  !! first's in /summary.
  subroutine test_report_name_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/report_name_twice.dat', err_input, &
                        [character(len=48) :: 'report_name_twice.dat:25:', 'field 3', &
                         'REPORT name "base" is used twice (first at line 24)'], error)
  end subroutine test_report_name_twice

  subroutine test_solver_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/solver_twice.dat', err_input, &
                        [character(len=40) :: 'solver_twice.dat:25:', 'given twice', 'line 24'], error)
  end subroutine test_solver_twice

  subroutine test_output_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/output_twice.dat', err_input, &
                        [character(len=40) :: 'output_twice.dat:25:', 'given twice', 'line 24'], error)
  end subroutine test_output_twice

  subroutine test_extra_field_on_e(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/extra_field_on_e.dat', err_input, &
                        [character(len=40) :: 'extra_field_on_e.dat:24:', 'field 2', 'one too many'], error)
  end subroutine test_extra_field_on_e

  !> The coordinate used to be ignored.
  subroutine test_nset_node_with_options(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/nset_node_with_options.dat', err_input, &
                        [character(len=40) :: 'nset_node_with_options.dat:24:', 'field 4', 'NODE='], error)
  end subroutine test_nset_node_with_options

  subroutine test_group_unknown_option(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/group_unknown_option.dat', err_input, &
                        [character(len=40) :: 'group_unknown_option.dat:8:', 'field 5', 'COLOR'], error)
  end subroutine test_group_unknown_option

  subroutine test_node_extra_field(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/node_extra_field.dat', err_input, &
                        [character(len=40) :: 'node_extra_field.dat:24:', 'field 6', '7.'], error)
  end subroutine test_node_extra_field

  !> NODE 40 on a 27-node mesh leaves 28-39 undefined; they used to be nodes at the origin.
  subroutine test_nset_undefined_node(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/nset_undefined_node.dat', err_input, &
                        [character(len=40) :: 'nset_undefined_node.dat:25: field 3:', 'node 30 is not defined'], error)
  end subroutine test_nset_undefined_node

  !> The force used to count in the applied force and the reactions, and act on nothing.
  subroutine test_force_on_orphan_node(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/force_on_orphan_node.dat', err_input, &
                        [character(len=40) :: 'force_on_orphan_node.dat:26:', 'field 2', 'belongs to no element'], error)
  end subroutine test_force_on_orphan_node

  !> The missing PEAK= used to default to 1, so the load could exceed VALUE.
  subroutine test_vary_without_peak(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/vary_without_peak.dat', err_input, &
                        [character(len=40) :: 'vary_without_peak.dat:23:', 'field 4', 'needs ZERO= and PEAK='], error)
  end subroutine test_vary_without_peak

  !> They used to be ignored: a uniform load instead of a ramp.
  subroutine test_zero_without_vary(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/zero_without_vary.dat', err_input, &
                        [character(len=40) :: 'zero_without_vary.dat:23:', 'field 4', 'give VARY='], error)
  end subroutine test_zero_without_vary

  !> X used to mean R and Y theta (in degrees) there.
  subroutine test_vary_coordinate_of_other_system(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/vary_coordinate_of_other_system.dat', err_input, &
                        [character(len=40) :: 'vary_coordinate_of_other_system.dat:23:', 'field 4', &
                         'no coordinate of system 3'], error)
  end subroutine test_vary_coordinate_of_other_system

  !> The XDMF file is written beside the results as <name>.xmf: an OUTPUT record ending in .xmf
  !! used to lose the XDMF file silently (the HDF5 file replaced it).
  subroutine test_output_xmf(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/output_xmf.dat', err_input, &
                        [character(len=60) :: 'output_xmf.dat:25: field 2:', 'cube_results.xmf', &
                         'must not end in .xmf'], error)
  end subroutine test_output_xmf

  subroutine test_unknown_record(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/unknown_record.dat', err_input, &
                        [character(len=40) :: 'unknown_record.dat:5:'], error)
  end subroutine test_unknown_record

  subroutine test_missing_field(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/missing_field.dat', err_input, &
                        [character(len=40) :: 'missing_field.dat:15:', 'field 3'], error)
  end subroutine test_missing_field

  subroutine test_non_numeric(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/non_numeric_field.dat', err_input, &
                        [character(len=40) :: 'non_numeric_field.dat:15:', 'field 4', '2o0000'], error)
  end subroutine test_non_numeric

  subroutine test_zero_repeat(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/zero_repeat.dat', err_input, &
                        [character(len=40) :: 'zero_repeat.dat:5:', 'repeat'], error)
  end subroutine test_zero_repeat

  subroutine test_truncated(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/truncated.dat', err_input, &
                        [character(len=40) :: 'truncated.dat:', 'truncated'], error)
  end subroutine test_truncated

  subroutine test_empty(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/empty.dat', err_input, [character(len=40) :: 'empty.dat', 'empty'], error)
  end subroutine test_empty

  !> A deck that cannot be read is an input file error (feps exits 2: the user fixes the input),
  !! not err_io, which is for results that cannot be written (exit 1).
  subroutine test_missing_file(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=60), parameter :: pieces(1) = &
      [character(len=60) :: 'test/data/bad/no_such_deck.dat: cannot open file: no such file']
    call expect_failure('test/data/bad/no_such_deck.dat', err_input_file, pieces, error)
    if (.not. allocated(error)) call expect_failure('test/data/bad/no_such_deck.dat', err_input_file, pieces, &
                                                    error, check_only=.true.)
  end subroutine test_missing_file

  !> A directory opens and reads as a file without records: it was reported as an empty file.
  subroutine test_deck_is_directory(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad', err_input_file, &
                        [character(len=60) :: 'test/data/bad: cannot open file: it is a directory'], error, &
                        absent=[character(len=20) :: 'empty'])
  end subroutine test_deck_is_directory

  !> Only regular files are read (issue 24: INCLUDE of /dev/zero or of a FIFO hung for ever).
  subroutine test_deck_is_device(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('/dev/zero', err_input_file, &
                        [character(len=70) :: '/dev/zero: cannot open file: it is not a regular file'], error)
  end subroutine test_deck_is_device

  subroutine test_include_device(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/include_device.dat', err_input, &
                        [character(len=80) :: 'include_device.dat:2: INCLUDE: /dev/zero: cannot open file: ' // &
                         'it is not a regular file'], error)
  end subroutine test_include_device

  subroutine test_include_fifo(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'build/test_include_fifo.dat', fifo = 'build/test_include_fifo.datain'
    integer :: u, status, cmdstat
    status = 1
    call execute_command_line('rm -f ' // fifo // ' && mkfifo ' // fifo, exitstat=status, cmdstat=cmdstat)
    if (cmdstat /= 0 .or. status /= 0) return      ! no mkfifo here: nothing to test
    open (newunit=u, file=deck, status='replace', action='write')
    write (u, '(a)') 'INCLUDE, test_include_fifo.datain'
    close (u)
    call expect_failure(deck, err_input, [character(len=80) :: 'test_include_fifo.dat:1: INCLUDE: ', &
                        'test_include_fifo.datain: cannot open file: it is not a regular file'], error)
    call execute_command_line('rm -f ' // fifo // ' ' // deck)
  end subroutine test_include_fifo

  !> Lines are read in bounded pieces (issue 24: a 1 MB line took time quadratic in its length,
  !! and a longer one overflowed the stack).
  subroutine test_line_too_long(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'build/test_line_too_long.dat'
    character(len=80) :: expected(1)
    integer :: u
    open (newunit=u, file=deck, status='replace', action='write')
    write (u, '(a)') 'TITLE, a title', 'TITLE, ' // repeat('x', 2 * max_line_length), 'TITLE, not read'
    close (u)
    expected(1) = 'test_line_too_long.dat:2: line longer than ' // str(max_line_length) // ' characters'
    call expect_failure(deck, err_input, expected, error, before_first_step=.true.)
    open (newunit=u, file=deck)
    close (u, status='delete')
  end subroutine test_line_too_long

  !> A node record continued over 200 000 lines: its fields grow by doubling (copied per line,
  !! this took minutes), and the error for its first field too many names the line it is on.
  subroutine test_long_record(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'build/test_long_record.dat'
    integer :: u, i
    open (newunit=u, file=deck, status='replace', action='write')
    write (u, '(a)') 'NODE, 1, 0.,'
    do i = 1, 200000
      write (u, '(a)') '0.,'
    end do
    close (u)
    call expect_failure(deck, err_input, [character(len=80) :: 'test_long_record.dat:4: field 6:'], error)
    open (newunit=u, file=deck)
    close (u, status='delete')
  end subroutine test_long_record

  !> Issue 24: an existing directory as the results file ran the whole analysis, failed at the
  !! rename, and was then removed. The result paths are checked first, and nothing but regular
  !! files feps wrote is ever removed.
  subroutine test_output_is_directory(error)
    type(error_t), allocatable, intent(out) :: error
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    type(error_t), allocatable :: run_error
    logical :: exists
    opt%deck = 'test/data/cube.dat'
    opt%output = 'test/data/bad'
    call run_feps(opt, summary, run_error)
    call check(error, allocated(run_error), 'a directory as the results file is refused')
    if (allocated(error)) return
    call check(error, run_error%code, err_input, run_error%message)
    if (allocated(error)) return
    call check(error, index(run_error%message, 'results file "test/data/bad": it is a directory') > 0, &
               run_error%message)
    if (allocated(error)) return
    inquire (file='test/data/bad/empty.dat', exist=exists)
    call check(error, exists, 'the directory and its files are still there')
  end subroutine test_output_is_directory

  subroutine test_xdmf_is_directory(error)
    type(error_t), allocatable, intent(out) :: error
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    type(error_t), allocatable :: run_error
    integer :: status, cmdstat
    logical :: exists
    status = 1
    call execute_command_line('mkdir -p build/test_xmf_dir.xmf && touch build/test_xmf_dir.xmf/keep', &
                              exitstat=status, cmdstat=cmdstat)
    if (cmdstat /= 0 .or. status /= 0) return
    opt%deck = 'test/data/cube.dat'
    opt%output = 'build/test_xmf_dir.h5'
    call run_feps(opt, summary, run_error)
    call check(error, allocated(run_error), 'a directory in the XDMF file''s place is refused')
    if (allocated(error)) return
    call check(error, run_error%code == err_input .and. &
               index(run_error%message, '"build/test_xmf_dir.xmf": it is a directory') > 0, run_error%message)
    if (allocated(error)) return
    inquire (file='build/test_xmf_dir.xmf/keep', exist=exists)
    call check(error, exists, 'the directory and its file are still there')
    if (allocated(error)) return
    inquire (file='build/test_xmf_dir.h5.part', exist=exists)
    call check(error, .not. exists, 'no .part file')
    call execute_command_line('rm -rf build/test_xmf_dir.xmf')
  end subroutine test_xdmf_is_directory

  subroutine test_output_folder_missing(error)
    type(error_t), allocatable, intent(out) :: error
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    type(error_t), allocatable :: run_error
    opt%deck = 'test/data/cube.dat'
    opt%output = 'build/no_such_folder/cube.h5'
    call run_feps(opt, summary, run_error, count_steps)
    call check(error, allocated(run_error), 'a missing folder is refused')
    if (allocated(error)) return
    call check(error, run_error%code == err_input .and. &
               index(run_error%message, 'cannot create it: no folder "build/no_such_folder"') > 0, run_error%message)
  end subroutine test_output_folder_missing

  !> Stages are named in messages, progress lines and /steps: a second one of a name is refused.
  subroutine test_stage_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/stage_twice.dat', err_input, &
                        [character(len=60) :: 'stage_twice.dat:26: field 2:', &
                         'STAGE "load" is defined twice (first at line 25)'], error, check_only=.true.)
  end subroutine test_stage_twice

  subroutine test_node_out_of_range(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/node_out_of_range.dat', err_input, &
                        [character(len=40) :: 'node_out_of_range.dat:9:', '99'], error)
  end subroutine test_node_out_of_range

  !> A mistyped repeat count is refused before any node is generated (it used to fill the
  !! machine's memory).
  subroutine test_repeat_too_large(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/repeat_too_large.dat', err_input, &
                        [character(len=60) :: 'repeat_too_large.dat:5: field 2:', &
                         'repeat count 100000000 is outside the allowed range', '-20000000..20000000'], error)
  end subroutine test_repeat_too_large

  !> Integer fields are range-checked before any arithmetic (issue 24: STEPS=2147483647 ran 16 s
  !! and ended with an internal message; steps adding up past the integer range ended with a
  !! negative step number after the whole run).
  subroutine test_steps_out_of_range(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/steps_out_of_range.dat', err_input, &
                        [character(len=70) :: 'steps_out_of_range.dat:24: field 3:', &
                         'STEPS 2147483647 is outside the allowed range 1..10000000'], error, before_first_step=.true.)
  end subroutine test_steps_out_of_range

  subroutine test_steps_total_too_large(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/steps_total_too_large.dat', err_input, &
                        [character(len=80) :: 'steps_total_too_large.dat:25: field 3:', &
                         'steps add up to 12000000, more than feps numbers in one run (10000000)'], error, &
                        before_first_step=.true.)
  end subroutine test_steps_total_too_large

  subroutine test_maxit_out_of_range(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/maxit_out_of_range.dat', err_input, &
                        [character(len=70) :: 'maxit_out_of_range.dat:24: field 4:', &
                         'MAXIT 2147483647 is outside the allowed range 1..1000'], error)
  end subroutine test_maxit_out_of_range

  subroutine test_cutbacks_out_of_range(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/cutbacks_out_of_range.dat', err_input, &
                        [character(len=70) :: 'cutbacks_out_of_range.dat:24: field 4:', &
                         'CUTBACKS 1000000 is outside the allowed range 0..50'], error)
  end subroutine test_cutbacks_out_of_range

  subroutine test_subnormal_number(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/subnormal_number.dat', err_input, &
                        [character(len=70) :: 'subnormal_number.dat:15: field 4:', &
                         'number "1e-320" is out of range'], error, before_first_step=.true.)
  end subroutine test_subnormal_number

  !> The error names the line the field is on (issue 24: it named the record's first line).
  subroutine test_continuation_field_line(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/continuation_field_line.dat', err_input, &
                        [character(len=70) :: 'continuation_field_line.dat:26: field 5:', &
                         'expected a number, got "1x0."'], error)
  end subroutine test_continuation_field_line

  subroutine test_element_repeat_too_large(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/element_repeat_too_large.dat', err_input, &
                        [character(len=60) :: 'element_repeat_too_large.dat:12: field 2:', &
                         'repeat count 30000000 is outside the allowed range', '-20000000..20000000'], error)
  end subroutine test_element_repeat_too_large

  subroutine test_node_number_too_large(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/node_number_too_large.dat', err_input, &
                        [character(len=60) :: 'node_number_too_large.dat:16: field 2:', &
                         'node number 2000000000 is larger than feps reads (20000000)'], error)
  end subroutine test_node_number_too_large

  subroutine test_tension_rule_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/tension_rule_unknown.dat', err_input, &
                        [character(len=60) :: 'tension_rule_unknown.dat:14: field 9:', 'material concrete', &
                         'TENSION = "sideways"', 'PROPORTIONAL', 'CLOSEST-POINT'], error)
  end subroutine test_tension_rule_unknown

  !> An elastic material used to ignore parameters it does not know.
  subroutine test_tension_on_elastic(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/tension_on_elastic.dat', err_input, &
                        [character(len=60) :: 'tension_on_elastic.dat:14: field 6:', 'material concrete', &
                         'unknown parameter TENSION', '(expected E, NU, G, GAMMA, K0)'], error)
  end subroutine test_tension_on_elastic

  !> E and G together used to keep E and ignore G. The second of the two (G) is named.
  subroutine test_elastic_e_and_g(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/elastic_e_and_g.dat', err_input, &
                        [character(len=60) :: 'elastic_e_and_g.dat:15: field 6:', 'material steel', &
                         'give only one of E and G'], error)
  end subroutine test_elastic_e_and_g

  !> A key given twice used to keep the first value.
  subroutine test_material_key_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/material_key_twice.dat', err_input, &
                        [character(len=60) :: 'material_key_twice.dat:15: field 6:', &
                         'material steel: NU is given twice (fields 5 and 6)'], error)
  end subroutine test_material_key_twice

  !> Names become HDF5 groups: a slash used to stop the run with exit 1 when the results were
  !! written (for a material, after the whole analysis).
  subroutine test_material_name_slash(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/material_name_slash.dat', err_input, &
                        [character(len=60) :: 'material_name_slash.dat:15: field 2:', 'the material name "st/eel"', &
                         'may not contain /'], error)
  end subroutine test_material_name_slash

  !> G = -5 with NU = 0.3 used to be reported as "E = -13.0000", a value the deck never gave.
  subroutine test_elastic_g_negative(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/elastic_g_negative.dat', err_input, &
                        [character(len=60) :: 'elastic_g_negative.dat:15: field 4:', 'material steel', &
                         'G = -5.00000 must be positive and finite'], error, absent=['E = '])
  end subroutine test_elastic_g_negative

  subroutine test_concrete_gf_negative(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_gf_negative.dat', err_input, &
                        [character(len=60) :: 'concrete_gf_negative.dat:15: field 7:', 'material concrete', &
                         'GF = -0.100000 must be positive and finite'], error)
  end subroutine test_concrete_gf_negative

  subroutine test_concrete_fc_below_ft(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_fc_below_ft.dat', err_input, &
                        [character(len=60) :: 'concrete_fc_below_ft.dat:15: field 8:', 'material concrete', &
                         'FC = 2.00000 must exceed FT = 3.00000'], error)
  end subroutine test_concrete_fc_below_ft

  subroutine test_concrete_fc_negative(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_fc_negative.dat', err_input, &
                        [character(len=60) :: 'concrete_fc_negative.dat:15: field 8:', 'material concrete', &
                         'FC = -30.0000 must be positive and finite'], error)
  end subroutine test_concrete_fc_negative

  subroutine test_concrete_phi_out_of_range(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_phi_out_of_range.dat', err_input, &
                        [character(len=60) :: 'concrete_phi_out_of_range.dat:15: field 9:', 'material concrete', &
                         'PHI = 95.0000 must lie in (0, 90) degrees'], error)
  end subroutine test_concrete_phi_out_of_range

  subroutine test_concrete_psi_above_phi(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_psi_above_phi.dat', err_input, &
                        [character(len=60) :: 'concrete_psi_above_phi.dat:15: field 10:', 'material concrete', &
                         'PSI = 50.0000 must lie in [0, PHI]'], error)
  end subroutine test_concrete_psi_above_phi

  subroutine test_concrete_phi_without_fc(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_phi_without_fc.dat', err_input, &
                        [character(len=60) :: 'concrete_phi_without_fc.dat:15: field 8:', 'material concrete', &
                         'PHI needs FC'], error)
  end subroutine test_concrete_phi_without_fc

  subroutine test_concrete_fc_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_fc_twice.dat', err_input, &
                        [character(len=60) :: 'concrete_fc_twice.dat:15: field 9:', 'material concrete', &
                         'FC is given twice (fields 8 and 9)'], error)
  end subroutine test_concrete_fc_twice

  subroutine test_concrete_softening_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_softening_unknown.dat', err_input, &
                        [character(len=60) :: 'concrete_softening_unknown.dat:15: field 8:', 'material concrete', &
                         'SOFTENING = "bilinear"', 'LINEAR (the default) or EXPONENTIAL'], error)
  end subroutine test_concrete_softening_unknown

  subroutine test_concrete_damage_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_damage_unknown.dat', err_input, &
                        [character(len=60) :: 'concrete_damage_unknown.dat:15: field 8:', 'material concrete', &
                         'DAMAGE = "anisotropic"', 'ISOTROPIC (the default) or TENSILE'], error)
  end subroutine test_concrete_damage_unknown

  !> 5 mm elements where the crack band may be at most 2 E GF / FT^2 = 0.667 mm: refused before
  !! the first step, at GF's field, naming the element and group (--check too: check_cli.sh).
  subroutine test_concrete_band_too_large(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/concrete_band_too_large.dat', err_input, &
                        [character(len=60) :: 'concrete_band_too_large.dat:15: field 7:', 'material concrete', &
                         'element 1 of group block is 5.00000 mm long', '0.666667 mm allows'], error)
  end subroutine test_concrete_band_too_large

  subroutine test_elastic_g_overflow(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/elastic_g_overflow.dat', err_input, &
                        [character(len=60) :: 'elastic_g_overflow.dat:15: field 4:', 'material steel', &
                         'G = 0.100000E+309 is too large'], error)
  end subroutine test_elastic_g_overflow

  !> The overflow guard of E = 2 G (1 + NU) is tested before the product and must not refuse
  !! a G whose E is finite: G = 1e308 with NU = -0.9 gives E = 2e307 (a factor 2 (1 + NU) = 0.2
  !! below 1, where huge / factor itself would overflow).
  subroutine test_elastic_g_large_nu_negative(error)
    type(error_t), allocatable, intent(out) :: error
    class(material_t), allocatable :: mat
    call new_material(material_spec('steel', 'elastic', [character(len=2) :: 'g', 'nu'], [1.0e308_dp, -0.9_dp]), &
                      mat, error)
    if (allocated(error)) return
    select type (mat)
    type is (linear_elastic_t)
      call check(error, mat%e, 2.0e307_dp, 'E = 2 G (1 + NU)', rel=1.0e-15_dp)
    class default
      call test_failed(error, 'ELASTIC did not give a linear_elastic_t')
    end select
  end subroutine test_elastic_g_large_nu_negative

  subroutine test_elastic_unknown_key(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/elastic_unknown_key.dat', err_input, &
                        [character(len=60) :: 'elastic_unknown_key.dat:15: field 6:', 'material steel', &
                         'unknown parameter PHI (expected E, NU, G, GAMMA, K0)'], error)
  end subroutine test_elastic_unknown_key

  subroutine test_material_kind_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/material_kind_unknown.dat', err_input, &
                        [character(len=60) :: 'material_kind_unknown.dat:15: field 3:', 'material steel', &
                         'unknown material kind "elastick"'], error)
  end subroutine test_material_kind_unknown

  !> FT then C: C (field 9) is the one that makes the record wrong.
  subroutine test_matsuoka_ft_and_c(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/matsuoka_ft_and_c.dat', err_input, &
                        [character(len=60) :: 'matsuoka_ft_and_c.dat:14: field 9:', 'material concrete', &
                         'give only one of FT and C'], error)
  end subroutine test_matsuoka_ft_and_c

  subroutine test_matsuoka_psi_above_phi(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/matsuoka_psi_above_phi.dat', err_input, &
                        [character(len=60) :: 'matsuoka_psi_above_phi.dat:14: field 7:', 'material concrete', &
                         'PSI = 40.0000 must lie in [0, PHI] = [0, 30.0000]'], error)
  end subroutine test_matsuoka_psi_above_phi

  subroutine test_interface_psi_above_phi(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/interface_psi_above_phi.dat', err_input, &
                        [character(len=60) :: 'interface_psi_above_phi.dat:30: field 7:', 'material contact', &
                         'PSI = 40.0000 must lie in [0, PHI] = [0, 30.0000]'], error)
  end subroutine test_interface_psi_above_phi

  subroutine test_bar_area_negative(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/bar_area_negative.dat', err_input, &
                        [character(len=60) :: 'bar_area_negative.dat:12: field 5:', 'material soft', &
                         'A = -10.0000 must be positive and finite'], error)
  end subroutine test_bar_area_negative

  !> A missing key is no one field's fault: the message names the line only.
  subroutine test_bar_area_missing(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/bar_area_missing.dat', err_input, &
                        [character(len=60) :: 'bar_area_missing.dat:12: material soft: A is missing'], error, &
                        absent=['field'])
  end subroutine test_bar_area_missing

  !> Issue 24: a control byte or invalid UTF-8 in a group name made an XDMF file no XML parser
  !! reads; the deck reader refuses it, showing the byte as \xNN.
  subroutine test_group_name_control(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/group_name_control.dat', err_input, &
                        [character(len=70) :: 'group_name_control.dat:8: field 2:', &
                         'the group name "blo\x1bck" has a byte that is no printable text at byte 4'], error)
  end subroutine test_group_name_control

  subroutine test_group_name_not_utf8(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/group_name_not_utf8.dat', err_input, &
                        [character(len=70) :: 'group_name_not_utf8.dat:8: field 2:', &
                         'the group name "caf\xe9" has a byte that is no printable text at byte 4'], error)
  end subroutine test_group_name_not_utf8

  subroutine test_utf8_text(error)
    type(error_t), allocatable, intent(out) :: error
    call check(error, utf8_text_length('b' // achar(195) // achar(169) // 'ton') == 6, 'UTF-8 text is printable')
    if (allocated(error)) return
    call check(error, utf8_text_length('ab' // achar(9)) == 2, 'a tab is a control character')
    if (allocated(error)) return
    call check(error, utf8_text_length('a' // achar(192) // achar(175)) == 1, 'an overlong form is no UTF-8')
    if (allocated(error)) return
    call check(error, utf8_text_length(achar(237) // achar(160) // achar(128)) == 0, 'a surrogate is no UTF-8')
    if (allocated(error)) return
    call check(error, utf8_text_length('x' // achar(226) // achar(130)) == 1, 'a cut sequence is no UTF-8')
    if (allocated(error)) return
    call check(error, utf8_text_length(achar(194) // achar(133)) == 0, 'U+0085 is a C1 control')
    if (allocated(error)) return
    call check(error, shown('a' // achar(27) // 'b') == 'a\x1bb', 'shown: ' // shown('a' // achar(27) // 'b'))
  end subroutine test_utf8_text

  subroutine test_group_name_slash(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/group_name_slash.dat', err_input, &
                        [character(len=60) :: 'group_name_slash.dat:8: field 2:', 'the group name "bl/ock"', &
                         'may not contain /'], error)
  end subroutine test_group_name_slash

  subroutine test_duplicate_node(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/duplicate_node.dat', err_input, &
                        [character(len=40) :: 'duplicate_node.dat:17:', 'duplicate node 28'], error)
  end subroutine test_duplicate_node

  subroutine test_negative_jacobian(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/negative_jacobian.dat', err_input, &
                        [character(len=40) :: 'negative_jacobian.dat:8:', 'element 1 ', 'Jacobian'], error)
  end subroutine test_negative_jacobian

  subroutine test_face_set_on_bars(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/face_set_on_bars.dat', err_input, &
                        [character(len=40) :: 'face_set_on_bars.dat:14:', 'group bars (bar2) has no faces'], error)
  end subroutine test_face_set_on_bars

  subroutine test_undefined_material(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/undefined_material.dat', err_input, &
                        [character(len=40) :: 'undefined_material.dat:8: field 4:', 'unobtainium'], error)
  end subroutine test_undefined_material

  !> The list of types in the message is what GROUP accepts (it once left out hex8b): the
  !! element catalog's names, by family.
  subroutine test_element_type_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/element_type_unknown.dat', err_input, &
                        [character(len=60) :: 'element_type_unknown.dat:8: field 3:', 'unknown element type "hex9"', &
                         '(solids: hex8, hex8b, hex20, hex20r, tet4, tet10, wedge6, wedge15, tri6, tri6-6', &
                         'interfaces: interface-quad4, interface-quad4-nodal,', 'interface-line3-nodal;', &
                         'bars: bar2, bar3, bar4, bar5;'], error)
  end subroutine test_element_type_unknown

  subroutine test_fields_csys_cartesian(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/fields_csys_cartesian.dat', err_input, &
                        [character(len=60) :: 'fields_csys_cartesian.dat:24: field 4:', &
                         'CSYS=2 is not a cylindrical system'], error)
  end subroutine test_fields_csys_cartesian

  subroutine test_fields_option_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/fields_option_unknown.dat', err_input, &
                        [character(len=60) :: 'fields_option_unknown.dat:24: field 3:', &
                         'unknown FIELDS option "AXIS=3"'], error)
  end subroutine test_fields_option_unknown

  subroutine test_nu_half(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/nu_half.dat', err_input, &
                        [character(len=40) :: 'nu_half.dat:15: field 5:', 'nu = 0.5'], error)
  end subroutine test_nu_half

  subroutine test_nu_minus_one(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/nu_minus_one.dat', err_input, &
                        [character(len=40) :: 'nu_minus_one.dat:15: field 5:', 'nu = -1.0'], error)
  end subroutine test_nu_minus_one

  subroutine test_rigid_body_mode(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/rigid_body_mode.dat', err_model, &
                        [character(len=40) :: 'rigid_body_mode.dat', 'node ', 'DOF u'], error)
  end subroutine test_rigid_body_mode

  subroutine test_activate_unknown(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/activate_unknown_group.dat', err_input, &
                        [character(len=40) :: 'activate_unknown_group.dat:15:', 'field 4', 'nosuch'], error)
  end subroutine test_activate_unknown

  subroutine test_activate_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/activate_twice.dat', err_input, &
                        [character(len=40) :: 'activate_twice.dat:19:', 'field 5', 'twice', 'second'], error)
  end subroutine test_activate_twice

  subroutine test_activate_orphan(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/activate_orphan_node.dat', err_model, &
                        [character(len=40) :: 'activate_orphan_node.dat', 'stage first', 'node 3', 'DOF ux', &
                         'group new'], error)
  end subroutine test_activate_orphan

  subroutine test_release_before_stage(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/release_before_stage.dat', err_input, &
                        [character(len=40) :: 'release_before_stage.dat:18:', 'after the STAGE record'], error)
  end subroutine test_release_before_stage

  subroutine test_release_not_held(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/release_not_held.dat', err_input, &
                        [character(len=40) :: 'release_not_held.dat:24:', 'node 5, DOF uz', 'stage let_go', &
                         'not held in the stage before (hold)'], error)
  end subroutine test_release_not_held

  subroutine test_release_prescribed(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/release_prescribed.dat', err_input, &
                        [character(len=40) :: 'release_prescribed.dat:25:', 'node 1, DOF uz', 'DISPLACE at line 18'], &
                        error)
  end subroutine test_release_prescribed

  subroutine test_parameter_twice(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/parameter_twice.dat', err_input, &
                        [character(len=40) :: 'parameter_twice.dat:16:', 'field 2', '"E_s" is given twice'], error)
  end subroutine test_parameter_twice

  subroutine test_vary2_alone(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/vary2_alone.dat', err_input, &
                        [character(len=40) :: 'vary2_alone.dat:18: field 4:', 'give VARY= too'], error)
  end subroutine test_vary2_alone

  subroutine test_fix_prescribed(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/fix_prescribed.dat', err_input, &
                        [character(len=40) :: 'fix_prescribed.dat:22:', 'FIX of node 5, DOF uz', 'stage hold', &
                         'DISPLACE at line 21'], error)
  end subroutine test_fix_prescribed

  subroutine test_parameter_bad_name(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/parameter_bad_name.dat', err_input, &
                        [character(len=40) :: 'parameter_bad_name.dat:15:', 'field 3', '"2nd_soil"'], error)
  end subroutine test_parameter_bad_name

  !> Only bars take a prestress.
  subroutine test_prestress_on_solid(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_on_solid.dat', err_input, &
                        [character(len=60) :: 'prestress_on_solid.dat:33:', 'field 2', 'acts on bars', &
                         'group "block" holds hex8'], error)
  end subroutine test_prestress_on_solid

  !> A prestress in a stage before its bars are born would act on nothing.
  subroutine test_prestress_before_birth(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_before_birth.dat', err_input, &
                        [character(len=60) :: 'prestress_before_birth.dat:32:', 'acts in stage load', &
                         'before the group is born (in stage prestress: ACTIVATE'], error)
  end subroutine test_prestress_before_birth

  subroutine test_prestress_force_and_stress(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_force_and_stress.dat', err_input, &
                        [character(len=60) :: 'prestress_force_and_stress.dat:33:', 'field 4', &
                         'one of FORCE= and STRESS='], error)
  end subroutine test_prestress_force_and_stress

  subroutine test_prestress_bare_value(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_bare_value.dat', err_input, &
                        [character(len=60) :: 'prestress_bare_value.dat:33:', 'field 3', &
                         'expected FORCE=axial force or STRESS=axial stress', 'got "100."'], error)
  end subroutine test_prestress_bare_value

  subroutine test_prestress_overflow(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_overflow.dat', err_input, &
                        [character(len=60) :: 'prestress_overflow.dat:33:', 'field 3', &
                         'STRESS times the area A of material strand overflows'], error)
  end subroutine test_prestress_overflow

  !> Post-tensioned bars are bonded at the start of the next stage: there must be one.
  subroutine test_prestress_bond_last_stage(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_bond_last_stage.dat', err_input, &
                        [character(len=70) :: 'prestress_bond_last_stage.dat:33:', 'field 4', &
                         'bonds it at the start of the next', 'another STAGE follows'], error)
  end subroutine test_prestress_bond_last_stage

  subroutine test_prestress_bond_activate(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_bond_activate.dat', err_input, &
                        [character(len=70) :: 'prestress_bond_activate.dat:33:', 'field 4', &
                         'at the start of stage more, but it is born in stage tension'], error)
  end subroutine test_prestress_bond_activate

  subroutine test_prestress_bond_word(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/prestress_bond_word.dat', err_input, &
                        [character(len=70) :: 'prestress_bond_word.dat:33:', 'field 4', &
                         'BOND is BEFORE', 'not "later"'], error)
  end subroutine test_prestress_bond_word

  !> 1e307 MPa on the cube: the middle top node's force, 2.5e308 N, used to become -Infinity and
  !! the run to write NaN results with exit 0.
  subroutine test_load_overflow(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/load_overflow.dat', err_input, &
                        [character(len=60) :: 'load_overflow.dat:24:', 'PRESSURE on face set top', &
                         'node 23, DOF uz is not finite (-Inf)'], error)
  end subroutine test_load_overflow

  !> Two finite forces of 1e308 N on one node, a reference one and the stage's own.
  subroutine test_stage_load_overflow(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/bad/stage_load_overflow.dat', err_input, &
                        [character(len=60) :: 'stage_load_overflow.dat:27:', 'stage push', &
                         'node 27, DOF uz is not finite (Inf)'], error)
  end subroutine test_stage_load_overflow

  !> Finite loads, but a displacement of 1e311 mm: a numerical failure (exit 1), not bad input,
  !! and no result file of NaN.
  subroutine test_solution_overflow(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_failure('test/data/overflow_solution.dat', err_solver, &
                        [character(len=60) :: 'overflow_solution.dat: stage stage1', 'the solution is not finite at node', &
                         'too large for the stiffness'], error)
  end subroutine test_solution_overflow

  !> cube.dat writes its results (and XDMF) under `out`; a run of a failing deck to the same
  !! name must not leave them there, where they would pass for the failed run's results.
  subroutine test_failed_run_removes_stale(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: run_error
    logical :: exists
    call remove_outputs()
    call run_deck('test/data/cube.dat', error)
    if (allocated(error)) return
    inquire (file=out, exist=exists)
    call check(error, exists, 'the first run wrote its results')
    if (allocated(error)) return
    call run_deck('test/data/overflow_solution.dat', run_error)
    call check(error, allocated(run_error), 'the second run fails')
    if (allocated(error)) return
    inquire (file=out, exist=exists)
    call check(error, .not. exists, 'the earlier results are gone')
    if (allocated(error)) return
    inquire (file='build/test_bad_input.xmf', exist=exists)
    call check(error, .not. exists, 'the earlier XDMF file is gone')
  end subroutine test_failed_run_removes_stale

  !> docs/output-format.md: a deck refused as bad input leaves an earlier run's results alone.
  !! nu = 0.5 (checked when the materials are built) and a rigid-body mode (found by the first
  !! factorization) are refused after the results file was begun: they used to remove cube.dat's
  !! results and XDMF file, while an unknown keyword left them.
  subroutine test_refused_deck_keeps_earlier(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: decks(2) = [character(len=40) :: 'test/data/bad/nu_half.dat', &
                                               'test/data/bad/rigid_body_mode.dat']
    type(error_t), allocatable :: run_error
    logical :: exists(3)
    integer :: i
    do i = 1, size(decks)
      call remove_outputs()
      call run_deck('test/data/cube.dat', error)
      if (allocated(error)) return
      call run_deck(trim(decks(i)), run_error)
      call check(error, allocated(run_error), trim(decks(i)) // ' is refused')
      if (allocated(error)) return
      call check(error, any(run_error%code == [err_input, err_model]), trim(decks(i)) // ': ' // run_error%message)
      if (allocated(error)) return
      inquire (file=out, exist=exists(1))
      inquire (file='build/test_bad_input.xmf', exist=exists(2))
      inquire (file=out // '.part', exist=exists(3))
      call check(error, exists(1) .and. exists(2) .and. .not. exists(3), trim(decks(i)) // &
                 ': the earlier results and XDMF file are still there, and no .part file')
      if (allocated(error)) return
      deallocate (run_error)
    end do
  end subroutine test_refused_deck_keeps_earlier

  !> A REPORT's sections depend on the mesh only: they used to be looked for after the whole
  !! analysis, whose results were then thrown away, and --check passed the deck.
  subroutine test_report_no_section(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=60), parameter :: pieces(3) = [character(len=60) :: 'report_no_section.dat:26:', &
      'REPORT t: group block', 'has no node on the section z = 7']
    call expect_failure('test/data/bad/report_no_section.dat', err_input, pieces, error, before_first_step=.true.)
    if (.not. allocated(error)) call expect_failure('test/data/bad/report_no_section.dat', err_input, pieces, &
                                                    error, check_only=.true.)
  end subroutine test_report_no_section

  subroutine test_report_ring_span(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=60), parameter :: pieces(2) = [character(len=60) :: 'report_ring_span.dat:25:', &
      'REPORT top: FROM/TO lie outside the ring of nodes']
    call expect_failure('test/data/bad/report_ring_span.dat', err_input, pieces, error, before_first_step=.true.)
    if (.not. allocated(error)) call expect_failure('test/data/bad/report_ring_span.dat', err_input, pieces, &
                                                    error, check_only=.true.)
  end subroutine test_report_ring_span

  !> A node at x = 2e308 (Infinity): the run used to stop only when the writer refused the mesh
  !! (exit 1), and --check at a load made of NaN; now both name the node as bad input.
  subroutine test_coordinates_overflow(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=60), parameter :: pieces(2) = [character(len=60) :: 'coordinates_overflow.dat: node 3:', &
      'its coordinate x is not finite (Inf)']
    call expect_failure('test/data/bad/coordinates_overflow.dat', err_input, pieces, error)
    if (.not. allocated(error)) call expect_failure('test/data/bad/coordinates_overflow.dat', err_input, pieces, &
                                                    error, check_only=.true.)
  end subroutine test_coordinates_overflow

  !> A unit slip is a warning, not an error: E outside 1 .. 1e6 MPa for every material with a
  !! modulus, and a Matsuoka material whose E is so small beside f_t that it would reach f_t at a
  !! strain above 5 % (E = 31.7 for 31.7 GPa with f_t = 5 MPa: 0.158). Plausible values say nothing.
  subroutine test_unit_warnings(error)
    type(error_t), allocatable, intent(out) :: error
    call expect('elastic', [character(len=4) :: 'e', 'nu'], [2.0e11_dp, 0.3_dp], 'above 1e6 MPa')
    if (allocated(error)) return
    call expect('elastic', [character(len=4) :: 'g', 'nu'], [0.3_dp, 0.25_dp], 'below 1 MPa')
    if (allocated(error)) return
    call expect('elastic', [character(len=4) :: 'e', 'nu'], [40.0_dp, 0.3_dp], '')   ! a soft soil
    if (allocated(error)) return
    call expect('elastic', [character(len=4) :: 'e', 'nu'], [2.1e5_dp, 0.3_dp], '')  ! steel
    if (allocated(error)) return
    call expect('bar', [character(len=4) :: 'e', 'a'], [2.0e8_dp, 10.0_dp], 'above 1e6 MPa')
    if (allocated(error)) return
    call expect('matsuoka', [character(len=4) :: 'e', 'nu', 'phi', 'psi', 'ft'], &
                [31.7_dp, 0.22_dp, 54.9_dp, 54.9_dp, 5.0_dp], 'reaches f_t at a strain of 1.577E-01')
    if (allocated(error)) return
    call expect('matsuoka', [character(len=4) :: 'e', 'nu', 'phi', 'psi', 'ft'], &
                [31700.0_dp, 0.22_dp, 54.9_dp, 54.9_dp, 5.0_dp], '')                 ! thesis CR concrete
  contains
    subroutine expect(kind, keys, values, text)
      character(len=*), intent(in) :: kind, keys(:), text
      real(dp), intent(in) :: values(:)
      class(material_t), allocatable :: material
      character(len=:), allocatable :: warning, key
      call new_material(material_spec('m', kind, keys, values), material, error)
      if (allocated(error)) return
      call material%unit_warning(warning, key)
      if (len(text) == 0 .and. len(warning) > 0) then
        call test_failed(error, kind // ': unexpected warning "' // warning // '"')
      else if (len(text) > 0 .and. index(warning, text) == 0) then
        call test_failed(error, kind // ': expected a warning with "' // text // '", got "' // warning // '"')
      end if
    end subroutine expect
  end subroutine test_unit_warnings

end module test_bad_input
