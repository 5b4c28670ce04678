!> A mechanical system with a massless coordinate (singular mass matrix,
!! paper section 4.3): a unit point mass (px, py) on a unit rod whose pivot
!! sits on a massless carrier at (s, 0),
!! $$ M = \mathrm{diag}(1, 1, 0), \quad f = (0, -g, 0), \quad
!!    g_1 = (p_x - s)^2 + p_y^2 - 1, \quad g_2 = s - c(q), $$
!! with the carrier either held at the origin (`follower = .false.`: c = 0, the
!! hand-eliminated model is the pendulum with a fixed pivot) or made to follow the
!! mass horizontally (`follower = .true.`: c = px/2, a massless coordinate that
!! must accelerate).
module massless_problem
    use regdae, only: wp, mechanical_problem
    implicit none
    private

    !> The pendulum on a massless carrier (n = 3, m = 2).
    type, extends(mechanical_problem), public :: massless_carrier
        real(wp) :: gravity = 9.81_wp
        logical :: follower = .false.   !! carrier at px/2 instead of at the origin
    contains
        procedure :: mass_matrix => mc_mass
        procedure :: forces => mc_forces
        procedure :: constraint => mc_g
        procedure :: constraint_jacobian => mc_gx
        procedure :: constraint_dt => mc_gt
    end type massless_carrier

    public :: new_massless_carrier

contains

    function new_massless_carrier(gravity, follower) result(p)
        real(wp), intent(in) :: gravity
        logical, intent(in) :: follower
        type(massless_carrier) :: p
        p%n = 3
        p%m = 2
        p%gravity = gravity
        p%follower = follower
    end function new_massless_carrier

    subroutine mc_mass(self, t, q, mass, stat)
        class(massless_carrier), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        mass = 0.0_wp
        mass(1, 1) = 1.0_wp
        mass(2, 2) = 1.0_wp
    end subroutine mc_mass

    subroutine mc_forces(self, t, q, qd, f, stat)
        class(massless_carrier), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        f = [0.0_wp, -self%gravity, 0.0_wp]
    end subroutine mc_forces

    subroutine mc_g(self, t, x, val, stat)
        class(massless_carrier), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val(1) = (x(1) - x(3))**2 + x(2)**2 - 1.0_wp
        val(2) = x(3)
        if (self%follower) val(2) = x(3) - 0.5_wp*x(1)
    end subroutine mc_g

    subroutine mc_gx(self, t, x, a, stat)
        class(massless_carrier), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        a(1, :) = [2.0_wp*(x(1) - x(3)), 2.0_wp*x(2), -2.0_wp*(x(1) - x(3))]
        a(2, :) = [0.0_wp, 0.0_wp, 1.0_wp]
        if (self%follower) a(2, 1) = -0.5_wp
    end subroutine mc_gx

    subroutine mc_gt(self, t, x, val, stat)
        class(massless_carrier), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = 0.0_wp
    end subroutine mc_gt

end module massless_problem
