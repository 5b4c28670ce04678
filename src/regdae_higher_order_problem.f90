!> The user's problem of order m >= 3 (index m + 1; paper, eq. 4.12):
!! $$ x^{(m)} = f(x, x', \dots, x^{(m-1)}, t) - B(x, \dots, x^{(m-1)}, t)\,y, \qquad 0 = g(x, t), $$
!! written first order in z = (x, x', ..., x^(m-1)). The multiplier is regularized
!! with the Taylor weights m!/(k! h^(m-k)) on G x^(k) (eq. 4.16, with the typos of
!! 4.14/4.15 corrected as in NOTES.md; h is the option `taylor_h`).
!!
!! Extend `higher_order_problem`, set `n`, `m` and `order`, and implement the
!! deferred procedures; the state is passed as `xs(n, order)`, column k+1 holding
!! x^(k). Same `stat` convention as `dae_problem`.
module regdae_higher_order_problem
    use regdae_kinds, only: wp
    use regdae_differences, only: central_difference_step
    implicit none
    private

    !> Abstract Hessenberg DAE of order m >= 3.
    type, abstract, public :: higher_order_problem
        integer :: n = 0       !! number of coordinates x
        integer :: m = 0       !! number of constraints and multipliers y
        integer :: order = 3   !! m in x^(m) = f - B y (>= 3; use the other types for 1 and 2)
    contains
        !> f(x, ..., x^(m-1), t), length n.
        procedure(derivatives_field), deferred :: rhs
        !> B(x, ..., x^(m-1), t), n x m.
        procedure(derivatives_matrix), deferred :: matrix_b
        !> g(x, t), length m.
        procedure(position_field), deferred :: constraint
        !> G = dg/dx (x, t), m x n.
        procedure(position_matrix), deferred :: constraint_jacobian
        !> dg/dt (x, t), length m; default: central difference quotient in t.
        procedure :: constraint_dt => default_constraint_dt
    end type higher_order_problem

    abstract interface
        subroutine derivatives_field(self, t, xs, val, stat)
            import :: higher_order_problem, wp
            class(higher_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t
            real(wp), intent(in) :: xs(:, :)   !! (n, order): x, x', ..., x^(m-1)
            real(wp), intent(out) :: val(:)
            integer, intent(inout) :: stat
        end subroutine derivatives_field

        subroutine derivatives_matrix(self, t, xs, a, stat)
            import :: higher_order_problem, wp
            class(higher_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t
            real(wp), intent(in) :: xs(:, :)
            real(wp), intent(out) :: a(:, :)
            integer, intent(inout) :: stat
        end subroutine derivatives_matrix

        subroutine position_field(self, t, x, val, stat)
            import :: higher_order_problem, wp
            class(higher_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t, x(:)
            real(wp), intent(out) :: val(:)
            integer, intent(inout) :: stat
        end subroutine position_field

        subroutine position_matrix(self, t, x, a, stat)
            import :: higher_order_problem, wp
            class(higher_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t, x(:)
            real(wp), intent(out) :: a(:, :)
            integer, intent(inout) :: stat
        end subroutine position_matrix
    end interface

    public :: taylor_weights

contains

    !> The weights of (4.16): w(k) = m!/(k! h^(m-k)), k = 0, ..., m-1, on G x^(k)
    !! (w(0) on g, w(1) also on g_t).
    pure function taylor_weights(order, h) result(w)
        integer, intent(in) :: order
        real(wp), intent(in) :: h
        real(wp) :: w(0:order - 1)
        integer :: k
        do k = 0, order - 1
            w(k) = exp(log_gamma(real(order + 1, wp)) - log_gamma(real(k + 1, wp))) / h**(order - k)
        end do
    end function taylor_weights

    subroutine default_constraint_dt(self, t, x, val, stat)
        class(higher_order_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: d, gm(size(val))
        d = central_difference_step(t)
        call self%constraint(t + d, x, val, stat)
        if (stat /= 0) return
        call self%constraint(t - d, x, gm, stat)
        if (stat /= 0) return
        val = (val - gm)/((t + d) - (t - d))
    end subroutine default_constraint_dt

end module regdae_higher_order_problem
