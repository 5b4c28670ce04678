!> IDA on an ODE: the benchmark's BDF oracle (plain SUNDIALS IDA, BDF of variable order up to 5,
!! dense linear solver with IDA's own difference-quotient Jacobian) on \(y' = F(t, y)\) written as
!! the residual \(y' - F(t, y)\). On the slider crank's reduced ODE it shows how many steps BDF
!! takes on a smooth two-state problem, without any regularization (doc/performance.md).
module ida_ode_oracle
    use, intrinsic :: iso_c_binding
    use fida_mod
    use fsundials_context_mod
    use fsundials_nvector_mod
    use fnvector_serial_mod
    use fsundials_matrix_mod
    use fsunmatrix_dense_mod
    use fsundials_linearsolver_mod
    use fsunlinsol_dense_mod
    use regdae, only: wp
    use reference_ode, only: ode_system
    implicit none
    private

    public :: integrate_ida

    !> IDA's step limit per output interval.
    integer(c_long), parameter :: max_steps = 1000000_c_long

    !> The ODE, passed to the residual through IDA's user_data.
    type :: ode_link
        class(ode_system), pointer :: system => null()
        integer :: n = 0
    end type ode_link

contains

    !> Integrate \(y' = F(t, y)\) from (t0, y0), with the consistent \(y'(t_0) = F(t_0, y_0)\), and
    !! return the states at `times` (ascending, >= t0; interpolated by IDA, IDA_NORMAL) in
    !! `states(:, k)`. `steps`, `res_evals` (including the difference-quotient Jacobian's) and
    !! `jac_evals` are IDA's counters; `stat` is 0, IDA's negative flag, or IDA_MEM_FAIL if
    !! SUNDIALS could not allocate its objects (states after a failure: those of the last output
    !! reached, 0 beyond).
    subroutine integrate_ida(system, t0, y0, times, states, rtol, atol, steps, res_evals, jac_evals, stat)
        class(ode_system), intent(inout), target :: system
        real(wp), intent(in) :: t0, y0(:), times(:)
        real(wp), intent(out) :: states(:, :)
        real(wp), intent(in) :: rtol, atol
        integer, intent(out) :: steps, res_evals, jac_evals, stat
        type(ode_link), target :: link
        type(c_ptr) :: ctx, mem
        type(N_Vector), pointer :: uu, up
        type(SUNMatrix), pointer :: a
        type(SUNLinearSolver), pointer :: ls
        real(c_double), pointer :: u(:), p(:)
        real(c_double) :: tret(1)
        integer(c_long) :: counter(1), n
        integer(c_int) :: ierr
        integer :: k

        link%system => system
        link%n = size(y0)
        n = int(link%n, c_long)
        steps = 0
        res_evals = 0
        jac_evals = 0
        states = 0.0_wp
        ctx = c_null_ptr
        mem = c_null_ptr
        nullify (uu, up, a, ls)
        ierr = IDA_MEM_FAIL
        setup: block
            if (FSUNContext_Create(c_null_ptr, ctx) /= 0) exit setup
            uu => FN_VNew_Serial(n, ctx)
            up => FN_VNew_Serial(n, ctx)
            if (.not. (associated(uu) .and. associated(up))) exit setup
            u => FN_VGetArrayPointer(uu)
            p => FN_VGetArrayPointer(up)
            u = y0
            call system%rhs(t0, y0, p)
            a => FSUNDenseMatrix(n, n, ctx)
            if (.not. associated(a)) exit setup
            ls => FSUNLinSol_Dense(uu, a, ctx)
            if (.not. associated(ls)) exit setup
            mem = FIDACreate(ctx)
            if (.not. c_associated(mem)) exit setup
            ierr = FIDAInit(mem, c_funloc(ode_residual), t0, uu, up)
            if (ierr == 0) ierr = FIDASStolerances(mem, rtol, atol)
            if (ierr == 0) ierr = FIDASetUserData(mem, c_loc(link))
            if (ierr == 0) ierr = FIDASetMaxNumSteps(mem, max_steps)
            if (ierr == 0) ierr = FIDASetLinearSolver(mem, ls, a)
        end block setup
        do k = 1, size(times)
            if (ierr /= 0) exit
            if (times(k) > t0) then
                ierr = FIDASolve(mem, times(k), tret, uu, up, IDA_NORMAL)
                if (ierr > 0) ierr = 0
                if (ierr /= 0) exit
            end if
            states(:, k) = u
        end do
        stat = int(ierr)
        if (c_associated(mem)) then
            if (FIDAGetNumSteps(mem, counter) == 0) steps = int(counter(1))
            if (FIDAGetNumResEvals(mem, counter) == 0) res_evals = int(counter(1))
            if (FIDAGetNumLinResEvals(mem, counter) == 0) res_evals = res_evals + int(counter(1))
            if (FIDAGetNumJacEvals(mem, counter) == 0) jac_evals = int(counter(1))
            call FIDAFree(mem)
        end if
        if (associated(ls)) ierr = FSUNLinSolFree(ls)
        if (associated(a)) call FSUNMatDestroy(a)
        if (associated(up)) call FN_VDestroy(up)
        if (associated(uu)) call FN_VDestroy(uu)
        if (c_associated(ctx)) ierr = FSUNContext_Free(ctx)
    end subroutine integrate_ida

    ! The residual y' - F(t, y) (IDAResFn).
    integer(c_int) function ode_residual(t, nv_u, nv_up, nv_r, user_data) result(ierr) bind(C)
        real(c_double), value :: t
        type(N_Vector) :: nv_u, nv_up, nv_r
        type(c_ptr), value :: user_data
        type(ode_link), pointer :: link
        real(c_double), pointer :: u(:), up(:), r(:)
        call c_f_pointer(user_data, link)
        u => FN_VGetArrayPointer(nv_u)
        up => FN_VGetArrayPointer(nv_up)
        r => FN_VGetArrayPointer(nv_r)
        call link%system%rhs(t, u, r)
        r = up - r
        ierr = 0
    end function ode_residual

end module ida_ode_oracle
