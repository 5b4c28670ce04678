!> An order-3 (index-4) test problem with a kinematic singularity, in the
!! spirit of Example 5.1:
!! $$ x''' = f(t) - t\,y, \qquad 0 = g = t\,(x - \varphi(t)), \qquad \varphi = 1 + \sin t, $$
!! f = phi''' + 1 = 1 - cos t, so x = phi(t) and y = 1/t exactly. G = t = B, GB = t^2
!! vanishes at t = 0, where y is unbounded and x smooth.
module order3_problem
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae, only: wp, higher_order_problem
    implicit none
    private

    !> The order-3 problem (n = m = 1).
    type, extends(higher_order_problem), public :: order3
    contains
        procedure :: rhs => o3_f
        procedure :: matrix_b => o3_b
        procedure :: constraint => o3_g
        procedure :: constraint_jacobian => o3_gx
        procedure :: constraint_dt => o3_gt
    end type order3

    public :: new_order3, order3_exact

contains

    function new_order3() result(p)
        type(order3) :: p
        p%n = 1
        p%m = 1
        p%order = 3
    end function new_order3

    !> Exact x, x', x'' (column 1 of `xs`) and y at t (y = NaN at t = 0).
    subroutine order3_exact(t, xs, y)
        real(wp), intent(in) :: t
        real(wp), intent(out) :: xs(1, 3), y
        xs(1, :) = [1.0_wp + sin(t), cos(t), -sin(t)]
        y = ieee_value(1.0_wp, ieee_quiet_nan)
        if (t /= 0.0_wp) y = 1.0_wp/t
    end subroutine order3_exact

    subroutine o3_f(self, t, xs, val, stat)
        class(order3), intent(inout) :: self
        real(wp), intent(in) :: t, xs(:, :)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = 1.0_wp - cos(t)
    end subroutine o3_f

    subroutine o3_b(self, t, xs, a, stat)
        class(order3), intent(inout) :: self
        real(wp), intent(in) :: t, xs(:, :)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, 1) = t
    end subroutine o3_b

    subroutine o3_g(self, t, x, val, stat)
        class(order3), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = t*(x(1) - 1.0_wp - sin(t))
    end subroutine o3_g

    subroutine o3_gx(self, t, x, a, stat)
        class(order3), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, 1) = t
    end subroutine o3_gx

    subroutine o3_gt(self, t, x, val, stat)
        class(order3), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = x(1) - 1.0_wp - sin(t) - t*cos(t)
    end subroutine o3_gt

end module order3_problem
