!> Reference solutions of small ODEs with SUNDIALS CVODE (Adams-Moulton,
!! fixed-point iteration) at tight tolerances: the independent check the
!! drivers compare regdae's DAE solutions with.
module reference_ode
    use, intrinsic :: iso_c_binding
    use fcvode_mod
    use fsundials_context_mod
    use fsundials_nvector_mod
    use fnvector_serial_mod
    use fsundials_nonlinearsolver_mod
    use fsunnonlinsol_fixedpoint_mod
    use regdae, only: wp
    implicit none
    private

    !> An ODE y' = F(t, y) to integrate.
    type, abstract, public :: ode_system
    contains
        procedure(ode_rhs), deferred :: rhs
    end type ode_system

    abstract interface
        subroutine ode_rhs(self, t, y, ydot)
            import :: ode_system, wp
            class(ode_system), intent(inout) :: self
            real(wp), intent(in) :: t, y(:)
            real(wp), intent(out) :: ydot(:)
        end subroutine ode_rhs
    end interface

    type :: bridge
        class(ode_system), pointer :: system => null()
    end type bridge

    public :: integrate_reference

contains

    !> Integrate from (t0, y0) and return the states at `times` (ascending,
    !! >= t0) in `states(:, k)`. stat = 0, or CVODE's negative flag.
    subroutine integrate_reference(system, t0, y0, times, states, rtol, atol, stat)
        class(ode_system), intent(inout), target :: system
        real(wp), intent(in) :: t0, y0(:), times(:)
        real(wp), intent(out) :: states(:, :)
        real(wp), intent(in) :: rtol, atol
        integer, intent(out) :: stat
        type(bridge), target :: link
        type(c_ptr) :: ctx, mem
        type(N_Vector), pointer :: y
        type(SUNNonlinearSolver), pointer :: nls
        real(c_double), pointer :: yp(:)
        real(c_double) :: tret(1)
        integer(c_int) :: ierr
        integer :: k

        link%system => system
        ierr = FSUNContext_Create(c_null_ptr, ctx)
        y => FN_VNew_Serial(int(size(y0), c_long), ctx)
        yp => FN_VGetArrayPointer(y)
        yp = y0
        mem = FCVodeCreate(CV_ADAMS, ctx)
        ierr = FCVodeInit(mem, c_funloc(cvode_rhs), t0, y)
        if (ierr == 0) ierr = FCVodeSStolerances(mem, rtol, atol)
        if (ierr == 0) ierr = FCVodeSetUserData(mem, c_loc(link))
        if (ierr == 0) ierr = FCVodeSetMaxNumSteps(mem, 1000000_c_long)
        nls => FSUNNonlinSol_FixedPoint(y, 0, ctx)
        if (ierr == 0) ierr = FCVodeSetNonlinearSolver(mem, nls)
        do k = 1, size(times)
            if (ierr /= 0) exit
            if (times(k) > t0) then
                ierr = FCVode(mem, times(k), y, tret, CV_NORMAL)
                if (ierr > 0) ierr = 0
            end if
            states(:, k) = yp
        end do
        stat = int(ierr)
        call FCVodeFree(mem)
        ierr = FSUNNonlinSolFree(nls)
        call FN_VDestroy(y)
        ierr = FSUNContext_Free(ctx)
    end subroutine integrate_reference

    integer(c_int) function cvode_rhs(t, nv_y, nv_ydot, user_data) result(ierr) bind(C)
        real(c_double), value :: t
        type(N_Vector) :: nv_y, nv_ydot
        type(c_ptr), value :: user_data
        type(bridge), pointer :: link
        real(c_double), pointer :: y(:), ydot(:)
        call c_f_pointer(user_data, link)
        y => FN_VGetArrayPointer(nv_y)
        ydot => FN_VGetArrayPointer(nv_ydot)
        call link%system%rhs(t, y, ydot)
        ierr = 0
    end function cvode_rhs

end module reference_ode
