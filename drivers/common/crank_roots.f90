!> Event functions of the drivers' one-degree-of-freedom mechanisms and their
!! independently located roots. On the reduced ODE th'' = F(th, th') the three
!! functions are th (through 0), th - c (a regular crossing) and th' (the
!! turning points); their times are found on the reduced ODE (CVODE at 1e-12,
!! Newton's method on the event function along it from a grid of 600 points),
!! not by regdae. The slider crank's functions (c = pi/4) are `crank_events`;
!! the pendulum's in Cartesian coordinates (x1 = sin th, v1 = th' cos th, so
!! the same three zeros while |th| < pi/2) are `pendulum_events`.
module crank_roots
    use regdae, only: wp, event_functions
    use slider_crank_problem, only: slider_crank_reduced
    use reference_ode, only: ode_system, integrate_reference
    implicit none
    private

    public :: crank_reference_roots, reduced_reference_roots, root_errors

    real(wp), parameter :: pi = acos(-1.0_wp)

    !> e = (th1, th1 - pi/4, th1') of the crank's state (th, w).
    type, extends(event_functions), public :: crank_events
    contains
        procedure :: values => crank_event_values
    end type crank_events

    !> e = (x1, x1 - sin(c), v1) of the pendulum's Cartesian state.
    type, extends(event_functions), public :: pendulum_events
        real(wp) :: c = 0.5_wp   !! the angle of the regular crossing
    contains
        procedure :: values => pendulum_event_values
    end type pendulum_events

contains

    subroutine crank_event_values(self, t, x, v, e, stat)
        class(crank_events), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        e(1:3) = [x(1), x(1) - pi/4, v(1)]
    end subroutine crank_event_values

    subroutine pendulum_event_values(self, t, x, v, e, stat)
        class(pendulum_events), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        e(1:3) = [x(1), x(1) - sin(self%c), v(1)]
    end subroutine pendulum_event_values

    !> The slider crank's reduced roots over (0, t_end] from rest at th1_0
    !! (`reduced_reference_roots` with c = pi/4).
    subroutine crank_reference_roots(gravity, th1_0, t_end, ref, stat)
        real(wp), intent(in) :: gravity, th1_0, t_end
        real(wp), allocatable, intent(out) :: ref(:, :)
        integer, intent(out) :: stat
        type(slider_crank_reduced) :: sys
        sys%gravity = gravity
        call reduced_reference_roots(sys, [th1_0, 0.0_wp], pi/4, t_end, ref, stat)
    end subroutine crank_reference_roots

    !> The roots of (th, th - c, th') along the reduced ODE `sys` from (th, th')
    !! = y0 at t = 0 over (0, t_end]: ref(1, k) the time, ref(2, k) the function
    !! (1, 2, 3), in time order per grid interval. A function zero at the start
    !! takes its sign from the motion (th'' for th' = 0 at rest).
    subroutine reduced_reference_roots(sys, y0, c, t_end, ref, stat)
        class(ode_system), intent(inout), target :: sys
        real(wp), intent(in) :: y0(2), c, t_end
        real(wp), allocatable, intent(out) :: ref(:, :)
        integer, intent(out) :: stat
        integer, parameter :: ng = 600
        real(wp) :: times(ng), states(2, ng), y(2), ya(2), ta, tau, dt, slope, f(2), prev(3), now(3), one(2, 1)
        integer :: k, kind, it
        times = [(t_end*k/ng, k=1, ng)]
        allocate (ref(2, 0))
        call integrate_reference(sys, 0.0_wp, y0, times, states, 1.0e-12_wp, 1.0e-12_wp, stat)
        if (stat /= 0) return
        prev = values3(y0)
        call sys%rhs(0.0_wp, y0, f)
        if (prev(1) == 0.0_wp) prev(1) = sign(1.0_wp, merge(f(1), f(2), f(1) /= 0.0_wp))
        if (prev(2) == 0.0_wp) prev(2) = sign(1.0_wp, merge(f(1), f(2), f(1) /= 0.0_wp))
        if (prev(3) == 0.0_wp) prev(3) = sign(1.0_wp, f(2))
        do k = 1, ng
            now = values3(states(:, k))
            do kind = 1, 3
                if (sign(1.0_wp, now(kind)) == sign(1.0_wp, prev(kind))) cycle
                ta = 0.0_wp
                ya = y0
                if (k > 1) then
                    ta = times(k - 1)
                    ya = states(:, k - 1)
                end if
                ! Newton on tau, each iterate integrated afresh from the grid point (forward)
                tau = 0.0_wp
                y = ya
                do it = 1, 30
                    call sys%rhs(ta + tau, y, f)
                    slope = merge(f(2), y(2), kind == 3)
                    dt = -val_of(y, kind)/slope
                    tau = max(0.0_wp, min(times(1), tau + dt))
                    if (abs(dt) < 1.0e-14_wp) exit
                    call integrate_reference(sys, ta, ya, [ta + tau], one, 1.0e-12_wp, 1.0e-12_wp, stat)
                    if (stat /= 0) return
                    y = one(:, 1)
                end do
                ref = reshape([ref, [ta + tau, real(kind, wp)]], [2, size(ref, 2) + 1])
            end do
            prev = now
        end do
    contains
        pure function values3(s) result(v)
            real(wp), intent(in) :: s(2)
            real(wp) :: v(3)
            v = [s(1), s(1) - c, s(2)]
        end function values3
        pure real(wp) function val_of(s, kind)
            real(wp), intent(in) :: s(2)
            integer, intent(in) :: kind
            real(wp) :: v(3)
            v = values3(s)
            val_of = v(kind)
        end function val_of
    end subroutine reduced_reference_roots

    !> The largest time error per function (1, 2, 3) of the roots in an event
    !! log (its lines 't = T: event K ...', regdae_solver%events()), each matched
    !! to the nearest reference root of its function in ref (as above).
    function root_errors(log, ref) result(worst)
        character(len=*), intent(in) :: log
        real(wp), intent(in) :: ref(:, :)
        real(wp) :: worst(3)
        real(wp) :: d, tl
        integer :: a, b, j, kind
        worst = 0.0_wp
        a = 1
        do while (a <= len(log))
            b = index(log(a:), new_line('a')) + a - 1
            if (b < a) b = len(log) + 1
            j = index(log(a:b - 1), ': event ')
            if (log(a:min(a + 3, len(log))) == 't = ' .and. j > 0) then
                read (log(a + 4:a + j - 2), *) tl
                read (log(a + j + 7:a + j + 7), *) kind
                d = huge(1.0_wp)
                do j = 1, size(ref, 2)
                    if (nint(ref(2, j)) == kind) d = min(d, abs(ref(1, j) - tl))
                end do
                worst(kind) = max(worst(kind), d)
            end if
            a = b + 1
        end do
    end function root_errors

end module crank_roots
