/*
 * check_format.c - the renderer checks' words: route names, what each
 * route checks and cannot see, and the text block of a report.  Every
 * binding prints this text; none composes its own.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "check.h"

#include <stdarg.h>
#include <stdio.h>

static const char *const route_names[MCSTAT_CHECK_ROUTE_COUNT] = {
    "cells", "mass", "pdf_value", "weight", "support", "integrals", "energy", "reciprocity", "ks"};

static const char *const route_meanings[MCSTAT_CHECK_ROUTE_COUNT] = {
    "sample() draws from the density pdf() claims (chi-squared on cells of equal probability)",
    "the share of samples that succeed is the integral of pdf() (exact binomial test)",
    "the pdf sample() reports equals pdf() at the sampled point",
    "the sample weight equals eval/pdf at the sampled point",
    "eval() is positive only where pdf() is (no part of the integrand is never sampled)",
    "integrals of eval() over regions agree between the sample weights and an eval-only estimator (Wald test)",
    "the albedo, the mean weight, is at most 1 (one-sided t test; a phase function's is 1, two-sided)",
    "eval(wi, wo)/|cos wo| equals eval(wo, wi)/|cos wi| (a phase function's eval(wi, wo) equals eval(wo, wi))",
    "the sampled points, resampled by their weights, follow eval() (K-S with Canner's weight on Morton keys)"};

static const char *const route_blind_spots[MCSTAT_CHECK_ROUTE_COUNT] = {
    "a pdf() off by a constant factor; anything about eval() and the weights",
    "errors that move probability within the domain without changing its total",
    "a sampler and a pdf() that are wrong together",
    "eval() and the weight wrong together (the integrals and energy routes see that only against each other)",
    "regions neither the sample nor the eval-only points reach",
    "errors that cancel within a region; needs finite variance",
    "energy lost rather than gained (except for phase functions); needs finite variance",
    "BSDFs that are not reciprocal by design (refraction in radiance mode)",
    "eval() and the weights wrong together; weights beyond the pilot's envelope (then no answer)"};

const char *mcstat_check_route_name(int route)
{
    return route >= 0 && route < MCSTAT_CHECK_ROUTE_COUNT ? route_names[route] : NULL;
}

const char *mcstat_check_route_meaning(int route)
{
    return route >= 0 && route < MCSTAT_CHECK_ROUTE_COUNT ? route_meanings[route] : NULL;
}

const char *mcstat_check_route_blind_spot(int route)
{
    return route >= 0 && route < MCSTAT_CHECK_ROUTE_COUNT ? route_blind_spots[route] : NULL;
}

int mcstat_check_route_parse(const char *name, int *route)
{
    if (!name || !route)
        return MCSTAT_EINVAL;
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        if (strcmp(name, route_names[i]) == 0) {
            *route = i;
            return MCSTAT_OK;
        }
    return MCSTAT_EINVAL;
}

/* ---- text ------------------------------------------------------------------- */

typedef struct text {
    char *buf;
    size_t size, len;
} text;

static void put(text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *dst = t->len < t->size ? t->buf + t->len : NULL;
    size_t room = t->len < t->size ? t->size - t->len : 0;
    int k = vsnprintf(dst, room, fmt, ap);
    va_end(ap);
    if (k > 0)
        t->len += (size_t)k;
}

static void put_point(text *t, const double *x, int dims)
{
    put(t, "(");
    for (int c = 0; c < dims; c++)
        put(t, c ? ", %.6g" : "%.6g", x[c]);
    put(t, ")");
}

static void put_g(text *t, const char *fmt, double v)
{
    if (isnan(v))
        put(t, "%s", "NA");
    else
        put(t, fmt, v);
}

static const char *kind_title(int kind)
{
    switch (kind) {
    case MCSTAT_CHECK_KIND_BSDF: return "BSDF check: do sample(), pdf(), eval() and the weights agree?";
    case MCSTAT_CHECK_KIND_EMITTER: return "Emitter check: do sample(), pdf(), eval() and the weights agree?";
    case MCSTAT_CHECK_KIND_PHASE: return "Phase function check: do sample(), pdf(), eval() and the weights agree?";
    case MCSTAT_CHECK_KIND_MEDIUM:
        return "Distance sampling check: do sample(), pdf(), eval() and the weights agree?";
    default: return "Warp check: does sample() draw what pdf() claims?";
    }
}

static void put_route(text *t, const mcstat_check_report *r, int i)
{
    const mcstat_check_route_result *rr = &r->route[i];
    int dims = mcstat_check_domain_dims(r->domain);
    put(t, "  %-12s", route_names[i]);
    if (rr->state == MCSTAT_CHECK_STATE_SKIPPED) {
        put(t, "skipped\n");
        return;
    }
    if (rr->state == MCSTAT_CHECK_STATE_INVALID) {
        int heavy_w = r->tail_index[0] < 2.0, heavy_v = r->tail_index[1] < 2.0;
        if ((i == MCSTAT_CHECK_ROUTE_ENERGY && heavy_w) || (i == MCSTAT_CHECK_ROUTE_INTEGRALS && (heavy_w || heavy_v))) {
            put(t, "no answer: %s heavy-tailed (tail index below 2: infinite variance), a mean test would be "
                   "invalid\n",
                heavy_w && heavy_v ? "the weights and the eval-only estimates are"
                                   : (heavy_w ? "the weights are" : "the eval-only estimates are"));
        } else if (i == MCSTAT_CHECK_ROUTE_KS && rr->count > 0) {
            put(t, "no answer: %s exceeded its envelope at ", rr->count == 1 ? "a weight" : "eval/table");
            put_point(t, rr->where, dims);
            put(t, " (%.6g > %.6g), so the kept points would not follow eval\n", rr->value[0], rr->value[1]);
        } else {
            put(t, "no answer: %s\n", mcstat_check_why_text(rr->why) && rr->why ? mcstat_check_why_text(rr->why)
                                                                           : "too little to test");
        }
        return;
    }
    if (rr->deterministic && i != MCSTAT_CHECK_ROUTE_ENERGY) {
        put(t, "%-6s %llu of %llu points beyond tolerance", rr->reject ? "FAIL" : "pass",
            (unsigned long long)rr->count, (unsigned long long)rr->checked);
        put(t, "; largest relative difference ");
        put_g(t, "%.3g", rr->effect);
        if (rr->reject) {
            put(t, " at ");
            put_point(t, rr->where, dims);
            put(t, ": %.9g vs %.9g", rr->value[0], rr->value[1]);
        }
        put(t, "\n");
        return;
    }
    if (rr->deterministic) { /* ENERGY with constant weights */
        put(t, "%-6s constant weights: albedo %.9g\n", rr->reject ? "FAIL" : "pass", rr->value[0]);
        return;
    }
    put(t, "%-6s ", rr->reject ? "FAIL" : "pass");
    switch (i) {
    case MCSTAT_CHECK_ROUTE_CELLS: put(t, "X-squared = %.4g, df = %.0f", rr->statistic, rr->df); break;
    case MCSTAT_CHECK_ROUTE_MASS:
        put(t, "success share %.6g vs mass %.6g", rr->statistic, r->mass);
        if (r->lobes > 0) /* the lobe furthest off */
            put(t, "; lobe (%.6g, %.6g, %.6g) share %.6g vs mass %.6g", rr->where[0], rr->where[1], rr->where[2],
                rr->value[0], rr->value[1]);
        if (r->kind == MCSTAT_CHECK_KIND_MEDIUM && !isnan(r->escape_weight))
        {
            put(t, "; escape weights %.6g (se ", r->escape_weight);
            put_g(t, "%.2g", r->escape_weight_se);
            put(t, ") vs T(tmax) %.6g", rr->value[1]);
        }
        break;
    case MCSTAT_CHECK_ROUTE_INTEGRALS: put(t, "W = %.4g, df = %.0f", rr->statistic, rr->df); break;
    case MCSTAT_CHECK_ROUTE_KS:
        put(t, "D2 = %.4g (Canner), %llu resampled points vs %llu from eval", rr->statistic,
            (unsigned long long)rr->count, (unsigned long long)(rr->checked - rr->count));
        break;
    default: put(t, "t = %.4g, df = %.0f", rr->statistic, rr->df); break;
    }
    put(t, ", p-value = ");
    put_g(t, "%.4g", rr->p_value);
    put(t, ", Holm-adjusted ");
    put_g(t, "%.4g", rr->p_adjusted);
    put(t, "\n");
}

static void put_budget(text *t, const mcstat_check_report *r, int i)
{
    const mcstat_check_route_result *rr = &r->route[i];
    if (rr->state != MCSTAT_CHECK_STATE_RAN || (rr->deterministic && i == MCSTAT_CHECK_ROUTE_ENERGY))
        return;
    put(t, "  %-12s", route_names[i]);
    switch (i) {
    case MCSTAT_CHECK_ROUTE_CELLS:
        /* w in the sampler's terms: moving a share q of the probability
         * from one half of the domain to the other gives w = 2 q */
        put(t, "Cohen's w ");
        put_g(t, "%.3g", rr->detectable);
        put(t, ", a sampler moving ");
        put_g(t, "%.3g", 50.0 * rr->detectable);
        put(t, "%% of its probability between two halves of the domain (measured w ");
        put_g(t, "%.3g", rr->effect);
        put(t, "); w = 0.01 needs ");
        put_g(t, "%.3g", rr->n_for_1pct);
        put(t, " samples\n");
        break;
    case MCSTAT_CHECK_ROUTE_MASS:
    case MCSTAT_CHECK_ROUTE_INTEGRALS:
        put(t, i == MCSTAT_CHECK_ROUTE_MASS ? "pdf() off its integral by a relative " : "integrals off by a relative ");
        put_g(t, "%.3g", rr->detectable);
        put(t, " (measured ");
        put_g(t, "%.3g", rr->effect);
        if (isinf(rr->n_for_1pct))
            put(t, "); 1%% is within the integrals' own error, whatever n (more cells or n_eval)\n");
        else {
            put(t, "); 1%% needs ");
            put_g(t, "%.3g", rr->n_for_1pct);
            put(t, " samples\n");
        }
        break;
    case MCSTAT_CHECK_ROUTE_KS:
        put(t, "a sup distance of about ");
        put_g(t, "%.3g", rr->detectable);
        put(t, " between the CDFs (probability ~0.5); ");
        if (isinf(rr->n_for_1pct))
            put(t, "0.01 is beyond its cap of points a side, whatever n\n");
        else {
            put(t, "0.01 needs ");
            put_g(t, "%.3g", rr->n_for_1pct);
            put(t, " samples\n");
        }
        break;
    case MCSTAT_CHECK_ROUTE_ENERGY:
        put(t, r->kind == MCSTAT_CHECK_KIND_PHASE ? "albedo off 1 by " : "albedo above 1 by ");
        put_g(t, "%.3g", rr->detectable);
        put(t, "; 0.01 needs ");
        put_g(t, "%.3g", rr->n_for_1pct);
        put(t, " samples\n");
        break;
    default:
        put(t, "any difference above rtol in a region of probability ");
        put_g(t, "%.3g", rr->detectable);
        put(t, "; a region of 1%% needs %.0f samples\n", rr->n_for_1pct);
        break;
    }
}

int mcstat_check_format(const mcstat_check_report *r, char *buf, size_t size, size_t *length)
{
    MCSTAT_IEEE_SCOPE();
    if (!r || (!buf && size > 0) || r->kind < 0 || r->kind > MCSTAT_CHECK_KIND_MEDIUM ||
        mcstat_check_domain_dims(r->domain) == 0)
        return MCSTAT_EINVAL;
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        if (r->route[i].state < MCSTAT_CHECK_STATE_RAN || r->route[i].state > MCSTAT_CHECK_STATE_INVALID)
            return MCSTAT_EINVAL;
    text t = {buf, size, 0};
    put(&t, "\n\t%s\n\n", kind_title(r->kind));
    if (r->kind == MCSTAT_CHECK_KIND_BSDF || r->kind == MCSTAT_CHECK_KIND_PHASE)
        put(&t, "wi = (%.6g, %.6g, %.6g), ", r->wi[0], r->wi[1], r->wi[2]);
    put(&t, "domain %s, n = %llu samples (%llu failed), alpha = %g\n", mcstat_check_domain_name(r->domain),
        (unsigned long long)r->n, (unsigned long long)r->n_failed, r->alpha);
    if (r->kind == MCSTAT_CHECK_KIND_MEDIUM)
        put(&t, "distances t as points x = 1 - exp(-%.6g t) of [0, 1]; samples that passed the surface count as "
                "failed\n",
            r->sigma_ref);
    put(&t, "cells: %llu from %llu pilot samples; pdf() integrates to %.9g (cubature error %.2g)\n",
        (unsigned long long)r->cells, (unsigned long long)r->n_pilot, r->mass, r->mass_error);
    if (r->kind != MCSTAT_CHECK_KIND_WARP) {
        put(&t, "integral of eval(): %.6g (se %.2g) from the weights, %.6g (se %.2g) from eval() alone\n",
            r->albedo, r->albedo_se, r->albedo_eval, r->albedo_eval_se);
        put(&t, "upper tail index: weights ");
        put_g(&t, "%.3g", r->tail_index[0]);
        put(&t, ", eval-only estimates ");
        put_g(&t, "%.3g", r->tail_index[1]);
        put(&t, "%s\n", r->heavy_tailed ? " (below 2: infinite variance)" : "");
    }
    if (r->lobes > 0)
        put(&t, "discrete lobes: %llu, mass %.9g, albedo %.9g; %llu samples on them (the lines above: the smooth "
                "part)\n",
            (unsigned long long)r->lobes, r->lobe_mass, r->lobe_albedo, (unsigned long long)r->n_lobe);
    /* many zero weights with pdf > 0: most likely failed samples marked by the
     * weight alone, which the mass and cells routes then count as successes */
    if (r->kind != MCSTAT_CHECK_KIND_WARP && r->zero_weight > 0 && r->zero_weight >= r->n / 100)
        put(&t,
            "%llu samples have weight 0 where pdf and eval() are > 0: if sample() failed there, it must "
            "return pdf 0 "
            "(as Mitsuba and pbrt mark a failed sample); counted as successes they enter the mass and "
            "cells routes\n",
            (unsigned long long)r->zero_weight);
    if (r->pdf_without_eval > 0)
        put(&t, "pdf() > 0 where eval() = 0 at %llu points (samples wasted there; not an error)\n",
            (unsigned long long)r->pdf_without_eval);
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        if (r->route[i].state == MCSTAT_CHECK_STATE_RAN && !isnan(r->route[i].resolution)) {
            double res = r->route[i].resolution;
            put(&t, "numerical floor: differences of %.2g relative are rounding, not evidence%s\n", res,
                res == MCSTAT_RESOLUTION_FLOAT32   ? " (every value a float32)"
                : res == MCSTAT_RESOLUTION_FLOAT64 ? " (float64 values)"
                                                          : "");
            break;
        }
    put(&t, "routes:\n");
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        put_route(&t, r, i);
    put(&t, "smallest departure each route detects with probability 0.8 at this budget:\n");
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        put_budget(&t, r, i);
    put(&t, "decision at alpha = %g: ", r->alpha);
    int verdict;
    uint32_t open_routes = 0;
    (void)mcstat_check_verdict(r, &verdict, &open_routes);
    if (!r->reject && open_routes) {
        put(&t, "INCONCLUSIVE: no route rejected, but");
        const char *sep = " ";
        for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
            if (open_routes & (1u << i)) {
                put(&t, "%s%s", sep, route_names[i]);
                sep = ", ";
            }
        put(&t, " could not answer:\n");
        for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
            if (open_routes & (1u << i))
                put(&t, "  %-12s%s\n", route_names[i], mcstat_check_why_text(r->route[i].why) && r->route[i].why
                                                          ? mcstat_check_why_text(r->route[i].why)
                                                          : "too little to test");
    } else if (!r->reject) {
        put(&t, "consistent (no route rejected; the battery's error rate is at most alpha)\n");
    } else {
        put(&t, "INCONSISTENT:");
        for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
            if (r->route[i].state == MCSTAT_CHECK_STATE_RAN && r->route[i].reject)
                put(&t, " %s", route_names[i]);
        put(&t, " rejected\n");
    }
    if (length)
        *length = t.len;
    return t.len < size ? MCSTAT_OK : MCSTAT_EBUFSIZE;
}
