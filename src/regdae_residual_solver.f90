!> IDA on a general implicit DAE F(t, y, y') = 0 (`residual_problem`), as DASSL and
!! DDASKR integrate one: BDF of orders 1 ... 5, a dense or band Newton matrix (the
!! user's dF/dy + cj dF/dy', or IDA's difference quotients), error weights
!! 1/(rtol_i |y_i| + atol_i), consistent initial values by IDACalcIC, inequality
!! constraints (IDASetConstraints), root finding (IDARootInit), a stop time and
!! returns after every step.
!!
!! Nothing is regularized: a DAE with a singular constraint Jacobian (a mechanism at
!! a kinematic singularity) fails here as it fails in DASSL. Such problems belong to
!! regdae's other doors (`dae_problem`, `mechanical_problem`, DREGDAE, DREGDAEM).
!!
!! No global state: the solver's IDA-facing part (the problem's copy, IDA's memory,
!! the vectors) lives in a heap-allocated core whose address is IDA's user_data, so
!! any number of solvers run side by side in one process. Call `free` when done.
module regdae_residual_solver
    use, intrinsic :: iso_c_binding
    use, intrinsic :: iso_fortran_env, only: int64
    use fida_mod
    use fsundials_context_mod
    use fsundials_nvector_mod
    use fnvector_serial_mod
    use fsundials_matrix_mod
    use fsunmatrix_dense_mod
    use fsunmatrix_band_mod
    use fsundials_linearsolver_mod
    use fsunlinsol_dense_mod
    use fsunlinsol_band_mod
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_format, only: format_int, format_real, text_length
    use regdae_c_strings, only: c_string
    use regdae_residual_problem, only: residual_problem
    use regdae_residual_options, only: residual_options, check_residual_options, initial_given, initial_algebraic
    implicit none
    private

    !> How `advance` returned (its `reached` argument): at tout, at the end of a step
    !! short of tout (one_step), at the stop time, at a root.
    integer, parameter, public :: reached_tout = 1, reached_step = 2, reached_tstop = 3, reached_root = 4

    !> Counters and step data of IDA (DDASKR's IWORK / RWORK outputs map onto these).
    type, public :: residual_stats
        integer(int64) :: steps = 0          !! steps taken (IDAGetNumSteps)
        integer(int64) :: res_evals = 0      !! all calls of the residual, difference quotients included
        integer(int64) :: jac_evals = 0      !! Newton matrix evaluations (user's or difference quotients)
        integer(int64) :: err_test_fails = 0 !! error test failures
        integer(int64) :: conv_fails = 0     !! nonlinear convergence failures
        integer(int64) :: nonlin_iters = 0   !! Newton iterations
        integer(int64) :: root_evals = 0     !! calls of the event functions
        integer :: order_last = 0            !! order of the last step
        integer :: order_next = 0            !! order to be attempted next
        real(wp) :: h_last = 0.0_wp          !! the last step
        real(wp) :: h_next = 0.0_wp          !! the step to be attempted next
        real(wp) :: t_reached = 0.0_wp       !! IDA's internal time (the end of its last step)
    end type residual_stats

    ! Everything IDA's callbacks reach (through user_data): never moves once created.
    type :: residual_core
        class(residual_problem), allocatable :: problem
        type(residual_options) :: opts
        integer :: neq = 0, nroots = 0
        real(wp), allocatable :: rtol(:), atol(:), pd(:, :)
        type(c_ptr) :: sunctx = c_null_ptr, ida_mem = c_null_ptr
        type(N_Vector), pointer :: yy => null(), yp => null(), idv => null(), cons => null()
        type(SUNMatrix), pointer :: jmat => null()
        type(SUNLinearSolver), pointer :: ls => null()
        logical :: band = .false., ic_pending = .false., root_pending = .false.
        real(wp) :: t_root = 0.0_wp
        integer, allocatable :: found(:)
        integer :: flag = 0                    ! IDA's last flag
        integer :: weight_component = 0        ! > 0: that error weight was not positive
        integer :: callback_stat = 0           ! the last failing user callback's stat, its name and time
        character(len=:), allocatable :: callback_name, ida_message
        real(wp) :: callback_t = 0.0_wp
        character(len=8) :: names(3) = [character(len=8) :: 'residual', 'jacobian', 'roots']
    end type residual_core

    !> The solver: init, then advance as often as needed, then free.
    type, public :: residual_solver
        private
        type(residual_core), pointer :: core => null()
        character(len=:), allocatable :: msg
    contains
        !> Check the options, copy the problem, create IDA at (t0, y0, y0').
        procedure :: init => solver_init
        !> Consistent initial values now (IDACalcIC towards tout1) into y, yp; advance
        !! does this itself on its first call when opts%initial asks for it.
        procedure :: initial_values => solver_initial_values
        !> Integrate towards tout: y, y' at t (tout, a step's end, tstop or a root).
        procedure :: advance => solver_advance
        !> IDA's counters.
        procedure :: statistics => solver_statistics
        !> After reached_root: +1 / -1 / 0 per event function (a root, increasing /
        !! decreasing, none), as IDAGetRootInfo and DDASKR's JROOT.
        procedure :: roots => solver_roots
        !> The message of the last call ('' after success).
        procedure :: message => solver_message
        !> IDA's flag of the last call (0: none or success).
        procedure :: ida_flag => solver_ida_flag
        !> The solver's copy of the problem (to update its components between calls).
        procedure :: problem => solver_problem
        !> New tolerances for the next advance (length neq each), as DDASKR allows between calls.
        procedure :: set_tolerances => solver_set_tolerances
        !> Name the callbacks in messages (default: residual, jacobian, roots).
        procedure :: name_routines => solver_name_routines
        !> True between a successful init and free.
        procedure :: ready => solver_ready
        !> Free IDA and everything else (safe to call twice, or before init).
        procedure :: free => solver_free
    end type residual_solver

    !> The stop time in force when none is asked for (SUNDIALS 6.4 has no IDAClearStopTime):
    !! far, and small enough that IDA's products of it with a step do not overflow.
    real(wp), parameter :: far_away = sqrt(huge(1.0_wp))

contains

    subroutine solver_init(self, problem, t0, y0, yp0, opts, stat)
        class(residual_solver), intent(inout) :: self
        class(residual_problem), intent(in) :: problem   !! copied into the solver
        real(wp), intent(in) :: t0                       !! initial time
        real(wp), intent(in) :: y0(:), yp0(:)            !! initial y and y' (guesses for what initial computes)
        type(residual_options), intent(in) :: opts
        integer, intent(out) :: stat
        character(len=:), allocatable :: msg
        integer :: neq

        call self%free()
        neq = problem%neq
        call check_residual_options(opts, neq, stat, msg)
        if (stat == regdae_success .and. (size(y0) /= neq .or. size(yp0) /= neq)) &
            msg = 'y0 and yp0 must have neq = '//format_int(neq)//' entries'
        if (stat == regdae_success .and. problem%nroots < 0) msg = 'nroots must be >= 0'
        if (len(msg) > 0) then
            stat = regdae_err_bad_input
            self%msg = msg
            return
        end if
        allocate (self%core)
        call create(self%core, problem, t0, y0, yp0, opts, msg)
        if (len(msg) > 0) then
            stat = regdae_err_sundials
            if (self%core%flag == IDA_ILL_INPUT) stat = regdae_err_bad_input
            self%msg = msg
            call self%free()
            return
        end if
        self%msg = ''
        stat = regdae_success
    end subroutine solver_init

    ! The SUNDIALS objects of the core; msg '' on success.
    subroutine create(c, problem, t0, y0, yp0, opts, msg)
        type(residual_core), intent(inout), target :: c
        class(residual_problem), intent(in) :: problem
        real(wp), intent(in) :: t0, y0(:), yp0(:)
        type(residual_options), intent(in) :: opts
        character(len=:), allocatable, intent(out) :: msg
        integer(c_long) :: n
        integer(c_int) :: ierr
        real(c_double), pointer :: p(:)
        type(c_ptr) :: user_data

        allocate (c%problem, source=problem)
        c%opts = opts
        c%neq = problem%neq
        c%nroots = problem%nroots
        c%rtol = spread(opts%rtol, 1, c%neq)
        if (allocated(opts%rtol_v)) c%rtol = opts%rtol_v
        c%atol = spread(opts%atol, 1, c%neq)
        if (allocated(opts%atol_v)) c%atol = opts%atol_v
        c%band = (opts%band_lower >= 0)
        c%ic_pending = (opts%initial /= initial_given)
        c%ida_message = ''
        c%callback_name = ''
        allocate (c%found(c%nroots))
        c%found = 0
        user_data = c_loc(c)
        n = int(c%neq, c_long)
        msg = 'creating the SUNDIALS context, vectors or IDA failed'
        if (FSUNContext_Create(c_null_ptr, c%sunctx) /= 0) return
        c%yy => FN_VNew_Serial(n, c%sunctx)
        c%yp => FN_VNew_Serial(n, c%sunctx)
        if (.not. (associated(c%yy) .and. associated(c%yp))) return
        p => FN_VGetArrayPointer(c%yy)
        p = y0
        p => FN_VGetArrayPointer(c%yp)
        p = yp0
        c%ida_mem = FIDACreate(c%sunctx)
        if (.not. c_associated(c%ida_mem)) return
        ierr = FIDASetErrHandlerFn(c%ida_mem, c_funloc(plain_ida_error_handler), user_data)
        if (ierr == 0) ierr = FIDAInit(c%ida_mem, c_funloc(plain_ida_residual), t0, c%yy, c%yp)
        if (ierr == 0) ierr = FIDASetUserData(c%ida_mem, user_data)
        if (ierr == 0) ierr = FIDAWFtolerances(c%ida_mem, c_funloc(plain_ida_error_weights))
        if (ierr == 0 .and. allocated(opts%algebraic)) then
            c%idv => FN_VNew_Serial(n, c%sunctx)
            p => FN_VGetArrayPointer(c%idv)
            p = merge(0.0_wp, 1.0_wp, opts%algebraic)   ! IDA's id: 1 differential, 0 algebraic
            ierr = FIDASetId(c%ida_mem, c%idv)
            if (ierr == 0 .and. opts%suppress_alg) ierr = FIDASetSuppressAlg(c%ida_mem, 1_c_int)
        end if
        if (ierr == 0 .and. (allocated(opts%constraints) .or. allocated(opts%ic_constraints))) then
            c%cons => FN_VNew_Serial(n, c%sunctx)
            ierr = set_constraints(c, c%ic_pending)
        end if
        if (ierr /= 0) then
            c%flag = int(ierr)
            msg = 'IDA refused the problem or the options: '//c%ida_message
            return
        end if
        msg = 'creating the '//trim(merge('band ', 'dense', c%band))//' matrix or linear solver failed'
        if (c%band) then
            c%jmat => FSUNBandMatrix(n, int(opts%band_upper, c_long), int(opts%band_lower, c_long), c%sunctx)
            if (associated(c%jmat)) c%ls => FSUNLinSol_Band(c%yy, c%jmat, c%sunctx)
            allocate (c%pd(2*opts%band_lower + opts%band_upper + 1, c%neq))
        else
            c%jmat => FSUNDenseMatrix(n, n, c%sunctx)
            if (associated(c%jmat)) c%ls => FSUNLinSol_Dense(c%yy, c%jmat, c%sunctx)
        end if
        if (.not. (associated(c%jmat) .and. associated(c%ls))) return
        ierr = FIDASetLinearSolver(c%ida_mem, c%ls, c%jmat)
        if (ierr == 0 .and. c%problem%has_jacobian()) ierr = FIDASetJacFn(c%ida_mem, c_funloc(plain_ida_jacobian))
        if (ierr == 0) ierr = FIDASetMaxNumSteps(c%ida_mem, int(opts%max_steps, c_long))
        if (ierr == 0 .and. opts%max_order < 5) ierr = FIDASetMaxOrd(c%ida_mem, int(opts%max_order, c_int))
        if (ierr == 0 .and. opts%h_init > 0.0_wp) ierr = FIDASetInitStep(c%ida_mem, opts%h_init)
        if (ierr == 0 .and. opts%h_max > 0.0_wp) ierr = FIDASetMaxStep(c%ida_mem, opts%h_max)
        if (ierr == 0 .and. c%nroots > 0) ierr = FIDARootInit(c%ida_mem, int(c%nroots, c_int), c_funloc(plain_ida_roots))
        if (ierr == 0 .and. c%nroots > 0) ierr = FIDASetNoInactiveRootWarn(c%ida_mem)
        c%flag = int(ierr)
        msg = ''
        if (ierr /= 0) msg = 'IDA setup failed: '//c%ida_message
    end subroutine create

    ! IDA's constraints for the initial-value computation (ic) or the integration;
    ! codes 0 where the options give none for that phase.
    integer(c_int) function set_constraints(c, ic) result(ierr)
        type(residual_core), intent(inout) :: c
        logical, intent(in) :: ic
        real(c_double), pointer :: p(:)
        ierr = 0
        if (.not. associated(c%cons)) return
        p => FN_VGetArrayPointer(c%cons)
        if (ic .and. allocated(c%opts%ic_constraints)) then
            p = real(c%opts%ic_constraints, wp)
        else if (allocated(c%opts%constraints)) then
            p = real(c%opts%constraints, wp)
        else
            p = 0.0_wp
        end if
        ierr = FIDASetConstraints(c%ida_mem, c%cons)   ! all 0: none (the binding cannot pass NULL)
    end function set_constraints

    subroutine solver_initial_values(self, tout1, y, yp, stat)
        class(residual_solver), intent(inout) :: self
        real(wp), intent(in) :: tout1                  !! the first output time (sets IDA's trial step)
        real(wp), intent(out) :: y(:), yp(:)           !! the consistent values
        integer, intent(out) :: stat
        integer(c_int) :: ierr, icopt
        real(c_double), pointer :: p(:)
        if (.not. started(self, stat)) return
        associate (c => self%core)
            icopt = IDA_Y_INIT
            if (c%opts%initial == initial_algebraic) icopt = IDA_YA_YDP_INIT
            call clear_failure(c)
            ierr = FIDACalcIC(c%ida_mem, icopt, tout1)
            if (ierr == 0) ierr = FIDAGetConsistentIC(c%ida_mem, c%yy, c%yp)
            c%flag = int(ierr)
            if (ierr == 0) ierr = set_constraints(c, .false.)
            c%ic_pending = .false.
            p => FN_VGetArrayPointer(c%yy)
            y = p
            p => FN_VGetArrayPointer(c%yp)
            yp = p
            if (ierr == 0) then
                stat = regdae_success
                self%msg = ''
            else
                stat = failure_status(c, regdae_err_inconsistent_ic)
                call failure_text(c, self%msg)
                self%msg = 'consistent initial values (IDACalcIC) failed: '//self%msg
            end if
        end associate
    end subroutine solver_initial_values

    subroutine solver_advance(self, tout, t, y, yp, stat, one_step, tstop, reached)
        class(residual_solver), intent(inout) :: self
        real(wp), intent(in) :: tout                !! where to go
        real(wp), intent(inout) :: t                !! in: the current time; out: the time reached
        real(wp), intent(inout) :: y(:), yp(:)      !! out: y and y' at t
        integer, intent(out) :: stat                !! regdae_success, regdae_root_found, or a failure
        logical, intent(in), optional :: one_step   !! return after each step short of tout (DDASKR's INFO(3) = 1)
        real(wp), intent(in), optional :: tstop     !! do not step past tstop (DDASKR's INFO(4) = 1)
        integer, intent(out), optional :: reached   !! reached_tout, _step, _tstop or _root
        integer :: how
        logical :: each_step
        real(wp) :: direction, tn

        how = 0
        if (.not. started(self, stat)) return
        associate (c => self%core)
            call clear_failure(c)
            if (c%ic_pending) then
                call self%initial_values(tout, y, yp, stat)
                if (stat /= regdae_success) return
            end if
            each_step = .false.
            if (present(one_step)) each_step = one_step
            direction = sign(1.0_wp, tout - t)
            tn = current_time(c)
            if (c%root_pending .and. (c%t_root - tout)*direction <= 0.0_wp) then
                ! a root of the last step beyond the last tout: return it now
                call interpolate(c, c%t_root, t, y, yp, stat)
                c%root_pending = .false.
                how = reached_root
            else if (each_step .and. steps_taken(c) > 0 .and. (tn - tout)*direction >= 0.0_wp) then
                call interpolate(c, tout, t, y, yp, stat)   ! tout inside the last step
                how = reached_tout
            else
                call solve(c, tout, each_step, tstop, direction, t, y, yp, stat, how)
            end if
            if (stat == regdae_success .and. how == reached_root) stat = regdae_root_found
            self%msg = ''
            if (stat /= regdae_success .and. stat /= regdae_root_found) call failure_text(c, self%msg)
        end associate
        if (present(reached)) reached = how
    end subroutine solver_advance

    ! One call of IDASolve (IDA_NORMAL, or IDA_ONE_STEP with tout inside the step
    ! interpolated and a root beyond tout kept for the next call).
    subroutine solve(c, tout, each_step, tstop, direction, t, y, yp, stat, how)
        type(residual_core), intent(inout) :: c
        real(wp), intent(in) :: tout, direction
        logical, intent(in) :: each_step
        real(wp), intent(in), optional :: tstop
        real(wp), intent(inout) :: t, y(:), yp(:)
        integer, intent(out) :: stat, how
        real(c_double) :: tret(1)
        real(c_double), pointer :: p(:)
        integer(c_int) :: flag, mode
        real(wp) :: t_before
        t_before = t
        if (present(tstop)) then
            flag = FIDASetStopTime(c%ida_mem, tstop)
        else
            flag = FIDASetStopTime(c%ida_mem, sign(far_away, direction))
        end if
        mode = merge(IDA_ONE_STEP, IDA_NORMAL, each_step)
        tret(1) = t
        if (flag == 0) flag = FIDASolve(c%ida_mem, tout, tret, c%yy, c%yp, mode)
        c%flag = int(flag)
        how = 0
        select case (flag)
        case (IDA_SUCCESS)
            how = reached_tout
            if (each_step .and. (tret(1) - tout)*direction < 0.0_wp) how = reached_step
            ! tstop = tout: IDA's test of tout comes first; the step ended at tstop all the same
            if (present(tstop)) then
                if (tret(1) == tstop) how = reached_tstop
            end if
        case (IDA_TSTOP_RETURN)
            how = reached_tstop
        case (IDA_ROOT_RETURN)
            how = reached_root
            flag = FIDAGetRootInfo(c%ida_mem, c%found)
            if (each_step .and. (tret(1) - tout)*direction > 0.0_wp) then
                c%root_pending = .true.   ! beyond tout: tout first, the root at the next call
                c%t_root = tret(1)
                how = reached_tout
            end if
        case default
            stat = failure_status(c, regdae_err_integration)
            t = tret(1)
            if (flag == IDA_ILL_INPUT .or. .not. ((t - t_before)*direction >= 0.0_wp)) t = t_before
            p => FN_VGetArrayPointer(c%yy)
            y = p
            p => FN_VGetArrayPointer(c%yp)
            yp = p
            return
        end select
        if (how == reached_tout .and. each_step .and. (tret(1) - tout)*direction > 0.0_wp) then
            call interpolate(c, tout, t, y, yp, stat)
            return
        end if
        t = tret(1)
        p => FN_VGetArrayPointer(c%yy)
        y = p
        p => FN_VGetArrayPointer(c%yp)
        yp = p
        stat = regdae_success
    end subroutine solve

    ! y, y' at tw from IDA's interpolant (tw within the last step).
    subroutine interpolate(c, tw, t, y, yp, stat)
        type(residual_core), intent(inout) :: c
        real(wp), intent(in) :: tw
        real(wp), intent(out) :: t, y(:), yp(:)
        integer, intent(out) :: stat
        integer(c_int) :: ierr
        real(c_double), pointer :: p(:)
        ierr = FIDAGetDky(c%ida_mem, tw, 0_c_int, c%yy)
        if (ierr == 0) ierr = FIDAGetDky(c%ida_mem, tw, 1_c_int, c%yp)
        c%flag = int(ierr)
        stat = merge(regdae_success, regdae_err_integration, ierr == 0)
        t = tw
        p => FN_VGetArrayPointer(c%yy)
        y = p
        p => FN_VGetArrayPointer(c%yp)
        yp = p
    end subroutine interpolate

    ! True if the solver was initialized; else stat and the message say so.
    logical function started(self, stat)
        class(residual_solver), intent(inout) :: self
        integer, intent(out) :: stat
        started = associated(self%core)
        stat = regdae_success
        if (started) return
        stat = regdae_err_not_initialized
        self%msg = 'the solver is not initialized (init first, or init failed)'
    end function started

    real(wp) function current_time(c) result(tn)
        type(residual_core), intent(in) :: c
        real(c_double) :: tcur(1)
        tcur(1) = 0.0_wp
        if (FIDAGetCurrentTime(c%ida_mem, tcur) /= 0) tcur(1) = 0.0_wp
        tn = tcur(1)
    end function current_time

    integer(int64) function steps_taken(c) result(nst)
        type(residual_core), intent(in) :: c
        integer(c_long) :: k(1)
        k(1) = 0
        if (FIDAGetNumSteps(c%ida_mem, k) /= 0) k(1) = 0
        nst = k(1)
    end function steps_taken

    subroutine clear_failure(c)
        type(residual_core), intent(inout) :: c
        c%callback_stat = 0
        c%callback_name = ''
        c%ida_message = ''
        c%weight_component = 0
        c%flag = 0
    end subroutine clear_failure

    ! The status of a failed IDA call: a user callback's unrecoverable failure, bad
    ! input, or `otherwise`.
    integer function failure_status(c, otherwise) result(stat)
        type(residual_core), intent(in) :: c
        integer, intent(in) :: otherwise
        stat = otherwise
        if (c%callback_stat < 0) then
            stat = regdae_err_user_callback
        else if (c%flag == IDA_ILL_INPUT .and. c%weight_component == 0) then
            stat = regdae_err_bad_input
        end if
    end function failure_status

    ! What failed: the user's routine by its name, IDA's message.
    subroutine failure_text(c, text)
        type(residual_core), intent(in) :: c
        character(len=:), allocatable, intent(out) :: text
        integer :: code
        text = ''
        if (c%weight_component > 0) then
            text = 'the error weight of component '//format_int(c%weight_component)//' is not positive (ATOL = 0 '// &
                   'there and the component is 0): give it a positive absolute tolerance; '
        end if
        if (len(c%callback_name) > 0) then
            code = c%callback_stat
            if (c%names(1) == 'RES' .and. code > 0) code = -1   ! DDASKR's RES: IRES = -1 is the recoverable failure
            text = text//trim(c%callback_name)//' returned '//trim(merge('IRES', 'stat', c%names(1) == 'RES'))// &
                   ' = '//format_int(code)//' at t = '//format_real(c%callback_t)//'; '
        end if
        if (c%flag /= 0) text = text//'IDA flag '//format_int(c%flag)
        if (len(c%ida_message) > 0) text = text//' ('//c%ida_message//')'
    end subroutine failure_text

    function solver_statistics(self) result(st)
        class(residual_solver), intent(in) :: self
        type(residual_stats) :: st
        integer(c_long) :: k(1)
        integer(c_int) :: q(1), ierr
        real(c_double) :: h(1)
        if (.not. associated(self%core)) return
        associate (m => self%core%ida_mem)
            ierr = FIDAGetNumSteps(m, k); st%steps = k(1)
            ierr = FIDAGetNumResEvals(m, k); st%res_evals = k(1)
            ierr = FIDAGetNumLinResEvals(m, k); st%res_evals = st%res_evals + k(1)
            ierr = FIDAGetNumJacEvals(m, k); st%jac_evals = k(1)
            ierr = FIDAGetNumErrTestFails(m, k); st%err_test_fails = k(1)
            ierr = FIDAGetNumNonlinSolvConvFails(m, k); st%conv_fails = k(1)
            ierr = FIDAGetNumNonlinSolvIters(m, k); st%nonlin_iters = k(1)
            if (self%core%nroots > 0) then
                ierr = FIDAGetNumGEvals(m, k); st%root_evals = k(1)
            end if
            ierr = FIDAGetLastOrder(m, q); st%order_last = q(1)
            ierr = FIDAGetCurrentOrder(m, q); st%order_next = q(1)
            ierr = FIDAGetLastStep(m, h); st%h_last = h(1)
            ierr = FIDAGetCurrentStep(m, h); st%h_next = h(1)
            ierr = FIDAGetCurrentTime(m, h); st%t_reached = h(1)
        end associate
    end function solver_statistics

    function solver_roots(self) result(found)
        class(residual_solver), intent(in) :: self
        integer, allocatable :: found(:)
        if (associated(self%core)) then
            found = self%core%found
        else
            allocate (found(0))
        end if
    end function solver_roots

    function solver_message(self) result(msg)
        class(residual_solver), intent(in) :: self
        character(len=text_length(self%msg)) :: msg
        if (allocated(self%msg)) msg = self%msg
    end function solver_message

    integer function solver_ida_flag(self) result(flag)
        class(residual_solver), intent(in) :: self
        flag = 0
        if (associated(self%core)) flag = self%core%flag
    end function solver_ida_flag

    function solver_problem(self) result(p)
        class(residual_solver), intent(in) :: self
        class(residual_problem), pointer :: p
        p => null()
        if (associated(self%core)) p => self%core%problem
    end function solver_problem

    subroutine solver_name_routines(self, residual, jacobian, roots)
        class(residual_solver), intent(inout) :: self
        character(len=*), intent(in) :: residual, jacobian, roots   !! the names messages use
        if (associated(self%core)) self%core%names = [character(len=8) :: residual, jacobian, roots]
    end subroutine solver_name_routines

    subroutine solver_set_tolerances(self, rtol, atol)
        class(residual_solver), intent(inout) :: self
        real(wp), intent(in) :: rtol(:), atol(:)   !! per component (>= 0; checked by the caller)
        if (.not. associated(self%core)) return
        self%core%rtol = rtol
        self%core%atol = atol
    end subroutine solver_set_tolerances

    logical function solver_ready(self)
        class(residual_solver), intent(in) :: self
        solver_ready = associated(self%core)
    end function solver_ready

    subroutine solver_free(self)
        class(residual_solver), intent(inout) :: self
        integer(c_int) :: ierr
        if (.not. associated(self%core)) return
        associate (c => self%core)
            if (c_associated(c%ida_mem)) call FIDAFree(c%ida_mem)
            if (associated(c%ls)) ierr = FSUNLinSolFree(c%ls)
            if (associated(c%jmat)) call FSUNMatDestroy(c%jmat)
            if (associated(c%cons)) call FN_VDestroy(c%cons)
            if (associated(c%idv)) call FN_VDestroy(c%idv)
            if (associated(c%yp)) call FN_VDestroy(c%yp)
            if (associated(c%yy)) call FN_VDestroy(c%yy)
            if (c_associated(c%sunctx)) ierr = FSUNContext_Free(c%sunctx)
        end associate
        deallocate (self%core)
    end subroutine solver_free

    ! ---------------------------------------------------------------------
    ! The bind(C) callbacks: IDA's user_data is the core.
    ! ---------------------------------------------------------------------

    ! A user callback's stat as IDA's flag (0, 1 recoverable, -1 stop), the failure kept.
    integer(c_int) function callback_flag(c, which, t, stat) result(ierr)
        type(residual_core), intent(inout) :: c
        integer, intent(in) :: which, stat
        real(wp), intent(in) :: t
        ierr = 0
        if (stat == 0) return
        ierr = merge(1_c_int, -1_c_int, stat > 0)
        c%callback_stat = stat
        c%callback_name = trim(c%names(which))
        c%callback_t = t
    end function callback_flag

    integer(c_int) function plain_ida_residual(t, nv_y, nv_yp, nv_r, user_data) result(ierr) bind(C)
        real(c_double), value :: t
        type(N_Vector) :: nv_y, nv_yp, nv_r
        type(c_ptr), value :: user_data
        type(residual_core), pointer :: c
        real(c_double), pointer :: y(:), yp(:), r(:)
        integer :: stat
        real(c_double) :: cj(1)
        call c_f_pointer(user_data, c)
        y => FN_VGetArrayPointer(nv_y)
        yp => FN_VGetArrayPointer(nv_yp)
        r => FN_VGetArrayPointer(nv_r)
        if (FIDAGetCurrentCj(c%ida_mem, cj) == 0) c%problem%cj = cj(1)
        stat = 0
        call c%problem%residual(t, y, yp, r, stat)
        ierr = callback_flag(c, 1, t, stat)
    end function plain_ida_residual

    ! The user's dF/dy + cj dF/dy', dense in place or band through c%pd (LINPACK
    ! storage, copied into SUNDIALS' band matrix).
    integer(c_int) function plain_ida_jacobian(t, cj, nv_y, nv_yp, nv_r, jmat, user_data, tmp1, tmp2, tmp3) &
        result(ierr) bind(C)
        real(c_double), value :: t, cj
        type(N_Vector) :: nv_y, nv_yp, nv_r
        type(SUNMatrix) :: jmat
        type(c_ptr), value :: user_data
        type(N_Vector) :: tmp1, tmp2, tmp3
        type(residual_core), pointer :: c
        real(c_double), pointer :: y(:), yp(:), jdata(:), dense(:, :)
        integer :: stat, i, j, ml, mu, ldim, smu, n
        call c_f_pointer(user_data, c)
        y => FN_VGetArrayPointer(nv_y)
        yp => FN_VGetArrayPointer(nv_yp)
        n = c%neq
        stat = 0
        if (.not. c%band) then
            jdata => FSUNDenseMatrix_Data(jmat)
            call c_f_pointer(c_loc(jdata(1)), dense, [n, n])
            dense = 0.0_wp
            call c%problem%jacobian(t, y, yp, cj, dense, stat)
        else
            ml = c%opts%band_lower
            mu = c%opts%band_upper
            c%pd = 0.0_wp
            call c%problem%jacobian(t, y, yp, cj, c%pd, stat)
            jdata => FSUNBandMatrix_Data(jmat)
            ldim = int(FSUNBandMatrix_LDim(jmat))
            smu = int(FSUNBandMatrix_StoredUpperBandwidth(jmat))
            call c_f_pointer(c_loc(jdata(1)), dense, [ldim, n])
            do j = 1, n
                do i = max(1, j - mu), min(n, j + ml)
                    dense(smu + i - j + 1, j) = c%pd(i - j + ml + mu + 1, j)
                end do
            end do
        end if
        ierr = callback_flag(c, 2, t, stat)
    end function plain_ida_jacobian

    integer(c_int) function plain_ida_roots(t, nv_y, nv_yp, gout, user_data) result(ierr) bind(C)
        real(c_double), value :: t
        type(N_Vector) :: nv_y, nv_yp
        real(c_double) :: gout(*)
        type(c_ptr), value :: user_data
        type(residual_core), pointer :: c
        real(c_double), pointer :: y(:), yp(:)
        integer :: stat
        call c_f_pointer(user_data, c)
        y => FN_VGetArrayPointer(nv_y)
        yp => FN_VGetArrayPointer(nv_yp)
        stat = 0
        call c%problem%roots(t, y, yp, gout(1:c%nroots), stat)
        ierr = callback_flag(c, 3, t, stat)
        if (ierr > 0) ierr = -1   ! IDA's root functions have no recoverable failure
    end function plain_ida_roots

    ! Error weights 1/(rtol_i |y_i| + atol_i) (DDASKR's DDAWTS with vector tolerances);
    ! -1 if one is not positive (the component kept for the message).
    integer(c_int) function plain_ida_error_weights(nv_y, nv_ewt, user_data) result(ierr) bind(C)
        type(N_Vector) :: nv_y, nv_ewt
        type(c_ptr), value :: user_data
        type(residual_core), pointer :: c
        real(c_double), pointer :: y(:), ewt(:)
        integer :: i
        real(wp) :: w
        call c_f_pointer(user_data, c)
        y => FN_VGetArrayPointer(nv_y)
        ewt => FN_VGetArrayPointer(nv_ewt)
        ierr = 0
        do i = 1, c%neq
            w = c%rtol(i)*abs(y(i)) + c%atol(i)
            if (.not. (w > 0.0_wp)) then
                c%weight_component = i
                ierr = -1
                return
            end if
            ewt(i) = 1.0_wp/w
        end do
    end function plain_ida_error_weights

    ! Keep IDA's last message in the core instead of printing it.
    subroutine plain_ida_error_handler(error_code, module_name, function_name, msg, user_data) bind(C)
        integer(c_int), value :: error_code
        type(c_ptr), value :: module_name, function_name, msg
        type(c_ptr), value :: user_data
        type(residual_core), pointer :: c
        if (error_code == 0) return
        call c_f_pointer(user_data, c)
        c%ida_message = c_string(function_name)//': '//c_string(msg)
    end subroutine plain_ida_error_handler

end module regdae_residual_solver
