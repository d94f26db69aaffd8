!> What feps asks the operating system about files and memory (C shim feps_files_shim.c): the
!! kind of a path, so that only regular files are read as input (a FIFO blocks at open, a
!! device such as /dev/zero never ends, a directory reads as an empty file); whether a folder
!! takes new files, so that result paths are checked before a run; the removal of regular
!! files only, so that feps never removes a directory; the memory a process may use; and text
!! files written through C stdio (`text_file_t`), whose write errors are reported: gfortran's
!! formatted WRITE, FLUSH and CLOSE report none when the disk is full.
module feps_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_int64_t, c_null_char, c_ptr, c_null_ptr, c_associated
  use feps_kinds, only: i8
  implicit none
  private

  public :: report_file_size_limit, mark_partial_file, file_kind, file_kind_text, folder_writable, remove_regular_file, &
            memory_limit_bytes, folder_of

  integer, parameter, public :: file_missing = 0     !! no such file
  integer, parameter, public :: file_regular = 1     !! a regular file (or a link to one)
  integer, parameter, public :: file_directory = 2   !! a directory
  integer, parameter, public :: file_special = 3     !! a FIFO, a device or a socket
  integer, parameter, public :: file_unknown = 4     !! cannot be looked at (permissions, a dangling link)

  !> A text file being written line by line; `status` keeps the first failure (an errno), after
  !! which nothing more is written. Always `close` it: that flushes, and reports a full disk.
  type, public :: text_file_t
    private
    type(c_ptr) :: handle = c_null_ptr
    integer :: status = 0
  contains
    procedure :: open => text_open        !! create or truncate the file
    procedure :: write => text_write      !! one line (a newline added)
    procedure :: close => text_close      !! flush, sync and close; the first failure's text, or ''
  end type text_file_t

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
    function c_text_open(path, status) result(handle) bind(C, name='feps_text_open')
      import :: c_char, c_int, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), intent(out) :: status
      type(c_ptr) :: handle
    end function c_text_open
    function c_text_write(handle, text, length) result(status) bind(C, name='feps_text_write')
      import :: c_char, c_int, c_int64_t, c_ptr
      type(c_ptr), value :: handle
      character(kind=c_char), intent(in) :: text(*)
      integer(c_int64_t), value :: length
      integer(c_int) :: status
    end function c_text_write
    function c_text_close(handle) result(status) bind(C, name='feps_text_close')
      import :: c_int, c_ptr
      type(c_ptr), value :: handle
      integer(c_int) :: status
    end function c_text_close
    subroutine c_mark_partial(slot, path) bind(C, name='feps_mark_partial')
      import :: c_char, c_int
      integer(c_int), value :: slot
      character(kind=c_char), intent(in) :: path(*)
    end subroutine c_mark_partial
    subroutine c_ignore_file_size_signal() bind(C, name='feps_ignore_file_size_signal')
    end subroutine c_ignore_file_size_signal
    subroutine c_error_text(status, buffer, size) bind(C, name='feps_error_text')
      import :: c_char, c_int, c_int64_t
      integer(c_int), value :: status
      character(kind=c_char), intent(out) :: buffer(*)
      integer(c_int64_t), value :: size
    end subroutine c_error_text
  end interface

contains

  !> A write past the file-size limit (ulimit -f) fails with an error that feps reports, instead
  !! of the signal SIGXFSZ killing the program (no message, a partial file left). For the
  !! program to call once at its start (it changes the process's signal disposition).
  subroutine report_file_size_limit()
    call c_ignore_file_size_signal()
  end subroutine report_file_size_limit

  !> Remember the temporary file `path` (slot 1: the results, 2: the XDMF file, 3: meshio's, 4: the restart checkpoint) to be removed
  !! if the process exits while it is there (the Fortran runtime ends a run whose allocation
  !! fails without returning); '' forgets it, once it is renamed or removed.
  subroutine mark_partial_file(slot, path)
    integer, intent(in) :: slot
    character(len=*), intent(in) :: path
    call c_mark_partial(int(slot - 1, c_int), path // c_null_char)
  end subroutine mark_partial_file

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

  !> Create (or truncate) the text file `path`; the failure's text in `message` ('' on success).
  subroutine text_open(self, path, message)
    class(text_file_t), intent(inout) :: self
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: message
    integer(c_int) :: status
    self%handle = c_text_open(path // c_null_char, status)
    self%status = int(status)
    message = ''
    if (self%status /= 0) message = error_text(self%status)
  end subroutine text_open

  !> One line; after the first failure nothing more is written (`close` reports it).
  subroutine text_write(self, line)
    class(text_file_t), intent(inout) :: self
    character(len=*), intent(in) :: line
    if (self%status /= 0 .or. .not. c_associated(self%handle)) return
    self%status = int(c_text_write(self%handle, line, int(len(line), c_int64_t)))
  end subroutine text_write

  !> Flush, sync and close the file; the text of the first failure of any write or of the
  !! close in `message` ('' when all of it is written).
  subroutine text_close(self, message)
    class(text_file_t), intent(inout) :: self
    character(len=:), allocatable, intent(out) :: message
    integer :: status
    message = ''
    if (.not. c_associated(self%handle)) then
      if (self%status /= 0) message = error_text(self%status)
      return
    end if
    status = int(c_text_close(self%handle))
    self%handle = c_null_ptr
    if (self%status == 0) self%status = status
    if (self%status /= 0) message = error_text(self%status)
  end subroutine text_close

  !> The system's text for an errno (strerror).
  function error_text(status) result(text)
    integer, intent(in) :: status
    character(len=:), allocatable :: text
    character(kind=c_char, len=200) :: buffer
    call c_error_text(int(status, c_int), buffer, int(len(buffer), c_int64_t))
    text = trim(buffer)
  end function error_text

end module feps_files
