!> The car axis of the Test Set for IVP Solvers (Mazzia, Magherini et al., "car axis
!! problem"), an index-3 mechanism: a light axis of length L whose left wheel (x_l, y_l)
!! hangs on a spring of rest length L0 from the origin and whose right wheel (x_r, y_r)
!! hangs on an equal spring from a point (x_b, y_b) that rides over a bump of the road,
!! y_b = r sin(w t), x_b = sqrt(L^2 - y_b^2). With k = M eps^2 / 2 (the wheels' mass),
!! L_l = |(x_l, y_l)|, L_r = |(x_r - x_b, y_r - y_b)|, p = (x_l, y_l, x_r, y_r):
!! $$ k\, p'' = \Big(\tfrac{(L_0 - L_l)}{L_l} (x_l, y_l),
!!              \tfrac{(L_0 - L_r)}{L_r} (x_r - x_b, y_r - y_b)\Big) - k g\,(0, 1, 0, 1)
!!              + G(p, t)^T \lambda, $$
!! $$ 0 = g(p, t) = \big(x_b x_l + y_b y_l,\ (x_l - x_r)^2 + (y_l - y_r)^2 - L^2\big), $$
!! eps = 1e-2 (the springs are stiff: frequencies ~ 1/eps), M = 10, L = 1, L0 = 1/2,
!! r = 0.1, w = 10, g = 1 on [0, 3]. In regdae's form x'' = f - B y: x = p, f = the
!! springs' force / k - g, B = G^T / k and y = -lambda (G B = G G^T / k is then
!! positive definite). Start: p = (0, 1/2, 1, 1/2), p' = (-1/2, 0, -1/2, 0).
!! The equations are written here from the test set's description; the reference at
!! t = 3 is the test set's published solution (`car_axis_reference`).
module car_axis_problem
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp, second_order_problem
    implicit none
    private

    !> The car axis (n = 4, m = 2) with the test set's parameters as defaults.
    type, extends(second_order_problem), public :: car_axis
        real(wp) :: eps = 1.0e-2_wp     !! the stiffness parameter (spring frequency ~ 1/eps)
        real(wp) :: mass = 10.0_wp      !! M
        real(wp) :: length = 1.0_wp     !! L, the axis
        real(wp) :: rest = 0.5_wp       !! L0, the springs' rest length
        real(wp) :: bump = 0.1_wp       !! r, the bump's height
        real(wp) :: omega = 10.0_wp     !! w, the bump's frequency
        real(wp) :: gravity = 1.0_wp    !! g
        ! the road at the last time asked for (each evaluation of the regularized system asks
        ! five callbacks at the same t, a Radau step's stages and Jacobian a few times more)
        logical, private :: road_known = .false.
        integer(int64), private :: road_key(4) = 0   ! the bits of t, bump, omega, length of the stored road
        real(wp), private :: road_at(6) = 0       ! b, db, ddb there
    contains
        procedure :: rhs => car_axis_f
        procedure :: matrix_b => car_axis_b
        procedure :: matrix_b_from_jacobian => car_axis_b_from_gx
        procedure :: constraint => car_axis_g
        procedure :: constraint_jacobian => car_axis_gx
        procedure :: constraint_dt => car_axis_gt
        procedure :: constraint_curvature => car_axis_curvature
    end type car_axis

    !> The published reference solution at t = 3 (Test Set for IVP Solvers, car axis):
    !! positions, velocities (x_l', y_l', x_r', y_r') and the multipliers lambda.
    real(wp), parameter, public :: car_axis_reference(10) = [ &
                                   0.493455784275402809122e-1_wp, 0.496989460230171153861_wp, &
                                   0.104174252488542151681e1_wp, 0.373911027265361256927_wp, &
                                   -0.770583684040972357970e-1_wp, 0.744686658723778553466e-2_wp, &
                                   0.175568157537232222276e-1_wp, 0.770341043779251976443_wp, &
                                   -0.473688659084893324729e-2_wp, -0.110468033125734368808e-2_wp]
    !> The end of the test set's interval.
    real(wp), parameter, public :: car_axis_t_end = 3.0_wp
    !> The start: positions and velocities (consistent with g and its derivative).
    real(wp), parameter, public :: car_axis_x0(4) = [0.0_wp, 0.5_wp, 1.0_wp, 0.5_wp]
    real(wp), parameter, public :: car_axis_v0(4) = [-0.5_wp, 0.0_wp, -0.5_wp, 0.0_wp]

    public :: new_car_axis

contains

    !> The car axis with the test set's parameters.
    function new_car_axis() result(p)
        type(car_axis) :: p
        p%n = 4
        p%m = 2
    end function new_car_axis

    !> The road point (x_b, y_b) and its first two time derivatives, kept for the last
    !! time asked for (the same numbers as computing them again).
    subroutine road(self, t, b, db, ddb)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: b(2), db(2), ddb(2)
        if (self%road_known) then
            if (all(self%road_key == transfer([t, self%bump, self%omega, self%length], 1_int64, 4))) then
                b = self%road_at(1:2)
                db = self%road_at(3:4)
                ddb = self%road_at(5:6)
                return
            end if
        end if
        call road_from_scratch(self, t, b, db, ddb)
        self%road_key = transfer([t, self%bump, self%omega, self%length], 1_int64, 4)
        self%road_at = [b, db, ddb]
        self%road_known = .true.
    end subroutine road

    pure subroutine road_from_scratch(self, t, b, db, ddb)
        class(car_axis), intent(in) :: self
        real(wp), intent(in) :: t
        real(wp), intent(out) :: b(2), db(2), ddb(2)
        b(2) = self%bump*sin(self%omega*t)
        db(2) = self%bump*self%omega*cos(self%omega*t)
        ddb(2) = -self%omega**2*b(2)
        b(1) = sqrt(self%length**2 - b(2)**2)
        db(1) = -b(2)*db(2)/b(1)
        ddb(1) = -(db(2)**2 + b(2)*ddb(2) + db(1)**2)/b(1)
    end subroutine road_from_scratch

    !> The wheels' mass k = M eps^2 / 2.
    pure real(wp) function wheel_mass(self)
        class(car_axis), intent(in) :: self
        wheel_mass = 0.5_wp*self%mass*self%eps**2
    end function wheel_mass

    subroutine car_axis_f(self, t, x, v, val, stat)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: b(2), db(2), ddb(2), dl(2), dr(2), ll, lr, k
        call road(self, t, b, db, ddb)
        dl = x(1:2)
        dr = x(3:4) - b
        ll = norm2(dl)
        lr = norm2(dr)
        if (ll == 0.0_wp .or. lr == 0.0_wp) then   ! a spring of zero length: no direction
            stat = 1
            return
        end if
        k = wheel_mass(self)
        val(1:2) = (self%rest - ll)/ll*dl/k
        val(3:4) = (self%rest - lr)/lr*dr/k
        val(2) = val(2) - self%gravity
        val(4) = val(4) - self%gravity
    end subroutine car_axis_f

    subroutine car_axis_b(self, t, x, v, a, stat)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        real(wp) :: gx(2, 4)
        call car_axis_gx(self, t, x, gx, stat)
        a = transpose(gx)/wheel_mass(self)
    end subroutine car_axis_b

    subroutine car_axis_b_from_gx(self, t, x, v, gx, a, stat)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(in) :: gx(:, :)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a = transpose(gx)/wheel_mass(self)
    end subroutine car_axis_b_from_gx

    subroutine car_axis_g(self, t, x, val, stat)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: b(2), db(2), ddb(2)
        call road(self, t, b, db, ddb)
        val(1) = b(1)*x(1) + b(2)*x(2)
        val(2) = (x(1) - x(3))**2 + (x(2) - x(4))**2 - self%length**2
    end subroutine car_axis_g

    subroutine car_axis_gx(self, t, x, a, stat)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        real(wp) :: b(2), db(2), ddb(2), d(2)
        call road(self, t, b, db, ddb)
        d = 2.0_wp*(x(1:2) - x(3:4))
        a(1, :) = [b(1), b(2), 0.0_wp, 0.0_wp]
        a(2, :) = [d(1), d(2), -d(1), -d(2)]
    end subroutine car_axis_gx

    !> g_t: only the first constraint moves with the road.
    subroutine car_axis_gt(self, t, x, val, stat)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: b(2), db(2), ddb(2)
        call road(self, t, b, db, ddb)
        val(1) = db(1)*x(1) + db(2)*x(2)
        val(2) = 0.0_wp
    end subroutine car_axis_gt

    !> c = g_xx(v, v) + 2 g_xt v + g_tt, exact.
    subroutine car_axis_curvature(self, t, x, v, val, stat)
        class(car_axis), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: b(2), db(2), ddb(2)
        call road(self, t, b, db, ddb)
        val(1) = 2.0_wp*(db(1)*v(1) + db(2)*v(2)) + ddb(1)*x(1) + ddb(2)*x(2)
        val(2) = 2.0_wp*((v(1) - v(3))**2 + (v(2) - v(4))**2)
    end subroutine car_axis_curvature

end module car_axis_problem
