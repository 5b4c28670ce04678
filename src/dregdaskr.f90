!> DREGDASKR, DREGDASKRMSG, DREGDASKRFREE: DDASKR's calling sequence for FORTRAN 77
!! codes that integrate a general DAE F(t, y, y') = 0 (no regularization: for a
!! mechanism through singular configurations use DREGDAE or DREGDAEM). External
!! subroutines over `regdae_ddaskr`; doc/api.md, "FORTRAN 77 interface for plain DAEs
!! (DREGDASKR)", has INFO, RWORK, IWORK and IDID.
!!
!!     CALL DREGDASKR (RES, NEQ, T, Y, YPRIME, TOUT, INFO, RTOL, ATOL, IDID,
!!    *                RWORK, LRW, IWORK, LIW, RPAR, IPAR, JAC, PSOL, RT, NRT, JROOT)
!!     CALL DREGDASKRMSG (IWORK, LIW, MSG)
!!     CALL DREGDASKRFREE (IWORK, LIW)

!> Integrate F(T, Y, YPRIME) = 0 from T to TOUT, as DDASKR does.
subroutine dregdaskr(res, neq, t, y, yprime, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, rpar, ipar, jac, &
                     psol, rt, nrt, jroot)
    use regdae_kinds, only: wp
    use regdae_ddaskr, only: ddaskr_call
    implicit none
    external :: res, jac, rt                !! RES, JAC (INFO(5) = 1), RT (NRT > 0): DDASKR's argument lists
    external :: psol                        !! DDASKR's PSOL: never called (INFO(12) = 1 is refused)
    integer, intent(in) :: neq              !! number of equations
    real(wp), intent(inout) :: t            !! the time: t0 at the first call; on return the time reached
    real(wp), intent(inout) :: y(*)         !! y(NEQ)
    real(wp), intent(inout) :: yprime(*)    !! y'(NEQ)
    real(wp), intent(in) :: tout            !! the next output time
    integer, intent(inout) :: info(*)       !! INFO(20)
    real(wp), intent(in) :: rtol(*), atol(*)   !! scalars, or (INFO(2) = 1) vectors of length NEQ
    integer, intent(out) :: idid            !! DDASKR's codes (doc/api.md)
    real(wp), intent(inout) :: rwork(*)     !! RWORK(LRW), LRW >= 20
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)      !! IWORK(LIW), LIW >= 40 (+ NEQ per array INFO(10), (11), (16) read)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)      !! passed to RES, JAC, RT
    integer, intent(inout) :: ipar(*)       !! passed to RES, JAC, RT
    integer, intent(in) :: nrt              !! number of event functions of RT (0: none)
    integer, intent(out) :: jroot(*)        !! IDID = 5: JROOT(NRT), +1 / -1 / 0 each
    call ddaskr_call(res, neq, t, y, yprime, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, rpar, ipar, &
                     jac, rt, nrt, jroot)
end subroutine dregdaskr

!> The message of the last DREGDASKR call on IWORK (blank after success), cut or
!! blank-padded to the length of MSG.
subroutine dregdaskrmsg(iwork, liw, msg)
    use regdae_ddaskr, only: ddaskr_message
    implicit none
    integer, intent(in) :: iwork(*)      !! the problem's IWORK
    integer, intent(in) :: liw           !! its declared length
    character(len=*), intent(out) :: msg !! the message
    call ddaskr_message(iwork, liw, msg)
end subroutine dregdaskrmsg

!> Free what IWORK holds (the solver and its message); a start with INFO(1) = 0 on
!! the same IWORK frees it too.
subroutine dregdaskrfree(iwork, liw)
    use regdae_ddaskr, only: ddaskr_free
    implicit none
    integer, intent(inout) :: iwork(*)   !! the problem's IWORK
    integer, intent(in) :: liw           !! its declared length
    call ddaskr_free(iwork, liw)
end subroutine dregdaskrfree
