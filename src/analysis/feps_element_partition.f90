!> The elements each rank works on in an element-partitioned run (issue 29: `mpirun -np N feps
!! DECK --solver mumps`): METIS's partition of the mesh's dual graph (all groups together, each
!! element weighted by its number of points, neighbours sharing a node), so each rank's elements
!! form compact regions of nearly equal work. A rank updates its own elements' points and
!! assembles its own element matrices; MUMPS sums the ranks' matrices and the internal forces are
!! summed over the ranks (feps_parallel), after which every rank takes every other rank's points
!! (`share_trial`), so commit, restore, the step report and the results see the whole model on
!! every rank. On one rank every element is its own, in mesh order.
module feps_element_partition
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_internal, str
  use feps_model, only: model_t
  use feps_metis, only: partition_mesh
  use feps_parallel, only: gather_blocks, broadcast_from_root
  use feps_point_state_store, only: point_state_store_t
  implicit none
  private

  public :: partition_elements

  !> Elements of one group: this rank's (ascending), and all of them ordered rank by rank.
  type :: group_share_t
    integer, allocatable :: own(:)        !! this rank's elements, ascending
    integer, allocatable :: by_rank(:)    !! every element: rank 0's ascending, then rank 1's, ...
    integer, allocatable :: count(:)      !! (0:ranks-1) each rank's number of elements
  end type group_share_t

  type, public :: element_partition_t
    logical :: distributed = .false.     !! more than one rank, each on its own elements
    integer :: rank = 0
    integer :: ranks = 1
    type(group_share_t), allocatable :: groups(:)
  contains
    procedure :: own => partition_own
    procedure :: elements_of_rank => partition_elements_of_rank
    procedure :: share_trial => partition_share_trial
  end type element_partition_t

contains

  !> The elements of `model` over `ranks` ranks (METIS, computed on rank 0 and sent to the
  !! others), for rank `rank`; one rank (or not `distributed`): every element is this rank's.
  !! npoints(g): the points of an element of group g, its weight.
  subroutine partition_elements(model, npoints, rank, ranks, distributed, part, error)
    type(model_t), intent(in) :: model
    integer, intent(in) :: npoints(:)
    integer, intent(in) :: rank, ranks
    logical, intent(in) :: distributed
    type(element_partition_t), intent(out) :: part
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: owner(:), element_nodes(:), weights(:), status(:)
    integer(i8), allocatable :: element_ptr(:)
    integer :: g, e, id, nelem, r, k
    logical :: ok
    part%distributed = distributed .and. ranks > 1
    part%rank = merge(rank, 0, part%distributed)
    part%ranks = merge(ranks, 1, part%distributed)
    nelem = model%nelem()
    allocate (owner(nelem), part%groups(size(model%groups)))
    owner = 0
    if (part%distributed) then
      status = [1]
      if (part%rank == 0) then
        allocate (element_ptr(nelem + 1), weights(nelem))
        element_ptr(1) = 1
        id = 0
        do g = 1, size(model%groups)
          do e = 1, size(model%groups(g)%connectivity, 2)
            id = id + 1
            element_ptr(id + 1) = element_ptr(id) + size(model%groups(g)%connectivity, 1)
            weights(id) = npoints(g)
          end do
        end do
        allocate (element_nodes(element_ptr(nelem + 1) - 1))
        id = 0
        do g = 1, size(model%groups)
          do e = 1, size(model%groups(g)%connectivity, 2)
            id = id + 1
            element_nodes(element_ptr(id):element_ptr(id + 1) - 1) = model%groups(g)%connectivity(:, e)
          end do
        end do
        call partition_mesh(model%nnode, element_ptr, element_nodes, weights, 1, part%ranks, owner, ok)
        status = merge([0], [1], ok)
      end if
      call broadcast_from_root(status)
      if (status(1) /= 0) then
        call fatal_error(error, err_internal, 'METIS could not partition the ' // str(nelem) // &
                         ' elements over ' // str(part%ranks) // ' ranks')
        return
      end if
      call broadcast_from_root(owner)
    end if
    id = 0
    do g = 1, size(model%groups)
      associate (share => part%groups(g), n => size(model%groups(g)%connectivity, 2))
        allocate (share%count(0:part%ranks - 1), share%by_rank(n))
        share%count = 0
        do e = 1, n
          share%count(owner(id + e)) = share%count(owner(id + e)) + 1
        end do
        share%own = pack([(e, e = 1, n)], owner(id + 1:id + n) == part%rank)
        k = 0
        do r = 0, part%ranks - 1
          do e = 1, n
            if (owner(id + e) /= r) cycle
            k = k + 1
            share%by_rank(k) = e
          end do
        end do
        id = id + n
      end associate
    end do
  end subroutine partition_elements

  !> This rank's elements of group g, ascending.
  pure function partition_own(self, g) result(own)
    class(element_partition_t), intent(in) :: self
    integer, intent(in) :: g
    integer, allocatable :: own(:)
    own = self%groups(g)%own
  end function partition_own

  !> The number of elements of rank r (0-based), over every group.
  pure integer function partition_elements_of_rank(self, r) result(n)
    class(element_partition_t), intent(in) :: self
    integer, intent(in) :: r
    integer :: g
    n = 0
    do g = 1, size(self%groups)
      n = n + self%groups(g)%count(r)
    end do
  end function partition_elements_of_rank

  !> Every rank takes every other rank's trial point states of group g (`npoints` per
  !! element): stress, strain, flag, internal variables and tangent, copied as they are. Each
  !! rank's points go as one block (its elements ascending), placed back element by element.
  subroutine partition_share_trial(self, g, npoints, store)
    class(element_partition_t), intent(in) :: self
    integer, intent(in) :: g, npoints
    class(point_state_store_t), intent(inout) :: store
    real(dp), allocatable :: flags(:)
    integer :: points
    if (.not. self%distributed .or. .not. allocated(store%sig_t)) return
    points = size(store%state_t)
    call share_real(store%sig_t, size(store%sig_t, 1))
    call share_real(store%eps_t, size(store%eps_t, 1))
    flags = real(store%state_t, dp)   ! small integers: exact
    call share_real(flags, 1)
    store%state_t = nint(flags)
    if (size(store%vars_t, 1) > 0) call share_real(store%vars_t, size(store%vars_t, 1))
    call share_real(store%dtan_t, size(store%dtan_t, 1) * size(store%dtan_t, 2))
  contains
    !> x(rows, points) (any contiguous array of `rows` values a point, a tangent's too): this
    !! rank's points into a buffer ordered rank by rank, gathered, and every point put back.
    subroutine share_real(x, rows)
      integer, intent(in) :: rows
      real(dp), intent(inout) :: x(rows, points)
      real(dp), allocatable :: buffer(:, :)
      integer :: k, e, first
      allocate (buffer(rows, points))
      first = sum(self%groups(g)%count(:self%rank - 1)) * npoints
      do k = 1, size(self%groups(g)%own)
        e = self%groups(g)%own(k)
        buffer(:, first + (k - 1) * npoints + 1:first + k * npoints) = x(:, (e - 1) * npoints + 1:e * npoints)
      end do
      call gather_blocks(buffer, counts(rows), displs(rows))
      do k = 1, size(self%groups(g)%by_rank)
        e = self%groups(g)%by_rank(k)
        x(:, (e - 1) * npoints + 1:e * npoints) = buffer(:, (k - 1) * npoints + 1:k * npoints)
      end do
    end subroutine share_real
    !> Each rank's number of values, `per_point` a point.
    pure function counts(per_point) result(c)
      integer, intent(in) :: per_point
      integer(i8) :: c(self%ranks)
      c = int(self%groups(g)%count, i8) * npoints * per_point
    end function counts
    !> Where each rank's values start (0-based): the ranks' blocks one after another.
    pure function displs(per_point) result(d)
      integer, intent(in) :: per_point
      integer(i8) :: d(self%ranks)
      integer :: r
      d(1) = 0
      do r = 2, self%ranks
        d(r) = d(r - 1) + int(self%groups(g)%count(r - 2), i8) * npoints * per_point
      end do
    end function displs
  end subroutine partition_share_trial

end module feps_element_partition
