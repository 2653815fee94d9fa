/*
 * test_tests.c - properties of the four tests: invariance under x -> a + b x,
 * swapping samples, agreement of p-value, critical values and confidence
 * interval, the three-way decision, and calibration under H0 (rejection rate
 * alpha within binomial bounds, CI coverage 1 - alpha) and power.
 */
#include "harness.h"
#include "mcstat.h"

#include <float.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <stdlib.h>

static gsl_rng *rng;

static void normal(double *x, size_t n, double mu, double sd)
{
    for (size_t i = 0; i < n; i++)
        x[i] = mu + gsl_ran_gaussian_ziggurat(rng, sd);
}

/* t is invariant under x -> a + b x with mu0 -> a + b mu0 (b > 0), negated
 * for b < 0; chi-squared and F scale with b^2. */
static void test_affine_invariance(void)
{
    double x[37], y[23], xa[37], ya[23];
    normal(x, 37, 1.0, 2.0);
    normal(y, 23, 0.5, 1.0);
    const double as[] = {0.0, 1e9, -3.5, 1e-7};
    const double bs[] = {1.0, 1e-3, -2.0, 1e150, 1e-150};
    for (size_t i = 0; i < 4; i++) {
        for (size_t j = 0; j < 5; j++) {
            double a = as[i], b = bs[j];
            if (fabs(a) > 0 && fabs(b) < 1e-100)
                continue; /* a would swamp the data */
            for (int k = 0; k < 37; k++)
                xa[k] = a + b * x[k];
            for (int k = 0; k < 23; k++)
                ya[k] = a + b * y[k];
            mcstat_result r0, r1;
            mcstat_t_test_1(x, 37, 0.7, MCSTAT_TWO_SIDED, 0.05, &r0);
            CHECK_INT(mcstat_t_test_1(xa, 37, a + b * 0.7, MCSTAT_TWO_SIDED, 0.05, &r1), MCSTAT_OK);
            /* the transformed data are rounded to ulp(a), i.e. by ulp(a)/|b|
             * in units of the original data (sd 2): allow that */
            double tol = 1e-13 + 10.0 * fabs(a) * DBL_EPSILON / fabs(b);
            CHECK_REL(r1.statistic, b > 0 ? r0.statistic : -r0.statistic, tol, "t a=%g b=%g", a, b);
            CHECK_REL(r1.p_value, r0.p_value, tol * 10, "p a=%g b=%g", a, b);
            mcstat_t_test_2(x, 37, y, 23, 0.0, MCSTAT_TWO_SIDED, 0.05, &r0);
            CHECK_INT(mcstat_t_test_2(xa, 37, ya, 23, 0.0, MCSTAT_TWO_SIDED, 0.05, &r1), MCSTAT_OK);
            CHECK_REL(r1.statistic, b > 0 ? r0.statistic : -r0.statistic, tol, "welch a=%g b=%g", a, b);
            CHECK_REL(r1.df[0], r0.df[0], tol, "welch df a=%g b=%g", a, b);
            mcstat_var_test_2(x, 37, y, 23, 1.0, MCSTAT_TWO_SIDED, 0.05, &r0);
            CHECK_INT(mcstat_var_test_2(xa, 37, ya, 23, 1.0, MCSTAT_TWO_SIDED, 0.05, &r1), MCSTAT_OK);
            CHECK_REL(r1.statistic, r0.statistic, tol, "F a=%g b=%g", a, b);
            if (fabs(b) < 1e100 && fabs(b) > 1e-100) {
                mcstat_var_test_1(x, 37, 3.0, MCSTAT_TWO_SIDED, 0.05, &r0);
                CHECK_INT(mcstat_var_test_1(xa, 37, 3.0 * b * b, MCSTAT_TWO_SIDED, 0.05, &r1), MCSTAT_OK);
                CHECK_REL(r1.statistic, r0.statistic, tol, "chisq a=%g b=%g", a, b);
            }
        }
    }
}

/* Swapping x and y negates Welch's t and keeps its two-sided p; inverts F. */
static void test_swap(void)
{
    double x[41], y[17];
    normal(x, 41, 0.0, 1.0);
    normal(y, 17, 0.4, 3.0);
    mcstat_result a, b;
    mcstat_t_test_2(x, 41, y, 17, 0.0, MCSTAT_TWO_SIDED, 0.05, &a);
    mcstat_t_test_2(y, 17, x, 41, 0.0, MCSTAT_TWO_SIDED, 0.05, &b);
    CHECK(a.statistic == -b.statistic);
    CHECK(a.df[0] == b.df[0]);
    CHECK_REL(a.p_value, b.p_value, 1e-15, "welch swap p");
    CHECK_REL(a.conf_int[0], -b.conf_int[1], 1e-15, "welch swap ci");
    mcstat_t_test_2(x, 41, y, 17, 0.0, MCSTAT_LESS, 0.05, &a);
    mcstat_t_test_2(y, 17, x, 41, 0.0, MCSTAT_GREATER, 0.05, &b);
    CHECK_REL(a.p_value, b.p_value, 1e-15, "welch swap one-sided");
    mcstat_var_test_2(x, 41, y, 17, 1.0, MCSTAT_TWO_SIDED, 0.05, &a);
    mcstat_var_test_2(y, 17, x, 41, 1.0, MCSTAT_TWO_SIDED, 0.05, &b);
    CHECK_REL(a.statistic, 1.0 / b.statistic, 1e-15, "F swap");
    CHECK_REL(a.p_value, b.p_value, 1e-13, "F swap p");
    CHECK_INT(a.decision, -b.decision);
}

/* reject <=> statistic outside [critical0, critical1] <=> null value outside the CI. */
static void test_consistency(void)
{
    for (int rep = 0; rep < 400; rep++) {
        size_t n = 2 + (size_t)gsl_rng_uniform_int(rng, 60);
        double x[64], y[64];
        normal(x, n, 0.0, 1.0);
        normal(y, n + 1, gsl_ran_gaussian(rng, 1.0), 0.5 + gsl_rng_uniform(rng));
        int alt = (int)gsl_rng_uniform_int(rng, 3);
        double alpha = 0.001 + 0.3 * gsl_rng_uniform(rng);
        double mu0 = gsl_ran_gaussian(rng, 0.8);
        mcstat_result r[4];
        CHECK_INT(mcstat_t_test_1(x, n, mu0, alt, alpha, &r[0]), MCSTAT_OK);
        CHECK_INT(mcstat_t_test_2(x, n, y, n + 1, mu0, alt, alpha, &r[1]), MCSTAT_OK);
        CHECK_INT(mcstat_var_test_1(x, n, 1.0 + mu0 * mu0, alt, alpha, &r[2]), MCSTAT_OK);
        CHECK_INT(mcstat_var_test_2(x, n, y, n + 1, 1.0 + mu0 * mu0, alt, alpha, &r[3]), MCSTAT_OK);
        for (int k = 0; k < 4; k++) {
            const mcstat_result *q = &r[k];
            int outside = q->statistic < q->critical[0] || q->statistic > q->critical[1];
            /* skip exact ties with a critical value (measure zero) */
            double margin = fmin(fabs(q->statistic - q->critical[0]), fabs(q->statistic - q->critical[1]));
            if (margin > 1e-9 * fabs(q->statistic) && fabs(q->p_value - alpha) > 1e-9) {
                CHECK_MSG(outside == q->reject, "test %d alt %d: stat %g crit [%g, %g] p %g alpha %g", q->test, alt,
                          q->statistic, q->critical[0], q->critical[1], q->p_value, alpha);
                int in_ci = q->null_value >= q->conf_int[0] && q->null_value <= q->conf_int[1];
                CHECK_MSG(in_ci == !q->reject, "test %d alt %d: null %g ci [%g, %g] reject %d", q->test, alt,
                          q->null_value, q->conf_int[0], q->conf_int[1], q->reject);
            }
            CHECK(q->decision == 0 || q->reject);
            if (q->reject)
                CHECK(q->decision == (alt == MCSTAT_LESS ? -1 : alt == MCSTAT_GREATER ? 1 : q->decision));
            if (alt == MCSTAT_TWO_SIDED && q->reject)
                CHECK(q->decision == (q->estimate[0] - (k == 1 ? q->estimate[1] : 0) <
                                              (k == 3 ? q->null_value : (k == 1 ? q->null_value : q->null_value))
                                          ? -1
                                          : 1) ||
                      k == 3 || k == 2);
            CHECK(q->alpha == alpha && q->alternative == alt);
            CHECK(q->p_value >= 0.0 && q->p_value <= 1.0);
        }
    }
}

/* Under H0 each test rejects at rate alpha: |count - N alpha| within 4.5 binomial sd. */
static void test_calibration(void)
{
    enum { N = 6000 };
    const double alpha = 0.05, sd = sqrt(N * alpha * (1 - alpha));
    for (int alt = 0; alt < 3; alt++) {
        int rej[4] = {0, 0, 0, 0}, cover[4] = {0, 0, 0, 0};
        for (int rep = 0; rep < N; rep++) {
            double x[12], y[30];
            normal(x, 12, 5.0, 2.0);
            normal(y, 30, 5.0, 7.0); /* Welch: unequal variances */
            double yv[30];
            normal(yv, 30, -1.0, 2.0); /* F: equal variances */
            mcstat_result r;
            mcstat_t_test_1(x, 12, 5.0, alt, alpha, &r);
            rej[0] += r.reject;
            cover[0] += 5.0 >= r.conf_int[0] && 5.0 <= r.conf_int[1];
            mcstat_t_test_2(x, 12, y, 30, 0.0, alt, alpha, &r);
            rej[1] += r.reject;
            cover[1] += 0.0 >= r.conf_int[0] && 0.0 <= r.conf_int[1];
            mcstat_var_test_1(x, 12, 4.0, alt, alpha, &r);
            rej[2] += r.reject;
            cover[2] += 4.0 >= r.conf_int[0] && 4.0 <= r.conf_int[1];
            mcstat_var_test_2(x, 12, yv, 30, 1.0, alt, alpha, &r);
            rej[3] += r.reject;
            cover[3] += 1.0 >= r.conf_int[0] && 1.0 <= r.conf_int[1];
        }
        for (int k = 0; k < 4; k++) {
            /* Welch is approximate: allow a little more than sampling noise */
            double slack = (k == 1 ? 6.0 : 4.5) * sd;
            CHECK_MSG(fabs(rej[k] - N * alpha) <= slack, "test %d alt %d: %d rejections of %d", k + 1, alt, rej[k], N);
            CHECK_MSG(fabs((N - cover[k]) - N * alpha) <= slack, "test %d alt %d: CI missed %d of %d", k + 1, alt,
                      N - cover[k], N);
        }
    }
}

/* And it has power: shifts of one standard error of the mean difference... */
static void test_power(void)
{
    enum { N = 500 };
    int hit[4] = {0, 0, 0, 0};
    for (int rep = 0; rep < N; rep++) {
        double x[40], y[40];
        normal(x, 40, 1.5, 1.0);
        normal(y, 40, 0.0, 2.5);
        mcstat_result r;
        mcstat_t_test_1(x, 40, 0.0, MCSTAT_TWO_SIDED, 0.01, &r);
        hit[0] += r.decision == 1;
        mcstat_t_test_2(x, 40, y, 40, 0.0, MCSTAT_TWO_SIDED, 0.01, &r);
        hit[1] += r.decision == 1;
        mcstat_var_test_1(y, 40, 1.0, MCSTAT_TWO_SIDED, 0.01, &r);
        hit[2] += r.decision == 1;
        mcstat_var_test_2(x, 40, y, 40, 1.0, MCSTAT_TWO_SIDED, 0.01, &r);
        hit[3] += r.decision == -1;
    }
    /* noncentrality 9.5 (t), 3.5 (Welch, df ~ 51, power ~ 0.8 at alpha 0.01),
     * and variance ratios of 6.25: powers ~1, ~0.8, ~1, ~1 */
    CHECK_MSG(hit[0] > 0.97 * N, "t power %d", hit[0]);
    CHECK_MSG(hit[1] > 0.65 * N, "welch power %d", hit[1]);
    CHECK_MSG(hit[2] > 0.97 * N, "chisq power %d", hit[2]);
    CHECK_MSG(hit[3] > 0.97 * N, "F power %d", hit[3]);
}

/* Edge cases that must work. */
static void test_edges(void)
{
    mcstat_result r;
    const double two[2] = {1.0, 3.0}, other[2] = {2.0, 2.5};
    CHECK_INT(mcstat_t_test_1(two, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_REL(r.statistic, 2.0, 1e-15, "n = 2");
    CHECK_REL(r.p_value, 0.29516723530086416, 1e-14, "n = 2 p (Cauchy: 1 - 2 atan(2)/pi)");
    /* Welch with one constant sample is fine (df = n of the other - 1) */
    const double c3[3] = {4.0, 4.0, 4.0}, v4[4] = {1.0, 2.0, 4.0, 7.0};
    CHECK_INT(mcstat_t_test_2(c3, 3, v4, 4, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_REL(r.df[0], 3.0, 1e-15, "welch one constant sample df");
    CHECK_INT(mcstat_t_test_2(c3, 3, c3, 3, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_EDEGENERATE);
    CHECK_INT(mcstat_var_test_2(c3, 3, v4, 4, 1.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_EDEGENERATE);
    CHECK_INT(mcstat_var_test_1(c3, 3, 1.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_EDEGENERATE);
    CHECK_INT(mcstat_t_test_1(c3, 3, 4.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_EDEGENERATE);
    /* equal to within rounding is constant; one ulp of spread at 1 is not */
    const double ulp[3] = {1.0, 1.0 + DBL_EPSILON, 1.0};
    CHECK_INT(mcstat_t_test_1(ulp, 3, 1.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_EDEGENERATE);
    const double tiny[3] = {1e-300, 2e-300, 4e-300};
    CHECK_INT(mcstat_t_test_1(tiny, 3, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_var_test_2(two, 2, other, 2, 1.0, MCSTAT_GREATER, 0.5, &r), MCSTAT_OK);
    CHECK_REL(r.statistic, 16.0, 1e-15, "F with n = 2");
}

/* Confidence intervals at extreme alpha are finite or -+Inf, never NaN with
 * status OK: t_test_1({0, 1e47}) at alpha = 1e-268 gave (NaN, NaN), the
 * product of the critical value 6.4e267 and se 5e46 overflowing inside the
 * exact product; one-sided tests gave (-Inf, NaN), Welch and the
 * equivalence test (which share the bound) likewise.  Where the true bound
 * is beyond DBL_MAX it is -+Inf; where it is not, it is est -+ c se. */
static void check_interval(int st, const mcstat_result *r, const char *what, double scale, double alpha, int alt)
{
    CHECK_INT(st, MCSTAT_OK);
    CHECK_MSG(!isnan(r->conf_int[0]) && !isnan(r->conf_int[1]) && r->conf_int[0] <= r->conf_int[1],
              "%s: data scale %g, alpha %g, alternative %d: conf_int (%g, %g)", what, scale, alpha, alt,
              r->conf_int[0], r->conf_int[1]);
}

static void test_interval_extreme_alpha(void)
{
    mcstat_result r;
    const double x47[2] = {0.0, 1e47}, y1[2] = {0.0, 1.0};
    CHECK_INT(mcstat_t_test_1(x47, 2, 0.0, MCSTAT_TWO_SIDED, 1e-268, &r), MCSTAT_OK);
    CHECK(r.conf_int[0] == -INFINITY && r.conf_int[1] == INFINITY); /* 5e46 -+ 3.2e314 */
    CHECK_INT(mcstat_t_test_2(x47, 2, y1, 2, 0.0, MCSTAT_TWO_SIDED, 1e-268, &r), MCSTAT_OK);
    CHECK(r.conf_int[0] == -INFINITY && r.conf_int[1] == INFINITY);
    CHECK_INT(mcstat_equivalence_test_1(x47, 2, 0.0, -1.0, 1.0, 1e-268, &r), MCSTAT_OK);
    CHECK(r.conf_int[0] == -INFINITY && r.conf_int[1] == INFINITY);
    const double x60[2] = {0.0, 1e60};
    CHECK_INT(mcstat_t_test_1(x60, 2, 0.0, MCSTAT_LESS, 1e-250, &r), MCSTAT_OK);
    CHECK(r.conf_int[0] == -INFINITY && r.conf_int[1] == INFINITY); /* 5e59 + 1.6e309 */
    CHECK_INT(mcstat_t_test_1(x60, 2, 0.0, MCSTAT_GREATER, 1e-250, &r), MCSTAT_OK);
    CHECK(r.conf_int[0] == -INFINITY && r.conf_int[1] == INFINITY);
    /* c se = 3.2e307 is past 2^900 but finite: est -+ c se to rounding */
    const double x40[2] = {0.0, 1e40};
    CHECK_INT(mcstat_t_test_1(x40, 2, 0.0, MCSTAT_TWO_SIDED, 1e-268, &r), MCSTAT_OK);
    CHECK_REL(r.conf_int[0], r.estimate[0] - r.critical[1] * r.std_error, 1e-15, "lower bound, c se = 3e307");
    CHECK_REL(r.conf_int[1], r.estimate[0] - r.critical[0] * r.std_error, 1e-15, "upper bound, c se = 3e307");
    CHECK(isfinite(r.conf_int[0]) && isfinite(r.conf_int[1]));
    /* a sweep: data scales 1e-300 .. 1e300, alpha 1e-1 .. 1e-320, every
     * alternative, through every test and entry point that forms intervals */
    for (int k = -300; k <= 300; k += 20) {
        double s = pow(10.0, k), x[3] = {0.0, s, 0.25 * s}, y[2] = {s, 0.5 * s}, z[2] = {0.0, 1.0};
        for (int m = 1; m <= 320; m += 7) {
            double alpha = pow(10.0, -m);
            if (alpha == 0.0) /* a caller running with flush-to-zero (portability-test) cannot form 1e-316 */
                continue;
            for (int alt = 0; alt < 3; alt++) {
                check_interval(mcstat_t_test_1(x, 2, 0.0, alt, alpha, &r), &r, "t_test_1", s, alpha, alt);
                check_interval(mcstat_t_test_1(x, 3, 0.0, alt, alpha, &r), &r, "t_test_1 n 3", s, alpha, alt);
                check_interval(mcstat_t_test_2(x, 2, z, 2, 0.0, alt, alpha, &r), &r, "t_test_2", s, alpha, alt);
                check_interval(mcstat_t_test_2(z, 2, x, 3, 0.0, alt, alpha, &r), &r, "t_test_2 swapped", s, alpha,
                               alt);
                check_interval(mcstat_var_test_1(x, 2, 1.0, alt, alpha, &r), &r, "var_test_1", s, alpha, alt);
                check_interval(mcstat_var_test_2(x, 3, y, 2, 1.0, alt, alpha, &r), &r, "var_test_2", s, alpha, alt);
                check_interval(mcstat_var_test_2(z, 2, x, 2, 1.0, alt, alpha, &r), &r, "var_test_2 swapped", s,
                               alpha, alt);
                mcstat_result rows[1];
                int32_t rst[1];
                CHECK_INT(mcstat_t_test_1_matrix(x, 2, 2, 1, 0.0, alt, alpha, 0, rows, rst), MCSTAT_OK);
                check_interval(rst[0], rows, "t_test_1_rows", s, alpha, alt);
                CHECK_INT(mcstat_t_test_2_matrix(x, 2, 2, z, 2, 2, 1, 0.0, alt, alpha, 0, rows, rst), MCSTAT_OK);
                check_interval(rst[0], rows, "t_test_2_rows", s, alpha, alt);
            }
            if (alpha < 0.5) {
                check_interval(mcstat_equivalence_test_1(x, 2, 0.0, -1.0, 1.0, alpha, &r), &r, "equivalence_1", s,
                               alpha, 0);
                check_interval(mcstat_equivalence_test_2(x, 2, z, 2, -1.0, 1.0, alpha, &r), &r, "equivalence_2", s,
                               alpha, 0);
            }
        }
    }
}

int main(void)
{
    gsl_rng_env_setup();
    rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 20261123);
    test_affine_invariance();
    test_swap();
    test_consistency();
    test_calibration();
    test_power();
    test_edges();
    test_interval_extreme_alpha();
    gsl_rng_free(rng);
    return h_report("test_tests");
}
