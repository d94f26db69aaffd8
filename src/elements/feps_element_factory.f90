!> Make a solid element from its name. Adding an element type means adding its module and one
!! case here.
module feps_element_factory
  use feps_strings, only: to_lower
  use feps_error, only: error_t, fatal_error, err_input
  use feps_element, only: element_t
  use feps_hex8, only: hex8_t
  use feps_hex20, only: hex20_t
  use feps_tri6, only: tri6_t
  use feps_hex8_bbar, only: hex8_bbar_t
  use feps_tet4, only: tet4_t
  use feps_tet10, only: tet10_t
  use feps_wedge6, only: wedge6_t
  use feps_wedge15, only: wedge15_t
  implicit none
  private

  public :: new_element

contains

  !> Allocate `element` for `type_name` (case-insensitive, surrounding blanks ignored):
  !! 'hex8' (2x2x2 Gauss), 'hex20' (3x3x3), 'hex20r' (hex20 with 2x2x2 reduced integration),
  !! 'tri6' (plane-strain 6-node triangle, 3-point rule), 'tri6-6' (tri6 with the 6-point rule),
  !! 'tet4' (1 point), 'tet10' (4 points), 'wedge6' (6 points), 'wedge15' (18 points).
  !! An unknown name returns an err_input error naming it and the known names.
  subroutine new_element(type_name, element, error)
    character(len=*), intent(in) :: type_name
    class(element_t), allocatable, intent(out) :: element
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
    case ('tri6')
      allocate (element, source=tri6_t(six_point=.false.))
    case ('tri6-6')
      allocate (element, source=tri6_t(six_point=.true.))
    case ('tet4')
      allocate (tet4_t :: element)
    case ('tet10')
      allocate (tet10_t :: element)
    case ('wedge6')
      allocate (wedge6_t :: element)
    case ('wedge15')
      allocate (wedge15_t :: element)
    case default
      call fatal_error(error, err_input, "unknown element type '" // trim(adjustl(type_name)) // &
                       "' (known: hex8, hex8b, hex20, hex20r, tri6, tri6-6, tet4, tet10, wedge6, wedge15)")
    end select
  end subroutine new_element


end module feps_element_factory
