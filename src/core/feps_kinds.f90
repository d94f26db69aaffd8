!> Kinds and a few mathematical constants used everywhere in feps.
module feps_kinds
  use, intrinsic :: iso_fortran_env, only: real32, real64, int64, int32
  implicit none
  private

  integer, parameter, public :: dp = real64   !! working real kind
  integer, parameter, public :: sp = real32   !! single precision (a factor's copy for mixed-precision solves)
  integer, parameter, public :: i8 = int64    !! long integers (sparse pointers, flop counts)
  integer, parameter, public :: i4 = int32

  real(dp), parameter, public :: pi = 3.14159265358979323846264338327950288_dp
  real(dp), parameter, public :: deg2rad = pi / 180.0_dp
  real(dp), parameter, public :: rad2deg = 180.0_dp / pi
end module feps_kinds
