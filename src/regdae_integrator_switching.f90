!> The switching policy of integrator=auto between the explicit Dormand-Prince
!! integrator (`regdae_explicit_rk`) and IDA (`regdae_ida_backend`) on the state
!! of one problem (`regdae_solver_core`): the switch to IDA when the explicit
!! method's stiffness test fires (on the eliminated formulation, or the augmented
!! one for a mechanical problem that declares its structure; from t0 before the
!! first output), the test on IDA's side whether the explicit method would do
!! again (the spectral radius by power iteration), and the switch back. The front
!! asks and switches at its steps; the monitor is restarted through
!! `regdae_solver_sampling`.
module regdae_integrator_switching
    use, intrinsic :: iso_c_binding, only: c_double
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_mechanical_problem, only: mechanical_problem, mechanical_structure
    use regdae_options, only: solver_options, formulation_auto, formulation_augmented, integrator_ida, &
                              integrator_dopri5, linear_solver_dense, linear_solver_sparse, exclusion_off
    use regdae_regularized_system, only: new_regularized_system
    use regdae_augmented_system, only: augmented_system
    use regdae_format, only: format_real
    use regdae_solver_core, only: solver_core, log_event
    use regdae_solver_sampling, only: start_monitor, start_monitor_augmented
    implicit none
    private

    public :: switch_to_ida, explicit_would_do, switch_to_dopri5

contains

    !> integrator=auto: the explicit method found the system stiff at rk%t: IDA
    !! takes over there (created at the first switch, restarted at the others).
    subroutine switch_to_ida(core, stat, msg)
        type(solver_core), intent(inout) :: core
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp) :: zp(core%n), y(core%m), t, z(core%n)
        logical :: recoverable, from_start
        t = core%rk%t
        z = core%rk%z
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
        if (augmented_fits(core)) then
            call switch_to_augmented(core, t, z, from_start, stat, msg)
            if (stat == regdae_success) call now_ida(core, ', augmented formulation with KLU', from_start)
            return
        end if
        call core%model%slope_eliminated(t, z, zp, y, stat, recoverable)
        if (stat /= regdae_success) then
            msg = 'switching to IDA at t = '//format_real(t)//': '//core%model%message
            return
        end if
        if (c_associated_ida(core)) then
            call core%ida%restart(t, z, zp, stat)
            if (stat /= regdae_success) msg = 'switching to IDA at t = '//format_real(t)//': FIDAReInit failed'
        else
            call core%ida%create(new_regularized_system(core%model, core%n, core%n), core%opts, linear_solver_dense, &
                                 core%excluded(1:core%n), t, z, zp, stat, msg, core%atol_z)
        end if
        if (stat /= regdae_success) return
        if (from_start) call start_monitor(core, t, z, zp)
        call now_ida(core, '', from_start)
    end subroutine switch_to_ida

    ! After a switch to IDA: the counters and the event (what: the formulation, if not
    ! the eliminated one).
    subroutine now_ida(core, what, from_start)
        type(solver_core), intent(inout) :: core
        character(len=*), intent(in) :: what
        logical, intent(in) :: from_start
        core%active = integrator_ida
        core%switches = core%switches + 1
        core%explicit_votes = 0
        call log_event(core, 't = '//format_real(core%rk%t)//': dopri5 -> ida'//what//' (the stiffness test fired: '// &
                       'h |lambda| at the explicit method''s stability limit for 15 steps)'// &
                       trim(merge('; IDA starts from t0', '                    ', from_start)))
    end subroutine now_ida

    ! integrator=auto, formulation=auto: IDA takes the augmented formulation for a
    ! mechanical problem at index 3 that declares its structure (M positive definite:
    ! no mass_damping), whatever its size (the stiff 4-link chain: 1.2-2.5x faster per
    ! run than the eliminated formulation on IDA, doc/performance.md).
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
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t, z(:)
        logical, intent(in) :: from_start
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        type(augmented_system) :: sys
        type(solver_options) :: opts
        real(wp), allocatable :: u0(:), up0(:), id(:)
        integer :: nx
        nx = core%nx
        opts = core%opts
        opts%eps = core%model%eps   ! the automatic eps in force (raised along the run)
        select type (problem => core%model%second)
        class is (mechanical_problem)
            call sys%setup(problem, opts, stat)
        end select
        if (stat /= regdae_success) then
            msg = 'switching to IDA at t = '//format_real(t)//' (augmented formulation): '//sys%message
            return
        end if
        if (allocated(core%ida%system)) call core%ida%free()
        allocate (u0(sys%neq), up0(sys%neq), id(sys%neq))
        call sys%initial_guess(z(1:nx), z(nx + 1:2*nx), u0, up0, id)
        core%neq = sys%neq
        core%linear_solver = linear_solver_sparse
        core%excluded = sys%excluded_unknowns(opts%excluded)
        if (opts%exclusion == exclusion_off) core%excluded = .false.
        call core%ida%create(sys, opts, core%linear_solver, core%excluded, t, u0, up0, stat, msg, &
                             sys%tolerance_vector(core%atol_z(1:nx), core%atol_z(nx + 1:), opts%atol))
        if (stat == regdae_success) call core%ida%calc_ic(id, t + 1.0e-3_wp*max(1.0_wp, abs(t)), stat, msg)
        if (stat /= regdae_success) then
            msg = 'switching to IDA at t = '//format_real(t)//' (augmented formulation): '//msg
            return
        end if
        core%augmented = .true.
        core%formulation = formulation_augmented
        if (from_start) call start_monitor_augmented(core, t, opts%eps)
        core%active = integrator_ida
    end subroutine switch_to_augmented

    logical function c_associated_ida(core)
        type(solver_core), intent(in) :: core
        c_associated_ida = allocated(core%ida%system)
    end function c_associated_ida

    ! The spectral radius of dF/dz at (t, z), F the eliminated formulation's slope:
    ! five power iterations with difference quotients of F, from the last estimate's
    ! vector, rho = sqrt(|J w_4| |J w_5|) (0: F failed). The model is left evaluated
    ! at (t, z).
    real(wp) function spectral_radius(core, t, z) result(rho)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t, z(:)
        real(wp) :: f0(core%n), f1(core%n), y(core%m), d, wn, norm_now, norm_last
        integer :: it, stat
        logical :: recoverable
        rho = 0.0_wp
        norm_now = 0.0_wp
        call core%model%slope_eliminated(t, z, f0, y, stat, recoverable)
        if (stat /= regdae_success) return
        if (.not. allocated(core%rho_w)) then
            allocate (core%rho_w(core%n))
            core%rho_w = 1.0_wp
        end if
        d = sqrt(epsilon(1.0_wp))*max(1.0_wp, maxval(abs(z)))
        do it = 1, 5
            wn = norm2(core%rho_w)
            if (.not. (wn > 0.0_wp)) core%rho_w = 1.0_wp
            core%rho_w = core%rho_w/norm2(core%rho_w)
            call core%model%slope_eliminated(t, z + d*core%rho_w, f1, y, stat, recoverable)
            if (stat /= regdae_success) then
                rho = 0.0_wp
                exit
            end if
            core%rho_w = (f1 - f0)/d
            norm_last = norm_now
            norm_now = norm2(core%rho_w)
            if (.not. (norm_now > 0.0_wp)) exit
            ! |J^2 w| / |w| over two iterations: a dominant complex pair (the oscillation
            ! of a second-order system) makes the single ratios alternate
            if (it >= 2) rho = sqrt(norm_now*norm_last)
        end do
        call core%model%evaluate(t, z, stat, recoverable)   ! the model back at the state
    end function spectral_radius

    !> integrator=auto, IDA active: would the explicit method do here? Its stable
    !! step 3.3/rho (rho: the spectral radius of dF/dz, by five power iterations
    !! with F) against IDA's last step: larger than twice IDA's at two checks in a
    !! row (20 steps apart) means that IDA's steps are set by accuracy, not stiffness.
    !! No vote inside a singular interval.
    logical function explicit_would_do(core, t) result(yes)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t
        real(c_double), pointer :: u(:)
        real(wp) :: rho
        yes = .false.
        if (core%augmented) return   ! no switch back from the augmented formulation
        u => core%ida%state()
        rho = spectral_radius(core, t, u(1:core%n))
        ! not inside a singular interval: the damped multiplier softens the constraint
        ! modes there for a moment (gamma sigma^2/(sigma^2 + eps) -> 0), and the explicit
        ! method would take the pass with the steps of the regular motion (measured:
        ! ex52 index=2 gamma=1e6 rtol=1e-6 switched back at t = 9.507 and lost 3e-2 rad)
        if (rho > 0.0_wp .and. 3.3_wp/rho > 2.0_wp*core%ida%last_step() .and. .not. core%monitor%in_singular) then
            core%explicit_votes = core%explicit_votes + 1
        else
            core%explicit_votes = 0
        end if
        ! two checks in a row; after each return to IDA twice as many (at most 64), so that
        ! a problem at the border between the two does not switch at every check
        yes = (core%explicit_votes >= 2*2**min(core%back_switches, 5))
    end function explicit_would_do

    !> integrator=auto: back to the explicit method at t, IDA's state there.
    subroutine switch_to_dopri5(core, t)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t
        real(c_double), pointer :: u(:)
        integer :: stat
        u => core%ida%state()
        core%z_rk = u(1:core%n)
        call core%rk%start(core%model, t, core%z_rk, core%ida%last_step(), stat)
        core%active = integrator_dopri5
        core%switches = core%switches + 1
        core%back_switches = core%back_switches + 1
        core%explicit_votes = 0
        call log_event(core, 't = '//format_real(t)//': ida -> dopri5 (the explicit method''s stable step '// &
                       'exceeds twice IDA''s)')
    end subroutine switch_to_dopri5

end module regdae_integrator_switching
