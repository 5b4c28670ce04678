!> Driver for Example 5.1 of Petzold, Ren & Maly (1997):
!! x' = 2 + t y, 0 = t x - t(t+1), t in [-1, 1], x(-1) = 0; singular at t = 0.
!!
!! Usage: ex51 [key=value ...]
!!   method=baumgarte|trust_region|direct   (trust_region)
!!   gamma=1e3 eps=1e-6 rtol=1e-5 atol=1e-5 nout=200
!!   formulation=multiplier|eliminated      (multiplier)
!!   lsq=auto|normal|stacked                (auto)
!!   orientation=psd|paper                  (psd: B = t; paper: B = -t)
!!   exclusion=suppress|weights|off         (suppress)
!!   stop_at_output=yes|no                  (yes)
!!   x0=0 (x(-1); anything else is inconsistent), max_steps, h_init, h_max, ic_tol
!! Output: '#' lines, the table 't x y x_exact y_exact' at nout+1 equally spaced
!! times, and the last line
!!   summary method=... status=ok|warning|failed t_end=... max_err_x=... steps=... res_evals=...
!!           jac_evals=... err_test_fails=... conv_fails=... seconds=...
!! (status=warning: an advance returned a warning, e.g. y undefined at t = 0 or an unresolved
!! approach to the singularity; x is valid, the run goes on, and '# warning:' lines say which.)
!! Exit status: 0 ok or warning, 1 solver failure, 2 bad arguments.
program ex51_driver
    use regdae
    use ex51_problem, only: ex51, new_ex51, orientation_psd, orientation_paper
    use driver_support, only: resolved_line, event_lines, &
                              format_int, common_argument, stats_fields, run_status, argument, split_key_value, num, &
                              stopwatch, warning_log, die_usage, read_number
    implicit none

    character(len=*), parameter :: prog = 'ex51'
    real(wp), parameter :: t0 = -1.0_wp, tf = 1.0_wp
    type(solver_options) :: opts
    type(regdae_solver) :: solver
    type(solver_stats) :: st
    type(ex51) :: problem
    character(len=:), allocatable :: key, value, status_text
    integer :: i, k, nout, orientation, stat
    logical :: ok, run_failed
    real(wp) :: x0(1), x(1), y(1), t, max_err_x, seconds, output_seconds
    type(stopwatch) :: solve_clock, output_clock   ! the solve (init, advances); the table
    type(warning_log) :: warnings                  ! the advances' warnings

    nout = 200
    orientation = orientation_psd
    x0 = 0.0_wp
    opts%stop_at_output = .true.
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        select case (key)
        case ('orientation')
            select case (value)
            case ('psd'); orientation = orientation_psd
            case ('paper'); orientation = orientation_paper
            case default; call die_usage(prog, 'bad value "'//value//'" for orientation (psd|paper)')
            end select
        case ('x0')
            call read_number(prog, key, value, x0(1))
        case default
            call common_argument(prog, key, value, opts, nout)
        end select
    end do

    problem = new_ex51(orientation)
    write (*, '(a)') '# regdae ex51: Example 5.1 of Petzold, Ren & Maly (1997)'
    write (*, '(a)') '#   x'' = 2 + t y, 0 = t x - t(t+1), t in [-1, 1]; exact x = t + 1'
    write (*, '(a)') '#   orientation='//trim(merge('psd  ', 'paper', orientation == orientation_psd))// &
        trim(merge(' (B = t, y = 1/t)  ', ' (B = -t, y = -1/t)', orientation == orientation_psd))
    write (*, '(a)') '# method='//method_name(opts%method)//' formulation='//formulation_name(opts%formulation)// &
        ' lsq='//lsq_name(opts%lsq)//' exclusion='//exclusion_name(opts%exclusion)// &
        ' stop_at_output='//trim(merge('yes', 'no ', opts%stop_at_output))
    write (*, '(a)') '# gamma='//num(opts%gamma)//' eps='//num(opts%eps)//' rtol='//num(opts%rtol)// &
        ' atol='//num(opts%atol)//' nout='//format_int(nout)//' x0='//num(x0(1))
    write (*, '(a)') '# y_exact is undefined at t = 0 (printed NaN)'

    max_err_x = 0.0_wp
    call solve_clock%start()
    call solver%init(problem, t0, x0, opts, stat)
    call solve_clock%stop()
    if (stat == regdae_success) then
        write (*, '(a)') resolved_line(solver)
        write (*, '(a)') '# lsq resolved to '//lsq_name(solver%lsq_method())
        write (*, '(a1,a23,4a24)') '#', 't', 'x', 'y', 'x_exact', 'y_exact'
        do k = 0, nout
            t = t0 + (tf - t0)*real(k, wp)/real(nout, wp)
            call solve_clock%start()
            call solver%advance(t, x, y, stat)
            call solve_clock%stop()
            if (stat < 0) exit
            ! A singular multiplier equation at an output time (Baumgarte at t = 0)
            ! leaves x valid and y undefined (NaN); an unresolved approach to the
            ! singularity leaves x valid to less than the tolerance: say so and go on.
            if (stat > 0) write (*, '(a)') '# warning: '//solver%message()
            call warnings%note(solver, stat, t)
            max_err_x = max(max_err_x, abs(x(1) - problem%x_exact(t)))
            call output_clock%start()
            write (*, '(5es24.15e3)') t, x(1), y(1), problem%x_exact(t), problem%y_exact(t)
            call output_clock%stop()
        end do
        if (stat > 0) stat = regdae_success
    end if
    seconds = solve_clock%seconds()
    output_seconds = output_clock%seconds()
    st = solver%statistics()
    status_text = run_status(solver, stat, warnings)
    write (*, '(a)') '# steps, residual evaluations (IDA + Jacobian), Jacobians, linear setups, Newton iterations: '// &
        format_int(st%steps)//' '//format_int(st%res_evals)//' ('//format_int(st%res_evals - st%jac_res_evals)// &
        ' + '//format_int(st%jac_res_evals)//') '//format_int(st%jac_evals)//' '//format_int(st%lin_setups)// &
        ' '//format_int(st%nonlin_iters)
    write (*, '(a)', advance='no') event_lines(solver)
    write (*, '(a)') 'summary method='//method_name(opts%method)//' status='//status_text// &
        ' t_end='//num(st%t)//' max_err_x='//num(max_err_x)//stats_fields(st, seconds, output_seconds)
    call solver%destroy()
    run_failed = (status_text == 'failed')
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (status_text)
    if (run_failed) stop 1

end program ex51_driver
