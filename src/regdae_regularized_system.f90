!> The regularized DAE (`regdae_regularization`) as an implicit system for IDA:
!! the eliminated formulation (unknowns z, the multiplier solved inside the
!! residual) or the multiplier formulation (unknowns (z, y)).
module regdae_regularized_system
    use regdae_kinds, only: wp
    use regdae_regularization, only: regularized_dae
    use regdae_implicit_system, only: implicit_system
    implicit none
    private

    !> The eliminated (neq = n) or multiplier (neq = n + m) residual of a model.
    type, extends(implicit_system), public :: regularized_system
        type(regularized_dae), pointer :: model => null()   !! the model evaluated (owned by the solver)
        integer :: n = 0                                    !! size of the state z
        real(wp), allocatable :: y_work(:)                  !! eliminated: the multiplier of the last residual
    contains
        procedure :: residual => regularized_residual
        procedure :: jacobian_phase => regularized_jacobian_phase
        procedure :: nonnegative_unknowns => regularized_nonnegative
    end type regularized_system

    public :: new_regularized_system

contains

    !> The residual of `model` with `neq` unknowns: n (eliminated) or n + m (multiplier).
    function new_regularized_system(model, n, neq) result(sys)
        type(regularized_dae), pointer, intent(in) :: model
        integer, intent(in) :: n, neq
        type(regularized_system) :: sys
        sys%model => model
        sys%n = n
        sys%neq = neq
        allocate (sys%y_work(model%m))
        sys%message = ''
    end function new_regularized_system

    subroutine regularized_residual(self, t, u, up, res, stat, recoverable)
        class(regularized_system), intent(inout) :: self
        real(wp), intent(in) :: t, u(:), up(:)
        real(wp), intent(out) :: res(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        integer :: n
        n = self%n
        if (self%neq == n) then
            call self%model%residual_eliminated(t, u, up, res, self%y_work, stat, recoverable)
        else
            call self%model%residual_multiplier(t, u(1:n), u(n + 1:), up(1:n), res(1:n), res(n + 1:), &
                                                stat, recoverable)
        end if
        if (stat /= 0) self%message = self%model%message
    end subroutine regularized_residual

    ! The state z (u without the multiplier) linearizes the problem's f there.
    subroutine regularized_jacobian_phase(self, t, u, on, stat, recoverable)
        class(regularized_system), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        logical, intent(in) :: on
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        call self%model%linearize_rhs(t, u(1:self%n), on, stat, recoverable)
        if (stat /= 0) self%message = self%model%message
    end subroutine regularized_jacobian_phase

    ! The components of the state z the problem keeps >= 0 (none of the multiplier).
    function regularized_nonnegative(self) result(mask)
        class(regularized_system), intent(in) :: self
        logical :: mask(self%neq)
        mask = .false.
        mask(1:self%n) = self%model%nonnegative_state()
    end function regularized_nonnegative

end module regdae_regularized_system
