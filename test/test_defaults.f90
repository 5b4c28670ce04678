!> The automatic defaults (issue 11): each automatic rule is scale-free (the
!! same trajectory in metres, millimetres, kilograms and grams, seconds and
!! milliseconds), the work-energy check is quiet on a correct rheonomic run and
!! fires on one that gains energy, integrator=auto switches to IDA where a
!! problem becomes stiff and back where it stops being stiff, and a run of the
!! explicit integrator that leaves the physical branch ends with a status.
module test_defaults
    use regdae
    use chain_problem, only: chain, new_chain, chain_start
    use slider_crank_problem, only: new_slider_crank
    use regdae_testing, only: checker, test_case, new_test
    use regdae_auto_rules, only: constraint_mode_step, stable_radius, rest_in_equilibrium
    use fourbar_problem, only: new_fourbar, fourbar_branch_start
    use regdae_taylor_layer, only: taylor_layer_watch, layer_efolds_max
    use regdae_work_energy, only: interval_work
    implicit none
    private
    public :: defaults_tests

    real(wp), parameter :: pi = acos(-1.0_wp)
    real(wp), parameter :: omega = 50.0_wp   !! stiff_middle's frequency

    !> A point mass on a string whose length L(t) = 1 + 0.2 sin(2t) is driven
    !! (rheonomic: g = x^2 + y^2 - L(t)^2), under gravity; with `forget_gt` the
    !! problem reports g_t = 0, as a user who forgets the moving constraint would.
    type, extends(mechanical_problem), public :: growing_pendulum
        logical :: forget_gt = .false.
    contains
        procedure :: mass_matrix => growing_mass
        procedure :: forces => growing_forces
        procedure :: constraint => growing_g
        procedure :: constraint_jacobian => growing_gx
        procedure :: constraint_dt => growing_gt
    end type growing_pendulum

    !> x1' = -lambda(t) (x1 - sin wt) + w cos wt, x2' = 1 - y, 0 = x2 - t (B = (0, 1)^T),
    !! w = 50: exact x = (sin wt, t), y = 0; lambda = 1 + 1e5 on t in [1, 2] (smoothly), 1
    !! elsewhere. Outside [1, 2] the steps are set by accuracy (the oscillation), inside by
    !! stability.
    type, extends(dae_problem) :: stiff_middle
    contains
        procedure :: rhs => middle_rhs
        procedure :: matrix_b => middle_b
        procedure :: constraint => middle_g
        procedure :: constraint_jacobian => middle_gx
        procedure :: constraint_dt => middle_gt
    end type stiff_middle

contains

    function defaults_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('rules_are_scale_free', rules_are_scale_free), &
                 new_test('work_check_quiet_and_fires', work_check_quiet_and_fires), &
                 new_test('work_over_a_long_step', work_over_a_long_step), &
                 new_test('switches_halfway_and_back', switches_halfway_and_back), &
                 new_test('explicit_off_branch_fails', explicit_off_branch_fails), &
                 new_test('stiff_chain_switches_to_augmented', stiff_chain_switches_to_augmented), &
                 new_test('stiff_chain_starts_augmented', stiff_chain_starts_augmented), &
                 new_test('light_chain_keeps_explicit_start', light_chain_keeps_explicit_start), &
                 new_test('small_stiff_chain_starts_radau', small_stiff_chain_starts_radau), &
                 new_test('radau_start_is_integrator_radau', radau_start_is_integrator_radau), &
                 new_test('rate_continuous_at_rest', rate_continuous_at_rest), &
                 new_test('eps_at_singular_start', eps_at_singular_start), &
                 new_test('eps_is_translation_free', eps_is_translation_free), &
                 new_test('constraint_mode_step', constraint_mode_step_values), &
                 new_test('rest_in_equilibrium', rest_in_equilibrium_values), &
                 new_test('fourbar_top_stays', fourbar_top_stays), &
                 new_test('taylor_layer_growth', taylor_layer_growth)]
    end function defaults_tests

    ! The stable step of dopri5 on the constraint modes: stable_radius/|s|, s the largest root
    ! of s + gamma (order 1) and s^2 + gamma1 s + gamma0 (order 2; |s| = gamma1/sqrt(2) for the
    ! automatic gamma0 = gamma1^2/2, |s| = (gamma1 + sqrt(gamma1^2 - 4 gamma0))/2 for real roots);
    ! none for the Taylor weights (order 3).
    subroutine constraint_mode_step_values(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: g1 = 20.0_wp
        call chk%close(constraint_mode_step(1, [g1]), stable_radius/g1, 1.0e-14_wp, 'order 1')
        call chk%close(constraint_mode_step(2, [0.5_wp*g1**2, g1]), stable_radius*sqrt(2.0_wp)/g1, &
                             1.0e-14_wp, 'order 2, automatic gamma0 = gamma1^2/2')
        call chk%close(constraint_mode_step(2, [64.0_wp, 20.0_wp]), stable_radius/16.0_wp, 1.0e-14_wp, &
                             'order 2, roots -4 and -16')
        call chk%true(constraint_mode_step(3, [6.0e6_wp, 6.0e4_wp, 300.0_wp]) == huge(1.0_wp), &
                            'order 3: no stable step')
    end subroutine constraint_mode_step_values

    ! A start at rest in an equilibrium: every velocity zero, an acceleration within 10x the
    ! damping's bias eps/sigma^2 of the applied one (the four-bar's top: 1e-6 of it at eps = 4e-6,
    ! sigma = 2); not with a velocity, an acceleration 100x the bias, a large bias, or no load.
    subroutine rest_in_equilibrium_values(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: f(3) = [0.0_wp, -4.9_wp, 0.0_wp], rest(3) = 0.0_wp
        real(wp), parameter :: a(3) = [0.0_wp, -4.9e-6_wp, 0.0_wp]
        call chk%true(rest_in_equilibrium(rest, a, f, 4.0e-6_wp, 2.0_wp), 'the four-bar''s top')
        call chk%true(.not. rest_in_equilibrium([0.0_wp, 1.0e-12_wp, 0.0_wp], a, f, 4.0e-6_wp, 2.0_wp), &
                      'not at rest')
        call chk%true(.not. rest_in_equilibrium(rest, 100*a, f, 4.0e-6_wp, 2.0_wp), 'an acceleration 100x the bias')
        call chk%true(.not. rest_in_equilibrium(rest, a, f, 4.0e-6_wp, 1.0e-2_wp), 'near a singular configuration')
        call chk%true(.not. rest_in_equilibrium(rest, rest, rest, 4.0e-6_wp, 2.0_wp), 'no load')
        call chk%true(rest_in_equilibrium(rest, 1.0e-15_wp*f, f, 0.0_wp, 2.0_wp), 'eps = 0: the rounding')
    end subroutine rest_in_equilibrium_values

    ! The parallelogram four-bar at rest at its unstable top (th1 = pi/2): the exact motion stays,
    ! the unstable mode grows like exp(sqrt(g/r) t), 6e6 over 5 s. With every step within the
    ! constraint modes' stable step (a start at rest in an equilibrium) the defaults at rtol 1e-3
    ! stay within 0.1 error weights, |q_i(5) - q_i(0)| / (rtol |q_i(0)| + atol) (measured 3.2e-5 at
    ! index 3, 1.4e-3 at index 2, th2's drift; before the rule the trust grid's cells 9 and 63 were
    ! 14.3 and 32.4: dopri5's steps grew 5x to 0.625 s, h |s| = 7.8, and the constraint modes, set
    ! off by the damping's bias, grew to 1e-4 and fed the unstable mode).
    subroutine fourbar_top_stays(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        real(wp) :: q0(3), v0(3), q(3), err
        integer :: stat, index, k
        do index = 2, 3
            opts = solver_options()
            opts%rtol = 1.0e-3_wp
            opts%atol = 1.0e-3_wp
            opts%index = index
            call fourbar_branch_start(pi/2, 0.0_wp, q0, v0)
            call solver%init(new_fourbar(1.0_wp, 2.0_wp, 9.81_wp), 0.0_wp, q0, v0, opts, stat)
            call chk%equal(stat, 0, 'init at the top, index '//achar(48 + index))
            do k = 1, 200   ! the trust grid's outputs (at index 2 one output at t = 5 stayed without the rule)
                call solver%advance(0.025_wp*k, q, stat=stat)
                if (stat /= 0) exit
            end do
            call chk%equal(stat, 0, 'advance to t = 5, index '//achar(48 + index))
            err = maxval(abs(q - q0)/(opts%rtol*abs(q0) + opts%atol))
            print '(a,i0,a,es10.2)', '    index ', index, ': error weights at t = 5:', err
            call chk%true(err < 0.1_wp, 'still at the top at t = 5, index '//achar(48 + index))
            call solver%destroy()
        end do
    end subroutine fourbar_top_stays

    ! The growth bound in the layer of the Taylor weights (regdae_taylor_layer): at order 3 with
    ! taylor_h = h and d = 0 (sigma_min(GB) = 0) it adds 0.2071 dt/h per step and warns once
    ! past layer_efolds_max; a step with d >= 1/3 ends the stretch; order 2 never warns.
    subroutine taylor_layer_growth(chk)
        type(checker), intent(inout) :: chk
        type(taylor_layer_watch) :: watch
        real(wp), parameter :: h = 1.0e-5_wp, dt = 1.0e-6_wp, eps = 1.0e-10_wp
        real(wp) :: w(3), t
        integer :: k, warned_at, warnings
        w = [6.0_wp/h**3, 6.0_wp/h**2, 3.0_wp/h]
        warned_at = -1
        warnings = 0
        t = 0.0_wp
        do k = 1, 1000
            if (watch%step(3, w, method_trust_region, eps, 0.0_wp, t, t + dt)) then
                warnings = warnings + 1
                if (warned_at < 0) warned_at = k
            end if
            t = t + dt
        end do
        ! 18/(0.2071 * 0.1) = 869.1 steps
        call chk%equal(warned_at, ceiling(layer_efolds_max/(0.2071_wp*dt/h)), 'the step that warns')
        call chk%equal(warnings, 1, 'one warning per stretch')
        call chk%true(index(watch%message, 'Taylor weights') > 0, 'the message names the layer')
        call chk%true(.not. watch%step(3, w, method_trust_region, eps, 1.0_wp, t, t + dt), &
                            'sigma = 1 (d ~ 1): out of the stretch')
        call chk%true(watch%efolds == 0.0_wp, 'the stretch ended')
        do k = 1, 2000
            call chk%true(.not. watch%step(2, [200.0_wp, 20.0_wp], method_trust_region, eps, 0.0_wp, t, t + dt), &
                                'order 2 is stable for every d')
        end do
    end subroutine taylor_layer_growth

    ! The automatic weights as the initial speed goes to zero (issue 19): the slider crank
    ! from th1 = 2 with w1 = 0, 1e-12, 1e-6, 1e-3 resolves gamma1 within a factor 2 of
    ! each other (the rule it replaced had 1/|v| in it: gamma1 = 1.05e7 at w1 = 1e-5,
    ! 31 at w1 = 0); and the run at w1 = 1e-5, rtol 1e-6 takes a few hundred steps (the
    ! rule it replaced: 9.1e-3 rad in 156,057 steps). Its accuracy against the reduced ODE
    ! is asserted by test/check_trust.sh (driver.trust_reproducers, the start "2.0 1e-5 1e-6").
    subroutine rate_continuous_at_rest(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts, resolved
        real(wp), parameter :: speeds(4) = [0.0_wp, 1.0e-12_wp, 1.0e-6_wp, 1.0e-3_wp]
        real(wp) :: gammas(4), th(2)
        integer :: k, stat
        type(solver_stats) :: st
        do k = 1, 4
            call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [2.0_wp, pi - 2.0_wp], [speeds(k), -speeds(k)], &
                             opts, stat)
            resolved = solver%options()
            gammas(k) = resolved%gamma1
            call chk%equal(stat, regdae_success, 'init')
        end do
        write (*, '(a,4es11.3)') '    gamma1 at w1 = 0, 1e-12, 1e-6, 1e-3: ', gammas
        call chk%true(maxval(gammas)/minval(gammas) <= 2.0_wp, 'gamma1 within a factor 2 as v -> 0')
        opts%rtol = 1.0e-6_wp
        opts%atol = 1.0e-6_wp
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [2.0_wp, pi - 2.0_wp], [1.0e-5_wp, -1.0e-5_wp], opts, stat)
        do k = 1, 10
            if (stat < 0) exit
            call solver%advance(real(k, wp), th, stat=stat)
        end do
        st = solver%statistics()
        call chk%true(stat >= 0 .and. st%steps < 5000, 'w1 = 1e-5 at rtol 1e-6: runs in a few hundred steps')
        write (*, '(a,i6)') '    w1 = 1e-5, rtol 1e-6: steps ', int(st%steps)
        call solver%destroy()
    end subroutine rate_continuous_at_rest

    ! A start on a singular configuration (issue 19): the slider crank at th1 = 1e-8
    ! (G ~ 1e-8, sigma_min(GB) ~ 5e-16) resolves a positive eps that damps the layer it
    ! starts in (eps >= 100 sigma_min(GB(t0))^2; the rule it replaced: 2.5e-37, and a
    ! theta error of 0.337 rad with status ok at rtol 1e-3), and the start is a singular
    ! interval of its own (the pass check takes it).
    subroutine eps_at_singular_start(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts, resolved
        real(wp) :: sigma0
        integer :: stat
        opts%rtol = 1.0e-3_wp
        opts%atol = 1.0e-3_wp
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [1.0e-8_wp, pi - 1.0e-8_wp], [2.5_wp, -2.5_wp], opts, stat)
        call chk%equal(stat, regdae_success, 'init')
        resolved = solver%options()
        sigma0 = solver%sigma_min()
        write (*, '(a,2es11.3)') '    eps, sigma_min(GB(t0)): ', resolved%eps, sigma0
        call chk%true(resolved%eps > 0.0_wp .and. resolved%eps >= 100.0_wp*sigma0**2, 'eps positive, the start in its layer')
        call chk%true(resolved%eps >= 1.0e-12_wp, 'eps at the regular scale, not the start''s')
        call chk%true(size(solver%singular_intervals(), 2) == 1, 'the start is a singular interval')
        call solver%destroy()
    end subroutine eps_at_singular_start

    ! The slider crank's start with th1 shifted by 2 pi k (k = 0, 1, 10, 100; th2 = pi - th1
    ! shifted with it, as ex52 starts it: the same physical state) resolves the same eps,
    ! at a singular start (th1 = 1e-8, w1 = 20: a vanishing row's prediction measured
    ! the scale of x by rms(x), and eps was 3.8e-5, 9.5e-4, 22 and 2.4e5; now from the
    ! angles' representative in (-pi, pi]) and at a regular one (th1 = 1), in the
    ! eliminated and the augmented formulation. The representative of th1 + 2 pi k is
    ! th1 to the rounding of th1 + 2 pi k (1e-13 at k = 100): 1e-6 relative bounds it.
    subroutine eps_is_translation_free(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: starts(2) = [1.0e-8_wp, 1.0_wp]
        integer, parameter :: shifts(4) = [0, 1, 10, 100]
        type(regdae_solver) :: solver
        type(solver_options) :: opts, resolved(size(shifts))
        integer :: stat, i, k, f
        real(wp) :: th1
        character(len=80) :: label
        do f = 1, 2
            do i = 1, size(starts)
                do k = 1, size(shifts)
                    opts = solver_options()
                    opts%rtol = 1.0e-3_wp
                    opts%atol = 1.0e-3_wp
                    if (f == 2) opts%formulation = formulation_augmented
                    th1 = starts(i) + 2.0_wp*pi*shifts(k)
                    call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [th1, pi - th1], [20.0_wp, -20.0_wp], opts, stat)
                    call chk%equal(stat, regdae_success, 'init')
                    resolved(k) = solver%options()
                    call solver%destroy()
                end do
                write (label, '(a,es8.1,a,i0)') ' at th1 = ', starts(i), ' + 2 pi k, formulation ', f
                write (*, '(a,4es16.8)') '    eps'//trim(label)//': ', resolved(:)%eps
                call chk%close_rel(resolved(2:)%eps, spread(resolved(1)%eps, 1, size(shifts) - 1), 1.0e-6_wp, &
                                   'the same eps'//trim(label))
            end do
        end do
    end subroutine eps_is_translation_free

    ! Example 5.2 in Cartesian coordinates (the chain of 2 links with the slider: two
    ! singular passes on [0, 2]) with every option at its default but the tolerances,
    ! in (m, kg, s) and in (mm, g, ms): the automatic eps, weights and drift bound
    ! scale with the units (eps like (GB)^2: 1e-6; gamma like 1/time: 1e-3; the drift
    ! bound like length: 1e3), so both runs solve the same regularized problem; their
    ! step sequences differ (difference-quotient increments are not scale-free), and
    ! the positions differ by the integration error (measured 1.7e-5 at rtol 1e-6,
    ! through two singular passes); 100 rtol bounds it.
    subroutine rules_are_scale_free(chk)
        type(checker), intent(inout) :: chk
        integer, parameter :: nout = 20
        real(wp) :: q(4, 0:nout, 2), scale_length(2), scale_time(2), scale_mass(2), diff
        type(solver_options) :: resolved(2)
        integer :: stat(2), u, k
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(chain) :: p
        real(wp) :: q0(4), v0(4), v(4), y(3)
        scale_length = [1.0_wp, 1.0e3_wp]   ! m, mm
        scale_time = [1.0_wp, 1.0e3_wp]     ! s, ms
        scale_mass = [1.0_wp, 1.0e3_wp]     ! kg, g
        do u = 1, 2
            p = new_chain(2, .true., 9.81_wp*scale_length(u)/scale_time(u)**2)
            p%length = scale_length(u)
            p%joint_mass = scale_mass(u)
            call chain_start(p, q0, v0)
            opts = solver_options()
            opts%rtol = 1.0e-6_wp
            opts%atol = 1.0e-6_wp*scale_length(u)
            call solver%init(p, 0.0_wp, q0, v0, opts, stat(u))
            if (stat(u) /= regdae_success) write (*, '(a)') '    '//solver%message()
            resolved(u) = solver%options()
            q(:, 0, u) = q0/scale_length(u)
            do k = 1, nout
                if (stat(u) /= regdae_success) exit
                call solver%advance(0.1_wp*k*scale_time(u), q(:, k, u), y, stat(u), v)
                if (stat(u) /= regdae_success) write (*, '(a)') '    '//solver%message()
                q(:, k, u) = q(:, k, u)/scale_length(u)
            end do
            call solver%destroy()
        end do
        call chk%equal(stat(1), regdae_success, 'the run in m, kg, s')
        call chk%equal(stat(2), regdae_success, 'the run in mm, g, ms')
        call chk%close_rel([resolved(2)%eps], [resolved(1)%eps*1.0e-6_wp], 1.0e-10_wp, 'eps scales like (GB)^2')
        call chk%close_rel([resolved(2)%gamma1], [resolved(1)%gamma1*1.0e-3_wp], 1.0e-10_wp, 'gamma1 scales like 1/time')
        call chk%close_rel([resolved(2)%gamma0], [resolved(1)%gamma0*1.0e-6_wp], 1.0e-10_wp, &
                           'gamma0 scales like 1/time^2')
        call chk%close_rel([resolved(2)%drift_tol], [resolved(1)%drift_tol*1.0e3_wp], 1.0e-10_wp, &
                           'the drift bound scales like length')
        diff = maxval(abs(q(:, :, 2) - q(:, :, 1)))
        call chk%true(diff <= 1.0e-4_wp, 'the same positions in both unit systems')
        write (*, '(a,es10.2)') '    max |x(mm, g, ms) / 1000 - x(m, kg, s)|: ', diff
    end subroutine rules_are_scale_free

    ! The growing pendulum on [0, 5]: with g_t the constraint force's work is the
    ! moving string's, y^T g_t, and the work-energy balance holds (measured defect
    ! 1e-7 of the energy scale at rtol 1e-6); without it the string still moves (the
    ! stabilization follows g(x, t)), its work is missing from the balance, and the
    ! check stops the run (the drift and jump checks off, so that this one is tested).
    ! The work over one long step (regdae_work_energy's interval_work): uniform motion on the
    ! unit circle, q = (cos wt, sin wt), over h w = 1.2 (a long explicit step), under gravity.
    ! The work of the constant force along the interpolated path is exactly -g (y1 - y0) (Boole's
    ! rule is exact for it), where the trapezoid of the ends' powers v.f is 12% off; the estimate
    ! (the interpolant's own q' against its v, times the forces) is small against the work but
    ! not zero. A moving constraint (g_t /= 0) is left to the caller's quadrature (stat /= 0).
    subroutine work_over_a_long_step(chk)
        type(checker), intent(inout) :: chk
        type(growing_pendulum) :: p
        real(wp), parameter :: w = 2.0_wp, h = 0.6_wp, g = 9.81_wp
        real(wp) :: z0(4), dz0(4), z1(4), dz1(4), work, error, exact, trapezoid
        integer :: stat
        p%n = 2
        p%m = 1
        p%forget_gt = .true.
        z0 = [1.0_wp, 0.0_wp, 0.0_wp, w]
        dz0 = [0.0_wp, w, -w**2, 0.0_wp]
        z1 = [cos(w*h), sin(w*h), -w*sin(w*h), w*cos(w*h)]
        dz1 = [z1(3:4), -w**2*z1(1:2)]
        exact = -g*(z1(2) - z0(2))
        trapezoid = 0.5_wp*h*(-g*z0(4) - g*z1(4))
        call interval_work(p, 0.0_wp, z0, dz0, -g*z0(4), h, z1, dz1, -g*z1(4), work, error, stat)
        call chk%true(stat == 0, 'interval_work succeeds')
        call chk%close(work, exact, 1.0e-13_wp, 'the work along the path: -g (y1 - y0)')
        call chk%true(abs(trapezoid - exact) > 0.1_wp*abs(exact), 'the trapezoid of the ends is 10% off')
        call chk%true(error > 0.0_wp .and. error < 0.02_wp*abs(exact), 'the estimate: small, not zero')
        p%forget_gt = .false.
        call interval_work(p, 0.0_wp, z0, dz0, -g*z0(4), h, z1, dz1, -g*z1(4), work, error, stat)
        call chk%true(stat /= 0, 'a moving constraint: left to the caller')
    end subroutine work_over_a_long_step

    subroutine work_check_quiet_and_fires(chk)
        type(checker), intent(inout) :: chk
        type(growing_pendulum) :: p
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        real(wp) :: x(2), y(1)
        ! radial at the speed L'(0) = 0.4 of the string: G v + g_t = 0 at t0
        real(wp), parameter :: v0(2) = 0.4_wp*[0.6_wp, -0.8_wp]
        integer :: stat, k
        p%n = 2
        p%m = 1
        opts%rtol = 1.0e-6_wp
        opts%atol = 1.0e-6_wp
        call solver%init(p, 0.0_wp, [0.6_wp, -0.8_wp], v0, opts, stat)
        do k = 1, 50
            if (stat /= regdae_success) exit
            call solver%advance(0.1_wp*k, x, y, stat)
        end do
        st = solver%statistics()
        call chk%equal(stat, regdae_success, 'the rheonomic run with g_t ends ok')
        call chk%true(st%work_defect < 1.0e-3_wp, 'its work-energy defect is small')
        write (*, '(a,es10.2)') '    work_defect with g_t: ', st%work_defect
        call solver%destroy()
        p%forget_gt = .true.
        opts%drift_tol = 0.0_wp
        opts%jump_tol = 0.0_wp
        call solver%init(p, 0.0_wp, [0.6_wp, -0.8_wp], [0.0_wp, 0.0_wp], opts, stat)   ! at rest: g_t = 0
        do k = 1, 50
            if (stat /= regdae_success) exit
            call solver%advance(0.1_wp*k, x, y, stat)
        end do
        call chk%equal(stat, regdae_err_work, 'without g_t the work-energy check stops the run')
        call chk%true(index(solver%message(), 'work-energy balance failed') > 0 .and. &
                      index(solver%message(), 'work_tol=0 turns this check off') > 0, &
                      'the message says what failed and which option turns the check off')
        call solver%destroy()
    end subroutine work_check_quiet_and_fires

    ! stiff_middle on [0, 6], rtol 1e-6, all defaults: the explicit method until the
    ! stiffness test fires near t = 1, IDA through the stiff stretch, the explicit
    ! method again after t = 2. The exact x1 = sin t: error bound 100 rtol. The explicit
    ! integrator alone stops with the stiffness message. The exact x1 = sin wt.
    subroutine switches_halfway_and_back(chk)
        type(checker), intent(inout) :: chk
        type(stiff_middle) :: p
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        character(len=:), allocatable :: events
        real(wp) :: x(2), err, t
        integer :: stat, k, to_ida, to_dopri5
        p%n = 2
        p%m = 1
        opts%rtol = 1.0e-6_wp
        opts%atol = 1.0e-6_wp
        call solver%init(p, 0.0_wp, [0.0_wp, 0.0_wp], opts, stat)
        err = 0.0_wp
        do k = 1, 120
            if (stat /= regdae_success) exit
            t = 0.05_wp*k
            call solver%advance(t, x, stat=stat)
            err = max(err, abs(x(1) - sin(omega*t)), abs(x(2) - t))
        end do
        st = solver%statistics()
        events = solver%events()
        call chk%equal(stat, regdae_success, 'integrator=auto reaches t = 6')
        call chk%true(st%switches >= 2, 'it switches at least twice')
        to_ida = index(events, 'dopri5 -> ida')
        to_dopri5 = index(events, 'ida -> dopri5')
        call chk%true(to_ida > 0 .and. to_dopri5 > to_ida, 'to IDA first, then back to the explicit method')
        call chk%true(err <= 1.0e-4_wp, 'x = (sin wt, t) within 100 rtol')
        write (*, '(a,i0,a,es10.2)') '    switches: ', st%switches, ', max error: ', err
        call solver%destroy()
        opts%integrator = integrator_dopri5
        call solver%init(p, 0.0_wp, [0.0_wp, 0.0_wp], opts, stat)
        do k = 1, 60
            if (stat /= regdae_success) exit
            call solver%advance(0.05_wp*k, x, stat=stat)
        end do
        call chk%equal(stat, regdae_err_integration, 'integrator=dopri5 alone stops')
        call chk%true(index(solver%message(), 'stiff') > 0, 'because the system is stiff there')
        call solver%destroy()
    end subroutine switches_halfway_and_back

    ! The stiff chain of 6 links (joints of mass 1e-2 on vertical springs 1e4 and
    ! dashpots 10: eigenvalues near -500 +- 866i; 24 states, above radau_structured_max_n)
    ! on [0, 0.2], all defaults but rtol = atol = 1e-7: the explicit method starts, its
    ! stiffness test fires, and IDA takes over on the augmented formulation (the chain
    ! declares its structure); against the same chain by IDA on the augmented formulation
    ! from t0 at rtol = atol = 1e-11 (eps 1e-14): the positions at t = 0.01, ..., 0.2 (the
    ! transient: after it the chain rests on its springs) within 100 rtol (both runs solve
    ! the regularized problem, whose regularization error is below the tolerance here:
    ! sigma_min(GB) = 5.8, far from any singular configuration). The first outputs come
    ! before the switch (near t = 0.03): it happens in the middle of the run.
    subroutine stiff_chain_switches_to_augmented(chk)
        type(checker), intent(inout) :: chk
        call stiff_chain_against_reference(chk, 6, 1.0e-7_wp, 1.0e-2_wp, 1.0e4_wp, 10.0_wp, &
                                           'dopri5 -> ida, augmented formulation')
    end subroutine stiff_chain_switches_to_augmented

    ! The same chain at rtol 1e-4: the step that accuracy allows at t0 (7.3e-3) exceeds
    ! stiff_start_factor = 7 times the explicit method's stable step: IDA on the augmented
    ! formulation from t0, no explicit step.
    subroutine stiff_chain_starts_augmented(chk)
        type(checker), intent(inout) :: chk
        call stiff_chain_against_reference(chk, 6, 1.0e-4_wp, 1.0e-2_wp, 1.0e4_wp, 10.0_wp, &
                                           'ida from the start, augmented formulation')
    end subroutine stiff_chain_starts_augmented

    ! A lightly damped stiff chain at rtol 1e-4 (mass 1.2e-2, stiffness 8.5e3, damping 0.16:
    ! damping ratio 0.008 at 840 rad/s): the first test says stiff at t0 (the accurate step 25
    ! times the stable one), but the spring mode is lightly damped and not resolved by the
    ! accurate step: the explicit start stays (from t0 on IDA it cost 2.9x the instructions),
    ! and the stiffness test switches later: 6 links to IDA on the augmented formulation, 4
    ! links (16 states, at most radau_structured_max_n) to Radau on the eliminated one.
    subroutine light_chain_keeps_explicit_start(chk)
        type(checker), intent(inout) :: chk
        call stiff_chain_against_reference(chk, 6, 1.0e-4_wp, 1.2e-2_wp, 8.5e3_wp, 0.16_wp, &
                                           'dopri5 -> ida, augmented formulation')
        call stiff_chain_against_reference(chk, 4, 1.0e-4_wp, 1.2e-2_wp, 8.5e3_wp, 0.16_wp, 'dopri5 -> radau')
    end subroutine light_chain_keeps_explicit_start

    ! The stiff chain of 4 links (16 states, at most radau_structured_max_n) at rtol 1e-7: the
    ! accurate step at t0 (2.9e-3) is 3.2 times the explicit method's stable step, beyond
    ! stiff_start_factor_radau = 1 (not beyond the 7 for IDA): Radau IIA on the eliminated
    ! formulation from t0, no explicit step.
    subroutine small_stiff_chain_starts_radau(chk)
        type(checker), intent(inout) :: chk
        call stiff_chain_against_reference(chk, 4, 1.0e-7_wp, 1.0e-2_wp, 1.0e4_wp, 10.0_wp, 'radau from the start')
    end subroutine small_stiff_chain_starts_radau

    ! The same chain and rtol on [0, 0.2]: the defaults (Radau from t0) give integrator=radau's
    ! run bit for bit, with its statistics (the start test's Jacobian, which Radau takes as its
    ! first, is the one it would compute; the explicit method is not set up).
    subroutine radau_start_is_integrator_radau(chk)
        type(checker), intent(inout) :: chk
        integer, parameter :: links = 4, nout = 20
        type(chain) :: p
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(solver_stats) :: st(2)
        real(wp) :: q0(2*links), v0(2*links), q(2*links, nout, 2), y(links)
        integer :: stat(2), run, k
        p = new_chain(links, .false., 9.81_wp)
        p%joint_mass = 1.0e-2_wp
        p%stiffness = 1.0e4_wp
        p%damping = 10.0_wp
        call chain_start(p, q0, v0)
        do run = 1, 2
            opts = solver_options()
            opts%rtol = 1.0e-7_wp
            opts%atol = 1.0e-7_wp
            if (run == 2) opts%integrator = integrator_radau
            call solver%init(p, 0.0_wp, q0, v0, opts, stat(run))
            do k = 1, nout
                if (stat(run) /= regdae_success) exit
                call solver%advance(0.01_wp*k, q(:, k, run), y, stat(run))
            end do
            st(run) = solver%statistics()
            call solver%destroy()
        end do
        call chk%true(all(stat == regdae_success), 'both runs reach t = 0.2')
        call chk%true(st(1)%switches == 1 .and. st(2)%switches == 0, 'auto: one switch, to Radau at t0')
        call chk%true(all(q(:, :, 1) == q(:, :, 2)), 'the same positions, bit for bit')
        call chk%true(st(1)%res_evals == st(2)%res_evals .and. st(1)%jac_evals == st(2)%jac_evals .and. &
                      st(1)%steps == st(2)%steps, 'the same steps, evaluations of F and Jacobians')
    end subroutine radau_start_is_integrator_radau

    ! The chain of `links` links (joint mass, spring stiffness, damping) with the defaults at
    ! rtol = atol = tol against formulation=augmented at 1e-11 (eps 1e-14) on [0, 0.2]: one
    ! switch, the event `what`, positions within 100 tol.
    subroutine stiff_chain_against_reference(chk, links, tol, joint_mass, stiffness, damping, what)
        type(checker), intent(inout) :: chk
        integer, intent(in) :: links
        real(wp), intent(in) :: tol, joint_mass, stiffness, damping
        character(len=*), intent(in) :: what
        integer, parameter :: nout = 20
        type(chain) :: p
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        character(len=:), allocatable :: events
        real(wp) :: q0(2*links), v0(2*links), q(2*links, nout, 2), y(links), err
        integer :: stat(2), run, k
        p = new_chain(links, .false., 9.81_wp)
        p%joint_mass = joint_mass
        p%stiffness = stiffness
        p%damping = damping
        call chain_start(p, q0, v0)
        do run = 1, 2
            opts = solver_options()
            if (run == 1) then
                opts%rtol = tol
                opts%atol = tol
            else
                opts%rtol = 1.0e-11_wp
                opts%atol = 1.0e-11_wp
                opts%eps = 1.0e-14_wp
                opts%formulation = formulation_augmented
            end if
            call solver%init(p, 0.0_wp, q0, v0, opts, stat(run))
            do k = 1, nout
                if (stat(run) /= regdae_success) exit
                call solver%advance(0.01_wp*k, q(:, k, run), y, stat(run))
            end do
            if (stat(run) /= regdae_success) write (*, '(a)') '    '//solver%message()
            if (run == 1) then
                st = solver%statistics()
                events = solver%events()
            end if
            call solver%destroy()
        end do
        call chk%equal(stat(1), regdae_success, 'defaults reach t = 0.2')
        call chk%equal(stat(2), regdae_success, 'the reference reaches t = 0.2')
        call chk%true(st%switches == 1 .and. index(events, what) > 0, 'one switch: '//what)
        err = maxval(abs(q(:, :, 1) - q(:, :, 2)))
        call chk%true(err <= 100.0_wp*tol, 'positions within 100 rtol of the reference')
        write (*, '(a,i0,a,es10.2)') '    ', links, ' links, max |q - q_ref| at the outputs: ', err
    end subroutine stiff_chain_against_reference

    ! The slider crank from th1 = 1e-2 (near the singular configuration 0, pi) at
    ! w1 = 0.5, with the explicit integrator, weights gamma1 = 20, gamma0 = 200 and
    ! eps = 1e-14, rtol = 1e-4: with the checks off and no pass check the run ends
    ! with status ok off the physical branch (max |th1 + th2 - pi| > 0.1: measured
    ! 0.68); with the checks on it stops with a branch or work alarm, or stays on the
    ! branch (measured: the pass check's level at rtol/10 keeps it there, 6e-5).
    subroutine explicit_off_branch_fails(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        real(wp) :: dev
        integer :: stat
        opts%integrator = integrator_dopri5
        opts%gamma1 = 20.0_wp
        opts%gamma0 = 200.0_wp
        opts%eps = 1.0e-14_wp
        opts%rtol = 1.0e-4_wp
        opts%atol = 1.0e-4_wp
        call run_crank(opts, stat, dev)
        ! (the branch check, or the work-energy check: with the pass check, an alarm inside a
        ! pass is left to it, and the run that goes wrong is caught by the next check outside;
        ! or the pass check's finer level keeps the run on the branch: never ok off it)
        call chk%true(stat == regdae_err_branch .or. stat == regdae_err_work .or. (stat >= 0 .and. dev <= 0.1_wp), &
                      'the explicit run stops with a status, or stays on the branch')
        write (*, '(a,i5,es10.2)') '    every check on: status, max |th1 + th2 - pi|: ', stat, dev
        opts%jump_tol = 0.0_wp
        opts%work_tol = 0.0_wp
        opts%drift_tol = 0.0_wp
        call run_crank(opts, stat, dev)
        call chk%true(stat /= regdae_success .or. dev <= 0.1_wp, 'the pass check alone: on the branch, or a warning')
        write (*, '(a,i4,es10.2)') '    the pass check alone: status, max |th1 + th2 - pi|: ', stat, dev
        opts%pass_check = .false.
        call run_crank(opts, stat, dev)
        call chk%true(stat == regdae_success .and. dev > 0.1_wp, 'without any check it ends ok, off the branch')
        write (*, '(a,es10.2)') '    without the checks, max |th1 + th2 - pi|: ', dev
    contains
        subroutine run_crank(opts, stat, dev)
            type(solver_options), intent(in) :: opts
            integer, intent(out) :: stat
            real(wp), intent(out) :: dev
            type(regdae_solver) :: solver
            real(wp) :: th(2)
            integer :: k
            dev = 0.0_wp
            call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [1.0e-2_wp, pi - 1.0e-2_wp], [0.5_wp, -0.5_wp], opts, stat)
            do k = 1, 500
                if (stat /= regdae_success) exit
                call solver%advance(0.02_wp*k, th, stat=stat)
                dev = max(dev, abs(modulo(th(1) + th(2), 2*pi) - pi))
            end do
            call solver%destroy()
        end subroutine run_crank
    end subroutine explicit_off_branch_fails

    ! --- the growing pendulum ---

    pure real(wp) function string_length(t)
        real(wp), intent(in) :: t
        string_length = 1.0_wp + 0.2_wp*sin(2.0_wp*t)
    end function string_length

    subroutine growing_mass(self, t, q, mass, stat)
        class(growing_pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        mass = reshape([1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 2])
    end subroutine growing_mass

    subroutine growing_forces(self, t, q, qd, f, stat)
        class(growing_pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        f = [0.0_wp, -9.81_wp]
    end subroutine growing_forces

    subroutine growing_g(self, t, x, val, stat)
        class(growing_pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = x(1)**2 + x(2)**2 - string_length(t)**2
    end subroutine growing_g

    subroutine growing_gx(self, t, x, a, stat)
        class(growing_pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, :) = 2.0_wp*x
    end subroutine growing_gx

    subroutine growing_gt(self, t, x, val, stat)
        class(growing_pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = -2.0_wp*string_length(t)*0.4_wp*cos(2.0_wp*t)
        if (self%forget_gt) val(1) = 0.0_wp
    end subroutine growing_gt

    ! --- stiff_middle ---

    pure real(wp) function middle_lambda(t)
        real(wp), intent(in) :: t
        middle_lambda = 1.0_wp + 1.0e5_wp*0.5_wp*(tanh(20.0_wp*(t - 1.0_wp)) - tanh(20.0_wp*(t - 2.0_wp)))
    end function middle_lambda

    subroutine middle_rhs(self, t, x, v, stat)
        class(stiff_middle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = -middle_lambda(t)*(x(1) - sin(omega*t)) + omega*cos(omega*t)
        v(2) = 1.0_wp
    end subroutine middle_rhs

    subroutine middle_b(self, t, x, a, stat)
        class(stiff_middle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(:, 1) = [0.0_wp, 1.0_wp]
    end subroutine middle_b

    subroutine middle_g(self, t, x, v, stat)
        class(stiff_middle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = x(2) - t
    end subroutine middle_g

    subroutine middle_gx(self, t, x, a, stat)
        class(stiff_middle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, :) = [0.0_wp, 1.0_wp]
    end subroutine middle_gx

    subroutine middle_gt(self, t, x, v, stat)
        class(stiff_middle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = -1.0_wp
    end subroutine middle_gt

end module test_defaults
