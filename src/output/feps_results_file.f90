!> The HDF5 results file of a run (SPEC section 10) and the XDMF file beside it.
!!
!! The file is written under the temporary name `<path>.part` and renamed to `<path>` only by a
!! successful `close`; `discard` removes the temporary file, so a failed run leaves no partial
!! result behind. Arrays are passed as Fortran sees them, (components, rows); HDF5 stores them
!! transposed, so h5py sees (rows, components). Every results dataset carries a string attribute
!! `components`; Gauss-point datasets are element-major and carry `points_per_element`.
!!
!! Errors: HDF5 or file-system failures return `err_io`; calls that break the contract (wrong
!! shapes, a step not begun, no open file) return `err_internal`; a value that is not finite
!! (NaN, Infinity: a run that left double precision) is never written and returns `err_solver`,
!! naming the dataset or attribute, the row and the component.
module feps_results_file
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char, c_loc, c_ptr
  use feps_kinds, only: dp, i8
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use feps_error, only: error_t, fatal_error, err_io, err_internal, err_solver, str
  use feps_element_catalog, only: element_info_t, element_info, family_name, point_coordinates
  use feps_result_schema, only: field_name, family_field
  use feps_model, only: constraint_t
  use feps_xdmf, only: xdmf_group_t, xdmf_field_t, xdmf_step_t, write_xdmf, write_meshio_xdmf, xdmf_topology_path, &
                       count_words, word
  use feps_paths, only: is_xdmf_name, xdmf_file_name, meshio_file_name
  use feps_files, only: remove_regular_file, mark_partial_file
  use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5dont_atexit_f, h5eset_auto_f, h5fcreate_f, h5fclose_f, &
                  H5F_ACC_TRUNC_F, h5gcreate_f, h5gopen_f, h5gclose_f, h5lexists_f, &
                  h5screate_f, h5screate_simple_f, h5sclose_f, H5S_SCALAR_F, &
                  h5dcreate_f, h5dopen_f, h5dwrite_f, h5dclose_f, h5acreate_f, h5awrite_f, h5aclose_f, &
                  h5aexists_f, h5adelete_f, h5tcopy_f, h5tset_size_f, h5tset_strpad_f, h5tclose_f, &
                  H5T_FORTRAN_S1, H5T_STR_NULLPAD_F, H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, &
                  H5T_STD_I64LE, h5kind_to_type, H5_INTEGER_KIND, &
                  h5pcreate_f, h5pset_create_inter_group_f, h5pclose_f, H5P_LINK_CREATE_F
  implicit none
  private

  public :: results_file_t, step_group_name

  !> Element averages of one field and group in the step being written, kept until the step
  !! ends: the meshio file needs each field's averages over every cell of the mesh in one dataset.
  type :: pending_cells_t
    character(len=:), allocatable :: kind
    character(len=:), allocatable :: components
    integer :: group = 0
    real(dp), allocatable :: averages(:, :)
  end type pending_cells_t

  !> An HDF5 results file being written; see the module notes for the life cycle.
  type :: results_file_t
    private
    character(len=:), allocatable :: path        ! final name
    character(len=:), allocatable :: part_path   ! temporary name while writing
    integer(hid_t) :: file_id = -1
    integer(hid_t) :: link_plist = -1            ! creates missing intermediate groups
    logical :: is_open = .false.
    logical :: part_exists = .false.
    logical :: silent = .false.                  ! writes nothing (`keep_silent`)
    integer :: node_count = 0                    ! 0 until write_mesh
    type(xdmf_group_t), allocatable :: groups(:)
    type(xdmf_step_t), allocatable :: steps(:)
    type(pending_cells_t), allocatable :: pending(:)  ! this step's element averages
  contains
    procedure :: create
    procedure :: keep_silent
    procedure :: write_mesh
    procedure :: write_group
    procedure :: begin_step
    procedure :: write_nodal
    procedure :: write_gauss
    procedure :: write_summary_string
    procedure :: write_summary_real
    procedure :: write_summary_reals
    procedure :: write_summary_int
    procedure :: write_group_int
    procedure :: write_group_real
    procedure :: write_material
    procedure :: write_set
    procedure :: write_constraint
    procedure :: close => close_file
    procedure :: discard
  end type results_file_t

  interface
    function c_rename(old_name, new_name) bind(C, name='rename') result(status)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: old_name(*), new_name(*)
      integer(c_int) :: status
    end function c_rename
  end interface

contains

  !> Name of the group of a step: the number with at least 4 digits, zero padded ('0001').
  pure function step_group_name(step) result(name)
    integer, intent(in) :: step
    character(len=:), allocatable :: name
    name = str(step)
    if (len(name) < 4) name = repeat('0', 4 - len(name)) // name
  end function step_group_name

  !> From now on write nothing and touch no file, every call succeeding: the ranks above 0 of an
  !! MPI run, which compute what rank 0 does and leave the writing to it.
  subroutine keep_silent(self)
    class(results_file_t), intent(inout) :: self
    self%silent = .true.
  end subroutine keep_silent

  !> Start a results file: HDF5 file `path // '.part'`, renamed to `path` by `close`.
  subroutine create(self, path, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    integer :: hdferr

    if (self%silent) return
    if (self%is_open) then
      call fatal_error(error, err_internal, 'results file ' // self%path // ' is already open')
      return
    end if
    if (len_trim(path) == 0) then
      call fatal_error(error, err_io, 'results file name is empty')
      return
    end if
    if (is_xdmf_name(path)) then
      call fatal_error(error, err_io, 'results file name ' // trim(path) // ' ends in .xmf: the XDMF file ' // &
                       'written beside it would replace it')
      return
    end if
    self%path = trim(path)
    self%part_path = self%path // '.part'
    self%node_count = 0
    if (allocated(self%groups)) deallocate (self%groups)
    if (allocated(self%steps)) deallocate (self%steps)
    if (allocated(self%pending)) deallocate (self%pending)
    allocate (self%groups(0), self%steps(0), self%pending(0))

    ! No HDF5 clean-up at exit: a file whose close failed (the disk full) stays open inside the
    ! library, and its exit handler, flushing it once more, crashed the program after feps had
    ! reported the failure and removed the file. Every file feps writes is closed explicitly.
    call h5dont_atexit_f(hdferr)
    call h5open_f(hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot initialise the HDF5 library')
      return
    end if
    ! Failures are reported through error_t; the HDF5 error stack must not print to the screen.
    call h5eset_auto_f(0, hdferr)

    call h5fcreate_f(self%part_path, H5F_ACC_TRUNC_F, self%file_id, hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot create results file ' // self%part_path)
      return
    end if
    self%is_open = .true.
    self%part_exists = .true.
    call mark_partial_file(1, self%part_path)
    call h5pcreate_f(H5P_LINK_CREATE_F, self%link_plist, hdferr)
    if (hdferr >= 0) call h5pset_create_inter_group_f(self%link_plist, 1, hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot set up HDF5 link creation in ' // self%part_path)
      return
    end if
  end subroutine create

  !> `/mesh/coordinates`: coordinates(3, nnode), global Cartesian (h5py: nnode x 3).
  subroutine write_mesh(self, coordinates, error)
    class(results_file_t), intent(inout) :: self
    real(dp), intent(in) :: coordinates(:, :)
    type(error_t), allocatable, intent(out) :: error

    if (self%silent) return
    call require_open(self, error)
    if (allocated(error)) return
    if (size(coordinates, 1) /= 3) then
      call fatal_error(error, err_internal, 'write_mesh: coordinates need 3 rows, got ' // &
                       str(size(coordinates, 1)))
      return
    end if
    if (self%node_count > 0) then
      call fatal_error(error, err_internal, 'write_mesh: the mesh is already written')
      return
    end if
    call refuse_non_finite(coordinates, '/mesh/coordinates', 'x y z', 'node', error)
    if (allocated(error)) return
    call write_real_dataset(self, '/mesh/coordinates', coordinates, 'x y z', error)
    if (allocated(error)) return
    self%node_count = size(coordinates, 2)
  end subroutine write_mesh

  !> `/mesh/groups/<name>/connectivity`: connectivity(k, nelem), 1-based node numbers, and the
  !! group attribute `element_type`; for a type of the element catalog also what the catalog
  !! says of it (attributes `family`, `dimension`, `points_per_element`, `result_field`,
  !! `components`, `xdmf_topology`: the scripts read these, never a table of their own) and the
  !! 0-based nodes of its XDMF cell at `/xdmf/<name>/topology` (all k, or the lower layer of an
  !! interface element). Given the mesh `coordinates`, also `/mesh/groups/<name>/points`: the
  !! global coordinates of its integration points, in the rows of its point datasets. An untyped
  !! block of a bare DATAIN mesh (`nodes<k>`) has none of these.
  subroutine write_group(self, name, element_type, connectivity, error, material, coordinates, element_ids)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: element_type
    integer, intent(in) :: connectivity(:, :)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: material   !! its material's name (attribute `material`)
    real(dp), intent(in), optional :: coordinates(:, :)  !! (3, nnode) the mesh: with it a catalog type's
                                                         !! integration points go to `points`, the
                                                         !! measure each stands for to `point_weights`
    integer, intent(in), optional :: element_ids(:)      !! the deck's element ids: written to `element_ids`
                                                         !! (nelem x 1) unless they are 1, 2, ..., nelem
    integer(hid_t) :: group_id
    integer :: hdferr, cell_nodes
    type(xdmf_group_t), allocatable :: grown(:)
    type(element_info_t) :: info
    type(error_t), allocatable :: unknown
    real(dp), allocatable :: xg(:, :), wg(:)

    if (self%silent) return
    call require_open(self, error)
    if (allocated(error)) return
    call check_name(name, 'element group', error)
    if (allocated(error)) return
    if (find_group(self, name) > 0) then
      call fatal_error(error, err_internal, 'write_group: group ' // name // ' is already written')
      return
    end if

    call h5gcreate_f(self%file_id, '/mesh/groups/' // name, group_id, hdferr, lcpl_id=self%link_plist)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot create group /mesh/groups/' // name // ' in ' // self%part_path)
      return
    end if
    call write_string_attribute(group_id, 'element_type', element_type, error)
    if (present(material) .and. .not. allocated(error)) call write_string_attribute(group_id, 'material', material, &
                                                                                     error)
    call element_info(element_type, info, unknown)
    if (.not. allocated(unknown) .and. .not. allocated(error)) call write_catalog_attributes(group_id, info, error)
    call h5gclose_f(group_id, hdferr)
    if (allocated(error)) return
    call write_int_dataset(self, '/mesh/groups/' // name // '/connectivity', connectivity, error)
    if (allocated(error)) return
    if (present(element_ids)) then
      if (any(element_ids /= [(hdferr, hdferr = 1, size(element_ids))])) then
        call write_int_dataset(self, '/mesh/groups/' // name // '/element_ids', &
                               reshape(element_ids, [1, size(element_ids)]), error)
        if (allocated(error)) return
      end if
    end if
    cell_nodes = size(connectivity, 1)
    if (allocated(unknown)) then
      info%xdmf_topology = ''
    else
      cell_nodes = info%xdmf_cell_nodes
      call write_int_dataset(self, xdmf_topology_path(name), connectivity(:cell_nodes, :) - 1, error)
      if (allocated(error)) return
      if (present(coordinates)) then
        call point_coordinates(element_type, coordinates, connectivity, xg, error, wg)
        if (allocated(error)) return
        call write_points_dataset(self, '/mesh/groups/' // name // '/points', xg, 'x y z', info%npoints, error)
        if (allocated(error)) return
        call write_points_dataset(self, '/mesh/groups/' // name // '/point_weights', reshape(wg, [1, size(wg)]), &
                                  'weight', info%npoints, error)
        if (allocated(error)) return
      end if
    end if

    allocate (grown(size(self%groups) + 1))
    grown(:size(self%groups)) = self%groups
    grown(size(grown))%name = name
    grown(size(grown))%element_type = element_type
    grown(size(grown))%topology = info%xdmf_topology
    grown(size(grown))%nodes_per_element = cell_nodes
    grown(size(grown))%element_count = size(connectivity, 2)
    call move_alloc(grown, self%groups)
  end subroutine write_group

  !> A dataset with one row per integration point (element-major) and its attribute
  !! `points_per_element`.
  subroutine write_points_dataset(self, path, values, components, points_per_element, error)
    type(results_file_t), intent(in) :: self
    character(len=*), intent(in) :: path, components
    real(dp), intent(in) :: values(:, :)
    integer, intent(in) :: points_per_element
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: dataset_id
    integer :: hdferr
    call write_real_dataset(self, path, values, components, error, dataset_id)
    if (allocated(error)) return
    call write_int_attribute(dataset_id, 'points_per_element', points_per_element, error)
    call h5dclose_f(dataset_id, hdferr)
  end subroutine write_points_dataset

  !> The element catalog's answers for a group's type, as attributes of its HDF5 group.
  subroutine write_catalog_attributes(group_id, info, error)
    integer(hid_t), intent(in) :: group_id
    type(element_info_t), intent(in) :: info
    type(error_t), allocatable, intent(out) :: error
    call write_string_attribute(group_id, 'family', family_name(info%family), error)
    if (.not. allocated(error)) call write_int_attribute(group_id, 'dimension', info%dimension, error)
    if (.not. allocated(error)) call write_int_attribute(group_id, 'points_per_element', info%npoints, error)
    if (.not. allocated(error)) call write_string_attribute(group_id, 'result_field', &
                                                            field_name(family_field(info%family)), error)
    if (.not. allocated(error)) call write_string_attribute(group_id, 'components', info%component_names, error)
    if (.not. allocated(error)) call write_string_attribute(group_id, 'xdmf_topology', info%xdmf_topology, error)
    if (len(info%abaqus_type) > 0 .and. .not. allocated(error)) &
      call write_string_attribute(group_id, 'abaqus_type', info%abaqus_type, error)
  end subroutine write_catalog_attributes

  !> Group `/steps/<NNNN>` with attributes `load_factor`, `iterations` and `residual`, and
  !! `tangent_determinant_sign` where `tangent_sign` is given and not 0 (known).
  subroutine begin_step(self, step, load_factor, iterations, residual, error, tangent_sign)
    class(results_file_t), intent(inout) :: self
    integer, intent(in) :: step
    real(dp), intent(in) :: load_factor
    integer, intent(in) :: iterations
    real(dp), intent(in) :: residual
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: tangent_sign   !! +1 or -1: the sign of the step's exact tangent's determinant
    integer(hid_t) :: group_id
    integer :: hdferr
    type(xdmf_step_t), allocatable :: grown(:)

    if (self%silent) return
    call require_open(self, error)
    if (allocated(error)) return
    call flush_cells(self, error)
    if (allocated(error)) return
    if (step < 0) then
      call fatal_error(error, err_internal, 'begin_step: negative step number ' // str(step))
      return
    end if
    if (find_step(self, step) > 0) then
      call fatal_error(error, err_internal, 'begin_step: step ' // str(step) // ' is already written')
      return
    end if
    call refuse_non_finite_attribute('/steps/' // step_group_name(step), 'load_factor', load_factor, error)
    if (allocated(error)) return
    call refuse_non_finite_attribute('/steps/' // step_group_name(step), 'residual', residual, error)
    if (allocated(error)) return
    call h5gcreate_f(self%file_id, '/steps/' // step_group_name(step), group_id, hdferr, &
                     lcpl_id=self%link_plist)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot create group /steps/' // step_group_name(step) // &
                       ' in ' // self%part_path)
      return
    end if
    call write_real_attribute(group_id, 'load_factor', load_factor, error)
    if (.not. allocated(error)) call write_int_attribute(group_id, 'iterations', iterations, error)
    if (.not. allocated(error)) call write_real_attribute(group_id, 'residual', residual, error)
    if (present(tangent_sign)) then
      if (tangent_sign /= 0 .and. .not. allocated(error)) &
        call write_int_attribute(group_id, 'tangent_determinant_sign', tangent_sign, error)
    end if
    call h5gclose_f(group_id, hdferr)
    if (allocated(error)) return

    allocate (grown(size(self%steps) + 1))
    grown(:size(self%steps)) = self%steps
    grown(size(grown))%number = step
    grown(size(grown))%load_factor = load_factor
    allocate (grown(size(grown))%fields(0), grown(size(grown))%cells(0))
    call move_alloc(grown, self%steps)
  end subroutine begin_step

  !> `/steps/<NNNN>/<name>`: values(ncomp, nnode) at the nodes, attribute `components`
  !! (ncomp space-separated names, e.g. 'ux uy uz'). With `group`, the field belongs to that
  !! element group, `/steps/<NNNN>/<name>/<group>`, and the XDMF file shows it on its grid only.
  subroutine write_nodal(self, step, name, values, components, error, group)
    class(results_file_t), intent(inout) :: self
    integer, intent(in) :: step
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: values(:, :)
    character(len=*), intent(in) :: components
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: group
    integer :: istep
    character(len=:), allocatable :: dataset, owner

    if (self%silent) return
    call require_step(self, step, istep, error)
    if (allocated(error)) return
    call check_name(name, 'nodal field', error)
    if (allocated(error)) return
    owner = ''
    if (present(group)) then
      call check_name(group, 'element group', error)
      if (allocated(error)) return
      owner = group
    end if
    call check_components(components, size(values, 1), name, error)
    if (allocated(error)) return
    if (self%node_count > 0 .and. size(values, 2) /= self%node_count) then
      call fatal_error(error, err_internal, 'write_nodal: ' // name // ' has ' // str(size(values, 2)) // &
                       ' nodes, the mesh ' // str(self%node_count))
      return
    end if
    dataset = '/steps/' // step_group_name(step) // '/' // name
    if (len(owner) > 0) dataset = dataset // '/' // owner
    call refuse_non_finite(values, dataset, components, 'node', error)
    if (allocated(error)) return
    call write_real_dataset(self, dataset, values, components, error)
    if (allocated(error)) return
    call add_field(self%steps(istep), name, dataset, owner, components, .true., size(values, 2), size(values, 1))
  end subroutine write_nodal

  !> `/steps/<NNNN>/<kind>/<group>`: values(ncomp, npoints) at the Gauss points, element-major, with
  !! attributes `components` and `points_per_element`; and the element averages of each component,
  !! (ncomp, nelem), at `/steps/<NNNN>/cell/<kind>/<group>` for the XDMF file.
  subroutine write_gauss(self, step, kind, group, values, components, points_per_element, error)
    class(results_file_t), intent(inout) :: self
    integer, intent(in) :: step
    character(len=*), intent(in) :: kind
    character(len=*), intent(in) :: group
    real(dp), intent(in) :: values(:, :)
    character(len=*), intent(in) :: components
    integer, intent(in) :: points_per_element
    type(error_t), allocatable, intent(out) :: error
    integer :: istep, igroup, nelem, e
    integer(hid_t) :: dataset_id
    integer :: hdferr
    character(len=:), allocatable :: dataset, cell_dataset
    real(dp), allocatable :: averages(:, :)

    if (self%silent) return
    call require_step(self, step, istep, error)
    if (allocated(error)) return
    call check_name(kind, 'Gauss-point field', error)
    if (allocated(error)) return
    if (kind == 'cell') then
      call fatal_error(error, err_internal, "write_gauss: kind 'cell' is reserved for element averages")
      return
    end if
    call check_name(group, 'element group', error)
    if (allocated(error)) return
    call check_components(components, size(values, 1), kind // '/' // group, error)
    if (allocated(error)) return
    if (points_per_element < 1) then
      call fatal_error(error, err_internal, 'write_gauss: points_per_element must be positive')
      return
    end if
    if (mod(size(values, 2), points_per_element) /= 0) then
      call fatal_error(error, err_internal, 'write_gauss: ' // str(size(values, 2)) // &
                       ' points are not a multiple of ' // str(points_per_element) // ' per element')
      return
    end if
    nelem = size(values, 2) / points_per_element
    igroup = find_group(self, group)
    if (igroup > 0) then
      if (self%groups(igroup)%element_count /= nelem) then
        call fatal_error(error, err_internal, 'write_gauss: ' // kind // '/' // group // ' has ' // &
                         str(nelem) // ' elements, the group ' // str(self%groups(igroup)%element_count))
        return
      end if
    end if

    dataset = '/steps/' // step_group_name(step) // '/' // kind // '/' // group
    call refuse_non_finite(values, dataset, components, 'point', error, points_per_element)
    if (allocated(error)) return
    call write_real_dataset(self, dataset, values, components, error, dataset_id)
    if (allocated(error)) return
    call write_int_attribute(dataset_id, 'points_per_element', points_per_element, error)
    call h5dclose_f(dataset_id, hdferr)
    if (allocated(error)) return

    allocate (averages(size(values, 1), nelem))
    do e = 1, nelem
      averages(:, e) = sum(values(:, (e - 1) * points_per_element + 1:e * points_per_element), dim=2) &
                       / real(points_per_element, dp)
    end do
    cell_dataset = '/steps/' // step_group_name(step) // '/cell/' // kind // '/' // group
    ! finite values near huge() can still sum beyond it
    call refuse_non_finite(averages, cell_dataset, components, 'element', error)
    if (allocated(error)) return
    call write_real_dataset(self, cell_dataset, averages, components, error)
    if (allocated(error)) return
    call add_field(self%steps(istep), kind, cell_dataset, group, components, .false., nelem, size(values, 1))
    if (igroup > 0) then
      if (len(self%groups(igroup)%topology) > 0) call keep_cells(self, kind, igroup, components, averages)
    end if
  end subroutine write_gauss

  !> Keep the element averages of `kind` of group `igroup` until the step ends (flush_cells).
  subroutine keep_cells(self, kind, igroup, components, averages)
    type(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: kind, components
    integer, intent(in) :: igroup
    real(dp), intent(in) :: averages(:, :)
    type(pending_cells_t), allocatable :: grown(:)
    integer :: n
    n = size(self%pending)
    allocate (grown(n + 1))
    grown(:n) = self%pending
    grown(n + 1)%kind = kind
    grown(n + 1)%components = components
    grown(n + 1)%group = igroup
    grown(n + 1)%averages = averages
    call move_alloc(grown, self%pending)
  end subroutine keep_cells

  !> End of a step's element averages: `/xdmf/steps/<NNNN>/<kind>` (h5py: ncell x ncomp) for each
  !! field, the averages of every cell the XDMF files show (the groups with an XDMF cell, in
  !! their order), NaN in the rows of groups without the field: the one dataset per field that
  !! meshio's reader splits over the cell blocks of its mesh. A field whose groups differ in
  !! their number of components is left out (meshio cannot hold it; none does today).
  subroutine flush_cells(self, error)
    type(results_file_t), intent(inout) :: self
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: first(:)
    real(dp), allocatable :: values(:, :)
    integer :: p, q, g, total, ncomp, istep, n
    logical :: seen, same
    type(xdmf_field_t), allocatable :: grown(:)
    character(len=:), allocatable :: dataset

    if (size(self%pending) == 0 .or. size(self%steps) == 0) return
    istep = size(self%steps)
    allocate (first(size(self%groups)))
    total = 0
    do g = 1, size(self%groups)
      first(g) = total + 1
      if (len(self%groups(g)%topology) > 0) total = total + self%groups(g)%element_count
    end do
    do p = 1, size(self%pending)
      seen = .false.
      same = .true.
      ncomp = size(self%pending(p)%averages, 1)
      do q = 1, size(self%pending)
        if (self%pending(q)%kind /= self%pending(p)%kind) cycle
        if (q < p) seen = .true.
        if (size(self%pending(q)%averages, 1) /= ncomp) same = .false.
      end do
      if (seen .or. .not. same) cycle
      allocate (values(ncomp, total))
      values = ieee_value(0.0_dp, ieee_quiet_nan)
      do q = p, size(self%pending)
        if (self%pending(q)%kind /= self%pending(p)%kind) cycle
        g = self%pending(q)%group
        values(:, first(g):first(g) + self%groups(g)%element_count - 1) = self%pending(q)%averages
      end do
      dataset = '/xdmf/steps/' // step_group_name(self%steps(istep)%number) // '/' // self%pending(p)%kind
      call write_real_dataset(self, dataset, values, self%pending(p)%components, error)
      deallocate (values)
      if (allocated(error)) return
      n = size(self%steps(istep)%cells)
      allocate (grown(n + 1))
      grown(:n) = self%steps(istep)%cells
      grown(n + 1)%name = self%pending(p)%kind
      grown(n + 1)%dataset = dataset
      grown(n + 1)%group = ''
      grown(n + 1)%components = self%pending(p)%components
      grown(n + 1)%nodal = .false.
      grown(n + 1)%rows = total
      grown(n + 1)%columns = ncomp
      call move_alloc(grown, self%steps(istep)%cells)
    end do
    deallocate (self%pending)
    allocate (self%pending(0))
  end subroutine flush_cells

  !> String attribute `key` of the group `/summary` (replaced if it exists).
  subroutine write_summary_string(self, key, value, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: key
    character(len=*), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: group_id
    integer :: hdferr
    if (self%silent) return
    call open_summary(self, key, group_id, error)
    if (allocated(error)) return
    call write_string_attribute(group_id, key, value, error)
    call h5gclose_f(group_id, hdferr)
  end subroutine write_summary_string

  !> Real attribute `key` of the group `/summary` (replaced if it exists).
  subroutine write_summary_real(self, key, value, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: key
    real(dp), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: group_id
    integer :: hdferr
    if (self%silent) return
    call refuse_non_finite_attribute('/summary', key, value, error)
    if (allocated(error)) return
    call open_summary(self, key, group_id, error)
    if (allocated(error)) return
    call write_real_attribute(group_id, key, value, error)
    call h5gclose_f(group_id, hdferr)
  end subroutine write_summary_real

  !> Real array attribute `key` of the group `/summary` (replaced if it exists), e.g. one value per
  !! MPI rank.
  subroutine write_summary_reals(self, key, values, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: key
    real(dp), intent(in) :: values(:)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: group_id, space_id, attribute_id
    integer(hsize_t) :: dims(1)
    integer :: hdferr, ignored, i
    if (self%silent) return
    do i = 1, size(values)
      call refuse_non_finite_attribute('/summary', key, values(i), error)
      if (allocated(error)) return
    end do
    call open_summary(self, key, group_id, error)
    if (allocated(error)) return
    dims = size(values)
    call h5screate_simple_f(1, dims, space_id, hdferr)
    if (hdferr >= 0) then
      call h5acreate_f(group_id, key, H5T_NATIVE_DOUBLE, space_id, attribute_id, hdferr)
      if (hdferr >= 0) then
        call h5awrite_f(attribute_id, H5T_NATIVE_DOUBLE, values, dims, hdferr)
        call h5aclose_f(attribute_id, ignored)
      end if
      call h5sclose_f(space_id, ignored)
    end if
    call h5gclose_f(group_id, ignored)
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot write attribute /summary/' // key)
  end subroutine write_summary_reals

  !> 64-bit integer attribute `key` of the group `/summary` (replaced if it exists).
  subroutine write_summary_int(self, key, value, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: key
    integer(i8), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: group_id
    integer :: hdferr2

    if (self%silent) return
    call open_summary(self, key, group_id, error)
    if (allocated(error)) return
    call write_int8_attribute(group_id, key, value, error)
    call h5gclose_f(group_id, hdferr2)
    if (allocated(error)) error%message = 'cannot write attribute /summary/' // key
  end subroutine write_summary_int

  !> Integer attribute `key` on `/mesh/groups/<name>` (a group written before).
  subroutine write_group_int(self, name, key, value, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: name, key
    integer(i8), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: group_id
    integer :: hdferr

    if (self%silent) return
    call open_mesh_group(self, name, group_id, error)
    if (allocated(error)) return
    call write_int8_attribute(group_id, key, value, error)
    call h5gclose_f(group_id, hdferr)
    if (allocated(error)) error%message = 'cannot write attribute /mesh/groups/' // name // '/' // key
  end subroutine write_group_int

  !> Real attribute `key` on `/mesh/groups/<name>` (a group written before).
  subroutine write_group_real(self, name, key, value, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: name, key
    real(dp), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: group_id
    integer :: hdferr

    if (self%silent) return
    call refuse_non_finite_attribute('/mesh/groups/' // name, key, value, error)
    if (allocated(error)) return
    call open_mesh_group(self, name, group_id, error)
    if (allocated(error)) return
    call write_real_attribute(group_id, key, value, error)
    call h5gclose_f(group_id, hdferr)
    if (allocated(error)) error%message = 'cannot write attribute /mesh/groups/' // name // '/' // key
  end subroutine write_group_real

  !> A resolved selection of the deck: `/sets/<kind>/<name>` holding `members(k, n)` (1-based:
  !! the node numbers of a node set, k = 1; the element of the group and its face of a face
  !! set, k = 2), with the attribute `components` (`node`, or `element face`) and, for a face
  !! set, `group`.
  subroutine write_set(self, kind, name, members, error, group)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: kind, name
    integer, intent(in) :: members(:, :)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: group
    integer(hid_t) :: id
    integer :: hdferr
    character(len=:), allocatable :: path
    if (self%silent) return
    call require_open(self, error)
    if (allocated(error)) return
    call check_name(name, kind // ' set', error)
    if (allocated(error)) return
    path = '/sets/' // kind // '/' // name
    call write_int_dataset(self, path, members, error)
    if (allocated(error)) return
    call h5dopen_f(self%file_id, path, id, hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot open dataset ' // path // ' in ' // self%part_path)
      return
    end if
    call write_string_attribute(id, 'components', trim(merge('node        ', 'element face', size(members, 1) == 1)), &
                                error)
    if (present(group) .and. .not. allocated(error)) call write_string_attribute(id, 'group', group, error)
    call h5dclose_f(id, hdferr)
  end subroutine write_set

  !> Support record k (from 1, in the deck's order) as the run read it, so that an exporter
  !! needs no second reading of the deck: the group `/constraints/<kkkk>` with the attributes
  !! `kind` (`fix`, `displace` or `release`), `set` (its node set, `/sets/nodes/<set>`), `dof`
  !! (1, 2 or 3: the direction in coordinate system `csys`), `csys`, `value` (the prescribed
  !! displacement, mm; 0 for fix and release), `stage` (0: scaled by each stage's load; s: an
  !! increment in stage s), `active_from` (the first stage it acts in), `total` (1: a DISPLACE
  !! with MODE=TOTAL) and `source` (the deck's file and line, `file:line`). A row of a LIST
  !! record acts on one node, which has no set: `set` is empty and `node` names it.
  subroutine write_constraint(self, k, c, set_name, error, node)
    class(results_file_t), intent(inout) :: self
    integer, intent(in) :: k
    type(constraint_t), intent(in) :: c
    character(len=*), intent(in) :: set_name
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: node
    integer(hid_t) :: id
    integer :: hdferr
    character(len=4) :: number
    character(len=:), allocatable :: path, kind, source
    if (self%silent) return
    call require_open(self, error)
    if (allocated(error)) return
    write (number, '(i4.4)') k
    path = '/constraints/' // number
    call h5gcreate_f(self%file_id, path, id, hdferr, lcpl_id=self%link_plist)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot create group ' // path // ' in ' // self%part_path)
      return
    end if
    kind = 'fix'
    if (c%prescribed) kind = 'displace'
    if (c%release) kind = 'release'
    source = ''
    if (allocated(c%file)) source = c%file
    source = source // ':' // str(c%line)
    call write_string_attribute(id, 'kind', kind, error)
    if (.not. allocated(error)) call write_string_attribute(id, 'set', set_name, error)
    if (.not. allocated(error)) call write_int_attribute(id, 'dof', c%dof, error)
    if (.not. allocated(error)) call write_int_attribute(id, 'csys', c%csys, error)
    if (.not. allocated(error)) call write_real_attribute(id, 'value', c%value, error)
    if (.not. allocated(error)) call write_int_attribute(id, 'stage', c%stage, error)
    if (.not. allocated(error)) call write_int_attribute(id, 'active_from', c%active_from, error)
    if (.not. allocated(error)) call write_int_attribute(id, 'total', merge(1, 0, c%total), error)
    if (.not. allocated(error)) call write_string_attribute(id, 'source', source, error)
    if (present(node) .and. .not. allocated(error)) call write_int_attribute(id, 'node', node, error)
    call h5gclose_f(id, hdferr)
  end subroutine write_constraint

  !> Open `/mesh/groups/<name>` of the open file (the caller closes it).
  subroutine open_mesh_group(self, name, group_id, error)
    class(results_file_t), intent(in) :: self
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: group_id
    type(error_t), allocatable, intent(out) :: error
    integer :: hdferr
    call require_open(self, error)
    if (allocated(error)) return
    call h5gopen_f(self%file_id, '/mesh/groups/' // name, group_id, hdferr)
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot open /mesh/groups/' // name // ' in ' // self%part_path)
  end subroutine open_mesh_group

  !> Group `/materials/<name>` with a string attribute `kind` and one attribute per parameter
  !! as the MATERIAL record gave it: a real, or a string where `texts(i)` is not empty.
  subroutine write_material(self, name, kind, keys, values, texts, error)
    class(results_file_t), intent(inout) :: self
    character(len=*), intent(in) :: name, kind
    character(len=*), intent(in) :: keys(:)
    real(dp), intent(in) :: values(:)
    character(len=*), intent(in) :: texts(:)    !! '' for a number (size 0: all numbers)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: group_id
    integer :: hdferr, i

    if (self%silent) return
    call require_open(self, error)
    if (allocated(error)) return
    call check_name(name, 'material', error)
    if (allocated(error)) return
    if (size(values) /= size(keys) .or. (size(texts) /= 0 .and. size(texts) /= size(keys))) then
      call fatal_error(error, err_internal, 'write_material: keys, values and texts differ in size')
      return
    end if
    do i = 1, size(keys)
      if (size(texts) > 0) then
        if (len_trim(texts(i)) > 0) cycle
      end if
      call refuse_non_finite_attribute('/materials/' // name, trim(keys(i)), values(i), error)
      if (allocated(error)) return
    end do
    call h5gcreate_f(self%file_id, '/materials/' // name, group_id, hdferr, lcpl_id=self%link_plist)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot create group /materials/' // name // ' in ' // self%part_path)
      return
    end if
    call write_string_attribute(group_id, 'kind', kind, error)
    do i = 1, size(keys)
      if (allocated(error)) exit
      if (size(texts) > 0) then
        if (len_trim(texts(i)) > 0) then
          call write_string_attribute(group_id, trim(keys(i)), trim(texts(i)), error)
          cycle
        end if
      end if
      call write_real_attribute(group_id, trim(keys(i)), values(i), error)
    end do
    call h5gclose_f(group_id, hdferr)
    if (allocated(error)) error%message = 'cannot write /materials/' // name // ': ' // error%message
  end subroutine write_material

  !> A scalar 64-bit integer attribute on an open group.
  subroutine write_int8_attribute(group_id, key, value, error)
    integer(hid_t), intent(in) :: group_id
    character(len=*), intent(in) :: key
    integer(i8), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: space_id, attribute_id
    integer :: hdferr, hdferr2
    integer(i8), target :: buffer
    type(c_ptr) :: pointer

    buffer = value
    pointer = c_loc(buffer)
    call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
    if (hdferr >= 0) then
      call h5acreate_f(group_id, key, H5T_STD_I64LE, space_id, attribute_id, hdferr)
      if (hdferr >= 0) then
        call h5awrite_f(attribute_id, h5kind_to_type(i8, H5_INTEGER_KIND), pointer, hdferr)
        call h5aclose_f(attribute_id, hdferr2)
      end if
      call h5sclose_f(space_id, hdferr2)
    end if
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot write attribute ' // key)
  end subroutine write_int8_attribute

  !> Close the HDF5 file, write the XDMF files beside it (ParaView's and meshio's, as `.part`) and
  !! rename the three to their names, the results first. On an error nothing of either is left (the caller's
  !! `discard` then removes what an earlier run left under these names).
  subroutine close_file(self, error)
    class(results_file_t), intent(inout) :: self
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: xdmf_path, meshio_path
    integer :: hdferr
    logical :: removed

    if (self%silent) return
    call require_open(self, error)
    if (allocated(error)) return
    call flush_cells(self, error)
    if (allocated(error)) return
    call release_handles(self, hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot write results file ' // self%path // ': closing ' // &
                       self%part_path // ' failed (disk full, quota, or an I/O error)')
      return
    end if

    xdmf_path = xdmf_file_name(self%path)
    meshio_path = meshio_file_name(self%path)
    call mark_partial_file(2, xdmf_path // '.part')
    call mark_partial_file(3, meshio_path // '.part')
    call write_xdmf(xdmf_path // '.part', base_name(self%path), self%node_count, self%groups, self%steps, error)
    if (.not. allocated(error)) call write_meshio_xdmf(meshio_path // '.part', base_name(self%path), &
                                                       self%node_count, self%groups, self%steps, error)
    if (allocated(error)) then
      removed = remove_regular_file(xdmf_path // '.part')
      removed = remove_regular_file(meshio_path // '.part')
      call mark_partial_file(2, '')
      call mark_partial_file(3, '')
      return
    end if
    if (c_rename(self%part_path // c_null_char, self%path // c_null_char) /= 0) then
      removed = remove_regular_file(xdmf_path // '.part')
      removed = remove_regular_file(meshio_path // '.part')
      call mark_partial_file(2, '')
      call mark_partial_file(3, '')
      call fatal_error(error, err_io, 'cannot rename ' // self%part_path // ' to ' // self%path)
      return
    end if
    self%part_exists = .false.
    call mark_partial_file(1, '')
    if (c_rename(xdmf_path // '.part' // c_null_char, xdmf_path // c_null_char) /= 0) then
      removed = remove_regular_file(xdmf_path // '.part')
      removed = remove_regular_file(meshio_path // '.part')
      removed = remove_regular_file(self%path)
      call mark_partial_file(2, '')
      call mark_partial_file(3, '')
      call fatal_error(error, err_io, 'cannot rename ' // xdmf_path // '.part to ' // xdmf_path)
      return
    end if
    call mark_partial_file(2, '')
    if (c_rename(meshio_path // '.part' // c_null_char, meshio_path // c_null_char) /= 0) then
      removed = remove_regular_file(meshio_path // '.part')
      removed = remove_regular_file(xdmf_path)
      removed = remove_regular_file(self%path)
      call mark_partial_file(3, '')
      call fatal_error(error, err_io, 'cannot rename ' // meshio_path // '.part to ' // meshio_path)
      return
    end if
    call mark_partial_file(3, '')
  end subroutine close_file

  !> Give up the file: close what is open and delete `<path>.part`, and the results and XDMF
  !! files (both: ParaView's and meshio's) an earlier run left under this name: after a failed run they would pass for its
  !! results. With keep_earlier (a deck refused before its first step) only `<path>.part` goes.
  !! Only regular files are removed, never a directory (the program refuses such result paths
  !! before a run). Harmless after `close`, twice, or before `create`.
  subroutine discard(self, keep_earlier)
    class(results_file_t), intent(inout) :: self
    logical, intent(in), optional :: keep_earlier
    integer :: hdferr
    logical :: keep, removed
    if (self%silent) return
    keep = .false.
    if (present(keep_earlier)) keep = keep_earlier
    if (self%is_open) call release_handles(self, hdferr)
    if (self%part_exists) then
      removed = remove_regular_file(self%part_path)
      if (.not. keep) then
        removed = remove_regular_file(self%path)
        removed = remove_regular_file(xdmf_file_name(self%path))
        removed = remove_regular_file(meshio_file_name(self%path))
      end if
      self%part_exists = .false.
      call mark_partial_file(1, '')
    end if
  end subroutine discard

  ! ---------------------------------------------------------------------------------------------

  !> Close the property list and the file; the object is closed even if HDF5 reports an error.
  subroutine release_handles(self, hdferr)
    type(results_file_t), intent(inout) :: self
    integer, intent(out) :: hdferr
    integer :: plist_err
    plist_err = 0
    if (self%link_plist >= 0) call h5pclose_f(self%link_plist, plist_err)
    self%link_plist = -1
    call h5fclose_f(self%file_id, hdferr)
    if (plist_err < 0) hdferr = plist_err
    self%file_id = -1
    self%is_open = .false.
  end subroutine release_handles

  subroutine require_open(self, error)
    type(results_file_t), intent(in) :: self
    type(error_t), allocatable, intent(out) :: error
    if (.not. self%is_open) call fatal_error(error, err_internal, 'results file is not open')
  end subroutine require_open

  !> Index of `step` in the steps begun, or an error.
  subroutine require_step(self, step, istep, error)
    type(results_file_t), intent(in) :: self
    integer, intent(in) :: step
    integer, intent(out) :: istep
    type(error_t), allocatable, intent(out) :: error
    istep = 0
    call require_open(self, error)
    if (allocated(error)) return
    istep = find_step(self, step)
    if (istep == 0) call fatal_error(error, err_internal, 'step ' // str(step) // ' was not begun')
  end subroutine require_step

  pure function find_step(self, step) result(istep)
    type(results_file_t), intent(in) :: self
    integer, intent(in) :: step
    integer :: istep
    do istep = size(self%steps), 1, -1
      if (self%steps(istep)%number == step) return
    end do
    istep = 0
  end function find_step

  pure function find_group(self, name) result(igroup)
    type(results_file_t), intent(in) :: self
    character(len=*), intent(in) :: name
    integer :: igroup
    do igroup = 1, size(self%groups)
      if (self%groups(igroup)%name == name) return
    end do
    igroup = 0
  end function find_group

  !> HDF5 link names: not empty, no '/', not '.' (they become one path component).
  subroutine check_name(name, what, error)
    character(len=*), intent(in) :: name, what
    type(error_t), allocatable, intent(out) :: error
    if (len_trim(name) == 0 .or. index(name, '/') > 0 .or. name == '.') then
      call fatal_error(error, err_io, 'cannot write results: ' // what // " name '" // name // &
                       "' is empty, '.' or contains '/'")
    end if
  end subroutine check_name

  subroutine check_components(components, ncomp, what, error)
    character(len=*), intent(in) :: components
    integer, intent(in) :: ncomp
    character(len=*), intent(in) :: what
    type(error_t), allocatable, intent(out) :: error
    if (count_words(components) /= ncomp) then
      call fatal_error(error, err_internal, what // ": components '" // components // "' name " // &
                       str(count_words(components)) // ' columns, the values have ' // str(ncomp))
    end if
  end subroutine check_components

  subroutine add_field(step, name, dataset, group, components, nodal, rows, columns)
    type(xdmf_step_t), intent(inout) :: step
    character(len=*), intent(in) :: name, dataset, group, components
    logical, intent(in) :: nodal
    integer, intent(in) :: rows, columns
    type(xdmf_field_t), allocatable :: grown(:)
    integer :: n
    n = size(step%fields)
    allocate (grown(n + 1))
    grown(:n) = step%fields
    grown(n + 1)%name = name
    grown(n + 1)%dataset = dataset
    grown(n + 1)%group = group
    grown(n + 1)%components = components
    grown(n + 1)%nodal = nodal
    grown(n + 1)%rows = rows
    grown(n + 1)%columns = columns
    call move_alloc(grown, step%fields)
  end subroutine add_field

  !> No NaN or Infinity in a dataset: values(ncomp, n), one row per `rows` ('node', 'element',
  !! or 'point': a Gauss point, whose element is named too).
  subroutine refuse_non_finite(values, dataset, components, rows, error, points_per_element)
    real(dp), intent(in) :: values(:, :)
    character(len=*), intent(in) :: dataset, components, rows
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: points_per_element
    character(len=:), allocatable :: row
    integer :: at(2)
    if (all(ieee_is_finite(values))) return
    at = findloc(ieee_is_finite(values), .false.)
    row = rows // ' ' // str(at(2))
    if (present(points_per_element)) row = row // ' (element ' // str((at(2) - 1) / points_per_element + 1) // ')'
    call fatal_error(error, err_solver, 'refusing to write a value that is not finite: ' // dataset // ': ' // &
                     row // ', ' // word(components, at(1)) // ' is ' // str(values(at(1), at(2))))
  end subroutine refuse_non_finite

  !> No NaN or Infinity in a real attribute `key` of the object at `path`.
  subroutine refuse_non_finite_attribute(path, key, value, error)
    character(len=*), intent(in) :: path, key
    real(dp), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    if (ieee_is_finite(value)) return
    call fatal_error(error, err_solver, 'refusing to write a value that is not finite: ' // path // &
                     ': attribute ' // key // ' is ' // str(value))
  end subroutine refuse_non_finite_attribute

  !> Open `/summary` (created on first use) and remove an existing attribute `key`.
  subroutine open_summary(self, key, group_id, error)
    type(results_file_t), intent(in) :: self
    character(len=*), intent(in) :: key
    integer(hid_t), intent(out) :: group_id
    type(error_t), allocatable, intent(out) :: error
    logical :: exists
    integer :: hdferr

    group_id = -1
    call require_open(self, error)
    if (allocated(error)) return
    if (len_trim(key) == 0) then
      call fatal_error(error, err_internal, 'summary attribute name is empty')
      return
    end if
    call h5lexists_f(self%file_id, 'summary', exists, hdferr)
    if (hdferr >= 0) then
      if (exists) then
        call h5gopen_f(self%file_id, 'summary', group_id, hdferr)
      else
        call h5gcreate_f(self%file_id, 'summary', group_id, hdferr)
      end if
    end if
    if (hdferr >= 0) then
      call h5aexists_f(group_id, key, exists, hdferr)
      if (hdferr >= 0 .and. exists) call h5adelete_f(group_id, key, hdferr)
      if (hdferr < 0) call h5gclose_f(group_id, hdferr)
    end if
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot open group /summary in ' // self%part_path)
  end subroutine open_summary

  !> Dataset of doubles, values(ncomp, n) (h5py: n x ncomp), with attribute `components`. With
  !! `dataset_id` present the dataset stays open for more attributes (the caller closes it).
  subroutine write_real_dataset(self, path, values, components, error, dataset_id)
    type(results_file_t), intent(in) :: self
    character(len=*), intent(in) :: path
    real(dp), intent(in) :: values(:, :)
    character(len=*), intent(in) :: components
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t), intent(out), optional :: dataset_id
    integer(hid_t) :: id
    integer(hsize_t) :: dims(2)
    integer :: hdferr, ignored

    dims = shape(values, kind=hsize_t)
    call create_dataset_2d(self, path, H5T_NATIVE_DOUBLE, dims, id, error)
    if (allocated(error)) return
    hdferr = 0
    if (size(values) > 0) call h5dwrite_f(id, H5T_NATIVE_DOUBLE, values, dims, hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot write dataset ' // path // ' in ' // self%part_path // &
                                   ' (disk full, quota, or an I/O error)')
    else
      call write_string_attribute(id, 'components', components, error)
    end if
    if (present(dataset_id) .and. .not. allocated(error)) then
      dataset_id = id
    else
      call h5dclose_f(id, ignored)
      if (present(dataset_id)) dataset_id = -1
    end if
  end subroutine write_real_dataset

  !> Create the 2D dataset `path` of HDF5 type `type_id` and shape `dims`; `id` stays open.
  subroutine create_dataset_2d(self, path, type_id, dims, id, error)
    type(results_file_t), intent(in) :: self
    character(len=*), intent(in) :: path
    integer(hid_t), intent(in) :: type_id
    integer(hsize_t), intent(in) :: dims(2)
    integer(hid_t), intent(out) :: id
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: space_id
    integer :: hdferr, ignored

    id = -1
    call h5screate_simple_f(2, dims, space_id, hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot create dataspace for ' // path)
      return
    end if
    call h5dcreate_f(self%file_id, path, type_id, space_id, id, hdferr, lcpl_id=self%link_plist)
    call h5sclose_f(space_id, ignored)
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot create dataset ' // path // ' in ' // self%part_path)
  end subroutine create_dataset_2d

  !> Dataset of default integers, values(k, n) (h5py: n x k).
  subroutine write_int_dataset(self, path, values, error)
    type(results_file_t), intent(in) :: self
    character(len=*), intent(in) :: path
    integer, intent(in) :: values(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: id
    integer(hsize_t) :: dims(2)
    integer :: hdferr, ignored

    dims = shape(values, kind=hsize_t)
    call create_dataset_2d(self, path, H5T_NATIVE_INTEGER, dims, id, error)
    if (allocated(error)) return
    hdferr = 0
    if (size(values) > 0) call h5dwrite_f(id, H5T_NATIVE_INTEGER, values, dims, hdferr)
    call h5dclose_f(id, ignored)
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot write dataset ' // path // ' in ' // self%part_path // &
                                   ' (disk full, quota, or an I/O error)')
  end subroutine write_int_dataset

  !> Fixed-length, null-padded ASCII string attribute (h5py reads it as bytes).
  subroutine write_string_attribute(object_id, name, value, error)
    integer(hid_t), intent(in) :: object_id
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: type_id, space_id, attribute_id
    integer(hsize_t) :: dims(1)
    integer :: hdferr, ignored
    character(len=max(1, len(value))) :: buffer

    ! HDF5 strings cannot have length 0: an empty value is stored as one null character.
    buffer = value
    if (len(value) == 0) buffer = c_null_char
    dims = 1
    call h5tcopy_f(H5T_FORTRAN_S1, type_id, hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot create string type for attribute ' // name)
      return
    end if
    call h5tset_size_f(type_id, int(len(buffer), size_t), hdferr)
    if (hdferr >= 0) call h5tset_strpad_f(type_id, H5T_STR_NULLPAD_F, hdferr)
    if (hdferr >= 0) call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
    if (hdferr >= 0) then
      call h5acreate_f(object_id, name, type_id, space_id, attribute_id, hdferr)
      if (hdferr >= 0) then
        call h5awrite_f(attribute_id, type_id, buffer, dims, hdferr)
        call h5aclose_f(attribute_id, ignored)
      end if
      call h5sclose_f(space_id, ignored)
    end if
    call h5tclose_f(type_id, ignored)
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot write string attribute ' // name)
  end subroutine write_string_attribute

  subroutine write_real_attribute(object_id, name, value, error)
    integer(hid_t), intent(in) :: object_id
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: space_id, attribute_id
    integer(hsize_t) :: dims(1)
    integer :: hdferr, ignored
    dims = 1
    call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
    if (hdferr >= 0) then
      call h5acreate_f(object_id, name, H5T_NATIVE_DOUBLE, space_id, attribute_id, hdferr)
      if (hdferr >= 0) then
        call h5awrite_f(attribute_id, H5T_NATIVE_DOUBLE, value, dims, hdferr)
        call h5aclose_f(attribute_id, ignored)
      end if
      call h5sclose_f(space_id, ignored)
    end if
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot write attribute ' // name)
  end subroutine write_real_attribute

  subroutine write_int_attribute(object_id, name, value, error)
    integer(hid_t), intent(in) :: object_id
    character(len=*), intent(in) :: name
    integer, intent(in) :: value
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: space_id, attribute_id
    integer(hsize_t) :: dims(1)
    integer :: hdferr, ignored
    dims = 1
    call h5screate_f(H5S_SCALAR_F, space_id, hdferr)
    if (hdferr >= 0) then
      call h5acreate_f(object_id, name, H5T_NATIVE_INTEGER, space_id, attribute_id, hdferr)
      if (hdferr >= 0) then
        call h5awrite_f(attribute_id, H5T_NATIVE_INTEGER, value, dims, hdferr)
        call h5aclose_f(attribute_id, ignored)
      end if
      call h5sclose_f(space_id, ignored)
    end if
    if (hdferr < 0) call fatal_error(error, err_io, 'cannot write attribute ' // name)
  end subroutine write_int_attribute

  pure function base_name(path) result(name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: name
    name = path(index(path, '/', back=.true.) + 1:)
  end function base_name

end module feps_results_file
