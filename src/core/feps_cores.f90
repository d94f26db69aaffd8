!> The cores a run may take by default: those of this machine that nothing else is using when
!! it starts (feps_cores_shim.c reads /proc/stat). A waiting OpenMP thread whose core another
!! process holds slows every parallel region down (FE1 twofold on 2 cores, docs/performance.md),
!! so the default counts only the cores idle at the start (a process that starts later is not
!! seen).
module feps_cores
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  private

  public :: idle_cores

  interface
    integer(c_int) function feps_other_running(readings) bind(C, name='feps_other_running')
      import :: c_int
      integer(c_int), value :: readings
    end function feps_other_running
  end interface

  !> Readings of the running threads, 10 ms apart; the least counts.
  integer, parameter :: readings = 5

contains

  !> Of `cores` cores, those no other process is running on: cores less the threads of other
  !! processes running or ready to run (the least of 5 readings over 40 ms); at least 1, and
  !! all of them where the machine's load cannot be read.
  integer function idle_cores(cores)
    integer, intent(in) :: cores
    integer :: others
    others = int(feps_other_running(int(readings, c_int)))
    if (others < 0) then
      idle_cores = max(1, cores)
    else
      idle_cores = max(1, min(cores, cores - others))
    end if
  end function idle_cores

end module feps_cores
