!> Tests of the principal stresses written to /steps/<NNNN>/principal: exact cases (uniaxial,
!! biaxial with a repeated root, hydrostatic, each in a rotated frame) and random rotated tensors
!! against LAPACK's dsyev, all to 1e-13 of the tensor's largest eigenvalue in magnitude (the
!! closed-form cubic used before lost up to half the digits near a repeated root: a rotated
!! uniaxial 100 MPa compression gave a most tensile stress of 1e-6 MPa).
module test_principal
  use feps_kinds, only: dp, i8
  use feps_error, only: str
  use feps_testing, only: error_t, unittest_t, new_unittest, check, test_failed
  use feps_lapack, only: dsyev
  use feps_principal, only: principal_values
  implicit none
  private

  public :: collect_principal

  real(dp), parameter :: tol = 1.0e-13_dp   !! relative to the largest |eigenvalue|

contains

  subroutine collect_principal(tests)
    type(unittest_t), allocatable, intent(out) :: tests(:)
    tests = [ &
      new_unittest("uniaxial compression in rotated frames", test_uniaxial), &
      new_unittest("biaxial with a repeated root, rotated", test_biaxial_repeated), &
      new_unittest("hydrostatic and zero", test_hydrostatic), &
      new_unittest("random rotated tensors against dsyev", test_random_against_dsyev), &
      new_unittest("tiny and huge tensors keep their digits", test_extreme_scales) &
    ]
  end subroutine collect_principal

  ! ------------------------------------------------------------------ helpers

  !> Voigt [xx yy zz yz xz xy] of R diag(lambda) R^T.
  pure function rotated(lambda, r) result(s)
    real(dp), intent(in) :: lambda(3), r(3, 3)
    real(dp) :: s(6), a(3, 3)
    integer :: k
    a = 0.0_dp
    do k = 1, 3
      a = a + lambda(k) * spread(r(:, k), 2, 3) * spread(r(:, k), 1, 3)
    end do
    s = [a(1, 1), a(2, 2), a(3, 3), a(2, 3), a(1, 3), a(1, 2)]
  end function rotated

  !> Rotation matrix of the unit quaternion q / |q|.
  pure function rotation(q_in) result(r)
    real(dp), intent(in) :: q_in(4)
    real(dp) :: r(3, 3), q(4)
    q = q_in / norm2(q_in)
    associate (w => q(1), x => q(2), y => q(3), z => q(4))
      r(1, :) = [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)]
      r(2, :) = [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)]
      r(3, :) = [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]
    end associate
  end function rotation

  !> Eigenvalues in descending order by LAPACK (dsyev, ascending, reversed).
  function lapack_values(s) result(w)
    real(dp), intent(in) :: s(6)
    real(dp) :: w(3), a(3, 3), work(64), wa(3)
    integer :: info
    a = reshape([s(1), s(6), s(5), s(6), s(2), s(4), s(5), s(4), s(3)], [3, 3])
    call dsyev('N', 'U', 3, a, 3, wa, work, size(work), info)
    w = wa(3:1:-1)
    if (info /= 0) w = huge(1.0_dp)
  end function lapack_values

  !> Pseudo-random numbers in (-1, 1) from the Park-Miller generator with a fixed seed (the
  !! same sequence with every compiler; no integer overflow in 64 bits).
  subroutine next_random(state, x)
    integer(i8), intent(inout) :: state
    real(dp), intent(out) :: x(:)
    integer :: i
    do i = 1, size(x)
      state = modulo(16807_i8 * state, 2147483647_i8)
      x(i) = 2.0_dp * real(state, dp) / 2147483647.0_dp - 1.0_dp
    end do
  end subroutine next_random

  !> Fail unless p equals expected to tol * max |expected| (both descending).
  subroutine check_values(error, p, expected, label)
    type(error_t), allocatable, intent(out) :: error
    real(dp), intent(in) :: p(3), expected(3)
    character(len=*), intent(in) :: label
    real(dp) :: bound
    integer :: k
    bound = tol * maxval(abs(expected))
    do k = 1, 3
      call check(error, p(k), expected(k), label // ': principal value ' // str(k), abs=bound)
      if (allocated(error)) return
    end do
  end subroutine check_values

  ! ------------------------------------------------------------------ tests

  !> -100 MPa along n, nothing across: eigenvalues 0, 0, -100 (a double root at zero, where the
  !! cubic's acos is steepest). Frames: the axes, one tilted axis, random rotations.
  subroutine test_uniaxial(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: q(4), p(3), s(6)
    integer(i8) :: state
    integer :: i
    p = principal_values([-100.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
    call check_values(error, p, [0.0_dp, 0.0_dp, -100.0_dp], 'uniaxial along x')
    if (allocated(error)) return
    ! n = (1, 2, 2) / 3: s = -100 n n^T
    s = -100.0_dp / 9.0_dp * [1.0_dp, 4.0_dp, 4.0_dp, 4.0_dp, 2.0_dp, 2.0_dp]
    p = principal_values(s)
    call check_values(error, p, [0.0_dp, 0.0_dp, -100.0_dp], 'uniaxial along (1, 2, 2)/3')
    if (allocated(error)) return
    ! the audit's case: a finite-element uniaxial state, shears at round-off level
    p = principal_values([-100.0_dp, 3.0e-13_dp, -2.0e-13_dp, 1.0e-14_dp, 4.0e-12_dp, -5.0e-12_dp])
    call check_values(error, p, lapack_values([-100.0_dp, 3.0e-13_dp, -2.0e-13_dp, 1.0e-14_dp, 4.0e-12_dp, &
                                               -5.0e-12_dp]), 'uniaxial with round-off shears')
    if (allocated(error)) return
    call check(error, abs(p(1)) <= 1.0e-12_dp, 'most tensile of a uniaxial compression is round-off: ' // str(p(1)))
    if (allocated(error)) return
    state = 11
    do i = 1, 200
      call next_random(state, q)
      s = rotated([0.0_dp, -100.0_dp, 0.0_dp], rotation(q))
      p = principal_values(s)
      call check_values(error, p, [0.0_dp, 0.0_dp, -100.0_dp], 'rotated uniaxial ' // str(i))
      if (allocated(error)) return
    end do
  end subroutine test_uniaxial

  !> 50, 50, -20 MPa (a double root at the top) and 30, -70, -70 (at the bottom), rotated.
  subroutine test_biaxial_repeated(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: q(4), p(3)
    integer(i8) :: state
    integer :: i
    state = 5
    do i = 1, 200
      call next_random(state, q)
      p = principal_values(rotated([50.0_dp, -20.0_dp, 50.0_dp], rotation(q)))
      call check_values(error, p, [50.0_dp, 50.0_dp, -20.0_dp], 'biaxial 50 50 -20, rotation ' // str(i))
      if (allocated(error)) return
      p = principal_values(rotated([-70.0_dp, 30.0_dp, -70.0_dp], rotation(q)))
      call check_values(error, p, [30.0_dp, -70.0_dp, -70.0_dp], 'biaxial 30 -70 -70, rotation ' // str(i))
      if (allocated(error)) return
    end do
  end subroutine test_biaxial_repeated

  !> -5 MPa all round (a triple root) is returned exactly; zero gives zeros.
  subroutine test_hydrostatic(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: p(3)
    p = principal_values([-5.0_dp, -5.0_dp, -5.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
    call check(error, all(p == -5.0_dp), 'hydrostatic -5: ' // str(p(1)) // ' ' // str(p(2)) // ' ' // str(p(3)))
    if (allocated(error)) return
    p = principal_values([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
    call check(error, all(p == 0.0_dp), 'zero tensor')
    if (allocated(error)) return
    ! a triple root with round-off shears
    p = principal_values([-5.0_dp, -5.0_dp, -5.0_dp, 1.0e-15_dp, -2.0e-15_dp, 3.0e-15_dp])
    call check_values(error, p, [-5.0_dp, -5.0_dp, -5.0_dp], 'hydrostatic with round-off shears')
  end subroutine test_hydrostatic

  !> 3000 tensors R diag(lambda) R^T: random eigenvalues, every third pair of them nearly equal
  !! (1e-9 apart, where the cubic was worst), against dsyev; descending order.
  subroutine test_random_against_dsyev(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: q(4), lambda(3), s(6), p(3)
    integer(i8) :: state
    integer :: i
    state = 2024
    do i = 1, 3000
      call next_random(state, q)
      call next_random(state, lambda)
      lambda = 100.0_dp * lambda
      if (mod(i, 3) == 0) lambda(2) = lambda(1) * (1.0_dp + 1.0e-9_dp)
      s = rotated(lambda, rotation(q))
      p = principal_values(s)
      call check(error, p(1) >= p(2) .and. p(2) >= p(3), 'descending order, tensor ' // str(i))
      if (allocated(error)) return
      call check_values(error, p, lapack_values(s), 'random tensor ' // str(i))
      if (allocated(error)) return
    end do
  end subroutine test_random_against_dsyev

  !> No overflow or underflow at 1e+-300 MPa: the same relative accuracy.
  subroutine test_extreme_scales(error)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: r(3, 3), p(3), f
    integer :: k
    r = rotation([0.3_dp, -0.5_dp, 0.7_dp, 0.2_dp])
    do k = 1, 2
      f = merge(1.0e-300_dp, 1.0e300_dp, k == 1)
      p = principal_values(rotated(f * [2.0_dp, -1.0_dp, 0.5_dp], r))
      if (any(p /= p)) then
        call test_failed(error, 'NaN at scale ' // str(f))
        return
      end if
      call check_values(error, p / f, [2.0_dp, 0.5_dp, -1.0_dp], 'scale ' // str(f))
      if (allocated(error)) return
    end do
  end subroutine test_extreme_scales

end module test_principal
