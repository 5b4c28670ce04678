!> Driver: the convergence rates of Theorems 3.1 and 3.2 measured on the
!! manufactured linear DAEs of `theory_problems` (t in [-1, 1], t* = 0).
!!
!! For each case, regularization and gamma in {1e2, 1e3, 1e4}, eps in {1e-2, ..., 1e-10}:
!! the maximum error in x before the singular neighbourhood (t < -delta), inside it
!! (|t| <= delta), after it (t > delta) and at t_end, on an output grid that resolves the
!! singular layer (uniform spacing 0.01/refine plus points at +-10^(-j/(16 refine)) down to
!! 1e-10; steps end at every output time), and the fitted order p in error ~ C eps^p.
!!
!! Usage: rates [key=value ...]
!!   problem=all|R1|R2|S1|S2|S3|S4|EX51 (all)   method=both|direct|trust_region (both: direct,
!!   i.e. (3.2), only where B = C^T; trust_region (3.3) everywhere)   gamma=<one value> (default: the grid)
!!   refine=1 (output grid density)   delta=0.1   rtol=1e-11 atol=1e-11   lsq (stacked), other solver options
!! Output: '#' lines; rows 'problem method gamma eps status err_before err_inside err_after err_end'
!!   (a failed row follows a line '# error: problem method gamma eps: <the solver's message>');
!!   'fit problem=... method=... gamma=... region=... p=... eps_from=... eps_to=... points=...' lines (fit
!!   over the eps whose error exceeds 1e3 rtol, the integration noise); and the last line
!!   summary status=ok|failed runs=... failed_runs=... seconds=...
program rates_driver
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
    use regdae
    use theory_problems, only: theory_problem, new_theory_problem, theory_cases
    use rates_measure, only: output_grid, measure_errors
    use driver_support, only: format_int, common_argument, argument, split_key_value, num, clock_start, &
                              elapsed_seconds, die_usage, read_number
    implicit none
    character(len=*), parameter :: prog = 'rates'
    character(len=*), parameter :: regions(4) = ['before', 'inside', 'after ', 'end   ']
    type(solver_options) :: opts, run_opts
    character(len=:), allocatable :: key, value, which_problem, which_method, msg
    character(len=12) :: methods(2)
    real(wp), allocatable :: times(:), gammas(:), epss(:), err(:, :)
    real(wp) :: delta, refine_r, gamma_one, seconds, errors_run(4)
    integer :: i, ip, im, ig, ie, nmethods, nout_unused, runs, failed_runs, refine, stat
    logical :: ok
    integer(int64) :: start
    type(theory_problem) :: problem

    which_problem = 'all'
    which_method = 'both'
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
        case default
            call common_argument(prog, key, value, opts, nout_unused)
        end select
    end do
    refine = nint(refine_r)
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
    allocate (err(size(epss), 4))
    do ip = 1, size(theory_cases)
        if (which_problem /= 'all' .and. which_problem /= trim(theory_cases(ip))) cycle
        problem = new_theory_problem(trim(theory_cases(ip)))
        write (*, '(a)') '# '//trim(theory_cases(ip))//': '//problem%theorem()
        nmethods = 0
        if ((which_method == 'both' .and. problem%b_is_ct) .or. which_method == 'direct') then
            nmethods = nmethods + 1
            methods(nmethods) = 'direct'
        end if
        if (which_method == 'both' .or. which_method == 'trust_region') then
            nmethods = nmethods + 1
            methods(nmethods) = 'trust_region'
        end if
        do im = 1, nmethods
            do ig = 1, size(gammas)
                do ie = 1, size(epss)
                    run_opts = opts
                    call set_option(run_opts, 'method', trim(methods(im)), stat, msg)
                    run_opts%gamma = gammas(ig)
                    run_opts%eps = epss(ie)
                    call measure_errors(problem, run_opts, times, delta, errors_run, stat, msg)
                    err(ie, :) = errors_run
                    runs = runs + 1
                    if (stat /= regdae_success) then
                        failed_runs = failed_runs + 1
                        write (*, '(a)') '# error: '//trim(theory_cases(ip))//' '//trim(methods(im))//' gamma='// &
                            num(gammas(ig))//' eps='//num(epss(ie))//': '//msg
                    end if
                    write (*, '(a,1x,a,1x,a,1x,a,1x,a,4(1x,a))') trim(theory_cases(ip)), trim(methods(im)), &
                        num(gammas(ig)), num(epss(ie)), trim(merge('ok    ', 'failed', stat == regdae_success)), &
                        (num(err(ie, i)), i=1, 4)
                end do
                do i = 1, 4
                    call fit(trim(theory_cases(ip)), trim(methods(im)), gammas(ig), trim(regions(i)), epss, err(:, i))
                end do
            end do
        end do
    end do
    seconds = elapsed_seconds(start)
    write (*, '(a)') 'summary status='//trim(merge('ok    ', 'failed', failed_runs == 0))//' runs='//format_int(runs)// &
        ' failed_runs='//format_int(failed_runs)//' seconds='//num(seconds)
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (which_problem, which_method, times, gammas, epss, err)
    if (allocated(msg)) deallocate (msg)
    if (failed_runs > 0) stop 1

contains

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
