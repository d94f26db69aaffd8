!> Tests of the tetrahedra and wedges (tet4, tet10, wedge6, wedge15) and, through the same loops,
!! hex8 and hex20: the triangle, tetrahedron and wedge rules, node orders (CalculiX/Abaqus C3D4,
!! C3D10, C3D6, C3D15), shape functions, volumes, every face (shape functions, node lists,
!! outward normals, areas, consistent loads, closed surfaces), the constant-strain patch test,
!! the zero-energy modes and the exactness of each volume rule on an undistorted element.
!! Reference values come from closed forms or from this file's own quadrature (collapsed
!! Gauss-Legendre products on the simplices), never from the rules under test.
module test_solid_elements
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_geometry_testing, only: cross, linear_field, voigt_strain, rigid_mode
  use feps_elasticity_testing, only: isotropic_d, d_at_points
  use feps_error, only: str
  use feps_lapack, only: dsyev
  use feps_gauss, only: gauss_legendre, triangle_rule, tetrahedron_rule, wedge_rule
  use feps_solid_element, only: solid_element_t
  use feps_element_catalog, only: new_element => new_solid_element
  implicit none
  private

  public :: collect_solid_elements

  !> The elements of every loop, by their factory names.
  integer, parameter :: n_kinds = 6
  character(len=7), parameter :: names(n_kinds) = ['tet4   ', 'tet10  ', 'wedge6 ', 'wedge15', 'hex8   ', 'hex20  ']

  !> Reference shapes: the tetrahedron (0 <= xi_i, sum <= 1), the wedge (triangle times
  !! zeta in [-1, 1]) and the cube [-1, 1]^3, with their volumes.
  integer, parameter :: tet = 1, wedge = 2, hex = 3
  integer, parameter :: shape_of(n_kinds) = [tet, tet, wedge, wedge, hex, hex]
  real(dp), parameter :: reference_volume(3) = [1.0_dp / 6.0_dp, 1.0_dp, 8.0_dp]

  !> Nodes, volume Gauss points and faces of each element, as the brief states them.
  integer, parameter :: nen(n_kinds) = [4, 10, 6, 15, 8, 20]
  integer, parameter :: ngauss(n_kinds) = [1, 4, 6, 18, 8, 27]
  integer, parameter :: nfaces(3) = [4, 5, 6]

  !> Corner pairs of the mid-edge nodes, in the brief's node order (independent copies).
  integer, parameter :: tet10_edges(2, 6) = reshape([1, 2, 2, 3, 3, 1, 1, 4, 2, 4, 3, 4], [2, 6])
  integer, parameter :: wedge15_edges(2, 9) = reshape([1, 2, 2, 3, 3, 1, 4, 5, 5, 6, 6, 4, 1, 4, 2, 5, 3, 6], [2, 9])
  integer, parameter :: hex20_edges(2, 12) = reshape([1, 2, 2, 3, 3, 4, 4, 1, 5, 6, 6, 7, 7, 8, 8, 5, &
                                                      1, 5, 2, 6, 3, 7, 4, 8], [2, 12])

  !> Corner nodes of each face as Abaqus lists them (S1, S2, ...; a triangle's 4th is 0).
  integer, parameter :: abaqus_tet_faces(4, 4) = reshape([1, 2, 3, 0, 1, 4, 2, 0, 2, 4, 3, 0, 3, 4, 1, 0], [4, 4])
  integer, parameter :: abaqus_wedge_faces(4, 5) = reshape([1, 2, 3, 0, 4, 6, 5, 0, 1, 4, 5, 2, 2, 5, 6, 3, &
                                                            3, 6, 4, 1], [4, 5])
  integer, parameter :: abaqus_hex_faces(4, 6) = reshape([1, 2, 3, 4, 5, 8, 7, 6, 1, 5, 6, 2, 2, 6, 7, 3, &
                                                          3, 7, 8, 4, 4, 8, 5, 1], [4, 6])

  !> The affine map x = A xi + c of the test elements (det A = 1.3905).
  real(dp), parameter :: amap(3, 3) = reshape([1.2_dp, 0.1_dp, -0.2_dp, 0.3_dp, 0.9_dp, 0.15_dp, &
                                               -0.1_dp, 0.25_dp, 1.4_dp], [3, 3])
  real(dp), parameter :: cmap(3) = [0.5_dp, -1.0_dp, 2.0_dp]

  !> A displacement gradient and translation for the patch test.
  real(dp), parameter :: hgrad(3, 3) = reshape([0.1_dp, -0.3_dp, 0.25_dp, 0.7_dp, -0.2_dp, 0.05_dp, &
                                                -0.45_dp, 0.33_dp, 0.6_dp], [3, 3])

contains

  subroutine collect_solid_elements(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("simplex_and_wedge_rules", test_rules), &
      new_unittest("factory_and_counts", test_factory), &
      new_unittest("kronecker_and_partition_of_unity", test_kronecker_unity), &
      new_unittest("derivatives_finite_difference", test_derivatives_fd), &
      new_unittest("volume_reference_and_affine", test_volume), &
      new_unittest("face_shapes_and_traces", test_face_shapes), &
      new_unittest("face_lists_and_reference_normals", test_face_lists), &
      new_unittest("faces_affine_area_normal_loads", test_faces_affine), &
      new_unittest("closed_surface_distorted", test_closed_surface), &
      new_unittest("patch_test_constant_strain", test_patch), &
      new_unittest("zero_energy_modes", test_zero_energy_modes), &
      new_unittest("volume_rule_exact_undistorted", test_exact_stiffness) &
    ]
  end subroutine collect_solid_elements

  ! ------------------------------------------------------------------ helpers

  !> The element of kind `k` from the factory.
  subroutine make_element(k, element)
    integer, intent(in) :: k
    class(solid_element_t), allocatable, intent(out) :: element
    type(error_t), allocatable :: error
    call new_element(names(k), element, error)
  end subroutine make_element

  !> Corners followed by the midpoints of the listed edges.
  pure function with_mid_edges(corners, edges) result(xi)
    real(dp), intent(in) :: corners(:, :)
    integer, intent(in) :: edges(:, :)
    real(dp) :: xi(size(corners, 1), size(corners, 2) + size(edges, 2))
    integer :: m
    xi(:, 1:size(corners, 2)) = corners
    do m = 1, size(edges, 2)
      xi(:, size(corners, 2) + m) = 0.5_dp * (corners(:, edges(1, m)) + corners(:, edges(2, m)))
    end do
  end function with_mid_edges

  !> Natural coordinates of the nodes of kind `k`, built from the brief's node order.
  pure function reference_nodes(k) result(xi)
    integer, intent(in) :: k
    real(dp), allocatable :: xi(:, :)
    real(dp) :: corners(3, 8)
    select case (shape_of(k))
    case (tet)
      corners(:, 1:4) = reshape([0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1] * 1.0_dp, [3, 4])
      xi = corners(:, 1:4)
      if (nen(k) == 10) xi = with_mid_edges(corners(:, 1:4), tet10_edges)
    case (wedge)
      corners(:, 1:6) = reshape([0, 0, -1, 1, 0, -1, 0, 1, -1, 0, 0, 1, 1, 0, 1, 0, 1, 1] * 1.0_dp, [3, 6])
      xi = corners(:, 1:6)
      if (nen(k) == 15) xi = with_mid_edges(corners(:, 1:6), wedge15_edges)
    case default
      corners = reshape([-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, &
                         -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1] * 1.0_dp, [3, 8])
      xi = corners
      if (nen(k) == 20) xi = with_mid_edges(corners, hex20_edges)
    end select
  end function reference_nodes

  !> Face-local coordinates of the nodes of a face with `nfn` nodes (triangles: area coordinates,
  !! quadrilaterals: [-1, 1]^2; corners, then the midpoints of the face edges).
  pure function face_node_s(nfn) result(s)
    integer, intent(in) :: nfn
    real(dp), allocatable :: s(:, :)
    integer, parameter :: tri_edges(2, 3) = reshape([1, 2, 2, 3, 3, 1], [2, 3])
    integer, parameter :: quad_edges(2, 4) = reshape([1, 2, 2, 3, 3, 4, 4, 1], [2, 4])
    real(dp), parameter :: tri(2, 3) = reshape([0, 0, 1, 0, 0, 1] * 1.0_dp, [2, 3])
    real(dp), parameter :: quad(2, 4) = reshape([-1, -1, 1, -1, 1, 1, -1, 1] * 1.0_dp, [2, 4])
    select case (nfn)
    case (3)
      s = tri
    case (6)
      s = with_mid_edges(tri, tri_edges)
    case (4)
      s = quad
    case default
      s = with_mid_edges(quad, quad_edges)
    end select
  end function face_node_s

  !> Interior sample points of the reference shape of kind `k`.
  pure function sample_points(k) result(xi)
    integer, intent(in) :: k
    real(dp) :: xi(3, 5)
    select case (shape_of(k))
    case (tet)
      xi = reshape([0.1_dp, 0.2_dp, 0.3_dp, 0.25_dp, 0.25_dp, 0.25_dp, 0.6_dp, 0.1_dp, 0.05_dp, &
                    0.05_dp, 0.7_dp, 0.1_dp, 0.3_dp, 0.05_dp, 0.55_dp], [3, 5])
    case (wedge)
      xi = reshape([0.1_dp, 0.2_dp, -0.3_dp, 0.3_dp, 0.35_dp, 0.0_dp, 0.6_dp, 0.1_dp, 0.8_dp, &
                    0.05_dp, 0.7_dp, -0.9_dp, 0.3_dp, 0.45_dp, 0.55_dp], [3, 5])
    case default
      xi = reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.3_dp, -0.7_dp, 0.55_dp, -0.9_dp, 0.2_dp, 0.8_dp, &
                    0.6_dp, -0.4_dp, 0.35_dp, -0.123_dp, 0.456_dp, -0.789_dp], [3, 5])
    end select
  end function sample_points

  !> The reference nodes of kind `k` under x = A xi + c: straight edges, flat faces.
  pure function affine_element(k) result(xe)
    integer, intent(in) :: k
    real(dp), allocatable :: xe(:, :)
    integer :: a
    xe = reference_nodes(k)
    do a = 1, size(xe, 2)
      xe(:, a) = matmul(amap, xe(:, a)) + cmap
    end do
  end function affine_element

  !> The affine element with every node moved by up to 0.06 in each direction: curved edges and
  !! faces for the quadratic elements, warped quadrilateral faces for wedge6 and hex8 (tet4 stays
  !! a tetrahedron, the only shape it has).
  pure function distorted_element(k) result(xe)
    integer, intent(in) :: k
    real(dp), allocatable :: xe(:, :)
    integer :: a, i
    xe = affine_element(k)
    do a = 1, size(xe, 2)
      do i = 1, 3
        xe(i, a) = xe(i, a) + 0.06_dp * sin(1.7_dp * a + 2.3_dp * i + 0.5_dp)
      end do
    end do
  end function distorted_element

  !> A quadrature of the reference shape of kind `k` independent of the rules under test:
  !! collapsed (Duffy) products of 5-point Gauss-Legendre on the simplices, xi1 = u,
  !! xi2 = (1 - u) v, xi3 = (1 - u)(1 - v) t with weight (1 - u)^2 (1 - v) on the tetrahedron
  !! (exact to total degree 7), (1 - u) on the triangle (degree 8), and 5-point Gauss in zeta and
  !! on the cube (degree 9 in each coordinate).
  pure subroutine independent_rule(k, xi, w)
    integer, intent(in) :: k
    real(dp), allocatable, intent(out) :: xi(:, :), w(:)
    real(dp) :: x(5), wx(5), u(5), wu(5)
    integer :: i, j, l, p
    call gauss_legendre(5, x, wx)
    u = 0.5_dp * (x + 1.0_dp)   ! the rule on [0, 1]
    wu = 0.5_dp * wx
    allocate (xi(3, 125), w(125))
    p = 0
    do l = 1, 5
      do j = 1, 5
        do i = 1, 5
          p = p + 1
          select case (shape_of(k))
          case (tet)
            xi(:, p) = [u(i), (1.0_dp - u(i)) * u(j), (1.0_dp - u(i)) * (1.0_dp - u(j)) * u(l)]
            w(p) = wu(i) * wu(j) * wu(l) * (1.0_dp - u(i))**2 * (1.0_dp - u(j))
          case (wedge)
            xi(:, p) = [u(i), (1.0_dp - u(i)) * u(j), x(l)]
            w(p) = wu(i) * wu(j) * wx(l) * (1.0_dp - u(i))
          case default
            xi(:, p) = [x(i), x(j), x(l)]
            w(p) = wx(i) * wx(j) * wx(l)
          end select
        end do
      end do
    end do
  end subroutine independent_rule

  !> n! for small n.
  pure real(dp) function factorial(n)
    integer, intent(in) :: n
    integer :: i
    factorial = 1.0_dp
    do i = 2, n
      factorial = factorial * i
    end do
  end function factorial

  ! ------------------------------------------------------------------ rules

  !> Triangle rules integrate s1^p s2^q exactly (p! q! / (p + q + 2)!) up to their degree (1, 2,
  !! 4 for 1, 3, 6 points) and miss some monomial of the next degree; tetrahedron rules likewise
  !! (p! q! r! / (p + q + r + 3)!, degree 1 and 2 for 1 and 4 points); the wedge rule of 6 x 3
  !! points integrates s1^p s2^q zeta^r for p + q <= 4, r <= 5 (zeta: 2/(r + 1) for even r, 0
  !! for odd). Tolerance 1e-15 (the integrals are at most 1). A 2-point triangle rule is refused.
  subroutine test_rules(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: refused
    integer, parameter :: tri_n(3) = [1, 3, 6], tri_degree(3) = [1, 2, 4]
    integer, parameter :: tet_n(2) = [1, 4], tet_degree(2) = [1, 2]
    real(dp) :: s(2, 6), ws(6), xi(3, 18), w(18), exact, worst
    integer :: m, p, q, r, d
    do m = 1, 3
      call triangle_rule(tri_n(m), s, ws, error)
      if (allocated(error)) return
      do d = 0, tri_degree(m) + 1
        worst = 0.0_dp
        do p = 0, d
          q = d - p
          exact = factorial(p) * factorial(q) / factorial(p + q + 2)
          worst = max(worst, abs(sum(ws(1:tri_n(m)) * s(1, 1:tri_n(m))**p * s(2, 1:tri_n(m))**q) - exact))
        end do
        if (d <= tri_degree(m)) then
          call check(error, worst, 0.0_dp, 'triangle rule ' // str(tri_n(m)) // ': degree ' // str(d), abs=1.0e-15_dp)
        else
          call check(error, worst > 1.0e-6_dp, 'triangle rule ' // str(tri_n(m)) // ' must miss degree ' // str(d))
        end if
        if (allocated(error)) return
      end do
    end do
    do m = 1, 2
      call tetrahedron_rule(tet_n(m), xi, w, error)
      if (allocated(error)) return
      do d = 0, tet_degree(m) + 1
        worst = 0.0_dp
        do p = 0, d
          do q = 0, d - p
            r = d - p - q
            exact = factorial(p) * factorial(q) * factorial(r) / factorial(d + 3)
            worst = max(worst, abs(sum(w(1:tet_n(m)) * xi(1, 1:tet_n(m))**p * xi(2, 1:tet_n(m))**q * &
                                       xi(3, 1:tet_n(m))**r) - exact))
          end do
        end do
        if (d <= tet_degree(m)) then
          call check(error, worst, 0.0_dp, 'tetrahedron rule ' // str(tet_n(m)) // ': degree ' // str(d), &
                     abs=1.0e-15_dp)
        else
          call check(error, worst > 1.0e-6_dp, 'tetrahedron rule ' // str(tet_n(m)) // ' must miss degree ' // str(d))
        end if
        if (allocated(error)) return
      end do
    end do
    call wedge_rule(6, 3, xi, w, error)
    if (allocated(error)) return
    do d = 0, 4
      do p = 0, d
        q = d - p
        do r = 0, 5
          exact = factorial(p) * factorial(q) / factorial(p + q + 2) * merge(2.0_dp / (r + 1), 0.0_dp, mod(r, 2) == 0)
          call check(error, sum(w * xi(1, :)**p * xi(2, :)**q * xi(3, :)**r), exact, 'wedge rule 6 x 3: s1^' // &
                     str(p) // ' s2^' // str(q) // ' zeta^' // str(r), abs=1.0e-15_dp)
          if (allocated(error)) return
        end do
      end do
    end do
    call triangle_rule(2, s, ws, refused)
    call check(error, allocated(refused), 'a 2-point triangle rule must be refused')
  end subroutine test_rules

  ! ------------------------------------------------------------------ factory and counts

  !> The factory makes every kind with its name, node, point and face counts, and each face's
  !! node and point counts: tetrahedra 3/6 nodes and 3/6 points on every face, wedges triangles
  !! (faces 1, 2) of 3/6 nodes and 3/6 points and quadrilaterals of 4/8 nodes and 4/9 points.
  subroutine test_factory(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    integer :: k, face, nfn, nfg
    do k = 1, n_kinds
      call make_element(k, element)
      call check(error, allocated(element), trim(names(k)) // ': made by the factory')
      if (allocated(error)) return
      call check(error, element%element_type() == trim(names(k)), 'element_type of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, element%nnodes(), nen(k), trim(names(k)) // ': nnodes')
      if (allocated(error)) return
      call check(error, element%ngauss(), ngauss(k), trim(names(k)) // ': ngauss')
      if (allocated(error)) return
      call check(error, element%nfaces(), nfaces(shape_of(k)), trim(names(k)) // ': nfaces')
      if (allocated(error)) return
      do face = 1, element%nfaces()
        select case (names(k))
        case ('tet4', 'wedge6')
          nfn = merge(3, 4, shape_of(k) == tet .or. face <= 2)
          nfg = merge(3, 4, shape_of(k) == tet .or. face <= 2)
        case ('tet10', 'wedge15')
          nfn = merge(6, 8, shape_of(k) == tet .or. face <= 2)
          nfg = merge(6, 9, shape_of(k) == tet .or. face <= 2)
        case ('hex8')
          nfn = 4
          nfg = 4
        case default
          nfn = 8
          nfg = 9
        end select
        call check(error, element%nface_nodes(face), nfn, trim(names(k)) // ': nface_nodes(' // str(face) // ')')
        if (allocated(error)) return
        call check(error, size(element%face_nodes(face)), nfn, trim(names(k)) // ': size of face_nodes(' // &
                   str(face) // ')')
        if (allocated(error)) return
        call check(error, element%nface_gauss(face), nfg, trim(names(k)) // ': nface_gauss(' // str(face) // ')')
        if (allocated(error)) return
      end do
      deallocate (element)
    end do
  end subroutine test_factory

  ! ------------------------------------------------------------------ shape functions

  !> The natural coordinates of the nodes are the brief's (exactly); N_a(xi_b) = delta_ab
  !! (1e-15); at interior points sum N = 1, sum dN/dxi = 0, sum N_a xi_a = xi and
  !! sum dN_a/dxi_i xi_a,j = delta_ij (1e-14).
  subroutine test_kronecker_unity(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: n(:), dn(:, :), nodes(:, :), expected(:, :)
    real(dp) :: pts(3, 5)
    integer :: k, a, b, p, i, j
    do k = 1, n_kinds
      call make_element(k, element)
      allocate (n(nen(k)), dn(3, nen(k)), nodes(3, nen(k)))
      expected = reference_nodes(k)
      call element%natural_coordinates(nodes)
      call check(error, maxval(abs(nodes - expected)), 0.0_dp, trim(names(k)) // ': node natural coordinates', &
                 abs=0.0_dp)
      if (allocated(error)) return
      do b = 1, nen(k)
        call element%shape(expected(:, b), n, dn)
        do a = 1, nen(k)
          call check(error, n(a), merge(1.0_dp, 0.0_dp, a == b), trim(names(k)) // ': N_' // str(a) // &
                     ' at node ' // str(b), abs=1.0e-15_dp)
          if (allocated(error)) return
        end do
      end do
      pts = sample_points(k)
      do p = 1, 5
        call element%shape(pts(:, p), n, dn)
        call check(error, sum(n), 1.0_dp, trim(names(k)) // ': sum of N', abs=1.0e-14_dp)
        if (allocated(error)) return
        do i = 1, 3
          call check(error, sum(dn(i, :)), 0.0_dp, trim(names(k)) // ': sum of dN/dxi', abs=1.0e-14_dp)
          if (allocated(error)) return
          call check(error, sum(n * expected(i, :)), pts(i, p), trim(names(k)) // ': sum of N xi_a', abs=1.0e-14_dp)
          if (allocated(error)) return
          do j = 1, 3
            call check(error, sum(dn(i, :) * expected(j, :)), merge(1.0_dp, 0.0_dp, i == j), trim(names(k)) // &
                       ': sum of dN/dxi_' // str(i) // ' xi_a,' // str(j), abs=1.0e-14_dp)
            if (allocated(error)) return
          end do
        end do
      end do
      deallocate (element, n, dn, nodes)
    end do
  end subroutine test_kronecker_unity

  !> dN/dxi against central differences (h = 1e-5: the quadratic and serendipity functions leave
  !! rounding of ~1e-11 and the hex20's cubic terms ~1e-10; tolerance 1e-9).
  subroutine test_derivatives_fd(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: n(:), dn(:, :), np(:), nm(:), dummy(:, :)
    real(dp), parameter :: h = 1.0e-5_dp
    real(dp) :: pts(3, 5), step(3)
    integer :: k, p, i
    do k = 1, n_kinds
      call make_element(k, element)
      allocate (n(nen(k)), dn(3, nen(k)), np(nen(k)), nm(nen(k)), dummy(3, nen(k)))
      pts = sample_points(k)
      do p = 1, 5
        call element%shape(pts(:, p), n, dn)
        do i = 1, 3
          step = 0.0_dp
          step(i) = h
          call element%shape(pts(:, p) + step, np, dummy)
          call element%shape(pts(:, p) - step, nm, dummy)
          call check(error, maxval(abs((np - nm) / (2.0_dp * h) - dn(i, :))), 0.0_dp, trim(names(k)) // &
                     ': dN/dxi_' // str(i) // ' vs finite differences at point ' // str(p), abs=1.0e-9_dp)
          if (allocated(error)) return
        end do
      end do
      deallocate (element, n, dn, np, nm, dummy)
    end do
  end subroutine test_derivatives_fd

  ! ------------------------------------------------------------------ volume

  !> Volume of the reference element (1/6, 1, 8: the node coordinates are the natural ones,
  !! detJ = 1) and of its affine image (det A times that), relative 1e-14; on the affine element
  !! detJ = det A at every Gauss point and node (jacobian_range, relative 1e-14), and with the
  !! C3D4/C3D6 orientation (x2 - x1) x (x3 - x1) . (x4 - x1) > 0 the Jacobian is positive.
  subroutine test_volume(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :)
    real(dp) :: deta, jmin, jmax, v
    integer :: k
    deta = dot_product(amap(:, 1), cross(amap(:, 2), amap(:, 3)))
    do k = 1, n_kinds
      call make_element(k, element)
      xe = reference_nodes(k)
      call check(error, element%volume(xe), reference_volume(shape_of(k)), trim(names(k)) // ': reference volume', &
                 rel=1.0e-14_dp)
      if (allocated(error)) return
      xe = affine_element(k)
      call check(error, element%volume(xe), deta * reference_volume(shape_of(k)), trim(names(k)) // &
                 ': affine volume = det A times the reference volume', rel=1.0e-14_dp)
      if (allocated(error)) return
      call element%jacobian_range(xe, jmin, jmax)
      call check(error, jmin, deta, trim(names(k)) // ': affine min detJ', rel=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, jmax, deta, trim(names(k)) // ': affine max detJ', rel=1.0e-14_dp)
      if (allocated(error)) return
      if (shape_of(k) /= hex) then
        v = dot_product(cross(xe(:, 2) - xe(:, 1), xe(:, 3) - xe(:, 1)), xe(:, 4) - xe(:, 1))
        call check(error, v > 0.0_dp .and. jmin > 0.0_dp, trim(names(k)) // ': C3D4/C3D6 orientation, positive detJ')
        if (allocated(error)) return
      end if
      deallocate (element)
    end do
  end subroutine test_volume

  ! ------------------------------------------------------------------ faces

  !> Every face: the face shape functions are 1 at their own face node and 0 at the others
  !! (1e-15), sum to 1 and have finite-difference derivatives (h = 1e-5, 1e-9) at sample points;
  !! and they are the traces of the element's: at the natural point xi(s) = sum_b N_b(s) xi_fn(b)
  !! of face point s, the element's N_a equals the face's N_b for a = fn(b) and is 0 for the nodes
  !! off the face (1e-14), so the face lists name the nodes of that face in the face's order.
  subroutine test_face_shapes(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: nf(:), dnf(:, :), np(:), nm(:), dummy(:, :), snodes(:, :), nodes(:, :)
    real(dp), allocatable :: n(:), dn(:, :), trace(:)
    real(dp), parameter :: h = 1.0e-5_dp
    real(dp) :: spts(2, 2), step(2), xi(3)
    integer, allocatable :: fn(:)
    integer :: k, face, nfn, a, b, p, i
    do k = 1, n_kinds
      call make_element(k, element)
      nodes = reference_nodes(k)
      allocate (n(nen(k)), dn(3, nen(k)), trace(nen(k)))
      do face = 1, element%nfaces()
        fn = element%face_nodes(face)
        nfn = size(fn)
        snodes = face_node_s(nfn)
        allocate (nf(nfn), dnf(2, nfn), np(nfn), nm(nfn), dummy(2, nfn))
        do b = 1, nfn
          call element%face_shape(face, snodes(:, b), nf, dnf)
          do a = 1, nfn
            call check(error, nf(a), merge(1.0_dp, 0.0_dp, a == b), trim(names(k)) // ': face ' // str(face) // &
                       ' N_' // str(a) // ' at face node ' // str(b), abs=1.0e-15_dp)
            if (allocated(error)) return
          end do
        end do
        if (nfn == 3 .or. nfn == 6) then
          spts = reshape([0.2_dp, 0.3_dp, 0.6_dp, 0.15_dp], [2, 2])
        else
          spts = reshape([0.37_dp, -0.61_dp, -0.8_dp, 0.25_dp], [2, 2])
        end if
        do p = 1, 2
          call element%face_shape(face, spts(:, p), nf, dnf)
          call check(error, sum(nf), 1.0_dp, trim(names(k)) // ': face ' // str(face) // ' sum of N', abs=1.0e-14_dp)
          if (allocated(error)) return
          do i = 1, 2
            step = 0.0_dp
            step(i) = h
            call element%face_shape(face, spts(:, p) + step, np, dummy)
            call element%face_shape(face, spts(:, p) - step, nm, dummy)
            call check(error, maxval(abs((np - nm) / (2.0_dp * h) - dnf(i, :))), 0.0_dp, trim(names(k)) // &
                       ': face ' // str(face) // ' dN/ds_' // str(i) // ' vs finite differences', abs=1.0e-9_dp)
            if (allocated(error)) return
          end do
          xi = matmul(nodes(:, fn), nf)
          call element%shape(xi, n, dn)
          trace = 0.0_dp
          trace(fn) = nf
          call check(error, maxval(abs(n - trace)), 0.0_dp, trim(names(k)) // ': face ' // str(face) // &
                     ' shape functions are the traces of the element''s', abs=1.0e-14_dp)
          if (allocated(error)) return
        end do
        deallocate (nf, dnf, np, nm, dummy)
      end do
      deallocate (element, n, dn, trace)
    end do
  end subroutine test_face_shapes

  !> The face lists against Abaqus's (S1, S2, ...): each face's corners are the Abaqus corners in
  !! the opposite cyclic sense (the Abaqus listing has the right-hand normal inwards; hex8's faces,
  !! older than this test, are so too), and on the reference element every Gauss-point normal is
  !! the face's outward unit normal by hand: tetrahedron -z, -y, (1,1,1)/sqrt 3, -x; wedge -z, +z,
  !! -y, (1,1,0)/sqrt 2, -x; cube -z, +z, -y, +x, +y, -x (1e-15).
  subroutine test_face_lists(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), xg(:, :), normal(:, :), wda(:), nf(:, :), outward(:, :)
    integer, allocatable :: fn(:), abq(:), reversed(:)
    integer :: k, face, nc, r, g
    logical :: rotation
    real(dp), parameter :: r3 = 1.0_dp / sqrt(3.0_dp), r2 = 1.0_dp / sqrt(2.0_dp)
    do k = 1, n_kinds
      call make_element(k, element)
      select case (shape_of(k))
      case (tet)
        outward = reshape([0.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, r3, r3, r3, -1.0_dp, 0.0_dp, 0.0_dp], [3, 4])
      case (wedge)
        outward = reshape([0.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, &
                           r2, r2, 0.0_dp, -1.0_dp, 0.0_dp, 0.0_dp], [3, 5])
      case default
        outward = reshape([0.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, &
                           1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, -1.0_dp, 0.0_dp, 0.0_dp], [3, 6])
      end select
      xe = reference_nodes(k)
      do face = 1, element%nfaces()
        select case (shape_of(k))
        case (tet)
          abq = abaqus_tet_faces(:, face)
        case (wedge)
          abq = abaqus_wedge_faces(:, face)
        case default
          abq = abaqus_hex_faces(:, face)
        end select
        nc = count(abq > 0)
        abq = abq(1:nc)
        fn = element%face_nodes(face)
        ! the Abaqus cycle read backwards from its first node
        reversed = [abq(1), abq(nc:2:-1)]
        rotation = .false.
        do r = 0, nc - 1
          rotation = rotation .or. all(fn(1:nc) == cshift(reversed, r))
        end do
        call check(error, rotation, trim(names(k)) // ': face ' // str(face) // ' corners are Abaqus S' // &
                   str(face) // ' in the opposite sense')
        if (allocated(error)) return
        allocate (xg(3, element%nface_gauss(face)), normal(3, element%nface_gauss(face)), &
                  wda(element%nface_gauss(face)), nf(size(fn), element%nface_gauss(face)))
        call element%face_integration(xe, face, xg, normal, wda, nf)
        do g = 1, size(wda)
          call check(error, norm2(normal(:, g) - outward(:, face)), 0.0_dp, trim(names(k)) // ': reference face ' // &
                     str(face) // ' outward normal at point ' // str(g), abs=1.0e-15_dp)
          if (allocated(error)) return
        end do
        deallocate (xg, normal, wda, nf)
      end do
      deallocate (element)
    end do
  end subroutine test_face_lists

  !> On the affine element (flat faces, straight edges): per face, sum of wda = the face's area
  !! (a triangle's |(p2 - p1) x (p3 - p1)| / 2, a parallelogram's |(p2 - p1) x (p4 - p1)|,
  !! relative 1e-14); every normal is the plane's unit normal and points away from the element
  !! centroid (1e-14); and the consistent nodal weights int N_a dA, whose product with a uniform
  !! traction t are the nodal forces (summing to t times the area), have their closed forms:
  !! 3-node triangle A/3 each; 6-node triangle 0 at the corners and A/3 at the mid-edges; 4-node
  !! parallelogram A/4; 8-node parallelogram -A/12 at the corners and A/3 at the mid-edges
  !! (1e-14 of A).
  subroutine test_faces_affine(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), xg(:, :), normal(:, :), wda(:), nf(:, :), weights(:), expected(:)
    integer, allocatable :: fn(:)
    real(dp) :: p(3, 4), c(3), area, plane(3), out(3), t(3), force(3)
    integer :: k, face, g, nfn, a
    t = [1.5_dp, -2.0_dp, 0.7_dp]
    do k = 1, n_kinds
      call make_element(k, element)
      xe = affine_element(k)
      do face = 1, element%nfaces()
        fn = element%face_nodes(face)
        nfn = size(fn)
        allocate (xg(3, element%nface_gauss(face)), normal(3, element%nface_gauss(face)), &
                  wda(element%nface_gauss(face)), nf(nfn, element%nface_gauss(face)))
        call element%face_integration(xe, face, xg, normal, wda, nf)
        if (nfn == 3 .or. nfn == 6) then
          p(:, 1:3) = xe(:, fn(1:3))
          c = cross(p(:, 2) - p(:, 1), p(:, 3) - p(:, 1))
          area = 0.5_dp * norm2(c)
          out = sum(p(:, 1:3), dim=2) / 3.0_dp - sum(xe, dim=2) / size(xe, 2)
        else
          p = xe(:, fn(1:4))
          c = cross(p(:, 2) - p(:, 1), p(:, 4) - p(:, 1))
          area = norm2(c)
          out = sum(p, dim=2) / 4.0_dp - sum(xe, dim=2) / size(xe, 2)
        end if
        plane = c / norm2(c)
        call check(error, sum(wda), area, trim(names(k)) // ': affine face ' // str(face) // ' area', rel=1.0e-14_dp)
        if (allocated(error)) return
        do g = 1, size(wda)
          call check(error, dot_product(normal(:, g), out) > 0.0_dp, trim(names(k)) // ': affine face ' // &
                     str(face) // ' normal points away from the centroid')
          if (allocated(error)) return
          call check(error, norm2(normal(:, g) - sign(1.0_dp, dot_product(plane, out)) * plane), 0.0_dp, &
                     trim(names(k)) // ': affine face ' // str(face) // ' normal is the plane''s', abs=1.0e-14_dp)
          if (allocated(error)) return
        end do
        weights = matmul(nf, wda)
        select case (nfn)
        case (3)
          expected = [1.0_dp, 1.0_dp, 1.0_dp] * area / 3.0_dp
        case (6)
          expected = [0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp] * area / 3.0_dp
        case (4)
          expected = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp] * area / 4.0_dp
        case default
          expected = [-0.25_dp, -0.25_dp, -0.25_dp, -0.25_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp] * area / 3.0_dp
        end select
        call check(error, maxval(abs(weights - expected)), 0.0_dp, trim(names(k)) // ': affine face ' // str(face) // &
                   ' consistent nodal weights of a uniform traction', abs=1.0e-14_dp * area)
        if (allocated(error)) return
        force = 0.0_dp
        do a = 1, nfn
          force = force + weights(a) * t
        end do
        call check(error, norm2(force - t * area), 0.0_dp, trim(names(k)) // ': affine face ' // str(face) // &
                   ' nodal forces sum to traction times area', abs=1.0e-14_dp * area * norm2(t))
        if (allocated(error)) return
        deallocate (xg, normal, wda, nf)
      end do
      deallocate (element)
    end do
  end subroutine test_faces_affine

  !> On the distorted element (curved or warped faces): the closed surface integral of n dA is
  !! zero (1e-14 of the total area) and that of x.n dA is 3 V (divergence theorem, relative 1e-13;
  !! both exact for the face rules), with V from this file's independent quadrature (exact for
  !! detJ of these elements); every Gauss-point normal is a unit vector pointing away from the
  !! element centroid, xg = sum N x (1e-14), and the element has a positive Jacobian.
  subroutine test_closed_surface(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), xg(:, :), normal(:, :), wda(:), nf(:, :), xi(:, :), w(:)
    real(dp), allocatable :: n(:), dndx(:, :)
    integer, allocatable :: fn(:)
    real(dp) :: flux_n(3), flux_x, total_area, out(3), vol, detj, jmin, jmax
    integer :: k, face, g
    do k = 1, n_kinds
      call make_element(k, element)
      xe = distorted_element(k)
      call element%jacobian_range(xe, jmin, jmax)
      call check(error, jmin > 0.0_dp, trim(names(k)) // ': distorted element has a positive Jacobian')
      if (allocated(error)) return
      call independent_rule(k, xi, w)
      allocate (n(nen(k)), dndx(3, nen(k)))
      vol = 0.0_dp
      do g = 1, size(w)
        call element%shape_gradients(xe, xi(:, g), n, dndx, detj)
        vol = vol + detj * w(g)
      end do
      flux_n = 0.0_dp
      flux_x = 0.0_dp
      total_area = 0.0_dp
      do face = 1, element%nfaces()
        fn = element%face_nodes(face)
        allocate (xg(3, element%nface_gauss(face)), normal(3, element%nface_gauss(face)), &
                  wda(element%nface_gauss(face)), nf(size(fn), element%nface_gauss(face)))
        call element%face_integration(xe, face, xg, normal, wda, nf)
        out = sum(xe(:, fn), dim=2) / size(fn) - sum(xe, dim=2) / size(xe, 2)
        do g = 1, size(wda)
          call check(error, dot_product(normal(:, g), out) > 0.0_dp, trim(names(k)) // ': distorted face ' // &
                     str(face) // ' normal points out at point ' // str(g))
          if (allocated(error)) return
          call check(error, norm2(normal(:, g)), 1.0_dp, trim(names(k)) // ': unit normal', abs=1.0e-14_dp)
          if (allocated(error)) return
          call check(error, norm2(matmul(xe(:, fn), nf(:, g)) - xg(:, g)), 0.0_dp, trim(names(k)) // &
                     ': xg = sum N x', abs=1.0e-14_dp)
          if (allocated(error)) return
        end do
        flux_n = flux_n + matmul(normal, wda)
        flux_x = flux_x + sum(wda * sum(xg * normal, dim=1))
        total_area = total_area + sum(wda)
        deallocate (xg, normal, wda, nf)
      end do
      call check(error, norm2(flux_n), 0.0_dp, trim(names(k)) // ': closed surface integral of n dA', &
                 abs=1.0e-14_dp * total_area)
      if (allocated(error)) return
      call check(error, flux_x, 3.0_dp * vol, trim(names(k)) // ': closed surface integral of x.n dA = 3 V', &
                 rel=1.0e-13_dp)
      if (allocated(error)) return
      deallocate (element, n, dndx)
    end do
  end subroutine test_closed_surface

  ! ------------------------------------------------------------------ strains and stiffness

  !> Patch test: u = H x + c at the nodes of the distorted element gives the exact constant
  !! strain sym(H) (engineering) at every Gauss point, and B u at an interior point, to 1e-12 of
  !! the largest strain component.
  subroutine test_patch(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), u(:), eps(:, :), b(:, :)
    real(dp) :: expected(6), detj, pts(3, 5)
    integer :: k, g
    expected = voigt_strain(hgrad)
    do k = 1, n_kinds
      call make_element(k, element)
      xe = distorted_element(k)
      u = linear_field(xe, hgrad, [1.0_dp, -2.0_dp, 0.5_dp])
      allocate (eps(6, element%ngauss()), b(6, size(u)))
      call element%strains(xe, u, eps)
      do g = 1, element%ngauss()
        call check(error, maxval(abs(eps(:, g) - expected)), 0.0_dp, trim(names(k)) // ': strain at Gauss point ' // &
                   str(g), abs=1.0e-12_dp * maxval(abs(expected)))
        if (allocated(error)) return
      end do
      pts = sample_points(k)
      call element%b_matrix(xe, pts(:, 2), b, detj)
      call check(error, maxval(abs(matmul(b, u) - expected)), 0.0_dp, trim(names(k)) // ': B u at a point', &
                 abs=1.0e-12_dp * maxval(abs(expected)))
      if (allocated(error)) return
      deallocate (element, eps, b)
    end do
  end subroutine test_patch

  !> A single free distorted element (E = 30000, nu = 0.2): K symmetric (1e-13 of ||K||), K
  !! times each of the 6 rigid-body modes zero (1e-10 ||K|| ||u||), and exactly 6 eigenvalues
  !! (LAPACK dsyev) below 1e-10 of the largest, none negative beyond that, the 7th above 1e-4 of
  !! the largest: the rules leave no spurious zero-energy mode.
  subroutine test_zero_energy_modes(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), ke(:, :), lam(:), work(:), u(:)
    real(dp) :: min_detj, kn, h(3, 3), c(3)
    integer :: k, ndof, info, mode
    do k = 1, n_kinds
      call make_element(k, element)
      xe = distorted_element(k)
      ndof = 3 * nen(k)
      allocate (ke(ndof, ndof), lam(ndof), work(64 * ndof))
      call element%stiffness(xe, d_at_points(isotropic_d(30000.0_dp, 0.2_dp), element%ngauss()), ke)
      min_detj = element%min_jacobian(xe)
      call check(error, min_detj > 0.0_dp, trim(names(k)) // ': positive Jacobian')
      if (allocated(error)) return
      kn = norm2(ke)
      call check(error, maxval(abs(ke - transpose(ke))), 0.0_dp, trim(names(k)) // ': K symmetric', abs=1.0e-13_dp * kn)
      if (allocated(error)) return
      do mode = 1, 6
        call rigid_mode(mode, h, c)
        u = linear_field(xe, h, c)
        call check(error, norm2(matmul(ke, u)), 0.0_dp, trim(names(k)) // ': K times rigid mode ' // str(mode), &
                   abs=1.0e-10_dp * kn * norm2(u))
        if (allocated(error)) return
      end do
      call dsyev('N', 'U', ndof, ke, ndof, lam, work, size(work), info)
      call check(error, info, 0, trim(names(k)) // ': dsyev info')
      if (allocated(error)) return
      call check(error, count(abs(lam) <= 1.0e-10_dp * lam(ndof)), 6, trim(names(k)) // ': number of zero eigenvalues')
      if (allocated(error)) return
      call check(error, lam(1) > -1.0e-10_dp * lam(ndof), trim(names(k)) // ': no negative eigenvalue')
      if (allocated(error)) return
      call check(error, lam(7) > 1.0e-4_dp * lam(ndof), trim(names(k)) // ': smallest deformation mode is stiff, ' // &
                 'ratio ' // str(lam(7) / lam(ndof)))
      if (allocated(error)) return
      deallocate (element, ke, lam, work)
    end do
  end subroutine test_zero_energy_modes

  !> The volume rules integrate the stiffness of an undistorted (affine) element exactly: K
  !! equals sum B^T D B detJ w over this file's independent quadrature (exact to degree 7 on the
  !! tetrahedron, 8 on the triangle, 9 per coordinate in zeta and on the cube, above the
  !! integrands' 2 (tet10), 2 x 2 (wedge6), 4 x 4 (wedge15) and 2 or 4 per coordinate (hex8,
  !! hex20)), built from the element's b_matrix, to 1e-13 of max |K|.
  subroutine test_exact_stiffness(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), ke(:, :), kref(:, :), b(:, :), xi(:, :), w(:)
    real(dp) :: d(6, 6), detj
    integer :: k, g, ndof
    d = isotropic_d(30000.0_dp, 0.2_dp)
    do k = 1, n_kinds
      call make_element(k, element)
      xe = affine_element(k)
      ndof = 3 * nen(k)
      allocate (ke(ndof, ndof), kref(ndof, ndof), b(6, ndof))
      call element%stiffness(xe, d_at_points(d, element%ngauss()), ke)
      call independent_rule(k, xi, w)
      kref = 0.0_dp
      do g = 1, size(w)
        call element%b_matrix(xe, xi(:, g), b, detj)
        kref = kref + matmul(transpose(b), matmul(d, b)) * (detj * w(g))
      end do
      call check(error, maxval(abs(ke - kref)), 0.0_dp, trim(names(k)) // ': K of the affine element against ' // &
                 'an independent exact quadrature', abs=1.0e-13_dp * maxval(abs(kref)))
      if (allocated(error)) return
      deallocate (element, ke, kref, b)
    end do
  end subroutine test_exact_stiffness

end module test_solid_elements
