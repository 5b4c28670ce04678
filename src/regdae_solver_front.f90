!> The regdae solver front: a regularized index-2 or index-3 DAE integrated by
!! one of the backends, SUNDIALS IDA (`regdae_ida_backend`) or the explicit
!! Dormand-Prince integrator (`regdae_explicit_rk`). The front checks the
!! input, computes consistent initial values, drives the backend from output
!! to output, samples the diagnostics (`regdae_monitor`) and keeps the status
!! and statistics. The state of one problem is `regdae_solver_core`'s record;
!! the monitor's start and samples are in `regdae_solver_sampling`, the
!! switching policy of integrator=auto in `regdae_integrator_switching`, and
!! the augmented formulation's scales for the automatic rules in
!! `regdae_augmented_rules`.
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
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_problem, only: dae_problem
    use regdae_second_order_problem, only: second_order_problem, velocity_constraint
    use regdae_mechanical_problem, only: mechanical_problem, mechanical_structure, &
                                         structured_velocity_constraint
    use regdae_higher_order_problem, only: higher_order_problem
    use regdae_linear_problem, only: linear_dae_problem
    use regdae_velocity_index2, only: new_velocity_index2, velocity_index2_problem
    use regdae_projection, only: project_first_order, project_second_order
    use regdae_sparse_projection, only: project_structured
    use regdae_options
    use regdae_regularization, only: regularized_dae
    use regdae_regularized_system, only: new_regularized_system
    use regdae_augmented_system, only: augmented_system, user_routine_failure
    use regdae_differences, only: central_difference_step
    use regdae_solver_stats, only: solver_stats
    use regdae_monitor, only: alarm_jump, alarm_invariant, alarm_work
    use regdae_auto_rules, only: automatic_eps_factor, automatic_eps, baumgarte_weights, dense_motion_scales, rms
    use regdae_work_energy, only: kinetic_energy_and_power
    use regdae_scales, only: drift_rtol_min
    use regdae_format, only: format_real, format_int
    use regdae_solver_core, only: solver_core, new_core, log_event, active_integrator
    use regdae_augmented_rules, only: mass_diagonal, gb_row_scale, augmented_motion_scales
    use regdae_solver_sampling, only: start_monitor, start_monitor_augmented
    use regdae_integrator, only: integrator, outcome_reached, outcome_pass_end, outcome_stiff, outcome_nonstiff, &
                                 outcome_alarm, outcome_failed, outcome_exhausted
    use regdae_dopri5_integrator, only: dopri5_integrator, dopri5_in_slot
    use regdae_ida_integrator, only: ida_integrator, ida_in_slot
    use regdae_integrator_switching, only: hand_over
    use regdae_auto_parameters, only: set_state_tolerances, resolve_auto_parameters, resolve_augmented_parameters, &
                                      augmented_eps, check_first_step, time_resolution
    use regdae_jacobian_check, only: check_second_order_jacobian, check_structured_jacobian
    implicit none
    private

    public :: solver_stats

    !> A regularized DAE solver on IDA (see the module documentation).
    type, public :: solver_engine
        private
        type(solver_core), pointer :: core => null()
        real(wp) :: t = 0.0_wp   ! time reached
        integer :: last_stat = regdae_err_not_initialized
        character(len=:), allocatable :: last_message
        logical :: assigned = .false.   ! the target of an assignment (which does not copy)
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

contains

    subroutine solver_init_first(self, problem, t0, x0, opts, stat, atol_vector)
        class(solver_engine), intent(inout) :: self
        class(dae_problem), intent(in) :: problem   !! the index-2 DAE (copied)
        real(wp), intent(in) :: t0                  !! initial time
        real(wp), intent(in) :: x0(:)               !! x(t0), length n; must satisfy g(x0, t0) = 0
        type(solver_options), intent(in) :: opts    !! options (validated here)
        integer, intent(out) :: stat                !! regdae status code
        real(wp), intent(in), optional :: atol_vector(:)   !! absolute tolerance per component of the state
                                                          !! (replaces atol, atol_v; second order: positions,
                                                          !! then velocities; order m: x, ..., x^(m-1))

        if (.not. self%check_input(t0, x0, x0, problem%n, problem%m, opts, stat)) return
        if (.not. formulation_fits(self, opts, stat)) return
        call new_core(self%core)
        if (present(atol_vector)) self%core%atol_z = atol_vector
        self%core%nx = problem%n
        select type (problem)
        class is (linear_dae_problem)
            self%core%multiplier_sign = -1.0_wp   ! section 3 writes x' = A x + B y + q
        end select
        call self%core%model%init_first_order(problem, opts, lsq_normal, stat)
        if (stat /= 0) then
            call self%record(regdae_err_memory, self%core%model%message, stat)
            return
        end if
        call self%start(t0, x0, opts, stat)
    end subroutine solver_init_first

    subroutine solver_init_second(self, problem, t0, x0, v0, opts, stat, atol_vector)
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
        class(second_order_problem), allocatable :: copy
        real(wp) :: gval(problem%m), gnorm
        integer :: ustat
        logical :: augmented
        character(len=:), allocatable :: msg

        if (.not. self%check_input(t0, x0, v0, problem%n, problem%m, opts, stat)) return
        ! Position and velocity constraints at t0 (the regularized system checks only one of them).
        allocate (copy, source=problem)
        ustat = 0
        call copy%constraint(t0, x0, gval, ustat)
        gnorm = 0.0_wp
        if (ustat == 0 .and. problem%m > 0) gnorm = maxval(abs(gval))
        if (ustat == 0) call initial_velocity_constraint(copy, t0, x0, v0, gval, ustat)
        if (ustat == regdae_err_memory) then
            call self%record(regdae_err_memory, 'at the initial point: the system refused the values of G ('// &
                             'the declared pattern)', stat)
            return
        else if (ustat == regdae_err_structure) then
            call self%record(regdae_err_structure, status_message(regdae_err_structure)//' at the initial point '// &
                             '(in constraint_jacobian_values)', stat)
            return
        else if (ustat /= 0) then
            call self%record(regdae_err_user_callback, 'at the initial point: a user routine of the constraint '// &
                             'reported failure (stat = '//format_int(ustat)//')', stat)
            return
        end if
        if (problem%m > 0) gnorm = max(gnorm, maxval(abs(gval)))
        if (.not. (gnorm <= opts%ic_tol)) then
            call self%record(regdae_err_inconsistent_ic, 'inconsistent initial values: max(|g(x0, t0)|, '// &
                             '|G v0 + g_t|) = '//format_real(gnorm)//' exceeds ic_tol = '//format_real(opts%ic_tol), stat)
            return
        end if
        if (opts%check_jacobians) then
            call check_second_order_jacobian(copy, t0, x0, ustat, msg)
            if (ustat /= regdae_success) then
                call self%record(ustat, msg, stat)
                return
            end if
        end if
        augmented = .false.
        select type (copy)
        class is (mechanical_problem)
            augmented = use_augmented(copy, opts)
        end select
        if (.not. augmented) then
            if (.not. formulation_fits(self, opts, stat)) return
        end if
        call new_core(self%core)
        if (present(atol_vector)) self%core%atol_z = atol_vector
        self%core%nx = problem%n
        self%core%second_order = .true.
        select type (copy)
        class is (mechanical_problem)
            self%core%multiplier_sign = -1.0_wp
            copy%mass_damping = opts%mass_damping
            if (augmented) then
                call self%start_augmented(copy, t0, x0, v0, opts, stat)
                return
            end if
        end select
        if (opts%index == 3) then
            call self%core%model%init_second_order(copy, opts, lsq_normal, stat)
        else
            call self%core%model%init_first_order(new_velocity_index2(copy), opts, lsq_normal, stat)
        end if
        if (stat /= 0) then
            call self%record(regdae_err_memory, self%core%model%message, stat)
            return
        end if
        call self%start(t0, [x0, v0], opts, stat)
    end subroutine solver_init_second

    subroutine solver_init_higher(self, problem, t0, xs0, opts, stat, atol_vector)
        class(solver_engine), intent(inout) :: self
        class(higher_order_problem), intent(in) :: problem   !! the order-m DAE (copied)
        real(wp), intent(in) :: t0                   !! initial time
        real(wp), intent(in) :: xs0(:, :)            !! (n, order): x, x', ..., x^(m-1) at t0
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        real(wp), intent(in), optional :: atol_vector(:)   !! absolute tolerance per component of the state
                                                          !! (replaces atol, atol_v; second order: positions,
                                                          !! then velocities; order m: x, ..., x^(m-1))
        class(higher_order_problem), allocatable :: copy
        real(wp) :: gval(problem%m), gt(problem%m), gnorm
        real(wp), allocatable :: gx(:, :)
        integer :: ustat, astat

        if (problem%order < 3 .or. size(xs0, 2) /= problem%order) then
            call self%record(regdae_err_bad_input, 'a higher_order_problem needs order >= 3 and xs0(n, order); '// &
                             'got order '//format_int(problem%order)//' and '//format_int(size(xs0, 2))// &
                             ' columns', stat)
            return
        end if
        if (.not. self%check_input(t0, xs0(:, 1), xs0(:, 2), problem%n, problem%m, opts, stat)) return
        if (.not. formulation_fits(self, opts, stat)) return
        if (.not. all(ieee_is_finite(xs0))) then
            call self%record(regdae_err_bad_input, 'xs0 contains NaN or Inf', stat)
            return
        end if
        allocate (gx(problem%m, problem%n), stat=astat)
        if (astat /= 0) then
            call self%record(regdae_err_memory, 'out of memory: G at the initial point ('//format_int(problem%m)// &
                             ' x '//format_int(problem%n)//' reals) was refused', stat)
            return
        end if
        allocate (copy, source=problem)
        ustat = 0
        call copy%constraint(t0, xs0(:, 1), gval, ustat)
        if (ustat == 0) call copy%constraint_jacobian(t0, xs0(:, 1), gx, ustat)
        if (ustat == 0) call copy%constraint_dt(t0, xs0(:, 1), gt, ustat)
        if (ustat /= 0) then
            call self%record(regdae_err_user_callback, 'at the initial point: a user routine of the constraint '// &
                             'reported failure (stat = '//format_int(ustat)//')', stat)
            return
        end if
        gnorm = 0.0_wp
        if (problem%m > 0) gnorm = max(maxval(abs(gval)), maxval(abs(matmul(gx, xs0(:, 2)) + gt)))
        if (.not. (gnorm <= opts%ic_tol)) then
            call self%record(regdae_err_inconsistent_ic, 'inconsistent initial values: max(|g(x0, t0)|, '// &
                             '|G x0'' + g_t|) = '//format_real(gnorm)//' exceeds ic_tol = '//format_real(opts%ic_tol), stat)
            return
        end if
        call new_core(self%core)
        if (present(atol_vector)) self%core%atol_z = atol_vector
        self%core%nx = problem%n
        self%core%second_order = .true.
        call self%core%model%init_higher_order(copy, opts, lsq_normal, stat)
        if (stat /= 0) then
            call self%record(regdae_err_memory, self%core%model%message, stat)
            return
        end if
        call self%start(t0, reshape(xs0, [size(xs0)]), opts, stat)
    end subroutine solver_init_higher

    ! Common checks of init; false (with stat and message set) if the input is bad.
    logical function check_input(self, t0, x0, v0, n, m, opts, stat) result(ok)
        class(solver_engine), intent(inout) :: self
        real(wp), intent(in) :: t0, x0(:), v0(:)
        integer, intent(in) :: n, m
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        character(len=:), allocatable :: msg
        integer :: code

        call self%destroy()
        self%t = t0
        self%assigned = .false.
        ok = .false.
        call validate_options(opts, code, msg)
        if (code /= regdae_success) then
            call self%record(code, msg, stat)
        else if (n < 1 .or. m < 0 .or. m > n) then
            call self%record(regdae_err_bad_input, 'problem sizes must satisfy 1 <= n and 0 <= m <= n (n = '// &
                             format_int(n)//', m = '//format_int(m)//')', stat)
        else if (size(x0) /= n .or. size(v0) /= n) then
            call self%record(regdae_err_bad_input, 'x0 (and v0) must have length n = '//format_int(n)// &
                             '; got '//format_int(size(x0))//' (and '//format_int(size(v0))//')', stat)
        else if (.not. ieee_is_finite(t0)) then
            call self%record(regdae_err_bad_input, 't0 is NaN or Inf', stat)
        else if (.not. (all(ieee_is_finite(x0)) .and. all(ieee_is_finite(v0)))) then
            call self%record(regdae_err_bad_input, 'x0 (or v0) contains NaN or Inf', stat)
        else
            ok = .true.
        end if
    end function check_input

    ! G v0 + g_t at t0: from the declared pattern of G for a mechanical problem that
    ! declares its structure (O(nonzeros) memory), otherwise from the dense G.
    subroutine initial_velocity_constraint(problem, t0, x0, v0, val, stat)
        class(second_order_problem), intent(inout) :: problem
        real(wp), intent(in) :: t0, x0(:), v0(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        type(mechanical_structure) :: st
        select type (problem)
        class is (mechanical_problem)
            st = problem%structure()
            if (st%declared) then
                call structured_velocity_constraint(problem, st%constraint, t0, x0, v0, val, stat)
                return
            end if
        end select
        call velocity_constraint(problem, t0, x0, v0, val, stat)
    end subroutine initial_velocity_constraint

    ! formulation=auto takes the augmented formulation for a mechanical problem
    ! that declares its structure and is large enough, with M positive definite
    ! and integrator ida or auto (which is then IDA: the explicit integrator works on
    ! the eliminated formulation); formulation=augmented always (its setup refuses
    ! what does not fit).
    logical function use_augmented(problem, opts)
        class(mechanical_problem), intent(in) :: problem
        type(solver_options), intent(in) :: opts
        type(mechanical_structure) :: st
        use_augmented = (opts%formulation == formulation_augmented)
        if (opts%formulation /= formulation_auto) return
        if (opts%integrator == integrator_dopri5 .or. opts%mass_damping > 0.0_wp .or. problem%n < augmented_min_n) return
        st = problem%structure()
        use_augmented = st%declared
    end function use_augmented

    ! The dense formulations: refuse formulation=augmented and the structured
    ! linear solvers (the problem is not a mechanical one, or auto chose dense).
    logical function formulation_fits(self, opts, stat) result(ok)
        class(solver_engine), intent(inout) :: self
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        ok = .true.
        if (opts%formulation == formulation_augmented) then
            call self%record(regdae_err_bad_input, 'formulation=augmented needs a mechanical_problem', stat)
            ok = .false.
        else if (opts%linear_solver == linear_solver_band .or. opts%linear_solver == linear_solver_sparse) then
            call self%record(regdae_err_bad_input, 'linear_solver='//linear_solver_name(opts%linear_solver)// &
                             ' needs the augmented formulation (a mechanical problem that declares its structure, '// &
                             'or formulation=augmented); the Newton matrix here is dense', stat)
            ok = .false.
        end if
    end function formulation_fits

    ! The augmented formulation (regdae_augmented_system): the sparse residual on
    ! IDA with a dense, band or sparse linear solver, consistent initial values by
    ! IDACalcIC, the diagnostics from IDA's state.
    subroutine solver_start_augmented(self, problem, t0, q0, v0, opts, stat)
        class(solver_engine), intent(inout) :: self
        class(mechanical_problem), intent(in) :: problem
        real(wp), intent(in) :: t0, q0(:), v0(:)
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        type(solver_core), pointer :: core
        type(augmented_system) :: sys
        type(ida_integrator), pointer :: ida
        real(wp), allocatable :: u0(:), up0(:), id(:)
        character(len=:), allocatable :: msg

        core => self%core
        core%opts = opts
        core%augmented = .true.
        core%formulation = formulation_augmented
        core%active = integrator_ida
        core%events = ''
        core%n = 2*problem%n
        core%m = problem%m
        core%t = t0
        call set_state_tolerances(core, stat, msg)
        if (stat /= regdae_success) then
            call fail(stat, msg)
            return
        end if
        call sys%setup(problem, opts, stat)
        if (stat /= regdae_success) then
            call fail(stat, sys%message)
            return
        end if
        call resolve_augmented_parameters(core, sys, t0, q0, v0, stat, msg)
        if (stat /= regdae_success) then
            call fail(stat, msg)
            return
        end if
        core%neq = sys%neq
        core%linear_solver = opts%linear_solver
        ! KLU on the grouped Newton matrix was the fastest per step at every chain size
        ! measured (N = 2 ... 1024: 1.1-2.4x faster than band and dense, doc/performance.md)
        if (core%linear_solver == linear_solver_auto) core%linear_solver = linear_solver_sparse
        allocate (u0(sys%neq), up0(sys%neq), id(sys%neq), core%y_work(core%m))
        call sys%initial_guess(q0, v0, u0, up0, id)
        call augmented_eps(core, sys, t0, u0)
        core%excluded = sys%excluded_unknowns(opts%excluded)
        if (opts%exclusion == exclusion_off) core%excluded = .false.
        ida => ida_in_slot(core)
        call ida%ida%create(sys, core%opts, core%linear_solver, core%excluded, t0, u0, up0, stat, msg, &
                            sys%tolerance_vector(core%atol_z(1:problem%n), core%atol_z(problem%n + 1:), opts%atol))
        if (stat /= regdae_success) then
            call fail(stat, msg)
            return
        end if
        call ida%ida%calc_ic(id, t0 + 1.0e-3_wp*max(1.0_wp, abs(t0)), stat, msg)
        if (stat /= regdae_success) then
            call fail(stat, 'at the initial point: '//msg)
            return
        end if
        if (opts%check_jacobians) then
            call ida%ida%check_grouped_jacobian(t0, 1.0e3_wp/max(1.0_wp, abs(t0)), stat, msg)
            if (stat == regdae_success) call check_structured_jacobian(problem, sys, t0, q0, stat, msg)
            if (stat /= regdae_success) then
                call fail(stat, msg)
                return
            end if
        end if
        call start_monitor_augmented(core, t0, core%opts%eps)
        if (opts%invariant_tol > 0.0_wp .and. .not. (core%monitor%invariant0 == core%monitor%invariant0)) then
            call fail(regdae_err_bad_input, 'invariant_tol > 0, but the problem has no invariant at t0 '// &
                      '(override `invariant` of the second-order problem)')
            return
        end if
        call self%record(regdae_success, '', stat)
    contains
        subroutine fail(code, text)
            integer, intent(in) :: code
            character(len=*), intent(in) :: text
            call self%record(code, text, stat)
            call self%destroy()
        end subroutine fail
    end subroutine solver_start_augmented

    ! With the model set up: consistent initial values, then the IDA objects.
    subroutine solver_start(self, t0, z0, opts, stat)
        class(solver_engine), intent(inout) :: self
        real(wp), intent(in) :: t0, z0(:)
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        type(solver_core), pointer :: core
        type(dopri5_integrator), pointer :: dopri5
        type(ida_integrator), pointer :: ida
        character(len=:), allocatable :: msg
        real(wp), allocatable :: y0(:), zp0(:)
        integer :: lsq, n, m, nx
        logical :: recoverable
        real(wp) :: gnorm

        core => self%core
        core%opts = opts
        core%n = size(z0)
        core%m = core%model%m
        core%t = t0
        n = core%n
        m = core%m
        nx = core%model%n

        call core%model%evaluate(t0, z0, stat, recoverable)
        if (stat /= regdae_success) then
            call fail(stat, 'at the initial point: '//core%model%message)
            return
        end if
        gnorm = 0.0_wp
        if (m > 0) gnorm = maxval(abs(core%model%g))
        if (.not. (gnorm <= opts%ic_tol)) then
            call fail(regdae_err_inconsistent_ic, 'inconsistent initial values: max |g(x0, t0)| = '// &
                      format_real(gnorm)//' exceeds ic_tol = '//format_real(opts%ic_tol))
            return
        end if
        lsq = opts%lsq
        if (lsq == lsq_auto) lsq = lsq_checked   ! by conditioning, per solve (regdae_damped_lsq)
        core%model%lsq = lsq
        call set_state_tolerances(core, stat, msg)
        if (stat /= regdae_success) then
            call fail(stat, msg)
            return
        end if
        call resolve_auto_parameters(core, t0, z0, stat, msg)
        if (stat /= regdae_success) then
            call fail(stat, msg)
            return
        end if
        allocate (y0(m), zp0(n))
        call core%model%solve_multiplier(t0, y0, stat)
        if (stat /= regdae_success) then
            call fail(stat, 'at the initial point: '//core%model%message)
            return
        end if
        call core%model%dynamics_slope(z0, y0, zp0)   ! (x', ..., x^(m-1), x^(m))
        call start_monitor(core, t0, z0, zp0)
        core%t0 = t0
        ! (allocated explicitly: the reallocating assignment to a component never allocated
        ! reads its undefined bounds, which UBSan reports as an integer overflow)
        if (allocated(core%z0)) deallocate (core%z0)
        allocate (core%z0, source=z0)
        if (opts%invariant_tol > 0.0_wp .and. .not. (core%monitor%invariant0 == core%monitor%invariant0)) then
            call fail(regdae_err_bad_input, 'invariant_tol > 0, but the problem has no invariant at t0 '// &
                      '(override `invariant` of the second-order problem; first-order problems have none)')
            return
        end if

        core%neq = n
        core%formulation = formulation_eliminated
        if (opts%formulation == formulation_multiplier) core%formulation = formulation_multiplier
        if (opts%formulation == formulation_multiplier) core%neq = n + m
        allocate (core%excluded(core%neq), source=.false.)
        if (opts%exclusion /= exclusion_off) then
            core%excluded(n + 1:) = .true.
            if (core%model%order >= 2 .and. opts%excluded == excluded_vy) core%excluded(nx + 1:n) = .true.
        end if
        allocate (core%y_work(m), core%zp_work(n))
        if (opts%h_init == 0.0_wp) then
            call check_first_step(core, t0, z0, zp0, stat, msg)
            if (stat /= regdae_success) then
                call fail(stat, msg)
                return
            end if
        end if
        ! integrator=auto: dopri5 first (the eliminated formulation only), IDA created
        ! when the stiffness test hands over
        core%active = opts%integrator
        core%events = ''
        if (opts%integrator == integrator_auto) then
            core%active = merge(integrator_dopri5, integrator_ida, core%formulation == formulation_eliminated)
            ! Regularization layers far thinner than the automatic eps's (a user's eps below
            ! 1/100 of it): the explicit method steps through them inaccurately, without an
            ! alarm (doc/methods.md); IDA passes them
            if (core%active == integrator_dopri5 .and. core%m > 0) then
                if (core%model%eps < core%eps_auto0/100.0_wp) then
                    core%active = integrator_ida
                    call log_event(core, 't = '//format_real(t0)//': ida from the start (eps = '// &
                                   format_real(core%model%eps)//' is below 1/100 of the automatic eps for this '// &
                                   'rtol: layers too thin for the explicit method)')
                end if
            end if
            core%switching = (core%active == integrator_dopri5)
        end if
        if (core%active == integrator_dopri5) then
            dopri5 => dopri5_in_slot(core)
            call dopri5%start(t0, z0, stat, msg, h0=opts%h_init)
            if (stat /= regdae_success) then
                call fail(stat, 'dopri5: the slope at the initial point failed: '//core%model%message)
                return
            end if
            call self%record(regdae_success, '', stat)
            return
        end if
        ida => ida_in_slot(core)
        call ida%start(t0, z0, stat, msg, zp=zp0, y=y0)
        if (stat /= regdae_success) then
            call fail(stat, msg)
            return
        end if
        call self%record(regdae_success, '', stat)
    contains
        subroutine fail(code, text)
            integer, intent(in) :: code
            character(len=*), intent(in) :: text
            call self%record(code, text, stat)
            call self%destroy()
        end subroutine fail
    end subroutine solver_start

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
                                          !! (augmented formulation: IDA's interpolated v')
        type(solver_core), pointer :: core
        class(integrator), pointer :: stepper
        type(augmented_system), pointer :: sys
        real(c_double), pointer :: u(:)
        character(len=:), allocatable :: msg
        logical :: recoverable
        integer :: nx, outcome
        real(wp) :: t_reached, t_stop

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
        if (tout > core%t) then
            ! The integrator in charge to tout; with integrator=auto the explicit one hands
            ! over to the implicit one where the system is stiff, and back where it is not
            ! (regdae_integrator_switching). With stop_at_pass_end, the integrator stops
            ! early at the end of a singular pass.
            do
                stepper => active_integrator(core)
                u => stepper%state()
                call stepper%advance(tout, t_stop, outcome, stat, msg)
                select case (outcome)
                case (outcome_reached)
                    exit
                case (outcome_pass_end)
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
                ! No first step fits (IDA: "tout too close to t0"); later, IDA and dopri5
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

        ! Success at tout, or the resolution warning when the monitor flagged a new
        ! unresolved singular pass during this advance (logged as an event too).
        subroutine record_done()
            if (core%monitor%weights_new) then
                core%monitor%weights_new = .false.
                call log_event(core, core%monitor%weights_message)
            end if
            if (core%monitor%unresolved_new) then
                core%monitor%unresolved_new = .false.
                call log_event(core, 't = '//format_real(core%t)//': unresolved: '//core%monitor%unresolved_message)
                call self%record(regdae_warn_unresolved, core%monitor%unresolved_message, stat)
            else
                call self%record(regdae_success, '', stat)
            end if
        end subroutine record_done

        ! x (and v) from the integrator's state u (the augmented formulation's unpacked).
        subroutine copy_state()
            sys => stepper%augmented()
            if (associated(sys)) then
                call sys%unpack(u, u, q=x)
                if (present(v)) call sys%unpack(u, u, v=v)
                return
            end if
            x = u(1:nx)
            if (present(v)) v = u(nx + 1:2*nx)
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
            branch_alarm = core%monitor%alarm
            if (.not. branch_alarm) return
            if (present(y)) y = ieee_value(1.0_wp, ieee_quiet_nan)
            if (core%monitor%alarm_kind == alarm_jump) then
                call fail(regdae_err_branch, core%monitor%alarm_message// &
                          ': the solution probably changed branch there; x(tout) is returned but not trustworthy '// &
                          '(a smaller rtol or eps'//trim(merge(', or index=3,', '             ', index2()))// &
                          ' may help; jump_tol=0 turns this check off, at the risk of a run that leaves the '// &
                          'physical branch with status ok)')
            else if (core%monitor%alarm_kind == alarm_work) then
                call fail(regdae_err_work, core%monitor%alarm_message// &
                          ': x is returned but not trustworthy (the constraint forces did work: a drift, a '// &
                          'branch change or too stiff a regularization; a smaller rtol or smaller Baumgarte '// &
                          'weights may help; work_tol=0 turns this check off, at the risk of a wrong answer '// &
                          'with status ok)')
            else if (core%monitor%alarm_kind == alarm_invariant) then
                call fail(regdae_err_invariant, core%monitor%alarm_message// &
                          ': x(tout) is returned but not trustworthy (a smaller rtol, or smaller Baumgarte weights, '// &
                          'may help; invariant_tol=0 turns this check off)')
            else if (.not. core%opts%curvature .and. .not. index2()) then
                call fail(regdae_err_drift, core%monitor%alarm_message// &
                          ': x(tout) is returned but not trustworthy (with curvature=no the constraint error '// &
                          'has a floor of about |g_xx(v, v)|/gamma0 whatever the tolerance: curvature=yes '// &
                          'removes it; drift_tol=0 turns this check off, at the risk of positions that violate '// &
                          'the constraint with status ok)')
            else
                call fail(regdae_err_drift, core%monitor%alarm_message// &
                          ': x(tout) is returned but not trustworthy (a smaller rtol'// &
                          trim(merge(', index=3,', '          ', index2()))//' or a larger gamma may help; '// &
                          'drift_tol=0 turns this check off, at the risk of positions that violate the '// &
                          'constraint with status ok)')
            end if
        end function branch_alarm

        ! The problem is integrated at index 2 (the constraint on velocities only).
        logical function index2()
            index2 = core%second_order .and. core%opts%index == 2
        end function index2
    end subroutine solver_advance

    function solver_statistics(self) result(st)
        class(solver_engine), intent(in) :: self
        type(solver_stats) :: st
        class(integrator), pointer :: active

        st%t = self%t
        if (.not. associated(self%core)) return
        associate (core => self%core)
            st%switches = core%switches
            ! the implicit integrator's counts (none if it never ran) plus the explicit one's;
            ! the last step of the one in charge
            active => active_integrator(core)
            if (allocated(core%stiff)) call core%stiff%statistics(st, associated(active, core%stiff))
            if (allocated(core%nonstiff)) call core%nonstiff%statistics(st, associated(active, core%nonstiff))
            st%singular_passes = core%monitor%n_singular
            st%sigma_min = core%monitor%sigma_min
            st%velocity_jump = core%monitor%jump_max
            st%max_drift = core%monitor%drift_max
            st%invariant_change = core%monitor%invariant_change
            st%work_defect = core%monitor%work_defect
            st%unresolved_passes = core%monitor%unresolved
            st%resolution_ratio = core%monitor%resolution_ratio
            st%weight_changes = core%monitor%weights%changes
            st%eps_changes = core%monitor%scales%eps_changes
        end associate
    end function solver_statistics

    function solver_message(self) result(msg)
        class(solver_engine), intent(in) :: self
        character(len=:), allocatable :: msg
        if (allocated(self%last_message)) then
            msg = self%last_message
        else
            msg = status_message(self%last_stat)
        end if
    end function solver_message

    function solver_events(self) result(text)
        class(solver_engine), intent(in) :: self
        character(len=:), allocatable :: text
        text = ''
        if (associated(self%core)) then
            if (allocated(self%core%events)) text = self%core%events
        end if
    end function solver_events

    function solver_options_in_force(self) result(opts)
        class(solver_engine), intent(in) :: self
        type(solver_options) :: opts
        if (associated(self%core)) opts = self%core%opts
    end function solver_options_in_force

    integer function solver_formulation(self)
        class(solver_engine), intent(in) :: self
        solver_formulation = 0
        if (associated(self%core)) solver_formulation = self%core%formulation
    end function solver_formulation

    integer function solver_linear_solver(self)
        class(solver_engine), intent(in) :: self
        solver_linear_solver = 0
        if (associated(self%core)) solver_linear_solver = self%core%linear_solver
    end function solver_linear_solver

    integer function solver_lsq_method(self)
        class(solver_engine), intent(in) :: self
        solver_lsq_method = 0
        if (associated(self%core)) then
            if (.not. self%core%augmented) solver_lsq_method = self%core%model%lsq
        end if
    end function solver_lsq_method

    real(wp) function solver_sigma_min(self)
        class(solver_engine), intent(in) :: self
        solver_sigma_min = ieee_value(1.0_wp, ieee_quiet_nan)
        if (associated(self%core)) solver_sigma_min = self%core%monitor%sigma_last
    end function solver_sigma_min

    function solver_singular_intervals(self) result(intervals)
        class(solver_engine), intent(in) :: self
        real(wp), allocatable :: intervals(:, :)
        if (associated(self%core)) then
            intervals = self%core%monitor%intervals()
        else
            allocate (intervals(2, 0))
        end if
    end function solver_singular_intervals

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

    subroutine solver_destroy(self)
        class(solver_engine), intent(inout) :: self
        type(solver_core), pointer :: core

        core => self%core
        if (.not. associated(core)) return
        if (allocated(core%stiff)) call core%stiff%free()
        if (allocated(core%nonstiff)) call core%nonstiff%free()
        if (associated(core%model)) deallocate (core%model)
        deallocate (self%core)
        self%core => null()
    end subroutine solver_destroy

    subroutine solver_assign(lhs, rhs)
        class(solver_engine), intent(inout) :: lhs
        class(solver_engine), intent(in) :: rhs
        integer :: stat
        if (associated(lhs%core) .and. associated(rhs%core)) then
            if (associated(lhs%core, rhs%core)) return   ! a = a
        end if
        call lhs%destroy()
        lhs%t = rhs%t
        lhs%assigned = .true.
        call lhs%record(regdae_err_not_initialized, 'a regdae_solver cannot be copied by assignment (it owns '// &
                        'IDA memory): this one is uninitialized; call init on it', stat)
    end subroutine solver_assign

    subroutine solver_finalize(self)
        type(solver_engine), intent(inout) :: self
        call self%destroy()
    end subroutine solver_finalize

    subroutine engine_stop_at_pass_ends(self, on)
        class(solver_engine), intent(inout) :: self
        logical, intent(in) :: on
        if (.not. associated(self%core)) return
        self%core%stop_at_pass_end = on
        self%core%monitor%defer_in_pass = on
    end subroutine engine_stop_at_pass_ends

    logical function engine_take_pass_end(self) result(ended)
        class(solver_engine), intent(inout) :: self
        ended = .false.
        if (.not. associated(self%core)) return
        ended = self%core%monitor%pass_ended
        self%core%monitor%pass_ended = .false.
    end function engine_take_pass_end

    subroutine engine_checkpoint(self, t, z, frozen, valid)
        class(solver_engine), intent(in) :: self
        real(wp), intent(out) :: t
        real(wp), allocatable, intent(out) :: z(:)
        logical, intent(out) :: frozen, valid
        t = 0.0_wp
        frozen = .false.
        valid = .false.
        if (.not. associated(self%core)) return
        associate (mon => self%core%monitor)
            valid = mon%checkpoint_valid
            frozen = mon%checkpoint_frozen
            if (.not. valid) return
            t = mon%checkpoint_t
            z = mon%checkpoint_z
        end associate
    end subroutine engine_checkpoint

    subroutine engine_release_checkpoint(self, t, z)
        class(solver_engine), intent(inout) :: self
        real(wp), intent(in) :: t, z(:)
        if (associated(self%core)) call self%core%monitor%release_checkpoint(t, z)
    end subroutine engine_release_checkpoint

    real(wp) function engine_integrator_time(self) result(t)
        class(solver_engine), intent(in) :: self
        class(integrator), pointer :: stepper
        t = self%t
        if (.not. associated(self%core)) return
        t = self%core%t
        stepper => active_integrator(self%core)
        if (.not. associated(stepper)) return
        if (stepper%ready()) t = stepper%time()
    end function engine_integrator_time

    logical function engine_same(self, other) result(same)
        class(solver_engine), intent(in) :: self, other
        same = .false.
        if (associated(self%core) .and. associated(other%core)) same = associated(self%core, other%core)
    end function engine_same

    integer function engine_x_size(self) result(n)
        class(solver_engine), intent(in) :: self
        n = 0
        if (associated(self%core)) n = self%core%nx
    end function engine_x_size

    real(wp) function engine_time(self) result(t)
        class(solver_engine), intent(in) :: self
        t = self%t
    end function engine_time

    integer function engine_state_size(self) result(n)
        class(solver_engine), intent(in) :: self
        n = 0
        if (associated(self%core)) n = self%core%n
    end function engine_state_size

    subroutine engine_state(self, z)
        class(solver_engine), intent(in) :: self
        real(wp), intent(out) :: z(:)   !! length state_size()
        class(integrator), pointer :: stepper
        type(augmented_system), pointer :: sys
        real(c_double), pointer :: u(:)
        integer :: nx
        if (.not. associated(self%core)) return
        nx = self%core%nx
        stepper => active_integrator(self%core)
        u => stepper%state()
        sys => stepper%augmented()
        if (associated(sys)) then
            call sys%unpack(u, u, q=z(1:nx), v=z(nx + 1:2*nx))
        else
            z = u(1:size(z))
        end if
    end subroutine engine_state

    subroutine engine_restart_at(self, t, z, stat)
        class(solver_engine), intent(inout) :: self
        real(wp), intent(in) :: t, z(:)
        integer, intent(out) :: stat
        class(integrator), pointer :: stepper
        character(len=:), allocatable :: msg
        stat = regdae_err_not_initialized
        if (.not. associated(self%core)) return
        associate (core => self%core)
            core%t = t
            self%t = t
            core%sampled_t = t
            stepper => active_integrator(core)
            call stepper%start(t, z, stat, msg, h0=stepper%last_step())
            if (stat == regdae_success .and. core%monitor%work_tol > 0.0_wp) call rebase_work(core, stepper, t, z)
        end associate
    end subroutine engine_restart_at

    ! The work-energy balance goes on from the state z at t (engine_restart_at).
    subroutine rebase_work(core, stepper, t, z)
        type(solver_core), intent(inout) :: core
        class(integrator), intent(in), target :: stepper
        real(wp), intent(in) :: t, z(:)
        type(augmented_system), pointer :: sys
        real(c_double), pointer :: u(:), up(:)
        real(wp) :: kinetic, power, y(core%m), q(core%nx), v(core%nx)
        integer :: wstat
        logical :: recoverable
        wstat = -1
        sys => stepper%augmented()
        if (associated(sys)) then
            u => stepper%state()
            up => stepper%slope()
            call sys%unpack(u, up, q=q, v=v, y=y)
            call kinetic_energy_and_power(sys%problem, t, q, v, y, kinetic, power, wstat, sys%st%mass)
        else
            call core%model%evaluate(t, z, wstat, recoverable)
            if (wstat == regdae_success) call core%model%work_sample(t, z, kinetic, power, wstat)
        end if
        if (wstat == 0) call core%monitor%rebase_work(t, kinetic, power)
    end subroutine rebase_work

    subroutine engine_start_companion(self, other, kappa, t, z, stat, eps_scale)
        class(solver_engine), intent(in) :: self
        class(solver_engine), intent(inout) :: other
        real(wp), intent(in) :: kappa       !! the tolerances' divisor (> 1)
        real(wp), intent(in) :: t, z(:)     !! the start: a state of self (x, v)
        integer, intent(out) :: stat
        real(wp), intent(in), optional :: eps_scale   !! the companion's eps times this (a probe of the
                                                      !! regularization error)
        type(solver_options) :: opts
        type(augmented_system), pointer :: sys
        real(wp) :: eps, zs(size(z)), ratio
        integer :: nx, pstat
        stat = regdae_err_not_initialized
        if (.not. associated(self%core)) return
        associate (core => self%core)
            nx = core%nx
            if (core%augmented) sys => core%stiff%augmented()
            opts = core%opts
            opts%rtol = core%opts%rtol/kappa
            opts%atol = core%opts%atol/kappa
            if (opts%atol_v /= option_auto) opts%atol_v = core%opts%atol_v/kappa
            opts%jump_tol = 0.0_wp
            opts%drift_tol = 0.0_wp
            opts%work_tol = 0.0_wp
            opts%invariant_tol = 0.0_wp
            opts%resolution_tol = 0.0_wp
            opts%ic_tol = huge(1.0_wp)
            opts%check_jacobians = .false.
            opts%h_init = 0.0_wp
            opts%integrator = merge(integrator_dopri5, integrator_ida, core%active == integrator_dopri5)
            opts%formulation = core%formulation
            opts%linear_solver = merge(core%linear_solver, linear_solver_auto, core%augmented)
            if (core%augmented) then
                eps = sys%eps
                opts%gamma = sys%gamma1
                opts%gamma1 = sys%gamma1
                opts%gamma0 = sys%gamma0
                if (opts%index == 2) opts%gamma0 = 0.5_wp*sys%gamma1**2
            else
                eps = core%model%eps
                if (core%model%order == 1) opts%gamma = core%model%w(1)
                if (core%model%order == 2) then
                    opts%gamma0 = core%model%w(1)
                    opts%gamma1 = core%model%w(2)
                end if
            end if
            ! an automatic eps shrinks with the tolerance as its rule says (rtol^2 within its
            ! bounds; direct: the square root of that): below the rule's floor thinner layers
            ! are not resolved in double precision, and the companion has the same eps
            opts%eps = eps
            if (core%eps_factor > 0.0_wp) then
                ratio = automatic_eps_factor(opts%rtol)/automatic_eps_factor(core%opts%rtol)
                if (opts%method == method_direct) ratio = sqrt(ratio)
                opts%eps = eps*ratio
            end if
            if (present(eps_scale)) opts%eps = opts%eps*eps_scale
            ! the start projected onto the constraints: the solution's drift is within its
            ! tolerance, not within the companion's (with a thinner layer it can bounce off the branch)
            zs = z
            if (core%augmented) then
                if (sys%st%declared) then
                    call project_structured(sys%problem, sys%st%constraint, t, zs(1:nx), zs(nx + 1:2*nx), pstat)
                else
                    call project_second_order(sys%problem, t, zs(1:nx), zs(nx + 1:2*nx), pstat)
                end if
                call other%init(sys%problem, t, zs(1:nx), zs(nx + 1:2*nx), opts, stat, &
                                atol_vector=core%atol_z/kappa)
            else if (allocated(core%model%second)) then
                call project_second_order(core%model%second, t, zs(1:nx), zs(nx + 1:2*nx), pstat)
                call other%init(core%model%second, t, zs(1:nx), zs(nx + 1:2*nx), opts, stat, &
                                atol_vector=core%atol_z/kappa)
            else if (allocated(core%model%higher)) then
                stat = regdae_err_bad_input   ! order >= 3: not verified
            else
                select type (p => core%model%first)
                type is (velocity_index2_problem)
                    call project_second_order(p%second, t, zs(1:nx), zs(nx + 1:2*nx), pstat)
                    call other%init(p%second, t, zs(1:nx), zs(nx + 1:2*nx), opts, stat, atol_vector=core%atol_z/kappa)
                class default
                    call project_first_order(p, t, zs(1:nx), pstat)
                    call other%init(p, t, zs(1:nx), opts, stat, atol_vector=core%atol_z/kappa)
                end select
            end if
        end associate
    end subroutine engine_start_companion

    subroutine engine_limit_steps(self, steps)
        class(solver_engine), intent(inout) :: self
        integer, intent(in) :: steps   !! >= 1
        if (associated(self%core)) self%core%opts%max_steps = max(1, steps)
    end subroutine engine_limit_steps

    logical function engine_regularized(self) result(yes)
        class(solver_engine), intent(in) :: self
        yes = .false.
        if (associated(self%core)) yes = self%core%opts%method /= method_baumgarte .and. self%core%monitor%regularized()
    end function engine_regularized

    logical function engine_eps_floored(self, kappa_a, kappa_b) result(floored)
        class(solver_engine), intent(in) :: self
        real(wp), intent(in) :: kappa_a, kappa_b
        floored = .false.
        if (.not. associated(self%core)) return
        if (.not. (self%core%eps_factor > 0.0_wp)) return
        floored = abs(automatic_eps_factor(self%core%opts%rtol/kappa_a) - automatic_eps_factor(self%core%opts%rtol/ &
                      kappa_b)) <= 1.0e-6_wp*automatic_eps_factor(self%core%opts%rtol/kappa_a)
    end function engine_eps_floored

    real(wp) function engine_state_distance(self, za, zb) result(d)
        class(solver_engine), intent(in) :: self
        real(wp), intent(in) :: za(:), zb(:)
        integer :: i
        logical :: skip_v
        d = 0.0_wp
        if (.not. associated(self%core)) return
        associate (core => self%core)
            ! the positions (x) only: the error the user reads; right after a pass the
            ! velocities carry its layer's sensitivity, which the positions integrate away
            skip_v = core%second_order
            do i = 1, min(size(za), size(zb), core%n)
                if (skip_v .and. i > core%nx) cycle
                d = max(d, abs(za(i) - zb(i))/(core%opts%rtol*abs(zb(i)) + core%atol_z(i)))
            end do
        end associate
        if (.not. (d == d)) d = huge(1.0_wp)
    end function engine_state_distance

    subroutine engine_note_event(self, text)
        class(solver_engine), intent(inout) :: self
        character(len=*), intent(in) :: text
        if (associated(self%core)) call log_event(self%core, text)
    end subroutine engine_note_event


end module regdae_solver_front
