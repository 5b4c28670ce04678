!> The solution monitor's start and samples (`regdae_monitor`) on the state of
!! one problem (`regdae_solver_core`): the monitor set up from core%opts at the
!! start of the dense formulations and of the augmented one, the sample at the
!! end of an accepted step of the implicit integrator (the core's stiff slot,
!! `regdae_integrator`), and along the run the augmented formulation's automatic
!! weights (from `regdae_augmented_rules`). One concept, the monitor
!! fed from the integrators' state, used by the front and by the switching policy
!! (`regdae_integrator_switching`), which starts the monitor when IDA starts from t0.
module regdae_solver_sampling
    use, intrinsic :: iso_c_binding, only: c_double
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success
    use regdae_options, only: resolved_work_tol, method_direct, method_baumgarte
    use regdae_augmented_system, only: augmented_system
    use regdae_auto_rules, only: baumgarte_weights
    use regdae_work_energy, only: kinetic_energy_and_power
    use regdae_augmented_rules, only: mass_diagonal, augmented_motion_scales
    use regdae_solver_core, only: solver_core
    use regdae_monitor, only: forgetting_rate
    use regdae_mechanical_problem, only: mechanical_problem
    implicit none
    private

    public :: start_monitor, start_monitor_augmented, sample_step

contains

    !> The monitor from (t0, z0) with its slope zp0 (dense formulations): the checks
    !! and automatic scales of core%opts, the first sample.
    subroutine start_monitor(core, t0, z0, zp0)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t0, z0(:), zp0(:)
        ! the velocity check looks at the positions' velocities, z(nx+1:2nx), of order >= 2
        call core%monitor%reset(core%opts%singular_threshold, core%model%eps, merge(core%nx, 0, core%second_order), &
                                core%opts%jump_tol, core%opts%drift_tol, core%opts%invariant_tol, &
                                merge(resolved_work_tol(core%opts), 0.0_wp, core%model%is_mechanical()))
        call core%monitor%automatic(core%eps_factor, core%model%eps, core%drift_factor, core%opts%rtol, &
                                    maxval(core%atol_z(1:core%nx)), core%model%method == method_direct, &
                                    core%sigma_pred0)
        if (core%follow_weights) call core%monitor%follow_weights(core%nx, core%second_order .and. &
                                                                  size(z0) >= 2*core%nx, core%rate0, core%ell0, t0)
        core%monitor%work_floor = core%work_floor
        core%monitor%work_rate = core%rate0
        call core%monitor%set_resolution(core%opts%resolution_tol)
        call core%monitor%sample(t0, core%model, z0, zp0)
        core%sampled_t = t0
    end subroutine start_monitor

    !> The monitor of the augmented formulation from t with the eps in force: the
    !! checks and automatic scales of core%opts, the first sample (IDA's state at t).
    subroutine start_monitor_augmented(core, t, eps)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t, eps
        call core%monitor%reset(core%opts%singular_threshold, eps, core%nx, core%opts%jump_tol, &
                                core%opts%drift_tol, core%opts%invariant_tol, resolved_work_tol(core%opts))
        call core%monitor%automatic(core%eps_factor, eps, core%drift_factor, core%opts%rtol, &
                                    maxval(core%atol_z(1:core%nx)), core%opts%method == method_direct, &
                                    core%sigma_pred0)
        if (core%follow_weights) call core%monitor%follow_weights(0, .true., core%rate0, core%ell0, t)
        core%monitor%work_floor = core%work_floor
        core%monitor%work_rate = core%rate0
        call sample_augmented(core, t)
        core%sampled_t = t
    end subroutine start_monitor_augmented

    !> The monitor's sample at the end of an accepted step of the implicit integrator
    !! (its state and slope there): the full sample where a singular interval may be
    !! near (the monitor's `full_sample_due`: the regularized model evaluated there,
    !! sigma_min(GB) and every check), elsewhere only the work-energy balance's
    !! energies at the step's end (its quadrature of the power needs every step; an
    !! output time inside the step is not sampled there).
    subroutine sample_step(core, t)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t
        real(c_double), pointer :: u(:), up(:)
        integer :: stat
        logical :: recoverable
        if (core%augmented) then
            call sample_augmented(core, t)
            return
        end if
        u => core%stiff%state()
        up => core%stiff%slope()
        if (.not. core%monitor%full_sample_due(t, t < core%stiff%time())) then
            if (t < core%stiff%time()) return   ! an output time inside the step: its end serves the balance
            if (work_sampled(core, t, u(1:core%n), up(1:core%n))) return
        end if
        call core%model%evaluate(t, u(1:core%n), stat, recoverable)
        if (stat /= regdae_success) return
        call core%monitor%sample(t, core%model, u(1:core%n), up(1:core%n))
        if (core%layer%step(core%model%order, core%model%w, core%model%method, core%model%eps, &
                            core%monitor%sigma_last, core%sampled_t, t)) then
            core%monitor%unresolved_new = .true.   ! the front warns at tout (regdae_taylor_layer)
            core%monitor%unresolved_message = core%layer%message
        end if
    end subroutine sample_step

    ! The work-energy balance's sample at (t, z) without the regularized model: T and P
    ! of a mechanical problem of order 2 whose constraints do not move (g_t = 0 there,
    ! so that the multiplier does no work); false where that does not hold (the full
    ! sample then serves).
    logical function work_sampled(core, t, z, dz) result(done)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t, z(:), dz(:)   !! the state and its slope
        real(wp) :: kinetic, power, sums(2), gt(core%m), y(core%m)
        integer :: stat, nx
        done = .not. (core%monitor%work_tol > 0.0_wp)   ! no balance: nothing to sample
        if (done .or. .not. allocated(core%model%second)) return
        nx = core%model%n
        select type (p => core%model%second)
        class is (mechanical_problem)
            stat = 0
            gt = 0.0_wp
            if (p%m > 0) call p%constraint_dt(t, z(1:nx), gt, stat)
            if (stat /= 0 .or. any(gt /= 0.0_wp)) return
            y = 0.0_wp
            call kinetic_energy_and_power(p, t, z(1:nx), z(nx + 1:2*nx), y, kinetic, power, stat, sums=sums)
            call core%monitor%sample_work(t, kinetic, power, stat, core%monitor%energy_tolerance(sums, z(1:nx), &
                                          z(nx + 1:min(size(z), 2*nx))), p, z(1:2*nx), dz(1:2*nx))
            done = .true.
        end select
    end function work_sampled

    ! The monitor's sample of the augmented formulation at the implicit integrator's state:
    ! full where a singular interval may be near (as sample_step's), else the work-energy
    ! balance's energies at a step's end (the multiplier is one of the unknowns).
    subroutine sample_augmented(core, t)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t
        type(augmented_system), pointer :: sys
        logical :: full
        sys => core%stiff%augmented()
        full = .true.
        if (associated(sys)) full = core%monitor%full_sample_due(t, t < core%stiff%time())
        ! an output time inside the step: its end serves the balance
        if (.not. full .and. t < core%stiff%time()) return
        call sample_augmented_state(core, t, sys, full)
    end subroutine sample_augmented

    ! sample_augmented's sample at t, full or the work-energy balance's alone; sys: IDA's
    ! augmented system (not associated: the full sample's values without it).
    subroutine sample_augmented_state(core, t, sys, full)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t
        type(augmented_system), pointer, intent(in) :: sys
        logical, intent(in) :: full
        real(c_double), pointer :: u(:), up(:)
        real(wp), target :: z(2*core%nx), dz(2*core%nx)   ! (q, v) and its slope: one block each
        real(wp) :: a(core%nx), y(core%m), drift, invariant, sigma, kinetic, power, gb, g, sums(2)
        real(wp), pointer :: q(:), v(:)
        integer :: dstat, istat, wstat
        q => z(1:core%nx)
        v => z(core%nx + 1:2*core%nx)
        u => core%stiff%state()
        up => core%stiff%slope()
        if (.not. full) then
            call sys%unpack(u, up, q=q, v=v)
        else
            drift = 0.0_wp
            invariant = 0.0_wp
            sigma = huge(1.0_wp)
            dstat = 0
            istat = 0
            if (associated(sys)) then
                call sys%unpack(u, up, q=q, v=v, a=a)
                drift = sys%drift(t, u, dstat)
                if (dstat /= 0) drift = huge(1.0_wp)
                ! (also leaves M and G at q in sys%mvals, sys%gvals)
                sigma = sys%sigma_min_gb(t, u, dstat, gb, g, far=core%monitor%near_level())
                if (dstat == 0 .and. (core%eps_factor > 0.0_wp .or. core%drift_factor > 0.0_wp)) then
                    if (core%monitor%observe_scales(t, gb, g, maxval(abs(q)), sigma)) sys%eps = core%monitor%scales%eps
                end if
                if (core%opts%invariant_tol > 0.0_wp) call sys%problem%invariant(t, q, v, invariant, istat)
            end if
            if (associated(sys)) then
                core%monitor%fold_rate = 0.0_wp
                if (core%opts%method /= method_baumgarte) core%monitor%fold_rate = forgetting_rate(sys%gamma0, sys%gamma1)
            end if
            call core%monitor%sample_values(t, drift, sigma, invariant, istat, v, a, z)
            if (core%monitor%weights_due(t)) call follow_weights_augmented(core, t, q, v, a)
        end if
        if (core%monitor%work_tol > 0.0_wp .and. associated(sys)) then   ! after sample_values: it knows
            call sys%unpack(u, up, y=y)                                    ! whether t is in a layer
            call sys%unpack(up, up, q=dz(1:core%nx), v=dz(core%nx + 1:2*core%nx))   ! (q', v'): the slope
            call kinetic_energy_and_power(sys%problem, t, q, v, y, kinetic, power, wstat, sys%st%mass, sums, &
                                          constant=sys%st%mass_constant)
            ! with the state and its slope: an interval whose quadrature is uncertain is refined
            ! on the integrator's motion (as the dense formulations' samples are)
            call core%monitor%sample_work(t, kinetic, power, wstat, core%monitor%energy_tolerance(sums, q, v), &
                                          sys%problem, z, dz, sys%st%mass, sys%st%mass_constant)
        end if
    end subroutine sample_augmented_state

    ! The automatic weights of the augmented formulation follow the motion: a new
    ! look at the rate at (t, q, v) with the accelerations a (IDA's v'); new
    ! weights into the system when it moved by the rule's hysteresis.
    subroutine follow_weights_augmented(core, t, q, v, a)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t, q(:), v(:), a(:)
        real(wp) :: f(core%nx), mdiag(core%nx), ell, rate, sigma_pred, gamma, gamma0, gamma1
        integer :: stat
        type(augmented_system), pointer :: sys
        sys => core%stiff%augmented()
        if (associated(sys)) then
            stat = 0
            call sys%problem%forces(t, q, v, f, stat)   ! M and G at q are in sys from the sample
            if (stat /= 0) return
            call mass_diagonal(sys, mdiag)
            call augmented_motion_scales(sys, t, q, v, a, f/mdiag, core%monitor%weights%ell, .false., ell, rate, &
                                         sigma_pred, stat, .false.)
            if (stat /= 0) return
            core%monitor%weights%ell = ell
            if (.not. core%monitor%new_rate(t, rate)) return
            call baumgarte_weights(core%monitor%weights%rate, gamma, gamma0, gamma1)
            if (core%opts%index == 3) then
                sys%gamma0 = gamma0
                sys%gamma1 = gamma1
            else
                sys%gamma0 = 0.0_wp
                sys%gamma1 = gamma
            end if
        end if
    end subroutine follow_weights_augmented

end module regdae_solver_sampling
