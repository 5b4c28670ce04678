!> DREGDAE, DREGDAEM, DREGDAEMSG, DREGDAEFREE: the entry points for FORTRAN 77
!! codes, in the manner of DASSL (Petzold, SAND82-8637, 1982). External
!! subroutines (no module needed: a FORTRAN 77 program calls them with implicit
!! interfaces) over `regdae_dassl`, where the work is done. The full description
!! (INFO, RWORK, IWORK, IDID) is doc/api.md, "FORTRAN 77 interface (DREGDAE)".
!!
!!     CALL DREGDAE (F, B, G, GX, GT, N, M, T, X, Y, TOUT, INFO, RTOL, ATOL,
!!    *              IDID, RWORK, LRW, IWORK, LIW, RPAR, IPAR)
!!     CALL DREGDAEM (MASS, FORCES, G, GX, GT, N, M, T, Q, V, LAMBDA, TOUT,
!!    *               INFO, RTOL, ATOL, IDID, RWORK, LRW, IWORK, LIW, RPAR, IPAR)
!!     CALL DREGDAER (F, B, G, GX, GT, N, M, T, X, Y, TOUT, INFO, RTOL, ATOL,
!!    *               IDID, RWORK, LRW, IWORK, LIW, RPAR, IPAR, RT, NRT, JROOT)
!!     CALL DREGDAEMR (..., as DREGDAEM ..., RT, NRT, JROOT)   (events: IDID = 5 at a root)
!!     CALL DREGDAEJ (..., as DREGDAE ..., JAC)    (INFO(5) = 1: JAC gives df/dx)
!!     CALL DREGDAEMJ (..., as DREGDAEM ..., JAC)  (INFO(5) = 1: JAC gives df/dq, df/dq')
!!     CALL DREGDAEJR (..., as DREGDAE ..., JAC, RT, NRT, JROOT)    (both, in DDASKR's order)
!!     CALL DREGDAEMJR (..., as DREGDAEM ..., JAC, RT, NRT, JROOT)
!!     CALL DREGDAEMSG (IWORK, LIW, MSG)
!!     CALL DREGDAEFREE (IWORK, LIW)
!!
!! Problems: DREGDAE solves x' = f(x, t) - B(x, t) y, 0 = g(x, t) (paper, eq. 2.1);
!! DREGDAEM solves M(q) q'' = f(q, q', t) + G^T lambda, 0 = g(q, t) (eq. 1.2).
!! User routines (declared EXTERNAL by the caller; IRES = 0 on entry, -1: try a
!! smaller step, other nonzero values: stop with IDID = -11; messages name them as
!! this argument list does, e.g. "G returned IRES = -2 at t = ..."):
!!     SUBROUTINE F(T, X, FX, IRES, RPAR, IPAR)       FX(N)     = f(x, t)
!!     SUBROUTINE B(T, X, BX, IRES, RPAR, IPAR)       BX(N, M)  = B(x, t)
!!     SUBROUTINE G(T, X, GV, IRES, RPAR, IPAR)       GV(M)     = g(x, t)
!!     SUBROUTINE GX(T, X, GM, IRES, RPAR, IPAR)      GM(M, N)  = dg/dx
!!     SUBROUTINE GT(T, X, GTV, IRES, RPAR, IPAR)     GTV(M)    = dg/dt (INFO(17) = 1)
!!     SUBROUTINE MASS(T, Q, AM, IRES, RPAR, IPAR)    AM(N, N)  = M(q, t)
!!     SUBROUTINE FORCES(T, Q, V, FV, IRES, RPAR, IPAR)  FV(N)  = f(q, q', t)
!!     SUBROUTINE JAC(T, X, PD, IRES, RPAR, IPAR)     PD(N, N)  = df/dx        (DREGDAEJ)
!!     SUBROUTINE JAC(T, Q, V, PD, IRES, RPAR, IPAR)  PD(N, 2N) = [df/dq, df/dq'] (DREGDAEMJ)

!> Integrate x' = f(x, t) - B(x, t) y, 0 = g(x, t) from T to TOUT.
subroutine dregdae(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, rpar, ipar)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_first_order
    use regdae_f77_routines, only: f77_point_routine
    implicit none
    procedure(f77_point_routine) :: f, b, g, gx, gt   !! the user's routines (GT read when INFO(17) = 1)
    integer, intent(in) :: n                          !! size of x
    integer, intent(in) :: m                          !! number of constraints and multipliers
    real(wp), intent(inout) :: t                      !! the time: t0 at the first call; on return TOUT
                                                      !! (success) or the time reached (failure)
    real(wp), intent(inout) :: x(*)                   !! x(t0) at the first call; on return x(T)
    real(wp), intent(inout) :: y(*)                   !! on return y(T), length M
    real(wp), intent(in) :: tout                      !! the next output time (> T)
    integer, intent(inout) :: info(*)                 !! INFO(20): the options (doc/api.md)
    real(wp), intent(in) :: rtol(*), atol(*)          !! relative and absolute tolerance (INFO(2) = 1: vectors of length N)
    integer, intent(out) :: idid                      !! 2 or 3: success; 4: x valid, y undefined; 6: success with
                                                      !! the warning regdae_warn_unresolved; 1: a step's end
                                                      !! (INFO(3) = 1); 5: a root (DREGDAER); < 0: failure
    real(wp), intent(inout) :: rwork(*)               !! RWORK(LRW), LRW >= 20
    integer, intent(in) :: lrw                        !! declared length of RWORK
    integer, intent(inout) :: iwork(*)                !! IWORK(LIW), LIW >= 22; holds the solver between calls
    integer, intent(in) :: liw                        !! declared length of IWORK
    real(wp), intent(inout) :: rpar(*)                !! passed to the user's routines
    integer, intent(inout) :: ipar(*)                 !! passed to the user's routines
    call dassl_first_order(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, &
                           rpar, ipar)
end subroutine dregdae

!> Integrate M(q) q'' = f(q, q', t) + G^T lambda, 0 = g(q, t) from T to TOUT.
subroutine dregdaem(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                    iwork, liw, rpar, ipar)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_mechanical
    use regdae_f77_routines, only: f77_point_routine, f77_motion_routine
    implicit none
    procedure(f77_point_routine) :: mass, g, gx, gt   !! the user's routines (GT read when INFO(17) = 1)
    procedure(f77_motion_routine) :: forces           !! the applied forces f(q, q', t)
    integer, intent(in) :: n                          !! number of coordinates
    integer, intent(in) :: m                          !! number of constraints
    real(wp), intent(inout) :: t                      !! as for DREGDAE
    real(wp), intent(inout) :: q(*)                   !! q(t0) at the first call; on return q(T)
    real(wp), intent(inout) :: v(*)                   !! q'(t0) at the first call; on return q'(T)
    real(wp), intent(inout) :: lambda(*)              !! on return lambda(T), length M
    real(wp), intent(in) :: tout
    integer, intent(inout) :: info(*)
    real(wp), intent(in) :: rtol(*), atol(*)          !! on q and q' (INFO(2) = 1: vectors of length 2N, q then q')
    integer, intent(out) :: idid
    real(wp), intent(inout) :: rwork(*)
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)
    integer, intent(inout) :: ipar(*)
    call dassl_mechanical(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                          iwork, liw, rpar, ipar)
end subroutine dregdaem

!> DREGDAE with root finding in DDASKR's manner: the NRT event functions of RT,
!! CALL RT(N, T, X, X, NRT, RVAL, RPAR, IPAR) (e_i(t, x)); at a root IDID = 5, T the
!! root, X and Y there, JROOT(i) = +1 / -1 / 0 (a root of function i there,
!! increasing / decreasing, none); the next call (INFO(1) = 1) goes on from it.
subroutine dregdaer(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, rpar, ipar, &
                    rt, nrt, jroot)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_first_order
    use regdae_f77_routines, only: f77_point_routine, f77_root_routine
    implicit none
    procedure(f77_point_routine) :: f, b, g, gx, gt   !! as for DREGDAE
    integer, intent(in) :: n, m
    real(wp), intent(inout) :: t, x(*), y(*)
    real(wp), intent(in) :: tout
    integer, intent(inout) :: info(*)
    real(wp), intent(in) :: rtol(*), atol(*)
    integer, intent(out) :: idid                      !! as for DREGDAE, and 5: a root of RT at T
    real(wp), intent(inout) :: rwork(*)
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)
    integer, intent(inout) :: ipar(*)
    procedure(f77_root_routine) :: rt                 !! the event functions
    integer, intent(in) :: nrt                        !! their number (>= 0; read at INFO(1) = 0)
    integer, intent(out) :: jroot(*)                  !! IDID = 5: JROOT(NRT), +1, -1 or 0 each
    call dassl_first_order(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, &
                           rpar, ipar, rt, nrt, jroot)
end subroutine dregdaer

!> DREGDAEM with root finding: RT(N, T, Q, V, NRT, RVAL, RPAR, IPAR), NRT, JROOT
!! as for DREGDAER (e_i(t, q, q')).
subroutine dregdaemr(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                     iwork, liw, rpar, ipar, rt, nrt, jroot)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_mechanical
    use regdae_f77_routines, only: f77_point_routine, f77_motion_routine, f77_root_routine
    implicit none
    procedure(f77_point_routine) :: mass, g, gx, gt   !! as for DREGDAEM
    procedure(f77_motion_routine) :: forces
    integer, intent(in) :: n, m
    real(wp), intent(inout) :: t, q(*), v(*), lambda(*)
    real(wp), intent(in) :: tout
    integer, intent(inout) :: info(*)
    real(wp), intent(in) :: rtol(*), atol(*)
    integer, intent(out) :: idid                      !! as for DREGDAEM, and 5: a root of RT at T
    real(wp), intent(inout) :: rwork(*)
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)
    integer, intent(inout) :: ipar(*)
    procedure(f77_root_routine) :: rt
    integer, intent(in) :: nrt
    integer, intent(out) :: jroot(*)
    call dassl_mechanical(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                          iwork, liw, rpar, ipar, rt, nrt, jroot)
end subroutine dregdaemr

!> DREGDAE with JAC after IPAR, as DASSL's: with INFO(5) = 1, PD = df/dx of F, the
!! Jacobian of f(x, t) in x (not of regdae's regularized residual, which regdae forms:
!! JAC takes the place of the difference quotients of F in it); INFO(5) = 0: JAC is
!! not called. RWORK(19) = 1 checks PD against difference quotients at the start.
subroutine dregdaej(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, rpar, ipar, &
                    jac)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_first_order
    use regdae_f77_routines, only: f77_point_routine
    implicit none
    procedure(f77_point_routine) :: f, b, g, gx, gt   !! as for DREGDAE
    integer, intent(in) :: n, m
    real(wp), intent(inout) :: t, x(*), y(*)
    real(wp), intent(in) :: tout
    integer, intent(inout) :: info(*)
    real(wp), intent(in) :: rtol(*), atol(*)
    integer, intent(out) :: idid                      !! as for DREGDAE; -116: JAC failed the check
    real(wp), intent(inout) :: rwork(*)
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)
    integer, intent(inout) :: ipar(*)
    procedure(f77_point_routine) :: jac               !! JAC(T, X, PD, IRES, RPAR, IPAR), PD(N, N) = df/dx
    call dassl_first_order(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, &
                           rpar, ipar, jac=jac)
end subroutine dregdaej

!> DREGDAEM with JAC after IPAR: with INFO(5) = 1, PD(N, 2N) = [df/dq, df/dq'], the
!! Jacobians of the forces f(q, q', t) (columns 1 to N: in q; N+1 to 2N: in q').
subroutine dregdaemj(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                     iwork, liw, rpar, ipar, jac)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_mechanical
    use regdae_f77_routines, only: f77_point_routine, f77_motion_routine
    implicit none
    procedure(f77_point_routine) :: mass, g, gx, gt   !! as for DREGDAEM
    procedure(f77_motion_routine) :: forces
    integer, intent(in) :: n, m
    real(wp), intent(inout) :: t, q(*), v(*), lambda(*)
    real(wp), intent(in) :: tout
    integer, intent(inout) :: info(*)
    real(wp), intent(in) :: rtol(*), atol(*)
    integer, intent(out) :: idid                      !! as for DREGDAEM; -116: JAC failed the check
    real(wp), intent(inout) :: rwork(*)
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)
    integer, intent(inout) :: ipar(*)
    procedure(f77_motion_routine) :: jac              !! JAC(T, Q, V, PD, IRES, RPAR, IPAR), PD(N, 2N)
    call dassl_mechanical(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                          iwork, liw, rpar, ipar, jac=jac)
end subroutine dregdaemj

!> DREGDAEJ with root finding (JAC, then RT, NRT, JROOT as DDASKR orders them): JAC
!! as for DREGDAEJ, RT, NRT and JROOT as for DREGDAER.
subroutine dregdaejr(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, rpar, &
                     ipar, jac, rt, nrt, jroot)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_first_order
    use regdae_f77_routines, only: f77_point_routine, f77_root_routine
    implicit none
    procedure(f77_point_routine) :: f, b, g, gx, gt   !! as for DREGDAE
    integer, intent(in) :: n, m
    real(wp), intent(inout) :: t, x(*), y(*)
    real(wp), intent(in) :: tout
    integer, intent(inout) :: info(*)
    real(wp), intent(in) :: rtol(*), atol(*)
    integer, intent(out) :: idid                      !! as for DREGDAER and DREGDAEJ
    real(wp), intent(inout) :: rwork(*)
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)
    integer, intent(inout) :: ipar(*)
    procedure(f77_point_routine) :: jac               !! as for DREGDAEJ
    procedure(f77_root_routine) :: rt                 !! as for DREGDAER
    integer, intent(in) :: nrt
    integer, intent(out) :: jroot(*)
    call dassl_first_order(f, b, g, gx, gt, n, m, t, x, y, tout, info, rtol, atol, idid, rwork, lrw, iwork, liw, &
                           rpar, ipar, rt, nrt, jroot, jac)
end subroutine dregdaejr

!> DREGDAEMJ with root finding: JAC as for DREGDAEMJ, RT, NRT, JROOT as for DREGDAEMR.
subroutine dregdaemjr(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                      iwork, liw, rpar, ipar, jac, rt, nrt, jroot)
    use regdae_kinds, only: wp
    use regdae_dassl, only: dassl_mechanical
    use regdae_f77_routines, only: f77_point_routine, f77_motion_routine, f77_root_routine
    implicit none
    procedure(f77_point_routine) :: mass, g, gx, gt   !! as for DREGDAEM
    procedure(f77_motion_routine) :: forces
    integer, intent(in) :: n, m
    real(wp), intent(inout) :: t, q(*), v(*), lambda(*)
    real(wp), intent(in) :: tout
    integer, intent(inout) :: info(*)
    real(wp), intent(in) :: rtol(*), atol(*)
    integer, intent(out) :: idid                      !! as for DREGDAEMR and DREGDAEMJ
    real(wp), intent(inout) :: rwork(*)
    integer, intent(in) :: lrw
    integer, intent(inout) :: iwork(*)
    integer, intent(in) :: liw
    real(wp), intent(inout) :: rpar(*)
    integer, intent(inout) :: ipar(*)
    procedure(f77_motion_routine) :: jac              !! as for DREGDAEMJ
    procedure(f77_root_routine) :: rt                 !! as for DREGDAEMR
    integer, intent(in) :: nrt
    integer, intent(out) :: jroot(*)
    call dassl_mechanical(mass, forces, g, gx, gt, n, m, t, q, v, lambda, tout, info, rtol, atol, idid, rwork, lrw, &
                          iwork, liw, rpar, ipar, rt, nrt, jroot, jac)
end subroutine dregdaemjr

!> The message of the last DREGDAE or DREGDAEM call on the problem of IWORK
!! (blank after success), cut or blank-padded to the length of MSG.
subroutine dregdaemsg(iwork, liw, msg)
    use regdae_dassl, only: dassl_message
    implicit none
    integer, intent(in) :: iwork(*)      !! the problem's IWORK
    integer, intent(in) :: liw           !! its declared length
    character(len=*), intent(out) :: msg !! the message
    call dassl_message(iwork, liw, msg)
end subroutine dregdaemsg

!> Free what IWORK holds: the solver, or after a refused start its message (call it
!! when a problem is done, whatever IDID was; a start with INFO(1) = 0 on the same
!! IWORK frees it too).
subroutine dregdaefree(iwork, liw)
    use regdae_dassl, only: dassl_free
    implicit none
    integer, intent(inout) :: iwork(*)   !! the problem's IWORK
    integer, intent(in) :: liw           !! its declared length
    call dassl_free(iwork, liw)
end subroutine dregdaefree
