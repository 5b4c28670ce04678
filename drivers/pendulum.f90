!> Driver: the planar pendulum in Cartesian coordinates (index 3), where the
!! curvature term g_xx(v, v) = 2|v|^2 of d^2 g/dt^2 does not vanish; compares
!! regdae's solution with the angle ODE integrated by CVODE at rtol = 1e-13.
!!
!! Usage: pendulum [key=value ...]
!!   phi0=1.5707963267948966 w0=0 (initial angle from the downward vertical, angular velocity)
!!   tf=10 nout=1000 gravity=9.81, and the solver options (method, index, gamma, gamma0, gamma1,
!!   eps, rtol, atol, curvature, excluded, formulation, lsq, exclusion, stop_at_output (yes), ...)
!!   events=no|yes: three event functions, logged and continued: x1 (phi through 0, the bottom),
!!   x1 - sin(phi0/2) (phi through phi0/2) and v1 (the turning points; needs an amplitude below pi/2),
!!   their times against the angle ODE's (CVODE at 1e-12 and Newton's method): summary fields
!!   roots=... roots_ref=... max_root_err=... root_err_bottom=... root_err_half=... root_err_turn=...
!! Output: '#' lines, the table 't x1 x2 v1 v2 y err_pos g', and the last line
!!   summary method=... index=... curvature=... status=ok|warning|failed t_end=... max_err_pos=... max_abs_g=...
!!           steps=... res_evals=... jac_evals=... err_test_fails=... conv_fails=... seconds=...
!! (status=warning: an advance returned a warning, x valid but the tolerance maybe not met; the run
!! goes on and a '# warning:' line says which.)
!! Exit status: 0 ok or warning, 1 solver failure, 2 bad arguments.
program pendulum_driver
    use regdae
    use pendulum_problem, only: pendulum, pendulum_angle, new_pendulum
    use reference_ode, only: integrate_reference
    use crank_roots, only: pendulum_events, reduced_reference_roots, root_errors
    use driver_support, only: resolved_line, event_lines, &
                              format_int, common_argument, stats_fields, run_status, argument, split_key_value, num, &
                              stopwatch, warning_log, &
                              die_usage, read_number
    implicit none

    character(len=*), parameter :: prog = 'pendulum'
    real(wp), parameter :: t0 = 0.0_wp
    type(solver_options) :: opts
    type(regdae_solver) :: solver
    type(solver_stats) :: st
    type(pendulum) :: problem
    type(pendulum_angle) :: angle
    character(len=:), allocatable :: key, value, status_text
    integer :: i, k, nout, stat, rstat
    logical :: ok, run_failed, events
    type(pendulum_events) :: pendulum_ev
    real(wp) :: phi0, w0, tf, gravity, x(2), v(2), y(1), t, err, max_err, max_g, seconds, output_seconds
    real(wp), allocatable :: times(:), ref(:, :)
    type(stopwatch) :: solve_clock, output_clock   ! the solve (init, advances); the table
    type(warning_log) :: warnings                  ! the advances' warnings

    phi0 = acos(0.0_wp)
    w0 = 0.0_wp
    tf = 10.0_wp
    nout = 1000
    gravity = 9.81_wp
    opts%stop_at_output = .true.
    events = .false.
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        select case (key)
        case ('phi0'); call read_number(prog, key, value, phi0)
        case ('w0'); call read_number(prog, key, value, w0)
        case ('tf'); call read_number(prog, key, value, tf)
        case ('gravity'); call read_number(prog, key, value, gravity)
        case ('events')
            if (value /= 'yes' .and. value /= 'no') call die_usage(prog, 'events must be yes or no')
            events = (value == 'yes')
        case default
            call common_argument(prog, key, value, opts, nout)
        end select
    end do
    if (.not. (tf > t0)) call die_usage(prog, 'tf must be > 0')
    ! v1 = phi' cos(phi) has simple zeros at the turning points only while |phi| < pi/2: the energy
    ! below g, with a margin (at the amplitude pi/2 both factors vanish: a double zero)
    if (events .and. .not. (0.5_wp*w0**2 + gravity*(1.0_wp - cos(phi0)) < gravity*(1.0_wp - 1.0e-6_wp) &
                            .and. phi0 /= 0.0_wp)) &
        call die_usage(prog, 'events=yes needs a swing with amplitude below pi/2 (0.5 w0^2 + g (1 - cos phi0) < g), phi0 /= 0')
    pendulum_ev%c = 0.5_wp*phi0

    problem = new_pendulum(gravity)
    angle%gravity = gravity
    times = [(t0 + (tf - t0)*real(k, wp)/real(nout, wp), k=0, nout)]
    allocate (ref(2, 0:nout))
    call integrate_reference(angle, t0, [phi0, w0], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
    if (rstat /= 0) call die_usage(prog, 'the reference integration (CVODE) failed, flag '//format_int(rstat))

    write (*, '(a)') '# regdae pendulum: x'''' = (0, -g) - 2 x y, 0 = |x|^2 - 1 (index 3, Cartesian coordinates)'
    write (*, '(a)') '# reference: phi'''' = -g sin(phi) by CVODE (Adams, rtol = atol = 1e-13)'
    write (*, '(a)') '# method='//method_name(opts%method)//' index='//format_int(opts%index)// &
        ' formulation='//formulation_name(opts%formulation)//' curvature='//trim(merge('yes', 'no ', opts%curvature))// &
        ' excluded='//excluded_name(opts%excluded)//' exclusion='//exclusion_name(opts%exclusion)
    write (*, '(a)') '# gamma='//num(opts%gamma)//' gamma0='//num(opts%gamma0)//' gamma1='//num(opts%gamma1)// &
        ' eps='//num(opts%eps)//' rtol='//num(opts%rtol)//' atol='//num(opts%atol)//' phi0='//num(phi0)// &
        ' w0='//num(w0)//' tf='//num(tf)//' nout='//format_int(nout)
    write (*, '(a1,a23,7a24)') '#', 't', 'x1', 'x2', 'v1', 'v2', 'y', 'err_pos', 'g'

    max_err = 0.0_wp
    max_g = 0.0_wp
    call solve_clock%start()
    call solver%init(problem, t0, [sin(phi0), -cos(phi0)], w0*[cos(phi0), sin(phi0)], opts, stat)
    call solve_clock%stop()
    if (events .and. stat == regdae_success) call solver%set_events(pendulum_ev, 3, stat, stop=[.false., .false., .false.])
    if (stat == regdae_success) then
        write (*, '(a)') resolved_line(solver)
        do k = 0, nout
            t = times(k + 1)
            call solve_clock%start()
            call solver%advance(t, x, y, stat, v)
            call solve_clock%stop()
            if (stat < 0) exit
            call warnings%note(solver, stat, t)
            err = maxval(abs(x - [sin(ref(1, k)), -cos(ref(1, k))]))
            max_err = max(max_err, err)
            max_g = max(max_g, abs(x(1)**2 + x(2)**2 - 1.0_wp))
            call output_clock%start()
            write (*, '(8es24.15e3)') t, x, v, y, err, x(1)**2 + x(2)**2 - 1.0_wp
            call output_clock%stop()
        end do
        if (stat > 0) stat = regdae_success
    end if
    seconds = solve_clock%seconds()
    output_seconds = output_clock%seconds()
    st = solver%statistics()
    status_text = run_status(solver, stat, warnings)
    write (*, '(a)', advance='no') event_lines(solver)
    write (*, '(a)') 'summary method='//method_name(opts%method)//' index='//format_int(opts%index)// &
        ' curvature='//trim(merge('yes', 'no ', opts%curvature))//' status='//status_text// &
        ' t_end='//num(st%t)//' max_err_pos='//num(max_err)//' max_abs_g='//num(max_g)// &
        stats_fields(st, seconds, output_seconds)//root_fields()
    call solver%destroy()
    run_failed = (status_text == 'failed')
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (times, ref, status_text)
    if (run_failed) stop 1

contains

    ! The summary's event fields (events=yes only): the roots logged against the angle ODE's.
    function root_fields() result(text)
        character(len=:), allocatable :: text
        real(wp), allocatable :: rref(:, :)
        real(wp) :: worst(3)
        integer :: rs
        text = ''
        if (.not. events) return
        call reduced_reference_roots(angle, [phi0, w0], pendulum_ev%c, st%t, rref, rs)
        worst = root_errors(solver%events(), rref)
        text = ' roots='//format_int(st%roots_found)//' roots_ref='//format_int(size(rref, 2))// &
               ' max_root_err='//num(maxval(worst))//' root_err_bottom='//num(worst(1))//' root_err_half='// &
               num(worst(2))//' root_err_turn='//num(worst(3))
        if (rs /= 0) text = text//' reference_failed'
    end function root_fields
end program pendulum_driver
