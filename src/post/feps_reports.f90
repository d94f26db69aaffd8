!> The REPORT quantities of a solved model (thesis 7.3): the rotation of a pipe section from
!! the axial displacements on a ring of nodes, and the tilt of a group's axis. Physics only: the
!! program prints them and writes them to the results file.
module feps_reports
  use feps_kinds, only: dp, rad2deg
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t, report_t
  implicit none
  private

  public :: section_rotation, axis_tilt

contains

  !> Rotation (degrees) of the section z = r%z from the axial displacements w of the group's
  !! nodes on r = R (thesis 7.3): (w(x1) - w(x0)) / (x1 - x0), with w interpolated linearly in x
  !! between those nodes, over FROM=x0 .. TO=x1 (the loaded region for the edge load: the slope
  !! the Australian model's linear compression has) or between the extreme nodes.
  subroutine section_rotation(model, r, u, angle, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: angle
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: on_ring(:)
    integer, allocatable :: ring(:), order(:)
    real(dp), allocatable :: xs(:), ws(:)
    real(dp) :: tol, x0, x1
    integer :: n, i, j, t
    allocate (on_ring(model%nnode))
    on_ring = .false.
    on_ring(pack(model%groups(r%group)%connectivity, .true.)) = .true.
    tol = 1.0e-6_dp * max(1.0_dp, r%r)
    do n = 1, model%nnode
      if (.not. on_ring(n)) cycle
      on_ring(n) = abs(hypot(model%coords(1, n), model%coords(2, n)) - r%r) <= tol .and. &
                   abs(model%coords(3, n) - r%z) <= tol
    end do
    ring = pack([(n, n = 1, model%nnode)], on_ring)
    if (size(ring) < 2) then
      call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': group ' // model%groups(r%group)%name // &
                       ' has no two nodes on r = ' // str(r%r) // ', z = ' // str(r%z))
      return
    end if
    ! nodes sorted by x (insertion sort: a ring has tens of nodes)
    order = [(i, i = 1, size(ring))]
    do i = 2, size(order)
      t = order(i)
      j = i - 1
      do while (j >= 1)
        if (model%coords(1, ring(order(j))) <= model%coords(1, ring(t))) exit
        order(j + 1) = order(j)
        j = j - 1
      end do
      order(j + 1) = t
    end do
    xs = model%coords(1, ring(order))
    ws = u(3, ring(order))
    x0 = xs(1)
    x1 = xs(size(xs))
    if (.not. r%has_span .and. x1 - x0 <= tol) then
      call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': the nodes of group ' // &
                       model%groups(r%group)%name // ' on r = ' // str(r%r) // ', z = ' // str(r%z) // &
                       ' all lie at x = ' // str(x0) // ': no slope to measure')
      return
    end if
    if (r%has_span) then
      x0 = r%x_from
      x1 = r%x_to
      if (min(x0, x1) < xs(1) - tol .or. max(x0, x1) > xs(size(xs)) + tol) then
        call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': FROM/TO lie outside the ring of nodes')
        return
      end if
    end if
    angle = atan((interpolate(x1) - interpolate(x0)) / (x1 - x0)) * rad2deg
    if (angle == 0.0_dp) angle = 0.0_dp   ! a zero slope over x1 < x0 is -0: printed as 0, not -0
  contains
    real(dp) function interpolate(x)
      real(dp), intent(in) :: x
      integer :: k
      k = 1
      do while (k < size(xs) - 1)
        if (xs(k + 1) >= x) exit
        k = k + 1
      end do
      interpolate = ws(k) + (ws(k + 1) - ws(k)) * (x - xs(k)) / max(xs(k + 1) - xs(k), tiny(1.0_dp))
    end function interpolate
  end subroutine section_rotation

  !> Tilt (degrees) of a group's axis between the sections z = FROM and z = TO: the mean ux of
  !! the group's nodes on each section, -atan(d ux / d z), so that a rigid rotation of the
  !! group gives the same angle as REPORT, ROTATION does from the slope of w (thesis 7.3: the
  !! rigid-body rotation of the pipe in the soil).
  subroutine axis_tilt(model, r, u, angle, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: angle
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: ux0, ux1
    logical, allocatable :: in_group(:)
    allocate (in_group(model%nnode))
    in_group = .false.
    in_group(pack(model%groups(r%group)%connectivity, .true.)) = .true.
    call section_mean_ux(r%x_from, ux0)
    if (allocated(error)) return
    call section_mean_ux(r%x_to, ux1)
    if (allocated(error)) return
    angle = -atan((ux1 - ux0) / (r%x_to - r%x_from)) * rad2deg
    if (angle == 0.0_dp) angle = 0.0_dp   ! -atan(0) is -0: printed and written as 0, not -0
  contains
    subroutine section_mean_ux(z, ux)
      real(dp), intent(in) :: z
      real(dp), intent(out) :: ux
      real(dp) :: tol
      integer :: n, count
      tol = 1.0e-6_dp * max(1.0_dp, abs(z))
      ux = 0.0_dp
      count = 0
      do n = 1, model%nnode
        if (.not. in_group(n) .or. abs(model%coords(3, n) - z) > tol) cycle
        ux = ux + u(1, n)
        count = count + 1
      end do
      if (count == 0) then
        call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': group ' // &
                         model%groups(r%group)%name // ' has no node on the section z = ' // str(z))
        return
      end if
      ux = ux / count
    end subroutine section_mean_ux
  end subroutine axis_tilt

end module feps_reports
