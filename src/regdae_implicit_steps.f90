!> The implicit integrators' loop over steps, written once: `implicit_stepper`
!! extends the integrator interface (`regdae_integrator`) with an `advance` over
!! three primitives of its extensions (`regdae_ida_integrator`,
!! `regdae_radau_integrator`): one step towards tout (landing on it with
!! stop_at_output), the state at the last step's end, and the method's name.
!! Around each step it does, in one place: the step budget of one advance
!! (max_steps), and after an accepted step the monitor's sample
!! (`regdae_solver_sampling`) with its alarm, the end of a singular pass
!! (stop_at_pass_end), and with integrator=auto the switching policy's vote every
!! 20 steps (`regdae_switching_policy`). Each of the module's functions
!! budget_spent, sampled_alarm and after_step returns .true. when the advance
!! stops there, with its outcome (`regdae_integrator`) and t_stop set.
module regdae_implicit_steps
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_integration
    use regdae_format, only: format_real, format_int
    use regdae_integrator, only: integrator, outcome_reached, outcome_pass_end, outcome_nonstiff, outcome_alarm, &
                                 outcome_exhausted, outcome_failed, outcome_broken
    use regdae_solver_core, only: solver_core
    use regdae_solver_sampling, only: sample_step
    use regdae_switching_policy, only: explicit_would_do
    implicit none
    private

    !> The length of a stepper's name (blank-padded).
    integer, parameter, public :: name_len = 8

    !> An implicit integrator of the core's model, stepping under the loop of
    !! `advance` (written here once) through the deferred one-step primitives.
    type, abstract, extends(integrator), public :: implicit_stepper
        type(solver_core), pointer :: core => null()   !! the problem's state (set by the integrator's *_in_slot)
    contains
        !> One step at a time to tout; the outcome: at tout (interpolated there), the
        !! end of a singular pass (stop_at_pass_end), the monitor's alarm, the
        !! policy's hand-back to the explicit method (integrator=auto), the step
        !! budget spent, or a failure. Not for the extensions to override (it is not
        !! declared non_overridable: gfortran 12 then dispatches a call through
        !! class(integrator) to the wrong binding).
        procedure :: advance => implicit_advance
        !> Yes: with one_step, advance returns after one accepted step.
        procedure :: steps_singly => implicit_steps_singly
        !> One step towards tout (landing on it with stop_at_output), state() and
        !! slope() at its end t_now; stat /= regdae_success: it failed at t_now (msg).
        procedure(stepper_step), deferred :: step_towards
        !> state() and slope() at the end of the last step, time().
        procedure(stepper_step_end), deferred :: to_step_end
        !> The method's name in messages ('IDA', 'Radau'), padded with blanks to name_len
        !! (a fixed length: doc/methods.md, "No global state").
        procedure(stepper_name), deferred :: name
    end type implicit_stepper

    abstract interface
        subroutine stepper_step(self, tout, t_now, stat, msg)
            import :: implicit_stepper, wp
            class(implicit_stepper), intent(inout), target :: self
            real(wp), intent(in) :: tout
            real(wp), intent(out) :: t_now
            integer, intent(out) :: stat
            character(len=:), allocatable, intent(inout) :: msg
        end subroutine stepper_step

        subroutine stepper_step_end(self)
            import :: implicit_stepper
            class(implicit_stepper), intent(inout), target :: self
        end subroutine stepper_step_end

        function stepper_name(self) result(who)
            import :: implicit_stepper, name_len
            class(implicit_stepper), intent(in) :: self
            character(len=name_len) :: who
        end function stepper_name
    end interface

contains

    subroutine implicit_advance(self, tout, t_stop, outcome, stat, msg, one_step)
        class(implicit_stepper), intent(inout), target :: self
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: t_stop
        integer, intent(out) :: outcome, stat
        character(len=:), allocatable, intent(out) :: msg
        logical, intent(in), optional :: one_step   !! return after one accepted step (at its end if before tout)
        real(wp) :: t_now
        integer :: taken, istat
        type(solver_core), pointer :: core
        core => self%core
        stat = regdae_success
        msg = ''
        t_stop = tout
        outcome = outcome_reached
        t_now = self%time()
        if (t_now > core%sampled_t .and. t_now <= tout) then   ! a step end passed over at the last output
            call self%to_step_end()
            if (sampled_alarm(core, t_now, t_stop, outcome)) return
        end if
        taken = 0
        do while (t_now < tout)
            ! (state() is at t_now: max_steps >= 1, so a step was taken)
            if (budget_spent(self, taken, t_now, tout, t_stop, outcome, stat, msg)) return
            call self%step_towards(tout, t_now, stat, msg)
            if (stat /= regdae_success) then
                t_stop = t_now
                outcome = outcome_failed
                return
            end if
            taken = taken + 1
            if (after_step(core, taken, t_now, tout, t_stop, outcome)) return
            if (t_now < tout .and. present(one_step)) then
                if (one_step) then   ! state() is at the step's end, sampled there
                    t_stop = t_now
                    return
                end if
            end if
        end do
        if (t_now > tout) then
            call self%interpolate(tout, istat)
            if (istat /= regdae_success) then
                outcome = outcome_broken
                stat = regdae_err_integration
                msg = trim(self%name())//' could not interpolate at t = '//format_real(tout)
                return
            end if
            if (sampled_alarm(core, tout, t_stop, outcome)) return
        end if
    end subroutine implicit_advance

    logical function implicit_steps_singly(self)
        class(implicit_stepper), intent(in) :: self
        implicit_steps_singly = .true.
    end function implicit_steps_singly

    ! max_steps steps taken in this advance (`taken`) without reaching tout: stop at
    ! t_now with outcome_exhausted, regdae_err_integration and a message naming the method.
    logical function budget_spent(self, taken, t_now, tout, t_stop, outcome, stat, msg) result(stop)
        class(implicit_stepper), intent(in) :: self
        integer, intent(in) :: taken           !! steps taken in this advance
        real(wp), intent(in) :: t_now, tout
        real(wp), intent(inout) :: t_stop
        integer, intent(inout) :: outcome, stat
        character(len=:), allocatable, intent(inout) :: msg
        stop = (taken >= self%core%opts%max_steps)
        if (.not. stop) return
        t_stop = t_now
        outcome = outcome_exhausted
        stat = regdae_err_integration
        msg = trim(self%name())//' took max_steps = '//format_int(self%core%opts%max_steps)//' steps without reaching tout = '// &
              format_real(tout)//' (t = '//format_real(t_now)//')'
    end function budget_spent

    ! The monitor samples the implicit integrator's state at t (the stiff slot's
    ! state() and slope() there); its alarm stops at t (outcome_alarm).
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

    ! After the `taken`-th accepted step of this advance, ending at t_now: the sample
    ! and its alarm and the end of a singular pass (t_now <= tout), the hand-back
    ! vote of integrator=auto every 20 steps (t_now < tout).
    logical function after_step(core, taken, t_now, tout, t_stop, outcome) result(stop)
        type(solver_core), intent(inout), target :: core
        integer, intent(in) :: taken
        real(wp), intent(in) :: t_now, tout
        real(wp), intent(inout) :: t_stop
        integer, intent(inout) :: outcome
        stop = .true.
        if (t_now <= tout) then
            if (sampled_alarm(core, t_now, t_stop, outcome)) return
            if ((core%monitor%project_due .or. (core%stop_at_pass_end .and. core%monitor%pass_ended)) .and. &
                t_now < tout) then
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
