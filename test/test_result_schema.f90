!> The result schema (src/model/feps_result_schema.f90) against the manual, and its two fields
!! added through it: stress_cyl (and nodal_stress_cyl) and point_state.
module test_result_schema
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check
  use feps_result_schema, only: result_fields
  use feps_h5_testing, only: run_and_open, close_and_delete, read_real, read_int, file_text, string_attribute, &
                              int_attribute
  use hdf5, only: hid_t, h5lexists_f
  use feps_solid_element, only: solid_element_t
  use feps_element_catalog, only: new_solid_element
  implicit none
  private

  public :: collect_result_schema

  real(dp), parameter :: a = 600.0_dp, b = 715.0_dp, p = 10.0_dp, nu = 0.2_dp

contains

  !> Collect the suite.
  subroutine collect_result_schema(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('docs/output-format.md has a row for every field, with its components', test_manual), &
      new_unittest('applied_force of the Lame cylinder: the bore pressure, balanced by the reactions', &
                   test_applied_force), &
      new_unittest('stress_cyl of the hex20 Lame cylinder against the closed form', test_stress_cyl), &
      new_unittest('nodal_stress_cyl at the bore of the hex20 Lame cylinder', test_nodal_stress_cyl), &
      new_unittest('point_weights of the hex20 Lame cylinder add up to its volume', test_point_weights), &
      new_unittest('point_state of a concrete cantilever past its tensile strength', test_point_state), &
      new_unittest('model B SE1: the resolved node and face sets', test_sets), &
      new_unittest('model B SE1: its FIX records as /constraints', test_constraints)]
  end subroutine collect_result_schema

  !> Every field of the schema has its row `/steps/<NNNN>/<name>...` in the manual's table of
  !! datasets, and a field with fixed components names them there.
  subroutine test_manual(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text, row
    integer :: k, at, eol
    text = file_text('docs/output-format.md')
    do k = 1, size(result_fields)
      associate (field => result_fields(k))
        at = index(text, '| `/steps/<NNNN>/' // trim(field%name) // '/')
        if (at == 0) at = index(text, '| `/steps/<NNNN>/' // trim(field%name) // '`')
        call check(error, at > 0, 'docs/output-format.md has a row for field ' // trim(field%name))
        if (allocated(error)) return
        eol = index(text(at:), new_line('a'))
        row = text(at:at + eol - 1)
        if (len_trim(field%components) > 0) then
          call check(error, index(row, '`' // trim(field%components) // '`') > 0, 'its row names the components `' // &
                     trim(field%components) // '` of ' // trim(field%name))
          if (allocated(error)) return
        end if
      end associate
    end do
  end subroutine test_manual

  !> test/data/lame_hex20.dat with the default fields: applied_force sums to the bore pressure's
  !! resultant p a h (1, 1, 0) (exact for the isoparametric bore, test_analysis: 1e-12) and the
  !! reactions balance it (1e-9 of p a h).
  subroutine test_applied_force(error)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: file_id
    real(dp), allocatable :: applied(:, :), reaction(:, :), x(:, :)
    real(dp) :: h, total(3)
    call run_and_open('test/data/lame_hex20.dat', 'schema_applied', file_id, error)
    if (allocated(error)) return
    call read_real(file_id, '/steps/0001/applied_force', applied, error)
    if (.not. allocated(error)) call read_real(file_id, '/steps/0001/reaction', reaction, error)
    if (.not. allocated(error)) call read_real(file_id, '/mesh/coordinates', x, error)
    if (.not. allocated(error)) call check(error, string_attribute(file_id, '/steps/0001/applied_force', &
                                                                     'components') == 'fx fy fz', 'its components')
    call close_and_delete(file_id, 'schema_applied')
    if (allocated(error)) return
    h = maxval(x(3, :)) - minval(x(3, :))
    total = sum(applied, dim=2)
    call check(error, norm2(total - p * a * h * [1.0_dp, 1.0_dp, 0.0_dp]), 0.0_dp, 'resultant p a h (1, 1, 0)', &
               abs=1.0e-12_dp * p * a * h)
    if (allocated(error)) return
    call check(error, norm2(total + sum(reaction, dim=2)), 0.0_dp, 'the reactions balance it', abs=1.0e-9_dp * p * a * h)
  end subroutine test_applied_force

  !> test/data/lame_hex20.dat with stress_cyl (about system 3, the global z axis): at every
  !! Gauss point srr and stt follow Lame's s_r = A - B / r^2 and s_t = A + B / r^2 within the
  !! hex20 discretisation error (5e-3 p and 1e-3 p; measured 2.4e-3 p, steepest at the bore,
  !! and 6.1e-4 p), szz = nu (srr + stt) (plane strain, to round-off), the shear components
  !! vanish (1e-4 p; measured 2.5e-5 p), and the trace equals that of the Cartesian stresses
  !! (1e-12: the rotation keeps invariants).
  subroutine test_stress_cyl(error)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: file_id
    real(dp), allocatable :: cyl(:, :), cart(:, :), xg(:, :)
    real(dp) :: ca, cb, r
    integer :: q
    call run_and_open('test/data/lame_hex20.dat', 'schema_cyl', file_id, error, fields='stress,stress_cyl')
    if (allocated(error)) return
    call read_real(file_id, '/steps/0001/stress_cyl/wall', cyl, error)
    if (.not. allocated(error)) call read_real(file_id, '/steps/0001/stress/wall', cart, error)
    if (.not. allocated(error)) call read_real(file_id, '/mesh/groups/wall/points', xg, error)
    if (.not. allocated(error)) call check(error, string_attribute(file_id, '/steps/0001/stress_cyl/wall', &
                                                                     'components') == 'srr stt szz stz srz srt', &
                                           'stress_cyl components')
    call close_and_delete(file_id, 'schema_cyl')
    if (allocated(error)) return
    ca = p * a**2 / (b**2 - a**2)
    cb = p * a**2 * b**2 / (b**2 - a**2)
    do q = 1, size(cyl, 2)
      r = hypot(xg(1, q), xg(2, q))
      call check(error, cyl(1, q), ca - cb / r**2, 'srr at a Gauss point', abs=5.0e-3_dp * p)
      if (allocated(error)) return
      call check(error, cyl(2, q), ca + cb / r**2, 'stt at a Gauss point', abs=1.0e-3_dp * p)
      if (allocated(error)) return
      call check(error, cyl(3, q), nu * (cyl(1, q) + cyl(2, q)), 'szz = nu (srr + stt)', abs=1.0e-12_dp * p)
      if (allocated(error)) return
      call check(error, maxval(abs(cyl(4:6, q))), 0.0_dp, 'shear stresses stz srz srt', abs=1.0e-4_dp * p)
      if (allocated(error)) return
      call check(error, sum(cyl(1:3, q)), sum(cart(1:3, q)), 'trace kept', abs=1.0e-12_dp * p)
      if (allocated(error)) return
    end do
  end subroutine test_stress_cyl

  !> /mesh/groups/wall/point_weights of test/data/lame_hex20.dat (a quarter of the annulus
  !! a..b, 50 mm long, 16 hex20 around it): one positive weight per Gauss point, adding up to
  !! pi/4 (b^2 - a^2) 50 within 1e-5 (the elements' quadratic edges only approximate their
  !! 11.25 deg arcs, a relative error of order h^4; measured 3.1e-6 short).
  subroutine test_point_weights(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp), parameter :: pi = acos(-1.0_dp), length = 50.0_dp
    integer(hid_t) :: file_id
    real(dp), allocatable :: w(:, :), xg(:, :)
    call run_and_open('test/data/lame_hex20.dat', 'schema_weights', file_id, error)
    if (allocated(error)) return
    call read_real(file_id, '/mesh/groups/wall/point_weights', w, error)
    if (.not. allocated(error)) call read_real(file_id, '/mesh/groups/wall/points', xg, error)
    if (.not. allocated(error)) call check(error, string_attribute(file_id, '/mesh/groups/wall/point_weights', &
                                                                     'components') == 'weight', &
                                           'point_weights components')
    call close_and_delete(file_id, 'schema_weights')
    if (allocated(error)) return
    call check(error, size(w, 1) == 1 .and. size(w, 2) == size(xg, 2), 'one weight per point')
    if (allocated(error)) return
    call check(error, minval(w) > 0.0_dp, 'every weight is positive')
    if (allocated(error)) return
    call check(error, sum(w), pi / 4.0_dp * (b**2 - a**2) * length, 'the weights add up to the volume', rel=1.0e-5_dp)
  end subroutine test_point_weights

  !> nodal_stress_cyl of the hex20 Lame cylinder: stt at the bore nodes against s_t(a) within
  !! 5e-4 (as test_stress_recovery's hoop stress rotated by hand: measured 2.2e-4).
  subroutine test_nodal_stress_cyl(error)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: file_id
    real(dp), allocatable :: cyl(:, :), x(:, :)
    integer, allocatable :: connectivity(:, :)
    real(dp) :: ca, cb
    integer :: n, checked
    call run_and_open('test/data/lame_hex20.dat', 'schema_nodal_cyl', file_id, error, fields='nodal_stress_cyl')
    if (allocated(error)) return
    call read_real(file_id, '/steps/0001/nodal_stress_cyl/wall', cyl, error)
    if (.not. allocated(error)) call read_real(file_id, '/mesh/coordinates', x, error)
    if (.not. allocated(error)) call read_int(file_id, '/mesh/groups/wall/connectivity', connectivity, error)
    call close_and_delete(file_id, 'schema_nodal_cyl')
    if (allocated(error)) return
    ca = p * a**2 / (b**2 - a**2)
    cb = p * a**2 * b**2 / (b**2 - a**2)
    checked = 0
    do n = 1, size(x, 2)
      ! the lattice's face-centre nodes belong to no hex20 (filled with the column's minimum)
      if (abs(hypot(x(1, n), x(2, n)) - a) > 1.0e-6_dp .or. .not. any(connectivity == n)) cycle
      call check(error, cyl(2, n), ca + cb / a**2, 'nodal stt at the bore', rel=5.0e-4_dp)
      if (allocated(error)) return
      checked = checked + 1
    end do
    call check(error, checked, 43, 'bore nodes of the hex20 mesh')
  end subroutine test_nodal_stress_cyl

  !> test/data/beam_point_state.dat (beam_tension_cap.dat writing every step: a concrete
  !! cantilever, tip pushed down 1 mm in 5 steps;
  !! beam theory puts the first yield, ft = 5 MPa at the clamp's top fibre, at a tip
  !! displacement of 0.21 mm): after step 1 (0.2 mm) every Gauss point is elastic (state 0);
  !! at the end the points next to the clamp have left the elastic state (the tension cap, 1
  !! or 3) and those of the last 20 mm, where the beam-theory stress of the end step stays
  !! below ft / 2, are elastic.
  subroutine test_point_state(error)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: file_id
    real(dp), allocatable :: first(:, :), last(:, :), xg(:, :)
    integer, allocatable :: state(:)
    call run_and_open('test/data/beam_point_state.dat', 'schema_state', file_id, error)
    if (allocated(error)) return
    call read_real(file_id, '/steps/0001/point_state/beam', first, error)
    if (.not. allocated(error)) call read_real(file_id, '/steps/0005/point_state/beam', last, error)
    if (.not. allocated(error)) call read_real(file_id, '/mesh/groups/beam/points', xg, error)
    call close_and_delete(file_id, 'schema_state')
    if (allocated(error)) return
    call check(error, size(first, 1), 1, 'one component (state)')
    if (allocated(error)) return
    call check(error, all(nint(first) == 0), 'step 1, below the first yield: every point elastic')
    if (allocated(error)) return
    state = nint(last(1, :))
    call check(error, any(state /= 0 .and. xg(1, :) < 20.0_dp .and. xg(2, :) > 15.0_dp), &
               'step 5: points of the top fibre next to the clamp are not elastic')
    if (allocated(error)) return
    call check(error, all(state == 0 .or. xg(1, :) < 180.0_dp), 'step 5: the last 20 mm stay elastic')
    if (allocated(error)) return
    call check(error, all(state == 0 .or. state == 1 .or. state == 3), &
               'states are 0 (elastic), 1 (yielding) or 3 (tension cut-off)')
  end subroutine test_point_state

  !> input/modelB/SE1.dat: /sets/nodes/anchor is the one soil node at r = 2000, theta = 0,
  !! z = 1250; /sets/faces/end_low holds the 54 pipe faces (2 through the wall x 27 around) whose
  !! nodes (by the element catalog's face lists) all lie at z = 0, and end_high those at z = 2500.
  subroutine test_sets(error)
    type(error_t), allocatable, intent(out) :: error
    integer(hid_t) :: file_id
    real(dp), allocatable :: x(:, :)
    integer, allocatable :: anchor(:, :), low(:, :), high(:, :), connectivity(:, :)
    class(solid_element_t), allocatable :: hex8
    call run_and_open('input/modelB/SE1.dat', 'schema_sets', file_id, error)
    if (allocated(error)) return
    call read_real(file_id, '/mesh/coordinates', x, error)
    if (.not. allocated(error)) call read_int(file_id, '/sets/nodes/anchor', anchor, error)
    if (.not. allocated(error)) call read_int(file_id, '/sets/faces/end_low', low, error)
    if (.not. allocated(error)) call read_int(file_id, '/sets/faces/end_high', high, error)
    if (.not. allocated(error)) call read_int(file_id, '/mesh/groups/pipe/connectivity', connectivity, error)
    if (.not. allocated(error)) call check(error, string_attribute(file_id, '/sets/faces/end_low', 'group') == 'pipe', &
                                           'the face set names its group')
    call close_and_delete(file_id, 'schema_sets')
    if (allocated(error)) return
    call check(error, size(anchor), 1, 'one anchor node')
    if (allocated(error)) return
    call check(error, norm2(x(:, anchor(1, 1)) - [2000.0_dp, 0.0_dp, 1250.0_dp]), 0.0_dp, 'the anchor node''s position', &
               abs=1.0e-9_dp)
    if (allocated(error)) return
    call new_solid_element('hex8', hex8, error)
    if (allocated(error)) return
    call check_faces(low, 0.0_dp)
    if (allocated(error)) return
    call check_faces(high, 2500.0_dp)
  contains
    subroutine check_faces(faces, z)
      integer, intent(in) :: faces(:, :)
      real(dp), intent(in) :: z
      integer :: k
      call check(error, size(faces, 2), 54, 'faces at z = end')
      if (allocated(error)) return
      call check(error, size(faces, 1), 2, 'element and face per row')
      if (allocated(error)) return
      do k = 1, size(faces, 2)
        call check(error, maxval(abs(x(3, connectivity(hex8%face_nodes(faces(2, k)), faces(1, k))) - z)), 0.0_dp, &
                   'the face''s nodes lie on the end', abs=1.0e-9_dp)
        if (allocated(error)) return
      end do
    end subroutine check_faces
  end subroutine test_sets

  !> input/modelB/SE1.dat's three FIX records (lines 55-57: soil_outer X, Y; symmetry Y; anchor
  !! Z; global system) as /constraints/0001-0004, one per direction, in the deck's order, with
  !! their sets, directions, kind, stage and source line; nothing more.
  subroutine test_constraints(error)
    type(error_t), allocatable, intent(out) :: error
    character(len=*), parameter :: sets(4) = [character(len=10) :: 'soil_outer', 'soil_outer', 'symmetry', 'anchor']
    integer, parameter :: dofs(4) = [1, 2, 2, 3], lines(4) = [55, 55, 56, 57]
    integer(hid_t) :: file_id
    character(len=:), allocatable :: path, source
    integer :: k
    logical :: more
    call run_and_open('input/modelB/SE1.dat', 'schema_constraints', file_id, error)
    if (allocated(error)) return
    do k = 1, 4
      path = '/constraints/000' // achar(iachar('0') + k)
      call check(error, string_attribute(file_id, path, 'set') == trim(sets(k)), path // ': set ' // trim(sets(k)))
      if (.not. allocated(error)) call check(error, int_attribute(file_id, path, 'dof'), dofs(k), path // ': dof')
      if (.not. allocated(error)) call check(error, string_attribute(file_id, path, 'kind') == 'fix', path // ': kind fix')
      if (.not. allocated(error)) call check(error, int_attribute(file_id, path, 'csys'), 2, path // ': global system')
      if (.not. allocated(error)) call check(error, int_attribute(file_id, path, 'active_from'), 1, path // ': stage 1 on')
      if (.not. allocated(error)) then
        source = string_attribute(file_id, path, 'source')
        call check(error, index(source, 'SE1.dat:' // achar(iachar('0') + lines(k) / 10) // &
                                achar(iachar('0') + mod(lines(k), 10))) > 0, path // ': source ' // source)
      end if
      if (allocated(error)) exit
    end do
    if (.not. allocated(error)) then
      call h5lexists_f(file_id, '/constraints/0005', more, k)
      call check(error, .not. more, 'no fifth constraint')
    end if
    call close_and_delete(file_id, 'schema_constraints')
  end subroutine test_constraints

end module test_result_schema
