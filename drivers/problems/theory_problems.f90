!> Manufactured linear DAEs (section-3 form x' = A x + B y + q, 0 = C x + r) for
!! every case of Theorems 3.1 and 3.2, each with a closed-form solution, on
!! t in [-1, 1] (singular cases: t* = 0). With e(t) = (cos t, sin t),
!! s(t) = 1 + sin t, x*(t) = (1 + sin(t)/2, cos 2t), A = [-1/2, 1; -1, -1/2]:
!!
!! | case  | theorem | C          | B          | y*              | sigma_min(CB) | sigma_min(C C^T) |
!! |-------|---------|------------|------------|-----------------|---------------|------------------|
!! | R1    | 3.1.1   | [e^T; e^T] | C^T        | (s/2, s/2)      | 2 (rank 1)    | 2 (rank 1)       |
!! | R2    | 3.1.2   | [e^T; e^T] | [2e, -e]   | (s, s)          | rank 1        | rank 1           |
!! | S1    | 3.2.1   | t e^T      | C^T        | s/t             | t^2           | t^2              |
!! | S2    | 3.2.1   | t^2 e^T    | C^T        | s/t^2           | t^4           | t^4              |
!! | S3    | 3.2.2   | t e^T      | e          | s               | |t|           | t^2              |
!! | S4    | 3.2.2   | t^2 e^T    | e          | s               | t^2           | t^4              |
!! | EX51  | 3.2.1   | t          | t          | -1/t            | t^2           | t^2              |
!!
!! In all 2-D cases B y* = s e, r = -C x*, and q = x*' - A x* - B y*, so (x*, y*)
!! solves the DAE (x* is unique; y* is the minimum-norm multiplier in R1).
!! EX51 is Example 5.1: x' = 2 + t y, 0 = t x - t(t+1), x* = t + 1.
!! The S cases can be moved and scaled (drivers/trust, family linear with seed=S): with
!! `singular_at` = t* and `scale` = c, C = c (t - t*)^p e^T (p = 1, 2), the singular point at t*
!! and GB = c^2 (t - t*)^(2p) for S1, S2 (y* = s / (c (t - t*)^p)); x*, B y* and q are unchanged.
!! The defaults t* = 0, c = 1 give the table's cases bit for bit.
module theory_problems
    use regdae, only: wp, linear_dae_problem
    implicit none
    private

    character(len=4), parameter, public :: theory_cases(7) = ['R1  ', 'R2  ', 'S1  ', 'S2  ', 'S3  ', 'S4  ', 'EX51']

    !> One manufactured case.
    type, extends(linear_dae_problem), public :: theory_problem
        character(len=4) :: name = 'R1'
        integer :: power = 1          !! C vanishes like t^power (S cases)
        logical :: b_is_ct = .true.   !! B = C^T
        real(wp) :: singular_at = 0.0_wp   !! t*, where C vanishes (S cases)
        real(wp) :: scale = 1.0_wp         !! c, the factor of C (S cases)
    contains
        procedure :: coefficient_a => tp_a
        procedure :: coefficient_b => tp_b
        procedure :: coefficient_c => tp_c
        procedure :: coefficient_c_dot => tp_cd
        procedure :: inhomogeneity_q => tp_q
        procedure :: inhomogeneity_r => tp_r
        procedure :: inhomogeneity_r_dot => tp_rd
        !> Exact x*(t).
        procedure :: x_exact => tp_x
        !> Exact x*'(t).
        procedure :: x_exact_dot => tp_xd
        !> The theorem and regularization this case illustrates.
        procedure :: theorem => tp_theorem
    end type theory_problem

    public :: new_theory_problem

contains

    !> The case `name` (one of `theory_cases`).
    function new_theory_problem(name) result(p)
        character(len=*), intent(in) :: name
        type(theory_problem) :: p
        p%name = name
        select case (name)
        case ('R1'); p%n = 2; p%m = 2; p%b_is_ct = .true.
        case ('R2'); p%n = 2; p%m = 2; p%b_is_ct = .false.
        case ('S1'); p%n = 2; p%m = 1; p%power = 1; p%b_is_ct = .true.
        case ('S2'); p%n = 2; p%m = 1; p%power = 2; p%b_is_ct = .true.
        case ('S3'); p%n = 2; p%m = 1; p%power = 1; p%b_is_ct = .false.
        case ('S4'); p%n = 2; p%m = 1; p%power = 2; p%b_is_ct = .false.
        case default; p%name = 'EX51'; p%n = 1; p%m = 1; p%power = 1; p%b_is_ct = .true.
        end select
    end function new_theory_problem

    pure function theorem_of(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        select case (name)
        case ('R1'); text = 'Thm 3.1.1: constant-rank redundant, B = C^T, N(C^T) constant'
        case ('R2'); text = 'Thm 3.1.2: constant-rank redundant, B /= C^T, N(B^T) = N(C)'
        case ('S1'); text = 'Thm 3.2.1: isolated singularity, B = C^T, C ~ t'
        case ('S2'); text = 'Thm 3.2.1: isolated singularity, B = C^T, C ~ t^2'
        case ('S3'); text = 'Thm 3.2.2: isolated singularity, B /= C^T, C ~ t'
        case ('S4'); text = 'Thm 3.2.2: isolated singularity, B /= C^T, C ~ t^2'
        case default; text = 'Example 5.1 as a linear DAE (Thm 3.2.1, B = C^T = t)'
        end select
    end function theorem_of

    function tp_theorem(self) result(text)
        class(theory_problem), intent(in) :: self
        character(len=:), allocatable :: text
        text = theorem_of(self%name)
    end function tp_theorem

    pure function e(t)
        real(wp), intent(in) :: t
        real(wp) :: e(2)
        e = [cos(t), sin(t)]
    end function e

    pure function ed(t)
        real(wp), intent(in) :: t
        real(wp) :: ed(2)
        ed = [-sin(t), cos(t)]
    end function ed

    pure real(wp) function s(t)
        real(wp), intent(in) :: t
        s = 1.0_wp + sin(t)
    end function s

    function tp_x(self, t) result(x)
        class(theory_problem), intent(in) :: self
        real(wp), intent(in) :: t
        real(wp), allocatable :: x(:)
        if (self%name == 'EX51') then
            x = [t + 1.0_wp]
        else
            x = [1.0_wp + 0.5_wp*sin(t), cos(2.0_wp*t)]
        end if
    end function tp_x

    function tp_xd(self, t) result(x)
        class(theory_problem), intent(in) :: self
        real(wp), intent(in) :: t
        real(wp), allocatable :: x(:)
        if (self%name == 'EX51') then
            x = [1.0_wp]
        else
            x = [0.5_wp*cos(t), -2.0_wp*sin(2.0_wp*t)]
        end if
    end function tp_xd

    subroutine tp_a(self, t, a)
        class(theory_problem), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: a(:, :)
        if (self%name == 'EX51') then
            a = 0.0_wp
        else
            a = reshape([-0.5_wp, -1.0_wp, 1.0_wp, -0.5_wp], [2, 2])
        end if
    end subroutine tp_a

    subroutine tp_c(self, t, a)
        class(theory_problem), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: a(:, :)
        select case (self%name)
        case ('R1', 'R2')
            a(1, :) = e(t)
            a(2, :) = e(t)
        case ('EX51')
            a(1, 1) = t
        case default
            a(1, :) = self%scale*(t - self%singular_at)**self%power*e(t)
        end select
    end subroutine tp_c

    subroutine tp_cd(self, t, a)
        class(theory_problem), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: a(:, :)
        select case (self%name)
        case ('R1', 'R2')
            a(1, :) = ed(t)
            a(2, :) = ed(t)
        case ('EX51')
            a(1, 1) = 1.0_wp
        case default
            a(1, :) = self%scale*(self%power*(t - self%singular_at)**(self%power - 1)*e(t) + &
                                  (t - self%singular_at)**self%power*ed(t))
        end select
    end subroutine tp_cd

    subroutine tp_b(self, t, a)
        class(theory_problem), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: a(:, :)
        real(wp) :: c(self%m, self%n)
        select case (self%name)
        case ('R2')
            a(:, 1) = 2.0_wp*e(t)
            a(:, 2) = -e(t)
        case ('S3', 'S4')
            a(:, 1) = e(t)
        case default   ! B = C^T
            call self%coefficient_c(t, c)
            a = transpose(c)
        end select
    end subroutine tp_b

    ! q = x*' - A x* - B y*, with B y* = s e (2-D cases); EX51: q = 2.
    subroutine tp_q(self, t, v)
        class(theory_problem), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: v(:)
        real(wp) :: a(self%n, self%n)
        if (self%name == 'EX51') then
            v = 2.0_wp
        else
            call self%coefficient_a(t, a)
            v = self%x_exact_dot(t) - matmul(a, self%x_exact(t)) - s(t)*e(t)
        end if
    end subroutine tp_q

    ! r = -C x*.
    subroutine tp_r(self, t, v)
        class(theory_problem), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: v(:)
        real(wp) :: c(self%m, self%n)
        call self%coefficient_c(t, c)
        v = -matmul(c, self%x_exact(t))
    end subroutine tp_r

    ! r' = -(C' x* + C x*').
    subroutine tp_rd(self, t, v)
        class(theory_problem), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: v(:)
        real(wp) :: c(self%m, self%n), cd(self%m, self%n)
        call self%coefficient_c(t, c)
        call self%coefficient_c_dot(t, cd)
        v = -(matmul(cd, self%x_exact(t)) + matmul(c, self%x_exact_dot(t)))
    end subroutine tp_rd

end module theory_problems
