/*
 * test_stream.c - the buffered accumulator (mcstat_stream) and the checks of
 * mcstat/embedded.h with checks compiled in: exactness against add_array,
 * buffer boundaries, non-finite values, merges, and checks that pass on
 * right estimates and fail on biased or noisy ones at the stated rates.
 */
#define MCSTAT_CHECKS 1
static int failures_reported;
#define MCSTAT_CHECK_ON_FAILURE(what, file, line, status, result) \
    ((void)(what), (void)(file), (void)(line), (void)(status), (void)(result), failures_reported++)
#include "mcstat/embedded.h"

#include "harness.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng = 12345;
static double unif(void) /* splitmix64, 53 bits, in (0, 1) */
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}
static double normal(void)
{
    return sqrt(-2 * log(unif())) * cos(6.283185307179586 * unif());
}

static void test_layout(void)
{
    CHECK_INT(sizeof(mcstat_stream), MCSTAT_STREAM_BYTES);
    CHECK_INT(mcstat_sizeof_stream(), 4096);
    CHECK_INT(offsetof(mcstat_stream, moments), 0);
    CHECK_INT(offsetof(mcstat_stream, count), 128);
    CHECK_INT(offsetof(mcstat_stream, n_nonfinite), 136);
    CHECK_INT(offsetof(mcstat_stream, buf), 160);
    CHECK_INT(MCSTAT_STREAM_CAPACITY, (4096 - 160) / 8);
    CHECK_INT(mcstat_stream_init(NULL), MCSTAT_EINVAL);
    mcstat_stream s;
    memset(&s, 0xff, sizeof s);
    CHECK_INT(mcstat_stream_flush(&s), MCSTAT_EINVAL); /* never initialised */
    CHECK_INT(mcstat_stream_init(&s), MCSTAT_OK);
    CHECK_INT(s.count, 0);
    CHECK_INT(s.moments.n, 0);
    CHECK_INT(s.n_nonfinite, 0);
}

/* The stream's moments are add_array's on the same values: 1e9 + noise keeps
 * its digits; the buffer empties exactly at capacity. */
static void test_exact(void)
{
    const size_t n = 100003;
    double *x = malloc(n * sizeof *x);
    for (size_t i = 0; i < n; i++)
        x[i] = 1e9 + 1e-3 * normal();
    mcstat_stream s;
    mcstat_stream_init(&s);
    for (size_t i = 0; i < n; i++) {
        mcstat_stream_add(&s, x[i]);
        if (i + 1 == MCSTAT_STREAM_CAPACITY) {
            CHECK_INT(s.count, 0);
            CHECK_INT(s.moments.n, MCSTAT_STREAM_CAPACITY);
        }
    }
    CHECK_INT(s.count, n % MCSTAT_STREAM_CAPACITY);
    mcstat_moments all, got;
    mcstat_moments_init(&all);
    CHECK_INT(mcstat_moments_add_array(&all, x, n), MCSTAT_OK);
    mcstat_stream before = s;
    CHECK_INT(mcstat_stream_moments(&s, &got), MCSTAT_OK);
    CHECK(!memcmp(&before, &s, sizeof s)); /* not modified */
    CHECK_INT(got.n, n);
    /* the double-double mean: compare mean - 1e9 */
    CHECK_REL((got.mean - 1e9) + got.mean_lo, (all.mean - 1e9) + all.mean_lo, 1e-9, "mean - 1e9");
    CHECK_REL(mcstat_moments_var(&got), mcstat_moments_var(&all), 1e-12, "var");
    CHECK_INT(got.min == all.min && got.max == all.max, 1);
    CHECK_INT(mcstat_stream_flush(&s), MCSTAT_OK);
    CHECK_INT(s.count, 0);
    CHECK_REL(mcstat_moments_var(&s.moments), mcstat_moments_var(&all), 1e-12, "var after flush");
    free(x);
}

static void test_nonfinite(void)
{
    mcstat_stream s;
    mcstat_stream_init(&s);
    for (int i = 0; i < 1000; i++)
        mcstat_stream_add(&s, i == 17 ? NAN : i == 600 ? INFINITY : i == 999 ? -INFINITY : (double)(i % 7));
    mcstat_moments m;
    CHECK_INT(mcstat_stream_flush(&s), MCSTAT_OK);
    CHECK_INT(s.n_nonfinite, 3);
    CHECK_INT(s.moments.n, 997);
    CHECK_INT(mcstat_stream_moments(&s, &m), MCSTAT_OK);
    mcstat_result r;
    CHECK_INT(mcstat_stream_check_mean(&s, 3.0, 0.0, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_stream_check_var(&s, 100.0, 0.05, &r), MCSTAT_ENONFINITE);
    /* a NaN still in the buffer is seen too */
    mcstat_stream t;
    mcstat_stream_init(&t);
    for (int i = 0; i < 10; i++)
        mcstat_stream_add(&t, i == 5 ? NAN : (double)i);
    CHECK_INT(mcstat_stream_check_mean(&t, 4.5, 0.0, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_stream_moments(&t, &m), MCSTAT_OK);
    CHECK_INT(m.n, 9);
    failures_reported = 0;
    CHECK_INT(MCSTAT_CHECK_MEAN(t, 4.5, 0.0, 0.05), 1);
    CHECK_INT(failures_reported, 1);
}

/* Four "threads" with uneven counts, merged: the same moments as one array;
 * src untouched; merging a stream into itself doubles it. */
static void test_merge(void)
{
    const size_t n = 50000;
    double *x = malloc(n * sizeof *x);
    for (size_t i = 0; i < n; i++)
        x[i] = 3.0 + normal();
    mcstat_stream th[4], frame;
    for (int t = 0; t < 4; t++)
        MCSTAT_CHECK_INIT(th[t]);
    MCSTAT_CHECK_INIT(frame);
    size_t cut[5] = {0, 7, 20011, 20500, n};
    for (int t = 0; t < 4; t++)
        for (size_t i = cut[t]; i < cut[t + 1]; i++)
            MCSTAT_CHECK_ADD(th[t], x[i]);
    for (int t = 0; t < 4; t++) {
        mcstat_stream copy = th[t];
        MCSTAT_CHECK_MERGE(frame, th[t]);
        CHECK(!memcmp(&copy, &th[t], sizeof copy));
    }
    mcstat_moments all, got;
    mcstat_moments_init(&all);
    mcstat_moments_add_array(&all, x, n);
    CHECK_INT(mcstat_stream_moments(&frame, &got), MCSTAT_OK);
    CHECK_INT(got.n, n);
    CHECK_REL(mcstat_moments_mean(&got), mcstat_moments_mean(&all), 1e-15, "merged mean");
    CHECK_REL(mcstat_moments_var(&got), mcstat_moments_var(&all), 1e-13, "merged var");
    CHECK_INT(mcstat_stream_merge(&frame, &frame), MCSTAT_OK);
    CHECK_INT(mcstat_stream_moments(&frame, &got), MCSTAT_OK);
    CHECK_INT(got.n, 2 * n);
    CHECK_REL(mcstat_moments_mean(&got), mcstat_moments_mean(&all), 1e-15, "self-merged mean");
    CHECK_INT(mcstat_stream_merge(NULL, &frame), MCSTAT_EINVAL);
    CHECK_INT(mcstat_stream_merge(&frame, NULL), MCSTAT_EINVAL);
    free(x);
}

static void fill(mcstat_stream *s, size_t n, double mean, double sd)
{
    mcstat_stream_init(s);
    for (size_t i = 0; i < n; i++)
        mcstat_stream_add(s, mean + sd * normal());
}

static void test_checks(void)
{
    mcstat_stream s;
    mcstat_result r, t;
    mcstat_moments m;
    /* tolerance 0 is exactly the two-sided t test on the moments */
    fill(&s, 10000, 0.5, 0.3);
    mcstat_stream_moments(&s, &m);
    CHECK_INT(mcstat_stream_check_mean(&s, 0.5, 0.0, 0.01, &r), MCSTAT_OK);
    CHECK_INT(mcstat_t_test_1_moments(&m, 0.5, MCSTAT_TWO_SIDED, 0.01, &t), MCSTAT_OK);
    CHECK(!memcmp(&r, &t, sizeof r));
    /* a bias of 0.01 with standard error 0.003: t ~ 3.3 */
    fill(&s, 1000000, 0.51, 0.3);
    failures_reported = 0;
    CHECK_INT(MCSTAT_CHECK_MEAN(s, 0.5, 0.0, 0.01), 1);
    CHECK_INT(failures_reported, 1);
    /* ... within a tolerance of 0.02 it passes; of 0.005 it fails, naming the
     * upper bound */
    CHECK_INT(MCSTAT_CHECK_MEAN(s, 0.5, 0.02, 0.01), 0);
    CHECK_INT(mcstat_stream_check_mean(&s, 0.5, 0.005, 0.01, &r), MCSTAT_OK);
    CHECK_INT(r.reject, 1);
    CHECK_INT(r.alternative, MCSTAT_GREATER);
    CHECK_REL(r.null_value, 0.505, 1e-15, "upper bound");
    CHECK_REL(r.alpha, 0.005, 1e-15, "alpha/2");
    CHECK_INT(mcstat_stream_check_mean(&s, 0.52, 0.005, 0.01, &r), MCSTAT_OK);
    CHECK_INT(r.reject, 1);
    CHECK_INT(r.alternative, MCSTAT_LESS);
    CHECK_INT(failures_reported, 1);
    /* variance 0.09: below 0.1 passes, below 0.085 fails (chi2, n = 1e6) */
    CHECK_INT(MCSTAT_CHECK_VAR_BELOW(s, 0.1, 0.01), 0);
    CHECK_INT(MCSTAT_CHECK_VAR_BELOW(s, 0.085, 0.01), 1);
    CHECK_INT(mcstat_stream_check_var(&s, 0.085, 0.01, &r), MCSTAT_OK);
    CHECK_INT(r.test, MCSTAT_TEST_VAR_1);
    CHECK_INT(r.alternative, MCSTAT_GREATER);
    /* bad arguments */
    CHECK_INT(mcstat_stream_check_mean(&s, 0.5, -1.0, 0.01, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_stream_check_mean(&s, NAN, 0.0, 0.01, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_stream_check_mean(&s, 0.5, 0.1, 1.5, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_stream_check_var(&s, 0.0, 0.01, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_stream_check_var(&s, 1.0, 0.01, NULL), MCSTAT_EINVAL);
    /* too few values: the check fails with a status */
    mcstat_stream one;
    mcstat_stream_init(&one);
    mcstat_stream_add(&one, 1.0);
    CHECK_INT(mcstat_stream_check_mean(&one, 1.0, 0.0, 0.01, &r), MCSTAT_ETOOFEW);
    CHECK_INT(MCSTAT_CHECK_MEAN(one, 1.0, 0.0, 0.01), 1);
}

/* Rejection rates: on the boundary of H0 (mean = reference + tolerance) the
 * tolerance check rejects at about alpha/2; inside, rarely; with tolerance 0
 * at about alpha.  4000 checks of 64 normal values each; bounds at +-5
 * binomial standard deviations. */
static void test_calibration(void)
{
    const int reps = 4000;
    const double alpha = 0.05;
    int rej_edge = 0, rej_in = 0, rej_zero = 0;
    mcstat_stream s;
    mcstat_result r;
    for (int k = 0; k < reps; k++) {
        fill(&s, 64, 1.1, 1.0);
        mcstat_stream_check_mean(&s, 1.0, 0.1, alpha, &r);
        rej_edge += r.reject;
        mcstat_stream_check_mean(&s, 1.1, 0.3, alpha, &r);
        rej_in += r.reject;
        mcstat_stream_check_mean(&s, 1.1, 0.0, alpha, &r);
        rej_zero += r.reject;
    }
    double e = reps * alpha / 2, sd = sqrt(e * (1 - alpha / 2));
    CHECK_MSG(fabs(rej_edge - e) < 5 * sd, "boundary: %d rejections, expected %.0f", rej_edge, e);
    CHECK_MSG(rej_in < e / 4, "inside: %d rejections", rej_in);
    e = reps * alpha;
    sd = sqrt(e * (1 - alpha));
    CHECK_MSG(fabs(rej_zero - e) < 5 * sd, "tolerance 0: %d rejections, expected %.0f", rej_zero, e);
    printf("rejections in %d checks at alpha %.2f: on the boundary %d (expect %.0f), inside %d, tolerance 0 %d "
           "(expect %.0f)\n", reps, alpha, rej_edge, reps * alpha / 2, rej_in, rej_zero, reps * alpha);
}

/* Counts never wrap.  Merging a stream into itself doubles it: after 63
 * doublings the next is refused with the stream unchanged (it used to wrap
 * n to 0).  A flush that would pass 2^64 - 1 leaves its values out, counts
 * them, keeps the buffer usable, and the checks refuse the stream. */
static void test_count_overflow(void)
{
    mcstat_stream s, before;
    mcstat_stream_init(&s);
    mcstat_stream_add(&s, 1.0);
    mcstat_stream_add(&s, NAN);
    CHECK_INT(mcstat_stream_flush(&s), MCSTAT_OK);
    mcstat_stream_add(&s, 2.0);
    mcstat_stream_add(&s, 4.0);
    int k = 0, st;
    while ((st = mcstat_stream_merge(&s, &s)) == MCSTAT_OK && k < 100)
        k++;
    CHECK_INT(st, MCSTAT_ETOOBIG);
    CHECK_INT(k, 62); /* 3 * 2^62 values would not fit */
    CHECK(s.moments.n == (uint64_t)3 << 62 && s.n_nonfinite == (uint64_t)1 << 62);
    before = s;
    CHECK_INT(mcstat_stream_merge(&s, &s), MCSTAT_ETOOBIG);
    CHECK(!memcmp(&s, &before, sizeof s));

    mcstat_stream t;
    mcstat_stream_init(&t);
    for (int i = 0; i < 10; i++)
        mcstat_stream_add(&t, (double)i);
    CHECK_INT(mcstat_stream_flush(&t), MCSTAT_OK);
    t.moments.n = UINT64_MAX - 100; /* room for 100 more values */
    for (int i = 0; i < 50; i++)
        mcstat_stream_add(&t, (double)i);
    CHECK_INT(mcstat_stream_flush(&t), MCSTAT_OK);
    CHECK(t.moments.n == UINT64_MAX - 50);
    mcstat_moments m0 = t.moments;
    for (unsigned i = 0; i < MCSTAT_STREAM_CAPACITY + 5; i++) /* the automatic flush overflows */
        mcstat_stream_add(&t, (double)i);
    CHECK_INT(t.count, 5);
    CHECK_INT(t.n_overflow, MCSTAT_STREAM_CAPACITY);
    CHECK(!memcmp(&t.moments, &m0, sizeof m0));
    mcstat_result r;
    CHECK_INT(mcstat_stream_check_mean(&t, 4.5, 0.0, 0.05, &r), MCSTAT_ETOOBIG);
    CHECK_INT(mcstat_stream_check_var(&t, 100.0, 0.05, &r), MCSTAT_ETOOBIG);
    failures_reported = 0;
    CHECK_INT(MCSTAT_CHECK_MEAN(t, 4.5, 0.0, 0.05), 1);
    CHECK_INT(failures_reported, 1);
    /* the overflow is carried by a merge */
    mcstat_stream u;
    mcstat_stream_init(&u);
    CHECK_INT(mcstat_stream_merge(&u, &t), MCSTAT_OK);
    CHECK_INT(u.n_overflow, MCSTAT_STREAM_CAPACITY);
    CHECK_INT(mcstat_stream_check_var(&u, 100.0, 0.05, &r), MCSTAT_ETOOBIG);
}

int main(void)
{
    test_layout();
    test_exact();
    test_nonfinite();
    test_merge();
    test_checks();
    test_calibration();
    test_count_overflow();
    return h_report("test_stream");
}
