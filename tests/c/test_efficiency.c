/*
 * test_efficiency.c - mcstat_efficiency_test: against an independent 50-digit
 * oracle (tests/data/efficiency_ref.tsv, tools/refgen/make_efficiency_ref.py),
 * its calibration under H0 and its power on simulated data (fixed seeds),
 * the generic result functions, bad input and extreme magnitudes.
 */
#include "harness.h"
#include "mcstat.h"
#include "ref_tsv.h"

#include <float.h>
#include <stdint.h>
#include <string.h>

static uint64_t rng_state = 20261203;
#include "test_rng.h"

static int moments_of(const double *v, size_t n, mcstat_moments *m)
{
    mcstat_moments_init(m);
    return mcstat_moments_add_array(m, v, n);
}

/* ---- against the oracle --------------------------------------------------- */

static void ref_row(char **f, int nf, void *ctx)
{
    int *rows = ctx;
    (*rows)++;
    CHECK_INT(nf, 18);
    if (nf != 18)
        return;
    const char *name = f[0];
    int alt = atoi(f[1]);
    double ratio = strtod(f[2], NULL), alpha = strtod(f[3], NULL);
    size_t n[4];
    double *v[4];
    mcstat_moments m[4];
    for (int k = 0; k < 4; k++) {
        v[k] = tsv_doubles(f[4 + k], &n[k]);
        CHECK_INT(moments_of(v[k], n[k], &m[k]), MCSTAT_OK);
    }
    double want[10];
    for (int k = 0; k < 10; k++)
        want[k] = strtod(f[8 + k], NULL);
    mcstat_result r;
    int st = mcstat_efficiency_test(&m[0], &m[1], &m[2], &m[3], ratio, alt, alpha, &r);
    CHECK_MSG(st == MCSTAT_OK, "%s: status %d", name, st);
    if (st) {
        for (int k = 0; k < 4; k++)
            free(v[k]);
        return;
    }
    /* the moments are accumulated (blocked sums), the oracle's exact: a few
     * ulps in the logs, amplified by |t| in the tail's p-value */
    const double tol = 1e-12;
    CHECK_REL(r.statistic, want[0], tol, "%s statistic", name);
    CHECK_REL(r.df[0], want[1], tol, "%s df", name);
    double lp;
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK_REL(lp, want[3], tol, "%s log p", name);
    /* p itself: relative where it is a normal double, else through its log */
    if (want[2] >= DBL_MIN)
        CHECK_REL(r.p_value, want[2], 1e-11, "%s p", name);
    else
        CHECK_MSG(r.p_value <= 2.0 * want[2] + 1e-320 && r.p_value >= 0.5 * want[2], "%s p %g vs %g", name,
                  r.p_value, want[2]);
    for (int k = 0; k < 2; k++) {
        double w = want[4 + k];
        if (w >= DBL_MIN || isinf(w) || w == 0.0)
            CHECK_REL(r.conf_int[k], w, tol, "%s conf_int[%d]", name, k);
        else /* subnormal: the log's rounding is amplified */
            CHECK_MSG(fabs(r.conf_int[k] - w) <= 1e-3 * w, "%s conf_int[%d]", name, k);
    }
    CHECK_REL(r.estimate[0], want[6], want[6] >= DBL_MIN || want[6] == 0.0 ? tol : 1e-3, "%s estimate", name);
    CHECK_REL(r.eff_var_ratio, want[7], want[7] >= DBL_MIN || want[7] == 0.0 ? tol : 1e-3, "%s var ratio", name);
    CHECK_REL(r.estimate[1], r.eff_var_ratio, 0.0, "%s estimate[1]", name);
    CHECK_REL(r.eff_time_ratio, want[8], tol, "%s time ratio", name);
    CHECK_REL(r.std_error, want[9], tol, "%s std_error", name);
    double se2 = r.eff_se_log_var_x * r.eff_se_log_var_x + r.eff_se_log_var_y * r.eff_se_log_var_y +
                 r.eff_se_log_time_x * r.eff_se_log_time_x + r.eff_se_log_time_y * r.eff_se_log_time_y;
    CHECK_REL(sqrt(se2), r.std_error, 1e-15, "%s the parts' errors add up", name);
    CHECK_INT(r.test, MCSTAT_TEST_EFFICIENCY);
    CHECK_INT(r.method, MCSTAT_METHOD_ASYMPTOTIC);
    CHECK_INT(r.eff_batches_x, (long)n[2]);
    CHECK_INT(r.eff_batches_y, (long)n[3]);
    CHECK(r.n[0] == n[0] && r.n[1] == n[1]);
    CHECK(r.null_value == ratio && r.alpha == alpha && r.alternative == alt);
    CHECK_INT(r.reject, want[2] <= alpha);
    CHECK_INT(r.decision, !r.reject ? MCSTAT_DECISION_EQUAL : want[0] < 0 ? MCSTAT_DECISION_LESS
                                                                         : MCSTAT_DECISION_GREATER);
    /* the interval at the result's own level, and at another */
    double ci[2];
    CHECK_INT(mcstat_result_conf_int(&r, 1.0 - alpha, ci), MCSTAT_OK);
    for (int k = 0; k < 2; k++)
        CHECK_REL(ci[k], r.conf_int[k], ci[k] >= DBL_MIN || ci[k] == 0.0 || isinf(ci[k]) ? 1e-13 : 1e-3,
                  "%s conf_int at 1 - alpha, end %d", name, k);
    CHECK_INT(mcstat_result_conf_int(&r, 0.5, ci), MCSTAT_OK);
    CHECK(ci[0] <= ci[1]);
    /* the block */
    char buf[2048];
    size_t len;
    CHECK_INT(mcstat_result_format(&r, "new", "old", buf, sizeof buf, &len), MCSTAT_OK);
    CHECK(strstr(buf, "\tEfficiency ratio test (delta method)\n") != NULL);
    CHECK(strstr(buf, "data:  new and old\n") != NULL);
    CHECK(strstr(buf, "true ratio of efficiencies is") != NULL);
    CHECK(strstr(buf, "ratio of efficiencies") != NULL && strstr(buf, "decision at alpha") != NULL);
    for (int k = 0; k < 4; k++)
        free(v[k]);
}

static void test_reference(void)
{
    int rows = 0;
    int n = tsv_read(MCSTAT_TEST_DATA_DIR "/efficiency_ref.tsv", ref_row, &rows);
    CHECK_MSG(n >= 6, "efficiency_ref.tsv: %d rows", n);
}

/* ---- a block, exactly -------------------------------------------------------- */

static void test_block(void)
{
    double x[] = {1, 2, 3, 4, 6}, y[] = {0, 0, 5, 9, 1, 2}, tx[] = {1.0, 1.1, 0.9}, ty[] = {2.0, 2.0};
    mcstat_moments mx, my, mtx, mty;
    moments_of(x, 5, &mx);
    moments_of(y, 6, &my);
    moments_of(tx, 3, &mtx);
    moments_of(ty, 2, &mty);
    mcstat_result r;
    CHECK_INT(mcstat_efficiency_test(&mx, &my, &mtx, &mty, 1.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    char buf[1024];
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_OK);
    /* s_x^2 = 3.7, s_y^2 = 12.5667, times 1 and 2: rho = 2 s_y^2 / s_x^2; the
     * numbers are make_efficiency_ref.py's reference() on these data */
    const char *want = "\n\tEfficiency ratio test (delta method)\n\n"
                       "data:  x and y\n"
                       "t = 2.4535, df = 9.0122, p-value = 0.03651\n"
                       "timed batches: 3 of x, 2 of y\n"
                       "alternative hypothesis: true ratio of efficiencies is not equal to 1\n"
                       "95 percent confidence interval:\n"
                       "  1.161611 39.722466\n"
                       "sample estimates:\n"
                       "ratio of efficiencies ratio of variances ratio of times \n"
                       "             6.792793           3.396396       2.000000 \n"
                       "decision at alpha = 0.05: greater\n\n";
    CHECK_MSG(strcmp(buf, want) == 0, "block:\n%s", buf);
    CHECK_REL(r.estimate[0], 2.0 * (377.0 / 30.0) / 3.7, 1e-14, "rho_hat");
    CHECK_REL(r.std_error, 0.7808566886, 1e-9, "se");
    size_t len = 0;
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, 10, &len), MCSTAT_EBUFSIZE);
    CHECK(len == strlen(want) && strlen(buf) == 9);
}

/* ---- calibration and power ------------------------------------------------- */

enum { EXPONENTIAL, MOSTLY_ZERO };

static void draw(int kind, double scale, double *v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double u = unif();
        /* mostly zeros: 1% exponential values (u / 0.01 is again uniform) */
        v[i] = kind == EXPONENTIAL ? -scale * log(u) : u < 0.01 ? -scale * log(u / 0.01) : 0.0;
    }
}

/* Rejections among reps tests of samples of n values whose variances differ
 * by var_ratio = var_y / var_x, with k timed batches of equal mean time and
 * lognormal noise of log-sd noise. */
static int rejections(int kind, size_t n, size_t k, double noise, double var_ratio, int alternative, int reps,
                      double *v)
{
    int rej = 0;
    for (int i = 0; i < reps; i++) {
        mcstat_moments m[4];
        draw(kind, 1.0, v, n);
        moments_of(v, n, &m[0]);
        draw(kind, sqrt(var_ratio), v, n);
        moments_of(v, n, &m[1]);
        for (int j = 2; j < 4; j++) {
            mcstat_moments_init(&m[j]);
            for (size_t b = 0; b < k; b++)
                mcstat_moments_add(&m[j], 1e-6 * exp(noise * normal()));
        }
        mcstat_result r;
        int st = mcstat_efficiency_test(&m[0], &m[1], &m[2], &m[3], 1.0, alternative, 0.05, &r);
        if (st == MCSTAT_EDEGENERATE) /* a mostly-zero sample of only zeros: redraw */
        {
            i--;
            continue;
        }
        CHECK_INT(st, MCSTAT_OK);
        rej += r.reject;
    }
    return rej;
}

static void test_calibration(void)
{
    rng_state = 20261203; /* a fixed seed, whatever ran before: the rates are the same every run */
    const int reps = (int)h_scaled(2000, 200);
    /* 2000 tests at alpha = 0.05: mean 100, sd 9.7; 3.5 sd either side */
    const double mean = 0.05 * reps, sd = sqrt(reps * 0.05 * 0.95);
    const int lo = (int)floor(mean - 3.5 * sd), hi = (int)ceil(mean + 3.5 * sd);
    static double v[50000];
    struct {
        int kind;
        size_t n, k;
        double noise;
        const char *what;
    } c[] = {
        {EXPONENTIAL, 1000, 10, 0.1, "exponential, n = 1000, 10 batches at 10% noise"},
        {EXPONENTIAL, 1000, 5, 0.3, "exponential, n = 1000, 5 batches at 30% noise"},
        {MOSTLY_ZERO, 50000, 10, 0.1, "99% zeros, n = 50000 (~500 non-zero), 10 batches"},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        int rej = rejections(c[i].kind, c[i].n, c[i].k, c[i].noise, 1.0, MCSTAT_TWO_SIDED, reps, v);
        printf("H0, %s: %d / %d rejected (%.4f)\n", c[i].what, rej, reps, (double)rej / reps);
        CHECK_MSG(rej >= lo && rej <= hi, "%s: %d rejections of %d, want [%d, %d]", c[i].what, rej, reps, lo, hi);
    }
    /* few non-zero values: the sample kurtosis is too small, the test
     * anti-conservative; mcstat.h promises at most twice alpha */
    int rej = rejections(MOSTLY_ZERO, 2000, 10, 0.1, 1.0, MCSTAT_TWO_SIDED, reps, v);
    printf("H0, 99%% zeros, n = 2000 (~20 non-zero): %d / %d rejected (%.4f), at most 2 alpha\n", rej, reps,
           (double)rej / reps);
    const int hi2 = (int)ceil(0.1 * reps + 3.5 * sqrt(reps * 0.1 * 0.9));
    CHECK_MSG(rej <= hi2, "~20 non-zero: %d rejections of %d, above twice alpha's bound %d", rej, reps, hi2);
    /* one-sided: half the two-sided level in each direction */
    rej = rejections(EXPONENTIAL, 1000, 10, 0.1, 1.0, MCSTAT_GREATER, reps, v);
    printf("H0 greater, exponential, n = 1000: %d / %d rejected\n", rej, reps);
    CHECK_MSG(rej >= lo && rej <= hi, "greater: %d rejections", rej);

    /* power: x's variance 1.5 times smaller (rho = 1.5) */
    const int preps = (int)h_scaled(500, 100);
    rej = rejections(EXPONENTIAL, 1000, 10, 0.1, 1.5, MCSTAT_TWO_SIDED, preps, v);
    printf("rho = 1.5, exponential, n = 1000: power %.3f\n", (double)rej / preps);
    CHECK_MSG(rej > 0.6 * preps, "power %d / %d", rej, preps);
    rej = rejections(MOSTLY_ZERO, 50000, 10, 0.1, 2.0, MCSTAT_GREATER, preps, v);
    printf("rho = 2, 99%% zeros, n = 50000, greater: power %.3f\n", (double)rej / preps);
    CHECK_MSG(rej > 0.6 * preps, "power %d / %d", rej, preps);
    /* the wrong direction rejects almost never */
    rej = rejections(EXPONENTIAL, 1000, 10, 0.1, 1.5, MCSTAT_LESS, preps, v);
    CHECK_MSG(rej <= 2, "less when x is better: %d rejections", rej);
}

/* ---- bad input -------------------------------------------------------------- */

static void test_bad_input(void)
{
    double x[] = {1, 2, 3, 4}, t[] = {1, 1.2, 0.8};
    mcstat_moments m, tm, one, empty, bad, zero_t, neg_t, const_x, single_t;
    moments_of(x, 4, &m);
    moments_of(t, 3, &tm);
    moments_of(x, 1, &one);
    mcstat_moments_init(&empty);
    bad = m; /* not an accumulator: no version */
    bad.version = 0;
    double z[] = {0, 0, 0}, neg[] = {1, -0.5, 2}, c[] = {5, 5, 5, 5};
    moments_of(z, 3, &zero_t);
    moments_of(neg, 3, &neg_t);
    moments_of(c, 4, &const_x);
    moments_of(t, 1, &single_t);
    mcstat_result r, keep;
    memset(&keep, 0x5a, sizeof keep);
    r = keep;
#define ST(call, want)                                                 \
    do {                                                               \
        CHECK_INT(call, want);                                         \
        CHECK(memcmp(&r, &keep, sizeof r) == 0); /* out untouched */   \
    } while (0)
    ST(mcstat_efficiency_test(NULL, &m, &tm, &tm, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, NULL, &tm, &tm, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, NULL, &tm, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, NULL, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_efficiency_test(&m, &m, &tm, &tm, 1, 0, 0.05, NULL), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, 1, 0, 0.0, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, 1, 0, 1.0, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, 1, 0, NAN, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, 0.0, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, -1.0, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, INFINITY, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, NAN, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, 1, 3, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &tm, &tm, 1, -1, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&bad, &m, &tm, &tm, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&m, &m, &bad, &tm, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    ST(mcstat_efficiency_test(&one, &m, &tm, &tm, 1, 0, 0.05, &r), MCSTAT_ETOOFEW);
    ST(mcstat_efficiency_test(&m, &empty, &tm, &tm, 1, 0, 0.05, &r), MCSTAT_ETOOFEW);
    ST(mcstat_efficiency_test(&m, &m, &single_t, &tm, 1, 0, 0.05, &r), MCSTAT_ETOOFEW);
    ST(mcstat_efficiency_test(&m, &m, &tm, &empty, 1, 0, 0.05, &r), MCSTAT_ETOOFEW);
    ST(mcstat_efficiency_test(&const_x, &m, &tm, &tm, 1, 0, 0.05, &r), MCSTAT_EDEGENERATE);
    ST(mcstat_efficiency_test(&m, &const_x, &tm, &tm, 1, 0, 0.05, &r), MCSTAT_EDEGENERATE);
    ST(mcstat_efficiency_test(&m, &m, &zero_t, &tm, 1, 0, 0.05, &r), MCSTAT_EDEGENERATE);
    ST(mcstat_efficiency_test(&m, &m, &tm, &neg_t, 1, 0, 0.05, &r), MCSTAT_EINVAL);
#undef ST
    /* equal times (an exact cost) are accepted and add no error */
    double ct[] = {2.5, 2.5};
    mcstat_moments cm;
    moments_of(ct, 2, &cm);
    CHECK_INT(mcstat_efficiency_test(&m, &m, &cm, &cm, 1, 0, 0.05, &r), MCSTAT_OK);
    CHECK(r.eff_se_log_time_x == 0.0 && r.eff_se_log_time_y == 0.0 && r.eff_time_ratio == 1.0);
    CHECK(r.estimate[0] == 1.0 && r.statistic == 0.0 && r.p_value == 1.0 && !r.reject);
    /* one batch timed as 0 among others is a coarse timer, not an error */
    double t0[] = {0.0, 1e-6, 2e-6};
    moments_of(t0, 3, &cm);
    CHECK_INT(mcstat_efficiency_test(&m, &m, &cm, &tm, 1, 0, 0.05, &r), MCSTAT_OK);
}

/* ---- extremes ---------------------------------------------------------------- */

static int finite_result(const mcstat_result *r)
{
    return isfinite(r->statistic) && isfinite(r->df[0]) && r->df[0] > 0 && r->p_value >= 0 && r->p_value <= 1 &&
           !isnan(r->conf_int[0]) && !isnan(r->conf_int[1]) && r->conf_int[0] <= r->conf_int[1] &&
           !isnan(r->estimate[0]) && isfinite(r->std_error) && r->std_error > 0;
}

static void test_extremes(void)
{
    mcstat_moments a, b, ta, tb;
    double t[] = {1e-9, 1.1e-9, 0.9e-9};
    moments_of(t, 3, &ta);
    moments_of(t, 3, &tb);
    mcstat_result r;
    /* variances near the ends of the doubles: 1e300 against 1e-300 */
    CHECK_INT(mcstat_moments_from_summary(100, 0.0, 99.0 * 1e300, &a), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_summary(100, 0.0, 99.0 * 1e-300, &b), MCSTAT_OK);
    CHECK_INT(mcstat_efficiency_test(&a, &b, &ta, &tb, 1, 0, 0.05, &r), MCSTAT_OK);
    CHECK(finite_result(&r) || (r.estimate[0] == 0.0 && r.conf_int[1] == 0.0 && isfinite(r.statistic)));
    CHECK(r.estimate[0] == 0.0 && r.decision == MCSTAT_DECISION_LESS); /* 1e-600 underflows: 0, not NaN */
    double lp;
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    double lt; /* the time parts' 2 df each dominate: log p -41, p itself 1e-18 */
    CHECK_INT(mcstat_t_logcdf(r.statistic, r.df[0], 0, &lt), MCSTAT_OK);
    CHECK_REL(lp, M_LN2 + lt, 1e-14, "log p beyond the doubles' ratio");
    CHECK(lp < -30);
    CHECK_INT(mcstat_efficiency_test(&b, &a, &ta, &tb, 1, 0, 0.05, &r), MCSTAT_OK);
    CHECK(isinf(r.estimate[0]) && r.decision == MCSTAT_DECISION_GREATER && isfinite(r.statistic));
    /* the largest variance: M2 = DBL_MAX */
    CHECK_INT(mcstat_moments_from_summary(10, 1.0, DBL_MAX, &a), MCSTAT_OK);
    CHECK_INT(mcstat_efficiency_test(&a, &a, &ta, &tb, 1, 0, 0.05, &r), MCSTAT_OK);
    CHECK(finite_result(&r) && r.estimate[0] == 1.0);
    /* the count near its end: 2^64 - 1 values (a two-point sample: beta2 = 1,
     * Var(log s^2) = 2/(n(n-1)), which 1 - (n-3)/(n-1) would round to 0) */
    CHECK_INT(mcstat_moments_from_summary(UINT64_MAX, 0.5, 0.25 * 0x1p64, &a), MCSTAT_OK);
    CHECK_INT(mcstat_moments_from_summary(UINT64_MAX, 0.5, 0.26 * 0x1p64, &b), MCSTAT_OK);
    CHECK_INT(mcstat_efficiency_test(&a, &b, &ta, &tb, 1, 0, 0.05, &r), MCSTAT_OK);
    CHECK(finite_result(&r));
    CHECK_REL(r.eff_se_log_var_x, sqrt(2.0) * 0x1p-64, 1e-12, "two-point sample at n = 2^64 - 1");
    /* and with equal times the variance parts alone: a huge df, capped */
    double ct[] = {1.0, 1.0};
    moments_of(ct, 2, &ta);
    CHECK_INT(mcstat_efficiency_test(&a, &b, &ta, &ta, 1, 0, 0.05, &r), MCSTAT_OK);
    CHECK(finite_result(&r) && r.df[0] <= 1e15 && r.reject);
    /* times near the ends of the doubles */
    double tt[] = {1e-310, 2e-310, 1.5e-310}, th[] = {1e300, 1.2e300};
    moments_of(tt, 3, &ta);
    moments_of(th, 2, &tb);
    CHECK_INT(mcstat_moments_from_summary(50, 0.0, 49.0, &a), MCSTAT_OK);
    CHECK_INT(mcstat_efficiency_test(&a, &a, &ta, &tb, 1, 0, 0.05, &r), MCSTAT_OK);
    CHECK(isfinite(r.statistic) && isinf(r.estimate[0]) && r.decision == MCSTAT_DECISION_GREATER);
    CHECK(isfinite(r.eff_se_log_time_x) && isfinite(r.eff_se_log_time_y));
}

/* ---- random extremes: never NaN with status OK --------------------------------
 * Accumulators of random summaries and data across the doubles' range, times
 * with zeros and negatives among them: every status is one of those
 * documented, and every OK result is whole (no NaN, p in [0, 1], ordered
 * interval and critical values, reject == p <= alpha, the interval's ends on
 * the right side of the null value, the block and the log p-value). */
static double any_magnitude(void)
{
    return ldexp(0.5 + unif(), (int)(unif() * 1960.0) - 980);
}

static void random_moments(mcstat_moments *m, int positive)
{
    double v[8];
    if (unif() < 1.0 / 3.0) { /* a summary at any n, mean and spread */
        uint64_t n = unif() < 0.2 ? UINT64_MAX - (uint64_t)(unif() * 1000.0) : 2 + (uint64_t)(unif() * 1e6);
        if (mcstat_moments_from_summary(n, (unif() < 0.5 ? -1 : 1) * any_magnitude(),
                                        unif() < 0.1 ? 0.0 : any_magnitude(), m) == MCSTAT_OK)
            return;
    }
    /* a few values at one magnitude, some of them zeros (also where the
     * summary overflowed) */
    double scale = any_magnitude();
    size_t k = 1 + (size_t)(unif() * 8.0);
    for (size_t i = 0; i < k; i++)
        v[i] = unif() < 0.3 ? 0.0 : (positive || unif() < 0.8 ? 1.0 : -1.0) * scale * unif();
    mcstat_moments_init(m);
    mcstat_moments_add_array(m, v, k);
}

static void test_random_extremes(void)
{
    const int cases = (int)h_scaled(100000, 2000);
    int ok = 0, bad = 0;
    for (int i = 0; i < cases; i++) {
        mcstat_moments m[4];
        for (int k = 0; k < 4; k++)
            random_moments(&m[k], k >= 2 && unif() < 0.8); /* times: mostly >= 0 */
        static const double alphas[] = {0.05, 1e-300, 0.5, 0.999999, 1e-12};
        double alpha = alphas[i % 5], ratio = unif() < 0.5 ? 1.0 : any_magnitude();
        int alt = i % 3;
        mcstat_result r;
        int st = mcstat_efficiency_test(&m[0], &m[1], &m[2], &m[3], ratio, alt, alpha, &r);
        if (st != MCSTAT_OK) {
            bad += !(st == MCSTAT_EINVAL || st == MCSTAT_ETOOFEW || st == MCSTAT_EDEGENERATE);
            CHECK_MSG(st == MCSTAT_EINVAL || st == MCSTAT_ETOOFEW || st == MCSTAT_EDEGENERATE, "case %d: status %d",
                      i, st);
            continue;
        }
        ok++;
        int whole = !isnan(r.statistic) && r.df[0] > 0 && r.df[0] <= 1e15 && r.p_value >= 0 && r.p_value <= 1 &&
                    !isnan(r.conf_int[0]) && !isnan(r.conf_int[1]) && r.conf_int[0] <= r.conf_int[1] &&
                    r.conf_int[0] >= 0 && !isnan(r.estimate[0]) && !isnan(r.estimate[1]) && r.std_error > 0 &&
                    isfinite(r.std_error) && !isnan(r.critical[0]) && !isnan(r.critical[1]) &&
                    r.critical[0] <= r.critical[1] && r.reject == (r.p_value <= alpha) &&
                    !isnan(r.eff_var_ratio) && !isnan(r.eff_time_ratio) && !isnan(r.eff_se_log_var_x) &&
                    !isnan(r.eff_se_log_var_y) && !isnan(r.eff_se_log_time_x) && !isnan(r.eff_se_log_time_y);
        CHECK_MSG(whole, "case %d: t %g df %g p %g ci [%g, %g] est %g se %g", i, r.statistic, r.df[0], r.p_value,
                  r.conf_int[0], r.conf_int[1], r.estimate[0], r.std_error);
        /* the interval holds the estimate (where both are doubles, and at
         * levels 1 - alpha >= 1/2: at alpha near 1 it need not) */
        if (r.estimate[0] > 0 && isfinite(r.estimate[0]) && alpha <= 0.5)
            CHECK_MSG(r.conf_int[0] <= r.estimate[0] * (1 + 1e-12) && r.estimate[0] <= r.conf_int[1] * (1 + 1e-12),
                      "case %d: estimate %g outside [%g, %g]", i, r.estimate[0], r.conf_int[0], r.conf_int[1]);
        double lp, ci[2];
        CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
        CHECK(!isnan(lp) && lp <= 0);
        CHECK_INT(mcstat_result_conf_int(&r, 0.9, ci), MCSTAT_OK);
        CHECK(!isnan(ci[0]) && !isnan(ci[1]) && ci[0] <= ci[1]);
        char buf[1024];
        CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_OK);
        CHECK(strstr(buf, "nan") == NULL && strstr(buf, "NaN") == NULL);
    }
    printf("random extremes: %d of %d cases OK, %d unexpected statuses\n", ok, cases, bad);
    CHECK_MSG(ok > cases / 20, "only %d OK results", ok);
}

int main(void)
{
    test_random_extremes();
    test_reference();
    test_block();
    test_bad_input();
    test_extremes();
    test_calibration();
    printf("%d checks, %d failures\n", h_checks, h_failures);
    return h_failures != 0;
}
