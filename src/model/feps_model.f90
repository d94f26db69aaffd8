!> The analysis model as plain data: nodes, coordinate systems, element groups, material
!! parameters, node and face selections, supports, loads and controls. The deck reader fills
!! it; the element, material and assembly layers interpret it.
module feps_model
  use feps_kinds, only: dp
  use feps_coordinate_system, only: coordinate_system_t
  use feps_element_catalog, only: element_info_t, family_interface
  use feps_result_schema, only: result_fields, field_index, known_field_names
  implicit none
  private

  integer, parameter, public :: name_len = 64

  !> A material's parameters as a typed record. The material layer's `material_t` extends it:
  !! a material object is its own parameter record, and the one the deck reader built and
  !! checked is kept with its MATERIAL record (this layer, below the materials, cannot name
  !! their types).
  type, abstract, public :: material_params_t
  end type material_params_t

  !> A MATERIAL record: its parameters as given (by name: E, nu, G, ..., for the results and
  !! messages) and, once the deck reader has checked them, as the material's typed record.
  type, public :: material_spec_t
    character(len=:), allocatable :: name
    character(len=:), allocatable :: kind          !! 'elastic', ...
    character(len=name_len), allocatable :: keys(:)
    real(dp), allocatable :: values(:)
    character(len=name_len), allocatable :: texts(:)  !! lower-case word of a text-valued key, else ''
    integer, allocatable :: fields(:)     !! each key's field number on the record (unallocated: not known)
    integer :: kind_field = 0             !! field number of the kind (0: not known)
    character(len=:), allocatable :: file
    integer :: line = 0
    !> The parameters parsed and checked into the material's own record (the material object,
    !! from feps_material_factory). Unallocated: not built yet (a record built by hand), or a
    !! value changed since (`set`).
    class(material_params_t), allocatable :: params
  contains
    procedure :: get => material_get
    procedure :: set => material_set
    procedure :: get_text => material_get_text
    procedure :: field_of => material_field_of
  end type material_spec_t

  !> MATERIAL keys whose value is a word, not a number (e.g. TENSION=closest-point).
  character(len=*), parameter, public :: text_material_keys(3) = ['tension  ', 'softening', 'damage   ']

  !> Elements of one type and one material.
  type, public :: element_group_t
    character(len=:), allocatable :: name
    character(len=:), allocatable :: element_type   !! the element catalog's name ('nodes<k>': an
                                                    !! untyped block of a bare DATAIN mesh)
    type(element_info_t) :: element                 !! what the catalog says of it (family 0: untyped)
    character(len=:), allocatable :: material_name
    integer :: material_field = 0                   !! the GROUP record's MATERIAL= field (for errors)
    integer :: material = 0                         !! index into model%materials
    integer, allocatable :: connectivity(:, :)      !! (nodes per element, nelem), 1-based
    integer, allocatable :: blocks(:)               !! DATAIN element blocks it holds
    integer, allocatable :: element_ids(:)          !! the deck's element ids (ELEMENTS tables); not
                                                    !! allocated: the elements are numbered 1, 2, ...
    integer :: activate_stage = 0                   !! 0: active from the start; s: born in stage s
    character(len=:), allocatable :: file
    integer :: line = 0
  end type element_group_t

  !> A box in a coordinate system: each coordinate within [lo - tol, hi + tol] when active.
  !! For a cylindrical system's theta (degrees) the range is taken modulo 360.
  type, public :: region_t
    integer :: csys = 2
    logical :: active(3) = .false.
    real(dp) :: lo(3) = 0.0_dp
    real(dp) :: hi(3) = 0.0_dp
    real(dp) :: tol = 1.0e-6_dp
  end type region_t

  type, public :: node_set_t
    character(len=:), allocatable :: name
    integer, allocatable :: nodes(:)
    logical :: listed = .false.              !! the one node of FORCE/DISPLACE LIST rows (not written to /sets)
  end type node_set_t

  !> Element faces whose nodes all lie in a region, within one group (resolved by the
  !! assembly layer, which knows the element faces).
  type, public :: face_set_t
    character(len=:), allocatable :: name
    integer :: group = 0
    type(region_t) :: region
    integer, allocatable :: element(:)
    integer, allocatable :: face(:)
    character(len=:), allocatable :: file
    integer :: line = 0
    logical :: listed = .false.              !! FSET LIST: element and face given by rows
    integer, allocatable :: row_line(:)      !! each row's line (FSET LIST)
    integer, allocatable :: row_field(:)     !! each row's face-number field (the element's is one before)
  end type face_set_t

  !> Fixed (value 0) or prescribed displacement of one DOF of every node of a set, the DOF
  !! counted in the directions of coordinate system csys (radial, hoop, axial if cylindrical).
  !! Which DOFs are held in stage s: the constraints with active_from <= s, in deck order, the
  !! last one on a DOF deciding (a release frees it).
  type, public :: constraint_t
    integer :: node_set = 0
    integer :: csys = 2
    integer :: dof = 0
    real(dp) :: value = 0.0_dp
    integer :: stage = 0                     !! 0: scaled by each stage's LOAD=; s: increment in stage s
    integer :: active_from = 1               !! held from this stage on (FIX after a STAGE record)
    logical :: release = .false.             !! RELEASE: free from stage active_from on
    logical :: prescribed = .false.          !! DISPLACE: held in every stage
    logical :: total = .false.               !! DISPLACE MODE=TOTAL: value is the total at the stage's end
    character(len=:), allocatable :: file
    integer :: line = 0
  end type constraint_t

  !> Force on every node of a set, components in the directions of system csys.
  type, public :: nodal_load_t
    integer :: stage = 0                     !! 0: reference load scaled by LOAD=; s: increment in stage s
    integer :: node_set = 0
    integer :: csys = 2
    real(dp) :: components(3) = 0.0_dp
    character(len=:), allocatable :: file    !! the FORCE record (for messages)
    integer :: line = 0
    integer :: field = 2                     !! the field naming its nodes (the set; a LIST row's node)
    logical :: total = .false.               !! MODE=TOTAL: the given components are totals at the stage's end
    logical :: given(3) = .false.            !! the components the record gives
  end type nodal_load_t

  !> Prestress of the bars of one group: an axial force, tension positive, added to every
  !! point of the group in equal parts over the stage's steps (PRESTRESS record). The bars
  !! are bonded: after the prestress their force changes with their strain as before.
  type, public :: prestress_t
    integer :: stage = 0                     !! 0: reference, scaled by LOAD=; s: increment in stage s
    integer :: group = 0
    real(dp) :: force = 0.0_dp               !! axial force (STRESS= times the bars' area)
    logical :: per_area = .false.            !! given as STRESS= (the deck reader converts it)
    !> BOND=after (post-tensioned): during its stage the bars are not yet bonded, their force
    !! acts on their nodes as a load, and they are born at the start of the next stage carrying
    !! it. Otherwise (BOND=before, pretensioned) they are bonded while the force is added.
    logical :: bond_after = .false.
    integer :: bond_field = 0                !! the record's BOND= field (for messages)
    character(len=:), allocatable :: file
    integer :: line = 0
  end type prestress_t

  integer, parameter, public :: load_pressure = 1, load_traction = 2

  !> Distributed load on a face set. Pressure acts against the outward normal; a traction has
  !! components in the directions of system csys. Intensity = peak * shape(x), where shape is
  !! 1 (uniform) or linear in one coordinate of system vary_csys: 0 at `zero`, 1 at `peak_at`,
  !! clipped below at 0, times a second such ramp when vary2_coord > 0 (a bilinear load, e.g.
  !! linear in x and in r). With `use_total` the peak is scaled so that the integral of the
  !! intensity over the faces equals `total`.
  type, public :: face_load_t
    integer :: stage = 0                     !! 0: reference load scaled by LOAD=; s: increment in stage s
    integer :: face_set = 0
    integer :: kind = load_pressure
    integer :: csys = 2
    real(dp) :: components(3) = 0.0_dp       !! traction direction and size (kind = traction)
    real(dp) :: value = 0.0_dp               !! peak intensity (pressure)
    logical :: use_total = .false.
    real(dp) :: total = 0.0_dp
    integer :: vary_csys = 2
    integer :: vary_coord = 0                !! 0: uniform; 1..3: coordinate of vary_csys
    real(dp) :: zero = 0.0_dp
    real(dp) :: peak_at = 1.0_dp
    integer :: vary2_csys = 2                !! the second ramp (VARY2=): same meaning
    integer :: vary2_coord = 0               !! 0: none
    real(dp) :: zero2 = 0.0_dp
    real(dp) :: peak2_at = 1.0_dp
    character(len=:), allocatable :: file
    integer :: line = 0
  end type face_load_t

  !> Solution methods of the modified Newton-Raphson family (thesis 2.6).
  integer, parameter, public :: method_euler = 1, method_modified_euler = 2, method_newton_raphson = 3, &
                                method_modified_newton_raphson = 4, method_initial_stiffness = 5, &
                                method_full_newton_raphson = 6
  character(len=23), parameter, public :: method_names(6) = [character(len=23) :: 'euler', 'modified-euler', &
    'newton-raphson', 'modified-newton-raphson', 'initial-stiffness', 'full-newton-raphson']

  !> How a stage follows its load path (STAGE PATH=).
  integer, parameter, public :: path_load = 0, path_arc_length = 1, path_displacement = 2
  character(len=12), parameter, public :: path_names(0:2) = [character(len=12) :: 'load', 'arc-length', &
    'displacement']

  !> Limits of the controls, checked where the deck (or the command line) gives them, before
  !! any arithmetic: steps are numbered over all stages in default integers; MAXIT sizes the
  !! BFGS history (two vectors of the DOFs per iteration); a step halved more than 50 times is
  !! below double precision's resolution of the load factor.
  integer, parameter, public :: max_total_steps = 10000000     !! steps of all stages together
  integer, parameter, public :: max_iterations_limit = 1000    !! MAXIT, --maxit
  integer, parameter, public :: max_cutbacks_limit = 50        !! CUTBACKS

  !> Solution controls of a stage (thesis eqs. 2.6.6-2.6.7).
  type, public :: controls_t
    integer :: method = method_modified_newton_raphson
    integer :: max_iterations = 10           !! per step (1 for the Euler methods)
    real(dp) :: delta1 = 1.0e-6_dp           !! converged when |R| / |P| < delta1 ...
    real(dp) :: delta2 = 0.0_dp              !! ... or |R| < delta2 (N)
    real(dp) :: delta3 = 1.0e-3_dp           !! modified NR refactorizes when |R| / |P| > delta3 ...
    real(dp) :: delta4 = huge(1.0_dp)        !! ... or |R| > delta4 at the end of a step
    integer :: max_cutbacks = 10             !! halvings of a step that diverges
    real(dp) :: divergence = 1.0e-2_dp       !! a step ending with |R| / |P| above this diverged
    logical :: bfgs = .false.                !! quasi-Newton (BFGS) updates of the factorized stiffness
    logical :: max_iterations_set = .false.
    logical :: line_search = .false.         !! LINESEARCH=energy: Newton corrections scaled by a line search
    !> where LINESEARCH=energy was given (CONTROLS or STAGE record), for the error when the
    !! method it reaches cannot take it
    character(len=:), allocatable :: line_search_file
    integer :: line_search_line = 0
    integer :: line_search_field = 0
  end type controls_t

  !> A loading stage: its own load and displacement increments plus LOAD= times the
  !! reference (stage-0) loads, applied in equal steps.
  type, public :: stage_t
    character(len=:), allocatable :: name
    integer :: steps = 1
    real(dp) :: load_fraction = 1.0_dp
    logical :: load_given = .false.          !! LOAD= was given (else the default of the deck)
    integer :: output_every = 0              !! write every k steps (0: the stage's last step)
    type(controls_t) :: controls
    !> PATH=: load control (the stage's loads in equal steps), arc-length (Crisfield's
    !! cylindrical constraint on the stage's load factor) or displacement control (the load
    !! factor set so that a node set's mean displacement follows VALUE= in equal steps)
    integer :: path = path_load
    integer :: path_field = 0                !! the PATH= field (for messages)
    real(dp) :: arc = 0.0_dp                 !! ARC=: the first step's arc length (0: from the first predictor)
    integer :: path_set = 0                  !! PATH=DISPLACEMENT: NSET= (index into model%node_sets)
    integer :: path_from_set = 0             !! FROM=: the value followed is NSET's mean minus this set's
                                             !! (a relative displacement: a crack's opening; 0: none)
    integer :: path_dof = 0                  !! DOF= (1..3, global x, y, z)
    real(dp) :: path_value = 0.0_dp          !! VALUE=: the set's mean displacement increment over the stage
    character(len=name_len), allocatable :: activate(:)  !! groups born at the start of this stage
    integer, allocatable :: activate_field(:)            !! their fields in the STAGE record
    character(len=:), allocatable :: file
    integer :: line = 0
  end type stage_t

  !> A quantity computed after the run (thesis post-processing): 'rotation' is the rotation
  !! of the section z = const of a pipe from the axial displacements of its nodes on r = R at
  !! theta = 180 and 0 deg; 'tilt' the tilt of a group's axis between two sections; 'reaction'
  !! the resultant of the support reactions on a node set; 'section' the forces through a
  !! section; 'joint' the design summary of a pipe joint.
  type, public :: report_t
    character(len=:), allocatable :: name
    character(len=:), allocatable :: kind
    integer :: group = 0
    integer :: node_set = 0                  !! 'reaction': index into model%node_sets
    real(dp) :: r = 0.0_dp
    real(dp) :: z = 0.0_dp
    logical :: has_span = .false.            !! FROM=/TO= x positions; else the extreme nodes
    real(dp) :: x_from = 0.0_dp
    real(dp) :: x_to = 0.0_dp
    logical :: has_reference = .false.
    real(dp) :: reference = 0.0_dp
    real(dp) :: about(2) = 0.0_dp            !! 'section': X0=, Y0= of the point moments are taken about
    !> 'joint': the interface group across the joint, the pipe groups (PIPE=g1:g2, the one below
    !! the joint first), the packing group (0: none), the cylindrical system (0: FIELDS CSYS=),
    !! the loaded edge's theta (deg) and the keys that override what the model gives:
    !! A= packing thickness, L= pipe length, P= the joint load (each with its has_ flag).
    integer :: interface_group = 0
    integer, allocatable :: pipe_groups(:)
    integer :: packing_group = 0
    integer :: csys = 0
    real(dp) :: edge = 0.0_dp
    logical :: has_a = .false., has_l = .false., has_p = .false.
    real(dp) :: packing_thickness = 0.0_dp
    real(dp) :: pipe_length = 0.0_dp
    real(dp) :: load = 0.0_dp
    real(dp) :: near = 0.0_dp                !! 'joint': NEAR=, the pipe points within this axial distance (0: 2R)
    character(len=:), allocatable :: file
    integer :: line = 0
  end type report_t

  !> Which result fields a run writes (deck keyword FIELDS; default: the schema's `by_default`
  !! fields: all but the nodal averages and the optional point fields, which are written only
  !! when named). A field not asked for is not computed either where that saves work (stress
  !! recovery of elastic groups, principal stresses).
  type, public :: output_fields_t
    logical :: on(size(result_fields)) = result_fields%by_default  !! by the schema's field ids
    integer :: csys = 3                   !! the cylindrical system of stress_cyl (FIELDS CSYS=)
  contains
    procedure :: select => fields_select
    procedure :: names => fields_names
    procedure :: clear => fields_clear
  end type output_fields_t

  type, public :: model_t
    character(len=:), allocatable :: title
    character(len=:), allocatable :: deck_file
    type(coordinate_system_t), allocatable :: systems(:)
    integer :: nnode = 0
    real(dp), allocatable :: coords(:, :)                 !! (3, nnode) global Cartesian
    type(element_group_t), allocatable :: groups(:)
    type(material_spec_t), allocatable :: materials(:)
    type(node_set_t), allocatable :: node_sets(:)
    type(face_set_t), allocatable :: face_sets(:)
    type(constraint_t), allocatable :: constraints(:)
    type(nodal_load_t), allocatable :: nodal_loads(:)
    type(face_load_t), allocatable :: face_loads(:)
    type(prestress_t), allocatable :: prestresses(:)       !! PRESTRESS records (bars)
    type(stage_t), allocatable :: stages(:)
    type(report_t), allocatable :: reports(:)
    type(controls_t) :: controls                           !! defaults for the stages
    character(len=:), allocatable :: solver                !! 'cholmod' or 'skyline'
    character(len=:), allocatable :: output_file
    type(output_fields_t) :: fields                        !! result fields to write
    integer :: restart_every = 0                           !! RESTART, EVERY=n: restart data every n steps (0: none)
    logical :: mesh_only = .false.                         !! a file holding only a DATAIN mesh
    logical :: plane_strain = .false.                      !! a 2D model: uz = 0 at every node
    character(len=name_len), allocatable :: parameter_names(:)    !! PARAMETERS: the campaign's own labels
    character(len=name_len), allocatable :: parameter_values(:)   !! (written to /summary as parameter_<name>)
    !> GRAVITY: the acceleration in multiples of g, the stage it acts from (0: no GRAVITY) and
    !! its record. Each group with a unit weight gets its weight in the later of that stage and
    !! the stage it is born in, spread over that stage's steps.
    real(dp) :: gravity(3) = 0.0_dp
    integer :: gravity_stage = 0
    character(len=:), allocatable :: gravity_file
    integer :: gravity_line = 0
    !> GEOSTATIC, SURFACE=h: the stage that sets the in-situ stress of the ground (0: none), the
    !! height of the ground surface against gravity, and its record.
    integer :: geostatic_stage = 0
    real(dp) :: geostatic_surface = 0.0_dp
    !> WATER=: the water table's height, where a ground material whose elements lie below it
    !! (by their centres) meets one above; huge when not given
    real(dp) :: geostatic_water = huge(1.0_dp)
    character(len=:), allocatable :: geostatic_file
    integer :: geostatic_line = 0
    !> What the deck reader found doubtful but not wrong (a value far outside the physical
    !! range in N, mm and MPa), each naming file, line and field: the command prints them.
    character(len=600), allocatable :: warnings(:)
  contains
    procedure :: nelem => model_nelem
    procedure :: has_interfaces
    procedure :: supports_change
    procedure :: stage_prestress, is_prestressed
    procedure :: find_node_set, find_face_set, find_material, find_group
  end type model_t

  public :: in_region, line_search_refusal, known_fields

contains

  !> Turn on the field called `name` (a name of the result schema, or `all` for its default
  !! fields); `known` false if there is none.
  pure subroutine fields_select(self, name, known)
    class(output_fields_t), intent(inout) :: self
    character(len=*), intent(in) :: name
    logical, intent(out) :: known
    integer :: k
    known = .true.
    if (name == 'all') then     ! the default fields, to which FIELDS can add the others
      self%on = self%on .or. result_fields%by_default
      return
    end if
    k = field_index(name)
    known = k > 0
    if (known) self%on(k) = .true.
  end subroutine fields_select

  !> No field selected (the start of a FIELDS record or of --fields).
  pure subroutine fields_clear(self)
    class(output_fields_t), intent(inout) :: self
    self%on = .false.
  end subroutine fields_clear

  !> The names FIELDS and --fields accept, comma-separated, for error messages.
  pure function known_fields() result(list)
    character(len=:), allocatable :: list
    list = known_field_names()
  end function known_fields

  !> The selected fields as one space-separated list (for the results file's summary).
  pure function fields_names(self) result(list)
    class(output_fields_t), intent(in) :: self
    character(len=:), allocatable :: list
    integer :: i
    list = ''
    do i = 1, size(result_fields)
      if (.not. self%on(i)) cycle
      if (len(list) > 0) list = list // ' '
      list = list // trim(result_fields(i)%name)
    end do
  end function fields_names

  !> Value of parameter `key` (case as stored: lower case); `found` false if absent.
  pure subroutine material_get(self, key, value, found)
    class(material_spec_t), intent(in) :: self
    character(len=*), intent(in) :: key
    real(dp), intent(out) :: value
    logical, intent(out) :: found
    integer :: i
    found = .false.
    value = 0.0_dp
    if (.not. allocated(self%keys)) return
    do i = 1, size(self%keys)
      if (trim(self%keys(i)) == key) then
        value = self%values(i)
        found = .true.
        return
      end if
    end do
  end subroutine material_get

  !> Set parameter `key` (lower case) to `value`, adding it if absent, or the word of a
  !! text-valued key to `text`. The typed record no longer matches and is dropped: the
  !! analysis builds and checks the material again.
  pure subroutine material_set(self, key, value, text)
    class(material_spec_t), intent(inout) :: self
    character(len=*), intent(in) :: key
    real(dp), intent(in) :: value
    character(len=*), intent(in), optional :: text
    character(len=name_len) :: word
    integer :: i
    if (allocated(self%params)) deallocate (self%params)
    word = ''
    if (present(text)) word = text
    if (.not. allocated(self%keys)) allocate (self%keys(0), self%values(0))
    do i = 1, size(self%keys)
      if (trim(self%keys(i)) == key) then
        self%values(i) = value
        if (allocated(self%texts)) self%texts(i) = word
        return
      end if
    end do
    self%keys = [character(len=name_len) :: self%keys, key]
    self%values = [self%values, value]
    if (allocated(self%texts)) self%texts = [character(len=name_len) :: self%texts, word]
    if (allocated(self%fields)) self%fields = [self%fields, 0]
  end subroutine material_set

  !> The word given for a text-valued key (lower case; '' if it was given as a number).
  pure subroutine material_get_text(self, key, text, found)
    class(material_spec_t), intent(in) :: self
    character(len=*), intent(in) :: key
    character(len=:), allocatable, intent(out) :: text
    logical, intent(out) :: found
    integer :: i
    found = .false.
    text = ''
    if (.not. allocated(self%keys)) return
    do i = 1, size(self%keys)
      if (trim(self%keys(i)) == key) then
        if (allocated(self%texts)) text = trim(self%texts(i))
        found = .true.
        return
      end if
    end do
  end subroutine material_get_text

  !> The field number of `key` on the MATERIAL record: 0 if the key was not given or the
  !! record's field numbers are not known (a spec built by hand).
  pure integer function material_field_of(self, key) result(field)
    class(material_spec_t), intent(in) :: self
    character(len=*), intent(in) :: key
    integer :: i
    field = 0
    if (.not. (allocated(self%keys) .and. allocated(self%fields))) return
    do i = 1, min(size(self%keys), size(self%fields))
      if (trim(self%keys(i)) == key) then
        field = self%fields(i)
        return
      end if
    end do
  end function material_field_of

  !> Number of elements in all groups.
  pure integer function model_nelem(self) result(n)
    class(model_t), intent(in) :: self
    integer :: g
    n = 0
    if (.not. allocated(self%groups)) return
    do g = 1, size(self%groups)
      n = n + size(self%groups(g)%connectivity, 2)
    end do
  end function model_nelem

  !> Why the controls `c` cannot take LINESEARCH=energy, or '' when they can. The line search
  !! scales the corrections of the methods that must converge every step (newton-raphson,
  !! full-newton-raphson): it changes how a step reaches its solution, not which (to DELTA1).
  !! The Euler methods take one iteration, and modified Newton-Raphson and initial stiffness
  !! may end a step unconverged and carry the rest (thesis 2.6.3): there a search would change
  !! the results the method defines. BFGS pairs would have to be built on the scaled
  !! corrections (not done).
  pure function line_search_refusal(c) result(why)
    type(controls_t), intent(in) :: c
    character(len=:), allocatable :: why
    why = ''
    if (.not. c%line_search) return
    select case (c%method)
    case (method_newton_raphson, method_full_newton_raphson)
      if (c%bfgs .and. c%method == method_newton_raphson) &
        why = 'LINESEARCH=energy does not combine with ACCELERATION=bfgs (METHOD=newton-raphson)'
    case default
      why = 'LINESEARCH=energy applies to METHOD=newton-raphson and full-newton-raphson, not to ' // &
            trim(method_names(c%method))
    end select
  end function line_search_refusal

  !> True if some group holds interface elements.
  pure logical function has_interfaces(self)
    class(model_t), intent(in) :: self
    integer :: g
    has_interfaces = .false.
    do g = 1, size(self%groups)
      if (self%groups(g)%element%family == family_interface) has_interfaces = .true.
    end do
  end function has_interfaces

  !> Axial force that stage s adds to the bars of each group by prestress: the stage's own
  !! PRESTRESS records plus its LOAD= fraction of the reference ones (0 for other groups). By
  !! default the bonded (pretensioned) records; with after = .true. the post-tensioned ones
  !! (BOND=after, never reference records), whose force loads the bars' nodes during stage s
  !! and which the bars carry when they are born at the start of the next.
  pure function stage_prestress(self, s, after) result(force)
    class(model_t), intent(in) :: self
    integer, intent(in) :: s
    logical, intent(in), optional :: after
    real(dp) :: force(size(self%groups))
    logical :: want_after
    integer :: i
    force = 0.0_dp
    want_after = .false.
    if (present(after)) want_after = after
    if (.not. allocated(self%prestresses)) return
    do i = 1, size(self%prestresses)
      associate (p => self%prestresses(i))
        if (p%bond_after .neqv. want_after) cycle
        if (p%stage == 0) then
          force(p%group) = force(p%group) + self%stages(s)%load_fraction * p%force
        else if (p%stage == s) then
          force(p%group) = force(p%group) + p%force
        end if
      end associate
    end do
  end function stage_prestress

  !> True if a PRESTRESS record names group g.
  pure logical function is_prestressed(self, g)
    class(model_t), intent(in) :: self
    integer, intent(in) :: g
    is_prestressed = .false.
    if (allocated(self%prestresses)) is_prestressed = any(self%prestresses(:)%group == g)
  end function is_prestressed

  !> Some DOF is held or freed from stage s on (FIX or RELEASE after the STAGE record of s).
  pure logical function supports_change(self, s)
    class(model_t), intent(in) :: self
    integer, intent(in) :: s
    supports_change = .false.
    if (s <= 1 .or. .not. allocated(self%constraints)) return
    supports_change = any(self%constraints(:)%active_from == s)
  end function supports_change

  !> Index of the node set called `name` (the last one if several); 0 if none.
  pure integer function find_node_set(self, name) result(idx)
    class(model_t), intent(in) :: self
    character(len=*), intent(in) :: name
    integer :: i
    idx = 0
    if (.not. allocated(self%node_sets)) return
    do i = 1, size(self%node_sets)
      if (self%node_sets(i)%name == name) idx = i
    end do
  end function find_node_set

  !> Index of the face set called `name` (the last one if several); 0 if none.
  pure integer function find_face_set(self, name) result(idx)
    class(model_t), intent(in) :: self
    character(len=*), intent(in) :: name
    integer :: i
    idx = 0
    if (.not. allocated(self%face_sets)) return
    do i = 1, size(self%face_sets)
      if (self%face_sets(i)%name == name) idx = i
    end do
  end function find_face_set

  !> Index of the material called `name` (the last one if several); 0 if none.
  pure integer function find_material(self, name) result(idx)
    class(model_t), intent(in) :: self
    character(len=*), intent(in) :: name
    integer :: i
    idx = 0
    if (.not. allocated(self%materials)) return
    do i = 1, size(self%materials)
      if (self%materials(i)%name == name) idx = i
    end do
  end function find_material

  !> Index of the element group called `name` (the last one if several); 0 if none.
  pure integer function find_group(self, name) result(idx)
    class(model_t), intent(in) :: self
    character(len=*), intent(in) :: name
    integer :: i
    idx = 0
    if (.not. allocated(self%groups)) return
    do i = 1, size(self%groups)
      if (self%groups(i)%name == name) idx = i
    end do
  end function find_group

  !> Is global point x inside region r (coordinates taken in system cs)?
  pure logical function in_region(r, cs, x)
    type(region_t), intent(in) :: r
    type(coordinate_system_t), intent(in) :: cs
    real(dp), intent(in) :: x(3)
    real(dp) :: c(3), t
    integer :: k
    c = cs%from_global(x)
    in_region = .true.
    do k = 1, 3
      if (.not. r%active(k)) cycle
      if (k == 2 .and. cs%kind == 3) then
        ! theta in degrees: shift into [lo - tol, lo - tol + 360)
        t = modulo(c(2) - (r%lo(2) - r%tol), 360.0_dp) + (r%lo(2) - r%tol)
        if (t > r%hi(2) + r%tol) then
          in_region = .false.
          return
        end if
      else if (c(k) < r%lo(k) - r%tol .or. c(k) > r%hi(k) + r%tol) then
        in_region = .false.
        return
      end if
    end do
  end function in_region

end module feps_model
