!> Tests of the nodal stresses (feps_stress_recovery, fields nodal_stress and nodal_principal):
!! - the extrapolation of every solid element type reproduces at its nodes any polynomial of
!!   the space its Gauss points determine (trilinear for 2x2x2, triquadratic for 3x3x3, linear
!!   and quadratic for the triangles' 3 and 6 points), to 1e-12;
!! - the average at a node is over the elements of one group;
!! - end to end: the hex20 cantilever in pure bending, whose exact stress sxx = 20 (y - 5) MPa
!!   hex20 reproduces, written at every node of an element to 1e-10 of the peak, with its
!!   principal values; and the hex20 Lame cylinder, whose hoop stress at the bore the nodal
!!   average gives within 5e-4 of the closed form (the largest Gauss-point value, 3 mm inside
!!   the wall, is 0.6% low).
module test_stress_recovery
  use feps_kinds, only: dp
  use feps_error, only: str
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_solid_element, only: solid_element_t
  use feps_element_catalog, only: new_element => new_solid_element
  use feps_stress_recovery, only: extrapolation_matrix, extrapolation_from_points, nodal_average
  use feps_interface_element, only: interface_element_t, new_interface_element
  use feps_h5_testing, only: run_and_open, close_and_delete, scratch_path, read_real, read_int, file_text, &
                             occurrences
  use hdf5, only: hid_t, h5lexists_f
  implicit none
  private

  public :: collect_stress_recovery

contains

  subroutine collect_stress_recovery(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('extrapolation reproduces the polynomials of each rule at the nodes', test_polynomials), &
      new_unittest('nodal average over one group''s elements', test_average), &
      new_unittest('hex20 cantilever in pure bending: exact nodal stresses in the results file', test_bending), &
      new_unittest('hex20 Lame cylinder: nodal hoop stress at the bore against the closed form', test_lame), &
      new_unittest('interfaces: extrapolation reproduces the polynomials of each rule', test_interface_polynomials), &
      new_unittest('contact under a linear pressure: exact nodal tractions in the results file', &
                   test_contact_tractions) &
    ]
  end subroutine collect_stress_recovery

  !> A polynomial of the rule's space with every term of it: for the element types with
  !! 2 x 2 x 2 points sum of c xi^i eta^j zeta^k (i, j, k <= 1), 3 x 3 x 3 up to 2 each, the
  !! triangles total degree 1 (3 points) or 2 (6 points).
  pure real(dp) function field(xi, degree, tensor)
    real(dp), intent(in) :: xi(3)
    integer, intent(in) :: degree
    logical, intent(in) :: tensor
    integer :: i, j, k
    real(dp) :: c
    field = 0.0_dp
    c = 0.7_dp
    do k = 0, merge(degree, 0, tensor)
      do j = 0, degree
        do i = 0, degree
          if (.not. tensor .and. i + j > degree) cycle
          c = -1.3_dp * c + 0.4_dp          ! distinct, non-trivial coefficients
          field = field + c * xi(1)**i * xi(2)**j * xi(3)**k
        end do
      end do
    end do
  end function field

  subroutine test_polynomials(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=6), parameter :: types(6) = [character(len=6) :: 'hex8', 'hex8b', 'hex20', 'hex20r', 'tri6', 'tri6-6']
    integer, parameter :: degrees(6) = [1, 1, 2, 1, 1, 2]
    logical, parameter :: tensor(6) = [.true., .true., .true., .true., .false., .false.]
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: e(:, :), xg(:, :), w(:), xn(:, :), at_gauss(:), at_nodes(:)
    logical :: ok
    integer :: t, q, a
    do t = 1, size(types)
      call new_element(types(t), element, error)
      if (allocated(error)) return
      call extrapolation_matrix(element, e, ok)
      call check(error, ok, trim(types(t)) // ': an extrapolation exists')
      if (allocated(error)) return
      allocate (xg(3, element%ngauss()), w(element%ngauss()), xn(3, element%nnodes()))
      call element%gauss_rule(xg, w)
      call element%natural_coordinates(xn)
      allocate (at_gauss(size(w)), at_nodes(size(xn, 2)))
      do q = 1, size(w)
        at_gauss(q) = field(xg(:, q), degrees(t), tensor(t))
      end do
      do a = 1, size(xn, 2)
        at_nodes(a) = field(xn(:, a), degrees(t), tensor(t))
      end do
      call check(error, maxval(abs(matmul(e, at_gauss) - at_nodes)), 0.0_dp, trim(types(t)) // &
                 ': polynomial at the nodes', abs=1.0e-12_dp * maxval(abs(at_nodes)))
      if (allocated(error)) return
      ! one degree more is not reproduced: the space is no larger than the rule's
      do q = 1, size(w)
        at_gauss(q) = xg(1, q)**(degrees(t) + 1)
      end do
      do a = 1, size(xn, 2)
        at_nodes(a) = xn(1, a)**(degrees(t) + 1)
      end do
      call check(error, maxval(abs(matmul(e, at_gauss) - at_nodes)) > 1.0e-3_dp, trim(types(t)) // &
                 ': xi^' // str(degrees(t) + 1) // ' is beyond the rule''s polynomials')
      if (allocated(error)) return
      deallocate (xg, w, xn, at_gauss, at_nodes)
    end do
  end subroutine test_polynomials

  !> Two hex8 elements sharing the face of nodes 2, 3, 6, 7 (13 nodes; node 12 in no
  !! element): each element's values uniform, 1 and 3 MPa in sxx. The shared nodes
  !! average to 2, the others keep their element's value; count says 2 and 1; a node of no
  !! element is 0 with count 0.
  subroutine test_average(error)
    type(error_t), allocatable, intent(out) :: error
    class(solid_element_t), allocatable :: element
    real(dp), allocatable :: e(:, :)
    real(dp) :: values(6, 16), nodal(6, 13)
    integer :: count(13), node
    logical :: ok
    integer, parameter :: conn(8, 2) = reshape([1, 2, 3, 4, 5, 6, 7, 8, 2, 9, 10, 3, 6, 11, 13, 7], [8, 2])
    real(dp) :: expect
    call new_element('hex8', element, error)
    if (allocated(error)) return
    call extrapolation_matrix(element, e, ok)
    values = 0.0_dp
    values(1, 1:8) = 1.0_dp
    values(1, 9:16) = 3.0_dp
    values(4, :) = -0.5_dp
    call nodal_average(e, conn, values, 13, nodal, count)
    do node = 1, 13
      if (any(node == [2, 3, 6, 7])) then
        expect = 2.0_dp
        call check(error, count(node), 2, 'count at shared node ' // str(node))
      else if (node == 12) then
        expect = 0.0_dp
        call check(error, count(node), 0, 'count at node 12, in no element')
      else
        expect = merge(1.0_dp, 3.0_dp, any(node == conn(:, 1)))
        call check(error, count(node), 1, 'count at node ' // str(node))
      end if
      if (allocated(error)) return
      call check(error, nodal(1, node), expect, 'sxx at node ' // str(node), abs=1.0e-13_dp)
      if (allocated(error)) return
      call check(error, nodal(4, node), merge(0.0_dp, -0.5_dp, node == 12), 'syz at node ' // str(node), &
                 abs=1.0e-13_dp)
      if (allocated(error)) return
    end do
  end subroutine test_average

  !> test/data/bending_hex20.dat: the cantilever of cantilever_hex20.dat (nu = 0, clamped at
  !! x = 0) under an end moment, a traction sxx = 20 (y - 5) MPa on x = 100. The exact field,
  !! u = 20 (y - 5) x / E, v = -10 x^2 / E, w = 0, meets the clamp and is quadratic, so hex20
  !! reproduces it and sxx = 20 (y - 5) holds at every node of an element; the other five
  !! components vanish; the principal values are (max(sxx, 0), min(sxx, 0)); nodes of no
  !! element (face and body centres of the grid) hold each column's smallest value over the
  !! group's nodes, so that a viewer's colour range is the group's. The default fields are written too
  !! (FIELDS, all, ...), and the XDMF file shows the nodal fields on the group's grid.
  subroutine test_bending(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: x(:, :), nodal(:, :), principal(:, :)
    integer, allocatable :: connectivity(:, :)
    integer(hid_t) :: file_id
    integer :: hdferr, n
    logical :: used, exists
    character(len=:), allocatable :: xmf
    real(dp) :: exact
    call open_with_mesh('test/data/bending_hex20.dat', 'bending', 'beam', file_id, x, connectivity, error)
    if (allocated(error)) return
    call read_real(file_id, '/steps/0001/nodal_stress/beam', nodal, error)
    if (.not. allocated(error)) call read_real(file_id, '/steps/0001/nodal_principal/beam', principal, error)
    if (.not. allocated(error)) then
      call h5lexists_f(file_id, '/steps/0001/stress', exists, hdferr)
      call check(error, exists, 'FIELDS, all, ...: the Gauss-point stresses are written too')
    end if
    xmf = file_text(scratch_path('bending.xmf'))
    call close_and_delete(file_id, 'bending')
    if (allocated(error)) return
    call check(error, size(nodal, 1) == 6 .and. size(nodal, 2) == size(x, 2), 'nodal_stress is 6 x nnode')
    if (allocated(error)) return
    do n = 1, size(x, 2)
      used = any(connectivity == n)
      ! a node of no element holds each column's smallest value over the group (fill_outside):
      ! sxx -100 (at y = 0), most tensile 0, most compressive -100
      exact = merge(20.0_dp * (x(2, n) - 5.0_dp), -100.0_dp, used)
      call check(error, nodal(1, n), exact, 'sxx at node ' // str(n), abs=1.0e-10_dp * 100.0_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(nodal(2:6, n))), 0.0_dp, 'other components at node ' // str(n), &
                 abs=1.0e-10_dp * 100.0_dp)
      if (allocated(error)) return
      call check(error, principal(1, n), merge(max(exact, 0.0_dp), 0.0_dp, used), 'most tensile at node ' // str(n), &
                 abs=1.0e-10_dp * 100.0_dp)
      if (allocated(error)) return
      call check(error, principal(2, n), min(exact, 0.0_dp), 'most compressive at node ' // str(n), &
                 abs=1.0e-10_dp * 100.0_dp)
      if (allocated(error)) return
    end do
    call check(error, occurrences(xmf, '<Attribute Name="nodal_stress" AttributeType="Matrix" ' // &
               'Center="Node">') == 1 .and. occurrences(xmf, 'nodal_principal/beam') == 1, &
               'the XDMF file shows the nodal fields')
  end subroutine test_bending

  !> test/data/lame_hex20.dat (a = 600, b = 715 mm, p = 10 MPa, plane strain, 8 hex20 through
  !! the wall) with FIELDS, nodal_stress: the hoop stress p a^2 / (b^2 - a^2) (1 + b^2 / a^2) =
  !! 57.611 MPa at every bore node within 5e-4 (measured 2.2e-4; discretisation); the largest
  !! Gauss-point hoop stress (r = 603.2) is 0.6% lower.
  subroutine test_lame(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: x(:, :), nodal(:, :)
    integer, allocatable :: connectivity(:, :)
    real(dp), parameter :: a = 600.0_dp, b = 715.0_dp, p = 10.0_dp
    real(dp) :: hoop, exact, c, s
    integer(hid_t) :: file_id
    integer :: n, bore
    call open_with_mesh('test/data/lame_hex20_nodal.dat', 'lame_nodal', 'wall', file_id, x, connectivity, error)
    if (allocated(error)) return
    call read_real(file_id, '/steps/0001/nodal_stress/wall', nodal, error)
    call close_and_delete(file_id, 'lame_nodal')
    if (allocated(error)) return
    exact = p * a**2 / (b**2 - a**2) * (1.0_dp + b**2 / a**2)
    bore = 0
    do n = 1, size(x, 2)
      if (abs(hypot(x(1, n), x(2, n)) - a) > 1.0e-6_dp .or. .not. any(connectivity == n)) cycle
      bore = bore + 1
      c = x(1, n) / a
      s = x(2, n) / a
      hoop = nodal(1, n) * s * s + nodal(2, n) * c * c - 2.0_dp * nodal(6, n) * s * c
      call check(error, hoop, exact, 'hoop stress at bore node ' // str(n), rel=5.0e-4_dp)
      if (allocated(error)) return
    end do
    call check(error, bore, 43, 'bore nodes of the hex20 mesh')
  end subroutine test_lame

  !> Every interface type, with its Gauss rule and with '-nodal': a polynomial of its rule's
  !! space sampled at the points is found at the lower layer's nodes (1e-12). Spaces: quad4 2 x 2
  !! and its nodes bilinear, quad8 3 x 3 (Gauss) and 8 nodes + centre biquadratic, tri3 (3 points
  !! or nodes) and tri6-nodal (3 mid-edge nodes) linear, tri6 (6 points) quadratic, line2 linear,
  !! line3 quadratic.
  subroutine test_interface_polynomials(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=16), parameter :: types(6) = [character(len=16) :: 'interface-quad4', 'interface-quad8', &
      'interface-tri3', 'interface-tri6', 'interface-line2', 'interface-line3']
    integer, parameter :: degrees(2, 6) = reshape([1, 1, 2, 2, 1, 1, 2, 1, 1, 1, 2, 2], [2, 6])  ! (Gauss, nodal)
    logical, parameter :: tensor(6) = [.true., .true., .false., .false., .true., .true.]
    type(interface_element_t) :: element
    real(dp), allocatable :: e(:, :), points(:, :), w(:), nodes(:, :), at_points(:), at_nodes(:)
    real(dp) :: xi(3)
    character(len=:), allocatable :: name
    logical :: ok, lines
    integer :: t, k, q, a
    do t = 1, size(types)
      do k = 1, 2
        name = trim(types(t)) // trim(merge('      ', '-nodal', k == 1))
        call new_interface_element(name, element, error)
        if (allocated(error)) return
        allocate (points(2, element%ngauss()), w(element%ngauss()), nodes(2, element%npairs()))
        call element%integration_rule(points, w)
        call element%node_coordinates(nodes)
        call extrapolation_from_points(points, nodes, e, ok)
        call check(error, ok, name // ': an extrapolation exists')
        if (allocated(error)) return
        lines = index(name, 'line') > 0
        allocate (at_points(size(w)), at_nodes(size(nodes, 2)))
        do q = 1, size(w)
          xi = [points(:, q), 0.0_dp]
          at_points(q) = surface_field(xi, degrees(k, t), tensor(t), lines)
        end do
        do a = 1, size(nodes, 2)
          xi = [nodes(:, a), 0.0_dp]
          at_nodes(a) = surface_field(xi, degrees(k, t), tensor(t), lines)
        end do
        call check(error, maxval(abs(matmul(e, at_points) - at_nodes)), 0.0_dp, name // ': polynomial at the nodes', &
                   abs=1.0e-12_dp * maxval(abs(at_nodes)))
        if (allocated(error)) return
        deallocate (points, w, nodes, at_points, at_nodes)
      end do
    end do
  end subroutine test_interface_polynomials

  !> A polynomial in (s1, s2) with every term of the space: tensor products up to `degree` in
  !! each of s1, s2 (s1 only for lines), or total degree `degree`.
  pure real(dp) function surface_field(xi, degree, tensor, line)
    real(dp), intent(in) :: xi(3)
    integer, intent(in) :: degree
    logical, intent(in) :: tensor, line
    integer :: i, j
    real(dp) :: c
    surface_field = 0.0_dp
    c = 0.3_dp
    do j = 0, merge(0, degree, line)
      do i = 0, degree
        if (.not. tensor .and. i + j > degree) cycle
        c = -1.7_dp * c + 0.9_dp
        surface_field = surface_field + c * xi(1)**i * xi(2)**j
      end do
    end do
  end function surface_field

  !> test/data/block_contact_nodal.dat: two hex8 blocks and an interface-quad4 layer pressed by
  !! p(x) = 1.5 (x + 10) / 30 MPa. The contact stress is linear, sigma_n = -p(x), tau = 0 (the
  !! Gauss points have it to rounding), so the nodal tractions at the lower layer's 9 nodes are
  !! -p(x) and 0 to 1e-12 of the peak; the other nodes hold the columns' smallest values.
  subroutine test_contact_tractions(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: x(:, :), nodal(:, :)
    integer, allocatable :: connectivity(:, :)
    integer(hid_t) :: file_id
    integer :: n
    logical :: lower
    real(dp) :: p
    call open_with_mesh('test/data/block_contact_nodal.dat', 'contact_nodal', 'joint', file_id, x, connectivity, error)
    if (allocated(error)) return
    call read_real(file_id, '/steps/0002/nodal_interface/joint', nodal, error)
    call close_and_delete(file_id, 'contact_nodal')
    if (allocated(error)) return
    call check(error, size(nodal, 1) == 3, 'nodal_interface has tau1 tau2 sigma_n')
    if (allocated(error)) return
    do n = 1, size(x, 2)
      lower = any(connectivity(1:4, :) == n)
      ! the other nodes hold each column's smallest value over the lower layer: sigma_n -1.5
      p = merge(1.5_dp * (x(1, n) + 10.0_dp) / 30.0_dp, 1.5_dp, lower)
      call check(error, nodal(3, n), -p, 'sigma_n at node ' // str(n), abs=1.5e-12_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(nodal(1:2, n))), 0.0_dp, 'tau at node ' // str(n), abs=1.5e-12_dp)
      if (allocated(error)) return
    end do
  end subroutine test_contact_tractions

  ! ------------------------------------------------------------------ helpers

  !> run_and_open, then the mesh coordinates and the connectivity of `group`.
  subroutine open_with_mesh(deck, stem, group, file_id, x, connectivity, error)
    character(len=*), intent(in) :: deck, stem, group
    integer(hid_t), intent(out) :: file_id
    real(dp), allocatable, intent(out) :: x(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :)
    type(error_t), allocatable, intent(out) :: error
    call run_and_open(deck, stem, file_id, error)
    if (allocated(error)) return
    call read_real(file_id, '/mesh/coordinates', x, error)
    if (.not. allocated(error)) call read_int(file_id, '/mesh/groups/' // group // '/connectivity', connectivity, error)
    if (allocated(error)) call close_and_delete(file_id, stem)
  end subroutine open_with_mesh

end module test_stress_recovery
