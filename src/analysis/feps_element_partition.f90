!> The elements each rank works on in an element-partitioned run (issue 29: `mpirun -np N feps
!! DECK --solver mumps`): each group's elements in N contiguous blocks of nearly equal size, rank
!! r the r-th. A rank updates its own elements' points and assembles its own element matrices;
!! MUMPS sums the ranks' matrices and the internal forces are summed over the ranks
!! (feps_parallel), after which every rank takes every other rank's block of point states, so
!! commit, restore, the step report and the results see the whole model on every rank.
!!
!! Contiguous blocks, not a METIS partition of the element graph: the internal forces are summed
!! as whole vectors and MUMPS orders and distributes the matrix itself, so a block's shape saves
!! no messages here, and a block's points are one contiguous slice of the point-state arrays, sent
!! as it is. The meshes feps makes number their elements in sweeps, so the blocks are slabs.
module feps_element_partition
  use feps_kinds, only: i8
  use feps_parallel, only: gather_blocks, gather_int_blocks
  use feps_point_state_store, only: point_state_store_t
  implicit none
  private

  public :: partition_elements

  type, public :: element_partition_t
    logical :: distributed = .false.     !! more than one rank, each on its own elements
    integer :: rank = 0
    integer :: ranks = 1
    !> Rank r's elements of group g are first(r, g) .. first(r + 1, g) - 1 (r = 0 .. ranks - 1).
    integer, allocatable :: first(:, :)
  contains
    procedure :: lo => partition_lo
    procedure :: hi => partition_hi
    procedure :: share_trial => partition_share_trial
  end type element_partition_t

contains

  !> The blocks of `elements(g)` elements of each group g over `ranks` ranks, for rank `rank`;
  !! one rank (or not `distributed`): every element is this rank's.
  pure function partition_elements(elements, rank, ranks, distributed) result(part)
    integer, intent(in) :: elements(:)
    integer, intent(in) :: rank, ranks
    logical, intent(in) :: distributed
    type(element_partition_t) :: part
    integer :: g, r
    part%distributed = distributed .and. ranks > 1
    part%rank = merge(rank, 0, part%distributed)
    part%ranks = merge(ranks, 1, part%distributed)
    allocate (part%first(0:part%ranks, size(elements)))
    do g = 1, size(elements)
      do r = 0, part%ranks
        part%first(r, g) = 1 + int(int(r, i8) * elements(g) / part%ranks)
      end do
    end do
  end function partition_elements

  !> This rank's first element of group g.
  pure integer function partition_lo(self, g) result(e)
    class(element_partition_t), intent(in) :: self
    integer, intent(in) :: g
    e = self%first(self%rank, g)
  end function partition_lo

  !> This rank's last element of group g (lo - 1 when it has none).
  pure integer function partition_hi(self, g) result(e)
    class(element_partition_t), intent(in) :: self
    integer, intent(in) :: g
    e = self%first(self%rank + 1, g) - 1
  end function partition_hi

  !> Every rank takes every other rank's block of group g's trial point states (`npoints` per
  !! element): stress, strain, flag, internal variables and tangent, copied as they are.
  subroutine partition_share_trial(self, g, npoints, store)
    class(element_partition_t), intent(in) :: self
    integer, intent(in) :: g, npoints
    class(point_state_store_t), intent(inout) :: store
    if (.not. self%distributed .or. .not. allocated(store%sig_t)) return
    call gather_blocks(store%sig_t, counts(size(store%sig_t, 1)), displs(size(store%sig_t, 1)))
    call gather_blocks(store%eps_t, counts(size(store%eps_t, 1)), displs(size(store%eps_t, 1)))
    call gather_int_blocks(store%state_t, counts(1), displs(1))
    if (size(store%vars_t, 1) > 0) &
      call gather_blocks(store%vars_t, counts(size(store%vars_t, 1)), displs(size(store%vars_t, 1)))
    call gather_blocks(store%dtan_t, counts(size(store%dtan_t, 1) * size(store%dtan_t, 2)), &
                       displs(size(store%dtan_t, 1) * size(store%dtan_t, 2)))
  contains
    !> Each rank's number of values, `per_point` a point.
    pure function counts(per_point) result(c)
      integer, intent(in) :: per_point
      integer(i8) :: c(self%ranks)
      integer :: r
      do r = 0, self%ranks - 1
        c(r + 1) = int(self%first(r + 1, g) - self%first(r, g), i8) * npoints * per_point
      end do
    end function counts
    !> Where each rank's values start (0-based).
    pure function displs(per_point) result(d)
      integer, intent(in) :: per_point
      integer(i8) :: d(self%ranks)
      integer :: r
      do r = 0, self%ranks - 1
        d(r + 1) = int(self%first(r, g) - 1, i8) * npoints * per_point
      end do
    end function displs
  end subroutine partition_share_trial

end module feps_element_partition
