!> Tests of the HDF5 results file and its XDMF companion: a small file is written, then read back
!! with the HDF5 API and compared exactly with the values written (all are exact binary fractions).
module test_results_file
  use feps_kinds, only: dp, i8
  use feps_error, only: err_internal, err_solver, err_input, err_io, str
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_results_file, only: results_file_t, step_group_name
  use feps_program, only: run_options_t, run_summary_t, run_feps
  use feps_h5_testing, only: run_and_open, close_and_delete, scratch_path, open_read, dataset_dims, read_real, &
                             read_int, string_attribute, &
                             real_attribute, int_attribute, int64_attribute, file_exists, delete_file, &
                             file_text, occurrences
  use hdf5, only: hid_t, hsize_t, h5fclose_f
  use feps_xdmf, only: write_xdmf, xdmf_group_t, xdmf_step_t
  use feps_files, only: text_file_t, remove_regular_file, file_kind, file_directory, file_special
  implicit none
  private

  public :: collect_results_file

  integer, parameter :: nnode = 12, nelem = 2, npe = 8, ngauss = 8

contains

  subroutine collect_results_file(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("mesh datasets read back", test_mesh_datasets), &
      new_unittest("step datasets and cell averages", test_step_datasets), &
      new_unittest("summary attributes", test_summary), &
      new_unittest("xdmf file and rename", test_xdmf_file), &
      new_unittest("xdmf: only global x y z nodal fields are vectors", test_xdmf_nodal_system_field), &
      new_unittest("mesh-only xdmf", test_mesh_only_xdmf), &
      new_unittest("meshio file: each field over every cell, NaN where a group has none", test_meshio_file), &
      new_unittest("discard leaves no file", test_discard), &
      new_unittest("a full disk under the XDMF file is reported (/dev/full)", test_xdmf_disk_full), &
      new_unittest("a text file's write errors are reported, unlike gfortran's", test_text_file_errors), &
      new_unittest("discard removes regular files only, never a directory", test_discard_keeps_directory), &
      new_unittest("contract violations are errors", test_contract_errors), &
      new_unittest("non-finite values are refused", test_non_finite_refused, nonfinite=.true.), &
      new_unittest("step group names", test_step_names), &
      new_unittest("summary analysis is the bare word", test_summary_analysis_word), &
      new_unittest("PARAMETERS starting with a word: words as strings, numbers as reals", test_summary_parameters), &
      new_unittest("xdmf topology of every element type", test_xdmf_every_type), &
      new_unittest("REPORT, REACTION: resultants of the cube's reactions in closed form", test_reaction_report), &
      new_unittest("--fields replaces the deck's FIELDS; an unknown name is an input error", test_fields_option) &
    ]
  end subroutine collect_results_file

  ! ----------------------------------------------------------------- sample model

  !> Nodes on a 3 x 2 x 2 grid (x = 100 i, y = 50 j, z = 25 k), node = 1 + i + 3 j + 6 k.
  pure function sample_coordinates() result(x)
    real(dp) :: x(3, nnode)
    integer :: i, j, k, n
    do k = 0, 1
      do j = 0, 1
        do i = 0, 2
          n = 1 + i + 3 * j + 6 * k
          x(:, n) = [100.0_dp * i, 50.0_dp * j, 25.0_dp * k]
        end do
      end do
    end do
  end function sample_coordinates

  !> Two hex8 along x: bottom face counter-clockwise, then the top face.
  pure function sample_connectivity() result(c)
    integer :: c(npe, nelem)
    integer :: e
    do e = 1, nelem
      c(:4, e) = [e, e + 1, e + 4, e + 3]
      c(5:, e) = c(:4, e) + 6
    end do
  end function sample_connectivity

  pure function sample_displacement() result(u)
    real(dp) :: u(3, nnode)
    integer :: c, n
    do n = 1, nnode
      do c = 1, 3
        u(c, n) = c + 0.25_dp * n
      end do
    end do
  end function sample_displacement

  !> Stress at Gauss point p (element-major): 1000 c + p + 0.5.
  pure function sample_stress() result(s)
    real(dp) :: s(6, nelem * ngauss)
    integer :: c, p
    do p = 1, nelem * ngauss
      do c = 1, 6
        s(c, p) = 1000.0_dp * c + p + 0.5_dp
      end do
    end do
  end function sample_stress

  !> Write the sample file (mesh, one step, summary) and close it.
  subroutine write_sample(path, error)
    character(len=*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    type(results_file_t) :: file

    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (.not. allocated(error)) call file%write_group('pipe', 'hex8', sample_connectivity(), error)
    if (.not. allocated(error)) call file%begin_step(1, 0.5_dp, 3, 1.25e-7_dp, error)
    if (.not. allocated(error)) call file%write_nodal(1, 'displacement', sample_displacement(), 'ux uy uz', error)
    if (.not. allocated(error)) call file%write_gauss(1, 'stress', 'pipe', sample_stress(), &
                                                      'sxx syy szz syz sxz sxy', ngauss, error)
    if (.not. allocated(error)) call file%write_summary_string('version', 'feps 0.1.0', error)
    if (.not. allocated(error)) call file%write_summary_string('input', '', error)
    if (.not. allocated(error)) call file%write_summary_real('wall_time', 2.5_dp, error)
    if (.not. allocated(error)) call file%write_summary_int('dofs', 5000000000_i8, error)
    if (.not. allocated(error)) call file%write_summary_int('dofs', 36_i8, error)   ! replaces
    if (.not. allocated(error)) call file%close(error)
    if (allocated(error)) call file%discard()
  end subroutine write_sample

  ! ----------------------------------------------------------------- reading helpers

  ! ----------------------------------------------------------------- tests

  subroutine test_mesh_datasets(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path
    integer(hid_t) :: file_id
    integer :: hdferr
    real(dp), allocatable :: x(:, :)
    integer, allocatable :: c(:, :), t(:, :)

    path = scratch_path('mesh.h5')
    call write_sample(path, error)
    if (allocated(error)) return
    call open_read(path, file_id, error)
    if (allocated(error)) return
    call read_real(file_id, '/mesh/coordinates', x, error)
    if (.not. allocated(error)) call read_int(file_id, '/mesh/groups/pipe/connectivity', c, error)
    if (.not. allocated(error)) call read_int(file_id, '/xdmf/pipe/topology', t, error)
    if (.not. allocated(error)) then
      ! Fortran (3, nnode) is h5py (nnode, 3).
      call check(error, size(x, 1) == 3 .and. size(x, 2) == nnode, 'coordinates shape (3, 12)')
      if (.not. allocated(error)) call check(error, all(x == sample_coordinates()), 'coordinates exact')
      if (.not. allocated(error)) call check(error, string_attribute(file_id, '/mesh/coordinates', &
                                                  'components') == 'x y z', 'coordinates components')
      if (.not. allocated(error)) call check(error, size(c, 1) == npe .and. size(c, 2) == nelem, &
                                             'connectivity shape (8, 2)')
      if (.not. allocated(error)) call check(error, all(c == sample_connectivity()), 'connectivity 1-based')
      if (.not. allocated(error)) call check(error, c(1, 1), 1, 'first node of element 1')
      if (.not. allocated(error)) call check(error, string_attribute(file_id, '/mesh/groups/pipe', &
                                                  'element_type') == 'hex8', 'element_type hex8')
      if (.not. allocated(error)) call check(error, size(t, 1) == npe .and. size(t, 2) == nelem, &
                                             'topology shape (8, 2)')
      if (.not. allocated(error)) call check(error, all(t == sample_connectivity() - 1), 'topology 0-based')
      if (.not. allocated(error)) call check(error, minval(t), 0, 'smallest topology node')
    end if
    call h5fclose_f(file_id, hdferr)
    call delete_file(path)
    call delete_file(scratch_path('mesh.xmf'))
  end subroutine test_mesh_datasets

  subroutine test_step_datasets(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path
    character(len=*), parameter :: step = '/steps/0001'
    integer(hid_t) :: file_id
    integer :: hdferr, e, k
    real(dp), allocatable :: u(:, :), s(:, :), a(:, :)
    real(dp) :: expected(6, nelem)

    path = scratch_path('step.h5')
    call write_sample(path, error)
    if (allocated(error)) return
    call open_read(path, file_id, error)
    if (allocated(error)) return
    call read_real(file_id, step // '/displacement', u, error)
    if (.not. allocated(error)) call read_real(file_id, step // '/stress/pipe', s, error)
    if (.not. allocated(error)) call read_real(file_id, step // '/cell/stress/pipe', a, error)
    if (.not. allocated(error)) then
      call check(error, real_attribute(file_id, step, 'load_factor'), 0.5_dp, 'load_factor', abs=0.0_dp)
      if (.not. allocated(error)) call check(error, int_attribute(file_id, step, 'iterations'), 3, 'iterations')
      if (.not. allocated(error)) call check(error, real_attribute(file_id, step, 'residual'), 1.25e-7_dp, &
                                             'residual', abs=0.0_dp)
      if (.not. allocated(error)) call check(error, size(u, 1) == 3 .and. size(u, 2) == nnode, &
                                             'displacement shape (3, 12)')
      if (.not. allocated(error)) call check(error, all(u == sample_displacement()), 'displacement exact')
      if (.not. allocated(error)) call check(error, string_attribute(file_id, step // '/displacement', &
                                                  'components') == 'ux uy uz', 'displacement components')
      if (.not. allocated(error)) call check(error, size(s, 1) == 6 .and. size(s, 2) == nelem * ngauss, &
                                             'stress shape (6, 16)')
      if (.not. allocated(error)) call check(error, all(s == sample_stress()), 'stress exact')
      if (.not. allocated(error)) call check(error, string_attribute(file_id, step // '/stress/pipe', &
                                                  'components') == 'sxx syy szz syz sxz sxy', 'stress components')
      if (.not. allocated(error)) call check(error, int_attribute(file_id, step // '/stress/pipe', &
                                                  'points_per_element'), ngauss, 'points_per_element')
      if (.not. allocated(error)) call check(error, size(a, 1) == 6 .and. size(a, 2) == nelem, &
                                             'cell average shape (6, 2)')
      if (.not. allocated(error)) then
        ! mean over p = 8(e-1)+1 .. 8e of (1000 c + p + 0.5) = 1000 c + 8(e-1) + 4.5 + 0.5
        do e = 1, nelem
          do k = 1, 6
            expected(k, e) = 1000.0_dp * k + 8.0_dp * (e - 1) + 5.0_dp
          end do
        end do
        call check(error, a(1, 2), expected(1, 2), 'cell average sxx of element 2', abs=0.0_dp)
        if (.not. allocated(error)) call check(error, all(a == expected), 'all cell averages exact')
      end if
      if (.not. allocated(error)) call check(error, string_attribute(file_id, step // '/cell/stress/pipe', &
                                                  'components') == 'sxx syy szz syz sxz sxy', 'cell components')
    end if
    call h5fclose_f(file_id, hdferr)
    call delete_file(path)
    call delete_file(scratch_path('step.xmf'))
  end subroutine test_step_datasets

  subroutine test_summary(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path
    integer(hid_t) :: file_id
    integer :: hdferr

    path = scratch_path('summary.h5')
    call write_sample(path, error)
    if (allocated(error)) return
    call open_read(path, file_id, error)
    if (allocated(error)) return
    call check(error, string_attribute(file_id, '/summary', 'version') == 'feps 0.1.0', 'version string')
    if (.not. allocated(error)) call check(error, string_attribute(file_id, '/summary', 'input') == '', &
                                           'empty string attribute')
    if (.not. allocated(error)) call check(error, real_attribute(file_id, '/summary', 'wall_time'), 2.5_dp, &
                                           'wall_time', abs=0.0_dp)
    if (.not. allocated(error)) call check(error, int64_attribute(file_id, '/summary', 'dofs') == 36_i8, &
                                           'dofs (second write replaces the first)')
    call h5fclose_f(file_id, hdferr)
    call delete_file(path)
    call delete_file(scratch_path('summary.xmf'))
  end subroutine test_summary

  subroutine test_xdmf_file(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path, xmf, text

    path = scratch_path('xdmf.h5')
    xmf = scratch_path('xdmf.xmf')
    call write_sample(path, error)
    if (allocated(error)) return
    text = file_text(xmf)
    call check(error, file_exists(path), 'results file exists after close')
    if (.not. allocated(error)) call check(error, .not. file_exists(path // '.part'), 'no .part after close')
    if (.not. allocated(error)) call check(error, file_exists(xmf), 'XDMF file beside it (extension replaced)')
    if (.not. allocated(error)) call check(error, occurrences(text, 'CollectionType="Temporal"'), 1, &
                                           'one temporal collection')
    if (.not. allocated(error)) call check(error, occurrences(text, 'TopologyType="Hexahedron"'), 1, &
                                           'hexahedron topology per step')
    if (.not. allocated(error)) call check(error, occurrences(text, 'feps_test_xdmf.h5:/xdmf/pipe/topology'), 1, &
                                           'topology from the 0-based copy')
    if (.not. allocated(error)) call check(error, occurrences(text, 'feps_test_xdmf.h5:/mesh/coordinates'), 1, &
                                           'geometry from coordinates')
    if (.not. allocated(error)) call check(error, occurrences(text, &
                                           'Name="displacement" AttributeType="Vector" Center="Node"'), 1, &
                                           'displacement as a nodal vector')
    ! the stress averages one whole dataset of 6 components: the XDMF 3 readers skip hyperslabs
    if (.not. allocated(error)) call check(error, occurrences(text, 'Center="Cell"'), 1, &
                                           'one cell array for the stress')
    if (.not. allocated(error)) call check(error, occurrences(text, 'Name="stress" AttributeType="Matrix" ' // &
                                           'Center="Cell"'), 1, 'stress a Matrix of its columns')
    if (.not. allocated(error)) call check(error, occurrences(text, 'HyperSlab'), 0, 'no hyperslab')
    ! time is the load factor; the step number grid data
    if (.not. allocated(error)) call check(error, occurrences(text, '<Time Value="5.0000000000000000E-001"/>'), 1, &
                                           'time = the load factor 0.5')
    if (.not. allocated(error)) call check(error, occurrences(text, '<Attribute Name="step" AttributeType="Scalar" ' // &
                                           'Center="Grid">'), 1, 'step number as grid data')
    ! the step's load factor as grid data, which XDMF readers give as field data
    if (.not. allocated(error)) call check(error, occurrences(text, '<Attribute Name="load_factor" ' // &
                                           'AttributeType="Scalar" Center="Grid">'), 1, 'load factor as grid data')
    if (.not. allocated(error)) call check(error, occurrences(text, 'Format="XML">' // &
                                           '5.0000000000000000E-001</DataItem>'), 1, 'its value, 0.5')
    if (.not. allocated(error)) call check(error, occurrences(text, '<Grid'), &
                                           occurrences(text, '</Grid>'), 'Grid elements balanced')
    if (.not. allocated(error)) call check(error, occurrences(text, '<DataItem'), &
                                           occurrences(text, '</DataItem>'), 'DataItem elements balanced')
    call delete_file(path)
    call delete_file(xmf)
  end subroutine test_xdmf_file

  !> A vector attribute is drawn in global x y z (glyphs, Warp By Vector): reaction_nodal, whose
  !! columns f1 f2 f3 are in each node's own system (radial, hoop, axial), must not be one. At a
  !! node at theta = 90 a hoop force f2 points along -x; a vector would draw it along +y.
  subroutine test_xdmf_nodal_system_field(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path, xmf, text
    type(results_file_t) :: file

    path = scratch_path('nodal_system.h5')
    xmf = scratch_path('nodal_system.xmf')
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (.not. allocated(error)) call file%write_group('pipe', 'hex8', sample_connectivity(), error)
    if (.not. allocated(error)) call file%begin_step(1, 1.0_dp, 1, 0.0_dp, error)
    if (.not. allocated(error)) call file%write_nodal(1, 'displacement', sample_displacement(), 'ux uy uz', error)
    if (.not. allocated(error)) call file%write_nodal(1, 'reaction', sample_displacement(), 'fx fy fz', error)
    if (.not. allocated(error)) call file%write_nodal(1, 'reaction_nodal', sample_displacement(), 'f1 f2 f3', error)
    if (.not. allocated(error)) call file%close(error)
    if (allocated(error)) then
      call file%discard()
      return
    end if
    text = file_text(xmf)
    call check(error, occurrences(text, 'Name="displacement" AttributeType="Vector" Center="Node"'), 1, &
               'displacement (ux uy uz) a vector')
    if (.not. allocated(error)) call check(error, occurrences(text, &
                                           'Name="reaction" AttributeType="Vector" Center="Node"'), 1, &
                                           'reaction (fx fy fz) a vector')
    if (.not. allocated(error)) call check(error, occurrences(text, 'Name="reaction_nodal" AttributeType="Matrix" ' // &
                                           'Center="Node"'), 1, 'reaction_nodal (f1 f2 f3) a Matrix, not a vector')
    if (.not. allocated(error)) call check(error, occurrences(text, 'AttributeType="Vector"'), 2, &
                                           'only displacement and reaction vectors')
    call delete_file(path)
    call delete_file(xmf)
  end subroutine test_xdmf_nodal_system_field

  !> The file for meshio's time-series reader: one mesh of every shown group, and per step and
  !! Gauss-point field one dataset of the averages of every cell in the groups' order: the pipe's
  !! two hex8 then the tie's bar2; stress on the bar and the bar's force on the pipe are NaN.
  subroutine test_meshio_file(error)
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path, text
    type(results_file_t) :: file
    integer :: bars(2, 1), e
    real(dp) :: force(1, 1)
    real(dp), allocatable :: stress(:, :), axial(:, :), pipe(:, :), want(:, :), points(:, :)
    integer(hid_t) :: file_id
    integer :: hdferr

    path = scratch_path('meshio.h5')
    bars(:, 1) = [1, 12]
    force = 7.5_dp
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (.not. allocated(error)) call file%write_group('pipe', 'hex8', sample_connectivity(), error)
    if (.not. allocated(error)) call file%write_group('tie', 'bar2', bars, error)
    if (.not. allocated(error)) call file%begin_step(1, 1.5_dp, 1, 0.0_dp, error)
    if (.not. allocated(error)) call file%write_nodal(1, 'displacement', sample_displacement(), 'ux uy uz', error)
    if (.not. allocated(error)) call file%write_gauss(1, 'stress', 'pipe', sample_stress(), &
                                                      'sxx syy szz syz sxz sxy', ngauss, error)
    if (.not. allocated(error)) call file%write_gauss(1, 'bar', 'tie', force, 'axial_force', 1, error)
    if (.not. allocated(error)) call file%close(error)
    if (allocated(error)) then
      call file%discard()
      return
    end if
    text = file_text(scratch_path('meshio.meshio.xdmf'))
    call check(error, occurrences(text, '<Topology TopologyType="Hexahedron" NumberOfElements="2"'), 1, &
               'the pipe one cell block')
    if (.not. allocated(error)) call check(error, occurrences(text, '<Topology TopologyType="Polyline" ' // &
                                           'NumberOfElements="1"'), 1, 'the tie another')
    if (.not. allocated(error)) call check(error, occurrences(text, '<Time Value="1.5000000000000000E+000"/>'), &
                                           1, 'time = the load factor')
    if (.not. allocated(error)) call check(error, occurrences(text, 'Center="Grid"') + &
                                           occurrences(text, 'HyperSlab'), 0, 'nothing meshio refuses')
    if (.not. allocated(error)) call check(error, occurrences(text, 'feps_test_meshio.h5:/xdmf/steps/0001/stress<'), &
                                           1, 'stress over every cell')
    if (allocated(error)) return
    call open_read(path, file_id, error)
    if (allocated(error)) return
    call read_real(file_id, '/xdmf/steps/0001/stress', stress, error)
    if (.not. allocated(error)) call read_real(file_id, '/xdmf/steps/0001/bar', axial, error)
    if (.not. allocated(error)) call read_real(file_id, '/steps/0001/cell/stress/pipe', pipe, error)
    call h5fclose_f(file_id, hdferr)
    if (allocated(error)) return
    ! the pipe's averages by hand: the mean of each element's 8 points
    allocate (want(6, nelem))
    points = sample_stress()
    do e = 1, nelem
      want(:, e) = sum(points(:, (e - 1) * ngauss + 1:e * ngauss), dim=2) / real(ngauss, dp)
    end do
    call check(error, size(stress, 1) == 6 .and. size(stress, 2) == 3, 'stress 3 cells x 6')
    if (.not. allocated(error)) call check(error, all(stress(:, 1:2) == pipe) .and. &
                                           all(abs(pipe - want) <= 1.0e-14_dp * maxval(abs(want))), &
                                           'the pipe rows: its averages')
    if (.not. allocated(error)) call check(error, all(ieee_is_nan(stress(:, 3))), 'the tie row NaN')
    if (.not. allocated(error)) call check(error, size(axial, 1) == 1 .and. size(axial, 2) == 3, 'bar 3 cells x 1')
    if (.not. allocated(error)) call check(error, all(ieee_is_nan(axial(1, 1:2))) .and. axial(1, 3) == 7.5_dp, &
                                           'the bar force on the tie only')
    call delete_file(path)
    call delete_file(scratch_path('meshio.xmf'))
    call delete_file(scratch_path('meshio.meshio.xdmf'))
  end subroutine test_meshio_file

  subroutine test_mesh_only_xdmf(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path, text
    type(results_file_t) :: file
    integer :: bars(2, 1)

    ! No extension: '.xmf' is appended.
    path = scratch_path('meshonly')
    bars(:, 1) = [1, 12]
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (.not. allocated(error)) call file%write_group('pipe', 'hex8', sample_connectivity(), error)
    if (.not. allocated(error)) call file%write_group('tie', 'bar2', bars, error)
    if (.not. allocated(error)) call file%write_group('odd', 'unknown-type', bars, error)
    if (.not. allocated(error)) call file%close(error)
    if (allocated(error)) then
      call file%discard()
      return
    end if
    text = file_text(path // '.xmf')
    call check(error, file_exists(path) .and. .not. file_exists(path // '.part'), 'renamed file')
    if (.not. allocated(error)) call check(error, occurrences(text, 'CollectionType="Temporal"'), 0, &
                                           'no temporal collection without steps')
    if (.not. allocated(error)) call check(error, occurrences(text, 'CollectionType="Spatial"'), 1, &
                                           'one spatial collection')
    if (.not. allocated(error)) call check(error, occurrences(text, 'GridType="Uniform"'), 2, &
                                           'two grids: the unknown type is left out')
    if (.not. allocated(error)) call check(error, occurrences(text, &
                                           'TopologyType="Polyline" NumberOfElements="1" NodesPerElement="2"'), &
                                           1, 'bar2 as a 2-node polyline')
    if (.not. allocated(error)) call check(error, occurrences(text, '<Attribute'), 0, 'no attributes')
    call delete_file(path)
    call delete_file(path // '.xmf')
  end subroutine test_mesh_only_xdmf

  subroutine test_discard(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path
    type(results_file_t) :: file

    path = scratch_path('discard.h5')
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (allocated(error)) return
    call check(error, file_exists(path // '.part'), '.part exists while writing')
    if (allocated(error)) return
    call file%discard()
    call check(error, .not. file_exists(path // '.part'), 'no .part after discard')
    if (.not. allocated(error)) call check(error, .not. file_exists(path), 'no file after discard')
    if (allocated(error)) return
    call file%discard()   ! twice is harmless

    ! discard after a successful close keeps the results
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (.not. allocated(error)) call file%close(error)
    if (allocated(error)) then
      call file%discard()
      return
    end if
    call file%discard()
    call check(error, file_exists(path), 'discard after close keeps the file')
    call delete_file(path)
    call delete_file(scratch_path('discard.xmf'))
  end subroutine test_discard

  subroutine test_contract_errors(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: failure
    character(len=:), allocatable :: path
    type(results_file_t) :: file
    real(dp) :: u(3, nnode)

    path = scratch_path('contract.h5')
    u = sample_displacement()
    call file%write_mesh(sample_coordinates(), failure)
    call check(error, allocated(failure), 'write_mesh before create fails')
    if (allocated(error)) return
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (allocated(error)) then
      call file%discard()
      return
    end if
    call file%write_nodal(2, 'displacement', u, 'ux uy uz', failure)
    call check(error, allocated(failure), 'nodal field of a step not begun fails')
    if (.not. allocated(error)) then
      call check(error, failure%code, err_internal, 'error category')
      deallocate (failure)
    end if
    if (.not. allocated(error)) call file%begin_step(2, 1.0_dp, 1, 0.0_dp, error)
    if (.not. allocated(error)) then
      call file%write_nodal(2, 'displacement', u, 'ux uy', failure)
      call check(error, allocated(failure), 'two component names for three columns fails')
      if (allocated(failure)) deallocate (failure)
    end if
    if (.not. allocated(error)) then
      call file%write_nodal(2, 'displacement', u(:, :10), 'ux uy uz', failure)
      call check(error, allocated(failure), '10 nodes for a 12-node mesh fails')
      if (allocated(failure)) deallocate (failure)
    end if
    if (.not. allocated(error)) then
      call file%write_gauss(2, 'stress', 'pipe', sample_stress(), 'sxx syy szz syz sxz sxy', 5, failure)
      call check(error, allocated(failure), '16 points with 5 per element fails')
      if (allocated(failure)) deallocate (failure)
    end if
    if (.not. allocated(error)) then
      call file%write_group('a/b', 'hex8', sample_connectivity(), failure)
      call check(error, allocated(failure), "group name with '/' fails")
      if (allocated(failure)) deallocate (failure)
    end if
    call file%discard()
    if (.not. allocated(error)) call check(error, .not. file_exists(path // '.part') .and. &
                                           .not. file_exists(path), 'nothing left after discard')
    if (allocated(error)) return
    ! a results file named like its XDMF file would be replaced by it
    call file%create(scratch_path('contract.XMF'), failure)
    call check(error, allocated(failure), 'a results file name ending in .xmf fails')
    if (allocated(failure)) deallocate (failure)
    call file%discard()
    if (.not. allocated(error)) call check(error, .not. file_exists(scratch_path('contract.XMF.part')), &
                                           'no .part for a .xmf name')
  end subroutine test_contract_errors

  !> The last guard against a run that overflowed: no NaN or Infinity reaches the file, in a
  !! dataset or an attribute; the error names the dataset, the row and the component.
  subroutine test_non_finite_refused(error)
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: failure
    character(len=:), allocatable :: path
    type(results_file_t) :: file
    real(dp) :: u(3, nnode), s(6, nelem * ngauss)

    path = scratch_path('non_finite.h5')
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    if (.not. allocated(error)) call file%write_group('pipe', 'hex8', sample_connectivity(), error)
    if (.not. allocated(error)) call file%begin_step(1, 1.0_dp, 1, 0.0_dp, error)
    if (allocated(error)) then
      call file%discard()
      return
    end if
    u = sample_displacement()
    u(2, 5) = ieee_value(1.0_dp, ieee_quiet_nan)
    call file%write_nodal(1, 'displacement', u, 'ux uy uz', failure)
    call expect_refusal('/steps/0001/displacement: node 5, uy is NaN')
    s = sample_stress()
    s(4, 11) = -ieee_value(1.0_dp, ieee_positive_inf)
    if (.not. allocated(error)) call file%write_gauss(1, 'stress', 'pipe', s, 'sxx syy szz syz sxz sxy', ngauss, &
                                                      failure)
    call expect_refusal('/steps/0001/stress/pipe: point 11 (element 2), syz is -Inf')
    s = sample_stress()
    s(1, 9:16) = 0.75_dp * huge(1.0_dp)     ! finite, but element 2's sum is not
    if (.not. allocated(error)) call file%write_gauss(1, 'stress', 'pipe', s, 'sxx syy szz syz sxz sxy', ngauss, &
                                                      failure)
    call expect_refusal('/steps/0001/cell/stress/pipe: element 2, sxx is Inf')
    if (.not. allocated(error)) call file%begin_step(2, 1.0_dp, 1, ieee_value(1.0_dp, ieee_quiet_nan), failure)
    call expect_refusal('/steps/0002: attribute residual is NaN')
    if (.not. allocated(error)) call file%write_summary_real('max_displacement', &
                                                            ieee_value(1.0_dp, ieee_positive_inf), failure)
    call expect_refusal('/summary: attribute max_displacement is Inf')
    call file%discard()
  contains
    subroutine expect_refusal(piece)
      character(len=*), intent(in) :: piece
      if (allocated(error)) return
      if (.not. allocated(failure)) then
        call test_failed(error, 'no error for ' // piece)
        return
      end if
      call check(error, failure%code, err_solver, 'error category (' // failure%message // ')')
      if (.not. allocated(error)) call check(error, index(failure%message, piece) > 0, &
                                             '"' // failure%message // '" names "' // piece // '"')
      deallocate (failure)
    end subroutine expect_refusal
  end subroutine test_non_finite_refused

  subroutine test_step_names(error)
    type(error_t), allocatable, intent(out) :: error
    call check(error, step_group_name(1) == '0001', 'step 1')
    if (.not. allocated(error)) call check(error, step_group_name(120) == '0120', 'step 120')
    if (.not. allocated(error)) call check(error, step_group_name(12345) == '12345', 'step 12345')
  end subroutine test_step_names

  !> /summary analysis of a linear and a nonlinear run: exactly 'linear' and 'nonlinear', as
  !! every other string attribute (it used to be 'linear   ', padded to the longer word).
  subroutine test_summary_analysis_word(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: decks(2) = [character(len=40) :: 'test/data/cube.dat', &
                                                                    'test/data/block_contact.dat']
    character(len=*), parameter :: words(2) = [character(len=9) :: 'linear', 'nonlinear']
    character(len=:), allocatable :: path, value
    type(run_options_t) :: options
    type(run_summary_t) :: summary
    integer(hid_t) :: file_id
    integer :: hdferr, k

    path = scratch_path('analysis.h5')
    do k = 1, 2
      options%deck = trim(decks(k))
      options%output = path
      options%quiet = .true.
      call run_feps(options, summary, error)
      if (allocated(error)) return
      call open_read(path, file_id, error)
      if (allocated(error)) return
      value = string_attribute(file_id, '/summary', 'analysis')
      call h5fclose_f(file_id, hdferr)
      call delete_file(path)
      call delete_file(scratch_path('analysis.xmf'))
      ! compare the lengths too: Fortran's == ignores trailing blanks
      call check(error, value == trim(words(k)) .and. len(value) == len_trim(words(k)), &
                 trim(decks(k)) // ": /summary analysis is '" // value // "', expected '" // trim(words(k)) // "'")
      if (allocated(error)) return
    end do
  end subroutine test_summary_analysis_word

  !> test/data/cube_reaction.dat: the cube of cube.dat (10 mm, p = 100 MPa on top) with REPORT,
  !! REACTION on the bottom (fz = p A = 1e4 N, fx = fy = 0) and on the corner node at the origin
  !! (p A_e / 4 = 625 N of its 5 x 5 mm face); each is also the sum of /steps/<last>/reaction
  !! over the set's nodes, read back from the file.
  subroutine test_reaction_report(error)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: file_id
    integer :: n
    real(dp) :: base(3), corner(3), from_file(3)
    real(dp), allocatable :: reaction(:, :), x(:, :)
    character(len=2), parameter :: axes(3) = ['fx', 'fy', 'fz']
    call run_and_open('test/data/cube_reaction.dat', 'reaction', file_id, error)
    if (allocated(error)) return
    do n = 1, 3
      base(n) = real_attribute(file_id, '/summary', 'reaction_base_' // axes(n))
      corner(n) = real_attribute(file_id, '/summary', 'reaction_corner_' // axes(n))
    end do
    call read_real(file_id, '/steps/' // step_group_name(1) // '/reaction', reaction, error)
    if (.not. allocated(error)) call read_real(file_id, '/mesh/coordinates', x, error)
    call close_and_delete(file_id, 'reaction')
    if (allocated(error)) return
    call check(error, base(3), 100.0_dp * 10.0_dp * 10.0_dp, 'bottom fz = p A', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, maxval(abs(base(1:2))), 0.0_dp, 'bottom fx, fy', abs=1.0e-9_dp)
    if (allocated(error)) return
    call check(error, corner(3), 100.0_dp * 5.0_dp * 5.0_dp / 4.0_dp, 'corner fz = p A_e / 4', rel=1.0e-12_dp)
    if (allocated(error)) return
    from_file = 0.0_dp
    do n = 1, size(x, 2)
      if (abs(x(3, n)) < 1.0e-9_dp) from_file = from_file + reaction(:, n)
    end do
    call check(error, maxval(abs(base - from_file)), 0.0_dp, 'bottom resultant = sum of the written reactions', &
               abs=1.0e-9_dp)
  end subroutine test_reaction_report

  !> --fields (run_options_t%fields) in place of the deck's FIELDS: 'displacement, nodal_principal'
  !! writes those two only (the nodal principal stresses of the uniaxial cube: 0 and -100 MPa at
  !! every node), and /summary fields names them; a misspelt name stops the run before any file
  !! with an input error naming the option and the name.
  subroutine test_fields_option(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: path, fields
    type(run_options_t) :: options
    type(run_summary_t) :: summary
    integer(hid_t) :: file_id
    integer(hsize_t) :: dims(2)
    real(dp), allocatable :: principal(:, :)
    type(error_t), allocatable :: refused
    call run_and_open('test/data/cube.dat', 'fields_option', file_id, error, &
                      fields='displacement, nodal_principal')
    if (allocated(error)) return
    fields = string_attribute(file_id, '/summary', 'fields')
    call read_real(file_id, '/steps/0001/nodal_principal/block', principal, error)
    if (.not. allocated(error)) call dataset_dims(file_id, '/steps/0001/displacement', dims, error)
    call close_and_delete(file_id, 'fields_option')
    if (allocated(error)) return
    call check(error, fields == 'displacement nodal_principal', "/summary fields is '" // fields // "'")
    if (allocated(error)) return
    call check(error, maxval(abs(principal(1, :))), 0.0_dp, 'most tensile nodal stress', abs=1.0e-9_dp)
    if (allocated(error)) return
    call check(error, maxval(abs(principal(2, :) + 100.0_dp)), 0.0_dp, 'most compressive nodal stress', abs=1.0e-9_dp)
    if (allocated(error)) return
    path = scratch_path('fields_option.h5')
    options%deck = 'test/data/cube.dat'
    options%output = path
    options%quiet = .true.
    options%fields = 'displacement,stresses'
    call run_feps(options, summary, refused)
    call check(error, allocated(refused), 'a misspelt --fields name is refused')
    if (allocated(error)) return
    call check(error, refused%code == err_input .and. index(refused%message, &
               '--fields: unknown field "stresses"') > 0, 'the error names --fields and the name: ' // refused%message)
    if (allocated(error)) return
    call check(error, .not. file_exists(path) .and. .not. file_exists(path // '.part'), 'no results file')
  end subroutine test_fields_option

  !> test/data/cube_parameters.dat: PARAMETERS, kind=F, E_s=144, tag=S1. write_parameters
  !! tested the number of a value that was no number (kind=F) before knowing it was one: a read
  !! of an uninitialised real, which a build with -finit-real=snan -ffpe-trap=invalid stopped
  !! on (test/cli/check_runtime.sh runs this test under such a build).
  subroutine test_summary_parameters(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: kind, tag
    integer(hid_t) :: file_id
    real(dp) :: e_s
    call run_and_open('test/data/cube_parameters.dat', 'parameters', file_id, error)
    if (allocated(error)) return
    kind = string_attribute(file_id, '/summary', 'parameter_kind')
    e_s = real_attribute(file_id, '/summary', 'parameter_E_s')
    tag = string_attribute(file_id, '/summary', 'parameter_tag')
    call close_and_delete(file_id, 'parameters')
    call check(error, kind == 'F' .and. len(kind) == 1, "parameter_kind is '" // kind // "', expected 'F'")
    if (allocated(error)) return
    call check(error, e_s, 144.0_dp, 'parameter_E_s', abs=0.0_dp)
    if (allocated(error)) return
    call check(error, tag == 'S1' .and. len(tag) == 2, "parameter_tag is '" // tag // "', expected 'S1'")
  end subroutine test_summary_parameters

  !> Every feps element type is in the XDMF file with its cell type, and /xdmf/<group>/topology
  !! holds the 0-based node numbers of that cell: all nodes for solids and bars (bars as polylines
  !! through their nodes in order, bar3 included: Edge_3 would need the middle node last), the
  !! lower layer (the first half of the nodes) for interface elements. Group g has g elements, so
  !! each Topology line of the file is unique. (Hex8b, hex20r, tri6-6, the quadratic and line
  !! interfaces, the -nodal variants and bar3-bar5 used to be left out.)
  subroutine test_xdmf_every_type(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: ntypes = 22
    character(len=*), parameter :: types(ntypes) = [character(len=21) :: &
      'hex8', 'hex8b', 'hex20', 'hex20r', 'tri6', 'tri6-6', &
      'interface-quad4', 'interface-quad4-nodal', 'interface-quad8', 'interface-quad8-nodal', &
      'interface-tri3', 'interface-tri3-nodal', 'interface-tri6', 'interface-tri6-nodal', &
      'interface-line2', 'interface-line2-nodal', 'interface-line3', 'interface-line3-nodal', &
      'bar2', 'bar3', 'bar4', 'bar5']
    character(len=*), parameter :: cells(ntypes) = [character(len=15) :: &
      'Hexahedron', 'Hexahedron', 'Hexahedron_20', 'Hexahedron_20', 'Triangle_6', 'Triangle_6', &
      'Quadrilateral', 'Quadrilateral', 'Quadrilateral_8', 'Quadrilateral_8', &
      'Triangle', 'Triangle', 'Triangle_6', 'Triangle_6', &
      'Polyline', 'Polyline', 'Edge_3', 'Edge_3', &
      'Polyline', 'Polyline', 'Polyline', 'Polyline']
    ! nodes of the element and of the cell shown
    integer, parameter :: nodes(ntypes) = [8, 8, 20, 20, 6, 6, 8, 8, 16, 16, 6, 6, 12, 12, 4, 4, 6, 6, &
                                           2, 3, 4, 5]
    integer, parameter :: shown(ntypes) = [8, 8, 20, 20, 6, 6, 4, 4, 8, 8, 3, 3, 6, 6, 2, 2, 3, 3, &
                                           2, 3, 4, 5]
    character(len=:), allocatable :: path, text, line, name
    type(results_file_t) :: file
    integer, allocatable :: c(:, :), t(:, :)
    integer(hid_t) :: file_id
    integer :: g, hdferr

    path = scratch_path('every_type.h5')
    call file%create(path, error)
    if (.not. allocated(error)) call file%write_mesh(sample_coordinates(), error)
    do g = 1, ntypes
      if (allocated(error)) exit
      call group_connectivity(g, c)
      call file%write_group('g' // str(g), trim(types(g)), c, error)
    end do
    if (.not. allocated(error)) call file%close(error)
    if (allocated(error)) then
      call file%discard()
      return
    end if
    text = file_text(scratch_path('every_type.xmf'))
    call open_read(path, file_id, error)
    if (allocated(error)) return
    do g = 1, ntypes
      name = 'g' // str(g)
      call group_connectivity(g, c)
      line = '<Topology TopologyType="' // trim(cells(g)) // '" NumberOfElements="' // str(g) // '"'
      if (cells(g) == 'Polyline') line = line // ' NodesPerElement="' // str(shown(g)) // '"'
      call check(error, occurrences(text, '<Grid Name="' // name // '" GridType="Uniform">'), 1, &
                 trim(types(g)) // ': one grid in the XDMF file')
      if (.not. allocated(error)) call check(error, occurrences(text, line // '>'), 1, &
                                             trim(types(g)) // ': ' // line // '>')
      if (.not. allocated(error)) call check(error, occurrences(text, '<DataItem Dimensions="' // str(g) // ' ' // &
                                             str(shown(g)) // '" NumberType="Int" Precision="4" Format="HDF">' // &
                                             'feps_test_every_type.h5:/xdmf/' // name // '/topology</DataItem>'), 1, &
                                             trim(types(g)) // ': topology DataItem of ' // str(shown(g)) // ' columns')
      if (.not. allocated(error)) call read_int(file_id, '/xdmf/' // name // '/topology', t, error)
      if (.not. allocated(error)) call check(error, size(t, 1) == shown(g) .and. size(t, 2) == g, &
                                             trim(types(g)) // ': /xdmf topology shape')
      if (.not. allocated(error)) call check(error, all(t == c(:shown(g), :) - 1), &
                                             trim(types(g)) // ': /xdmf topology = first nodes - 1')
      if (allocated(error)) exit
    end do
    call h5fclose_f(file_id, hdferr)
    call delete_file(path)
    call delete_file(scratch_path('every_type.xmf'))
  contains
    !> Group g: g elements of nodes(g) nodes, node numbers in 1..nnode.
    subroutine group_connectivity(g, c)
      integer, intent(in) :: g
      integer, allocatable, intent(out) :: c(:, :)
      integer :: i, e
      allocate (c(nodes(g), g))
      do e = 1, g
        do i = 1, nodes(g)
          c(i, e) = 1 + mod(3 * i + e + g, nnode)
        end do
      end do
    end subroutine group_connectivity
  end subroutine test_xdmf_every_type

  !> Issue 24: the disk filling while the XDMF file was written left it empty or cut short with
  !! exit status 0 (gfortran's WRITE and CLOSE report no error). /dev/full fails every write
  !! with ENOSPC.
  subroutine test_xdmf_disk_full(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: got
    type(xdmf_group_t) :: groups(0)
    type(xdmf_step_t) :: steps(0)
    logical :: exists
    inquire (file='/dev/full', exist=exists)
    if (.not. exists) return
    call write_xdmf('/dev/full', 'r.h5', 8, groups, steps, got)
    call check(error, allocated(got), 'the full disk is reported')
    if (allocated(error)) return
    call check(error, got%code == err_io .and. index(got%message, 'cannot write XDMF file /dev/full: ') > 0, &
               got%message)
  end subroutine test_xdmf_disk_full

  subroutine test_text_file_errors(error)
    type(error_t), allocatable, intent(out) :: error
    type(text_file_t) :: file
    character(len=:), allocatable :: message
    call file%open('build/no_such_folder/x.txt', message)
    call check(error, len(message) > 0, 'a file in a missing folder cannot be opened')
    if (allocated(error)) return
    call file%write('nothing')
    call file%close(message)
    call check(error, len(message) > 0, 'and its close says so')
    if (allocated(error)) return
    call file%open('build/test_text_file.txt', message)
    call check(error, len(message) == 0, 'a file opens: ' // message)
    if (allocated(error)) return
    call file%write('one line')
    call file%close(message)
    call check(error, len(message) == 0, 'it is written: ' // message)
    if (allocated(error)) return
    call check(error, remove_regular_file('build/test_text_file.txt'), 'and removed')
  end subroutine test_text_file_errors

  subroutine test_discard_keeps_directory(error)
    type(error_t), allocatable, intent(out) :: error
    call check(error, .not. remove_regular_file('build'), 'a directory is not removed')
    if (allocated(error)) return
    call check(error, file_kind('build') == file_directory, 'it is still there')
    if (allocated(error)) return
    call check(error, file_kind('/dev/null') == file_special, '/dev/null is no regular file')
    if (allocated(error)) return
    call check(error, .not. remove_regular_file('/dev/null'), 'and is not removed')
  end subroutine test_discard_keeps_directory

end module test_results_file
