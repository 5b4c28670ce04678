!> The car axis (drivers/problems/car_axis_problem.f90) as the test set's index-3 DAE in the
!! mass-matrix form RADAU5 runs, M u' = F(t, u) with u = (p, p', lambda), M = diag(1 x 4, k x 4, 0 x 2), k = M eps^2 / 2,
!! under regdae's own Radau IIA (regdae_radau_iia), not through the regularized system.
!! The equations are those of drivers/problems/car_axis_problem.f90 (the test set's
!! description) written with the multipliers as unknowns:
!! k p'' = the springs' force - k g (0, 1, 0, 1) + G(p, t)^T lambda, 0 = g(p, t).
module car_axis_index3_problem
    use regdae_kinds, only: wp
    use regdae_radau_system, only: radau_system, radau_options
    use car_axis_problem, only: car_axis, car_axis_x0, car_axis_v0
    implicit none
    private
    public :: car_axis_index3_setup

    !> The car axis's index-3 system for the Radau integrator (the test set's parameters).
    type, extends(radau_system), public :: car_axis_index3
        type(car_axis) :: axis  !! the parameters (the test set's by default)
    contains
        procedure :: rhs => index3_rhs
        procedure :: wheel_mass => index3_wheel_mass
    end type car_axis_index3

contains

    !> The start u0 = (p0, p0', 0) and the options of a run at rtol = atol = TOL as RADAU5 runs
    !! an index-3 problem: M's diagonal, the velocities' error scaled by h and the multipliers'
    !! by h^2 (dae_index 2, 3), first step 1e-6, and with RADAU5_TOLERANCES its tolerance
    !! transform (local tolerance 0.1 tol^(2/3)).
    subroutine car_axis_index3_setup(sys, tol, radau5_tolerances, u0, opts)
        type(car_axis_index3), intent(in) :: sys
        real(wp), intent(in) :: tol                 !! rtol = atol
        logical, intent(in) :: radau5_tolerances    !! RADAU5's tolerance transform
        real(wp), intent(out) :: u0(10)             !! the consistent start (lambda = 0 there)
        type(radau_options), intent(out) :: opts
        u0 = [car_axis_x0, car_axis_v0, 0.0_wp, 0.0_wp]
        opts%rtol = tol
        opts%atol = tol
        opts%h0 = 1.0e-6_wp
        opts%mass = [1, 1, 1, 1, 0, 0, 0, 0, 0, 0]*1.0_wp
        opts%mass(5:8) = sys%wheel_mass()
        opts%dae_index = [1, 1, 1, 1, 2, 2, 2, 2, 3, 3]
        opts%radau5_tolerances = radau5_tolerances
    end subroutine car_axis_index3_setup

    !> k = M eps^2 / 2, the wheels' mass (the diagonal of M on the velocity rows).
    pure real(wp) function index3_wheel_mass(self) result(k)
        class(car_axis_index3), intent(in) :: self
        k = self%axis%mass*self%axis%eps**2/2
    end function index3_wheel_mass

    !> F(t, u): the velocities, the forces with G^T lambda, and the position constraints.
    subroutine index3_rhs(self, t, u, f, stat, recoverable)
        class(car_axis_index3), intent(inout) :: self
        real(wp), intent(in) :: t           !! time
        real(wp), intent(in) :: u(:)        !! (x_l, y_l, x_r, y_r, their velocities, lambda_1, lambda_2)
        real(wp), intent(out) :: f(:)       !! F(t, u), size 10
        integer, intent(out) :: stat        !! 0
        logical, intent(out) :: recoverable !! .false.
        real(wp) :: k, xb, yb, ll, lr, dx, dy
        k = self%wheel_mass()
        yb = self%axis%bump*sin(self%axis%omega*t)
        xb = sqrt(self%axis%length**2 - yb**2)
        ll = sqrt(u(1)**2 + u(2)**2)
        lr = sqrt((u(3) - xb)**2 + (u(4) - yb)**2)
        dx = u(1) - u(3)
        dy = u(2) - u(4)
        f(1:4) = u(5:8)
        f(5) = (self%axis%rest - ll)*u(1)/ll + u(9)*xb + 2*u(10)*dx
        f(6) = (self%axis%rest - ll)*u(2)/ll + u(9)*yb + 2*u(10)*dy - k*self%axis%gravity
        f(7) = (self%axis%rest - lr)*(u(3) - xb)/lr - 2*u(10)*dx
        f(8) = (self%axis%rest - lr)*(u(4) - yb)/lr - 2*u(10)*dy - k*self%axis%gravity
        f(9) = xb*u(1) + yb*u(2)
        f(10) = dx**2 + dy**2 - self%axis%length**2
        stat = 0
        recoverable = .false.
    end subroutine index3_rhs

end module car_axis_index3_problem
