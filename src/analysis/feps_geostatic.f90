!> The in-situ stress of a GEOSTATIC stage (the K0 procedure of PLAXIS; Abaqus's *GEOSTATIC
!! step after *INITIAL CONDITIONS, TYPE=STRESS, GEOSTATIC). The ground is horizontal layers,
!! one per ground material (a material with K0): a layer spans the heights of its elements'
!! nodes, heights measured against gravity, and the top layer reaches up to the ground surface
!! (SURFACE=). Two layers meet where their spans touch, or, when a water table is given (WATER=),
!! at the table where the lower layer's elements lie below it and the upper one's above it (by
!! their centres; a mesh need not follow the table: an element it cuts is wholly one or the
!! other, and the stage's balance iterations take up the difference).
!! At height h the vertical stress is the weight of the ground above,
!! sigma_v = sum over the layers of gamma |g| times their thickness between h and the surface,
!! and the horizontal stresses are K0 sigma_v (compression negative):
!!
!!     sigma = -sigma_v (K0 (I - d d^T) + d d^T),   d the unit vector of gravity.
!!
!! The stage imposes that stress on the points of the ground's solids, with the K0 of their own
!! material, and on the interfaces beside the ground (every node of one of their two faces is a
!! node of a ground element), as the tractions of the field on their plane with the K0 of the
!! layer at their height, while it applies the weight: over its steps both grow together. A
!! layered ground with horizontal surface is then in balance and does not move; what is not
!! ground (a pipe, with its weight) settles in it. After the stage the displacements count from
!! zero again and the stresses stay (see `end_geostatic_stage`).
module feps_geostatic
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t
  use feps_element_catalog, only: family_solid, family_interface
  use feps_analysis_state, only: analysis_t
  implicit none
  private

  public :: in_situ_field_t, build_in_situ_field, set_in_situ_stress, end_geostatic_stage

  !> One layer of ground: a ground material's span of heights, weight and K0.
  type :: ground_layer_t
    integer :: material = 0
    real(dp) :: bottom = 0.0_dp      !! height of its elements' lowest node
    real(dp) :: top = 0.0_dp         !! ... highest node (the top layer: the ground surface)
    real(dp) :: weight = 0.0_dp      !! gamma |g| (N/mm3)
    real(dp) :: k0 = 0.0_dp
  end type ground_layer_t

  !> The in-situ stress field: gravity's direction, the ground surface and the layers.
  type, public :: in_situ_field_t
    real(dp) :: down(3) = 0.0_dp                       !! unit vector along gravity
    real(dp) :: surface = 0.0_dp                       !! height of the ground surface
    type(ground_layer_t), allocatable :: layers(:)     !! bottom up
  contains
    procedure :: height => field_height
    procedure :: vertical_stress => field_vertical_stress
    procedure :: layer_k0 => field_layer_k0
    procedure :: tensor => field_tensor
  end type in_situ_field_t

contains

  !> Height of point x against gravity.
  pure real(dp) function field_height(self, x) result(h)
    class(in_situ_field_t), intent(in) :: self
    real(dp), intent(in) :: x(3)
    h = 0.0_dp - dot_product(self%down, x)   ! not -0 on the horizontal plane through 0
  end function field_height

  !> The vertical stress (positive: the weight of the ground above, per area) at height h.
  pure real(dp) function field_vertical_stress(self, h) result(sv)
    class(in_situ_field_t), intent(in) :: self
    real(dp), intent(in) :: h
    integer :: i
    sv = 0.0_dp
    do i = 1, size(self%layers)
      associate (l => self%layers(i))
        sv = sv + l%weight * max(0.0_dp, min(l%top, self%surface) - max(l%bottom, h))
      end associate
    end do
  end function field_vertical_stress

  !> K0 of the layer at height h (below the lowest layer: the lowest one's; above: the top one's).
  pure real(dp) function field_layer_k0(self, h) result(k0)
    class(in_situ_field_t), intent(in) :: self
    real(dp), intent(in) :: h
    integer :: i
    k0 = self%layers(1)%k0
    do i = 2, size(self%layers)
      if (h >= self%layers(i)%bottom) k0 = self%layers(i)%k0
    end do
  end function field_layer_k0

  !> The in-situ stress tensor at x with the given K0 (compression negative).
  pure function field_tensor(self, x, k0) result(sig)
    class(in_situ_field_t), intent(in) :: self
    real(dp), intent(in) :: x(3), k0
    real(dp) :: sig(3, 3)
    real(dp) :: sv, ddt(3, 3)
    integer :: i
    sv = self%vertical_stress(self%height(x))
    ddt = spread(self%down, 2, 3) * spread(self%down, 1, 3)
    sig = -sv * (1.0_dp - k0) * ddt
    do i = 1, 3
      sig(i, i) = sig(i, i) - sv * k0
    end do
  end function field_tensor

  !> Is group g active in the GEOSTATIC stage?
  pure logical function active_in_stage(model, g)
    type(model_t), intent(in) :: model
    integer, intent(in) :: g
    active_in_stage = max(model%groups(g)%activate_stage, 1) <= model%geostatic_stage
  end function active_in_stage

  !> The field of the model's GEOSTATIC record: one layer per ground material of the solids
  !! active in its stage. An input error naming the record when no active solid is ground, when
  !! two layers overlap or leave a gap between them (the ground must be horizontal layers), or
  !! when the surface lies below the top of the ground.
  subroutine build_in_situ_field(model, an, field, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(in) :: an
    type(in_situ_field_t), intent(out) :: field
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: lo(size(model%materials)), hi(size(model%materials)), h, tol, span
    real(dp) :: clo(size(model%materials)), chi(size(model%materials)), centre
    logical :: used(size(model%materials))
    integer :: g, m, n, i, k
    integer, allocatable :: order(:)
    field%down = model%gravity / norm2(model%gravity)
    field%surface = model%geostatic_surface
    used = .false.
    lo = huge(1.0_dp)
    hi = -huge(1.0_dp)
    clo = huge(1.0_dp)
    chi = -huge(1.0_dp)
    do g = 1, size(model%groups)
      m = model%groups(g)%material
      if (an%kernels(g)%family /= family_solid .or. .not. active_in_stage(model, g)) cycle
      if (.not. an%materials(m)%m%is_ground()) cycle
      used(m) = .true.
      do k = 1, size(model%groups(g)%connectivity, 2)
        centre = 0.0_dp
        do i = 1, size(model%groups(g)%connectivity, 1)
          n = model%groups(g)%connectivity(i, k)
          h = field%height(model%coords(:, n))
          lo(m) = min(lo(m), h)
          hi(m) = max(hi(m), h)
          centre = centre + h
        end do
        centre = centre / size(model%groups(g)%connectivity, 1)
        clo(m) = min(clo(m), centre)
        chi(m) = max(chi(m), centre)
      end do
    end do
    if (.not. any(used)) then
      call geostatic_error(error, model, 'no solid active in its stage has a material with K0= (the ground ' // &
                           'whose in-situ stress it sets)')
      return
    end if
    ! layers bottom up, by their elements' centres
    order = pack([(m, m = 1, size(used))], used)
    do i = 2, size(order)
      k = i
      do while (k > 1)
        if (clo(order(k - 1)) <= clo(order(k))) exit
        order([k - 1, k]) = order([k, k - 1])
        k = k - 1
      end do
    end do
    allocate (field%layers(size(order)))
    do i = 1, size(order)
      m = order(i)
      field%layers(i) = ground_layer_t(m, lo(m), hi(m), an%materials(m)%m%unit_weight * norm2(model%gravity), &
                                       an%materials(m)%m%k0)
    end do
    span = max(hi(order(size(order))) - lo(order(1)), abs(field%surface), 1.0_dp)
    tol = 1.0e-9_dp * span
    do i = 2, size(order)
      associate (below => field%layers(i - 1), above => field%layers(i))
        if (chi(below%material) < model%geostatic_water .and. model%geostatic_water < clo(above%material) .and. &
            above%bottom <= model%geostatic_water + tol .and. model%geostatic_water <= below%top + tol) then
          ! a submerged layer below the water table, a dry one above: they meet at the table
          below%top = model%geostatic_water
          above%bottom = model%geostatic_water
        else if (abs(above%bottom - below%top) > tol) then
          call geostatic_error(error, model, 'the ground must be horizontal layers, one per material with K0=: ' // &
                               'material ' // model%materials(below%material)%name // ' reaches height ' // &
                               str(below%top) // ' and material ' // model%materials(above%material)%name // &
                               ' starts at ' // str(above%bottom) // trim(merge(' (they overlap)', ' (a gap)       ', &
                               above%bottom < below%top)) // '; a submerged layer meets a dry one at the ' // &
                               'water table WATER=')
          return
        end if
        above%bottom = below%top   ! no sliver of round-off between them
      end associate
    end do
    associate (top => field%layers(size(order)))
      if (field%surface < top%top - tol) then
        call geostatic_error(error, model, 'SURFACE=' // str(field%surface) // ' lies below the top of the ' // &
                             'ground (material ' // model%materials(top%material)%name // ' reaches height ' // &
                             str(top%top) // ')')
        return
      end if
      top%top = field%surface  ! the top layer reaches the surface
    end associate
  end subroutine build_in_situ_field

  subroutine geostatic_error(error, model, message)
    type(error_t), allocatable, intent(out) :: error
    type(model_t), intent(in) :: model
    character(len=*), intent(in) :: message
    call input_error(error, model%geostatic_file, model%geostatic_line, 'GEOSTATIC: ' // message)
  end subroutine geostatic_error

  !> The stress the GEOSTATIC stage imposes on each point over its steps (the point-state
  !! stores' patterns): the field's, on the ground's solids (their own K0) and the interfaces
  !! beside them (the K0 of the layer at their height); no pattern elsewhere.
  subroutine set_in_situ_stress(model, an, error)
    type(model_t), intent(in) :: model
    type(analysis_t), intent(inout) :: an
    type(error_t), allocatable, intent(out) :: error
    type(in_situ_field_t) :: field
    logical, allocatable :: ground_node(:)
    real(dp), allocatable :: xe(:, :), xg(:, :), tensors(:, :, :), sig(:, :)
    integer :: g, e, q, np, nn, half
    logical :: taken, beside
    real(dp) :: k0
    call build_in_situ_field(model, an, field, error)
    if (allocated(error)) return
    allocate (ground_node(model%nnode))
    ground_node = .false.
    do g = 1, size(model%groups)
      if (an%kernels(g)%family /= family_solid .or. .not. active_in_stage(model, g)) cycle
      if (an%materials(model%groups(g)%material)%m%is_ground()) &
        ground_node(pack(model%groups(g)%connectivity, .true.)) = .true.
    end do
    do g = 1, size(model%groups)
      if (.not. active_in_stage(model, g) .or. .not. an%states(g)%kept()) cycle
      associate (k => an%kernels(g), conn => model%groups(g)%connectivity, s => an%states(g), &
                 mat => an%materials(model%groups(g)%material)%m)
        if (k%family == family_solid .and. .not. mat%is_ground()) cycle
        if (k%family /= family_solid .and. k%family /= family_interface) cycle
        np = k%npoints
        nn = k%nnodes
        half = nn / 2
        allocate (xe(3, nn), xg(3, np), tensors(3, 3, np), sig(k%ncomp, np))
        if (allocated(s%pattern)) deallocate (s%pattern)
        allocate (s%pattern(k%ncomp, np * size(conn, 2)))
        s%pattern = 0.0_dp
        do e = 1, size(conn, 2)
          ! an interface takes the ground's stress when one of its faces (lower layer nodes
          ! 1..half, upper half+1..) lies wholly on the ground
          beside = k%family == family_solid
          if (.not. beside) beside = all(ground_node(conn(1:half, e))) .or. all(ground_node(conn(half + 1:, e)))
          if (.not. beside) cycle
          xe = model%coords(:, conn(:, e))
          call k%element%point_coordinates(xe, xg)
          do q = 1, np
            k0 = mat%k0
            if (k%family /= family_solid) k0 = field%layer_k0(field%height(xg(:, q)))
            tensors(:, :, q) = field%tensor(xg(:, q), k0)
          end do
          call k%element%stresses_of_tensors(xe, tensors, sig, taken)
          if (taken) s%pattern(:, (e - 1) * np + 1:e * np) = sig
        end do
        deallocate (xe, xg, tensors, sig)
        if (all(s%pattern == 0.0_dp)) deallocate (s%pattern)
      end associate
    end do
  end subroutine set_in_situ_stress

  !> After the GEOSTATIC stage: displacements (and the prescribed values reached) count from
  !! zero again; stresses, states and the loads applied stay. Every group keeps its own point
  !! stress in a model with such a stage, so the internal forces do not depend on the
  !! displacements reset.
  subroutine end_geostatic_stage(an)
    type(analysis_t), intent(inout) :: an
    integer :: g
    an%path%u = 0.0_dp
    an%path%u_t = 0.0_dp
    an%path%uc = 0.0_dp
    do g = 1, size(an%states)
      if (allocated(an%states(g)%pattern)) deallocate (an%states(g)%pattern)
    end do
  end subroutine end_geostatic_stage

end module feps_geostatic
