!> Forward and back substitution with a supernodal Cholesky factor in CHOLMOD's layout
!! (L L' = P A P'), done by feps rather than by `cholmod_l_solve`, for two reasons:
!!
!! - Threads. A solve with one right-hand side streams the whole factor twice and does little
!!   arithmetic on it, so its speed is the memory bandwidth one core draws (issue 28: FE1's 1 316
!!   solves were 70% of its time). Independent subtrees of the supernodal elimination tree are
!!   solved on different threads, which draws the bandwidth of several cores; the supernodes
!!   above them (the top separators) follow on one thread.
!! - The same bits for any thread count. Every sum has one fixed order: in the forward pass a
!!   supernode keeps its contributions to the rows below it in a buffer (`buf`, one entry per
!!   stored row index), and each supernode gathers those addressed to it in ascending order of
!!   the supernode that made them, which is the order of a serial pass; the back pass only reads
!!   the solution of ancestors. The BLAS runs on one thread meanwhile, so each call's sums
!!   have one order too.
!!
!! Each supernode makes CHOLMOD's own BLAS calls (dtrsv, dgemv), so the back pass is CHOLMOD's
!! arithmetic; in the forward pass CHOLMOD adds each supernode's contributions into the rows
!! below in place (x - L21 x1 in one dgemv), feps adds the finished -L21 x1 afterwards, so
!! results agree with `cholmod_l_solve` to round-off, not bit for bit (docs/verification.md).
!!
!! Layout (CHOLMOD's `cholmod_factor`, 0-based values, here read through 1-based arrays):
!! supernode k holds columns super(k)+1 .. super(k+1); its row indices are rows(pi(k)+1 ..
!! pi(k+1)) (0-based rows of P A P', the first ncol of them its own columns), and its values
!! the nrow x ncol column-major block at lx(px(k)+1 ..). perm(i)+1 is the equation of row i.
module feps_supernodal_solve
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int64_t, c_double, c_f_pointer
  use feps_kinds, only: dp, sp, i8
  use feps_lapack, only: dgemv, dtrsv, sgemv, strsv
  use feps_blas, only: blas_threads, set_blas_threads
  !$ use omp_lib, only: omp_get_max_threads, omp_get_thread_num, omp_get_num_threads
  implicit none
  private

  !> A plan for solving with one numeric supernodal factor: its arrays (CHOLMOD's, not copied),
  !! the gather lists of the forward pass and the threads' shares of the elimination tree.
  type, public :: supernodal_solve_t
    private
    integer :: n = 0                     !! equations
    integer :: nsuper = 0                !! supernodes; 0 when there is no plan
    integer :: threads = 1               !! threads of a solve
    integer(c_int64_t), pointer, contiguous :: super(:) => null(), pi(:) => null(), px(:) => null(), &
                                               rows(:) => null(), perm(:) => null()
    real(c_double), pointer, contiguous :: lx(:) => null()
    !> Supernode k gathers the ranges gather_range(:, gather_ptr(k) : gather_ptr(k+1)-1) of buf
    !! (first and last position), in ascending order of the supernode that filled them.
    integer, allocatable :: gather_ptr(:)
    integer(i8), allocatable :: gather_range(:, :)
    !> Thread t solves part_nodes(part_ptr(t) : part_ptr(t+1)-1) (whole subtrees, ascending);
    !! top_nodes (ascending) are the supernodes above them, solved on one thread.
    integer, allocatable :: part_ptr(:), part_nodes(:), top_nodes(:)
    integer :: max_rows = 0              !! the most rows of a supernode
    real(dp), allocatable :: buf(:)      !! a supernode's contributions to the rows below it
    real(dp), allocatable :: y(:)        !! the permuted right-hand side, then the solution
    real(dp), allocatable :: w(:, :)     !! each thread's supernode workspace
    !> Mixed precision: the solves may read a single-precision copy of the factor (half the
    !! bytes that a solve streams), with buf and w in single precision too; y stays double
    logical :: single = .false.
    logical :: in_single = .false.       !! the solve under way reads the copy
    real(sp), allocatable :: lx4(:), buf4(:), w4(:, :)
  contains
    procedure :: setup => plan_setup
    procedure :: ready => plan_ready
    procedure :: thread_count => plan_threads
    procedure :: single_precision => plan_single
    procedure :: add_single_copy => plan_add_single_copy
    procedure :: drop_single_copy => plan_drop_single_copy
    procedure :: solve => plan_solve
    procedure :: clear => plan_clear
  end type supernodal_solve_t

  !> A subtree is split further while the threads' shares differ by more than this factor,
  !! at most max_splits times per thread (each split moves a supernode to the serial top).
  real(dp), parameter :: balance = 1.05_dp
  integer, parameter :: max_splits = 64
  !> Single precision: diagonal blocks of at most this many columns are solved by feps's own
  !! loops (lower_solve), larger ones by strsv (OpenBLAS's blocked kernels; 64 is the block
  !! size below which strsv does no more than these loops, plus its buffer's lock).
  integer, parameter :: small_triangle = 64

contains

  !> Plan solves with the factor whose CHOLMOD arrays are given (see the module's layout); the
  !! arrays must stay allocated and unchanged while the plan is used. Threads: OpenMP's
  !! current maximum.
  subroutine plan_setup(self, n, nsuper, super, pi, px, rows, x, perm)
    class(supernodal_solve_t), intent(inout) :: self
    integer, intent(in) :: n
    integer(c_int64_t), intent(in) :: nsuper
    type(c_ptr), intent(in) :: super, pi, px, rows, x, perm
    integer, allocatable :: col_super(:), parent(:)
    integer :: k, k1, nscol, nsrow
    integer(i8) :: p0
    call self%clear()
    if (nsuper < 1 .or. n < 1) return
    self%n = n
    self%nsuper = int(nsuper)
    call c_f_pointer(super, self%super, [nsuper + 1])
    call c_f_pointer(pi, self%pi, [nsuper + 1])
    call c_f_pointer(px, self%px, [nsuper + 1])
    call c_f_pointer(rows, self%rows, [self%pi(nsuper + 1)])
    call c_f_pointer(x, self%lx, [self%px(nsuper + 1)])
    call c_f_pointer(perm, self%perm, [n])
    allocate (col_super(n), parent(self%nsuper))
    self%max_rows = 0
    do k = 1, self%nsuper
      col_super(self%super(k) + 1:self%super(k + 1)) = k
      self%max_rows = max(self%max_rows, int(self%pi(k + 1) - self%pi(k)))
    end do
    do k = 1, self%nsuper   ! the parent: the supernode of the first row below the diagonal block
      call extent(k, self%super, self%pi, k1, nscol, nsrow, p0)
      parent(k) = 0
      if (nsrow > nscol) parent(k) = col_super(self%rows(p0 + nscol + 1) + 1)
    end do
    call build_gather_lists(self, col_super)
    self%threads = 1
    !$ self%threads = max(1, omp_get_max_threads())
    call share_tree(self, parent)
    allocate (self%buf(size(self%rows)), self%y(n), self%w(self%max_rows, self%threads))
    self%buf = 0.0_dp
  end subroutine plan_setup

  !> Mixed precision: from now on the solves read a single-precision copy of the factor (half
  !! the bytes a solve streams; about kappa(A) 6e-8 relative error), unless one asks for an
  !! exact solve. Where the copy does not fit in memory the solves stay with the factor.
  subroutine plan_add_single_copy(self)
    class(supernodal_solve_t), intent(inout) :: self
    integer :: stat
    if (self%nsuper < 1 .or. self%single) return
    allocate (self%lx4(size(self%lx, kind=i8)), self%buf4(size(self%rows)), self%w4(self%max_rows, self%threads), &
              stat=stat)
    if (stat /= 0) then
      call self%drop_single_copy()
      return
    end if
    self%lx4 = real(self%lx, sp)
    self%buf4 = 0.0_sp
    self%single = .true.
  end subroutine plan_add_single_copy

  !> Back to solves with the factor itself.
  subroutine plan_drop_single_copy(self)
    class(supernodal_solve_t), intent(inout) :: self
    if (allocated(self%lx4)) deallocate (self%lx4)
    if (allocated(self%buf4)) deallocate (self%buf4)
    if (allocated(self%w4)) deallocate (self%w4)
    self%single = .false.
  end subroutine plan_drop_single_copy

  !> Whether a plan is set up.
  pure logical function plan_ready(self)
    class(supernodal_solve_t), intent(in) :: self
    plan_ready = self%nsuper > 0
  end function plan_ready

  !> Threads a solve runs on.
  pure integer function plan_threads(self)
    class(supernodal_solve_t), intent(in) :: self
    plan_threads = self%threads
  end function plan_threads

  !> Whether the plan holds a single-precision copy of the factor for its solves.
  pure logical function plan_single(self)
    class(supernodal_solve_t), intent(in) :: self
    plan_single = self%single
  end function plan_single

  !> Forget the plan (the factor's arrays are CHOLMOD's and are not freed here).
  subroutine plan_clear(self)
    class(supernodal_solve_t), intent(inout) :: self
    self%n = 0
    self%nsuper = 0
    self%threads = 1
    nullify (self%super, self%pi, self%px, self%rows, self%perm, self%lx)
    if (allocated(self%gather_ptr)) deallocate (self%gather_ptr)
    if (allocated(self%gather_range)) deallocate (self%gather_range)
    if (allocated(self%part_ptr)) deallocate (self%part_ptr)
    if (allocated(self%part_nodes)) deallocate (self%part_nodes)
    if (allocated(self%top_nodes)) deallocate (self%top_nodes)
    if (allocated(self%buf)) deallocate (self%buf)
    if (allocated(self%y)) deallocate (self%y)
    if (allocated(self%w)) deallocate (self%w)
    call self%drop_single_copy()
    self%in_single = .false.
  end subroutine plan_clear

  !> Solve A x = b in place for the columns of b (n x nrhs, stored one after another); with the
  !! factor's single-precision copy where the plan holds one, unless `exact` (then the factor).
  subroutine plan_solve(self, b, exact)
    class(supernodal_solve_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    logical, intent(in), optional :: exact
    integer :: i, k, blas
    integer(i8) :: off
    self%in_single = self%single
    if (present(exact)) self%in_single = self%single .and. .not. exact
    blas = blas_threads()
    if (blas > 1) call set_blas_threads(1)
    do off = 0, size(b, kind=i8) - self%n, self%n
      do k = 1, self%n
        self%y(k) = b(off + self%perm(k) + 1)
      end do
      if (self%threads > 1) call solve_shares(self, forward_pass=.true.)
      do i = 1, size(self%top_nodes)
        call forward_node(self, self%top_nodes(i), 1)
      end do
      do i = size(self%top_nodes), 1, -1
        call backward_node(self, self%top_nodes(i), 1)
      end do
      if (self%threads > 1) call solve_shares(self, forward_pass=.false.)
      do k = 1, self%n
        b(off + self%perm(k) + 1) = self%y(k)
      end do
    end do
    if (blas > 1) call set_blas_threads(blas)
  end subroutine plan_solve

  !> The threads' shares of the tree, each on its thread: the forward pass (ascending) or the
  !! back pass (descending).
  subroutine solve_shares(self, forward_pass)
    type(supernodal_solve_t), intent(inout) :: self
    logical, intent(in) :: forward_pass
    integer :: i, t, part, team
    !$omp parallel num_threads(self%threads) private(t, i, part, team)
    t = 1
    team = 1
    !$ t = omp_get_thread_num() + 1
    !$ team = omp_get_num_threads()
    do part = t, self%threads, team   ! every share, should OpenMP give fewer threads
      if (forward_pass) then
        do i = self%part_ptr(part), self%part_ptr(part + 1) - 1
          call forward_node(self, self%part_nodes(i), t)
        end do
      else
        do i = self%part_ptr(part + 1) - 1, self%part_ptr(part), -1
          call backward_node(self, self%part_nodes(i), t)
        end do
      end if
    end do
    !$omp end parallel
  end subroutine solve_shares

  !> Forward pass at supernode k with thread t's workspace, in the plan's precision.
  subroutine forward_node(self, k, t)
    type(supernodal_solve_t), intent(inout) :: self
    integer, intent(in) :: k, t
    if (self%in_single) then
      call forward_single(k, self%super, self%pi, self%px, self%rows, self%lx4, self%gather_ptr, &
                          self%gather_range, self%y, self%buf4, self%w4(:, t))
    else
      call forward(k, self%super, self%pi, self%px, self%rows, self%lx, self%gather_ptr, &
                   self%gather_range, self%y, self%buf, self%w(:, t))
    end if
  end subroutine forward_node

  !> Back pass at supernode k with thread t's workspace, in the plan's precision.
  subroutine backward_node(self, k, t)
    type(supernodal_solve_t), intent(inout) :: self
    integer, intent(in) :: k, t
    if (self%in_single) then
      call backward_single(k, self%super, self%pi, self%px, self%rows, self%lx4, self%y, self%w4(:, t))
    else
      call backward(k, self%super, self%pi, self%px, self%rows, self%lx, self%y, self%w(:, t))
    end if
  end subroutine backward_node

  !> Forward pass at supernode k: gather what the supernodes below sent to its rows, solve its
  !! diagonal block, and keep its contributions to the rows below (-L21 x1) in buf. The BLAS
  !! calls are CHOLMOD's own (t_cholmod_super_solve.c); only where the contributions are added
  !! differs.
  subroutine forward(k, super, pi, px, rows, lx, gather_ptr, gather_range, y, buf, w)
    integer, intent(in) :: k
    integer(c_int64_t), intent(in) :: super(:), pi(:), px(:), rows(:)
    real(dp), intent(in) :: lx(*)
    integer, intent(in) :: gather_ptr(:)
    integer(i8), intent(in) :: gather_range(:, :)
    real(dp), intent(inout) :: y(*), buf(*)
    real(dp), intent(inout) :: w(*)
    integer :: nscol, nsrow, k1, g, i
    integer(i8) :: p, p0
    call extent(k, super, pi, k1, nscol, nsrow, p0)
    w(1:nscol) = y(k1:k1 + nscol - 1)
    do g = gather_ptr(k), gather_ptr(k + 1) - 1
      do p = gather_range(1, g), gather_range(2, g)
        i = int(rows(p)) + 2 - k1
        w(i) = w(i) + buf(p)
      end do
    end do
    call dtrsv('L', 'N', 'N', nscol, lx(px(k) + 1), nsrow, w, 1)
    if (nsrow > nscol) call dgemv('N', nsrow - nscol, nscol, -1.0_dp, lx(px(k) + nscol + 1), nsrow, w, 1, &
                                  0.0_dp, buf(p0 + nscol + 1), 1)
    y(k1:k1 + nscol - 1) = w(1:nscol)
  end subroutine forward

  !> Back pass at supernode k: its columns of L' x = y, from the solution at the rows below
  !! (its ancestors', already final); CHOLMOD's arithmetic.
  subroutine backward(k, super, pi, px, rows, lx, y, w)
    integer, intent(in) :: k
    integer(c_int64_t), intent(in) :: super(:), pi(:), px(:), rows(:)
    real(dp), intent(in) :: lx(*)
    real(dp), intent(inout) :: y(*)
    real(dp), intent(inout) :: w(*)
    integer :: nscol, nsrow, k1
    integer(i8) :: p, p0
    call extent(k, super, pi, k1, nscol, nsrow, p0)
    w(1:nscol) = y(k1:k1 + nscol - 1)
    do p = p0 + nscol + 1, p0 + nsrow
      w(p - p0) = y(rows(p) + 1)
    end do
    if (nsrow > nscol) call dgemv('T', nsrow - nscol, nscol, -1.0_dp, lx(px(k) + nscol + 1), nsrow, &
                                  w(nscol + 1), 1, 1.0_dp, w, 1)
    call dtrsv('L', 'T', 'N', nscol, lx(px(k) + 1), nsrow, w, 1)
    y(k1:k1 + nscol - 1) = w(1:nscol)
  end subroutine backward

  !> `forward` with the factor, its workspace and its contributions in single precision (y, the
  !! right-hand side and solution, stays double). Fortran has no generics over kinds, hence
  !! the twin.
  subroutine forward_single(k, super, pi, px, rows, lx, gather_ptr, gather_range, y, buf, w)
    integer, intent(in) :: k
    integer(c_int64_t), intent(in) :: super(:), pi(:), px(:), rows(:)
    real(sp), intent(in) :: lx(*)
    integer, intent(in) :: gather_ptr(:)
    integer(i8), intent(in) :: gather_range(:, :)
    real(dp), intent(inout) :: y(*)
    real(sp), intent(inout) :: buf(*), w(*)
    integer :: nscol, nsrow, k1, g, i
    integer(i8) :: p, p0
    call extent(k, super, pi, k1, nscol, nsrow, p0)
    w(1:nscol) = real(y(k1:k1 + nscol - 1), sp)
    do g = gather_ptr(k), gather_ptr(k + 1) - 1
      do p = gather_range(1, g), gather_range(2, g)
        i = int(rows(p)) + 2 - k1
        w(i) = w(i) + buf(p)
      end do
    end do
    if (nscol <= small_triangle) then
      call lower_solve(nscol, lx(px(k) + 1), nsrow, w)
    else
      call strsv('L', 'N', 'N', nscol, lx(px(k) + 1), nsrow, w, 1)
    end if
    if (nsrow > nscol) call sgemv('N', nsrow - nscol, nscol, -1.0_sp, lx(px(k) + nscol + 1), nsrow, w, 1, &
                                  0.0_sp, buf(p0 + nscol + 1), 1)
    y(k1:k1 + nscol - 1) = real(w(1:nscol), dp)
  end subroutine forward_single

  !> `backward` in single precision (see forward_single).
  subroutine backward_single(k, super, pi, px, rows, lx, y, w)
    integer, intent(in) :: k
    integer(c_int64_t), intent(in) :: super(:), pi(:), px(:), rows(:)
    real(sp), intent(in) :: lx(*)
    real(dp), intent(inout) :: y(*)
    real(sp), intent(inout) :: w(*)
    integer :: nscol, nsrow, k1
    integer(i8) :: p, p0
    call extent(k, super, pi, k1, nscol, nsrow, p0)
    w(1:nscol) = real(y(k1:k1 + nscol - 1), sp)
    do p = p0 + nscol + 1, p0 + nsrow
      w(p - p0) = real(y(rows(p) + 1), sp)
    end do
    if (nsrow > nscol) call sgemv('T', nsrow - nscol, nscol, -1.0_sp, lx(px(k) + nscol + 1), nsrow, &
                                  w(nscol + 1), 1, 1.0_sp, w, 1)
    if (nscol <= small_triangle) then
      call lower_transpose_solve(nscol, lx(px(k) + 1), nsrow, w)
    else
      call strsv('L', 'T', 'N', nscol, lx(px(k) + 1), nsrow, w, 1)
    end if
    y(k1:k1 + nscol - 1) = real(w(1:nscol), dp)
  end subroutine backward_single

  !> w <- L^-1 w for the n x n lower triangle of the column-major block a (leading dimension
  !! lda), in single precision. strsv's arithmetic in a loop of feps's own: OpenBLAS's strsv
  !! takes and returns a work buffer under a lock on every call, which on FE1's small
  !! supernodes (414 of its 474 have at most 64 columns) cost about as much as their
  !! arithmetic (docs/performance.md, "FE1's serial work").
  pure subroutine lower_solve(n, a, lda, w)
    integer, intent(in) :: n, lda
    real(sp), intent(in) :: a(lda, n)
    real(sp), intent(inout) :: w(n)
    integer :: j, i
    real(sp) :: wj
    do j = 1, n
      wj = w(j) / a(j, j)
      w(j) = wj
      do i = j + 1, n
        w(i) = w(i) - wj * a(i, j)
      end do
    end do
  end subroutine lower_solve

  !> w <- L^-T w for the lower triangle of a, as lower_solve.
  pure subroutine lower_transpose_solve(n, a, lda, w)
    integer, intent(in) :: n, lda
    real(sp), intent(in) :: a(lda, n)
    real(sp), intent(inout) :: w(n)
    integer :: j, i
    real(sp) :: s
    do j = n, 1, -1
      s = w(j)
      do i = j + 1, n
        s = s - a(i, j) * w(i)
      end do
      w(j) = s / a(j, j)
    end do
  end subroutine lower_transpose_solve

  !> Supernode k's first column k1, its columns and rows, and p0, where its row indices start
  !! (0-based).
  pure subroutine extent(k, super, pi, k1, nscol, nsrow, p0)
    integer, intent(in) :: k
    integer(c_int64_t), intent(in) :: super(:), pi(:)
    integer, intent(out) :: k1, nscol, nsrow
    integer(i8), intent(out) :: p0
    k1 = int(super(k)) + 1
    nscol = int(super(k + 1) - super(k))
    p0 = pi(k)
    nsrow = int(pi(k + 1) - p0)
  end subroutine extent

  !> For each supernode, the ranges of buf it gathers: the runs of the rows below each
  !! supernode d that fall in its columns, in ascending d.
  subroutine build_gather_lists(self, col_super)
    type(supernodal_solve_t), intent(inout) :: self
    integer, intent(in) :: col_super(:)
    integer, allocatable :: fill(:)
    integer :: d, target, previous, nscol, pass, g
    integer(i8) :: p
    allocate (self%gather_ptr(self%nsuper + 1), fill(self%nsuper))
    fill = 0
    do pass = 1, 2
      do d = 1, self%nsuper
        nscol = int(self%super(d + 1) - self%super(d))
        previous = 0
        do p = self%pi(d) + nscol + 1, self%pi(d + 1)
          target = col_super(self%rows(p) + 1)
          if (target /= previous) then
            fill(target) = fill(target) + 1
            if (pass == 2) self%gather_range(1, self%gather_ptr(target) + fill(target) - 1) = p
            previous = target
          end if
          if (pass == 2) self%gather_range(2, self%gather_ptr(target) + fill(target) - 1) = p
        end do
      end do
      if (pass == 1) then
        self%gather_ptr(1) = 1
        do g = 1, self%nsuper
          self%gather_ptr(g + 1) = self%gather_ptr(g) + fill(g)
        end do
        allocate (self%gather_range(2, self%gather_ptr(self%nsuper + 1) - 1))
        fill = 0
      end if
    end do
  end subroutine build_gather_lists

  !> Share the elimination tree among the threads: whole subtrees to each (greedy, largest
  !! first, by the values they hold), splitting the largest at its root, which then joins the
  !! top, until the shares are within `balance` of each other, the largest is a leaf or the
  !! splits run out; of the cuts seen, the one whose top plus largest share is least.
  !! One thread: every supernode in the top.
  subroutine share_tree(self, parent)
    type(supernodal_solve_t), intent(inout) :: self
    integer, intent(in) :: parent(:)
    real(dp), allocatable :: own(:), work(:), load(:)
    integer, allocatable :: child_ptr(:), child(:), frontier(:), best_frontier(:), owner(:), stack(:), fill(:)
    logical, allocatable :: in_top(:)
    integer :: k, nf, best_nf, i, j, t, largest, top, count_top, splits
    integer :: ns
    real(dp) :: top_work, best_cost
    ns = self%nsuper
    allocate (own(ns), in_top(ns), owner(ns))
    do k = 1, ns           ! values read, and one more per row for its index
      own(k) = real(self%pi(k + 1) - self%pi(k), dp) * real(self%super(k + 1) - self%super(k) + 1, dp)
    end do
    work = own
    do k = 1, ns           ! subtree sums: a parent comes after its children
      if (parent(k) > 0) work(parent(k)) = work(parent(k)) + work(k)
    end do
    in_top = .true.
    owner = 0
    if (self%threads > 1) then
      allocate (child_ptr(ns + 1), child(ns), fill(ns), frontier(ns), best_frontier(ns), load(self%threads), &
                stack(ns))
      fill = 0
      do k = 1, ns
        if (parent(k) > 0) fill(parent(k)) = fill(parent(k)) + 1
      end do
      child_ptr(1) = 1
      do k = 1, ns
        child_ptr(k + 1) = child_ptr(k) + fill(k)
      end do
      fill = 0
      do k = 1, ns
        if (parent(k) > 0) then
          child(child_ptr(parent(k)) + fill(parent(k))) = k
          fill(parent(k)) = fill(parent(k)) + 1
        end if
      end do
      nf = 0
      do k = 1, ns
        if (parent(k) == 0) then
          nf = nf + 1
          frontier(nf) = k
        end if
      end do
      top_work = 0.0_dp
      best_cost = huge(1.0_dp)
      do splits = 0, max_splits * self%threads
        call sort_by_work(frontier(1:nf), work)
        call assign(frontier(1:nf), work, load, owner)
        ! a solve's time, counted in values read: the top's on one thread, then the largest share
        if (top_work + maxval(load) < best_cost) then
          best_cost = top_work + maxval(load)
          best_nf = nf
          best_frontier(1:nf) = frontier(1:nf)
        end if
        if (maxval(load) <= balance * sum(load) / self%threads) exit
        largest = frontier(1)
        if (child_ptr(largest + 1) == child_ptr(largest)) exit
        top_work = top_work + own(largest)
        frontier(1:nf - 1) = frontier(2:nf)
        nf = nf - 1
        do j = child_ptr(largest), child_ptr(largest + 1) - 1
          nf = nf + 1
          frontier(nf) = child(j)
        end do
      end do
      ! the best cut seen: each split moves a supernode to the serial top, so beyond some point
      ! splitting more (for a closer balance) makes the solve slower
      nf = best_nf
      frontier(1:nf) = best_frontier(1:nf)
      call sort_by_work(frontier(1:nf), work)
      call assign(frontier(1:nf), work, load, owner)
      ! everything below a frontier supernode goes with it
      do i = 1, nf
        top = 1
        stack(1) = frontier(i)
        do while (top > 0)
          k = stack(top)
          top = top - 1
          owner(k) = owner(frontier(i))
          in_top(k) = .false.
          do j = child_ptr(k), child_ptr(k + 1) - 1
            top = top + 1
            stack(top) = child(j)
          end do
        end do
      end do
    end if
    count_top = count(in_top)
    allocate (self%top_nodes(count_top), self%part_ptr(self%threads + 1), self%part_nodes(ns - count_top))
    self%top_nodes = pack([(k, k = 1, ns)], in_top)
    self%part_ptr(1) = 1
    do t = 1, self%threads
      self%part_ptr(t + 1) = self%part_ptr(t) + count(.not. in_top .and. owner == t)
      self%part_nodes(self%part_ptr(t):self%part_ptr(t + 1) - 1) = pack([(k, k = 1, ns)], &
                                                                       .not. in_top .and. owner == t)
    end do
  end subroutine share_tree

  !> Sort supernodes by subtree work, largest first (ties: lower number first).
  pure subroutine sort_by_work(nodes, work)
    integer, intent(inout) :: nodes(:)
    real(dp), intent(in) :: work(:)
    integer :: i, j, key
    do i = 2, size(nodes)
      key = nodes(i)
      j = i - 1
      do while (j >= 1)
        if (.not. before(key, nodes(j))) exit
        nodes(j + 1) = nodes(j)
        j = j - 1
      end do
      nodes(j + 1) = key
    end do
  contains
    pure logical function before(a, b)
      integer, intent(in) :: a, b
      before = work(a) > work(b) .or. (work(a) == work(b) .and. a < b)
    end function before
  end subroutine sort_by_work

  !> Give each subtree (largest first) to the thread with the least work so far.
  pure subroutine assign(nodes, work, load, owner)
    integer, intent(in) :: nodes(:)
    real(dp), intent(in) :: work(:)
    real(dp), intent(out) :: load(:)
    integer, intent(inout) :: owner(:)
    integer :: i, t
    load = 0.0_dp
    do i = 1, size(nodes)
      t = minloc(load, 1)
      owner(nodes(i)) = t
      load(t) = load(t) + work(nodes(i))
    end do
  end subroutine assign

end module feps_supernodal_solve
