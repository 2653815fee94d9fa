/*
 * brdf_plan.c - a BRDF at a fixed wo: the envelope of the rejection
 * sampler, the albedo by cubature, and the exact (rejection) sampler.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

static inline double pow5(double x)
{
    double x2 = x * x;
    return x2 * x2 * x;
}

int mcest_plan_ok(const mcest_brdf_plan *p)
{
    return p && p->version == MCEST_BRDF_PLAN_VERSION && mcest_brdf_valid(&p->brdf);
}

/* Ward: sup over half vectors h of sqrt(cos_i/cos_o) hz^3 (wo.h).
 * It grows with hz and with wo.h (cos_i = 2 (wo.h) hz - cos_o), and for a
 * given hz, wo.h is largest with h in the plane of n and wo, between them:
 * h at angle t from n, t in [0, theta_o], where the function is
 *   g(t) = sqrt(cos(2t - theta_o)/cos_o) cos^3 t cos(theta_o - t).
 * log g is a sum of logarithms of cosines, each concave on its interval,
 * so g is unimodal and its maximum is where the derivative of log g,
 *   D(t) = -tan(2t - theta_o) - 3 tan t + tan(theta_o - t),
 * changes sign (D(0) = 2 tan theta_o > 0, D(theta_o) = -4 tan theta_o < 0):
 * bisection to the last bit.  At that t, g'(t) = 0, so the rounding of t
 * moves g only at second order; the caller adds a relative 1e-10. */
static double ward_gmax(const double *wo)
{
    double so = hypot(wo[0], wo[1]), co = wo[2];
    double th = atan2(so, co);
    if (!(th > 0.0))
        return 1.0;
    double lo = 0.0, hi = th;
    for (int it = 0; it < 200 && hi - lo > 0.0; it++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;
        double d = -tan(2.0 * mid - th) - 3.0 * tan(mid) + tan(th - mid);
        if (d > 0.0)
            lo = mid;
        else
            hi = mid;
    }
    double best = 0.0;
    double cand[3] = {lo, hi, 0.5 * (lo + hi)};
    for (int i = 0; i < 3; i++) {
        double t = cand[i], ct = cos(t);
        double g = sqrt(cos(2.0 * t - th) / co) * ct * ct * ct * cos(th - t);
        best = fmax(best, g);
    }
    return best;
}

int mcest_brdf_plan_init(const mcest_brdf *brdf, const double wo[3], mcest_brdf_plan *plan)
{
    if (!plan || !mcest_brdf_valid(brdf) || !wo || !finite3(wo))
        return MCEST_EINVAL;
    double l = norm3(wo);
    if (!(l > 0.0) || !isfinite(l))
        return MCEST_EINVAL;
    mcest_brdf_plan P;
    double *raw = (double *)&P;
    for (size_t i = 0; i < sizeof P / sizeof(double); i++)
        raw[i] = 0.0;
    P.version = MCEST_BRDF_PLAN_VERSION;
    P.brdf = *brdf;
    for (int i = 0; i < 3; i++)
        P.wo[i] = wo[i] / l;
    double co = P.wo[2];
    if (!(co >= 1e-12))
        return MCEST_EINVAL;
    const mcest_brdf *b = brdf;
    if (b->model == MCEST_WARD) {
        P.bound_d = b->diffuse;
        P.bound_s = b->specular > 0.0 ? b->specular * ward_gmax(P.wo) * (1.0 + 1e-10) : 0.0;
        P.albedo_d = b->diffuse;
    } else {
        double fo = 1.0 - pow5(1.0 - 0.5 * co);
        P.bound_d = 28.0 / 23.0 * b->diffuse * (1.0 - b->specular) * fo * (31.0 / 32.0);
        P.bound_s = b->specular + (1.0 - b->specular) * pow5(1.0 - 0.5 * co);
        /* 2 pi int_0^1 (1 - (1 - mu/2)^5) mu dmu = 2 pi 23/56 */
        P.albedo_d = b->diffuse * (1.0 - b->specular) * fo;
    }
    P.bound = P.bound_d + P.bound_s;
    P.mix = P.bound > 0.0 ? P.bound_d / P.bound : 1.0;
    P.albedo_s = NAN;
    P.albedo = NAN;
    P.albedo_err = NAN;
    *plan = P;
    return MCEST_OK;
}

/* ---- cubature ------------------------------------------------------------- */

static const double gl7x[7] = {-0.9491079123427585245, -0.7415311855993944399,
                               -0.4058451513773971669, 0.0,
                               0.4058451513773971669,  0.7415311855993944399,
                               0.9491079123427585245};
static const double gl7w[7] = {0.1294849661688696933, 0.2797053914892766679,
                               0.3818300505051189449, 0.4179591836734693878,
                               0.3818300505051189449, 0.2797053914892766679,
                               0.1294849661688696933};
static const double gl4x[4] = {-0.8611363115940525752, -0.3399810435848562648,
                               0.3399810435848562648, 0.8611363115940525752};
static const double gl4w[4] = {0.3478548451374538574, 0.6521451548625461427,
                               0.6521451548625461427, 0.3478548451374538574};

typedef struct {
    double x0, y0, s, q, e;
} cub_node;

static void cub_rule(mcest_fn2 f, void *ctx, cub_node *nd)
{
    double h = 0.5 * nd->s, cx = nd->x0 + h, cy = nd->y0 + h;
    double q7 = 0.0, q4 = 0.0;
    for (int i = 0; i < 7; i++) {
        double row = 0.0;
        for (int j = 0; j < 7; j++)
            row += gl7w[j] * f(ctx, cx + h * gl7x[i], cy + h * gl7x[j]);
        q7 += gl7w[i] * row;
    }
    for (int i = 0; i < 4; i++) {
        double row = 0.0;
        for (int j = 0; j < 4; j++)
            row += gl4w[j] * f(ctx, cx + h * gl4x[i], cy + h * gl4x[j]);
        q4 += gl4w[i] * row;
    }
    nd->q = q7 * h * h;
    nd->e = fabs(q7 - q4) * h * h;
}

#define CUB_NODES 3000

/* Global adaptive subdivision: split the square with the largest error
 * estimate (|7x7 - 4x4 Gauss-Legendre|) until the sum of the estimates is
 * below rel_tol * |integral|.  No allocation: a fixed array of squares. */
double mcest_cubature(mcest_fn2 f, void *ctx, double rel_tol, double *err)
{
    cub_node nodes[CUB_NODES];
    int m = 0;
    /* start from a 4x4 grid: cheap insurance against a lucky coarse rule */
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            cub_node nd = {0.25 * i, 0.25 * j, 0.25, 0, 0};
            cub_rule(f, ctx, &nd);
            nodes[m++] = nd;
        }
    for (;;) {
        double q = 0.0, e = 0.0;
        int worst = 0;
        for (int k = 0; k < m; k++) {
            q += nodes[k].q;
            e += nodes[k].e;
            if (nodes[k].e > nodes[worst].e)
                worst = k;
        }
        if (e <= rel_tol * fabs(q) || e == 0.0 || m + 3 > CUB_NODES) {
            *err = e;
            return q;
        }
        cub_node w = nodes[worst];
        double s = 0.5 * w.s;
        cub_node c[4] = {{w.x0, w.y0, s, 0, 0},
                         {w.x0 + s, w.y0, s, 0, 0},
                         {w.x0, w.y0 + s, s, 0, 0},
                         {w.x0 + s, w.y0 + s, s, 0, 0}};
        for (int i = 0; i < 4; i++)
            cub_rule(f, ctx, &c[i]);
        nodes[worst] = c[0];
        nodes[m++] = c[1];
        nodes[m++] = c[2];
        nodes[m++] = c[3];
    }
}

typedef struct {
    const mcest_brdf_plan *p;
    double (*g)(const double *);
} integ_ctx;

static double spec_integrand(void *vctx, double u1, double u2)
{
    integ_ctx *c = vctx;
    double wi[3];
    if (!mcest_brdf_spec_sample(&c->p->brdf, c->p->wo, u1, u2, wi))
        return 0.0;
    /* f_s cos / p_spec: the plan's ratio with no diffuse part */
    mcest_brdf_plan q = *c->p;
    q.mix = 0.0;
    double r = mcest_plan_ratio(&q, wi);
    return c->g ? r * c->g(wi) : r;
}

static double diff_integrand(void *vctx, double u1, double u2)
{
    integ_ctx *c = vctx;
    double s, co;
    mcest_sincos(2.0 * M_PI * u2, &s, &co);
    double rho = sqrt(u1);
    double wi[3] = {rho * co, rho * s, sqrt(1.0 - u1)};
    if (!(wi[2] > 0.0))
        return 0.0;
    const mcest_brdf *b = &c->p->brdf;
    double pf; /* pi f_d */
    if (b->model == MCEST_WARD)
        pf = b->diffuse;
    else
        pf = 28.0 / 23.0 * b->diffuse * (1.0 - b->specular) * (1.0 - pow5(1.0 - 0.5 * wi[2])) *
             (1.0 - pow5(1.0 - 0.5 * c->p->wo[2]));
    return c->g ? pf * c->g(wi) : pf;
}

int mcest_plan_integrate(const mcest_brdf_plan *p, double (*g)(const double *), double rel_tol,
                         double *value, double *err)
{
    integ_ctx c = {p, g};
    double vd = 0.0, ed = 0.0, vs = 0.0, es = 0.0;
    if (p->brdf.diffuse > 0.0) {
        if (g)
            vd = mcest_cubature(diff_integrand, &c, rel_tol, &ed);
        else
            vd = p->albedo_d;
    }
    if (p->brdf.specular > 0.0)
        vs = mcest_cubature(spec_integrand, &c, rel_tol, &es);
    *value = vd + vs;
    *err = ed + es;
    if (!isfinite(*value))
        return MCEST_ENUMERIC;
    return *err <= rel_tol * fabs(*value) || *err == 0.0 ? MCEST_OK : MCEST_ENUMERIC;
}

int mcest_brdf_plan_albedo(mcest_brdf_plan *plan, double rel_tol)
{
    if (!mcest_plan_ok(plan) || !(rel_tol >= 1e-13 && rel_tol <= 1e-2))
        return MCEST_EINVAL;
    integ_ctx c = {plan, NULL};
    double vs = 0.0, es = 0.0;
    if (plan->brdf.specular > 0.0)
        vs = mcest_cubature(spec_integrand, &c, rel_tol, &es);
    plan->albedo_s = vs;
    plan->albedo = plan->albedo_d + vs;
    plan->albedo_err = es;
    plan->has_albedo = isfinite(plan->albedo);
    if (!plan->has_albedo)
        return MCEST_ENUMERIC;
    return es <= rel_tol * fabs(plan->albedo) || es == 0.0 ? MCEST_OK : MCEST_ENUMERIC;
}

/* ---- the exact sampler ------------------------------------------------------ */

/* One direction of density f cos / albedo: proposals from the plan's
 * mixture, accepted with probability (f cos / q) / bound.  Trial b of
 * estimate `index` uses block (index, b): words 0-2 for the proposal, 3 for
 * the acceptance test. */
int mcest_exact_one(const mcest_brdf_plan *p, uint64_t seed, uint64_t tag, uint64_t index,
                    uint64_t max_trials, double *wi, uint64_t *trials)
{
    const double bound = p->bound, limit = bound * (1.0 + 1e-9);
    for (uint64_t b = 0;; b++) {
        if (max_trials && b >= max_trials) {
            *trials += b;
            return MCEST_ELIMIT;
        }
        mcest_u64x4 r = mcest_random_block(seed, tag, index, b);
        double w[3];
        mcest_plan_propose(p, r.v, w);
        double ratio = mcest_plan_ratio(p, w);
        if (!(ratio <= limit)) { /* the envelope failed (or NaN): never expected */
            *trials += b + 1;
            return MCEST_ENUMERIC;
        }
        if (u01(r.v[3]) * bound < ratio) {
            wi[0] = w[0];
            wi[1] = w[1];
            wi[2] = w[2];
            *trials += b + 1;
            return MCEST_OK;
        }
    }
}

int mcest_brdf_sample_exact(const mcest_brdf_plan *plan, uint64_t seed, uint64_t first_index,
                            size_t n, uint64_t max_trials, double *wi, uint64_t *trials)
{
    if (!mcest_plan_ok(plan) || (n > 0 && !wi) || !(plan->bound > 0.0))
        return MCEST_EINVAL;
    uint64_t tag = mcest_tag(MCEST_DOMAIN_BRDF_EXACT, (uint64_t)plan->brdf.model, 0);
    uint64_t total = 0;
    int st = MCEST_OK;
    for (size_t k = 0; k < n && st == MCEST_OK; k++)
        st = mcest_exact_one(plan, seed, tag, first_index + k, max_trials, wi + 3 * k, &total);
    if (trials)
        *trials = total;
    return st;
}
