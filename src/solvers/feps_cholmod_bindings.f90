!> C interfaces to the CHOLMOD shim (feps_cholmod_shim.c). The C side owns all CHOLMOD
!! state behind an opaque handle; nothing of cholmod_common is mirrored here.
!! Column numbers returned by the shim are original (unpermuted) and 1-based.
module feps_cholmod_bindings
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_int32_t, c_int64_t, c_double
  implicit none
  private

  public :: feps_chol_create, feps_chol_free, feps_chol_analyze, feps_chol_factorize, feps_chol_solve
  public :: feps_chol_multiply
  public :: feps_chol_flops, feps_chol_lnz, feps_chol_status, feps_chol_failed_column
  public :: feps_chol_min_ratio, feps_chol_max_ratio, feps_chol_min_ratio_column
  public :: feps_chol_supervariables, feps_chol_count_supervariables, feps_chol_supernodes

  !> Return codes of analyze, factorize and solve (must match the enum in the shim).
  integer(c_int), parameter, public :: chol_ok = 0            !! success
  integer(c_int), parameter, public :: chol_bad_input = 1     !! invalid pattern or sizes
  integer(c_int), parameter, public :: chol_not_posdef = 2    !! a pivot <= 0; see failed_column
  integer(c_int), parameter, public :: chol_cholmod_error = 3 !! CHOLMOD failed; see status
  integer(c_int), parameter, public :: chol_not_ready = 4     !! no analysis or no valid factor

  interface
    !> New handle (supernodal, METIS ordering of the supervariable graph, silent); c_null_ptr if out of memory.
    function feps_chol_create() result(handle) bind(C, name="feps_chol_create")
      import :: c_ptr
      type(c_ptr) :: handle
    end function feps_chol_create

    !> Free the handle and everything it holds; a null handle is ignored.
    subroutine feps_chol_free(handle) bind(C, name="feps_chol_free")
      import :: c_ptr
      type(c_ptr), value :: handle
    end subroutine feps_chol_free

    !> Keep the pattern (lower triangle CSR, 1-based, diagonal last in each row) and analyse it.
    function feps_chol_analyze(handle, n, row_ptr, col) result(code) bind(C, name="feps_chol_analyze")
      import :: c_ptr, c_int, c_int32_t, c_int64_t
      type(c_ptr), value :: handle
      integer(c_int64_t), value :: n
      integer(c_int64_t), intent(in) :: row_ptr(*)
      integer(c_int32_t), intent(in) :: col(*)
      integer(c_int) :: code
    end function feps_chol_analyze

    !> Numerical factorization with the values in the order of the analysed pattern.
    function feps_chol_factorize(handle, val) result(code) bind(C, name="feps_chol_factorize")
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      real(c_double), intent(in) :: val(*)
      integer(c_int) :: code
    end function feps_chol_factorize

    !> y = A x with the matrix last factorized.
    function feps_chol_multiply(handle, n, x, y) result(code) bind(C, name="feps_chol_multiply")
      import :: c_ptr, c_int64_t, c_double, c_int
      type(c_ptr), value :: handle
      integer(c_int64_t), value :: n
      real(c_double), intent(in) :: x(*)
      real(c_double), intent(inout) :: y(*)
      integer(c_int) :: code
    end function feps_chol_multiply

    !> Solve A x = b in place; b is n x nrhs, column-major.
    function feps_chol_solve(handle, n, nrhs, b) result(code) bind(C, name="feps_chol_solve")
      import :: c_ptr, c_int, c_int64_t, c_double
      type(c_ptr), value :: handle
      integer(c_int64_t), value :: n, nrhs
      real(c_double), intent(inout) :: b(*)
      integer(c_int) :: code
    end function feps_chol_solve

    !> LL' flop count of the last analysis.
    function feps_chol_flops(handle) result(flops) bind(C, name="feps_chol_flops")
      import :: c_ptr, c_double
      type(c_ptr), value :: handle
      real(c_double) :: flops
    end function feps_chol_flops

    !> Nonzeros in L (with diagonal, without supernodal padding) of the last analysis.
    function feps_chol_lnz(handle) result(lnz) bind(C, name="feps_chol_lnz")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: handle
      integer(c_int64_t) :: lnz
    end function feps_chol_lnz

    !> CHOLMOD's Common->status after the last call.
    function feps_chol_status(handle) result(status) bind(C, name="feps_chol_status")
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int) :: status
    end function feps_chol_status

    !> Equation whose pivot was <= 0 in the last factorization (original, 1-based), or 0.
    function feps_chol_failed_column(handle) result(column) bind(C, name="feps_chol_failed_column")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: handle
      integer(c_int64_t) :: column
    end function feps_chol_failed_column

    !> Smallest L_jj**2 / A_jj of the last factorization (0 if it failed).
    function feps_chol_min_ratio(handle) result(ratio) bind(C, name="feps_chol_min_ratio")
      import :: c_ptr, c_double
      type(c_ptr), value :: handle
      real(c_double) :: ratio
    end function feps_chol_min_ratio

    !> Largest L_jj**2 / A_jj of the last factorization.
    function feps_chol_max_ratio(handle) result(ratio) bind(C, name="feps_chol_max_ratio")
      import :: c_ptr, c_double
      type(c_ptr), value :: handle
      real(c_double) :: ratio
    end function feps_chol_max_ratio

    !> Equation of the smallest ratio (original, 1-based).
    function feps_chol_min_ratio_column(handle) result(column) bind(C, name="feps_chol_min_ratio_column")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: handle
      integer(c_int64_t) :: column
    end function feps_chol_min_ratio_column

    !> Vertices of the supervariable graph METIS ordered in the last analysis; 0 when the
    !! analysis fell back to CHOLMOD's own METIS ordering of the full graph.
    function feps_chol_supervariables(handle) result(count) bind(C, name="feps_chol_supervariables")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: handle
      integer(c_int64_t) :: count
    end function feps_chol_supervariables

    !> The numeric supernodal LL' factor's arrays (CHOLMOD's L->super, pi, px, s, x and Perm,
    !! 0-based): 1 with the pointers set, 0 when the factor is not supernodal (or absent).
    function feps_chol_supernodes(handle, nsuper, super, pi, px, rows, x, perm) result(found) &
        bind(C, name="feps_chol_supernodes")
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value :: handle
      integer(c_int64_t), intent(out) :: nsuper
      type(c_ptr), intent(out) :: super, pi, px, rows, x, perm
      integer(c_int) :: found
    end function feps_chol_supernodes

    !> Number of groups of equations with identical pattern (row and column, diagonal included)
    !! of a lower triangle CSR pattern; -1 if the pattern is invalid, -2 if out of memory.
    function feps_chol_count_supervariables(n, row_ptr, col) result(count) &
        bind(C, name="feps_chol_count_supervariables")
      import :: c_int32_t, c_int64_t
      integer(c_int64_t), value :: n
      integer(c_int64_t), intent(in) :: row_ptr(*)
      integer(c_int32_t), intent(in) :: col(*)
      integer(c_int64_t) :: count
    end function feps_chol_count_supervariables
  end interface

end module feps_cholmod_bindings
