!> The plain-DAE door in Fortran 2008 (`residual_solver`, F(t, y, y') = 0 by IDA):
!! misuse returns a status and a message; consistent initial values by
!! IDACalcIC against the exact ones; two solvers interleaved in one process give
!! what each gives alone, bit for bit (no global state); per-component tolerances;
!! free twice and a new init on a used solver. The DDASKR door over it:
!! test/legacy/ddaskr_tester.f.
module test_plain_dae
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_residual_problem, only: residual_problem
    use regdae_residual_options, only: residual_options, initial_algebraic
    use regdae_residual_solver, only: residual_solver, residual_stats, reached_tout
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: plain_dae_tests

    !> y1' = -k y1, 0 = y2 - 2 y1: y1 = exp(-k t) y1(0), y2 = 2 y1.
    type, extends(residual_problem) :: decay
        real(wp) :: k = 1.0_wp
    contains
        procedure :: residual => decay_residual
    end type decay

contains

    function plain_dae_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('misuse_statuses', misuse_statuses), &
                 new_test('initial_values_exact', initial_values_exact), &
                 new_test('two_solvers_interleaved', two_solvers_interleaved), &
                 new_test('tolerance_per_component', tolerance_per_component)]
    end function plain_dae_tests

    subroutine decay_residual(self, t, y, yp, r, stat)
        class(decay), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:)
        real(wp), intent(out) :: r(:)
        integer, intent(inout) :: stat
        r(1) = yp(1) + self%k*y(1)
        r(2) = y(2) - 2.0_wp*y(1)
    end subroutine decay_residual

    ! advance before init, bad options, bad sizes: a status and a message, no crash;
    ! free twice is harmless; init on a used solver starts afresh.
    subroutine misuse_statuses(chk)
        type(checker), intent(inout) :: chk
        type(residual_solver) :: s
        type(residual_options) :: opts
        type(decay) :: p
        real(wp) :: t, y(2), yp(2)
        integer :: stat
        t = 0.0_wp
        y = [1.0_wp, 2.0_wp]
        yp = [-1.0_wp, 0.0_wp]
        call s%advance(1.0_wp, t, y, yp, stat)
        call chk%equal(stat, regdae_err_not_initialized, 'advance before init')
        call chk%true(len(s%message()) > 0, 'its message')
        p%neq = 2
        opts%rtol_v = [1.0e-6_wp]
        call s%init(p, t, y, yp, opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'rtol_v of the wrong length')
        call chk%true(index(s%message(), 'rtol_v') > 0, 'the message names rtol_v')
        call chk%true(.not. s%ready(), 'nothing created')
        deallocate (opts%rtol_v)
        opts%band_lower = 1
        call s%init(p, t, y, yp, opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'band_lower without band_upper')
        opts%band_lower = -1
        opts%initial = initial_algebraic
        call s%init(p, t, y, yp, opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'initial_algebraic without algebraic')
        opts%initial = 0
        call s%init(p, t, y(1:1), yp, opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'y0 of the wrong length')
        call s%init(p, t, y, yp, opts, stat)
        call chk%equal(stat, regdae_success, 'a good init')
        call s%advance(1.0_wp, t, y, yp, stat)
        call chk%equal(stat, regdae_success, 'advance')
        call s%init(p, 0.0_wp, [1.0_wp, 2.0_wp], [-1.0_wp, 0.0_wp], opts, stat)
        call chk%equal(stat, regdae_success, 'init again on a used solver')
        call s%free()
        call s%free()
        call chk%true(.not. s%ready(), 'free twice')
    end subroutine misuse_statuses

    ! y2 and y1' guessed 0: IDACalcIC gives y2 = 2, y1' = -k exactly (a linear
    ! system); the run to t = 1 then within 10 rtol of exp(-k).
    subroutine initial_values_exact(chk)
        type(checker), intent(inout) :: chk
        type(residual_solver) :: s
        type(residual_options) :: opts
        type(decay) :: p
        real(wp) :: t, y(2), yp(2)
        integer :: stat, how
        p%neq = 2
        p%k = 3.0_wp
        opts%rtol = 1.0e-8_wp
        opts%atol = 1.0e-10_wp
        opts%algebraic = [.false., .true.]
        opts%initial = initial_algebraic
        t = 0.0_wp
        y = [1.0_wp, 0.0_wp]
        yp = 0.0_wp
        call s%init(p, t, y, yp, opts, stat)
        call s%initial_values(1.0_wp, y, yp, stat)
        call chk%equal(stat, regdae_success, 'IDACalcIC')
        call chk%close(y(2), 2.0_wp, 1.0e-12_wp, 'y2(0)')
        call chk%close(yp(1), -3.0_wp, 1.0e-10_wp, 'y1''(0)')
        call s%advance(1.0_wp, t, y, yp, stat, reached=how)
        call chk%equal(how, reached_tout, 'reached tout')
        call chk%close(y(1), exp(-3.0_wp), 10.0_wp*opts%rtol, 'y1(1)')
        call chk%close(y(2), 2.0_wp*exp(-3.0_wp), 20.0_wp*opts%rtol, 'y2(1)')
        call s%free()
    end subroutine initial_values_exact

    ! Two solvers with different rates and tolerances, advanced in turn, against each
    ! alone: the same numbers and step counts, bit for bit.
    subroutine two_solvers_interleaved(chk)
        type(checker), intent(inout) :: chk
        type(residual_solver) :: s(2)
        type(residual_options) :: opts(2)
        type(decay) :: p(2)
        real(wp) :: t(2), y(2, 2), yp(2, 2), alone(2, 2)
        integer :: stat, j, k
        integer(int64) :: steps(2)
        type(residual_stats) :: st(2)
        do j = 1, 2
            p(j)%neq = 2
            p(j)%k = real(j, wp)
            opts(j)%rtol = 10.0_wp**(-4 - 3*j)
        end do
        do j = 1, 2   ! each alone
            call start(j)
            do k = 1, 10
                call s(j)%advance(0.1_wp*k, t(j), y(:, j), yp(:, j), stat)
            end do
            alone(:, j) = y(:, j)
            st(j) = s(j)%statistics()
            steps(j) = st(j)%steps
            call s(j)%free()
        end do
        call start(1)
        call start(2)
        do k = 1, 10
            do j = 1, 2
                call s(j)%advance(0.1_wp*k, t(j), y(:, j), yp(:, j), stat)
            end do
        end do
        call chk%true(all(y == alone), 'interleaved = alone, bit for bit')
        st(1) = s(1)%statistics()
        st(2) = s(2)%statistics()
        call chk%true(st(1)%steps == steps(1) .and. st(2)%steps == steps(2) .and. steps(1) /= steps(2), &
                      'the same step counts (and the two runs differ)')
        call s(1)%free()
        call s(2)%free()
    contains
        subroutine start(i)
            integer, intent(in) :: i
            t(i) = 0.0_wp
            y(:, i) = [1.0_wp, 2.0_wp]
            yp(:, i) = [-p(i)%k, 0.0_wp]
            call s(i)%init(p(i), t(i), y(:, i), yp(:, i), opts(i), stat)
        end subroutine start
    end subroutine two_solvers_interleaved

    ! rtol_v: a tight tolerance on y1 (1e-10, y2 1e-3) makes y1 far more accurate than
    ! 1e-3 on both.
    subroutine tolerance_per_component(chk)
        type(checker), intent(inout) :: chk
        type(residual_solver) :: s
        type(residual_options) :: opts
        type(decay) :: p
        real(wp) :: t, y(2), yp(2), err(2)
        integer :: stat, run
        p%neq = 2
        opts%atol = 1.0e-12_wp
        allocate (opts%rtol_v(2))
        do run = 1, 2
            opts%rtol_v(1) = merge(1.0e-3_wp, 1.0e-10_wp, run == 1)
            opts%rtol_v(2) = 1.0e-3_wp
            t = 0.0_wp
            y = [1.0_wp, 2.0_wp]
            yp = [-1.0_wp, 0.0_wp]
            call s%init(p, t, y, yp, opts, stat)
            call s%advance(2.0_wp, t, y, yp, stat)
            err(run) = abs(y(1) - exp(-2.0_wp))
            call s%free()
        end do
        call chk%true(err(2) < 1.0e-3_wp*err(1), 'rtol_v(1) = 1e-10: y1 1000 times more accurate')
        call chk%true(err(2) < 1.0e-8_wp, 'y1 within 1e-8')
    end subroutine tolerance_per_component

end module test_plain_dae
