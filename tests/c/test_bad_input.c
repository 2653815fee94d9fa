/*
 * test_bad_input.c - every public function gets every kind of bad input and
 * must answer with a status (or NaN/NULL where it returns a value), never
 * crash, and never reach GSL's error handler: GSL's default handler, which
 * aborts, stays installed for the whole run, so a single slip kills the test.
 */
#include "harness.h"
#include "mcstat.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>

static const double good[5] = {1.0, 2.5, 3.0, 4.5, 2.0};
static const double good2[6] = {0.5, 1.5, 1.0, 2.0, 0.75, 3.0};

typedef int (*array_test)(const double *x, size_t nx, const double *y, size_t ny, double nullv, int alt,
                          double alpha, mcstat_result *out);

static int t1(const double *x, size_t nx, const double *y, size_t ny, double v, int alt, double a, mcstat_result *o)
{
    (void)y, (void)ny;
    return mcstat_t_test_1(x, nx, v, alt, a, o);
}
static int t2(const double *x, size_t nx, const double *y, size_t ny, double v, int alt, double a, mcstat_result *o)
{
    return mcstat_t_test_2(x, nx, y, ny, v, alt, a, o);
}
static int v1(const double *x, size_t nx, const double *y, size_t ny, double v, int alt, double a, mcstat_result *o)
{
    (void)y, (void)ny;
    return mcstat_var_test_1(x, nx, v, alt, a, o);
}
static int v2(const double *x, size_t nx, const double *y, size_t ny, double v, int alt, double a, mcstat_result *o)
{
    return mcstat_var_test_2(x, nx, y, ny, v, alt, a, o);
}

static void test_array_tests(void)
{
    struct {
        array_test f;
        const char *name;
        double nullv;
        int positive_null, two_sample;
    } tests[] = {{t1, "t1", 0.0, 0, 0}, {t2, "t2", 0.0, 0, 1}, {v1, "v1", 1.0, 1, 0}, {v2, "v2", 1.0, 1, 1}};
    for (int k = 0; k < 4; k++) {
        array_test f = tests[k].f;
        double nv = tests[k].nullv;
        mcstat_result r, untouched;
        memset(&r, 0xAB, sizeof r);
        untouched = r;
        CHECK_INT(f(good, 5, good2, 6, nv, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
        memcpy(&r, &untouched, sizeof r);
        /* NULL pointers */
        CHECK_INT(f(NULL, 5, good2, 6, nv, 0, 0.05, &r), MCSTAT_EINVAL);
        CHECK_INT(f(good, 5, good2, 6, nv, 0, 0.05, NULL), MCSTAT_EINVAL);
        if (tests[k].two_sample)
            CHECK_INT(f(good, 5, NULL, 6, nv, 0, 0.05, &r), MCSTAT_EINVAL);
        /* alternatives */
        const int bad_alt[] = {-1, 3, 99, -2147483647 - 1};
        for (int i = 0; i < 4; i++)
            CHECK_INT(f(good, 5, good2, 6, nv, bad_alt[i], 0.05, &r), MCSTAT_EINVAL);
        /* alpha outside (0, 1) */
        const double bad_alpha[] = {0.0, 1.0, -0.1, 1.5, NAN, INFINITY, -INFINITY};
        for (int i = 0; i < 7; i++)
            CHECK_INT(f(good, 5, good2, 6, nv, 0, bad_alpha[i], &r), MCSTAT_EINVAL);
        /* null values */
        const double bad_null[] = {NAN, INFINITY, -INFINITY, 0.0, -1.0};
        for (int i = 0; i < (tests[k].positive_null ? 5 : 3); i++)
            CHECK_MSG(f(good, 5, good2, 6, bad_null[i], 0, 0.05, &r) == MCSTAT_EINVAL, "%s null %g", tests[k].name,
                      bad_null[i]);
        /* sizes */
        CHECK_INT(f(good, 0, good2, 6, nv, 0, 0.05, &r), MCSTAT_ETOOFEW);
        CHECK_INT(f(good, 1, good2, 6, nv, 0, 0.05, &r), MCSTAT_ETOOFEW);
        if (tests[k].two_sample) {
            CHECK_INT(f(good, 5, good2, 1, nv, 0, 0.05, &r), MCSTAT_ETOOFEW);
            CHECK_INT(f(good, 5, good2, 0, nv, 0, 0.05, &r), MCSTAT_ETOOFEW);
        }
        /* non-finite data, in either sample */
        const double nonfinite[] = {NAN, INFINITY, -INFINITY};
        for (int i = 0; i < 3; i++) {
            double bad[5];
            memcpy(bad, good, sizeof bad);
            bad[3] = nonfinite[i];
            CHECK_INT(f(bad, 5, good2, 6, nv, 0, 0.05, &r), MCSTAT_ENONFINITE);
            if (tests[k].two_sample)
                CHECK_INT(f(good2, 6, bad, 5, nv, 0, 0.05, &r), MCSTAT_ENONFINITE);
        }
        /* constant data */
        const double same[4] = {7.0, 7.0, 7.0, 7.0};
        int st = f(same, 4, same, 4, nv, 0, 0.05, &r);
        CHECK_MSG(st == MCSTAT_EDEGENERATE, "%s constant: %d", tests[k].name, st);
        /* nothing was written on failure */
        CHECK(!memcmp(&r, &untouched, sizeof r));
    }
}

static void test_moments_api(void)
{
    mcstat_moments m, garbage;
    mcstat_moments_init(&m);
    mcstat_moments_add_array(&m, good, 5);
    memset(&garbage, 0x5A, sizeof garbage); /* n != 0, version wrong */
    double v = 1.0;
    size_t k;
    CHECK_INT(mcstat_moments_init(NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add(NULL, 1.0), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add(&garbage, 1.0), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_array(NULL, &v, 1), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_array(&m, NULL, 3), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_array(&m, NULL, 0), MCSTAT_OK);
    CHECK_INT(mcstat_moments_add_array_omit_nan(&m, NULL, 3, &k), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_add_array_omit_nan(NULL, &v, 1, &k), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_merge(NULL, &m), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_merge(&m, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_merge(&m, &garbage), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_merge(&garbage, &m), MCSTAT_EINVAL);
    CHECK(isnan(mcstat_moments_mean(NULL)) && isnan(mcstat_moments_var(NULL)) && isnan(mcstat_moments_sd(NULL)));
    CHECK(isnan(mcstat_moments_skewness(NULL)) && isnan(mcstat_moments_kurtosis(NULL)));
    CHECK(isnan(mcstat_moments_mean(&garbage)) && isnan(mcstat_moments_var(&garbage)));
    mcstat_result r;
    CHECK_INT(mcstat_t_test_1_moments(NULL, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_1_moments(&garbage, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_moments(&m, &garbage, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_var_test_1_moments(&garbage, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_var_test_2_moments(&garbage, &m, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_moments(&m, NULL, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    /* a hand-made accumulator with non-finite fields */
    mcstat_moments bad = m;
    bad.m2 = NAN;
    CHECK_INT(mcstat_t_test_1_moments(&bad, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    bad = m;
    bad.mean = INFINITY;
    CHECK_INT(mcstat_var_test_1_moments(&bad, 1, 0, 0.05, &r), MCSTAT_EINVAL);
    /* bytes */
    unsigned char buf[MCSTAT_MOMENTS_BYTES];
    CHECK_INT(mcstat_moments_to_bytes(NULL, buf, sizeof buf), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_to_bytes(&m, NULL, sizeof buf), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_to_bytes(&garbage, buf, sizeof buf), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_from_bytes(NULL, sizeof buf, &m), MCSTAT_EINVAL);
    CHECK_INT(mcstat_moments_from_bytes(buf, sizeof buf, NULL), MCSTAT_EINVAL);
    memset(buf, 0, sizeof buf);
    CHECK_INT(mcstat_moments_from_bytes(buf, sizeof buf, &m), MCSTAT_ECORRUPT);
}

static void test_misc_api(void)
{
    int alt = 42;
    CHECK_INT(mcstat_alternative_parse(NULL, &alt), MCSTAT_EINVAL);
    CHECK_INT(mcstat_alternative_parse("less", NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_alternative_parse("lesser", &alt), MCSTAT_EINVAL);
    CHECK_INT(mcstat_alternative_parse("", &alt), MCSTAT_EINVAL);
    CHECK_INT(alt, 42);
    CHECK_INT(mcstat_alternative_parse("two.sided", &alt), MCSTAT_OK);
    CHECK_INT(alt, MCSTAT_TWO_SIDED);
    CHECK(mcstat_alternative_name(3) == NULL && mcstat_alternative_name(-1) == NULL);
    CHECK(mcstat_decision_name(2) == NULL && mcstat_decision_name(-2) == NULL);
    const int codes[] = {-1, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 1000, -2147483647 - 1};
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++)
        CHECK(mcstat_strerror(codes[i]) != NULL && strlen(mcstat_strerror(codes[i])) > 5);
    CHECK(strcmp(mcstat_strerror(MCSTAT_EINVAL), mcstat_strerror(MCSTAT_EDEGENERATE)) != 0);
    /* the formatter */
    mcstat_result r;
    mcstat_t_test_1(good, 5, 0.0, 0, 0.05, &r);
    char buf[1024];
    CHECK_INT(mcstat_result_format(NULL, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, NULL, 10, NULL), MCSTAT_EINVAL);
    mcstat_result bad = r;
    bad.test = 0;
    CHECK_INT(mcstat_result_format(&bad, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_EINVAL);
    bad = r;
    bad.alternative = 7;
    CHECK_INT(mcstat_result_format(&bad, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_EINVAL);
    bad = r;
    bad.statistic = NAN;
    bad.p_value = NAN;
    bad.decision = 5; /* garbage in a plain struct must not crash the printer */
    int st = mcstat_result_format(&bad, NULL, NULL, buf, sizeof buf, NULL);
    CHECK(st == MCSTAT_OK || st == MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, 0, NULL), MCSTAT_EBUFSIZE);
}

static void test_distributions(void)
{
    double out = 12345.0;
    const double bad_df[] = {0.0, -1.0, NAN, INFINITY, -INFINITY};
    for (int i = 0; i < 5; i++) {
        double d = bad_df[i];
        CHECK_INT(mcstat_t_cdf(1.0, d, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_t_logcdf(1.0, d, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_t_quantile(0.5, d, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_chisq_cdf(1.0, d, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_chisq_logcdf(1.0, d, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_chisq_quantile(0.5, d, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_f_cdf(1.0, d, 3, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_f_cdf(1.0, 3, d, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_f_logcdf(1.0, d, 3, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_f_quantile(0.5, 3, d, 0, &out), MCSTAT_EINVAL);
    }
    CHECK_INT(mcstat_t_cdf(NAN, 3, 0, &out), MCSTAT_EINVAL);
    CHECK_INT(mcstat_chisq_cdf(NAN, 3, 1, &out), MCSTAT_EINVAL);
    CHECK_INT(mcstat_f_cdf(NAN, 3, 3, 1, &out), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_cdf(1.0, 3, 2, &out), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_cdf(1.0, 3, -1, &out), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_cdf(1.0, 3, 0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_chisq_quantile(0.5, 3, 0, NULL), MCSTAT_EINVAL);
    const double bad_p[] = {-0.1, 1.1, NAN, INFINITY, -INFINITY};
    for (int i = 0; i < 5; i++) {
        CHECK_INT(mcstat_t_quantile(bad_p[i], 3, 0, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_chisq_quantile(bad_p[i], 3, 1, &out), MCSTAT_EINVAL);
        CHECK_INT(mcstat_f_quantile(bad_p[i], 3, 4, 1, &out), MCSTAT_EINVAL);
    }
    CHECK(out == 12345.0); /* untouched by failures */
}

/* Random extreme arguments: every call answers, with a status or a number
 * in range; with GSL's aborting handler installed, reaching it is fatal.
 * 200000 draws, divided by MCSTAT_TEST_SCALE (harness.h) under the
 * sanitizer and valgrind runs. */
static void fuzz_distributions(void)
{
    uint64_t s = 12345;
    int bad = 0;
    const int draws = (int)h_scaled(200000, 5000);
    for (int i = 0; i < draws; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        double u1 = (double)(s >> 11) * 0x1p-53;
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        double u2 = (double)(s >> 11) * 0x1p-53;
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        double u3 = (double)(s >> 11) * 0x1p-53;
        double x = (u1 < 0.5 ? -1 : 1) * pow(10.0, 616.0 * u2 - 308.0);
        double df = pow(10.0, 300.0 * u3 - 20.0), df2 = pow(10.0, 40.0 * u1 - 20.0);
        double p = pow(10.0, -320.0 * u2), out;
        int up = (int)(s >> 63);
        int st[6];
        st[0] = mcstat_t_cdf(x, df, up, &out);
        bad += st[0] == MCSTAT_OK && !(out >= 0.0 && out <= 1.0);
        st[1] = mcstat_chisq_logcdf(fabs(x), df, up, &out);
        bad += st[1] == MCSTAT_OK && !(out <= 0.0);
        st[2] = mcstat_f_cdf(fabs(x), df, df2, up, &out);
        bad += st[2] == MCSTAT_OK && !(out >= 0.0 && out <= 1.0);
        st[3] = mcstat_t_quantile(p, df, up, &out);
        bad += st[3] == MCSTAT_OK && isnan(out);
        st[4] = mcstat_chisq_quantile(p, df2, up, &out);
        bad += st[4] == MCSTAT_OK && !(out >= 0.0);
        st[5] = mcstat_f_quantile(p, df2, df, up, &out);
        bad += st[5] == MCSTAT_OK && !(out >= 0.0);
        for (int k = 0; k < 6; k++)
            bad += st[k] != MCSTAT_OK && st[k] != MCSTAT_ENUMERIC;
    }
    CHECK_MSG(bad == 0, "%d calls returned out-of-range values or unexpected statuses", bad);
}

static void custom_handler(const char *reason, const char *file, int line, int err)
{
    (void)reason, (void)file, (void)line, (void)err;
}

static void test_gsl_handler(void)
{
    /* mcstat never changed the handler: GSL's default (NULL) is still in force */
    gsl_error_handler_t *prev = gsl_set_error_handler(NULL);
    CHECK(prev == NULL);
    /* the opt-in: turns off only the default */
    CHECK_INT(mcstat_gsl_handler_off_if_default(), 1);
    gsl_set_error_handler(custom_handler);
    CHECK_INT(mcstat_gsl_handler_off_if_default(), 0);
    CHECK(gsl_set_error_handler(NULL) == custom_handler);
}

/* The t and variance tests refuse with a reason naming the argument and
 * its value (mcstat_last_error), and a call that succeeds leaves none. */
static void test_reasons(void)
{
    mcstat_result r;
    mcstat_moments m, bad;
    mcstat_moments_init(&m);
    CHECK_INT(mcstat_moments_add_array(&m, good, 5), MCSTAT_OK);
    /* each call's status, and its reason as it stands right after it */
#define REFUSED(call, want)                                                                                       \
    do {                                                                                                          \
        int st_ = (call);                                                                                         \
        CHECK_MSG(st_ == MCSTAT_EINVAL, "%s: status %d", #call, st_);                                             \
        CHECK_MSG(strcmp(mcstat_last_error(), (want)) == 0, "%s: \"%s\", want \"%s\"", #call, mcstat_last_error(), \
                  (want));                                                                                        \
    } while (0)
    REFUSED(mcstat_t_test_1(good, 5, 0.0, MCSTAT_TWO_SIDED, 1.5, &r), "alpha must be in (0, 1), got 1.5");
    REFUSED(mcstat_t_test_1(good, 5, NAN, MCSTAT_TWO_SIDED, 0.05, &r), "mu0 must be finite, got nan");
    REFUSED(mcstat_t_test_1(good, 5, 0.0, 7, 0.05, &r),
            "alternative must be MCSTAT_TWO_SIDED (0), MCSTAT_LESS (1) or MCSTAT_GREATER (2), got 7");
    REFUSED(mcstat_t_test_1(good, 5, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL), "out (the result) is NULL");
    REFUSED(mcstat_t_test_2(good, 5, NULL, 5, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), "y is NULL");
    REFUSED(mcstat_t_test_1_moments(NULL, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), "x is NULL");
    REFUSED(mcstat_t_test_2_pooled(good, 5, good, 5, INFINITY, MCSTAT_LESS, 0.05, &r), "mu0 must be finite, got inf");
    REFUSED(mcstat_t_test_paired(good, good, 5, 0.0, MCSTAT_GREATER, 0.0, &r), "alpha must be in (0, 1), got 0");
    REFUSED(mcstat_var_test_1(good, 5, -1.0, MCSTAT_TWO_SIDED, 0.05, &r), "sigma2 must be finite and > 0, got -1");
    REFUSED(mcstat_var_test_2(good, 5, good, 5, NAN, MCSTAT_TWO_SIDED, 0.05, &r),
            "ratio must be finite and > 0, got nan");
    REFUSED(mcstat_var_test_2_moments(&m, NULL, 1.0, MCSTAT_TWO_SIDED, 0.05, &r), "y is NULL");
    REFUSED(mcstat_var_test_1(good, 5, 1.0, MCSTAT_TWO_SIDED, 0.05, NULL), "out (the result) is NULL");
#undef REFUSED
    /* an accumulator whose fields were changed */
    bad = m;
    bad.m2 = NAN;
    CHECK_INT(mcstat_t_test_1_moments(&bad, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_EINVAL);
    CHECK(strstr(mcstat_last_error(), "accumulator") != NULL);
    /* a call that succeeds leaves no reason behind */
    CHECK_INT(mcstat_t_test_1(good, 5, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK(strcmp(mcstat_last_error(), "") == 0);
    CHECK_INT(mcstat_var_test_1(good, 5, 1.0, MCSTAT_TWO_SIDED, 0.05, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_var_test_2_moments(&m, &m, 1.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK(strcmp(mcstat_last_error(), "") == 0);
}

int main(void)
{
    test_array_tests();
    test_reasons();
    test_moments_api();
    test_misc_api();
    test_distributions();
    fuzz_distributions();
    test_gsl_handler(); /* last: it changes the handler */
    return h_report("test_bad_input");
}
