!> Threaded element loops (issue 28 item 3): the point updates, internal forces and tangents are
!! made in parallel over the elements of a chunk and added in element order, so a run gives the
!! same bits with one thread and with two. Decks: test/data/friction_pull.dat (interfaces sliding,
!! full Newton-Raphson: the tangent of every iterate) and beam_tension_cap.dat (Matsuoka-Nakai
!! points yielding and reaching the tension cap), lame_hex20.dat (a linear model: the stress
!! recovery of its steps).
module test_threads
  use omp_lib, only: omp_set_num_threads, omp_get_max_threads, omp_get_num_procs
  use feps_blas, only: factorization_threads, set_blas_threads
  use feps_kinds, only: dp, i8
  use feps_stress_recovery, only: nodal_average
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  implicit none
  private

  public :: collect_threads

contains

  !> Collect the suite.
  subroutine collect_threads(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('sliding interfaces: 1 and 2 threads give the same bits', test_friction), &
      new_unittest('yielding soil: 1 and 2 threads give the same bits', test_collapse), &
      new_unittest('linear model''s stress recovery: 1 and 2 threads give the same bits', test_linear), &
      new_unittest('factorization threads: every core up to 4, three quarters above', test_policy), &
      new_unittest('nodal averaging: 1 and 2 threads give the same bits', test_nodal_average)]
  end subroutine collect_threads

  subroutine test_friction(error)
    type(error_t), allocatable, intent(out) :: error
    call same_bits('test/data/friction_pull.dat', error)
  end subroutine test_friction

  subroutine test_collapse(error)
    type(error_t), allocatable, intent(out) :: error
    call same_bits('test/data/beam_tension_cap.dat', error)
  end subroutine test_collapse

  subroutine test_linear(error)
    type(error_t), allocatable, intent(out) :: error
    call same_bits('test/data/lame_hex20.dat', error)
  end subroutine test_linear

  !> The policy measured on a 16-core Xeon (docs/performance.md): 12 OpenBLAS threads
  !! factorized the 200k mesh in 2.1-2.7 s, 16 in 28-33 s; on 2 cores, 2 beat 1.
  subroutine test_policy(error)
    type(error_t), allocatable, intent(out) :: error
    integer :: cores
    call check(error, all([(factorization_threads(cores), cores = 1, 4)] == [1, 2, 3, 4]), &
               'all the cores of a machine of up to 4')
    if (allocated(error)) return
    call check(error, factorization_threads(16), 12, '12 of 16 cores')
    if (allocated(error)) return
    call check(error, factorization_threads(8), 6, '6 of 8 cores')
    if (allocated(error)) return
    call check(error, factorization_threads(0), 1, 'at least one thread')
  end subroutine test_policy

  !> Extrapolation to the nodes and averaging over 20 000 elements (three chunks) sharing 5 000
  !! nodes in a scrambled order: the sums at each node are made in element order whatever the
  !! threads, so one thread and two give the same bits.
  subroutine test_nodal_average(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: nen = 8, np = 8, nelem = 20000, nnode = 5000
    real(dp) :: e(nen, np)
    real(dp), allocatable :: values(:, :), one(:, :), two(:, :)
    integer, allocatable :: connectivity(:, :), count1(:), count2(:)
    integer :: threads, i, j, seed
    seed = 12345
    do j = 1, np
      do i = 1, nen
        e(i, j) = next() - 0.5_dp
      end do
    end do
    allocate (connectivity(nen, nelem), values(6, nelem * np))
    do j = 1, nelem
      do i = 1, nen
        connectivity(i, j) = 1 + int(next() * nnode)
      end do
    end do
    do j = 1, nelem * np
      do i = 1, 6
        values(i, j) = 100.0_dp * (next() - 0.5_dp)
      end do
    end do
    allocate (one(6, nnode), two(6, nnode), count1(nnode), count2(nnode))
    threads = omp_get_max_threads()
    call omp_set_num_threads(1)
    call nodal_average(e, connectivity, values, nnode, one, count1)
    call omp_set_num_threads(2)
    call nodal_average(e, connectivity, values, nnode, two, count2)
    call omp_set_num_threads(threads)
    call check(error, all(count1 == count2) .and. all(one == two), 'nodal values and counts bit-identical')
  contains
    !> A fixed pseudo-random sequence in [0, 1) (Park-Miller).
    real(dp) function next()
      seed = int(mod(16807_i8 * int(seed, i8), 2147483647_i8))
      next = real(seed, dp) / 2147483647.0_dp
    end function next
  end subroutine test_nodal_average

  !> Run `deck` with one element-loop thread and with two, the BLAS on one (its thread count
  !! changes the factorization at round-off): every step's displacements, reactions and point
  !! stresses must be equal bit for bit.
  subroutine same_bits(deck, error)
    character(len=*), intent(in) :: deck
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: one, two
    type(analysis_summary_t) :: summary
    integer :: threads, k, g
    logical :: same
    threads = omp_get_max_threads()
    call read_deck(deck, model, error)
    if (allocated(error)) return
    call omp_set_num_threads(1)
    call set_blas_threads(1)
    call run_analysis(model, 'cholmod', one, summary, error)
    if (.not. allocated(error)) then
      call omp_set_num_threads(2)
      call run_analysis(model, 'cholmod', two, summary, error)
    end if
    call omp_set_num_threads(threads)
    call set_blas_threads(factorization_threads(omp_get_num_procs()))
    if (allocated(error)) return
    call check(error, size(two%steps), size(one%steps), 'as many steps')
    if (allocated(error)) return
    same = .true.
    do k = 1, size(one%steps)
      same = same .and. all(one%steps(k)%displacement == two%steps(k)%displacement) .and. &
             all(one%steps(k)%reaction == two%steps(k)%reaction)
      do g = 1, size(one%steps(k)%groups)
        if (allocated(one%steps(k)%groups(g)%stress)) &
          same = same .and. all(one%steps(k)%groups(g)%stress == two%steps(k)%groups(g)%stress)
      end do
    end do
    call check(error, same, 'every step''s displacements, reactions and stresses bit-identical')
  end subroutine same_bits

end module test_threads
