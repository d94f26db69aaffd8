!> Explicit lists in the deck (issue 25 item 1): test/data/lists_lame_hex20.dat is the Lame
!! cylinder of lame_hex20.dat with its mesh as NODES and ELEMENTS tables and its supports on an
!! NSET LIST, the nodes and elements renumbered (gaps, reverse order; make_lists_decks.py). The
!! same model: every node's displacement equals that of the DATAIN deck's node at the same
!! coordinates to 1e-12 of the largest displacement (measured 2.0e-13: the other numbering gives
!! another elimination order, so the two solutions differ by rounding only).
module test_lists
  use feps_kinds, only: dp
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_model, only: model_t
  use feps_deck, only: read_deck
  use feps_incremental_analysis, only: run_analysis, analysis_summary_t
  use feps_test_observers, only: all_steps_t
  use feps_element_catalog, only: new_solid_element
  use feps_solid_element, only: solid_element_t
  implicit none
  private

  public :: collect_lists

contains

  !> Collect the suite.
  subroutine collect_lists(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest('tables: the ids are kept', test_ids), &
      new_unittest('tables: the displacements of the DATAIN deck', test_same_displacements), &
      new_unittest('a cube on rollers in a turned Cartesian system: uniaxial stress', test_rotated_rollers), &
      new_unittest('FORCE, LIST and DISPLACE, LIST rows: the loads on node sets', test_listed_loads), &
      new_unittest('MODE=TOTAL: pulled to 0.1, then back to 0.05; 10 N, then 4 N', test_mode_total), &
      new_unittest('face numbers: the CalculiX faces of every solid', test_calculix_faces), &
      new_unittest('FSET LIST (element, face): the forces of the box FSET, hex8', test_faces_hex8), &
      new_unittest('FSET LIST (element, face): the forces of the box FSET, hex20', test_faces_hex20), &
      new_unittest('FSET LIST (element, face): the forces of the box FSET, tet10', test_faces_tet10), &
      new_unittest('FSET LIST (element, face): the forces of the box FSET, wedge15', test_faces_wedge15), &
      new_unittest('FSET ELSET=, FACE=: the forces of the box FSET, hex8 cube', test_elset_faces)]
  end subroutine collect_lists

  !> Node numbers index the mesh (the gaps are unused nodes); element ids are kept per group.
  subroutine test_ids(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    integer :: nel
    call read_deck('test/data/lists_lame_hex20.dat', model, error)
    if (allocated(error)) return
    ! 459 lattice nodes: the largest number is 3 (459 - 1) + 5
    call check(error, model%nnode, 3 * 458 + 5, 'the largest node number is the mesh size')
    if (allocated(error)) return
    call check(error, allocated(model%groups(1)%element_ids), 'element ids kept')
    if (allocated(error)) return
    nel = size(model%groups(1)%element_ids)
    call check(error, nel, 32, 'elements of the table')
    if (allocated(error)) return
    call check(error, model%groups(1)%element_ids(1), 101, 'first row''s id')
    if (allocated(error)) return
    call check(error, model%groups(1)%element_ids(nel), 2 * (nel - 1) + 101, 'last row''s id')
    if (allocated(error)) return
    call check(error, size(model%node_sets(1)%nodes), 459, 'the NSET LIST holds every node')
  end subroutine test_ids

  subroutine test_same_displacements(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: datain, lists
    type(all_steps_t) :: obs_d, obs_l
    type(analysis_summary_t) :: summary
    real(dp) :: worst, scale
    integer :: i, j, matched
    call read_deck('test/data/lame_hex20.dat', datain, error)
    if (allocated(error)) return
    call read_deck('test/data/lists_lame_hex20.dat', lists, error)
    if (allocated(error)) return
    call run_analysis(datain, 'cholmod', obs_d, summary, error)
    if (allocated(error)) return
    call run_analysis(lists, 'cholmod', obs_l, summary, error)
    if (allocated(error)) return
    associate (ud => obs_d%steps(size(obs_d%steps))%displacement, ul => obs_l%steps(size(obs_l%steps))%displacement)
      scale = maxval(abs(ud))
      worst = 0.0_dp
      matched = 0
      do i = 1, datain%nnode
        do j = 1, lists%nnode
          ! the table's coordinates are the DATAIN ones printed to 17 digits: equal
          if (all(lists%coords(:, j) == datain%coords(:, i))) then
            if (mod(j - 5, 3) /= 0) then
              call test_failed(error, 'a gap node matched a lattice node')
              return
            end if
            worst = max(worst, maxval(abs(ul(:, j) - ud(:, i))))
            matched = matched + 1
            exit
          end if
        end do
      end do
      call check(error, matched, datain%nnode, 'every DATAIN node has its table node')
      if (allocated(error)) return
      call check(error, worst, 0.0_dp, 'largest difference of a displacement', abs=1.0e-12_dp * scale)
    end associate
  end subroutine test_same_displacements

  !> test/data/lists_rotated_cube.dat: a cube in CSYS 4 (turned 30 degrees about z, shifted),
  !! on rollers in that system (a nodal system, as the cylindrical ones) and pulled along its
  !! x' axis by s = 100 MPa: u' = (s x', -nu s y', -nu s z') / E exactly (hex8 holds a uniform
  !! stress), turned back to global axes; 1e-12 of the largest displacement (measured 4.5e-15).
  subroutine test_rotated_rollers(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    real(dp), parameter :: s = 100.0_dp, young = 200000.0_dp, nu = 0.3_dp
    real(dp) :: axes(3, 3), local(3), expected(3), worst, scale
    integer :: n
    call read_deck('test/data/lists_rotated_cube.dat', model, error)
    if (allocated(error)) return
    ! the turned axes, independently of the deck reader
    axes(:, 1) = [cos(30.0_dp * acos(-1.0_dp) / 180.0_dp), sin(30.0_dp * acos(-1.0_dp) / 180.0_dp), 0.0_dp]
    axes(:, 2) = [-axes(2, 1), axes(1, 1), 0.0_dp]
    axes(:, 3) = [0.0_dp, 0.0_dp, 1.0_dp]
    call check(error, maxval(abs(model%systems(4)%axes - axes)), 0.0_dp, 'the axes of CSYS 4', abs=1.0e-15_dp)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    associate (u => obs%steps(size(obs%steps))%displacement)
      scale = s * 10.0_dp / young
      worst = 0.0_dp
      do n = 1, model%nnode
        local = matmul(transpose(axes), model%coords(:, n) - [100.0_dp, 50.0_dp, 0.0_dp])
        expected = matmul(axes, [s * local(1), -nu * s * local(2), -nu * s * local(3)] / young)
        worst = max(worst, maxval(abs(u(:, n) - expected)))
      end do
      call check(error, worst, 0.0_dp, 'largest difference from the closed form', abs=1.0e-12_dp * scale)
    end associate
  end subroutine test_rotated_rollers

  !> test/data/lists_loads_rows.dat gives lists_loads_sets.dat's FORCE and DISPLACE on node sets
  !! as rows per node (one node's force in two rows that add up): the same applied forces and
  !! displacements (measured: equal to the last bit; held to 1e-14 of the largest), and the
  !! prescribed corner at its value.
  subroutine test_listed_loads(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: sets, rows
    type(all_steps_t) :: obs_s, obs_r
    type(analysis_summary_t) :: summary
    call read_deck('test/data/lists_loads_sets.dat', sets, error)
    if (allocated(error)) return
    call read_deck('test/data/lists_loads_rows.dat', rows, error)
    if (allocated(error)) return
    call run_analysis(sets, 'cholmod', obs_s, summary, error)
    if (allocated(error)) return
    call run_analysis(rows, 'cholmod', obs_r, summary, error)
    if (allocated(error)) return
    associate (a => obs_s%steps(1), b => obs_r%steps(1))
      call check(error, maxval(abs(a%applied_force - b%applied_force)), 0.0_dp, 'applied forces', abs=1.0e-14_dp * 100.0_dp)
      if (allocated(error)) return
      call check(error, sum(b%applied_force(3, :)), -900.0_dp, 'nine nodes of 100 N down', rel=1.0e-15_dp)
      if (allocated(error)) return
      call check(error, maxval(abs(a%displacement - b%displacement)), 0.0_dp, 'displacements', &
                 abs=1.0e-14_dp * maxval(abs(a%displacement)))
      if (allocated(error)) return
      call check(error, b%displacement(1, 27), 0.001_dp, 'the corner''s prescribed x', rel=1.0e-15_dp)
    end associate
  end subroutine test_listed_loads

  !> test/data/lists_mode_total.dat, by hand: the top nodes (z = 10) end stage one at uz = 0.1
  !! and stage two, DISPLACE MODE=TOTAL 0.05, at 0.05 (its increment -0.05); node 27 carries
  !! -10 N in x after stage one and, FORCE LIST MODE=TOTAL -4, -4 N after stage two, the other
  !! eight side nodes still -10: -84 N in all. Rounding only: 1e-14 relative.
  subroutine test_mode_total(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: model
    type(all_steps_t) :: obs
    type(analysis_summary_t) :: summary
    integer :: n, top
    call read_deck('test/data/lists_mode_total.dat', model, error)
    if (allocated(error)) return
    call run_analysis(model, 'cholmod', obs, summary, error)
    if (allocated(error)) return
    call check(error, size(obs%steps), 2, 'the last step of each stage')
    if (allocated(error)) return
    top = 0
    do n = 1, model%nnode
      if (model%coords(3, n) /= 10.0_dp) cycle
      top = top + 1
      call check(error, obs%steps(1)%displacement(3, n), 0.1_dp, 'uz at the end of stage one', rel=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, obs%steps(2)%displacement(3, n), 0.05_dp, 'uz at the end of stage two (MODE=TOTAL)', &
                 rel=1.0e-14_dp)
      if (allocated(error)) return
    end do
    call check(error, top, 9, 'top nodes checked')
    if (allocated(error)) return
    call check(error, obs%steps(1)%applied_force(1, 27), -10.0_dp, 'node 27 after stage one', rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, obs%steps(2)%applied_force(1, 27), -4.0_dp, 'node 27 after stage two (MODE=TOTAL)', &
               rel=1.0e-14_dp)
    if (allocated(error)) return
    call check(error, sum(obs%steps(2)%applied_force(1, :)), -84.0_dp, 'the side''s force after stage two', &
               rel=1.0e-14_dp)
  end subroutine test_mode_total

  !> FSET LIST's face numbers are the element files' (feps_hex8.f90 ...): they must be those of
  !! the CalculiX manual (section 6.2, "element types"), written out here from it as corner
  !! nodes: C3D8/C3D20 S1 = 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3, S5 = 3-7-8-4,
  !! S6 = 4-8-5-1; C3D4/C3D10 S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1; C3D6/C3D15
  !! S1 = 1-2-3, S2 = 4-5-6, S3 = 1-2-5-4, S4 = 2-3-6-5, S5 = 3-1-4-6; tri6 edges 1-2, 2-3, 3-1.
  !! The same corners (as a set: feps winds every face outwards) for each face number.
  subroutine test_calculix_faces(error)
    type(error_t), allocatable, intent(out) :: error
    integer, parameter :: hex(4, 6) = reshape([1, 2, 3, 4, 5, 8, 7, 6, 1, 5, 6, 2, 2, 6, 7, 3, 3, 7, 8, 4, &
                                               4, 8, 5, 1], [4, 6])
    integer, parameter :: tet(4, 4) = reshape([1, 2, 3, 0, 1, 4, 2, 0, 2, 4, 3, 0, 3, 4, 1, 0], [4, 4])
    integer, parameter :: wedge(4, 5) = reshape([1, 2, 3, 0, 4, 5, 6, 0, 1, 2, 5, 4, 2, 3, 6, 5, 3, 1, 4, 6], [4, 5])
    integer, parameter :: tri(4, 3) = reshape([1, 2, 0, 0, 2, 3, 0, 0, 3, 1, 0, 0], [4, 3])
    call compare('hex8', hex, error)
    if (.not. allocated(error)) call compare('hex20', hex, error)
    if (.not. allocated(error)) call compare('tet4', tet, error)
    if (.not. allocated(error)) call compare('tet10', tet, error)
    if (.not. allocated(error)) call compare('wedge6', wedge, error)
    if (.not. allocated(error)) call compare('wedge15', wedge, error)
    if (.not. allocated(error)) call compare('tri6', tri, error)
  contains
    subroutine compare(type_name, corners, error)
      character(len=*), intent(in) :: type_name
      integer, intent(in) :: corners(:, :)
      type(error_t), allocatable, intent(out) :: error
      class(solid_element_t), allocatable :: solid
      integer, allocatable :: fn(:)
      integer :: f, k, ncorner
      call new_solid_element(type_name, solid, error)
      if (allocated(error)) return
      call check(error, solid%nfaces(), size(corners, 2), type_name // ': faces')
      if (allocated(error)) return
      do f = 1, size(corners, 2)
        ncorner = count(corners(:, f) > 0)
        fn = solid%face_nodes(f)
        do k = 1, ncorner
          if (.not. any(fn(1:ncorner) == corners(k, f))) then
            call test_failed(error, type_name // ': face ' // char(48 + f) // ' is not CalculiX''s')
            return
          end if
        end do
      end do
    end subroutine compare
  end subroutine test_calculix_faces

  subroutine test_faces_hex8(error)
    type(error_t), allocatable, intent(out) :: error
    call same_face_forces('hex8', error)
  end subroutine test_faces_hex8

  subroutine test_faces_hex20(error)
    type(error_t), allocatable, intent(out) :: error
    call same_face_forces('hex20', error)
  end subroutine test_faces_hex20

  subroutine test_faces_tet10(error)
    type(error_t), allocatable, intent(out) :: error
    call same_face_forces('tet10', error)
  end subroutine test_faces_tet10

  subroutine test_faces_wedge15(error)
    type(error_t), allocatable, intent(out) :: error
    call same_face_forces('wedge15', error)
  end subroutine test_faces_wedge15

  !> test/data/lists_faces_<type>.dat: lame_<type>.dat with its bore pressure on an FSET LIST
  !! of (element, face) rows (make_lists_decks.py faces): the same faces, the same nodal
  !! forces (measured equal to the last bit; held to 1e-14 of p a h) and displacements.
  subroutine same_face_forces(type_name, error)
    character(len=*), intent(in) :: type_name
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: box, rows
    type(all_steps_t) :: obs_b, obs_r
    type(analysis_summary_t) :: summary
    call read_deck('test/data/lame_' // type_name // '.dat', box, error)
    if (allocated(error)) return
    call read_deck('test/data/lists_faces_' // type_name // '.dat', rows, error)
    if (allocated(error)) return
    call run_analysis(box, 'cholmod', obs_b, summary, error)
    if (allocated(error)) return
    call run_analysis(rows, 'cholmod', obs_r, summary, error)
    if (allocated(error)) return
    call check(error, all(box%face_sets(1)%element == rows%face_sets(1)%element) .and. &
               all(box%face_sets(1)%face == rows%face_sets(1)%face), type_name // ': the same faces')
    if (allocated(error)) return
    call check(error, maxval(abs(obs_b%steps(1)%applied_force - obs_r%steps(1)%applied_force)), 0.0_dp, &
               type_name // ': nodal forces', abs=1.0e-14_dp * 10.0_dp * 600.0_dp * 50.0_dp)
    if (allocated(error)) return
    call check(error, size(rows%face_sets(1)%face) > 0 .and. sum(abs(obs_r%steps(1)%applied_force)) > 0.0_dp, &
               type_name // ': faces loaded')
  end subroutine same_face_forces

  !> test/data/lists_elset_cube.dat: cube.dat's top face set as face 2 of an ELSET of its upper
  !! layer: the same faces, the same nodal forces to the last bit.
  subroutine test_elset_faces(error)
    type(error_t), allocatable, intent(out) :: error
    type(model_t) :: box, listed
    type(all_steps_t) :: obs_b, obs_l
    type(analysis_summary_t) :: summary
    call read_deck('test/data/cube.dat', box, error)
    if (allocated(error)) return
    call read_deck('test/data/lists_elset_cube.dat', listed, error)
    if (allocated(error)) return
    call run_analysis(box, 'cholmod', obs_b, summary, error)
    if (allocated(error)) return
    call run_analysis(listed, 'cholmod', obs_l, summary, error)
    if (allocated(error)) return
    call check(error, all(listed%face_sets(1)%face == 2) .and. size(listed%face_sets(1)%face) == 4, &
               'face 2 of four elements')
    if (allocated(error)) return
    call check(error, maxval(abs(obs_b%steps(1)%applied_force - obs_l%steps(1)%applied_force)), 0.0_dp, &
               'nodal forces', abs=0.0_dp)
  end subroutine test_elset_faces

end module test_lists
