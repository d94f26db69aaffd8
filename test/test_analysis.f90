!> End-to-end linear analyses against closed forms and each other.
module test_analysis
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use feps_kinds, only: dp, pi
  use feps_error, only: str
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_model, only: model_t, node_set_t, constraint_t
  use feps_result_schema, only: field_stress, field_principal
  use feps_element_catalog, only: family_interface
  use feps_elasticity_testing, only: lame_bore_displacement, mean_radial_displacement
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_observer, only: step_result_t
  use feps_test_observers, only: all_steps_t
  use feps_elastic, only: elastic_matrix
  use feps_program, only: run_options_t, run_summary_t, run_feps
  implicit none
  private

  public :: collect_analysis

contains

  !> Run a model and return its last step.
  subroutine solve(model, solver, res, error)
    type(model_t), intent(inout) :: model
    character(len=*), intent(in) :: solver
    type(step_result_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    call run_analysis(model, solver, obs, summary, error)
    if (.not. allocated(error)) res = obs%steps(size(obs%steps))
  end subroutine solve

  subroutine collect_analysis(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('cube under uniform pressure, both solvers', test_cube), &
      new_unittest('patch test on a distorted hex8 mesh', test_patch_hex8), &
      new_unittest('patch test on a distorted hex20 mesh', test_patch_hex20), &
      new_unittest('Lame cylinder, hex20, nodal cylindrical supports', test_lame), &
      new_unittest('cantilever tip deflection, hex20', test_cantilever), &
      new_unittest('model B: skyline equals CHOLMOD', test_model_b_solvers), &
      new_unittest('model B: edge load integrates to 1000 kN', test_model_b_load), &
      new_unittest('Table 2.1 read as a mesh-only input', test_mesh_only), &
      new_unittest('a mesh-only input with a block of another node count', test_mesh_only_mixed), &
      new_unittest('plane strain: tri6 strip under pressure, both rules', test_plane_strain), &
      new_unittest('patch test on a distorted hex8b (B-bar) mesh', test_patch_hex8b), &
      new_unittest('Lame cylinder near incompressibility and at negative nu: locking and B-bar', test_locking), &
      new_unittest('model B: the symmetric half equals the full 360-degree model', test_symmetry), &
      new_unittest('fields not asked for are not computed; elastic groups keep no point state', test_fields), &
      new_unittest('REPORT, TILT: axis tilt of a cantilever column against Timoshenko', test_tilt_report), &
      new_unittest('feps --check: the run''s model and factorization, no step, no file', test_check_only), &
      new_unittest('PRESSURE with VARY and VARY2: bilinear load, exact nodal forces', test_bilinear_load), &
      new_unittest('TRACTION by components alone: the pressure''s nodal forces, resultant t A', test_traction_components), &
      new_unittest('STAGE with a negative LOAD= unloads: half the cube''s pressure taken off', test_stage_unload), &
      new_unittest('a gap in the node numbering selects nothing', test_node_gap), &
      new_unittest('cube with E = 1e-300 and 1e300: closed form, finite summary', test_cube_extreme_modulus), &
      new_unittest('PRESSURE on a cylindrical bore: resultant and moment in closed form', &
                   test_bore_pressure_resultant), &
      new_unittest('PRESSURE varying in THETA from 180 to 270 deg: the 0-90 deg load turned by 180 deg', &
                   test_theta_ramp_third_quadrant), &
      new_unittest('mixed precision: initial stiffness within 1e-7 of double; BFGS, an ill-conditioned and a ' // &
                   'linear model unchanged', test_mixed_precision) &
      ]
  end subroutine collect_analysis

  !> Uniaxial compression: szz = -p, other stresses 0; uz(top) = -p L / E, lateral nu p L / E.
  subroutine test_cube(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    character(len=7), parameter :: solvers(2) = ['cholmod', 'skyline']
    integer :: s, q, n
    real(dp), parameter :: p = 100.0_dp, e = 200000.0_dp, nu = 0.3_dp, l = 10.0_dp
    do s = 1, 2
      call read_deck('test/data/cube.dat', model, error)
      if (allocated(error)) return
      call solve(model, trim(solvers(s)), res, error)
      if (allocated(error)) return
      do q = 1, size(res%groups(1)%stress, 2)
        call check(error, res%groups(1)%stress(3, q), -p, 'szz at a Gauss point', rel=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, maxval(abs(res%groups(1)%stress([1, 2, 4, 5, 6], q))), 0.0_dp, 'other stresses', &
                   abs=1.0e-9_dp)
        if (allocated(error)) return
      end do
      n = 27   ! corner (10, 10, 10)
      call check(error, res%displacement(3, n), -p * l / e, 'uz at the top', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, res%displacement(1, n), nu * p * l / e, 'ux at x = 10', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, sum(res%reaction(3, :)), p * l * l, 'vertical reaction', rel=1.0e-10_dp)
      if (allocated(error)) return
    end do
  end subroutine test_cube

  !> The cube of test_cube with E = 1e-300 and 1e300 MPa: the displacements (1e303 and 1e-297
  !! mm) still match the closed form, and the summary's largest displacement, whose squares
  !! overflow or underflow, is the corner's p l / E sqrt(1 + 2 nu^2) at node 27.
  subroutine test_cube_extreme_modulus(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    real(dp), parameter :: p = 100.0_dp, nu = 0.3_dp, l = 10.0_dp, moduli(2) = [1.0e-300_dp, 1.0e300_dp]
    real(dp) :: e
    integer :: i
    do i = 1, size(moduli)
      e = moduli(i)
      call read_deck('test/data/cube.dat', model, error)
      if (allocated(error)) return
      call model%materials(1)%set('e', e)
      call run_analysis(model, 'cholmod', obs, summary, error)
      if (allocated(error)) return
      associate (u => obs%steps(size(obs%steps))%displacement)
        call check(error, u(3, 27), -p * l / e, 'uz at the top', rel=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, u(1, 27), nu * p * l / e, 'ux at x = 10', rel=1.0e-10_dp)
        if (allocated(error)) return
      end associate
      call check(error, summary%max_displacement, p * l / e * sqrt(1.0_dp + 2.0_dp * nu**2), &
                 'largest displacement', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, summary%max_displacement_node, 27, 'node of the largest displacement')
      if (allocated(error)) return
    end do
  end subroutine test_cube_extreme_modulus

  !> FIELDS without stresses: the displacements are unchanged (closed form) and no stress is
  !! recovered; in the block-contact deck only the interface group keeps point state, 2 x (3
  !! tractions + 3 strains + 9 tangent entries) reals and 2 flags per point (committed, trial).
  subroutine test_fields(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    type(analysis_summary_t) :: summary
    type(all_steps_t) :: obs
    real(dp), parameter :: p = 100.0_dp, e = 200000.0_dp, l = 10.0_dp
    integer :: g, np
    call read_deck('test/data/cube.dat', model, error)
    if (allocated(error)) return
    model%fields%on(field_stress) = .false.
    model%fields%on(field_principal) = .false.
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    call check(error, .not. allocated(res%groups(1)%stress), 'no stresses recovered')
    if (allocated(error)) return
    call check(error, res%displacement(3, 27), -p * l / e, 'uz at the top', rel=1.0e-10_dp)
    if (allocated(error)) return

    call read_deck('test/data/block_contact.dat', model, error)
    if (allocated(error)) return
    model%fields%on(field_stress) = .false.
    model%fields%on(field_principal) = .false.
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    res = obs%steps(size(obs%steps))
    do g = 1, size(model%groups)
      np = res%groups(g)%points_per_element * size(model%groups(g)%connectivity, 2)
      if (res%groups(g)%family == family_interface) then
        call check(error, allocated(res%groups(g)%stress), 'interface tractions kept')
        if (allocated(error)) return
        call check(error, real(summary%state_bytes(g), dp), real(np * (2 * (3 + 3 + 9) * 8 + 2 * 4), dp), &
                   'interface point state bytes', rel=0.0_dp)
      else
        call check(error, .not. allocated(res%groups(g)%stress), 'no solid stresses recovered')
        if (allocated(error)) return
        call check(error, real(summary%state_bytes(g), dp), 0.0_dp, 'elastic group keeps no state', abs=0.0_dp)
      end if
      if (allocated(error)) return
    end do
  end subroutine test_fields

  subroutine test_patch_hex8(error)
    type(error_t), allocatable, intent(out) :: error
    call patch_test('test/data/patch_hex8.dat', 0.12_dp, error)
  end subroutine test_patch_hex8

  subroutine test_patch_hex8b(error)
    type(error_t), allocatable, intent(out) :: error
    call patch_test('test/data/patch_hex8.dat', 0.12_dp, error, 'hex8b')
  end subroutine test_patch_hex8b

  subroutine test_patch_hex20(error)
    type(error_t), allocatable, intent(out) :: error
    call patch_test('test/data/patch_hex20.dat', 0.05_dp, error)
  end subroutine test_patch_hex20

  !> Distort every node but the cube's, prescribe u = A x + c on the boundary nodes, solve:
  !! the interior displacements and every Gauss-point stress must be exact (1e-10).
  subroutine patch_test(deck, amplitude, error, element_type)
    character(len=*), intent(in) :: deck
    real(dp), intent(in) :: amplitude
    type(error_t), allocatable, intent(out) :: error
    character(len=*), intent(in), optional :: element_type
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp), parameter :: grad(3, 3) = reshape([1.0e-3_dp, -2.0e-4_dp, 3.0e-4_dp, 5.0e-4_dp, -7.0e-4_dp, &
                                                 1.0e-4_dp, -4.0e-4_dp, 6.0e-4_dp, 2.0e-3_dp], [3, 3])
    real(dp), parameter :: shift(3) = [0.01_dp, -0.02_dp, 0.03_dp]
    real(dp) :: x(3), eps(6), sig(6), u(3)
    logical, allocatable :: boundary(:)
    integer :: n, d, q, nb
    type(node_set_t), allocatable :: sets(:)
    type(constraint_t), allocatable :: cons(:)

    call read_deck(deck, model, error)
    if (allocated(error)) return
    if (present(element_type)) model%groups(1)%element_type = element_type
    allocate (boundary(model%nnode))
    do n = 1, model%nnode
      x = model%coords(:, n)
      boundary(n) = any(abs(x) < 1.0e-9_dp .or. abs(x - 1.0_dp) < 1.0e-9_dp)
      ! Deterministic distortion of interior nodes
      if (.not. boundary(n)) model%coords(:, n) = x + amplitude * [sin(7.1_dp * n), cos(3.3_dp * n), sin(5.7_dp * n + 1)]
    end do
    nb = count(boundary)
    allocate (sets(nb), cons(3 * nb))
    nb = 0
    do n = 1, model%nnode
      if (.not. boundary(n)) cycle
      nb = nb + 1
      sets(nb)%name = 'b'
      sets(nb)%nodes = [n]
      u = matmul(grad, model%coords(:, n)) + shift
      do d = 1, 3
        cons(3 * (nb - 1) + d) = constraint_t(node_set=nb, csys=2, dof=d, value=u(d), prescribed=.true., &
                                               file=deck, line=0)
      end do
    end do
    model%node_sets = sets
    model%constraints = cons
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    do n = 1, model%nnode
      u = matmul(grad, model%coords(:, n)) + shift
      if (boundary(n)) cycle
      if (all(res%displacement(:, n) == 0.0_dp)) cycle   ! a lattice node in no element
      do d = 1, 3
        call check(error, res%displacement(d, n), u(d), 'interior displacement', abs=1.0e-12_dp)
        if (allocated(error)) return
      end do
    end do
    eps = [grad(1, 1), grad(2, 2), grad(3, 3), grad(2, 3) + grad(3, 2), grad(1, 3) + grad(3, 1), &
           grad(1, 2) + grad(2, 1)]
    sig = matmul(elastic_matrix(1000.0_dp, 0.25_dp), eps)
    do q = 1, size(res%groups(1)%stress, 2)
      do d = 1, 6
        call check(error, res%groups(1)%stress(d, q), sig(d), 'constant stress', abs=1.0e-10_dp * maxval(abs(sig)))
        if (allocated(error)) return
      end do
    end do
  end subroutine patch_test

  !> Plane-strain Lame solution: u(a) and the hoop stress at the Gauss points nearest the bore.
  subroutine test_lame(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp), parameter :: a = 600.0_dp, b = 715.0_dp, p = 10.0_dp, e = 40000.0_dp, nu = 0.2_dp
    real(dp) :: ca, cb, r, sr, st, u_exact, x(3), hoop
    integer :: n, q, e_idx, g, checked
    call read_deck('test/data/lame_hex20.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    ca = p * a**2 / (b**2 - a**2)
    cb = p * a**2 * b**2 / (b**2 - a**2)
    ! plane strain: u/r = ((1 - nu^2) s_theta - nu (1 + nu) s_r) / E at r = a
    sr = ca - cb / a**2
    st = ca + cb / a**2
    u_exact = a * ((1.0_dp - nu**2) * st - nu * (1.0_dp + nu) * sr) / e
    checked = 0
    do n = 1, model%nnode
      x = model%coords(:, n)
      if (abs(hypot(x(1), x(2)) - a) > 1.0e-6_dp) cycle
      if (all(res%displacement(:, n) == 0.0_dp)) cycle
      call check(error, dot_product(res%displacement(1:2, n), x(1:2)) / a, u_exact, 'radial displacement at bore', &
                 rel=0.01_dp)
      if (allocated(error)) return
      checked = checked + 1
    end do
    call check(error, checked > 10, 'bore nodes were checked')
    if (allocated(error)) return
    ! Reactions in the nodal (r, theta, z) systems: inside the quarter no hoop reaction
    ! (axisymmetry); on each symmetry plane the hoop reactions carry the hoop force, the
    ! integral of s_theta over the wall: p a per unit length (Lame), p a h in all; the axial
    ! reactions on z = 0 carry sigma_zz = nu (s_r + s_theta) = 2 nu ca over the quarter
    ! annulus: nu p a^2 pi / 2 in total.
    call check(error, res%has_nodal_systems, 'nodal systems reported')
    if (allocated(error)) return
    ! r is free at every node: its nodal reaction is zero (docs/output-format.md), not the
    ! round-off of rotating the global reaction back (5e-26 N)
    call check(error, maxval(abs(res%reaction_nodal(1, :))), 0.0_dp, 'radial (free) nodal reactions', abs=0.0_dp)
    if (allocated(error)) return
    call check(error, maxval(abs(res%reaction_nodal(2, :)), mask=abs(model%coords(2, :)) > 1.0e-6_dp .and. &
                             abs(model%coords(1, :)) > 1.0e-6_dp), 0.0_dp, 'hoop reactions inside the quarter', &
               abs=1.0e-6_dp * p * a)
    if (allocated(error)) return
    call check(error, abs(sum(res%reaction_nodal(2, :), mask=abs(model%coords(2, :)) < 1.0e-6_dp)), &
               p * a * 50.0_dp, 'hoop force on the plane theta = 0 (N)', rel=0.01_dp)
    if (allocated(error)) return
    call check(error, abs(sum(res%reaction_nodal(3, :), mask=abs(model%coords(3, :)) < 1.0e-9_dp)), &
               nu * p * a**2 * pi / 2.0_dp, 'axial reaction on z = 0 (N)', rel=0.01_dp)
    if (allocated(error)) return
    ! hoop stress at every Gauss point of the elements at the bore against the exact field
    do e_idx = 1, size(model%groups(1)%connectivity, 2), 4
      do g = 1, 27
        q = (e_idx - 1) * 27 + g
        x = gauss_point_position(model, e_idx, g)
        r = hypot(x(1), x(2))
        hoop = hoop_stress(res%groups(1)%stress(:, q), x)
        call check(error, hoop, ca + cb / r**2, 'hoop stress at a Gauss point near the bore', rel=0.01_dp)
        if (allocated(error)) return
      end do
    end do
  end subroutine test_lame

  !> Position of Gauss point g (3x3x3 rule, first direction fastest) of element e of group 1,
  !! from the element's corner nodes by trilinear interpolation (enough to get its radius).
  function gauss_point_position(model, e, g) result(x)
    type(model_t), intent(in) :: model
    integer, intent(in) :: e, g
    real(dp) :: x(3), xi(3), nsh(8)
    real(dp), parameter :: pts(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
    real(dp), parameter :: sgn(3, 8) = reshape([-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, &
                                               1, 1, 1, -1, 1, 1], [3, 8]) * 1.0_dp
    integer :: i, j, k, a
    i = mod(g - 1, 3) + 1
    j = mod((g - 1) / 3, 3) + 1
    k = (g - 1) / 9 + 1
    xi = [pts(i), pts(j), pts(k)]
    do a = 1, 8
      nsh(a) = product(1.0_dp + sgn(:, a) * xi) / 8.0_dp
    end do
    x = matmul(model%coords(:, model%groups(1)%connectivity(1:8, e)), nsh)
  end function gauss_point_position

  pure real(dp) function hoop_stress(s, x)
    real(dp), intent(in) :: s(6), x(3)
    real(dp) :: c, sn
    c = x(1) / hypot(x(1), x(2))
    sn = x(2) / hypot(x(1), x(2))
    hoop_stress = s(1) * sn**2 + s(2) * c**2 - 2.0_dp * s(6) * sn * c
  end function hoop_stress

  !> Timoshenko cantilever: P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6, within 2%.
  subroutine test_cantilever(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp), parameter :: p = 100.0_dp, l = 100.0_dp, h = 10.0_dp, e = 200000.0_dp
    real(dp) :: inertia, g, delta, tip
    integer :: n, count_tip
    call read_deck('test/data/cantilever_hex20.dat', model, error)
    if (allocated(error)) return
    call solve(model, model%solver, res, error)
    if (allocated(error)) return
    inertia = h**4 / 12.0_dp
    g = e / 2.0_dp
    delta = p * l**3 / (3.0_dp * e * inertia) + p * l / (5.0_dp / 6.0_dp * g * h * h)
    tip = 0.0_dp
    count_tip = 0
    do n = 1, model%nnode
      if (abs(model%coords(1, n) - l) > 1.0e-9_dp .or. all(res%displacement(:, n) == 0.0_dp)) cycle
      tip = tip + res%displacement(2, n)
      count_tip = count_tip + 1
    end do
    call check(error, -tip / count_tip, delta, 'mean tip deflection', rel=0.02_dp)
    if (allocated(error)) return
    call check(error, sum(res%reaction(2, :)), p, 'shear reaction at the clamp', rel=1.0e-9_dp)
  end subroutine test_cantilever

  !> test/data/bilinear_load.dat: p = p0 (x / 10) (y / 10) on a 2 x 2 top face, TOTAL = 900 N.
  !! Each consistent nodal force is p0 / 100 times the product of the 1D integrals of the hat
  !! function times the coordinate (25/6, 25, 125/6 at 0, 5, 10), exact with the 2 x 2 rule.
  subroutine test_bilinear_load(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp), parameter :: p0 = 900.0_dp / 25.0_dp, a(3) = [25.0_dp / 6.0_dp, 25.0_dp, 125.0_dp / 6.0_dp]
    integer :: n, i, j
    call read_deck('test/data/bilinear_load.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    do n = 1, model%nnode
      if (abs(model%coords(3, n) - 10.0_dp) > 1.0e-9_dp) cycle
      i = nint(model%coords(1, n) / 5.0_dp) + 1
      j = nint(model%coords(2, n) / 5.0_dp) + 1
      call check(error, res%applied_force(3, n), -p0 / 100.0_dp * a(i) * a(j), 'nodal force at x = ' // &
                 str(model%coords(1, n)) // ', y = ' // str(model%coords(2, n)), rel=1.0e-12_dp)
      if (allocated(error)) return
    end do
    call check(error, sum(res%applied_force(3, :)), -900.0_dp, 'resultant (N)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, sum(res%applied_force(3, :) * model%coords(1, :)) / sum(res%applied_force(3, :)), &
               20.0_dp / 3.0_dp, 'x of the resultant (mm)', rel=1.0e-12_dp)
  end subroutine test_bilinear_load

  !> test/data/traction_components.dat: TRACTION, top, X=3., Z=-100. (no TOTAL=) on the 10 x 10
  !! top face of cube.dat. Its z forces are the nodal forces of cube.dat's PRESSURE VALUE=100,
  !! its x forces 3/100 of those (a uniform traction), and the resultant is t A.
  subroutine test_traction_components(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res, pressure
    integer :: n
    call read_deck('test/data/cube.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', pressure, error)
    if (allocated(error)) return
    call read_deck('test/data/traction_components.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    call check(error, sum(res%applied_force(1, :)), 300.0_dp, 'x resultant (N)', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, sum(res%applied_force(3, :)), -10000.0_dp, 'z resultant (N)', rel=1.0e-12_dp)
    if (allocated(error)) return
    do n = 1, model%nnode
      call check(error, res%applied_force(3, n), pressure%applied_force(3, n), 'z force at node ' // str(n), &
                 abs=1.0e-9_dp)
      if (allocated(error)) return
      call check(error, res%applied_force(1, n), -0.03_dp * pressure%applied_force(3, n), &
                 'x force at node ' // str(n), abs=1.0e-9_dp)
      if (allocated(error)) return
    end do
  end subroutine test_traction_components

  !> test/data/stage_unload.dat: LOAD=1 then LOAD=-0.5 of cube.dat's 100 MPa. A negative LOAD=
  !! used to be taken for "not given" and replaced by the default 0.
  subroutine test_stage_unload(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp), parameter :: p = 100.0_dp, e = 200000.0_dp, l = 10.0_dp
    call read_deck('test/data/stage_unload.dat', model, error)
    if (allocated(error)) return
    call check(error, model%stages(2)%load_fraction, -0.5_dp, 'LOAD= of the second stage', abs=0.0_dp)
    if (allocated(error)) return
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    call check(error, res%displacement(3, 27), -0.5_dp * p * l / e, 'uz at the top corner', rel=1.0e-10_dp)
  end subroutine test_stage_unload

  !> test/data/node_gap.dat: NODE 40 on the 27-node cube leaves 28-39 undefined (they hold the
  !! origin as coordinates); the set at the origin is node 1 alone, and the run is the cube's.
  !! The gap's coordinates were never set: they were whatever the heap held (zero in a fresh
  !! process, NaN here, where freed blocks of the coordinates' size held NaN), written to
  !! /mesh/coordinates, and a NaN there made feps refuse the deck ('node 28 ... not finite').
  subroutine test_node_gap(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    integer :: s
    call dirty_heap(3 * 40)
    call read_deck('test/data/node_gap.dat', model, error)
    if (allocated(error)) return
    call check(error, model%nnode, 40, 'nodes numbered')
    if (allocated(error)) return
    call check(error, all(model%coords(:, 28:39) == 0.0_dp), 'the gap''s nodes 28-39 hold the origin')
    if (allocated(error)) return
    s = model%find_node_set('corner')
    call check(error, size(model%node_sets(s)%nodes) == 1 .and. model%node_sets(s)%nodes(1) == 1, &
               'the set at the origin is node 1 alone')
    if (allocated(error)) return
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    call check(error, res%displacement(3, 27), -100.0_dp * 10.0_dp / 200000.0_dp, 'uz at the top corner', &
               rel=1.0e-10_dp)
  end subroutine test_node_gap

  !> Leave freed heap blocks of n reals (and of the sizes around it) filled with NaN, so that a
  !! later allocation of that size that is read before it is set shows NaN, not the zeros of
  !! fresh memory.
  subroutine dirty_heap(n)
    integer, intent(in) :: n
    type :: block_t
      real(dp), allocatable :: x(:)
    end type block_t
    type(block_t) :: blocks(8, -2:2)
    integer :: i, k
    do k = -2, 2
      do i = 1, size(blocks, 1)
        allocate (blocks(i, k)%x(n + 2 * k))
        blocks(i, k)%x = ieee_value(1.0_dp, ieee_quiet_nan)
      end do
    end do
    do k = -2, 2
      do i = 1, size(blocks, 1)
        deallocate (blocks(i, k)%x)
      end do
    end do
  end subroutine dirty_heap

  !> `feps --check` on a linear deck and on a staged one with element birth: the same DOFs,
  !! matrix and factor (nonzeros and flops of one factorization) as the run, the same total
  !! applied force (the run sums what it applied; the check sums the stages' increments), every
  !! stage's steps counted, and no result file.
  subroutine test_check_only(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: decks(2) = [character(len=32) :: 'test/data/column_tilt.dat', &
                                                'test/data/activate_block.dat']
    type(run_options_t) :: opt
    type(run_summary_t) :: run, chk
    integer :: k
    logical :: exists
    do k = 1, size(decks)
      opt%deck = trim(decks(k))
      opt%solver = 'cholmod'
      opt%output = 'build/test_check_run.h5'
      opt%check_only = .false.
      call run_feps(opt, run, error)
      if (allocated(error)) return
      opt%output = 'build/test_check_only.h5'
      opt%check_only = .true.
      call run_feps(opt, chk, error)
      if (allocated(error)) return
      inquire (file='build/test_check_only.h5', exist=exists)
      call check(error, .not. exists, trim(decks(k)) // ': no result file')
      if (allocated(error)) return
      inquire (file='build/test_check_only.h5.part', exist=exists)
      call check(error, .not. exists, trim(decks(k)) // ': no partial file')
      if (allocated(error)) return
      call check(error, chk%checked_only .and. .not. run%checked_only, 'reported as checked')
      if (allocated(error)) return
      call check(error, chk%dofs, run%dofs, trim(decks(k)) // ': DOFs')
      if (allocated(error)) return
      call check(error, int(chk%matrix_nnz), int(run%matrix_nnz), trim(decks(k)) // ': matrix nonzeros')
      if (allocated(error)) return
      call check(error, int(chk%factor_nnz), int(run%factor_nnz), trim(decks(k)) // ': factor nonzeros')
      if (allocated(error)) return
      call check(error, chk%flops, run%flops, trim(decks(k)) // ': flops of one factorization', rel=1.0e-12_dp)
      if (allocated(error)) return
      call check(error, chk%linear .eqv. run%linear, trim(decks(k)) // ': linear or not')
      if (allocated(error)) return
      if (.not. run%linear) then
        call check(error, chk%steps, run%steps, trim(decks(k)) // ': steps of all stages')
        if (allocated(error)) return
      end if
      call check(error, norm2(chk%applied_force - run%applied_force) <= 1.0e-9_dp * norm2(run%applied_force), &
                 trim(decks(k)) // ': total applied force')
      if (allocated(error)) return
    end do
    call check(error, chk%stages, 2, 'activate_block.dat: two stages')
  end subroutine test_check_only

  !> REPORT, TILT on the cantilever turned onto the z axis: the axis tilt between clamp and tip
  !! is atan(delta / L) with the Timoshenko tip deflection (within 1%), and REPORT, ROTATION of
  !! the tip section gives P L^2 / (2 E I) (within 1%) with the same sign.
  subroutine test_tilt_report(error)
    type(error_t), allocatable, intent(out) :: error
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    real(dp), parameter :: p = 100.0_dp, l = 100.0_dp, h = 10.0_dp, e = 200000.0_dp
    real(dp) :: inertia, delta, tilt, rotation
    inertia = h**4 / 12.0_dp
    delta = p * l**3 / (3.0_dp * e * inertia) + p * l / (5.0_dp / 6.0_dp * e / 2.0_dp * h * h)
    opt%deck = 'test/data/column_tilt.dat'
    opt%output = 'build/test_tilt.h5'
    opt%solver = ''
    call run_feps(opt, summary, error)
    if (allocated(error)) return
    call check(error, size(summary%reports), 2, 'two report lines')
    if (allocated(error)) return
    tilt = angle_of(summary%reports(1))
    rotation = angle_of(summary%reports(2))
    call check(error, tilt, atan(delta / l) * 180.0_dp / pi, 'axis tilt (deg)', rel=0.01_dp)
    if (allocated(error)) return
    call check(error, rotation, p * l**2 / (2.0_dp * e * inertia) * 180.0_dp / pi, 'tip section rotation (deg)', &
               rel=0.01_dp)
  contains
    !> The angle printed after '):' in a report line.
    real(dp) function angle_of(line)
      character(len=*), intent(in) :: line
      integer :: k
      k = index(line, '):')
      read (line(k + 2:), *) angle_of
    end function angle_of
  end subroutine test_tilt_report

  !> The two solvers on the model B deck: displacements equal to 1e-9 relative.
  subroutine test_model_b_solvers(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res_c, res_s
    real(dp) :: diff, scale
    call read_deck('input/modelB/SE1.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', res_c, error)
    if (allocated(error)) return
    call read_deck('input/modelB/SE1.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'skyline', res_s, error)
    if (allocated(error)) return
    scale = maxval(abs(res_c%displacement))
    diff = maxval(abs(res_c%displacement - res_s%displacement))
    call check(error, diff / scale, 0.0_dp, 'max |u_cholmod - u_skyline| / max |u|', abs=1.0e-9_dp)
    if (allocated(error)) return
    call check(error, scale > 0.0_dp, 'nonzero displacements')
  end subroutine test_model_b_solvers

  !> The edge load on each end sums to 1000 kN (in +z at z = 0, -z at z = 2500) and its
  !! peak intensity matches the closed-form integral over the exact annulus within 1%
  !! (the mesh's faces are chords of the circle); the anchor's z reaction vanishes.
  subroutine test_model_b_load(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp) :: f_low, f_high, integral, r, dr, theta0, moment_fe, moment_exact, w
    integer :: n, i
    integer, parameter :: nsimpson = 2000
    call read_deck('input/modelB/SE1.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    f_low = 0.0_dp
    f_high = 0.0_dp
    moment_fe = 0.0_dp
    do n = 1, model%nnode
      if (abs(model%coords(3, n)) < 1.0e-6_dp) then
        f_low = f_low + res%applied_force(3, n)
        moment_fe = moment_fe + res%applied_force(3, n) * model%coords(1, n)
      end if
      if (abs(model%coords(3, n) - 2500.0_dp) < 1.0e-6_dp) f_high = f_high + res%applied_force(3, n)
    end do
    call check(error, f_low, 1.0e6_dp, 'resultant at z = 0 (N)', rel=1.0e-10_dp)
    if (allocated(error)) return
    call check(error, f_high, -1.0e6_dp, 'resultant at z = 2500 (N)', rel=1.0e-10_dp)
    if (allocated(error)) return
    ! Closed form: for a unit peak, integral of (-220 - x)/495 over the part of the half
    ! annulus with x < -220, and its first moment in x; the resultant's x position follows.
    dr = (715.0_dp - 600.0_dp) / nsimpson
    integral = 0.0_dp
    moment_exact = 0.0_dp
    do i = 0, nsimpson
      r = 600.0_dp + i * dr
      w = merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(i, 2) == 1), i == 0 .or. i == nsimpson) * dr / 3.0_dp
      theta0 = acos(-220.0_dp / r)
      integral = integral + w * r * (-220.0_dp * (pi - theta0) + r * sin(theta0)) / 495.0_dp
      ! integral of x (-220 - x) over theta: x = r cos t
      moment_exact = moment_exact + w * r * (-220.0_dp * r * (-sin(theta0)) - r**2 * &
                     ((pi - theta0) / 2.0_dp - sin(2.0_dp * theta0) / 4.0_dp)) / 495.0_dp
    end do
    call check(error, moment_fe / f_low, moment_exact / integral, 'x of the load resultant (mm)', rel=0.01_dp)
    if (allocated(error)) return
    call check(error, maxval(abs(res%reaction(3, :))), 0.0_dp, 'z reaction at the anchor node (N)', &
               abs=1.0e-6_dp * 1.0e6_dp)
  end subroutine test_model_b_load

  !> Table 2.1 as the whole input: counts and a positive smallest Jacobian.
  subroutine test_mesh_only(error)
    type(error_t), allocatable, intent(out) :: error
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    opt%deck = '../shared/benchmarks/table2_1.datain'
    opt%output = ''
    opt%solver = ''
    call run_feps(opt, summary, error)
    if (allocated(error)) return
    call check(error, summary%nodes, 3375, 'nodes')
    if (allocated(error)) return
    call check(error, summary%elements, 2496, 'elements')
    if (allocated(error)) return
    call check(error, summary%mesh_only, 'reported as a mesh')
    if (allocated(error)) return
    call check(error, summary%min_jacobian > 0.0_dp, 'positive Jacobians')
    if (allocated(error)) return
    call check(error, summary%bbox(3, 2), 220.0_dp, 'z extent', rel=1.0e-12_dp)
    if (allocated(error)) return
    call check(error, summary%bbox(1, 1), -100.0_dp, 'x min (r = 100 at theta = 180)', rel=1.0e-12_dp)
  end subroutine test_mesh_only

  !> docs/output-format.md: a bare mesh's block of k nodes other than 8 or 20 is typed nodes<k>
  !! and written; it used to stop the run ('unsupported element type "nodes4"'). The Jacobian
  !! is the hex8 block's alone: a unit cube, 1/8.
  subroutine test_mesh_only_mixed(error)
    type(error_t), allocatable, intent(out) :: error
    type(run_options_t) :: opt
    type(run_summary_t) :: summary
    logical :: exists
    opt%deck = 'test/data/mesh_mixed.datain'
    opt%output = 'build/test_mesh_mixed.h5'
    opt%solver = ''
    call run_feps(opt, summary, error)
    if (allocated(error)) return
    call check(error, summary%mesh_only .and. summary%nodes == 12 .and. summary%elements == 3, &
               'a mesh of 12 nodes and 3 elements: ' // str(summary%nodes) // ', ' // str(summary%elements))
    if (allocated(error)) return
    call check(error, summary%min_jacobian, 0.125_dp, 'smallest Jacobian (the hex8 block)', rel=1.0e-12_dp)
    if (allocated(error)) return
    inquire (file='build/test_mesh_mixed.h5', exist=exists)
    call check(error, exists, 'the mesh written to build/test_mesh_mixed.h5')
  end subroutine test_mesh_only_mixed

  !> Plane-strain compression of a tri6 square against the closed form (3- and 6-point rules).
  subroutine test_plane_strain(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp), parameter :: p = 100.0_dp, e = 200000.0_dp, nu = 0.3_dp, l = 10.0_dp
    character(len=6), parameter :: types(2) = ['tri6  ', 'tri6-6']
    integer :: t, q, n
    do t = 1, 2
      call read_deck('test/data/strip_tri6.dat', model, error)
      if (allocated(error)) return
      model%groups(1)%element_type = trim(types(t))
      call check(error, model%plane_strain, 'read as a plane-strain model')
      if (allocated(error)) return
      call solve(model, 'cholmod', res, error)
      if (allocated(error)) return
      do q = 1, size(res%groups(1)%stress, 2)
        call check(error, res%groups(1)%stress(2, q), -p, 'syy', rel=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, res%groups(1)%stress(3, q), -nu * p, 'szz = nu (sxx + syy)', rel=1.0e-10_dp)
        if (allocated(error)) return
        call check(error, abs(res%groups(1)%stress(1, q)) + abs(res%groups(1)%stress(6, q)), 0.0_dp, &
                   'sxx and sxy', abs=1.0e-9_dp)
        if (allocated(error)) return
      end do
      n = 25   ! corner (10, 10)
      call check(error, res%displacement(2, n), -p * l * (1.0_dp - nu**2) / e, 'uy at the top', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, res%displacement(1, n), nu * (1.0_dp + nu) * p * l / e, 'ux at x = L', rel=1.0e-10_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(res%displacement(3, :))), 0.0_dp, 'uz held', abs=0.0_dp)
      if (allocated(error)) return
    end do
  end subroutine test_plane_strain

  !> The half model with its y = 0 symmetry plane and the full ring under the doubled load:
  !! the same displacements at every node of the half (1e-6 of the largest).
  subroutine test_symmetry(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: half, full
    type(step_result_t) :: rh, rf
    integer :: n, m, match
    real(dp) :: diff, scale
    call read_deck('test/data/symmetry_half.dat', half, error)
    if (allocated(error)) return
    call solve(half, 'cholmod', rh, error)
    if (allocated(error)) return
    call read_deck('test/data/symmetry_full.dat', full, error)
    if (allocated(error)) return
    call solve(full, 'cholmod', rf, error)
    if (allocated(error)) return
    scale = maxval(abs(rh%displacement))
    diff = 0.0_dp
    do n = 1, half%nnode
      match = 0
      do m = 1, full%nnode     ! first node at the same place (the full ring's theta = 360 copies are unused)
        if (all(abs(full%coords(:, m) - half%coords(:, n)) < 1.0e-6_dp)) then
          match = m
          exit
        end if
      end do
      call check(error, match > 0, 'every node of the half is in the full model')
      if (allocated(error)) return
      diff = max(diff, maxval(abs(rh%displacement(:, n) - rf%displacement(:, match))))
    end do
    call check(error, diff / scale, 0.0_dp, 'max |u_half - u_full| / max |u|', abs=1.0e-6_dp)
  end subroutine test_symmetry

  !> Radial displacement at the bore of the plane-strain Lame cylinder against the closed form:
  !! hex20 and the B-bar hex8 within 1% for nu = 0.49 .. 0.4999 and -0.3, -0.9; plain hex8
  !! locks (more than 5% too stiff at nu = 0.4999), which is why hex8b exists.
  subroutine test_locking(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: nus(5) = [0.49_dp, 0.499_dp, 0.4999_dp, -0.3_dp, -0.9_dp]
    character(len=5), parameter :: types(3) = ['hex8 ', 'hex8b', 'hex20']
    integer :: i, t
    real(dp) :: err
    character(len=40) :: what
    do t = 1, 3
      do i = 1, size(nus)
        call lame_error(trim(types(t)), nus(i), err, error)
        if (allocated(error)) return
        write (what, '(a,a,f7.4)') trim(types(t)), ', nu = ', nus(i)
        if (trim(types(t)) == 'hex8') then
          if (nus(i) > 0.4998_dp) then
            call check(error, err < -0.05_dp, trim(what) // ': plain hex8 locks (error below -5%)')
            if (allocated(error)) return
          end if
        else
          call check(error, err, 0.0_dp, trim(what) // ': relative error of u(a)', abs=0.01_dp)
          if (allocated(error)) return
        end if
      end do
    end do
  end subroutine test_locking

  subroutine lame_error(element_type, nu, err, error)
    character(len=*), intent(in) :: element_type
    real(dp), intent(in) :: nu
    real(dp), intent(out) :: err
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp), parameter :: a = 600.0_dp, b = 715.0_dp, p = 10.0_dp, e = 40000.0_dp
    real(dp) :: u_exact, mean
    integer :: count
    if (element_type == 'hex20') then
      call read_deck('test/data/lame_hex20.dat', model, error)
    else
      call read_deck('test/data/lame_hex8.dat', model, error)
    end if
    if (allocated(error)) return
    model%groups(1)%element_type = element_type
    call model%materials(1)%set('nu', nu)
    call solve(model, 'cholmod', res, error)
    if (allocated(error)) return
    u_exact = lame_bore_displacement(a, b, p, e, nu)
    call mean_radial_displacement(model%coords, res%displacement, a, mean, count)
    err = (mean - u_exact) / u_exact
  end subroutine lame_error

  !> PRESSURE p on the bore r = a of the Lame quarter annuli (hex20: parabolic faces; hex8: flat
  !! facets; every node on the circle), theta from 0 to 90 deg, height h: the applied nodal forces
  !! (feps_loads, through the face set selected in cylindrical coordinates) have the resultant
  !! p a h (1, 1, 0) and the moment about the origin p a h^2 / 2 (-1, 1, 0), those of the true
  !! cylinder (t = p e_r: int p e_r a dtheta dz and int z e_z x p e_r a dtheta dz). Exact for the
  !! isoparametric bore too: both depend only on the boundary of the loaded surface, two straight
  !! vertical edges on the circle and two equal arcs at z = 0 and z = h (Stokes). Tolerance 1e-12.
  subroutine test_bore_pressure_resultant(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: decks(2) = [character(len=24) :: 'test/data/lame_hex20.dat', &
                                                'test/data/lame_hex8.dat ']
    real(dp), parameter :: a = 600.0_dp, p = 10.0_dp
    type(model_t) :: model
    type(step_result_t) :: res
    real(dp) :: h, force(3), moment(3), x(3), f(3)
    integer :: k, n
    do k = 1, size(decks)
      call read_deck(trim(decks(k)), model, error)
      if (allocated(error)) return
      call solve(model, 'cholmod', res, error)
      if (allocated(error)) return
      h = maxval(model%coords(3, :)) - minval(model%coords(3, :))
      force = 0.0_dp
      moment = 0.0_dp
      do n = 1, model%nnode
        x = model%coords(:, n)
        f = res%applied_force(:, n)
        force = force + f
        moment = moment + [x(2) * f(3) - x(3) * f(2), x(3) * f(1) - x(1) * f(3), x(1) * f(2) - x(2) * f(1)]
      end do
      call check(error, norm2(force - p * a * h * [1.0_dp, 1.0_dp, 0.0_dp]), 0.0_dp, trim(decks(k)) // &
                 ': resultant p a h (1, 1, 0)', abs=1.0e-12_dp * p * a * h)
      if (allocated(error)) return
      call check(error, norm2(moment - 0.5_dp * p * a * h**2 * [-1.0_dp, 1.0_dp, 0.0_dp]), 0.0_dp, trim(decks(k)) // &
                 ': moment p a h^2 / 2 (-1, 1, 0)', abs=1.0e-12_dp * p * a * h * (a + h))
      if (allocated(error)) return
    end do
  end subroutine test_bore_pressure_resultant

  !> VARY=THETA with ZERO=180, PEAK=270 on the bore of a quarter annulus spanning 180-270 deg
  !! (bore_theta_ramp_q3.dat) must give the nodal forces of the same ramp from 0 to 90 deg on the
  !! quarter spanning 0-90 deg (bore_theta_ramp_q1.dat), turned by 180 deg about z: f3(n) =
  !! (-f1x, -f1y, f1z) node by node (1e-10 of the largest force). And the 0-90 deg load itself:
  !! p(theta) = P theta / 90 deg on r = a, height h, has the resultant P a h (2 / pi)
  !! (pi/2 - 1, 1, 0) (the integral of theta (cos, sin) theta); the nodal forces reproduce it to
  !! the quadrature error of the ramp over the parabolic faces (1e-5 relative).
  !! (The theta of a point used to be atan2's, in (-180, 180]: a ramp given between 180 and 360
  !! deg found every point below ZERO and loaded nothing.)
  subroutine test_theta_ramp_third_quadrant(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: a = 600.0_dp, p = 10.0_dp
    type(model_t) :: model
    type(step_result_t) :: q1, q3
    real(dp) :: h, force(3), expected(3), scale
    call read_deck('test/data/bore_theta_ramp_q1.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', q1, error)
    if (allocated(error)) return
    h = maxval(model%coords(3, :)) - minval(model%coords(3, :))
    force = sum(q1%applied_force, dim=2)
    expected = p * a * h * 2.0_dp / pi * [0.5_dp * pi - 1.0_dp, 1.0_dp, 0.0_dp]
    call check(error, norm2(force - expected), 0.0_dp, 'theta ramp 0-90 deg: resultant', &
               abs=1.0e-5_dp * norm2(expected))
    if (allocated(error)) return
    call read_deck('test/data/bore_theta_ramp_q3.dat', model, error)
    if (allocated(error)) return
    call solve(model, 'cholmod', q3, error)
    if (allocated(error)) return
    scale = maxval(abs(q1%applied_force))
    call check(error, maxval(abs(q3%applied_force(1:2, :) + q1%applied_force(1:2, :))), 0.0_dp, &
               'theta ramp 180-270 deg: x and y nodal forces those of 0-90 deg turned by 180 deg', &
               abs=1.0e-10_dp * scale)
    if (allocated(error)) return
    call check(error, maxval(abs(q3%applied_force(3, :) - q1%applied_force(3, :))), 0.0_dp, &
               'theta ramp 180-270 deg: z nodal forces', abs=1.0e-10_dp * scale)
  end subroutine test_theta_ramp_third_quadrant

  !> The 'cholmod-mixed' solver against 'cholmod' on four decks:
  !! - slide_1dof_unload_is.dat (initial stiffness, 157 iterations on 12 factors): factors
  !!   solved three times or more use their single-precision copy; the iterations are the
  !!   same and the displacements within 1e-7 of the largest (measured: 1.1e-8): each step's
  !!   iterations correct the solves against their double-precision residual, to DELTA1;
  !! - block_shear.dat (ACCELERATION=bfgs): BFGS asks for exact solves, so no copy is made and
  !!   every bit is the double run's;
  !! - sec2_3_4_lift.dat (a stiff interface on soft blocks): its factor's test solve is off by
  !!   0.17, above the tolerance, so it stays in double precision: every bit the same;
  !! - cube.dat (linear: one solve per stage): solved in double precision as 'cholmod'.
  subroutine test_mixed_precision(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: double, mixed
    type(analysis_summary_t) :: sd, sm
    integer :: k
    call run_both('test/data/slide_1dof_unload_is.dat', error)
    if (allocated(error)) return
    call check(error, sm%solver == 'cholmod-mixed', 'the solver: ' // sm%solver)
    if (allocated(error)) return
    call check(error, sm%single_precision_factors > 0, 'factors solved in single precision: ' // &
               str(sm%single_precision_factors))
    if (allocated(error)) return
    call check(error, sm%iterations, sd%iterations, 'iterations')
    if (allocated(error)) return
    do k = 1, size(double%steps)
      associate (ud => double%steps(k)%displacement, um => mixed%steps(k)%displacement)
        call check(error, maxval(abs(um - ud)), 0.0_dp, 'step ' // str(k) // ': displacements', &
                   abs=1.0e-7_dp * maxval(abs(ud)))
      end associate
      if (allocated(error)) return
    end do
    call run_both('test/data/block_shear.dat', error)
    if (allocated(error)) return
    call check(error, sm%single_precision_factors, 0, 'BFGS: no factor solved in single precision')
    if (allocated(error)) return
    call same_bits('BFGS')
    if (allocated(error)) return
    call run_both('test/data/sec2_3_4_lift.dat', error)
    if (allocated(error)) return
    call check(error, sm%precision_fallbacks, 1, 'the ill-conditioned factor kept in double precision')
    if (allocated(error)) return
    call same_bits('an ill-conditioned factor')
    if (allocated(error)) return
    call run_both('test/data/cube.dat', error)
    if (allocated(error)) return
    call check(error, sm%solver == 'cholmod', 'a linear model''s solver: ' // sm%solver)
    if (allocated(error)) return
    call same_bits('a linear model')
  contains
    subroutine run_both(deck, error)
      character(len=*), intent(in) :: deck
      type(error_t), allocatable, intent(out) :: error
      double = all_steps_t()
      mixed = all_steps_t()
      call read_deck(deck, model, error)
      if (.not. allocated(error)) call run_analysis(model, 'cholmod', double, sd, error)
      if (allocated(error)) return
      call read_deck(deck, model, error)
      if (.not. allocated(error)) call run_analysis(model, 'cholmod-mixed', mixed, sm, error)
      if (allocated(error)) return
      call check(error, size(mixed%steps), size(double%steps), deck // ': steps written')
    end subroutine run_both
    subroutine same_bits(what)
      character(len=*), intent(in) :: what
      logical :: same
      integer :: j
      same = .true.
      do j = 1, size(double%steps)
        same = same .and. all(double%steps(j)%displacement == mixed%steps(j)%displacement)
      end do
      call check(error, same, what // ': every step''s displacements bit-identical to the double run''s')
    end subroutine same_bits
  end subroutine test_mixed_precision

end module test_analysis
