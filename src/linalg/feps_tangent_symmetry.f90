!> Symmetric stand-ins for non-symmetric point tangents, for the symmetric solvers.
!!
!! A material tangent is non-symmetric under non-associated flow (psi /= phi) and where an
!! interface gap closes inside a step. feps's solvers (CHOLMOD, skyline) factorize symmetric
!! matrices, so such a tangent is replaced by a symmetric stand-in: the material's own
!! (`symmetric_stand_in` of feps_material), by default the nearest symmetric positive
!! semi-definite matrix below. Only the iteration matrix changes: the residual, hence a
!! converged solution, does not.
module feps_tangent_symmetry
  use feps_kinds, only: dp
  use feps_lapack, only: dsyev
  implicit none
  private

  public :: nearest_symmetric_psd

contains

  !> Replace `d` by the symmetric positive semi-definite matrix nearest to it in the Frobenius
  !! norm (Higham 1988): its symmetric part with the negative eigenvalues set to zero. The
  !! symmetric part alone is indefinite wherever psi /= phi: at a sliding interface point its
  !! determinant is -(ks kn / h)^2 (tan phi - tan psi)^2 / 4 (h = ks + kn tan phi tan psi), so
  !! with psi = 0 a joint whose faces slide gave an assembled tangent that Cholesky refuses.
  !! Where the symmetric part is semi-definite already, that is the result.
  subroutine nearest_symmetric_psd(d)
    real(dp), intent(inout) :: d(:, :)
    real(dp) :: s(size(d, 1), size(d, 1)), w(size(d, 1)), work(64)
    integer :: n, info, k
    n = size(d, 1)
    s = 0.5_dp * (d + transpose(d))
    d = s
    call dsyev('V', 'U', n, s, n, w, work, size(work), info)
    if (info /= 0 .or. minval(w) >= 0.0_dp) return
    d = 0.0_dp
    do k = 1, n
      if (w(k) > 0.0_dp) d = d + w(k) * spread(s(:, k), 2, n) * spread(s(:, k), 1, n)
    end do
  end subroutine nearest_symmetric_psd

end module feps_tangent_symmetry
