!> The planar pendulum in Cartesian coordinates, an index-3 DAE:
!! $$ x'' = (0, -g_{grav}) - 2 x\, y, \qquad 0 = |x|^2 - 1, $$
!! unit mass and length, G = 2 x^T, B = G^T. The curvature term of d^2g/dt^2 is
!! g_xx(v, v) = 2 |v|^2 (not zero: the paper's index-3 forms miss it). The exact
!! motion follows the angle ODE phi'' = -g_grav sin(phi), x = (sin phi, -cos phi).
module pendulum_problem
    use regdae, only: wp, second_order_problem
    use reference_ode, only: ode_system
    implicit none
    private

    !> The Cartesian pendulum (n = 2, m = 1).
    type, extends(second_order_problem), public :: pendulum
        real(wp) :: gravity = 9.81_wp   !! gravitational acceleration
    contains
        procedure :: rhs => pendulum_f
        procedure :: matrix_b => pendulum_b
        procedure :: constraint => pendulum_g
        procedure :: constraint_jacobian => pendulum_gx
    end type pendulum

    !> The angle ODE (phi, phi') of the same pendulum: the reference.
    type, extends(ode_system), public :: pendulum_angle
        real(wp) :: gravity = 9.81_wp
    contains
        procedure :: rhs => angle_rhs
    end type pendulum_angle

    public :: new_pendulum

contains

    function new_pendulum(gravity) result(p)
        real(wp), intent(in) :: gravity
        type(pendulum) :: p
        p%n = 2
        p%m = 1
        p%gravity = gravity
    end function new_pendulum

    subroutine pendulum_f(self, t, x, v, val, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = [0.0_wp, -self%gravity]
    end subroutine pendulum_f

    subroutine pendulum_b(self, t, x, v, a, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(:, 1) = 2.0_wp*x
    end subroutine pendulum_b

    subroutine pendulum_g(self, t, x, val, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = x(1)**2 + x(2)**2 - 1.0_wp
    end subroutine pendulum_g

    subroutine pendulum_gx(self, t, x, a, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, :) = 2.0_wp*x
    end subroutine pendulum_gx

    subroutine angle_rhs(self, t, y, ydot)
        class(pendulum_angle), intent(inout) :: self
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: ydot(:)
        ydot = [y(2), -self%gravity*sin(y(1))]
    end subroutine angle_rhs

end module pendulum_problem
