!> The measurement behind `drivers/rates` and the `theory` tests: the maximum
!! error in x of a manufactured linear DAE before, inside and after the
!! singular neighbourhood |t| <= delta and at t_end, on an output grid that
!! resolves the singular layer (steps end at every output time).
module rates_measure
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae
    use theory_problems, only: theory_problem
    use driver_support, only: warning_log, sort_ascending
    implicit none
    private
    public :: output_grid, measure_errors, converged_errors, vanishing_orders

    real(wp), parameter :: t0 = -1.0_wp, tf = 1.0_wp

contains

    !> Uniform points with spacing 0.01/refine on [-1, 1], plus +-10^(-j/(16 refine)),
    !! j = 1, ..., 160 refine (ratio 1.155/refine-th root, down to 1e-10) around t* = 0;
    !! sorted. The geometric points sample the error peak of a layer of any width
    !! to better than 1% (the peak is smooth: its sampling error is quadratic).
    function output_grid(refine) result(grid)
        integer, intent(in) :: refine
        real(wp), allocatable :: grid(:), near(:)
        integer :: nu, j
        nu = 200*refine
        near = [(10.0_wp**(-real(j, wp)/(16*refine)), j=1, 160*refine)]
        grid = [([(t0 + (tf - t0)*real(j, wp)/real(nu, wp), j=0, nu)]), -near, near]
        call sort_ascending(grid)   ! a few hundred points
    end function output_grid

    !> One run from x*(-1): errors(1:4) = max |x - x*| for t < -delta, |t| <= delta,
    !! t > delta, and at t = 1. NaN and stat < 0 if the run fails; then `message`,
    !! if present, is the solver's message (empty after success). unresolved: an
    !! advance warned regdae_warn_unresolved; ratio: the statistic resolution_ratio;
    !! warnings: every warning of the advances (stat stays 0 after them: x is valid).
    subroutine measure_errors(problem, opts, times, delta, errors, stat, message, unresolved, ratio, warnings)
        type(theory_problem), intent(in) :: problem
        type(solver_options), intent(in) :: opts   !! method, gamma, eps, tolerances
        real(wp), intent(in) :: times(:)           !! sorted output times in [-1, 1]
        real(wp), intent(in) :: delta              !! half-width of the singular neighbourhood
        real(wp), intent(out) :: errors(4)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out), optional :: message
        logical, intent(out), optional :: unresolved
        real(wp), intent(out), optional :: ratio
        type(warning_log), intent(out), optional :: warnings
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        type(warning_log) :: log
        logical :: warned
        real(wp) :: x(problem%n), y(problem%m), e, t
        integer :: k, region
        errors = 0.0_wp
        warned = .false.
        if (present(message)) message = ''
        if (present(unresolved)) unresolved = .false.
        if (present(ratio)) ratio = 0.0_wp
        call solver%init(problem, t0, problem%x_exact(t0), opts, stat)
        if (stat /= regdae_success) then
            errors = ieee_value(1.0_wp, ieee_quiet_nan)
            if (present(message)) message = solver%message()
            return
        end if
        do k = 1, size(times)
            t = times(k)
            if (k > 1) then
                if (t <= times(k - 1)) cycle
            end if
            call solver%advance(t, x, y, stat)
            if (stat < 0) exit
            call log%note(solver, stat, t)
            if (stat == regdae_warn_unresolved) warned = .true.
            stat = regdae_success
            e = maxval(abs(x - problem%x_exact(t)))
            region = 2
            if (t < -delta) region = 1
            if (t > delta) region = 3
            errors(region) = max(errors(region), e)
            if (k == size(times)) errors(4) = e
        end do
        if (stat /= regdae_success) then
            errors = ieee_value(1.0_wp, ieee_quiet_nan)
            if (present(message)) message = solver%message()
        end if
        st = solver%statistics()
        if (present(unresolved)) unresolved = warned
        if (present(ratio)) ratio = st%resolution_ratio
        if (present(warnings)) warnings = log
        call solver%destroy()
    end subroutine measure_errors

    !> measure_errors with the tolerance tightened until the errors stop changing:
    !! rtol = atol = rtol_start, then 10x tighter each time, until the inside and after
    !! errors of two successive tolerances agree to `change_tol` (relative), or rtol_floor
    !! is reached. errors: those of the tightest run; rtol_used: its tolerance; change:
    !! the largest relative change of the inside and after errors between the last two
    !! runs; converged: change <= change_tol; first: the errors at rtol_start. Errors
    !! below 1e3 rtol (the integration error) count as equal. stat < 0 (and message)
    !! if a run fails. warnings: those of the tightest run (the one whose errors are returned).
    subroutine converged_errors(problem, opts, times, delta, rtol_start, rtol_floor, change_tol, errors, &
                                first, rtol_used, change, converged, stat, message, first_unresolved, first_ratio, &
                                warnings)
        type(theory_problem), intent(in) :: problem
        type(solver_options), intent(in) :: opts
        real(wp), intent(in) :: times(:), delta, rtol_start, rtol_floor, change_tol
        real(wp), intent(out) :: errors(4), first(4), rtol_used, change
        logical, intent(out) :: converged
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: message
        logical, intent(out) :: first_unresolved   !! the run at rtol_start warned regdae_warn_unresolved
        real(wp), intent(out) :: first_ratio       !! its resolution_ratio
        type(warning_log), intent(out), optional :: warnings
        type(solver_options) :: run_opts
        real(wp) :: previous(4), ratio
        logical :: unresolved
        integer :: i
        run_opts = opts
        rtol_used = rtol_start
        first = 0.0_wp
        first_unresolved = .false.
        first_ratio = 0.0_wp
        change = huge(1.0_wp)
        converged = .false.
        do
            run_opts%rtol = rtol_used
            run_opts%atol = rtol_used
            call measure_errors(problem, run_opts, times, delta, errors, stat, message, unresolved, ratio, warnings)
            if (rtol_used >= rtol_start) then
                first_unresolved = unresolved
                first_ratio = ratio
            end if
            if (stat /= regdae_success) return
            if (rtol_used < rtol_start) then
                change = 0.0_wp
                do i = 2, 3
                    change = max(change, abs(errors(i) - previous(i))/max(errors(i), 1.0e3_wp*rtol_used))
                end do
                converged = change <= change_tol
                if (converged) return
            end if
            if (rtol_used/10.0_wp < rtol_floor*(1.0_wp - 1.0e-9_wp)) return
            if (rtol_used >= rtol_start) first = errors
            previous = errors
            rtol_used = rtol_used/10.0_wp
        end do
    end subroutine converged_errors

    !> The orders to which sigma_min(C), sigma_min(CB) and sigma_min of the damped matrix
    !! (CB for `direct`, (3.2); (CB)^T CB for `trust_region`, (3.3)) vanish at t* = 0:
    !! log10 of their ratio between t = 1e-2 and 1e-3, rounded. Cases with one constraint
    !! (the singular ones); -1 for the others.
    subroutine vanishing_orders(problem, method, m_c, m_cb, k)
        type(theory_problem), intent(in) :: problem
        character(len=*), intent(in) :: method
        integer, intent(out) :: m_c, m_cb, k
        type(theory_problem) :: p
        real(wp) :: sc(2), scb(2), t
        real(wp), allocatable :: c(:, :), b(:, :)
        integer :: i
        m_c = -1
        m_cb = -1
        k = -1
        if (problem%m /= 1) return
        p = problem
        allocate (c(p%m, p%n), b(p%n, p%m))
        do i = 1, 2
            t = 10.0_wp**(-1 - i)
            call p%coefficient_c(t, c)
            call p%coefficient_b(t, b)
            sc(i) = norm2(c(1, :))
            scb(i) = abs(sum(c(1, :)*b(:, 1)))
        end do
        m_c = nint(log10(sc(1)/sc(2)))
        m_cb = nint(log10(scb(1)/scb(2)))
        k = merge(m_cb, 2*m_cb, method == 'direct')
    end subroutine vanishing_orders

end module rates_measure
