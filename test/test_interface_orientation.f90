!> The order of an interface's layers checked against its neighbouring solids (issue 24): given
!! the wrong way round (or the lower layer wound clockwise), the normal would point into the
!! lower solid and compression would read as opening. Such decks are input errors naming the
!! GROUP record's file and line and the element; the decks as they are pass.
module test_interface_orientation
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: err_input
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: check_analysis, analysis_summary_t
  implicit none
  private

  public :: collect_interface_orientation

contains

  subroutine collect_interface_orientation(testsuite)
    type(unittest_t), allocatable, intent(out) :: testsuite(:)
    testsuite = [ &
      new_unittest('a quad4 joint given upper layer first is refused at its GROUP line', test_swapped), &
      new_unittest('a quad4 joint wound clockwise seen from above is refused', test_clockwise), &
      new_unittest('a 2D line3 joint given upper layer first is refused', test_swapped_2d), &
      new_unittest('the joints as the decks give them pass (3D and 2D)', test_as_given) &
      ]
  end subroutine collect_interface_orientation

  !> `path` is refused as an input error whose message starts with "path:line:" and names the
  !! element's wrong layer order.
  subroutine expect_refused(path, line, error)
    character(len=*), intent(in) :: path, line
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(error_t), allocatable :: run_error
    call read_deck(path, model, error)
    if (allocated(error)) return
    call check_analysis(model, 'cholmod', summary, run_error)
    if (.not. allocated(run_error)) then
      call test_failed(error, path // ': accepted')
      return
    end if
    call check(error, run_error%code == err_input .and. index(run_error%message, path // ':' // line // ':') == 1 &
               .and. index(run_error%message, 'interface element 1 of group joint') > 0 .and. &
               index(run_error%message, 'layers in the wrong order') > 0, 'the message: ' // run_error%message)
  end subroutine expect_refused

  subroutine test_swapped(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_refused('test/data/bad/interface_layers_swapped.dat', '33', error)
  end subroutine test_swapped

  subroutine test_clockwise(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_refused('test/data/bad/interface_layers_clockwise.dat', '32', error)
  end subroutine test_clockwise

  subroutine test_swapped_2d(error)
    type(error_t), allocatable, intent(out) :: error
    call expect_refused('test/data/bad/interface_layers_swapped_2d.dat', '33', error)
  end subroutine test_swapped_2d

  subroutine test_as_given(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: decks(3) = [character(len=40) :: 'test/data/block_shear.dat', &
                                               'test/data/contact_2d.dat', 'input/modelB/FE1.dat']
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    integer :: k
    do k = 1, size(decks)
      call read_deck(trim(decks(k)), model, error)
      if (allocated(error)) return
      call check_analysis(model, 'cholmod', summary, error)
      if (allocated(error)) then
        error%message = trim(decks(k)) // ': ' // error%message
        return
      end if
    end do
  end subroutine test_as_given

end module test_interface_orientation
