!> Benchmark (not a test): the car axis of the Test Set for IVP Solvers
!! (drivers/problems/car_axis_problem.f90), a stiff index-3 mechanism, against the test
!! set's published solution at t = 3 and against RADAU5's reference point (issue 21:
!! 99 / 201 / 416 steps, 4 / 6 / 8 digits on the positions in 0.37 / 0.96 / 2.4 ms at
!! rtol = atol = 1e-4 / 1e-6 / 1e-8 on this machine).
!!
!! Each configuration runs with every option at its default but rtol = atol = tol and the
!! listed `key=value` items: `defaults`, `radau` (integrator=radau), `ida`
!! (integrator=ida). Time: the solve alone, `init` (the consistent start) and one
!! `advance` to t = 3 (no intermediate outputs, the state there by the integrator's
!! own stop at the output time); not the problem's construction nor `destroy`. The
!! median of at least `reps` repetitions in this process, repeated until they take
!! `min_time` seconds in all (at most 201).
!!
!! Usage: car_axis [reps=5] [min_time=0.05] [tol_from=4] [tol_to=8] [tol_step=2]
!!        [config=all|defaults|radau|ida] [check=yes|no] [extra='key=value ...']
!! (tol: rtol = atol = 10^-k for k = tol_from, tol_from + tol_step, ... <= tol_to, k in [1, 14];
!! extra: option items added to every configuration's; check=yes first runs each configuration
!! at tight tolerances (1e-11 and 1e-12) and prints its error on positions and velocities
!! against the published solution.)
!! Output: '#' lines, rows 'car_axis config rtol pos_err digits seconds steps res_evals
!! jac_evals lin_setups newton_iters rejected conv_fails status x_radau5_time x_radau5_steps'
!! (steps: accepted; rejected: error test failures; conv_fails: Newton failures; digits: the test set's mixed
!! significant digits on the positions, -log10 max |err_i| / (1 + |ref_i|); the last two
!! columns: the ratios to RADAU5's reference point at 1e-4, 1e-6, 1e-8, '-' elsewhere),
!! and the last line 'summary rows=... ok=... failed=... warned=...'.
program car_axis_driver
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae
    use car_axis_problem, only: car_axis, new_car_axis, car_axis_reference, car_axis_t_end, car_axis_x0, &
                                car_axis_v0
    use driver_support, only: format_int, argument, split_key_value, num, die_usage, read_count, timing_option
    implicit none
    character(len=*), parameter :: prog = 'car_axis'
    integer, parameter :: max_reps = 201
    !> RADAU5's reference point (issue 21): tol exponent, steps, seconds.
    integer, parameter :: radau5_k(3) = [4, 6, 8]
    integer, parameter :: radau5_steps(3) = [99, 201, 416]
    real(wp), parameter :: radau5_seconds(3) = [0.37e-3_wp, 0.96e-3_wp, 2.4e-3_wp]
    character(len=8), parameter :: config_names(3) = [character(len=8) :: 'defaults', 'radau', 'ida']
    character(len=*), parameter :: config_items(3) = [character(len=16) :: '', 'integrator=radau', 'integrator=ida']
    character(len=:), allocatable :: key, value, which, extra
    integer :: i, k, c, reps, tol_from, tol_to, tol_step
    integer :: row_counts(3) = 0   ! ok, failed, warning
    real(wp) :: min_time
    logical :: ok, check

    reps = 5
    min_time = 0.05_wp
    tol_from = 4
    tol_to = 8
    tol_step = 2
    which = 'all'
    extra = ''
    check = .true.
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        if (timing_option(prog, key, value, max_reps, reps, min_time, tol_from, tol_to)) cycle
        select case (key)
        case ('tol_step'); call read_count(prog, key, value, tol_step, 1, 13)
        case ('config'); which = value
            if (which /= 'all' .and. all(config_names /= which)) call die_usage(prog, 'bad config '//value)
        case ('extra'); extra = value
        case ('check')
            if (value /= 'yes' .and. value /= 'no') call die_usage(prog, 'check must be yes or no')
            check = value == 'yes'
        case default; call die_usage(prog, 'unknown option "'//key//'"')
        end select
    end do
    if (tol_from > tol_to) call die_usage(prog, 'tol_from must be <= tol_to')

    write (*, '(a)') '# car axis (Test Set for IVP Solvers), error at t = 3 against the published solution'
    if (check) then
        write (*, '(a)') '# check: config rtol max|x err| max|v err| steps status'
        do c = 1, size(config_names)
            if (which /= 'all' .and. which /= config_names(c)) cycle
            do k = 11, 12
                call tight(config_names(c), trim(config_items(c))//' '//extra, 10.0_wp**(-k))
            end do
        end do
    end if
    write (*, '(a)') '# median of at least '//format_int(reps)//' runs (and '//num(min_time)// &
        ' s) in one process; the solve alone: init and one advance to t = 3'
    write (*, '(a)') '# problem config rtol pos_err digits seconds steps res_evals jac_evals lin_setups newton_iters '// &
        'rejected conv_fails status '// &
        'x_radau5_time x_radau5_steps'
    do k = tol_from, tol_to, tol_step
        do c = 1, size(config_names)
            if (which /= 'all' .and. which /= config_names(c)) cycle
            call timed(config_names(c), trim(config_items(c))//' '//extra, k)
        end do
    end do
    write (*, '(a)') 'summary rows='//format_int(sum(row_counts))//' ok='//format_int(row_counts(1))//' failed='// &
        format_int(row_counts(2))//' warned='//format_int(row_counts(3))
    if (allocated(key)) deallocate (key, value)
    deallocate (which, extra)

contains

    !> Options: the defaults, rtol = atol = tol, then the blank-separated `key=value` items.
    function options_for(items, tol) result(opts)
        character(len=*), intent(in) :: items
        real(wp), intent(in) :: tol
        type(solver_options) :: opts
        character(len=:), allocatable :: rest, item, msg
        integer :: j, stat
        opts = solver_options()
        opts%rtol = tol
        opts%atol = tol
        rest = trim(adjustl(items))
        do while (len(rest) > 0)
            j = scan(rest//' ', ' ')
            item = rest(:j - 1)
            rest = trim(adjustl(rest(j:)))
            j = scan(item, '=')
            call set_option(opts, item(:j - 1), item(j + 1:), stat, msg)
            if (stat /= 0) call die_usage(prog, msg)
        end do
    end function options_for

    !> One solve from the test set's start to t = 3: x, v there, statistics, status.
    subroutine solve(opts, x, v, st, stat)
        type(solver_options), intent(in) :: opts
        real(wp), intent(out) :: x(4), v(4)
        type(solver_stats), intent(out) :: st
        integer, intent(out) :: stat
        type(car_axis) :: problem
        type(regdae_solver) :: solver
        problem = new_car_axis()
        call solver%init(problem, 0.0_wp, car_axis_x0, car_axis_v0, opts, stat)
        x = huge(1.0_wp)
        v = huge(1.0_wp)
        if (stat >= 0) call solver%advance(car_axis_t_end, x, stat=stat, v=v)
        st = solver%statistics()
        call solver%destroy()
    end subroutine solve

    !> A tight run: the formulation against the published solution.
    subroutine tight(name, items, tol)
        character(len=*), intent(in) :: name, items
        real(wp), intent(in) :: tol
        real(wp) :: x(4), v(4)
        type(solver_stats) :: st
        integer :: stat
        call solve(options_for(items, tol), x, v, st, stat)
        write (*, '(a)') '# check: '//name//' '//num(tol)//' '//num(maxval(abs(x - car_axis_reference(1:4))))// &
            ' '//num(maxval(abs(v - car_axis_reference(5:8))))//' '//format_int(int(st%steps))//' '// &
            status_word(stat)
    end subroutine tight

    !> The timed rows of one configuration at rtol = atol = 10^-k.
    subroutine timed(name, items, k)
        character(len=*), intent(in) :: name, items
        integer, intent(in) :: k
        type(solver_options) :: opts
        type(solver_stats) :: st
        real(wp) :: x(4), v(4), seconds(max_reps), err, digits, t_med
        integer(int64) :: c0, c1, rate
        integer :: r, stat, j
        character(len=:), allocatable :: ratios
        opts = options_for(items, 10.0_wp**(-k))
        do r = 1, max_reps
            call system_clock(c0, rate)
            call solve(opts, x, v, st, stat)
            call system_clock(c1)
            seconds(r) = real(c1 - c0, wp)/real(rate, wp)
            if ((r >= reps .and. sum(seconds(1:r)) >= min_time) .or. r >= max_reps) exit
        end do
        err = maxval(abs(x - car_axis_reference(1:4)))
        digits = -log10(max(maxval(abs(x - car_axis_reference(1:4))/(1.0_wp + abs(car_axis_reference(1:4)))), &
                            tiny(1.0_wp)))
        t_med = middle(seconds(1:r))
        ratios = '- -'
        do j = 1, size(radau5_k)
            if (radau5_k(j) == k) ratios = num(t_med/radau5_seconds(j))//' '// &
                                            num(real(st%steps, wp)/radau5_steps(j))
        end do
        if (stat == 0) then
            row_counts(1) = row_counts(1) + 1
        else if (stat < 0) then
            row_counts(2) = row_counts(2) + 1
        else
            row_counts(3) = row_counts(3) + 1
        end if
        write (*, '(a)') 'car_axis '//name//' '//num(10.0_wp**(-k))//' '//num(err)//' '//num(digits)//' '// &
            num(t_med)//' '//format_int(int(st%steps))//' '//format_int(int(st%res_evals))//' '// &
            format_int(int(st%jac_evals))//' '//format_int(int(st%lin_setups))//' '//format_int(int(st%nonlin_iters))// &
            ' '//format_int(int(st%err_test_fails))//' '//format_int(int(st%conv_fails))//' '//status_word(stat)//' '//ratios
    end subroutine timed

    !> ok, warning (the run ended, x valid, the tolerance maybe not met) or failed.
    pure function status_word(stat) result(word)
        integer, intent(in) :: stat
        character(len=:), allocatable :: word
        if (stat == 0) then
            word = 'ok'
        else if (stat > 0) then
            word = 'warning'
        else
            word = 'failed'
        end if
    end function status_word

    !> The median (the lower one of an even count): the value with at most half below it.
    pure real(wp) function middle(s)
        real(wp), intent(in) :: s(:)
        integer :: i, half
        half = (size(s) - 1)/2
        middle = s(1)
        do i = 1, size(s)
            if (count(s < s(i)) <= half .and. count(s <= s(i)) > half) then
                middle = s(i)
                return
            end if
        end do
    end function middle

end program car_axis_driver
