!> REPORT, SECTION (issue 26): the forces and moments through a section, from the internal
!! nodal forces of the elements below it, against beam statics on test/data/bent_pipe.dat (a
!! half pipe bent as a cantilever: Vx = P/2, My = (P/2) (L - z), N = Vy = Mx = 0) and, all six,
!! against the applied loads and reactions on the nodes at or above the plane.
module test_section_report
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  use feps_reports, only: section_forces
  implicit none
  private

  public :: collect_section_report

contains

  !> Collect the suite.
  subroutine collect_section_report(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [new_unittest('bent pipe: beam statics and the loads above each section', test_bent_pipe)]
  end subroutine collect_section_report

  subroutine test_bent_pipe(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: half_p = 500.0_dp, length = 1000.0_dp, tol = 1.0e-9_dp * 2.0_dp * half_p * length
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp) :: force(3), moment(3), statics_f(3), statics_m(3), arm(3), fn(3)
    integer :: k, count, n
    call read_deck('test/data/bent_pipe.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    associate (res => obs%steps(size(obs%steps)))
      do k = 1, size(model%reports)
        associate (r => model%reports(k))
          call section_forces(model, r, res%groups, force, moment, count, error)
          if (allocated(error)) return
          call check(error, count, 24, r%name // ': the 24 elements under the plane')
          if (allocated(error)) return
          call check(error, norm2([force(3), force(2)]), 0.0_dp, r%name // ': N = Vy = 0', abs=tol / length)
          if (allocated(error)) return
          call check(error, force(1), half_p, r%name // ': Vx = P/2', rel=1.0e-9_dp)
          if (allocated(error)) return
          call check(error, moment(1), 0.0_dp, r%name // ': Mx = 0', abs=tol)
          if (allocated(error)) return
          call check(error, moment(2), half_p * (length - r%z), r%name // ': My = (P/2) (L - z)', rel=1.0e-9_dp)
          if (allocated(error)) return
          ! statics: the applied loads and reactions on the nodes at or above the plane
          statics_f = 0.0_dp
          statics_m = 0.0_dp
          do n = 1, model%nnode
            if (model%coords(3, n) < r%z - 1.0e-6_dp) cycle
            fn = res%applied_force(:, n) + res%reaction(:, n)
            arm = model%coords(:, n) - [0.0_dp, 0.0_dp, r%z]
            statics_f = statics_f + fn
            statics_m = statics_m + [arm(2) * fn(3) - arm(3) * fn(2), arm(3) * fn(1) - arm(1) * fn(3), &
                                     arm(1) * fn(2) - arm(2) * fn(1)]
          end do
          call check(error, norm2(force - statics_f), 0.0_dp, r%name // ': forces = the loads above', abs=tol / length)
          if (allocated(error)) return
          call check(error, norm2(moment - statics_m), 0.0_dp, r%name // ': moments = the loads above', abs=tol)
          if (allocated(error)) return
        end associate
      end do
    end associate
  end subroutine test_bent_pipe

end module test_section_report
