/* Tests of the C interface (include/regdae.h): `capi_tester SUITE` runs one suite
 * (ctest has an entry per suite), `capi_tester` all. Prints one line per check
 * that fails and 'N passed, N failed'; exits with 1 if a check failed.
 *
 * Suites:
 *   bad_input  NULL handles, NULL arrays and callbacks, wrong lengths, unknown keys
 *              and bad values: a status and a message naming the argument, no crash
 *   problems   first-order, second-order (index 3 and 2), mechanical and structured
 *              mechanical problems against their exact solutions
 *   handles    two handles side by side give what each gives alone, bit for bit
 *   callbacks  user_data passed through; a callback's < 0 and > 0 reported like a
 *              Fortran routine's stat
 *   options    typed setters, text options, resolved options, statistics
 *   warnings   a warning is a status of its own (> 0) with its message, and the
 *              integration goes on after it: REGDAE_WARN_UNRESOLVED on Example 5.1's
 *              approach to t = 0, REGDAE_WARN_MULTIPLIER_UNDEFINED at t = 0
 *   version    regdae_version against REGDAE_VERSION_*; regdae_status_string of every
 *              status (static, distinct, never NULL) and of codes that are none
 *   events     regdae_set_events on the circle (x = (cos t, sin t)): stops at the exact
 *              roots within 10 rtol, the direction filter, roots[], a continuing
 *              function counted in the statistics, v NULL for a first-order problem,
 *              user_data passed through, bad input
 *   threads    two handles in two POSIX threads at once, each on the same problems,
 *              give what one handle gives run serially, bit for bit
 *   threads_stress  the same with four threads for 100 rounds (run only when named)
 *   estimate   the error estimate (option error_estimate, regdae_error_estimate and the
 *              error_estimate statistic) on the circle x = (cos t, sin t) against the true
 *              error: within a factor 10 of it at the outputs (issue 19)
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "regdae.h"

static int checks_failed = 0;
static int checks_passed = 0;

#define CHECK(cond) check((cond), #cond, __FILE__, __LINE__)

static void check(int ok, const char *what, const char *file, int line)
{
    if (ok) {
        checks_passed++;
    } else {
        checks_failed++;
        printf("  FAIL %s:%d: %s\n", file, line, what);
    }
}

/* The message contains `part`. */
static int says(const regdae_solver *s, const char *part)
{
    const char *msg = regdae_message(s);
    return msg != NULL && strstr(msg, part) != NULL;
}

/* ---- problems ---------------------------------------------------------------- */

/* What the callbacks see: a counter, and a time from which g fails (recoverably
   or fatally). */
typedef struct {
    long calls;
    double fail_from;
    int fail_value;
} circle_data;

static int counted(void *user_data, double t)
{
    circle_data *d = (circle_data *)user_data;
    if (d == NULL) return 0;
    d->calls++;
    return t >= d->fail_from ? d->fail_value : 0;
}

/* First order, the circle of example_circle: x' = (x1 - x2, x1 + x2) - 2x y. */
static int c1_f(double t, const double *x, double *out, void *u)
{
    (void)t;
    (void)u;
    out[0] = x[0] - x[1];
    out[1] = x[0] + x[1];
    return 0;
}

static int c_gradient(double t, const double *x, double *out, void *u)
{
    (void)t;
    (void)u;
    out[0] = 2.0 * x[0];
    out[1] = 2.0 * x[1];
    return 0;
}

static int c_g(double t, const double *x, double *out, void *u)
{
    out[0] = x[0] * x[0] + x[1] * x[1] - 1.0;
    return counted(u, t);
}

/* Second order: x'' = 0 - 2x y on the unit circle; uniform motion, y = 1/2. */
static int c2_f(double t, const double *x, const double *v, double *out, void *u)
{
    (void)t;
    (void)x;
    (void)v;
    (void)u;
    out[0] = 0.0;
    out[1] = 0.0;
    return 0;
}

static int c2_b(double t, const double *x, const double *v, double *out, void *u)
{
    (void)v;
    return c_gradient(t, x, out, u);
}

static int c2_curvature(double t, const double *x, const double *v, double *out, void *u)
{
    (void)t;
    (void)x;
    (void)u;
    out[0] = 2.0 * (v[0] * v[0] + v[1] * v[1]); /* g_xx(v, v) */
    return 0;
}

static int c2_energy(double t, const double *x, const double *v, double *out, void *u)
{
    (void)t;
    (void)x;
    (void)u;
    out[0] = 0.5 * (v[0] * v[0] + v[1] * v[1]);
    return 0;
}

/* Mechanical: q'' = G^T lambda with M = I, no forces; lambda = -1/2. */
static int m_identity(double t, const double *q, double *out, void *u)
{
    (void)t;
    (void)q;
    (void)u;
    out[0] = 1.0;
    out[1] = 0.0;
    out[2] = 0.0;
    out[3] = 1.0;
    return 0;
}

static int m_no_forces(double t, const double *q, const double *v, double *out, void *u)
{
    return c2_f(t, q, v, out, u);
}

/* Structured: K particles, each on its own unit circle, n = 2K, m = K. */
#define K 8
static int k_mass(double t, const double *q, double *out, void *u)
{
    int i;
    (void)t;
    (void)q;
    (void)u;
    for (i = 0; i < 4 * K * K; i++) out[i] = 0.0;
    for (i = 0; i < 2 * K; i++) out[i + i * 2 * K] = 1.0;
    return 0;
}

static int k_forces(double t, const double *q, const double *v, double *out, void *u)
{
    int i;
    (void)t;
    (void)q;
    (void)v;
    (void)u;
    for (i = 0; i < 2 * K; i++) out[i] = 0.0;
    return 0;
}

static int k_g(double t, const double *q, double *out, void *u)
{
    int j;
    (void)t;
    (void)u;
    for (j = 0; j < K; j++) out[j] = q[2 * j] * q[2 * j] + q[2 * j + 1] * q[2 * j + 1] - 1.0;
    return 0;
}

static int k_gx(double t, const double *q, double *out, void *u)
{
    int j;
    (void)t;
    (void)u;
    for (j = 0; j < 2 * K * K; j++) out[j] = 0.0;
    for (j = 0; j < K; j++) { /* G is K x 2K, column-major: (j, c) at out[j + c*K] */
        out[j + (2 * j) * K] = 2.0 * q[2 * j];
        out[j + (2 * j + 1) * K] = 2.0 * q[2 * j + 1];
    }
    return 0;
}

static int k_mass_values(double t, const double *q, double *out, void *u)
{
    int i;
    (void)t;
    (void)q;
    (void)u;
    for (i = 0; i < 2 * K; i++) out[i] = 1.0; /* the diagonal, row by row */
    return 0;
}

static int k_gx_values(double t, const double *q, double *out, void *u)
{
    int i;
    (void)t;
    (void)u;
    for (i = 0; i < 2 * K; i++) out[i] = 2.0 * q[i]; /* row j: columns 2j, 2j+1 */
    return 0;
}

static double k_speed(int j)
{
    return 1.0 + 0.1 * j;
}

static void k_start(double *q, double *v)
{
    int j;
    for (j = 0; j < K; j++) {
        double phi = 0.3 * j;
        q[2 * j] = cos(phi);
        q[2 * j + 1] = sin(phi);
        v[2 * j] = -k_speed(j) * sin(phi);
        v[2 * j + 1] = k_speed(j) * cos(phi);
    }
}

/* max |q - exact| at t */
static double k_error(const double *q, double t)
{
    double err = 0.0;
    int j;
    for (j = 0; j < K; j++) {
        double phi = 0.3 * j + k_speed(j) * t;
        err = fmax(err, fmax(fabs(q[2 * j] - cos(phi)), fabs(q[2 * j + 1] - sin(phi))));
    }
    return err;
}

/* A first-order circle solver with tolerances 1e-8. */
static regdae_solver *circle_solver(circle_data *d)
{
    regdae_solver *s = regdae_create();
    regdae_set_first_order(s, 2, 1, c1_f, c_gradient, c_g, c_gradient, NULL, d);
    regdae_set_rtol(s, 1e-8);
    regdae_set_atol(s, 1e-8);
    return s;
}

/* ---- bad_input ----------------------------------------------------------------- */

static void bad_input(void)
{
    const double x0[2] = {1.0, 0.0}, v0[2] = {0.0, 1.0};
    const int rows[2] = {0, 5}, cols[2] = {0, 1};
    double x[3], y[2], v[2];
    regdae_stats st;
    regdae_options opts;
    regdae_solver *none = NULL;
    regdae_solver *s = regdae_create();

    /* a NULL handle: REGDAE_ERR_BAD_INPUT from everything, no message, no crash */
    CHECK(regdae_set_first_order(NULL, 2, 1, c1_f, c_gradient, c_g, c_gradient, NULL, NULL) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_second_order(NULL, 2, 1, c2_f, c2_b, c_g, c_gradient, NULL, NULL) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_mechanical(NULL, 2, 1, m_identity, m_no_forces, c_g, c_gradient, NULL, NULL) ==
          REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_curvature(NULL, c2_curvature) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_invariant(NULL, c2_energy) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_pattern(NULL, REGDAE_PATTERN_MASS, 2, rows, cols) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_pattern_values(NULL, REGDAE_PATTERN_MASS, k_mass_values) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_pattern_position(NULL, REGDAE_PATTERN_MASS, 0, 0) == -1);
    CHECK(regdae_set_option(NULL, "rtol", "1e-6") == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_real_option(NULL, "rtol", 1e-6) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_int_option(NULL, "index", 2) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_rtol(NULL, 1e-6) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_get_options(NULL, &opts) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_init(NULL, 0.0, x0, 2, NULL, 0) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_advance(NULL, 1.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_get_statistics(NULL, &st) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_message(NULL) != NULL && strstr(regdae_message(NULL), "NULL handle") != NULL);
    regdae_destroy(NULL);
    regdae_destroy(&none);
    CHECK(none == NULL);

    /* no problem yet */
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "no problem"));
    CHECK(regdae_advance(s, 1.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_NOT_INITIALIZED &&
          says(s, "no successful regdae_init"));
    CHECK(regdae_set_curvature(s, c2_curvature) == REGDAE_ERR_BAD_INPUT && says(s, "regdae_set_second_order"));
    CHECK(regdae_set_pattern(s, REGDAE_PATTERN_MASS, 2, rows, cols) == REGDAE_ERR_BAD_INPUT &&
          says(s, "regdae_set_mechanical"));

    /* the problem: sizes and NULL callbacks */
    CHECK(regdae_set_first_order(s, 0, 1, c1_f, c_gradient, c_g, c_gradient, NULL, NULL) == REGDAE_ERR_BAD_INPUT &&
          says(s, "n = 0"));
    CHECK(regdae_set_first_order(s, 2, 3, c1_f, c_gradient, c_g, c_gradient, NULL, NULL) == REGDAE_ERR_BAD_INPUT &&
          says(s, "m = 3"));
    CHECK(regdae_set_first_order(s, 2, 1, c1_f, NULL, c_g, c_gradient, NULL, NULL) == REGDAE_ERR_BAD_INPUT &&
          says(s, "callback b is NULL"));
    CHECK(regdae_set_mechanical(s, 2, 1, NULL, m_no_forces, c_g, c_gradient, NULL, NULL) == REGDAE_ERR_BAD_INPUT &&
          says(s, "callback mass is NULL"));
    CHECK(regdae_set_first_order(s, 2, 1, c1_f, c_gradient, c_g, c_gradient, NULL, NULL) == REGDAE_SUCCESS &&
          says(s, ""));
    CHECK(regdae_set_invariant(s, c2_energy) == REGDAE_ERR_BAD_INPUT && says(s, "second-order or mechanical"));
    CHECK(regdae_set_pattern_values(s, REGDAE_PATTERN_MASS, k_mass_values) == REGDAE_ERR_BAD_INPUT &&
          says(s, "mechanical problem"));

    /* options: unknown keys, bad values, NULL text, codes that are none */
    CHECK(regdae_set_option(s, "colour", "red") == REGDAE_ERR_BAD_INPUT && says(s, "unknown option \"colour\""));
    CHECK(regdae_set_option(s, "rtol", "1-3") == REGDAE_ERR_BAD_INPUT && says(s, "bad value \"1-3\""));
    CHECK(regdae_set_option(s, "rtol", "2") == REGDAE_ERR_BAD_INPUT && says(s, "rtol must be in (0, 1)"));
    CHECK(regdae_set_option(s, NULL, "1") == REGDAE_ERR_BAD_INPUT && says(s, "key or value is NULL"));
    CHECK(regdae_set_option(s, "rtol", NULL) == REGDAE_ERR_BAD_INPUT && says(s, "key or value is NULL"));
    CHECK(regdae_set_real_option(s, "colour", 1.0) == REGDAE_ERR_BAD_INPUT && says(s, "unknown option"));
    CHECK(regdae_set_real_option(s, NULL, 1.0) == REGDAE_ERR_BAD_INPUT && says(s, "key is NULL"));
    CHECK(regdae_set_rtol(s, NAN) == REGDAE_ERR_BAD_INPUT && says(s, "rtol"));
    CHECK(regdae_set_atol(s, REGDAE_AUTO) == REGDAE_ERR_BAD_INPUT && says(s, "atol"));
    CHECK(regdae_set_method(s, 7) == REGDAE_ERR_BAD_INPUT && says(s, "7 is not a value of option \"method\""));
    CHECK(regdae_set_index(s, 4) == REGDAE_ERR_BAD_INPUT && says(s, "index"));
    CHECK(regdae_set_int_option(s, "curvature", 2) == REGDAE_ERR_BAD_INPUT && says(s, "curvature"));
    CHECK(regdae_set_int_option(s, NULL, 2) == REGDAE_ERR_BAD_INPUT && says(s, "key is NULL"));
    CHECK(regdae_set_max_steps(s, 0) == REGDAE_ERR_BAD_INPUT && says(s, "max_steps"));
    CHECK(regdae_get_options(s, NULL) == REGDAE_ERR_BAD_INPUT && says(s, "options is NULL"));
    CHECK(regdae_get_options(s, &opts) == REGDAE_SUCCESS && opts.rtol == 1e-5); /* unchanged by the refusals */

    /* init: NULL arrays, wrong lengths, v0 for a first-order problem, NaN */
    CHECK(regdae_init(s, 0.0, NULL, 2, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "x0 is NULL"));
    CHECK(regdae_init(s, 0.0, x0, 3, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "x0 has length 3"));
    CHECK(regdae_init(s, 0.0, x0, 2, v0, 2) == REGDAE_ERR_BAD_INPUT && says(s, "v0 is for second-order"));
    CHECK(regdae_init(s, NAN, x0, 2, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "t0"));
    CHECK(regdae_advance(s, 1.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_NOT_INITIALIZED);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);

    /* advance: NULL x, wrong lengths, v for a first-order problem, tout backwards */
    CHECK(regdae_advance(s, 1.0, NULL, 2, NULL, 0, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "x is NULL"));
    CHECK(regdae_advance(s, 1.0, x, 3, NULL, 0, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "x has length 3"));
    CHECK(regdae_advance(s, 1.0, x, 2, y, 2, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "y has length 2"));
    CHECK(regdae_advance(s, 1.0, x, 2, NULL, 1, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "y is NULL"));
    CHECK(regdae_advance(s, 1.0, x, 2, y, 1, v, 2) == REGDAE_ERR_BAD_INPUT && says(s, "v is for second-order"));
    CHECK(regdae_advance(s, 1.0, x, 2, y, 1, NULL, 0) == REGDAE_SUCCESS && says(s, ""));
    CHECK(regdae_advance(s, 0.5, x, 2, y, 1, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "before the current time"));
    CHECK(regdae_get_statistics(s, NULL) == REGDAE_ERR_BAD_INPUT && says(s, "stats is NULL"));

    /* second order: v0 and v lengths */
    CHECK(regdae_set_second_order(s, 2, 1, c2_f, c2_b, c_g, c_gradient, NULL, NULL) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 2.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_NOT_INITIALIZED); /* a new problem */
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "v0 is NULL"));
    CHECK(regdae_init(s, 0.0, x0, 2, v0, 1) == REGDAE_ERR_BAD_INPUT && says(s, "v0 has length 1"));
    CHECK(regdae_init(s, 0.0, x0, 2, v0, 2) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 1.0, x, 2, NULL, 0, v, 3) == REGDAE_ERR_BAD_INPUT && says(s, "v has length 3"));

    /* patterns */
    CHECK(regdae_set_mechanical(s, 2, 1, m_identity, m_no_forces, c_g, c_gradient, NULL, NULL) == REGDAE_SUCCESS);
    CHECK(regdae_set_pattern(s, 9, 2, rows, cols) == REGDAE_ERR_BAD_INPUT && says(s, "which = 9"));
    CHECK(regdae_set_pattern(s, REGDAE_PATTERN_MASS, -1, rows, cols) == REGDAE_ERR_BAD_INPUT && says(s, "negative"));
    CHECK(regdae_set_pattern(s, REGDAE_PATTERN_MASS, 2, NULL, cols) == REGDAE_ERR_BAD_INPUT && says(s, "NULL"));
    CHECK(regdae_set_pattern(s, REGDAE_PATTERN_MASS, 2, rows, cols) == REGDAE_ERR_BAD_INPUT &&
          says(s, "outside the 2 x 2 matrix"));
    CHECK(regdae_set_pattern(s, REGDAE_PATTERN_CONSTRAINT, 1, cols, cols) == REGDAE_SUCCESS);
    CHECK(regdae_pattern_position(s, REGDAE_PATTERN_CONSTRAINT, 0, 0) == 0);
    CHECK(regdae_pattern_position(s, REGDAE_PATTERN_CONSTRAINT, 0, 1) == -1);
    CHECK(regdae_pattern_position(s, REGDAE_PATTERN_MASS, 0, 0) == -1); /* not declared */
    CHECK(regdae_pattern_position(s, 0, 0, 0) == -1 && says(s, "which = 0"));
    CHECK(regdae_set_pattern_values(s, REGDAE_PATTERN_FORCE_Q, k_mass_values) == REGDAE_ERR_BAD_INPUT &&
          says(s, "neither"));
    /* the declared G pattern misses G(0, 1) = 2 x2, nonzero near x0: refused by the default values */
    CHECK(regdae_set_formulation(s, REGDAE_FORMULATION_AUGMENTED) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, v0, 2) == REGDAE_ERR_STRUCTURE && says(s, "outside the sparsity pattern"));

    /* a C string has its own length: blanks around a key or a value are refused, and the
       options stay as they were */
    {
        static const char *padded[][2] = {{"rtol", "1e-3 "}, {"rtol", " 1e-3"}, {"rtol", "1e-3\t"},
                                          {"rtol ", "1e-3"}, {"max_steps", "100 "}, {"method", "direct "}};
        int k;
        regdae_solver *s = regdae_create();
        regdae_set_option(s, "rtol", "1e-6");
        for (k = 0; k < (int)(sizeof padded / sizeof padded[0]); k++) {
            CHECK(regdae_set_option(s, padded[k][0], padded[k][1]) == REGDAE_ERR_BAD_INPUT &&
                  says(s, "begins or ends with a blank"));
        }
        CHECK(regdae_get_options(s, &opts) == REGDAE_SUCCESS && opts.rtol == 1e-6 &&
              opts.method == REGDAE_METHOD_TRUST_REGION && opts.max_steps == 100000);
        CHECK(regdae_set_option(s, "rtol", "1e-3") == REGDAE_SUCCESS);
        regdae_destroy(&s);
    }
    regdae_destroy(&s);
    CHECK(s == NULL);
    regdae_destroy(&s); /* twice: nothing happens */
}

/* ---- problems -------------------------------------------------------------------- */

/* Max error of x against (cos t, sin t) (and v against (-sin t, cos t), y against
   y_exact) over 10 outputs in [0, 5] of a circle problem set up on s. */
static double circle_run(regdae_solver *s, int second_order, double y_exact)
{
    const double x0[2] = {1.0, 0.0}, v0[2] = {0.0, 1.0};
    double x[2], y[1], v[2], err = 0.0, t;
    int k, status;
    status = second_order ? regdae_init(s, 0.0, x0, 2, v0, 2) : regdae_init(s, 0.0, x0, 2, NULL, 0);
    if (status != REGDAE_SUCCESS) {
        printf("  init: %s\n", regdae_message(s));
        return INFINITY;
    }
    for (k = 1; k <= 10; k++) {
        t = 0.5 * k;
        status = second_order ? regdae_advance(s, t, x, 2, y, 1, v, 2) : regdae_advance(s, t, x, 2, y, 1, NULL, 0);
        if (status != REGDAE_SUCCESS) {
            printf("  advance: %s\n", regdae_message(s));
            return INFINITY;
        }
        err = fmax(err, fmax(fabs(x[0] - cos(t)), fabs(x[1] - sin(t))));
        if (second_order) err = fmax(err, fmax(fabs(v[0] + sin(t)), fabs(v[1] - cos(t))));
        /* the multiplier is recomputed from the state: error ~ the state's */
        err = fmax(err, fabs(y[0] - y_exact));
    }
    return err;
}

/* Tolerances 1e-8 over 0.8 revolutions: the errors measured are 1.2e-8 to 4.6e-8
   (x, v and y); the bound 1e-6 (20 times the largest) fails on a wrong
   formulation, sign or column order, which give errors of order 1. */
#define CIRCLE_BOUND 1e-6

static void problems(void)
{
    regdae_solver *s = regdae_create();
    regdae_options opts;
    regdae_stats st;
    double q[2 * K], v[2 * K], lambda[K], err;
    int j, status;
    int diag[2 * K], grow[2 * K], gcol[2 * K];

    regdae_set_rtol(s, 1e-8);
    regdae_set_atol(s, 1e-8);
    /* first order */
    regdae_set_first_order(s, 2, 1, c1_f, c_gradient, c_g, c_gradient, NULL, NULL);
    CHECK(circle_run(s, 0, 0.5) < CIRCLE_BOUND);
    /* second order, index 3 (the default) and 2; with the analytic curvature; with
       the invariant checked */
    regdae_set_second_order(s, 2, 1, c2_f, c2_b, c_g, c_gradient, NULL, NULL);
    CHECK(circle_run(s, 1, 0.5) < CIRCLE_BOUND);
    regdae_set_index(s, 2);
    CHECK(circle_run(s, 1, 0.5) < CIRCLE_BOUND);
    regdae_set_index(s, 3);
    CHECK(regdae_set_curvature(s, c2_curvature) == REGDAE_SUCCESS);
    CHECK(regdae_set_invariant(s, c2_energy) == REGDAE_SUCCESS);
    regdae_set_option(s, "invariant_tol", "1e-4");
    CHECK(circle_run(s, 1, 0.5) < CIRCLE_BOUND);
    regdae_get_statistics(s, &st);
    CHECK(st.invariant_change < 1e-6);
    regdae_set_option(s, "invariant_tol", "0");
    /* mechanical: lambda = -1/2 */
    regdae_set_mechanical(s, 2, 1, m_identity, m_no_forces, c_g, c_gradient, NULL, NULL);
    CHECK(circle_run(s, 1, -0.5) < CIRCLE_BOUND);
    /* the same through Radau IIA (integrator radau, the option's setter), with its statistics */
    CHECK(regdae_set_integrator(s, REGDAE_INTEGRATOR_RADAU) == REGDAE_SUCCESS);
    CHECK(circle_run(s, 1, -0.5) < CIRCLE_BOUND);
    regdae_get_options(s, &opts);
    regdae_get_statistics(s, &st);
    CHECK(opts.integrator == REGDAE_INTEGRATOR_RADAU && st.steps > 0 && st.jac_evals > 0 && st.switches == 0);
    /* and Radau IIA on the augmented formulation (the multiplier one of its unknowns) */
    CHECK(regdae_set_formulation(s, REGDAE_FORMULATION_AUGMENTED) == REGDAE_SUCCESS);
    CHECK(circle_run(s, 1, -0.5) < CIRCLE_BOUND);
    regdae_get_options(s, &opts);
    CHECK(opts.integrator == REGDAE_INTEGRATOR_RADAU && opts.formulation == REGDAE_FORMULATION_AUGMENTED);
    regdae_set_formulation(s, REGDAE_FORMULATION_AUTO);
    regdae_set_integrator(s, REGDAE_INTEGRATOR_AUTO);

    /* K particles: dense (eliminated), then structured (augmented, from the dense
       callbacks, then from the values callbacks) */
    for (j = 0; j < 2 * K; j++) {
        diag[j] = j;
        grow[j] = j / 2;
        gcol[j] = j;
    }
    for (status = 0; status < 3; status++) {
        regdae_set_mechanical(s, 2 * K, K, k_mass, k_forces, k_g, k_gx, NULL, NULL);
        if (status > 0) {
            CHECK(regdae_set_pattern(s, REGDAE_PATTERN_MASS, 2 * K, diag, diag) == REGDAE_SUCCESS);
            CHECK(regdae_set_pattern(s, REGDAE_PATTERN_CONSTRAINT, 2 * K, grow, gcol) == REGDAE_SUCCESS);
            CHECK(regdae_set_pattern(s, REGDAE_PATTERN_FORCE_Q, 0, NULL, NULL) == REGDAE_SUCCESS);
            CHECK(regdae_set_pattern(s, REGDAE_PATTERN_FORCE_V, 0, NULL, NULL) == REGDAE_SUCCESS);
            CHECK(regdae_pattern_position(s, REGDAE_PATTERN_CONSTRAINT, 3, 7) == 7);
        }
        if (status > 1) {
            CHECK(regdae_set_pattern_values(s, REGDAE_PATTERN_MASS, k_mass_values) == REGDAE_SUCCESS);
            CHECK(regdae_set_pattern_values(s, REGDAE_PATTERN_CONSTRAINT, k_gx_values) == REGDAE_SUCCESS);
        }
        k_start(q, v);
        CHECK(regdae_init(s, 0.0, q, 2 * K, v, 2 * K) == REGDAE_SUCCESS);
        regdae_get_options(s, &opts);
        CHECK(opts.formulation == (status > 0 ? REGDAE_FORMULATION_AUGMENTED : REGDAE_FORMULATION_ELIMINATED));
        CHECK(regdae_advance(s, 2.0, q, 2 * K, lambda, K, v, 2 * K) == REGDAE_SUCCESS);
        err = k_error(q, 2.0);
        for (j = 0; j < K; j++) err = fmax(err, fabs(lambda[j] + 0.5 * k_speed(j) * k_speed(j)));
        /* tolerances 1e-8 to t = 2: measured 2.8e-8 dense, 2.3e-6
           augmented (lambda is IDA's interpolated unknown there); 40 times that */
        CHECK(err < 1e-4);
        if (err >= 1e-4) printf("  K particles, variant %d: error %g: %s\n", status, err, regdae_message(s));
    }
    regdae_destroy(&s);
}

/* ---- handles ------------------------------------------------------------------------ */

static void handles(void)
{
    const double x0[2] = {1.0, 0.0};
    double xa[2], xb[2], ya[1], yb[1], alone[10][2];
    int k, same = 1;
    regdae_solver *a = circle_solver(NULL), *b = circle_solver(NULL);

    /* a alone */
    regdae_init(a, 0.0, x0, 2, NULL, 0);
    for (k = 1; k <= 10; k++) {
        regdae_advance(a, 0.5 * k, alone[k - 1], 2, NULL, 0, NULL, 0);
    }
    /* a and b interleaved, b with other options */
    regdae_set_method(b, REGDAE_METHOD_BAUMGARTE);
    CHECK(regdae_init(a, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_init(b, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    for (k = 1; k <= 10; k++) {
        CHECK(regdae_advance(a, 0.5 * k, xa, 2, ya, 1, NULL, 0) == REGDAE_SUCCESS);
        CHECK(regdae_advance(b, 0.25 * k, xb, 2, yb, 1, NULL, 0) == REGDAE_SUCCESS);
        same = same && xa[0] == alone[k - 1][0] && xa[1] == alone[k - 1][1];
    }
    CHECK(same);
    CHECK(fabs(xb[0] - cos(2.5)) < CIRCLE_BOUND && fabs(xb[1] - sin(2.5)) < CIRCLE_BOUND);
    /* a message belongs to its handle */
    CHECK(regdae_set_option(b, "colour", "red") == REGDAE_ERR_BAD_INPUT && says(b, "colour") && says(a, ""));
    CHECK(strlen(regdae_message(a)) == 0);
    regdae_destroy(&a);
    regdae_destroy(&b);
}

/* ---- callbacks ---------------------------------------------------------------------- */

static void callbacks(void)
{
    const double x0[2] = {1.0, 0.0};
    double x[2];
    circle_data d = {0, INFINITY, 0};
    regdae_solver *s = circle_solver(&d);

    /* user_data reaches the callbacks */
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 1.0, x, 2, NULL, 0, NULL, 0) == REGDAE_SUCCESS);
    CHECK(d.calls > 0);
    /* < 0 stops the integration: REGDAE_ERR_USER_CALLBACK, the callback named */
    d.fail_from = 1.5;
    d.fail_value = -7;
    CHECK(regdae_advance(s, 2.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_USER_CALLBACK);
    CHECK(says(s, "callback g returned -7 at t = 1.5") && says(s, "stat = -7"));
    /* > 0 at every time beyond 1.5: retried with smaller steps until the integrator
       gives up (IDA: "cannot get past"; dopri5, the automatic choice here: "step size
       too small"), naming the last failure */
    d.fail_value = 3;
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 2.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_INTEGRATION);
    CHECK(says(s, "reported failure (stat = 3)"));
    CHECK(regdae_set_integrator(s, REGDAE_INTEGRATOR_IDA) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 2.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_INTEGRATION);
    CHECK(says(s, "cannot get past t = 1.49"));
    CHECK(regdae_set_integrator(s, REGDAE_INTEGRATOR_RADAU) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 2.0, x, 2, NULL, 0, NULL, 0) == REGDAE_ERR_INTEGRATION);
    CHECK(says(s, "Radau failed at t = 1.49") && says(s, "reported failure (stat = 3)"));
    regdae_set_integrator(s, REGDAE_INTEGRATOR_IDA);
    /* > 0 at the initial point: REGDAE_ERR_USER_CALLBACK */
    d.fail_from = 0.0;
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_ERR_USER_CALLBACK);
    CHECK(says(s, "callback g returned 3"));
    regdae_destroy(&s);
}

/* ---- options -------------------------------------------------------------------------- */

static void options(void)
{
    const double x0[2] = {1.0, 0.0};
    double x[2];
    regdae_options opts;
    regdae_stats st;
    regdae_solver *s = circle_solver(NULL);

    CHECK(regdae_get_options(s, &opts) == REGDAE_SUCCESS);
    CHECK(opts.rtol == 1e-8 && opts.atol == 1e-8); /* exactly: 17 digits through the parser */
    CHECK(opts.eps == REGDAE_AUTO && opts.method == REGDAE_METHOD_TRUST_REGION && opts.max_steps == 100000);
    CHECK(opts.atol_v == REGDAE_AUTO && opts.resolution_tol == 1e4);
    CHECK(regdae_set_real_option(s, "atol_v", 1e-6) == REGDAE_SUCCESS && regdae_get_options(s, &opts) == 0 &&
          opts.atol_v == 1e-6);
    CHECK(regdae_set_real_option(s, "atol_v", REGDAE_AUTO) == REGDAE_SUCCESS);
    CHECK(regdae_set_rtol(s, 0.1 + 0.2) == REGDAE_SUCCESS); /* 0.30000000000000004 */
    regdae_get_options(s, &opts);
    CHECK(opts.rtol == 0.1 + 0.2);
    CHECK(regdae_set_eps(s, 1e-9) == REGDAE_SUCCESS && regdae_set_eps(s, REGDAE_AUTO) == REGDAE_SUCCESS);
    CHECK(regdae_set_gamma(s, 7.0) == REGDAE_SUCCESS && regdae_set_gamma0(s, 8.0) == REGDAE_SUCCESS &&
          regdae_set_gamma1(s, 9.0) == REGDAE_SUCCESS && regdae_set_h_init(s, 1e-4) == REGDAE_SUCCESS &&
          regdae_set_h_max(s, 0.25) == REGDAE_SUCCESS && regdae_set_index(s, 2) == REGDAE_SUCCESS &&
          regdae_set_integrator(s, REGDAE_INTEGRATOR_IDA) == REGDAE_SUCCESS &&
          regdae_set_formulation(s, REGDAE_FORMULATION_MULTIPLIER) == REGDAE_SUCCESS &&
          regdae_set_max_steps(s, 5000) == REGDAE_SUCCESS &&
          regdae_set_int_option(s, "stop_at_output", 1) == REGDAE_SUCCESS &&
          regdae_set_option(s, "lsq", "stacked") == REGDAE_SUCCESS && regdae_set_rtol(s, 1e-8) == REGDAE_SUCCESS);
    regdae_get_options(s, &opts);
    CHECK(opts.gamma == 7.0 && opts.gamma0 == 8.0 && opts.gamma1 == 9.0 && opts.h_init == 1e-4 &&
          opts.h_max == 0.25 && opts.index == 2 && opts.integrator == REGDAE_INTEGRATOR_IDA &&
          opts.formulation == REGDAE_FORMULATION_MULTIPLIER && opts.max_steps == 5000 && opts.stop_at_output == 1 &&
          opts.lsq == REGDAE_LSQ_STACKED && opts.eps == REGDAE_AUTO);
    /* after init: auto resolved */
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    regdae_get_options(s, &opts);
    CHECK(opts.eps != REGDAE_AUTO && opts.eps > 0.0 && opts.gamma == 7.0 && opts.lsq == REGDAE_LSQ_STACKED);
    CHECK(regdae_advance(s, 1.0, x, 2, NULL, 0, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_get_statistics(s, &st) == REGDAE_SUCCESS);
    CHECK(st.t == 1.0 && st.steps > 0 && st.res_evals >= st.steps && st.h_last > 0.0 && st.h_last <= 0.25);
    /* integrator auto: regdae_get_options gives the integrator in charge: on the
       multiplier formulation IDA (it does the whole run); on the eliminated one dopri5
       after init (the explicit method starts; the switching stays in force) */
    CHECK(regdae_set_integrator(s, REGDAE_INTEGRATOR_AUTO) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    regdae_get_options(s, &opts);
    CHECK(opts.integrator == REGDAE_INTEGRATOR_IDA && opts.formulation == REGDAE_FORMULATION_MULTIPLIER);
    CHECK(regdae_set_formulation(s, REGDAE_FORMULATION_ELIMINATED) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    regdae_get_options(s, &opts);
    CHECK(opts.integrator == REGDAE_INTEGRATOR_DOPRI5 && opts.formulation == REGDAE_FORMULATION_ELIMINATED);
    regdae_destroy(&s);
}

/* ---- atol_vector ----------------------------------------------------------------- */

/* regdae_set_atol_vector: a vector of equal entries gives the scalar run bit for bit,
   another vector another run; a wrong length is refused by regdae_init, NULL by the setter. */
static void atol_vector(void)
{
    const double x0[2] = {1.0, 0.0}, same[2] = {1e-8, 1e-8}, loose[2] = {1e-8, 1e-3}, three[3] = {1e-8, 1e-8, 1e-8};
    double xs[2], xv[2], xl[2];
    regdae_solver *s = circle_solver(NULL);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS && regdae_advance(s, 1.0, xs, 2, NULL, 0, NULL, 0) == 0);
    CHECK(regdae_set_atol_vector(s, same, 2) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS && regdae_advance(s, 1.0, xv, 2, NULL, 0, NULL, 0) == 0);
    CHECK(xv[0] == xs[0] && xv[1] == xs[1]);
    CHECK(regdae_set_atol_vector(s, loose, 2) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS && regdae_advance(s, 1.0, xl, 2, NULL, 0, NULL, 0) == 0);
    CHECK(xl[0] != xs[0] || xl[1] != xs[1]);
    CHECK(regdae_set_atol_vector(s, three, 3) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "atol_vector has 3 entries"));
    CHECK(regdae_set_atol_vector(s, NULL, 2) == REGDAE_ERR_BAD_INPUT && says(s, "atol is NULL"));
    CHECK(regdae_set_atol_vector(NULL, same, 2) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_atol_vector(s, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS && regdae_advance(s, 1.0, xv, 2, NULL, 0, NULL, 0) == 0);
    CHECK(xv[0] == xs[0] && xv[1] == xs[1]);
    regdae_destroy(&s);
}

/* ---- warnings ------------------------------------------------------------------- */

/* Example 5.1 (drivers/example_ex51.f): x' = 2 - t y, g = t x - t (t + 1), singular at
   t = 0; x = t + 1, y = 1/t. */
static int e51_f(double t, const double *x, double *out, void *u)
{
    (void)t;
    (void)x;
    (void)u;
    out[0] = 2.0;
    return 0;
}

static int e51_t(double t, const double *x, double *out, void *u) /* B = G = t */
{
    (void)x;
    (void)u;
    out[0] = t;
    return 0;
}

static int e51_g(double t, const double *x, double *out, void *u)
{
    (void)u;
    out[0] = t * x[0] - t * (t + 1.0);
    return 0;
}

static int e51_gt(double t, const double *x, double *out, void *u)
{
    (void)u;
    out[0] = x[0] - 2.0 * t - 1.0;
    return 0;
}

/* Example 5.1 from t = -1 through t = 0 to 1 in steps of 0.1 with IDA and the option
   resolution_tol = `tol`: the number of advances that returned REGDAE_WARN_UNRESOLVED
   (each with the warning's message), -1 if any other returned anything but
   REGDAE_SUCCESS with an empty message; *x1 = x(1). */
static int e51_warnings(regdae_solver *s, const char *tol, double *x1)
{
    const double x0[1] = {0.0};
    double x[1] = {0.0}, y[1];
    int k, status, warned = 0, other = 0;
    regdae_set_first_order(s, 1, 1, e51_f, e51_t, e51_g, e51_t, e51_gt, NULL);
    regdae_set_integrator(s, REGDAE_INTEGRATOR_IDA);
    regdae_set_option(s, "resolution_tol", tol);
    if (regdae_init(s, -1.0, x0, 1, NULL, 0) != REGDAE_SUCCESS) return -1;
    for (k = 1; k <= 20; k++) {
        status = regdae_advance(s, -1.0 + 0.1 * k, x, 1, y, 1, NULL, 0);
        if (status == REGDAE_WARN_UNRESOLVED && says(s, "approaching the singular configuration") &&
            says(s, "resolution_tol")) {
            warned++;
        } else if (status != REGDAE_SUCCESS || strlen(regdae_message(s)) > 0) {
            printf("  t = %g: status %d: %s\n", -1.0 + 0.1 * k, status, regdae_message(s));
            other++;
        }
    }
    *x1 = x[0];
    return other > 0 ? -1 : warned;
}

static void warnings(void)
{
    const double x0[1] = {0.0};
    double x[1], y[1], x1;
    regdae_stats st;
    regdae_solver *s = regdae_create();

    /* REGDAE_WARN_UNRESOLVED: the ratio resolution_tol is compared with is >= 1 by
       construction at every sample of a singular interval before the layer (here
       t = -0.2, -0.1), so resolution_tol = 1e-6 warns, once (one pass); with 0 (off)
       nothing warns. The run goes on after the warning and ends at x(1) = 2 (rtol =
       atol = 1e-5: the error measured is 2e-10; 1e-4 means a bug). */
    CHECK(e51_warnings(s, "1e-6", &x1) == 1);
    CHECK(fabs(x1 - 2.0) < 1e-4);
    CHECK(regdae_get_statistics(s, &st) == REGDAE_SUCCESS && st.unresolved_passes == 1 && st.t == 1.0);
    CHECK(e51_warnings(s, "0", &x1) == 0);
    CHECK(fabs(x1 - 2.0) < 1e-4);
    CHECK(regdae_get_statistics(s, &st) == REGDAE_SUCCESS && st.unresolved_passes == 0);
    /* the message is the last call's: the warning's (the sample at t = -0.1), then a
       refusal's, then "" */
    regdae_set_option(s, "resolution_tol", "1e-6");
    CHECK(regdae_init(s, -1.0, x0, 1, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, -0.5, x, 1, y, 1, NULL, 0) == REGDAE_SUCCESS && strlen(regdae_message(s)) == 0);
    CHECK(regdae_advance(s, -0.1, x, 1, y, 1, NULL, 0) == REGDAE_WARN_UNRESOLVED && says(s, "resolution_tol"));
    CHECK(regdae_advance(s, -0.2, x, 1, y, 1, NULL, 0) == REGDAE_ERR_BAD_INPUT && says(s, "before the current time") &&
          !says(s, "resolution_tol"));
    CHECK(regdae_advance(s, 1.0, x, 1, y, 1, NULL, 0) == REGDAE_SUCCESS && strlen(regdae_message(s)) == 0);

    /* REGDAE_WARN_MULTIPLIER_UNDEFINED: Baumgarte's multiplier equation t^2 y = ... is
       singular at t = 0: x valid, y NaN; then on to t = 1, x = 2 and y = 1 */
    regdae_set_method(s, REGDAE_METHOD_BAUMGARTE);
    CHECK(regdae_init(s, -1.0, x0, 1, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 0.0, x, 1, y, 1, NULL, 0) == REGDAE_WARN_MULTIPLIER_UNDEFINED &&
          says(s, "the multiplier at t = 0.000000E+00 is undefined"));
    CHECK(fabs(x[0] - 1.0) < 1e-4 && isnan(y[0]));
    CHECK(regdae_advance(s, 1.0, x, 1, y, 1, NULL, 0) == REGDAE_SUCCESS && strlen(regdae_message(s)) == 0);
    CHECK(fabs(x[0] - 2.0) < 1e-4 && fabs(y[0] - 1.0) < 1e-4);
    regdae_destroy(&s);
}

/* ---- estimate ------------------------------------------------------------------------ */

/* The circle of `problems` (first order) at rtol = atol = 1e-6 with error_estimate=yes, 10
   outputs in [0, 5]: e = regdae_error_estimate's x_companion - x, est its norm in error
   weights max_i |e_i| / (rtol |x_i| + atol), true the same norm of x - (cos t, sin t). At each
   output est is within a factor 10 of true, and the statistic error_estimate is est; without
   the option there is no estimate (REGDAE_ERR_BAD_INPUT, e NaN, the statistic -1). */
static void estimate(void)
{
    const double x0[2] = {1.0, 0.0}, tol = 1e-6;
    double x[2], y[1], e[2], t, w, est, truth, ratio_min = INFINITY, ratio_max = 0.0;
    regdae_stats st;
    int k, i, status, stat_ok = 1, outputs = 0;
    regdae_solver *s = circle_solver(NULL);
    regdae_set_rtol(s, tol);
    regdae_set_atol(s, tol);
    CHECK(regdae_set_option(s, "error_estimate", "yes") == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    for (k = 1; k <= 10; k++) {
        t = 0.5 * k;
        status = regdae_advance(s, t, x, 2, y, 1, NULL, 0);
        if (status != REGDAE_SUCCESS || regdae_error_estimate(s, e, 2) != REGDAE_SUCCESS) {
            printf("  t = %g: status %d: %s\n", t, status, regdae_message(s));
            break;
        }
        est = 0.0;
        truth = 0.0;
        for (i = 0; i < 2; i++) {
            w = tol * fabs(x[i]) + tol;
            est = fmax(est, fabs(e[i]) / w);
            truth = fmax(truth, fabs(x[i] - (i == 0 ? cos(t) : sin(t))) / w);
        }
        regdae_get_statistics(s, &st);
        stat_ok = stat_ok && fabs(st.error_estimate - est) <= 1e-6 * est;
        ratio_min = fmin(ratio_min, est / truth);
        ratio_max = fmax(ratio_max, est / truth);
        outputs++;
    }
    printf("  estimate/true error over %d outputs: %.3g ... %.3g\n", outputs, ratio_min, ratio_max);
    CHECK(outputs == 10);
    CHECK(stat_ok);
    CHECK(ratio_min >= 0.1 && ratio_max <= 10.0);
    /* off: no estimate */
    CHECK(regdae_set_option(s, "error_estimate", "no") == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 1.0, x, 2, y, 1, NULL, 0) == REGDAE_SUCCESS);
    CHECK(regdae_error_estimate(s, e, 2) == REGDAE_ERR_BAD_INPUT && isnan(e[0]) && isnan(e[1]));
    CHECK(regdae_get_statistics(s, &st) == REGDAE_SUCCESS && st.error_estimate == -1.0);
    regdae_destroy(&s);
}

/* ---- version and status texts -------------------------------------------------------- */

static void version(void)
{
    static const int codes[] = {REGDAE_SUCCESS, REGDAE_WARN_MULTIPLIER_UNDEFINED, REGDAE_WARN_UNRESOLVED,
                                REGDAE_ERR_BAD_INPUT, REGDAE_ERR_INCONSISTENT_IC, REGDAE_ERR_USER_CALLBACK,
                                REGDAE_ERR_NOT_PSD, REGDAE_ERR_SINGULAR, REGDAE_ERR_LAPACK, REGDAE_ERR_SUNDIALS,
                                REGDAE_ERR_INTEGRATION, REGDAE_ERR_NOT_INITIALIZED, REGDAE_ERR_NONFINITE,
                                REGDAE_ERR_MASS_MATRIX, REGDAE_ERR_BRANCH, REGDAE_ERR_DRIFT, REGDAE_ERR_INVARIANT,
                                REGDAE_ERR_STRUCTURE, REGDAE_ERR_JACOBIAN, REGDAE_ERR_WORK, REGDAE_ERR_MEMORY,
                                REGDAE_ROOT_FOUND};
    static const int not_codes[] = {-1, 4, 100, -100, -119, -33};
    const int n_codes = (int)(sizeof codes / sizeof codes[0]);
    char expected[64];
    const char *text;
    int major = -1, minor = -1, patch = -1, i, j, distinct = 1;

    /* the library's version is the header's */
    text = regdae_version(&major, &minor, &patch);
    snprintf(expected, sizeof expected, "%d.%d.%d", REGDAE_VERSION_MAJOR, REGDAE_VERSION_MINOR, REGDAE_VERSION_PATCH);
    CHECK(text != NULL && strcmp(text, expected) == 0);
    CHECK(major == REGDAE_VERSION_MAJOR && minor == REGDAE_VERSION_MINOR && patch == REGDAE_VERSION_PATCH);
    CHECK(regdae_version(NULL, NULL, NULL) == text); /* static: the same text each time */
    major = -1;
    CHECK(strcmp(regdae_version(&major, NULL, NULL), expected) == 0 && major == REGDAE_VERSION_MAJOR);

    /* every status has its own static text; the texts are the Fortran API's */
    CHECK(strcmp(regdae_status_string(REGDAE_SUCCESS), "success") == 0);
    CHECK(strcmp(regdae_status_string(REGDAE_ERR_BAD_INPUT), "invalid input") == 0);
    CHECK(strstr(regdae_status_string(REGDAE_ERR_MEMORY), "out of memory") != NULL);
    for (i = 0; i < n_codes; i++) {
        text = regdae_status_string(codes[i]);
        CHECK(text != NULL && strlen(text) > 0 && strstr(text, "unknown") == NULL);
        CHECK(regdae_status_string(codes[i]) == text);
        for (j = 0; j < i; j++) distinct = distinct && strcmp(regdae_status_string(codes[j]), text) != 0;
    }
    CHECK(distinct);
    for (i = 0; i < (int)(sizeof not_codes / sizeof not_codes[0]); i++) {
        text = regdae_status_string(not_codes[i]);
        CHECK(text != NULL && strstr(text, "unknown status code") != NULL);
    }
}

/* ---- events ---------------------------------------------------------------------------- */

typedef struct {
    long calls;
    int v_null;   /* v was NULL at the last call */
} event_data;

/* e = (x2, x1) (first order) or (v1, x1) (second order): on the circle x = (cos t, sin t)
   the roots are x2 at k pi, x1 at pi/2 + k pi, v1 = -sin t at k pi. */
static int circle_events(double t, const double *x, const double *v, double *e, void *u)
{
    event_data *d = (event_data *)u;
    (void)t;
    d->calls++;
    d->v_null = (v == NULL);
    e[0] = v == NULL ? x[1] : v[0];
    e[1] = x[0];
    return 0;
}

static void events(void)
{
    const double pi = acos(-1.0), x0[2] = {1.0, 0.0}, v0[2] = {0.0, 1.0};
    const int direction[2] = {0, 1}, stop_none[2] = {0, 0}, bad_direction[2] = {2, 0};
    double x[2], v[2];
    int roots[2], status;
    event_data d = {0, 0};
    regdae_stats st;
    regdae_solver *s = circle_solver(NULL);

    /* first order: x2 both ways, x1 increasing only; rtol 1e-8, the roots within 1e-7 */
    CHECK(regdae_set_events(s, 2, circle_events, direction, NULL, &d) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, NULL, 0) == REGDAE_SUCCESS);
    status = regdae_advance(s, 5.0, x, 2, NULL, 0, NULL, 0);
    regdae_get_statistics(s, &st);
    CHECK(status == REGDAE_ROOT_FOUND);
    CHECK(fabs(st.t - pi) <= 1e-7); /* x1 = 0 at pi/2 is decreasing: filtered */
    CHECK(regdae_get_roots(s, roots, 2) == REGDAE_SUCCESS && roots[0] == -1 && roots[1] == 0);
    CHECK(fabs(x[1]) <= 1e-7);
    CHECK(d.calls > 0 && d.v_null);
    status = regdae_advance(s, 5.0, x, 2, NULL, 0, NULL, 0);
    regdae_get_statistics(s, &st);
    CHECK(status == REGDAE_ROOT_FOUND && fabs(st.t - 1.5 * pi) <= 1e-7);
    CHECK(regdae_get_roots(s, roots, 2) == REGDAE_SUCCESS && roots[0] == 0 && roots[1] == 1);
    CHECK(regdae_advance(s, 5.0, x, 2, NULL, 0, NULL, 0) == REGDAE_SUCCESS);
    regdae_get_statistics(s, &st);
    CHECK(st.roots_found == 2 && st.t == 5.0);
    CHECK(regdae_get_roots(s, roots, 1) == REGDAE_ERR_BAD_INPUT && says(s, "n_events = 2"));
    regdae_destroy(&s);

    /* second order: v1 = -sin t and x1 = cos t logged and continued over [0, 5]: pi/2, pi, 3pi/2 */
    s = regdae_create();
    regdae_set_second_order(s, 2, 1, c2_f, c2_b, c_g, c_gradient, NULL, NULL);
    regdae_set_rtol(s, 1e-8);
    regdae_set_atol(s, 1e-8);
    CHECK(regdae_set_events(s, 2, circle_events, NULL, stop_none, &d) == REGDAE_SUCCESS);
    CHECK(regdae_init(s, 0.0, x0, 2, v0, 2) == REGDAE_SUCCESS);
    CHECK(regdae_advance(s, 5.0, x, 2, NULL, 0, v, 2) == REGDAE_SUCCESS);
    regdae_get_statistics(s, &st);
    CHECK(st.roots_found == 3 && !d.v_null);

    /* bad input: n_events < 0, no routine, a direction of 2 */
    CHECK(regdae_set_events(s, -1, circle_events, NULL, NULL, &d) == REGDAE_ERR_BAD_INPUT);
    CHECK(regdae_set_events(s, 2, NULL, NULL, NULL, &d) == REGDAE_ERR_BAD_INPUT && says(s, "NULL"));
    CHECK(regdae_set_events(s, 2, circle_events, bad_direction, NULL, &d) == REGDAE_ERR_BAD_INPUT &&
          says(s, "direction"));
    CHECK(regdae_set_events(s, 0, NULL, NULL, NULL, NULL) == REGDAE_SUCCESS); /* none */
    regdae_destroy(&s);
}

/* ---- threads -------------------------------------------------------------------------- */

/* What one run of thread_problems writes: the circle (first order, integrator auto) at 40
   outputs, x and y; the K particles (structured: augmented, KLU) at 8 outputs, q and
   lambda; the statuses. */
#define CIRCLE_OUTPUTS 40
#define PARTICLE_OUTPUTS 8
typedef struct {
    double circle[CIRCLE_OUTPUTS][3];
    double particles[PARTICLE_OUTPUTS][3 * K];
    int status;
} thread_result;

static void *thread_problems(void *arg)
{
    thread_result *r = (thread_result *)arg;
    const double x0[2] = {1.0, 0.0};
    double q[2 * K], v[2 * K];
    int diag[2 * K], grow[2 * K], gcol[2 * K], j, k;
    regdae_solver *s = circle_solver(NULL);

    memset(r, 0, sizeof *r);
    r->status = regdae_init(s, 0.0, x0, 2, NULL, 0);
    for (k = 0; k < CIRCLE_OUTPUTS && r->status == REGDAE_SUCCESS; k++) {
        r->status = regdae_advance(s, 0.25 * (k + 1), r->circle[k], 2, &r->circle[k][2], 1, NULL, 0);
    }
    for (j = 0; j < 2 * K; j++) {
        diag[j] = j;
        grow[j] = j / 2;
        gcol[j] = j;
    }
    regdae_set_mechanical(s, 2 * K, K, k_mass, k_forces, k_g, k_gx, NULL, NULL);
    regdae_set_pattern(s, REGDAE_PATTERN_MASS, 2 * K, diag, diag);
    regdae_set_pattern(s, REGDAE_PATTERN_CONSTRAINT, 2 * K, grow, gcol);
    regdae_set_pattern(s, REGDAE_PATTERN_FORCE_Q, 0, NULL, NULL);
    regdae_set_pattern(s, REGDAE_PATTERN_FORCE_V, 0, NULL, NULL);
    k_start(q, v);
    if (r->status == REGDAE_SUCCESS) r->status = regdae_init(s, 0.0, q, 2 * K, v, 2 * K);
    for (k = 0; k < PARTICLE_OUTPUTS && r->status == REGDAE_SUCCESS; k++) {
        r->status = regdae_advance(s, 0.25 * (k + 1), r->particles[k], 2 * K, &r->particles[k][2 * K], K, v, 2 * K);
    }
    regdae_destroy(&s);
    return NULL;
}

/* rounds of n_threads (at most MAX_THREADS) threads at once, each result compared bitwise
   with a serial run */
#define MAX_THREADS 4
static void thread_rounds(int rounds, int n_threads)
{
    thread_result serial, parallel[MAX_THREADS];
    pthread_t id[MAX_THREADS];
    int round, i, started;

#ifdef REGDAE_TEST_NO_THREADS
    /* a library built with gfortran's -fcheck=recursion stops a second thread entering a
       procedure another thread is in ("Recursive call to nonrecursive procedure") */
    printf("  skipped: the library checks recursion (-fcheck=all), which threads trip\n");
    return;
#endif

    thread_problems(&serial);
    CHECK(serial.status == REGDAE_SUCCESS);
    /* the circle is right (so the comparison below compares solutions) */
    CHECK(fabs(serial.circle[CIRCLE_OUTPUTS - 1][0] - cos(10.0)) < 1e-5 &&
          fabs(serial.particles[PARTICLE_OUTPUTS - 1][0] - cos(0.25 * PARTICLE_OUTPUTS)) < 1e-4);
    for (round = 0; round < rounds; round++) {
        started = 0;
        for (i = 0; i < n_threads; i++) started += pthread_create(&id[i], NULL, thread_problems, &parallel[i]) == 0;
        CHECK(started == n_threads);
        for (i = 0; i < started; i++) pthread_join(id[i], NULL);
        for (i = 0; i < started; i++) {
            CHECK(parallel[i].status == REGDAE_SUCCESS);
            CHECK(memcmp(parallel[i].circle, serial.circle, sizeof serial.circle) == 0);
            CHECK(memcmp(parallel[i].particles, serial.particles, sizeof serial.particles) == 0);
        }
    }
}

static void threads(void) { thread_rounds(3, 2); }

/* the same at 4 threads for 100 rounds, where a race (e.g. on a static the compiler made:
   doc/methods.md, "No global state") shows more often; run only when named */
static void threads_stress(void) { thread_rounds(100, MAX_THREADS); }

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*run)(void);
        int named_only; /* run only when named (not in a run of all suites) */
    } suites[] = {{"bad_input", bad_input, 0},   {"problems", problems, 0},
                  {"handles", handles, 0},       {"callbacks", callbacks, 0},
                  {"options", options, 0},       {"atol_vector", atol_vector, 0},
                  {"warnings", warnings, 0},     {"version", version, 0},
                  {"events", events, 0},         {"threads", threads, 0},
                  {"threads_stress", threads_stress, 1}, {"estimate", estimate, 0}};
    const int n_suites = (int)(sizeof suites / sizeof suites[0]);
    int i, ran = 0;
    for (i = 0; i < n_suites; i++) {
        if (argc > 1 ? strcmp(argv[1], suites[i].name) != 0 : suites[i].named_only) continue;
        printf("suite %s\n", suites[i].name);
        suites[i].run();
        ran++;
    }
    if (ran == 0) {
        printf("capi_tester: unknown suite \"%s\" (bad_input, problems, handles, callbacks, options, atol_vector, "
               "warnings, version, events, threads, threads_stress, estimate)\n",
               argv[1]);
        return 2;
    }
    printf("%d passed, %d failed\n", checks_passed, checks_failed);
    return checks_failed > 0 ? 1 : 0;
}
