!> The observer that writes a run's steps to its results file (HDF5, with the XDMF beside it)
!! and forwards its progress lines: every field of the result schema that the deck's FIELDS
!! asks for, the point results as the analysis hands them over and the nodal fields that
!! feps_nodal_fields makes of them.
module feps_results_observer
  use feps_kinds, only: dp
  use feps_error, only: error_t, str
  use feps_model, only: model_t
  use feps_observer, only: observer_t, step_result_t, group_result_t
  use feps_restart_data, only: restart_data_t
  use feps_restart_file, only: write_restart_point
  use feps_results_file, only: results_file_t
  use feps_principal, only: principal_values
  use feps_element_catalog, only: point_coordinates, family_solid, family_interface, family_bar
  use feps_result_schema, only: field_name, field_components, field_displacement, field_reaction, &
                                field_applied_force, field_stress, field_principal, field_interface, field_bar, &
                                field_interface_strain, field_nodal_stress, field_nodal_principal, &
                                field_nodal_interface, field_point_state, field_stress_cyl, field_nodal_stress_cyl
  use feps_stress_frames, only: stresses_in_system
  use feps_nodal_fields, only: solid_nodal_stresses, interface_nodal_tractions
  implicit none
  private

  !> Where progress lines go (the program prints them; tests pass nothing).
  abstract interface
    subroutine line_sink(line)
      character(len=*), intent(in) :: line
    end subroutine line_sink
  end interface
  public :: line_sink

  !> Positions of a group's integration points (stress_cyl's frame), computed on first use.
  type :: group_points_t
    real(dp), allocatable :: xg(:, :)   !! (3, points) element-major
  end type group_points_t

  !> Writes the steps of a run to the results file and forwards progress lines.
  type, public, extends(observer_t) :: results_observer_t
    type(results_file_t) :: h5
    logical :: writing = .false.
    integer :: steps_written = 0
    real(dp), allocatable :: last_displacement(:, :)
    real(dp), allocatable :: last_reaction(:, :)          !! (3, nnode) global, of the last step written
    type(group_result_t), allocatable :: last_groups(:)   !! each group's point results of the last step
    type(model_t), pointer :: model => null()
    type(group_points_t), allocatable :: points(:)        !! per group, for stress_cyl
    procedure(line_sink), pointer, nopass :: sink => null()
    character(len=:), allocatable :: restart_path         !! the checkpoint file (RESTART); unallocated: none
  contains
    procedure :: progress => observer_progress
    procedure :: write_step => observer_write_step
    procedure :: checkpoint => observer_checkpoint
  end type results_observer_t

contains

  subroutine observer_progress(self, line)
    class(results_observer_t), intent(inout) :: self
    character(len=*), intent(in) :: line
    if (associated(self%sink)) call self%sink(line)
  end subroutine observer_progress

  !> Restart data: added to the checkpoint file beside the results (feps_restart_file).
  subroutine observer_checkpoint(self, data, error)
    class(results_observer_t), intent(inout) :: self
    type(restart_data_t), intent(in) :: data
    type(error_t), allocatable, intent(out) :: error
    if (.not. allocated(self%restart_path)) return
    call write_restart_point(self%restart_path, data, error)
    if (.not. allocated(error)) call self%progress('  restart data of step ' // str(data%step) // ' written to ' // &
                                                   self%restart_path)
  end subroutine observer_checkpoint

  !> One step: displacement, reactions; solids: stresses and the most tensile and most
  !! compressive principal stresses; interfaces: tractions with the point state, and the
  !! relative displacements.
  subroutine observer_write_step(self, res, error)
    class(results_observer_t), intent(inout) :: self
    type(step_result_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: extra(:, :)
    real(dp) :: p(3)
    integer :: g, q, nc
    self%last_displacement = res%displacement
    self%last_reaction = res%reaction
    self%last_groups = res%groups
    self%steps_written = self%steps_written + 1
    associate (f => self%model%fields)
      call self%h5%begin_step(res%step, res%load_factor, res%iterations, res%residual, error, &
                              tangent_sign=res%tangent_sign)
      if (f%on(field_displacement) .and. .not. allocated(error)) call write_field(field_displacement, res%displacement)
      if (f%on(field_reaction) .and. .not. allocated(error)) call write_field(field_reaction, res%reaction)
      if (f%on(field_applied_force) .and. .not. allocated(error)) call write_field(field_applied_force, res%applied_force)
      if (f%on(field_reaction) .and. res%has_nodal_systems .and. .not. allocated(error)) call self%h5%write_nodal(res%step, &
        'reaction_nodal', res%reaction_nodal, 'f1 f2 f3', error)
      do g = 1, size(res%groups)
        if (allocated(error)) return
        associate (gr => res%groups(g), name => self%model%groups(g)%name, element => self%model%groups(g)%element)
          if (.not. allocated(gr%stress)) cycle      ! no field of this group was asked for
          select case (element%family)
          case (family_bar)
            call self%h5%write_gauss(res%step, field_name(field_bar), name, gr%stress, element%component_names, &
                                     gr%points_per_element, error)
          case (family_interface)
            nc = size(gr%stress, 1)
            if (f%on(field_interface)) then
              allocate (extra(nc + 1, size(gr%state)))
              extra(1:nc, :) = gr%stress
              extra(nc + 1, :) = real(gr%state, dp)
              call self%h5%write_gauss(res%step, field_name(field_interface), name, extra, &
                                       element%component_names // ' state', gr%points_per_element, error)
              deallocate (extra)
            end if
            if (f%on(field_interface_strain) .and. .not. allocated(error)) call self%h5%write_gauss(res%step, &
              field_name(field_interface_strain), name, gr%strain, element%strain_component_names, &
              gr%points_per_element, error)
            if (f%on(field_nodal_interface) .and. .not. allocated(error)) &
              call write_nodal_tractions(self%h5, self%model, res%step, g, gr%stress, error)
          case (family_solid)
            if (f%on(field_stress)) call self%h5%write_gauss(res%step, field_name(field_stress), name, gr%stress, &
                                                   element%component_names, gr%points_per_element, error)
            if (f%on(field_principal) .and. .not. allocated(error)) then
              allocate (extra(2, size(gr%stress, 2)))
              do q = 1, size(gr%stress, 2)
                p = principal_values(gr%stress(:, q))
                extra(:, q) = [p(1), p(3)]
              end do
              call self%h5%write_gauss(res%step, field_name(field_principal), name, extra, &
                                       field_components(field_principal), gr%points_per_element, error)
              deallocate (extra)
            end if
            if (f%on(field_point_state) .and. .not. allocated(error)) &
              call self%h5%write_gauss(res%step, field_name(field_point_state), name, reshape(real(gr%state, dp), &
                                       [1, size(gr%state)]), field_components(field_point_state), &
                                       gr%points_per_element, error)
            if (f%on(field_stress_cyl) .and. .not. allocated(error)) then
              if (.not. allocated(self%points)) allocate (self%points(size(res%groups)))
              if (.not. allocated(self%points(g)%xg)) call point_coordinates(self%model%groups(g)%element_type, &
                self%model%coords, self%model%groups(g)%connectivity, self%points(g)%xg, error)
              if (.not. allocated(error)) call write_point_stress_cyl(self%h5, self%model, res%step, g, gr%stress, &
                                                                      self%points(g)%xg, gr%points_per_element, error)
            end if
            if ((f%on(field_nodal_stress) .or. f%on(field_nodal_principal) .or. f%on(field_nodal_stress_cyl)) .and. &
                .not. allocated(error)) call write_nodal_stresses(self%h5, self%model, res%step, g, gr%stress, error)
          end select
        end associate
      end do
    end associate
  contains
    !> A nodal field of the whole mesh, named and labelled by the result schema.
    subroutine write_field(id, values)
      integer, intent(in) :: id
      real(dp), intent(in) :: values(:, :)
      call self%h5%write_nodal(res%step, field_name(id), values, field_components(id), error)
    end subroutine write_field
  end subroutine observer_write_step

  !> The field stress_cyl of solid group `g`: its Gauss-point stresses in the frame (radial,
  !! hoop, axial) of the cylindrical system that FIELDS CSYS= names, at the points `xg`.
  subroutine write_point_stress_cyl(h5, model, step, g, stress, xg, points_per_element, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    integer, intent(in) :: step, g, points_per_element
    real(dp), intent(in) :: stress(:, :)       !! (6, points) element-major
    real(dp), intent(in) :: xg(:, :)           !! (3, points) their positions
    type(error_t), allocatable, intent(out) :: error
    associate (group => model%groups(g))
      call h5%write_gauss(step, field_name(field_stress_cyl), group%name, &
                          stresses_in_system(stress, xg, model%systems(model%fields%csys)), &
                          field_components(field_stress_cyl), points_per_element, error)
    end associate
  end subroutine write_point_stress_cyl

  !> The fields nodal_stress, nodal_principal and nodal_stress_cyl of solid group `g` (those
  !! the deck asks for).
  subroutine write_nodal_stresses(h5, model, step, g, stress, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    integer, intent(in) :: step, g
    real(dp), intent(in) :: stress(:, :)       !! (6, points) element-major
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: nodal(:, :), principal(:, :), cylindrical(:, :)
    associate (group => model%groups(g), f => model%fields)
      call solid_nodal_stresses(model, g, stress, f%on(field_nodal_principal), &
                                merge(f%csys, 0, f%on(field_nodal_stress_cyl)), nodal, principal, cylindrical, error)
      if (allocated(error)) return
      if (f%on(field_nodal_stress_cyl)) then
        call h5%write_nodal(step, field_name(field_nodal_stress_cyl), cylindrical, &
                            field_components(field_nodal_stress_cyl), error, group=group%name)
        if (allocated(error)) return
      end if
      if (f%on(field_nodal_stress)) call h5%write_nodal(step, field_name(field_nodal_stress), nodal, &
                                                        field_components(field_nodal_stress), error, group=group%name)
      if (allocated(error) .or. .not. f%on(field_nodal_principal)) return
      call h5%write_nodal(step, field_name(field_nodal_principal), principal, field_components(field_nodal_principal), &
                          error, group=group%name)
    end associate
  end subroutine write_nodal_stresses

  !> The field nodal_interface of interface group `g`.
  subroutine write_nodal_tractions(h5, model, step, g, traction, error)
    type(results_file_t), intent(inout) :: h5
    type(model_t), intent(in) :: model
    integer, intent(in) :: step, g
    real(dp), intent(in) :: traction(:, :)     !! (ncomp, points) element-major
    type(error_t), allocatable, intent(out) :: error
    real(dp), allocatable :: nodal(:, :)
    call interface_nodal_tractions(model, g, traction, nodal, error)
    if (allocated(error)) return
    call h5%write_nodal(step, field_name(field_nodal_interface), nodal, model%groups(g)%element%component_names, &
                        error, group=model%groups(g)%name)
  end subroutine write_nodal_tractions

end module feps_results_observer
