/*
 * test_equivalence.c - TOST (equivalence.c) against R's two one-sided
 * t.test calls (tests/data/equivalence_ref.tsv, written by
 * tools/refgen/make_power_ref.R); arrays against accumulators;
 * calibration at the margin; the printed block; statuses.
 */
#include "harness.h"
#include "mcstat.h"
#include "ref_tsv.h"

static uint64_t rng_state = 20261123;
#include "test_rng.h"

#include <stdlib.h>

static int cases;

static void check_row(char **f, int nf, void *ctx)
{
    (void)ctx;
    CHECK_INT(nf, 15);
    if (nf != 15)
        return;
    cases++;
    size_t nx, ny = 0;
    double *x = tsv_doubles(f[0], &nx), *y = strcmp(f[1], "-") ? tsv_doubles(f[1], &ny) : NULL;
    double mu0 = atof(f[2]), lower = atof(f[3]), upper = atof(f[4]), alpha = atof(f[5]);
    double tl = atof(f[6]), pl = atof(f[7]), tu = atof(f[8]), pu = atof(f[9]), df = atof(f[10]);
    double ci0 = atof(f[11]), ci1 = atof(f[12]), ex = atof(f[13]), ey = atof(f[14]);
    mcstat_result r, rm;
    mcstat_moments mx, my;
    mcstat_moments_init(&mx);
    mcstat_moments_init(&my);
    mcstat_moments_add_array(&mx, x, nx);
    int st, stm;
    if (y) {
        mcstat_moments_add_array(&my, y, ny);
        st = mcstat_equivalence_test_2(x, nx, y, ny, lower, upper, alpha, &r);
        stm = mcstat_equivalence_test_2_moments(&mx, &my, lower, upper, alpha, &rm);
    } else {
        st = mcstat_equivalence_test_1(x, nx, mu0, lower, upper, alpha, &r);
        stm = mcstat_equivalence_test_1_moments(&mx, mu0, lower, upper, alpha, &rm);
    }
    CHECK_INT(st, MCSTAT_OK);
    CHECK_INT(stm, MCSTAT_OK);
    CHECK(memcmp(&r, &rm, sizeof r) == 0);
    CHECK_INT(r.test, y ? MCSTAT_TEST_EQUIV_2 : MCSTAT_TEST_EQUIV_1);
    /* R forms mean(x) - mu in double: at an offset (1e6 + 0.01 noise) its t
     * carries an error of ~eps |mean| / se, which mcstat (double-double
     * means) does not; tolerances grow with that condition number (the
     * Python tests check this case against mpmath at 50 digits). */
    double cond = 1.0 + fabs(r.estimate[0]) / (r.std_error * fmin(fabs(tl), fabs(tu)));
    double ttol = 1e-11 + 8 * 2.2e-16 * cond, ptol = 1e-9 + 30 * ttol;
    CHECK_REL(MCSTAT_RESULT_TOST_T_LOWER(&r), tl, ttol, "case %d t_lower", cases);
    CHECK_REL(MCSTAT_RESULT_TOST_T_UPPER(&r), tu, ttol, "case %d t_upper", cases);
    CHECK_REL(MCSTAT_RESULT_TOST_P_LOWER(&r), pl, ptol, "case %d p_lower", cases);
    CHECK_REL(MCSTAT_RESULT_TOST_P_UPPER(&r), pu, ptol, "case %d p_upper", cases);
    CHECK_REL(r.p_value, fmax(pl, pu), ptol, "case %d p", cases);
    CHECK(r.statistic == (pu >= pl ? MCSTAT_RESULT_TOST_T_UPPER(&r) : MCSTAT_RESULT_TOST_T_LOWER(&r)));
    CHECK_REL(r.df[0], df, 1e-12, "case %d df", cases);
    /* intervals: absolute error relative to their width (large offsets) */
    double w = ci1 - ci0;
    double ctol = 1e-10 * w + 4 * 2.2e-16 * fabs(r.estimate[0]);
    CHECK_MSG(fabs(r.conf_int[0] - ci0) <= ctol && fabs(r.conf_int[1] - ci1) <= ctol,
              "case %d interval [%.15g, %.15g], R [%.15g, %.15g]", cases, r.conf_int[0], r.conf_int[1], ci0, ci1);
    CHECK_REL(r.estimate[0], ex, 1e-14, "case %d mean x", cases);
    if (y)
        CHECK_REL(r.estimate[1], ey, 1e-14, "case %d mean y", cases);
    CHECK_REL(MCSTAT_RESULT_TOST_LOWER(&r), mu0 + lower, 1e-15, "case %d", cases);
    CHECK_REL(MCSTAT_RESULT_TOST_UPPER(&r), mu0 + upper, 1e-15, "case %d", cases);
    /* the decision: both one-sided tests reject <=> interval inside the bounds */
    int equiv = fmax(pl, pu) <= alpha;
    CHECK_INT(r.reject, equiv);
    CHECK_INT(r.decision, equiv ? 0 : pu >= pl ? 1 : -1);
    CHECK_INT(r.conf_int[0] > mu0 + lower && r.conf_int[1] < mu0 + upper, equiv);
    CHECK_INT(MCSTAT_RESULT_TOST_T_LOWER(&r) > r.critical[1] && MCSTAT_RESULT_TOST_T_UPPER(&r) < r.critical[0], equiv);
    char buf[2048];
    size_t len;
    CHECK_INT(mcstat_result_format(&r, "u", "v", buf, sizeof buf, &len), MCSTAT_OK);
    CHECK(strstr(buf, equiv ? "decision at alpha = " : "not equivalent") != NULL);
    CHECK(strstr(buf, equiv ? ": equivalent\n" : ": not equivalent\n") != NULL);
    CHECK(strstr(buf, y ? "data:  u and v\n" : "data:  u\n") != NULL);
    CHECK(strstr(buf, "lower bound ") != NULL && strstr(buf, "upper bound ") != NULL);
    free(x);
    free(y);
}

/* A fixed example's block, line by line. */
static void test_format(void)
{
    const double x[] = {0.1, -0.2, 0.05, 0.3, -0.1, 0.0, 0.15, -0.05};
    mcstat_result r;
    CHECK_INT(mcstat_equivalence_test_1(x, 8, 0.0, -0.25, 0.25, 0.05, &r), MCSTAT_OK);
    char buf[1024];
    CHECK_INT(mcstat_result_format(&r, NULL, NULL, buf, sizeof buf, NULL), MCSTAT_OK);
    /* R 4.2.2: t.test(x, mu = -0.25, alternative = "greater"): t = 5.1093025332,
     * p = 0.0006925524; t.test(x, mu = 0.25, alternative = "less"): t =
     * -3.9739019703, p = 0.0026827487; print(t.test(x, conf.level = 0.9)):
     * " -0.07304021  0.13554021" and the estimate block below. */
    const char *want =
        "\n\tOne Sample TOST equivalence t-test\n\n"
        "data:  x\n"
        "t = -3.9739, df = 7, p-value = 0.002683\n"
        "lower bound -0.25: t = 5.1093, p-value = 0.0006926\n"
        "upper bound 0.25: t = -3.9739, p-value = 0.002683\n"
        "alternative hypothesis: true mean is between -0.25 and 0.25\n"
        "90 percent confidence interval:\n"
        " -0.07304021  0.13554021\n";
    CHECK_MSG(strncmp(buf, want, strlen(want)) == 0, "got:\n%s", buf);
    CHECK(strstr(buf, "mean of x \n  0.03125 \ndecision at alpha = 0.05: equivalent\n\n") != NULL);
}

/* At the boundary (true mean = mu0 + upper) the test is of size alpha when
 * the margin is wide against the standard error: rejection rate within
 * binomial bounds of alpha; inside the margin it has power. */
static void test_calibration(void)
{
    const int reps = 4000, n = 50;
    const double alpha = 0.05;
    double x[50], y[50];
    for (int two = 0; two < 2; two++) {
        int rej = 0, rej_inside = 0;
        for (int i = 0; i < reps; i++) {
            mcstat_result r;
            for (int k = 0; k < n; k++) {
                x[k] = 1.0 + normal(); /* boundary: mean (difference) = 1 = upper */
                y[k] = 2.0 * normal();
            }
            int st = two ? mcstat_equivalence_test_2(x, n, y, n, -1.0, 1.0, alpha, &r)
                         : mcstat_equivalence_test_1(x, n, 0.0, -1.0, 1.0, alpha, &r);
            CHECK_INT(st, MCSTAT_OK);
            rej += r.reject;
            for (int k = 0; k < n; k++)
                x[k] -= 1.0; /* now centred: inside the margin */
            st = two ? mcstat_equivalence_test_2(x, n, y, n, -1.0, 1.0, alpha, &r)
                     : mcstat_equivalence_test_1(x, n, 0.0, -1.0, 1.0, alpha, &r);
            rej_inside += r.reject;
        }
        double rate = (double)rej / reps, sd = sqrt(alpha * (1 - alpha) / reps);
        CHECK_MSG(fabs(rate - alpha) < 4 * sd, "%s: rejection rate at the margin %.4f, alpha %.2f (+- %.4f)",
                  two ? "two-sample" : "one-sample", rate, alpha, 4 * sd);
        CHECK_MSG((double)rej_inside / reps > (two ? 0.7 : 0.99), "power inside the margin %.3f",
                  (double)rej_inside / reps);
    }
}

static void test_statuses(void)
{
    const double x[] = {1, 2, 3, 4}, c[] = {2, 2, 2}, bad[] = {1, NAN, 2};
    mcstat_result r;
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, -1, 1, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_equivalence_test_1(NULL, 4, 0, -1, 1, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, -1, 1, 0.05, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, 1, -1, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, 1, 1, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, -INFINITY, 1, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, NAN, -1, 1, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, -1, 1, 0.5, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, -1, 1, 0.0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 4, 0, -1, 1, NAN, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_1(x, 1, 0, -1, 1, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_equivalence_test_1(x, 0, 0, -1, 1, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_equivalence_test_1(bad, 3, 0, -1, 1, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_equivalence_test_1(c, 3, 0, -1, 1, 0.05, &r), MCSTAT_EDEGENERATE);
    CHECK_INT(mcstat_equivalence_test_2(x, 4, c, 3, -1, 1, 0.05, &r), MCSTAT_OK); /* Welch: one constant is fine */
    CHECK_INT(mcstat_equivalence_test_2(c, 3, c, 3, -1, 1, 0.05, &r), MCSTAT_EDEGENERATE);
    CHECK_INT(mcstat_equivalence_test_2(x, 4, NULL, 3, -1, 1, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_2(x, 4, x, 1, -1, 1, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_equivalence_test_2(x, 4, bad, 3, -1, 1, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_equivalence_test_2(x, 4, x, 4, 2, -2, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_equivalence_test_2_moments(NULL, NULL, -1, 1, 0.05, &r), MCSTAT_EINVAL);
    mcstat_moments m;
    mcstat_moments_init(&m);
    CHECK_INT(mcstat_equivalence_test_1_moments(&m, 0, -1, 1, 0.05, &r), MCSTAT_ETOOFEW);
}

int main(void)
{
    int n = tsv_read(MCSTAT_TEST_DATA_DIR "/equivalence_ref.tsv", check_row, NULL);
    CHECK_MSG(n >= 25, "read %d rows of equivalence_ref.tsv", n);
    test_format();
    test_calibration();
    test_statuses();
    return h_report("test_equivalence");
}
