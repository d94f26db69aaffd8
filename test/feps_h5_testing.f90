!> Helpers the tests share to read results files: scratch paths, HDF5 datasets and attributes
!! (with the HDF5 Fortran API, independently of feps's writer), and text files.
module feps_h5_testing
  use feps_kinds, only: dp, i8
  use feps_testing, only: error_t, test_failed
  use feps_program, only: run_options_t, run_summary_t, run_feps
  use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5fopen_f, h5fclose_f, H5F_ACC_RDONLY_F, &
                  h5dopen_f, h5dread_f, h5dclose_f, h5dget_space_f, h5sget_simple_extent_ndims_f, &
                  h5sget_simple_extent_dims_f, h5sclose_f, h5aopen_by_name_f, h5aread_f, h5aclose_f, &
                  h5aget_type_f, h5tget_size_f, h5tcopy_f, h5tset_size_f, h5tclose_f, H5T_FORTRAN_S1, &
                  H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, h5kind_to_type, H5_INTEGER_KIND
  use, intrinsic :: iso_c_binding, only: c_loc, c_ptr
  implicit none
  private

  public :: run_and_open, close_and_delete
  public :: scratch_path, open_read, dataset_dims, read_real, read_int, string_attribute, real_attribute, &
            int_attribute, int64_attribute, file_exists, delete_file, file_text, occurrences

contains

  !> Run `deck` quietly into the scratch file `stem`.h5 (with --fields `fields` when given) and
  !! open the result for reading.
  subroutine run_and_open(deck, stem, file_id, error, fields)
    character(len=*), intent(in) :: deck, stem
    integer(hid_t), intent(out) :: file_id
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: fields
    type(run_options_t) :: options
    type(run_summary_t) :: summary
    options%deck = deck
    options%output = scratch_path(stem // '.h5')
    options%quiet = .true.
    if (present(fields)) options%fields = fields
    call run_feps(options, summary, error)
    if (allocated(error)) return
    call open_read(options%output, file_id, error)
  end subroutine run_and_open

  !> Close a result of run_and_open and delete it and its XDMF file.
  subroutine close_and_delete(file_id, stem)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: stem
    integer :: hdferr
    call h5fclose_f(file_id, hdferr)
    call delete_file(scratch_path(stem // '.h5'))
    call delete_file(scratch_path(stem // '.xmf'))
  end subroutine close_and_delete

  !> A scratch file name: under build/ when run from the package root, else /tmp.
  function scratch_path(name) result(path)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: path
    logical :: exists
    inquire (file='build/.', exist=exists)
    if (exists) then
      path = 'build/feps_test_' // name
    else
      path = '/tmp/feps_test_' // name
    end if
  end function scratch_path

  !> Open an HDF5 file read-only (test_failed if it cannot be opened).
  subroutine open_read(path, file_id, error)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: file_id
    type(error_t), allocatable, intent(out) :: error
    integer :: hdferr
    call h5open_f(hdferr)
    call h5fopen_f(path, H5F_ACC_RDONLY_F, file_id, hdferr)
    if (hdferr < 0) call test_failed(error, 'cannot open ' // path // ' for reading')
  end subroutine open_read

  !> Fortran-order dimensions of a rank-2 dataset (h5py shows them reversed).
  subroutine dataset_dims(file_id, path, dims, error)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: path
    integer(hsize_t), intent(out) :: dims(2)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: dataset_id, space_id
    integer(hsize_t) :: maxdims(2)
    integer :: hdferr, rank
    dims = 0
    call h5dopen_f(file_id, path, dataset_id, hdferr)
    if (hdferr < 0) then
      call test_failed(error, 'no dataset ' // path)
      return
    end if
    call h5dget_space_f(dataset_id, space_id, hdferr)
    call h5sget_simple_extent_ndims_f(space_id, rank, hdferr)
    if (rank == 2) call h5sget_simple_extent_dims_f(space_id, dims, maxdims, hdferr)
    call h5sclose_f(space_id, hdferr)
    call h5dclose_f(dataset_id, hdferr)
    if (rank /= 2) call test_failed(error, path // ' is not rank 2')
  end subroutine dataset_dims

  !> A rank-2 double dataset, in Fortran order (h5py shows it transposed).
  subroutine read_real(file_id, path, values, error)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: path
    real(dp), allocatable, intent(out) :: values(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(hsize_t) :: dims(2)
    integer(hid_t) :: dataset_id
    integer :: hdferr
    call dataset_dims(file_id, path, dims, error)
    if (allocated(error)) return
    allocate (values(dims(1), dims(2)))
    call h5dopen_f(file_id, path, dataset_id, hdferr)
    call h5dread_f(dataset_id, H5T_NATIVE_DOUBLE, values, dims, hdferr)
    call h5dclose_f(dataset_id, hdferr)
  end subroutine read_real

  !> A rank-2 integer dataset, in Fortran order.
  subroutine read_int(file_id, path, values, error)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: path
    integer, allocatable, intent(out) :: values(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(hsize_t) :: dims(2)
    integer(hid_t) :: dataset_id
    integer :: hdferr
    call dataset_dims(file_id, path, dims, error)
    if (allocated(error)) return
    allocate (values(dims(1), dims(2)))
    call h5dopen_f(file_id, path, dataset_id, hdferr)
    call h5dread_f(dataset_id, H5T_NATIVE_INTEGER, values, dims, hdferr)
    call h5dclose_f(dataset_id, hdferr)
  end subroutine read_int

  !> String attribute `name` of the object `object` (trailing nulls removed; '?' when absent).
  function string_attribute(file_id, object, name) result(value)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: object, name
    character(len=:), allocatable :: value
    integer(hid_t) :: attribute_id, file_type, memory_type
    integer(size_t) :: length
    integer(hsize_t) :: dims(1)
    integer :: hdferr, last
    value = '?'
    call h5aopen_by_name_f(file_id, object, name, attribute_id, hdferr)
    if (hdferr < 0) return
    call h5aget_type_f(attribute_id, file_type, hdferr)
    call h5tget_size_f(file_type, length, hdferr)
    call h5tclose_f(file_type, hdferr)
    call h5tcopy_f(H5T_FORTRAN_S1, memory_type, hdferr)
    call h5tset_size_f(memory_type, length, hdferr)
    deallocate (value)
    allocate (character(len=length) :: value)
    dims = 1
    call h5aread_f(attribute_id, memory_type, value, dims, hdferr)
    call h5tclose_f(memory_type, hdferr)
    call h5aclose_f(attribute_id, hdferr)
    last = len(value)
    do while (last > 0)
      if (value(last:last) /= achar(0)) exit
      last = last - 1
    end do
    value = value(:last)
  end function string_attribute

  !> Real attribute `name` of `object` (-huge when absent).
  function real_attribute(file_id, object, name) result(value)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: object, name
    real(dp) :: value
    integer(hid_t) :: attribute_id
    integer(hsize_t) :: dims(1)
    integer :: hdferr
    value = -huge(1.0_dp)
    dims = 1
    call h5aopen_by_name_f(file_id, object, name, attribute_id, hdferr)
    if (hdferr < 0) return
    call h5aread_f(attribute_id, H5T_NATIVE_DOUBLE, value, dims, hdferr)
    call h5aclose_f(attribute_id, hdferr)
  end function real_attribute

  !> Integer attribute `name` of `object` (-huge when absent).
  function int_attribute(file_id, object, name) result(value)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: object, name
    integer :: value
    integer(hid_t) :: attribute_id
    integer(hsize_t) :: dims(1)
    integer :: hdferr
    value = -huge(1)
    dims = 1
    call h5aopen_by_name_f(file_id, object, name, attribute_id, hdferr)
    if (hdferr < 0) return
    call h5aread_f(attribute_id, H5T_NATIVE_INTEGER, value, dims, hdferr)
    call h5aclose_f(attribute_id, hdferr)
  end function int_attribute

  !> 64-bit integer attribute `name` of `object` (-huge when absent).
  function int64_attribute(file_id, object, name) result(value)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: object, name
    integer(i8) :: value
    integer(i8), target :: buffer
    integer(hid_t) :: attribute_id
    integer :: hdferr
    type(c_ptr) :: pointer
    buffer = -huge(1_i8)
    pointer = c_loc(buffer)
    call h5aopen_by_name_f(file_id, object, name, attribute_id, hdferr)
    if (hdferr >= 0) then
      call h5aread_f(attribute_id, h5kind_to_type(i8, H5_INTEGER_KIND), pointer, hdferr)
      call h5aclose_f(attribute_id, hdferr)
    end if
    value = buffer
  end function int64_attribute

  !> Whether a file exists.
  logical function file_exists(path)
    character(len=*), intent(in) :: path
    inquire (file=path, exist=file_exists)
  end function file_exists

  !> Delete a file if it exists.
  subroutine delete_file(path)
    character(len=*), intent(in) :: path
    integer :: unit, ios
    if (.not. file_exists(path)) return
    open (newunit=unit, file=path, status='old', iostat=ios)
    if (ios == 0) close (unit, status='delete')
  end subroutine delete_file

  !> The whole text of a file, lines joined by new lines ('' if it cannot be read).
  function file_text(path) result(text)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: text
    character(len=1000) :: line
    integer :: unit, ios
    text = ''
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      text = text // trim(line) // new_line('a')
    end do
    close (unit)
  end function file_text

  !> Times `pattern` occurs in `text`.
  pure function occurrences(text, pattern) result(n)
    character(len=*), intent(in) :: text, pattern
    integer :: n, start, at
    n = 0
    start = 1
    do
      at = index(text(start:), pattern)
      if (at == 0) exit
      n = n + 1
      start = start + at - 1 + len(pattern)
    end do
  end function occurrences

end module feps_h5_testing
