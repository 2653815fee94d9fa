/*
 * irradiance.c - the four irradiance estimators U, C, A, S of section 3.1
 * and the planted bugs of section 3.4, in batches.
 *
 * Estimate number i uses Philox block (i, 0) under key (seed, tag(method,
 * bug)): two uniforms from its first two words.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#define _GNU_SOURCE
#include "internal.h"

static inline int cone_hit(const mcest_irradiance_plan *P, const double *w)
{
    return dot3(w, P->edge_n[0]) >= 0.0 && dot3(w, P->edge_n[1]) >= 0.0 &&
           dot3(w, P->edge_n[2]) >= 0.0;
}

static void est_U(const mcest_irradiance_plan *P, uint64_t seed, uint64_t tag, uint64_t first,
                  size_t n, double *out)
{
    const double k = 2.0 * M_PI * P->radiance;
    for (size_t j = 0; j < n; j++) {
        mcest_u64x4 r = mcest_random_block(seed, tag, first + j, 0);
        double z = u01(r.v[0]); /* uniform on the hemisphere: z uniform */
        double s, c;
        mcest_sincos(2.0 * M_PI * u01(r.v[1]), &s, &c);
        double rho = sqrt((1.0 - z) * (1.0 + z));
        double w[3] = {rho * c, rho * s, z};
        out[j] = cone_hit(P, w) ? k * z : 0.0;
    }
}

static void est_C(const mcest_irradiance_plan *P, uint64_t seed, uint64_t tag, uint64_t first,
                  size_t n, double *out)
{
    const double k = M_PI * P->radiance;
    for (size_t j = 0; j < n; j++) {
        mcest_u64x4 r = mcest_random_block(seed, tag, first + j, 0);
        double u = u01(r.v[0]); /* Malley: uniform disk, lifted */
        double s, c;
        mcest_sincos(2.0 * M_PI * u01(r.v[1]), &s, &c);
        double rho = sqrt(u);
        double w[3] = {rho * c, rho * s, sqrt(1.0 - u)};
        out[j] = cone_hit(P, w) ? k : 0.0;
    }
}

static void est_A(const mcest_irradiance_plan *P, int bug, uint64_t seed, uint64_t tag,
                  uint64_t first, size_t n, double *out)
{
    const double *v0 = P->v[0], *e1 = P->e01, *e2 = P->e02;
    for (size_t j = 0; j < n; j++) {
        mcest_u64x4 r = mcest_random_block(seed, tag, first + j, 0);
        double u1 = u01(r.v[0]), u2 = u01(r.v[1]);
        double b1, b2;
        if (bug == MCEST_BUG_BARYCENTRIC) {
            b1 = u1; /* ERRATA 8: not area-preserving */
            b2 = (1.0 - u1) * u2;
        } else {
            double su = sqrt(u1);
            b1 = 1.0 - su;
            b2 = u2 * su;
        }
        double y0 = v0[0] + b1 * e1[0] + b2 * e2[0];
        double y1 = v0[1] + b1 * e1[1] + b2 * e2[1];
        double y2 = v0[2] + b1 * e1[2] + b2 * e2[2];
        double r2 = y0 * y0 + y1 * y1 + y2 * y2;
        double cz = y2 > 0.0 ? y2 : 0.0; /* below the horizon: 0 */
        double e;
        switch (bug) {
        case MCEST_BUG_NO_COSINE: /* L area h / r^3, above the horizon */
            e = y2 > 0.0 ? P->a_coef / (r2 * sqrt(r2)) : 0.0;
            break;
        case MCEST_BUG_NO_JACOBIAN: /* L area cos */
            e = P->la_coef * cz / sqrt(r2);
            break;
        default: /* L area h z / r^4 */
            e = P->a_coef * cz / (r2 * r2);
            break;
        }
        out[j] = e;
    }
}

static void est_S(const mcest_irradiance_plan *P, uint64_t seed, uint64_t tag, uint64_t first,
                  size_t n, double *out)
{
    const double omega = P->solid_angle, k = P->radiance * omega;
    const double o0 = P->fan[0][16];
    const int two = P->n_fan == 2;
    for (size_t j = 0; j < n; j++) {
        mcest_u64x4 r = mcest_random_block(seed, tag, first + j, 0);
        double x = u01(r.v[0]) * omega, u2 = u01(r.v[1]);
        const double *fan = P->fan[0];
        if (two && x >= o0) {
            fan = P->fan[1];
            x -= o0;
        }
        double z = mcest_sph_tri_sample_z(fan, 0.5 * x, u2);
        out[j] = z > 0.0 ? k * z : 0.0;
    }
}

int mcest_irradiance_estimates(const mcest_irradiance_plan *plan, int method, int bug,
                               uint64_t seed, uint64_t first_index, size_t n, double *out)
{
    if (!plan || plan->version != MCEST_IRRADIANCE_PLAN_VERSION || (!out && n > 0))
        return MCEST_EINVAL;
    if (method < MCEST_U || method > MCEST_S || bug < MCEST_BUG_NONE || bug > MCEST_BUG_NO_JACOBIAN)
        return MCEST_EINVAL;
    if (bug != MCEST_BUG_NONE && method != MCEST_A)
        return MCEST_EUNSUPPORTED;
    if (plan->n_poly == 0 || plan->radiance == 0.0) {
        /* Nothing visible (or nothing emitted): every estimator is 0. */
        for (size_t j = 0; j < n; j++)
            out[j] = 0.0;
        return MCEST_OK;
    }
    uint64_t tag = mcest_tag(MCEST_DOMAIN_IRRADIANCE, (uint64_t)method, (uint64_t)bug);
    switch (method) {
    case MCEST_U: est_U(plan, seed, tag, first_index, n, out); break;
    case MCEST_C: est_C(plan, seed, tag, first_index, n, out); break;
    case MCEST_A: est_A(plan, bug, seed, tag, first_index, n, out); break;
    default:
        if (plan->n_fan == 0) {
            for (size_t j = 0; j < n; j++)
                out[j] = 0.0;
        } else {
            est_S(plan, seed, tag, first_index, n, out);
        }
        break;
    }
    return MCEST_OK;
}

int mcest_irradiance(const mcest_scene *scene, int method, int bug, uint64_t seed,
                     uint64_t first_index, size_t n, double *out)
{
    mcest_irradiance_plan P;
    int st = mcest_irradiance_plan_init(scene, &P);
    if (st != MCEST_OK)
        return st;
    return mcest_irradiance_estimates(&P, method, bug, seed, first_index, n, out);
}

int mcest_scene_paper(mcest_scene *out)
{
    if (!out)
        return MCEST_EINVAL;
    static const mcest_scene paper = {
        {-0.6, -0.4, 1.0, 0.9, -0.3, 1.3, 0.1, 0.9, 0.8},
        {0.0, 0.0, 0.0},
        {0.0, 0.0, 1.0},
        1.0};
    *out = paper;
    return MCEST_OK;
}
