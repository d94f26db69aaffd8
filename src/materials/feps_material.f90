!> The abstract material: an elastic tangent (for the initial stiffness) and a stress update
!! from the state at the start of a step, returning the consistent tangent. Solid materials
!! work on 6 Voigt components [xx yy zz yz xz xy] (engineering shears); interface materials
!! on 3 [gamma1 gamma2 eps_n] (3D) or 2 [gamma eps_n] (2D) relative displacements.
module feps_material
  use feps_kinds, only: dp
  use feps_model, only: material_params_t
  use feps_strings, only: sci
  use feps_tangent_symmetry, only: nearest_symmetric_psd
  implicit none
  private

  public :: modulus_warning

  !> Gauss-point states written to the results.
  integer, parameter, public :: state_elastic = 0   !! elastic (interfaces: stuck)
  integer, parameter, public :: state_plastic = 1   !! on the yield surface (interfaces: sliding)
  integer, parameter, public :: state_open = 2      !! interface gap: open
  integer, parameter, public :: state_tension = 3   !! tension zone (apex) of a solid material
  integer, parameter, public :: state_cracked = 4   !! cracked (damaged in tension) concrete

  !> A material is its own typed parameter record (extending the model's material_params_t):
  !! the deck reader builds and checks it once and keeps it with the MATERIAL record. What a
  !! point carries is stress, total strain (size(sig0) components), a state flag and
  !! `state_size()` internal variables, held by `point_state_store_t`.
  type, abstract, extends(material_params_t), public :: material_t
    character(len=:), allocatable :: name
    real(dp) :: unit_weight = 0.0_dp     !! GAMMA (N/mm3): weight per volume (a bar's: times its area)
    !> K0: the ratio of horizontal to vertical in-situ stress; negative when not given (the
    !! material is not ground: a GEOSTATIC stage leaves its points unstressed).
    real(dp) :: k0 = -1.0_dp
  contains
    procedure(elastic_tangent_interface), deferred :: elastic_tangent
    procedure(update_interface), deferred :: update
    procedure(is_linear_interface), deferred :: is_linear
    procedure :: symmetric_tangent => material_symmetric_tangent
    procedure :: symmetric_stand_in => material_symmetric_stand_in
    procedure :: state_note => material_state_note
    procedure :: state_size => material_state_size
    procedure :: section_area => material_section_area
    procedure :: unit_warning => material_unit_warning
    procedure :: is_ground => material_is_ground
    procedure :: band_slot => material_band_slot
    procedure :: max_band => material_max_band
  end type material_t

  abstract interface
    !> Elastic stiffness matrix for size(d, 1) components.
    !! (A subroutine: gfortran 12 fails on array-valued deferred functions called through
    !! arrays of polymorphic components.)
    pure subroutine elastic_tangent_interface(self, d)
      import :: material_t, dp
      class(material_t), intent(in) :: self
      real(dp), intent(out) :: d(:, :)
    end subroutine elastic_tangent_interface

    !> Stress update over a step: from stress sig0, total strain eps0, state0 and the internal
    !! variables var0 at the start of the step and the strain increment deps, the stress sig,
    !! state and internal variables var at its end and the consistent tangent
    !! dtan = d sig / d deps there. var0 and var have `state_size()` entries; the point-state
    !! store always passes them, and a material with no internal variables may ignore them.
    pure subroutine update_interface(self, sig0, eps0, deps, state0, sig, state, dtan, var0, var)
      import :: material_t, dp
      class(material_t), intent(in) :: self
      real(dp), intent(in) :: sig0(:), eps0(:), deps(:)
      integer, intent(in) :: state0
      real(dp), intent(out) :: sig(:)
      integer, intent(out) :: state
      real(dp), intent(out) :: dtan(:, :)
      real(dp), intent(in), optional :: var0(:)
      real(dp), intent(out), optional :: var(:)
    end subroutine update_interface

    !> True when the material is linear elastic (no iteration, no state).
    pure logical function is_linear_interface(self)
      import :: material_t
      class(material_t), intent(in) :: self
    end function is_linear_interface
  end interface

  !> The range of Young's moduli (MPa) feps takes without a word: softer than the softest soil
  !! or stiffer than steel by far is most likely a unit slip (feps works in N, mm and MPa).
  real(dp), parameter, public :: plausible_modulus(2) = [1.0_dp, 1.0e6_dp]

  !> A slot in an array of polymorphic materials.
  type, public :: material_slot_t
    class(material_t), allocatable :: m
  end type material_slot_t

contains

  !> True when the consistent tangent is symmetric (associated flow); a material with
  !! non-associated flow overrides this.
  pure logical function material_symmetric_tangent(self)
    class(material_t), intent(in) :: self
    material_symmetric_tangent = .true.
  end function material_symmetric_tangent

  !> Replace a non-symmetric point tangent `d` by the symmetric matrix the symmetric solvers
  !! factorize in its place: by default the nearest symmetric positive semi-definite one
  !! (feps_tangent_symmetry). Only the iteration matrix changes, not the residual. A material
  !! that knows a better stand-in for its own tangent overrides this.
  subroutine material_symmetric_stand_in(self, d)
    class(material_t), intent(in) :: self
    real(dp), intent(inout) :: d(:, :)
    call nearest_symmetric_psd(d)
  end subroutine material_symmetric_stand_in

  !> A note for the user about points in `state` (empty: nothing to say). A material whose
  !! update is not smooth in some state overrides this to name the remedy.
  pure subroutine material_state_note(self, state, note)
    class(material_t), intent(in) :: self
    integer, intent(in) :: state
    character(len=:), allocatable, intent(out) :: note
    note = ''
  end subroutine material_state_note

  !> Number of internal variables per point beyond stress, strain and the state flag (hardening
  !! variables, plastic strains, ...): what `update` receives as var0 and returns as var. None
  !! by default; a material that needs them overrides this.
  pure integer function material_state_size(self) result(n)
    class(material_t), intent(in) :: self
    n = 0
  end function material_state_size

  !> The internal variable (1 to `state_size()`) in which the material wants its point's crack
  !! band, the length of its element (volume^(1/3)), set once by the analysis before the first
  !! step; 0 (the default): it needs none.
  pure integer function material_band_slot(self) result(slot)
    class(material_t), intent(in) :: self
    slot = 0
  end function material_band_slot

  !> The largest crack band the material takes (mm; a larger element is refused before the
  !! run); huge by default.
  pure real(dp) function material_max_band(self) result(h)
    class(material_t), intent(in) :: self
    h = huge(1.0_dp)
  end function material_max_band

  !> The cross-section area of a material whose stress is a force (bars: A, so that a
  !! PRESTRESS given as STRESS= is the axial force STRESS A); 0 for a material without one.
  pure real(dp) function material_section_area(self) result(area)
    class(material_t), intent(in) :: self
    area = 0.0_dp
  end function material_section_area

  !> A warning when a parameter lies far outside the physical range in N, mm and MPa, most
  !! likely a unit slip (E in GPa or Pa); empty when every value is plausible. `key` is the
  !! parameter it names (for the deck's field), empty with no warning.
  pure subroutine material_unit_warning(self, warning, key)
    class(material_t), intent(in) :: self
    character(len=:), allocatable, intent(out) :: warning, key
    warning = ''
    key = ''
  end subroutine material_unit_warning

  !> True when the material is ground: its K0 is given, so a GEOSTATIC stage sets its in-situ
  !! stress.
  elemental logical function material_is_ground(self)
    class(material_t), intent(in) :: self
    material_is_ground = self%k0 >= 0.0_dp
  end function material_is_ground

  !> The unit warning about a Young's modulus e outside plausible_modulus (empty inside it).
  pure function modulus_warning(e) result(warning)
    real(dp), intent(in) :: e
    character(len=:), allocatable :: warning
    warning = ''
    if (e < plausible_modulus(1)) then
      warning = 'E = ' // sci(e, 3, 0) // ' MPa is below 1 MPa, softer than any soil: feps works in N, mm ' // &
                'and MPa (E given in GPa?)'
    else if (e > plausible_modulus(2)) then
      warning = 'E = ' // sci(e, 3, 0) // ' MPa is above 1e6 MPa, five times steel: a rigid stand-in, ' // &
                'or a unit slip (E given in kPa or Pa? feps works in N, mm and MPa)'
    end if
  end function modulus_warning

end module feps_material
