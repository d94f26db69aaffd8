!> XDMF (version 3 XML) description of a feps HDF5 results file, so that ParaView (its "XDMF Reader"
!! and its "Xdmf3ReaderS/T") can open it.
!!
!! The XML only points into the HDF5 file: geometry from `/mesh/coordinates`, topology from the
!! 0-based connectivity copies `/xdmf/<group>/topology`, attributes from the nodal datasets and the
!! element averages `/steps/<NNNN>/cell/<kind>/<group>`, each a whole dataset (the XDMF 3 readers
!! skip hyperslabs as "unrecognized array type"). The steps of a group form a temporal collection
!! named after it, inside one spatial collection: readers that make grid names unique over the
!! file (both XDMF libraries do) then never rename a group from step to step, as they did when
!! each step was a spatial collection of the groups. Time is the step's load factor (stage - 1 +
!! the fraction of the stage applied: cumulative over the stages, so it grows from step to step);
!! the step number is grid (field) data. Every feps element type has an XDMF cell; a type without
!! one (none today) would be left out.
module feps_xdmf
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_io, str
  use feps_files, only: text_file_t
  implicit none
  private

  public :: write_xdmf, write_meshio_xdmf, xdmf_topology_path, count_words, word

  !> An element group as the XDMF file needs it.
  type, public :: xdmf_group_t
    character(len=:), allocatable :: name           !! group name, as in `/mesh/groups/<name>`
    character(len=:), allocatable :: element_type   !! feps element type (the element catalog's name)
    character(len=:), allocatable :: topology       !! its XDMF TopologyType ('': none, not shown)
    integer :: nodes_per_element = 0                !! nodes of the XDMF cell
    integer :: element_count = 0
  end type xdmf_group_t

  !> A dataset of one step that ParaView should show.
  type, public :: xdmf_field_t
    character(len=:), allocatable :: name        !! attribute name (nodal) or prefix (cell), e.g. 'stress'
    character(len=:), allocatable :: dataset     !! absolute HDF5 path of the dataset
    character(len=:), allocatable :: group       !! element group of a cell field or of a group's nodal
                                                 !! field; '' for a nodal field of every group
    character(len=:), allocatable :: components  !! space-separated component names
    logical :: nodal = .true.                    !! Center="Node" (else Center="Cell")
    integer :: rows = 0                          !! nodes or elements (h5py first dimension)
    integer :: columns = 0                       !! components (h5py second dimension)
  end type xdmf_field_t

  !> One written step and its fields.
  type, public :: xdmf_step_t
    integer :: number = 0
    real(dp) :: load_factor = 0.0_dp
    type(xdmf_field_t), allocatable :: fields(:)
    type(xdmf_field_t), allocatable :: cells(:)  !! each field's averages over every shown cell, for meshio
  end type xdmf_step_t

contains

  !> HDF5 path of the 0-based connectivity copy of a group.
  pure function xdmf_topology_path(group) result(path)
    character(len=*), intent(in) :: group
    character(len=:), allocatable :: path
    path = '/xdmf/' // group // '/topology'
  end function xdmf_topology_path

  !> Number of blank-separated words in `text`.
  pure function count_words(text) result(n)
    character(len=*), intent(in) :: text
    integer :: n
    integer :: i
    logical :: in_word
    n = 0
    in_word = .false.
    do i = 1, len(text)
      if (text(i:i) /= ' ') then
        if (.not. in_word) n = n + 1
        in_word = .true.
      else
        in_word = .false.
      end if
    end do
  end function count_words

  !> The k-th blank-separated word of `text` ('' if there are fewer words).
  pure function word(text, k) result(w)
    character(len=*), intent(in) :: text
    integer, intent(in) :: k
    character(len=:), allocatable :: w
    integer :: i, n, first
    n = 0
    first = 0
    w = ''
    do i = 1, len(text) + 1
      if (i <= len(text)) then
        if (text(i:i) /= ' ') then
          if (first == 0) first = i
          cycle
        end if
      end if
      if (first > 0) then
        n = n + 1
        if (n == k) then
          w = text(first:i - 1)
          return
        end if
        first = 0
      end if
    end do
  end function word

  !> Write the XDMF file `path` describing the HDF5 file `hdf5_name` (a name relative to the
  !! XDMF file's folder). With no steps the file shows the mesh alone; with no nodes, nothing.
  subroutine write_xdmf(path, hdf5_name, node_count, groups, steps, error)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: hdf5_name
    integer, intent(in) :: node_count
    type(xdmf_group_t), intent(in) :: groups(:)
    type(xdmf_step_t), intent(in) :: steps(:)
    type(error_t), allocatable, intent(out) :: error
    type(text_file_t) :: file
    integer :: i, g
    character(len=:), allocatable :: h5, message

    h5 = escape(hdf5_name)
    call file%open(path, message)
    if (len(message) > 0) then
      call fatal_error(error, err_io, 'cannot write XDMF file ' // path // ': ' // message)
      return
    end if

    call put('<?xml version="1.0" ?>')
    call put('<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>')
    call put('<Xdmf Version="3.0">')
    call put('  <Domain>')
    if (node_count > 0) then
      if (size(steps) == 0) then
        call put('    <Grid Name="mesh" GridType="Collection" CollectionType="Spatial">')
        do g = 1, size(groups)
          if (len(groups(g)%topology) > 0) call put_group_grid(6, g, 0)
        end do
        call put('    </Grid>')
      else
        call put('    <Grid Name="results" GridType="Collection" CollectionType="Spatial">')
        do g = 1, size(groups)
          if (len(groups(g)%topology) == 0) cycle
          call put('      <Grid Name="' // escape(groups(g)%name) // '" GridType="Collection" CollectionType="Temporal">')
          do i = 1, size(steps)
            call put_group_grid(8, g, i)
          end do
          call put('      </Grid>')
        end do
        call put('    </Grid>')
      end if
    end if
    call put('  </Domain>')
    call put('</Xdmf>')

    ! The close reports the first failure of any write, and a full disk at the flush: gfortran's
    ! formatted WRITE and CLOSE report none (an XDMF file was left empty with exit status 0).
    call file%close(message)
    if (len(message) > 0) call fatal_error(error, err_io, 'cannot write XDMF file ' // path // ': ' // message)

  contains

    !> One line; after the first failure nothing more is written (the close reports it).
    subroutine put(line)
      character(len=*), intent(in) :: line
      call file%write(line)
    end subroutine put

    !> The uniform grid of group `g` at step `istep` (0: the mesh alone, no time and no fields).
    subroutine put_group_grid(indent, g, istep)
      integer, intent(in) :: indent, g, istep
      character(len=:), allocatable :: pad, topology
      integer :: f
      pad = repeat(' ', indent)
      topology = groups(g)%topology
      call put(pad // '<Grid Name="' // escape(groups(g)%name) // '" GridType="Uniform">')
      if (istep > 0) call put(pad // '  <Time Value="' // real_text(steps(istep)%load_factor) // '"/>')
      if (topology == 'Polyline') then
        call put(pad // '  <Topology TopologyType="' // topology // '" NumberOfElements="' // &
                 str(groups(g)%element_count) // '" NodesPerElement="' // &
                 str(groups(g)%nodes_per_element) // '">')
      else
        call put(pad // '  <Topology TopologyType="' // topology // '" NumberOfElements="' // &
                 str(groups(g)%element_count) // '">')
      end if
      call put(pad // '    ' // data_item(h5, groups(g)%element_count, groups(g)%nodes_per_element, &
               'Int', '4', xdmf_topology_path(escape(groups(g)%name))))
      call put(pad // '  </Topology>')
      call put(pad // '  <Geometry GeometryType="XYZ">')
      call put(pad // '    ' // data_item(h5, node_count, 3, 'Float', '8', '/mesh/coordinates'))
      call put(pad // '  </Geometry>')
      if (istep == 0) then
        call put(pad // '</Grid>')
        return
      end if
      ! the step number and load factor as grid (field) data, which every reader shows beside
      ! the arrays (they ignore Information elements)
      call put(pad // '  <Attribute Name="step" AttributeType="Scalar" Center="Grid">')
      call put(pad // '    <DataItem Dimensions="1" NumberType="Int" Precision="4" Format="XML">' // &
               str(steps(istep)%number) // '</DataItem>')
      call put(pad // '  </Attribute>')
      call put(pad // '  <Attribute Name="load_factor" AttributeType="Scalar" Center="Grid">')
      call put(pad // '    <DataItem Dimensions="1" NumberType="Float" Precision="8" Format="XML">' // &
               real_text(steps(istep)%load_factor) // '</DataItem>')
      call put(pad // '  </Attribute>')
      if (allocated(steps(istep)%fields)) then
        do f = 1, size(steps(istep)%fields)
          associate (field => steps(istep)%fields(f))
            if (field%nodal) then
              if (field%rows == node_count .and. (len(field%group) == 0 .or. field%group == groups(g)%name)) &
                call put_attribute(pad // '  ', field, 'Node')
            else if (field%group == groups(g)%name .and. field%rows == groups(g)%element_count) then
              call put_attribute(pad // '  ', field, 'Cell')
            end if
          end associate
        end do
      end if
      call put(pad // '</Grid>')
    end subroutine put_group_grid

    !> One attribute of the whole dataset: a nodal field of global x y z components (e.g. 'ux uy
    !! uz') a Vector, one column a Scalar, anything else a Matrix of its columns (its components
    !! in the order of the dataset's `components`). Readers draw a Vector in global axes, so a field in
    !! nodal systems ('f1 f2 f3' of reaction_nodal) must not be one; a Tensor6 would be expanded
    !! to 9 components by one reader and not by the others.
    subroutine put_attribute(pad, field, center)
      character(len=*), intent(in) :: pad
      type(xdmf_field_t), intent(in) :: field
      character(len=*), intent(in) :: center
      character(len=:), allocatable :: kind
      if (field%nodal .and. field%columns == 3 .and. global_xyz(field%components)) then
        kind = 'Vector'
      else if (field%columns == 1) then
        kind = 'Scalar'
      else
        kind = 'Matrix'
      end if
      call put(pad // '<Attribute Name="' // escape(field%name) // '" AttributeType="' // kind // &
               '" Center="' // center // '">')
      call put(pad // '  ' // data_item(h5, field%rows, field%columns, 'Float', '8', escape(field%dataset)))
      call put(pad // '</Attribute>')
    end subroutine put_attribute

  end subroutine write_xdmf

  !> Write the XDMF file `path` for meshio's time-series reader (meshio.xdmf.TimeSeriesReader),
  !! describing the HDF5 file `hdf5_name`. That reader takes one mesh, the domain's uniform grid
  !! (one Topology per group with an XDMF cell: one cell block each, in the groups' order), and a
  !! temporal collection of uniform grids holding only Time and whole-dataset Attributes (no grid
  !! data, no hyperslab), whose cell data it splits over all the cell blocks: so a cell field is
  !! its dataset over every cell, `/xdmf/steps/<NNNN>/<kind>` (NaN for groups without it). A
  !! group's nodal field is named `<field>/<group>`, as its dataset.
  subroutine write_meshio_xdmf(path, hdf5_name, node_count, groups, steps, error)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: hdf5_name
    integer, intent(in) :: node_count
    type(xdmf_group_t), intent(in) :: groups(:)
    type(xdmf_step_t), intent(in) :: steps(:)
    type(error_t), allocatable, intent(out) :: error
    type(text_file_t) :: file
    integer :: i, g, f
    character(len=:), allocatable :: h5, message, name

    h5 = escape(hdf5_name)
    call file%open(path, message)
    if (len(message) > 0) then
      call fatal_error(error, err_io, 'cannot write XDMF file ' // path // ': ' // message)
      return
    end if
    call file%write('<?xml version="1.0" ?>')
    call file%write('<Xdmf Version="3.0">')
    call file%write('  <Domain>')
    if (node_count > 0) then
      call file%write('    <Grid Name="mesh" GridType="Uniform">')
      do g = 1, size(groups)
        if (len(groups(g)%topology) == 0) cycle
        call file%write('      <Topology TopologyType="' // groups(g)%topology // '" NumberOfElements="' // &
                        str(groups(g)%element_count) // '" NodesPerElement="' // &
                        str(groups(g)%nodes_per_element) // '">')
        call file%write('        ' // data_item(h5, groups(g)%element_count, groups(g)%nodes_per_element, 'Int', '4', &
                        xdmf_topology_path(escape(groups(g)%name))))
        call file%write('      </Topology>')
      end do
      call file%write('      <Geometry GeometryType="XYZ">')
      call file%write('        ' // data_item(h5, node_count, 3, 'Float', '8', '/mesh/coordinates'))
      call file%write('      </Geometry>')
      call file%write('    </Grid>')
    end if
    call file%write('    <Grid Name="steps" GridType="Collection" CollectionType="Temporal">')
    do i = 1, size(steps)
      if (node_count == 0) exit
      call file%write('      <Grid Name="step ' // str(steps(i)%number) // '" GridType="Uniform">')
      call file%write('        <Time Value="' // real_text(steps(i)%load_factor) // '"/>')
      if (allocated(steps(i)%fields)) then
        do f = 1, size(steps(i)%fields)
          associate (field => steps(i)%fields(f))
            if (.not. field%nodal .or. field%rows /= node_count) cycle
            name = field%name
            if (len(field%group) > 0) name = name // '/' // field%group
            call put_whole(name, field, 'Node')
          end associate
        end do
      end if
      if (allocated(steps(i)%cells)) then
        do f = 1, size(steps(i)%cells)
          call put_whole(steps(i)%cells(f)%name, steps(i)%cells(f), 'Cell')
        end do
      end if
      call file%write('      </Grid>')
    end do
    call file%write('    </Grid>')
    call file%write('  </Domain>')
    call file%write('</Xdmf>')
    call file%close(message)
    if (len(message) > 0) call fatal_error(error, err_io, 'cannot write XDMF file ' // path // ': ' // message)

  contains

    !> An attribute of the whole dataset of `field`.
    subroutine put_whole(attribute, field, center)
      character(len=*), intent(in) :: attribute, center
      type(xdmf_field_t), intent(in) :: field
      call file%write('        <Attribute Name="' // escape(attribute) // '" AttributeType="' // &
                      merge('Scalar', 'Matrix', field%columns == 1) // '" Center="' // center // '">')
      call file%write('          ' // data_item(h5, field%rows, field%columns, 'Float', '8', escape(field%dataset)))
      call file%write('        </Attribute>')
    end subroutine put_whole

  end subroutine write_meshio_xdmf

  !> True when the three words of `components` end in x, y and z (global Cartesian components).
  pure logical function global_xyz(components)
    character(len=*), intent(in) :: components
    character(len=*), parameter :: axes = 'xyz'
    character(len=:), allocatable :: w
    integer :: c
    global_xyz = count_words(components) == 3
    do c = 1, 3
      if (.not. global_xyz) return
      w = word(components, c)
      global_xyz = w(len(w):) == axes(c:c)
    end do
  end function global_xyz

  !> Full-precision text of a real.
  pure function real_text(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=40) :: buf
    write (buf, '(es24.16e3)') x
    s = trim(adjustl(buf))
  end function real_text

  !> Text safe inside XML attribute values and element content.
  pure function escape(text) result(safe)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: safe
    integer :: i
    safe = ''
    do i = 1, len(text)
      select case (text(i:i))
      case ('&')
        safe = safe // '&amp;'
      case ('<')
        safe = safe // '&lt;'
      case ('>')
        safe = safe // '&gt;'
      case ('"')
        safe = safe // '&quot;'
      case ("'")
        safe = safe // '&apos;'
      case default
        safe = safe // text(i:i)
      end select
    end do
  end function escape

  !> A DataItem pointing into the HDF5 file `h5` (its name, XML-escaped); rows x columns as
  !! h5py sees the dataset. Both XDMF files, ParaView's and meshio's, point with it.
  pure function data_item(h5, rows, columns, number_type, precision, dataset) result(line)
    character(len=*), intent(in) :: h5
    integer, intent(in) :: rows, columns
    character(len=*), intent(in) :: number_type, precision, dataset
    character(len=:), allocatable :: line
    line = '<DataItem Dimensions="' // str(rows) // ' ' // str(columns) // '" NumberType="' // &
           number_type // '" Precision="' // precision // '" Format="HDF">' // h5 // ':' // &
           dataset // '</DataItem>'
  end function data_item

end module feps_xdmf
