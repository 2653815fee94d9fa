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
