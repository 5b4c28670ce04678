!> The user's problem of order 2 (index 3; paper, eq. 4.1):
!! $$ x'' = f(x, x', t) - B(x, x', t)\,y, \qquad 0 = g(x, t), $$
!! x in R^n, y in R^m, G = g_x (m x n), B (n x m). regdae writes it first order
!! in (x, v = x').
!!
!! Extend `second_order_problem`, set `n` and `m`, and implement the deferred
!! procedures (same `stat` convention as `dae_problem`). The optional
!! `constraint_curvature` is the part of d^2 g/dt^2 that does not contain x'':
!! $$ c = g_{xx}(v, v) + 2 g_{xt} v + g_{tt}, $$
!! used by the curvature-corrected regularization (option `curvature=yes`); by
!! default it is a difference quotient of G v + g_t along (v, 1), so the user
!! supplies only G.
module regdae_second_order_problem
    use regdae_kinds, only: wp
    use regdae_differences, only: central_difference_step
    use regdae_status, only: regdae_err_memory
    implicit none
    private

    !> Abstract second-order (index-3) Hessenberg DAE.
    type, abstract, public :: second_order_problem
        integer :: n = 0   !! number of coordinates x
        integer :: m = 0   !! number of constraints and multipliers y
    contains
        !> f(x, v, t), length n.
        procedure(second_order_field), deferred :: rhs
        !> B(x, v, t), n x m.
        procedure(second_order_matrix), deferred :: matrix_b
        !> g(x, t), length m.
        procedure(position_field), deferred :: constraint
        !> G = dg/dx (x, t), m x n.
        procedure(position_matrix), deferred :: constraint_jacobian
        !> B(x, v, t) when G(x, t) is already known (regdae evaluates G first);
        !! default: `matrix_b`, ignoring gx. A `mechanical_problem` forms M^{-1} G^T
        !! from it instead of evaluating G again.
        procedure :: matrix_b_from_jacobian => default_matrix_b_from_jacobian
        !> dg/dt (x, t), length m; default: central difference quotient in t.
        procedure :: constraint_dt => second_order_constraint_dt_difference
        !> c = g_xx(v, v) + 2 g_xt v + g_tt, length m; default: difference quotient.
        procedure :: constraint_curvature => default_constraint_curvature
        !> An invariant I(x, v, t) of the motion (e.g. the energy of a conservative
        !! mechanism), checked when the option invariant_tol > 0; default: none (NaN).
        procedure :: invariant => default_invariant
        !> As `linearize_rhs` of `dae_problem`, at (t, x, v): meanwhile f may come from
        !! the user's df/dx and df/dv at (x0, v0). Default: nothing.
        procedure :: linearize_rhs => default_linearize_second_order
        !> The components of x (not of v) that IDA keeps >= 0; default: none.
        procedure :: nonnegative => default_nonnegative_second_order
    end type second_order_problem

    abstract interface
        !> A vector function of (x, v, t): f (length n).
        subroutine second_order_field(self, t, x, v, val, stat)
            import :: second_order_problem, wp
            class(second_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t, x(:), v(:)   !! time, position, velocity
            real(wp), intent(out) :: val(:)
            integer, intent(inout) :: stat          !! 0 on entry; > 0 recoverable, < 0 fatal failure
        end subroutine second_order_field

        !> A matrix function of (x, v, t): B (n x m).
        subroutine second_order_matrix(self, t, x, v, a, stat)
            import :: second_order_problem, wp
            class(second_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t, x(:), v(:)
            real(wp), intent(out) :: a(:, :)
            integer, intent(inout) :: stat
        end subroutine second_order_matrix

        !> A vector function of (x, t): g (length m).
        subroutine position_field(self, t, x, val, stat)
            import :: second_order_problem, wp
            class(second_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t, x(:)
            real(wp), intent(out) :: val(:)
            integer, intent(inout) :: stat
        end subroutine position_field

        !> A matrix function of (x, t): G (m x n).
        subroutine position_matrix(self, t, x, a, stat)
            import :: second_order_problem, wp
            class(second_order_problem), intent(inout) :: self
            real(wp), intent(in) :: t, x(:)
            real(wp), intent(out) :: a(:, :)
            integer, intent(inout) :: stat
        end subroutine position_matrix
    end interface

    public :: velocity_constraint, curvature_difference, second_order_constraint_dt_difference

    !> Constraint Jacobians with at most this many entries are formed in a local buffer.
    integer, parameter :: small_jacobian_entries = 256

contains

    subroutine default_matrix_b_from_jacobian(self, t, x, v, gx, a, stat)
        class(second_order_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(in) :: gx(:, :)      !! G(x, t), m x n
        real(wp), intent(out) :: a(:, :)      !! B, n x m
        integer, intent(inout) :: stat
        call self%matrix_b(t, x, v, a, stat)
    end subroutine default_matrix_b_from_jacobian

    !> g_t by the central difference in t (as for `dae_problem`): the default
    !! `constraint_dt`, callable from an override (through the generic
    !! `constraint_dt_difference` of module regdae).
    subroutine second_order_constraint_dt_difference(self, t, x, val, stat)
        class(second_order_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: d, tp, tm
        real(wp) :: gm(size(val))

        d = central_difference_step(t)
        tp = t + d
        tm = t - d
        call self%constraint(tp, x, val, stat)
        if (stat /= 0) return
        call self%constraint(tm, x, gm, stat)
        if (stat /= 0) return
        val = (val - gm)/(tp - tm)
    end subroutine second_order_constraint_dt_difference

    !> The velocity constraint dg/dt = G(x, t) v + g_t(x, t), length m.
    !! G goes into a local buffer when it has at most `small_jacobian_entries` entries (no heap
    !! allocation on the slope's hot path: malloc and free were 18% of the slider crank's
    !! instructions), else into an allocated one.
    subroutine velocity_constraint(problem, t, x, v, val, stat)
        class(second_order_problem), intent(inout) :: problem
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: small(small_jacobian_entries)
        real(wp), allocatable :: large(:)
        integer :: astat

        if (problem%m*problem%n <= small_jacobian_entries) then
            call jacobian_times_velocity(problem, t, x, v, small, val, stat)
            return
        end if
        allocate (large(problem%m*problem%n), stat=astat)
        if (astat /= 0) then
            stat = regdae_err_memory
            return
        end if
        call jacobian_times_velocity(problem, t, x, v, large, val, stat)
    end subroutine velocity_constraint

    ! G v + g_t with G formed in gx (the caller's buffer of at least m n entries).
    subroutine jacobian_times_velocity(problem, t, x, v, gx, val, stat)
        class(second_order_problem), intent(inout) :: problem
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: gx(problem%m, problem%n)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: row_sum
        integer :: i, j

        call problem%constraint_jacobian(t, x, gx, stat)
        if (stat /= 0) return
        call problem%constraint_dt(t, x, val, stat)
        if (stat /= 0) return
        do i = 1, problem%m
            row_sum = 0.0_wp
            do j = 1, problem%n
                row_sum = row_sum + gx(i, j)*v(j)
            end do
            val(i) = val(i) + row_sum
        end do
    end subroutine jacobian_times_velocity

    subroutine default_invariant(self, t, x, v, val, stat)
        use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
        class(second_order_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val      !! I(x, v, t)
        integer, intent(inout) :: stat
        val = ieee_value(1.0_wp, ieee_quiet_nan)
    end subroutine default_invariant

    subroutine default_linearize_second_order(self, t, x, v, on, stat)
        class(second_order_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)   !! the point of the Jacobian
        logical, intent(in) :: on               !! .true.: linearize at (t, x, v); .false.: evaluate f again
        integer, intent(inout) :: stat          !! 0 on entry; > 0 recoverable, < 0 fatal failure
    end subroutine default_linearize_second_order

    function default_nonnegative_second_order(self) result(mask)
        class(second_order_problem), intent(in) :: self
        logical :: mask(self%n)   !! true: x_i must stay >= 0
        mask = .false.
    end function default_nonnegative_second_order

    subroutine default_constraint_curvature(self, t, x, v, val, stat)
        class(second_order_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call curvature_difference(self, t, x, v, val, stat)
    end subroutine default_constraint_curvature

    !> c = d/ds [G v + g_t](x + s v, t + s) at s = 0 by a central difference,
    !! step d = u^(1/3) max(1, |x|) / max(1, |v|): error ~ u^(2/3) relative. The
    !! default `constraint_curvature`; callable from an override.
    subroutine curvature_difference(self, t, x, v, val, stat)
        class(second_order_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: small(2*small_jacobian_entries)
        real(wp), allocatable :: large(:)
        integer :: n, m, mn, astat

        ! (G v + g_t through jacobian_times_velocity with G in this routine's buffer, not through
        ! velocity_constraint: its buffer and call were 1.1M of ex52's 23.4M instructions at rtol 1e-8)
        n = size(x)
        m = size(val)
        mn = self%m*self%n   ! G's entries
        if (n + m + mn <= size(small)) then
            call curvature_in(self, t, x, v, n, m, val, stat, small, small(n + 1), small(n + m + 1))
            return
        end if
        allocate (large(n + m + mn), stat=astat)
        if (astat /= 0) then
            stat = regdae_err_memory
            return
        end if
        call curvature_in(self, t, x, v, n, m, val, stat, large, large(n + 1), large(n + m + 1))
    end subroutine curvature_difference

    ! The difference of curvature_difference with the shifted positions, the backward value and G
    ! in the caller's buffers; every array of explicit shape (x, v and val too: their assumed
    ! shapes' stride-general loops were 170 instructions a call).
    subroutine curvature_in(self, t, x, v, n, m, val, stat, shifted, minus, gx)
        class(second_order_problem), intent(inout) :: self
        integer, intent(in) :: n, m
        real(wp), intent(in) :: t, x(n), v(n)
        real(wp), intent(out) :: val(m)
        integer, intent(inout) :: stat
        real(wp), intent(out) :: shifted(n), minus(m), gx(self%m*self%n)
        real(wp) :: d, scale_x, scale_v
        integer :: i

        ! max(maxval(abs(x)), abs(t)) and max(1, maxval(abs(v))) by one loop: the same
        ! maxima where x, v and t hold no NaN (a NaN in x or v, which maxval skips, makes d
        ! and the curvature NaN here: `evaluate` then reports the state non-finite, as it
        ! did unless G and g_t depend on no NaN entry)
        scale_x = abs(t)
        scale_v = 1.0_wp
        do i = 1, n
            scale_x = max(scale_x, abs(x(i)))
            scale_v = max(scale_v, abs(v(i)))
        end do
        d = central_difference_step(scale_x)/scale_v
        shifted = x + d*v
        call jacobian_times_velocity(self, t + d, shifted, v, gx, val, stat)
        if (stat /= 0) return
        shifted = x - d*v
        call jacobian_times_velocity(self, t - d, shifted, v, gx, minus, stat)
        if (stat /= 0) return
        val = (val - minus)/(2.0_wp*d)
    end subroutine curvature_in

end module regdae_second_order_problem
