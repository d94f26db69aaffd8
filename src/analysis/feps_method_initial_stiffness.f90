!> Initial stiffness (thesis 2.6.3): the elastic stiffness factorized once and kept for every
!! step; a stage whose elements change factorizes it again. A factor another stage's method
!! left is a tangent, not the initial stiffness, and is not kept.
module feps_method_initial_stiffness
  use feps_model, only: controls_t
  use feps_solution_method, only: solution_method_t, factor_state_t
  implicit none
  private

  type, public, extends(solution_method_t) :: initial_stiffness_t
  contains
    procedure :: name
    procedure :: needs_factor
    procedure :: factorizes_elastic
    procedure :: after_cutback
    procedure :: refactors_for_new_elements
  end type initial_stiffness_t

contains

  pure function name(self) result(method_name)
    class(initial_stiffness_t), intent(in) :: self
    character(len=:), allocatable :: method_name
    method_name = 'initial-stiffness'
  end function name

  pure logical function needs_factor(self, f, c)
    class(initial_stiffness_t), intent(in) :: self
    type(factor_state_t), intent(in) :: f
    type(controls_t), intent(in) :: c
    needs_factor = .not. (f%have_factor .and. f%factor_elastic)
  end function needs_factor

  pure logical function factorizes_elastic(self, f)
    class(initial_stiffness_t), intent(in) :: self
    type(factor_state_t), intent(in) :: f
    factorizes_elastic = .true.
  end function factorizes_elastic

  !> The factor is the elastic stiffness already: a cut-back changes nothing of it.
  pure subroutine after_cutback(self, f)
    class(initial_stiffness_t), intent(in) :: self
    type(factor_state_t), intent(inout) :: f
    f%elastic_retry = .false.
  end subroutine after_cutback

  pure logical function refactors_for_new_elements(self)
    class(initial_stiffness_t), intent(in) :: self
    refactors_for_new_elements = .true.
  end function refactors_for_new_elements

end module feps_method_initial_stiffness
