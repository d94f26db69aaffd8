!> The program's version, one place for the command, the results files and the mesh-only mode.
module feps_version
  implicit none
  private

  character(len=*), parameter, public :: feps_release = '0.1.0'   !! as in fpm.toml
end module feps_version
