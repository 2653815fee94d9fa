/*
 * test_ks.c - the two-sample K-S test: statistic against R (unweighted) and
 * the direct O(N^2) definition (weighted); exact p-values against exact
 * rational ones (ref_ks_exact.h, big-integer path counts by
 * tools/refgen/make_ks_exact.py, both weights), against R's exact ks.test
 * (ref_ks.h, made by tools/refgen/make_ks_ref.R) and against a
 * full enumeration of all arrangements (weighted and unweighted, with and
 * without ties); simulated p-values within 4.5 standard errors of exact;
 * critical values consistent with the p-values; bit-identical results for
 * any thread count and from both simulation kernels; the cache; R's
 * printed block; bad inputs.
 */
#include "harness.h"
#include "internal.h" /* the simulation kernels, compared directly */
#include "mcstat.h"
#include "ref_accuracy.h"
#include "ref_ks.h"
#include "ref_ks_exact.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state = 20261124;
#include "test_rng.h"

static mcstat_ks_options opts(int weight, int method)
{
    mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
    o.weight = weight;
    o.method = method;
    return o;
}

/* ---- the statistic by its definition (ERRATA 1, 2): F and G counted at
 * every pooled value, which is "after the last of a run of equal values" ---- */
/* mcstat's alternatives <-> R's (by the CDF): the direct definitions below
 * and the R references use R's; the library takes mcstat's. */
static int r_alt(int alternative)
{
    return alternative == MCSTAT_LESS ? MCSTAT_GREATER : alternative == MCSTAT_GREATER ? MCSTAT_LESS : alternative;
}

/* alt in R's (CDF) sense: GREATER = sup (F - G) */
static double direct_stat(const double *x, int nx, const double *y, int ny, int weight, int alt)
{
    int N = nx + ny;
    double best = 0.0;
    for (int k = 0; k < N; k++) {
        double t = k < nx ? x[k] : y[k - nx];
        int cx = 0, cy = 0;
        for (int i = 0; i < nx; i++)
            cx += x[i] <= t;
        for (int j = 0; j < ny; j++)
            cy += y[j] <= t;
        long double F = (long double)cx / nx, G = (long double)cy / ny;
        long double z = (nx * F + ny * G) / N;
        long double d = alt == MCSTAT_GREATER ? F - G : alt == MCSTAT_LESS ? G - F : fabsl(F - G);
        if (weight == MCSTAT_KS_WEIGHT_CANNER) {
            if (cx + cy == N) /* z = 1: left out */
                continue;
            d /= sqrtl(z * (1 - z));
        }
        if (d > best)
            best = (double)d;
    }
    return weight == MCSTAT_KS_WEIGHT_CANNER ? sqrt((double)nx * ny / N) * best : best;
}

/* ---- exact p-value by enumerating every arrangement of the labels over
 * the pooled sorted values (so ties stay where they are) ---- */
static double enumerate_p(const double *x, int nx, const double *y, int ny, int weight, int alt)
{
    int N = nx + ny;
    double v[32], a[32], b[32];
    memcpy(v, x, nx * sizeof *x);
    memcpy(v + nx, y, ny * sizeof *y);
    for (int i = 1; i < N; i++) /* sort */
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            double t = v[j];
            v[j] = v[j - 1];
            v[j - 1] = t;
        }
    double obs = direct_stat(x, nx, y, ny, weight, alt);
    long count = 0, total = 0;
    for (uint32_t m = 0; m < (1u << N); m++) {
        if (__builtin_popcount(m) != nx)
            continue;
        int ia = 0, ib = 0;
        for (int k = 0; k < N; k++) {
            if (m >> k & 1)
                a[ia++] = v[k];
            else
                b[ib++] = v[k];
        }
        total++;
        count += direct_stat(a, nx, b, ny, weight, alt) >= obs * (1 - 1e-9);
    }
    return (double)count / total;
}

static void test_reference_r(void)
{
    double worst_p = 0, worst_s = 0;
    int r_less_ties = 0, r_less_ties_wrong = 0, n_blocks = 0;
    mcstat_ks_options o = opts(MCSTAT_KS_WEIGHT_NONE, MCSTAT_METHOD_EXACT);
    for (size_t i = 0; i < REF_NKS; i++) {
        const ref_ks *c = &REF_KS[i];
        mcstat_result r;
        /* c->alternative is R's; the library takes mcstat's */
        int st = mcstat_ks_test_2(c->x, c->nx, c->y, c->ny, r_alt(c->alternative), 0.05, &o, &r);
        CHECK_INT(st, MCSTAT_OK);
        /* R's statistic is a cumulative sum of 1/nx - 1/ny: a few ulps of noise */
        double es = fabs(r.statistic - c->statistic) / fmax(fabs(c->statistic), 1.0);
        CHECK_MSG(es < 1e-13, "case %zu: D = %.17g, R %.17g", i, r.statistic, c->statistic);
        CHECK_REL(r.statistic, direct_stat(c->x, c->nx, c->y, c->ny, 0, c->alternative), 1e-13, "case %zu", i);
        /* against the exact fractions: relative accuracy */
        CHECK_REL(r.p_value, REF_KS_EXACT[i][0], acc_bound("ks_test_2", "ref_ks.h cases, exact method, unweighted"),
                  "case %zu (%d+%d, alt %d)", i, c->nx, c->ny, c->alternative);
        worst_p = fmax(worst_p, rel_err(r.p_value, REF_KS_EXACT[i][0]));
        mcstat_ks_options oc = opts(MCSTAT_KS_WEIGHT_CANNER, MCSTAT_METHOD_EXACT);
        mcstat_result rc;
        CHECK_INT(mcstat_ks_test_2(c->x, c->nx, c->y, c->ny, r_alt(c->alternative), 0.05, &oc, &rc), MCSTAT_OK);
        CHECK_REL(rc.p_value, REF_KS_EXACT[i][1],
                  acc_bound("ks_test_2", "ref_ks.h cases, exact method, Canner's weight"),
                  "Canner, case %zu (%d+%d, alt %d)", i, c->nx, c->ny, c->alternative);
        worst_p = fmax(worst_p, rel_err(rc.p_value, REF_KS_EXACT[i][1]));
        /* against R: its upper tail is 1 - P, accurate to ~1e-13 absolutely;
         * for "less" with ties R 4.2.2 uses the law of max(F - G) instead of
         * max(G - F), which the exact values show to be wrong */
        int ties = 0;
        for (int a = 0; a < c->nx && !ties; a++) {
            for (int b = a + 1; b < c->nx; b++)
                ties |= c->x[a] == c->x[b];
            for (int b = 0; b < c->ny; b++)
                ties |= c->x[a] == c->y[b];
        }
        for (int a = 0; a < c->ny && !ties; a++)
            for (int b = a + 1; b < c->ny; b++)
                ties |= c->y[a] == c->y[b];
        if (c->alternative == MCSTAT_LESS && ties) { /* R's "less" */
            r_less_ties++;
            r_less_ties_wrong += fabs(c->p - REF_KS_EXACT[i][0]) > 1e-9;
            continue;
        }
        CHECK_MSG(fabs(r.p_value - c->p) <= 1e-9 * c->p + 1e-12, "case %zu (%d+%d, alt %d): p = %.17g, R %.17g", i,
                  c->nx, c->ny, c->alternative, r.p_value, c->p);
        worst_s = fmax(worst_s, es);
        /* R's printed block, without our decision line */
        if (fabs(c->statistic) < 1e-12 && r.statistic == 0.0)
            continue; /* R prints its rounding noise, e.g. D^- = -3.4694e-17 */
        if (rel_err(c->p, REF_KS_EXACT[i][0]) > 1e-6)
            continue; /* R's 1 - P below ~1e-11 prints other digits than the exact value */
        n_blocks++;
        char text[2048];
        size_t len;
        CHECK_INT(mcstat_result_format(&r, NULL, NULL, text, sizeof text, &len), MCSTAT_OK);
        CHECK_INT(len, strlen(text));
        char *dl = strstr(text, "decision at alpha = 0.05: ");
        CHECK(dl != NULL);
        if (!dl)
            continue;
        memmove(dl, strchr(dl, '\n') + 1, strlen(strchr(dl, '\n') + 1) + 1);
        char want[2048];
        snprintf(want, sizeof want, "%s", c->text);
        /* R names the data by their expressions; ours by the names given */
        char *d0 = strstr(want, "data:  "), *d1 = d0 ? strchr(d0, '\n') : NULL;
        if (d0 && d1) {
            char rest[2048];
            snprintf(rest, sizeof rest, "%s", d1);
            snprintf(d0, sizeof want - (size_t)(d0 - want), "data:  x and y%s", rest);
        }
        CHECK_MSG(!strcmp(text, want), "case %zu:\n--- mcstat\n%s--- R\n%s---", i, text, want);
    }
    printf("R's cases: %zu, worst statistic error %.2g, worst p-value relative error against exact fractions %.2g;"
           " R's 'less' with ties differs from the exact value in %d of %d cases; %d printed blocks equal R's\n",
           (size_t)REF_NKS, worst_s, worst_p, r_less_ties_wrong, r_less_ties, n_blocks);
}

static void random_sample(double *x, int n, int ties, double shift)
{
    for (int i = 0; i < n; i++) {
        if (ties == 1)
            x[i] = round(normal() + shift);
        else if (ties == 2)
            x[i] = unif() < 0.7 ? 0.0 : round(4 * (unif() + shift)) / 4;
        else
            x[i] = normal() + shift;
    }
}

static void test_enumeration(void)
{
    static const int sizes[][2] = {{1, 5}, {3, 4}, {5, 5}, {4, 9}, {2, 11}, {7, 7}, {6, 8}, {9, 5}, {10, 6}};
    double worst = 0;
    int n = 0;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        for (int ties = 0; ties < 3; ties++)
            for (int alt = 0; alt < 3; alt++)
                for (int w = 0; w < 2; w++) {
                    int nx = sizes[k][0], ny = sizes[k][1];
                    double x[16], y[16];
                    random_sample(x, nx, ties, 0.4);
                    random_sample(y, ny, ties, 0.0);
                    mcstat_ks_options o = opts(w, MCSTAT_METHOD_EXACT);
                    mcstat_result r;
                    CHECK_INT(mcstat_ks_test_2(x, nx, y, ny, alt, 0.05, &o, &r), MCSTAT_OK);
                    CHECK_REL(r.statistic, direct_stat(x, nx, y, ny, w, r_alt(alt)), 1e-13, "%d+%d ties %d alt %d w %d",
                              nx, ny, ties, alt, w);
                    double pe = enumerate_p(x, nx, y, ny, w, r_alt(alt));
                    CHECK_REL(r.p_value, pe, 1e-12, "%d+%d ties %d alt %d w %d", nx, ny, ties, alt, w);
                    worst = fmax(worst, rel_err(r.p_value, pe));
                    n++;
                    /* the critical value agrees with the p-value */
                    CHECK_INT(r.reject, r.statistic > r.critical[1]);
                }
    printf("enumeration: %d cases, worst relative error %.2g\n", n, worst);
}

/* Statistic by the direct definition at larger sizes, with ties (weighted). */
static void test_statistic_direct(void)
{
    for (int k = 0; k < 40; k++) {
        int nx = 1 + (int)(unif() * 150), ny = 1 + (int)(unif() * 150), ties = k % 3, alt = k % 3, w = k & 1;
        double *x = malloc(nx * sizeof *x), *y = malloc(ny * sizeof *y);
        random_sample(x, nx, ties, 0.3 * unif());
        random_sample(y, ny, ties, 0.0);
        mcstat_ks_options o = opts(w, MCSTAT_METHOD_EXACT);
        mcstat_result r;
        CHECK_INT(mcstat_ks_test_2(x, nx, y, ny, alt, 0.05, &o, &r), MCSTAT_OK);
        CHECK_REL(r.statistic, direct_stat(x, nx, y, ny, w, r_alt(alt)), 1e-13, "%d+%d ties %d alt %d w %d", nx, ny,
                  ties, alt, w);
        free(x);
        free(y);
    }
}

/* Simulated p-values against exact ones, within 4.5 standard errors. */
static void test_simulated(void)
{
    static const int sizes[][2] = {{8, 11}, {30, 25}, {100, 80}, {300, 310}};
    int n = 0;
    double worst = 0;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        for (int ties = 0; ties < 3; ties += 2)
            for (int alt = 0; alt < 3; alt++)
                for (int w = 0; w < 2; w++) {
                    int nx = sizes[k][0], ny = sizes[k][1];
                    double *x = malloc(nx * sizeof *x), *y = malloc(ny * sizeof *y);
                    /* a shift that gives mid-range p-values */
                    random_sample(x, nx, ties, 1.2 / sqrt(nx * ny / (double)(nx + ny)));
                    random_sample(y, ny, ties, 0.0);
                    mcstat_ks_options o = opts(w, MCSTAT_METHOD_EXACT);
                    mcstat_result re, rs;
                    CHECK_INT(mcstat_ks_test_2(x, nx, y, ny, alt, 0.05, &o, &re), MCSTAT_OK);
                    o.method = MCSTAT_METHOD_SIMULATE;
                    o.n_sim = 20000;
                    o.seed = 1000 + n;
                    CHECK_INT(mcstat_ks_test_2(x, nx, y, ny, alt, 0.05, &o, &rs), MCSTAT_OK);
                    CHECK_INT(rs.method, MCSTAT_METHOD_SIMULATE);
                    CHECK(rs.statistic == re.statistic);
                    double se = sqrt(re.p_value * (1 - re.p_value) / o.n_sim) + 1.0 / o.n_sim;
                    double z = (rs.p_value - re.p_value) / se;
                    CHECK_MSG(fabs(z) < 4.5, "%d+%d ties %d alt %d w %d: simulated %.5g, exact %.5g (z = %.2f)", nx,
                              ny, ties, alt, w, rs.p_value, re.p_value, z);
                    CHECK(rs.p_value > 0 && rs.p_value_se >= 0 && (rs.p_value_se > 0 || rs.p_value == 1));
                    CHECK_REL(rs.p_value_se, sqrt(rs.p_value * (1 - rs.p_value) / o.n_sim), 1e-12, "se");
                    CHECK_INT(rs.reject, rs.statistic > rs.critical[1]);
                    CHECK(MCSTAT_RESULT_CRITICAL_SE(&rs) >= 0 && MCSTAT_RESULT_N_SIM(&rs) == o.n_sim);
                    /* the simulated critical value is near the exact one */
                    CHECK_MSG(fabs(rs.critical[1] - re.critical[1]) <=
                                  4.5 * MCSTAT_RESULT_CRITICAL_SE(&rs) + 0.02 * re.critical[1],
                              "critical %.5g vs exact %.5g (se %.3g)", rs.critical[1], re.critical[1],
                              MCSTAT_RESULT_CRITICAL_SE(&rs));
                    worst = fmax(worst, fabs(z));
                    n++;
                    free(x);
                    free(y);
                }
    printf("simulation vs exact: %d cases, worst |z| %.2f\n", n, worst);
}

static void test_threads_and_cache(void)
{
    enum { NX = 400, NY = 350 };
    double x[NX], y[NY];
    random_sample(x, NX, 0, 0.1);
    random_sample(y, NY, 0, 0.0);
    mcstat_result r1, r2, r3;
    for (int w = 0; w < 2; w++) {
        mcstat_ks_options o = opts(w, MCSTAT_METHOD_SIMULATE);
        o.n_sim = 3001;
        o.seed = 42;
        o.threads = 1;
        CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &o, &r1), MCSTAT_OK);
        o.threads = 2;
        CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &o, &r2), MCSTAT_OK);
        o.threads = 7;
        CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &o, &r3), MCSTAT_OK);
        CHECK(!memcmp(&r1, &r2, sizeof r1) && !memcmp(&r1, &r3, sizeof r1));
        o.seed = 43;
        CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &o, &r2), MCSTAT_OK);
        CHECK(r2.p_value != r1.p_value || r2.critical[1] != r1.critical[1]);
    }
    /* a battery at the same sizes simulates once; results equal uncached ones */
    mcstat_ks_cache *cache = NULL;
    CHECK_INT(mcstat_ks_cache_new(1 << 26, &cache), MCSTAT_OK);
    mcstat_ks_options o = opts(MCSTAT_KS_WEIGHT_CANNER, MCSTAT_METHOD_SIMULATE), oc;
    o.n_sim = 2000;
    oc = o;
    oc.cache = cache;
    for (int k = 0; k < 6; k++) {
        random_sample(x, NX, 0, 0.05 * k);
        random_sample(y, NY, 0, 0.0);
        CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &o, &r1), MCSTAT_OK);
        CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &oc, &r2), MCSTAT_OK);
        CHECK(!memcmp(&r1, &r2, sizeof r1));
    }
    /* ties make another distribution: a miss */
    random_sample(x, NX, 2, 0.0);
    random_sample(y, NY, 2, 0.0);
    CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &oc, &r2), MCSTAT_OK);
    uint64_t hits, misses, entries;
    CHECK_INT(mcstat_ks_cache_stats(cache, &hits, &misses, &entries), MCSTAT_OK);
    CHECK_INT(hits, 5);
    CHECK_INT(misses, 2);
    CHECK_INT(entries, 2);
    mcstat_ks_cache_free(cache);
    /* a cache too small for one entry still gives right answers */
    CHECK_INT(mcstat_ks_cache_new(100, &cache), MCSTAT_OK);
    oc.cache = cache;
    CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &oc, &r1), MCSTAT_OK);
    CHECK_INT(mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &oc, &r2), MCSTAT_OK);
    CHECK(!memcmp(&r1, &r2, sizeof r1));
    CHECK_INT(mcstat_ks_cache_stats(cache, NULL, NULL, &entries), MCSTAT_OK);
    CHECK_INT(entries, 0);
    mcstat_ks_cache_free(cache);
    mcstat_ks_cache_free(NULL);
}

/* The AVX2 kernel (8 replicates per group, where the machine has it) and the
 * scalar kernel give bit-identical keys: every replicate is a pure function
 * of (data, seed, index).  n_sim not a multiple of 8 or of the block size,
 * ties, both weights, all alternatives, sizes near the kernel's limits. */
static void test_simulation_kernels(void)
{
    static const int sizes[][2] = {{1, 1}, {1, 7}, {8, 11}, {30, 25}, {257, 3}, {400, 350}, {40000, 50000}};
    int cases = 0;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        for (int ties = 0; ties < 2; ties++)
            for (int alt = 0; alt < 3; alt++)
                for (int w = 0; w < 2; w++) {
                    int nx = sizes[k][0], ny = sizes[k][1];
                    if (nx > 1000 && (ties || alt)) /* n1 n2 = 2e9, just inside the AVX2 kernel's int32 range: few */
                        continue;
                    mcstat__ks_data d = {0};
                    d.n1 = (uint64_t)nx;
                    d.n2 = (uint64_t)ny;
                    d.N = d.n1 + d.n2;
                    d.weight = w;
                    d.alternative = alt;
                    d.nblocks = d.N;
                    uint64_t ends[1000];
                    if (ties && d.N > 3 && d.N <= 1000) { /* blocks of 1, 2 or 3 */
                        size_t nb = 0;
                        for (uint64_t e = 0; e < d.N;) {
                            e += 1 + (e * 7 % 3);
                            ends[nb++] = e < d.N ? e : d.N;
                        }
                        d.ends = ends;
                        d.nblocks = nb;
                    }
                    int64_t B = nx > 1000 ? 37 : 1003;
                    double *a = malloc(2 * B * sizeof *a), *b = a + B;
                    CHECK_INT(mcstat__ks_simulate_rng(&d, B, 99 + k, 2, MCSTAT__KS_RNG_XOSHIRO, a), MCSTAT_OK);
                    CHECK_INT(mcstat__ks_simulate_rng(&d, B, 99 + k, 1, MCSTAT__KS_RNG_XOSHIRO_SCALAR, b), MCSTAT_OK);
                    CHECK_MSG(!memcmp(a, b, B * sizeof *a), "%d+%d ties %d alt %d weight %d: kernels differ", nx, ny,
                              ties, alt, w);
                    /* GSL's taus2 lives in the benchmark's build only */
                    CHECK_INT(mcstat__ks_simulate_rng(&d, B, 99 + k, 1, MCSTAT__KS_RNG_TAUS2, b), MCSTAT_EINVAL);
                    int distinct = 0;
                    for (int64_t i = 1; i < B; i++)
                        distinct += a[i] != a[i - 1];
                    CHECK(d.N < 4 || distinct > 0);
                    free(a);
                    cases++;
                }
    printf("simulation kernels bit-identical in %d cases\n", cases);
}

static void test_methods_and_edges(void)
{
    double x[3000], y[3000];
    random_sample(x, 3000, 0, 0.0);
    random_sample(y, 3000, 0, 0.0);
    mcstat_result r;
    mcstat_ks_options o = opts(MCSTAT_KS_WEIGHT_CANNER, MCSTAT_METHOD_AUTO);
    CHECK_INT(mcstat_ks_test_2(x, 50, y, 60, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_INT(r.method, MCSTAT_METHOD_EXACT);
    CHECK_INT(r.test, MCSTAT_TEST_KS_2);
    CHECK_INT(MCSTAT_RESULT_KS_WEIGHT(&r), MCSTAT_KS_WEIGHT_CANNER);
    CHECK(r.p_value_se == 0 && isnan(r.df[0]) && isnan(r.estimate[0]) && r.critical[0] == -INFINITY);
    o.n_sim = 500;
    CHECK_INT(mcstat_ks_test_2(x, 3000, y, 3000, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_INT(r.method, MCSTAT_METHOD_SIMULATE);
    o.weight = MCSTAT_KS_WEIGHT_NONE;
    CHECK_INT(mcstat_ks_test_2(x, 3000, y, 3000, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_INT(r.method, MCSTAT_METHOD_ASYMPTOTIC);
    for (int i = 0; i < 3000; i++)
        x[i] = round(x[i]);
    CHECK_INT(mcstat_ks_test_2(x, 3000, y, 3000, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_INT(r.method, MCSTAT_METHOD_SIMULATE); /* ties: the limit would be conservative */

    /* identical constant samples: no jump point with 0 < z < 1, D = 0, p = 1 */
    double c[4] = {2, 2, 2, 2};
    for (int w = 0; w < 2; w++)
        for (int m = MCSTAT_METHOD_EXACT; m <= MCSTAT_METHOD_SIMULATE; m++) {
            o = opts(w, m);
            CHECK_INT(mcstat_ks_test_2(c, 4, c, 3, 0, 0.05, &o, &r), MCSTAT_OK);
            CHECK(r.statistic == 0 && r.p_value == 1 && r.reject == 0 && r.decision == 0);
        }
    /* one observation per sample is enough */
    double a1 = 1, b1 = 2;
    o = opts(MCSTAT_KS_WEIGHT_NONE, MCSTAT_METHOD_EXACT);
    CHECK_INT(mcstat_ks_test_2(&a1, 1, &b1, 1, MCSTAT_TWO_SIDED, 0.05, &o, &r), MCSTAT_OK);
    CHECK(r.statistic == 1 && r.p_value == 1);
    CHECK_INT(mcstat_ks_test_2(&a1, 1, &b1, 1, MCSTAT_LESS, 0.05, &o, &r), MCSTAT_OK); /* x = 1 < y = 2 */
    CHECK(r.statistic == 1 && fabs(r.p_value - 0.5) < 1e-15);
    CHECK_INT(mcstat_ks_test_2(&a1, 1, &b1, 1, MCSTAT_GREATER, 0.05, &o, &r), MCSTAT_OK);
    CHECK(r.statistic == 0 && r.p_value == 1);
    /* +-Inf are ordered values; -0 ties with +0 */
    double xi[] = {-INFINITY, -0.0, 1, INFINITY}, yi[] = {0.0, 2, 3, INFINITY};
    CHECK_INT(mcstat_ks_test_2(xi, 4, yi, 4, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_REL(r.statistic, direct_stat(xi, 4, yi, 4, 0, 0), 0, "inf");
    CHECK_REL(r.p_value, enumerate_p(xi, 4, yi, 4, 0, 0), 1e-13, "inf");
    /* disjoint samples of 1000: p = 2/C(2000,1000) ~ 1e-600 is below doubles */
    for (int i = 0; i < 1000; i++) {
        x[i] = i;
        y[i] = 1000 + i;
    }
    CHECK_INT(mcstat_ks_test_2(x, 1000, y, 1000, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK(r.statistic == 1 && r.p_value >= 0 && r.p_value < 1e-290 && r.reject && r.decision == -1); /* x less */
    /* 30 vs 30 disjoint: p = 2/C(60,30), relative accuracy at 1e-17 */
    CHECK_INT(mcstat_ks_test_2(x, 30, y, 30, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_REL(r.p_value, 2.0 / 118264581564861424.0, 1e-13, "disjoint 30+30");
    o.weight = MCSTAT_KS_WEIGHT_CANNER;
    CHECK_INT(mcstat_ks_test_2(x, 30, y, 30, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_REL(r.p_value, 2.0 / 118264581564861424.0, 1e-13, "disjoint 30+30 Canner");
    CHECK_INT(mcstat_ks_test_2(y, 30, x, 30, MCSTAT_GREATER, 0.05, &o, &r), MCSTAT_OK); /* y is larger */
    CHECK_REL(r.p_value, 1.0 / 118264581564861424.0, 1e-13, "disjoint 30+30 Canner greater");
    CHECK_INT(r.decision, 1);
}

static void test_bad_inputs(void)
{
    double x[4] = {1, 2, 3, 4}, y[4] = {2, 3, 4, 5};
    mcstat_result r, before;
    memset(&r, 0x5a, sizeof r);
    before = r;
    mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT, b;
    CHECK_INT(mcstat_ks_test_2(NULL, 4, y, 4, 0, 0.05, &o, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_test_2(x, 4, NULL, 4, 0, 0.05, &o, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &o, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_test_2(x, 0, y, 4, 0, 0.05, &o, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 0, 0, 0.05, &o, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 3, 0.05, &o, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, -1, 0.05, &o, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.0, &o, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 1.0, &o, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, NAN, &o, &r), MCSTAT_EINVAL);
    b = o, b.n_sim = 0;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.n_sim = -5;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.weight = 2;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.method = MCSTAT_METHOD_ANALYTIC;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.method = 99;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.method = MCSTAT_METHOD_ASYMPTOTIC; /* Canner's has no usable limit */
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.threads = 0;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.threads = 65;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.size = 8;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    b = o, b.critical = 2;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, &b, &r), MCSTAT_EINVAL);
    double xn[4] = {1, NAN, 3, 4};
    CHECK_INT(mcstat_ks_test_2(xn, 4, y, 4, 0, 0.05, &o, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_ks_test_2(y, 4, xn, 4, 0, 0.05, &o, &r), MCSTAT_ENONFINITE);
    /* sizes whose product overflows, or whose exact lattice is too large:
     * refused before the data are read (the arrays here are short) */
    CHECK_INT(mcstat_ks_test_2(x, (size_t)1 << 31, y, (size_t)1 << 31, 0, 0.05, &o, &r), MCSTAT_ETOOBIG);
    CHECK_INT(mcstat_ks_test_2(x, SIZE_MAX, y, SIZE_MAX, 0, 0.05, &o, &r), MCSTAT_ETOOBIG);
    b = o, b.method = MCSTAT_METHOD_EXACT;
    CHECK_INT(mcstat_ks_test_2(x, 400000, y, 400000, 0, 0.05, &b, &r), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&r, &before, sizeof r)); /* nothing written on failure */
    CHECK(strlen(mcstat_strerror(MCSTAT_ETOOBIG)) > 10);
    /* NULL options are the defaults */
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, NULL, &r), MCSTAT_OK);
    CHECK_INT(MCSTAT_RESULT_KS_WEIGHT(&r), MCSTAT_KS_WEIGHT_CANNER);
    mcstat_ks_options f;
    memset(&f, 0, sizeof f);
    CHECK_INT(mcstat_ks_options_init(&f), MCSTAT_OK);
    CHECK(!memcmp(&f, &o, sizeof f));
    CHECK_INT(mcstat_ks_options_init_size(NULL, sizeof f), MCSTAT_EINVAL);
    CHECK_INT((mcstat_ks_options_init)(NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_sizeof_ks_options(), sizeof(mcstat_ks_options));
    CHECK_INT(mcstat_ks_cache_new(10, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_ks_cache_stats(NULL, NULL, NULL, NULL), MCSTAT_EINVAL);
    /* formatting a K-S result with a bad alternative */
    mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, NULL, &r);
    r.alternative = 7;
    char buf[256];
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_EINVAL);
}

static void test_format_simulated(void)
{
    double x[20], y[25];
    random_sample(x, 20, 0, 0.5);
    random_sample(y, 25, 0, 0.0);
    mcstat_ks_options o = opts(MCSTAT_KS_WEIGHT_CANNER, MCSTAT_METHOD_SIMULATE);
    o.n_sim = 999;
    mcstat_result r;
    CHECK_INT(mcstat_ks_test_2(x, 20, y, 25, MCSTAT_LESS, 0.01, &o, &r), MCSTAT_OK);
    char buf[1024];
    CHECK_INT(mcstat_result_format(&r, "new", "trusted", buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "\tMonte-Carlo two-sample Kolmogorov-Smirnov test with Canner's weight\n") != NULL);
    CHECK(strstr(buf, "data:  new and trusted\nD2^+ = ") != NULL); /* mcstat's less is R's greater */
    CHECK(strstr(buf, "Monte Carlo standard error of the p-value: ") != NULL);
    CHECK(strstr(buf, " (999 replicates)\nalternative hypothesis: the CDF of x lies above that of y\n") != NULL);
    CHECK(strstr(buf, "decision at alpha = 0.01: ") != NULL);
}

/* u^2 q in 32-bit limbs (least significant first): an independent oracle for
 * the cross products of mcstat__ks_point_cmp. */
static void limbs_u2q(uint64_t u, uint64_t q, uint32_t out[6])
{
    uint32_t a[2] = {(uint32_t)u, (uint32_t)(u >> 32)}, b[2] = {(uint32_t)q, (uint32_t)(q >> 32)};
    uint32_t s[4] = {0}, r[6] = {0};
    for (int i = 0; i < 2; i++) {
        uint64_t c = 0;
        for (int j = 0; j < 2; j++) {
            uint64_t t = (uint64_t)a[i] * a[j] + s[i + j] + c;
            s[i + j] = (uint32_t)t;
            c = t >> 32;
        }
        s[i + 2] = (uint32_t)c;
    }
    for (int i = 0; i < 4; i++) {
        uint64_t c = 0;
        for (int j = 0; j < 2; j++) {
            uint64_t t = (uint64_t)s[i] * b[j] + r[i + j] + c;
            r[i + j] = (uint32_t)t;
            c = t >> 32;
        }
        r[i + 2] = (uint32_t)c;
    }
    memcpy(out, r, sizeof r);
}

static int ref_point_cmp(mcstat__ks_point a, mcstat__ks_point b)
{
    uint32_t l[6], r[6];
    limbs_u2q(a.u, b.q, l);
    limbs_u2q(b.u, a.q, r);
    for (int i = 5; i >= 0; i--)
        if (l[i] != r[i])
            return l[i] > r[i] ? 1 : -1;
    return 0;
}

/* Canner keys u^2/q compared exactly where the cross products pass 2^128
 * (samples of millions): long double rounded them to 64 (or 53) bits and
 * called unequal keys equal. */
static void test_point_cmp_wide(void)
{
    const uint64_t U = (1ull << 62) + 1, Q = UINT64_MAX;
    struct { mcstat__ks_point a, b; int want; } c[] = {
        {{U, Q}, {U, Q - 1}, -1},                      /* same u, q one apart */
        {{U, Q - 1}, {U, Q}, 1},
        {{(1ull << 61) + 1, (1ull << 62) - 1}, {(1ull << 62) + 2, UINT64_MAX - 3}, 0}, /* u, q and 2u, 4q */
        {{U + 1, Q}, {U, Q}, 1},
        {{3037000499ull * 1000, 1ull << 63}, {3037000499ull * 1000 + 1, (1ull << 63) + 1}, -1},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        CHECK_MSG(mcstat__ks_point_cmp(MCSTAT_KS_WEIGHT_CANNER, c[i].a, c[i].b) == c[i].want, "case %zu", i);
        CHECK_INT(ref_point_cmp(c[i].a, c[i].b), c[i].want);
    }
    /* random wide points, and pairs one unit apart, against the limb oracle */
    for (int k = 0; k < 2000; k++) {
        mcstat__ks_point a, b;
        a.u = (uint64_t)(unif() * 0x1p62) + 1;
        a.q = (uint64_t)(unif() * 0x1p63) + 1;
        b.u = k & 1 ? a.u + (k & 2 ? 1 : 0) : (uint64_t)(unif() * 0x1p62) + 1;
        b.q = k & 1 ? a.q + (k & 4 ? 1 : 0) : (uint64_t)(unif() * 0x1p63) + 1;
        CHECK_MSG(mcstat__ks_point_cmp(MCSTAT_KS_WEIGHT_CANNER, a, b) == ref_point_cmp(a, b),
                  "u %llu q %llu vs u %llu q %llu", (unsigned long long)a.u, (unsigned long long)a.q,
                  (unsigned long long)b.u, (unsigned long long)b.q);
    }
}

int main(void)
{
    test_reference_r();
    test_enumeration();
    test_statistic_direct();
    test_simulated();
    test_threads_and_cache();
    test_simulation_kernels();
    test_methods_and_edges();
    test_bad_inputs();
    test_format_simulated();
    test_point_cmp_wide();
    return h_report("test_ks");
}
