!> The solver front's events and statistics (`regdae_solver_front`): the event
!! functions set on the engine (`regdae_events`), their roots at a stop, the
!! return after every step (DASSL's INFO(3) = 1), and the statistics with the
!! roots found.
submodule (regdae_solver_front) regdae_solver_events
    implicit none

contains

    module procedure solver_set_events
        character(len=:), allocatable :: msg
        integer :: code
        call self%ev%set(fn, n, code, msg, direction, stop)
        call self%record(code, msg, stat)
    end procedure solver_set_events

    module procedure solver_return_each_step
        self%each_step = on
    end procedure solver_return_each_step

    module procedure solver_roots
        if (self%ev%n > 0) then
            found = self%ev%found
        else
            allocate (found(0))
        end if
    end procedure solver_roots

    module procedure solver_statistics
        class(integrator), pointer :: active

        st%t = self%t
        if (.not. associated(self%core)) return
        associate (core => self%core)
            st%switches = core%switches
            ! the implicit integrator's counts (none if it never ran) plus the explicit one's;
            ! the last step of the one in charge
            active => active_integrator(core)
            if (allocated(core%stiff)) call core%stiff%statistics(st, associated(active, core%stiff))
            if (allocated(core%nonstiff)) call core%nonstiff%statistics(st, associated(active, core%nonstiff))
            st%singular_passes = core%monitor%n_singular
            st%sigma_min = core%monitor%sigma_min
            st%velocity_jump = core%monitor%jump_max
            st%max_drift = core%monitor%drift_max
            st%invariant_change = core%monitor%invariant_change
            st%work_defect = core%monitor%work_defect
            st%unresolved_passes = core%monitor%unresolved
            st%resolution_ratio = core%monitor%resolution_ratio
            st%weight_changes = core%monitor%weights%changes
            st%eps_changes = core%monitor%scales%eps_changes
            st%roots_found = self%ev%total
        end associate
    end procedure solver_statistics

end submodule regdae_solver_events
