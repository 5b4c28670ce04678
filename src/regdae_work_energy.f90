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

    public :: kinetic_energy_and_power, interval_work, parabola_work, tolerance_energy

contains

    !> T = v^T M v / 2 and P = v^T f + v^T (dM/dt) v / 2 + y^T g_t at (t, q, v)
    !! with the multiplier y = -lambda. With `pattern`, M comes in pattern order
    !! from `mass_values` (O(nnz)); else dense from `mass_matrix`. stat: the user
    !! routines' (0 on success).
    subroutine kinetic_energy_and_power(problem, t, q, v, y, kinetic, power, stat, pattern, sums, moving, path, &
                                        constant)
        class(mechanical_problem), intent(inout) :: problem
        real(wp), intent(in) :: t, q(:), v(:), y(:)
        real(wp), intent(out) :: kinetic, power
        integer, intent(out) :: stat
        type(sparsity_pattern), intent(in), optional :: pattern
        real(wp), intent(out), optional :: sums(2)   !! sum_i |(M v)_i| and sum_i |f_i|: the energy an error
                                                     !! dv, dq moves by at most sums(1) max|dv| + sums(2) max|dq|
        logical, intent(out), optional :: moving     !! g_t /= 0 here (the multiplier y does work)
        real(wp), intent(in), optional :: path(:)    !! the velocity q' of the path q(t) when it is not v (an
                                                     !! interpolant's): P = q'^T f + v^T (dM/dt along q') v / 2 + y^T g_t
                                                     !! only (kinetic = 0, sums(1) = 0)
        logical, intent(in), optional :: constant    !! .true.: M depends on neither q nor t (declared), dM/dt = 0
                                                     !! without the difference quotient (which gives exactly 0 then)
        real(wp) :: d, vmax
        logical :: quotient
        real(wp), allocatable :: dense(:, :), vals(:)   ! M at a point (one allocation for the three)
        real(wp), allocatable, target :: work(:)         ! f, M v, dM/dt v, q', q shifted and g_t: one allocation
        integer :: n                                     ! (a heap block each as automatic arrays: 1/4 of the cost)
        stat = 0
        n = size(q)
        if (present(pattern)) then
            allocate (vals(pattern%nnz()))
        else
            allocate (dense(n, n))
        end if
        allocate (work(5*n + problem%m))
        associate (f => work(1:n), mv => work(n + 1:2*n), mdot_v => work(2*n + 1:3*n), u => work(3*n + 1:4*n), &
                   qs => work(4*n + 1:5*n), gt => work(5*n + 1:5*n + problem%m))
            kinetic = 0.0_wp
            power = 0.0_wp
            u = v
            mv = 0.0_wp
            if (present(path)) then   ! a point of an interpolant: its power only
                u = path
            else
                call mass_times(q, t, v, mv)
                if (stat /= 0) return
                kinetic = 0.5_wp*dot_product(v, mv)
            end if
            vmax = maxval(abs(u))
            mdot_v = 0.0_wp
            quotient = (vmax > 0.0_wp)
            if (present(constant)) quotient = quotient .and. .not. constant
            if (quotient) then   ! (M(q + d u) - M(q - d u)) v / (2 d), u = q'
                d = central_difference_step(max(maxval(abs(q)), abs(t)))/max(1.0_wp, vmax)
                qs = q + d*u
                call mass_times(qs, t, v, mdot_v)
                if (stat /= 0) return
                qs = q - d*u
                call mass_times(qs, t, v, f)
                if (stat /= 0) return
                mdot_v = (mdot_v - f)/(2.0_wp*d)
            end if
            call problem%forces(t, q, v, f, stat)
            if (stat /= 0) return
            gt = 0.0_wp
            if (problem%m > 0) call problem%constraint_dt(t, q, gt, stat)
            if (stat /= 0) return
            power = dot_product(u, f) + 0.5_wp*dot_product(v, mdot_v) + dot_product(y, gt)
            if (present(sums)) sums = [sum(abs(mv)), sum(abs(f))]
            if (present(moving)) moving = any(gt /= 0.0_wp)
        end associate
    contains
        ! M(qq) x, dense or from the pattern's values
        subroutine mass_times(qq, tt, x, mx)
            real(wp), intent(in) :: qq(:), tt, x(:)
            real(wp), intent(out) :: mx(:)
            integer :: i
            if (present(pattern)) then
                call problem%mass_values(tt, qq, pattern, vals, stat)
                if (stat /= 0) return
                mx = sparse_times(pattern, vals, x)
            else
                call problem%mass_matrix(tt, qq, dense, stat)
                if (stat /= 0) return
                do i = 1, size(mx)   ! (matmul's sums, without its temporary)
                    mx(i) = dot_product(dense(i, :), x)
                end do
            end if
        end subroutine mass_times
    end subroutine kinetic_energy_and_power

    !> The work of the applied forces over a sample interval [t0, t1] from the states
    !! z = (q, v) and slopes dz = (q', v') at its ends and the powers p0, p1 there:
    !! Boole's rule on the cubic Hermite interpolant of z (the power at t0 + h/4, h/2,
    !! 3h/4), its error estimate |S2 - S1|/15 (Simpson on the halves against Simpson
    !! on the interval). A long explicit step (h omega ~ 1) leaves P far from the
    !! parabola through three samples; the interpolant follows the integrated motion to
    !! O(h^4). stat /= 0: a user routine failed, or the constraints move inside the
    !! interval (g_t /= 0: the multiplier's work needs the multiplier there); the
    !! caller keeps its own quadrature then.
    subroutine interval_work(problem, t0, z0, dz0, p0, t1, z1, dz1, p1, work, error, stat, pattern, constant)
        class(mechanical_problem), intent(inout) :: problem
        real(wp), intent(in) :: t0, z0(:), dz0(:), p0, t1, z1(:), dz1(:), p1
        real(wp), intent(out) :: work, error
        integer, intent(out) :: stat
        type(sparsity_pattern), intent(in), optional :: pattern   !! M in pattern order (`mass_values`), as for
        logical, intent(in), optional :: constant                  !! kinetic_energy_and_power; M declared constant
        real(wp), parameter :: nodes(3) = [0.25_wp, 0.5_wp, 0.75_wp]
        real(wp) :: h, s, z(size(z0)), dq(size(z0)/2), y(problem%m), p(3), kinetic, simpson1, simpson2, sums(2), &
                    path_error
        integer :: k, n
        logical :: moving
        work = 0.0_wp
        error = 0.0_wp
        path_error = 0.0_wp
        n = size(z0)/2
        h = t1 - t0
        y = 0.0_wp
        do k = 1, 3
            s = nodes(k)   ! the cubic Hermite basis at s
            z = (2*s**3 - 3*s**2 + 1)*z0 + (s**3 - 2*s**2 + s)*h*dz0 + (3*s**2 - 2*s**3)*z1 + (s**3 - s**2)*h*dz1
            dq = (6*s - 6*s**2)*(z1(1:n) - z0(1:n))/h + (3*s**2 - 4*s + 1)*dz0(1:n) + (3*s**2 - 2*s)*dz1(1:n)
            call kinetic_energy_and_power(problem, t0 + s*h, z(1:n), z(n + 1:2*n), y, kinetic, p(k), stat, &
                                          pattern, sums, moving, dq, constant)
            ! the path's own uncertainty at the midpoint: q' of the positions' interpolant against
            ! the velocities' (the step's integration error of q' = v), times the forces
            if (k == 2) path_error = h*sums(2)*maxval(abs(dq - z(n + 1:2*n)))
            if (stat == 0 .and. moving) stat = -1
            if (stat /= 0) return
        end do
        simpson1 = h*(p0 + 4*p(2) + p1)/6
        simpson2 = h*(p0 + 4*p(1) + 2*p(2) + 4*p(3) + p1)/12
        work = simpson2 + (simpson2 - simpson1)/15
        error = abs(simpson2 - simpson1)/15
        error = error + path_error
    end subroutine interval_work

    !> The work over a sample interval of length h from the powers at its ends (p, the
    !! new one) and, with `three`, at the sample before (h_before earlier): the parabola
    !! through the three (trapezoidal on the first interval), and the estimate of its error:
    !! |parabola - trapezoid|; for a `long` step (against the motion's time scale) or one
    !! much longer than the one before, at least h |dP|/4 (the parabola through three samples
    !! does not follow P there, and its correction is no bound of its error: a 0.625 s step
    !! of the crank at rtol 1e-3 over a turning point, error 0.28 J against a correction of
    !! 0.05 J); on the first interval h |dP|/2.
    pure subroutine parabola_work(h, h_before, p_before, p_last, p, three, long, work, estimate)
        real(wp), intent(in) :: h, h_before, p_before, p_last, p
        logical, intent(in) :: three, long
        real(wp), intent(out) :: work, estimate
        real(wp) :: trapezoid, d2
        trapezoid = 0.5_wp*h*(p + p_last)
        work = trapezoid
        estimate = 0.5_wp*h*abs(p - p_last)
        if (.not. three) return
        d2 = ((p - p_last)/h - (p_last - p_before)/h_before)/(h + h_before)
        work = trapezoid - d2*h**3/6.0_wp
        estimate = abs(work - trapezoid)
        if (long .or. h > 2.5_wp*h_before) estimate = max(estimate, 0.25_wp*h*abs(p - p_last))
    end subroutine parabola_work

    !> The energy that errors within the tolerance (rtol, atol) on the state leave open:
    !! sums(1) max|dv| + sums(2) max|dq| with dv, dq at rtol |.| + atol (sums from
    !! kinetic_energy_and_power); 0 where it is not a number.
    pure real(wp) function tolerance_energy(sums, q, v, rtol, atol) result(e)
        real(wp), intent(in) :: sums(2), q(:), v(:), rtol, atol
        real(wp) :: vmax, qmax
        vmax = 0.0_wp
        qmax = 0.0_wp
        if (size(v) > 0) vmax = maxval(abs(v))
        if (size(q) > 0) qmax = maxval(abs(q))
        e = sums(1)*(rtol*vmax + atol) + sums(2)*(rtol*qmax + atol)
        if (.not. (e == e)) e = 0.0_wp
    end function tolerance_energy

end module regdae_work_energy
