!> Integration tests of the solver on Example 5.1: formulations and
!! least-squares solvers against each other and the exact solution, the
!! exclusion mechanisms, bad input, failing user routines, and two solvers in
!! one process.
module test_solver
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
    use regdae
    use ex51_problem, only: ex51, new_ex51, orientation_psd, orientation_paper
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: solver_tests

    integer, parameter :: nout = 200
    real(wp), parameter :: t0 = -1.0_wp, tf = 1.0_wp

    !> Example 5.1 whose f fails (with the given sign) or returns NaN for t > t_fail,
    !! counting its calls there in `calls_after` if associated (a pointer, so that
    !! the solver's copy of the problem counts into the test's variable).
    type, extends(ex51), public :: failing_ex51
        real(wp) :: t_fail = 0.0_wp
        integer :: fail_stat = -1     !! 0: return NaN instead of failing
        integer, pointer :: calls_after => null()
    contains
        procedure :: rhs => failing_rhs
    end type failing_ex51

contains

    function solver_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('formulations_and_lsq_agree', formulations_and_lsq_agree), &
                 new_test('exclusion_mechanisms', exclusion_mechanisms), &
                 new_test('accuracy_away_from_singularity', accuracy_away_from_singularity), &
                 new_test('direct_refuses_indefinite_gb', direct_refuses_indefinite_gb), &
                 new_test('bad_input', bad_input), &
                 new_test('inconsistent_initial_value', inconsistent_initial_value), &
                 new_test('failing_user_routine', failing_user_routine), &
                 new_test('options_from_text', options_from_text), &
                 new_test('two_solvers_sequential', two_solvers_sequential), &
                 new_test('two_solvers_side_by_side', two_solvers_side_by_side), &
                 new_test('explicit_integrator', explicit_integrator), &
                 new_test('advance_without_multiplier', advance_without_multiplier)]
    end function solver_tests

    subroutine failing_rhs(self, t, x, v, stat)
        class(failing_ex51), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = 2.0_wp
        if (t > self%t_fail) then
            if (associated(self%calls_after)) self%calls_after = self%calls_after + 1
            if (self%fail_stat == 0) then
                v(1) = ieee_value(1.0_wp, ieee_quiet_nan)
            else
                stat = self%fail_stat
            end if
        end if
    end subroutine failing_rhs

    function options(method, formulation, lsq, eps) result(opts)
        integer, intent(in) :: method, formulation, lsq
        real(wp), intent(in) :: eps
        type(solver_options) :: opts
        opts%method = method
        opts%formulation = formulation
        opts%lsq = lsq
        opts%eps = eps
        opts%stop_at_output = .true.
        ! these tests compare formulations and least-squares solvers: one integrator and
        ! the paper's weight (the bounds below were measured with them)
        opts%integrator = integrator_ida
        opts%gamma = 100.0_wp
    end function options

    !> x at the nout+1 output times; stat is the first failure, if any.
    subroutine run_ex51(opts, orientation, x, stat)
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: orientation
        real(wp), intent(out) :: x(0:nout)
        integer, intent(out) :: stat
        type(regdae_solver) :: solver
        real(wp) :: xk(1), yk(1)
        integer :: k
        x = ieee_value(1.0_wp, ieee_quiet_nan)
        call solver%init(new_ex51(orientation), t0, [0.0_wp], opts, stat)
        if (stat /= regdae_success) return
        do k = 0, nout
            call solver%advance(output_time(k), xk, yk, stat)
            if (stat /= regdae_success) exit
            x(k) = xk(1)
        end do
        call solver%destroy()
    end subroutine run_ex51

    pure real(wp) function output_time(k)
        integer, intent(in) :: k
        output_time = t0 + (tf - t0)*real(k, wp)/real(nout, wp)
    end function output_time

    ! Both formulations and both least-squares solvers integrate the same
    ! regularized ODE for x; they differ by the integration error only. With
    ! rtol = atol = 1e-5 and the local error controlled per step, the global
    ! differences observed are ~1e-6; 10 rtol bounds them with margin.
    subroutine formulations_and_lsq_agree(chk)
        type(checker), intent(inout) :: chk
        real(wp) :: x(0:nout, 4)
        integer :: stat(4), i, j
        call run_ex51(options(method_trust_region, formulation_multiplier, lsq_normal, 1.0e-6_wp), &
                      orientation_psd, x(:, 1), stat(1))
        call run_ex51(options(method_trust_region, formulation_multiplier, lsq_stacked, 1.0e-6_wp), &
                      orientation_psd, x(:, 2), stat(2))
        call run_ex51(options(method_trust_region, formulation_eliminated, lsq_normal, 1.0e-6_wp), &
                      orientation_psd, x(:, 3), stat(3))
        call run_ex51(options(method_trust_region, formulation_eliminated, lsq_stacked, 1.0e-6_wp), &
                      orientation_psd, x(:, 4), stat(4))
        do i = 1, 4
            call chk%equal(stat(i), regdae_success, 'run reaches t = 1')
        end do
        do i = 1, 4
            do j = i + 1, 4
                call chk%true(maxval(abs(x(:, i) - x(:, j))) <= 1.0e-4_wp, 'x agrees within 10 rtol')
            end do
        end do
        write (*, '(a,es10.2)') '    max |x difference| between the four runs: ', &
            max(maxval(abs(x(:, 1) - x(:, 2))), maxval(abs(x(:, 1) - x(:, 3))), maxval(abs(x(:, 1) - x(:, 4))))
    end subroutine formulations_and_lsq_agree

    ! Zero error weights and FIDASetId + SuppressAlg both leave y out of the error
    ! test; with our weight-independent Jacobian both must work and agree.
    subroutine exclusion_mechanisms(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        real(wp) :: xs(0:nout), xw(0:nout)
        integer :: ss, sw
        opts = options(method_trust_region, formulation_multiplier, lsq_normal, 1.0e-6_wp)
        opts%exclusion = exclusion_suppress
        call run_ex51(opts, orientation_psd, xs, ss)
        opts%exclusion = exclusion_weights
        call run_ex51(opts, orientation_psd, xw, sw)
        call chk%equal(ss, regdae_success, 'suppress reaches t = 1')
        call chk%equal(sw, regdae_success, 'weights reaches t = 1')
        call chk%true(maxval(abs(xs - xw)) <= 1.0e-4_wp, 'x agrees within 10 rtol')
    end subroutine exclusion_mechanisms

    ! Away from the singular layer (|t| >= 0.2) the trust-region solution is the
    ! exact x = t + 1 up to the integration error (rtol = 1e-5): bound 1e-4.
    ! Within it the regularization error of eps = 1e-9 is ~eps^(1/4) = 5.6e-3: bound 1e-2.
    subroutine accuracy_away_from_singularity(chk)
        type(checker), intent(inout) :: chk
        real(wp) :: x(0:nout), err
        integer :: stat, k
        real(wp) :: far, near
        call run_ex51(options(method_trust_region, formulation_eliminated, lsq_stacked, 1.0e-9_wp), &
                      orientation_psd, x, stat)
        call chk%equal(stat, regdae_success, 'reaches t = 1')
        far = 0.0_wp
        near = 0.0_wp
        do k = 0, nout
            err = abs(x(k) - (output_time(k) + 1.0_wp))
            if (abs(output_time(k)) >= 0.2_wp) then
                far = max(far, err)
            else
                near = max(near, err)
            end if
        end do
        call chk%true(far <= 1.0e-4_wp, 'error for |t| >= 0.2 below 1e-4')
        call chk%true(near <= 1.0e-2_wp, 'error near t = 0 below 1e-2')
        write (*, '(a,2es10.2)') '    max error |t| >= 0.2, |t| < 0.2: ', far, near
    end subroutine accuracy_away_from_singularity

    subroutine direct_refuses_indefinite_gb(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        integer :: stat
        call solver%init(new_ex51(orientation_paper), t0, [0.0_wp], &
                         options(method_direct, formulation_multiplier, lsq_auto, 1.0e-6_wp), stat)
        call chk%equal(stat, regdae_err_not_psd, 'status')
        call chk%true(index(solver%message(), 'positive') > 0, 'message says what is wrong')
    end subroutine direct_refuses_indefinite_gb

    subroutine bad_input(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        real(wp) :: x(1), y(1), x2(2)
        integer :: stat
        call solver%advance(0.0_wp, x, y, stat)
        call chk%equal(stat, regdae_err_not_initialized, 'advance before init')
        call solver%init(new_ex51(orientation_psd), t0, [ieee_value(1.0_wp, ieee_quiet_nan)], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'NaN in x0')
        call chk%true(index(solver%message(), 'x0') > 0, 'message names x0')
        call solver%init(new_ex51(orientation_psd), t0, [ieee_value(1.0_wp, ieee_positive_inf)], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'Inf in x0')
        call solver%init(new_ex51(orientation_psd), t0, [0.0_wp, 0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'x0 of wrong length')
        call solver%init(new_ex51(orientation_psd), ieee_value(1.0_wp, ieee_quiet_nan), [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 't0 NaN')
        opts%eps = -1.0e-6_wp
        call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'eps < 0')
        call chk%true(index(solver%message(), 'eps') > 0, 'message names eps')
        opts = solver_options()
        opts%gamma = 0.0_wp
        call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'gamma = 0')
        call chk%true(index(solver%message(), 'gamma') > 0, 'message names gamma')
        opts = solver_options()
        call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_success, 'valid init')
        call solver%advance(-0.5_wp, x2, y, stat)
        call chk%equal(stat, regdae_err_bad_input, 'x of wrong length in advance')
        call solver%advance(-2.0_wp, x, y, stat)
        call chk%equal(stat, regdae_err_bad_input, 'tout before the current time')
        call solver%advance(ieee_value(1.0_wp, ieee_quiet_nan), x, y, stat)
        call chk%equal(stat, regdae_err_bad_input, 'tout NaN')
        call solver%advance(-0.5_wp, x, y, stat)
        call chk%equal(stat, regdae_success, 'still usable after rejected calls')
        call chk%close(x(1), 0.5_wp, 1.0e-4_wp, 'x(-0.5)')
        call solver%destroy()
    end subroutine bad_input

    subroutine inconsistent_initial_value(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        integer :: stat
        call solver%init(new_ex51(orientation_psd), t0, [0.5_wp], opts, stat)
        call chk%equal(stat, regdae_err_inconsistent_ic, 'x(-1) = 0.5 violates g = 0')
        call chk%true(index(solver%message(), 'g(x0, t0)') > 0, 'message names the constraint')
        ! Within ic_tol it is accepted.
        call solver%init(new_ex51(orientation_psd), t0, [1.0e-10_wp], opts, stat)
        call chk%equal(stat, regdae_success, 'violation 1e-10 < ic_tol accepted')
    end subroutine inconsistent_initial_value

    subroutine failing_user_routine(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(failing_ex51) :: p
        type(solver_options) :: opts
        type(solver_stats) :: st
        real(wp) :: x(1), y(1)
        integer :: stat
        p%ex51 = new_ex51(orientation_psd)
        ! Fails at the initial point.
        p%t_fail = -2.0_wp
        call solver%init(p, t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_user_callback, 'failure at t0 reported by init')
        call chk%true(index(solver%message(), 'rhs') > 0, 'message names the routine')
        ! Fatal failure during the integration.
        p%t_fail = -0.5_wp
        call solver%init(p, t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_success, 'init')
        call solver%advance(0.0_wp, x, y, stat)
        call chk%equal(stat, regdae_err_user_callback, 'fatal failure stops the integration')
        call chk%true(index(solver%message(), 'rhs') > 0, 'message names the routine')
        st = solver%statistics()
        call chk%true(st%t <= -0.5_wp + 1.0e-12_wp, 'time reached before the failure')
        ! Recoverable failure, repeated: IDA gives up, the message says why.
        p%fail_stat = 1
        call solver%init(p, t0, [0.0_wp], opts, stat)
        call solver%advance(0.0_wp, x, y, stat)
        call chk%equal(stat, regdae_err_integration, 'repeated recoverable failures')
        call chk%true(index(solver%message(), 'rhs') > 0, 'message names the routine')
        ! NaN from the user routine.
        p%fail_stat = 0
        call solver%init(p, t0, [0.0_wp], opts, stat)
        call solver%advance(0.0_wp, x, y, stat)
        call chk%true(stat < 0, 'NaN in f stops the integration')
        call chk%true(index(solver%message(), 'NaN') > 0, 'message says NaN')
        call solver%destroy()
    end subroutine failing_user_routine

    subroutine options_from_text(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        character(len=:), allocatable :: msg
        integer :: stat
        call set_option(opts, 'method', 'direct', stat, msg)
        call chk%equal(opts%method, method_direct, 'method=direct')
        call set_option(opts, 'eps', '1e-9', stat, msg)
        call chk%close(opts%eps, 1.0e-9_wp, 0.0_wp, 'eps=1e-9')
        call set_option(opts, 'epsilon', '1e-9', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'unknown key')
        call chk%true(index(msg, 'epsilon') > 0, 'message names the key')
        call set_option(opts, 'method', 'newton', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'bad value')
        call chk%true(index(msg, 'newton') > 0, 'message names the value')
        call chk%equal(opts%method, method_direct, 'bad value leaves the option unchanged')
        call set_option(opts, 'eps', '-1', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'eps = -1 refused')
        call chk%close(opts%eps, 1.0e-9_wp, 0.0_wp, 'eps unchanged')
        call set_option(opts, 'gamma', 'abc', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'gamma not a number')
        call set_option(opts, 'gamma', 'nan', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'gamma = nan refused')
    end subroutine options_from_text

    ! One solver after another, and the first again: identical results.
    subroutine two_solvers_sequential(chk)
        type(checker), intent(inout) :: chk
        real(wp) :: xa(0:nout), xb(0:nout), xa2(0:nout)
        integer :: sa, sb, sa2
        call run_ex51(options(method_trust_region, formulation_multiplier, lsq_normal, 1.0e-6_wp), &
                      orientation_psd, xa, sa)
        call run_ex51(options(method_direct, formulation_eliminated, lsq_normal, 1.0e-9_wp), &
                      orientation_psd, xb, sb)
        call run_ex51(options(method_trust_region, formulation_multiplier, lsq_normal, 1.0e-6_wp), &
                      orientation_psd, xa2, sa2)
        call chk%true(sa == 0 .and. sb == 0 .and. sa2 == 0, 'all runs reach t = 1')
        call chk%true(all(xa == xa2), 'a repeated run gives identical results')
        call chk%true(any(xa /= xb), 'different methods give different results')
    end subroutine two_solvers_sequential

    ! Two solvers advanced alternately give the same results as alone.
    subroutine two_solvers_side_by_side(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: sa, sb
        type(solver_options) :: oa, ob
        real(wp) :: xa(0:nout), xb(0:nout), ra(0:nout), rb(0:nout), x(1), y(1)
        integer :: stat, k, s1, s2
        oa = options(method_trust_region, formulation_multiplier, lsq_normal, 1.0e-6_wp)
        ob = options(method_direct, formulation_eliminated, lsq_normal, 1.0e-9_wp)
        call run_ex51(oa, orientation_psd, ra, s1)
        call run_ex51(ob, orientation_psd, rb, s2)
        call sa%init(new_ex51(orientation_psd), t0, [0.0_wp], oa, stat)
        call sb%init(new_ex51(orientation_psd), t0, [0.0_wp], ob, stat)
        do k = 0, nout
            call sa%advance(output_time(k), x, y, s1)
            xa(k) = x(1)
            call sb%advance(output_time(k), x, y, s2)
            xb(k) = x(1)
        end do
        call chk%true(all(xa == ra), 'solver a side by side = alone')
        call chk%true(all(xb == rb), 'solver b side by side = alone')
        call sa%destroy()
        call sb%destroy()
    end subroutine two_solvers_side_by_side

    ! integrator=dopri5 integrates the same regularized ODE as IDA (eliminated
    ! formulation): x agrees with the IDA run to the tolerance scale (measured 3.4e-5 at
    ! rtol = 1e-5; bound 1e-4 = 10 rtol), away from the layer x is exact to 1e-4; the
    ! statistics count slope evaluations; and the multiplier formulation is refused.
    subroutine explicit_integrator(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        real(wp) :: x_ida(0:nout), x_rk(0:nout)
        integer :: s1, s2, stat
        opts = options(method_trust_region, formulation_eliminated, lsq_auto, 1.0e-6_wp)
        opts%gamma = 10.0_wp   ! non-stiff: the explicit method's steps are not limited by -gamma
        call run_ex51(opts, orientation_psd, x_ida, s1)
        opts%integrator = integrator_dopri5
        call run_ex51(opts, orientation_psd, x_rk, s2)
        call chk%equal(s1, regdae_success, 'IDA run')
        call chk%equal(s2, regdae_success, 'dopri5 run')
        call chk%true(maxval(abs(x_ida - x_rk)) <= 1.0e-4_wp, 'x agrees with IDA within 10 rtol')
        call chk%close(x_rk(0), 0.0_wp, 0.0_wp, 'x(-1)')
        call chk%close(x_rk(nout), 2.0_wp, 1.0e-4_wp, 'x(1) = 2')
        write (*, '(a,es10.2)') '    max |x_dopri5 - x_ida|: ', maxval(abs(x_ida - x_rk))
        call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call solver%advance(0.5_wp, x_rk(0:0), x_ida(0:0), stat)
        st = solver%statistics()
        call chk%true(st%steps > 0 .and. st%res_evals >= 6*st%steps .and. st%jac_evals == 0, &
                      'statistics: steps, slope evaluations, no Jacobian')
        call solver%destroy()
        opts%formulation = formulation_multiplier
        call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'dopri5 with the multiplier formulation refused')
        call chk%true(index(solver%message(), 'eliminated') > 0, 'message says why')
        ! gamma = 1e3 makes the regularized system stiff (eigenvalue -1e3): the stiffness
        ! test stops the explicit method instead of crawling at its stability limit.
        opts%formulation = formulation_eliminated
        opts%gamma = 1.0e3_wp
        call run_ex51(opts, orientation_psd, x_rk, s2)
        call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call solver%advance(0.5_wp, x_rk(0:0), x_ida(0:0), stat)
        call chk%equal(stat, regdae_err_integration, 'stiff system stopped')
        call chk%true(index(solver%message(), 'stiff') > 0, 'message says stiff')
        call solver%destroy()
    end subroutine explicit_integrator

    ! advance without y: the same x (bitwise: the output-time evaluation does not
    ! touch the integrator's state), with IDA and with dopri5; a y of the wrong
    ! length is refused by name. With dopri5 the diagnostics come from the steps.
    subroutine advance_without_multiplier(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: with_y, without_y
        type(solver_stats) :: st
        real(wp) :: xa(1), xb(1), y(1), y_bad(2), diff
        integer :: k, sa, sb, pass
        do pass = 1, 2
            opts = options(method_trust_region, formulation_eliminated, lsq_auto, 1.0e-6_wp)
            opts%stop_at_output = .false.
            if (pass == 2) then
                opts%integrator = integrator_dopri5
                opts%gamma = 10.0_wp   ! non-stiff for the explicit method
            end if
            call with_y%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, sa)
            call without_y%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, sb)
            diff = 0.0_wp
            do k = 1, nout
                call with_y%advance(output_time(k), xa, y, sa)
                call without_y%advance(output_time(k), xb, stat=sb)
                if (sa < 0 .or. sb < 0) exit
                diff = max(diff, abs(xa(1) - xb(1)))
            end do
            call chk%true(sa >= 0 .and. sb >= 0, 'both runs succeed (pass '//merge('IDA   ', 'dopri5', pass == 1)//')')
            call chk%true(diff == 0.0_wp, 'x without y is bitwise the same (pass '// &
                          merge('IDA   ', 'dopri5', pass == 1)//')')
            st = without_y%statistics()
            call chk%true(st%sigma_min < 0.05_wp .and. st%singular_passes >= 1, &
                          'singular pass at t = 0 seen without y (pass '//merge('IDA   ', 'dopri5', pass == 1)//')')
            call without_y%advance(tf + 1.0_wp, xb, y_bad, sb)
            call chk%equal(sb, regdae_err_bad_input, 'y of length 2 refused')
            call chk%true(index(without_y%message(), 'y must have length 1') > 0, 'message names y')
            call with_y%destroy()
            call without_y%destroy()
        end do
    end subroutine advance_without_multiplier

end module test_solver
