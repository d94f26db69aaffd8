!> `feps joint`: the analytical joint models of thesis chapter 7 (feps_joint_models) from the
!! command line, so that scripts ask the library instead of keeping a second implementation.
!!
!!   feps joint --beta DEG | --Z MM  --a MM --Ep MPa [--P N] [--L MM] [--Ec MPa] [--R MM] [--r MM] [--json]
!!
!! Plain output is one line per model, `australian Z=<mm> sigma_max=<MPa>` (2 and 3 decimals);
!! `--json` gives every quantity of both models to full double precision (17 digits, so that a
!! reader gets the very doubles the library computed), and the closed-form factors
!! p(Z) = P / sigma_max and m(Z) = M / sigma_max of the contact width.
module feps_joint_command
  use feps_kinds, only: dp
  use feps_error, only: error_t, fatal_error, err_input
  use feps_records, only: real_from_text
  use feps_strings, only: sci
  use feps_results_observer, only: line_sink
  use feps_joint_models, only: joint_t, joint_solution_t, australian, haslem, joint_load_factor, &
                               joint_moment_factor
  implicit none
  private

  public :: joint_request_t, set_joint_option, run_joint_command, joint_usage

  !> What `feps joint` is asked: the joint, the given quantities and the output form.
  type :: joint_request_t
    type(joint_t) :: joint
    real(dp) :: beta = 0.0_dp, z = 0.0_dp, load = 0.0_dp
    logical :: has_beta = .false., has_z = .false., has_load = .false.
    logical :: has_thickness = .false., has_packing_modulus = .false.
    logical :: json = .false.
  end type joint_request_t

  character(len=*), parameter :: joint_usage = &
    'usage: feps joint --beta DEG | --Z MM  --a MM --Ep MPa [--P N] [--L MM] [--Ec MPa] [--R MM] [--r MM] [--json]'

contains

  !> Take one option of `feps joint`: `name` with its `value` (empty for `--json`). An unknown
  !! option, a repeated one or a value that is not a finite number is an input error.
  subroutine set_joint_option(request, name, value, error)
    type(joint_request_t), intent(inout) :: request
    character(len=*), intent(in) :: name, value
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: number
    logical :: ok

    if (name == '--json') then
      if (request%json) call fatal_error(error, err_input, 'joint: --json is given twice')
      request%json = .true.
      return
    end if
    select case (name)
    case ('--beta', '--Z', '--P', '--a', '--Ep', '--L', '--Ec', '--R', '--r')
    case default
      call fatal_error(error, err_input, 'joint: unknown option "' // name // '" (' // joint_usage // ')')
      return
    end select
    call real_from_text(value, number, ok)
    if (.not. ok) then
      call fatal_error(error, err_input, 'joint: need a finite ' // name(3:) // ', got "' // value // '"')
      return
    end if
    select case (name)
    case ('--beta')
      call take(request%has_beta, request%beta)
    case ('--Z')
      call take(request%has_z, request%z)
    case ('--P')
      call take(request%has_load, request%load)
    case ('--a')
      call take(request%has_thickness, request%joint%packing_thickness)
    case ('--Ep')
      call take(request%has_packing_modulus, request%joint%packing_modulus)
    case ('--L')
      request%joint%pipe_length = number
    case ('--Ec')
      request%joint%concrete_modulus = number
    case ('--R')
      request%joint%outer_radius = number
    case default
      request%joint%inner_radius = number
    end select

  contains

    subroutine take(given, target)
      logical, intent(inout) :: given
      real(dp), intent(inout) :: target
      if (given) then
        call fatal_error(error, err_input, 'joint: ' // name // ' is given twice')
        return
      end if
      given = .true.
      target = number
    end subroutine take

  end subroutine set_joint_option

  !> Solve both models for `request` and hand the output lines to `emit`; an impossible request
  !! (a missing quantity, a value out of range, an angle no contact width gives) is an input error.
  subroutine run_joint_command(request, emit, error)
    type(joint_request_t), intent(in) :: request
    procedure(line_sink) :: emit
    type(error_t), allocatable, intent(out) :: error
    type(joint_solution_t) :: solutions(2)
    character(len=*), parameter :: names(2) = ['australian', 'haslem    ']
    integer :: k

    if (.not. (request%has_thickness .and. request%has_packing_modulus)) then
      call fatal_error(error, err_input, 'joint: --a and --Ep are required (' // joint_usage // ')')
      return
    end if
    if (request%has_beta .eqv. request%has_z) then
      call fatal_error(error, err_input, 'joint: give exactly one of --beta and --Z (' // joint_usage // ')')
      return
    end if
    do k = 1, 2
      call solve(k, solutions(k))
      if (allocated(error)) then
        error%message = 'joint: ' // error%message
        return
      end if
    end do

    if (.not. request%json) then
      do k = 1, 2
        call emit(trim(names(k)) // ' Z=' // fixed(solutions(k)%contact_width, 2) // &
                  ' sigma_max=' // fixed(solutions(k)%sigma_max, 3))
      end do
      return
    end if
    call emit('{')
    do k = 1, 2
      associate (s => solutions(k), r => request%joint)
        call emit('  "' // trim(names(k)) // '": {"model": "' // trim(names(k)) // '", ' // &
                  '"Z": ' // sci(s%contact_width, 16, 0) // ', "sigma_max": ' // sci(s%sigma_max, 16, 0) // &
                  ', "beta": ' // sci(s%beta, 16, 0) // ', "P": ' // sci(s%load, 16, 0) // ', "M": ' // sci(s%moment, 16, 0) // &
                  ', "p_factor": ' // sci(joint_load_factor(s%contact_width, r%outer_radius, r%inner_radius), 16, 0) // &
                  ', "m_factor": ' // sci(joint_moment_factor(s%contact_width, r%outer_radius, r%inner_radius), 16, 0) // &
                  '}' // trim(merge(',', ' ', k == 1)))
      end associate
    end do
    call emit('}')

  contains

    subroutine solve(model, solution)
      integer, intent(in) :: model
      type(joint_solution_t), intent(out) :: solution
      procedure(australian), pointer :: joint_model
      if (model == 1) then
        joint_model => australian
      else
        joint_model => haslem
      end if
      ! the given pair of (beta or Z) and, optionally, P
      if (request%has_beta .and. request%has_load) then
        call joint_model(request%joint, solution, error, beta=request%beta, load=request%load)
      else if (request%has_beta) then
        call joint_model(request%joint, solution, error, beta=request%beta)
      else if (request%has_load) then
        call joint_model(request%joint, solution, error, z=request%z, load=request%load)
      else
        call joint_model(request%joint, solution, error, z=request%z)
      end if
    end subroutine solve

  end subroutine run_joint_command

  !> x with `decimals` decimals and no padding (a leading zero kept: 0.50, not .50).
  pure function fixed(x, decimals) result(text)
    real(dp), intent(in) :: x
    integer, intent(in) :: decimals
    character(len=:), allocatable :: text
    character(len=40) :: buffer
    character(len=16) :: form
    write (form, '(a,i0,a)') '(f40.', decimals, ')'
    write (buffer, form) x
    text = trim(adjustl(buffer))
  end function fixed

end module feps_joint_command
