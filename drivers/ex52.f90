!> Driver for Example 5.2 of Petzold, Ren & Maly (1997): the slider crank
!! (equations 5.2-5.4), started at rest (by default) from th1 = th2 = pi/2, so
!! that it passes the singular configuration (0, pi) every half swing.
!!
!! Usage: ex52 [key=value ...]
!!   method=baumgarte|trust_region|direct (trust_region)   index=2|3 (3)
!!   gamma=1e3 (index 2)   gamma0=2e6 gamma1=2e3 (index 3)   eps=1e-6   rtol=1e-5 atol=1e-5
!!   tf=10 nout=1000 th1=pi/2 w1=0 (th2 = pi - th1, w2 = -w1: the physical branch)
!!   excluded=y|vy (index 3: what leaves the error test)   curvature=no|yes (index 3)
!!   branch_tol=0.1 (a larger |th1 + th2 - pi| flags the run as off the physical branch)
!!   and formulation, lsq, exclusion, stop_at_output (yes), max_steps, h_init, h_max, ic_tol,
!!   singular_threshold (0.05: sigma_min(GB) below it at an output time counts as singular)
!!   events=no|yes: three event functions, logged and continued (th1 through 0, the singular
!!   passes; th1 through pi/4; th1' = 0, the turning points th1 = +-pi/2), their times against the
!!   reduced ODE's (CVODE at 1e-12 and Newton's method): summary fields roots=... (found)
!!   roots_ref=... (in the reference) max_root_err=... (the largest time error of a found root)
!!   root_err_th1=... root_err_pi4=... root_err_w1=... (the same per function)
!! The reference is the reduced one-degree-of-freedom ODE on the physical branch, integrated by
!! CVODE at rtol = atol = 1e-13.
!! Output: '#' lines, the table 't th1 th2 w1 w2 lambda g3 energy' (lambda of eq. 5.2), and the last line
!!   summary method=... index=... status=ok|warning|failed t_end=... max_err_th=... max_abs_g3=...
!!           max_energy_err=... max_branch_dev=... singular_passes=... steps=... res_evals=...
!!           jac_evals=... err_test_fails=... conv_fails=... seconds=...
!!   and with error_estimate=yes the estimate against the true theta error at the outputs t > 0
!!   (true = max_i |th_i - th_i,ref|, est = max_i |e_i| from solver%error_estimate, both floored
!!   at rtol/100): est_outputs=... est_bounds=... (outputs with est >= true/10) est_within10=...
!!   (true/10 <= est <= 10 true) est_ratio_min=... est_ratio_max=... (of est/true)
!! Exit status: 0 ok, 1 solver failure or off the physical branch, 2 bad arguments.
program ex52_driver
    use regdae
    use slider_crank_problem, only: slider_crank, slider_crank_reduced, new_slider_crank
    use reference_ode, only: integrate_reference
    use crank_roots, only: crank_events, crank_reference_roots, root_errors
    use driver_support, only: resolved_line, event_lines, &
                              format_int, common_argument, stats_fields, run_status, argument, split_key_value, num, &
                              stopwatch, warning_log, &
                              die_usage, read_number
    implicit none

    character(len=*), parameter :: prog = 'ex52'
    real(wp), parameter :: t0 = 0.0_wp, pi = acos(-1.0_wp), gravity = 9.8_wp
    type(solver_options) :: opts
    type(regdae_solver) :: solver
    type(solver_stats) :: st
    type(slider_crank) :: crank
    type(slider_crank_reduced) :: reduced
    character(len=:), allocatable :: key, value, status_text
    integer :: i, k, nout, stat, rstat
    logical :: ok, run_failed, off_branch, events
    type(crank_events) :: crank_ev
    real(wp) :: th1, w1, tf, branch_tol, th(2), w(2), lam(1), t, e0, e, seconds, output_seconds
    real(wp) :: max_err, max_g3, max_de, max_dev, dev, t_off, ref_drift
    real(wp) :: est(2), err_true, err_est, ratio_min, ratio_max   ! error_estimate=yes
    integer :: est_outputs, est_bounds, est_within
    real(wp), allocatable :: times(:), ref(:, :)
    type(stopwatch) :: solve_clock, output_clock   ! the solve (init, advances); the table
    type(warning_log) :: warnings                  ! the advances' warnings

    th1 = pi/2
    w1 = 0.0_wp
    tf = 10.0_wp
    nout = 1000
    branch_tol = 0.1_wp
    events = .false.
    opts%stop_at_output = .true.
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        select case (key)
        case ('th1'); call read_number(prog, key, value, th1)
        case ('w1'); call read_number(prog, key, value, w1)
        case ('tf'); call read_number(prog, key, value, tf)
        case ('branch_tol'); call read_number(prog, key, value, branch_tol)
        case ('events')
            if (value /= 'yes' .and. value /= 'no') call die_usage(prog, 'events must be yes or no')
            events = (value == 'yes')
        case default
            call common_argument(prog, key, value, opts, nout)
        end select
    end do
    if (.not. (tf > t0)) call die_usage(prog, 'tf must be > 0')

    crank = new_slider_crank(gravity)
    reduced%gravity = gravity
    times = [(t0 + (tf - t0)*real(k, wp)/real(nout, wp), k=0, nout)]
    allocate (ref(2, 0:nout))
    call integrate_reference(reduced, t0, [th1, w1], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
    if (rstat /= 0) call die_usage(prog, 'the reference integration (CVODE) failed, flag '//format_int(rstat))
    ref_drift = maxval(abs(reduced_energy(ref(1, :), ref(2, :)) - reduced_energy(ref(1, 0), ref(2, 0))))

    write (*, '(a)') '# regdae ex52: the slider crank, Example 5.2 of Petzold, Ren & Maly (1997)'
    write (*, '(a)') '#   M(th) th'''' + h(th, th'') + G^T lambda = 0, g3 = -cos th1 - cos th2 = 0 (index 3); '// &
        'index 2: G th'' = 0'
    write (*, '(a)') '# method='//method_name(opts%method)//' index='//format_int(opts%index)// &
        ' formulation='//formulation_name(opts%formulation)//' lsq='//lsq_name(opts%lsq)// &
        ' excluded='//excluded_name(opts%excluded)//' exclusion='//exclusion_name(opts%exclusion)// &
        ' curvature='//trim(merge('yes', 'no ', opts%curvature))
    write (*, '(a)') '# gamma='//num(opts%gamma)//' gamma0='//num(opts%gamma0)//' gamma1='//num(opts%gamma1)// &
        ' eps='//num(opts%eps)//' rtol='//num(opts%rtol)//' atol='//num(opts%atol)//' th1='//num(th1)// &
        ' w1='//num(w1)//' tf='//num(tf)//' nout='//format_int(nout)
    write (*, '(a)') '# reference: reduced ODE on th2 = pi - th1 by CVODE (Adams, rtol = atol = 1e-13); '// &
        'its energy drift '//num(ref_drift)
    write (*, '(a1,a23,7a24)') '#', 't', 'th1', 'th2', 'w1', 'w2', 'lambda', 'g3', 'energy'

    max_err = 0.0_wp
    max_g3 = 0.0_wp
    max_de = 0.0_wp
    max_dev = 0.0_wp
    est_outputs = 0
    est_bounds = 0
    est_within = 0
    ratio_min = huge(1.0_wp)
    ratio_max = 0.0_wp
    off_branch = .false.
    t_off = t0
    e0 = crank%energy([th1, pi - th1], [w1, -w1])
    call solve_clock%start()
    call solver%init(crank, t0, [th1, pi - th1], [w1, -w1], opts, stat)
    if (events .and. stat == regdae_success) call solver%set_events(crank_ev, 3, stat, stop=[.false., .false., .false.])
    call solve_clock%stop()
    if (stat == regdae_success) then
        write (*, '(a)') resolved_line(solver)
        do k = 0, nout
            t = times(k + 1)
            call solve_clock%start()
            call solver%advance(t, th, lam, stat, w)
            call solve_clock%stop()
            if (stat < 0) exit
            call warnings%note(solver, stat, t)
            ! lambda of (5.2) is minus the mechanical multiplier (M q'' = f + G^T lambda_m).
            lam = -lam
            e = crank%energy(th, w)
            max_err = max(max_err, abs(th(1) - ref(1, k)), abs(th(2) - (pi - ref(1, k))))
            max_g3 = max(max_g3, abs(cos(th(1)) + cos(th(2))))
            max_de = max(max_de, abs(e - e0))
            dev = abs(modulo(th(1) + th(2) - pi + pi, 2*pi) - pi)
            if (dev > branch_tol .and. .not. off_branch) then
                off_branch = .true.
                t_off = t
            end if
            max_dev = max(max_dev, dev)
            if (opts%error_estimate .and. k > 0) then
                if (solver%error_estimate(est)) then
                    err_true = max(abs(th(1) - ref(1, k)), abs(th(2) - (pi - ref(1, k))), 0.01_wp*opts%rtol)
                    err_est = max(maxval(abs(est)), 0.01_wp*opts%rtol)
                    est_outputs = est_outputs + 1
                    if (err_est >= 0.1_wp*err_true) est_bounds = est_bounds + 1
                    if (err_est >= 0.1_wp*err_true .and. err_est <= 10.0_wp*err_true) est_within = est_within + 1
                    ratio_min = min(ratio_min, err_est/err_true)
                    ratio_max = max(ratio_max, err_est/err_true)
                end if
            end if
            call output_clock%start()
            write (*, '(8es24.15e3)') t, th, w, lam, -cos(th(1)) - cos(th(2)), e
            call output_clock%stop()
        end do
        if (stat > 0) stat = regdae_success
    end if
    seconds = solve_clock%seconds()
    output_seconds = output_clock%seconds()
    st = solver%statistics()
    status_text = run_status(solver, stat, warnings)
    if (status_text /= 'failed' .and. off_branch) then
        write (*, '(a)') '# warning: left the physical branch th2 = pi - th1 at t = '//num(t_off)// &
            ' (max |th1 + th2 - pi| = '//num(max_dev)//' > branch_tol = '//num(branch_tol)//')'
        status_text = 'failed'
    end if
    call print_singular_intervals(solver%singular_intervals())
    write (*, '(a)', advance='no') event_lines(solver)
    write (*, '(a)') 'summary method='//method_name(opts%method)//' index='//format_int(opts%index)// &
        ' status='//status_text//' t_end='//num(st%t)//' max_err_th='//num(max_err)// &
        ' max_abs_g3='//num(max_g3)//' max_energy_err='//num(max_de)//' max_branch_dev='//num(max_dev)// &
        ' singular_passes='//format_int(st%singular_passes)//stats_fields(st, seconds, output_seconds)// &
        estimate_fields()//root_fields()
    call solver%destroy()
    run_failed = (status_text == 'failed')
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (times, ref, status_text)
    if (run_failed) stop 1

contains

    ! The summary's error-estimate fields (error_estimate=yes only).
    function estimate_fields() result(text)
        character(len=:), allocatable :: text
        text = ''
        if (.not. opts%error_estimate) return
        if (est_outputs == 0) ratio_min = 0.0_wp
        text = ' est_outputs='//format_int(est_outputs)//' est_bounds='//format_int(est_bounds)// &
               ' est_within10='//format_int(est_within)//' est_ratio_min='//num(ratio_min)// &
               ' est_ratio_max='//num(ratio_max)
    end function estimate_fields

    ! The summary's event fields (events=yes only): the roots logged (their lines
    ! '# event: t = T: event K ...') against the reduced ODE's.
    function root_fields() result(text)
        character(len=:), allocatable :: text
        real(wp), allocatable :: rref(:, :)
        real(wp) :: worst(3)
        integer :: rs
        text = ''
        if (.not. events) return
        call crank_reference_roots(gravity, th1, st%t, rref, rs)
        worst = root_errors(solver%events(), rref)
        text = ' roots='//format_int(st%roots_found)//' roots_ref='//format_int(size(rref, 2))// &
               ' max_root_err='//num(maxval(worst))//' root_err_th1='//num(worst(1))//' root_err_pi4='// &
               num(worst(2))//' root_err_w1='//num(worst(3))
        if (rs /= 0) text = text//' reference_failed'
    end function root_fields

    elemental real(wp) function reduced_energy(th, w)
        real(wp), intent(in) :: th, w
        reduced_energy = 0.5_wp*w**2*(1.0_wp + 4.0_wp*cos(th)**2) - gravity*cos(th)
    end function reduced_energy

    subroutine print_singular_intervals(intervals)
        real(wp), intent(in) :: intervals(:, :)
        integer :: j
        write (*, '(a)') '# singular passes (sigma_min(GB) < '//num(opts%singular_threshold)//' at the outputs): '// &
            format_int(size(intervals, 2))
        do j = 1, size(intervals, 2)
            write (*, '(a)') '#   t in ['//num(intervals(1, j))//', '//num(intervals(2, j))//']'
        end do
    end subroutine print_singular_intervals

end program ex52_driver
