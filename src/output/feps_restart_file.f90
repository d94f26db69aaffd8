!> The restart checkpoint file (RESTART, --restart-every; docs/output-format.md): HDF5 with
!! `/restart/steps`, the steps it holds, and one group `/restart/step_NNNNNN` per restart
!! point. Each point is added by writing a new file `NAME.part` (the points of the same model
!! before it copied over, then the new one) and renaming it to NAME, so a run killed at any
!! moment leaves the file of its last complete checkpoint. Values are stored as they are in
!! memory (doubles, integers), so a continued run starts from the same bits.
module feps_restart_file
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_io, err_input, err_input_file, str
  use feps_files, only: mark_partial_file, remove_regular_file, file_kind, file_missing, file_regular
  use feps_point_state_store, only: point_state_store_t
  use feps_restart_data, only: restart_data_t, summary_reals, summary_ints, set_summary_scalars
  use hdf5, only: hid_t, hsize_t, h5open_f, h5dont_atexit_f, h5eset_auto_f, h5fcreate_f, h5fopen_f, h5fclose_f, &
                  H5F_ACC_TRUNC_F, H5F_ACC_RDONLY_F, h5gcreate_f, h5gopen_f, h5gclose_f, h5lexists_f, &
                  h5screate_simple_f, h5sclose_f, h5sget_simple_extent_ndims_f, h5sget_simple_extent_dims_f, &
                  h5dcreate_f, h5dopen_f, h5dwrite_f, h5dread_f, h5dclose_f, h5dget_space_f, &
                  H5T_NATIVE_DOUBLE, H5T_NATIVE_INTEGER, h5ocopy_f
  implicit none
  private

  public :: write_restart_point, read_restart_point, restart_steps

  integer, parameter :: n_ints = 17, n_reals = 4

  interface
    function c_rename(old_name, new_name) bind(C, name='rename') result(status)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: old_name(*), new_name(*)
      integer(c_int) :: status
    end function c_rename
  end interface

contains

  !> Name of the group of the restart point of `step`.
  pure function point_name(step) result(name)
    integer, intent(in) :: step
    character(len=:), allocatable :: name
    character(len=12) :: buf
    write (buf, '(i6.6)') step
    name = '/restart/step_' // trim(buf)
  end function point_name

  subroutine start_hdf5(error)
    type(error_t), allocatable, intent(out) :: error
    integer :: hdferr
    call h5dont_atexit_f(hdferr)
    call h5open_f(hdferr)
    if (hdferr < 0) then
      call fatal_error(error, err_io, 'cannot initialise the HDF5 library')
      return
    end if
    call h5eset_auto_f(0, hdferr)
  end subroutine start_hdf5

  !> Add the restart point `data` to the checkpoint file `path`: the points of the same model
  !! (fingerprint) at earlier steps stay, later ones (of a run continued from an earlier
  !! point) and those of another model go; written as `path.part` and renamed.
  subroutine write_restart_point(path, data, error)
    character(len=*), intent(in) :: path
    type(restart_data_t), intent(in) :: data
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: old_id, new_id, gid
    integer :: hdferr, i
    integer, allocatable :: old_steps(:), kept(:), ints(:)
    integer(hsize_t), allocatable :: shp(:)
    character(len=:), allocatable :: part
    logical :: have_old, removed

    call start_hdf5(error)
    if (allocated(error)) return
    part = path // '.part'
    allocate (kept(0))
    have_old = .false.
    if (file_kind(path) == file_regular) then
      call h5fopen_f(path, H5F_ACC_RDONLY_F, old_id, hdferr)
      have_old = hdferr >= 0
      if (have_old) then
        call read_steps(old_id, old_steps, hdferr)
        if (hdferr < 0) allocate (old_steps(0))
      end if
    end if
    call h5fcreate_f(part, H5F_ACC_TRUNC_F, new_id, hdferr)
    if (hdferr < 0) then
      if (have_old) call h5fclose_f(old_id, hdferr)
      call fatal_error(error, err_io, 'cannot create the restart file ' // part)
      return
    end if
    call mark_partial_file(4, part)
    call h5gcreate_f(new_id, '/restart', gid, hdferr)
    if (hdferr >= 0) call h5gclose_f(gid, hdferr)
    if (have_old) then
      do i = 1, size(old_steps)
        if (old_steps(i) >= data%step) cycle
        call get_int(old_id, point_name(old_steps(i)) // '/ints', ints, shp, hdferr)
        if (hdferr < 0) cycle
        if (fingerprint_of(ints) /= data%fingerprint) cycle
        call h5ocopy_f(old_id, point_name(old_steps(i)), new_id, point_name(old_steps(i)), hdferr)
        if (hdferr < 0) exit
        kept = [kept, old_steps(i)]
      end do
      call h5fclose_f(old_id, i)
    end if
    if (hdferr >= 0) call write_point(new_id, data, hdferr)
    if (hdferr >= 0) call put_int(new_id, '/restart/steps', [kept, data%step], [size(kept) + 1], hdferr)
    call h5fclose_f(new_id, i)
    if (hdferr >= 0 .and. i >= 0) then
      if (c_rename(part // c_null_char, path // c_null_char) /= 0) hdferr = -1
    end if
    if (hdferr < 0 .or. i < 0) then
      call fatal_error(error, err_io, 'cannot write the restart file ' // path // ' (step ' // str(data%step) // ')')
      removed = remove_regular_file(part)
    end if
    call mark_partial_file(4, '')
  end subroutine write_restart_point

  !> The fingerprint that the first two integers of a point hold (31 bits each).
  pure integer(i8) function fingerprint_of(ints) result(fp)
    integer, intent(in) :: ints(:)
    fp = ior(ishft(int(ints(1), i8), 31), int(ints(2), i8))
  end function fingerprint_of

  subroutine write_point(fid, data, hdferr)
    integer(hid_t), intent(in) :: fid
    type(restart_data_t), intent(in) :: data
    integer, intent(out) :: hdferr
    character(len=:), allocatable :: g
    integer :: k
    g = point_name(data%step)
    call make_group(fid, g, hdferr)
    if (hdferr < 0) return
    call put_int(fid, g // '/ints', [int(ishft(data%fingerprint, -31)), int(iand(data%fingerprint, 2147483647_i8)), &
                 data%step, data%stage, data%step_in_stage, flag(data%use_lu), flag(data%symmetrized), &
                 flag(data%warned_condition), data%lu_singular, data%solver_factorizations, data%lu_factorizations, &
                 flag(data%factor%have_factor), flag(data%factor%factor_elastic), flag(data%factor%elastic_retry), &
                 data%solves_with_factor, data%lower_precision_factors, data%precision_fallbacks], &
                 [n_ints], hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/reals', [data%lu_min_rcond, data%factor%rel_prev, &
                                   data%factor%abs_prev, data%test_solve_error], [n_reals], hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/summary_reals', summary_reals(data%summary), &
                                   [size(summary_reals(data%summary))], hdferr)
    if (hdferr >= 0) call put_int(fid, g // '/summary_ints', summary_ints(data%summary), &
                                  [size(summary_ints(data%summary))], hdferr)
    if (hdferr >= 0) call put_text(fid, g // '/unbalanced_stage', text_or_empty(data%summary%unbalanced_stage), hdferr)
    if (hdferr >= 0) call put_text(fid, g // '/unbalanced_at', text_or_empty(data%summary%unbalanced_at), hdferr)
    if (hdferr >= 0) call put_text(fid, g // '/run_notes', data%run_notes, hdferr)
    if (hdferr >= 0) call put_nodal(fid, g // '/u', data%u, hdferr)
    if (hdferr >= 0) call put_nodal(fid, g // '/u_t', data%u_t, hdferr)
    if (hdferr >= 0) call put_nodal(fid, g // '/fint', data%fint, hdferr)
    if (hdferr >= 0) call put_nodal(fid, g // '/f_applied', data%f_applied, hdferr)
    if (hdferr >= 0) call put_nodal(fid, g // '/uc', data%uc, hdferr)
    if (hdferr >= 0) call put_nodal(fid, g // '/release_force', data%release_force, hdferr)
    if (hdferr >= 0) call put_int(fid, g // '/active', merge(1, 0, data%active), [size(data%active)], hdferr)
    if (hdferr >= 0) call put_int(fid, g // '/fully_open', merge(1, 0, data%fully_open), [size(data%fully_open)], hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/a_val', data%a_val, [size(data%a_val)], hdferr)
    if (allocated(data%a_full_val) .and. hdferr >= 0) &
      call put_real(fid, g // '/a_full_val', data%a_full_val, [size(data%a_full_val)], hdferr)
    do k = 1, size(data%states)
      if (hdferr < 0) return
      call write_store(fid, g // '/states/' // str(k), data%states(k), hdferr)
    end do
  end subroutine write_point

  !> One group's point states; a group that keeps none gets an empty group.
  subroutine write_store(fid, g, s, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: g
    type(point_state_store_t), intent(in) :: s
    integer, intent(out) :: hdferr
    call make_group(fid, g, hdferr)
    if (hdferr < 0 .or. .not. s%kept()) return
    call put_int(fid, g // '/ints', [s%nvars, flag(s%imposing)], [2], hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/sig', reshape(s%sig, [size(s%sig)]), shape(s%sig), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/eps', reshape(s%eps, [size(s%eps)]), shape(s%eps), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/vars', reshape(s%vars, [size(s%vars)]), shape(s%vars), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/dtan', reshape(s%dtan, [size(s%dtan)]), shape(s%dtan), hdferr)
    if (hdferr >= 0) call put_int(fid, g // '/state', s%state, shape(s%state), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/sig_t', reshape(s%sig_t, [size(s%sig_t)]), shape(s%sig_t), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/eps_t', reshape(s%eps_t, [size(s%eps_t)]), shape(s%eps_t), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/vars_t', reshape(s%vars_t, [size(s%vars_t)]), shape(s%vars_t), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/dtan_t', reshape(s%dtan_t, [size(s%dtan_t)]), shape(s%dtan_t), hdferr)
    if (hdferr >= 0) call put_int(fid, g // '/state_t', s%state_t, shape(s%state_t), hdferr)
    if (hdferr >= 0) call put_real(fid, g // '/imposed', [s%imposed], [1], hdferr)
  end subroutine write_store

  !> The steps the checkpoint file `path` holds restart data of (an input error when it is
  !! missing or holds none).
  subroutine restart_steps(path, steps, error)
    character(len=*), intent(in) :: path
    integer, allocatable, intent(out) :: steps(:)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: fid
    integer :: hdferr, i
    call open_restart(path, fid, error)
    if (allocated(error)) return
    call read_steps(fid, steps, hdferr)
    call h5fclose_f(fid, i)
    if (hdferr < 0) call fatal_error(error, err_input, path // ': holds no restart data (no /restart/steps; ' // &
                                     'a checkpoint file is written by RESTART, EVERY=n or --restart-every n)')
  end subroutine restart_steps

  subroutine open_restart(path, fid, error)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: fid
    type(error_t), allocatable, intent(out) :: error
    integer :: hdferr
    if (file_kind(path) == file_missing) then
      call fatal_error(error, err_input_file, path // ': no such file (--restart)')
      return
    end if
    call start_hdf5(error)
    if (allocated(error)) return
    call h5fopen_f(path, H5F_ACC_RDONLY_F, fid, hdferr)
    if (hdferr < 0) call fatal_error(error, err_input_file, path // ': cannot be read as an HDF5 file (--restart)')
  end subroutine open_restart

  subroutine read_steps(fid, steps, hdferr)
    integer(hid_t), intent(in) :: fid
    integer, allocatable, intent(out) :: steps(:)
    integer, intent(out) :: hdferr
    integer(hsize_t), allocatable :: shp(:)
    logical :: there
    call h5lexists_f(fid, '/restart', there, hdferr)
    if (hdferr >= 0 .and. there) call h5lexists_f(fid, '/restart/steps', there, hdferr)
    if (hdferr < 0 .or. .not. there) then
      hdferr = -1
      return
    end if
    call get_int(fid, '/restart/steps', steps, shp, hdferr)
  end subroutine read_steps

  !> The restart point of `step` (0: the last) of the checkpoint file `path`. Input errors: a
  !! missing or unreadable file, one without restart data, a step it does not hold.
  subroutine read_restart_point(path, step, data, error)
    character(len=*), intent(in) :: path
    integer, intent(in) :: step
    type(restart_data_t), intent(out) :: data
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: fid
    integer :: hdferr, i, k, ng, at
    integer, allocatable :: steps(:), ints(:), nums(:)
    real(dp), allocatable :: reals(:), sr(:)
    integer(hsize_t), allocatable :: shp(:)
    character(len=:), allocatable :: g, list
    logical :: full

    call restart_steps(path, steps, error)
    if (allocated(error)) return
    at = step
    if (at == 0) at = maxval(steps)
    if (.not. any(steps == at)) then
      list = ''
      do i = 1, size(steps)
        if (i > 1) list = list // ' '
        list = list // str(steps(i))
      end do
      call fatal_error(error, err_input, path // ': holds no restart data of step ' // str(at) // &
                       ' (--step; it holds steps ' // list // ')')
      return
    end if
    call open_restart(path, fid, error)
    if (allocated(error)) return
    data%source = path
    g = point_name(at)
    call get_int(fid, g // '/ints', ints, shp, hdferr)
    if (hdferr >= 0) call get_real(fid, g // '/reals', reals, shp, hdferr)
    ! another layout (an older feps's, before the mixed-precision counters) reads as foreign
    if (hdferr >= 0 .and. (size(ints) /= n_ints .or. size(reals) /= n_reals)) hdferr = -1
    if (hdferr >= 0) then
      data%fingerprint = fingerprint_of(ints)
      data%step = ints(3)
      data%stage = ints(4)
      data%step_in_stage = ints(5)
      data%use_lu = ints(6) == 1
      data%symmetrized = ints(7) == 1
      data%warned_condition = ints(8) == 1
      data%lu_singular = ints(9)
      data%solver_factorizations = ints(10)
      data%lu_factorizations = ints(11)
      data%factor%have_factor = ints(12) == 1
      data%factor%factor_elastic = ints(13) == 1
      data%factor%elastic_retry = ints(14) == 1
      data%solves_with_factor = ints(15)
      data%lower_precision_factors = ints(16)
      data%precision_fallbacks = ints(17)
      data%lu_min_rcond = reals(1)
      data%factor%rel_prev = reals(2)
      data%factor%rel_accepted = reals(2)   ! written at the end of an accepted step
      data%factor%abs_prev = reals(3)
      data%test_solve_error = reals(4)
      call get_real(fid, g // '/summary_reals', sr, shp, hdferr)
    end if
    if (hdferr >= 0) call get_int(fid, g // '/summary_ints', nums, shp, hdferr)
    if (hdferr >= 0) call set_summary_scalars(data%summary, sr, nums)
    if (hdferr >= 0) call get_text(fid, g // '/unbalanced_stage', data%summary%unbalanced_stage, hdferr)
    if (hdferr >= 0) call get_text(fid, g // '/unbalanced_at', data%summary%unbalanced_at, hdferr)
    if (hdferr >= 0) call get_text(fid, g // '/run_notes', data%run_notes, hdferr)
    if (hdferr >= 0) call get_nodal(fid, g // '/u', data%u, hdferr)
    if (hdferr >= 0) call get_nodal(fid, g // '/u_t', data%u_t, hdferr)
    if (hdferr >= 0) call get_nodal(fid, g // '/fint', data%fint, hdferr)
    if (hdferr >= 0) call get_nodal(fid, g // '/f_applied', data%f_applied, hdferr)
    if (hdferr >= 0) call get_nodal(fid, g // '/uc', data%uc, hdferr)
    if (hdferr >= 0) call get_nodal(fid, g // '/release_force', data%release_force, hdferr)
    if (hdferr >= 0) call get_int(fid, g // '/active', nums, shp, hdferr)
    if (hdferr >= 0) data%active = nums == 1
    if (hdferr >= 0) call get_int(fid, g // '/fully_open', nums, shp, hdferr)
    if (hdferr >= 0) data%fully_open = nums == 1
    if (hdferr >= 0) call get_real(fid, g // '/a_val', data%a_val, shp, hdferr)
    if (hdferr >= 0) call h5lexists_f(fid, g // '/a_full_val', full, hdferr)
    if (hdferr >= 0 .and. full) call get_real(fid, g // '/a_full_val', data%a_full_val, shp, hdferr)
    ng = 0
    if (hdferr >= 0) ng = size(data%active)
    allocate (data%states(ng))
    do k = 1, ng
      if (hdferr < 0) exit
      call read_store(fid, g // '/states/' // str(k), data%states(k), hdferr)
    end do
    call h5fclose_f(fid, i)
    if (hdferr < 0) call fatal_error(error, err_input_file, path // ': the restart data of step ' // str(at) // &
                                     ' cannot be read (a damaged or foreign file)')
  end subroutine read_restart_point

  subroutine read_store(fid, g, s, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: g
    type(point_state_store_t), intent(inout) :: s
    integer, intent(out) :: hdferr
    integer, allocatable :: ints(:)
    real(dp), allocatable :: x(:)
    integer(hsize_t), allocatable :: shp(:)
    logical :: there
    call h5lexists_f(fid, g // '/ints', there, hdferr)
    if (hdferr < 0 .or. .not. there) return
    call get_int(fid, g // '/ints', ints, shp, hdferr)
    if (hdferr < 0) return
    s%nvars = ints(1)
    s%imposing = ints(2) == 1
    call get_real(fid, g // '/sig', x, shp, hdferr)
    if (hdferr >= 0) s%sig = reshape(x, [int(shp(1)), int(shp(2))])
    if (hdferr >= 0) call get_real(fid, g // '/eps', x, shp, hdferr)
    if (hdferr >= 0) s%eps = reshape(x, [int(shp(1)), int(shp(2))])
    if (hdferr >= 0) call get_real(fid, g // '/vars', x, shp, hdferr)
    if (hdferr >= 0) s%vars = reshape(x, [int(shp(1)), int(shp(2))])
    if (hdferr >= 0) call get_real(fid, g // '/dtan', x, shp, hdferr)
    if (hdferr >= 0) s%dtan = reshape(x, [int(shp(1)), int(shp(2)), int(shp(3))])
    if (hdferr >= 0) call get_int(fid, g // '/state', s%state, shp, hdferr)
    if (hdferr >= 0) call get_real(fid, g // '/sig_t', x, shp, hdferr)
    if (hdferr >= 0) s%sig_t = reshape(x, [int(shp(1)), int(shp(2))])
    if (hdferr >= 0) call get_real(fid, g // '/eps_t', x, shp, hdferr)
    if (hdferr >= 0) s%eps_t = reshape(x, [int(shp(1)), int(shp(2))])
    if (hdferr >= 0) call get_real(fid, g // '/vars_t', x, shp, hdferr)
    if (hdferr >= 0) s%vars_t = reshape(x, [int(shp(1)), int(shp(2))])
    if (hdferr >= 0) call get_real(fid, g // '/dtan_t', x, shp, hdferr)
    if (hdferr >= 0) s%dtan_t = reshape(x, [int(shp(1)), int(shp(2)), int(shp(3))])
    if (hdferr >= 0) call get_int(fid, g // '/state_t', s%state_t, shp, hdferr)
    if (hdferr >= 0) call get_real(fid, g // '/imposed', x, shp, hdferr)
    if (hdferr >= 0 .and. size(x) > 0) s%imposed = x(1)
  end subroutine read_store

  ! ---------------------------------------------------------------------------------------

  pure integer function flag(l)
    logical, intent(in) :: l
    flag = merge(1, 0, l)
  end function flag

  pure function text_or_empty(text) result(t)
    character(len=:), allocatable, intent(in) :: text
    character(len=:), allocatable :: t
    t = ''
    if (allocated(text)) t = text
  end function text_or_empty

  recursive subroutine make_group(fid, name, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    integer, intent(out) :: hdferr
    integer(hid_t) :: gid
    integer :: slash, e
    logical :: there
    slash = index(name, '/', back=.true.)
    if (slash > 1) then
      call h5lexists_f(fid, name(:slash - 1), there, hdferr)
      if (hdferr < 0) return
      if (.not. there) call make_group(fid, name(:slash - 1), hdferr)
      if (hdferr < 0) return
    end if
    call h5gcreate_f(fid, name, gid, hdferr)
    if (hdferr >= 0) call h5gclose_f(gid, e)
  end subroutine make_group

  subroutine put_real(fid, name, x, shp, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: shp(:)
    integer, intent(out) :: hdferr
    integer(hid_t) :: space, dset
    integer(hsize_t) :: dims(size(shp))
    integer :: e
    dims = int(shp, hsize_t)
    call h5screate_simple_f(size(shp), dims, space, hdferr)
    if (hdferr < 0) return
    call h5dcreate_f(fid, name, H5T_NATIVE_DOUBLE, space, dset, hdferr)
    if (hdferr >= 0) then
      if (size(x) > 0) call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, x, dims, hdferr)
      call h5dclose_f(dset, e)
    end if
    call h5sclose_f(space, e)
  end subroutine put_real

  subroutine put_int(fid, name, x, shp, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    integer, intent(in) :: x(:)
    integer, intent(in) :: shp(:)
    integer, intent(out) :: hdferr
    integer(hid_t) :: space, dset
    integer(hsize_t) :: dims(size(shp))
    integer :: e
    dims = int(shp, hsize_t)
    call h5screate_simple_f(size(shp), dims, space, hdferr)
    if (hdferr < 0) return
    call h5dcreate_f(fid, name, H5T_NATIVE_INTEGER, space, dset, hdferr)
    if (hdferr >= 0) then
      if (size(x) > 0) call h5dwrite_f(dset, H5T_NATIVE_INTEGER, x, dims, hdferr)
      call h5dclose_f(dset, e)
    end if
    call h5sclose_f(space, e)
  end subroutine put_int

  !> A text as its character codes (one integer each).
  subroutine put_text(fid, name, text, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: text
    integer, intent(out) :: hdferr
    integer :: i
    call put_int(fid, name, [(ichar(text(i:i)), i = 1, len(text))], [len(text)], hdferr)
  end subroutine put_text

  subroutine put_nodal(fid, name, x, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:, :)
    integer, intent(out) :: hdferr
    call put_real(fid, name, reshape(x, [size(x)]), shape(x), hdferr)
  end subroutine put_nodal

  !> Shape of dataset `dset` (Fortran order) and its element count.
  subroutine data_shape(dset, shp, n, hdferr)
    integer(hid_t), intent(in) :: dset
    integer(hsize_t), allocatable, intent(out) :: shp(:)
    integer, intent(out) :: n, hdferr
    integer(hid_t) :: space
    integer :: rank, e
    integer(hsize_t), allocatable :: maxdims(:)
    n = 0
    call h5dget_space_f(dset, space, hdferr)
    if (hdferr < 0) return
    call h5sget_simple_extent_ndims_f(space, rank, hdferr)
    if (hdferr >= 0) then
      allocate (shp(rank), maxdims(rank))
      call h5sget_simple_extent_dims_f(space, shp, maxdims, hdferr)
      if (hdferr >= 0) then
        hdferr = 0
        n = int(product(shp))
      end if
    end if
    call h5sclose_f(space, e)
  end subroutine data_shape

  subroutine get_real(fid, name, x, shp, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    real(dp), allocatable, intent(out) :: x(:)
    integer(hsize_t), allocatable, intent(out) :: shp(:)
    integer, intent(out) :: hdferr
    integer(hid_t) :: dset
    integer :: n, e
    call h5dopen_f(fid, name, dset, hdferr)
    if (hdferr < 0) return
    call data_shape(dset, shp, n, hdferr)
    if (hdferr >= 0) then
      allocate (x(n))
      if (n > 0) call h5dread_f(dset, H5T_NATIVE_DOUBLE, x, shp, hdferr)
    end if
    call h5dclose_f(dset, e)
  end subroutine get_real

  subroutine get_int(fid, name, x, shp, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    integer, allocatable, intent(out) :: x(:)
    integer(hsize_t), allocatable, intent(out) :: shp(:)
    integer, intent(out) :: hdferr
    integer(hid_t) :: dset
    integer :: n, e
    call h5dopen_f(fid, name, dset, hdferr)
    if (hdferr < 0) return
    call data_shape(dset, shp, n, hdferr)
    if (hdferr >= 0) then
      allocate (x(n))
      if (n > 0) call h5dread_f(dset, H5T_NATIVE_INTEGER, x, shp, hdferr)
    end if
    call h5dclose_f(dset, e)
  end subroutine get_int

  subroutine get_text(fid, name, text, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    character(len=:), allocatable, intent(out) :: text
    integer, intent(out) :: hdferr
    integer, allocatable :: codes(:)
    integer(hsize_t), allocatable :: shp(:)
    integer :: i
    call get_int(fid, name, codes, shp, hdferr)
    if (hdferr < 0) return
    allocate (character(len=size(codes)) :: text)
    do i = 1, size(codes)
      text(i:i) = achar(codes(i))
    end do
  end subroutine get_text

  subroutine get_nodal(fid, name, x, hdferr)
    integer(hid_t), intent(in) :: fid
    character(len=*), intent(in) :: name
    real(dp), allocatable, intent(out) :: x(:, :)
    integer, intent(out) :: hdferr
    real(dp), allocatable :: flat(:)
    integer(hsize_t), allocatable :: shp(:)
    call get_real(fid, name, flat, shp, hdferr)
    if (hdferr < 0) return
    if (size(shp) /= 2) then
      hdferr = -1
      return
    end if
    x = reshape(flat, [int(shp(1)), int(shp(2))])
  end subroutine get_nodal

end module feps_restart_file
