!> File-name conventions that the input checks and the output follows, so that neither layer
!! has to ask the other.
module feps_paths
  use feps_strings, only: to_lower
  implicit none
  private

  public :: is_xdmf_name, xdmf_file_name, restart_file_name, meshio_file_name

contains

  !> True when a results file name ends in '.xmf' (any letter case): the XDMF file written beside
  !! the results is named `<name without extension>.xmf` and would replace them (or, on a
  !! case-insensitive file system, be the same file).
  pure logical function is_xdmf_name(path)
    character(len=*), intent(in) :: path
    integer :: n
    n = len_trim(path)
    is_xdmf_name = .false.
    if (n >= 4) is_xdmf_name = to_lower(path(n - 3:n)) == '.xmf'
  end function is_xdmf_name

  !> The XDMF file beside the results file `path`: its extension replaced by '.xmf', or '.xmf'
  !! appended (a dot that starts the file name, a hidden file, is no extension). The program
  !! checks this path before a run; the output writes it.
  pure function xdmf_file_name(path) result(xdmf)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: xdmf
    integer :: slash, dot
    slash = index(path, '/', back=.true.)
    dot = index(path, '.', back=.true.)
    if (dot > slash + 1) then
      xdmf = path(:dot - 1) // '.xmf'
    else
      xdmf = path // '.xmf'
    end if
  end function xdmf_file_name

  !> The checkpoint file beside the results file `path` (RESTART, --restart-every): its
  !! extension replaced by '.restart.h5', or '.restart.h5' appended, as for the XDMF file.
  pure function restart_file_name(path) result(restart)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: restart
    integer :: slash, dot
    slash = index(path, '/', back=.true.)
    dot = index(path, '.', back=.true.)
    if (dot > slash + 1) then
      restart = path(:dot - 1) // '.restart.h5'
    else
      restart = path // '.restart.h5'
    end if
  end function restart_file_name
  !> The XDMF file for meshio beside the results file `path`: the name of its XDMF file with
  !! '.meshio.xdmf' for '.xmf' (`run.h5` -> `run.meshio.xdmf`), which no results name can take
  !! (that of `run.meshio.xdmf` is `run.meshio.meshio.xdmf`).
  pure function meshio_file_name(path) result(meshio)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: meshio
    meshio = xdmf_file_name(path)
    meshio = meshio(:len(meshio) - 4) // '.meshio.xdmf'
  end function meshio_file_name

end module feps_paths
