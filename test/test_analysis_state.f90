!> The analysis state's operations on hand-made states: what the driver does with a tangent
!! that the runs reach only in rare iterates.
module test_analysis_state
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_error, only: str
  use feps_kinds, only: i8
  use feps_material, only: material_t, state_plastic, state_elastic
  use feps_model, only: model_t
  use feps_point_state_store, only: point_state_store_t
  use feps_material_factory, only: material_of
  use feps_linear_elastic, only: linear_elastic_t
  use feps_deck, only: read_deck
  use feps_analysis_summary, only: analysis_summary_t
  use feps_analysis_state, only: analysis_t, set_up, init_states, update_points, &
                                 factorize_tangent, support_reaction
  implicit none
  private

  public :: collect_analysis_state

  !> A material with two internal variables, to prove that the store sizes and carries them:
  !! stress = stress0 + deps, var(1) = var0(1) + |deps(1)| (an accumulated strain), var(2) =
  !! var0(2) + 1 (the updates since the last commit, counted from the committed value).
  type, extends(material_t) :: counting_material_t
  contains
    procedure :: elastic_tangent => counting_tangent
    procedure :: update => counting_update
    procedure :: is_linear => counting_is_linear
    procedure :: state_size => counting_state_size
  end type counting_material_t

contains

  subroutine collect_analysis_state(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('a body held only by non-dilatant sliding faces: the singular exact tangent falls back ' // &
                   'to the stand-in', test_singular_exact_tangent), &
      new_unittest('the support reaction is the out-of-balance force in the held directions only', &
                   test_support_reaction), &
      new_unittest('point-state store: sized by the material, internal variables carried, commit and restore', &
                   test_store_commit_restore), &
      new_unittest('point-state store: an imposed stress increment starts the step', test_store_impose), &
      new_unittest('the deck keeps each material as its typed record; set drops it, and it is built again', &
                   test_typed_material_record) &
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
      an%path%u_t(:, n) = [1.0_dp, 0.0_dp, -0.01_dp]
    end do
    call update_points(model, an, [(0.0_dp, g = 1, size(model%groups))])
    g = size(model%groups)            ! joint, the deck's last group
    call check(error, all(an%states(g)%state_t == state_plastic), 'every interface point slides: states ' // &
               str(count(an%states(g)%state_t == state_plastic)) // ' of ' // str(size(an%states(g)%state_t)))
    if (allocated(error)) return
    call factorize_tangent(model, an, .false., summary, error, trial=.true., exact=.true.)
    if (allocated(error)) return
    call check(error, an%eq%lu_singular == 1, 'the exact tangent is found singular once, got ' // str(an%eq%lu_singular))
    if (allocated(error)) return
    call check(error, .not. an%eq%use_lu .and. an%eq%symmetrized, 'the symmetric stand-in is factorized')
    if (allocated(error)) return
    ! The stand-in is regular: x in the lower block's nodes under a unit load there is finite.
    allocate (b(an%eq%map%neq))
    b = 0.0_dp
    do n = 1, 18
      if (an%eq%map%eq(1, n) > 0) b(an%eq%map%eq(1, n)) = 1.0_dp
    end do
    x = b
    call an%eq%solver%solve(x, error)
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
    if (.not. allocated(an%path%f_applied)) allocate (an%path%f_applied(3, model%nnode))
    if (.not. allocated(an%path%fint)) allocate (an%path%fint(3, model%nnode))
    an%path%f_applied = 0.0_dp
    an%path%fint = 0.0_dp
    do n = 1, model%nnode
      if (.not. an%eq%map%used(n)) cycle
      call check(error, (.not. an%eq%map%constrained(1, n)) .and. an%eq%map%constrained(2, n) .and. &
                 an%eq%map%constrained(3, n), 'node ' // str(n) // ' is held in theta and z only')
      if (allocated(error)) return
      an%path%fint(:, n) = f
      r = support_reaction(an, n)
      expected = dot_product(an%eq%map%basis(:, 2, n), f) * an%eq%map%basis(:, 2, n) + &
                 dot_product(an%eq%map%basis(:, 3, n), f) * an%eq%map%basis(:, 3, n)
      call check(error, maxval(abs(r - expected)) <= 1.0e-14_dp * norm2(f), 'reaction at node ' // str(n))
      if (allocated(error)) return
      call check(error, abs(dot_product(an%eq%map%basis(:, 1, n), r)) <= 1.0e-14_dp * norm2(f), &
                 'no radial reaction at node ' // str(n))
      if (allocated(error)) return
    end do
  end subroutine test_support_reaction

  pure subroutine counting_tangent(self, d)
    class(counting_material_t), intent(in) :: self
    real(dp), intent(out) :: d(:, :)
    integer :: i
    d = 0.0_dp
    do i = 1, size(d, 1)
      d(i, i) = 1.0_dp
    end do
  end subroutine counting_tangent

  pure subroutine counting_update(self, sig0, eps0, deps, state0, sig, state, dtan, var0, var)
    class(counting_material_t), intent(in) :: self
    real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
    integer, intent(in) :: state0
    real(dp), intent(out) :: sig(:)
    integer, intent(out) :: state
    real(dp), intent(out) :: dtan(:, :)
    real(dp), intent(in), optional :: var0(:)
    real(dp), intent(out), optional :: var(:)
    sig = sig0 + deps
    state = state_plastic
    call self%elastic_tangent(dtan)
    dtan = 2.0_dp * dtan
    var(1) = var0(1) + abs(deps(1))
    var(2) = var0(2) + 1.0_dp
  end subroutine counting_update

  pure logical function counting_is_linear(self)
    class(counting_material_t), intent(in) :: self
    counting_is_linear = .false.
  end function counting_is_linear

  pure integer function counting_state_size(self) result(n)
    class(counting_material_t), intent(in) :: self
    n = 2
  end function counting_state_size

  !> Three points of two components: init allocates the two internal variables the material
  !! declares (zero, elastic tangent, committed = trial); two updates of point 2 start from the
  !! committed state each time; restore brings the trial back, commit makes it the committed
  !! state; bytes counts committed and trial stress, strain, variables, flags and tangents.
  subroutine test_store_commit_restore(error)
    type(error_t), allocatable, intent(out) :: error
    type(point_state_store_t) :: store
    type(counting_material_t) :: mat
    call check(error, .not. store%kept() .and. store%bytes() == 0_i8, 'an empty store keeps nothing')
    if (allocated(error)) return
    call store%init(mat, 2, 3)
    call check(error, store%nvars == 2 .and. all(shape(store%vars) == [2, 3]) .and. &
               all(shape(store%vars_t) == [2, 3]) .and. all(store%vars == 0.0_dp) .and. &
               all(store%state == state_elastic) .and. all(store%dtan(:, :, 3) == reshape([1, 0, 0, 1], [2, 2])), &
               'init: two zero internal variables per point, elastic, the elastic tangent')
    if (allocated(error)) return
    call check(error, store%bytes() == 2_i8 * 3 * ((2 + 2 + 2 + 4) * 8 + 4), &
               'bytes: committed and trial stress, strain, two variables, tangent and flag: ' // str(store%bytes()))
    if (allocated(error)) return
    call store%update(mat, 2, [0.5_dp, -1.0_dp])
    call store%update(mat, 2, [-0.25_dp, 2.0_dp])
    call check(error, all(store%sig_t(:, 2) == [-0.25_dp, 2.0_dp]) .and. &
               all(store%eps_t(:, 2) == [-0.25_dp, 2.0_dp]) .and. all(store%vars_t(:, 2) == [0.25_dp, 1.0_dp]) &
               .and. store%state_t(2) == state_plastic .and. store%dtan_t(1, 1, 2) == 2.0_dp, &
               'update: the trial from the committed state, variables included')
    if (allocated(error)) return
    call check(error, all(store%sig == 0.0_dp) .and. all(store%vars == 0.0_dp) .and. &
               all(store%sig_t(:, [1, 3]) == 0.0_dp), 'update: the committed state and the other points unchanged')
    if (allocated(error)) return
    call store%restore()
    call check(error, all(store%sig_t == 0.0_dp) .and. all(store%vars_t == 0.0_dp) .and. &
               all(store%state_t == state_elastic) .and. store%dtan_t(1, 1, 2) == 1.0_dp, &
               'restore: the trial is the committed state')
    if (allocated(error)) return
    call store%update(mat, 2, [0.5_dp, -1.0_dp])
    call store%commit()
    call store%update(mat, 2, [0.5_dp, 0.0_dp])
    call check(error, all(store%sig(:, 2) == [0.5_dp, -1.0_dp]) .and. all(store%vars(:, 2) == [0.5_dp, 1.0_dp]) .and. &
               all(store%sig_t(:, 2) == [1.0_dp, -1.0_dp]) .and. all(store%eps_t(:, 2) == [1.0_dp, -1.0_dp]) .and. &
               all(store%vars_t(:, 2) == [1.0_dp, 2.0_dp]), 'commit: the next update starts from the committed state')
  end subroutine test_store_commit_restore

  !> An imposed increment is added to the committed stress at the start of each update (not to
  !! the committed state itself), until another (zero: none) is imposed.
  subroutine test_store_impose(error)
    type(error_t), allocatable, intent(out) :: error
    type(point_state_store_t) :: store
    type(counting_material_t) :: mat
    call store%init(mat, 1, 2)
    call store%set_stress(10.0_dp)
    call store%impose(3.0_dp)
    call store%update(mat, 1, [1.0_dp])
    call check(error, store%sig_t(1, 1), 14.0_dp, 'committed 10 + imposed 3 + deps 1')
    if (allocated(error)) return
    call check(error, store%sig(1, 1), 10.0_dp, 'the committed stress is not changed')
    if (allocated(error)) return
    call store%impose(0.0_dp)
    call store%update(mat, 1, [1.0_dp])
    call check(error, store%sig_t(1, 1), 11.0_dp, 'nothing imposed: committed 10 + deps 1')
  end subroutine test_store_impose

  !> test/data/cube.dat: its MATERIAL record (E=200000, NU=0.3) is kept as a linear_elastic_t
  !! with those values, which material_of copies; after set('e', ...) the record is built again
  !! with the new value.
  subroutine test_typed_material_record(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    class(material_t), allocatable :: mat
    logical :: typed
    call read_deck('test/data/cube.dat', model, error)
    if (allocated(error)) return
    typed = .false.
    if (allocated(model%materials(1)%params)) then
      select type (p => model%materials(1)%params)
      type is (linear_elastic_t)
        typed = p%e == 200000.0_dp .and. p%nu == 0.3_dp .and. p%name == 'steel'
      end select
    end if
    call check(error, typed, 'the deck keeps a linear_elastic_t with E = 200000, NU = 0.3')
    if (allocated(error)) return
    call model%materials(1)%set('e', 1000.0_dp)
    call check(error, .not. allocated(model%materials(1)%params), 'set drops the typed record')
    if (allocated(error)) return
    call material_of(model%materials(1), mat, error)
    if (allocated(error)) return
    typed = .false.
    select type (mat)
    type is (linear_elastic_t)
      typed = mat%e == 1000.0_dp .and. mat%nu == 0.3_dp
    end select
    call check(error, typed, 'built again with E = 1000')
  end subroutine test_typed_material_record

end module test_analysis_state
