!> Restart (RESTART, --restart): a run stopped after step K and continued from its restart
!! data gives, at every later step, the very bits of the uninterrupted run (displacements,
!! reactions, the interface tractions, the point stresses) and the same summary totals; restart
!! data of another model and a step the file does not hold are refused. The longer decks (FE1,
!! model C, every method, a killed run) are in test/cli/check_restart.sh.
module test_restart
  use feps_kinds, only: dp, i8
  use feps_testing, only: unittest_t, new_unittest, error_t, check, test_failed
  use feps_error, only: err_input, err_solver
  use feps_program, only: run_options_t, run_summary_t, run_feps
  use feps_results_file, only: step_group_name
  use feps_h5_testing, only: scratch_path, open_read, read_real, int64_attribute, file_exists, delete_file
  use hdf5, only: hid_t, h5fclose_f
  implicit none
  private

  public :: collect_restart

contains

  subroutine collect_restart(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('supports changing, modified Newton-Raphson: continued mid-stage is bit-identical', &
                   test_support_change), &
      new_unittest('full Newton-Raphson, line search, LU: continued mid-stage and at the stage boundary', &
                   test_friction), &
      new_unittest('restart data of another model: refused, no results', test_other_model), &
      new_unittest('a step the restart file does not hold: refused', test_missing_step) &
      ]
  end subroutine collect_restart

  !> Run `deck` into stem.h5 with restart data every step; with stop > 0 stop after that step
  !! (the test aid); with a restart file, continue from it (after `step`, 0: the last).
  subroutine run(deck, stem, error, stop, restart, step, summary)
    character(len=*), intent(in) :: deck, stem
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: stop, step
    character(len=*), intent(in), optional :: restart
    type(run_summary_t), intent(out), optional :: summary
    type(run_options_t) :: options
    type(run_summary_t) :: s
    options%deck = deck
    options%output = scratch_path(stem // '.h5')
    options%quiet = .true.
    options%restart_every = 1
    if (present(stop)) options%stop_after_step = stop
    if (present(restart)) options%restart = restart
    if (present(step)) options%restart_step = step
    call run_feps(options, s, error)
    if (present(summary)) summary = s
  end subroutine run

  !> Every step after k of full.h5 and continued.h5: the same fields, bit for bit, and the
  !! summary totals equal.
  subroutine compare_after(full, continued, k, last, fields, error)
    character(len=*), intent(in) :: full, continued
    integer, intent(in) :: k, last
    character(len=*), intent(in) :: fields(:)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: fa, fb
    integer :: n, i, hdferr
    real(dp), allocatable :: a(:, :), b(:, :)
    character(len=*), parameter :: totals(5) = [character(len=17) :: 'steps', 'iterations', 'factorizations', &
                                                'cutbacks', 'lu_factorizations']
    call open_read(scratch_path(full // '.h5'), fa, error)
    if (allocated(error)) return
    call open_read(scratch_path(continued // '.h5'), fb, error)
    if (allocated(error)) return
    outer: do n = k + 1, last
      do i = 1, size(fields)
        call read_real(fa, 'steps/' // step_group_name(n) // '/' // trim(fields(i)), a, error)
        if (allocated(error)) exit outer
        call read_real(fb, 'steps/' // step_group_name(n) // '/' // trim(fields(i)), b, error)
        if (allocated(error)) exit outer
        ! bit for bit: the same shape and every value equal (no NaN in results)
        call check(error, all(shape(a) == shape(b)), 'step ' // step_group_name(n) // ' ' // trim(fields(i)) // &
                   ': shapes differ')
        if (allocated(error)) exit outer
        call check(error, all(a == b), 'step ' // step_group_name(n) // ' ' // trim(fields(i)) // &
                   ': differs from the uninterrupted run')
        if (allocated(error)) exit outer
      end do
    end do outer
    if (.not. allocated(error)) then
      do i = 1, size(totals)
        call check(error, int64_attribute(fa, 'summary', trim(totals(i))) == &
                   int64_attribute(fb, 'summary', trim(totals(i))), 'summary ' // trim(totals(i)) // ' differs')
        if (allocated(error)) exit
      end do
    end if
    if (.not. allocated(error)) call check(error, int64_attribute(fb, 'summary', 'restart_step') == int(k, i8), &
                                           'summary restart_step is not the step continued after')
    call h5fclose_f(fa, hdferr)
    call h5fclose_f(fb, hdferr)
  end subroutine compare_after

  subroutine remove(stem)
    character(len=*), intent(in) :: stem
    call delete_file(scratch_path(stem // '.h5'))
    call delete_file(scratch_path(stem // '.xmf'))
    call delete_file(scratch_path(stem // '.restart.h5'))
  end subroutine remove

  !> Stopped after step 7 (stage b, after its supports changed: the equations renumbered),
  !! continued: steps 8 to 10 as the uninterrupted run's.
  subroutine test_support_change(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'test/data/slide_1dof_support_change.dat'
    type(error_t), allocatable :: stopped
    call run(deck, 'rs_full', error)
    if (allocated(error)) return
    call run(deck, 'rs_stop', stopped, stop=7)
    if (.not. allocated(stopped)) then
      call test_failed(error, 'the run with --stop-after-step 7 did not stop')
      return
    end if
    call check(error, stopped%code == err_solver .and. .not. file_exists(scratch_path('rs_stop.h5')) .and. &
               file_exists(scratch_path('rs_stop.restart.h5')), 'stopped: a failed run, no results, the checkpoint kept')
    if (allocated(error)) return
    call run(deck, 'rs_cont', error, restart=scratch_path('rs_stop.restart.h5'), step=7)
    if (allocated(error)) return
    call compare_after('rs_full', 'rs_cont', 7, 10, [character(len=16) :: 'displacement', 'reaction'], error)
    call remove('rs_full')
    call remove('rs_stop')
    call remove('rs_cont')
  end subroutine test_support_change

  !> Full Newton-Raphson with LINESEARCH=energy (exact LU tangents, BFGS-free): continued after
  !! step 1 (the end of stage press) and after step 5 (mid-stage pull).
  subroutine test_friction(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: deck = 'test/data/friction_pull.dat'
    integer :: k
    call run(deck, 'rf_full', error)
    if (allocated(error)) return
    do k = 1, 5, 4
      call run(deck, 'rf_cont', error, restart=scratch_path('rf_full.restart.h5'), step=k)
      if (allocated(error)) return
      call compare_after('rf_full', 'rf_cont', k, 11, [character(len=40) :: 'displacement', 'reaction', &
                         'cell/interface/joint', 'cell/principal/lower'], error)
      if (allocated(error)) return
      call remove('rf_cont')
    end do
    call remove('rf_full')
  end subroutine test_friction

  !> Restart data of friction_pull given to block_shear: exit 2 (err_input), no results.
  subroutine test_other_model(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: refused
    call run('test/data/friction_pull.dat', 'ro_a', error, stop=2)
    if (.not. allocated(error)) then
      call test_failed(error, 'the run with --stop-after-step 2 did not stop')
      return
    end if
    deallocate (error)
    call run('test/data/block_shear.dat', 'ro_b', refused, restart=scratch_path('ro_a.restart.h5'))
    if (.not. allocated(refused)) then
      call test_failed(error, 'restart data of another model accepted')
    else
      call check(error, refused%code == err_input .and. index(refused%message, 'restart data of another model') > 0 &
                 .and. .not. file_exists(scratch_path('ro_b.h5')) .and. .not. file_exists(scratch_path('ro_b.h5.part')), &
                 'refused as input (exit 2), no results: ' // refused%message)
    end if
    call remove('ro_a')
    call remove('ro_b')
  end subroutine test_other_model

  !> --step 9 of a file that holds steps 1 and 2: exit 2, naming the steps it holds.
  subroutine test_missing_step(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: refused
    call run('test/data/friction_pull.dat', 'rm_a', error, stop=2)
    if (.not. allocated(error)) then
      call test_failed(error, 'the run with --stop-after-step 2 did not stop')
      return
    end if
    deallocate (error)
    call run('test/data/friction_pull.dat', 'rm_b', refused, restart=scratch_path('rm_a.restart.h5'), step=9)
    if (.not. allocated(refused)) then
      call test_failed(error, '--step 9 accepted')
    else
      call check(error, refused%code == err_input .and. index(refused%message, 'holds no restart data of step 9 ' // &
                 '(--step; it holds steps 1 2)') > 0 .and. .not. file_exists(scratch_path('rm_b.h5')), &
                 'refused as input (exit 2) naming the steps held: ' // refused%message)
    end if
    call remove('rm_a')
    call remove('rm_b')
  end subroutine test_missing_step

end module test_restart
