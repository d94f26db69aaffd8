!> Reader for DATAIN meshes (thesis Table 2.1; grammar in SPEC section 2).
!!
!! A mesh is a sequence of blocks, each opened by an `A` record and closed by `E`; a further
!! `E` ends the mesh. Node numbers continue across node blocks and element numbers across
!! element blocks; a mesh read into a `datain_mesh_t` that already holds blocks is appended to.
!!
!! Node block: `A, c, x1, x2[, x3]` gives the block's coordinate system `c` (1 = 2D Cartesian
!! x,y with z = 0; 2 = 3D Cartesian; 3 = cylindrical r, theta [deg], z about global z; c > 3 a
!! system the deck defined, from the `systems` array) and the first node. `%, n, d1, d2[, d3]`
!! (2 increments for a 2D system, 3 otherwise):
!! - n > 0: all nodes generated so far in the block are copied n-1 more times, copy j shifted
!!   by j*d; this opens a new direction (n counts the nodes along it, the first included);
!! - n < 0: the current direction is continued by |n| more layers, each shifted by d further
!!   from the last one (the first layer of the direction is the one copied);
!! - n = 0 is an error, and so is n < 0 before any direction was opened.
!! The first direction varies fastest. Nodes are generated in the block's own system and
!! converted to global Cartesian coordinates when the block closes.
!!
!! Element block: `A, k, i1, ..., ik` gives k nodes per element and the first element.
!! `%, n, s1, s2, inc` (`*` for s1 means slot 1, for s2 slot k; 1 <= s1 <= s2 <= k):
!! - n > 0: all elements generated so far in the block are copied n-1 more times, copy j
!!   adding j*inc to the node numbers in slots s1..s2; this opens a new direction;
!! - n < 0 (feps's reading, the thesis has no example): the current direction is continued
!!   by |n| more copies of its first layer, each adding inc once more to slots s1..s2 on top
!!   of the offsets the direction already reached;
!! - n = 0 is an error, and so is n < 0 before any direction was opened.
!!
!! Telling the blocks apart from the `A` record, with m fields after the second:
!! - it reads as a node block if c is a known system and m is its number of coordinates
!!   (2 for a 2D system, 3 otherwise), and as an element block if m = k >= 1;
!! - if a field after the second contains '.', 'e', 'E', 'd' or 'D' it is coordinates, so a
!!   node block (its system must exist and m must match);
!! - otherwise, when only one reading fits it is taken; when both fit (`A, 3, 75, 0, 0`) it is
!!   an element block if the mesh already has nodes, else a node block.
!!
!! Node numbers in elements are checked by `datain_check`, to be called once every block is
!! read (a deck may add nodes after an element block that uses them).
module feps_datain
  use feps_kinds, only: dp, i8
  use feps_error, only: error_t, input_error, fatal_error, str, err_input
  use feps_coordinate_system, only: coordinate_system_t
  use feps_records, only: record_t, read_records, keyword, nfields, field_text, field_real, &
                          field_int, field_line, record_error, is_integer_text
  implicit none
  private

  public :: element_block_t, datain_mesh_t
  public :: datain_read_block, datain_read_file, datain_read_records, is_datain_record, datain_check
  public :: max_mesh_nodes, max_mesh_elements

  !> Most nodes and elements a mesh may have. Far beyond what a machine can factor (a 3D mesh
  !! of 20 million nodes needs terabytes for its Cholesky factor), so a mistyped repeat count
  !! is an input error at once instead of filling the machine's memory with generated nodes.
  integer, parameter :: max_mesh_nodes = 20000000
  integer, parameter :: max_mesh_elements = 20000000

  !> Elements of one `A ... E` element block.
  type :: element_block_t
    integer :: nodes_per_element = 0
    integer, allocatable :: connectivity(:, :)     !! (nodes_per_element, nelem)
    character(len=:), allocatable :: file          !! file of the block's A record
    integer :: line = 0                            !! line of the block's A record
  end type element_block_t

  !> A DATAIN mesh: nodes in global Cartesian coordinates and the element blocks.
  type :: datain_mesh_t
    integer :: nnode = 0
    real(dp), allocatable :: coords(:, :)          !! (3, nnode), global Cartesian
    type(element_block_t), allocatable :: blocks(:)
  contains
    procedure :: nelements     !! elements in all blocks
  end type datain_mesh_t

contains

  !> Total number of elements in all blocks.
  pure integer function nelements(self)
    class(datain_mesh_t), intent(in) :: self
    integer :: b
    nelements = 0
    if (.not. allocated(self%blocks)) return
    do b = 1, size(self%blocks)
      nelements = nelements + size(self%blocks(b)%connectivity, 2)
    end do
  end function nelements

  !> True for the DATAIN records A, % and E.
  pure logical function is_datain_record(rec)
    type(record_t), intent(in) :: rec
    character(len=:), allocatable :: key
    key = keyword(rec)
    is_datain_record = key == 'A' .or. key == '%' .or. key == 'E'
  end function is_datain_record

  !> Read a whole DATAIN file: blocks until the final `E`, appended to `mesh`.
  !! Errors: the file's read errors (cannot open, empty file, empty field) and those of
  !! `datain_read_records`.
  subroutine datain_read_file(path, systems, mesh, error)
    character(len=*), intent(in) :: path
    type(coordinate_system_t), intent(in) :: systems(:)
    type(datain_mesh_t), intent(inout) :: mesh
    type(error_t), allocatable, intent(out) :: error
    type(record_t), allocatable :: records(:)
    call read_records(path, records, error)
    if (allocated(error)) return
    call datain_read_records(records, systems, mesh, error)
  end subroutine datain_read_file

  !> Read a whole DATAIN mesh held in records (a file's, or lines built in memory): blocks
  !! until the final `E`, appended to `mesh`. Errors: records other than A or E between
  !! blocks, records that end before the final `E` (truncated), records after the final `E`,
  !! no records at all, and the errors of `datain_read_block`.
  pure subroutine datain_read_records(records, systems, mesh, error)
    type(record_t), intent(in) :: records(:)
    type(coordinate_system_t), intent(in) :: systems(:)
    type(datain_mesh_t), intent(inout) :: mesh
    type(error_t), allocatable, intent(out) :: error
    integer :: pos, nrec

    nrec = size(records)
    if (nrec == 0) then
      call fatal_error(error, err_input, 'DATAIN mesh: empty file (no records)')
      return
    end if
    pos = 1
    do
      if (pos > nrec) then
        call input_error(error, records(nrec)%file, last_line(records(nrec)), &
                         'truncated file: the mesh is not closed by a final E record')
        return
      end if
      select case (keyword(records(pos)))
      case ('A')
        call datain_read_block(records, pos, systems, mesh, error)
        if (allocated(error)) return
      case ('E')
        call check_close_record(records(pos), error)
        if (allocated(error)) return
        pos = pos + 1
        exit
      case default
        call record_error(error, records(pos), "unknown record '" // field_text(records(pos), 1) // &
                          "' in a DATAIN mesh: expected A (a block) or E (end of mesh)", 1)
        return
      end select
    end do
    if (pos <= nrec) then
      call record_error(error, records(pos), "record '" // field_text(records(pos), 1) // &
                        "' after the final E record of the mesh", 1)
    end if
  end subroutine datain_read_records

  !> Read one block: records(pos) is its `A` record; on return pos is the record after its
  !! `E`. The block's nodes or elements are appended to `mesh`.
  pure subroutine datain_read_block(records, pos, systems, mesh, error)
    type(record_t), intent(in) :: records(:)
    integer, intent(inout) :: pos
    type(coordinate_system_t), intent(in) :: systems(:)
    type(datain_mesh_t), intent(inout) :: mesh
    type(error_t), allocatable, intent(out) :: error
    logical :: node_block

    if (pos < 1 .or. pos > size(records)) then
      if (size(records) > 0) then
        call input_error(error, records(size(records))%file, last_line(records(size(records))), &
                         'truncated file: expected an A record opening a DATAIN block')
      else
        call input_error(error, '(no file)', 0, 'expected an A record opening a DATAIN block')
      end if
      return
    end if
    if (keyword(records(pos)) /= 'A') then
      call record_error(error, records(pos), "expected an A record opening a DATAIN block, got '" // &
                        field_text(records(pos), 1) // "'", 1)
      return
    end if
    call classify_block(records(pos), systems, mesh%nnode > 0, node_block, error)
    if (allocated(error)) return
    if (node_block) then
      call read_node_block(records, pos, systems, mesh, error)
    else
      call read_element_block(records, pos, mesh, error)
    end if
  end subroutine datain_read_block

  !> Every element node number within 1..nnode; the error names the element block's file and
  !! line (its A record), the element number (counted over all blocks) and the slot.
  pure subroutine datain_check(mesh, error)
    type(datain_mesh_t), intent(in) :: mesh
    type(error_t), allocatable, intent(out) :: error
    integer :: b, e, s, first_element, node
    if (.not. allocated(mesh%blocks)) return
    first_element = 0
    do b = 1, size(mesh%blocks)
      associate (blk => mesh%blocks(b))
        do e = 1, size(blk%connectivity, 2)
          do s = 1, blk%nodes_per_element
            node = blk%connectivity(s, e)
            if (node < 1 .or. node > mesh%nnode) then
              call input_error(error, blk%file, blk%line, 'element ' // str(first_element + e) // &
                               ' (element ' // str(e) // ' of the block), slot ' // str(s) // &
                               ': node number ' // str(node) // ' out of range 1..' // str(mesh%nnode))
              return
            end if
          end do
        end do
        first_element = first_element + size(blk%connectivity, 2)
      end associate
    end do
  end subroutine datain_check

  ! ---- private ----

  !> Decide from an A record whether it opens a node block (rules in the module header).
  pure subroutine classify_block(rec, systems, mesh_has_nodes, node_block, error)
    type(record_t), intent(in) :: rec
    type(coordinate_system_t), intent(in) :: systems(:)
    logical, intent(in) :: mesh_has_nodes
    logical, intent(out) :: node_block
    type(error_t), allocatable, intent(out) :: error
    integer :: c, m, i, need
    logical :: has_real, fits_node, fits_element

    node_block = .false.
    call field_int(rec, 2, c, error, -huge(1), huge(1))
    if (allocated(error)) return
    m = nfields(rec) - 2
    has_real = .false.
    do i = 3, nfields(rec)
      if (scan(rec%fields(i)%text, '.eEdD') > 0) has_real = .true.
    end do
    need = 0
    if (c >= 1 .and. c <= size(systems)) need = systems(c)%ncoords()
    fits_node = need > 0 .and. m == need
    fits_element = c >= 1 .and. m == c

    if (has_real) then
      if (need == 0) then
        call record_error(error, rec, 'unknown coordinate system ' // str(c) // &
                          ' (known: 1..' // str(size(systems)) // ')', 2)
      else if (.not. fits_node) then
        call record_error(error, rec, 'wrong number of fields: coordinate system ' // str(c) // &
                          ' needs ' // str(need) // ' coordinates after it, got ' // str(m))
      else
        node_block = .true.
      end if
    else if (fits_node .and. fits_element) then
      node_block = .not. mesh_has_nodes
    else if (fits_node) then
      node_block = .true.
    else if (fits_element) then
      node_block = .false.
    else if (need == 0 .and. (m == 2 .or. m == 3)) then
      ! coordinates after a number that is no system: most likely a bad system number
      call record_error(error, rec, 'unknown coordinate system ' // str(c) // &
                        ' (known: 1..' // str(size(systems)) // ')', 2)
    else
      call record_error(error, rec, 'wrong number of fields: an element block needs ' // &
                        str(max(c, 1)) // ' node numbers after k = ' // str(c) // &
                        ', a node block 2 or 3 coordinates after its coordinate system; got ' // &
                        str(m) // ' fields')
    end if
  end subroutine classify_block

  !> Read a node block from its A record through its E record.
  pure subroutine read_node_block(records, pos, systems, mesh, error)
    type(record_t), intent(in) :: records(:)
    integer, intent(inout) :: pos
    type(coordinate_system_t), intent(in) :: systems(:)
    type(datain_mesh_t), intent(inout) :: mesh
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: local(:, :)
    real(dp) :: shift(3), step(3), reached(3)
    integer :: c, nc, n, npts, layer, count, i, j, k, first_pos
    logical :: ok

    first_pos = pos
    call field_int(records(pos), 2, c, error, 1, size(systems))
    if (allocated(error)) return
    nc = systems(c)%ncoords()
    allocate (local(3, 64))
    local(:, 1) = 0.0_dp
    do i = 1, nc
      call field_real(records(pos), 2 + i, local(i, 1), error)
      if (allocated(error)) return
    end do
    npts = 1
    layer = 0           ! nodes in the first layer of the current direction (0: none opened)
    reached = 0.0_dp    ! shift of the current direction's last layer from its first

    do
      pos = pos + 1
      if (pos > size(records)) then
        call truncated_block(records, first_pos, error)
        return
      end if
      select case (keyword(records(pos)))
      case ('E')
        call check_close_record(records(pos), error)
        if (allocated(error)) return
        pos = pos + 1
        exit
      case ('%')
        call read_repeat(records(pos), n, error)
        if (allocated(error)) return
        if (nfields(records(pos)) /= 2 + nc) then
          call record_error(error, records(pos), 'wrong number of fields: a node repeat in system ' // &
                            str(c) // ' is %, n and ' // str(nc) // ' increments; got ' // &
                            str(nfields(records(pos))) // ' fields')
          return
        end if
        step = 0.0_dp
        do i = 1, nc
          call field_real(records(pos), 2 + i, step(i), error)
          if (allocated(error)) return
        end do
        if (n > 0) then
          layer = npts
          reached = 0.0_dp
        else if (layer == 0) then
          call record_error(error, records(pos), 'negative repeat count with no direction to continue', 2)
          return
        end if
        count = merge(n - 1, -n, n > 0)
        call make_room(records(pos), mesh%nnode + npts, layer, count, 'nodes', max_mesh_nodes, error)
        if (allocated(error)) return
        call grow_real(local, npts + layer * count, ok)
        if (.not. ok) then
          call record_error(error, records(pos), 'cannot allocate memory for the nodes of this repeat', 2)
          return
        end if
        do j = 1, count
          shift = reached + j * step
          do k = 1, layer
            local(:, npts + k) = local(:, k) + shift
          end do
          npts = npts + layer
        end do
        reached = reached + count * step
      case default
        call unknown_in_block(records(pos), records(first_pos), error)
        return
      end select
    end do

    call resize_coords(mesh, mesh%nnode + npts)
    do k = 1, npts
      mesh%coords(:, mesh%nnode + k) = systems(c)%to_global(local(:, k))
    end do
    mesh%nnode = mesh%nnode + npts
  end subroutine read_node_block

  !> Read an element block from its A record through its E record.
  pure subroutine read_element_block(records, pos, mesh, error)
    type(record_t), intent(in) :: records(:)
    integer, intent(inout) :: pos
    type(datain_mesh_t), intent(inout) :: mesh
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: conn(:, :), reached(:), offset(:)
    integer :: k, n, nel, layer, count, s1, s2, inc, i, j, e, first_pos
    logical :: ok

    first_pos = pos
    call field_int(records(pos), 2, k, error, 1, nfields(records(pos)) - 2)
    if (allocated(error)) return
    allocate (conn(k, 64), reached(k), offset(k))
    do i = 1, k
      call field_int(records(pos), 2 + i, conn(i, 1), error, 1, max_mesh_nodes, 'node number')
      if (allocated(error)) return
    end do
    nel = 1
    layer = 0        ! elements in the first layer of the current direction (0: none opened)
    reached = 0      ! per-slot offset of the current direction's last layer from its first

    do
      pos = pos + 1
      if (pos > size(records)) then
        call truncated_block(records, first_pos, error)
        return
      end if
      select case (keyword(records(pos)))
      case ('E')
        call check_close_record(records(pos), error)
        if (allocated(error)) return
        pos = pos + 1
        exit
      case ('%')
        call read_repeat(records(pos), n, error)
        if (allocated(error)) return
        if (nfields(records(pos)) /= 5) then
          call record_error(error, records(pos), 'wrong number of fields: an element repeat is ' // &
                            '%, n, s1, s2, inc; got ' // str(nfields(records(pos))) // ' fields')
          return
        end if
        call read_slot(records(pos), 3, 1, k, s1, error)
        if (allocated(error)) return
        call read_slot(records(pos), 4, k, k, s2, error)
        if (allocated(error)) return
        if (s2 < s1) then
          call record_error(error, records(pos), 'last slot ' // str(s2) // ' before first slot ' // &
                            str(s1), 4)
          return
        end if
        call field_int(records(pos), 5, inc, error, -max_mesh_nodes, max_mesh_nodes, 'increment')
        if (allocated(error)) return
        if (n > 0) then
          layer = nel
          reached = 0
        else if (layer == 0) then
          call record_error(error, records(pos), 'negative repeat count with no direction to continue', 2)
          return
        end if
        count = merge(n - 1, -n, n > 0)
        call make_room(records(pos), mesh%nelements() + nel, layer, count, 'elements', &
                       max_mesh_elements, error)
        if (allocated(error)) return
        ! the largest shift of a node number, checked wide before the copies add it up
        if (maxval(abs(int(reached(s1:s2), i8) + int(count, i8) * inc)) > max_mesh_nodes) then
          call record_error(error, records(pos), 'this repeat would shift node numbers by ' // &
                            str(maxval(abs(int(reached(s1:s2), i8) + int(count, i8) * inc))) // &
                            ', beyond the largest node number feps reads (' // str(max_mesh_nodes) // ')', 5)
          return
        end if
        call grow_int(conn, nel + layer * count, ok)
        if (.not. ok) then
          call record_error(error, records(pos), 'cannot allocate memory for the elements of this repeat', 2)
          return
        end if
        do j = 1, count
          offset = reached
          offset(s1:s2) = offset(s1:s2) + j * inc
          do e = 1, layer
            conn(:, nel + e) = conn(:, e) + offset
          end do
          nel = nel + layer
        end do
        reached(s1:s2) = reached(s1:s2) + count * inc
      case default
        call unknown_in_block(records(pos), records(first_pos), error)
        return
      end select
    end do

    call append_block(mesh, k, conn(:, :nel), records(first_pos)%file, records(first_pos)%line)
  end subroutine read_element_block

  pure subroutine append_block(mesh, k, conn, file, line)
    type(datain_mesh_t), intent(inout) :: mesh
    integer, intent(in) :: k
    integer, intent(in) :: conn(:, :)
    character(len=*), intent(in) :: file
    integer, intent(in) :: line
    type(element_block_t), allocatable :: blocks(:)
    integer :: b, nb
    nb = 0
    if (allocated(mesh%blocks)) nb = size(mesh%blocks)
    allocate (blocks(nb + 1))
    do b = 1, nb
      call move_alloc(mesh%blocks(b)%connectivity, blocks(b)%connectivity)
      call move_alloc(mesh%blocks(b)%file, blocks(b)%file)
      blocks(b)%nodes_per_element = mesh%blocks(b)%nodes_per_element
      blocks(b)%line = mesh%blocks(b)%line
    end do
    blocks(nb + 1)%nodes_per_element = k
    blocks(nb + 1)%connectivity = conn
    blocks(nb + 1)%file = file
    blocks(nb + 1)%line = line
    call move_alloc(blocks, mesh%blocks)
  end subroutine append_block

  !> Repeat count n of a % record (field 2): an integer other than zero, |n| within the mesh's
  !! size limit (so that -n and n - 1 are safe).
  pure subroutine read_repeat(rec, n, error)
    type(record_t), intent(in) :: rec
    integer, intent(out) :: n
    type(error_t), allocatable, intent(out) :: error
    call field_int(rec, 2, n, error, -max(max_mesh_nodes, max_mesh_elements), max(max_mesh_nodes, max_mesh_elements), &
                   'repeat count')
    if (allocated(error)) return
    if (n == 0) call record_error(error, rec, 'zero repeat count', 2)
  end subroutine read_repeat

  !> A slot number in 1..k, or `*` meaning `star_value`.
  pure subroutine read_slot(rec, i, star_value, k, slot, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: i, star_value, k
    integer, intent(out) :: slot
    type(error_t), allocatable, intent(out) :: error
    if (field_text(rec, i) == '*') then
      slot = star_value
      return
    end if
    if (.not. is_integer_text(field_text(rec, i))) then
      call record_error(error, rec, "expected a slot number or '*', got '" // field_text(rec, i) // "'", i)
      slot = 0
      return
    end if
    call field_int(rec, i, slot, error, 1, k, 'slot')
    if (allocated(error)) return
    if (slot < 1 .or. slot > k) call record_error(error, rec, 'slot ' // str(slot) // &
                                                   ' out of range 1..' // str(k), i)
  end subroutine read_slot

  !> An E record has no fields after the keyword.
  pure subroutine check_close_record(rec, error)
    type(record_t), intent(in) :: rec
    type(error_t), allocatable, intent(out) :: error
    if (nfields(rec) /= 1) call record_error(error, rec, 'wrong number of fields: E takes no fields; got ' // &
                                             str(nfields(rec)) // ' fields', 2)
  end subroutine check_close_record

  pure subroutine unknown_in_block(rec, opening, error)
    type(record_t), intent(in) :: rec, opening
    type(error_t), allocatable, intent(out) :: error
    if (keyword(rec) == 'A') then
      call record_error(error, rec, 'A record inside a block: the block opened at line ' // &
                        str(opening%line) // ' is not closed by E', 1)
    else
      call record_error(error, rec, "unknown record '" // field_text(rec, 1) // &
                        "' inside a DATAIN block (opened at line " // str(opening%line) // &
                        '): expected % or E', 1)
    end if
  end subroutine unknown_in_block

  pure subroutine truncated_block(records, first_pos, error)
    type(record_t), intent(in) :: records(:)
    integer, intent(in) :: first_pos
    type(error_t), allocatable, intent(out) :: error
    associate (last => records(size(records)))
      call input_error(error, last%file, last_line(last), 'truncated file: the block opened at line ' // &
                       str(records(first_pos)%line) // ' is not closed by E')
    end associate
  end subroutine truncated_block

  !> The line a record ends on.
  pure integer function last_line(rec)
    type(record_t), intent(in) :: rec
    last_line = field_line(rec, nfields(rec))
  end function last_line

  !> coords becomes (3, nnode) exactly, keeping the first mesh%nnode nodes.
  pure subroutine resize_coords(mesh, nnode)
    type(datain_mesh_t), intent(inout) :: mesh
    integer, intent(in) :: nnode
    real(dp), allocatable :: coords(:, :)
    allocate (coords(3, nnode))
    if (mesh%nnode > 0) coords(:, :mesh%nnode) = mesh%coords(:, :mesh%nnode)
    call move_alloc(coords, mesh%coords)
  end subroutine resize_coords

  !> Error unless a repeat adding `count` copies of `layer` items to the mesh's `have` keeps
  !! their number within `limit`.
  pure subroutine make_room(rec, have, layer, count, what, limit, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: have, layer, count, limit
    character(len=*), intent(in) :: what
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: total
    total = int(have, i8) + int(layer, i8) * int(count, i8)
    if (total > int(limit, i8)) then
      call record_error(error, rec, 'repeat count too large: the mesh would have ' // str(total) // &
                        ' ' // what // ', more than feps reads (' // str(limit) // ')', 2)
    end if
  end subroutine make_room

  !> Make room for at least `needed` columns, keeping the contents; `ok` false if memory ran out.
  pure subroutine grow_real(a, needed, ok)
    real(dp), allocatable, intent(inout) :: a(:, :)
    integer, intent(in) :: needed
    logical, intent(out) :: ok
    real(dp), allocatable :: bigger(:, :)
    integer :: stat
    ok = .true.
    if (size(a, 2) >= needed) return
    allocate (bigger(size(a, 1), max(needed, min(2 * int(size(a, 2), i8), int(huge(1), i8)))), stat=stat)
    ok = stat == 0
    if (.not. ok) return
    bigger(:, :size(a, 2)) = a
    call move_alloc(bigger, a)
  end subroutine grow_real

  pure subroutine grow_int(a, needed, ok)
    integer, allocatable, intent(inout) :: a(:, :)
    integer, intent(in) :: needed
    logical, intent(out) :: ok
    integer, allocatable :: bigger(:, :)
    integer :: stat
    ok = .true.
    if (size(a, 2) >= needed) return
    allocate (bigger(size(a, 1), max(needed, min(2 * int(size(a, 2), i8), int(huge(1), i8)))), stat=stat)
    ok = stat == 0
    if (.not. ok) return
    bigger(:, :size(a, 2)) = a
    call move_alloc(bigger, a)
  end subroutine grow_int

end module feps_datain
