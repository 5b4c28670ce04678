!> Example 5.1 of Petzold, Ren & Maly (1997), a linear index-2 DAE singular at t = 0:
!! $$ x' = 2 + t y, \qquad 0 = t x - t (t + 1), $$
!! exact solution x = t + 1, y = -1/t. In regdae's form x' = f - B y:
!! f = 2, g = t x - t(t+1), G = t, g_t = x - 2t - 1, and
!! - orientation `paper`: B = -t (the equation as printed), GB = -t^2 <= 0;
!! - orientation `psd`:   B = +t = G^T, GB = t^2 >= 0. The multiplier changes sign:
!!   x' = 2 - t y, y = 1/t. x is the same in both.
module ex51_problem
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae, only: wp, dae_problem
    implicit none
    private

    integer, parameter, public :: orientation_psd = 1    !! B = t
    integer, parameter, public :: orientation_paper = 2  !! B = -t

    !> Example 5.1 (n = m = 1) with the sign of B as a parameter.
    type, extends(dae_problem), public :: ex51
        real(wp) :: b_sign = 1.0_wp   !! +1: B = t (psd); -1: B = -t (paper)
    contains
        procedure :: rhs => ex51_rhs
        procedure :: matrix_b => ex51_b
        procedure :: constraint => ex51_g
        procedure :: constraint_jacobian => ex51_gx
        procedure :: constraint_dt => ex51_gt
        !> Exact x(t) = t + 1.
        procedure, nopass :: x_exact => ex51_x_exact
        !> Exact y(t); undefined at t = 0, where it returns NaN.
        procedure :: y_exact => ex51_y_exact
    end type ex51

    public :: new_ex51

contains

    !> Example 5.1 with the given orientation (`orientation_psd` or `orientation_paper`).
    function new_ex51(orientation) result(p)
        integer, intent(in) :: orientation
        type(ex51) :: p
        p%n = 1
        p%m = 1
        p%b_sign = merge(-1.0_wp, 1.0_wp, orientation == orientation_paper)
    end function new_ex51

    subroutine ex51_rhs(self, t, x, v, stat)
        class(ex51), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = 2.0_wp
    end subroutine ex51_rhs

    subroutine ex51_b(self, t, x, a, stat)
        class(ex51), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, 1) = self%b_sign*t
    end subroutine ex51_b

    subroutine ex51_g(self, t, x, v, stat)
        class(ex51), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = t*x(1) - t*(t + 1.0_wp)
    end subroutine ex51_g

    subroutine ex51_gx(self, t, x, a, stat)
        class(ex51), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, 1) = t
    end subroutine ex51_gx

    subroutine ex51_gt(self, t, x, v, stat)
        class(ex51), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        v(1) = x(1) - 2.0_wp*t - 1.0_wp
    end subroutine ex51_gt

    pure real(wp) function ex51_x_exact(t)
        real(wp), intent(in) :: t
        ex51_x_exact = t + 1.0_wp
    end function ex51_x_exact

    real(wp) function ex51_y_exact(self, t)
        class(ex51), intent(in) :: self
        real(wp), intent(in) :: t
        if (t == 0.0_wp) then
            ex51_y_exact = ieee_value(1.0_wp, ieee_quiet_nan)
        else
            ex51_y_exact = self%b_sign/t
        end if
    end function ex51_y_exact

end module ex51_problem
