!> Tests of the solid element library: Gauss rules, hex8 and hex20 shape functions, B-matrix,
!! stiffness, Gauss-point results, Jacobian checks and face integration.
module test_elements
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_geometry_testing, only: cross, add_edge_integrals, linear_field, voigt_strain, rigid_mode
  use feps_elasticity_testing, only: isotropic_d, d_at_points
  use feps_error, only: str
  use feps_gauss, only: gauss_legendre, square_rule, cube_rule
  use feps_solid_element, only: solid_element_t
  use feps_hex8, only: hex8_t
  use feps_hex20, only: hex20_t
  use feps_hex8_bbar, only: hex8_bbar_t
  use feps_element_catalog, only: new_element => new_solid_element
  implicit none
  private

  public :: collect_elements

  !> Number of elements `test_element` makes (hex8, hex20, hex20r, hex8b).
  integer, parameter :: n_test_elements = 4

  !> Corner pairs of the hex20 mid-edge nodes 9-20.
  integer, parameter :: hex20_edges(2, 12) = reshape([1, 2, 2, 3, 3, 4, 4, 1, 5, 6, 6, 7, 7, 8, 8, 5, &
                                                      1, 5, 2, 6, 3, 7, 4, 8], [2, 12])

  interface
    !> LAPACK symmetric eigenvalues (local explicit interface).
    subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
      import :: dp
      character, intent(in) :: jobz, uplo
      integer, intent(in) :: n, lda, lwork
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: w(*), work(*)
      integer, intent(out) :: info
    end subroutine dsyev
  end interface

contains

  subroutine collect_elements(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("gauss_rules_exact_degree", test_gauss_rules), &
      new_unittest("tensor_rules", test_tensor_rules), &
      new_unittest("factory", test_factory), &
      new_unittest("partition_of_unity", test_partition_of_unity), &
      new_unittest("kronecker_at_nodes", test_kronecker), &
      new_unittest("derivatives_finite_difference", test_derivatives_fd), &
      new_unittest("face_shape_functions", test_face_shapes), &
      new_unittest("linear_field_constant_strain", test_linear_field), &
      new_unittest("rigid_modes_and_symmetry", test_rigid_modes), &
      new_unittest("unit_cube_hex8_stiffness", test_unit_cube_hex8), &
      new_unittest("zero_energy_modes", test_zero_energy_modes), &
      new_unittest("jacobian_range", test_jacobian_range), &
      new_unittest("faces_planar_hex8", test_faces_planar_hex8), &
      new_unittest("faces_curved_hex20", test_faces_curved_hex20), &
      new_unittest("faces_divergence_theorem", test_divergence_theorem), &
      new_unittest("uniform_stress_patch", test_uniform_stress_patch), &
      new_unittest("bbar_strain_definition", test_bbar_strains), &
      new_unittest("bbar_mean_dilatation_stiffness", test_bbar_mean_dilatation), &
      new_unittest("stiffness_general_material", test_general_material), &
      new_unittest("face_pressure_resultant_and_moment", test_pressure_resultant_moment), &
      new_unittest("hex20r_spurious_modes_in_patches", test_hex20r_patches) &
    ]
  end subroutine collect_elements

  ! ------------------------------------------------------------------ helpers

  !> Natural coordinates of the hex8 corners (independent copy of the node order in the brief).
  pure function corner_xi() result(xi)
    real(dp) :: xi(3, 8)
    xi = reshape([-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, &
                  -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1] * 1.0_dp, [3, 8])
  end function corner_xi

  !> A distorted hex8: a 2 x 1.5 x 1 box with every node moved by up to 0.2 in each direction.
  pure function distorted_hex8() result(xe)
    real(dp) :: xe(3, 8), c(3, 8)
    real(dp), parameter :: box(3) = [2.0_dp, 1.5_dp, 1.0_dp]
    integer :: a, i
    c = corner_xi()
    do a = 1, 8
      do i = 1, 3
        xe(i, a) = 0.5_dp * (c(i, a) + 1.0_dp) * box(i) + 0.2_dp * sin(1.7_dp * a + 2.3_dp * i + 0.5_dp)
      end do
    end do
  end function distorted_hex8

  !> A hex20 on the corners of `distorted_hex8` whose mid-edge nodes are moved off the edge
  !! midpoints by up to 0.1: curved edges and faces.
  pure function curved_hex20() result(xe)
    real(dp) :: xe(3, 20)
    integer :: m, i
    xe(:, 1:8) = distorted_hex8()
    do m = 1, 12
      do i = 1, 3
        xe(i, 8 + m) = 0.5_dp * (xe(i, hex20_edges(1, m)) + xe(i, hex20_edges(2, m))) + &
                       0.1_dp * cos(1.3_dp * m + 0.7_dp * i)
      end do
    end do
  end function curved_hex20

  !> hex20 with straight edges and mid-edge nodes at the midpoints of the given corners.
  pure function straight_hex20(corners) result(xe)
    real(dp), intent(in) :: corners(3, 8)
    real(dp) :: xe(3, 20)
    integer :: m
    xe(:, 1:8) = corners
    do m = 1, 12
      xe(:, 8 + m) = 0.5_dp * (corners(:, hex20_edges(1, m)) + corners(:, hex20_edges(2, m)))
    end do
  end function straight_hex20

  !> The unit cube [0, 1]^3 as hex8 corners.
  pure function unit_cube() result(xe)
    real(dp) :: xe(3, 8)
    xe = 0.5_dp * (corner_xi() + 1.0_dp)
  end function unit_cube

  !> A general affine image of the unit cube: x = A xi + c (a parallelepiped).
  pure function affine_hex8() result(xe)
    real(dp) :: xe(3, 8), a(3, 3), c(3, 8)
    integer :: k
    a = reshape([1.2_dp, 0.1_dp, -0.2_dp, 0.3_dp, 0.9_dp, 0.15_dp, -0.1_dp, 0.25_dp, 1.4_dp], [3, 3])
    c = corner_xi()
    do k = 1, 8
      xe(:, k) = matmul(a, c(:, k)) + [0.5_dp, -1.0_dp, 2.0_dp]
    end do
  end function affine_hex8

  !> The test elements: distorted hex8, curved hex20 (3x3x3), curved hex20 reduced, and the
  !! B-bar hex8 on the distorted hex8.
  subroutine test_element(k, element, xe, label)
    integer, intent(in) :: k
    class(solid_element_t), allocatable, intent(out) :: element
    real(dp), allocatable, intent(out) :: xe(:, :)
    character(len=:), allocatable, intent(out) :: label
    select case (k)
    case (1)
      allocate (hex8_t :: element)
      xe = distorted_hex8()
      label = 'hex8'
    case (2)
      allocate (element, source=hex20_t(reduced=.false.))
      xe = curved_hex20()
      label = 'hex20'
    case (3)
      allocate (element, source=hex20_t(reduced=.true.))
      xe = curved_hex20()
      label = 'hex20r'
    case default
      allocate (hex8_bbar_t :: element)
      xe = distorted_hex8()
      label = 'hex8b'
    end select
  end subroutine test_element

  !> A few fixed points inside the reference cube.
  pure function sample_points() result(xi)
    real(dp) :: xi(3, 5)
    xi = reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.3_dp, -0.7_dp, 0.55_dp, -0.9_dp, 0.2_dp, 0.8_dp, &
                  1.0_dp, -1.0_dp, 0.35_dp, -0.123_dp, 0.456_dp, -0.789_dp], [3, 5])
  end function sample_points

  ! ------------------------------------------------------------------ Gauss rules

  !> n points integrate x^k exactly (2/(k+1) for even k, 0 for odd) up to k = 2n-1, not x^(2n).
  subroutine test_gauss_rules(error)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: refused
    real(dp) :: x(5), w(5), exact
    integer :: n, k
    do n = 1, 5
      call gauss_legendre(n, x, w, error)
      if (allocated(error)) return
      do k = 0, 2 * n
        exact = merge(2.0_dp / (k + 1), 0.0_dp, mod(k, 2) == 0)
        if (k <= 2 * n - 1) then
          call check(error, sum(w(1:n) * x(1:n)**k), exact, 'n = ' // str(n) // ': integral of x^' // str(k), &
                     abs=2.0e-15_dp)
        else
          call check(error, abs(sum(w(1:n) * x(1:n)**k) - exact) > 1.0e-3_dp, 'n = ' // str(n) // &
                     ': x^' // str(k) // ' must not be integrated exactly')
        end if
        if (allocated(error)) return
      end do
    end do
    call gauss_legendre(6, x, w, refused)
    call check(error, allocated(refused), '6-point rule must be refused')
    if (allocated(error)) return
  end subroutine test_gauss_rules

  !> Tensor rules: weights sum to the measure, integral of x^2 y^4 z^2 over the cube (3x3x3:
  !! 2/3 * 2/5 * 2/3 = 8/45), x^2 y^2 over the square (2x2: 4/9).
  subroutine test_tensor_rules(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: xi(3, 27), w(27), s(2, 4), ws(4)
    call cube_rule(3, xi, w, error)
    if (allocated(error)) return
    call check(error, sum(w), 8.0_dp, 'cube weights', abs=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, sum(w * xi(1, :)**2 * xi(2, :)**4 * xi(3, :)**2), 8.0_dp / 45.0_dp, &
               'cube integral x^2 y^4 z^2', abs=1.0e-14_dp)
    if (allocated(error)) return
    ! first coordinate varies fastest
    call check(error, xi(1, 1) < xi(1, 2) .and. xi(2, 1) == xi(2, 2) .and. xi(2, 1) < xi(2, 4) .and. &
               xi(3, 1) == xi(3, 9) .and. xi(3, 1) < xi(3, 10), &
               'cube rule ordering')
    if (allocated(error)) return
    call square_rule(2, s, ws, error)
    if (allocated(error)) return
    call check(error, sum(ws), 4.0_dp, 'square weights', abs=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, sum(ws * s(1, :)**2 * s(2, :)**2), 4.0_dp / 9.0_dp, 'square integral x^2 y^2', abs=1.0e-14_dp)
    if (allocated(error)) return
  end subroutine test_tensor_rules

  ! ------------------------------------------------------------------ factory

  subroutine test_factory(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    type(error_t), allocatable :: refused
    character(len=6), parameter :: names(3) = ['hex8  ', 'hex20 ', 'HEX20r']
    character(len=6), parameter :: types(3) = ['hex8  ', 'hex20 ', 'hex20r']
    integer, parameter :: nen(3) = [8, 20, 20], ng(3) = [8, 27, 8], nfg(3) = [4, 9, 9], nfn(3) = [4, 8, 8]
    integer :: k
    do k = 1, 3
      call new_element(names(k), element, error)
      if (allocated(error)) return
      call check(error, element%element_type() == trim(types(k)), 'element_type of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, element%nnodes(), nen(k), 'nnodes of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, element%ngauss(), ng(k), 'ngauss of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, element%nfaces(), 6, 'nfaces of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, element%nface_gauss(3), nfg(k), 'nface_gauss of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, element%nface_nodes(3), nfn(k), 'nface_nodes of ' // trim(names(k)))
      if (allocated(error)) return
      call check(error, size(element%face_nodes(3)), nfn(k), 'size of face_nodes of ' // trim(names(k)))
      if (allocated(error)) return
    end do
    call new_element('hex27', element, refused)
    call check(error, allocated(refused), 'unknown element type must be refused')
    if (allocated(error)) return
  end subroutine test_factory

  ! ------------------------------------------------------------------ shape functions

  !> sum N = 1, sum dN/dxi = 0 and sum N_a xi_a = xi at sample points, hex8 and hex20.
  subroutine test_partition_of_unity(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: n(:), dn(:, :), nodes(:, :)
    real(dp) :: pts(3, 5)
    integer :: k, p, i
    pts = sample_points()
    do k = 1, 2
      if (k == 1) then
        allocate (hex8_t :: element)
      else
        allocate (hex20_t :: element)
      end if
      allocate (n(element%nnodes()), dn(3, element%nnodes()), nodes(3, element%nnodes()))
      call element%natural_coordinates(nodes)
      do p = 1, size(pts, 2)
        call element%shape(pts(:, p), n, dn)
        call check(error, sum(n), 1.0_dp, element%element_type() // ': sum of N', abs=1.0e-14_dp)
        if (allocated(error)) return
        do i = 1, 3
          call check(error, sum(dn(i, :)), 0.0_dp, element%element_type() // ': sum of dN/dxi', abs=1.0e-14_dp)
          if (allocated(error)) return
          call check(error, sum(n * nodes(i, :)), pts(i, p), element%element_type() // ': sum of N xi_a', &
                     abs=1.0e-14_dp)
          if (allocated(error)) return
          ! d/dxi_i of sum N_a xi_a,j = delta_ij
          call check(error, sum(dn(i, :) * nodes(i, :)), 1.0_dp, element%element_type() // &
                     ': sum of dN/dxi_i xi_a,i', abs=1.0e-14_dp)
          if (allocated(error)) return
        end do
      end do
      deallocate (element, n, dn, nodes)
    end do
  end subroutine test_partition_of_unity

  !> N_a(xi_b) = delta_ab; also the node coordinates follow the stated node order.
  subroutine test_kronecker(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: n(:), dn(:, :), nodes(:, :)
    real(dp) :: expected_xi(3, 20)
    integer :: k, a, b, m
    ! the brief's node order, built independently: corners, then midpoints of the listed edges
    expected_xi(:, 1:8) = corner_xi()
    do m = 1, 12
      expected_xi(:, 8 + m) = 0.5_dp * (expected_xi(:, hex20_edges(1, m)) + expected_xi(:, hex20_edges(2, m)))
    end do
    do k = 1, 2
      if (k == 1) then
        allocate (hex8_t :: element)
      else
        allocate (hex20_t :: element)
      end if
      allocate (n(element%nnodes()), dn(3, element%nnodes()), nodes(3, element%nnodes()))
      call element%natural_coordinates(nodes)
      call check(error, maxval(abs(nodes - expected_xi(:, 1:element%nnodes()))), 0.0_dp, &
                 element%element_type() // ': node natural coordinates', abs=0.0_dp)
      if (allocated(error)) return
      do b = 1, element%nnodes()
        call element%shape(nodes(:, b), n, dn)
        do a = 1, element%nnodes()
          call check(error, n(a), merge(1.0_dp, 0.0_dp, a == b), element%element_type() // ': N_' // str(a) // &
                     ' at node ' // str(b), abs=1.0e-15_dp)
          if (allocated(error)) return
        end do
      end do
      deallocate (element, n, dn, nodes)
    end do
  end subroutine test_kronecker

  !> dN/dxi against central differences of N (h = 1e-5; the cubic terms give errors ~1e-10).
  subroutine test_derivatives_fd(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: n(:), dn(:, :), np(:), nm(:), dummy(:, :)
    real(dp) :: pts(3, 5), step(3)
    real(dp), parameter :: h = 1.0e-5_dp
    integer :: k, p, i
    pts = sample_points()
    do k = 1, 2
      if (k == 1) then
        allocate (hex8_t :: element)
      else
        allocate (hex20_t :: element)
      end if
      allocate (n(element%nnodes()), dn(3, element%nnodes()), np(element%nnodes()), nm(element%nnodes()), &
                dummy(3, element%nnodes()))
      do p = 1, size(pts, 2)
        call element%shape(pts(:, p), n, dn)
        do i = 1, 3
          step = 0.0_dp
          step(i) = h
          call element%shape(pts(:, p) + step, np, dummy)
          call element%shape(pts(:, p) - step, nm, dummy)
          call check(error, maxval(abs((np - nm) / (2.0_dp * h) - dn(i, :))), 0.0_dp, &
                     element%element_type() // ': dN/dxi_' // str(i) // ' vs finite differences', abs=1.0e-9_dp)
          if (allocated(error)) return
        end do
      end do
      deallocate (element, n, dn, np, nm, dummy)
    end do
  end subroutine test_derivatives_fd

  !> Face shape functions: partition of unity, Kronecker at the face nodes (corners (+-1, +-1)
  !! counter-clockwise, then mid-edges), finite-difference derivatives; and the face tables:
  !! face mid-edge node k+4 is the natural midpoint of face corners k and k+1, and all face nodes
  !! lie on the face plane of the reference cube.
  subroutine test_face_shapes(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: n(:), dn(:, :), np(:), nm(:), dummy(:, :), nodes(:, :)
    real(dp) :: snodes(2, 8), s(2), step(2)
    real(dp), parameter :: h = 1.0e-5_dp
    integer, allocatable :: fn(:)
    integer :: k, a, b, i, face, nfn
    snodes = reshape([-1, -1, 1, -1, 1, 1, -1, 1, 0, -1, 1, 0, 0, 1, -1, 0] * 1.0_dp, [2, 8])
    do k = 1, 2
      if (k == 1) then
        allocate (hex8_t :: element)
      else
        allocate (hex20_t :: element)
      end if
      nfn = element%nface_nodes(1)   ! a hexahedron's faces are alike: face 1 stands for all
      allocate (n(nfn), dn(2, nfn), np(nfn), nm(nfn), dummy(2, nfn), nodes(3, element%nnodes()))
      do b = 1, nfn
        call element%face_shape(1, snodes(:, b), n, dn)
        do a = 1, nfn
          call check(error, n(a), merge(1.0_dp, 0.0_dp, a == b), element%element_type() // ': face N_' // str(a) // &
                     ' at face node ' // str(b), abs=1.0e-15_dp)
          if (allocated(error)) return
        end do
      end do
      s = [0.37_dp, -0.61_dp]
      call element%face_shape(1, s, n, dn)
      call check(error, sum(n), 1.0_dp, element%element_type() // ': face sum of N', abs=1.0e-14_dp)
      if (allocated(error)) return
      do i = 1, 2
        step = 0.0_dp
        step(i) = h
        call element%face_shape(1, s + step, np, dummy)
        call element%face_shape(1, s - step, nm, dummy)
        call check(error, maxval(abs((np - nm) / (2.0_dp * h) - dn(i, :))), 0.0_dp, &
                   element%element_type() // ': face dN/ds_' // str(i) // ' vs finite differences', abs=1.0e-9_dp)
        if (allocated(error)) return
      end do
      call element%natural_coordinates(nodes)
      do face = 1, element%nfaces()
        fn = element%face_nodes(face)
        ! all nodes of a face share one natural coordinate at +-1
        call check(error, any([(all(abs(nodes(i, fn) - nodes(i, fn(1))) < 1.0e-14_dp .and. &
                                    abs(abs(nodes(i, fn(1))) - 1.0_dp) < 1.0e-14_dp), i = 1, 3)]), &
                   element%element_type() // ': nodes of face ' // str(face) // ' on one face of the cube')
        if (allocated(error)) return
        do a = 5, nfn
          call check(error, maxval(abs(nodes(:, fn(a)) - 0.5_dp * (nodes(:, fn(a - 4)) + &
                     nodes(:, fn(mod(a - 4, 4) + 1))))), 0.0_dp, element%element_type() // ': face ' // str(face) // &
                     ' mid-edge node ' // str(a), abs=1.0e-15_dp)
          if (allocated(error)) return
        end do
      end do
      deallocate (element, n, dn, np, nm, dummy, nodes)
    end do
  end subroutine test_face_shapes

  ! ------------------------------------------------------------------ B-matrix and stiffness

  !> u = H x + c on distorted/curved elements gives eps = sym(H) (engineering) at every Gauss point
  !! (1e-10), D eps as stresses, and b_matrix times u gives the same strain at an arbitrary point.
  subroutine test_linear_field(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), u(:), eps(:, :), sig(:, :), b(:, :), dg(:, :, :)
    character(len=:), allocatable :: label
    real(dp) :: h(3, 3), c(3), expected(6), d(6, 6), detj
    integer :: k, g
    h = reshape([0.1_dp, -0.3_dp, 0.25_dp, 0.7_dp, -0.2_dp, 0.05_dp, -0.45_dp, 0.33_dp, 0.6_dp], [3, 3])
    c = [1.0_dp, -2.0_dp, 0.5_dp]
    expected = voigt_strain(h)
    d = isotropic_d(30000.0_dp, 0.2_dp)
    do k = 1, n_test_elements
      call test_element(k, element, xe, label)
      u = linear_field(xe, h, c)
      allocate (eps(6, element%ngauss()), sig(6, element%ngauss()), b(6, size(u)))
      dg = d_at_points(d, element%ngauss())
      call element%strains(xe, u, eps)
      call element%gauss_stresses(xe, u, dg, sig)
      do g = 1, element%ngauss()
        call check(error, maxval(abs(eps(:, g) - expected)), 0.0_dp, label // ': strain at Gauss point ' // str(g), &
                   abs=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, maxval(abs(sig(:, g) - matmul(d, expected))), 0.0_dp, label // ': stress at Gauss point ' &
                   // str(g), abs=1.0e-10_dp * maxval(abs(d)))
        if (allocated(error)) return
      end do
      call element%b_matrix(xe, [0.21_dp, -0.77_dp, 0.4_dp], b, detj)
      call check(error, detj > 0.0_dp, label // ': positive Jacobian')
      if (allocated(error)) return
      call check(error, maxval(abs(matmul(b, u) - expected)), 0.0_dp, label // ': B u at a point', abs=1.0e-10_dp)
      if (allocated(error)) return
      deallocate (eps, sig, b)
    end do
  end subroutine test_linear_field

  !> Rigid translations and rotations: ke u = 0 (to 1e-10 ||ke|| ||u||); ke symmetric.
  subroutine test_rigid_modes(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), ke(:, :), u(:)
    character(len=:), allocatable :: label
    real(dp) :: h(3, 3), c(3), min_detj, kn
    integer :: k, mode
    do k = 1, n_test_elements
      call test_element(k, element, xe, label)
      allocate (ke(3 * size(xe, 2), 3 * size(xe, 2)))
      call element%stiffness(xe, d_at_points(isotropic_d(30000.0_dp, 0.2_dp), element%ngauss()), ke)
      min_detj = element%min_jacobian(xe)
      call check(error, min_detj > 0.0_dp, label // ': positive Jacobian')
      if (allocated(error)) return
      kn = norm2(ke)
      call check(error, maxval(abs(ke - transpose(ke))), 0.0_dp, label // ': ke symmetric', abs=1.0e-13_dp * kn)
      if (allocated(error)) return
      do mode = 1, 6
        call rigid_mode(mode, h, c)
        u = linear_field(xe, h, c)
        call check(error, norm2(matmul(ke, u)), 0.0_dp, label // ': ke times rigid mode ' // str(mode), &
                   abs=1.0e-10_dp * kn * norm2(u))
        if (allocated(error)) return
      end do
      deallocate (ke)
    end do
  end subroutine test_rigid_modes

  !> Unit cube, E = 1, nu = 0.25 (lambda = mu = 0.4): volume 1 (hex8 and hex20), detJ = 1/8;
  !! closed forms K(1x,1x) = (lambda + 4 mu)/9 = 2/9, K(1x,1y) = (lambda + mu)/12 = 1/15,
  !! trace = 24 * 2/9; and every entry against an independent 3x3x3 integration written here
  !! with the trilinear functions in x, y, z.
  subroutine test_unit_cube_hex8(error)
    type(error_t), allocatable, intent(out) :: error
    type(hex8_t) :: hex8
    type(hex20_t) :: hex20
    real(dp) :: xe(3, 8), ke(24, 24), kref(24, 24), d(6, 6), min_detj
    integer :: i
    xe = unit_cube()
    d = isotropic_d(1.0_dp, 0.25_dp)
    call check(error, hex8%volume(xe), 1.0_dp, 'hex8 unit cube volume', abs=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, hex20%volume(straight_hex20(xe)), 1.0_dp, 'hex20 unit cube volume', abs=1.0e-14_dp)
    if (allocated(error)) return
    call hex8%stiffness(xe, d_at_points(d, 8), ke)
    min_detj = hex8%min_jacobian(xe)
    call check(error, min_detj, 0.125_dp, 'unit cube detJ', abs=1.0e-15_dp)
    if (allocated(error)) return
    call check(error, ke(1, 1), 2.0_dp / 9.0_dp, 'K(1x,1x)', abs=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, ke(1, 2), 1.0_dp / 15.0_dp, 'K(1x,1y)', abs=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, sum([(ke(i, i), i = 1, 24)]), 48.0_dp / 9.0_dp, 'trace of ke', abs=1.0e-13_dp)
    if (allocated(error)) return
    kref = reference_cube_stiffness(d)
    call check(error, maxval(abs(ke - kref)), 0.0_dp, 'ke against independent integration', abs=1.0e-14_dp)
    if (allocated(error)) return
  end subroutine test_unit_cube_hex8

  !> Independent stiffness of the hex8 unit cube [0,1]^3: 3-point Gauss on [0,1] per direction
  !! (exact for the degree-2 integrand), derivatives of the trilinear functions taken directly in
  !! x, y, z, full B^T D B products.
  pure function reference_cube_stiffness(d) result(kref)
    real(dp), intent(in) :: d(6, 6)
    real(dp) :: kref(24, 24)
    real(dp) :: pts(3), wts(3), corner(3, 8), x(3), b(6, 24), grad(3), f(3), df(3)
    integer :: i, j, l, a, m
    pts = [0.5_dp - sqrt(0.15_dp), 0.5_dp, 0.5_dp + sqrt(0.15_dp)]
    wts = [5.0_dp, 8.0_dp, 5.0_dp] / 18.0_dp
    corner = unit_cube()
    kref = 0.0_dp
    do l = 1, 3
      do j = 1, 3
        do i = 1, 3
          x = [pts(i), pts(j), pts(l)]
          b = 0.0_dp
          do a = 1, 8
            ! 1D factors: x for a corner at 1, (1 - x) for a corner at 0
            do m = 1, 3
              if (corner(m, a) > 0.5_dp) then
                f(m) = x(m)
                df(m) = 1.0_dp
              else
                f(m) = 1.0_dp - x(m)
                df(m) = -1.0_dp
              end if
            end do
            grad = [df(1) * f(2) * f(3), f(1) * df(2) * f(3), f(1) * f(2) * df(3)]
            b(1, 3 * a - 2) = grad(1)
            b(2, 3 * a - 1) = grad(2)
            b(3, 3 * a) = grad(3)
            b(4, 3 * a - 1) = grad(3)
            b(4, 3 * a) = grad(2)
            b(5, 3 * a - 2) = grad(3)
            b(5, 3 * a) = grad(1)
            b(6, 3 * a - 2) = grad(2)
            b(6, 3 * a - 1) = grad(1)
          end do
          kref = kref + wts(i) * wts(j) * wts(l) * matmul(transpose(b), matmul(d, b))
        end do
      end do
    end do
  end function reference_cube_stiffness

  !> Eigenvalues of ke on the distorted elements: exactly 6 below 1e-9 lambda_max for hex8
  !! (2x2x2), hex20 (3x3x3) and hex8b (B-bar), and the 7th above 1e-4 lambda_max; hex20 with
  !! 2x2x2 has 12 (6 spurious zero-energy modes, the known count of the single 20-node brick
  !! with 2x2x2 Gauss; they do not survive in a 2x2x2 or 2x2x1 patch of elements, but a single
  !! column of elements keeps some: the element audit of 2026-11 found 3 in a 1x1x2 column).
  subroutine test_zero_energy_modes(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), ke(:, :), lam(:), work(:)
    character(len=:), allocatable :: label
    integer :: k, ndof, info, nzero
    do k = 1, n_test_elements
      call test_element(k, element, xe, label)
      ndof = 3 * size(xe, 2)
      allocate (ke(ndof, ndof), lam(ndof), work(64 * ndof))
      call element%stiffness(xe, d_at_points(isotropic_d(30000.0_dp, 0.2_dp), element%ngauss()), ke)
      call dsyev('N', 'U', ndof, ke, ndof, lam, work, size(work), info)
      call check(error, info, 0, label // ': dsyev info')
      if (allocated(error)) return
      nzero = count(abs(lam) <= 1.0e-9_dp * maxval(abs(lam)))
      call check(error, minval(lam) > -1.0e-9_dp * maxval(abs(lam)), label // ': no negative eigenvalue')
      if (allocated(error)) return
      if (k /= 3) then
        call check(error, nzero, 6, label // ': number of zero eigenvalues')
        if (allocated(error)) return
        call check(error, lam(7) > 1.0e-4_dp * lam(ndof), label // ': smallest deformation mode is stiff, ratio ' // &
                   str(lam(7) / lam(ndof)))
      else
        ! 6 rigid + 6 spurious modes, the known count for the 20-node brick with 2x2x2 Gauss
        call check(error, nzero, 12, label // ': number of zero eigenvalues')
      end if
      if (allocated(error)) return
      deallocate (ke, lam, work)
    end do
  end subroutine test_zero_energy_modes

  !> Jacobian range: 1/8 everywhere on the unit cube (hex8, straight hex20); det(A) for an affine
  !! element; a node-order mistake (top and bottom swapped) gives negative values; a hex20 with
  !! quarter-point mid-edge nodes along one corner's three edges has detJ = 0 at that corner.
  subroutine test_jacobian_range(error)
    type(error_t), allocatable, intent(out) :: error
    type(hex8_t) :: hex8
    type(hex20_t) :: hex20
    real(dp) :: xe(3, 8), xe20(3, 20), jmin, jmax, a(3, 3)
    xe = unit_cube()
    call hex8%jacobian_range(xe, jmin, jmax)
    call check(error, jmin, 0.125_dp, 'unit cube min detJ', abs=1.0e-15_dp)
    if (allocated(error)) return
    call check(error, jmax, 0.125_dp, 'unit cube max detJ', abs=1.0e-15_dp)
    if (allocated(error)) return
    call hex20%jacobian_range(straight_hex20(xe), jmin, jmax)
    call check(error, jmin, 0.125_dp, 'hex20 unit cube min detJ', abs=1.0e-15_dp)
    if (allocated(error)) return
    call check(error, jmax, 0.125_dp, 'hex20 unit cube max detJ', abs=1.0e-15_dp)
    if (allocated(error)) return
    ! affine element x = A xi + c: detJ = det(A)
    a = reshape([1.2_dp, 0.1_dp, -0.2_dp, 0.3_dp, 0.9_dp, 0.15_dp, -0.1_dp, 0.25_dp, 1.4_dp], [3, 3])
    call hex8%jacobian_range(affine_hex8(), jmin, jmax)
    call check(error, jmin, dot_product(a(:, 1), cross(a(:, 2), a(:, 3))), 'affine detJ', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, hex8%volume(affine_hex8()), 8.0_dp * dot_product(a(:, 1), cross(a(:, 2), a(:, 3))), &
               'affine volume', rel=1.0e-14_dp)
    if (allocated(error)) return
    ! inverted: top and bottom faces swapped
    call hex8%jacobian_range(xe(:, [5, 6, 7, 8, 1, 2, 3, 4]), jmin, jmax)
    call check(error, jmax, -0.125_dp, 'inverted element max detJ', abs=1.0e-15_dp)
    if (allocated(error)) return
    ! quarter-point nodes next to corner 1 on edges 1-2 (node 9), 4-1 (node 12), 1-5 (node 17)
    xe20 = straight_hex20(xe)
    xe20(:, 9) = [0.25_dp, 0.0_dp, 0.0_dp]
    xe20(:, 12) = [0.0_dp, 0.25_dp, 0.0_dp]
    xe20(:, 17) = [0.0_dp, 0.0_dp, 0.25_dp]
    call hex20%jacobian_range(xe20, jmin, jmax)
    call check(error, jmin, 0.0_dp, 'quarter-point corner detJ', abs=1.0e-15_dp)
    if (allocated(error)) return
  end subroutine test_jacobian_range

  ! ------------------------------------------------------------------ faces

  !> Area, centroid (by two triangles) and unit normal of a planar quadrilateral p1 p2 p3 p4.
  pure subroutine planar_quad(p, area, centroid, normal)
    real(dp), intent(in) :: p(3, 4)
    real(dp), intent(out) :: area, centroid(3), normal(3)
    real(dp) :: a1, a2, c(3)
    c = cross(p(:, 3) - p(:, 1), p(:, 4) - p(:, 2))
    normal = c / norm2(c)
    a1 = 0.5_dp * norm2(cross(p(:, 2) - p(:, 1), p(:, 3) - p(:, 1)))
    a2 = 0.5_dp * norm2(cross(p(:, 3) - p(:, 1), p(:, 4) - p(:, 1)))
    area = a1 + a2
    centroid = (a1 * (p(:, 1) + p(:, 2) + p(:, 3)) + a2 * (p(:, 1) + p(:, 3) + p(:, 4))) / (3.0_dp * area)
  end subroutine planar_quad

  !> A hex8 whose faces are planar but not parallel (a skew frustum under a general affine map).
  pure function planar_face_hex8() result(xe)
    real(dp) :: xe(3, 8), a(3, 3), p(3, 8)
    integer :: k
    p = reshape([0.0_dp, 0.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 2.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, &
                 0.3_dp, 0.2_dp, 1.5_dp, 1.5_dp, 0.2_dp, 1.5_dp, 1.5_dp, 1.8_dp, 1.5_dp, 0.3_dp, 1.8_dp, 1.5_dp], [3, 8])
    a = reshape([1.2_dp, 0.1_dp, -0.2_dp, 0.3_dp, 0.9_dp, 0.15_dp, -0.1_dp, 0.25_dp, 1.4_dp], [3, 3])
    do k = 1, 8
      xe(:, k) = matmul(a, p(:, k))
    end do
  end function planar_face_hex8

  !> hex8 with planar, non-parallel faces: per face, sum of wda = area (two triangles), the
  !! integral of a linear function = area times its value at the area centroid, every normal
  !! equals the plane's unit normal and points out (dot with face centroid minus element centroid > 0).
  subroutine test_faces_planar_hex8(error)
    type(error_t), allocatable, intent(out) :: error
    type(hex8_t) :: hex8
    real(dp) :: xe(3, 8), xg(3, 4), normal(3, 4), wda(4), nf(4, 4), area, centroid(3), plane_normal(3)
    real(dp) :: out(3), coef(3)
    integer, allocatable :: fn(:)
    integer :: face, g
    xe = planar_face_hex8()
    coef = [0.7_dp, -1.3_dp, 2.1_dp]
    do face = 1, 6
      fn = hex8%face_nodes(face)
      call hex8%face_integration(xe, face, xg, normal, wda, nf)
      call planar_quad(xe(:, fn), area, centroid, plane_normal)
      call check(error, sum(wda), area, 'hex8 face ' // str(face) // ' area', rel=1.0e-13_dp)
      if (allocated(error)) return
      call check(error, sum(wda * (3.0_dp + matmul(coef, xg))), area * (3.0_dp + dot_product(coef, centroid)), &
                 'hex8 face ' // str(face) // ' integral of a linear function', rel=1.0e-13_dp)
      if (allocated(error)) return
      out = sum(xe(:, fn), dim=2) / 4.0_dp - sum(xe, dim=2) / 8.0_dp
      do g = 1, 4
        call check(error, dot_product(normal(:, g), out) > 0.0_dp, 'hex8 face ' // str(face) // ' normal outward')
        if (allocated(error)) return
        call check(error, norm2(normal(:, g) - sign(1.0_dp, dot_product(plane_normal, out)) * plane_normal), &
                   0.0_dp, 'hex8 face ' // str(face) // ' normal equals plane normal', abs=1.0e-14_dp)
        if (allocated(error)) return
      end do
    end do
  end subroutine test_faces_planar_hex8

  !> hex20 extruded along z (height 1.2) from a planar quadrilateral with parabolic edges: the
  !! bottom and top faces are planar, so their areas and linear integrals have closed forms
  !! (polygon plus parabolic segments 2/3 L delta with centroid 2/5 delta off the chord), the
  !! volume is height times that area, and the bottom/top normals are -z/+z.
  subroutine test_faces_curved_hex20(error)
    type(error_t), allocatable, intent(out) :: error
    type(hex20_t) :: hex20
    real(dp), parameter :: height = 1.2_dp
    real(dp) :: corners(2, 4), delta(4), xe(3, 20), chord(2), nout(2), seg_area, seg_c(2)
    real(dp) :: area, moment(2), area_c(3), a_tri, xg(3, 9), normal(3, 9), wda(9), nf(8, 9), coef(3)
    integer :: e, k
    corners = reshape([0.0_dp, 0.0_dp, 3.0_dp, 0.0_dp, 2.6_dp, 2.2_dp, 0.2_dp, 1.8_dp], [2, 4])
    delta = [0.15_dp, -0.1_dp, 0.2_dp, 0.12_dp]   ! sagitta of each edge, outward positive
    do k = 1, 4
      xe(:, k) = [corners(:, k), 0.0_dp]
      xe(:, k + 4) = [corners(:, k), height]
      xe(:, 16 + k) = [corners(:, k), 0.5_dp * height]
    end do
    ! closed-form area and first moment of the planar region
    area = 0.0_dp
    moment = 0.0_dp
    do e = 1, 4
      k = mod(e, 4) + 1
      chord = corners(:, k) - corners(:, e)
      nout = [chord(2), -chord(1)] / norm2(chord)   ! outward for a counter-clockwise polygon
      xe(:, 8 + e) = [0.5_dp * (corners(:, e) + corners(:, k)) + delta(e) * nout, 0.0_dp]
      xe(:, 12 + e) = [xe(1:2, 8 + e), height]
      seg_area = 2.0_dp / 3.0_dp * norm2(chord) * delta(e)
      seg_c = 0.5_dp * (corners(:, e) + corners(:, k)) + 0.4_dp * delta(e) * nout
      area = area + seg_area
      moment = moment + seg_area * seg_c
    end do
    do k = 2, 3   ! polygon as two triangles 1-2-3 and 1-3-4
      a_tri = 0.5_dp * ((corners(1, k) - corners(1, 1)) * (corners(2, k + 1) - corners(2, 1)) - &
                        (corners(2, k) - corners(2, 1)) * (corners(1, k + 1) - corners(1, 1)))
      area = area + a_tri
      moment = moment + a_tri * (corners(:, 1) + corners(:, k) + corners(:, k + 1)) / 3.0_dp
    end do
    call check(error, hex20%volume(xe), height * area, 'extruded hex20 volume', rel=1.0e-13_dp)
    if (allocated(error)) return
    coef = [0.7_dp, -1.3_dp, 2.1_dp]
    do k = 1, 2   ! face 1 bottom (z = 0), face 2 top (z = height)
      call hex20%face_integration(xe, k, xg, normal, wda, nf)
      call check(error, sum(wda), area, 'hex20 curved face ' // str(k) // ' area', rel=1.0e-13_dp)
      if (allocated(error)) return
      area_c = [moment / area, merge(0.0_dp, height, k == 1)]
      call check(error, sum(wda * (3.0_dp + matmul(coef, xg))), area * (3.0_dp + dot_product(coef, area_c)), &
                 'hex20 curved face ' // str(k) // ' linear integral', rel=1.0e-13_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(normal(3, :) - merge(-1.0_dp, 1.0_dp, k == 1))), 0.0_dp, &
                 'hex20 face ' // str(k) // ' normal', abs=1.0e-14_dp)
      if (allocated(error)) return
    end do
  end subroutine test_faces_curved_hex20

  !> Divergence theorem on closed element surfaces (distorted hex8 with warped faces, curved
  !! hex20): sum over faces of the integral of n dA = 0 and of x.n dA = 3 V (both exact for
  !! these rules), and every Gauss-point normal is unit and points out of the element.
  subroutine test_divergence_theorem(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), xg(:, :), normal(:, :), wda(:), nf(:, :)
    character(len=:), allocatable :: label
    real(dp) :: flux_n(3), flux_x, out(3), scale
    integer, allocatable :: fn(:)
    integer :: k, face, g
    do k = 1, 2
      call test_element(k, element, xe, label)
      ! hexahedra: every face has the size of face 1
      allocate (xg(3, element%nface_gauss(1)), normal(3, element%nface_gauss(1)), wda(element%nface_gauss(1)), &
                nf(element%nface_nodes(1), element%nface_gauss(1)))
      flux_n = 0.0_dp
      flux_x = 0.0_dp
      scale = 0.0_dp
      do face = 1, element%nfaces()
        call element%face_integration(xe, face, xg, normal, wda, nf)
        fn = element%face_nodes(face)
        out = sum(xe(:, fn), dim=2) / size(fn) - sum(xe, dim=2) / size(xe, 2)
        do g = 1, size(wda)
          call check(error, dot_product(normal(:, g), out) > 0.0_dp, label // ': face ' // str(face) // &
                     ' normal outward at point ' // str(g))
          if (allocated(error)) return
          call check(error, norm2(normal(:, g)), 1.0_dp, label // ': unit normal', abs=1.0e-14_dp)
          if (allocated(error)) return
          ! nf interpolates the position
          call check(error, norm2(matmul(xe(:, fn), nf(:, g)) - xg(:, g)), 0.0_dp, label // ': xg = sum N x', &
                     abs=1.0e-14_dp)
          if (allocated(error)) return
        end do
        flux_n = flux_n + matmul(normal, wda)
        flux_x = flux_x + sum(wda * sum(xg * normal, dim=1))
        scale = scale + sum(wda)
      end do
      call check(error, norm2(flux_n), 0.0_dp, label // ': closed surface integral of n', abs=1.0e-13_dp * scale)
      if (allocated(error)) return
      call check(error, flux_x, 3.0_dp * element%volume(xe), label // ': integral of x.n = 3 V', rel=1.0e-13_dp)
      if (allocated(error)) return
      deallocate (xg, normal, wda, nf)
    end do
  end subroutine test_divergence_theorem

  !> Constant strain patch, one element: for u = H x, ke u equals the consistent nodal forces of the
  !! surface tractions sigma.n (sigma = D eps(H)) integrated with face_integration. Distorted hex8
  !! and hex8b, curved hex20 (exact for these rules) and hex20 reduced on a parallelepiped.
  subroutine test_uniform_stress_patch(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), ke(:, :), u(:), f(:), xg(:, :), normal(:, :), wda(:), nf(:, :)
    character(len=:), allocatable :: label
    real(dp) :: h(3, 3), sv(6), sigma(3, 3)
    integer, allocatable :: fn(:)
    integer :: k, face, g, a
    h = reshape([0.1_dp, -0.3_dp, 0.25_dp, 0.7_dp, -0.2_dp, 0.05_dp, -0.45_dp, 0.33_dp, 0.6_dp], [3, 3]) * 1.0e-3_dp
    sv = matmul(isotropic_d(30000.0_dp, 0.2_dp), voigt_strain(h))
    sigma = reshape([sv(1), sv(6), sv(5), sv(6), sv(2), sv(4), sv(5), sv(4), sv(3)], [3, 3])
    do k = 1, n_test_elements
      call test_element(k, element, xe, label)
      if (k == 3) xe = straight_hex20(affine_hex8())
      ! hexahedra: every face has the size of face 1
      allocate (ke(3 * size(xe, 2), 3 * size(xe, 2)), f(3 * size(xe, 2)), xg(3, element%nface_gauss(1)), &
                normal(3, element%nface_gauss(1)), wda(element%nface_gauss(1)), &
                nf(element%nface_nodes(1), element%nface_gauss(1)))
      call element%stiffness(xe, d_at_points(isotropic_d(30000.0_dp, 0.2_dp), element%ngauss()), ke)
      u = linear_field(xe, h, [0.0_dp, 0.0_dp, 0.0_dp])
      f = 0.0_dp
      do face = 1, element%nfaces()
        call element%face_integration(xe, face, xg, normal, wda, nf)
        fn = element%face_nodes(face)
        do g = 1, size(wda)
          do a = 1, size(fn)
            f(3 * fn(a) - 2:3 * fn(a)) = f(3 * fn(a) - 2:3 * fn(a)) + nf(a, g) * wda(g) * matmul(sigma, normal(:, g))
          end do
        end do
      end do
      call check(error, maxval(abs(matmul(ke, u) - f)), 0.0_dp, label // ': ke u against face tractions', &
                 abs=1.0e-10_dp * maxval(abs(f)))
      if (allocated(error)) return
      deallocate (ke, f, xg, normal, wda, nf)
    end do
  end subroutine test_uniform_stress_patch

  ! ------------------------------------------------------------------ B-bar (hex8b)

  !> A displacement vector with no structure: u_i = 1e-3 sin(1.37 i + 0.4).
  pure function scrambled_displacement(ndof) result(u)
    integer, intent(in) :: ndof
    real(dp) :: u(ndof)
    integer :: i
    u = [(1.0e-3_dp * sin(1.37_dp * i + 0.4_dp), i = 1, ndof)]
  end function scrambled_displacement

  !> hex8b strains against the definition of B-bar (Hughes 1980, the mean-dilatation form): at
  !! every Gauss point the volumetric strain is the element mean of div u, (1/V) int div u dV,
  !! and the deviatoric part and the shears are those of the plain hex8 (both computed here from
  !! hex8_t's strains and Jacobians, 1e-13 of the largest strain), for a deformation that is not
  !! a constant strain on the distorted hex8.
  subroutine test_bbar_strains(error)
    type(error_t), allocatable, intent(out) :: error
    type(hex8_t) :: plain
    type(hex8_bbar_t) :: bbar
    real(dp) :: xe(3, 8), u(24), eps(6, 8), epsb(6, 8), xi(3, 8), w(8), n(8), dndx(3, 8), detj(8)
    real(dp) :: vol, theta_mean, scale, dev, devb
    integer :: g, i
    xe = distorted_hex8()
    u = scrambled_displacement(24)
    call plain%strains(xe, u, eps)
    call bbar%strains(xe, u, epsb)
    call plain%gauss_rule(xi, w)
    do g = 1, 8
      call plain%shape_gradients(xe, xi(:, g), n, dndx, detj(g))
    end do
    vol = sum(w * detj)
    theta_mean = sum(w * detj * (eps(1, :) + eps(2, :) + eps(3, :))) / vol
    scale = maxval(abs(eps))
    do g = 1, 8
      call check(error, sum(epsb(1:3, g)), theta_mean, 'hex8b: volumetric strain = element mean of div u at point ' &
                 // str(g), abs=1.0e-13_dp * scale)
      if (allocated(error)) return
      do i = 1, 3
        dev = eps(i, g) - sum(eps(1:3, g)) / 3.0_dp
        devb = epsb(i, g) - sum(epsb(1:3, g)) / 3.0_dp
        call check(error, devb, dev, 'hex8b: deviatoric normal strain ' // str(i) // ' at point ' // str(g), &
                   abs=1.0e-13_dp * scale)
        if (allocated(error)) return
      end do
      call check(error, maxval(abs(epsb(4:6, g) - eps(4:6, g))), 0.0_dp, 'hex8b: shear strains at point ' // str(g), &
                 abs=1.0e-13_dp * scale)
      if (allocated(error)) return
    end do
    ! the deformation is not a constant strain: the plain volumetric strain varies over the points
    call check(error, maxval(eps(1, :) + eps(2, :) + eps(3, :)) - minval(eps(1, :) + eps(2, :) + eps(3, :)) > &
               0.1_dp * scale, 'the test displacement has a varying dilatation')
  end subroutine test_bbar_strains

  !> For an isotropic material, B-bar equals the mean-dilatation method (Nagtegaal et al. 1974;
  !! Hughes 1980, Hughes' book section 4.5): K = sum_g B^T (D - kappa m m^T) B w detJ
  !! + kappa V gbar gbar^T, with kappa = lambda + 2 mu / 3, m = [1 1 1 0 0 0], the plain hex8 B
  !! and gbar = (1/V) sum_g m^T B w detJ. Built here from hex8_t's b_matrix, against hex8b's
  !! stiffness on the distorted hex8 at nu = 0.2 and 0.4999 (1e-12 of max |K|). hex8b's
  !! b_matrix (the internal forces use it) gives the same K.
  subroutine test_bbar_mean_dilatation(error)
    type(error_t), allocatable, intent(out) :: error
    type(hex8_t) :: plain
    type(hex8_bbar_t) :: bbar
    real(dp) :: xe(3, 8), d(6, 6), ddev(6, 6), ke(24, 24), kref(24, 24), kb(24, 24), b(6, 24), gbar(24)
    real(dp) :: xi(3, 8), w(8), detj, vol, kappa, nu, m(6)
    integer :: g, i, j, trial
    xe = distorted_hex8()
    m = [1.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
    call plain%gauss_rule(xi, w)
    do trial = 1, 2
      nu = merge(0.2_dp, 0.4999_dp, trial == 1)
      d = isotropic_d(30000.0_dp, nu)
      kappa = 30000.0_dp / (3.0_dp * (1.0_dp - 2.0_dp * nu))
      do j = 1, 6
        do i = 1, 6
          ddev(i, j) = d(i, j) - kappa * m(i) * m(j)
        end do
      end do
      kref = 0.0_dp
      gbar = 0.0_dp
      vol = 0.0_dp
      do g = 1, 8
        call plain%b_matrix(xe, xi(:, g), b, detj)
        kref = kref + matmul(transpose(b), matmul(ddev, b)) * (w(g) * detj)
        gbar = gbar + matmul(m, b) * (w(g) * detj)
        vol = vol + w(g) * detj
      end do
      gbar = gbar / vol
      do j = 1, 24
        kref(:, j) = kref(:, j) + kappa * vol * gbar * gbar(j)
      end do
      call bbar%stiffness(xe, d_at_points(d, 8), ke)
      call check(error, maxval(abs(ke - kref)), 0.0_dp, 'hex8b stiffness = mean-dilatation form, nu = ' // str(nu), &
                 abs=1.0e-12_dp * maxval(abs(kref)))
      if (allocated(error)) return
      kb = 0.0_dp
      do g = 1, 8
        call bbar%b_matrix(xe, xi(:, g), b, detj)
        kb = kb + matmul(transpose(b), matmul(d, b)) * (w(g) * detj)
      end do
      call check(error, maxval(abs(kb - kref)), 0.0_dp, 'hex8b: sum of Bbar^T D Bbar from b_matrix, nu = ' // str(nu), &
                 abs=1.0e-12_dp * maxval(abs(kref)))
      if (allocated(error)) return
    end do
  end subroutine test_bbar_mean_dilatation

  ! ------------------------------------------------------------------ general material

  !> With an anisotropic, non-symmetric material matrix (a plastic tangent's kind), each element's
  !! stiffness (whose product exploits the sparsity of B) equals the plain sum of
  !! B^T D B detJ w built from its b_matrix, which the internal forces use (1e-13 of max |K|), and
  !! ke(D^T) = ke(D)^T; so ke u = the internal forces of D B u. The kernels were also compared
  !! entry by entry with an independent numpy implementation (shape functions from the inverse
  !! Vandermonde matrix of each element's polynomial space) on distorted elements; they agreed to
  !! 1e-15 (element audit, 2026-11).
  subroutine test_general_material(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: xe(:, :), ke(:, :), kt(:, :), kref(:, :), b(:, :), xi(:, :), w(:)
    character(len=:), allocatable :: label
    real(dp) :: d(6, 6), dt(6, 6), detj
    integer :: k, i, j, g, ndof
    do j = 1, 6
      do i = 1, 6
        d(i, j) = 1000.0_dp * sin(0.7_dp * i + 1.9_dp * j + 0.3_dp)
      end do
      d(j, j) = d(j, j) + 5000.0_dp
    end do
    dt = transpose(d)
    do k = 1, n_test_elements
      call test_element(k, element, xe, label)
      ndof = 3 * size(xe, 2)
      allocate (ke(ndof, ndof), kt(ndof, ndof), kref(ndof, ndof), b(6, ndof), xi(3, element%ngauss()), &
                w(element%ngauss()))
      call element%stiffness(xe, d_at_points(d, element%ngauss()), ke)
      call element%stiffness(xe, d_at_points(dt, element%ngauss()), kt)
      call element%gauss_rule(xi, w)
      kref = 0.0_dp
      do g = 1, element%ngauss()
        call element%b_matrix(xe, xi(:, g), b, detj)
        kref = kref + matmul(transpose(b), matmul(d, b)) * (w(g) * detj)
      end do
      call check(error, maxval(abs(ke - kref)), 0.0_dp, label // ': ke = sum B^T D B detJ w, non-symmetric D', &
                 abs=1.0e-13_dp * maxval(abs(kref)))
      if (allocated(error)) return
      call check(error, maxval(abs(kt - transpose(ke))), 0.0_dp, label // ': ke(D^T) = ke(D)^T', &
                 abs=1.0e-13_dp * maxval(abs(kref)))
      if (allocated(error)) return
      call check(error, maxval(abs(ke - transpose(ke))) > 1.0e-3_dp * maxval(abs(ke)), &
                 label // ': the test D makes ke non-symmetric')
      if (allocated(error)) return
      deallocate (ke, kt, kref, b, xi, w)
    end do
  end subroutine test_general_material

  ! ------------------------------------------------------------------ pressure on curved faces

  !> A hex20 whose nodes all lie on the cylinders r = 2, 2.3, 2.6 (theta 0.2 .. 0.9 rad,
  !! z 0 .. 1.3), each node then moved by up to 0.03: every face curved and warped.
  pure function cylindrical_hex20() result(xe)
    real(dp) :: xe(3, 20), c(3, 20), r, th, z
    integer :: a, m
    c(:, 1:8) = corner_xi()
    do m = 1, 12
      c(:, 8 + m) = 0.5_dp * (c(:, hex20_edges(1, m)) + c(:, hex20_edges(2, m)))
    end do
    do a = 1, 20
      r = 2.3_dp + 0.3_dp * c(1, a)
      th = 0.55_dp + 0.35_dp * c(2, a)
      z = 0.65_dp + 0.65_dp * c(3, a)
      xe(:, a) = [r * cos(th), r * sin(th), z] + 0.03_dp * [sin(2.1_dp * a), cos(1.7_dp * a), sin(0.9_dp * a + 1.0_dp)]
    end do
  end function cylindrical_hex20

  !> Uniform pressure p on each face of a distorted hex8, a curved hex20 and a hex20 on
  !! cylinders: the consistent nodal forces f_a = -p int N_a n dA (face_integration) have the
  !! resultant -p A with the vector area A = 1/2 closed-integral of x cross dx, and the moment
  !! sum x_a cross f_a = -p int x cross n dA = p/2 closed-integral of |x|^2 dx (Stokes:
  !! int n cross grad(phi) dA = closed-integral of phi dx with phi = |x|^2 / 2). The loop runs
  !! along the face's four edges, each the line (hex8) or parabola (hex20) through the edge's
  !! nodes (its mid-edge node found from this file's table of hex20 edges), by 4-point Gauss
  !! (exact). Both identities hold exactly for the isoparametric face and its rule.
  !! Tolerance 1e-13 of p times the face's size.
  subroutine test_pressure_resultant_moment(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), parameter :: p = 2.5_dp
    real(dp), allocatable :: xe(:, :), xg(:, :), normal(:, :), wda(:), nf(:, :)
    integer, allocatable :: fn(:)
    real(dp) :: force(3), moment(3), area(3), loop_moment(3), xa(3), xb(3), xm(3), x(3)
    real(dp) :: size_face
    integer :: k, face, a, b, edge
    character(len=:), allocatable :: label
    do k = 1, 3
      select case (k)
      case (1)
        allocate (hex8_t :: element)
        xe = distorted_hex8()
        label = 'distorted hex8'
      case (2)
        allocate (element, source=hex20_t(reduced=.false.))
        xe = curved_hex20()
        label = 'curved hex20'
      case default
        allocate (element, source=hex20_t(reduced=.false.))
        xe = cylindrical_hex20()
        label = 'cylindrical hex20'
      end select
      ! hexahedra: every face has the size of face 1
      allocate (xg(3, element%nface_gauss(1)), normal(3, element%nface_gauss(1)), wda(element%nface_gauss(1)), &
                nf(element%nface_nodes(1), element%nface_gauss(1)))
      do face = 1, 6
        fn = element%face_nodes(face)
        call element%face_integration(xe, face, xg, normal, wda, nf)
        force = 0.0_dp
        moment = 0.0_dp
        do a = 1, size(fn)
          x = -p * matmul(normal, nf(a, :) * wda)
          force = force + x
          moment = moment + cross(xe(:, fn(a)), x)
        end do
        area = 0.0_dp
        loop_moment = 0.0_dp
        do edge = 1, 4
          xa = xe(:, fn(edge))
          xb = xe(:, fn(mod(edge, 4) + 1))
          if (size(fn) == 8) then
            ! the mid-edge node of the element edge between the two corners (this file's own table)
            b = fn(mod(edge, 4) + 1)
            xm = xe(:, 8 + findloc((hex20_edges(1, :) == fn(edge) .and. hex20_edges(2, :) == b) .or. &
                                   (hex20_edges(2, :) == fn(edge) .and. hex20_edges(1, :) == b), .true., dim=1))
          else
            xm = 0.5_dp * (xa + xb)
          end if
          call add_edge_integrals(xa, xb, xm, area, loop_moment)
        end do
        size_face = sqrt(norm2(area)) * maxval(abs(xe))
        call check(error, norm2(force + p * area), 0.0_dp, label // ' face ' // str(face) // &
                   ': resultant = -p times the vector area', abs=1.0e-13_dp * p * norm2(area))
        if (allocated(error)) return
        call check(error, norm2(moment - p * loop_moment), 0.0_dp, label // ' face ' // str(face) // &
                   ': moment = p/2 loop integral of |x|^2 dx', abs=1.0e-13_dp * p * norm2(area) * size_face)
        if (allocated(error)) return
      end do
      deallocate (element, xg, normal, wda, nf)
    end do
  end subroutine test_pressure_resultant_moment

  ! ------------------------------------------------------------------ hex20r in patches

  !> Zero eigenvalues of the stiffness of a block of nx x ny x nz unit-cube elements of `element`
  !! (isotropic, nu = 0.3), nodes shared between neighbours, nothing held.
  integer function patch_zero_modes(element, nx, ny, nz) result(nzero)
    class(solid_element_t), intent(in) :: element
    integer, intent(in) :: nx, ny, nz
    real(dp), allocatable :: k(:, :), lam(:), work(:)
    real(dp) :: xi(3, 20), xe(3, 20), ke(60, 60)
    integer :: key(3, 20 * nx * ny * nz), node(20), dofs(60), nnode, i, j, l, a, b, info
    call element%natural_coordinates(xi)
    nnode = 0
    allocate (k(3 * 20 * nx * ny * nz, 3 * 20 * nx * ny * nz))
    k = 0.0_dp
    do l = 0, nz - 1
      do j = 0, ny - 1
        do i = 0, nx - 1
          do a = 1, 20
            xe(:, a) = 0.5_dp * (xi(:, a) + 1.0_dp) + [i, j, l]
            ! node identity: the point's coordinates times 2 are integers
            node(a) = 0
            do b = 1, nnode
              if (all(key(:, b) == nint(2.0_dp * xe(:, a)))) node(a) = b
            end do
            if (node(a) == 0) then
              nnode = nnode + 1
              key(:, nnode) = nint(2.0_dp * xe(:, a))
              node(a) = nnode
            end if
            dofs(3 * a - 2:3 * a) = 3 * node(a) - [2, 1, 0]
          end do
          call element%stiffness(xe, d_at_points(isotropic_d(1.0_dp, 0.3_dp), element%ngauss()), ke)
          k(dofs, dofs) = k(dofs, dofs) + ke
        end do
      end do
    end do
    allocate (lam(3 * nnode), work(64 * 3 * nnode))
    call dsyev('N', 'U', 3 * nnode, k, size(k, 1), lam, work, size(work), info)
    nzero = -1
    if (info == 0) nzero = count(abs(lam) <= 1.0e-10_dp * maxval(abs(lam)))
  end function patch_zero_modes

  !> hex20 with 2x2x2 Gauss (hex20r) has 6 spurious zero-energy modes in one element (12 zero
  !! eigenvalues). In a layer of 2 x 2 x 1 elements they are gone (6, the rigid modes) - they do
  !! not communicate across the shared faces - but in a single column of elements some survive:
  !! 9 zero eigenvalues for 1 x 1 x 2 (and 10, 11 for columns of 3, 4: n + 1 spurious modes).
  !! Counts found by the element audit (2026-11) with feps's kernels and an independent numpy
  !! implementation alike. hex20 with 3x3x3 has the 6 rigid modes only in every case. A mesh of
  !! hex20r must not be one element wide in two directions.
  subroutine test_hex20r_patches(error)
    type(error_t), allocatable, intent(out) :: error
    type(hex20_t) :: full, reduced
    integer, parameter :: shapes(3, 3) = reshape([1, 1, 1, 2, 2, 1, 1, 1, 2], [3, 3])
    integer, parameter :: expected_reduced(3) = [12, 6, 9]
    integer :: k
    character(len=:), allocatable :: label
    full = hex20_t(reduced=.false.)
    reduced = hex20_t(reduced=.true.)
    do k = 1, 3
      label = str(shapes(1, k)) // ' x ' // str(shapes(2, k)) // ' x ' // str(shapes(3, k))
      call check(error, patch_zero_modes(full, shapes(1, k), shapes(2, k), shapes(3, k)), 6, &
                 'hex20, ' // label // ' elements: zero eigenvalues')
      if (allocated(error)) return
      call check(error, patch_zero_modes(reduced, shapes(1, k), shapes(2, k), shapes(3, k)), expected_reduced(k), &
                 'hex20r, ' // label // ' elements: zero eigenvalues')
      if (allocated(error)) return
    end do
  end subroutine test_hex20r_patches

end module test_elements
