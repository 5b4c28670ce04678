!> drivers/trust's families chain (t in [0, 1], N = 2 ... 4096) and chain_long (t in [0, 10],
!! N = 2 ... 256): the chain of N links, plain and with sliders, against the plain IDA peer at
!! 1e-11, else the chain's reduced ODE at every N (its O(N) slopes; regdae's own tight run only
!! where the reduced ODE fails) (chain), or judged on the energy change and the violation in
!! units of a tight run's (chain_long: the reduced ODE at every N, regdae's where it fails);
!! reference methods the peer at R and Dormand-Prince on the slider crank's reduced ODE.
module trust_chain
    use regdae, only: wp, solver_options, formulation_augmented
    use chain_problem, only: chain, new_chain, chain_start, chain_slider_recursive, chain_slider_joints, chain_energy_of, &
                             chain_violation, chain_plain_recursive, chain_plain_joints
    use slider_crank_problem, only: slider_crank_reduced
    use reference_ode, only: integrate_reference, ode_system
    use trust_support, only: tally, weighted_error, verdict, cell_class, stopped_by_check, checks_off, write_row, &
                             write_note, class_no_reference
    use driver_support, only: num
    use trust_grid, only: trust_setup, pi, chain_gravity, ref_tol, ref_check_tol
    use trust_text, only: itext, etext
    use trust_runs, only: run_record, run_mechanical
    use trust_judge, only: judge_and_print, notes
    use trust_children, only: peer_run, oracle_run, output_times, peer_good, finite_outputs, oracle_text, &
                              oracle_timeout, peer_ref_timeout, peer_method_timeout
    implicit none
    private
    public :: chain_family

    !> The regdae reference's tolerance and eps, and its check's.
    real(wp), parameter :: chain_ref_tol = 1.0e-11_wp, chain_ref_eps = 1.0e-16_wp
    real(wp), parameter :: chain_check_tol = 1.0e-10_wp, chain_check_eps = 1.0e-14_wp
    !> A chain reference, kept for the cells of one (variant, N).
    type :: chain_reference
        logical :: slider = .false.
        integer :: links = 0
        real(wp) :: tf = 0.0_wp
        character(len=:), allocatable :: source   !! 'peer', 'regdae', 'reduced' (the chain's reduced ODE) or 'none'
        real(wp), allocatable :: x(:, :), check(:, :)
        real(wp) :: energy_change = 0.0_wp, violation = 0.0_wp, energy_scale = 0.0_wp, q_scale = 0.0_wp
    end type chain_reference

contains

    !> The family chain (t in [0, 1], N = 2 ... 4096) or, with `long`, chain_long (t in [0, 10],
    !! N = 2 ... 256): its header, the reference lines, one row per selected cell, the summary.
    subroutine chain_family(setup, long)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        logical, intent(in) :: long
        type(tally) :: counts
        type(chain_reference) :: cached
        real(wp), allocatable :: times(:), rtols(:)
        integer :: iv, in, ir, cell, nsizes, links
        logical :: slider
        character(len=:), allocatable :: name
        name = trim(merge('chain_long', 'chain     ', long))
        if (long) then
            nsizes = 8
            times = output_times(10.0_wp, 100)
        else
            nsizes = 12
            times = output_times(1.0_wp, 10)
        end if
        write (*, '(a)') '# family='//name//': the chain of N unit links, unit masses, g = 9.81, plain and with '// &
            'sliders (every even joint on y = 0), from the straight horizontal chain at rest (chain_start), t in [0, '// &
            num(times(size(times)))//'], '//itext(size(times))//' outputs; p1 = N, p2 = tf; budget '// &
            num(setup%run_budget(120.0_wp))//' s per run'
        write (*, '(a)') '#   the plain chain starts horizontal too: chain_peer (the reference) starts only there '// &
            '(a 45-degree start is not available without changing chain_peer)'
        if (long) then
            write (*, '(a)') '#   judged on the energy change dE = max |E - E(0)| and the violation max |g| at the '// &
                'outputs: err = max(dE/dE_unit, viol/viol_unit), dE_unit = dE_tight + R E_scale, viol_unit = '// &
                'viol_tight + R (1 + q_scale)'
            write (*, '(a)') '#   (dE_tight, viol_tight: the tight run''s; E_scale: the largest potential-energy drop of that '// &
                'run; q_scale: its max |q|; the tight run: '//reduced_text()//', where it fails regdae formulation=augmented '// &
                'rtol = atol = 1e-11 eps = 1e-16)'
            write (*, '(a)') '#   reference method: the peer at R (plain IDA, not regdae), plain and with the sliders '// &
                '(N > 2: the peer on the same constraints, the sliders'' too); slider N = 2 (the slider crank) '// &
                'Dormand-Prince on its reduced ODE at R; its err_ref the same over the outputs it reached (after a '// &
                'failure: those before it); bound = 10 max(1, err_ref)'
            write (*, '(a)') '#   extra columns: dE dE_unit viol viol_unit method (the reference method''s status: the '// &
                'peer''s 0 or IDA''s flag, Dormand-Prince''s ok/diverged/timeout/failed); a note gives its dE and viol'
        else
            write (*, '(a)') '#   reference: plain the peer (plain IDA, band, stabilized index 2, not regdae) at '// &
                'rtol = atol = 1e-11 checked against 1e-10; where either fails, and for the sliders, the reduced ODE: '// &
                reduced_text()//'; where it fails, from regdae itself (formulation=augmented, rtol = atol = 1e-11, '// &
                'eps = 1e-16; check: 1e-10 with eps = 1e-14); ref_src says which'
            write (*, '(a)') '#   reference method: plain the peer at R; slider N > 2 the peer at R on the same '// &
                'constraints (the sliders'' too), N = 2 (the slider crank) Dormand-Prince on its reduced ODE at R'
            write (*, '(a)') '#   extra columns: ref_src ref_chk (the norm at R of check - reference) '// &
                'peer_status (the reference method''s status: the peer''s 0 or IDA''s flag, Dormand-Prince''s '// &
                'ok/diverged/timeout/failed; its err_ref over the outputs it reached)'
        end if
        rtols = setup%grid_rtols()
        cell = 0
        do iv = 1, 2
            slider = (iv == 2)
            do in = 1, nsizes
                links = 2**in
                if (links > setup%max_links) cycle
                do ir = 1, size(rtols)
                    cell = cell + 1
                    if (.not. setup%filter%selected(cell, rtols(ir))) cycle
                    call ensure_reference(setup, cached, slider, links, times, long)
                    if (long) then
                        call chain_long_cell(setup, cached, counts, cell, slider, links, rtols(ir), times)
                    else
                        call chain_cell(setup, cached, counts, cell, slider, links, rtols(ir), times)
                    end if
                end do
            end do
        end do
        write (*, '(a)') counts%summary(name)
    end subroutine chain_family

    ! The reduced ODEs, for the families' header lines.
    function reduced_text() result(text)
        character(len=:), allocatable :: text
        text = 'the slider chain''s reduced ODE in its crank angles, the plain chain''s in its link angles, at every N '// &
               '(O(N) slopes by articulated-body recursions; CVODE 1e-13, checked at 1e-12; regdae''s tight run a cross-check)'
    end function reduced_text

    ! The reference method of a chain cell at R: the peer (plain IDA, not regdae) on the same
    ! constraints (the sliders' too for N > 2), or for the slider crank (slider, N = 2)
    ! Dormand-Prince on its reduced ODE; q and v at the outputs (column 1: t = 0), GOOD the outputs
    ! it reached, TEXT its status for the row, METHOD its name for a note.
    subroutine reference_method_joints(setup, links, slider, rtol, times, q, v, stat, message, text, method, good)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        integer, intent(in) :: links
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        real(wp), intent(out) :: q(:, :), v(:, :)
        integer, intent(out) :: stat, good
        character(len=:), allocatable, intent(out) :: message, text, method
        integer :: steps
        real(wp) :: seconds
        if (.not. slider .or. links > 2) then
            call peer_run(setup%child_tag(), links, slider, rtol, times, q, stat, steps, seconds, message, &
                          peer_method_timeout, v)
            good = peer_good(q(:, 2:))
            text = itext(stat)
            method = 'peer'
        else
            call crank_method_joints(setup, rtol, times, q(:, 2:), v(:, 2:), stat, message, text)
            good = finite_outputs(q(:, 2:))
            method = 'Dormand-Prince'
        end if
    end subroutine reference_method_joints

    ! A cell of the family chain: positions against the reference at the outputs.
    subroutine chain_cell(setup, cached, counts, cell, slider, links, rtol, times)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        type(chain_reference), intent(in) :: cached   !! the reference of (slider, links)
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell, links
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        type(run_record) :: rec, rerun
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links), qpeer(2*links, size(times) + 1), vpeer(2*links, size(times) + 1)
        real(wp) :: err, err_ref, bound, ref_chk
        integer :: peer_stat, good
        character(len=:), allocatable :: label, peer_text, peer_message, method
        label = trim(merge('slider', 'plain ', slider))
        if (cached%source == 'none') then
            call unjudged_chain_run(setup, counts, 'chain', cell, label, slider, links, rtol, times)
            return
        end if
        ! the reference method (reference_method_joints); its err_ref over the outputs it reached
        call reference_method_joints(setup, links, slider, rtol, times, qpeer, vpeer, peer_stat, peer_message, &
                                     peer_text, method, good)
        err_ref = weighted_error(qpeer(:, 2:), cached%x, rtol, good)
        bound = 10.0_wp*max(1.0_wp, err_ref)
        ref_chk = weighted_error(cached%check, cached%x, rtol, size(times))
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        call run_mechanical(p, q0, v0, times, setup%cell_options(rtol), setup%run_budget(120.0_wp), rec)
        err = weighted_error(rec%x, cached%x, rtol, rec%good)
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(p, q0, v0, times, checks_off(setup%cell_options(rtol)), setup%run_budget(120.0_wp), rerun)
            rerun%err = weighted_error(rerun%x, cached%x, rtol, rerun%good)
        end if
        call judge_and_print(counts, 'chain', cell, label, real(links, wp), times(size(times)), rtol, rec, err, err_ref, bound, &
                             ref_chk, rerun, ' '//cached%source//' '//etext(ref_chk)//' '//peer_text)
        if (peer_stat /= 0) call write_note('reference method ('//method//') failed: ', peer_message)
    end subroutine chain_cell

    ! A cell of the family chain_long: the energy change and the violation in the units.
    subroutine chain_long_cell(setup, cached, counts, cell, slider, links, rtol, times)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        type(chain_reference), intent(in) :: cached   !! the reference of (slider, links)
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell, links
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        type(run_record) :: rec, rerun
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links), de, viol, de_unit, viol_unit, err, err_ref, bound, rerun_err
        real(wp) :: qpeer(2*links, size(times) + 1), vpeer(2*links, size(times) + 1)
        real(wp) :: de_ref, viol_ref
        integer :: code, rerun_stat, peer_stat, good
        character(len=:), allocatable :: label, peer_text, peer_message, method
        label = trim(merge('slider', 'plain ', slider))
        if (cached%source == 'none') then
            call unjudged_chain_run(setup, counts, 'chain_long', cell, label, slider, links, rtol, times)
            return
        end if
        ! the units: the tight run's own change and violation plus R times the scales
        de_unit = cached%energy_change + rtol*cached%energy_scale
        viol_unit = cached%violation + rtol*(1.0_wp + cached%q_scale)
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        ! the reference method (reference_method_joints): its energy change and violation in the
        ! same units over the outputs it reached
        call reference_method_joints(setup, links, slider, rtol, times, qpeer, vpeer, peer_stat, peer_message, &
                                     peer_text, method, good)
        call method_energy_and_violation(p, times, qpeer(:, 2:), vpeer(:, 2:), de_ref, viol_ref)
        err_ref = max(de_ref/de_unit, viol_ref/viol_unit)
        bound = 10.0_wp*max(1.0_wp, err_ref)
        call run_mechanical(p, q0, v0, times, setup%cell_options(rtol), setup%run_budget(120.0_wp), rec)
        call energy_and_violation(rec, de, viol)
        err = max(de/de_unit, viol/viol_unit)
        rerun_err = 0.0_wp
        rerun_stat = 0
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(p, q0, v0, times, checks_off(setup%cell_options(rtol)), setup%run_budget(120.0_wp), rerun)
            call energy_and_violation(rerun, de, viol)
            rerun_err = max(de/de_unit, viol/viol_unit)
            rerun_stat = rerun%stat
            call energy_and_violation(rec, de, viol)
        end if
        ! the units already carry the tight run's own values: no further uncertainty
        code = cell_class(rec%stat, verdict(err, bound, 0.0_wp), rerun_stat, verdict(rerun_err, bound, 0.0_wp), &
                          rec%refused)
        call counts%add(code)
        call write_row(cell, 'chain_long', label, real(links, wp), times(size(times)), rtol, rec%stat, code, err, &
                       err_ref, bound, rec%st%t, rec%st%steps, rec%seconds, &
                       ' '//etext(de)//' '//etext(de_unit)//' '//etext(viol)//' '//etext(viol_unit)//' '//peer_text)
        call notes(rec, rerun, rerun_err)
        call write_note('reference method: ', 'dE='//etext(de_ref)//' viol='//etext(viol_ref)//' over '// &
                        itext(peer_good(qpeer(:, 2:)))//' of '//itext(size(times))//' outputs')
        if (peer_stat /= 0) call write_note('reference method failed: ', peer_message)
    end subroutine chain_long_cell

    ! The chain of 2 links with the slider is the slider crank: Dormand-Prince on its reduced ODE
    ! at R from the chain's start (th1 = pi/2 at rest), mapped to the joints at `times`, joint 1 =
    ! (sin th1, -cos th1), joint 2 = (2 sin th1, 0); `text` the reference method's column.
    subroutine crank_method_joints(setup, rtol, times, q, v, stat, message, text)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        real(wp), intent(in) :: rtol, times(:)
        real(wp), intent(out) :: q(:, :), v(:, :)   !! (4, size(times))
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: message, text
        real(wp) :: crank_states(2, size(times))
        call oracle_run(setup%child_tag(), 'chain2', pi/2, 0.0_wp, rtol, times, crank_states, stat, message, oracle_timeout)
        call crank_joints(crank_states, q, v)
        text = oracle_text(stat, crank_states)
    end subroutine crank_method_joints

    ! The joints of the chain of 2 links with the slider (q, v: (4, size(states, 2))) from the
    ! slider crank's states (th1, w1): joint 1 = (sin th1, -cos th1), joint 2 = (2 sin th1, 0).
    pure subroutine crank_joints(states, q, v)
        real(wp), intent(in) :: states(:, :)
        real(wp), intent(out) :: q(:, :), v(:, :)
        q(1, :) = sin(states(1, :))
        q(2, :) = -cos(states(1, :))
        q(3, :) = 2.0_wp*sin(states(1, :))
        q(4, :) = 0.0_wp
        v(1, :) = states(2, :)*cos(states(1, :))
        v(2, :) = states(2, :)*sin(states(1, :))
        v(3, :) = 2.0_wp*states(2, :)*cos(states(1, :))
        v(4, :) = 0.0_wp
    end subroutine crank_joints

    ! The energy change and the largest violation of a reference method's run (q, v at `times`)
    ! over the outputs it reached, against the chain's start (chain_start).
    subroutine method_energy_and_violation(p, times, q, v, de, viol)
        type(chain), intent(in) :: p
        real(wp), intent(in) :: times(:), q(:, :), v(:, :)
        real(wp), intent(out) :: de, viol
        type(chain) :: probe
        real(wp) :: e, e0, gval(p%m), q0(size(q, 1)), v0(size(q, 1))
        integer :: k, ustat
        probe = p
        call chain_start(probe, q0, v0)
        ustat = 0
        call probe%invariant(0.0_wp, q0, v0, e0, ustat)
        de = 0.0_wp
        viol = 0.0_wp
        do k = 1, peer_good(q)
            call probe%invariant(times(k), q(:, k), v(:, k), e, ustat)
            de = max(de, abs(e - e0))
            call probe%constraint(times(k), q(:, k), gval, ustat)
            viol = max(viol, maxval(abs(gval)))
        end do
    end subroutine method_energy_and_violation

    ! A chain cell without a reference: the run is made and shown (status, t_end) but not judged.
    subroutine unjudged_chain_run(setup, counts, family, cell, label, slider, links, rtol, times)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        character(len=*), intent(in) :: family   !! chain or chain_long
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell, links
        character(len=*), intent(in) :: label
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        type(run_record) :: rec
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links)
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        call run_mechanical(p, q0, v0, times, setup%cell_options(rtol), setup%run_budget(120.0_wp), rec)
        call counts%add(class_no_reference)
        call write_row(cell, family, label, real(links, wp), times(size(times)), rtol, rec%stat, &
                       class_no_reference, 0.0_wp, 0.0_wp, 0.0_wp, rec%st%t, rec%st%steps, rec%seconds, '')
        call write_note('no reference (see the # reference line): not judged', '')
        if (rec%stat < 0) call write_note('message: ', rec%message)
        if (rec%stat > 0) call write_note('warning: ', rec%message)
    end subroutine unjudged_chain_run

    ! The energy change and the largest violation over the outputs a run reached.
    subroutine energy_and_violation(rec, de, viol)
        type(run_record), intent(in) :: rec
        real(wp), intent(out) :: de, viol
        integer :: k
        de = 0.0_wp
        viol = 0.0_wp
        do k = 1, rec%good
            de = max(de, abs(rec%energy(k) - rec%energy0))
            viol = max(viol, rec%violation(k))
        end do
    end subroutine energy_and_violation

    ! The reference of (slider, links) on `times` into `cached` (computed once per process).
    subroutine ensure_reference(setup, cached, slider, links, times, long)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        type(chain_reference), intent(inout) :: cached   !! the reference, kept for the cells of one (variant, N)
        logical, intent(in) :: slider, long
        integer, intent(in) :: links
        real(wp), intent(in) :: times(:)
        real(wp) :: q11(2*links, size(times) + 1), q10(2*links, size(times) + 1), t11, t10
        integer :: s11, s10, steps
        logical :: peer_ok
        type(run_record) :: tight
        character(len=:), allocatable :: m11, m10, text, rtext, check_text
        if (cached%links == links .and. (cached%slider .eqv. slider) .and. cached%tf == times(size(times))) return
        cached%links = links
        cached%slider = slider
        cached%tf = times(size(times))
        cached%source = 'none'
        peer_ok = .false.
        s11 = -1
        s10 = -1
        check_text = ''
        text = '# reference '//trim(merge('chain_long', 'chain     ', long))//' '// &
               trim(merge('slider', 'plain ', slider))//' N='//itext(links)//': '
        if (.not. slider .and. .not. long .and. .not. setup%reduced_only) then
            call peer_run(setup%child_tag(), links, .false., chain_ref_tol, times, q11, s11, steps, t11, m11, peer_ref_timeout)
            call peer_run(setup%child_tag(), links, .false., chain_check_tol, times, q10, s10, steps, t10, m10, peer_ref_timeout)
            text = text//'peer 1e-11 status='//itext(s11)//' ('//num(t11)//' s), 1e-10 status='//itext(s10)// &
                   ' ('//num(t10)//' s); '
            peer_ok = (s11 == 0 .and. s10 == 0)
            if (peer_ok) then
                cached%source = 'peer'
                cached%x = q11(:, 2:)
                cached%check = q10(:, 2:)
            end if
        end if
        ! where the peer is not the reference, the chain's reduced ODE, regdae's tight run a
        ! cross-check (over the outputs it reached); the regdae reference where the ODE fails
        if (.not. peer_ok) then
            call reduced_reference(cached, slider, links, times, rtext)
            text = text//rtext
        end if
        if (cached%source == 'none') then
            call regdae_reference(cached, slider, links, times, text, tight)
        else if (cached%source == 'reduced' .and. setup%tight_check) then
            call regdae_run(slider, links, times, chain_ref_tol, chain_ref_eps, tight)
            check_text = ' vs regdae 1e-11 (status='//itext(tight%stat)//' at t = '//num(tight%st%t)//', '// &
                         itext(int(tight%st%steps))//' steps)'
            if (tight%good > 0) &
                check_text = check_text//' dE='//etext(maxval(abs(tight%energy(:tight%good) - tight%energy0)))// &
                             ' viol='//etext(maxval(tight%violation(:tight%good)))//' over the '//itext(tight%good)// &
                             ' outputs it reached: norm(1e-8)='//etext(weighted_error(tight%x, cached%x, 1.0e-8_wp, tight%good))
            if (long .and. tight%good > 0) &
                check_text = check_text//' (to t = 1: '// &
                             etext(weighted_error(tight%x, cached%x, 1.0e-8_wp, min(tight%good, count(times <= 1.0_wp))))//')'
        end if
        if (cached%source /= 'none') then
            text = text//'source='//cached%source//' check: max|diff|='// &
                   etext(maxval(abs(cached%check - cached%x)))//' norm(1e-8)='// &
                   etext(weighted_error(cached%check, cached%x, 1.0e-8_wp, size(times)))
            ! Cross-checks: the regdae or reduced reference of the plain chain against the peer's
            ! runs that succeeded; the slider chain's N = 2 against the slider crank's reduced ODE.
            if (.not. slider .and. .not. long .and. cached%source /= 'peer') then
                if (s11 == 0) text = text//' vs peer 1e-11: norm(1e-8)='// &
                                     etext(weighted_error(q11(:, 2:), cached%x, 1.0e-8_wp, size(times)))
                if (s10 == 0) text = text//' vs peer 1e-10: norm(1e-8)='// &
                                     etext(weighted_error(q10(:, 2:), cached%x, 1.0e-8_wp, size(times)))
            end if
            if (slider .and. links == 2) text = text//' vs the reduced ODE (CVODE 1e-13): norm(1e-8)='// &
                                                etext(crank_cross_check(cached, times))
            text = text//check_text
            if (slider) text = text//' folds passed (sign changes of x_2k - x_2k-2 between outputs, all pairs; '// &
                               'a lower bound)='//itext(fold_passes(cached%x))
        end if
        write (*, '(a)') text
    end subroutine ensure_reference

    ! The regdae reference of a chain (formulation=augmented, 1e-11, eps = 1e-16) and its
    ! check (1e-10, eps = 1e-14). Fills `cached`; a run that regdae's own checks stop leaves
    ! cached%source = 'none' (no reference: the cells are run but not judged).
    subroutine regdae_reference(cached, slider, links, times, text, tight)
        type(chain_reference), intent(inout) :: cached   !! the reference, kept for the cells of one (variant, N)
        logical, intent(in) :: slider
        integer, intent(in) :: links
        real(wp), intent(in) :: times(:)
        character(len=:), allocatable, intent(inout) :: text
        type(run_record), intent(out) :: tight   !! the tight run (also when stopped)
        type(run_record) :: loose
        real(wp) :: v_ref(size(times))
        integer :: k
        call regdae_run(slider, links, times, chain_ref_tol, chain_ref_eps, tight)
        if (tight%stat < 0) then
            ! A tight run that regdae's own checks stop is no reference: the cells are not judged.
            text = text//'regdae 1e-11 status='//itext(tight%stat)//' at t = '//num(tight%st%t)//' ('// &
                   tight%message(1:min(80, len(tight%message)))//'): no reference; '
            return
        end if
        call regdae_run(slider, links, times, chain_check_tol, chain_check_eps, loose)
        text = text//'regdae 1e-11 status='//itext(tight%stat)//' ('//num(tight%seconds)//' s, '// &
               itext(int(tight%st%steps))//' steps), 1e-10 status='//itext(loose%stat)//' ('//num(loose%seconds)//' s); '
        if (loose%stat < 0) then
            text = text//'the check failed ('//loose%message(1:min(80, len(loose%message)))//'): no reference; '
            return
        end if
        cached%source = 'regdae'
        cached%x = tight%x
        cached%check = loose%x
        do k = 1, size(times)
            v_ref(k) = chain_gravity*sum(tight%x(2::2, k))   ! potential energy (unit masses); 0 at the start
        end do
        cached%energy_scale = maxval(abs(v_ref))
        cached%energy_change = maxval(abs(tight%energy - tight%energy0))
        cached%violation = maxval(tight%violation)
        cached%q_scale = maxval(abs(tight%x))
        text = text//'tight run: dE='//etext(cached%energy_change)//' viol='//etext(cached%violation)// &
               ' E_scale='//etext(cached%energy_scale)//' q_scale='//etext(cached%q_scale)//'; '
    end subroutine regdae_reference

    ! A regdae run of a chain for a reference: formulation=augmented, rtol = atol = tol, eps.
    subroutine regdae_run(slider, links, times, tol, eps, rec)
        logical, intent(in) :: slider
        integer, intent(in) :: links
        real(wp), intent(in) :: times(:), tol, eps
        type(run_record), intent(out) :: rec
        type(solver_options) :: opts
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links)
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        opts = solver_options()
        opts%formulation = formulation_augmented
        opts%rtol = tol
        opts%atol = tol
        opts%eps = eps
        call run_mechanical(p, q0, v0, times, opts, 3600.0_wp, rec)
    end subroutine regdae_run

    ! The reference of the chain of `links` links from its reduced ODE (chain_problem's
    ! chain_slider_recursive in the crank angles, or chain_plain_recursive in the link angles,
    ! their O(N) slopes equal to the dense chain_slider_reduced's and chain_plain_reduced's; CVODE
    ! at ref_tol) from chain_start (every angle pi/2, at rest), its check at ref_check_tol; the
    ! units as regdae_reference's from the joints at the outputs. Accepted (cached%source =
    ! 'reduced') when both runs succeed and agree on the units' scales (E_scale, q_scale) within
    ! reduced_scale_tol.
    subroutine reduced_reference(cached, slider, links, times, text)
        type(chain_reference), intent(out) :: cached   !! the reference (source 'reduced', else 'none')
        logical, intent(in) :: slider
        integer, intent(in) :: links
        real(wp), intent(in) :: times(:)
        character(len=:), allocatable, intent(out) :: text
        real(wp), parameter :: reduced_scale_tol = 1.0e-3_wp
        class(ode_system), allocatable :: ode
        type(chain) :: p
        real(wp), allocatable :: y0(:), tight(:, :), loose(:, :)
        real(wp) :: q0(2*links), v0(2*links)
        real(wp) :: q(2*links, size(times)), v(2*links, size(times)), qc(2*links, size(times)), vc(2*links, size(times))
        real(wp) :: e0, de, viol, e_scale, q_scale, e_scale_chk, q_scale_chk, scale_diff, cpu0, cpu1
        integer :: s_tight, s_loose, k, angles
        cached%slider = slider
        cached%links = links
        cached%tf = times(size(times))
        cached%source = 'none'
        if (slider) then
            angles = links/2
            ode = chain_slider_recursive(links=links, gravity=chain_gravity)
        else
            angles = links
            ode = chain_plain_recursive(links=links, gravity=chain_gravity)
        end if
        allocate (y0(2*angles), tight(2*angles, size(times)), loose(2*angles, size(times)))
        y0(:angles) = pi/2
        y0(angles + 1:) = 0.0_wp
        call cpu_time(cpu0)
        call integrate_reference(ode, 0.0_wp, y0, times, tight, ref_tol, ref_tol, s_tight)
        call cpu_time(cpu1)
        call integrate_reference(ode, 0.0_wp, y0, times, loose, ref_check_tol, ref_check_tol, s_loose)
        text = 'reduced ODE (CVODE) '//etext(ref_tol)//' status='//itext(s_tight)//' ('//num(cpu1 - cpu0)// &
               ' s cpu), '//etext(ref_check_tol)//' status='//itext(s_loose)//'; '
        if (s_tight /= 0 .or. s_loose /= 0) then
            text = text//'no reference; '
            return
        end if
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        e0 = chain_energy_of(p, q0, v0)
        de = 0.0_wp
        viol = 0.0_wp
        do k = 1, size(times)
            if (slider) then
                call chain_slider_joints(tight(:, k), q(:, k), v(:, k))
                call chain_slider_joints(loose(:, k), qc(:, k), vc(:, k))
            else
                call chain_plain_joints(tight(:, k), q(:, k), v(:, k))
                call chain_plain_joints(loose(:, k), qc(:, k), vc(:, k))
            end if
            de = max(de, abs(chain_energy_of(p, q(:, k), v(:, k)) - e0))
            viol = max(viol, chain_violation(p, q(:, k)))
        end do
        e_scale = chain_gravity*maxval(abs(sum(q(2::2, :), dim=1)))   ! potential energy (unit masses); 0 at the start
        q_scale = maxval(abs(q))
        e_scale_chk = chain_gravity*maxval(abs(sum(qc(2::2, :), dim=1)))
        q_scale_chk = maxval(abs(qc))
        scale_diff = max(abs(e_scale_chk - e_scale)/e_scale, abs(q_scale_chk - q_scale)/q_scale)
        text = text//'tight run: dE='//etext(de)//' viol='//etext(viol)//' E_scale='//etext(e_scale)//' q_scale='// &
               etext(q_scale)//'; check: E_scale='//etext(e_scale_chk)//' q_scale='//etext(q_scale_chk)// &
               ' (relative difference '//etext(scale_diff)//'); '
        if (.not. scale_diff <= reduced_scale_tol) then
            text = text//'the scales differ by more than '//etext(reduced_scale_tol)//': no reference; '
            return
        end if
        cached%source = 'reduced'
        cached%x = q
        cached%check = qc
        cached%energy_change = de
        cached%violation = viol
        cached%energy_scale = e_scale
        cached%q_scale = q_scale
    end subroutine reduced_reference

    ! N = 2 with the slider is the slider crank (unit masses and links, g = 9.81) from
    ! th1 = th2 = pi/2 at rest: joint 1 = (sin th1, -cos th1), joint 2 = (2 sin th1, 0).
    real(wp) function crank_cross_check(cached, times) result(norm)
        type(chain_reference), intent(in) :: cached   !! the reference of (slider, links)
        real(wp), intent(in) :: times(:)
        type(slider_crank_reduced) :: reduced
        real(wp) :: ref(2, size(times)), q(4, size(times)), v(4, size(times))
        integer :: rstat
        reduced%gravity = chain_gravity
        call integrate_reference(reduced, 0.0_wp, [pi/2, 0.0_wp], times, ref, ref_tol, ref_tol, rstat)
        call crank_joints(ref, q, v)
        norm = weighted_error(cached%x, q, 1.0e-8_wp, size(times))
        if (rstat /= 0) norm = -1.0_wp
    end function crank_cross_check

    ! The singular passes of a slider chain seen at the outputs `q(:, k)`: a pair of links
    ! (2k-1, 2k) folds (G loses rank: crank straight down or up, rod back along it) where joint
    ! 2k crosses joint 2k-2 (the pivot for k = 1) on the line, so the sign changes of
    ! x_2k - x_2k-2 between outputs, summed over the pairs (two crossings between two outputs
    ! are missed: a lower bound).
    pure integer function fold_passes(q) result(passes)
        real(wp), intent(in) :: q(:, :)
        real(wp) :: gap(size(q, 2))
        integer :: k
        passes = 0
        do k = 1, size(q, 1)/4
            gap = q(4*k - 1, :)
            if (k > 1) gap = gap - q(4*k - 5, :)
            passes = passes + count(gap(2:)*gap(:size(gap) - 1) < 0.0_wp)
        end do
    end function fold_passes

end module trust_chain
