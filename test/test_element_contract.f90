!> The element contract (src/elements/feps_element.f90) for every row of the element catalog:
!! each type is made by `new_element`, says what the catalog says of it, and its stiffness,
!! internal force and strains agree (K u = the internal force of the stresses D B u) with 3 DOFs
!! per node, a plane-strain type's z DOFs left out.
module test_element_contract
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_element, only: element_t
  use feps_solid_element, only: solid_element_t
  use feps_interface_element, only: interface_element_t, new_interface_element
  use feps_bar_element, only: bar_element_t
  use feps_element_catalog, only: new_element, element_info, element_info_t, known_element_types
  implicit none
  private

  public :: collect_element_contract

  !> An affine map of the reference element (det > 0; its in-plane block for 2D types).
  real(dp), parameter :: a_map(3, 3) = reshape([1.2_dp, 0.2_dp, 0.0_dp, 0.1_dp, 0.9_dp, 0.0_dp, &
                                                0.05_dp, 0.1_dp, 1.1_dp], [3, 3])
  real(dp), parameter :: shift(3) = [10.0_dp, -3.0_dp, 2.0_dp]

contains

  !> Collect the suite.
  subroutine collect_element_contract(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('every catalog type is made by new_element and agrees with element_info', test_made), &
      new_unittest('every catalog type: K u equals the internal force of D B u', test_consistent), &
      new_unittest('every catalog type: a rigid translation strains nothing', test_translation), &
      new_unittest('a 2D interface embeds its x-y kernels in 3 DOFs per node', test_embedding), &
      new_unittest('every catalog type: body forces add up to b times its volume or length', test_body_force), &
      new_unittest('every catalog type: point weights add up to its measure (closed form)', test_point_weights)]
  end subroutine collect_element_contract

  !> The catalog's names, one per element.
  function catalog_names() result(names)
    character(len=32), allocatable :: names(:)
    character(len=:), allocatable :: list
    integer :: at
    list = known_element_types() // ','
    allocate (names(0))
    do
      at = index(list, ',')
      if (at == 0) exit
      names = [character(len=32) :: names, adjustl(list(:at - 1))]
      list = list(at + 1:)
    end do
  end function catalog_names

  !> Node coordinates `xe(3, nnodes)` of a valid element of the type: the reference nodes of its
  !! family under the affine map (a 2D type in the x-y plane).
  subroutine reference_nodes(element, xe, error)
    class(element_t), intent(in) :: element
    real(dp), allocatable, intent(out) :: xe(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: xi(:, :), s(:)
    real(dp) :: map(3, 3)
    integer :: p
    allocate (xi(3, element%nnodes()))
    xi = 0.0_dp
    select type (element)
    class is (solid_element_t)
      call element%natural_coordinates(xi)
    type is (interface_element_t)
      p = element%npairs()
      call element%node_coordinates(xi(1:2, 1:p))
      xi(:, p + 1:) = xi(:, 1:p)
    type is (bar_element_t)
      allocate (s(element%nnodes()))
      call element%natural_coordinates(s)
      xi(1, :) = s
    class default
      call check(error, .false., element%element_type() // ': no reference geometry in this test for its family')
      return
    end select
    map = a_map
    if (element%ndim() == 2) then
      map(3, :) = 0.0_dp
      map(:, 3) = 0.0_dp
    end if
    xe = matmul(map, xi)
    if (element%ndim() == 3) xe = xe + spread(shift, 2, size(xe, 2))
  end subroutine reference_nodes

  !> A symmetric positive definite material matrix of `n` components.
  pure function material(n) result(d)
    integer, intent(in) :: n
    real(dp) :: d(n, n)
    integer :: i
    d = 0.1_dp
    do i = 1, n
      d(i, i) = 2.0_dp + i
    end do
  end function material

  subroutine test_made(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=32), allocatable :: names(:)
    character(len=:), allocatable :: name
    class(element_t), allocatable :: element
    type(element_info_t) :: info
    integer :: k
    names = catalog_names()
    call check(error, size(names) > 20, 'the catalog lists its types')
    if (allocated(error)) return
    do k = 1, size(names)
      name = trim(names(k))
      call new_element(name, element, error)
      if (allocated(error)) return
      call element_info(name, info, error)
      if (allocated(error)) return
      call check(error, element%element_type() == name, name // ': element_type() ' // element%element_type())
      if (allocated(error)) return
      call check(error, element%nnodes() == info%nnodes .and. element%npoints() == info%npoints .and. &
                 element%ncomp() == info%ncomp .and. element%ndim() == info%dimension, &
                 name // ': nodes, points, components and dimension as the catalog says')
      if (allocated(error)) return
    end do
    call new_element('interface-quad5', element, error)
    call check(error, allocated(error), 'an unknown name is an error')
    if (allocated(error)) deallocate (error)
  end subroutine test_made

  subroutine test_consistent(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=32), allocatable :: names(:)
    character(len=:), allocatable :: name
    class(element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), u(:), eps(:, :), sig(:, :), d(:, :, :), ke(:, :), fe(:), xg(:, :)
    integer :: k, q, nd, np, nc, i
    names = catalog_names()
    do k = 1, size(names)
      name = trim(names(k))
      call new_element(name, element, error)
      if (allocated(error)) return
      call reference_nodes(element, xe, error)
      if (allocated(error)) return
      nd = 3 * element%nnodes()
      np = element%npoints()
      nc = element%ncomp()
      allocate (u(nd), eps(nc, np), sig(nc, np), d(nc, nc, np), ke(nd, nd), fe(nd), xg(3, np))
      u = [(0.01_dp * sin(1.7_dp * i), i = 1, nd)]
      do q = 1, np
        d(:, :, q) = material(nc)
      end do
      call check(error, element%min_jacobian(xe) > 0.0_dp, name // ': positive Jacobian')
      if (allocated(error)) return
      call element%strains(xe, u, eps)
      do q = 1, np
        sig(:, q) = matmul(d(:, :, q), eps(:, q))
      end do
      call element%internal_force(xe, sig, fe)
      call element%stiffness(xe, d, ke)
      call check(error, maxval(abs(fe - matmul(ke, u))), 0.0_dp, name // ': K u = internal force of D B u', &
                 abs=1.0e-13_dp * maxval(abs(fe)))
      if (allocated(error)) return
      call check(error, maxval(abs(fe)) > 0.0_dp, name // ': the displacements strain the element')
      if (allocated(error)) return
      if (element%ndim() == 2) then
        call check(error, maxval(abs(ke(3::3, :))) + maxval(abs(ke(:, 3::3))) + maxval(abs(fe(3::3))), 0.0_dp, &
                   name // ': 2D: no z stiffness or force', abs=0.0_dp)
        if (allocated(error)) return
      end if
      call element%point_coordinates(xe, xg)
      do i = 1, 3
        call check(error, all(xg(i, :) >= minval(xe(i, :)) - 1.0e-12_dp .and. &
                              xg(i, :) <= maxval(xe(i, :)) + 1.0e-12_dp), name // ': points within the nodes')
        if (allocated(error)) return
      end do
      deallocate (u, eps, sig, d, ke, fe, xg)
    end do
  end subroutine test_consistent

  subroutine test_translation(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=32), allocatable :: names(:)
    character(len=:), allocatable :: name
    class(element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), eps(:, :)
    integer :: k
    names = catalog_names()
    do k = 1, size(names)
      name = trim(names(k))
      call new_element(name, element, error)
      if (allocated(error)) return
      call reference_nodes(element, xe, error)
      if (allocated(error)) return
      allocate (eps(element%ncomp(), element%npoints()))
      call element%strains(xe, reshape(spread([0.3_dp, -0.2_dp, 0.1_dp], 2, element%nnodes()), &
                                       [3 * element%nnodes()]), eps)
      call check(error, maxval(abs(eps)), 0.0_dp, name // ': rigid translation', abs=1.0e-14_dp)
      if (allocated(error)) return
      deallocate (eps)
    end do
  end subroutine test_translation

  !> A uniform body force b per unit measure gives nodal forces that add up to b times the
  !! element's volume (a solid; a plane-strain solid's area, its z force held), its length (a
  !! bar), or nothing (an interface: no thickness, no weight). The measure comes from the
  !! family's own volume or length, the sum of the nodal forces from body_force.
  subroutine test_body_force(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: b(3) = [0.3_dp, -0.7_dp, -2.0_dp]
    character(len=32), allocatable :: names(:)
    character(len=:), allocatable :: name
    class(element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), fe(:)
    real(dp) :: measure, expected(3)
    integer :: k
    names = catalog_names()
    do k = 1, size(names)
      name = trim(names(k))
      call new_element(name, element, error)
      if (allocated(error)) return
      call reference_nodes(element, xe, error)
      if (allocated(error)) return
      allocate (fe(3 * element%nnodes()))
      call element%body_force(xe, b, fe)
      select type (element)
      class is (solid_element_t)
        measure = element%volume(xe)
        expected = b * measure
        if (element%ndim() == 2) expected(3) = 0.0_dp
      class is (bar_element_t)
        measure = element%length(xe)
        expected = b * measure
      class default
        measure = 1.0_dp
        expected = 0.0_dp
      end select
      call check(error, norm2(sum(reshape(fe, [3, element%nnodes()]), dim=2) - expected), 0.0_dp, &
                 name // ': the body forces add up to b times the measure', abs=1.0e-13_dp * norm2(b) * measure)
      if (allocated(error)) return
      deallocate (fe)
    end do
  end subroutine test_body_force

  !> The points' weights (point_weights) of each type on its reference element under the
  !! affine map add up to the closed-form measure: the natural domain's (a cube of side 2: 8; the
  !! unit tetrahedron: 1/6; the wedge, unit triangle times 2: 1; the unit triangle: 1/2; a square
  !! of side 2: 4; a line of length 2: 2) times the map's volume, area or length scale. Every
  !! weight is positive.
  subroutine test_point_weights(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=32), allocatable :: names(:)
    character(len=:), allocatable :: name
    class(element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), w(:)
    real(dp) :: natural, scale, c(3), m(3, 3)
    integer :: k
    names = catalog_names()
    m = a_map
    do k = 1, size(names)
      name = trim(names(k))
      call new_element(name, element, error)
      if (allocated(error)) return
      call reference_nodes(element, xe, error)
      if (allocated(error)) return
      allocate (w(element%npoints()))
      call element%point_weights(xe, w)
      select type (element)
      class is (solid_element_t)
        if (element%ndim() == 2) then
          natural = 0.5_dp                                   ! tri6: the unit triangle
          scale = m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)
        else
          scale = m(1, 1) * (m(2, 2) * m(3, 3) - m(2, 3) * m(3, 2)) - m(1, 2) * (m(2, 1) * m(3, 3) - m(2, 3) * &
                  m(3, 1)) + m(1, 3) * (m(2, 1) * m(3, 2) - m(2, 2) * m(3, 1))
          natural = 8.0_dp
          if (index(name, 'tet') == 1) natural = 1.0_dp / 6.0_dp
          if (index(name, 'wedge') == 1) natural = 1.0_dp
        end if
      type is (interface_element_t)
        if (element%ndim() == 2) then
          natural = 2.0_dp
          scale = norm2(m(1:2, 1))
        else
          natural = 4.0_dp
          if (index(name, 'interface-tri') == 1) natural = 0.5_dp
          c = [m(2, 1) * m(3, 2) - m(3, 1) * m(2, 2), m(3, 1) * m(1, 2) - m(1, 1) * m(3, 2), &
               m(1, 1) * m(2, 2) - m(2, 1) * m(1, 2)]
          scale = norm2(c)
        end if
      class default                                          ! a bar along the first axis
        natural = 2.0_dp
        scale = norm2(m(:, 1))
      end select
      call check(error, minval(w) > 0.0_dp, name // ': every weight is positive')
      if (allocated(error)) return
      call check(error, sum(w), natural * scale, name // ': the weights add up to the measure', &
                 rel=1.0e-13_dp)
      if (allocated(error)) return
      deallocate (w)
    end do
  end subroutine test_point_weights

  !> interface-line2 and line3 (both rules): the contract's stiffness, internal force, strains
  !! and point coordinates are stiffness_nd, ... on the x-y coordinates, placed at the x and y DOFs.
  subroutine test_embedding(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=21), parameter :: names(4) = [character(len=21) :: 'interface-line2', 'interface-line3', &
                                                'interface-line2-nodal', 'interface-line3-nodal']
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), u(:), d(:, :, :), ke(:, :), k2(:, :), fe(:), f2(:), eps(:, :), e2(:, :), &
                             sig(:, :), xg(:, :), x2(:, :)
    integer, allocatable :: xy(:)
    integer :: k, n, np, i
    do k = 1, size(names)
      call new_interface_element(names(k), element, error)
      if (allocated(error)) return
      call reference_nodes(element, xe, error)
      if (allocated(error)) return
      xe(3, :) = 5.0_dp     ! z is not the 2D element's
      n = element%nnodes()
      np = element%npoints()
      xy = [(3 * ((i + 1) / 2) - 2 + mod(i + 1, 2), i = 1, 2 * n)]
      u = [(0.01_dp * cos(0.9_dp * i), i = 1, 3 * n)]
      allocate (d(2, 2, np), ke(3 * n, 3 * n), k2(2 * n, 2 * n), fe(3 * n), f2(2 * n), eps(2, np), e2(2, np), &
                sig(2, np), xg(3, np), x2(2, np))
      d = spread(material(2), 3, np)
      sig = reshape([(real(i, dp), i = 1, 2 * np)], [2, np])
      call element%stiffness(xe, d, ke)
      call element%stiffness_nd(xe(1:2, :), d, k2)
      call element%internal_force(xe, sig, fe)
      call element%internal_force_nd(xe(1:2, :), sig, f2)
      call element%strains(xe, u, eps)
      call element%strains_nd(xe(1:2, :), u(xy), e2)
      call element%point_coordinates(xe, xg)
      call element%point_coordinates_nd(xe(1:2, :), x2)
      call check(error, all(ke(xy, xy) == k2) .and. sum(abs(ke)) == sum(abs(k2)) .and. all(fe(xy) == f2) .and. &
                 sum(abs(fe)) == sum(abs(f2)) .and. all(eps == e2) .and. all(xg(1:2, :) == x2) .and. &
                 all(xg(3, :) == 0.0_dp) .and. element%min_jacobian(xe) == element%min_jacobian_nd(xe(1:2, :)), &
                 trim(names(k)) // ': the x-y kernels at the x and y DOFs, exactly')
      if (allocated(error)) return
      deallocate (d, ke, k2, fe, f2, eps, e2, sig, xg, x2)
    end do
  end subroutine test_embedding

end module test_element_contract
