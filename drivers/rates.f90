!> Driver: the convergence rates of Theorems 3.1 and 3.2 measured on the
!! manufactured linear DAEs of `theory_problems` (t in [-1, 1], t* = 0).
!!
!! For each case, regularization and gamma in {1e2, 1e3, 1e4}, eps in {1e-2, ..., 1e-10}:
!! the maximum error in x before the singular neighbourhood (t < -delta), inside it
!! (|t| <= delta), after it (t > delta) and at t_end, on an output grid that resolves the
!! singular layer (uniform spacing 0.01/refine plus points at +-10^(-j/(16 refine)) down to
!! 1e-10; steps end at every output time), and the fitted order p in error ~ C eps^p.
!!
!! With study=after (issue 14): the error after the singularity of the singular cases (S1-S4,
!! EX51) at gamma in {10, 1} (or gamma=) and eps = 1e-2, 1e-3, ..., eps_to (1e-18), each run
!! with the tolerance tightened (rtol = atol from rtol, default 1e-11, 10x tighter each time,
!! down to 1e-14) until the inside and after errors change by at most 2%; beside each row the
!! orders to which sigma_min(C), sigma_min(CB) and the damped matrix vanish at t* (m_C, m_CB, k).
!! Rows 'problem method gamma eps m_C m_CB k status rtol change converged err_inside err_after
!! err_end', then 'slope problem=... method=... gamma=... eps_from=... eps_to=... p=... converged=...'
!! lines: the local order of the after error over two decades of eps ('-' where an error is
!! below 1e3 rtol, the integration noise), and the summary with unconverged= (and warned_runs=,
!! last: the rows whose tightest run warned).
!!
!! With study=trace: one run (problem=, method=, gamma=, eps=, rtol=, integrator=, ...), the
!! error |x - x*| at the output times within 1e-2 of t* (rows 'trace t err steps'), every
!! warning of advance ('# warning: t ...'), and 'summary status=ok|warning|failed steps=...
!! unresolved_passes=... resolution_ratio=...'.
!!
!! Usage: rates [key=value ...]
!!   study=orders|after|trace (orders)   eps=<one value> (study=trace: 1e-14)   eps_to=1e-18 (study=after: the smallest eps, 1e-30 .. 1e-3)
!!   problem=all|R1|R2|S1|S2|S3|S4|EX51 (all)   method=both|direct|trust_region (both: direct,
!!   i.e. (3.2), only where B = C^T; trust_region (3.3) everywhere)   gamma=<one value> (default: the grid)
!!   refine=1 (output grid density)   delta=0.1   rtol=1e-11 atol=1e-11   lsq (stacked), other solver options
!! Output: '#' lines; rows 'problem method gamma eps status err_before err_inside err_after err_end'
!!   (status ok, warning or failed; a failed row follows a line '# error: problem method gamma eps:
!!   <the solver's message>', a warning row (an advance returned a warning: x valid, the tolerance
!!   maybe not met; its errors count in the fits) a line '# warning: problem method gamma eps: ...');
!!   'fit problem=... method=... gamma=... region=... p=... eps_from=... eps_to=... points=...' lines (fit
!!   over the eps whose error exceeds 1e3 rtol, the integration noise); and the last line
!!   summary status=ok|warning|failed runs=... failed_runs=... seconds=... warned_runs=...
!! (status=warning: no run failed, warned_runs did.) Exit status: 0 ok or warning, 1 a failed run,
!! 2 bad arguments.
program rates_driver
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
    use regdae
    use theory_problems, only: theory_problem, new_theory_problem, theory_cases
    use rates_measure, only: output_grid, measure_errors, converged_errors, vanishing_orders
    use driver_support, only: format_int, common_argument, argument, split_key_value, num, clock_start, &
                              elapsed_seconds, die_usage, read_number, warning_log, run_status
    implicit none
    character(len=*), parameter :: prog = 'rates'
    character(len=*), parameter :: regions(4) = ['before', 'inside', 'after ', 'end   ']
    type(solver_options) :: opts, run_opts
    character(len=:), allocatable :: key, value, which_problem, which_method, msg
    character(len=12) :: methods(2)
    real(wp), allocatable :: times(:), gammas(:), epss(:), err(:, :)
    real(wp) :: delta, refine_r, gamma_one, seconds, errors_run(4), first_run(4), eps_to, eps_one
    character(len=:), allocatable :: study
    integer :: i, ip, im, ig, ie, nmethods, nout_unused, runs, failed_runs, warned_runs, refine, stat
    logical :: ok
    integer(int64) :: start
    type(theory_problem) :: problem
    type(warning_log) :: run_warnings   ! the warnings of a cell's (reported) run

    which_problem = 'all'
    which_method = 'both'
    study = 'orders'
    eps_to = 1.0e-18_wp
    eps_one = 1.0e-14_wp
    gamma_one = -1.0_wp
    refine_r = 1.0_wp
    delta = 0.1_wp
    nout_unused = 1
    opts%rtol = 1.0e-11_wp
    opts%atol = 1.0e-11_wp
    opts%lsq = lsq_stacked
    opts%stop_at_output = .true.
    opts%max_steps = 1000000
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        select case (key)
        case ('problem')
            if (value /= 'all' .and. .not. any(theory_cases == value)) &
                call die_usage(prog, 'bad value "'//value//'" for problem (all, R1, R2, S1, S2, S3, S4, EX51)')
            which_problem = value
        case ('method')
            if (value /= 'both' .and. value /= 'direct' .and. value /= 'trust_region') &
                call die_usage(prog, 'bad value "'//value//'" for method (both, direct, trust_region)')
            which_method = value
        case ('gamma'); call read_number(prog, key, value, gamma_one)
            if (.not. (gamma_one > 0)) call die_usage(prog, 'gamma must be > 0')
        case ('refine'); call read_number(prog, key, value, refine_r)
            if (.not. (refine_r >= 1 .and. refine_r <= 8)) call die_usage(prog, 'refine must be in [1, 8]')
        case ('delta'); call read_number(prog, key, value, delta)
            if (.not. (delta > 0 .and. delta < 1)) call die_usage(prog, 'delta must be in (0, 1)')
        case ('study')
            if (value /= 'orders' .and. value /= 'after' .and. value /= 'trace') &
                call die_usage(prog, 'bad value "'//value//'" for study (orders, after, trace)')
            study = value
        case ('eps'); call read_number(prog, key, value, eps_one)
            if (.not. (eps_one >= 0)) call die_usage(prog, 'eps must be >= 0')
        case ('eps_to'); call read_number(prog, key, value, eps_to)
            if (.not. (eps_to >= 1.0e-30_wp .and. eps_to <= 1.0e-3_wp)) call die_usage(prog, 'eps_to must be in [1e-30, 1e-3]')
        case default
            call common_argument(prog, key, value, opts, nout_unused)
        end select
    end do
    refine = nint(refine_r)
    if (study == 'after') then
        call after_study()
        stop
    end if
    if (study == 'trace') then
        call trace_run()
        stop
    end if
    gammas = [1.0e2_wp, 1.0e3_wp, 1.0e4_wp]
    if (gamma_one > 0) gammas = [gamma_one]
    epss = [(10.0_wp**(-ie), ie=2, 10)]
    times = output_grid(refine)

    write (*, '(a)') '# regdae rates: Theorems 3.1 and 3.2 on manufactured linear DAEs, t in [-1, 1], t* = 0'
    write (*, '(a)') '# regularizations: direct = (3.2) (C C^T + eps I) y = -d (B = C^T only); '// &
        'trust_region = (3.3) ((CB)^T CB + eps I) y = -(CB)^T d'
    write (*, '(a)') '# rtol='//num(opts%rtol)//' atol='//num(opts%atol)//' lsq='//lsq_name(opts%lsq)// &
        ' delta='//num(delta)//' refine='//format_int(refine)//' output times='//format_int(size(times))
    write (*, '(a)') '# problem method gamma eps status err_before err_inside err_after err_end'
    start = clock_start()
    runs = 0
    failed_runs = 0
    warned_runs = 0
    allocate (err(size(epss), 4))
    do ip = 1, size(theory_cases)
        if (which_problem /= 'all' .and. which_problem /= trim(theory_cases(ip))) cycle
        problem = new_theory_problem(trim(theory_cases(ip)))
        write (*, '(a)') '# '//trim(theory_cases(ip))//': '//problem%theorem()
        call choose_methods()
        do im = 1, nmethods
            do ig = 1, size(gammas)
                do ie = 1, size(epss)
                    run_opts = cell_options(im, ig, ie)
                    call measure_errors(problem, run_opts, times, delta, errors_run, stat, msg, warnings=run_warnings)
                    call count_run(ie)
                    write (*, '(a,1x,a,1x,a,1x,a,1x,a,4(1x,a))') trim(theory_cases(ip)), trim(methods(im)), &
                        num(gammas(ig)), num(epss(ie)), row_status(), (num(err(ie, i)), i=1, 4)
                end do
                do i = 1, 4
                    call fit(trim(theory_cases(ip)), trim(methods(im)), gammas(ig), trim(regions(i)), epss, err(:, i))
                end do
            end do
        end do
    end do
    seconds = elapsed_seconds(start)
    write (*, '(a)') 'summary status='//summary_status()//' runs='//format_int(runs)// &
        ' failed_runs='//format_int(failed_runs)//' seconds='//num(seconds)//' warned_runs='//format_int(warned_runs)
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (which_problem, which_method, times, gammas, epss, err, study)
    if (allocated(msg)) deallocate (msg)
    if (failed_runs > 0) stop 1

contains

    ! A cell's run done (errors_run, stat, msg, run_warnings): its errors into err(ie, :), the
    ! counts, and a '# error:' line when it failed, a '# warning:' line when it warned.
    subroutine count_run(ie)
        integer, intent(in) :: ie
        character(len=:), allocatable :: cell
        err(ie, :) = errors_run
        runs = runs + 1
        cell = trim(theory_cases(ip))//' '//trim(methods(im))//' gamma='//num(gammas(ig))//' eps='//num(epss(ie))
        if (stat /= regdae_success) then
            failed_runs = failed_runs + 1
            write (*, '(a)') '# error: '//cell//': '//msg
        else if (run_warnings%count > 0) then
            warned_runs = warned_runs + 1
            write (*, '(a)') '# warning: '//cell//': '//format_int(run_warnings%count)// &
                ' advance(s) returned a warning; the first, at t = '//num(run_warnings%t_first)//': '//run_warnings%first
        end if
    end subroutine count_run

    ! The status word of a cell's row: failed, warning (the run warned) or ok.
    function row_status() result(word)
        character(len=:), allocatable :: word
        word = 'ok'
        if (stat /= regdae_success) then
            word = 'failed'
        else if (run_warnings%count > 0) then
            word = 'warning'
        end if
    end function row_status

    ! The summary's status word: failed if a run failed, else warning if one warned, else ok.
    function summary_status() result(word)
        character(len=:), allocatable :: word
        word = 'ok'
        if (failed_runs > 0) then
            word = 'failed'
        else if (warned_runs > 0) then
            word = 'warning'
        end if
    end function summary_status

    ! The options of one cell: opts with methods(im), gammas(ig), epss(ie).
    function cell_options(im, ig, ie) result(o)
        integer, intent(in) :: im, ig, ie
        type(solver_options) :: o
        o = opts
        call set_option(o, 'method', trim(methods(im)), stat, msg)
        o%gamma = gammas(ig)
        o%eps = epss(ie)
    end function cell_options

    ! The regularizations to run on `problem`: direct (3.2) only where B = C^T (or asked
    ! for), trust_region (3.3) everywhere; in methods(1:nmethods).
    subroutine choose_methods()
        nmethods = 0
        if ((which_method == 'both' .and. problem%b_is_ct) .or. which_method == 'direct') then
            nmethods = nmethods + 1
            methods(nmethods) = 'direct'
        end if
        if (which_method == 'both' .or. which_method == 'trust_region') then
            nmethods = nmethods + 1
            methods(nmethods) = 'trust_region'
        end if
    end subroutine choose_methods

    ! study=trace: one run, its error near t* at every output time, its warnings.
    subroutine trace_run()
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        type(warning_log) :: warnings
        real(wp), allocatable :: x(:), y(:)
        character(len=:), allocatable :: method, status_text
        integer :: k
        if (which_problem == 'all') which_problem = 'S1'
        method = merge('direct      ', 'trust_region', which_method == 'direct')
        problem = new_theory_problem(which_problem)
        run_opts = opts
        call set_option(run_opts, 'method', trim(method), stat, msg)
        run_opts%gamma = merge(gamma_one, 10.0_wp, gamma_one > 0)
        run_opts%eps = eps_one
        times = output_grid(refine)
        allocate (x(problem%n), y(problem%m))
        write (*, '(a)') '# regdae rates study=trace: '//which_problem//' '//trim(method)//' gamma='// &
            num(run_opts%gamma)//' eps='//num(run_opts%eps)//' rtol='//num(run_opts%rtol)//' atol='//num(run_opts%atol)
        write (*, '(a)') '# trace t err steps (the outputs within 1e-2 of t* = 0)'
        call solver%init(problem, -1.0_wp, problem%x_exact(-1.0_wp), run_opts, stat)
        if (stat /= regdae_success) call die_usage(prog, solver%message())
        do k = 2, size(times)
            if (times(k) <= times(k - 1)) cycle
            call solver%advance(times(k), x, y, stat)
            if (stat < 0) exit
            if (stat > 0) write (*, '(a)') '# warning: t = '//num(times(k))//': '//solver%message()
            call warnings%note(solver, stat, times(k))
            st = solver%statistics()
            if (abs(times(k)) <= 1.0e-2_wp) write (*, '(a)') 'trace '//num(times(k))//' '// &
                num(maxval(abs(x - problem%x_exact(times(k)))))//' '//format_int(st%steps)
        end do
        if (stat > 0) stat = regdae_success   ! the last warning is in the log too
        st = solver%statistics()
        status_text = run_status(solver, stat, warnings)   ! '# error:' or the warnings' line, then the word
        write (*, '(a)') 'summary status='//status_text//' steps='//format_int(st%steps)// &
            ' unresolved_passes='//format_int(st%unresolved_passes)//' resolution_ratio='//num(st%resolution_ratio)
        call solver%destroy()
        if (stat < 0) stop 1
    end subroutine trace_run

    ! study=after: the after-singularity errors of the singular cases, converged in the
    ! tolerance, and their local orders over two decades of eps.
    subroutine after_study()
        real(wp), allocatable :: rtols(:), changes(:), first(:), ratios(:)
        logical, allocatable :: warned(:)
        logical, allocatable :: done(:)
        real(wp) :: p
        character(len=:), allocatable :: slope_text
        integer :: m_c, m_cb, k, unconverged, neps
        logical :: fine
        neps = 1 - 2 + nint(-log10(eps_to))
        epss = [(10.0_wp**(-ie), ie=2, neps + 1)]
        gammas = [10.0_wp, 1.0_wp]
        if (gamma_one > 0) gammas = [gamma_one]
        times = output_grid(refine)
        allocate (err(size(epss), 4), rtols(size(epss)), changes(size(epss)), done(size(epss)), first(size(epss)), &
                  ratios(size(epss)), warned(size(epss)))
        write (*, '(a)') '# regdae rates study=after: the error after the singularity, t in [-1, 1], t* = 0, '// &
            'the tolerance tightened until it stops changing'
        write (*, '(a)') '# rtol from '//num(opts%rtol)//' down to 1e-14 (10x a step) until the inside and after '// &
            'errors change by <= 2%; lsq='//lsq_name(opts%lsq)//' delta='//num(delta)//' output times='// &
            format_int(size(times))
        write (*, '(a)') '# m_C, m_CB, k: the orders to which sigma_min(C), sigma_min(CB) and the damped matrix '// &
            '(CB for direct, (CB)^T CB for trust_region) vanish at t*'
        write (*, '(a)') '# problem method gamma eps m_C m_CB k status rtol change converged err_inside err_after err_end '// &
            'err_inside_first unresolved_first resolution_ratio_first (the run at the first rtol: its inside error, '// &
            'whether it warned regdae_warn_unresolved, its statistic resolution_ratio)'
        start = clock_start()
        runs = 0
        failed_runs = 0
        warned_runs = 0
        unconverged = 0
        do ip = 1, size(theory_cases)
            if (which_problem /= 'all' .and. which_problem /= trim(theory_cases(ip))) cycle
            problem = new_theory_problem(trim(theory_cases(ip)))
            if (problem%m /= 1) cycle   ! the redundant cases have no singularity
            call choose_methods()
            do im = 1, nmethods
                call vanishing_orders(problem, trim(methods(im)), m_c, m_cb, k)
                do ig = 1, size(gammas)
                    do ie = 1, size(epss)
                        run_opts = cell_options(im, ig, ie)
                        call converged_errors(problem, run_opts, times, delta, opts%rtol, 1.0e-14_wp, 0.02_wp, &
                                              errors_run, first_run, rtols(ie), changes(ie), done(ie), stat, msg, &
                                              warned(ie), ratios(ie), run_warnings)
                        first(ie) = first_run(2)
                        call count_run(ie)
                        if (stat /= regdae_success) done(ie) = .false.
                        if (.not. done(ie)) unconverged = unconverged + 1
                        write (*, '(a,1x,a,1x,a,1x,a,3(1x,a),1x,a,1x,a,1x,a,1x,a,6(1x,a))') trim(theory_cases(ip)), &
                            trim(methods(im)), num(gammas(ig)), num(epss(ie)), format_int(m_c), format_int(m_cb), &
                            format_int(k), row_status(), num(rtols(ie)), &
                            num(min(changes(ie), 9.99e99_wp)), trim(merge('yes', 'no ', done(ie))), (num(err(ie, i)), i=2, 4), &
                            num(first(ie)), trim(merge('yes', 'no ', warned(ie))), num(ratios(ie))
                    end do
                    do ie = 1, size(epss) - 2
                        fine = err(ie, 3) > 1.0e3_wp*rtols(ie) .and. err(ie + 2, 3) > 1.0e3_wp*rtols(ie + 2)
                        slope_text = '-'
                        if (fine) then
                            p = log10(err(ie, 3)/err(ie + 2, 3))/log10(epss(ie)/epss(ie + 2))
                            if (ieee_is_finite(p)) slope_text = num(p)
                        end if
                        write (*, '(a)') 'slope problem='//trim(theory_cases(ip))//' method='//trim(methods(im))// &
                            ' gamma='//num(gammas(ig))//' eps_from='//num(epss(ie))//' eps_to='//num(epss(ie + 2))// &
                            ' p='//slope_text//' converged='// &
                            trim(merge('yes', 'no ', done(ie) .and. done(ie + 2)))
                    end do
                end do
            end do
        end do
        seconds = elapsed_seconds(start)
        write (*, '(a)') 'summary status='//summary_status()//' runs='//format_int(runs)// &
            ' failed_runs='//format_int(failed_runs)//' unconverged='//format_int(unconverged)//' seconds='//num(seconds)// &
            ' warned_runs='//format_int(warned_runs)
        if (failed_runs > 0) stop 1
    end subroutine after_study

    ! Least-squares slope of log(err) against log(eps) over the points above the noise floor.
    subroutine fit(name, method, gamma, region, eps, errors)
        character(len=*), intent(in) :: name, method, region
        real(wp), intent(in) :: gamma, eps(:), errors(:)
        logical :: use(size(eps))
        real(wp) :: lx(size(eps)), ly(size(eps)), p, mx, my
        integer :: np
        use = ieee_is_finite(errors) .and. errors > 1.0e3_wp*max(opts%rtol, opts%atol)
        np = count(use)
        if (np >= 3) then
            lx = log10(eps)
            ly = log10(max(errors, tiny(1.0_wp)))
            mx = sum(lx, mask=use)/np
            my = sum(ly, mask=use)/np
            p = sum((lx - mx)*(ly - my), mask=use)/sum((lx - mx)**2, mask=use)
            write (*, '(a)') 'fit problem='//name//' method='//method//' gamma='//num(gamma)//' region='//region// &
                ' p='//num(p)//' eps_from='//num(maxval(eps, mask=use))//' eps_to='//num(minval(eps, mask=use))// &
                ' points='//format_int(np)
        else
            write (*, '(a)') 'fit problem='//name//' method='//method//' gamma='//num(gamma)//' region='//region// &
                ' p=- eps_from=- eps_to=- points='//format_int(np)
        end if
    end subroutine fit

end program rates_driver
