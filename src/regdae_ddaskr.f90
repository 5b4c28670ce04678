!> The DDASKR door: what the external subroutines DREGDASKR, DREGDASKRMSG and
!! DREGDASKRFREE of `dregdaskr.f90` do. DREGDASKR takes DDASKR's argument list
!! (Brown, Hindmarsh, Petzold; RES, JAC, RT, NRT, JROOT) and integrates the general
!! DAE F(t, y, y') = 0 of RES by IDA through `regdae_residual_solver`: no
!! regularization (a mechanism through singular configurations needs DREGDAE or
!! DREGDAEM). doc/api.md, "FORTRAN 77 interface for plain DAEs (DREGDASKR)", has the
!! INFO table, the IWORK / RWORK map and the IDID codes.
!!
!! Reentrant without SAVE, COMMON or module variables: INFO(1) = 0 allocates a
!! session (the solver, the last message) whose address IWORK(39...) keeps, with a
!! mark in IWORK(37) and a check word in IWORK(38) (DDASKR's private words); INFO(1)
!! = 0 on an IWORK that holds a session frees it first. A refused start allocates
!! nothing (the input is checked first); its reason's code goes to IWORK(10), which
!! DREGDASKRMSG reads when IWORK holds no session.
module regdae_ddaskr
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_loc, c_f_pointer
    use regdae_iwork_address, only: address_words, put_address, get_address
    use, intrinsic :: iso_fortran_env, only: error_unit, int64
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_root_found, regdae_err_inconsistent_ic, regdae_err_user_callback, &
                             regdae_err_bad_input
    use regdae_format, only: format_int, format_real
    use regdae_residual_problem, only: residual_problem
    use regdae_residual_options, only: residual_options, initial_given
    use regdae_residual_solver, only: residual_solver, residual_stats, reached_tout, reached_step, reached_tstop, &
                                      reached_root
    use regdae_ddaskr_input, only: info_length, info_start, info_vector_tol, info_intermediate, info_tstop, info_jac, &
                                   info_ic_only, info_messages, rwork_tstop, min_liw, min_lrw, iwork_mark, &
                                   iwork_check, iwork_address, iwork_refusal, refused_no_solver, refused_after_failure, &
                                   refused_info1, refused_start, check_call, options_from, tolerances, needed_liw
    use fida_mod, only: IDA_TOO_MUCH_WORK, IDA_TOO_MUCH_ACC, IDA_ERR_FAIL, IDA_CONV_FAIL, IDA_LSETUP_FAIL, &
                        IDA_LSOLVE_FAIL, IDA_RES_FAIL, IDA_REP_RES_ERR, IDA_FIRST_RES_FAIL, IDA_CONSTR_FAIL, &
                        IDA_ILL_INPUT, IDA_RTFUNC_FAIL
    implicit none
    private

    public :: ddaskr_call, ddaskr_message, ddaskr_free

    !> RES(T, Y, YPRIME, CJ, DELTA, IRES, RPAR, IPAR): DELTA = F(T, Y, YPRIME); IRES = 0
    !! on entry, -1: Y illegal (IDA tries a smaller step), -2 (or any other nonzero): stop.
    abstract interface
        subroutine ddaskr_res(t, y, yprime, cj, delta, ires, rpar, ipar)
            import :: wp
            real(wp), intent(in) :: t, y(*), yprime(*), cj
            real(wp), intent(out) :: delta(*)
            integer, intent(inout) :: ires
            real(wp), intent(inout) :: rpar(*)
            integer, intent(inout) :: ipar(*)
        end subroutine ddaskr_res
        !> JAC(T, Y, YPRIME, PD, CJ, RPAR, IPAR): PD = dF/dY + CJ dF/dYPRIME (dense PD(NEQ, NEQ)
        !! or band PD(2 ML + MU + 1, NEQ) with (i, j) in row i - j + ML + MU + 1); PD is 0 on entry.
        subroutine ddaskr_jac(t, y, yprime, pd, cj, rpar, ipar)
            import :: wp
            real(wp), intent(in) :: t, y(*), yprime(*), cj
            real(wp), intent(inout) :: pd(*)
            real(wp), intent(inout) :: rpar(*)
            integer, intent(inout) :: ipar(*)
        end subroutine ddaskr_jac
        !> RT(NEQ, T, Y, YP, NRT, RVAL, RPAR, IPAR): RVAL(1:NRT) the event functions.
        subroutine ddaskr_rt(neq, t, y, yp, nrt, rval, rpar, ipar)
            import :: wp
            integer, intent(in) :: neq, nrt
            real(wp), intent(in) :: t, y(*), yp(*)
            real(wp), intent(out) :: rval(*)
            real(wp), intent(inout) :: rpar(*)
            integer, intent(inout) :: ipar(*)
        end subroutine ddaskr_rt
    end interface

    ! The user's routines as a residual_problem.
    type, extends(residual_problem) :: ddaskr_problem
        procedure(ddaskr_res), pointer, nopass :: res => null()
        procedure(ddaskr_jac), pointer, nopass :: jac => null()
        procedure(ddaskr_rt), pointer, nopass :: rt => null()
        logical :: with_jac = .false.
        type(c_ptr) :: rpar = c_null_ptr, ipar = c_null_ptr   ! RPAR(1), IPAR(1) of the current call
    contains
        procedure :: residual => problem_residual
        procedure :: has_jacobian => problem_has_jacobian
        procedure :: jacobian => problem_jacobian
        procedure :: roots => problem_roots
    end type ddaskr_problem

    ! One problem's state, behind IWORK.
    type :: ddaskr_session
        type(residual_solver) :: solver
        integer :: neq = 0, nrt = 0
        character(len=:), allocatable :: message
    end type ddaskr_session

    ! DDASKR's IDID values.
    integer, parameter :: idid_step = 1, idid_tstop = 2, idid_tout = 3, idid_initial = 4, idid_root = 5, &
                          idid_work = -1, idid_accuracy = -2, idid_weight = -3, idid_error_test = -6, &
                          idid_convergence = -7, idid_singular = -8, idid_both = -9, idid_ires1 = -10, &
                          idid_ires2 = -11, idid_ic = -12, idid_bad_input = -33

    ! IWORK's and RWORK's outputs (DDASKR's places).
    integer, parameter :: iwork_order_next = 7, iwork_order_last = 8, iwork_steps = 11, iwork_res_evals = 12, &
                          iwork_jac_evals = 13, iwork_err_test_fails = 14, iwork_conv_fails = 15, &
                          iwork_lin_fails = 16, iwork_leniw = 17, iwork_lenrw = 18, iwork_nonlin_iters = 19, &
                          iwork_lin_iters = 20, iwork_psol = 21, iwork_root_evals = 36
    integer, parameter :: rwork_h_next = 3, rwork_tn = 4, rwork_h_last = 7

    integer, parameter :: session_mark = 2002815   ! IWORK(37) of an IWORK that holds a session

contains

    !> DREGDASKR: F(t, y, y') = 0 from T to TOUT (one call of DDASKR's).
    subroutine ddaskr_call(res, neq, t, y, yprime, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, rpar, ipar, &
                           jac, rt, nrt, jroot)
        procedure(ddaskr_res) :: res
        integer, intent(in) :: neq
        real(wp), intent(inout) :: t
        real(wp), intent(inout) :: y(neq), yprime(neq)
        real(wp), intent(in) :: tout
        integer, intent(inout) :: info(info_length)
        real(wp), intent(in) :: rtol(*), atol(*)
        integer, intent(out) :: idid
        integer, intent(in) :: lrw, liw
        real(wp), intent(inout) :: rwork(lrw)
        integer, intent(inout) :: iwork(liw)
        real(wp), intent(inout), target :: rpar(*)
        integer, intent(inout), target :: ipar(*)
        procedure(ddaskr_jac) :: jac
        procedure(ddaskr_rt) :: rt
        integer, intent(in) :: nrt
        integer, intent(out) :: jroot(*)
        type(ddaskr_session), pointer :: s
        type(residual_options) :: opts
        type(ddaskr_problem) :: problem
        integer :: stat, how
        real(wp) :: rtol_v(max(neq, 0)), atol_v(max(neq, 0))

        if (.not. open_call(neq, nrt, t, tout, info, rtol, atol, rwork, lrw, iwork, liw, idid, s, opts)) return
        if (info(info_start) == 0) then
            problem%neq = neq
            problem%nroots = nrt
            problem%with_jac = (info(info_jac) == 1)
            call s%solver%init(problem, t, y, yprime, opts, stat)
            if (stat /= regdae_success) then
                call close_call(s, stat, 0, t, info, rwork, iwork, idid, jroot)
                call s%solver%free()
                return
            end if
            call s%solver%name_routines('RES', 'JAC', 'RT')
        end if
        call attach(s, res, jac, rt, rpar, ipar)
        call tolerances(info, rtol, atol, neq, rtol_v, atol_v)
        call s%solver%set_tolerances(rtol_v, atol_v)
        if (info(info_start) == 0 .and. info(info_ic_only) == 1 .and. opts%initial /= initial_given) then
            call s%solver%initial_values(tout, y, yprime, stat)
            how = 0
            if (stat == regdae_success) how = -1   ! IDID = 4: the next call starts afresh
        else if (info(info_tstop) == 1) then
            call s%solver%advance(tout, t, y, yprime, stat, one_step=(info(info_intermediate) == 1), &
                                  tstop=rwork(rwork_tstop), reached=how)
        else
            call s%solver%advance(tout, t, y, yprime, stat, one_step=(info(info_intermediate) == 1), reached=how)
        end if
        call close_call(s, stat, how, t, info, rwork, iwork, idid, jroot)
    end subroutine ddaskr_call

    !> DREGDASKRMSG: the message of the last call on IWORK ('' after success).
    subroutine ddaskr_message(iwork, liw, msg)
        integer, intent(in) :: liw
        integer, intent(in) :: iwork(liw)
        character(len=*), intent(out) :: msg
        type(ddaskr_session), pointer :: s
        character(len=:), allocatable :: text
        if (liw < min_liw) then
            msg = 'DREGDASKRMSG: an IWORK of LIW = '//format_int(liw)//' holds no solver (LIW >= '// &
                  format_int(min_liw)//' is needed)'
        else if (iwork(iwork_refusal) >= refused_no_solver .and. iwork(iwork_refusal) <= refused_start) then
            call refusal_text(iwork(iwork_refusal), text)
            msg = text
        else if (session_in(iwork, liw, s)) then
            msg = s%message
        else
            msg = 'DREGDASKRMSG: IWORK holds no solver (no call with INFO(1) = 0 yet, or DREGDASKRFREE since)'
        end if
    end subroutine ddaskr_message

    !> DREGDASKRFREE: free the solver of IWORK (nothing if it holds none).
    subroutine ddaskr_free(iwork, liw)
        integer, intent(in) :: liw
        integer, intent(inout) :: iwork(liw)
        type(ddaskr_session), pointer :: s
        if (.not. session_in(iwork, liw, s)) return
        call s%solver%free()
        deallocate (s)
        iwork(iwork_mark) = 0
        iwork(iwork_check) = 0
    end subroutine ddaskr_free

    ! --- the steps of a call ------------------------------------------------------------

    ! The checks of a call and the session of IWORK (a new one at INFO(1) = 0, after
    ! the old one is freed; none when the start is refused). False: IDID = -33, the
    ! message kept (in the session, or its code in IWORK(10)) and printed.
    logical function open_call(neq, nrt, t, tout, info, rtol, atol, rwork, lrw, iwork, liw, idid, s, opts) result(ok)
        integer, intent(in) :: neq, nrt, lrw, liw
        real(wp), intent(in) :: t, tout
        integer, intent(inout) :: info(info_length)
        real(wp), intent(in) :: rtol(*), atol(*)
        real(wp), intent(in) :: rwork(lrw)
        integer, intent(inout) :: iwork(liw)
        integer, intent(out) :: idid
        type(ddaskr_session), pointer, intent(out) :: s
        type(residual_options), intent(out) :: opts
        character(len=:), allocatable :: msg
        integer :: refusal
        ok = .false.
        idid = idid_bad_input
        s => null()
        msg = ''
        refusal = 0
        if (liw < min_liw) then
            msg = 'LIW = '//format_int(liw)//' is too small: IWORK needs LIW >= '//format_int(min_liw)
        else if (info(info_start) == 0) then
            call check_call(neq, t, tout, info, rwork, lrw, msg)
            if (len(msg) == 0 .and. nrt < 0) msg = 'NRT = '//format_int(nrt)//' must be >= 0'
            if (len(msg) == 0 .and. liw < needed_liw(info, neq)) &
                msg = 'LIW = '//format_int(liw)//' is too small for these INFO(10), (11), (16): IWORK needs LIW >= '// &
                      format_int(needed_liw(info, neq))
            if (len(msg) == 0) call options_from(neq, info, rtol, atol, rwork, iwork, opts, msg)
            call ddaskr_free(iwork, liw)
            if (len(msg) == 0) then
                call new_session(iwork, liw, s)
                s%neq = neq
                s%nrt = nrt
            else
                refusal = refused_start   ! its own text is printed; DREGDASKRMSG gives its gist
            end if
        else if (session_in(iwork, liw, s)) then
            if (info(info_start) == 1) then
                if (s%neq /= neq .or. s%nrt /= nrt) msg = 'INFO(1) = 1 but IWORK holds another problem (NEQ = '// &
                    format_int(s%neq)//', NRT = '//format_int(s%nrt)//')'
                if (len(msg) == 0) call check_call(neq, t, tout, info, rwork, lrw, msg)
            else if (info(info_start) == -1) then
                call refusal_text(refused_after_failure, msg)
            else
                call refusal_text(refused_info1, msg)
                msg = msg//' (INFO(1) = '//format_int(info(info_start))//')'
            end if
        else
            refusal = refused_info1
            if (info(info_start) == 1) refusal = refused_no_solver
            if (info(info_start) == -1) refusal = refused_after_failure
            call refusal_text(refusal, msg)
        end if
        ok = (len(msg) == 0)
        if (liw >= min_liw) iwork(iwork_refusal) = 0
        if (ok) return
        if (associated(s)) then
            s%message = msg
        else if (liw >= min_liw) then
            iwork(iwork_refusal) = refusal   ! no session: the reason's code, for DREGDASKRMSG
        end if
        info(info_start) = -1
        call report(info, msg)
    end function open_call

    ! The user's routines and this call's RPAR, IPAR into the solver's problem.
    subroutine attach(s, res, jac, rt, rpar, ipar)
        type(ddaskr_session), intent(inout) :: s
        procedure(ddaskr_res) :: res
        procedure(ddaskr_jac) :: jac
        procedure(ddaskr_rt) :: rt
        real(wp), intent(inout), target :: rpar(*)
        integer, intent(inout), target :: ipar(*)
        class(residual_problem), pointer :: p
        p => s%solver%problem()
        select type (p)
        type is (ddaskr_problem)
            p%res => res
            p%jac => jac
            p%rt => rt
            p%rpar = c_loc(rpar(1))
            p%ipar = c_loc(ipar(1))
        end select
    end subroutine attach

    ! After the solver's call: T, the counters, IDID, INFO(1), JROOT and the message.
    ! how: the solver's `reached`, -1 after the initial values alone (INFO(14) = 1).
    subroutine close_call(s, stat, how, t, info, rwork, iwork, idid, jroot)
        type(ddaskr_session), intent(inout) :: s
        integer, intent(in) :: stat, how
        real(wp), intent(inout) :: t
        integer, intent(inout) :: info(info_length)
        real(wp), intent(inout) :: rwork(:)
        integer, intent(inout) :: iwork(:)
        integer, intent(out) :: idid
        integer, intent(out) :: jroot(*)
        type(residual_stats) :: st
        st = s%solver%statistics()
        iwork(iwork_order_next) = st%order_next
        iwork(iwork_order_last) = st%order_last
        iwork(iwork_steps) = counter(st%steps)
        iwork(iwork_res_evals) = counter(st%res_evals)
        iwork(iwork_jac_evals) = counter(st%jac_evals)
        iwork(iwork_err_test_fails) = counter(st%err_test_fails)
        iwork(iwork_conv_fails) = counter(st%conv_fails)
        iwork(iwork_nonlin_iters) = counter(st%nonlin_iters)
        iwork(iwork_lin_fails) = 0
        iwork(iwork_lin_iters) = 0
        iwork(iwork_psol) = 0
        iwork(iwork_root_evals) = counter(st%root_evals)
        iwork(iwork_leniw) = needed_liw(info, s%neq)
        iwork(iwork_lenrw) = min_lrw
        rwork(rwork_h_next) = st%h_next
        rwork(rwork_tn) = st%t_reached
        rwork(rwork_h_last) = st%h_last
        s%message = s%solver%message()
        if (stat == regdae_success .or. stat == regdae_root_found) then
            select case (how)
            case (reached_step)
                idid = idid_step
            case (reached_tstop)
                idid = idid_tstop
            case (reached_root)
                idid = idid_root
                jroot(1:s%nrt) = s%solver%roots()
            case (reached_tout)
                idid = idid_tout
            case default
                idid = idid_initial
            end select
            if (idid /= idid_initial) info(info_start) = 1
            return
        end if
        idid = failure_idid(stat, s%solver%ida_flag(), s%message)
        info(info_start) = -1
        s%message = 'IDID = '//format_int(idid)//': '//s%message
        call report(info, s%message)
    end subroutine close_call

    ! DDASKR's IDID of a failure, from the solver's status and IDA's flag.
    integer function failure_idid(stat, flag, message) result(idid)
        integer, intent(in) :: stat, flag
        character(len=*), intent(in) :: message
        if (stat == regdae_err_user_callback) then
            idid = idid_ires2
            return
        end if
        if (stat == regdae_err_inconsistent_ic) then
            idid = idid_ic
            return
        end if
        if (stat == regdae_err_bad_input) then
            idid = idid_bad_input   ! IDA refused the input (init, or IDASolve's first checks)
            return
        end if
        select case (flag)
        case (IDA_TOO_MUCH_WORK)
            idid = idid_work
        case (IDA_TOO_MUCH_ACC)
            idid = idid_accuracy
        case (IDA_ERR_FAIL)
            idid = idid_error_test
        case (IDA_CONV_FAIL)
            idid = idid_convergence
        case (IDA_LSETUP_FAIL, IDA_LSOLVE_FAIL)
            idid = idid_singular
        case (IDA_CONSTR_FAIL)
            idid = idid_both
        case (IDA_REP_RES_ERR, IDA_FIRST_RES_FAIL)
            idid = idid_ires1
        case (IDA_RES_FAIL, IDA_RTFUNC_FAIL)
            idid = idid_ires2
        case (IDA_ILL_INPUT)
            idid = idid_bad_input
            if (index(message, 'error weight') > 0) idid = idid_weight
        case default
            idid = idid_convergence
        end select
    end function failure_idid

    ! The text of a refusal whose code IWORK(10) keeps.
    pure subroutine refusal_text(reason, text)
        integer, intent(in) :: reason
        character(len=:), allocatable, intent(out) :: text
        select case (reason)
        case (refused_no_solver)
            text = 'INFO(1) = 1 but IWORK holds no solver: start a problem with INFO(1) = 0 (IWORK must not '// &
                   'change between the calls of a problem)'
        case (refused_after_failure)
            text = 'INFO(1) = -1: the last call failed; set INFO(1) = 1 to try to continue, or 0 to restart'
        case (refused_info1)
            text = 'INFO(1) must be 0 (start) or 1 (continue)'
        case default
            text = 'the last start (INFO(1) = 0) was refused: its input was invalid (the message was printed '// &
                   'on the unit of INFO(20)); nothing was allocated'
        end select
    end subroutine refusal_text

    ! Print a message on the unit of INFO(20) (0: the error unit; -1: none).
    subroutine report(info, msg)
        integer, intent(in) :: info(info_length)
        character(len=*), intent(in) :: msg
        if (info(info_messages) == 0) then
            write (error_unit, '(a)') 'DREGDASKR-- '//msg
        else if (info(info_messages) > 0) then
            write (info(info_messages), '(a)') 'DREGDASKR-- '//msg
        end if
    end subroutine report

    pure integer function counter(k)
        integer(int64), intent(in) :: k
        counter = int(min(k, int(huge(0), int64)))
    end function counter

    ! --- the user's routines as a residual_problem ------------------------------------

    subroutine problem_residual(self, t, y, yp, r, stat)
        class(ddaskr_problem), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:)
        real(wp), intent(out) :: r(:)
        integer, intent(inout) :: stat
        real(wp), pointer, contiguous :: rpar(:)
        integer, pointer, contiguous :: ipar(:)
        integer :: ires
        call c_f_pointer(self%rpar, rpar, [1])
        call c_f_pointer(self%ipar, ipar, [1])
        ires = 0
        call self%res(t, y, yp, self%cj, r, ires, rpar, ipar)
        if (ires == -1) then
            stat = 1            ! recoverable: a smaller step
        else if (ires /= 0) then
            stat = min(ires, -1)
        end if
    end subroutine problem_residual

    logical function problem_has_jacobian(self)
        class(ddaskr_problem), intent(in) :: self
        problem_has_jacobian = self%with_jac
    end function problem_has_jacobian

    subroutine problem_jacobian(self, t, y, yp, cj, pd, stat)
        class(ddaskr_problem), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:), cj
        real(wp), intent(inout) :: pd(:, :)
        integer, intent(inout) :: stat
        real(wp), pointer, contiguous :: rpar(:)
        integer, pointer, contiguous :: ipar(:)
        call c_f_pointer(self%rpar, rpar, [1])
        call c_f_pointer(self%ipar, ipar, [1])
        call self%jac(t, y, yp, pd, cj, rpar, ipar)
    end subroutine problem_jacobian

    subroutine problem_roots(self, t, y, yp, rval, stat)
        class(ddaskr_problem), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:)
        real(wp), intent(out) :: rval(:)
        integer, intent(inout) :: stat
        real(wp), pointer, contiguous :: rpar(:)
        integer, pointer, contiguous :: ipar(:)
        call c_f_pointer(self%rpar, rpar, [1])
        call c_f_pointer(self%ipar, ipar, [1])
        call self%rt(self%neq, t, y, yp, self%nroots, rval, rpar, ipar)
    end subroutine problem_roots

    ! --- the session's address in IWORK ---------------------------------------------------

    subroutine new_session(iwork, liw, s)
        integer, intent(in) :: liw
        integer, intent(inout) :: iwork(liw)
        type(ddaskr_session), pointer, intent(out) :: s
        allocate (s)
        s%message = ''
        call put_address(c_loc(s), session_mark, iwork(iwork_mark), iwork(iwork_check), &
                         iwork(iwork_address:iwork_address + address_words - 1))
    end subroutine new_session

    logical function session_in(iwork, liw, s)
        integer, intent(in) :: liw
        integer, intent(in) :: iwork(liw)
        type(ddaskr_session), pointer, intent(out) :: s
        type(c_ptr) :: address
        s => null()
        session_in = .false.
        if (liw < min_liw) return
        session_in = get_address(session_mark, iwork(iwork_mark), iwork(iwork_check), &
                                 iwork(iwork_address:iwork_address + address_words - 1), address)
        if (session_in) call c_f_pointer(address, s)
    end function session_in

end module regdae_ddaskr
