/*
 * integrator.c - a tiny multi-threaded Monte Carlo "renderer" with mcstat's
 * embedded checks (mcstat/embedded.h).
 *
 * Each frame estimates the irradiance at a point under a sky of radiance
 * L(w) = 1 + cos^2(theta):  E = integral L cos dw = 1.5 pi.  Every thread
 * draws cosine-weighted directions (mu = cos theta = sqrt(u)) and returns the
 * primary estimate pi L(w); it keeps one mcstat_stream, merged at the end of
 * the frame, where two expectations are checked without storing samples:
 *   - the mean is E (to within a tolerance, t test at alpha), and
 *   - the variance per sample is below a bound (chi-squared test at alpha);
 *     the right sampler's is pi^2/12 = 0.822.
 * Planted bugs show what the checks catch:
 *   --bug bias      mu = u instead of sqrt(u): mean 4 pi / 3, not 1.5 pi;
 *   --bug variance  uniform directions weighted correctly (2 pi L mu): the
 *                   mean is right, the variance is 12.4.
 *
 * Built twice (examples/check/CMakeLists.txt): mcstat_integrator with
 * MCSTAT_CHECKS=1 and mcstat_integrator_nochecks with checks compiled out;
 * both print the time per sample, whose difference is the checks' cost.
 *
 * usage: integrator [--threads T] [--frames F] [--samples N] [--bug bias|variance]
 *                   [--expect-failure mean|variance]
 * Exit status: 0 when every check passed (with --expect-failure: when that
 * check failed in every frame and the other never did), 1 otherwise, 2 for
 * bad usage.
 */
#include "mcstat/embedded.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_THREADS 64
#define PI 3.14159265358979323846

enum { BUG_NONE, BUG_BIAS, BUG_VARIANCE };

/* One per thread, on its own cache lines: threads that wrote next to each
 * other's fields would slow each other down (false sharing). */
typedef struct {
    _Alignas(64) uint64_t seed;
    long samples;
    int bug;
    double sum; /* the "image": one pixel */
    MCSTAT_CHECK_ONLY(mcstat_stream acc;)
} worker;

static inline double uniform01(uint64_t *s) /* splitmix64, 53 bits, in (0, 1) */
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}

static void *render(void *arg)
{
    worker *w = arg;
    uint64_t s = w->seed;
    const long n = w->samples; /* locals: the flush, an opaque call, could */
    const int bug = w->bug;    /* otherwise force them to be reloaded      */
    double sum = 0.0;
    MCSTAT_CHECK_INIT(w->acc);
    for (long i = 0; i < n; i++) {
        double u = uniform01(&s), e;
        if (bug == BUG_NONE) {
            double mu = sqrt(u); /* cosine-weighted: pdf cos/pi */
            e = PI * (1.0 + mu * mu);
        } else if (bug == BUG_BIAS) {
            double mu = u; /* not cosine-weighted, weighted as if it were */
            e = PI * (1.0 + mu * mu);
        } else {
            double mu = u; /* uniform on the hemisphere: pdf 1/(2 pi) */
            e = 2.0 * PI * (1.0 + mu * mu) * mu;
        }
        sum += e;
        MCSTAT_CHECK_ADD(w->acc, e);
    }
    w->sum = sum;
    return NULL;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
    int threads = 2, frames = 3, bug = BUG_NONE, expect_failure = 0;
    long samples = 2000000;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--samples") && i + 1 < argc)
            samples = atol(argv[++i]);
        else if (!strcmp(argv[i], "--bug") && i + 1 < argc) {
            ++i;
            bug = !strcmp(argv[i], "bias") ? BUG_BIAS : !strcmp(argv[i], "variance") ? BUG_VARIANCE : -1;
        } else if (!strcmp(argv[i], "--expect-failure") && i + 1 < argc) {
            ++i;
            expect_failure = !strcmp(argv[i], "mean") ? 1 : !strcmp(argv[i], "variance") ? 2 : -1;
        }
        else
            bug = -1;
    }
    if (bug < 0 || expect_failure < 0 || threads < 1 || threads > MAX_THREADS || frames < 1 || samples < 2) {
        fprintf(stderr, "usage: %s [--threads T] [--frames F] [--samples N] [--bug bias|variance] "
                        "[--expect-failure mean|variance]\n", argv[0]);
        return 2;
    }
    const double exact = 1.5 * PI;
    worker w[MAX_THREADS];
    pthread_t tid[MAX_THREADS];
    int mean_failures = 0, var_failures = 0;
    double best = INFINITY;
    printf("checks %s; %d threads, %ld samples per thread per frame, E = 1.5 pi = %.6f\n",
           MCSTAT_CHECKS ? "on" : "off (compiled out)", threads, samples, exact);
    for (int f = 0; f < frames; f++) {
        double t0 = now();
        for (int t = 0; t < threads; t++) {
            memset(&w[t], 0, sizeof w[t]);
            w[t].seed = 0x5EED0000ull + (uint64_t)f * 1000003u + (uint64_t)t * 7919u;
            w[t].samples = samples;
            w[t].bug = bug;
            pthread_create(&tid[t], NULL, render, &w[t]);
        }
        double sum = 0.0;
        for (int t = 0; t < threads; t++) {
            pthread_join(tid[t], NULL);
            sum += w[t].sum;
        }
        double dt = now() - t0, ns = dt * 1e9 * threads / ((double)samples * threads);
        best = ns < best ? ns : best;
        printf("frame %d: estimate %.6f, %.2f ns per sample per thread", f, sum / ((double)samples * threads), ns);
        /* end of frame: merge the threads' streams, check, report */
        MCSTAT_CHECK_ONLY(
            mcstat_stream frame;
            MCSTAT_CHECK_INIT(frame);
            for (int t = 0; t < threads; t++)
                MCSTAT_CHECK_MERGE(frame, w[t].acc);
            /* the reference is exact: a tolerance of 1e-9 only absorbs its rounding */
            int bad_mean = MCSTAT_CHECK_MEAN(frame, exact, 1e-9, 0.001);
            int bad_var = MCSTAT_CHECK_VAR_BELOW(frame, 1.0, 0.001);
            printf(", mean check %s, variance check %s", bad_mean ? "FAILED" : "passed",
                   bad_var ? "FAILED" : "passed");
            mean_failures += bad_mean;
            var_failures += bad_var;
        )
        printf("\n");
    }
    printf("best frame: %.2f ns per sample (wall time x threads / samples)\n", best);
    if (!MCSTAT_CHECKS)
        return expect_failure ? 1 : 0; /* nothing can be detected without checks */
    if (expect_failure == 1)
        return mean_failures == frames && var_failures == 0 ? 0 : 1;
    if (expect_failure == 2)
        return var_failures == frames && mean_failures == 0 ? 0 : 1;
    return mean_failures + var_failures == 0 ? 0 : 1;
}
