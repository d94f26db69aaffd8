!> Tests of the plane-strain 6-node triangle: shape functions, the 3- and 6-point rules, the
!! constant-strain patch test on a curved element, rigid modes and zero eigenvalues, plane-strain
!! stresses, edge integration, nodal forces of a uniform stress and the Jacobian checks.
module test_tri6
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_elasticity_testing, only: isotropic_d, d_at_points
  use feps_error, only: str
  use feps_lapack, only: dsyev
  use feps_solid_element, only: solid_element_t
  use feps_tri6, only: tri6_t
  use feps_element_catalog, only: new_element => new_solid_element
  implicit none
  private

  public :: collect_tri6

  !> Corners of each edge and its mid-side node (independent copy of the node order in the brief).
  integer, parameter :: edge_nodes(3, 3) = reshape([1, 2, 4,  2, 3, 5,  3, 1, 6], [3, 3])

  !> Element DOFs of the in-plane displacements (x, y of every node).
  integer, parameter :: inplane(12) = [1, 2, 4, 5, 7, 8, 10, 11, 13, 14, 16, 17]

contains

  subroutine collect_tri6(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("factory_and_counts", test_factory), &
      new_unittest("kronecker_and_partition_of_unity", test_kronecker_unity), &
      new_unittest("derivatives_finite_difference", test_derivatives_fd), &
      new_unittest("rules_exact_to_degree", test_rules), &
      new_unittest("edge_shape_functions", test_edge_shapes), &
      new_unittest("constant_strain_patch_curved", test_patch), &
      new_unittest("rigid_modes_and_zero_eigenvalues", test_rigid_modes), &
      new_unittest("linear_field_energy", test_energy), &
      new_unittest("plane_strain_stresses", test_plane_strain), &
      new_unittest("edges_straight", test_edges_straight), &
      new_unittest("edges_curved_divergence", test_uniform_stress_forces), &
      new_unittest("jacobian_range_and_area", test_jacobian_area) &
    ]
  end subroutine collect_tri6

  ! ------------------------------------------------------------------ helpers

  !> Corners of the test triangle (counter-clockwise), z = 0.
  pure function corners() result(p)
    real(dp) :: p(3, 3)
    p = reshape([0.5_dp, -0.2_dp, 0.0_dp,  2.5_dp, 0.4_dp, 0.0_dp,  1.0_dp, 1.9_dp, 0.0_dp], [3, 3])
  end function corners

  !> Straight-sided tri6 on `p` (mid-side nodes at the edge midpoints).
  pure function straight_tri6(p) result(xe)
    real(dp), intent(in) :: p(3, 3)
    real(dp) :: xe(3, 6)
    integer :: k
    xe(:, 1:3) = p
    do k = 1, 3
      xe(:, 3 + k) = 0.5_dp * (p(:, edge_nodes(1, k)) + p(:, edge_nodes(2, k)))
    end do
  end function straight_tri6

  !> The test triangle with every mid-side node moved off its midpoint by ~0.15 (curved sides).
  pure function curved_tri6() result(xe)
    real(dp) :: xe(3, 6)
    integer :: k
    xe = straight_tri6(corners())
    do k = 4, 6
      xe(1:2, k) = xe(1:2, k) + 0.15_dp * [cos(1.9_dp * k + 0.3_dp), sin(1.9_dp * k + 0.3_dp)]
    end do
  end function curved_tri6

  pure real(dp) function triangle_area(p)
    real(dp), intent(in) :: p(3, 3)
    triangle_area = 0.5_dp * ((p(1, 2) - p(1, 1)) * (p(2, 3) - p(2, 1)) - (p(1, 3) - p(1, 1)) * (p(2, 2) - p(2, 1)))
  end function triangle_area

  !> Nodal vector (3 DOFs per node, uz = 0) of the in-plane field u = h x + c.
  pure function inplane_field(xe, h, c) result(u)
    real(dp), intent(in) :: xe(:, :), h(2, 2), c(2)
    real(dp) :: u(3 * size(xe, 2))
    integer :: a
    do a = 1, size(xe, 2)
      u(3 * a - 2:3 * a) = [matmul(h, xe(1:2, a)) + c, 0.0_dp]
    end do
  end function inplane_field

  !> Engineering Voigt strain of an in-plane gradient h (plane strain).
  pure function plane_voigt(h) result(eps)
    real(dp), intent(in) :: h(2, 2)
    real(dp) :: eps(6)
    eps = [h(1, 1), h(2, 2), 0.0_dp, 0.0_dp, 0.0_dp, h(1, 2) + h(2, 1)]
  end function plane_voigt

  !> Points inside the reference triangle (s1, s2, 0), including a corner and an edge point.
  pure function sample_points() result(xi)
    real(dp) :: xi(3, 5)
    xi = reshape([0.2_dp, 0.3_dp, 0.0_dp,  0.05_dp, 0.8_dp, 0.0_dp,  0.6_dp, 0.15_dp, 0.0_dp, &
                  0.0_dp, 0.0_dp, 0.0_dp,  0.4_dp, 0.6_dp, 0.0_dp], [3, 5])
  end function sample_points

  pure integer function factorial(n)
    integer, intent(in) :: n
    integer :: k
    factorial = 1
    do k = 2, n
      factorial = factorial * k
    end do
  end function factorial

  ! ------------------------------------------------------------------ tests

  !> The factory makes both variants (case-insensitive); counts and names.
  subroutine test_factory(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    character(len=*), parameter :: names(2) = ['TRI6  ', 'tri6-6']
    character(len=*), parameter :: types(2) = ['tri6  ', 'tri6-6']
    integer, parameter :: ng(2) = [3, 6]
    integer :: k
    do k = 1, 2
      call new_element(' ' // trim(names(k)), element, error)
      if (allocated(error)) return
      call check(error, element%element_type() == trim(types(k)), 'element_type of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, element%ngauss(), ng(k), trim(names(k)) // ' ngauss')
      if (allocated(error)) return
      call check(error, element%nnodes() * 100 + element%nfaces() * 10 + element%nface_nodes(2), 633, &
                 trim(names(k)) // ' nnodes, nfaces, nface_nodes')
      if (allocated(error)) return
      call check(error, element%nface_gauss(2), 3, trim(names(k)) // ' nface_gauss')
      if (allocated(error)) return
      call check(error, all(element%face_nodes(2) == [2, 3, 5]), trim(names(k)) // ' face_nodes(2)')
      if (allocated(error)) return
    end do
  end subroutine test_factory

  !> N_a(node b) = delta_ab (nodes at the stated natural coordinates); sum N = 1 and sum dN = 0
  !! at interior points.
  subroutine test_kronecker_unity(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: nodes(2, 6) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
                                                  0.5_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp, 0.5_dp], [2, 6])
    real(dp) :: n(6), dn(3, 6), xin(3, 6), pts(3, 5)
    integer :: a, b, k
    call tri%natural_coordinates(xin)
    do b = 1, 6
      call check(error, maxval(abs(xin(:, b) - [nodes(:, b), 0.0_dp])), 0.0_dp, 'natural coordinates of node ' // &
                 str(b), abs=0.0_dp)
      if (allocated(error)) return
      call tri%shape([nodes(:, b), 0.37_dp], n, dn)
      do a = 1, 6
        call check(error, n(a), merge(1.0_dp, 0.0_dp, a == b), 'N' // str(a) // ' at node ' // str(b), abs=1.0e-15_dp)
        if (allocated(error)) return
      end do
    end do
    pts = sample_points()
    do k = 1, size(pts, 2)
      call tri%shape(pts(:, k), n, dn)
      call check(error, sum(n), 1.0_dp, 'sum N at point ' // str(k), abs=1.0e-15_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(sum(dn, dim=2))), 0.0_dp, 'sum dN at point ' // str(k), abs=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(dn(3, :))), 0.0_dp, 'dN/dxi3 = 0 at point ' // str(k), abs=0.0_dp)
      if (allocated(error)) return
    end do
  end subroutine test_kronecker_unity

  !> dN/ds against central differences (h = 1e-6; quadratic N makes them exact up to rounding).
  subroutine test_derivatives_fd(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: h = 1.0e-6_dp
    real(dp) :: n(6), dn(3, 6), np(6), nm(6), dummy(3, 6), pts(3, 5), step(3)
    integer :: k, i
    pts = sample_points()
    do k = 1, size(pts, 2)
      call tri%shape(pts(:, k), n, dn)
      do i = 1, 2
        step = 0.0_dp
        step(i) = h
        call tri%shape(pts(:, k) + step, np, dummy)
        call tri%shape(pts(:, k) - step, nm, dummy)
        call check(error, maxval(abs((np - nm) / (2.0_dp * h) - dn(i, :))), 0.0_dp, &
                   'dN/ds' // str(i) // ' at point ' // str(k), abs=1.0e-8_dp)
        if (allocated(error)) return
      end do
    end do
  end subroutine test_derivatives_fd

  !> Both rules integrate s1^i s2^j exactly (= i! j! / (i + j + 2)!) up to their degree (2 and 4)
  !! and not s1^(degree+1); points inside with xi(3) = 0; symmetric rules put the mean Gauss
  !! point (weighted) at the centroid of a triangle.
  subroutine test_rules(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), allocatable :: xi(:, :), w(:), xg(:, :)
    real(dp) :: q, exact, xe(3, 6)
    integer :: variant, degree, i, j
    xe = straight_tri6(corners())
    do variant = 1, 2
      tri%six_point = variant == 2
      degree = merge(4, 2, tri%six_point)
      allocate (xi(3, tri%ngauss()), w(tri%ngauss()), xg(3, tri%ngauss()))
      call tri%gauss_rule(xi, w)
      call check(error, all(xi(3, :) == 0.0_dp) .and. all(xi(1, :) > 0.0_dp) .and. all(xi(2, :) > 0.0_dp) .and. &
                 all(xi(1, :) + xi(2, :) < 1.0_dp) .and. all(w > 0.0_dp), tri%element_type() // ': points inside')
      if (allocated(error)) return
      do i = 0, degree
        do j = 0, degree - i
          q = sum(w * xi(1, :)**i * xi(2, :)**j)
          exact = real(factorial(i) * factorial(j), dp) / real(factorial(i + j + 2), dp)
          call check(error, q, exact, tri%element_type() // ': integral of s1^' // str(i) // ' s2^' // str(j), &
                     rel=1.0e-14_dp)
          if (allocated(error)) return
        end do
      end do
      q = sum(w * xi(1, :)**(degree + 1))
      exact = real(factorial(degree + 1), dp) / real(factorial(degree + 3), dp)
      call check(error, abs(q - exact) > 1.0e-6_dp * exact, tri%element_type() // ': not exact beyond its degree')
      if (allocated(error)) return
      call tri%point_coordinates(xe, xg)
      call check(error, maxval(abs(matmul(xg, w) / sum(w) - sum(corners(), dim=2) / 3.0_dp)), 0.0_dp, &
                 tri%element_type() // ': weighted mean Gauss point is the centroid', abs=1.0e-14_dp)
      if (allocated(error)) return
      deallocate (xi, w, xg)
    end do
  end subroutine test_rules

  !> Edge shape functions: Kronecker at s = -1, 1, 0, partition of unity, derivatives by
  !! differences; the 3-point edge rule integrates s^5 exactly.
  subroutine test_edge_shapes(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: s_nodes(3) = [-1.0_dp, 1.0_dp, 0.0_dp], h = 1.0e-6_dp
    real(dp) :: n(3), dn(2, 3), np(3), nm(3), dummy(2, 3), s(2, 3), w(3)
    integer :: a, b
    do b = 1, 3
      call tri%face_shape(1, [s_nodes(b), 0.7_dp], n, dn)
      do a = 1, 3
        call check(error, n(a), merge(1.0_dp, 0.0_dp, a == b), 'edge N' // str(a) // ' at node ' // str(b), &
                   abs=1.0e-15_dp)
        if (allocated(error)) return
      end do
    end do
    call tri%face_shape(1, [0.3_dp, 0.0_dp], n, dn)
    call check(error, sum(n), 1.0_dp, 'edge sum N', abs=1.0e-15_dp)
    if (allocated(error)) return
    call tri%face_shape(1, [0.3_dp + h, 0.0_dp], np, dummy)
    call tri%face_shape(1, [0.3_dp - h, 0.0_dp], nm, dummy)
    call check(error, maxval(abs((np - nm) / (2.0_dp * h) - dn(1, :))), 0.0_dp, 'edge dN/ds', abs=1.0e-8_dp)
    if (allocated(error)) return
    call check(error, maxval(abs(dn(2, :))), 0.0_dp, 'edge dN/ds2 = 0', abs=0.0_dp)
    if (allocated(error)) return
    call tri%face_gauss_rule(1, s, w)
    call check(error, sum(w * (s(1, :) + 1.0_dp)**5), 64.0_dp / 6.0_dp, 'edge rule: integral of (s + 1)^5', &
               rel=1.0e-14_dp)
    if (allocated(error)) return
  end subroutine test_edge_shapes

  !> u = A x + c (in plane) on a curved tri6: constant eps = [a11, a22, 0, 0, 0, a12 + a21] from
  !! gauss_strains (both rules) and from b_matrix at arbitrary points; uz values do not enter.
  subroutine test_patch(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: h(2, 2) = reshape([1.0e-3_dp, -4.0e-4_dp, 7.0e-4_dp, -2.5e-3_dp], [2, 2])
    real(dp), allocatable :: eps(:, :)
    real(dp) :: xe(3, 6), u(18), b(6, 18), detj, pts(3, 5), expected(6)
    integer :: variant, g, k
    xe = curved_tri6()
    u = inplane_field(xe, h, [0.3_dp, -0.2_dp])
    u(3:18:3) = [0.1_dp, -0.4_dp, 0.7_dp, 0.2_dp, 0.9_dp, -0.3_dp]   ! z DOFs: must have no effect
    expected = plane_voigt(h)
    do variant = 1, 2
      tri%six_point = variant == 2
      allocate (eps(6, tri%ngauss()))
      call tri%strains(xe, u, eps)
      do g = 1, tri%ngauss()
        call check(error, maxval(abs(eps(:, g) - expected)), 0.0_dp, tri%element_type() // ': strain at point ' // &
                   str(g), abs=1.0e-10_dp * maxval(abs(h)))
        if (allocated(error)) return
      end do
      deallocate (eps)
    end do
    pts = sample_points()
    do k = 1, size(pts, 2)
      call tri%b_matrix(xe, pts(:, k), b, detj)
      call check(error, maxval(abs(matmul(b, u) - expected)), 0.0_dp, 'B u at sample point ' // str(k), &
                 abs=1.0e-10_dp * maxval(abs(h)))
      if (allocated(error)) return
      call check(error, maxval(abs(b(3:5, :))) + maxval(abs(b(:, 3:18:3))), 0.0_dp, &
                 'B rows zz, yz, xz and z columns are zero', abs=0.0_dp)
      if (allocated(error)) return
    end do
  end subroutine test_patch

  !> ke symmetric with zero z rows/columns; ke u = 0 for the two translations and the in-plane
  !! rotation; the 12 x 12 in-plane stiffness has exactly 3 zero eigenvalues (no spurious modes
  !! for either rule) and no negative ones.
  subroutine test_rigid_modes(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: e = 30000.0_dp
    real(dp) :: xe(3, 6), ke(18, 18), kp(12, 12), lam(12), work(12 * 64), modes(18, 3), min_detj, scale
    integer :: variant, m, info, nzero
    character(len=:), allocatable :: label
    xe = curved_tri6()
    modes(:, 1) = inplane_field(xe, reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), [1.0_dp, 0.0_dp])
    modes(:, 2) = inplane_field(xe, reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), [0.0_dp, 1.0_dp])
    modes(:, 3) = inplane_field(xe, reshape([0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp], [2, 2]), [0.0_dp, 0.0_dp])
    do variant = 1, 2
      tri%six_point = variant == 2
      label = tri%element_type()
      call tri%stiffness(xe, d_at_points(isotropic_d(e, 0.3_dp), tri%ngauss()), ke)
      min_detj = tri%min_jacobian(xe)
      call check(error, min_detj > 0.0_dp, label // ': positive detJ')
      if (allocated(error)) return
      scale = maxval(abs(ke))
      call check(error, maxval(abs(ke - transpose(ke))), 0.0_dp, label // ': symmetry', abs=1.0e-13_dp * scale)
      if (allocated(error)) return
      call check(error, maxval(abs(ke(3:18:3, :))) + maxval(abs(ke(:, 3:18:3))), 0.0_dp, &
                 label // ': z rows and columns zero', abs=0.0_dp)
      if (allocated(error)) return
      do m = 1, 3
        call check(error, maxval(abs(matmul(ke, modes(:, m)))), 0.0_dp, label // ': ke u = 0 for rigid mode ' // &
                   str(m), abs=1.0e-12_dp * scale)
        if (allocated(error)) return
      end do
      kp = ke(inplane, inplane)
      call dsyev('N', 'U', 12, kp, 12, lam, work, size(work), info)
      call check(error, info, 0, label // ': dsyev info')
      if (allocated(error)) return
      nzero = count(abs(lam) <= 1.0e-10_dp * lam(12))
      call check(error, nzero, 3, label // ': number of zero eigenvalues')
      if (allocated(error)) return
      call check(error, lam(1) > -1.0e-10_dp * lam(12), label // ': no negative eigenvalue')
      if (allocated(error)) return
      call check(error, lam(4) > 1.0e-3_dp * lam(12), label // ': smallest deformation mode is stiff, ratio ' // &
                 str(lam(4) / lam(12)))
      if (allocated(error)) return
    end do
  end subroutine test_rigid_modes

  !> Straight-sided element, linear field: u^T ke u = eps^T D eps * area (unit thickness) and
  !! ke u = B^T sigma integrated (internal force from b_matrix); both rules.
  subroutine test_energy(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: h(2, 2) = reshape([2.0e-3_dp, 5.0e-4_dp, -1.0e-3_dp, -1.5e-3_dp], [2, 2])
    real(dp), allocatable :: xi(:, :), w(:)
    real(dp) :: xe(3, 6), ke(18, 18), u(18), d(6, 6), eps(6), sig(6), f(18), b(6, 18), detj
    integer :: variant, g
    xe = straight_tri6(corners())
    d = isotropic_d(200.0_dp, 0.25_dp)
    u = inplane_field(xe, h, [0.01_dp, 0.02_dp])
    eps = plane_voigt(h)
    sig = matmul(d, eps)
    do variant = 1, 2
      tri%six_point = variant == 2
      call tri%stiffness(xe, d_at_points(d, tri%ngauss()), ke)
      call check(error, dot_product(u, matmul(ke, u)), dot_product(eps, sig) * triangle_area(corners()), &
                 tri%element_type() // ': strain energy', rel=1.0e-12_dp)
      if (allocated(error)) return
      allocate (xi(3, tri%ngauss()), w(tri%ngauss()))
      call tri%gauss_rule(xi, w)
      f = 0.0_dp
      do g = 1, size(w)
        call tri%b_matrix(xe, xi(:, g), b, detj)
        f = f + matmul(sig, b) * w(g) * detj
      end do
      call check(error, maxval(abs(matmul(ke, u) - f)), 0.0_dp, tri%element_type() // ': ke u = int B^T sigma', &
                 abs=1.0e-12_dp * maxval(abs(f)))
      if (allocated(error)) return
      deallocate (xi, w)
    end do
  end subroutine test_energy

  !> Plane strain with the 3D D: eps_xx only gives sigma_xx = E (1 - nu) / ((1 + nu)(1 - 2 nu)) eps,
  !! sigma_yy = sigma_zz = nu / (1 - nu) sigma_xx; a general in-plane field gives
  !! sigma = lambda tr(eps) I + 2 mu eps with eps_zz = 0 (so sigma_zz = nu (sigma_xx + sigma_yy)).
  subroutine test_plane_strain(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: e = 1000.0_dp, nu = 0.3_dp, exx = 1.0e-3_dp
    real(dp), parameter :: h(2, 2) = reshape([1.0e-3_dp, 3.0e-4_dp, 8.0e-4_dp, -6.0e-4_dp], [2, 2])
    real(dp) :: xe(3, 6), sig(6, 3), sxx, lambda, mu, tr, expected(6)
    integer :: g
    xe = curved_tri6()
    call tri%gauss_stresses(xe, inplane_field(xe, reshape([exx, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), [0.0_dp, 0.0_dp]), &
                            d_at_points(isotropic_d(e, nu), 3), sig)
    sxx = e * (1.0_dp - nu) / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu)) * exx
    do g = 1, 3
      call check(error, sig(1, g), sxx, 'uniaxial strain: sigma_xx', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, sig(2, g), nu / (1.0_dp - nu) * sxx, 'uniaxial strain: sigma_yy', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, sig(3, g), nu / (1.0_dp - nu) * sxx, 'uniaxial strain: sigma_zz', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(sig(4:6, g))), 0.0_dp, 'uniaxial strain: shears', abs=1.0e-10_dp * sxx)
      if (allocated(error)) return
    end do
    lambda = e * nu / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
    mu = e / (2.0_dp * (1.0_dp + nu))
    tr = h(1, 1) + h(2, 2)
    expected = [lambda * tr + 2.0_dp * mu * h(1, 1), lambda * tr + 2.0_dp * mu * h(2, 2), lambda * tr, 0.0_dp, 0.0_dp, &
                mu * (h(1, 2) + h(2, 1))]
    call tri%gauss_stresses(xe, inplane_field(xe, h, [0.0_dp, 0.0_dp]), d_at_points(isotropic_d(e, nu), 3), sig)
    do g = 1, 3
      call check(error, maxval(abs(sig(:, g) - expected)), 0.0_dp, 'general plane strain at point ' // str(g), &
                 abs=1.0e-10_dp * maxval(abs(expected)))
      if (allocated(error)) return
      call check(error, sig(3, g), nu * (sig(1, g) + sig(2, g)), 'sigma_zz = nu (sxx + syy)', rel=1.0e-10_dp)
      if (allocated(error)) return
    end do
  end subroutine test_plane_strain

  !> Straight edges (one mid-side node off-centre along its edge): sum wda = edge length, outward
  !! unit normal = (dy, -dx) / L, integral of f = 1 + 2x - 3y = L f(midpoint); with centred
  !! mid-side nodes the edge weights of a uniform load are L [1/6, 1/6, 2/3].
  subroutine test_edges_straight(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp) :: p(3, 3), xe(3, 6), xg(3, 3), normal(3, 3), wda(3), nf(3, 3), pa(3), pb(3), len, mid(3)
    integer :: face, g, variant
    p = corners()
    do variant = 1, 2
      xe = straight_tri6(p)
      ! mid-side node 5 at 0.3 of edge 2-3: still straight, non-uniform parametrisation
      if (variant == 2) xe(:, 5) = 0.7_dp * p(:, 2) + 0.3_dp * p(:, 3)
      do face = 1, 3
        pa = p(:, edge_nodes(1, face))
        pb = p(:, edge_nodes(2, face))
        len = norm2(pb - pa)
        mid = 0.5_dp * (pa + pb)
        call tri%face_integration(xe, face, xg, normal, wda, nf)
        call check(error, sum(wda), len, 'edge ' // str(face) // ' length', rel=1.0e-14_dp)
        if (allocated(error)) return
        do g = 1, 3
          call check(error, maxval(abs(normal(:, g) - [pb(2) - pa(2), pa(1) - pb(1), 0.0_dp] / len)), 0.0_dp, &
                     'edge ' // str(face) // ' outward normal', abs=1.0e-14_dp)
          if (allocated(error)) return
        end do
        call check(error, sum(wda * (1.0_dp + 2.0_dp * xg(1, :) - 3.0_dp * xg(2, :))), &
                   len * (1.0_dp + 2.0_dp * mid(1) - 3.0_dp * mid(2)), 'edge ' // str(face) // ' integral of linear f', &
                   rel=1.0e-13_dp)
        if (allocated(error)) return
        if (variant == 1) then
          call check(error, maxval(abs(matmul(nf, wda) - len * [1.0_dp, 1.0_dp, 4.0_dp] / 6.0_dp)), 0.0_dp, &
                     'edge ' // str(face) // ' consistent load weights', abs=1.0e-14_dp)
          if (allocated(error)) return
        end if
      end do
    end do
  end subroutine test_edges_straight

  !> Curved tri6, uniform stress sigma: the internal forces int B^T sigma dA equal the edge
  !! integrals of N_a sigma.n (divergence theorem; both integrands are polynomials the rules
  !! integrate exactly); the normals integrate to zero around the closed boundary; area =
  !! integral of x n_x along the boundary.
  subroutine test_uniform_stress_forces(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: sig(6) = [3.0_dp, -1.5_dp, 0.8_dp, 0.0_dp, 0.0_dp, 1.2_dp]
    real(dp) :: xe(3, 6), xg(3, 3), normal(3, 3), wda(3), nf(3, 3), xi(3, 3), w(3), b(6, 18), detj
    real(dp) :: f_int(18), f_edge(18), t(2), closure(3), area_boundary
    integer :: face, g, a, node
    xe = curved_tri6()
    call tri%gauss_rule(xi, w)
    f_int = 0.0_dp
    do g = 1, 3
      call tri%b_matrix(xe, xi(:, g), b, detj)
      f_int = f_int + matmul(sig, b) * w(g) * detj
    end do
    f_edge = 0.0_dp
    closure = 0.0_dp
    area_boundary = 0.0_dp
    do face = 1, 3
      call tri%face_integration(xe, face, xg, normal, wda, nf)
      do g = 1, 3
        ! in-plane traction sigma.n with Voigt xy = sig(6)
        t = [sig(1) * normal(1, g) + sig(6) * normal(2, g), sig(6) * normal(1, g) + sig(2) * normal(2, g)]
        do a = 1, 3
          node = edge_nodes(a, face)
          f_edge(3 * node - 2:3 * node - 1) = f_edge(3 * node - 2:3 * node - 1) + nf(a, g) * t * wda(g)
        end do
        closure = closure + normal(:, g) * wda(g)
        area_boundary = area_boundary + xg(1, g) * normal(1, g) * wda(g)
      end do
    end do
    call check(error, maxval(abs(f_int - f_edge)), 0.0_dp, 'internal forces = edge integrals of sigma.n', &
               abs=1.0e-13_dp * maxval(abs(f_int)))
    if (allocated(error)) return
    call check(error, maxval(abs(f_int(3:18:3))), 0.0_dp, 'no z forces', abs=0.0_dp)
    if (allocated(error)) return
    call check(error, maxval(abs(closure)), 0.0_dp, 'closed boundary: integral of n = 0', abs=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, area_boundary, tri%volume(xe), 'area by the boundary integral of x n_x', rel=1.0e-13_dp)
    if (allocated(error)) return
  end subroutine test_uniform_stress_forces

  !> Straight CCW triangle: detJ = 2 area everywhere and volume = area (unit thickness); the
  !! clockwise numbering gives detJ = -2 area; mid-side nodes pushed out perpendicular to their
  !! chords by delta add the parabolic segments 2/3 delta L; a mid-side node pulled across the
  !! element makes min detJ negative.
  subroutine test_jacobian_area(error)
    type(error_t), allocatable, intent(out) :: error
    type(tri6_t) :: tri
    real(dp), parameter :: delta(3) = [0.1_dp, -0.05_dp, 0.2_dp]
    real(dp) :: p(3, 3), xe(3, 6), area, jmin, jmax, chord(3), outward(3), bulge
    integer :: variant, k
    p = corners()
    area = triangle_area(p)
    do variant = 1, 2
      tri%six_point = variant == 2
      xe = straight_tri6(p)
      call tri%jacobian_range(xe, jmin, jmax)
      call check(error, jmin, 2.0_dp * area, tri%element_type() // ': min detJ', rel=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, jmax, 2.0_dp * area, tri%element_type() // ': max detJ', rel=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, tri%volume(xe), area, tri%element_type() // ': area', rel=1.0e-14_dp)
      if (allocated(error)) return
      ! clockwise: corners 1 3 2, mid-sides (1-3) (3-2) (2-1)
      call tri%jacobian_range(xe(:, [1, 3, 2, 6, 5, 4]), jmin, jmax)
      call check(error, jmax, -2.0_dp * area, tri%element_type() // ': clockwise max detJ', rel=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, jmin, -2.0_dp * area, tri%element_type() // ': clockwise min detJ', rel=1.0e-14_dp)
      if (allocated(error)) return
      bulge = 0.0_dp
      do k = 1, 3
        chord = p(:, edge_nodes(2, k)) - p(:, edge_nodes(1, k))
        outward = [chord(2), -chord(1), 0.0_dp] / norm2(chord)
        xe(:, 3 + k) = xe(:, 3 + k) + delta(k) * outward
        bulge = bulge + 2.0_dp / 3.0_dp * delta(k) * norm2(chord)
      end do
      call check(error, tri%volume(xe), area + bulge, tri%element_type() // ': area with parabolic sides', &
                 rel=1.0e-14_dp)
      if (allocated(error)) return
      ! mid-side node 4 pulled beyond the opposite corner's height: the element folds over
      xe = straight_tri6(p)
      xe(:, 4) = 0.5_dp * (p(:, 1) + p(:, 2)) + 0.9_dp * (p(:, 3) - 0.5_dp * (p(:, 1) + p(:, 2)))
      call tri%jacobian_range(xe, jmin, jmax)
      call check(error, jmin < 0.0_dp, tri%element_type() // ': folded element has negative min detJ')
      if (allocated(error)) return
    end do
  end subroutine test_jacobian_area

end module test_tri6
