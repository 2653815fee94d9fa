/*
 * test_moments_rows.c - arrays of accumulators (one per pixel): adding
 * pixel-major stacks is bit for bit add_array + merge per pixel, batches
 * pushed on "two machines" and merged equal one machine's pushes bit for
 * bit, 1e9 + tiny-noise data keep their digits through merging (exact
 * integer oracle), the byte form round-trips and rejects corruption without
 * touching the array, and the row-wise tests on accumulators equal the
 * single *_moments calls bit for bit.
 */
#include "harness.h"
#include "mcstat.h"

#include <stdlib.h>
#include <string.h>

#define PIX 37  /* pixels (rows) */
#define K 29    /* samples per pixel in a batch */

static double urand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1p-53;
}

static int same_m(const mcstat_moments *a, const mcstat_moments *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

static int same_r(const mcstat_result *a, const mcstat_result *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

/* A pixel-major stack: pixel i's k values at x[i*k .. i*k+k). */
static void fill(double *x, size_t pix, size_t k, unsigned long long seed, double offset)
{
    for (size_t i = 0; i < pix; i++)
        for (size_t j = 0; j < k; j++)
            x[i * k + j] = offset + (double)(i % 7) + (urand(&seed) - 0.5) * (1.0 + (double)(i % 3));
}

static void test_add_is_add_array_then_merge(void)
{
    static double a[PIX * K], b[PIX * K];
    fill(a, PIX, K, 1, 0.0);
    fill(b, PIX, K, 2, 0.0);
    static mcstat_moments m[PIX];
    int32_t status[PIX];
    CHECK_INT(mcstat_moments_init_rows(m, PIX), MCSTAT_OK);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, 0, status), MCSTAT_OK);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, b, K, K, 0, NULL), MCSTAT_OK);
    int bad = 0;
    for (int i = 0; i < PIX; i++) {
        mcstat_moments ref, part;
        mcstat_moments_init(&ref);
        mcstat_moments_add_array(&ref, a + i * K, K);
        mcstat_moments_init(&part);
        mcstat_moments_add_array(&part, b + i * K, K);
        mcstat_moments_merge(&ref, &part);
        bad += !same_m(&m[i], &ref) || status[i] != MCSTAT_OK;
    }
    CHECK_INT(bad, 0);

    /* one image at a time (n = 1, x_stride = K reads column 0 of the stack) */
    static mcstat_moments img[PIX];
    mcstat_moments_init_rows(img, PIX);
    CHECK_INT(mcstat_moments_add_rows(img, PIX, a, 1, K, 0, NULL), MCSTAT_OK);
    for (int i = 0; i < PIX; i++)
        CHECK(img[i].n == 1 && img[i].mean == a[i * K] && img[i].m2 == 0.0);
}

/* Two "machines" each push half of the batches; merged in a fixed order the
 * result is one machine's pushes bit for bit, and a different order agrees
 * to rounding. */
static void test_distributed_equals_single(void)
{
    enum { B = 6 };
    static double batch[B][PIX * K];
    for (int t = 0; t < B; t++)
        fill(batch[t], PIX, K, 100 + (unsigned)t, 3.0);
    static mcstat_moments one[PIX], w0[PIX], w1[PIX], w2[PIX], rev[PIX];
    mcstat_moments_init_rows(one, PIX);
    for (int t = 0; t < B; t++)
        mcstat_moments_add_rows(one, PIX, batch[t], K, K, 0, NULL);
    /* worker 0 renders batches 0..2, worker 1 renders 3..5 */
    mcstat_moments_init_rows(w0, PIX);
    mcstat_moments_init_rows(w1, PIX);
    for (int t = 0; t < B / 2; t++) {
        mcstat_moments_add_rows(w0, PIX, batch[t], K, K, 0, NULL);
        mcstat_moments_add_rows(w1, PIX, batch[B / 2 + t], K, K, 0, NULL);
    }
    /* ... but a merge of partial sums only reproduces the sequential pushes
     * when the merge tree is the same: left fold of batch accumulators */
    mcstat_moments_init_rows(w2, PIX);
    for (int t = 0; t < B; t++) {
        static mcstat_moments part[PIX];
        mcstat_moments_init_rows(part, PIX);
        mcstat_moments_add_rows(part, PIX, batch[t], K, K, 0, NULL);
        CHECK_INT(mcstat_moments_merge_rows(w2, part, PIX), MCSTAT_OK);
    }
    int bad = 0;
    for (int i = 0; i < PIX; i++)
        bad += !same_m(&w2[i], &one[i]);
    CHECK_INT(bad, 0);
    /* a tree (w0 + w1) and a reversed order: equal to rounding */
    CHECK_INT(mcstat_moments_merge_rows(w0, w1, PIX), MCSTAT_OK);
    mcstat_moments_init_rows(rev, PIX);
    for (int t = B - 1; t >= 0; t--)
        mcstat_moments_add_rows(rev, PIX, batch[t], K, K, 0, NULL);
    for (int i = 0; i < PIX; i++) {
        CHECK(w0[i].n == one[i].n && rev[i].n == one[i].n);
        CHECK_REL(mcstat_moments_mean(&w0[i]), mcstat_moments_mean(&one[i]), 1e-15, "tree mean %d", i);
        CHECK_REL(mcstat_moments_var(&w0[i]), mcstat_moments_var(&one[i]), 1e-13, "tree var %d", i);
        CHECK_REL(mcstat_moments_mean(&rev[i]), mcstat_moments_mean(&one[i]), 1e-15, "rev mean %d", i);
        CHECK_REL(mcstat_moments_var(&rev[i]), mcstat_moments_var(&one[i]), 1e-13, "rev var %d", i);
        CHECK(w0[i].min == one[i].min && w0[i].max == one[i].max);
    }
    /* merging an array with itself doubles every count, as the single merge does */
    static mcstat_moments self[PIX];
    memcpy(self, one, sizeof self);
    CHECK_INT(mcstat_moments_merge_rows(self, self, PIX), MCSTAT_OK);
    for (int i = 0; i < PIX; i++) {
        mcstat_moments r = one[i];
        mcstat_moments_merge(&r, &one[i]);
        CHECK(same_m(&self[i], &r));
    }
}

/* 1e9 + j * 2^-20 for integers j: exact doubles whose mean and variance are
 * known exactly from integer sums.  Many small batches merged across
 * "machines" must keep the 1e-6-sized spread to ~1e-12. */
static void test_offset_accuracy(void)
{
    enum { P = 4, KB = 50, NB = 40 };
    static double x[P * KB];
    static mcstat_moments w[4][P], total[P];
    for (int q = 0; q < 4; q++)
        mcstat_moments_init_rows(w[q], P);
    long long s1[P] = {0}, s2[P] = {0};
    unsigned long long seed = 7;
    for (int t = 0; t < NB; t++) {
        for (int i = 0; i < P; i++)
            for (int j = 0; j < KB; j++) {
                long long k = (long long)(urand(&seed) * 2001.0) - 1000 + 300 * i;
                s1[i] += k;
                s2[i] += k * k;
                x[i * KB + j] = 1e9 + (double)k * 0x1p-20;
            }
        mcstat_moments_add_rows(w[t % 4], P, x, KB, KB, 0, NULL);
    }
    mcstat_moments_init_rows(total, P);
    mcstat_moments_merge_rows(w[0], w[1], P); /* a tree: (w0 + w1) + (w2 + w3) */
    mcstat_moments_merge_rows(w[2], w[3], P);
    mcstat_moments_merge_rows(total, w[0], P);
    mcstat_moments_merge_rows(total, w[2], P);
    double n = (double)(KB * NB);
    for (int i = 0; i < P; i++) {
        CHECK_INT(total[i].n, KB * NB);
        double mean_off = (double)s1[i] / n * 0x1p-20; /* exact mean - 1e9 */
        double got_off = (total[i].mean - 1e9) + total[i].mean_lo;
        CHECK(fabs(got_off - mean_off) <= 1e-12 * 0x1p-20 * 1000);
        long double ss = (long double)s2[i] - (long double)s1[i] * (long double)s1[i] / (long double)n;
        double var = (double)(ss / (long double)(n - 1)) * 0x1p-40;
        CHECK_REL(mcstat_moments_var(&total[i]), var, 1e-12, "var pixel %d", i);
    }
}

static void test_nonfinite_rows(void)
{
    static double a[(PIX + 1) * K]; /* one row more: the first add reads rows 1..PIX */
    fill(a, PIX + 1, K, 3, 0.0);
    a[4 * K + 2] = NAN;
    a[9 * K + 0] = INFINITY;
    static mcstat_moments m[PIX], before[PIX];
    int32_t status[PIX];
    mcstat_moments_init_rows(m, PIX);
    mcstat_moments_add_rows(m, PIX, a + K, K, K, 0, NULL); /* something already there */
    memcpy(before, m, sizeof m);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, 0, status), MCSTAT_ENONFINITE);
    CHECK_INT(status[4], MCSTAT_ENONFINITE);
    CHECK_INT(status[9], MCSTAT_ENONFINITE);
    CHECK(same_m(&m[4], &before[4]) && same_m(&m[9], &before[9])); /* failed rows unchanged */
    CHECK_INT(status[5], MCSTAT_OK);
    CHECK_INT(m[5].n, before[5].n + K);
    /* NaN omitted: row 4 gets its K - 1 other values; Inf is still an error */
    memcpy(m, before, sizeof m);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, MCSTAT_ROWS_OMIT_NAN, status), MCSTAT_ENONFINITE);
    CHECK_INT(status[4], MCSTAT_OK);
    CHECK_INT(status[9], MCSTAT_ENONFINITE);
    CHECK_INT(m[4].n, before[4].n + K - 1);

    /* argument errors change nothing */
    memcpy(m, before, sizeof m);
    CHECK_INT(mcstat_moments_add_rows(NULL, PIX, a, K, K, 0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, NULL, K, K, 0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, 64u, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, MCSTAT_ROWS_NO_INTERVALS, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_rows(m, 0, NULL, K, K, 0, NULL), MCSTAT_OK);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, NULL, 0, K, 0, NULL), MCSTAT_OK); /* nothing to add */
    m[PIX - 1].version = 77; /* an uninitialised accumulator (n > 0, wrong version) */
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, 0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_merge_rows(m, before, PIX), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_merge_rows(before, m, PIX), MCSTAT_EINVAL);
    m[PIX - 1].version = MCSTAT_MOMENTS_VERSION;
    int bad = 0;
    for (int i = 0; i < PIX; i++)
        bad += !same_m(&m[i], &before[i]) ;
    CHECK_INT(bad, 0);
    CHECK_INT(mcstat_moments_merge_rows(NULL, before, 2), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_merge_rows(m, NULL, 2), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_init_rows(NULL, 2), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_init_rows(NULL, 0), MCSTAT_OK);
}

static void test_bytes(void)
{
    static double a[PIX * K];
    fill(a, PIX, K, 4, 1e6);
    static mcstat_moments m[PIX], r[PIX], keep[PIX];
    mcstat_moments_init_rows(m, PIX);
    mcstat_moments_add_rows(m, PIX - 2, a, K, K, 0, NULL); /* the last two stay empty */
    static unsigned char buf[PIX * MCSTAT_MOMENTS_BYTES];
    CHECK_INT(mcstat_moments_to_bytes_rows(m, PIX, buf, sizeof buf - 1), MCSTAT_EBUFSIZE);
    CHECK_INT(mcstat_moments_to_bytes_rows(m, PIX, buf, sizeof buf), MCSTAT_OK);
    for (int i = 0; i < PIX; i++) { /* record i is exactly the single record */
        unsigned char one[MCSTAT_MOMENTS_BYTES];
        mcstat_moments_to_bytes(&m[i], one, sizeof one);
        CHECK(memcmp(one, buf + i * MCSTAT_MOMENTS_BYTES, sizeof one) == 0);
    }
    CHECK_INT(mcstat_moments_from_bytes_rows(buf, sizeof buf, PIX, r), MCSTAT_OK);
    int bad = 0;
    for (int i = 0; i < PIX; i++)
        bad += !same_m(&m[i], &r[i]);
    CHECK_INT(bad, 0);
    /* corrupt, truncated or mis-sized input leaves the array alone */
    mcstat_moments_init_rows(r, PIX);
    memcpy(keep, r, sizeof r);
    buf[5 * MCSTAT_MOMENTS_BYTES + 30] ^= 1;
    CHECK_INT(mcstat_moments_from_bytes_rows(buf, sizeof buf, PIX, r), MCSTAT_ECORRUPT);
    buf[5 * MCSTAT_MOMENTS_BYTES + 30] ^= 1;
    CHECK_INT(mcstat_moments_from_bytes_rows(buf, sizeof buf - 1, PIX, r), MCSTAT_ECORRUPT);
    CHECK_INT(mcstat_moments_from_bytes_rows(buf, sizeof buf, PIX - 1, r), MCSTAT_ECORRUPT);
    CHECK(memcmp(keep, r, sizeof r) == 0);
    CHECK_INT(mcstat_moments_from_bytes_rows(NULL, sizeof buf, PIX, r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_from_bytes_rows(buf, sizeof buf, PIX, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_to_bytes_rows(NULL, PIX, buf, sizeof buf), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_from_bytes_rows(buf, 0, 0, r), MCSTAT_OK);
}

static void test_tests_on_rows(void)
{
    static double a[PIX * K], b[PIX * K];
    fill(a, PIX, K, 5, 0.0);
    fill(b, PIX, K, 6, 0.2);
    static mcstat_moments x[PIX], y[PIX];
    mcstat_moments_init_rows(x, PIX);
    mcstat_moments_init_rows(y, PIX);
    mcstat_moments_add_rows(x, PIX, a, K, K, 0, NULL);
    mcstat_moments_add_rows(y, PIX, b, K - 5, K, 0, NULL); /* unequal sizes */
    /* failing rows: too few in x[2], constant x[6] (Welch still fine), empty y[11] */
    mcstat_moments_init(&x[2]);
    mcstat_moments_add(&x[2], 1.0);
    mcstat_moments_init(&x[6]);
    for (int j = 0; j < 5; j++)
        mcstat_moments_add(&x[6], 2.5);
    mcstat_moments_init(&y[11]);
    static mcstat_result out[PIX], nointv[PIX];
    int32_t status[PIX];
    for (int alt = 0; alt < 3; alt++) {
        int first;
        for (int test = 0; test < 4; test++) {
            double alpha = 0.01 + 0.04 * test;
            switch (test) {
            case 0: first = mcstat_t_test_1_moments_rows(x, PIX, 0.1, alt, alpha, 0, out, status); break;
            case 1: first = mcstat_t_test_2_moments_rows(x, y, PIX, -0.1, alt, alpha, 0, out, status); break;
            case 2: first = mcstat_var_test_1_moments_rows(x, PIX, 0.4, alt, alpha, 0, out, status); break;
            default: first = mcstat_var_test_2_moments_rows(x, y, PIX, 1.3, alt, alpha, 0, out, status); break;
            }
            int expect_first = MCSTAT_OK, bad = 0;
            for (int i = 0; i < PIX; i++) {
                mcstat_result r;
                int s1;
                switch (test) {
                case 0: s1 = mcstat_t_test_1_moments(&x[i], 0.1, alt, alpha, &r); break;
                case 1: s1 = mcstat_t_test_2_moments(&x[i], &y[i], -0.1, alt, alpha, &r); break;
                case 2: s1 = mcstat_var_test_1_moments(&x[i], 0.4, alt, alpha, &r); break;
                default: s1 = mcstat_var_test_2_moments(&x[i], &y[i], 1.3, alt, alpha, &r); break;
                }
                if (s1 && expect_first == MCSTAT_OK)
                    expect_first = s1;
                if (status[i] != s1)
                    bad++;
                else if (s1 == MCSTAT_OK ? !same_r(&out[i], &r) : !(isnan(out[i].p_value) && isnan(out[i].statistic)))
                    bad++;
            }
            CHECK_MSG(bad == 0, "test %d alt %d: %d rows differ", test, alt, bad);
            CHECK_INT(first, expect_first);
            CHECK(first != MCSTAT_OK); /* the planted rows fail in every test */
        }
    }
    CHECK_INT(mcstat_t_test_2_moments_rows(x, y, PIX, 0.0, 0, 0.05, 0, out, status), MCSTAT_ETOOFEW);
    CHECK_INT(status[2], MCSTAT_ETOOFEW);
    CHECK_INT(status[6], MCSTAT_OK);
    CHECK_INT(status[11], MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_t_test_1_moments_rows(x, PIX, 0.0, 0, 0.05, 0, out, status), MCSTAT_ETOOFEW);
    CHECK_INT(status[6], MCSTAT_EDEGENERATE);

    /* MCSTAT_ROWS_NO_INTERVALS: same p-values and decisions, no intervals */
    mcstat_var_test_2_moments_rows(x, y, PIX, 1.0, 0, 0.05, 0, out, NULL);
    mcstat_var_test_2_moments_rows(x, y, PIX, 1.0, 0, 0.05, MCSTAT_ROWS_NO_INTERVALS, nointv, status);
    for (int i = 0; i < PIX; i++) {
        if (status[i])
            continue;
        CHECK(out[i].p_value == nointv[i].p_value && out[i].reject == nointv[i].reject &&
              out[i].decision == nointv[i].decision && out[i].statistic == nointv[i].statistic);
        CHECK(isnan(nointv[i].conf_int[0]) && isnan(nointv[i].critical[1]) && isfinite(out[i].conf_int[0]));
    }
    /* argument errors */
    CHECK_INT(mcstat_t_test_1_moments_rows(x, PIX, 0.0, 0, 0.05, MCSTAT_ROWS_OMIT_NAN, out, status), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_1_moments_rows(NULL, PIX, 0.0, 0, 0.05, 0, out, status), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_moments_rows(x, NULL, PIX, 0.0, 0, 0.05, 0, out, status), MCSTAT_EINVAL);
    CHECK_INT(mcstat_var_test_2_moments_rows(x, y, PIX, 1.0, 0, 0.05, 0, NULL, status), MCSTAT_EINVAL);
    CHECK_INT(mcstat_var_test_1_moments_rows(x, 0, 1.0, 0, 0.05, 0, NULL, NULL), MCSTAT_OK);
    /* per-row argument errors (alpha, sigma2) are row statuses */
    CHECK_INT(mcstat_t_test_1_moments_rows(x, 2, 0.0, 0, 1.5, 0, out, status), MCSTAT_EINVAL);
    CHECK_INT(status[0], MCSTAT_EINVAL);
    CHECK_INT(mcstat_var_test_1_moments_rows(x, 2, -1.0, 0, 0.05, 0, out, status), MCSTAT_EINVAL);
    CHECK(isnan(out[0].p_value));
}

/* A row whose count would pass 2^64 - 1: add_rows refuses that row alone
 * (the others are added), merge_rows refuses the whole call, changing
 * nothing; both used to wrap the count silently. */
static void test_count_overflow_rows(void)
{
    static double a[PIX * K];
    fill(a, PIX, K, 7, 0.0);
    static mcstat_moments m[PIX], before[PIX], src[PIX];
    int32_t status[PIX];
    mcstat_moments_init_rows(m, PIX);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, 0, NULL), MCSTAT_OK);
    m[3].n = UINT64_MAX - (K - 1); /* one short of room for K more */
    memcpy(before, m, sizeof m);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, 0, status), MCSTAT_ETOOBIG);
    CHECK_INT(status[3], MCSTAT_ETOOBIG);
    CHECK(same_m(&m[3], &before[3]));
    CHECK(status[2] == MCSTAT_OK && m[2].n == 2 * K && status[4] == MCSTAT_OK && m[4].n == 2 * K);
    CHECK_INT(mcstat_moments_add_rows(m, PIX, a, K, K, MCSTAT_ROWS_OMIT_NAN, status), MCSTAT_ETOOBIG);
    CHECK_INT(status[3], MCSTAT_ETOOBIG);
    CHECK(same_m(&m[3], &before[3]));

    memcpy(src, m, sizeof m);
    memcpy(before, m, sizeof m);
    CHECK_INT(mcstat_moments_merge_rows(m, src, PIX), MCSTAT_ETOOBIG);
    CHECK(!memcmp(m, before, sizeof m));
    CHECK_INT(mcstat_moments_merge_rows(m, m, PIX), MCSTAT_ETOOBIG);
    CHECK(!memcmp(m, before, sizeof m));
    src[3].n = 0; /* now every row fits */
    CHECK_INT(mcstat_moments_merge_rows(m, src, PIX), MCSTAT_OK);
    CHECK(m[3].n == UINT64_MAX - (K - 1) && m[4].n == 6 * K);
}

int main(void)
{
    test_add_is_add_array_then_merge();
    test_distributed_equals_single();
    test_offset_accuracy();
    test_nonfinite_rows();
    test_bytes();
    test_tests_on_rows();
    test_count_overflow_rows();
    return h_report("test_moments_rows");
}
