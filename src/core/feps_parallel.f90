!> The ranks of an element-partitioned run (issue 29, the MPI build): which rank this is, and
!! the collectives that join the ranks' pieces (feps_parallel_shim.c). Every rank runs the same
!! analysis on the same replicated vectors and owns a block of each group's elements; these
!! calls sum the ranks' internal forces, exchange the point-state blocks and pass on rank 0's
!! errors. Without MPI (the default build) there is one rank and every call is a no-op.
module feps_parallel
  use, intrinsic :: iso_c_binding, only: c_int, c_int32_t, c_int64_t, c_double
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error
  implicit none
  private

  public :: parallel_rank, parallel_ranks, sum_over_ranks, min_over_ranks, any_rank
  public :: gather_blocks, broadcast_from_root, share_root_error, silence_output, peak_memory_mb

  interface
    integer(c_int) function feps_par_rank() bind(C, name='feps_par_rank')
      import :: c_int
    end function feps_par_rank
    integer(c_int) function feps_par_size() bind(C, name='feps_par_size')
      import :: c_int
    end function feps_par_size
    subroutine feps_par_sum(x, n) bind(C, name='feps_par_sum')
      import :: c_double, c_int64_t
      real(c_double), intent(inout) :: x(*)
      integer(c_int64_t), value :: n
    end subroutine feps_par_sum
    subroutine feps_par_min_int(x, n) bind(C, name='feps_par_min_int')
      import :: c_int32_t, c_int64_t
      integer(c_int32_t), intent(inout) :: x(*)
      integer(c_int64_t), value :: n
    end subroutine feps_par_min_int
    integer(c_int) function feps_par_gather_real(x, counts, displs) bind(C, name='feps_par_gather_real')
      import :: c_int, c_double, c_int64_t
      real(c_double), intent(inout) :: x(*)
      integer(c_int64_t), intent(in) :: counts(*), displs(*)
    end function feps_par_gather_real
    integer(c_int) function feps_par_any(flag) bind(C, name='feps_par_any')
      import :: c_int
      integer(c_int), value :: flag
    end function feps_par_any
    subroutine feps_par_from_root(v, n) bind(C, name='feps_par_from_root')
      import :: c_int, c_int32_t
      integer(c_int32_t), intent(inout) :: v(*)
      integer(c_int), value :: n
    end subroutine feps_par_from_root
    subroutine feps_par_silence() bind(C, name='feps_par_silence')
    end subroutine feps_par_silence
    real(c_double) function feps_par_peak_memory_mb() bind(C, name='feps_par_peak_memory_mb')
      import :: c_double
    end function feps_par_peak_memory_mb
  end interface

contains

  !> This process's rank (0 without MPI).
  integer function parallel_rank()
    parallel_rank = int(feps_par_rank())
  end function parallel_rank

  !> The number of ranks (1 without MPI).
  integer function parallel_ranks()
    parallel_ranks = int(feps_par_size())
  end function parallel_ranks

  !> x(1:n) <- the sum over the ranks of x(1:n), the same bits on every rank (summed on rank 0
  !! and sent back). Any contiguous real array (sequence association).
  subroutine sum_over_ranks(x, n)
    real(dp), intent(inout) :: x(*)
    integer(i8), intent(in) :: n
    call feps_par_sum(x, int(n, c_int64_t))
  end subroutine sum_over_ranks

  !> x(1:n) <- the smallest over the ranks of x(1:n).
  subroutine min_over_ranks(x, n)
    integer, intent(inout) :: x(*)
    integer(i8), intent(in) :: n
    call feps_par_min_int(x, int(n, c_int64_t))
  end subroutine min_over_ranks

  !> Whether `flag` holds on any rank.
  logical function any_rank(flag)
    logical, intent(in) :: flag
    any_rank = feps_par_any(merge(1_c_int, 0_c_int, flag)) /= 0
  end function any_rank

  !> Every rank gets every rank's block of x: rank r's is x(displs(r+1)+1 : displs(r+1)+counts(r+1)).
  !! The values are copied, not summed. A block is at most 2**31 - 1 values (the caller checks:
  !! MPI's counts are int; beyond, the shim stops every rank, naming the reason).
  subroutine gather_blocks(x, counts, displs)
    real(dp), intent(inout) :: x(*)
    integer(i8), intent(in) :: counts(:), displs(:)
    integer(c_int) :: code
    code = feps_par_gather_real(x, int(counts, c_int64_t), int(displs, c_int64_t))
  end subroutine gather_blocks

  !> Every rank gets rank 0's v.
  subroutine broadcast_from_root(v)
    integer, intent(inout) :: v(:)
    call feps_par_from_root(v, int(size(v), c_int))
  end subroutine broadcast_from_root

  !> After a step only rank 0 takes (writing the results): every rank takes rank 0's verdict,
  !! so that all of them stop at the same place; the other ranks' error carries rank 0's code
  !! (rank 0 prints the message).
  subroutine share_root_error(error)
    type(error_t), allocatable, intent(inout) :: error
    integer(c_int32_t) :: word(2)
    if (feps_par_size() < 2) return
    word = 0
    if (allocated(error)) word = [1_c_int32_t, int(error%code, c_int32_t)]
    call feps_par_from_root(word, 2_c_int)
    if (word(1) /= 0 .and. .not. allocated(error)) then
      call fatal_error(error, int(word(2)), 'rank 0 failed (its message is the run''s)')
    else if (word(1) == 0 .and. allocated(error)) then
      deallocate (error)   ! rank 0's verdict is the run's: the other ranks write nothing
    end if
  end subroutine share_root_error

  !> This process's largest resident memory so far (MB; 0 where the system does not say).
  function peak_memory_mb() result(mb)
    real(dp) :: mb
    mb = real(feps_par_peak_memory_mb(), dp)
  end function peak_memory_mb

  !> The ranks above 0 print nothing (feps_parallel_shim.c): rank 0's lines are the run's.
  subroutine silence_output()
    if (feps_par_rank() > 0) call feps_par_silence()
  end subroutine silence_output

end module feps_parallel
