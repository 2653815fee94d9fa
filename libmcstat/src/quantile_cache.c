/*
 * quantile_cache.c - the last two quantiles of one t, chi-squared or F
 * distribution, so that row-wise tests with rows of equal degrees of freedom
 * solve each critical value once.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <string.h>

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
