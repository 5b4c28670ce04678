/* Events through the C interface: the pendulum x'' = (0, -g) - 2 x y on |x| = 1
 * from rest at 1 rad; the event functions e0 = x1 (the bottom, stop there) and
 * e1 = v1 (the turning points, logged and continued). The program checks each
 * stop against the exact time (2k - 1) T/4 (T the period, from the complete
 * elliptic integral by the arithmetic-geometric mean). */
#include <math.h>
#include <stdio.h>

#include "regdae.h"

typedef struct {
    double gravity;
} pendulum;

static int f(double t, const double *x, const double *v, double *out, void *u)
{
    (void)t;
    (void)x;
    (void)v;
    out[0] = 0.0;
    out[1] = -((pendulum *)u)->gravity;
    return 0;
}

static int b(double t, const double *x, const double *v, double *out, void *u)
{
    (void)t;
    (void)v;
    (void)u;
    out[0] = 2.0 * x[0];
    out[1] = 2.0 * x[1];
    return 0;
}

static int g(double t, const double *x, double *out, void *u)
{
    (void)t;
    (void)u;
    out[0] = x[0] * x[0] + x[1] * x[1] - 1.0;
    return 0;
}

static int gx(double t, const double *x, double *out, void *u)
{
    (void)t;
    (void)u;
    out[0] = 2.0 * x[0];
    out[1] = 2.0 * x[1];
    return 0;
}

/* e0 = x1, e1 = v1 (v is NULL for a first-order problem) */
static int events(double t, const double *x, const double *v, double *e, void *u)
{
    (void)t;
    (void)u;
    e[0] = x[0];
    e[1] = v[0];
    return 0;
}

int main(void)
{
    const double phi0 = 1.0, x0[2] = {sin(phi0), -cos(phi0)}, v0[2] = {0.0, 0.0};
    const int direction[2] = {0, 0}, stop[2] = {1, 0};
    pendulum p = {9.81};
    double x[2], v[2], a = 1.0, bb = cos(0.5 * phi0), c, period, err = 0.0;
    int roots[2], status, k = 0, i;
    regdae_stats st;
    regdae_solver *s = regdae_create();

    regdae_set_second_order(s, 2, 1, f, b, g, gx, NULL, &p);
    regdae_set_rtol(s, 1e-8);
    regdae_set_atol(s, 1e-8);
    if (regdae_init(s, 0.0, x0, 2, v0, 2) != REGDAE_SUCCESS) {
        printf("init: %s\n", regdae_message(s));
        return 1;
    }
    /* e0 stops at its roots, e1 is logged and the integration goes on; both directions */
    regdae_set_events(s, 2, events, direction, stop, NULL);
    for (i = 0; i < 30; i++) { /* the exact period: 4 K(sin(phi0/2)) / sqrt(g) */
        c = 0.5 * (a + bb);
        bb = sqrt(a * bb);
        a = c;
    }
    period = 2.0 * acos(-1.0) / a / sqrt(p.gravity);
    while ((status = regdae_advance(s, 1.2 * period, x, 2, NULL, 0, v, 2)) == REGDAE_ROOT_FOUND) {
        k++;
        regdae_get_statistics(s, &st);
        regdae_get_roots(s, roots, 2);
        printf("stop %d at t = %.15e, roots %d %d\n", k, st.t, roots[0], roots[1]);
        err = fmax(err, fabs(st.t - (2 * k - 1) * period / 4));
    }
    regdae_get_statistics(s, &st);
    printf("roots found: %d, largest stop-time error %.2e\n", st.roots_found, err);
    regdae_destroy(&s);
    /* rtol 1e-8: 10 rtol = 1e-7 (measured about 1e-9) */
    return status != REGDAE_SUCCESS || k != 2 || st.roots_found != 4 || err > 1e-7;
}
