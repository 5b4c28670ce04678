!> DREGDASKR's input: DDASKR's INFO, RWORK and IWORK entries read into
!! `residual_options`, and the checks that refuse a call (IDID = -33) with a message
!! that says why and what to do. The places are DDASKR's (doc/api.md has the table).
module regdae_ddaskr_input
    use regdae_kinds, only: wp
    use regdae_format, only: format_int, format_real
    use regdae_residual_options, only: residual_options, check_residual_options, initial_given, &
                                       initial_algebraic, initial_from_slope
    use regdae_status, only: regdae_success
    implicit none
    private

    !> INFO's entries (DDASKR's meanings; INFO(20) is regdae's: the message unit).
    integer, parameter, public :: info_length = 20
    integer, parameter, public :: info_start = 1, info_vector_tol = 2, info_intermediate = 3, info_tstop = 4, &
                                  info_jac = 5, info_band = 6, info_hmax = 7, info_h0 = 8, info_max_order = 9, &
                                  info_constraints = 10, info_initial = 11, info_krylov = 12, info_krylov_params = 13, &
                                  info_ic_only = 14, info_krylov_jac = 15, info_exclude_alg = 16, info_ic_controls = 17, &
                                  info_ic_print = 18, info_messages = 20
    !> RWORK's inputs.
    integer, parameter, public :: rwork_tstop = 1, rwork_hmax = 2, rwork_h0 = 3
    !> IWORK's inputs: ML, MU, MAXORD; the constraint codes and the ID array start after
    !! IWORK(iwork_arrays) (DDASKR's LID rule: ID at 40 + NEQ when INFO(10) = 1 or 3).
    integer, parameter, public :: iwork_ml = 1, iwork_mu = 2, iwork_maxord = 3, iwork_arrays = 40
    !> DDASKR's private words that hold regdae's session: the reason of a refusal found
    !! without a session (10), the mark (37), the check word (38), the address (39, 40).
    integer, parameter, public :: iwork_refusal = 10, iwork_mark = 37, iwork_check = 38, iwork_address = 39
    integer, parameter, public :: refused_no_solver = 1, refused_after_failure = 2, refused_info1 = 3, &
                                  refused_start = 4
    !> The smallest LIW and LRW (DDASKR's own are larger and suffice).
    integer, parameter, public :: min_liw = 40, min_lrw = 20

    public :: check_call, options_from, tolerances, needed_liw

contains

    !> The LIW that INFO's options need: 40, + NEQ for the constraint codes (INFO(10)
    !! = 1, 3), + NEQ for the ID array (INFO(11) = 1 or INFO(16) = 1).
    pure integer function needed_liw(info, neq)
        integer, intent(in) :: info(info_length), neq
        needed_liw = iwork_arrays
        if (info(info_constraints) == 1 .or. info(info_constraints) == 3) needed_liw = needed_liw + neq
        if (info(info_initial) == 1 .or. info(info_exclude_alg) == 1) needed_liw = needed_liw + neq
    end function needed_liw

    !> The checks of every call that do not depend on the session: NEQ, LRW, TOUT, TSTOP.
    subroutine check_call(neq, t, tout, info, rwork, lrw, msg)
        integer, intent(in) :: neq, lrw
        real(wp), intent(in) :: t, tout
        integer, intent(in) :: info(info_length)
        real(wp), intent(in) :: rwork(lrw)
        character(len=:), allocatable, intent(inout) :: msg
        if (neq < 1) then
            msg = 'NEQ = '//format_int(neq)//' must be >= 1'
        else if (lrw < min_lrw) then
            msg = 'LRW = '//format_int(lrw)//' is too small: RWORK needs LRW >= '//format_int(min_lrw)
        else if (tout == t) then
            msg = 'TOUT = '//format_real(tout)//' is equal to T'
        else if (info(info_tstop) == 1 .and. (tout - rwork(rwork_tstop))*(tout - t) > 0.0_wp) then
            msg = 'INFO(4) = 1 and TOUT = '//format_real(tout)//' is beyond TSTOP = RWORK(1) = '// &
                  format_real(rwork(rwork_tstop))
        else if (info(info_tstop) == 1 .and. (rwork(rwork_tstop) - t)*(tout - t) < 0.0_wp) then
            msg = 'INFO(4) = 1 and TSTOP = RWORK(1) = '//format_real(rwork(rwork_tstop))//' is behind T = '// &
                  format_real(t)
        end if
    end subroutine check_call

    !> RTOL and ATOL per component: the vectors (INFO(2) = 1) or the scalars spread.
    pure subroutine tolerances(info, rtol, atol, neq, rtol_v, atol_v)
        integer, intent(in) :: info(info_length), neq
        real(wp), intent(in) :: rtol(*), atol(*)
        real(wp), intent(out) :: rtol_v(neq), atol_v(neq)
        if (info(info_vector_tol) == 1) then
            rtol_v = rtol(1:neq)
            atol_v = atol(1:neq)
        else
            rtol_v = rtol(1)
            atol_v = atol(1)
        end if
    end subroutine tolerances

    !> The options of a start (INFO(1) = 0) from INFO, RTOL, ATOL, RWORK and IWORK;
    !! msg '' if they are accepted, else why not and what to do.
    subroutine options_from(neq, info, rtol, atol, rwork, iwork, opts, msg)
        integer, intent(in) :: neq
        integer, intent(in) :: info(info_length)
        real(wp), intent(in) :: rtol(*), atol(*), rwork(*)
        integer, intent(in) :: iwork(*)
        type(residual_options), intent(out) :: opts
        character(len=:), allocatable, intent(inout) :: msg
        real(wp) :: rtol_v(neq), atol_v(neq)
        integer :: k, lid, stat
        msg = ''
        do k = 2, 18
            if (k == info_constraints .or. k == info_initial .or. k == info_ic_print) cycle
            if (info(k) /= 0 .and. info(k) /= 1) then
                msg = 'INFO('//format_int(k)//') = '//format_int(info(k))//' must be 0 or 1'
                return
            end if
        end do
        if (info(info_krylov) == 1) then
            msg = 'INFO(12) = 1 asks for DDASKR''s Krylov method (SPIGMR with the user''s preconditioner PSOL), '// &
                  'which DREGDASKR does not have: its Newton systems are solved directly by IDA''s dense or band '// &
                  'LU. Set INFO(12) = 0 (INFO(6) = 1 with IWORK(1) = ML, IWORK(2) = MU for a banded matrix); for '// &
                  'a large sparse system call IDA with SUNLinSol_SPGMR yourself'
        else if (info(info_ic_controls) == 1) then
            msg = 'INFO(17) = 1 (MXNIT, MXNJ, MXNH, LSOFF, STPTOL, EPINIT of the initial-value computation) is not '// &
                  'mapped: IDACalcIC runs with IDA''s defaults; set INFO(17) = 0'
        else if (info(info_constraints) < 0 .or. info(info_constraints) > 3) then
            msg = 'INFO(10) = '//format_int(info(info_constraints))//' must be 0, 1, 2 or 3'
        else if (info(info_initial) < 0 .or. info(info_initial) > 2) then
            msg = 'INFO(11) = '//format_int(info(info_initial))//' must be 0, 1 or 2'
        else if (info(info_ic_print) < 0 .or. info(info_ic_print) > 2) then
            msg = 'INFO(18) = '//format_int(info(info_ic_print))//' must be 0, 1 or 2'
        end if
        if (len(msg) > 0) return
        call tolerances(info, rtol, atol, neq, rtol_v, atol_v)
        if (any(rtol_v < 0.0_wp) .or. any(atol_v < 0.0_wp)) then
            msg = 'RTOL and ATOL must be >= 0 (component '//format_int(minloc(min(rtol_v, atol_v), 1))//')'
        else if (all(rtol_v == 0.0_wp) .and. all(atol_v == 0.0_wp)) then
            msg = 'RTOL and ATOL are all 0: give at least one a positive value'
        else if (info(info_band) == 1 .and. (iwork(iwork_ml) < 0 .or. iwork(iwork_ml) >= neq .or. &
                                               iwork(iwork_mu) < 0 .or. iwork(iwork_mu) >= neq)) then
            msg = 'INFO(6) = 1 and ML = IWORK(1) = '//format_int(iwork(iwork_ml))//', MU = IWORK(2) = '// &
                  format_int(iwork(iwork_mu))//': both must be 0 ... NEQ - 1'
        else if (info(info_hmax) == 1 .and. .not. rwork(rwork_hmax) > 0.0_wp) then
            msg = 'INFO(7) = 1 and HMAX = RWORK(2) = '//format_real(rwork(rwork_hmax))//' is not > 0'
        else if (info(info_h0) == 1 .and. .not. rwork(rwork_h0) /= 0.0_wp) then
            msg = 'INFO(8) = 1 and H0 = RWORK(3) = '//format_real(rwork(rwork_h0))//' is 0'
        else if (info(info_max_order) == 1 .and. (iwork(iwork_maxord) < 1 .or. iwork(iwork_maxord) > 5)) then
            msg = 'INFO(9) = 1 and MAXORD = IWORK(3) = '//format_int(iwork(iwork_maxord))//' is not 1 ... 5'
        end if
        if (len(msg) > 0) return
        opts%rtol_v = rtol_v
        opts%atol_v = atol_v
        if (info(info_band) == 1) then
            opts%band_lower = iwork(iwork_ml)
            opts%band_upper = iwork(iwork_mu)
        end if
        if (info(info_hmax) == 1) opts%h_max = rwork(rwork_hmax)
        if (info(info_h0) == 1) opts%h_init = abs(rwork(rwork_h0))
        if (info(info_max_order) == 1) opts%max_order = iwork(iwork_maxord)
        lid = iwork_arrays
        select case (info(info_constraints))
        case (1, 3)
            opts%ic_constraints = iwork(iwork_arrays + 1:iwork_arrays + neq)
            lid = iwork_arrays + neq
            if (any(abs(opts%ic_constraints) > 2)) then
                msg = 'INFO(10) = '//format_int(info(info_constraints))//': IWORK(40 + I) must be -2 ... 2, got '// &
                      format_int(opts%ic_constraints(maxloc(abs(opts%ic_constraints), 1)))//' at I = '// &
                      format_int(maxloc(abs(opts%ic_constraints), 1))
                return
            end if
        end select
        if (info(info_constraints) >= 2) opts%constraints = spread(1, 1, neq)   ! y >= 0 in the integration
        if (info(info_constraints) == 1) opts%constraints = spread(0, 1, neq)   ! in the initial values only
        if (info(info_initial) == 1 .or. info(info_exclude_alg) == 1) then
            associate (id => iwork(lid + 1:lid + neq))
                if (any(id /= 1 .and. id /= -1)) then
                    msg = 'INFO(11) = 1 or INFO(16) = 1: IWORK('//format_int(lid)//' + I) must be +1 (differential)'// &
                          ' or -1 (algebraic), got '//format_int(id(findloc(id /= 1 .and. id /= -1, .true., 1)))// &
                          ' at I = '//format_int(findloc(id /= 1 .and. id /= -1, .true., 1))
                    return
                end if
                opts%algebraic = (id == -1)
            end associate
        end if
        select case (info(info_initial))
        case (1)
            opts%initial = initial_algebraic
        case (2)
            opts%initial = initial_from_slope
        case default
            opts%initial = initial_given
        end select
        opts%suppress_alg = (info(info_exclude_alg) == 1)
        call check_residual_options(opts, neq, stat, msg)
        if (stat /= regdae_success) msg = 'the options: '//msg
    end subroutine options_from

end module regdae_ddaskr_input
