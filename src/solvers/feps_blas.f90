!> The BLAS feps runs on, as one line (feps_blas_shim.c): OpenBLAS's version, the kernels it
!! chose for this CPU and its threads, or that the BLAS is another one.
module feps_blas
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  implicit none
  private

  public :: blas_description

  interface
    subroutine feps_blas_describe(buf, len) bind(C, name="feps_blas_describe")
      import :: c_char, c_int
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value :: len
    end subroutine feps_blas_describe
  end interface

contains

  !> 'OpenBLAS 0.3.21, SkylakeX kernels, 2 threads (solves on 1)', or 'not OpenBLAS (...)'.
  function blas_description() result(text)
    character(len=:), allocatable :: text
    character(kind=c_char) :: buf(400)
    integer :: n
    buf = c_null_char
    call feps_blas_describe(buf, size(buf, kind=c_int))
    n = 0
    do while (n < size(buf))
      if (buf(n + 1) == c_null_char) exit
      n = n + 1
    end do
    allocate (character(len=n) :: text)
    text = transfer(buf(:n), text)
  end function blas_description

end module feps_blas
