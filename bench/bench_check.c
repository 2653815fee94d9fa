/*
 * bench_check.c - the cost of an embedded check per added sample.
 *
 *   add      mcstat_stream_add on values already in memory (store, counter,
 *            a flush through mcstat_moments_add_array every 492 values);
 *   loop     a Monte Carlo loop (splitmix64, a sqrt, a sum) without and with
 *            mcstat_stream_add of each estimate: the difference is what a
 *            renderer pays per sample;
 *   moments  mcstat_moments_add per value, for comparison (a full merge).
 * Each figure is the median of `reps` runs (default 7, at most 64), one
 * thread, with the fastest and slowest run beside it; the overhead is the
 * median of the per-run differences (each run times both loops back to
 * back, so a slow moment of the shared machine hits both).
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

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Prints "label median [min-max] unit" of t[0..reps-1] (sorted in place). */
static void show(const char *label, double *t, int reps, const char *unit)
{
    qsort(t, (size_t)reps, sizeof *t, cmp_double);
    double med = reps % 2 ? t[reps / 2] : 0.5 * (t[reps / 2 - 1] + t[reps / 2]);
    printf("%-38s %.2f %s [%.2f-%.2f]\n", label, med, unit, t[0], t[reps - 1]);
}

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
    if (reps < 1)
        reps = 1;
    if (reps > 64)
        reps = 64;
    const long n = 20000000;
    double *v = malloc(65536 * sizeof *v);
    uint64_t seed = 1;
    for (int i = 0; i < 65536; i++)
        v[i] = uniform01(&seed);
    double t_add[64], t_plain[64], t_checked[64], t_over[64], t_mom[64];
    mcstat_stream s;
    for (int r = 0; r < reps; r++) {
        mcstat_stream_init(&s);
        double t = now();
        for (long i = 0; i < n; i++)
            mcstat_stream_add(&s, v[i & 65535]);
        t = now() - t;
        t_add[r] = t / n * 1e9;

        t = now();
        sink = loop_plain(n, 42 + r);
        t = now() - t;
        t_plain[r] = t / n * 1e9;

        mcstat_stream_init(&s);
        t = now();
        sink = loop_checked(n, 42 + r, &s);
        t = now() - t;
        t_checked[r] = t / n * 1e9;
        t_over[r] = t_checked[r] - t_plain[r];

        mcstat_moments m;
        mcstat_moments_init(&m);
        t = now();
        for (long i = 0; i < n / 10; i++)
            mcstat_moments_add(&m, v[i & 65535]);
        t = now() - t;
        t_mom[r] = t / (n / 10) * 1e9;
    }
    printf("median [fastest-slowest] of %d runs\n", reps);
    show("mcstat_stream_add on stored values:", t_add, reps, "ns per value");
    show("Monte Carlo loop without checks:", t_plain, reps, "ns per sample");
    show("Monte Carlo loop with mcstat_stream:", t_checked, reps, "ns per sample");
    show("overhead of the check per sample:", t_over, reps, "ns");
    show("mcstat_moments_add (for comparison):", t_mom, reps, "ns per value");
    free(v);
    return 0;
}
