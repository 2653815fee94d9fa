/*
 * ks_bench.c - measurements behind bench/RESULTS_ks.md and the K-S bounds in
 * mcstat.h: exact p-value and critical-value times, simulation cost per
 * replicate (GSL taus2 against inline xoshiro256++, 1 and 2 threads), the
 * simulated p-value's error against its run time, the asymptotic
 * approximations' errors against exact values, and the unweighted test on
 * 1e6 + 1e6 values.  Usage: ks_bench [section] (all by default):
 *   exact | rng | error | asymp | big
 * Writes bench/out/ks_error_time.csv (data for a plot of error vs time).
 */
#include "internal.h"
#include "mcstat.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static uint64_t rs = 12345;
static double unif(void)
{
    uint64_t z = (rs += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}
static double normal(void) { return sqrt(-2.0 * log(unif())) * cos(2.0 * M_PI * unif()); }

static void sample(double *x, int n, double shift)
{
    for (int i = 0; i < n; i++)
        x[i] = normal() + shift;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median, fastest and slowest of t[0..k-1] (k <= 16; sorted in place). */
typedef struct {
    double med, lo, hi;
} spread;

static spread summarise(double *t, int k)
{
    qsort(t, (size_t)k, sizeof *t, cmp_double);
    spread s = {k % 2 ? t[k / 2] : 0.5 * (t[k / 2 - 1] + t[k / 2]), t[0], t[k - 1]};
    return s;
}

/* "median [fastest-slowest]" of s, scaled */
static const char *fmt_spread(char *buf, size_t len, spread s, double scale, const char *f)
{
    char a[24], b[24], c[24];
    snprintf(a, sizeof a, f, scale * s.med);
    snprintf(b, sizeof b, f, scale * s.lo);
    snprintf(c, sizeof c, f, scale * s.hi);
    snprintf(buf, len, "%s [%s-%s]", a, b, c);
    return buf;
}

/* median (and range) of k runs of a test, in seconds */
static spread time_test(const double *x, int nx, const double *y, int ny, mcstat_ks_options *o, int k,
                        mcstat_result *r)
{
    double t[16];
    k = k > 16 ? 16 : k;
    for (int i = 0; i < k; i++) {
        double t0 = now();
        if (mcstat_ks_test_2(x, nx, y, ny, MCSTAT_TWO_SIDED, 0.05, o, r)) {
            spread bad = {NAN, NAN, NAN};
            return bad;
        }
        t[i] = now() - t0;
    }
    return summarise(t, k);
}

static void bench_exact(void)
{
    printf("\n## Exact method: time per call (median [fastest-slowest] of 5, 3 with the critical value; 2 and 1 "
           "from 2000 + 2000 on), two-sided\n\n");
    printf("| n1 = n2 | weight | p-value | p only (ms) | with critical value (ms) | lattice cells |\n|---|---|---|---|---|---|\n");
    static const int ns[] = {100, 500, 1000, 2000, 4000};
    for (size_t a = 0; a < sizeof ns / sizeof ns[0]; a++)
        for (int w = 1; w >= 0; w--)
            for (int e = 0; e < 3; e++) {
                int n = ns[a];
                double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
                static const double shifts[] = {0.0, 2.2, 6.5}; /* in units of 1/sqrt(n/2) */
                sample(x, n, shifts[e] / sqrt(n / 2.0));
                sample(y, n, 0.0);
                mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
                o.weight = w;
                o.method = MCSTAT_METHOD_EXACT;
                o.critical = 0;
                mcstat_result r;
                int reps = n >= 2000 ? 2 : 5;
                spread t1 = time_test(x, n, y, n, &o, reps, &r);
                o.critical = 1;
                spread t2 = time_test(x, n, y, n, &o, n >= 2000 ? 1 : 3, &r);
                char b1[96], b2[96];
                printf("| %d | %s | %.3g | %s | %s | %.3g |\n", n, w ? "Canner" : "none", r.p_value,
                       fmt_spread(b1, sizeof b1, t1, 1e3, "%.3f"), fmt_spread(b2, sizeof b2, t2, 1e3, "%.2f"),
                       (n + 1.0) * (2.0 * n + 1.0));
                free(x);
                free(y);
            }
}

static void bench_rng(void)
{
    printf("\n## Simulation: time per replicate, n1 = n2 = 1000, 20000 replicates (median [fastest-slowest] of 3)\n\n");
    printf("| generator, kernel | threads | weight | us / replicate | ns / label |\n|---|---|---|---|---|\n");
    static const char *names[] = {"GSL taus2 (gsl_rng_get), scalar", "xoshiro256++, AVX2 kernel (8 lanes)",
                                  "xoshiro256++, scalar kernel"};
    for (int g = 0; g < 3; g++)
        for (int th = 1; th <= 2; th++)
            for (int w = 1; w >= 0; w--) {
                mcstat__ks_data d = {0};
                d.n1 = d.n2 = 1000;
                d.N = 2000;
                d.weight = w;
                d.alternative = MCSTAT_TWO_SIDED;
                d.nblocks = 2000;
                int64_t B = 20000;
                double *keys = malloc(B * sizeof *keys), t[3];
                for (int k = 0; k < 3; k++) {
                    double t0 = now();
                    mcstat__ks_simulate_rng(&d, B, 1, th, g, keys);
                    t[k] = now() - t0;
                }
                spread sp = summarise(t, 3);
                char b1[96];
                printf("| %s | %d | %s | %s | %.2f |\n", names[g], th, w ? "Canner" : "none",
                       fmt_spread(b1, sizeof b1, sp, 1e6 / B, "%.2f"), 1e9 * sp.med / B / 2000);
                free(keys);
            }
}

static void bench_error(void)
{
    printf("\n## Simulated p-value: error against the exact value vs run time (2 threads, Canner)\n\n");
    mkdir("bench/out", 0755);
    FILE *csv = fopen("bench/out/ks_error_time.csv", "w");
    if (csv)
        fprintf(csv, "n,p_exact,n_sim,seconds_per_test,rms_abs_error,rms_rel_error,mean_se\n");
    printf("| n1 = n2 | exact p | n_sim | mean time per test (ms) | RMS error | RMS relative error | mean reported s.e. |\n|---|---|---|---|---|---|---|\n");
    static const int ns[] = {50, 200, 1000};
    static const double targets[] = {0.05, 0.005};
    for (size_t a = 0; a < 3; a++)
        for (size_t b = 0; b < 2; b++) {
            int n = ns[a];
            double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
            mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
            o.method = MCSTAT_METHOD_EXACT;
            o.critical = 0;
            mcstat_result re;
            /* data whose exact p-value is near the target */
            for (int tries = 0; tries < 400; tries++) {
                sample(x, n, (targets[b] > 0.01 ? 2.0 : 2.8) / sqrt(n / 2.0));
                sample(y, n, 0.0);
                mcstat_ks_test_2(x, n, y, n, MCSTAT_TWO_SIDED, 0.05, &o, &re);
                if (re.p_value > 0.7 * targets[b] && re.p_value < 1.4 * targets[b])
                    break;
            }
            for (int64_t B = 99; B <= 99999; B = B * 10 + 9) {
                int reps = B >= 99999 ? 4 : B >= 9999 ? 12 : 40;
                double s2 = 0, r2 = 0, se = 0, t = 0;
                for (int k = 0; k < reps; k++) {
                    mcstat_ks_options os = MCSTAT_KS_OPTIONS_INIT;
                    os.method = MCSTAT_METHOD_SIMULATE;
                    os.threads = 2; /* the table's heading: not the default (1) */
                    os.n_sim = B;
                    os.seed = (uint64_t)k * 7919 + 1;
                    os.critical = 0;
                    mcstat_result rsim;
                    double t0 = now();
                    mcstat_ks_test_2(x, n, y, n, MCSTAT_TWO_SIDED, 0.05, &os, &rsim);
                    t += now() - t0;
                    double e = rsim.p_value - re.p_value;
                    s2 += e * e;
                    r2 += (e / re.p_value) * (e / re.p_value);
                    se += rsim.p_value_se;
                }
                printf("| %d | %.4g | %lld | %.2f | %.2g | %.2g | %.2g |\n", n, re.p_value, (long long)B, 1e3 * t / reps,
                       sqrt(s2 / reps), sqrt(r2 / reps), se / reps);
                if (csv)
                    fprintf(csv, "%d,%.6g,%lld,%.6g,%.4g,%.4g,%.4g\n", n, re.p_value, (long long)B, t / reps,
                            sqrt(s2 / reps), sqrt(r2 / reps), se / reps);
            }
            free(x);
            free(y);
        }
    if (csv)
        fclose(csv);
}

/* Exact upper tail at the exact critical values for alpha, against the
 * approximations there. */
/* Jaeschke's (1979) limit for Canner's statistic, measured here against the
 * exact p-values and not used by the library (bench/RESULTS_ks.md). */
static double ks_jaeschke_sf(double n, int two_sided, double d2)
{
    double ll = log(log(n));
    double a = sqrt(2.0 * ll), b = 2.0 * ll + 0.5 * log(ll) - 0.5 * log(M_PI);
    double x = a * d2 - b;
    return -expm1(-(two_sided ? 2.0 : 1.0) * exp(-x));
}

static void bench_asymp(void)
{
    printf("\n## Asymptotic approximations against exact p-values (two-sided, at the exact critical values)\n\n");
    printf("| n1 | n2 | weight | exact p | Kolmogorov sqrt(ne) D | Stephens-corrected | Jaeschke (n = N) | Jaeschke (n = ne) |\n|---|---|---|---|---|---|---|---|\n");
    static const int sz[][2] = {{20, 20}, {50, 50}, {100, 100}, {300, 300}, {1000, 1000}, {50, 500}, {2000, 2000}};
    static const double alphas[] = {0.1, 0.01, 0.001};
    for (size_t a = 0; a < sizeof sz / sizeof sz[0]; a++)
        for (int w = 0; w < 2; w++)
            for (size_t b = 0; b < 3; b++) {
                int n1 = sz[a][0], n2 = sz[a][1];
                double *x = malloc(n1 * sizeof *x), *y = malloc(n2 * sizeof *y);
                sample(x, n1, 0);
                sample(y, n2, 0);
                mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
                o.weight = w;
                o.method = MCSTAT_METHOD_EXACT;
                mcstat_result r;
                mcstat_ks_test_2(x, n1, y, n2, MCSTAT_TWO_SIDED, alphas[b], &o, &r);
                /* the exact law at the critical value: P(stat > c) = P(stat >= next) <= alpha;
                 * compare the approximations at c itself, P(stat >= c) */
                mcstat__ks_data d = {0};
                d.n1 = n1;
                d.n2 = n2;
                d.N = n1 + n2;
                d.weight = w;
                d.alternative = MCSTAT_TWO_SIDED;
                d.nblocks = d.N;
                double c = r.critical[1], pe;
                mcstat__ks_point t;
                if (w == 0) {
                    t.u = (uint64_t)llround(c * n1 * n2);
                    t.q = 1;
                } else { /* find the lattice point with this value: scan s */
                    t.u = 0;
                    t.q = 1;
                    double key = c * c * n1 * (double)n2 / d.N;
                    for (uint64_t s = 1; s < d.N && !t.u; s++)
                        for (uint64_t i = s > (uint64_t)n2 ? s - n2 : 0; i <= s && i <= (uint64_t)n1; i++) {
                            int64_t u = (int64_t)i * d.N - (int64_t)s * n1;
                            uint64_t au = (uint64_t)(u < 0 ? -u : u), q = s * (d.N - s);
                            if (fabs(mcstat__ks_key(1, au, q) - key) <= 1e-12 * key) {
                                t.u = au;
                                t.q = q;
                                break;
                            }
                        }
                }
                mcstat__ks_exact_sf(&d, t, &pe);
                double ne = (double)n1 * n2 / (n1 + n2);
                if (w == 0) {
                    double k0 = mcstat__ks_asymp_sf(n1, n2, 1, c), k1 = mcstat__kolmogorov_sf((sqrt(ne) + 0.12 + 0.11 / sqrt(ne)) * c);
                    printf("| %d | %d | none | %.4g | %.4g (%+.0f%%) | %.4g (%+.1f%%) | | |\n", n1, n2, pe, k0,
                           100 * (k0 / pe - 1), k1, 100 * (k1 / pe - 1));
                } else {
                    double j0 = ks_jaeschke_sf(d.N, 1, c), j1 = ks_jaeschke_sf(ne, 1, c);
                    printf("| %d | %d | Canner | %.4g | | | %.4g (%+.0f%%) | %.4g (%+.0f%%) |\n", n1, n2, pe, j0,
                           100 * (j0 / pe - 1), j1, 100 * (j1 / pe - 1));
                }
                free(x);
                free(y);
            }
}

static void bench_big(void)
{
    printf("\n## Unweighted, 1e6 + 1e6 values, asymptotic (median [fastest-slowest] of 5; includes the radix sort)\n\n");
    int n = 1000000;
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
    sample(x, n, 0.0);
    sample(y, n, 0.002);
    printf("| threads | ms |\n|---|---|\n");
    for (int th = 1; th <= 2; th++) {
        mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
        o.weight = MCSTAT_KS_WEIGHT_NONE;
        o.method = MCSTAT_METHOD_ASYMPTOTIC;
        o.threads = th;
        mcstat_result r;
        spread t = time_test(x, n, y, n, &o, 5, &r);
        char b1[96];
        printf("| %d | %s |\n", th, fmt_spread(b1, sizeof b1, t, 1e3, "%.1f"));
        fprintf(stderr, "D = %.10g p = %.6g\n", r.statistic, r.p_value);
    }
    free(x);
    free(y);
}

int main(int argc, char **argv)
{
    const char *what = argc > 1 ? argv[1] : "all";
    int all = !strcmp(what, "all");
    if (all || !strcmp(what, "exact"))
        bench_exact();
    if (all || !strcmp(what, "rng"))
        bench_rng();
    if (all || !strcmp(what, "error"))
        bench_error();
    if (all || !strcmp(what, "asymp"))
        bench_asymp();
    if (all || !strcmp(what, "big"))
        bench_big();
    return 0;
}
