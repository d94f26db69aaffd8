!> Explicit lists in the deck (issue 25): the node table (NODES), element tables (ELEMENTS) and
!! id lists (NSET, name, LIST). A table is its keyword line, then one row a line: the rows are
!! continuation lines of the record (docs/input-format.md), so every field keeps its line and
!! an error names the line and field at fault. Whether a node that an element or a set names
!! is defined is known only once every node is read: finish_model checks it (names the field).
!! The rows of FORCE/DISPLACE LIST and FSET LIST, which fill the model's loads and face sets,
!! are read where those records are (feps_deck: read_listed_values, read_face_rows).
module feps_deck_tables
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_records, only: record_t, nfields, field_text, field_line
  use feps_deck_fields, only: get_real, get_int, parse_range_int, check_option_keys, get_csys_option
  use feps_coordinate_system, only: csys_cartesian
  use feps_datain, only: max_mesh_nodes, max_mesh_elements
  use feps_model, only: model_t
  implicit none
  private

  public :: first_row_field, read_nodes_table, read_elements_table, read_id_list

contains

  !> The first field of a table's rows: the first field after the keyword line (nfields + 1
  !! when the table has no row).
  pure integer function first_row_field(rec) result(first)
    type(record_t), intent(in) :: rec
    first = 2
    do while (first <= nfields(rec))
      if (field_line(rec, first) > rec%line) return
      first = first + 1
    end do
  end function first_row_field

  !> NODES [, CSYS=n]: rows `id, c1, c2, c3` (or `id, x, y` with z = 0 for a plane mesh).
  !! Returns each row's node id, global coordinates (3, n), line and id field.
  subroutine read_nodes_table(rec, model, ids, coords, lines, fields, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    integer, allocatable, intent(out) :: ids(:), lines(:)
    integer, allocatable, intent(out) :: fields(:)   !! each row's id field
    real(dp), allocatable, intent(out) :: coords(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer :: first, i, j, n, cs, line, ncoord, d
    real(dp) :: c(3)
    type(record_t) :: head

    first = first_row_field(rec)
    head = keyword_line(rec, first)
    call check_option_keys(head, 2, error, allowed=['CSYS'], expected='CSYS=n (the rows follow on lines of their own)')
    if (allocated(error)) return
    if (first > nfields(rec)) then
      call input_error(error, rec%file, rec%line, 'NODES has no row (its rows follow on lines of their own)')
      return
    end if
    call get_csys_option(head, model, 'CSYS', csys_cartesian, cs, error)
    if (allocated(error)) return
    ! count the rows (one a line) to size the arrays once
    n = 0
    do i = first, nfields(rec)
      if (i == first) then
        n = 1
      else if (field_line(rec, i) /= field_line(rec, i - 1)) then
        n = n + 1
      end if
    end do
    allocate (ids(n), lines(n), coords(3, n), fields(n))
    i = first
    do j = 1, n
      line = field_line(rec, i)
      ncoord = 0
      do while (i + 1 + ncoord <= nfields(rec))
        if (field_line(rec, i + 1 + ncoord) /= line) exit
        ncoord = ncoord + 1
      end do
      if (ncoord < 2 .or. ncoord > 3) then
        call input_error(error, rec%file, line, 'a NODES row is "id, x, y, z" (or "id, x, y" in a plane mesh): ' // &
                         'this one has ' // str(ncoord + 1) // ' fields', min(i + 1 + ncoord, i + 4))
        return
      end if
      call get_int(rec, i, 1, max_mesh_nodes, ids(j), error, 'node number')
      if (allocated(error)) return
      c = 0.0_dp
      do d = 1, ncoord
        call get_real(rec, i + d, c(d), error)
        if (allocated(error)) return
      end do
      i = i + 1 + ncoord
      coords(:, j) = model%systems(cs)%to_global(c)
      lines(j) = line
      fields(j) = i - 1 - ncoord
    end do
  end subroutine read_nodes_table

  !> ELEMENTS, group: rows `id, n1, ..., nk`, k the nodes of the group's type; a row may go on
  !! over the next lines (Abaqus splits C3D20 rows), so fields are counted, not lines. Returns
  !! the group, the ids, the connectivity (k, n) and the field of each row's id.
  subroutine read_elements_table(rec, model, group, ids, connectivity, id_field, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    integer, intent(out) :: group
    integer, allocatable, intent(out) :: ids(:), connectivity(:, :), id_field(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: first, k, n, j, i, nrow_fields

    group = 0
    first = first_row_field(rec)
    if (first /= 3) then
      if (first < 3) then
        call input_error(error, rec%file, rec%line, 'ELEMENTS needs the name of its group on its own line ' // &
                         '(ELEMENTS, group), then the rows', 2)
      else
        call input_error(error, rec%file, rec%line, 'ELEMENTS takes only the name of its group on its line; "' // &
                         field_text(rec, 3) // '" is one too many (the rows follow on lines of their own)', 3)
      end if
      return
    end if
    group = model%find_group(field_text(rec, 2))
    if (group == 0) then
      call input_error(error, rec%file, rec%line, 'undefined element group "' // field_text(rec, 2) // &
                       '" (its GROUP record comes before its ELEMENTS)', 2)
      return
    end if
    k = model%groups(group)%element%nnodes
    nrow_fields = nfields(rec) - first + 1
    if (nrow_fields == 0) then
      call input_error(error, rec%file, rec%line, 'ELEMENTS, ' // field_text(rec, 2) // ' has no row')
      return
    end if
    n = (nrow_fields + k) / (k + 1)
    if (mod(nrow_fields, k + 1) /= 0) then
      i = first + (n - 1) * (k + 1)
      call input_error(error, rec%file, field_line(rec, nfields(rec)), 'element ' // field_text(rec, i) // &
                       ' of group ' // model%groups(group)%name // ' has ' // str(mod(nrow_fields, k + 1) - 1) // &
                       ' nodes; its type ' // model%groups(group)%element_type // ' has ' // str(k), nfields(rec) + 1)
      return
    end if
    allocate (ids(n), connectivity(k, n), id_field(n))
    do j = 1, n
      i = first + (j - 1) * (k + 1)
      id_field(j) = i
      call get_int(rec, i, 1, max_mesh_elements, ids(j), error, 'element number')
      if (allocated(error)) return
      do i = 1, k
        call get_int(rec, id_field(j) + i, 1, max_mesh_nodes, connectivity(i, j), error, 'node number')
        if (allocated(error)) return
      end do
    end do
  end subroutine read_elements_table

  !> Ids listed from field `first` on: each field an id or a range `a:b`, each in 1..`last`.
  !! Returns the ids in order and the field each came from.
  subroutine read_id_list(rec, first, last, ids, fields, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: first, last
    integer, allocatable, intent(out) :: ids(:), fields(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: i, id, n, m
    integer, allocatable :: from(:), to(:)

    allocate (from(nfields(rec)), to(nfields(rec)))
    n = 0
    do i = first, nfields(rec)
      call parse_range_int(field_text(rec, i), 1, last, from(i), to(i), error, rec, i)
      if (allocated(error)) return
      if (to(i) < from(i)) then
        call input_error(error, rec%file, field_line(rec, i), 'empty range "' // field_text(rec, i) // &
                         '" (from > to)', i)
        return
      end if
      n = n + (to(i) - from(i) + 1)
    end do
    allocate (ids(n), fields(n))
    m = 0
    do i = first, nfields(rec)
      do id = from(i), to(i)
        m = m + 1
        ids(m) = id
        fields(m) = i
      end do
    end do
  end subroutine read_id_list

  !> The record cut to its keyword line (fields 1 .. first - 1).
  pure function keyword_line(rec, first) result(head)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: first
    type(record_t) :: head
    head%file = rec%file
    head%line = rec%line
    head%fields = rec%fields(1:first - 1)
  end function keyword_line

end module feps_deck_tables
