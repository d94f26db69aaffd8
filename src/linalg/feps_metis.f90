!> METIS's mesh partition (feps_metis_shim.c): the elements of a mesh into parts of nearly
!! equal weight, each part a compact region of neighbouring elements (METIS_PartMeshDual).
module feps_metis
  use, intrinsic :: iso_c_binding, only: c_int, c_int32_t, c_int64_t
  use feps_kinds, only: i8
  implicit none
  private

  public :: partition_mesh

  interface
    integer(c_int) function feps_metis_part_mesh_dual(elements, nodes, element_ptr, element_nodes, weights, &
                                                      common, parts, part) bind(C, name='feps_metis_part_mesh_dual')
      import :: c_int, c_int32_t, c_int64_t
      integer(c_int32_t), value :: elements, nodes, common, parts
      integer(c_int64_t), intent(in) :: element_ptr(*)
      integer(c_int32_t), intent(in) :: element_nodes(*), weights(*)
      integer(c_int32_t), intent(out) :: part(*)
    end function feps_metis_part_mesh_dual
  end interface

contains

  !> part(e) in 0 .. parts - 1 for each of the elements, whose nodes (1-based, numbered up to
  !! `nodes`) are element_nodes(element_ptr(e) : element_ptr(e + 1) - 1) (element_ptr 1-based),
  !! weighted by `weights`; elements that share `common` nodes are neighbours. ok is false when
  !! METIS fails.
  subroutine partition_mesh(nodes, element_ptr, element_nodes, weights, common, parts, part, ok)
    integer, intent(in) :: nodes
    integer(i8), intent(in) :: element_ptr(:)
    integer, intent(in) :: element_nodes(:), weights(:)
    integer, intent(in) :: common, parts
    integer, intent(out) :: part(:)
    logical, intent(out) :: ok
    ok = feps_metis_part_mesh_dual(int(size(weights), c_int32_t), int(nodes, c_int32_t), &
                                   int(element_ptr - 1, c_int64_t), int(element_nodes - 1, c_int32_t), &
                                   int(weights, c_int32_t), int(common, c_int32_t), int(parts, c_int32_t), &
                                   part) == 0
  end subroutine partition_mesh

end module feps_metis
