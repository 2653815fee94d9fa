/*
 * test_moments.c - the accumulator's properties: merges in any order equal
 * one pass, one value at a time equals an array, exact power-of-two scaling
 * from 1e-300 to 1e300, drift, NaN omission, non-finite data leave the
 * accumulator untouched, and the byte form round-trips and rejects damage.
 * (Accuracy against exact rational moments is in test_reference.)
 */
#include "harness.h"
#include "mcstat.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;

static double urand(void) /* splitmix64 -> [0, 1) */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1p-53;
}

static double nrand(void)
{
    double u = urand(), v = urand();
    return sqrt(-2.0 * log(1.0 - u)) * cos(6.283185307179586 * v);
}

/* Reference central moments by two passes in long double. */
static void ref_moments(const double *x, size_t n, long double *mean, long double *m2, long double *m3,
                        long double *m4)
{
    long double s = 0;
    for (size_t i = 0; i < n; i++)
        s += x[i];
    long double mu = s / n, a2 = 0, a3 = 0, a4 = 0, c = 0;
    for (size_t i = 0; i < n; i++) {
        long double d = x[i] - mu;
        c += d;
        a2 += d * d;
        a3 += d * d * d;
        a4 += d * d * d * d;
    }
    *mean = mu + c / n;
    *m2 = a2 - c * c / n;
    *m3 = a3;
    *m4 = a4;
}

static void check_same(const mcstat_moments *a, const mcstat_moments *b, double tol, const char *what)
{
    /* The mean is compared relative to the spread (a mean near 0 has no
     * relative accuracy to speak of), kurtosis as n M4 / M2^2 (not the excess,
     * which is near 0 for normal data), skewness absolutely. */
    CHECK_INT(a->n, b->n);
    double sd = mcstat_moments_sd(b);
    double dmean = fabs((a->mean - b->mean) + (a->mean_lo - b->mean_lo));
    CHECK_MSG(dmean <= tol * (fabs(b->mean) + sd), "%s mean: %.3g apart", what, dmean);
    CHECK_REL(mcstat_moments_var(a), mcstat_moments_var(b), tol, "%s var", what);
    CHECK_MSG(fabs(mcstat_moments_skewness(a) - mcstat_moments_skewness(b)) <= 100 * tol, "%s skewness", what);
    CHECK_REL(mcstat_moments_kurtosis(a) + 3.0, mcstat_moments_kurtosis(b) + 3.0, 10 * tol, "%s kurtosis", what);
    CHECK(a->min == b->min && a->max == b->max);
}

static void test_against_long_double(void)
{
    const size_t sizes[] = {2, 3, 7, 8, 9, 100, 2047, 2048, 2049, 100003};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        size_t n = sizes[s];
        double *x = malloc(n * sizeof *x);
        for (size_t i = 0; i < n; i++)
            x[i] = 3.0 + exp(nrand()); /* skewed, heavy-ish tail */
        mcstat_moments m;
        mcstat_moments_init(&m);
        CHECK_INT(mcstat_moments_add_array(&m, x, n), MCSTAT_OK);
        long double mu, m2, m3, m4;
        ref_moments(x, n, &mu, &m2, &m3, &m4);
        CHECK_REL(m.mean + m.mean_lo, (double)mu, DBL_EPSILON, "mean n=%zu", n);
        CHECK_REL(mcstat_moments_var(&m), (double)(m2 / (n - 1)), 1e-14, "var n=%zu", n);
        if (n > 2) {
            CHECK_REL(mcstat_moments_skewness(&m), (double)(sqrtl(n) * m3 / (m2 * sqrtl(m2))), 1e-12, "skew n=%zu", n);
            CHECK_REL(mcstat_moments_kurtosis(&m), (double)(n * m4 / (m2 * m2) - 3), 1e-12, "kurt n=%zu", n);
        }
        double mn = x[0], mx = x[0];
        for (size_t i = 0; i < n; i++) {
            mn = fmin(mn, x[i]);
            mx = fmax(mx, x[i]);
        }
        CHECK(m.min == mn && m.max == mx);
        free(x);
    }
}

/* Merging in any order or tree equals one pass, to 1e-14. */
static void test_merge_orders(void)
{
    enum { N = 50000, PARTS = 37 };
    double *x = malloc(N * sizeof *x);
    for (int i = 0; i < N; i++)
        x[i] = 1e9 + 1e-3 * nrand();
    mcstat_moments whole;
    mcstat_moments_init(&whole);
    mcstat_moments_add_array(&whole, x, N);

    size_t cut[PARTS + 1];
    cut[0] = 0;
    cut[PARTS] = N;
    for (int k = 1; k < PARTS; k++)
        cut[k] = (size_t)(urand() * N);
    for (int k = 1; k < PARTS; k++) /* sort */
        for (int j = k; j > 1 && cut[j] < cut[j - 1]; j--) {
            size_t t = cut[j];
            cut[j] = cut[j - 1];
            cut[j - 1] = t;
        }
    mcstat_moments part[PARTS];
    for (int k = 0; k < PARTS; k++) {
        mcstat_moments_init(&part[k]);
        mcstat_moments_add_array(&part[k], x + cut[k], cut[k + 1] - cut[k]);
    }
    for (int trial = 0; trial < 20; trial++) {
        int order[PARTS];
        for (int k = 0; k < PARTS; k++)
            order[k] = k;
        for (int k = PARTS - 1; k > 0; k--) {
            int j = (int)(urand() * (k + 1));
            int t = order[k];
            order[k] = order[j];
            order[j] = t;
        }
        mcstat_moments acc;
        if (trial % 2 == 0) { /* left fold in a random order */
            mcstat_moments_init(&acc);
            for (int k = 0; k < PARTS; k++)
                CHECK_INT(mcstat_moments_merge(&acc, &part[order[k]]), MCSTAT_OK);
        } else { /* a random tree */
            mcstat_moments pool[PARTS];
            int np = PARTS;
            for (int k = 0; k < PARTS; k++)
                pool[k] = part[order[k]];
            while (np > 1) {
                int i = (int)(urand() * np), j = (int)(urand() * (np - 1));
                if (j >= i)
                    j++;
                mcstat_moments_merge(&pool[i], &pool[j]);
                pool[j] = pool[np - 1];
                np--;
            }
            acc = pool[0];
        }
        check_same(&acc, &whole, 1e-14, "merge order");
        /* the difference of means keeps its digits at the 1e9 offset */
        CHECK(fabs((acc.mean - whole.mean) + (acc.mean_lo - whole.mean_lo)) < 1e-20);
    }
    /* one value at a time */
    mcstat_moments one;
    mcstat_moments_init(&one);
    for (int i = 0; i < N; i++)
        CHECK(mcstat_moments_add(&one, x[i]) == MCSTAT_OK || 0);
    check_same(&one, &whole, 1e-14, "add one at a time");
    /* merging with itself doubles the count and keeps mean and spread */
    mcstat_moments twice = whole;
    mcstat_moments_merge(&twice, &twice);
    CHECK_INT(twice.n, 2 * whole.n);
    CHECK_REL(twice.mean, whole.mean, 1e-16, "self merge mean");
    CHECK_REL(twice.m2, 2 * whole.m2, 1e-14, "self merge m2");
    free(x);
}

/* Scaling data by 2^k is exact, so the moments must scale exactly too, from
 * 1e-300 to 1e300 and across the fast/scaled boundary at 2^+-200. */
static void test_power_of_two_scaling(void)
{
    enum { N = 3000 };
    double x[N], y[N];
    for (int i = 0; i < N; i++)
        x[i] = 1.5 + 0.25 * nrand();
    mcstat_moments m0;
    mcstat_moments_init(&m0);
    mcstat_moments_add_array(&m0, x, N);
    double sd0 = mcstat_moments_sd(&m0), sk0 = mcstat_moments_skewness(&m0), ku0 = mcstat_moments_kurtosis(&m0);
    for (int k = -1000; k <= 1000; k += 37) {
        for (int i = 0; i < N; i++)
            y[i] = ldexp(x[i], k);
        mcstat_moments m;
        mcstat_moments_init(&m);
        CHECK_INT(mcstat_moments_add_array(&m, y, N), MCSTAT_OK);
        CHECK_REL(mcstat_moments_mean(&m), ldexp(m0.mean, k), 4 * DBL_EPSILON, "mean at 2^%d", k);
        CHECK_REL(mcstat_moments_sd(&m), ldexp(sd0, k), 1e-14, "sd at 2^%d", k);
        CHECK_REL(mcstat_moments_skewness(&m), sk0, 1e-11, "skew at 2^%d", k);
        CHECK_REL(mcstat_moments_kurtosis(&m), ku0, 1e-13, "kurt at 2^%d", k);
        if (2 * k < 1000 && 2 * k > -1000)
            CHECK_REL(mcstat_moments_var(&m), ldexp(sd0 * sd0, 2 * k), 1e-14, "var at 2^%d", k);
        /* the t statistic is scale-free */
        mcstat_result r0, r;
        mcstat_t_test_1_moments(&m0, 1.4, MCSTAT_TWO_SIDED, 0.05, &r0);
        CHECK_INT(mcstat_t_test_1_moments(&m, ldexp(1.4, k), MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
        CHECK_REL(r.statistic, r0.statistic, 1e-13, "t at 2^%d", k);
        CHECK_REL(r.p_value, r0.p_value, 1e-12, "p at 2^%d", k);
    }
    /* samples at very different scales merge correctly */
    mcstat_moments big, tiny, both, direct;
    mcstat_moments_init(&big);
    mcstat_moments_init(&tiny);
    for (int i = 0; i < N; i++)
        y[i] = ldexp(x[i], 900);
    mcstat_moments_add_array(&big, y, N);
    for (int i = 0; i < N; i++)
        y[i] = ldexp(x[i], -900);
    mcstat_moments_add_array(&tiny, y, N);
    both = tiny;
    mcstat_moments_merge(&both, &big);
    CHECK_INT(both.n, 2 * N);
    CHECK_REL(mcstat_moments_mean(&both), ldexp(m0.mean, 899), 1e-15, "mixed-scale mean");
    /* var of the union = (var_big (N-1) + N/2 mean_big^2) / (2N-1) */
    double vb = ldexp(sd0 * sd0, 0), mb = m0.mean;
    double want_sd = ldexp(sqrt((vb * (N - 1) + 0.5 * N * mb * mb) / (2.0 * N - 1.0)), 900);
    CHECK_REL(mcstat_moments_sd(&both), want_sd, 1e-13, "mixed-scale sd");
    CHECK(isinf(mcstat_moments_var(&both))); /* 1e541 overflows; the sd does not */
    direct = big;
    mcstat_moments_merge(&direct, &tiny); /* either order */
    check_same(&direct, &both, 1e-15, "mixed-scale merge order");
}

/* Data that drift (each block far from the previous block's mean). */
static void test_drift(void)
{
    enum { N = 20000 };
    double *x = malloc(N * sizeof *x);
    for (int i = 0; i < N; i++)
        x[i] = 1e6 * i + nrand();
    mcstat_moments m;
    mcstat_moments_init(&m);
    mcstat_moments_add_array(&m, x, N);
    long double mu, m2, m3, m4;
    ref_moments(x, N, &mu, &m2, &m3, &m4);
    CHECK_REL(mcstat_moments_var(&m), (double)(m2 / (N - 1)), 1e-14, "drift var");
    CHECK_REL(mcstat_moments_kurtosis(&m), (double)(N * m4 / (m2 * m2) - 3), 1e-12, "drift kurtosis");
    free(x);
}

static void test_nonfinite_and_omit(void)
{
    double x[5000];
    for (int i = 0; i < 5000; i++)
        x[i] = nrand();
    mcstat_moments m, before;
    mcstat_moments_init(&m);
    mcstat_moments_add_array(&m, x, 100);
    before = m;
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int b = 0; b < 3; b++) {
        x[4321] = bad[b];
        CHECK_INT(mcstat_moments_add_array(&m, x, 5000), MCSTAT_ENONFINITE);
        CHECK(!memcmp(&m, &before, sizeof m));
        CHECK_INT(mcstat_moments_add(&m, bad[b]), MCSTAT_ENONFINITE);
        CHECK(!memcmp(&m, &before, sizeof m));
    }
    /* omit NaN: same as the filtered array; Inf is still an error */
    double *filtered = malloc(5000 * sizeof *filtered);
    size_t nf = 0, omitted = 0;
    for (int i = 0; i < 5000; i++) {
        if (i % 7 == 3)
            x[i] = NAN;
        else if (i == 4321)
            x[i] = 0.25;
        if (!isnan(x[i]))
            filtered[nf++] = x[i];
    }
    mcstat_moments a, b;
    mcstat_moments_init(&a);
    mcstat_moments_init(&b);
    CHECK_INT(mcstat_moments_add_array_omit_nan(&a, x, 5000, &omitted), MCSTAT_OK);
    CHECK_INT(omitted, 5000 - nf);
    mcstat_moments_add_array(&b, filtered, nf);
    check_same(&a, &b, 1e-14, "omit nan");
    x[10] = INFINITY;
    CHECK_INT(mcstat_moments_add_array_omit_nan(&a, x, 5000, &omitted), MCSTAT_ENONFINITE);
    /* all NaN: nothing added */
    double allnan[3] = {NAN, NAN, NAN};
    mcstat_moments e;
    mcstat_moments_init(&e);
    CHECK_INT(mcstat_moments_add_array_omit_nan(&e, allnan, 3, &omitted), MCSTAT_OK);
    CHECK_INT(e.n, 0);
    CHECK_INT(omitted, 3);
    free(filtered);
}

static void test_empty_and_zeroed(void)
{
    mcstat_moments z;
    memset(&z, 0, sizeof z); /* a zeroed struct is an empty accumulator */
    double v[3] = {1, 2, 4};
    CHECK_INT(mcstat_moments_add_array(&z, v, 3), MCSTAT_OK);
    CHECK_REL(mcstat_moments_mean(&z), 7.0 / 3.0, 1e-16, "zeroed struct");
    CHECK(z.min == 1 && z.max == 4);
    mcstat_moments e;
    mcstat_moments_init(&e);
    CHECK(isnan(mcstat_moments_mean(&e)) && isnan(mcstat_moments_var(&e)));
    CHECK(e.min == INFINITY && e.max == -INFINITY);
    mcstat_moments_add(&e, 5.0);
    CHECK(mcstat_moments_mean(&e) == 5.0 && isnan(mcstat_moments_var(&e)));
    CHECK_INT(mcstat_moments_add_array(&e, v, 0), MCSTAT_OK);
    CHECK_INT(e.n, 1);
    CHECK_INT(sizeof(mcstat_moments), 128);
    CHECK_INT(mcstat_sizeof_moments(), 128);
}

static void test_bytes(void)
{
    double x[777];
    for (int i = 0; i < 777; i++)
        x[i] = ldexp(nrand(), 700);
    mcstat_moments m, back;
    mcstat_moments_init(&m);
    mcstat_moments_add_array(&m, x, 777);
    unsigned char buf[MCSTAT_MOMENTS_BYTES];
    CHECK_INT(mcstat_sizeof_moments_bytes(), 96);
    CHECK_INT(mcstat_moments_to_bytes(&m, buf, sizeof buf), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_bytes(buf, sizeof buf, &back), MCSTAT_OK);
    CHECK(!memcmp(&m, &back, sizeof m));
    /* the byte form is little-endian by definition */
    CHECK(!memcmp(buf, "MCSM", 4) && buf[4] == 1 && buf[8] == (777 & 0xff) && buf[9] == (777 >> 8));
    /* every single-byte change is caught */
    for (size_t i = 0; i < sizeof buf; i++) {
        unsigned char bad[MCSTAT_MOMENTS_BYTES];
        memcpy(bad, buf, sizeof bad);
        bad[i] ^= (unsigned char)(1u << (i % 8));
        CHECK_MSG(mcstat_moments_from_bytes(bad, sizeof bad, &back) == MCSTAT_ECORRUPT, "byte %zu", i);
    }
    for (size_t len = 0; len < sizeof buf; len += 5)
        CHECK_INT(mcstat_moments_from_bytes(buf, len, &back), MCSTAT_ECORRUPT);
    CHECK_INT(mcstat_moments_to_bytes(&m, buf, 95), MCSTAT_EBUFSIZE);
    /* an inconsistent accumulator with a valid checksum is rejected too */
    mcstat_moments bad = m;
    bad.m2 = -1.0;
    CHECK_INT(mcstat_moments_to_bytes(&bad, buf, sizeof buf), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_bytes(buf, sizeof buf, &back), MCSTAT_ECORRUPT);
    /* the empty accumulator */
    mcstat_moments e;
    mcstat_moments_init(&e);
    CHECK_INT(mcstat_moments_to_bytes(&e, buf, sizeof buf), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_bytes(buf, sizeof buf, &back), MCSTAT_OK);
    CHECK(!memcmp(&e, &back, sizeof e));
}

/* The count never wraps: adds and merges that would pass 2^64 - 1 are
 * refused with m unchanged (they used to give n = 2 or 0 and MCSTAT_OK). */
static void test_count_overflow(void)
{
    double v[3] = {0, 1, 2};
    mcstat_moments big, small, before;
    mcstat_moments_init(&small);
    CHECK_INT(mcstat_moments_add_array(&small, v, 3), MCSTAT_OK);
    big = small;
    big.n = UINT64_MAX; /* as from_bytes may deliver it */
    before = big;
    CHECK_INT(mcstat_moments_merge(&big, &small), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&big, &before, sizeof big));
    CHECK_INT(mcstat_moments_add(&big, 1.0), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&big, &before, sizeof big));
    CHECK_INT(mcstat_moments_add_array(&big, v, 3), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&big, &before, sizeof big));
    size_t omitted = 99;
    CHECK_INT(mcstat_moments_add_array_omit_nan(&big, v, 3, &omitted), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&big, &before, sizeof big));
    CHECK_INT(omitted, 99);
    /* NaN only: nothing is added, so nothing overflows */
    double nan3[3] = {NAN, NAN, NAN};
    CHECK_INT(mcstat_moments_add_array_omit_nan(&big, nan3, 3, &omitted), MCSTAT_OK);
    CHECK_INT(omitted, 3);
    CHECK(!memcmp(&big, &before, sizeof big));
    /* an empty array and an empty accumulator change nothing either way */
    CHECK_INT(mcstat_moments_add_array(&big, v, 0), MCSTAT_OK);
    mcstat_moments e;
    mcstat_moments_init(&e);
    CHECK_INT(mcstat_moments_merge(&big, &e), MCSTAT_OK);
    CHECK(!memcmp(&big, &before, sizeof big));
    /* small merged into big from the other side: refused too */
    mcstat_moments s0 = small;
    CHECK_INT(mcstat_moments_merge(&small, &big), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&small, &s0, sizeof small));
    /* 2^63 merged with itself would be 0 */
    mcstat_moments half = s0;
    half.n = (uint64_t)1 << 63;
    before = half;
    CHECK_INT(mcstat_moments_merge(&half, &half), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&half, &before, sizeof half));
    /* the last representable count is still reached */
    mcstat_moments edge = s0;
    edge.n = UINT64_MAX - 4;
    CHECK_INT(mcstat_moments_add_array(&edge, v, 3), MCSTAT_OK);
    CHECK(edge.n == UINT64_MAX - 1);
    CHECK_INT(mcstat_moments_add(&edge, 1.0), MCSTAT_OK);
    CHECK(edge.n == UINT64_MAX);
    CHECK_INT(mcstat_moments_add(&edge, 1.0), MCSTAT_ETOOBIG);
    CHECK(edge.n == UINT64_MAX);
}

/* An accumulator from a summary (n, mean, M2) is a valid accumulator: the
 * t and variance tests give what they give on data with that summary, it
 * survives serialization, and bad summaries are refused. */
static void test_from_summary(void)
{
    const double x[6] = {1.5, 2.25, -0.75, 3.0, 0.5, 1.0};
    mcstat_moments d, s, back;
    mcstat_moments_init(&d);
    mcstat_moments_add_array(&d, x, 6);
    double m2 = mcstat_moments_var(&d) * 5.0;
    CHECK_INT(mcstat_moments_from_summary(6, mcstat_moments_mean(&d), m2, &s), MCSTAT_OK);
    CHECK(s.n == 6 && mcstat_moments_mean(&s) == mcstat_moments_mean(&d));
    CHECK(mcstat_moments_var(&s) == mcstat_moments_var(&d));
    mcstat_result a, b;
    CHECK_INT(mcstat_t_test_1_moments(&d, 0.5, MCSTAT_TWO_SIDED, 0.05, &a), MCSTAT_OK);
    CHECK_INT(mcstat_t_test_1_moments(&s, 0.5, MCSTAT_TWO_SIDED, 0.05, &b), MCSTAT_OK);
    CHECK_REL(b.p_value, a.p_value, 1e-15, "t p-value from a summary");
    CHECK_INT(mcstat_var_test_1_moments(&s, 0.5, MCSTAT_GREATER, 0.05, &b), MCSTAT_OK);
    CHECK_INT(mcstat_var_test_1_moments(&d, 0.5, MCSTAT_GREATER, 0.05, &a), MCSTAT_OK);
    CHECK_REL(b.p_value, a.p_value, 1e-15, "var p-value from a summary");
    /* the stand-in keeps the invariants from_bytes checks */
    unsigned char buf[MCSTAT_MOMENTS_BYTES];
    CHECK_INT(mcstat_moments_to_bytes(&s, buf, sizeof buf), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_bytes(buf, sizeof buf, &back), MCSTAT_OK);
    CHECK(mcstat_moments_merge(&back, &d) == MCSTAT_OK && back.n == 12);
    /* a constant sample */
    CHECK_INT(mcstat_moments_from_summary(4, 2.0, 0.0, &s), MCSTAT_OK);
    CHECK(s.min == 2.0 && s.max == 2.0 && s.m4 == 0.0);
    /* refused */
    CHECK_INT(mcstat_moments_from_summary(0, 1.0, 0.0, &s), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_moments_from_summary(5, 1.0, -1e-300, &s), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_from_summary(1, 1.0, 2.0, &s), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_moments_from_summary(0, NAN, 1.0, &s), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_moments_from_summary(5, NAN, 1.0, &s), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_moments_from_summary(5, 1.0, INFINITY, &s), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_moments_from_summary(5, 1.0, 1.0, NULL), MCSTAT_EINVAL);
}

int main(void)
{
    test_against_long_double();
    test_merge_orders();
    test_power_of_two_scaling();
    test_drift();
    test_nonfinite_and_omit();
    test_empty_and_zeroed();
    test_bytes();
    test_count_overflow();
    test_from_summary();
    return h_report("test_moments");
}
