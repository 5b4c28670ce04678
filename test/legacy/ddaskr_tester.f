C     Tests of the DDASKR door (DREGDASKR, DREGDASKRMSG, DREGDASKRFREE),
C     written as a DDASKR user writes a program (-std=legacy).
C     DDASKR_TESTER SUITE runs one suite, DDASKR_TESTER all; prints one
C     line per failed check and 'N PASSED, N FAILED'; STOP 1 on a failure.
C
C     The heat problem: NEQ = 21 points on [0, 1], u(0) = u(1) = 0 as
C     algebraic equations, u_i' = (u_(i-1) - 2 u_i + u_(i+1))/dx**2 else;
C     its exact solution exp(-lam t) sin(pi x_i), lam = 4/dx**2
C     sin(pi dx/2)**2 (exact for the semi-discrete system).
C
C     BAND     INFO(6) = 1 (ML = MU = 1) against the dense matrix, with
C              IDA's difference quotients and with a user JAC in each
C              storage: all within 50 RTOL of the exact solution, band
C              and dense with JAC within 1E-12 of each other
C     RTOLV    INFO(2) = 1: equal entries give the scalar run bit for
C              bit; RTOL(11) = 1E-10 (the rest 1E-4) makes y(11) at
C              least 100 times more accurate than with 1E-4 everywhere
C     KRYLOV   INFO(12) = 1 and INFO(17) = 1 refused with IDID = -33 and
C              a message that says why; nothing allocated (IWORK(37)
C              holds no mark); INFO(1) = 1 without a start refused; TOUT
C              = T refused; a negative RTOL refused; ATOL = 0 where Y = 0:
C              IDID = -3, the message names the component
C     IC       INFO(11) = 1 with the ID array (the pendulum of
C              drivers/example_ddaskr.f, lambda and y' guessed 0) and
C              INFO(14) = 1: IDID = 4 with lambda = g cos(theta0) and
C              the consistent y' to 1E-10; the next call (INFO(11) = 0)
C              integrates
C     IRES     IRES = -1 once (a smaller step, the run succeeds), IRES
C              = -2 after t = 0.05: IDID = -11, the message names RES
C     TSTOP    INFO(4) = 1, TSTOP = TOUT: IDID = 2 and T = TSTOP exactly
C     TWO      two heat problems interleaved (different tolerances) give
C              what each gives alone, bit for bit
C     NONNEG   INFO(10) = 2 on Robertson's kinetics (y3 algebraic,
C              INFO(2) = 1, RTOL = 1E-4) with INFO(3) = 1 to T = 4E10:
C              IDA's constraints in force (another run than INFO(10) =
C              0, fewer convergence failures), every step end >= -0.1
C              ATOL (measured: two step ends at -3.0E-8 and -3.8E-8,
C              accepted by IDA), y1 + y2 + y3 = 1 to 1E-6 (IDA's Newton
C              test; measured 5.9E-9); a negative start refused (-33)
C     RESTART  INFO(1) = 0 again on the same IWORK without DREGDASKRFREE
C              gives the same run bit for bit (ctest
C              valgrind.ddaskr_restart: no leak)
      PROGRAM DKTEST
      IMPLICIT NONE
      CHARACTER*16 SUITE
      INTEGER NPASS, NFAIL
      COMMON /COUNT/ NPASS, NFAIL
      NPASS = 0
      NFAIL = 0
      SUITE = ' '
      IF (COMMAND_ARGUMENT_COUNT() .GE. 1) CALL GET_COMMAND_ARGUMENT(1,
     *   SUITE)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'BAND') CALL TBAND
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'RTOLV') CALL TRTOLV
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'KRYLOV') CALL TKRYL
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'IC') CALL TIC
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'IRES') CALL TIRES
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'TSTOP') CALL TTSTOP
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'TWO') CALL TTWO
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'NONNEG') CALL TNONNG
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'RESTART') CALL TRESTA
      WRITE (*, '(I4, A, I4, A)') NPASS, ' passed, ', NFAIL, ' failed'
      IF (NFAIL .GT. 0 .OR. NPASS .EQ. 0) STOP 1
      END

C     Count a check; print its name if it failed.
      SUBROUTINE CHECK(OK, NAME)
      IMPLICIT NONE
      LOGICAL OK
      CHARACTER*(*) NAME
      INTEGER NPASS, NFAIL
      COMMON /COUNT/ NPASS, NFAIL
      IF (OK) THEN
         NPASS = NPASS + 1
      ELSE
         NFAIL = NFAIL + 1
         WRITE (*, '(2A)') 'FAILED: ', NAME
      END IF
      END

C     The heat problem from T = 0 to 0.1 (outputs every 0.01): IBAND = 1
C     band (ML = MU = 1), IJAC = 1 a user JAC, IVEC = 1 vector RTOL,
C     ATOL. Returns Y at 0.1, the largest error against the exact
C     solution, IWORK(11) and the last IDID.
      SUBROUTINE HEAT(IBAND, IJAC, IVEC, RTOL, ATOL, Y, ERR, NST, IDID)
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 21, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER IBAND, IJAC, IVEC, NST, IDID, INFO(20), IWORK(LIW),
     *   IPAR(1), JROOT(1), I, K
      DOUBLE PRECISION RTOL(*), ATOL(*), Y(NEQ), ERR, YP(NEQ),
     *   RWORK(LRW), RPAR(1), T, TOUT, HEXACT
      EXTERNAL HRES, HJAC, HJACB, PSOL, RTNONE
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      CALL IZERO(IWORK, LIW)
      INFO(2) = IVEC
      INFO(5) = IJAC
      INFO(6) = IBAND
      IWORK(1) = 1
      IWORK(2) = 1
      IPAR(1) = NEQ
      CALL HINIT(NEQ, Y, YP)
      T = 0.0D0
      DO 30 K = 1, 10
         TOUT = 0.01D0*K
         IF (IBAND .EQ. 1) THEN
            CALL DREGDASKR(HRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL,
     *         IDID, RWORK, LRW, IWORK, LIW, RPAR, IPAR, HJACB, PSOL,
     *         RTNONE, 0, JROOT)
         ELSE
            CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *         RWORK, LRW, IWORK, LIW, IPAR)
         END IF
         IF (IDID .LT. 0) GO TO 40
   30 CONTINUE
   40 ERR = 0.0D0
      DO 50 I = 1, NEQ
         ERR = MAX(ERR, ABS(Y(I) - HEXACT(I, NEQ, T)))
   50 CONTINUE
      NST = IWORK(11)
      CALL DREGDASKRFREE(IWORK, LIW)
      END

C     The exact solution of the heat problem, component I at T.
      DOUBLE PRECISION FUNCTION HEXACT(I, NEQ, T)
      IMPLICIT NONE
      INTEGER I, NEQ
      DOUBLE PRECISION T, PI, DX, LAM
      PI = 4.0D0*ATAN(1.0D0)
      DX = 1.0D0/(NEQ - 1)
      LAM = 4.0D0/DX**2*SIN(PI*DX/2.0D0)**2
      HEXACT = EXP(-LAM*T)*SIN(PI*(I - 1)*DX)
      IF (I .EQ. 1 .OR. I .EQ. NEQ) HEXACT = 0.0D0
      END

C     Consistent initial values of the heat problem.
      SUBROUTINE HINIT(NEQ, Y, YP)
      IMPLICIT NONE
      INTEGER NEQ, I
      DOUBLE PRECISION Y(NEQ), YP(NEQ), HEXACT, PI, DX, LAM
      PI = 4.0D0*ATAN(1.0D0)
      DX = 1.0D0/(NEQ - 1)
      LAM = 4.0D0/DX**2*SIN(PI*DX/2.0D0)**2
      DO 10 I = 1, NEQ
         Y(I) = HEXACT(I, NEQ, 0.0D0)
         YP(I) = -LAM*Y(I)
   10 CONTINUE
      END

      SUBROUTINE HRES(T, Y, YP, CJ, DELTA, IRES, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER IRES, IPAR(*), I, N
      DOUBLE PRECISION T, Y(*), YP(*), CJ, DELTA(*), RPAR(*), DX2
      N = IPAR(1)
      DX2 = (1.0D0/(N - 1))**2
      DELTA(1) = Y(1)
      DELTA(N) = Y(N)
      DO 10 I = 2, N - 1
         DELTA(I) = YP(I) - (Y(I-1) - 2.0D0*Y(I) + Y(I+1))/DX2
   10 CONTINUE
      END

C     The dense PD = dF/dY + CJ dF/dYPRIME of the heat problem.
      SUBROUTINE HJAC(T, Y, YP, PD, CJ, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER IPAR(*), I, N
      DOUBLE PRECISION T, Y(*), YP(*), PD(IPAR(1), *), CJ, RPAR(*),
     *   DX2
      N = IPAR(1)
      DX2 = (1.0D0/(N - 1))**2
      PD(1, 1) = 1.0D0
      PD(N, N) = 1.0D0
      DO 10 I = 2, N - 1
         PD(I, I - 1) = -1.0D0/DX2
         PD(I, I) = CJ + 2.0D0/DX2
         PD(I, I + 1) = -1.0D0/DX2
   10 CONTINUE
      END

C     The same in band storage, ML = MU = 1: (I, J) in row I - J + 3.
      SUBROUTINE HJACB(T, Y, YP, PD, CJ, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER IPAR(*), I, N
      DOUBLE PRECISION T, Y(*), YP(*), PD(4, *), CJ, RPAR(*), DX2
      N = IPAR(1)
      DX2 = (1.0D0/(N - 1))**2
      PD(3, 1) = 1.0D0
      PD(3, N) = 1.0D0
      DO 10 I = 2, N - 1
         PD(4, I - 1) = -1.0D0/DX2
         PD(3, I) = CJ + 2.0D0/DX2
         PD(2, I + 1) = -1.0D0/DX2
   10 CONTINUE
      END

C     One DREGDASKR call on the heat problem (dense, JAC when INFO(5)
C     = 1, no events).
      SUBROUTINE HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, IPAR)
      IMPLICIT NONE
      INTEGER NEQ, INFO(20), IDID, LRW, IWORK(*), LIW, IPAR(*),
     *   JROOT(1)
      DOUBLE PRECISION T, Y(*), YP(*), TOUT, RTOL(*), ATOL(*),
     *   RWORK(*), RPAR(1)
      EXTERNAL HRES, HJAC, PSOL, RTNONE
      CALL DREGDASKR(HRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, RPAR, IPAR, HJAC, PSOL, RTNONE, 0,
     *   JROOT)
      END

C     IWORK zeroed: DREGDASKR reads IWORK(37:40) at a start to find the
C     solver of an earlier one (any content works; zeros keep valgrind
C     from reporting the read of uninitialized words).
      SUBROUTINE IZERO(IWORK, LIW)
      INTEGER LIW, IWORK(LIW), I
      DO 10 I = 1, LIW
         IWORK(I) = 0
   10 CONTINUE
      END

      SUBROUTINE RTNONE(NEQ, T, Y, YP, NRT, RVAL, RPAR, IPAR)
      INTEGER NEQ, NRT, IPAR(*)
      DOUBLE PRECISION T, Y(*), YP(*), RVAL(*), RPAR(*)
      END

      SUBROUTINE PSOL
      END

C     ------------------------------------------------------------------
      SUBROUTINE TBAND
      IMPLICIT NONE
      INTEGER NST(4), IDID(4), I, K
      DOUBLE PRECISION RTOL(1), ATOL(1), Y(21, 4), ERR(4), D
      RTOL(1) = 1.0D-8
      ATOL(1) = 1.0D-10
      CALL HEAT(0, 0, 0, RTOL, ATOL, Y(1, 1), ERR(1), NST(1), IDID(1))
      CALL HEAT(1, 0, 0, RTOL, ATOL, Y(1, 2), ERR(2), NST(2), IDID(2))
      CALL HEAT(0, 1, 0, RTOL, ATOL, Y(1, 3), ERR(3), NST(3), IDID(3))
      CALL HEAT(1, 1, 0, RTOL, ATOL, Y(1, 4), ERR(4), NST(4), IDID(4))
      DO 10 K = 1, 4
         CALL CHECK(IDID(K) .EQ. 3, 'BAND: IDID = 3 at TOUT')
         CALL CHECK(ERR(K) .LE. 50.0D0*RTOL(1),
     *      'BAND: within 50 RTOL of the exact solution')
   10 CONTINUE
      D = 0.0D0
      DO 20 I = 1, 21
         D = MAX(D, ABS(Y(I, 3) - Y(I, 4)))
   20 CONTINUE
      CALL CHECK(D .LE. 1.0D-12, 'BAND: band JAC = dense JAC')
      WRITE (*, '(A, 4ES9.2, A, ES9.2, A, 4I5)') ' BAND: errors',
     *   ERR, '  |band - dense| (JAC)', D, '  steps', NST
      END

C     ------------------------------------------------------------------
      SUBROUTINE TRTOLV
      IMPLICIT NONE
      INTEGER NST(4), IDID(4), I
      DOUBLE PRECISION RS(1), AS(1), RV(21), AV(21), Y(21, 4), ERR(4),
     *   HEXACT, E1, E2
      LOGICAL SAME
      RS(1) = 1.0D-6
      AS(1) = 1.0D-9
      DO 10 I = 1, 21
         RV(I) = RS(1)
         AV(I) = AS(1)
   10 CONTINUE
      CALL HEAT(0, 0, 0, RS, AS, Y(1, 1), ERR(1), NST(1), IDID(1))
      CALL HEAT(0, 0, 1, RV, AV, Y(1, 2), ERR(2), NST(2), IDID(2))
      SAME = NST(1) .EQ. NST(2)
      DO 20 I = 1, 21
         SAME = SAME .AND. Y(I, 1) .EQ. Y(I, 2)
   20 CONTINUE
      CALL CHECK(SAME, 'RTOLV: equal entries = the scalar run')
      DO 30 I = 1, 21
         RV(I) = 1.0D-4
   30 CONTINUE
      CALL HEAT(0, 0, 1, RV, AV, Y(1, 3), ERR(3), NST(3), IDID(3))
      RV(11) = 1.0D-10
      CALL HEAT(0, 0, 1, RV, AV, Y(1, 4), ERR(4), NST(4), IDID(4))
      E1 = ABS(Y(11, 3) - HEXACT(11, 21, 0.1D0))
      E2 = ABS(Y(11, 4) - HEXACT(11, 21, 0.1D0))
      CALL CHECK(IDID(3) .EQ. 3 .AND. IDID(4) .EQ. 3,
     *   'RTOLV: IDID = 3')
      CALL CHECK(E2 .LE. 0.01D0*E1,
     *   'RTOLV: RTOL(11) = 1E-10 makes Y(11) 100 times more accurate')
      WRITE (*, '(A, 2ES9.2, A, 2I5)') ' RTOLV: error of Y(11)', E1, E2,
     *   '  steps', NST(3), NST(4)
      END

C     ------------------------------------------------------------------
      SUBROUTINE TKRYL
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 21, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), JROOT(1), IDID, I
      DOUBLE PRECISION Y(NEQ), YP(NEQ), RWORK(LRW), RPAR(1), T, TOUT,
     *   RTOL(1), ATOL(1)
      CHARACTER*300 MSG
      EXTERNAL HRES, HJAC, PSOL, RTNONE
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      CALL IZERO(IWORK, LIW)
      DO 15 I = 1, LIW
         IWORK(I) = 0
   15 CONTINUE
      INFO(20) = -1
      IPAR(1) = NEQ
      RTOL(1) = 1.0D-6
      ATOL(1) = 1.0D-6
      CALL HINIT(NEQ, Y, YP)
      T = 0.0D0
      TOUT = 0.1D0
      INFO(12) = 1
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. -33, 'KRYLOV: INFO(12) = 1 gives -33')
      CALL CHECK(IWORK(37) .EQ. 0, 'KRYLOV: nothing allocated')
      CALL CHECK(INFO(1) .EQ. -1, 'KRYLOV: INFO(1) = -1 after it')
      CALL DREGDASKRMSG(IWORK, LIW, MSG)
      CALL CHECK(INDEX(MSG, 'refused') .GT. 0,
     *   'KRYLOV: DREGDASKRMSG says the start was refused')
C     the message printed on unit 6 (INFO(20) = 6) names Krylov
      INFO(1) = 0
      INFO(20) = 6
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      INFO(20) = -1
      INFO(1) = 0
      INFO(12) = 0
      INFO(17) = 1
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. -33, 'KRYLOV: INFO(17) = 1 gives -33')
      INFO(17) = 0
      INFO(1) = 1
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. -33, 'KRYLOV: INFO(1) = 1 without a start')
      CALL DREGDASKRMSG(IWORK, LIW, MSG)
      CALL CHECK(INDEX(MSG, 'holds no solver') .GT. 0,
     *   'KRYLOV: its message')
      INFO(1) = 0
      CALL HCALL(NEQ, T, Y, YP, T, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. -33, 'KRYLOV: TOUT = T refused')
      INFO(1) = 0
      RTOL(1) = -1.0D0
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. -33, 'KRYLOV: RTOL < 0 refused')
      CALL CHECK(IWORK(37) .EQ. 0, 'KRYLOV: still nothing allocated')
C     ATOL = 0 and Y(1) = 0 (the boundary): no error weight, IDID = -3
      INFO(1) = 0
      RTOL(1) = 1.0D-6
      ATOL(1) = 0.0D0
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL DREGDASKRMSG(IWORK, LIW, MSG)
      CALL CHECK(IDID .EQ. -3 .AND. INDEX(MSG, 'component 1') .GT. 0,
     *   'KRYLOV: ATOL = 0 at a zero component gives -3')
      CALL DREGDASKRFREE(IWORK, LIW)
      END

C     ------------------------------------------------------------------
      SUBROUTINE TIC
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 5, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), JROOT(1), IDID, I
      DOUBLE PRECISION Y(NEQ), YP(NEQ), RWORK(LRW), RPAR(1), T, TOUT,
     *   RTOL(1), ATOL(1), G, PI, E
      EXTERNAL PRES, PJAC, PSOL, RTNONE
      G = 9.81D0
      PI = 4.0D0*ATAN(1.0D0)
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      CALL IZERO(IWORK, LIW)
      INFO(5) = 1
      INFO(11) = 1
      INFO(14) = 1
      INFO(20) = -1
      DO 20 I = 1, 4
         IWORK(40 + I) = 1
   20 CONTINUE
      IWORK(45) = -1
      RTOL(1) = 1.0D-8
      ATOL(1) = 1.0D-8
      Y(1) = SIN(PI/3.0D0)
      Y(2) = -COS(PI/3.0D0)
      DO 30 I = 3, 5
         Y(I) = 0.0D0
   30 CONTINUE
      DO 40 I = 1, 5
         YP(I) = 0.0D0
   40 CONTINUE
      T = 0.0D0
      TOUT = 0.1D0
      CALL DREGDASKR(PRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, RPAR, IPAR, PJAC, PSOL, RTNONE, 0,
     *   JROOT)
      CALL CHECK(IDID .EQ. 4, 'IC: IDID = 4 after the initial values')
      E = MAX(ABS(Y(5) - G*COS(PI/3.0D0)), ABS(YP(3) + Y(5)*Y(1)),
     *   ABS(YP(4) + Y(5)*Y(2) + G), ABS(Y(1) - SIN(PI/3.0D0)))
      CALL CHECK(E .LE. 1.0D-10, 'IC: lambda and y'' consistent')
      CALL CHECK(T .EQ. 0.0D0, 'IC: T unchanged')
      INFO(11) = 0
      CALL DREGDASKR(PRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, RPAR, IPAR, PJAC, PSOL, RTNONE, 0,
     *   JROOT)
      CALL CHECK(IDID .EQ. 3 .AND. T .EQ. TOUT, 'IC: then integrates')
      CALL DREGDASKRFREE(IWORK, LIW)
      WRITE (*, '(A, ES9.2)') ' IC: largest inconsistency', E
      END

C     The pendulum of drivers/example_ddaskr.f.
      SUBROUTINE PRES(T, Y, YP, CJ, DELTA, IRES, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Y(*), YP(*), CJ, DELTA(*), RPAR(*), G
      PARAMETER (G = 9.81D0)
      DELTA(1) = YP(1) - Y(3)
      DELTA(2) = YP(2) - Y(4)
      DELTA(3) = YP(3) + Y(5)*Y(1)
      DELTA(4) = YP(4) + Y(5)*Y(2) + G
      DELTA(5) = Y(3)**2 + Y(4)**2 - Y(5)*(Y(1)**2 + Y(2)**2) - G*Y(2)
      END

      SUBROUTINE PJAC(T, Y, YP, PD, CJ, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER IPAR(*)
      DOUBLE PRECISION T, Y(*), YP(*), PD(5, 5), CJ, RPAR(*), G
      PARAMETER (G = 9.81D0)
      PD(1, 1) = CJ
      PD(1, 3) = -1.0D0
      PD(2, 2) = CJ
      PD(2, 4) = -1.0D0
      PD(3, 1) = Y(5)
      PD(3, 3) = CJ
      PD(3, 5) = Y(1)
      PD(4, 2) = Y(5)
      PD(4, 4) = CJ
      PD(4, 5) = Y(2)
      PD(5, 1) = -2.0D0*Y(5)*Y(1)
      PD(5, 2) = -2.0D0*Y(5)*Y(2) - G
      PD(5, 3) = 2.0D0*Y(3)
      PD(5, 4) = 2.0D0*Y(4)
      PD(5, 5) = -(Y(1)**2 + Y(2)**2)
      END

C     ------------------------------------------------------------------
C     IRES: the heat problem whose RES says IRES = -1 at its first call
C     beyond T = 0.02 (RPAR(1) counts it) and IRES = -2 beyond T = 0.05
C     when IPAR(2) = 1.
      SUBROUTINE TIRES
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 21, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER INFO(20), IWORK(LIW), IPAR(2), JROOT(1), IDID, I
      DOUBLE PRECISION Y(NEQ), YP(NEQ), RWORK(LRW), RPAR(1), T, TOUT,
     *   RTOL(1), ATOL(1)
      CHARACTER*300 MSG
      EXTERNAL FRES, HJAC, PSOL, RTNONE
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      CALL IZERO(IWORK, LIW)
      INFO(20) = -1
      IPAR(1) = NEQ
      IPAR(2) = 0
      RPAR(1) = 0.0D0
      RTOL(1) = 1.0D-6
      ATOL(1) = 1.0D-6
      CALL HINIT(NEQ, Y, YP)
      T = 0.0D0
      TOUT = 0.1D0
      CALL DREGDASKR(FRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, RPAR, IPAR, HJAC, PSOL, RTNONE, 0,
     *   JROOT)
      CALL CHECK(IDID .EQ. 3 .AND. RPAR(1) .EQ. 1.0D0,
     *   'IRES: IRES = -1 once, then success')
      INFO(1) = 0
      IPAR(2) = 1
      CALL HINIT(NEQ, Y, YP)
      T = 0.0D0
      CALL DREGDASKR(FRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, RPAR, IPAR, HJAC, PSOL, RTNONE, 0,
     *   JROOT)
      CALL DREGDASKRMSG(IWORK, LIW, MSG)
      CALL CHECK(IDID .EQ. -11, 'IRES: IRES = -2 gives IDID = -11')
      CALL CHECK(INDEX(MSG, 'RES returned IRES = -2') .GT. 0,
     *   'IRES: the message names RES')
      CALL CHECK(INFO(1) .EQ. -1, 'IRES: INFO(1) = -1')
      CALL CHECK(T .LE. 0.05D0 + 1.0D-2, 'IRES: T where it stopped')
      CALL DREGDASKRFREE(IWORK, LIW)
      WRITE (*, '(2A)') ' IRES: ', MSG(1:120)
      END

      SUBROUTINE FRES(T, Y, YP, CJ, DELTA, IRES, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Y(*), YP(*), CJ, DELTA(*), RPAR(*)
      IF (T .GT. 0.02D0 .AND. RPAR(1) .EQ. 0.0D0) THEN
         RPAR(1) = 1.0D0
         IRES = -1
         RETURN
      END IF
      IF (IPAR(2) .EQ. 1 .AND. T .GT. 0.05D0) THEN
         IRES = -2
         RETURN
      END IF
      CALL HRES(T, Y, YP, CJ, DELTA, IRES, RPAR, IPAR)
      END

C     ------------------------------------------------------------------
      SUBROUTINE TTSTOP
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 21, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), JROOT(1), IDID, I
      DOUBLE PRECISION Y(NEQ), YP(NEQ), RWORK(LRW), RPAR(1), T, TOUT,
     *   RTOL(1), ATOL(1)
      EXTERNAL HRES, HJAC, PSOL, RTNONE
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      CALL IZERO(IWORK, LIW)
      INFO(4) = 1
      INFO(20) = -1
      IPAR(1) = NEQ
      RTOL(1) = 1.0D-6
      ATOL(1) = 1.0D-6
      CALL HINIT(NEQ, Y, YP)
      T = 0.0D0
      TOUT = 0.0123D0
      RWORK(1) = TOUT
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. 2 .AND. T .EQ. TOUT,
     *   'TSTOP: IDID = 2 at TSTOP exactly')
      CALL CHECK(RWORK(4) .EQ. TOUT, 'TSTOP: RWORK(4) = TN = TSTOP')
      TOUT = 0.02D0
      RWORK(1) = 0.0123D0
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. -33, 'TSTOP: TOUT beyond TSTOP refused')
      INFO(1) = 1
      RWORK(1) = 0.05D0
      CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID, RWORK,
     *   LRW, IWORK, LIW, IPAR)
      CALL CHECK(IDID .EQ. 3 .AND. T .EQ. TOUT,
     *   'TSTOP: a later TSTOP, IDID = 3 at TOUT')
      CALL DREGDASKRFREE(IWORK, LIW)
      END

C     ------------------------------------------------------------------
      SUBROUTINE TTWO
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 21, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER INFO(20, 2), IWORK(LIW, 2), IPAR(1), JROOT(1), IDID(2),
     *   I, K, J, NST(2), ID
      DOUBLE PRECISION Y(NEQ, 2), YP(NEQ, 2), RWORK(LRW, 2), RPAR(1),
     *   T(2), TOUT, RTOL(2), ATOL(2), YA(NEQ, 2), ERR
      LOGICAL SAME
      EXTERNAL HRES, HJAC, PSOL, RTNONE
      RTOL(1) = 1.0D-6
      RTOL(2) = 1.0D-9
      ATOL(1) = 1.0D-9
      ATOL(2) = 1.0D-11
      IPAR(1) = NEQ
C     each alone
      DO 10 J = 1, 2
         CALL HEAT(0, 0, 0, RTOL(J), ATOL(J), YA(1, J), ERR, NST(J), ID)
   10 CONTINUE
C     interleaved
      DO 20 J = 1, 2
         DO 15 I = 1, 20
            INFO(I, J) = 0
   15    CONTINUE
         CALL HINIT(NEQ, Y(1, J), YP(1, J))
         CALL IZERO(IWORK(1, J), LIW)
         T(J) = 0.0D0
   20 CONTINUE
      DO 30 K = 1, 10
         TOUT = 0.01D0*K
         DO 25 J = 1, 2
            CALL DREGDASKR(HRES, NEQ, T(J), Y(1, J), YP(1, J), TOUT,
     *         INFO(1, J), RTOL(J), ATOL(J), IDID(J), RWORK(1, J), LRW,
     *         IWORK(1, J), LIW, RPAR, IPAR, HJAC, PSOL, RTNONE, 0,
     *         JROOT)
   25    CONTINUE
   30 CONTINUE
      SAME = .TRUE.
      DO 40 J = 1, 2
         SAME = SAME .AND. IWORK(11, J) .EQ. NST(J)
         DO 35 I = 1, NEQ
            SAME = SAME .AND. Y(I, J) .EQ. YA(I, J)
   35    CONTINUE
         CALL DREGDASKRFREE(IWORK(1, J), LIW)
   40 CONTINUE
      CALL CHECK(SAME .AND. NST(1) .NE. NST(2),
     *   'TWO: interleaved = alone, bit for bit')
      END

C     ------------------------------------------------------------------
      SUBROUTINE TRESTA
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 21, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), JROOT(1), IDID, I, K, R,
     *   NST(3)
      DOUBLE PRECISION Y(NEQ), YP(NEQ), RWORK(LRW), RPAR(1), T, TOUT,
     *   RTOL(1), ATOL(1), YE(NEQ, 3)
      LOGICAL SAME
      EXTERNAL HRES, HJAC, PSOL, RTNONE
      IPAR(1) = NEQ
      RTOL(1) = 1.0D-7
      ATOL(1) = 1.0D-9
      DO 5 I = 1, 20
         INFO(I) = 0
    5 CONTINUE
      CALL IZERO(IWORK, LIW)
      INFO(20) = -1
      DO 30 R = 1, 3
C        a start on the same IWORK, without DREGDASKRFREE (the second
C        after a refused start)
         IF (R .EQ. 2) THEN
            INFO(1) = 0
            INFO(12) = 1
            CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *         RWORK, LRW, IWORK, LIW, IPAR)
            INFO(12) = 0
         END IF
         INFO(1) = 0
         CALL HINIT(NEQ, Y, YP)
         T = 0.0D0
         DO 20 K = 1, 5
            TOUT = 0.01D0*K
            CALL HCALL(NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *         RWORK, LRW, IWORK, LIW, IPAR)
   20    CONTINUE
         NST(R) = IWORK(11)
         DO 25 I = 1, NEQ
            YE(I, R) = Y(I)
   25    CONTINUE
   30 CONTINUE
      CALL DREGDASKRFREE(IWORK, LIW)
      SAME = NST(1) .EQ. NST(2) .AND. NST(1) .EQ. NST(3)
      DO 40 I = 1, NEQ
         SAME = SAME .AND. YE(I, 1) .EQ. YE(I, 2)
     *        .AND. YE(I, 1) .EQ. YE(I, 3)
   40 CONTINUE
      CALL CHECK(SAME .AND. IDID .EQ. 3,
     *   'RESTART: INFO(1) = 0 again gives the same run')
      END

C     ------------------------------------------------------------------
      SUBROUTINE TNONNG
      IMPLICIT NONE
      INTEGER NEQ, LRW, LIW
      PARAMETER (NEQ = 3, LRW = 60 + 9*NEQ + NEQ**2, LIW = 40 + NEQ)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), JROOT(1), IDID, I, NNEG,
     *   NSTEP
      DOUBLE PRECISION Y(NEQ), YP(NEQ), RWORK(LRW), RPAR(1), T, TOUT,
     *   RTOL(NEQ), ATOL(NEQ), CONS, YMIN
      INTEGER NCFN(2), NSTEPS(2), K
      EXTERNAL RRES, HJAC, PSOL, RTNONE
      DO 50 K = 1, 2
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      CALL IZERO(IWORK, LIW)
      INFO(2) = 1
      INFO(3) = 1
      INFO(10) = 2*(K - 1)
      INFO(20) = -1
      DO 20 I = 1, NEQ
         RTOL(I) = 1.0D-4
   20 CONTINUE
      ATOL(1) = 1.0D-6
      ATOL(2) = 1.0D-10
      ATOL(3) = 1.0D-6
      Y(1) = 1.0D0
      Y(2) = 0.0D0
      Y(3) = 0.0D0
      YP(1) = -0.04D0
      YP(2) = 0.04D0
      YP(3) = 0.0D0
      T = 0.0D0
      TOUT = 4.0D10
      NNEG = 0
      NSTEP = 0
      CONS = 0.0D0
      YMIN = 0.0D0
   30 CALL DREGDASKR(RRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, RPAR, IPAR, HJAC, PSOL, RTNONE, 0,
     *   JROOT)
      IF (IDID .EQ. 1 .OR. IDID .EQ. -1) THEN
         NSTEP = NSTEP + 1
         IF (MIN(Y(1), Y(2), Y(3)) .LT. -0.1D0*ATOL(1)) NNEG = NNEG + 1
         YMIN = MIN(YMIN, Y(1), Y(2), Y(3))
         CONS = MAX(CONS, ABS(Y(1) + Y(2) + Y(3) - 1.0D0))
         INFO(1) = 1
         IF (NSTEP .LT. 100000) GO TO 30
      END IF
      CALL CHECK(IDID .EQ. 3 .AND. T .EQ. TOUT, 'NONNEG: reaches 4E10')
      NCFN(K) = IWORK(15)
      NSTEPS(K) = IWORK(11)
      WRITE (*, '(A, I2, A, I6, A, I4, A, 3ES10.2, 2(A, ES9.2))')
     *   ' NONNEG: INFO(10) =', INFO(10), ' steps', IWORK(11),
     *   ' conv. failures', IWORK(15), '  Y(4E10)', Y, '  |sum - 1|',
     *   CONS, '  min', YMIN
      CALL DREGDASKRFREE(IWORK, LIW)
   50 CONTINUE
      CALL CHECK(NNEG .EQ. 0, 'NONNEG: every step end >= -0.1 ATOL')
      CALL CHECK(CONS .LE. 1.0D-6, 'NONNEG: y1 + y2 + y3 = 1')
      CALL CHECK(NSTEPS(1) .NE. NSTEPS(2) .AND. NCFN(2) .LT. NCFN(1),
     *   'NONNEG: INFO(10) = 2 in force')
      INFO(1) = 0
      INFO(10) = 2
      Y(1) = -1.0D-3
      Y(2) = 0.0D0
      Y(3) = 1.001D0
      T = 0.0D0
      CALL DREGDASKR(RRES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL, IDID,
     *   RWORK, LRW, IWORK, LIW, RPAR, IPAR, HJAC, PSOL, RTNONE, 0,
     *   JROOT)
      CALL CHECK(IDID .EQ. -33, 'NONNEG: a negative start refused')
      CALL DREGDASKRFREE(IWORK, LIW)
      END

C     Robertson's kinetics with the conservation law as its algebraic
C     equation.
      SUBROUTINE RRES(T, Y, YP, CJ, DELTA, IRES, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Y(*), YP(*), CJ, DELTA(*), RPAR(*)
      DELTA(1) = -0.04D0*Y(1) + 1.0D4*Y(2)*Y(3) - YP(1)
      DELTA(2) = 0.04D0*Y(1) - 1.0D4*Y(2)*Y(3) - 3.0D7*Y(2)**2 - YP(2)
      DELTA(3) = Y(1) + Y(2) + Y(3) - 1.0D0
      END
