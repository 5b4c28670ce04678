!> The measurement behind `drivers/rates` and the `theory` tests: the maximum
!! error in x of a manufactured linear DAE before, inside and after the
!! singular neighbourhood |t| <= delta and at t_end, on an output grid that
!! resolves the singular layer (steps end at every output time).
module rates_measure
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae
    use theory_problems, only: theory_problem
    implicit none
    private
    public :: output_grid, measure_errors

    real(wp), parameter :: t0 = -1.0_wp, tf = 1.0_wp

contains

    !> Uniform points with spacing 0.01/refine on [-1, 1], plus +-10^(-j/(16 refine)),
    !! j = 1, ..., 160 refine (ratio 1.155/refine-th root, down to 1e-10) around t* = 0;
    !! sorted. The geometric points sample the error peak of a layer of any width
    !! to better than 1% (the peak is smooth: its sampling error is quadratic).
    function output_grid(refine) result(grid)
        integer, intent(in) :: refine
        real(wp), allocatable :: grid(:), near(:)
        integer :: nu, j, k
        real(wp) :: tmp
        nu = 200*refine
        near = [(10.0_wp**(-real(j, wp)/(16*refine)), j=1, 160*refine)]
        grid = [([(t0 + (tf - t0)*real(j, wp)/real(nu, wp), j=0, nu)]), -near, near]
        do j = 2, size(grid)   ! insertion sort: a few hundred points
            tmp = grid(j)
            k = j - 1
            do while (k >= 1)
                if (grid(k) <= tmp) exit
                grid(k + 1) = grid(k)
                k = k - 1
            end do
            grid(k + 1) = tmp
        end do
    end function output_grid

    !> One run from x*(-1): errors(1:4) = max |x - x*| for t < -delta, |t| <= delta,
    !! t > delta, and at t = 1. NaN and stat < 0 if the run fails; then `message`,
    !! if present, is the solver's message (empty after success).
    subroutine measure_errors(problem, opts, times, delta, errors, stat, message)
        type(theory_problem), intent(in) :: problem
        type(solver_options), intent(in) :: opts   !! method, gamma, eps, tolerances
        real(wp), intent(in) :: times(:)           !! sorted output times in [-1, 1]
        real(wp), intent(in) :: delta              !! half-width of the singular neighbourhood
        real(wp), intent(out) :: errors(4)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out), optional :: message
        type(regdae_solver) :: solver
        real(wp) :: x(problem%n), y(problem%m), e, t
        integer :: k, region
        errors = 0.0_wp
        if (present(message)) message = ''
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
        call solver%destroy()
    end subroutine measure_errors

end module rates_measure
