!> Orderings that reduce the bandwidth and profile (skyline) of a symmetric sparse matrix.
!!
!! Conventions: `perm(new) = old`, `iperm(old) = new`, both 1-based. The pattern is read from a
!! `csr_matrix_t` (lower triangle); the full symmetric adjacency is built internally.
!! The profile of an ordering counts, for each column j of the upper triangle in the new
!! numbering, the entries from the first structurally nonzero row down to the diagonal.
module feps_ordering
  use feps_kinds, only: i8
  use feps_sparse_matrix, only: csr_matrix_t
  implicit none
  private

  public :: reverse_cuthill_mckee, profile_size, skyline_first_rows

  !> Neighbour lists at most this long are sorted by insertion, longer ones by heapsort.
  integer, parameter :: insertion_sort_limit = 24

contains

  !> Reverse Cuthill-McKee ordering of the symmetric pattern of `a`.
  !!
  !! Each connected component starts from a pseudo-peripheral node (George-Liu search on
  !! rooted level structures); neighbours are numbered in increasing degree (ties by index).
  !! Disconnected components and isolated equations are handled. Returns
  !! `perm(new) = old` and `iperm(old) = new`.
  pure subroutine reverse_cuthill_mckee(a, perm, iperm)
    type(csr_matrix_t), intent(in) :: a
    integer, allocatable, intent(out) :: perm(:)
    integer, allocatable, intent(out) :: iperm(:)
    integer(i8), allocatable :: adj_ptr(:)
    integer, allocatable :: adj(:), degree(:), stamp(:), order(:)
    integer :: n, seed, root, numbered, current_stamp, k

    n = a%n
    allocate (perm(n), iperm(n))
    if (n == 0) return

    call build_adjacency(a, adj_ptr, adj, degree)
    call sort_neighbours_by_degree(adj_ptr, adj, degree)

    allocate (stamp(n), source=0)
    allocate (order(n))
    iperm = 0
    numbered = 0
    current_stamp = 0
    ! Each unnumbered seed belongs to a component not yet visited.
    do seed = 1, n
      if (iperm(seed) /= 0) cycle
      call pseudo_peripheral_node(seed, adj_ptr, adj, degree, stamp, current_stamp, order, root)
      call cuthill_mckee_component(root, adj_ptr, adj, perm, iperm, numbered)
    end do

    ! Reversal keeps the bandwidth and never increases the profile (George 1971).
    perm = perm(n:1:-1)
    do k = 1, n
      iperm(perm(k)) = k
    end do
  end subroutine reverse_cuthill_mckee

  !> First (smallest) row of each column of the upper-triangle skyline of `a` renumbered by
  !! `iperm(old) = new`; column j (new numbering) spans rows first(j) .. j.
  pure function skyline_first_rows(a, iperm) result(first)
    type(csr_matrix_t), intent(in) :: a
    integer, intent(in) :: iperm(:)
    integer :: first(a%n)
    integer :: i, j, new_i, new_j
    integer(i8) :: k

    do j = 1, a%n
      first(j) = j
    end do
    do i = 1, a%n
      new_i = iperm(i)
      do k = a%row_ptr(i), a%row_ptr(i + 1) - 1
        new_j = iperm(a%col(k))
        ! The entry lands in column max(new_i, new_j) at row min(new_i, new_j).
        j = max(new_i, new_j)
        first(j) = min(first(j), new_i, new_j)
      end do
    end do
  end function skyline_first_rows

  !> Number of entries (diagonal included) in the skyline of `a` renumbered by
  !! `iperm(old) = new`.
  pure function profile_size(a, iperm) result(entries)
    type(csr_matrix_t), intent(in) :: a
    integer, intent(in) :: iperm(:)
    integer(i8) :: entries
    integer, allocatable :: first(:)
    integer :: j

    allocate (first(a%n))
    first = skyline_first_rows(a, iperm)
    entries = 0
    do j = 1, a%n
      entries = entries + int(j - first(j) + 1, i8)
    end do
  end function profile_size

  !> Full symmetric adjacency (no self loops) from the lower-triangle pattern.
  pure subroutine build_adjacency(a, adj_ptr, adj, degree)
    type(csr_matrix_t), intent(in) :: a
    integer(i8), allocatable, intent(out) :: adj_ptr(:)
    integer, allocatable, intent(out) :: adj(:)
    integer, allocatable, intent(out) :: degree(:)
    integer(i8), allocatable :: fill(:)
    integer(i8) :: k
    integer :: i, j, n

    n = a%n
    allocate (degree(n), source=0)
    do i = 1, n
      do k = a%row_ptr(i), a%row_ptr(i + 1) - 1
        j = a%col(k)
        if (j == i) cycle
        degree(i) = degree(i) + 1
        degree(j) = degree(j) + 1
      end do
    end do

    allocate (adj_ptr(n + 1))
    adj_ptr(1) = 1
    do i = 1, n
      adj_ptr(i + 1) = adj_ptr(i) + degree(i)
    end do
    allocate (adj(adj_ptr(n + 1) - 1))
    allocate (fill, source=adj_ptr(1:n))
    do i = 1, n
      do k = a%row_ptr(i), a%row_ptr(i + 1) - 1
        j = a%col(k)
        if (j == i) cycle
        adj(fill(i)) = j
        fill(i) = fill(i) + 1
        adj(fill(j)) = i
        fill(j) = fill(j) + 1
      end do
    end do
  end subroutine build_adjacency

  !> Sort every neighbour list by (degree, index) once, so the Cuthill-McKee sweep can take
  !! neighbours in list order.
  pure subroutine sort_neighbours_by_degree(adj_ptr, adj, degree)
    integer(i8), intent(in) :: adj_ptr(:)
    integer, intent(inout) :: adj(:)
    integer, intent(in) :: degree(:)
    integer :: v
    integer(i8) :: lo, hi

    do v = 1, size(degree)
      lo = adj_ptr(v)
      hi = adj_ptr(v + 1) - 1
      if (hi - lo + 1 <= insertion_sort_limit) then
        call insertion_sort(adj(lo:hi), degree)
      else
        call heap_sort(adj(lo:hi), degree)
      end if
    end do
  end subroutine sort_neighbours_by_degree

  !> Node u goes before node w: smaller degree first, then smaller index.
  pure logical function precedes(u, w, degree)
    integer, intent(in) :: u, w
    integer, intent(in) :: degree(:)
    precedes = degree(u) < degree(w) .or. (degree(u) == degree(w) .and. u < w)
  end function precedes

  pure subroutine insertion_sort(nodes, degree)
    integer, intent(inout) :: nodes(:)
    integer, intent(in) :: degree(:)
    integer :: i, j, node

    do i = 2, size(nodes)
      node = nodes(i)
      j = i - 1
      do while (j >= 1)
        if (.not. precedes(node, nodes(j), degree)) exit
        nodes(j + 1) = nodes(j)
        j = j - 1
      end do
      nodes(j + 1) = node
    end do
  end subroutine insertion_sort

  !> Heapsort for long neighbour lists (a node tied to many others must not cost O(d^2)).
  pure subroutine heap_sort(nodes, degree)
    integer, intent(inout) :: nodes(:)
    integer, intent(in) :: degree(:)
    integer :: last, start, node

    last = size(nodes)
    do start = last / 2, 1, -1
      call sift_down(nodes, start, last, degree)
    end do
    do while (last > 1)
      node = nodes(1)
      nodes(1) = nodes(last)
      nodes(last) = node
      last = last - 1
      call sift_down(nodes, 1, last, degree)
    end do
  end subroutine heap_sort

  !> Restore the max-heap property below `root` within nodes(1:last).
  pure subroutine sift_down(nodes, root, last, degree)
    integer, intent(inout) :: nodes(:)
    integer, intent(in) :: root, last
    integer, intent(in) :: degree(:)
    integer :: parent, child, node

    parent = root
    node = nodes(parent)
    do
      child = 2 * parent
      if (child > last) exit
      if (child < last) then
        if (precedes(nodes(child), nodes(child + 1), degree)) child = child + 1
      end if
      if (.not. precedes(node, nodes(child), degree)) exit
      nodes(parent) = nodes(child)
      parent = child
    end do
    nodes(parent) = node
  end subroutine sift_down

  !> Breadth-first level structure rooted at `root`. The component's nodes are written to
  !! order(1:count) level by level; the last level is order(last_level_start:count).
  !! Nodes are marked with a fresh stamp, so `stamp` never needs clearing.
  pure subroutine rooted_level_structure(root, adj_ptr, adj, stamp, current_stamp, order, &
                                         levels, last_level_start, count)
    integer, intent(in) :: root
    integer(i8), intent(in) :: adj_ptr(:)
    integer, intent(in) :: adj(:)
    integer, intent(inout) :: stamp(:)
    integer, intent(inout) :: current_stamp
    integer, intent(inout) :: order(:)
    integer, intent(out) :: levels, last_level_start, count
    integer :: level_start, level_end, q, v, w
    integer(i8) :: k

    current_stamp = current_stamp + 1
    stamp(root) = current_stamp
    order(1) = root
    count = 1
    levels = 0
    level_start = 1
    last_level_start = 1
    do while (level_start <= count)
      level_end = count
      levels = levels + 1
      last_level_start = level_start
      do q = level_start, level_end
        v = order(q)
        do k = adj_ptr(v), adj_ptr(v + 1) - 1
          w = adj(k)
          if (stamp(w) /= current_stamp) then
            stamp(w) = current_stamp
            count = count + 1
            order(count) = w
          end if
        end do
      end do
      level_start = level_end + 1
    end do
  end subroutine rooted_level_structure

  !> George-Liu pseudo-peripheral node of the component of `seed`: root a level structure,
  !! move to a minimum-degree node of its last level, and repeat while the number of levels
  !! (the eccentricity) grows.
  pure subroutine pseudo_peripheral_node(seed, adj_ptr, adj, degree, stamp, current_stamp, order, root)
    integer, intent(in) :: seed
    integer(i8), intent(in) :: adj_ptr(:)
    integer, intent(in) :: adj(:), degree(:)
    integer, intent(inout) :: stamp(:)
    integer, intent(inout) :: current_stamp
    integer, intent(inout) :: order(:)
    integer, intent(out) :: root
    integer :: levels, last_start, count, candidate, candidate_levels, q

    root = seed
    call rooted_level_structure(root, adj_ptr, adj, stamp, current_stamp, order, levels, last_start, count)
    ! A single node, or a path already rooted at an end: nothing to improve.
    do while (levels > 1 .and. levels < count)
      candidate = order(last_start)
      do q = last_start + 1, count
        if (precedes(order(q), candidate, degree)) candidate = order(q)
      end do
      call rooted_level_structure(candidate, adj_ptr, adj, stamp, current_stamp, order, &
                                  candidate_levels, last_start, count)
      root = candidate
      if (candidate_levels <= levels) exit
      levels = candidate_levels
    end do
  end subroutine pseudo_peripheral_node

  !> Cuthill-McKee numbering of the component of `root`, continuing from `numbered`;
  !! perm doubles as the breadth-first queue.
  pure subroutine cuthill_mckee_component(root, adj_ptr, adj, perm, iperm, numbered)
    integer, intent(in) :: root
    integer(i8), intent(in) :: adj_ptr(:)
    integer, intent(in) :: adj(:)
    integer, intent(inout) :: perm(:), iperm(:)
    integer, intent(inout) :: numbered
    integer :: head, v, w
    integer(i8) :: k

    numbered = numbered + 1
    perm(numbered) = root
    iperm(root) = numbered
    head = numbered
    do while (head <= numbered)
      v = perm(head)
      head = head + 1
      do k = adj_ptr(v), adj_ptr(v + 1) - 1
        w = adj(k)
        if (iperm(w) == 0) then
          numbered = numbered + 1
          perm(numbered) = w
          iperm(w) = numbered
        end if
      end do
    end do
  end subroutine cuthill_mckee_component

end module feps_ordering
