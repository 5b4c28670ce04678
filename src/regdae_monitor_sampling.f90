!> The sampling of values of `regdae_monitor` (its header describes the checks): a sample of the
!! model's last evaluation (`sample`), the singular intervals, the drift, the invariant and the
!! velocity jump (`sample_values`), and the checkpoint before a singular pass.
submodule (regdae_monitor) regdae_monitor_sampling
    implicit none

contains

    module procedure monitor_sample
        real(wp) :: drift, invariant, kinetic, power, gb, g, g_min, row, sigma, sums(2), energy
        integer :: stat, invariant_stat, i
        logical :: have_g_min
        class(mechanical_problem), pointer :: p
        invariant = 0.0_wp
        invariant_stat = 0
        if (present(sigma_now)) then
            sigma = sigma_now
        else
            sigma = model%sigma_min_gb()
        end if
        have_g_min = .false.
        if (self%scales%eps_factor > 0.0_wp .or. self%drift_auto) then
            gb = 0.0_wp
            g = 0.0_wp
            g_min = huge(1.0_wp)
            do i = 1, model%m
                gb = max(gb, abs(model%gb(i, i)))
                row = norm2(model%gx(i, :))
                g = max(g, row)
                g_min = min(g_min, row)
            end do
            have_g_min = .true.
            if (self%observe_scales(t, gb, g, maxval(abs(z(1:model%n))), sigma)) then
                model%eps = self%scales%eps
                self%model_changed = .true.
            end if
        end if
        if (self%invariant_tol > 0.0_wp) invariant = model%invariant_value(t, z, invariant_stat)
        self%fold_rate = 0.0_wp   ! (order >= 3: the Taylor weights; no projection)
        if (model%order == 1 .and. model%method /= method_baumgarte) self%fold_rate = forgetting_rate(0.0_wp, model%w(1))
        if (model%order == 2 .and. model%method /= method_baumgarte) self%fold_rate = forgetting_rate(model%w(1), model%w(2))
        drift = 0.0_wp
        if (self%np > 0) drift = model%position_drift(t, z, stat)
        if (self%np > 0) then
            call self%sample_values(t, drift, sigma, invariant, invariant_stat, &
                                    z(self%np + 1:2*self%np), dz(self%np + 1:2*self%np), z)
        else
            call self%sample_values(t, drift, sigma, invariant, invariant_stat, z(1:0), dz(1:0), z)
        end if
        call weights_sample(self, t, model, z, dz)
        if (self%work_tol > 0.0_wp) then   ! after sample_values: it knows whether t is in a layer
            if (cached_sample(self, t, z, model)) then   ! step_energy's at this point
                kinetic = self%cached_kinetic
                power = self%cached_power
                sums = self%cached_sums
                stat = 0
            else
                call model%work_sample(t, z, kinetic, power, stat, sums)   ! and the energy the tolerance leaves open:
            end if
            self%have_cached = .false.
            energy = self%energy_tolerance(sums, z(1:model%n), z(model%n + 1:min(size(z), 2*model%n)))
            p => model%mechanical()   ! the problem, z = (q, v) and its slope for the refinement
            if (associated(p)) call self%sample_work(t, kinetic, power, stat, energy, p, z(1:2*p%n), dz(1:2*p%n))
        end if
        if (self%resolution_tol > 0.0_wp) then   ! after sample_values too; G unchanged since the rows' norms
            if (have_g_min) then
                call resolution_sample(self, t, model, g_min)
            else
                call resolution_sample(self, t, model)
            end if
        end if
    end procedure monitor_sample

    ! step_energy's sample of the work-energy balance is at (t, z) with the model's eps and weights
    ! unchanged since (the same multiplier, T and P)
    logical function cached_sample(self, t, z, model) result(same)
        type(solution_monitor), intent(in) :: self
        real(wp), intent(in) :: t, z(:)
        type(regularized_dae), intent(in) :: model
        same = .false.
        if (.not. (self%have_cached .and. allocated(self%step_z) .and. allocated(self%cached_w))) return
        if (t /= self%step_t .or. size(self%step_z) > size(z) .or. model%eps /= self%cached_eps) return
        if (.not. allocated(model%w)) return
        if (size(model%w) /= size(self%cached_w)) return
        same = all(self%step_z == z(1:size(self%step_z))) .and. all(model%w == self%cached_w)
    end function cached_sample

    module procedure monitor_sample_values
        real(wp), allocatable :: grown(:, :)
        real(wp) :: slope, reach
        logical :: was_in_layer
        if (self%invariant_tol > 0.0_wp) call invariant_sample(self, t, invariant, invariant_stat)
        if (self%np > 0) then
            self%drift_max = max(self%drift_max, drift)
            if (self%drift_tol > 0.0_wp .and. drift > self%drift_tol .and. .not. self%alarm) then
                self%alarm = .true.
                self%alarm_kind = alarm_drift
                self%alarm_message = 'the position constraint drifted to max |g| = '//format_real(drift)// &
                                     ' > drift_tol = '//format_real(self%drift_tol)//' at t = '//format_real(t)
            end if
        end if
        self%sigma_last = sigma
        self%sigma_min = min(self%sigma_min, self%sigma_last)
        if (self%relative .and. sigma == sigma) then
            self%sigma_peak = max(self%sigma_peak, sigma)
            ! a singular start's predicted peak holds until the scales release it
            self%threshold = 0.05_wp*max(self%sigma_peak, self%scales%sigma_pred)
            self%layer_threshold = max(self%threshold, 3*sqrt(self%layer_eps))
        end if
        if (self%sigma_last < self%threshold) then
            if (.not. self%in_singular) then
                if (.not. allocated(self%singular)) allocate (self%singular(2, 8))
                if (self%n_singular == size(self%singular, 2)) then
                    allocate (grown(2, 2*size(self%singular, 2)))
                    grown(:, 1:self%n_singular) = self%singular
                    call move_alloc(grown, self%singular)
                end if
                self%n_singular = self%n_singular + 1
                self%singular(1, self%n_singular) = t
            end if
            self%singular(2, self%n_singular) = t
            self%in_singular = .true.
        else
            if (self%in_singular) self%pass_ended = .true.
            self%in_singular = .false.
        end if
        if (present(z)) call checkpoint_sample(self, t, z)
        call fold_sample(self, t, sigma)
        ! the secant of sigma over the last two samples: for a convex decrease (sigma_min
        ! ~ distance^2 at a rank-one singular configuration) it reaches threshold/2 at
        ! most halfway to the minimum, so the landing sample does not jump over it
        self%land_by = huge(1.0_wp)
        slope = 0.0_wp
        if (self%sigma_before >= 0.0_wp .and. t > self%t_sigma_before .and. sigma == sigma) &
            slope = (sigma - self%sigma_before)/(t - self%t_sigma_before)
        if (.not. self%in_singular .and. slope < 0.0_wp) then
            reach = (sigma - 0.5_wp*self%threshold)/(-slope)
            ! a convex decrease (the secant slopes flatten: sigma ~ distance^2, the rank-one
            ! singular configuration of a mechanism): the double root's Newton step, 2x the
            ! secant's, still ends before the minimum
            if (self%slope_before < slope .and. self%slope_before < 0.0_wp) reach = 2.0_wp*reach
            self%land_by = t + reach
        end if
        self%slope_before = slope
        if (sigma == sigma) then
            self%sigma_before = sigma
            self%t_sigma_before = t
        end if
        was_in_layer = self%in_layer
        self%in_layer = (self%sigma_last < self%layer_threshold)
        if (self%np > 0 .and. self%jump_tol > 0.0_wp .and. .not. self%in_layer) &
            call regular_sample(self, t, v, a, was_in_layer)
        call settle_alarm(self)
    end procedure monitor_sample_values

    ! A fold's residual ahead of the next fold: once sigma_min(GB) has risen fold_factor times
    ! above the minimum of a dip to below threshold/fold_factor^2 (a fold passed) and fallen to
    ! half its peak since (towards another fold) while the stabilization has forgotten less than
    ! e^-fold_memory of what that fold's layer left in the constraints, project_due (the front
    ! projects the state).
    subroutine fold_sample(self, t, sigma)
        type(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: t, sigma
        if (.not. (sigma == sigma)) return
        if (sigma < self%threshold .and. sigma <= self%fold_low) then
            self%fold_low = sigma
            self%t_fold = t
            self%fold_peak = 0.0_wp
        end if
        if (self%fold_low == huge(1.0_wp) .or. .not. (self%fold_rate > 0.0_wp)) return
        if ((t - self%t_fold)*self%fold_rate > fold_memory) then   ! forgotten
            self%fold_low = huge(1.0_wp)
            return
        end if
        if (sigma > fold_factor*self%fold_low .and. fold_factor**2*self%fold_low < self%threshold) &
            self%fold_peak = max(self%fold_peak, sigma)
        if (sigma < 0.5_wp*self%fold_peak) then
            if (self%project_on) self%project_due = .true.
            self%fold_low = huge(1.0_wp)
        end if
    end subroutine fold_sample

    ! The invariant at t: the first sample sets I(t0).
    subroutine invariant_sample(self, t, val, stat)
        type(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: t, val
        integer, intent(in) :: stat
        real(wp) :: change
        if (.not. self%have_invariant) then
            self%invariant0 = val
            self%have_invariant = .true.
            return
        end if
        change = abs(val - self%invariant0)
        if (change == change) self%invariant_change = max(self%invariant_change, change)
        if (stat == 0 .and. change <= self%invariant_tol) return
        if (.not. self%alarm) then   ! too large, NaN, or the user routine failed
            self%alarm = .true.
            self%alarm_kind = alarm_invariant
            if (stat /= 0) then
                self%alarm_message = 'user routine invariant reported failure (stat = '//format_int(stat)// &
                                     ') at t = '//format_real(t)
            else
                self%alarm_message = 'the invariant changed by '//format_real(change)//' > invariant_tol = '// &
                                     format_real(self%invariant_tol)//' at t = '//format_real(t)
            end if
        end if
    end subroutine invariant_sample

    ! A regular sample (v, a) at t: J against the last regular sample if a
    ! singular interval lies between them; then keep this one.
    subroutine regular_sample(self, t, v, a, after_interval)
        type(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: t, v(:), a(:)
        logical, intent(in) :: after_interval
        real(wp) :: dt, jump, scale
        if (after_interval .and. self%have_regular) then
            dt = t - self%t_regular
            scale = max(norm2(self%v_regular), norm2(v), dt*max(norm2(self%a_regular), norm2(a)))
            jump = 0.0_wp
            if (scale > 0.0_wp) jump = norm2(v - self%v_regular - 0.5_wp*dt*(self%a_regular + a))/scale
            self%jump_max = max(self%jump_max, jump)
            if (jump > self%jump_tol .and. .not. self%alarm) then
                self%alarm = .true.
                self%alarm_kind = alarm_jump
                self%alarm_message = 'the velocity jumped across the singular configuration between t = '// &
                                     format_real(self%t_regular)//' and '//format_real(t)//' (relative jump '// &
                                     format_real(jump)//' > jump_tol = '//format_real(self%jump_tol)//')'
            end if
        end if
        self%have_regular = .true.
        self%t_regular = t
        self%v_regular = v
        self%a_regular = a
    end subroutine regular_sample

    module procedure monitor_release_checkpoint
        self%checkpoint_frozen = .false.
        self%checkpoint_t = t
        self%checkpoint_z = z
        self%checkpoint_valid = .true.
    end procedure monitor_release_checkpoint

    ! The checkpoint at a sample (t, z): frozen at the first sample of a pass (a
    ! start inside one takes that sample), else moved to every sample on the
    ! approach level.
    subroutine checkpoint_sample(self, t, z)
        type(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: t, z(:)
        if (self%checkpoint_frozen) return
        if (self%in_singular) then
            self%checkpoint_frozen = .true.
            if (self%checkpoint_valid) return
        else if (.not. (self%sigma_last >= checkpoint_factor*self%threshold) .and. self%checkpoint_valid) then
            return
        end if
        self%checkpoint_t = t
        self%checkpoint_z = z
        self%checkpoint_valid = .true.
    end subroutine checkpoint_sample

end submodule regdae_monitor_sampling
