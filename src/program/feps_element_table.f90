!> `feps elements`: the element catalog as JSON, for tools that translate other programs' meshes
!! (scripts/import_mesh.py) and must not keep a second table of element types, node orders or
!! face numbers. One object per catalog type: its name, family, dimension, nodes, integration
!! points, the Abaqus/CalculiX and meshio names of the same element, and (solids) the local
!! nodes of each face, face k being the deck's face number k (FSET ..., FACE=k).
module feps_element_table
  use feps_error, only: error_t, str
  use feps_element_catalog, only: element_info_t, element_info, catalog_types, family_name, &
                                  new_solid_element, family_solid
  use feps_solid_element, only: solid_element_t
  use feps_results_observer, only: line_sink
  implicit none
  private

  public :: element_table_lines

contains

  !> Hand the catalog, as a JSON array with one type per line, to `emit`.
  subroutine element_table_lines(emit, error)
    procedure(line_sink) :: emit
    type(error_t), allocatable, intent(out) :: error
    character(len=24), allocatable :: names(:)
    type(element_info_t) :: info
    class(solid_element_t), allocatable :: solid
    character(len=:), allocatable :: line
    integer :: t, k

    names = catalog_types()
    call emit('[')
    do t = 1, size(names)
      call element_info(names(t), info, error)
      if (allocated(error)) return
      line = '  {"name": "' // info%name // '", "family": "' // family_name(info%family) // &
             '", "dimension": ' // str(info%dimension) // ', "nodes": ' // str(info%nnodes) // &
             ', "points": ' // str(info%npoints) // ', "abaqus": "' // info%abaqus_type // &
             '", "meshio": "' // info%meshio_type // '", "faces": ['
      if (info%family == family_solid) then
        call new_solid_element(info%name, solid, error)
        if (allocated(error)) return
        do k = 1, solid%nfaces()
          if (k > 1) line = line // ', '
          line = line // int_list(solid%face_nodes(k))
        end do
      end if
      line = line // ']}'
      if (t < size(names)) line = line // ','
      call emit(line)
    end do
    call emit(']')
  end subroutine element_table_lines

  pure function int_list(values) result(text)
    integer, intent(in) :: values(:)
    character(len=:), allocatable :: text
    integer :: i
    text = '['
    do i = 1, size(values)
      if (i > 1) text = text // ', '
      text = text // str(values(i))
    end do
    text = text // ']'
  end function int_list

end module feps_element_table
