!> External loads: face sets resolved from element faces, consistent nodal forces of
!! pressures and tractions (uniform or linear in one coordinate, by intensity or total),
!! of gravity (each element's weight), and nodal forces. Forces are assembled in global Cartesian components per node, then
!! rotated into nodal systems for the free equations.
module feps_loads
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
  use feps_kinds, only: dp
  use feps_error, only: error_t, input_error, str
  use feps_model, only: model_t, face_load_t, in_region, load_pressure, load_traction
  use feps_coordinate_system, only: csys_cylindrical
  use feps_dof_map, only: dof_map_t
  use feps_assembly, only: group_kernel_t
  use feps_solid_element, only: solid_element_t
  use feps_material, only: material_t
  use feps_material_factory, only: material_of
  implicit none
  private

  public :: resolve_face_sets, nodal_load_vector, to_equations, face_load_intensity_integral

contains

  !> Faces of the set's group whose nodes all lie in the set's region. Faces are a solid's:
  !! a set on a group of another family is an input error.
  subroutine resolve_face_sets(model, kernels, error)
    type(model_t), intent(inout) :: model
    type(group_kernel_t), intent(in) :: kernels(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: s, g, e, f, k, nfound
    integer, allocatable :: fn(:), elems(:), faces(:)
    logical :: all_in
    class(solid_element_t), allocatable :: solid

    do s = 1, size(model%face_sets)
      g = model%face_sets(s)%group
      call solid_of(kernels(g), solid)
      if (.not. allocated(solid)) then
        call input_error(error, model%face_sets(s)%file, model%face_sets(s)%line, 'face set ' // &
                         model%face_sets(s)%name // ': group ' // model%groups(g)%name // ' (' // &
                         model%groups(g)%element_type // ') has no faces; face sets take faces of solid elements')
        return
      end if
      if (model%face_sets(s)%listed) then
        ! FSET LIST: the faces are given; their numbers are the element's (CalculiX's for solids)
        do k = 1, size(model%face_sets(s)%face)
          if (model%face_sets(s)%face(k) > solid%nfaces()) then
            e = model%face_sets(s)%element(k)
            if (allocated(model%groups(g)%element_ids)) e = model%groups(g)%element_ids(e)
            call input_error(error, model%face_sets(s)%file, model%face_sets(s)%row_line(k), 'face set ' // &
                             model%face_sets(s)%name // ': element ' // str(e) // ' (' // &
                             model%groups(g)%element_type // ') has faces 1 to ' // str(solid%nfaces()) // ', not ' // &
                             str(model%face_sets(s)%face(k)), model%face_sets(s)%row_field(k))
            return
          end if
        end do
        cycle
      end if
      allocate (elems(0), faces(0))
      nfound = 0
      do e = 1, size(model%groups(g)%connectivity, 2)
        do f = 1, solid%nfaces()
          fn = solid%face_nodes(f)
          all_in = .true.
          do k = 1, size(fn)
            if (.not. in_region(model%face_sets(s)%region, model%systems(model%face_sets(s)%region%csys), &
                                model%coords(:, model%groups(g)%connectivity(fn(k), e)))) then
              all_in = .false.
              exit
            end if
          end do
          if (all_in) then
            elems = [elems, e]
            faces = [faces, f]
            nfound = nfound + 1
          end if
        end do
      end do
      if (nfound == 0) then
        call input_error(error, model%face_sets(s)%file, model%face_sets(s)%line, 'face set ' // &
                         model%face_sets(s)%name // ' selects no element face')
        return
      end if
      call move_alloc(elems, model%face_sets(s)%element)
      call move_alloc(faces, model%face_sets(s)%face)
    end do
  end subroutine resolve_face_sets

  !> Shape of a face load at global point x: 1, or linear from 0 at `zero` to 1 at `peak_at`
  !! (times the second ramp's factor when there is one),
  !! never negative.
  pure real(dp) function load_shape(model, l, x)
    type(model_t), intent(in) :: model
    type(face_load_t), intent(in) :: l
    real(dp), intent(in) :: x(3)
    load_shape = 1.0_dp
    if (l%vary_coord > 0) load_shape = ramp(model, l%vary_csys, l%vary_coord, l%zero, l%peak_at, x)
    if (l%vary2_coord > 0) load_shape = load_shape * ramp(model, l%vary2_csys, l%vary2_coord, l%zero2, l%peak2_at, x)
  end function load_shape

  !> max(0, (c - zero) / (peak - zero)) for coordinate `coord` of system `csys` at global point x.
  !! A cylindrical theta (degrees) is taken modulo 360 within 180 deg of the ramp's middle, as
  !! region theta ranges are: from_global's theta lies in (-180, 180], and a ramp given between
  !! 180 and 360 deg would otherwise find every point below ZERO.
  pure real(dp) function ramp(model, csys, coord, zero, peak, x)
    type(model_t), intent(in) :: model
    integer, intent(in) :: csys, coord
    real(dp), intent(in) :: zero, peak, x(3)
    real(dp) :: c(3), middle
    c = model%systems(csys)%from_global(x)
    if (coord == 2 .and. model%systems(csys)%kind == csys_cylindrical) then
      middle = 0.5_dp * (zero + peak)
      c(2) = middle + modulo(c(2) - middle + 180.0_dp, 360.0_dp) - 180.0_dp
    end if
    ramp = max(0.0_dp, (c(coord) - zero) / (peak - zero))
  end function ramp

  !> Integral of the load's shape over its faces (the total of a unit peak intensity).
  function face_load_intensity_integral(model, kernels, l) result(total)
    type(model_t), intent(in) :: model
    type(group_kernel_t), intent(in) :: kernels(:)
    type(face_load_t), intent(in) :: l
    real(dp) :: total
    integer :: k, g, e, q
    real(dp), allocatable :: xg(:, :), nrm(:, :), wda(:), nf(:, :)
    class(solid_element_t), allocatable :: solid
    total = 0.0_dp
    associate (fs => model%face_sets(l%face_set))
      g = fs%group
      call solid_of(kernels(g), solid)
      do k = 1, size(fs%element)
        e = fs%element(k)
        call face_work_arrays(solid, fs%face(k), xg, nrm, wda, nf)
        call solid%face_integration(model%coords(:, model%groups(g)%connectivity(:, e)), fs%face(k), &
                                    xg, nrm, wda, nf)
        do q = 1, size(wda)
          total = total + load_shape(model, l, xg(:, q)) * wda(q)
        end do
      end do
    end associate
  end function face_load_intensity_integral

  !> Nodal forces (3, nnode), global Cartesian, of the loads of the model (of one stage's
  !! own loads if `stage` is given: 0 for the reference loads).
  subroutine nodal_load_vector(model, kernels, f, error, stage)
    type(model_t), intent(in) :: model
    type(group_kernel_t), intent(in) :: kernels(:)
    real(dp), intent(out) :: f(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: stage
    integer :: i, k, n, g, e, q, a
    real(dp) :: t(3), peak, integral, dir(3), basis(3, 3)
    real(dp), allocatable :: xg(:, :), nrm(:, :), wda(:), nf(:, :)
    integer, allocatable :: fn(:)
    class(solid_element_t), allocatable :: solid

    f = 0.0_dp
    do i = 1, size(model%nodal_loads)
      if (present(stage)) then
        if (model%nodal_loads(i)%stage /= stage) cycle
      end if
      associate (l => model%nodal_loads(i))
        do k = 1, size(model%node_sets(l%node_set)%nodes)
          n = model%node_sets(l%node_set)%nodes(k)
          basis = model%systems(l%csys)%local_basis(model%coords(:, n))
          f(:, n) = f(:, n) + matmul(basis, l%components)
        end do
        call check_finite_forces(f, l%file, l%line, 'FORCE on node set ' // model%node_sets(l%node_set)%name, error)
        if (allocated(error)) return
      end associate
    end do

    do i = 1, size(model%face_loads)
      if (present(stage)) then
        if (model%face_loads(i)%stage /= stage) cycle
      end if
      associate (l => model%face_loads(i), fs => model%face_sets(model%face_loads(i)%face_set))
        g = fs%group
        dir = l%components
        if (l%kind == load_pressure) then
          peak = l%value
        else
          peak = 1.0_dp
        end if
        if (l%use_total) then
          integral = face_load_intensity_integral(model, kernels, l)
          if (.not. (integral > 0.0_dp)) then
            call input_error(error, l%file, l%line, 'the load shape integrates to zero over face set ' // fs%name // &
                             ': check ZERO= and PEAK=')
            return
          end if
          if (l%kind == load_pressure) then
            peak = l%total / integral
          else
            peak = l%total / integral / norm2(l%components)
          end if
        end if
        call solid_of(kernels(g), solid)
        do k = 1, size(fs%element)
          e = fs%element(k)
          fn = solid%face_nodes(fs%face(k))
          call face_work_arrays(solid, fs%face(k), xg, nrm, wda, nf)
          call solid%face_integration(model%coords(:, model%groups(g)%connectivity(:, e)), fs%face(k), &
                                      xg, nrm, wda, nf)
          do q = 1, size(wda)
            if (l%kind == load_pressure) then
              t = -peak * load_shape(model, l, xg(:, q)) * nrm(:, q)
            else
              basis = model%systems(l%csys)%local_basis(xg(:, q))
              t = peak * load_shape(model, l, xg(:, q)) * matmul(basis, dir)
            end if
            do a = 1, size(fn)
              n = model%groups(g)%connectivity(fn(a), e)
              f(:, n) = f(:, n) + nf(a, q) * wda(q) * t
            end do
          end do
        end do
        call check_finite_forces(f, l%file, l%line, trim(merge('PRESSURE', 'TRACTION', l%kind == load_pressure)) // &
                                 ' on face set ' // fs%name, error)
        if (allocated(error)) return
      end associate
    end do

    if (present(stage)) then
      if (stage >= 1) call add_weights(model, kernels, stage, f, error)
    end if
  end subroutine nodal_load_vector

  !> f <- f + the weight of every group that gets it in stage `stage`: the later of GRAVITY's
  !! stage and the group's birth, so that a group born under gravity brings its weight with it
  !! (as PLAXIS does when it activates a cluster). A group's weight per unit volume is its
  !! material's unit weight times the acceleration (per unit length for a bar: times its area);
  !! an interface, of zero thickness, weighs nothing.
  subroutine add_weights(model, kernels, stage, f, error)
    type(model_t), intent(in) :: model
    type(group_kernel_t), intent(in) :: kernels(:)
    integer, intent(in) :: stage
    real(dp), intent(inout) :: f(:, :)
    type(error_t), allocatable, intent(out) :: error
    class(material_t), allocatable :: material
    real(dp), allocatable :: fe(:)
    real(dp) :: b(3)
    integer :: g, e
    if (model%gravity_stage == 0) return
    do g = 1, size(model%groups)
      if (max(model%gravity_stage, model%groups(g)%activate_stage, 1) /= stage) cycle
      call material_of(model%materials(model%groups(g)%material), material, error)
      if (allocated(error)) return
      if (material%unit_weight == 0.0_dp) cycle
      b = material%unit_weight * model%gravity
      if (material%section_area() > 0.0_dp) b = b * material%section_area()
      associate (conn => model%groups(g)%connectivity)
        allocate (fe(3 * size(conn, 1)))
        do e = 1, size(conn, 2)
          call kernels(g)%element%body_force(model%coords(:, conn(:, e)), b, fe)
          f(:, conn(:, e)) = f(:, conn(:, e)) + reshape(fe, [3, size(conn, 1)])
        end do
        deallocate (fe)
      end associate
      call check_finite_forces(f, model%gravity_file, model%gravity_line, 'GRAVITY on group ' // &
                               model%groups(g)%name, error)
      if (allocated(error)) return
    end do
  end subroutine add_weights

  !> A load whose nodal forces (with those of the records before it) leave double precision:
  !! an input error naming the record, the node and the DOF, before anything is solved. A force
  !! beyond huge() is Infinity; NaN comes from a coordinate system that gives no direction.
  subroutine check_finite_forces(f, file, line, what, error)
    real(dp), intent(in) :: f(:, :)
    character(len=*), intent(in) :: file
    integer, intent(in) :: line
    character(len=*), intent(in) :: what
    type(error_t), allocatable, intent(out) :: error
    character(len=2), parameter :: dofs(3) = ['ux', 'uy', 'uz']
    integer :: at(2)
    character(len=:), allocatable :: why
    if (all(ieee_is_finite(f))) return
    at = findloc(ieee_is_finite(f), .false.)
    if (ieee_is_nan(f(at(1), at(2)))) then
      why = 'check the load and the coordinate system it is given in'
    else
      why = 'the load is beyond double precision'
    end if
    call input_error(error, file, line, what // ': the nodal force at node ' // str(at(2)) // ', DOF ' // &
                     dofs(at(1)) // ' is not finite (' // str(f(at(1), at(2))) // '): ' // why)
  end subroutine check_finite_forces

  !> Face-integration arrays sized for face `face` of the group's element, kept when they have
  !! that size already (the faces of one element may differ: a wedge's triangles and quadrilaterals).
  subroutine face_work_arrays(solid, face, xg, nrm, wda, nf)
    class(solid_element_t), intent(in) :: solid
    integer, intent(in) :: face
    real(dp), allocatable, intent(inout) :: xg(:, :), nrm(:, :), wda(:), nf(:, :)
    integer :: ng, nn
    ng = solid%nface_gauss(face)
    nn = solid%nface_nodes(face)
    if (allocated(xg)) then
      if (size(wda) == ng .and. size(nf, 1) == nn) return
      deallocate (xg, nrm, wda, nf)
    end if
    allocate (xg(3, ng), nrm(3, ng), wda(ng), nf(nn, ng))
  end subroutine face_work_arrays

  !> The group's element as a solid, for its faces (a copy: the elements carry no data beyond
  !! their type); not allocated for an element of another family, which has no faces.
  subroutine solid_of(kernel, solid)
    type(group_kernel_t), intent(in) :: kernel
    class(solid_element_t), allocatable, intent(out) :: solid
    select type (element => kernel%element)
    class is (solid_element_t)
      allocate (solid, source=element)
    end select
  end subroutine solid_of

  !> Free-equation right-hand side from nodal forces (rotated into nodal systems).
  pure subroutine to_equations(map, f_nodes, b)
    type(dof_map_t), intent(in) :: map
    real(dp), intent(in) :: f_nodes(:, :)
    real(dp), intent(out) :: b(:)
    integer :: n, d
    real(dp) :: fl(3)
    b = 0.0_dp
    do n = 1, size(f_nodes, 2)
      if (map%node_csys(n) /= 0) then
        fl = matmul(transpose(map%basis(:, :, n)), f_nodes(:, n))
      else
        fl = f_nodes(:, n)
      end if
      do d = 1, 3
        if (map%eq(d, n) > 0) b(map%eq(d, n)) = b(map%eq(d, n)) + fl(d)
      end do
    end do
  end subroutine to_equations

end module feps_loads
