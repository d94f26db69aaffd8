!> Degrees of freedom: equation numbers, constrained DOFs and nodal coordinate systems.
!! A node whose DOFs are constrained in a cylindrical (or rotated) system carries that
!! system's basis T (columns: radial, hoop, axial); its unknowns are u_local = T^T u_global,
!! element matrices are rotated accordingly, and results are rotated back.
module feps_dof_map
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t
  implicit none
  private

  character(len=1), parameter :: cart_names(3) = ['x', 'y', 'z']
  character(len=5), parameter :: cyl_names(3) = ['r    ', 'theta', 'z    ']

  type, public :: dof_map_t
    integer :: neq = 0                       !! number of equations (free DOFs)
    integer, allocatable :: eq(:, :)         !! (3, nnode): equation, 0 if constrained or unused
    logical, allocatable :: constrained(:, :)
    integer, allocatable :: node_csys(:)     !! nodal system of each node (0: global Cartesian)
    real(dp), allocatable :: basis(:, :, :)  !! (3, 3, nnode) nodal basis, identity if global
    integer, allocatable :: eq_node(:)       !! node of each equation
    integer, allocatable :: eq_dof(:)        !! direction (1..3) of each equation
    logical, allocatable :: used(:)          !! node belongs to some element
    integer :: unused_nodes = 0
    logical :: rotated = .false.             !! some node has a nodal system (set once, read per element)
  contains
    procedure :: dof_name                    !! 'node 12, DOF uy' for messages
    procedure :: has_rotations
  end type dof_map_t

  public :: build_dof_map, build_all_dofs_map

contains

  !> Number the free DOFs of stage `stage` (default 1) node by node; DOFs held in that stage
  !! and nodes of no element get none. A node's nodal system comes from all its constraint
  !! records, whatever their stage, so it does not change between stages. A RELEASE from this
  !! stage must free DOFs held in the stage before, and no DOF a DISPLACE prescribes.
  subroutine build_dof_map(model, map, error, stage)
    type(model_t), intent(in) :: model
    type(dof_map_t), intent(out) :: map
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: stage
    integer :: nn, g, e, c, k, n, cs, d, line_of_csys, s
    integer, allocatable :: csys_line(:)

    s = 1
    if (present(stage)) s = stage

    nn = model%nnode
    allocate (map%eq(3, nn), map%constrained(3, nn), map%node_csys(nn))
    allocate (map%basis(3, 3, nn), map%used(nn), csys_line(nn))
    map%constrained = .false.
    map%node_csys = 0
    csys_line = 0
    map%used = .false.
    do g = 1, size(model%groups)
      do e = 1, size(model%groups(g)%connectivity, 2)
        map%used(model%groups(g)%connectivity(:, e)) = .true.
      end do
    end do
    map%unused_nodes = count(.not. map%used)

    do c = 1, size(model%constraints)
      cs = model%constraints(c)%csys
      do k = 1, size(model%node_sets(model%constraints(c)%node_set)%nodes)
        n = model%node_sets(model%constraints(c)%node_set)%nodes(k)
        ! Constraints in the global Cartesian system need no nodal system.
        if (.not. is_global(model, cs)) then
          if (map%node_csys(n) /= 0 .and. map%node_csys(n) /= cs) then
            line_of_csys = csys_line(n)
            call input_error(error, model%constraints(c)%file, model%constraints(c)%line, 'node ' // str(n) // &
                             ' is constrained in coordinate system ' // str(cs) // ' and, at line ' // &
                             str(line_of_csys) // ', in system ' // str(map%node_csys(n)) // &
                             ': a node can have one nodal system')
            return
          end if
          map%node_csys(n) = cs
          csys_line(n) = model%constraints(c)%line
        end if
      end do
    end do
    ! A node with a nodal system may not also have global constraints on other axes.
    do c = 1, size(model%constraints)
      if (.not. is_global(model, model%constraints(c)%csys)) cycle
      do k = 1, size(model%node_sets(model%constraints(c)%node_set)%nodes)
        n = model%node_sets(model%constraints(c)%node_set)%nodes(k)
        if (map%node_csys(n) /= 0) then
          call input_error(error, model%constraints(c)%file, model%constraints(c)%line, 'node ' // str(n) // &
                           ' is constrained in the global system here and in system ' // str(map%node_csys(n)) // &
                           ' at line ' // str(csys_line(n)) // ': give all its constraints in one system')
          return
        end if
      end do
    end do
    do n = 1, nn
      if (map%node_csys(n) == 0) then
        map%basis(:, :, n) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
      else
        map%basis(:, :, n) = model%systems(map%node_csys(n))%local_basis(model%coords(:, n))
      end if
    end do
    call check_releases(model, s, error)
    if (allocated(error)) return
    map%constrained = held_dofs(model, s)

    map%rotated = any(map%node_csys /= 0)
    ! Plane strain: uz = 0 everywhere.
    if (model%plane_strain) map%constrained(3, :) = .true.
    call number_equations(map)
  end subroutine build_dof_map

  !> The DOFs held in stage s (nodal directions): the constraint records active by then, in
  !! deck order, the last one on a DOF deciding.
  pure function held_dofs(model, s) result(held)
    type(model_t), intent(in) :: model
    integer, intent(in) :: s
    logical :: held(3, model%nnode)
    integer :: c, k
    held = .false.
    do c = 1, size(model%constraints)
      associate (con => model%constraints(c))
        if (con%active_from > s) cycle
        do k = 1, size(model%node_sets(con%node_set)%nodes)
          held(con%dof, model%node_sets(con%node_set)%nodes(k)) = .not. con%release
        end do
      end associate
    end do
  end function held_dofs

  !> The RELEASE records of stage s free DOFs held in stage s - 1, and neither they nor the
  !! FIX records of stage s touch a DOF that a DISPLACE prescribes (a prescribed displacement
  !! holds its DOF in every stage).
  subroutine check_releases(model, s, error)
    type(model_t), intent(in) :: model
    integer, intent(in) :: s
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: before(:, :)
    integer :: c, k, n, p
    if (s <= 1) return
    if (.not. any(model%constraints(:)%active_from == s)) return
    before = held_dofs(model, s - 1)
    do c = 1, size(model%constraints)
      associate (con => model%constraints(c))
        if (con%prescribed .or. con%active_from /= s) cycle
        do k = 1, size(model%node_sets(con%node_set)%nodes)
          n = model%node_sets(con%node_set)%nodes(k)
          do p = 1, size(model%constraints)
            associate (pre => model%constraints(p))
              if (.not. pre%prescribed .or. pre%dof /= con%dof) cycle
              if (.not. any(model%node_sets(pre%node_set)%nodes == n)) cycle
              call input_error(error, con%file, con%line, trim(merge('RELEASE', 'FIX    ', con%release)) // &
                               ' of node ' // str(n) // ', DOF ' // trim(dof_label(model, con%csys, con%dof)) // &
                               ' from stage ' // model%stages(s)%name // ', which DISPLACE at line ' // &
                               str(pre%line) // ' prescribes: a prescribed displacement holds its DOF in every stage')
              return
            end associate
          end do
          if (con%release .and. .not. before(con%dof, n)) then
            call input_error(error, con%file, con%line, 'RELEASE of node ' // str(n) // ', DOF ' // &
                             trim(dof_label(model, con%csys, con%dof)) // ' from stage ' // model%stages(s)%name // &
                             ', which is not held in the stage before (' // model%stages(s - 1)%name // ')')
            return
          end if
        end do
      end associate
    end do
  end subroutine check_releases

  !> 'ux' in a Cartesian system (its own axes), 'ur' / 'utheta' / 'uz' in a cylindrical one.
  function dof_label(model, cs, d) result(label)
    type(model_t), intent(in) :: model
    integer, intent(in) :: cs, d
    character(len=:), allocatable :: label
    if (model%systems(cs)%kind /= 3) then
      label = 'u' // trim(cart_names(d))
    else
      label = 'u' // trim(cyl_names(d))
    end if
  end function dof_label

  !> Every DOF of every node in an element numbered, in global Cartesian directions: the
  !! numbering of the matrices that give internal forces of linear groups as one product.
  subroutine build_all_dofs_map(model, map)
    type(model_t), intent(in) :: model
    type(dof_map_t), intent(out) :: map
    integer :: nn, g, e, n
    nn = model%nnode
    allocate (map%eq(3, nn), map%constrained(3, nn), map%node_csys(nn), map%basis(3, 3, nn), map%used(nn))
    map%constrained = .false.
    map%node_csys = 0
    map%used = .false.
    do g = 1, size(model%groups)
      do e = 1, size(model%groups(g)%connectivity, 2)
        map%used(model%groups(g)%connectivity(:, e)) = .true.
      end do
    end do
    do n = 1, nn
      map%basis(:, :, n) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
    end do
    call number_equations(map)
  end subroutine build_all_dofs_map

  !> Equation numbers for the free DOFs of the nodes that elements use, node by node, and the
  !! inverse maps (equation -> node, direction): what both DOF maps share once `used` and
  !! `constrained` are set.
  pure subroutine number_equations(map)
    type(dof_map_t), intent(inout) :: map
    integer :: n, d
    map%neq = 0
    map%eq = 0
    do n = 1, size(map%used)
      if (.not. map%used(n)) cycle
      do d = 1, 3
        if (map%constrained(d, n)) cycle
        map%neq = map%neq + 1
        map%eq(d, n) = map%neq
      end do
    end do
    allocate (map%eq_node(map%neq), map%eq_dof(map%neq))
    do n = 1, size(map%used)
      do d = 1, 3
        if (map%eq(d, n) > 0) then
          map%eq_node(map%eq(d, n)) = n
          map%eq_dof(map%eq(d, n)) = d
        end if
      end do
    end do
  end subroutine number_equations

  logical function is_global(model, cs)
    type(model_t), intent(in) :: model
    integer, intent(in) :: cs
    is_global = model%systems(cs)%kind /= 3 .and. &
                all(abs(model%systems(cs)%axes - reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, &
                                                          0.0_dp, 0.0_dp, 1.0_dp], [3, 3])) < 1.0e-14_dp)
  end function is_global

  !> 'node N, DOF u<dir>' naming an equation, in the node's own system.
  function dof_name(self, ieq) result(s)
    class(dof_map_t), intent(in) :: self
    integer, intent(in) :: ieq
    character(len=:), allocatable :: s
    integer :: n, d
    n = self%eq_node(ieq)
    d = self%eq_dof(ieq)
    if (self%node_csys(n) == 0) then
      s = 'node ' // str(n) // ', DOF u' // cart_names(d)
    else
      s = 'node ' // str(n) // ', DOF u' // trim(cyl_names(d)) // ' (system ' // str(self%node_csys(n)) // ')'
    end if
  end function dof_name

  !> True if some node has a nodal (cylindrical or rotated) system.
  pure logical function has_rotations(self)
    class(dof_map_t), intent(in) :: self
    has_rotations = self%rotated
  end function has_rotations

end module feps_dof_map
