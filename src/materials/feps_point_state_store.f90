!> The state of a group's material points: committed (the end of the last accepted step) and
!! trial (the current iterate), each point with its stress, total strain, state flag, tangent
!! and the internal variables its material declares (`material_t%state_size`). One store per
!! group; the analysis updates the trial from the committed state and then commits or restores.
!!
!! The start of a step is the committed state plus an imposed stress increment, zero unless the
!! stage imposes one on the group: a prestress (the bars' axial force added over the stage's
!! steps, the same at every point) or an in-situ stress (GEOSTATIC: a stress of its own at each
!! point, the `pattern`, added over the stage's steps), so such a point is updated like any other.
module feps_point_state_store
  use feps_kinds, only: dp, i8
  use feps_material, only: material_t, state_elastic
  implicit none
  private

  !> Committed and trial point states of one group (components (ncomp, npoints), internal
  !! variables (nvars, npoints), tangents (ncomp, ncomp, npoints)). Unallocated: the group
  !! keeps no point state.
  type, public :: point_state_store_t
    integer :: nvars = 0                                       !! internal variables per point
    real(dp), allocatable :: sig(:, :), eps(:, :)              !! committed stress, total strain
    integer, allocatable :: state(:)                           !! committed state flag (state_*)
    real(dp), allocatable :: vars(:, :)                        !! committed internal variables
    real(dp), allocatable :: dtan(:, :, :)                     !! committed tangent
    real(dp), allocatable :: sig_t(:, :), eps_t(:, :)          !! trial ...
    integer, allocatable :: state_t(:)
    real(dp), allocatable :: vars_t(:, :)
    real(dp), allocatable :: dtan_t(:, :, :)
    !> Stress increment imposed at the start of the step (see `impose`): `imposed` on every
    !! component of every point, or `imposed` times the point's `pattern` where one is set.
    real(dp) :: imposed = 0.0_dp
    logical :: imposing = .false.
    real(dp), allocatable :: pattern(:, :)                     !! (ncomp, npoints) or unallocated
  contains
    procedure :: init => store_init
    procedure :: impose => store_impose
    procedure :: update => store_update
    procedure :: set_stress => store_set_stress
    procedure :: commit => store_commit
    procedure :: restore => store_restore
    procedure :: bytes => store_bytes
    procedure :: kept => store_kept
  end type point_state_store_t

contains

  !> `npoints` points of `ncomp` components in their initial state: zero stress, strain and
  !! internal variables, elastic, with the material's elastic tangent, committed and trial.
  subroutine store_init(self, material, ncomp, npoints)
    class(point_state_store_t), intent(inout) :: self
    class(material_t), intent(in) :: material
    integer, intent(in) :: ncomp, npoints
    integer :: q
    self%nvars = material%state_size()
    allocate (self%sig(ncomp, npoints), self%eps(ncomp, npoints), self%state(npoints), &
              self%vars(self%nvars, npoints), self%dtan(ncomp, ncomp, npoints))
    self%sig = 0.0_dp
    self%eps = 0.0_dp
    self%state = state_elastic
    self%vars = 0.0_dp
    do q = 1, npoints
      call material%elastic_tangent(self%dtan(:, :, q))
    end do
    self%sig_t = self%sig
    self%eps_t = self%eps
    self%state_t = self%state
    self%vars_t = self%vars
    self%dtan_t = self%dtan
    self%imposed = 0.0_dp
    self%imposing = .false.
  end subroutine store_init

  !> The stress increment imposed on every point at the start of the steps updated from now
  !! on: `dsig` on every component, or `dsig` times the point's pattern where one is set (zero:
  !! none).
  pure subroutine store_impose(self, dsig)
    class(point_state_store_t), intent(inout) :: self
    real(dp), intent(in) :: dsig
    self%imposed = dsig
    self%imposing = dsig /= 0.0_dp
  end subroutine store_impose

  !> The trial state of point q: the material's update from the committed state (plus the
  !! imposed stress increment) over the strain increment `deps`.
  subroutine store_update(self, material, q, deps)
    class(point_state_store_t), intent(inout) :: self
    class(material_t), intent(in) :: material
    integer, intent(in) :: q
    real(dp), intent(in) :: deps(:)
    if (self%imposing .and. allocated(self%pattern)) then
      call material%update(self%sig(:, q) + self%imposed * self%pattern(:, q), self%eps(:, q), deps, self%state(q), &
                           self%sig_t(:, q), self%state_t(q), self%dtan_t(:, :, q), self%vars(:, q), self%vars_t(:, q))
    else if (self%imposing) then
      call material%update(self%sig(:, q) + self%imposed, self%eps(:, q), deps, self%state(q), &
                           self%sig_t(:, q), self%state_t(q), self%dtan_t(:, :, q), self%vars(:, q), self%vars_t(:, q))
    else
      call material%update(self%sig(:, q), self%eps(:, q), deps, self%state(q), &
                           self%sig_t(:, q), self%state_t(q), self%dtan_t(:, :, q), self%vars(:, q), self%vars_t(:, q))
    end if
    self%eps_t(:, q) = self%eps(:, q) + deps
  end subroutine store_update

  !> Every point's committed and trial stress set to `sig` (a group born carrying a force).
  pure subroutine store_set_stress(self, sig)
    class(point_state_store_t), intent(inout) :: self
    real(dp), intent(in) :: sig
    self%sig = sig
    self%sig_t = sig
  end subroutine store_set_stress

  !> Accept the trial state: it becomes the committed one.
  pure subroutine store_commit(self)
    class(point_state_store_t), intent(inout) :: self
    if (.not. self%kept()) return
    self%sig = self%sig_t
    self%eps = self%eps_t
    self%state = self%state_t
    self%vars = self%vars_t
    self%dtan = self%dtan_t
  end subroutine store_commit

  !> Back to the committed state (after a failed step).
  pure subroutine store_restore(self)
    class(point_state_store_t), intent(inout) :: self
    if (.not. self%kept()) return
    self%sig_t = self%sig
    self%eps_t = self%eps
    self%state_t = self%state
    self%vars_t = self%vars
    self%dtan_t = self%dtan
  end subroutine store_restore

  !> Memory held (bytes): committed and trial stresses, strains, flags, internal variables and
  !! tangents; 0 when the group keeps no point state.
  pure integer(i8) function store_bytes(self) result(bytes)
    class(point_state_store_t), intent(in) :: self
    bytes = 0
    if (.not. self%kept()) return
    bytes = 2 * (real_bytes(self%sig) + real_bytes(self%eps) + real_bytes(self%vars) + &
                 storage_size(self%state, i8) / 8 * size(self%state, kind=i8) + &
                 storage_size(self%dtan, i8) / 8 * size(self%dtan, kind=i8))
  contains
    pure integer(i8) function real_bytes(a)
      real(dp), intent(in) :: a(:, :)
      real_bytes = storage_size(a, i8) / 8 * size(a, kind=i8)
    end function real_bytes
  end function store_bytes

  !> True when the store holds point states (init was called).
  pure logical function store_kept(self)
    class(point_state_store_t), intent(in) :: self
    store_kept = allocated(self%sig)
  end function store_kept

end module feps_point_state_store
