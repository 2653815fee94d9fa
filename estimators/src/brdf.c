/*
 * brdf.c - Ward's and Ashikhmin-Shirley's anisotropic BRDFs: evaluation,
 * half-vector sampling, and the true densities of the sampled directions
 * (sections 3.2 and 3.3; formulas in mcest.h).
 *
 * Numerical traps avoided:
 *   - Ward's exponent tan^2(theta_h)(cos^2 phi/ax^2 + sin^2 phi/ay^2) is
 *     (hx^2/ax^2 + hy^2/ay^2)/hz^2 of the unnormalised h = wi + wo: no
 *     angles, no atan; with alpha = 1e-3 it overflows harmlessly into
 *     exp(-large) = 0, and the sampler's and the BRDF's exponentials are the
 *     same number, so ratios f cos / p are formed analytically (they do not
 *     become 0/0 where both underflow).
 *   - Ward's sampler: tan(phi_h) = (ay/ax) tan(2 pi u2) with the right
 *     quadrant is the direction (ax cos 2 pi u2, ay sin 2 pi u2), and then
 *     cos^2 phi/ax^2 + sin^2 phi/ay^2 = 1/|that|^2, so the half vector is
 *     simply (g ax cos 2 pi u2, g ay sin 2 pi u2, 1), g = sqrt(-ln(1 - u1)).
 *   - Ashikhmin-Shirley's exponent (nu hx^2 + nv hy^2)/(1 - hz^2) is formed
 *     with hx^2 + hy^2 in the denominator (1 - hz^2 cancels near the pole),
 *     and hz^e = exp(e * log1p(-(hx^2 + hy^2))/2): exponents up to 1e7
 *     without pow() of a number rounded to 1.  Its sampler draws
 *     cos(theta_h) = exp(log1p(-u2)/(e+1)) and sin(theta_h) from
 *     -expm1(...) for the same reason.
 *   - sqrt(cos_i) * sqrt(cos_o), not sqrt(cos_i cos_o): the product of two
 *     grazing cosines underflows.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

static inline double pow5(double x)
{
    double x2 = x * x;
    return x2 * x2 * x;
}

int mcest_brdf_valid(const mcest_brdf *b)
{
    if (!b || !isfinite(b->diffuse) || !isfinite(b->specular) || !isfinite(b->rough_x) ||
        !isfinite(b->rough_y))
        return 0;
    if (b->model == MCEST_WARD)
        return b->diffuse >= 0.0 && b->specular >= 0.0 && b->rough_x >= 1e-4 &&
               b->rough_x <= 10.0 && b->rough_y >= 1e-4 && b->rough_y <= 10.0;
    if (b->model == MCEST_ASHIKHMIN_SHIRLEY)
        return b->diffuse >= 0.0 && b->diffuse <= 1.0 && b->specular >= 0.0 &&
               b->specular <= 1.0 && b->rough_x >= 0.0 && b->rough_x <= 1e7 &&
               b->rough_y >= 0.0 && b->rough_y <= 1e7;
    return 0;
}

int mcest_brdf_ward(double rho_d, double rho_s, double alpha_x, double alpha_y, mcest_brdf *out)
{
    mcest_brdf b = {MCEST_WARD, 0, rho_d, rho_s, alpha_x, alpha_y, {0, 0, 0}};
    if (!out || !mcest_brdf_valid(&b))
        return MCEST_EINVAL;
    *out = b;
    return MCEST_OK;
}

int mcest_brdf_ashikhmin_shirley(double rd, double rs, double n_u, double n_v, mcest_brdf *out)
{
    mcest_brdf b = {MCEST_ASHIKHMIN_SHIRLEY, 0, rd, rs, n_u, n_v, {0, 0, 0}};
    if (!out || !mcest_brdf_valid(&b))
        return MCEST_EINVAL;
    *out = b;
    return MCEST_OK;
}

/* Ward's exponent of a (not necessarily unit) half vector with hz > 0. */
static inline double ward_exponent(const mcest_brdf *b, const double *h)
{
    double x = h[0] / b->rough_x, y = h[1] / b->rough_y;
    return (x * x + y * y) / (h[2] * h[2]);
}

/* log(hz^e) of Ashikhmin-Shirley's lobe for a unit half vector. */
static inline double as_log_lobe(const mcest_brdf *b, const double *h)
{
    double hx2 = h[0] * h[0], hy2 = h[1] * h[1], s2 = hx2 + hy2;
    if (!(s2 > 0.0))
        return 0.0;
    double e = (b->rough_x * hx2 + b->rough_y * hy2) / s2;
    return e * 0.5 * log1p(-fmin(s2, 1.0));
}

static inline double as_norm(const mcest_brdf *b)
{
    return sqrt((b->rough_x + 1.0) * (b->rough_y + 1.0));
}

static inline double as_fresnel(const mcest_brdf *b, double c)
{
    return b->specular + (1.0 - b->specular) * pow5(1.0 - c);
}

static inline double as_diffuse(const mcest_brdf *b, double ci, double co)
{
    return 28.0 / (23.0 * M_PI) * b->diffuse * (1.0 - b->specular) * (1.0 - pow5(1.0 - 0.5 * ci)) *
           (1.0 - pow5(1.0 - 0.5 * co));
}

/* The unit half vector of two upper-hemisphere directions. */
static inline void half_unit(const double *wo, const double *wi, double *h)
{
    double hv[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double l = norm3(hv);
    h[0] = hv[0] / l;
    h[1] = hv[1] / l;
    h[2] = hv[2] / l;
}

double mcest_brdf_f(const mcest_brdf *b, const double *wo, const double *wi)
{
    if (!(wi[2] > 0.0) || !(wo[2] > 0.0))
        return 0.0;
    if (b->model == MCEST_WARD) {
        double hv[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
        double ex = ward_exponent(b, hv);
        double spec = 0.0;
        if (ex < 745.0)
            spec = b->specular * exp(-ex) /
                   (4.0 * M_PI * b->rough_x * b->rough_y * sqrt(wi[2]) * sqrt(wo[2]));
        return b->diffuse / M_PI + spec;
    }
    double h[3];
    half_unit(wo, wi, h);
    double kh = dot3(wo, h);
    double lobe = exp(as_log_lobe(b, h));
    double spec = as_norm(b) / (8.0 * M_PI) * lobe * as_fresnel(b, kh) / (kh * fmax(wi[2], wo[2]));
    return as_diffuse(b, wi[2], wo[2]) + spec;
}

/* The half-vector samplers; wi = reflect(wo, h).  Returns 1 when wi is in
 * the upper hemisphere. */
int mcest_brdf_spec_sample(const mcest_brdf *b, const double *wo, double u1, double u2, double *wi)
{
    double h[3];
    if (b->model == MCEST_WARD) {
        double g = sqrt(-log1p(-u1));
        double s, c;
        mcest_sincos(2.0 * M_PI * u2, &s, &c);
        double hv[3] = {g * b->rough_x * c, g * b->rough_y * s, 1.0};
        double l = norm3(hv);
        h[0] = hv[0] / l;
        h[1] = hv[1] / l;
        h[2] = hv[2] / l;
    } else {
        double s, c;
        mcest_sincos(2.0 * M_PI * u1, &s, &c);
        double px = sqrt(b->rough_y + 1.0) * c, py = sqrt(b->rough_x + 1.0) * s;
        double l = hypot(px, py);
        double cp = px / l, sp = py / l;
        double e = b->rough_x * cp * cp + b->rough_y * sp * sp;
        double lc = log1p(-u2) / (e + 1.0); /* log cos(theta_h) */
        double ct = exp(lc), omc = -expm1(lc);
        double st = sqrt(omc * (1.0 + ct));
        h[0] = st * cp;
        h[1] = st * sp;
        h[2] = ct;
    }
    double oh = dot3(wo, h);
    for (int i = 0; i < 3; i++)
        wi[i] = 2.0 * oh * h[i] - wo[i];
    return wi[2] > 0.0;
}

/* Density of the half-vector sampler's directions, anywhere on the sphere:
 * p_h(h) / (4 |wo.h|), h = +-(wi + wo)/|wi + wo| with hz > 0. */
double mcest_brdf_spec_pdf(const mcest_brdf *b, const double *wo, const double *wi)
{
    double hv[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double l = norm3(hv);
    if (!(l > 0.0))
        return 0.0;
    double h[3] = {hv[0] / l, hv[1] / l, hv[2] / l};
    if (h[2] < 0.0)
        h[0] = -h[0], h[1] = -h[1], h[2] = -h[2];
    double oh = fabs(dot3(wo, h));
    if (!(h[2] > 0.0) || !(oh > 0.0))
        return 0.0;
    double ph;
    if (b->model == MCEST_WARD) {
        double ex = ward_exponent(b, h);
        if (!(ex < 745.0))
            return 0.0;
        ph = exp(-ex) / (M_PI * b->rough_x * b->rough_y * h[2] * h[2] * h[2]);
    } else {
        ph = as_norm(b) / (2.0 * M_PI) * exp(as_log_lobe(b, h));
    }
    return ph / (4.0 * oh);
}

/* f_s cos_i / p_spec for wi in the upper hemisphere, analytically (the
 * lobes cancel): Ward rho_s sqrt(cos_i/cos_o) hz^3 (wo.h); Ashikhmin-
 * Shirley F(wo.h) cos_i / max(cos_i, cos_o). */
static double spec_ratio(const mcest_brdf *b, const double *wo, const double *wi)
{
    double h[3];
    half_unit(wo, wi, h);
    double oh = dot3(wo, h);
    if (b->model == MCEST_WARD)
        return b->specular * sqrt(wi[2]) / sqrt(wo[2]) * h[2] * h[2] * h[2] * oh;
    return as_fresnel(b, oh) * wi[2] / fmax(wi[2], wo[2]);
}

/* ---- the mixture of a plan ------------------------------------------------ */

static inline double diffuse_cos(const mcest_brdf *b, const double *wo, const double *wi)
{
    if (b->model == MCEST_WARD)
        return b->diffuse / M_PI * wi[2];
    return as_diffuse(b, wi[2], wo[2]) * wi[2];
}

double mcest_plan_pdf(const mcest_brdf_plan *p, const double *wi)
{
    double pc = wi[2] > 0.0 ? wi[2] / M_PI : 0.0;
    double ps = p->mix < 1.0 ? mcest_brdf_spec_pdf(&p->brdf, p->wo, wi) : 0.0;
    return p->mix * pc + (1.0 - p->mix) * ps;
}

/* f cos / q for the plan's mixture q, 0 below the horizon. */
double mcest_plan_ratio(const mcest_brdf_plan *p, const double *wi)
{
    if (!(wi[2] > 0.0))
        return 0.0;
    double rs = spec_ratio(&p->brdf, p->wo, wi);
    if (p->mix == 0.0)
        return rs;
    double ps = mcest_brdf_spec_pdf(&p->brdf, p->wo, wi);
    double num = diffuse_cos(&p->brdf, p->wo, wi) + rs * ps;
    double den = p->mix * wi[2] / M_PI + (1.0 - p->mix) * ps;
    return num / den;
}

void mcest_plan_propose(const mcest_brdf_plan *p, const uint64_t *r, double *wi)
{
    double u1 = u01(r[1]), u2 = u01(r[2]);
    if (u01(r[0]) < p->mix) { /* cosine-weighted (Malley) */
        double s, c;
        mcest_sincos(2.0 * M_PI * u2, &s, &c);
        double rho = sqrt(u1);
        wi[0] = rho * c;
        wi[1] = rho * s;
        wi[2] = sqrt(1.0 - u1);
    } else {
        mcest_brdf_spec_sample(&p->brdf, p->wo, u1, u2, wi);
    }
}

/* ---- public ---------------------------------------------------------------- */

static int unit_wo(const double *wo, double *out)
{
    if (!wo || !finite3(wo))
        return 0;
    double l = norm3(wo);
    if (!(l > 0.0) || !isfinite(l))
        return 0;
    for (int i = 0; i < 3; i++)
        out[i] = wo[i] / l;
    return 1;
}

int mcest_brdf_eval(const mcest_brdf *brdf, const double wo[3], const double *wi, size_t n,
                    double *f)
{
    double o[3];
    if (!mcest_brdf_valid(brdf) || !unit_wo(wo, o) || (n > 0 && (!wi || !f)))
        return MCEST_EINVAL;
    for (size_t k = 0; k < n; k++) {
        double w[3];
        if (!unit_wo(wi + 3 * k, w))
            return MCEST_EINVAL;
        f[k] = mcest_brdf_f(brdf, o, w);
    }
    return MCEST_OK;
}

static int plan_ok(const mcest_brdf_plan *p)
{
    return p && p->version == MCEST_BRDF_PLAN_VERSION && mcest_brdf_valid(&p->brdf);
}

int mcest_brdf_sample(const mcest_brdf_plan *plan, uint64_t seed, uint64_t first_index, size_t n,
                      double *wi, double *pdf)
{
    if (!plan_ok(plan) || (n > 0 && !wi))
        return MCEST_EINVAL;
    uint64_t tag = mcest_tag(MCEST_DOMAIN_BRDF_SAMPLE, (uint64_t)plan->brdf.model, 0);
    for (size_t k = 0; k < n; k++) {
        mcest_u64x4 r = mcest_random_block(seed, tag, first_index + k, 0);
        mcest_plan_propose(plan, r.v, wi + 3 * k);
        if (pdf)
            pdf[k] = mcest_plan_pdf(plan, wi + 3 * k);
    }
    return MCEST_OK;
}

int mcest_brdf_pdf(const mcest_brdf_plan *plan, const double *wi, size_t n, double *pdf)
{
    if (!plan_ok(plan) || (n > 0 && (!wi || !pdf)))
        return MCEST_EINVAL;
    for (size_t k = 0; k < n; k++) {
        double w[3];
        if (!unit_wo(wi + 3 * k, w))
            return MCEST_EINVAL;
        pdf[k] = mcest_plan_pdf(plan, w);
    }
    return MCEST_OK;
}
