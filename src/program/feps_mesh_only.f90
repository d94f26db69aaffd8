!> Mesh-only mode (a file of DATAIN records only: checked, reported and, with --output, written)
!! and the mesh part that every results file starts with.
module feps_mesh_only
  use feps_kinds, only: dp
  use feps_error, only: error_t
  use feps_version, only: feps_release
  use feps_model, only: model_t
  use feps_assembly, only: group_kernel_t, build_kernels, check_jacobians
  use feps_results_file, only: results_file_t
  use feps_element_catalog, only: family_solid
  implicit none
  private

  public :: mesh_jacobians, write_mesh_only, write_mesh

contains

  !> The smallest Jacobian of a bare DATAIN mesh, over its typed blocks (element_catalog's
  !! bare_mesh_type: hex8, hex20): a block of another node count (typed nodes<k>) has no
  !! element to evaluate and is only counted and
  !! written (it used to stop the run as an unsupported element type).
  subroutine mesh_jacobians(model, min_detj, error)
    type(model_t), intent(in) :: model
    real(dp), intent(out) :: min_detj
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: solids
    type(group_kernel_t), allocatable :: kernels(:)
    integer :: g
    solids%coords = model%coords
    allocate (solids%groups(0))
    do g = 1, size(model%groups)
      if (model%groups(g)%element%family == family_solid) solids%groups = [solids%groups, model%groups(g)]
    end do
    call build_kernels(solids, kernels, error)
    if (allocated(error)) return
    call check_jacobians(solids, kernels, min_detj, error)
  end subroutine mesh_jacobians

  !> Write the mesh of a bare DATAIN file to `path` (the results layout without steps).
  subroutine write_mesh_only(path, model, error)
    character(len=*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    type(results_file_t) :: h5
    call h5%create(path, error)
    if (allocated(error)) return
    call write_mesh(h5, model, error)
    if (.not. allocated(error)) call h5%write_summary_string('program', 'feps ' // feps_release, error)
    if (.not. allocated(error)) call h5%write_summary_string('input_file', model%deck_file, error)
    if (.not. allocated(error)) call h5%close(error)
    if (allocated(error)) call h5%discard()
  end subroutine write_mesh_only

  !> The mesh of `model` into an open results file: coordinates and every group (with the
  !! element catalog's attributes and integration points).
  subroutine write_mesh(h5, model, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    integer :: g
    call h5%write_mesh(model%coords, error)
    if (allocated(error)) return
    do g = 1, size(model%groups)
      if (allocated(model%groups(g)%element_ids)) then
        call h5%write_group(model%groups(g)%name, model%groups(g)%element_type, model%groups(g)%connectivity, error, &
                            material=model%groups(g)%material_name, coordinates=model%coords, &
                            element_ids=model%groups(g)%element_ids)
      else
        call h5%write_group(model%groups(g)%name, model%groups(g)%element_type, model%groups(g)%connectivity, error, &
                            material=model%groups(g)%material_name, coordinates=model%coords)
      end if
      if (allocated(error)) return
    end do
  end subroutine write_mesh

end module feps_mesh_only
