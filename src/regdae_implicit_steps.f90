!> What the implicit integrators (`regdae_ida_integrator`, `regdae_radau_integrator`)
!! do around each of their steps inside `advance`, in one place: the step budget
!! of one advance (max_steps), and after an accepted step the monitor's sample
!! (`regdae_solver_sampling`) with its alarm, the end of a singular pass
!! (stop_at_pass_end), and with integrator=auto the switching policy's vote every
!! 20 steps (`regdae_switching_policy`). Each function returns .true. when the
!! advance stops there, with its outcome (`regdae_integrator`) and t_stop set.
module regdae_implicit_steps
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_err_integration
    use regdae_format, only: format_real, format_int
    use regdae_integrator, only: outcome_pass_end, outcome_nonstiff, outcome_alarm, outcome_exhausted
    use regdae_solver_core, only: solver_core
    use regdae_solver_sampling, only: sample_step
    use regdae_switching_policy, only: explicit_would_do
    implicit none
    private

    public :: budget_spent, sampled_alarm, after_step

contains

    !> max_steps steps taken in this advance (`taken`) without reaching tout: stop at
    !! t_now with outcome_exhausted, regdae_err_integration and a message naming `who`.
    logical function budget_spent(core, who, taken, t_now, tout, t_stop, outcome, stat, msg) result(stop)
        type(solver_core), intent(in) :: core
        character(len=*), intent(in) :: who    !! the integrator's name in the message
        integer, intent(in) :: taken           !! steps taken in this advance
        real(wp), intent(in) :: t_now, tout
        real(wp), intent(inout) :: t_stop
        integer, intent(inout) :: outcome, stat
        character(len=:), allocatable, intent(inout) :: msg
        stop = (taken >= core%opts%max_steps)
        if (.not. stop) return
        t_stop = t_now
        outcome = outcome_exhausted
        stat = regdae_err_integration
        msg = who//' took max_steps = '//format_int(core%opts%max_steps)//' steps without reaching tout = '// &
              format_real(tout)//' (t = '//format_real(t_now)//')'
    end function budget_spent

    !> The monitor samples the implicit integrator's state at t (the stiff slot's
    !! state() and slope() there); its alarm stops at t (outcome_alarm).
    logical function sampled_alarm(core, t, t_stop, outcome) result(stop)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t
        real(wp), intent(inout) :: t_stop
        integer, intent(inout) :: outcome
        call sample_step(core, t)
        core%sampled_t = t
        stop = core%monitor%alarm
        if (.not. stop) return
        t_stop = t
        outcome = outcome_alarm
    end function sampled_alarm

    !> After the `taken`-th accepted step of this advance, ending at t_now: the sample
    !! and its alarm and the end of a singular pass (t_now <= tout), the hand-back
    !! vote of integrator=auto every 20 steps (t_now < tout).
    logical function after_step(core, taken, t_now, tout, t_stop, outcome) result(stop)
        type(solver_core), intent(inout), target :: core
        integer, intent(in) :: taken
        real(wp), intent(in) :: t_now, tout
        real(wp), intent(inout) :: t_stop
        integer, intent(inout) :: outcome
        stop = .true.
        if (t_now <= tout) then
            if (sampled_alarm(core, t_now, t_stop, outcome)) return
            if (core%stop_at_pass_end .and. core%monitor%pass_ended .and. t_now < tout) then
                t_stop = t_now   ! the integrator's state is the step's end
                outcome = outcome_pass_end
                return
            end if
        end if
        if (core%switching .and. t_now < tout .and. mod(taken, 20) == 0) then
            if (explicit_would_do(core, t_now)) then
                t_stop = t_now
                outcome = outcome_nonstiff
                return
            end if
        end if
        stop = .false.
    end function after_step

end module regdae_implicit_steps
