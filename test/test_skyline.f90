!> Tests of the reverse Cuthill-McKee ordering and the skyline LDL^T solver.
module test_skyline
  use feps_kinds, only: dp, i8
  use feps_error, only: err_model, str
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_ordering, only: reverse_cuthill_mckee, profile_size
  use feps_skyline_solver, only: skyline_solver_t
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  implicit none
  private

  public :: collect_skyline

contains

  subroutine collect_skyline(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("laplacian_2d_solve", test_laplacian_2d), &
      new_unittest("laplacian_3d_solve", test_laplacian_3d), &
      new_unittest("irregular_sparse_solve", test_irregular), &
      new_unittest("rcm_profile_shuffled_grid", test_rcm_grid), &
      new_unittest("rcm_shuffled_path_is_banded", test_rcm_path), &
      new_unittest("rcm_hand_worked_tree", test_rcm_hand), &
      new_unittest("profile_size_int64", test_profile_int64), &
      new_unittest("refactorize_scaled_matrix", test_refactorize), &
      new_unittest("singular_free_free_bar", test_singular_bar), &
      new_unittest("negative_diagonal_named", test_negative_diagonal), &
      new_unittest("disconnected_components", test_disconnected), &
      new_unittest("tridiagonal_counts", test_tridiagonal_counts), &
      new_unittest("dense_counts", test_dense_counts), &
      new_unittest("name_and_misuse", test_name_and_misuse) &
    ]
  end subroutine collect_skyline

  ! ---------------------------------------------------------------- tests

  !> 5-point Laplacian (Dirichlet) on 30x30: x within 1e-10 relative (max norm).
  subroutine test_laplacian_2d(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: a
    a = grid_laplacian_2d(30, 4.0_dp)
    call check_solve(a, 1.0e-10_dp, error)
  end subroutine test_laplacian_2d

  !> 7-point Laplacian (Dirichlet) on 8x8x8: x within 1e-10 relative (max norm).
  subroutine test_laplacian_3d(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: a
    a = grid_laplacian_3d(8, 6.0_dp)
    call check_solve(a, 1.0e-10_dp, error)
  end subroutine test_laplacian_3d

  !> Irregular pattern (ragged skyline, column heights not monotone): 400 equations, each tied
  !! to 3 random earlier ones with weights in (-1, 0]; the diagonal (1 + sum of |row|) makes it
  !! strictly diagonally dominant, hence SPD. x within 1e-10 relative.
  subroutine test_irregular(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 400, ties = 3
    integer :: rows(n * (ties + 1)), cols(n * (ties + 1)), i, t, k, other
    real(dp) :: vals(n * (ties + 1)), row_sum(n)
    integer, allocatable :: pick(:)
    integer(i8) :: state

    state = 2024
    row_sum = 0.0_dp
    k = 0
    do i = 2, n
      pick = random_permutation(i - 1, i * 7919)
      do t = 1, min(ties, i - 1)
        other = pick(t)
        k = k + 1
        state = modulo(state * 48271_i8, 2147483647_i8)
        rows(k) = i
        cols(k) = other
        vals(k) = -real(state, dp) / 2147483647.0_dp
        row_sum(i) = row_sum(i) + abs(vals(k))
        row_sum(other) = row_sum(other) + abs(vals(k))
      end do
    end do
    do i = 1, n
      k = k + 1
      rows(k) = i
      cols(k) = i
      vals(k) = 1.0_dp + row_sum(i)
    end do
    call check_solve(from_triplets(n, rows(1:k), cols(1:k), vals(1:k)), 1.0e-10_dp, error)
  end subroutine test_irregular

  !> 20x20 grid numbered randomly. Natural (row by row) profile in closed form:
  !! m(m-1)(m+1) + 2(m-1) + 1 = 8019 for m = 20. Checked bound: RCM profile < natural profile
  !! <= n (m + 1), i.e. no worse than the band of the bandwidth-optimal ordering (bandwidth m),
  !! and >= n (m + 1) / 4, i.e. of the same order of magnitude; RCM < random profile.
  !! The root found by the George-Liu search must be a grid corner (degree 2).
  subroutine test_rcm_grid(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: m = 20, n = m * m
    type(csr_matrix_t) :: grid, shuffled
    integer, allocatable :: shuffle(:), unshuffle(:), perm(:), iperm(:), identity(:)
    integer(i8) :: natural, random, rcm
    integer :: k

    grid = grid_laplacian_2d(m, 4.0_dp)
    shuffle = random_permutation(n, 12345)
    allocate (unshuffle(n))
    unshuffle(shuffle) = [(k, k=1, n)]
    shuffled = permuted_matrix(grid, unshuffle)  ! grid node shuffle(k) becomes node k
    identity = [(k, k=1, n)]

    natural = profile_size(shuffled, shuffle)     ! node k -> its grid number shuffle(k)
    call check(error, natural == int(m * (m - 1) * (m + 1) + 2 * (m - 1) + 1, i8), &
               'natural profile ' // str(int(natural)) // ' against closed form 8019')
    if (allocated(error)) return
    call check(error, profile_size(grid, identity) == natural, 'profile independent of labels')
    if (allocated(error)) return
    random = profile_size(shuffled, identity)

    call reverse_cuthill_mckee(shuffled, perm, iperm)
    call check_permutation(perm, iperm, error)
    if (allocated(error)) return
    rcm = profile_size(shuffled, iperm)
    call check(error, rcm < natural, 'RCM profile ' // str(int(rcm)) // ' < natural ' // str(int(natural)))
    if (allocated(error)) return
    call check(error, rcm < random, 'RCM profile ' // str(int(rcm)) // ' < random ' // str(int(random)))
    if (allocated(error)) return
    call check(error, 4 * rcm >= int(n * (m + 1), i8) .and. rcm <= int(n * (m + 1), i8), &
               'RCM profile ' // str(int(rcm)) // ' within [1/4, 1] n(m+1)')
    if (allocated(error)) return
    ! Reversed Cuthill-McKee: the root is numbered last.
    call check(error, row_degree(shuffled, perm(n)), 2, 'degree of the pseudo-peripheral root')
  end subroutine test_rcm_grid

  !> A path numbered randomly: RCM recovers bandwidth 1, profile 2n - 1 exactly.
  subroutine test_rcm_path(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 50
    type(csr_matrix_t) :: path, shuffled
    integer, allocatable :: perm(:), iperm(:)

    path = tridiagonal(n, 2.0_dp, -1.0_dp)
    shuffled = permuted_matrix(path, random_permutation(n, 777))
    call reverse_cuthill_mckee(shuffled, perm, iperm)
    call check_permutation(perm, iperm, error)
    if (allocated(error)) return
    call check(error, int(profile_size(shuffled, iperm)), 2 * n - 1, 'RCM profile of a path')
  end subroutine test_rcm_path

  !> Tree 5-4-2-1-3-6 with leaves 7 (on 4) and 8 (on 1), worked by hand. Seed 1: levels
  !! {1}{2,3,8}{4,6}{5,7}; min-degree last-level node 5 has 6 levels, more than 4, so go on to
  !! 6 (last level of 5), which has 6 levels too: root 6. Cuthill-McKee from 6: 6, 3, 1, then
  !! 1's neighbours by increasing degree 8 (1) before 2 (2), then 4, then 5, 7 (tie: index).
  !! Reversed: perm = [7, 5, 4, 2, 8, 1, 3, 6].
  subroutine test_rcm_hand(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: expected(8) = [7, 5, 4, 2, 8, 1, 3, 6]
    type(csr_matrix_t) :: tree
    integer, allocatable :: perm(:), iperm(:)
    integer :: k

    tree = from_triplets(8, [2, 3, 4, 5, 6, 7, 8, [(k, k=1, 8)]], [1, 1, 2, 4, 3, 4, 1, [(k, k=1, 8)]], &
                         [[(-1.0_dp, k=1, 7)], [(4.0_dp, k=1, 8)]])
    call reverse_cuthill_mckee(tree, perm, iperm)
    call check_permutation(perm, iperm, error)
    if (allocated(error)) return
    do k = 1, 8
      call check(error, perm(k), expected(k), 'perm(' // str(k) // ')')
      if (allocated(error)) return
    end do
  end subroutine test_rcm_hand

  !> Star with n = 70000 (node 1 tied to all): profile n(n+1)/2 = 2 450 035 000 > 2^31 in
  !! the natural order; RCM puts the centre last but one: 2n - 1.
  subroutine test_profile_int64(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 70000
    type(csr_matrix_t) :: star
    integer, allocatable :: perm(:), iperm(:)
    integer(i8) :: entries
    integer :: i

    allocate (star%row_ptr(n + 1), star%col(2 * n - 1), star%val(2 * n - 1))
    star%n = n
    star%row_ptr(1) = 1
    star%row_ptr(2) = 2
    star%col(1) = 1
    do i = 2, n
      star%row_ptr(i + 1) = star%row_ptr(i) + 2
      star%col(2 * i - 2:2 * i - 1) = [1, i]
    end do
    star%val = 1.0_dp
    entries = profile_size(star, [(i, i=1, n)])
    call check(error, entries == int(n, i8) * int(n + 1, i8) / 2, 'natural profile of the star: ' // &
               str(real(entries, dp)))
    if (allocated(error)) return
    call reverse_cuthill_mckee(star, perm, iperm)
    call check(error, int(profile_size(star, iperm)), 2 * n - 1, 'RCM profile of the star')
  end subroutine test_profile_int64

  !> Refactorizing with 2A halves the solution (relative 1e-13), and counts factorizations.
  subroutine test_refactorize(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: a
    type(skyline_solver_t) :: solver
    real(dp), allocatable :: b(:), x1(:), x2(:)

    a = grid_laplacian_2d(12, 4.0_dp)
    call solver%analyze(a, error)
    if (allocated(error)) return
    call solver%factorize(a, error)
    if (allocated(error)) return
    b = test_vector(a%n)
    x1 = b
    call solver%solve(x1, error)
    if (allocated(error)) return
    a%val = 2.0_dp * a%val
    call solver%factorize(a, error)
    if (allocated(error)) return
    x2 = b
    call solver%solve(x2, error)
    if (allocated(error)) return
    call check(error, maxval(abs(2.0_dp * x2 - x1)) / maxval(abs(x1)), 0.0_dp, 'x(2A) = x(A)/2', &
               abs=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, solver%factorizations, 2, 'factorizations')
  end subroutine test_refactorize

  !> Free-free bar of 10 springs (11 equations, one rigid mode): err_model, item in 1..n,
  !! the item named in the message, no NaN, and solve refuses to run.
  subroutine test_singular_bar(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 11
    type(csr_matrix_t) :: a
    type(skyline_solver_t) :: solver
    type(error_t), allocatable :: failure
    real(dp), allocatable :: stiffness(:), b(:)
    integer :: e

    stiffness = [(1.0_dp + 0.37_dp * e, e=1, n - 1)]
    a = spring_chain(stiffness)
    call solver%analyze(a, error)
    if (allocated(error)) return
    call solver%factorize(a, failure)
    call check(error, allocated(failure), 'singular bar must fail')
    if (allocated(error)) return
    call check(error, failure%code, err_model, 'error code')
    if (allocated(error)) return
    call check(error, failure%item >= 1 .and. failure%item <= n, 'item in 1..n: ' // str(failure%item))
    if (allocated(error)) return
    call check(error, index(failure%message, 'equation ' // str(failure%item)) > 0, &
               'message names the equation: ' // failure%message)
    if (allocated(error)) return
    call check(error, index(failure%message, 'NaN') == 0 .and. index(failure%message, 'Inf') == 0, &
               'no NaN/Inf in message: ' // failure%message)
    if (allocated(error)) return
    call check(error, solver%min_pivot_ratio == solver%min_pivot_ratio .and. &
               solver%min_pivot_ratio <= 1.0e-11_dp, 'min pivot ratio finite and below tolerance')
    if (allocated(error)) return
    b = test_vector(n)
    call solver%solve(b, failure)
    call check(error, allocated(failure), 'solve after a failed factorization must fail')
    if (allocated(error)) return
    call check(error, all(b == test_vector(n)), 'b untouched by a refused solve')
  end subroutine test_singular_bar

  !> 6x6 grid with diagonal 5 (strictly dominant) except a(17,17) = -1: every principal
  !! submatrix without 17 is positive definite, so the failure names equation 17.
  subroutine test_negative_diagonal(error)
    type(error_t), allocatable, intent(out) :: error
    type(csr_matrix_t) :: a
    type(skyline_solver_t) :: solver
    type(error_t), allocatable :: failure

    a = grid_laplacian_2d(6, 5.0_dp)
    a%val(a%row_ptr(18) - 1) = -1.0_dp
    call solver%analyze(a, error)
    if (allocated(error)) return
    call solver%factorize(a, failure)
    call check(error, allocated(failure), 'negative diagonal must fail')
    if (allocated(error)) return
    call check(error, failure%code, err_model, 'error code')
    if (allocated(error)) return
    call check(error, failure%item, 17, 'failing equation')
    if (allocated(error)) return
    call check(error, index(failure%message, 'equation 17 ') > 0, 'message names 17: ' // failure%message)
  end subroutine test_negative_diagonal

  !> Block diagonal: a 5x5 grid, a path of 7 and three isolated equations, labels shuffled.
  !! Solution within 1e-12; the profile is at most the sum of natural profiles
  !! (5*4*6 + 2*4 + 1 = 129, 2*7 - 1 = 13, 3) = 145 and at least 25 + 13 + 3.
  subroutine test_disconnected(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 25 + 7 + 3
    type(csr_matrix_t) :: grid, path, blocks
    integer, allocatable :: rows(:), cols(:)
    real(dp), allocatable :: vals(:)
    type(skyline_solver_t) :: solver
    integer :: i
    integer(i8) :: k

    grid = grid_laplacian_2d(5, 4.0_dp)
    path = tridiagonal(7, 3.0_dp, -1.0_dp)
    allocate (rows(0), cols(0), vals(0))
    do i = 1, 25
      do k = grid%row_ptr(i), grid%row_ptr(i + 1) - 1
        rows = [rows, i]
        cols = [cols, grid%col(k)]
        vals = [vals, grid%val(k)]
      end do
    end do
    do i = 1, 7
      do k = path%row_ptr(i), path%row_ptr(i + 1) - 1
        rows = [rows, 25 + i]
        cols = [cols, 25 + path%col(k)]
        vals = [vals, path%val(k)]
      end do
    end do
    rows = [rows, 33, 34, 35]
    cols = [cols, 33, 34, 35]
    vals = [vals, 2.0_dp, 5.0_dp, 7.0_dp]
    blocks = permuted_matrix(from_triplets(n, rows, cols, vals), random_permutation(n, 4242))

    call check_solve(blocks, 1.0e-12_dp, error, solver)
    if (allocated(error)) return
    call check(error, solver%factor_nnz <= 145_i8 .and. solver%factor_nnz >= 41_i8, &
               'profile of the blocks: ' // str(int(solver%factor_nnz)))
  end subroutine test_disconnected

  !> Tridiagonal (2, -1), n = 40: profile 2n - 1 = 79, flops 3(n - 1) = 117 (per off-diagonal
  !! entry one division and one multiply-add, no inner products), pivots d_k = (k+1)/k so
  !! min pivot ratio (n+1)/(2n) = 41/80 and max 1.
  subroutine test_tridiagonal_counts(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 40
    type(skyline_solver_t) :: solver

    call check_solve(tridiagonal(n, 2.0_dp, -1.0_dp), 1.0e-12_dp, error, solver)
    if (allocated(error)) return
    call check(error, int(solver%factor_nnz), 2 * n - 1, 'factor_nnz')
    if (allocated(error)) return
    call check(error, solver%flops, real(3 * (n - 1), dp), 'flops', abs=0.0_dp)
    if (allocated(error)) return
    call check(error, solver%min_pivot_ratio, real(n + 1, dp) / real(2 * n, dp), 'min pivot ratio', &
               rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, solver%max_pivot_ratio, 1.0_dp, 'max pivot ratio', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, solver%factorizations, 1, 'factorizations')
  end subroutine test_tridiagonal_counts

  !> Dense n = 20 (n + 2 on the diagonal, 1 elsewhere): profile n(n+1)/2 = 210; column j does
  !! inner products of lengths 0 .. j-2 and j-1 scalings, so flops
  !! sum_j sum_{i<j} (2(i-1) + 3) = sum_j (j^2 - 1) = n(n+1)(2n+1)/6 - n = 2850, whatever the
  !! ordering.
  subroutine test_dense_counts(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: n = 20
    type(skyline_solver_t) :: solver
    integer :: rows(n * (n + 1) / 2), cols(n * (n + 1) / 2), i, j, k

    k = 0
    do i = 1, n
      do j = 1, i
        k = k + 1
        rows(k) = i
        cols(k) = j
      end do
    end do
    call check_solve(from_triplets(n, rows, cols, merge(real(n + 2, dp), 1.0_dp, rows == cols)), &
                     1.0e-13_dp, error, solver)
    if (allocated(error)) return
    call check(error, int(solver%factor_nnz), n * (n + 1) / 2, 'factor_nnz')
    if (allocated(error)) return
    call check(error, solver%flops, real(n * (n + 1) * (2 * n + 1) / 6 - n, dp), 'flops', abs=0.0_dp)
  end subroutine test_dense_counts

  !> Name, and errors for solve before factorize and for a wrong right-hand side length.
  subroutine test_name_and_misuse(error)
    type(error_t), allocatable, intent(out) :: error
    type(skyline_solver_t) :: solver
    type(error_t), allocatable :: failure
    type(csr_matrix_t) :: a
    real(dp) :: b(5)

    call check(error, solver%name() == 'skyline', 'name')
    if (allocated(error)) return
    b = 1.0_dp
    call solver%solve(b, failure)
    call check(error, allocated(failure), 'solve before factorize must fail')
    if (allocated(error)) return
    a = tridiagonal(4, 2.0_dp, -1.0_dp)
    call solver%factorize(a, failure)
    call check(error, allocated(failure), 'factorize before analyze must fail')
    if (allocated(error)) return
    call solver%analyze(a, error)
    if (allocated(error)) return
    call solver%factorize(a, error)
    if (allocated(error)) return
    call solver%solve(b, failure)
    call check(error, allocated(failure), 'wrong length of b must fail')
  end subroutine test_name_and_misuse

  ! ---------------------------------------------------------------- helpers

  !> Analyse, factorize and solve A x = A x_true; max|x - x_true| / max|x_true| <= tol.
  subroutine check_solve(a, tol, error, solver_out)
    type(csr_matrix_t), intent(in) :: a
    real(dp), intent(in) :: tol
    type(error_t), allocatable, intent(out) :: error
    type(skyline_solver_t), intent(out), optional :: solver_out
    type(skyline_solver_t) :: solver
    real(dp), allocatable :: x_true(:), x(:)

    x_true = test_vector(a%n)
    allocate (x(a%n))
    call a%multiply(x_true, x)
    call solver%analyze(a, error)
    if (allocated(error)) return
    call solver%factorize(a, error)
    if (allocated(error)) return
    call solver%solve(x, error)
    if (allocated(error)) return
    call check(error, maxval(abs(x - x_true)) / maxval(abs(x_true)), 0.0_dp, 'relative error of x', abs=tol)
    if (present(solver_out)) solver_out = solver
  end subroutine check_solve

  pure function test_vector(n) result(x)
    integer, intent(in) :: n
    real(dp) :: x(n)
    integer :: i
    x = [(1.0_dp + sin(real(i, dp)), i=1, n)]
  end function test_vector

  subroutine check_permutation(perm, iperm, error)
    integer, intent(in) :: perm(:), iperm(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: k
    call check(error, size(perm) == size(iperm) .and. all(perm >= 1 .and. perm <= size(perm)), 'perm range')
    if (allocated(error)) return
    call check(error, all([(iperm(perm(k)) == k, k=1, size(perm))]), 'iperm inverts perm')
  end subroutine check_permutation

  !> Off-diagonal entries of row/column i of the symmetric matrix.
  pure integer function row_degree(a, i) result(degree)
    type(csr_matrix_t), intent(in) :: a
    integer, intent(in) :: i
    integer :: r
    integer(i8) :: k
    degree = 0
    do r = 1, a%n
      do k = a%row_ptr(r), a%row_ptr(r + 1) - 1
        if (a%col(k) == r) cycle
        if (r == i .or. a%col(k) == i) degree = degree + 1
      end do
    end do
  end function row_degree

  !> Lower-triangle CSR from triplets (either triangle, no duplicates).
  pure function from_triplets(n, rows, cols, vals) result(a)
    integer, intent(in) :: n, rows(:), cols(:)
    real(dp), intent(in) :: vals(:)
    type(csr_matrix_t) :: a
    integer, allocatable :: fill(:)
    integer :: e, r, c, p, q, ctmp
    real(dp) :: vtmp

    a%n = n
    allocate (a%row_ptr(n + 1), a%col(size(rows)), a%val(size(rows)), fill(n))
    fill = 0
    do e = 1, size(rows)
      r = max(rows(e), cols(e))
      fill(r) = fill(r) + 1
    end do
    a%row_ptr(1) = 1
    do r = 1, n
      a%row_ptr(r + 1) = a%row_ptr(r) + fill(r)
    end do
    fill = int(a%row_ptr(1:n))
    do e = 1, size(rows)
      r = max(rows(e), cols(e))
      c = min(rows(e), cols(e))
      a%col(fill(r)) = c
      a%val(fill(r)) = vals(e)
      fill(r) = fill(r) + 1
    end do
    do r = 1, n
      do p = int(a%row_ptr(r)) + 1, int(a%row_ptr(r + 1)) - 1
        ctmp = a%col(p)
        vtmp = a%val(p)
        q = p - 1
        do while (q >= a%row_ptr(r))
          if (a%col(q) <= ctmp) exit
          a%col(q + 1) = a%col(q)
          a%val(q + 1) = a%val(q)
          q = q - 1
        end do
        a%col(q + 1) = ctmp
        a%val(q + 1) = vtmp
      end do
    end do
  end function from_triplets

  !> B with b(new(i), new(j)) = a(i, j).
  pure function permuted_matrix(a, new) result(b)
    type(csr_matrix_t), intent(in) :: a
    integer, intent(in) :: new(:)
    type(csr_matrix_t) :: b
    integer, allocatable :: rows(:), cols(:)
    integer :: i
    integer(i8) :: k

    allocate (rows(a%nnz()), cols(a%nnz()))
    do i = 1, a%n
      do k = a%row_ptr(i), a%row_ptr(i + 1) - 1
        rows(k) = new(i)
        cols(k) = new(a%col(k))
      end do
    end do
    b = from_triplets(a%n, rows, cols, a%val)
  end function permuted_matrix

  !> Fisher-Yates shuffle driven by the minimal-standard Lehmer generator (reproducible).
  pure function random_permutation(n, seed) result(p)
    integer, intent(in) :: n, seed
    integer :: p(n)
    integer(i8) :: state
    integer :: i, j, t
    p = [(i, i=1, n)]
    state = int(seed, i8)
    do i = n, 2, -1
      state = modulo(state * 48271_i8, 2147483647_i8)
      j = 1 + int(modulo(state, int(i, i8)))
      t = p(i)
      p(i) = p(j)
      p(j) = t
    end do
  end function random_permutation

  !> Tridiagonal matrix, `diag` on the diagonal and `off` beside it.
  pure function tridiagonal(n, diag, off) result(a)
    integer, intent(in) :: n
    real(dp), intent(in) :: diag, off
    type(csr_matrix_t) :: a
    integer :: i
    integer(i8) :: k
    a%n = n
    allocate (a%row_ptr(n + 1), a%col(2 * n - 1), a%val(2 * n - 1))
    a%row_ptr(1) = 1
    k = 0
    do i = 1, n
      if (i > 1) then
        k = k + 1
        a%col(k) = i - 1
        a%val(k) = off
      end if
      k = k + 1
      a%col(k) = i
      a%val(k) = diag
      a%row_ptr(i + 1) = k + 1
    end do
  end function tridiagonal

  !> Stiffness of a chain of springs with free ends: n = size(stiffness) + 1 equations.
  pure function spring_chain(stiffness) result(a)
    real(dp), intent(in) :: stiffness(:)
    type(csr_matrix_t) :: a
    integer :: i, n
    integer(i8) :: k
    n = size(stiffness) + 1
    a%n = n
    allocate (a%row_ptr(n + 1), a%col(2 * n - 1), a%val(2 * n - 1))
    a%row_ptr(1) = 1
    k = 0
    do i = 1, n
      if (i > 1) then
        k = k + 1
        a%col(k) = i - 1
        a%val(k) = -stiffness(i - 1)
      end if
      k = k + 1
      a%col(k) = i
      a%val(k) = 0.0_dp
      if (i > 1) a%val(k) = a%val(k) + stiffness(i - 1)
      if (i < n) a%val(k) = a%val(k) + stiffness(i)
      a%row_ptr(i + 1) = k + 1
    end do
  end function spring_chain

  !> 5-point stencil on an m x m grid numbered row by row: `diag` on the diagonal, -1 off.
  function grid_laplacian_2d(m, diag) result(a)
    integer, intent(in) :: m
    real(dp), intent(in) :: diag
    type(csr_matrix_t) :: a
    a = grid_laplacian(m, m, 1, diag)
  end function grid_laplacian_2d

  !> 7-point stencil on an m x m x m grid numbered lexicographically.
  function grid_laplacian_3d(m, diag) result(a)
    integer, intent(in) :: m
    real(dp), intent(in) :: diag
    type(csr_matrix_t) :: a
    a = grid_laplacian(m, m, m, diag)
  end function grid_laplacian_3d

  !> Lower triangle (CSR) of the nearest-neighbour stencil on an nx x ny x nz grid numbered
  !! x fastest: `diag` on the diagonal, -1 to each lower neighbour.
  function grid_laplacian(nx, ny, nz, diag) result(a)
    integer, intent(in) :: nx, ny, nz
    real(dp), intent(in) :: diag
    type(csr_matrix_t) :: a
    integer :: x, y, z, node
    integer(i8) :: k
    a%n = nx * ny * nz
    allocate (a%row_ptr(a%n + 1), a%col(4 * a%n), a%val(4 * a%n))
    a%row_ptr(1) = 1
    k = 0
    do z = 1, nz
      do y = 1, ny
        do x = 1, nx
          node = ((z - 1) * ny + (y - 1)) * nx + x
          if (z > 1) call add(node - nx * ny, -1.0_dp)
          if (y > 1) call add(node - nx, -1.0_dp)
          if (x > 1) call add(node - 1, -1.0_dp)
          call add(node, diag)
          a%row_ptr(node + 1) = k + 1
        end do
      end do
    end do
    a%col = a%col(1:k)
    a%val = a%val(1:k)
  contains
    subroutine add(column, value)
      integer, intent(in) :: column
      real(dp), intent(in) :: value
      k = k + 1
      a%col(k) = column
      a%val(k) = value
    end subroutine add
  end function grid_laplacian

end module test_skyline
