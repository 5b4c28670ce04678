!> Misuse and edge cases found by sanitizers, valgrind and fuzzing (issue 9):
!! strict number parsing, unrecoverable callback failures under dopri5, a
!! residual that fails at every t beyond a point, input errors that IDA
!! refuses before it writes a time, a first step that cannot be taken, and
!! copying a solver by assignment.
module test_hardening
    use regdae
    use ex51_problem, only: ex51, new_ex51, orientation_psd
    use test_solver, only: failing_ex51
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: hardening_tests

    real(wp), parameter :: t0 = -1.0_wp

    !> Example 5.1 (x = t + 1 >= 0 on [-1, 1]) with x declared nonnegative.
    type, extends(ex51) :: nonnegative_ex51
    contains
        procedure :: nonnegative => all_nonnegative
    end type nonnegative_ex51

contains

    function all_nonnegative(self) result(mask)
        class(nonnegative_ex51), intent(in) :: self
        logical :: mask(self%n)
        mask = .true.
    end function all_nonnegative

    ! A problem with nonnegative components: only IDA enforces them, so dopri5 and radau
    ! are refused with a message and auto runs IDA throughout (x(1) = 2 exactly).
    subroutine nonnegative_needs_ida(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts, used
        type(nonnegative_ex51) :: p
        real(wp) :: x(1), y(1)
        integer :: stat, integrator
        p%ex51 = new_ex51(orientation_psd)
        do integrator = integrator_dopri5, integrator_radau
            if (integrator /= integrator_dopri5 .and. integrator /= integrator_radau) cycle
            opts = solver_options()
            opts%integrator = integrator
            call solver%init(p, t0, [0.0_wp], opts, stat)
            call chk%equal(stat, regdae_err_bad_input, 'nonnegative with '//integrator_name(integrator)//' refused')
            call chk%true(index(solver%message(), 'only IDA enforces') > 0, 'the message says why')
            call solver%destroy()
        end do
        opts = solver_options()
        call solver%init(p, t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_success, 'nonnegative with auto: init')
        used = solver%options()
        call chk%equal(used%integrator, integrator_ida, 'auto runs IDA')
        call solver%advance(1.0_wp, x, y, stat)
        call chk%equal(stat, regdae_success, 'advance to t = 1')
        call chk%close(x(1), 2.0_wp, 1.0e-4_wp, 'x(1) = 2 (rtol 1e-6 default: 100 rtol)')
        call solver%destroy()
    end subroutine nonnegative_needs_ida

    real(wp) function time_reached(solver)
        type(regdae_solver), intent(in) :: solver
        type(solver_stats) :: st
        st = solver%statistics()
        time_reached = st%t
    end function time_reached

    function hardening_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('numbers_parsed_strictly', numbers_parsed_strictly), &
                 new_test('options_refuse_typos', options_refuse_typos), &
                 new_test('dopri5_stops_on_fatal_callback', dopri5_stops_on_fatal_callback), &
                 new_test('stuck_integration_stops_early', stuck_integration_stops_early), &
                 new_test('tout_too_close_to_t0', tout_too_close_to_t0), &
                 new_test('tiny_output_intervals_later', tiny_output_intervals_later), &
                 new_test('first_step_impossible', first_step_impossible), &
                 new_test('assignment_does_not_copy', assignment_does_not_copy), &
                 new_test('nonnegative_needs_ida', nonnegative_needs_ida)]
    end function hardening_tests

    ! The forms people write are read; list-directed input's extensions
    ! (1-3 for 1e-3) and non-numbers are refused, the target left unchanged.
    subroutine numbers_parsed_strictly(chk)
        type(checker), intent(inout) :: chk
        character(len=8), parameter :: good(10) = [character(len=8) :: '1e-3', '1E-3', '1d-3', '1D-3', '.5', '5.', &
                                                   '+5', '-2.5e+2', ' 7 ', '0.001']
        real(wp), parameter :: good_value(10) = [1.0e-3_wp, 1.0e-3_wp, 1.0e-3_wp, 1.0e-3_wp, 0.5_wp, 5.0_wp, 5.0_wp, &
                                                 -250.0_wp, 7.0_wp, 1.0e-3_wp]
        character(len=10), parameter :: bad(16) = [character(len=10) :: '1-3', '1+3', '1.5-2', '1e', '.', '+', '', &
                                                   'nan', 'inf', '1e400', '0x10', '1 2', '1..2', 'e5', '1e-3x', '--1']
        character(len=12), parameter :: good_int(4) = [character(len=12) :: '7', '+7', '-7', '2147483647']
        character(len=12), parameter :: bad_int(6) = [character(len=12) :: '1e3', '1.0', '2147483648', '', '7-', 'x']
        real(wp) :: x
        integer :: i, k
        logical :: ok
        do i = 1, size(good)
            x = -1.0_wp
            call parse_real(good(i), x, ok)
            call chk%true(ok .and. x == good_value(i), 'parse_real accepts "'//trim(good(i))//'"')
        end do
        do i = 1, size(bad)
            x = -1.0_wp
            call parse_real(bad(i), x, ok)
            call chk%true(.not. ok .and. x == -1.0_wp, 'parse_real refuses "'//trim(bad(i))//'"')
        end do
        do i = 1, size(good_int)
            call parse_integer(good_int(i), k, ok)
            call chk%true(ok, 'parse_integer accepts "'//trim(good_int(i))//'"')
        end do
        do i = 1, size(bad_int)
            k = -1
            call parse_integer(bad_int(i), k, ok)
            call chk%true(.not. ok .and. k == -1, 'parse_integer refuses "'//trim(bad_int(i))//'"')
        end do
    end subroutine numbers_parsed_strictly

    subroutine options_refuse_typos(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        character(len=:), allocatable :: msg
        integer :: stat
        call set_option(opts, 'eps', '1-3', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'eps=1-3 refused')
        call chk%true(index(msg, '"eps"') > 0 .and. index(msg, '1-3') > 0, 'message names the key and the value')
        call chk%true(opts%eps == option_auto, 'eps unchanged (its default, auto)')
        call set_option(opts, 'max_steps', '1e5', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'max_steps=1e5 refused (an integer)')
        call set_option(opts, 'max_steps', '99999999999', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'max_steps overflow refused')
        call set_option(opts, 'gamma', '1e400', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'gamma=1e400 (Inf) refused')
        call set_option(opts, 'eps', '1D-9', stat, msg)
        call chk%true(stat == regdae_success .and. opts%eps == 1.0e-9_wp, 'eps=1D-9 read')
    end subroutine options_refuse_typos

    ! A user routine's stat < 0 stops dopri5 at once with regdae_err_user_callback
    ! (before the fix: 47 more calls, step halving to "step size too small", -108).
    subroutine dopri5_stops_on_fatal_callback(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(failing_ex51) :: p
        type(solver_options) :: opts
        real(wp) :: x(1), y(1)
        integer, target :: calls_after
        integer :: stat
        p%ex51 = new_ex51(orientation_psd)
        p%t_fail = -0.5_wp
        p%fail_stat = -1
        p%calls_after => calls_after
        calls_after = 0
        opts%integrator = integrator_dopri5
        opts%gamma = 10.0_wp
        call solver%init(p, t0, [0.0_wp], opts, stat)
        call chk%equal(stat, regdae_success, 'init')
        call solver%advance(0.0_wp, x, y, stat)
        call chk%equal(stat, regdae_err_user_callback, 'status of a fatal callback failure')
        call chk%equal(calls_after, 1, 'no call after the one that asked to stop')
        call chk%true(index(solver%message(), 'rhs') > 0, 'message names the routine')
        call chk%true(time_reached(solver) <= -0.5_wp, 'time reached before the failure')
        call solver%destroy()
    end subroutine dopri5_stops_on_fatal_callback

    ! f fails (recoverably, or with NaN) for every t > -0.5: IDA would creep to
    ! max_steps (100000 steps); it now stops after a few dozen failures there, at
    ! t = -0.5, saying where it is stuck. dopri5 stops on its step-size floor.
    subroutine stuck_integration_stops_early(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(failing_ex51) :: p
        type(solver_options) :: opts
        type(solver_stats) :: st
        real(wp) :: x(1), y(1)
        integer :: stat, mode, integrator
        character(len=:), allocatable :: what
        p%ex51 = new_ex51(orientation_psd)
        p%t_fail = -0.5_wp
        do integrator = integrator_ida, integrator_dopri5
            do mode = 0, 1
                p%fail_stat = mode
                opts = solver_options()
                opts%integrator = integrator
                if (integrator == integrator_dopri5) opts%gamma = 10.0_wp
                what = ' ('//integrator_name(integrator)//', '//trim(merge('NaN   ', 'stat=1', mode == 0))//')'
                call solver%init(p, t0, [0.0_wp], opts, stat)
                call solver%advance(1.0_wp, x, y, stat)
                st = solver%statistics()
                call chk%equal(stat, regdae_err_integration, 'status'//what)
                call chk%true(st%steps < 1000 .and. st%res_evals < 5000, 'stops early'//what)
                call chk%close(st%t, -0.5_wp, 1.0e-6_wp, 'stuck at t = -0.5'//what)
                if (integrator == integrator_ida) &
                    call chk%true(index(solver%message(), 't = -5.0') > 0, 'message says where'//what)
            end do
        end do
        call solver%destroy()
    end subroutine stuck_integration_stops_early

    ! tout one ulp after t0: refused as bad input (IDA would refuse it without
    ! writing a time: the time reported was uninitialized); the time stays t0
    ! and the solver stays usable.
    subroutine tout_too_close_to_t0(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        real(wp) :: x(1), y(1)
        integer :: stat, integrator
        do integrator = integrator_ida, integrator_dopri5
            opts = solver_options()
            opts%integrator = integrator
            opts%gamma = 10.0_wp
            opts%stop_at_output = .true.
            call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
            call solver%advance(nearest(t0, 1.0_wp), x, y, stat)
            call chk%equal(stat, regdae_err_bad_input, 'one ulp after t0 refused ('//integrator_name(integrator)//')')
            call chk%true(index(solver%message(), 'too close') > 0, 'message says why')
            call chk%true(time_reached(solver) == t0, 'time stays t0, finite')
            call solver%advance(-0.5_wp, x, y, stat)
            call chk%equal(stat, regdae_success, 'usable afterwards')
            call chk%close(x(1), 0.5_wp, 1.0e-4_wp, 'x(-0.5)')
        end do
        call solver%destroy()
    end subroutine tout_too_close_to_t0

    ! After the start, output intervals of a few ulps are stepped across, with
    ! stops at the outputs (IDA steps them; dopri5 takes an Euler step).
    subroutine tiny_output_intervals_later(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        real(wp) :: x(1), y(1), t
        integer :: stat, integrator
        do integrator = integrator_ida, integrator_dopri5
            opts = solver_options()
            opts%integrator = integrator
            opts%gamma = 10.0_wp
            opts%stop_at_output = .true.
            call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
            call solver%advance(-0.5_wp, x, y, stat)
            t = nearest(nearest(-0.5_wp, 1.0_wp), 1.0_wp)
            call solver%advance(t, x, y, stat)
            call chk%equal(stat, regdae_success, 'two ulps later ('//integrator_name(integrator)//')')
            call chk%true(time_reached(solver) == t, 'time reached exactly')
            call chk%close(x(1), 0.5_wp, 1.0e-4_wp, 'x')
        end do
        call solver%destroy()
    end subroutine tiny_output_intervals_later

    ! No first step fits: atol so small that the weighted norm overflows, or a
    ! Baumgarte weight that turns the rounding of g(x0, t0) into a huge slope.
    ! Refused at init with a message naming the cause (IDA's own message spoke
    ! of tstop, and the time it reported was uninitialized).
    subroutine first_step_impossible(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        integer :: stat, integrator
        do integrator = integrator_ida, integrator_dopri5
            opts = solver_options()
            opts%integrator = integrator
            opts%gamma = 10.0_wp
            opts%atol = 1.0e-300_wp
            call solver%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
            call chk%equal(stat, regdae_err_bad_input, 'atol = 1e-300 ('//integrator_name(integrator)//')')
            call chk%true(index(solver%message(), 'atol') > 0, 'message names atol')
            opts%atol = 1.0e-5_wp
            opts%gamma = 1.0e300_wp
            ! x(-1) = 1e-10 is within ic_tol; gamma g = 1e290 becomes the multiplier
            call solver%init(new_ex51(orientation_psd), t0, [1.0e-10_wp], opts, stat)
            call chk%equal(stat, regdae_err_bad_input, 'gamma = 1e300 ('//integrator_name(integrator)//')')
            call chk%true(index(solver%message(), 'gamma') > 0, 'message names gamma')
            call chk%true(time_reached(solver) == t0, 'time is t0')
        end do
    end subroutine first_step_impossible

    ! a = b leaves a uninitialized (its advance says why) and b intact; a = a is
    ! harmless. Before: a shared b's IDA memory, and the second destroy freed it again.
    subroutine assignment_does_not_copy(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: a, b, fresh
        type(solver_options) :: opts
        real(wp) :: xa(1), xb(1), y(1)
        integer :: stat
        call b%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call fresh%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call a%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        a = b
        call a%advance(0.5_wp, xa, y, stat)
        call chk%equal(stat, regdae_err_not_initialized, 'the target of an assignment is uninitialized')
        call chk%true(index(a%message(), 'assignment') > 0, 'message says why')
        b = b
        call b%advance(0.5_wp, xb, y, stat)
        call fresh%advance(0.5_wp, xa, y, stat)
        call chk%equal(stat, regdae_success, 'the source still works')
        call chk%true(xa(1) == xb(1), 'and gives the same result as a fresh solver')
        call a%init(new_ex51(orientation_psd), t0, [0.0_wp], opts, stat)
        call a%advance(0.5_wp, xa, y, stat)
        call chk%true(stat == regdae_success .and. xa(1) == xb(1), 'init makes the target usable')
        call a%destroy()
        call b%destroy()
        call fresh%destroy()
    end subroutine assignment_does_not_copy

end module test_hardening
