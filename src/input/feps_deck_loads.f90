!> The deck's support and load records: FIX and RELEASE, DISPLACE, FORCE, PRESTRESS, and
!! PRESSURE and TRACTION with their variations. Before the first STAGE record a record is a
!! reference scaled by each stage's LOAD=; after one it belongs to that stage.
module feps_deck_loads
  use feps_strings, only: to_upper
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_records, only: record_t, keyword, nfields, field_text, field_line, get_option
  use feps_coordinate_system, only: csys_cartesian, csys_cylindrical
  use feps_element_catalog, only: family_bar
  use feps_model, only: model_t, constraint_t, nodal_load_t, face_load_t, load_pressure, load_traction, prestress_t
  use feps_deck_fields, only: key_value, check_option_keys, option_real, dof_index, dof_names, get_csys_option, option_text, &
                              require_fields, parse_real
  implicit none
  private

  public :: read_fix, read_displace, read_force, read_prestress, read_face_load, read_gravity, read_geostatic, read_mode

contains

  !> FIX, set, dof [, dof ...] [, CSYS=n]: dofs X Y Z (Cartesian) or R T Z (cylindrical), or ALL.
  subroutine read_fix(rec, model, stage, release, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer, intent(in) :: stage         !! 0 before any STAGE record: held in every stage
    logical, intent(in) :: release       !! RELEASE: free the DOFs from this stage on
    type(error_t), allocatable, intent(out) :: error
    integer :: iset, cs, i, dof, from, csys_field
    character(len=:), allocatable :: f

    if (release .and. stage <= 1) then
      call input_error(error, rec%file, field_line(rec, 1), &
                       'RELEASE frees supports from a stage on: put it after the ' // &
                       'STAGE record of a later stage than the first (in the first stage, leave the FIX out)', 1)
      return
    end if
    from = max(stage, 1)
    csys_field = 0
    call require_fields(rec, 3, error)
    if (allocated(error)) return
    call get_node_set(rec, model, iset, error)
    if (allocated(error)) return
    call get_csys_option(rec, model, 'CSYS', csys_cartesian, cs, error)
    if (allocated(error)) return
    do i = 3, nfields(rec)
      f = to_upper(field_text(rec, i))
      if (index(f, '=') > 0) then
        if (f(:index(f, '=') - 1) == 'CSYS') then
          csys_field = csys_field + 1
          if (csys_field == 1) cycle
          call input_error(error, rec%file, field_line(rec, i), 'CSYS is given twice', i)
          return
        end if
        call input_error(error, rec%file, field_line(rec, i), keyword(rec) // ' takes DOF names and CSYS=n, not "' // &
                         field_text(rec, i) // '"', i)
        return
      end if
      if (f == 'ALL') then
        do dof = 1, 3
          call add_hold(dof)
        end do
        cycle
      end if
      call dof_index(f, model%systems(cs)%kind, dof)
      if (dof == 0) then
        call input_error(error, rec%file, field_line(rec, i), &
                         'unknown degree of freedom "' // f // '" for this system (' &
                         // dof_names(model%systems(cs)%kind) // ' or ALL)', i)
        return
      end if
      call add_hold(dof)
    end do
  contains
    !> A FIX after a STAGE record holds from that stage on (at the value reached: its
    !! increment in the stage is zero); a RELEASE frees from that stage on.
    subroutine add_hold(d)
      integer, intent(in) :: d
      call add_constraint(model, rec, iset, cs, d, 0.0_dp, merge(from, 0, from > 1))
      model%constraints(size(model%constraints))%active_from = from
      model%constraints(size(model%constraints))%release = release
    end subroutine add_hold
  end subroutine read_fix

  !> DISPLACE, set, DOF=value [, DOF=value ...] [, CSYS=n]
  subroutine read_displace(rec, model, stage, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer, intent(in) :: stage
    type(error_t), allocatable, intent(out) :: error
    integer :: iset, cs, i
    integer, allocatable :: dofs(:)
    real(dp), allocatable :: values(:)
    logical :: total

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    call get_node_set(rec, model, iset, error)
    if (allocated(error)) return
    call get_csys_option(rec, model, 'CSYS', csys_cartesian, cs, error)
    if (allocated(error)) return
    call read_dof_values(rec, model%systems(cs)%kind, dofs, values, error)
    if (allocated(error)) return
    call read_mode(rec, stage, total, error)
    if (allocated(error)) return
    do i = 1, size(dofs)
      call add_constraint(model, rec, iset, cs, dofs(i), values(i), stage)
      model%constraints(size(model%constraints))%prescribed = .true.
      model%constraints(size(model%constraints))%total = total
    end do
  end subroutine read_displace

  !> FORCE, set, DOF=value ... [, CSYS=n]: the same force on every node of the set.
  subroutine read_force(rec, model, stage, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer, intent(in) :: stage
    type(error_t), allocatable, intent(out) :: error
    type(nodal_load_t) :: l
    type(nodal_load_t), allocatable :: tmp(:)
    integer, allocatable :: dofs(:)
    real(dp), allocatable :: values(:)

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    l%stage = stage
    l%file = rec%file
    l%line = rec%line
    call get_node_set(rec, model, l%node_set, error)
    if (allocated(error)) return
    call get_csys_option(rec, model, 'CSYS', csys_cartesian, l%csys, error)
    if (allocated(error)) return
    call read_dof_values(rec, model%systems(l%csys)%kind, dofs, values, error)
    if (allocated(error)) return
    call read_mode(rec, stage, l%total, error)
    if (allocated(error)) return
    l%components(dofs) = values
    l%given(dofs) = .true.
    tmp = [model%nodal_loads, l]
    call move_alloc(tmp, model%nodal_loads)
  end subroutine read_force

  !> The DOF=value fields (3 on, or `first` on; CSYS= aside) of a DISPLACE, FORCE or GRAVITY
  !! record: the directions of a system of kind `kind`, each once (Z and UZ are one), and their
  !! values.
  subroutine read_dof_values(rec, kind, dofs, values, error, first)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: kind
    integer, allocatable, intent(out) :: dofs(:)
    real(dp), allocatable, intent(out) :: values(:)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: first
    character(len=:), allocatable :: k, f
    integer :: i, dof, given(3), start
    real(dp) :: v
    allocate (dofs(0), values(0))
    start = 3
    if (present(first)) start = first
    call check_option_keys(rec, start, error, expected='DOF=value')
    if (allocated(error)) return
    given = 0
    do i = start, nfields(rec)
      call key_value(rec, i, 'DOF=value', k, f, error)
      if (allocated(error)) return
      if (k == 'CSYS' .or. k == 'MODE') cycle
      call dof_index(k, kind, dof)
      if (dof == 0) then
        call input_error(error, rec%file, field_line(rec, i), 'unknown direction "' // k // '" for this system (' // &
                         dof_names(kind) // ')', i)
        return
      end if
      call claim_dof(rec, given, dof, i, error)
      if (allocated(error)) return
      call parse_real(f, v, error, rec, i)
      if (allocated(error)) return
      dofs = [dofs, dof]
      values = [values, v]
    end do
  end subroutine read_dof_values

  !> GRAVITY, X=gx, Y=gy, Z=gz: the acceleration of gravity in multiples of g (global
  !! Cartesian; `Z=-1.` is the earth's, downwards in z), which gives every element of a material
  !! with a unit weight GAMMA its weight: gamma (gx, gy, gz) per unit volume. Once per deck; it
  !! acts from its stage on (the first stage when it comes before any STAGE record).
  subroutine read_gravity(rec, model, stage, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer, intent(in) :: stage
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: dofs(:)
    real(dp), allocatable :: values(:)
    character(len=:), allocatable :: text
    logical :: given
    integer :: at
    if (model%gravity_line > 0) then
      call input_error(error, rec%file, rec%line, 'GRAVITY is given twice (first at line ' // &
                       str(model%gravity_line) // '): gravity is switched on once', 1)
      return
    end if
    call require_fields(rec, 2, error)
    if (allocated(error)) return
    call get_option(rec, 'CSYS', text, given, at)
    if (given) then
      call input_error(error, rec%file, field_line(rec, at), 'GRAVITY takes X=, Y= and Z= in the global ' // &
                       'system, not CSYS=', at)
      return
    end if
    call read_dof_values(rec, csys_cartesian, dofs, values, error, first=2)
    if (allocated(error)) return
    model%gravity = 0.0_dp
    model%gravity(dofs) = values
    if (all(model%gravity == 0.0_dp)) then
      call input_error(error, rec%file, rec%line, 'GRAVITY has no direction: give X=, Y= or Z= ' // &
                       '(multiples of g, e.g. Z=-1.)', 2)
      return
    end if
    model%gravity_stage = max(stage, 1)
    model%gravity_file = rec%file
    model%gravity_line = rec%line
  end subroutine read_gravity

  !> GEOSTATIC, SURFACE=h [, WATER=w]: the stage it is in (the first when it comes before any STAGE record)
  !! sets the in-situ stress of the ground, the materials with K0: at height h' below the
  !! surface h (heights measured against gravity) the vertical stress is the weight of the ground
  !! above and the horizontal one K0 times it; WATER= is the height where a material of submerged
  !! unit weight below meets one above (see feps_geostatic). Once per deck; the stage must hold the GRAVITY
  !! record too (checked when the deck is complete).
  subroutine read_geostatic(rec, model, stage, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer, intent(in) :: stage
    type(error_t), allocatable, intent(out) :: error
    logical :: found
    if (model%geostatic_line > 0) then
      call input_error(error, rec%file, rec%line, 'GEOSTATIC is given twice (first at line ' // &
                       str(model%geostatic_line) // '): the in-situ stress is set once', 1)
      return
    end if
    call check_option_keys(rec, 2, error, allowed=['SURFACE', 'WATER  '])
    if (allocated(error)) return
    call option_real(rec, 'WATER', model%geostatic_water, found, error)
    if (allocated(error)) return
    call option_real(rec, 'SURFACE', model%geostatic_surface, found, error)
    if (allocated(error)) return
    if (.not. found) then
      call input_error(error, rec%file, rec%line, 'GEOSTATIC needs SURFACE=h, the height of the ground ' // &
                       'surface measured against gravity (e.g. its z when GRAVITY is Z=-1.)', 1)
      return
    end if
    model%geostatic_stage = max(stage, 1)
    model%geostatic_file = rec%file
    model%geostatic_line = rec%line
  end subroutine read_geostatic

  !> MODE=INCREMENT (the default) or MODE=TOTAL of a DISPLACE or FORCE record: with TOTAL its
  !! values are the totals at the end of its stage, which must be a STAGE's own (a reference
  !! value before any STAGE is scaled by each stage's LOAD= and has no total).
  subroutine read_mode(rec, stage, total, error)
    type(record_t), intent(in) :: rec
    integer, intent(in) :: stage
    logical, intent(out) :: total
    type(error_t), allocatable, intent(out) :: error
    character(len=:), allocatable :: text
    integer :: ifield
    logical :: found
    total = .false.
    call option_text(rec, 'MODE', text, ifield, found)
    if (.not. found) return
    select case (to_upper(text))
    case ('INCREMENT')
    case ('TOTAL')
      total = .true.
      if (stage == 0) then
        call input_error(error, rec%file, field_line(rec, ifield), 'MODE=TOTAL needs a STAGE record before it: ' // &
                         'before any STAGE a value is a reference, scaled by each stage''s LOAD=', ifield)
      end if
    case default
      call input_error(error, rec%file, field_line(rec, ifield), 'MODE takes INCREMENT or TOTAL, not "' // text // &
                       '"', ifield)
    end select
  end subroutine read_mode

  !> Field `i` of `rec` sets `dof`; another field that set it before (Z and UZ, say) is an error.
  subroutine claim_dof(rec, given, dof, i, error)
    type(record_t), intent(in) :: rec
    integer, intent(inout) :: given(3)   !! the field that set each DOF (0: none yet)
    integer, intent(in) :: dof, i
    type(error_t), allocatable, intent(out) :: error
    if (given(dof) > 0) then
      call input_error(error, rec%file, field_line(rec, i), 'fields ' // str(given(dof)) // ' and ' // str(i) // &
                       ' set the same direction', i)
      return
    end if
    given(dof) = i
  end subroutine claim_dof

  !> PRESTRESS, group, FORCE=N | STRESS=s: bars of the group prestressed by an axial force
  !! (tension positive; STRESS= is multiplied by the bars' area when the deck is finished).
  !! Before any STAGE a reference scaled by each stage's LOAD=, after one that stage's own.
  subroutine read_prestress(rec, model, stage, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer, intent(in) :: stage
    type(error_t), allocatable, intent(out) :: error
    type(prestress_t) :: p
    integer :: i, eq, given
    character(len=:), allocatable :: f, name

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    name = field_text(rec, 2)
    p%group = model%find_group(name)
    if (p%group == 0) then
      call input_error(error, rec%file, field_line(rec, 2), 'undefined element group "' // name // '"', 2)
      return
    end if
    if (model%groups(p%group)%element%family /= family_bar) then
      call input_error(error, rec%file, field_line(rec, 2), 'PRESTRESS acts on bars; group "' // name // '" holds ' // &
                       model%groups(p%group)%element_type // ' elements', 2)
      return
    end if
    given = 0
    do i = 3, nfields(rec)
      f = field_text(rec, i)
      eq = index(f, '=')
      select case (to_upper(f(:max(eq - 1, 0))))
      case ('FORCE', 'STRESS')
        given = given + 1
        if (given > 1) then
          call input_error(error, rec%file, field_line(rec, i), 'PRESTRESS takes one of FORCE= and STRESS=, once', i)
          return
        end if
        call parse_real(f(eq + 1:), p%force, error, rec, i)
        if (allocated(error)) return
        p%per_area = to_upper(f(:eq - 1)) == 'STRESS'
      case ('BOND')
        select case (to_upper(f(eq + 1:)))
        case ('BEFORE')
          p%bond_after = .false.
        case ('AFTER')
          p%bond_after = .true.
          p%bond_field = i
        case default
          call input_error(error, rec%file, field_line(rec, i), 'BOND is BEFORE (pretensioned: bonded while ' // &
                           'prestressed) or AFTER (post-tensioned: bonded from the next stage), not "' // &
                           f(eq + 1:) // '"', i)
          return
        end select
      case default
        call input_error(error, rec%file, field_line(rec, i), 'expected FORCE=axial force or STRESS=axial stress ' // &
                         '(tension positive) or BOND=BEFORE|AFTER, got "' // f // '"', i)
        return
      end select
    end do
    if (given == 0) then
      call input_error(error, rec%file, field_line(rec, 3), &
                       'PRESTRESS needs FORCE=axial force or STRESS=axial stress', 3)
      return
    end if
    p%stage = stage
    p%file = rec%file
    p%line = rec%line
    model%prestresses = [model%prestresses, p]
  end subroutine read_prestress

  !> PRESSURE, fset, VALUE=p | TOTAL=P [, VARY=coord, ZERO=a, PEAK=b, VARY_CSYS=n]
  !! TRACTION, fset, [CSYS=n,] DIR=value ..., [TOTAL=P,] [VARY=...]
  subroutine read_face_load(rec, model, stage, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(inout) :: model
    integer, intent(in) :: stage
    type(error_t), allocatable, intent(out) :: error
    type(face_load_t) :: l
    type(face_load_t), allocatable :: tmp(:)
    character(len=:), allocatable :: text, f, k
    integer :: ifield, i, dof, given(3)
    logical :: found, has_value
    real(dp) :: v

    call require_fields(rec, 3, error)
    if (allocated(error)) return
    l%face_set = model%find_face_set(field_text(rec, 2))
    if (l%face_set == 0) then
      call input_error(error, rec%file, field_line(rec, 2), 'undefined face set "' // field_text(rec, 2) // '"', 2)
      return
    end if
    l%file = rec%file
    l%line = rec%line
    l%stage = stage
    l%kind = merge(load_pressure, load_traction, keyword(rec) == 'PRESSURE')
    call get_csys_option(rec, model, 'CSYS', csys_cartesian, l%csys, error)
    if (allocated(error)) return
    call check_option_keys(rec, 3, error)
    if (allocated(error)) return
    has_value = .false.
    given = 0
    do i = 3, nfields(rec)
      call key_value(rec, i, 'KEY=value', k, f, error)
      if (allocated(error)) return
      select case (k)
      case ('CSYS', 'VARY', 'VARY_CSYS', 'VARY2', 'VARY2_CSYS')
        cycle
      case ('VALUE', 'TOTAL', 'ZERO', 'PEAK', 'ZERO2', 'PEAK2')
        call parse_real(f, v, error, rec, i)
        if (allocated(error)) return
        select case (k)
        case ('VALUE')
          if (l%kind == load_traction) then
            call input_error(error, rec%file, field_line(rec, i), &
                             'TRACTION takes components (e.g. Z=1.0), not VALUE=', i)
            return
          end if
          l%value = v
          has_value = .true.
        case ('TOTAL')
          l%total = v
          l%use_total = .true.
        case ('ZERO')
          l%zero = v
        case ('PEAK')
          l%peak_at = v
        case ('ZERO2')
          l%zero2 = v
        case ('PEAK2')
          l%peak2_at = v
        end select
      case default
        if (l%kind == load_pressure) then
          call input_error(error, rec%file, field_line(rec, i), 'unknown PRESSURE option "' // k // &
                           '" (VALUE, TOTAL, VARY, ZERO, PEAK, VARY_CSYS, VARY2, ZERO2, PEAK2, VARY2_CSYS)', i)
          return
        end if
        call dof_index(k, model%systems(l%csys)%kind, dof)
        if (dof == 0) then
          call input_error(error, rec%file, field_line(rec, i), 'unknown TRACTION option or direction "' // k // '"', i)
          return
        end if
        call claim_dof(rec, given, dof, i, error)
        if (allocated(error)) return
        call parse_real(f, v, error, rec, i)
        if (allocated(error)) return
        l%components(dof) = v
        has_value = .true.
      end select
    end do
    if (l%kind == load_pressure .and. (has_value .eqv. l%use_total)) then
      call input_error(error, rec%file, rec%line, 'PRESSURE needs exactly one of VALUE= and TOTAL=')
      return
    end if
    if (l%kind == load_traction .and. .not. has_value) then
      call input_error(error, rec%file, rec%line, 'TRACTION needs at least one component (e.g. Z=1.0)')
      return
    end if
    if (l%kind == load_traction .and. l%use_total .and. norm2(l%components) == 0.0_dp) then
      call input_error(error, rec%file, rec%line, 'TRACTION with TOTAL= needs a nonzero direction')
      return
    end if
    ! A linear variation in one coordinate, and optionally in a second one (the product)
    call read_ramp('', l%vary_csys, l%vary_coord, l%zero, l%peak_at)
    if (allocated(error)) return
    call read_ramp('2', l%vary2_csys, l%vary2_coord, l%zero2, l%peak2_at)
    if (allocated(error)) return
    if (l%vary2_coord > 0 .and. l%vary_coord == 0) then
      call option_text(rec, 'VARY2', text, ifield, found)   ! the field to name
      call input_error(error, rec%file, field_line(rec, ifield), &
                       'VARY2 is the second variation: give VARY= too', ifield)
      return
    end if
    tmp = [model%face_loads, l]
    call move_alloc(tmp, model%face_loads)
  contains
    !> VARY<n>=coordinate with ZERO<n>= and PEAK<n>= (and VARY<n>_CSYS=), n = '' or '2'.
    subroutine read_ramp(n, csys, coord, zero, peak_at)
      character(len=*), intent(in) :: n
      integer, intent(inout) :: csys, coord
      real(dp), intent(in) :: zero, peak_at
      integer :: default_csys, zero_field, peak_field
      logical :: has_zero, has_peak
      call option_text(rec, 'ZERO' // n, text, zero_field, has_zero)
      call option_text(rec, 'PEAK' // n, text, peak_field, has_peak)
      call option_text(rec, 'VARY' // n, text, ifield, found)
      if (.not. found) then
        ! without VARY<n> they would be ignored, and VARY<n>_CSYS too
        call option_text(rec, 'VARY' // n // '_CSYS', text, ifield, found)
        if (has_zero .or. has_peak .or. found) then
          if (.not. found) ifield = merge(zero_field, peak_field, has_zero)
          call input_error(error, rec%file, field_line(rec, ifield), &
                           'ZERO' // n // '=, PEAK' // n // '= and VARY' // n // &
                           '_CSYS= belong to a variation: give VARY' // n // '= too', ifield)
        end if
        return
      end if
      if (.not. (has_zero .and. has_peak)) then
        call input_error(error, rec%file, field_line(rec, ifield), &
                         'VARY' // n // ' needs ZERO' // n // '= and PEAK' // n // &
                         '= (where the load is zero and where it peaks)', ifield)
        return
      end if
      csys = csys_cartesian
      select case (to_upper(text))
      case ('X')
        coord = 1
      case ('Y')
        coord = 2
      case ('Z')
        coord = 3
      case ('R')
        coord = 1
        csys = csys_cylindrical
      case ('THETA', 'T')
        coord = 2
        csys = csys_cylindrical
      case default
        call input_error(error, rec%file, field_line(rec, ifield), &
                         'VARY' // n // ' takes X, Y, Z, R or THETA, not "' // text // &
                         '"', ifield)
        return
      end select
      default_csys = csys
      call get_csys_option(rec, model, 'VARY' // n // '_CSYS', default_csys, csys, error)
      if (allocated(error)) return
      ! X and Y name no coordinate of a cylindrical system, R and THETA none of a Cartesian one
      if (coord /= 3 .and. ((model%systems(csys)%kind == csys_cylindrical) .neqv. &
                            (default_csys == csys_cylindrical))) then
        call input_error(error, rec%file, field_line(rec, ifield), &
                         'VARY' // n // '=' // to_upper(text) // ' is no coordinate of ' // &
                         'system ' // str(csys) // ' (' // dof_names(model%systems(csys)%kind) // ')', ifield)
        return
      end if
      if (peak_at == zero) then
        call input_error(error, rec%file, rec%line, 'VARY' // n // ' needs ZERO' // n // '= and PEAK' // n // &
                         '= at different places')
        return
      end if
    end subroutine read_ramp
  end subroutine read_face_load

  subroutine add_constraint(model, rec, iset, cs, dof, value, stage)
    type(model_t), intent(inout) :: model
    type(record_t), intent(in) :: rec
    integer, intent(in) :: iset, cs, dof, stage
    real(dp), intent(in) :: value
    type(constraint_t) :: c
    type(constraint_t), allocatable :: tmp(:)
    c%node_set = iset
    c%csys = cs
    c%dof = dof
    c%value = value
    c%stage = stage
    c%file = rec%file
    c%line = rec%line
    tmp = [model%constraints, c]
    call move_alloc(tmp, model%constraints)
  end subroutine add_constraint

  subroutine get_node_set(rec, model, iset, error)
    type(record_t), intent(in) :: rec
    type(model_t), intent(in) :: model
    integer, intent(out) :: iset
    type(error_t), allocatable, intent(out) :: error
    iset = model%find_node_set(field_text(rec, 2))
    if (iset == 0) call input_error(error, rec%file, field_line(rec, 2), &
                                    'undefined node set "' // field_text(rec, 2) // '"', 2)
  end subroutine get_node_set

end module feps_deck_loads
