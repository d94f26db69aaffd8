!> Principal stresses of a symmetric 3x3 stress tensor given in Voigt order.
module feps_principal
  use feps_kinds, only: dp
  implicit none
  private

  public :: principal_values, principal_frame

contains

  !> Eigenvalues in descending order (most tensile first), accurate to a few ulps of the
  !! tensor's largest eigenvalue in magnitude, repeated roots included (`jacobi_rotations`).
  pure function principal_values(s) result(p)
    real(dp), intent(in) :: s(6)   !! [xx yy zz yz xz xy]
    real(dp) :: p(3)
    call jacobi_rotations(s, p)
    call sort3(p)
  end function principal_values

  !> Eigenvalues (in no particular order) and the orthonormal eigenvectors (columns of
  !! `vectors`, vectors(:, k) belongs to values(k)) of a symmetric 3x3 tensor in Voigt order,
  !! by the same Jacobi rotations as `principal_values` (the values are bit for bit its own).
  pure subroutine principal_frame(s, values, vectors)
    real(dp), intent(in) :: s(6)   !! [xx yy zz yz xz xy]
    real(dp), intent(out) :: values(3)
    real(dp), intent(out) :: vectors(3, 3)
    call jacobi_rotations(s, values, vectors)
  end subroutine principal_frame

  !> Cyclic Jacobi rotations with Rutishauser's stable updates (Golub and Van Loan, Matrix
  !! Computations, section 8.5): every rotation is orthogonal, so rounding stays at the level of
  !! the tensor's norm. The closed-form solution of the characteristic cubic it replaces lost up
  !! to half the digits near a repeated root (acos is infinitely steep at +-1): a uniaxial
  !! 100 MPa compression had a most tensile stress of 1e-6 MPa. A 3x3 tensor needs about five
  !! sweeps of three rotations. With `v`, the rotations are accumulated into it (the
  !! eigenvectors as columns).
  pure subroutine jacobi_rotations(s, p, v)
    real(dp), intent(in) :: s(6)
    real(dp), intent(out) :: p(3)
    real(dp), intent(out), optional :: v(3, 3)
    integer, parameter :: max_sweeps = 50   ! never reached: 3x3 converges quadratically
    ! the off-diagonal pair (i, j) of each rotation and the third index k
    integer, parameter :: pair_i(3) = [1, 1, 2], pair_j(3) = [2, 3, 3], third(3) = [3, 2, 1]
    real(dp) :: a(3, 3), d(3), largest, g, h, t, theta, c, sn, tau, api, apj, vi(3), vj(3)
    integer :: sweep, r, i, j, k, e

    if (present(v)) then
      v = 0.0_dp
      v(1, 1) = 1.0_dp
      v(2, 2) = 1.0_dp
      v(3, 3) = 1.0_dp
    end if
    largest = maxval(abs(s))
    if (largest == 0.0_dp) then
      p = 0.0_dp
      return
    end if
    ! scale by a power of two (exact) so that squares can neither overflow nor underflow
    e = exponent(largest)
    a(1, 1) = scale(s(1), -e)
    a(2, 2) = scale(s(2), -e)
    a(3, 3) = scale(s(3), -e)
    a(2, 3) = scale(s(4), -e)
    a(1, 3) = scale(s(5), -e)
    a(1, 2) = scale(s(6), -e)
    d = [a(1, 1), a(2, 2), a(3, 3)]

    do sweep = 1, max_sweeps
      if (a(1, 2) == 0.0_dp .and. a(1, 3) == 0.0_dp .and. a(2, 3) == 0.0_dp) exit
      do r = 1, 3
        i = pair_i(r)
        j = pair_j(r)
        k = third(r)
        if (a(i, j) == 0.0_dp) cycle
        g = 100.0_dp * abs(a(i, j))
        ! after four sweeps an element below the diagonal's rounding is set to zero
        if (sweep > 4 .and. abs(d(i)) + g == abs(d(i)) .and. abs(d(j)) + g == abs(d(j))) then
          a(i, j) = 0.0_dp
          cycle
        end if
        h = d(j) - d(i)
        if (abs(h) + g == abs(h)) then
          t = a(i, j) / h                  ! theta so large that t = 1 / (2 theta)
        else
          theta = 0.5_dp * h / a(i, j)
          t = 1.0_dp / (abs(theta) + sqrt(1.0_dp + theta * theta))
          if (theta < 0.0_dp) t = -t
        end if
        c = 1.0_dp / sqrt(1.0_dp + t * t)
        sn = t * c
        tau = sn / (1.0_dp + c)
        h = t * a(i, j)
        d(i) = d(i) - h
        d(j) = d(j) + h
        a(i, j) = 0.0_dp
        ! the two elements coupling i and j to the third index (upper triangle)
        api = a(min(i, k), max(i, k))
        apj = a(min(j, k), max(j, k))
        a(min(i, k), max(i, k)) = api - sn * (apj + api * tau)
        a(min(j, k), max(j, k)) = apj + sn * (api - apj * tau)
        if (present(v)) then
          vi = v(:, i)
          vj = v(:, j)
          v(:, i) = vi - sn * (vj + vi * tau)
          v(:, j) = vj + sn * (vi - vj * tau)
        end if
      end do
    end do

    p = scale(d, e)
  end subroutine jacobi_rotations

  pure subroutine sort3(p)
    real(dp), intent(inout) :: p(3)
    real(dp) :: t
    if (p(1) < p(2)) then
      t = p(1); p(1) = p(2); p(2) = t
    end if
    if (p(2) < p(3)) then
      t = p(2); p(2) = p(3); p(3) = t
    end if
    if (p(1) < p(2)) then
      t = p(1); p(1) = p(2); p(2) = t
    end if
  end subroutine sort3

end module feps_principal
