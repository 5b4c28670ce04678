!> The IDA backend: SUNDIALS IDA integrating an `implicit_system`, with the
!! bind(C) callbacks that reach the backend through IDA's user_data, the
!! difference-quotient Jacobian, the error weights that leave unknowns out of
!! the error test, and IDA's counters.
!!
!! Linear solvers: dense (SUNLinSol_Dense), band (SUNLinSol_Band) and sparse
!! (SUNLinSol_KLU). A system without a pattern gets the dense matrix and one
!! residual per column; a structured system gets its Jacobian by grouped
!! difference quotients (Curtis, Powell and Reid: the columns of one group share
!! no row and are perturbed together, one residual per group), stored in the
!! chosen matrix. The increments do not depend on IDA's error weights, so the
!! Jacobian is defined also where a weight is zero.
!!
!! Tolerances: IDA controls the local error of each step, and on a motion that
!! does not damp its errors (a mechanism) they add up over the steps: the global
!! error grows like tau^(q/(q+1)) for IDA's tolerance tau and order q. IDA gets
!! the tolerance of `ida_relative_tolerance` (tighter than rtol below 1e-3), so
!! that the error follows rtol (doc/methods.md, "Integrators"). The algebraic
!! unknowns left out of the error test stay in Newton's convergence test with a
!! relative tolerance of at least sqrt(u) (`algebraic_rtol`).
!! IDA's weighted norms divide by all its unknowns, those left out of the error
!! test included: the weights of the unknowns in the test are multiplied by
!! sqrt(neq / unknowns in the test), so that the error test is the RMS over them
!! whatever the formulation adds (doc/methods.md, "The error test's norm").
!!
!! The backend object must not move while IDA exists (its address is IDA's
!! user_data): the solver front keeps it inside its heap-allocated core.
module regdae_ida_backend
    use, intrinsic :: iso_c_binding
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fida_mod
    use fsundials_context_mod
    use fsundials_nvector_mod
    use fnvector_serial_mod
    use fsundials_matrix_mod
    use fsunmatrix_dense_mod
    use fsunmatrix_band_mod
    use fsunmatrix_sparse_mod
    use fsundials_linearsolver_mod
    use fsunlinsol_dense_mod
    use fsunlinsol_band_mod
    use fsunlinsol_klu_mod
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_format, only: format_real, format_int
    use regdae_options, only: solver_options, exclusion_weights, exclusion_suppress, excluded_vy, linear_solver_dense, &
                              linear_solver_band, linear_solver_sparse, linear_solver_name
    use regdae_implicit_system, only: implicit_system
    use regdae_sparsity, only: sparsity_pattern, column_groups, permuted_bandwidths
    use regdae_solver_stats, only: solver_stats
    use regdae_c_strings, only: c_string
    implicit none
    private

    public :: ida_relative_tolerance

    !> rtol at and above which IDA gets rtol itself.
    real(wp), parameter :: proportional_from = 1.0e-3_wp
    !> IDA's largest order q (its default): the global error of error-per-step
    !! control grows like tau^(q/(q+1)).
    real(wp), parameter :: bdf_order = 5.0_wp
    !> The smallest relative tolerance IDA gets from the mapping: 100 u, the bound
    !! below which DASSL refuses tolerances as too stringent.
    real(wp), parameter :: smallest_ida_rtol = 100.0_wp*epsilon(1.0_wp)
    !> The smallest relative tolerance of the algebraic unknowns left out of the
    !! error test (y; u and s of the augmented formulation), in Newton's convergence
    !! test: sqrt(u). They solve a linear system of condition up to
    !! (max_i (GB)_ii)^2/eps near a singular configuration, where a tighter test
    !! fails on rounding alone (measured: the augmented slider crank at rtol 1e-13,
    !! corrector failures down to h = 2e-18 at t = 2.59). With excluded=vy the
    !! velocities, differential unknowns, are left out too and keep the full test
    !! (with it on them too the augmented slider crank failed at rtol 1e-9 and 1e-10).
    real(wp), parameter :: algebraic_rtol = sqrt(epsilon(1.0_wp))

    !> IDA and everything its callbacks need.
    type, public :: ida_backend
        class(implicit_system), allocatable :: system   !! the residual integrated
        type(solver_options) :: opts                    !! tolerances, exclusion, step limits
        integer :: neq = 0
        integer :: linear_solver = linear_solver_dense  !! the matrix IDA factors
        logical, allocatable :: excluded(:)             !! unknowns left out of the error test
        ! grouped difference quotients (structured systems): the columns of group c are
        ! group_cols(group_start(c):group_start(c+1)-1); column j holds the rows
        ! csc_rows(csc_start(j):csc_start(j+1)-1)
        integer :: ngroups = 0
        integer, allocatable :: group_start(:), group_cols(:), csc_start(:), csc_rows(:)
        integer :: band_upper = 0, band_lower = 0
        real(wp), allocatable :: delta(:)
        type(c_ptr) :: sunctx = c_null_ptr
        type(c_ptr) :: ida_mem = c_null_ptr
        type(N_Vector), pointer :: uu => null(), up => null(), idv => null()
        type(N_Vector), pointer :: constraints => null()   ! IDASetConstraints: 1 for the unknowns kept >= 0
        type(SUNMatrix), pointer :: jmat => null()
        type(SUNLinearSolver), pointer :: ls => null()
        real(wp), allocatable :: u_pert(:), up_pert(:), r_pert(:)
        real(wp), allocatable :: atol_u(:)   ! the absolute tolerance of each unknown (the user's)
        ! IDA's tolerances (ida_relative_tolerance): rtol_ida, and atol_u scaled by
        ! rtol_ida/rtol; the factor by which the algebraic unknowns left out of the
        ! error test have them loosened in Newton's test (algebraic_rtol)
        real(wp) :: rtol_ida = 0.0_wp
        real(wp), allocatable :: atol_ida(:)
        real(wp) :: algebraic_factor = 1.0_wp
        ! sqrt(neq / unknowns in the error test): IDA's weighted norms divide by neq, the
        ! unknowns left out included; the weights of those in the test carry this factor
        real(wp) :: test_scale = 1.0_wp
        integer(c_long) :: jac_res_evals = 0
        type(solver_stats) :: carried                   !! IDA's counters before the last FIDAReInit (which zeroes them)
        integer :: pending_stat = regdae_success        !! last failure seen in a callback
        logical :: pending_recoverable = .true.
        character(len=:), allocatable :: pending_message, ida_message
        ! recoverable residual failures that IDA has not got past: how many, and the
        ! earliest time at which one happened (see note_recoverable_failure)
        integer :: stall_count = 0
        real(wp) :: stall_t = 0.0_wp
        ! u, u' hold IDA's interpolant at t_interpolated (set by interpolate only; a step,
        ! a restart or a write into state() forgets it): interpolate there again is a no-op
        logical :: interpolated = .false.
        real(wp) :: t_interpolated = 0.0_wp
        ! u' at t_interpolated not yet computed: slope() takes it from IDA's interpolant (the
        ! slope of an output time is read only where the monitor's sample or the caller needs it)
        logical :: slope_pending = .false.
    contains
        !> Create the SUNDIALS context, vectors, IDA memory and the linear solver.
        procedure :: create => backend_create
        !> Consistent initial values by IDACalcIC (IDA_YA_YDP_INIT): the algebraic
        !! unknowns and the derivatives of the differential ones.
        procedure :: calc_ic => backend_calc_ic
        !> Integrate to tout (IDA_NORMAL); tret: the time reached; ierr: IDA's flag.
        procedure :: solve => backend_solve
        !> One internal step towards tout (IDA_ONE_STEP): u, u' at the step's end.
        procedure :: step => backend_step
        !> IDA's internal time (the end of its last step).
        procedure :: current_time => backend_current_time
        !> The step size IDA used last.
        procedure :: last_step => backend_last_step
        !> Restart IDA at (t, u, u') (its history forgotten).
        procedure :: restart => backend_restart
        !> u, u' at t within IDA's last step, from its interpolant (nothing to do
        !! where they hold it at t already).
        procedure :: interpolate => backend_interpolate
        !> u or u' was written other than by interpolate: the next interpolate computes.
        procedure :: forget_interpolation => backend_forget_interpolation
        !> IDA's solution vector u and its derivative u' (at the last return).
        procedure :: state => backend_state
        procedure :: slope => backend_slope
        !> The status of a failed solve: the callback's unrecoverable status, or
        !! regdae_err_integration.
        procedure :: failure_status => backend_failure_status
        !> A structured system: the grouped difference-quotient Newton matrix against
        !! the column-by-column one at IDA's current u, u' (a pattern that misses a
        !! dependence makes them differ); stat = regdae_err_jacobian with the worst entry.
        procedure :: check_grouped_jacobian => backend_check_grouped
        !> IDA's counters into a solver_stats record.
        procedure :: get_statistics => backend_statistics
        !> Free all SUNDIALS objects.
        procedure :: free => backend_free
    end type ida_backend

    interface
        !> The grouped Newton matrix against the column-by-column one (submodule
        !! `regdae_ida_checks`).
        module subroutine backend_check_grouped(self, t, cj, stat, msg)
            class(ida_backend), intent(inout) :: self
            real(wp), intent(in) :: t, cj
            integer, intent(out) :: stat
            character(len=:), allocatable, intent(out) :: msg
        end subroutine backend_check_grouped
        !> IDA's counters into a solver_stats record (submodule `regdae_ida_checks`).
        module subroutine backend_statistics(self, st)
            class(ida_backend), intent(in) :: self
            type(solver_stats), intent(inout) :: st
        end subroutine backend_statistics
        !> The system's residual; 0, or +1 (recoverable) / -1 (fatal) after recording the
        !! failure in the backend (submodule `regdae_ida_checks`).
        integer(c_int) module function evaluate_residual(self, t, u, up, res) result(ierr)
            type(ida_backend), intent(inout) :: self
            real(wp), intent(in) :: t, u(:), up(:)
            real(wp), intent(out) :: res(:)
        end function evaluate_residual
        !> A callback of the system failed at t: kept for failure_status, and IDA's flag
        !! (1: recoverable, -1: not) (submodule `regdae_ida_checks`).
        integer(c_int) module function callback_failure(self, t, stat, recoverable) result(ierr)
            type(ida_backend), intent(inout) :: self
            real(wp), intent(in) :: t
            integer, intent(in) :: stat
            logical, intent(in) :: recoverable
        end function callback_failure
    end interface

contains

    subroutine backend_create(self, system, opts, linear_solver, excluded, t0, u0, up0, stat, msg, atol_u)
        class(ida_backend), target, intent(inout) :: self
        class(implicit_system), intent(in) :: system     !! copied into the backend
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: linear_solver             !! linear_solver_dense, _band or _sparse (resolved)
        logical, intent(in) :: excluded(:)               !! length neq
        real(wp), intent(in) :: t0, u0(:), up0(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), intent(in), optional :: atol_u(:)      !! absolute tolerance per unknown (default: opts%atol)
        integer(c_long) :: neq
        integer(c_int) :: ierr
        real(c_double), pointer :: p(:)
        type(c_ptr) :: user_data
        self%interpolated = .false.
        self%slope_pending = .false.

        user_data = c_null_ptr
        select type (self)
        type is (ida_backend)
            user_data = c_loc(self)   ! what the callbacks receive
        end select
        allocate (self%system, source=system)
        self%opts = opts
        self%neq = system%neq
        self%linear_solver = linear_solver
        if (self%system%structured) call prepare_groups(self)
        self%excluded = excluded
        self%test_scale = sqrt(real(self%neq, wp)/real(max(1, count(.not. excluded)), wp))
        if (present(atol_u)) then
            self%atol_u = atol_u
        else
            self%atol_u = spread(opts%atol, 1, self%neq)
        end if
        self%rtol_ida = ida_relative_tolerance(opts%rtol)
        self%atol_ida = self%atol_u*(self%rtol_ida/opts%rtol)
        ! excluded=y: the unknowns left out are the algebraic ones
        self%algebraic_factor = 1.0_wp
        if (opts%excluded /= excluded_vy) self%algebraic_factor = max(1.0_wp, algebraic_rtol/self%rtol_ida)
        self%pending_message = ''
        self%ida_message = ''
        allocate (self%u_pert(self%neq), self%up_pert(self%neq), self%r_pert(self%neq))
        stat = regdae_err_sundials
        neq = int(self%neq, c_long)
        ierr = FSUNContext_Create(c_null_ptr, self%sunctx)
        if (ierr /= 0) then
            msg = 'FSUNContext_Create failed'
            return
        end if
        self%uu => FN_VNew_Serial(neq, self%sunctx)
        self%up => FN_VNew_Serial(neq, self%sunctx)
        if (.not. (associated(self%uu) .and. associated(self%up))) then
            msg = 'FN_VNew_Serial failed'
            return
        end if
        p => FN_VGetArrayPointer(self%uu)
        p = u0(1:self%neq)
        p => FN_VGetArrayPointer(self%up)
        p = up0(1:self%neq)

        self%ida_mem = FIDACreate(self%sunctx)
        if (.not. c_associated(self%ida_mem)) then
            msg = 'FIDACreate failed'
            return
        end if
        ierr = FIDASetErrHandlerFn(self%ida_mem, c_funloc(ida_error_handler), user_data)
        if (ierr == 0) ierr = FIDAInit(self%ida_mem, c_funloc(ida_residual), t0, self%uu, self%up)
        if (ierr == 0) ierr = FIDASetUserData(self%ida_mem, user_data)
        if (ierr /= 0) then
            msg = 'FIDAInit failed: '//self%ida_message
            return
        end if

        ! Tolerances (our error weights: IDA's tolerances, and the unknowns left out of
        ! the error test) and the exclusion of y (and v) from the local error test.
        ierr = FIDAWFtolerances(self%ida_mem, c_funloc(ida_error_weights))
        if (ierr == 0 .and. any(self%excluded) .and. opts%exclusion == exclusion_suppress) then
            self%idv => FN_VNew_Serial(neq, self%sunctx)
            if (.not. associated(self%idv)) then
                msg = 'FN_VNew_Serial failed'
                return
            end if
            p => FN_VGetArrayPointer(self%idv)
            p = merge(0.0_wp, 1.0_wp, self%excluded)   ! 0: left out of the error test
            ierr = FIDASetId(self%ida_mem, self%idv)
            if (ierr == 0) ierr = FIDASetSuppressAlg(self%ida_mem, 1_c_int)
        end if
        if (ierr /= 0) then
            msg = 'setting the tolerances failed: '//self%ida_message
            return
        end if
        call set_nonnegative(self, msg)
        if (len(msg) > 0) return

        ! The linear solver, with our own, weight-independent Jacobian.
        call create_linear_solver(self, msg)
        if (len(msg) > 0) return
        ierr = FIDASetLinearSolver(self%ida_mem, self%ls, self%jmat)
        if (ierr == 0) then
            if (self%system%structured) then
                ierr = FIDASetJacFn(self%ida_mem, c_funloc(ida_jacobian_grouped))
            else
                ierr = FIDASetJacFn(self%ida_mem, c_funloc(ida_jacobian))
            end if
        end if
        if (ierr == 0) ierr = FIDASetMaxNumSteps(self%ida_mem, int(opts%max_steps, c_long))
        if (ierr == 0 .and. opts%max_order < 5) ierr = FIDASetMaxOrd(self%ida_mem, int(opts%max_order, c_int))
        if (ierr == 0 .and. opts%h_init > 0.0_wp) ierr = FIDASetInitStep(self%ida_mem, opts%h_init)
        if (ierr == 0 .and. opts%h_max > 0.0_wp) ierr = FIDASetMaxStep(self%ida_mem, opts%h_max)
        if (ierr /= 0) then
            msg = 'IDA setup failed: '//self%ida_message
            return
        end if
        stat = regdae_success
        msg = ''
    end subroutine backend_create

    ! IDA's constraint option (IDASetConstraints, code 1: >= 0) for the unknowns the
    ! system keeps nonnegative, if any; msg is empty on success.
    subroutine set_nonnegative(self, msg)
        type(ida_backend), intent(inout) :: self
        character(len=:), allocatable, intent(out) :: msg
        logical :: mask(self%neq)
        real(c_double), pointer :: p(:)
        msg = ''
        mask = self%system%nonnegative_unknowns()
        if (.not. any(mask)) return
        self%constraints => FN_VNew_Serial(int(self%neq, c_long), self%sunctx)
        if (.not. associated(self%constraints)) then
            msg = 'FN_VNew_Serial failed'
            return
        end if
        p => FN_VGetArrayPointer(self%constraints)
        p = merge(1.0_wp, 0.0_wp, mask)
        if (FIDASetConstraints(self%ida_mem, self%constraints) /= 0) &
            msg = 'setting the nonnegativity constraints failed: '//self%ida_message
    end subroutine set_nonnegative

    ! The groups of columns and the column pattern of a structured system.
    subroutine prepare_groups(self)
        type(ida_backend), intent(inout) :: self
        type(sparsity_pattern) :: columns
        integer :: j
        associate (p => self%system%jac_pattern)
            columns = p%transposed()
            self%csc_start = columns%row_start
            self%csc_rows = columns%cols
            call column_groups(p, self%ngroups, self%group_start, self%group_cols, columns)
            call permuted_bandwidths(p, [(j, j=1, p%ncols)], self%band_lower, self%band_upper)
        end associate
        allocate (self%delta(self%neq))
    end subroutine prepare_groups

    ! The SUNDIALS matrix and linear solver of `linear_solver`; msg is empty on success.
    subroutine create_linear_solver(self, msg)
        type(ida_backend), intent(inout) :: self
        character(len=:), allocatable, intent(out) :: msg
        integer(c_long) :: neq
        msg = ''
        neq = int(self%neq, c_long)
        select case (self%linear_solver)
        case (linear_solver_band)
            self%jmat => FSUNBandMatrix(neq, int(self%band_upper, c_long), int(self%band_lower, c_long), self%sunctx)
            if (associated(self%jmat)) self%ls => FSUNLinSol_Band(self%uu, self%jmat, self%sunctx)
        case (linear_solver_sparse)
            self%jmat => FSUNSparseMatrix(neq, neq, int(max(1, size(self%csc_rows)), c_long), CSC_MAT, self%sunctx)
            if (associated(self%jmat)) self%ls => FSUNLinSol_KLU(self%uu, self%jmat, self%sunctx)
        case default
            self%jmat => FSUNDenseMatrix(neq, neq, self%sunctx)
            if (associated(self%jmat)) self%ls => FSUNLinSol_Dense(self%uu, self%jmat, self%sunctx)
        end select
        if (.not. (associated(self%jmat) .and. associated(self%ls))) &
            msg = 'creating the '//linear_solver_name(self%linear_solver)//' matrix or linear solver failed'
    end subroutine create_linear_solver

    subroutine backend_calc_ic(self, differential, tout1, stat, msg)
        class(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: differential(:)   !! 1: differential unknown (kept), 0: algebraic (computed)
        real(wp), intent(in) :: tout1             !! the first output time (sets IDA's step for the iteration)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        type(N_Vector), pointer :: id
        real(c_double), pointer :: p(:)
        integer(c_int) :: ierr
        self%interpolated = .false.
        self%slope_pending = .false.
        stat = regdae_success
        msg = ''
        id => FN_VNew_Serial(int(self%neq, c_long), self%sunctx)
        p => FN_VGetArrayPointer(id)
        p = differential
        ierr = FIDASetId(self%ida_mem, id)
        if (ierr == 0) ierr = FIDACalcIC(self%ida_mem, IDA_YA_YDP_INIT, tout1)
        if (ierr == 0) ierr = FIDAGetConsistentIC(self%ida_mem, self%uu, self%up)
        ! the error test's id (suppress) again, if any
        if (associated(self%idv)) then
            if (ierr == 0) ierr = FIDASetId(self%ida_mem, self%idv)
        end if
        call FN_VDestroy(id)
        if (ierr /= 0) then
            stat = regdae_err_inconsistent_ic
            if (self%pending_stat /= regdae_success .and. .not. self%pending_recoverable) stat = self%pending_stat
            msg = 'consistent initial values (IDACalcIC) failed, flag '//format_int(int(ierr))//': '// &
                  self%ida_message
            if (len(self%pending_message) > 0) msg = msg//' | last residual failure: '//self%pending_message
        end if
    end subroutine backend_calc_ic

    subroutine backend_solve(self, tout, stop_at_output, tret, ierr)
        class(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: tout
        logical, intent(in) :: stop_at_output   !! make a step end at tout
        real(wp), intent(inout) :: tret         !! in: the current time; out: the time reached
        integer, intent(out) :: ierr            !! IDA's return flag (< 0: failure)
        real(c_double) :: t_reached(1)
        integer(c_int) :: flag
        real(wp) :: t_before
        self%interpolated = .false.
        self%slope_pending = .false.

        self%pending_stat = regdae_success
        if (len(self%pending_message) > 0) self%pending_message = ''
        t_before = tret
        t_reached(1) = tret   ! IDA does not write tret when it refuses its input
        if (within_roundoff_of_start(self, tret, tout)) then
            tret = tout
            ierr = 0
            return
        end if
        ! SUNDIALS 6.4.1 keeps a stop time in force after returning at it: set it anew each call.
        flag = 0
        if (stop_at_output) flag = FIDASetStopTime(self%ida_mem, tout)
        if (flag == 0) flag = FIDASolve(self%ida_mem, tout, t_reached, self%uu, self%up, IDA_NORMAL)
        ierr = int(flag)
        tret = t_reached(1)
        if (flag < 0) then
            ! On a failure during the integration IDA returns the last time
            ! reached and the solution there; on an input error, nothing.
            if (flag == IDA_ILL_INPUT .or. .not. (tret >= t_before .and. tret <= tout)) tret = t_before
        end if
    end subroutine backend_solve

    subroutine backend_step(self, tout, stop_at_output, tret, ierr)
        class(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: tout
        logical, intent(in) :: stop_at_output   !! the step does not go beyond tout
        real(wp), intent(inout) :: tret         !! in: the current time; out: the step's end
        integer, intent(out) :: ierr            !! IDA's return flag (< 0: failure)
        real(c_double) :: t_reached(1)
        integer(c_int) :: flag
        real(wp) :: t_before
        self%interpolated = .false.
        self%slope_pending = .false.

        self%pending_stat = regdae_success
        if (len(self%pending_message) > 0) self%pending_message = ''
        t_before = tret
        t_reached(1) = tret
        if (within_roundoff_of_start(self, tret, tout)) then
            tret = tout
            ierr = 0
            return
        end if
        flag = 0
        if (stop_at_output) flag = FIDASetStopTime(self%ida_mem, tout)
        if (flag == 0) flag = FIDASolve(self%ida_mem, tout, t_reached, self%uu, self%up, IDA_ONE_STEP)
        ierr = int(flag)
        tret = t_reached(1)
        if (flag < 0) then
            if (flag == IDA_ILL_INPUT .or. .not. (tret >= t_before)) tret = t_before
        end if
    end subroutine backend_step

    ! No step since IDA's (re)start (a restart inside a pass check, say) and tout within IDA's
    ! roundoff of the start, 2 u (|t| + |tout|): IDA refuses such a first call ("tout too
    ! close to t0"); the state at the start is the state at tout to that roundoff.
    logical function within_roundoff_of_start(self, t, tout) result(close)
        class(ida_backend), intent(in) :: self
        real(wp), intent(in) :: t, tout
        integer(c_long) :: nst(1)
        close = .false.
        if (.not. (abs(tout - t) < 2.0_wp*epsilon(1.0_wp)*(abs(t) + abs(tout)))) return
        if (.not. c_associated(self%ida_mem)) return
        if (FIDAGetNumSteps(self%ida_mem, nst) /= 0) return
        close = (nst(1) == 0)
    end function within_roundoff_of_start

    real(wp) function backend_current_time(self) result(t)
        class(ida_backend), intent(in) :: self
        real(c_double) :: tcur(1)
        integer(c_int) :: ierr
        ierr = FIDAGetCurrentTime(self%ida_mem, tcur)
        t = tcur(1)
    end function backend_current_time

    real(wp) function backend_last_step(self) result(h)
        class(ida_backend), intent(in) :: self
        real(c_double) :: hl(1)
        integer(c_int) :: ierr
        ierr = FIDAGetLastStep(self%ida_mem, hl)
        h = hl(1)
    end function backend_last_step

    subroutine backend_restart(self, t, u, up, stat)
        class(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: t, u(:), up(:)
        integer, intent(out) :: stat
        real(c_double), pointer :: p(:)
        self%interpolated = .false.
        self%slope_pending = .false.
        call self%get_statistics(self%carried)   ! FIDAReInit zeroes IDA's counters: keep them
        self%carried%jac_res_evals = 0           ! (counted by regdae itself, not reset)
        self%carried%res_evals = self%carried%res_evals - self%jac_res_evals
        p => FN_VGetArrayPointer(self%uu)
        p = u
        p => FN_VGetArrayPointer(self%up)
        p = up
        stat = int(FIDAReInit(self%ida_mem, t, self%uu, self%up))
        if (stat /= 0) stat = regdae_err_sundials
    end subroutine backend_restart

    subroutine backend_interpolate(self, t, ierr)
        class(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: t
        integer, intent(out) :: ierr
        if (self%interpolated .and. t == self%t_interpolated) then
            ierr = 0
            return
        end if
        ierr = int(FIDAGetDky(self%ida_mem, t, 0_c_int, self%uu))
        self%interpolated = (ierr == 0)
        self%slope_pending = self%interpolated   ! u' there: slope() computes it when asked
        self%t_interpolated = t
    end subroutine backend_interpolate

    subroutine backend_forget_interpolation(self)
        class(ida_backend), intent(inout) :: self
        self%interpolated = .false.   ! (a pending slope stays: IDA's interpolant is unchanged)
    end subroutine backend_forget_interpolation

    function backend_state(self) result(u)
        class(ida_backend), intent(in) :: self
        real(c_double), pointer :: u(:)
        u => FN_VGetArrayPointer(self%uu)
    end function backend_state

    function backend_slope(self) result(up)
        class(ida_backend), intent(in) :: self
        real(c_double), pointer :: up(:)
        integer(c_int) :: ierr
        ! (IDAGetDky at a time inside the last step, where interpolate succeeded: it cannot fail)
        if (self%slope_pending) ierr = FIDAGetDky(self%ida_mem, self%t_interpolated, 1_c_int, self%up)
        up => FN_VGetArrayPointer(self%up)
    end function backend_slope

    integer function backend_failure_status(self) result(stat)
        class(ida_backend), intent(in) :: self
        if (self%pending_stat /= regdae_success .and. .not. self%pending_recoverable) then
            stat = self%pending_stat
        else
            stat = regdae_err_integration
        end if
    end function backend_failure_status

    subroutine backend_free(self)
        class(ida_backend), intent(inout) :: self
        integer(c_int) :: ierr
        self%interpolated = .false.
        self%slope_pending = .false.
        if (c_associated(self%ida_mem)) then   ! the counters of a later IDA continue from these
            call self%get_statistics(self%carried)
            self%carried%jac_res_evals = 0
            self%carried%res_evals = self%carried%res_evals - self%jac_res_evals
            call FIDAFree(self%ida_mem)
        end if
        if (associated(self%ls)) ierr = FSUNLinSolFree(self%ls)
        if (associated(self%jmat)) call FSUNMatDestroy(self%jmat)
        if (associated(self%idv)) call FN_VDestroy(self%idv)
        if (associated(self%constraints)) call FN_VDestroy(self%constraints)
        if (associated(self%up)) call FN_VDestroy(self%up)
        if (associated(self%uu)) call FN_VDestroy(self%uu)
        if (c_associated(self%sunctx)) ierr = FSUNContext_Free(self%sunctx)
        self%ida_mem = c_null_ptr
        self%sunctx = c_null_ptr
        self%ls => null()
        self%jmat => null()
        self%idv => null()
        self%constraints => null()
        self%up => null()
        self%uu => null()
    end subroutine backend_free

    ! ---------------------------------------------------------------------
    ! The bind(C) callbacks: IDA's user_data is the backend.
    ! ---------------------------------------------------------------------

    integer(c_int) function ida_residual(t, nv_u, nv_up, nv_res, user_data) result(ierr) bind(C)
        real(c_double), value :: t
        type(N_Vector) :: nv_u, nv_up, nv_res
        type(c_ptr), value :: user_data
        type(ida_backend), pointer :: self
        real(c_double), pointer :: u(:), up(:), res(:)

        call c_f_pointer(user_data, self)
        u => FN_VGetArrayPointer(nv_u)
        up => FN_VGetArrayPointer(nv_up)
        res => FN_VGetArrayPointer(nv_res)
        ierr = evaluate_residual(self, t, u, up, res)
    end function ida_residual

    ! Dense Jacobian dF/du + cj dF/du' by forward differences, column j with the
    ! increment d_j = sqrt(u) max(|u_j|, 1): independent of IDA's error weights,
    ! so it is defined also when some weights are zero.
    integer(c_int) function ida_jacobian(t, cj, nv_u, nv_up, nv_res, jmat, user_data, tmp1, tmp2, tmp3) &
        result(ierr) bind(C)
        real(c_double), value :: t, cj
        type(N_Vector) :: nv_u, nv_up, nv_res
        type(SUNMatrix) :: jmat
        type(c_ptr), value :: user_data
        type(N_Vector) :: tmp1, tmp2, tmp3
        type(ida_backend), pointer :: self
        real(c_double), pointer :: u(:), up(:), res(:), jdata(:), jac(:, :)
        real(wp) :: delta, sqrt_unit
        integer :: j, neq, stat
        logical :: recoverable

        call c_f_pointer(user_data, self)
        neq = self%neq
        u => FN_VGetArrayPointer(nv_u)
        up => FN_VGetArrayPointer(nv_up)
        res => FN_VGetArrayPointer(nv_res)
        ! FSUNDenseMatrix_Data returns a rank-1 pointer of extent 1: rebuild the
        ! n x n view from its address.
        jdata => FSUNDenseMatrix_Data(jmat)
        call c_f_pointer(c_loc(jdata(1)), jac, [neq, neq])
        sqrt_unit = sqrt(epsilon(1.0_wp))
        self%u_pert = u(1:neq)
        self%up_pert = up(1:neq)
        ! the system may take the user's Jacobian of f at u for the perturbed residuals
        ierr = 0
        call self%system%jacobian_phase(t, u(1:neq), .true., stat, recoverable)
        if (stat /= regdae_success) then
            ierr = callback_failure(self, t, stat, recoverable)
            return
        end if
        do j = 1, neq
            delta = sqrt_unit*max(abs(u(j)), 1.0_wp)
            self%u_pert(j) = u(j) + delta
            delta = self%u_pert(j) - u(j)       ! the increment actually represented
            self%up_pert(j) = up(j) + cj*delta
            ierr = evaluate_residual(self, t, self%u_pert, self%up_pert, self%r_pert)
            self%jac_res_evals = self%jac_res_evals + 1
            if (ierr /= 0) exit
            jac(:, j) = (self%r_pert - res(1:neq))/delta
            self%u_pert(j) = u(j)
            self%up_pert(j) = up(j)
        end do
        call self%system%jacobian_phase(t, u(1:neq), .false., stat, recoverable)
    end function ida_jacobian

    ! The Jacobian dF/du + cj dF/du' of a structured system by grouped forward
    ! differences (the increments of `ida_jacobian`), into a dense, band or
    ! sparse (CSC) matrix.
    integer(c_int) function ida_jacobian_grouped(t, cj, nv_u, nv_up, nv_res, jmat, user_data, tmp1, tmp2, tmp3) &
        result(ierr) bind(C)
        real(c_double), value :: t, cj
        type(N_Vector) :: nv_u, nv_up, nv_res
        type(SUNMatrix) :: jmat
        type(c_ptr), value :: user_data
        type(N_Vector) :: tmp1, tmp2, tmp3
        type(ida_backend), pointer :: self
        real(c_double), pointer :: u(:), up(:), res(:), jdata(:), dense(:, :), band(:), sparse(:)
        integer(c_long_long), pointer :: col_ptr(:), row_idx(:)
        real(wp) :: sqrt_unit, d
        integer :: c, a, j, k, neq, ldim, smu

        call c_f_pointer(user_data, self)
        neq = self%neq
        u => FN_VGetArrayPointer(nv_u)
        up => FN_VGetArrayPointer(nv_up)
        res => FN_VGetArrayPointer(nv_res)
        ldim = 0
        smu = 0
        select case (self%linear_solver)
        case (linear_solver_band)
            jdata => FSUNBandMatrix_Data(jmat)
            ldim = int(FSUNBandMatrix_LDim(jmat))
            smu = int(FSUNBandMatrix_StoredUpperBandwidth(jmat))
            call c_f_pointer(c_loc(jdata(1)), band, [ldim*neq])
        case (linear_solver_sparse)
            ! SUNMatZero cleared the index arrays too: write the pattern every time.
            jdata => FSUNSparseMatrix_Data(jmat)
            call c_f_pointer(c_loc(jdata(1)), sparse, [size(self%csc_rows)])
            col_ptr => FSUNSparseMatrix_IndexPointers(jmat)
            row_idx => FSUNSparseMatrix_IndexValues(jmat)
            call c_f_pointer(c_loc(col_ptr(1)), col_ptr, [neq + 1])
            call c_f_pointer(c_loc(row_idx(1)), row_idx, [size(self%csc_rows)])
            col_ptr = int(self%csc_start - 1, c_long_long)
            row_idx = int(self%csc_rows - 1, c_long_long)
        case default
            jdata => FSUNDenseMatrix_Data(jmat)
            call c_f_pointer(c_loc(jdata(1)), dense, [neq, neq])
        end select
        sqrt_unit = sqrt(epsilon(1.0_wp))
        self%u_pert = u(1:neq)
        self%up_pert = up(1:neq)
        do c = 1, self%ngroups
            do a = self%group_start(c), self%group_start(c + 1) - 1
                j = self%group_cols(a)
                d = sqrt_unit*max(abs(u(j)), 1.0_wp)
                self%u_pert(j) = u(j) + d
                self%delta(j) = self%u_pert(j) - u(j)
                self%up_pert(j) = up(j) + cj*self%delta(j)
            end do
            ierr = evaluate_residual(self, t, self%u_pert, self%up_pert, self%r_pert)
            self%jac_res_evals = self%jac_res_evals + 1
            if (ierr /= 0) return
            do a = self%group_start(c), self%group_start(c + 1) - 1
                j = self%group_cols(a)
                self%u_pert(j) = u(j)
                self%up_pert(j) = up(j)
                do k = self%csc_start(j), self%csc_start(j + 1) - 1
                    associate (i => self%csc_rows(k))
                        select case (self%linear_solver)
                        case (linear_solver_band)
                            band((j - 1)*ldim + smu + i - j + 1) = (self%r_pert(i) - res(i))/self%delta(j)
                        case (linear_solver_sparse)
                            sparse(k) = (self%r_pert(i) - res(i))/self%delta(j)
                        case default
                            dense(i, j) = (self%r_pert(i) - res(i))/self%delta(j)
                        end select
                    end associate
                end do
            end do
        end do
        ierr = 0
    end function ida_jacobian_grouped

    !> The relative tolerance IDA gets for a user's rtol:
    !! $$ \tau = \mathrm{rtol}\,\min\bigl(1, (\mathrm{rtol}/10^{-3})^{1/q}\bigr), $$
    !! q = 5 IDA's largest order, and not below 100 u (nor above rtol). IDA keeps the
    !! local error of each step within tau; on a motion that does not damp its errors
    !! they add up over the N ~ tau^(-1/(q+1)) steps, and the global error grows like
    !! tau^(q/(q+1)) (measured on plain IDA on the slider crank's reduced ODE: slope
    !! 0.82 over rtol 1e-3 ... 1e-10, 36-833 times rtol). With this tau it grows like
    !! rtol (measured on regdae's slider crank: slope 1.01, 29-54 times rtol); at the
    !! same error the steps are those of IDA with tau = rtol.
    elemental real(wp) function ida_relative_tolerance(rtol) result(tau)
        real(wp), intent(in) :: rtol   !! the user's relative tolerance (> 0)
        tau = rtol
        if (rtol >= proportional_from .or. rtol <= smallest_ida_rtol) return
        tau = max(rtol*(rtol/proportional_from)**(1.0_wp/bdf_order), smallest_ida_rtol)
    end function ida_relative_tolerance

    ! Error weights 1/(rtol_ida |u_i| + atol_ida_i), times test_scale for the unknowns in the
    ! error test; for those left out (y, and v if asked) 0 (exclusion=weights), or (suppress:
    ! Newton's test only) with the algebraic ones' tolerances loosened to a relative algebraic_rtol.
    integer(c_int) function ida_error_weights(nv_u, nv_ewt, user_data) result(ierr) bind(C)
        type(N_Vector) :: nv_u, nv_ewt
        type(c_ptr), value :: user_data
        type(ida_backend), pointer :: self
        real(c_double), pointer :: u(:), ewt(:)
        integer :: i

        call c_f_pointer(user_data, self)
        u => FN_VGetArrayPointer(nv_u)
        ewt => FN_VGetArrayPointer(nv_ewt)
        do i = 1, self%neq
            ewt(i) = 1.0_wp/(self%rtol_ida*abs(u(i)) + self%atol_ida(i))
            if (self%excluded(i)) then
                if (self%opts%exclusion == exclusion_weights) then
                    ewt(i) = 0.0_wp
                else
                    ewt(i) = ewt(i)/self%algebraic_factor
                end if
            else
                ewt(i) = ewt(i)*self%test_scale
            end if
        end do
        ierr = 0
    end function ida_error_weights

    ! Keep IDA's last message in the backend instead of printing it.
    subroutine ida_error_handler(error_code, module_name, function_name, msg, user_data) bind(C)
        integer(c_int), value :: error_code
        type(c_ptr), value :: module_name, function_name, msg
        type(c_ptr), value :: user_data
        type(ida_backend), pointer :: self

        if (error_code == 0) return
        call c_f_pointer(user_data, self)
        self%ida_message = c_string(function_name)//': '//c_string(msg)
    end subroutine ida_error_handler

end module regdae_ida_backend
