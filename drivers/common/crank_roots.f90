!> The slider crank's event functions and their independently located roots:
!! th1 (through 0: the singular configurations), th1 - pi/4 (a regular
!! crossing) and th1' (the turning points th1 = +-pi/2, where th1 - pi/2 only
!! touches zero), as regdae event functions, and their times on the reduced
!! one-degree-of-freedom ODE (`slider_crank_reduced`, CVODE at 1e-12, Newton's
!! method on the event function along it from a grid of 600 points).
module crank_roots
    use regdae, only: wp, event_functions
    use slider_crank_problem, only: slider_crank_reduced
    use reference_ode, only: integrate_reference
    implicit none
    private

    public :: crank_reference_roots

    real(wp), parameter :: pi = acos(-1.0_wp)

    !> e = (th1, th1 - pi/4, th1') of the crank's state (th, w).
    type, extends(event_functions), public :: crank_events
    contains
        procedure :: values => crank_event_values
    end type crank_events

contains

    subroutine crank_event_values(self, t, x, v, e, stat)
        class(crank_events), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        e(1:3) = [x(1), x(1) - pi/4, v(1)]
    end subroutine crank_event_values

    !> The reduced ODE's roots over (0, t_end] from rest at th1_0: ref(1, k) the
    !! time, ref(2, k) the function (1, 2, 3 as `crank_events`), in time order
    !! per grid interval. A function zero at the start takes its sign from the motion
    !! (th1' < 0 first).
    subroutine crank_reference_roots(gravity, th1_0, t_end, ref, stat)
        real(wp), intent(in) :: gravity, th1_0, t_end
        real(wp), allocatable, intent(out) :: ref(:, :)
        integer, intent(out) :: stat
        type(slider_crank_reduced) :: sys
        integer, parameter :: ng = 600
        real(wp) :: times(ng), states(2, ng), y(2), ya(2), ta, tau, dt, slope, f(2), prev(3), now(3), one(2, 1)
        integer :: k, kind, it
        sys%gravity = gravity
        times = [(t_end*k/ng, k=1, ng)]
        allocate (ref(2, 0))
        call integrate_reference(sys, 0.0_wp, [th1_0, 0.0_wp], times, states, 1.0e-12_wp, 1.0e-12_wp, stat)
        if (stat /= 0) return
        prev = values3([th1_0, 0.0_wp])
        prev(3) = -1.0_wp
        do k = 1, ng
            now = values3(states(:, k))
            do kind = 1, 3
                if (sign(1.0_wp, now(kind)) == sign(1.0_wp, prev(kind))) cycle
                ta = 0.0_wp
                ya = [th1_0, 0.0_wp]
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
            v = [s(1), s(1) - pi/4, s(2)]
        end function values3
        pure real(wp) function val_of(s, kind)
            real(wp), intent(in) :: s(2)
            integer, intent(in) :: kind
            real(wp) :: v(3)
            v = values3(s)
            val_of = v(kind)
        end function val_of
    end subroutine crank_reference_roots

end module crank_roots
