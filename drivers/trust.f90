!> Can a status ok from regdae's default options be trusted? Grids the project had not
!! used, each cell a regdae run with every option at its default but rtol = atol = R,
!! judged against a reference that (but for the slider chain) does not come from regdae.
!!
!! Per cell: err = max over the outputs and components of |x_i - xref_i| / (R |xref_i| + R)
!! (x: the positions of a mechanical problem, all of x for a first-order one); err_ref, the
!! same norm for a reference method at the same rtol where the family has one (else 0);
!! bound = 10 max(1, err_ref); the class (drivers/common/trust_support.f90): ok, warned,
!! silent (status ok above the bound; also a warned run whose status-0 outputs after its last
!! warning, past a fold of the reference other than the warned pass's, are above the bound and
!! 100x every error before that fold), false_alarm (stopped by regdae's branch, drift, work-energy or invariant check while
!! the same run with jump_tol = drift_tol = work_tol = 0 ends with status >= 0 within the
!! bound), failed, refused (init refused the case), undecided (the reference's own convergence
!! check, column ref_chk, is larger than |err - bound|) and no_reference. For a failure err counts
!! the outputs before it. A run longer than its wall budget (`budget`, checked after each output)
!! is stopped with status -1000 and counts as failed. status and t_end are regdae's (the run's
!! first failure, else its first warning, else 0; statistics()%t).
!!
!! Families (cells numbered from 1 in the loop order given, the last index fastest):
!! - crank: the slider crank of Example 5.2 (index 3, g = 9.8), th2 = pi - th1, w2 = -w1, tf = 10,
!!   200 outputs; th1 (25, ascending): 1e-8, 1e-6, 1e-4, 1e-2, pi minus each, pi/2 and 16 uniform
!!   in (0, pi) from xorshift64 with seed 20250101; R = 1e-3 ... 1e-8; w1 in {0, 1e-6, ..., 20}
!!   (13). With seed=S (another grid of starts, for checking a rule on starts it was not chosen
!!   on): the 4 near-singular th1 log-uniform in [1e-8, 1e-1] and the 16 uniform ones from seed S.
!!   Reference: the reduced ODE by CVODE at 1e-13 (check: at 1e-12, column ref_chk); reference
!!   method: Dormand-Prince (drivers/common/dopri5.f90) on it at R.
!! - chain: the chain of N = 2 ... 4096 links without (plain) and with sliders, t in [0, 1],
!!   10 outputs, from the straight horizontal chain at rest (chain_start); plain: reference the
!!   plain IDA peer (drivers/common/chain_peer.f90, stabilized index 2, not regdae) at 1e-11
!!   checked against 1e-10, and where the peer fails there the regdae reference below (column
!!   ref_src); reference method the peer at R. slider: reference regdae itself (formulation =
!!   augmented, rtol = atol = 1e-11, eps = 1e-16; check: 1e-10 with eps = 1e-14); reference
!!   method as on chain_long: the peer at R on the same constraints (N > 2) and Dormand-Prince on
!!   the slider crank's reduced ODE at R (N = 2), over the outputs it reached.
!! - chain_long: the same chains on [0, 10] (100 outputs), N = 2 ... 256: judged on the energy
!!   change and the largest constraint violation at the outputs, in units of the tight regdae
!!   run's own plus R times the scales; reference method the peer at R (plain, and with the
!!   sliders for N > 2: plain IDA on the same constraints, the sliders' too; it passes the pairs'
!!   folds where its steps do not land on them) and Dormand-Prince on the slider crank's reduced
!!   ODE (N = 2 with the slider), in those units, over the outputs the method reached.
!! - fourbar: the parallelogram four-bar (drivers/problems/fourbar_problem.f90, r = 1, L = 2,
!!   g = 9.81), 9 starts, index 3 and 2, tf = 5, 200 outputs; reference th1'' = -(g/r) cos th1 by
!!   CVODE at 1e-13, reference method Dormand-Prince at R; th2_ref = 0, th3_ref = th1_ref. With
!!   seed=S: 3 slow swings near a fold (th1 = 0 or pi plus or minus 10^u, u uniform in [-6, -1];
!!   w1 = plus or minus 10^u, u in [-6, 0]) and 6 starts uniform in th1 in (0, 2 pi), w1 in (-8, 8).
!! - linear: theory_problems S1 and S2 on [-1, 1], 201 outputs (t = 0 among them), methods
!!   trust_region, direct, baumgarte, R = 1e-3 ... 1e-10; the exact solution; no reference method.
!!   With seed=S: 3 variants of each, the singular point t* uniform in (-0.9, 0.9) and C scaled by
!!   c = 10^u, u uniform in [-2, 2] (theory_problems' singular_at and scale; GB = c^2 (t - t*)^2,
!!   c^2 (t - t*)^4), t* added to the outputs; p1 = t*, p2 = c.
!! (seed=S: the crank, fourbar and linear families' grids drawn from seed S, for checking the
!! rules on starts they were not chosen on, e.g. `trust family=fourbar seed=2026`; no seed: the
!! fixed grids.)
!!
!! Usage: trust [family=crank|chain|chain_long|fourbar|linear|all] [part=k/K] [rtol=R] [cell=I]
!!              [budget=S] [th1=A [w1=W]] [seed=S] [option.KEY=VALUE ...]
!! (option.KEY=VALUE: that solver option in every cell's run instead of its default, for diagnosing a
!! cell; the header says which; the grids' figures are from the defaults)
!! (th1=A, w1=W: the crank family at that start only, one cell per R, case th00; with rtol=R off
!! the grid's R, e.g. 1e-10, the one cell at that R; A outside [0, pi], e.g. A + 2 pi k, runs
!! another representative of the same physical start)
!! (part=k/K: only the cells whose number I has mod(I, K) = k - 1; rtol=R: only the cells of that
!! R; cell=I: only cell I of the family, for reproducing one; budget: the wall budget in seconds
!! per regdae run, default 30, chains 120.)
!! Output per family: '#' header lines, one row per cell
!!   cell family case p1 p2 R status class err err_ref bound t_end steps seconds [family columns]
!! (seconds: init and advances of the run; after a failure or a warning a '#' line with the first
!! 80 characters of the solver's message), and the line
!!   summary family=NAME cells=.. ok=.. warned=.. silent=.. false_alarm=.. failed=.. refused=.. undecided=..
!!           no_reference=..
!! The chain's peer and the Dormand-Prince reference method run in child processes of this program
!! (`peer_job=...`, `oracle_job=...`) under coreutils' `timeout`: neither has a wall budget of its own
!! (some peer runs take minutes; a Dormand-Prince run whose solution blows up loops on a NaN error).
program trust_driver
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae
    use slider_crank_problem, only: slider_crank_reduced, new_slider_crank
    use chain_problem, only: chain, new_chain, chain_start
    use chain_peer, only: run_chain_peer
    use fourbar_problem, only: fourbar_reduced, new_fourbar, fourbar_branch_start
    use theory_problems, only: theory_problem, new_theory_problem
    use reference_ode, only: integrate_reference
    use dopri5, only: dopri5_integrate
    use xorshift_random, only: xorshift64, new_xorshift64
    use trust_support, only: tally, cell_filter, weighted_error, verdict, cell_class, stopped_by_check, checks_off, &
                             write_row, write_note, status_budget, class_no_reference, verdict_undecided, &
                             class_warned, class_silent
    use driver_support, only: argument, split_key_value, die_usage, read_number, read_count, num, stopwatch, &
                              clock_start, elapsed_seconds
    implicit none

    character(len=*), parameter :: prog = 'trust'
    character(len=*), parameter :: usage = 'usage: trust [family=crank|chain|chain_long|fourbar|linear|all] '// &
                                           '[part=k/K] [rtol=R] [cell=I] [budget=S] [th1=A [w1=W]] [seed=S] [option.KEY=VALUE ...]'
    real(wp), parameter :: pi = acos(-1.0_wp)
    real(wp), parameter :: mech_rtols(6) = [1.0e-3_wp, 1.0e-4_wp, 1.0e-5_wp, 1.0e-6_wp, 1.0e-7_wp, 1.0e-8_wp]
    real(wp), parameter :: linear_rtols(8) = [1.0e-3_wp, 1.0e-4_wp, 1.0e-5_wp, 1.0e-6_wp, 1.0e-7_wp, 1.0e-8_wp, &
                                              1.0e-9_wp, 1.0e-10_wp]
    !> The status of a child process (the peer, Dormand-Prince) that `timeout` stopped, or that failed.
    integer, parameter :: child_timed_out = -9124, child_failed = -9125
    !> Wall-clock limit (s) of a Dormand-Prince run (a normal one takes milliseconds).
    integer, parameter :: oracle_timeout = 10
    !> The problems' parameters: the slider crank's gravity (Example 5.2); the four-bar's r, L, g.
    real(wp), parameter :: crank_gravity = 9.8_wp, fourbar_r = 1.0_wp, fourbar_l = 2.0_wp, fourbar_g = 9.81_wp
    real(wp), parameter :: chain_gravity = 9.81_wp   !! chain_peer's, fixed there
    !> The tight tolerances of the references; the looser ones of their convergence checks.
    real(wp), parameter :: ref_tol = 1.0e-13_wp, ref_check_tol = 1.0e-12_wp
    real(wp), parameter :: chain_ref_tol = 1.0e-11_wp, chain_ref_eps = 1.0e-16_wp
    real(wp), parameter :: chain_check_tol = 1.0e-10_wp, chain_check_eps = 1.0e-14_wp
    !> Wall-clock limits (s) of a peer run: a reference, a reference-method run.
    integer, parameter :: peer_ref_timeout = 600, peer_method_timeout = 120

    !> One run: its status (the failure, else the first warning, else 0), the outputs reached
    !! with status >= 0, the positions there, energy and constraint violation there (mechanical),
    !! the statistics, the solve's seconds and the message of the failure or first warning.
    type :: run_record
        integer :: stat = 0
        integer :: good = 0
        logical :: refused = .false.
        real(wp), allocatable :: x(:, :), energy(:), violation(:)
        real(wp) :: energy0 = 0.0_wp   !! the energy at the start
        real(wp) :: err = 0.0_wp       !! the error the family measured for this run
        integer, allocatable :: out_stat(:)   !! the status of each output's advance
        logical :: silent_later = .false.     !! a later pass went wrong with status 0 (split_at_last_warning)
        type(solver_stats) :: st
        real(wp) :: seconds = 0.0_wp
        character(len=:), allocatable :: message
    end type run_record

    !> A chain reference, kept for the cells of one (variant, N).
    type :: chain_reference
        logical :: slider = .false.
        integer :: links = 0
        real(wp) :: tf = 0.0_wp
        character(len=:), allocatable :: source   !! 'peer', 'regdae' or 'none'
        real(wp), allocatable :: x(:, :), check(:, :)
        real(wp) :: energy_change = 0.0_wp, violation = 0.0_wp, energy_scale = 0.0_wp, q_scale = 0.0_wp
    end type chain_reference

    type(cell_filter) :: filter
    type(chain_reference) :: cached
    character(len=:), allocatable :: family, family_name
    real(wp) :: budget = -1.0_wp
    real(wp) :: start_th1 = -1.0_wp, start_w1 = 0.0_wp   ! th1= (w1=): the crank family at this start only
    integer(int64) :: grid_seed = 0_int64   ! seed=S: the crank, fourbar, linear grids from seed S (0: the fixed grids)
    type(solver_options) :: overrides        ! the defaults with the option.KEY=VALUE arguments applied
    character(len=:), allocatable :: override_text   ! those arguments, for the header

    call main()

contains

    subroutine main()
        character(len=:), allocatable :: key, value, msg
        integer :: i, slash, stat
        logical :: ok
        family = 'all'
        overrides = solver_options()
        override_text = ''
        do i = 1, command_argument_count()
            call split_key_value(argument(i), key, value, ok)
            if (.not. ok) call die_usage(prog, usage)
            if (index(key, 'option.') == 1) then
                call set_option(overrides, key(8:), value, stat, msg)
                if (stat /= 0) call die_usage(prog, msg)
                override_text = override_text//' '//key(8:)//'='//value
                cycle
            end if
            select case (key)
            case ('family')
                family = value
                if (all(value /= [character(len=10) :: 'crank', 'chain', 'chain_long', 'fourbar', 'linear', 'all'])) &
                    call die_usage(prog, 'bad value "'//value//'" for family (crank, chain, chain_long, fourbar, '// &
                                   'linear, all)')
            case ('part')
                slash = index(value, '/')
                if (slash < 2) call die_usage(prog, 'part must be k/K, e.g. part=1/2')
                call read_count(prog, 'K of part', value(slash + 1:), filter%parts, 1, 1000000)
                call read_count(prog, 'k of part', value(:slash - 1), filter%part, 1, filter%parts)
            case ('rtol'); call read_number(prog, key, value, filter%rtol)
                if (.not. (filter%rtol > 0.0_wp)) call die_usage(prog, 'rtol must be > 0')
            case ('cell'); call read_count(prog, key, value, filter%cell, 1, 1000000)
            case ('th1'); call read_number(prog, key, value, start_th1)
                if (.not. (abs(start_th1) < huge(1.0_wp))) call die_usage(prog, 'th1 must be finite')
            case ('w1'); call read_number(prog, key, value, start_w1)
            case ('seed'); call read_seed(value)
            case ('budget'); call read_number(prog, key, value, budget)
                if (.not. (budget > 0.0_wp)) call die_usage(prog, 'budget must be > 0')
            case ('peer_job')
                call peer_job(value)
                return
            case ('oracle_job')
                call oracle_job(value)
                return
            case default; call die_usage(prog, usage)
            end select
        end do
        write (*, '(a)') '# regdae trust: is a status ok from the default options right? Every option at its '// &
            'default but rtol = atol = R.'
        write (*, '(a)') '# err = max_(outputs, i) |x_i - xref_i| / (R |xref_i| + R); bound = 10 max(1, err_ref); '// &
            'part='//itext(filter%part)//'/'//itext(filter%parts)
        write (*, '(a)') '# columns: cell family case p1 p2 R status class err err_ref bound t_end steps seconds '// &
            '[the family''s columns]'
        if (len(override_text) > 0) write (*, '(a)') '# NOT the defaults: every run with'//override_text
        if (family == 'all' .or. family == 'crank') call crank_family()
        if (family == 'all' .or. family == 'chain') call chain_family(.false.)
        if (family == 'all' .or. family == 'chain_long') call chain_family(.true.)
        if (family == 'all' .or. family == 'fourbar') call fourbar_family()
        if (family == 'all' .or. family == 'linear') call linear_family()
    end subroutine main

    ! seed=S: a positive integer.
    subroutine read_seed(value)
        character(len=*), intent(in) :: value
        integer :: ios
        read (value, *, iostat=ios) grid_seed
        if (ios /= 0 .or. grid_seed <= 0_int64) call die_usage(prog, 'seed must be a positive integer')
    end subroutine read_seed

    ! The generator of the seeded grids: seed S, its first 16 draws dropped (a small seed's
    ! first draws are small: let the bits mix).
    function seeded_generator() result(gen)
        type(xorshift64) :: gen
        integer(int64) :: bits
        integer :: i
        gen = new_xorshift64(grid_seed)
        do i = 1, 16
            bits = gen%next_bits()
        end do
    end function seeded_generator

    ! plus or minus 10^u, u uniform in [lo, hi], the sign drawn first.
    real(wp) function signed_log_uniform(gen, lo, hi) result(x)
        type(xorshift64), intent(inout) :: gen
        real(wp), intent(in) :: lo, hi
        real(wp) :: sgn
        sgn = merge(1.0_wp, -1.0_wp, gen%next_uniform() < 0.5_wp)
        x = sgn*10.0_wp**gen%next_between(lo, hi)
    end function signed_log_uniform

    ! The wall budget of one regdae run: budget=S, else `default`.
    real(wp) function run_budget(default)
        real(wp), intent(in) :: default
        run_budget = merge(budget, default, budget > 0.0_wp)
    end function run_budget

    ! The options of a cell: the defaults (with the option.KEY=VALUE arguments) but rtol = atol = R.
    function cell_options(rtol) result(opts)
        real(wp), intent(in) :: rtol
        type(solver_options) :: opts
        opts = overrides
        opts%rtol = rtol
        opts%atol = rtol
    end function cell_options

    !---------------------------------------------------------------- runs

    ! A regdae run of a mechanical (or second-order) problem from (q0, v0) at t = 0 to the
    ! outputs `times`: the positions, the energy (the problem's invariant) and max |g| there.
    subroutine run_mechanical(problem, q0, v0, times, opts, seconds_budget, rec)
        class(second_order_problem), intent(in) :: problem
        real(wp), intent(in) :: q0(:), v0(:), times(:)
        type(solver_options), intent(in) :: opts
        real(wp), intent(in) :: seconds_budget
        type(run_record), intent(out) :: rec
        type(regdae_solver) :: solver
        type(stopwatch) :: clock
        class(second_order_problem), allocatable :: probe
        real(wp) :: q(size(q0)), v(size(q0)), gval(problem%m), e
        integer(int64) :: start
        integer :: k, stat, warning, ustat

        allocate (probe, source=problem)
        call new_record(rec, size(q0), size(times))
        ustat = 0
        call probe%invariant(0.0_wp, q0, v0, rec%energy0, ustat)
        warning = 0
        start = clock_start()
        call clock%start()
        call solver%init(problem, 0.0_wp, q0, v0, opts, stat)
        call clock%stop()
        if (stat < 0) then
            call init_failed(rec, solver, stat)
        else
            do k = 1, size(times)
                call clock%start()
                call solver%advance(times(k), q, stat=stat, v=v)
                call clock%stop()
                if (advance_failed(rec, solver, stat, warning)) exit
                rec%out_stat(k) = stat
                rec%x(:, k) = q
                rec%good = k
                ustat = 0
                call probe%invariant(times(k), q, v, e, ustat)
                rec%energy(k) = e
                call probe%constraint(times(k), q, gval, ustat)
                rec%violation(k) = maxval(abs(gval))
                if (over_budget(rec, k, times, start, seconds_budget)) exit
            end do
            if (rec%stat == 0) rec%stat = warning
        end if
        rec%st = solver%statistics()
        rec%seconds = clock%seconds()
        call solver%destroy()
    end subroutine run_mechanical

    ! A regdae run of a first-order DAE from (t0, x0) to the outputs `times`.
    subroutine run_first_order(problem, t0, x0, times, opts, seconds_budget, rec)
        class(dae_problem), intent(in) :: problem
        real(wp), intent(in) :: t0, x0(:), times(:)
        type(solver_options), intent(in) :: opts
        real(wp), intent(in) :: seconds_budget
        type(run_record), intent(out) :: rec
        type(regdae_solver) :: solver
        type(stopwatch) :: clock
        real(wp) :: x(size(x0))
        integer(int64) :: start
        integer :: k, stat, warning

        call new_record(rec, size(x0), size(times))
        warning = 0
        start = clock_start()
        call clock%start()
        call solver%init(problem, t0, x0, opts, stat)
        call clock%stop()
        if (stat < 0) then
            call init_failed(rec, solver, stat)
        else
            do k = 1, size(times)
                if (times(k) == t0) then   ! the initial point itself is an output
                    rec%x(:, k) = x0
                    rec%good = k
                    cycle
                end if
                call clock%start()
                call solver%advance(times(k), x, stat=stat)
                call clock%stop()
                if (advance_failed(rec, solver, stat, warning)) exit
                rec%out_stat(k) = stat
                rec%x(:, k) = x
                rec%good = k
                if (over_budget(rec, k, times, start, seconds_budget)) exit
            end do
            if (rec%stat == 0) rec%stat = warning
        end if
        rec%st = solver%statistics()
        rec%seconds = clock%seconds()
        call solver%destroy()
    end subroutine run_first_order

    subroutine new_record(rec, n, nout)
        type(run_record), intent(out) :: rec
        integer, intent(in) :: n, nout
        real(wp) :: nan
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        allocate (rec%x(n, nout), rec%energy(nout), rec%violation(nout), rec%out_stat(nout))
        rec%out_stat = 0
        rec%x = nan
        rec%energy = nan
        rec%violation = nan
        rec%message = ''
    end subroutine new_record

    ! init failed: a refusal (bad input, or `direct` on a GB that is not PSD) or a failure.
    ! After an advance: a failure (stat < 0) recorded with the solver's message (true: the run
    ! ends); the first warning kept in `warning` with its message.
    logical function advance_failed(rec, solver, stat, warning) result(failed)
        type(run_record), intent(inout) :: rec
        type(regdae_solver), intent(in) :: solver
        integer, intent(in) :: stat
        integer, intent(inout) :: warning
        failed = (stat < 0)
        if (failed) then
            rec%stat = stat
            rec%message = solver%message()
        else if (stat > 0 .and. warning == 0) then
            warning = stat
            rec%message = solver%message()
        end if
    end function advance_failed

    ! After output k: the driver's wall budget exhausted before the last output (recorded; true:
    ! the run ends).
    logical function over_budget(rec, k, times, start, seconds_budget) result(over)
        type(run_record), intent(inout) :: rec
        integer, intent(in) :: k
        real(wp), intent(in) :: times(:), seconds_budget
        integer(int64), intent(in) :: start
        over = (k < size(times) .and. elapsed_seconds(start) > seconds_budget)
        if (over) then
            rec%stat = status_budget
            rec%message = 'the driver''s wall budget of '//num(seconds_budget)//' s is exhausted at t = '// &
                          num(times(k))
        end if
    end function over_budget

    subroutine init_failed(rec, solver, stat)
        type(run_record), intent(inout) :: rec
        type(regdae_solver), intent(in) :: solver
        integer, intent(in) :: stat
        rec%stat = stat
        rec%message = solver%message()
        rec%refused = (stat == regdae_err_bad_input .or. stat == regdae_err_not_psd)
    end subroutine init_failed

    ! Classify a cell of the error families, rerunning it with the checks off when a check
    ! stopped it, print its row and notes, and count it.
    ! ref_chk: the reference's uncertainty in the same norm (trust_support's verdict).
    subroutine judge_and_print(counts, index, label, p1, p2, rtol, rec, err, err_ref, bound, ref_chk, rerun, extra)
        type(tally), intent(inout) :: counts
        integer, intent(in) :: index
        character(len=*), intent(in) :: label
        real(wp), intent(in) :: p1, p2, rtol
        type(run_record), intent(in) :: rec
        real(wp), intent(in) :: err, err_ref, bound, ref_chk
        type(run_record), intent(in) :: rerun     !! the checks-off run (used when a check stopped rec)
        character(len=*), intent(in) :: extra
        real(wp) :: rerun_err
        integer :: code, rerun_stat, rerun_judged
        rerun_err = 0.0_wp
        rerun_stat = 0
        rerun_judged = verdict_undecided
        if (stopped_by_check(rec%stat)) then
            rerun_err = rerun%err
            rerun_stat = rerun%stat
            rerun_judged = verdict(rerun_err, bound, ref_chk)
        end if
        code = cell_class(rec%stat, verdict(err, bound, ref_chk), rerun_stat, rerun_judged, rec%refused)
        ! a warning does not cover a later pass that goes wrong with status 0 (a branch left
        ! silently after a harmless warning: fourbar seed=77 cell 107, about 10 error weights when
        ! warned at t = 0.65 and 1.85, 1e8 at status 0 after the fold at t = 3)
        if (code == class_warned .and. rec%silent_later) code = class_silent
        call counts%add(code)
        call write_row(index, family_name, label, p1, p2, rtol, rec%stat, code, err, err_ref, bound, rec%st%t, &
                       rec%st%steps, rec%seconds, extra)
        call notes(rec, rerun, rerun_err)
    end subroutine judge_and_print

    ! rec%silent_later: after the last output returned with a warning, the reference passes a
    ! singular configuration other than the warned pass's (crossing(k): between outputs k-1 and k;
    ! the warned pass's is the crossing nearest to that output), and at an output with status 0
    ! from there on the error is beyond `bound` and 100 times the largest error at all the outputs
    ! before that crossing: a new departure at a later pass, not what the warned pass left behind
    ! (whose error grows over the passes after it: the crank's slow starts at the singular
    ! configuration, warned at t = 0, 8e4 error weights at R = 1e-8 by t = 10 without a jump).
    subroutine split_at_last_warning(rec, xref, rtol, crossing, bound)
        type(run_record), intent(inout) :: rec
        real(wp), intent(in) :: xref(:, :), rtol
        logical, intent(in) :: crossing(:)
        real(wp), intent(in) :: bound
        real(wp) :: before, e
        integer :: k, last, own
        rec%silent_later = .false.
        last = 0
        do k = 1, rec%good
            if (rec%out_stat(k) > 0) last = k
        end do
        if (last == 0) return
        own = 0
        do k = 1, size(crossing)
            if (.not. crossing(k)) cycle
            if (own == 0) then
                own = k
            else if (abs(k - last) < abs(own - last)) then
                own = k
            end if
        end do
        before = -1.0_wp   ! < 0: no later crossing yet
        do k = last + 1, rec%good
            if (crossing(k) .and. k /= own) before = weighted_error(rec%x, xref, rtol, k - 1)
            if (before < 0.0_wp .or. rec%out_stat(k) /= 0) cycle
            e = weighted_error(rec%x(:, k:k), xref(:, k:k), rtol, 1)
            if (e > max(bound, 100.0_wp*before)) rec%silent_later = .true.
        end do
    end subroutine split_at_last_warning

    ! crossing(k): th1 passes a multiple of pi (a fold of the four-bar, the crank's dead point
    ! (0, pi)) between outputs k-1 and k of the reference th1(:).
    pure function fold_crossings(th1) result(crossing)
        real(wp), intent(in) :: th1(:)
        logical :: crossing(size(th1))
        integer :: k
        crossing = .false.
        do k = 2, size(th1)
            crossing(k) = floor(th1(k - 1)/pi) /= floor(th1(k)/pi)
        end do
    end function fold_crossings

    ! The '#' lines after a row: the message of a failure or warning, the checks-off run.
    subroutine notes(rec, rerun, rerun_err)
        type(run_record), intent(in) :: rec, rerun
        real(wp), intent(in) :: rerun_err
        if (rec%stat < 0) call write_note('message: ', rec%message)
        if (rec%stat > 0) call write_note('warning: ', rec%message)
        if (stopped_by_check(rec%stat)) then
            write (*, '(a,i0,a,es11.4e3,a,es12.5e2)') '#   checks off: status=', rerun%stat, ' err=', rerun_err, &
                ' t_end=', rerun%st%t
            if (rerun%stat < 0) call write_note('checks off, message: ', rerun%message)
        end if
    end subroutine notes

    !---------------------------------------------------------------- crank

    subroutine crank_family()
        real(wp), parameter :: speeds(13) = [0.0_wp, 1.0e-6_wp, 1.0e-5_wp, 1.0e-4_wp, 1.0e-3_wp, 1.0e-2_wp, 0.1_wp, &
                                             0.5_wp, 1.0_wp, 2.0_wp, 5.0_wp, 10.0_wp, 20.0_wp]
        type(tally) :: counts
        real(wp) :: angles(25), times(200)
        integer :: i, ir, j, cell
        family_name = 'crank'
        angles = crank_angles()
        times = output_times(10.0_wp, 200)
        write (*, '(a)') '# family=crank: the slider crank (Example 5.2, g = 9.8, index 3), p1 = th1, p2 = w1, '// &
            'th2 = pi - th1, w2 = -w1; tf = 10, 200 outputs; case thNN = the index of th1 (ascending)'
        write (*, '(a)') '#   reference: the reduced ODE by CVODE (Adams) at rtol = atol = 1e-13; reference method: '// &
            'Dormand-Prince on it at R; budget '//num(run_budget(30.0_wp))//' s per run'
        if (grid_seed > 0_int64) write (*, '(a,i0)') '#   starts from seed=', grid_seed
        write (*, '(a)') '#   th1 values: '//list_text(angles)
        write (*, '(a)') '#   extra columns: ref_chk = the norm of (CVODE at 1e-12 - CVODE at 1e-13) at R; '// &
            'refm = the reference method: ok, diverged (err_ref over the outputs before a NaN/Inf), timeout '// &
            '(no result in '//itext(oracle_timeout)//' s: err_ref = 0), failed'
        cell = 0
        if (start_th1 >= 0.0_wp .and. filter%rtol > 0.0_wp .and. all(mech_rtols /= filter%rtol)) then
            ! one start at an R off the grid's (e.g. 1e-10): one cell
            call crank_cell(counts, 1, 0, start_th1, start_w1, filter%rtol, times)
            write (*, '(a)') counts%summary('crank')
            return
        end if
        if (start_th1 >= 0.0_wp) then   ! one start of the caller's (the reproducers of issue 19)
            do ir = 1, size(mech_rtols)
                cell = cell + 1
                if (.not. filter%selected(cell, mech_rtols(ir))) cycle
                call crank_cell(counts, cell, 0, start_th1, start_w1, mech_rtols(ir), times)
            end do
            write (*, '(a)') counts%summary('crank')
            return
        end if
        do i = 1, size(angles)
            do ir = 1, size(mech_rtols)
                do j = 1, size(speeds)
                    cell = cell + 1
                    if (.not. filter%selected(cell, mech_rtols(ir))) cycle
                    call crank_cell(counts, cell, i, angles(i), speeds(j), mech_rtols(ir), times)
                end do
            end do
        end do
        write (*, '(a)') counts%summary('crank')
    end subroutine crank_family

    ! th1 of the crank's starts, ascending: near both singular ends, pi/2, 16 random (seed=S:
    ! the near ones log-uniform in [1e-8, 1e-1] and the random ones from seed S).
    function crank_angles() result(angles)
        real(wp) :: angles(25)
        real(wp) :: near(4)
        type(xorshift64) :: gen
        integer :: i
        near = [1.0e-8_wp, 1.0e-6_wp, 1.0e-4_wp, 1.0e-2_wp]
        gen = new_xorshift64(20250101_int64)
        if (grid_seed > 0_int64) then
            gen = seeded_generator()
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
        call sort(angles)
    end function crank_angles

    subroutine crank_cell(counts, cell, ith, th1, w1, rtol, times)
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
            call no_reference(counts, cell, label, th1, w1, rtol, 'CVODE failed, flags '//itext(rstat)//' '// &
                              itext(cstat))
            return
        end if
        xref(1, :) = ref(1, :)
        xref(2, :) = pi - ref(1, :)
        ref_chk = weighted_error(crank_positions(chk), xref, rtol, size(times))
        call oracle_run('crank', th1, w1, rtol, times, oracle, ostat, omessage, oracle_timeout)
        err_ref = weighted_error(crank_positions(oracle), xref, rtol, finite_outputs(oracle))
        bound = 10.0_wp*max(1.0_wp, err_ref)
        call run_mechanical(new_slider_crank(crank_gravity), [th1, pi - th1], [w1, -w1], times, cell_options(rtol), &
                            run_budget(30.0_wp), rec)
        err = weighted_error(rec%x, xref, rtol, rec%good)
        call split_at_last_warning(rec, xref, rtol, fold_crossings(xref(1, :)), bound)
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(new_slider_crank(crank_gravity), [th1, pi - th1], [w1, -w1], times, &
                                checks_off(cell_options(rtol)), run_budget(30.0_wp), rerun)
            rerun%err = weighted_error(rerun%x, xref, rtol, rerun%good)
        end if
        call judge_and_print(counts, cell, trim(label), th1, w1, rtol, rec, err, err_ref, bound, ref_chk, rerun, &
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

    !---------------------------------------------------------------- fourbar

    subroutine fourbar_family()
        type(tally) :: counts
        real(wp) :: th(9), w(9), times(200)
        character(len=10) :: labels(9)
        integer :: i, ir, ix, cell
        integer, parameter :: indices(2) = [3, 2]
        family_name = 'fourbar'
        call fourbar_starts(th, w, labels)
        times = output_times(5.0_wp, 200)
        write (*, '(a)') '# family=fourbar: the parallelogram four-bar (r = 1, L = 2, g = 9.81, unit masses at the '// &
            'moving joints), p1 = th1, p2 = w1, th2 = 0, th3 = th1, w2 = 0, w3 = w1; tf = 5, 200 outputs'
        write (*, '(a)') '#   case = start/index; fold+0.02: th1 = 0.02 at rest (passes both folds slowly); '// &
            'turn6e-5: th1 = -6e-5 at rest (turns back 6e-5 rad before the folds 0 and -pi); randK: xorshift64 seed '// &
            '20250202, th1 in (0, 2 pi), w1 in (-8, 8); top: pi/2 at rest (unstable)'
        write (*, '(a)') '#   reference: th1'''' = -(g/r) cos th1 by CVODE (Adams) at 1e-13; reference method: '// &
            'Dormand-Prince on it at R; compared: th1, th2 (ref 0, weight 1/R), th3 (ref th1); budget '// &
            num(run_budget(30.0_wp))//' s per run'
        write (*, '(a)') '#   extra columns: ref_chk = the norm of (CVODE at 1e-12 - CVODE at 1e-13) at R; '// &
            'refm = the reference method: ok, diverged, timeout, failed (as for the crank)'
        if (grid_seed > 0_int64) then
            write (*, '(a,i0,a)') '#   starts from seed=', grid_seed, ' (instead of the cases above): slowK = a '// &
                'slow swing near a fold, th1 = 0 or pi +- 10^[-6,-1], w1 = +-10^[-6,0]; randK: th1 in (0, 2 pi), '// &
                'w1 in (-8, 8) from this seed'
            write (*, '(a)') '#   th1 values: '//list_text(th, exact=.true.)
            write (*, '(a)') '#   w1 values: '//list_text(w, exact=.true.)
        end if
        cell = 0
        do ix = 1, size(indices)
            do ir = 1, size(mech_rtols)
                do i = 1, size(th)
                    cell = cell + 1
                    if (.not. filter%selected(cell, mech_rtols(ir))) cycle
                    call fourbar_cell(counts, cell, trim(labels(i))//'/i'//itext(indices(ix)), th(i), w(i), &
                                      indices(ix), mech_rtols(ir), times)
                end do
            end do
        end do
        write (*, '(a)') counts%summary('fourbar')
    end subroutine fourbar_family

    subroutine fourbar_starts(th, w, labels)
        real(wp), intent(out) :: th(9), w(9)
        character(len=*), intent(out) :: labels(9)
        type(xorshift64) :: gen
        integer :: i
        if (grid_seed > 0_int64) then
            call seeded_fourbar_starts(th, w, labels)
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
    subroutine seeded_fourbar_starts(th, w, labels)
        real(wp), intent(out) :: th(9), w(9)
        character(len=*), intent(out) :: labels(9)
        type(xorshift64) :: gen
        real(wp) :: fold
        integer :: i
        gen = seeded_generator()
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

    subroutine fourbar_cell(counts, cell, label, th1, w1, index, rtol, times)
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
            call no_reference(counts, cell, label, th1, w1, rtol, 'CVODE failed, flags '//itext(rstat)//' '// &
                              itext(cstat))
            return
        end if
        xref = fourbar_positions(ref)
        ref_chk = weighted_error(fourbar_positions(chk), xref, rtol, size(times))
        call oracle_run('fourbar', th1, w1, rtol, times, oracle, ostat, omessage, oracle_timeout)
        err_ref = weighted_error(fourbar_positions(oracle), xref, rtol, finite_outputs(oracle))
        bound = 10.0_wp*max(1.0_wp, err_ref)
        opts = cell_options(rtol)
        opts%index = index
        call fourbar_branch_start(th1, w1, q0, v0)
        call run_mechanical(new_fourbar(fourbar_r, fourbar_l, fourbar_g), q0, v0, times, opts, run_budget(30.0_wp), rec)
        err = weighted_error(rec%x, xref, rtol, rec%good)
        call split_at_last_warning(rec, xref, rtol, fold_crossings(xref(1, :)), bound)
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(new_fourbar(fourbar_r, fourbar_l, fourbar_g), q0, v0, times, checks_off(opts), &
                                run_budget(30.0_wp), rerun)
            rerun%err = weighted_error(rerun%x, xref, rtol, rerun%good)
        end if
        call judge_and_print(counts, cell, label, th1, w1, rtol, rec, err, err_ref, bound, ref_chk, rerun, &
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

    !---------------------------------------------------------------- linear

    subroutine linear_family()
        character(len=2), parameter :: cases(2) = ['S1', 'S2']
        character(len=12), parameter :: methods(3) = [character(len=12) :: 'trust_region', 'direct', 'baumgarte']
        character(len=1), parameter :: letters(3) = ['a', 'b', 'c']
        type(tally) :: counts
        type(theory_problem) :: problem
        real(wp) :: grid(201), singular_at(3, 2), scale(3, 2), p1, p2
        real(wp), allocatable :: times(:)
        integer :: ic, iv, im, ir, k, cell, variants
        character(len=:), allocatable :: name
        family_name = 'linear'
        grid = [(real(k - 100, wp)/100.0_wp, k=0, 200)]
        call linear_variants(singular_at, scale, variants)
        write (*, '(a)') '# family=linear: drivers/problems/theory_problems.f90 S1 (C = t e^T, GB ~ t^2) and S2 '// &
            '(C = t^2 e^T, GB ~ t^4), B = C^T, t in [-1, 1], 201 outputs (t = -1, -0.99, ..., 0, ..., 1), '// &
            'x(-1) = x*(-1); p1 = t0, p2 = tf'
        write (*, '(a)') '#   case = problem/method; reference: the exact x*; no reference method (err_ref = 0). '// &
            'direct needs GB PSD in the core''s convention: B = C^T gives GB = C C^T >= 0 (theory_problems maps '// &
            'y_core = -y); budget '//num(run_budget(30.0_wp))//' s per run'
        if (grid_seed > 0_int64) then
            write (*, '(a,i0,a)') '#   variants from seed=', grid_seed, ' (case S1a ... S2c): C = c (t - t*)^p e^T, '// &
                't* uniform in (-0.9, 0.9), c = 10^[-2,2]; t* added to the outputs; p1 = t*, p2 = c'
            write (*, '(a)') '#   t* of S1a-c, S2a-c: '//list_text(pack(singular_at, .true.), exact=.true.)
            write (*, '(a)') '#   c of S1a-c, S2a-c: '//list_text(pack(scale, .true.), exact=.true.)
        end if
        cell = 0
        do ic = 1, size(cases)
            do iv = 1, variants
                problem = new_theory_problem(cases(ic))
                name = cases(ic)
                times = grid
                p1 = grid(1)
                p2 = grid(size(grid))
                if (grid_seed > 0_int64) then
                    problem%singular_at = singular_at(iv, ic)
                    problem%scale = scale(iv, ic)
                    name = cases(ic)//letters(iv)
                    times = [grid, singular_at(iv, ic)]
                    call sort(times)
                    p1 = singular_at(iv, ic)
                    p2 = scale(iv, ic)
                end if
                do im = 1, size(methods)
                    do ir = 1, size(linear_rtols)
                        cell = cell + 1
                        if (.not. filter%selected(cell, linear_rtols(ir))) cycle
                        call linear_cell(counts, cell, problem, name, p1, p2, trim(methods(im)), linear_rtols(ir), times)
                    end do
                end do
            end do
        end do
        write (*, '(a)') counts%summary('linear')
    end subroutine linear_family

    ! The linear family's variants of S1 and S2 (columns): one, unmoved, without a seed; with seed=S
    ! three of each, the singular point t* uniform in (-0.9, 0.9) and the scale of C log-uniform in
    ! [1e-2, 1e2].
    subroutine linear_variants(singular_at, scale, variants)
        real(wp), intent(out) :: singular_at(:, :), scale(:, :)
        integer, intent(out) :: variants
        type(xorshift64) :: gen
        integer :: ic, iv
        singular_at = 0.0_wp
        scale = 1.0_wp
        variants = 1
        if (grid_seed == 0_int64) return
        variants = size(singular_at, 1)
        gen = seeded_generator()
        do ic = 1, size(singular_at, 2)
            do iv = 1, variants
                singular_at(iv, ic) = gen%next_between(-0.9_wp, 0.9_wp)
                scale(iv, ic) = 10.0_wp**gen%next_between(-2.0_wp, 2.0_wp)
            end do
        end do
    end subroutine linear_variants

    subroutine linear_cell(counts, cell, problem, name, p1, p2, method, rtol, times)
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell
        type(theory_problem), intent(in) :: problem   !! S1 or S2, perhaps moved and scaled
        character(len=*), intent(in) :: name, method
        real(wp), intent(in) :: p1, p2, rtol, times(:)
        type(run_record) :: rec, rerun
        type(solver_options) :: opts
        real(wp) :: xref(2, size(times)), err
        integer :: k, stat
        character(len=:), allocatable :: msg
        do k = 1, size(times)
            xref(:, k) = problem%x_exact(times(k))
        end do
        opts = cell_options(rtol)
        call set_option(opts, 'method', method, stat, msg)
        call run_first_order(problem, times(1), problem%x_exact(times(1)), times, opts, run_budget(30.0_wp), rec)
        err = weighted_error(rec%x, xref, rtol, rec%good)
        call split_at_last_warning(rec, xref, rtol, spread(.false., 1, size(times)), 10.0_wp)
        ! First-order problems have no branch, drift or work check; the rerun stays unused.
        call judge_and_print(counts, cell, name//'/'//method, p1, p2, rtol, rec, err, 0.0_wp, &
                             10.0_wp, 0.0_wp, rerun, '')
    end subroutine linear_cell

    !---------------------------------------------------------------- chains

    ! chain (t in [0, 1], N = 2 ... 4096) or chain_long (t in [0, 10], N = 2 ... 256).
    subroutine chain_family(long)
        logical, intent(in) :: long
        type(tally) :: counts
        real(wp), allocatable :: times(:)
        integer :: iv, in, ir, cell, nsizes, links
        logical :: slider
        character(len=:), allocatable :: name
        name = trim(merge('chain_long', 'chain     ', long))
        family_name = name
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
            num(run_budget(120.0_wp))//' s per run'
        write (*, '(a)') '#   the plain chain starts horizontal too: chain_peer (the reference) starts only there '// &
            '(a 45-degree start is not available without changing chain_peer)'
        if (long) then
            write (*, '(a)') '#   judged on the energy change dE = max |E - E(0)| and the violation max |g| at the '// &
                'outputs: err = max(dE/dE_unit, viol/viol_unit), dE_unit = dE_tight + R E_scale, viol_unit = '// &
                'viol_tight + R (1 + q_scale)'
            write (*, '(a)') '#   (dE_tight, viol_tight: the tight run, regdae formulation=augmented rtol = atol = 1e-11 '// &
                'eps = 1e-16; E_scale: the largest potential-energy drop of that run; q_scale: its max |q|)'
            write (*, '(a)') '#   reference method: the peer at R (plain IDA, not regdae), plain and with the sliders '// &
                '(N > 2: the peer on the same constraints, the sliders'' too); slider N = 2 (the slider crank) '// &
                'Dormand-Prince on its reduced ODE at R; its err_ref the same over the outputs it reached (after a '// &
                'failure: those before it); bound = 10 max(1, err_ref)'
            write (*, '(a)') '#   extra columns: dE dE_unit viol viol_unit method (the reference method''s status: the '// &
                'peer''s 0 or IDA''s flag, Dormand-Prince''s ok/diverged/timeout/failed); a note gives its dE and viol'
        else
            write (*, '(a)') '#   plain: reference the peer (plain IDA, band, stabilized index 2, not regdae) at '// &
                'rtol = atol = 1e-11 checked against 1e-10; where either fails, the regdae reference (ref_src); '// &
                'reference method: the peer at R'
            write (*, '(a)') '#   slider: reference from regdae itself (formulation=augmented, rtol = atol = 1e-11, '// &
                'eps = 1e-16; check: 1e-10 with eps = 1e-14); reference method: N > 2 the peer at R on the same '// &
                'constraints (the sliders'' too), N = 2 (the slider crank) Dormand-Prince on its reduced ODE at R'
            write (*, '(a)') '#   extra columns: ref_src ref_chk (the norm at R of check - reference) '// &
                'peer_status (the reference method''s status: the peer''s 0 or IDA''s flag, Dormand-Prince''s '// &
                'ok/diverged/timeout/failed; its err_ref over the outputs it reached)'
        end if
        cell = 0
        do iv = 1, 2
            slider = (iv == 2)
            do in = 1, nsizes
                links = 2**in
                do ir = 1, size(mech_rtols)
                    cell = cell + 1
                    if (.not. filter%selected(cell, mech_rtols(ir))) cycle
                    call ensure_reference(slider, links, times, long)
                    if (long) then
                        call chain_long_cell(counts, cell, slider, links, mech_rtols(ir), times)
                    else
                        call chain_cell(counts, cell, slider, links, mech_rtols(ir), times)
                    end if
                end do
            end do
        end do
        write (*, '(a)') counts%summary(name)
    end subroutine chain_family

    subroutine chain_cell(counts, cell, slider, links, rtol, times)
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell, links
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        type(run_record) :: rec, rerun
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links), qpeer(2*links, size(times) + 1), vpeer(2*links, size(times) + 1)
        real(wp) :: err, err_ref, bound, ref_chk, seconds
        integer :: peer_stat, steps, good
        character(len=:), allocatable :: label, peer_text, peer_message, method
        label = trim(merge('slider', 'plain ', slider))
        if (cached%source == 'none') then
            call unjudged_chain_run(counts, cell, label, slider, links, rtol, times)
            return
        end if
        ! the reference method, as on chain_long: the peer at R (plain, and with the sliders for
        ! N > 2), N = 2 with the slider Dormand-Prince on the slider crank's reduced ODE; its
        ! err_ref over the outputs it reached
        if (.not. slider .or. links > 2) then
            call peer_run(links, slider, rtol, times, qpeer, peer_stat, steps, seconds, peer_message, &
                          peer_method_timeout)
            good = peer_good(qpeer(:, 2:))
            peer_text = itext(peer_stat)
            method = 'peer'
        else
            call crank_method_joints(rtol, times, qpeer(:, 2:), vpeer(:, 2:), peer_stat, peer_message, peer_text)
            good = finite_outputs(qpeer(:, 2:))
            method = 'Dormand-Prince'
        end if
        err_ref = weighted_error(qpeer(:, 2:), cached%x, rtol, good)
        bound = 10.0_wp*max(1.0_wp, err_ref)
        ref_chk = weighted_error(cached%check, cached%x, rtol, size(times))
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        call run_mechanical(p, q0, v0, times, cell_options(rtol), run_budget(120.0_wp), rec)
        err = weighted_error(rec%x, cached%x, rtol, rec%good)
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(p, q0, v0, times, checks_off(cell_options(rtol)), run_budget(120.0_wp), rerun)
            rerun%err = weighted_error(rerun%x, cached%x, rtol, rerun%good)
        end if
        call judge_and_print(counts, cell, label, real(links, wp), times(size(times)), rtol, rec, err, err_ref, bound, &
                             ref_chk, rerun, ' '//cached%source//' '//etext(ref_chk)//' '//peer_text)
        if (peer_stat /= 0) call write_note('reference method ('//method//') failed: ', peer_message)
    end subroutine chain_cell

    subroutine chain_long_cell(counts, cell, slider, links, rtol, times)
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell, links
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        type(run_record) :: rec, rerun
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links), de, viol, de_unit, viol_unit, err, err_ref, bound, rerun_err, seconds
        real(wp) :: qpeer(2*links, size(times) + 1), vpeer(2*links, size(times) + 1)
        real(wp) :: de_ref, viol_ref
        integer :: code, rerun_stat, peer_stat, steps
        character(len=:), allocatable :: label, peer_text, peer_message
        label = trim(merge('slider', 'plain ', slider))
        if (cached%source == 'none') then
            call unjudged_chain_run(counts, cell, label, slider, links, rtol, times)
            return
        end if
        ! the units: the tight run's own change and violation plus R times the scales
        de_unit = cached%energy_change + rtol*cached%energy_scale
        viol_unit = cached%violation + rtol*(1.0_wp + cached%q_scale)
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        ! the reference method: the peer at R (plain, and with the sliders for N > 2: plain IDA on
        ! the same constraints, the sliders' too), its energy change and violation in the same
        ! units over the outputs it reached; N = 2 with the slider Dormand-Prince on the reduced ODE
        if (.not. slider .or. links > 2) then
            call peer_run(links, slider, rtol, times, qpeer, peer_stat, steps, seconds, peer_message, &
                          peer_method_timeout, vpeer)
            peer_text = itext(peer_stat)
        else
            call crank_method_joints(rtol, times, qpeer(:, 2:), vpeer(:, 2:), peer_stat, peer_message, peer_text)
        end if
        call method_energy_and_violation(p, times, qpeer(:, 2:), vpeer(:, 2:), de_ref, viol_ref)
        err_ref = max(de_ref/de_unit, viol_ref/viol_unit)
        bound = 10.0_wp*max(1.0_wp, err_ref)
        call run_mechanical(p, q0, v0, times, cell_options(rtol), run_budget(120.0_wp), rec)
        call energy_and_violation(rec, de, viol)
        err = max(de/de_unit, viol/viol_unit)
        rerun_err = 0.0_wp
        rerun_stat = 0
        if (stopped_by_check(rec%stat)) then
            call run_mechanical(p, q0, v0, times, checks_off(cell_options(rtol)), run_budget(120.0_wp), rerun)
            call energy_and_violation(rerun, de, viol)
            rerun_err = max(de/de_unit, viol/viol_unit)
            rerun_stat = rerun%stat
            call energy_and_violation(rec, de, viol)
        end if
        ! the units already carry the tight run's own values: no further uncertainty
        code = cell_class(rec%stat, verdict(err, bound, 0.0_wp), rerun_stat, verdict(rerun_err, bound, 0.0_wp), &
                          rec%refused)
        call counts%add(code)
        call write_row(cell, family_name, label, real(links, wp), times(size(times)), rtol, rec%stat, code, err, &
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
    subroutine crank_method_joints(rtol, times, q, v, stat, message, text)
        real(wp), intent(in) :: rtol, times(:)
        real(wp), intent(out) :: q(:, :), v(:, :)   !! (4, size(times))
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: message, text
        real(wp) :: crank_states(2, size(times))
        call oracle_run('chain2', pi/2, 0.0_wp, rtol, times, crank_states, stat, message, oracle_timeout)
        q(1, :) = sin(crank_states(1, :))
        q(2, :) = -cos(crank_states(1, :))
        q(3, :) = 2.0_wp*sin(crank_states(1, :))
        q(4, :) = 0.0_wp
        v(1, :) = crank_states(2, :)*cos(crank_states(1, :))
        v(2, :) = crank_states(2, :)*sin(crank_states(1, :))
        v(3, :) = 2.0_wp*crank_states(2, :)*cos(crank_states(1, :))
        v(4, :) = 0.0_wp
        text = oracle_text(stat, crank_states)
    end subroutine crank_method_joints

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
    subroutine unjudged_chain_run(counts, cell, label, slider, links, rtol, times)
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
        call run_mechanical(p, q0, v0, times, cell_options(rtol), run_budget(120.0_wp), rec)
        call counts%add(class_no_reference)
        call write_row(cell, family_name, label, real(links, wp), times(size(times)), rtol, rec%stat, &
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
    subroutine ensure_reference(slider, links, times, long)
        logical, intent(in) :: slider, long
        integer, intent(in) :: links
        real(wp), intent(in) :: times(:)
        real(wp) :: q11(2*links, size(times) + 1), q10(2*links, size(times) + 1), t11, t10
        integer :: s11, s10, steps
        logical :: peer_ok
        character(len=:), allocatable :: m11, m10, text
        if (cached%links == links .and. (cached%slider .eqv. slider) .and. cached%tf == times(size(times))) return
        cached%links = links
        cached%slider = slider
        cached%tf = times(size(times))
        cached%source = 'none'
        peer_ok = .false.
        s11 = -1
        s10 = -1
        text = '# reference '//family_name//' '//trim(merge('slider', 'plain ', slider))//' N='//itext(links)//': '
        if (.not. slider .and. .not. long) then
            call peer_run(links, .false., chain_ref_tol, times, q11, s11, steps, t11, m11, peer_ref_timeout)
            call peer_run(links, .false., chain_check_tol, times, q10, s10, steps, t10, m10, peer_ref_timeout)
            text = text//'peer 1e-11 status='//itext(s11)//' ('//num(t11)//' s), 1e-10 status='//itext(s10)// &
                   ' ('//num(t10)//' s); '
            peer_ok = (s11 == 0 .and. s10 == 0)
            if (peer_ok) then
                cached%source = 'peer'
                cached%x = q11(:, 2:)
                cached%check = q10(:, 2:)
            end if
        end if
        if (.not. peer_ok) call regdae_reference(slider, links, times, text)
        if (cached%source /= 'none') then
            text = text//'source='//cached%source//' check: max|diff|='// &
                   etext(maxval(abs(cached%check - cached%x)))//' norm(1e-8)='// &
                   etext(weighted_error(cached%check, cached%x, 1.0e-8_wp, size(times)))
            ! Cross-checks: the regdae reference of the plain chain against the peer's runs that
            ! succeeded; the slider chain's N = 2 against the slider crank's reduced ODE.
            if (.not. slider .and. .not. long .and. cached%source == 'regdae') then
                if (s11 == 0) text = text//' vs peer 1e-11: norm(1e-8)='// &
                                     etext(weighted_error(q11(:, 2:), cached%x, 1.0e-8_wp, size(times)))
                if (s10 == 0) text = text//' vs peer 1e-10: norm(1e-8)='// &
                                     etext(weighted_error(q10(:, 2:), cached%x, 1.0e-8_wp, size(times)))
            end if
            if (slider .and. links == 2) text = text//' vs the reduced ODE (CVODE 1e-13): norm(1e-8)='// &
                                                etext(crank_cross_check(times))
            if (slider) text = text//' folds passed (sign changes of x_2k - x_2k-2 between outputs, all pairs; '// &
                               'a lower bound)='//itext(fold_passes(cached%x))
        end if
        write (*, '(a)') text
    end subroutine ensure_reference

    ! The regdae reference of a chain (formulation=augmented, 1e-11, eps = 1e-16) and its
    ! check (1e-10, eps = 1e-14). Fills `cached`; a run that regdae's own checks stop leaves
    ! cached%source = 'none' (no reference: the cells are run but not judged).
    subroutine regdae_reference(slider, links, times, text)
        logical, intent(in) :: slider
        integer, intent(in) :: links
        real(wp), intent(in) :: times(:)
        character(len=:), allocatable, intent(inout) :: text
        type(run_record) :: tight, loose
        type(solver_options) :: opts
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links), v_ref(size(times))
        integer :: k
        p = new_chain(links, slider, chain_gravity)
        call chain_start(p, q0, v0)
        opts = solver_options()
        opts%formulation = formulation_augmented
        opts%rtol = chain_ref_tol
        opts%atol = chain_ref_tol
        opts%eps = chain_ref_eps
        call run_mechanical(p, q0, v0, times, opts, 3600.0_wp, tight)
        if (tight%stat < 0) then
            ! A tight run that regdae's own checks stop is no reference: the cells are not judged.
            text = text//'regdae 1e-11 status='//itext(tight%stat)//' at t = '//num(tight%st%t)//' ('// &
                   tight%message(1:min(80, len(tight%message)))//'): no reference; '
            return
        end if
        opts%rtol = chain_check_tol
        opts%atol = chain_check_tol
        opts%eps = chain_check_eps
        call run_mechanical(p, q0, v0, times, opts, 3600.0_wp, loose)
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

    ! N = 2 with the slider is the slider crank (unit masses and links, g = 9.81) from
    ! th1 = th2 = pi/2 at rest: joint 1 = (sin th1, -cos th1), joint 2 = (2 sin th1, 0).
    real(wp) function crank_cross_check(times) result(norm)
        real(wp), intent(in) :: times(:)
        type(slider_crank_reduced) :: reduced
        real(wp) :: ref(2, size(times)), q(4, size(times))
        integer :: rstat
        reduced%gravity = chain_gravity
        call integrate_reference(reduced, 0.0_wp, [pi/2, 0.0_wp], times, ref, ref_tol, ref_tol, rstat)
        q(1, :) = sin(ref(1, :))
        q(2, :) = -cos(ref(1, :))
        q(3, :) = 2.0_wp*sin(ref(1, :))
        q(4, :) = 0.0_wp
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

    ! The outputs before the first one with a component that is NaN or infinite.
    pure integer function finite_outputs(states) result(good)
        real(wp), intent(in) :: states(:, :)
        good = 0
        do while (good < size(states, 2))
            if (.not. all(abs(states(:, good + 1)) <= huge(1.0_wp))) exit
            good = good + 1
        end do
    end function finite_outputs

    ! The reference method's column: ok, timeout, failed, or diverged (a NaN or Inf output).
    function oracle_text(stat, states) result(text)
        integer, intent(in) :: stat
        real(wp), intent(in) :: states(:, :)
        character(len=:), allocatable :: text
        if (stat == child_timed_out) then
            text = 'timeout'
        else if (stat /= 0) then
            text = 'failed'
        else if (finite_outputs(states) < size(states, 2)) then
            text = 'diverged'
        else
            text = 'ok'
        end if
    end function oracle_text

    ! The outputs of a peer run before its first NaN.
    integer function peer_good(q) result(good)
        real(wp), intent(in) :: q(:, :)
        good = 0
        do while (good < size(q, 2))
            if (any(q(:, good + 1) /= q(:, good + 1))) exit
            good = good + 1
        end do
    end function peer_good

    ! The chain (with `slider`, every even joint on y = 0) by the peer at rtol = atol = `rtol`,
    ! outputs at 0 and `times` (output_times), in a child process of this program stopped after
    ! `timeout` seconds (status child_timed_out).
    subroutine peer_run(links, slider, rtol, times, q, stat, steps, seconds, message, timeout, v)
        integer, intent(in) :: links, timeout
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        real(wp), intent(out) :: q(:, :)
        real(wp), intent(out), optional :: v(:, :)   !! the velocities, as q
        integer, intent(out) :: stat, steps
        real(wp), intent(out) :: seconds
        character(len=:), allocatable, intent(out) :: message
        character(len=:), allocatable :: file
        integer :: unit, ios, nmsg
        q = ieee_value(1.0_wp, ieee_quiet_nan)
        if (present(v)) v = ieee_value(1.0_wp, ieee_quiet_nan)
        steps = 0
        seconds = 0.0_wp
        call run_child('peer_job='//itext(links)//','//trim(merge('slider', 'plain ', slider))//','// &
                       num_exact(rtol)//','//itext(size(times))//','// &
                       num_exact(times(size(times))), timeout, 'the peer', file, unit, stat, message)
        if (stat /= 0) return
        read (unit, iostat=ios) stat, steps, seconds, nmsg
        if (ios == 0) then
            deallocate (message)
            allocate (character(len=nmsg) :: message)
            read (unit, iostat=ios) message, q
            if (ios == 0 .and. present(v)) read (unit, iostat=ios) v
        end if
        close (unit, status='delete')
        if (ios /= 0) then
            stat = child_failed
            message = 'the peer''s result could not be read'
        end if
    end subroutine peer_run

    ! The reference method: Dormand-Prince (drivers/common/dopri5.f90) at rtol = atol = `rtol` on
    ! the reduced ODE of `system` ('crank' or 'fourbar') from (th1, w1) to `times` (output_times),
    ! in a child process stopped after `timeout` seconds: dopri5_integrate has no step limit,
    ! and an error estimate that becomes NaN (a solution that blew up) makes it loop for ever.
    subroutine oracle_run(system, th1, w1, rtol, times, states, stat, message, timeout)
        character(len=*), intent(in) :: system
        real(wp), intent(in) :: th1, w1, rtol, times(:)
        real(wp), intent(out) :: states(:, :)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: message
        integer, intent(in) :: timeout
        character(len=:), allocatable :: file
        integer :: unit, ios
        states = ieee_value(1.0_wp, ieee_quiet_nan)
        call run_child('oracle_job='//system//','//num_exact(th1)//','//num_exact(w1)//','//num_exact(rtol)//','// &
                       itext(size(times))//','//num_exact(times(size(times))), timeout, 'Dormand-Prince', file, unit, &
                       stat, message)
        if (stat /= 0) return
        read (unit, iostat=ios) states
        close (unit, status='delete')
        if (ios /= 0) then
            stat = child_failed
            message = 'the Dormand-Prince result could not be read'
        end if
    end subroutine oracle_run

    ! Run this program as `exe job,FILE` under coreutils' timeout; on success (stat = 0) FILE is
    ! open for reading on `unit` (stream access), otherwise stat = child_timed_out or child_failed.
    subroutine run_child(job, timeout, what, file, unit, stat, message)
        character(len=*), intent(in) :: job, what
        integer, intent(in) :: timeout
        character(len=:), allocatable, intent(out) :: file, message
        integer, intent(out) :: unit, stat
        character(len=:), allocatable :: exe, tmp
        integer :: length, exit_stat, cmd_stat, ios
        integer(int64) :: tick
        stat = 0
        unit = -1
        message = ''
        call get_command_argument(0, length=length)
        allocate (character(len=length) :: exe)
        call get_command_argument(0, exe)
        call get_environment_variable('TMPDIR', length=length)
        if (length > 0) then
            allocate (character(len=length) :: tmp)
            call get_environment_variable('TMPDIR', tmp)
        else
            tmp = '/tmp'
        end if
        call system_clock(tick)
        file = tmp//'/trust_child_'//itext(filter%part)//'of'//itext(filter%parts)//'_'// &
               itext(int(modulo(tick, 1000000000_int64)))
        call execute_command_line('timeout '//itext(timeout)//' '//exe//' '//job//','//file//' >/dev/null 2>&1', &
                                  exitstat=exit_stat, cmdstat=cmd_stat)
        if (cmd_stat /= 0) then
            stat = child_failed
            message = 'could not start the child process for '//what
        else if (exit_stat == 124) then
            stat = child_timed_out
            message = what//' ran longer than '//itext(timeout)//' s (stopped by timeout)'
            call remove_file(file)
        else
            open (newunit=unit, file=file, access='stream', form='unformatted', status='old', action='read', &
                  iostat=ios)
            if (ios /= 0) then
                stat = child_failed
                message = 'the child process for '//what//' wrote no result (exit status '//itext(exit_stat)//')'
            end if
        end if
    end subroutine run_child

    ! The child process: peer_job=N,plain|slider,rtol,nout,tf,file runs the chain (slider: every
    ! even joint on y = 0) by the peer at rtol = atol on the outputs 0 and output_times(tf, nout)
    ! and writes the result.
    subroutine peer_job(spec)
        character(len=*), intent(in) :: spec
        character(len=len(spec)) :: fields(6)
        character(len=:), allocatable :: message
        real(wp) :: rtol, tf, seconds
        real(wp), allocatable :: q(:, :), v(:, :)
        integer :: links, nout, stat, steps, res_evals, jac_evals, unit, count
        call split_fields(spec, fields, count)
        if (count /= 6 .or. all(trim(fields(2)) /= ['plain ', 'slider'])) &
            call die_usage(prog, 'peer_job=N,plain|slider,rtol,nout,tf,file')
        call read_count(prog, 'peer_job N', trim(fields(1)), links, 1, 1000000)
        call read_number(prog, 'peer_job rtol', trim(fields(3)), rtol)
        call read_count(prog, 'peer_job nout', trim(fields(4)), nout, 1, 1000000)
        call read_number(prog, 'peer_job tf', trim(fields(5)), tf)
        allocate (q(2*links, nout + 1), v(2*links, nout + 1))
        call run_chain_peer(links, trim(fields(2)) == 'slider', rtol, rtol, [0.0_wp, output_times(tf, nout)], q, &
                            steps, res_evals, jac_evals, seconds, stat, message, v_out=v)
        open (newunit=unit, file=trim(fields(6)), access='stream', form='unformatted', status='replace', action='write')
        write (unit) stat, steps, seconds, len(message), message, q, v
        close (unit)
    end subroutine peer_job

    ! The child process: oracle_job=crank|chain2|fourbar,th1,w1,rtol,nout,tf,file runs Dormand-Prince on
    ! the reduced ODE from (th1, w1) to output_times(tf, nout) and writes the states (2, nout).
    subroutine oracle_job(spec)
        character(len=*), intent(in) :: spec
        character(len=len(spec)) :: fields(7)
        type(slider_crank_reduced) :: crank
        type(fourbar_reduced) :: bar
        real(wp) :: th1, w1, rtol, tf
        real(wp), allocatable :: states(:, :)
        integer :: nout, steps, evals, unit, count
        call split_fields(spec, fields, count)
        if (count /= 7) call die_usage(prog, 'oracle_job=crank|chain2|fourbar,th1,w1,rtol,nout,tf,file')
        call read_number(prog, 'oracle_job th1', trim(fields(2)), th1)
        call read_number(prog, 'oracle_job w1', trim(fields(3)), w1)
        call read_number(prog, 'oracle_job rtol', trim(fields(4)), rtol)
        call read_count(prog, 'oracle_job nout', trim(fields(5)), nout, 1, 1000000)
        call read_number(prog, 'oracle_job tf', trim(fields(6)), tf)
        allocate (states(2, nout))
        select case (trim(fields(1)))
        case ('crank', 'chain2')   ! chain2: the slider crank as the chain of 2 links with the slider
            crank%gravity = merge(chain_gravity, crank_gravity, trim(fields(1)) == 'chain2')
            call dopri5_integrate(crank, 0.0_wp, [th1, w1], output_times(tf, nout), states, rtol, rtol, steps, evals)
        case ('fourbar')
            bar%crank = fourbar_r
            bar%gravity = fourbar_g
            call dopri5_integrate(bar, 0.0_wp, [th1, w1], output_times(tf, nout), states, rtol, rtol, steps, evals)
        case default
            call die_usage(prog, 'oracle_job: crank or fourbar')
        end select
        open (newunit=unit, file=trim(fields(7)), access='stream', form='unformatted', status='replace', action='write')
        write (unit) states
        close (unit)
    end subroutine oracle_job

    !> The nout outputs tf k / nout, k = 1 ... nout (the parent's and the child processes' alike).
    pure function output_times(tf, nout) result(times)
        real(wp), intent(in) :: tf
        integer, intent(in) :: nout
        real(wp) :: times(nout)
        integer :: k
        times = [(tf*real(k, wp)/real(nout, wp), k=1, nout)]
    end function output_times

    ! The comma-separated fields of `text` into fields(1:min(count, size(fields))).
    subroutine split_fields(text, fields, count)
        character(len=*), intent(in) :: text
        character(len=*), intent(out) :: fields(:)
        integer, intent(out) :: count
        integer :: a, b
        fields = ''
        count = 0
        a = 1
        do
            count = count + 1
            b = index(text(a:), ',')
            if (count <= size(fields)) then
                if (b == 0) then
                    fields(count) = text(a:)
                else
                    fields(count) = text(a:a + b - 2)
                end if
            end if
            if (b == 0) exit
            a = a + b
        end do
    end subroutine split_fields

    subroutine remove_file(file)
        character(len=*), intent(in) :: file
        integer :: unit, ios
        open (newunit=unit, file=file, status='old', iostat=ios)
        if (ios == 0) close (unit, status='delete')
    end subroutine remove_file

    !---------------------------------------------------------------- common

    ! A cell whose reference could not be computed: a row of class no_reference and the cause.
    subroutine no_reference(counts, cell, label, p1, p2, rtol, why)
        type(tally), intent(inout) :: counts
        integer, intent(in) :: cell
        character(len=*), intent(in) :: label, why
        real(wp), intent(in) :: p1, p2, rtol
        integer(int64), parameter :: no_steps = 0
        call counts%add(class_no_reference)
        call write_row(cell, family_name, label, p1, p2, rtol, 0, class_no_reference, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                       no_steps, 0.0_wp, '')
        call write_note('no reference: ', why)
    end subroutine no_reference

    ! Insertion sort, ascending.
    pure subroutine sort(a)
        real(wp), intent(inout) :: a(:)
        real(wp) :: x
        integer :: i, j
        do i = 2, size(a)
            x = a(i)
            j = i - 1
            do while (j >= 1)
                if (a(j) <= x) exit
                a(j + 1) = a(j)
                j = j - 1
            end do
            a(j + 1) = x
        end do
    end subroutine sort

    ! The values of `a` in es11.4e3, or (exact = .true., the seeded grids' draws, which may be
    ! negative) with 17 significant digits.
    function list_text(a, exact) result(s)
        real(wp), intent(in) :: a(:)
        logical, intent(in), optional :: exact
        character(len=:), allocatable :: s
        integer :: i
        logical :: digits17
        digits17 = .false.
        if (present(exact)) digits17 = exact
        s = ''
        do i = 1, size(a)
            if (digits17) then
                s = s//' '//num_exact(a(i))
            else
                s = s//' '//etext(a(i))
            end if
        end do
    end function list_text

    function itext(k) result(s)
        integer, intent(in) :: k
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0)') k
        s = trim(buf)
    end function itext

    ! A real in es11.4e3 (the rows' format for errors).
    function etext(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=16) :: buf
        write (buf, '(es11.4e3)') x
        s = trim(adjustl(buf))
    end function etext

    ! A real with 17 significant digits (read back exactly).
    function num_exact(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        write (buf, '(es24.16e3)') x
        s = trim(adjustl(buf))
    end function num_exact

end program trust_driver
