!> Wall-clock time for the run's timings.
module feps_clock
  use feps_kinds, only: dp, i8
  implicit none
  private

  public :: wall_clock

contains

  !> Seconds since an arbitrary origin.
  real(dp) function wall_clock()
    integer(i8) :: count, rate
    call system_clock(count, rate)
    wall_clock = real(count, dp) / real(rate, dp)
  end function wall_clock

end module feps_clock
