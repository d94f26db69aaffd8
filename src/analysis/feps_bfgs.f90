!> ACCELERATION=bfgs: quasi-Newton updates of the factorized stiffness within a step, by the
!! two-loop recursion of the BFGS inverse update (Matthies and Strang 1979) with the factor
!! held as H0 = K^-1. The pairs are those of the step's earlier iterations: s (the correction
!! taken), y (the change of the internal forces, = -the change of the residual) and
!! rho = 1 / (s . y) > 0.
module feps_bfgs
  use feps_kinds, only: dp
  use feps_error, only: error_t
  use feps_linear_solver, only: linear_solver_t
  implicit none
  private

  !> The secant pairs of one (sub)step.
  type, public :: bfgs_t
    real(dp), allocatable :: s_hist(:, :), y_hist(:, :), rho(:)
    real(dp), allocatable :: r_old(:)    !! the residual the last direction was computed from
    integer :: npairs = 0
  contains
    procedure :: start
    procedure :: direction
    procedure :: record_correction
    procedure :: add_pair
  end type bfgs_t

contains

  !> No pair yet, room for one per iteration of a step of `neq` equations.
  subroutine start(self, neq, max_iterations)
    class(bfgs_t), intent(inout) :: self
    integer, intent(in) :: neq, max_iterations
    if (allocated(self%s_hist)) deallocate (self%s_hist, self%y_hist, self%rho, self%r_old)
    allocate (self%s_hist(neq, max_iterations), self%y_hist(neq, max_iterations), self%rho(max_iterations), &
              self%r_old(neq))
    self%npairs = 0
  end subroutine start

  !> The quasi-Newton direction d = H r: r is overwritten by d (with no pair, the plain solve
  !! by the factor held).
  subroutine direction(self, solver, r, error)
    class(bfgs_t), intent(inout) :: self
    class(linear_solver_t), intent(inout) :: solver
    real(dp), intent(inout) :: r(:)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: alpha(self%npairs), beta
    integer :: i
    self%r_old = r
    associate (s_hist => self%s_hist, y_hist => self%y_hist, rho => self%rho)
      do i = self%npairs, 1, -1
        alpha(i) = rho(i) * dot_product(s_hist(:, i), r)
        r = r - alpha(i) * y_hist(:, i)
      end do
      ! the secant updates hold the factor as H0 = K^-1 exactly: no lower-precision solve here
      ! (with mixed-precision solves test/data/block_shear.dat's BFGS stalled near 1e-5)
      solver%exact_solves = .true.
      call solver%solve(r, error)
      solver%exact_solves = .false.
      if (allocated(error)) return
      do i = 1, self%npairs
        beta = rho(i) * dot_product(y_hist(:, i), r)
        r = r + (alpha(i) - beta) * s_hist(:, i)
      end do
    end associate
  end subroutine direction

  !> The correction just taken (the direction, as added to the displacements).
  pure subroutine record_correction(self, du)
    class(bfgs_t), intent(inout) :: self
    real(dp), intent(in) :: du(:)
    self%s_hist(:, self%npairs + 1) = du
  end subroutine record_correction

  !> Keep the pair of the iteration just done when it has positive curvature, given the new
  !! residual r. When the residual grew (a gap opened or a point started to slide: the pairs
  !! describe a response that no longer holds) drop every pair and start again from the
  !! factor held.
  pure subroutine add_pair(self, r)
    class(bfgs_t), intent(inout) :: self
    real(dp), intent(in) :: r(:)
    real(dp) :: sy
    integer :: k
    k = self%npairs + 1
    self%y_hist(:, k) = self%r_old - r
    sy = dot_product(self%s_hist(:, k), self%y_hist(:, k))
    if (norm2(r) > norm2(self%r_old)) then
      self%npairs = 0
    else if (sy > 1.0e-10_dp * norm2(self%s_hist(:, k)) * norm2(self%y_hist(:, k))) then
      self%npairs = k
      self%rho(k) = 1.0_dp / sy
    end if
  end subroutine add_pair

end module feps_bfgs
