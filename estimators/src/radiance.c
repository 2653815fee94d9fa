/*
 * radiance.c - the analytic environment and the two estimators of
 * reflected radiance of section 3.3 (formulas in mcest.h).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

double mcest_env(const double *w)
{
    static const double d[3] = {0.3, -0.4, 0.86602540378443864676};
    double x = w[0], y = w[1];
    return 1.0 + 0.5 * (x * x * x - 3.0 * x * y * y) + 0.3 * cos(12.0 * y) +
           4.0 * exp(20.0 * (dot3(w, d) - 1.0));
}

int mcest_environment_radiance(const double *w, size_t n, double *L)
{
    if (n > 0 && (!w || !L))
        return MCEST_EINVAL;
    for (size_t k = 0; k < n; k++) {
        const double *v = w + 3 * k;
        if (!finite3(v))
            return MCEST_EINVAL;
        double l = norm3(v);
        if (!(l > 0.0))
            return MCEST_EINVAL;
        double u[3] = {v[0] / l, v[1] / l, v[2] / l};
        L[k] = mcest_env(u);
    }
    return MCEST_OK;
}

int mcest_reflected_radiance(const mcest_brdf_plan *plan, int method, uint64_t seed,
                             uint64_t first_index, size_t n, uint64_t max_trials, double *out)
{
    if (!mcest_plan_ok(plan) || (n > 0 && !out))
        return MCEST_EINVAL;
    if (method < MCEST_RR_SAMPLING || method > MCEST_RR_REJECTION_UNBIASED)
        return MCEST_EINVAL;
    uint64_t tag = mcest_tag(MCEST_DOMAIN_RR, (uint64_t)method, (uint64_t)plan->brdf.model);
    if (!(plan->bound > 0.0)) { /* f = 0 */
        for (size_t k = 0; k < n; k++)
            out[k] = 0.0;
        return MCEST_OK;
    }
    if (method == MCEST_RR_SAMPLING) {
        for (size_t k = 0; k < n; k++) {
            mcest_u64x4 r = mcest_random_block(seed, tag, first_index + k, 0);
            double wi[3];
            mcest_plan_propose(plan, r.v, wi);
            /* f cos / p with p the sampler's true density; 0 below the horizon */
            out[k] = wi[2] > 0.0 ? mcest_plan_ratio(plan, wi) * mcest_env(wi) : 0.0;
        }
        return MCEST_OK;
    }
    if (method == MCEST_RR_REJECTION && !plan->has_albedo)
        return MCEST_ENOTREADY;
    uint64_t trials = 0;
    for (size_t k = 0; k < n; k++) {
        double wi[3];
        int st = mcest_exact_one(plan, seed, tag, first_index + k, max_trials, wi, &trials);
        if (st != MCEST_OK)
            return st;
        double albedo = plan->albedo;
        if (method == MCEST_RR_REJECTION_UNBIASED) {
            /* An independent unbiased estimate of the albedo: f cos / q at
             * one more proposal, drawn from a block the rejection loop
             * never reaches (blocks count up from 0). */
            mcest_u64x4 r = mcest_random_block(seed, tag, first_index + k, UINT64_MAX);
            double w2[3];
            mcest_plan_propose(plan, r.v, w2);
            albedo = mcest_plan_ratio(plan, w2);
        }
        out[k] = albedo * mcest_env(wi);
    }
    return MCEST_OK;
}

int mcest_reflected_radiance_reference(const mcest_brdf_plan *plan, double rel_tol, double *Lr)
{
    if (!mcest_plan_ok(plan) || !Lr || !(rel_tol >= 1e-13 && rel_tol <= 1e-2))
        return MCEST_EINVAL;
    double v, e;
    int st = mcest_plan_integrate(plan, mcest_env, rel_tol, &v, &e);
    *Lr = v;
    return st;
}
