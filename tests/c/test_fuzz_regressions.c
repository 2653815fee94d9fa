/*
 * test_fuzz_regressions.c - every defect the fuzz harnesses (tests/fuzz)
 * found, as an ordinary test that needs neither clang nor libFuzzer.  The
 * crashing inputs themselves are replayed from tests/fuzz/regressions/.
 * GSL's default handler (abort) stays installed: a call that reaches it
 * kills the test.
 */
#include "harness.h"
#include "mcstat.h"

#include <float.h>
#include <string.h>

/* fuzz_ks: Canner's weight at 1 + 1 values.  The critical value's first
 * guess used log log N, NaN at N = 2, then converted it to an integer
 * (undefined behaviour; UBSan: "-nan is outside the range of unsigned long"). */
static void test_ks_canner_one_each(void)
{
    const double x[1] = {0.0}, y0[1] = {0.0}, y1[1] = {1.0};
    const double *ys[2] = {y0, y1};
    for (int k = 0; k < 2; k++) {
        mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
        o.method = MCSTAT_METHOD_EXACT;
        mcstat_result r;
        int st = mcstat_ks_test_2(x, 1, ys[k], 1, MCSTAT_TWO_SIDED, 0.022, &o, &r);
        CHECK_INT(st, MCSTAT_OK);
        /* both labelings of two values give the same D2: p = 1, never rejected */
        CHECK_REL(r.p_value, 1.0, 0.0, "1 + 1 values, case %d", k);
        CHECK(r.reject == 0 && r.decision == 0);
        CHECK(!isnan(r.critical[1]) && r.statistic <= r.critical[1]);
    }
}

/* fuzz_dist: the t far tail (|t| >= 1e150) at df near DBL_MAX computed
 * (a - 1/2) log a - (a + 1/2) log(a + 1/2) as Inf - Inf: P = NaN with
 * status OK.  Oracle: for u^2 >> df the log tail is -df log(u / sqrt(df))
 * to relative O(log(df) / (df log(u/sqrt df))). */
static void test_t_far_tail_huge_df(void)
{
    double p = -1.0, lp = 1.0;
    CHECK_INT(mcstat_t_cdf(DBL_MAX, DBL_MAX, 0, &p), MCSTAT_OK);
    CHECK_REL(p, 1.0, 0.0, "t_cdf(DBL_MAX; DBL_MAX) lower");
    CHECK_INT(mcstat_t_cdf(DBL_MAX, DBL_MAX, 1, &p), MCSTAT_OK);
    CHECK_REL(p, 0.0, 0.0, "t_cdf(DBL_MAX; DBL_MAX) upper");
    CHECK_INT(mcstat_t_logcdf(DBL_MAX, DBL_MAX, 1, &lp), MCSTAT_OK);
    CHECK(!isnan(lp) && lp <= 0.0);
    CHECK_INT(mcstat_t_logcdf(1e200, 1e300, 1, &lp), MCSTAT_OK);
    CHECK_REL(lp, -1e300 * log(1e50), 1e-9, "log P[T > 1e200], df 1e300");
    /* df > (u / 1e10)^2: the normal-like branch, -u^2/2 to leading order */
    CHECK_INT(mcstat_t_logcdf(1e150, 1e300, 1, &lp), MCSTAT_OK);
    CHECK_REL(lp, -0.5 * (1e300 + 1.0) * log1p(1e-300 * 1e150 * 1e150), 1e-9, "log P[T > 1e150], df 1e300");
    CHECK_INT(mcstat_t_logcdf(-1e200, 1e300, 0, &lp), MCSTAT_OK);
    CHECK_REL(lp, -1e300 * log(1e50), 1e-9, "log P[T <= -1e200], df 1e300 (symmetry)");
}

/* fuzz_dist: degrees of freedom so small that df/2 is 0 or below 1e-300
 * reached GSL's gammastar outside its domain or past its overflow, and
 * GSL's default handler aborted the process. */
static void test_tiny_df_no_gsl_abort(void)
{
    double p = -1.0;
    const double tiny = 4.9406564584124654e-324;
    /* and where the method fails (df/2 rounds to 0), a status, not NaN */
    p = -1.0;
    int st = mcstat_t_cdf(-3.7233823367636213e+198, tiny, 0, &p);
    CHECK(st != MCSTAT_OK || (p >= 0.0 && p <= 1.0));
    CHECK(st == MCSTAT_OK || p == -1.0);
    st = mcstat_t_cdf(tiny, tiny, 0, &p);
    CHECK(st == MCSTAT_OK || st == MCSTAT_EINVAL || st == MCSTAT_ENUMERIC);
    if (st == MCSTAT_OK)
        CHECK(p >= 0.5 && p <= 1.0);
    /* chi-squared at df = 2.2e-308 (a = df/2 = 1.1e-308 < 1e-300): no abort,
     * tails in [0, 1] summing to 1.  (Their accuracy is not promised below
     * df = 1e-3, and is poor here: Q = 5.7e-14 where the series gives
     * -a (log(x/2) + Euler's gamma) = 8.3e-306; tests/fuzz/README.md.) */
    const double df = 2.2250738585072014e-308, x = 4 * tiny;
    double q = -1.0;
    CHECK_INT(mcstat_chisq_cdf(x, df, 1, &q), MCSTAT_OK);
    CHECK_INT(mcstat_chisq_cdf(x, df, 0, &p), MCSTAT_OK);
    CHECK(p >= 0.0 && p <= 1.0 && q >= 0.0 && q <= 1.0);
    CHECK_REL(p + q, 1.0, 1e-15, "tails of chi2(2.2e-308) at 2e-323");
    CHECK_INT(mcstat_chisq_cdf(tiny, 0.5 * df, 0, &p), MCSTAT_OK);
    CHECK(p >= 0.0 && p <= 1.0);
}

/* fuzz_bytes: an accumulator whose m2 is near underflow (possible only
 * through from_bytes or merges): v/n underflowed to 0 and t = 0/0 = NaN with
 * status OK.  Oracle: t = mean / sqrt(m2 / ((n - 1) n)) with m2 scaled by 2^200. */
static void test_t_tiny_m2(void)
{
    mcstat_moments m;
    mcstat_moments_init(&m);
    m.n = 42949672985ull;
    m.scale = 0;
    m.mean = 1e-170;
    m.m2 = 0x1.4ffff60ff1919p-1015;
    m.min = -1e-160;
    m.max = 1e-160;
    mcstat_result r;
    CHECK_INT(mcstat_t_test_1_moments(&m, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    /* the oracle scales by powers of two (exact) instead of relying on long
     * double's exponent range, which valgrind and some ABIs do not have */
    double n = (double)m.n, se = sqrt(ldexp(m.m2, 200) / ((n - 1) * n)) * 0x1p-100;
    CHECK_REL(r.statistic, 1e-170 / se, 1e-14, "t with m2 = 1.3e-305");
    CHECK_REL(r.std_error, se, 1e-14, "standard error");
    CHECK(r.p_value > 0.99 && r.p_value <= 1.0);
    CHECK(r.conf_int[0] < 1e-170 && r.conf_int[1] > 1e-170);
    mcstat_result v;
    CHECK_INT(mcstat_var_test_2_moments(&m, &m, 1.0, MCSTAT_TWO_SIDED, 0.05, &v), MCSTAT_OK);
    CHECK_REL(v.statistic, 1.0, 0.0, "F of an accumulator against itself");
}

/* FNV-1a 64 and the layout of serialize.c, to write bytes by hand. */
static uint64_t fnv1a(const unsigned char *p, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

static void moments_bytes(unsigned char *b, uint64_t n, const double f[7])
{
    memset(b, 0, MCSTAT_MOMENTS_BYTES);
    memcpy(b, "MCSM", 4);
    b[4] = 1;
    for (int i = 0; i < 8; i++)
        b[8 + i] = (unsigned char)(n >> (8 * i));
    for (int k = 0; k < 7; k++) {
        uint64_t u;
        memcpy(&u, &f[k], 8);
        for (int i = 0; i < 8; i++)
            b[24 + 8 * k + i] = (unsigned char)(u >> (8 * i));
    }
    uint64_t h = fnv1a(b, 88);
    for (int i = 0; i < 8; i++)
        b[88 + i] = (unsigned char)(h >> (8 * i));
}

/* fuzz_bytes: from_bytes accepted (mean, mean_lo) = (0, 2^-1074), not a
 * normalised double-double, and min == max with m2 > 0; merging such an
 * accumulator with itself gave a mean above max, which from_bytes then
 * refused: the library produced what it would not read back. */
static void test_from_bytes_consistency(void)
{
    const double tiny = 4.9406564584124654e-324;
    unsigned char b[MCSTAT_MOMENTS_BYTES];
    mcstat_moments m;
    const double noncanonical[7] = {0.0, tiny, 0x0.086p-1022, 0.0, 0.0, 0.0, 0.0};
    moments_bytes(b, 81, noncanonical);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    /* (fuzz_bytes in CI) the same lower part among values that spread, -1
     * and 1: refused (a t interval formed from hi + lo left the estimate, hi
     * = 0, outside it); without it, the record is read */
    const double zero_with_lo[7] = {0.0, tiny, 2.0, 0.0, 2.0, -1.0, 1.0};
    moments_bytes(b, 2, zero_with_lo);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    const double zero_without_lo[7] = {0.0, 0.0, 2.0, 0.0, 2.0, -1.0, 1.0};
    moments_bytes(b, 2, zero_without_lo);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_OK);
    const double spread_without_range[7] = {0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0};
    moments_bytes(b, 81, spread_without_range);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    /* third and fourth sums beyond what the second allows */
    const double m3_without_m2[7] = {1.0, 0.0, 0.0, 0x1p1008, 0.0, -1.0, 3.0};
    moments_bytes(b, 7, m3_without_m2);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    const double m4_too_big[7] = {1.0, 0.0, 4.0, 0.0, 17.0, -1.0, 3.0};
    moments_bytes(b, 7, m4_too_big);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    const double m4_too_small[7] = {1.0, 0.0, 4.0, 0.0, 2.2e-308, -1.0, 3.0};
    moments_bytes(b, 7, m4_too_small);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    const double not_psd[7] = {0x1.4cc69cccccccdp+1, 0.0, 7.2, -12.5, 9.0, 1.0, 4.5};
    moments_bytes(b, 21, not_psd);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    /* (fuzz_bytes in CI) a spread far below the range: min and max are two
     * of the values, so m2 >= (max - min)^2 / 2; its merge with 30 equal
     * values was refused on reading back */
    const double m2_below_range[7] = {0x1.e2acccccccccdp+1, 0.0, 0x1.ccccccccccccdp+1, 0x1.009000001p+0,
                                      0x1.2p+3, 0x1p-4, 0x1.1410000004941p+21};
    moments_bytes(b, 2, m2_below_range);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_ECORRUPT);
    /* ... while two genuine values at those extremes sit on the bound */
    const double pair[2] = {0x1p-4, 0x1.1410000004941p+21};
    mcstat_moments pm, pm_back;
    mcstat_moments_init(&pm);
    CHECK_INT(mcstat_moments_add_array(&pm, pair, 2), MCSTAT_OK);
    CHECK_INT(mcstat_moments_to_bytes(&pm, b, sizeof b), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &pm_back), MCSTAT_OK);
    const double m4_ok[7] = {1.0, 0.0, 8.0, 0.0, 32.0, -1.0, 3.0}; /* {-1, 3, 1, 1, 1, 1, 1} */
    moments_bytes(b, 7, m4_ok);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &m), MCSTAT_OK);
    /* (fuzz_moments) data 2^-1019 apart by a few ulps: mean_lo on the
     * subnormal grid is half an ulp of the mean, and must still read back */
    double near_min[40];
    for (int i = 0; i < 40; i++)
        near_min[i] = -0x1.ff165p-1020 + (double)((i * 7) % 13 - 6) * 0x1p-1072;
    mcstat_moments nm, nm_back;
    mcstat_moments_init(&nm);
    CHECK_INT(mcstat_moments_add_array(&nm, near_min, 40), MCSTAT_OK);
    CHECK_INT(mcstat_moments_to_bytes(&nm, b, sizeof b), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &nm_back), MCSTAT_OK);
    /* a genuine accumulator still reads back, and so does its self-merge */
    const double x[4] = {0.0, tiny, 2 * tiny, tiny};
    mcstat_moments g, back;
    mcstat_moments_init(&g);
    CHECK_INT(mcstat_moments_add_array(&g, x, 4), MCSTAT_OK);
    CHECK_INT(mcstat_moments_merge(&g, &g), MCSTAT_OK);
    CHECK_INT(mcstat_moments_to_bytes(&g, b, sizeof b), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_bytes(b, sizeof b, &back), MCSTAT_OK);
    CHECK(back.n == 8 && back.mean >= back.min && back.mean <= back.max);
}

/* fuzz_bytes: the t statistics formed mean - mu0 before scaling to the
 * data's units, so mean(y) = 1.4e300 against mu0 = 1.8e308 overflowed to
 * -Inf and the statistic came out NaN with status OK (ordinary arrays reach
 * it).  Oracle: the statistic in units of 2^1000, where every term is a
 * double (whatever the width of long double). */
static void scaled_mean_var(const double *v, int n, double *m, double *var)
{
    const double S = 0x1p-1000;
    *m = 0.0;
    for (int i = 0; i < n; i++)
        *m += v[i] * S;
    *m /= n;
    *var = 0.0;
    for (int i = 0; i < n; i++)
        *var += (v[i] * S - *m) * (v[i] * S - *m);
    *var /= n - 1;
}

static void test_t_null_value_near_overflow(void)
{
    const double S = 0x1p-1000;
    const double x[4] = {1.0, 2.0, 3.0, 4.0}, y[4] = {1e300, 2e300, 1.5e300, 1.2e300};
    double mx, my, vx, vy; /* in units of 2^1000: x's variance underflows, 1e-600 of y's */
    scaled_mean_var(x, 4, &mx, &vx);
    scaled_mean_var(y, 4, &my, &vy);
    mcstat_result r;
    CHECK_INT(mcstat_t_test_2(x, 4, y, 4, DBL_MAX, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_REL(r.statistic, (mx - my - DBL_MAX * S) / sqrt(vx / 4 + vy / 4), 1e-12, "Welch t, mu0 = DBL_MAX");
    CHECK(r.p_value < 1e-20 && r.reject == 1 && r.decision == -1);
    CHECK_INT(mcstat_t_test_1(y, 4, -DBL_MAX, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_REL(r.statistic, (my + DBL_MAX * S) / sqrt(vy / 4), 1e-12, "t, mu0 = -DBL_MAX");
    CHECK(r.reject == 1 && r.decision == 1);
    /* and the other way (fuzz_tests): subnormal data (scale 2^-1026) against
     * mu0 = -50: scaling mu0 first overflowed to Inf, the statistic was NaN.
     * The mean is 5e-310 above -50 in units of a 5e-310 standard error. */
    const double s[3] = {-0x0.114034bc6a7fp-1022, 0.0, 0.0};
    CHECK_INT(mcstat_t_test_1(s, 3, -50.2, MCSTAT_GREATER, 0.25, &r), MCSTAT_OK);
    CHECK(r.statistic == INFINITY && r.p_value == 0.0 && r.reject == 1);
    CHECK_INT(mcstat_t_test_2(s, 3, x, 4, -50.2, MCSTAT_TWO_SIDED, 0.25, &r), MCSTAT_OK);
    CHECK_REL(r.statistic, (-2.5 + 50.2) / sqrt((5.0 / 3.0) / 4), 1e-12, "Welch t, subnormal x");
    /* (fuzz_rows) means near -DBL_MAX and +DBL_MAX/2: mean(x) - mean(y)
     * itself overflowed unscaled; the statistic was NaN. */
    const double u[3] = {-DBL_MAX, -DBL_MAX, -0.5 * DBL_MAX}, w[3] = {0.5 * DBL_MAX, 0.25 * DBL_MAX, 0.0};
    double mu, mw, vu, vw;
    scaled_mean_var(u, 3, &mu, &vu);
    scaled_mean_var(w, 3, &mw, &vw);
    CHECK_INT(mcstat_t_test_2(u, 3, w, 3, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_REL(r.statistic, (mu - mw) / sqrt(vu / 3 + vw / 3), 1e-12, "Welch t, means near -+DBL_MAX");
    CHECK(r.conf_int[0] == -INFINITY && r.conf_int[1] < 0.0);
}

/* fuzz_rows: a t critical value beyond 2^900 (df = 1, alpha = DBL_MIN:
 * -1/(pi alpha) = -1.43e307) overflowed Dekker's split in the interval's
 * bound, giving conf_int[1] = NaN.  Oracle: mean - c se, c from the Cauchy
 * quantile tan(pi (alpha - 1/2)) = -1/(pi alpha) to relative 1e-16. */
static void test_t_interval_huge_critical(void)
{
    const double x[2] = {0.0, 1.0};
    mcstat_result r;
    CHECK_INT(mcstat_t_test_1(x, 2, 0.0, MCSTAT_LESS, DBL_MIN, &r), MCSTAT_OK);
    CHECK(r.conf_int[0] == -INFINITY);
    CHECK_REL(r.conf_int[1], 0.5 + 0.5 / (M_PI * DBL_MIN), 1e-12, "upper bound at alpha = DBL_MIN");
    const double y[3] = {0.0, 1.0, 2.0};
    CHECK_INT(mcstat_t_test_2(x, 2, y, 3, 0.0, MCSTAT_TWO_SIDED, DBL_MIN, &r), MCSTAT_OK);
    CHECK(!isnan(r.conf_int[0]) && !isnan(r.conf_int[1]) && r.conf_int[0] < -0.5 && r.conf_int[1] > -0.5);
}

/* fuzz_moments: merging blocks whose means are near +-DBL_MAX formed the
 * difference of the means unscaled: it overflowed (or Dekker's split did)
 * and the mean came out NaN.  Oracle: exact means of small integers times
 * 2^1000, and min <= mean <= max. */
static void test_merge_extreme_means(void)
{
    mcstat_moments a, b;
    mcstat_moments_init(&a);
    mcstat_moments_init(&b);
    const double big = 0x1p1020, xa[2] = {-big, -3 * big}, xb[2] = {7 * big, 5 * big};
    CHECK_INT(mcstat_moments_add_array(&a, xa, 2), MCSTAT_OK);
    CHECK_INT(mcstat_moments_add_array(&b, xb, 2), MCSTAT_OK);
    CHECK_INT(mcstat_moments_merge(&a, &b), MCSTAT_OK);
    CHECK_REL(mcstat_moments_mean(&a), 2 * big, 0.0, "mean of -1, -3, 7, 5 times 2^1020");
    CHECK_REL(mcstat_moments_sd(&a), sqrt(68.0 / 3.0) * big, 1e-15, "sd");
    const double xs[4] = {-DBL_MAX, 54039278518272.0, -DBL_MAX, DBL_MAX};
    mcstat_moments c;
    mcstat_moments_init(&c);
    CHECK_INT(mcstat_moments_add_array(&c, xs, 2), MCSTAT_OK);
    CHECK_INT(mcstat_moments_merge(&c, &c), MCSTAT_OK);
    CHECK_INT(mcstat_moments_add_array(&c, xs + 2, 2), MCSTAT_OK);
    double m = mcstat_moments_mean(&c);
    CHECK(!isnan(m) && m >= -DBL_MAX && m <= DBL_MAX);
    CHECK_REL(m, -DBL_MAX / 3, 1e-15, "mean of 2 x {-DBL_MAX, 5.4e13}, -DBL_MAX, DBL_MAX");
    /* 1 value at -DBL_MAX merged with 7 at DBL_MAX: the increment of the
     * mean, 7/8 of 2 DBL_MAX, exceeds DBL_MAX; the mean, 3/4 DBL_MAX, does not */
    const double lo1[1] = {-DBL_MAX}, hi7[7] = {DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX};
    mcstat_moments l, h;
    mcstat_moments_init(&l);
    mcstat_moments_init(&h);
    CHECK_INT(mcstat_moments_add_array(&l, lo1, 1), MCSTAT_OK);
    CHECK_INT(mcstat_moments_add_array(&h, hi7, 7), MCSTAT_OK);
    CHECK_INT(mcstat_moments_merge(&l, &h), MCSTAT_OK);
    CHECK_REL(mcstat_moments_mean(&l), 0.75 * DBL_MAX, 1e-15, "mean of -DBL_MAX and 7 x DBL_MAX");
}

/* fuzz_dist: F with df1 = 0.125, df2 = 2^29: the incomplete beta's
 * continued fraction converges slowly there and its iteration cap (from
 * min(a, b) = 1/16) returned MCSTAT_ENUMERIC for 1.2% of points.  Oracle:
 * mpmath 1.3 at 40 digits, betainc(df1/2, df2/2, 0, df1 f/(df1 f + df2),
 * regularized=True).  The slow fraction then stopped early (5e-13 off);
 * a = 1/16 now takes the small-parameter series (3e-16 against mpmath). */
static void test_f_small_df1_large_df2(void)
{
    const double f[3] = {1.0110785291877413, 1.1946665533426208, 2.5};
    const double lower[3] = {0.86648945130511305, 0.87499999999999533, 0.91216476390659686};
    const double upper[3] = {0.13351054869488695, 0.12500000000000467, 0.087835236093403145};
    for (int i = 0; i < 3; i++) {
        double p = -1.0, q = -1.0;
        CHECK_INT(mcstat_f_cdf(f[i], 0.125, 536870912.0, 0, &p), MCSTAT_OK);
        CHECK_INT(mcstat_f_cdf(f[i], 0.125, 536870912.0, 1, &q), MCSTAT_OK);
        CHECK_REL(p, lower[i], 1e-14, "P[F(0.125, 2^29) <= %g]", f[i]);
        CHECK_REL(q, upper[i], 1e-14, "P[F(0.125, 2^29) > %g]", f[i]);
    }
}

/* fuzz_dist (a clean-clone CI run of make fuzz-ci): F with df1 = 0x1.ffp+48,
 * df2 = 1/32 was not monotone at 1: F(1) = 0.054841186279286872 >
 * F(1 + 2^-52) = 0.054841186279192211.  At f = 1 exactly the incomplete
 * beta took its lower-tail continued fraction, one ulp above the upper
 * tail's, and the two disagreed by 1.7e-12 (each stopping early with
 * b = 1/64).  Input: regressions/fuzz_dist/f_huge_df1_df2_1_32_not_monotone.
 * Oracle: mpmath at 50 digits (tools/refgen/mpref.py f_tails). */
static void test_f_huge_df1_small_df2_monotone(void)
{
    const double df1 = 0x1.ffp+48, df2 = 0.03125, up = 1.0000000000000002;
    double a = -1.0, b = -1.0;
    CHECK_INT(mcstat_f_cdf(1.0, df1, df2, 0, &a), MCSTAT_OK);
    CHECK_INT(mcstat_f_cdf(up, df1, df2, 0, &b), MCSTAT_OK);
    CHECK(a <= b);
    CHECK_REL(a, 5.4841186279191243e-2, 1e-14, "F(1; 0x1.ffp+48, 1/32)");
    CHECK_REL(b, 5.4841186279191246e-2, 1e-14, "F(1 + 2^-52; 0x1.ffp+48, 1/32)");
}

/* fuzz_dist (once MCSTAT_ENUMERIC counted as a failure in the documented
 * df range): chi-squared at df = 1/32 and x = DBL_MAX returned
 * MCSTAT_ENUMERIC: the prefactor's u = (x/2 - a)/a overflowed and
 * Inf - log1p(Inf) gave NaN.  Input: regressions/fuzz_dist/
 * chisq_df_1_32_at_dbl_max_enumeric.  Oracle: log Q(a, z) = -z + (a - 1)
 * log z - log Gamma(a) + O(1/z), z = x/2 (DLMF 8.11.2), here -z to 1e-300. */
static void test_chisq_small_df_at_dbl_max(void)
{
    double p = -1.0, lq = 1.0;
    CHECK_INT(mcstat_chisq_cdf(DBL_MAX, 0.03125, 0, &p), MCSTAT_OK);
    CHECK(p == 1.0);
    CHECK_INT(mcstat_chisq_logcdf(DBL_MAX, 0.03125, 1, &lq), MCSTAT_OK);
    CHECK_REL(lq, -0.5 * DBL_MAX, 1e-15, "log P[chi2(1/32) > DBL_MAX]");
    CHECK_INT(mcstat_chisq_logcdf(0.25 * DBL_MAX, 0.001, 1, &lq), MCSTAT_OK);
    CHECK_REL(lq, -0.125 * DBL_MAX, 1e-15, "log P[chi2(0.001) > DBL_MAX/4]");
}

/* fuzz_dist (once MCSTAT_ENUMERIC counted as a failure in the documented
 * range; the harness had accepted it): F with df1 = 0.001, df2 = 562 at
 * x = 1.5 and the upper quantile at p = 1e-300 returned it, the continued
 * fraction for I_y(281, 0.0005) not converging.  Input:
 * regressions/fuzz_dist/f_df1_0001_enumeric.  Oracle: mpmath at 50 digits
 * (mpref.py f_tails, quantile). */
static void test_f_df1_0001_answers(void)
{
    double p = -1.0, q = -1.0, x = -1.0;
    CHECK_INT(mcstat_f_cdf(1.5, 0.001, 562, 1, &q), MCSTAT_OK);
    CHECK_REL(q, 0.0033051069838228338, 1e-14, "P[F(0.001, 562) > 1.5]");
    CHECK_INT(mcstat_f_cdf(2.0, 0.001, 562, 0, &p), MCSTAT_OK);
    CHECK_REL(p, 0.9968381444657125, 1e-15, "P[F(0.001, 562) <= 2]");
    CHECK_INT(mcstat_f_quantile(1e-300, 0.001, 562, 1, &x), MCSTAT_OK);
    CHECK_REL(x, 5.7047112680203527e+6, 1e-13, "upper 1e-300 quantile of F(0.001, 562)");
}

/* fuzz_rows: variance intervals at extreme alpha.  A critical value below
 * DBL_MIN came back 0 from the quantile (or above DBL_MAX, Inf), and the
 * bound M2 / c became Inf (or 0) although the true bound is an ordinary
 * double: at alpha = 9.2e-274, var_test_2 on {2.5e-312, 0} against 9 values
 * up to 1e301 gave [0, Inf] with p = 0 rejecting ratio 4e86
 * (regressions/fuzz_rows/var_ci_critical_below_dbl_min; both true bounds,
 * 2.9e-1313 and 1.0e-697, underflow: [0, 0]).  The expected bounds are
 * from mpmath at 50 digits:
 *   F(1, 8) lower quantile at p = 1e-200/2 (the double 1e-200):
 *     findroot(lambda z: log(betainc(1/2, 4, 0, exp(z)/(exp(z)+8), regularized=True)) - log(p), log(4e-401))
 *     = 4.179591836734693727923826e-401; (1e-50)^2/2 / 7.5 / that = 1.595052083333333414731908e+299
 *   chi2(1) lower quantile at the same p:
 *     findroot(lambda z: log(gammainc(1/2, 0, exp(z)/2, regularized=True)) - log(p), log(4e-401))
 *     = 3.926990816987241407494094e-401; (1e-50)^2/2 / that = 1.273239544735162751126932e+300
 *   F(2, 1) upper quantile at p (betainc(1/2, 1, 0, 1/(2 f + 1), regularized=True) = p)
 *     = 2.00000000000000007159895e+400; (1e100)^2 / (1/2) / that = 9.99999999999999996006307e-201;
 *   at p = 1e-200 (one-sided), f = (1/p^2 - 1)/2 exactly: (1e100)^2 * 2 / f = 3.999999999999999984025228e-200
 * (mpmath's 1e-50 and 1e100 are the doubles' exact values.) */
static void test_var_interval_extreme_alpha(void)
{
    const double alpha = 1e-200;
    double x[2] = {0.0, 1e-50}, y[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    double x3[3] = {0.0, 1e100, 2e100}, y2[2] = {0.0, 1.0};
    mcstat_result r, rows[1];

    CHECK_INT(mcstat_var_test_2(x, 2, y, 9, 1.0, MCSTAT_TWO_SIDED, alpha, &r), MCSTAT_OK);
    CHECK(r.critical[0] == 0.0); /* the reported critical value stays clamped */
    CHECK_REL(r.conf_int[1], 1.595052083333333414731908e+299, 1e-12, "F(1, 8) upper bound at alpha 1e-200");
    CHECK(r.conf_int[0] > 0.0 && r.conf_int[0] < r.conf_int[1]);
    CHECK(!r.reject); /* ratio 1 lies inside */
    CHECK_INT(mcstat_var_test_2_matrix(x, 2, 2, y, 9, 9, 1, 1.0, MCSTAT_TWO_SIDED, alpha, 0, rows, NULL), MCSTAT_OK);
    CHECK(memcmp(&rows[0], &r, sizeof r) == 0);

    CHECK_INT(mcstat_var_test_1(x, 2, 1.0, MCSTAT_TWO_SIDED, alpha, &r), MCSTAT_OK);
    CHECK(r.critical[0] == 0.0);
    CHECK_REL(r.conf_int[1], 1.273239544735162751126932e+300, 1e-12, "chi2(1) upper bound at alpha 1e-200");
    CHECK_INT(mcstat_var_test_1_matrix(x, 2, 2, 1, 1.0, MCSTAT_TWO_SIDED, alpha, 0, rows, NULL), MCSTAT_OK);
    CHECK(memcmp(&rows[0], &r, sizeof r) == 0);

    /* the other side: the upper critical value overflows, the lower bound does not */
    CHECK_INT(mcstat_var_test_2(x3, 3, y2, 2, 1.0, MCSTAT_TWO_SIDED, alpha, &r), MCSTAT_OK);
    CHECK(r.critical[1] == INFINITY);
    CHECK_REL(r.conf_int[0], 9.99999999999999996006307e-201, 1e-12, "F(2, 1) lower bound at alpha 1e-200");
    CHECK(r.conf_int[1] == INFINITY); /* 2e200 / 5e-201 does overflow */
    CHECK_INT(mcstat_var_test_2(x3, 3, y2, 2, 1.0, MCSTAT_GREATER, alpha, &r), MCSTAT_OK);
    CHECK_REL(r.conf_int[0], 3.999999999999999984025228e-200, 1e-12, "one-sided: F(2, 1) upper quantile at alpha");
    CHECK(r.conf_int[1] == INFINITY);

    /* the fuzzer's input: both true bounds underflow */
    double fx[2] = {0x0.00000000002ffp-1022, 0.0};
    double fy[9] = {-0x1.f5c28f5c28f8p+1001, -0x1.f00ff99809a2p-1020, -0x1.47bp+6, 0x1.eb84p+6, -0x1.fd04p+382,
                    0x1.0bff35c28f5c2p-215, 0x1.f5c8f8028f5c2p-1012, 0x1.9998p+5, -0x1.a9p+3};
    CHECK_INT(mcstat_var_test_2(fx, 2, fy, 9, 0x1.b851eb880bfe7p+287, MCSTAT_TWO_SIDED, 0x1.ff2663f526666p-908, &r),
              MCSTAT_OK);
    CHECK(r.reject && r.p_value == 0.0);
    CHECK(r.conf_int[0] == 0.0 && r.conf_int[1] == 0.0);
}

/* Found by the duality check once it ran on saturated bounds: with data near
 * 1e58 against data near 1e286, M2_x / M2_y in the accumulators' units
 * (times 2^k, k = -1510 here) over a normal critical value 2.7e-199
 * overflowed before the scaling, and the upper bound came out Inf for
 * 5.3e-259.  mpmath, 50 digits: est = var{x} / var{y} from the exact
 * values = 1.429330276341942670711915e-457; F(1, 3) lower quantile at alpha,
 *   findroot(lambda z: log(betainc(1/2, 3/2, 0, exp(z)/(exp(z)+3), regularized=True)) - log(alpha), log(2.7e-199))
 *   = 2.688607230755516502892913e-199; est / that = 5.316247981451315826321548e-259. */
static void test_var_interval_quotient_overflow(void)
{
    double x[2] = {0x1.7044c66e6c48cp+193, -3.0};
    double y[4] = {-4.0, -0x1.c64ddf9c4b662p+952, -0x1.007ce9f8ed42ap-379, -5.0};
    mcstat_result r;
    CHECK_INT(mcstat_var_test_2(x, 2, y, 4, 0x1.a203c3fc2d15dp-792, MCSTAT_LESS, 0x1.aadb36ec3d491p-331, &r),
              MCSTAT_OK);
    CHECK_REL(r.critical[0], 2.688607230755516502892913e-199, 1e-12, "F(1, 3) lower quantile");
    CHECK(r.conf_int[0] == 0.0);
    CHECK_REL(r.conf_int[1], 5.316247981451315826321548e-259, 1e-12, "upper bound");
}

/* fuzz_checks: RECIPROCITY evaluates eval(x, wi) with wi and the sampled
 * point swapped; for a hemisphere BSDF with wi below the horizon (allowed:
 * light from below) that passed eval() a point off the model's domain.
 * Oracle: a uniform hemisphere BSDF whose eval() counts points with z < 0. */
typedef struct hemi_model {
    int off_domain;
} hemi_model;

static int hemi_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                       double *pdf)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++) {
        double z = u[3 * k], r = sqrt(fmax(0.0, 1.0 - z * z)), phi = 6.283185307179586 * u[3 * k + 1];
        x[3 * k] = r * cos(phi), x[3 * k + 1] = r * sin(phi), x[3 * k + 2] = z;
        pdf[k] = 1.0 / 6.283185307179586;
        weight[k] = 0.5;
    }
    return 0;
}

static int hemi_density(void *user, const double *wi, const double *x, size_t n, double *out, double scale)
{
    hemi_model *m = user;
    (void)wi;
    for (size_t k = 0; k < n; k++) {
        if (x[3 * k + 2] < -1e-4)
            m->off_domain++;
        out[k] = scale / 6.283185307179586;
    }
    return 0;
}

static int hemi_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    return hemi_density(user, wi, x, n, out, 1.0);
}

static int hemi_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    return hemi_density(user, wi, x, n, out, 0.5);
}

static void test_check_reciprocity_wi_below_hemisphere(void)
{
    hemi_model hm = {0};
    mcstat_check_model m = {MCSTAT_CHECK_DOMAIN_HEMISPHERE, 3, MCSTAT_CHECK_WEIGHT_OVER_PDF, 1, &hm, hemi_sample, hemi_pdf,
                            hemi_eval, {{0, 0, 0, 0}}};
    mcstat_check_options o;
    mcstat_check_options_init(&o);
    o.reciprocal = 1;
    const double wi[3] = {0.35, 0.52, -0.78};
    mcstat_check_report r;
    CHECK_INT(mcstat_check_bsdf(&m, wi, 1000, 1, 0.05, &o, NULL, 0, &r), MCSTAT_OK);
    CHECK_MSG(hm.off_domain == 0, "eval() got %d points below the horizon", hm.off_domain);
    CHECK(r.route[MCSTAT_CHECK_ROUTE_RECIPROCITY].state == MCSTAT_CHECK_STATE_INVALID);
}

/* fuzz_checks: pdf() finite but near DBL_MAX (valid by the contract: the
 * callbacks only promise finite values >= 0) made the cubature's integral
 * overflow; the table built from it was NaN, so was the Monte Carlo mass,
 * and MASS "ran" with p-value NaN: the Holm-adjusted NaN never rejected and
 * a density integrating to far above 1 passed.  Oracle: such a pdf() cannot
 * match any sampler (its integral exceeds 1), so MASS rejects. */
static int square_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                         double *pdf)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++) {
        x[2 * k] = u[2 * k], x[2 * k + 1] = u[2 * k + 1];
        weight[k] = 1.0, pdf[k] = 1.0;
    }
    return 0;
}

static int square_pdf_huge(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi, (void)x;
    for (size_t k = 0; k < n; k++)
        out[k] = DBL_MAX / 2;
    return 0;
}

static void test_check_mass_pdf_integral_overflows(void)
{
    mcstat_check_model m = {MCSTAT_CHECK_DOMAIN_SQUARE, 2, MCSTAT_CHECK_WEIGHT_OVER_PDF, 1, NULL, square_sample,
                            square_pdf_huge, NULL, {{0, 0, 0, 0}}};
    mcstat_check_options o;
    mcstat_check_options_init(&o);
    o.routes = 1u << MCSTAT_CHECK_ROUTE_MASS;
    mcstat_check_report r;
    CHECK_INT(mcstat_check_warp(&m, 1000, 1, 0.05, &o, NULL, 0, &r), MCSTAT_OK);
    const mcstat_check_route_result *rr = &r.route[MCSTAT_CHECK_ROUTE_MASS];
    CHECK_INT(rr->state, MCSTAT_CHECK_STATE_RAN);
    CHECK_MSG(rr->p_value >= 0.0 && rr->p_value <= 1.0, "MASS p-value %g", rr->p_value);
    CHECK(rr->reject == 1 && r.reject == 1);
}

int main(void)
{
    test_var_interval_extreme_alpha();
    test_var_interval_quotient_overflow();
    test_f_df1_0001_answers();
    test_chisq_small_df_at_dbl_max();
    test_f_huge_df1_small_df2_monotone();
    test_f_small_df1_large_df2();
    test_t_interval_huge_critical();
    test_merge_extreme_means();
    test_t_null_value_near_overflow();
    test_ks_canner_one_each();
    test_t_far_tail_huge_df();
    test_tiny_df_no_gsl_abort();
    test_t_tiny_m2();
    test_from_bytes_consistency();
    test_check_reciprocity_wi_below_hemisphere();
    test_check_mass_pdf_integral_overflows();
    return h_report("test_fuzz_regressions");
}
