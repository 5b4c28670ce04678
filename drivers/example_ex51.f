C     A complete FORTRAN 77 program calling regdae the DASSL way:
C     Example 5.1 of Petzold, Ren & Maly (1997), singular at T = 0,
C
C        X' = 2 - T*Y,   0 = G(X,T) = T*X - T*(T+1),   T in [-1, 1],
C
C     (X' = F - B*Y with F = 2, B = RPAR(1)*T, RPAR(1) = 1), exact
C     solution X = T + 1, Y = 1/T. Through DREGDAE with the trust-region
C     method, RTOL = ATOL = 1E-8 and the analytic DG/DT (GT); the
C     program checks X against the exact solution. Compile with
C     -std=legacy.
      PROGRAM EX51
      IMPLICIT NONE
      EXTERNAL F, B, G, GX, GT
      INTEGER LRW, LIW
      PARAMETER (LRW = 20, LIW = 22)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), IDID, I, K
      DOUBLE PRECISION RWORK(LRW), RPAR(1), RTOL, ATOL, T, TOUT,
     *     X(1), Y(1), ERR
C
C     Every option at its default (0), then the choices: INFO(16) = 2,
C     the trust-region method; INFO(17) = 1, GT is supplied. IWORK
C     zeroed: a start reads IWORK(19:22) to free a solver left there.
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      DO 20 I = 1, LRW
         RWORK(I) = 0.0D0
   20 CONTINUE
      DO 25 I = 1, LIW
         IWORK(I) = 0
   25 CONTINUE
      INFO(16) = 2
      INFO(17) = 1
      RTOL = 1.0D-8
      ATOL = 1.0D-8
      RPAR(1) = 1.0D0
      T = -1.0D0
      X(1) = 0.0D0
      ERR = 0.0D0
      DO 30 K = 1, 20
         TOUT = -1.0D0 + DBLE(K) / 10.0D0
         CALL DREGDAE (F, B, G, GX, GT, 1, 1, T, X, Y, TOUT, INFO,
     *        RTOL, ATOL, IDID, RWORK, LRW, IWORK, LIW, RPAR, IPAR)
         IF (IDID .LT. 0) THEN
            WRITE (*, '(A, I4)') ' DREGDAE FAILED, IDID =', IDID
            CALL DREGDAEFREE (IWORK, LIW)
            STOP 1
         END IF
         ERR = MAX(ERR, ABS(X(1) - (T + 1.0D0)))
         WRITE (*, 100) T, X(1), Y(1)
   30 CONTINUE
      WRITE (*, '(A, 1P, E9.2, A, I6, A)') ' MAX ERROR', ERR, ' IN',
     *     IWORK(11), ' STEPS'
      CALL DREGDAEFREE (IWORK, LIW)
C     RTOL = 1E-8 through the singularity: the error measured is 1.5E-8;
C     1E-6 means a bug.
      IF (ERR .GT. 1.0D-6) STOP 1
  100 FORMAT (F6.2, 1P, 2E25.16)
      END
C
      SUBROUTINE F(T, X, FX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(*), FX(*), RPAR(*)
      FX(1) = 2.0D0
      END
C
      SUBROUTINE B(T, X, BX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(*), BX(1, 1), RPAR(*)
      BX(1, 1) = RPAR(1) * T
      END
C
      SUBROUTINE G(T, X, GV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(*), GV(*), RPAR(*)
      GV(1) = T * X(1) - T * (T + 1.0D0)
      END
C
      SUBROUTINE GX(T, X, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(*), GM(1, 1), RPAR(*)
      GM(1, 1) = T
      END
C
      SUBROUTINE GT(T, X, GTV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(*), GTV(*), RPAR(*)
      GTV(1) = X(1) - 2.0D0 * T - 1.0D0
      END
