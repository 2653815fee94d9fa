/*
 * test_ks_calibration.c - the K-S test's behaviour as a test: under H0 it
 * rejects at most at rate alpha (plus Monte Carlo noise) and not far below,
 * on continuous data and on data with heavy ties (primary estimates with 70%
 * exact zeros, ERRATA 7), exact and simulated; and Canner's weight has more
 * power than the unweighted statistic against a difference in the tails
 * (Student's t with 3 degrees of freedom against a normal).
 */
#include "harness.h"
#include "mcstat.h"

#include <stdint.h>
#include <stdlib.h>

static uint64_t rng_state = 777;
#include "test_rng.h"

static double student3(void)
{
    double z = normal(), c = 0;
    for (int k = 0; k < 3; k++) {
        double g = normal();
        c += g * g;
    }
    return z / sqrt(c / 3.0);
}

/* a primary estimate: 0 when the sample misses the emitter (70%) */
static double primary(void)
{
    return unif() < 0.7 ? 0.0 : -log(unif());
}

static void calibration(const char *what, double (*draw)(void), int nx, int ny, int method, int reps)
{
    const double alpha = 0.05;
    double *x = malloc(nx * sizeof *x), *y = malloc(ny * sizeof *y);
    for (int w = 0; w < 2; w++) {
        mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
        o.weight = w;
        o.method = method;
        o.threads = 2; /* simulation threads, as before the default became 1 (make tsan-test runs this) */
        o.n_sim = 999;
        o.critical = 0;
        int rej = 0;
        for (int k = 0; k < reps; k++) {
            for (int i = 0; i < nx; i++)
                x[i] = draw();
            for (int i = 0; i < ny; i++)
                y[i] = draw();
            o.seed = (uint64_t)k;
            mcstat_result r;
            CHECK_INT(mcstat_ks_test_2(x, nx, y, ny, MCSTAT_TWO_SIDED, alpha, &o, &r), MCSTAT_OK);
            rej += r.reject;
        }
        double rate = (double)rej / reps, se = sqrt(alpha * (1 - alpha) / reps);
        printf("H0 %-10s %3d+%-3d %-8s %-6s: rejection rate %.4f (alpha %.2f, s.e. %.4f)\n", what, nx, ny,
               method == MCSTAT_METHOD_EXACT ? "exact" : "simulate", w ? "Canner" : "none", rate, alpha, se);
        CHECK_MSG(rate <= alpha + 3.5 * se, "%s %s: rate %.4f", what, w ? "Canner" : "none", rate);
        CHECK_MSG(rate >= 0.6 * alpha, "%s %s: rate %.4f is far below alpha", what, w ? "Canner" : "none", rate);
    }
    free(x);
    free(y);
}

static void power(void)
{
    enum { N = 100, REPS = 400 };
    double x[N], y[N];
    int rej[2] = {0, 0};
    for (int k = 0; k < REPS; k++) {
        for (int i = 0; i < N; i++) {
            x[i] = student3();
            y[i] = normal();
        }
        for (int w = 0; w < 2; w++) {
            mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
            o.weight = w;
            o.method = MCSTAT_METHOD_EXACT;
            o.critical = 0;
            mcstat_result r;
            CHECK_INT(mcstat_ks_test_2(x, N, y, N, MCSTAT_TWO_SIDED, 0.05, &o, &r), MCSTAT_OK);
            rej[w] += r.reject;
        }
    }
    double p0 = (double)rej[0] / REPS, p1 = (double)rej[1] / REPS;
    printf("power, t(3) vs N(0,1), %d+%d, alpha 0.05: unweighted %.3f, Canner %.3f\n", N, N, p0, p1);
    /* paired on the same data: Canner's must win clearly */
    CHECK_MSG(p1 > p0 + 0.1, "Canner %.3f vs unweighted %.3f", p1, p0);
}

int main(void)
{
    calibration("continuous", normal, 40, 50, MCSTAT_METHOD_EXACT, 2000);
    calibration("70% zeros", primary, 40, 50, MCSTAT_METHOD_EXACT, 2000);
    calibration("70% zeros", primary, 150, 120, MCSTAT_METHOD_SIMULATE, 600);
    power();
    return h_report("test_ks_calibration");
}
