!> Stresses in a local frame: the components of a stress tensor along the unit vectors of a
!! coordinate system at a point (for stress_cyl, the radial, hoop and axial stresses of a pipe).
module feps_stress_frames
  use feps_kinds, only: dp
  use feps_coordinate_system, only: coordinate_system_t
  implicit none
  private

  public :: stress_in_basis, stresses_in_system

contains

  !> The components T^T S T of the stress `s` [xx yy zz yz xz xy] (global Cartesian) in the
  !! orthonormal basis whose columns are `t` (e.g. radial, hoop, axial), in the same Voigt order
  !! [11 22 33 23 13 12] of the local axes.
  pure function stress_in_basis(s, t) result(local)
    real(dp), intent(in) :: s(6), t(3, 3)
    real(dp) :: local(6)
    real(dp) :: full(3, 3), st(3, 3)
    full = reshape([s(1), s(6), s(5), s(6), s(2), s(4), s(5), s(4), s(3)], [3, 3])
    st = matmul(transpose(t), matmul(full, t))
    local = [st(1, 1), st(2, 2), st(3, 3), st(2, 3), st(1, 3), st(1, 2)]
  end function stress_in_basis

  !> The stresses `s(6, n)` at the points `x(3, n)` in the local frame of `system` there.
  pure function stresses_in_system(s, x, system) result(local)
    real(dp), intent(in) :: s(:, :), x(:, :)
    type(coordinate_system_t), intent(in) :: system
    real(dp) :: local(6, size(s, 2))
    integer :: q
    do q = 1, size(s, 2)
      local(:, q) = stress_in_basis(s(:, q), system%local_basis(x(:, q)))
    end do
  end function stresses_in_system

end module feps_stress_frames
