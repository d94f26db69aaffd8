!> The state an incremental analysis works on, and the operations on it that do not decide
!! how a step is solved: setting up (kernels, materials, DOF map, pattern, solver), point
!! states and the linear part, supports that change and groups born between stages, a
!! stage's increments, trial displacements and point updates, the residual, commit and
!! restore, and the assembly and factorization of the tangent (exact, LU, or its nearest
!! symmetric positive semi-definite stand-in). feps_incremental_analysis decides what to do
!! with them (thesis 2.6); feps_step_report says what happened.
module feps_analysis_state
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, input_error, err_model, err_input, err_memory, str
  use feps_clock, only: wall_clock
  use feps_files, only: memory_limit_bytes
  use feps_blas, only: blas_threads, take_blas_buffers
  !$ use omp_lib, only: omp_get_max_threads
  use feps_strings, only: gib_text
  use feps_model, only: model_t, path_load
  use feps_dof_map, only: dof_map_t, build_dof_map, build_all_dofs_map
  use feps_sparse_matrix, only: csr_matrix_t, full_pattern
  use feps_assembly, only: group_kernel_t, build_kernels, build_materials, build_pattern, check_jacobians, &
                           element_dofs, element_stiffness, element_strains, element_internal_force, &
                           scatter_element_matrix, rotate_matrix
  use feps_interface_orientation, only: check_interface_orientation
  use feps_tangent_symmetry, only: nearest_symmetric_psd
  use feps_loads, only: resolve_face_sets, nodal_load_vector, to_equations
  use feps_material, only: material_slot_t
  use feps_material_params, only: material_error
  use feps_solid_element, only: solid_element_t
  use feps_point_state_store, only: point_state_store_t
  use feps_solver_factory, only: new_linear_solver, new_lu_solver
  use feps_observer, only: observer_t
  use feps_equation_system, only: equation_system_t
  use feps_analysis_summary, only: analysis_summary_t, condition_warning
  use feps_restart_data, only: restart_data_t
  use feps_element_partition, only: element_partition_t, partition_elements
  use feps_parallel, only: parallel_rank, parallel_ranks, sum_over_ranks, min_over_ranks, any_rank
  implicit none
  private

  !> Point states of one group, committed (end of the last step) and trial: the store, with
  !! commit, restore and its size, allocated for the groups that carry point state.
  type, extends(point_state_store_t), public :: group_state_t
    !> Carries point state: a nonlinear material, a group born in a later stage (whose
    !! strains count from its activation) or a prestressed one (whose force is not K u), so
    !! it cannot join the total-strain linear part.
    logical :: nonlinear = .false.
  end type group_state_t

  !> Internal forces of all linear groups as one product K_lin u (global Cartesian DOFs of
  !! every node in an element): linear elements carry no point state at all, and their
  !! stresses are computed only for the steps written.
  type, public :: linear_part_t
    logical :: present = .false.
    type(dof_map_t) :: map
    type(csr_matrix_t) :: k
  end type linear_part_t

  !> The state along the load path: displacements (committed and trial), internal forces,
  !! the loads applied so far, the constrained values reached and the groups active.
  type, public :: load_path_t
    real(dp), allocatable :: u(:, :), u_t(:, :)        !! committed and trial displacements (global)
    real(dp), allocatable :: fint(:, :)                !! internal forces of the trial state (global)
    real(dp), allocatable :: f_ref(:, :)               !! reference (stage-0) loads (global)
    real(dp), allocatable :: f_applied(:, :)           !! external load applied so far (global)
    real(dp), allocatable :: uc(:, :)                  !! constrained values reached (nodal systems)
    real(dp), allocatable :: release_force(:, :)       !! load increment of the stage that removes released supports' forces
    logical, allocatable :: active(:)                  !! groups active in the current stage
  end type load_path_t

  !> Everything the analysis works on: the element and material objects, the equation system
  !! (numbering, matrix, its factors), the point states, the linear part, and the state along
  !! the load path.
  type, public :: analysis_t
    type(group_kernel_t), allocatable :: kernels(:)
    type(material_slot_t), allocatable :: materials(:)
    type(equation_system_t) :: eq
    type(group_state_t), allocatable :: states(:)
    type(linear_part_t) :: lin
    type(load_path_t) :: path
    type(element_partition_t) :: part      !! this rank's elements (all of them on one rank)
  end type analysis_t

  !> Elements per chunk of the threaded element loops: their matrices (or forces) are made in
  !! parallel and then added in element order. The point updates, once per iteration, take big
  !! chunks (few thread barriers; 8192 hex20 forces are 3.9 MB); the element matrices, once per
  !! factorization, small ones (256 hex20 matrices are 7.4 MB).
  integer, parameter :: element_chunk = 256
  integer, parameter :: force_chunk = 8192

  public :: is_linear_model, set_up, init_states, set_crack_bands, state_bytes
  public :: change_supports, activate_groups, check_born_nodes, stage_increments
  public :: set_trial, add_free, update_points, residual, committed_residual, commit, restore

  !> OpenBLAS's work buffer (BUFFER_SIZE, 32 << 22 bytes on x86-64), taken by each of its
  !! threads at its first level-3 call and by each caller of its level-2 routines (dtrsv, dgemv)
  !! for the length of the call. OpenBLAS 0.3.21 retries an allocation that fails forever: FE1
  !! under ulimit -v 450000 hung in the factorization's dpotrf, so the check counts the buffers.
  integer(i8), parameter :: blas_buffer_bytes = 134217728_i8
  !> Room for the threads CHOLMOD's supernodal factorization starts (OpenMP, up to 4 in Debian's
  !! build): their stacks, 8 MiB each under the usual stack limit, and what they allocate.
  !! Where they did not fit, libgomp ended the run itself ("Thread creation failed", exit 1):
  !! FE1 on one thread under ulimit -v 440000-450000 with nothing counted, 455000-458000 with
  !! 32 MiB; with 64 MiB it is refused up to the limit where it runs.
  integer(i8), parameter :: thread_stacks_bytes = 8_i8 * 8388608_i8
  public :: factorize_tangent, support_reaction, support_reaction_nodal
  public :: save_state, restore_state

contains

  !> All materials linear and no interfaces: one factorization, one solve per stage.
  logical function is_linear_model(model, materials)
    type(model_t), intent(in) :: model
    type(material_slot_t), intent(in) :: materials(:)
    integer :: m
    is_linear_model = .not. model%has_interfaces() .and. model%geostatic_stage == 0
    do m = 1, size(materials)
      if (.not. materials(m)%m%is_linear()) is_linear_model = .false.
    end do
  end function is_linear_model

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
    call check_jacobians(model, an%kernels, summary%min_jacobian, error)
    if (allocated(error)) return
    call check_interface_orientation(model, an%kernels, error)
    if (allocated(error)) return
    call resolve_face_sets(model, an%kernels, error)
    if (allocated(error)) return
    call build_dof_map(model, an%eq%map, error)
    if (allocated(error)) return
    summary%dofs = an%eq%map%neq
    summary%unused_nodes = an%eq%map%unused_nodes
    if (an%eq%map%neq == 0) then
      call fatal_error(error, err_model, model%deck_file // ': the model has no free degree of freedom')
      return
    end if
    call check_later_supports(model, error)
    if (allocated(error)) return
    ! a path-following stage finds its load factor by iteration, also in a linear model
    summary%linear = is_linear_model(model, an%materials) .and. all(model%stages%path == path_load)
    ! mixed precision leans on a step's iterations to correct its solves: a linear model's one
    ! solve per stage has none, so it stays in double precision
    if (summary%linear .and. solver_name == 'cholmod-mixed') then
      call new_linear_solver('cholmod', an%eq%solver, error)
    else
      call new_linear_solver(solver_name, an%eq%solver, error)
    end if
    if (allocated(error)) return
    call new_lu_solver(solver_name, an%eq%lu)
    summary%solver = an%eq%solver%name()
    call set_partition(model, an, error)
    if (allocated(error)) return
    call analyze_pattern(model, an, summary, error)
  end subroutine set_up

  !> The elements this rank works on: its part of METIS's partition when the solver takes its
  !! matrix from every rank (MUMPS on more than one rank), else all of them
  !! (feps_element_partition).
  subroutine set_partition(model, an, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(error_t), allocatable, intent(out) :: error
    integer :: g
    integer, allocatable :: npoints(:)
    npoints = [(an%kernels(g)%npoints, g = 1, size(an%kernels))]   ! contiguous (no array temporary)
    call partition_elements(model, npoints, parallel_rank(), parallel_ranks(), &
                            an%eq%solver%takes_distributed_matrix() .and. an%eq%lu%takes_distributed_matrix(), &
                            an%part, error)
    if (allocated(error) .or. .not. an%part%distributed) return
    ! a group's point states are exchanged in one call, whose counts and offsets are ints
    do g = 1, size(model%groups)
      if (.not. carries_state(model, an, g)) cycle
      if (real(size(model%groups(g)%connectivity, 2), dp) * an%kernels(g)%npoints * an%kernels(g)%ncomp**2 &
          >= real(huge(1), dp)) then
        call fatal_error(error, err_model, model%deck_file // ': group ' // trim(model%groups(g)%name) // &
                         ' has too many points for an MPI run (its point states are exchanged in one call ' // &
                         'of at most 2**31 values): split it into several groups')
        return
      end if
    end do
  end subroutine set_partition

  !> The pattern of the stiffness for the current DOF map, and the solver's analysis of it (in an
  !! element-partitioned run, of the entries this rank's elements give).
  subroutine analyze_pattern(model, an, summary, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    call build_pattern(model, an%eq%map, an%eq%a)
    if (allocated(an%eq%a_full%row_ptr)) deallocate (an%eq%a_full%row_ptr, an%eq%a_full%col, an%eq%a_full%val)
    summary%matrix_nnz = an%eq%a%nnz()
    if (an%part%distributed) call an%eq%solver%set_local_entries(own_entries(model, an, an%eq%a, .false.))
    call an%eq%solver%analyze(an%eq%a, error)
    if (.not. allocated(error)) call check_factor_memory(model, an, error)
  end subroutine analyze_pattern

  !> Both triangles of the stiffness's pattern, and the LU solver's analysis of it.
  subroutine analyze_full_pattern(model, an, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(error_t), allocatable, intent(out) :: error
    call full_pattern(an%eq%a, an%eq%a_full)
    if (an%part%distributed) call an%eq%lu%set_local_entries(own_entries(model, an, an%eq%a_full, .true.))
    call an%eq%lu%analyze(an%eq%a_full, error)
  end subroutine analyze_full_pattern

  !> The entries of `a` (lower triangle, or `both` triangles) that this rank's elements give.
  function own_entries(model, an, a, both) result(own)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    type(csr_matrix_t), intent(in) :: a
    logical, intent(in) :: both
    logical, allocatable :: own(:)
    type(csr_matrix_t) :: marks
    real(dp), allocatable :: ones(:, :)
    integer, allocatable :: dofs(:)
    integer :: g, i
    marks = a
    marks%val = 0.0_dp
    do g = 1, size(model%groups)
      allocate (ones(3 * an%kernels(g)%nnodes, 3 * an%kernels(g)%nnodes), dofs(3 * an%kernels(g)%nnodes))
      ones = 1.0_dp
      do i = 1, size(an%part%groups(g)%own)
        call element_dofs(an%eq%map, model%groups(g)%connectivity(:, an%part%groups(g)%own(i)), dofs)
        call scatter_element_matrix(dofs, ones, marks, both_triangles=both)
      end do
      deallocate (ones, dofs)
    end do
    own = marks%val /= 0.0_dp
  end function own_entries

  !> A whole matrix held on every rank (restart data) as this rank's share of it: each entry
  !! kept by the lowest rank whose elements give it, zero on the others, so that the solver's
  !! sum over the ranks is the matrix.
  subroutine keep_own_share(model, an, a, both)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    type(csr_matrix_t), intent(inout) :: a
    logical, intent(in) :: both
    integer, allocatable :: keeper(:)
    if (.not. an%part%distributed) return
    keeper = merge(an%part%rank, an%part%ranks, own_entries(model, an, a, both))
    call min_over_ranks(keeper, size(keeper, kind=i8))
    where (keeper /= an%part%rank) a%val = 0.0_dp
  end subroutine keep_own_share

  !> A failed run (err_memory, exit status 1) when the memory the solver's analysis foresees for
  !! its factorization (memory_need_bytes: 8 bytes a factor nonzero, a lower bound, or the
  !! solver's own estimate), with the matrix it is made from and the BLAS's work buffers, is
  !! beyond the memory this process may still use (memory_limit_bytes), before it is allocated.
  !! When it fits, the BLAS's buffers are taken at once (take_blas_buffers), while the room is
  !! there.
  subroutine check_factor_memory(model, an, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: need, limit
    integer :: solve_threads
    limit = memory_limit_bytes()
    if (limit <= 0) return
    ! the factorization's BLAS threads hold a buffer each, and the solves' threads (OpenMP,
    ! calling dtrsv and dgemv at once) one each besides, the main thread's reused: with one
    ! buffer fewer, FE1 on two threads hung or crashed under ulimit -v 560000-650000
    solve_threads = 1
    !$ solve_threads = omp_get_max_threads()
    need = an%eq%solver%memory_need_bytes() + 12_i8 * an%eq%a%nnz() + &
           blas_buffer_bytes * (blas_threads() + solve_threads - 1) + thread_stacks_bytes
    if (need <= limit) then
      call take_blas_buffers()
      return
    end if
    call fatal_error(error, err_memory, model%deck_file // ': the factor of the stiffness matrix (' // &
                     str(an%eq%map%neq) // ' equations, ' // str(real(an%eq%solver%factor_nnz, dp)) // &
                     ' nonzeros) needs about ' // gib_text(need) // ' GiB at least, more than the ' // &
                     gib_text(limit) // ' GiB this process may use (its address-space limit, ulimit -v, ' // &
                     'or the machine''s memory)')
  end subroutine check_factor_memory

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

    an%path%release_force = 0.0_dp
    changed = model%supports_change(s)
    if (.not. changed) return
    call build_dof_map(model, new, error, stage=s)
    if (allocated(error)) return
    nheld = 0
    nfreed = 0
    do n = 1, model%nnode
      if (.not. new%used(n)) cycle
      if (all(new%constrained(:, n) .eqv. an%eq%map%constrained(:, n))) cycle
      ul = matmul(transpose(an%eq%map%basis(:, :, n)), an%path%u(:, n))
      support = matmul(transpose(an%eq%map%basis(:, :, n)), an%path%fint(:, n) - an%path%f_applied(:, n))
      do d = 1, 3
        if (new%constrained(d, n) .and. .not. an%eq%map%constrained(d, n)) then
          an%path%uc(d, n) = ul(d)
          nheld = nheld + 1
        else if (an%eq%map%constrained(d, n) .and. .not. new%constrained(d, n)) then
          an%path%f_applied(:, n) = an%path%f_applied(:, n) + support(d) * an%eq%map%basis(:, d, n)
          an%path%release_force(:, n) = an%path%release_force(:, n) - support(d) * an%eq%map%basis(:, d, n)
          nfreed = nfreed + 1
        end if
      end do
    end do
    an%eq%map = new
    summary%dofs = an%eq%map%neq
    call analyze_pattern(model, an, summary, error)
    if (allocated(error)) return
    if (.not. present(observer)) return
    if (nfreed > 0) then
      call observer%progress('stage ' // model%stages(s)%name // ': supports change: ' // str(nheld) // &
                             ' DOFs held from here, ' // str(nfreed) // ' released (their support forces ' // &
                             'removed over the stage); ' // str(an%eq%map%neq) // ' equations')
    else
      call observer%progress('stage ' // model%stages(s)%name // ': supports change: ' // str(nheld) // &
                             ' DOFs held from here; ' // str(an%eq%map%neq) // ' equations')
    end if
  end subroutine change_supports

  !> Whether group g carries point state (group_state_t%nonlinear): a nonlinear material, a
  !! group born in a later stage or prestressed, or any group of a model with a GEOSTATIC
  !! stage, which resets the displacements after it (every stress must be a point's own).
  logical function carries_state(model, an, g)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: g
    carries_state = .not. an%materials(model%groups(g)%material)%m%is_linear() .or. &
                    model%groups(g)%activate_stage > 1 .or. model%is_prestressed(g) .or. model%geostatic_stage > 0
  end function carries_state

  !> Point states of the groups that carry them (zero, with the elastic tangent), the
  !! assembled stiffness of the linear part, the active groups of stage 1, and zero
  !! displacements and forces.
  subroutine init_states(model, an)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer :: g, np, nc, nn, q, i, i0, i1
    integer, allocatable :: own(:)
    real(dp), allocatable :: ke(:, :, :), d(:, :, :)
    integer, allocatable :: dofs(:, :)
    allocate (an%states(size(model%groups)))
    do g = 1, size(model%groups)
      np = an%kernels(g)%npoints * size(model%groups(g)%connectivity, 2)
      nc = an%kernels(g)%ncomp
      associate (s => an%states(g))
        s%nonlinear = carries_state(model, an, g)
        if (.not. s%nonlinear) then
          an%lin%present = .true.
          cycle
        end if
        call s%init(an%materials(model%groups(g)%material)%m, nc, np)
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
        nn = an%kernels(g)%nnodes
        allocate (ke(3 * nn, 3 * nn, element_chunk), d(nc, nc, np), dofs(3 * nn, element_chunk))
        do q = 1, np
          call an%materials(model%groups(g)%material)%m%elastic_tangent(d(:, :, q))
        end do
        ! element matrices of a chunk in parallel, added in element order (bit-identical for any
        ! number of threads)
        ! (this rank's elements: in an element-partitioned run K_lin is each rank's share)
        own = an%part%own(g)
        associate (conn => model%groups(g)%connectivity)
          do i0 = 1, size(own), element_chunk
            i1 = min(size(own), i0 + element_chunk - 1)
            !$omp parallel do schedule(static)
            do i = i0, i1
              call element_stiffness(an%kernels(g), model%coords(:, conn(:, own(i))), d, ke(:, :, i - i0 + 1))
              call element_dofs(an%lin%map, conn(:, own(i)), dofs(:, i - i0 + 1))
            end do
            !$omp end parallel do
            do i = i0, i1
              call scatter_element_matrix(dofs(:, i - i0 + 1), ke(:, :, i - i0 + 1), an%lin%k)
            end do
          end do
        end associate
        deallocate (ke, d, dofs)
      end do
    end if
    allocate (an%path%active(size(model%groups)))
    an%path%active = model%groups(:)%activate_stage <= 1
    allocate (an%path%u(3, model%nnode), an%path%u_t(3, model%nnode), an%path%fint(3, model%nnode), an%path%uc(3, model%nnode))
    an%path%u = 0.0_dp
    an%path%u_t = 0.0_dp
    an%path%fint = 0.0_dp
    an%path%uc = 0.0_dp
    allocate (an%path%release_force(3, model%nnode))
    an%path%release_force = 0.0_dp
  end subroutine init_states

  !> Every point of a material that asks for its crack band (`band_slot`) gets its element's
  !! length: volume^(1/3) in 3D, area^(1/2) in plane strain (the element's volume per unit
  !! thickness). An element longer than the material's `max_band` is an input error at the
  !! MATERIAL record, naming the group and element: the band would snap back.
  subroutine set_crack_bands(model, an, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(error_t), allocatable, intent(out) :: error
    integer :: g, e, slot, np, m
    real(dp) :: h, hmax
    do g = 1, size(model%groups)
      m = model%groups(g)%material
      slot = an%materials(m)%m%band_slot()
      if (slot == 0 .or. .not. an%states(g)%kept()) cycle
      hmax = an%materials(m)%m%max_band()
      np = an%kernels(g)%npoints
      select type (el => an%kernels(g)%element)
      class is (solid_element_t)
        do e = 1, size(model%groups(g)%connectivity, 2)
          h = el%volume(model%coords(:, model%groups(g)%connectivity(:, e)))
          if (el%ndim() == 2) then
            h = sqrt(h)
          else
            h = h**(1.0_dp / 3.0_dp)
          end if
          if (h > hmax) then
            call material_error(error, model%materials(m), 'element ' // str(e) // ' of group ' // &
                                model%groups(g)%name // ' is ' // str(h) // ' mm long (its volume^(1/3)), more ' // &
                                'than the crack band 2 E GF / FT^2 = ' // str(hmax) // ' mm allows (its ' // &
                                'softening would snap back): refine the mesh or raise GF', 'gf')
            return
          end if
          an%states(g)%vars(slot, (e - 1) * np + 1:e * np) = h
          an%states(g)%vars_t(slot, (e - 1) * np + 1:e * np) = h
        end do
      end select
    end do
  end subroutine set_crack_bands

  !> Memory held per group for point states (stresses, strains, flags, internal variables,
  !! tangents; committed and trial), to show that elastic groups keep none.
  pure function state_bytes(states) result(bytes)
    type(group_state_t), intent(in) :: states(:)
    integer(i8) :: bytes(size(states))
    integer :: g
    do g = 1, size(states)
      bytes(g) = states(g)%bytes()
    end do
  end function state_bytes

  !> Which groups carry point state.
  pure function nonlinear_groups(an) result(mask)
    type(analysis_t), intent(in) :: an
    logical :: mask(size(an%states))
    integer :: g
    do g = 1, size(an%states)
      mask(g) = an%states(g)%nonlinear
    end do
  end function nonlinear_groups

  !> f <- f + K_lin u for the linear groups (global Cartesian components): in an
  !! element-partitioned run, this rank's elements' share (the caller sums over the ranks).
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
      an%path%active(g) = .true.
      any_born = .true.
      if (tension(g) /= 0.0_dp) call an%states(g)%set_stress(tension(g))
    end do
    call add_group_stress_forces(model, an, merge(tension, 0.0_dp, model%groups(:)%activate_stage == s), 1.0_dp, &
                        an%path%f_applied)
  end subroutine activate_groups

  !> f <- f + sign * the nodal forces of each group g's elements under the uniform stress
  !! force(g) at every point (a prestress: the axial force of a tendon's bars), in global
  !! components; groups with force(g) = 0 are skipped.
  subroutine add_group_stress_forces(model, an, force, sign, f)
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
  end subroutine add_group_stress_forces

  !> A free DOF whose node touches no active element has no stiffness: name it (and the group
  !! that will bring it) rather than let the factorization find a zero pivot.
  subroutine check_born_nodes(model, an, s, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: s
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: carried(:)
    integer :: g, n, d, later
    if (all(an%path%active)) return
    allocate (carried(model%nnode))
    carried = .false.
    do g = 1, size(model%groups)
      if (an%path%active(g)) carried(pack(model%groups(g)%connectivity, .true.)) = .true.
    end do
    do n = 1, model%nnode
      if (carried(n)) cycle
      do d = 1, 3
        if (an%eq%map%eq(d, n) == 0) cycle
        later = 0
        do g = 1, size(model%groups)
          if (.not. an%path%active(g) .and. any(model%groups(g)%connectivity == n)) later = g
        end do
        if (later == 0) cycle   ! a node of no element at all: the DOF map does not number it
        call fatal_error(error, err_model, model%deck_file // ': stage ' // model%stages(s)%name // ': ' // &
                         an%eq%map%dof_name(an%eq%map%eq(d, n)) // ' has no stiffness: its node belongs only to ' // &
                         'elements not yet active (group ' // model%groups(later)%name // ', ACTIVATE in stage ' // &
                         model%stages(model%groups(later)%activate_stage)%name // '); hold it (FIX, DISPLACE) ' // &
                         'or activate its elements earlier', item=an%eq%map%eq(d, n))
        return
      end do
    end do
  end subroutine check_born_nodes

  !> FORCE MODE=TOTAL: each given component is the total at the end of stage s, so the force the
  !! node carried in that direction at the end of the stage before comes off the increment that
  !! nodal_load_vector added (the component itself).
  subroutine subtract_carried_forces(model, an, s, df)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: s
    real(dp), intent(inout) :: df(:, :)
    real(dp) :: basis(3, 3)
    integer :: i, k, n, d
    if (.not. allocated(an%path%f_applied)) return
    do i = 1, size(model%nodal_loads)
      associate (l => model%nodal_loads(i))
        if (.not. l%total .or. l%stage /= s) cycle
        do k = 1, size(model%node_sets(l%node_set)%nodes)
          n = model%node_sets(l%node_set)%nodes(k)
          basis = model%systems(l%csys)%local_basis(model%coords(:, n))
          do d = 1, 3
            if (l%given(d)) df(:, n) = df(:, n) - dot_product(basis(:, d), an%path%f_applied(:, n)) * basis(:, d)
          end do
        end do
      end associate
    end do
  end subroutine subtract_carried_forces

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
    ! GEOSTATIC: the in-situ stress of each point (its pattern), grown over the stage's steps
    do c = 1, size(an%states)
      if (allocated(an%states(c)%pattern)) dps(c) = 1.0_dp
    end do
    call nodal_load_vector(model, an%kernels, df, error, stage=s)
    if (allocated(error)) return
    call subtract_carried_forces(model, an, s, df)
    ! Post-tensioned bars, not yet bonded: their force pulls on their nodes as a load.
    call add_group_stress_forces(model, an, model%stage_prestress(s, after=.true.), -1.0_dp, df)
    frac = model%stages(s)%load_fraction
    df = df + frac * an%path%f_ref
    if (allocated(an%path%release_force)) df = df + an%path%release_force
    duc = 0.0_dp
    do c = 1, size(model%constraints)
      associate (con => model%constraints(c))
        if (con%stage /= 0 .and. con%stage /= s) cycle
        do k = 1, size(model%node_sets(con%node_set)%nodes)
          n = model%node_sets(con%node_set)%nodes(k)
          ! Prescribed values add up (LOAD= times the reference ones plus the stage's own, and
          ! several records on one DOF); a FIX later in the deck holds the DOF where it is.
          if (.not. con%prescribed) then
            duc(con%dof, n) = 0.0_dp
          else if (con%total) then
            ! MODE=TOTAL: to the value at the stage's end from the value reached
            duc(con%dof, n) = con%value - an%path%uc(con%dof, n)
          else if (con%stage == 0) then
            duc(con%dof, n) = duc(con%dof, n) + frac * con%value
          else
            duc(con%dof, n) = duc(con%dof, n) + con%value
          end if
        end do
      end associate
    end do
    call check_finite_increment(df, 'load increment', .false., error)
    if (.not. allocated(error)) call check_finite_increment(duc, 'prescribed displacement', .true., error)
  contains
    !> Each record's loads are finite (feps_loads); their sum over the stage (its own, LOAD=
    !! times the reference ones, released support forces, post-tensioned bars) and the stage's
    !! prescribed displacements must be too: an input error naming the STAGE record, the node
    !! and the DOF (global for loads, the node's system for displacements), before any solve.
    subroutine check_finite_increment(v, what, nodal, error)
      real(dp), intent(in) :: v(:, :)
      character(len=*), intent(in) :: what
      logical, intent(in) :: nodal
      type(error_t), allocatable, intent(out) :: error
      character(len=6), parameter :: cartesian(3) = ['ux    ', 'uy    ', 'uz    '], &
                                     cylindrical(3) = ['ur    ', 'utheta', 'uz    ']
      character(len=:), allocatable :: message
      character(len=6) :: dof
      integer :: at(2)
      if (all(ieee_is_finite(v))) return
      at = findloc(ieee_is_finite(v), .false.)
      dof = cartesian(at(1))
      if (nodal .and. an%eq%map%node_csys(at(2)) /= 0) dof = cylindrical(at(1))
      message = 'stage ' // model%stages(s)%name // ': its ' // what // ' at node ' // str(at(2)) // ', DOF ' // &
                trim(dof) // ' is not finite (' // str(v(at(1), at(2))) // '): what the stage adds up there is ' // &
                'beyond double precision'
      if (model%stages(s)%line > 0) then
        call input_error(error, model%stages(s)%file, model%stages(s)%line, message)
      else
        call fatal_error(error, err_input, model%deck_file // ': ' // message)
      end if
    end subroutine check_finite_increment
  end subroutine stage_increments

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
    call add_linear_forces(an, an%path%u, f)
    if (an%part%distributed) call sum_over_ranks(f, size(f, kind=i8))
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
    call to_equations(an%eq%map, an%path%f_applied - f, rf)
    r = rf
  end subroutine committed_residual

  !> Trial displacements: the committed ones with the constrained DOFs moved to their
  !! current targets an%path%uc (nodal systems).
  subroutine set_trial(model, an)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    integer :: n, d
    real(dp) :: ul(3)
    do n = 1, model%nnode
      if (.not. any(an%eq%map%constrained(:, n))) then
        an%path%u_t(:, n) = an%path%u(:, n)
        cycle
      end if
      if (an%eq%map%node_csys(n) == 0) then   ! the global system: no rotation to make
        an%path%u_t(:, n) = merge(an%path%uc(:, n), an%path%u(:, n), an%eq%map%constrained(:, n))
        cycle
      end if
      ul = matmul(transpose(an%eq%map%basis(:, :, n)), an%path%u(:, n))
      do d = 1, 3
        if (an%eq%map%constrained(d, n)) ul(d) = an%path%uc(d, n)
      end do
      an%path%u_t(:, n) = matmul(an%eq%map%basis(:, :, n), ul)
    end do
  end subroutine set_trial

  !> u <- u + dx on the free equations (dx in nodal systems). A node in the global system
  !! takes its DOFs' values directly: its basis is the identity, whose product would give the
  !! same values (up to the sign of a zero) at many times the cost, once per iteration.
  pure subroutine add_free(an, x, u)
    type(analysis_t), intent(in) :: an
    real(dp), intent(in) :: x(:)
    real(dp), intent(inout) :: u(:, :)
    integer :: n, d, ieq
    real(dp) :: dl(3)
    associate (map => an%eq%map)
      do n = 1, size(u, 2)
        if (map%node_csys(n) == 0) then
          do d = 1, 3
            ieq = map%eq(d, n)
            if (ieq > 0) u(d, n) = u(d, n) + x(ieq)
          end do
          cycle
        end if
        if (all(map%eq(:, n) == 0)) cycle
        dl = 0.0_dp
        do d = 1, 3
          if (map%eq(d, n) > 0) dl(d) = x(map%eq(d, n))
        end do
        u(:, n) = u(:, n) + matmul(map%basis(:, :, n), dl)
      end do
    end associate
  end subroutine add_free

  !> Update every point from the committed state with the strain of u_t - u, and sum the
  !! internal forces of the trial state. The points of group g start from their committed
  !! state plus the stress increment dps(g) imposed on every component (a prestress: the
  !! bars' axial force).
  !!
  !! Threaded (OpenMP) over the elements of a chunk: each element updates its own points and
  !! writes its forces to its own column; the forces are then summed in element order, so the
  !! result is bit-identical for any number of threads.
  subroutine update_points(model, an, dps)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    real(dp), intent(in) :: dps(:)
    integer :: g, e, i, i0, i1, np, nn, nc, a
    integer, allocatable :: own(:)
    real(dp), allocatable :: fe(:, :)
    an%path%fint = 0.0_dp
    call add_linear_forces(an, an%path%u_t, an%path%fint)   ! this rank's share: summed below
    do g = 1, size(model%groups)
      if (.not. an%states(g)%nonlinear .or. .not. an%path%active(g)) cycle
      np = an%kernels(g)%npoints
      nn = an%kernels(g)%nnodes
      nc = an%kernels(g)%ncomp
      allocate (fe(3 * nn, force_chunk))
      associate (s => an%states(g), conn => model%groups(g)%connectivity)
        call s%impose(dps(g))
        own = an%part%own(g)
        do i0 = 1, size(own), force_chunk
          i1 = min(size(own), i0 + force_chunk - 1)
          !$omp parallel do schedule(static)
          do i = i0, i1
            call update_element(g, own(i), fe(:, i - i0 + 1))
          end do
          !$omp end parallel do
          do i = i0, i1
            e = own(i)
            do a = 1, nn
              an%path%fint(:, conn(a, e)) = an%path%fint(:, conn(a, e)) + fe(3 * a - 2:3 * a, i - i0 + 1)
            end do
          end do
        end do
      end associate
      deallocate (fe)
    end do
    if (an%part%distributed) then
      call sum_over_ranks(an%path%fint, size(an%path%fint, kind=i8))
      do g = 1, size(model%groups)
        if (an%states(g)%nonlinear .and. an%path%active(g)) &
          call an%part%share_trial(g, an%kernels(g)%npoints, an%states(g))
      end do
    end if
  contains
    !> Element e of group g: its points' trial states and its internal forces fe.
    subroutine update_element(g, e, fe)
      integer, intent(in) :: g, e
      real(dp), intent(out) :: fe(:)
      real(dp) :: xe(3, an%kernels(g)%nnodes), due(3 * an%kernels(g)%nnodes)
      real(dp) :: deps(an%kernels(g)%ncomp, an%kernels(g)%npoints)
      integer :: q, q0, np
      np = an%kernels(g)%npoints
      associate (conn => model%groups(g)%connectivity)
        xe = model%coords(:, conn(:, e))
        due = reshape(an%path%u_t(:, conn(:, e)) - an%path%u(:, conn(:, e)), [size(due)])
        call element_strains(an%kernels(g), xe, due, deps)
        q0 = (e - 1) * np
        do q = 1, np
          call an%states(g)%update(an%materials(model%groups(g)%material)%m, q0 + q, deps(:, q))
        end do
        call element_internal_force(an%kernels(g), xe, an%states(g)%sig_t(:, q0 + 1:q0 + np), fe)
      end associate
    end subroutine update_element
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
    allocate (p(size(r)), react(3 * size(an%path%fint, 2)))
    call to_equations(an%eq%map, an%path%f_applied - an%path%fint, r)
    call to_equations(an%eq%map, an%path%f_applied, p)
    rnorm = norm2(r)
    ! norm2 scales: a sum of squares would overflow for forces near huge() and make the
    ! relative residual zero
    k = 0
    associate (map => an%eq%map, fint => an%path%fint, fa => an%path%f_applied)
      do n = 1, size(fint, 2)
        if (.not. any(map%constrained(:, n))) cycle
        ! F_int - P in the node's system; a node in the global system without the product with
        ! its identity basis (a library matmul for each node, once per iteration)
        if (map%node_csys(n) /= 0) then
          fl = matmul(transpose(map%basis(:, :, n)), fint(:, n) - fa(:, n))
        else
          fl = fint(:, n) - fa(:, n)
        end if
        do d = 1, 3
          if (.not. map%constrained(d, n)) cycle
          k = k + 1
          react(k) = fl(d)
        end do
      end do
    end associate
    pnorm = max(norm2(p), norm2(react(1:k)), tiny(1.0_dp))
  end subroutine residual

  !> Accept the trial state: it becomes the committed one.
  subroutine commit(an)
    type(analysis_t), intent(inout) :: an
    integer :: g
    an%path%u = an%path%u_t
    do g = 1, size(an%states)
      call an%states(g)%commit()
    end do
  end subroutine commit

  !> Back to the committed state after a failed step.
  subroutine restore(an)
    type(analysis_t), intent(inout) :: an
    integer :: g
    an%path%u_t = an%path%u
    do g = 1, size(an%states)
      call an%states(g)%restore()
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
    logical :: use_trial, nonsymmetric, want_exact
    use_trial = .false.
    if (present(trial)) use_trial = trial
    want_exact = .false.
    if (present(exact)) want_exact = exact
    ! Non-symmetric points under full Newton: factorize the exact tangent (UMFPACK LU) and
    ! solve with it. Where it is singular (a body held only by faces sliding without
    ! dilation, a neutral equilibrium) the symmetric stand-in below is used instead.
    an%eq%use_lu = .false.
    an%eq%tangent_sign = 0
    nonsymmetric = .false.
    if (present(exact) .and. .not. elastic) then
      if (exact) nonsymmetric = any_nonsymmetric_tangent(model, an, use_trial)
    end if
    if (nonsymmetric) then
      t0 = wall_clock()
      if (.not. allocated(an%eq%a_full%row_ptr)) then
        call analyze_full_pattern(model, an, error)
        if (allocated(error)) return
      end if
      call assemble_tangent(model, an, elastic, use_trial, .true., an%eq%a_full, nonsymmetric)
      summary%time_assembly = summary%time_assembly + wall_clock() - t0
      t0 = wall_clock()
      call an%eq%lu%factorize(an%eq%a_full, lu_error)
      summary%time_factorization = summary%time_factorization + wall_clock() - t0
      if (.not. allocated(lu_error)) then
        an%eq%use_lu = .true.
        an%eq%tangent_sign = an%eq%lu%determinant_sign()
        summary%lu_factorizations = an%eq%lu%factorizations
        summary%lu_min_rcond = an%eq%lu_min_rcond()
        summary%factorizations = an%eq%solver%factorizations + an%eq%lu%factorizations
        return
      end if
      if (lu_error%code /= err_model) then
        call move_alloc(lu_error, error)
        return
      end if
      an%eq%lu_singular = an%eq%lu_singular + 1
    end if

    ! Full Newton whose exact tangent was singular takes the nearest positive semi-definite
    ! matrices, which regularise it; the other methods each material's own stand-in.
    t0 = wall_clock()
    call assemble_tangent(model, an, elastic, use_trial, .false., an%eq%a, nonsymmetric, nearest=want_exact)
    summary%time_assembly = summary%time_assembly + wall_clock() - t0
    if (nonsymmetric) an%eq%symmetrized = .true.

    t0 = wall_clock()
    call an%eq%solver%factorize(an%eq%a, error)
    summary%time_factorization = summary%time_factorization + wall_clock() - t0
    if (allocated(error)) then
      ieq = error%item   ! fatal_error reallocates error: keep the item first
      if (ieq > 0 .and. ieq <= an%eq%map%neq) then
        call fatal_error(error, err_model, model%deck_file // ': the stiffness matrix is singular at ' // &
                         an%eq%map%dof_name(ieq) // ' ' // node_position(model, an%eq%map%eq_node(ieq)) // &
                         ': that DOF is not held (an unconstrained rigid-body mode ' // &
                         'or a missing support), or held only through a stiffness contrast beyond double ' // &
                         'precision (' // an%eq%solver%zero_pivot_rule() // ')', item=ieq)
      end if
      return
    end if
    summary%factorizations = an%eq%solver%factorizations + an%eq%lu%factorizations
    ! the exact tangent itself, symmetric (a stand-in is no state's tangent)
    if (want_exact .and. .not. elastic .and. .not. nonsymmetric) an%eq%tangent_sign = an%eq%solver%determinant_sign()
    if (.not. an%eq%warned_condition .and. an%eq%solver%min_pivot_ratio > 0.0_dp) then
      if (an%eq%solver%max_pivot_ratio / an%eq%solver%min_pivot_ratio > condition_warning) then
        an%eq%warned_condition = .true.
        summary%condition_warning = .true.
      end if
    end if
  end subroutine factorize_tangent

  !> '(x, y, z)' of node n, for messages that name a node.
  function node_position(model, n) result(text)
    type(model_t), intent(in) :: model
    integer, intent(in) :: n
    character(len=:), allocatable :: text
    text = '(x, y, z = ' // str(model%coords(1, n)) // ', ' // str(model%coords(2, n)) // ', ' // &
           str(model%coords(3, n)) // ')'
  end function node_position

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
      if (.not. an%path%active(g) .or. .not. an%states(g)%nonlinear) cycle
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
  !! tangent replaced by its material's symmetric stand-in (`symmetric_stand_in`; with
  !! `nearest`, by the nearest symmetric positive semi-definite matrix), or (`exact`) both
  !! triangles with the point tangents as they are. `nonsymmetric` tells whether any point
  !! tangent was non-symmetric.
  subroutine assemble_tangent(model, an, elastic, use_trial, exact, a, nonsymmetric, nearest)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    logical, intent(in) :: elastic, use_trial, exact
    logical, intent(in), optional :: nearest
    type(csr_matrix_t), intent(inout) :: a
    logical, intent(out) :: nonsymmetric
    integer :: g, i, i0, i1, q, np, nn, nc
    integer, allocatable :: own(:)
    real(dp), allocatable :: ke(:, :, :), d(:, :, :)
    integer, allocatable :: dofs(:, :)
    logical :: from_states, found, psd
    nonsymmetric = .false.
    psd = .false.
    if (present(nearest)) psd = nearest
    a%val = 0.0_dp
    do g = 1, size(model%groups)
      if (.not. an%path%active(g)) cycle   ! not yet born: no stiffness
      np = an%kernels(g)%npoints
      nn = an%kernels(g)%nnodes
      nc = an%kernels(g)%ncomp
      allocate (ke(3 * nn, 3 * nn, element_chunk), d(nc, nc, np), dofs(3 * nn, element_chunk))
      associate (s => an%states(g), conn => model%groups(g)%connectivity)
        from_states = .not. (elastic .or. .not. s%nonlinear)
        if (.not. from_states) then
          do q = 1, np
            call an%materials(model%groups(g)%material)%m%elastic_tangent(d(:, :, q))
          end do
        end if
        ! Element matrices of a chunk in parallel (threads), then added in element order: the
        ! matrix is bit-identical for any number of threads.
        own = an%part%own(g)
        do i0 = 1, size(own), element_chunk
          i1 = min(size(own), i0 + element_chunk - 1)
          found = .false.
          !$omp parallel do schedule(static) reduction(.or.:found)
          do i = i0, i1
            call element_matrix(g, own(i), from_states, d, ke(:, :, i - i0 + 1), dofs(:, i - i0 + 1), found)
          end do
          !$omp end parallel do
          nonsymmetric = nonsymmetric .or. found
          do i = i0, i1
            call scatter_element_matrix(dofs(:, i - i0 + 1), ke(:, :, i - i0 + 1), a, both_triangles=exact)
          end do
        end do
      end associate
      deallocate (ke, d, dofs)
    end do
    if (an%part%distributed) nonsymmetric = any_rank(nonsymmetric)
  contains
    !> Element e's matrix (in the nodal systems) and DOFs: from the elastic point matrices d, or
    !! (from_states) its points' tangents; found is set when one of them is non-symmetric.
    subroutine element_matrix(g, e, from_states, d_elastic, ke, dofs, found)
      integer, intent(in) :: g, e
      logical, intent(in) :: from_states
      real(dp), intent(in) :: d_elastic(:, :, :)
      real(dp), intent(out) :: ke(:, :)
      integer, intent(out) :: dofs(:)
      logical, intent(inout) :: found
      real(dp) :: d(size(d_elastic, 1), size(d_elastic, 2), size(d_elastic, 3))
      integer :: q, q0, np
      np = size(d_elastic, 3)
      associate (s => an%states(g), conn => model%groups(g)%connectivity)
        if (.not. from_states) then
          call element_stiffness(an%kernels(g), model%coords(:, conn(:, e)), d_elastic, ke)
        else
          q0 = (e - 1) * np
          do q = 1, np
            if (use_trial) then
              d(:, :, q) = s%dtan_t(:, :, q0 + q)
            else
              d(:, :, q) = s%dtan(:, :, q0 + q)
            end if
            if (is_nonsymmetric(d(:, :, q))) then
              found = .true.
              if (exact) cycle
              if (psd) then
                call nearest_symmetric_psd(d(:, :, q))
              else
                call an%materials(model%groups(g)%material)%m%symmetric_stand_in(d(:, :, q))
              end if
            end if
          end do
          call element_stiffness(an%kernels(g), model%coords(:, conn(:, e)), d, ke)
        end if
        if (an%eq%map%has_rotations()) call rotate_matrix(an%eq%map, conn(:, e), ke)
        call element_dofs(an%eq%map, conn(:, e), dofs)
      end associate
    end subroutine element_matrix
  end subroutine assemble_tangent

  !> The support reaction at node `n` (global Cartesian): the internal less the applied force,
  !! in the node's nodal system, kept only in its constrained directions. In a free direction
  !! that difference is the out-of-balance force, which is no reaction (it is round-off at a
  !! converged step, but the unbalanced force a step carries when it does not converge).
  pure function support_reaction(an, n) result(r)
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: n
    real(dp) :: r(3)
    r = matmul(an%eq%map%basis(:, :, n), support_reaction_nodal(an, n))
  end function support_reaction

  !> The support reaction at node `n` in its nodal system: exactly zero in the free directions
  !! (rotating the global reaction back would leave round-off there, ~1e-26 N).
  pure function support_reaction_nodal(an, n) result(local)
    type(analysis_t), intent(in) :: an
    integer, intent(in) :: n
    real(dp) :: local(3)
    local = matmul(transpose(an%eq%map%basis(:, :, n)), an%path%fint(:, n) - an%path%f_applied(:, n))
    where (.not. an%eq%map%constrained(:, n)) local = 0.0_dp
  end function support_reaction_nodal

  !> The state of `an` at the end of a step into restart data: the load path, every group's
  !! point states, the values of the matrices the held factors were formed from and the
  !! equation system's flags and counters.
  subroutine save_state(an, data)
    type(analysis_t), intent(in) :: an
    type(restart_data_t), intent(inout) :: data
    integer :: g
    data%u = an%path%u
    data%u_t = an%path%u_t
    data%fint = an%path%fint
    data%f_applied = an%path%f_applied
    data%uc = an%path%uc
    data%release_force = an%path%release_force
    data%active = an%path%active
    allocate (data%states(size(an%states)))
    do g = 1, size(an%states)
      data%states(g) = an%states(g)%point_state_store_t
    end do
    data%a_val = an%eq%a%val
    if (allocated(an%eq%a_full%val)) data%a_full_val = an%eq%a_full%val
    ! an element-partitioned run's ranks each hold their elements' share: the whole matrix
    if (an%part%distributed) then
      call sum_over_ranks(data%a_val, size(data%a_val, kind=i8))
      if (allocated(data%a_full_val)) call sum_over_ranks(data%a_full_val, size(data%a_full_val, kind=i8))
    end if
    data%use_lu = an%eq%use_lu
    data%symmetrized = an%eq%symmetrized
    data%warned_condition = an%eq%warned_condition
    data%lu_singular = an%eq%lu_singular
    data%solver_factorizations = an%eq%solver%factorizations
    data%solves_with_factor = an%eq%solver%solves_with_factor
    data%lower_precision_factors = an%eq%solver%lower_precision_factors
    data%precision_fallbacks = an%eq%solver%precision_fallbacks
    data%test_solve_error = an%eq%solver%test_solve_error
    data%lu_factorizations = an%eq%lu%factorizations
    data%lu_min_rcond = an%eq%lu_min_rcond()
  end subroutine save_state

  !> `an` (set up, its states initialised) as restart data saved it at the end of a step of
  !! stage s: the equations of stage s (renumbered where supports changed up to it), the load
  !! path, the point states, and the held factors formed again from the same matrix values,
  !! so that they are the same bit for bit; the solvers' counters as they were.
  subroutine restore_state(model, an, data, s, summary, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(restart_data_t), intent(in) :: data
    integer, intent(in) :: s
    type(analysis_summary_t), intent(inout) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(dof_map_t) :: map
    integer :: g, j, numbered
    numbered = 1
    do j = 2, s
      if (model%supports_change(j)) numbered = j
    end do
    if (numbered > 1) then
      call build_dof_map(model, map, error, stage=numbered)
      if (allocated(error)) return
      an%eq%map = map
      summary%dofs = an%eq%map%neq
      call analyze_pattern(model, an, summary, error)
      if (allocated(error)) return
    end if
    if (size(data%a_val) /= size(an%eq%a%val) .or. size(data%active) /= size(an%path%active) .or. &
        any(shape(data%u) /= shape(an%path%u))) then
      call fatal_error(error, err_input, data%source // ': its restart data do not fit the model of ' // &
                       model%deck_file // ' (another mesh or other supports)')
      return
    end if
    an%path%u = data%u
    an%path%u_t = data%u_t
    an%path%fint = data%fint
    an%path%f_applied = data%f_applied
    an%path%uc = data%uc
    an%path%release_force = data%release_force
    an%path%active = data%active
    do g = 1, size(an%states)
      an%states(g)%point_state_store_t = data%states(g)
    end do
    an%eq%a%val = data%a_val
    call keep_own_share(model, an, an%eq%a, .false.)
    if (data%solver_factorizations > 0) then
      call an%eq%solver%factorize(an%eq%a, error)
      if (allocated(error)) return
    end if
    an%eq%solver%factorizations = data%solver_factorizations
    an%eq%solver%solves_with_factor = data%solves_with_factor
    an%eq%solver%lower_precision_factors = data%lower_precision_factors
    an%eq%solver%precision_fallbacks = data%precision_fallbacks
    an%eq%solver%test_solve_error = data%test_solve_error
    if (allocated(data%a_full_val)) then
      call analyze_full_pattern(model, an, error)
      if (allocated(error)) return
      an%eq%a_full%val = data%a_full_val
      call keep_own_share(model, an, an%eq%a_full, .true.)
      if (data%use_lu) then
        call an%eq%lu%factorize(an%eq%a_full, error)
        if (allocated(error)) return
      end if
    end if
    an%eq%lu%factorizations = data%lu_factorizations
    call an%eq%set_lu_min_rcond(data%lu_min_rcond)
    an%eq%use_lu = data%use_lu
    an%eq%symmetrized = data%symmetrized
    an%eq%warned_condition = data%warned_condition
    an%eq%lu_singular = data%lu_singular
  end subroutine restore_state

end module feps_analysis_state
