!> Tests of the CHOLMOD solver: accuracy against known solutions and LAPACK, refactorization,
!! and detection of singular and indefinite stiffness matrices.
module test_cholmod
  use feps_kinds, only: dp, i8, pi
  use feps_error, only: err_model, err_internal, str
  use feps_sparse_matrix, only: csr_matrix_t, full_pattern
  use feps_lapack, only: dposv, dgemm, dgesv
  use feps_umfpack_solver, only: umfpack_solver_t
  use feps_cholmod_solver, only: cholmod_solver_t, count_supervariables, mixed_tolerance
  use feps_skyline_solver, only: skyline_solver_t
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_blas, only: blas_threads, set_blas_threads
  use omp_lib, only: omp_get_max_threads, omp_set_num_threads, omp_get_max_active_levels, omp_set_max_active_levels
  implicit none
  private

  public :: collect_cholmod

contains

  subroutine collect_cholmod(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("laplacian 2d solution", test_laplacian), &
      new_unittest("random spd equals lapack dposv", test_random_spd), &
      new_unittest("refactorize with doubled values", test_refactorize), &
      new_unittest("several right-hand sides", test_several_rhs), &
      new_unittest("free-free bar is singular", test_free_bar), &
      new_unittest("negative diagonal names its equation", test_indefinite), &
      new_unittest("pivot ratios of a nearly dependent pair", test_pivot_ratios), &
      new_unittest("factor statistics of a dense matrix", test_statistics), &
      new_unittest("solve before factorize fails", test_solve_unfactorized), &
      new_unittest("supervariables of known patterns", test_supervariable_counts), &
      new_unittest("node-graph ordering equals skyline", test_node_ordering_vs_skyline), &
      new_unittest("UMFPACK: non-symmetric Laplacian plus convection against dgesv; singular is err_model", &
                   test_umfpack), &
      new_unittest("skyline, CHOLMOD and UMFPACK give one solution of an SPD system", test_three_solvers), &
      new_unittest("symmetric product: the one-loop form's bits, the dense product to 1e-14", test_multiply_order), &
      new_unittest("symmetric product on 1-4 threads: the one-loop form's bits", test_multiply_threads), &
      new_unittest("feps's own supernodal solves: cholmod_l_solve's x to 1e-13, the same bits on 1-4 threads", &
                   test_own_solves), &
      new_unittest("mixed precision: the solve within kappa u_single of x, the same bits on 1-4 threads", &
                   test_mixed_solves), &
      new_unittest("mixed precision: an ill-conditioned factor (kappa 1e9) stays in double precision", &
                   test_mixed_fallback) &
    ]
  end subroutine collect_cholmod

  !> csr_multiply against two independent computations on a 60 x 60 symmetric matrix whose
  !! entries and x span 16 orders of magnitude, so that the order of the additions shows in the
  !! last bits: bit for bit the one-loop form (y(i) and y(j) updated entry by entry in row
  !! order), which the thesis results were computed with, and the dense product to 1e-14 of
  !! sum |a_ij x_j|. The same sums added in reverse order differ in some bit (the bitwise
  !! check can fail).
  subroutine test_multiply_order(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 60
    real(dp) :: dense(n, n), x(n), y(n), y_loop(n), y_reverse(n), scale(n)
    type(csr_matrix_t) :: a
    integer :: i, j
    dense = 0.0_dp
    do i = 1, n
      x(i) = sin(0.37_dp * i) * 10.0_dp**modulo(7 * i, 17 - 8)
      do j = 1, i
        if (i /= j .and. modulo(i * j + 3 * i, 4) /= 0) cycle
        dense(i, j) = cos(1.3_dp * i + 0.7_dp * j) * 10.0_dp**modulo(5 * i + 3 * j, 9)
        dense(j, i) = dense(i, j)
      end do
      dense(i, i) = dense(i, i) + 2.0e9_dp
    end do
    a = dense_to_csr(dense)
    call a%multiply(x, y)
    y_loop = one_loop_product(a, x)
    y_reverse = 0.0_dp
    do i = 1, n
      do j = n, 1, -1
        y_reverse(i) = y_reverse(i) + dense(i, j) * x(j)
      end do
    end do
    call check(error, all(y == y_loop), 'csr_multiply differs from the one-loop form in some bit')
    if (allocated(error)) return
    call check(error, any(y_reverse /= y_loop), 'the reverse order gives the same bits: the data cannot tell orders apart')
    if (allocated(error)) return
    scale = matmul(abs(dense), abs(x))
    call check(error, maxval(abs(y - matmul(dense, x)) / scale) <= 1.0e-14_dp, &
               'csr_multiply differs from the dense product by more than 1e-14')
  end subroutine test_multiply_order

  !> csr_multiply on a matrix large enough for its threaded form (the 5-point Laplacian of a
  !! 200 x 200 grid, 119 600 stored entries, its values and x spanning 16 orders of magnitude):
  !! on 1, 2, 3 and 4 threads the bits of the one-loop form, whose every y(j) takes its terms
  !! in row order.
  subroutine test_multiply_threads(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: a
    real(dp), allocatable :: x(:), y(:), y_loop(:)
    integer :: i, t, threads
    integer(i8) :: k
    a = laplacian_2d(200)
    do k = 1, a%nnz()
      a%val(k) = a%val(k) * 10.0_dp**modulo(7 * k, 16_i8) * (1.0_dp + 0.3_dp * sin(real(k, dp)))
    end do
    allocate (y(a%n), y_loop(a%n))
    x = [(cos(0.37_dp * i) * 10.0_dp**modulo(5 * i, 16), i = 1, a%n)]
    y_loop = one_loop_product(a, x)
    call check(error, a%nnz() >= 100000_i8, 'the matrix is large enough for the threaded form')
    if (allocated(error)) return
    threads = omp_get_max_threads()
    do t = 1, 4
      call omp_set_num_threads(t)
      call a%multiply(x, y)
      if (any(y /= y_loop)) exit
    end do
    call omp_set_num_threads(threads)
    call check(error, all(y == y_loop), 'csr_multiply on ' // str(min(t, 4)) // ' threads differs from ' // &
               'the one-loop form in some bit')
  end subroutine test_multiply_threads

  !> A x in the form that updates y in memory entry by entry: each y(j) takes row j's own
  !! terms, then one term from each later row, in row order (the order csr_multiply keeps).
  pure function one_loop_product(a, x) result(y)
    type(csr_matrix_t), intent(in) :: a
    real(dp), intent(in) :: x(:)
    real(dp) :: y(a%n)
    integer :: i, j
    integer(i8) :: k
    y = 0.0_dp
    do i = 1, a%n
      do k = a%row_ptr(i), a%row_ptr(i + 1) - 1
        j = a%col(k)
        y(i) = y(i) + a%val(k) * x(j)
        if (j /= i) y(j) = y(j) + a%val(k) * x(i)
      end do
    end do
  end function one_loop_product

  !> The 2D Laplacian of a 9 x 9 grid with a varying diagonal (SPD) solved by skyline (LDL^T,
  !! RCM), CHOLMOD (LL^T, METIS) and UMFPACK (LU of both triangles, as full Newton factorizes a
  !! non-symmetric tangent): one solution to 1e-12, and A x = b to 1e-12 (residual).
  subroutine test_three_solvers(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: lower, full
    type(skyline_solver_t) :: sky
    type(cholmod_solver_t) :: chol
    type(umfpack_solver_t) :: lu
    real(dp), allocatable :: b(:), x(:, :), ax(:)
    integer :: i, j, s
    integer(i8) :: k, kf
    lower = laplacian_2d(9)
    do i = 1, lower%n
      do k = lower%row_ptr(i), lower%row_ptr(i + 1) - 1
        if (lower%col(k) == i) lower%val(k) = 4.0_dp + 0.5_dp * sin(real(i, dp))
      end do
    end do
    call full_pattern(lower, full)
    do i = 1, lower%n
      do k = lower%row_ptr(i), lower%row_ptr(i + 1) - 1
        j = lower%col(k)
        do kf = full%row_ptr(i), full%row_ptr(i + 1) - 1
          if (full%col(kf) == j) full%val(kf) = lower%val(k)
        end do
        do kf = full%row_ptr(j), full%row_ptr(j + 1) - 1
          if (full%col(kf) == i) full%val(kf) = lower%val(k)
        end do
      end do
    end do
    allocate (b(lower%n), x(lower%n, 3), ax(lower%n))
    do i = 1, lower%n
      b(i) = cos(1.7_dp * i)
    end do
    x = spread(b, 2, 3)
    call sky%analyze(lower, error)
    if (allocated(error)) return
    call sky%factorize(lower, error)
    if (allocated(error)) return
    call sky%solve(x(:, 1), error)
    if (allocated(error)) return
    call chol%analyze(lower, error)
    if (allocated(error)) return
    call chol%factorize(lower, error)
    if (allocated(error)) return
    call chol%solve(x(:, 2), error)
    if (allocated(error)) return
    call lu%factorize(full, error)
    if (allocated(error)) return
    call lu%solve(x(:, 3), error)
    if (allocated(error)) return
    do s = 1, 3
      call lower%multiply(x(:, s), ax)
      call check(error, maxval(abs(ax - b)) <= 1.0e-12_dp * maxval(abs(b)), 'A x = b, solver ' // str(s))
      if (allocated(error)) return
      call check(error, maxval(abs(x(:, s) - x(:, 2))) <= 1.0e-12_dp * maxval(abs(x(:, 2))), &
                 'the same solution as CHOLMOD, solver ' // str(s))
      if (allocated(error)) return
    end do
  end subroutine test_three_solvers

  !> The full pattern of the 2D Laplacian (6 x 6 grid) filled with a non-symmetric matrix,
  !! the Laplacian plus a convection term (+c to the right neighbour, -c to the left, so
  !! a(i, j) /= a(j, i)), solved by UMFPACK against LAPACK's dense LU (dgesv) to 1e-12;
  !! every row of the pattern sorted; then a matrix with a zero row fails with err_model.
  subroutine test_umfpack(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: lower, full
    type(umfpack_solver_t) :: lu
    real(dp), allocatable :: dense(:, :), x(:), b(:, :)
    integer, allocatable :: ipiv(:)
    integer :: i, j, n, info, code
    integer(i8) :: k
    character(len=:), allocatable :: msg
    lower = laplacian_2d(6)
    call full_pattern(lower, full)
    n = full%n
    call check(error, int(size(full%col)), int(2 * lower%nnz() - n), 'both triangles')
    if (allocated(error)) return
    allocate (dense(n, n), x(n), b(n, 1), ipiv(n))
    dense = 0.0_dp
    do i = 1, n
      do k = full%row_ptr(i), full%row_ptr(i + 1) - 1
        j = full%col(k)
        if (k > full%row_ptr(i)) then
          if (full%col(k - 1) >= j) then
            call test_failed(error, 'row ' // str(i) // ' not sorted')
            return
          end if
        end if
        if (i == j) then
          full%val(k) = 4.0_dp
        else if (j == i + 1) then
          full%val(k) = -1.0_dp + 0.3_dp
        else if (j == i - 1) then
          full%val(k) = -1.0_dp - 0.3_dp
        else
          full%val(k) = -1.0_dp
        end if
        dense(i, j) = full%val(k)
      end do
    end do
    do i = 1, n
      x(i) = sin(real(i, dp))
    end do
    b(:, 1) = x
    call lu%factorize(full, error)
    if (allocated(error)) return
    call lu%solve(x, error)
    if (allocated(error)) return
    call dgesv(n, 1, dense, n, ipiv, b, n, info)
    call check(error, info, 0, 'dgesv')
    if (allocated(error)) return
    call check(error, maxval(abs(x - b(:, 1))) <= 1.0e-12_dp * maxval(abs(b)), 'UMFPACK equals dgesv')
    if (allocated(error)) return
    ! another pattern with the same size and number of entries (equations renumbered between
    ! stages): [[2, 0, 1], [0, 3, 0], [-1, 0, 4]] x = [3, 3, 3] has x = [1, 1, 1]
    call three_by_three([1, 1, 2, 3, 3], [1, 3, 2, 1, 3], [2.0_dp, 1.0_dp, 3.0_dp, -1.0_dp, 4.0_dp], error)
    if (allocated(error)) return
    ! a zero row: singular
    full%val(full%row_ptr(3):full%row_ptr(4) - 1) = 0.0_dp
    call lu%factorize(full, error)
    if (.not. allocated(error)) then
      call test_failed(error, 'a singular matrix was factorized')
      return
    end if
    code = error%code
    msg = error%message
    deallocate (error)
    call check(error, code, err_model, 'singular: ' // msg)
  contains
    !> Factorize a 3 x 3 matrix given by its entries, row by row, with the solver that holds
    !! the Laplacian's analysis (first [[2, 1, 0], [1, 3, 0], [0, 0, 4]], same size and count),
    !! and solve for the right-hand side [3, 3, 3].
    subroutine three_by_three(rows, cols, vals, error)
      integer, intent(in) :: rows(5), cols(5)
      real(dp), intent(in) :: vals(5)
      type(error_t), allocatable, intent(out) :: error
      type(csr_matrix_t) :: m
      type(umfpack_solver_t) :: small
      real(dp) :: y(3)
      m%n = 3
      m%row_ptr = [1_i8, 3_i8, 4_i8, 6_i8]
      m%col = [1, 2, 2, 1, 3]
      m%val = [2.0_dp, 1.0_dp, 3.0_dp, 1.0_dp, 4.0_dp]
      call small%factorize(m, error)
      if (allocated(error)) return
      m%col = cols
      m%val = vals
      m%row_ptr = [1_i8, int(count(rows <= 1) + 1, i8), int(count(rows <= 2) + 1, i8), 6_i8]
      call small%factorize(m, error)
      if (allocated(error)) return
      y = 3.0_dp
      call small%solve(y, error)
      if (allocated(error)) return
      call check(error, maxval(abs(y - 1.0_dp)) <= 1.0e-14_dp, &
                 'a new pattern of the same size is analysed again')
    end subroutine three_by_three
  end subroutine test_umfpack

  !> 5-point Laplacian on an m x m interior grid with Dirichlet boundaries (lower triangle).
  function laplacian_2d(m) result(a)
    integer, intent(in) :: m
    type(csr_matrix_t) :: a
    integer :: i, j, row
    integer(i8) :: pos
    a%n = m * m
    allocate (a%row_ptr(a%n + 1), a%col(3 * a%n), a%val(3 * a%n))
    pos = 1
    do j = 1, m
      do i = 1, m
        row = (j - 1) * m + i
        a%row_ptr(row) = pos
        if (j > 1) call add(row - m, -1.0_dp)
        if (i > 1) call add(row - 1, -1.0_dp)
        call add(row, 4.0_dp)
      end do
    end do
    a%row_ptr(a%n + 1) = pos
    a%col = a%col(1:pos - 1)
    a%val = a%val(1:pos - 1)
  contains
    subroutine add(column, value)
      integer, intent(in) :: column
      real(dp), intent(in) :: value
      a%col(pos) = column
      a%val(pos) = value
      pos = pos + 1
    end subroutine add
  end function laplacian_2d

  !> Lower triangle of a dense symmetric matrix, zeros kept, as CSR.
  pure function dense_to_csr(dense) result(a)
    real(dp), intent(in) :: dense(:, :)
    type(csr_matrix_t) :: a
    integer :: i, j
    integer(i8) :: pos
    a%n = size(dense, 1)
    allocate (a%row_ptr(a%n + 1), a%col(a%n * (a%n + 1) / 2), a%val(a%n * (a%n + 1) / 2))
    pos = 1
    do i = 1, a%n
      a%row_ptr(i) = pos
      do j = 1, i
        a%col(pos) = j
        a%val(pos) = dense(i, j)
        pos = pos + 1
      end do
    end do
    a%row_ptr(a%n + 1) = pos
  end function dense_to_csr

  !> Tridiagonal lower triangle with the given diagonal and sub-diagonal.
  pure function tridiagonal(diag, sub) result(a)
    real(dp), intent(in) :: diag(:), sub(:)
    type(csr_matrix_t) :: a
    integer :: i
    integer(i8) :: pos
    a%n = size(diag)
    allocate (a%row_ptr(a%n + 1), a%col(2 * a%n - 1), a%val(2 * a%n - 1))
    pos = 1
    do i = 1, a%n
      a%row_ptr(i) = pos
      if (i > 1) then
        a%col(pos) = i - 1
        a%val(pos) = sub(i - 1)
        pos = pos + 1
      end if
      a%col(pos) = i
      a%val(pos) = diag(i)
      pos = pos + 1
    end do
    a%row_ptr(a%n + 1) = pos
  end function tridiagonal

  !> Deterministic pseudo-random numbers in [0, 1) (linear congruential, 31-bit).
  pure subroutine fill_random(x, seed)
    real(dp), intent(out) :: x(:)
    integer(i8), intent(inout) :: seed
    integer :: k
    do k = 1, size(x)
      seed = modulo(1103515245_i8 * seed + 12345_i8, 2147483648_i8)
      x(k) = real(seed, dp) / 2147483648.0_dp
    end do
  end subroutine fill_random

  !> Pass when `error` (consumed) is an err_model error whose item lies in first..last and whose
  !! message names that equation and has no NaN; fail otherwise, saying `what`.
  subroutine expect_model_error(error, first, last, what)
    type(error_t), allocatable, intent(inout) :: error
    integer, intent(in) :: first, last
    character(len=*), intent(in) :: what
    type(error_t), allocatable :: got
    call move_alloc(error, got)
    if (.not. allocated(got)) then
      call test_failed(error, what // ': no error')
    else if (got%code /= err_model .or. got%item < first .or. got%item > last .or. &
             (index(got%message, 'equation ' // str(got%item) // ' ') == 0 .and. &
              index(got%message, 'equation ' // str(got%item) // ':') == 0) .or. &
             index(got%message, 'NaN') > 0) then
      call test_failed(error, what // ': expected err_model naming an equation in ' // str(first) // '..' // &
                       str(last) // ', got code ' // str(got%code) // ' item ' // str(got%item) // ': ' // &
                       got%message)
    end if
  end subroutine expect_model_error

  !> Analyse and factorize `a` with `solver`.
  subroutine analyze_and_factorize(solver, a, error)
    type(cholmod_solver_t), intent(inout) :: solver
    type(csr_matrix_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    call solver%analyze(a, error)
    if (allocated(error)) return
    call solver%factorize(a, error)
  end subroutine analyze_and_factorize

  !> b = A x_true on a 30 x 30 grid; the solve must return x_true to 1e-10 relative.
  subroutine test_laplacian(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp), allocatable :: x_true(:), b(:)
    integer :: k
    a = laplacian_2d(30)
    allocate (x_true(a%n), b(a%n))
    x_true = [(sin(0.1_dp * k) + 0.01_dp * k, k = 1, a%n)]
    call a%multiply(x_true, b)
    call analyze_and_factorize(solver, a, error)
    if (allocated(error)) return
    call check(error, solver%name() == 'cholmod', 'solver name')
    if (allocated(error)) return
    call solver%solve(b, error)
    if (allocated(error)) return
    call check(error, maxval(abs(b - x_true)) / maxval(abs(x_true)), 0.0_dp, &
               'relative error of the Laplacian solution', abs=1.0e-10_dp)
    if (allocated(error)) return
    ! Every pivot of an SPD matrix lies in [lambda_min(A), A_jj]; the first one eliminated is A_jj.
    call check(error, solver%max_pivot_ratio, 1.0_dp, 'largest pivot ratio', abs=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, solver%min_pivot_ratio >= (4.0_dp - 4.0_dp * cos(pi / 31.0_dp)) / 4.0_dp, &
               'smallest pivot ratio >= lambda_min / 4: ' // str(solver%min_pivot_ratio))
  end subroutine test_laplacian

  !> A = M^T M + n I for a random M; CHOLMOD and LAPACK dposv agree to 1e-12 relative.
  subroutine test_random_spd(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 12
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp) :: m(n, n), dense(n, n), b(n), x_lapack(n, 1), x_cholmod(n)
    integer(i8) :: seed
    integer :: info, i
    seed = 2024
    call fill_random(m(:, 1), seed)
    do i = 2, n
      call fill_random(m(:, i), seed)
    end do
    m = m - 0.5_dp
    dense = 0.0_dp
    do i = 1, n
      dense(i, i) = real(n, dp)
    end do
    call dgemm('T', 'N', n, n, n, 1.0_dp, m, n, m, n, 1.0_dp, dense, n)
    call fill_random(b, seed)

    x_lapack(:, 1) = b
    block
      real(dp) :: work(n, n)
      work = dense
      call dposv('L', n, 1, work, n, x_lapack, n, info)
    end block
    call check(error, info, 0, 'dposv info')
    if (allocated(error)) return

    a = dense_to_csr(dense)
    call analyze_and_factorize(solver, a, error)
    if (allocated(error)) return
    x_cholmod = b
    call solver%solve(x_cholmod, error)
    if (allocated(error)) return
    call check(error, maxval(abs(x_cholmod - x_lapack(:, 1))) / maxval(abs(x_lapack)), 0.0_dp, &
               'relative difference to dposv', abs=1.0e-12_dp)
  end subroutine test_random_spd

  !> Same pattern, values doubled: the factorization is redone and the solution halves.
  subroutine test_refactorize(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp), allocatable :: b(:), x1(:), x2(:)
    a = laplacian_2d(12)
    allocate (b(a%n))
    b = 1.0_dp
    call analyze_and_factorize(solver, a, error)
    if (allocated(error)) return
    x1 = b
    call solver%solve(x1, error)
    if (allocated(error)) return
    a%val = 2.0_dp * a%val
    call solver%factorize(a, error)
    if (allocated(error)) return
    x2 = b
    call solver%solve(x2, error)
    if (allocated(error)) return
    call check(error, solver%factorizations, 2, 'factorization count')
    if (allocated(error)) return
    call check(error, maxval(abs(2.0_dp * x2 - x1)) / maxval(abs(x1)), 0.0_dp, &
               'solution halves when A doubles', abs=1.0e-13_dp)
  end subroutine test_refactorize

  !> Two right-hand sides stored one after another are solved in one call.
  subroutine test_several_rhs(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp), allocatable :: x1(:), x2(:), b(:)
    integer :: k
    a = laplacian_2d(8)
    x1 = [(1.0_dp + k, k = 1, a%n)]
    x2 = [(cos(0.3_dp * k), k = 1, a%n)]
    allocate (b(2 * a%n))
    call a%multiply(x1, b(1:a%n))
    call a%multiply(x2, b(a%n + 1:))
    call analyze_and_factorize(solver, a, error)
    if (allocated(error)) return
    call solver%solve(b, error)
    if (allocated(error)) return
    call check(error, maxval(abs(b(1:a%n) - x1)) / maxval(abs(x1)), 0.0_dp, 'first solution', abs=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, maxval(abs(b(a%n + 1:) - x2)) / maxval(abs(x2)), 0.0_dp, 'second solution', abs=1.0e-12_dp)
  end subroutine test_several_rhs

  !> A bar of 20 elements with no support has one rigid mode, with equal or unequal element
  !! stiffness (exact zero or round-off last pivot).
  subroutine test_free_bar(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: nel = 20
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp) :: stiffness(nel), diag(nel + 1)
    integer :: e, variant
    do variant = 0, 1
      stiffness = [(1.0_dp + 0.37_dp * variant * e, e = 1, nel)]
      diag = 0.0_dp
      diag(1:nel) = stiffness
      diag(2:nel + 1) = diag(2:nel + 1) + stiffness
      a = tridiagonal(diag, -stiffness)
      call analyze_and_factorize(solver, a, error)
      call expect_model_error(error, 1, a%n, 'free-free bar, variant ' // str(variant))
      if (allocated(error)) return
      call check(error, solver%min_pivot_ratio == solver%min_pivot_ratio, 'min pivot ratio is not NaN')
      if (allocated(error)) return
    end do
  end subroutine test_free_bar

  !> Diagonally dominant tridiagonal matrix with A(7,7) = -4: the pivot of equation 7 is the
  !! first to fail whatever the ordering (the other leading principal blocks stay SPD).
  subroutine test_indefinite(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 20, bad = 7
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp) :: diag(n), sub(n - 1)
    diag = 4.0_dp
    diag(bad) = -4.0_dp
    sub = -1.0_dp
    a = tridiagonal(diag, sub)
    call analyze_and_factorize(solver, a, error)
    call expect_model_error(error, bad, bad, 'negative diagonal')
    if (allocated(error)) return
    ! The solver recovers: the same pattern with a positive diagonal factorizes and solves.
    a%val(a%row_ptr(bad + 1) - 1) = 4.0_dp
    call solver%factorize(a, error)
    if (allocated(error)) return
    block
      real(dp) :: x_true(n), b(n)
      integer :: k
      x_true = [(real(k, dp), k = 1, n)]
      call a%multiply(x_true, b)
      call solver%solve(b, error)
      if (allocated(error)) return
      call check(error, maxval(abs(b - x_true)) / n, 0.0_dp, 'solution after recovery', abs=1.0e-13_dp)
    end block
  end subroutine test_indefinite

  !> A = S B S with S = diag(1..n), B unit diagonal with only B(14,13) = 1 - delta off the diagonal.
  !! Pivot ratios are invariant under the scaling: the pair's second one is 1 - (1 - delta)**2, all
  !! others 1. Small delta passes; delta = 1e-13 fails naming 13 or 14.
  subroutine test_pivot_ratios(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 20
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp) :: diag(n), sub(n - 1), delta
    integer :: i
    diag = [(real(i, dp)**2, i = 1, n)]
    sub = 0.0_dp
    delta = 1.0e-3_dp
    sub(13) = (1.0_dp - delta) * 13.0_dp * 14.0_dp
    a = tridiagonal(diag, sub)
    call analyze_and_factorize(solver, a, error)
    if (allocated(error)) return
    call check(error, solver%min_pivot_ratio, 1.0_dp - (1.0_dp - delta)**2, 'smallest pivot ratio', rel=1.0e-10_dp)
    if (allocated(error)) return
    call check(error, solver%max_pivot_ratio, 1.0_dp, 'largest pivot ratio', abs=1.0e-15_dp)
    if (allocated(error)) return

    a%val(a%row_ptr(14)) = (1.0_dp - 1.0e-13_dp) * 13.0_dp * 14.0_dp
    call solver%factorize(a, error)
    call expect_model_error(error, 13, 14, 'nearly dependent pair')
  end subroutine test_pivot_ratios

  !> A dense n x n SPD matrix fills L completely: nnz(L) = n(n+1)/2 under any ordering, and
  !! the LL' flop count is at least n^3/3.
  subroutine test_statistics(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 15
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp) :: dense(n, n)
    integer :: i, j
    do j = 1, n
      do i = 1, n
        dense(i, j) = 1.0_dp / real(i + j, dp)
      end do
      dense(j, j) = dense(j, j) + 1.0_dp
    end do
    a = dense_to_csr(dense)
    call analyze_and_factorize(solver, a, error)
    if (allocated(error)) return
    call check(error, solver%factor_nnz > 0 .and. solver%flops > 0.0_dp, 'factor_nnz and flops positive')
    if (allocated(error)) return
    call check(error, int(solver%factor_nnz), n * (n + 1) / 2, 'nnz(L) of a dense matrix')
    if (allocated(error)) return
    call check(error, solver%flops >= real(n, dp)**3 / 3.0_dp, 'flops >= n^3/3: ' // str(solver%flops))
    if (allocated(error)) return
    call check(error, solver%factorizations, 1, 'factorization count')
  end subroutine test_statistics

  !> Solving without a factorization is an error, not a crash.
  subroutine test_solve_unfactorized(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: solver
    type(error_t), allocatable :: got
    real(dp) :: b(4)
    b = 1.0_dp
    call solver%solve(b, error)
    call move_alloc(error, got)
    if (.not. allocated(got)) then
      call test_failed(error, 'solve without factorization succeeded')
    else if (got%code /= err_internal) then
      call test_failed(error, 'expected err_internal, got ' // str(got%code) // ': ' // got%message)
    end if
  end subroutine test_solve_unfactorized

  !> Lower triangle of a quad mesh of mx x my elements with 3 DOFs per node, the third held at
  !! the nodes of the first column (2 DOFs there). Each element adds B^T B with a random 12 x 12
  !! B, so A is SPD and every entry coupling two nodes of one element is in the pattern, zero or
  !! not. Node by node numbering, or all first DOFs, then all second, then all third DOFs.
  function quad_mesh_matrix(mx, my, by_node) result(a)
    integer, intent(in) :: mx, my
    logical, intent(in) :: by_node
    type(csr_matrix_t) :: a
    integer, parameter :: dofs_per_node = 3
    integer :: equation(dofs_per_node, (mx + 1) * (my + 1))
    real(dp), allocatable :: dense(:, :)
    logical, allocatable :: coupled(:, :)
    real(dp) :: b(12, 12), ke(12, 12)
    integer :: ex, ey, node, d, i, j, n, corner(4), element_eq(12)
    integer(i8) :: seed, pos

    n = 0
    equation = 0
    do d = 1, dofs_per_node
      do node = 1, size(equation, 2)
        if (d == 3 .and. modulo(node - 1, mx + 1) == 0) cycle   ! held DOF
        if (by_node) cycle
        n = n + 1
        equation(d, node) = n
      end do
    end do
    if (by_node) then
      do node = 1, size(equation, 2)
        do d = 1, dofs_per_node
          if (d == 3 .and. modulo(node - 1, mx + 1) == 0) cycle
          n = n + 1
          equation(d, node) = n
        end do
      end do
    end if

    allocate (dense(n, n), coupled(n, n))
    dense = 0.0_dp
    coupled = .false.
    seed = 77
    do ey = 1, my
      do ex = 1, mx
        node = (ey - 1) * (mx + 1) + ex
        corner = [node, node + 1, node + mx + 2, node + mx + 1]
        element_eq = reshape(equation(:, corner), [12])
        do j = 1, 12
          call fill_random(b(:, j), seed)
        end do
        ke = matmul(transpose(b - 0.5_dp), b - 0.5_dp)
        do j = 1, 12
          if (element_eq(j) == 0) cycle
          do i = 1, 12
            if (element_eq(i) == 0) cycle
            dense(element_eq(i), element_eq(j)) = dense(element_eq(i), element_eq(j)) + ke(i, j)
            coupled(element_eq(i), element_eq(j)) = .true.
          end do
        end do
      end do
    end do
    ! Exact zeros in the pattern, as an assembled matrix can have them.
    dense(equation(1, 1), equation(2, 2)) = 0.0_dp
    dense(equation(2, 2), equation(1, 1)) = 0.0_dp

    a%n = n
    allocate (a%row_ptr(n + 1), a%col(count(coupled)), a%val(count(coupled)))
    pos = 1
    do i = 1, n
      a%row_ptr(i) = pos
      do j = 1, i
        if (.not. coupled(i, j)) cycle
        a%col(pos) = j
        a%val(pos) = dense(i, j)
        pos = pos + 1
      end do
    end do
    a%row_ptr(n + 1) = pos
    a%col = a%col(1:pos - 1)
    a%val = a%val(1:pos - 1)
  end function quad_mesh_matrix

  !> Supervariables (equations with identical pattern): 1 for a dense matrix, n for a diagonal
  !! or tridiagonal one, m*m for the 5-point Laplacian, and one per node for a mesh whatever the
  !! DOF numbering (30 nodes, 80 equations).
  subroutine test_supervariable_counts(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: a
    real(dp) :: dense(7, 7)
    integer(i8) :: count
    integer :: k
    dense = 1.0_dp
    call count_supervariables(dense_to_csr(dense), count, error)
    if (allocated(error)) return
    call check(error, int(count), 1, 'dense 7 x 7')
    if (allocated(error)) return
    call count_supervariables(tridiagonal([(2.0_dp, k = 1, 5)], [(0.0_dp, k = 1, 4)]), count, error)
    if (allocated(error)) return
    call check(error, int(count), 5, 'tridiagonal 5 x 5')
    if (allocated(error)) return
    a = tridiagonal([(2.0_dp, k = 1, 1)], [(0.0_dp, k = 1, 0)])
    call count_supervariables(a, count, error)
    if (allocated(error)) return
    call check(error, int(count), 1, 'one equation')
    if (allocated(error)) return
    call count_supervariables(laplacian_2d(6), count, error)
    if (allocated(error)) return
    call check(error, int(count), 36, '5-point Laplacian 6 x 6')
    if (allocated(error)) return
    a = quad_mesh_matrix(5, 4, by_node=.true.)
    call check(error, a%n, 3 * 30 - 5, 'equations of the 5 x 4 mesh')
    if (allocated(error)) return
    call count_supervariables(a, count, error)
    if (allocated(error)) return
    call check(error, int(count), 30, 'mesh numbered node by node')
    if (allocated(error)) return
    call count_supervariables(quad_mesh_matrix(5, 4, by_node=.false.), count, error)
    if (allocated(error)) return
    call check(error, int(count), 30, 'mesh numbered DOF by DOF')
    if (allocated(error)) return
    ! A diagonal entry missing from a row is rejected, not miscounted.
    a = laplacian_2d(3)
    a%col(a%row_ptr(2) - 1) = 0
    block
      type(error_t), allocatable :: got
      call count_supervariables(a, count, got)
      call check(error, allocated(got), 'invalid pattern rejected')
    end block
  end subroutine test_supervariable_counts

  !> On a mesh with 2- and 3-DOF nodes, numbered both ways, the CHOLMOD solution (METIS on the
  !! 30-vertex node graph) equals the skyline solution to 1e-10 relative, and both equal x_true.
  subroutine test_node_ordering_vs_skyline(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: cholmod
    type(skyline_solver_t) :: skyline
    type(csr_matrix_t) :: a
    real(dp), allocatable :: x_true(:), b(:), x_cholmod(:), x_skyline(:)
    integer :: k, numbering
    do numbering = 1, 2
      a = quad_mesh_matrix(5, 4, by_node=numbering == 1)
      x_true = [(cos(0.7_dp * k) + 0.1_dp * k, k = 1, a%n)]
      allocate (b(a%n))
      call a%multiply(x_true, b)
      call analyze_and_factorize(cholmod, a, error)
      if (allocated(error)) return
      call check(error, int(cholmod%supervariables()), 30, 'vertices METIS ordered')
      if (allocated(error)) return
      x_cholmod = b
      call cholmod%solve(x_cholmod, error)
      if (allocated(error)) return
      call skyline%analyze(a, error)
      if (allocated(error)) return
      call skyline%factorize(a, error)
      if (allocated(error)) return
      x_skyline = b
      call skyline%solve(x_skyline, error)
      if (allocated(error)) return
      call check(error, maxval(abs(x_cholmod - x_skyline)) / maxval(abs(x_skyline)), 0.0_dp, &
                 'cholmod against skyline, numbering ' // str(numbering), abs=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(x_cholmod - x_true)) / maxval(abs(x_true)), 0.0_dp, &
                 'cholmod against x_true, numbering ' // str(numbering), abs=1.0e-10_dp)
      if (allocated(error)) return
      deallocate (b)
    end do
  end subroutine test_node_ordering_vs_skyline

  !> feps's own forward and back substitution with CHOLMOD's supernodal factor (issue 28), on
  !! the 5-point Laplacian of a 120 x 120 grid (14 400 equations; METIS's nested dissection
  !! gives a tree that splits among threads): the x of CHOLMOD's own cholmod_l_solve to 1e-13
  !! relative (the two add the forward pass's contributions in another order), A x = b to 1e-12
  !! of |b|, and the same bits with 1, 2, 3 and 4 threads (the BLAS on one thread throughout,
  !! since its thread count changes the factor itself at round-off), and with four planned
  !! where OpenMP gives one (inside another parallel region).
  subroutine test_own_solves(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: solver
    type(csr_matrix_t) :: a
    real(dp), allocatable :: b(:), x(:, :), reference(:), ax(:)
    integer :: k, t, threads, blas
    a = laplacian_2d(120)
    b = [(sin(0.01_dp * k) + 0.3_dp * cos(0.37_dp * k), k = 1, a%n)]
    allocate (x(a%n, 5), ax(a%n))
    threads = omp_get_max_threads()
    blas = blas_threads()
    call set_blas_threads(1)
    do t = 1, 4
      call omp_set_num_threads(t)
      call analyze_and_factorize(solver, a, error)
      if (allocated(error)) exit
      call check(error, solver%solve_threads(), t, 'threads of the own solves')
      if (allocated(error)) exit
      x(:, t) = b
      call solver%solve(x(:, t), error)
      if (allocated(error)) exit
    end do
    if (.not. allocated(error)) then
      reference = b
      call solver%library_solve(reference, error)
    end if
    if (.not. allocated(error)) then
      ! the plan of four threads, run where OpenMP gives it one (a region inside a region)
      x(:, 5) = b
      call solve_inside_a_region(solver, x(:, 5), error)
    end if
    call omp_set_num_threads(threads)
    call set_blas_threads(blas)
    if (allocated(error)) return
    call check(error, maxval(abs(x(:, 1) - reference)) / maxval(abs(reference)), 0.0_dp, &
               'own solve against cholmod_l_solve', abs=1.0e-13_dp)
    if (allocated(error)) return
    call a%multiply(x(:, 1), ax)
    call check(error, maxval(abs(ax - b)) / maxval(abs(b)), 0.0_dp, 'A x - b', abs=1.0e-12_dp)
    if (allocated(error)) return
    do t = 2, 4
      call check(error, all(x(:, t) == x(:, 1)), 'the same bits on ' // str(t) // ' threads as on one')
      if (allocated(error)) return
    end do
    call check(error, all(x(:, 5) == x(:, 1)), 'the same bits when four threads are planned and one is given')
  end subroutine test_own_solves

  !> Mixed precision ('cholmod-mixed') on the 5-point Laplacian of a 120 x 120 grid, b = A x
  !! for a smooth x. A factor's first two solves are the double-precision ones (bit for bit);
  !! from its third on they read a single-precision copy. A backward-stable solve in single
  !! precision is within about kappa u of x, u = 2^-24 the unit round-off of single precision
  !! and kappa = sin^2(120 pi / 242) / sin^2(pi / 242) = 5.93e3 the condition number (the
  !! grid's extreme eigenvalues); the check allows kappa u (3.5e-4) and needs more than the
  !! double solve's accuracy (1e-10), so it fails if the copy is not used (measured: 1.3e-6).
  !! An exact solve (BFGS's) is the double one; the same bits on 1-4 threads.
  subroutine test_mixed_solves(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: solver, reference
    type(csr_matrix_t) :: a
    real(dp), allocatable :: b(:), x(:, :), x_true(:), x_double(:), x_exact(:)
    real(dp) :: kappa, err
    integer :: k, t, threads, blas
    a = laplacian_2d(120)
    x_true = [(sin(0.01_dp * k) + 0.3_dp * cos(0.37_dp * k), k = 1, a%n)]
    allocate (b(a%n), x(a%n, 4))
    call a%multiply(x_true, b)
    kappa = (sin(120 * pi / 242) / sin(pi / 242))**2
    solver = cholmod_solver_t(mixed=.true.)
    call check(error, solver%name() == 'cholmod-mixed', 'the solver''s name')
    if (allocated(error)) return
    threads = omp_get_max_threads()
    blas = blas_threads()
    call set_blas_threads(1)
    call analyze_and_factorize(reference, a, error)
    if (.not. allocated(error)) then
      x_double = b
      call reference%solve(x_double, error)
    end if
    do t = 1, 4
      if (allocated(error)) exit
      call omp_set_num_threads(t)
      call analyze_and_factorize(solver, a, error)
      do k = 1, 3   ! the third solve of the factor reads the copy
        if (allocated(error)) exit
        x(:, t) = b
        call solver%solve(x(:, t), error)
        if (k == 1 .and. t == 1 .and. .not. allocated(error)) &
          call check(error, all(x(:, 1) == x_double), 'a factor''s first solve in double precision')
      end do
    end do
    if (.not. allocated(error)) then
      x_exact = b
      solver%exact_solves = .true.
      call solver%solve(x_exact, error)
      solver%exact_solves = .false.
    end if
    call omp_set_num_threads(threads)
    call set_blas_threads(blas)
    if (allocated(error)) return
    err = maxval(abs(x(:, 1) - x_true)) / maxval(abs(x_true))
    call check(error, err <= kappa * 2.0_dp**(-24), 'mixed solve within kappa u of x: ' // str(err))
    if (allocated(error)) return
    call check(error, err > 1.0e-10_dp, 'the mixed solve is less accurate than a double one: ' // str(err))
    if (allocated(error)) return
    call check(error, solver%lower_precision_factors, 4, 'factors solved in single precision')
    if (allocated(error)) return
    call check(error, solver%test_solve_error <= kappa * 2.0_dp**(-24), 'the test solves'' error')
    if (allocated(error)) return
    call check(error, all(x_exact == x_double), 'an exact solve is the double one, bit for bit')
    if (allocated(error)) return
    do t = 2, 4
      call check(error, all(x(:, t) == x(:, 1)), 'the same bits on ' // str(t) // ' threads as on one')
      if (allocated(error)) return
    end do
  end subroutine test_mixed_solves

  !> Mixed precision on a dense SPD matrix of 200 equations with eigenvalues 1 .. 1e9
  !! (A = Q diag(lambda) Q, Q a Householder reflection): kappa = 1e9, so the single-precision
  !! copy of its factor alone may put the solution off by kappa u = 60. (A grid's Laplacian,
  !! even of two materials 1e8 apart, stays within 1e-5: Cholesky of such matrices is
  !! accurate well beyond its condition number.) The test solve must find the error above
  !! mixed_tolerance and keep the factor in double precision: the third solve equals the
  !! double solver's bit for bit.
  subroutine test_mixed_fallback(error)
    type(error_t), allocatable, intent(out) :: error
    type(cholmod_solver_t) :: solver, reference
    type(csr_matrix_t) :: a
    real(dp), allocatable :: b(:), x(:), x_double(:), v(:), lambda(:)
    integer, parameter :: n = 200
    integer :: i, j, k
    v = [(sin(1.7_dp * k) + 0.1_dp, k = 1, n)]
    v = v / norm2(v)
    lambda = [(10.0_dp**(9.0_dp * (k - 1) / (n - 1)), k = 1, n)]
    a = dense_to_csr(reshape([((entry(i, j), i = 1, n), j = 1, n)], [n, n]))
    b = [(cos(0.3_dp * k), k = 1, n)]
    solver = cholmod_solver_t(mixed=.true.)
    call analyze_and_factorize(reference, a, error)
    if (allocated(error)) return
    x_double = b
    call reference%solve(x_double, error)
    if (allocated(error)) return
    call analyze_and_factorize(solver, a, error)
    do k = 1, 3
      if (allocated(error)) return
      x = b
      call solver%solve(x, error)
    end do
    if (allocated(error)) return
    call check(error, solver%precision_fallbacks, 1, 'the factor kept in double precision; test solve ' // &
               str(solver%mixed_error))
    if (allocated(error)) return
    call check(error, solver%lower_precision_factors, 0, 'no factor solved in single precision')
    if (allocated(error)) return
    call check(error, all(x == x_double), 'the third solve is the double one, bit for bit')
  contains
    !> (Q diag(lambda) Q)_ij with Q = I - 2 v v^T.
    pure real(dp) function entry(i, j)
      integer, intent(in) :: i, j
      real(dp) :: qi(n), qj(n)
      qi = -2.0_dp * v(i) * v
      qi(i) = qi(i) + 1.0_dp
      qj = -2.0_dp * v(j) * v
      qj(j) = qj(j) + 1.0_dp
      entry = sum(qi * lambda * qj)
    end function entry
  end subroutine test_mixed_fallback

  !> Solve inside a parallel region of two threads (one of them solving), where nested regions
  !! get one thread: every share of the tree must still be solved.
  subroutine solve_inside_a_region(solver, x, error)
    type(cholmod_solver_t), intent(inout) :: solver
    real(dp), intent(inout) :: x(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: levels
    levels = omp_get_max_active_levels()
    call omp_set_max_active_levels(1)
    !$omp parallel num_threads(2) shared(solver, x, error)
    !$omp single
    call solver%solve(x, error)
    !$omp end single
    !$omp end parallel
    call omp_set_max_active_levels(levels)
  end subroutine solve_inside_a_region

end module test_cholmod
