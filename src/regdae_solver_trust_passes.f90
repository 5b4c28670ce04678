!> The pass check of `regdae_solver_trust` (its header describes it): the ladder of companions
!! at rtol/kappa^k started from the checkpoint before a pass and brought to each output, the
!! eps probes of the regularization error, the verdict against `pass_tol`, the restart of the
!! solution from the answer's level, and the companions' step budget.
submodule (regdae_solver_trust) regdae_solver_trust_passes
    implicit none

contains

    ! The pass check at time t (the engine's current time; a pass is going on, or
    ! ended there if `ended`): the ladder started or continued from the
    ! checkpoint, its levels brought to t, the answer level's values into the
    ! outputs; at the end of the pass the engine continues from the answer.
    module subroutine check_pass(self, t, ended, x, y, v, a, warn, warn_text, pending)
        type(regdae_solver), intent(inout) :: self
        real(wp), intent(in) :: t
        logical, intent(in) :: ended
        real(wp), intent(inout) :: x(:)
        real(wp), intent(inout), optional :: y(:), v(:), a(:)
        integer, intent(inout) :: warn
        character(len=:), allocatable, intent(inout) :: warn_text
        logical, intent(inout) :: pending
        integer :: k, n, answer, adopt, lstat
        real(wp) :: tc
        real(wp), allocatable :: zc(:)
        logical :: frozen, valid, agreed
        character(len=:), allocatable :: text
        n = self%main%state_size()
        associate (lad => self%ladder)
            if (.not. lad%active) then
                call self%main%checkpoint(tc, frozen, valid, zc)
                lad%active = .true.
                lad%warned = .false.
                lad%regularized = .false.
                lad%outputs_warned = .false.
                lad%step_end = -huge(1.0_wp)
                lad%prev_level = max_levels + 1
                lad%output_level = max_levels + 1
                lad%over_budget = 0
                lad%dead_level = max_levels + 1
                lad%probes_failed = .false.
                lad%fine_probes = .false.
                lad%levels = 0
                lad%t_start = tc
                lad%z_start = zc
                call self%main%project_start(tc, lad%z_start)   ! once for all the pass's companions
                if (allocated(lad%z)) deallocate (lad%z)
                allocate (lad%z(n, 0:max_levels))
                lad%d = 0.0_wp
            end if
            call self%main%state(lad%z(:, 0))
            answer = -1
            ! a level that failed or ran out of its budget in this pass is not started again from
            ! the pass's start at the next output (measured: the crank with gamma0 = 5e15 at rtol
            ! 1e-7, the companion at rtol/10 restarted at each of 10 outputs, 6.8M steps)
            do k = 1, min(self%max_level, lad%dead_level - 1)
                if (k > lad%levels) then
                    allocate (lad%level(k)%engine)
                    lad%levels = k
                    call self%main%start_companion(lad%level(k)%engine, kappa**k, lad%t_start, lad%z_start, lstat, &
                                                   projected=.true.)
                    if (lstat < 0) then
                        lad%dead_level = k
                        call retire(self, k)
                        exit
                    end if
                end if
                call lad%level(k)%engine%limit_steps(step_budget(self, lad%level(k)%engine, k, t))
                call bring_to(lad%level(k)%engine, t, lad%z(:, k), lstat)
                if (lstat < 0) then   ! this level cannot go on: the pass is not verified beyond k-1
                    if (lstat == regdae_err_integration) lad%over_budget = k
                    lad%dead_level = k
                    call retire(self, k)
                    exit
                end if
                lad%d(k) = self%main%state_distance(lad%z(:, k - 1), lad%z(:, k))
                if (k == 1) self%pass_error = max(self%pass_error, lad%d(1))
                if (lad%d(k) <= self%pass_tol) then
                    answer = k - 1
                    exit
                end if
            end do
            agreed = (answer >= 0)
            ! no agreement: the finest level that ran; without a regularization (eps = 0,
            ! Baumgarte) the levels' branches at a bifurcation are chance, and the solution
            ! keeps its own (measured: the crank with Baumgarte's weights 1e6 at rtol 1e-9,
            ! the finest level off the branch)
            ! (the pass's layer, also where the solution went on from a level inside it)
            lad%regularized = lad%regularized .or. self%main%regularized()
            if (.not. agreed) answer = merge(lad%levels, 0, lad%regularized)
            if (agreed .and. answer < lad%levels) then
                ! the answer and the next level share the eps floor: probes at 10 and 100 eps tell
                ! whether the regularization error is within the tolerance: first at the answer's
                ! tolerance (against x(eps) at that tolerance from the same start); where those
                ! find it above pass_tol, at the next level's tolerance (where the integration
                ! error is 10 times smaller), which give the verdict for the rest of the pass
                if (self%main%eps_floored(kappa**answer, kappa**(answer + 1))) then
                    if (.not. lad%fine_probes) then
                        call probe_regularization(self, t, answer, lstat)
                        if (lstat == regdae_success .and. lad%d_probe > self%pass_tol) then
                            lad%fine_probes = .true.
                            call retire_probe(self)
                        end if
                    end if
                    if (lad%fine_probes) call probe_regularization(self, t, answer + 1, lstat)
                    if (lstat == regdae_success .and. lad%d_probe > self%pass_tol) agreed = .false.
                end if
            end if
            ! The outputs and the state the run goes on from: the finer level of the agreeing
            ! pair (level answer + 1, already at t: local extrapolation, as an embedded pair
            ! goes on from its higher order), so that the passes' errors, each within pass_tol
            ! for the answer, do not add up over many passes at the answer's size.
            adopt = merge(min(answer + 1, lad%levels), answer, agreed)
            if (adopt > 0) then
                call lad%level(adopt)%engine%advance(t, x, y, lstat, v, a)
                ! (y and a are the level's: so is a warning that the multiplier is undefined)
                if (pending .and. lstat > 0 .and. warn == regdae_success) then
                    warn = lstat
                    warn_text = lad%level(adopt)%engine%message()
                end if
                pending = .false.
            end if
            ! the solution itself farther from level 1 than a finer tolerance moves a state (another
            ! branch, or caught at the fold: the pass does not end, and the outputs would come from
            ! a companion without checks of its own to the end): it goes on from the adopted level
            ! now (fourbar seed=77 cell 107, index 2: 1.2e6 error weights at t = 1.85, the solution
            ! stuck at th1 = 2 pi to t = 5 while a companion's outputs left the branch at t = 3)
            if (.not. ended .and. adopt > 0 .and. lad%d(1) > branch_gap*self%pass_tol) then
                call self%main%restart_at(t, lad%z(:, adopt), lstat)
                call self%main%note_event('t = '//format_real(t)//': the solution differed from the pass''s '// &
                                          'level at rtol/10 by '//format_real(lad%d(1))//' error weights: '// &
                                          'it goes on from the level''s state')
            end if
            if (.not. agreed .and. .not. lad%warned) then
                lad%warned = .true.
                text = 'the singular pass after t = '//format_real(lad%t_start)//' is not resolved to the '// &
                       'tolerance at t = '//format_real(t)//': '
                if (lad%levels > 0) then
                    text = text//'re-integrated at rtol/10^k, consecutive levels differ by'
                    do k = 1, lad%levels
                        text = text//' '//format_real(lad%d(k))
                    end do
                    text = text//' error weights (> pass_tol = '//format_real(self%pass_tol)//')'
                else
                    text = text//'no re-integration at rtol/10 reached it'
                end if
                if (lad%over_budget > 0) text = text//'; the level at rtol/'//format_real(kappa**lad%over_budget)// &
                    ' failed or exceeded its step budget (50 times the solution''s step density)'
                if (lad%probe_level == answer .or. lad%probe_level == answer + 1) then
                    text = text//'; the regularization error at its eps is about '//format_real(lad%d_probe)// &
                           ' (10 eps moves x by '//format_real(lad%d_probes(1))
                    if (lad%d_probes(2) >= 0.0_wp) text = text//', 100 eps by '//format_real(lad%d_probes(2))//' more'
                    text = text//')'
                end if
                if (adopt > 0) then
                    text = text//'; x is the level''s at rtol/'//format_real(kappa**adopt)
                else if (lad%levels == 0) then
                    text = text//'; x is the solution''s own'
                else
                    text = text//'; x is the solution''s own (no regularization: the levels'' branches are chance)'
                end if
                text = text//'; a smaller rtol, or another eps, may resolve it; pass_check=no skips this check'
                call warn_unresolved(self, t, text, warn, warn_text)
            end if
            ! Outputs returned earlier from inside one step of the solution (interpolated), from a
            ! level that this check, in that step or the first one after it, finds off: the check at
            ! those outputs could not see it (levels 0 and 1 agreed, both off alike: a Dormand-Prince
            ! step over the singular point, the outputs inside it from its continuous extension;
            ! linear seed=2026 cell 97, S2 at rtol 1e-3: 10.9 error weights at t = -0.62 with levels
            ! 0 and 1 2.5 apart, at t = -0.61, after the step's end, levels 1 and 2 8.5 apart).
            ! Warned. Outputs at step ends and of earlier steps are not: the levels' difference at a
            ! singular point says nothing of them (ex51 direct with stop_at_output at t = 0).
            if (self%main%integrator_time() /= lad%step_end) then   ! a new step since the last output
                lad%step_end = self%main%integrator_time()
                lad%prev_level = lad%output_level
                lad%prev_output = lad%t_output
                lad%output_level = max_levels + 1
            end if
            if (lad%prev_level < lad%output_level) then
                lad%output_level = lad%prev_level
                lad%t_output = lad%prev_output
            end if
            lad%prev_level = max_levels + 1
            if (agreed .and. lad%output_level < answer .and. .not. lad%outputs_warned) then
                lad%outputs_warned = .true.   ! (a later disagreement of the levels still warns)
                text = 'the singular pass after t = '//format_real(lad%t_start)//': outputs from t = '// &
                       format_real(lad%t_output)//' on came from the level at rtol/'// &
                       format_real(kappa**lad%output_level)//', which at t = '//format_real(t)// &
                       ' differs from the next finer level by '//format_real(lad%d(lad%output_level + 1))// &
                       ' error weights (> pass_tol = '//format_real(self%pass_tol)//'): those outputs may be '// &
                       'off by as much; a smaller rtol, or stop_at_output=yes, may resolve it'
                call warn_unresolved(self, t, text, warn, warn_text)
            end if
            if (.not. ended .and. adopt < lad%output_level .and. lad%step_end > t) then
                lad%output_level = adopt
                lad%t_output = t
            end if
            if (.not. ended) return
            ! the end of the pass: the engine goes on from the answer's state
            self%pass_checks = self%pass_checks + 1
            if (adopt > 0) call self%main%restart_at(t, lad%z(:, adopt), lstat)
            if (answer > 0) then
                if (agreed) then
                    self%passes_resolved = self%passes_resolved + 1
                    call self%main%note_event('t = '//format_real(t)//': the singular pass after t = '// &
                                              format_real(lad%t_start)//' resolved at rtol/'// &
                                              format_real(kappa**answer)//' (the solution differed by '// &
                                              format_real(lad%d(1))//' error weights); the run goes on from there')
                end if
            end if
            call self%main%release_checkpoint(t, lad%z(:, adopt))
            call retire(self, 1)
            call retire_probe(self)
            lad%active = .false.
        end associate
    end subroutine check_pass

    ! A pass not resolved at t: logged, counted, and the call's warning (the first one of the call).
    subroutine warn_unresolved(self, t, text, warn, warn_text)
        type(regdae_solver), intent(inout) :: self
        real(wp), intent(in) :: t
        character(len=*), intent(in) :: text
        integer, intent(inout) :: warn
        character(len=:), allocatable, intent(inout) :: warn_text
        self%passes_unresolved = self%passes_unresolved + 1
        call self%main%note_event('t = '//format_real(t)//': unresolved: '//text)
        if (warn /= regdae_success) return
        warn = regdae_warn_unresolved
        warn_text = text
    end subroutine warn_unresolved

    ! The eps probes at the tolerance of level `level` (started from the checkpoint if they are
    ! not running for that level) brought to t: the regularization error at the level's eps,
    ! estimated from x(eps), x(10 eps), x(100 eps) for an error C eps^p (p from the ratio of the
    ! two changes d1, d2: 10^p = d2/d1, the error d1/(10^p - 1); where the changes do not shrink
    ! by 1.3 at least, 4 d1, the error of p = 0.1), in lad%d_probe. x(eps) is the level's own
    ! (level >= 1: a companion from the same checkpoint) or, for level 0 (the solution, which did
    ! not start from the checkpoint), the reference probe probe(0) at eps: the probes then differ
    ! from it by the regularization and not by the restart. Every estimate is at most 4 d1: where
    ! 4 d1 is within pass_tol, the 100 eps probe cannot change the verdict and is not run
    ! (d_probe = 4 d1; d_probes(2) = -1). ex52 (paper case, 1000 outputs): the same outputs, the
    ! solve 40.6M -> 32.6M instructions at rtol 1e-8, 22.9M -> 20.5M at 1e-7 (callgrind).
    subroutine probe_regularization(self, t, level, stat)
        type(regdae_solver), intent(inout) :: self
        real(wp), intent(in) :: t
        integer, intent(in) :: level
        integer, intent(out) :: stat
        real(wp), allocatable :: zp(:, :)
        real(wp) :: ratio
        integer :: j
        allocate (zp(self%main%state_size(), 0:2))
        associate (lad => self%ladder)
            stat = regdae_err_integration
            if (lad%probes_failed) return   ! not started again from the pass's start at each output
            if (lad%probe_level /= level) call retire_probe(self)
            lad%probe_level = level
            if (level > 0) zp(:, 0) = lad%z(:, level)
            do j = merge(1, 0, level > 0), 2
                if (.not. associated(lad%probe(j)%engine)) then
                    allocate (lad%probe(j)%engine)
                    call self%main%start_companion(lad%probe(j)%engine, kappa**level, lad%t_start, lad%z_start, &
                                                   stat, eps_scale=eps_probe**j, projected=.true.)
                    if (stat < 0) then
                        lad%probes_failed = .true.
                        call retire_probe(self)
                        return
                    end if
                end if
                call lad%probe(j)%engine%limit_steps(step_budget(self, lad%probe(j)%engine, level, t))
                call bring_to(lad%probe(j)%engine, t, zp(:, j), stat)
                if (stat < 0) then
                    lad%probes_failed = .true.
                    call retire_probe(self)
                    return
                end if
                if (j == 1) then
                    lad%d_probes(1) = self%main%state_distance(zp(:, 0), zp(:, 1))
                    if (4.0_wp*lad%d_probes(1) <= self%pass_tol) then
                        lad%d_probe = 4.0_wp*lad%d_probes(1)
                        lad%d_probes(2) = -1.0_wp
                        return
                    end if
                end if
            end do
            lad%d_probes(2) = self%main%state_distance(zp(:, 1), zp(:, 2))
            ratio = lad%d_probes(2)/max(lad%d_probes(1), tiny(1.0_wp))
            if (ratio >= 1.3_wp) then
                lad%d_probe = lad%d_probes(1)/(ratio - 1.0_wp)
            else
                lad%d_probe = 4.0_wp*lad%d_probes(1)
            end if
        end associate
    end subroutine probe_regularization

    module subroutine retire_probe(self)
        type(regdae_solver), intent(inout) :: self
        type(solver_engine), pointer :: engine
        integer :: j
        self%ladder%probe_level = -1
        do j = 0, 2
            engine => self%ladder%probe(j)%engine
            if (.not. associated(engine)) cycle
            self%retired_steps = self%retired_steps + engine%steps_taken()
            call engine%destroy()
            deallocate (engine)
            self%ladder%probe(j)%engine => null()
        end do
    end subroutine retire_probe

    ! Bring a companion to time t (if it is behind) and read its state.
    subroutine bring_to(engine, t, z, stat)
        type(solver_engine), intent(inout) :: engine
        real(wp), intent(in) :: t
        real(wp), intent(out) :: z(:)
        integer, intent(out) :: stat
        real(wp), allocatable :: xk(:)
        stat = regdae_success
        if (engine%time() < t) then
            allocate (xk(engine%x_size()))
            do while (engine%time() < t)   ! a companion stops at its own pass ends only if asked: once
                call engine%advance(t, xk, stat=stat)
                if (stat < 0) return
            end do
        end if
        call engine%state(z)
    end subroutine bring_to

    ! The steps a companion at rtol/kappa^level may still take on its way to t: over the pass
    ! (from its start, the checkpoint at t_start, to t) 1000 plus 50 times what the solution's
    ! mean step density since t0 gives it at that level (steps grow like 10^(1/5) per decade of
    ! the tolerance for a method of order 4 or 5), less the steps it has taken. Counted from the
    ! pass's start, not per call: a pass checked at many outputs does not get the floor of 1000
    ! at each. A pass that takes the companions far more steps (Baumgarte's weights 1e6 through
    ! an unregularized singularity at rtol 1e-10: 667,000 steps of the companions against 11,857
    ! of the solution) is reported unresolved instead.
    integer function step_budget(self, engine, level, t) result(steps)
        type(regdae_solver), intent(in) :: self
        type(solver_engine), intent(in) :: engine
        integer, intent(in) :: level
        real(wp), intent(in) :: t
        real(wp) :: density, allowed
        ! (the step counts alone: statistics() twice per companion and output cost 0.10M instructions
        ! of ex52's solve at rtol 1e-8)
        density = real(self%main%steps_taken(), wp)/max(self%main%time() - self%t0, tiny(1.0_wp))
        allowed = 1000.0_wp + 50.0_wp*10.0_wp**(0.2_wp*level)*density*max(t - self%ladder%t_start, 0.0_wp)
        steps = int(max(1.0_wp, min(allowed - real(engine%steps_taken(), wp), 1.0e9_wp)))
    end function step_budget

    ! Destroy level k of the ladder (the levels above it too), keeping their step counts.
    module subroutine retire(self, k)
        type(regdae_solver), intent(inout) :: self
        integer, intent(in) :: k
        type(solver_engine), pointer :: engine
        integer :: j
        do j = self%ladder%levels, k, -1
            engine => self%ladder%level(j)%engine   ! (through a local pointer: gfortran 12's -fcheck
            if (.not. associated(engine)) cycle     ! build fails on the component's deallocate)
            self%retired_steps = self%retired_steps + engine%steps_taken()
            call engine%destroy()
            deallocate (engine)
            self%ladder%level(j)%engine => null()
        end do
        self%ladder%levels = min(self%ladder%levels, k - 1)
    end subroutine retire

end submodule regdae_solver_trust_passes
