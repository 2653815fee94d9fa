/*
 * check_verdict.c - a renderer check's verdict (mcstat.h's section
 * "Renderer checks"): consistent, inconsistent, or inconclusive when a
 * route the check needed could not answer, and the reason in words.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "check.h"

static const char *const why_texts[] = {
    "",
    "the values it averages are heavy-tailed (tail index below 2: infinite variance), so a mean test would "
    "be invalid; more samples do not help: a sampler whose weights are bounded would, or a route that does "
    "not average them",
    "too little to test (too few samples, cells, regions or kept points): more samples (n) would",
    "a ratio exceeded the resampling envelope the pilot set, so the kept points would not follow eval(); "
    "another seed or a larger pilot (n_pilot) would, as would the integrals route, which checks the same claim",
    "nothing to compare: eval() and the weights are 0 wherever looked, or no smooth part is claimed or sampled",
    "a numerical step failed",
    "the integral of pdf() is not known well enough to test against (its cubature and its Monte Carlo "
    "estimate disagree beyond their errors): more cells or eval-only points (n_eval) would"};

static const char *const verdict_names[] = {"consistent", "inconsistent", "inconclusive"};

const char *mcstat_check_why_text(int why)
{
    return why >= 0 && why < (int)(sizeof why_texts / sizeof why_texts[0]) ? why_texts[why] : NULL;
}

const char *mcstat_check_verdict_name(int verdict)
{
    return verdict >= 0 && verdict <= MCSTAT_CHECK_INCONCLUSIVE ? verdict_names[verdict] : NULL;
}

/* A route could not answer, and its claim is not answered by another:
 * KS and INTEGRALS both check eval() against the sampler, and KS's
 * envelope fails by chance on correct models, so KS counts only when
 * INTEGRALS could not answer either (and had something to compare).  A
 * route with nothing to compare (eval and the weights zero wherever
 * looked, no smooth part claimed or sampled) has no claim left open. */
static int unanswered(const mcstat_check_report *r, int i)
{
    const mcstat_check_route_result *rr = &r->route[i];
    if (rr->state != MCSTAT_CHECK_STATE_INVALID || rr->why == MCSTAT_CHECK_WHY_NOTHING)
        return 0;
    const mcstat_check_route_result *in = &r->route[MCSTAT_CHECK_ROUTE_INTEGRALS];
    if (i == MCSTAT_CHECK_ROUTE_KS && (in->state == MCSTAT_CHECK_STATE_RAN || in->why == MCSTAT_CHECK_WHY_NOTHING))
        return 0;
    return 1;
}

int mcstat_check_verdict(const mcstat_check_report *report, int *verdict, uint32_t *unanswered_routes)
{
    if (!report || !verdict)
        return MCSTAT_EINVAL;
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        if (report->route[i].state < MCSTAT_CHECK_STATE_RAN || report->route[i].state > MCSTAT_CHECK_STATE_INVALID)
            return MCSTAT_EINVAL;
    uint32_t mask = 0;
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        if (unanswered(report, i))
            mask |= 1u << i;
    *verdict = report->reject ? MCSTAT_CHECK_INCONSISTENT : (mask ? MCSTAT_CHECK_INCONCLUSIVE : MCSTAT_CHECK_CONSISTENT);
    if (unanswered_routes)
        *unanswered_routes = mask;
    return MCSTAT_OK;
}
