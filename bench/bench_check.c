/*
 * bench_check.c - the cost of an embedded check per added sample.
 *
 *   add      mcstat_stream_add on values already in memory (store, counter,
 *            a flush through mcstat_moments_add_array every 492 values);
 *   loop     a Monte Carlo loop (splitmix64, a sqrt, a sum) without and with
 *            mcstat_stream_add of each estimate: the difference is what a
 *            renderer pays per sample;
 *   moments  mcstat_moments_add per value, for comparison (a full merge).
 * Each figure is the best of `reps` runs (default 7), one thread.
 * usage: bench_check [reps]
 */
#include "mcstat.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline double uniform01(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}

static volatile double sink;

__attribute__((noinline)) static double loop_plain(long n, uint64_t seed)
{
    double sum = 0.0;
    for (long i = 0; i < n; i++) {
        double mu = sqrt(uniform01(&seed));
        sum += 3.141592653589793 * (1.0 + mu * mu);
    }
    return sum;
}

__attribute__((noinline)) static double loop_checked(long n, uint64_t seed, mcstat_stream *s)
{
    double sum = 0.0;
    for (long i = 0; i < n; i++) {
        double mu = sqrt(uniform01(&seed));
        double e = 3.141592653589793 * (1.0 + mu * mu);
        sum += e;
        mcstat_stream_add(s, e);
    }
    return sum;
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 7;
    const long n = 20000000;
    double *v = malloc(65536 * sizeof *v);
    uint64_t seed = 1;
    for (int i = 0; i < 65536; i++)
        v[i] = uniform01(&seed);
    double best_add = INFINITY, best_plain = INFINITY, best_checked = INFINITY, best_mom = INFINITY;
    mcstat_stream s;
    for (int r = 0; r < reps; r++) {
        mcstat_stream_init(&s);
        double t = now();
        for (long i = 0; i < n; i++)
            mcstat_stream_add(&s, v[i & 65535]);
        t = now() - t;
        best_add = fmin(best_add, t / n * 1e9);

        t = now();
        sink = loop_plain(n, 42 + r);
        t = now() - t;
        best_plain = fmin(best_plain, t / n * 1e9);

        mcstat_stream_init(&s);
        t = now();
        sink = loop_checked(n, 42 + r, &s);
        t = now() - t;
        best_checked = fmin(best_checked, t / n * 1e9);

        mcstat_moments m;
        mcstat_moments_init(&m);
        t = now();
        for (long i = 0; i < n / 10; i++)
            mcstat_moments_add(&m, v[i & 65535]);
        t = now() - t;
        best_mom = fmin(best_mom, t / (n / 10) * 1e9);
    }
    printf("mcstat_stream_add on stored values:   %.2f ns per value\n", best_add);
    printf("Monte Carlo loop without checks:      %.2f ns per sample\n", best_plain);
    printf("Monte Carlo loop with mcstat_stream:  %.2f ns per sample\n", best_checked);
    printf("overhead of the check per sample:     %.2f ns\n", best_checked - best_plain);
    printf("mcstat_moments_add (for comparison):  %.2f ns per value\n", best_mom);
    free(v);
    return 0;
}
