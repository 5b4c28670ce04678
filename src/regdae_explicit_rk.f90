!> An explicit Dormand-Prince 5(4) integrator for the eliminated regularized
!! system z' = F(z, t) (option `integrator=dopri5`), an alternative to IDA when the
!! regularized system is not stiff: moderate Baumgarte weights (e.g. gamma1 = 20,
!! gamma0 = gamma1^2/2 for index 3) and no stiff forces. Step-size control on the
!! embedded 4th-order solution, first-same-as-last stages, 4th-order continuous
!! extension for the output.
!! F comes from the same regularized model IDA uses (`slope_eliminated`; IDA's
!! residual is z' - F), so every method, order and problem type works unchanged.
module regdae_explicit_rk
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_integration
    use regdae_format, only: format_real
    use regdae_regularization, only: regularized_dae
    use regdae_monitor, only: solution_monitor, approach_factor
    use regdae_auto_rules, only: constraint_mode_step
    use regdae_taylor_layer, only: taylor_layer_watch
    use regdae_dopri_tableau
    implicit none
    private

    public :: continuous_extension

    !> After a start from a given first step (the restart at the end of a checked pass, the
    !! hand-over from the implicit integrator, h_init) this many accepted steps stay within the
    !! constraint modes' stable step (constraint_mode_step; as many as the stiffness test counts).
    integer, parameter :: restart_stable_steps = 15

    !> The integrator's state: the last accepted step [t_old, t] and its end values.
    type, public :: rk_integrator
        real(wp) :: t = 0.0_wp, t_old = 0.0_wp, h = 0.0_wp, h_last = 0.0_wp
        real(wp), allocatable :: z(:), k1(:), z_old(:), k_old(:)
        real(wp), allocatable :: k2(:), k3(:), k4(:), k5(:), k6(:), k7(:), z_new(:), z_stage(:), work(:), y_work(:)
        integer :: steps = 0, evals = 0, rejects = 0
        integer :: stiff_count = 0, quiet_count = 0   ! the stiffness test's counters
        integer :: restart_steps = 0   !! accepted steps left within the stable step after a restart
        integer :: energy_rejects = 0  !! steps taken again because their work-energy balance was unresolved
        real(wp) :: h_energy = 0.0_wp  !! after such a step, the longest step (growing 1.25x per step; 0: none)
        logical :: stiff_detected = .false.          !! the last advance stopped because the system is stiff
        logical :: pass_stop = .false.               !! the last advance stopped at the end of a singular pass
        ! the continuous extension's vectors of the step ending at dense_t
        real(wp), allocatable :: dense_dz(:), dense_p(:), dense_q(:), dense_r(:)
        real(wp) :: dense_t = -huge(1.0_wp)
        ! the monitor's last two samples (time, sigma_min(GB)): a singular pass between them
        ! and the step's end is looked for (sample_step_end)
        real(wp) :: t_seen(2) = 0.0_wp, sigma_seen(2) = -1.0_wp
        character(len=:), allocatable :: message
        type(taylor_layer_watch) :: layer   !! order >= 3: the growth in the layer of the Taylor weights
    contains
        !> Start at (t0, z0) with the slope at z0.
        procedure :: start => rk_start
        !> Step until the solution is known at tout; return z(tout).
        procedure :: advance => rk_advance
    end type rk_integrator

contains

    ! F(t, z) from the regularized residual; stat /= 0 on failure (message in
    ! model), with `recoverable` false when a smaller step cannot help (a user
    ! routine's stat < 0, a mass matrix that is not SPD, GB not PSD).
    subroutine slope(self, model, t, z, f, stat, recoverable)
        class(rk_integrator), intent(inout) :: self
        type(regularized_dae), intent(inout) :: model
        real(wp), intent(in) :: t
        real(wp), intent(in), contiguous :: z(:)    ! contiguous: the slope's loops without stride cases
        real(wp), intent(out), contiguous :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        call model%slope_eliminated(t, z, f, self%y_work, stat, recoverable)
        self%evals = self%evals + 1
        ! No NaN/Inf check here: the model has checked f, GB, r and y (B through GB),
        ! and a NaN that reaches the step through z makes the error estimate NaN,
        ! which rejects the step (and, repeated, fails with 'step size too small').
    end subroutine slope

    subroutine rk_start(self, model, t0, z0, h0, stat)
        class(rk_integrator), intent(inout) :: self
        type(regularized_dae), intent(inout) :: model
        real(wp), intent(in) :: t0, z0(:)
        real(wp), intent(in) :: h0        !! first step (0: chosen here)
        integer, intent(out) :: stat
        integer :: n
        logical :: recoverable
        n = size(z0)
        if (allocated(self%z)) deallocate (self%dense_dz, self%dense_p, self%dense_q, self%dense_r, self%z, self%k1, &
                                           self%z_old, self%k_old, self%k2, self%k3, self%k4, self%k5, self%k6, &
                                           self%k7, self%z_new, self%z_stage, self%work, self%y_work)
        self%stiff_count = 0
        self%t_seen = t0
        self%sigma_seen = -1.0_wp
        self%quiet_count = 0
        self%stiff_detected = .false.
        allocate (self%dense_dz(n), self%dense_p(n), self%dense_q(n), self%dense_r(n))
        self%dense_t = -huge(1.0_wp)
        allocate (self%z(n), self%k1(n), self%z_old(n), self%k_old(n), self%k2(n), self%k3(n), self%k4(n), &
                  self%k5(n), self%k6(n), self%k7(n), self%z_new(n), self%z_stage(n), self%work(n), &
                  self%y_work(model%m))
        self%t = t0
        self%t_old = t0
        self%z = z0
        self%z_old = z0
        self%h = h0
        self%restart_steps = 0
        self%h_energy = 0.0_wp
        if (h0 > 0.0_wp) self%restart_steps = restart_stable_steps
        if (.not. (h0 > 0.0_wp)) self%h = 1.0e-3_wp*max(1.0_wp, abs(t0))
        self%message = ''
        call slope(self, model, t0, z0, self%k1, stat, recoverable)
        self%k_old = self%k1
    end subroutine rk_start

    !> Advance to tout (> the current output time): steps until t >= tout (or, with
    !! `land_on_tout`, exactly to tout) and interpolates. stat: regdae_success,
    !! regdae_err_integration with `message`, or the status of an evaluation that
    !! failed unrecoverably (a user routine's stat < 0: regdae_err_user_callback;
    !! regdae_err_mass_matrix, regdae_err_not_psd), which stops the integration at once. `monitor`, if given, samples every
    !! accepted step's end, where `model` holds the evaluation of the
    !! first-same-as-last stage (no extra evaluation).
    subroutine rk_advance(self, model, tout, rtol, atol, h_max, max_steps, land_on_tout, zout, stat, monitor, &
                          stop_when_stiff, stop_at_pass_end, stable_weights, stable_always)
        class(rk_integrator), intent(inout) :: self
        type(regularized_dae), intent(inout) :: model
        real(wp), intent(in) :: tout, rtol, h_max
        real(wp), intent(in) :: atol(:)   !! absolute tolerance per component of z
        integer, intent(in) :: max_steps
        logical, intent(in) :: land_on_tout
        real(wp), intent(out) :: zout(:)
        integer, intent(out) :: stat
        type(solution_monitor), intent(inout), optional :: monitor
        logical, intent(in), optional :: stop_when_stiff   !! return (success, stiff_detected) instead of failing
        logical, intent(in), optional :: stop_at_pass_end  !! return (success, pass_stop) at the step where the
                                                           !! monitor saw a singular interval end (zout: z there)
        logical, intent(in), optional :: stable_weights    !! after a start from a given step, keep the first
                                                           !! steps within the constraint modes' stable step
                                                           !! (constraint_mode_step; the automatic weights)
        logical, intent(in), optional :: stable_always     !! with stable_weights: every step within it
                                                           !! (a start at rest in an equilibrium)
        real(wp) :: h, e, fac, t_landing
        integer :: taken, n, energy_tries
        logical :: recoverable, cap, unresolved, hold

        n = size(self%z)
        cap = .false.
        if (present(stable_weights)) cap = stable_weights
        hold = .false.
        if (present(stable_always)) hold = stable_always
        stat = regdae_success
        self%stiff_detected = .false.
        self%pass_stop = .false.
        taken = 0
        energy_tries = 0
        do while (self%t < tout)
            if (taken >= max_steps) then
                call fail('max_steps steps taken before reaching tout')
                return
            end if
            h = self%h
            if (h_max > 0.0_wp) h = min(h, h_max)
            ! from a smooth restart the steps grow 5x per step, and one far beyond the stability
            ! of the constraint modes passes the error test while their amplitude is small, taken
            ! back only after it has grown: the crank after a pass check, a 0.55 s step at h |s| =
            ! 6.5 took the energy 1.4% off (doc/methods.md, "The stable step after a restart");
            ! after a start at rest in an equilibrium every step (the four-bar at its top: a 0.625 s
            ! step at h |s| = 7.8 grew the modes the damping's bias set off, and they fed the
            ! unstable one)
            if (cap .and. (self%restart_steps > 0 .or. hold)) h = min(h, constraint_mode_step(model%order, model%w))
            if (self%h_energy > 0.0_wp) h = min(h, self%h_energy)
            ! the monitor's predicted entry into a singular pass: the step ends there (not in
            ! the pass, whose layer its continuous extension would not follow)
            if (present(monitor)) then
                if (monitor%land_by > self%t + 0.1_wp*h .and. monitor%land_by < self%t + h) h = monitor%land_by - self%t
            end if
            if (land_on_tout .and. self%t + h > tout) h = tout - self%t
            if (land_on_tout .and. h <= 16*epsilon(1.0_wp)*max(1.0_wp, abs(self%t)) .and. h == tout - self%t) then
                ! tout within a few roundoffs of t: one Euler step with the slope at t
                ! (its error, h^2 |z''|, is far below the rounding of z).
                self%z = self%z + h*self%k1
                self%t = tout
                exit
            end if
            if (h <= 16*epsilon(1.0_wp)*max(1.0_wp, abs(self%t))) then
                call fail('step size too small (h = '//format_real(h)//')')
                return
            end if
            call self_step(h, e, stat, recoverable)
            if (stat /= regdae_success .and. .not. recoverable) then
                ! A smaller step cannot help: stop with the evaluation's own status.
                self%message = 'dopri5 at t = '//format_real(self%t)//': '//model%message
                zout = self%z
                return
            end if
            if (stat == regdae_success .and. e <= 1.0_wp) then
                ! Stiffness test (as in Hairer's DOPRI5): h rho, rho ~ |k7 - k6| / |z_new - z6|
                ! from the two stages at t + h, beyond the stability boundary (3.25) for
                ! 15 accepted steps without 6 quiet ones in between: the step size is
                ! limited by stability, and the error estimate no longer protects the result.
                if (stiff_step(h)) then
                    self%stiff_count = self%stiff_count + 1
                    self%quiet_count = 0
                    if (self%stiff_count >= 15) then
                        if (present(stop_when_stiff)) then
                            if (stop_when_stiff) then   ! the caller switches integrators at t
                                self%stiff_detected = .true.
                                self%stiff_count = 0
                                zout = self%z
                                return
                            end if
                        end if
                        call fail('the regularized system is stiff here (h |lambda| at the stability limit '// &
                                  'of the explicit method for 15 steps): use integrator=ida, or smaller gamma1, gamma0')
                        return
                    end if
                else
                    self%quiet_count = self%quiet_count + 1
                    if (self%quiet_count >= 6) self%stiff_count = 0
                end if
            end if
            if (stat /= regdae_success .or. .not. (e <= 1.0_wp)) then
                ! A rejected step, or a failed evaluation: retry smaller.
                self%rejects = self%rejects + 1
                fac = 0.2_wp
                if (stat == regdae_success .and. e == e) fac = max(0.2_wp, 0.9_wp*e**(-0.25_wp))
                self%h = h*fac
                stat = regdae_success
                cycle
            end if
            ! a long step whose work-energy balance the monitor cannot resolve is taken again at
            ! half the length (at most 3 times in a row), and the steps after it grow from there
            ! (the crank at th1 = 1.688, w1 = 0.1, rtol 1e-3: 0.26 s steps gained 60% of the energy,
            ! 0.23 rad; the four-bar across a fold: 0.5 J in a 0.44 s step, over the top)
            ! (a step still unresolved after that is taken: the monitor counts its quadrature
            ! estimate against the balance, not in its allowance)
            if (present(monitor)) then
                call monitor%step_energy(self%t + h, model, self%z_new, self%k7, unresolved)
                if (unresolved .and. energy_tries < 3) then
                    energy_tries = energy_tries + 1
                    self%energy_rejects = self%energy_rejects + 1
                    self%rejects = self%rejects + 1
                    self%h = 0.5_wp*h
                    self%h_energy = 0.5_wp*h
                    cycle
                end if
            end if
            energy_tries = 0
            if (self%h_energy > 0.0_wp) self%h_energy = 1.25_wp*self%h_energy
            self%t_old = self%t
            self%z_old = self%z
            self%k_old = self%k1
            self%t = self%t + h
            if (land_on_tout .and. abs(self%t - tout) <= 4*epsilon(1.0_wp)*max(1.0_wp, abs(tout))) self%t = tout
            self%z = self%z_new
            self%k1 = self%k7
            self%h_last = h
            self%restart_steps = max(0, self%restart_steps - 1)
            self%steps = self%steps + 1
            taken = taken + 1
            fac = 0.9_wp*max(e, 1.0e-10_wp)**(-0.2_wp)
            self%h = h*min(5.0_wp, max(0.2_wp, fac))
            if (present(monitor)) then
                call sample_step_end(self, model, monitor, stat, t_landing)
                if (stat /= regdae_success) then
                    self%message = 'dopri5 at t = '//format_real(self%t)//': '//model%message
                    zout = self%z
                    return
                end if
                if (t_landing > self%t_old) then
                    ! the step jumped into a singular pass: taken back, and again to the sample
                    ! found in the pass (the continuous extension of a step over a pass misses
                    ! its layer: the crank at th1 = 2.1, rtol 1e-4, 0.28 s steps, 19x the
                    ! oracle's error at the outputs)
                    self%t = self%t_old
                    self%z = self%z_old
                    self%k1 = self%k_old
                    self%steps = self%steps - 1
                    self%rejects = self%rejects + 1
                    taken = taken - 1
                    self%h = t_landing - self%t_old
                    self%dense_t = -huge(1.0_wp)
                    cycle
                end if
                if (self%layer%step(model%order, model%w, model%method, model%eps, monitor%sigma_last, &
                                    self%t_old, self%t)) then
                    monitor%unresolved_new = .true.   ! the front warns at tout (regdae_taylor_layer)
                    monitor%unresolved_message = self%layer%message
                end if
                if (monitor%model_changed) then   ! eps or weights changed: the first stage of the next step anew
                    monitor%model_changed = .false.
                    call slope(self, model, self%t, self%z, self%k1, stat, recoverable)
                    if (stat /= regdae_success) then
                        self%message = 'dopri5 at t = '//format_real(self%t)//': '//model%message
                        zout = self%z
                        return
                    end if
                end if
                if (monitor%project_due .and. self%t < tout) then
                    self%pass_stop = .true.
                    zout = self%z
                    return
                end if
                if (present(stop_at_pass_end)) then
                    if (stop_at_pass_end .and. monitor%pass_ended .and. self%t < tout) then
                        self%pass_stop = .true.
                        zout = self%z
                        return
                    end if
                end if
            end if
        end do
        if (tout >= self%t) then
            zout = self%z
        else
            call continuous_extension(self, tout, zout)
        end if
    contains
        subroutine self_step(h, err_norm, stat, recoverable)
            real(wp), intent(in) :: h
            real(wp), intent(out) :: err_norm
            integer, intent(out) :: stat
            logical, intent(out) :: recoverable
            real(wp) :: t
            t = self%t
            err_norm = huge(1.0_wp)
            ! Stage values in z_stage (whole-array expressions without temporaries).
            self%z_stage(:) = self%z + h*a21*self%k1
            call slope(self, model, t + c2*h, self%z_stage, self%k2, stat, recoverable)
            if (stat /= 0) return
            call stage_sum(n, 2, self%z, h, [a31, a32], self%k1, self%k2, self%k2, self%k2, self%k2, self%k2, &
                           self%z_stage)
            call slope(self, model, t + c3*h, self%z_stage, self%k3, stat, recoverable)
            if (stat /= 0) return
            call stage_sum(n, 3, self%z, h, [a41, a42, a43], self%k1, self%k2, self%k3, self%k3, self%k3, self%k3, &
                           self%z_stage)
            call slope(self, model, t + c4*h, self%z_stage, self%k4, stat, recoverable)
            if (stat /= 0) return
            call stage_sum(n, 4, self%z, h, [a51, a52, a53, a54], self%k1, self%k2, self%k3, self%k4, self%k4, &
                           self%k4, self%z_stage)
            call slope(self, model, t + c5*h, self%z_stage, self%k5, stat, recoverable)
            if (stat /= 0) return
            call stage_sum(n, 5, self%z, h, [a61, a62, a63, a64, a65], self%k1, self%k2, self%k3, self%k4, self%k5, &
                           self%k5, self%z_stage)
            call slope(self, model, t + h, self%z_stage, self%k6, stat, recoverable)
            if (stat /= 0) return
            call stage_sum(n, 5, self%z, h, [b1, b3, b4, b5, b6], self%k1, self%k3, self%k4, self%k5, self%k6, &
                           self%k6, self%z_new)
            call slope(self, model, t + h, self%z_new, self%k7, stat, recoverable)
            if (stat /= 0) return
            call stage_sum(n, -6, self%z, h, [e1, e3, e4, e5, e6, e7], self%k1, self%k3, self%k4, self%k5, self%k6, &
                           self%k7, self%work)
            err_norm = sqrt(sum((self%work/(atol + rtol*max(abs(self%z), abs(self%z_new))))**2)/n)
        end subroutine self_step

        logical function stiff_step(h)
            real(wp), intent(in) :: h
            real(wp) :: num, den
            num = norm2(self%k7 - self%k6)
            den = norm2(self%z_new - self%z_stage)   ! z_stage: the sixth stage's argument
            stiff_step = .false.
            if (den > 0.0_wp) stiff_step = (h*num > 3.25_wp*den)
        end function stiff_step

        subroutine fail(text)
            character(len=*), intent(in) :: text
            stat = regdae_err_integration
            self%message = 'dopri5 at t = '//format_real(self%t)//': '//text
            if (len(model%message) > 0) self%message = self%message//' | last evaluation failure: '//model%message
            zout = self%z
        end subroutine fail
    end subroutine rk_advance

    !> The 4th-order continuous extension (regdae_dopri_tableau) at tp on the last
    !! accepted step [t_old, t]: its stages k_old (first), k3 ... k6 and k1 (last)
    !! are intact until the next step.
    subroutine continuous_extension(self, tp, zp)
        class(rk_integrator), intent(inout) :: self
        real(wp), intent(in) :: tp
        real(wp), intent(out) :: zp(:)
        real(wp) :: hs, th
        integer :: i
        hs = self%t - self%t_old
        th = (tp - self%t_old)/hs
        if (self%dense_t /= self%t) then   ! once per step, for all its outputs
            do i = 1, size(self%z)
                self%dense_dz(i) = self%z(i) - self%z_old(i)
                self%dense_p(i) = hs*self%k_old(i) - self%dense_dz(i)
                self%dense_q(i) = self%dense_dz(i) - hs*self%k1(i) - self%dense_p(i)
                self%dense_r(i) = hs*(d1*self%k_old(i) + d3*self%k3(i) + d4*self%k4(i) + d5*self%k5(i) + &
                                      d6*self%k6(i) + d7*self%k1(i))
            end do
            self%dense_t = self%t
        end if
        do i = 1, size(self%z)
            zp(i) = self%z_old(i) + th*(self%dense_dz(i) + (1 - th)*(self%dense_p(i) + &
                    th*(self%dense_q(i) + (1 - th)*self%dense_r(i))))
        end do
    end subroutine continuous_extension

    ! The monitor's samples of an accepted step [t_old, t], so that a step does not
    ! jump over a singular pass unseen: where sigma_min(GB) may dip below the
    ! threshold inside the step, it is evaluated at the continuous extension (at most
    ! 4 points, one evaluation of the regularized model each); a point below the
    ! threshold becomes a sample (one slope), then the step's end is sampled (the
    ! model put back there by one slope if it moved; else it holds the end's
    ! evaluation, the first-same-as-last stage). The first point is the monitor's
    ! predicted entry into the pass (land_by) if it lies in the step; the next ones
    ! the vertex of the parabola through the lowest value known in and around the
    ! step and its neighbours in time, if it lies inside and the parabola's minimum
    ! is below 4x the threshold (sigma_min(GB) ~ distance^2 near a rank-one singular
    ! configuration); on the approach, and in a step longer than the motion's time
    ! scale (monitor%motion_time), also its quarter points.
    subroutine sample_step_end(self, model, monitor, stat, t_landing)
        class(rk_integrator), intent(inout) :: self
        type(regularized_dae), intent(inout) :: model
        type(solution_monitor), intent(inout) :: monitor
        integer, intent(out) :: stat
        real(wp), intent(out) :: t_landing   !! > t_old: a pass begins inside the step, at least a tenth of it
                                             !! in, at this time; nothing is sampled (the caller takes the
                                             !! step back and lands there)
        ! the probes' state and slope: allocated at the first probe (most steps have none)
        real(wp), allocatable :: z_probe(:), k_probe(:)
        real(wp) :: tp(9), sp(9), t_found, t_probe, sigma_end
        integer :: probes, known, quarter
        logical :: recoverable_probe, moved, approach
        stat = regdae_success
        probes = 0
        moved = .false.
        t_found = self%t_old
        ! the values known: the last two samples (when the last is the step's start) and the end
        known = 0
        if (self%t_seen(2) == self%t_old .and. self%sigma_seen(2) >= 0.0_wp) then
            if (self%sigma_seen(1) >= 0.0_wp .and. self%t_seen(1) < self%t_seen(2)) &
                call add(self%t_seen(1), self%sigma_seen(1))
            call add(self%t_seen(2), self%sigma_seen(2))
        end if
        sigma_end = model%sigma_min_gb()
        call add(self%t, sigma_end)
        ! a step that ends, or starts, on the approach (sigma below approach_factor x the
        ! threshold) may hold a whole pass between its samples (the crank from rest at th1 = 2.1,
        ! rtol 1e-4: a 0.28 s step over a 0.05 s pass, which neither the secant nor the parabola
        ! found): its quarter points are probed too
        approach = .false.
        if (known >= 2) approach = min(sp(known), sp(known - 1)) < approach_factor*monitor%threshold
        ! so may a step longer than the motion's time scale (the four-bar at rtol 1e-3: a 0.34 s step
        ! over a fold between sigma 1.9 and 0.96, unchecked, the energy 4% off)
        approach = approach .or. self%t - self%t_old > monitor%motion_time()
        quarter = 0
        if (known >= 2 .and. .not. monitor%in_singular .and. sp(known) >= monitor%threshold) then
            do while (probes < 7)
                t_probe = next_probe()
                if (.not. (t_probe > self%t_old .and. t_probe < self%t) .and. approach .and. quarter < 3) then
                    quarter = quarter + 1
                    t_probe = self%t_old + 0.25_wp*quarter*(self%t - self%t_old)
                end if
                if (.not. (t_probe > self%t_old .and. t_probe < self%t)) exit
                if (.not. allocated(z_probe)) allocate (z_probe(size(self%z)), k_probe(size(self%z)))
                call continuous_extension(self, t_probe, z_probe)
                call model%evaluate(t_probe, z_probe, stat, recoverable_probe)
                probes = probes + 1
                moved = .true.
                if (stat /= regdae_success) exit
                call add(t_probe, model%sigma_min_gb())
                if (sp(known) < monitor%threshold) then
                    t_found = t_probe
                    exit
                end if
            end do
        end if
        stat = regdae_success
        t_landing = self%t_old
        if (t_found > self%t_old + 0.1_wp*(self%t - self%t_old)) then
            t_landing = t_found
            return
        end if
        if (t_found > self%t_old) then   ! a sample inside the pass
            call continuous_extension(self, t_found, z_probe)
            call slope(self, model, t_found, z_probe, k_probe, stat, recoverable_probe)
            if (stat == regdae_success) then
                call monitor%sample(t_found, model, z_probe, k_probe)
                call remember(self, t_found, monitor%sigma_last)
            end if
        end if
        if (moved) then
            call slope(self, model, self%t, self%z, k_probe, stat, recoverable_probe)
            if (stat /= regdae_success) return
            call monitor%sample(self%t, model, self%z, self%k1)
        else   ! the model still at the step's end, as sigma_end was taken: not computed again
            call monitor%sample(self%t, model, self%z, self%k1, sigma_now=sigma_end)
        end if
        call remember(self, self%t, monitor%sigma_last)
    contains
        subroutine add(t_point, sigma_point)
            real(wp), intent(in) :: t_point, sigma_point
            if (known == size(tp)) return
            known = known + 1
            tp(known) = t_point
            sp(known) = sigma_point
        end subroutine add

        ! land_by first; then the vertex of the parabola through the lowest value and
        ! its neighbours in time (t_old: none)
        real(wp) function next_probe() result(t_next)
            real(wp) :: ta, tb, tc, sa, sb, sc, d1, d2, curvature, lowest
            integer :: order(9), a, b, k
            t_next = self%t_old
            if (probes == 0 .and. monitor%land_by > self%t_old .and. monitor%land_by < self%t) then
                t_next = monitor%land_by
                return
            end if
            if (known < 3) return
            do k = 1, known
                order(k) = k
            end do
            do a = 2, known   ! by time (insertion sort of at most 9)
                k = order(a)
                b = a - 1
                do while (b >= 1)
                    if (tp(order(b)) <= tp(k)) exit
                    order(b + 1) = order(b)
                    b = b - 1
                end do
                order(b + 1) = k
            end do
            b = minloc(sp(order(1:known)), 1)
            b = min(max(b, 2), known - 1)
            ta = tp(order(b - 1))
            tb = tp(order(b))
            tc = tp(order(b + 1))
            sa = sp(order(b - 1))
            sb = sp(order(b))
            sc = sp(order(b + 1))
            if (.not. (ta < tb .and. tb < tc)) return
            d1 = (sb - sa)/(tb - ta)
            d2 = (sc - sb)/(tc - tb)
            curvature = (d2 - d1)/(tc - ta)
            if (.not. (curvature > 0.0_wp)) return
            t_next = 0.5_wp*(tb + tc) - 0.5_wp*d2/curvature
            lowest = sc + (t_next - tc)*(d2 + curvature*(t_next - tb))
            ! 4x: far from the pass sigma_min(GB) is not a parabola in t (measured: the
            ! slider crank's first pass at rtol 1e-3 predicted 0.089 for a threshold 0.05)
            if (.not. (lowest < 4.0_wp*monitor%threshold)) t_next = self%t_old
        end function next_probe
    end subroutine sample_step_end

    ! out = z + h*(c(1) k1 + ... + c(terms) k_terms) (terms = 2 ... 5), or out = h*(c(1) k1 + ...
    ! + c(6) k6) (terms = -6: the error estimate's), each entry's sum from the left as the
    ! whole-array expressions it replaces (the same numbers); the unused k's are any array.
    ! By loops over explicit shapes: a third of the explicit method's own instructions on the
    ! car axis went to those expressions on the integrator's components.
    pure subroutine stage_sum(n, terms, z, h, c, k1, k2, k3, k4, k5, k6, out)
        integer, intent(in) :: n, terms
        real(wp), intent(in) :: z(n), h, c(:), k1(n), k2(n), k3(n), k4(n), k5(n), k6(n)
        real(wp), intent(out) :: out(n)
        integer :: i
        select case (terms)
        case (2)
            do i = 1, n
                out(i) = z(i) + h*(c(1)*k1(i) + c(2)*k2(i))
            end do
        case (3)
            do i = 1, n
                out(i) = z(i) + h*(c(1)*k1(i) + c(2)*k2(i) + c(3)*k3(i))
            end do
        case (4)
            do i = 1, n
                out(i) = z(i) + h*(c(1)*k1(i) + c(2)*k2(i) + c(3)*k3(i) + c(4)*k4(i))
            end do
        case (5)
            do i = 1, n
                out(i) = z(i) + h*(c(1)*k1(i) + c(2)*k2(i) + c(3)*k3(i) + c(4)*k4(i) + c(5)*k5(i))
            end do
        case default
            do i = 1, n
                out(i) = h*(c(1)*k1(i) + c(2)*k2(i) + c(3)*k3(i) + c(4)*k4(i) + c(5)*k5(i) + c(6)*k6(i))
            end do
        end select
    end subroutine stage_sum

    ! The monitor's last two samples, for sample_step_end.
    subroutine remember(self, t_sample, sigma_sample)
        class(rk_integrator), intent(inout) :: self
        real(wp), intent(in) :: t_sample, sigma_sample
        self%t_seen(1) = self%t_seen(2)
        self%sigma_seen(1) = self%sigma_seen(2)
        self%t_seen(2) = t_sample
        self%sigma_seen(2) = sigma_sample
    end subroutine remember

end module regdae_explicit_rk
