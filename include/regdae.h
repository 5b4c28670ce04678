/*
 * regdae.h: the C interface of regdae, regularized higher-index DAEs with
 * rank-deficient or singular constraints (Petzold, Ren & Maly, SIAM J. Sci.
 * Comput. 18(3), 1997) on SUNDIALS IDA.
 *
 * C99. A thin layer over the Fortran API (doc/api.md): the same problems,
 * options, statuses and messages. Implemented in Fortran (src/regdae_c_api.f90);
 * link with the regdae library and its Fortran, SUNDIALS and LAPACK libraries
 * (CMake: target_link_libraries(prog PRIVATE regdae::regdae)).
 *
 * Use:
 *   regdae_solver *s = regdae_create();
 *   regdae_set_first_order(s, n, m, f, b, g, gx, NULL, &my_data);
 *   regdae_set_rtol(s, 1e-8);                 (or regdae_set_option(s, "rtol", "1e-8"))
 *   regdae_init(s, t0, x0, n, NULL, 0);
 *   regdae_advance(s, tout, x, n, y, m, NULL, 0);
 *   regdae_destroy(&s);
 *
 * Conventions:
 * - Every function that can fail returns a status: REGDAE_SUCCESS (0), a
 *   warning (> 0: the result is usable) or an error (< 0); regdae_message(s)
 *   then says what and where. Status codes are those of src/regdae_status.f90.
 * - NULL pointers, lengths that do not match the problem and unknown option keys
 *   give REGDAE_ERR_BAD_INPUT and a message naming the argument; a NULL handle
 *   gives REGDAE_ERR_BAD_INPUT alone (there is nowhere to keep a message:
 *   regdae_message(NULL) is a static text saying so). regdae_status_string(status)
 *   describes any status without a handle.
 * - Every array comes with its length; a length must equal the problem's size.
 * - Matrices are stored column by column (Fortran and LAPACK order): entry
 *   (i, j), 0-based, of an r x c matrix a is a[i + j*r].
 * - Threads: all state of a solver lives in its handle (regdae's sources declare
 *   no global or static variable that is written; the static texts of
 *   regdae_version, regdae_status_string and regdae_message(NULL) are never
 *   written), and SUNDIALS' serial vectors and IDA keep theirs in their own
 *   objects. One handle is used by one thread at a time (calls on a handle are
 *   not synchronized); its callbacks run in the thread that called it. Separate
 *   handles in separate threads: ctest capi.threads runs two handles in two POSIX
 *   threads on the same problems and gets what one handle run serially gets, bit
 *   for bit. One defect of the compiler stands in the way of more: gfortran 12
 *   keeps the length of a text that a function returns in a static variable
 *   (valgrind --tool=helgrind reports races on these, slen.N, in regdae_init,
 *   regdae_advance and regdae_set_real_option, and on nothing else), so texts built at the same moment
 *   in two threads may come out with a wrong length. Until the library is built
 *   with a compiler without it: read messages, and set options (the setters pass
 *   values as text), from one thread at a time; the integration itself does not
 *   depend on those texts (the test above).
 * - Callbacks return 0 on success, > 0 for a recoverable failure (the integrator
 *   retries with a smaller step: e.g. x left the domain of f) and < 0 to stop the
 *   integration (REGDAE_ERR_USER_CALLBACK; the message names the callback, the
 *   value it returned and the time). user_data is passed through untouched.
 */
#pragma once
#ifndef REGDAE_H
#define REGDAE_H

#include <float.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Version ----------------------------------------------------------------- */

/** The version of this header: CMakeLists.txt's project(VERSION) (ctest capi.version_cmake; capi.version checks the library against the header).
 *  regdae_version() gives the library's at run time. */
#define REGDAE_VERSION_MAJOR 0
#define REGDAE_VERSION_MINOR 1
#define REGDAE_VERSION_PATCH 0

/* ---- Status codes (src/regdae_status.f90; doc/api.md section 4) ------------ */

/** Success. */
#define REGDAE_SUCCESS 0
/** Warning: x(tout) is valid, but the multiplier is undefined at tout (y = NaN). */
#define REGDAE_WARN_MULTIPLIER_UNDEFINED 1
/** Warning: near a singular configuration passed the tolerance may not be met: the pass check's levels
 *  did not agree within pass_tol (or outputs interpolated inside a step came from a level found off),
 *  the error on the approach exceeded resolution_tol times the tolerance, or (order 3, 4) the Taylor
 *  weights' regularization layer grew the errors; regdae_message says which and where. */
#define REGDAE_WARN_UNRESOLVED 2
/** regdae_advance returned at a root of an event function that stops (regdae_set_events): x there; which
 *  functions: regdae_get_roots. Not a failure: the next regdae_advance goes on from the root. */
#define REGDAE_ROOT_FOUND 3
/** Invalid argument or option: NULL pointer, wrong length, unknown key, bad value. */
#define REGDAE_ERR_BAD_INPUT -101
/** x0 (and v0) violate g(x0, t0) = 0 (G v0 + g_t = 0) beyond ic_tol. */
#define REGDAE_ERR_INCONSISTENT_IC -102
/** A callback returned < 0 (or > 0 at the initial point). */
#define REGDAE_ERR_USER_CALLBACK -103
/** method direct: GB + eps I is not symmetric positive definite. */
#define REGDAE_ERR_NOT_PSD -104
/** A matrix that must be invertible is singular (Baumgarte's GB at t0). */
#define REGDAE_ERR_SINGULAR -105
/** LAPACK reported an illegal argument (a bug). */
#define REGDAE_ERR_LAPACK -106
/** Creating or setting up an IDA object failed. */
#define REGDAE_ERR_SUNDIALS -107
/** The integrator failed (error test or convergence failures, max_steps, ...). */
#define REGDAE_ERR_INTEGRATION -108
/** regdae_advance without a successful regdae_init. */
#define REGDAE_ERR_NOT_INITIALIZED -109
/** NaN or Inf in a computed quantity. */
#define REGDAE_ERR_NONFINITE -110
/** A mechanical problem's M(q) is not symmetric positive definite. */
#define REGDAE_ERR_MASS_MATRIX -111
/** The velocity jumped across a singular configuration (probably a branch change). */
#define REGDAE_ERR_BRANCH -112
/** max |g(x, t)| exceeded drift_tol. */
#define REGDAE_ERR_DRIFT -113
/** The invariant changed by more than invariant_tol. */
#define REGDAE_ERR_INVARIANT -114
/** A matrix has a nonzero outside the declared pattern (or, Fortran's mass_constant, an M declared constant varies). */
#define REGDAE_ERR_STRUCTURE -115
/** check_jacobians: G or the Newton matrix disagrees with difference quotients. */
#define REGDAE_ERR_JACOBIAN -116
/** The work-energy balance of a mechanical problem failed. */
#define REGDAE_ERR_WORK -117
/** The system refused an allocation (out of memory); the message names what. */
#define REGDAE_ERR_MEMORY -118

/* ---- Option codes (src/regdae_options.f90; doc/api.md section 2) ----------- */

/** The value of a real option that regdae chooses itself (the text "auto"). */
#define REGDAE_AUTO (-DBL_MAX)

/** method: the regularization (default trust_region). */
#define REGDAE_METHOD_BAUMGARTE 1
#define REGDAE_METHOD_TRUST_REGION 2
#define REGDAE_METHOD_DIRECT 3

/** formulation: what the implicit integrator integrates (IDA: all three; Radau: eliminated or
 *  augmented; default auto). */
#define REGDAE_FORMULATION_AUTO 0
#define REGDAE_FORMULATION_MULTIPLIER 1
#define REGDAE_FORMULATION_ELIMINATED 2
#define REGDAE_FORMULATION_AUGMENTED 3

/** linear_solver: IDA's linear solver (default auto). */
#define REGDAE_LINEAR_SOLVER_AUTO 0
#define REGDAE_LINEAR_SOLVER_DENSE 1
#define REGDAE_LINEAR_SOLVER_BAND 2
#define REGDAE_LINEAR_SOLVER_SPARSE 3

/** lsq: the damped least-squares solver (default auto; CHECKED is what auto resolves to). */
#define REGDAE_LSQ_AUTO 0
#define REGDAE_LSQ_NORMAL 1
#define REGDAE_LSQ_STACKED 2
#define REGDAE_LSQ_CHECKED 3

/** exclusion: how y leaves IDA's error test (default suppress). */
#define REGDAE_EXCLUSION_SUPPRESS 1
#define REGDAE_EXCLUSION_WEIGHTS 2
#define REGDAE_EXCLUSION_OFF 3

/** integrator (default auto). */
#define REGDAE_INTEGRATOR_AUTO 0
#define REGDAE_INTEGRATOR_IDA 1
#define REGDAE_INTEGRATOR_DOPRI5 2
#define REGDAE_INTEGRATOR_RADAU 3

/** excluded: index 3, what leaves the error test (default y). */
#define REGDAE_EXCLUDED_Y 1
#define REGDAE_EXCLUDED_VY 2

/** The patterns a mechanical problem may declare (regdae_set_pattern). */
#define REGDAE_PATTERN_MASS 1       /* M, n x n */
#define REGDAE_PATTERN_CONSTRAINT 2 /* G, m x n */
#define REGDAE_PATTERN_FORCE_Q 3    /* d(f - M(q) a)/dq for any a, n x n */
#define REGDAE_PATTERN_FORCE_V 4    /* df/dq', n x n */

/* ---- Types ------------------------------------------------------------------ */

/** A solver: opaque; create with regdae_create, free with regdae_destroy. */
typedef struct regdae_solver regdae_solver;

/**
 * A routine of (t, x): writes out and returns 0 (ok), > 0 (recoverable) or < 0 (stop).
 * x has length n; out has the length of the value (f: n; g, g_t: m; B: n x m;
 * G: m x n; M: n x n; a pattern's values: its number of entries), column-major.
 */
typedef int (*regdae_point_fn)(double t, const double *x, double *out, void *user_data);

/**
 * A routine of (t, x, v) (x and v of length n): the f and B of a second-order
 * problem, the forces of a mechanical one, the curvature (length m), the
 * invariant (one value). Same return convention.
 */
typedef int (*regdae_motion_fn)(double t, const double *x, const double *v, double *out, void *user_data);

/** The options (solver_options of the Fortran API, field for field; doc/api.md section 2). */
typedef struct regdae_options {
    int method;                /**< REGDAE_METHOD_* */
    int formulation;           /**< REGDAE_FORMULATION_* */
    int lsq;                   /**< REGDAE_LSQ_* */
    int exclusion;             /**< REGDAE_EXCLUSION_* */
    double gamma;              /**< Baumgarte weight, or REGDAE_AUTO */
    double eps;                /**< damping of trust_region and direct, or REGDAE_AUTO */
    double rtol;               /**< relative tolerance */
    double atol;               /**< absolute tolerance (on x; at index 3 on (x, v)) */
    int stop_at_output;        /**< 1: steps end at every output time */
    int max_steps;             /**< steps per regdae_advance */
    double h_init;             /**< first step (0: the integrator's choice) */
    double h_max;              /**< largest step (0: unlimited) */
    double ic_tol;             /**< allowed max |g(x0, t0)| (and |G v0 + g_t|) */
    int index;                 /**< second-order problems: 3 or 2 */
    double gamma0;             /**< index 3: weight of g, or REGDAE_AUTO */
    double gamma1;             /**< index 3: weight of G v + g_t, or REGDAE_AUTO */
    int curvature;             /**< index 3: 1 adds the curvature term */
    int excluded;              /**< REGDAE_EXCLUDED_* */
    double singular_threshold; /**< sigma_min(GB) below it: singular, or REGDAE_AUTO */
    double jump_tol;           /**< velocity-jump alarm (0: off) */
    double drift_tol;          /**< drift alarm (0: off), or REGDAE_AUTO */
    double work_tol;           /**< work-energy alarm (0: off), or REGDAE_AUTO */
    double invariant_tol;      /**< invariant alarm (0: off) */
    double taylor_h;           /**< order >= 3: h of the Taylor weights */
    double mass_damping;       /**< mechanical: mu of (4.11) */
    int integrator;            /**< REGDAE_INTEGRATOR_* */
    int linear_solver;         /**< REGDAE_LINEAR_SOLVER_* */
    int check_jacobians;       /**< 1: check G (and the Newton matrix) at init */
    double resolution_tol;     /**< warn (REGDAE_WARN_UNRESOLVED) above this ratio (0: off) */
    double atol_v;             /**< second order: absolute tolerance on the velocities, or REGDAE_AUTO (atol) */
    int pass_check;            /**< 1: each singular pass re-integrated at rtol/10^k and compared */
    double pass_tol;           /**< agreement of two levels of a pass check, in error weights */
    int error_estimate;        /**< 1: a companion at rtol/10 estimates the error of x (regdae_error_estimate) */
    int max_order;             /**< IDA's largest BDF order, 1 ... 5 */
} regdae_options;

/** The statistics (solver_stats of the Fortran API, field for field; doc/api.md section 3). */
typedef struct regdae_stats {
    int64_t steps;            /**< steps taken */
    int64_t res_evals;        /**< all residual evaluations (IDA's and the Jacobian's) */
    int64_t jac_res_evals;    /**< residual evaluations in difference-quotient Jacobians */
    int64_t jac_evals;        /**< Jacobian evaluations */
    int64_t lin_setups;       /**< linear solver setups */
    int64_t nonlin_iters;     /**< Newton iterations */
    int64_t err_test_fails;   /**< local error test failures */
    int64_t conv_fails;       /**< nonlinear convergence failures */
    double t;                 /**< time reached */
    double h_last;            /**< last step size */
    int singular_passes;      /**< runs of samples with sigma_min(GB) below singular_threshold */
    double sigma_min;         /**< smallest sigma_min(GB) at the samples */
    double velocity_jump;     /**< largest relative velocity jump across a singular interval */
    double max_drift;         /**< largest max |g(x, t)| at the samples (order >= 2) */
    double invariant_change;  /**< largest change of the invariant (invariant_tol > 0) */
    int switches;             /**< integrator auto: switches between dopri5 and the implicit integrator (IDA or Radau) */
    double work_defect;       /**< mechanical: largest work-energy defect, relative */
    int unresolved_passes;    /**< singular passes approached with more error than resolution_tol allows */
    double resolution_ratio;  /**< largest x error implied by the residual on an approach, over the tolerance */
    int pass_checks;          /**< singular passes re-integrated at tighter tolerances (pass_check) */
    int passes_resolved;      /**< of those, passes where the solution disagreed with rtol/10 and a tighter pair agreed */
    int passes_unresolved;    /**< the pass check's warnings: levels that did not agree, outputs found off */
    double pass_error;        /**< largest difference of the solution from the first tighter level, in error weights */
    int64_t companion_steps;  /**< steps of the companions (pass checks, error estimate) */
    double error_estimate;    /**< error_estimate: the estimated error of x at the last output in error weights; -1: none */
    int weight_changes;       /**< automatic Baumgarte weights changed along the run */
    int eps_changes;          /**< automatic eps changed along the run */
    int roots_found;          /**< roots of the event functions reported (regdae_set_events) */
} regdae_stats;

/* ---- Handles and messages --------------------------------------------------- */

/**
 * A new solver with the default options and no problem.
 * Returns NULL only if memory is exhausted.
 */
regdae_solver *regdae_create(void);

/**
 * Free a solver (its IDA memory too) and set *solver to NULL.
 * solver == NULL or *solver == NULL: nothing happens.
 */
void regdae_destroy(regdae_solver **solver);

/**
 * The message of the last call on this solver: what went wrong, with the time
 * and the quantity; "" after success. Owned by the solver, valid until its next
 * call. For a NULL solver a static text saying so; never NULL.
 */
const char *regdae_message(const regdae_solver *solver);

/**
 * The fixed description of a status code (the Fortran API's status_message):
 * "success", "invalid input", ... (regdae_message adds the details of a call).
 * A static text, never NULL; for a code that is no regdae status a text that
 * says so ("unknown status code (not a regdae status)").
 */
const char *regdae_status_string(int status);

/**
 * The version of the library linked, "MAJOR.MINOR.PATCH" (a static text, never
 * NULL), and its three numbers in *major, *minor, *patch (each may be NULL).
 * Compare with REGDAE_VERSION_* to catch a header of another version.
 */
const char *regdae_version(int *major, int *minor, int *patch);

/* ---- The problem -------------------------------------------------------------
 * One of regdae_set_first_order, regdae_set_second_order, regdae_set_mechanical
 * defines the problem (and forgets a previous one, its optional callbacks and
 * patterns); the optional callbacks and patterns come after it. All are read by
 * regdae_init.
 */

/**
 * A semi-explicit index-2 problem (paper, eq. 2.1):
 *   x' = f(x, t) - B(x, t) y,   0 = g(x, t),   x in R^n, y in R^m, 1 <= n, 0 <= m <= n.
 * f (length n), b (B, n x m), g (length m), gx (G = dg/dx, m x n) are required;
 * gt (dg/dt, length m) may be NULL: a central difference quotient (error ~ 4e-11).
 * Sign convention: B multiplies y with a minus sign (a section-3 linear DAE
 * x' = A x + C^T y + q has B = -C^T).
 * Returns REGDAE_SUCCESS, or REGDAE_ERR_BAD_INPUT (sizes, a NULL required callback).
 */
int regdae_set_first_order(regdae_solver *solver, int n, int m, regdae_point_fn f, regdae_point_fn b,
                           regdae_point_fn g, regdae_point_fn gx, regdae_point_fn gt, void *user_data);

/**
 * A second-order (index-3) problem (paper, eq. 4.1):
 *   x'' = f(x, x', t) - B(x, x', t) y,   0 = g(x, t).
 * f (length n) and b (n x m) are functions of (t, x, v); g, gx and gt (NULL: a
 * difference quotient) of (t, x). The index (3, or 2 through G v + g_t = 0) is
 * the option "index". Optional: regdae_set_curvature, regdae_set_invariant.
 */
int regdae_set_second_order(regdae_solver *solver, int n, int m, regdae_motion_fn f, regdae_motion_fn b,
                            regdae_point_fn g, regdae_point_fn gx, regdae_point_fn gt, void *user_data);

/**
 * A constrained mechanical system (paper, eq. 1.2):
 *   M(q) q'' = f(q, q', t) + G^T lambda,   0 = g(q, t).
 * mass (M, n x n, symmetric positive definite), forces (f, length n, of (t, q, v)),
 * g, gx and gt (NULL: a difference quotient). regdae_advance returns lambda as y.
 * Optional: regdae_set_curvature, regdae_set_invariant, and the structure
 * (regdae_set_pattern, regdae_set_pattern_values).
 */
int regdae_set_mechanical(regdae_solver *solver, int n, int m, regdae_point_fn mass, regdae_motion_fn forces,
                          regdae_point_fn g, regdae_point_fn gx, regdae_point_fn gt, void *user_data);

/**
 * Second-order and mechanical problems: c = g_xx(v, v) + 2 g_xt v + g_tt (length m),
 * used by the curvature-corrected regularization (option curvature=yes).
 * NULL restores the default (a difference quotient of G v + g_t).
 */
int regdae_set_curvature(regdae_solver *solver, regdae_motion_fn curvature);

/**
 * Second-order and mechanical problems: an invariant I(x, v, t) of the motion
 * (one value, e.g. the energy), checked when the option invariant_tol > 0.
 * NULL: none.
 */
int regdae_set_invariant(regdae_solver *solver, regdae_motion_fn invariant);

/**
 * Mechanical problems: declare which entries of a matrix may be nonzero
 * (doc/api.md, "Large mechanisms"). which: REGDAE_PATTERN_*; rows[k], cols[k]
 * (0-based, k < nnz) in any order, duplicates count once. Declaring any pattern
 * declares the structure; a pattern not declared is dense. With at least 16
 * coordinates (or formulation=augmented) the augmented formulation then uses the
 * patterns. Values in "pattern order": row by row, columns increasing
 * (regdae_pattern_position gives the index of an entry).
 * Returns REGDAE_ERR_BAD_INPUT for an entry outside the matrix.
 */
int regdae_set_pattern(regdae_solver *solver, int which, int nnz, const int *rows, const int *cols);

/**
 * The 0-based index of entry (i, j) (0-based) in the values of the declared
 * pattern which (pattern order); -1 if the entry is not in it, the pattern is not
 * declared, or which is not a REGDAE_PATTERN_* code.
 */
int regdae_pattern_position(const regdae_solver *solver, int which, int i, int j);

/**
 * Mechanical problems with a declared pattern of M (which = REGDAE_PATTERN_MASS)
 * or G (REGDAE_PATTERN_CONSTRAINT): the routine that gives its entries at
 * (t, q) in pattern order (out has the pattern's number of entries), without
 * forming the dense matrix. NULL (the default): taken from the mass or gx
 * callback (dense, O(n^2)), refusing a nonzero outside the pattern
 * (REGDAE_ERR_STRUCTURE).
 */
int regdae_set_pattern_values(regdae_solver *solver, int which, regdae_point_fn values);

/* ---- Options ------------------------------------------------------------------
 * Read by regdae_init (changing one later affects the next regdae_init).
 */

/**
 * Set an option from its key and value as text, through the same parser as the
 * drivers' key=value arguments (doc/api.md section 2: method, formulation, lsq,
 * exclusion, gamma, eps, rtol, atol, atol_v, stop_at_output, max_steps, h_init,
 * h_max, ic_tol, index, gamma0, gamma1, curvature, excluded, singular_threshold,
 * jump_tol, drift_tol, invariant_tol, resolution_tol, work_tol, taylor_h,
 * mass_damping, integrator, linear_solver, check_jacobians, pass_check, pass_tol,
 * error_estimate, max_order; a test checks this
 * list against the options). Numbers are read strictly ("1e-3", ".5"; not "1-3"),
 * and a key or value is taken as given: a blank before or after it ("1e-3 ") is
 * refused. An unknown key or a bad value gives REGDAE_ERR_BAD_INPUT, a message
 * naming it, and leaves the options unchanged.
 */
int regdae_set_option(regdae_solver *solver, const char *key, const char *value);

/**
 * The absolute tolerance per component of the state for the next regdae_init
 * (replaces the atol option): n entries, the state's length (first order: n;
 * second-order and mechanical problems: 2n, the positions then the velocities;
 * regdae_init refuses another length or an entry <= 0). atol NULL and n 0 clear
 * it. The array is copied.
 */
int regdae_set_atol_vector(regdae_solver *solver, const double *atol, int n);

/**
 * Set a real option by its key (gamma, eps, rtol, atol, atol_v, h_init, h_max,
 * ic_tol, gamma0, gamma1, singular_threshold, jump_tol, drift_tol, invariant_tol,
 * resolution_tol, work_tol, taylor_h, mass_damping, pass_tol); REGDAE_AUTO is "auto".
 * The value goes through the same parser and checks as regdae_set_option,
 * exactly.
 */
int regdae_set_real_option(regdae_solver *solver, const char *key, double value);

/**
 * Set an integer option by its key: a number (index, max_steps, max_order), a code
 * (method: REGDAE_METHOD_*, formulation, lsq, exclusion, excluded, integrator,
 * linear_solver) or a switch, 0 or 1 (stop_at_output, curvature,
 * check_jacobians, pass_check, error_estimate). A value that is no code of the key: REGDAE_ERR_BAD_INPUT.
 */
int regdae_set_int_option(regdae_solver *solver, const char *key, int value);

/* Typed setters for the common options (regdae_set_real_option and
   regdae_set_int_option with the key spelled out). */

/** rtol, 0 < rtol < 1 (default 1e-5). */
static inline int regdae_set_rtol(regdae_solver *solver, double rtol)
{
    return regdae_set_real_option(solver, "rtol", rtol);
}
/** atol > 0 (default 1e-5). */
static inline int regdae_set_atol(regdae_solver *solver, double atol)
{
    return regdae_set_real_option(solver, "atol", atol);
}
/** eps >= 0, or REGDAE_AUTO (the default). */
static inline int regdae_set_eps(regdae_solver *solver, double eps)
{
    return regdae_set_real_option(solver, "eps", eps);
}
/** Baumgarte's gamma > 0, or REGDAE_AUTO (the default). */
static inline int regdae_set_gamma(regdae_solver *solver, double gamma)
{
    return regdae_set_real_option(solver, "gamma", gamma);
}
/** Index 3: gamma0 > 0, or REGDAE_AUTO (the default). */
static inline int regdae_set_gamma0(regdae_solver *solver, double gamma0)
{
    return regdae_set_real_option(solver, "gamma0", gamma0);
}
/** Index 3: gamma1 > 0, or REGDAE_AUTO (the default). */
static inline int regdae_set_gamma1(regdae_solver *solver, double gamma1)
{
    return regdae_set_real_option(solver, "gamma1", gamma1);
}
/** First step size, >= 0 (0: the integrator's estimate, the default). */
static inline int regdae_set_h_init(regdae_solver *solver, double h_init)
{
    return regdae_set_real_option(solver, "h_init", h_init);
}
/** Largest step size, >= 0 (0: unlimited, the default). */
static inline int regdae_set_h_max(regdae_solver *solver, double h_max)
{
    return regdae_set_real_option(solver, "h_max", h_max);
}
/** REGDAE_METHOD_* (default REGDAE_METHOD_TRUST_REGION). */
static inline int regdae_set_method(regdae_solver *solver, int method)
{
    return regdae_set_int_option(solver, "method", method);
}
/** Second-order and mechanical problems: 3 (the default) or 2. */
static inline int regdae_set_index(regdae_solver *solver, int index)
{
    return regdae_set_int_option(solver, "index", index);
}
/** REGDAE_INTEGRATOR_* (default REGDAE_INTEGRATOR_AUTO). */
static inline int regdae_set_integrator(regdae_solver *solver, int integrator)
{
    return regdae_set_int_option(solver, "integrator", integrator);
}
/** REGDAE_FORMULATION_* (default REGDAE_FORMULATION_AUTO). */
static inline int regdae_set_formulation(regdae_solver *solver, int formulation)
{
    return regdae_set_int_option(solver, "formulation", formulation);
}
/** Steps allowed per regdae_advance, >= 1 (default 100000). */
static inline int regdae_set_max_steps(regdae_solver *solver, int max_steps)
{
    return regdae_set_int_option(solver, "max_steps", max_steps);
}

/**
 * The options: after a successful regdae_init those in force, every REGDAE_AUTO
 * resolved to the value at t0 (formulation, linear_solver and lsq to the choice
 * made; singular_threshold stays REGDAE_AUTO, a rule); before, those set so far.
 * integrator after init: the integrator in charge at the call, never
 * REGDAE_INTEGRATOR_AUTO: the one chosen, or with REGDAE_INTEGRATOR_AUTO IDA on a
 * formulation other than eliminated (IDA does the whole run there) and on the
 * eliminated formulation the one the switching policy has put in charge (dopri5
 * while the system is not stiff, IDA or Radau where it is; regdae_stats.switches counts
 * the switches): dopri5 right after init, which may change along the run.
 */
int regdae_get_options(const regdae_solver *solver, regdae_options *options);

/* ---- Integration -------------------------------------------------------------- */

/**
 * Start the problem at t0: check the input (sizes, NaN/Inf, options), check
 * |g(x0, t0)| <= ic_tol, compute y(t0) and x'(t0), create the integrator.
 * x0 has length nx0 = n; v0 (length nv0 = n) is the initial velocity of a
 * second-order or mechanical problem (G v0 + g_t = 0), NULL and 0 for a
 * first-order one. May be called again to restart.
 */
int regdae_init(regdae_solver *solver, double t0, const double *x0, int nx0, const double *v0, int nv0);

/**
 * Integrate to tout (>= the time reached) and return x(tout) (length nx = n),
 * and on request y(tout) (length ny = m; lambda for a mechanical problem,
 * recomputed from the state at tout) and v(tout) (length nv = n, second-order
 * and mechanical problems). Pass NULL and 0 for what is not wanted (no y: no
 * multiplier is computed at tout). A warning is a status of its own, > 0, with
 * its message in regdae_message; the solver can go on after it:
 * REGDAE_WARN_MULTIPLIER_UNDEFINED: x (and v) valid, y NaN;
 * REGDAE_WARN_UNRESOLVED: x is the integrator's, but near a singular configuration
 * passed during this call it may miss the tolerance (the pass check, the option
 * resolution_tol, or the Taylor layer at order 3 and 4: see REGDAE_WARN_UNRESOLVED);
 * REGDAE_ROOT_FOUND: returned at a root of an event function
 * that stops (regdae_set_events), x there, stats.t its time.
 */
int regdae_advance(regdae_solver *solver, double tout, double *x, int nx, double *y, int ny, double *v, int nv);

/* ---- Events (root finding; doc/api.md, Events) ------------------------------- */

/**
 * Event functions e_i(t, x, v), i = 0 ... n_events - 1: write e (length n_events) and
 * return 0 (nonzero: the advance fails with REGDAE_ERR_USER_CALLBACK). x has length n;
 * v (length n) is the velocity of a second-order or mechanical problem, NULL for a
 * first-order one (e_i(t, x)).
 */
typedef int (*regdae_event_fn)(double t, const double *x, const double *v, double *e, void *user_data);

/**
 * Set n_events event functions (0: none; they stay set across regdae_init). Each root is
 * located on the integrator's continuous extension (Illinois) to 4 epsilon max(|t|, |h|).
 * direction[i] (NULL: all 0): +1 report only increasing crossings, -1 only decreasing,
 * 0 both. stop[i] (NULL: all 1): 1 regdae_advance returns at the root with
 * REGDAE_ROOT_FOUND, 0 the root is counted (regdae_stats.roots_found) and logged, and the
 * integration goes on. A function zero at t0 is not reported there. Returns
 * REGDAE_SUCCESS or REGDAE_ERR_BAD_INPUT (n_events < 0, events NULL, a direction not in
 * -1, 0, 1).
 */
int regdae_set_events(regdae_solver *solver, int n_events, regdae_event_fn events, const int *direction,
                      const int *stop, void *user_data);

/**
 * After REGDAE_ROOT_FOUND: roots[i] = +1 (a root of function i there, increasing), -1
 * (decreasing) or 0 (none at that time); roots has length n_events.
 */
int regdae_get_roots(const regdae_solver *solver, int *roots, int n_events);

/** The statistics of the integration so far (stats->t: the time reached). */
int regdae_get_statistics(const regdae_solver *solver, regdae_stats *stats);

/**
 * With the option error_estimate (1): e = x_companion - x at the last output, the
 * estimated global error of x (a companion solution at rtol/10, atol/10); n: the size
 * of x. REGDAE_ERR_BAD_INPUT, e filled with NaN, when there is no estimate (the option
 * off, no output yet, another n, or the companion failed).
 */
int regdae_error_estimate(regdae_solver *solver, double *e, int n);

#ifdef __cplusplus
}
#endif

#endif /* REGDAE_H */
