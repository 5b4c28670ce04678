!> Linear DAEs in the form of section 3 of the paper (eq. 3.1):
!! $$ x' = A(t) x + B(t) y + q(t), \qquad 0 = C(t) x + r(t). $$
!!
!! Extend `linear_dae_problem`, set `n` and `m`, and give A, B, C, C', q, r, r'.
!! Sign convention, stated once: section 3 writes +B y, regdae's core writes
!! x' = f - B y. regdae maps the linear DAE onto the core with f = A x + q, the same
!! B, g = C x + r, G = C, g_t = C' x + r' and **y_core = -y**; `advance` returns the
!! section-3 y. Then the core's regularizations are the theorems' ones:
!! - `method=direct`:       (C B + eps I) y_core = G f + g_t + gamma g = d, i.e. for B = C^T
!!   (C C^T + eps I) y = -d, eq. (3.2);
!! - `method=trust_region`: ((CB)^T CB + eps I) y = -(CB)^T d, eq. (3.3);
!! with d = gamma (C x + r) + C A x + C q + C' x + r'.
module regdae_linear_problem
    use regdae_kinds, only: wp
    use regdae_problem, only: dae_problem
    implicit none
    private

    !> Abstract linear DAE (3.1).
    type, abstract, extends(dae_problem), public :: linear_dae_problem
    contains
        !> A(t), n x n.
        procedure(coefficient), deferred :: coefficient_a
        !> B(t), n x m.
        procedure(coefficient), deferred :: coefficient_b
        !> C(t), m x n.
        procedure(coefficient), deferred :: coefficient_c
        !> C'(t), m x n.
        procedure(coefficient), deferred :: coefficient_c_dot
        !> q(t), length n.
        procedure(inhomogeneity), deferred :: inhomogeneity_q
        !> r(t), length m.
        procedure(inhomogeneity), deferred :: inhomogeneity_r
        !> r'(t), length m.
        procedure(inhomogeneity), deferred :: inhomogeneity_r_dot
        procedure :: rhs => linear_f
        procedure :: matrix_b => linear_b
        procedure :: constraint => linear_g
        procedure :: constraint_jacobian => linear_gx
        procedure :: constraint_dt => linear_gt
    end type linear_dae_problem

    abstract interface
        subroutine coefficient(self, t, a)
            import :: linear_dae_problem, wp
            class(linear_dae_problem), intent(inout) :: self
            real(wp), intent(in) :: t
            real(wp), intent(out) :: a(:, :)
        end subroutine coefficient

        subroutine inhomogeneity(self, t, v)
            import :: linear_dae_problem, wp
            class(linear_dae_problem), intent(inout) :: self
            real(wp), intent(in) :: t
            real(wp), intent(out) :: v(:)
        end subroutine inhomogeneity
    end interface

contains

    subroutine linear_f(self, t, x, v, stat)
        class(linear_dae_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        real(wp) :: a(self%n, self%n)
        call self%coefficient_a(t, a)
        call self%inhomogeneity_q(t, v)
        v = v + matmul(a, x)
    end subroutine linear_f

    subroutine linear_b(self, t, x, a, stat)
        class(linear_dae_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call self%coefficient_b(t, a)
    end subroutine linear_b

    subroutine linear_g(self, t, x, v, stat)
        class(linear_dae_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        real(wp) :: c(self%m, self%n)
        call self%coefficient_c(t, c)
        call self%inhomogeneity_r(t, v)
        v = v + matmul(c, x)
    end subroutine linear_g

    subroutine linear_gx(self, t, x, a, stat)
        class(linear_dae_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call self%coefficient_c(t, a)
    end subroutine linear_gx

    subroutine linear_gt(self, t, x, v, stat)
        class(linear_dae_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        real(wp) :: cd(self%m, self%n)
        call self%coefficient_c_dot(t, cd)
        call self%inhomogeneity_r_dot(t, v)
        v = v + matmul(cd, x)
    end subroutine linear_gt

end module regdae_linear_problem
