!> The analysis state's operations on hand-made states: what the driver does with a tangent
!! that the runs reach only in rare iterates.
module test_analysis_state
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_material, only: state_plastic
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_analysis_summary, only: analysis_summary_t
  use feps_analysis_state, only: analysis_t, set_up, init_states, update_points, &
                                 factorize_tangent, support_reaction
  implicit none
  private

  public :: collect_analysis_state

contains

  subroutine collect_analysis_state(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('a body held only by non-dilatant sliding faces: the singular exact tangent falls back ' // &
                   'to the stand-in', test_singular_exact_tangent), &
      new_unittest('the support reaction is the out-of-balance force in the held directions only', &
                   test_support_reaction) &
      ]
  end subroutine collect_analysis_state

  !> test/data/slide_singular.dat with the upper block moved 1 in x and 0.01 down: every
  !! interface point slides, the exact (LU) tangent is singular in the lower block's x
  !! translation, and factorize_tangent counts it and factorizes the symmetric stand-in, whose
  !! solution of a load on the lower block is finite and satisfies the stand-in's equations.
  subroutine test_singular_exact_tangent(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_t) :: an
    type(analysis_summary_t) :: summary
    real(dp), allocatable :: x(:), b(:)
    integer :: g, n
    call read_deck('test/data/slide_singular.dat', model, error)
    if (allocated(error)) return
    call set_up(model, 'cholmod', an, summary, error)
    if (allocated(error)) return
    call init_states(model, an)
    do n = 19, model%nnode            ! the upper block (the deck's second node block)
      an%u_t(:, n) = [1.0_dp, 0.0_dp, -0.01_dp]
    end do
    call update_points(model, an, [(0.0_dp, g = 1, size(model%groups))])
    g = size(model%groups)            ! joint, the deck's last group
    call check(error, all(an%states(g)%state_t == state_plastic), 'every interface point slides: states ' // &
               str(count(an%states(g)%state_t == state_plastic)) // ' of ' // str(size(an%states(g)%state_t)))
    if (allocated(error)) return
    call factorize_tangent(model, an, .false., summary, error, trial=.true., exact=.true.)
    if (allocated(error)) return
    call check(error, an%lu_singular == 1, 'the exact tangent is found singular once, got ' // str(an%lu_singular))
    if (allocated(error)) return
    call check(error, .not. an%use_lu .and. an%symmetrized, 'the symmetric stand-in is factorized')
    if (allocated(error)) return
    ! The stand-in is regular: x in the lower block's nodes under a unit load there is finite.
    allocate (b(an%map%neq))
    b = 0.0_dp
    do n = 1, 18
      if (an%map%eq(1, n) > 0) b(an%map%eq(1, n)) = 1.0_dp
    end do
    x = b
    call an%solver%solve(x, error)
    if (allocated(error)) return
    call check(error, all(abs(x) <= huge(1.0_dp)) .and. maxval(abs(x)) > 0.0_dp .and. maxval(abs(x)) < 1.0e3_dp, &
               'the stand-in solve is finite and bounded, max |x| = ' // str(maxval(abs(x))))
  end subroutine test_singular_exact_tangent

  !> test/data/lame_hex8.dat holds every node in theta and z of its cylindrical nodal system and
  !! leaves r free. With an out-of-balance force f at a node, its reaction must be f's theta and
  !! z parts (the basis's hoop and axial columns times f's components along them), with no part
  !! along r, which used to be reported as a reaction when a step carried an unbalanced force.
  subroutine test_support_reaction(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_t) :: an
    type(analysis_summary_t) :: summary
    real(dp) :: f(3), expected(3), r(3)
    integer :: n
    call read_deck('test/data/lame_hex8.dat', model, error)
    if (allocated(error)) return
    call set_up(model, 'cholmod', an, summary, error)
    if (allocated(error)) return
    call init_states(model, an)
    f = [3.0_dp, -2.0_dp, 5.0_dp]
    if (.not. allocated(an%f_applied)) allocate (an%f_applied(3, model%nnode))
    if (.not. allocated(an%fint)) allocate (an%fint(3, model%nnode))
    an%f_applied = 0.0_dp
    an%fint = 0.0_dp
    do n = 1, model%nnode
      if (.not. an%map%used(n)) cycle
      call check(error, (.not. an%map%constrained(1, n)) .and. an%map%constrained(2, n) .and. &
                 an%map%constrained(3, n), 'node ' // str(n) // ' is held in theta and z only')
      if (allocated(error)) return
      an%fint(:, n) = f
      r = support_reaction(an, n)
      expected = dot_product(an%map%basis(:, 2, n), f) * an%map%basis(:, 2, n) + &
                 dot_product(an%map%basis(:, 3, n), f) * an%map%basis(:, 3, n)
      call check(error, maxval(abs(r - expected)) <= 1.0e-14_dp * norm2(f), 'reaction at node ' // str(n))
      if (allocated(error)) return
      call check(error, abs(dot_product(an%map%basis(:, 1, n), r)) <= 1.0e-14_dp * norm2(f), &
                 'no radial reaction at node ' // str(n))
      if (allocated(error)) return
    end do
  end subroutine test_support_reaction

end module test_analysis_state
