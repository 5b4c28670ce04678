!> A complete minimal regdae program: a point driven around the unit circle.
!!
!!   x' = f(x) - B(x) y,  0 = g(x) = x1^2 + x2^2 - 1,
!!   f(x) = (x1 - x2, x1 + x2),  G = 2 (x1, x2),  B = G^T.
!!
!! f pushes the point outwards; the multiplier y = 1/2 cancels that push, and
!! x(t) = (cos t, sin t) exactly. The program checks its answer against it.
!! A warning of advance (stat > 0: x is valid, the tolerance may not be met) is
!! printed and the run goes on (exit status 0); a failure (stat < 0) stops it.
module circle_problem
    use regdae, only: wp, dae_problem
    implicit none
    private

    !> The problem: parameters (here: none) would be components of this type.
    type, extends(dae_problem), public :: circle
    contains
        procedure :: rhs => circle_f
        procedure :: matrix_b => circle_b
        procedure :: constraint => circle_g
        procedure :: constraint_jacobian => circle_gx
        ! constraint_dt is not overridden: g does not depend on t, and the
        ! default difference quotient returns 0 for it.
    end type circle

contains

    subroutine circle_f(self, t, x, v, stat)
        class(circle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v = [x(1) - x(2), x(1) + x(2)]
    end subroutine circle_f

    subroutine circle_b(self, t, x, a, stat)
        class(circle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(:, 1) = 2.0_wp*x        ! B = G^T, n x m = 2 x 1
    end subroutine circle_b

    subroutine circle_g(self, t, x, v, stat)
        class(circle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = x(1)**2 + x(2)**2 - 1.0_wp
    end subroutine circle_g

    subroutine circle_gx(self, t, x, a, stat)
        class(circle), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, :) = 2.0_wp*x        ! G, m x n = 1 x 2
    end subroutine circle_gx

end module circle_problem

program example_circle
    use regdae
    use circle_problem, only: circle
    implicit none
    type(circle) :: problem
    type(solver_options) :: opts
    type(regdae_solver) :: solver
    type(solver_stats) :: st
    real(wp) :: x(2), y(1), t, err
    integer :: k, stat

    problem%n = 2                        ! x in R^2
    problem%m = 1                        ! one constraint, one multiplier
    opts%method = method_trust_region    ! the defaults, spelled out
    opts%eps = 1.0e-6_wp
    opts%rtol = 1.0e-8_wp
    opts%atol = 1.0e-8_wp

    call solver%init(problem, 0.0_wp, [1.0_wp, 0.0_wp], opts, stat)
    if (stat /= regdae_success) then
        print '(a)', 'init failed: '//solver%message()
        stop 1
    end if
    err = 0.0_wp
    do k = 1, 10
        t = 0.5_wp*k
        call solver%advance(t, x, y, stat)
        if (stat < 0) then
            print '(a)', 'advance failed: '//solver%message()
            stop 1
        end if
        if (stat > 0) print '(a)', 'warning: '//solver%message()
        err = max(err, maxval(abs(x - [cos(t), sin(t)])))
        print '(f5.2, 3es16.8)', t, x, y
    end do
    st = solver%statistics()
    print '(a, es9.2, a, i0, a)', 'max error ', err, ' in ', st%steps, ' steps'
    call solver%destroy()
    ! rtol = 1e-8 over 0.8 revolutions: the error measured is 4e-7; 1e-5 means a bug.
    if (err > 1.0e-5_wp) stop 1
end program example_circle
