!> The API's rough edges of issue 12: the acceleration on request, absolute
!! tolerances per component (atol_vector, atol_v), the default g_t callable from
!! a second-order override, what index 2 does with a curvature override, and
!! the 64-bit counters printed without conversion.
module test_api
    use regdae
    use slider_crank_problem, only: slider_crank, new_slider_crank, slider_crank_reduced
    use chain_problem, only: chain, new_chain, chain_start
    use ex51_problem, only: new_ex51, orientation_psd
    use test_defaults, only: growing_pendulum
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: api_tests

    real(wp), parameter :: pi = acos(-1.0_wp)

    !> The slider crank with its analytic curvature shifted by 1: a wrong override,
    !! which an index-2 run does not call.
    type, extends(slider_crank) :: crank_wrong_curvature
    contains
        procedure :: constraint_curvature => wrong_curvature
    end type crank_wrong_curvature

contains

    function api_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('acceleration_on_request', acceleration_on_request), &
                 new_test('absolute_tolerance_per_component', absolute_tolerance_per_component), &
                 new_test('default_gt_callable_from_override', default_gt_callable_from_override), &
                 new_test('index2_ignores_the_curvature', index2_ignores_the_curvature)]
    end function api_tests

    ! The slider crank at index 3 from rest at th1 = pi/2, rtol = atol = 1e-10: the
    ! acceleration th1'' that advance returns against the reduced ODE's right-hand
    ! side at the returned (th1, th1') (the exact constrained acceleration there: it
    ! differs only by the constraint residual times the weights, below 1e-8 here;
    ! bound 1e-6 max(1, |a|)); and the augmented formulation's a (IDA's interpolated
    ! v') against the eliminated one's on the chain of 16 links at rtol 1e-8 (both
    ! within the integration error of the same solution: bound 1e-4 max(1, |a|),
    ! measured 5e-7; the slider crank's measured 1.7e-10).
    subroutine acceleration_on_request(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(slider_crank_reduced) :: reduced
        type(chain) :: p
        real(wp) :: th(2), w(2), a(2), lambda(1), exact(2), err, q0(32), v0(32), q(32), v(32), y(16), acc(32, 2)
        integer :: stat, k, run
        opts%rtol = 1.0e-10_wp
        opts%atol = 1.0e-10_wp
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
        err = 0.0_wp
        do k = 1, 8
            if (stat /= regdae_success) exit
            call solver%advance(0.5_wp*k, th, lambda, stat, v=w, a=a)
            call reduced%rhs(0.5_wp*k, [th(1), w(1)], exact)
            err = max(err, abs(a(1) - exact(2))/max(1.0_wp, abs(exact(2))))
        end do
        call chk%equal(stat, regdae_success, 'the slider crank with the acceleration')
        call chk%true(err <= 1.0e-6_wp, 'th1'''' = the reduced ODE''s at the returned state')
        write (*, '(a,es10.2)') '    slider crank, max relative error of th1'''': ', err
        call solver%advance(4.5_wp, th, stat=stat, a=a(1:1))
        call chk%equal(stat, regdae_err_bad_input, 'a of the wrong length refused')
        call solver%destroy()
        p = new_chain(16, .false., 9.81_wp)
        call chain_start(p, q0, v0)
        do run = 1, 2
            opts = solver_options()
            opts%rtol = 1.0e-8_wp
            opts%atol = 1.0e-8_wp
            opts%integrator = integrator_ida
            opts%formulation = merge(formulation_augmented, formulation_eliminated, run == 1)
            call solver%init(p, 0.0_wp, q0, v0, opts, stat)
            if (stat == regdae_success) call solver%advance(0.3_wp, q, y, stat, v=v, a=acc(:, run))
            call chk%equal(stat, regdae_success, 'the chain, '//formulation_name(opts%formulation))
            call solver%destroy()
        end do
        err = maxval(abs(acc(:, 1) - acc(:, 2)))/max(1.0_wp, maxval(abs(acc(:, 2))))
        call chk%true(err <= 1.0e-4_wp, 'the augmented formulation''s acceleration = the eliminated one''s')
        write (*, '(a,es10.2)') '    chain of 16, augmented against eliminated: ', err
    end subroutine acceleration_on_request

    ! atol per component: a vector of the wrong length and atol_v on a first-order
    ! problem are refused with a message; atol_v gives the same run as the vector
    ! (atol, atol, atol_v, atol_v); loose tolerances on the velocities take fewer
    ! steps (the velocities leave the error test in effect).
    subroutine absolute_tolerance_per_component(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(solver_stats) :: st(3)
        real(wp) :: th(2)
        integer :: stat, run
        opts%rtol = 1.0e-8_wp
        opts%atol = 1.0e-8_wp
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat, &
                         atol_vector=[1.0e-8_wp, 1.0e-8_wp, 1.0e-8_wp])
        call chk%equal(stat, regdae_err_bad_input, 'atol_vector of length 3 for 4 components refused')
        call chk%true(index(solver%message(), 'atol_vector') > 0, 'the message names atol_vector')
        do run = 1, 3
            opts%atol_v = merge(1.0e-3_wp, option_auto, run == 2)
            if (run == 1) then
                call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat, &
                                 atol_vector=[1.0e-8_wp, 1.0e-8_wp, 1.0e-3_wp, 1.0e-3_wp])
            else if (run == 2) then
                call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
            else
                call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
            end if
            if (stat == regdae_success) call solver%advance(3.0_wp, th, stat=stat)
            call chk%equal(stat, regdae_success, 'run '//format_int(run))
            st(run) = solver%statistics()
            call solver%destroy()
        end do
        call chk%equal(int(st(1)%steps), int(st(2)%steps), 'atol_v = the vector (atol, atol, atol_v, atol_v)')
        call chk%true(st(1)%steps < st(3)%steps, 'loose velocities take fewer steps')
        write (*, '(a)') '    steps with atol_v = 1e-3 and with 1e-8: '//format_int(st(1)%steps)//', '// &
            format_int(st(3)%steps)
        opts = solver_options()
        opts%atol_v = 1.0e-3_wp
        call solver%init(new_ex51(orientation_psd), -1.0_wp, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'atol_v on a first-order problem refused')
        call chk%true(index(solver%message(), 'atol_v') > 0, 'the message names atol_v')
    end subroutine absolute_tolerance_per_component

    ! constraint_dt_difference (module regdae) on a second-order problem: the
    ! default g_t, callable from an override, against the analytic one (central
    ! difference: error ~ u^(2/3) |g| ~ 1e-10 here; bound 1e-8).
    subroutine default_gt_callable_from_override(chk)
        type(checker), intent(inout) :: chk
        type(growing_pendulum) :: p
        real(wp) :: by_difference(1), exact(1), x(2)
        integer :: stat, k
        p%n = 2
        p%m = 1
        stat = 0
        x = [0.6_wp, -0.9_wp]
        do k = 0, 4
            call constraint_dt_difference(p, 0.3_wp*k, x, by_difference, stat)
            call p%constraint_dt(0.3_wp*k, x, exact, stat)
            call chk%close(by_difference(1), exact(1), 1.0e-8_wp, 'g_t by difference at t = '//format_real(0.3_wp*k, 2))
        end do
        call chk%equal(stat, 0, 'no failure')
    end subroutine default_gt_callable_from_override

    ! Index 2 (5.4) with the slider crank, rtol 1e-8 on [0, 2] (one singular pass):
    ! index 2 takes the derivative of the velocity constraint by central
    ! differences of G v + g_t, not from `constraint_curvature` (doc/api.md): the
    ! analytic curvature, regdae's difference quotient and a curvature shifted by 1
    ! give the same run (bit for bit: measured 0).
    subroutine index2_ignores_the_curvature(chk)
        type(checker), intent(inout) :: chk
        type(slider_crank) :: crank
        type(crank_wrong_curvature) :: wrong
        real(wp) :: th(2, 3)
        integer :: stat(3)
        crank = new_slider_crank(9.8_wp)
        crank%analytic_curvature = .true.
        call run(crank, th(:, 1), stat(1))
        crank%analytic_curvature = .false.
        call run(crank, th(:, 2), stat(2))
        wrong%slider_crank = new_slider_crank(9.8_wp)
        wrong%analytic_curvature = .true.
        call run(wrong, th(:, 3), stat(3))
        call chk%true(all(stat == regdae_success), 'the three runs end ok')
        call chk%true(maxval(abs(th(:, 1) - th(:, 2))) == 0.0_wp .and. maxval(abs(th(:, 1) - th(:, 3))) == 0.0_wp, &
                      'the same run whatever constraint_curvature says')
    contains
        subroutine run(problem, th_end, stat)
            class(slider_crank), intent(in) :: problem
            real(wp), intent(out) :: th_end(2)
            integer, intent(out) :: stat
            type(regdae_solver) :: solver
            type(solver_options) :: opts
            opts%index = 2
            opts%rtol = 1.0e-8_wp
            opts%atol = 1.0e-8_wp
            opts%gamma = 100.0_wp
            opts%eps = 1.0e-10_wp
            opts%integrator = integrator_ida
            call solver%init(problem, 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
            th_end = 0.0_wp
            if (stat == regdae_success) call solver%advance(2.0_wp, th_end, stat=stat)
            call solver%destroy()
        end subroutine run
    end subroutine index2_ignores_the_curvature

    subroutine wrong_curvature(self, t, x, v, val, stat)
        class(crank_wrong_curvature), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call self%slider_crank%constraint_curvature(t, x, v, val, stat)
        val = val + 1.0_wp
    end subroutine wrong_curvature

end module test_api
