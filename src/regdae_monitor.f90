!> Diagnostics sampled along the computed solution: sigma_min(GB) and the
!! singular intervals (runs of consecutive samples with sigma_min(GB) below a
!! threshold), and the velocity jump across each singular interval. A sample
!! reads the regularized model's last evaluation, so it costs nothing when that
!! evaluation was made at a point of the solution anyway (dopri5: the end of each
!! accepted step). An implicit integrator evaluates the model for it; it takes the
!! full sample only where `full_sample_due` (a singular interval may be near) and
!! elsewhere feeds the work-energy balance alone (`sample_work`).
!!
!! Velocity jump: on the physical branch the velocity v = x' of a problem of
!! order >= 2 is continuous through a singular configuration, v' = a with
!! bounded, smooth accelerations (the regularization damps the multiplier there);
!! changing branch turns v by an impulse inside the interval. Between the last
!! regular sample before an interval (t_a, v_a, a_a) and the first one after it (t_b, ...),
!! regular meaning sigma_min(GB) >= max(threshold, 3 sqrt(eps)), outside the
!! regularization layer too (where the damped multiplier lets the motion run free),
!! $$ J = \frac{|v_b - v_a - \tfrac{t_b - t_a}{2}(a_a + a_b)|}
!!           {\max(|v_a|, |v_b|, (t_b - t_a)\max(|a_a|, |a_b|))}, $$
!! the relative defect of the trapezoidal rule for v' = a across the interval;
!! J > jump_tol raises the alarm (`alarm_kind = alarm_jump`). The slopes a are the integrator's own (IDA's
!! interpolated z', dopri5's last stage), not recomputed from the regularized
!! equation at interpolated states, so they are as accurate as the states.
!!
!! Position drift: for a problem of order >= 2 the monitor also records
!! max |g(x, t)| over the samples; above drift_tol it raises the alarm
!! (`alarm_kind = alarm_drift`). With index=2 nothing enforces g = 0 and the
!! drift is what lets the solution slip to another branch at the next pass.
!!
!! Invariant: if the problem supplies an invariant I(x, v, t) (e.g. the energy
!! of a conservative mechanism) and invariant_tol > 0, |I - I(t0)| above
!! invariant_tol raises the alarm (`alarm_kind = alarm_invariant`).
!!
!! Work-energy balance (mechanical problems, regdae_work_energy): D = T - T(t0) - W,
!! W the quadrature of the power P over the samples (`parabola_work`; an interval whose
!! estimate is not small against the allowance by `interval_work` on the integrator's motion
!! inside it), against work_tol S plus the quadratures' estimates and the energy the state's
!! tolerance leaves open (`alarm_kind = alarm_work`); tested outside the regularization layers
!! (the damped multiplier exchanges energy with the motion there for a moment). A pass check's
!! new start (`rebase_work`) closes a stretch: its defect at its last tested sample is carried, and
!! once the carried defects plus the open stretch's exceed work_tol S plus the quadratures'
!! estimates and 3 times the root of the defects' squares (a drift through the passes, not a random
!! walk), the monitor warns once (`unresolved_new`, regdae_warn_unresolved); the run goes on.
!!
!! Resolution (problems of order 1 and 2, dense formulations): the constraint
!! residual g of the integrated solution, made at each step at the scale of the
!! constraint's conditioning sigma_G = min_i |G_i| (sigma_min(G) for one
!! constraint) and damped by the stabilization only at its rate (gamma at index
!! 2; the slower root of s^2 + gamma1 s + gamma0 at index 3), stands for an error
!! in x of g / sigma_G. On the approach to a singular configuration sigma_G falls
!! faster than the stabilization forgets the residual made further back, so the
!! integration errors of the approach are amplified in x by about
!! R = max_k sigma_G(t_k) exp(-rate (t - t_k)) / sigma_G(t), which the error test,
!! local to each step, cannot see. R is taken at the samples of a singular
!! interval before it enters the layer where the damping acts (sigma_min(GB)^2 <
!! 100 eps; direct: sigma_min(GB) < 100 eps), recorded (`resolution_ratio`), and
!! R > resolution_tol counts the pass as unresolved (`unresolved`, and
!! `unresolved_new` for the solver to warn with regdae_warn_unresolved): x near
!! the pass may carry about R times the tolerance in integration error, and a
!! tighter rtol (or a larger eps) changes it.
module regdae_monitor
    use regdae_kinds, only: wp
    use regdae_format, only: format_real, format_int
    use regdae_regularization, only: regularized_dae
    use regdae_options, only: option_auto, method_direct, method_baumgarte
    use regdae_scales, only: running_scales
    use regdae_auto_rules, only: weight_rule, dense_motion_scales, baumgarte_weights
    use regdae_mechanical_problem, only: mechanical_problem
    use regdae_sparsity, only: sparsity_pattern
    use regdae_work_energy, only: interval_work, parabola_work, state_energy_tolerance => tolerance_energy
    implicit none
    private

    public :: forgetting_rate

    integer, parameter, public :: alarm_none = 0, alarm_jump = 1, alarm_drift = 2, alarm_invariant = 3, alarm_work = 4
    !> The approach to a singular pass begins where sigma_min(GB) falls below this
    !! many times the singular threshold: the checkpoint a pass is re-integrated from.
    real(wp), parameter, public :: approach_factor = 5.0_wp
    !> The checkpoint a pass is re-integrated from: the last sample where sigma_min(GB) was
    !! at least this many times the singular threshold.
    real(wp), parameter, public :: checkpoint_factor = 2.0_wp
    !> An implicit integrator's step end needs the full sample while sigma_min(GB) at the last
    !! one is below this many times the singular threshold (and the regularization layer's).
    real(wp), parameter, public :: near_factor = 10.0_wp
    !> Far from a singular interval, full samples at most this fraction of the motion's time
    !! scale apart (`motion_time`).
    real(wp), parameter, public :: far_gap = 0.25_wp
    !> The work-energy balance refines an interval whose quadrature estimate is above this x work_tol S.
    real(wp), parameter, public :: work_refine = 0.1_wp
    !> A long explicit step whose energy defect plus the quadrature's estimate exceeds this many times
    !! the energy the tolerance leaves open at its end is unresolved (`step_energy`).
    real(wp), parameter, public :: step_energy_factor = 3.0_wp
    !> sigma_min(GB) risen this many times above a fold's minimum: that fold is passed.
    real(wp), parameter, public :: fold_factor = 10.0_wp
    !> A fold's residual counts until the stabilization has forgotten all but e^-fold_memory of it.
    real(wp), parameter, public :: fold_memory = 4.0_wp

    !> The sampled diagnostics of one solver.
    type, public :: solution_monitor
        real(wp) :: threshold = 0.05_wp          !! sigma_min(GB) below this marks a singular sample
        logical :: relative = .false.            !! threshold = 0.05 times the running maximum of sigma_min(GB)
        real(wp) :: sigma_last = huge(1.0_wp)    !! sigma_min(GB) at the last sample
        real(wp) :: sigma_min = huge(1.0_wp)     !! smallest sigma_min(GB) over the samples
        integer :: n_singular = 0                !! singular intervals so far
        logical :: in_singular = .false.         !! the last sample was singular
        real(wp), allocatable :: singular(:, :)  !! (2, n_singular): first and last sample time of each
        integer :: np = 0                        !! positions whose velocity is checked (0: no check)
        real(wp) :: jump_tol = 0.1_wp            !! alarm when the relative jump J exceeds this
        real(wp) :: jump_max = 0.0_wp            !! largest J so far
        real(wp) :: drift_tol = 0.0_wp           !! alarm when max |g| exceeds this (0: no check)
        real(wp) :: drift_max = 0.0_wp           !! largest max |g(x, t)| so far
        real(wp) :: invariant_tol = 0.0_wp       !! alarm when |I - I(t0)| exceeds this (0: no check)
        real(wp) :: invariant0 = 0.0_wp          !! I(t0)
        real(wp) :: invariant_change = 0.0_wp    !! largest |I - I(t0)| so far
        real(wp) :: work_tol = 0.0_wp            !! alarm when |D| > work_tol S (0: no check)
        real(wp) :: work_defect = 0.0_wp         !! largest |D| / S so far
        real(wp) :: work_floor = 0.0_wp          !! the smallest energy scale S (set after reset)
        real(wp) :: work_rate = 0.0_wp           !! the rate of the motion (1/time; set after reset): a
                                                 !! quadrature step longer than 0.3/work_rate is a long one
        type(running_scales) :: scales           !! the problem's scales seen so far (automatic eps, drift bound)
        type(weight_rule) :: weights             !! the automatic Baumgarte weights along the run
        integer :: weight_nx = 0                 !! dense models: the size of x (for the weights' rate)
        logical :: weight_order2 = .false.       !! dense models: z = (x, v, ...)
        logical :: weights_new = .false.         !! the weights changed since the flag was last cleared
        character(len=:), allocatable :: weights_message   !! the last change: where and to what
        logical :: drift_auto = .false.          !! drift_tol follows scales%drift_bound()
        real(wp) :: land_by = huge(1.0_wp)       !! sigma_min(GB) falls towards the threshold: a sample by this
                                                 !! time lands inside the coming singular interval (the secant
                                                 !! of the last two samples reaching threshold/2; huge: none).
                                                 !! An explicit integrator ends its next step there at the latest,
                                                 !! so that its steps do not jump over a singular pass.
        logical :: model_changed = .false.       !! the last sample raised the model's eps (an explicit
                                                 !! integrator must re-evaluate its slope)
        real(wp) :: resolution_tol = 0.0_wp      !! R above this counts a pass as unresolved (0: no check)
        real(wp) :: resolution_ratio = 0.0_wp    !! largest amplification R on an approach so far
        integer :: unresolved = 0                !! singular intervals whose approach had R > resolution_tol
        logical :: unresolved_new = .false.      !! a new unresolved interval since the flag was last cleared
        character(len=:), allocatable :: unresolved_message   !! where and how much (the last one)
        logical :: pass_ended = .false.          !! a singular interval ended at the last sample (cleared by the caller)
        logical :: project_on = .false.          !! the front projects the solution where `project_due` (the integrators stop)
        logical :: project_due = .false.         !! another fold lies ahead inside the singular interval: project the state
        real(wp) :: fold_rate = 0.0_wp           !! the rate at which the stabilization forgets a constraint residual
        real(wp), private :: fold_low = huge(1.0_wp)   ! the smallest sigma_min(GB) of the last fold's dip
        real(wp), private :: t_fold = 0.0_wp             ! its time
        real(wp), private :: fold_peak = 0.0_wp         ! the largest sigma_min(GB) since it rose fold_factor times above
                                                         ! fold_low (0: not risen)
        ! The checkpoint before a singular pass (regdae_solver_trust re-integrates the pass
        ! from it): the last sample with sigma_min(GB) >= checkpoint_factor x the threshold
        ! before the pass, frozen from the pass's first sample until released.
        real(wp), allocatable :: checkpoint_z(:) !! the state there
        real(wp) :: checkpoint_t = 0.0_wp        !! its time
        logical :: checkpoint_frozen = .false.   !! a pass began since the checkpoint
        logical :: checkpoint_valid = .false.    !! a checkpoint exists
        logical :: defer_in_pass = .false.       !! a pass check is on: an alarm inside a pass (checkpoint
                                                 !! frozen) does not stop the run; the pass check decides
        integer :: deferred_alarms = 0           !! alarms inside passes left to the pass check
        character(len=:), allocatable :: deferred_message   !! the last of them
        logical :: alarm = .false.               !! a jump above jump_tol or a drift above drift_tol
        integer :: alarm_kind = alarm_none       !! alarm_jump or alarm_drift
        character(len=:), allocatable :: alarm_message   !! what, where and how much
        logical, private :: have_regular = .false., have_invariant = .false., in_layer = .false., have_work = .false.
        real(wp), private :: kinetic_last = 0.0_wp, tolerance_energy = 0.0_wp
        ! step_energy's interval work from the last sample to (step_t, step_z): sample_work reuses it
        real(wp), private :: step_t = -huge(1.0_wp), step_from = -huge(1.0_wp), step_work = 0.0_wp, step_error = 0.0_wp
        real(wp), allocatable, private :: step_z(:)
        logical, private :: step_unresolved = .false.   ! that step's balance stayed unresolved (taken as it is)
        ! step_energy's sample of T, P and the tolerance's sums at (step_t, step_z) for the model's eps and
        ! weights then: the sample at the accepted step's end reuses it (the same evaluation point)
        real(wp), private :: cached_kinetic = 0.0_wp, cached_power = 0.0_wp, cached_sums(2) = 0.0_wp, &
                             cached_eps = 0.0_wp
        real(wp), allocatable, private :: cached_w(:)
        logical, private :: have_cached = .false.
        real(wp), private :: unresolved_error = 0.0_wp   ! the quadrature estimates of such steps: against the balance
        real(wp), private :: kinetic0 = 0.0_wp, work = 0.0_wp, work_scale = 0.0_wp, power_last = 0.0_wp, &
                             t_work = 0.0_wp, power_before = 0.0_wp, t_before = 0.0_wp, quadrature_error = 0.0_wp
        integer, private :: work_samples = 0
        ! the balance across pass checks: the defect, the quadratures' estimates (E) and the
        ! unresolved steps' (U) of the stretches closed by a pass check's new start, summed; and
        ! those of the current stretch at its last tested sample (what a new start closes)
        real(wp), private :: carried(4) = 0.0_wp, stretch(3) = 0.0_wp   ! carried(4): the defects' squares
        logical, private :: carried_warned = .false.   ! the carried balance warned (once per run)
        real(wp), allocatable, private :: work_z(:), work_dz(:)   ! the last sample's (q, v) and slope (or none)
        real(wp), private :: layer_threshold = 0.05_wp   ! max(threshold, 3 sqrt(eps)): J's end samples lie above
        real(wp), private :: layer_eps = 0.0_wp
        real(wp), private :: sigma_peak = 0.0_wp         ! relative threshold: the largest sigma_min(GB) so far
        real(wp), private :: t_regular = 0.0_wp
        real(wp), private :: sigma_before = -1.0_wp, t_sigma_before = 0.0_wp   ! the sample before, for land_by
        real(wp), private :: slope_before = 0.0_wp   ! the secant slope of sigma before that (0: none)
        real(wp), allocatable, private :: v_regular(:), a_regular(:)
        real(wp), private :: memory = -1.0_wp, t_memory = 0.0_wp   ! max_k sigma_G(t_k) exp(-rate (t - t_k))
        logical, private :: layer_reached = .false., pass_flagged = .false.
    contains
        !> The time scale of the motion, 1 / its rate (the automatic weights' rate, else the
        !! rate at t0; huge if neither is known): a step longer than this may hold a whole
        !! singular pass between its samples.
        procedure :: motion_time => monitor_motion_time
        !> Turn the resolution check on (tol > 0) or off.
        procedure :: set_resolution => monitor_set_resolution
        !> Forget all samples; set the threshold.
        procedure :: reset => monitor_reset
        !> Sample the kinetic energy and the power of the applied forces at t (work-energy balance).
        procedure :: sample_work => monitor_sample_work
        !> Is the work-energy balance of a long explicit step resolved, before it is sampled?
        procedure :: step_energy => monitor_step_energy
        !> The solution goes on from another state at the last sample's time (a pass
        !! check's): its kinetic energy and power; the balance starts again there.
        procedure :: rebase_work => monitor_rebase_work
        !> Does a regularization act in the layers (eps > 0; not Baumgarte's)?
        procedure :: regularized => monitor_regularized
        !> Sample the model's last evaluation, made at time t on the solution.
        procedure :: sample => monitor_sample
        !> Sample given values: the drift max |g|, sigma_min(GB), the invariant
        !! (and its routine's stat), the velocities and their slopes at t.
        procedure :: sample_values => monitor_sample_values
        !> The singular intervals, (2, n_singular).
        procedure :: intervals => monitor_intervals
        !> Make eps (eps_factor > 0) and the drift bound (drift_factor > 0) automatic,
        !! following the scales seen at the samples (regdae_scales).
        procedure :: automatic => monitor_automatic
        !> Take the scales of a sample at t: max_i (GB)_ii, max_i |G_i|, max |x|, and
        !! sigma_min(GB); true if the automatic eps changed (the new value in scales%eps).
        procedure :: observe_scales => monitor_observe_scales
        !> Let the Baumgarte weights follow the motion (regdae_auto_rules): dense
        !! models of size nx of x, order2: the state holds (x, v); the rule's rate
        !! and length at t0, and t0.
        procedure :: follow_weights => monitor_follow_weights
        !> A new rate of the motion at t: true if the weights change (the rule's
        !! rate is then the new one; weights_new and weights_message set).
        procedure :: new_rate => monitor_new_rate
        !> The energy the state's tolerance leaves open at a sample (the work check allows their sum).
        procedure :: energy_tolerance => monitor_energy_tolerance
        !> Release the frozen checkpoint: (t, z) is the new one (a verified state after a pass).
        procedure :: release_checkpoint => monitor_release_checkpoint
        !> Is a new look at the rate due at t (weights following, a regular sample,
        !! half a time scale after the last look)?
        procedure :: weights_due => monitor_weights_due
        !> Does a sample at t need the full sample (`sample`), or do the work-energy
        !! balance's energies (`sample_work`) do: is a singular interval near? (The time since the
        !! last full sample counts at a step's end; at an output inside a step once an interval was seen.)
        procedure :: full_sample_due => monitor_full_sample_due
        !> The near level: sigma_min(GB) below it, a singular interval may be near
        !! (`near_factor` times the singular threshold and the layer's); huge before the
        !! first full sample (a relative threshold is not known yet).
        procedure :: near_level => monitor_near_level
    end type solution_monitor

    ! The work-energy balance (submodule regdae_monitor_work).
    interface
        !> Sample the kinetic energy and the power of the applied forces at t (`sample_work`).
        module subroutine monitor_sample_work(self, t, kinetic, power, stat, energy_tol, problem, z, dz, pattern, &
                                              constant)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t, kinetic, power
            integer, intent(in) :: stat   !! the user routines' status (nonzero: the sample is skipped)
            real(wp), intent(in), optional :: energy_tol   !! the energy the tolerance on the state leaves open
                                                           !! here (energy_tolerance); the sum over the samples
                                                           !! is allowed
            class(mechanical_problem), intent(inout), optional :: problem   !! with z = (q, v) at t and its slope dz:
            real(wp), intent(in), optional :: z(:), dz(:)                   !! an uncertain interval is refined
            type(sparsity_pattern), intent(in), optional :: pattern   !! the refinement's M from `mass_values` in
            logical, intent(in), optional :: constant                 !! this pattern; M declared constant
        end subroutine monitor_sample_work
        !> The work-energy balance of an explicit step ending at t (the model evaluated at its end z,
        !! slope dz), before the step is taken: from the last sample (its start) on the cubic Hermite
        !! interpolant of the two (`interval_work`), the step's defect dT - W plus the quadrature's
        !! estimate of W against step_energy_factor x the energy the tolerance leaves open at t (and
        !! at least work_refine work_tol S). `unresolved`: above it, the balance cannot vouch for the
        !! step (the integrator takes it again shorter). Only a long step (h work_rate > 0.3, as
        !! `parabola_work` counts it) outside the layers is looked at; rheonomic constraints are not.
        module subroutine monitor_step_energy(self, t, model, z, dz, unresolved)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t, z(:), dz(:)
            type(regularized_dae), intent(inout), target :: model   !! its mechanical problem is used by pointer
            logical, intent(out) :: unresolved
        end subroutine monitor_step_energy
        !> The balance goes on from another state at the last sample's time (`rebase_work`).
        module subroutine monitor_rebase_work(self, t, kinetic, power)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t                !! the time of the new state
            real(wp), intent(in) :: kinetic, power   !! of the new state
        end subroutine monitor_rebase_work
        !> The energy the state's tolerance leaves open at a sample (`energy_tolerance`).
        module pure real(wp) function monitor_energy_tolerance(self, sums, q, v) result(e)
            class(solution_monitor), intent(in) :: self
            real(wp), intent(in) :: sums(2), q(:), v(:)
        end function monitor_energy_tolerance
        !> An alarm inside a singular pass while a pass check is on: left to the pass check
        !! (which re-integrates the pass and takes a state that tighter tolerances agree on).
        module subroutine settle_alarm(self)
            type(solution_monitor), intent(inout) :: self
        end subroutine settle_alarm
        ! the sampling of values (submodule regdae_monitor_sampling)
        !> Sample the model's last evaluation, made at time t on the solution (`sample`).
        module subroutine monitor_sample(self, t, model, z, dz, sigma_now)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t
            type(regularized_dae), intent(inout), target :: model   !! a target: its mechanical problem is used by pointer
            real(wp), intent(in) :: z(:)    !! the state at t (the model's last evaluation point)
            real(wp), intent(in) :: dz(:)   !! its slope F(z, t)
            real(wp), intent(in), optional :: sigma_now   !! model%sigma_min_gb() just taken at this point by the
                                                          !! caller, with no other call since (not taken again)
        end subroutine monitor_sample
        !> Sample given values at t (`sample_values`).
        module subroutine monitor_sample_values(self, t, drift, sigma, invariant, invariant_stat, v, a, z)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t
            real(wp), intent(in) :: drift           !! max |g(x, t)| (order >= 2)
            real(wp), intent(in) :: sigma           !! sigma_min(GB)
            real(wp), intent(in) :: invariant       !! I(x, v, t) (read when invariant_tol > 0)
            integer, intent(in) :: invariant_stat   !! the invariant routine's stat
            real(wp), intent(in) :: v(:), a(:)      !! the np velocities and their slopes
            real(wp), intent(in), optional :: z(:)  !! the state (for the checkpoint before a singular pass)
        end subroutine monitor_sample_values
        !> Release the frozen checkpoint: (t, z) is the new one (`release_checkpoint`).
        module subroutine monitor_release_checkpoint(self, t, z)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t, z(:)
        end subroutine monitor_release_checkpoint
        ! the Baumgarte weights following the motion (submodule regdae_monitor_weights)
        !> Let the Baumgarte weights follow the motion (`follow_weights`).
        module subroutine monitor_follow_weights(self, nx, order2, rate, ell, t0)
            class(solution_monitor), intent(inout) :: self
            integer, intent(in) :: nx        !! dense models: the size of x (0: the caller gathers the rate)
            logical, intent(in) :: order2
            real(wp), intent(in) :: rate, ell, t0   !! the rate and length at t0
        end subroutine monitor_follow_weights
        !> A new rate of the motion at t: true if the weights change (`new_rate`).
        module logical function monitor_new_rate(self, t, rate) result(change)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t, rate
        end function monitor_new_rate
        !> Is a new look at the rate due at t (`weights_due`)?
        module logical function monitor_weights_due(self, t) result(due)
            class(solution_monitor), intent(in) :: self
            real(wp), intent(in) :: t
        end function monitor_weights_due
        !> The weights follow the motion at a regular sample, half a time scale apart (`sample`): a new
        !! look at the rate at (t, z), slope dz; the model's weights change with the rule's.
        module subroutine weights_sample(self, t, model, z, dz)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t, z(:), dz(:)
            type(regularized_dae), intent(inout), target :: model
        end subroutine weights_sample
        ! the resolution check (submodule regdae_monitor_resolution)
        !> Turn the resolution check on (tol > 0) or off (`set_resolution`).
        module subroutine monitor_set_resolution(self, tol)
            class(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: tol    !! resolution_tol (<= 0: off)
        end subroutine monitor_set_resolution
        !> The resolution check at a sample (the model's last evaluation is at (t, z)):
        !! the memory of sigma_G, and R on the approach to a layer (module doc).
        module subroutine resolution_sample(self, t, model, row_norm_min)
            type(solution_monitor), intent(inout) :: self
            real(wp), intent(in) :: t
            type(regularized_dae), intent(inout) :: model
            real(wp), intent(in), optional :: row_norm_min   !! min_i |G(i, :)|, if the caller has it
        end subroutine resolution_sample
    end interface

contains

    subroutine monitor_reset(self, threshold, eps, np, jump_tol, drift_tol, invariant_tol, work_tol)
        class(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: threshold
        real(wp), intent(in) :: eps         !! the regularization parameter (its layer: sigma_min(GB)^2 < eps)
        integer, intent(in) :: np           !! positions: z(np+1:2np) is their velocity, F(np+1:2np) its slope
        real(wp), intent(in) :: jump_tol    !! <= 0: no velocity-jump check
        real(wp), intent(in) :: drift_tol   !! <= 0: no drift check
        real(wp), intent(in) :: invariant_tol   !! <= 0: no invariant check
        real(wp), intent(in), optional :: work_tol   !! <= 0 or absent: no work-energy check
        self%relative = (threshold == option_auto)
        self%threshold = merge(0.0_wp, threshold, self%relative)
        self%layer_eps = eps
        self%layer_threshold = max(self%threshold, 3*sqrt(eps))
        self%in_layer = .false.
        self%weights%on = .false.
        self%weight_nx = 0
        self%weights_new = .false.
        self%pass_ended = .false.
        self%checkpoint_frozen = .false.
        self%checkpoint_valid = .false.
        self%deferred_alarms = 0
        self%invariant_tol = invariant_tol
        self%invariant_change = 0.0_wp
        self%have_invariant = .false.
        self%np = np
        self%jump_tol = jump_tol
        self%drift_tol = drift_tol
        self%jump_max = 0.0_wp
        self%drift_max = 0.0_wp
        self%work_tol = 0.0_wp
        if (present(work_tol)) self%work_tol = max(0.0_wp, work_tol)
        self%work_defect = 0.0_wp
        self%work_floor = 0.0_wp
        self%have_work = .false.
        self%step_t = -huge(1.0_wp)
        self%alarm = .false.
        self%alarm_kind = alarm_none
        self%alarm_message = ''
        self%resolution_ratio = 0.0_wp
        self%unresolved = 0
        self%unresolved_new = .false.
        self%unresolved_message = ''
        self%layer_reached = .false.
        self%pass_flagged = .false.
        self%memory = -1.0_wp
        self%scales = running_scales()
        self%drift_auto = .false.
        self%model_changed = .false.
        self%have_regular = .false.
        self%sigma_peak = 0.0_wp
        self%sigma_before = -1.0_wp
        self%slope_before = 0.0_wp
        self%land_by = huge(1.0_wp)
        self%project_due = .false.
        self%fold_low = huge(1.0_wp)
        self%fold_peak = 0.0_wp
        if (allocated(self%v_regular)) deallocate (self%v_regular, self%a_regular)
        allocate (self%v_regular(self%np), self%a_regular(self%np))
        self%sigma_last = huge(1.0_wp)
        self%sigma_min = huge(1.0_wp)
        self%n_singular = 0
        self%in_singular = .false.
        if (allocated(self%singular)) deallocate (self%singular)
    end subroutine monitor_reset

    !> The rate at which the stabilization forgets a constraint residual: gamma of
    !! g' + gamma g = 0 (gamma0 = 0: index 2, or a first-order problem), else the real part
    !! of the slower root of s^2 + gamma1 s + gamma0 (index 3).
    pure real(wp) function forgetting_rate(gamma0, gamma1) result(rate)
        real(wp), intent(in) :: gamma0, gamma1
        if (gamma0 > 0.0_wp) then
            rate = 0.5_wp*gamma1 - sqrt(max(0.25_wp*gamma1**2 - gamma0, 0.0_wp))
        else
            rate = gamma1
        end if
    end function forgetting_rate

    pure real(wp) function monitor_motion_time(self) result(time)
        class(solution_monitor), intent(in) :: self
        real(wp) :: rate
        rate = max(self%weights%rate, self%work_rate)
        time = huge(1.0_wp)
        if (rate > 0.0_wp .and. rate < huge(1.0_wp)) time = 1.0_wp/rate
    end function monitor_motion_time

    ! The full sample is due (doc/methods.md, "The full sample where a singular interval may
    ! be near") unless the last two full samples lie above the near level, outside singular
    ! intervals and layers, less than far_gap motion times ago (at a step's end; at an output
    ! inside a step too once a singular interval was seen), and a falling
    ! sigma_min(GB) is less than halfway (in time) to the near level along their secant.
    logical function monitor_full_sample_due(self, t, inside_step) result(due)
        class(solution_monitor), intent(in) :: self
        real(wp), intent(in) :: t
        logical, intent(in) :: inside_step   !! t is an output time inside the last step (its end is sampled)
        real(wp) :: near, since
        due = .true.
        if (.not. (self%sigma_before >= 0.0_wp)) return   ! no full sample yet (or its sigma was NaN)
        if (self%in_singular .or. self%in_layer .or. self%weights_due(t)) return
        near = self%near_level()
        if (.not. (self%sigma_last >= near .and. self%sigma_before >= near)) return
        if (.not. (self%motion_time() < huge(1.0_wp))) return   ! no time scale: every sample full
        since = t - self%t_sigma_before
        if (.not. (since < far_gap*self%motion_time() .or. (inside_step .and. self%n_singular == 0))) return
        ! sigma falling (the secant of the last two full samples): the next full sample
        ! halfway to where the secant reaches the near level
        if (self%slope_before < 0.0_wp) then
            if (since >= 0.5_wp*(self%sigma_before - near)/(-self%slope_before)) return
        end if
        due = .false.
    end function monitor_full_sample_due

    pure real(wp) function monitor_near_level(self) result(near)
        class(solution_monitor), intent(in) :: self
        near = huge(1.0_wp)
        if (self%sigma_before >= 0.0_wp) near = near_factor*max(self%threshold, self%layer_threshold)
    end function monitor_near_level

    pure logical function monitor_regularized(self) result(yes)
        class(solution_monitor), intent(in) :: self
        yes = (self%layer_eps > 0.0_wp)
    end function monitor_regularized

    function monitor_intervals(self) result(intervals)
        class(solution_monitor), intent(in) :: self
        real(wp), allocatable :: intervals(:, :)
        allocate (intervals(2, 0))
        if (self%n_singular > 0) intervals = self%singular(:, 1:self%n_singular)
    end function monitor_intervals

    subroutine monitor_automatic(self, eps_factor, eps, drift_factor, rtol, atol, direct, sigma_pred)
        class(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: eps_factor   !! > 0: eps automatic (regdae_auto_rules' automatic_eps)
        real(wp), intent(in) :: eps          !! eps in force at t0
        real(wp), intent(in) :: drift_factor !! > 0: drift bound automatic
        real(wp), intent(in) :: rtol, atol
        logical, intent(in) :: direct        !! method=direct
        real(wp), intent(in) :: sigma_pred   !! the predicted regular sigma_min(GB) of a singular start (< 0: none)
        self%scales%eps_factor = eps_factor
        self%scales%eps = eps
        self%scales%direct = direct
        self%scales%sigma_pred = sigma_pred
        ! a start on a singular configuration: its regular sigma_min(GB) is the prediction,
        ! so that the relative threshold marks the start as singular
        if (self%relative .and. sigma_pred > 0.0_wp) self%threshold = 0.05_wp*max(self%sigma_peak, sigma_pred)
        self%scales%drift_factor = drift_factor
        self%scales%rtol = rtol
        self%scales%atol = atol
        self%drift_auto = (drift_factor > 0.0_wp .and. self%np > 0)
    end subroutine monitor_automatic

    logical function monitor_observe_scales(self, t, gb, g, x, sigma) result(raised)
        class(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: t, gb, g, x, sigma
        call self%scales%observe(gb, g, x, sigma)
        if (self%drift_auto) self%drift_tol = self%scales%drift_bound(self%layer_eps)
        raised = self%scales%retarget_eps(t, sigma)
        if (raised) then
            self%layer_eps = self%scales%eps
            self%layer_threshold = max(self%threshold, 3*sqrt(self%layer_eps))
        end if
    end function monitor_observe_scales

end module regdae_monitor
