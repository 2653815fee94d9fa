/*
 * result.c - the parts of a result every test shares: p-value for the
 * alternative, critical values, rejection and the three-way decision.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

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
    r->critical[0] = c0;
    r->critical[1] = c1;
    r->reject = r->p_value <= alpha;
    r->decision = r->reject ? (low_side ? MCSTAT_DECISION_LESS : MCSTAT_DECISION_GREATER) : MCSTAT_DECISION_EQUAL;
    return MCSTAT_OK;
}

void mcstat__qcache_init(mcstat_qcache *c)
{
    memset(c, 0, sizeof *c);
}

void mcstat__qcache_use(mcstat_qcache *c, int kind, double df1, double df2)
{
    if (c->kind != kind || c->df1 != df1 || c->df2 != df2) {
        c->kind = kind;
        c->df1 = df1;
        c->df2 = df2;
        c->n = c->next = 0;
    }
}

int mcstat__qcache_quantile(double p, int upper, const void *ctx, double *x)
{
    mcstat_qcache *c = (mcstat_qcache *)ctx;
    for (int i = 0; i < c->n; i++) {
        if (c->e[i].p != p)
            continue;
        if (c->e[i].upper == upper) {
            *x = c->e[i].x;
            return MCSTAT_OK;
        }
        if (c->kind == MCSTAT_Q_T) { /* t quantiles of the two tails are negatives */
            *x = -c->e[i].x;
            return MCSTAT_OK;
        }
    }
    int st;
    switch (c->kind) {
    case MCSTAT_Q_T: st = mcstat_t_quantile(p, c->df1, upper, x); break;
    case MCSTAT_Q_CHISQ: st = mcstat_chisq_quantile(p, c->df1, upper, x); break;
    case MCSTAT_Q_F: st = mcstat_f_quantile(p, c->df1, c->df2, upper, x); break;
    default: return MCSTAT_EINVAL;
    }
    if (st)
        return st;
    c->e[c->next].p = p;
    c->e[c->next].upper = upper;
    c->e[c->next].x = *x;
    c->next ^= 1;
    if (c->n < 2)
        c->n++;
    return MCSTAT_OK;
}
