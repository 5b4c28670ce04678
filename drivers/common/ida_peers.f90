!> The peers of the benchmark: IDA on the unregularized formulations of the
!! slider crank a user would write without regdae, unknowns (q, v, lambda):
!!   q' = v,  M(q) v' = f(q, v) + G^T lambda, and
!!   index 1 (`peer_kkt`):      G v' + g_xx(v, v) = 0  (the acceleration constraint, KKT form);
!!   index 2 (`peer_index2`):   G v = 0               (the velocity constraint, lambda out of the error test).
!! IDA's own difference-quotient Jacobian, lambda algebraic and out of the error test
!! (FIDASetId + FIDASetSuppressAlg). Only for the benchmark.
module ida_peers
    use, intrinsic :: iso_c_binding
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use fida_mod
    use fsundials_context_mod
    use fsundials_nvector_mod
    use fnvector_serial_mod
    use fsundials_matrix_mod
    use fsunmatrix_dense_mod
    use fsundials_linearsolver_mod
    use fsunlinsol_dense_mod
    use regdae, only: wp
    use regdae_lapack, only: dgesv
    use slider_crank_problem, only: slider_crank, new_slider_crank
    implicit none
    private

    integer, parameter, public :: peer_kkt = 1, peer_index2 = 2

    type :: peer_data
        type(slider_crank) :: crank
        integer :: kind = peer_kkt
    end type peer_data

    public :: run_peer

contains

    !> Integrate the slider crank from th1 = th2 = pi/2 at rest to `times`; theta at
    !! each output in `theta(:, k)`. stat = 0, or IDA's negative flag (theta after the
    !! failure is NaN).
    subroutine run_peer(kind, rtol, times, theta, steps, res_evals, stat)
        integer, intent(in) :: kind
        real(wp), intent(in) :: rtol, times(:)
        real(wp), intent(out) :: theta(:, :)
        integer, intent(out) :: steps, res_evals, stat
        type(peer_data), target :: data
        type(c_ptr) :: ctx, mem
        type(N_Vector), pointer :: uu, up, idv
        type(SUNMatrix), pointer :: a
        type(SUNLinearSolver), pointer :: ls
        real(c_double), pointer :: u(:), p(:)
        real(c_double) :: tret(1)
        integer(c_long) :: k1(1)
        integer(c_int) :: ierr
        real(wp) :: pi, mass(2, 2), f(2), gx(1, 2), kkt(3, 3), rhs(3)
        integer :: k, ipiv(3), info, ustat

        pi = acos(-1.0_wp)
        data%crank = new_slider_crank(9.8_wp)
        data%kind = kind
        ierr = FSUNContext_Create(c_null_ptr, ctx)
        uu => FN_VNew_Serial(5_c_long, ctx)
        up => FN_VNew_Serial(5_c_long, ctx)
        idv => FN_VNew_Serial(5_c_long, ctx)
        u => FN_VGetArrayPointer(uu)
        p => FN_VGetArrayPointer(up)
        ! Consistent start at rest: [M -G^T; G 0] (v', lambda) = (f, 0).
        u = [pi/2, pi/2, 0.0_wp, 0.0_wp, 0.0_wp]
        ustat = 0
        call data%crank%mass_matrix(0.0_wp, u(1:2), mass, ustat)
        call data%crank%forces(0.0_wp, u(1:2), u(3:4), f, ustat)
        call data%crank%constraint_jacobian(0.0_wp, u(1:2), gx, ustat)
        kkt = 0.0_wp
        kkt(1:2, 1:2) = mass
        kkt(1:2, 3) = -gx(1, :)
        kkt(3, 1:2) = gx(1, :)
        rhs = [f, 0.0_wp]
        call dgesv(3, 1, kkt, 3, ipiv, rhs, 3, info)
        u(5) = rhs(3)
        p = [0.0_wp, 0.0_wp, rhs(1), rhs(2), 0.0_wp]
        p => FN_VGetArrayPointer(idv)
        p = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 0.0_wp]
        mem = FIDACreate(ctx)
        ierr = FIDAInit(mem, c_funloc(peer_residual), 0.0_wp, uu, up)
        if (ierr == 0) ierr = FIDASStolerances(mem, rtol, rtol)
        if (ierr == 0) ierr = FIDASetUserData(mem, c_loc(data))
        if (ierr == 0) ierr = FIDASetId(mem, idv)
        if (ierr == 0) ierr = FIDASetSuppressAlg(mem, 1_c_int)
        if (ierr == 0) ierr = FIDASetMaxNumSteps(mem, 100000_c_long)
        a => FSUNDenseMatrix(5_c_long, 5_c_long, ctx)
        ls => FSUNLinSol_Dense(uu, a, ctx)
        if (ierr == 0) ierr = FIDASetLinearSolver(mem, ls, a)
        ierr = FIDASetErrFile(mem, c_null_ptr)
        theta = ieee_value(1.0_wp, ieee_quiet_nan)
        stat = 0
        do k = 1, size(times)
            if (times(k) > 0.0_wp) then
                ierr = FIDASolve(mem, times(k), tret, uu, up, IDA_NORMAL)
                if (ierr < 0) then
                    stat = int(ierr)
                    exit
                end if
            end if
            theta(:, k) = u(1:2)
        end do
        ierr = FIDAGetNumSteps(mem, k1)
        steps = int(k1(1))
        ierr = FIDAGetNumResEvals(mem, k1)
        res_evals = int(k1(1))
        ierr = FIDAGetNumLinResEvals(mem, k1)
        res_evals = res_evals + int(k1(1))
        call FIDAFree(mem)
        ierr = FSUNLinSolFree(ls)
        call FSUNMatDestroy(a)
        call FN_VDestroy(idv)
        call FN_VDestroy(up)
        call FN_VDestroy(uu)
        ierr = FSUNContext_Free(ctx)
    end subroutine run_peer

    integer(c_int) function peer_residual(t, nv_u, nv_up, nv_r, user_data) result(ierr) bind(C)
        real(c_double), value :: t
        type(N_Vector) :: nv_u, nv_up, nv_r
        type(c_ptr), value :: user_data
        type(peer_data), pointer :: data
        real(c_double), pointer :: u(:), up(:), r(:)
        real(wp) :: mass(2, 2), f(2), gx(1, 2)
        integer :: ustat
        call c_f_pointer(user_data, data)
        u => FN_VGetArrayPointer(nv_u)
        up => FN_VGetArrayPointer(nv_up)
        r => FN_VGetArrayPointer(nv_r)
        ustat = 0
        call data%crank%mass_matrix(t, u(1:2), mass, ustat)
        call data%crank%forces(t, u(1:2), u(3:4), f, ustat)
        call data%crank%constraint_jacobian(t, u(1:2), gx, ustat)
        r(1:2) = up(1:2) - u(3:4)
        r(3:4) = matmul(mass, up(3:4)) - f - gx(1, :)*u(5)
        if (data%kind == peer_kkt) then
            r(5) = dot_product(gx(1, :), up(3:4)) + cos(u(1))*u(3)**2 + cos(u(2))*u(4)**2
        else
            r(5) = dot_product(gx(1, :), u(3:4))
        end if
        ierr = 0
    end function peer_residual

end module ida_peers
