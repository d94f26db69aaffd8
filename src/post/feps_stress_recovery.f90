!> Nodal stresses (and interface tractions) from their Gauss-point values, as finite-element
!! post-processors show them
!! (Abaqus's and CalculiX's "averaged at nodes"): each element's point values are
!! extrapolated to its nodes with the polynomial that interpolates them, and the element values
!! at a node are averaged over the elements of one group (never across groups: the stress of a
!! pipe and of the soil around it differ at their common nodes).
!!
!! The polynomial is the one the integration points determine uniquely, read from the points
!! themselves, so that an element type brings no table of its own:
!! - a tensor-product rule (2x2x2, 3x3x3): the tensor product of 1D polynomials of degree one
!!   less than its distinct coordinates in each direction (trilinear, triquadratic);
!! - a simplex rule (the triangles' 3 and 6 points): the complete polynomials of the total degree
!!   with as many terms as points (linear, quadratic).
!! A stress field in that space is recovered exactly at the nodes (a uniform field by every
!! element; a linear one by all of feps's solids).
module feps_stress_recovery
  use feps_kinds, only: dp
  use feps_solid_element, only: solid_element_t
  implicit none
  private

  public :: extrapolation_matrix, extrapolation_from_points, nodal_average, fill_outside

contains

  !> `e(nen, ngauss)` maps a solid element's values at its Gauss points (in the rule's order) to
  !! its nodes (in connectivity order): nodal = matmul(e, gauss). `ok` is false when the rule's
  !! points determine no polynomial space of their own size (no feps element today).
  pure subroutine extrapolation_matrix(element, e, ok)
    class(solid_element_t), intent(in) :: element
    real(dp), allocatable, intent(out) :: e(:, :)
    logical, intent(out) :: ok
    real(dp), allocatable :: xi_gauss(:, :), w(:), xi_nodes(:, :)
    allocate (xi_gauss(3, element%ngauss()), w(element%ngauss()), xi_nodes(3, element%nnodes()))
    call element%gauss_rule(xi_gauss, w)
    call element%natural_coordinates(xi_nodes)
    call extrapolation_from_points(xi_gauss, xi_nodes, e, ok)
  end subroutine extrapolation_matrix

  !> `e(nnodes, npoints)`: the values at the nodes `nodes(:, nnodes)` of the polynomial that
  !! interpolates values at the points `points(:, npoints)` (natural coordinates, up to 3 rows;
  !! a coordinate that is the same at every point, such as the third of a surface, is not a
  !! variable). `ok` false when the points determine no polynomial space of their own size.
  pure subroutine extrapolation_from_points(points, nodes, e, ok)
    real(dp), intent(in) :: points(:, :)
    real(dp), intent(in) :: nodes(:, :)
    real(dp), allocatable, intent(out) :: e(:, :)
    logical, intent(out) :: ok
    real(dp) :: xi_points(3, size(points, 2)), xi_nodes(3, size(nodes, 2))
    real(dp), allocatable :: at_points(:, :), at_nodes(:, :)
    integer, allocatable :: powers(:, :)
    xi_points = 0.0_dp
    xi_nodes = 0.0_dp
    xi_points(:size(points, 1), :) = points
    xi_nodes(:size(nodes, 1), :) = nodes
    call polynomial_powers(xi_points, powers, ok)
    if (.not. ok) return
    at_points = monomials(xi_points, powers)   ! (npoints, npoints)
    at_nodes = monomials(xi_nodes, powers)     ! (nnodes, npoints)
    ! e = at_nodes inv(at_points): solve at_points^T e^T = at_nodes^T
    call solve_in_place(transpose(at_points), at_nodes, e, ok)
  end subroutine extrapolation_from_points

  !> Average over a group's elements of the values extrapolated to each node. `values(ncomp,
  !! nelem * p)` are element-major Gauss-point values (p = size(e, 2) points per element),
  !! `connectivity(nen, nelem)` the group's nodes; `nodal(ncomp, nnode)` is zero at nodes of
  !! no element of the group, and `count(nnode)` tells how many elements each node averages.
  subroutine nodal_average(e, connectivity, values, nnode, nodal, count)
    real(dp), intent(in) :: e(:, :)               !! (nen, p) from extrapolation_matrix
    integer, intent(in) :: connectivity(:, :)     !! (nen, nelem), 1-based
    real(dp), intent(in) :: values(:, :)          !! (ncomp, nelem * p)
    integer, intent(in) :: nnode
    real(dp), intent(out) :: nodal(:, :)          !! (ncomp, nnode)
    integer, intent(out) :: count(:)              !! (nnode)
    ! Elements per chunk: each chunk's extrapolations are made in parallel (OpenMP) and added to
    ! the nodes in element order, so the sums, and the bits, do not depend on the threads.
    integer, parameter :: chunk = 8192
    real(dp), allocatable :: at_nodes(:, :, :)    !! (ncomp, nen, elements of the chunk)
    integer :: el, a, p, q0, node, first, last
    p = size(e, 2)
    nodal = 0.0_dp
    count = 0
    allocate (at_nodes(size(values, 1), size(connectivity, 1), min(chunk, size(connectivity, 2))))
    do first = 1, size(connectivity, 2), chunk
      last = min(first + chunk - 1, size(connectivity, 2))
      !$omp parallel do schedule(static) private(q0, a)
      do el = first, last
        q0 = (el - 1) * p
        do a = 1, size(connectivity, 1)
          at_nodes(:, a, el - first + 1) = matmul(values(:, q0 + 1:q0 + p), e(a, :))
        end do
      end do
      !$omp end parallel do
      do el = first, last
        do a = 1, size(connectivity, 1)
          node = connectivity(a, el)
          if (node < 1 .or. node > nnode) cycle
          nodal(:, node) = nodal(:, node) + at_nodes(:, a, el - first + 1)
          count(node) = count(node) + 1
        end do
      end do
    end do
    do node = 1, nnode
      if (count(node) > 1) nodal(:, node) = nodal(:, node) / real(count(node), dp)
    end do
  end subroutine nodal_average

  !> Give the nodes of no element of the group (count 0) each column's smallest value over the
  !! group's nodes. Viewers colour a field by its range over all the points of a grid, and feps's
  !! XDMF grid of a group holds every mesh node: zeros there would stretch the colour scale to 0.
  pure subroutine fill_outside(nodal, count)
    real(dp), intent(inout) :: nodal(:, :)     !! (ncomp, nnode)
    integer, intent(in) :: count(:)            !! (nnode) from nodal_average
    integer :: c
    if (.not. any(count > 0)) return
    do c = 1, size(nodal, 1)
      where (count == 0) nodal(c, :) = minval(nodal(c, :), mask=count > 0)
    end do
  end subroutine fill_outside

  !> Exponents `powers(3, n)` of the n monomials the points `xi(3, n)` interpolate uniquely;
  !! `ok` false when neither a tensor product nor a complete polynomial has n terms.
  pure subroutine polynomial_powers(xi, powers, ok)
    real(dp), intent(in) :: xi(:, :)
    integer, allocatable, intent(out) :: powers(:, :)
    logical, intent(out) :: ok
    integer :: distinct(3), n, d, i, j, k, m, degree, terms
    logical :: varies(3)
    n = size(xi, 2)
    do d = 1, 3
      distinct(d) = count_distinct(xi(d, :))
    end do
    varies = distinct > 1
    ok = .true.
    if (product(distinct) == n) then
      allocate (powers(3, n))
      m = 0
      do k = 0, distinct(3) - 1
        do j = 0, distinct(2) - 1
          do i = 0, distinct(1) - 1
            m = m + 1
            powers(:, m) = [i, j, k]
          end do
        end do
      end do
      return
    end if
    ! complete polynomials of total degree `degree` in the varying directions
    do degree = 0, n
      terms = binomial(degree + count(varies), count(varies))
      if (terms >= n) exit
    end do
    if (terms /= n) then
      ok = .false.
      return
    end if
    allocate (powers(3, n))
    m = 0
    do k = 0, merge(degree, 0, varies(3))
      do j = 0, merge(degree, 0, varies(2))
        do i = 0, merge(degree, 0, varies(1))
          if (i + j + k > degree) cycle
          m = m + 1
          powers(:, m) = [i, j, k]
        end do
      end do
    end do
  end subroutine polynomial_powers

  !> Distinct values among `x`, equal within 1e-10 (the rules' points are exact to rounding).
  pure integer function count_distinct(x)
    real(dp), intent(in) :: x(:)
    integer :: i
    count_distinct = 0
    do i = 1, size(x)
      if (all(abs(x(:i - 1) - x(i)) > 1.0e-10_dp)) count_distinct = count_distinct + 1
    end do
  end function count_distinct

  pure integer function binomial(n, k)
    integer, intent(in) :: n, k
    integer :: i
    binomial = 1
    do i = 1, k
      binomial = binomial * (n - k + i) / i
    end do
  end function binomial

  !> Values `v(npoints, nterms)` of the monomials xi^i eta^j zeta^k at the points.
  pure function monomials(xi, powers) result(v)
    real(dp), intent(in) :: xi(:, :)
    integer, intent(in) :: powers(:, :)
    real(dp) :: v(size(xi, 2), size(powers, 2))
    integer :: p, t
    do t = 1, size(powers, 2)
      do p = 1, size(xi, 2)
        v(p, t) = xi(1, p)**powers(1, t) * xi(2, p)**powers(2, t) * xi(3, p)**powers(3, t)
      end do
    end do
  end function monomials

  !> x(m, n) with a(n, n) x^T = b^T for b(m, n), by Gaussian elimination with partial pivoting;
  !! `ok` false when a is singular.
  pure subroutine solve_in_place(a_in, b, x, ok)
    real(dp), intent(in) :: a_in(:, :)
    real(dp), intent(in) :: b(:, :)
    real(dp), allocatable, intent(out) :: x(:, :)
    logical, intent(out) :: ok
    real(dp) :: a(size(a_in, 1), size(a_in, 2)), rhs(size(b, 2), size(b, 1)), row(size(a_in, 2))
    real(dp) :: rrow(size(b, 1))
    integer :: n, c, r, pivot
    n = size(a_in, 1)
    a = a_in
    rhs = transpose(b)
    ok = .true.
    do c = 1, n
      pivot = c - 1 + maxloc(abs(a(c:, c)), dim=1)
      if (abs(a(pivot, c)) <= 1.0e-12_dp * maxval(abs(a))) then
        ok = .false.
        return
      end if
      if (pivot /= c) then
        row = a(c, :); a(c, :) = a(pivot, :); a(pivot, :) = row
        rrow = rhs(c, :); rhs(c, :) = rhs(pivot, :); rhs(pivot, :) = rrow
      end if
      do r = c + 1, n
        rhs(r, :) = rhs(r, :) - a(r, c) / a(c, c) * rhs(c, :)
        a(r, c:) = a(r, c:) - a(r, c) / a(c, c) * a(c, c:)
      end do
    end do
    do c = n, 1, -1
      rhs(c, :) = (rhs(c, :) - matmul(a(c, c + 1:), rhs(c + 1:, :))) / a(c, c)
    end do
    x = transpose(rhs)
  end subroutine solve_in_place

end module feps_stress_recovery
