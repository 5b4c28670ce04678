!> Driver: a singular mass matrix (paper, section 4.3, eq. 4.11): a unit mass on a
!! unit rod whose pivot rides on a massless carrier s (M = diag(1, 1, 0)), solved
!! through (M^T M + mu I) q'' = M^T f + M^T G^T lambda, against the model in which
!! the carrier is eliminated by hand (the pendulum; its angle ODE by CVODE at 1e-13).
!!
!! Usage: singular_mass [key=value ...]
!!   mass_damping (mu, default here 1e-8; 0 makes regdae require M positive definite)
!!   carrier=fixed|follower (fixed: s = 0; follower: s = px/2, a massless coordinate that must
!!   accelerate, which (4.11) cannot do)   phi0 (pi/2) tf (5) nout (500), and the solver options
!! Output: '#' lines, the table 't px py s lambda1 lambda2 err_pos', and the last line
!!   summary method=... status=ok|warning|failed t_end=... max_err=... max_abs_g=... steps=... res_evals=...
!!           jac_evals=... err_test_fails=... conv_fails=... seconds=...
!! (max_err: max position error of the mass against the hand-eliminated model, the pendulum, meaningful
!! for carrier=fixed; max_abs_g: largest constraint violation; status=warning: an advance returned a
!! warning, x valid but the tolerance maybe not met, the run goes on and a '# warning:' line says which.)
!! Exit status: 0 ok or warning, 1 failure, 2 bad arguments.
!! With carrier=follower the run starts consistently (px = 2 sin phi0, s = px/2, at rest) but (4.11) gives s'' = 0: the
!! driver reports the constraint violation it leads to.
program singular_mass_driver
    use regdae
    use massless_problem, only: massless_carrier, new_massless_carrier
    use pendulum_problem, only: pendulum_angle
    use reference_ode, only: integrate_reference
    use driver_support, only: resolved_line, event_lines, &
                              format_int, common_argument, stats_fields, run_status, argument, split_key_value, num, &
                              stopwatch, warning_log, die_usage, read_number
    implicit none
    character(len=*), parameter :: prog = 'singular_mass'
    real(wp), parameter :: t0 = 0.0_wp, gravity = 9.81_wp
    type(solver_options) :: opts
    type(regdae_solver) :: solver
    type(solver_stats) :: st
    type(pendulum_angle) :: angle
    character(len=:), allocatable :: key, value, status_text
    integer :: i, k, nout, stat, rstat
    logical :: ok, run_failed, follower
    real(wp) :: phi0, tf, q(3), lam(2), t, e, max_err, max_g, seconds, output_seconds, pref(2)
    real(wp), allocatable :: times(:), ref(:, :)
    type(stopwatch) :: solve_clock, output_clock   ! the solve (init, advances); the table
    type(warning_log) :: warnings                  ! the advances' warnings

    phi0 = acos(0.0_wp)
    tf = 5.0_wp
    nout = 500
    follower = .false.
    opts%stop_at_output = .true.
    opts%mass_damping = 1.0e-8_wp
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        select case (key)
        case ('phi0'); call read_number(prog, key, value, phi0)
        case ('tf'); call read_number(prog, key, value, tf)
        case ('carrier')
            if (value /= 'fixed' .and. value /= 'follower') &
                call die_usage(prog, 'bad value "'//value//'" for carrier (fixed|follower)')
            follower = (value == 'follower')
        case default; call common_argument(prog, key, value, opts, nout)
        end select
    end do
    if (.not. (tf > t0)) call die_usage(prog, 'tf must be > 0')
    times = [(t0 + (tf - t0)*real(k, wp)/real(nout, wp), k=0, nout)]
    allocate (ref(2, 0:nout))
    angle%gravity = gravity
    call integrate_reference(angle, t0, [phi0, 0.0_wp], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
    if (rstat /= 0) call die_usage(prog, 'the reference integration (CVODE) failed, flag '//format_int(rstat))

    write (*, '(a)') '# regdae singular_mass: M = diag(1, 1, 0), q = (px, py, s), g1 = (px - s)^2 + py^2 - 1, '// &
        trim(merge('g2 = s - px/2', 'g2 = s       ', follower))
    write (*, '(a)') '# method='//method_name(opts%method)//' index='//format_int(opts%index)// &
        ' mass_damping='//num(opts%mass_damping)//' eps='//num(opts%eps)//' rtol='//num(opts%rtol)// &
        ' atol='//num(opts%atol)
    write (*, '(a)') '# reference: the hand-eliminated model (carrier at the origin): the pendulum, by CVODE'
    write (*, '(a1,a23,6a24)') '#', 't', 'px', 'py', 's', 'lambda1', 'lambda2', 'err_pos'
    max_err = 0.0_wp
    max_g = 0.0_wp
    call solve_clock%start()
    call solver%init(new_massless_carrier(gravity, follower), t0, &
                     [merge(2.0_wp, 1.0_wp, follower)*sin(phi0), -cos(phi0), merge(sin(phi0), 0.0_wp, follower)], &
                     [0.0_wp, 0.0_wp, 0.0_wp], opts, stat)
    call solve_clock%stop()
    if (stat == regdae_success) then
        write (*, '(a)') resolved_line(solver)
        do k = 0, nout
            t = times(k + 1)
            call solve_clock%start()
            call solver%advance(t, q, lam, stat)
            call solve_clock%stop()
            if (stat < 0) exit
            call warnings%note(solver, stat, t)
            pref = [sin(ref(1, k)), -cos(ref(1, k))]
            e = maxval(abs(q(1:2) - pref))
            max_err = max(max_err, e)
            max_g = max(max_g, abs((q(1) - q(3))**2 + q(2)**2 - 1.0_wp), &
                        abs(q(3) - merge(0.5_wp*q(1), 0.0_wp, follower)))
            call output_clock%start()
            write (*, '(7es24.15e3)') t, q, lam, e
            call output_clock%stop()
        end do
        if (stat > 0) stat = regdae_success
    end if
    seconds = solve_clock%seconds()
    output_seconds = output_clock%seconds()
    st = solver%statistics()
    status_text = run_status(solver, stat, warnings)
    if (status_text /= 'failed' .and. follower) then
        write (*, '(a)') '# warning: carrier=follower is outside what (4.11) can do: it gives q'''' in the range of M^T, '// &
            'so the massless carrier keeps its velocity (s'''' = 0) and the constraints hold the mass near its start '// &
            'with large multipliers; this is not the motion of the mechanism'
        status_text = 'failed'
    end if
    write (*, '(a)', advance='no') event_lines(solver)
    write (*, '(a)') 'summary method='//method_name(opts%method)//' status='//status_text//' t_end='//num(st%t)// &
        ' max_err='//num(max_err)//' max_abs_g='//num(max_g)//stats_fields(st, seconds, output_seconds)
    call solver%destroy()
    run_failed = (status_text == 'failed')
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (times, ref, status_text)
    if (run_failed) stop 1
end program singular_mass_driver
