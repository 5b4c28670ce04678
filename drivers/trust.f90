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
!! Usage: trust [family=crank|chain|chain_long|fourbar|linear|all] [part=k/K] [rtol=R] [rtols=R1,R2,...]
!!              [max_links=L] [tight_check=no] [reference=reduced] [cell=I] [budget=S] [th1=A [w1=W]]
!!              [seed=S] [option.KEY=VALUE ...]
!! (option.KEY=VALUE: that solver option in every cell's run instead of its default, for diagnosing a
!! cell; the header says which; the grids' figures are from the defaults)
!! (th1=A, w1=W: the crank family at that start only, one cell per R, case th00; with rtol=R off
!! the grid's R, e.g. 1e-10, the one cell at that R; A outside [0, pi], e.g. A + 2 pi k, runs
!! another representative of the same physical start)
!! (rtols=R1,R2,...: the crank, chain, chain_long and fourbar grids at these R instead of 1e-3 ...
!! 1e-8, the cells numbered over them, e.g. `trust family=chain_long rtols=1e-9,1e-10`; max_links=L:
!! the chain families' cells with N <= L only, their numbers unchanged; tight_check=no: a chain
!! judged against its reduced ODE without regdae's tight run as a cross-check, for the ctest cells;
!! reference=reduced: the plain chain of family chain against its reduced ODE even where the peer
!! succeeds, for measuring errors below the peer's own at 1e-11)
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
!! The program reads the command line; the families, the judge and the runs are modules in
!! drivers/trust/: trust_crank, trust_chain (chain and chain_long), trust_fourbar, trust_linear;
!! trust_judge (class, row, notes), trust_runs (the regdae runs), trust_children (the child
!! processes), trust_grid (the settings and what the families share), trust_text.
program trust_driver
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp, solver_options, set_option
    use driver_support, only: argument, split_key_value, die_usage, read_number, read_count
    use trust_grid, only: trust_setup
    use trust_text, only: itext
    use trust_children, only: peer_job, oracle_job
    use trust_crank, only: crank_family
    use trust_chain, only: chain_family
    use trust_fourbar, only: fourbar_family
    use trust_linear, only: linear_family
    implicit none

    character(len=*), parameter :: prog = 'trust'
    character(len=*), parameter :: usage = 'usage: trust [family=crank|chain|chain_long|fourbar|linear|all] '// &
                                           '[part=k/K] [rtol=R] [rtols=R1,R2,...] [max_links=L] [tight_check=no] '// &
                                           '[reference=reduced] [cell=I] [budget=S] [th1=A [w1=W]] [seed=S] '// &
                                           '[option.KEY=VALUE ...]'

    call main()

contains

    ! Read the command line and run the families it names (or a child job).
    subroutine main()
        type(trust_setup) :: setup
        character(len=:), allocatable :: family, key, value, msg, override_text
        integer :: i, slash, stat
        logical :: ok
        family = 'all'
        setup%overrides = solver_options()
        override_text = ''
        do i = 1, command_argument_count()
            call split_key_value(argument(i), key, value, ok)
            if (.not. ok) call die_usage(prog, usage)
            if (index(key, 'option.') == 1) then
                call set_option(setup%overrides, key(8:), value, stat, msg)
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
                call read_count(prog, 'K of part', value(slash + 1:), setup%filter%parts, 1, 1000000)
                call read_count(prog, 'k of part', value(:slash - 1), setup%filter%part, 1, setup%filter%parts)
            case ('rtol'); call read_number(prog, key, value, setup%filter%rtol)
                if (.not. (setup%filter%rtol > 0.0_wp)) call die_usage(prog, 'rtol must be > 0')
            case ('cell'); call read_count(prog, key, value, setup%filter%cell, 1, 1000000)
            case ('rtols'); call read_rtols(value, setup%rtols)
            case ('max_links'); call read_count(prog, key, value, setup%max_links, 2, 1000000)
            case ('tight_check')
                if (value /= 'yes' .and. value /= 'no') call die_usage(prog, 'tight_check must be yes or no')
                setup%tight_check = (value == 'yes')
            case ('reference')
                if (value /= 'auto' .and. value /= 'reduced') call die_usage(prog, 'reference must be auto or reduced')
                setup%reduced_only = (value == 'reduced')
            case ('th1'); call read_number(prog, key, value, setup%start_th1)
                if (.not. (abs(setup%start_th1) < huge(1.0_wp))) call die_usage(prog, 'th1 must be finite')
            case ('w1'); call read_number(prog, key, value, setup%start_w1)
            case ('seed'); call read_seed(value, setup%grid_seed)
            case ('budget'); call read_number(prog, key, value, setup%budget)
                if (.not. (setup%budget > 0.0_wp)) call die_usage(prog, 'budget must be > 0')
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
            'part='//itext(setup%filter%part)//'/'//itext(setup%filter%parts)
        write (*, '(a)') '# columns: cell family case p1 p2 R status class err err_ref bound t_end steps seconds '// &
            '[the family''s columns]'
        if (len(override_text) > 0) write (*, '(a)') '# NOT the defaults: every run with'//override_text
        if (family == 'all' .or. family == 'crank') call crank_family(setup)
        if (family == 'all' .or. family == 'chain') call chain_family(setup, .false.)
        if (family == 'all' .or. family == 'chain_long') call chain_family(setup, .true.)
        if (family == 'all' .or. family == 'fourbar') call fourbar_family(setup)
        if (family == 'all' .or. family == 'linear') call linear_family(setup)
    end subroutine main

    ! rtols=R1,R2,...: the mechanical grids' tolerances, each in (0, 1).
    subroutine read_rtols(value, rtols)
        character(len=*), intent(in) :: value
        real(wp), allocatable, intent(out) :: rtols(:)
        integer :: start, comma
        real(wp) :: r
        allocate (rtols(0))
        start = 1
        do
            comma = index(value(start:), ',')
            if (comma == 0) then
                call read_number(prog, 'rtols', value(start:), r)
            else
                call read_number(prog, 'rtols', value(start:start + comma - 2), r)
            end if
            if (.not. (r > 0.0_wp .and. r < 1.0_wp)) call die_usage(prog, 'each of rtols must be in (0, 1)')
            rtols = [rtols, r]
            if (comma == 0) exit
            start = start + comma
        end do
    end subroutine read_rtols

    ! seed=S: a positive integer.
    subroutine read_seed(value, seed)
        character(len=*), intent(in) :: value
        integer(int64), intent(out) :: seed
        integer :: ios
        read (value, *, iostat=ios) seed
        if (ios /= 0 .or. seed <= 0_int64) call die_usage(prog, 'seed must be a positive integer')
    end subroutine read_seed

end program trust_driver
