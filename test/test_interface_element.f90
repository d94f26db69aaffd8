!> Tests of the zero-thickness interface elements: factory, shape functions, integration rules,
!! local frame, B-matrix (relative displacements), stiffness (consistent and nodal pair
!! matrices), internal forces, areas and Jacobians, for all six shapes and both integration
!! choices, on flat elements in a rotated plane and on curved quad8/tri6 surfaces.
module test_interface_element
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_geometry_testing, only: cross, add_edge_integrals
  use feps_error, only: err_input
  use feps_interface_element, only: interface_element_t, new_interface_element, is_interface_type
  implicit none
  private

  public :: collect_interface_element

  !> Shapes of the geometry cases; the last two are curved (parabolic cylinder z = c x^2).
  integer, parameter :: ncases = 8
  character(len=15), parameter :: case_shape(ncases) = [character(len=15) :: &
    'interface-quad4', 'interface-quad8', 'interface-tri3', 'interface-tri6', &
    'interface-line2', 'interface-line3', 'interface-quad8', 'interface-tri6']
  logical, parameter :: case_curved(ncases) = [.false., .false., .false., .false., &
                                               .false., .false., .true., .true.]

  !> Translation of the 3D test elements.
  real(dp), parameter :: shift(3) = [10.0_dp, -5.0_dp, 3.0_dp]

  ! curved cases: quad8 over x in [-qL, qL], y in [0, qW]; tri6 over (0,0), (tL,0), (0,tH)
  real(dp), parameter :: qL = 2.0_dp, qW = 3.0_dp, qc = 0.05_dp
  real(dp), parameter :: tL = 2.0_dp, tH = 1.5_dp, tc = 0.1_dp

contains

  subroutine collect_interface_element(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("factory_and_sizes", test_factory), &
      new_unittest("shape_functions", test_shape_functions), &
      new_unittest("integration_rules_exact_degree", test_integration_rules), &
      new_unittest("point_coordinates", test_point_coordinates), &
      new_unittest("frame_orientation", test_frame), &
      new_unittest("constant_jump_strain", test_constant_jump), &
      new_unittest("rigid_translation", test_rigid_translation), &
      new_unittest("stiffness_symmetry", test_symmetry), &
      new_unittest("area_exact", test_area), &
      new_unittest("consistent_pair_matrices", test_consistent_matrices), &
      new_unittest("internal_force_equals_ke_u", test_internal_force), &
      new_unittest("pressure_nodal_forces", test_pressure), &
      new_unittest("min_jacobian", test_min_jacobian), &
      new_unittest("normal_traction_on_cylinder_resultant_moment", test_cylinder_traction) &
    ]
  end subroutine collect_interface_element

  ! ------------------------------------------------------------------ helpers

  !> Rotation R = Rz(0.7) Ry(-0.4) Rx(1.1): a plane in general position.
  pure function rotation() result(r)
    real(dp) :: r(3, 3), rx(3, 3), ry(3, 3), rz(3, 3)
    rx = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, cos(1.1_dp), sin(1.1_dp), &
                  0.0_dp, -sin(1.1_dp), cos(1.1_dp)], [3, 3])
    ry = reshape([cos(-0.4_dp), 0.0_dp, -sin(-0.4_dp), 0.0_dp, 1.0_dp, 0.0_dp, &
                  sin(-0.4_dp), 0.0_dp, cos(-0.4_dp)], [3, 3])
    rz = reshape([cos(0.7_dp), sin(0.7_dp), 0.0_dp, -sin(0.7_dp), cos(0.7_dp), 0.0_dp, &
                  0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
    r = matmul(rz, matmul(ry, rx))
  end function rotation

  pure function identity3() result(r)
    real(dp) :: r(3, 3)
    integer :: i
    r = 0.0_dp
    do i = 1, 3
      r(i, i) = 1.0_dp
    end do
  end function identity3

  !> Both layers (coincident) from the lower-layer coordinates.
  pure function both_layers(lower) result(xe)
    real(dp), intent(in) :: lower(:, :)
    real(dp) :: xe(size(lower, 1), 2 * size(lower, 2))
    xe(:, 1:size(lower, 2)) = lower
    xe(:, size(lower, 2) + 1:) = lower
  end function both_layers

  !> Lower layer of a 3D element: reference coordinates (3, p) rotated by r and shifted.
  pure function placed(ref, r) result(x)
    real(dp), intent(in) :: ref(:, :), r(3, 3)
    real(dp) :: x(3, size(ref, 2))
    integer :: a
    do a = 1, size(ref, 2)
      x(:, a) = matmul(r, ref(:, a)) + shift
    end do
  end function placed

  !> Corner coordinates followed by the mid-edge points of the closed polygon (serendipity /
  !! tri6 order); `corners` is (nd, k).
  pure function with_midpoints(corners) result(x)
    real(dp), intent(in) :: corners(:, :)
    real(dp) :: x(size(corners, 1), 2 * size(corners, 2))
    integer :: k, i
    k = size(corners, 2)
    x(:, 1:k) = corners
    do i = 1, k
      x(:, k + i) = 0.5_dp * (corners(:, i) + corners(:, modulo(i, k) + 1))
    end do
  end function with_midpoints

  !> Geometry case `icase` (both layers `xe`) with its exact area; 3D cases are rotated by `r`.
  subroutine make_case(icase, nodal, element, xe, exact_area, error)
    integer, intent(in) :: icase
    logical, intent(in) :: nodal
    type(interface_element_t), intent(out) :: element
    real(dp), allocatable, intent(out) :: xe(:, :)
    real(dp), intent(out) :: exact_area
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: quad(3, 4), tri(3, 3), line(2, 2), r(3, 3), k, s, f1, f2
    real(dp), allocatable :: ref(:, :)
    integer :: a
    if (nodal) then
      call new_interface_element(trim(case_shape(icase)) // '-nodal', element, error)
    else
      call new_interface_element(case_shape(icase), element, error)
    end if
    if (allocated(error)) return
    r = rotation()
    quad = reshape([0.0_dp, 0.0_dp, 0.0_dp, 4.0_dp, 0.5_dp, 0.0_dp, 3.5_dp, 3.0_dp, 0.0_dp, &
                    0.5_dp, 2.5_dp, 0.0_dp], [3, 4])
    tri = reshape([0.0_dp, 0.0_dp, 0.0_dp, 3.0_dp, 0.4_dp, 0.0_dp, 1.0_dp, 2.5_dp, 0.0_dp], [3, 3])
    line = reshape([0.3_dp, 0.1_dp, 2.3_dp, 1.6_dp], [2, 2])
    select case (icase)
    case (1, 2)
      ! shoelace formula
      exact_area = 0.0_dp
      do a = 1, 4
        exact_area = exact_area + 0.5_dp * (quad(1, a) * quad(2, modulo(a, 4) + 1) - &
                                            quad(1, modulo(a, 4) + 1) * quad(2, a))
      end do
      if (icase == 1) then
        xe = both_layers(placed(quad, r))
      else
        xe = both_layers(placed(with_midpoints(quad), r))
      end if
    case (3, 4)
      exact_area = 0.5_dp * norm2(cross(tri(:, 2) - tri(:, 1), tri(:, 3) - tri(:, 1)))
      if (icase == 3) then
        xe = both_layers(placed(tri, r))
      else
        xe = both_layers(placed(with_midpoints(tri), r))
      end if
    case (5)
      exact_area = 2.5_dp
      xe = both_layers(line)
    case (6)
      ! straight, middle node off-centre (at 0.45 of the length): |dx/ds| is linear in s
      exact_area = 2.5_dp
      xe = both_layers(reshape([line(:, 1), line(:, 2), line(:, 1) + 0.45_dp * (line(:, 2) - line(:, 1))], &
                               [2, 3]))
    case (7)
      ! quad8 on z = qc x^2 (exactly representable: x linear, z quadratic in xi)
      allocate (ref(3, 8))
      ref(1:2, :) = with_midpoints(reshape([-qL, 0.0_dp, qL, 0.0_dp, qL, qW, -qL, qW], [2, 4]))
      ref(3, :) = qc * ref(1, :)**2
      xe = both_layers(placed(ref, r))
      k = 2.0_dp * qc
      s = sqrt(1.0_dp + (k * qL)**2)
      exact_area = qW * 2.0_dp * (0.5_dp * qL * s + asinh(k * qL) / (2.0_dp * k))
    case (8)
      allocate (ref(3, 6))
      ref(1:2, :) = with_midpoints(reshape([0.0_dp, 0.0_dp, tL, 0.0_dp, 0.0_dp, tH], [2, 3]))
      ref(3, :) = tc * ref(1, :)**2
      xe = both_layers(placed(ref, r))
      ! area = tH * integral_0^tL sqrt(1 + k^2 x^2) (1 - x/tL) dx
      k = 2.0_dp * tc
      s = sqrt(1.0_dp + (k * tL)**2)
      f1 = 0.5_dp * tL * s + asinh(k * tL) / (2.0_dp * k)
      f2 = (s**3 - 1.0_dp) / (3.0_dp * k**2)
      exact_area = tH * (f1 - f2 / tL)
    end select
  end subroutine make_case

  !> Short label of a case for messages.
  pure function label(icase, nodal) result(text)
    integer, intent(in) :: icase
    logical, intent(in) :: nodal
    character(len=:), allocatable :: text
    text = trim(case_shape(icase))
    if (nodal) text = text // '-nodal'
    if (case_curved(icase)) text = text // ' (curved)'
  end function label

  !> Fail when max |actual - expected| exceeds `tol`.
  subroutine check_array(error, actual, expected, tol, what)
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in) :: actual(:), expected(:)
    real(dp), intent(in) :: tol
    character(len=*), intent(in) :: what
    call check(error, maxval(abs(actual - expected)), 0.0_dp, what // ' (max abs difference)', abs=tol)
  end subroutine check_array

  !> A deterministic "random" vector with entries in [-1, 1].
  pure function pseudo_random(n, seed) result(v)
    integer, intent(in) :: n
    real(dp), intent(in) :: seed
    real(dp) :: v(n)
    integer :: i
    do i = 1, n
      v(i) = sin(seed * real(i, dp) + 0.37_dp * real(i, dp)**2)
    end do
  end function pseudo_random

  !> A symmetric, positive definite material matrix (ncomp x ncomp) with coupling terms.
  pure function symmetric_d(nc) result(d)
    integer, intent(in) :: nc
    real(dp) :: d(nc, nc)
    if (nc == 3) then
      d = reshape([2.0_dp, 0.3_dp, 0.1_dp, 0.3_dp, 1.5_dp, -0.2_dp, 0.1_dp, -0.2_dp, 5.0_dp], [3, 3])
    else
      d = reshape([2.0_dp, 0.3_dp, 0.3_dp, 5.0_dp], [2, 2])
    end if
  end function symmetric_d

  !> Natural coordinates of the nodes of one layer (independent table for the tests).
  subroutine node_coordinates(name, s)
    character(len=*), intent(in) :: name
    real(dp), allocatable, intent(out) :: s(:, :)
    select case (name)
    case ('interface-quad4')
      s = reshape([-1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp], [2, 4])
    case ('interface-quad8')
      s = reshape([-1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, &
                   0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp], [2, 8])
    case ('interface-tri3')
      s = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 3])
    case ('interface-tri6')
      s = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
                   0.5_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp, 0.5_dp], [2, 6])
    case ('interface-line2')
      s = reshape([-1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp], [2, 2])
    case default
      s = reshape([-1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 3])
    end select
  end subroutine node_coordinates

  ! ------------------------------------------------------------------ tests

  subroutine test_factory(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=15), parameter :: names(6) = [character(len=15) :: 'interface-quad4', &
      'interface-quad8', 'interface-tri3', 'interface-tri6', 'interface-line2', 'interface-line3']
    integer, parameter :: pairs(6) = [4, 8, 3, 6, 2, 3], dims(6) = [3, 3, 3, 3, 2, 2]
    integer, parameter :: ng_gauss(6) = [4, 9, 3, 6, 2, 3], ng_nodal(6) = [4, 9, 3, 3, 2, 3]
    type(interface_element_t) :: element
    integer :: i
    do i = 1, 6
      call new_interface_element(names(i), element, error)
      if (allocated(error)) return
      call check(error, element%npairs(), pairs(i), trim(names(i)) // ' npairs')
      if (allocated(error)) return
      call check(error, element%nnodes(), 2 * pairs(i), trim(names(i)) // ' nnodes')
      if (allocated(error)) return
      call check(error, element%ndim(), dims(i), trim(names(i)) // ' ndim')
      if (allocated(error)) return
      call check(error, element%ncomp(), dims(i), trim(names(i)) // ' ncomp')
      if (allocated(error)) return
      call check(error, element%ngauss(), ng_gauss(i), trim(names(i)) // ' ngauss')
      if (allocated(error)) return
      call check(error, element%element_type() == trim(names(i)) .and. .not. element%nodal_integration, &
                 trim(names(i)) // ' name and Gauss integration')
      if (allocated(error)) return
      call new_interface_element(' ' // trim(names(i)) // '-NODAL ', element, error)
      if (allocated(error)) return
      call check(error, element%ngauss(), ng_nodal(i), trim(names(i)) // '-nodal ngauss')
      if (allocated(error)) return
      call check(error, element%element_type() == trim(names(i)) // '-nodal' .and. element%nodal_integration, &
                 trim(names(i)) // '-nodal: the catalog name and nodal integration')
      if (allocated(error)) return
      call check(error, is_interface_type(names(i)) .and. is_interface_type(trim(names(i)) // '-nodal'), &
                 trim(names(i)) // ' is an interface type')
      if (allocated(error)) return
    end do
    call check(error, .not. (is_interface_type('hex8') .or. is_interface_type('interface-') .or. &
                             is_interface_type('-nodal') .or. is_interface_type('interface-quad4-nodal-nodal')), &
               'non-interface names rejected by is_interface_type')
    if (allocated(error)) return
    call new_interface_element('interface-quad5', element, error)
    if (.not. allocated(error)) then
      call test_failed(error, 'unknown name accepted')
      return
    end if
    if (error%code /= err_input .or. index(error%message, 'interface-quad5') == 0 .or. &
        index(error%message, 'interface-tri6') == 0) then
      call test_failed(error, 'unknown name: wrong error: ' // error%message)
      return
    end if
    deallocate (error)
  end subroutine test_factory

  !> Partition of unity, Kronecker property at the nodes and derivatives against central
  !! differences (step 1e-5: error O(h^2) ~ 1e-10 for quadratics, tolerance 1e-8).
  subroutine test_shape_functions(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: sn(:, :)
    real(dp) :: n(8), dn(2, 8), np(8), nm(8), dnx(2, 8), s(2), h
    integer :: icase, a, b, k, p, ndir
    h = 1.0e-5_dp
    do icase = 1, 6
      call new_interface_element(case_shape(icase), element, error)
      if (allocated(error)) return
      p = element%npairs()
      ndir = merge(2, 1, element%ndim() == 3)
      call node_coordinates(case_shape(icase), sn)
      do a = 1, p
        call element%shape(sn(:, a), n, dn)
        do b = 1, p
          call check(error, n(b), merge(1.0_dp, 0.0_dp, a == b), trim(case_shape(icase)) // &
                     ' N_b at node a', abs=1.0e-14_dp)
          if (allocated(error)) return
        end do
      end do
      ! a general interior point
      s = [0.21_dp, 0.17_dp]
      if (ndir == 1) s(2) = 0.0_dp
      call element%shape(s, n, dn)
      call check(error, sum(n(1:p)), 1.0_dp, trim(case_shape(icase)) // ' partition of unity', abs=1.0e-14_dp)
      if (allocated(error)) return
      do k = 1, ndir
        call element%shape(s + h * merge(1.0_dp, 0.0_dp, [1, 2] == k), np, dnx)
        call element%shape(s - h * merge(1.0_dp, 0.0_dp, [1, 2] == k), nm, dnx)
        call check_array(error, dn(k, 1:p), (np(1:p) - nm(1:p)) / (2.0_dp * h), 1.0e-8_dp, &
                         trim(case_shape(icase)) // ' derivatives')
        if (allocated(error)) return
      end do
    end do
  end subroutine test_shape_functions

  !> Each rule integrates monomials up to its stated degree exactly (1e-14): Gauss quad 2x2 and
  !! 3x3 to degree 3 / 5 per direction, tri3 degree 2, tri6 degree 4, lines 3 / 5; nodal rules:
  !! Lobatto 2x2 degree 1, Simpson 3x3 degree 3 per direction, vertices degree 1, mid-edges degree 2,
  !! line2 degree 1, line3 degree 3. The degree above is not integrated exactly (rule is sharp).
  subroutine test_integration_rules(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: degree_gauss(6) = [3, 5, 2, 4, 3, 5], degree_nodal(6) = [1, 3, 1, 2, 1, 3]
    type(interface_element_t) :: element
    real(dp) :: s(2, 9), w(9), q, exact
    integer :: icase, i, j, deg, g
    logical :: nodal, sharp
    do icase = 1, 6
      do i = 0, 1
        nodal = i == 1
        call new_interface_element(trim(case_shape(icase)) // merge('-nodal', '      ', nodal), element, error)
        if (allocated(error)) return
        call element%integration_rule(s, w)
        deg = merge(degree_nodal(icase), degree_gauss(icase), nodal)
        sharp = .false.
        do j = 0, deg + 1
          do g = 0, deg + 1
            if (element%ndim() == 2 .and. g > 0) cycle
            select case (icase)
            case (1, 2)
              if (max(j, g) > deg + 1) cycle
              exact = line_moment(j) * line_moment(g)
            case (3, 4)
              if (j + g > deg + 1) cycle
              exact = factorial(j) * factorial(g) / factorial(j + g + 2)
            case default
              exact = line_moment(j)
            end select
            q = sum(w(1:element%ngauss()) * s(1, 1:element%ngauss())**j * s(2, 1:element%ngauss())**g)
            if (max(j, g) <= deg .and. (icase < 3 .or. icase > 4 .or. j + g <= deg)) then
              call check(error, q, exact, label(icase, nodal) // ' monomial ' // achar(48 + j) // ',' // &
                         achar(48 + g), abs=1.0e-14_dp)
              if (allocated(error)) return
            else if (abs(q - exact) > 1.0e-6_dp) then
              sharp = .true.
            end if
          end do
        end do
        call check(error, sharp, label(icase, nodal) // ': some monomial of degree + 1 is not exact')
        if (allocated(error)) return
      end do
    end do
  contains
    pure real(dp) function line_moment(k)
      integer, intent(in) :: k
      line_moment = merge(2.0_dp / real(k + 1, dp), 0.0_dp, modulo(k, 2) == 0)
    end function line_moment
    pure real(dp) function factorial(k)
      integer, intent(in) :: k
      integer :: m
      factorial = 1.0_dp
      do m = 2, k
        factorial = factorial * real(m, dp)
      end do
    end function factorial
  end subroutine test_integration_rules

  !> Nodal rules put their points at the nodes (quad8: the 8 nodes then the centre; tri6: the
  !! mid-edge nodes 4..6); the 2x2 Gauss points of a rectangle [0,3]x[0,2] are at
  !! 1.5 (1 -+ 1/sqrt 3), 1 (1 -+ 1/sqrt 3). Tolerance 1e-13.
  subroutine test_point_coordinates(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), xg(:, :)
    real(dp) :: area_exact, expected(3), r
    integer :: icase, g, p, node
    do icase = 1, ncases
      call make_case(icase, .true., element, xe, area_exact, error)
      if (allocated(error)) return
      allocate (xg(element%ndim(), element%ngauss()))
      call element%point_coordinates_nd(xe, xg)
      p = element%npairs()
      do g = 1, element%ngauss()
        if (case_shape(icase) == 'interface-tri6') then
          node = 3 + g
        else
          node = g
        end if
        if (node <= p) then
          expected(1:element%ndim()) = xe(:, node)
        else
          ! quad8 centre: mean of the mid-edge nodes minus half the mean of the corners
          expected(1:3) = 0.5_dp * sum(xe(:, 5:8), dim=2) - 0.25_dp * sum(xe(:, 1:4), dim=2)
        end if
        call check_array(error, xg(:, g), expected(1:element%ndim()), 1.0e-13_dp, &
                         label(icase, .true.) // ' point at node')
        if (allocated(error)) return
      end do
      deallocate (xg)
    end do
    call new_interface_element('interface-quad4', element, error)
    if (allocated(error)) return
    xe = both_layers(reshape([0.0_dp, 0.0_dp, 0.0_dp, 3.0_dp, 0.0_dp, 0.0_dp, 3.0_dp, 2.0_dp, 0.0_dp, &
                              0.0_dp, 2.0_dp, 0.0_dp], [3, 4]))
    allocate (xg(3, 4))
    call element%point_coordinates_nd(xe, xg)
    r = 1.0_dp / sqrt(3.0_dp)
    call check_array(error, [xg], [1.5_dp * (1 - r), 1 - r, 0.0_dp, 1.5_dp * (1 + r), 1 - r, 0.0_dp, &
                                   1.5_dp * (1 - r), 1 + r, 0.0_dp, 1.5_dp * (1 + r), 1 + r, 0.0_dp], &
                     1.0e-13_dp, 'quad4 Gauss points of a rectangle')
  end subroutine test_point_coordinates

  !> Frame: orthonormal and right-handed (1e-13) everywhere; n = +z for a face in z = 0 numbered
  !! counter-clockwise; 2D n = +y for a line from (0,0) to (1,0); rotated flat elements: n = R e_z
  !! (e1 in the plane); 2D general line: e1 along the line; curved cases: n and e1 equal the
  !! analytical normal (-2cx, 0, 1) and tangent (1, 0, 2cx) (normalised, then rotated) at the point.
  subroutine test_frame(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), b(:, :), xg(:, :)
    real(dp) :: frame(3, 3), wdet, area_exact, r(3, 3), xr(3), c, nref(3), e1ref(3), orth(3, 3)
    integer :: icase, g, i, nd
    logical :: nodal
    r = rotation()
    do icase = 1, ncases
      do i = 0, 1
        nodal = i == 1
        call make_case(icase, nodal, element, xe, area_exact, error)
        if (allocated(error)) return
        nd = element%ndim()
        allocate (b(nd, nd * element%nnodes()), xg(nd, element%ngauss()))
        call element%point_coordinates_nd(xe, xg)
        do g = 1, element%ngauss()
          frame = 0.0_dp
          call element%point_b(xe, g, b, wdet, frame(1:nd, 1:nd))
          orth(1:nd, 1:nd) = matmul(frame(1:nd, 1:nd), transpose(frame(1:nd, 1:nd)))
          if (nd == 3) then
            call check_array(error, [orth], [identity3()], 1.0e-13_dp, label(icase, nodal) // ' frame orthonormal')
          else
            call check_array(error, [orth(1:2, 1:2)], [1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], 1.0e-13_dp, &
                             label(icase, nodal) // ' frame orthonormal')
          end if
          if (allocated(error)) return
          if (nd == 3) then
            orth = transpose(frame)
            call check_array(error, cross(orth(:, 1), orth(:, 2)), orth(:, 3), 1.0e-13_dp, &
                             label(icase, nodal) // ' frame right-handed')
            if (allocated(error)) return
          end if
          if (.not. case_curved(icase)) then
            if (nd == 3) then
              call check_array(error, frame(3, :), r(:, 3), 1.0e-13_dp, label(icase, nodal) // ' n = R e_z')
            else
              call check_array(error, [frame(1, 1:2), frame(2, 1:2)], [0.8_dp, 0.6_dp, -0.6_dp, 0.8_dp], &
                               1.0e-13_dp, label(icase, nodal) // ' 2D frame of the line')
            end if
            if (allocated(error)) return
          else
            xr = matmul(transpose(r), xg(:, g) - shift)
            c = merge(qc, tc, case_shape(icase) == 'interface-quad8')
            nref = [-2.0_dp * c * xr(1), 0.0_dp, 1.0_dp] / sqrt(1.0_dp + (2.0_dp * c * xr(1))**2)
            e1ref = [1.0_dp, 0.0_dp, 2.0_dp * c * xr(1)] / sqrt(1.0_dp + (2.0_dp * c * xr(1))**2)
            call check_array(error, [frame(3, :), frame(1, :)], [matmul(r, nref), matmul(r, e1ref)], &
                             1.0e-13_dp, label(icase, nodal) // ' analytical n and e1 of the curved surface')
            if (allocated(error)) return
          end if
        end do
        deallocate (b, xg)
      end do
    end do
    ! unrotated: face in z = 0 counter-clockwise seen from +z, and the unit line along x
    call new_interface_element('interface-quad4', element, error)
    if (allocated(error)) return
    xe = both_layers(reshape([0.0_dp, 0.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 2.0_dp, 1.0_dp, 0.0_dp, &
                              0.0_dp, 1.0_dp, 0.0_dp], [3, 4]))
    allocate (b(3, 24))
    call element%point_b(xe, 1, b, wdet, frame)
    call check_array(error, [frame], [identity3()], 1.0e-14_dp, 'quad4 in z = 0: frame = identity, n = +z')
    if (allocated(error)) return
    deallocate (b)
    call new_interface_element('interface-line2', element, error)
    if (allocated(error)) return
    xe = both_layers(reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp], [2, 2]))
    allocate (b(2, 8))
    call element%point_b(xe, 1, b, wdet, frame(1:2, 1:2))
    call check_array(error, [frame(1:2, 1:2)], [1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], 1.0e-14_dp, &
                     'line2 (0,0)-(1,0): e1 = +x, n = +y')
  end subroutine test_frame

  !> Upper = lower + a (lower displaced arbitrarily): strain = frame a at every point, from both
  !! point_b and strains (1e-12).
  subroutine test_constant_jump(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), b(:, :), ue(:), eps(:, :)
    real(dp) :: frame(3, 3), wdet, area_exact, jump(3)
    integer :: icase, g, i, nd, p, half
    logical :: nodal
    jump = [0.3_dp, -0.7_dp, 1.1_dp]
    do icase = 1, ncases
      do i = 0, 1
        nodal = i == 1
        call make_case(icase, nodal, element, xe, area_exact, error)
        if (allocated(error)) return
        nd = element%ndim()
        p = element%npairs()
        half = nd * p
        allocate (b(nd, 2 * half), ue(2 * half), eps(nd, element%ngauss()))
        ue(1:half) = pseudo_random(half, 1.3_dp)
        do g = 1, p
          ue(half + nd * (g - 1) + 1:half + nd * g) = ue(nd * (g - 1) + 1:nd * g) + jump(1:nd)
        end do
        call element%strains_nd(xe, ue, eps)
        do g = 1, element%ngauss()
          call element%point_b(xe, g, b, wdet, frame(1:nd, 1:nd))
          call check_array(error, matmul(b, ue), matmul(frame(1:nd, 1:nd), jump(1:nd)), 1.0e-12_dp, &
                           label(icase, nodal) // ' B ue = frame a')
          if (allocated(error)) return
          call check_array(error, eps(:, g), matmul(frame(1:nd, 1:nd), jump(1:nd)), 1.0e-12_dp, &
                           label(icase, nodal) // ' strains = frame a')
          if (allocated(error)) return
        end do
        deallocate (b, ue, eps)
      end do
    end do
  end subroutine test_constant_jump

  !> The same displacement on both layers: zero strain (1e-13) and ke u = 0 (1e-12 max|ke| |u|).
  subroutine test_rigid_translation(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), ue(:), eps(:, :), ke(:, :), d(:, :, :)
    real(dp) :: area_exact, move(3)
    integer :: icase, g, i, nd, p, half
    logical :: nodal
    move = [0.4_dp, 1.2_dp, -0.9_dp]
    do icase = 1, ncases
      do i = 0, 1
        nodal = i == 1
        call make_case(icase, nodal, element, xe, area_exact, error)
        if (allocated(error)) return
        nd = element%ndim()
        p = element%npairs()
        half = nd * p
        allocate (ue(2 * half), eps(nd, element%ngauss()), ke(2 * half, 2 * half), &
                  d(nd, nd, element%ngauss()))
        do g = 1, element%nnodes()
          ue(nd * (g - 1) + 1:nd * g) = move(1:nd)
        end do
        do g = 1, element%ngauss()
          d(:, :, g) = symmetric_d(nd)
        end do
        call element%strains_nd(xe, ue, eps)
        call check_array(error, [eps], [(0.0_dp, g = 1, size(eps))], 1.0e-13_dp, label(icase, nodal) // &
                         ' rigid translation strain')
        if (allocated(error)) return
        call element%stiffness_nd(xe, d, ke)
        call check_array(error, matmul(ke, ue), [(0.0_dp, g = 1, 2 * half)], &
                         1.0e-12_dp * maxval(abs(ke)) * norm2(move), label(icase, nodal) // ' ke u rigid')
        if (allocated(error)) return
        deallocate (ue, eps, ke, d)
      end do
    end do
  end subroutine test_rigid_translation

  !> Symmetric D gives a symmetric ke (1e-14 max|ke|), and a non-zero one.
  subroutine test_symmetry(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), ke(:, :), d(:, :, :)
    real(dp) :: area_exact
    integer :: icase, g, i, nd
    logical :: nodal
    do icase = 1, ncases
      do i = 0, 1
        nodal = i == 1
        call make_case(icase, nodal, element, xe, area_exact, error)
        if (allocated(error)) return
        nd = element%ndim()
        allocate (ke(nd * element%nnodes(), nd * element%nnodes()), d(nd, nd, element%ngauss()))
        do g = 1, element%ngauss()
          d(:, :, g) = symmetric_d(nd) * (1.0_dp + 0.1_dp * g)
        end do
        call element%stiffness_nd(xe, d, ke)
        call check(error, maxval(abs(ke)) > 0.1_dp * area_exact, label(icase, nodal) // ' ke not zero')
        if (allocated(error)) return
        call check_array(error, [ke], [transpose(ke)], 1.0e-14_dp * maxval(abs(ke)), &
                         label(icase, nodal) // ' ke symmetric')
        if (allocated(error)) return
        deallocate (ke, d)
      end do
    end do
  end subroutine test_symmetry

  !> Sum of wdet (and area()) equals the exact area: flat elements closed form (1e-12 rel);
  !! curved ones (parabolic cylinder, closed form with asinh) within the quadrature error of
  !! sqrt(1 + k^2 x^2), k = 0.2: Gauss rules 1e-6 rel, nodal rules 2e-4 rel (actual errors
  !! about 1e-7 and 7e-5; a projected or wrong Jacobian would be off by about 1%).
  subroutine test_area(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), b(:, :)
    real(dp) :: frame(3, 3), wdet, area_exact, total, tol
    integer :: icase, g, i, nd
    logical :: nodal
    do icase = 1, ncases
      do i = 0, 1
        nodal = i == 1
        call make_case(icase, nodal, element, xe, area_exact, error)
        if (allocated(error)) return
        nd = element%ndim()
        allocate (b(nd, nd * element%nnodes()))
        total = 0.0_dp
        do g = 1, element%ngauss()
          call element%point_b(xe, g, b, wdet, frame(1:nd, 1:nd))
          total = total + wdet
        end do
        tol = 1.0e-12_dp
        if (case_curved(icase)) tol = merge(2.0e-4_dp, 1.0e-6_dp, nodal)
        call check(error, total, area_exact, label(icase, nodal) // ' sum of wdet', rel=tol)
        if (allocated(error)) return
        call check(error, element%area(xe), area_exact, label(icase, nodal) // ' area()', rel=tol)
        if (allocated(error)) return
        deallocate (b)
      end do
    end do
  end subroutine test_area

  !> Compare ke with the pair matrix [M (x) Dg, -M (x) Dg; -M (x) Dg, M (x) Dg] (rel 1e-13 of max).
  subroutine check_pair_matrix(error, element, xe, dlocal, dglobal, m, what)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t), intent(in) :: element
    real(dp), intent(in) :: xe(:, :), dlocal(:, :), dglobal(:, :), m(:, :)
    character(len=*), intent(in) :: what
    real(dp) :: ke(element%ndim() * element%nnodes(), element%ndim() * element%nnodes())
    real(dp) :: expected(size(ke, 1), size(ke, 2))
    real(dp) :: d(element%ncomp(), element%ncomp(), element%ngauss())
    integer :: g, a, c, nd, p, ra, rc, la, lc
    nd = element%ndim()
    p = element%npairs()
    do g = 1, element%ngauss()
      d(:, :, g) = dlocal
    end do
    call element%stiffness_nd(xe, d, ke)
    do c = 1, p
      do a = 1, p
        la = nd * (a - 1)
        lc = nd * (c - 1)
        ra = la + nd * p
        rc = lc + nd * p
        expected(la + 1:la + nd, lc + 1:lc + nd) = m(a, c) * dglobal
        expected(la + 1:la + nd, rc + 1:rc + nd) = -m(a, c) * dglobal
        expected(ra + 1:ra + nd, lc + 1:lc + nd) = -m(a, c) * dglobal
        expected(ra + 1:ra + nd, rc + 1:rc + nd) = m(a, c) * dglobal
      end do
    end do
    call check_array(error, [ke], [expected], 1.0e-13_dp * maxval(abs(expected)), what)
  end subroutine check_pair_matrix

  !> Exact integration: with D = diag(ks, [ks,] kn) the stiffness is the consistent "mass-like"
  !! matrix M of the shape functions times C^T D C; nodal rules give the lumped M (pairs decoupled
  !! except for the quad8 centre point). Flat quad4 a x b: entry (lower 1, upper 1, normal) =
  !! -kn a b / 9, nodal -kn a b / 4. 3D elements rotated by R (C^T D C = R D R^T).
  subroutine test_consistent_matrices(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: ks = 1000.0_dp, kn = 2000.0_dp, a = 3.0_dp, b = 2.0_dp, h = 1.7_dp
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :)
    real(dp) :: ke(24, 24), d(3, 3, 4), d3(3, 3), d2(2, 2), r(3, 3), dg3(3, 3), dg2(2, 2), q(2, 2)
    real(dp) :: m4(4, 4), m8(8, 8), m3(3, 3), m6(6, 6), m2(2, 2), v8(8), area, length
    real(dp) :: rect(3, 4), tri(3, 3), line(2, 2)
    integer :: g, i
    d3 = reshape([ks, 0.0_dp, 0.0_dp, 0.0_dp, ks, 0.0_dp, 0.0_dp, 0.0_dp, kn], [3, 3])
    d2 = reshape([ks, 0.0_dp, 0.0_dp, kn], [2, 2])
    rect = reshape([0.0_dp, 0.0_dp, 0.0_dp, a, 0.0_dp, 0.0_dp, a, b, 0.0_dp, 0.0_dp, b, 0.0_dp], [3, 4])
    tri = reshape([0.0_dp, 0.0_dp, 0.0_dp, a, 0.0_dp, 0.0_dp, 1.0_dp, h, 0.0_dp], [3, 3])

    ! the explicit entry of the brief, unrotated quad4 in z = 0
    do g = 1, 4
      d(:, :, g) = d3
    end do
    call new_interface_element('interface-quad4', element, error)
    if (allocated(error)) return
    xe = both_layers(rect)
    call element%stiffness_nd(xe, d, ke)
    call check(error, ke(3, 12 + 3), -kn * a * b / 9.0_dp, 'quad4 Gauss: ke(lower 1 z, upper 1 z)', rel=1.0e-13_dp)
    if (allocated(error)) return
    call new_interface_element('interface-quad4-nodal', element, error)
    if (allocated(error)) return
    call element%stiffness_nd(xe, d, ke)
    call check(error, ke(3, 12 + 3), -kn * a * b / 4.0_dp, 'quad4 nodal: ke(lower 1 z, upper 1 z)', rel=1.0e-13_dp)
    if (allocated(error)) return
    call check(error, maxval(abs([ke(1:3, 4:12), ke(1:3, 16:24)])), 0.0_dp, &
               'quad4 nodal: no coupling of pair 1 with other pairs', abs=1.0e-12_dp * kn)
    if (allocated(error)) return

    ! full matrices in the rotated plane
    r = rotation()
    dg3 = matmul(r, matmul(d3, transpose(r)))
    area = a * b
    m4 = area / 36.0_dp * reshape([4, 2, 1, 2, 2, 4, 2, 1, 1, 2, 4, 2, 2, 1, 2, 4], [4, 4])
    call new_interface_element('interface-quad4', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(rect, r)), d3, dg3, m4, 'quad4 consistent')
    if (allocated(error)) return
    call new_interface_element('interface-quad4-nodal', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(rect, r)), d3, dg3, diagonal(4, area / 4.0_dp), &
                           'quad4 nodal lumped')
    if (allocated(error)) return

    ! quad8 on a rectangle: consistent serendipity matrix (A/180, exact symbolic integration)
    m8 = area / 180.0_dp * reshape([ &
      6, 2, 3, 2, -6, -8, -8, -6,  2, 6, 2, 3, -6, -6, -8, -8,  3, 2, 6, 2, -8, -6, -6, -8, &
      2, 3, 2, 6, -8, -8, -6, -6,  -6, -6, -8, -8, 32, 20, 16, 20,  -8, -6, -6, -8, 20, 32, 20, 16, &
      -8, -8, -6, -6, 16, 20, 32, 20,  -6, -8, -8, -6, 20, 16, 20, 32], [8, 8])
    call new_interface_element('interface-quad8', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(with_midpoints(rect), r)), d3, dg3, m8, &
                           'quad8 consistent')
    if (allocated(error)) return
    ! Simpson 3x3: node weights A/36 (corners), A/9 (mid-edges), and the centre (4A/9) where
    ! N = -1/4 (corners), 1/2 (mid-edges)
    v8 = [-0.25_dp, -0.25_dp, -0.25_dp, -0.25_dp, 0.5_dp, 0.5_dp, 0.5_dp, 0.5_dp]
    m8 = 0.0_dp
    do i = 1, 8
      m8(i, i) = merge(area / 36.0_dp, area / 9.0_dp, i <= 4)
      m8(:, i) = m8(:, i) + 4.0_dp * area / 9.0_dp * v8 * v8(i)
    end do
    call new_interface_element('interface-quad8-nodal', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(with_midpoints(rect), r)), d3, dg3, m8, &
                           'quad8 nodal (Simpson)')
    if (allocated(error)) return

    ! triangles (edge 1-2 along x, so the reference frame is the identity)
    area = 0.5_dp * a * h
    m3 = area / 12.0_dp * reshape([2, 1, 1, 1, 2, 1, 1, 1, 2], [3, 3])
    call new_interface_element('interface-tri3', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(tri, r)), d3, dg3, m3, 'tri3 consistent')
    if (allocated(error)) return
    call new_interface_element('interface-tri3-nodal', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(tri, r)), d3, dg3, diagonal(3, area / 3.0_dp), &
                           'tri3 nodal lumped')
    if (allocated(error)) return
    m6 = area / 180.0_dp * reshape([ &
      6, -1, -1, 0, -4, 0,  -1, 6, -1, 0, 0, -4,  -1, -1, 6, -4, 0, 0, &
      0, 0, -4, 32, 16, 16,  -4, 0, 0, 16, 32, 16,  0, -4, 0, 16, 16, 32], [6, 6])
    call new_interface_element('interface-tri6', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(with_midpoints(tri), r)), d3, dg3, m6, &
                           'tri6 consistent')
    if (allocated(error)) return
    m6 = 0.0_dp
    do i = 4, 6
      m6(i, i) = area / 3.0_dp
    end do
    call new_interface_element('interface-tri6-nodal', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(placed(with_midpoints(tri), r)), d3, dg3, m6, &
                           'tri6 nodal (mid-edge points)')
    if (allocated(error)) return

    ! lines along (0.8, 0.6), length 2.5: C = [e1; n] = [0.8 0.6; -0.6 0.8]
    line = reshape([0.3_dp, 0.1_dp, 2.3_dp, 1.6_dp], [2, 2])
    length = 2.5_dp
    q = reshape([0.8_dp, -0.6_dp, 0.6_dp, 0.8_dp], [2, 2])
    dg2 = matmul(transpose(q), matmul(d2, q))
    m2 = length / 6.0_dp * reshape([2, 1, 1, 2], [2, 2])
    call new_interface_element('interface-line2', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(line), d2, dg2, m2, 'line2 consistent')
    if (allocated(error)) return
    call new_interface_element('interface-line2-nodal', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, both_layers(line), d2, dg2, diagonal(2, length / 2.0_dp), &
                           'line2 nodal lumped')
    if (allocated(error)) return
    m3 = length / 30.0_dp * reshape([4, -1, 2, -1, 4, 2, 2, 2, 16], [3, 3])
    xe = both_layers(reshape([line(:, 1), line(:, 2), 0.5_dp * (line(:, 1) + line(:, 2))], [2, 3]))
    call new_interface_element('interface-line3', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, xe, d2, dg2, m3, 'line3 consistent')
    if (allocated(error)) return
    m3 = 0.0_dp
    m3(1, 1) = length / 6.0_dp
    m3(2, 2) = length / 6.0_dp
    m3(3, 3) = 2.0_dp * length / 3.0_dp
    call new_interface_element('interface-line3-nodal', element, error)
    if (allocated(error)) return
    call check_pair_matrix(error, element, xe, d2, dg2, m3, 'line3 nodal (Simpson)')
  contains
    pure function diagonal(n, value) result(m)
      integer, intent(in) :: n
      real(dp), intent(in) :: value
      real(dp) :: m(n, n)
      integer :: k
      m = 0.0_dp
      do k = 1, n
        m(k, k) = value
      end do
    end function diagonal
  end subroutine test_consistent_matrices

  !> sig = D(g) B ue with a non-symmetric D varying by point: internal_force = ke ue
  !! (1e-12 of max|ke ue|); and the element's tabulated rule is its computed one, bit for bit.
  subroutine test_internal_force(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), ue(:), eps(:, :), sig(:, :), ke(:, :), d(:, :, :), fe(:), ku(:)
    real(dp) :: area_exact
    integer :: icase, g, i, nd, ndof
    logical :: nodal
    do icase = 1, ncases
      do i = 0, 1
        nodal = i == 1
        call make_case(icase, nodal, element, xe, area_exact, error)
        if (allocated(error)) return
        nd = element%ndim()
        ndof = nd * element%nnodes()
        allocate (ue(ndof), eps(nd, element%ngauss()), sig(nd, element%ngauss()), ke(ndof, ndof), &
                  d(nd, nd, element%ngauss()), fe(ndof), ku(ndof))
        ue = pseudo_random(ndof, 0.91_dp)
        do g = 1, element%ngauss()
          d(:, :, g) = symmetric_d(nd) + reshape(pseudo_random(nd * nd, 0.2_dp * g), [nd, nd])
        end do
        call element%strains_nd(xe, ue, eps)
        do g = 1, element%ngauss()
          sig(:, g) = matmul(d(:, :, g), eps(:, g))
        end do
        call element%internal_force_nd(xe, sig, fe)
        call element%stiffness_nd(xe, d, ke)
        ku = matmul(ke, ue)
        call check_array(error, fe, ku, 1.0e-12_dp * maxval(abs(ku)), label(icase, nodal) // ' fe = ke ue')
        if (allocated(error)) return
        call check_computed_rule(error, element, xe, ue, d, eps, ke, label(icase, nodal))
        if (allocated(error)) return
        deallocate (ue, eps, sig, ke, d, fe, ku)
      end do
    end do
  end subroutine test_internal_force

  !> The rule and shape functions an element tabulates when it is made (new_interface_element)
  !! are those it computes otherwise: the same element without its table gives the strains
  !! `eps`, the stiffness `ke` and the same forces (of some tractions) bit for bit.
  subroutine check_computed_rule(error, element, xe, ue, d, eps, ke, name)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t), intent(in) :: element
    real(dp), intent(in) :: xe(:, :), ue(:), d(:, :, :), eps(:, :), ke(:, :)
    character(len=*), intent(in) :: name
    type(interface_element_t) :: computed
    real(dp) :: eps2(size(eps, 1), size(eps, 2)), fe1(size(ue)), fe2(size(ue)), ke2(size(ke, 1), size(ke, 2))
    if (.not. element%tabulated) then
      call test_failed(error, name // ': new_interface_element made no table')
      return
    end if
    computed = element
    computed%tabulated = .false.
    call computed%strains_nd(xe, ue, eps2)
    call element%internal_force_nd(xe, eps, fe1)
    call computed%internal_force_nd(xe, eps, fe2)
    call computed%stiffness_nd(xe, d, ke2)
    if (any(eps2 /= eps) .or. any(fe2 /= fe1) .or. any(ke2 /= ke)) &
      call test_failed(error, name // ': the tabulated rule differs from the computed one')
  end subroutine check_computed_rule


  !> Uniform normal traction p on flat elements: the upper-layer nodal forces are p n int(N_a)
  !! (quad4 A/4; quad8 corners -A/12, mid-edges A/3; tri3 A/3; tri6 corners 0, mid-edges A/3;
  !! line2 L/2; line3 L/6, L/6, 2L/3 for a centred middle node), summing to p A n; the lower
  !! layer gets the opposite. Both rules (1e-12 rel of p A).
  subroutine test_pressure(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: p = -2.5_dp
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :), sig(:, :), fe(:), share(:), b(:, :)
    real(dp) :: area_exact, frame(3, 3), wdet, normal(3), total(3)
    integer :: icase, i, nd, np, a, lo, up
    logical :: nodal
    do icase = 1, 6
      do i = 0, 1
        nodal = i == 1
        call make_case(icase, nodal, element, xe, area_exact, error)
        if (allocated(error)) return
        nd = element%ndim()
        np = element%npairs()
        if (icase == 6) xe(:, [3, 6]) = 0.5_dp * (xe(:, [1, 4]) + xe(:, [2, 5]))
        select case (icase)
        case (1)
          ! shares of a general quad4 are not A/4: use a parallelogram
          xe(:, [3, 7]) = xe(:, [2, 6]) + xe(:, [4, 8]) - xe(:, [1, 5])
          area_exact = norm2(cross(xe(:, 2) - xe(:, 1), xe(:, 4) - xe(:, 1)))
          share = [0.25_dp, 0.25_dp, 0.25_dp, 0.25_dp]
        case (2)
          xe(:, [3, 11]) = xe(:, [2, 10]) + xe(:, [4, 12]) - xe(:, [1, 9])
          xe(:, [6, 14]) = 0.5_dp * (xe(:, [2, 10]) + xe(:, [3, 11]))
          xe(:, [7, 15]) = 0.5_dp * (xe(:, [3, 11]) + xe(:, [4, 12]))
          area_exact = norm2(cross(xe(:, 2) - xe(:, 1), xe(:, 4) - xe(:, 1)))
          share = [-1.0_dp, -1.0_dp, -1.0_dp, -1.0_dp, 4.0_dp, 4.0_dp, 4.0_dp, 4.0_dp] / 12.0_dp
        case (3)
          share = [1.0_dp, 1.0_dp, 1.0_dp] / 3.0_dp
        case (4)
          share = [0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp] / 3.0_dp
        case (5)
          share = [0.5_dp, 0.5_dp]
        case (6)
          share = [1.0_dp, 1.0_dp, 4.0_dp] / 6.0_dp
        end select
        allocate (sig(nd, element%ngauss()), fe(nd * 2 * np), b(nd, nd * 2 * np))
        sig = 0.0_dp
        sig(nd, :) = p
        call element%internal_force_nd(xe, sig, fe)
        call element%point_b(xe, 1, b, wdet, frame(1:nd, 1:nd))
        normal(1:nd) = frame(nd, 1:nd)
        total = 0.0_dp
        do a = 1, np
          lo = nd * (a - 1)
          up = nd * (np + a - 1)
          call check_array(error, fe(up + 1:up + nd), p * area_exact * share(a) * normal(1:nd), &
                           1.0e-12_dp * abs(p) * area_exact, label(icase, nodal) // ' upper nodal force')
          if (allocated(error)) return
          call check_array(error, fe(lo + 1:lo + nd), -fe(up + 1:up + nd), 1.0e-12_dp * abs(p) * area_exact, &
                           label(icase, nodal) // ' lower force opposite')
          if (allocated(error)) return
          total(1:nd) = total(1:nd) + fe(up + 1:up + nd)
        end do
        call check_array(error, total(1:nd), p * area_exact * normal(1:nd), 1.0e-12_dp * abs(p) * area_exact, &
                         label(icase, nodal) // ' resultant p A n')
        if (allocated(error)) return
        deallocate (sig, fe, b)
      end do
    end do
  end subroutine test_pressure

  !> Rectangle a x b: min Jacobian a b / 4 (both rules); flat triangle: 2A; line2: L/2;
  !! a quad4 with a re-entrant corner is negative at the nearest point; a collapsed element gives 0. Tolerance 1e-13 rel.
  subroutine test_min_jacobian(error)
    type(error_t), allocatable, intent(out) :: error
    type(interface_element_t) :: element
    real(dp), allocatable :: xe(:, :)
    real(dp) :: rect(3, 4), r(3, 3)
    integer :: i
    r = rotation()
    rect = reshape([0.0_dp, 0.0_dp, 0.0_dp, 3.0_dp, 0.0_dp, 0.0_dp, 3.0_dp, 2.0_dp, 0.0_dp, &
                    0.0_dp, 2.0_dp, 0.0_dp], [3, 4])
    do i = 0, 1
      call new_interface_element('interface-quad4' // trim(merge('-nodal', '      ', i == 1)), element, error)
      if (allocated(error)) return
      call check(error, element%min_jacobian_nd(both_layers(placed(rect, r))), 1.5_dp, 'quad4 rectangle', &
                 rel=1.0e-13_dp)
      if (allocated(error)) return
      call new_interface_element('interface-quad8' // trim(merge('-nodal', '      ', i == 1)), element, error)
      if (allocated(error)) return
      call check(error, element%min_jacobian_nd(both_layers(placed(with_midpoints(rect), r))), 1.5_dp, &
                 'quad8 rectangle', rel=1.0e-13_dp)
      if (allocated(error)) return
    end do
    call new_interface_element('interface-tri3', element, error)
    if (allocated(error)) return
    call check(error, element%min_jacobian_nd(both_layers(placed(rect(:, [1, 2, 4]), r))), 6.0_dp, &
               'tri3: 2 A', rel=1.0e-13_dp)
    if (allocated(error)) return
    call new_interface_element('interface-line2', element, error)
    if (allocated(error)) return
    call check(error, element%min_jacobian_nd(both_layers(reshape([0.3_dp, 0.1_dp, 2.3_dp, 1.6_dp], [2, 2]))), &
               1.25_dp, 'line2: L/2', rel=1.0e-13_dp)
    if (allocated(error)) return
    call new_interface_element('interface-quad4', element, error)
    if (allocated(error)) return
    ! re-entrant corner 3 at (0.5, 0.5): the (linear) Jacobian is 6, 1.5, -3.5, 1 at the corners / 4
    rect(:, 3) = [0.5_dp, 0.5_dp, 0.0_dp]
    call check(error, element%min_jacobian_nd(both_layers(placed(rect, r))), &
               0.25_dp * (1.25_dp - 4.75_dp / sqrt(3.0_dp)), 'inverted quad4: negative Jacobian', rel=1.0e-13_dp)
    if (allocated(error)) return
    xe = both_layers(spread(shift, 2, 4))
    call check(error, element%min_jacobian_nd(xe), 0.0_dp, 'collapsed quad4', abs=0.0_dp)
  end subroutine test_min_jacobian

  !> A uniform normal traction sigma_n = p (tangential ones zero) on interface elements whose lower
  !! layer lies on a cylinder (r = 2.5, theta 0.05..0.75 rad, a height of 1.2, every node then
  !! moved by up to 0.02, rotated and shifted into general position): the upper layer's nodal
  !! forces (Gauss rules) have the resultant p A, A = 1/2 closed-integral of x cross dx, and the
  !! moment sum x_a cross f_a = p int x cross n dA = -p/2 closed-integral of |x|^2 dx, the loop
  !! running along the layer's edges through their nodes (Stokes; exact for these rules: degree
  !! 5 per direction for quad8, 4 for tri6, 2 for quad4). The lower layer carries the opposite
  !! forces. 2D lines on a circle of radius 2.5: resultant p (-(y2 - y1), x2 - x1), moment
  !! p (|x2|^2 - |x1|^2) / 2 about the origin. A wrong sign or axis of n fails. Tolerance 1e-13.
  subroutine test_cylinder_traction(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: nshape = 6
    character(len=15), parameter :: shapes(nshape) = [character(len=15) :: 'interface-quad4', 'interface-quad8', &
      'interface-tri3', 'interface-tri6', 'interface-line2', 'interface-line3']
    ! natural coordinates of the lower-layer nodes: quad (s1, s2) in [-1, 1]^2, tri (L2, L3),
    ! lines s1 (ends, then the middle)
    real(dp), parameter :: quad_nat(2, 8) = reshape([-1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, &
                                                     -1.0_dp, 1.0_dp, 0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, &
                                                     0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp], [2, 8])
    real(dp), parameter :: tri_nat(2, 6) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
                                                    0.5_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp, 0.5_dp], [2, 6])
    real(dp), parameter :: line_nat(3) = [-1.0_dp, 1.0_dp, 0.0_dp], p = -3.0_dp, radius = 2.5_dp
    type(interface_element_t) :: element
    real(dp), allocatable :: lower(:, :), xe(:, :), sig(:, :), fe(:)
    real(dp) :: r(3, 3), u(2), th, force(3), moment(3), area(3), loop(3), xa(3), xb(3), xm(3), x(3)
    real(dp) :: m2, scale
    integer :: k, np, nd, a, corners, edge, up
    integer, allocatable :: mid(:)
    r = rotation()
    do k = 1, nshape
      call new_interface_element(shapes(k), element, error)
      if (allocated(error)) return
      np = element%npairs()
      nd = element%ndim()
      allocate (lower(nd, np))
      do a = 1, np
        select case (k)
        case (1, 2)
          u = [0.5_dp * (quad_nat(1, a) + 1.0_dp), 0.5_dp * (quad_nat(2, a) + 1.0_dp)]
        case (3, 4)
          u = tri_nat(:, a)
        case default
          u = [0.5_dp * (line_nat(a) + 1.0_dp), 0.0_dp]
        end select
        th = 0.05_dp + 0.7_dp * u(1)
        if (nd == 3) then
          x = [radius * cos(th), radius * sin(th), 1.2_dp * u(2)] + 0.02_dp * pseudo_random(3, 0.3_dp * a + 0.1_dp)
          lower(:, a) = matmul(r, x) + shift
        else
          lower(:, a) = [radius * cos(th), radius * sin(th)]
        end if
      end do
      xe = both_layers(lower)
      allocate (sig(nd, element%ngauss()), fe(nd * 2 * np))
      sig = 0.0_dp
      sig(nd, :) = p
      call element%internal_force_nd(xe, sig, fe)
      force = 0.0_dp
      moment = 0.0_dp
      do a = 1, np
        up = nd * (np + a - 1)
        call check_array(error, fe(nd * (a - 1) + 1:nd * a), -fe(up + 1:up + nd), 1.0e-14_dp * abs(p), &
                         trim(shapes(k)) // ' on a cylinder: lower forces opposite the upper ones')
        if (allocated(error)) return
        force(1:nd) = force(1:nd) + fe(up + 1:up + nd)
        if (nd == 3) then
          moment = moment + cross(lower(:, a), fe(up + 1:up + 3))
        else
          moment(3) = moment(3) + lower(1, a) * fe(up + 2) - lower(2, a) * fe(up + 1)
        end if
      end do
      if (nd == 2) then
        area = [-(lower(2, 2) - lower(2, 1)), lower(1, 2) - lower(1, 1), 0.0_dp]
        loop = [0.0_dp, 0.0_dp, -0.5_dp * (sum(lower(:, 2)**2) - sum(lower(:, 1)**2))]
      else
        ! edges: corner to corner, through their mid-edge node (quad8: 5-8, tri6: 4-6)
        corners = merge(4, 3, k <= 2)
        if (np > corners) then
          mid = [(corners + edge, edge = 1, corners)]
        else
          mid = [(0, edge = 1, corners)]
        end if
        area = 0.0_dp
        loop = 0.0_dp
        do edge = 1, corners
          xa = lower(:, edge)
          xb = lower(:, mod(edge, corners) + 1)
          if (mid(edge) > 0) then
            xm = lower(:, mid(edge))
          else
            xm = 0.5_dp * (xa + xb)
          end if
          call add_edge_integrals(xa, xb, xm, area, loop)
        end do
      end if
      m2 = norm2(area)
      scale = abs(p) * m2 * maxval(abs(lower))
      call check_array(error, force, p * area, 1.0e-13_dp * abs(p) * m2, trim(shapes(k)) // &
                       ' on a cylinder: resultant p A')
      if (allocated(error)) return
      call check_array(error, moment, -p * loop, 1.0e-13_dp * scale, trim(shapes(k)) // &
                       ' on a cylinder: moment -p/2 loop integral of |x|^2 dx')
      if (allocated(error)) return
      deallocate (lower, sig, fe)
    end do
  end subroutine test_cylinder_traction

end module test_interface_element
