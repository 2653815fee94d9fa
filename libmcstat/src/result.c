/*
 * result.c - the parts of a result every test shares: p-value for the
 * alternative, critical values, rejection and the three-way decision.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>
#include <string.h>

void mcstat__result_clear(mcstat_result *r)
{
    memset(r, 0, sizeof *r);
    r->statistic = r->df[0] = r->df[1] = NAN;
    r->p_value = NAN;
    r->conf_int[0] = r->conf_int[1] = NAN;
    r->estimate[0] = r->estimate[1] = NAN;
    r->null_value = r->alpha = NAN;
    r->critical[0] = r->critical[1] = NAN;
    r->std_error = NAN;
}

int mcstat__finish(mcstat_result *r, const mcstat_tails *t, mcstat_quantile_fn quantile, const void *ctx)
{
    const double alpha = r->alpha;
    int st, low_side;
    double c0 = NAN, c1 = NAN;
    /* quantile == NULL: no critical values (the caller skips intervals) */
    switch (r->alternative) {
    case MCSTAT_TWO_SIDED:
        /* 2 min(P, Q): the small tail is computed directly, never as 1 - P */
        low_side = t->p < t->q;
        r->p_value = fmin(1.0, 2.0 * (low_side ? t->p : t->q));
        if (quantile && ((st = quantile(0.5 * alpha, 0, ctx, &c0)) || (st = quantile(0.5 * alpha, 1, ctx, &c1))))
            return st;
        break;
    case MCSTAT_LESS:
        low_side = 1;
        r->p_value = t->p;
        /* quantile(0, upper) is the top of the support: no upper critical value */
        if (quantile && ((st = quantile(alpha, 0, ctx, &c0)) || (st = quantile(0.0, 1, ctx, &c1))))
            return st;
        break;
    default:
        low_side = 0;
        r->p_value = t->q;
        if (quantile && ((st = quantile(0.0, 0, ctx, &c0)) || (st = quantile(alpha, 1, ctx, &c1))))
            return st;
        break;
    }
    if (!quantile)
        c0 = c1 = NAN;
    /* c0 <= c1 for alpha < 1; at alpha within a few ulps of 1 both two-sided
     * values are the median, solved separately, and may cross by rounding
     * (F with df (3e8, 1): by 10 ulps).  Ordered, they meet in the middle. */
    if (c0 > c1)
        c0 = c1 = c0 + 0.5 * (c1 - c0);
    r->critical[0] = c0;
    r->critical[1] = c1;
    r->reject = r->p_value <= alpha;
    r->decision = r->reject ? (low_side ? MCSTAT_DECISION_LESS : MCSTAT_DECISION_GREATER) : MCSTAT_DECISION_EQUAL;
    return MCSTAT_OK;
}

/* ---- the p-value in log scale -------------------------------------------- */

/* log p for `alternative` from the two log tails: two-sided
 * log 2 + the smaller one, capped at 0 (p = min(1, 2 min(P, Q))). */
static double log_p_of(const mcstat_tails *t, int alternative)
{
    if (alternative == MCSTAT_LESS)
        return t->logp;
    if (alternative == MCSTAT_GREATER)
        return t->logq;
    double lp = M_LN2 + fmin(t->logp, t->logq);
    return lp > 0.0 ? 0.0 : lp;
}

static int valid_df(double df)
{
    return df > 0.0 && isfinite(df); /* the distributions' domain (dist.c) */
}

int mcstat_result_log_p_value(const mcstat_result *r, double *log_p)
{
    MCSTAT_IEEE_SCOPE();
    if (!r || !log_p || !valid_alternative(r->alternative))
        return MCSTAT_EINVAL;
    mcstat_tails t, u;
    int st;
    double lp;
    switch (r->test) {
    case MCSTAT_TEST_T_1:
    case MCSTAT_TEST_T_2:
    case MCSTAT_TEST_T_2_POOLED:
    case MCSTAT_TEST_T_PAIRED:
    case MCSTAT_TEST_EFFICIENCY: /* a t on Satterthwaite's df, like Welch's */
        if (isnan(r->statistic) || !valid_df(r->df[0]))
            return MCSTAT_EINVAL;
        if ((st = mcstat__t_tails(r->statistic, r->df[0], &t)))
            return st;
        lp = log_p_of(&t, r->alternative);
        break;
    case MCSTAT_TEST_VAR_1:
    case MCSTAT_TEST_CHISQ_GOF: /* upper tail: its alternative is GREATER */
        if (isnan(r->statistic) || !valid_df(r->df[0]))
            return MCSTAT_EINVAL;
        if ((st = mcstat__chisq_tails(r->statistic, r->df[0], &t)))
            return st;
        lp = log_p_of(&t, r->alternative);
        break;
    case MCSTAT_TEST_VAR_2:
        if (isnan(r->statistic) || !valid_df(r->df[0]) || !valid_df(r->df[1]))
            return MCSTAT_EINVAL;
        if ((st = mcstat__f_tails(r->statistic, r->df[0], r->df[1], &t)))
            return st;
        lp = log_p_of(&t, r->alternative);
        break;
    case MCSTAT_TEST_EQUIV_1:
    case MCSTAT_TEST_EQUIV_2:
        /* the larger of the one-sided p's: "> lower" is the upper tail at
         * tost_t_lower, "< upper" the lower tail at tost_t_upper */
        if (isnan(r->tost_t_lower) || isnan(r->tost_t_upper) || !valid_df(r->df[0]))
            return MCSTAT_EINVAL;
        if ((st = mcstat__t_tails(r->tost_t_lower, r->df[0], &t)) ||
            (st = mcstat__t_tails(r->tost_t_upper, r->df[0], &u)))
            return st;
        lp = fmax(t.logq, u.logp);
        break;
    case MCSTAT_TEST_BINOM:
        lp = r->binom_log_p_value;
        break;
    case MCSTAT_TEST_SEQ_MEAN_1:
    case MCSTAT_TEST_SEQ_MEAN_2:
    case MCSTAT_TEST_SEQ_VAR_1:
    case MCSTAT_TEST_SEQ_VAR_2:
        /* the anytime p-value is 1 / (the running maximum of the e-value) */
        if (isnan(r->seq_log_e_max))
            return MCSTAT_EINVAL;
        lp = fmin(0.0, -r->seq_log_e_max);
        break;
    case MCSTAT_TEST_KS_2:
        if (isnan(r->statistic) || !(r->p_value >= 0.0 && r->p_value <= 1.0))
            return MCSTAT_EINVAL;
        /* Kolmogorov's limit has a log form; exact and simulated p-values
         * are the logs of what the test computed */
        if (r->method == MCSTAT_METHOD_ASYMPTOTIC && r->ks_weight == MCSTAT_KS_WEIGHT_NONE)
            lp = mcstat__ks_asymp_log_sf(r->n[0], r->n[1], r->alternative == MCSTAT_TWO_SIDED, r->statistic);
        else
            lp = log(r->p_value);
        break;
    default:
        return MCSTAT_EINVAL;
    }
    if (isnan(lp))
        return MCSTAT_EINVAL;
    *log_p = lp;
    return MCSTAT_OK;
}

/* ---- the interval at another level ---------------------------------------- */

/* v * s / c without intermediate over- or underflow (v, s, c >= 0 finite,
 * c > 0): the mantissas multiply in [1/4, 2), the exponents add. */
static double mul_div(double v, double s, double c)
{
    int ev, es, ec;
    double fv = frexp(v, &ev), fs = frexp(s, &es), fc = frexp(c, &ec);
    double e = (double)ev + (double)es - (double)ec;
    int ei = e > 4000.0 ? 4000 : e < -4000.0 ? -4000 : (int)e;
    return ldexp(fv * fs / fc, ei);
}

/* A variance (or ratio) bound null * stat / c, c the quantile of tail
 * `upper` at p; where c leaves the normal doubles its logarithm is used. */
static int var_bound(const mcstat_result *r, double p, int upper, double *out)
{
    double c, z;
    int f = r->test == MCSTAT_TEST_VAR_2;
    int st = f ? mcstat_f_quantile(p, r->df[0], r->df[1], upper, &c) : mcstat_chisq_quantile(p, r->df[0], upper, &c);
    if (st)
        return st;
    if (c >= DBL_MIN && c <= DBL_MAX) {
        *out = mul_div(r->null_value, r->statistic, c);
        return MCSTAT_OK;
    }
    st = f ? mcstat__f_log_quantile(p, r->df[0], r->df[1], upper, &z) : mcstat__chisq_log_quantile(p, r->df[0], upper, &z);
    if (st)
        return st;
    if (r->statistic == 0.0) {
        *out = 0.0;
        return MCSTAT_OK;
    }
    *out = exp(log(r->null_value) + log(r->statistic) - z);
    return MCSTAT_OK;
}

/* a b exactly where Dekker's split cannot overflow (each factor and the
 * product below 2^995); beyond, the rounded product (its error is then far
 * below what the other terms round by). */
static mcstat_dd prod(double a, double b)
{
    double p = a * b;
    if (!(fabs(a) <= 0x1p995 && fabs(b) <= 0x1p995 && fabs(p) <= 0x1p995))
        return (mcstat_dd){p, 0.0};
    return dd_two_prod(a, b);
}

/* est - c se in double-double (est already one). */
static double t_bound(mcstat_dd est, double se, double c)
{
    if (isinf(c))
        return c > 0 ? -INFINITY : INFINITY;
    mcstat_dd cs = prod(-c, se);
    if (!(fabs(cs.hi) <= 0x1p1000) || !(fabs(est.hi) <= 0x1p1000)) /* a sum that may overflow: plain doubles */
        return est.hi + cs.hi;
    mcstat_dd b = dd_add(est, cs);
    return b.hi + b.lo;
}

/* The estimate of a t test's result, from whichever source rounds less:
 * null + t se carries |null| + |t se| ulps, the stored estimates (the mean,
 * or the two means whose difference is exact in double-double) their own
 * magnitude's.  So data near 1e9 tested against 1e9 keep their digits, and
 * so do data far from their null. */
static mcstat_dd t_estimate(const mcstat_result *r, double null, double t)
{
    int two = r->test == MCSTAT_TEST_T_2 || r->test == MCSTAT_TEST_T_2_POOLED || r->test == MCSTAT_TEST_EQUIV_2;
    mcstat_dd ts = prod(t, r->std_error); /* an infinite t (data far from a huge null): the estimates */
    double e_stat = fabs(null) + fabs(ts.hi);
    double e_est = two ? fmax(fabs(r->estimate[0]), fabs(r->estimate[1])) : fabs(r->estimate[0]);
    if (isfinite(e_est) && !(e_stat <= e_est)) {
        mcstat_dd d = two ? dd_two_sum(r->estimate[0], -r->estimate[1]) : (mcstat_dd){r->estimate[0], 0.0};
        if (isfinite(d.hi))
            return d;
    }
    if (!(fabs(ts.hi) <= 0x1p1000) || !(fabs(null) <= 0x1p1000))
        return (mcstat_dd){null + ts.hi, 0.0};
    return dd_add((mcstat_dd){null, 0.0}, ts);
}

int mcstat_result_conf_int(const mcstat_result *r, double confidence_level, double conf_int[2])
{
    MCSTAT_IEEE_SCOPE();
    if (!r || !conf_int || !(confidence_level > 0.0 && confidence_level < 1.0) ||
        !valid_alternative(r->alternative))
        return MCSTAT_EINVAL;
    const double a = 1.0 - confidence_level;
    int alt = r->alternative, st;
    double ci[2], c;
    switch (r->test) {
    case MCSTAT_TEST_T_1:
    case MCSTAT_TEST_T_2:
    case MCSTAT_TEST_T_2_POOLED:
    case MCSTAT_TEST_T_PAIRED:
    case MCSTAT_TEST_EQUIV_1:
    case MCSTAT_TEST_EQUIV_2: {
        /* TOST: its t against the lower bound; its interval is two-sided */
        int tost = r->test == MCSTAT_TEST_EQUIV_1 || r->test == MCSTAT_TEST_EQUIV_2;
        double t = tost ? r->tost_t_lower : r->statistic, null = tost ? r->tost_lower : r->null_value;
        if (tost)
            alt = MCSTAT_TWO_SIDED;
        if (isnan(t) || !isfinite(null) || !(r->std_error > 0.0 && r->std_error <= DBL_MAX) ||
            !valid_df(r->df[0]))
            return MCSTAT_EINVAL;
        if ((st = mcstat_t_quantile(alt == MCSTAT_TWO_SIDED ? 0.5 * a : a, r->df[0], 1, &c)))
            return st;
        mcstat_dd est = t_estimate(r, null, t);
        ci[0] = alt == MCSTAT_LESS ? -INFINITY : t_bound(est, r->std_error, c);
        ci[1] = alt == MCSTAT_GREATER ? INFINITY : t_bound(est, r->std_error, -c);
        break;
    }
    case MCSTAT_TEST_VAR_1:
    case MCSTAT_TEST_VAR_2: {
        /* {v : c0 <= stat null / v <= c1} = [stat null / c1, stat null / c0] */
        if (!(r->statistic >= 0.0 && r->statistic <= DBL_MAX) || !(r->null_value > 0.0 && r->null_value <= DBL_MAX) ||
            !valid_df(r->df[0]) || (r->test == MCSTAT_TEST_VAR_2 && !valid_df(r->df[1])))
            return MCSTAT_EINVAL;
        double p = alt == MCSTAT_TWO_SIDED ? 0.5 * a : a;
        ci[0] = 0.0;
        ci[1] = INFINITY;
        if (alt != MCSTAT_LESS && (st = var_bound(r, p, 1, &ci[0])))
            return st;
        if (alt != MCSTAT_GREATER && (st = var_bound(r, p, 0, &ci[1])))
            return st;
        break;
    }
    case MCSTAT_TEST_EFFICIENCY: {
        /* exp(log rho_hat -+ c se); log rho_hat = log ratio + t se */
        if (!isfinite(r->statistic) || !(r->null_value > 0.0 && r->null_value <= DBL_MAX) ||
            !(r->std_error > 0.0 && r->std_error <= DBL_MAX) || !valid_df(r->df[0]))
            return MCSTAT_EINVAL;
        if ((st = mcstat_t_quantile(alt == MCSTAT_TWO_SIDED ? 0.5 * a : a, r->df[0], 1, &c)))
            return st;
        double lrho = log(r->null_value) + r->statistic * r->std_error;
        ci[0] = alt == MCSTAT_LESS ? 0.0 : exp(lrho - c * r->std_error);
        ci[1] = alt == MCSTAT_GREATER ? INFINITY : exp(lrho + c * r->std_error);
        break;
    }
    case MCSTAT_TEST_BINOM:
        if (!(r->statistic >= 0.0 && r->statistic <= (double)r->n[0]) || r->n[0] == 0)
            return MCSTAT_EINVAL;
        if ((st = mcstat__binom_conf_int(r->statistic, (double)r->n[0], alt, a, ci)))
            return st;
        break;
    default: /* K-S and chi-squared goodness of fit estimate no parameter; a
              * confidence sequence exists only at the level it was run at */
        return MCSTAT_EINVAL;
    }
    if (isnan(ci[0]) || isnan(ci[1]))
        return MCSTAT_ENUMERIC;
    conf_int[0] = ci[0];
    conf_int[1] = ci[1];
    return MCSTAT_OK;
}
