!> A small explicit Dormand-Prince 5(4) integrator with step-size control and
!! its 4th-order continuous extension for the output: the benchmark's oracle for the slider crank's reduced
!! ODE (the speed any DAE method here is measured against), with the tableau
!! of `regdae_dopri_tableau`.
module dopri5
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae, only: wp
    use reference_ode, only: ode_system
    use regdae_dopri_tableau
    implicit none
    private
    public :: dopri5_integrate

contains

    !> Integrate y' = F(t, y) from (t0, y0) to the ascending `times`; states(:, k)
    !! at times(k) by the continuous extension of the step. `steps` counts
    !! accepted steps, `evals` right-hand-side evaluations; where no step fits (h below
    !! the rounding of t), the outputs from there on are NaN and steps is negative.
    subroutine dopri5_integrate(system, t0, y0, times, states, rtol, atol, steps, evals)
        class(ode_system), intent(inout) :: system
        real(wp), intent(in) :: t0, y0(:), times(:), rtol, atol
        real(wp), intent(out) :: states(:, :)
        integer, intent(out) :: steps, evals
        real(wp), dimension(size(y0)) :: y, ynew, k1, k2, k3, k4, k5, k6, k7, err, dy, p, q, r
        real(wp) :: t, h, tend, e, theta, fac
        integer :: iout, n

        n = size(y0)
        y = y0
        t = t0
        tend = times(size(times))
        call system%rhs(t, y, k1)
        evals = 1
        steps = 0
        h = 0.01_wp*max(abs(tend - t0), 1.0_wp)*min(1.0_wp, (rtol/1.0e-3_wp)**0.2_wp)
        iout = 1
        do while (iout <= size(times))
            if (times(iout) <= t) then   ! outputs at or before the start
                states(:, iout) = y
                iout = iout + 1
                cycle
            end if
            h = min(h, tend - t)
            if (tend - t <= 16*epsilon(1.0_wp)*max(1.0_wp, abs(tend))) then   ! at tend up to rounding
                states(:, iout:) = spread(y, 2, size(times) - iout + 1)
                exit
            end if
            if (h <= 16*epsilon(1.0_wp)*max(1.0_wp, abs(t))) then   ! no step fits: the method fails here
                states(:, iout:) = ieee_value(1.0_wp, ieee_quiet_nan)
                steps = -steps
                exit
            end if
            call system%rhs(t + c2*h, y + h*a21*k1, k2)
            call system%rhs(t + c3*h, y + h*(a31*k1 + a32*k2), k3)
            call system%rhs(t + c4*h, y + h*(a41*k1 + a42*k2 + a43*k3), k4)
            call system%rhs(t + c5*h, y + h*(a51*k1 + a52*k2 + a53*k3 + a54*k4), k5)
            call system%rhs(t + h, y + h*(a61*k1 + a62*k2 + a63*k3 + a64*k4 + a65*k5), k6)
            ynew = y + h*(b1*k1 + b3*k3 + b4*k4 + b5*k5 + b6*k6)
            call system%rhs(t + h, ynew, k7)
            evals = evals + 6
            err = h*(e1*k1 + e3*k3 + e4*k4 + e5*k5 + e6*k6 + e7*k7)
            e = sqrt(sum((err/(atol + rtol*max(abs(y), abs(ynew))))**2)/n)
            if (.not. (e <= huge(1.0_wp))) e = huge(1.0_wp)   ! NaN or Inf (a step far too long): shrink it
            if (e <= 1.0_wp) then
                ! Outputs in (t, t + h]: the continuous extension (regdae_dopri_tableau).
                if (times(iout) <= t + h) then
                    dy = ynew - y
                    p = h*k1 - dy
                    q = dy - h*k7 - p
                    r = h*(d1*k1 + d3*k3 + d4*k4 + d5*k5 + d6*k6 + d7*k7)
                end if
                do while (iout <= size(times))
                    if (times(iout) > t + h) exit
                    theta = (times(iout) - t)/h
                    states(:, iout) = y + theta*(dy + (1 - theta)*(p + theta*(q + (1 - theta)*r)))
                    iout = iout + 1
                end do
                t = t + h
                y = ynew
                k1 = k7   ! first same as last
                steps = steps + 1
            end if
            fac = 0.9_wp*max(e, 1.0e-10_wp)**(-0.2_wp)
            h = h*min(5.0_wp, max(0.2_wp, fac))
        end do
    end subroutine dopri5_integrate

end module dopri5
