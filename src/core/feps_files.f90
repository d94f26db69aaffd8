!> What feps asks the operating system about files and memory (C shim feps_files_shim.c): the
!! kind of a path, so that only regular files are read as input (a FIFO blocks at open, a
!! device such as /dev/zero never ends, a directory reads as an empty file); whether a folder
!! takes new files, so that result paths are checked before a run; the removal of regular
!! files only, so that feps never removes a directory; and the memory a process may use.
module feps_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_int64_t, c_null_char
  use feps_kinds, only: i8
  implicit none
  private

  public :: file_kind, file_kind_text, folder_writable, remove_regular_file, memory_limit_bytes, folder_of

  integer, parameter, public :: file_missing = 0     !! no such file
  integer, parameter, public :: file_regular = 1     !! a regular file (or a link to one)
  integer, parameter, public :: file_directory = 2   !! a directory
  integer, parameter, public :: file_special = 3     !! a FIFO, a device or a socket
  integer, parameter, public :: file_unknown = 4     !! cannot be looked at (permissions, a dangling link)

  interface
    function c_file_kind(path) result(kind) bind(C, name='feps_file_kind')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: kind
    end function c_file_kind
    function c_folder_writable(path) result(ok) bind(C, name='feps_folder_writable')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: ok
    end function c_folder_writable
    function c_remove_regular(path) result(status) bind(C, name='feps_remove_regular')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int) :: status
    end function c_remove_regular
    function c_memory_limit() result(bytes) bind(C, name='feps_memory_limit')
      import :: c_int64_t
      integer(c_int64_t) :: bytes
    end function c_memory_limit
  end interface

contains

  !> The kind of `path` (following links): file_missing, file_regular, file_directory,
  !! file_special or file_unknown.
  integer function file_kind(path)
    character(len=*), intent(in) :: path
    file_kind = int(c_file_kind(path // c_null_char))
  end function file_kind

  !> What a path of that kind is, for messages: 'it is a directory', ...
  pure function file_kind_text(kind) result(text)
    integer, intent(in) :: kind
    character(len=:), allocatable :: text
    select case (kind)
    case (file_missing)
      text = 'no such file'
    case (file_regular)
      text = 'it is a regular file'
    case (file_directory)
      text = 'it is a directory'
    case (file_special)
      text = 'it is not a regular file (a FIFO, a device or a socket)'
    case default
      text = 'it cannot be looked at (permissions, or a link to nothing)'
    end select
  end function file_kind_text

  !> True when a new file can be created in the folder `path` ('' for the working directory).
  logical function folder_writable(path)
    character(len=*), intent(in) :: path
    if (len(path) == 0) then
      folder_writable = c_folder_writable('.' // c_null_char) /= 0
    else
      folder_writable = c_folder_writable(path // c_null_char) /= 0
    end if
  end function folder_writable

  !> Remove `path` if it is a regular file (a link to one: the link); never a directory or
  !! anything else. True when it was removed.
  logical function remove_regular_file(path)
    character(len=*), intent(in) :: path
    remove_regular_file = c_remove_regular(path // c_null_char) == 0
  end function remove_regular_file

  !> Bytes this process may allocate at most: the smaller of its address-space limit (ulimit
  !! -v) and the machine's physical memory; -1 when neither is known.
  integer(i8) function memory_limit_bytes()
    memory_limit_bytes = int(c_memory_limit(), i8)
  end function memory_limit_bytes

  !> The folder part of a path ('' for a bare name in the working directory, '/' for the root).
  pure function folder_of(path) result(folder)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: folder
    integer :: slash
    slash = index(path, '/', back=.true.)
    if (slash == 0) then
      folder = ''
    else if (slash == 1) then
      folder = '/'
    else
      folder = path(:slash - 1)
    end if
  end function folder_of

end module feps_files
