!> Measurement (not a benchmark of time): regdae's Radau IIA on the car axis's index-3 form
!! with RADAU5's conventions, to set its steps beside RADAU5's reference point (issue 21:
!! 99 / 201 / 416 steps at rtol = atol = 1e-4 / 1e-6 / 1e-8, 4 / 6 / 8 digits quoted) and
!! beside integrator=radau on the regularized (eliminated) system (`car_axis config=radau`).
!! Modes: `radau5`: the error of the velocities scaled by h and of the multipliers by h^2
!! (dae_index 2 and 3) and RADAU5's tolerance transform (local tolerance 0.1 rtol^(2/3), atol
!! alike), first step 1e-6, as RADAU5 runs an index-3 problem; `index3`: the same scaling
!! without the transform. (With the velocities' error unscaled the index-3 form's estimate is
!! not an error bound: runs at 1e-6 and 1e-10 stop with step size too small.)
!!
!! Usage: car_axis_index3 [mode=all|radau5|index3] [tol_from=4] [tol_to=10] [tol_step=2]
!! Output: '#' lines, rows 'car_axis_index3 mode rtol steps rejected rhs_evals jacobians digits
!! status x_radau5_steps' (digits: -log10 max |err_i| / (1 + |ref_i|) on the positions at
!! t = 3 against the test set's published solution; the last column at 1e-4, 1e-6, 1e-8 only).
program car_axis_index3_driver
    use regdae_kinds, only: wp
    use regdae_radau_iia, only: radau_integrator
    use regdae_radau_system, only: radau_options, radau_stats
    use car_axis_problem, only: car_axis_reference, car_axis_t_end
    use car_axis_index3_problem, only: car_axis_index3, car_axis_index3_setup
    use driver_support, only: argument, split_key_value, die_usage, read_count
    implicit none
    character(len=*), parameter :: prog = 'car_axis_index3'
    integer, parameter :: radau5_k(3) = [4, 6, 8]
    integer, parameter :: radau5_steps(3) = [99, 201, 416]
    character(len=6), parameter :: modes(2) = [character(len=6) :: 'radau5', 'index3']
    character(len=:), allocatable :: key, value, which
    integer :: i, k, m, tol_from, tol_to, tol_step, failed
    logical :: ok

    which = 'all'
    tol_from = 4
    tol_to = 10
    tol_step = 2
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'expected key=value: '//argument(i))
        select case (key)
        case ('mode')
            which = value
        case ('tol_from')
            call read_count(prog, key, value, tol_from, 1, 14)
        case ('tol_to')
            call read_count(prog, key, value, tol_to, 1, 14)
        case ('tol_step')
            call read_count(prog, key, value, tol_step, 1, 13)
        case default
            call die_usage(prog, 'unknown argument: '//argument(i))
        end select
    end do
    if (.not. any(modes == which) .and. which /= 'all') call die_usage(prog, 'mode must be all, radau5 or index3')

    print '(a)', '# regdae Radau IIA on the car axis index-3 form M u'' = F (u = p, p'', lambda), rtol = atol = 10^-k'
    print '(a)', '# columns: car_axis_index3 mode rtol steps rejected rhs_evals jacobians digits status x_radau5_steps'
    failed = 0
    do m = 1, size(modes)
        if (which /= 'all' .and. which /= modes(m)) cycle
        do k = tol_from, tol_to, tol_step
            call run_one(modes(m), k)
        end do
    end do
    print '(a, i0)', 'summary failed=', failed
    if (failed > 0) stop 1

contains

    !> One run to t = 3 in MODE at rtol = atol = 10^-K; prints its row.
    subroutine run_one(mode, k)
        character(len=*), intent(in) :: mode
        integer, intent(in) :: k
        type(car_axis_index3) :: sys
        type(radau_integrator) :: integrator
        type(radau_options) :: opts
        type(radau_stats) :: stats
        real(wp) :: u0(10), u(10), digits
        integer :: stat, j
        character(len=16) :: ratio
        call car_axis_index3_setup(sys, 10.0_wp**(-k), mode == 'radau5', u0, opts)
        call integrator%start(sys, 0.0_wp, u0, opts, stat)
        if (stat == 0) call integrator%advance(sys, car_axis_t_end, u, stat, land=.true.)
        stats = integrator%statistics()
        digits = 0
        if (stat == 0) digits = -log10(maxval(abs(u(1:4) - car_axis_reference(1:4))/(1 + abs(car_axis_reference(1:4)))))
        if (stat /= 0) failed = failed + 1
        ratio = '-'
        do j = 1, size(radau5_k)
            if (radau5_k(j) == k) write (ratio, '(f4.2)') real(stats%accepted, wp)/radau5_steps(j)
        end do
        print '(a, 1x, a6, 1x, es8.1, 4(1x, i7), 1x, f6.2, 1x, i5, 1x, a)', 'car_axis_index3', mode, opts%rtol, &
            stats%accepted, stats%rejected, stats%rhs_evals, stats%jacobians, digits, stat, trim(ratio)
    end subroutine run_one

end program car_axis_index3_driver
