!> Assembly: the sparse pattern of the free equations, the global stiffness, prescribed-
!! displacement loads, and element results (stresses, internal forces) from displacements.
module feps_assembly
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, fatal_error, input_error, err_input, err_model, str
  use feps_model, only: model_t
  use feps_dof_map, only: dof_map_t
  use feps_sparse_matrix, only: csr_matrix_t
  use feps_element, only: element_t
  use feps_element_catalog, only: new_element, family_solid
  use feps_material, only: material_slot_t
  use feps_material_factory, only: material_of
  implicit none
  private

  !> The element object of one group, made once by the element catalog, and its sizes.
  type, public :: group_kernel_t
    class(element_t), allocatable :: element      !! any family, behind the element contract
    integer :: family = 0                         !! the catalog's family of the group's type
    integer :: nnodes = 0                         !! nodes per element
    integer :: npoints = 0                        !! integration points per element
    integer :: ncomp = 0                          !! stress components per point (6 solid, 3 interface, ...)
  end type group_kernel_t


  public :: build_kernels, build_materials, build_pattern, element_dofs, check_jacobians, node_list
  public :: element_stiffness, element_strains, element_internal_force, scatter_element_matrix, rotate_matrix

contains

  !> One element object per group.
  subroutine build_kernels(model, kernels, error)
    type(model_t), intent(in) :: model
    type(group_kernel_t), allocatable, intent(out) :: kernels(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: g
    allocate (kernels(size(model%groups)))
    do g = 1, size(model%groups)
      associate (k => kernels(g), grp => model%groups(g))
        call new_element(grp%element_type, k%element, error)
        if (allocated(error)) then
          call input_error(error, grp%file, grp%line, 'group ' // grp%name // ': unsupported element type "' // &
                           grp%element_type // '"')
          return
        end if
        k%family = grp%element%family
        k%nnodes = k%element%nnodes()
        k%npoints = k%element%npoints()
        k%ncomp = k%element%ncomp()
      end associate
    end do
  end subroutine build_kernels

  !> One material object per material record: the typed record the deck reader checked.
  subroutine build_materials(model, materials, error)
    type(model_t), intent(in) :: model
    type(material_slot_t), allocatable, intent(out) :: materials(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: m
    allocate (materials(size(model%materials)))
    do m = 1, size(model%materials)
      call material_of(model%materials(m), materials(m)%m, error)
      if (allocated(error)) return
    end do
  end subroutine build_materials

  !> Every element must have a positive Jacobian (solids: determinant at their Gauss points and
  !! nodes; interfaces and bars: their signed surface or line Jacobian). `min_detj` is the
  !! smallest determinant of the solids (the summary's volume mapping check).
  subroutine check_jacobians(model, kernels, min_detj, error)
    type(model_t), intent(in) :: model
    type(group_kernel_t), intent(in) :: kernels(:)
    real(dp), intent(out) :: min_detj
    type(error_t), allocatable, intent(out) :: error
    integer :: g, e
    real(dp) :: lo
    min_detj = huge(1.0_dp)
    do g = 1, size(model%groups)
      associate (group => model%groups(g), element => kernels(g)%element)
        do e = 1, size(group%connectivity, 2)
          lo = element%min_jacobian(model%coords(:, group%connectivity(:, e)))
          if (kernels(g)%family == family_solid) min_detj = min(min_detj, lo)
          if (.not. (lo > 0.0_dp)) then
            call input_error(error, group%file, group%line, element%jacobian_message(str(e) // ' of group ' // &
                             group%name // ' (nodes ' // node_list(group%connectivity(:, e)) // ')', lo))
            return
          end if
        end do
      end associate
    end do
  end subroutine check_jacobians

  !> The node numbers of an element, blank-separated, for messages.
  function node_list(nodes) result(s)
    integer, intent(in) :: nodes(:)
    character(len=:), allocatable :: s
    integer :: i
    s = str(nodes(1))
    do i = 2, size(nodes)
      s = s // ' ' // str(nodes(i))
    end do
  end function node_list

  !> Compressed-row pattern (lower triangle) of the free equations: equation i couples with j
  !! when their nodes share an element. Equations are numbered node by node, so sorted
  !! neighbour nodes give sorted columns.
  subroutine build_pattern(model, map, a, only_groups)
    type(model_t), intent(in) :: model
    type(dof_map_t), intent(in) :: map
    type(csr_matrix_t), intent(out) :: a
    logical, intent(in), optional :: only_groups(:)   !! the groups whose elements count (all if absent)
    integer, allocatable :: node_ptr(:), node_elems(:), fill(:), marker(:), nbr(:)
    integer :: nn, g, e, k, n, m, p, nnbr, d, b, ieq, jeq, id, kmax
    integer(i8) :: pos
    integer, allocatable :: elem_group(:), elem_index(:)

    nn = model%nnode
    ! Node -> elements, elements numbered across groups.
    allocate (node_ptr(nn + 1), fill(nn))
    node_ptr = 0
    allocate (elem_group(model%nelem()), elem_index(model%nelem()))
    id = 0
    do g = 1, size(model%groups)
      if (present(only_groups)) then
        if (.not. only_groups(g)) then
          id = id + size(model%groups(g)%connectivity, 2)
          elem_group(id - size(model%groups(g)%connectivity, 2) + 1:id) = 0
          cycle
        end if
      end if
      do e = 1, size(model%groups(g)%connectivity, 2)
        id = id + 1
        elem_group(id) = g
        elem_index(id) = e
        do k = 1, size(model%groups(g)%connectivity, 1)
          n = model%groups(g)%connectivity(k, e)
          node_ptr(n + 1) = node_ptr(n + 1) + 1
        end do
      end do
    end do
    node_ptr(1) = 1
    do n = 1, nn
      node_ptr(n + 1) = node_ptr(n + 1) + node_ptr(n)
    end do
    allocate (node_elems(node_ptr(nn + 1) - 1))
    fill = node_ptr(1:nn)
    do id = 1, size(elem_group)
      g = elem_group(id)
      if (g == 0) cycle
      e = elem_index(id)
      do k = 1, size(model%groups(g)%connectivity, 1)
        n = model%groups(g)%connectivity(k, e)
        node_elems(fill(n)) = id
        fill(n) = fill(n) + 1
      end do
    end do

    a%n = map%neq
    allocate (a%row_ptr(map%neq + 1), marker(nn))
    kmax = 0
    do g = 1, size(model%groups)
      kmax = max(kmax, size(model%groups(g)%connectivity, 1))
    end do
    allocate (nbr(kmax * max(1, maxval(node_ptr(2:nn + 1) - node_ptr(1:nn)))))
    marker = 0
    ! Two passes: count, then fill.
    do p = 1, 2
      if (p == 2) then
        allocate (a%col(a%row_ptr(map%neq + 1) - 1))
        allocate (a%val(size(a%col)))
        a%val = 0.0_dp
      end if
      pos = 1
      ieq = 0
      marker = 0
      do n = 1, nn
        if (all(map%eq(:, n) == 0)) cycle
        call neighbours(n)
        do d = 1, 3
          ieq = map%eq(d, n)
          if (ieq == 0) cycle
          if (p == 1) a%row_ptr(ieq) = pos
          do k = 1, nnbr
            m = nbr(k)
            do b = 1, 3
              jeq = map%eq(b, m)
              if (jeq == 0 .or. jeq > ieq) cycle
              if (p == 2) a%col(pos) = jeq
              pos = pos + 1
            end do
          end do
        end do
      end do
      if (p == 1) a%row_ptr(map%neq + 1) = pos
    end do

  contains

    !> Sorted nodes sharing an element with node n (n included).
    subroutine neighbours(n)
      integer, intent(in) :: n
      integer :: q, j, node
      nnbr = 0
      do q = node_ptr(n), node_ptr(n + 1) - 1
        id = node_elems(q)
        do j = 1, size(model%groups(elem_group(id))%connectivity, 1)
          node = model%groups(elem_group(id))%connectivity(j, elem_index(id))
          if (marker(node) /= n) then
            marker(node) = n
            nnbr = nnbr + 1
            nbr(nnbr) = node
          end if
        end do
      end do
      call sort_int(nbr(1:nnbr))
    end subroutine neighbours

  end subroutine build_pattern

  !> Insertion sort: neighbour lists are short (<= a few hundred).
  pure subroutine sort_int(v)
    integer, intent(inout) :: v(:)
    integer :: i, j, t
    do i = 2, size(v)
      t = v(i)
      j = i - 1
      do while (j >= 1)
        if (v(j) <= t) exit
        v(j + 1) = v(j)
        j = j - 1
      end do
      v(j + 1) = t
    end do
  end subroutine sort_int

  !> Equation numbers of an element's DOFs (0 for constrained ones).
  pure subroutine element_dofs(map, nodes, dofs)
    type(dof_map_t), intent(in) :: map
    integer, intent(in) :: nodes(:)
    integer, intent(out) :: dofs(:)
    integer :: k
    do k = 1, size(nodes)
      dofs(3 * k - 2:3 * k) = map%eq(:, nodes(k))
    end do
  end subroutine element_dofs

  !> Rotate an element matrix into the nodal systems: ke <- R^T ke R with R = diag(T_node).
  pure subroutine rotate_matrix(map, nodes, ke)
    type(dof_map_t), intent(in) :: map
    integer, intent(in) :: nodes(:)
    real(dp), intent(inout) :: ke(:, :)
    integer :: k, r
    do k = 1, size(nodes)
      if (map%node_csys(nodes(k)) == 0) cycle
      r = 3 * k - 2
      ke(:, r:r + 2) = matmul(ke(:, r:r + 2), map%basis(:, :, nodes(k)))
      ke(r:r + 2, :) = matmul(transpose(map%basis(:, :, nodes(k))), ke(r:r + 2, :))
    end do
  end subroutine rotate_matrix


  !> Add an element matrix into the lower triangle of the free equations (or into both).
  subroutine scatter_element_matrix(dofs, ke, a, both_triangles)
    integer, intent(in) :: dofs(:)
    real(dp), intent(in) :: ke(:, :)
    type(csr_matrix_t), intent(inout) :: a
    logical, intent(in), optional :: both_triangles   !! `a` holds both triangles (full_pattern)
    integer :: i, j
    integer(i8) :: pos
    logical :: lower_only
    lower_only = .true.
    if (present(both_triangles)) lower_only = .not. both_triangles
    do i = 1, size(dofs)
      if (dofs(i) == 0) cycle
      do j = 1, size(dofs)
        if (dofs(j) == 0 .or. (lower_only .and. dofs(j) > dofs(i))) cycle
        pos = a%find(dofs(i), dofs(j))
        a%val(pos) = a%val(pos) + ke(i, j)
      end do
    end do
  end subroutine scatter_element_matrix




  !> Element stiffness from material tangents at its points: d(ncomp, ncomp, npoints), ke with
  !! 3 DOFs per node (every family, a 2D one embedded in them).
  subroutine element_stiffness(kernel, xe, d, ke)
    type(group_kernel_t), intent(in) :: kernel
    real(dp), intent(in) :: xe(:, :), d(:, :, :)
    real(dp), intent(out) :: ke(:, :)
    call kernel%element%stiffness(xe, d, ke)
  end subroutine element_stiffness

  !> Strains (solids: Voigt, engineering shears; interfaces: relative displacements; bars: the
  !! axial strain) at the element's points from its displacements ue (global Cartesian, node by node).
  subroutine element_strains(kernel, xe, ue, eps)
    type(group_kernel_t), intent(in) :: kernel
    real(dp), intent(in) :: xe(:, :), ue(:)
    real(dp), intent(out) :: eps(:, :)
    call kernel%element%strains(xe, ue, eps)
  end subroutine element_strains

  !> Internal nodal forces, sum of B^T sigma over the element's points.
  subroutine element_internal_force(kernel, xe, sig, fe)
    type(group_kernel_t), intent(in) :: kernel
    real(dp), intent(in) :: xe(:, :), sig(:, :)
    real(dp), intent(out) :: fe(:)
    call kernel%element%internal_force(xe, sig, fe)
  end subroutine element_internal_force

end module feps_assembly
