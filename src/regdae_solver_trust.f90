!> The solver users hold, `regdae_solver`: the integration engine
!! (`regdae_solver_front`) with what makes its status ok mean "right to the
!! tolerance" where the regularization acts, and an estimate of the error.
!!
!! **Pass check** (option `pass_check`, default on; problems of order 1 and 2).
!! The local error test cannot see what a singular pass does to the solution:
!! the integration errors of the approach are amplified where G loses rank, and
!! the regularization itself acts there. Each pass is therefore integrated again
!! from the checkpoint before it (the engine's last sample on the approach, where
!! sigma_min(GB) was still 2 times the singular threshold) by companions at
!! rtol/kappa^k, k = 1, 2, ... (kappa = 10, atol likewise, an automatic eps with
!! its rule's rtol^2, the weights in force, no checks), and held against the
!! solution in its own error weights: the first level k whose state differs from
!! level k+1 by at most `pass_tol` (in units of rtol |z| + atol, over the state
!! z = (x, v) in the error test) is the answer, level 0 being the solution
!! itself. At the end of the pass (the engine stops there) the solution continues
!! from the state of level answer + 1 (computed already: local extrapolation, so
!! that the errors of many passes do not add up at the answer's size); at outputs
!! inside the pass that level's values are returned. If no two levels agree (at most 3 levels, and none below rtol
!! 1e-13) the finest level is taken and `advance` returns
!! `regdae_warn_unresolved` with the differences. Statistics: `pass_checks`,
!! `passes_resolved`, `passes_unresolved`, `pass_error`, `companion_steps`.
!!
!! **Error estimate** (option `error_estimate`, default off): a second solver
!! on the same problem at rtol/10 and atol/10, with its own automatic parameters
!! and pass checks, alongside; at every output `error_estimate(e)` gives
!! e = x_companion - x, and statistics()%error_estimate its norm in error weights.
module regdae_solver_trust
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_options, only: solver_options
    use regdae_problem, only: dae_problem
    use regdae_second_order_problem, only: second_order_problem
    use regdae_higher_order_problem, only: higher_order_problem
    use regdae_solver_front, only: solver_engine, solver_stats, events_length
    use regdae_events, only: event_functions
    use regdae_format, only: format_real, format_int
    implicit none
    private

    public :: solver_stats

    !> The companions' tolerances are the solution's divided by kappa^k.
    real(wp), parameter :: kappa = 10.0_wp
    !> At most this many companion levels per pass.
    integer, parameter :: max_levels = 3
    !> The eps probe's eps over its level's: where consecutive levels share the automatic
    !! eps (its floor), their agreement says nothing about the regularization error.
    real(wp), parameter :: eps_probe = 10.0_wp
    !> Inside a pass, a solution farther than this times pass_tol from level 1 (another
    !! branch, not an integration error a tighter tolerance shrinks) restarts from the level.
    real(wp), parameter :: branch_gap = 1000.0_wp
    !> No companion below this rtol (the integrators' own floor).
    real(wp), parameter :: rtol_floor = 1.0e-13_wp

    ! A companion engine, allocated when started (a pointer: no array of finalizable
    ! objects as a component, which gfortran 12 finalizes wrongly).
    type :: engine_slot
        type(solver_engine), pointer :: engine => null()
    end type engine_slot

    ! The companions of the current singular pass: level(k) at rtol/kappa^k from
    ! the checkpoint (t_start, z_start).
    type :: pass_ladder
        type(engine_slot) :: level(max_levels)
        type(engine_slot) :: probe(0:2)  ! the eps probes: level probe_level's tolerance, eps_probe^j x its eps
                                         ! (probe(0), x(eps), for level 0 only)
        integer :: probe_level = -1
        real(wp) :: d_probe = 0.0_wp   ! the estimated regularization error at the level's eps
        real(wp) :: d_probes(2) = 0.0_wp   ! |x(10 eps) - x(eps)|, |x(100 eps) - x(10 eps)|
        integer :: levels = 0          ! levels started
        logical :: active = .false.
        logical :: warned = .false.    ! this pass has warned already
        logical :: outputs_warned = .false.   ! this pass has warned of its earlier outputs
        logical :: regularized = .false.   ! the solution entered the regularization's layer in this pass
        integer :: output_level = max_levels + 1   ! the lowest level whose values were returned at the
                                                   ! outputs inside the solution's current step
        real(wp) :: t_output = 0.0_wp      ! the first of those outputs from that level
        real(wp) :: step_end = -huge(1.0_wp)   ! the end of that step (the solution's integrator time)
        integer :: prev_level = max_levels + 1 ! output_level and t_output of the step before, until
        real(wp) :: prev_output = 0.0_wp       ! the first check after it
        real(wp) :: t_start = 0.0_wp
        real(wp), allocatable :: z_start(:)
        real(wp), allocatable :: z(:, :)   ! (n, 0:max_levels): the states at the last check
        real(wp) :: d(max_levels) = 0.0_wp ! d(k): distance between levels k-1 and k there
        integer :: over_budget = 0         ! the level that exceeded its step budget (0: none)
        integer :: dead_level = max_levels + 1   ! the lowest level that failed in this pass: not restarted
        logical :: probes_failed = .false.       ! the eps probes failed in this pass: not restarted
        logical :: fine_probes = .false.         ! the probes at the answer's tolerance found the regularization
                                                 ! error above pass_tol: those at the next level's decide
    end type pass_ladder

    !> A regularized DAE solver (doc/api.md): `init`, `advance`, `statistics`, ...
    type, public :: regdae_solver
        private
        ! the engine, through a pointer: gfortran 12 finalizes the components of the
        ! temporary it makes for `b = b`, which would destroy a shared engine
        type(solver_engine), pointer :: main => null()
        type(pass_ladder) :: ladder
        type(regdae_solver), pointer :: estimator => null()
        logical :: verify = .false.
        real(wp) :: pass_tol = 3.0_wp
        real(wp) :: rtol = 0.0_wp
        real(wp) :: t0 = 0.0_wp            ! the start (the solution's mean step density since)
        integer :: max_steps = 100000      ! the option max_steps: steps per call of advance
        integer :: max_level = 0
        integer :: pass_checks = 0, passes_resolved = 0, passes_unresolved = 0
        real(wp) :: pass_error = 0.0_wp
        integer(int64) :: retired_steps = 0         ! steps of companions already destroyed
        real(wp), allocatable :: x_error(:)         ! error_estimate: x_companion - x at the last output
        real(wp) :: error_norm = -1.0_wp
        integer :: last_stat = regdae_err_not_initialized
        character(len=:), allocatable :: last_message
        logical :: assigned = .false.
        logical :: each_step = .false.     ! advance returns after every step (return_each_step)
    contains
        !> Set up a problem (see regdae_solver_front for the three forms):
        !! `init(problem, t0, x0, opts, stat)` (order 1), `init(problem, t0, x0, v0, opts, stat)`
        !! (order 2, mechanical), `init(problem, t0, xs0, opts, stat)` (order m >= 3); optional
        !! last argument `atol_vector`.
        generic :: init => init_first_order, init_second_order, init_higher_order
        procedure, private :: init_first_order => trust_init_first
        procedure, private :: init_second_order => trust_init_second
        procedure, private :: init_higher_order => trust_init_higher
        !> Integrate to `tout`; return x(tout), the multiplier y(tout) (lambda for a
        !! mechanical problem) and, for second-order problems, optionally v(tout) and a(tout).
        procedure :: advance => trust_advance
        !> Event functions: `set_events(fn, n, stat [, direction] [, stop])` (doc/api.md, Events).
        procedure :: set_events => trust_set_events
        !> After regdae_root_found: +1 / -1 / 0 per event function (a root there, its direction).
        procedure :: roots => trust_roots
        !> `return_each_step(on)`: advance returns after every step (before tout, the state at
        !! the step's end), as DASSL's INFO(3) = 1; off by default.
        procedure :: return_each_step => trust_return_each_step
        !> Statistics of the integration so far.
        procedure :: statistics => trust_statistics
        !> Message of the last call (empty after success).
        procedure :: message => trust_message
        !> The resolved least-squares solver.
        procedure :: lsq_method => trust_lsq_method
        !> The log of integrator switches, weight changes and resolved passes, one line each.
        procedure :: events => trust_events
        !> The options in force, `auto` values resolved.
        procedure :: options => trust_options
        !> The resolved formulation and linear solver (codes of regdae_options).
        procedure :: formulation => trust_formulation
        procedure :: linear_solver => trust_linear_solver
        !> sigma_min(GB) at the last sample.
        procedure :: sigma_min => trust_sigma_min
        !> The singular intervals so far: (2, k) array of first and last sample times.
        procedure :: singular_intervals => trust_singular_intervals
        !> error_estimate=yes: e = x_companion - x at the last output (length n); false
        !! if there is no estimate.
        procedure :: error_estimate => trust_error_estimate
        !> Free everything (also done by `init` and finalization).
        procedure :: destroy => trust_destroy
        generic :: assignment(=) => assign_refused
        procedure, private :: assign_refused => trust_assign
        final :: trust_finalize
    end type regdae_solver

    interface
        !> The pass check at time t (submodule `regdae_solver_trust_passes`).
        module subroutine check_pass(self, t, ended, x, y, v, a, warn, warn_text, pending)
            type(regdae_solver), intent(inout) :: self
            real(wp), intent(in) :: t
            logical, intent(in) :: ended
            real(wp), intent(inout) :: x(:)
            real(wp), intent(inout), optional :: y(:), v(:), a(:)
            integer, intent(inout) :: warn
            character(len=:), allocatable, intent(inout) :: warn_text
            logical, intent(inout) :: pending   !! y and a are not set yet: false once a level's are returned
        end subroutine check_pass
        !> Destroy the eps probes, keeping their step counts.
        module subroutine retire_probe(self)
            type(regdae_solver), intent(inout) :: self
        end subroutine retire_probe
        !> Destroy level k of the ladder (the levels above it too), keeping their step counts.
        module subroutine retire(self, k)
            type(regdae_solver), intent(inout) :: self
            integer, intent(in) :: k
        end subroutine retire
    end interface

contains

    recursive subroutine trust_init_first(self, problem, t0, x0, opts, stat, atol_vector)
        class(regdae_solver), intent(inout) :: self
        class(dae_problem), intent(in) :: problem
        real(wp), intent(in) :: t0, x0(:)
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        real(wp), intent(in), optional :: atol_vector(:)
        call self%destroy()
        call ensure_engine(self)
        call self%main%init(problem, t0, x0, opts, stat, atol_vector)
        call after_init(self, opts, stat)
        self%t0 = t0
        if (.not. new_estimator(self, opts, stat)) return
        if (present(atol_vector)) then
            call self%estimator%init(problem, t0, x0, estimator_options(opts), stat, atol_vector/kappa)
        else
            call self%estimator%init(problem, t0, x0, estimator_options(opts), stat)
        end if
        call estimator_started(self, stat)
    end subroutine trust_init_first

    recursive subroutine trust_init_second(self, problem, t0, x0, v0, opts, stat, atol_vector)
        class(regdae_solver), intent(inout) :: self
        class(second_order_problem), intent(in) :: problem
        real(wp), intent(in) :: t0, x0(:), v0(:)
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        real(wp), intent(in), optional :: atol_vector(:)
        call self%destroy()
        call ensure_engine(self)
        call self%main%init(problem, t0, x0, v0, opts, stat, atol_vector)
        call after_init(self, opts, stat)
        self%t0 = t0
        if (.not. new_estimator(self, opts, stat)) return
        if (present(atol_vector)) then
            call self%estimator%init(problem, t0, x0, v0, estimator_options(opts), stat, atol_vector/kappa)
        else
            call self%estimator%init(problem, t0, x0, v0, estimator_options(opts), stat)
        end if
        call estimator_started(self, stat)
    end subroutine trust_init_second

    recursive subroutine trust_init_higher(self, problem, t0, xs0, opts, stat, atol_vector)
        class(regdae_solver), intent(inout) :: self
        class(higher_order_problem), intent(in) :: problem
        real(wp), intent(in) :: t0, xs0(:, :)
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        real(wp), intent(in), optional :: atol_vector(:)
        call self%destroy()
        call ensure_engine(self)
        call self%main%init(problem, t0, xs0, opts, stat, atol_vector)
        call after_init(self, opts, stat)
        self%t0 = t0
        self%verify = .false.   ! order >= 3: the Taylor weights leave their own error; no pass check
        call self%main%stop_at_pass_ends(.false.)
        if (.not. new_estimator(self, opts, stat)) return
        if (present(atol_vector)) then
            call self%estimator%init(problem, t0, xs0, estimator_options(opts), stat, atol_vector/kappa)
        else
            call self%estimator%init(problem, t0, xs0, estimator_options(opts), stat)
        end if
        call estimator_started(self, stat)
    end subroutine trust_init_higher

    ! The engine allocated (once; init and destroy keep it).
    subroutine ensure_engine(self)
        type(regdae_solver), intent(inout) :: self
        if (.not. associated(self%main)) allocate (self%main)
    end subroutine ensure_engine

    ! After the engine's init: the status, and the pass check's settings.
    subroutine after_init(self, opts, stat)
        type(regdae_solver), intent(inout) :: self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: stat
        self%assigned = .false.
        call record(self, stat, self%main%message())
        if (stat < 0) return
        self%pass_tol = opts%pass_tol
        self%rtol = opts%rtol
        self%max_steps = opts%max_steps
        self%max_level = 0
        do while (self%max_level < max_levels .and. opts%rtol/kappa**(self%max_level + 1) >= rtol_floor)
            self%max_level = self%max_level + 1
        end do
        self%verify = opts%pass_check .and. self%max_level > 0
        call self%main%stop_at_pass_ends(self%verify)
        allocate (self%x_error(0))
    end subroutine after_init

    ! The error estimate's companion: the user's options at rtol/10, atol/10.
    function estimator_options(opts) result(o)
        type(solver_options), intent(in) :: opts
        type(solver_options) :: o
        o = opts
        o%rtol = opts%rtol/kappa
        o%atol = opts%atol/kappa
        if (o%atol_v > 0.0_wp) o%atol_v = opts%atol_v/kappa
        o%error_estimate = .false.
    end function estimator_options

    ! error_estimate=yes after a successful init: the companion allocated (true),
    ! or refused with stat and a message (false). False without an estimate.
    recursive logical function new_estimator(self, opts, stat) result(wanted)
        type(regdae_solver), intent(inout) :: self
        type(solver_options), intent(in) :: opts
        integer, intent(inout) :: stat
        wanted = .false.
        if (stat < 0 .or. .not. opts%error_estimate) return
        if (opts%rtol/kappa < rtol_floor) then
            call record(self, regdae_err_bad_input, 'error_estimate=yes needs rtol >= '// &
                        format_real(kappa*rtol_floor)//' (its companion runs at rtol/10)', stat)
            call self%main%destroy()
            return
        end if
        allocate (self%estimator)
        wanted = .true.
    end function new_estimator

    recursive subroutine estimator_started(self, stat)
        type(regdae_solver), intent(inout) :: self
        integer, intent(inout) :: stat
        integer :: code
        if (stat < 0) then
            code = stat
            call record(self, code, 'error_estimate: the companion at rtol/10 could not start: '// &
                        self%estimator%message(), stat)
            call self%destroy()
            return
        end if
        call record(self, regdae_success, '', stat)
    end subroutine estimator_started

    recursive subroutine trust_advance(self, tout, x, y, stat, v, a)
        class(regdae_solver), intent(inout) :: self
        real(wp), intent(in) :: tout      !! output time (beyond the current time, or equal to it)
        real(wp), intent(out) :: x(:)     !! x(tout), length n
        real(wp), intent(out), optional :: y(:)   !! y(tout) (lambda for a mechanical problem), length m
        integer, intent(out) :: stat      !! regdae status code (> 0: a warning, x is returned)
        real(wp), intent(out), optional :: v(:)   !! second-order problems: v(tout)
        real(wp), intent(out), optional :: a(:)   !! second-order problems: the acceleration x''(tout)
        integer :: warn, estat
        character(len=:), allocatable :: warn_text
        real(wp) :: t_now
        real(wp), allocatable :: xe(:)
        logical :: ended, frozen, valid, pending
        real(wp) :: tc
        integer(int64) :: steps0
        warn = regdae_success   ! (warn_text is set with it: no allocation on the usual call)
        call ensure_engine(self)
        steps0 = self%main%steps_taken()
        do
            ! inside a pass being checked the outputs come from a companion level: the solution's
            ! multiplier and acceleration (one evaluation of the model each output) only if they
            ! do not (ex52 at rtol 1e-4, 1000 outputs: 128 evaluations)
            pending = .false.
            if (self%verify) then
                if (self%ladder%active) pending = present(y) .or. present(a)
            end if
            if (pending) then
                call self%main%advance(tout, x, stat=stat, v=v)
            else
                call self%main%advance(tout, x, y, stat, v, a)
            end if
            if (stat < 0) then
                if (pending .and. present(y)) y = ieee_value(1.0_wp, ieee_quiet_nan)
                call record(self, stat, self%main%message())
                return
            end if
            ! the engine stops at every pass end: max_steps holds for the whole call (the step
            ! count alone: statistics() on every call cost 0.36M instructions of ex52's 1000 outputs)
            if (self%main%time() < tout .and. self%main%steps_taken() - steps0 >= self%max_steps) then
                call record(self, regdae_err_integration, 'max_steps = '//format_int(self%max_steps)// &
                            ' steps taken in this call of advance, at t = '//format_real(self%main%time())// &
                            ' before tout = '//format_real(tout)//' (over '//format_int(self%pass_checks)// &
                            ' singular passes so far); x is the state there', stat)
                return
            end if
            if (stat > 0 .and. warn == regdae_success) then
                warn = stat
                warn_text = self%main%message()
            end if
            t_now = self%main%time()
            if (self%verify) then
                ended = self%main%take_pass_end()
                call self%main%checkpoint(tc, frozen, valid)
                if (frozen .and. valid) call check_pass(self, t_now, ended, x, y, v, a, warn, warn_text, pending)
            end if
            if (pending) then   ! the solution's own values at t_now (the engine is there: no step)
                call self%main%advance(t_now, x, y, estat, v, a)
                if (estat > 0 .and. warn == regdae_success) then
                    warn = estat
                    warn_text = self%main%message()
                end if
            end if
            if (.not. (t_now < tout) .or. stat == regdae_root_found .or. self%each_step) exit
        end do
        if (associated(self%estimator)) then
            allocate (xe(size(x)))
            call self%estimator%advance(t_now, xe, stat=estat)
            if (estat >= 0) then
                self%x_error = xe - x
                self%error_norm = self%main%state_distance(xe, x)
            else
                self%x_error = [real(wp) ::]
                self%error_norm = -1.0_wp
                if (warn == regdae_success) then
                    warn = regdae_warn_unresolved
                    warn_text = 'error_estimate: the companion at rtol/10 failed at t = '// &
                                format_real(self%estimator%main%time())//' ('//self%estimator%message()// &
                                '): no estimate from there on'
                end if
                call self%estimator%destroy()
                deallocate (self%estimator)
            end if
        end if
        if (stat == regdae_root_found) then
            call record(self, stat, self%main%message())
        else if (warn == regdae_success) then
            call record(self, warn, '', stat)
        else
            call record(self, warn, warn_text, stat)
        end if
    end subroutine trust_advance

    subroutine trust_set_events(self, fn, n, stat, direction, stop)
        class(regdae_solver), intent(inout) :: self
        class(event_functions), intent(in) :: fn   !! the event functions (copied)
        integer, intent(in) :: n                   !! their number (0: no events)
        integer, intent(out) :: stat               !! regdae_success or regdae_err_bad_input
        integer, intent(in), optional :: direction(:)   !! per function: +1, -1 or 0 (the default)
        logical, intent(in), optional :: stop(:)   !! per function: stop at its roots (the default) or not
        call ensure_engine(self)
        call self%main%set_events(fn, n, stat, direction, stop)
        call record(self, stat, self%main%message())
    end subroutine trust_set_events

    subroutine trust_return_each_step(self, on)
        class(regdae_solver), intent(inout) :: self
        logical, intent(in) :: on   !! return after every step
        call ensure_engine(self)
        self%each_step = on
        call self%main%return_each_step(on)
    end subroutine trust_return_each_step

    function trust_roots(self) result(found)
        class(regdae_solver), intent(in) :: self
        integer, allocatable :: found(:)
        if (associated(self%main)) then
            found = self%main%roots()
        else
            allocate (found(0))
        end if
    end function trust_roots


    recursive function trust_statistics(self) result(st)
        class(regdae_solver), intent(in) :: self
        type(solver_stats) :: st
        type(solver_stats) :: other
        integer :: k
        if (.not. associated(self%main)) return
        st = self%main%statistics()
        st%pass_checks = self%pass_checks
        st%passes_resolved = self%passes_resolved
        st%passes_unresolved = self%passes_unresolved
        st%pass_error = self%pass_error
        st%companion_steps = self%retired_steps
        do k = 1, self%ladder%levels
            other = self%ladder%level(k)%engine%statistics()
            st%companion_steps = st%companion_steps + other%steps
        end do
        do k = 0, 2
            if (.not. associated(self%ladder%probe(k)%engine)) cycle
            other = self%ladder%probe(k)%engine%statistics()
            st%companion_steps = st%companion_steps + other%steps
        end do
        if (associated(self%estimator)) then
            other = self%estimator%statistics()
            st%companion_steps = st%companion_steps + other%steps + other%companion_steps
        end if
        st%error_estimate = self%error_norm
    end function trust_statistics

    logical function trust_error_estimate(self, e) result(have)
        class(regdae_solver), intent(in) :: self
        real(wp), intent(out) :: e(:)   !! x_companion - x at the last output, length n
        have = associated(self%estimator) .and. size(self%x_error) == size(e) .and. size(e) > 0
        if (have) then
            e = self%x_error
        else
            e = ieee_value(1.0_wp, ieee_quiet_nan)
        end if
    end function trust_error_estimate

    ! message and events have automatic-length results (doc/methods.md, "No global state").
    function trust_message(self) result(msg)
        class(regdae_solver), intent(in) :: self
        character(len=trust_message_length(self)) :: msg
        if (allocated(self%last_message)) then
            msg = self%last_message
        else
            msg = status_message(self%last_stat)
        end if
    end function trust_message

    pure integer function trust_message_length(self) result(length)
        class(regdae_solver), intent(in) :: self
        length = reported_length(self%last_message, self%last_stat)
    end function trust_message_length

    function trust_events(self) result(text)
        class(regdae_solver), intent(in) :: self
        character(len=trust_events_length(self)) :: text
        if (len(text) > 0) text = self%main%events()
    end function trust_events

    pure integer function trust_events_length(self) result(length)
        class(regdae_solver), intent(in) :: self
        length = 0
        if (associated(self%main)) length = events_length(self%main)
    end function trust_events_length

    function trust_options(self) result(opts)
        class(regdae_solver), intent(in) :: self
        type(solver_options) :: opts
        if (associated(self%main)) opts = self%main%options()
    end function trust_options

    integer function trust_formulation(self)
        class(regdae_solver), intent(in) :: self
        trust_formulation = 0
        if (associated(self%main)) trust_formulation = self%main%formulation()
    end function trust_formulation

    integer function trust_linear_solver(self)
        class(regdae_solver), intent(in) :: self
        trust_linear_solver = 0
        if (associated(self%main)) trust_linear_solver = self%main%linear_solver()
    end function trust_linear_solver

    integer function trust_lsq_method(self)
        class(regdae_solver), intent(in) :: self
        trust_lsq_method = 0
        if (associated(self%main)) trust_lsq_method = self%main%lsq_method()
    end function trust_lsq_method

    real(wp) function trust_sigma_min(self)
        class(regdae_solver), intent(in) :: self
        trust_sigma_min = ieee_value(1.0_wp, ieee_quiet_nan)
        if (associated(self%main)) trust_sigma_min = self%main%sigma_min()
    end function trust_sigma_min

    function trust_singular_intervals(self) result(intervals)
        class(regdae_solver), intent(in) :: self
        real(wp), allocatable :: intervals(:, :)
        if (associated(self%main)) then
            intervals = self%main%singular_intervals()
        else
            allocate (intervals(2, 0))
        end if
    end function trust_singular_intervals

    ! The status and message of a call (stat, if present, gets the code).
    subroutine record(self, code, text, stat)
        type(regdae_solver), intent(inout) :: self
        integer, intent(in) :: code
        character(len=*), intent(in) :: text
        integer, intent(out), optional :: stat
        if (present(stat)) stat = code
        self%last_stat = code
        self%last_message = text
    end subroutine record

    recursive subroutine trust_destroy(self)
        class(regdae_solver), intent(inout) :: self
        if (associated(self%main)) call self%main%destroy()
        self%ladder%levels = max_levels
        call retire(self, 1)
        call retire_probe(self)
        self%ladder%active = .false.
        if (associated(self%estimator)) then
            call self%estimator%destroy()
            deallocate (self%estimator)
        end if
        self%estimator => null()
        self%verify = .false.
        self%pass_checks = 0
        self%passes_resolved = 0
        self%passes_unresolved = 0
        self%pass_error = 0.0_wp
        self%retired_steps = 0
        self%error_norm = -1.0_wp
        if (allocated(self%x_error)) deallocate (self%x_error)
    end subroutine trust_destroy

    subroutine trust_assign(lhs, rhs)
        class(regdae_solver), intent(inout) :: lhs
        class(regdae_solver), intent(in) :: rhs
        if (associated(lhs%main) .and. associated(rhs%main)) then
            if (lhs%main%same_engine(rhs%main)) return   ! a = a
        end if
        call lhs%destroy()
        call ensure_engine(lhs)
        if (associated(rhs%main)) lhs%main = rhs%main   ! the engine's assignment leaves it uninitialized, saying why
        lhs%assigned = .true.
        call record(lhs, regdae_err_not_initialized, 'a regdae_solver cannot be copied by assignment (it owns '// &
                    'IDA memory): this one is uninitialized; call init on it')
    end subroutine trust_assign

    subroutine trust_finalize(self)
        type(regdae_solver), intent(inout) :: self
        call self%destroy()
        if (associated(self%main)) deallocate (self%main)
    end subroutine trust_finalize

end module regdae_solver_trust
