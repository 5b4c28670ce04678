!> Driver: redundant constraints kept (paper, section 1; Theorem 3.1 in the nonlinear
!! setting): the slider crank of Example 5.2 with its constraint given twice, solved
!! without removing anything, against the reduced ODE (the reference of ex52) and
!! against the same run of the single-constraint model.
!!
!! Usage: redundant [key=value ...]
!!   method (trust_region), index (3), eps (1e-6), formulation (eliminated), lsq (auto), rtol, atol (1e-5),
!!   tf (10), nout (1000), th1 (pi/2), w1 (0), and the other solver options (stop_at_output: yes)
!! Output: '#' lines, the table 't th1 th2 lambda1 lambda2 th1_single', and the last line
!!   summary method=... status=ok|warning|failed t_end=... max_err=... max_diff_single=... max_branch_dev=...
!!           steps=... res_evals=... jac_evals=... err_test_fails=... conv_fails=... seconds=...
!! (max_err: max theta error against the reduced ODE; max_diff_single: against the single-constraint
!! model; status=warning: an advance returned a warning, x valid but the tolerance maybe not met, the
!! run goes on and a '# warning:' line says which. A warning of the single-constraint run is reported
!! on a '#' line and that run goes on too; only its failure ends the comparison.)
!! Exit status: 0 ok or warning, 1 failure or off the physical branch (> 0.1), 2 bad arguments.
program redundant_driver
    use regdae
    use slider_crank_problem, only: slider_crank_reduced, new_slider_crank, new_redundant_slider_crank
    use reference_ode, only: integrate_reference
    use driver_support, only: resolved_line, event_lines, &
                              format_int, common_argument, stats_fields, run_status, argument, split_key_value, num, &
                              stopwatch, warning_log, die_usage, read_number
    implicit none
    character(len=*), parameter :: prog = 'redundant'
    real(wp), parameter :: t0 = 0.0_wp, pi = acos(-1.0_wp), gravity = 9.8_wp
    type(solver_options) :: opts
    type(regdae_solver) :: solver, single
    type(solver_stats) :: st
    type(slider_crank_reduced) :: reduced
    character(len=:), allocatable :: key, value, status_text
    integer :: i, k, nout, stat, stat1, rstat
    logical :: ok, run_failed
    real(wp) :: th1, w1, tf, th(2), lam(2), th_s(2), lam_s(1), t, max_err, max_diff, max_dev, seconds, output_seconds
    real(wp), allocatable :: times(:), ref(:, :)
    type(stopwatch) :: solve_clock, output_clock   ! the solve (init, advances); the table
    type(warning_log) :: warnings, single_warnings ! the advances' warnings (this run, the comparison run)

    th1 = pi/2
    w1 = 0.0_wp
    tf = 10.0_wp
    nout = 1000
    opts%stop_at_output = .true.
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        select case (key)
        case ('th1'); call read_number(prog, key, value, th1)
        case ('w1'); call read_number(prog, key, value, w1)
        case ('tf'); call read_number(prog, key, value, tf)
        case default; call common_argument(prog, key, value, opts, nout)
        end select
    end do
    if (.not. (tf > t0)) call die_usage(prog, 'tf must be > 0')
    times = [(t0 + (tf - t0)*real(k, wp)/real(nout, wp), k=0, nout)]
    allocate (ref(2, 0:nout))
    reduced%gravity = gravity
    call integrate_reference(reduced, t0, [th1, w1], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
    if (rstat /= 0) call die_usage(prog, 'the reference integration (CVODE) failed, flag '//format_int(rstat))

    write (*, '(a)') '# regdae redundant: the slider crank with g3 = -cos th1 - cos th2 = 0 given twice (m = 2, '// &
        'GB of rank 1 for all t)'
    write (*, '(a)') '# method='//method_name(opts%method)//' index='//format_int(opts%index)// &
        ' formulation='//formulation_name(opts%formulation)//' lsq='//lsq_name(opts%lsq)//' eps='//num(opts%eps)// &
        ' rtol='//num(opts%rtol)//' atol='//num(opts%atol)
    max_err = 0.0_wp
    max_diff = 0.0_wp
    max_dev = 0.0_wp
    call solve_clock%start()
    call solver%init(new_redundant_slider_crank(gravity), t0, [th1, pi - th1], [w1, -w1], opts, stat)
    call solve_clock%stop()
    call single%init(new_slider_crank(gravity), t0, [th1, pi - th1], [w1, -w1], opts, stat1)
    if (stat == regdae_success) then
        write (*, '(a)') resolved_line(solver)
        write (*, '(a)') '# lsq resolved to '//lsq_name(solver%lsq_method())
        write (*, '(a1,a23,5a24)') '#', 't', 'th1', 'th2', 'lambda1', 'lambda2', 'th1_single'
        do k = 0, nout
            t = times(k + 1)
            call solve_clock%start()
            call solver%advance(t, th, lam, stat)
            call solve_clock%stop()
            if (stat < 0) exit
            call warnings%note(solver, stat, t)
            if (stat1 >= 0) then   ! the comparison run goes on after a warning too
                call single%advance(t, th_s, lam_s, stat1)
                call single_warnings%note(single, stat1, t)
            end if
            max_err = max(max_err, abs(th(1) - ref(1, k)), abs(th(2) - (pi - ref(1, k))))
            if (stat1 >= 0) max_diff = max(max_diff, maxval(abs(th - th_s)))
            max_dev = max(max_dev, abs(modulo(th(1) + th(2), 2*pi) - pi))
            call output_clock%start()
            write (*, '(6es24.15e3)') t, th, -lam, th_s(1)
            call output_clock%stop()
        end do
        if (stat > 0) stat = regdae_success
    end if
    seconds = solve_clock%seconds()
    output_seconds = output_clock%seconds()
    st = solver%statistics()
    status_text = run_status(solver, stat, warnings)
    if (status_text /= 'failed' .and. (max_dev > 0.1_wp)) then
        write (*, '(a)') '# warning: left the physical branch (max |th1 + th2 - pi| = '//num(max_dev)//')'
        status_text = 'failed'
    end if
    if (stat1 < 0) write (*, '(a)') '# the single-constraint comparison run failed: '//single%message()
    if (single_warnings%count > 0) write (*, '(a)') '# the single-constraint comparison run warned: '// &
        format_int(single_warnings%count)//' advance(s), the first at t = '//num(single_warnings%t_first)//': '// &
        single_warnings%first
    write (*, '(a)', advance='no') event_lines(solver)
    write (*, '(a)') 'summary method='//method_name(opts%method)//' status='//status_text//' t_end='//num(st%t)// &
        ' max_err='//num(max_err)//' max_diff_single='//num(max_diff)//' max_branch_dev='//num(max_dev)// &
        stats_fields(st, seconds, output_seconds)
    call solver%destroy()
    call single%destroy()
    run_failed = (status_text == 'failed')
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (times, ref, status_text)
    if (run_failed) stop 1
end program redundant_driver
