!> Index 2 for second-order systems (paper, eq. 5.4): the order-2 problem
!! x'' = f - B y, 0 = g(x, t) written first order in z = (x, v) with the
!! velocity constraint 0 = G(x, t) v + g_t(x, t) in place of g:
!! $$ z' = (v, f) - (0, B)\,y, \qquad 0 = \tilde g(z, t) = G v + g_t, $$
!! an index-2 `dae_problem` for the core. Its constraint Jacobian is
!! [d(G v + g_t)/dx, G], the x-part by central differences; G~ B~ = G B.
!! The position constraint g = 0 is not enforced (it drifts like in the paper).
module regdae_velocity_index2
    use regdae_kinds, only: wp
    use regdae_differences, only: central_difference_step
    use regdae_problem, only: dae_problem
    use regdae_second_order_problem, only: second_order_problem, velocity_constraint
    implicit none
    private

    !> A second-order problem seen as an index-2 problem on (x, v).
    type, extends(dae_problem), public :: velocity_index2_problem
        class(second_order_problem), allocatable :: second   !! the wrapped problem
    contains
        procedure :: rhs => vi2_rhs
        procedure :: matrix_b => vi2_b
        procedure :: constraint => vi2_g
        procedure :: constraint_jacobian => vi2_gx
        procedure :: linearize_rhs => vi2_linearize
        procedure :: nonnegative => vi2_nonnegative
    end type velocity_index2_problem

    public :: new_velocity_index2

contains

    !> Wrap a second-order problem (copied).
    function new_velocity_index2(second) result(p)
        class(second_order_problem), intent(in) :: second
        type(velocity_index2_problem) :: p
        allocate (p%second, source=second)
        p%n = 2*second%n
        p%m = second%m
    end function new_velocity_index2

    subroutine vi2_rhs(self, t, x, v, stat)
        class(velocity_index2_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        integer :: n
        n = self%second%n
        v(1:n) = x(n + 1:)
        call self%second%rhs(t, x(1:n), x(n + 1:), v(n + 1:), stat)
    end subroutine vi2_rhs

    subroutine vi2_linearize(self, t, x, on, stat)
        class(velocity_index2_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        logical, intent(in) :: on
        integer, intent(inout) :: stat
        call self%second%linearize_rhs(t, x(1:self%second%n), x(self%second%n + 1:), on, stat)
    end subroutine vi2_linearize

    function vi2_nonnegative(self) result(mask)
        class(velocity_index2_problem), intent(in) :: self
        logical :: mask(self%n)
        mask = .false.
        mask(1:self%second%n) = self%second%nonnegative()
    end function vi2_nonnegative

    subroutine vi2_b(self, t, x, a, stat)
        class(velocity_index2_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        integer :: n
        n = self%second%n
        a(1:n, :) = 0.0_wp
        call self%second%matrix_b(t, x(1:n), x(n + 1:), a(n + 1:, :), stat)
    end subroutine vi2_b

    subroutine vi2_g(self, t, x, v, stat)
        class(velocity_index2_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        integer :: n
        n = self%second%n
        call velocity_constraint(self%second, t, x(1:n), x(n + 1:), v, stat)
    end subroutine vi2_g

    ! [d(G v + g_t)/dx, G]: the x-columns by central differences with step
    ! u^(1/3) max(1, |x_j|).
    subroutine vi2_gx(self, t, x, a, stat)
        class(velocity_index2_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        real(wp) :: xp(self%second%n), plus(self%m), minus(self%m), d
        integer :: n, j
        n = self%second%n
        call self%second%constraint_jacobian(t, x(1:n), a(:, n + 1:), stat)
        if (stat /= 0) return
        do j = 1, n
            d = central_difference_step(x(j))
            xp = x(1:n)
            xp(j) = x(j) + d
            call velocity_constraint(self%second, t, xp, x(n + 1:), plus, stat)
            if (stat /= 0) return
            xp(j) = x(j) - d
            call velocity_constraint(self%second, t, xp, x(n + 1:), minus, stat)
            if (stat /= 0) return
            a(:, j) = (plus - minus)/(2.0_wp*d)
        end do
    end subroutine vi2_gx

end module regdae_velocity_index2
