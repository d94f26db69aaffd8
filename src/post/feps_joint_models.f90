!> Analytical joint models of thesis chapter 7: the Australian model (eqs. 7.2.1-7.2.11) and Haslem's
!! flexible pipe model (eqs. 7.2.12-7.2.16). Units N, mm, MPa; angles in degrees.
!!
!! Both models load the joint face with a normal stress linear in x, zero at x = H = R - Z and sigma_max
!! at the pipe edge x = R: sigma(x) = sigma_max (x - H) / Z for x > H (eqs. 7.2.2-7.2.3 without the
!! sigma_min/sigma_m split; Z > 2R means no gap and sigma(-R) = sigma_min > 0). Over the annulus
!! P = sigma_max p(Z) and M = sigma_max m(Z) in closed form, and
!!   Australian: tan(beta) = sigma_max (a / E_p + L / E_c) / Z
!!   Haslem:     beta = sigma_max a / (Z E_p) + M L / (E_c I_c),  I_c = pi (R^4 - r^4) / 4.
!! `feps joint` (feps_joint_command) gives them to scripts (scripts/joint_models.py and those that use it).
module feps_joint_models
  use feps_kinds, only: dp, pi, deg2rad, rad2deg
  use feps_error, only: error_t, fatal_error, err_input, str
  implicit none
  private

  public :: joint_t, joint_solution_t
  public :: australian, haslem
  public :: annulus_area, pipe_second_moment, joint_load_factor, joint_moment_factor
  public :: packing_youngs_modulus

  !> Pressure on the top pipe end in thesis section 7.4.3 (MPa); the default joint load is this
  !! pressure times the full annulus.
  real(dp), parameter, public :: thesis_joint_pressure = 10.0_dp

  integer, parameter :: australian_model = 1, haslem_model = 2

  !> A pipe joint: packing, pipes and their section (defaults: thesis model C, except E_p).
  type :: joint_t
    real(dp) :: packing_thickness = 15.0_dp    !! a (mm)
    real(dp) :: pipe_length = 2500.0_dp        !! L (mm): the two pipe halves next to the joint together
    real(dp) :: concrete_modulus = 40000.0_dp  !! E_c (MPa)
    real(dp) :: packing_modulus = 0.0_dp       !! E_p (MPa); no default, must be set (> 0)
    real(dp) :: outer_radius = 715.0_dp        !! R (mm)
    real(dp) :: inner_radius = 600.0_dp        !! r (mm)
  end type joint_t

  !> The state of a joint under one of the models.
  type :: joint_solution_t
    real(dp) :: contact_width = 0.0_dp  !! Z, diametrical contact width (mm)
    real(dp) :: sigma_max = 0.0_dp      !! normal stress at the pipe edge (MPa)
    real(dp) :: beta = 0.0_dp           !! misalignment angle (degrees)
    real(dp) :: load = 0.0_dp           !! P, load through the joint (N)
    real(dp) :: moment = 0.0_dp         !! M, moment of the joint stress about the pipe axis (N mm)
  end type joint_solution_t

contains

  !> Australian model. Give `beta` (degrees) or `z` (mm), with `load` (N; default 10 MPa on the
  !! full annulus); or `beta` and `z` without `load`, which then follows.
  pure subroutine australian(joint, solution, error, beta, z, load)
    type(joint_t), intent(in) :: joint
    type(joint_solution_t), intent(out) :: solution
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in), optional :: beta, z, load
    call solve_joint(australian_model, joint, solution, error, beta, z, load)
  end subroutine australian

  !> Haslem's flexible pipe model; arguments as `australian`.
  pure subroutine haslem(joint, solution, error, beta, z, load)
    type(joint_t), intent(in) :: joint
    type(joint_solution_t), intent(out) :: solution
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in), optional :: beta, z, load
    call solve_joint(haslem_model, joint, solution, error, beta, z, load)
  end subroutine haslem

  !> Area of the annulus pi (R^2 - r^2) (mm^2).
  elemental real(dp) function annulus_area(outer_radius, inner_radius)
    real(dp), intent(in) :: outer_radius, inner_radius
    annulus_area = pi * (outer_radius**2 - inner_radius**2)
  end function annulus_area

  !> Second moment of area of the pipe section I_c = pi (R^4 - r^4) / 4 (mm^4).
  elemental real(dp) function pipe_second_moment(outer_radius, inner_radius)
    real(dp), intent(in) :: outer_radius, inner_radius
    pipe_second_moment = pi / 4.0_dp * (outer_radius**4 - inner_radius**4)
  end function pipe_second_moment

  !> p(Z) = P / sigma_max (mm^2) for the linear joint stress (eq. 7.2.4). Needs Z > 0, R > r >= 0.
  elemental real(dp) function joint_load_factor(z, outer_radius, inner_radius) result(p)
    real(dp), intent(in) :: z, outer_radius, inner_radius
    real(dp) :: m
    call joint_factors(z, outer_radius, inner_radius, p, m)
  end function joint_load_factor

  !> m(Z) = M / sigma_max (mm^3), M about the pipe axis (eq. 7.2.12). Needs Z > 0, R > r >= 0.
  elemental real(dp) function joint_moment_factor(z, outer_radius, inner_radius) result(m)
    real(dp), intent(in) :: z, outer_radius, inner_radius
    real(dp) :: p
    call joint_factors(z, outer_radius, inner_radius, p, m)
  end function joint_moment_factor

  !> E_p = 2 G_p (1 + nu_p), the packing modulus as the thesis defines it (section 7.4.1).
  elemental real(dp) function packing_youngs_modulus(shear_modulus, poisson_ratio)
    real(dp), intent(in) :: shear_modulus, poisson_ratio
    packing_youngs_modulus = 2.0_dp * shear_modulus * (1.0_dp + poisson_ratio)
  end function packing_youngs_modulus

  ! ------------------------------------------------------------------------------------------------

  pure subroutine solve_joint(model, joint, solution, error, beta, z, load)
    integer, intent(in) :: model
    type(joint_t), intent(in) :: joint
    type(joint_solution_t), intent(out) :: solution
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in), optional :: beta, z, load
    character(len=:), allocatable :: name
    real(dp) :: p_factor, m_factor

    name = merge('australian', 'haslem    ', model == australian_model)
    name = trim(name)
    call check_joint(name, joint, error)
    if (allocated(error)) return
    if (present(beta)) then
      if (.not. beta > 0.0_dp) then
        call fatal_error(error, err_input, name // ': need beta > 0 degrees, got ' // str(beta))
        return
      end if
      if (.not. beta < 90.0_dp) then
        call fatal_error(error, err_input, name // ': need beta < 90 degrees, got ' // str(beta))
        return
      end if
    end if
    if (present(z)) then
      if (.not. z > 0.0_dp) then
        call fatal_error(error, err_input, name // ': need Z > 0, got ' // str(z))
        return
      end if
    end if
    if (present(load)) then
      if (.not. load > 0.0_dp) then
        call fatal_error(error, err_input, name // ': need P > 0, got ' // str(load))
        return
      end if
    end if

    if (present(beta) .and. present(z)) then
      if (present(load)) then
        call fatal_error(error, err_input, name // ': give at most two of beta, Z and P')
        return
      end if
      ! Both angle and width known: the stress follows from the angle, the load from the stress.
      call joint_factors(z, joint%outer_radius, joint%inner_radius, p_factor, m_factor)
      solution%contact_width = z
      solution%beta = beta
      solution%sigma_max = angle_measure(model, beta) / angle_per_stress(model, joint, z)
      solution%load = solution%sigma_max * p_factor
      solution%moment = solution%sigma_max * m_factor
      return
    end if

    if (present(load)) then
      solution%load = load
    else
      solution%load = thesis_joint_pressure * annulus_area(joint%outer_radius, joint%inner_radius)
    end if
    if (present(z)) then
      solution%contact_width = z
    else if (present(beta)) then
      call solve_contact_width(model, name, joint, angle_measure(model, beta), solution%load, &
                               solution%contact_width, error)
      if (allocated(error)) return
    else
      call fatal_error(error, err_input, name // ': give beta or Z')
      return
    end if
    call joint_factors(solution%contact_width, joint%outer_radius, joint%inner_radius, p_factor, m_factor)
    solution%sigma_max = solution%load / p_factor
    solution%moment = solution%sigma_max * m_factor
    solution%beta = angle_from_measure(model, &
                    solution%sigma_max * angle_per_stress(model, joint, solution%contact_width))
  end subroutine solve_joint

  pure subroutine check_joint(name, joint, error)
    character(len=*), intent(in) :: name
    type(joint_t), intent(in) :: joint
    type(error_t), allocatable, intent(out) :: error
    if (.not. (joint%outer_radius > joint%inner_radius .and. joint%inner_radius >= 0.0_dp)) then
      call fatal_error(error, err_input, name // ': need R > r >= 0, got R = ' // str(joint%outer_radius) // &
                       ', r = ' // str(joint%inner_radius))
    else if (.not. (joint%packing_thickness >= 0.0_dp .and. joint%pipe_length >= 0.0_dp)) then
      call fatal_error(error, err_input, name // ': need a >= 0 and L >= 0, got a = ' // &
                       str(joint%packing_thickness) // ', L = ' // str(joint%pipe_length))
    else if (.not. (joint%concrete_modulus > 0.0_dp .and. joint%packing_modulus > 0.0_dp)) then
      call fatal_error(error, err_input, name // ': need E_c > 0 and E_p > 0, got E_c = ' // &
                       str(joint%concrete_modulus) // ', E_p = ' // str(joint%packing_modulus))
    end if
  end subroutine check_joint

  !> Z where load * k(Z) / p(Z) equals the angle measure; that ratio decreases with Z, so bracket
  !! around 2R by halving/doubling and bisect in log Z.
  pure subroutine solve_contact_width(model, name, joint, target, load, z, error)
    integer, intent(in) :: model
    character(len=*), intent(in) :: name
    type(joint_t), intent(in) :: joint
    real(dp), intent(in) :: target, load
    real(dp), intent(out) :: z
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: lower, upper
    integer :: iteration

    z = 0.0_dp
    lower = 2.0_dp * joint%outer_radius
    upper = lower
    do while (excess(lower) < 0.0_dp)
      lower = 0.5_dp * lower
      if (lower < 1.0e-9_dp * joint%outer_radius) then
        ! Haslem with a = 0 has a largest angle, P R L / (E_c I_c).
        call fatal_error(error, err_input, name // ': no contact width gives this angle ' // &
                         '(beyond the model''s largest angle for this load)')
        return
      end if
    end do
    do while (excess(upper) > 0.0_dp)
      upper = 2.0_dp * upper
      if (upper > 1.0e12_dp * joint%outer_radius) then
        call fatal_error(error, err_input, name // ': angle too small for this load')
        return
      end if
    end do
    do iteration = 1, 200
      z = sqrt(lower * upper)
      if (excess(z) > 0.0_dp) then
        lower = z
      else
        upper = z
      end if
      if (upper - lower <= 1.0e-14_dp * upper) exit
    end do
    z = 0.5_dp * (lower + upper)

  contains

    pure real(dp) function excess(width)
      real(dp), intent(in) :: width
      excess = load * angle_per_stress(model, joint, width) &
               / joint_load_factor(width, joint%outer_radius, joint%inner_radius) - target
    end function excess

  end subroutine solve_contact_width

  !> k(Z) such that the angle measure = sigma_max k(Z) (tan(beta) for the Australian model,
  !! beta in radians for Haslem's).
  pure real(dp) function angle_per_stress(model, joint, z) result(k)
    integer, intent(in) :: model
    type(joint_t), intent(in) :: joint
    real(dp), intent(in) :: z
    associate (a => joint%packing_thickness, length => joint%pipe_length, &
               ec => joint%concrete_modulus, ep => joint%packing_modulus)
      if (model == australian_model) then
        k = (a / ep + length / ec) / z                                       ! eqs. 7.2.10-7.2.11
      else
        k = a / (z * ep) + joint_moment_factor(z, joint%outer_radius, joint%inner_radius) * length &
            / (ec * pipe_second_moment(joint%outer_radius, joint%inner_radius))   ! eqs. 7.2.14-7.2.16
      end if
    end associate
  end function angle_per_stress

  pure real(dp) function angle_measure(model, beta_deg)
    integer, intent(in) :: model
    real(dp), intent(in) :: beta_deg
    if (model == australian_model) then
      angle_measure = tan(beta_deg * deg2rad)
    else
      angle_measure = beta_deg * deg2rad
    end if
  end function angle_measure

  pure real(dp) function angle_from_measure(model, measure)
    integer, intent(in) :: model
    real(dp), intent(in) :: measure
    if (model == australian_model) then
      angle_from_measure = atan(measure) * rad2deg
    else
      angle_from_measure = measure * rad2deg
    end if
  end function angle_from_measure

  !> p(Z) and m(Z): the outer disk less the bore (eqs. 7.2.4-7.2.8, 7.2.12-7.2.13).
  pure subroutine joint_factors(z, outer_radius, inner_radius, p, m)
    real(dp), intent(in) :: z, outer_radius, inner_radius
    real(dp), intent(out) :: p, m
    real(dp) :: front, outer_load, outer_moment, inner_load, inner_moment
    front = outer_radius - z
    call disk_integrals(outer_radius, front, outer_load, outer_moment)
    call disk_integrals(inner_radius, front, inner_load, inner_moment)
    p = (outer_load - inner_load) / z
    m = (outer_moment - inner_moment) / z
  end subroutine joint_factors

  !> Over a disk of radius rho, for x > front: int (x - front) dA and int x (x - front) dA.
  pure subroutine disk_integrals(rho, front, load_part, moment_part)
    real(dp), intent(in) :: rho, front
    real(dp), intent(out) :: load_part, moment_part
    real(dp) :: h, half_chord, angle, first, area, second
    load_part = 0.0_dp
    moment_part = 0.0_dp
    if (rho <= 0.0_dp .or. front >= rho) return
    h = min(max(front, -rho), rho)                  ! H_1 (outer disk), H_2 (bore): eqs. 7.2.3, 7.2.8
    half_chord = sqrt(max(rho**2 - h**2, 0.0_dp))
    angle = acos(h / rho)
    first = 2.0_dp / 3.0_dp * half_chord**3                               ! int x dA
    area = rho**2 * angle - h * half_chord                                ! int dA
    second = rho**4 / 4.0_dp * angle - h / 4.0_dp * (2.0_dp * h**2 - rho**2) * half_chord   ! int x^2 dA
    load_part = first - front * area
    moment_part = second - front * first
  end subroutine disk_integrals

end module feps_joint_models
