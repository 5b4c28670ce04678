!> The DASSL-style door for FORTRAN 77 codes: what the external subroutines
!! DREGDAE (index-2 problems), DREGDAEM (mechanical systems), DREGDAEMSG and
!! DREGDAEFREE of `dregdae.f90` do. The calling sequence, INFO, RWORK, IWORK and
!! IDID follow DASSL (Petzold, SAND82-8637, 1982) where their meanings carry over;
!! doc/api.md, "FORTRAN 77 interface (DREGDAE)", has the tables.
!!
!! Reentrant without SAVE, COMMON or module variables: the first call of a problem
!! (INFO(1) = 0) allocates a session (the solver, the routines, the last message)
!! and keeps its address in IWORK(21...) with a mark and a check word in IWORK(19)
!! and IWORK(20); later calls (INFO(1) = 1), DREGDAEMSG and DREGDAEFREE find it
!! there and refuse an IWORK whose mark or check word is wrong. Each problem has
!! its own IWORK: any number can be interleaved. A start on an IWORK that holds a
!! session (its mark and check word intact) frees that session first, so a restart
!! the DASSL way (INFO(1) = 0 again, no DREGDAEFREE) leaks nothing; an IWORK that
!! holds none (DASSL's callers do not initialize it) is only written.
!!
!! A refused start allocates no solver: the input is checked first, and the session
!! then keeps only the refusal's message, for DREGDAEMSG (a start whose solver
!! `init` fails frees the solver's memory the same way). A continuation refused
!! because IWORK holds no session cannot keep its message there: it leaves the
!! reason's code in IWORK(10), which DREGDAEMSG reads first.
module regdae_dassl
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_loc, c_f_pointer
    use regdae_iwork_address, only: address_words, put_address, get_address
    use, intrinsic :: iso_fortran_env, only: error_unit, int64
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_warn_multiplier_undefined, regdae_warn_unresolved, &
                             regdae_root_found, regdae_err_bad_input, &
                             regdae_err_inconsistent_ic, regdae_err_user_callback, regdae_err_not_initialized
    use regdae_format, only: format_int, format_real
    use regdae_options, only: solver_options, validate_options, method_trust_region, method_direct, integrator_radau, &
                              integrator_auto, integrator_ida, integrator_dopri5
    use regdae_solver_trust, only: regdae_solver, solver_stats
    use regdae_foreign_problems, only: foreign_first_order, foreign_mechanical
    use regdae_f77_routines, only: f77_routines, f77_point_routine, f77_motion_routine, f77_root_routine, f77_events
    implicit none
    private

    ! INFO: DASSL's entries 1-11 (DDASPK's 12-15 must be 0) and regdae's 16-20.
    integer, parameter :: info_start = 1         ! 0: first call of a problem; 1: continue
    integer, parameter :: info_vector_tol = 2    ! 1: ATOL a vector (RTOL too, with equal entries)
    integer, parameter :: info_intermediate = 3  ! 1: return after every step (IDID = 1)
    integer, parameter :: info_tstop = 4         ! 1: do not pass TSTOP = RWORK(1)
    integer, parameter :: info_jac = 5           ! 1: JAC is given (DREGDAEJ, DREGDAEMJ)
    integer, parameter :: info_hmax = 7          ! 1: HMAX = RWORK(2)
    integer, parameter :: info_h0 = 8            ! 1: H0 = RWORK(3)
    integer, parameter :: info_max_order = 9     ! 1: MAXORD = IWORK(3), 1 ... 5 (IDA's largest order)
    integer, parameter :: info_nonnegative = 10  ! 1: X (DREGDAEM: Q) kept >= 0 by IDA (IDASetConstraints)
    integer, parameter :: info_method = 16       ! 0 (trust_region), 1 baumgarte, 2 trust_region, 3 direct
    integer, parameter :: info_gt = 17           ! 1: GT is supplied
    integer, parameter :: info_index = 18        ! DREGDAEM: 0 (3), 2 or 3
    integer, parameter :: info_integrator = 19   ! 0 auto, 1 ida, 2 dopri5, 3 radau
    integer, parameter :: info_messages = 20     ! 0: error unit; > 0: that unit; -1: none
    !> The length of INFO.
    integer, parameter, public :: info_length = 20

    ! RWORK: DASSL's inputs and outputs, and regdae's parameters (0: auto).
    integer, parameter :: rwork_tstop = 1, rwork_hmax = 2, rwork_h0 = 3   ! inputs (INFO(4), (7), (8))
    integer, parameter :: rwork_tn = 4, rwork_hold = 7                   ! outputs: time reached, last step
    integer, parameter :: rwork_eps = 11, rwork_gamma = 12, rwork_gamma0 = 13, rwork_gamma1 = 14
    ! pass_tol (0: the default; < 0: pass_check off), error_estimate (1: on); outputs: the
    ! error estimate (-1: none) and the largest pass error (solver_stats)
    integer, parameter :: rwork_pass_tol = 15, rwork_error_estimate = 16, rwork_estimate = 17, rwork_pass_error = 18
    ! check_jacobians (1: on): JAC and GX against difference quotients at the start
    integer, parameter :: rwork_check_jacobians = 19
    !> The smallest LRW.
    integer, parameter, public :: min_lrw = 20

    ! IWORK: DASSL's counters, regdae's, the last status and the session's address.
    integer, parameter :: iwork_steps = 11, iwork_res_evals = 12, iwork_jac_evals = 13, iwork_err_test_fails = 14, &
                          iwork_conv_fails = 15, iwork_singular_passes = 16, iwork_switches = 17, iwork_status = 18
    integer, parameter :: iwork_mark = 19, iwork_check = 20, iwork_address = 21
    ! IWORK(10): 0, or the reason a call that found no session in IWORK was refused
    ! (DASSL keeps an internal counter there; DREGDAE reads none of IWORK(1:10))
    integer, parameter :: iwork_refusal = 10
    integer, parameter :: iwork_max_order = 3   ! input: MAXORD with INFO(9) = 1 (as DASSL)
    integer, parameter :: refused_no_solver = 1, refused_after_failure = 2, refused_info1 = 3
    !> The smallest LIW.
    integer, parameter, public :: min_liw = iwork_address + address_words - 1
    ! IWORK(iwork_mark) of an IWORK that holds a session (and a check word next to it).
    integer, parameter :: session_mark = 1997018

    ! IDID (DASSL's meanings; the other failures are regdae's status codes). Each
    ! warning has its own positive IDID: 4 (regdae_warn_multiplier_undefined) and 6
    ! (regdae_warn_unresolved), the call succeeded otherwise; 5 (regdae_root_found,
    ! DREGDAER and DREGDAEMR) a root of RT, as DDASKR's. DDASKR's 4 (the initial values
    ! alone, INFO(14) = 1, refused here) cannot occur.
    integer, parameter :: idid_exact = 2, idid_interpolated = 3, idid_multiplier_undefined = 4, idid_unresolved = 6
    integer, parameter :: idid_root = 5, idid_step = 1   ! a root of RT; INFO(3) = 1: a step short of TOUT
    integer, parameter :: idid_user_stop = -11, idid_initial_values = -12, idid_bad_input = -33

    integer, parameter :: kind_first_order = 1, kind_mechanical = 2

    ! One problem's state, behind IWORK.
    type :: dassl_session
        type(regdae_solver) :: solver
        type(f77_routines) :: routines
        integer :: kind = 0
        integer :: n = 0, m = 0
        logical :: exact_stops = .false.   ! INFO(4) = 1 at the start: steps end at every TOUT (IDID = 2)
        character(len=:), allocatable :: message
    end type dassl_session

    public :: dassl_first_order, dassl_mechanical, dassl_message, dassl_free

contains

    !> DREGDAE: x' = f(x, t) - B(x, t) y, 0 = g(x, t), from T to TOUT.
    subroutine dassl_first_order(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, &
                                 iwork, liw, rpar, ipar, rt, nrt, jroot, jac)
        procedure(f77_point_routine) :: f, b, g, gx, gt   !! the user's routines (GT used when INFO(17) = 1)
        integer, intent(in) :: n, m                       !! sizes of x and y
        real(wp), intent(inout) :: t                      !! in: T (first call: t0); out: the time reached
        real(wp), intent(inout) :: x(n)                   !! in: x(t0) at the first call; out: x(T)
        real(wp), intent(inout) :: y(m)                   !! out: y(T)
        real(wp), intent(in) :: tout                      !! where to go
        integer, intent(inout) :: info(info_length)       !! options and the call's state (see the module)
        real(wp), intent(in) :: rtol(*), atol(*)          !! tolerances (INFO(2) = 0: scalars)
        integer, intent(out) :: idid                      !! what happened
        integer, intent(in) :: lrw, liw                   !! lengths of RWORK and IWORK
        real(wp), intent(inout) :: rwork(lrw)             !! inputs and outputs (see the module)
        integer, intent(inout) :: iwork(liw)              !! counters, status and the solver's address
        real(wp), intent(inout), target :: rpar(*)        !! passed to the user's routines
        integer, intent(inout), target :: ipar(*)         !! passed to the user's routines
        procedure(f77_root_routine), optional :: rt       !! DREGDAER: the event functions
        integer, intent(in), optional :: nrt              !! their number
        integer, intent(out), optional :: jroot(*)        !! IDID = 5: +1 / -1 / 0 per function
        procedure(f77_point_routine), optional :: jac     !! DREGDAEJ: df/dx (used with INFO(5) = 1)
        type(dassl_session), pointer :: s
        type(foreign_first_order) :: problem
        type(solver_options) :: opts
        integer :: stat
        logical :: init_failed   ! this call's start (INFO(1) = 0) failed in the solver's init

        if (.not. open_call(kind_first_order, n, m, t, tout, info, rtol, atol, rwork, lrw, iwork, liw, idid, s, &
                            opts, present(jac))) return
        call attach(s, g, gx, gt, rpar, ipar)
        call s%solver%return_each_step(info(info_intermediate) == 1)
        s%routines%f => f
        s%routines%b => b
        stat = regdae_success
        init_failed = .false.
        if (info(info_start) == 0) then
            if (info(info_jac) == 1) s%routines%jac => jac
            if (.not. start_accepted(s, t, x, opts, info, iwork, idid)) return
            problem%n = n
            problem%m = m
            problem%routines => s%routines
            call s%solver%init(problem, t, x, opts, stat, atol_vector=tolerances(info, atol, n))
            if (stat == regdae_success .and. present(rt)) call set_roots(s, rt, nrt, stat)
            init_failed = (stat /= regdae_success)
        end if
        if (stat == regdae_success) call s%solver%advance(tout, x, y, stat)
        call close_call(s, stat, init_failed, t, tout, info, rwork, iwork, idid, jroot)
    end subroutine dassl_first_order

    !> DREGDAEM: M(q) q'' = f(q, q', t) + G^T lambda, 0 = g(q, t), from T to TOUT.
    subroutine dassl_mechanical(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, &
                                rwork, lrw, iwork, liw, rpar, ipar, rt, nrt, jroot, jac)
        procedure(f77_point_routine) :: mass, g, gx, gt    !! the user's routines (GT used when INFO(17) = 1)
        procedure(f77_motion_routine) :: forces
        integer, intent(in) :: n, m
        real(wp), intent(inout) :: t
        real(wp), intent(inout) :: q(n)                    !! in: q(t0) at the first call; out: q(T)
        real(wp), intent(inout) :: v(n)                    !! in: q'(t0) at the first call; out: q'(T)
        real(wp), intent(inout) :: lambda(m)               !! out: lambda(T)
        real(wp), intent(in) :: tout
        integer, intent(inout) :: info(info_length)
        real(wp), intent(in) :: rtol(*), atol(*)
        integer, intent(out) :: idid
        integer, intent(in) :: lrw, liw
        real(wp), intent(inout) :: rwork(lrw)
        integer, intent(inout) :: iwork(liw)
        real(wp), intent(inout), target :: rpar(*)
        integer, intent(inout), target :: ipar(*)
        procedure(f77_root_routine), optional :: rt       !! DREGDAEMR: the event functions
        integer, intent(in), optional :: nrt
        integer, intent(out), optional :: jroot(*)
        procedure(f77_motion_routine), optional :: jac    !! DREGDAEMJ: [df/dq, df/dq'] (used with INFO(5) = 1)
        type(dassl_session), pointer :: s
        type(foreign_mechanical) :: problem
        type(solver_options) :: opts
        integer :: stat
        logical :: init_failed   ! this call's start (INFO(1) = 0) failed in the solver's init

        if (.not. open_call(kind_mechanical, n, m, t, tout, info, rtol, atol, rwork, lrw, iwork, liw, idid, s, &
                            opts, present(jac))) return
        call attach(s, g, gx, gt, rpar, ipar)
        call s%solver%return_each_step(info(info_intermediate) == 1)
        s%routines%mass => mass
        s%routines%forces => forces
        stat = regdae_success
        init_failed = .false.
        if (info(info_start) == 0) then
            if (info(info_jac) == 1) s%routines%jac_forces => jac
            if (.not. start_accepted(s, t, q, opts, info, iwork, idid, v)) return
            problem%n = n
            problem%m = m
            problem%routines => s%routines
            call s%solver%init(problem, t, q, v, opts, stat, atol_vector=tolerances(info, atol, 2*n))
            if (stat == regdae_success .and. present(rt)) call set_roots(s, rt, nrt, stat)
            init_failed = (stat /= regdae_success)
        end if
        if (stat == regdae_success) call s%solver%advance(tout, q, lambda, stat, v=v)
        call close_call(s, stat, init_failed, t, tout, info, rwork, iwork, idid, jroot)
    end subroutine dassl_mechanical

    !> DREGDAEMSG: the message of the last call on the problem of IWORK ('' after
    !! success), blank-padded or cut to the length of msg.
    subroutine dassl_message(iwork, liw, msg)
        integer, intent(in) :: liw
        integer, intent(in) :: iwork(liw)
        character(len=*), intent(out) :: msg
        type(dassl_session), pointer :: s
        character(len=:), allocatable :: text
        if (liw < min_liw) then
            msg = 'DREGDAEMSG: an IWORK of LIW = '//format_int(liw)//' holds no regdae solver (LIW >= '// &
                  format_int(min_liw)//' is needed: a call with this LIW is refused for that)'
        else if (iwork(iwork_refusal) >= refused_no_solver .and. iwork(iwork_refusal) <= refused_info1) then
            call refusal_text(iwork(iwork_refusal), text)   ! the last call found no session to keep its message
            msg = text
        else if (session_in(iwork, liw, s)) then
            msg = s%message
        else
            msg = 'DREGDAEMSG: IWORK holds no regdae solver (no call with INFO(1) = 0 yet, or DREGDAEFREE since)'
        end if
    end subroutine dassl_message

    !> DREGDAEFREE: free the solver of IWORK (nothing if it holds none).
    subroutine dassl_free(iwork, liw)
        integer, intent(in) :: liw
        integer, intent(inout) :: iwork(liw)
        type(dassl_session), pointer :: s
        if (.not. session_in(iwork, liw, s)) return
        call s%solver%destroy()
        deallocate (s)
        iwork(iwork_mark) = 0
        iwork(iwork_check) = 0
    end subroutine dassl_free

    ! --- the steps of a call ------------------------------------------------------------

    ! The routines of the constraint, and the RPAR and IPAR of this call, for the
    ! user's routines to receive.
    subroutine attach(s, g, gx, gt, rpar, ipar)
        type(dassl_session), intent(inout) :: s
        procedure(f77_point_routine) :: g, gx, gt
        real(wp), intent(inout), target :: rpar(*)
        integer, intent(inout), target :: ipar(*)
        s%routines%g => g
        s%routines%gx => gx
        s%routines%gt => gt
        s%routines%rpar = c_loc(rpar(1))
        s%routines%ipar = c_loc(ipar(1))
    end subroutine attach

    ! The checks of a call, the session of IWORK (created by INFO(1) = 0, after the
    ! one IWORK held is freed) and, at the start, the options. False: IDID = -33 is
    ! set, the message kept for DREGDAEMSG and printed.
    logical function open_call(kind, n, m, t, tout, info, rtol, atol, rwork, lrw, iwork, liw, idid, s, opts, &
                               with_jac) result(ok)
        integer, intent(in) :: kind, n, m, lrw, liw
        real(wp), intent(in) :: t, tout
        integer, intent(inout) :: info(info_length)
        real(wp), intent(in) :: rtol(*), atol(*)
        real(wp), intent(in) :: rwork(lrw)
        integer, intent(inout) :: iwork(liw)
        integer, intent(out) :: idid
        type(dassl_session), pointer, intent(out) :: s
        type(solver_options), intent(out) :: opts
        logical, intent(in) :: with_jac   ! called as DREGDAEJ or DREGDAEMJ
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
            ! The input first (a refused start creates no solver), then the session: the
            ! one IWORK held (a restart without DREGDAEFREE) is freed first
            call check_call(t, tout, info, rwork, lrw, msg)
            if (len(msg) == 0) call options_from(kind, n, m, info, rtol, atol, rwork, iwork(iwork_max_order), &
                                                 with_jac, opts, msg)
            call dassl_free(iwork, liw)
            call new_session(iwork, liw, s)
            s%kind = kind
            s%n = n
            s%m = m
            if (len(msg) == 0) then
                s%exact_stops = opts%stop_at_output
                s%routines%gt_supplied = (info(info_gt) == 1)
                s%routines%nonnegative = (info(info_nonnegative) == 1)
            end if
        else if (session_in(iwork, liw, s)) then
            ! A continuation, or a refused INFO(1): the session keeps this call's message
            ! for DREGDAEMSG, not the one of the call before
            if (info(info_start) == 1) then
                if (s%kind /= kind .or. s%n /= n .or. s%m /= m) &
                    msg = 'INFO(1) = 1 but IWORK holds another problem ('//trim(merge('DREGDAE ', 'DREGDAEM', &
                          s%kind == kind_first_order))//', N = '//format_int(s%n)//', M = '//format_int(s%m)//')'
            else if (info(info_start) == -1) then
                call refusal_text(refused_after_failure, msg)
            else
                call info1_text(info(info_start), msg)
            end if
            if (len(msg) == 0) call check_call(t, tout, info, rwork, lrw, msg)
        else
            ! No session to keep the message: IWORK(10) keeps the reason
            refusal = refused_info1
            if (info(info_start) == 1) refusal = refused_no_solver
            if (info(info_start) == -1) refusal = refused_after_failure
            call refusal_text(refusal, msg)
            if (refusal == refused_info1) call info1_text(info(info_start), msg)
        end if
        if (liw >= min_liw) iwork(iwork_refusal) = refusal
        ok = (len(msg) == 0)
        if (ok) return
        if (associated(s)) s%message = msg
        if (liw >= min_liw) iwork(iwork_status) = regdae_err_bad_input
        info(info_start) = -1
        call report(info, kind, msg)
    end function open_call

    ! The checks of a start that read X (Q): with INFO(10) = 1 no component < 0 (IDID
    ! = -33); with check_jacobians (RWORK(19) = 1) and JAC in use (INFO(5) = 1) PD
    ! against central difference quotients of F (FORCES), before the solver is
    ! created (IDID = -116, regdae_err_jacobian, naming the entry of PD; -11 when a
    ! routine stopped the check). False: the start fails, the message kept and printed.
    logical function start_accepted(s, t, x, opts, info, iwork, idid, v) result(ok)
        type(dassl_session), intent(inout) :: s
        real(wp), intent(in) :: t, x(:)
        type(solver_options), intent(in) :: opts
        integer, intent(inout) :: info(info_length)
        integer, intent(inout) :: iwork(:)
        integer, intent(out) :: idid
        real(wp), intent(in), optional :: v(:)   ! DREGDAEMJ: the velocity
        integer :: stat
        character(len=:), allocatable :: msg
        stat = regdae_success
        if (s%routines%nonnegative .and. any(x < 0.0_wp)) then
            stat = regdae_err_bad_input
            msg = 'INFO(10) = 1 and '//trim(merge('X', 'Q', s%kind == kind_first_order))//'('// &
                  format_int(minloc(x, 1))//') = '//format_real(minval(x))//' < 0 at the start: the '// &
                  'nonnegative components must start >= 0'
        else if (opts%check_jacobians .and. s%routines%has_jac()) then
            call s%routines%check_jac(t, x, stat, msg, v)
        end if
        ok = (stat == regdae_success)
        if (ok) return
        idid = merge(idid_user_stop, stat, stat == regdae_err_user_callback)
        if (stat == regdae_err_bad_input) idid = idid_bad_input
        iwork(iwork_status) = stat
        s%message = msg
        info(info_start) = -1
        call report(info, s%kind, msg)
        call s%routines%forget_failure()
    end function start_accepted

    ! The checks of every call that do not depend on the problem: LRW, TOUT, TSTOP.
    subroutine check_call(t, tout, info, rwork, lrw, msg)
        real(wp), intent(in) :: t, tout
        integer, intent(in) :: info(info_length), lrw
        real(wp), intent(in) :: rwork(lrw)
        character(len=:), allocatable, intent(inout) :: msg
        if (lrw < min_lrw) then
            msg = 'LRW = '//format_int(lrw)//' is too small: RWORK needs LRW >= '//format_int(min_lrw)
        else if (tout == t) then
            msg = 'TOUT = '//format_real(tout)//' is equal to T'
        else if (info(info_tstop) == 1 .and. rwork(rwork_tstop) < tout) then
            msg = 'INFO(4) = 1 and TSTOP = RWORK(1) = '//format_real(rwork(rwork_tstop))//' is behind TOUT = '// &
                  format_real(tout)
        end if
    end subroutine check_call

    ! The message of a refused INFO(1) (also what DREGDAEMSG says for IWORK(10)).
    pure subroutine refusal_text(reason, text)
        integer, intent(in) :: reason
        character(len=:), allocatable, intent(out) :: text
        select case (reason)
        case (refused_no_solver)
            text = 'INFO(1) = 1 but IWORK holds no solver: start a problem with INFO(1) = 0 (IWORK must not '// &
                   'change between the calls of a problem)'
        case (refused_after_failure)
            text = 'INFO(1) = -1: the last call failed; set INFO(1) = 1 to try to continue, or 0 to restart'
        case default
            text = 'INFO(1) was neither 0 (start) nor 1 (continue)'
        end select
    end subroutine refusal_text

    ! The message of an INFO(1) that is neither 0, 1 nor -1.
    pure subroutine info1_text(value, text)
        integer, intent(in) :: value
        character(len=:), allocatable, intent(out) :: text
        text = 'INFO(1) = '//format_int(value)//' must be 0 (start) or 1 (continue)'
    end subroutine info1_text

    ! After the solver's call: T, the counters, IDID, INFO(1) and the message (the
    ! user's routines named as DREGDAE's argument list names them); a start whose
    ! solver init failed frees the solver's memory (the session keeps the message).
    ! DREGDAER, DREGDAEMR: the NRT functions of RT, each stopping the integration at
    ! its roots (IDID = 5), both directions.
    subroutine set_roots(s, rt, nrt, stat)
        type(dassl_session), intent(inout), target :: s
        procedure(f77_root_routine) :: rt
        integer, intent(in) :: nrt
        integer, intent(out) :: stat
        type(f77_events) :: ev
        ev%rt => rt
        ev%routines => s%routines
        call s%solver%set_events(ev, nrt, stat)
        if (stat /= regdae_success .and. nrt < 0) stat = regdae_err_bad_input
    end subroutine set_roots

    subroutine close_call(s, stat, init_failed, t, tout, info, rwork, iwork, idid, jroot)
        type(dassl_session), intent(inout) :: s
        integer, intent(in) :: stat
        logical, intent(in) :: init_failed   ! this call's start failed in the solver's init
        real(wp), intent(inout) :: t
        real(wp), intent(in) :: tout
        integer, intent(inout) :: info(info_length)
        real(wp), intent(inout) :: rwork(:)
        integer, intent(inout) :: iwork(:)
        integer, intent(out) :: idid
        integer, intent(out), optional :: jroot(*)
        type(solver_stats) :: st
        integer, allocatable :: found(:)

        st = s%solver%statistics()
        iwork(iwork_steps) = counter(st%steps)
        iwork(iwork_res_evals) = counter(st%res_evals)
        iwork(iwork_jac_evals) = counter(st%jac_evals)
        iwork(iwork_err_test_fails) = counter(st%err_test_fails)
        iwork(iwork_conv_fails) = counter(st%conv_fails)
        iwork(iwork_singular_passes) = st%singular_passes
        iwork(iwork_switches) = st%switches
        iwork(iwork_status) = stat
        rwork(rwork_tn) = st%t
        rwork(rwork_hold) = st%h_last
        rwork(rwork_estimate) = st%error_estimate
        rwork(rwork_pass_error) = st%pass_error
        s%message = ''
        if (stat /= regdae_success) call in_dassl_words(s%solver%message(), s%routines, s%message)
        select case (stat)
        case (regdae_success)
            idid = merge(idid_exact, idid_interpolated, s%exact_stops)
            if (st%t < tout) idid = idid_step
        case (regdae_warn_multiplier_undefined)
            idid = idid_multiplier_undefined
        case (regdae_warn_unresolved)
            idid = idid_unresolved
        case (regdae_root_found)
            idid = idid_root
            found = s%solver%roots()
            if (present(jroot)) jroot(1:size(found)) = found
        case (regdae_err_bad_input, regdae_err_not_initialized)
            idid = idid_bad_input
        case (regdae_err_inconsistent_ic)
            idid = idid_initial_values
        case (regdae_err_user_callback)
            idid = idid_user_stop
        case default
            idid = stat
        end select
        if (idid > 0) then
            ! the time reached: TOUT, or with INFO(3) = 1 or at a root the step's end or the root
            t = st%t
            info(info_start) = 1
        else
            t = st%t
            info(info_start) = -1
        end if
        ! a failure or a warning (not a root)
        if (stat /= regdae_success .and. stat /= regdae_root_found) call report(info, s%kind, s%message)
        call s%routines%forget_failure()
        if (init_failed) call s%solver%destroy()
    end subroutine close_call

    ! A message of the solver in the words of DREGDAE's caller: each "user routine
    ! <name> reported failure (stat = <k>)" becomes what the user's routine did, e.g.
    ! "G returned IRES = -2", from the door's record of its last failure (which the
    ! message states too, with T, when it names no routine).
    subroutine in_dassl_words(message, routines, text)
        character(len=*), intent(in) :: message
        type(f77_routines), intent(in) :: routines
        character(len=:), allocatable, intent(out) :: text
        character(len=*), parameter :: opening = 'user routine ', closing = ' reported failure (stat = '
        character(len=*), parameter :: g_check = 'check_jacobians: constraint_jacobian disagrees with the '// &
                                                 'difference quotient of the constraint'
        integer :: at, name_end, paren
        logical :: named
        text = message
        at = index(text, g_check)   ! check_jacobians on GX (DREGDAEM)
        if (at > 0) text = text(:at - 1)//'check_jacobians: GX disagrees with the difference quotient of G'// &
                           text(at + len(g_check):)
        if (.not. allocated(routines%said)) return
        named = .false.
        do
            at = index(text, opening)
            if (at == 0) exit
            name_end = index(text(at + len(opening):), closing)
            if (name_end == 0) exit
            paren = index(text(at + len(opening) + name_end - 1 + len(closing):), ')')
            if (paren == 0) exit
            paren = at + len(opening) + name_end - 1 + len(closing) + paren - 1
            text = text(:at - 1)//routines%said//text(paren + 1:)
            named = .true.
        end do
        if (.not. named) text = text//' ('//routines%failure//')'
    end subroutine in_dassl_words

    ! The options from INFO, RTOL, ATOL and RWORK; msg names the first bad entry.
    subroutine options_from(kind, n, m, info, rtol, atol, rwork, maxord, with_jac, opts, msg)
        integer, intent(in) :: kind, n, m
        integer, intent(in) :: info(info_length)
        real(wp), intent(in) :: rtol(*), atol(*), rwork(:)
        integer, intent(in) :: maxord   ! IWORK(3): the largest order with INFO(9) = 1
        logical, intent(in) :: with_jac ! DREGDAEJ or DREGDAEMJ: INFO(5) = 1 may ask for JAC
        type(solver_options), intent(out) :: opts
        character(len=:), allocatable, intent(inout) :: msg
        character(len=:), allocatable :: feature
        integer :: i, stat, n_tol

        n_tol = merge(n, 2*n, kind == kind_first_order)   ! the tolerance vectors' length (INFO(2) = 1)
        if (n < 1 .or. m < 0 .or. m > n) then
            msg = 'N = '//format_int(n)//', M = '//format_int(m)//': the sizes must satisfy 1 <= N and 0 <= M <= N'
        else if (unequal_rtol()) then
            ! ATOL per component (DREGDAE: N entries; DREGDAEM: 2N, q then q'); regdae's rtol
            ! is one number
            msg = 'INFO(2) = 1 with unequal RTOL(1:'//format_int(n_tol)//'): regdae has one relative tolerance '// &
                  '(dopri5 and radau form their error weights from a scalar rtol, and so do regdae''s own '// &
                  'checks of the passes and the drift); give RTOL equal entries, e.g. all '// &
                  format_real(minval(rtol(1:n_tol)))//' (the smallest, which meets every component''s), and '// &
                  'set the scale of each component through ATOL, which may vary (a plain DAE F(t, y, y'') = 0 '// &
                  'without singular configurations: DREGDASKR, DDASKR''s door, takes RTOL per component)'
        end if
        do i = 2, 11
            if (len(msg) == 0 .and. info(i) /= 0 .and. info(i) /= 1) &
                msg = 'INFO('//format_int(i)//') = '//format_int(info(i))//' must be 0 or 1'
        end do
        do i = 3, 15
            if (len(msg) > 0) exit
            if (info(i) /= 0 .and. any(i == [5, 6, 12, 13, 14, 15]) .and. .not. (i == info_jac .and. with_jac)) then
                call dassl_feature(i, kind, feature)
                msg = 'INFO('//format_int(i)//') = '//format_int(info(i))//' asks for '//feature
            end if
        end do
        if (len(msg) > 0) return
        if (info(info_method) < 0 .or. info(info_method) > method_direct) then
            msg = 'INFO(16) = '//format_int(info(info_method))//' is not a method (0 or 2 trust_region, '// &
                  '1 baumgarte, 3 direct)'
        else if (info(info_gt) /= 0 .and. info(info_gt) /= 1) then
            msg = 'INFO(17) = '//format_int(info(info_gt))//' must be 0 (no GT) or 1 (GT supplied)'
        else if (kind == kind_first_order .and. info(info_index) /= 0) then
            msg = 'INFO(18) = '//format_int(info(info_index))//': the index is for DREGDAEM; set it to 0'
        else if (.not. any(info(info_index) == [0, 2, 3])) then
            msg = 'INFO(18) = '//format_int(info(info_index))//' must be 0 (index 3), 2 or 3'
        else if (info(info_integrator) < 0 .or. info(info_integrator) > integrator_radau) then
            msg = 'INFO(19) = '//format_int(info(info_integrator))//' must be 0 (auto), 1 (ida), 2 (dopri5) or 3 (radau)'
        else if (info(info_hmax) == 1 .and. .not. rwork(rwork_hmax) > 0.0_wp) then
            msg = 'INFO(7) = 1 and HMAX = RWORK(2) = '//format_real(rwork(rwork_hmax))//' is not > 0'
        else if (info(info_h0) == 1 .and. .not. rwork(rwork_h0) > 0.0_wp) then
            msg = 'INFO(8) = 1 and H0 = RWORK(3) = '//format_real(rwork(rwork_h0))//' is not > 0'
        else if (info(info_max_order) == 1 .and. (maxord < 1 .or. maxord > 5)) then
            msg = 'INFO(9) = 1 and MAXORD = IWORK(3) = '//format_int(maxord)//' is not 1 ... 5 (IDA''s orders)'
        else if (info(info_nonnegative) == 1 .and. info(info_integrator) > integrator_ida) then
            msg = 'INFO(10) = 1 (nonnegative solutions) with INFO(19) = '//format_int(info(info_integrator))// &
                  trim(merge(' (dopri5)', ' (radau) ', info(info_integrator) == integrator_dopri5))// &
                  ': nonnegativity is IDA''s constraint option (IDASetConstraints), which dopri5 and radau '// &
                  'do not have: set INFO(19) = 0 or 1 (IDA), or INFO(10) = 0 and check the signs after each return'
        end if
        if (len(msg) > 0) return
        opts%method = merge(method_trust_region, info(info_method), info(info_method) == 0)
        if (info(info_index) /= 0) opts%index = info(info_index)
        opts%integrator = info(info_integrator)
        ! INFO(10) = 1: IDA in charge throughout (auto would hand non-stiff stretches to dopri5)
        if (info(info_nonnegative) == 1 .and. opts%integrator == integrator_auto) opts%integrator = integrator_ida
        opts%rtol = rtol(1)
        opts%atol = atol(1)   ! INFO(2) = 1: the vector goes to init
        opts%stop_at_output = (info(info_tstop) == 1)
        if (info(info_hmax) == 1) opts%h_max = rwork(rwork_hmax)
        if (info(info_h0) == 1) opts%h_init = rwork(rwork_h0)
        if (info(info_max_order) == 1) opts%max_order = maxord
        if (rwork(rwork_eps) /= 0.0_wp) opts%eps = rwork(rwork_eps)
        if (rwork(rwork_gamma) /= 0.0_wp) opts%gamma = rwork(rwork_gamma)
        if (rwork(rwork_gamma0) /= 0.0_wp) opts%gamma0 = rwork(rwork_gamma0)
        if (rwork(rwork_gamma1) /= 0.0_wp) opts%gamma1 = rwork(rwork_gamma1)
        if (rwork(rwork_pass_tol) > 0.0_wp) opts%pass_tol = rwork(rwork_pass_tol)
        if (rwork(rwork_pass_tol) < 0.0_wp) opts%pass_check = .false.
        opts%error_estimate = (rwork(rwork_error_estimate) == 1.0_wp)
        call validate_options(opts, stat, msg)
        opts%check_jacobians = (rwork(rwork_check_jacobians) == 1.0_wp)
        if (stat == regdae_success .and. .not. (rwork(rwork_error_estimate) == 0.0_wp .or. &
                                                rwork(rwork_error_estimate) == 1.0_wp)) then
            stat = regdae_err_bad_input
            msg = 'RWORK(16) (error estimate) must be 0 or 1, got '//format_real(rwork(rwork_error_estimate))
        else if (stat == regdae_success .and. .not. (rwork(rwork_check_jacobians) == 0.0_wp .or. &
                                                     rwork(rwork_check_jacobians) == 1.0_wp)) then
            stat = regdae_err_bad_input
            msg = 'RWORK(19) (check_jacobians) must be 0 or 1, got '//format_real(rwork(rwork_check_jacobians))
        end if
        if (stat /= regdae_success) msg = 'RTOL, ATOL or RWORK(11..19): '//msg
    contains
        ! INFO(2) = 1 with unequal RTOL(1:n_tol); RTOL beyond its first entry read only with
        ! INFO(2) = 1 (a scalar RTOL has one: Fortran's .and. may evaluate both operands)
        logical function unequal_rtol()
            unequal_rtol = .false.
            if (info(info_vector_tol) == 1) unequal_rtol = any(rtol(1:n_tol) /= rtol(1))
        end function unequal_rtol
    end subroutine options_from

    ! ATOL for each of the k components of the state: ATOL(1:k) with INFO(2) = 1, else ATOL(1).
    pure function tolerances(info, atol, k) result(atol_state)
        integer, intent(in) :: info(info_length), k
        real(wp), intent(in) :: atol(*)
        real(wp) :: atol_state(k)
        if (info(info_vector_tol) == 1) then
            atol_state = atol(1:k)
        else
            atol_state = atol(1)
        end if
    end function tolerances

    ! What DASSL's (and DDASPK's) INFO(i) asks for, why DREGDAE does not have it, and
    ! what to do instead.
    pure subroutine dassl_feature(i, kind, text)
        integer, intent(in) :: i
        integer, intent(in) :: kind   ! kind_first_order (DREGDAE) or kind_mechanical (DREGDAEM)
        character(len=:), allocatable, intent(out) :: text
        select case (i)
        case (5)
            text = 'a JAC routine, which '//trim(merge('DREGDAE ', 'DREGDAEM', kind == kind_first_order))// &
                   ' does not take (its argument list has no place for it): call '// &
                   trim(merge('DREGDAEJ ', 'DREGDAEMJ', kind == kind_first_order))//' (the same arguments '// &
                   'and JAC after IPAR, as DASSL; with RT, NRT, JROOT: '// &
                   trim(merge('DREGDAEJR ', 'DREGDAEMJR', kind == kind_first_order))//'), or set INFO(5) = 0'
        case (6)
            text = 'a banded matrix (IWORK(1), IWORK(2)), which DREGDAE does not take: the Newton matrix of its '// &
                   'regularized system is not banded when df/dx is (the multiplier y(x) solves (GB) y = G f + ..., '// &
                   'so every component that G f reads enters every row that B has), and the dense solver '// &
                   'serves it; set INFO(6) = 0 (for a large mechanism declare its structure in the Fortran or C '// &
                   'API: the augmented formulation takes linear_solver=band or sparse; a plain banded DAE '// &
                   'F(t, y, y'') = 0 without singular configurations: DREGDASKR, DDASKR''s door, with INFO(6) = 1)'
        case (12, 13, 15)
            text = 'DDASPK''s Krylov method (INFO(12), (13), (15)), which DREGDAE does not have (its Newton '// &
                   'systems are solved directly): set INFO(12), INFO(13) and INFO(15) to 0'
        case default
            text = 'the initial values alone (DDASPK''s INFO(14)), which DREGDAE does not stop at (it checks '// &
                   'g(x0, t0) = 0 and computes y(t0) at every start, then integrates): set INFO(14) = 0'
        end select
    end subroutine dassl_feature

    ! Print a message on the unit of INFO(20) (0: the error unit; -1: none).
    subroutine report(info, kind, msg)
        integer, intent(in) :: info(info_length)
        integer, intent(in) :: kind
        character(len=*), intent(in) :: msg
        character(len=:), allocatable :: who
        who = trim(merge('DREGDAE ', 'DREGDAEM', kind == kind_first_order))//'-- '
        if (info(info_messages) == 0) then
            write (error_unit, '(a)') who//msg
        else if (info(info_messages) > 0) then
            write (info(info_messages), '(a)') who//msg
        end if
    end subroutine report

    ! An int64 counter in a default integer (the largest one if it does not fit).
    pure integer function counter(k)
        integer(int64), intent(in) :: k
        counter = int(min(k, int(huge(0), int64)))
    end function counter

    ! --- the session's address in IWORK ---------------------------------------------------

    ! A new session, its address kept in IWORK.
    subroutine new_session(iwork, liw, s)
        integer, intent(in) :: liw
        integer, intent(inout) :: iwork(liw)
        type(dassl_session), pointer, intent(out) :: s
        allocate (s)
        call put_address(c_loc(s), session_mark, iwork(iwork_mark), iwork(iwork_check), iwork(iwork_address:min_liw))
    end subroutine new_session

    ! The session whose address IWORK holds; false if it holds none (never had one,
    ! or freed since: the mark or the check word is wrong).
    logical function session_in(iwork, liw, s)
        integer, intent(in) :: liw
        integer, intent(in) :: iwork(liw)
        type(dassl_session), pointer, intent(out) :: s
        type(c_ptr) :: address
        s => null()
        session_in = .false.
        if (liw < min_liw) return
        session_in = get_address(session_mark, iwork(iwork_mark), iwork(iwork_check), iwork(iwork_address:min_liw), &
                                 address)
        if (session_in) call c_f_pointer(address, s)
    end function session_in

end module regdae_dassl
