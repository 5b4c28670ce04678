!> The init paths of the solver front (`regdae_solver_front`): the input
!! checked, the consistent initial values, the automatic parameters resolved
!! (`regdae_auto_parameters`), the monitor started and the first integrator
!! created in the core's slot: dopri5, Radau IIA or IDA on the eliminated or
!! multiplier formulation (solver_start), IDA or Radau IIA on the augmented formulation of a
!! mechanical problem (solver_start_augmented); and destroy, and the assignment that
!! does not copy a solver.
submodule (regdae_solver_front) regdae_solver_init
    use regdae_second_order_problem, only: velocity_constraint
    use regdae_mechanical_problem, only: mechanical_structure, structured_velocity_constraint
    use regdae_linear_problem, only: linear_dae_problem
    use regdae_velocity_index2, only: new_velocity_index2
    use regdae_solver_core, only: new_core
    use regdae_solver_sampling, only: start_monitor, start_monitor_augmented
    use regdae_dopri5_integrator, only: dopri5_integrator, dopri5_in_slot
    use regdae_integrator_switching, only: start_implicit_if_stiff
    use regdae_ida_integrator, only: ida_integrator, ida_in_slot
    use regdae_radau_integrator, only: radau_adapter, radau_in_slot
    use regdae_auto_parameters, only: set_state_tolerances, resolve_auto_parameters, resolve_augmented_parameters, &
                                      augmented_eps, check_first_step
    use regdae_jacobian_check, only: check_second_order_jacobian, check_structured_jacobian
    implicit none

contains

    module procedure solver_init_first

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
    end procedure solver_init_first

    module procedure solver_init_second
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
            call check_mass_constant(copy, t0, x0, augmented, ustat, msg)
            if (ustat /= regdae_success) then
                call self%record(ustat, msg, stat)
                return
            end if
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
            call copy%reset_mass_factor()   ! M's factor once for a declared constant M
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
    end procedure solver_init_second

    module procedure solver_init_higher
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
    end procedure solver_init_higher

    ! Common checks of init; false (with stat and message set) if the input is bad.
    module procedure check_input
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
    end procedure check_input

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

    ! A mass matrix declared constant (`mechanical_structure%mass_constant`) is taken at its word
    ! by the work-energy balance (dM/dt = 0) and the eliminated formulation (one factor per run),
    ! so the declaration is verified once here: M at (q0, t0) against M at a shifted point, every
    ! coordinate moved by its own amount (mass_shift max(|q0_i|, 1) times a factor in [0.5, 1.5),
    ! the signs alternating, so that an M of the differences of coordinates moves too) and t0 by
    ! mass_shift max(|t0|, 1). An entry that differs by more than mass_constant_tol max|M(q0, t0)|
    ! refuses the declaration (regdae_err_structure, msg names the entry). M from the declared
    ! pattern (`mass_values`, O(nonzeros)) where it fits (the augmented setup refuses one that does
    ! not), else dense (`mass_matrix`; unchecked if that does not fit in memory). A user routine
    ! that fails at the shifted point is tried at one 100 times closer; failing there too, the
    ! declaration stands unverified (a failure at q0 itself is reported where M is first needed);
    ! a nonzero outside the declared pattern at the shifted point refuses it.
    subroutine check_mass_constant(problem, t0, q0, augmented, stat, msg)
        class(mechanical_problem), intent(inout) :: problem
        real(wp), intent(in) :: t0, q0(:)
        logical, intent(in) :: augmented   !! the augmented formulation (it refuses a pattern that does not fit)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), parameter :: mass_shift = 1.0e-2_wp, golden = 0.6180339887498949_wp
        real(wp), parameter :: mass_constant_tol = 1.0e3_wp*epsilon(1.0_wp)
        type(mechanical_structure) :: st
        real(wp), allocatable :: m0(:), m1(:), dense(:, :), dq(:), q1(:)   ! (heap: n may be millions)
        real(wp) :: scale, shift, dt
        integer :: i, k, ustat, row, col, astat
        logical :: sparse
        stat = regdae_success
        msg = ''
        st = problem%structure()
        if (.not. (st%declared .and. st%mass_constant)) return
        sparse = allocated(st%mass%row_start) .and. st%mass%nrows == problem%n .and. st%mass%ncols == problem%n
        if (sparse) then
            allocate (m0(st%mass%nnz()), m1(st%mass%nnz()), stat=astat)
        else
            if (augmented .or. real(problem%n, wp)**2 > real(huge(1), wp)) return   ! (the augmented setup
            allocate (m0(problem%n**2), m1(problem%n**2), dense(problem%n, problem%n), stat=astat)   ! refuses it)
        end if
        if (astat == 0) allocate (dq(problem%n), q1(problem%n), stat=astat)
        if (astat /= 0) return   ! the formulation's own allocations report it
        do i = 1, size(q0)
            dq(i) = merge(1.0_wp, -1.0_wp, mod(i, 2) == 1)*(0.5_wp + modulo(i*golden, 1.0_wp))*max(abs(q0(i)), 1.0_wp)
        end do
        dt = max(abs(t0), 1.0_wp)
        ustat = 0
        call mass_at(t0, q0, m0)
        if (ustat /= 0) return   ! reported where M is first needed
        shift = mass_shift
        do k = 1, 2   ! the shifted point, or one 100 times closer where the user routine fails there
            ustat = 0
            q1 = q0 + shift*dq
            call mass_at(t0 + shift*dt, q1, m1)
            if (ustat == 0) exit
            shift = shift/100.0_wp
        end do
        if (ustat == regdae_err_structure) then   ! a nonzero outside the pattern there: M varies
            stat = regdae_err_structure
            msg = 'the structure declares M constant (mass_constant), but M varies: at q0 + dq, t0 + '// &
                  format_real(shift*dt)//' it has a nonzero outside the declared mass pattern (mass_values)'
            return
        end if
        if (ustat /= 0) return   ! not verified: M is not defined near q0 (the declaration stands)
        scale = 0.0_wp
        if (size(m0) > 0) scale = maxval(abs(m0))
        do k = 1, size(m0)
            if (.not. (abs(m1(k) - m0(k)) > mass_constant_tol*scale .or. m1(k) /= m1(k))) cycle
            if (sparse) then
                row = findloc(st%mass%row_start <= k, .false., dim=1) - 1   ! the first row start beyond k
                col = st%mass%cols(k)
            else
                row = modulo(k - 1, problem%n) + 1
                col = (k - 1)/problem%n + 1
            end if
            stat = regdae_err_structure
            msg = 'the structure declares M constant (mass_constant), but M varies: entry ('//format_int(row)// &
                  ', '//format_int(col)//') is '//format_real(m0(k))//' at (q0, t0) and '//format_real(m1(k))// &
                  ' at q0 + dq, t0 + '//format_real(shift*dt)//' (dq_i up to '//format_real(1.5_wp*shift)// &
                  ' max(|q0_i|, 1)); declare mass_constant = .false.'
            return
        end do
    contains
        ! M at (t, q) into vals: in pattern order (sparse) or column by column
        subroutine mass_at(t, q, vals)
            real(wp), intent(in) :: t, q(:)
            real(wp), intent(out) :: vals(:)
            if (sparse) then
                call problem%mass_values(t, q, st%mass, vals, ustat)
            else
                call problem%mass_matrix(t, q, dense, ustat)
                if (ustat == 0) vals = reshape(dense, [size(dense)])
            end if
        end subroutine mass_at
    end subroutine check_mass_constant

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
        if (opts%integrator == integrator_dopri5 .or. opts%integrator == integrator_radau .or. &
            opts%mass_damping > 0.0_wp .or. problem%n < augmented_min_n) return
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
    ! solves of the saddle-point matrix (consistent_start) or else IDACalcIC, the diagnostics from IDA's state; with integrator=radau, Radau IIA
    ! on the same system as an index-1 DAE (regdae_radau_augmented), dense LU,
    ! consistent initial values by its own Newton steps on the algebraic rows.
    module procedure solver_start_augmented
        type(solver_core), pointer :: core
        type(augmented_system) :: sys
        type(ida_integrator), pointer :: ida
        type(radau_adapter), pointer :: radau
        real(wp), allocatable :: u0(:), up0(:), id(:)
        character(len=:), allocatable :: msg
        logical :: on_radau, consistent

        core => self%core
        core%opts = opts
        core%augmented = .true.
        core%formulation = formulation_augmented
        on_radau = (opts%integrator == integrator_radau)
        core%active = merge(integrator_radau, integrator_ida, on_radau)
        core%events = ''
        if (any(problem%nonnegative())) then
            stat = start_failed(self, regdae_err_bad_input, 'the problem keeps components nonnegative '// &
                                '(its nonnegative binding), which the augmented formulation does not enforce: '// &
                                'set formulation=eliminated with integrator=ida or auto')
            return
        end if
        core%n = 2*problem%n
        core%m = problem%m
        core%t = t0
        call set_state_tolerances(core, stat, msg)
        if (stat /= regdae_success) then
            stat = start_failed(self, stat, msg)
            return
        end if
        call sys%setup(problem, opts, stat)
        if (stat /= regdae_success) then
            stat = start_failed(self, stat, sys%message)
            return
        end if
        call resolve_augmented_parameters(core, sys, t0, q0, v0, stat, msg)
        if (stat /= regdae_success) then
            stat = start_failed(self, stat, msg)
            return
        end if
        core%neq = sys%neq
        core%linear_solver = opts%linear_solver
        ! KLU on the grouped Newton matrix was the fastest per step at every chain size
        ! measured (N = 2 ... 1024: 1.1-2.4x faster than band and dense, doc/performance.md)
        if (core%linear_solver == linear_solver_auto) core%linear_solver = linear_solver_sparse
        if (on_radau) core%linear_solver = linear_solver_dense   ! (validate_options refuses band and sparse)
        allocate (u0(sys%neq), up0(sys%neq), id(sys%neq), core%y_work(core%m))
        call sys%initial_guess(q0, v0, u0, up0, id)
        call augmented_eps(core, sys, t0, u0)
        core%excluded = sys%excluded_unknowns(opts%excluded)
        if (opts%exclusion == exclusion_off) core%excluded = .false.
        if (on_radau) then
            radau => radau_in_slot(core)
            call radau%take_augmented(sys)
            call radau%start(t0, [q0, v0], stat, msg, h0=opts%h_init)
            if (stat /= regdae_success) then
                stat = start_failed(self, stat, 'at the initial point: '//msg)
                return
            end if
        else
            ida => ida_in_slot(core)
            consistent = sys%consistent_start(t0, u0, up0)
            call ida%ida%create(sys, core%opts, core%linear_solver, core%excluded, t0, u0, up0, stat, msg, &
                                sys%tolerance_vector(core%atol_z(1:problem%n), core%atol_z(problem%n + 1:), opts%atol))
            if (stat /= regdae_success) then
                stat = start_failed(self, stat, msg)
                return
            end if
            if (.not. consistent) call ida%ida%calc_ic(id, t0 + 1.0e-3_wp*max(1.0_wp, abs(t0)), stat, msg)
            if (stat /= regdae_success) then
                stat = start_failed(self, stat, 'at the initial point: '//msg)
                return
            end if
        end if
        if (opts%check_jacobians) then
            ! the user's patterns first, by (row, column) of M, G and the force Jacobians; then
            ! (IDA) the grouped Newton matrix against the full one
            call check_structured_jacobian(problem, sys, t0, q0, v0, stat, msg)
            if (stat == regdae_success .and. .not. on_radau) then
                ida => ida_in_slot(core)
                call ida%ida%check_grouped_jacobian(t0, 1.0e3_wp/max(1.0_wp, abs(t0)), stat, msg)
            end if
            if (stat /= regdae_success) then
                stat = start_failed(self, stat, msg)
                return
            end if
        end if
        call start_monitor_augmented(core, t0, core%opts%eps)
        if (opts%invariant_tol > 0.0_wp .and. .not. (core%monitor%invariant0 == core%monitor%invariant0)) then
            stat = start_failed(self, regdae_err_bad_input, 'invariant_tol > 0, but the problem has no invariant at t0 '// &
                      '(override `invariant` of the second-order problem)')
            return
        end if
        call self%record(regdae_success, '', stat)
    end procedure solver_start_augmented

    ! With the model set up: consistent initial values, then the IDA objects.
    module procedure solver_start
        type(solver_core), pointer :: core
        type(dopri5_integrator), pointer :: dopri5
        type(ida_integrator), pointer :: ida
        type(radau_adapter), pointer :: radau
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
            stat = start_failed(self, stat, 'at the initial point: '//core%model%message)
            return
        end if
        gnorm = 0.0_wp
        if (m > 0) gnorm = maxval(abs(core%model%g))
        if (.not. (gnorm <= opts%ic_tol)) then
            stat = start_failed(self, regdae_err_inconsistent_ic, 'inconsistent initial values: max |g(x0, t0)| = '// &
                      format_real(gnorm)//' exceeds ic_tol = '//format_real(opts%ic_tol))
            return
        end if
        lsq = opts%lsq
        if (lsq == lsq_auto) lsq = lsq_checked   ! by conditioning, per solve (regdae_damped_lsq)
        core%model%lsq = lsq
        call set_state_tolerances(core, stat, msg)
        if (stat /= regdae_success) then
            stat = start_failed(self, stat, msg)
            return
        end if
        call resolve_auto_parameters(core, t0, z0, stat, msg)
        if (stat /= regdae_success) then
            stat = start_failed(self, stat, msg)
            return
        end if
        allocate (y0(m), zp0(n))
        call core%model%solve_multiplier(t0, y0, stat)
        if (stat /= regdae_success) then
            stat = start_failed(self, stat, 'at the initial point: '//core%model%message)
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
            stat = start_failed(self, regdae_err_bad_input, 'invariant_tol > 0, but the problem has no invariant at t0 '// &
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
                stat = start_failed(self, stat, msg)
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
        ! Nonnegativity (the problem's `nonnegative`) is IDA's constraint option: auto keeps IDA,
        ! an integrator that cannot keep it is refused rather than ignoring it
        if (any(core%model%nonnegative_state())) then
            if (opts%integrator == integrator_auto) then
                core%active = integrator_ida
                core%switching = .false.
            else if (core%active /= integrator_ida) then
                stat = start_failed(self, regdae_err_bad_input, 'the problem keeps components nonnegative '// &
                                    '(its nonnegative binding), which only IDA enforces: set integrator=ida or auto')
                return
            end if
        end if
        if (core%active == integrator_dopri5) then
            ! integrator=auto, stiff at t0: the implicit integrator from there (started by
            ! start_implicit_if_stiff), dopri5 created only at a switch back
            call start_implicit_if_stiff(core, stat, msg)
            if (stat /= regdae_success) then
                stat = start_failed(self, stat, msg)
                return
            end if
            if (core%active == integrator_dopri5) then
                dopri5 => dopri5_in_slot(core)
                call dopri5%start(t0, z0, stat, msg, h0=opts%h_init)
                if (stat /= regdae_success) then
                    stat = start_failed(self, stat, 'dopri5: the slope at the initial point failed: '// &
                                        core%model%message)
                    return
                end if
            end if
            call self%record(regdae_success, '', stat)
            return
        end if
        if (core%active == integrator_radau) then
            radau => radau_in_slot(core)
            call radau%start(t0, z0, stat, msg, h0=opts%h_init)
            if (stat /= regdae_success) then
                stat = start_failed(self, stat, msg)
                return
            end if
            call self%record(regdae_success, '', stat)
            return
        end if
        ida => ida_in_slot(core)
        call ida%start(t0, z0, stat, msg, zp=zp0, y=y0)
        if (stat /= regdae_success) then
            stat = start_failed(self, stat, msg)
            return
        end if
        call self%record(regdae_success, '', stat)
    end procedure solver_start

    ! A start failed: the status (returned) and message recorded, the solver's objects freed.
    integer function start_failed(self, code, text) result(stat)
        class(solver_engine), intent(inout) :: self
        integer, intent(in) :: code
        character(len=*), intent(in) :: text
        call self%record(code, text, stat)
        call self%destroy()
    end function start_failed


    module procedure solver_destroy
        type(solver_core), pointer :: core

        core => self%core
        if (.not. associated(core)) return
        if (allocated(core%stiff)) call core%stiff%free()
        if (allocated(core%nonstiff)) call core%nonstiff%free()
        if (associated(core%model)) deallocate (core%model)
        deallocate (self%core)
        self%core => null()
    end procedure solver_destroy

    module procedure solver_assign
        integer :: stat
        if (associated(lhs%core) .and. associated(rhs%core)) then
            if (associated(lhs%core, rhs%core)) return   ! a = a
        end if
        call lhs%destroy()
        lhs%t = rhs%t
        lhs%assigned = .true.
        call lhs%record(regdae_err_not_initialized, 'a regdae_solver cannot be copied by assignment (it owns '// &
                        'IDA memory): this one is uninitialized; call init on it', stat)
    end procedure solver_assign

end submodule regdae_solver_init
