/*
 * efficiency.c - the efficiency-ratio test of two Monte Carlo estimators:
 * eff = 1 / (variance per sample x time per sample) (Kalos & Whitlock,
 * "Monte Carlo Methods", section 3.1), rho = eff(x) / eff(y).
 *
 * Everything is done in log scale: log rho is a sum of four independent
 * logs (two sample variances, two mean times), whose variances add.
 *
 *   log s^2: the exact variance of s^2 is sigma^4 (beta2/n - (n-3)/(n(n-1)))
 *   (beta2 = mu4/sigma^4, any distribution with a finite fourth moment), so
 *   by the delta method Var(log s^2) ~ (beta2 - (n-3)/(n-1))/n, with the
 *   sample's beta2 = n M4/M2^2 plugged in.  No normality: renderer
 *   estimators are heavy tailed (beta2 in the hundreds where most samples
 *   are exact zeros), and the normal theory's 2/(n-1) would be far too small.
 *   log tau: Var(log mean) ~ s_tau^2 / (k mean^2) over k timed batches.
 *
 * The reference distribution is a t on Satterthwaite's degrees of freedom
 * for the sum of the four variances: k - 1 for each time part (few batches:
 * a z was anti-conservative, 0.087 at alpha 0.05 with 5 batches of 30%
 * noise, 0.125 with 3; the t gave 0.054 and 0.037), and 2/V for each
 * variance part, V its estimated Var(log s^2): the df of the chi-squared
 * whose log has that variance, n - 1 for normal data, about the number of
 * non-zero values for mostly-zero data, where it cut the rejection rate
 * under H0 from 0.111 to 0.088 (n = 2000, 1% non-zero).  These rates are
 * from a NumPy simulation of 4000 replications per case; tests/c/
 * test_efficiency.c measures the calibration the header states.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>

/* Above this the t is the normal to the last digit; the distributions'
 * promised range ends at 1e15 (mcstat.h, section "Distributions"). */
#define DF_MAX 1e15

/* log s^2 and the delta method's Var(log s^2) of an accumulator that passed
 * mcstat__moments_check (n >= 2, M2 > 0). */
static void log_var_part(const mcstat_moments *m, double *log_s2, double *v)
{
    double s2;
    int e;
    mcstat__moments_var_scaled(m, &s2, &e);
    *log_s2 = log(s2) + 2.0 * (double)e * M_LN2;
    /* beta2 = n M4 / M2^2 from the mantissas and exponents: M2^2 may leave
     * the doubles (a deserialized m2 near 1e200) where the ratio does not.
     * A sample's beta2 is >= 1 (Cauchy-Schwarz); rounding may not undo it. */
    double n = (double)m->n;
    int k2, k4;
    double f2 = frexp(m->m2, &k2), f4 = frexp(m->m4, &k4);
    double beta2 = m->m4 > 0.0 ? n * ldexp(f4 / (f2 * f2), k4 - 2 * k2) : 1.0;
    if (!(beta2 >= 1.0))
        beta2 = 1.0;
    /* (n-3)/(n-1) = 1 - 2/(n-1): written so, a two-point sample (beta2 = 1)
     * keeps its 2/(n(n-1)) when n passes 2^53 */
    *v = ((beta2 - 1.0) + 2.0 / (n - 1.0)) / n;
}

/* log of the mean time and Var(log mean) = s^2 / (k mean^2) of a timing
 * accumulator.  MCSTAT_ETOOFEW (k < 2), MCSTAT_EINVAL (a negative time, or
 * not an accumulator), MCSTAT_EDEGENERATE (every batch timed as 0). */
static int log_time_part(const mcstat_moments *t, double *log_tau, double *v)
{
    int st = mcstat__moments_check(t);
    if (st == MCSTAT_EDEGENERATE) /* equal times are legitimate: an exact cost */
        st = MCSTAT_OK;
    if (st)
        return st;
    if (t->min < 0.0)
        return MCSTAT_EINVAL;
    if (!(t->mean > 0.0))
        return MCSTAT_EDEGENERATE;
    double s2;
    int e;
    mcstat__moments_var_scaled(t, &s2, &e);
    /* (s / mean)^2 / k in logs: s and the mean may sit at any scale (positive
     * times have s / mean <= sqrt(k), so the ratio itself is moderate) */
    double cv = s2 > 0.0 ? exp(0.5 * log(s2) + (double)e * M_LN2 - log(t->mean)) : 0.0;
    *log_tau = log(t->mean);
    *v = cv * cv / (double)t->n;
    return isfinite(*v) ? MCSTAT_OK : MCSTAT_ENUMERIC;
}

int mcstat_efficiency_test(const mcstat_moments *x, const mcstat_moments *y, const mcstat_moments *time_x,
                           const mcstat_moments *time_y, double ratio, int alternative, double alpha,
                           mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !y || !time_x || !time_y || !out || !(ratio > 0.0) || !isfinite(ratio) ||
        !valid_alternative(alternative) || !valid_alpha(alpha))
        return MCSTAT_EINVAL;
    int st;
    if ((st = mcstat__moments_check(x)) || (st = mcstat__moments_check(y)))
        return st;
    double lvx, vx, lvy, vy, ltx, wx, lty, wy;
    log_var_part(x, &lvx, &vx);
    log_var_part(y, &lvy, &vy);
    if ((st = log_time_part(time_x, &ltx, &wx)) || (st = log_time_part(time_y, &lty, &wy)))
        return st;

    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = MCSTAT_TEST_EFFICIENCY;
    r.method = MCSTAT_METHOD_ASYMPTOTIC;
    r.alternative = alternative;
    r.alpha = alpha;
    r.null_value = ratio;
    r.n[0] = x->n;
    r.n[1] = y->n;

    /* log rho = log s_y^2 - log s_x^2 + log tau_y - log tau_x */
    double lvr = lvy - lvx, ltr = lty - ltx, lrho = lvr + ltr;
    double var = vx + vy + wx + wy, se = sqrt(var);
    /* Satterthwaite: (sum V)^2 / sum V_i^2 / df_i, normalised by the largest
     * V; df_i = 2 / V_i for the variances (at most n - 1), k - 1 for times */
    double vmax = fmax(fmax(vx, vy), fmax(wx, wy));
    double dfx = fmin(2.0 / vx, (double)x->n - 1.0), dfy = fmin(2.0 / vy, (double)y->n - 1.0);
    double a = vx / vmax, b = vy / vmax, c = wx / vmax, d = wy / vmax;
    double den = a * a / dfx + b * b / dfy + c * c / ((double)time_x->n - 1.0) + d * d / ((double)time_y->n - 1.0);
    double df = (a + b + c + d) * (a + b + c + d) / den;
    if (!(df <= DF_MAX)) /* also NaN: not expected, but never passed on */
        df = DF_MAX;
    if (!(se > 0.0) || !isfinite(se) || !isfinite(lrho))
        return MCSTAT_ENUMERIC;

    r.statistic = (lrho - log(ratio)) / se;
    r.df[0] = df;
    r.std_error = se;
    r.estimate[0] = exp(lrho);
    r.estimate[1] = exp(lvr);
    r.eff_var_ratio = exp(lvr);
    r.eff_time_ratio = exp(ltr);
    r.eff_se_log_var_x = sqrt(vx);
    r.eff_se_log_var_y = sqrt(vy);
    r.eff_se_log_time_x = sqrt(wx);
    r.eff_se_log_time_y = sqrt(wy);
    r.eff_batches_x = time_x->n > INT32_MAX ? INT32_MAX : (int32_t)time_x->n;
    r.eff_batches_y = time_y->n > INT32_MAX ? INT32_MAX : (int32_t)time_y->n;

    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    mcstat__qcache_use(&qc, MCSTAT_Q_T, df, 0.0);
    mcstat_tails t;
    if ((st = mcstat__t_tails(r.statistic, df, &t)) || (st = mcstat__finish(&r, &t, mcstat__qcache_quantile, &qc)))
        return st;
    /* {rho : c0 <= (log rho_hat - log rho) / se <= c1} */
    /* exp(-Inf) = 0 and exp(Inf) = Inf: the open ends of one-sided intervals */
    r.conf_int[0] = exp(lrho - r.critical[1] * se);
    r.conf_int[1] = exp(lrho - r.critical[0] * se);
    if (isnan(r.p_value) || isnan(r.conf_int[0]) || isnan(r.conf_int[1]))
        return MCSTAT_ENUMERIC;
    *out = r;
    return MCSTAT_OK;
}
