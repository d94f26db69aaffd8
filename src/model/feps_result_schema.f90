!> The result schema: one table of the fields a run can write. FIELDS and --fields accept its
!! names, the run writes `/steps/<NNNN>/<name>` (or `/steps/<NNNN>/<name>/<group>`) with its
!! components, the summary lists the selected names, and test_result_schema holds
!! docs/output-format.md's table to it. A new field is a row here, its id, and its computation
!! in the program's observer.
module feps_result_schema
  use feps_element_catalog, only: family_solid, family_interface, family_bar
  implicit none
  private

  public :: field_index, known_field_names, field_name, field_components, family_field

  !> Where a field's rows are.
  integer, parameter, public :: at_nodes = 1        !! one row per mesh node
  integer, parameter, public :: at_points = 2       !! one row per integration point of a group
  integer, parameter, public :: at_group_nodes = 3  !! one row per mesh node, per group (averaged)

  !> One field: its name, where its rows are, which groups have it (0: the whole mesh), whether
  !! a run writes it without FIELDS, and its components ('': the element catalog's names for the
  !! group's type: its point results, or for interface_strain its point strains).
  type, public :: result_field_t
    character(len=16) :: name
    integer :: location
    integer :: family
    logical :: by_default
    character(len=40) :: components
  end type result_field_t

  integer, parameter, public :: field_displacement = 1, field_reaction = 2, field_applied_force = 3, &
                                field_stress = 4, field_principal = 5, field_interface = 6, &
                                field_interface_strain = 7, field_bar = 8, field_nodal_stress = 9, &
                                field_nodal_principal = 10, field_nodal_interface = 11, field_point_state = 12, &
                                field_stress_cyl = 13, field_nodal_stress_cyl = 14

  !> The fields, in the order of their ids (and of the summary's list).
  type(result_field_t), parameter, public :: result_fields(*) = [ &
    result_field_t('displacement', at_nodes, 0, .true., 'ux uy uz'), &
    result_field_t('reaction', at_nodes, 0, .true., 'fx fy fz'), &
    result_field_t('applied_force', at_nodes, 0, .true., 'fx fy fz'), &
    result_field_t('stress', at_points, family_solid, .true., ''), &
    result_field_t('principal', at_points, family_solid, .true., 'most_tensile most_compressive'), &
    result_field_t('interface', at_points, family_interface, .true., ''), &
    result_field_t('interface_strain', at_points, family_interface, .true., ''), &
    result_field_t('bar', at_points, family_bar, .true., ''), &
    result_field_t('nodal_stress', at_group_nodes, family_solid, .false., 'sxx syy szz syz sxz sxy'), &
    result_field_t('nodal_principal', at_group_nodes, family_solid, .false., 'most_tensile most_compressive'), &
    result_field_t('nodal_interface', at_group_nodes, family_interface, .false., ''), &
    result_field_t('point_state', at_points, family_solid, .false., 'state'), &
    result_field_t('stress_cyl', at_points, family_solid, .false., 'srr stt szz stz srz srt'), &
    result_field_t('nodal_stress_cyl', at_group_nodes, family_solid, .false., 'srr stt szz stz srz srt')]

contains

  !> The name of field `id`, as FIELDS takes it and the results file's datasets are called.
  pure function field_name(id) result(name)
    integer, intent(in) :: id
    character(len=:), allocatable :: name
    name = trim(result_fields(id)%name)
  end function field_name

  !> The fixed components of field `id` ('': the element catalog's, by the group's type).
  pure function field_components(id) result(components)
    integer, intent(in) :: id
    character(len=:), allocatable :: components
    components = trim(result_fields(id)%components)
  end function field_components

  !> The field of an element family's own point results (stress, interface or bar; 0 for
  !! another code), whose components are the element catalog's names for the group's type.
  pure integer function family_field(family)
    integer, intent(in) :: family
    select case (family)
    case (family_solid)
      family_field = field_stress
    case (family_interface)
      family_field = field_interface
    case (family_bar)
      family_field = field_bar
    case default
      family_field = 0
    end select
  end function family_field

  !> The id of the field called `name` (lower case), 0 if there is none.
  pure integer function field_index(name)
    character(len=*), intent(in) :: name
    integer :: k
    field_index = 0
    do k = 1, size(result_fields)
      if (trim(name) == trim(result_fields(k)%name)) then
        field_index = k
        return
      end if
    end do
  end function field_index

  !> The field names, comma-separated (for error messages).
  pure function known_field_names() result(list)
    character(len=:), allocatable :: list
    integer :: k
    list = trim(result_fields(1)%name)
    do k = 2, size(result_fields)
      list = list // ', ' // trim(result_fields(k)%name)
    end do
  end function known_field_names

end module feps_result_schema
