/*
 * escalation.c - the two-stage test of Bauer & Koehne (1994) that a test
 * suite uses instead of rerunning a suspicious statistical test: stage 1
 * rejects at alpha1, passes above alpha0, and in between a second,
 * independent stage decides on Fisher's product p1 p2 <= c.
 *
 * Under H0 with p1, p2 independent and uniform,
 *   P(reject) = alpha1 + integral_{alpha1}^{alpha0} P(p2 <= c / p1) dp1
 *             = alpha1 + c ln(alpha0 / alpha1)       when c <= alpha1,
 * so c = (alpha - alpha1) / ln(alpha0 / alpha1) spends alpha exactly.  The
 * condition c <= alpha1 keeps c / p1 <= 1 over the escalation band; the
 * design is refused where it fails rather than silently spending less.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

static int in_open_unit(double x)
{
    return x > 0.0 && x < 1.0;
}

int mcstat_escalation_design(double alpha, double share1, double alpha0, mcstat_escalation *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out || !in_open_unit(alpha) || !in_open_unit(share1))
        return MCSTAT_EINVAL;
    double alpha1 = share1 * alpha;
    if (!(alpha0 > alpha1 && alpha0 <= 1.0))
        return MCSTAT_EINVAL;
    /* log1p keeps the band's width accurate when alpha0 is just above alpha1 */
    double band = log1p((alpha0 - alpha1) / alpha1);
    double c = (alpha - alpha1) / band;
    if (!(c <= alpha1) || !(c > 0.0))
        return MCSTAT_EINVAL;
    out->alpha = alpha;
    out->alpha1 = alpha1;
    out->alpha0 = alpha0;
    out->c = c;
    return MCSTAT_OK;
}

static int valid_design(const mcstat_escalation *d)
{
    return in_open_unit(d->alpha) && d->alpha1 > 0.0 && d->alpha1 < d->alpha && d->alpha0 > d->alpha1 &&
           d->alpha0 <= 1.0 && d->c > 0.0 && d->c <= d->alpha1;
}

int mcstat_escalation_decide(const mcstat_escalation *design, double p1, double p2, int *decision)
{
    MCSTAT_IEEE_SCOPE();
    if (!design || !decision || !valid_design(design) || !(p1 >= 0.0 && p1 <= 1.0))
        return MCSTAT_EINVAL;
    int stage1 = p1 <= design->alpha1   ? MCSTAT_ESCALATION_REJECT
                 : p1 > design->alpha0 ? MCSTAT_ESCALATION_PASS
                                       : MCSTAT_ESCALATION_CONTINUE;
    if (isnan(p2)) {
        *decision = stage1;
        return MCSTAT_OK;
    }
    if (!(p2 >= 0.0 && p2 <= 1.0) || stage1 != MCSTAT_ESCALATION_CONTINUE)
        return MCSTAT_EINVAL;
    *decision = p1 * p2 <= design->c ? MCSTAT_ESCALATION_REJECT : MCSTAT_ESCALATION_PASS;
    return MCSTAT_OK;
}
