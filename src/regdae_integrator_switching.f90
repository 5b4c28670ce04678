!> The switches of integrator=auto between the explicit Dormand-Prince
!! integrator (`regdae_dopri5_integrator`, the core's nonstiff slot) and an
!! implicit one in the stiff slot, IDA (`regdae_ida_integrator`) or Radau IIA
!! (`regdae_radau_integrator`, small systems), on the state of one problem
!! (`regdae_solver_core`): the hand-over to IDA when the explicit method's
!! stiffness test fires (on the eliminated formulation, or the augmented one for
!! a mechanical problem that declares its structure; from t0 before the first
!! output), and the hand-back when the policy (`regdae_switching_policy`) finds
!! that the explicit method would do again. The front calls `hand_over` on the
!! outcomes `outcome_stiff` and `outcome_nonstiff` of the integrators' advance;
!! the monitor is restarted through `regdae_solver_sampling`.
module regdae_integrator_switching
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_mechanical_problem, only: mechanical_problem, mechanical_structure
    use regdae_options, only: solver_options, formulation_auto, formulation_augmented, integrator_ida, &
                              integrator_dopri5, integrator_radau, integrator_name, linear_solver_sparse, exclusion_off
    use regdae_augmented_system, only: augmented_system
    use regdae_format, only: format_real
    use regdae_integrator, only: outcome_stiff, outcome_nonstiff
    use regdae_solver_core, only: solver_core, log_event
    use regdae_solver_sampling, only: start_monitor, start_monitor_augmented
    use regdae_ida_integrator, only: ida_integrator, ida_in_slot
    use regdae_dopri5_integrator, only: dopri5_integrator, dopri5_in_slot
    use regdae_radau_integrator, only: radau_adapter, radau_in_slot
    use regdae_switching_policy, only: radau_preferred, stiff_at_start, stiff_start_factor, stiff_start_factor_radau
    implicit none
    private

    public :: hand_over, switch_to_implicit, switch_to_dopri5, start_implicit_if_stiff

contains

    !> integrator=auto: the switch an integrator's outcome asks for at t_stop:
    !! outcome_stiff to the implicit integrator (switch_to_implicit), outcome_nonstiff back to the explicit
    !! method (switch_to_dopri5).
    subroutine hand_over(core, outcome, t_stop, stat, msg)
        type(solver_core), pointer, intent(in) :: core
        integer, intent(in) :: outcome
        real(wp), intent(in) :: t_stop
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        stat = regdae_success
        msg = ''
        if (outcome == outcome_stiff) then
            call switch_to_implicit(core, stat, msg)
        else if (outcome == outcome_nonstiff) then
            call switch_to_dopri5(core, t_stop)
        end if
    end subroutine hand_over

    !> integrator=auto: the explicit method found the system stiff at rk%t: the
    !! implicit integrator takes over there (created at the first switch, restarted
    !! at the others): Radau IIA on the eliminated formulation for a small system
    !! and IDA for a large one (the policy's radau_preferred), IDA on the augmented
    !! formulation with KLU for a large mechanical problem that declares its structure.
    subroutine switch_to_implicit(core, stat, msg)
        type(solver_core), pointer, intent(in) :: core
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp) :: zp(core%n), y(core%m), t, z(core%n)
        real(wp), pointer :: u(:)
        type(ida_integrator), pointer :: ida
        type(radau_adapter), pointer :: radau
        logical :: recoverable, from_start, restart, structured
        t = core%nonstiff%time()
        u => core%nonstiff%state()
        z = u
        msg = ''
        ! Stiff before the first output: IDA from t0 (nothing has been returned yet), so
        ! that the run is the one integrator=ida gives, not one that carries the
        ! explicit method's steps at its stability limit.
        from_start = .not. core%started .and. core%switches == 0
        if (from_start) then
            t = core%t0
            z = core%z0
            core%model%eps = core%opts%eps
            if (core%model%order == 1) core%model%w = [core%opts%gamma]
            if (core%model%order == 2) core%model%w = [core%opts%gamma0, core%opts%gamma1]
        end if
        structured = augmented_fits(core)
        if (structured .and. .not. radau_preferred(core, structured)) then
            call switch_to_augmented(core, t, z, from_start, stat, msg)
            if (stat == regdae_success) call now_stiff(core, integrator_ida, ', augmented formulation with KLU', from_start)
            return
        end if
        call core%model%slope_eliminated(t, z, zp, y, stat, recoverable)
        if (stat /= regdae_success) then
            msg = 'switching to IDA at t = '//format_real(t)//': '//core%model%message
            return
        end if
        if (radau_preferred(core, structured)) then
            radau => radau_in_slot(core)
            call radau%start(t, z, stat, msg, h0=merge(0.0_wp, core%nonstiff%last_step(), from_start), zp=zp, y=y)
            if (stat /= regdae_success) msg = 'switching to Radau at t = '//format_real(t)//': '//msg
            if (stat /= regdae_success) return
            if (from_start) call start_monitor(core, t, z, zp)
            call now_stiff(core, integrator_radau, '', from_start)
            return
        end if
        ida => ida_in_slot(core)
        restart = ida%ready()
        call ida%start(t, z, stat, msg, zp=zp, y=y)
        if (stat /= regdae_success .and. restart) msg = 'switching to IDA at t = '//format_real(t)//': FIDAReInit failed'
        if (stat /= regdae_success) return
        if (from_start) call start_monitor(core, t, z, zp)
        call now_stiff(core, integrator_ida, '', from_start)
    end subroutine switch_to_implicit

    !> integrator=auto at t0, before dopri5 is started, on a mechanical problem that
    !! declares its structure: already stiff there (the policy's stiff_at_start), the
    !! implicit integrator starts from t0 (core%active set to it), rather than after
    !! 15 explicit steps at the stability limit: Radau IIA on the eliminated
    !! formulation for a small system (radau_preferred), else IDA on the augmented
    !! formulation with KLU. dopri5 is then created at a switch back (switch_to_dopri5).
    subroutine start_implicit_if_stiff(core, stat, msg)
        type(solver_core), pointer, intent(in) :: core
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        type(radau_adapter), pointer :: radau
        character(len=:), allocatable :: which
        real(wp) :: h_accurate, rho, factor
        real(wp), allocatable :: jac(:, :)
        logical :: on_radau
        stat = regdae_success
        msg = ''
        if (.not. (core%switching .and. augmented_fits(core))) return
        on_radau = radau_preferred(core, .true.)
        factor = merge(stiff_start_factor_radau, stiff_start_factor, on_radau)
        if (.not. stiff_at_start(core, core%t0, core%z0, factor, h_accurate, rho, jac)) return
        if (on_radau) then
            ! as integrator=radau starts (regdae_solver_init; the monitor started at t0 there),
            ! with the start test's Jacobian at (t0, z0) as its first (Radau's own difference
            ! quotients of the same F: not computed again)
            radau => radau_in_slot(core)
            call radau%start(core%t0, core%z0, stat, msg, h0=core%opts%h_init)
            if (stat == regdae_success) call radau%take_jacobian(jac)
            if (stat /= regdae_success) msg = 'starting Radau at t0: '//msg
            core%active = integrator_radau
            which = 'radau from the start '
        else
            call switch_to_augmented(core, core%t0, core%z0, .true., stat, msg)
            which = 'ida from the start, augmented formulation with KLU '
        end if
        if (stat /= regdae_success) return
        core%switches = core%switches + 1
        core%explicit_votes = 0
        call log_event(core, 't = '//format_real(core%t0)//': '//which// &
                       '(stiff at t0: the accurate first step '//format_real(h_accurate)//' exceeds '// &
                       format_real(factor)//' times the explicit method''s stable step 3.3/rho = '// &
                       format_real(3.3_wp/rho)//'; no lightly damped mode it would not resolve)')
    end subroutine start_implicit_if_stiff

    ! After a switch to the implicit integrator `which` (ida or radau): the counters
    ! and the event (what: the formulation, if not the eliminated one).
    subroutine now_stiff(core, which, what, from_start)
        type(solver_core), intent(inout) :: core
        integer, intent(in) :: which
        character(len=*), intent(in) :: what
        logical, intent(in) :: from_start
        character(len=:), allocatable :: tail
        core%active = which
        core%switches = core%switches + 1
        core%explicit_votes = 0
        tail = ''
        if (from_start .and. which == integrator_ida) tail = '; IDA starts from t0'
        if (from_start .and. which == integrator_radau) tail = '; Radau starts from t0'
        call log_event(core, 't = '//format_real(core%nonstiff%time())//': dopri5 -> '//integrator_name(which)//what// &
                       ' (the stiffness test fired: h |lambda| at the explicit method''s stability limit for 15 steps)'//tail)
    end subroutine now_stiff

    ! integrator=auto, formulation=auto: a mechanical problem at index 3 that declares
    ! its structure (M positive definite: no mass_damping): IDA takes the augmented
    ! formulation for it where Radau IIA does not take the eliminated one
    ! (radau_preferred; the stiff 4-link chain on IDA: augmented 1.2-2.5x faster per
    ! run than eliminated, doc/performance.md).
    logical function augmented_fits(core) result(fits)
        type(solver_core), intent(in) :: core
        type(mechanical_structure) :: st
        fits = .false.
        if (core%opts%formulation /= formulation_auto .or. core%opts%mass_damping > 0.0_wp) return
        if (.not. allocated(core%model%second)) return
        select type (problem => core%model%second)
        class is (mechanical_problem)
            st = problem%structure()
            fits = st%declared
        end select
    end function augmented_fits

    ! IDA on the augmented formulation from (t, z = (q, v)) (a switch, or the start):
    ! consistent u, y, s by IDACalcIC there, the monitor kept (from_start: restarted
    ! at t). There is no switch back to dopri5 from it (explicit_would_do).
    subroutine switch_to_augmented(core, t, z, from_start, stat, msg)
        type(solver_core), pointer, intent(in) :: core
        real(wp), intent(in) :: t, z(:)
        logical, intent(in) :: from_start
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        type(augmented_system) :: sys
        type(solver_options) :: opts
        type(ida_integrator), pointer :: ida
        real(wp), allocatable :: u0(:), up0(:), id(:)
        integer :: nx
        nx = core%nx
        opts = core%opts
        opts%eps = core%model%eps   ! the automatic eps in force (raised along the run)
        ! IDA's first step after a switch: the explicit method's last one (at its stability limit)
        ! rather than IDA's own guess from the distance to the next output
        if (.not. from_start .and. opts%h_init == 0.0_wp) opts%h_init = core%nonstiff%last_step()
        select type (problem => core%model%second)
        class is (mechanical_problem)
            call sys%setup(problem, opts, stat)
        end select
        if (stat /= regdae_success) then
            msg = 'switching to IDA at t = '//format_real(t)//' (augmented formulation): '//sys%message
            return
        end if
        ida => ida_in_slot(core)
        if (ida%ready()) call ida%free()
        allocate (u0(sys%neq), up0(sys%neq), id(sys%neq))
        call sys%initial_guess(z(1:nx), z(nx + 1:2*nx), u0, up0, id)
        core%neq = sys%neq
        core%linear_solver = linear_solver_sparse
        core%excluded = sys%excluded_unknowns(opts%excluded)
        if (opts%exclusion == exclusion_off) core%excluded = .false.
        call ida%ida%create(sys, opts, core%linear_solver, core%excluded, t, u0, up0, stat, msg, &
                            sys%tolerance_vector(core%atol_z(1:nx), core%atol_z(nx + 1:), opts%atol))
        if (stat == regdae_success) call ida%ida%calc_ic(id, t + 1.0e-3_wp*max(1.0_wp, abs(t)), stat, msg)
        if (stat /= regdae_success) then
            msg = 'switching to IDA at t = '//format_real(t)//' (augmented formulation): '//msg
            return
        end if
        core%augmented = .true.
        core%formulation = formulation_augmented
        if (from_start) call start_monitor_augmented(core, t, opts%eps)
        core%active = integrator_ida
    end subroutine switch_to_augmented

    !> integrator=auto: back to the explicit method at t, the implicit integrator's state there.
    subroutine switch_to_dopri5(core, t)
        type(solver_core), pointer, intent(in) :: core
        real(wp), intent(in) :: t
        real(wp), pointer :: u(:)
        character(len=:), allocatable :: msg
        type(dopri5_integrator), pointer :: dopri5
        integer :: stat
        logical :: from_radau
        u => core%stiff%state()
        dopri5 => dopri5_in_slot(core)   ! (created here after a start on the implicit integrator)
        call dopri5%start(t, u(1:core%n), stat, msg, h0=core%stiff%last_step())
        from_radau = (core%active == integrator_radau)
        core%active = integrator_dopri5
        core%switches = core%switches + 1
        core%back_switches = core%back_switches + 1
        core%explicit_votes = 0
        if (from_radau) then
            call log_event(core, 't = '//format_real(t)//': radau -> dopri5 (the explicit method''s stable step '// &
                           'exceeds twice Radau''s)')
        else
            call log_event(core, 't = '//format_real(t)//': ida -> dopri5 (the explicit method''s stable step '// &
                           'exceeds twice IDA''s)')
        end if
    end subroutine switch_to_dopri5

end module regdae_integrator_switching
