!> The BLAS feps runs on, as one line (feps_blas_shim.c): OpenBLAS's version, the kernels it
!! chose for this CPU and its threads, or that the BLAS is another one.
module feps_blas
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  use feps_kinds, only: dp
  use feps_lapack, only: dgemm
  implicit none
  private

  public :: blas_description, choose_blas_kernels, factorization_threads, set_blas_threads, blas_threads
  public :: take_blas_buffers

  interface
    subroutine feps_blas_describe(buf, len) bind(C, name="feps_blas_describe")
      import :: c_char, c_int
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_int), value :: len
    end subroutine feps_blas_describe
    function feps_blas_choose_kernels() result(status) bind(C, name="feps_blas_choose_kernels")
      import :: c_int
      integer(c_int) :: status
    end function feps_blas_choose_kernels
    subroutine feps_blas_set_threads(n) bind(C, name="feps_blas_set_threads")
      import :: c_int
      integer(c_int), value :: n
    end subroutine feps_blas_set_threads
    function feps_blas_get_threads() result(n) bind(C, name="feps_blas_get_threads")
      import :: c_int
      integer(c_int) :: n
    end function feps_blas_get_threads
  end interface

contains

  !> The most BLAS threads the factorization gets on a machine of `cores` cores: all of them up
  !! to 4, three quarters above. Measured on a 16-core Xeon (docs/performance.md, issue 28): the
  !! 200k mesh factorized in 2.1-2.7 s on 8 or 12 OpenBLAS threads, but in 6 s on 14, 19-21 s
  !! on 15 and 28-33 s on 16, and SE1 in 0.09 s on 8 against 1.8 s on 16: OpenBLAS's threads
  !! wait for each other between the many small supernodal calls, and a thread that shares its
  !! core with anything else holds all of them up. Two threads on two cores measured faster
  !! than one (1.1m mesh, 1.58x).
  pure integer function factorization_threads(cores) result(threads)
    integer, intent(in) :: cores
    if (cores <= 4) then
      threads = max(1, cores)
    else
      threads = (3 * cores) / 4
    end if
  end function factorization_threads

  !> Give OpenBLAS `threads` threads (for the factorization; solves run on one). Nothing with
  !! another BLAS.
  subroutine set_blas_threads(threads)
    integer, intent(in) :: threads
    call feps_blas_set_threads(int(max(1, threads), c_int))
  end subroutine set_blas_threads

  !> OpenBLAS's thread count now (1 with another BLAS).
  integer function blas_threads()
    blas_threads = int(feps_blas_get_threads())
  end function blas_threads

  !> Make OpenBLAS take its work buffers now, with one 256 x 256 dgemm on its threads. OpenBLAS
  !! 0.3.21 takes a buffer of 128 MiB per thread at its first level-3 call and retries an
  !! allocation that fails for ever (FE1 under ulimit -v 430000-450000 hung in CHOLMOD's dpotrf).
  !! Taken right after the memory check found room for them, they are there for the
  !! factorization's calls to reuse, and a factorization short of memory fails where CHOLMOD
  !! allocates (one line, exit 1) instead.
  subroutine take_blas_buffers()
    integer, parameter :: n = 256
    real(dp), allocatable :: a(:, :), c(:, :)
    allocate (a(n, n), c(n, n))
    a = 1.0_dp
    call dgemm('N', 'N', n, n, n, 1.0_dp, a, n, a, n, 0.0_dp, c, n)
  end subroutine take_blas_buffers

  !> Start this program again with the OpenBLAS kernels this CPU runs, when OpenBLAS chose older
  !! ones and the user did not choose (OPENBLAS_CORETYPE). Returns when nothing is to be done or
  !! the new start failed; call it first, before anything is read or written.
  subroutine choose_blas_kernels()
    integer(c_int) :: status
    status = feps_blas_choose_kernels()
  end subroutine choose_blas_kernels

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
