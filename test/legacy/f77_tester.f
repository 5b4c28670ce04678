C     Tests of the FORTRAN 77 door (DREGDAE, DREGDAEM, DREGDAEMSG,
C     DREGDAEFREE), written as a FORTRAN 77 caller would (-std=legacy).
C     F77_TESTER SUITE runs one suite, F77_TESTER all; prints one line
C     per failed check and 'N PASSED, N FAILED'; STOP 1 on a failure.
C
C     BADINPUT  work arrays too small, INFO entries DREGDAE lacks,
C               bad sizes, tolerances, TOUT, continuation without a
C               start: IDID = -33 and a message, never a crash
C     TWO       two problems interleaved give what each gives alone,
C               bit for bit (DREGDAE with DREGDAE, and with DREGDAEM)
C     MECH      DREGDAEM on a particle on the unit circle (index 3 and
C               2, IDID = 2 with INFO(4) = 1) against the exact motion
C     IRES      RPAR and IPAR reach the routines; IRES = -2 stops with
C               IDID = -11, IRES = -1 beyond a time fails with -108
C     VECTOR    INFO(2) = 1 (ATOL per component): equal entries give the
C               scalar run bit for bit, unequal ones a different one;
C               unequal RTOL entries are refused (IDID = -33)
C     WARN      a warning has an IDID of its own: 6 (the approach to
C               Example 5.1's singularity unresolved), 4 (Baumgarte's
C               multiplier undefined at T = 0); the run goes on after
C               it; DREGDAEMSG gives the last call's message, also after
C               a refused call
C     MAXORD    INFO(9) = 1 with IWORK(3) = MAXORD limits IDA's order:
C               MAXORD = 2 and 3 take several times the steps of 5 on
C               the circle of MECH; MAXORD = 5 is the default run; 0
C               and 6 are refused
C     ROOTS     DREGDAER and DREGDAEMR (NRT, RT, JROOT) on the circle
C               x = (cos t, sin t): IDID = 5 at each root (pi/2, pi,
C               3 pi/2 of X2 and X1) within 10 RTOL, JROOT the
C               function and its direction, T the root, the run goes on
C               to TOUT (IDID 3) after them; RPAR and IPAR reach RT
C     STEPS     INFO(3) = 1: IDID = 1 after every step (T the step's
C               end, X there on the circle, IWORK(11) one more step
C               each time), then IDID = 3 at TOUT; the same X at TOUT
C               as INFO(3) = 0 to 1E-7
C     JAC       DREGDAEJ and DREGDAEMJ (INFO(5) = 1, JAC the Jacobian
C               of F, of FORCES in Q and V) on stiff nonlinear problems
C               with exact solutions (the particle at index 3 and 2):
C               the results with JAC are those without it within the
C               tolerance, and exact to it; JAC replaces the difference
C               quotients of F (fewer F calls);
C               RWORK(19) = 1 (check_jacobians) passes the right JAC
C               and stops a wrong one with IDID = -116 and the entry
C               (row, column) of PD named; INFO(5) = 1 in DREGDAE is
C               refused with a message that points to DREGDAEJ;
C               DREGDAEJR and DREGDAEMJR (JAC and RT together) stop at
C               the root of X1 = cos t within 100 RTOL, then go on
C     NONNEG    INFO(10) = 1 on Robertson's kinetics (DREGDAE, M = 0)
C               with ATOL = 1E-6, RTOL = 1E-3 to T = 4E10: without it
C               components go negative and the run blows up; with it
C               every step end (INFO(3) = 1) is >= 0 and the end state
C               is the reference's to 10 ATOL; INFO(19) = 2 and a
C               negative X at the start are refused with IDID = -33
C     LINEAR    theory_problems' S1 (GB = T**2, singular at T = 0)
C               with its exact solution, trust_region and direct at
C               RTOL 1E-4, 1E-6, 1E-8: every output through T = 0
C               within 10 error weights, or IDID 4 or 6 (a warning)
C               with DREGDAEMSG's reason before it (issue 19)
C     ESTIMATE  RWORK(16) = 1: RWORK(17), the error estimate, within
C               a factor 10 of the true error on the circle at every
C               output; -1 without the option
C     RESTART   INFO(1) = 0 again on the same IWORK without DREGDAEFREE
C               (after a success, a refused start, an inconsistent x0)
C               gives a fresh run, bit for bit, and frees the old solver
C               (ctest valgrind.f77_restart: no leak); DREGDAEMSG holds
C               the last call's message, also when IWORK(20) was
C               corrupted for a call and restored
      PROGRAM F77TST
      IMPLICIT NONE
      CHARACTER*16 SUITE
      INTEGER NCHK(2)
      NCHK(1) = 0
      NCHK(2) = 0
      SUITE = ' '
      IF (IARGC() .GE. 1) CALL GETARG(1, SUITE)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'BADINPUT') CALL BADIN(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'TWO') CALL TWO(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'MECH') CALL MECH(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'IRES') CALL IRESTS(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'VECTOR') CALL VECTOR(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'WARN') CALL WARN(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'RESTART') CALL RESTRT(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'MAXORD') CALL MAXORD(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'ROOTS') CALL ROOTS(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'STEPS') CALL STEPS(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'JAC') CALL JACSUI(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'NONNEG') CALL NONNEG(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'LINEAR') CALL LINEAR(NCHK)
      IF (SUITE .EQ. ' ' .OR. SUITE .EQ. 'ESTIMATE') CALL ESTIM(NCHK)
      IF (NCHK(1) + NCHK(2) .EQ. 0) THEN
         WRITE (*, '(3A)') 'F77_TESTER: UNKNOWN SUITE "',
     *        SUITE(1:LEN_TRIM(SUITE)),
     *        '" (BADINPUT, TWO, MECH, IRES, VECTOR, WARN, RESTART, ',
     *        'MAXORD, ROOTS, STEPS, JAC, NONNEG, LINEAR, ESTIMATE)'
         STOP 2
      END IF
      WRITE (*, '(I0, A, I0, A)') NCHK(1), ' PASSED, ', NCHK(2),
     *     ' FAILED'
      IF (NCHK(2) .GT. 0) STOP 1
      END
C
C     Count a check (NCHK(1) passed, NCHK(2) failed); print the failed.
      SUBROUTINE CHECK(OK, WHAT, NCHK)
      LOGICAL OK
      CHARACTER*(*) WHAT
      INTEGER NCHK(2)
      IF (OK) THEN
         NCHK(1) = NCHK(1) + 1
      ELSE
         NCHK(2) = NCHK(2) + 1
         WRITE (*, '(2A)') '  FAIL ', WHAT
      END IF
      END
C
C     INFO, RWORK and IWORK at their defaults (all 0), messages off.
      SUBROUTINE CLEAR(INFO, RWORK, IWORK)
      INTEGER INFO(20), IWORK(22), I
      DOUBLE PRECISION RWORK(20)
      DO 10 I = 1, 20
         INFO(I) = 0
         RWORK(I) = 0.0D0
   10 CONTINUE
      DO 20 I = 1, 22
         IWORK(I) = 0
   20 CONTINUE
      INFO(20) = -1
      END
C
C     ---- BADINPUT ---------------------------------------------------
C     Start the circle (DREGDAE) from T = 0 to TOUT; return IDID and
C     the line DREGDAE printed (INFO(20) = a scratch unit), if any.
      SUBROUTINE TRY(N, M, TOUT, INFO, RTOL, ATOL, IDID, RWORK, LRW,
     *     IWORK, LIW, MSG)
      EXTERNAL CF, CB, CG, CGX
      INTEGER N, M, INFO(20), IDID, LRW, LIW, IWORK(LIW), IPAR(2)
      DOUBLE PRECISION TOUT, RTOL, ATOL, RWORK(LRW), T, X(2), Y(2),
     *     RPAR(2)
      CHARACTER*(*) MSG
      T = 0.0D0
      X(1) = 1.0D0
      X(2) = 0.0D0
      IPAR(1) = 0
      IPAR(2) = 0
      OPEN (UNIT=21, STATUS='SCRATCH')
      INFO(20) = 21
      CALL DREGDAE(CF, CB, CG, CGX, CGX, N, M, T, X, Y, TOUT, INFO,
     *     RTOL, ATOL, IDID, RWORK, LRW, IWORK, LIW, RPAR, IPAR)
      REWIND (21)
      MSG = ' '
      READ (21, '(A)', END=10) MSG
   10 CLOSE (21)
      END
C
      SUBROUTINE BADIN(NCHK)
      INTEGER NCHK(2), INFO(20), IWORK(22), IDID
      DOUBLE PRECISION RWORK(20)
      CHARACTER*300 MSG
C     IWORK too small: the message goes to the unit of INFO(20)
      CALL CLEAR(INFO, RWORK, IWORK)
      CALL TRY(2, 1, 1.0D0, INFO, 1.0D-6, 1.0D-6, IDID, RWORK, 20,
     *     IWORK, 21, MSG)
      CALL CHECK(IDID .EQ. -33, 'LIW 21: IDID -33', NCHK)
      CALL CHECK(INDEX(MSG, 'DREGDAE-- LIW = 21 is too small') .GT. 0
     *     .AND. INDEX(MSG, 'LIW >= 22') .GT. 0, 'LIW message', NCHK)
      CALL CHECK(INFO(1) .EQ. -1, 'LIW 21: INFO(1) = -1', NCHK)
C     RWORK too small
      CALL CLEAR(INFO, RWORK, IWORK)
      CALL TRY(2, 1, 1.0D0, INFO, 1.0D-6, 1.0D-6, IDID, RWORK, 19,
     *     IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'LRW = 19') .GT. 0
     *     .AND. INDEX(MSG, 'LRW >= 20') .GT. 0, 'LRW 19', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
C     INFO entries: INFO(3) not 0/1, JAC without DREGDAEJ, DDASPK's,
C     a method that is none, an index for DREGDAE, not 0/1 (INFO(2):
C     VECTOR)
C     (each message says why, and what to set instead)
      CALL ONEBAD(3, 2, 'INFO(3) = 2 must be 0 or 1', NCHK)
      CALL ONEBAD(5, 1, 'a JAC routine', NCHK)
      CALL ONEBAD(5, 1, 'call DREGDAEJ', NCHK)
      CALL ONEBAD(5, 1, 'set INFO(5) = 0', NCHK)
      CALL ONEBAD(6, 1, 'a banded matrix', NCHK)
      CALL ONEBAD(6, 1, 'set INFO(6) = 0', NCHK)
      CALL ONEBAD(6, 1, 'not banded when df/dx is', NCHK)
      CALL ONEBAD(9, 1, 'MAXORD = IWORK(3) = 0 is not 1 ... 5', NCHK)
      CALL ONEBAD(10, 2, 'INFO(10) = 2 must be 0 or 1', NCHK)
      CALL ONEBAD(12, 1, 'Krylov method', NCHK)
      CALL ONEBAD(13, 1, 'set INFO(12), INFO(13)', NCHK)
      CALL ONEBAD(14, 1, 'set INFO(14) = 0', NCHK)
      CALL ONEBAD(15, 1, 'Krylov method', NCHK)
      CALL ONEBAD(16, 7, 'INFO(16) = 7 is not a method', NCHK)
      CALL ONEBAD(17, 2, 'INFO(17) = 2', NCHK)
      CALL ONEBAD(18, 3, 'the index is for DREGDAEM', NCHK)
      CALL ONEBAD(19, 5, 'INFO(19) = 5', NCHK)
      CALL ONEBAD(11, 2, 'INFO(11) = 2 must be 0 or 1', NCHK)
      CALL ONEBAD(1, 2, 'INFO(1) = 2 must be 0', NCHK)
C     sizes, tolerances, TOUT, TSTOP, HMAX
      CALL CLEAR(INFO, RWORK, IWORK)
      CALL EXPECT(0, 0, 1.0D0, 1.0D-6, 1.0D-6, INFO, RWORK, 'N = 0',
     *     NCHK)
      CALL EXPECT(2, 3, 1.0D0, 1.0D-6, 1.0D-6, INFO, RWORK, 'M = 3',
     *     NCHK)
      CALL EXPECT(2, 1, 1.0D0, 2.0D0, 1.0D-6, INFO, RWORK, 'rtol must',
     *     NCHK)
      CALL EXPECT(2, 1, 1.0D0, 1.0D-6, 0.0D0, INFO, RWORK, 'atol must',
     *     NCHK)
      CALL EXPECT(2, 1, 0.0D0, 1.0D-6, 1.0D-6, INFO, RWORK,
     *     'TOUT = 0.000000E+00 is equal to T', NCHK)
      CALL EXPECT(2, 1, -1.0D0, 1.0D-6, 1.0D-6, INFO, RWORK,
     *     'before the current time', NCHK)
      INFO(4) = 1
      RWORK(1) = 0.5D0
      CALL EXPECT(2, 1, 1.0D0, 1.0D-6, 1.0D-6, INFO, RWORK,
     *     'TSTOP = RWORK(1) = 5.000000E-01 is behind TOUT', NCHK)
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(7) = 1
      CALL EXPECT(2, 1, 1.0D0, 1.0D-6, 1.0D-6, INFO, RWORK,
     *     'HMAX = RWORK(2) = 0.000000E+00 is not > 0', NCHK)
C     continuation: without a start; after a failure without resetting
C     INFO(1); on a freed IWORK
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(1) = 1
      CALL TRY(2, 1, 1.0D0, INFO, 1.0D-6, 1.0D-6, IDID, RWORK, 20,
     *     IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'holds no solver')
     *     .GT. 0, 'INFO(1) = 1 first', NCHK)
      CALL CHECK(INFO(1) .EQ. -1, 'INFO(1) = -1 after -33', NCHK)
      CALL TRY(2, 1, 1.0D0, INFO, 1.0D-6, 1.0D-6, IDID, RWORK, 20,
     *     IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'the last call failed')
     *     .GT. 0, 'INFO(1) = -1: IDID -33', NCHK)
C     an inconsistent start, x0 off the circle: IDID = -12
      CALL CLEAR(INFO, RWORK, IWORK)
      CALL BADX0(INFO, RWORK, IWORK, IDID, MSG)
      CALL CHECK(IDID .EQ. -12 .AND. INDEX(MSG, 'ic_tol') .GT. 0,
     *     'x0 inconsistent: IDID -12', NCHK)
      CALL CHECK(IWORK(18) .EQ. -102, 'IWORK(18) = -102', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(INDEX(MSG, 'no regdae solver') .GT. 0,
     *     'freed: DREGDAEMSG', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
      CALL DREGDAEMSG(IWORK, 3, MSG)
      CALL CHECK(INDEX(MSG, 'no regdae solver') .GT. 0,
     *     'LIW 3: DREGDAEMSG', NCHK)
      END
C
C     Start the circle with INFO(K) = VALUE: IDID = -33 and a message
C     that contains PART.
      SUBROUTINE ONEBAD(K, VALUE, PART, NCHK)
      INTEGER K, VALUE, NCHK(2), INFO(20), IWORK(22)
      DOUBLE PRECISION RWORK(20)
      CHARACTER*(*) PART
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(K) = VALUE
      CALL EXPECT(2, 1, 1.0D0, 1.0D-6, 1.0D-6, INFO, RWORK, PART, NCHK)
      END
C
C     Start the circle with these arguments: IDID = -33 and a printed
C     message that contains PART.
      SUBROUTINE EXPECT(N, M, TOUT, RTOL, ATOL, INFO, RWORK, PART,
     *     NCHK)
      INTEGER N, M, INFO(20), NCHK(2), IWORK(22), IDID, I, INF(20)
      DOUBLE PRECISION TOUT, RTOL, ATOL, RWORK(20)
      CHARACTER*(*) PART
      CHARACTER*600 MSG
C     a copy: DREGDAE sets INFO(1) = -1
      DO 10 I = 1, 20
         INF(I) = INFO(I)
   10 CONTINUE
      DO 20 I = 1, 22
         IWORK(I) = 0
   20 CONTINUE
      CALL TRY(N, M, TOUT, INF, RTOL, ATOL, IDID, RWORK, 20, IWORK, 22,
     *     MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, PART) .GT. 0, PART,
     *     NCHK)
      IF (IDID .NE. -33 .OR. INDEX(MSG, PART) .EQ. 0)
     *     WRITE (*, '(2A)') '    MESSAGE: ', MSG(1:LEN_TRIM(MSG))
      CALL DREGDAEFREE(IWORK, 22)
      END
C
      SUBROUTINE BADX0(INFO, RWORK, IWORK, IDID, MSG)
      EXTERNAL CF, CB, CG, CGX
      INTEGER INFO(20), IWORK(22), IDID, IPAR(2)
      DOUBLE PRECISION RWORK(20), T, X(2), Y(1), RPAR(2)
      CHARACTER*(*) MSG
      CALL CIRCLE0(T, X, IPAR)
      X(1) = 1.5D0
      CALL DREGDAE(CF, CB, CG, CGX, CGX, 2, 1, T, X, Y, 1.0D0, INFO,
     *     1.0D-6, 1.0D-6, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      END
C
C     ---- TWO ---------------------------------------------------------
      SUBROUTINE TWO(NCHK)
      EXTERNAL CG, CGX, MM, MF
      INTEGER NCHK(2), INFA(20), INFB(20), IWA(22), IWB(22), IDA, IDB,
     *     IPA(2), IPB(2), K
      DOUBLE PRECISION RWA(20), RWB(20), TA, TB, XA(2), XB(2), YA(1),
     *     YB(1), VB(2), ALONE(2, 10), RPA(2), RPB(2)
      LOGICAL SAME, OK
C     the circle alone
      CALL CLEAR(INFA, RWA, IWA)
      CALL CIRCLE0(TA, XA, IPA)
      DO 10 K = 1, 10
         CALL CSTEP(TA, XA, YA, 0.5D0 * K, INFA, IDA, RWA, IWA,
     *        RPA, IPA)
         ALONE(1, K) = XA(1)
         ALONE(2, K) = XA(2)
   10 CONTINUE
      CALL DREGDAEFREE(IWA, 22)
C     the circle with another circle (Baumgarte, other times), and with
C     the mechanical circle; neither disturbs it
      CALL CLEAR(INFA, RWA, IWA)
      CALL CLEAR(INFB, RWB, IWB)
      CALL CIRCLE0(TA, XA, IPA)
      CALL CIRCLE0(TB, XB, IPB)
      INFB(16) = 1
      SAME = .TRUE.
      OK = .TRUE.
      DO 20 K = 1, 10
         CALL CSTEP(TA, XA, YA, 0.5D0 * K, INFA, IDA, RWA, IWA,
     *        RPA, IPA)
         CALL CSTEP(TB, XB, YB, 0.25D0 * K, INFB, IDB, RWB, IWB,
     *        RPB, IPB)
         SAME = SAME .AND. XA(1) .EQ. ALONE(1, K) .AND.
     *        XA(2) .EQ. ALONE(2, K)
         OK = OK .AND. IDA .EQ. 3 .AND. IDB .EQ. 3
   20 CONTINUE
      CALL CHECK(OK, 'two DREGDAE: IDID 3', NCHK)
      CALL CHECK(SAME, 'two DREGDAE: the same as alone', NCHK)
      CALL CHECK(ABS(XB(1) - COS(2.5D0)) .LT. 1.0D-6 .AND.
     *     ABS(XB(2) - SIN(2.5D0)) .LT. 1.0D-6, 'Baumgarte circle',
     *     NCHK)
      CALL CHECK(IPA(1) .GT. 0 .AND. IPB(1) .GT. 0,
     *     'each IPAR counted its calls', NCHK)
      CALL DREGDAEFREE(IWA, 22)
      CALL DREGDAEFREE(IWB, 22)
      CALL CLEAR(INFA, RWA, IWA)
      CALL CLEAR(INFB, RWB, IWB)
      CALL CIRCLE0(TA, XA, IPA)
      CALL CIRCLE0(TB, XB, IPB)
      VB(1) = 0.0D0
      VB(2) = 1.0D0
      SAME = .TRUE.
      OK = .TRUE.
      DO 30 K = 1, 10
         CALL DREGDAEM(MM, MF, CG, CGX, CGX, 2, 1, TB, XB, VB, YB,
     *        0.5D0 * K, INFB, 1.0D-8, 1.0D-8, IDB, RWB, 20, IWB, 22,
     *        RPB, IPB)
         CALL CSTEP(TA, XA, YA, 0.5D0 * K, INFA, IDA, RWA, IWA,
     *        RPA, IPA)
         SAME = SAME .AND. XA(1) .EQ. ALONE(1, K) .AND.
     *        XA(2) .EQ. ALONE(2, K)
         OK = OK .AND. IDA .EQ. 3 .AND. IDB .EQ. 3
   30 CONTINUE
      CALL CHECK(OK, 'DREGDAE and DREGDAEM: IDID 3', NCHK)
      CALL CHECK(SAME, 'DREGDAE with DREGDAEM: as alone', NCHK)
      CALL CHECK(ABS(XB(1) - COS(5.0D0)) .LT. 1.0D-6 .AND.
     *     ABS(YB(1) + 0.5D0) .LT. 1.0D-6, 'DREGDAEM circle', NCHK)
      CALL DREGDAEFREE(IWA, 22)
      CALL DREGDAEFREE(IWB, 22)
      END
C
C     One DREGDAE call on the circle, tolerances 1E-8, to TOUT.
      SUBROUTINE CSTEP(T, X, Y, TOUT, INFO, IDID, RWORK, IWORK, RPAR,
     *     IPAR)
      EXTERNAL CF, CB, CG, CGX
      INTEGER INFO(20), IDID, IWORK(22), IPAR(2)
      DOUBLE PRECISION T, X(2), Y(1), TOUT, RWORK(20), RPAR(2)
      CALL DREGDAE(CF, CB, CG, CGX, CGX, 2, 1, T, X, Y, TOUT, INFO,
     *     1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR)
      END
C
      SUBROUTINE CIRCLE0(T, X, IPAR)
      INTEGER IPAR(2)
      DOUBLE PRECISION T, X(2)
      T = 0.0D0
      X(1) = 1.0D0
      X(2) = 0.0D0
      IPAR(1) = 0
      IPAR(2) = 0
      END
C
C     ---- MECH --------------------------------------------------------
C     The particle on the unit circle, M = I, no forces: q = (cos t,
C     sin t), lambda = -1/2; index 3, index 2, and INFO(4) = 1.
      SUBROUTINE MECH(NCHK)
      INTEGER NCHK(2), INFO(20), IWORK(22), VARIANT
      DOUBLE PRECISION RWORK(20), ERR
      INTEGER IDIDS(3)
      DO 10 VARIANT = 1, 3
         CALL CLEAR(INFO, RWORK, IWORK)
         IF (VARIANT .EQ. 2) INFO(18) = 2
         IF (VARIANT .EQ. 3) THEN
            INFO(4) = 1
            RWORK(1) = 10.0D0
         END IF
         CALL MRUN(INFO, RWORK, IWORK, ERR, IDIDS(VARIANT))
C        RTOL = ATOL = 1E-8 over 0.8 revolutions: the C tests measure
C        1.2E-8 to 4.6E-8 on this motion; 1E-6 is 20 times that
         CALL CHECK(ERR .LT. 1.0D-6, 'DREGDAEM error', NCHK)
         CALL CHECK(IWORK(11) .GT. 0 .AND. IWORK(12) .GE. IWORK(11)
     *        .AND. RWORK(4) .GE. 5.0D0 .AND. RWORK(7) .GT. 0.0D0,
     *        'DREGDAEM counters', NCHK)
         IF (ERR .GE. 1.0D-6) WRITE (*, '(A, I2, 1P, E10.2)')
     *        '    variant, error', VARIANT, ERR
         CALL DREGDAEFREE(IWORK, 22)
   10 CONTINUE
      CALL CHECK(IDIDS(1) .EQ. 3 .AND. IDIDS(2) .EQ. 3 .AND.
     *     IDIDS(3) .EQ. 2, 'IDID 3, 3, 2', NCHK)
      END
C
      SUBROUTINE MRUN(INFO, RWORK, IWORK, ERR, IDID)
      EXTERNAL MM, MF, CG, CGX
      INTEGER INFO(20), IWORK(22), IDID, IPAR(2), K
      DOUBLE PRECISION RWORK(20), ERR, T, Q(2), V(2), LAMBDA(1),
     *     RPAR(2), TOUT
      CALL CIRCLE0(T, Q, IPAR)
      V(1) = 0.0D0
      V(2) = 1.0D0
      ERR = 0.0D0
      DO 10 K = 1, 10
         TOUT = 0.5D0 * K
         CALL DREGDAEM(MM, MF, CG, CGX, CGX, 2, 1, T, Q, V, LAMBDA,
     *        TOUT, INFO, 1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK, 22,
     *        RPAR, IPAR)
         IF (IDID .LT. 0) THEN
            ERR = 1.0D0
            RETURN
         END IF
         ERR = MAX(ERR, ABS(Q(1) - COS(T)), ABS(Q(2) - SIN(T)),
     *        ABS(V(1) + SIN(T)), ABS(V(2) - COS(T)),
     *        ABS(LAMBDA(1) + 0.5D0))
   10 CONTINUE
      END
C
C     ---- IRES --------------------------------------------------------
C     IPAR(2) = 1: G sets IRES = -1 from T = RPAR(2) on; IPAR(2) = 2:
C     IRES = -2 from there.
      SUBROUTINE IRESTS(NCHK)
      INTEGER NCHK(2), INFO(20), IWORK(22), IPAR(2), IDID, MODE
      DOUBLE PRECISION RWORK(20), RPAR(2), T, X(2), Y(1)
      CHARACTER*600 MSG
      DO 10 MODE = 1, 2
         CALL CLEAR(INFO, RWORK, IWORK)
         CALL CIRCLE0(T, X, IPAR)
         IPAR(2) = MODE
         RPAR(2) = 1.5D0
         INFO(19) = 1
         CALL CSTEP(T, X, Y, 1.0D0, INFO, IDID, RWORK, IWORK, RPAR,
     *        IPAR)
         CALL CHECK(IDID .EQ. 3 .AND. INFO(1) .EQ. 1 .AND.
     *        IPAR(1) .GT. 0, 'to T = 1: RPAR, IPAR reach G', NCHK)
         CALL CSTEP(T, X, Y, 2.0D0, INFO, IDID, RWORK, IWORK, RPAR,
     *        IPAR)
         CALL DREGDAEMSG(IWORK, 22, MSG)
         IF (MODE .EQ. 1) THEN
            CALL CHECK(IDID .EQ. -108 .AND.
     *           INDEX(MSG, 'cannot get past') .GT. 0 .AND.
     *           INDEX(MSG, 'G returned IRES = -1') .GT. 0 .AND.
     *           INDEX(MSG, 'user routine') .EQ. 0,
     *           'IRES = -1: IDID -108', NCHK)
         ELSE
            CALL CHECK(IDID .EQ. -11 .AND.
     *           INDEX(MSG, 'G returned IRES = -2 at t = 1.5') .GT. 0
     *           .AND. INDEX(MSG, 'user routine') .EQ. 0,
     *           'IRES = -2: IDID -11', NCHK)
         END IF
         CALL CHECK(INFO(1) .EQ. -1 .AND. T .GE. 1.0D0 .AND.
     *        T .LT. 1.5D0, 'T reached, INFO(1) = -1', NCHK)
         IF (IDID .GE. 0 .OR. T .GE. 1.5D0) WRITE (*, '(2A)')
     *        '    MESSAGE: ', MSG(1:LEN_TRIM(MSG))
         CALL DREGDAEFREE(IWORK, 22)
   10 CONTINUE
      END
C
C     ---- RESTART -----------------------------------------------------
      SUBROUTINE RESTRT(NCHK)
      INTEGER NCHK(2), INFO(20), IWORK(22), IPAR(2), IDID, K, KEEP
      DOUBLE PRECISION RWORK(20), RPAR(2), T, X(2), Y(1), FRESH(2)
      CHARACTER*300 MSG
C     a fresh run to T = 2 (the reference), freed
      CALL CLEAR(INFO, RWORK, IWORK)
      CALL CIRCLE0(T, X, IPAR)
      CALL CSTEP(T, X, Y, 2.0D0, INFO, IDID, RWORK, IWORK, RPAR, IPAR)
      FRESH(1) = X(1)
      FRESH(2) = X(2)
      CALL DREGDAEFREE(IWORK, 22)
C     the same IWORK restarted three times without DREGDAEFREE: after
C     a success, after a refused start (INFO(3) = 2), after x0 off the
C     circle (IDID = -12); each restart runs as the fresh run
      CALL CLEAR(INFO, RWORK, IWORK)
      DO 10 K = 1, 3
         INFO(1) = 0
         CALL CIRCLE0(T, X, IPAR)
         CALL CSTEP(T, X, Y, 1.0D0, INFO, IDID, RWORK, IWORK, RPAR,
     *        IPAR)
         CALL CHECK(IDID .EQ. 3, 'a run to T = 1', NCHK)
         INFO(1) = 0
         IF (K .EQ. 2) THEN
            INFO(3) = 2
            CALL CIRCLE0(T, X, IPAR)
            CALL CSTEP(T, X, Y, 1.0D0, INFO, IDID, RWORK, IWORK, RPAR,
     *           IPAR)
            CALL DREGDAEMSG(IWORK, 22, MSG)
            CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'INFO(3)') .GT. 0,
     *           'a refused start: IDID -33, its message', NCHK)
            INFO(3) = 0
            INFO(1) = 0
         ELSE IF (K .EQ. 3) THEN
            CALL BADX0(INFO, RWORK, IWORK, IDID, MSG)
            CALL CHECK(IDID .EQ. -12 .AND. INDEX(MSG, 'ic_tol') .GT. 0,
     *           'a start with x0 off: IDID -12, its message', NCHK)
            INFO(1) = 0
         END IF
         CALL CIRCLE0(T, X, IPAR)
         CALL CSTEP(T, X, Y, 2.0D0, INFO, IDID, RWORK, IWORK, RPAR,
     *        IPAR)
         CALL DREGDAEMSG(IWORK, 22, MSG)
         CALL CHECK(IDID .EQ. 3 .AND. X(1) .EQ. FRESH(1) .AND.
     *        X(2) .EQ. FRESH(2) .AND. MSG .EQ. ' ',
     *        'the restart runs as a fresh run, bit for bit', NCHK)
   10 CONTINUE
C     IWORK(20) corrupted for one call: refused, with the message; the
C     message stays after IWORK(20) is restored; the next call goes on
      KEEP = IWORK(20)
      IWORK(20) = IWORK(20) + 1
      CALL CSTEP(T, X, Y, 3.0D0, INFO, IDID, RWORK, IWORK, RPAR, IPAR)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND.
     *     INDEX(MSG, 'IWORK holds no solver') .GT. 0,
     *     'IWORK(20) corrupted: IDID -33, the message', NCHK)
      IWORK(20) = KEEP
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(INDEX(MSG, 'IWORK holds no solver') .GT. 0,
     *     'IWORK(20) restored: still the refusal''s message', NCHK)
      INFO(1) = 1
      CALL CSTEP(T, X, Y, 3.0D0, INFO, IDID, RWORK, IWORK, RPAR, IPAR)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. 3 .AND. MSG .EQ. ' ' .AND.
     *     ABS(X(1) - COS(3.0D0)) .LT. 1.0D-6,
     *     'restored: the run goes on to T = 3', NCHK)
C     INFO(1) = -1 refused, with its message, after a failure
      INFO(1) = -1
      CALL CSTEP(T, X, Y, 4.0D0, INFO, IDID, RWORK, IWORK, RPAR, IPAR)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'INFO(1) = -1') .GT. 0,
     *     'INFO(1) = -1: refused, its message', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
      END
C
C     ---- ROOTS -------------------------------------------------------
C     The circle to TOUT = 5 with RT = (X2, X1): roots of X1 at pi/2
C     (decreasing) and 3 pi/2 (increasing), of X2 at pi (decreasing);
C     DREGDAER (first order) and DREGDAEMR (the particle).
      SUBROUTINE ROOTS(NCHK)
      EXTERNAL CF, CB, CG, CGX, MM, MF, CRT
      INTEGER NCHK(2), INFO(20), IWORK(22), IPAR(2), JROOT(2), IDID,
     *     K, KIND, EXPECT(2, 3)
      DOUBLE PRECISION RWORK(20), RPAR(2), T, X(2), Y(1), V(2), PI,
     *     TROOT(3)
      DATA EXPECT /0, -1, -1, 0, 0, 1/
      PI = ACOS(-1.0D0)
      TROOT(1) = 0.5D0 * PI
      TROOT(2) = PI
      TROOT(3) = 1.5D0 * PI
      DO 20 KIND = 1, 2
         CALL CLEAR(INFO, RWORK, IWORK)
         CALL CIRCLE0(T, X, IPAR)
         V(1) = 0.0D0
         V(2) = 1.0D0
         RPAR(1) = 0.0D0
         DO 10 K = 1, 4
            IF (KIND .EQ. 1) THEN
               CALL DREGDAER(CF, CB, CG, CGX, CGX, 2, 1, T, X, Y, 5.0D0,
     *              INFO, 1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK, 22,
     *              RPAR, IPAR, CRT, 2, JROOT)
            ELSE
               CALL DREGDAEMR(MM, MF, CG, CGX, CGX, 2, 1, T, X, V, Y,
     *              5.0D0, INFO, 1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK,
     *              22, RPAR, IPAR, CRT, 2, JROOT)
            END IF
            IF (K .LE. 3) THEN
               CALL CHECK(IDID .EQ. 5, 'IDID 5 at a root', NCHK)
               CALL CHECK(ABS(T - TROOT(K)) .LE. 1.0D-7,
     *              'the root within 10 RTOL', NCHK)
               CALL CHECK(JROOT(1) .EQ. EXPECT(1, K) .AND.
     *              JROOT(2) .EQ. EXPECT(2, K), 'JROOT', NCHK)
               IF (IDID .NE. 5 .OR. ABS(T - TROOT(K)) .GT. 1.0D-7)
     *              WRITE (*, '(A, 2I3, 1P, E24.15)')
     *              '    kind, root, T', KIND, K, T
            ELSE
               CALL CHECK(IDID .EQ. 3 .AND. T .EQ. 5.0D0,
     *              'TOUT after the roots', NCHK)
            END IF
   10    CONTINUE
         CALL CHECK(RPAR(1) .GT. 0.0D0, 'RPAR reaches RT', NCHK)
         CALL DREGDAEFREE(IWORK, 22)
   20 CONTINUE
      END
C
C     ---- STEPS -------------------------------------------------------
C     The circle to TOUT = 1 with INFO(3) = 1 (DREGDAE and DREGDAEM).
      SUBROUTINE STEPS(NCHK)
      EXTERNAL MM, MF, CG, CGX
      INTEGER NCHK(2), INFO(20), IWORK(22), IPAR(2), IDID, K, NSTEP,
     *     KIND, LAST
      DOUBLE PRECISION RWORK(20), RPAR(2), T, X(2), Y(1), V(2), XREF(2),
     *     TPREV, ERR
      LOGICAL ONE
      DO 20 KIND = 1, 2
C        the reference: INFO(3) = 0
         CALL CLEAR(INFO, RWORK, IWORK)
         CALL CIRCLE0(T, X, IPAR)
         V(1) = 0.0D0
         V(2) = 1.0D0
         IF (KIND .EQ. 1) THEN
            CALL CSTEP(T, X, Y, 1.0D0, INFO, IDID, RWORK, IWORK, RPAR,
     *           IPAR)
         ELSE
            CALL DREGDAEM(MM, MF, CG, CGX, CGX, 2, 1, T, X, V, Y, 1.0D0,
     *           INFO, 1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK, 22, RPAR,
     *           IPAR)
         END IF
         XREF(1) = X(1)
         XREF(2) = X(2)
         CALL DREGDAEFREE(IWORK, 22)
         CALL CLEAR(INFO, RWORK, IWORK)
         INFO(3) = 1
         CALL CIRCLE0(T, X, IPAR)
         V(1) = 0.0D0
         V(2) = 1.0D0
         NSTEP = 0
         ONE = .TRUE.
         ERR = 0.0D0
         LAST = 0
         IDID = 1
         K = 0
         DO WHILE (IDID .EQ. 1 .AND. K .LT. 100000)
            K = K + 1
            TPREV = T
            IF (KIND .EQ. 1) THEN
               CALL CSTEP(T, X, Y, 1.0D0, INFO, IDID, RWORK, IWORK,
     *              RPAR, IPAR)
            ELSE
               CALL DREGDAEM(MM, MF, CG, CGX, CGX, 2, 1, T, X, V, Y,
     *              1.0D0, INFO, 1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK,
     *              22, RPAR, IPAR)
            END IF
            IF (IDID .EQ. 1) THEN
               NSTEP = NSTEP + 1
C              one more step each time (after the integrator's first)
               IF (K .GT. 20 .AND. IWORK(11) .NE. LAST + 1) ONE =.FALSE.
               LAST = IWORK(11)
               IF (.NOT. (T .GT. TPREV .AND. T .LT. 1.0D0)) ONE =.FALSE.
               ERR = MAX(ERR, ABS(X(1) - COS(T)), ABS(X(2) - SIN(T)))
            END IF
         END DO
         CALL CHECK(IDID .EQ. 3 .AND. T .EQ. 1.0D0, 'IDID 3 at TOUT',
     *        NCHK)
         CALL CHECK(NSTEP .GT. 20, 'IDID 1 returns', NCHK)
         CALL CHECK(ONE, 'one step per return, T the step end', NCHK)
         CALL CHECK(ERR .LT. 1.0D-6, 'X at the step ends', NCHK)
         CALL CHECK(ABS(X(1) - XREF(1)) + ABS(X(2) - XREF(2))
     *        .LT. 1.0D-7, 'X at TOUT as with INFO(3) = 0', NCHK)
         IF (.NOT. ONE .OR. IDID .NE. 3) WRITE (*, '(A, 3I6)')
     *        '    kind, returns, IDID', KIND, NSTEP, IDID
         CALL DREGDAEFREE(IWORK, 22)
   20 CONTINUE
      END
C
C     RT: X2 and X1; counts its calls in RPAR(1).
      SUBROUTINE CRT(N, T, X, V, NRT, RVAL, RPAR, IPAR)
      INTEGER N, NRT, IPAR(*)
      DOUBLE PRECISION T, X(N), V(N), RVAL(NRT), RPAR(*)
      RVAL(1) = X(2)
      RVAL(2) = X(1)
      RPAR(1) = RPAR(1) + 1.0D0
      END
C
C     ---- the problems ------------------------------------------------
C     The circle (example_circle): x' = (x1 - x2, x1 + x2) - 2x y.
      SUBROUTINE CF(T, X, FX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(2), FX(2), RPAR(*)
      FX(1) = X(1) - X(2)
      FX(2) = X(1) + X(2)
      END
C
      SUBROUTINE CB(T, X, BX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(2), BX(2, 1), RPAR(*)
      BX(1, 1) = 2.0D0 * X(1)
      BX(2, 1) = 2.0D0 * X(2)
      END
C
C     g = x1^2 + x2^2 - 1, counting its calls in IPAR(1) and failing
C     from T = RPAR(2) on as IPAR(2) says.
      SUBROUTINE CG(T, X, GV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(2)
      DOUBLE PRECISION T, X(2), GV(1), RPAR(2)
      GV(1) = X(1)**2 + X(2)**2 - 1.0D0
      IPAR(1) = IPAR(1) + 1
      IF (IPAR(2) .NE. 0 .AND. T .GE. RPAR(2)) IRES = -IPAR(2)
      END
C
      SUBROUTINE CGX(T, X, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(2), GM(1, 2), RPAR(*)
      GM(1, 1) = 2.0D0 * X(1)
      GM(1, 2) = 2.0D0 * X(2)
      END
C
C     The particle: M = I, no forces.
      SUBROUTINE MM(T, Q, AM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), AM(2, 2), RPAR(*)
      AM(1, 1) = 1.0D0
      AM(2, 1) = 0.0D0
      AM(1, 2) = 0.0D0
      AM(2, 2) = 1.0D0
      END
C
      SUBROUTINE MF(T, Q, V, FV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), V(2), FV(2), RPAR(*)
      FV(1) = 0.0D0
      FV(2) = 0.0D0
      END
C
C     The circle from (1, 0) to TOUT = 1 with the tolerances RT, AT
C     (INFO(2) = 1: vectors of length 2); X, IDID and the message.
      SUBROUTINE TRYVEC(IVEC, INTEG, RT, AT, X, IDID, MSG)
      EXTERNAL CF, CB, CG, CGX
      INTEGER IVEC, INTEG, IDID, INFO(20), IWORK(22), IPAR(2)
      DOUBLE PRECISION RT(2), AT(2), X(2), Y(2), RWORK(20), RPAR(2), T
      CHARACTER*(*) MSG
C     IWORK zeroed too: a start reads IWORK(19:22) to free what an
C     earlier problem left there (doc/api.md section 8)
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(2) = IVEC
      INFO(19) = INTEG
      T = 0.0D0
      X(1) = 1.0D0
      X(2) = 0.0D0
      IPAR(1) = 0
      IPAR(2) = 0
      CALL DREGDAE(CF, CB, CG, CGX, CGX, 2, 1, T, X, Y, 1.0D0, INFO,
     *     RT, AT, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL DREGDAEFREE(IWORK, 22)
      END
C
      SUBROUTINE VECTOR(NCHK)
      INTEGER NCHK(2), IDID
      DOUBLE PRECISION RT(2), AT(2), XS(2), XV(2), XL(2)
      CHARACTER*600 MSG
      RT(1) = 1.0D-6
      RT(2) = 1.0D-6
      AT(1) = 1.0D-6
      AT(2) = 1.0D-6
      CALL TRYVEC(0, 0, RT, AT, XS, IDID, MSG)
      CALL CHECK(IDID .GT. 0, 'scalar tolerances: success', NCHK)
      CALL TRYVEC(1, 0, RT, AT, XV, IDID, MSG)
      CALL CHECK(IDID .GT. 0 .AND. XV(1) .EQ. XS(1) .AND.
     *     XV(2) .EQ. XS(2), 'equal ATOL(i): the scalar run', NCHK)
      AT(2) = 1.0D-2
      CALL TRYVEC(1, 0, RT, AT, XL, IDID, MSG)
      CALL CHECK(IDID .GT. 0 .AND. (XL(1) .NE. XS(1) .OR.
     *     XL(2) .NE. XS(2)), 'ATOL(2) = 1e-2: another run', NCHK)
      RT(2) = 1.0D-5
      CALL TRYVEC(1, 0, RT, AT, XL, IDID, MSG)
      CALL CHECK(IDID .EQ. -33 .AND.
     *     INDEX(MSG, 'one relative tolerance') .GT. 0 .AND.
     *     INDEX(MSG, 'e.g. all 1.000000E-06') .GT. 0 .AND.
     *     INDEX(MSG, 'through ATOL') .GT. 0,
     *     'unequal RTOL(i) refused, saying what to do', NCHK)
C     INFO(19) = 3: Radau IIA (integrator radau) on the circle, x(1) =
C     (cos 1, sin 1) within 1e-4 at tolerances 1e-6 (measured 4e-7);
C     INFO(19) = 4 refused
      RT(2) = 1.0D-6
      AT(2) = 1.0D-6
      CALL TRYVEC(0, 3, RT, AT, XL, IDID, MSG)
      CALL CHECK(IDID .GT. 0 .AND. ABS(XL(1) - COS(1.0D0)) .LT. 1D-4
     *     .AND. ABS(XL(2) - SIN(1.0D0)) .LT. 1D-4,
     *     'INFO(19) = 3: radau reaches x(1)', NCHK)
      CALL TRYVEC(0, 4, RT, AT, XL, IDID, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'INFO(19)') .GT. 0,
     *     'INFO(19) = 4 refused', NCHK)
      END
C
C     ---- WARN --------------------------------------------------------
C     Example 5.1 (drivers/example_ex51.f: X' = 2 - T*Y, G = T*X -
C     T*(T+1), singular at T = 0, X = T + 1) from T = -1 to 1 with IDA.
      SUBROUTINE WARN(NCHK)
      INTEGER NCHK(2), INFO(20), IWORK(22), IDID, K, NWARN, NOTHER
      DOUBLE PRECISION RWORK(20), T, X(1), Y(1), TOUT(16), TWARN, TT
      CHARACTER*300 MSG, LINE
      LOGICAL PRINTD
      DATA TOUT /-0.9D0, -0.8D0, -0.7D0, -0.6D0, -0.5D0, -0.4D0,
     *     -0.3D0, -0.2D0, -0.1D0, -1.0D-2, -1.0D-3, -1.0D-4, -1.0D-5,
     *     -2.0D-6, 0.5D0, 1.0D0/
C     regdae_warn_unresolved with the default resolution_tol (1E4):
C     the direct method (INFO(16) = 3) with eps = 1E-14 (RWORK(11))
C     and gamma = 10 (RWORK(12)). G = T is independent of X, so the
C     ratio the solver tests depends on the sample times alone: at
C     T = -2E-6, the last output before the layer (T**2 < 100 eps),
C     it is 0.1 EXP(-10*0.1) / 2E-6 = 1.84E4 (the memory of |G| at
C     T = -0.1), at T = -1E-5 3.7E3: the call to T = -2E-6 warns.
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(16) = 3
      INFO(17) = 1
      INFO(19) = 1
      RWORK(11) = 1.0D-14
      RWORK(12) = 10.0D0
      OPEN (UNIT=22, STATUS='SCRATCH')
      INFO(20) = 22
      T = -1.0D0
      X(1) = 0.0D0
      NWARN = 0
      NOTHER = 0
      TWARN = 0.0D0
      DO 10 K = 1, 16
         CALL E51RUN(T, X, Y, TOUT(K), INFO, IDID, RWORK, IWORK)
         CALL DREGDAEMSG(IWORK, 22, MSG)
         IF (IDID .EQ. 6) THEN
            NWARN = NWARN + 1
            TWARN = TOUT(K)
            CALL CHECK(T .EQ. TOUT(K) .AND. INFO(1) .EQ. 1 .AND.
     *           IWORK(18) .EQ. 2, 'IDID 6: T = TOUT, INFO(1) = 1, '//
     *           'IWORK(18) = 2', NCHK)
            CALL CHECK(INDEX(MSG, 'approaching the singular '//
     *           'configuration') .GT. 0 .AND.
     *           INDEX(MSG, 'resolution_tol') .GT. 0,
     *           'IDID 6: DREGDAEMSG says why', NCHK)
         ELSE IF (IDID .NE. 3 .OR. MSG .NE. ' ' .OR.
     *           IWORK(18) .NE. 0) THEN
            NOTHER = NOTHER + 1
            WRITE (*, '(A, 1P, E10.2, A, I5, 2A)') '    TOUT', TOUT(K),
     *           ' IDID', IDID, ': ', MSG(1:LEN_TRIM(MSG))
         END IF
   10 CONTINUE
      CALL CHECK(NWARN .EQ. 1 .AND. TWARN .LT. 0.0D0,
     *     'one IDID 6, on the approach', NCHK)
      CALL CHECK(NOTHER .EQ. 0, 'the other calls: IDID 3, no '//
     *     'message', NCHK)
C     the integration went on to T = 1 (RTOL = ATOL = 1E-8: the error
C     measured is 4E-15; 1E-6 means a bug)
      CALL CHECK(T .EQ. 1.0D0 .AND. ABS(X(1) - 2.0D0) .LT. 1.0D-6,
     *     'after IDID 6: on to T = 1', NCHK)
C     the warning was printed on the unit of INFO(20) too
      REWIND (22)
      PRINTD = .FALSE.
      DO 20 K = 1, 100
         READ (22, '(A)', END=30) LINE
         IF (INDEX(LINE, 'DREGDAE-- approaching the singular') .GT. 0)
     *        PRINTD = .TRUE.
   20 CONTINUE
   30 CLOSE (22)
      CALL CHECK(PRINTD, 'IDID 6: the message printed', NCHK)
C     a refused call after the warning: its own message, then on
      INFO(20) = -1
      TT = T
      CALL E51RUN(T, X, Y, TT, INFO, IDID, RWORK, IWORK)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'is equal to T') .GT. 0
     *     .AND. IWORK(18) .EQ. -101, 'TOUT = T refused: its message',
     *     NCHK)
      INFO(1) = 2
      CALL E51RUN(T, X, Y, 1.5D0, INFO, IDID, RWORK, IWORK)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'INFO(1) = 2 must be')
     *     .GT. 0, 'INFO(1) = 2 refused: its message', NCHK)
      INFO(1) = 1
      CALL E51RUN(T, X, Y, 1.5D0, INFO, IDID, RWORK, IWORK)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. 3 .AND. MSG .EQ. ' ' .AND. T .EQ. 1.5D0,
     *     'INFO(1) = 1 after the refusals: IDID 3, no message', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
C     regdae_warn_multiplier_undefined: Baumgarte (INFO(16) = 1),
C     whose multiplier equation T**2 Y = ... is singular at T = 0
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(16) = 1
      INFO(17) = 1
      INFO(19) = 1
      T = -1.0D0
      X(1) = 0.0D0
      CALL E51RUN(T, X, Y, -0.5D0, INFO, IDID, RWORK, IWORK)
      CALL CHECK(IDID .EQ. 3, 'Baumgarte to T = -0.5: IDID 3', NCHK)
      CALL E51RUN(T, X, Y, 0.0D0, INFO, IDID, RWORK, IWORK)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. 4 .AND. IWORK(18) .EQ. 1 .AND.
     *     INFO(1) .EQ. 1 .AND. T .EQ. 0.0D0 .AND. Y(1) .NE. Y(1),
     *     'T = 0: IDID 4, Y = NaN', NCHK)
      CALL CHECK(INDEX(MSG, 'the multiplier at t = 0.000000E+00 is '//
     *     'undefined') .GT. 0, 'IDID 4: DREGDAEMSG says why', NCHK)
      CALL E51RUN(T, X, Y, 1.0D0, INFO, IDID, RWORK, IWORK)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. 3 .AND. MSG .EQ. ' ' .AND.
     *     ABS(X(1) - 2.0D0) .LT. 1.0D-6 .AND.
     *     ABS(Y(1) - 1.0D0) .LT. 1.0D-6, 'after IDID 4: on to T = 1',
     *     NCHK)
      CALL DREGDAEFREE(IWORK, 22)
C     a refusal after a failure: DREGDAEMSG gives the refusal's text,
C     not the failure's (X(1) = 0.5 at T = -1 violates G = 0)
      CALL CLEAR(INFO, RWORK, IWORK)
      T = -1.0D0
      X(1) = 0.5D0
      CALL E51RUN(T, X, Y, 0.0D0, INFO, IDID, RWORK, IWORK)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -12 .AND. INDEX(MSG, 'ic_tol') .GT. 0,
     *     'X0 inconsistent: IDID -12', NCHK)
      CALL E51RUN(T, X, Y, 0.0D0, INFO, IDID, RWORK, IWORK)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND.
     *     INDEX(MSG, 'INFO(1) = -1: the last call failed') .GT. 0
     *     .AND. INDEX(MSG, 'ic_tol') .EQ. 0 .AND. IWORK(18) .EQ. -101,
     *     'INFO(1) = -1 refused: its message, not -12''s', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
      END
C
C     One DREGDAE call on Example 5.1, RTOL = ATOL = 1E-8, to TOUT.
      SUBROUTINE E51RUN(T, X, Y, TOUT, INFO, IDID, RWORK, IWORK)
      EXTERNAL E51F, E51G, E51GX, E51GT
      INTEGER INFO(20), IDID, IWORK(22), IPAR(1)
      DOUBLE PRECISION T, X(1), Y(1), TOUT, RWORK(20), RPAR(1)
      CALL DREGDAE(E51F, E51GX, E51G, E51GX, E51GT, 1, 1, T, X, Y, TOUT,
     *     INFO, 1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR)
      END
C
      SUBROUTINE E51F(T, X, FX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(1), FX(1), RPAR(*)
      FX(1) = 2.0D0
      END
C
      SUBROUTINE E51G(T, X, GV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(1), GV(1), RPAR(*)
      GV(1) = T * X(1) - T * (T + 1.0D0)
      END
C
C     G_X = T, and B = T too (E51RUN passes this routine as B)
      SUBROUTINE E51GX(T, X, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(1), GM(1, 1), RPAR(*)
      GM(1, 1) = T
      END
C
      SUBROUTINE E51GT(T, X, GTV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(1), GTV(1), RPAR(*)
      GTV(1) = X(1) - 2.0D0 * T - 1.0D0
      END
C
C     ---- MAXORD ------------------------------------------------------
C     DREGDAEM on the circle of MECH with IDA (INFO(19) = 1) at orders
C     up to 2, 3 and 5 (INFO(9) = 1, IWORK(3)), and the default
C     (INFO(9) = 0, IWORK(3) = 1 ignored).
      SUBROUTINE MAXORD(NCHK)
      EXTERNAL MM, MF, CG, CGX
      INTEGER NCHK(2), INFO(20), IWORK(22), IDID, K, STEPS(4), IDIDS(4)
      INTEGER MAXO(4), IPAR(2), NRES(4)
      DOUBLE PRECISION RWORK(20), ERR(4), HOLD(4), T, Q(2), V(2),
     *     LAMBDA(1), RPAR(2)
      CHARACTER*300 MSG
      DATA MAXO /2, 3, 5, 0/
      DO 10 K = 1, 4
         CALL CLEAR(INFO, RWORK, IWORK)
         INFO(19) = 1
         IF (MAXO(K) .GT. 0) THEN
            INFO(9) = 1
            IWORK(3) = MAXO(K)
         ELSE
            IWORK(3) = 1
         END IF
         CALL MRUN(INFO, RWORK, IWORK, ERR(K), IDIDS(K))
         STEPS(K) = IWORK(11)
         NRES(K) = IWORK(12)
         HOLD(K) = RWORK(7)
         CALL DREGDAEFREE(IWORK, 22)
   10 CONTINUE
C     RTOL = ATOL = 1E-8 as in MECH; the global error of the low orders
C     gathers more over the 0.8 revolutions (measured 2.8E-6, 1.4E-6
C     and 2.1E-7 at orders 2, 3 and 5): 1E-5 is 3.5 times the largest
      CALL CHECK(ERR(1) .LT. 1.0D-5 .AND. ERR(2) .LT. 1.0D-5 .AND.
     *     ERR(3) .LT. 1.0D-5, 'MAXORD 2, 3, 5: error', NCHK)
      CALL CHECK(IDIDS(1) .EQ. 3 .AND. IDIDS(2) .EQ. 3 .AND.
     *     IDIDS(3) .EQ. 3, 'MAXORD 2, 3, 5: IDID 3', NCHK)
C     the order limited: the local error of order p falls like h^(p+1),
C     so lower orders take more steps for the same tolerance (measured
C     4356, 872 and 187 steps at orders 2, 3 and 5)
      CALL CHECK(STEPS(1) .GT. 2 * STEPS(2) .AND.
     *     STEPS(2) .GT. 2 * STEPS(3), 'steps: order 2 > 2 x order 3 >'
     *     // ' 4 x order 5', NCHK)
      CALL CHECK(STEPS(3) .EQ. STEPS(4) .AND. NRES(3) .EQ. NRES(4)
     *     .AND. HOLD(3) .EQ. HOLD(4) .AND. ERR(3) .EQ. ERR(4),
     *     'MAXORD 5 is the default run (steps, evaluations, last '
     *     // 'step, error)', NCHK)
      IF (ERR(1) .GE. 1.0D-5 .OR. STEPS(1) .LE. 2 * STEPS(2) .OR.
     *     STEPS(2) .LE. 2 * STEPS(3) .OR. STEPS(3) .NE. STEPS(4))
     *     WRITE (*, '(A, 4I8, 1P, 3E10.2)') '    steps, errors',
     *     STEPS, ERR(1), ERR(2), ERR(3)
C     MAXORD outside 1 ... 5: refused
      DO 20 K = 1, 2
         CALL CLEAR(INFO, RWORK, IWORK)
         INFO(9) = 1
         IWORK(3) = 6 * (K - 1)
         CALL CIRCLE0(T, Q, IPAR)
         V(1) = 0.0D0
         V(2) = 1.0D0
         CALL DREGDAEM(MM, MF, CG, CGX, CGX, 2, 1, T, Q, V, LAMBDA,
     *        1.0D0, INFO, 1.0D-8, 1.0D-8, IDID, RWORK, 20, IWORK, 22,
     *        RPAR, IPAR)
         CALL DREGDAEMSG(IWORK, 22, MSG)
         CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'MAXORD = IWORK(3)')
     *        .GT. 0, 'MAXORD 0 and 6 refused', NCHK)
         CALL DREGDAEFREE(IWORK, 22)
   20 CONTINUE
      END
C
C     ---- JAC ---------------------------------------------------------
C     KIND 1: DREGDAE(J) on the stiff circle of JF (N = 3, M = 1);
C     KIND 2: DREGDAEM(J) on the damped particle of DF; KIND 3: the
C     particle at index 2 (INFO(18) = 2). MODE 0: no JAC
C     (DREGDAE, DREGDAEM); 1: the right JAC; 2: a wrong one (one entry
C     of PD off: JJBAD, DJBAD). INFO(19) = 1 (IDA, whose Newton matrix
C     JAC enters), RTOL = ATOL = 1E-7, to T = 2 in steps of 0.25.
C     ERR(1), ERR(2): the largest errors of the state (X; Q, V) and of
C     the multiplier against the exact solution; X the end state; NF
C     the calls of F (FORCES).
      SUBROUTINE JRUN(KIND, MODE, RCHECK, ERR, X, IDID, NF, MSG)
      EXTERNAL JF, CB3, CG3, CGX3, JJ, JJBAD, MM, DF, DGX, DJ,
     *     DJBAD
      INTEGER KIND, MODE, IDID, NF, INFO(20), IWORK(22), IPAR(2), K
      DOUBLE PRECISION RCHECK, ERR(2), X(3), RWORK(20), RPAR(2), T,
     *     Y(1), V(2), TOUT
      CHARACTER*(*) MSG
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(19) = 1
      IF (KIND .EQ. 3) INFO(18) = 2
      IF (MODE .GT. 0) INFO(5) = 1
      RWORK(19) = RCHECK
      RPAR(1) = 1.0D4
      RPAR(2) = 0.0D0
      IPAR(1) = 0
      IPAR(2) = 0
      CALL JX0(T, X)
      V(1) = 0.0D0
      V(2) = 1.0D0
      ERR(1) = 0.0D0
      ERR(2) = 0.0D0
      MSG = ' '
      DO 10 K = 1, 8
         TOUT = 0.25D0 * K
         IF (KIND .EQ. 1 .AND. MODE .EQ. 0) THEN
            CALL DREGDAE(JF, CB3, CG3, CGX3, CGX3, 3, 1, T, X, Y, TOUT,
     *           INFO, 1.0D-7, 1.0D-7, IDID, RWORK, 20, IWORK, 22, RPAR,
     *           IPAR)
         ELSE IF (KIND .EQ. 1) THEN
            IF (MODE .EQ. 1) CALL DREGDAEJ(JF, CB3, CG3, CGX3, CGX3, 3,
     *           1, T, X, Y, TOUT, INFO, 1.0D-7, 1.0D-7, IDID, RWORK,
     *           20, IWORK, 22, RPAR, IPAR, JJ)
            IF (MODE .EQ. 2) CALL DREGDAEJ(JF, CB3, CG3, CGX3, CGX3, 3,
     *           1, T, X, Y, TOUT, INFO, 1.0D-7, 1.0D-7, IDID, RWORK,
     *           20, IWORK, 22, RPAR, IPAR, JJBAD)
         ELSE IF (MODE .EQ. 0) THEN
            CALL DREGDAEM(MM, DF, CG3, DGX, DGX, 2, 1, T, X, V, Y, TOUT,
     *           INFO, 1.0D-7, 1.0D-7, IDID, RWORK, 20, IWORK, 22, RPAR,
     *           IPAR)
         ELSE
            IF (MODE .EQ. 1) CALL DREGDAEMJ(MM, DF, CG3, DGX, DGX, 2, 1,
     *           T, X, V, Y, TOUT, INFO, 1.0D-7, 1.0D-7, IDID, RWORK,
     *           20, IWORK, 22, RPAR, IPAR, DJ)
            IF (MODE .EQ. 2) CALL DREGDAEMJ(MM, DF, CG3, DGX, DGX, 2, 1,
     *           T, X, V, Y, TOUT, INFO, 1.0D-7, 1.0D-7, IDID, RWORK,
     *           20, IWORK, 22, RPAR, IPAR, DJBAD)
         END IF
         IF (IDID .LT. 0) GO TO 20
         ERR(1) = MAX(ERR(1), ABS(X(1) - COS(T)), ABS(X(2) - SIN(T)))
         IF (KIND .EQ. 1) THEN
            ERR(1) = MAX(ERR(1), ABS(X(3) - SIN(T)))
            ERR(2) = MAX(ERR(2), ABS(Y(1) - 0.5D0 * SIN(T)**2))
         ELSE
            ERR(1) = MAX(ERR(1), ABS(V(1) + SIN(T)),
     *           ABS(V(2) - COS(T)))
            ERR(2) = MAX(ERR(2), ABS(Y(1) + 0.5D0))
         END IF
   10 CONTINUE
   20 CALL DREGDAEMSG(IWORK, 22, MSG)
      NF = IPAR(1)
      CALL DREGDAEFREE(IWORK, 22)
      END
C
      SUBROUTINE JACSUI(NCHK)
      EXTERNAL JF, CB3, CG3, CGX3, JJ, MM, DF, DGXBAD
      INTEGER NCHK(2), KIND, IDID0, IDID1, IDIDC, IDIDW, NF0, NF1, NFC,
     *     NFW, INFO(20), IWORK(22), IPAR(2), IDID
      DOUBLE PRECISION ERR0(2), ERR1(2), ERRC(2), ERRW(2), X0(3), X1(3),
     *     XC(3),
     *     XW(3), DIFF, RWORK(20), RPAR(2), T, X(3), Y(1), V(2)
      CHARACTER*300 MSG, MSGW
      CHARACTER*12 ENTRY(3)
      DATA ENTRY /'entry (2, 3)', 'entry (1, 4)', 'entry (1, 4)'/
      DO 10 KIND = 1, 3
         CALL JRUN(KIND, 0, 0.0D0, ERR0, X0, IDID0, NF0, MSG)
         CALL JRUN(KIND, 1, 0.0D0, ERR1, X1, IDID1, NF1, MSG)
         CALL JRUN(KIND, 1, 1.0D0, ERRC, XC, IDIDC, NFC, MSG)
         CALL JRUN(KIND, 2, 1.0D0, ERRW, XW, IDIDW, NFW, MSGW)
         DIFF = MAX(ABS(X1(1) - X0(1)), ABS(X1(2) - X0(2)))
         IF (KIND .EQ. 1) DIFF = MAX(DIFF, ABS(X1(3) - X0(3)))
C        RTOL = ATOL = 1E-7 over T in [0, 2]: 1E-5 is 100 RTOL for the
C        state (measured 1.5E-6 and 2.6E-6 without and with JAC on the
C        stiff circle, 9.9E-8 both on the particle, 5.7E-8 and 2.2E-7
C        at index 2); the multiplier is not in the error test and
C        carries the regularization's error (measured 7.0E-5 and 2.4E-5
C        on the circle, 7.6E-5 both on the particle, 3.6E-6 and 8.6E-6
C        at index 2): 1E-3
         CALL CHECK(IDID0 .EQ. 3 .AND. IDID1 .EQ. 3 .AND. IDIDC .EQ. 3,
     *        'JAC: IDID 3 without JAC, with it, with the check', NCHK)
         CALL CHECK(ERR0(1) .LT. 1.0D-5 .AND. ERR1(1) .LT. 1.0D-5 .AND.
     *        ERR0(2) .LT. 1.0D-3 .AND. ERR1(2) .LT. 1.0D-3,
     *        'JAC: exact to the tolerance with and without JAC', NCHK)
         CALL CHECK(DIFF .LT. 1.0D-5, 'JAC: the same X as without JAC'
     *        // ' within 100 RTOL', NCHK)
C        JAC in place of the difference quotients of F: N - 1 (2N - 1)
C        fewer calls of F per Jacobian (measured 1262 and 1073 calls on
C        the circle, 1485 and 1212 on the particle, 693 and 567 at
C        index 2)
         CALL CHECK(NF1 .LT. NF0, 'JAC: fewer calls of F', NCHK)
C        the check at the start costs calls of F, nothing else changes
         CALL CHECK(XC(1) .EQ. X1(1) .AND. XC(2) .EQ. X1(2) .AND.
     *        XC(3) .EQ. X1(3), 'JAC: the checked run is the run', NCHK)
         CALL CHECK(IDIDW .EQ. -116 .AND. INDEX(MSGW, 'check_jacobians'
     *        // ': JAC disagrees with the difference quotient of')
     *        .GT. 0 .AND. INDEX(MSGW, ENTRY(KIND)) .GT. 0,
     *        'JAC: a wrong JAC caught by check_jacobians, its entry '
     *        // 'named', NCHK)
         IF (ERR0(1) .GE. 1.0D-5 .OR. ERR1(1) .GE. 1.0D-5 .OR.
     *        ERR0(2) .GE. 1.0D-3 .OR. ERR1(2) .GE. 1.0D-3 .OR.
     *        DIFF .GE. 1.0D-5 .OR. NF1 .GE. NF0)
     *        WRITE (*, '(A, I2, 1P, 5E10.2, 2I8)')
     *        '    JAC kind, errors 0, 1, diff, F calls 0, 1', KIND,
     *        ERR0, ERR1, DIFF, NF0, NF1
         IF (IDIDW .NE. -116) WRITE (*, '(A, I5, 2A)') '    IDID ',
     *        IDIDW, ' ', MSGW(1:LEN_TRIM(MSGW))
   10 CONTINUE
C     INFO(5) = 1 in DREGDAE: refused, pointing to DREGDAEJ
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(5) = 1
      CALL JX0(T, X)
      CALL DREGDAE(JF, CB3, CG3, CGX3, CGX3, 3, 1, T, X, Y, 1.0D0,
     *     INFO, 1.0D-7, 1.0D-7, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'call DREGDAEJ') .GT. 0,
     *     'INFO(5) = 1 in DREGDAE: use DREGDAEJ', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
C     RWORK(19) = 1 in DREGDAEM checks GX too: a wrong GX is named
      CALL CLEAR(INFO, RWORK, IWORK)
      RWORK(19) = 1.0D0
      RPAR(1) = 1.0D4
      RPAR(2) = 0.0D0
      CALL CIRCLE0(T, X, IPAR)
      V(1) = 0.0D0
      V(2) = 1.0D0
      CALL DREGDAEM(MM, DF, CG3, DGXBAD, DGXBAD, 2, 1, T, X, V, Y,
     *     1.0D0, INFO, 1.0D-7, 1.0D-7, IDID, RWORK, 20, IWORK, 22,
     *     RPAR, IPAR)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -116 .AND. INDEX(MSG, 'GX disagrees with '
     *     // 'the difference quotient of G at entry (1, 1)') .GT. 0,
     *     'DREGDAEM: a wrong GX caught by check_jacobians', NCHK)
      IF (IDID .NE. -116) WRITE (*, '(A, I5, 2A)') '    IDID ', IDID,
     *     ' ', MSG(1:LEN_TRIM(MSG))
      CALL DREGDAEFREE(IWORK, 22)
C     JAC and RT together (DREGDAEJR, DREGDAEMJR): the root of X1 =
C     cos t at pi/2 (decreasing), then on to T = 2
      CALL JROOTS(NCHK)
C     RWORK(19) neither 0 nor 1: refused
      CALL CLEAR(INFO, RWORK, IWORK)
      RWORK(19) = 2.0D0
      CALL JX0(T, X)
      CALL DREGDAEJ(JF, CB3, CG3, CGX3, CGX3, 3, 1, T, X, Y, 1.0D0,
     *     INFO, 1.0D-7, 1.0D-7, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR,
     *     JJ)
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'RWORK(19)') .GT. 0,
     *     'RWORK(19) = 2 refused', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
      END
C
C     The start of the stiff circle: T = 0, X = (1, 0, 0).
      SUBROUTINE JX0(T, X)
      DOUBLE PRECISION T, X(3)
      T = 0.0D0
      X(1) = 1.0D0
      X(2) = 0.0D0
      X(3) = 0.0D0
      END
C
C     The stiff circle: N = 3, M = 1, K = RPAR(1),
C        x1' = -x2 + x1 x3^2 - 2 x1 y,  x2' = x1 + x2 x3^2 - 2 x2 y,
C        x3' = cos t - K (x3 - sin t) - K (x3 - sin t)^3,
C        0 = x1^2 + x2^2 - 1;
C     exact: x = (cos t, sin t, sin t), y = sin(t)^2 / 2. JF counts
C     its calls in IPAR(1).
      SUBROUTINE JF(T, X, FX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), FX(3), RPAR(*), E
      E = X(3) - SIN(T)
      FX(1) = -X(2) + X(1) * X(3)**2
      FX(2) = X(1) + X(2) * X(3)**2
      FX(3) = COS(T) - RPAR(1) * (E + E**3)
      IPAR(1) = IPAR(1) + 1
      END
C
C     df/dx of JF
      SUBROUTINE JJ(T, X, PD, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), PD(3, 3), RPAR(*)
      PD(1, 1) = X(3)**2
      PD(1, 2) = -1.0D0
      PD(1, 3) = 2.0D0 * X(1) * X(3)
      PD(2, 1) = 1.0D0
      PD(2, 2) = X(3)**2
      PD(2, 3) = 2.0D0 * X(2) * X(3)
      PD(3, 1) = 0.0D0
      PD(3, 2) = 0.0D0
      PD(3, 3) = -RPAR(1) * (1.0D0 + 3.0D0 * (X(3) - SIN(T))**2)
      END
C
C     JJ with PD(2, 3) wrong (the factor 2 forgotten, and off by 1)
      SUBROUTINE JJBAD(T, X, PD, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), PD(3, 3), RPAR(*)
      CALL JJ(T, X, PD, IRES, RPAR, IPAR)
      PD(2, 3) = X(2) * X(3) + 1.0D0
      END
C
      SUBROUTINE CB3(T, X, BX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), BX(3, 1), RPAR(*)
      BX(1, 1) = 2.0D0 * X(1)
      BX(2, 1) = 2.0D0 * X(2)
      BX(3, 1) = 0.0D0
      END
C
C     g = x1^2 + x2^2 - 1 (N = 2 or 3)
      SUBROUTINE CG3(T, X, GV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(*), GV(1), RPAR(*)
      GV(1) = X(1)**2 + X(2)**2 - 1.0D0
      END
C
      SUBROUTINE CGX3(T, X, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), GM(1, 3), RPAR(*)
      GM(1, 1) = 2.0D0 * X(1)
      GM(1, 2) = 2.0D0 * X(2)
      GM(1, 3) = 0.0D0
      END
C
C     The damped particle on the unit circle: M = I, the forces
C     f = -D w (1 + |w|^2), w = v - (-q2, q1), D = RPAR(1) / 10, which
C     vanish on the exact motion q = (cos t, sin t) (lambda = -1/2)
C     and damp any other; DF counts its calls in IPAR(1). M: MM; g:
C     CG3 (which reads Q(1), Q(2)).
      SUBROUTINE DGX(T, Q, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), GM(1, 2), RPAR(*)
      GM(1, 1) = 2.0D0 * Q(1)
      GM(1, 2) = 2.0D0 * Q(2)
      END
C
C     DGX with dg/dq1 off by 1 (G v0 = 0 still: the start is
C     consistent)
      SUBROUTINE DGXBAD(T, Q, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), GM(1, 2), RPAR(*)
      GM(1, 1) = 2.0D0 * Q(1) + 1.0D0
      GM(1, 2) = 2.0D0 * Q(2)
      END
C
      SUBROUTINE DF(T, Q, V, FV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), V(2), FV(2), RPAR(*), W1, W2, S
      W1 = V(1) + Q(2)
      W2 = V(2) - Q(1)
      S = 1.0D0 + W1**2 + W2**2
      FV(1) = -0.1D0 * RPAR(1) * W1 * S
      FV(2) = -0.1D0 * RPAR(1) * W2 * S
      IPAR(1) = IPAR(1) + 1
      END
C
C     PD = [df/dq, df/dv] of DF: -D ((1 + |w|^2) I + 2 w w^T) times
C     dw/dq = [0 1; -1 0] and dw/dv = I
      SUBROUTINE DJ(T, Q, V, PD, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), V(2), PD(2, 4), RPAR(*), W1, W2, S, D,
     *     A(2, 2)
      W1 = V(1) + Q(2)
      W2 = V(2) - Q(1)
      S = 1.0D0 + W1**2 + W2**2
      D = 0.1D0 * RPAR(1)
      A(1, 1) = -D * (S + 2.0D0 * W1 * W1)
      A(1, 2) = -D * 2.0D0 * W1 * W2
      A(2, 1) = A(1, 2)
      A(2, 2) = -D * (S + 2.0D0 * W2 * W2)
C     df/dq = A [0 1; -1 0]: column 1 is -A(:, 2), column 2 is A(:, 1)
      PD(1, 1) = -A(1, 2)
      PD(2, 1) = -A(2, 2)
      PD(1, 2) = A(1, 1)
      PD(2, 2) = A(2, 1)
C     df/dv = A
      PD(1, 3) = A(1, 1)
      PD(2, 3) = A(2, 1)
      PD(1, 4) = A(1, 2)
      PD(2, 4) = A(2, 2)
      END
C
C     DJ with df1/dv2 = PD(1, 4) wrong (its sign)
      SUBROUTINE DJBAD(T, Q, V, PD, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, Q(2), V(2), PD(2, 4), RPAR(*)
      CALL DJ(T, Q, V, PD, IRES, RPAR, IPAR)
      PD(1, 4) = -PD(1, 4) + 1.0D0
      END
C
C     ---- NONNEG ------------------------------------------------------
C     Robertson's kinetics as DREGDAE with M = 0 (RF, and RB, RG, RGX
C     of size 0) from (1, 0, 0) to T = 4E10 with INFO(3) = 1 (a return
C     at every step end), RTOL = 1E-3, ATOL = 1E-6, INFO(10) = NONNEG,
C     INFO(19) = INTEG: XMIN the smallest value of any component at the
C     step ends, X the end state, IDID and the message.
      SUBROUTINE RROB(NONNG, INTEG, X, XMIN, IDID, MSG)
      EXTERNAL RF, RB, RG, RGX
      INTEGER NONNG, INTEG, IDID, INFO(20), IWORK(22), IPAR(1), K
      DOUBLE PRECISION X(3), XMIN, RWORK(20), RPAR(1), T, Y(1)
      CHARACTER*(*) MSG
      CALL CLEAR(INFO, RWORK, IWORK)
      INFO(3) = 1
      INFO(10) = NONNG
      INFO(19) = INTEG
      T = 0.0D0
      X(1) = 1.0D0
      X(2) = 0.0D0
      X(3) = 0.0D0
      IF (NONNG .EQ. 2) X(2) = -1.0D-9
      IF (NONNG .EQ. 2) INFO(10) = 1
      XMIN = 0.0D0
      IDID = 1
      DO WHILE (IDID .EQ. 1)
         CALL DREGDAE(RF, RB, RG, RGX, RGX, 3, 0, T, X, Y, 4.0D10,
     *        INFO, 1.0D-3, 1.0D-6, IDID, RWORK, 20, IWORK, 22, RPAR,
     *        IPAR)
         DO 10 K = 1, 3
            IF (IDID .GT. 0) XMIN = MIN(XMIN, X(K))
   10    CONTINUE
      END DO
      CALL DREGDAEMSG(IWORK, 22, MSG)
      CALL DREGDAEFREE(IWORK, 22)
      END
C
      SUBROUTINE NONNEG(NCHK)
      INTEGER NCHK(2), IDID0, IDID1, IDID, K
      DOUBLE PRECISION X0(3), X1(3), XMIN0, XMIN1, XREF(3), ERR, SUM
      CHARACTER*300 MSG
C     Robertson at T = 4E10 (the reference of SUNDIALS' cvRoberts_dns)
      DATA XREF /5.2083D-8, 2.0833D-13, 0.99999995D0/
      CALL RROB(0, 1, X0, XMIN0, IDID0, MSG)
      CALL RROB(1, 1, X1, XMIN1, IDID1, MSG)
      ERR = 0.0D0
      SUM = X1(1) + X1(2) + X1(3)
      DO 10 K = 1, 3
         ERR = MAX(ERR, ABS(X1(K) - XREF(K)))
   10 CONTINUE
C     where it matters: without INFO(10) a component goes negative and
C     the run blows up (measured: X1 down to -1.9E7 at step ends)
      CALL CHECK(XMIN0 .LT. 0.0D0, 'NONNEG: negative without INFO(10)',
     *     NCHK)
      CALL CHECK(IDID1 .EQ. 3 .AND. XMIN1 .GE. 0.0D0,
     *     'NONNEG: INFO(10) = 1 keeps every step end >= 0', NCHK)
C     ATOL = 1E-6: the end state within 10 ATOL of the reference
C     (measured 5.2E-8), and X1 + X2 + X3 = 1 kept to 10 ATOL
      CALL CHECK(ERR .LT. 1.0D-5 .AND. ABS(SUM - 1.0D0) .LT. 1.0D-5,
     *     'NONNEG: the end state is the reference''s', NCHK)
      IF (XMIN1 .LT. 0.0D0 .OR. ERR .GE. 1.0D-5 .OR. IDID1 .NE. 3)
     *     WRITE (*, '(A, 2I5, 1P, 4E11.3)')
     *     '    IDID, min 0, 1, end error', IDID0, IDID1, XMIN0, XMIN1,
     *     ERR
C     INFO(19) = 0 (auto) runs IDA throughout: the same run as 1
      CALL RROB(1, 0, X0, XMIN0, IDID0, MSG)
      CALL CHECK(IDID0 .EQ. 3 .AND. X0(1) .EQ. X1(1) .AND. X0(2) .EQ.
     *     X1(2) .AND. X0(3) .EQ. X1(3),
     *     'NONNEG: INFO(19) = 0 is IDA', NCHK)
C     dopri5 has no constraint option: refused, saying what to set
      CALL RROB(1, 2, X0, XMIN0, IDID, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'IDASetConstraints')
     *     .GT. 0 .AND. INDEX(MSG, 'set INFO(19) = 0 or 1') .GT. 0,
     *     'NONNEG: INFO(19) = 2 refused', NCHK)
C     a negative component at the start: refused
      CALL RROB(2, 1, X0, XMIN0, IDID, MSG)
      CALL CHECK(IDID .EQ. -33 .AND. INDEX(MSG, 'X(2) = -1.000000E-09')
     *     .GT. 0, 'NONNEG: X(2) < 0 at the start refused', NCHK)
      IF (IDID .NE. -33) WRITE (*, '(A, I5, 2A)') '    IDID ', IDID,
     *     ' ', MSG(1:LEN_TRIM(MSG))
      END
C
C     Robertson's kinetics: x1' = -0.04 x1 + 1E4 x2 x3, x3' = 3E7 x2^2,
C     x2' = -x1' - x3'.
      SUBROUTINE RF(T, X, FX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), FX(3), RPAR(*)
      FX(1) = -0.04D0 * X(1) + 1.0D4 * X(2) * X(3)
      FX(3) = 3.0D7 * X(2)**2
      FX(2) = -FX(1) - FX(3)
      END
C
C     B, G and GX of size 0 (M = 0): nothing to set
      SUBROUTINE RB(T, X, BX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), BX(*), RPAR(*)
      END
C
      SUBROUTINE RG(T, X, GV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), GV(*), RPAR(*)
      END
C
      SUBROUTINE RGX(T, X, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(3), GM(*), RPAR(*)
      END
C
C     DREGDAEJR on the stiff circle, DREGDAEMJR on the damped particle
C     (INFO(5) = 1, INFO(19) = 1, RTOL = ATOL = 1E-7), RT = X1 (JRT):
C     IDID = 5 at pi/2 with JROOT(1) = -1, then IDID = 3 at T = 2.
      SUBROUTINE JROOTS(NCHK)
      EXTERNAL JF, CB3, CG3, CGX3, JJ, MM, DF, DGX, DJ, JRT
      INTEGER NCHK(2), KIND, INFO(20), IWORK(22), IPAR(2), IDID, K,
     *     JROOT(1), IDIDS(3), JR
      DOUBLE PRECISION RWORK(20), RPAR(2), T, X(3), Y(1), V(2), TROOT
      DO 20 KIND = 1, 2
         CALL CLEAR(INFO, RWORK, IWORK)
         INFO(5) = 1
         INFO(19) = 1
         RPAR(1) = 1.0D4
         RPAR(2) = 0.0D0
         IPAR(1) = 0
         IPAR(2) = 0
         CALL JX0(T, X)
         V(1) = 0.0D0
         V(2) = 1.0D0
         TROOT = 0.0D0
         JR = 0
         DO 10 K = 1, 3
            IF (KIND .EQ. 1) CALL DREGDAEJR(JF, CB3, CG3, CGX3, CGX3, 3,
     *           1, T, X, Y, 2.0D0, INFO, 1.0D-7, 1.0D-7, IDIDS(K),
     *           RWORK, 20, IWORK, 22, RPAR, IPAR, JJ, JRT, 1, JROOT)
            IF (KIND .EQ. 2) CALL DREGDAEMJR(MM, DF, CG3, DGX, DGX, 2,
     *           1, T, X, V, Y, 2.0D0, INFO, 1.0D-7, 1.0D-7, IDIDS(K),
     *           RWORK, 20, IWORK, 22, RPAR, IPAR, DJ, JRT, 1, JROOT)
            IF (IDIDS(K) .EQ. 5) THEN
               TROOT = T
               JR = JROOT(1)
            END IF
            IF (IDIDS(K) .NE. 5) GO TO 15
   10    CONTINUE
   15    IDID = IDIDS(MIN(K, 3))
C        the root of X1 = cos t is as accurate as X1 (|X1'| = 1 there):
C        100 RTOL as for the state in JACSUI (measured 2.2E-6 on the
C        circle, 3.5E-8 on the particle)
         CALL CHECK(IDIDS(1) .EQ. 5 .AND. JR .EQ. -1 .AND.
     *        ABS(TROOT - 2.0D0 * ATAN(1.0D0)) .LT. 1.0D-5,
     *        'JAC with RT: IDID 5 at pi/2, JROOT -1', NCHK)
         CALL CHECK(IDID .EQ. 3 .AND. T .EQ. 2.0D0,
     *        'JAC with RT: then IDID 3 at TOUT', NCHK)
         IF (IDIDS(1) .NE. 5 .OR. IDID .NE. 3 .OR. JR .NE. -1 .OR.
     *        ABS(TROOT - 2.0D0 * ATAN(1.0D0)) .GE. 1.0D-5)
     *        WRITE (*, '(A, I2, 3I5, 1P, E12.4)')
     *        '    kind, JROOT, IDIDs, root', KIND, JR, IDIDS(1), IDID,
     *        TROOT - 2.0D0 * ATAN(1.0D0)
         CALL DREGDAEFREE(IWORK, 22)
   20 CONTINUE
      END
C
C     RT of JROOTS: X1
      SUBROUTINE JRT(N, T, X, V, NRT, RVAL, RPAR, IPAR)
      INTEGER N, NRT, IPAR(*)
      DOUBLE PRECISION T, X(N), V(N), RVAL(NRT), RPAR(*)
      RVAL(1) = X(1)
      END
C
C     ---- LINEAR ------------------------------------------------------
C     DREGDAE on theory_problems' S1 (drivers/problems): x' = A x + q
C     + B y, 0 = C x + r, C = T E^T with E = (COS T, SIN T), B = C^T
C     (GB = T**2: singular at T = 0), A = [-1/2, 1; -1, -1/2],
C     x* = (1 + SIN(T)/2, COS 2T), q and r from x* (q = x*' - A x* -
C     S E, S = 1 + SIN T; r = -C x*), from T = -1 through T = 0 in
C     steps of 0.01 to T = 0.2 (T = 0 an output), methods
C     trust_region (INFO(16) = 2) and direct (3), RTOL = ATOL = 1E-4,
C     1E-6, 1E-8. Issue 19: the direct method at 1E-8 returned X far
C     off at T = 0 with IDID = 3. Each output within the bound
C     (|X_I - X*_I| / (RTOL |X*_I| + ATOL) <= 10, the trust driver's
C     for this family) or a warning (IDID 4 or 6) with DREGDAEMSG
C     saying why (a singular pass not resolved), at this output or
C     before it. Measured: the largest error before the first warning
C     0.9 ... 2.7 weights; at T = 0 after it up to 8E4 (direct, 1E-8).
      SUBROUTINE LINEAR(NCHK)
      INTEGER NCHK(2), INFO(20), IWORK(22), IDID, K, IM, IR, NWARN,
     *     NBAD, METH(2)
      DOUBLE PRECISION RWORK(20), T, X(2), Y(1), TOUT, RT(3), ERR,
     *     WORST, XS(2), WBEF, TWARN
      CHARACTER*300 MSG
      CHARACTER*60 WHAT
      DATA METH /2, 3/
      DATA RT /1.0D-4, 1.0D-6, 1.0D-8/
      DO 30 IM = 1, 2
         DO 20 IR = 1, 3
            CALL CLEAR(INFO, RWORK, IWORK)
            INFO(16) = METH(IM)
            INFO(17) = 1
            T = -1.0D0
            CALL S1X(T, X)
            NWARN = 0
            NBAD = 0
            WORST = 0.0D0
            WBEF = 0.0D0
            TWARN = 9.0D0
            DO 10 K = 1, 120
               TOUT = -1.0D0 + 0.01D0 * K
               IF (K .EQ. 100) TOUT = 0.0D0
               CALL S1RUN(T, X, Y, TOUT, INFO, RT(IR), IDID, RWORK,
     *              IWORK)
               IF (IDID .LT. 0) GO TO 15
               IF (IDID .EQ. 4 .OR. IDID .EQ. 6) THEN
                  CALL DREGDAEMSG(IWORK, 22, MSG)
                  IF (INDEX(MSG, 'singular') .GT. 0) THEN
                     NWARN = NWARN + 1
                     IF (NWARN .EQ. 1) TWARN = T
                  END IF
               END IF
               CALL S1X(T, XS)
               ERR = MAX(ABS(X(1) - XS(1)) / (RT(IR) * ABS(XS(1))
     *              + RT(IR)), ABS(X(2) - XS(2)) / (RT(IR)
     *              * ABS(XS(2)) + RT(IR)))
               WORST = MAX(WORST, ERR)
               IF (NWARN .EQ. 0) WBEF = MAX(WBEF, ERR)
               IF (ERR .GT. 10.0D0 .AND. NWARN .EQ. 0) NBAD = NBAD + 1
   10       CONTINUE
   15       WRITE (*, '(A, I2, A, 1P, E8.1, A, I4, A, E9.2, A, I3, A,
     *           E9.2, A, E9.2)') '    S1 INFO(16) =', METH(IM),
     *           ' RTOL', RT(IR), ' IDID', IDID, ' max err', WORST,
     *           ' warnings', NWARN, ' the first at T =', TWARN,
     *           ', max err before it', WBEF
            WRITE (WHAT, '(A, I1, A, 1P, E8.1)') 'S1 INFO(16) = ',
     *           METH(IM), ', RTOL ', RT(IR)
            CALL CHECK(IDID .GT. 0 .AND. ABS(T - 0.2D0) .LT. 1.0D-12,
     *           WHAT(1:33)//
     *           ': on to T = 0.2', NCHK)
            CALL CHECK(NBAD .EQ. 0, WHAT(1:33)//': within 10 or '//
     *           'a warning before', NCHK)
            CALL DREGDAEFREE(IWORK, 22)
   20    CONTINUE
   30 CONTINUE
      END
C
C     One DREGDAE call on S1, RTOL = ATOL = TOL, to TOUT.
      SUBROUTINE S1RUN(T, X, Y, TOUT, INFO, TOL, IDID, RWORK, IWORK)
      EXTERNAL S1F, S1G, S1GX, S1GT
      INTEGER INFO(20), IDID, IWORK(22), IPAR(1)
      DOUBLE PRECISION T, X(2), Y(1), TOUT, TOL, RWORK(20), RPAR(1)
      CALL DREGDAE(S1F, S1GX, S1G, S1GX, S1GT, 2, 1, T, X, Y, TOUT,
     *     INFO, TOL, TOL, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR)
      END
C
C     x*(T) and x*'(T) of S1.
      SUBROUTINE S1X(T, XS)
      DOUBLE PRECISION T, XS(2)
      XS(1) = 1.0D0 + 0.5D0 * SIN(T)
      XS(2) = COS(2.0D0 * T)
      END
C
      SUBROUTINE S1XD(T, XD)
      DOUBLE PRECISION T, XD(2)
      XD(1) = 0.5D0 * COS(T)
      XD(2) = -2.0D0 * SIN(2.0D0 * T)
      END
C
C     f = A x + q, q = x*' - A x* - (1 + SIN T) E
      SUBROUTINE S1F(T, X, FX, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(2), FX(2), RPAR(*), XS(2), XD(2), S
      CALL S1X(T, XS)
      CALL S1XD(T, XD)
      S = 1.0D0 + SIN(T)
      FX(1) = -0.5D0 * (X(1) - XS(1)) + (X(2) - XS(2)) + XD(1)
     *     - S * COS(T)
      FX(2) = -(X(1) - XS(1)) - 0.5D0 * (X(2) - XS(2)) + XD(2)
     *     - S * SIN(T)
      END
C
C     g = T E . (x - x*)
      SUBROUTINE S1G(T, X, GV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(2), GV(1), RPAR(*), XS(2)
      CALL S1X(T, XS)
      GV(1) = T * (COS(T) * (X(1) - XS(1)) + SIN(T) * (X(2) - XS(2)))
      END
C
C     G_X = T E^T, and B = C^T = T E (S1RUN passes this routine as B:
C     GM(1, 2) and BX(2, 1) have the same storage)
      SUBROUTINE S1GX(T, X, GM, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(2), GM(1, 2), RPAR(*)
      GM(1, 1) = T * COS(T)
      GM(1, 2) = T * SIN(T)
      END
C
C     g_t = (E + T E') . (x - x*) - T E . x*'
      SUBROUTINE S1GT(T, X, GTV, IRES, RPAR, IPAR)
      INTEGER IRES, IPAR(*)
      DOUBLE PRECISION T, X(2), GTV(1), RPAR(*), XS(2), XD(2)
      CALL S1X(T, XS)
      CALL S1XD(T, XD)
      GTV(1) = (COS(T) - T * SIN(T)) * (X(1) - XS(1))
     *     + (SIN(T) + T * COS(T)) * (X(2) - XS(2))
     *     - T * (COS(T) * XD(1) + SIN(T) * XD(2))
      END
C
C     ---- ESTIMATE ----------------------------------------------------
C     RWORK(16) = 1 (error_estimate=yes) on the circle (DREGDAE, CF,
C     CB, CG, CGX: x = (COS T, SIN T)), RTOL = ATOL = 1E-6, to T = 0.5,
C     1, ..., 5: RWORK(17), the estimated error of X in error weights,
C     within a factor 10 of the true one, max_I |X_I - x*_I| / (RTOL
C     |X_I| + ATOL), at every output; without RWORK(16) = 1, -1.
      SUBROUTINE ESTIM(NCHK)
      INTEGER NCHK(2), INFO(20), IWORK(22), IDID, K, IPAR(2), NOK
      DOUBLE PRECISION RWORK(20), T, X(2), Y(1), TOUT, TOL, TRUE,
     *     RATIO, RMIN, RMAX, RPAR(2)
      TOL = 1.0D-6
      CALL CLEAR(INFO, RWORK, IWORK)
      RWORK(16) = 1.0D0
      CALL CIRCLE0(T, X, IPAR)
      NOK = 0
      RMIN = 1.0D30
      RMAX = 0.0D0
      DO 10 K = 1, 10
         TOUT = 0.5D0 * K
         CALL ECALL(T, X, Y, TOUT, INFO, TOL, IDID, RWORK, IWORK,
     *        RPAR, IPAR)
         IF (IDID .LT. 0) GO TO 20
         TRUE = MAX(ABS(X(1) - COS(T)) / (TOL * ABS(X(1)) + TOL),
     *        ABS(X(2) - SIN(T)) / (TOL * ABS(X(2)) + TOL))
         RATIO = RWORK(17) / TRUE
         RMIN = MIN(RMIN, RATIO)
         RMAX = MAX(RMAX, RATIO)
         IF (IDID .EQ. 3 .AND. RATIO .GE. 0.1D0 .AND. RATIO .LE. 10.0D0)
     *        NOK = NOK + 1
   10 CONTINUE
   20 WRITE (*, '(A, I3, A, 1P, E10.3, A, E10.3)') '    outputs', NOK,
     *     ' of 10 within 10x; RWORK(17)/true error', RMIN, ' ...', RMAX
      CALL CHECK(NOK .EQ. 10, 'RWORK(17) within 10x of the true '//
     *     'error at every output', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
C     off: RWORK(17) = -1
      CALL CLEAR(INFO, RWORK, IWORK)
      CALL CIRCLE0(T, X, IPAR)
      CALL ECALL(T, X, Y, 1.0D0, INFO, TOL, IDID, RWORK, IWORK,
     *     RPAR, IPAR)
      CALL CHECK(IDID .EQ. 3 .AND. RWORK(17) .EQ. -1.0D0,
     *     'RWORK(16) = 0: RWORK(17) = -1', NCHK)
      CALL DREGDAEFREE(IWORK, 22)
      END
C
C     One DREGDAE call on the circle, RTOL = ATOL = TOL, to TOUT.
      SUBROUTINE ECALL(T, X, Y, TOUT, INFO, TOL, IDID, RWORK, IWORK,
     *     RPAR, IPAR)
      EXTERNAL CF, CB, CG, CGX
      INTEGER INFO(20), IDID, IWORK(22), IPAR(2)
      DOUBLE PRECISION T, X(2), Y(1), TOUT, TOL, RWORK(20), RPAR(2)
      CALL DREGDAE(CF, CB, CG, CGX, CGX, 2, 1, T, X, Y, TOUT, INFO,
     *     TOL, TOL, IDID, RWORK, 20, IWORK, 22, RPAR, IPAR)
      END
