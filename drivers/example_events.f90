!> Events through the Fortran 2008 API: the pendulum x'' = (0, -g) - 2 x y on
!! |x| = 1 from rest at 1 rad; the event functions e1 = x1 (the bottom, stop
!! there) and e2 = v1 (the turning points, logged and continued). The program
!! checks each stop against the exact time (2k - 1) T/4 (T the period, from the
!! complete elliptic integral by the arithmetic-geometric mean).
module example_events_problem
    use regdae, only: wp, second_order_problem, event_functions
    implicit none
    private

    !> The pendulum, unit mass and length.
    type, extends(second_order_problem), public :: pendulum
        real(wp) :: gravity = 9.81_wp
    contains
        procedure :: rhs => pendulum_f
        procedure :: matrix_b => pendulum_b
        procedure :: constraint => pendulum_g
        procedure :: constraint_jacobian => pendulum_gx
    end type pendulum

    !> e1 = x1, e2 = v1.
    type, extends(event_functions), public :: pendulum_events
    contains
        procedure :: values => event_values
    end type pendulum_events

contains

    subroutine pendulum_f(self, t, x, v, val, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = [0.0_wp, -self%gravity]
    end subroutine pendulum_f

    subroutine pendulum_b(self, t, x, v, a, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(:, 1) = 2.0_wp*x
    end subroutine pendulum_b

    subroutine pendulum_g(self, t, x, val, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = x(1)**2 + x(2)**2 - 1.0_wp
    end subroutine pendulum_g

    subroutine pendulum_gx(self, t, x, a, stat)
        class(pendulum), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, :) = 2.0_wp*x
    end subroutine pendulum_gx

    subroutine event_values(self, t, x, v, e, stat)
        class(pendulum_events), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)   ! v: the velocity (empty for a first-order problem)
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        e(1) = x(1)
        e(2) = v(1)
    end subroutine event_values

end module example_events_problem

program example_events
    use regdae
    use example_events_problem, only: pendulum, pendulum_events
    implicit none
    real(wp), parameter :: phi0 = 1.0_wp
    type(regdae_solver) :: solver
    type(solver_options) :: opts
    type(solver_stats) :: st
    type(pendulum) :: problem
    type(pendulum_events) :: events
    real(wp) :: x(2), v(2), period, a, b, c, err
    integer :: stat, k, i

    problem%n = 2
    problem%m = 1
    opts%rtol = 1.0e-8_wp
    opts%atol = 1.0e-8_wp
    call solver%init(problem, 0.0_wp, [sin(phi0), -cos(phi0)], [0.0_wp, 0.0_wp], opts, stat)
    if (stat /= regdae_success) error stop 'init failed'
    ! e1 stops at its roots, e2 is logged and the integration goes on; both directions
    call solver%set_events(events, 2, stat, direction=[0, 0], stop=[.true., .false.])
    ! the exact period: 4 K(sin(phi0/2)) / sqrt(g)
    a = 1.0_wp
    b = cos(phi0/2)
    do i = 1, 30
        c = 0.5_wp*(a + b)
        b = sqrt(a*b)
        a = c
    end do
    period = 2.0_wp*acos(-1.0_wp)/a/sqrt(problem%gravity)
    k = 0
    err = 0.0_wp
    do
        call solver%advance(1.2_wp*period, x, stat=stat, v=v)
        if (stat /= regdae_root_found) exit
        k = k + 1
        st = solver%statistics()
        write (*, '(a, i0, a, es23.15, a, 2i3)') 'stop ', k, ' at t =', st%t, ', roots', solver%roots()
        err = max(err, abs(st%t - (2*k - 1)*period/4))
    end do
    if (stat < 0) error stop 'advance failed'
    st = solver%statistics()
    write (*, '(a, i0, a, es9.2)') 'roots found: ', st%roots_found, ', largest stop-time error', err
    write (*, '(a)', advance='no') solver%events()
    ! rtol 1e-8: 10 rtol = 1e-7 (measured about 1e-9)
    if (k /= 2 .or. st%roots_found /= 4 .or. err > 1.0e-7_wp) error stop 'wrong event times'
end program example_events
