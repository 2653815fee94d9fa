/*
 * test_gof_chisq.c - Pearson's chi-squared goodness of fit against R's
 * chisq.test (tests/data/ref_chisq.h, from tools/refgen/make_chisq_ref.R),
 * the R-style block, bad input, and calibration and power on multinomial
 * samples.
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "mcstat.h"
#include "ref_chisq.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state = 4242;
#include "test_rng.h"

static void test_reference(void)
{
    for (size_t i = 0; i < REF_NCHISQ; i++) {
        const ref_chisq *c = &REF_CHISQ[i];
        mcstat_gof_options o = MCSTAT_GOF_OPTIONS_INIT;
        o.pool = c->pool;
        o.min_expected = c->min_expected;
        o.n_estimated = c->n_estimated;
        o.expected = c->counts ? MCSTAT_GOF_COUNTS : MCSTAT_GOF_PROBABILITIES;
        mcstat_result r;
        int st = mcstat_gof_chisq_test(c->x, c->p, c->k, &o, 0.05, &r);
        CHECK_MSG(st == MCSTAT_OK, "%s: status %d", c->name, st);
        if (st)
            continue;
        CHECK_REL(r.statistic, c->statistic, 1e-12, "%s", c->name);
        CHECK_REL(r.df[0], c->df, 0.0, "%s", c->name);
        CHECK_INT(MCSTAT_RESULT_CHISQ_CELLS(&r), c->cells);
        if (c->p_value == 0.0) /* R's pchisq underflowed: ours must be as small or 0 */
            CHECK_MSG(r.p_value < 1e-300, "%s: p = %g", c->name, r.p_value);
        else
            CHECK_REL(r.p_value, c->p_value, 1e-11, "%s", c->name);
        CHECK_INT(r.reject, r.p_value <= 0.05);
        CHECK_INT(r.decision, r.reject ? 1 : 0);
        CHECK(r.test == MCSTAT_TEST_CHISQ_GOF && r.alternative == MCSTAT_GREATER);
        /* the critical value agrees with the p-value's decision */
        CHECK_INT(r.statistic > r.critical[1], r.reject);
    }
}

static void test_format(void)
{
    const double x[] = {22, 21, 22, 27, 22, 36}, p[] = {1 / 6., 1 / 6., 1 / 6., 1 / 6., 1 / 6., 1 / 6.};
    mcstat_result r;
    char buf[512];
    CHECK_INT(mcstat_gof_chisq_test(x, p, 6, NULL, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_format(&r, "c(22, 21, 22, 27, 22, 36)", NULL, buf, sizeof buf, NULL), MCSTAT_OK);
    /* R 4.2.2, print(chisq.test(c(22, 21, 22, 27, 22, 36), p = rep(1/6, 6))) */
    const char *want = "\n\tChi-squared test for given probabilities\n\n"
                       "data:  c(22, 21, 22, 27, 22, 36)\n"
                       "X-squared = 6.72, df = 5, p-value = 0.2423\n"
                       "decision at alpha = 0.05: do not reject\n\n";
    CHECK_MSG(strcmp(buf, want) == 0, "got <%s>", buf);
    /* pooled: the extra line */
    const double y[] = {0, 1, 0, 30, 40, 29}, q[] = {0.001, 0.01, 0.009, 0.3, 0.4, 0.28};
    CHECK_INT(mcstat_gof_chisq_test(y, q, 6, NULL, 0.05, &r), MCSTAT_OK);
    CHECK_INT(MCSTAT_RESULT_CHISQ_CELLS(&r), 3);
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK_MSG(strstr(buf, "cells: 6 given, 3 after pooling expected counts below 5") != NULL, "got <%s>", buf);
    size_t len;
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, 10, &len), MCSTAT_EBUFSIZE);
    CHECK(len > 10 && strlen(buf) == 9);
}

static void test_bad_input(void)
{
    const double x[] = {3, 4, 5}, p[] = {0.2, 0.3, 0.5};
    mcstat_result r;
    mcstat_gof_options o = MCSTAT_GOF_OPTIONS_INIT;
    CHECK_INT(mcstat_gof_chisq_test(NULL, p, 3, NULL, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_gof_chisq_test(x, NULL, 3, NULL, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, NULL, 0.05, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, NULL, 0.0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, NULL, 1.0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, NULL, NAN, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_gof_chisq_test(x, p, 1, NULL, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_gof_chisq_test(x, p, 0, NULL, 0.05, &r), MCSTAT_ETOOFEW);
    const double xn[] = {3, NAN, 5}, pi[] = {0.2, INFINITY, 0.5};
    CHECK_INT(mcstat_gof_chisq_test(xn, p, 3, NULL, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_gof_chisq_test(x, pi, 3, NULL, 0.05, &r), MCSTAT_ENONFINITE);
    const double xneg[] = {3, -1, 5}, pneg[] = {0.7, -0.2, 0.5};
    CHECK_INT(mcstat_gof_chisq_test(xneg, p, 3, NULL, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_gof_chisq_test(x, pneg, 3, NULL, 0.05, &r), MCSTAT_EINVAL);
    const double psum[] = {0.2, 0.3, 0.6}; /* sums to 1.1 */
    CHECK_INT(mcstat_gof_chisq_test(x, psum, 3, NULL, 0.05, &r), MCSTAT_EINVAL);
    o.rescale = 1;
    CHECK_INT(mcstat_gof_chisq_test(x, psum, 3, &o, 0.05, &r), MCSTAT_OK);
    /* huge counts: finite statistic; totals that overflow: EINVAL */
    const double big[] = {1e300, 1e300, 1e300}, huge[] = {1e308, 1e308, 1e308};
    CHECK_INT(mcstat_gof_chisq_test(big, p, 3, NULL, 0.05, &r), MCSTAT_OK);
    CHECK(isfinite(r.statistic) && r.p_value == 0.0 && r.reject);
    CHECK_INT(mcstat_gof_chisq_test(huge, p, 3, NULL, 0.05, &r), MCSTAT_EINVAL);
    const double zeros[] = {0, 0, 0};
    CHECK_INT(mcstat_gof_chisq_test(zeros, p, 3, NULL, 0.05, &r), MCSTAT_ETOOFEW);
    /* with the default pooling, 12 observations in 3 cells pool to 2: df 1; one
     * estimated parameter leaves df 0 */
    o = (mcstat_gof_options)MCSTAT_GOF_OPTIONS_INIT;
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, &o, 0.05, &r), MCSTAT_OK);
    CHECK_INT(MCSTAT_RESULT_CHISQ_CELLS(&r), 2);
    o.n_estimated = 1;
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, &o, 0.05, &r), MCSTAT_ETOOFEW);
    o = (mcstat_gof_options)MCSTAT_GOF_OPTIONS_INIT;
    o.pool = 0;
    const double p0[] = {0.5, 0.0, 0.5};
    CHECK_INT(mcstat_gof_chisq_test(x, p0, 3, &o, 0.05, &r), MCSTAT_EINVAL);
    o.pool = 1;
    CHECK_INT(mcstat_gof_chisq_test(x, p0, 3, &o, 0.05, &r), MCSTAT_OK);
    o.size = 4;
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, &o, 0.05, &r), MCSTAT_EINVAL);
    o = (mcstat_gof_options)MCSTAT_GOF_OPTIONS_INIT;
    o.min_expected = -1;
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, &o, 0.05, &r), MCSTAT_EINVAL);
    /* AUTO: probabilities summing to 1 and counts summing to N give the same
     * test; a sum that is neither is refused */
    {
        const double xa[] = {10, 20, 30}, pa[] = {0.2, 0.3, 0.5}, ca[] = {12, 18, 30}, bad[] = {1, 2, 3};
        mcstat_result rp, rc;
        o = (mcstat_gof_options)MCSTAT_GOF_OPTIONS_INIT;
        o.expected = MCSTAT_GOF_AUTO;
        CHECK_INT(mcstat_gof_chisq_test(xa, pa, 3, &o, 0.05, &rp), MCSTAT_OK);
        CHECK_INT(mcstat_gof_chisq_test(xa, ca, 3, &o, 0.05, &rc), MCSTAT_OK);
        CHECK(fabs(rp.statistic - rc.statistic) < 1e-12 && fabs(rp.statistic - (4.0 / 12 + 4.0 / 18)) < 1e-12);
        CHECK_INT(mcstat_gof_chisq_test(xa, bad, 3, &o, 0.05, &rc), MCSTAT_EINVAL);
        o.expected = MCSTAT_GOF_PROBABILITIES;
        CHECK_INT(mcstat_gof_chisq_test(xa, ca, 3, &o, 0.05, &rc), MCSTAT_EINVAL);
        o.expected = MCSTAT_GOF_COUNTS;
        CHECK_INT(mcstat_gof_chisq_test(xa, pa, 3, &o, 0.05, &rc), MCSTAT_EINVAL);
    }
    o = (mcstat_gof_options)MCSTAT_GOF_OPTIONS_INIT;
    o.expected = 7;
    CHECK_INT(mcstat_gof_chisq_test(x, p, 3, &o, 0.05, &r), MCSTAT_EINVAL);
    mcstat_gof_options o2;
    CHECK_INT(mcstat_gof_options_init(&o2), MCSTAT_OK);
    CHECK(memcmp(&o2, &(mcstat_gof_options)MCSTAT_GOF_OPTIONS_INIT, sizeof o2) == 0);
    CHECK_INT(mcstat_gof_options_init_size(NULL, sizeof o2), MCSTAT_EINVAL);
    CHECK(mcstat_sizeof_gof_options() == sizeof(mcstat_gof_options));
    CHECK(mcstat_gof_default_min_expected() == 5.0);
}

/* One multinomial sample of n over k cells with probabilities q (inversion). */
static void multinomial(const double *q, size_t k, int n, double *x)
{
    memset(x, 0, k * sizeof *x);
    for (int j = 0; j < n; j++) {
        double u = unif(), c = 0.0;
        size_t i = 0;
        for (; i + 1 < k; i++) {
            c += q[i];
            if (u < c)
                break;
        }
        x[i] += 1.0;
    }
}

/* Under H0 the rejection rate is alpha to within binomial noise: 2000 runs,
 * alpha = 0.05, bounds 0.05 +- 4.5 sd (sd 0.0049), wide enough for the
 * asymptotic approximation at expected counts >= 5 (pooling does that). */
static void test_calibration_and_power(void)
{
    enum { K = 40, RUNS = 2000 };
    double p[K], q[K], x[K];
    double s = 0.0;
    for (int i = 0; i < K; i++)
        s += (p[i] = (i < 10) ? 0.002 : 1.0 + 0.5 * sin(i));
    for (int i = 0; i < K; i++)
        p[i] /= s;
    int rej = 0, rej_alt = 0;
    for (int r = 0; r < RUNS; r++) {
        mcstat_result res;
        multinomial(p, K, 300, x);
        CHECK_INT(mcstat_gof_chisq_test(x, p, K, NULL, 0.05, &res), MCSTAT_OK);
        rej += res.reject;
        /* the alternative: 25% of the mass moved from cells 20-29 to 30-39 */
        for (int i = 0; i < K; i++)
            q[i] = p[i] * (i >= 20 && i < 30 ? 0.75 : i >= 30 ? 1.25 : 1.0);
        double t = 0.0;
        for (int i = 0; i < K; i++)
            t += q[i];
        for (int i = 0; i < K; i++)
            q[i] /= t;
        multinomial(q, K, 300, x);
        CHECK_INT(mcstat_gof_chisq_test(x, p, K, NULL, 0.05, &res), MCSTAT_OK);
        rej_alt += res.reject;
    }
    double rate = (double)rej / RUNS, rate_alt = (double)rej_alt / RUNS;
    printf("calibration: rate %.4f under H0, %.4f under the shift\n", rate, rate_alt);
    CHECK_MSG(fabs(rate - 0.05) < 4.5 * sqrt(0.05 * 0.95 / RUNS), "rate %g", rate);
    CHECK_MSG(rate_alt > 0.3, "power %g", rate_alt);
}

int main(void)
{
    (void)normal;
    test_reference();
    test_format();
    test_bad_input();
    test_calibration_and_power();
    return h_report("test_gof_chisq");
}
