!> The routines of a problem given to DREGDAE or DREGDAEM: FORTRAN 77 EXTERNAL
!! subroutines in the DASSL manner,
!!
!!     SUBROUTINE F(T, X, FX, IRES, RPAR, IPAR)          (F, B, G, GX, GT, MASS)
!!     SUBROUTINE FORCES(T, Q, V, FQ, IRES, RPAR, IPAR)
!!
!! with the caller's RPAR and IPAR passed through. IRES is 0 on entry; as in
!! DASSL, IRES = -1 asks for a smaller step (recoverable: `stat` 1) and any
!! other nonzero value stops the integration (`stat` = IRES, or -IRES if positive).
!! A failure is recorded in the caller's words ("G returned IRES = -2 at T = ..."),
!! the routine named as DREGDAE's argument list names it.
!!
!! DREGDAEJ and DREGDAEMJ (INFO(5) = 1) add JAC, the Jacobian of the user's f:
!!
!!     SUBROUTINE JAC(T, X, PD, IRES, RPAR, IPAR)        PD(N, N)  = df/dx
!!     SUBROUTINE JAC(T, Q, V, PD, IRES, RPAR, IPAR)     PD(N, 2N) = [df/dq, df/dq']
!!
!! used where IDA forms its dense Newton matrix by difference quotients: around
!! it (`linearize`) f at the perturbed points is f(x0) + PD (x - x0) instead of
!! a call of F (FORCES), and `check_jac` compares PD with central difference
!! quotients of F at the start (check_jacobians).
module regdae_f77_routines
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_f_pointer
    use regdae_kinds, only: wp
    use regdae_format, only: format_int, format_real
    use regdae_foreign_problems, only: foreign_routines, routine_f, routine_b, routine_g, routine_gx, routine_gt, &
                                       routine_mass, routine_forces, routine_name, n_routines
    use regdae_events, only: event_functions
    use regdae_status, only: regdae_success, regdae_err_user_callback
    use regdae_differences, only: central_difference_step
    use regdae_jacobian_check, only: compare_jacobian
    implicit none
    private

    ! A FORTRAN 77 routine declares no INTENT; these say what it may do with each argument.
    abstract interface
        !> A routine of (T, X): F (length N), B (N x M), G (M), GX (M x N), GT (M), MASS (N x N).
        subroutine f77_point_routine(t, x, val, ires, rpar, ipar)
            import :: wp
            real(wp), intent(in) :: t          !! time
            real(wp), intent(in) :: x(*)       !! position (state), length N
            real(wp), intent(out) :: val(*)    !! the value; matrices column by column
            integer, intent(inout) :: ires     !! 0 on entry; -1: retry with a smaller step; other: stop
            real(wp), intent(inout) :: rpar(*) !! the caller's RPAR
            integer, intent(inout) :: ipar(*)  !! the caller's IPAR
        end subroutine f77_point_routine

        !> A routine of (T, Q, V): FORCES (length N).
        subroutine f77_motion_routine(t, x, v, val, ires, rpar, ipar)
            import :: wp
            real(wp), intent(in) :: t
            real(wp), intent(in) :: x(*)       !! position, length N
            real(wp), intent(in) :: v(*)       !! velocity, length N
            real(wp), intent(out) :: val(*)
            integer, intent(inout) :: ires
            real(wp), intent(inout) :: rpar(*)
            integer, intent(inout) :: ipar(*)
        end subroutine f77_motion_routine

        !> RT of DREGDAER and DREGDAEMR (DDASKR's RT with V for YPRIME): the NRT event
        !! functions at (T, X, V) into RVAL; V is the velocity (DREGDAEMR) or X again
        !! (DREGDAER: e_i(t, x)).
        subroutine f77_root_routine(n, t, x, v, nrt, rval, rpar, ipar)
            import :: wp
            integer, intent(in) :: n           !! N
            real(wp), intent(in) :: t
            real(wp), intent(in) :: x(*)       !! position (state), length N
            real(wp), intent(in) :: v(*)       !! velocity, length N (DREGDAER: X)
            integer, intent(in) :: nrt         !! number of event functions
            real(wp), intent(out) :: rval(*)   !! their values, length NRT
            real(wp), intent(inout) :: rpar(*)
            integer, intent(inout) :: ipar(*)
        end subroutine f77_root_routine
    end interface

    !> The event functions of DREGDAER and DREGDAEMR: RT, with the RPAR and IPAR of
    !! the current call (from the problem's routines).
    type, extends(event_functions), public :: f77_events
        procedure(f77_root_routine), pointer, nopass :: rt => null()
        type(f77_routines), pointer :: routines => null()   !! the RPAR and IPAR of the call
    contains
        procedure :: values => f77_event_values
    end type f77_events

    !> The EXTERNAL routines of one DREGDAE or DREGDAEM problem and the RPAR and
    !! IPAR of the current call (addresses, set at every call).
    type, extends(foreign_routines), public :: f77_routines
        procedure(f77_point_routine), pointer, nopass :: f => null()       !! DREGDAE: F
        procedure(f77_point_routine), pointer, nopass :: b => null()       !! DREGDAE: B
        procedure(f77_point_routine), pointer, nopass :: g => null()       !! G
        procedure(f77_point_routine), pointer, nopass :: gx => null()      !! GX
        procedure(f77_point_routine), pointer, nopass :: gt => null()      !! GT, used when gt_supplied
        procedure(f77_point_routine), pointer, nopass :: mass => null()    !! DREGDAEM: MASS
        procedure(f77_motion_routine), pointer, nopass :: forces => null() !! DREGDAEM: FORCES
        procedure(f77_point_routine), pointer, nopass :: jac => null()     !! DREGDAEJ: JAC, df/dx (N x N)
        procedure(f77_motion_routine), pointer, nopass :: jac_forces => null() !! DREGDAEMJ: JAC, [df/dq, df/dq']
        logical :: gt_supplied = .false.                                   !! INFO(17) = 1
        !> Between `linearize` on and off: F (FORCES) at t_lin is f_lin + pd_lin (x - x_lin)
        !! (+ the q' part), from one call of F and one of JAC at (t_lin, x_lin, v_lin).
        logical :: linearized = .false.
        real(wp) :: t_lin = 0.0_wp
        real(wp), allocatable :: x_lin(:), v_lin(:), f_lin(:), pd_lin(:, :)
        type(c_ptr) :: rpar = c_null_ptr                                   !! RPAR(1) of the current call
        type(c_ptr) :: ipar = c_null_ptr                                   !! IPAR(1) of the current call
        !> The last failure in DASSL's words without the time, e.g. `G returned IRES = -2`
        !! (`failure` adds `at T = ...`); unallocated: none since `forget_failure`.
        character(len=:), allocatable :: said
    contains
        procedure :: has => f77_has
        procedure :: evaluate => f77_evaluate
        !> Around IDA's difference-quotient Jacobian: with JAC in use, keep f and PD at the point
        !! (on) and answer the perturbed evaluations by f + PD (x - x0) until off.
        procedure :: linearize => f77_linearize
        !> Whether JAC was given (DREGDAEJ, DREGDAEMJ with INFO(5) = 1).
        procedure :: has_jac => f77_has_jac
        !> check_jacobians: PD of JAC against central difference quotients of F
        !! (FORCES) at (t, x[, v]); regdae_err_jacobian names the worst entry (i, j) of PD.
        procedure :: check_jac => f77_check_jac
        !> Forget the last failure (`said`, `failure`): done after each call's message.
        procedure :: forget_failure => f77_forget_failure
    end type f77_routines

    public :: f77_point_routine, f77_motion_routine, f77_root_routine

    ! JAC among the routine codes (messages and `evaluate`): of F (DREGDAEJ), of FORCES (DREGDAEMJ).
    integer, parameter :: routine_jac = n_routines + 1, routine_jac_forces = n_routines + 2

contains

    logical function f77_has(self, which)
        class(f77_routines), intent(in) :: self
        integer, intent(in) :: which
        select case (which)
        case (routine_f); f77_has = associated(self%f)
        case (routine_b); f77_has = associated(self%b)
        case (routine_g); f77_has = associated(self%g)
        case (routine_gx); f77_has = associated(self%gx)
        case (routine_gt); f77_has = self%gt_supplied .and. associated(self%gt)
        case (routine_mass); f77_has = associated(self%mass)
        case (routine_forces); f77_has = associated(self%forces)
        case default; f77_has = .false.
        end select
    end function f77_has

    subroutine f77_evaluate(self, which, t, x, val, stat, v)
        class(f77_routines), intent(inout) :: self
        integer, intent(in) :: which
        real(wp), intent(in) :: t
        real(wp), intent(in) :: x(*)
        real(wp), intent(out) :: val(*)
        integer, intent(inout) :: stat
        real(wp), intent(in), optional :: v(*)
        real(wp), pointer, contiguous :: rpar(:)
        integer, pointer, contiguous :: ipar(:)
        procedure(f77_point_routine), pointer :: point
        procedure(f77_motion_routine), pointer :: motion
        integer :: ires

        ! The caller's arrays (their length is unknown: element 1 stands for them; the
        ! routine receives their address, as from DASSL)
        call c_f_pointer(self%rpar, rpar, [1])
        call c_f_pointer(self%ipar, ipar, [1])
        if (self%linearized .and. t == self%t_lin .and. (which == routine_f .or. which == routine_forces)) then
            call linearized_value(self, x, val, v)
            return
        end if
        ires = 0
        select case (which)
        case (routine_forces, routine_jac_forces)
            motion => self%forces
            if (which == routine_jac_forces) motion => self%jac_forces
            call motion(t, x, v, val, ires, rpar, ipar)
        case default
            select case (which)
            case (routine_f); point => self%f
            case (routine_b); point => self%b
            case (routine_g); point => self%g
            case (routine_gx); point => self%gx
            case (routine_gt); point => self%gt
            case (routine_jac); point => self%jac
            case default; point => self%mass
            end select
            call point(t, x, val, ires, rpar, ipar)
        end select
        if (ires == 0) return
        stat = merge(1, -abs(ires), ires == -1)
        self%said = trim(f77_routine_name(which))//' returned IRES = '//format_int(ires)
        self%failure = self%said//' at T = '//format_real(t)
    end subroutine f77_evaluate

    ! f_lin + PD (x - x_lin) [+ PD(:, N+1:2N) (v - v_lin)]: F or FORCES near the point of `linearize`.
    subroutine linearized_value(self, x, val, v)
        class(f77_routines), intent(in) :: self
        real(wp), intent(in) :: x(*)
        real(wp), intent(out) :: val(*)
        real(wp), intent(in), optional :: v(*)
        integer :: n, j
        n = size(self%x_lin)
        val(1:n) = self%f_lin
        do j = 1, n
            val(1:n) = val(1:n) + self%pd_lin(:, j)*(x(j) - self%x_lin(j))
            if (present(v)) val(1:n) = val(1:n) + self%pd_lin(:, n + j)*(v(j) - self%v_lin(j))
        end do
    end subroutine linearized_value

    logical function f77_has_jac(self)
        class(f77_routines), intent(in) :: self
        f77_has_jac = associated(self%jac) .or. associated(self%jac_forces)
    end function f77_has_jac

    ! On: F (FORCES) and JAC at (t, x[, v]), kept for `evaluate` until off. Nothing
    ! without JAC.
    subroutine f77_linearize(self, which, t, x, on, stat, v)
        class(f77_routines), intent(inout) :: self
        integer, intent(in) :: which
        real(wp), intent(in) :: t, x(:)
        logical, intent(in) :: on
        integer, intent(inout) :: stat
        real(wp), intent(in), optional :: v(:)
        integer :: n
        self%linearized = .false.
        if (.not. on .or. .not. self%has_jac()) return
        n = size(x)
        self%t_lin = t
        self%x_lin = x
        if (.not. allocated(self%f_lin)) allocate (self%f_lin(n), self%pd_lin(n, merge(2*n, n, which == routine_forces)))
        if (which == routine_forces) then
            self%v_lin = v
            call self%evaluate(routine_forces, t, x, self%f_lin, stat, v)
            if (stat == 0) call self%evaluate(routine_jac_forces, t, x, self%pd_lin, stat, v)
        else
            call self%evaluate(routine_f, t, x, self%f_lin, stat)
            if (stat == 0) call self%evaluate(routine_jac, t, x, self%pd_lin, stat)
        end if
        self%linearized = (stat == 0)
    end subroutine f77_linearize

    subroutine f77_check_jac(self, t, x, stat, msg, v)
        class(f77_routines), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), intent(in), optional :: v(:)          !! DREGDAEMJ: the velocity
        real(wp), allocatable :: pd(:, :), dq(:, :), xp(:), vp(:), fp(:), fm(:)
        integer :: n, j, k
        real(wp) :: d
        character(len=:), allocatable :: of
        n = size(x)
        stat = 0
        xp = x
        allocate (fp(n), fm(n))
        if (present(v)) then
            vp = v
            allocate (pd(n, 2*n), dq(n, 2*n))
            call self%evaluate(routine_jac_forces, t, x, pd, stat, v)
            of = 'FORCES'
        else
            allocate (pd(n, n), dq(n, n))
            call self%evaluate(routine_jac, t, x, pd, stat)
            of = 'F'
        end if
        ! column j: x_j (j <= N), q'_(j-N) (DREGDAEMJ, j > N)
        do j = 1, size(pd, 2)
            k = j - n
            if (stat /= 0) exit
            if (j <= n) then
                d = central_difference_step(x(j))
                xp(j) = x(j) + d
            else
                d = central_difference_step(v(k))
                vp(k) = v(k) + d
            end if
            call forward(fp)
            if (j <= n) xp(j) = x(j) - d
            if (j > n) vp(k) = v(k) - d
            if (stat == 0) call forward(fm)
            if (j <= n) xp(j) = x(j)
            if (j > n) vp(k) = v(k)
            dq(:, j) = (fp - fm)/(2.0_wp*d)
        end do
        if (stat /= 0) then
            stat = regdae_err_user_callback
            msg = 'check_jacobians: '//self%failure
            return
        end if
        call compare_jacobian('JAC', pd, dq, stat, msg, of)
    contains
        subroutine forward(val)
            real(wp), intent(out) :: val(:)
            if (present(v)) then
                call self%evaluate(routine_forces, t, xp, val, stat, vp)
            else
                call self%evaluate(routine_f, t, xp, val, stat)
            end if
        end subroutine forward
    end subroutine f77_check_jac

    subroutine f77_forget_failure(self)
        class(f77_routines), intent(inout) :: self
        if (allocated(self%said)) deallocate (self%said)
        if (allocated(self%failure)) deallocate (self%failure)
    end subroutine f77_forget_failure

    ! The name of a routine as DREGDAE's argument list has it: F, B, G, GX, GT, MASS, FORCES
    ! (padded with blanks).
    pure function f77_routine_name(which) result(name)
        integer, intent(in) :: which
        character(len=len(routine_name(1))) :: name
        integer :: k
        if (which > n_routines) then
            name = 'JAC'
            return
        end if
        name = routine_name(which)
        do k = 1, len(name)
            if (name(k:k) >= 'a' .and. name(k:k) <= 'z') name(k:k) = achar(iachar(name(k:k)) - 32)
        end do
    end function f77_routine_name

    subroutine f77_event_values(self, t, x, v, e, stat)
        class(f77_events), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        real(wp), pointer, contiguous :: rpar(:)
        integer, pointer, contiguous :: ipar(:)
        call c_f_pointer(self%routines%rpar, rpar, [1])
        call c_f_pointer(self%routines%ipar, ipar, [1])
        if (size(v) > 0) then
            call self%rt(size(x), t, x, v, size(e), e, rpar, ipar)
        else
            call self%rt(size(x), t, x, x, size(e), e, rpar, ipar)
        end if
        stat = 0
    end subroutine f77_event_values

end module regdae_f77_routines
