C     Events through the FORTRAN 77 door in DDASKR's manner (DREGDAEMR:
C     RT, NRT, JROOT, IDID = 5): the pendulum M q'' = (0, -G) + G^T
C     lambda on |q| = 1 from rest at 1 rad; RT gives Q(1) (the
C     bottom) and V(1) (the turning points); every root stops the
C     integration (IDID = 5, T the root, JROOT which function and its
C     direction). The program checks the bottoms against the exact
C     times (2k - 1) T/4 (T the period, from the complete elliptic
C     integral by the arithmetic-geometric mean). Compile with
C     -std=legacy.
      PROGRAM EVENTS
      IMPLICIT NONE
      EXTERNAL PM, PF, PG, PGX, RT
      INTEGER LRW, LIW, NRT
      PARAMETER (LRW = 20, LIW = 22, NRT = 2)
      INTEGER INFO(20), IWORK(LIW), IPAR(1), JROOT(NRT), IDID, I, K
      DOUBLE PRECISION RWORK(LRW), RPAR(1), T, TOUT, Q(2), V(2),
     *     LAMBDA(1), A, B, C, PERIOD, ERR
      DO 10 I = 1, 20
         INFO(I) = 0
   10 CONTINUE
      DO 20 I = 1, LRW
         RWORK(I) = 0.0D0
   20 CONTINUE
      DO 25 I = 1, LIW
         IWORK(I) = 0
   25 CONTINUE
C     RPAR(1): gravity
      RPAR(1) = 9.81D0
      T = 0.0D0
      Q(1) = SIN(1.0D0)
      Q(2) = -COS(1.0D0)
      V(1) = 0.0D0
      V(2) = 0.0D0
C     the exact period: 4 K(SIN(1/2)) / SQRT(G)
      A = 1.0D0
      B = COS(0.5D0)
      DO 30 I = 1, 30
         C = 0.5D0 * (A + B)
         B = SQRT(A * B)
         A = C
   30 CONTINUE
      PERIOD = 2.0D0 * ACOS(-1.0D0) / A / SQRT(RPAR(1))
      TOUT = 1.2D0 * PERIOD
      ERR = 0.0D0
      K = 0
      IDID = 5
      DO WHILE (IDID .EQ. 5)
         CALL DREGDAEMR (PM, PF, PG, PGX, PGX, 2, 1, T, Q, V, LAMBDA,
     *        TOUT, INFO, 1.0D-8, 1.0D-8, IDID, RWORK, LRW, IWORK, LIW,
     *        RPAR, IPAR, RT, NRT, JROOT)
         IF (IDID .EQ. 5) THEN
            WRITE (*, '(A, 1P, E23.15, A, 2I3)') ' ROOT AT T =', T,
     *           ', JROOT', JROOT(1), JROOT(2)
            IF (JROOT(1) .NE. 0) THEN
               K = K + 1
               ERR = MAX(ERR, ABS(T - (2 * K - 1) * PERIOD / 4.0D0))
            END IF
         END IF
      END DO
      CALL DREGDAEFREE (IWORK, LIW)
      WRITE (*, '(A, I3, A, 1P, E9.2)') ' IDID', IDID,
     *     ', LARGEST BOTTOM-TIME ERROR', ERR
C     RTOL = 1E-8: 10 RTOL = 1E-7 (measured about 1E-9)
      IF (IDID .NE. 3 .OR. K .NE. 2 .OR. ERR .GT. 1.0D-7) STOP 1
      END
C
      SUBROUTINE PM(T, Q, AM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), AM(2, 2), RPAR(*)
      AM(1, 1) = 1.0D0
      AM(2, 1) = 0.0D0
      AM(1, 2) = 0.0D0
      AM(2, 2) = 1.0D0
      END
C
      SUBROUTINE PF(T, Q, V, FV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), V(2), FV(2), RPAR(*)
      FV(1) = 0.0D0
      FV(2) = -RPAR(1)
      END
C
      SUBROUTINE PG(T, Q, GV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), GV(1), RPAR(*)
      GV(1) = 0.5D0 * (Q(1)**2 + Q(2)**2 - 1.0D0)
      END
C
      SUBROUTINE PGX(T, Q, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), GM(1, 2), RPAR(*)
      GM(1, 1) = Q(1)
      GM(1, 2) = Q(2)
      END
C
C     The event functions: Q(1) and V(1).
      SUBROUTINE RT(N, T, Q, V, NRT, RVAL, RPAR, IPAR)
      INTEGER N, NRT, IPAR(*)
      DOUBLE PRECISION T, Q(N), V(N), RVAL(NRT), RPAR(*)
      RVAL(1) = Q(1)
      RVAL(2) = V(1)
      END
