!> drivers/trust's family crank: the slider crank of Example 5.2 from 25 starts th1 at 13 speeds
!! w1, against the reduced ODE by CVODE, reference method Dormand-Prince on it at R.
module trust_crank
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp
    use slider_crank_problem, only: slider_crank_reduced, new_slider_crank
    use reference_ode, only: integrate_reference
    use xorshift_random, only: xorshift64, new_xorshift64
    use trust_support, only: tally, weighted_error, stopped_by_check, checks_off, write_note
    use driver_support, only: num, sort_ascending
    use trust_grid, only: trust_setup, pi, crank_gravity, ref_tol, ref_check_tol
    use trust_text, only: itext, etext, list_text
    use trust_runs, only: run_record, run_mechanical
    use trust_judge, only: judge_and_print, split_at_last_warning, fold_crossings, no_reference
    use trust_children, only: oracle_run, output_times, finite_outputs, oracle_text, oracle_timeout
    implicit none
    private
    public :: crank_family

contains

    !> The family crank: its header, one row per selected cell (25 th1, 6 R, 13 w1; or th1=A
    !! [w1=W] of the setup: one start, one cell per R or the one cell at an R off the grid), the summary.
    subroutine crank_family(setup)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        real(wp), parameter :: speeds(13) = [0.0_wp, 1.0e-6_wp, 1.0e-5_wp, 1.0e-4_wp, 1.0e-3_wp, 1.0e-2_wp, 0.1_wp, &
                                             0.5_wp, 1.0_wp, 2.0_wp, 5.0_wp, 10.0_wp, 20.0_wp]
        type(tally) :: counts
        real(wp) :: angles(25), times(200)
        real(wp), allocatable :: rtols(:)
        integer :: i, ir, j, cell
        angles = crank_angles(setup)
        rtols = setup%grid_rtols()
        times = output_times(10.0_wp, 200)
        write (*, '(a)') '# family=crank: the slider crank (Example 5.2, g = 9.8, index 3), p1 = th1, p2 = w1, '// &
            'th2 = pi - th1, w2 = -w1; tf = 10, 200 outputs; case thNN = the index of th1 (ascending)'
        write (*, '(a)') '#   reference: the reduced ODE by CVODE (Adams) at rtol = atol = 1e-13; reference method: '// &
            'Dormand-Prince on it at R; budget '//num(setup%run_budget(30.0_wp))//' s per run'
        if (setup%grid_seed > 0_int64) write (*, '(a,i0)') '#   starts from seed=', setup%grid_seed
        write (*, '(a)') '#   th1 values: '//list_text(angles)
        write (*, '(a)') '#   extra columns: ref_chk = the norm of (CVODE at 1e-12 - CVODE at 1e-13) at R; '// &
            'refm = the reference method: ok, diverged (err_ref over the outputs before a NaN/Inf), timeout '// &
            '(no result in '//itext(oracle_timeout)//' s: err_ref = 0), failed'
        cell = 0
        if (setup%start_th1 >= 0.0_wp .and. setup%filter%rtol > 0.0_wp .and. all(rtols /= setup%filter%rtol)) then
            ! one start at an R off the grid's (e.g. 1e-10): one cell
            call crank_cell(setup, counts, 1, 0, setup%start_th1, setup%start_w1, setup%filter%rtol, times)
            write (*, '(a)') counts%summary('crank')
            return
        end if
        if (setup%start_th1 >= 0.0_wp) then   ! one start of the caller's (the reproducers of issue 19)
            do ir = 1, size(rtols)
                cell = cell + 1
                if (.not. setup%filter%selected(cell, rtols(ir))) cycle
                call crank_cell(setup, counts, cell, 0, setup%start_th1, setup%start_w1, rtols(ir), times)
            end do
            write (*, '(a)') counts%summary('crank')
            return
        end if
        do i = 1, size(angles)
            do ir = 1, size(rtols)
                do j = 1, size(speeds)
                    cell = cell + 1
                    if (.not. setup%filter%selected(cell, rtols(ir))) cycle
                    call crank_cell(setup, counts, cell, i, angles(i), speeds(j), rtols(ir), times)
                end do
            end do
        end do
        write (*, '(a)') counts%summary('crank')
    end subroutine crank_family

    ! th1 of the crank's starts, ascending: near both singular ends, pi/2, 16 random (seed=S:
    ! the near ones log-uniform in [1e-8, 1e-1] and the random ones from seed S).
    function crank_angles(setup) result(angles)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        real(wp) :: angles(25)
        real(wp) :: near(4)
        type(xorshift64) :: gen
        integer :: i
        near = [1.0e-8_wp, 1.0e-6_wp, 1.0e-4_wp, 1.0e-2_wp]
        gen = new_xorshift64(20250101_int64)
        if (setup%grid_seed > 0_int64) then
            gen = setup%seeded_generator()
            do i = 1, size(near)
                near(i) = 10.0_wp**gen%next_between(-8.0_wp, -1.0_wp)
            end do
        end if
        angles(1:4) = near
        angles(5:8) = pi - near
        angles(9) = pi/2
        do i = 10, 25
            angles(i) = gen%next_between(0.0_wp, pi)
        end do
        call sort_ascending(angles)
    end function crank_angles

    subroutine crank_cell(setup, counts, cell, ith, th1, w1, rtol, times)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell, ith
        real(wp), intent(in) :: th1, w1, rtol, times(:)
        type(slider_crank_reduced) :: reduced
        type(run_record) :: rec, rerun
        real(wp) :: ref(2, size(times)), chk(2, size(times)), oracle(2, size(times))
        real(wp) :: xref(2, size(times)), err, err_ref, bound, ref_chk
        integer :: rstat, cstat, ostat
        character(len=8) :: label
        character(len=:), allocatable :: omessage
        write (label, '(a,i2.2)') 'th', ith
        reduced%gravity = crank_gravity
        call integrate_reference(reduced, 0.0_wp, [th1, w1], times, ref, ref_tol, ref_tol, rstat)
        call integrate_reference(reduced, 0.0_wp, [th1, w1], times, chk, ref_check_tol, ref_check_tol, cstat)
        if (rstat /= 0 .or. cstat /= 0) then
            call no_reference(counts, 'crank', cell, label, th1, w1, rtol, 'CVODE failed, flags '//itext(rstat)//' '// &
                              itext(cstat))
            return
        end if
        xref(1, :) = ref(1, :)
        xref(2, :) = pi - ref(1, :)
        ref_chk = weighted_error(crank_positions(chk), xref, rtol, size(times))
        call oracle_run(setup%child_tag(), 'crank', th1, w1, rtol, times, oracle, ostat, omessage, oracle_timeout)
        err_ref = weighted_error(crank_positions(oracle), xref, rtol, finite_outputs(oracle))
        bound = 10.0_wp*max(1.0_wp, err_ref)
        call run_mechanical(new_slider_crank(crank_gravity), [th1, pi - th1], [w1, -w1], times, setup%cell_options(rtol), &
                            setup%run_budget(30.0_wp), rec)
        err = weighted_error(rec%x, xref, rtol, rec%good)
        call split_at_last_warning(rec, xref, rtol, fold_crossings(xref(1, :)), bound)
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(new_slider_crank(crank_gravity), [th1, pi - th1], [w1, -w1], times, &
                                checks_off(setup%cell_options(rtol)), setup%run_budget(30.0_wp), rerun)
            rerun%err = weighted_error(rerun%x, xref, rtol, rerun%good)
        end if
        call judge_and_print(counts, 'crank', cell, trim(label), th1, w1, rtol, rec, err, err_ref, bound, ref_chk, rerun, &
                             ' '//etext(ref_chk)//' '//oracle_text(ostat, oracle))
        if (ostat /= 0) call write_note('reference method: ', omessage)
    end subroutine crank_cell

    ! (th1, pi - th1) from states (th1, w1) of the reduced ODE.
    pure function crank_positions(states) result(x)
        real(wp), intent(in) :: states(:, :)
        real(wp) :: x(2, size(states, 2))
        x(1, :) = states(1, :)
        x(2, :) = pi - states(1, :)
    end function crank_positions

end module trust_crank
