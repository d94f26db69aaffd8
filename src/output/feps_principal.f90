!> Principal stresses of a symmetric 3x3 stress tensor given in Voigt order.
module feps_principal
  use feps_kinds, only: dp, pi
  implicit none
  private

  public :: principal_values

contains

  !> Eigenvalues in descending order (most tensile first) by the trigonometric solution of
  !! the characteristic cubic; exact for repeated roots, no iteration, no NaN.
  pure function principal_values(s) result(p)
    real(dp), intent(in) :: s(6)   !! [xx yy zz yz xz xy]
    real(dp) :: p(3)
    real(dp) :: q, p1, p2, pp, r, phi, b(6), scale
    scale = maxval(abs(s))
    if (scale == 0.0_dp) then
      p = 0.0_dp
      return
    end if
    p1 = s(4)**2 + s(5)**2 + s(6)**2
    q = (s(1) + s(2) + s(3)) / 3.0_dp
    if (p1 <= (epsilon(1.0_dp) * scale)**2) then
      p = [s(1), s(2), s(3)]
      call sort3(p)
      return
    end if
    p2 = (s(1) - q)**2 + (s(2) - q)**2 + (s(3) - q)**2 + 2.0_dp * p1
    pp = sqrt(p2 / 6.0_dp)
    b = s / pp
    b(1:3) = (s(1:3) - q) / pp
    ! r = det(B) / 2
    r = 0.5_dp * (b(1) * (b(2) * b(3) - b(4) * b(4)) - b(6) * (b(6) * b(3) - b(4) * b(5)) + &
                  b(5) * (b(6) * b(4) - b(2) * b(5)))
    r = max(-1.0_dp, min(1.0_dp, r))
    phi = acos(r) / 3.0_dp
    p(1) = q + 2.0_dp * pp * cos(phi)
    p(3) = q + 2.0_dp * pp * cos(phi + 2.0_dp * pi / 3.0_dp)
    p(2) = 3.0_dp * q - p(1) - p(3)
  end function principal_values

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
