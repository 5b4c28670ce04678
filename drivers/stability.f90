!> The stability grid (not a test): trust-region runs of Example 5.1 and the
!! slider crank (index 2 and 3) over gamma, eps and rtol, and, with all options
!! at their defaults, slider-crank starts near the singular configuration with
!! an initial speed and the chain with sliders; each run classified
!!   ok           status ok and error within the bound below,
!!   failed       status failed (with the time reached),
!!   silent       status ok but off the physical branch or error above the bound,
!!   false_alarm  stopped by one of regdae's checks (branch, drift, invariant, work)
!!                although the same run without the checks ends within the bound,
!!   warned       status warning: the run ended, but an advance returned a warning (x valid,
!!                the tolerance maybe not met; code: the first warning), whatever its error.
!! Bounds: Example 5.1, max|x - (t+1)| <= 3 eps^(1/4) + 100 rtol (the layer estimate
!! 1.311 eps^(1/4) of doc/ex51.md with margin, plus the integration error); slider crank,
!! on the branch (max |th1 + th2 - pi| <= 0.1) and max theta error <=
!! max(0.1, 6 * 1.311 eps^(1/4) + 300 rtol) (six passes, each a layer; the explicit
!! oracle on the reduced ODE, which knows the branch, has errors up to 250 rtol here).
!! Index 3 uses gamma1 = gamma, gamma0 = gamma^2/2 (the paper's 2/h and 2/h^2). At most 20000
!! steps per output interval and 200000 per crank run: a cell that needs more counts as failed.
!!
!! The tuned grid (defaults=no, the default): the crank runs check the energy as regdae's
!! invariant (invariant_tol = 1 J), steps end at the outputs. The default-options grid
!! (defaults=yes): the grid's gamma, eps and rtol = atol, every other option at its default
!! (no invariant, integrator=auto, the automatic thresholds and the work-energy check).
!! crank_near (all options at their defaults but rtol = atol): the slider crank from
!! th1 = 1e-3, 1e-2, 0.1 near the singular configuration (0, pi), th2 = pi - th1, with
!! w1 = 0.5, 2, 5 rad/s, t in [0, 10], against the reduced ODE from there by CVODE at 1e-13;
!! bound: max(0.1, 300 rtol, 3 times the error of the Dormand-Prince oracle on the reduced ODE
!! at the same rtol) (a crank that spins piles up a phase error: the oracle's is 0.2 rad at
!! rtol 1e-5 and 4.5-13 rad at 1e-3 with w1 = 5; that term capped at 1 rad: a larger error is a
!! wrong answer whatever the oracle's).
!! chain_slider (the same): the chain of N = 2 ... 128 links with every other joint on the
!! slider line, t in [0, 3], against the same run at rtol = 1e-11 (N = 2: the reduced ODE);
!! bound: max(0.1, 300 rtol max|x|) on the positions (rtol is relative; the coordinates of
!! the N-link chain reach N).
!!
!! Usage: stability [problem=all|ex51|crank2|crank3|crank_near|chain_slider] [rtol=R] [gamma=G]
!!                  [checks=on|off] [defaults=yes|no]
!! (R, G: one value of the grid; checks=off: without regdae's jump, drift, invariant and
!! work checks; problem=all: the first three)
!! Output: rows 'problem gamma eps rtol status class max_err t_end code velocity_jump
!!   max_drift invariant_change work_defect switches' (status ok, warning or failed; code: regdae's
!!   status, after warnings the first warning's; the last five
!!   from the solver's statistics; for crank_near the gamma column holds th1 and the eps
!!   column w1, for chain_slider the gamma column holds N) and a last line
!!   summary cells=... ok=... failed=... silent=... false_alarms=... warned=...
!! (failed and warned cells are results, not errors: exit 0)
program stability_driver
    use regdae
    use ex51_problem, only: new_ex51, orientation_psd
    use slider_crank_problem, only: slider_crank_reduced, new_slider_crank
    use chain_problem, only: chain, new_chain, chain_start
    use reference_ode, only: integrate_reference
    use dopri5, only: dopri5_integrate
    use driver_support, only: format_int, argument, split_key_value, num, die_usage, read_number
    implicit none
    real(wp), parameter :: pi = acos(-1.0_wp)
    real(wp), parameter :: gammas(8) = [1.0e1_wp, 1.0e2_wp, 1.0e3_wp, 1.0e4_wp, 1.0e5_wp, 1.0e6_wp, 1.0e7_wp, 1.0e8_wp]
    real(wp), parameter :: epss(8) = [1.0e-2_wp, 1.0e-4_wp, 1.0e-6_wp, 1.0e-8_wp, 1.0e-10_wp, 1.0e-12_wp, 1.0e-14_wp, 0.0_wp]
    real(wp), parameter :: rtols(4) = [1.0e-3_wp, 1.0e-5_wp, 1.0e-7_wp, 1.0e-10_wp]
    integer, parameter :: max_steps = 20000   ! per output interval: a cell that needs more is 'failed'
    integer, parameter :: run_budget = 200000 ! steps per crank run: a cell that needs more is 'failed' (the
                                              ! grid's time: IDA at gamma0 = 5e15 takes millions of steps)
    character(len=*), parameter :: usage = 'usage: stability [problem=all|ex51|crank2|crank3|crank_near|chain_slider] '// &
                                           '[rtol=R] [gamma=G] [checks=on|off] [defaults=yes|no]'
    real(wp) :: crank_times(501), ref(2, 501)
    integer :: counts(5) = 0   ! ok, failed, silent, false alarms, warned
    logical :: checks = .true., defaults = .false.

    call run_grid()

contains

    subroutine run_grid()
        character(len=:), allocatable :: key, value, which
        real(wp) :: only_rtol, only_gamma
        integer :: i, k, ig, ie, ir, stat
        logical :: ok
        type(slider_crank_reduced) :: reduced

        which = 'all'
        only_rtol = -1.0_wp
        only_gamma = -1.0_wp
        do i = 1, command_argument_count()
            call split_key_value(argument(i), key, value, ok)
            if (.not. ok) call die_usage('stability', usage)
            select case (key)
            case ('problem'); which = value
                if (all(value /= [character(len=12) :: 'all', 'ex51', 'crank2', 'crank3', 'crank_near', &
                                  'chain_slider'])) &
                    call die_usage('stability', 'bad value "'//value//'" for problem (all, ex51, crank2, crank3, '// &
                                   'crank_near, chain_slider)')
            case ('rtol'); call read_number('stability', key, value, only_rtol)
                if (.not. any(rtols == only_rtol)) &
                    call die_usage('stability', 'rtol must be one of the grid''s values: 1e-3, 1e-5, 1e-7, 1e-10')
            case ('gamma'); call read_number('stability', key, value, only_gamma)
                if (.not. any(gammas == only_gamma)) &
                    call die_usage('stability', 'gamma must be one of the grid''s values: 1e1, 1e2, ..., 1e8')
            case ('checks')
                if (value /= 'on' .and. value /= 'off') call die_usage('stability', usage)
                checks = (value == 'on')
            case ('defaults')
                if (value /= 'yes' .and. value /= 'no') call die_usage('stability', usage)
                defaults = (value == 'yes')
            case default; call die_usage('stability', usage)
            end select
        end do
        crank_times = [(0.02_wp*k, k=0, 500)]
        call integrate_reference(reduced, 0.0_wp, [pi/2, 0.0_wp], crank_times, ref, 1.0e-13_wp, 1.0e-13_wp, stat)
        write (*, '(a)') '# problem gamma eps rtol status class max_err t_end code velocity_jump max_drift '// &
            'invariant_change work_defect switches'
        do ir = 1, size(rtols)
            if (only_rtol > 0.0_wp .and. rtols(ir) /= only_rtol) cycle
            if (which == 'crank_near') call crank_near_cells(rtols(ir))
            if (which == 'chain_slider') call chain_slider_cells(rtols(ir))
            if (which == 'crank_near' .or. which == 'chain_slider') cycle
            do ie = 1, size(epss)
                do ig = 1, size(gammas)
                    if (only_gamma > 0.0_wp .and. gammas(ig) /= only_gamma) cycle
                    if (which == 'all' .or. which == 'ex51') call ex51_cell(gammas(ig), epss(ie), rtols(ir))
                    if (which == 'all' .or. which == 'crank2') call crank_cell(2, gammas(ig), epss(ie), rtols(ir))
                    if (which == 'all' .or. which == 'crank3') call crank_cell(3, gammas(ig), epss(ie), rtols(ir))
                end do
            end do
        end do
        write (*, '(a)') 'summary cells='//format_int(sum(counts))//' ok='//format_int(counts(1))//' failed='// &
            format_int(counts(2))//' silent='//format_int(counts(3))//' false_alarms='//format_int(counts(4))// &
            ' warned='//format_int(counts(5))
    end subroutine run_grid

    ! The options of a cell: the grid's values over the tuned or the default options.
    function cell_options(rtol) result(opts)
        real(wp), intent(in) :: rtol
        type(solver_options) :: opts
        opts%rtol = rtol
        opts%atol = rtol
        opts%max_steps = max_steps
        if (.not. defaults) then
            opts%integrator = integrator_ida   ! the tuned grid of issue 5: IDA, the paper's weights
            opts%singular_threshold = 0.05_wp
            opts%drift_tol = 1.0e-2_wp
            opts%work_tol = 0.0_wp
        end if
    end function cell_options

    ! Without regdae's checks (the false-alarm test and checks=off).
    subroutine checks_off(opts)
        type(solver_options), intent(inout) :: opts
        opts%invariant_tol = 0.0_wp
        opts%jump_tol = 0.0_wp
        opts%drift_tol = 0.0_wp
        opts%work_tol = 0.0_wp
    end subroutine checks_off

    logical function stopped_by_check(stat)
        integer, intent(in) :: stat
        stopped_by_check = any(stat == [regdae_err_branch, regdae_err_drift, regdae_err_invariant, regdae_err_work])
    end function stopped_by_check

    subroutine ex51_cell(gamma, eps, rtol)
        real(wp), intent(in) :: gamma, eps, rtol
        type(solver_options) :: opts
        type(solver_stats) :: st, k_st
        real(wp) :: err, k_err
        integer :: stat, k_stat
        logical :: within
        opts = cell_options(rtol)
        opts%gamma = gamma
        opts%eps = eps
        if (.not. defaults) opts%stop_at_output = .true.
        if (.not. checks) call checks_off(opts)
        call run_ex51(opts, stat, err, st)
        within = err <= 3.0_wp*eps**0.25_wp + 100.0_wp*rtol
        if (stopped_by_check(stat)) then   ! would the run have been right without the check?
            call checks_off(opts)
            call run_ex51(opts, k_stat, k_err, k_st)
            within = (k_stat >= 0 .and. k_err <= 3.0_wp*eps**0.25_wp + 100.0_wp*rtol)
        end if
        call classify('ex51', num(gamma), num(eps), rtol, stat, err, within, st)
    end subroutine ex51_cell

    subroutine run_ex51(opts, stat, err, st)
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        real(wp), intent(out) :: err
        type(solver_stats), intent(out) :: st
        type(regdae_solver) :: solver
        real(wp) :: x(1), y(1), t
        integer :: k, first_warning
        err = 0.0_wp
        first_warning = 0
        call solver%init(new_ex51(orientation_psd), -1.0_wp, [0.0_wp], opts, stat)
        do k = 0, 200
            if (stat < 0) exit
            t = -1.0_wp + 0.01_wp*k
            call solver%advance(t, x, y, stat)
            call note_warning(first_warning, stat)
            if (stat >= 0) err = max(err, abs(x(1) - (t + 1.0_wp)))
        end do
        if (stat >= 0) stat = first_warning
        st = solver%statistics()
        call solver%destroy()
    end subroutine run_ex51

    subroutine crank_cell(index, gamma, eps, rtol)
        integer, intent(in) :: index
        real(wp), intent(in) :: gamma, eps, rtol
        type(solver_options) :: opts
        type(solver_stats) :: st, st_k
        real(wp) :: err, dev, bound, err_k, dev_k
        integer :: stat, k_stat
        logical :: within
        opts = cell_options(rtol)
        opts%index = index
        opts%gamma = gamma
        opts%gamma1 = gamma
        opts%gamma0 = gamma**2/2
        opts%eps = eps
        if (.not. defaults) opts%invariant_tol = 1.0_wp   ! energy (J): 1.7% of the potential-energy range 6 g
        if (.not. checks) call checks_off(opts)
        ! Six singular passes, each a regularization layer of 1.311 eps^(1/4) (doc/ex51.md),
        ! and the tolerance's share: the branch-knowing oracle's error is <= 250 rtol here.
        bound = max(0.1_wp, 6*1.311_wp*eps**0.25_wp + 300*rtol)
        call run_crank(opts, [pi/2, 0.0_wp], crank_times, ref, stat, err, dev, st)
        within = (dev <= 0.1_wp .and. err <= bound)
        if (stopped_by_check(stat)) then
            call checks_off(opts)
            call run_crank(opts, [pi/2, 0.0_wp], crank_times, ref, k_stat, err_k, dev_k, st_k)
            within = (k_stat >= 0 .and. dev_k <= 0.1_wp .and. err_k <= bound)
        end if
        call classify('crank'//format_int(index), num(gamma), num(eps), rtol, stat, err, within, st)
    end subroutine crank_cell

    ! The slider crank from (th1, w1) on the physical branch: max theta error against
    ! the reference rows (th1, w1) at `times`, and the largest departure from the branch.
    subroutine run_crank(opts, start, times, reference, stat, err, dev, st)
        type(solver_options), intent(in) :: opts
        real(wp), intent(in) :: start(2), times(:), reference(:, :)
        integer, intent(out) :: stat
        real(wp), intent(out) :: err, dev
        type(solver_stats), intent(out) :: st
        type(regdae_solver) :: solver
        real(wp) :: th(2)
        integer :: k, first_warning
        err = 0.0_wp
        dev = 0.0_wp
        first_warning = 0
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [start(1), pi - start(1)], [start(2), -start(2)], opts, stat)
        do k = 1, size(times)
            if (stat < 0) exit
            call solver%advance(times(k), th, stat=stat)
            call note_warning(first_warning, stat)
            if (stat >= 0) then
                err = max(err, abs(th(1) - reference(1, k)), abs(th(2) - (pi - reference(1, k))))
                dev = max(dev, abs(modulo(th(1) + th(2), 2*pi) - pi))
                st = solver%statistics()
                if (st%steps > run_budget) stat = regdae_err_integration
            end if
        end do
        if (stat >= 0) stat = first_warning
        st = solver%statistics()
        call solver%destroy()
    end subroutine run_crank

    ! All options at their defaults but rtol = atol: starts near the singular configuration.
    subroutine crank_near_cells(rtol)
        real(wp), intent(in) :: rtol
        real(wp), parameter :: th_starts(3) = [1.0e-3_wp, 1.0e-2_wp, 0.1_wp], speeds(3) = [0.5_wp, 2.0_wp, 5.0_wp]
        type(slider_crank_reduced) :: reduced
        type(solver_options) :: opts
        type(solver_stats) :: st, st_k
        real(wp) :: near_ref(2, 501), oracle(2, 501), err, dev, err_k, dev_k, bound
        integer :: i, j, stat, rstat, k_stat, steps, evals
        logical :: within
        do i = 1, size(th_starts)
            do j = 1, size(speeds)
                call integrate_reference(reduced, 0.0_wp, [th_starts(i), speeds(j)], crank_times, near_ref, &
                                         1.0e-13_wp, 1.0e-13_wp, rstat)
                opts = solver_options()
                opts%rtol = rtol
                opts%atol = rtol
                opts%max_steps = max_steps
                if (.not. checks) call checks_off(opts)
                ! the oracle's error at this rtol: a crank that spins (w1 = 5: nine turns) piles up
                ! a phase error that even Dormand-Prince on the reduced ODE has (0.2 rad at 1e-5)
                call dopri5_integrate(reduced, 0.0_wp, [th_starts(i), speeds(j)], crank_times, oracle, rtol, rtol, &
                                      steps, evals)
                bound = max(0.1_wp, 300*rtol, min(1.0_wp, 3*maxval(abs(oracle(1, :) - near_ref(1, :)))))
                call run_crank(opts, [th_starts(i), speeds(j)], crank_times, near_ref, stat, err, dev, st)
                within = (dev <= 0.1_wp .and. err <= bound)
                if (stopped_by_check(stat)) then
                    call checks_off(opts)
                    call run_crank(opts, [th_starts(i), speeds(j)], crank_times, near_ref, k_stat, err_k, dev_k, st_k)
                    within = (k_stat >= 0 .and. dev_k <= 0.1_wp .and. err_k <= bound)
                end if
                call classify('crank_near', num(th_starts(i)), num(speeds(j)), rtol, stat, err, within, st)
            end do
        end do
    end subroutine crank_near_cells

    ! All options at their defaults but rtol = atol: the chain with sliders, N = 2 ... 128.
    subroutine chain_slider_cells(rtol)
        real(wp), intent(in) :: rtol
        integer, parameter :: sizes(7) = [2, 4, 8, 16, 32, 64, 128]
        type(solver_options) :: opts
        type(solver_stats) :: st, st_k
        real(wp) :: times(31), err, err_k, bound
        real(wp), allocatable :: reference(:, :), q(:, :)
        integer :: i, k, stat, k_stat
        logical :: within
        times = [(0.1_wp*k, k=0, 30)]
        do i = 1, size(sizes)
            allocate (reference(2*sizes(i), size(times)), q(2*sizes(i), size(times)))
            opts = solver_options()
            opts%rtol = 1.0e-11_wp
            opts%atol = 1.0e-11_wp
            opts%max_steps = max_steps
            call run_chain(sizes(i), opts, times, reference, stat, st)   ! the reference run
            opts%rtol = rtol
            opts%atol = rtol
            if (.not. checks) call checks_off(opts)
            call run_chain(sizes(i), opts, times, q, stat, st)
            err = chain_error(q, reference, st%t, times)
            ! rtol is relative: the bound grows with the chain's coordinates (up to N link lengths)
            bound = max(0.1_wp, 300*rtol*maxval(abs(reference)))
            within = err <= bound
            if (stopped_by_check(stat)) then
                call checks_off(opts)
                call run_chain(sizes(i), opts, times, q, k_stat, st_k)
                err_k = chain_error(q, reference, st_k%t, times)
                within = (k_stat >= 0 .and. err_k <= bound)
            end if
            call classify('chain_slider', format_int(sizes(i)), 'auto', rtol, stat, err, within, st)
            deallocate (reference, q)
        end do
    end subroutine chain_slider_cells

    subroutine run_chain(links, opts, times, q, stat, st)
        integer, intent(in) :: links
        type(solver_options), intent(in) :: opts
        real(wp), intent(in) :: times(:)
        real(wp), intent(out) :: q(:, :)
        integer, intent(out) :: stat
        type(solver_stats), intent(out) :: st
        type(regdae_solver) :: solver
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links)
        integer :: k, first_warning
        q = huge(1.0_wp)
        first_warning = 0
        p = new_chain(links, .true., 9.81_wp)
        call chain_start(p, q0, v0)
        call solver%init(p, 0.0_wp, q0, v0, opts, stat)
        do k = 1, size(times)
            if (stat < 0) exit
            call solver%advance(times(k), q(:, k), stat=stat)
            call note_warning(first_warning, stat)
        end do
        if (stat >= 0) stat = first_warning
        st = solver%statistics()
        call solver%destroy()
    end subroutine run_chain

    ! Keep the first warning (stat > 0) of a run's advances in `first` (0: none yet): a run that
    ! ends without failure returns it as its status (`if (stat >= 0) stat = first`).
    subroutine note_warning(first, stat)
        integer, intent(inout) :: first
        integer, intent(in) :: stat
        if (first == 0 .and. stat > 0) first = stat
    end subroutine note_warning

    ! max |q - reference| over the outputs reached (t <= t_reached)
    real(wp) function chain_error(q, reference, t_reached, times) result(err)
        real(wp), intent(in) :: q(:, :), reference(:, :), t_reached, times(:)
        integer :: k
        err = 0.0_wp
        do k = 1, size(times)
            if (times(k) > t_reached) exit
            err = max(err, maxval(abs(q(:, k) - reference(:, k))))
        end do
    end function chain_error

    subroutine classify(name, first, second, rtol, stat, err, within, st)
        character(len=*), intent(in) :: name, first, second
        real(wp), intent(in) :: rtol, err
        integer, intent(in) :: stat
        logical, intent(in) :: within
        type(solver_stats), intent(in) :: st
        character(len=:), allocatable :: status, class
        if (stat < 0) then
            status = 'failed'
            class = 'failed'
            counts(2) = counts(2) + 1
            if (stopped_by_check(stat) .and. within) then
                class = 'false_alarm'
                counts(2) = counts(2) - 1
                counts(4) = counts(4) + 1
            end if
        else if (stat > 0) then   ! ended after a warning: neither ok nor silent, whatever the error
            status = 'warning'
            class = 'warned'
            counts(5) = counts(5) + 1
        else if (within) then
            status = 'ok'
            class = 'ok'
            counts(1) = counts(1) + 1
        else
            status = 'ok'
            class = 'silent'
            counts(3) = counts(3) + 1
        end if
        write (*, '(a)') name//' '//first//' '//second//' '//num(rtol)//' '//status//' '//class//' '// &
            num(err)//' '//num(st%t)//' '//format_int(stat)//' '//num(st%velocity_jump)//' '//num(st%max_drift)// &
            ' '//num(st%invariant_change)//' '//num(st%work_defect)//' '//format_int(st%switches)
    end subroutine classify

end program stability_driver
