!> The automatic parameters of a start (`auto` in core%opts resolved from the
!! problem at t0, by the rules of `regdae_auto_rules` and `regdae_augmented_rules`;
!! doc/methods.md) and the start's checks that depend on them: the absolute
!! tolerance of each state component, whether a first step fits (check_first_step)
!! and the time resolution of an integrator. Split from regdae_solver_front, whose
!! init paths call them on the solver's core record (`regdae_solver_core`).
module regdae_auto_parameters
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_options
    use regdae_regularization, only: regularized_dae
    use regdae_augmented_system, only: augmented_system, user_routine_failure
    use regdae_auto_rules, only: automatic_eps_factor, automatic_eps, baumgarte_weights, dense_motion_scales, rms, &
                                 rest_in_equilibrium
    use regdae_work_energy, only: kinetic_energy_and_power
    use regdae_scales, only: drift_rtol_min
    use regdae_format, only: format_real, format_int
    use regdae_solver_core, only: solver_core
    use regdae_augmented_rules, only: mass_diagonal, gb_row_scale, augmented_motion_scales
    implicit none
    private

    public :: set_state_tolerances, resolve_auto_parameters, resolve_augmented_parameters, augmented_eps, &
              check_first_step, time_resolution

    !> The automatic drift bound: this many times the constraint violation that the
    !! tolerances on x allow (regdae_scales; doc/methods.md).
    real(wp), parameter :: drift_factor = 1.0e2_wp

contains

    !> The absolute tolerance of each component of the state z (length core%n):
    !! init's atol_vector (in core%atol_z already), or atol, with atol_v on a
    !! second-order problem's velocities.
    subroutine set_state_tolerances(core, stat, msg)
        type(solver_core), intent(inout) :: core
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        stat = regdae_err_bad_input
        msg = ''
        if (core%opts%atol_v /= option_auto .and. .not. (core%second_order .and. core%n == 2*core%nx)) then
            msg = 'atol_v is the velocities'' tolerance of a second-order problem; this problem has none '// &
                  '(use atol, or atol_vector per component)'
        else if (allocated(core%atol_z)) then   ! init's atol_vector
            if (size(core%atol_z) /= core%n) then
                msg = 'atol_vector has '//format_int(size(core%atol_z))//' entries; it needs one per '// &
                      'component of the state: '//format_int(core%n)// &
                      trim(merge(' (the positions, then the velocities)', '                                     ', &
                                 core%second_order .and. core%n == 2*core%nx))
            else if (.not. all(core%atol_z > 0.0_wp .and. core%atol_z <= huge(1.0_wp))) then
                msg = 'atol_vector: every entry must be finite and > 0'
            end if
        else
            core%atol_z = spread(core%opts%atol, 1, core%n)
            if (core%opts%atol_v /= option_auto) core%atol_z(core%nx + 1:2*core%nx) = core%opts%atol_v
        end if
        if (len(msg) == 0) stat = regdae_success
    end subroutine set_state_tolerances

    !> The `auto` parameters of core%opts, from the problem at (t0, z0) (the model
    !! evaluated there with provisional weights); the model gets them, and
    !! core%opts holds them as numbers afterwards (singular_threshold stays auto:
    !! the monitor's running rule). The rules are regdae_auto_rules' (doc/methods.md):
    !!  - the rate of the motion omega from v, the accelerations and the constraint
    !!    length l; gamma = gamma1 = weight_factor omega, gamma0 = gamma1^2/2, and
    !!    along the run the monitor lets them follow the motion;
    !!  - eps = automatic_eps(rtol, sigma_reg, s), sigma_reg = sigma_min(GB) at t0 or,
    !!    if a row of G vanishes there, the prediction from the constraint curvature;
    !!  - drift_tol = 100 max_i |G_i| (rtol max|x0| + atol).
    subroutine resolve_auto_parameters(core, t0, z0, stat, msg)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t0, z0(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp) :: scale, rate, ell, sigma0, sigma_pred, y(core%m), zp(size(z0)), zc(size(z0)), kinetic, power
        integer :: wstat
        logical :: recoverable, weights_auto, work_check, eps_auto, order2
        stat = regdae_success
        msg = ''
        associate (opts => core%opts, model => core%model)
            eps_auto = (opts%eps == option_auto)
            if (eps_auto) then   ! provisional: for the slope at t0 (the rule needs the motion's directions)
                scale = gb_scale(model)
                if (.not. (scale > 0.0_wp)) scale = maxval(sum(model%gx**2, dim=2), 1, mask=.true.)
                if (.not. (scale > 0.0_wp)) scale = 1.0_wp
                core%eps_factor = automatic_eps_factor(opts%rtol)
                model%eps = automatic_eps(opts%rtol, scale, scale, model%method == method_direct)
            end if
            if (opts%drift_tol == option_auto) then
                core%drift_factor = drift_factor
                opts%drift_tol = drift_factor*maxval(sqrt(sum(model%gx**2, dim=2)), 1, mask=.true.)* &
                                 (max(opts%rtol, drift_rtol_min)*maxval(abs(z0(1:core%nx))) + &
                                  max(maxval(core%atol_z(1:core%nx)), drift_rtol_min))
                ! off without constraints, for first-order problems, and for order >= 3, whose
                ! Taylor weights leave a constraint error O(taylor_h^2) by design (doc/methods.md)
                if (core%m == 0 .or. .not. core%second_order .or. model%order >= 3) then
                    opts%drift_tol = 0.0_wp
                    core%drift_factor = 0.0_wp
                end if
            end if
            weights_auto = (opts%gamma == option_auto .or. opts%gamma0 == option_auto .or. opts%gamma1 == option_auto)
            work_check = (resolved_work_tol(opts) > 0.0_wp .and. model%is_mechanical())
            sigma0 = model%sigma_min_gb()
            sigma_pred = -1.0_wp
            rate = 0.0_wp
            core%ell0 = 0.0_wp
            core%rest_start = .false.
            if (weights_auto .or. work_check .or. eps_auto) then
                call model%solve_multiplier(t0, y, stat)
                if (stat /= regdae_success) then
                    msg = 'choosing the automatic parameters: the multiplier at t0 failed: '//model%message
                    return
                end if
                call model%dynamics_slope(z0, y, zp)
                order2 = core%second_order .and. size(z0) >= 2*core%nx
                ! at rest in an equilibrium the error test sees nothing but the damping's bias in
                ! the constraint modes (doc/methods.md, "The stable step after a restart")
                if (order2) core%rest_start = rest_in_equilibrium(z0(core%nx + 1:2*core%nx), &
                                                                  zp(core%nx + 1:2*core%nx), &
                                                                  model%f(size(model%f) - core%nx + 1:), &
                                                                  model%eps, sigma0)
                call dense_motion_scales(model, t0, z0, zp, core%nx, order2, 0.0_wp, eps_auto, ell, rate, &
                                         sigma_pred, stat, stiffness=.true.)
                if (stat /= 0) then
                    msg = 'choosing the automatic parameters: user routine constraint_jacobian reported failure '// &
                          '(stat = '//format_int(stat)//') at t0'
                    stat = regdae_err_user_callback
                    return
                end if
                core%ell0 = ell
            end if
            core%rate0 = rate
            core%sigma_pred0 = sigma_pred
            if (eps_auto) then
                scale = gb_scale(model)
                opts%eps = automatic_eps(opts%rtol, max(sigma0, sigma_pred), scale, model%method == method_direct)
                model%eps = opts%eps
            end if
            core%eps_auto0 = automatic_eps(opts%rtol, max(sigma0, sigma_pred), gb_scale(model), &
                                           model%method == method_direct)
            if (work_check) then
                ! the work-energy check's floor of the energy scale: the kinetic energy of the
                ! velocities that the accelerations at t0 reach in one time scale 1/rate (a start
                ! from rest has no energy of its own to compare the defect with)
                ! (the larger of the constrained and the applied forces' accelerations: a start at
                ! rest in an equilibrium has none of the first, and the rounding moves it)
                zc = z0
                zc(core%nx + 1:2*core%nx) = zp(core%nx + 1:2*core%nx)
                if (rms(model%f(size(model%f) - core%nx + 1:)) > rms(zp(core%nx + 1:2*core%nx))) &
                    zc(core%nx + 1:2*core%nx) = model%f(size(model%f) - core%nx + 1:)
                zc(core%nx + 1:2*core%nx) = zc(core%nx + 1:2*core%nx)/merge(rate, 1.0_wp, rate > 0.0_wp)
                call model%work_sample(t0, zc, kinetic, power, wstat)
                if (wstat == 0) core%work_floor = kinetic
            end if
            if (weights_auto) then
                call set_auto_weights(core, rate)
                if (model%order == 1) model%w = [opts%gamma]
                if (model%order == 2) model%w = [opts%gamma0, opts%gamma1]
            end if
            ! the weights follow the motion when all of those the model uses are automatic
            core%follow_weights = (model%order == 1 .and. core%auto_gamma) .or. &
                                  (model%order == 2 .and. core%auto_gamma0 .and. core%auto_gamma1)
            if (weights_auto .or. eps_auto) call model%evaluate(t0, z0, stat, recoverable)   ! r with the final values
        end associate
    end subroutine resolve_auto_parameters

    ! The weights of core%opts left auto from the rate of the motion (regdae_auto_rules);
    ! which ones were auto.
    subroutine set_auto_weights(core, rate)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: rate
        real(wp) :: gamma, gamma0, gamma1
        call baumgarte_weights(rate, gamma, gamma0, gamma1)
        associate (opts => core%opts)
            core%auto_gamma = (opts%gamma == option_auto)
            core%auto_gamma0 = (opts%gamma0 == option_auto)
            core%auto_gamma1 = (opts%gamma1 == option_auto)
            if (opts%gamma == option_auto) opts%gamma = gamma
            if (opts%gamma1 == option_auto) opts%gamma1 = gamma1
            if (opts%gamma0 == option_auto) opts%gamma0 = 0.5_wp*opts%gamma1**2
        end associate
    end subroutine set_auto_weights

    !> The `auto` parameters for the augmented formulation (the rules of
    !! resolve_auto_parameters with the sparse M and G): s = max_i sum_k G_ik^2 / M_kk
    !! (the diagonal of GB with M's diagonal), the accelerations M_kk^-1 f_k of the
    !! free motion, the constraint length from the sparse G along v and them. eps
    !! needs sigma_min(GB), by inverse iteration at IDA's first vector: the caller
    !! sets it (augmented_eps) once that vector exists.
    subroutine resolve_augmented_parameters(core, sys, t0, q0, v0, stat, msg)
        type(solver_core), intent(inout) :: core
        type(augmented_system), intent(inout) :: sys
        real(wp), intent(in) :: t0, q0(:), v0(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp) :: mdiag(sys%n), f(sys%n), acc(sys%n), g0(sys%st%constraint%nnz()), scale, rate, gmax, &
                    kinetic, power, y_zero(sys%m), ell, sigma_pred
        integer :: i, ustat
        logical :: recoverable, weights_auto, work_check
        stat = 0
        msg = ''
        associate (opts => core%opts, mp => sys%st%mass, gp => sys%st%constraint)
            ustat = 0
            call sys%problem%mass_values(t0, q0, mp, sys%mvals, ustat)
            if (failed('mass_values')) return
            call sys%problem%constraint_jacobian_values(t0, q0, gp, g0, ustat)
            if (failed('constraint_jacobian_values')) return
            call sys%problem%forces(t0, q0, v0, f, ustat)
            if (failed('forces')) return
            call mass_diagonal(sys, mdiag)
            scale = 0.0_wp
            gmax = 0.0_wp
            do i = 1, sys%m
                scale = max(scale, gb_row_scale(sys, g0, mdiag, i))
                gmax = max(gmax, norm2(g0(gp%row_start(i):gp%row_start(i + 1) - 1)))
            end do
            if (.not. (scale > 0.0_wp)) scale = 1.0_wp
            if (opts%eps == option_auto) then
                core%eps_factor = automatic_eps_factor(opts%rtol)
                opts%eps = automatic_eps(opts%rtol, scale, scale, opts%method == method_direct)   ! provisional
            end if
            if (opts%drift_tol == option_auto) then
                core%drift_factor = drift_factor
                opts%drift_tol = drift_factor*gmax*(max(opts%rtol, drift_rtol_min)*maxval(abs(q0)) + &
                                                    max(maxval(core%atol_z(1:size(q0))), drift_rtol_min))
            end if
            weights_auto = (opts%gamma == option_auto .or. opts%gamma0 == option_auto .or. opts%gamma1 == option_auto)
            work_check = resolved_work_tol(opts) > 0.0_wp
            acc = f/mdiag
            call augmented_motion_scales(sys, t0, q0, v0, acc, acc, 0.0_wp, opts%eps == option_auto .or. &
                                         core%eps_factor > 0.0_wp, ell, rate, sigma_pred, stat, .true.)
            if (stat /= 0) then
                ustat = stat
                call user_routine_failure(ustat, 'constraint_jacobian_values', t0, stat, msg, recoverable)
                return
            end if
            core%rate0 = rate
            core%ell0 = ell
            core%sigma_pred0 = sigma_pred
            call set_auto_weights(core, rate)
            core%follow_weights = merge(core%auto_gamma0 .and. core%auto_gamma1, core%auto_gamma, opts%index == 3)
            if (work_check) then   ! the floor of the work check's energy scale (as for the dense formulations)
                y_zero = 0.0_wp
                call kinetic_energy_and_power(sys%problem, t0, q0, acc/merge(rate, 1.0_wp, rate > 0.0_wp), y_zero, &
                                              kinetic, power, ustat, sys%st%mass)
                if (ustat == 0) core%work_floor = kinetic
            end if
            if (.not. weights_auto) core%follow_weights = .false.
            sys%eps = opts%eps
            call set_augmented_weights(core, sys)
        end associate
    contains
        ! A user routine returned ustat /= 0 at t0: stat and msg say which and what.
        logical function failed(name)
            character(len=*), intent(in) :: name
            failed = (ustat /= 0)
            if (failed) call user_routine_failure(ustat, name, t0, stat, msg, recoverable)
        end function failed
    end subroutine resolve_augmented_parameters

    ! The weights of core%opts into the augmented system (index 2: gamma0 = 0, gamma1 = gamma).
    subroutine set_augmented_weights(core, sys)
        type(solver_core), intent(in) :: core
        type(augmented_system), intent(inout) :: sys
        if (core%opts%index == 3) then
            sys%gamma0 = core%opts%gamma0
            sys%gamma1 = core%opts%gamma1
        else
            sys%gamma0 = 0.0_wp
            sys%gamma1 = core%opts%gamma
        end if
    end subroutine set_augmented_weights

    !> The automatic eps of the augmented formulation at t0 from sigma_min(GB) at
    !! IDA's first vector u0 (or the singular start's prediction).
    subroutine augmented_eps(core, sys, t0, u0)
        type(solver_core), intent(inout) :: core
        type(augmented_system), intent(inout) :: sys
        real(wp), intent(in) :: t0, u0(:)
        real(wp) :: sigma0, gb, g
        integer :: stat
        sigma0 = sys%sigma_min_gb(t0, u0, stat)
        if (stat /= 0 .or. .not. (sigma0 < huge(1.0_wp))) sigma0 = 0.0_wp
        call sys%diagonal_scales(gb, g)
        core%eps_auto0 = automatic_eps(core%opts%rtol, max(sigma0, core%sigma_pred0), gb, &
                                       core%opts%method == method_direct)
        if (core%eps_factor > 0.0_wp) then
            core%opts%eps = core%eps_auto0
            sys%eps = core%opts%eps
        end if
    end subroutine augmented_eps

    !> Can an integrator take a first step from (t0, z0) with slope zp0? The
    !! step that keeps the local error near the tolerance is about 1/|zp0|_w,
    !! the weighted RMS norm with the weights w = 1/(rtol |z0| + atol) of the
    !! components in the error test (IDA's own estimate of the first step is
    !! 0.5/|zp0|_w). When that norm overflows (IDA squares w zp0) or its step
    !! is below the time resolution at t0, no step can be taken: IDA would fail
    !! with a message about tstop or tout, dopri5 with "step size too small".
    !! Say what causes it instead: the tolerances, or a slope that a large
    !! Baumgarte weight has made huge.
    subroutine check_first_step(core, t0, z0, zp0, stat, msg)
        type(solver_core), intent(in) :: core
        real(wp), intent(in) :: t0, z0(:), zp0(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp) :: w, scaled, biggest, sumsq, norm
        character(len=:), allocatable :: weights
        integer :: i, worst
        stat = regdae_success
        msg = ''
        biggest = 0.0_wp
        worst = 0
        do i = 1, size(z0)
            if (core%excluded(i) .and. core%opts%integrator /= integrator_dopri5) cycle
            w = 1.0_wp/(core%opts%rtol*abs(z0(i)) + core%atol_z(i))
            scaled = abs(zp0(i))*w
            if (.not. (scaled <= biggest)) then
                biggest = scaled
                worst = i
            end if
        end do
        if (worst == 0) return
        norm = huge(1.0_wp)
        if (biggest < 1.0e150_wp) then
            sumsq = 0.0_wp
            do i = 1, size(z0)
                if (core%excluded(i) .and. core%opts%integrator /= integrator_dopri5) cycle
                w = 1.0_wp/(core%opts%rtol*abs(z0(i)) + core%atol_z(i))
                sumsq = sumsq + (zp0(i)*w/biggest)**2
            end do
            norm = biggest*sqrt(sumsq/size(z0))
            if (0.5_wp/norm >= time_resolution(t0, t0)) return
        end if
        stat = regdae_err_bad_input
        w = 1.0_wp/(core%opts%rtol*abs(z0(worst)) + core%atol_z(worst))
        msg = 'no first step possible at t0 = '//format_real(t0)//': the step that keeps the local error at the '// &
              'tolerance, about 1/|z''(t0)|_w with the error weights w = 1/(rtol |z| + atol), is below the time '// &
              'resolution (component '//format_int(worst)//': |z''| = '//format_real(abs(zp0(worst)))// &
              ', w = '//format_real(w)//'): '
        if (w > abs(zp0(worst))) then
            msg = msg//'atol = '//format_real(core%atol_z(worst))//' is too small (the weighted norms square the '// &
                  'weights, up to 1/atol, which overflow for atol below about 1e-150)'
        else
            call weights_text(core, weights)
            msg = msg//'the initial slope is huge; '//weights//' magnifies the rounding error of '// &
                  'the constraint at the initial point (max |g| = '//format_real(maxval(abs(core%model%g), 1))// &
                  ') into the multiplier, or f(x0, t0) itself is that large'
        end if
    end subroutine check_first_step

    ! The Baumgarte weights in use, for messages.
    subroutine weights_text(core, text)
        type(solver_core), intent(in) :: core
        character(len=:), allocatable, intent(out) :: text
        if (core%model%order == 2) then
            text = 'the weight gamma0 = '//format_real(core%opts%gamma0)//' (or gamma1 = '// &
                   format_real(core%opts%gamma1)//')'
        else if (core%model%order >= 3) then
            text = 'a Taylor weight (taylor_h = '//format_real(core%opts%taylor_h)//')'
        else
            text = 'the weight gamma = '//format_real(core%opts%gamma)
        end if
    end subroutine weights_text

    ! max_i (GB)_ii at the model's last evaluation (the scale of GB).
    pure real(wp) function gb_scale(model) result(s)
        type(regularized_dae), intent(in) :: model
        integer :: i
        s = 0.0_wp
        do i = 1, model%m
            s = max(s, abs(model%gb(i, i)))
        end do
    end function gb_scale

    !> The smallest interval an integrator can step across at t and tout:
    !! 4 epsilon max(|t|, |tout|) (IDA's own test for tout too close to t0), and
    !! at least sqrt(tiny) so that a first step of a fraction of it is a normal number.
    pure real(wp) function time_resolution(t, tout)
        real(wp), intent(in) :: t, tout
        time_resolution = max(4*epsilon(1.0_wp)*max(abs(t), abs(tout)), sqrt(tiny(1.0_wp)))
    end function time_resolution

end module regdae_auto_parameters
