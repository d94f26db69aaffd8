!> C interfaces to the UMFPACK shim (feps_umfpack_shim.c). The C side owns the UMFPACK
!! objects behind an opaque handle.
module feps_umfpack_bindings
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_int32_t, c_int64_t, c_double
  implicit none
  private

  public :: feps_umf_create, feps_umf_free, feps_umf_factorize, feps_umf_solve, feps_umf_status, feps_umf_flops, &
            feps_umf_rcond, feps_umf_determinant_sign

  !> Return codes of factorize and solve (must match the enum in the shim).
  integer(c_int), parameter, public :: umf_ok = 0          !! success
  integer(c_int), parameter, public :: umf_bad_input = 1   !! invalid sizes or pattern
  integer(c_int), parameter, public :: umf_singular = 2    !! a zero pivot
  integer(c_int), parameter, public :: umf_error = 3       !! UMFPACK failed; see status
  integer(c_int), parameter, public :: umf_not_ready = 4   !! no valid factorization

  interface
    !> New handle; c_null_ptr if out of memory.
    function feps_umf_create() result(handle) bind(C, name="feps_umf_create")
      import :: c_ptr
      type(c_ptr) :: handle
    end function feps_umf_create

    !> Free the handle and everything it holds; a null handle is ignored.
    subroutine feps_umf_free(handle) bind(C, name="feps_umf_free")
      import :: c_ptr
      type(c_ptr), value :: handle
    end subroutine feps_umf_free

    !> Factorize the full n x n matrix given in 1-based compressed rows.
    function feps_umf_factorize(handle, n, row_ptr, col, val) result(code) bind(C, name="feps_umf_factorize")
      import :: c_ptr, c_int, c_int32_t, c_int64_t, c_double
      type(c_ptr), value :: handle
      integer(c_int64_t), value :: n
      integer(c_int64_t), intent(in) :: row_ptr(*)
      integer(c_int32_t), intent(in) :: col(*)
      real(c_double), intent(in) :: val(*)
      integer(c_int) :: code
    end function feps_umf_factorize

    !> Solve A x = b in place.
    function feps_umf_solve(handle, b) result(code) bind(C, name="feps_umf_solve")
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      real(c_double), intent(inout) :: b(*)
      integer(c_int) :: code
    end function feps_umf_solve

    !> UMFPACK's status of the last call.
    function feps_umf_status(handle) result(status) bind(C, name="feps_umf_status")
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int) :: status
    end function feps_umf_status

    !> UMFPACK's reciprocal condition estimate (min / max |diag(U)|) of the last factorization.
    function feps_umf_rcond(handle) result(rcond) bind(C, name="feps_umf_rcond")
      import :: c_ptr, c_double
      type(c_ptr), value :: handle
      real(c_double) :: rcond
    end function feps_umf_rcond

    !> The sign of the last factorization's determinant: +1, -1, or 0 where UMFPACK gave none.
    function feps_umf_determinant_sign(handle) result(sign) bind(C, name="feps_umf_determinant_sign")
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int) :: sign
    end function feps_umf_determinant_sign

    !> Floating-point operations of the last numeric factorization.
    function feps_umf_flops(handle) result(flops) bind(C, name="feps_umf_flops")
      import :: c_ptr, c_double
      type(c_ptr), value :: handle
      real(c_double) :: flops
    end function feps_umf_flops
  end interface

end module feps_umfpack_bindings
