!> REPORT, JOINT (issue 26 item 5): the design summary of a pipe joint from a solved model's last
!! step: the largest hoop tension and axial compression in the pipes beside the joint, the joint's
!! largest normal compression, contact width Z (thesis 7.4.3), opening and deflection angle, the
!! load through it, and the Australian and Haslem models (thesis 7.2) for the same pipe, packing,
!! load and Z. Physics only: the program prints it and writes it to the results file.
module feps_joint_report
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf, ieee_is_finite
  use feps_kinds, only: dp, rad2deg, deg2rad
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t, report_t
  use feps_coordinate_system, only: coordinate_system_t
  use feps_element, only: element_t
  use feps_element_catalog, only: new_element, point_coordinates
  use feps_material, only: material_t, state_open
  use feps_material_factory, only: material_of
  use feps_observer, only: group_result_t
  use feps_stress_frames, only: stresses_in_system
  use feps_joint_models, only: joint_t, joint_solution_t, australian, haslem, annulus_area
  implicit none
  private

  public :: joint_geometry_t, joint_summary_t, joint_geometry, joint_summary

  !> What the mesh and materials say of a joint (REPORT, JOINT), before anything is solved.
  type :: joint_geometry_t
    type(coordinate_system_t) :: system         !! the cylindrical system about the pipe axis
    real(dp) :: outer_radius = 0.0_dp           !! R, r: the interface's extreme node radii (mm)
    real(dp) :: inner_radius = 0.0_dp
    real(dp) :: joint_z = 0.0_dp                !! the interface's mean axial coordinate (mm)
    real(dp) :: area = 0.0_dp                   !! the interface's area (mm2)
    integer :: copies = 1                       !! copies of the mesh that make the whole annulus
    real(dp) :: packing_thickness = 0.0_dp      !! a (mm; 0: not known: no PACKING= and no A=)
    real(dp) :: pipe_length = 0.0_dp            !! L (mm)
    real(dp) :: concrete_modulus = 0.0_dp       !! E_c of the first PIPE group (MPa)
    real(dp) :: packing_modulus = 0.0_dp        !! E_p of the PACKING group (MPa; 0: no PACKING=)
    real(dp), allocatable :: weight(:)          !! each interface point's area (mm2)
    real(dp), allocatable :: at(:, :)           !! (3, points) each interface point's r, theta, z
    real(dp) :: edge = 0.0_dp                   !! theta of the loaded edge (deg, EDGE=)
    real(dp), allocatable :: along(:)           !! each point's coordinate along the loaded edge's direction
    integer, allocatable :: ring(:)             !! each point's ring (its radius), 1..rings
    integer :: rings = 0
  end type joint_geometry_t

  !> The design summary of a joint (REPORT, JOINT). Stresses in MPa, tension positive, except
  !! `sigma_max` (the joint's largest normal compression, positive as the models give it);
  !! positions (r, theta in degrees, z) in the report's cylindrical system.
  type :: joint_summary_t
    type(joint_geometry_t) :: geometry
    real(dp) :: reach = 0.0_dp                                !! NEAR=: the pipes' points within it count
    real(dp) :: hoop_max = 0.0_dp, hoop_at(3) = 0.0_dp        !! largest s_tt in the pipes
    integer :: hoop_group = 0
    real(dp) :: axial_min = 0.0_dp, axial_at(3) = 0.0_dp      !! most negative s_zz in the pipes
    integer :: axial_group = 0
    real(dp) :: sigma_max = 0.0_dp, sigma_max_at(3) = 0.0_dp  !! largest -sigma_n on the interface
    real(dp) :: contact_width = 0.0_dp                        !! Z (mm); +inf: no gap front anywhere
    real(dp) :: opening = 0.0_dp, opening_at(3) = 0.0_dp      !! largest eps_n (mm; > 0 open)
    logical :: has_deflection = .false.                       !! two PIPE groups: their end faces
    real(dp) :: deflection = 0.0_dp                           !! relative rotation of the faces (deg)
    real(dp) :: face_z(2) = 0.0_dp                            !! the two end faces' axial coordinates
    real(dp) :: load = 0.0_dp                                 !! P through the whole joint (N)
    logical :: has_models = .false.
    character(len=:), allocatable :: models_note              !! why the models were not evaluated
    type(joint_solution_t) :: australian, haslem              !! at this P and Z
  end type joint_summary_t

contains

  !> The joint's geometry from the mesh and the materials: the interface's radii about the
  !! report's cylindrical system (CSYS=, else FIELDS CSYS=), its points' positions and areas
  !! (the area from the interface element's own integration: its internal force under a unit
  !! normal traction at one point), the rings of points (points whose radii differ by less than
  !! 1e-3 R form one ring), the copies of the mesh that make the annulus (1, 2 or 4 from the
  !! area, unless P= is given), a from A= or the packing's axial extent, L from L= or the longest
  !! PIPE group's axial extent, and the moduli from the groups' elastic tangents.
  subroutine joint_geometry(model, r, geo, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    type(joint_geometry_t), intent(out) :: geo
    type(error_t), allocatable, intent(out) :: error
    class(element_t), allocatable :: element
    real(dp), allocatable :: xg(:, :), sig(:, :), fe(:), radius(:)
    integer, allocatable :: order(:), nodes(:)
    real(dp) :: c(3), ratio, extent, tol, edge_dir(2)
    integer :: e, p, q, np, npairs, k
    geo%system = model%systems(merge(r%csys, model%fields%csys, r%csys /= 0))
    geo%edge = r%edge
    associate (group => model%groups(r%interface_group), conn => model%groups(r%interface_group)%connectivity)
      nodes = pack(conn, .true.)
      geo%outer_radius = 0.0_dp
      geo%inner_radius = huge(1.0_dp)
      do k = 1, size(nodes)
        c = geo%system%from_global(model%coords(:, nodes(k)))
        geo%outer_radius = max(geo%outer_radius, c(1))
        geo%inner_radius = min(geo%inner_radius, c(1))
      end do
      call new_element(group%element_type, element, error)
      if (allocated(error)) return
      call point_coordinates(group%element_type, model%coords, conn, xg, error)
      if (allocated(error)) return
      np = element%npoints()
      npairs = size(conn, 1) / 2
      allocate (geo%weight(size(xg, 2)), geo%at(3, size(xg, 2)), geo%along(size(xg, 2)))
      allocate (sig(element%ncomp(), np), fe(3 * size(conn, 1)))
      edge_dir = [cos(r%edge * deg2rad), sin(r%edge * deg2rad)]
      do e = 1, size(conn, 2)
        do q = 1, np
          p = (e - 1) * np + q
          sig = 0.0_dp
          sig(element%ncomp(), q) = 1.0_dp
          call element%internal_force(model%coords(:, conn(:, e)), sig, fe)
          ! the upper layer's nodal forces add up to the point's area times its unit normal
          geo%weight(p) = norm2(sum(reshape(fe(3 * npairs + 1:), [3, npairs]), dim=2))
          geo%at(:, p) = geo%system%from_global(xg(:, p))
          c = matmul(transpose(geo%system%axes), xg(:, p) - geo%system%origin)
          geo%along(p) = c(1) * edge_dir(1) + c(2) * edge_dir(2)
        end do
      end do
    end associate
    geo%area = sum(geo%weight)
    geo%joint_z = sum(geo%weight * geo%at(3, :)) / geo%area
    ratio = annulus_area(geo%outer_radius, geo%inner_radius) / geo%area
    geo%copies = 2**(minloc(abs(log(ratio / [1.0_dp, 2.0_dp, 4.0_dp])), dim=1) - 1)
    if (.not. r%has_p .and. abs(ratio / geo%copies - 1.0_dp) > 0.15_dp) then
      call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': the interface covers ' // &
                       str(100.0_dp / ratio) // '% of the annulus R = ' // str(geo%outer_radius) // ', r = ' // &
                       str(geo%inner_radius) // ', not the whole, a half or a quarter of it: give the joint load P=')
      return
    end if
    ! rings: the points sorted by radius; a new ring where the radius jumps by more than 1e-3 R
    radius = geo%at(1, :)
    order = sorted(radius)
    tol = 1.0e-3_dp * geo%outer_radius
    allocate (geo%ring(size(radius)))
    geo%rings = 1
    geo%ring(order(1)) = 1
    do k = 2, size(order)
      if (radius(order(k)) - radius(order(k - 1)) > tol) geo%rings = geo%rings + 1
      geo%ring(order(k)) = geo%rings
    end do

    geo%concrete_modulus = youngs_modulus(r%pipe_groups(1))
    if (allocated(error)) return
    if (r%has_l) then
      geo%pipe_length = r%pipe_length
    else
      do k = 1, size(r%pipe_groups)
        geo%pipe_length = max(geo%pipe_length, axial_extent(r%pipe_groups(k)))
      end do
    end if
    if (r%has_a) then
      geo%packing_thickness = r%packing_thickness
    else if (r%packing_group /= 0) then
      geo%packing_thickness = axial_extent(r%packing_group)
    end if
    if (r%packing_group /= 0) then
      geo%packing_modulus = youngs_modulus(r%packing_group)
      if (allocated(error)) return
    end if
    extent = axial_extent(r%interface_group)
    if (extent > 1.0e-3_dp * geo%outer_radius) then
      call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': the interface group ' // &
                       model%groups(r%interface_group)%name // ' spans ' // str(extent) // ' mm along the pipe ' // &
                       'axis: a joint interface lies in one section (is CSYS= the pipe''s axis?)')
    end if
  contains
    !> Young's modulus of a group's material from its elastic tangent (isotropic: D11 and D12).
    real(dp) function youngs_modulus(g)
      integer, intent(in) :: g
      class(material_t), allocatable :: material
      real(dp) :: d(6, 6)
      youngs_modulus = 0.0_dp
      call material_of(model%materials(model%groups(g)%material), material, error)
      if (allocated(error)) return
      call material%elastic_tangent(d)
      youngs_modulus = (d(1, 1) - d(1, 2)) * (d(1, 1) + 2.0_dp * d(1, 2)) / (d(1, 1) + d(1, 2))
    end function youngs_modulus

    !> The span of a group's nodes along the system's axis.
    real(dp) function axial_extent(g)
      integer, intent(in) :: g
      real(dp), allocatable :: z(:)
      z = matmul(geo%system%axes(:, 3), model%coords(:, pack(model%groups(g)%connectivity, .true.)))
      axial_extent = maxval(z) - minval(z)
    end function axial_extent
  end subroutine joint_geometry

  !> The design summary of the joint of REPORT `r` from the last step's displacements `u`
  !! (3, nnode) and point results `groups` (see joint_summary_t; docs/output-format.md).
  subroutine joint_summary(model, r, u, groups, js, error)
    type(model_t), intent(in) :: model
    type(report_t), intent(in) :: r
    real(dp), intent(in) :: u(:, :)
    type(group_result_t), intent(in) :: groups(:)
    type(joint_summary_t), intent(out) :: js
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: xg(:, :), local(:, :)
    real(dp) :: slope(2), centre(2), c(3), reach
    logical, allocatable :: near(:)
    integer :: k, g, p
    call joint_geometry(model, r, js%geometry, error)
    if (allocated(error)) return
    associate (geo => js%geometry)
      ! the pipes' points within NEAR= (default the outer diameter) of the joint's section
      reach = merge(r%near, 2.0_dp * geo%outer_radius, r%near > 0.0_dp)
      js%reach = reach
      allocate (near(maxval([(size(model%groups(r%pipe_groups(k))%connectivity, 2) * &
                              model%groups(r%pipe_groups(k))%element%npoints, k = 1, size(r%pipe_groups))])))
      ! the pipes: hoop tension and axial compression at their points
      js%hoop_max = -huge(1.0_dp)
      js%axial_min = huge(1.0_dp)
      do k = 1, size(r%pipe_groups)
        g = r%pipe_groups(k)
        if (.not. allocated(groups(g)%stress)) cycle
        call point_coordinates(model%groups(g)%element_type, model%coords, model%groups(g)%connectivity, xg, error)
        if (allocated(error)) return
        local = stresses_in_system(groups(g)%stress, xg, geo%system)
        do p = 1, size(xg, 2)
          c = geo%system%from_global(xg(:, p))
          near(p) = abs(c(3) - geo%joint_z) <= reach
        end do
        if (.not. any(near(:size(xg, 2)))) cycle
        p = maxloc(local(2, :), dim=1, mask=near(:size(xg, 2)))
        if (local(2, p) > js%hoop_max) then
          js%hoop_max = local(2, p)
          js%hoop_at = geo%system%from_global(xg(:, p))
          js%hoop_group = g
        end if
        p = minloc(local(3, :), dim=1, mask=near(:size(xg, 2)))
        if (local(3, p) < js%axial_min) then
          js%axial_min = local(3, p)
          js%axial_at = geo%system%from_global(xg(:, p))
          js%axial_group = g
        end if
      end do
      if (js%hoop_group == 0) then
        js%hoop_max = 0.0_dp
        js%axial_min = 0.0_dp
      end if

      ! the interface: compression, opening, load and contact width
      associate (res => groups(r%interface_group))
        if (.not. (allocated(res%stress) .and. allocated(res%strain) .and. allocated(res%state))) then
          call input_error(error, r%file, r%line, 'REPORT ' // r%name // ': the interface group ' // &
                           model%groups(r%interface_group)%name // ' has no results in the last step written')
          return
        end if
        p = minloc(res%stress(3, :), dim=1)
        js%sigma_max = -res%stress(3, p)
        js%sigma_max_at = geo%at(:, p)
        p = maxloc(res%strain(3, :), dim=1)
        js%opening = res%strain(3, p)
        js%opening_at = geo%at(:, p)
        js%load = -geo%copies * sum(res%stress(3, :) * geo%weight)
        if (r%has_p) js%load = r%load
        js%contact_width = contact_width(geo, res%stress(3, :), res%state)
      end associate

      if (size(r%pipe_groups) == 2) then
        do k = 1, 2
          call end_face_slope(r%pipe_groups(k), slope(k), js%face_z(k), centre(k))
        end do
        ! the upper pipe's face less the lower's: positive when the joint closes at the edge
        if (centre(1) > centre(2)) then
          slope = slope([2, 1])
          js%face_z = js%face_z([2, 1])
        end if
        js%deflection = -atan(slope(2) - slope(1)) * rad2deg
        js%has_deflection = .true.
      end if
      call joint_models(r, js)
    end associate
  contains
    !> The least-squares slope of the axial displacement over the coordinate along the loaded
    !! edge's direction, on the end face of pipe group `g` nearest the joint (its nodes on the
    !! section closest to the interface's); with the face's axial coordinate and the group's
    !! mean node axial coordinate (which side of the joint it is on).
    subroutine end_face_slope(g, b, face, mean_z)
      integer, intent(in) :: g
      real(dp), intent(out) :: b, face, mean_z
      real(dp), allocatable :: s(:), w(:)
      integer, allocatable :: nodes(:)
      logical, allocatable :: member(:)
      real(dp) :: c(3), zn, dist, tol, edge_dir(2)
      integer :: n
      associate (geo => js%geometry)
        allocate (member(model%nnode))
        member = .false.
        member(pack(model%groups(g)%connectivity, .true.)) = .true.
        nodes = pack([(n, n = 1, model%nnode)], member)
        dist = huge(1.0_dp)
        mean_z = 0.0_dp
        do n = 1, size(nodes)
          zn = axial(nodes(n))
          mean_z = mean_z + zn / size(nodes)
          if (abs(zn - geo%joint_z) < dist) then
            dist = abs(zn - geo%joint_z)
            face = zn
          end if
        end do
        tol = 1.0e-6_dp * max(1.0_dp, geo%outer_radius)
        edge_dir = [cos(r%edge * deg2rad), sin(r%edge * deg2rad)]
        allocate (s(0), w(0))
        do n = 1, size(nodes)
          if (abs(axial(nodes(n)) - face) > tol) cycle
          c = matmul(transpose(geo%system%axes), model%coords(:, nodes(n)) - geo%system%origin)
          s = [s, c(1) * edge_dir(1) + c(2) * edge_dir(2)]
          w = [w, dot_product(geo%system%axes(:, 3), u(:, nodes(n)))]
        end do
        b = line_slope(s, w)
      end associate
    end subroutine end_face_slope

    real(dp) function axial(n)
      integer, intent(in) :: n
      real(dp) :: c(3)
      c = js%geometry%system%from_global(model%coords(:, n))
      axial = c(3)
    end function axial
  end subroutine joint_summary

  !> Z (thesis 7.4.3; scripts/postprocess_model_c.py's reading): on each ring of interface points,
  !! taken from the loaded edge across the diameter (by their angular distance from EDGE=), the
  !! front of the contact zone is where sigma_n reaches zero: linear interpolation between the
  !! last compressive point and the next; when that next point is open (sigma_n = 0 exactly) the
  !! line through the last two compressive points extended to zero (kept between the two points;
  !! the one before the last taken at another s, as a whole ring's mirror pairs share theirs).
  !! A ring without a non-compressive point has no gap: the zero of the least-squares line
  !! sigma_n(s) through all its points; a ring open at the edge gives its first point. Z = R less
  !! the zero's coordinate s along the edge's direction, averaged over the rings of 2 or more points.
  function contact_width(geo, sn, state) result(z)
    type(joint_geometry_t), intent(in) :: geo
    real(dp), intent(in) :: sn(:)
    integer, intent(in) :: state(:)
    real(dp) :: z
    real(dp), allocatable :: s(:), v(:)
    integer, allocatable :: idx(:), order(:)
    real(dp) :: zero, a, b, total
    integer :: ring, k, p, used, j
    total = 0.0_dp
    used = 0
    do ring = 1, geo%rings
      idx = pack([(p, p = 1, size(sn))], geo%ring == ring)
      if (size(idx) < 2) cycle
      order = sorted(edge_distance(idx))
      idx = idx(order)
      s = geo%along(idx)
      v = sn(idx)
      k = findloc(v >= 0.0_dp, .true., dim=1)
      if (k == 0) then
        call line_fit(s, v, a, b)
        if (b == 0.0_dp) then
          total = ieee_value(total, ieee_positive_inf)
          used = used + 1
          cycle
        end if
        zero = -a / b
      else if (k == 1) then
        zero = s(1)
      else if (state(idx(k)) >= state_open .and. k >= 3) then
        ! the compressive point before the last at another s: on a whole ring the points come in
        ! mirror pairs about the plane of deflection (equal s and sigma_n), whose line is no line
        j = k - 2
        do while (j > 1 .and. abs(s(j) - s(k - 1)) <= 1.0e-9_dp * geo%outer_radius)
          j = j - 1
        end do
        if (v(k - 1) /= v(j)) then
          zero = s(k - 1) - v(k - 1) * (s(k - 1) - s(j)) / (v(k - 1) - v(j))
        else
          zero = s(k - 1)
        end if
        zero = min(max(zero, s(k)), s(k - 1))
      else
        zero = s(k - 1) + v(k - 1) / (v(k - 1) - v(k)) * (s(k) - s(k - 1))
      end if
      total = total + (geo%outer_radius - zero)
      used = used + 1
    end do
    z = total / max(used, 1)
  contains
    !> The points' angular distances (deg, 0..180) from the loaded edge.
    function edge_distance(points) result(d)
      integer, intent(in) :: points(:)
      real(dp) :: d(size(points))
      d = abs(modulo(geo%at(2, points) - geo%edge + 180.0_dp, 360.0_dp) - 180.0_dp)
    end function edge_distance
  end function contact_width

  !> The Australian and Haslem models for the joint's pipe, packing, load P and contact width Z:
  !! each one's sigma_max and beta (feps_joint_models), when a packing modulus and thickness are
  !! known, P > 0 and Z is finite and positive.
  subroutine joint_models(r, js)
    type(report_t), intent(in) :: r
    type(joint_summary_t), intent(inout) :: js
    type(joint_t) :: joint
    type(error_t), allocatable :: error
    associate (geo => js%geometry)
      if (geo%packing_modulus <= 0.0_dp .or. geo%packing_thickness <= 0.0_dp) then
        js%models_note = 'no PACKING= group: no packing modulus'
        if (r%packing_group /= 0) js%models_note = 'the packing has no thickness'
        return
      end if
      if (.not. js%load > 0.0_dp) then
        js%models_note = 'the joint carries no compression (P = ' // str(js%load) // ' N)'
        return
      end if
      if (.not. (ieee_is_finite(js%contact_width) .and. js%contact_width > 0.0_dp)) then
        js%models_note = 'no contact width (Z = ' // str(js%contact_width) // ' mm)'
        return
      end if
      joint%packing_thickness = geo%packing_thickness
      joint%pipe_length = geo%pipe_length
      joint%concrete_modulus = geo%concrete_modulus
      joint%packing_modulus = geo%packing_modulus
      joint%outer_radius = geo%outer_radius
      joint%inner_radius = geo%inner_radius
      call australian(joint, js%australian, error, z=js%contact_width, load=js%load)
      if (.not. allocated(error)) call haslem(joint, js%haslem, error, z=js%contact_width, load=js%load)
      if (allocated(error)) then
        js%models_note = error%message
        return
      end if
      js%has_models = .true.
    end associate
  end subroutine joint_models

  !> (a, b) of the least-squares line y = a + b x.
  pure subroutine line_fit(x, y, a, b)
    real(dp), intent(in) :: x(:), y(:)
    real(dp), intent(out) :: a, b
    real(dp) :: mx, my, sxx
    mx = sum(x) / size(x)
    my = sum(y) / size(y)
    sxx = sum((x - mx)**2)
    b = 0.0_dp
    if (sxx > 0.0_dp) b = sum((x - mx) * (y - my)) / sxx
    a = my - b * mx
  end subroutine line_fit

  pure real(dp) function line_slope(x, y) result(b)
    real(dp), intent(in) :: x(:), y(:)
    real(dp) :: a
    call line_fit(x, y, a, b)
  end function line_slope

  !> The permutation that sorts `v` ascending (stable insertion sort: a ring has tens to
  !! hundreds of points).
  pure function sorted(v) result(order)
    real(dp), intent(in) :: v(:)
    integer :: order(size(v))
    integer :: i, j, t
    order = [(i, i = 1, size(v))]
    do i = 2, size(v)
      t = order(i)
      j = i - 1
      do while (j >= 1)
        if (v(order(j)) <= v(t)) exit
        order(j + 1) = order(j)
        j = j - 1
      end do
      order(j + 1) = t
    end do
  end function sorted

end module feps_joint_report
