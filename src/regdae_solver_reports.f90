!> What the solver front reports (`regdae_solver_front`) beside its advance: the
!! status and message of an advance that the monitor's alarm stops, the message of the
!! last call, the events log, the options in force, the resolved formulation, linear
!! solver and least-squares method, the last sigma_min(GB) and the singular intervals.
submodule (regdae_solver_front) regdae_solver_reports
    use regdae_format, only: text_length
    implicit none

contains

    module procedure alarm_status
        logical :: index2   ! integrated at index 2 (the constraint on velocities only)
        index2 = core%second_order .and. core%opts%index == 2
        if (core%monitor%alarm_kind == alarm_jump) then
            code = regdae_err_branch
            msg = core%monitor%alarm_message// &
                  ': the solution probably changed branch there; x(tout) is returned but not trustworthy '// &
                  '(a smaller rtol or eps'//trim(merge(', or index=3,', '             ', index2))// &
                  ' may help; jump_tol=0 turns this check off, at the risk of a run that leaves the '// &
                  'physical branch with status ok)'
        else if (core%monitor%alarm_kind == alarm_work) then
            code = regdae_err_work
            msg = core%monitor%alarm_message// &
                  ': x is returned but not trustworthy (the constraint forces did work: a drift, a '// &
                  'branch change or too stiff a regularization; a smaller rtol or smaller Baumgarte '// &
                  'weights may help; work_tol=0 turns this check off, at the risk of a wrong answer '// &
                  'with status ok)'
        else if (core%monitor%alarm_kind == alarm_invariant) then
            code = regdae_err_invariant
            msg = core%monitor%alarm_message// &
                  ': x(tout) is returned but not trustworthy (a smaller rtol, or smaller Baumgarte weights, '// &
                  'may help; invariant_tol=0 turns this check off)'
        else if (.not. core%opts%curvature .and. .not. index2) then
            code = regdae_err_drift
            msg = core%monitor%alarm_message// &
                  ': x(tout) is returned but not trustworthy (with curvature=no the constraint error '// &
                  'has a floor of about |g_xx(v, v)|/gamma0 whatever the tolerance: curvature=yes '// &
                  'removes it; drift_tol=0 turns this check off, at the risk of positions that violate '// &
                  'the constraint with status ok)'
        else
            code = regdae_err_drift
            msg = core%monitor%alarm_message// &
                  ': x(tout) is returned but not trustworthy (a smaller rtol'// &
                  trim(merge(', index=3,', '          ', index2))//' or a larger gamma may help; '// &
                  'drift_tol=0 turns this check off, at the risk of positions that violate the '// &
                  'constraint with status ok)'
        end if
    end procedure alarm_status

    module procedure solver_message
        if (allocated(self%last_message)) then
            msg = self%last_message
        else
            msg = status_message(self%last_stat)
        end if
    end procedure solver_message

    module procedure message_length
        message_length = reported_length(self%last_message, self%last_stat)
    end procedure message_length

    module procedure solver_events
        if (len(text) > 0) text = self%core%events
    end procedure solver_events

    module procedure events_length
        events_length = 0
        if (associated(self%core)) events_length = text_length(self%core%events)
    end procedure events_length

    module procedure solver_options_in_force
        if (.not. associated(self%core)) return
        opts = self%core%opts
        ! integrator=auto: the integrator in charge now (it switches along the run)
        if (opts%integrator == integrator_auto) opts%integrator = self%core%active
    end procedure solver_options_in_force

    module procedure solver_formulation
        solver_formulation = 0
        if (associated(self%core)) solver_formulation = self%core%formulation
    end procedure solver_formulation

    module procedure solver_linear_solver
        solver_linear_solver = 0
        if (associated(self%core)) solver_linear_solver = self%core%linear_solver
    end procedure solver_linear_solver

    module procedure solver_lsq_method
        solver_lsq_method = 0
        if (associated(self%core)) then
            if (.not. self%core%augmented) solver_lsq_method = self%core%model%lsq
        end if
    end procedure solver_lsq_method

    module procedure solver_sigma_min
        solver_sigma_min = ieee_value(1.0_wp, ieee_quiet_nan)
        if (associated(self%core)) solver_sigma_min = self%core%monitor%sigma_last
    end procedure solver_sigma_min

    module procedure solver_singular_intervals
        if (associated(self%core)) then
            intervals = self%core%monitor%intervals()
        else
            allocate (intervals(2, 0))
        end if
    end procedure solver_singular_intervals

end submodule regdae_solver_reports
