!> The contract of a solution method of the incremental analysis (thesis 2.6.3): the
!! decisions that tell one method from another, asked by the step loop of
!! feps_incremental_analysis, which does the arithmetic. A method is one file extending
!! `solution_method_t` plus one line in feps_solution_methods (its catalog).
!!
!! What a decision may look at is the factor the run holds (`factor_state_t`, carried from
!! step to step and from stage to stage, whatever method the next stage uses) and the stage's
!! controls; the defaults are those of Newton-Raphson (a new tangent every step, the
!! unbalanced force carried, a step must converge only to within the divergence limit).
module feps_solution_method
  use feps_kinds, only: dp
  use feps_model, only: controls_t
  implicit none
  private

  !> The factor held by the run and what the last (sub)step left for the next decision.
  type, public :: factor_state_t
    logical :: have_factor = .false.     !! a factor of some stiffness is held
    logical :: factor_elastic = .false.  !! it is of the elastic stiffness (not a tangent)
    logical :: elastic_retry = .false.   !! the next factorization is the elastic stiffness
    real(dp) :: rel_prev = 0.0_dp        !! |R| / |P| at the end of the last (sub)step
    real(dp) :: abs_prev = 0.0_dp        !! |R| (N) at the end of the last (sub)step
    real(dp) :: rel_accepted = 0.0_dp    !! |R| / |P| of the last state accepted (rel_prev may be reset
                                         !! to force a factorization; a stop's message needs this one)
  end type factor_state_t

  type, abstract, public :: solution_method_t
  contains
    procedure(name_interface), deferred :: name
    procedure :: needs_factor
    procedure :: factorizes_elastic
    procedure :: exact_tangent
    procedure :: carries_residual
    procedure :: after_cutback
    procedure :: refactors_for_new_elements
    procedure :: takes_bfgs
    procedure :: step_accepted
  end type solution_method_t

  abstract interface
    !> The method's name as METHOD= spells it.
    pure function name_interface(self) result(name)
      import :: solution_method_t
      class(solution_method_t), intent(in) :: self
      character(len=:), allocatable :: name
    end function name_interface
  end interface

contains

  !> Whether the (sub)step about to be taken factorizes a stiffness first. Default: always.
  pure logical function needs_factor(self, f, c)
    class(solution_method_t), intent(in) :: self
    type(factor_state_t), intent(in) :: f
    type(controls_t), intent(in) :: c
    needs_factor = .true.
  end function needs_factor

  !> Whether that factorization is of the elastic stiffness rather than the tangent of the
  !! committed state. Default: only for the retry a cut-back asked for.
  pure logical function factorizes_elastic(self, f)
    class(solution_method_t), intent(in) :: self
    type(factor_state_t), intent(in) :: f
    factorizes_elastic = f%elastic_retry
  end function factorizes_elastic

  !> Whether the tangent is the exact one of the current iterate, refactorized every
  !! iteration and factorized as it is when non-symmetric (LU). Default: no.
  pure logical function exact_tangent(self)
    class(solution_method_t), intent(in) :: self
    exact_tangent = .false.
  end function exact_tangent

  !> Whether the unbalanced force a step leaves is carried into the next (eq. 2.6.4).
  !! Default: yes.
  pure logical function carries_residual(self)
    class(solution_method_t), intent(in) :: self
    carries_residual = .true.
  end function carries_residual

  !> What a cut-back leaves for the next factorization decision. Default: the last residual
  !! forgotten (a new factor, of the committed state's tangent).
  pure subroutine after_cutback(self, f)
    class(solution_method_t), intent(in) :: self
    type(factor_state_t), intent(inout) :: f
    f%rel_prev = huge(1.0_dp)
    f%elastic_retry = .false.
  end subroutine after_cutback

  !> Whether elements born in a later stage drop the factor held. Default: no (the method's
  !! own decision refactorizes).
  pure logical function refactors_for_new_elements(self)
    class(solution_method_t), intent(in) :: self
    refactors_for_new_elements = .false.
  end function refactors_for_new_elements

  !> Whether ACCELERATION=bfgs applies (quasi-Newton pairs on the factor held).
  pure logical function takes_bfgs(self, c)
    class(solution_method_t), intent(in) :: self
    type(controls_t), intent(in) :: c
    takes_bfgs = c%bfgs .and. c%max_iterations > 1
  end function takes_bfgs

  !> Whether a (sub)step whose iterations ended at |R| / |P| = rel, |R| = rnorm is accepted.
  !! Default: within the divergence limit, the rest carried (thesis 2.6.3).
  pure logical function step_accepted(self, rel, rnorm, c)
    class(solution_method_t), intent(in) :: self
    real(dp), intent(in) :: rel, rnorm
    type(controls_t), intent(in) :: c
    step_accepted = rel < max(c%divergence, c%delta1) .or. rnorm < c%delta2
  end function step_accepted

end module feps_solution_method
