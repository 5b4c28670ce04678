!> The scales that regdae_auto_rules' rules take, gathered from the augmented
!! formulation (`regdae_augmented_system`): M's diagonal, a row's part of the
!! GB scale, and the motion's scales (the constraint length, the rate of the
!! motion, a singular start's predicted GB scale) from the sparse G and M, the
!! counterpart of `dense_motion_scales` for the dense models. The front uses
!! them at t0 and the monitor's sampling (`regdae_solver_sampling`) along the
!! run, which is why they are a module of their own: in the sampling module the
!! front's start would depend on the monitor's sampling, and regdae_auto_rules
!! holds the rules on scales only and comes before the augmented system.
module regdae_augmented_rules
    use regdae_kinds, only: wp
    use regdae_differences, only: central_difference_step
    use regdae_augmented_system, only: augmented_system
    use regdae_auto_rules, only: motion_rate, constraint_length, rms, degenerate_row, predict_shift, generic_direction, &
                                 periodic_representative, same_geometry
    implicit none
    private

    public :: mass_diagonal, gb_row_scale, augmented_motion_scales

contains

    !> M's diagonal (1 where M has none, and everywhere if one is not positive).
    subroutine mass_diagonal(sys, mdiag)
        type(augmented_system), intent(in) :: sys
        real(wp), intent(out) :: mdiag(:)
        integer :: i, k
        mdiag = 1.0_wp
        do i = 1, sys%n
            k = sys%st%mass%position(i, i)
            if (k > 0) mdiag(i) = sys%mvals(k)
        end do
        if (.not. all(mdiag > 0.0_wp)) mdiag = 1.0_wp
    end subroutine mass_diagonal

    !> Row i's part of the GB scale: sum_k G_ik^2 / M_kk over the nonzeros of row i of
    !! the sparse G (its values gvals in the pattern's order; mdiag: M's diagonal).
    pure real(wp) function gb_row_scale(sys, gvals, mdiag, i) result(row)
        type(augmented_system), intent(in) :: sys
        real(wp), intent(in) :: gvals(:), mdiag(:)
        integer, intent(in) :: i
        integer :: k
        row = 0.0_wp
        do k = sys%st%constraint%row_start(i), sys%st%constraint%row_start(i + 1) - 1
            row = row + gvals(k)**2/mdiag(sys%st%constraint%cols(k))
        end do
    end function gb_row_scale

    !> The scales of regdae_auto_rules' dense_motion_scales for the augmented
    !! formulation at (t, q, v) with the accelerations acc and free (the applied
    !! forces' M_kk^-1 f_k): the sparse G along v and acc (or free), the length
    !! (at least ell_before), the rate, and at a singular start (predict) the
    !! predicted GB scale max_i sum_k G_pred,ik^2 / M_kk (-1: no row vanishes), G and the
    !! scale of q measured at the angles' representative where G is the same there.
    !! stat: the user's constraint_jacobian_values.
    subroutine augmented_motion_scales(sys, t, q, v, acc, free, ell_before, predict, ell, rate, sigma_pred, stat, &
                                       stiffness)
        type(augmented_system), intent(inout) :: sys
        real(wp), intent(in) :: t, q(:), v(:), acc(:), free(:), ell_before
        logical, intent(in) :: predict
        logical, intent(in) :: stiffness   ! the forces' frequency counts (t0)
        real(wp), intent(out) :: ell, rate, sigma_pred
        integer, intent(out) :: stat
        real(wp) :: g0(sys%st%constraint%nnz()), g1(sys%st%constraint%nnz()), dg(sys%st%constraint%nnz()), &
                    gnorm(sys%m), hnorm(sys%m), mdiag(sys%n), w(sys%n), qr(sys%n), ell_x, d, change, k_force
        integer :: i, pass
        logical :: degenerate
        stat = 0
        sigma_pred = -1.0_wp
        ell_x = rms(q)
        if (.not. (ell_x > 0.0_wp)) ell_x = 1.0_wp
        associate (gp => sys%st%constraint)
            call row_changes(q)
            if (stat /= 0) return
            ell = max(constraint_length(gnorm, hnorm, ell_x), ell_before)
            k_force = 0.0_wp
            if (stiffness) k_force = force_stiffness()
            rate = motion_rate(.true., v, acc, free, ell, k_force)
            if (.not. predict .or. sys%m == 0) return
            call sys%problem%constraint_jacobian_values(t, q, gp, g0, stat)
            if (stat /= 0) return
            if (any(gnorm < degenerate_row*hnorm*ell_x)) then
                ! a singular start: its geometry and the scale of q from the angles'
                ! representative in (-pi, pi] where G is the same there
                qr = periodic_representative(q)
                if (any(qr /= q)) then
                    call sys%problem%constraint_jacobian_values(t, qr, gp, g1, stat)
                    if (stat /= 0) return
                    if (same_geometry(g0, g1, q, maxval(hnorm))) then
                        call row_changes(qr)
                        if (stat /= 0) return
                        call sys%problem%constraint_jacobian_values(t, qr, gp, g0, stat)
                        if (stat /= 0) return
                        ell_x = rms(qr)
                        if (.not. (ell_x > 0.0_wp)) ell_x = 1.0_wp
                    end if
                end if
            end if
            call mass_diagonal(sys, mdiag)
            degenerate = .false.
            do i = 1, sys%m
                if (gnorm(i) < degenerate_row*hnorm(i)*ell_x) then
                    degenerate = .true.
                    g0(gp%row_start(i):gp%row_start(i + 1) - 1) = g0(gp%row_start(i):gp%row_start(i + 1) - 1) + &
                        predict_shift*ell_x*dg(gp%row_start(i):gp%row_start(i + 1) - 1)
                end if
            end do
            if (.not. degenerate) return
            sigma_pred = 0.0_wp
            do i = 1, sys%m
                sigma_pred = max(sigma_pred, gb_row_scale(sys, g0, mdiag, i))
            end do
        end associate
    contains
        ! gnorm, hnorm and dg at the positions qq: the rows of G and their largest change per unit
        ! length along v and acc (or free), central differences (g0, g1 overwritten)
        subroutine row_changes(qq)
            real(wp), intent(in) :: qq(:)
            d = central_difference_step(maxval(abs(qq)))
            gnorm = 0.0_wp
            hnorm = 0.0_wp
            dg = 0.0_wp
            associate (gp => sys%st%constraint)
                do pass = 1, 2
                    if (pass == 1) w = v
                    if (pass == 2) w = merge(acc, free, maxval(abs(acc)) > 0.0_wp)
                    if (.not. (maxval(abs(w)) > 0.0_wp .and. maxval(abs(w)) < huge(1.0_wp))) cycle
                    w = w/maxval(abs(w))
                    call sys%problem%constraint_jacobian_values(t, qq - d*w, gp, g0, stat)
                    if (stat == 0) call sys%problem%constraint_jacobian_values(t, qq + d*w, gp, g1, stat)
                    if (stat /= 0) return
                    do i = 1, sys%m
                        associate (a => gp%row_start(i), b => gp%row_start(i + 1) - 1)
                            change = norm2(g1(a:b) - g0(a:b))/(2.0_wp*d)
                            gnorm(i) = max(gnorm(i), 0.5_wp*norm2(g1(a:b) + g0(a:b)))
                            if (.not. (change*d > 1.0e3_wp*epsilon(1.0_wp)*gnorm(i))) change = 0.0_wp
                            if (change > hnorm(i)) then
                                hnorm(i) = change
                                dg(a:b) = (g1(a:b) - g0(a:b))/(2.0_wp*d)
                            end if
                        end associate
                    end do
                end do
            end associate
        end subroutine row_changes
        ! |d (M_kk^-1 f)/dq| along the generic direction (central differences of the forces)
        real(wp) function force_stiffness() result(k)
            real(wp) :: fp(sys%n), fm(sys%n), md(sys%n), wg(sys%n), dq
            integer :: s1, s2
            k = 0.0_wp
            wg = generic_direction(sys%n)
            dq = central_difference_step(maxval(abs(q)))
            s1 = 0
            s2 = 0
            call sys%problem%forces(t, q + dq*wg, v, fp, s1)
            call sys%problem%forces(t, q - dq*wg, v, fm, s2)
            if (s1 /= 0 .or. s2 /= 0) return
            call mass_diagonal(sys, md)
            k = rms((fp - fm)/md)/(2.0_wp*dq)
            if (.not. (k*dq > 1.0e3_wp*epsilon(1.0_wp)*max(rms(free), tiny(1.0_wp)))) k = 0.0_wp
        end function force_stiffness
    end subroutine augmented_motion_scales

end module regdae_augmented_rules
