!> Example 5.2 of Petzold, Ren & Maly (1997): the slider crank (Haug), a planar
!! double pendulum with unit point masses at the two joints, unit massless links,
!! gravity g downwards, angles from the downward vertical, whose end slides on
!! the horizontal line through the pivot. Equations (5.2)-(5.3):
!! $$ M(\theta)\theta'' + h(\theta, \theta') + G^T \lambda = 0, \qquad
!!    g_3 = -\cos\theta_1 - \cos\theta_2 = 0, $$
!! M = [2, cos th_d; cos th_d, 1], th_d = th2 - th1,
!! h = (-sin th_d th2'^2 + 2 g sin th1, sin th_d th1'^2 + g sin th2), G = (sin th1, sin th2).
!! As a `mechanical_problem` (M q'' = f + G^T lambda_m): f = -h and lambda_m = -lambda.
!!
!! At (th1, th2) = (0, pi) G vanishes. On the physical branch th2 = pi - th1
!! the motion has one degree of freedom with energy
!! E = 0.5 th1'^2 (1 + 4 cos^2 th1) - g cos th1, and (Euler-Lagrange)
!! $$ \theta_1'' = \sin\theta_1 \,(4 \cos\theta_1\, \theta_1'^2 - g) / (1 + 4\cos^2\theta_1), $$
!! the reduced ODE `slider_crank_reduced` integrates for the reference.
module slider_crank_problem
    use regdae, only: wp, mechanical_problem, curvature_difference
    use reference_ode, only: ode_system
    implicit none
    private

    !> The slider crank (n = 2 angles, m = 1 constraint).
    type, extends(mechanical_problem), public :: slider_crank
        real(wp) :: gravity = 9.8_wp   !! gravitational acceleration
        logical :: analytic_curvature = .false.   !! c = g_xx(v, v) analytic instead of regdae's difference quotient
        ! sin and cos of th1, th2 and th2 - th1 at q_trig: the callbacks at one
        ! evaluation point share them (regdae calls them all at the same q)
        real(wp), private :: q_trig(2) = huge(1.0_wp), s1 = 0, c1 = 0, s2 = 0, c2 = 0, sd = 0, cd = 0
    contains
        procedure :: mass_matrix => crank_mass
        procedure :: forces => crank_forces
        procedure :: constraint => crank_g
        procedure :: constraint_jacobian => crank_gx
        procedure :: constraint_dt => crank_gt
        !> c = g_xx(v, v) = cos th1 th1'^2 + cos th2 th2'^2: analytic if `analytic_curvature`
        !! (the benchmark), else the library's default difference quotient (the drivers).
        procedure :: constraint_curvature => crank_curvature
        !> Total energy T + V of a state (th, w).
        procedure :: energy => crank_energy
        !> The energy as regdae's invariant (checked with invariant_tol > 0).
        procedure :: invariant => crank_invariant
    end type slider_crank

    !> The slider crank with its constraint given twice (m = 2): GB has rank 1 for
    !! all t, the multiplier is not unique (only lambda1 + lambda2 is), x is.
    type, extends(slider_crank), public :: redundant_slider_crank
    contains
        procedure :: constraint => redundant_g
        procedure :: constraint_jacobian => redundant_gx
        procedure :: constraint_dt => redundant_gt
    end type redundant_slider_crank

    !> The reduced ODE on the physical branch, state (th1, th1').
    type, extends(ode_system), public :: slider_crank_reduced
        real(wp) :: gravity = 9.8_wp
    contains
        procedure :: rhs => reduced_rhs
    end type slider_crank_reduced

    public :: new_slider_crank, new_redundant_slider_crank

contains

    function new_slider_crank(gravity) result(p)
        real(wp), intent(in) :: gravity
        type(slider_crank) :: p
        p%n = 2
        p%m = 1
        p%gravity = gravity
    end function new_slider_crank

    function new_redundant_slider_crank(gravity) result(p)
        real(wp), intent(in) :: gravity
        type(redundant_slider_crank) :: p
        p%n = 2
        p%m = 2
        p%gravity = gravity
    end function new_redundant_slider_crank

    subroutine redundant_g(self, t, x, val, stat)
        class(redundant_slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = -cos(x(1)) - cos(x(2))
    end subroutine redundant_g

    subroutine redundant_gx(self, t, x, a, stat)
        class(redundant_slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, :) = [sin(x(1)), sin(x(2))]
        a(2, :) = a(1, :)
    end subroutine redundant_gx

    subroutine redundant_gt(self, t, x, val, stat)
        class(redundant_slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = 0.0_wp
    end subroutine redundant_gt

    ! The trigonometric values at q (recomputed only when q changes).
    subroutine update_trig(self, q)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: q(:)
        if (q(1) == self%q_trig(1) .and. q(2) == self%q_trig(2)) return
        self%q_trig = q(1:2)
        self%s1 = sin(q(1))
        self%c1 = cos(q(1))
        self%s2 = sin(q(2))
        self%c2 = cos(q(2))
        self%sd = self%s2*self%c1 - self%c2*self%s1   ! sin(th2 - th1)
        self%cd = self%c2*self%c1 + self%s2*self%s1   ! cos(th2 - th1)
    end subroutine update_trig

    subroutine crank_mass(self, t, q, mass, stat)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        call update_trig(self, q)
        mass(1, 1) = 2.0_wp
        mass(2, 1) = self%cd
        mass(1, 2) = self%cd
        mass(2, 2) = 1.0_wp
    end subroutine crank_mass

    subroutine crank_forces(self, t, q, qd, f, stat)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        call update_trig(self, q)
        f(1) = self%sd*qd(2)**2 - 2.0_wp*self%gravity*self%s1
        f(2) = -self%sd*qd(1)**2 - self%gravity*self%s2
    end subroutine crank_forces

    subroutine crank_g(self, t, x, val, stat)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call update_trig(self, x)
        val(1) = -self%c1 - self%c2
    end subroutine crank_g

    subroutine crank_gx(self, t, x, a, stat)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call update_trig(self, x)
        a(1, 1) = self%s1
        a(1, 2) = self%s2
    end subroutine crank_gx

    subroutine crank_gt(self, t, x, val, stat)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = 0.0_wp
    end subroutine crank_gt

    subroutine crank_curvature(self, t, x, v, val, stat)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        if (self%analytic_curvature) then
            call update_trig(self, x)
            val(1) = self%c1*v(1)**2 + self%c2*v(2)**2
        else
            call curvature_difference(self, t, x, v, val, stat)
        end if
    end subroutine crank_curvature

    subroutine crank_invariant(self, t, x, v, val, stat)
        class(slider_crank), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val
        integer, intent(inout) :: stat
        val = self%energy(x(1:2), v(1:2))
    end subroutine crank_invariant

    pure real(wp) function crank_energy(self, th, w) result(e)
        class(slider_crank), intent(in) :: self
        real(wp), intent(in) :: th(2), w(2)
        e = 0.5_wp*(2.0_wp*w(1)**2 + w(2)**2 + 2.0_wp*cos(th(2) - th(1))*w(1)*w(2)) &
            - 2.0_wp*self%gravity*cos(th(1)) - self%gravity*cos(th(2))
    end function crank_energy

    subroutine reduced_rhs(self, t, y, ydot)
        class(slider_crank_reduced), intent(inout) :: self
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: ydot(:)
        ydot(1) = y(2)
        ydot(2) = sin(y(1))*(4.0_wp*cos(y(1))*y(2)**2 - self%gravity)/(1.0_wp + 4.0_wp*cos(y(1))**2)
    end subroutine reduced_rhs

end module slider_crank_problem
