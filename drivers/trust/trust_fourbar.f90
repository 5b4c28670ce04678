!> drivers/trust's family fourbar: the parallelogram four-bar at index 3 and 2 from 9 starts,
!! against its one-coordinate ODE by CVODE, reference method Dormand-Prince on it at R.
module trust_fourbar
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp, solver_options
    use fourbar_problem, only: fourbar_reduced, new_fourbar, fourbar_branch_start
    use reference_ode, only: integrate_reference
    use xorshift_random, only: xorshift64, new_xorshift64
    use trust_support, only: tally, weighted_error, stopped_by_check, checks_off, write_note
    use driver_support, only: num
    use trust_grid, only: trust_setup, pi, fourbar_r, fourbar_l, fourbar_g, ref_tol, ref_check_tol, &
                          signed_log_uniform
    use trust_text, only: itext, etext, list_text
    use trust_runs, only: run_record, run_mechanical
    use trust_judge, only: judge_and_print, split_at_last_warning, fold_crossings, no_reference
    use trust_children, only: oracle_run, output_times, finite_outputs, oracle_text, oracle_timeout
    implicit none
    private
    public :: fourbar_family

contains

    !> The family fourbar: its header, one row per selected cell (index 3 and 2, 6 R, 9 starts), the
    !! summary.
    subroutine fourbar_family(setup)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        type(tally) :: counts
        real(wp) :: th(9), w(9), times(200)
        real(wp), allocatable :: rtols(:)
        character(len=10) :: labels(9)
        integer :: i, ir, ix, cell
        integer, parameter :: indices(2) = [3, 2]
        call fourbar_starts(setup, th, w, labels)
        times = output_times(5.0_wp, 200)
        write (*, '(a)') '# family=fourbar: the parallelogram four-bar (r = 1, L = 2, g = 9.81, unit masses at the '// &
            'moving joints), p1 = th1, p2 = w1, th2 = 0, th3 = th1, w2 = 0, w3 = w1; tf = 5, 200 outputs'
        write (*, '(a)') '#   case = start/index; fold+0.02: th1 = 0.02 at rest (passes both folds slowly); '// &
            'turn6e-5: th1 = -6e-5 at rest (turns back 6e-5 rad before the folds 0 and -pi); randK: xorshift64 seed '// &
            '20250202, th1 in (0, 2 pi), w1 in (-8, 8); top: pi/2 at rest (unstable)'
        write (*, '(a)') '#   reference: th1'''' = -(g/r) cos th1 by CVODE (Adams) at 1e-13; reference method: '// &
            'Dormand-Prince on it at R; compared: th1, th2 (ref 0, weight 1/R), th3 (ref th1); budget '// &
            num(setup%run_budget(30.0_wp))//' s per run'
        write (*, '(a)') '#   extra columns: ref_chk = the norm of (CVODE at 1e-12 - CVODE at 1e-13) at R; '// &
            'refm = the reference method: ok, diverged, timeout, failed (as for the crank)'
        if (setup%grid_seed > 0_int64) then
            write (*, '(a,i0,a)') '#   starts from seed=', setup%grid_seed, ' (instead of the cases above): slowK = a '// &
                'slow swing near a fold, th1 = 0 or pi +- 10^[-6,-1], w1 = +-10^[-6,0]; randK: th1 in (0, 2 pi), '// &
                'w1 in (-8, 8) from this seed'
            write (*, '(a)') '#   th1 values: '//list_text(th, exact=.true.)
            write (*, '(a)') '#   w1 values: '//list_text(w, exact=.true.)
        end if
        rtols = setup%grid_rtols()
        cell = 0
        do ix = 1, size(indices)
            do ir = 1, size(rtols)
                do i = 1, size(th)
                    cell = cell + 1
                    if (.not. setup%filter%selected(cell, rtols(ir))) cycle
                    call fourbar_cell(setup, counts, cell, trim(labels(i))//'/i'//itext(indices(ix)), th(i), w(i), &
                                      indices(ix), rtols(ir), times)
                end do
            end do
        end do
        write (*, '(a)') counts%summary('fourbar')
    end subroutine fourbar_family

    subroutine fourbar_starts(setup, th, w, labels)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        real(wp), intent(out) :: th(9), w(9)
        character(len=*), intent(out) :: labels(9)
        type(xorshift64) :: gen
        integer :: i
        if (setup%grid_seed > 0_int64) then
            call seeded_fourbar_starts(setup, th, w, labels)
            return
        end if
        gen = new_xorshift64(20250202_int64)
        th(1) = 0.02_wp
        w(1) = 0.0_wp
        labels(1) = 'fold+0.02'
        ! From rest the turning points are th0 and -pi - th0 (V = 2 g r sin th1 on the branch):
        ! th0 = -6e-5 turns back 6e-5 rad before the fold at -pi (and starts 6e-5 below the one at 0).
        th(2) = -6.0e-5_wp
        w(2) = 0.0_wp
        labels(2) = 'turn6e-5'
        do i = 3, 8
            th(i) = gen%next_between(0.0_wp, 2*pi)
            w(i) = gen%next_between(-8.0_wp, 8.0_wp)
            write (labels(i), '(a,i0)') 'rand', i - 2
        end do
        th(9) = pi/2
        w(9) = 0.0_wp
        labels(9) = 'top'
    end subroutine fourbar_starts

    ! seed=S: 3 slow swings near a fold (th1 = 0 or pi plus or minus 10^[-6,-1], w1 = plus or
    ! minus 10^[-6,0]), then 6 starts in the fixed grid's ranges (th1 in (0, 2 pi), w1 in (-8, 8)).
    subroutine seeded_fourbar_starts(setup, th, w, labels)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        real(wp), intent(out) :: th(9), w(9)
        character(len=*), intent(out) :: labels(9)
        type(xorshift64) :: gen
        real(wp) :: fold
        integer :: i
        gen = setup%seeded_generator()
        do i = 1, 3
            fold = merge(0.0_wp, pi, gen%next_uniform() < 0.5_wp)
            th(i) = fold + signed_log_uniform(gen, -6.0_wp, -1.0_wp)
            w(i) = signed_log_uniform(gen, -6.0_wp, 0.0_wp)
            write (labels(i), '(a,i0)') 'slow', i
        end do
        do i = 4, 9
            th(i) = gen%next_between(0.0_wp, 2*pi)
            w(i) = gen%next_between(-8.0_wp, 8.0_wp)
            write (labels(i), '(a,i0)') 'rand', i - 3
        end do
    end subroutine seeded_fourbar_starts

    subroutine fourbar_cell(setup, counts, cell, label, th1, w1, index, rtol, times)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell, index
        character(len=*), intent(in) :: label
        real(wp), intent(in) :: th1, w1, rtol, times(:)
        type(fourbar_reduced) :: reduced
        type(run_record) :: rec, rerun
        type(solver_options) :: opts
        real(wp) :: ref(2, size(times)), chk(2, size(times)), oracle(2, size(times))
        real(wp) :: xref(3, size(times)), err, err_ref, bound, ref_chk, q0(3), v0(3)
        integer :: rstat, cstat, ostat
        character(len=:), allocatable :: omessage
        reduced%crank = fourbar_r
        reduced%gravity = fourbar_g
        call integrate_reference(reduced, 0.0_wp, [th1, w1], times, ref, ref_tol, ref_tol, rstat)
        call integrate_reference(reduced, 0.0_wp, [th1, w1], times, chk, ref_check_tol, ref_check_tol, cstat)
        if (rstat /= 0 .or. cstat /= 0) then
            call no_reference(counts, 'fourbar', cell, label, th1, w1, rtol, 'CVODE failed, flags '//itext(rstat)//' '// &
                              itext(cstat))
            return
        end if
        xref = fourbar_positions(ref)
        ref_chk = weighted_error(fourbar_positions(chk), xref, rtol, size(times))
        call oracle_run(setup%child_tag(), 'fourbar', th1, w1, rtol, times, oracle, ostat, omessage, oracle_timeout)
        err_ref = weighted_error(fourbar_positions(oracle), xref, rtol, finite_outputs(oracle))
        bound = 10.0_wp*max(1.0_wp, err_ref)
        opts = setup%cell_options(rtol)
        opts%index = index
        call fourbar_branch_start(th1, w1, q0, v0)
        call run_mechanical(new_fourbar(fourbar_r, fourbar_l, fourbar_g), q0, v0, times, opts, setup%run_budget(30.0_wp), rec)
        err = weighted_error(rec%x, xref, rtol, rec%good)
        call split_at_last_warning(rec, xref, rtol, fold_crossings(xref(1, :)), bound)
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(new_fourbar(fourbar_r, fourbar_l, fourbar_g), q0, v0, times, checks_off(opts), &
                                setup%run_budget(30.0_wp), rerun)
            rerun%err = weighted_error(rerun%x, xref, rtol, rerun%good)
        end if
        call judge_and_print(counts, 'fourbar', cell, label, th1, w1, rtol, rec, err, err_ref, bound, ref_chk, rerun, &
                             ' '//etext(ref_chk)//' '//oracle_text(ostat, oracle))
        if (ostat /= 0) call write_note('reference method: ', omessage)
    end subroutine fourbar_cell

    ! (th1, 0, th1) on the parallelogram branch from states (th1, w1).
    pure function fourbar_positions(states) result(x)
        real(wp), intent(in) :: states(:, :)
        real(wp) :: x(3, size(states, 2))
        x(1, :) = states(1, :)
        x(2, :) = 0.0_wp
        x(3, :) = states(1, :)
    end function fourbar_positions

end module trust_fourbar
