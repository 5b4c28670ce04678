!> The explicit Dormand-Prince 5(4) integrator (`regdae_explicit_rk`) behind the
!! integrator interface (`regdae_integrator`): integrator=dopri5, and the
!! nonstiff slot of integrator=auto. It integrates the eliminated formulation
!! z' = F(z, t) of the core's model; its state is z itself. With the automatic
!! weights (which follow the motion) the first steps after a restart stay within the
!! stability of the constraint modes (`constraint_mode_step`). `advance` runs
!! rk_integrator's advance (the monitor sampling every accepted step there) and
!! reports the stiffness test's hand-over (with integrator=auto) and the end of
!! a singular pass.
module regdae_dopri5_integrator
    use, intrinsic :: iso_c_binding, only: c_double
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success
    use regdae_solver_stats, only: solver_stats
    use regdae_explicit_rk, only: rk_integrator, continuous_extension
    use regdae_integrator, only: integrator, outcome_reached, outcome_pass_end, outcome_stiff, outcome_failed
    use regdae_solver_core, only: solver_core
    implicit none
    private

    public :: dopri5_in_slot

    !> Dormand-Prince on the core's model (see the module documentation).
    type, extends(integrator), public :: dopri5_integrator
        type(solver_core), pointer :: core => null()   !! the problem's state (set by the creator)
        type(rk_integrator) :: rk                      !! the method's state
        real(wp), allocatable :: z(:)                  !! the state at the last output time
    contains   ! the interface's procedures (regdae_integrator documents them)
        procedure :: start => dopri5_start
        procedure :: advance => dopri5_advance
        procedure :: state => dopri5_state
        procedure :: slope => dopri5_slope
        procedure :: interpolate => dopri5_interpolate
        procedure :: time => dopri5_time
        procedure :: last_step => dopri5_last_step
        procedure :: statistics => dopri5_statistics
        procedure :: stiffness => dopri5_stiffness
        procedure :: ready => dopri5_ready
        procedure :: free => dopri5_free
        procedure :: steps_taken => dopri5_steps
    end type dopri5_integrator

contains

    !> The Dormand-Prince integrator in the core's nonstiff slot (allocated there if
    !! the slot is empty); null if the slot holds another integrator.
    function dopri5_in_slot(core) result(p)
        type(solver_core), pointer, intent(in) :: core
        type(dopri5_integrator), pointer :: p
        p => null()
        if (.not. allocated(core%nonstiff)) allocate (dopri5_integrator :: core%nonstiff)
        select type (s => core%nonstiff)
        type is (dopri5_integrator)
            p => s
            p%core => core
        end select
    end function dopri5_in_slot

    !> Start at (t, z) with the first step h0 (0: chosen); the slope is the method's own.
    subroutine dopri5_start(self, t, z, stat, msg, h0, zp, y)
        class(dopri5_integrator), intent(inout), target :: self
        real(wp), intent(in) :: t, z(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), intent(in), optional :: h0, zp(:), y(:)
        real(wp) :: h
        h = 0.0_wp
        if (present(h0)) h = h0
        self%z = z
        call self%rk%start(self%core%model, t, z, h, stat)
        msg = ''
        if (stat /= regdae_success) msg = self%core%model%message
    end subroutine dopri5_start

    !> To tout with the core's tolerances and step limits, the monitor sampling the
    !! accepted steps; with integrator=auto, stopped where the stiffness test fires.
    subroutine dopri5_advance(self, tout, t_stop, outcome, stat, msg, one_step)
        class(dopri5_integrator), intent(inout), target :: self
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: t_stop
        integer, intent(out) :: outcome, stat
        character(len=:), allocatable, intent(out) :: msg
        logical, intent(in), optional :: one_step   !! not honoured (steps_singly() is false)
        associate (core => self%core)
            call self%rk%advance(core%model, tout, core%opts%rtol, core%atol_z, core%opts%h_max, &
                                 core%opts%max_steps, core%opts%stop_at_output, self%z, stat, &
                                 core%monitor, stop_when_stiff=core%switching, &
                                 stop_at_pass_end=core%stop_at_pass_end, stable_weights=core%follow_weights, &
                                 stable_always=core%rest_start)
            t_stop = tout
            outcome = outcome_reached   ! (msg is set where the caller reads it: not at tout, no allocation)
            if (stat /= regdae_success) then
                t_stop = self%rk%t
                msg = self%rk%message
                outcome = outcome_failed
            else if (core%monitor%alarm) then
                outcome = outcome_reached   ! the front reports the alarm at tout
            else if (self%rk%pass_stop) then
                t_stop = self%rk%t
                outcome = outcome_pass_end
            else if (self%rk%stiff_detected) then
                t_stop = self%rk%t
                outcome = outcome_stiff
            end if
            if (outcome /= outcome_reached .and. .not. allocated(msg)) msg = ''
        end associate
    end subroutine dopri5_advance

    function dopri5_state(self) result(u)
        class(dopri5_integrator), intent(in), target :: self
        real(c_double), pointer :: u(:)
        u => self%z
    end function dopri5_state

    !> The slope at the end of the last step (the first-same-as-last stage).
    function dopri5_slope(self) result(up)
        class(dopri5_integrator), intent(in), target :: self
        real(c_double), pointer :: up(:)
        up => self%rk%k1
    end function dopri5_slope

    !> The 4th-order continuous extension at t in the last step, into state().
    subroutine dopri5_interpolate(self, t, stat)
        class(dopri5_integrator), intent(inout), target :: self
        real(wp), intent(in) :: t
        integer, intent(out) :: stat
        call continuous_extension(self%rk, t, self%z)
        stat = regdae_success
    end subroutine dopri5_interpolate

    real(wp) function dopri5_time(self)
        class(dopri5_integrator), intent(in) :: self
        dopri5_time = self%rk%t
    end function dopri5_time

    real(wp) function dopri5_last_step(self)
        class(dopri5_integrator), intent(in) :: self
        dopri5_last_step = self%rk%h_last
    end function dopri5_last_step

    !> The steps taken (the Runge-Kutta core's count, at hand: no statistics record).
    integer(int64) function dopri5_steps(self) result(n)
        class(dopri5_integrator), intent(in) :: self
        n = self%rk%steps
    end function dopri5_steps

    !> Steps, slopes and rejected steps added to IDA's terms; the last step when active.
    subroutine dopri5_statistics(self, st, active)
        class(dopri5_integrator), intent(in) :: self
        type(solver_stats), intent(inout) :: st
        logical, intent(in) :: active
        st%steps = st%steps + self%rk%steps
        st%res_evals = st%res_evals + self%rk%evals
        st%err_test_fails = st%err_test_fails + self%rk%rejects
        if (active) st%h_last = self%rk%h_last
    end subroutine dopri5_statistics

    !> Hairer's estimate of |lambda| from the last step's two stages at its end:
    !! |k7 - k6| / |z_new - z6| (the stiffness test's, h |lambda| against 3.25).
    real(wp) function dopri5_stiffness(self, t) result(rho)
        class(dopri5_integrator), intent(inout), target :: self
        real(wp), intent(in) :: t
        real(wp) :: den
        rho = 0.0_wp
        if (.not. allocated(self%rk%k7)) return
        den = norm2(self%rk%z_new - self%rk%z_stage)
        if (den > 0.0_wp) rho = norm2(self%rk%k7 - self%rk%k6)/den
    end function dopri5_stiffness

    logical function dopri5_ready(self)
        class(dopri5_integrator), intent(in) :: self
        dopri5_ready = allocated(self%rk%z)
    end function dopri5_ready

    subroutine dopri5_free(self)
        class(dopri5_integrator), intent(inout) :: self
    end subroutine dopri5_free

end module regdae_dopri5_integrator
