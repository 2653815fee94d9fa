/*
 * test_diagnose.c - estimator diagnostics: Hill's tail index against its
 * closed form on constructed data, shape against mcstat_moments, the batch
 * size rule against the size prediction it inverts, statuses.  (Calibration
 * - flag rates, the t test's level at the recommended k - is measured in
 * tests/python/test_diagnose.py.)
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "mcstat.h"
#include <stdint.h>
static uint64_t rng_state = 20261123;
#include "test_rng.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Data symmetric about 0 (the median) whose k+1 largest excesses are
 * (i+1)^(-1/a), i = 0..k: Hill's estimate is a k / (k log(k+1) - log k!). */
static void test_hill_closed_form(void)
{
    const double as[] = {0.7, 1.5, 2.0, 4.0};
    const size_t ks[] = {10, 31, 100};
    for (size_t ia = 0; ia < 4; ia++)
        for (size_t ik = 0; ik < 3; ik++) {
            size_t k = ks[ik], n = 2 * (k + 1) + 1 + 40;
            double *x = malloc(n * sizeof *x);
            size_t j = 0;
            x[j++] = 0.0;
            for (size_t i = 0; i <= k; i++) {
                x[j++] = pow((double)(i + 1), -1.0 / as[ia]);
                x[j++] = -pow((double)(i + 1), -1.0 / as[ia]);
            }
            for (int i = 0; i < 20; i++) { /* inner values that change neither tail nor median */
                double v = 1e-3 * pow((double)(k + 2), -1.0 / as[ia]) * (i + 1) / 21.0;
                x[j++] = v;
                x[j++] = -v;
            }
            double want = as[ia] * k / (k * log(k + 1.0) - lgamma(k + 1.0)), idx[2];
            CHECK(mcstat_diag_tail_index(x, n, k, idx) == MCSTAT_OK);
            CHECK_REL(idx[0], want, 1e-13, "lower a=%g k=%zu", as[ia], k);
            CHECK_REL(idx[1], want, 1e-13, "upper a=%g k=%zu", as[ia], k);
            free(x);
        }
}

static void test_diagnose_fields(void)
{
    enum { N = 20000 };
    static double x[N];
    for (int i = 0; i < N; i++)
        x[i] = -log(unif()); /* exponential: skewness 2, kurtosis 6 */
    mcstat_diagnostics d;
    CHECK(mcstat_diag_compute(x, N, NULL, &d) == MCSTAT_OK);
    mcstat_moments m;
    mcstat_moments_init(&m);
    mcstat_moments_add_array(&m, x, N);
    CHECK(d.n == N && d.skewness == mcstat_moments_skewness(&m) && d.kurtosis == mcstat_moments_kurtosis(&m));
    CHECK(fabs(d.skewness - 2.0) < 0.3 && fabs(d.kurtosis - 6.0) < 3.0);
    CHECK_REL(d.skewness_se, sqrt(6.0 * N * (N - 1.0) / ((N - 2.0) * (N + 1.0) * (N + 3.0))), 1e-15, "se");
    CHECK(d.tail_k == 565 && d.heavy_tail == 0 && d.tail_index[1] > 3.0 && isinf(d.tail_index[0]) == 0);
    CHECK(d.m == MCSTAT_DIAG_DEFAULT_M && d.k == 1 && d.t_size[0] > d.t_size[1]);
    CHECK(d.max_share > 0.0 && d.max_share < 0.01);
    /* with a batch size: m = n / k */
    mcstat_diag_options o = MCSTAT_DIAG_OPTIONS_INIT;
    o.k = 100;
    CHECK(mcstat_diag_compute(x, N, &o, &d) == MCSTAT_OK);
    CHECK(d.k == 100 && d.m == 200);
    /* normal data: no heavy tail, k = 1 suffices */
    for (int i = 0; i < N; i++)
        x[i] = 5.0 + normal();
    CHECK(mcstat_diag_compute(x, N, NULL, &d) == MCSTAT_OK);
    CHECK(d.heavy_tail == 0 && d.recommended_k == 1 && fabs(d.skewness) < 0.1);
    /* heavy tails: U^(-1/2) */
    for (int i = 0; i < N; i++)
        x[i] = 1.0 / sqrt(unif());
    CHECK(mcstat_diag_compute(x, N, NULL, &d) == MCSTAT_OK);
    CHECK(d.heavy_tail == 1 && d.tail_index[1] < 2.2 && isinf(d.tail_index[0]) == 0);
}

/* The rule returns the smallest k whose predicted tails are within tolerance. */
static void test_rule(void)
{
    const double g[] = {0.0, 0.5, 2.0, 6.18, -3.0};
    const double c[] = {0.0, 1.0, 6.0, 110.0, 20.0};
    const uint64_t ms[] = {2, 10, 50, 1000};
    const double alphas[] = {0.05, 0.01};
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 4; j++)
            for (int a = 0; a < 2; a++) {
                uint64_t k;
                double tol = 0.2, s[2], e = tol * 0.5 * alphas[a];
                CHECK(mcstat_diag_batch_size(g[i], c[i], ms[j], alphas[a], tol, &k) == MCSTAT_OK);
                CHECK(mcstat_diag_t_size(g[i], c[i], k, ms[j], alphas[a], s) == MCSTAT_OK);
                double dev = fmax(fabs(s[0] - 0.5 * alphas[a]), fabs(s[1] - 0.5 * alphas[a]));
                CHECK_MSG(dev <= e * (1 + 1e-12), "g=%g c=%g m=%llu: k=%llu dev %g", g[i], c[i],
                          (unsigned long long)ms[j], (unsigned long long)k, dev);
                if (k > 1) {
                    CHECK(mcstat_diag_t_size(g[i], c[i], k - 1, ms[j], alphas[a], s) == MCSTAT_OK);
                    dev = fmax(fabs(s[0] - 0.5 * alphas[a]), fabs(s[1] - 0.5 * alphas[a]));
                    CHECK_MSG(dev > e * (1 - 1e-12), "k-1 passes too");
                }
            }
    /* normal data need no batching; symmetric data predict alpha/2 per tail */
    uint64_t k;
    double s[2];
    CHECK(mcstat_diag_batch_size(0.0, 0.0, 10, 0.05, 0.2, &k) == MCSTAT_OK && k == 1);
    CHECK(mcstat_diag_t_size(0.0, 0.0, 1, 10, 0.05, s) == MCSTAT_OK && s[0] == 0.025 && s[1] == 0.025);
    /* a closed-form value: exponential (g = 2, c = 6), k = 1, m = 10 */
    double z = 1.959963984540054, phi = exp(-0.5 * z * z) / sqrt(2 * M_PI);
    double A = 2.0 * (2 * z * z + 1) / 6 * phi / sqrt(10.0);
    double B = z * (6.0 * (z * z - 3) / 12 - 4.0 * (z * z * z * z + 2 * z * z - 3) / 18) * phi / 10.0;
    CHECK(mcstat_diag_t_size(2.0, 6.0, 1, 10, 0.05, s) == MCSTAT_OK);
    CHECK_REL(s[0], 0.025 + A - B, 1e-12, "lower");
    CHECK_REL(s[1], fmax(0.0, 0.025 - A - B), 1e-12, "upper");
    /* more skewness needs bigger batches */
    uint64_t k1, k2;
    mcstat_diag_batch_size(1.0, 1.0, 20, 0.05, 0.2, &k1);
    mcstat_diag_batch_size(4.0, 1.0, 20, 0.05, 0.2, &k2);
    CHECK(k2 > 10 * k1);
}

static void test_bad_input(void)
{
    double x[64], idx[2], s[2];
    uint64_t k;
    for (int i = 0; i < 64; i++)
        x[i] = i * 0.37 - (i % 7);
    mcstat_diagnostics d;
    mcstat_diag_options o = MCSTAT_DIAG_OPTIONS_INIT;
    CHECK(mcstat_diag_compute(NULL, 64, NULL, &d) == MCSTAT_EINVAL);
    CHECK(mcstat_diag_compute(x, 64, NULL, NULL) == MCSTAT_EINVAL);
    o.alpha = 1.0;
    CHECK(mcstat_diag_compute(x, 64, &o, &d) == MCSTAT_EINVAL);
    o = (mcstat_diag_options)MCSTAT_DIAG_OPTIONS_INIT;
    o.size = 8;
    CHECK(mcstat_diag_compute(x, 64, &o, &d) == MCSTAT_EINVAL);
    o = (mcstat_diag_options)MCSTAT_DIAG_OPTIONS_INIT;
    o.k = 65;
    CHECK(mcstat_diag_compute(x, 64, &o, &d) == MCSTAT_EINVAL);
    o.k = 40; /* one batch mean */
    CHECK(mcstat_diag_compute(x, 64, &o, &d) == MCSTAT_ETOOFEW);
    CHECK(mcstat_diag_compute(x, 7, NULL, &d) == MCSTAT_ETOOFEW);
    CHECK(mcstat_diag_compute(x, 21, NULL, &d) == MCSTAT_ETOOFEW); /* tail_k 10 needs 22 */
    x[5] = NAN;
    CHECK(mcstat_diag_compute(x, 64, NULL, &d) == MCSTAT_ENONFINITE);
    CHECK(mcstat_diag_tail_index(x, 64, 0, idx) == MCSTAT_ENONFINITE);
    x[5] = INFINITY;
    CHECK(mcstat_diag_compute(x, 64, NULL, &d) == MCSTAT_ENONFINITE);
    CHECK(mcstat_diag_tail_index(x, 64, 0, idx) == MCSTAT_ENONFINITE);
    for (int i = 0; i < 64; i++)
        x[i] = 3.0;
    CHECK(mcstat_diag_compute(x, 64, NULL, &d) == MCSTAT_EDEGENERATE);
    CHECK(mcstat_diag_tail_index(x, 64, 0, idx) == MCSTAT_OK && isinf(idx[0]) && isinf(idx[1]));
    CHECK(mcstat_diag_t_size(NAN, 0, 1, 10, 0.05, s) == MCSTAT_EINVAL);
    CHECK(mcstat_diag_t_size(0, -3, 1, 10, 0.05, s) == MCSTAT_EINVAL);
    CHECK(mcstat_diag_t_size(0, 0, 0, 10, 0.05, s) == MCSTAT_EINVAL);
    CHECK(mcstat_diag_t_size(0, 0, 1, 1, 0.05, s) == MCSTAT_ETOOFEW);
    CHECK(mcstat_diag_batch_size(1, 1, 10, 0.05, 0.0, &k) == MCSTAT_EINVAL);
    CHECK(mcstat_diag_batch_size(1, 1, 10, 0.05, 0.2, NULL) == MCSTAT_EINVAL);
    CHECK(mcstat_diag_batch_size(1, 1, 1, 0.05, 0.2, &k) == MCSTAT_ETOOFEW);
    CHECK(mcstat_diag_batch_size(1e12, 1, 2, 0.05, 0.2, &k) == MCSTAT_ETOOBIG);
    CHECK(mcstat_diag_options_init(&o) == MCSTAT_OK && o.size == mcstat_sizeof_diag_options() && o.alpha == 0.05);
    CHECK(mcstat_sizeof_diagnostics() == sizeof(mcstat_diagnostics));
}

int main(void)
{
    test_hill_closed_form();
    test_diagnose_fields();
    test_rule();
    test_bad_input();
    return h_report("test_diagnose");
}
