!> Coordinate systems: 2D and 3D Cartesian and cylindrical (r, theta [deg], z) about an axis.
!! DATAIN numbers them 1 (2D Cartesian), 2 (3D Cartesian) and 3 (cylindrical about global z);
!! a deck may define more (an origin and an axis). Nodal systems use `local_basis`.
module feps_coordinate_system
  use feps_kinds, only: dp, deg2rad, rad2deg
  implicit none
  private

  integer, parameter, public :: csys_cartesian_2d = 1
  integer, parameter, public :: csys_cartesian = 2
  integer, parameter, public :: csys_cylindrical = 3

  !> A coordinate system: kind, origin and rotation (columns: local axes in global terms).
  type, public :: coordinate_system_t
    integer :: kind = csys_cartesian
    real(dp) :: origin(3) = 0.0_dp
    real(dp) :: axes(3, 3) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, &
                                      0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
  contains
    procedure :: to_global      !! local coordinates -> global Cartesian point
    procedure :: from_global    !! global point -> local coordinates (theta in (-180, 180])
    procedure :: local_basis    !! unit vectors (radial, hoop, axial) at a point, as columns
    procedure :: ncoords        !! number of coordinates a point has in this system
  end type coordinate_system_t

  public :: default_coordinate_systems, cylindrical_about

contains

  !> The three systems DATAIN knows.
  pure function default_coordinate_systems() result(systems)
    type(coordinate_system_t) :: systems(3)
    systems(1)%kind = csys_cartesian_2d
    systems(2)%kind = csys_cartesian
    systems(3)%kind = csys_cylindrical
  end function default_coordinate_systems

  !> A cylindrical system about the axis through `origin` along `axis`; theta = 0 along `ref`
  !! projected normal to the axis.
  pure function cylindrical_about(origin, axis, ref) result(cs)
    real(dp), intent(in) :: origin(3), axis(3), ref(3)
    type(coordinate_system_t) :: cs
    real(dp) :: e1(3), e2(3), e3(3)
    e3 = axis / norm2(axis)
    e1 = ref - dot_product(ref, e3) * e3
    e1 = e1 / norm2(e1)
    e2 = [e3(2) * e1(3) - e3(3) * e1(2), e3(3) * e1(1) - e3(1) * e1(3), e3(1) * e1(2) - e3(2) * e1(1)]
    cs%kind = csys_cylindrical
    cs%origin = origin
    cs%axes(:, 1) = e1
    cs%axes(:, 2) = e2
    cs%axes(:, 3) = e3
  end function cylindrical_about

  pure integer function ncoords(self)
    class(coordinate_system_t), intent(in) :: self
    ncoords = merge(2, 3, self%kind == csys_cartesian_2d)
  end function ncoords

  pure function to_global(self, local) result(x)
    class(coordinate_system_t), intent(in) :: self
    real(dp), intent(in) :: local(3)
    real(dp) :: x(3), c(3)
    select case (self%kind)
    case (csys_cylindrical)
      c = [local(1) * cos(local(2) * deg2rad), local(1) * sin(local(2) * deg2rad), local(3)]
    case (csys_cartesian_2d)
      c = [local(1), local(2), 0.0_dp]
    case default
      c = local
    end select
    x = self%origin + matmul(self%axes, c)
  end function to_global

  pure function from_global(self, x) result(local)
    class(coordinate_system_t), intent(in) :: self
    real(dp), intent(in) :: x(3)
    real(dp) :: local(3), c(3)
    c = matmul(transpose(self%axes), x - self%origin)
    select case (self%kind)
    case (csys_cylindrical)
      local(1) = hypot(c(1), c(2))
      local(2) = atan2(c(2), c(1)) * rad2deg
      local(3) = c(3)
    case default
      local = c
    end select
  end function from_global

  !> Unit vectors of the system's directions at global point x, as columns of a 3x3 matrix
  !! (radial, hoop, axial for a cylindrical system). On the axis the radial direction is the
  !! system's first axis.
  pure function local_basis(self, x) result(t)
    class(coordinate_system_t), intent(in) :: self
    real(dp), intent(in) :: x(3)
    real(dp) :: t(3, 3), c(3), r, er(3)
    if (self%kind /= csys_cylindrical) then
      t = self%axes
      return
    end if
    c = matmul(transpose(self%axes), x - self%origin)
    r = hypot(c(1), c(2))
    if (r > 0.0_dp) then
      er = [c(1) / r, c(2) / r, 0.0_dp]
    else
      er = [1.0_dp, 0.0_dp, 0.0_dp]
    end if
    t(:, 1) = matmul(self%axes, er)
    t(:, 2) = matmul(self%axes, [-er(2), er(1), 0.0_dp])
    t(:, 3) = self%axes(:, 3)
  end function local_basis

end module feps_coordinate_system
