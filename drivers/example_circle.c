/* A complete minimal regdae program in C: the problem of example_circle.f90.
 *
 *   x' = f(x) - B(x) y,  0 = g(x) = x1^2 + x2^2 - 1,
 *   f(x) = (x1 - x2, x1 + x2),  G = 2 (x1, x2),  B = G^T.
 *
 * x(t) = (cos t, sin t) exactly, y = 1/2. The program checks its answer against
 * it; with the options of example_circle.f90 it prints the same table.
 */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>

#include "regdae.h"

/* Parameters would live in a struct passed as user_data; the circle has none. */

static int circle_f(double t, const double *x, double *f, void *user_data)
{
    (void)t;
    (void)user_data;
    f[0] = x[0] - x[1];
    f[1] = x[0] + x[1];
    return 0;
}

static int circle_b(double t, const double *x, double *b, void *user_data)
{
    (void)t;
    (void)user_data;
    b[0] = 2.0 * x[0]; /* B = G^T, n x m = 2 x 1, column-major */
    b[1] = 2.0 * x[1];
    return 0;
}

static int circle_g(double t, const double *x, double *g, void *user_data)
{
    (void)t;
    (void)user_data;
    g[0] = x[0] * x[0] + x[1] * x[1] - 1.0;
    return 0;
}

static int circle_gx(double t, const double *x, double *gx, void *user_data)
{
    (void)t;
    (void)user_data;
    gx[0] = 2.0 * x[0]; /* G, m x n = 1 x 2: entry (0, j) at gx[0 + j*1] */
    gx[1] = 2.0 * x[1];
    return 0;
}

/* Print the message of a failed call, free the solver, and return 1. */
static int fail(const char *what, regdae_solver **solver)
{
    printf("%s failed: %s\n", what, regdae_message(*solver));
    regdae_destroy(solver);
    return 1;
}

int main(void)
{
    const double x0[2] = {1.0, 0.0};
    double x[2], y[1], t, err = 0.0;
    regdae_stats st;
    int k;
    regdae_solver *solver = regdae_create();

    if (solver == NULL) return 1;
    /* x in R^2, one constraint; g does not depend on t: gt = NULL (a difference quotient, 0) */
    if (regdae_set_first_order(solver, 2, 1, circle_f, circle_b, circle_g, circle_gx, NULL, NULL) != REGDAE_SUCCESS)
        return fail("set_first_order", &solver);
    /* the options of example_circle.f90, typed and as text */
    if (regdae_set_method(solver, REGDAE_METHOD_TRUST_REGION) != REGDAE_SUCCESS ||
        regdae_set_eps(solver, 1.0e-6) != REGDAE_SUCCESS || regdae_set_rtol(solver, 1.0e-8) != REGDAE_SUCCESS ||
        regdae_set_option(solver, "atol", "1e-8") != REGDAE_SUCCESS)
        return fail("set_option", &solver);

    if (regdae_init(solver, 0.0, x0, 2, NULL, 0) != REGDAE_SUCCESS) return fail("init", &solver);
    for (k = 1; k <= 10; k++) {
        t = 0.5 * k;
        if (regdae_advance(solver, t, x, 2, y, 1, NULL, 0) != REGDAE_SUCCESS) return fail("advance", &solver);
        err = fmax(err, fmax(fabs(x[0] - cos(t)), fabs(x[1] - sin(t))));
        printf("%5.2f%16.8E%16.8E%16.8E\n", t, x[0], x[1], y[0]);
    }
    regdae_get_statistics(solver, &st);
    printf("max error %9.2E in %" PRId64 " steps\n", err, st.steps);
    regdae_destroy(&solver);
    /* the same bound as example_circle.f90: rtol = 1e-8 over 0.8 revolutions gives
       an error of 6e-9; 1e-5 means a bug */
    return err > 1.0e-5 ? 1 : 0;
}
