!> Root finding (issue 22 item 1, regdae_events): event times against
!! independently located ones, the pendulum's from its exact period (the
!! complete elliptic integral by the arithmetic-geometric mean), the slider
!! crank's from its reduced ODE (CVODE at 1e-12 and Newton's method on the
!! event function along it), Example 5.1's from its exact solution; stop and
!! continue, the direction filter, an event at t0 (not reported), two events in
!! one step, two functions with one root, and bad input.
module test_events
    use regdae
    use pendulum_problem, only: new_pendulum
    use slider_crank_problem, only: new_slider_crank, slider_crank_reduced
    use ex51_problem, only: new_ex51, orientation_psd
    use crank_roots, only: crank_events, crank_reference_roots
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: events_tests

    real(wp), parameter :: pi = acos(-1.0_wp)
    real(wp), parameter :: gravity = 9.81_wp
    real(wp), parameter :: phi0 = 1.0_wp   ! the pendulum's start, at rest

    !> Event functions chosen by code: 1: x1, 2: v1, 3: x1 - shift, 4: 2 x1,
    !! 6: x - 1.5, 7: x - 1 (Example 5.1).
    type, extends(event_functions) :: chosen_events
        integer, allocatable :: which(:)
        real(wp) :: shift = 0.0_wp
        integer :: calls = 0
    contains
        procedure :: values => chosen_values
    end type chosen_events

contains

    function events_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('pendulum_stop_times', pendulum_stop_times), &
                 new_test('direction_filter', direction_filter), &
                 new_test('continue_counts_and_log', continue_counts_and_log), &
                 new_test('event_at_t0_not_reported', event_at_t0_not_reported), &
                 new_test('two_events_in_one_step', two_events_in_one_step), &
                 new_test('crank_against_reduced_ode', crank_against_reduced_ode), &
                 new_test('first_order_index2', first_order_index2), &
                 new_test('bad_input', bad_input)]
    end function events_tests

    subroutine chosen_values(self, t, x, v, e, stat)
        class(chosen_events), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        integer :: i
        self%calls = self%calls + 1
        do i = 1, size(self%which)
            select case (self%which(i))
            case (1)
                e(i) = x(1)
            case (2)
                e(i) = v(1)
            case (3)
                e(i) = x(1) - self%shift
            case (4)
                e(i) = 2.0_wp*x(1)
            case (6)
                e(i) = x(1) - 1.5_wp
            case default
                e(i) = x(1) - 1.0_wp
            end select
        end do
    end subroutine chosen_values

    !> The pendulum's period from rest at phi0: 4 K(sin(phi0/2)) / sqrt(g),
    !! K(k) = pi / (2 agm(1, sqrt(1 - k^2))).
    real(wp) function period()
        real(wp) :: a, b, c
        integer :: i
        a = 1.0_wp
        b = sqrt(1.0_wp - sin(phi0/2)**2)
        do i = 1, 40
            c = 0.5_wp*(a + b)
            b = sqrt(a*b)
            a = c
        end do
        period = 4.0_wp*(pi/(2.0_wp*a))/sqrt(gravity)
    end function period

    ! A pendulum solver from rest at phi0 with the events `which`.
    subroutine start_pendulum(solver, opts, which, stat, direction, stop, shift)
        type(regdae_solver), intent(inout) :: solver
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: which(:)
        integer, intent(out) :: stat
        integer, intent(in), optional :: direction(:)
        logical, intent(in), optional :: stop(:)
        real(wp), intent(in), optional :: shift
        type(chosen_events) :: ev
        call solver%init(new_pendulum(gravity), 0.0_wp, [sin(phi0), -cos(phi0)], [0.0_wp, 0.0_wp], opts, stat)
        if (stat /= regdae_success) return
        ev%which = which
        if (present(shift)) ev%shift = shift
        call solver%set_events(ev, size(which), stat, direction, stop)
    end subroutine start_pendulum

    ! The bottom crossings x1 = 0 of the pendulum stop the integration at
    ! (2k - 1) T/4, k = 1 ... 4, over [0, 2.2 T] (index 3 and 2, IDA,
    ! Dormand-Prince and Radau IIA, rtol 1e-6 and 1e-8): each within 10 rtol of the exact
    ! time, x1 there within 10 rtol of 0, the direction alternating (-1 first),
    ! and tout reached after the fourth with regdae_success.
    subroutine pendulum_stop_times(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        real(wp) :: x(2), v(2), tp, rtol, t
        integer :: stat, index, integ, level, k, found(1)
        integer, parameter :: integrators(3) = [integrator_ida, integrator_dopri5, integrator_radau]
        character(len=:), allocatable :: what
        tp = period()
        do index = 2, 3
            do integ = 1, 3
                do level = 6, 8, 2
                    rtol = 10.0_wp**(-level)
                    opts = solver_options()
                    opts%index = index
                    opts%rtol = rtol
                    opts%atol = rtol
                    opts%integrator = integrators(integ)
                    what = 'index '//format_int(index)//' '//integrator_name(opts%integrator)//' rtol '// &
                           format_real(rtol)
                    call start_pendulum(solver, opts, [1], stat)
                    call chk%equal(stat, regdae_success, what//': init and set_events')
                    k = 0
                    do
                        call solver%advance(2.2_wp*tp, x, stat=stat, v=v)
                        if (stat /= regdae_root_found) exit
                        k = k + 1
                        st_time: block
                            type(solver_stats) :: st
                            st = solver%statistics()
                            t = st%t
                        end block st_time
                        found = solver%roots()
                        call chk%close(t, (2*k - 1)*tp/4, 10*rtol, what//': root '//format_int(k))
                        call chk%close(x(1), 0.0_wp, 10*rtol, what//': x1 at root '//format_int(k))
                        call chk%equal(found(1), merge(-1, 1, mod(k, 2) == 1), what//': direction at root '// &
                                       format_int(k))
                        if (k > 6) exit
                    end do
                    call chk%equal(stat, regdae_success, what//': tout reached')
                    call chk%equal(k, 4, what//': four roots')
                end do
            end do
        end do
    end subroutine pendulum_stop_times

    ! direction +1 on x1: the first root is the increasing crossing at 3T/4; with
    ! -1, the decreasing one at T/4; a function with direction -1 next to one with
    ! +1 on the same x1 reports only its own crossings.
    subroutine direction_filter(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(solver_stats) :: st
        real(wp) :: x(2), tp
        integer :: stat, found(2)
        tp = period()
        opts = tolerances(1.0e-8_wp)
        call start_pendulum(solver, opts, [1], stat, direction=[1])
        call solver%advance(2.0_wp*tp, x, stat=stat)
        call chk%equal(stat, regdae_root_found, 'increasing only: a root')
        st = solver%statistics()
        call chk%close(st%t, 0.75_wp*tp, 1.0e-7_wp, 'increasing only: at 3T/4')
        call start_pendulum(solver, opts, [1, 1], stat, direction=[1, -1])
        call next_stop(solver, 2.0_wp*tp, x, stat, st, found)
        call chk%close(st%t, 0.25_wp*tp, 1.0e-7_wp, 'both: the first at T/4')
        call chk%true(all(found == [0, -1]), 'both: the decreasing one reports it')
        call next_stop(solver, 2.0_wp*tp, x, stat, st, found)
        call chk%close(st%t, 0.75_wp*tp, 1.0e-7_wp, 'both: the second at 3T/4')
        call chk%true(all(found == [1, 0]), 'both: the increasing one reports it')
    end subroutine direction_filter

    ! x1 and v1 logged and continued over [0, 1.9 T]: no stop, regdae_success at
    ! tout, 4 + 3 roots in the statistics, one line each in the events log.
    subroutine continue_counts_and_log(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(solver_stats) :: st
        real(wp) :: x(2), tp
        integer :: stat
        character(len=:), allocatable :: log
        tp = period()
        opts = tolerances(1.0e-8_wp)
        call start_pendulum(solver, opts, [1, 2], stat, stop=[.false., .false.])
        call solver%advance(1.9_wp*tp, x, stat=stat)
        call chk%equal(stat, regdae_success, 'continue: tout reached')
        st = solver%statistics()
        call chk%equal(st%roots_found, 7, 'continue: 7 roots counted')
        log = solver%events()
        call chk%equal(count_text(log, ': event 1 '), 4, 'continue: 4 log lines of event 1')
        call chk%equal(count_text(log, ': event 2 '), 3, 'continue: 3 log lines of event 2')
        ! a stop and a continue: v1 continues, x1 stops at T/4; then at 3T/4 after v1's T/2
        call start_pendulum(solver, opts, [1, 2], stat, stop=[.true., .false.])
        call solver%advance(1.9_wp*tp, x, stat=stat)
        call solver%advance(1.9_wp*tp, x, stat=stat)
        st = solver%statistics()
        call chk%equal(stat, regdae_root_found, 'stop and continue: the second stop')
        call chk%close(st%t, 0.75_wp*tp, 1.0e-7_wp, 'stop and continue: at 3T/4')
        call chk%equal(st%roots_found, 3, 'stop and continue: 3 roots so far')
    end subroutine continue_counts_and_log

    ! rtol = atol = tol.
    function tolerances(tol) result(opts)
        real(wp), intent(in) :: tol
        type(solver_options) :: opts
        opts%rtol = tol
        opts%atol = tol
    end function tolerances

    ! advance towards tout: the status, the time reached and the roots there.
    subroutine next_stop(solver, tout, x, stat, st, found)
        type(regdae_solver), intent(inout) :: solver
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: x(:)
        integer, intent(out) :: stat
        type(solver_stats), intent(out) :: st
        integer, intent(out) :: found(:)
        integer, allocatable :: roots(:)
        call solver%advance(tout, x, stat=stat)
        st = solver%statistics()
        roots = solver%roots()
        found = 0
        found(1:min(size(found), size(roots))) = roots(1:min(size(found), size(roots)))
    end subroutine next_stop

    integer function count_text(text, part) result(k)
        character(len=*), intent(in) :: text, part
        integer :: i, j
        k = 0
        i = 1
        do
            j = index(text(i:), part)
            if (j == 0) exit
            k = k + 1
            i = i + j
        end do
    end function count_text

    ! v1 = 0 at t0 (from rest): not reported there; the first root is the
    ! turning point at T/2, v1 increasing.
    subroutine event_at_t0_not_reported(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(solver_stats) :: st
        real(wp) :: x(2), tp
        integer :: stat, found(1)
        tp = period()
        opts = tolerances(1.0e-8_wp)
        call start_pendulum(solver, opts, [2], stat)
        call solver%advance(tp, x, stat=stat)
        call chk%equal(stat, regdae_root_found, 'at t0: a root later')
        st = solver%statistics()
        found = solver%roots()
        call chk%close(st%t, 0.5_wp*tp, 1.0e-7_wp, 'at t0: the first root at T/2')
        call chk%equal(found(1), 1, 'at t0: v1 increasing there')
    end subroutine event_at_t0_not_reported

    ! x1 - 1e-4 and x1 have roots 3.3e-5 apart, inside one step: two stops, in
    ! order, each at its exact time (x1 = 1e-4 at T/4 - asin(1e-4)/|phi'|, |phi'| =
    ! sqrt(2 g (1 - cos phi0)) at the bottom, the error of that formula ~1e-13);
    ! 2 x1 and x1 have one root: one stop reports both.
    subroutine two_events_in_one_step(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(solver_stats) :: st
        real(wp) :: x(2), tp, t_early, h_step
        integer :: stat, found(2)
        tp = period()
        opts = tolerances(1.0e-8_wp)
        t_early = 0.25_wp*tp - asin(1.0e-4_wp)/sqrt(2*gravity*(1 - cos(phi0)))
        call start_pendulum(solver, opts, [1, 3], stat, shift=1.0e-4_wp)
        call solver%advance(tp, x, stat=stat)
        st = solver%statistics()
        h_step = st%h_last
        found = solver%roots()
        call chk%equal(stat, regdae_root_found, 'two in a step: the first stop')
        call chk%close(st%t, t_early, 1.0e-7_wp, 'two in a step: x1 = 1e-4 first')
        call chk%true(all(found == [0, -1]), 'two in a step: the shifted function first')
        call chk%true(h_step > 10*(0.25_wp*tp - t_early), 'two in a step: the step is longer than their distance')
        call next_stop(solver, tp, x, stat, st, found)
        call chk%equal(stat, regdae_root_found, 'two in a step: the second stop')
        call chk%close(st%t, 0.25_wp*tp, 1.0e-7_wp, 'two in a step: x1 = 0 next')
        call chk%true(all(found == [-1, 0]), 'two in a step: x1 second')
        call start_pendulum(solver, opts, [1, 4], stat)
        call solver%advance(tp, x, stat=stat)
        found = solver%roots()
        call chk%true(all(found == [-1, -1]), 'one root of two functions: both reported')
    end subroutine two_events_in_one_step

    ! The slider crank from th1 = th2 = pi/2 at rest over [0, 6]: th1 through 0
    ! (the singular configurations), through pi/4 and th1' = 0 (the turning
    ! points, th1 = +-pi/2), all logged and continued, against the reduced ODE's
    ! times (CVODE at 1e-12, Newton on the event function); rtol 1e-6 and 1e-8:
    ! within 10 rtol.
    subroutine crank_against_reduced_ode(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(crank_events) :: ev
        real(wp) :: x(2), rtol, err
        real(wp), allocatable :: ref(:, :)
        integer :: stat, level, k, kind, got
        character(len=:), allocatable :: log, what
        call crank_reference_roots(9.8_wp, pi/2, 6.0_wp, ref, stat)
        call chk%equal(stat, 0, 'crank: the reference (CVODE)')
        do level = 6, 8, 2
            rtol = 10.0_wp**(-level)
            opts = solver_options()
            opts%rtol = rtol
            opts%atol = rtol
            what = 'crank rtol '//format_real(rtol)
            call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
            call solver%set_events(ev, 3, stat, stop=[.false., .false., .false.])
            call solver%advance(6.0_wp, x, stat=stat)
            call chk%true(stat >= 0 .and. stat /= regdae_root_found, what//': tout reached')
            log = solver%events()
            err = 0.0_wp
            got = 0
            do kind = 1, 3
                do k = 1, size(ref, 2)
                    if (nint(ref(2, k)) /= kind) cycle
                    err = max(err, log_distance(log, kind, ref(1, k)))
                    got = got + 1
                end do
                call chk%equal(count_text(log, ': event '//format_int(kind)//' '), count(nint(ref(2, :)) == kind), &
                               what//': the number of roots of function '//format_int(kind))
            end do
            call chk%true(err <= 10*rtol, what//': the times within 10 rtol (largest error '//format_real(err)//')')
            call chk%true(got >= 9, what//': at least 9 reference roots')
        end do
    end subroutine crank_against_reduced_ode

    ! The distance from t to the nearest time logged for function kind.
    real(wp) function log_distance(log, kind, t) result(d)
        character(len=*), intent(in) :: log
        integer, intent(in) :: kind
        real(wp), intent(in) :: t
        integer :: i, j, e
        real(wp) :: tl
        character(len=:), allocatable :: tag
        tag = ': event '//format_int(kind)//' '
        d = huge(1.0_wp)
        i = 1
        do
            j = index(log(i:), tag)
            if (j == 0) exit
            e = index(log(:i + j - 2), 't = ', back=.true.)
            read (log(e + 4:i + j - 2), *) tl
            d = min(d, abs(tl - t))
            i = i + j
        end do
    end function log_distance

    ! Example 5.1 (first order, index 2, x = t + 1 exactly, singular at t = 0)
    ! from t = -1: e = x - 1.5 stops at t = 0.5 (within 10 rtol), and e = x - 1
    ! at t = 0, the singular point itself, inside the singular interval: there
    ! the root is the regularized solution's, within 1e-3 (measured below it).
    subroutine first_order_index2(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(chosen_events) :: ev
        type(solver_stats) :: st
        real(wp) :: x(1), t_sing
        integer :: stat, found(2)
        opts = tolerances(1.0e-8_wp)
        call solver%init(new_ex51(orientation_psd), -1.0_wp, [0.0_wp], opts, stat)
        ev%which = [6, 7]
        call solver%set_events(ev, 2, stat)
        call next_stop(solver, 1.0_wp, x, stat, st, found)
        call chk%equal(stat, regdae_root_found, 'ex51: a root at the singular point')
        call chk%true(all(found == [0, 1]), 'ex51: x - 1 first')
        t_sing = st%t
        call chk%close(t_sing, 0.0_wp, 1.0e-3_wp, 'ex51: x = 1 near t = 0 (singular, got '//format_real(t_sing)//')')
        call next_stop(solver, 1.0_wp, x, stat, st, found)
        call chk%equal(stat, regdae_root_found, 'ex51: a second root')
        call chk%close(st%t, 0.5_wp, 1.0e-7_wp, 'ex51: x = 1.5 at t = 0.5')
        call chk%true(all(found == [1, 0]), 'ex51: x - 1.5 second')
        call chk%true(ev%calls == 0, 'ex51: the caller''s object is copied, not called')
    end subroutine first_order_index2

    ! Bad input: a direction of 2, arrays of the wrong length, n < 0.
    subroutine bad_input(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(chosen_events) :: ev
        integer :: stat
        ev%which = [1]
        call solver%init(new_pendulum(gravity), 0.0_wp, [sin(phi0), -cos(phi0)], [0.0_wp, 0.0_wp], opts, stat)
        call solver%set_events(ev, 1, stat, direction=[2])
        call chk%equal(stat, regdae_err_bad_input, 'direction 2')
        call chk%true(index(solver%message(), 'direction') > 0, 'direction 2: the message says so')
        call solver%set_events(ev, 1, stat, stop=[.true., .false.])
        call chk%equal(stat, regdae_err_bad_input, 'stop of length 2')
        call solver%set_events(ev, -1, stat)
        call chk%equal(stat, regdae_err_bad_input, 'n = -1')
        call solver%set_events(ev, 0, stat)
        call chk%equal(stat, regdae_success, 'n = 0 clears')
    end subroutine bad_input

end module test_events
