!> Tests of the record reader and the DATAIN mesh reader: Table 2.1 read verbatim, small
!! meshes built by hand, and one test per error kind checking file, line and field.
module test_datain
  use feps_kinds, only: dp, deg2rad
  use feps_error, only: err_input, err_input_file
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_coordinate_system, only: coordinate_system_t, default_coordinate_systems, cylindrical_about
  use feps_records, only: record_t, records_from_text, keyword, nfields, field_text, &
                          field_real, field_int, get_option
  use feps_datain, only: datain_mesh_t, datain_read_file, datain_read_records, datain_read_block, &
                         datain_check, is_datain_record
  implicit none
  private

  public :: collect_datain

  character(len=*), parameter :: table2_1 = '../shared/benchmarks/table2_1.datain'
  character(len=*), parameter :: name = 'test.datain'

contains

  subroutine collect_datain(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("table2_1_counts", test_table_counts), &
      new_unittest("table2_1_connectivity", test_table_connectivity), &
      new_unittest("table2_1_coordinates", test_table_coordinates), &
      new_unittest("block_2d", test_block_2d), &
      new_unittest("block_cartesian", test_block_cartesian), &
      new_unittest("deck_cylindrical_system", test_deck_system), &
      new_unittest("two_node_and_element_blocks", test_two_blocks), &
      new_unittest("ambiguous_a_record", test_ambiguous), &
      new_unittest("read_block_inline", test_read_block_inline), &
      new_unittest("records_lexical_rules", test_records_rules), &
      new_unittest("records_fields_and_options", test_records_fields), &
      new_unittest("elements_negative_repeat", test_elements_negative), &
      new_unittest("error_empty_field", test_error_empty_field), &
      new_unittest("error_cannot_open", test_error_cannot_open), &
      new_unittest("error_empty_file", test_error_empty_file), &
      new_unittest("error_unknown_record", test_error_unknown_record), &
      new_unittest("error_missing_field", test_error_missing_field), &
      new_unittest("error_non_numeric", test_error_non_numeric), &
      new_unittest("error_zero_repeat", test_error_zero_repeat), &
      new_unittest("error_truncated", test_error_truncated), &
      new_unittest("error_after_final_e", test_error_after_final_e), &
      new_unittest("error_unknown_system", test_error_unknown_system), &
      new_unittest("error_wrong_field_count", test_error_field_count), &
      new_unittest("error_node_out_of_range", test_error_node_range) &
      ]
  end subroutine collect_datain

  ! ---- helpers ----

  !> Read a mesh from in-memory lines (as file `name`) with the three DATAIN systems.
  subroutine mesh_from_lines(lines, mesh, error)
    character(len=*), intent(in) :: lines(:)
    type(datain_mesh_t), intent(inout) :: mesh
    type(error_t), allocatable, intent(out) :: error
    type(record_t), allocatable :: records(:)
    call records_from_text(name, lines, records, error)
    if (allocated(error)) return
    call datain_read_records(records, default_coordinate_systems(), mesh, error)
  end subroutine mesh_from_lines

  !> Fail unless `got` is an error of category `code` whose message starts with `prefix`
  !! (file, line and field) and contains `words`.
  subroutine expect_error(error, got, code, prefix, words)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable, intent(in) :: got
    integer, intent(in) :: code
    character(len=*), intent(in) :: prefix, words
    if (.not. allocated(got)) then
      call test_failed(error, 'expected an error "' // prefix // ' ... ' // words // '", got none')
      return
    end if
    call check(error, got%code, code, 'error category of "' // got%message // '"')
    if (allocated(error)) return
    call check(error, index(got%message, prefix) == 1, 'message "' // got%message // &
               '" should start with "' // prefix // '"')
    if (allocated(error)) return
    call check(error, index(got%message, words) > 0, 'message "' // got%message // &
               '" should contain "' // words // '"')
  end subroutine expect_error

  !> Error from reading `lines` as a whole mesh and checking it.
  subroutine mesh_error(lines, got)
    character(len=*), intent(in) :: lines(:)
    type(error_t), allocatable, intent(out) :: got
    type(datain_mesh_t) :: mesh
    call mesh_from_lines(lines, mesh, got)
    if (allocated(got)) return
    call datain_check(mesh, got)
  end subroutine mesh_error

  subroutine check_ints(error, actual, expected, what)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in) :: actual(:), expected(:)
    character(len=*), intent(in) :: what
    integer :: i
    call check(error, size(actual), size(expected), what // ': length')
    if (allocated(error)) return
    do i = 1, size(expected)
      call check(error, actual(i), expected(i), what // ': entry')
      if (allocated(error)) return
    end do
  end subroutine check_ints

  subroutine check_point(error, actual, expected, what)
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in) :: actual(3), expected(3)
    character(len=*), intent(in) :: what
    integer :: i
    do i = 1, 3
      call check(error, actual(i), expected(i), what, abs=1.0e-10_dp)
      if (allocated(error)) return
    end do
  end subroutine check_point

  subroutine read_table(mesh, error)
    type(datain_mesh_t), intent(out) :: mesh
    type(error_t), allocatable, intent(out) :: error
    call datain_read_file(table2_1, default_coordinate_systems(), mesh, error)
    if (allocated(error)) return
    call datain_check(mesh, error)
  end subroutine read_table

  ! ---- Table 2.1 ----

  !> Counts stated by the thesis: 3375 nodes = 5 x 25 x 27, 2496 elements = 4 x 24 x 26.
  subroutine test_table_counts(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    call read_table(mesh, error)
    if (allocated(error)) return
    call check(error, mesh%nnode, 5 * 25 * 27, 'nodes')
    if (allocated(error)) return
    call check(error, size(mesh%coords, 2), 3375, 'coordinate columns')
    if (allocated(error)) return
    call check(error, size(mesh%blocks), 1, 'element blocks')
    if (allocated(error)) return
    call check(error, mesh%blocks(1)%nodes_per_element, 8, 'nodes per element')
    if (allocated(error)) return
    call check(error, mesh%nelements(), 4 * 24 * 26, 'elements')
    if (allocated(error)) return
    call check(error, mesh%blocks(1)%line, 18, 'line of the element A record')
    if (allocated(error)) return
    call check(error, mesh%blocks(1)%file == table2_1, 'file of the element block')
  end subroutine test_table_counts

  !> First and last elements as printed in the thesis; element (i, j, k) in closed form.
  subroutine test_table_connectivity(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    integer :: i, j, k, e, base
    call read_table(mesh, error)
    if (allocated(error)) return
    associate (conn => mesh%blocks(1)%connectivity)
      call check_ints(error, conn(:, 1), [1, 2, 7, 6, 126, 127, 132, 131], 'first element')
      if (allocated(error)) return
      call check_ints(error, conn(:, 2496), [3244, 3245, 3250, 3249, 3369, 3370, 3375, 3374], 'last element')
      if (allocated(error)) return
      ! element (i, j, k), i fastest: its first node is i + 5 (j - 1) + 125 (k - 1)
      do k = 1, 26
        do j = 1, 24
          do i = 1, 4
            e = i + 4 * (j - 1) + 96 * (k - 1)
            base = i + 5 * (j - 1) + 125 * (k - 1)
            call check_ints(error, conn(:, e), [base, base + 1, base + 6, base + 5, &
                            base + 125, base + 126, base + 131, base + 130], 'element (i,j,k)')
            if (allocated(error)) return
          end do
        end do
      end do
    end associate
  end subroutine test_table_connectivity

  !> Nodes on the (r, theta, z) grid of Table 2.1, converted to x = r cos theta, y = r sin theta.
  subroutine test_table_coordinates(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    real(dp), parameter :: theta(25) = [0.0_dp, 5.5_dp, 11.0_dp, 16.5_dp, 22.0_dp, 29.0_dp, 36.0_dp, &
      45.0_dp, 54.0_dp, 63.0_dp, 72.0_dp, 81.0_dp, 90.0_dp, 99.0_dp, 108.0_dp, 117.0_dp, 126.0_dp, &
      135.0_dp, 144.0_dp, 151.0_dp, 158.0_dp, 163.5_dp, 169.0_dp, 174.5_dp, 180.0_dp]
    real(dp), parameter :: z(27) = [0.0_dp, 6.5_dp, 13.0_dp, 20.5_dp, 28.0_dp, 37.0_dp, 46.0_dp, &
      55.0_dp, 64.0_dp, 73.0_dp, 82.0_dp, 91.0_dp, 100.0_dp, 109.0_dp, 118.0_dp, 127.0_dp, 136.0_dp, &
      145.0_dp, 154.0_dp, 164.0_dp, 174.0_dp, 183.0_dp, 192.0_dp, 199.5_dp, 207.0_dp, 213.5_dp, 220.0_dp]
    real(dp) :: r, radius
    integer :: i, j, k, node
    call read_table(mesh, error)
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 1), [75.0_dp, 0.0_dp, 0.0_dp], 'node 1')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 5), [100.0_dp, 0.0_dp, 0.0_dp], 'node 5')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 125), [-100.0_dp, 0.0_dp, 0.0_dp], 'node 125')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 3375), [-100.0_dp, 0.0_dp, 220.0_dp], 'node 3375')
    if (allocated(error)) return
    do k = 1, 27
      do j = 1, 25
        do i = 1, 5
          node = i + 5 * (j - 1) + 125 * (k - 1)
          r = 75.0_dp + 6.25_dp * (i - 1)
          call check_point(error, mesh%coords(:, node), [r * cos(theta(j) * deg2rad), &
                           r * sin(theta(j) * deg2rad), z(k)], 'node on the (r, theta, z) grid')
          if (allocated(error)) return
          radius = hypot(mesh%coords(1, node), mesh%coords(2, node))
          call check(error, radius >= 75.0_dp - 1.0e-10_dp .and. radius <= 100.0_dp + 1.0e-10_dp, &
                     'node radius within [75, 100]')
          if (allocated(error)) return
        end do
      end do
    end do
  end subroutine test_table_coordinates

  ! ---- small meshes ----

  !> System 1: x, y with z = 0; 3 x 2 nodes, two quadrilaterals.
  subroutine test_block_2d(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    integer :: node
    call mesh_from_lines([character(len=40) :: &
      'A, 1, 10., 20.', '%, 3, 1.5, 0.', '%, 2, 0., 2.', 'E', &
      'A, 4, 1, 2, 5, 4', '%, 2, *, 4, 1', 'E', 'E'], mesh, error)
    if (allocated(error)) return
    call datain_check(mesh, error)
    if (allocated(error)) return
    call check(error, mesh%nnode, 6, '2D nodes')
    if (allocated(error)) return
    do node = 1, 6
      call check_point(error, mesh%coords(:, node), [10.0_dp + 1.5_dp * mod(node - 1, 3), &
                       20.0_dp + 2.0_dp * ((node - 1) / 3), 0.0_dp], '2D node')
      if (allocated(error)) return
    end do
    call check(error, mesh%nelements(), 2, '2D elements')
    if (allocated(error)) return
    call check_ints(error, mesh%blocks(1)%connectivity(:, 2), [2, 3, 6, 5], 'second quadrilateral')
  end subroutine test_block_2d

  !> System 2 in three directions, then the last direction continued with another increment.
  subroutine test_block_cartesian(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    integer :: node, i, j, k
    real(dp) :: zk
    call mesh_from_lines([character(len=40) :: &
      'a, 2, 1., 2., 3.', '%, 2, 1., 0., 0.', '%, 2, 0., 1., 0.', '%, 2, 0., 0., 1.', &
      '%, -2, 0., 0., 2.5', 'e', 'e'], mesh, error)
    if (allocated(error)) return
    call check(error, mesh%nnode, 16, 'nodes: 2 x 2 x (2 + 2)')
    if (allocated(error)) return
    ! z layers: 3, 4, then 4 + 2.5 and 4 + 5
    do k = 1, 4
      zk = merge(3.0_dp + (k - 1), 4.0_dp + 2.5_dp * (k - 2), k <= 2)
      do j = 1, 2
        do i = 1, 2
          node = i + 2 * (j - 1) + 4 * (k - 1)
          call check_point(error, mesh%coords(:, node), [real(i, dp), real(j + 1, dp), zk], &
                           'Cartesian node')
          if (allocated(error)) return
        end do
      end do
    end do
    call check(error, .not. allocated(mesh%blocks), 'no element blocks')
  end subroutine test_block_cartesian

  !> A deck-defined system 4: cylindrical about the global x axis through (0, 0, 5),
  !! theta = 0 along global y. Node (r, theta, z) -> (z, r cos theta, 5 + r sin theta).
  subroutine test_deck_system(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    type(coordinate_system_t) :: systems(4)
    type(record_t), allocatable :: records(:)
    systems(1:3) = default_coordinate_systems()
    systems(4) = cylindrical_about([0.0_dp, 0.0_dp, 5.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], &
                                   [0.0_dp, 1.0_dp, 0.0_dp])
    call records_from_text(name, [character(len=30) :: 'A, 4, 2., 0., 0.', '%, 3, 0., 45., 1.', &
                                  'E', 'E'], records, error)
    if (allocated(error)) return
    call datain_read_records(records, systems, mesh, error)
    if (allocated(error)) return
    call check(error, mesh%nnode, 3, 'nodes')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 1), [0.0_dp, 2.0_dp, 5.0_dp], 'node 1')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 2), [1.0_dp, sqrt(2.0_dp), 5.0_dp + sqrt(2.0_dp)], 'node 2')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 3), [2.0_dp, 0.0_dp, 7.0_dp], 'node 3')
  end subroutine test_deck_system

  !> Node numbers continue across node blocks, element numbers across element blocks.
  subroutine test_two_blocks(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    type(error_t), allocatable :: got
    character(len=40), parameter :: lines(12) = [character(len=40) :: &
      'A, 2, 0., 0., 0.', '%, 3, 1., 0., 0.', 'E', &
      'A, 2, 0., 1., 0.', '%, 3, 1., 0., 0.', 'E', &
      'A, 2, 1, 2', '%, 2, *, *, 1', 'E', &
      'A, 4, 1, 2, 5, 4', '%, 2, *, 4, 1', 'E']
    call mesh_from_lines([lines, [character(len=40) :: 'E']], mesh, error)
    if (allocated(error)) return
    call datain_check(mesh, error)
    if (allocated(error)) return
    call check(error, mesh%nnode, 6, 'nodes in both blocks')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 4), [0.0_dp, 1.0_dp, 0.0_dp], 'first node of block 2')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 6), [2.0_dp, 1.0_dp, 0.0_dp], 'last node of block 2')
    if (allocated(error)) return
    call check(error, size(mesh%blocks), 2, 'element blocks')
    if (allocated(error)) return
    call check(error, mesh%nelements(), 4, 'elements in both blocks')
    if (allocated(error)) return
    call check_ints(error, mesh%blocks(1)%connectivity(:, 2), [2, 3], 'line element 2')
    if (allocated(error)) return
    call check_ints(error, mesh%blocks(2)%connectivity(:, 2), [2, 3, 6, 5], 'quad element 4')
    if (allocated(error)) return
    call check(error, mesh%blocks(2)%line, 10, 'line of the second element block')
    if (allocated(error)) return
    ! element numbering continues: the second block's first element is element 3
    call mesh_error([lines(1:9), [character(len=40) :: 'A, 4, 1, 2, 9, 4', 'E', 'E']], got)
    call expect_error(error, got, err_input, name // ':10: ', 'element 3 (element 1 of the block), slot 3')
  end subroutine test_two_blocks

  !> `A, 3, 75, 0, 0` fits both readings: a node block in an empty mesh, else elements.
  subroutine test_ambiguous(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    call mesh_from_lines([character(len=30) :: 'A, 3, 75, 0, 0', '%, 2, 0, 90, 0', 'E', &
                          'A, 3, 1, 2, 1', 'E', 'E'], mesh, error)
    if (allocated(error)) return
    call check(error, mesh%nnode, 2, 'nodes of the integer-only node block')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 2), [0.0_dp, 75.0_dp, 0.0_dp], 'node at 90 degrees')
    if (allocated(error)) return
    call check(error, size(mesh%blocks), 1, 'element block after nodes')
    if (allocated(error)) return
    call check_ints(error, mesh%blocks(1)%connectivity(:, 1), [1, 2, 1], 'element of 3 nodes')
    if (allocated(error)) return
    ! with a decimal point it is a node block even when the mesh has nodes
    call mesh_from_lines([character(len=30) :: 'A, 3, 10., 0, 5', 'E', 'E'], mesh, error)
    if (allocated(error)) return
    call check(error, mesh%nnode, 3, 'appended node')
    if (allocated(error)) return
    call check_point(error, mesh%coords(:, 3), [10.0_dp, 0.0_dp, 5.0_dp], 'appended node')
  end subroutine test_ambiguous

  !> A block inside other records: datain_read_block stops after its E record.
  subroutine test_read_block_inline(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh
    type(record_t), allocatable :: records(:)
    integer :: pos
    call records_from_text(name, [character(len=40) :: 'nodes, material=steel', &
      'A, 2, 0., 0., 0.', '%, 4, 0.5, 0., 0.', 'E', 'solve'], records, error)
    if (allocated(error)) return
    call check(error, .not. is_datain_record(records(1)) .and. is_datain_record(records(2)) .and. &
               is_datain_record(records(3)) .and. is_datain_record(records(4)), 'is_datain_record')
    if (allocated(error)) return
    pos = 2
    call datain_read_block(records, pos, default_coordinate_systems(), mesh, error)
    if (allocated(error)) return
    call check(error, pos, 5, 'position after the block')
    if (allocated(error)) return
    call check(error, mesh%nnode, 4, 'nodes')
    if (allocated(error)) return
    call check(error, mesh%coords(1, 4), 1.5_dp, 'x of node 4', abs=1.0e-14_dp)
  end subroutine test_read_block_inline

  ! ---- records ----

  !> Comments, blank lines, tabs, trailing commas, continuation lines.
  subroutine test_records_rules(error)
    type(error_t), allocatable, intent(out) :: error
    type(record_t), allocatable :: records(:)
    call records_from_text(name, [character(len=40) :: &
      '! a comment line', '', &
      'A, 8, 1, 2, 7, 6,   ! first four nodes', &
      '126, 127,' // achar(9) // '132, 131,', &
      '   ', &
      '%,' // achar(9) // '4, *, 8, 1', &
      '-1.5e2, +3, .5', &
      'E,'], records, error)
    if (allocated(error)) return
    call check(error, size(records), 3, 'records')
    if (allocated(error)) return
    call check(error, nfields(records(1)), 10, 'fields of the continued record')
    if (allocated(error)) return
    call check(error, records(1)%line, 3, 'first line of record 1')
    if (allocated(error)) return
    call check(error, records(1)%fields(6)%line, 3, 'line of field 6')
    if (allocated(error)) return
    call check(error, records(1)%fields(7)%line, 4, 'line of field 7')
    if (allocated(error)) return
    call check(error, field_text(records(1), 9) == '132', 'tab is a blank: ' // field_text(records(1), 9))
    if (allocated(error)) return
    call check(error, field_text(records(1), 10) == '131', 'last field ' // field_text(records(1), 10))
    if (allocated(error)) return
    call check(error, nfields(records(2)), 8, 'record continued by a line of signed numbers')
    if (allocated(error)) return
    call check(error, keyword(records(2)) == '%' .and. field_text(records(2), 2) == '4', 'record 2')
    if (allocated(error)) return
    call check(error, field_text(records(2), 6) == '-1.5e2', 'field 6 of record 2')
    if (allocated(error)) return
    call check(error, nfields(records(3)), 1, 'E, has one field')
    if (allocated(error)) return
    call check(error, records(3)%line, 8, 'line of E')
    if (allocated(error)) return
    call check(error, records(3)%file == name, 'file name')
  end subroutine test_records_rules

  !> Numbers, keywords and key=value options.
  subroutine test_records_fields(error)
    type(error_t), allocatable, intent(out) :: error
    type(record_t), allocatable :: records(:)
    type(error_t), allocatable :: got
    character(len=:), allocatable :: value
    logical :: found
    real(dp) :: x
    integer :: i, where
    call records_from_text(name, [character(len=60) :: &
      'group, Material = Concrete, 12, -3.25D1, 7, x1'], records, error)
    if (allocated(error)) return
    call check(error, keyword(records(1)) == 'GROUP', 'keyword upper-cased')
    if (allocated(error)) return
    call get_option(records(1), 'MATERIAL', value, found, where)
    call check(error, found .and. value == 'Concrete' .and. where == 2, 'option material=' // value)
    if (allocated(error)) return
    call get_option(records(1), 'thickness', value, found)
    call check(error, .not. found .and. len(value) == 0, 'missing option')
    if (allocated(error)) return
    call field_int(records(1), 3, i, error, 1, 12)
    if (allocated(error)) return
    call check(error, i, 12, 'integer field')
    if (allocated(error)) return
    call field_real(records(1), 4, x, error)
    if (allocated(error)) return
    call check(error, x, -32.5_dp, 'real field with D exponent', rel=1.0e-15_dp)
    if (allocated(error)) return
    call field_real(records(1), 5, x, error)
    if (allocated(error)) return
    call check(error, x, 7.0_dp, 'integer text as a real', rel=1.0e-15_dp)
    if (allocated(error)) return
    call field_int(records(1), 4, i, got, -huge(1), huge(1))
    call expect_error(error, got, err_input, name // ':1: field 4: ', 'expected an integer')
    if (allocated(error)) return
    call field_real(records(1), 6, x, got)
    call expect_error(error, got, err_input, name // ':1: field 6: ', "expected a real number, got 'x1'")
    if (allocated(error)) return
    call field_int(records(1), 7, i, got, -huge(1), huge(1))
    call expect_error(error, got, err_input, name // ':1: field 7: ', 'missing')
  end subroutine test_records_fields

  !> n < 0 in an element block continues the current direction: with the same increment it
  !! equals a longer n > 0 repeat; with a new one it adds on top of the offset reached.
  subroutine test_elements_negative(error)
    type(error_t), allocatable, intent(out) :: error
    type(datain_mesh_t) :: mesh, reference, partial
    integer :: e
    call mesh_from_lines([character(len=30) :: 'A, 4, 1, 2, 5, 4', '%, 2, *, 4, 1', &
      '%, 2, *, 4, 3', '%, -2, *, 4, 3', '%, -1, *, 4, 5', 'E', 'E'], mesh, error)
    if (allocated(error)) return
    call mesh_from_lines([character(len=30) :: 'A, 4, 1, 2, 5, 4', '%, 2, *, 4, 1', &
      '%, 4, *, 4, 3', 'E', 'E'], reference, error)
    if (allocated(error)) return
    call check(error, mesh%nelements(), 10, 'elements: 2 x (2 + 2 + 1)')
    if (allocated(error)) return
    do e = 1, 8
      call check_ints(error, mesh%blocks(1)%connectivity(:, e), reference%blocks(1)%connectivity(:, e), &
                      'continued direction equals a longer repeat')
      if (allocated(error)) return
    end do
    ! last layer: offset 3 + 2 x 3 + 5 = 14 from the first
    call check_ints(error, mesh%blocks(1)%connectivity(:, 9), [15, 16, 19, 18], 'element 9')
    if (allocated(error)) return
    call check_ints(error, mesh%blocks(1)%connectivity(:, 10), [16, 17, 20, 19], 'element 10')
    if (allocated(error)) return
    ! slots 3..4 only: upper nodes move, lower nodes stay
    call mesh_from_lines([character(len=30) :: 'A, 4, 1, 2, 5, 4', '%, 2, 3, *, 10', &
      '%, -1, 3, 4, 10', 'E', 'E'], partial, error)
    if (allocated(error)) return
    call check_ints(error, partial%blocks(1)%connectivity(:, 3), [1, 2, 25, 24], 'slots 3..4 shifted twice')
  end subroutine test_elements_negative

  ! ---- errors ----

  subroutine test_error_empty_field(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    type(record_t), allocatable :: records(:)
    call records_from_text(name, [character(len=30) :: 'A, 8, 1, 2,', '3,, 4'], records, got)
    call expect_error(error, got, err_input, name // ':2: field 6: ', 'empty field')
    if (allocated(error)) return
    call records_from_text(name, [character(len=30) :: 'E', 'x, 1,,'], records, got)
    call expect_error(error, got, err_input, name // ':2: field 3: ', 'empty field')
  end subroutine test_error_empty_field

  subroutine test_error_cannot_open(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    type(datain_mesh_t) :: mesh
    call datain_read_file('no/such/dir/mesh.datain', default_coordinate_systems(), mesh, got)
    call expect_error(error, got, err_input_file, 'no/such/dir/mesh.datain: ', 'cannot open')
  end subroutine test_error_cannot_open

  !> A file of comments only has no records (read through a real file).
  subroutine test_error_empty_file(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    type(datain_mesh_t) :: mesh
    type(record_t), allocatable :: records(:)
    character(len=*), parameter :: path = 'test_datain_empty.tmp'
    integer :: unit
    open (newunit=unit, file=path, status='replace', action='write')
    write (unit, '(a)') '! nothing but a comment'
    write (unit, '(a)') ''
    close (unit)
    call datain_read_file(path, default_coordinate_systems(), mesh, got)
    open (newunit=unit, file=path, status='old')
    close (unit, status='delete')
    call expect_error(error, got, err_input, path // ': ', 'empty file (no records)')
    if (allocated(error)) return
    call records_from_text(name, [character(len=10) :: '', '  ! x'], records, got)
    call expect_error(error, got, err_input, name // ': ', 'empty file (no records)')
  end subroutine test_error_empty_file

  subroutine test_error_unknown_record(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: '! mesh', 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', &
                     'X, 1', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':4: field 1: ', "unknown record 'X' inside")
    if (allocated(error)) return
    ! an A record before the block is closed
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', 'A, 2, 1., 0., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':2: field 1: ', 'not closed by E')
    if (allocated(error)) return
    ! between blocks
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', 'E', 'nodes', 'E'], got)
    call expect_error(error, got, err_input, name // ':3: field 1: ', "unknown record 'nodes'")
  end subroutine test_error_unknown_record

  subroutine test_error_missing_field(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: '! mesh', 'A,', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':2: field 2: ', 'missing')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '', '%', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':3: field 2: ', 'missing field: expected an integer')
  end subroutine test_error_missing_field

  subroutine test_error_non_numeric(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: 'A, 2, 0., x, 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':1: field 4: ', "expected a real number, got 'x'")
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E', &
                     'A, 2, 1, 2', '%, 2, *, *, q', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':5: field 5: ', "expected an integer, got 'q'")
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E', &
                     'A, 2, 1, 2', '%, 2, a, *, 1', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':5: field 3: ', "slot number or '*'")
  end subroutine test_error_non_numeric

  subroutine test_error_zero_repeat(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 0, 1., 0., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':2: field 2: ', 'zero repeat count')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E', &
                     'A, 2, 1, 2', '%, 0, *, *, 1', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':5: field 2: ', 'zero repeat count')
    if (allocated(error)) return
    ! n < 0 needs a direction to continue
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, -2, 1., 0., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':2: field 2: ', 'no direction to continue')
    if (allocated(error)) return
    ! a count whose nodes could not be numbered
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', &
                     '%, 2000000000, 0., 1., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':3: field 2: ', &
                      'repeat count 2000000000 is outside the allowed range -20000000..20000000')
    if (allocated(error)) return
    ! the most negative integer, whose negation overflows (it crashed the reader, issue 24), in a
    ! node block and in an element block
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', &
                     '%, -2147483648, 1., 0., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':3: field 2: ', &
                      'repeat count -2147483648 is outside the allowed range -20000000..20000000')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E', &
                     'A, 2, 1, 2', '%, 2, *, *, 1', '%, -2147483648, *, *, 1', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':6: field 2: ', &
                      'repeat count -2147483648 is outside the allowed range')
    if (allocated(error)) return
    ! beyond any integer
    call mesh_error([character(len=40) :: 'A, 2, 0., 0., 0.', '%, 99999999999999999999999, 1., 0., 0.', &
                     'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':2: field 2: ', &
                      'repeat count 99999999999999999999999 is outside the allowed range')
    if (allocated(error)) return
    ! an increment, and the shift a repeat adds up from counts and increments within range
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E', &
                     'A, 2, 1, 2', '%, 2, *, *, 2147483647', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':5: field 5: ', &
                      'increment 2147483647 is outside the allowed range -20000000..20000000')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E', &
                     'A, 2, 1, 2', '%, 20000, *, *, 20000', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':5: field 5: ', &
                      'would shift node numbers by 399980000, beyond the largest node number feps reads')
    if (allocated(error)) return
    ! a node number of an A record
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E', &
                     'A, 2, 1, -2147483648', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':4: field 4: ', &
                      'node number -2147483648 is outside the allowed range 1..20000000')
    if (allocated(error)) return
    ! one node past the mesh size limit, counted across node blocks: 3 + 2 x 9999999 = 2e7 + 1
    ! (the second block alone is within it)
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 3, 1., 0., 0.', 'E', &
                     'A, 2, 0., 0., 1.', '%, 2, 1., 0., 0.', '%, 9999999, 0., 1., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':6: field 2: ', &
                      'the mesh would have 20000001 nodes, more than feps reads (20000000)')
  end subroutine test_error_zero_repeat

  !> Records that end inside a block, or before the final E; the line is the last one.
  subroutine test_error_truncated(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', '! end'], got)
    call expect_error(error, got, err_input, name // ':2: ', 'truncated file: the block opened at line 1')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0., 0.', 'E'], got)
    call expect_error(error, got, err_input, name // ':3: ', 'truncated file: the mesh is not closed')
    if (allocated(error)) return
    ! an element record continued on the last line
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', 'E', 'A, 4, 1, 1,', '1, 1'], got)
    call expect_error(error, got, err_input, name // ':4: ', 'truncated file: the block opened at line 3')
  end subroutine test_error_truncated

  subroutine test_error_after_final_e(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', 'E', 'E', '', 'A, 2, 1., 0., 0.'], got)
    call expect_error(error, got, err_input, name // ':5: field 1: ', 'after the final E')
  end subroutine test_error_after_final_e

  subroutine test_error_unknown_system(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: '', 'A, 7, 1., 2., 3.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':2: field 2: ', 'unknown coordinate system 7')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 0, 1, 2, 3', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':1: field 2: ', 'unknown coordinate system 0')
  end subroutine test_error_unknown_system

  subroutine test_error_field_count(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    ! system 1 has two coordinates
    call mesh_error([character(len=30) :: 'A, 1, 0., 0., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':1: ', 'wrong number of fields')
    if (allocated(error)) return
    ! a 3D node repeat needs three increments
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 2, 1., 0.', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':2: ', 'wrong number of fields')
    if (allocated(error)) return
    ! an element block with fewer node numbers than k
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', 'E', 'A, 8, 1, 2, 7, 6', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':3: ', 'wrong number of fields')
    if (allocated(error)) return
    ! an element repeat is %, n, s1, s2, inc
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', 'E', 'A, 2, 1, 1', '%, 2, *, 2', &
                     'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':4: ', 'wrong number of fields')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', 'E,', 'E, 3'], got)
    call expect_error(error, got, err_input, name // ':3: field 2: ', 'wrong number of fields')
  end subroutine test_error_field_count

  subroutine test_error_node_range(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 4, 1., 0., 0.', 'E', '', &
                     'A, 2, 1, 2', '%, 4, *, *, 1', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':5: ', &
                      'element 4 (element 4 of the block), slot 2: node number 5 out of range 1..4')
    if (allocated(error)) return
    call mesh_error([character(len=30) :: 'A, 2, 0., 0., 0.', '%, 4, 1., 0., 0.', 'E', &
                     'A, 2, 2, 1', '%, 2, 2, *, -1', 'E', 'E'], got)
    call expect_error(error, got, err_input, name // ':4: ', 'slot 2: node number 0 out of range')
  end subroutine test_error_node_range

end module test_datain
