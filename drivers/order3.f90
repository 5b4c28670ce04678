!> Driver: the order-3 (index-4) problem x''' = (1 - cos t) - t y, 0 = t (x - 1 - sin t),
!! t in [-1, 1], exact x = 1 + sin t, y = 1/t; singular at t = 0 (paper, section 4.4).
!!
!! Usage: order3 [key=value ...]
!!   method (trust_region), eps (1e-6), taylor_h (1e-2: weights 3!/(k! h^(3-k))), rtol, atol (1e-5),
!!   nout (200), and the other solver options (stop_at_output defaults to yes)
!! Output: '#' lines, the table 't x y x_exact y_exact', and the last line
!!   summary method=... status=ok|warning|failed t_end=... max_err=... steps=... res_evals=... jac_evals=...
!!           err_test_fails=... conv_fails=... seconds=...
!! (max_err: max |x - x_exact| over the output times; status=warning: an advance returned a warning,
!! x valid but the tolerance maybe not met, the run goes on and a '# warning:' line says which.)
!! Exit status: 0 ok or warning, 1 failure, 2 bad arguments.
program order3_driver
    use regdae
    use order3_problem, only: order3, new_order3, order3_exact
    use driver_support, only: resolved_line, event_lines, &
                              format_int, common_argument, stats_fields, run_status, argument, split_key_value, num, &
                              stopwatch, warning_log, die_usage
    implicit none
    character(len=*), parameter :: prog = 'order3'
    real(wp), parameter :: t0 = -1.0_wp, tf = 1.0_wp
    type(solver_options) :: opts
    type(regdae_solver) :: solver
    type(solver_stats) :: st
    character(len=:), allocatable :: key, value, status_text
    integer :: i, k, nout, stat
    logical :: ok, run_failed
    real(wp) :: xs0(1, 3), xe(1, 3), ye, x(1), y(1), t, max_err, seconds, output_seconds
    type(stopwatch) :: solve_clock, output_clock   ! the solve (init, advances); the table
    type(warning_log) :: warnings                  ! the advances' warnings

    nout = 200
    opts%stop_at_output = .true.
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        call common_argument(prog, key, value, opts, nout)
    end do
    write (*, '(a)') '# regdae order3: x''''''= (1 - cos t) - t y, 0 = t (x - 1 - sin t), t in [-1, 1]; '// &
        'exact x = 1 + sin t, y = 1/t'
    write (*, '(a)') '# method='//method_name(opts%method)//' formulation='//formulation_name(opts%formulation)// &
        ' eps='//num(opts%eps)//' taylor_h='//num(opts%taylor_h)//' rtol='//num(opts%rtol)//' atol='//num(opts%atol)
    write (*, '(a1,a23,4a24)') '#', 't', 'x', 'y', 'x_exact', 'y_exact'
    max_err = 0.0_wp
    call order3_exact(t0, xs0, ye)
    call solve_clock%start()
    call solver%init(new_order3(), t0, xs0, opts, stat)
    call solve_clock%stop()
    if (stat == regdae_success) then
        write (*, '(a)') resolved_line(solver)
        do k = 0, nout
            t = t0 + (tf - t0)*real(k, wp)/real(nout, wp)
            call solve_clock%start()
            call solver%advance(t, x, y, stat)
            call solve_clock%stop()
            if (stat < 0) exit
            call warnings%note(solver, stat, t)
            call order3_exact(t, xe, ye)
            max_err = max(max_err, abs(x(1) - xe(1, 1)))
            call output_clock%start()
            write (*, '(5es24.15e3)') t, x(1), y(1), xe(1, 1), ye
            call output_clock%stop()
        end do
        if (stat > 0) stat = regdae_success
    end if
    seconds = solve_clock%seconds()
    output_seconds = output_clock%seconds()
    st = solver%statistics()
    status_text = run_status(solver, stat, warnings)
    write (*, '(a)', advance='no') event_lines(solver)
    write (*, '(a)') 'summary method='//method_name(opts%method)//' status='//status_text//' t_end='//num(st%t)// &
        ' max_err='//num(max_err)//stats_fields(st, seconds, output_seconds)
    call solver%destroy()
    run_failed = (status_text == 'failed')
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (status_text)
    if (run_failed) stop 1
end program order3_driver
