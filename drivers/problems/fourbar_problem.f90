!> A parallelogram four-bar linkage in absolute angles (drivers/trust, family `fourbar`).
!!
!! Ground pivots O1 = (0, 0) and O2 = (L, 0); crank 1 (length r) from O1 to the joint A,
!! the coupler (length L) from A to the joint B, crank 2 (length r) from O2 to B. The
!! coordinates are the three absolute angles q = (th1, th2, th3) of crank 1, the coupler
!! and crank 2 from the +x axis:
!! $$ A = r(\cos\theta_1, \sin\theta_1), \quad B = A + L(\cos\theta_2, \sin\theta_2)
!!    = O_2 + r(\cos\theta_3, \sin\theta_3), $$
!! and the loop closure (m = 2 constraints, n = 3 coordinates)
!! $$ g = (r\cos\theta_1 + L\cos\theta_2 - r\cos\theta_3 - L,\;
!!         r\sin\theta_1 + L\sin\theta_2 - r\sin\theta_3) = 0, $$
!! G = [-r s1, -L s2, r s3; r c1, L c2, -r c3] (s_i = sin th_i, c_i = cos th_i). Unit point
!! masses at A and B, massless links, gravity g in -y.
!!
!! **Mass matrix.** With B written through the coupler (th1, th2), th3 carries no mass and M
!! is singular; through crank 2 (th3), th2 carries none. The kinetic energy of B is taken as
!! the mean of the two expressions, which agree on the constraint manifold (B' is the same
!! vector there), so the constrained motion is the physical one (Lagrange's equations with
!! multipliers depend on the kinetic and potential energies only through their values on
!! the manifold and its tangent space) while M is positive definite everywhere:
!! $$ T = \tfrac12 |A'|^2 + \tfrac14 |A' + L\theta_2'(-s_2, c_2)|^2 + \tfrac14 r^2\theta_3'^2, $$
!! $$ M = \begin{pmatrix} \tfrac32 r^2 & \tfrac12 rL\cos(\theta_1-\theta_2) & 0 \\
!!        \tfrac12 rL\cos(\theta_1-\theta_2) & \tfrac12 L^2 & 0 \\ 0 & 0 & \tfrac12 r^2 \end{pmatrix}, $$
!! det of the leading 2x2 block = r^2 L^2 (3 - cos^2(th1 - th2))/4 >= r^2 L^2/2 > 0. The potential
!! energy the same way, V = g (y_A + (r s1 + L s2)/2 + r s3/2) = g (3 r s1 + L s2 + r s3)/2.
!! Lagrange's equations M q'' = f + G^T lambda with (s12 = sin(th1 - th2))
!! $$ f = \left(-\tfrac12 rL\, s_{12}\, \theta_2'^2 - \tfrac32 g r c_1,\;
!!             \tfrac12 rL\, s_{12}\, \theta_1'^2 - \tfrac12 g L c_2,\; -\tfrac12 g r c_3\right) $$
!! (f_1, f_2 = -(M' q')_i + dT/dq_i - dV/dq_i; M depends on q only through cos(th1 - th2)).
!!
!! **The parallelogram branch** th2 = 0, th3 = th1 (w2 = 0, w3 = w1): both masses move on
!! circles of radius r, translated by (L, 0) from each other; T = r^2 th1'^2, V = 2 g r sin th1
!! and th1'' = -(g/r) cos th1. Check in the equations: with th2'' = 0 and th3'' = th1'' the sum
!! of rows 1 and 3 is 2 r^2 th1'' = -2 g r c1 + (-r s1 + r s1) lambda_1 + (r c1 - r c1) lambda_2
!! (the constraint forces cancel), the same equation. `fourbar_reduced` integrates it for the
!! reference. G loses rank where sin th1 = 0 on the branch, th1 = 0 or pi (all links
!! collinear: the folds), where the anti-parallelogram branch (the coupler crossing the
!! ground link) crosses it. The energy T + V is the problem's `invariant`.
!! The drivers use r = 1, L = 2 and g = 9.81.
module fourbar_problem
    use regdae, only: wp, mechanical_problem
    use reference_ode, only: ode_system
    implicit none
    private

    !> The four-bar linkage (n = 3 angles, m = 2 loop-closure equations).
    type, extends(mechanical_problem), public :: fourbar
        real(wp) :: crank = 1.0_wp     !! r, the length of both cranks
        real(wp) :: coupler = 2.0_wp   !! L, the coupler's length and the distance of the ground pivots
        real(wp) :: gravity = 9.81_wp  !! g, in -y
    contains
        procedure :: mass_matrix => fourbar_mass
        procedure :: forces => fourbar_forces
        procedure :: constraint => fourbar_g
        procedure :: constraint_jacobian => fourbar_gx
        procedure :: constraint_dt => fourbar_gt
        !> c = g_qq(v, v), analytic.
        procedure :: constraint_curvature => fourbar_curvature
        !> The energy T + V (as the invariant).
        procedure :: invariant => fourbar_invariant
    end type fourbar

    !> The motion on the parallelogram branch, state (th1, th1'): th1'' = -(g/r) cos th1.
    type, extends(ode_system), public :: fourbar_reduced
        real(wp) :: crank = 1.0_wp     !! r
        real(wp) :: gravity = 9.81_wp  !! g
    contains
        procedure :: rhs => reduced_rhs
    end type fourbar_reduced

    public :: new_fourbar, fourbar_branch_start

contains

    !> The linkage with crank length `crank` (r), coupler `coupler` (L) and gravity `gravity`.
    function new_fourbar(crank, coupler, gravity) result(p)
        real(wp), intent(in) :: crank, coupler, gravity
        type(fourbar) :: p
        p%n = 3
        p%m = 2
        p%crank = crank
        p%coupler = coupler
        p%gravity = gravity
    end function new_fourbar

    !> The consistent state on the parallelogram branch for crank angle `th1` and speed `w1`:
    !! q = (th1, 0, th1), v = (w1, 0, w1).
    pure subroutine fourbar_branch_start(th1, w1, q0, v0)
        real(wp), intent(in) :: th1, w1
        real(wp), intent(out) :: q0(3), v0(3)
        q0 = [th1, 0.0_wp, th1]
        v0 = [w1, 0.0_wp, w1]
    end subroutine fourbar_branch_start

    subroutine fourbar_mass(self, t, q, mass, stat)
        class(fourbar), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        real(wp) :: r, l
        r = self%crank
        l = self%coupler
        mass = 0.0_wp
        mass(1, 1) = 1.5_wp*r**2
        mass(1, 2) = 0.5_wp*r*l*cos(q(1) - q(2))
        mass(2, 1) = mass(1, 2)
        mass(2, 2) = 0.5_wp*l**2
        mass(3, 3) = 0.5_wp*r**2
    end subroutine fourbar_mass

    subroutine fourbar_forces(self, t, q, qd, f, stat)
        class(fourbar), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        real(wp) :: r, l, g, s12
        r = self%crank
        l = self%coupler
        g = self%gravity
        s12 = sin(q(1) - q(2))
        f(1) = -0.5_wp*r*l*s12*qd(2)**2 - 1.5_wp*g*r*cos(q(1))
        f(2) = 0.5_wp*r*l*s12*qd(1)**2 - 0.5_wp*g*l*cos(q(2))
        f(3) = -0.5_wp*g*r*cos(q(3))
    end subroutine fourbar_forces

    subroutine fourbar_g(self, t, x, val, stat)
        class(fourbar), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: r, l
        r = self%crank
        l = self%coupler
        val(1) = r*cos(x(1)) + l*cos(x(2)) - r*cos(x(3)) - l
        val(2) = r*sin(x(1)) + l*sin(x(2)) - r*sin(x(3))
    end subroutine fourbar_g

    subroutine fourbar_gx(self, t, x, a, stat)
        class(fourbar), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        real(wp) :: r, l
        r = self%crank
        l = self%coupler
        a(1, :) = [-r*sin(x(1)), -l*sin(x(2)), r*sin(x(3))]
        a(2, :) = [r*cos(x(1)), l*cos(x(2)), -r*cos(x(3))]
    end subroutine fourbar_gx

    subroutine fourbar_gt(self, t, x, val, stat)
        class(fourbar), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = 0.0_wp
    end subroutine fourbar_gt

    ! d^2 g / dt^2 at q'' = 0: the second derivatives of cos and sin along v.
    subroutine fourbar_curvature(self, t, x, v, val, stat)
        class(fourbar), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: r, l
        r = self%crank
        l = self%coupler
        val(1) = -r*cos(x(1))*v(1)**2 - l*cos(x(2))*v(2)**2 + r*cos(x(3))*v(3)**2
        val(2) = -r*sin(x(1))*v(1)**2 - l*sin(x(2))*v(2)**2 + r*sin(x(3))*v(3)**2
    end subroutine fourbar_curvature

    subroutine fourbar_invariant(self, t, x, v, val, stat)
        class(fourbar), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val
        integer, intent(inout) :: stat
        real(wp) :: mass(3, 3), r, l
        r = self%crank
        l = self%coupler
        call fourbar_mass(self, t, x, mass, stat)
        val = 0.5_wp*dot_product(v(1:3), matmul(mass, v(1:3))) + &
              0.5_wp*self%gravity*(3.0_wp*r*sin(x(1)) + l*sin(x(2)) + r*sin(x(3)))
    end subroutine fourbar_invariant

    subroutine reduced_rhs(self, t, y, ydot)
        class(fourbar_reduced), intent(inout) :: self
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: ydot(:)
        ydot(1) = y(2)
        ydot(2) = -(self%gravity/self%crank)*cos(y(1))
    end subroutine reduced_rhs

end module fourbar_problem
