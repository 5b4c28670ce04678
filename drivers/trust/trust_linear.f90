!> drivers/trust's family linear: theory_problems' index-2 DAEs S1 and S2 (GB ~ t^2, t^4) under
!! the methods trust_region, direct and baumgarte, against the exact solution.
module trust_linear
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp, solver_options, set_option
    use theory_problems, only: theory_problem, new_theory_problem
    use xorshift_random, only: xorshift64
    use trust_support, only: tally, weighted_error
    use driver_support, only: num, sort_ascending
    use trust_grid, only: trust_setup, linear_rtols
    use trust_text, only: list_text
    use trust_runs, only: run_record, run_first_order
    use trust_judge, only: judge_and_print, split_at_last_warning
    implicit none
    private
    public :: linear_family

contains

    !> The family linear: its header, one row per selected cell (S1 and S2, or 3 seeded variants of
    !! each; 3 methods, 8 R), the summary.
    subroutine linear_family(setup)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        character(len=2), parameter :: cases(2) = ['S1', 'S2']
        character(len=12), parameter :: methods(3) = [character(len=12) :: 'trust_region', 'direct', 'baumgarte']
        character(len=1), parameter :: letters(3) = ['a', 'b', 'c']
        type(tally) :: counts
        type(theory_problem) :: problem
        real(wp) :: grid(201), singular_at(3, 2), scale(3, 2), p1, p2
        real(wp), allocatable :: times(:)
        integer :: ic, iv, im, ir, k, cell, variants
        character(len=:), allocatable :: name
        grid = [(real(k - 100, wp)/100.0_wp, k=0, 200)]
        call linear_variants(setup, singular_at, scale, variants)
        write (*, '(a)') '# family=linear: drivers/problems/theory_problems.f90 S1 (C = t e^T, GB ~ t^2) and S2 '// &
            '(C = t^2 e^T, GB ~ t^4), B = C^T, t in [-1, 1], 201 outputs (t = -1, -0.99, ..., 0, ..., 1), '// &
            'x(-1) = x*(-1); p1 = t0, p2 = tf'
        write (*, '(a)') '#   case = problem/method; reference: the exact x*; no reference method (err_ref = 0). '// &
            'direct needs GB PSD in the core''s convention: B = C^T gives GB = C C^T >= 0 (theory_problems maps '// &
            'y_core = -y); budget '//num(setup%run_budget(30.0_wp))//' s per run'
        if (setup%grid_seed > 0_int64) then
            write (*, '(a,i0,a)') '#   variants from seed=', setup%grid_seed, ' (case S1a ... S2c): C = c (t - t*)^p e^T, '// &
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
                if (setup%grid_seed > 0_int64) then
                    problem%singular_at = singular_at(iv, ic)
                    problem%scale = scale(iv, ic)
                    name = cases(ic)//letters(iv)
                    times = [grid, singular_at(iv, ic)]
                    call sort_ascending(times)
                    p1 = singular_at(iv, ic)
                    p2 = scale(iv, ic)
                end if
                do im = 1, size(methods)
                    do ir = 1, size(linear_rtols)
                        cell = cell + 1
                        if (.not. setup%filter%selected(cell, linear_rtols(ir))) cycle
                        call linear_cell(setup, counts, cell, problem, name, p1, p2, trim(methods(im)), linear_rtols(ir), times)
                    end do
                end do
            end do
        end do
        write (*, '(a)') counts%summary('linear')
    end subroutine linear_family

    ! The linear family's variants of S1 and S2 (columns): one, unmoved, without a seed; with seed=S
    ! three of each, the singular point t* uniform in (-0.9, 0.9) and the scale of C log-uniform in
    ! [1e-2, 1e2].
    subroutine linear_variants(setup, singular_at, scale, variants)
        type(trust_setup), intent(in) :: setup   !! the run's settings
        real(wp), intent(out) :: singular_at(:, :), scale(:, :)
        integer, intent(out) :: variants
        type(xorshift64) :: gen
        integer :: ic, iv
        singular_at = 0.0_wp
        scale = 1.0_wp
        variants = 1
        if (setup%grid_seed == 0_int64) return
        variants = size(singular_at, 1)
        gen = setup%seeded_generator()
        do ic = 1, size(singular_at, 2)
            do iv = 1, variants
                singular_at(iv, ic) = gen%next_between(-0.9_wp, 0.9_wp)
                scale(iv, ic) = 10.0_wp**gen%next_between(-2.0_wp, 2.0_wp)
            end do
        end do
    end subroutine linear_variants

    subroutine linear_cell(setup, counts, cell, problem, name, p1, p2, method, rtol, times)
        type(trust_setup), intent(in) :: setup   !! the run's settings
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
        opts = setup%cell_options(rtol)
        call set_option(opts, 'method', method, stat, msg)
        call run_first_order(problem, times(1), problem%x_exact(times(1)), times, opts, setup%run_budget(30.0_wp), rec)
        err = weighted_error(rec%x, xref, rtol, rec%good)
        call split_at_last_warning(rec, xref, rtol, spread(.false., 1, size(times)), 10.0_wp)
        ! First-order problems have no branch, drift or work check; the rerun stays unused.
        call judge_and_print(counts, 'linear', cell, name//'/'//method, p1, p2, rtol, rec, err, 0.0_wp, &
                             10.0_wp, 0.0_wp, rerun, '')
    end subroutine linear_cell

end module trust_linear
