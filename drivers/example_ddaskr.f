C     A DDASKR program run by DREGDASKR: the pendulum (length 1, g = 9.81,
C     released at rest 60 degrees from the vertical) in index-1 form, F(t,y,y')=0
C     with y = (x, y, u, v, lambda):
C        x' = u,  y' = v,  u' = -lambda x,  v' = -lambda y - g,
C        0 = u**2 + v**2 - lambda (x**2 + y**2) - g y.
C     INFO(3) = 1 (a return after every step), a user JAC (INFO(5) = 1),
C     lambda left out of the error test (INFO(16) = 1), and two event
C     functions: RT = (x, u), roots at the bottom (odd multiples of P/4)
C     and at the turning points (multiples of P/2), P the exact period
C     4 K(sin(pi/6))/sqrt(g) (K by the arithmetic-geometric mean).
C     Checks: each root within 10 RTOL of the exact time, with JROOT's
C     direction; after each period the start within 100 RTOL (measured:
C     6.2 RTOL and 34 RTOL, the global error of the phase). STOP 1 if a
C     check fails.
      PROGRAM PENDKR
      IMPLICIT NONE
      EXTERNAL RES, JAC, PSOL, RT
      INTEGER NEQ, NRT, LRW, LIW
      PARAMETER (NEQ = 5, NRT = 2, LRW = 60 + 9*NEQ + NEQ**2 + 3*NRT,
     *           LIW = 40 + NEQ + NEQ)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), JROOT(NRT), IDID, I, K,
     *        NFAIL, NROOT
      DOUBLE PRECISION Y(NEQ), YP(NEQ), RWORK(LRW), RPAR(1), RTOL,
     *        ATOL, T, TOUT, P, PI, A, B, C, TEX, ERR, G, Y0(4),
     *        ETMAX, EYMAX
      CHARACTER*200 MSG
      G = 9.81D0
      PI = 4.0D0*ATAN(1.0D0)
C     The exact period: K(k) = pi/(2 AGM(1, cos(theta0/2))).
      A = 1.0D0
      B = COS(PI/6.0D0)
      DO 10 I = 1, 8
         C = 0.5D0*(A + B)
         B = SQRT(A*B)
         A = C
   10 CONTINUE
      P = 4.0D0*(PI/(2.0D0*A))/SQRT(G)
      DO 20 I = 1, 20
         INFO(I) = 0
   20 CONTINUE
      INFO(3) = 1
      INFO(5) = 1
      INFO(16) = 1
      DO 30 I = 1, NEQ - 1
         IWORK(40 + I) = 1
   30 CONTINUE
      IWORK(40 + NEQ) = -1
      RTOL = 1.0D-8
      ATOL = 1.0D-8
      T = 0.0D0
C     Consistent initial values: at rest, lambda = g cos(theta0).
      Y(1) = SIN(PI/3.0D0)
      Y(2) = -COS(PI/3.0D0)
      Y(3) = 0.0D0
      Y(4) = 0.0D0
      Y(5) = -G*Y(2)
      YP(1) = 0.0D0
      YP(2) = 0.0D0
      YP(3) = -Y(5)*Y(1)
      YP(4) = -Y(5)*Y(2) - G
      YP(5) = 0.0D0
      DO 35 I = 1, 4
         Y0(I) = Y(I)
   35 CONTINUE
      NFAIL = 0
      NROOT = 0
      ETMAX = 0.0D0
      EYMAX = 0.0D0
      WRITE (*, '(A)') ' pendulum, index 1, DREGDASKR, RTOL = 1E-8'
      WRITE (*, '(A)') ' IDID  T                        X'
     *   // '                        U'
      DO 60 K = 1, 17
         TOUT = K*P/8.0D0
   40    CALL DREGDASKR(RES, NEQ, T, Y, YP, TOUT, INFO, RTOL, ATOL,
     *        IDID, RWORK, LRW, IWORK, LIW, RPAR, IPAR, JAC, PSOL,
     *        RT, NRT, JROOT)
         IF (IDID .LT. 0) THEN
            CALL DREGDASKRMSG(IWORK, LIW, MSG)
            WRITE (*, '(A, I4, 2A)') ' IDID = ', IDID, ': ', MSG
            STOP 1
         END IF
         IF (IDID .EQ. 1) GO TO 40
         WRITE (*, '(I4, 3ES25.16)') IDID, T, Y(1), Y(3)
         IF (IDID .EQ. 5) THEN
            NROOT = NROOT + 1
            IF (JROOT(1) .NE. 0) THEN
               I = NINT((4.0D0*T/P - 1.0D0)/2.0D0)
               TEX = (2*I + 1)*P/4.0D0
               IF (JROOT(1) .NE. (-1)**(I + 1)) NFAIL = NFAIL + 1
            ELSE
               I = NINT(2.0D0*T/P)
               TEX = I*P/2.0D0
               IF (JROOT(2) .NE. (-1)**(I + 1)) NFAIL = NFAIL + 1
            END IF
            ERR = ABS(T - TEX)
            ETMAX = MAX(ETMAX, ERR)
            IF (ERR .GT. 10.0D0*RTOL) NFAIL = NFAIL + 1
            GO TO 40
         END IF
         IF (MOD(K, 8) .EQ. 0) THEN
            DO 50 I = 1, 4
               ERR = ABS(Y(I) - Y0(I))
               EYMAX = MAX(EYMAX, ERR)
               IF (ERR .GT. 100.0D0*RTOL) NFAIL = NFAIL + 1
   50       CONTINUE
         END IF
   60 CONTINUE
      WRITE (*, '(A, I6, A, I6, A, I5, A, I3)') ' steps', IWORK(11),
     *   '  RES calls', IWORK(12), '  JAC calls', IWORK(13),
     *   '  roots', NROOT
      WRITE (*, '(A, ES9.2, A, ES9.2)') ' largest error: root times',
     *   ETMAX, '  state after a period', EYMAX
      CALL DREGDASKRFREE(IWORK, LIW)
      IF (NFAIL .GT. 0 .OR. NROOT .NE. 8) THEN
         WRITE (*, '(A, I3, A)') ' FAILED:', NFAIL, ' checks'
         STOP 1
      END IF
      WRITE (*, '(A)') ' all checks passed'
      END

      SUBROUTINE RES(T, Y, YP, CJ, DELTA, IRES, RPAR, IPAR)
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

C     PD = dF/dY + CJ dF/dYPRIME (PD is zero on entry).
      SUBROUTINE JAC(T, Y, YP, PD, CJ, RPAR, IPAR)
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

C     The event functions: x (the bottom) and u (the turning points).
      SUBROUTINE RT(NEQ, T, Y, YP, NRT, RVAL, RPAR, IPAR)
      IMPLICIT NONE
      INTEGER NEQ, NRT, IPAR(*)
      DOUBLE PRECISION T, Y(*), YP(*), RVAL(*), RPAR(*)
      RVAL(1) = Y(1)
      RVAL(2) = Y(3)
      END

C     PSOL is not called (the direct method, INFO(12) = 0).
      SUBROUTINE PSOL
      END
