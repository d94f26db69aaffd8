!> Explicit lists in the deck (issue 25 item 1): test/data/lists_lame_hex20.dat is the Lame
!! cylinder of lame_hex20.dat with its mesh as NODES and ELEMENTS tables and its supports on an
!! NSET LIST, the nodes and elements renumbered (gaps, reverse order; make_lists_decks.py). The
!! same model: every node's displacement equals that of the DATAIN deck's node at the same
!! coordinates to 1e-12 of the largest displacement (measured 2.0e-13: the other numbering gives
!! another elimination order, so the two solutions differ by rounding only).
module test_lists
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  implicit none
  private

  public :: collect_lists

contains

  !> Collect the suite.
  subroutine collect_lists(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('tables: the ids are kept', test_ids), &
      new_unittest('tables: the displacements of the DATAIN deck', test_same_displacements)]
  end subroutine collect_lists

  !> Node numbers index the mesh (the gaps are unused nodes); element ids are kept per group.
  subroutine test_ids(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    integer :: nel
    call read_deck('test/data/lists_lame_hex20.dat', model, error)
    if (allocated(error)) return
    ! 459 lattice nodes: the largest number is 3 (459 - 1) + 5
    call check(error, model%nnode, 3 * 458 + 5, 'the largest node number is the mesh size')
    if (allocated(error)) return
    call check(error, allocated(model%groups(1)%element_ids), 'element ids kept')
    if (allocated(error)) return
    nel = size(model%groups(1)%element_ids)
    call check(error, nel, 32, 'elements of the table')
    if (allocated(error)) return
    call check(error, model%groups(1)%element_ids(1), 101, 'first row''s id')
    if (allocated(error)) return
    call check(error, model%groups(1)%element_ids(nel), 2 * (nel - 1) + 101, 'last row''s id')
    if (allocated(error)) return
    call check(error, size(model%node_sets(1)%nodes), 459, 'the NSET LIST holds every node')
  end subroutine test_ids

  subroutine test_same_displacements(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: datain, lists
    type(all_steps_t) :: obs_d, obs_l
    type(analysis_summary_t) :: summary
    real(dp) :: worst, scale
    integer :: i, j, matched
    call read_deck('test/data/lame_hex20.dat', datain, error)
    if (allocated(error)) return
    call read_deck('test/data/lists_lame_hex20.dat', lists, error)
    if (allocated(error)) return
    call run_analysis(datain, 'cholmod', obs_d, summary, error)
    if (allocated(error)) return
    call run_analysis(lists, 'cholmod', obs_l, summary, error)
    if (allocated(error)) return
    associate (ud => obs_d%steps(size(obs_d%steps))%displacement, ul => obs_l%steps(size(obs_l%steps))%displacement)
      scale = maxval(abs(ud))
      worst = 0.0_dp
      matched = 0
      do i = 1, datain%nnode
        do j = 1, lists%nnode
          ! the table's coordinates are the DATAIN ones printed to 17 digits: equal
          if (all(lists%coords(:, j) == datain%coords(:, i))) then
            if (mod(j - 5, 3) /= 0) then
              call test_failed(error, 'a gap node matched a lattice node')
              return
            end if
            worst = max(worst, maxval(abs(ul(:, j) - ud(:, i))))
            matched = matched + 1
            exit
          end if
        end do
      end do
      call check(error, matched, datain%nnode, 'every DATAIN node has its table node')
      if (allocated(error)) return
      call check(error, worst, 0.0_dp, 'largest difference of a displacement', abs=1.0e-12_dp * scale)
    end associate
  end subroutine test_same_displacements

end module test_lists
