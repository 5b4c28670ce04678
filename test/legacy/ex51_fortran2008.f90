!> drivers/example_ex51.f through the Fortran 2008 API: Example 5.1 (orientation
!! psd, B = t) with the same options (trust_region, rtol = atol = 1e-8, the
!! analytic g_t) and the same output times and table, so that
!! check_same_output.sh can require both outputs to be the same digit for digit.
!! A warning (stat > 0) goes on, as the FORTRAN 77 program does after IDID > 0.
program ex51_fortran2008
    use regdae, only: wp, solver_options, regdae_solver, solver_stats, method_trust_region, regdae_success
    use ex51_problem, only: ex51, new_ex51, orientation_psd
    implicit none
    type(ex51) :: problem
    type(solver_options) :: opts
    type(regdae_solver) :: solver
    type(solver_stats) :: st
    real(wp) :: t, x(1), y(1), err
    integer :: k, stat

    problem = new_ex51(orientation_psd)
    opts%method = method_trust_region
    opts%rtol = 1.0e-8_wp
    opts%atol = 1.0e-8_wp
    call solver%init(problem, -1.0_wp, [0.0_wp], opts, stat)
    if (stat /= regdae_success) error stop 'init failed'
    err = 0.0_wp
    do k = 1, 20
        t = -1.0_wp + real(k, wp)/10.0_wp
        call solver%advance(t, x, y, stat)
        if (stat < 0) error stop 'advance failed'
        err = max(err, abs(x(1) - (t + 1.0_wp)))
        write (*, '(f6.2, 1p, 2e25.16)') t, x(1), y(1)
    end do
    st = solver%statistics()
    write (*, '(a, 1p, e9.2, a, i6, a)') ' MAX ERROR', err, ' IN', st%steps, ' STEPS'
end program ex51_fortran2008
