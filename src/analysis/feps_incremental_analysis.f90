!> Staged incremental analysis by the thesis's modified Newton-Raphson family (section 2.6):
!! Euler, modified Euler, Newton-Raphson (tangent each step), modified Newton-Raphson
!! (refactorize when the residual at the end of a step exceeds delta3/delta4) and initial
!! stiffness. Residual formulation: R = P - F_int with stresses updated from the start of the
!! step (eq. 2.3.21), so the unbalanced force of a step is carried into the next (eq. 2.6.4)
!! except by Euler, which drops it. Steps that diverge are cut back (halved) up to a bound; a
!! model that is linear (all materials elastic, no interfaces) is solved with one
!! factorization and one solve per stage whatever the deck asks.
module feps_incremental_analysis
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, err_model, err_solver, str
  use feps_clock, only: wall_clock
  use feps_model, only: model_t, stage_t, controls_t, output_fields_t, method_names, method_euler, method_modified_euler, &
                        method_newton_raphson, method_modified_newton_raphson, method_initial_stiffness, &
                        method_full_newton_raphson
  use feps_dof_map, only: dof_map_t, build_dof_map, build_all_dofs_map
  use feps_sparse_matrix, only: csr_matrix_t, full_pattern
  use feps_umfpack_solver, only: umfpack_solver_t
  use feps_assembly, only: group_kernel_t, build_kernels, build_materials, build_pattern, check_jacobians, &
                           element_dofs, element_stiffness, element_strains, element_internal_force, &
                           scatter_element_matrix, rotate_matrix
  use feps_loads, only: resolve_face_sets, nodal_load_vector, to_equations
  use feps_material, only: material_slot_t, state_open, state_elastic, state_tension
  use feps_tangent_symmetry, only: nearest_symmetric_psd
  use feps_linear_solver, only: linear_solver_t
  use feps_solver_factory, only: new_linear_solver
  use feps_observer, only: observer_t, step_result_t, group_result_t
  implicit none
  private

  !> Totals of a run, for the summary.
  type, public :: analysis_summary_t
    logical :: linear = .false.
    integer :: neq = 0
    integer :: unused_nodes = 0
    integer :: steps = 0
    integer :: iterations = 0
    integer :: factorizations = 0
    integer :: lu_factorizations = 0        !! LU factorizations of exact non-symmetric tangents (full Newton)
    integer :: cutbacks = 0
    integer :: unconverged_steps = 0         !! steps accepted with |R| / |P| above delta1 (carried on)
    integer(i8) :: matrix_nnz = 0
    integer(i8) :: factor_nnz = 0
    real(dp) :: flops = 0.0_dp
    real(dp) :: min_pivot_ratio = 0.0_dp
    real(dp) :: max_pivot_ratio = 0.0_dp
    real(dp) :: min_detj = 0.0_dp
    real(dp) :: time_assembly = 0.0_dp
    real(dp) :: time_factorization = 0.0_dp
    real(dp) :: time_solve = 0.0_dp
    real(dp) :: time_update = 0.0_dp
    real(dp) :: max_displacement = 0.0_dp
    integer :: max_displacement_node = 0
    real(dp) :: applied_force(3) = 0.0_dp
    real(dp) :: reaction_force(3) = 0.0_dp
    character(len=:), allocatable :: solver
    logical :: condition_warning = .false.   !! max/min pivot ratio passed condition_warning
    integer(i8), allocatable :: state_bytes(:)  !! per group: bytes of point state (0: elastic, none kept)
  end type analysis_summary_t

  !> Above this max/min pivot ratio the results may have lost digits: say so.
  real(dp), parameter, public :: condition_warning = 1.0e12_dp

  !> Point states of one group: committed (end of the last step) and trial.
  type :: group_state_t
    real(dp), allocatable :: sig(:, :), eps(:, :)
    integer, allocatable :: state(:)
    real(dp), allocatable :: sig_t(:, :), eps_t(:, :)
    integer, allocatable :: state_t(:)
    real(dp), allocatable :: dtan(:, :, :), dtan_t(:, :, :)   !! nonlinear groups only
    !> Carries point state: a nonlinear material, a group born in a later stage (whose
    !! strains count from its activation) or a prestressed one (whose force is not K u), so
    !! it cannot join the total-strain linear part.
    logical :: nonlinear = .false.
  end type group_state_t

  !> Internal forces of all linear groups as one product K_lin u (global Cartesian DOFs of
  !! every node in an element): linear elements carry no point state at all, and their
  !! stresses are computed only for the steps written.
  type :: linear_part_t
    logical :: present = .false.
    type(dof_map_t) :: map
    type(csr_matrix_t) :: k
  end type linear_part_t

  !> Everything the analysis works on.
  type :: analysis_t
    type(group_kernel_t), allocatable :: kernels(:)
    type(material_slot_t), allocatable :: materials(:)
    type(dof_map_t) :: map
    type(csr_matrix_t) :: a
    class(linear_solver_t), allocatable :: solver
    type(group_state_t), allocatable :: states(:)
    real(dp), allocatable :: u(:, :), u_t(:, :)        !! committed and trial displacements (global)
    real(dp), allocatable :: fint(:, :)                !! internal forces of the trial state (global)
    real(dp), allocatable :: f_ref(:, :)               !! reference (stage-0) loads (global)
    real(dp), allocatable :: f_applied(:, :)           !! external load applied so far (global)
    real(dp), allocatable :: uc(:, :)                  !! constrained values reached (nodal systems)
    logical :: symmetrized = .false.
    logical :: warned_condition = .false.
    type(csr_matrix_t) :: a_full                       !! both triangles: the exact non-symmetric tangent
    type(umfpack_solver_t) :: lu                       !! its LU factors (full Newton, psi /= phi)
    logical :: use_lu = .false.                        !! solve with lu, not solver (set by factorize_tangent)
    integer :: lu_singular = 0                         !! exact tangents found singular (the stand-in was used)
    type(linear_part_t) :: lin
    logical, allocatable :: active(:)                  !! groups active in the current stage
    real(dp), allocatable :: release_force(:, :)       !! load increment of the stage that removes released supports' forces
  end type analysis_t

  public :: run_analysis, check_analysis, is_linear_model

contains

  !> All materials linear and no interfaces: one factorization, one solve per stage.
  logical function is_linear_model(model, materials)
    type(model_t), intent(in) :: model
    type(material_slot_t), intent(in) :: materials(:)
    integer :: m
    is_linear_model = .not. model%has_interfaces()
    do m = 1, size(materials)
      if (.not. materials(m)%m%is_linear()) is_linear_model = .false.
    end do
  end function is_linear_model

  !> Run every stage of the model; report progress and the steps to write to `observer`.
  subroutine run_analysis(model, solver_name, observer, summary, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: solver_name
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(analysis_t) :: an
    real(dp) :: t0, length
    integer :: n

    t0 = wall_clock()
    call set_up(model, solver_name, an, summary, error)
    if (allocated(error)) return
    call init_states(model, an)
    summary%state_bytes = state_bytes(an%states)
    allocate (an%f_ref(3, model%nnode), an%f_applied(3, model%nnode))
    call nodal_load_vector(model, an%kernels, an%f_ref, error, stage=0)
    if (allocated(error)) return
    an%f_applied = 0.0_dp
    summary%time_assembly = wall_clock() - t0

    summary%linear = is_linear_model(model, an%materials)
    if (summary%linear) then
      call observer%progress('linear model (all materials elastic, no interfaces): one factorization, ' // &
                             'one solve per stage')
      call run_linear_stages(model, an, observer, summary, error)
    else
      call run_nonlinear_stages(model, an, observer, summary, error)
    end if
    if (allocated(error)) return

    summary%factor_nnz = an%solver%factor_nnz
    summary%flops = an%solver%flops
    summary%min_pivot_ratio = an%solver%min_pivot_ratio
    summary%max_pivot_ratio = an%solver%max_pivot_ratio
    summary%applied_force = sum(an%f_applied, dim=2)
    summary%reaction_force = 0.0_dp
    do n = 1, model%nnode
      if (any(an%map%constrained(:, n))) summary%reaction_force = summary%reaction_force + an%fint(:, n) - &
                                                                  an%f_applied(:, n)
      length = magnitude(an%u(:, n))
      if (length > summary%max_displacement) then
        summary%max_displacement = length
        summary%max_displacement_node = n
      end if
    end do
  end subroutine run_analysis

  !> Euclidean length without the under- or overflow of the squares that norm2 has in
  !! gfortran (a displacement of 1e-297 mm stays 1e-297, one of 1e200 stays finite).
  pure real(dp) function magnitude(v)
    real(dp), intent(in) :: v(:)
    real(dp) :: scale
    scale = maxval(abs(v))
    magnitude = 0.0_dp
    if (scale > 0.0_dp) magnitude = scale * norm2(v / scale)
  end function magnitude

  !> Everything a run checks before it takes a step, without taking one: elements and their
  !! Jacobians, materials, face sets, DOF numbering, the sparse pattern, the solver's analysis,
  !! and, stage by stage, the loads, the prescribed displacements, the nodes of elements born
  !! later and the factorization of the elastic stiffness of the elements active in the stage
  !! (a missing support or rigid-body mode is found there, as in a run; summary%factor_nnz,
  !! %flops and the pivot ratios are those of the factorization). The same errors as
  !! run_analysis up to that point.
  subroutine check_analysis(model, solver_name, summary, error, observer)
    type(model_t), intent(inout) :: model     !! face sets are resolved into it
    character(len=*), intent(in) :: solver_name
    type(analysis_summary_t), intent(out) :: summary
    type(error_t), allocatable, intent(out) :: error
    class(observer_t), intent(inout), optional :: observer   !! gets one line per stage
    type(analysis_t) :: an
    real(dp), allocatable :: df(:, :), duc(:, :), dps(:), post(:)
    real(dp) :: t0, f(3)
    integer :: s, g
    logical :: changed
    character(len=:), allocatable :: line
    character(len=40) :: buf

    t0 = wall_clock()
    call set_up(model, solver_name, an, summary, error)
    if (allocated(error)) return
    summary%linear = is_linear_model(model, an%materials)
    call init_states(model, an)
    summary%state_bytes = state_bytes(an%states)
    allocate (an%f_ref(3, model%nnode), df(3, model%nnode), duc(3, model%nnode), dps(size(model%groups)))
    call nodal_load_vector(model, an%kernels, an%f_ref, error, stage=0)
    if (allocated(error)) return
    summary%time_assembly = wall_clock() - t0
    allocate (an%f_applied(3, model%nnode))
    an%f_applied = 0.0_dp
    do s = 1, size(model%stages)
      ! as a run reports a failed factorization: a nonlinear run factorizes in the stage's first step
      call start_elastic_stage(model, an, s, summary, changed, error, observer=observer, &
                               name_failed_step=.not. summary%linear)
      if (allocated(error)) return
      call stage_increments(model, an, s, df, duc, dps, error)
      if (allocated(error)) return
      summary%steps = summary%steps + model%stages(s)%steps
      f = sum(df, dim=2)
      summary%applied_force = summary%applied_force + f
      if (.not. present(observer)) cycle
      associate (st => model%stages(s), c => model%stages(s)%controls)
        line = 'stage ' // st%name // ': ' // str(st%steps) // ' steps, ' // &
               trim(merge('linear (one solve)     ', method_names(c%method), summary%linear))
        if (.not. summary%linear) line = line // ', at most ' // str(c%max_iterations) // ' iterations per step'
        write (buf, '(3(1x,es10.3))') f
        line = line // '; load increment' // trim(buf) // ' N; ' // str(count(duc /= 0.0_dp)) // ' DOFs moved'
        do g = 1, size(model%groups)
          if (model%groups(g)%activate_stage == s .and. s > 1) line = line // '; born: ' // model%groups(g)%name
        end do
        do g = 1, size(model%groups)
          if (dps(g) == 0.0_dp) cycle
          write (buf, '(es10.3)') dps(g)
          line = line // '; prestress ' // model%groups(g)%name // ' ' // trim(adjustl(buf)) // ' N'
        end do
        post = model%stage_prestress(s, after=.true.)
        do g = 1, size(model%groups)
          if (post(g) == 0.0_dp) cycle
          write (buf, '(es10.3)') post(g)
          line = line // '; post-tension ' // model%groups(g)%name // ' ' // trim(adjustl(buf)) // ' N (bonded next stage)'
        end do
      end associate
      call observer%progress(line)
    end do
    summary%factor_nnz = an%solver%factor_nnz
    summary%flops = an%solver%flops
    summary%min_pivot_ratio = an%solver%min_pivot_ratio
    summary%max_pivot_ratio = an%solver%max_pivot_ratio
  end subroutine check_analysis

  !> Kernels, materials, Jacobians, face sets, DOF map, pattern and the solver's analysis.
  subroutine set_up(model, solver_name, an, summary, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: solver_name
    type(analysis_t), intent(inout) :: an
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error

    call build_kernels(model, an%kernels, error)
    if (allocated(error)) return
    call build_materials(model, an%materials, error)
    if (allocated(error)) return
    call check_jacobians(model, an%kernels, summary%min_detj, error)
    if (allocated(error)) return
    call resolve_face_sets(model, an%kernels, error)
    if (allocated(error)) return
    call build_dof_map(model, an%map, error)
    if (allocated(error)) return
    summary%neq = an%map%neq
    summary%unused_nodes = an%map%unused_nodes
    if (an%map%neq == 0) then
      call fatal_error(error, err_model, model%deck_file // ': the model has no free degree of freedom')
      return
    end if
    call check_later_supports(model, error)
    if (allocated(error)) return
    call build_pattern(model, an%map, an%a)
    if (allocated(an%a_full%row_ptr)) deallocate (an%a_full%row_ptr, an%a_full%col, an%a_full%val)
    summary%matrix_nnz = an%a%nnz()
    call new_linear_solver(solver_name, an%solver, error)
    if (allocated(error)) return
    summary%solver = an%solver%name()
    call an%solver%analyze(an%a, error)
  end subroutine set_up

  !> The supports of every later stage whose supports change are valid (RELEASE records)
  !! and leave a free DOF: input errors before any solving.
  subroutine check_later_supports(model, error)
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    type(dof_map_t) :: map
    integer :: s
    do s = 2, size(model%stages)
      if (.not. model%supports_change(s)) cycle
      call build_dof_map(model, map, error, stage=s)
      if (allocated(error)) return
      if (map%neq == 0) then
        call fatal_error(error, err_model, model%deck_file // ': stage ' // model%stages(s)%name // &
                         ': the supports leave no free degree of freedom')
        return
      end if
    end do
  end subroutine check_later_supports

  !> At the start of stage s, when FIX or RELEASE records change the supports: number the
  !! equations of the new set; a DOF held from now on stays where it is (its target is its
  !! current displacement), and a released DOF's support force becomes a load at once
  !! (nothing moves) that the stage's increments remove in equal parts over its steps; then
  !! the new pattern is analysed (the caller factorizes). changed is false when nothing changes.
  subroutine change_supports(model, an, s, changed, summary, error, observer)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer, intent(in) :: s
    logical, intent(out) :: changed
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    class(observer_t), intent(inout), optional :: observer
    type(dof_map_t) :: new
    real(dp) :: ul(3), support(3)
    integer :: n, d, nheld, nfreed

    an%release_force = 0.0_dp
    changed = model%supports_change(s)
    if (.not. changed) return
    call build_dof_map(model, new, error, stage=s)
    if (allocated(error)) return
    nheld = 0
    nfreed = 0
    do n = 1, model%nnode
      if (.not. new%used(n)) cycle
      if (all(new%constrained(:, n) .eqv. an%map%constrained(:, n))) cycle
      ul = matmul(transpose(an%map%basis(:, :, n)), an%u(:, n))
      support = matmul(transpose(an%map%basis(:, :, n)), an%fint(:, n) - an%f_applied(:, n))
      do d = 1, 3
        if (new%constrained(d, n) .and. .not. an%map%constrained(d, n)) then
          an%uc(d, n) = ul(d)
          nheld = nheld + 1
        else if (an%map%constrained(d, n) .and. .not. new%constrained(d, n)) then
          an%f_applied(:, n) = an%f_applied(:, n) + support(d) * an%map%basis(:, d, n)
          an%release_force(:, n) = an%release_force(:, n) - support(d) * an%map%basis(:, d, n)
          nfreed = nfreed + 1
        end if
      end do
    end do
    an%map = new
    summary%neq = an%map%neq
    call build_pattern(model, an%map, an%a)
    if (allocated(an%a_full%row_ptr)) deallocate (an%a_full%row_ptr, an%a_full%col, an%a_full%val)
    summary%matrix_nnz = an%a%nnz()
    call an%solver%analyze(an%a, error)
    if (allocated(error)) return
    if (.not. present(observer)) return
    if (nfreed > 0) then
      call observer%progress('stage ' // model%stages(s)%name // ': supports change: ' // str(nheld) // &
                             ' DOFs held from here, ' // str(nfreed) // ' released (their support forces ' // &
                             'removed over the stage); ' // str(an%map%neq) // ' equations')
    else
      call observer%progress('stage ' // model%stages(s)%name // ': supports change: ' // str(nheld) // &
                             ' DOFs held from here; ' // str(an%map%neq) // ' equations')
    end if
  end subroutine change_supports

  subroutine init_states(model, an)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer :: g, np, nc, q, e
    real(dp), allocatable :: ke(:, :), d(:, :, :)
    integer, allocatable :: dofs(:)
    allocate (an%states(size(model%groups)))
    do g = 1, size(model%groups)
      np = an%kernels(g)%npoints * size(model%groups(g)%connectivity, 2)
      nc = an%kernels(g)%ncomp
      associate (s => an%states(g))
        s%nonlinear = .not. an%materials(model%groups(g)%material)%m%is_linear() .or. &
                      model%groups(g)%activate_stage > 1 .or. model%is_prestressed(g)
        if (.not. s%nonlinear) then
          an%lin%present = .true.
          cycle
        end if
        allocate (s%sig(nc, np), s%eps(nc, np), s%state(np), s%sig_t(nc, np), s%eps_t(nc, np), s%state_t(np))
        s%sig = 0.0_dp
        s%eps = 0.0_dp
        s%state = 0
        s%sig_t = 0.0_dp
        s%eps_t = 0.0_dp
        s%state_t = 0
        if (s%nonlinear) then
          allocate (s%dtan(nc, nc, np), s%dtan_t(nc, nc, np))
          do q = 1, np
            call an%materials(model%groups(g)%material)%m%elastic_tangent(s%dtan(:, :, q))
          end do
          s%dtan_t = s%dtan
        end if
      end associate
    end do
    if (an%lin%present) then
      ! K_lin: the elastic stiffness of the linear groups over all DOFs, global directions.
      call build_all_dofs_map(model, an%lin%map)
      call build_pattern(model, an%lin%map, an%lin%k, only_groups=.not. nonlinear_groups(an))
      do g = 1, size(model%groups)
        if (an%states(g)%nonlinear) cycle
        np = an%kernels(g)%npoints
        nc = an%kernels(g)%ncomp
        allocate (ke(3 * an%kernels(g)%nnodes, 3 * an%kernels(g)%nnodes), d(nc, nc, np), dofs(3 * an%kernels(g)%nnodes))
        do q = 1, np
          call an%materials(model%groups(g)%material)%m%elastic_tangent(d(:, :, q))
        end do
        do e = 1, size(model%groups(g)%connectivity, 2)
          call element_stiffness(an%kernels(g), model%coords(:, model%groups(g)%connectivity(:, e)), d, ke)
          call element_dofs(an%lin%map, model%groups(g)%connectivity(:, e), dofs)
          call scatter_element_matrix(dofs, ke, an%lin%k)
        end do
        deallocate (ke, d, dofs)
      end do
    end if
    allocate (an%active(size(model%groups)))
    an%active = model%groups(:)%activate_stage <= 1
    allocate (an%u(3, model%nnode), an%u_t(3, model%nnode), an%fint(3, model%nnode), an%uc(3, model%nnode))
    an%u = 0.0_dp
    an%u_t = 0.0_dp
    an%fint = 0.0_dp
    an%uc = 0.0_dp
    allocate (an%release_force(3, model%nnode))
    an%release_force = 0.0_dp
  end subroutine init_states

  !> Memory held per group for point states (stresses, strains, flags, tangents; committed
  !! and trial), to show that elastic groups keep none.
  pure function state_bytes(states) result(bytes)
    type(group_state_t), intent(in) :: states(:)
    integer(i8) :: bytes(size(states))
    integer :: g
    bytes = 0
    do g = 1, size(states)
      associate (s => states(g))
        if (allocated(s%sig)) bytes(g) = bytes(g) + 2 * storage_size(s%sig, i8) / 8 * size(s%sig, kind=i8)
        if (allocated(s%eps)) bytes(g) = bytes(g) + 2 * storage_size(s%eps, i8) / 8 * size(s%eps, kind=i8)
        if (allocated(s%state)) bytes(g) = bytes(g) + 2 * storage_size(s%state, i8) / 8 * size(s%state, kind=i8)
        if (allocated(s%dtan)) bytes(g) = bytes(g) + 2 * storage_size(s%dtan, i8) / 8 * size(s%dtan, kind=i8)
      end associate
    end do
  end function state_bytes

  pure function nonlinear_groups(an) result(mask)
    type(analysis_t), intent(in) :: an
    logical :: mask(size(an%states))
    integer :: g
    do g = 1, size(an%states)
      mask(g) = an%states(g)%nonlinear
    end do
  end function nonlinear_groups

  !> f <- f + K_lin u for the linear groups (global Cartesian components).
  subroutine add_linear_forces(an, u, f)
    type(analysis_t), intent(in) :: an
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(inout) :: f(:, :)
    real(dp), allocatable :: x(:), y(:)
    integer :: n, d
    if (.not. an%lin%present) return
    allocate (x(an%lin%map%neq), y(an%lin%map%neq))
    do n = 1, size(u, 2)
      do d = 1, 3
        if (an%lin%map%eq(d, n) > 0) x(an%lin%map%eq(d, n)) = u(d, n)
      end do
    end do
    call an%lin%k%multiply(x, y)
    do n = 1, size(u, 2)
      do d = 1, 3
        if (an%lin%map%eq(d, n) > 0) f(d, n) = f(d, n) + y(an%lin%map%eq(d, n))
      end do
    end do
  end subroutine add_linear_forces

  !> The start of a stage on the elastic stiffness (the linear driver, feps --check): the
  !! stage's supports and born groups, then a factorization when either changed (and in the
  !! first stage). With name_failed_step a failed factorization names stage, step 1 and load
  !! factor, as the nonlinear driver reports it.
  subroutine start_elastic_stage(model, an, s, summary, changed, error, observer, name_failed_step)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer, intent(in) :: s
    type(analysis_summary_t), intent(inout) :: summary
    logical, intent(out) :: changed
    type(error_t), allocatable, intent(out) :: error
    class(observer_t), intent(inout), optional :: observer
    logical, intent(in), optional :: name_failed_step
    logical :: born
    call change_supports(model, an, s, changed, summary, error, observer)
    if (allocated(error)) return
    call activate_groups(model, an, s, born)
    if (.not. (s == 1 .or. born .or. changed)) return
    call check_born_nodes(model, an, s, error)
    if (allocated(error)) return
    call factorize_tangent(model, an, .true., summary, error)
    if (.not. allocated(error) .or. .not. present(name_failed_step)) return
    if (name_failed_step) call name_step(error, model%stages(s), 1, real(s - 1, dp))
  end subroutine start_elastic_stage

  !> Activate the groups born in stage s (true if there are any). Their point states are still
  !! zero, so their strains count from the displacement at the start of the stage. Bars
  !! post-tensioned in stage s - 1 are born carrying that force, which until now loaded their
  !! nodes: the load goes, and the same forces are now the bars' own, so the balance holds.
  subroutine activate_groups(model, an, s, any_born)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer, intent(in) :: s
    logical, intent(out) :: any_born
    real(dp) :: tension(size(model%groups))
    integer :: g
    any_born = .false.
    tension = 0.0_dp
    if (s > 1) tension = model%stage_prestress(s - 1, after=.true.)
    do g = 1, size(model%groups)
      if (model%groups(g)%activate_stage /= s .or. s == 1) cycle
      an%active(g) = .true.
      any_born = .true.
      if (tension(g) /= 0.0_dp) then
        an%states(g)%sig = tension(g)
        an%states(g)%sig_t = tension(g)
      end if
    end do
    call add_bar_forces(model, an, merge(tension, 0.0_dp, model%groups(:)%activate_stage == s), 1.0_dp, &
                        an%f_applied)
  end subroutine activate_groups

  !> f <- f + sign * the nodal forces of the bars of each group g at the axial force force(g)
  !! (global components; groups with force(g) = 0 are skipped).
  subroutine add_bar_forces(model, an, force, sign, f)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    real(dp), intent(in) :: force(:)
    real(dp), intent(in) :: sign
    real(dp), intent(inout) :: f(:, :)
    real(dp), allocatable :: sig(:, :), fe(:)
    integer :: g, e
    do g = 1, size(model%groups)
      if (force(g) == 0.0_dp) cycle
      associate (conn => model%groups(g)%connectivity, k => an%kernels(g))
        allocate (sig(k%ncomp, k%npoints), fe(3 * k%nnodes))
        sig = force(g)
        do e = 1, size(conn, 2)
          call element_internal_force(k, model%coords(:, conn(:, e)), sig, fe)
          f(:, conn(:, e)) = f(:, conn(:, e)) + sign * reshape(fe, [3, k%nnodes])
        end do
        deallocate (sig, fe)
      end associate
    end do
  end subroutine add_bar_forces

  !> A free DOF whose node touches no active element has no stiffness: name it (and the group
  !! that will bring it) rather than let the factorization find a zero pivot.
  subroutine check_born_nodes(model, an, s, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: s
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: carried(:)
    integer :: g, n, d, later
    if (all(an%active)) return
    allocate (carried(model%nnode))
    carried = .false.
    do g = 1, size(model%groups)
      if (an%active(g)) carried(pack(model%groups(g)%connectivity, .true.)) = .true.
    end do
    do n = 1, model%nnode
      if (carried(n)) cycle
      do d = 1, 3
        if (an%map%eq(d, n) == 0) cycle
        later = 0
        do g = 1, size(model%groups)
          if (.not. an%active(g) .and. any(model%groups(g)%connectivity == n)) later = g
        end do
        if (later == 0) cycle   ! a node of no element at all: the DOF map does not number it
        call fatal_error(error, err_model, model%deck_file // ': stage ' // model%stages(s)%name // ': ' // &
                         an%map%dof_name(an%map%eq(d, n)) // ' has no stiffness: its node belongs only to ' // &
                         'elements not yet active (group ' // model%groups(later)%name // ', ACTIVATE in stage ' // &
                         model%stages(model%groups(later)%activate_stage)%name // '); hold it (FIX, DISPLACE) ' // &
                         'or activate its elements earlier', item=an%map%eq(d, n))
        return
      end do
    end do
  end subroutine check_born_nodes

  !> Increments of one whole stage: external forces (global) and constrained values (nodal).
  subroutine stage_increments(model, an, s, df, duc, dps, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: s
    real(dp), intent(out) :: df(:, :), duc(:, :)
    real(dp), intent(out) :: dps(:)      !! prestress force added to each group's bars
    type(error_t), allocatable, intent(out) :: error
    integer :: c, k, n
    real(dp) :: frac
    dps = model%stage_prestress(s)
    call nodal_load_vector(model, an%kernels, df, error, stage=s)
    if (allocated(error)) return
    ! Post-tensioned bars, not yet bonded: their force pulls on their nodes as a load.
    call add_bar_forces(model, an, model%stage_prestress(s, after=.true.), -1.0_dp, df)
    frac = model%stages(s)%load_fraction
    df = df + frac * an%f_ref
    if (allocated(an%release_force)) df = df + an%release_force
    duc = 0.0_dp
    do c = 1, size(model%constraints)
      associate (con => model%constraints(c))
        if (con%stage /= 0 .and. con%stage /= s) cycle
        do k = 1, size(model%node_sets(con%node_set)%nodes)
          n = model%node_sets(con%node_set)%nodes(k)
          if (con%stage == 0) then
            duc(con%dof, n) = frac * con%value
          else
            duc(con%dof, n) = con%value
          end if
        end do
      end associate
    end do
  end subroutine stage_increments

  ! ---------------------------------------------------------------------------------------
  ! Linear models
  ! ---------------------------------------------------------------------------------------

  subroutine run_linear_stages(model, an, observer, summary, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: df(:, :), duc(:, :), dps(:), r(:)
    real(dp) :: t0, rnorm, pnorm, r_scale
    integer :: s, step
    logical :: changed

    allocate (df(3, model%nnode), duc(3, model%nnode), dps(size(model%groups)), r(an%map%neq))
    step = 0
    do s = 1, size(model%stages)
      call start_elastic_stage(model, an, s, summary, changed, error, observer=observer)
      if (allocated(error)) return
      if (changed) then
        deallocate (r)
        allocate (r(an%map%neq))
      end if
      call stage_increments(model, an, s, df, duc, dps, error)
      if (allocated(error)) return
      an%f_applied = an%f_applied + df
      an%uc = an%uc + duc
      ! Move the constrained DOFs, then one solve for the free ones.
      call set_trial(model, an)
      call update_points(model, an, dps)
      call residual(an, r, rnorm, pnorm)
      r_scale = rnorm
      t0 = wall_clock()
      call an%solver%solve(r, error)
      if (allocated(error)) return
      summary%time_solve = summary%time_solve + wall_clock() - t0
      call add_free(an, r, an%u_t)
      call update_points(model, an, dps)
      call residual(an, r, rnorm, pnorm)
      ! A stage loaded only by a prestress (a band on a free pipe) has no load and no
      ! reaction: its initial out-of-balance force is the scale, as in substep.
      if (pnorm <= 1.0e-8_dp * r_scale) pnorm = r_scale
      call commit(an)
      step = step + model%stages(s)%steps
      summary%steps = step
      summary%iterations = summary%iterations + 1
      call observer%progress(progress_line(s, model%stages(s)%steps, model%stages(s)%steps, real(s, dp), 1, &
                                           rnorm / pnorm, summary%factorizations, 0))
      call report_step(model, an, observer, step, s, model%stages(s)%steps, real(s, dp), 1, rnorm / pnorm, error)
      if (allocated(error)) return
    end do
  end subroutine run_linear_stages

  ! ---------------------------------------------------------------------------------------
  ! Nonlinear models
  ! ---------------------------------------------------------------------------------------

  subroutine run_nonlinear_stages(model, an, observer, summary, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    class(observer_t), intent(inout) :: observer
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: df(:, :), duc(:, :), dps(:), r(:)
    real(dp) :: h, done, rnorm, pnorm, rel_prev, abs_prev
    integer :: s, k, step, iters, cut, nfact0, iters_step, opened
    character(len=:), allocatable :: step_notes, run_notes
    logical :: ok, need_factor, have_factor, step_unconverged, born, changed
    logical :: elastic_retry     !! the next factorization is the elastic stiffness (a cut-back under modified NR)
    logical, allocatable :: fully_open(:)

    allocate (df(3, model%nnode), duc(3, model%nnode), dps(size(model%groups)), r(an%map%neq), &
              fully_open(size(model%groups)))
    fully_open = .false.
    step = 0
    have_factor = .false.
    elastic_retry = .false.
    rel_prev = 0.0_dp
    abs_prev = 0.0_dp
    do s = 1, size(model%stages)
      associate (st => model%stages(s), c => model%stages(s)%controls)
        call change_supports(model, an, s, changed, summary, error, observer)
        if (allocated(error)) return
        if (changed) then
          deallocate (r)
          allocate (r(an%map%neq))
          have_factor = .false.     ! a new set of equations: factorize again, whatever the method
        end if
        call activate_groups(model, an, s, born)
        if (s == 1 .or. born .or. changed) then
          call check_born_nodes(model, an, s, error)
          if (allocated(error)) return
          ! New elements change the stiffness: refactorize (the tangent, or the initial
          ! stiffness for that method) before the stage's first step.
          if (s > 1 .and. c%method == method_initial_stiffness) have_factor = .false.
          if (s > 1) rel_prev = huge(1.0_dp)
        end if
        call stage_increments(model, an, s, df, duc, dps, error)
        if (allocated(error)) return
        call observer%progress('stage ' // st%name // ': ' // str(st%steps) // ' steps, method ' // &
                               trim(method_names(c%method)) // ', at most ' // str(c%max_iterations) // &
                               ' iterations per step')
        do k = 1, st%steps
          step = step + 1
          done = 0.0_dp
          h = 1.0_dp
          cut = 0
          iters_step = 0
          nfact0 = summary%factorizations
          step_unconverged = .false.
          step_notes = ''
          do while (done < 1.0_dp - 1.0e-12_dp)
            h = min(h, 1.0_dp - done)
            ! Which stiffness: the method decides (thesis 2.6.3).
            select case (c%method)
            case (method_initial_stiffness)
              need_factor = .not. have_factor
            case (method_modified_newton_raphson)
              need_factor = .not. have_factor .or. rel_prev > c%delta3 .or. abs_prev > c%delta4
            case default
              need_factor = .true.
            end select
            if (need_factor) then
              call factorize_tangent(model, an, c%method == method_initial_stiffness .or. .not. have_factor &
                                     .or. elastic_retry, summary, error, exact=c%method == method_full_newton_raphson)
              if (allocated(error)) then
                call name_step(error, st, k, s - 1 + (k - 1 + done) / st%steps)
                return
              end if
              have_factor = .true.
              elastic_retry = .false.
            end if
            call substep(model, an, c, df * (h / st%steps), duc * (h / st%steps), dps * (h / st%steps), r, &
                         rnorm, pnorm, iters, ok, summary, error, step_notes)
            if (allocated(error)) return
            iters_step = iters_step + iters
            if (ok) then
              done = done + h
              rel_prev = rnorm / pnorm
              abs_prev = rnorm
              if (.not. (rel_prev < c%delta1 .or. rnorm < c%delta2)) step_unconverged = .true.
              call commit(an)
              call collect_point_notes(model, an, .false., run_notes)
              an%f_applied = an%f_applied + df * (h / st%steps)
              an%uc = an%uc + duc * (h / st%steps)
            else
              cut = cut + 1
              summary%cutbacks = summary%cutbacks + 1
              opened = newly_open_points(an)
              call restore(an)
              if (cut > c%max_cutbacks) then
                call stop_error(model, an, r, st, k, s - 1 + (k - 1 + done + h) / st%steps, rnorm / pnorm, &
                                cut > c%max_cutbacks, opened, step_notes, error)
                return
              end if
              h = h / 2.0_dp
              ! After a cut-back, start again from a new factorization: the tangent of the
              ! committed state, except under modified Newton-Raphson, which keeps its factor
              ! for the whole step. There the committed tangent may be what failed: points at
              ! the yield surface or in the tension zone that unload have their elastic
              ! stiffness, far stiffer than their tangent, and a fixed tangent softer than the
              ! response overshoots by the same ratio at every iteration whatever the step size
              ! (chapter 9's PR with a 6 MPa band: the same residual after all ten cut-backs).
              ! The elastic stiffness, the thesis's initial one, is never softer.
              if (c%method /= method_initial_stiffness) rel_prev = huge(1.0_dp)
              elastic_retry = c%method == method_modified_newton_raphson
              call observer%progress('  step ' // str(k) // ' diverged: cut back to ' // str(h) // ' of a step')
            end if
          end do
          summary%steps = step
          summary%iterations = summary%iterations + iters_step
          if (step_unconverged) summary%unconverged_steps = summary%unconverged_steps + 1
          call observer%progress(progress_line(s, k, st%steps, s - 1 + real(k, dp) / st%steps, iters_step, &
                                               rel_prev, summary%factorizations, summary%factorizations - nfact0) &
                                 // trim(merge('  (not converged: carried) ', '                           ', &
                                                step_unconverged)))
          call report_open_interfaces(model, an, observer, fully_open)
          if (writes_step(st, k)) then
            call report_step(model, an, observer, step, s, k, s - 1 + real(k, dp) / st%steps, iters_step, &
                             rel_prev, error)
            if (allocated(error)) return
          end if
        end do
      end associate
    end do
    if (summary%lu_factorizations > 0) call observer%progress('note: ' // str(summary%lu_factorizations) // &
      ' tangents were non-symmetric (non-associated flow, psi /= phi, or a gap closing within a step): ' // &
      'factorized as they are by UMFPACK (LU)')
    if (an%lu_singular > 0) call observer%progress('note: ' // str(an%lu_singular) // ' exact non-symmetric ' // &
      'tangents were singular (a body held only by faces sliding without dilation): their nearest symmetric ' // &
      'positive semi-definite stand-ins were factorized')
    if (allocated(run_notes)) then
      if (len(run_notes) > 0) call observer%progress('note: ' // run_notes)
    end if
    if (an%symmetrized) call observer%progress('note: the tangent was non-symmetric at some points (non-' // &
                                               'associated flow, psi /= phi, or a gap closing within a step); ' // &
                                               'the nearest symmetric positive semi-definite matrix was ' // &
                                               'factorized and the exact residual iterated on')
  end subroutine run_nonlinear_stages

  !> Say when an interface group opens completely (only the residual gap stiffness then holds
  !! what it joined) and when it closes again.
  subroutine report_open_interfaces(model, an, observer, fully_open)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    class(observer_t), intent(inout) :: observer
    logical, intent(inout) :: fully_open(:)
    integer :: g
    logical :: now
    do g = 1, size(model%groups)
      if (.not. an%kernels(g)%is_interface) cycle
      now = all(an%states(g)%state == state_open)
      if (now .and. .not. fully_open(g)) then
        call observer%progress('note: interface group ' // model%groups(g)%name // ' is fully open (' // &
                               str(size(an%states(g)%state)) // ' points): only the residual gap stiffness ' // &
                               'holds what it joined')
      else if (fully_open(g) .and. .not. now) then
        call observer%progress('note: interface group ' // model%groups(g)%name // ' is in contact again')
      end if
      fully_open(g) = now
    end do
  end subroutine report_open_interfaces

  pure logical function writes_step(st, k)
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k
    if (st%output_every > 0) then
      writes_step = mod(k, st%output_every) == 0 .or. k == st%steps
    else
      writes_step = k == st%steps
    end if
  end function writes_step

  !> One (sub)step: move the constrained DOFs by duc, apply df, iterate on the residual.
  !! ok is false when the step diverges (non-finite or growing residual, or iterations run out
  !! far from convergence).
  subroutine substep(model, an, c, df, duc, dps, r, rnorm, pnorm, iters, ok, summary, error, notes)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(controls_t), intent(in) :: c
    real(dp), intent(in) :: df(:, :), duc(:, :)
    real(dp), intent(in) :: dps(:)          !! prestress force added to each group's bars
    real(dp), intent(inout) :: r(:)
    real(dp), intent(out) :: rnorm, pnorm
    integer, intent(out) :: iters
    logical, intent(out) :: ok
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    !> materials' notes about the states of every iterate (collect_point_notes)
    character(len=:), allocatable, intent(inout) :: notes
    real(dp), allocatable :: r_carry(:)
    real(dp) :: t0, r_first, rel, r_scale
    integer :: m, npairs
    logical :: use_bfgs
    real(dp), allocatable :: s_hist(:, :), y_hist(:, :), rho(:), r_old(:)

    if (c%method == method_euler) then
      ! Euler drops the unbalanced force of the previous step (eq. 2.6.4 not applied).
      allocate (r_carry(size(r)))
      call committed_residual(model, an, r_carry)
    end if
    an%f_applied = an%f_applied + df
    an%uc = an%uc + duc
    call set_trial(model, an)
    call update_points(model, an, dps)
    call collect_point_notes(model, an, .true., notes)
    call residual(an, r, rnorm, pnorm)
    if (allocated(r_carry)) r = r - r_carry
    r_scale = rnorm
    ok = .true.
    r_first = -1.0_dp
    iters = 0
    ! Full Newton refactorizes every iteration: quasi-Newton pairs built on an earlier factor
    ! would not describe the new one, so ACCELERATION=bfgs does not apply to it.
    use_bfgs = c%bfgs .and. c%max_iterations > 1 .and. c%method /= method_full_newton_raphson
    if (use_bfgs) then
      allocate (s_hist(size(r), c%max_iterations), y_hist(size(r), c%max_iterations), rho(c%max_iterations), &
                r_old(size(r)))
      npairs = 0
    end if
    do m = 1, c%max_iterations
      if (c%method == method_full_newton_raphson .and. m > 1) then
        ! Full Newton: the consistent tangent of the current iterate, refactorized every iteration
        ! (factorize_tangent times its assembly and factorization itself).
        call factorize_tangent(model, an, .false., summary, error, trial=.true., exact=.true.)
        if (allocated(error)) exit
      end if
      t0 = wall_clock()
      if (use_bfgs) then
        r_old = r
        call bfgs_direction(an, s_hist(:, 1:npairs), y_hist(:, 1:npairs), rho(1:npairs), r, error)
      else if (an%use_lu) then
        call an%lu%solve(r, error)
      else
        call an%solver%solve(r, error)
      end if
      if (allocated(error)) exit
      summary%time_solve = summary%time_solve + wall_clock() - t0
      call add_free(an, r, an%u_t)
      if (use_bfgs) s_hist(:, npairs + 1) = r
      t0 = wall_clock()
      call update_points(model, an, dps)
      call collect_point_notes(model, an, .true., notes)
      summary%time_update = summary%time_update + wall_clock() - t0
      call residual(an, r, rnorm, pnorm)
      if (use_bfgs) call bfgs_add_pair(s_hist, y_hist, rho, npairs, r_old, r)
      ! The step's initial out-of-balance force is the scale only when load and reactions
      ! vanish (a block lifted off: no load, no reaction, no stress).
      if (pnorm <= 1.0e-8_dp * r_scale) pnorm = r_scale
      iters = m
      rel = rnorm / pnorm
      if (.not. (rnorm <= huge(rnorm))) then
        ok = .false.
        exit
      end if
      if (r_first < 0.0_dp) r_first = rnorm
      if (rel < c%delta1 .or. rnorm < c%delta2) exit
      if (m > 1 .and. rnorm > 1.0e4_dp * r_first) then
        ok = .false.
        exit
      end if
    end do
    ! Undo the step's load and constraint increments; the caller applies them on success.
    an%f_applied = an%f_applied - df
    an%uc = an%uc - duc
    if (allocated(error)) return
    if (.not. ok) return
    rel = rnorm / pnorm
    ! Newton-Raphson must converge; the other methods may end a step unconverged and carry the
    ! unbalanced force (thesis 2.6.3), unless it exceeds the divergence limit.
    ! The one-iteration Euler methods leave transitions (a gap opening, yield) unbalanced by
    ! design and correct them in the next step: for them only an unbalanced force larger than
    ! the load itself is divergence.
    select case (c%method)
    case (method_newton_raphson, method_full_newton_raphson)
      ok = rel < c%delta1 .or. rnorm < c%delta2
    case (method_euler, method_modified_euler)
      ok = rel < max(1.0_dp, c%divergence)
    case default
      ok = rel < max(c%divergence, c%delta1) .or. rnorm < c%delta2
    end select
  end subroutine substep

  !> Quasi-Newton direction d = H r by the two-loop recursion of the BFGS inverse update
  !! (Matthies and Strang 1979) with the factorized stiffness K as H0 = K^-1; r is overwritten by
  !! d. Pairs of the step's earlier iterations: s (displacement change), y (change of the
  !! internal forces, = -change of the residual), rho = 1 / (s . y) > 0. With no pair this is
  !! the plain solve.
  subroutine bfgs_direction(an, s_hist, y_hist, rho, r, error)
    type(analysis_t), intent(inout) :: an
    real(dp), intent(in) :: s_hist(:, :), y_hist(:, :), rho(:)
    real(dp), intent(inout) :: r(:)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: alpha(size(rho)), beta
    integer :: i
    do i = size(rho), 1, -1
      alpha(i) = rho(i) * dot_product(s_hist(:, i), r)
      r = r - alpha(i) * y_hist(:, i)
    end do
    call an%solver%solve(r, error)
    if (allocated(error)) return
    do i = 1, size(rho)
      beta = rho(i) * dot_product(y_hist(:, i), r)
      r = r + (alpha(i) - beta) * s_hist(:, i)
    end do
  end subroutine bfgs_direction

  !> Keep the secant pair of the iteration just done (s already in column npairs + 1) when it
  !! has positive curvature. When the residual grew (a gap opened or a point started to slide:
  !! the pairs describe a response that no longer holds) drop every pair and start again from
  !! the factorized stiffness.
  pure subroutine bfgs_add_pair(s_hist, y_hist, rho, npairs, r_old, r)
    real(dp), intent(inout) :: s_hist(:, :), y_hist(:, :), rho(:)
    integer, intent(inout) :: npairs
    real(dp), intent(in) :: r_old(:), r(:)
    real(dp) :: sy
    y_hist(:, npairs + 1) = r_old - r
    sy = dot_product(s_hist(:, npairs + 1), y_hist(:, npairs + 1))
    if (norm2(r) > norm2(r_old)) then
      npairs = 0
    else if (sy > 1.0e-10_dp * norm2(s_hist(:, npairs + 1)) * norm2(y_hist(:, npairs + 1))) then
      npairs = npairs + 1
      rho(npairs) = 1.0_dp / sy
    end if
  end subroutine bfgs_add_pair

  !> Residual of the committed state (R_n of eq. 2.6.3) on the free equations.
  subroutine committed_residual(model, an, r)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    real(dp), intent(out) :: r(:)
    real(dp), allocatable :: f(:, :), rf(:)
    integer :: g, e, q0, np
    real(dp), allocatable :: fe(:)
    allocate (f(3, model%nnode))
    f = 0.0_dp
    call add_linear_forces(an, an%u, f)
    do g = 1, size(model%groups)
      if (.not. an%states(g)%nonlinear) cycle
      np = an%kernels(g)%npoints
      allocate (fe(3 * an%kernels(g)%nnodes))
      do e = 1, size(model%groups(g)%connectivity, 2)
        q0 = (e - 1) * np
        call element_internal_force(an%kernels(g), model%coords(:, model%groups(g)%connectivity(:, e)), &
                                    an%states(g)%sig(:, q0 + 1:q0 + np), fe)
        f(:, model%groups(g)%connectivity(:, e)) = f(:, model%groups(g)%connectivity(:, e)) + &
                                                   reshape(fe, [3, an%kernels(g)%nnodes])
      end do
      deallocate (fe)
    end do
    allocate (rf(size(r)))
    call to_equations(an%map, an%f_applied - f, rf)
    r = rf
  end subroutine committed_residual

  !> Trial displacements: the committed ones with the constrained DOFs moved to their
  !! current targets an%uc (nodal systems).
  subroutine set_trial(model, an)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer :: n, d
    real(dp) :: ul(3)
    do n = 1, model%nnode
      if (.not. any(an%map%constrained(:, n))) then
        an%u_t(:, n) = an%u(:, n)
        cycle
      end if
      ul = matmul(transpose(an%map%basis(:, :, n)), an%u(:, n))
      do d = 1, 3
        if (an%map%constrained(d, n)) ul(d) = an%uc(d, n)
      end do
      an%u_t(:, n) = matmul(an%map%basis(:, :, n), ul)
    end do
  end subroutine set_trial

  !> u <- u + dx on the free equations (dx in nodal systems).
  pure subroutine add_free(an, x, u)
    type(analysis_t), intent(in) :: an
    real(dp), intent(in) :: x(:)
    real(dp), intent(inout) :: u(:, :)
    integer :: n, d
    real(dp) :: dl(3)
    do n = 1, size(u, 2)
      if (all(an%map%eq(:, n) == 0)) cycle
      dl = 0.0_dp
      do d = 1, 3
        if (an%map%eq(d, n) > 0) dl(d) = x(an%map%eq(d, n))
      end do
      u(:, n) = u(:, n) + matmul(an%map%basis(:, :, n), dl)
    end do
  end subroutine add_free

  !> Update every point from the committed state with the strain of u_t - u, and sum the
  !! internal forces of the trial state. The bars of group g start from their committed force
  !! plus the prestress increment dps(g).
  subroutine update_points(model, an, dps)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    real(dp), intent(in) :: dps(:)
    integer :: g, e, q, q0, np, nn, nc
    real(dp), allocatable :: xe(:, :), due(:), deps(:, :), fe(:), dtan(:, :)
    an%fint = 0.0_dp
    call add_linear_forces(an, an%u_t, an%fint)
    do g = 1, size(model%groups)
      if (.not. an%states(g)%nonlinear .or. .not. an%active(g)) cycle
      np = an%kernels(g)%npoints
      nn = an%kernels(g)%nnodes
      nc = an%kernels(g)%ncomp
      allocate (xe(3, nn), due(3 * nn), deps(nc, np), fe(3 * nn), dtan(nc, nc))
      associate (s => an%states(g), mat => an%materials(model%groups(g)%material)%m, &
                 conn => model%groups(g)%connectivity)
        do e = 1, size(conn, 2)
          xe = model%coords(:, conn(:, e))
          due = reshape(an%u_t(:, conn(:, e)) - an%u(:, conn(:, e)), [3 * nn])
          call element_strains(an%kernels(g), xe, due, deps)
          q0 = (e - 1) * np
          do q = 1, np
            if (dps(g) == 0.0_dp) then
              call mat%update(s%sig(:, q0 + q), s%eps(:, q0 + q), deps(:, q), s%state(q0 + q), &
                              s%sig_t(:, q0 + q), s%state_t(q0 + q), dtan)
            else
              ! only bars are prestressed: one component, the axial force
              call mat%update(s%sig(:, q0 + q) + dps(g), s%eps(:, q0 + q), deps(:, q), s%state(q0 + q), &
                              s%sig_t(:, q0 + q), s%state_t(q0 + q), dtan)
            end if
            s%eps_t(:, q0 + q) = s%eps(:, q0 + q) + deps(:, q)
            s%dtan_t(:, :, q0 + q) = dtan
          end do
          call element_internal_force(an%kernels(g), xe, s%sig_t(:, q0 + 1:q0 + np), fe)
          an%fint(:, conn(:, e)) = an%fint(:, conn(:, e)) + reshape(fe, [3, nn])
        end do
      end associate
      deallocate (xe, due, deps, fe, dtan)
    end do
  end subroutine update_points

  !> R = P - F_int on the free equations; |R| and the reference |P| (the larger of the applied
  !! load and the support reactions, so displacement-driven steps have a scale too).
  subroutine residual(an, r, rnorm, pnorm)
    type(analysis_t), intent(in) :: an
    real(dp), intent(out) :: r(:)
    real(dp), intent(out) :: rnorm, pnorm
    real(dp), allocatable :: p(:), react(:)
    real(dp) :: fl(3)
    integer :: n, d, k
    allocate (p(size(r)), react(3 * size(an%fint, 2)))
    call to_equations(an%map, an%f_applied - an%fint, r)
    call to_equations(an%map, an%f_applied, p)
    rnorm = norm2(r)
    ! norm2 scales: a sum of squares would overflow for forces near huge() and make the
    ! relative residual zero
    k = 0
    do n = 1, size(an%fint, 2)
      if (.not. any(an%map%constrained(:, n))) cycle
      fl = matmul(transpose(an%map%basis(:, :, n)), an%fint(:, n) - an%f_applied(:, n))
      do d = 1, 3
        if (.not. an%map%constrained(d, n)) cycle
        k = k + 1
        react(k) = fl(d)
      end do
    end do
    pnorm = max(norm2(p), norm2(react(1:k)), tiny(1.0_dp))
  end subroutine residual

  subroutine commit(an)
    type(analysis_t), intent(inout) :: an
    integer :: g
    an%u = an%u_t
    do g = 1, size(an%states)
      if (.not. an%states(g)%nonlinear) cycle
      associate (s => an%states(g))
        s%sig = s%sig_t
        s%eps = s%eps_t
        s%state = s%state_t
        s%dtan = s%dtan_t
      end associate
    end do
  end subroutine commit

  !> Back to the committed state after a failed step.
  subroutine restore(an)
    type(analysis_t), intent(inout) :: an
    integer :: g
    an%u_t = an%u
    do g = 1, size(an%states)
      if (.not. an%states(g)%nonlinear) cycle
      associate (s => an%states(g))
        s%sig_t = s%sig
        s%eps_t = s%eps
        s%state_t = s%state
        s%dtan_t = s%dtan
      end associate
    end do
  end subroutine restore

  !> Assemble and factorize the stiffness: elastic (initial), the committed tangent, or (trial)
  !! the tangent of the current iterate (full Newton-Raphson).
  subroutine factorize_tangent(model, an, elastic, summary, error, trial, exact)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    logical, intent(in) :: elastic
    logical, intent(in), optional :: trial   !! the tangent of the current iterate, not of the committed state
    logical, intent(in), optional :: exact   !! also factorize a non-symmetric tangent as it is (LU)
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: lu_error
    integer :: ieq
    real(dp) :: t0
    logical :: use_trial, nonsymmetric
    use_trial = .false.
    if (present(trial)) use_trial = trial
    ! Non-symmetric points under full Newton: factorize the exact tangent (UMFPACK LU) and
    ! solve with it. Where it is singular (a body held only by faces sliding without
    ! dilation, a neutral equilibrium) the symmetric stand-in below is used instead.
    an%use_lu = .false.
    nonsymmetric = .false.
    if (present(exact) .and. .not. elastic) then
      if (exact) nonsymmetric = any_nonsymmetric_tangent(model, an, use_trial)
    end if
    if (nonsymmetric) then
      t0 = wall_clock()
      if (.not. allocated(an%a_full%row_ptr)) call full_pattern(an%a, an%a_full)
      call assemble_tangent(model, an, elastic, use_trial, .true., an%a_full, nonsymmetric)
      summary%time_assembly = summary%time_assembly + wall_clock() - t0
      t0 = wall_clock()
      call an%lu%factorize(an%a_full, lu_error)
      summary%time_factorization = summary%time_factorization + wall_clock() - t0
      if (.not. allocated(lu_error)) then
        an%use_lu = .true.
        summary%lu_factorizations = an%lu%factorizations
        summary%factorizations = an%solver%factorizations + an%lu%factorizations
        return
      end if
      if (lu_error%code /= err_model) then
        call move_alloc(lu_error, error)
        return
      end if
      an%lu_singular = an%lu_singular + 1
    end if

    t0 = wall_clock()
    call assemble_tangent(model, an, elastic, use_trial, .false., an%a, nonsymmetric)
    summary%time_assembly = summary%time_assembly + wall_clock() - t0
    if (nonsymmetric) an%symmetrized = .true.

    t0 = wall_clock()
    call an%solver%factorize(an%a, error)
    summary%time_factorization = summary%time_factorization + wall_clock() - t0
    if (allocated(error)) then
      ieq = error%item   ! fatal_error reallocates error: keep the item first
      if (ieq > 0 .and. ieq <= an%map%neq) then
        call fatal_error(error, err_model, model%deck_file // ': the stiffness matrix is singular at ' // &
                         an%map%dof_name(ieq) // ': that DOF is not held (an unconstrained rigid-body mode ' // &
                         'or a missing support), or held only through a stiffness contrast beyond double ' // &
                         'precision (pivot below 1e-11 of its diagonal)', item=ieq)
      end if
      return
    end if
    summary%factorizations = an%solver%factorizations + an%lu%factorizations
    if (.not. an%warned_condition .and. an%solver%min_pivot_ratio > 0.0_dp) then
      if (an%solver%max_pivot_ratio / an%solver%min_pivot_ratio > condition_warning) then
        an%warned_condition = .true.
        summary%condition_warning = .true.
      end if
    end if
  end subroutine factorize_tangent

  !> A point tangent that differs from its transpose beyond rounding.
  pure logical function is_nonsymmetric(d)
    real(dp), intent(in) :: d(:, :)
    is_nonsymmetric = any(abs(d - transpose(d)) > 1.0e-12_dp * maxval(abs(d)))
  end function is_nonsymmetric

  !> Whether any point tangent of the active nonlinear groups (committed, or of the current
  !! iterate with `use_trial`) is non-symmetric: a pass over the points, no element matrices.
  pure logical function any_nonsymmetric_tangent(model, an, use_trial) result(found)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    logical, intent(in) :: use_trial
    integer :: g, q
    found = .false.
    do g = 1, size(model%groups)
      if (.not. an%active(g) .or. .not. an%states(g)%nonlinear) cycle
      do q = 1, size(an%states(g)%dtan, 3)
        if (use_trial) then
          found = is_nonsymmetric(an%states(g)%dtan_t(:, :, q))
        else
          found = is_nonsymmetric(an%states(g)%dtan(:, :, q))
        end if
        if (found) return
      end do
    end do
  end function any_nonsymmetric_tangent

  !> Assemble the tangent stiffness into `a`: the lower triangle with every non-symmetric point
  !! tangent replaced by its nearest symmetric positive semi-definite stand-in, or (`exact`)
  !! both triangles with the point tangents as they are. `nonsymmetric` tells whether any
  !! point tangent was non-symmetric.
  subroutine assemble_tangent(model, an, elastic, use_trial, exact, a, nonsymmetric)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    logical, intent(in) :: elastic, use_trial, exact
    type(csr_matrix_t), intent(inout) :: a
    logical, intent(out) :: nonsymmetric
    integer :: g, e, q, np, nn, nc, q0
    real(dp), allocatable :: ke(:, :), d(:, :, :)
    integer, allocatable :: dofs(:)
    nonsymmetric = .false.
    a%val = 0.0_dp
    do g = 1, size(model%groups)
      if (.not. an%active(g)) cycle   ! not yet born: no stiffness
      np = an%kernels(g)%npoints
      nn = an%kernels(g)%nnodes
      nc = an%kernels(g)%ncomp
      allocate (ke(3 * nn, 3 * nn), d(nc, nc, np), dofs(3 * nn))
      associate (s => an%states(g), conn => model%groups(g)%connectivity)
        if (elastic .or. .not. s%nonlinear) then
          do q = 1, np
            call an%materials(model%groups(g)%material)%m%elastic_tangent(d(:, :, q))
          end do
        end if
        do e = 1, size(conn, 2)
          if (.not. (elastic .or. .not. s%nonlinear)) then
            q0 = (e - 1) * np
            do q = 1, np
              if (use_trial) then
                d(:, :, q) = s%dtan_t(:, :, q0 + q)
              else
                d(:, :, q) = s%dtan(:, :, q0 + q)
              end if
              if (is_nonsymmetric(d(:, :, q))) then
                nonsymmetric = .true.
                if (.not. exact) call nearest_symmetric_psd(d(:, :, q))
              end if
            end do
          end if
          call element_stiffness(an%kernels(g), model%coords(:, conn(:, e)), d, ke)
          if (an%map%has_rotations()) call rotate_matrix(an%map, conn(:, e), ke)
          call element_dofs(an%map, conn(:, e), dofs)
          call scatter_element_matrix(dofs, ke, a, both_triangles=exact)
        end do
      end associate
      deallocate (ke, d, dofs)
    end do
  end subroutine assemble_tangent


  subroutine name_step(error, st, k, lf)
    type(error_t), intent(inout) :: error
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k
    real(dp), intent(in) :: lf
    error%message = error%message // ' (stage ' // st%name // ', step ' // str(k) // ', load factor ' // str(lf) // ')'
  end subroutine name_step

  !> Interface points open in the trial state that were not open at the start of the step.
  pure integer function newly_open_points(an) result(n)
    type(analysis_t), intent(in) :: an
    integer :: g
    n = 0
    do g = 1, size(an%states)
      if (.not. an%kernels(g)%is_interface .or. .not. an%states(g)%nonlinear) cycle
      n = n + count(an%states(g)%state_t == state_open .and. an%states(g)%state /= state_open)
    end do
  end function newly_open_points

  !> Add to `notes` (separated by '; ') each material's note about a point state present in
  !! the trial (`trial`) or committed states of the active nonlinear groups, once.
  subroutine collect_point_notes(model, an, trial, notes)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    logical, intent(in) :: trial
    character(len=:), allocatable, intent(inout) :: notes
    character(len=:), allocatable :: note
    integer :: g, state
    logical :: present_
    if (.not. allocated(notes)) notes = ''
    do g = 1, size(an%states)
      if (.not. an%active(g) .or. .not. an%states(g)%nonlinear) cycle
      do state = state_elastic, state_tension
        if (trial) then
          present_ = any(an%states(g)%state_t == state)
        else
          present_ = any(an%states(g)%state == state)
        end if
        if (.not. present_) cycle
        call an%materials(model%groups(g)%material)%m%state_note(state, note)
        if (len(note) == 0 .or. index(notes, note) > 0) cycle
        if (len(notes) > 0) notes = notes // '; '
        notes = notes // note
      end do
    end do
  end subroutine collect_point_notes

  !> The clear stop: step, load factor, residual and the DOF where it is largest; when interface
  !! points opened in the last try, a hint that the load may have passed a limit point.
  subroutine stop_error(model, an, r, st, k, lf, rel, cutbacks_exhausted, opened, notes, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    real(dp), intent(in) :: r(:)
    type(stage_t), intent(in) :: st
    integer, intent(in) :: k
    real(dp), intent(in) :: lf, rel
    logical, intent(in) :: cutbacks_exhausted
    integer, intent(in) :: opened   !! interface points that opened in the last try
    character(len=*), intent(in) :: notes   !! materials' notes about the states the step's iterates reached
    type(error_t), allocatable, intent(out) :: error
    integer :: imax
    character(len=:), allocatable :: why, hint
    imax = maxloc(abs(r), dim=1, mask=r == r)
    if (imax < 1) imax = 1
    if (cutbacks_exhausted) then
      why = 'the step does not converge after ' // str(st%controls%max_cutbacks) // ' cut-backs'
    else
      why = 'the residual is not finite'
    end if
    hint = ''
    if (opened > 0) then
      hint = '; ' // str(opened) // ' interface points opened in the last try, each dropping ' // &
        'its tensile strength c / tan(phi) at once: '
      if (st%controls%method == method_full_newton_raphson) then
        ! Each opening sheds its force onto its neighbours, which may open in turn: the
        ! iterations follow that cascade point by point (model B FD2 needs 75 at its unzipping).
        hint = hint // 'the opening may spread further than ' // str(st%controls%max_iterations) // &
          ' iterations can follow (STAGE ..., MAXIT=400 or feps --maxit 400), or the load passed a limit point'
      else
        hint = hint // 'the load may have passed a limit point (the thesis carries the unbalanced ' // &
          'force: STAGE ..., DIVERGENCE=1)'
      end if
    end if
    if (an%symmetrized .and. st%controls%method /= method_initial_stiffness .and. cutbacks_exhausted) then
      ! Non-associated flow: outside full Newton (which factorizes the exact tangent by LU) the
      ! factorized matrix is only a symmetric stand-in for the tangent, and as psi -> 0 the
      ! iterations stall (the 2D joint with psi = 0; docs/input-format.md, CONTROLS).
      hint = hint // '; the tangent was non-symmetric (psi /= phi, or a gap closing) and only its nearest symmetric ' // &
        'stand-in was factorized: try STAGE ..., METHOD=full-newton-raphson (exact tangent, LU) or ' // &
        'METHOD=initial-stiffness, ACCELERATION=bfgs, MAXIT=400'
    end if
    if (len(notes) > 0 .and. cutbacks_exhausted) hint = hint // '; ' // notes
    call fatal_error(error, err_solver, model%deck_file // ': stage ' // st%name // ', step ' // str(k) // &
                     ', load factor ' // str(lf) // ': ' // why // ' (relative residual ' // str(rel) // &
                     ', largest at ' // an%map%dof_name(imax) // ')' // hint)
  end subroutine stop_error

  function progress_line(s, k, n, lf, iters, rel, nfact, nfact_step) result(line)
    integer, intent(in) :: s, k, n, iters, nfact, nfact_step
    real(dp), intent(in) :: lf, rel
    character(len=:), allocatable :: line
    character(len=160) :: buf
    write (buf, '(a,i0,a,i0,a,i0,a,f9.5,a,i4,a,es9.2,a,i0,a,i0,a)') 'stage ', s, '  step ', k, '/', n, &
      '  load ', lf, '  iterations ', iters, '  residual ', rel, '  refactorizations ', nfact, ' (+', nfact_step, ')'
    line = trim(buf)
  end function progress_line

  !> Hand the step's results to the observer.
  subroutine report_step(model, an, observer, step, s, k, lf, iters, rel, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    class(observer_t), intent(inout) :: observer
    integer, intent(in) :: step, s, k, iters
    real(dp), intent(in) :: lf, rel
    type(error_t), allocatable, intent(out) :: error
    type(step_result_t) :: res
    integer :: g, n
    res%step = step
    res%stage = s
    res%step_in_stage = k
    res%load_factor = lf
    res%iterations = iters
    res%residual = rel
    res%displacement = an%u
    res%applied_force = an%f_applied
    allocate (res%reaction(3, model%nnode), res%reaction_nodal(3, model%nnode))
    res%reaction = 0.0_dp
    res%reaction_nodal = 0.0_dp
    do n = 1, model%nnode
      if (.not. any(an%map%constrained(:, n))) cycle
      res%reaction(:, n) = an%fint(:, n) - an%f_applied(:, n)
      res%reaction_nodal(:, n) = matmul(transpose(an%map%basis(:, :, n)), res%reaction(:, n))
    end do
    res%has_nodal_systems = an%map%has_rotations()
    allocate (res%groups(size(model%groups)))
    do g = 1, size(model%groups)
      res%groups(g)%points_per_element = an%kernels(g)%npoints
      res%groups(g)%is_interface = an%kernels(g)%is_interface
      res%groups(g)%is_bar = an%kernels(g)%is_bar
      ! Fields not asked for are not computed (stress recovery is most of a linear step's output cost).
      if (.not. group_output_wanted(model%fields, an%kernels(g))) cycle
      if (an%states(g)%nonlinear) then
        res%groups(g)%stress = an%states(g)%sig
        res%groups(g)%strain = an%states(g)%eps
        res%groups(g)%state = an%states(g)%state
      else
        call linear_group_results(model, an, g, res%groups(g))
      end if
    end do
    call observer%write_step(res, error)
  end subroutine report_step

  !> Does any requested field need the point results of a group of this kernel's kind?
  pure logical function group_output_wanted(fields, kernel)
    type(output_fields_t), intent(in) :: fields
    type(group_kernel_t), intent(in) :: kernel
    if (kernel%is_bar) then
      group_output_wanted = fields%bar
    else if (kernel%is_interface) then
      group_output_wanted = fields%interface .or. fields%interface_strain
    else
      group_output_wanted = fields%stress .or. fields%principal
    end if
  end function group_output_wanted

  !> Strains and stresses of a linear group from the total displacements (sigma = D eps).
  subroutine linear_group_results(model, an, g, gr)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: g
    type(group_result_t), intent(inout) :: gr
    integer :: e, q, np, nn, nc, q0
    real(dp), allocatable :: d(:, :), ue(:)
    np = an%kernels(g)%npoints
    nn = an%kernels(g)%nnodes
    nc = an%kernels(g)%ncomp
    allocate (gr%stress(nc, np * size(model%groups(g)%connectivity, 2)), gr%strain(nc, size(gr%stress, 2)))
    allocate (gr%state(size(gr%stress, 2)), d(nc, nc), ue(3 * nn))
    gr%state = 0
    call an%materials(model%groups(g)%material)%m%elastic_tangent(d)
    do e = 1, size(model%groups(g)%connectivity, 2)
      q0 = (e - 1) * np
      ue = reshape(an%u(:, model%groups(g)%connectivity(:, e)), [3 * nn])
      call element_strains(an%kernels(g), model%coords(:, model%groups(g)%connectivity(:, e)), ue, &
                           gr%strain(:, q0 + 1:q0 + np))
      do q = 1, np
        gr%stress(:, q0 + q) = matmul(d, gr%strain(:, q0 + q))
      end do
    end do
  end subroutine linear_group_results

end module feps_incremental_analysis
