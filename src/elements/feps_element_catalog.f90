!> The element catalog: the one place that maps an element type name (the `TYPE=` of a deck's
!! GROUP) to its element object (`new_element`, any family behind the element contract
!! `element_t`) and to everything the rest of feps asks of a type: family, dimension, nodes,
!! integration points, the component names of its point results, XDMF cell (which result field
!! a family's points fill is the result schema's, src/model). The deck reader, model, assembly,
!! results and XDMF writers and stress recovery ask it; no other module spells an element type
!! name. The results file carries the answers as attributes of each `/mesh/groups/<name>`, so
!! the Python scripts read them from there.
!!
!! Adding an element type: its module in src/elements/, a row in `catalog` below and, for a
!! solid, its constructor `case` in `new_solid_element` (an interface or bar type: its shape in
!! that family's module, whose constructor parses the name). A new family: its module (a type
!! extending `element_t`), a `family_*` code, its `case` in `new_element` and its result
!! component names in `element_info`. test_element_contract runs every row through the contract.
module feps_element_catalog
  use feps_kinds, only: dp
  use feps_strings, only: to_lower
  use feps_error, only: error_t, fatal_error, err_input
  use feps_element, only: element_t
  use feps_solid_element, only: solid_element_t
  use feps_hex8, only: hex8_t
  use feps_hex8_bbar, only: hex8_bbar_t
  use feps_hex20, only: hex20_t
  use feps_tri6, only: tri6_t
  use feps_tet4, only: tet4_t
  use feps_tet10, only: tet10_t
  use feps_wedge6, only: wedge6_t
  use feps_wedge15, only: wedge15_t
  use feps_interface_element, only: interface_element_t, new_interface_element
  use feps_bar_element, only: bar_element_t, new_bar_element
  implicit none
  private

  public :: element_info_t, element_info, is_element_type, new_element, new_solid_element, known_element_types
  public :: family_name, bare_mesh_type, point_coordinates, catalog_types

  !> Element families: how an element's points carry their results.
  integer, parameter, public :: family_solid = 1       !! 6 stress components per point
  integer, parameter, public :: family_interface = 2   !! tractions (2D: 2, 3D: 3) per point
  integer, parameter, public :: family_bar = 3         !! the axial force per point

  !> One catalog row: the type's name, family, dimension (2: plane strain), XDMF cell, and the
  !! names of the same element elsewhere, for meshes made by other tools: the Abaqus/CalculiX
  !! element type and the meshio cell type ('' where none is the same element). The node order
  !! of every solid is that of Abaqus/CalculiX, which is also the order of meshio's cells read
  !! from an .inp or a gmsh .msh (meshio puts gmsh's second-order nodes in that order), so a
  !! mesh from either needs no reordering (test/cli/check_import.sh checks each against Lame).
  type :: catalog_row_t
    character(len=24) :: name
    integer :: family
    integer :: dimension
    character(len=16) :: xdmf_topology
    character(len=8) :: abaqus_type = ''
    character(len=16) :: meshio_type = ''
  end type catalog_row_t

  type(catalog_row_t), parameter :: catalog(*) = [ &
    catalog_row_t('hex8', family_solid, 3, 'Hexahedron', 'C3D8', 'hexahedron'), &
    catalog_row_t('hex8b', family_solid, 3, 'Hexahedron'), &
    catalog_row_t('hex20', family_solid, 3, 'Hexahedron_20', 'C3D20', 'hexahedron20'), &
    catalog_row_t('hex20r', family_solid, 3, 'Hexahedron_20', 'C3D20R', ''), &
    catalog_row_t('tet4', family_solid, 3, 'Tetrahedron', 'C3D4', 'tetra'), &
    catalog_row_t('tet10', family_solid, 3, 'Tetrahedron_10', 'C3D10', 'tetra10'), &
    catalog_row_t('wedge6', family_solid, 3, 'Wedge', 'C3D6', 'wedge'), &
    catalog_row_t('wedge15', family_solid, 3, 'Wedge_15', 'C3D15', 'wedge15'), &
    catalog_row_t('tri6', family_solid, 2, 'Triangle_6', 'CPE6', 'triangle6'), &
    catalog_row_t('tri6-6', family_solid, 2, 'Triangle_6'), &
    catalog_row_t('interface-quad4', family_interface, 3, 'Quadrilateral'), &
    catalog_row_t('interface-quad4-nodal', family_interface, 3, 'Quadrilateral'), &
    catalog_row_t('interface-quad8', family_interface, 3, 'Quadrilateral_8'), &
    catalog_row_t('interface-quad8-nodal', family_interface, 3, 'Quadrilateral_8'), &
    catalog_row_t('interface-tri3', family_interface, 3, 'Triangle'), &
    catalog_row_t('interface-tri3-nodal', family_interface, 3, 'Triangle'), &
    catalog_row_t('interface-tri6', family_interface, 3, 'Triangle_6'), &
    catalog_row_t('interface-tri6-nodal', family_interface, 3, 'Triangle_6'), &
    catalog_row_t('interface-line2', family_interface, 2, 'Polyline'), &
    catalog_row_t('interface-line2-nodal', family_interface, 2, 'Polyline'), &
    catalog_row_t('interface-line3', family_interface, 2, 'Edge_3'), &
    catalog_row_t('interface-line3-nodal', family_interface, 2, 'Edge_3'), &
    catalog_row_t('bar2', family_bar, 3, 'Polyline'), &
    catalog_row_t('bar3', family_bar, 3, 'Polyline'), &
    catalog_row_t('bar4', family_bar, 3, 'Polyline'), &
    catalog_row_t('bar5', family_bar, 3, 'Polyline')]

  !> What feps knows of an element type, from its catalog row and its element object.
  type :: element_info_t
    character(len=:), allocatable :: name             !! the catalog name, lower case
    integer :: family = 0                             !! family_solid, family_interface or family_bar
    integer :: dimension = 3                          !! 3, or 2 for plane-strain types
    integer :: nnodes = 0                             !! nodes per element (both layers of an interface)
    integer :: npoints = 0                            !! integration points per element
    integer :: ncomp = 0                              !! result components per point
    character(len=:), allocatable :: component_names  !! of its point results, blank-separated
    character(len=:), allocatable :: strain_component_names  !! of its point strains ('' if none written)
    character(len=:), allocatable :: xdmf_topology    !! the XDMF TopologyType of its cell
    integer :: xdmf_cell_nodes = 0                    !! nodes of that cell (an interface: its lower layer)
    character(len=:), allocatable :: abaqus_type      !! the same element in Abaqus/CalculiX ('' if none)
    character(len=:), allocatable :: meshio_type      !! meshio's cell type read as this type ('' if none)
  end type element_info_t

contains

  !> Everything the catalog knows of `type_name` (case-insensitive, surrounding blanks ignored).
  !! An unknown name returns an err_input error naming it and every known name.
  subroutine element_info(type_name, info, error)
    character(len=*), intent(in) :: type_name
    type(element_info_t), intent(out) :: info
    type(error_t), allocatable, intent(out) :: error
    class(element_t), allocatable :: element
    integer :: row
    row = find_row(type_name)
    if (row == 0) then
      call unknown_type(type_name, error)
      return
    end if
    info%name = trim(catalog(row)%name)
    info%family = catalog(row)%family
    info%dimension = catalog(row)%dimension
    info%xdmf_topology = trim(catalog(row)%xdmf_topology)
    info%abaqus_type = trim(catalog(row)%abaqus_type)
    info%meshio_type = trim(catalog(row)%meshio_type)
    call new_element(info%name, element, error)
    if (allocated(error)) return
    info%nnodes = element%nnodes()
    info%npoints = element%npoints()
    info%ncomp = element%ncomp()
    info%strain_component_names = ''
    info%xdmf_cell_nodes = info%nnodes
    select case (info%family)
    case (family_solid)
      info%component_names = 'sxx syy szz syz sxz sxy'
    case (family_interface)
      info%component_names = trim(merge('tau1 tau2 sigma_n', 'tau sigma_n      ', info%ncomp == 3))
      info%strain_component_names = trim(merge('gamma1 gamma2 eps_n', 'gamma eps_n        ', info%ncomp == 3))
      info%xdmf_cell_nodes = info%nnodes / 2
    case (family_bar)
      info%component_names = 'axial_force'
    end select
  end subroutine element_info

  !> Global coordinates `xg(3, npoints * nelem)` of the integration points of the elements
  !! `connectivity(:, e)` of type `type_name`, element by element in the row order of the
  !! results' point datasets (interfaces: on their lower layer; plane strain: z = 0), and, when
  !! asked for, the measure each stands for, `w(npoints * nelem)` (element_t's point_weights).
  subroutine point_coordinates(type_name, coords, connectivity, xg, error, w)
    character(len=*), intent(in) :: type_name
    real(dp), intent(in) :: coords(:, :)          !! (3, nnode)
    integer, intent(in) :: connectivity(:, :)     !! (nnodes, nelem)
    real(dp), allocatable, intent(out) :: xg(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable, intent(out), optional :: w(:)
    class(element_t), allocatable :: element
    integer :: e, np
    call new_element(type_name, element, error)
    if (allocated(error)) return
    np = element%npoints()
    allocate (xg(3, np * size(connectivity, 2)))
    xg = 0.0_dp
    if (present(w)) allocate (w(np * size(connectivity, 2)))
    do e = 1, size(connectivity, 2)
      call element%point_coordinates(coords(:, connectivity(:, e)), xg(:, (e - 1) * np + 1:e * np))
      if (present(w)) call element%point_weights(coords(:, connectivity(:, e)), w((e - 1) * np + 1:e * np))
    end do
  end subroutine point_coordinates

  !> True if `type_name` (case-insensitive) is in the catalog.
  pure logical function is_element_type(type_name)
    character(len=*), intent(in) :: type_name
    is_element_type = find_row(type_name) /= 0
  end function is_element_type

  !> Allocate the element object of `type_name` (case-insensitive, surrounding blanks ignored),
  !! of any family, behind the element contract. An unknown name returns an err_input error
  !! naming it and every known name.
  subroutine new_element(type_name, element, error)
    character(len=*), intent(in) :: type_name
    class(element_t), allocatable, intent(out) :: element
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: solid
    type(interface_element_t) :: iface
    type(bar_element_t) :: bar
    integer :: row
    row = find_row(type_name)
    if (row == 0) then
      call unknown_type(type_name, error)
      return
    end if
    select case (catalog(row)%family)
    case (family_solid)
      call new_solid_element(catalog(row)%name, solid, error)
      if (.not. allocated(error)) call move_alloc(solid, element)
    case (family_interface)
      call new_interface_element(catalog(row)%name, iface, error)
      if (.not. allocated(error)) allocate (element, source=iface)
    case (family_bar)
      call new_bar_element(catalog(row)%name, bar, error)
      if (.not. allocated(error)) allocate (element, source=bar)
    end select
  end subroutine new_element

  !> Allocate the solid element object of `type_name` (case-insensitive, surrounding blanks
  !! ignored), for what only solids have (shape functions, faces): 'hex8' (2x2x2 Gauss),
  !! 'hex8b' (B-bar), 'hex20' (3x3x3), 'hex20r' (2x2x2 reduced), 'tet4' (1 point), 'tet10'
  !! (4 points), 'wedge6' (3 x 2 points), 'wedge15' (6 x 3 points), 'tri6' (plane strain,
  !! 3 points), 'tri6-6' (6 points). Any other name, an interface or a bar included, returns
  !! an err_input error.
  subroutine new_solid_element(type_name, element, error)
    character(len=*), intent(in) :: type_name
    class(solid_element_t), allocatable, intent(out) :: element
    type(error_t), allocatable, intent(out) :: error
    select case (to_lower(trim(adjustl(type_name))))
    case ('hex8')
      allocate (hex8_t :: element)
    case ('hex8b')
      allocate (hex8_bbar_t :: element)
    case ('hex20')
      allocate (element, source=hex20_t(reduced=.false.))
    case ('hex20r')
      allocate (element, source=hex20_t(reduced=.true.))
    case ('tet4')
      allocate (tet4_t :: element)
    case ('tet10')
      allocate (tet10_t :: element)
    case ('wedge6')
      allocate (wedge6_t :: element)
    case ('wedge15')
      allocate (wedge15_t :: element)
    case ('tri6')
      allocate (element, source=tri6_t(six_point=.false.))
    case ('tri6-6')
      allocate (element, source=tri6_t(six_point=.true.))
    case default
      call fatal_error(error, err_input, "unknown solid element type '" // trim(adjustl(type_name)) // &
                       "' (known: " // known_element_types(family_solid) // ")")
    end select
  end subroutine new_solid_element

  !> The catalog's names, comma-separated: all of them, or those of one family and/or one
  !! dimension (2: the plane-strain types).
  pure function known_element_types(family, dimension) result(names)
    integer, intent(in), optional :: family
    integer, intent(in), optional :: dimension
    character(len=:), allocatable :: names
    integer :: row
    names = ''
    do row = 1, size(catalog)
      if (present(family)) then
        if (catalog(row)%family /= family) cycle
      end if
      if (present(dimension)) then
        if (catalog(row)%dimension /= dimension) cycle
      end if
      if (len(names) > 0) names = names // ', '
      names = names // trim(catalog(row)%name)
    end do
  end function known_element_types

  !> Every type name of the catalog, in its order.
  pure function catalog_types() result(names)
    character(len=24), allocatable :: names(:)
    names = catalog(:)%name
  end function catalog_types

  !> The type a block of a bare DATAIN mesh (a file of DATAIN records only, checked and reported
  !! without a deck) is read as, from its nodes per element: the first hexahedron of the catalog
  !! with that many nodes (hex8, hex20), the cells the DATAIN generator makes; '' for other
  !! counts, which several families share (6 nodes: a wedge, a plane triangle or a triangular
  !! interface), so such a block stays untyped.
  pure function bare_mesh_type(nodes) result(name)
    integer, intent(in) :: nodes
    character(len=:), allocatable :: name
    character(len=:), allocatable :: cell
    integer :: row
    name = ''
    select case (nodes)
    case (8)
      cell = 'Hexahedron'
    case (20)
      cell = 'Hexahedron_20'
    case default
      return
    end select
    do row = 1, size(catalog)
      if (catalog(row)%family == family_solid .and. trim(catalog(row)%xdmf_topology) == cell) then
        name = trim(catalog(row)%name)
        return
      end if
    end do
  end function bare_mesh_type

  !> 'solid', 'interface' or 'bar' for a family code ('' for any other).
  pure function family_name(family) result(name)
    integer, intent(in) :: family
    character(len=:), allocatable :: name
    select case (family)
    case (family_solid)
      name = 'solid'
    case (family_interface)
      name = 'interface'
    case (family_bar)
      name = 'bar'
    case default
      name = ''
    end select
  end function family_name

  pure integer function find_row(type_name) result(row)
    character(len=*), intent(in) :: type_name
    character(len=:), allocatable :: key
    integer :: i
    key = to_lower(trim(adjustl(type_name)))
    row = 0
    do i = 1, size(catalog)
      if (key == trim(catalog(i)%name)) then
        row = i
        return
      end if
    end do
  end function find_row

  pure subroutine unknown_type(type_name, error)
    character(len=*), intent(in) :: type_name
    type(error_t), allocatable, intent(out) :: error
    call fatal_error(error, err_input, "unknown element type '" // trim(adjustl(type_name)) // "' (known: " // &
                     known_element_types() // ")")
  end subroutine unknown_type

end module feps_element_catalog
