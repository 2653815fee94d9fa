/*
 * demo.c - the tests of mcstat on generated Monte Carlo estimates.
 *
 * Two estimators of the same integral, I = integral_0^1 3x^2 dx = 1:
 *   "uniform":    f(U) = 3 U^2, U uniform            (variance 4/5)
 *   "importance": f(X)/p(X) with p(x) = 2x, X = sqrt(U)  (variance 1/8)
 * Following the paper (section 2, ERRATA 7), each observation is a secondary
 * estimate: the mean of k = 16 primary estimates.  The demo asks the
 * paper's five questions and prints R-style answers.
 */
#include "mcstat.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

static uint64_t state = 20261123;

static double uniform01(void) /* splitmix64, 53 bits */
{
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}

static double uniform_estimate(void)
{
    double u = uniform01();
    return 3.0 * u * u;
}

static double importance_estimate(void)
{
    double x = sqrt(uniform01()); /* density 2x */
    return 3.0 * x * x / (2.0 * x);
}

static void show(const char *question, int status, const mcstat_result *r, const char *xn, const char *yn)
{
    char text[2048];
    printf("==> %s\n", question);
    if (status != MCSTAT_OK) {
        printf("error: %s\n\n", mcstat_strerror(status));
        return;
    }
    mcstat_result_format(r, xn, yn, text, sizeof text, NULL);
    fputs(text, stdout);
}

int main(void)
{
    enum { M = 200, K = 16 };
    double uni[M], imp[M];
    mcstat_moments streamed;
    mcstat_moments_init(&streamed);
    for (int i = 0; i < M; i++) {
        double su = 0.0, si = 0.0;
        for (int k = 0; k < K; k++) {
            su += uniform_estimate();
            si += importance_estimate();
        }
        uni[i] = su / K;
        imp[i] = si / K;
        mcstat_moments_add(&streamed, imp[i]); /* as a renderer would, without storing */
    }
    printf("mcstat %s: %d secondary estimates (means of %d primary estimates) of each estimator;\n"
           "the integral is 1; Var(uniform) = 0.8/%d, Var(importance) = 0.125/%d.\n\n",
           mcstat_version(), M, K, K, K);
    mcstat_result r;
    int st;

    st = mcstat_t_test_1(uni, M, 1.0, MCSTAT_TWO_SIDED, 0.05, &r);
    show("Is the uniform estimator unbiased? (one-sample t against the analytic value)", st, &r, "uniform", NULL);

    st = mcstat_t_test_1_moments(&streamed, 1.0, MCSTAT_TWO_SIDED, 0.05, &r);
    show("The same for importance sampling, from a streaming accumulator", st, &r, "importance", NULL);

    st = mcstat_var_test_1(imp, M, 0.01, MCSTAT_LESS, 0.05, &r);
    show("Is the importance estimator's variance below 0.01? (one-sample chi-squared)", st, &r, "importance",
         NULL);

    st = mcstat_t_test_2(uni, M, imp, M, 0.0, MCSTAT_TWO_SIDED, 0.05, &r);
    show("Do the two estimators agree? (Welch two-sample t)", st, &r, "uniform", "importance");

    st = mcstat_var_test_2(uni, M, imp, M, 1.0, MCSTAT_TWO_SIDED, 0.05, &r);
    show("Which has less variance? (two-sample F)", st, &r, "uniform", "importance");

    /* Section 3.2: does a sampler draw from the density it claims?  The
     * importance sampler above claims p(x) = 2x.  sqrt(U) and max(U1, U2)
     * both have that density; U^0.45 (a plausible slip) does not. */
    enum { S = 2000 };
    static double inv[S], maxu[S], slip[S];
    for (int i = 0; i < S; i++) {
        inv[i] = sqrt(uniform01());
        double a = uniform01(), b = uniform01();
        maxu[i] = a > b ? a : b;
        slip[i] = pow(uniform01(), 0.45);
    }
    mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT; /* Canner's weight, exact where affordable */
    o.seed = 7;
    st = mcstat_ks_test_2(inv, S, maxu, S, MCSTAT_TWO_SIDED, 0.05, &o, &r);
    show("Do two samplers of the density 2x agree? (two-sample K-S, Canner's weight)", st, &r, "sqrt(U)",
         "max(U1,U2)");
    st = mcstat_ks_test_2(slip, S, maxu, S, MCSTAT_TWO_SIDED, 0.05, &o, &r);
    show("And a sampler with a slip in its exponent?", st, &r, "U^0.45", "max(U1,U2)");
    return 0;
}
