!> The nodal fields of a group: its point results extrapolated to the nodes of each element
!! (feps_stress_recovery) and averaged over the elements that share a node. A row per mesh
!! node; at nodes of no element of the group each column holds its smallest value over the
!! group's nodes (fill_outside), so that one colour scale shows every group.
module feps_nodal_fields
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_internal
  use feps_model, only: model_t
  use feps_solid_element, only: solid_element_t
  use feps_element_catalog, only: new_solid_element
  use feps_interface_element, only: interface_element_t, new_interface_element
  use feps_principal, only: principal_values
  use feps_stress_frames, only: stress_in_basis
  use feps_stress_recovery, only: extrapolation_matrix, extrapolation_from_points, nodal_average, fill_outside
  implicit none
  private

  public :: solid_nodal_stresses, interface_nodal_tractions

contains

  !> Solid group `g`: the stresses at its nodes (`nodal`, 6 x nnode), and from the averaged
  !! tensors, before the filling, their most tensile and most compressive principal values
  !! (`principal`, 2 x nnode, when `want_principal`) and their components in the frame of
  !! system `csys` at each node (`cylindrical`, 6 x nnode, when csys > 0).
  subroutine solid_nodal_stresses(model, g, stress, want_principal, csys, nodal, principal, cylindrical, error)
    type(model_t), intent(in) :: model
    integer, intent(in) :: g
    real(dp), intent(in) :: stress(:, :)       !! (6, points) element-major
    logical, intent(in) :: want_principal
    integer, intent(in) :: csys                !! 0: no cylindrical components
    real(dp), allocatable, intent(out) :: nodal(:, :), principal(:, :), cylindrical(:, :)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: e(:, :)
    integer, allocatable :: count(:)
    real(dp) :: p(3)
    integer :: node
    logical :: ok
    associate (group => model%groups(g))
      call new_solid_element(group%element_type, element, error)
      if (allocated(error)) return
      call extrapolation_matrix(element, e, ok)
      if (.not. ok) then
        call fatal_error(error, err_internal, 'group ' // group%name // ': no extrapolation from the Gauss points ' // &
                         'of element type ' // group%element_type // ' to its nodes')
        return
      end if
      allocate (nodal(size(stress, 1), model%nnode), count(model%nnode))
      call nodal_average(e, group%connectivity, stress, model%nnode, nodal, count)
      if (want_principal) then
        allocate (principal(2, model%nnode))
        principal = 0.0_dp
        !$omp parallel do schedule(static) private(p)
        do node = 1, model%nnode
          if (count(node) == 0) cycle
          p = principal_values(nodal(:, node))
          principal(:, node) = [p(1), p(3)]
        end do
        !$omp end parallel do
        call fill_outside(principal, count)
      end if
      if (csys > 0) then
        allocate (cylindrical(6, model%nnode))
        cylindrical = 0.0_dp
        !$omp parallel do schedule(static)
        do node = 1, model%nnode
          if (count(node) == 0) cycle
          cylindrical(:, node) = stress_in_basis(nodal(:, node), model%systems(csys)%local_basis(model%coords(:, node)))
        end do
        !$omp end parallel do
        call fill_outside(cylindrical, count)
      end if
      call fill_outside(nodal, count)
    end associate
  end subroutine solid_nodal_stresses

  !> Interface group `g`: its tractions extrapolated from the integration points to the nodes
  !! of its lower layer (the XDMF grid's) and averaged there (`nodal`, ncomp x nnode).
  subroutine interface_nodal_tractions(model, g, traction, nodal, error)
    type(model_t), intent(in) :: model
    integer, intent(in) :: g
    real(dp), intent(in) :: traction(:, :)     !! (ncomp, points) element-major: tau1 tau2 sigma_n | tau sigma_n
    real(dp), allocatable, intent(out) :: nodal(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: e(:, :), points(:, :), w(:), nodes(:, :)
    integer, allocatable :: count(:)
    logical :: ok
    associate (group => model%groups(g))
      call new_interface_element(group%element_type, element, error)
      if (allocated(error)) return
      allocate (points(2, element%ngauss()), w(element%ngauss()), nodes(2, element%npairs()))
      call element%integration_rule(points, w)
      call element%node_coordinates(nodes)
      call extrapolation_from_points(points, nodes, e, ok)
      if (.not. ok) then
        call fatal_error(error, err_internal, 'group ' // group%name // ': no extrapolation from the points ' // &
                         'of element type ' // group%element_type // ' to its nodes')
        return
      end if
      allocate (nodal(size(traction, 1), model%nnode), count(model%nnode))
      call nodal_average(e, group%connectivity(1:element%npairs(), :), traction, model%nnode, nodal, count)
      call fill_outside(nodal, count)
    end associate
  end subroutine interface_nodal_tractions

end module feps_nodal_fields
