!> Element activation per stage (STAGE ..., ACTIVATE=group): a group born in stage k carries
!! nothing before k and is stress-free at the start of k, so it takes only its share of the
!! later increments. Checked against two-springs-in-parallel closed forms, on the linear path
!! (bars) and on the nonlinear path (solids and interfaces, a model with interfaces). Supports
!! that change between stages (FIX and RELEASE after a STAGE record) against a bar's closed form.
module test_activation
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_observer, only: step_result_t
  use feps_test_observers, only: all_steps_t
  implicit none
  private

  public :: collect_activation

contains

  subroutine collect_activation(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("bars_in_parallel_born_in_stage_2", test_bars), &
      new_unittest("block_and_interface_born_in_stage_2", test_block), &
      new_unittest("deck_records_activation_stage", test_deck), &
      new_unittest("supports_held_and_released_between_stages", test_stage_supports) &
      ]
  end subroutine collect_activation

  !> Run a deck; the written steps (one per stage here) are returned in obs.
  subroutine run_deck(path, obs, error)
    character(len=*), intent(in) :: path
    type(all_steps_t), intent(out) :: obs
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    call read_deck(path, model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
  end subroutine run_deck

  !> Check every point of component `comp` of group g against `expected`.
  subroutine check_group(error, res, g, comp, expected, what, strain)
    type(error_t), allocatable, intent(out) :: error
    type(step_result_t), intent(in) :: res
    integer, intent(in) :: g, comp
    real(dp), intent(in) :: expected
    character(len=*), intent(in) :: what
    logical, intent(in), optional :: strain
    integer :: q
    logical :: use_strain
    use_strain = .false.
    if (present(strain)) use_strain = strain
    do q = 1, size(res%groups(g)%stress, 2)
      if (use_strain) then
        call check(error, res%groups(g)%strain(comp, q), expected, what, rel=1.0e-7_dp, abs=1.0e-12_dp)
      else
        call check(error, res%groups(g)%stress(comp, q), expected, what, rel=1.0e-7_dp, abs=1.0e-9_dp)
      end if
      if (allocated(error)) return
    end do
  end subroutine check_group

  !> Bars old (k = EA/L = 100 N/mm) and new (300 N/mm) between a fixed node and node 2.
  !! Stage 1, F1 = 50 N: u = 0.5, N_old = 50, N_new = 0 (not born). Stage 2, F2 = 40 N on both:
  !! du = 40 / 400 = 0.1, N_old = 50 + 10 = 60, N_new = 30 (its strain is du / L only).
  subroutine test_bars(error)
    type(error_t), allocatable, intent(out) :: error
    type(all_steps_t) :: obs
    call run_deck('test/data/activate_bars.dat', obs, error)
    if (allocated(error)) return
    call check(error, size(obs%steps), 2, 'one written step per stage')
    if (allocated(error)) return
    call check(error, obs%steps(1)%displacement(1, 2), 0.5_dp, 'stage 1: u = F1 / k_old', rel=1.0e-10_dp)
    if (allocated(error)) return
    call check_group(error, obs%steps(1), 1, 1, 50.0_dp, 'stage 1: N_old = F1')
    if (allocated(error)) return
    call check_group(error, obs%steps(1), 2, 1, 0.0_dp, 'stage 1: the unborn bar carries nothing')
    if (allocated(error)) return
    call check_group(error, obs%steps(1), 2, 1, 0.0_dp, 'stage 1: the unborn bar has no strain', strain=.true.)
    if (allocated(error)) return
    call check(error, obs%steps(2)%displacement(1, 2), 0.6_dp, 'stage 2: u = F1/k_old + F2/(k_old + k_new)', &
               rel=1.0e-10_dp)
    if (allocated(error)) return
    call check_group(error, obs%steps(2), 1, 1, 60.0_dp, 'stage 2: N_old = F1 + F2 k_old / (k_old + k_new)')
    if (allocated(error)) return
    call check_group(error, obs%steps(2), 2, 1, 30.0_dp, 'stage 2: N_new = F2 k_new / (k_old + k_new)')
    if (allocated(error)) return
    call check_group(error, obs%steps(2), 2, 1, 0.1_dp / 100.0_dp, 'stage 2: strain of new = du / L', strain=.true.)
    if (allocated(error)) return
    call check(error, obs%steps(2)%reaction(1, 1), -90.0_dp, 'reaction = -(F1 + F2)', rel=1.0e-10_dp)
  end subroutine test_bars

  !> Blocks of E = 1000 (10 mm high, nu = 0) pressed through a joint of Kn = 800; born in
  !! stage 2: upper2 (E = 3000) over the upper block's nodes and joint2 (Kn = 200) over the
  !! joint's nodes. Stage 1, p1 = 1: sigma_zz = -1 everywhere, born groups zero. Stage 2,
  !! p2 = 2 more: lower -3; upper -1 - 2 (1000/4000) = -1.5, upper2 -2 (3000/4000) = -1.5
  !! (strain -5e-4, counted from its birth); joint -1 - 2 (800/1000) = -2.6, joint2 -0.4.
  !! Top: uz = -3 (10/1000) - (1/800 + 2/1000) - (10/1000 + 2 (10/4000)) = -0.04825.
  subroutine test_block(error)
    type(error_t), allocatable, intent(out) :: error
    type(all_steps_t) :: obs
    integer, parameter :: lower = 1, upper = 2, joint = 3, upper2 = 4, joint2 = 5
    integer :: top
    call run_deck('test/data/activate_block.dat', obs, error)
    if (allocated(error)) return
    call check(error, size(obs%steps), 2, 'one written step per stage')
    if (allocated(error)) return
    top = size(obs%steps(1)%displacement, 2)    ! the last node: a top corner (z = 20)
    ! end of stage 1
    call check_group(error, obs%steps(1), lower, 3, -1.0_dp, 'stage 1: lower sigma_zz')
    if (allocated(error)) return
    call check_group(error, obs%steps(1), upper, 3, -1.0_dp, 'stage 1: upper sigma_zz')
    if (allocated(error)) return
    call check_group(error, obs%steps(1), joint, 3, -1.0_dp, 'stage 1: joint sigma_n')
    if (allocated(error)) return
    call check_group(error, obs%steps(1), upper2, 3, 0.0_dp, 'stage 1: unborn upper2 sigma_zz')
    if (allocated(error)) return
    call check_group(error, obs%steps(1), joint2, 3, 0.0_dp, 'stage 1: unborn joint2 sigma_n')
    if (allocated(error)) return
    call check(error, obs%steps(1)%displacement(3, top), -0.02125_dp, 'stage 1: top uz', rel=1.0e-6_dp)
    if (allocated(error)) return
    ! end of stage 2
    call check_group(error, obs%steps(2), lower, 3, -3.0_dp, 'stage 2: lower sigma_zz')
    if (allocated(error)) return
    call check_group(error, obs%steps(2), upper, 3, -1.5_dp, 'stage 2: upper sigma_zz')
    if (allocated(error)) return
    call check_group(error, obs%steps(2), upper2, 3, -1.5_dp, 'stage 2: upper2 sigma_zz (share of p2 only)')
    if (allocated(error)) return
    call check_group(error, obs%steps(2), upper2, 3, -5.0e-4_dp, 'stage 2: upper2 strain from its birth', &
                     strain=.true.)
    if (allocated(error)) return
    call check_group(error, obs%steps(2), upper2, 1, 0.0_dp, 'stage 2: upper2 sigma_xx')
    if (allocated(error)) return
    call check_group(error, obs%steps(2), joint, 3, -2.6_dp, 'stage 2: joint sigma_n')
    if (allocated(error)) return
    call check_group(error, obs%steps(2), joint2, 3, -0.4_dp, 'stage 2: joint2 sigma_n (share of p2 only)')
    if (allocated(error)) return
    call check(error, obs%steps(2)%displacement(3, top), -0.04825_dp, 'stage 2: top uz', rel=1.0e-6_dp)
  end subroutine test_block

  !> The reader keeps each group's birth stage: 0 for the groups present from the start.
  subroutine test_deck(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    call read_deck('test/data/activate_block.dat', model, error)
    if (allocated(error)) return
    call check(error, model%groups(model%find_group('upper2'))%activate_stage, 2, 'upper2 born in stage 2')
    if (allocated(error)) return
    call check(error, model%groups(model%find_group('joint2'))%activate_stage, 2, 'joint2 born in stage 2')
    if (allocated(error)) return
    call check(error, model%groups(model%find_group('joint'))%activate_stage, 0, 'joint present from the start')
  end subroutine test_deck

  !> test/data/stage_supports.dat (linear driver) and its Matsuoka twin (incremental driver,
  !! never yields): a bar pulled at the top (stage 1), its top then held where it is while the
  !! middle is pulled (stage 2), then released, its support force removed over 5 steps
  !! (stage 3, OUTPUT=1). Closed forms in the deck's header; both drivers write every step of
  !! stage 3, where the support force falls linearly: u_mid = 1.5 + 0.1 k after k steps (the
  !! linear driver's step k is the stage start plus k/5 of its one solve). The two drivers'
  !! steps agree in every displacement, reaction and stress, and in the load factor.
  subroutine test_stage_supports(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: decks(2) = [character(len=48) :: 'test/data/stage_supports.dat', &
                                                'test/data/stage_supports_incremental.dat']
    type(all_steps_t) :: obs(2)
    type(model_t) :: model
    real(dp) :: umid, utop, rtop, rbot
    integer :: d, k, n, j
    do d = 1, size(decks)
      call run_deck(trim(decks(d)), obs(d), error)
      if (allocated(error)) return
      call read_deck(trim(decks(d)), model, error)
      if (allocated(error)) return
      n = size(obs(d)%steps)
      call check(error, n, 7, trim(decks(d)) // ': steps written (the ends of stages 1 and 2, every step of stage 3)')
      if (allocated(error)) return
      call measure(obs(d)%steps(1))
      call compare([1.0_dp, 2.0_dp, 0.0_dp, -1000.0_dp], 'stage 1')
      if (allocated(error)) return
      call measure(obs(d)%steps(2))
      call compare([1.5_dp, 2.0_dp, -500.0_dp, -1500.0_dp], 'stage 2 (top held where it was)')
      if (allocated(error)) return
      do k = 3, n
        j = k - 2     ! steps of stage 3 done
        call measure(obs(d)%steps(k))
        call compare([1.5_dp + 0.1_dp * j, 2.0_dp + 0.2_dp * j, 0.0_dp, &
                      -1500.0_dp - 100.0_dp * j], 'stage 3 (top released), step ' // achar(iachar('0') + j))
        if (allocated(error)) return
        call check(error, obs(d)%steps(k)%step, 5 + j, trim(decks(d)) // ': step number over the stages')
        if (allocated(error)) return
        call check(error, obs(d)%steps(k)%load_factor, 2.0_dp + j / 5.0_dp, trim(decks(d)) // &
                   ': load factor of stage 3, step ' // achar(iachar('0') + j), rel=1.0e-14_dp)
        if (allocated(error)) return
      end do
    end do
    do k = 1, 7
      call agree(obs(1)%steps(k), obs(2)%steps(k))
      if (allocated(error)) return
    end do
  contains
    !> u_mid and u_top (mm) to 1e-9 mm, the reactions (N) to 1e-6 N.
    subroutine compare(expected, what)
      real(dp), intent(in) :: expected(4)
      character(len=*), intent(in) :: what
      character(len=*), parameter :: names(4) = [character(len=8) :: 'u_mid', 'u_top', 'R_top', 'R_bottom']
      real(dp) :: got(4)
      integer :: i
      got = [umid, utop, rtop, rbot]
      do i = 1, 4
        call check(error, got(i), expected(i), trim(decks(d)) // ', ' // what // ': ' // trim(names(i)), &
                   abs=merge(1.0e-9_dp, 1.0e-6_dp, i <= 2))
        if (allocated(error)) return
      end do
    end subroutine compare

    !> Mean axial displacement of the middle and top layers, summed axial reactions of the top
    !! and bottom layers.
    subroutine measure(res)
      type(step_result_t), intent(in) :: res
      logical :: top(model%nnode), mid(model%nnode), bot(model%nnode)
      top = abs(model%coords(3, :) - 200.0_dp) < 1.0e-9_dp
      mid = abs(model%coords(3, :) - 100.0_dp) < 1.0e-9_dp
      bot = abs(model%coords(3, :)) < 1.0e-9_dp
      umid = sum(res%displacement(3, :), mask=mid) / count(mid)
      utop = sum(res%displacement(3, :), mask=top) / count(top)
      rtop = sum(res%reaction(3, :), mask=top)
      rbot = sum(res%reaction(3, :), mask=bot)
    end subroutine measure

    !> The linear and the incremental driver's step: the same step number and load factor, every
    !! displacement within 1e-9 of the largest (mm), every reaction within 1e-9 of the largest
    !! (N), every stress within 1e-9 of the largest (MPa). Each incremental step converges to
    !! |R| / |P| < 1e-6 (DELTA1), but a bar far from yield converges in one iteration to rounding.
    subroutine agree(lin, inc)
      type(step_result_t), intent(in) :: lin, inc
      character(len=:), allocatable :: what
      what = 'step ' // achar(iachar('0') + lin%step) // ', linear against incremental driver: '
      call check(error, lin%step, inc%step, what // 'step number')
      if (.not. allocated(error)) call check(error, lin%load_factor, inc%load_factor, what // 'load factor', &
                                             rel=1.0e-14_dp)
      if (.not. allocated(error)) call check(error, maxval(abs(lin%displacement - inc%displacement)), 0.0_dp, &
                                             what // 'largest displacement difference', &
                                             abs=1.0e-9_dp * maxval(abs(inc%displacement)))
      if (.not. allocated(error)) call check(error, maxval(abs(lin%reaction - inc%reaction)), 0.0_dp, &
                                             what // 'largest reaction difference', &
                                             abs=1.0e-9_dp * maxval(abs(inc%reaction)))
      if (.not. allocated(error)) call check(error, maxval(abs(lin%groups(1)%stress - inc%groups(1)%stress)), &
                                             0.0_dp, what // 'largest stress difference', &
                                             abs=1.0e-9_dp * maxval(abs(inc%groups(1)%stress)))
    end subroutine agree
  end subroutine test_stage_supports

end module test_activation
