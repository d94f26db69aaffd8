!> The order of an interface element's two layers, checked against its neighbours. An
!! interface's normal points from its lower layer (nodes 1..p) to its upper one (p+1..2p), so
!! that a positive normal strain is opening; given the layers the other way round (or the lower
!! layer wound clockwise seen from the upper side) the normal flips, and compression reads as
!! opening with nothing to show it. The check asks the element itself, through its strains:
!! the upper layer moved away from the solid element its lower layer is a face of must open
!! (and the lower layer moved away from the solid on the upper side must open too).
module feps_interface_orientation
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t
  use feps_element_catalog, only: family_solid, family_interface
  use feps_assembly, only: group_kernel_t, element_strains, node_list
  implicit none
  private

  public :: check_interface_orientation

  !> Below this share of the test displacement, the normal strain says nothing about the side
  !! (a neighbour whose centre lies nearly in the interface's plane): no verdict.
  real(dp), parameter :: clear_share = 1.0e-3_dp

contains

  !> Every interface element whose lower-layer (or upper-layer) nodes are all nodes of a solid
  !! element must open when its layers move apart away from that solid; an element that closes
  !! instead has its layers in the wrong order: an input error naming the group's file and line,
  !! the element and its nodes.
  subroutine check_interface_orientation(model, kernels, error)
    type(model_t), intent(in) :: model
    type(group_kernel_t), intent(in) :: kernels(:)
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: ptr(:), solid_group(:), solid_element(:)
    integer :: g, e, p, side
    if (.not. any([(model%groups(g)%element%family == family_interface, g = 1, size(model%groups))])) return
    call solids_at_nodes(model, ptr, solid_group, solid_element)
    do g = 1, size(model%groups)
      if (model%groups(g)%element%family /= family_interface) cycle
      associate (grp => model%groups(g))
        p = grp%element%nnodes / 2
        do e = 1, size(grp%connectivity, 2)
          do side = 1, 2
            if (opens_wrong_way(model, kernels(g), grp%connectivity(:, e), p, side, grp%element%ncomp, ptr, &
                                solid_group, solid_element)) then
              call input_error(error, grp%file, grp%line, 'interface element ' // str(e) // ' of group ' // &
                               grp%name // ' (nodes ' // node_list(grp%connectivity(:, e)) // ') has its ' // &
                               'layers in the wrong order: its normal points into the solid on its ' // &
                               trim(merge('lower', 'upper', side == 1)) // ' side, so compression would ' // &
                               'read as opening; give the lower layer first (the side the normal leaves, ' // &
                               'numbered counter-clockwise seen from the upper side), then the upper layer')
              return
            end if
          end do
        end do
      end associate
    end do
  end subroutine check_interface_orientation

  !> For layer `side` (1 lower, 2 upper) of the interface element `nodes`: the first solid
  !! element that holds every node of that layer, and whether moving the other layer away
  !! from that solid's centre closes the interface (wrong order) beyond doubt.
  logical function opens_wrong_way(model, kernel, nodes, p, side, normal, ptr, solid_group, solid_element) &
    result(wrong)
    type(model_t), intent(in) :: model
    type(group_kernel_t), intent(in) :: kernel
    integer, intent(in) :: nodes(:), p, side
    integer, intent(in) :: normal               !! the normal strain's component (the last)
    integer, intent(in) :: ptr(:), solid_group(:), solid_element(:)
    integer, allocatable :: layer(:), other(:)
    real(dp) :: centre(3), away(3), xe(3, size(nodes)), ue(3 * size(nodes)), length
    real(dp), allocatable :: eps(:, :)
    integer :: k, i, n
    wrong = .false.
    if (side == 1) then
      layer = nodes(1:p)
      other = [(i, i = p + 1, 2 * p)]
    else
      layer = nodes(p + 1:2 * p)
      other = [(i, i = 1, p)]
    end if
    do k = ptr(layer(1)), ptr(layer(1) + 1) - 1
      associate (solid => model%groups(solid_group(k))%connectivity(:, solid_element(k)))
        if (.not. all([(any(solid == layer(i)), i = 1, p)])) cycle
        centre = sum(model%coords(:, solid), dim=2) / size(solid)
      end associate
      away = sum(model%coords(:, layer), dim=2) / p - centre
      length = norm2(away)
      if (.not. (length > 0.0_dp)) return
      away = away / length
      xe = model%coords(:, nodes)
      ue = 0.0_dp
      do i = 1, p
        n = other(i)
        ue(3 * n - 2:3 * n) = away
      end do
      allocate (eps(kernel%ncomp, kernel%npoints))
      call element_strains(kernel, xe, ue, eps)
      ! the other layer moved away from this side's solid: opening, whichever side this is
      wrong = all(eps(normal, :) < -clear_share)
      return
    end do
  end function opens_wrong_way

  !> Solid elements at each node: for node n, entries ptr(n) .. ptr(n + 1) - 1 of
  !! solid_group and solid_element.
  subroutine solids_at_nodes(model, ptr, solid_group, solid_element)
    type(model_t), intent(in) :: model
    integer, allocatable, intent(out) :: ptr(:), solid_group(:), solid_element(:)
    integer, allocatable :: fill(:)
    integer :: g, e, a, n
    allocate (ptr(model%nnode + 1))
    ptr = 0
    do g = 1, size(model%groups)
      if (model%groups(g)%element%family /= family_solid) cycle
      do e = 1, size(model%groups(g)%connectivity, 2)
        do a = 1, size(model%groups(g)%connectivity, 1)
          n = model%groups(g)%connectivity(a, e)
          ptr(n + 1) = ptr(n + 1) + 1
        end do
      end do
    end do
    ptr(1) = 1
    do n = 1, model%nnode
      ptr(n + 1) = ptr(n + 1) + ptr(n)
    end do
    allocate (solid_group(ptr(model%nnode + 1) - 1), solid_element(ptr(model%nnode + 1) - 1))
    fill = ptr(1:model%nnode)
    do g = 1, size(model%groups)
      if (model%groups(g)%element%family /= family_solid) cycle
      do e = 1, size(model%groups(g)%connectivity, 2)
        do a = 1, size(model%groups(g)%connectivity, 1)
          n = model%groups(g)%connectivity(a, e)
          solid_group(fill(n)) = g
          solid_element(fill(n)) = e
          fill(n) = fill(n) + 1
        end do
      end do
    end do
  end subroutine solids_at_nodes

end module feps_interface_orientation
