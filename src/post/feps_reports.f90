!> The REPORT quantities of a solved model (thesis 7.3): the rotation of a pipe section from
!! the axial displacements on a ring of nodes, the tilt of a group's axis, and the forces and
!! moments through a section. Physics only: the program prints them and writes them to the
!! results file.
module feps_reports
  use feps_kinds, only: dp, rad2deg
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t, report_t
  use feps_element, only: element_t
  use feps_element_catalog, only: new_element
  use feps_observer, only: group_result_t
  implicit none
  private

  public :: section_rotation, axis_tilt, section_forces

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

  !> Forces and moments through the section z = r%z (REPORT, SECTION; Abaqus's free-body cut):
  !! the internal nodal forces (B^T sigma) of the elements below the plane at their nodes on it,
  !! summed: `force` = (Vx, Vy, N), the traction resultant on the cut with outward normal +z
  !! (N: tension positive), and `moment` = (Mx, My, T) about (X0, Y0, z). By each node's
  !! equilibrium this equals the applied loads and reactions on everything above the plane
  !! (where none act on the plane's own nodes), whatever the mesh. The elements of group r%group
  !! (every group when 0) with all nodes at or below the plane count; one with nodes on both
  !! sides is an input error (the plane must follow a layer of nodes), as is a plane with no
  !! element below it. `groups` holds each group's point stresses (zero: checks the mesh only).
  subroutine section_forces(model, r, groups, force, moment, count, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    type(group_result_t), intent(in) :: groups(:)
    real(dp), intent(out) :: force(3), moment(3)
    integer, intent(out) :: count                  !! elements below the plane with a node on it
    type(error_t), allocatable, intent(out) :: error
    class(element_t), allocatable :: element
    real(dp), allocatable :: fe(:), sig(:, :)
    real(dp) :: tol, arm(3)
    integer :: g, e, a, n, np
    logical :: on_plane, above, below
    force = 0.0_dp
    moment = 0.0_dp
    count = 0
    tol = 1.0e-6_dp * max(1.0_dp, maxval(abs(model%coords(3, :))))
    do g = 1, size(model%groups)
      if (r%group /= 0 .and. g /= r%group) cycle
      associate (conn => model%groups(g)%connectivity)
        call new_element(model%groups(g)%element_type, element, error)
        if (allocated(error)) return
        np = element%npoints()
        allocate (fe(3 * size(conn, 1)), sig(element%ncomp(), np))
        do e = 1, size(conn, 2)
          above = any(model%coords(3, conn(:, e)) > r%z + tol)
          below = any(model%coords(3, conn(:, e)) < r%z - tol)
          on_plane = any(abs(model%coords(3, conn(:, e)) - r%z) <= tol)
          if (above .and. below) then
            call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': the section z = ' // str(r%z) // &
                             ' cuts through element ' // str(e) // ' of group ' // model%groups(g)%name // &
                             ': put the section on a layer of nodes')
            return
          end if
          if (above .or. .not. on_plane) cycle
          count = count + 1
          sig = 0.0_dp
          if (g <= size(groups)) then
            if (allocated(groups(g)%stress)) sig = groups(g)%stress(:, (e - 1) * np + 1:e * np)
          end if
          call element%internal_force(model%coords(:, conn(:, e)), sig, fe)
          do a = 1, size(conn, 1)
            n = conn(a, e)
            if (abs(model%coords(3, n) - r%z) > tol) cycle
            force = force + fe(3 * a - 2:3 * a)
            arm = [model%coords(1, n) - r%about(1), model%coords(2, n) - r%about(2), 0.0_dp]
            moment = moment + cross(arm, fe(3 * a - 2:3 * a))
          end do
        end do
        deallocate (fe, sig)
      end associate
    end do
    if (count == 0) call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': no element lies below ' // &
                                     'the section z = ' // str(r%z) // ' with a node on it')
  contains
    pure function cross(p, q) result(c)
      real(dp), intent(in) :: p(3), q(3)
      real(dp) :: c(3)
      c = [p(2) * q(3) - p(3) * q(2), p(3) * q(1) - p(1) * q(3), p(1) * q(2) - p(2) * q(1)]
    end function cross
  end subroutine section_forces

end module feps_reports
