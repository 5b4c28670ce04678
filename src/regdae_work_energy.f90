!> The work-energy balance of a constrained mechanical system, the check that
!! needs nothing from the user.
!!
!! For M(q) v' = f(q, v, t) + G^T lambda the kinetic energy T = v^T M v / 2 obeys
!! $$ \frac{dT}{dt} = v^T f + \tfrac12 v^T \dot M v + \lambda^T G v $$
!! exactly, whatever f is. Ideal constraints do no work on the constraint
!! manifold but that of moving constraints: G v = -g_t there, so
!! $$ P = v^T f + \tfrac12 v^T \dot M v - \lambda^T g_t $$
!! is the power of the applied forces (and of the moving constraints), and
!! T(t) - T(t0) - \int P dt stays at the integration error on a correct run. A
!! run that gains energy through the constraint forces (a drift, a branch change,
!! a too stiff regularization) breaks the balance. dM/dt along the motion is a
!! central difference of M along v.
module regdae_work_energy
    use regdae_kinds, only: wp
    use regdae_differences, only: central_difference_step
    use regdae_sparsity, only: sparsity_pattern, sparse_times
    use regdae_mechanical_problem, only: mechanical_problem
    implicit none
    private

    public :: kinetic_energy_and_power

contains

    !> T = v^T M v / 2 and P = v^T f + v^T (dM/dt) v / 2 + y^T g_t at (t, q, v)
    !! with the multiplier y = -lambda. With `pattern`, M comes in pattern order
    !! from `mass_values` (O(nnz)); else dense from `mass_matrix`. stat: the user
    !! routines' (0 on success).
    subroutine kinetic_energy_and_power(problem, t, q, v, y, kinetic, power, stat, pattern, sums)
        class(mechanical_problem), intent(inout) :: problem
        real(wp), intent(in) :: t, q(:), v(:), y(:)
        real(wp), intent(out) :: kinetic, power
        integer, intent(out) :: stat
        type(sparsity_pattern), intent(in), optional :: pattern
        real(wp), intent(out), optional :: sums(2)   !! sum_i |(M v)_i| and sum_i |f_i|: the energy an error
                                                     !! dv, dq moves by at most sums(1) max|dv| + sums(2) max|dq|
        real(wp) :: f(size(q)), gt(problem%m), mv(size(q)), mdot_v(size(q)), d, vmax
        real(wp), allocatable :: dense(:, :), vals(:)   ! M at a point (one allocation for the three)
        stat = 0
        if (present(pattern)) then
            allocate (vals(pattern%nnz()))
        else
            allocate (dense(size(q), size(q)))
        end if
        kinetic = 0.0_wp
        power = 0.0_wp
        call mass_times(q, t, v, mv)
        if (stat /= 0) return
        kinetic = 0.5_wp*dot_product(v, mv)
        vmax = maxval(abs(v))
        mdot_v = 0.0_wp
        if (vmax > 0.0_wp) then   ! (M(q + d v) - M(q - d v)) v / (2 d)
            d = central_difference_step(max(maxval(abs(q)), abs(t)))/max(1.0_wp, vmax)
            call mass_times(q + d*v, t, v, mdot_v)
            if (stat /= 0) return
            call mass_times(q - d*v, t, v, f)
            if (stat /= 0) return
            mdot_v = (mdot_v - f)/(2.0_wp*d)
        end if
        call problem%forces(t, q, v, f, stat)
        if (stat /= 0) return
        gt = 0.0_wp
        if (problem%m > 0) call problem%constraint_dt(t, q, gt, stat)
        if (stat /= 0) return
        power = dot_product(v, f) + 0.5_wp*dot_product(v, mdot_v) + dot_product(y, gt)
        if (present(sums)) sums = [sum(abs(mv)), sum(abs(f))]
    contains
        ! M(qq) x, dense or from the pattern's values
        subroutine mass_times(qq, tt, x, mx)
            real(wp), intent(in) :: qq(:), tt, x(:)
            real(wp), intent(out) :: mx(:)
            if (present(pattern)) then
                call problem%mass_values(tt, qq, pattern, vals, stat)
                if (stat /= 0) return
                mx = sparse_times(pattern, vals, x)
            else
                call problem%mass_matrix(tt, qq, dense, stat)
                if (stat /= 0) return
                mx = matmul(dense, x)
            end if
        end subroutine mass_times
    end subroutine kinetic_energy_and_power

end module regdae_work_energy
