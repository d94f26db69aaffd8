!> The energy line search of a Newton correction du (LINESEARCH=energy): the factor s along
!! du at which the residual is orthogonal to it, g(s) = du . R(u + s du) = 0, the stationary
!! point of the potential energy along du where there is one (Crisfield 1991, Non-linear
!! Finite Element Analysis of Solids and Structures, vol. 1, section 9.3: a "slack" search
!! that stops once |g(s)| <= eta |g(0)|; the CalculiX manual's "Line search" section
!! describes the same orthogonality condition with s clamped to [0.25, 1.01]).
!!
!! Only an overshooting correction is searched: g(0) > 0 (du points downhill) and g(1) < 0
!! (the energy rises again before s = 1), the case of a Newton method cycling over a kink of
!! a non-smooth law (points switching between sticking and sliding). The root is bracketed in
!! (0, 1) and found by regula falsi with the Illinois modification (the end kept twice in a
!! row has its g halved), s clamped to [s_min, 1]: no extrapolation beyond the full
!! correction. The caller evaluates the residual at each s this asks for, and keeps the last.
module feps_line_search
  use feps_kinds, only: dp
  implicit none
  private

  real(dp), parameter, public :: line_search_eta = 0.5_dp    !! accept once |g(s)| <= eta g(0)
  real(dp), parameter, public :: line_search_s_min = 0.1_dp  !! the shortest correction taken
  !> residual evaluations a search may add to the iteration's own one at s = 1
  integer, parameter, public :: line_search_max_evaluations = 4

  !> The bracket of a search and the next factor to evaluate.
  type, public :: line_search_t
    real(dp) :: s = 1.0_dp          !! the factor to evaluate next (or the one accepted when done)
    real(dp) :: g0 = 0.0_dp         !! g(0) = du . R(u)
    real(dp) :: s_lo = 0.0_dp, g_lo = 0.0_dp   !! the end where g > 0 (short of the root)
    real(dp) :: s_hi = 1.0_dp, g_hi = 0.0_dp   !! the end where g < 0 (beyond it)
    integer :: kept = 0             !! the end kept by the last update: -1 lo, +1 hi, 0 none yet
    integer :: evaluations = 0      !! residual evaluations added so far
    logical :: done = .true.
  end type line_search_t

  public :: line_search_begin, line_search_next

contains

  !> Start from g(0) and g(1) (the full correction). done when nothing is to be searched (no
  !! overshoot, or |g(1)| already small enough); otherwise ls%s is the first factor to evaluate.
  pure subroutine line_search_begin(ls, g0, g1, eta, s_min)
    type(line_search_t), intent(out) :: ls
    real(dp), intent(in) :: g0, g1
    real(dp), intent(in) :: eta, s_min
    ls%g0 = g0
    ls%s_lo = 0.0_dp
    ls%g_lo = g0
    ls%s_hi = 1.0_dp
    ls%g_hi = g1
    ls%s = 1.0_dp
    ls%kept = 0
    ls%evaluations = 0
    ls%done = .not. (g0 > 0.0_dp .and. g1 < 0.0_dp .and. abs(g1) > eta * g0)
    if (.not. ls%done) ls%s = secant(ls, s_min)
  end subroutine line_search_begin

  !> g at ls%s (just evaluated): accept it, or narrow the bracket and set the next ls%s.
  pure subroutine line_search_next(ls, g, eta, s_min, max_evaluations)
    type(line_search_t), intent(inout) :: ls
    real(dp), intent(in) :: g
    real(dp), intent(in) :: eta, s_min
    integer, intent(in) :: max_evaluations
    ls%evaluations = ls%evaluations + 1
    ! still beyond the root at the shortest correction allowed: nothing shorter is tried; a
    ! residual that left double precision ends the search (the iteration then diverges)
    ls%done = abs(g) <= eta * ls%g0 .or. ls%evaluations >= max_evaluations .or. &
              (g < 0.0_dp .and. ls%s <= s_min) .or. .not. (abs(g) <= huge(g))
    if (ls%done) return
    if (g < 0.0_dp) then
      ls%s_hi = ls%s
      ls%g_hi = g
      if (ls%kept == -1) ls%g_lo = 0.5_dp * ls%g_lo     ! Illinois: lo kept twice
      ls%kept = -1
    else
      ls%s_lo = ls%s
      ls%g_lo = g
      if (ls%kept == 1) ls%g_hi = 0.5_dp * ls%g_hi
      ls%kept = 1
    end if
    ls%s = secant(ls, s_min)
  end subroutine line_search_next

  !> The root of the straight line through (s_lo, g_lo) and (s_hi, g_hi), g_lo > 0 > g_hi,
  !! clamped to [s_min, 1].
  pure real(dp) function secant(ls, s_min) result(s)
    type(line_search_t), intent(in) :: ls
    real(dp), intent(in) :: s_min
    s = ls%s_lo + (ls%s_hi - ls%s_lo) * ls%g_lo / (ls%g_lo - ls%g_hi)
    s = min(1.0_dp, max(s_min, s))
  end function secant

end module feps_line_search
