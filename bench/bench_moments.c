/*
 * bench_moments.c - moments and the one-sample t test over a large array,
 * against a plain sum of the same array in the same run (the machine's
 * memory read bandwidth), and against the textbook alternatives.
 *
 * Usage: bench_moments [n] [repeats]   (default 1e7 doubles, 7 runs, at most 64)
 * Prints a Markdown table on stdout: median time per case with the fastest
 * and slowest run; the bandwidth share compares medians.
 */
#include "mcstat.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The yardstick: a sum with eight independent accumulators, as fast as the
 * memory delivers the data. */
static double plain_sum(const double *x, size_t n)
{
    double s[8] = {0};
    size_t i = 0;
    for (; i + 8 <= n; i += 8)
        for (int k = 0; k < 8; k++)
            s[k] += x[i + k];
    for (; i < n; i++)
        s[0] += x[i];
    return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

/* Welford's one-value update, the usual streaming algorithm. */
static double welford_var(const double *x, size_t n)
{
    double mean = 0.0, m2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = x[i] - mean;
        mean += d / (double)(i + 1);
        m2 += d * (x[i] - mean);
    }
    return m2 / (double)(n - 1);
}

/* The naive one-pass formula: sum of squares minus n mean^2. */
static double naive_var(const double *x, size_t n)
{
    double s = 0.0, s2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        s += x[i];
        s2 += x[i] * x[i];
    }
    return (s2 - s * s / (double)n) / (double)(n - 1);
}

static volatile double sink;

typedef struct {
    const char *name;
    double t[64], value, median;
} row;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? (size_t)atof(argv[1]) : 10000000;
    int reps = argc > 2 ? atoi(argv[2]) : 7;
    if (reps < 1)
        reps = 1;
    if (reps > 64)
        reps = 64;
    double *x = malloc(n * sizeof *x);
    if (!x)
        return 1;
    /* 1e9 + U(0,1) noise: where naive formulas lose digits */
    uint64_t s = 20261123;
    for (size_t i = 0; i < n; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        x[i] = 1e9 + (double)(s >> 11) * 0x1p-53;
    }
    /* reference variance in long double, two passes */
    long double mu = 0;
    for (size_t i = 0; i < n; i++)
        mu += x[i];
    mu /= n;
    long double ss = 0;
    for (size_t i = 0; i < n; i++)
        ss += (x[i] - mu) * (x[i] - mu);
    double var_ref = (double)(ss / (n - 1));

    static row rows[5] = {{"plain sum (memory bandwidth)", {0}, 0, 0},
                          {"mcstat_moments_add_array", {0}, 0, 0},
                          {"mcstat_t_test_1 (moments + test)", {0}, 0, 0},
                          {"Welford's update", {0}, 0, 0},
                          {"naive sum of squares", {0}, 0, 0}};
    for (int r = 0; r < reps; r++) {
        double t0 = now();
        sink = plain_sum(x, n);
        double t1 = now();
        mcstat_moments m;
        mcstat_moments_init(&m);
        mcstat_moments_add_array(&m, x, n);
        double t2 = now();
        mcstat_result res;
        mcstat_t_test_1(x, n, 1e9 + 0.5, MCSTAT_TWO_SIDED, 0.05, &res);
        double t3 = now();
        double wv = welford_var(x, n);
        double t4 = now();
        double nv = naive_var(x, n);
        double t5 = now();
        double t[5] = {t1 - t0, t2 - t1, t3 - t2, t4 - t3, t5 - t4};
        double v[5] = {0, mcstat_moments_var(&m), mcstat_moments_var(&m), wv, nv};
        for (int k = 0; k < 5; k++) {
            rows[k].t[r] = t[k];
            rows[k].value = v[k];
        }
        sink = res.p_value;
    }
    double bytes = (double)n * sizeof(double);
    for (int k = 0; k < 5; k++) {
        qsort(rows[k].t, (size_t)reps, sizeof(double), cmp_double);
        rows[k].median = reps % 2 ? rows[k].t[reps / 2] : 0.5 * (rows[k].t[reps / 2 - 1] + rows[k].t[reps / 2]);
    }
    printf("| %.0e doubles (1e9 + U(0,1)), %d runs | time (ms), median [fastest-slowest] | GB/s (median) | "
           "share of plain-sum bandwidth | relative error of the variance |\n|---|---:|---:|---:|---:|\n",
           (double)n, reps);
    for (int k = 0; k < 5; k++) {
        double gbs = bytes / rows[k].median / 1e9;
        char err[32] = "-";
        if (k > 0)
            snprintf(err, sizeof err, "%.1e", fabs(rows[k].value - var_ref) / var_ref);
        printf("| %s | %.2f [%.2f-%.2f] | %.1f | %.0f%% | %s |\n", rows[k].name, 1e3 * rows[k].median,
               1e3 * rows[k].t[0], 1e3 * rows[k].t[reps - 1], gbs, 100.0 * rows[0].median / rows[k].median, err);
    }
    free(x);
    return 0;
}
