!> The work-energy balance of `regdae_monitor` (its header describes it): the samples of the
!! kinetic energy and the power (`sample_work`), the quadrature of the work and its refinement,
!! the allowance and the alarm; the balance of a long explicit step before it is taken
!! (`step_energy`); the new start after a pass check (`rebase_work`).
submodule (regdae_monitor) regdae_monitor_work
    implicit none

contains

    module procedure monitor_sample_work
        real(wp) :: defect, h, quadratic, allowed, estimate, refined, refined_error, kinetic_before, &
                    thresh, interval_defect
        integer :: rstat
        logical :: refine, step_end
        if (.not. (self%work_tol > 0.0_wp) .or. stat /= 0) return
        refine = present(problem) .and. present(z) .and. present(dz) .and. allocated(self%work_z)
        if (refine) refine = size(self%work_z) == size(z)
        if (.not. self%have_work) then
            self%kinetic_last = kinetic
            self%kinetic0 = kinetic
            self%tolerance_energy = 0.0_wp
            self%work = 0.0_wp
            self%work_scale = max(kinetic, self%work_floor)
            self%power_last = power
            self%t_work = t
            self%quadrature_error = 0.0_wp
            self%unresolved_error = 0.0_wp
            self%work_samples = 1
            self%carried = 0.0_wp
            self%stretch = 0.0_wp
            self%carried_warned = .false.
            self%have_work = .true.
            call keep_state()
            return
        end if
        h = t - self%t_work
        if (.not. (h > 0.0_wp)) return
        ! T at t_work: a sample inside the last interval (an output inside a step) leaves it
        kinetic_before = self%kinetic_last
        self%kinetic_last = kinetic
        step_end = t == self%step_t .and. self%t_work == self%step_from .and. allocated(self%step_z) .and. present(z)
        if (step_end) step_end = size(self%step_z) == size(z)
        if (step_end) step_end = all(self%step_z == z)   ! step_energy looked at this interval
        call parabola_work(h, self%t_work - self%t_before, self%power_before, self%power_last, power, &
                           self%work_samples >= 2, h*self%work_rate > 0.3_wp, quadratic, estimate)
        ! an interval whose estimate is not small against the allowance: Boole's rule on the
        ! integrator's motion inside it (the Hermite interpolant of the ends), with its own estimate;
        ! also (outside the layers) one whose own balance T - T_last - W is not small, where the
        ! ends' estimate cannot see a power that vanishes at both (a quarter period from rest to
        ! the peak of T): its refinement is taken only where it closes that balance, estimate
        ! included (else its estimate would widen the allowance where the energy did move)
        thresh = work_refine*self%work_tol*self%work_scale
        interval_defect = abs(kinetic - kinetic_before - quadratic)
        if (refine .and. (estimate > thresh .or. (.not. self%in_layer .and. interval_defect > thresh))) then
            rstat = -1
            if (step_end) then   ! step_energy's of this interval
                refined = self%step_work
                refined_error = self%step_error
                rstat = 0
            end if
            if (rstat /= 0) call interval_work(problem, self%t_work, self%work_z, self%work_dz, self%power_last, t, z, &
                                               dz, power, refined, refined_error, rstat, pattern, constant)
            if (rstat == 0 .and. .not. (estimate > thresh)) then
                if (.not. (abs(kinetic - kinetic_before - refined) + refined_error < interval_defect)) rstat = -1
            end if
            if (rstat == 0) then
                quadratic = refined
                estimate = refined_error
            end if
        end if
        call keep_state()
        ! a step whose balance the halvings did not resolve: its estimate counts against the
        ! balance (with the defect), not for it (the allowance)
        if (step_end .and. self%step_unresolved) then
            self%unresolved_error = self%unresolved_error + estimate
        else
            self%quadrature_error = self%quadrature_error + estimate
        end if
        self%work = self%work + quadratic
        self%power_before = self%power_last
        self%t_before = self%t_work
        self%power_last = power
        self%t_work = t
        self%work_samples = self%work_samples + 1
        defect = kinetic - self%kinetic0 - self%work
        self%work_scale = max(self%work_scale, kinetic, abs(self%work), abs(kinetic - self%kinetic0))
        if (.not. (self%work_scale > 0.0_wp)) return
        if (.not. (abs(defect) <= huge(1.0_wp))) defect = huge(1.0_wp)   ! NaN or Inf: a failure
        if (self%in_layer) return   ! tested outside the layers only
        self%work_defect = max(self%work_defect, abs(defect)/self%work_scale)
        ! the energy errors the tolerance allows: each step's error within the tolerance moves
        ! the energy by at most energy_tol; summed as a random walk (squares), three times:
        ! the check is for energy gains beyond the integration error (a branch change, too
        ! stiff a regularization), not for the integrator's own energy drift
        if (present(energy_tol)) self%tolerance_energy = self%tolerance_energy + energy_tol**2
        allowed = self%work_tol*self%work_scale + self%quadrature_error + 3.0_wp*sqrt(self%tolerance_energy)
        call carried_balance()
        if (abs(defect) + self%unresolved_error > allowed .and. .not. self%alarm) then
            self%alarm = .true.
            self%alarm_kind = alarm_work
            self%alarm_message = 'the work-energy balance failed at t = '//format_real(t)//': the kinetic energy '// &
                                 'changed by '//format_real(kinetic - self%kinetic0)//' but the applied forces did '// &
                                 format_real(self%work)//' of work (defect '//format_real(abs(defect)/self%work_scale)// &
                                 ' of the energy scale '//format_real(self%work_scale)//' > work_tol = '// &
                                 format_real(self%work_tol)//')'
            if (self%unresolved_error > 0.0_wp) self%alarm_message = self%alarm_message//'; steps whose balance '// &
                'shorter steps did not resolve leave '//format_real(self%unresolved_error)//' more open'
        end if
        call settle_alarm(self)
    contains
        ! The balance carried across the pass checks (module doc): the stretches' defects summed
        ! against work_tol S and their quadratures' estimates, without the tolerance's energy
        subroutine carried_balance()
            real(wp) :: total, open_error
            self%stretch = [defect, self%quadrature_error, self%unresolved_error]
            if (self%carried_warned .or. .not. (self%carried(1) /= 0.0_wp .or. self%carried(2) > 0.0_wp)) return
            total = self%carried(1) + defect
            open_error = self%carried(3) + self%unresolved_error
            if (.not. (abs(total) + open_error > self%work_tol*self%work_scale + self%carried(2) + &
                       self%quadrature_error)) return
            ! a drift, not a random walk: the sum beyond 3 times the root of the squares
            if (.not. (abs(total) > 3.0_wp*sqrt(self%carried(4) + defect**2))) return
            self%carried_warned = .true.
            self%unresolved_new = .true.
            self%unresolved_message = 'the work-energy balance carried across the pass checks is off at t = '// &
                format_real(t)//': the stretches between them left a defect of '//format_real(total)// &
                ' (the energy scale '//format_real(self%work_scale)//', work_tol = '//format_real(self%work_tol)// &
                ', the quadratures'' estimates '//format_real(self%carried(2) + self%quadrature_error)// &
                ') that grew like a drift, not a random walk: the motion gains or loses energy through the passes, '// &
                'and x may be off beyond the tolerance; a smaller rtol and atol may resolve it; work_tol=0 turns '// &
                'this warning off'
        end subroutine carried_balance

        subroutine keep_state()   ! this sample's state and slope for the next interval's refinement
            if (.not. (present(problem) .and. present(z) .and. present(dz))) then
                if (allocated(self%work_z)) deallocate (self%work_z, self%work_dz)
                return
            end if
            self%work_z = z
            self%work_dz = dz   ! (both reallocated only when the size changes)
        end subroutine keep_state
    end procedure monitor_sample_work

    module procedure monitor_step_energy
        real(wp) :: kinetic, power, sums(2), work, error, allowed
        integer :: stat, n, rstat
        class(mechanical_problem), pointer :: p
        unresolved = .false.
        self%step_unresolved = .false.
        self%have_cached = .false.
        if (.not. (self%work_tol > 0.0_wp .and. self%have_work .and. allocated(self%work_z))) return
        if (self%in_layer .or. self%in_singular .or. .not. (t > self%t_work)) return
        if (.not. ((t - self%t_work)*self%work_rate > 0.3_wp)) return
        call model%work_sample(t, z, kinetic, power, stat, sums)
        if (stat /= 0) return
        p => model%mechanical()
        if (.not. associated(p)) return
        n = p%n
        if (size(self%work_z) /= 2*n) return
        call interval_work(p, self%t_work, self%work_z, self%work_dz, self%power_last, t, z(1:2*n), dz(1:2*n), &
                           power, work, error, rstat)
        if (rstat /= 0) return
        self%step_t = t
        self%step_from = self%t_work
        self%step_z = z(1:2*n)
        self%step_work = work
        self%step_error = error
        self%cached_kinetic = kinetic
        self%cached_power = power
        self%cached_sums = sums
        self%cached_eps = model%eps
        self%cached_w = model%w
        self%have_cached = .true.
        allowed = max(step_energy_factor*self%energy_tolerance(sums, z(1:n), z(n + 1:2*n)), &
                      work_refine*self%work_tol*self%work_scale)
        unresolved = abs(kinetic - self%kinetic_last - work) + error > allowed
        self%step_unresolved = unresolved
    end procedure monitor_step_energy

    module procedure monitor_rebase_work
        if (.not. self%have_work) return
        self%carried(1:3) = self%carried(1:3) + self%stretch   ! the closed stretch, at its last tested sample
        self%carried(4) = self%carried(4) + self%stretch(1)**2
        self%stretch = 0.0_wp
        ! the balance starts again from the verified state: D = 0 there (the path the
        ! solution took through the pass is not the one it goes on from)
        self%kinetic0 = kinetic
        self%work = 0.0_wp
        self%quadrature_error = 0.0_wp
        self%unresolved_error = 0.0_wp
        self%tolerance_energy = 0.0_wp
        self%kinetic_last = kinetic
        self%power_last = power
        self%power_before = power
        self%t_work = t      ! the quadrature goes on from t (the last sample may lie beyond it)
        self%t_before = t
        self%work_samples = 1
        if (allocated(self%work_z)) deallocate (self%work_z, self%work_dz)   ! the last sample is not the state at t
    end procedure monitor_rebase_work

    module procedure monitor_energy_tolerance
        e = state_energy_tolerance(sums, q, v, self%scales%rtol, self%scales%atol)
    end procedure monitor_energy_tolerance

    module procedure settle_alarm
        if (.not. (self%alarm .and. self%defer_in_pass .and. self%checkpoint_frozen)) return
        ! without a regularization (eps = 0, Baumgarte) the branch at a bifurcation is not the
        ! damped multiplier's: every level takes the same, and the jump check decides
        if (self%alarm_kind == alarm_jump .and. .not. (self%layer_eps > 0.0_wp)) return
        self%alarm = .false.
        self%deferred_alarms = self%deferred_alarms + 1
        self%deferred_message = self%alarm_message
        self%alarm_kind = alarm_none
    end procedure settle_alarm

end submodule regdae_monitor_work
