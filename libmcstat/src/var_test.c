/*
 * var_test.c - one-sample chi-squared test on a variance (section 2.2, eq. 2)
 * and the two-sample F test on a ratio of variances (section 2.4, eq. 4).
 *
 * Variances live in the accumulators as m2 * 2^(2 scale); statistics and
 * intervals are formed from the scaled values and a frexp'd null value, so a
 * variance of 1e600 (data near 1e300) still gives a finite statistic when the
 * statistic itself is finite.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

/* num * 2^k / den, den > 0 finite, without intermediate over/underflow. */
static double ratio_pow2(double num, int k, double den)
{
    int kd;
    double fd = frexp(den, &kd);
    return scale2(num / fd, k - kd);
}

int mcstat__var_test_1(const mcstat_moments *x, double sigma2, int alternative, double alpha,
                       mcstat_qcache *qc, mcstat_result *out)
{
    if (!x || !out || !(sigma2 > 0.0) || !isfinite(sigma2) || !valid_alternative(alternative) ||
        !valid_alpha(alpha))
        return MCSTAT_EINVAL;
    int st = mcstat__moments_check(x);
    if (st)
        return st;
    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = MCSTAT_TEST_VAR_1;
    r.method = MCSTAT_METHOD_ANALYTIC;
    r.alternative = alternative;
    r.alpha = alpha;
    r.null_value = sigma2;
    r.n[0] = x->n;

    double df = (double)(x->n - 1);
    /* X^2 = (n-1) s^2 / sigma2 = M2 / sigma2 */
    r.statistic = ratio_pow2(x->m2, 2 * x->scale, sigma2);
    r.df[0] = df;
    r.estimate[0] = mcstat_moments_var(x);

    mcstat_tails t;
    if (qc)
        mcstat__qcache_use(qc, MCSTAT_Q_CHISQ, df, 0.0);
    if ((st = mcstat__chisq_tails(r.statistic, df, &t)) ||
        (st = mcstat__finish(&r, &t, qc ? mcstat__qcache_quantile : NULL, qc)))
        return st;
    if (!qc) {
        *out = r;
        return MCSTAT_OK;
    }
    /* {sigma^2 : c0 <= M2 / sigma^2 <= c1} */
    r.conf_int[0] = scale2(x->m2 / r.critical[1], 2 * x->scale);
    r.conf_int[1] = scale2(x->m2 / r.critical[0], 2 * x->scale);
    *out = r;
    return MCSTAT_OK;
}

int mcstat__var_test_2(const mcstat_moments *x, const mcstat_moments *y, double ratio, int alternative,
                       double alpha, mcstat_qcache *qc, mcstat_result *out)
{
    if (!x || !y || !out || !(ratio > 0.0) || !isfinite(ratio) || !valid_alternative(alternative) ||
        !valid_alpha(alpha))
        return MCSTAT_EINVAL;
    int st = mcstat__moments_check(x);
    if (!st)
        st = mcstat__moments_check(y);
    if (st)
        return st;
    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = MCSTAT_TEST_VAR_2;
    r.method = MCSTAT_METHOD_ANALYTIC;
    r.alternative = alternative;
    r.alpha = alpha;
    r.null_value = ratio;
    r.n[0] = x->n;
    r.n[1] = y->n;

    const double df1 = (double)(x->n - 1), df2 = (double)(y->n - 1);
    double vx, vy;
    int ex, ey;
    mcstat__moments_var_scaled(x, &vx, &ex);
    mcstat__moments_var_scaled(y, &vy, &ey);
    int k = 2 * (ex - ey);
    double est = scale2(vx / vy, k); /* s_x^2 / s_y^2, as R reports it */
    r.statistic = ratio_pow2(vx / vy, k, ratio);
    r.df[0] = df1;
    r.df[1] = df2;
    r.estimate[0] = est;

    mcstat_tails t;
    if (qc)
        mcstat__qcache_use(qc, MCSTAT_Q_F, df1, df2);
    if ((st = mcstat__f_tails(r.statistic, df1, df2, &t)) ||
        (st = mcstat__finish(&r, &t, qc ? mcstat__qcache_quantile : NULL, qc)))
        return st;
    if (!qc) {
        *out = r;
        return MCSTAT_OK;
    }
    /* {rho : c0 <= est / rho <= c1} */
    r.conf_int[0] = scale2((vx / vy) / r.critical[1], k);
    r.conf_int[1] = scale2((vx / vy) / r.critical[0], k);
    *out = r;
    return MCSTAT_OK;
}

int mcstat_var_test_1_moments(const mcstat_moments *x, double sigma2, int alternative, double alpha,
                              mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__var_test_1(x, sigma2, alternative, alpha, &qc, out);
}

int mcstat_var_test_2_moments(const mcstat_moments *x, const mcstat_moments *y, double ratio,
                              int alternative, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__var_test_2(x, y, ratio, alternative, alpha, &qc, out);
}

int mcstat_var_test_1(const double *x, size_t n, double sigma2, int alternative, double alpha,
                      mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !out)
        return MCSTAT_EINVAL;
    mcstat_moments m;
    mcstat_moments_init(&m);
    int st = mcstat_moments_add_array(&m, x, n);
    return st ? st : mcstat_var_test_1_moments(&m, sigma2, alternative, alpha, out);
}

int mcstat_var_test_2(const double *x, size_t nx, const double *y, size_t ny, double ratio,
                      int alternative, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !y || !out)
        return MCSTAT_EINVAL;
    mcstat_moments mx, my;
    mcstat_moments_init(&mx);
    mcstat_moments_init(&my);
    int st = mcstat_moments_add_array(&mx, x, nx);
    if (!st)
        st = mcstat_moments_add_array(&my, y, ny);
    return st ? st : mcstat_var_test_2_moments(&mx, &my, ratio, alternative, alpha, out);
}
