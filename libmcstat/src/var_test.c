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

#include <float.h>

/* num * 2^k / den, den > 0 finite, without intermediate over/underflow. */
static double ratio_pow2(double num, int k, double den)
{
    int kd;
    double fd = frexp(den, &kd);
    return scale2(num / fd, k - kd);
}

/* The quantile the critical value c of bound `which` (0: conf_int[0], from
 * critical[1]; 1: conf_int[1], from critical[0]) was computed at: see
 * mcstat__finish. */
static double bound_p(const mcstat_result *r, int which, int *upper)
{
    *upper = which == 0;
    if (r->alternative == MCSTAT_TWO_SIDED)
        return 0.5 * r->alpha;
    if (r->alternative == (which == 0 ? MCSTAT_GREATER : MCSTAT_LESS))
        return r->alpha;
    return 0.0; /* the end of the support: the bound is 0 or Inf */
}

/* A variance interval's bound num * 2^k / c, c the critical value.  Where c
 * is 0, subnormal or Inf only because the quantile left the normal doubles
 * (chi-squared with df 1 or 2, F with a small df, at alpha ~ 1e-270), the
 * bound itself may well be representable (M2 = 1e-100 over c = 1e-400):
 * then it is formed from log c, c = 2^j e^rem, as num / e^rem * 2^(k - j).
 * Otherwise the quotient, rounded as before, so ordinary intervals are
 * unchanged. */
static int var_bound(const mcstat_result *r, int which, double num, int k, double df1, double df2,
                     double *out)
{
    double c = r->critical[which ? 0 : 1];
    int upper;
    double p = bound_p(r, which, &upper);
    if (p == 0.0) {
        *out = scale2(num / c, k);
        return MCSTAT_OK;
    }
    if (c >= DBL_MIN && c <= DBL_MAX) {
        /* num / c itself may overflow where k brings the bound back (data
         * near 1e-300 against data near 1e300); otherwise the same bits */
        *out = ratio_pow2(num, k, c);
        return MCSTAT_OK;
    }
    double z;
    int st = r->test == MCSTAT_TEST_VAR_1 ? mcstat__chisq_log_quantile(p, df1, upper, &z)
                                          : mcstat__f_log_quantile(p, df1, df2, upper, &z);
    if (st)
        return st;
    if (!isfinite(z) || fabs(z) > 1e6) { /* not for df >= 1 (|z| < 2000); keeps j ln2_hi exact */
        *out = scale2(num / c, k);
        return MCSTAT_OK;
    }
    /* z = j ln 2 + rem, |rem| <= ln 2 / 2; j ln 2 exact with ln 2's leading 32 bits */
    const double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
    double j = floor(z / M_LN2 + 0.5);
    double rem = (z - j * ln2_hi) - j * ln2_lo;
    /* k - j may leave int's range only where the bound over- or underflows anyway */
    double e = (double)k - j;
    int ei = e > 4000.0 ? 4000 : e < -4000.0 ? -4000 : (int)e;
    *out = ldexp(num / exp(rem), ei);
    return MCSTAT_OK;
}

int mcstat__var_test_1(const mcstat_moments *x, double sigma2, int alternative, double alpha,
                       mcstat_qcache *qc, mcstat_result *out)
{
    if (!x)
        return mcstat__refuse(MCSTAT_EINVAL, "x is NULL");
    if (!(sigma2 > 0.0) || !isfinite(sigma2))
        return mcstat__refuse(MCSTAT_EINVAL, "sigma2 must be finite and > 0, got %g", sigma2);
    int st_args = mcstat__refuse_test_args(alternative, alpha, out);
    if (st_args)
        return st_args;
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
    if ((st = var_bound(&r, 0, x->m2, 2 * x->scale, df, 0.0, &r.conf_int[0])) ||
        (st = var_bound(&r, 1, x->m2, 2 * x->scale, df, 0.0, &r.conf_int[1])))
        return st;
    *out = r;
    return MCSTAT_OK;
}

int mcstat__var_test_2(const mcstat_moments *x, const mcstat_moments *y, double ratio, int alternative,
                       double alpha, mcstat_qcache *qc, mcstat_result *out)
{
    if (!x || !y)
        return mcstat__refuse(MCSTAT_EINVAL, "%s is NULL", x ? "y" : "x");
    if (!(ratio > 0.0) || !isfinite(ratio))
        return mcstat__refuse(MCSTAT_EINVAL, "ratio must be finite and > 0, got %g", ratio);
    int st_args = mcstat__refuse_test_args(alternative, alpha, out);
    if (st_args)
        return st_args;
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
    if ((st = var_bound(&r, 0, vx / vy, k, df1, df2, &r.conf_int[0])) ||
        (st = var_bound(&r, 1, vx / vy, k, df1, df2, &r.conf_int[1])))
        return st;
    *out = r;
    return MCSTAT_OK;
}

int mcstat_var_test_1_moments(const mcstat_moments *x, double sigma2, int alternative, double alpha,
                              mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__var_test_1(x, sigma2, alternative, alpha, &qc, out);
}

int mcstat_var_test_2_moments(const mcstat_moments *x, const mcstat_moments *y, double ratio,
                              int alternative, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__var_test_2(x, y, ratio, alternative, alpha, &qc, out);
}

int mcstat_var_test_1(const double *x, size_t n, double sigma2, int alternative, double alpha,
                      mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    if (!x || !out)
        return mcstat__refuse(MCSTAT_EINVAL, "%s is NULL", x ? "out (the result)" : "x");
    mcstat_moments m;
    mcstat_moments_init(&m);
    int st = mcstat_moments_add_array(&m, x, n);
    return st ? st : mcstat_var_test_1_moments(&m, sigma2, alternative, alpha, out);
}

int mcstat_var_test_2(const double *x, size_t nx, const double *y, size_t ny, double ratio,
                      int alternative, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    if (!x || !y || !out)
        return mcstat__refuse(MCSTAT_EINVAL, "%s is NULL", !x ? "x" : !y ? "y" : "out (the result)");
    mcstat_moments mx, my;
    int st = mcstat__moments_of_two(x, nx, y, ny, &mx, &my);
    return st ? st : mcstat_var_test_2_moments(&mx, &my, ratio, alternative, alpha, out);
}
