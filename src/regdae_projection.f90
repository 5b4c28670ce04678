!> Projection of a state onto the constraint manifold: the nearest (minimum-norm
!! correction) x with g(x, t) = 0 by Gauss-Newton steps x <- x - G^+ g, and for a
!! second-order problem the velocity with G v + g_t = 0 by v <- v - G^+ (G v + g_t)
!! (G^+ by LAPACK's dgelsd, so that a rank-deficient G is handled). The pass check
!! starts its companions from a checkpoint of the solution, whose drift is within
!! the solution's tolerance but far outside the companions' (regdae_solver_trust).
module regdae_projection
    use regdae_kinds, only: wp
    use regdae_problem, only: dae_problem
    use regdae_second_order_problem, only: second_order_problem
    use regdae_damped_lsq, only: damped_lsq_workspace, damped_lsq_solve, lsq_stacked
    use regdae_status, only: regdae_err_memory
    implicit none
    private

    public :: project_first_order, project_second_order

    !> Gauss-Newton steps at most.
    integer, parameter :: max_steps = 4

contains

    !> x onto g(x, t) = 0 of a first-order problem (stat: a user routine's, or a
    !! LAPACK failure).
    subroutine project_first_order(problem, t, x, stat)
        class(dae_problem), intent(inout) :: problem
        real(wp), intent(in) :: t
        real(wp), intent(inout) :: x(:)
        integer, intent(out) :: stat
        real(wp) :: g(problem%m)
        real(wp), allocatable :: gx(:, :)
        type(damped_lsq_workspace) :: ws
        integer :: it
        stat = 0
        if (problem%m == 0) return
        call workspace_for(problem%m, problem%n, gx, ws, stat)
        if (stat /= 0) return
        do it = 1, max_steps
            call problem%constraint(t, x, g, stat)
            if (stat == 0) call problem%constraint_jacobian(t, x, gx, stat)
            if (stat /= 0) return
            if (newton_step(ws, gx, g, x, stat)) exit
        end do
    end subroutine project_first_order

    !> (x, v) onto g = 0 and G v + g_t = 0 of a second-order problem.
    subroutine project_second_order(problem, t, x, v, stat)
        class(second_order_problem), intent(inout) :: problem
        real(wp), intent(in) :: t
        real(wp), intent(inout) :: x(:), v(:)
        integer, intent(out) :: stat
        real(wp) :: g(problem%m), gt(problem%m), dx(problem%n)
        real(wp), allocatable :: gx(:, :)
        type(damped_lsq_workspace) :: ws
        integer :: it
        stat = 0
        if (problem%m == 0) return
        call workspace_for(problem%m, problem%n, gx, ws, stat)
        if (stat /= 0) return
        do it = 1, max_steps
            call problem%constraint(t, x, g, stat)
            if (stat == 0) call problem%constraint_jacobian(t, x, gx, stat)
            if (stat /= 0) return
            if (newton_step(ws, gx, g, x, stat)) exit
        end do
        if (stat /= 0) return
        call problem%constraint_jacobian(t, x, gx, stat)
        if (stat == 0) call problem%constraint_dt(t, x, gt, stat)
        if (stat /= 0) return
        g = matmul(gx, v) + gt
        call damped_lsq_solve(ws, gx, g, 0.0_wp, lsq_stacked, dx, stat)
        if (stat /= 0) return
        v = v - dx
    end subroutine project_second_order

    ! G's array and the least-squares workspace (stat: regdae_err_memory if refused).
    subroutine workspace_for(m, n, gx, ws, stat)
        integer, intent(in) :: m, n
        real(wp), allocatable, intent(out) :: gx(:, :)
        type(damped_lsq_workspace), intent(inout) :: ws
        integer, intent(out) :: stat
        allocate (gx(m, n), stat=stat)
        if (stat == 0) call ws%init(m, n, stat)
        if (stat /= 0) stat = regdae_err_memory
    end subroutine workspace_for

    ! One minimum-norm Gauss-Newton step x <- x - dx, G dx = g (stacked least squares): true when
    ! the step is at rounding level (converged) or the solve failed (stat /= 0).
    logical function newton_step(ws, gx, g, x, stat) result(done)
        type(damped_lsq_workspace), intent(inout) :: ws
        real(wp), intent(in) :: gx(:, :), g(:)
        real(wp), intent(inout) :: x(:)
        integer, intent(out) :: stat
        real(wp) :: dx(size(x))
        call damped_lsq_solve(ws, gx, g, 0.0_wp, lsq_stacked, dx, stat)
        done = (stat /= 0)
        if (done) return
        x = x - dx
        done = maxval(abs(dx)) <= 4.0_wp*epsilon(1.0_wp)*max(1.0_wp, maxval(abs(x)))
    end function newton_step

end module regdae_projection
