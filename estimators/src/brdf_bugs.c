/*
 * brdf_bugs.c - planted bugs in the BRDF samplers (documented in mcest.h):
 * realistic mistakes in the half-vector warps, for measuring how quickly a
 * goodness-of-fit test of the directions catches them.  The density the
 * sampler claims (mcest_brdf_pdf) stays the correct one.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <string.h>

/* Roughness 10% too large: Ward alpha * 1.1; Ashikhmin-Shirley n / 1.21,
 * the same widening (n ~ 2/alpha^2 for narrow lobes). */
#define BUG_ROUGH 1.1

/* The sin(theta) of d(omega) forgotten.  Correct warps give the half
 * vector's polar radius r (Ward: the slope tan theta_h; Ashikhmin-Shirley:
 * theta_h) a Rayleigh-like law, r^2 exponential, because the density per
 * d(theta) carries sin(theta) ~ theta; without it the law is half-normal.
 * With r^2 = 2 E sigma^2 (E exponential), r |cos(2 pi u3)| is exactly the
 * half-normal of the same sigma (Box-Muller), which is what a derivation
 * with d(omega) = d(theta) d(phi) yields for a narrow lobe. */
static void jacobian_bug(const mcest_brdf *b, const double *wo, double u1, double u2, double u3, double *wi)
{
    double f = fabs(cos(2.0 * M_PI * u3));
    double h[3];
    if (b->model == MCEST_WARD) {
        double g = sqrt(-log1p(-u1)) * f;
        double s, c;
        mcest_sincos(2.0 * M_PI * u2, &s, &c);
        double hv[3] = {g * b->rough_x * c, g * b->rough_y * s, 1.0};
        double l = norm3(hv);
        for (int i = 0; i < 3; i++)
            h[i] = hv[i] / l;
    } else {
        double s, c;
        mcest_sincos(2.0 * M_PI * u1, &s, &c);
        double px = sqrt(b->rough_y + 1.0) * c, py = sqrt(b->rough_x + 1.0) * s;
        double l = hypot(px, py);
        double cp = px / l, sp = py / l;
        double e = b->rough_x * cp * cp + b->rough_y * sp * sp;
        double ct = exp(log1p(-u2) / (e + 1.0));
        double th = acos(fmin(1.0, ct)) * f;
        double st = sin(th);
        h[0] = st * cp, h[1] = st * sp, h[2] = cos(th);
    }
    double oh = dot3(wo, h);
    for (int i = 0; i < 3; i++)
        wi[i] = 2.0 * oh * h[i] - wo[i];
}

/* The half-vector sampler with `bug`. */
static void spec_sample_bug(const mcest_brdf *b0, const double *wo, int bug, double u1, double u2, double u3,
                            double *wi)
{
    mcest_brdf b = *b0;
    switch (bug) {
    case MCEST_SAMPLER_BUG_ROUGHNESS:
        if (b.model == MCEST_WARD) {
            b.rough_x *= BUG_ROUGH;
            b.rough_y *= BUG_ROUGH;
        } else {
            b.rough_x /= BUG_ROUGH * BUG_ROUGH;
            b.rough_y /= BUG_ROUGH * BUG_ROUGH;
        }
        break;
    case MCEST_SAMPLER_BUG_AXES_SWAPPED: {
        double t = b.rough_x;
        b.rough_x = b.rough_y;
        b.rough_y = t;
        break;
    }
    case MCEST_SAMPLER_BUG_PHI_HALF:
        /* the azimuth's uniform number is u2 for Ward, u1 for A-S */
        if (b.model == MCEST_WARD)
            u2 *= 0.5;
        else
            u1 *= 0.5;
        break;
    case MCEST_SAMPLER_BUG_JACOBIAN:
        jacobian_bug(&b, wo, u1, u2, u3, wi);
        return;
    default:
        break;
    }
    mcest_brdf_spec_sample(&b, wo, u1, u2, wi);
}

int mcest_brdf_sample_bug(const mcest_brdf_plan *plan, int bug, uint64_t seed, uint64_t first_index,
                          size_t n, double *wi)
{
    if (!mcest_plan_ok(plan) || (n > 0 && !wi) || bug < MCEST_SAMPLER_BUG_NONE || bug > MCEST_SAMPLER_BUG_JACOBIAN)
        return MCEST_EINVAL;
    if (bug == MCEST_SAMPLER_BUG_NONE)
        return mcest_brdf_sample(plan, seed, first_index, n, wi, NULL);
    /* the tag of mcest_brdf_sample with the bug in its low byte: independent streams per bug */
    uint64_t tag = mcest_tag(MCEST_DOMAIN_BRDF_SAMPLE, (uint64_t)plan->brdf.model, (uint64_t)bug);
    for (size_t k = 0; k < n; k++) {
        mcest_u64x4 r = mcest_random_block(seed, tag, first_index + k, 0);
        double *w = wi + 3 * k;
        double u1 = u01(r.v[1]), u2 = u01(r.v[2]);
        if (u01(r.v[0]) < plan->mix) { /* the cosine-weighted component has no bug */
            double s, c;
            mcest_sincos(2.0 * M_PI * u2, &s, &c);
            double rho = sqrt(u1);
            w[0] = rho * c;
            w[1] = rho * s;
            w[2] = sqrt(1.0 - u1);
        } else {
            spec_sample_bug(&plan->brdf, plan->wo, bug, u1, u2, u01(r.v[3]), w);
        }
    }
    return MCEST_OK;
}

int mcest_sampler_bug_parse(const char *name, int *bug)
{
    if (!bug)
        return MCEST_EINVAL;
    if (!name || !name[0] || !strcmp(name, "none"))
        *bug = MCEST_SAMPLER_BUG_NONE;
    else if (!strcmp(name, "roughness"))
        *bug = MCEST_SAMPLER_BUG_ROUGHNESS;
    else if (!strcmp(name, "axes_swapped"))
        *bug = MCEST_SAMPLER_BUG_AXES_SWAPPED;
    else if (!strcmp(name, "phi_half"))
        *bug = MCEST_SAMPLER_BUG_PHI_HALF;
    else if (!strcmp(name, "jacobian"))
        *bug = MCEST_SAMPLER_BUG_JACOBIAN;
    else
        return MCEST_EINVAL;
    return MCEST_OK;
}

const char *mcest_sampler_bug_name(int bug)
{
    switch (bug) {
    case MCEST_SAMPLER_BUG_NONE: return "none";
    case MCEST_SAMPLER_BUG_ROUGHNESS: return "roughness";
    case MCEST_SAMPLER_BUG_AXES_SWAPPED: return "axes_swapped";
    case MCEST_SAMPLER_BUG_PHI_HALF: return "phi_half";
    case MCEST_SAMPLER_BUG_JACOBIAN: return "jacobian";
    default: return NULL;
    }
}
