!> The regdae solver front: a regularized index-2 or index-3 DAE integrated by
!! the integrators behind one interface (`regdae_integrator`): the explicit
!! Dormand-Prince (`regdae_dopri5_integrator`), SUNDIALS IDA on the
!! eliminated, multiplier or augmented formulation (`regdae_ida_integrator`) and
!! Radau IIA on the eliminated or augmented one (`regdae_radau_integrator`),
!! with integrator=auto switching between them (`regdae_integrator_switching`,
!! its policy in `regdae_switching_policy`). The front is what a user calls:
!! init (submodule `regdae_solver_init`: the input checked, consistent initial
!! values, the automatic parameters of `regdae_auto_parameters`, the first
!! integrator started), advance (written once over the interface: the integrator
!! in charge to the output time, the outcome acted on, the outputs and the
!! diagnostics' status), the statistics and the events; and what
!! regdae_solver_trust needs to verify singular passes (submodule
!! `regdae_solver_passes`); the queries in submodule `regdae_solver_reports`. The state of
!! one problem is `regdae_solver_core`'s record; the monitor's start and samples are in
!! `regdae_solver_sampling`.
!!
!! ```fortran
!! type(solver_engine) :: solver
!! call solver%init(problem, t0, x0, opts, stat)          ! dae_problem (index 2)
!! call solver%init(problem, t0, x0, v0, opts, stat)      ! second_order_problem or mechanical_problem
!! do k = 1, nout
!!     call solver%advance(tout(k), x, y, stat [, v])
!! end do
!! call solver%destroy()
!! ```
!! All state lives in the solver object (IDA memory, vectors, options, the
!! problem's copy, counters), so any number of solvers can exist in one
!! program. Assignment does not copy a solver: `a = b` leaves `a`
!! uninitialized (its `advance` says why) and `b` untouched. `init` may be
!! called again to start a new problem on the same object.
module regdae_solver_front
    use, intrinsic :: iso_c_binding, only: c_double
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_problem, only: dae_problem
    use regdae_second_order_problem, only: second_order_problem
    use regdae_mechanical_problem, only: mechanical_problem
    use regdae_higher_order_problem, only: higher_order_problem
    use regdae_options
    use regdae_augmented_system, only: augmented_system
    use regdae_solver_stats, only: solver_stats
    use regdae_monitor, only: alarm_jump, alarm_invariant, alarm_work
    use regdae_format, only: format_real, format_int
    use regdae_solver_core, only: solver_core, log_event, active_integrator
    use regdae_integrator, only: integrator, outcome_reached, outcome_pass_end, outcome_stiff, outcome_nonstiff, &
                                 outcome_alarm, outcome_failed, outcome_exhausted
    use regdae_integrator_switching, only: hand_over
    use regdae_auto_parameters, only: time_resolution
    use regdae_events, only: event_locator, event_functions
    implicit none
    private

    public :: solver_stats, event_functions, events_length

    !> A regularized DAE solver on IDA (see the module documentation).
    type, public :: solver_engine
        private
        type(solver_core), pointer :: core => null()
        real(wp) :: t = 0.0_wp   ! time reached
        integer :: last_stat = regdae_err_not_initialized
        character(len=:), allocatable :: last_message
        logical :: assigned = .false.   ! the target of an assignment (which does not copy)
        type(event_locator) :: ev       ! the event functions and their search (regdae_events)
        type(solver_core), pointer :: ev_core => null()   ! the problem the search started on
        logical :: each_step = .false.  ! advance returns after every step (DASSL's INFO(3) = 1)
    contains
        !> Set up a problem: check the input, compute consistent initial values
        !! and create the IDA objects. `init(problem, t0, x0, opts, stat)` for a
        !! `dae_problem`; `init(problem, t0, x0, v0, opts, stat)` for a
        !! `second_order_problem` or `mechanical_problem` (index from `opts%index`);
        !! `init(problem, t0, xs0, opts, stat)` for a `higher_order_problem`, xs0(n, order).
        !! Optional last argument `atol_vector`: the absolute tolerance per component.
        generic :: init => init_first_order, init_second_order, init_higher_order
        procedure, private :: init_first_order => solver_init_first
        procedure, private :: init_second_order => solver_init_second
        procedure, private :: init_higher_order => solver_init_higher
        procedure, private :: start => solver_start
        procedure, private :: start_augmented => solver_start_augmented
        procedure, private :: check_input
        !> Integrate to `tout`; return x(tout), the multiplier y(tout) (lambda for a
        !! mechanical problem) and, for second-order problems, optionally v(tout).
        procedure :: advance => solver_advance
        !> Event functions: `set_events(fn, n, stat [, direction] [, stop])` (regdae_events;
        !! n = 0 clears them). They persist across init.
        procedure :: set_events => solver_set_events
        !> After a return with regdae_root_found: per event function +1 (a root,
        !! increasing), -1 (decreasing) or 0 (none at that time); length n.
        procedure :: roots => solver_roots
        !> advance returns after every step of the integrator (on) or at tout (off, the default).
        procedure :: return_each_step => solver_return_each_step
        !> Statistics of the integration so far.
        procedure :: statistics => solver_statistics
        !> Message of the last call (empty after success).
        procedure :: message => solver_message
        !> The resolved least-squares solver (`lsq_normal`, `lsq_stacked` or
        !! `lsq_checked` for auto; 0 for the augmented formulation, which solves
        !! no least-squares problem).
        procedure :: lsq_method => solver_lsq_method
        !> The log of integrator switches (integrator=auto), one line each.
        procedure :: events => solver_events
        !> The options in force, `auto` values resolved (the defaults before init).
        procedure :: options => solver_options_in_force
        !> The resolved formulation and linear solver (codes of regdae_options).
        procedure :: formulation => solver_formulation
        procedure :: linear_solver => solver_linear_solver
        !> sigma_min(GB) at the last sample (output time with IDA, accepted step with dopri5).
        procedure :: sigma_min => solver_sigma_min
        !> The singular intervals so far: (2, k) array of first and last sample times.
        procedure :: singular_intervals => solver_singular_intervals
        !> Free all IDA and SUNDIALS objects (also done by `init` and finalization).
        procedure :: destroy => solver_destroy
        ! What regdae_solver_trust needs to verify singular passes with companions:
        !> Stop `advance` early at the end of a singular pass (on) or not.
        procedure :: stop_at_pass_ends => engine_stop_at_pass_ends
        !> Did a singular pass end during the last advances (the flag is cleared)?
        procedure :: take_pass_end => engine_take_pass_end
        !> The checkpoint before the current singular pass: time, state, and whether
        !! it is frozen (a pass began since), valid (one exists).
        procedure :: checkpoint => engine_checkpoint
        !> (t, z) is the new checkpoint, the last pass is over.
        procedure :: release_checkpoint => engine_release_checkpoint
        !> The integrator's own time (dopri5 may have stepped beyond the last output).
        procedure :: integrator_time => engine_integrator_time
        !> The state z at the current time: (x, v) of a second-order problem, x of a first-order one.
        procedure :: state => engine_state
        !> Continue from the state z at t (the current time), e.g. a more accurate one.
        procedure :: restart_at => engine_restart_at
        !> Start `other` on the same problem from (t, z) with the tolerances divided by
        !! kappa (eps too when automatic), the weights in force, no checks.
        procedure :: start_companion => engine_start_companion
        !> A companion's start: z at t projected onto the constraints (start_companion does it
        !! unless told that z is projected already).
        procedure :: project_start => engine_project_start
        !> Does the automatic eps of companions at rtol/kappa_a and rtol/kappa_b coincide (the
        !! rule's floor)? False if eps is the user's.
        procedure :: eps_floored => engine_eps_floored
        !> Does a regularization act in the layers (eps > 0; not Baumgarte's)?
        procedure :: regularized => engine_regularized
        !> The steps allowed per call of `advance` from now on (a companion's budget).
        procedure :: limit_steps => engine_limit_steps
        !> max_i |za_i - zb_i| / (rtol |zb_i| + atol_i) over x, the positions of the state z.
        procedure :: state_distance => engine_state_distance
        !> Append a line to the events log.
        procedure :: note_event => engine_note_event
        !> The size of the state z (0 before init).
        procedure :: state_size => engine_state_size
        !> The time reached.
        procedure :: time => engine_time
        !> The steps taken so far (statistics()%steps without the rest).
        procedure :: steps_taken => engine_steps_taken
        !> The size of x (0 before init).
        procedure :: x_size => engine_x_size
        !> Is this the same engine as `other` (both initialized, one state)?
        procedure :: same_engine => engine_same
        procedure, private :: record => solver_record
        !> `a = b` does not copy a solver (it owns IDA memory and its callbacks
        !! point at it): `a` is left uninitialized, `b` unchanged; `a%advance`
        !! then reports `regdae_err_not_initialized` and says why. Call `init`
        !! on `a` to start a problem there.
        generic :: assignment(=) => assign_refused
        procedure, private :: assign_refused => solver_assign
        final :: solver_finalize
    end type solver_engine

    ! The queries and the monitor's alarm as a status (submodule regdae_solver_reports).
    interface
        ! (message and events have automatic-length results: doc/methods.md, "No global state")
        module function solver_message(self) result(msg)
            class(solver_engine), intent(in) :: self
            character(len=message_length(self)) :: msg
        end function solver_message

        module function solver_events(self) result(text)
            class(solver_engine), intent(in) :: self
            character(len=events_length(self)) :: text
        end function solver_events

        pure module integer function message_length(self)
            class(solver_engine), intent(in) :: self
        end function message_length

        !> The length of the events log (`events`).
        pure module integer function events_length(self)
            class(solver_engine), intent(in) :: self
        end function events_length

        module function solver_options_in_force(self) result(opts)
            class(solver_engine), intent(in) :: self
            type(solver_options) :: opts
        end function solver_options_in_force

        module integer function solver_formulation(self)
            class(solver_engine), intent(in) :: self
        end function solver_formulation

        module integer function solver_linear_solver(self)
            class(solver_engine), intent(in) :: self
        end function solver_linear_solver

        module integer function solver_lsq_method(self)
            class(solver_engine), intent(in) :: self
        end function solver_lsq_method

        module real(wp) function solver_sigma_min(self)
            class(solver_engine), intent(in) :: self
        end function solver_sigma_min

        module function solver_singular_intervals(self) result(intervals)
            class(solver_engine), intent(in) :: self
            real(wp), allocatable :: intervals(:, :)
        end function solver_singular_intervals

        ! The status and message of an advance that the monitor's alarm stops.
        module subroutine alarm_status(core, code, msg)
            type(solver_core), intent(in) :: core
            integer, intent(out) :: code
            character(len=:), allocatable, intent(out) :: msg
        end subroutine alarm_status
    end interface

    ! The init paths and destroy (submodule regdae_solver_init).
    interface
        module subroutine solver_init_first(self, problem, t0, x0, opts, stat, atol_vector)
            class(solver_engine), intent(inout) :: self
            class(dae_problem), intent(in) :: problem   !! the index-2 DAE (copied)
            real(wp), intent(in) :: t0                  !! initial time
            real(wp), intent(in) :: x0(:)               !! x(t0), length n; must satisfy g(x0, t0) = 0
            type(solver_options), intent(in) :: opts    !! options (validated here)
            integer, intent(out) :: stat                !! regdae status code
            real(wp), intent(in), optional :: atol_vector(:)   !! absolute tolerance per component of the state
                                                              !! (replaces atol, atol_v; second order: positions,
                                                              !! then velocities; order m: x, ..., x^(m-1))
        end subroutine solver_init_first

        module subroutine solver_init_second(self, problem, t0, x0, v0, opts, stat, atol_vector)
            class(solver_engine), intent(inout) :: self
            class(second_order_problem), intent(in) :: problem   !! the order-2 DAE or mechanical system (copied)
            real(wp), intent(in) :: t0                  !! initial time
            real(wp), intent(in) :: x0(:)               !! x(t0), length n; g(x0, t0) = 0
            real(wp), intent(in) :: v0(:)               !! x'(t0), length n; G v0 + g_t = 0
            type(solver_options), intent(in) :: opts    !! options (validated here; `index` chooses 2 or 3)
            integer, intent(out) :: stat
            real(wp), intent(in), optional :: atol_vector(:)   !! absolute tolerance per component of the state
                                                              !! (replaces atol, atol_v; second order: positions,
                                                              !! then velocities; order m: x, ..., x^(m-1))
        end subroutine solver_init_second

        module subroutine solver_init_higher(self, problem, t0, xs0, opts, stat, atol_vector)
            class(solver_engine), intent(inout) :: self
            class(higher_order_problem), intent(in) :: problem   !! the order-m DAE (copied)
            real(wp), intent(in) :: t0                   !! initial time
            real(wp), intent(in) :: xs0(:, :)            !! (n, order): x, x', ..., x^(m-1) at t0
            type(solver_options), intent(in) :: opts
            integer, intent(out) :: stat
            real(wp), intent(in), optional :: atol_vector(:)   !! absolute tolerance per component of the state
                                                              !! (replaces atol, atol_v; second order: positions,
                                                              !! then velocities; order m: x, ..., x^(m-1))
        end subroutine solver_init_higher

        module logical function check_input(self, t0, x0, v0, n, m, opts, stat) result(ok)
            class(solver_engine), intent(inout) :: self
            real(wp), intent(in) :: t0, x0(:), v0(:)
            integer, intent(in) :: n, m
            type(solver_options), intent(in) :: opts
            integer, intent(out) :: stat
        end function check_input

        module subroutine solver_start_augmented(self, problem, t0, q0, v0, opts, stat)
            class(solver_engine), intent(inout) :: self
            class(mechanical_problem), intent(in) :: problem
            real(wp), intent(in) :: t0, q0(:), v0(:)
            type(solver_options), intent(in) :: opts
            integer, intent(out) :: stat
        end subroutine solver_start_augmented

        module subroutine solver_start(self, t0, z0, opts, stat)
            class(solver_engine), intent(inout) :: self
            real(wp), intent(in) :: t0, z0(:)
            type(solver_options), intent(in) :: opts
            integer, intent(out) :: stat
        end subroutine solver_start

        module subroutine solver_destroy(self)
            class(solver_engine), intent(inout) :: self
        end subroutine solver_destroy

        module subroutine solver_assign(lhs, rhs)
            class(solver_engine), intent(inout) :: lhs
            class(solver_engine), intent(in) :: rhs
        end subroutine solver_assign
    end interface

    ! What regdae_solver_trust needs to verify singular passes with companions
    ! (submodule regdae_solver_passes).
    interface
        module subroutine engine_stop_at_pass_ends(self, on)
            class(solver_engine), intent(inout) :: self
            logical, intent(in) :: on
        end subroutine engine_stop_at_pass_ends

        module logical function engine_take_pass_end(self) result(ended)
            class(solver_engine), intent(inout) :: self
        end function engine_take_pass_end

        module subroutine engine_checkpoint(self, t, frozen, valid, z)
            class(solver_engine), intent(in) :: self
            real(wp), intent(out) :: t
            logical, intent(out) :: frozen, valid
            real(wp), allocatable, intent(out), optional :: z(:)   !! the state (not copied if absent)
        end subroutine engine_checkpoint

        module subroutine engine_release_checkpoint(self, t, z)
            class(solver_engine), intent(inout) :: self
            real(wp), intent(in) :: t, z(:)
        end subroutine engine_release_checkpoint

        module real(wp) function engine_integrator_time(self) result(t)
            class(solver_engine), intent(in) :: self
        end function engine_integrator_time

        module logical function engine_same(self, other) result(same)
            class(solver_engine), intent(in) :: self, other
        end function engine_same

        module integer function engine_x_size(self) result(n)
            class(solver_engine), intent(in) :: self
        end function engine_x_size

        module real(wp) function engine_time(self) result(t)
            class(solver_engine), intent(in) :: self
        end function engine_time

        module integer(int64) function engine_steps_taken(self) result(n)
            class(solver_engine), intent(in) :: self
        end function engine_steps_taken

        module integer function engine_state_size(self) result(n)
            class(solver_engine), intent(in) :: self
        end function engine_state_size

        module subroutine engine_state(self, z)
            class(solver_engine), intent(in) :: self
            real(wp), intent(out) :: z(:)   !! length state_size()
        end subroutine engine_state

        module subroutine engine_restart_at(self, t, z, stat)
            class(solver_engine), intent(inout) :: self
            real(wp), intent(in) :: t, z(:)
            integer, intent(out) :: stat
        end subroutine engine_restart_at

        module subroutine engine_start_companion(self, other, kappa, t, z, stat, eps_scale, projected)
            class(solver_engine), intent(in) :: self
            class(solver_engine), intent(inout) :: other
            real(wp), intent(in) :: kappa       !! the tolerances' divisor (>= 1)
            real(wp), intent(in) :: t, z(:)     !! the start: a state of self (x, v)
            integer, intent(out) :: stat
            real(wp), intent(in), optional :: eps_scale   !! the companion's eps times this (a probe of the
                                                          !! regularization error)
            logical, intent(in), optional :: projected    !! z is projected already (project_start)
        end subroutine engine_start_companion

        module subroutine engine_project_start(self, t, z)
            class(solver_engine), intent(in) :: self
            real(wp), intent(in) :: t
            real(wp), intent(inout) :: z(:)     !! a state of self (x, v), projected in place
        end subroutine engine_project_start

        module subroutine engine_limit_steps(self, steps)
            class(solver_engine), intent(inout) :: self
            integer, intent(in) :: steps   !! >= 1
        end subroutine engine_limit_steps

        module logical function engine_regularized(self) result(yes)
            class(solver_engine), intent(in) :: self
        end function engine_regularized

        module logical function engine_eps_floored(self, kappa_a, kappa_b) result(floored)
            class(solver_engine), intent(in) :: self
            real(wp), intent(in) :: kappa_a, kappa_b
        end function engine_eps_floored

        module real(wp) function engine_state_distance(self, za, zb) result(d)
            class(solver_engine), intent(in) :: self
            real(wp), intent(in) :: za(:), zb(:)
        end function engine_state_distance

        module subroutine engine_note_event(self, text)
            class(solver_engine), intent(inout) :: self
            character(len=*), intent(in) :: text
        end subroutine engine_note_event

        module subroutine solver_set_events(self, fn, n, stat, direction, stop)
            class(solver_engine), intent(inout) :: self
            class(event_functions), intent(in) :: fn        !! the event functions (copied)
            integer, intent(in) :: n                        !! their number (0: no events)
            integer, intent(out) :: stat                    !! regdae_success or regdae_err_bad_input
            integer, intent(in), optional :: direction(:)   !! per function: +1, -1 or 0 (both, the default)
            logical, intent(in), optional :: stop(:)        !! per function: stop at its roots (the default)
        end subroutine solver_set_events

        module subroutine solver_return_each_step(self, on)
            class(solver_engine), intent(inout) :: self
            logical, intent(in) :: on   !! return after every step (the state at its end, before tout)
        end subroutine solver_return_each_step

        module function solver_roots(self) result(found)
            class(solver_engine), intent(in) :: self
            integer, allocatable :: found(:)
        end function solver_roots

        module function solver_statistics(self) result(st)
            class(solver_engine), intent(in) :: self
            type(solver_stats) :: st
        end function solver_statistics
    end interface

contains

    subroutine solver_advance(self, tout, x, y, stat, v, a)
        class(solver_engine), intent(inout) :: self
        real(wp), intent(in) :: tout      !! output time (beyond the current time, or equal to it)
        real(wp), intent(out) :: x(:)     !! x(tout), length n
        real(wp), intent(out), optional :: y(:)   !! y(tout) (lambda for a mechanical problem), length m,
                                          !! recomputed from the state at tout; leave it out when
                                          !! only x is needed (saves one evaluation per output
                                          !! with integrator=dopri5)
        integer, intent(out) :: stat      !! regdae status code
        real(wp), intent(out), optional :: v(:)   !! second-order problems: v(tout), length n
        real(wp), intent(out), optional :: a(:)   !! second-order problems: the acceleration x''(tout), length
                                          !! n: f - B y from the regularized equation at the state
                                          !! (augmented formulation: the implicit integrator's interpolated v')
        type(solver_core), pointer :: core
        class(integrator), pointer :: stepper
        type(augmented_system), pointer :: sys
        real(c_double), pointer :: u(:)
        character(len=:), allocatable :: msg
        logical :: recoverable, events, at_root, stop_user, held, driving, single
        integer :: nx, outcome, taken
        real(wp) :: t_reached, t_stop, t_ask, t_before

        core => self%core
        if (.not. associated(core)) then
            if (self%assigned) then
                call fail(regdae_err_not_initialized, 'advance called on a solver that was the target of an '// &
                          'assignment, which does not copy a solver: call init on it first')
            else
                call fail(regdae_err_not_initialized, 'advance called before a successful init')
            end if
            return
        end if
        nx = core%nx
        if (.not. outputs_fit()) return
        t_reached = tout
        at_root = .false.
        events = self%ev%n > 0
        driving = events .or. self%each_step   ! one step at a time
        if (tout > core%t) then
            ! The integrator in charge to tout; with integrator=auto the explicit one hands
            ! over to the implicit one where the system is stiff, and back where it is not
            ! (regdae_integrator_switching). With stop_at_pass_end, the integrator stops
            ! early at the end of a singular pass. With events, one step at a time, each
            ! searched for roots (regdae_events); a stopping root ends the advance there.
            stop_user = core%opts%stop_at_output
            taken = 0
            core%monitor%project_on = .not. driving
            if (driving) core%monitor%project_due = .false.   ! a pending one too (events or single steps now)
            if (events) then
                self%ev%found = 0
                self%ev%t_step_end = -huge(1.0_wp)   ! (a restart since may have replaced the state)
                if (.not. (self%ev%primed .and. core%started .and. associated(self%ev_core, core))) then
                    stepper => active_integrator(core)
                    call self%ev%prime(stepper, core%t, nx, core%second_order, stat, msg)
                    if (stat /= regdae_success) then
                        call fail(stat, msg)
                        return
                    end if
                    self%ev_core => core
                end if
                ! the rest of the last step before the integrator steps on (else searched after the advance)
                outcome = outcome_reached
                stepper => active_integrator(core)
                t_stop = stepper%time()
                if (t_stop > self%ev%t_lo .and. core%started .and. (stepper%steps_singly() .or. tout > t_stop)) then
                    if (.not. search_roots()) return
                end if
            end if
            do
                if (at_root) exit
                stepper => active_integrator(core)
                u => stepper%state()
                t_ask = tout
                single = driving .and. stepper%steps_singly()   ! advance returns after one step (else t + |h|/1000)
                if (driving .and. .not. single) t_ask = self%ev%step_target(stepper%time(), stepper%last_step(), tout, &
                                                                            time_resolution(core%t, tout), stop_user)
                if (driving) then
                    core%opts%stop_at_output = stop_user .and. t_ask == tout
                    taken = taken + 1
                    if (taken > core%opts%max_steps) then
                        call fail(regdae_err_integration, 'max_steps = '//format_int(core%opts%max_steps)// &
                                  ' steps taken without reaching tout = '//format_real(tout)//' (t = '// &
                                  format_real(stepper%time())//')')
                        return
                    end if
                end if
                if (core%monitor%project_due .and. .not. driving .and. stepper%time() <= tout) then
                    ! the last step ended before tout (its outputs are given): project there
                    if (.not. projected_at(stepper%time())) return
                end if
                held = .false.
                if (single) t_before = stepper%time()
                if (driving .and. .not. single .and. core%stop_at_pass_end .and. core%started .and. &
                    stepper%time() < tout) then
                    ! the step end passed over (an implicit integrator samples it now): a pass end
                    ! there stops before the next step, as it does without events
                    call stepper%advance(stepper%time(), t_stop, outcome, stat, msg)
                    held = (outcome /= outcome_reached .or. core%monitor%pass_ended)
                    if (outcome == outcome_reached .and. held) outcome = outcome_pass_end
                end if
                if (.not. held) call stepper%advance(t_ask, t_stop, outcome, stat, msg, one_step=single)
                if (events) call self%ev%state_after(outcome == outcome_reached, single, t_before, t_stop, stepper%time())
                if (single .and. outcome == outcome_reached) t_ask = t_stop   ! the step's end, or tout
                core%opts%stop_at_output = stop_user
                if (driving) then
                    ! a step beyond t_ask: the integrator did not report a pass end there
                    if (outcome == outcome_reached .and. core%stop_at_pass_end .and. core%monitor%pass_ended .and. &
                        stepper%time() < tout) then
                        outcome = outcome_pass_end
                        t_stop = stepper%time()
                    end if
                end if
                if (events) then
                    if (.not. search_roots()) return
                    if (at_root) exit
                end if
                select case (outcome)
                case (outcome_reached)
                    t_reached = t_ask
                    if (self%each_step .and. t_ask < tout .and. stepper%time() < tout) t_reached = stepper%time()
                    if (t_ask < tout .and. .not. core%monitor%alarm .and. .not. self%each_step) cycle
                    if (self%each_step .and. t_ask < tout .and. .not. (stepper%time() < tout)) cycle
                    exit
                case (outcome_pass_end)
                    if (core%monitor%project_due) then   ! (the integrator stopped for it)
                        if (.not. projected_at(t_stop)) return
                        if (.not. core%monitor%pass_ended .or. .not. core%stop_at_pass_end) cycle
                    end if
                    t_reached = t_stop
                    exit
                case (outcome_stiff, outcome_nonstiff)
                    call hand_over(core, outcome, t_stop, stat, msg)
                    if (stat /= regdae_success) then
                        call fail(stat, msg)
                        return
                    end if
                case (outcome_alarm)
                    core%t = t_stop
                    call copy_state()
                    if (branch_alarm()) return
                case (outcome_failed, outcome_exhausted)
                    core%t = t_stop
                    call copy_state()
                    if (present(y) .and. outcome == outcome_failed) y = ieee_value(1.0_wp, ieee_quiet_nan)
                    call fail(stat, msg)
                    return
                case default
                    call fail(stat, msg)
                    return
                end select
            end do
            core%t = t_reached
            core%started = .true.
            if (driving) then
                stepper => active_integrator(core)
                if (self%ev%t_state /= core%t .or. .not. events) call stepper%interpolate(core%t, stat)
                self%ev%t_state = core%t
            end if
        end if
        stepper => active_integrator(core)
        u => stepper%state()
        self%t = core%t
        call copy_state()
        if (core%augmented) then
            ! y is one of the implicit integrator's unknowns (interpolated like the others)
            if (present(y)) then
                call sys%unpack(u, u, y=core%y_work)
                y = core%multiplier_sign*core%y_work
            end if
            if (present(a)) call sys%unpack(u, stepper%slope(), a=a)
            call record_done()
            return
        end if
        ! The diagnostics come from the accepted steps; the multiplier is computed only
        ! when asked for.
        if (branch_alarm()) return
        if (.not. (present(y) .or. present(a))) then
            call record_done()
            return
        end if
        ! The multiplier (and the acceleration) at an output time come from the
        ! regularized equation, not from the integrator's interpolant.
        call core%model%evaluate(core%t, u(1:core%n), stat, recoverable)
        if (stat == regdae_success) call core%model%solve_multiplier(core%t, core%y_work, stat)
        if (stat /= regdae_success) then
            ! The state at tout is valid; only the multiplier equation is singular here
            ! (Baumgarte where GB is singular, or eps = 0 with the normal equations).
            if (present(y)) y = ieee_value(1.0_wp, ieee_quiet_nan)
            if (present(a)) a = ieee_value(1.0_wp, ieee_quiet_nan)
            call self%record(regdae_warn_multiplier_undefined, 'the multiplier at t = '//format_real(core%t)// &
                             ' is undefined: '//core%model%message, stat)
            return
        end if
        if (present(y)) y = core%multiplier_sign*core%y_work
        if (present(a)) then
            call core%model%dynamics_slope(u(1:core%n), core%y_work, core%zp_work)
            a = core%zp_work(nx + 1:2*nx)
        end if
        call record_done()
    contains
        ! Another fold ahead within the stabilization's memory of the last one (the monitor's
        ! project_due, doc/methods.md "The residual a fold leaves"): the state at t_at, the
        ! integrator's step end, projected onto g = 0 and G v + g_t = 0 and the integrator
        ! started again from it; false (recorded) on a failure.
        logical function projected_at(t_at) result(ok)
            real(wp), intent(in) :: t_at
            real(wp), allocatable :: zs(:)
            core%monitor%project_due = .false.
            allocate (zs(self%state_size()))
            stepper => active_integrator(core)
            call stepper%interpolate(t_at, stat)   ! the state at the step's end (not at the last output)
            if (stat == regdae_success) then
                call self%state(zs)
                call self%project_start(t_at, zs)
                call self%restart_at(t_at, zs, stat)
            end if
            ok = (stat == regdae_success)
            if (.not. ok) call fail(stat, 'the projection before the next fold at t = '//format_real(t_at)//' failed')
        end function projected_at

        ! The sizes of the outputs and tout; false (recorded) if one does not fit.
        logical function outputs_fit() result(ok)
            ok = .false.
            if (size(x) /= nx) then
                call fail(regdae_err_bad_input, 'advance: x must have length '//format_int(nx))
                return
            end if
            if (present(y)) then
                if (size(y) /= core%m) then
                    call fail(regdae_err_bad_input, 'advance: y must have length '//format_int(core%m))
                    return
                end if
            end if
            if (present(v)) then
                if (.not. core%second_order .or. size(v) /= nx) then
                    call fail(regdae_err_bad_input, 'advance: v is for second-order problems, length '//format_int(nx))
                    return
                end if
            end if
            if (present(a)) then
                if (.not. core%second_order .or. size(a) /= nx) then
                    call fail(regdae_err_bad_input, 'advance: a is for second-order problems, length '//format_int(nx))
                    return
                end if
            end if
            if (.not. ieee_is_finite(tout)) then
                call fail(regdae_err_bad_input, 'advance: tout is NaN or Inf')
                return
            end if
            if (tout < core%t) then
                call fail(regdae_err_bad_input, 'advance: tout = '//format_real(tout)// &
                          ' is before the current time '//format_real(core%t))
                return
            end if
            if (.not. core%started .and. tout > core%t .and. tout - core%t < time_resolution(core%t, tout)) then
                ! No first step fits (IDA: "tout too close to t0"); later, the integrators
                ! step across such intervals.
                call fail(regdae_err_bad_input, 'advance: tout = '//format_real(tout, 16)// &
                          ' is too close to t0 = '//format_real(core%t, 16)//' to start the integration: tout - t0 = '// &
                          format_real(tout - core%t)//' is below the time resolution '// &
                          format_real(time_resolution(core%t, tout))// &
                          ' (4 epsilon max(|t0|, |tout|), at least sqrt(tiny) = 1.5E-154)')
                return
            end if
            ok = .true.
        end function outputs_fit

        ! The step just taken searched for roots up to its end (or tout); false
        ! (recorded) on a failure. A stopping root: at_root, the time there.
        logical function search_roots() result(ok)
            logical :: stop_here
            real(wp) :: t_hi
            character(len=:), allocatable :: scan_msg   ! (set on a failure only)
            ok = .true.
            select case (outcome)
            case (outcome_reached, outcome_pass_end, outcome_stiff, outcome_nonstiff)
                t_hi = t_stop
                if (outcome == outcome_reached) t_hi = min(stepper%time(), tout)
                call self%ev%scan(stepper, t_hi, stop_here, stat, scan_msg)
                if (len(self%ev%log) > 0) then
                    call log_event(core, self%ev%log(:len(self%ev%log) - 1))
                    self%ev%log = ''
                end if
                if (stat /= regdae_success) then
                    call fail(stat, scan_msg)
                    ok = .false.
                else if (stop_here) then
                    at_root = .true.
                    t_reached = self%ev%t_root
                else if (outcome /= outcome_reached .and. self%ev%t_state /= t_stop) then
                    call stepper%interpolate(t_stop, stat)   ! the state there for the hand-over
                    self%ev%t_state = t_stop
                end if
            end select
        end function search_roots

        ! Success at tout, or the resolution warning when the monitor flagged a new
        ! unresolved singular pass during this advance (logged as an event too); at a
        ! stopping root, regdae_root_found.
        subroutine record_done()
            if (core%monitor%weights_new) then
                core%monitor%weights_new = .false.
                call log_event(core, core%monitor%weights_message)
            end if
            if (at_root) then
                call self%record(regdae_root_found, 'an event function that stops has a root at t = '// &
                                 format_real(core%t, 16), stat)
            else if (core%monitor%unresolved_new) then
                core%monitor%unresolved_new = .false.
                call log_event(core, 't = '//format_real(core%t)//': unresolved: '//core%monitor%unresolved_message)
                call self%record(regdae_warn_unresolved, core%monitor%unresolved_message, stat)
            else
                call self%record(regdae_success, '', stat)
            end if
        end subroutine record_done

        ! x (and v) from the integrator's state u (the augmented formulation's unpacked).
        subroutine copy_state()
            integer :: i
            sys => stepper%augmented()
            if (associated(sys)) then
                call sys%unpack(u, u, q=x)
                if (present(v)) call sys%unpack(u, u, v=v)
                return
            end if
            do i = 1, nx   ! (loops over the few entries: cheaper than the section assignments)
                x(i) = u(i)
            end do
            if (present(v)) then
                do i = 1, nx
                    v(i) = u(nx + i)
                end do
            end if
        end subroutine copy_state

        subroutine fail(code, text)
            integer, intent(in) :: code
            character(len=*), intent(in) :: text
            call self%record(code, text, stat)
            if (associated(core)) self%t = core%t
        end subroutine fail

        ! The monitor saw the velocity jump across a singular interval, or the
        ! position constraint drift: stop.
        logical function branch_alarm()
            integer :: code
            branch_alarm = core%monitor%alarm
            if (.not. branch_alarm) return
            if (present(y)) y = ieee_value(1.0_wp, ieee_quiet_nan)
            call alarm_status(core, code, msg)
            call fail(code, msg)
        end function branch_alarm
    end subroutine solver_advance

    ! Set the status of a call and its message.
    subroutine solver_record(self, code, text, stat)
        class(solver_engine), intent(inout) :: self
        integer, intent(in) :: code
        character(len=*), intent(in) :: text
        integer, intent(out) :: stat
        stat = code
        self%last_stat = code
        if (.not. allocated(self%last_message)) then
            self%last_message = text
        else if (len(text) > 0 .or. len(self%last_message) > 0) then   ! no reallocation per output
            self%last_message = text
        end if
    end subroutine solver_record

    subroutine solver_finalize(self)
        type(solver_engine), intent(inout) :: self
        call self%destroy()
    end subroutine solver_finalize


end module regdae_solver_front
