!> The user's problem: a semi-explicit index-2 Hessenberg DAE (paper, eq. 2.1)
!! $$ x' = f(x, t) - B(x, t)\,y, \qquad 0 = g(x, t), $$
!! with x in R^n, y in R^m, G = g_x (m x n) and B (n x m).
!!
!! Extend `dae_problem`, set the components `n` and `m`, and implement the
!! deferred procedures. Problem parameters are components of your type (never
!! module variables), so several problems can live in one program. Every
!! routine receives `stat = 0`; leave it so on success, set it > 0 for a
!! recoverable failure (the step is retried with a smaller step size) or < 0
!! to stop the integration.
!!
!! Sign convention: B multiplies y with a minus sign, as in sections 2 and 4 of
!! the paper. A linear DAE written as x' = A x + C^T y + q (section 3) has
!! B = -C^T here.
module regdae_problem
    use regdae_kinds, only: wp
    use regdae_differences, only: central_difference_step
    implicit none
    private

    !> Abstract semi-explicit index-2 Hessenberg DAE.
    type, abstract, public :: dae_problem
        integer :: n = 0   !! number of differential variables x
        integer :: m = 0   !! number of constraints and multipliers y
    contains
        !> f(x, t), length n.
        procedure(vector_field), deferred :: rhs
        !> B(x, t), n x m.
        procedure(matrix_field), deferred :: matrix_b
        !> g(x, t), length m.
        procedure(vector_field), deferred :: constraint
        !> G = dg/dx (x, t), m x n.
        procedure(matrix_field), deferred :: constraint_jacobian
        !> dg/dt (x, t), length m; default: central difference quotient in t.
        procedure :: constraint_dt => default_constraint_dt
        !> Called by the solver around the difference-quotient Jacobian of IDA's dense
        !! Newton matrix at (t, x): on = .true. before its perturbed evaluations, then
        !! .false.; meanwhile `rhs` may return f(x0) + J (x - x0), J = df/dx at x0 from
        !! a Jacobian the user supplied (the FORTRAN 77 door's JAC). Default: nothing.
        procedure :: linearize_rhs => default_linearize_rhs
        !> The components of x that IDA keeps >= 0 (its constraint option; the FORTRAN 77
        !! door's INFO(10)); default: none.
        procedure :: nonnegative => default_nonnegative
    end type dae_problem

    public :: constraint_dt_difference

    abstract interface
        !> A vector-valued function of (x, t): f (length n) or g (length m).
        subroutine vector_field(self, t, x, v, stat)
            import :: dae_problem, wp
            class(dae_problem), intent(inout) :: self
            real(wp), intent(in) :: t       !! time
            real(wp), intent(in) :: x(:)    !! state, length n
            real(wp), intent(out) :: v(:)   !! value
            integer, intent(inout) :: stat  !! 0 on entry; > 0 recoverable, < 0 fatal failure
        end subroutine vector_field

        !> A matrix-valued function of (x, t): B (n x m) or G (m x n).
        subroutine matrix_field(self, t, x, a, stat)
            import :: dae_problem, wp
            class(dae_problem), intent(inout) :: self
            real(wp), intent(in) :: t          !! time
            real(wp), intent(in) :: x(:)       !! state, length n
            real(wp), intent(out) :: a(:, :)   !! value
            integer, intent(inout) :: stat     !! 0 on entry; > 0 recoverable, < 0 fatal failure
        end subroutine matrix_field
    end interface

contains

    subroutine default_constraint_dt(self, t, x, v, stat)
        class(dae_problem), intent(inout) :: self
        real(wp), intent(in) :: t        !! time
        real(wp), intent(in) :: x(:)     !! state, length n
        real(wp), intent(out) :: v(:)    !! g_t, length m
        integer, intent(inout) :: stat
        call constraint_dt_difference(self, t, x, v, stat)
    end subroutine default_constraint_dt

    subroutine default_linearize_rhs(self, t, x, on, stat)
        class(dae_problem), intent(inout) :: self
        real(wp), intent(in) :: t        !! time
        real(wp), intent(in) :: x(:)     !! the point of the Jacobian, length n
        logical, intent(in) :: on        !! .true.: linearize at (t, x); .false.: evaluate f again
        integer, intent(inout) :: stat   !! 0 on entry; > 0 recoverable, < 0 fatal failure
    end subroutine default_linearize_rhs

    function default_nonnegative(self) result(mask)
        class(dae_problem), intent(in) :: self
        logical :: mask(self%n)   !! true: x_i must stay >= 0
        mask = .false.
    end function default_nonnegative

    !> g_t by the central difference (g(x, t+d) - g(x, t-d)) / (2 d),
    !! d = u^(1/3) max(|t|, 1): truncation and rounding errors both ~ u^(2/3).
    !! The default `constraint_dt`; callable from an override.
    subroutine constraint_dt_difference(problem, t, x, v, stat)
        class(dae_problem), intent(inout) :: problem
        real(wp), intent(in) :: t        !! time
        real(wp), intent(in) :: x(:)     !! state, length n
        real(wp), intent(out) :: v(:)    !! g_t, length m
        integer, intent(inout) :: stat
        real(wp) :: d, tp, tm
        real(wp) :: gm(size(v))

        d = central_difference_step(t)
        tp = t + d
        tm = t - d
        call problem%constraint(tp, x, v, stat)
        if (stat /= 0) return
        call problem%constraint(tm, x, gm, stat)
        if (stat /= 0) return
        v = (v - gm)/(tp - tm)
    end subroutine constraint_dt_difference

end module regdae_problem
