!> Path following within a stage (STAGE PATH=): the stage's load increment df is the
!! reference load q, scaled by a load factor lambda that is an unknown of each step beside
!! the displacements, fixed by one more equation, the constraint:
!!
!! - arc-length (Crisfield 1981, cylindrical): |du|^2 = l^2, du the step's displacement
!!   increment on the free DOFs; the predictor's sign follows the angle with the previous
!!   step's increment (it keeps going through a limit point), and of the two roots of the
!!   corrector's quadratic the one nearer the iterate's increment (largest cosine) is taken;
!! - displacement control (indirect): e . du = v, e the mean of one direction over a node set,
!!   less its mean over a second set (FROM=) when one is given: a relative displacement such as a
!!   crack's opening, which grows monotonically through a snap-back (de Borst 1987);
!! - load: lambda fixed (a step to the stage's full load that ends an arc-length stage).
!!
!! Each iteration solves K du_r = R and K du_t = q with the stiffness held (the method's) and
!! adds du_r + dlambda du_t with dlambda from the constraint (Batoz and Dhatt 1979).
module feps_path_following
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t, stage_t, controls_t, path_names
  use feps_loads, only: to_equations
  use feps_strings, only: to_upper
  use feps_analysis_summary, only: analysis_summary_t
  use feps_analysis_state, only: analysis_t, set_trial, add_free, update_points, residual, factorize_tangent
  use feps_step_report, only: collect_point_notes
  implicit none
  private

  public :: path_t, start_path, path_substep

  !> The constraint of a (sub)step: the arc length, the followed displacement, or a fixed load factor.
  integer, parameter, public :: constrain_arc = 1, constrain_displacement = 2, constrain_load = 3

  !> A stage's path: its reference load, the load factor reached, the arc length and the
  !! previous step's increment (for the predictor's sign).
  type :: path_t
    real(dp) :: lam = 0.0_dp                 !! the stage's load factor committed (0 at its start)
    real(dp) :: arc = 0.0_dp                 !! the arc length of the next step (0: from the first predictor)
    real(dp) :: arc0 = 0.0_dp                !! the stage's arc length (a cut-back halves arc; it grows back to this)
    integer :: steps = 1
    real(dp), allocatable :: q(:)            !! the reference load on the free equations
    real(dp), allocatable :: e(:)            !! displacement control: the functional of the DOF followed
    real(dp), allocatable :: du_prev(:)      !! the previous step's increment (empty before the first)
    real(dp), allocatable :: f0(:, :)        !! the applied force at the stage's start
    real(dp), allocatable :: df(:, :)        !! the stage's load increment (lambda = 1)
  end type path_t

contains

  !> The path of stage st from its increments: loads only. Prescribed displacements, a
  !! prestress or an in-situ stress in the stage, a stage without load and, for displacement
  !! control, a set held in its DOF are input errors naming the STAGE record.
  subroutine start_path(model, an, st, df, duc, dps, pt, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    type(stage_t), intent(in) :: st
    real(dp), intent(in) :: df(:, :), duc(:, :), dps(:)
    type(path_t), intent(out) :: pt
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: unit(:, :)
    character(len=:), allocatable :: path
    integer :: i, n
    path = 'PATH=' // to_upper(trim(path_names(st%path))) // ' (stage ' // st%name // ')'
    if (any(duc /= 0.0_dp)) then
      call input_error(error, st%file, st%line, path // ' scales the stage''s loads; it moves no DOF by ' // &
                       'DISPLACE (prescribe the displacement by PATH=DISPLACEMENT, or move it in a stage of its own)')
      return
    end if
    if (any(dps /= 0.0_dp)) then
      call input_error(error, st%file, st%line, path // ' scales the stage''s loads; a prestress or an ' // &
                       'in-situ stress (GEOSTATIC) belongs in a stage of its own')
      return
    end if
    if (all(df == 0.0_dp)) then
      call input_error(error, st%file, st%line, path // ' has no load to scale: give the stage a load ' // &
                       '(FORCE, PRESSURE, TRACTION, LOAD=)')
      return
    end if
    allocate (pt%q(an%eq%map%neq))
    call to_equations(an%eq%map, df, pt%q)
    pt%f0 = an%path%f_applied
    pt%df = df
    pt%steps = st%steps
    pt%arc = st%arc
    pt%arc0 = st%arc
    allocate (pt%du_prev(0))
    if (st%path_set == 0) return
    associate (nodes => model%node_sets(st%path_set)%nodes)
      allocate (unit(3, model%nnode), pt%e(an%eq%map%neq))
      unit = 0.0_dp
      do i = 1, size(nodes)
        n = nodes(i)
        if (an%eq%map%node_csys(n) == 0 .and. an%eq%map%constrained(st%path_dof, n)) then
          call input_error(error, st%file, st%line, path // ': node ' // str(n) // ' of set ' // &
                           model%node_sets(st%path_set)%name // ' is held in ' // 'XYZ'(st%path_dof:st%path_dof) // &
                           ': its displacement cannot be followed')
          return
        end if
        unit(st%path_dof, n) = 1.0_dp / size(nodes)
      end do
    end associate
    if (st%path_from_set > 0) then
      ! FROM's nodes may be held (a base): they add nothing then
      associate (nodes => model%node_sets(st%path_from_set)%nodes)
        do i = 1, size(nodes)
          unit(st%path_dof, nodes(i)) = unit(st%path_dof, nodes(i)) - 1.0_dp / size(nodes)
        end do
      end associate
    end if
    ! The mean displacement in direction DOF is e . u (nodal systems rotate e as they rotate loads).
    call to_equations(an%eq%map, unit, pt%e)
    if (all(pt%e == 0.0_dp)) then
      call input_error(error, st%file, st%line, path // ': NSET''s mean displacement less FROM''s is ' // &
                       'no displacement of a free DOF (the two sets move together)')
    end if
  end subroutine start_path

  !> One (sub)step of the path from the committed state: the constraint `mode` with `target`
  !! (the arc length, the mean displacement increment, or the load factor increment). Ends
  !! with the trial state (u_t, the points) at the step's end, its increment du and dlam, and
  !! an%path%f_applied back at f0 + pt%lam df; ok is false when the step does not converge
  !! within MAXIT iterations (or the arc misses the equilibrium path: no real root).
  subroutine path_substep(model, an, c, exact, pt, mode, target, dlam, du, r, rnorm, pnorm, iters, ok, summary, &
                          error, notes)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(controls_t), intent(in) :: c
    logical, intent(in) :: exact              !! full Newton: the iterate's tangent every iteration
    type(path_t), intent(inout) :: pt
    integer, intent(in) :: mode
    real(dp), intent(in) :: target
    real(dp), intent(out) :: dlam
    real(dp), allocatable, intent(out) :: du(:)
    real(dp), intent(inout) :: r(:)
    real(dp), intent(out) :: rnorm, pnorm
    integer, intent(out) :: iters
    logical, intent(out) :: ok
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable, intent(inout) :: notes
    real(dp), allocatable :: dut(:), dur(:), b(:), zero(:)
    real(dp) :: r_first, x, l
    integer :: m

    ok = .false.
    iters = 1
    dlam = 0.0_dp
    allocate (zero(size(model%groups)), du(size(r)))
    zero = 0.0_dp
    du = 0.0_dp
    dut = pt%q
    call an%eq%solve(dut, error)
    if (allocated(error)) return
    select case (mode)
    case (constrain_arc)
      ! The stage's first arc: the displacement a load step of 1 / STEPS gives on this stiffness.
      if (.not. pt%arc > 0.0_dp) then
        pt%arc0 = norm2(dut) / pt%steps
        pt%arc = pt%arc0
      end if
      l = pt%arc
      dlam = l / norm2(dut)
      if (size(pt%du_prev) > 0) then
        if (dot_product(dut, pt%du_prev) < 0.0_dp) dlam = -dlam
      end if
    case (constrain_displacement)
      x = dot_product(pt%e, dut)
      if (x == 0.0_dp) return      ! the load does not move the DOF on this stiffness: cut back
      dlam = target / x
    case default
      dlam = target
    end select
    du = dlam * dut
    call set_trial(model, an)
    call add_free(an, du, an%path%u_t)
    call evaluate()
    r_first = rnorm
    do m = 1, c%max_iterations
      if (.not. (rnorm <= huge(rnorm))) exit
      if (rnorm / pnorm < c%delta1 .or. rnorm < c%delta2) then
        ok = .true.
        exit
      end if
      if (m > 1 .and. rnorm > 1.0e4_dp * r_first) exit
      if (exact) then
        call factorize_tangent(model, an, .false., summary, error, trial=.true., exact=.true.)
        ! singular at a limit point or on a plateau: the elastic stiffness instead (the constraint
        ! keeps the bordered system regular)
        if (allocated(error)) then
          deallocate (error)
          call factorize_tangent(model, an, .true., summary, error)
        end if
        if (allocated(error)) exit
        dut = pt%q
        call an%eq%solve(dut, error)
        if (allocated(error)) exit
      end if
      dur = r
      call an%eq%solve(dur, error)
      if (allocated(error)) exit
      select case (mode)
      case (constrain_arc)
        b = du + dur
        x = arc_root(dut, b, du, l)
        if (.not. (abs(x) <= huge(x))) exit      ! no real root: the arc misses the path
      case (constrain_displacement)
        x = -dot_product(pt%e, dur) / dot_product(pt%e, dut)
      case default
        x = 0.0_dp
      end select
      dur = dur + x * dut
      du = du + dur
      dlam = dlam + x
      call add_free(an, dur, an%path%u_t)
      call evaluate()
      iters = m + 1
    end do
    ! the step's last iterate may also converge
    if (.not. ok .and. .not. allocated(error) .and. rnorm <= huge(rnorm)) &
      ok = rnorm / pnorm < c%delta1 .or. rnorm < c%delta2
    an%path%f_applied = pt%f0 + pt%lam * pt%df
  contains
    subroutine evaluate()
      an%path%f_applied = pt%f0 + (pt%lam + dlam) * pt%df
      call update_points(model, an, zero)
      call collect_point_notes(model, an, .true., notes)
      call residual(an, r, rnorm, pnorm)
    end subroutine evaluate
  end subroutine path_substep

  !> The correction x of the load factor that keeps |b + x t| = l (b: the increment with the
  !! residual's correction, t: the tangent's response to the reference load), of the two roots
  !! the one whose increment makes the smallest angle with the iterate's increment du; huge()
  !! where the roots are complex.
  pure real(dp) function arc_root(t, b, du, l) result(x)
    real(dp), intent(in) :: t(:), b(:), du(:)
    real(dp), intent(in) :: l
    real(dp) :: a1, a2, a3, disc, x1, x2
    a1 = dot_product(t, t)
    a2 = 2.0_dp * dot_product(t, b)
    a3 = dot_product(b, b) - l**2
    disc = a2**2 - 4.0_dp * a1 * a3
    x = huge(1.0_dp)
    if (disc < 0.0_dp .or. a1 <= 0.0_dp) return
    ! the numerically stable pair of roots
    x1 = -(a2 + sign(sqrt(disc), a2)) / (2.0_dp * a1)
    x2 = 0.0_dp
    if (x1 /= 0.0_dp) x2 = a3 / (a1 * x1)
    x = x1
    if (dot_product(b + x2 * t, du) > dot_product(b + x1 * t, du)) x = x2
  end function arc_root

end module feps_path_following
