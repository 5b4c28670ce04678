!> Benchmark (not a test): error against run time for regdae's configurations
!! and the oracles, over rtol = atol = 1e-3 ... 1e-10.
!!
!! Problems: the slider crank (index 3 and 2, 1001 outputs on [0, 10], error in theta
!! against the reduced ODE by CVODE at 1e-13) and Example 5.1 (201 outputs on [-1, 1],
!! error in x against t + 1). Oracles on the slider crank's reduced ODE (they know the
!! branch): the project's Dormand-Prince 5(4), CVODE Adams and IDA (BDF, dense, its own
!! Jacobian; drivers/common/ida_ode_oracle.f90). Time: median of at least
!! `reps` repetitions inside this process, repeated until they take `min_time` seconds
!! in all (at most 201; the machine's timing noise shrinks with the count), setup included; outputs are interpolated (no
!! stop at output times) and nothing is printed while timing.
!!
!! Usage: bench [reps=5] [min_time=0.05] [tol_from=3] [tol_to=10]
!!        [problem=all|crank|ex51|others|crank_defaults|crank_radau]
!! (reps: an integer in [1, 201]; min_time: seconds in [0, 60]; tol_from <= tol_to: integers k in
!! [1, 14] of rtol = atol = 10^-k)
!! (others: order3, redundant, singular_mass and the linear family, every method and
!! formulation; with tol_to >= 10 the explicit integrator, IDA and the oracles also run
!! at 1e-11 and 1e-12; the explicit integrator and its paired oracle also at the
!! half-decades 10^(-k-1/2).)
!! Output: '#' lines and rows 'problem config rtol max_err seconds steps res_evals jac_evals status',
!! status ok, warning (a regdae run that ended but whose advances returned a warning: x valid, the
!! tolerance maybe not met; neither ok nor failed), failed, or off_branch (a slider-crank run with
!! max |th1 + th2 - pi| > 0.1, also after a warning), and the last line
!! 'summary rows=... ok=... failed=... off_branch=... warned=...' (failed and warning rows are
!! results, not errors: exit 0).
program bench_driver
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae
    use slider_crank_problem, only: slider_crank, slider_crank_reduced, new_slider_crank
    use ex51_problem, only: new_ex51, orientation_psd
    use reference_ode, only: integrate_reference
    use dopri5, only: dopri5_integrate
    use ida_peers, only: run_peer, peer_kkt, peer_index2
    use ida_ode_oracle, only: integrate_ida
    use slider_crank_problem, only: new_redundant_slider_crank
    use order3_problem, only: new_order3, order3_exact
    use massless_problem, only: new_massless_carrier
    use pendulum_problem, only: pendulum_angle
    use theory_problems, only: theory_cases, new_theory_problem, theory_problem
    use driver_support, only: format_int, argument, split_key_value, num, die_usage, &
                              warning_log, timing_option, sort_ascending
    implicit none
    character(len=*), parameter :: prog = 'bench'
    real(wp), parameter :: pi = acos(-1.0_wp)
    integer, parameter :: branch_left = 1000   ! status of a run off the physical branch
    integer, parameter :: run_warned = 1001    ! status of a run that ended after warnings (x valid)
    integer, parameter :: max_reps = 201
    real(wp) :: crank_times(1001), ex51_times(201), ref(2, 1001), tol, min_time
    real(wp) :: mass_times(501), mass_ref(2, 501)
    character(len=12), parameter :: method_names(3) = [character(len=12) :: 'trust_region', 'direct', 'baumgarte']
    character(len=12), parameter :: formulation_names(2) = [character(len=12) :: 'eliminated', 'multiplier']
    type(pendulum_angle) :: angle
    integer :: im, jf, ic
    integer :: i, k, reps, stat, tol_from, tol_to
    integer :: row_counts(4) = 0   ! rows ok, failed, off_branch, warning
    character(len=:), allocatable :: key, value, which
    logical :: ok
    type(slider_crank_reduced) :: reduced

    reps = 5
    min_time = 0.05_wp
    tol_from = 3
    tol_to = 10
    which = 'all'
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
        if (timing_option(prog, key, value, max_reps, reps, min_time, tol_from, tol_to)) cycle
        select case (key)
        case ('problem'); which = value
            if (which /= 'all' .and. which /= 'crank' .and. which /= 'ex51' .and. which /= 'others' .and. &
                which /= 'crank_defaults' .and. which /= 'crank_radau') call die_usage(prog, 'bad problem '//value)
        case default; call die_usage(prog, 'unknown option "'//key//'"')
        end select
    end do
    if (tol_from > tol_to) call die_usage(prog, 'tol_from must be <= tol_to')
    crank_times = [(0.01_wp*k, k=0, 1000)]
    ex51_times = [(-1.0_wp + 0.01_wp*k, k=0, 200)]
    call integrate_reference(reduced, 0.0_wp, [pi/2, 0.0_wp], crank_times, ref, 1.0e-13_wp, 1.0e-13_wp, stat)
    mass_times = [(0.01_wp*k, k=0, 500)]
    call integrate_reference(angle, 0.0_wp, [pi/2, 0.0_wp], mass_times, mass_ref, 1.0e-13_wp, 1.0e-13_wp, stat)
    write (*, '(a)') '# regdae bench: median of at least '//format_int(reps)//' runs (and '//num(min_time)// &
        ' s) in one process, setup included'
    write (*, '(a)') '# problem config rtol max_err seconds steps res_evals jac_evals status'
    do k = tol_from, tol_to
        tol = 10.0_wp**(-k)
        if (which == 'crank_defaults') then   ! the defaults' rows alone (tools/benchmark.sh --trust-only)
            call crank('crank3', 'defaults', 3, 'trust_region', 0.0_wp, tol, pair=.true., defaults=.true.)
            call crank('crank3', 'defaults integrator=ida', 3, 'trust_region', 0.0_wp, tol, defaults=.true., &
                       extra='integrator=ida')
        end if
        if (which == 'crank_radau') then   ! integrator=radau against the paired oracle (doc/performance.md)
            call crank('crank3', 'defaults integrator=radau', 3, 'trust_region', 0.0_wp, tol, pair=.true., &
                       defaults=.true., extra='integrator=radau')
            call crank('crank3', 'defaults integrator=radau pass_check=no', 3, 'trust_region', 0.0_wp, tol, &
                       pair=.true., defaults=.true., extra='integrator=radau pass_check=no')
        end if
        if (which == 'all' .or. which == 'crank') then
            call crank('crank3', 'defaults', 3, 'trust_region', 0.0_wp, tol, pair=.true., defaults=.true.)
            call crank('crank3', 'defaults pass_check=no', 3, 'trust_region', 0.0_wp, tol, defaults=.true., &
                       extra='pass_check=no')
            call crank('crank3', 'defaults error_estimate=yes', 3, 'trust_region', 0.0_wp, tol, defaults=.true., &
                       extra='error_estimate=yes')
            call crank('crank3', 'defaults integrator=ida', 3, 'trust_region', 0.0_wp, tol, defaults=.true., &
                       extra='integrator=ida')
            call crank('crank3', 'trust_region eps=1e-12', 3, 'trust_region', 1.0e-12_wp, tol, pair=.true.)
            call crank('crank3', 'trust_region eps=1e-6', 3, 'trust_region', 1.0e-6_wp, tol)
            call crank('crank3', 'trust_region eps=1e-12 excluded=vy', 3, 'trust_region', 1.0e-12_wp, tol, excl='vy')
            call crank('crank3', 'baumgarte', 3, 'baumgarte', 1.0e-12_wp, tol)
            call crank('crank3', 'direct eps=1e-12', 3, 'direct', 1.0e-12_wp, tol)
            call crank('crank3', 'trust_region eps=1e-12 multiplier', 3, 'trust_region', 1.0e-12_wp, tol, &
                       formulation='multiplier')
            call crank('crank3', 'trust_region eps=1e-14 dopri5 gamma1=20', 3, 'trust_region', 1.0e-14_wp, tol, &
                       rk=.true., pair=.true.)
            call crank('crank2', 'trust_region gamma=1e6 eps=1e-12', 2, 'trust_region', 1.0e-12_wp, tol)
            call oracle('dopri5', tol)
            call oracle('cvode_adams', tol)
            call oracle('ida_bdf', tol)
            call peer(peer_kkt, 'ida index-1 KKT, no regularization', tol)
            call peer(peer_index2, 'ida index-2, no regularization', tol)
        end if
        if (which == 'all' .or. which == 'ex51') then
            do im = 1, size(method_names)
                do jf = 1, size(formulation_names)
                    call timed('ex51', tol, method_names(im), formulation_names(jf), 1.0e-12_wp)
                end do
            end do
        end if
        if (which == 'all' .or. which == 'others') then
            ! The other problems, every method and formulation (failures are rows too).
            do im = 1, size(method_names)
                do jf = 1, size(formulation_names)
                    call timed('order3', tol, method_names(im), formulation_names(jf), 1.0e-9_wp)
                    call timed('redundant', tol, method_names(im), formulation_names(jf), 1.0e-12_wp)
                    call timed('singular_mass', tol, method_names(im), formulation_names(jf), 1.0e-12_wp)
                    do ic = 1, size(theory_cases)
                        call timed('linear_'//trim(theory_cases(ic)), tol, method_names(im), formulation_names(jf), &
                                   1.0e-10_wp)
                    end do
                end do
            end do
        end if
    end do
    ! Half-decade tolerances for the explicit integrator and its paired oracle: the
    ! errors move in steps with rtol (a pass gets one step more or less), so the
    ! interpolation at matched accuracy needs the finer grid.
    if (which == 'all' .or. which == 'crank') then
        do k = 2*tol_from, 2*tol_to
            if (mod(k, 2) == 0) cycle
            tol = 10.0_wp**(-0.5_wp*k)
            call crank('crank3', 'trust_region eps=1e-14 dopri5 gamma1=20', 3, 'trust_region', 1.0e-14_wp, tol, &
                       rk=.true., pair=.true.)
            call crank('crank3', 'defaults', 3, 'trust_region', 0.0_wp, tol, pair=.true., defaults=.true.)
        end do
    end if
    ! Beyond 1e-10 for the defaults' rows alone (--trust-only: the same rows as the full run's)
    if (tol_to >= 10 .and. which == 'crank_defaults') then
        do k = 11, 12
            tol = 10.0_wp**(-k)
            call crank('crank3', 'defaults', 3, 'trust_region', 0.0_wp, tol, pair=.true., defaults=.true.)
            call crank('crank3', 'defaults integrator=ida', 3, 'trust_region', 0.0_wp, tol, defaults=.true., &
                       extra='integrator=ida')
        end do
    end if
    ! Beyond 1e-10 for the explicit integrator and the oracles: where 1e-8 is reached.
    if (tol_to >= 10 .and. (which == 'all' .or. which == 'crank')) then
        do k = 11, 12
            tol = 10.0_wp**(-k)
            call crank('crank3', 'trust_region eps=1e-14 dopri5 gamma1=20', 3, 'trust_region', 1.0e-14_wp, tol, &
                       rk=.true., pair=.true.)
            call crank('crank3', 'trust_region eps=1e-12', 3, 'trust_region', 1.0e-12_wp, tol, pair=.true.)
            call crank('crank3', 'defaults', 3, 'trust_region', 0.0_wp, tol, pair=.true., defaults=.true.)
            call crank('crank3', 'defaults integrator=ida', 3, 'trust_region', 0.0_wp, tol, defaults=.true., &
                       extra='integrator=ida')
            call oracle('dopri5', tol)
            call oracle('cvode_adams', tol)
            call oracle('ida_bdf', tol)
        end do
    end if
    write (*, '(a)') 'summary rows='//format_int(sum(row_counts))//' ok='//format_int(row_counts(1))//' failed='// &
        format_int(row_counts(2))//' off_branch='//format_int(row_counts(3))//' warned='//format_int(row_counts(4))
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (which)

contains

    ! With `pair`, every repetition also times the Dormand-Prince oracle right after
    ! regdae's run, and a row 'crank_oracle "dopri5 reduced ODE, paired: CONFIG"'
    ! follows: the ratio of the two is then immune to the machine's slow drifts.
    ! A configuration of the slider crank (index 2 or 3) with its options by hand: IDA and
    ! the paper's weights (gamma = 1e6; gamma1 = 2e3, gamma0 = 2e6) unless rk; or, with
    ! `defaults`, every option at its default but rtol = atol = tol.
    subroutine crank(name, config, index, method, eps, tol, excl, rk, pair, formulation, defaults, extra)
        character(len=*), intent(in) :: name, config, method
        integer, intent(in) :: index
        real(wp), intent(in) :: eps, tol
        character(len=*), intent(in), optional :: excl
        logical, intent(in), optional :: rk   ! explicit integrator with gamma1 = 20, gamma0 = 200
        logical, intent(in), optional :: pair
        character(len=*), intent(in), optional :: formulation
        logical, intent(in), optional :: defaults
        character(len=*), intent(in), optional :: extra   ! 'key=value' items set after the defaults
        character(len=:), allocatable :: rest, item
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        character(len=:), allocatable :: msg
        type(slider_crank) :: crank_problem
        type(warning_log) :: warnings   ! the advances' warnings (of the last repetition)
        real(wp) :: th(2), w(2), err, dev, seconds(max_reps), oracle_seconds(max_reps), states(2, 1001)
        integer(int64) :: c0, c1, rate
        integer :: r, j, stat, o_steps, o_evals
        logical :: paired
        type(slider_crank_reduced) :: sys
        type(solver_stats) :: o_st
        paired = .false.
        if (present(pair)) paired = pair
        dev = 0.0_wp
        opts%index = index
        opts%rtol = tol
        opts%atol = tol
        opts%eps = eps
        opts%gamma = 1.0e6_wp
        opts%gamma1 = 2.0e3_wp
        opts%gamma0 = 2.0e6_wp
        opts%integrator = integrator_ida
        call set_option(opts, 'method', method, stat, msg)
        if (present(excl)) call set_option(opts, 'excluded', excl, stat, msg)
        if (present(formulation)) call set_option(opts, 'formulation', formulation, stat, msg)
        if (present(rk)) then
            if (rk) then
                opts%integrator = integrator_dopri5
                opts%gamma1 = 20.0_wp
                opts%gamma0 = 200.0_wp
            end if
        end if
        if (present(defaults)) then
            if (defaults) then
                opts = solver_options()
                opts%rtol = tol
                opts%atol = tol
            end if
        end if
        if (present(extra)) then   ! 'key=value' items separated by blanks
            rest = trim(adjustl(extra))
            do while (len(rest) > 0)
                j = scan(rest//' ', ' ')
                item = rest(:j - 1)
                rest = trim(adjustl(rest(j:)))
                j = scan(item, '=')
                call set_option(opts, item(:j - 1), item(j + 1:), stat, msg)
            end do
        end if
        crank_problem = new_slider_crank(9.8_wp)
        crank_problem%analytic_curvature = .true.   ! the user-supplied g_xx(v, v) (doc/performance.md)
        do r = 1, max_reps
            call system_clock(c0, rate)
            err = 0.0_wp
            warnings = warning_log()
            call solver%init(crank_problem, 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
            do j = 1, size(crank_times)
                if (stat < 0) exit
                call solver%advance(crank_times(j), th, stat=stat, v=w)   ! x only: no multiplier at the outputs
                call warnings%note(solver, stat, crank_times(j))
                err = max(err, abs(th(1) - ref(1, j)), abs(th(2) - (pi - ref(1, j))))
                dev = max(dev, abs(modulo(th(1) + th(2), 2*pi) - pi))
            end do
            call system_clock(c1)
            seconds(r) = real(c1 - c0, wp)/real(rate, wp)
            st = solver%statistics()
            call solver%destroy()
            if (paired) then
                call system_clock(c0, rate)
                call dopri5_integrate(sys, 0.0_wp, [pi/2, 0.0_wp], crank_times, states, tol, tol, o_steps, o_evals)
                call system_clock(c1)
                oracle_seconds(r) = real(c1 - c0, wp)/real(rate, wp)
            end if
            if (enough(r, seconds)) exit
        end do
        ! A run that left the physical branch (|th1 + th2 - pi| > 0.1) is not a good run, warned or not.
        stat = ended_status(stat, warnings)
        if ((stat == regdae_success .or. stat == run_warned) .and. dev > 0.1_wp) stat = branch_left
        call row(name, config, tol, err, median(seconds(1:r)), st, stat)
        if (paired) then
            o_st%steps = o_steps
            o_st%res_evals = o_evals
            call row('crank_oracle', 'dopri5 reduced ODE, paired: '//config, tol, &
                     maxval(abs(states(1, :) - ref(1, :))), median(oracle_seconds(1:r)), o_st, regdae_success)
        end if
    end subroutine crank

    ! Median time of one problem/method/formulation at rtol = atol = tol, error
    ! against its exact or reference solution (`one_run`).
    subroutine timed(problem, tol, method, formulation, eps)
        character(len=*), intent(in) :: problem, method, formulation
        real(wp), intent(in) :: tol, eps
        type(solver_options) :: opts
        type(solver_stats) :: st
        character(len=:), allocatable :: msg
        real(wp) :: err, seconds(max_reps)
        integer(int64) :: c0, c1, rate
        integer :: r, stat
        opts%rtol = tol
        opts%atol = tol
        opts%eps = eps
        call set_option(opts, 'method', method, stat, msg)
        call set_option(opts, 'formulation', formulation, stat, msg)
        do r = 1, max_reps
            call system_clock(c0, rate)
            call one_run(problem, opts, err, st, stat)
            call system_clock(c1)
            seconds(r) = real(c1 - c0, wp)/real(rate, wp)
            if (enough(r, seconds)) exit
        end do
        call row(problem, trim(method)//' '//trim(formulation)//' eps='//num(eps), tol, err, median(seconds(1:r)), &
                 st, stat)
    end subroutine timed

    ! One run: ex51 (exact x = t + 1 on [-1, 1], 201 outputs, steps end at each),
    ! order3 (exact x = 1 + sin t on [-1, 1], 201 outputs, steps end at each),
    ! redundant (the slider crank with its constraint twice, index 3, against the
    ! reduced ODE, 1001 outputs), singular_mass (the massless carrier, mu = 1e-8,
    ! against the hand-eliminated pendulum, 501 outputs on [0, 5]), linear_<case>
    ! (the manufactured linear DAEs of doc/theory.md, exact x, 201 outputs).
    subroutine one_run(problem, opts_in, err, st, stat)
        character(len=*), intent(in) :: problem
        type(solver_options), intent(in) :: opts_in
        real(wp), intent(out) :: err
        type(solver_stats), intent(out) :: st
        integer, intent(out) :: stat
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(warning_log) :: warnings   ! the advances' warnings
        real(wp) :: x1(1), xs(1, 3), ye, th(2), q(3), t
        real(wp), allocatable :: x(:)
        integer :: j
        opts = opts_in
        err = 0.0_wp
        select case (problem)
        case ('ex51')   ! steps end at each output, else IDA steps over the layer (doc/ex51.md)
            opts%stop_at_output = .true.
            call solver%init(new_ex51(orientation_psd), -1.0_wp, [0.0_wp], opts, stat)
            do j = 1, size(ex51_times)
                if (stat < 0) exit
                call solver%advance(ex51_times(j), x1, stat=stat)
                call warnings%note(solver, stat, ex51_times(j))
                if (stat >= 0) err = max(err, abs(x1(1) - (ex51_times(j) + 1.0_wp)))
            end do
        case ('order3')
            opts%stop_at_output = .true.
            call order3_exact(-1.0_wp, xs, ye)
            call solver%init(new_order3(), -1.0_wp, xs, opts, stat)
            do j = 0, 200
                if (stat < 0) exit
                t = -1.0_wp + 0.01_wp*j
                call solver%advance(t, x1, stat=stat)
                call warnings%note(solver, stat, t)
                call order3_exact(t, xs, ye)
                if (stat >= 0) err = max(err, abs(x1(1) - xs(1, 1)))
            end do
        case ('redundant')
            call solver%init(new_redundant_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
            do j = 1, size(crank_times)
                if (stat < 0) exit
                call solver%advance(crank_times(j), th, stat=stat)
                call warnings%note(solver, stat, crank_times(j))
                if (stat >= 0) err = max(err, abs(th(1) - ref(1, j)), abs(th(2) - (pi - ref(1, j))))
            end do
        case ('singular_mass')
            opts%mass_damping = 1.0e-8_wp
            call solver%init(new_massless_carrier(9.81_wp, .false.), 0.0_wp, [1.0_wp, 0.0_wp, 0.0_wp], &
                             [0.0_wp, 0.0_wp, 0.0_wp], opts, stat)
            do j = 1, size(mass_times)
                if (stat < 0) exit
                call solver%advance(mass_times(j), q, stat=stat)
                call warnings%note(solver, stat, mass_times(j))
                if (stat >= 0) err = max(err, abs(q(1) - sin(mass_ref(1, j))), abs(q(2) + cos(mass_ref(1, j))))
            end do
        case default   ! linear_<case>
            opts%stop_at_output = .true.
            block
                type(theory_problem) :: lin
                lin = new_theory_problem(problem(8:))
                allocate (x(lin%n))
                call solver%init(lin, -1.0_wp, lin%x_exact(-1.0_wp), opts, stat)
                do j = 0, 200
                    if (stat < 0) exit
                    t = -1.0_wp + 0.01_wp*j
                    call solver%advance(t, x, stat=stat)
                    call warnings%note(solver, stat, t)
                    if (stat >= 0) err = max(err, maxval(abs(x - lin%x_exact(t))))
                end do
            end block
        end select
        stat = ended_status(stat, warnings)
        if (stat < 0) stat = regdae_err_integration
        st = solver%statistics()
        call solver%destroy()
    end subroutine one_run

    ! An oracle on the slider crank's reduced ODE (it knows the branch): the project's
    ! Dormand-Prince 5(4) ('dopri5'), CVODE Adams ('cvode_adams', the reference integrator)
    ! or IDA's BDF with its own dense Jacobian ('ida_bdf': BDF's step count without
    ! regularization, against regdae's IDA path on the index-3 system).
    subroutine oracle(name, tol)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: tol
        type(slider_crank_reduced) :: sys
        type(solver_stats) :: st
        real(wp) :: states(2, 1001), seconds(max_reps)
        integer(int64) :: c0, c1, rate
        integer :: r, stat, steps, evals, jacs
        steps = 0
        evals = 0
        jacs = 0
        stat = 0
        do r = 1, max_reps
            call system_clock(c0, rate)
            select case (name)
            case ('dopri5')
                call dopri5_integrate(sys, 0.0_wp, [pi/2, 0.0_wp], crank_times, states, tol, tol, steps, evals)
            case ('cvode_adams')
                call integrate_reference(sys, 0.0_wp, [pi/2, 0.0_wp], crank_times, states, tol, tol, stat)
            case default
                call integrate_ida(sys, 0.0_wp, [pi/2, 0.0_wp], crank_times, states, tol, tol, steps, evals, jacs, stat)
            end select
            call system_clock(c1)
            seconds(r) = real(c1 - c0, wp)/real(rate, wp)
            if (enough(r, seconds)) exit
        end do
        st%steps = steps
        st%res_evals = evals
        st%jac_evals = jacs
        call row('crank_oracle', name//' reduced ODE', tol, maxval(abs(states(1, :) - ref(1, :))), &
                 median(seconds(1:r)), st, merge(regdae_success, regdae_err_integration, stat == 0))
    end subroutine oracle

    ! IDA on the unregularized formulations (drivers/common/ida_peers.f90).
    subroutine peer(kind, config, tol)
        integer, intent(in) :: kind
        character(len=*), intent(in) :: config
        real(wp), intent(in) :: tol
        type(solver_stats) :: st
        real(wp) :: theta(2, 1001), seconds(max_reps), err, dev
        integer(int64) :: c0, c1, rate
        integer :: r, steps, evals, stat, j
        do r = 1, max_reps
            call system_clock(c0, rate)
            call run_peer(kind, tol, crank_times, theta, steps, evals, stat)
            call system_clock(c1)
            seconds(r) = real(c1 - c0, wp)/real(rate, wp)
            if (enough(r, seconds)) exit
        end do
        err = 0.0_wp
        dev = 0.0_wp
        do j = 1, size(crank_times)
            if (theta(1, j) /= theta(1, j)) exit
            err = max(err, abs(theta(1, j) - ref(1, j)), abs(theta(2, j) - (pi - ref(1, j))))
            dev = max(dev, abs(modulo(theta(1, j) + theta(2, j), 2*pi) - pi))
        end do
        st%steps = steps
        st%res_evals = evals
        if (stat /= 0) then
            stat = regdae_err_integration
        else if (dev > 0.1_wp) then
            stat = branch_left
        end if
        call row('crank_peer', config, tol, err, median(seconds(1:r)), st, stat)
    end subroutine peer

    subroutine row(name, config, tol, err, seconds, st, stat)
        character(len=*), intent(in) :: name, config
        real(wp), intent(in) :: tol, err, seconds
        type(solver_stats), intent(in) :: st
        integer, intent(in) :: stat
        write (*, '(a)') name//' "'//config//'" '//num(tol)//' '//num(err)//' '//num(seconds)//' '// &
            format_int(st%steps)//' '//format_int(st%res_evals)//' '//format_int(st%jac_evals)//' '// &
            trim(status_word(stat))
        if (stat == regdae_success) then
            row_counts(1) = row_counts(1) + 1
        else if (stat == branch_left) then
            row_counts(3) = row_counts(3) + 1
        else if (stat == run_warned) then
            row_counts(4) = row_counts(4) + 1
        else
            row_counts(2) = row_counts(2) + 1
        end if
    end subroutine row

    pure function status_word(stat) result(w)
        integer, intent(in) :: stat
        character(len=:), allocatable :: w
        if (stat == regdae_success) then
            w = 'ok'
        else if (stat == branch_left) then
            w = 'off_branch'
        else if (stat == run_warned) then
            w = 'warning'
        else
            w = 'failed'
        end if
    end function status_word

    ! The status of a regdae run that ended with `stat` after the advances' `warnings`: the
    ! failure (stat < 0), run_warned if any advance warned, else regdae_success.
    pure integer function ended_status(stat, warnings)
        integer, intent(in) :: stat
        type(warning_log), intent(in) :: warnings
        ended_status = regdae_success
        if (stat < 0) then
            ended_status = stat
        else if (warnings%count > 0) then
            ended_status = run_warned
        end if
    end function ended_status

    ! Enough repetitions: at least `reps` and `min_time` seconds in all, or max_reps.
    logical function enough(r, seconds)
        integer, intent(in) :: r
        real(wp), intent(in) :: seconds(:)
        enough = (r >= reps .and. sum(seconds(1:r)) >= min_time) .or. r >= max_reps
    end function enough

    pure real(wp) function median(v)
        real(wp), intent(in) :: v(:)
        real(wp) :: s(size(v))
        s = v
        call sort_ascending(s)
        median = s((size(s) + 1)/2)
    end function median

end program bench_driver
