!> The eliminated formulation z' = F(t, z) of a regularized model (its
!! slope_eliminated) as a Radau IIA system (`regdae_radau_system`): what Radau
!! integrates with integrator=radau on the eliminated formulation
!! (`regdae_radau_integrator`), and what integrator=auto's start test takes its
!! Jacobian of (`regdae_switching_policy`), the same difference quotients.
module regdae_eliminated_ode
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success
    use regdae_regularization, only: regularized_dae
    use regdae_radau_system, only: radau_system
    implicit none
    private

    !> The eliminated formulation of `model` (set by the owner, with y of size model%m).
    type, extends(radau_system), public :: eliminated_ode
        type(regularized_dae), pointer :: model => null()
        real(wp), allocatable :: y(:)   !! the multiplier of the last evaluation
        character(len=:), allocatable :: failure   !! the model's message at F's last failure ('' none)
        real(wp) :: seen_eps = 0.0_wp                !! the model's eps at the last `note_parameters`
        real(wp), allocatable :: seen_w(:)           !! its weights w there
    contains
        !> F(t, z): the model's slope_eliminated (failure: its message kept).
        procedure :: rhs => eliminated_rhs
        !> Whether eps or the weights changed since the last call (which records them).
        procedure :: note_parameters => eliminated_note_parameters
    end type eliminated_ode

contains

    subroutine eliminated_rhs(self, t, u, f, stat, recoverable)
        class(eliminated_ode), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        call self%model%slope_eliminated(t, u, f, self%y, stat, recoverable)
        if (stat /= regdae_success) self%failure = self%model%message
    end subroutine eliminated_rhs

    !> Whether the model's eps or weights w (which the monitor sets between steps)
    !! differ from their values at the last call; records them.
    subroutine eliminated_note_parameters(self, changed)
        class(eliminated_ode), intent(inout) :: self
        logical, intent(out) :: changed
        changed = (self%model%eps /= self%seen_eps) .or. .not. allocated(self%seen_w)
        if (.not. changed) changed = size(self%seen_w) /= size(self%model%w)
        if (.not. changed) changed = any(self%model%w /= self%seen_w)
        if (.not. changed) return
        self%seen_eps = self%model%eps
        self%seen_w = self%model%w
    end subroutine eliminated_note_parameters

end module regdae_eliminated_ode
