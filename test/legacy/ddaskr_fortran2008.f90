!> drivers/example_ddaskr.f (the pendulum in index-1 form by DREGDASKR) through the
!! Fortran 2008 API, `residual_problem` and `residual_solver`, with the same options
!! (one_step, the user Jacobian, lambda out of the error test, the events x and u):
!! it must print the same table, digit for digit (ctest
!! example.ddaskr_f77_matches_fortran2008): the door passes RES, JAC, RT and INFO on
!! unchanged, so IDA receives the same calls and gives the same numbers.
module ddaskr_pendulum
    use regdae_kinds, only: wp
    use regdae_residual_problem, only: residual_problem
    implicit none
    private

    !> y = (x, y, u, v, lambda), F as RES of the FORTRAN 77 program.
    type, extends(residual_problem), public :: pendulum
        real(wp) :: g = 9.81_wp
    contains
        procedure :: residual => pendulum_residual
        procedure :: has_jacobian => pendulum_has_jacobian
        procedure :: jacobian => pendulum_jacobian
        procedure :: roots => pendulum_roots
    end type pendulum

contains

    subroutine pendulum_residual(self, t, y, yp, r, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:)
        real(wp), intent(out) :: r(:)
        integer, intent(inout) :: stat
        r(1) = yp(1) - y(3)
        r(2) = yp(2) - y(4)
        r(3) = yp(3) + y(5)*y(1)
        r(4) = yp(4) + y(5)*y(2) + self%g
        r(5) = y(3)**2 + y(4)**2 - y(5)*(y(1)**2 + y(2)**2) - self%g*y(2)
    end subroutine pendulum_residual

    logical function pendulum_has_jacobian(self)
        class(pendulum), intent(in) :: self
        pendulum_has_jacobian = .true.
    end function pendulum_has_jacobian

    subroutine pendulum_jacobian(self, t, y, yp, cj, pd, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:), cj
        real(wp), intent(inout) :: pd(:, :)
        integer, intent(inout) :: stat
        pd(1, 1) = cj
        pd(1, 3) = -1.0_wp
        pd(2, 2) = cj
        pd(2, 4) = -1.0_wp
        pd(3, 1) = y(5)
        pd(3, 3) = cj
        pd(3, 5) = y(1)
        pd(4, 2) = y(5)
        pd(4, 4) = cj
        pd(4, 5) = y(2)
        pd(5, 1) = -2.0_wp*y(5)*y(1)
        pd(5, 2) = -2.0_wp*y(5)*y(2) - self%g
        pd(5, 3) = 2.0_wp*y(3)
        pd(5, 4) = 2.0_wp*y(4)
        pd(5, 5) = -(y(1)**2 + y(2)**2)
    end subroutine pendulum_jacobian

    subroutine pendulum_roots(self, t, y, yp, rval, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:)
        real(wp), intent(out) :: rval(:)
        integer, intent(inout) :: stat
        rval(1) = y(1)
        rval(2) = y(3)
    end subroutine pendulum_roots

end module ddaskr_pendulum

program ddaskr_fortran2008
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_root_found
    use regdae_residual_options, only: residual_options
    use regdae_residual_solver, only: residual_solver, residual_stats, reached_root, reached_step
    use ddaskr_pendulum, only: pendulum
    implicit none
    type(pendulum) :: problem
    type(residual_options) :: opts
    type(residual_solver) :: solver
    type(residual_stats) :: st
    real(wp) :: y(5), yp(5), y0(4), t, tout, p, pi, a, b, c, tex, err, etmax, eymax
    integer :: i, k, stat, how, nfail, nroot
    integer :: jroot(2)

    pi = 4.0_wp*atan(1.0_wp)
    a = 1.0_wp
    b = cos(pi/6.0_wp)
    do i = 1, 8
        c = 0.5_wp*(a + b)
        b = sqrt(a*b)
        a = c
    end do
    p = 4.0_wp*(pi/(2.0_wp*a))/sqrt(problem%g)
    problem%neq = 5
    problem%nroots = 2
    opts%rtol = 1.0e-8_wp
    opts%atol = 1.0e-8_wp
    opts%algebraic = [.false., .false., .false., .false., .true.]
    opts%suppress_alg = .true.
    y = [sin(pi/3.0_wp), -cos(pi/3.0_wp), 0.0_wp, 0.0_wp, 0.0_wp]
    y(5) = -problem%g*y(2)
    yp = [0.0_wp, 0.0_wp, -y(5)*y(1), -y(5)*y(2) - problem%g, 0.0_wp]
    y0 = y(1:4)
    t = 0.0_wp
    nfail = 0
    nroot = 0
    etmax = 0.0_wp
    eymax = 0.0_wp
    call solver%init(problem, t, y, yp, opts, stat)
    if (stat /= regdae_success) error stop 'init failed'
    write (*, '(a)') ' pendulum, index 1, DREGDASKR, RTOL = 1E-8'
    write (*, '(a)') ' IDID  T                        X                        U'
    do k = 1, 17
        tout = k*p/8.0_wp
        do
            call solver%advance(tout, t, y, yp, stat, one_step=.true., reached=how)
            if (stat /= regdae_success .and. stat /= regdae_root_found) then
                write (*, '(a)') solver%message()
                error stop 1
            end if
            if (how == reached_step) cycle   ! IDID = 1: a step short of tout
            write (*, '(i4, 3es25.16)') merge(5, 3, how == reached_root), t, y(1), y(3)
            if (how /= reached_root) exit
            nroot = nroot + 1
            jroot = solver%roots()
            if (jroot(1) /= 0) then
                i = nint((4.0_wp*t/p - 1.0_wp)/2.0_wp)
                tex = (2*i + 1)*p/4.0_wp
                if (jroot(1) /= (-1)**(i + 1)) nfail = nfail + 1
            else
                i = nint(2.0_wp*t/p)
                tex = i*p/2.0_wp
                if (jroot(2) /= (-1)**(i + 1)) nfail = nfail + 1
            end if
            err = abs(t - tex)
            etmax = max(etmax, err)
            if (err > 10.0_wp*opts%rtol) nfail = nfail + 1
        end do
        if (mod(k, 8) == 0) then
            do i = 1, 4
                err = abs(y(i) - y0(i))
                eymax = max(eymax, err)
                if (err > 100.0_wp*opts%rtol) nfail = nfail + 1
            end do
        end if
    end do
    st = solver%statistics()
    write (*, '(a, i6, a, i6, a, i5, a, i3)') ' steps', st%steps, '  RES calls', st%res_evals, '  JAC calls', &
        st%jac_evals, '  roots', nroot
    write (*, '(a, es9.2, a, es9.2)') ' largest error: root times', etmax, '  state after a period', eymax
    call solver%free()
    if (nfail > 0 .or. nroot /= 8) then
        write (*, '(a, i3, a)') ' FAILED:', nfail, ' checks'
        error stop 1
    end if
    write (*, '(a)') ' all checks passed'
end program ddaskr_fortran2008
