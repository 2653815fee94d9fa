/*
 * check_run.c - the renderer checks: drive the caller's sample, pdf and eval
 * callbacks, validate what they return, and run the routes of mcstat.h's
 * section "Renderer checks" on it.
 *
 * The order of a check:
 *   1. pilot: n_pilot samples (stream 1) give the cells (check_cells.c);
 *   2. cubature of pdf() over each cell: the cells' probabilities, and
 *      their sum, the mass of pdf();
 *   3. the tested sample: n samples (stream 2); at each successful one,
 *      pdf() and eval(); cell counts, region sums of the weights, the
 *      deterministic comparisons;
 *   4. the eval-only estimator: n_eval points (stream 3) from the cells'
 *      table, eval() and pdf() there;
 *   5. reciprocity, then the routes' statistics (check_routes.c), Holm
 *      across them.
 * Every uniform is a pure function of (seed, stream, index): the results
 * do not depend on the batch size.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "check_run.h"

#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#define LEAF_POINTS 32
#define RECIPROCITY_POINTS 1000
#define DEFENSIVE 0.1   /* share of uniform points in the eval-only estimator's table */
#define CUBATURE_SHARE 0.05 /* cubature error target, in sampling sd of a cell's count */

enum { STREAM_PILOT = 1, STREAM_TEST = 2, STREAM_EVAL = 3, STREAM_KEEP_SAMPLE = 4, STREAM_KEEP_EVAL = 5 };
/* The KS route's envelopes: twice the largest ratio seen.  A ratio with
 * tail index 4 (eval/table, measured) exceeds 1.25 times the largest of
 * an independent half in about 30% of runs, twice it in about 6%. */
#define ENVELOPE_MARGIN 2.0

static const uint32_t known_sizes[] = {MCSTAT_CHECK_OPTIONS_SIZE_0_2, MCSTAT_CHECK_OPTIONS_SIZE_0_3};
_Static_assert(sizeof(mcstat_check_options) == MCSTAT_CHECK_OPTIONS_SIZE_0_3,
               "a grown mcstat_check_options needs its size appended to known_sizes");

static const mcstat_check_options defaults = MCSTAT_CHECK_OPTIONS_INIT;

int mcstat_check_options_init_size(mcstat_check_options *opt, size_t size)
{
    return mcstat__options_init(opt, size, &defaults, sizeof defaults, known_sizes,
                                sizeof known_sizes / sizeof known_sizes[0]);
}

size_t mcstat_sizeof_check_options(void) { return sizeof(mcstat_check_options); }
size_t mcstat_sizeof_check_model(void) { return sizeof(mcstat_check_model); }
size_t mcstat_sizeof_check_report(void) { return sizeof(mcstat_check_report); }

/* ---- the plan: sizes, and the scratch carved from one block (check_run.h) -- */

/* Carves the scratch from base (NULL: only sizes it); *bytes the total. */
static int carve(const plan *pl, char *base, scratch *s, size_t *bytes)
{
    size_t off = 0;
    int overflow = 0;
#define TAKE(ptr, count, type)                                                        \
    do {                                                                              \
        size_t c_ = (size_t)(count);                                                  \
        if (c_ > (SIZE_MAX - off - 16) / sizeof(type))                                \
            overflow = 1;                                                             \
        else {                                                                        \
            if (base)                                                                 \
                (ptr) = (type *)(void *)(base + off);                                 \
            off += (c_ * sizeof(type) + 15) & ~(size_t)15;                             \
        }                                                                             \
    } while (0)
    size_t B = pl->batch, dims = (size_t)pl->d.dims;
    TAKE(s->u, B * (size_t)pl->nu, double);
    TAKE(s->x, B * dims, double);
    TAKE(s->w, B, double);
    TAKE(s->p, B, double);
    TAKE(s->xs, B * dims, double);
    TAKE(s->ws, B, double);
    TAKE(s->ps, B, double);
    TAKE(s->f, B, double);
    TAKE(s->p2, B, double);
    TAKE(s->sb, 2 * B, double);
    TAKE(s->cellb, B, int32_t);
    TAKE(s->st, 2 * pl->n_pilot, double);
    TAKE(s->wsave, pl->n, double);
    TAKE(s->vsave, pl->n_eval, double);
    TAKE(s->rsave, pl->n_eval, double);
    TAKE(s->keys_a, pl->n, double);
    TAKE(s->keys_b, pl->n_eval / 2 + 1, double);
    TAKE(s->recip, 4 * RECIPROCITY_POINTS, double);
    TAKE(s->counts, pl->max_cells, double);
    TAKE(s->cell_r, pl->max_cells, double);
    TAKE(s->cell_r2, pl->max_cells, double);
    TAKE(s->cdf, pl->max_rects, double);
    TAKE(s->nodes, 2 * pl->max_cells, mcstat__node);
    TAKE(s->cells, pl->max_cells, mcstat__cell);
    TAKE(s->rects, pl->max_rects, mcstat__rect);
#undef TAKE
    if (overflow)
        return mcstat__refuse(MCSTAT_ETOOBIG, "the check's work memory for n = %llu and these options would pass "
                              "SIZE_MAX", (unsigned long long)pl->n);
    *bytes = off;
    return MCSTAT_OK;
}

static const char *kind_name(int kind)
{
    switch (kind) {
    case MCSTAT_CHECK_KIND_BSDF: return "a BSDF";
    case MCSTAT_CHECK_KIND_EMITTER: return "an emitter";
    case MCSTAT_CHECK_KIND_PHASE: return "a phase function";
    case MCSTAT_CHECK_KIND_MEDIUM: return "a medium";
    default: return "a warp";
    }
}

/* Every refusal says why (mcstat_last_error), naming the field as a C
 * caller writes it; the bindings pass the text on. */
#define REFUSE(...) return mcstat__refuse(MCSTAT_EINVAL, __VA_ARGS__)

static int make_plan(const mcstat_check_model *m, int kind, size_t n, const mcstat_check_options *o, plan *pl)
{
    if (!m)
        REFUSE("model is NULL");
    if (!m->sample || !m->pdf)
        REFUSE("model.%s is NULL: every check calls sample() and pdf()", m->sample ? "pdf" : "sample");
    if (mcstat__domain_get(m->domain, &pl->d) != MCSTAT_OK)
        REFUSE("model.domain %d is not a domain (MCSTAT_CHECK_DOMAIN_*)", m->domain);
    const char *dom = mcstat_check_domain_name(m->domain);
    if (m->n_uniforms < 1 || m->n_uniforms > MCSTAT_CHECK_MAX_UNIFORMS)
        REFUSE("model.n_uniforms must be in 1..%d, got %d", MCSTAT_CHECK_MAX_UNIFORMS, m->n_uniforms);
    if (m->weight != MCSTAT_CHECK_WEIGHT_OVER_PDF && m->weight != MCSTAT_CHECK_WEIGHT_VALUE)
        REFUSE("model.weight must be MCSTAT_CHECK_WEIGHT_OVER_PDF or MCSTAT_CHECK_WEIGHT_VALUE, got %d", m->weight);
    if (m->sample_reports != 0 && m->sample_reports != 1)
        REFUSE("model.sample_reports must be 0 or 1, got %d", m->sample_reports);
    if (kind != MCSTAT_CHECK_KIND_WARP && !m->eval) /* BSDFs and emitters have an integrand and weights */
        REFUSE("model.eval is NULL: the check of %s integrates eval()", kind_name(kind));
    if (kind != MCSTAT_CHECK_KIND_WARP && !m->sample_reports)
        REFUSE("model.sample_reports is 0: the check of %s needs each sample's pdf and weight from sample()",
               kind_name(kind));
    if ((kind == MCSTAT_CHECK_KIND_EMITTER || kind == MCSTAT_CHECK_KIND_BSDF) &&
        m->domain != MCSTAT_CHECK_DOMAIN_SPHERE && m->domain != MCSTAT_CHECK_DOMAIN_HEMISPHERE)
        REFUSE("model.domain of %s must be sphere or hemisphere (directions), got %s", kind_name(kind), dom);
    if (kind == MCSTAT_CHECK_KIND_PHASE && m->domain != MCSTAT_CHECK_DOMAIN_SPHERE)
        REFUSE("model.domain of a phase function must be sphere (it is normalised over the whole sphere), got %s",
               dom);
    if (kind == MCSTAT_CHECK_KIND_MEDIUM && m->domain != MCSTAT_CHECK_DOMAIN_INTERVAL)
        REFUSE("model.domain of a medium must be interval (distances mapped to [0, 1]), got %s", dom);
    if (n < 1000)
        REFUSE("n must be at least 1000, got %zu", n);
    if ((uint64_t)n > (1ull << 48))
        return mcstat__refuse(MCSTAT_ETOOBIG, "n must be at most 2^48, got %zu", n);
    if (o->routes == 0 || (o->routes & ~MCSTAT_CHECK_ROUTE_ALL))
        REFUSE("options.routes must be a nonzero set of MCSTAT_CHECK_ROUTE_* bits, got 0x%x", (unsigned)o->routes);
    for (int i = 0; i < 4; i++)
        if ((i < 3 && m->reserved_rest[i] != 0.0) || o->reserved[i] != 0.0) /* kept zero for later releases */
            REFUSE("%s[%d] must be 0 (reserved for later releases)",
                   i < 3 && m->reserved_rest[i] != 0.0 ? "model.reserved_rest" : "options.reserved", i);
    if (m->lobes && kind != MCSTAT_CHECK_KIND_BSDF)
        REFUSE("model.lobes is set in the check of %s: discrete lobes are a BSDF's", kind_name(kind));
    if (isnan(o->escape_transmittance) || o->escape_transmittance > 1.0)
        REFUSE("options.escape_transmittance must be negative (off) or in [0, 1], got %g", o->escape_transmittance);
    if (o->escape_transmittance >= 0.0 && kind != MCSTAT_CHECK_KIND_MEDIUM)
        REFUSE("options.escape_transmittance is %g in the check of %s: it is a medium's", o->escape_transmittance,
               kind_name(kind));
    if (o->escape_transmittance >= 0.0 && m->weight != MCSTAT_CHECK_WEIGHT_OVER_PDF)
        REFUSE("options.escape_transmittance needs model.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF (an escape's weight is "
               "what it carries on)");
    if (o->reserved_i != 0)
        REFUSE("options.reserved_i must be 0 (reserved for later releases), got %d", o->reserved_i);
    if (o->stochastic != 0 && o->stochastic != 1)
        REFUSE("options.stochastic must be 0 or 1, got %d", o->stochastic);
    if (o->reciprocal != 0 && o->reciprocal != 1)
        REFUSE("options.reciprocal must be 0 or 1, got %d", o->reciprocal);
    if (o->cells < 0 || o->cells == 1 || o->cells > (1 << 20))
        REFUSE("options.cells must be 0 (automatic) or 2..1048576, got %d", o->cells);
    if (o->batch < 64 || o->batch > ((uint64_t)1 << 32))
        REFUSE("options.batch must be in 64..2^32, got %llu", (unsigned long long)o->batch);
    if (!(o->rtol > 0.0 && o->rtol < 1.0))
        REFUSE("options.rtol must be in (0, 1), got %g", o->rtol);
    if (!(o->tolerated >= 0.0 && o->tolerated < 1.0))
        REFUSE("options.tolerated must be in [0, 1), got %g", o->tolerated);
    if (!(o->resolution >= 0.0 && o->resolution < 0.01))
        REFUSE("options.resolution must be 0 (derived from the values) or in (0, 0.01), got %g", o->resolution);
    if (o->n_pilot > (1ull << 40))
        return mcstat__refuse(MCSTAT_ETOOBIG, "options.n_pilot must be at most 2^40, got %llu",
                              (unsigned long long)o->n_pilot);
    if (o->n_eval > (1ull << 48))
        return mcstat__refuse(MCSTAT_ETOOBIG, "options.n_eval must be at most 2^48, got %llu",
                              (unsigned long long)o->n_eval);
    pl->kind = kind;
    pl->nu = m->n_uniforms;
    pl->reports = m->sample_reports;
    pl->has_eval = kind != MCSTAT_CHECK_KIND_WARP && m->eval != NULL;
    pl->n = n;
    uint64_t k = (uint64_t)o->cells;
    if (k == 0) {
        /* Mann and Wald's order, 2 n^(2/5) cells (256 at n = 1e5... 200) */
        double kk = 2.0 * pow((double)n, 0.4);
        k = kk < 8 ? 8 : (kk > 8192 ? 8192 : (uint64_t)kk);
    }
    pl->cells_target = k;
    pl->n_pilot = o->n_pilot ? o->n_pilot : LEAF_POINTS * k;
    if (pl->n_pilot < 2 * LEAF_POINTS)
        REFUSE("options.n_pilot must be 0 (automatic) or at least %d, got %llu", 2 * LEAF_POINTS,
               (unsigned long long)pl->n_pilot);
    pl->n_eval = o->n_eval ? o->n_eval : n;
    if (pl->n_eval < 1000)
        REFUSE("options.n_eval must be 0 (n) or at least 1000, got %llu", (unsigned long long)pl->n_eval);
    uint64_t most = n > pl->n_pilot ? n : pl->n_pilot;
    if (pl->n_eval > most)
        most = pl->n_eval;
    pl->batch = (size_t)(o->batch < most ? o->batch : most);
    if (pl->batch < 64)
        pl->batch = 64;
    pl->max_cells = mcstat__tree_max_cells(pl->n_pilot, LEAF_POINTS);
    pl->max_rects = 48 * pl->max_cells + 1024;
    return MCSTAT_OK;
}

static int read_options(const mcstat_check_options *opt, mcstat_check_options *o)
{
    *o = defaults;
    if (!opt)
        return MCSTAT_OK;
    if (mcstat__options_read(o, sizeof *o, opt, known_sizes, sizeof known_sizes / sizeof known_sizes[0]))
        REFUSE("options.size %u is not a size of mcstat_check_options this version knows (MCSTAT_CHECK_OPTIONS_INIT "
               "sets it)", (unsigned)opt->size);
    return MCSTAT_OK;
}

int mcstat_check_work_size(const mcstat_check_model *model, size_t n, const mcstat_check_options *opt,
                           size_t *bytes)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    mcstat_check_options o;
    plan pl;
    scratch s;
    if (!bytes)
        REFUSE("bytes is NULL");
    int st = read_options(opt, &o);
    if (st)
        return st;
    /* the sizes do not depend on the kind: any model valid for one of the
     * checks is sized by the plan of a BSDF's (directions) or a warp's */
    int kind = model && model->eval && model->sample_reports && mcstat_check_domain_dims(model->domain) == 3
                   ? MCSTAT_CHECK_KIND_BSDF
                   : MCSTAT_CHECK_KIND_WARP;
    st = make_plan(model, kind, n, &o, &pl);
    if (st)
        return st;
    return carve(&pl, NULL, &s, bytes);
}

/* ---- the run --------------------------------------------------------------- */

static void format_point(const run *r, const double *x, char *buf, size_t size)
{
    if (r->pl.d.dims == 3)
        snprintf(buf, size, "(%.9g, %.9g, %.9g)", x[0], x[1], x[2]);
    else if (r->pl.d.dims == 2)
        snprintf(buf, size, "(%.9g, %.9g)", x[0], x[1]);
    else
        snprintf(buf, size, "(%.9g)", x[0]);
}

static int fail(run *r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->out->message, sizeof r->out->message, fmt, ap);
    va_end(ap);
    return MCSTAT_ECALLBACK;
}

/* Why x is off the domain, in words. */
static const char *domain_rule(const mcstat__domain *d, const double *x)
{
    for (int c = 0; c < d->dims; c++)
        if (!isfinite(x[c]))
            return "its coordinates must be finite";
    switch (d->kind) {
    case MCSTAT_CHECK_DOMAIN_SPHERE: return "a direction must have unit length within 1e-4";
    case MCSTAT_CHECK_DOMAIN_HEMISPHERE:
        return fabs(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] - 1.0) <= 2e-4
                   ? "a direction must have z >= 0 (below the horizon: use the sphere domain)"
                   : "a direction must have unit length within 1e-4";
    case MCSTAT_CHECK_DOMAIN_DISK: return "x^2 + y^2 must be at most 1";
    default: return "coordinates must lie in [0, 1]";
    }
}

/* The weight as eval/pdf, whatever the model's convention. */
static double weight_over_pdf(const run *r, double w, double p)
{
    return (r->pl.reports && r->m->weight == MCSTAT_CHECK_WEIGHT_VALUE) ? w / p : w;
}

/* Whether v is a float32 value (a float renderer's result converted to
 * double is exactly one); out of float's range it is not (and converting
 * it would be undefined). */
static int is_float32(double v)
{
    return fabs(v) <= FLT_MAX && (double)(float)v == v;
}

static int call_sample(run *r, uint64_t key, const char *stream, uint64_t first, size_t k)
{
    const plan *pl = &r->pl;
    size_t nu = (size_t)pl->nu;
    for (size_t i = 0; i < k; i++)
        for (size_t j = 0; j < nu; j++)
            r->s.u[i * nu + j] = mcstat__uniform(key, (first + i) * nu + j);
    /* NaN sentinels: what the callback leaves unwritten shows as NaN */
    for (size_t i = 0; i < k; i++) {
        r->s.w[i] = pl->reports ? NAN : 0.0;
        r->s.p[i] = pl->reports ? NAN : 1.0;
        for (int c = 0; c < pl->d.dims; c++)
            r->s.x[i * pl->d.dims + c] = NAN;
    }
    r->out->calls++;
    int st = r->m->sample(r->m->user, r->wi, r->s.u, k, r->s.x, r->s.w, r->s.p);
    if (st)
        return fail(r, "sample() returned status %d (call with %zu points from sample %llu of the %s)", st, k,
                    (unsigned long long)first, stream);
    for (size_t i = 0; i < k; i++) {
        double w = r->s.w[i], p = r->s.p[i];
        if (pl->reports && !(is_float32(w) && is_float32(p)))
            r->not_float32 = 1;
        if (isfinite(p) && p >= 0.0 && isfinite(w) && w >= 0.0 && p == 0.0)
            continue; /* a failed sample: its point is not looked at */
        if (isfinite(p) && p >= 0.0 && isfinite(w) && w >= 0.0 &&
            !mcstat__domain_coords(&pl->d, r->s.x + i * pl->d.dims, &r->s.sb[2 * i], &r->s.sb[2 * i + 1]))
            continue;
        /* something is wrong with this sample: say what */
        char pt[128];
        format_point(r, r->s.x + i * pl->d.dims, pt, sizeof pt);
        if (!isfinite(p) || p < 0.0)
            return fail(r, "sample() returned pdf %.17g at sample %llu of the %s (point %s): a density must be finite "
                        "and >= 0", p, (unsigned long long)(first + i), stream, pt);
        if (!isfinite(w) || w < 0.0)
            return fail(r, "sample() returned weight %.17g at sample %llu of the %s (point %s, pdf %.17g): a weight "
                        "must be finite and >= 0", w, (unsigned long long)(first + i), stream, pt, p);
        return fail(r, "sample() returned the point %s at sample %llu of the %s: not in the %s domain (%s)", pt,
                    (unsigned long long)(first + i), stream, mcstat_check_domain_name(pl->d.kind),
                    domain_rule(&pl->d, r->s.x + i * pl->d.dims));
    }
    return MCSTAT_OK;
}

/* pdf or eval at n points, validated. */
static int call_density(run *r, mcstat_check_density_fn fn, const char *name, const double *x, size_t n,
                        double *out)
{
    for (size_t i = 0; i < n; i++)
        out[i] = NAN;
    r->out->calls++;
    int st = fn(r->m->user, r->wi, x, n, out);
    if (st)
        return fail(r, "%s() returned status %d (call with %zu points)", name, st, n);
    for (size_t i = 0; i < n && !r->not_float32; i++)
        r->not_float32 = !is_float32(out[i]);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(out[i]) || out[i] < 0.0) {
            char pt[128];
            format_point(r, x + i * r->pl.d.dims, pt, sizeof pt);
            return fail(r, "%s() returned %.17g at the point %s (point %zu of a call with %zu): %s must be finite "
                        "and >= 0", name, out[i], pt, i, n, strcmp(name, "pdf") == 0 ? "a density" : "the integrand");
        }
    return MCSTAT_OK;
}

static int pdf_for_cubature(void *ctx, const double *x, size_t n, double *out)
{
    run *r = ctx;
    return call_density(r, r->m->pdf, "pdf", x, n, out);
}

/* A deterministic comparison of a (the renderer's claim) with b (what it
 * should equal) at x. */
static void compare(run *r, int route, const double *x, double a, double b)
{
    double scale = fmax(fabs(a), fabs(b));
    double diff = fabs(a - b);
    r->checked[route]++;
    double rel = scale > 0.0 ? diff / scale : 0.0;
    if (rel > r->rtol)
        r->bad[route]++;
    if (rel > r->worst[route] || (r->checked[route] == 1 && r->worst[route] == 0.0 && rel == 0.0)) {
        r->worst[route] = rel;
        for (int c = 0; c < 3; c++)
            r->worst_x[route][c] = c < r->pl.d.dims ? x[c] : NAN;
        r->worst_v[route][0] = a;
        r->worst_v[route][1] = b;
    }
}

/* ---- rounding at the sampled point ----------------------------------------------
 * A float32 renderer computes a sample's pdf and weight from the direction it
 * holds and returns that direction rounded to float32; where the formula is
 * ill-conditioned (at grazing incidence the half vector of two nearly
 * opposite directions loses digits) pdf() and eval() at the returned point
 * differ from the reported values by far more than rtol, for a correct BSDF.
 * So a point beyond rtol whose coordinates are float32 values, or whose
 * model returns float32 values, is also evaluated at its float32
 * neighbours (one float32 ulp down and up in each coordinate): a difference within a few ulps' worth of the value's change
 * there is rounding, not evidence.  At most rounding_cap points are re-evaluated (a wrong model puts
 * every point beyond rtol; past the cap they count as they are). */

#define ROUNDING_ULPS 4.0

/* v moved by one float32 ulp toward `toward`: to the float32 neighbour of
 * a float32 value; by the ulp of float32 at |v| otherwise (a direction a
 * caller renormalised in double after a float32 renderer computed it). */
static double float32_step(double v, double toward)
{
    if (is_float32(v))
        return (double)nextafterf((float)v, (float)toward);
    float a = fabsf((float)v);
    double ulp = (double)nextafterf(a, INFINITY) - (double)a;
    return toward > v ? v + ulp : v - ulp;
}

/* The reference to compare `claim` with: `at_x`, the quantity at x (pdf(),
 * ps < 0; or eval()/ps, the weight's reference), or `claim` itself when the
 * difference is within what ROUNDING_ULPS ulps of x change the quantity by
 * (measured at x's float32 neighbours). */
static int rounding_nearest(run *r, const double *x, double claim, double at_x, double ps, double *out)
{
    *out = at_x;
    int dims = r->pl.d.dims;
    double diff = fabs(claim - at_x), scale = fmax(fabs(claim), fabs(at_x));
    if (!(diff > r->rtol * scale) || r->rounding_checks >= r->rounding_cap)
        return MCSTAT_OK;
    /* a float32 point, or a point of a model whose values are all float32
     * so far (its point computed in float32, then perhaps renormalised) */
    int f32_values = r->o.resolution > 0.0 ? r->o.resolution >= MCSTAT_RESOLUTION_FLOAT32 : !r->not_float32;
    for (int c = 0; c < dims && !f32_values; c++)
        if (!is_float32(x[c]))
            return MCSTAT_OK;
    r->rounding_checks++;
    double pts[2 * 3 * 3], v[2 * 3];
    size_t k = 0;
    for (int c = 0; c < dims; c++)
        for (int side = 0; side < 2; side++, k++) {
            memcpy(pts + k * (size_t)dims, x, (size_t)dims * sizeof(double));
            pts[k * (size_t)dims + (size_t)c] = float32_step(x[c], side ? INFINITY : -INFINITY);
        }
    int st = ps < 0.0 ? call_density(r, r->m->pdf, "pdf", pts, k, v) : call_density(r, r->m->eval, "eval", pts, k, v);
    if (st)
        return st;
    /* the value's change per ulp of the point, at most: a renderer's
     * direction carries a few ulps of its own arithmetic (a normalisation,
     * a rotation into the shading frame), ROUNDING_ULPS of them here */
    double per_ulp = 0.0;
    for (size_t j = 0; j < k; j++) {
        double val = ps < 0.0 ? v[j] : v[j] / ps;
        if (isfinite(val))
            per_ulp = fmax(per_ulp, fabs(val - at_x));
    }
    if (diff <= r->rtol * scale + ROUNDING_ULPS * per_ulp)
        *out = claim; /* explained by rounding at the point */
    return MCSTAT_OK;
}

/* ---- discrete lobes ---------------------------------------------------------- */

/* The lobe a sampled direction lies on, or -1 (a smooth sample). */
static int lobe_of(const run *r, const double *x)
{
    for (int k = 0; k < r->n_lobes; k++) {
        double d0 = x[0] - r->lobe_x[k][0], d1 = x[1] - r->lobe_x[k][1], d2 = x[2] - r->lobe_x[k][2];
        if (d0 * d0 + d1 * d1 + d2 * d2 <= MCSTAT_CHECK_LOBE_TOLERANCE * MCSTAT_CHECK_LOBE_TOLERANCE)
            return k;
    }
    return -1;
}

/* lobes() once for the check's wi, validated; SUPPORT sees a lobe that
 * carries energy but is never sampled. */
static int fetch_lobes(run *r)
{
    double x[3 * MCSTAT_CHECK_MAX_LOBES], mass[MCSTAT_CHECK_MAX_LOBES], value[MCSTAT_CHECK_MAX_LOBES];
    size_t count = (size_t)-1;
    for (int k = 0; k < 3 * MCSTAT_CHECK_MAX_LOBES; k++)
        x[k] = NAN;
    for (int k = 0; k < MCSTAT_CHECK_MAX_LOBES; k++)
        mass[k] = value[k] = NAN;
    r->out->calls++;
    int st = r->m->lobes(r->m->user, r->wi, x, mass, value, &count);
    if (st)
        return fail(r, "lobes() returned status %d", st);
    if (count == (size_t)-1)
        return fail(r, "lobes() returned 0 without setting *count");
    if (count > MCSTAT_CHECK_MAX_LOBES)
        return fail(r, "lobes() gave %zu lobes: at most %d", count, MCSTAT_CHECK_MAX_LOBES);
    for (size_t k = 0; k < count; k++) {
        const double *d = x + 3 * k;
        char pt[128];
        format_point(r, d, pt, sizeof pt);
        double ds, dt;
        if (mcstat__domain_coords(&r->pl.d, d, &ds, &dt))
            return fail(r, "lobes() gave the direction %s for lobe %zu: not in the %s domain (%s)", pt, k,
                        mcstat_check_domain_name(r->pl.d.kind), domain_rule(&r->pl.d, d));
        if (!(mass[k] >= 0.0 && mass[k] <= 1.0))
            return fail(r, "lobes() gave mass %.17g for lobe %zu (direction %s): a probability must lie in [0, 1]",
                        mass[k], k, pt);
        if (!(value[k] >= 0.0) || !isfinite(value[k]))
            return fail(r, "lobes() gave value %.17g for lobe %zu (direction %s): it must be finite and >= 0",
                        value[k], k, pt);
        for (size_t j = 0; j < k; j++) {
            const double *e = x + 3 * j;
            double c = (d[0] - e[0]) * (d[0] - e[0]) + (d[1] - e[1]) * (d[1] - e[1]) + (d[2] - e[2]) * (d[2] - e[2]);
            if (c <= 4.0 * MCSTAT_CHECK_LOBE_TOLERANCE * MCSTAT_CHECK_LOBE_TOLERANCE)
                return fail(r, "lobes() gave lobes %zu and %zu at the same direction %s (closer than twice %g)", j, k,
                            pt, MCSTAT_CHECK_LOBE_TOLERANCE);
        }
        memcpy(r->lobe_x[k], d, sizeof r->lobe_x[k]);
        r->lobe_mass[k] = mass[k];
        r->lobe_value[k] = value[k];
        int unsampled = value[k] > 0.0 && mass[k] == 0.0;
        compare(r, MCSTAT_CHECK_ROUTE_SUPPORT, d, unsampled ? value[k] : 0.0, 0.0);
        r->hard[MCSTAT_CHECK_ROUTE_SUPPORT] |= unsampled;
    }
    r->n_lobes = (int)count;
    r->out->lobes = count;
    for (size_t k = 0; k < count; k++) {
        r->out->lobe_mass += mass[k];
        r->out->lobe_albedo += value[k];
    }
    return MCSTAT_OK;
}

/* A tested sample on lobe k: its pdf is the lobe's mass, its weight the
 * lobe's value over it; the weight enters the albedo. */
static int lobe_sample(run *r, sums *sm, int k, const double *x, double w, double p)
{
    r->lobe_count[k]++;
    sm->n_lobe++;
    if (!r->o.stochastic) {
        compare(r, MCSTAT_CHECK_ROUTE_PDF_VALUE, x, p, r->lobe_mass[k]);
        if (r->m->weight == MCSTAT_CHECK_WEIGHT_VALUE)
            compare(r, MCSTAT_CHECK_ROUTE_WEIGHT, x, w, r->lobe_value[k]);
        else if (r->lobe_mass[k] > 0.0)
            compare(r, MCSTAT_CHECK_ROUTE_WEIGHT, x, w, r->lobe_value[k] / r->lobe_mass[k]);
    }
    int st = mcstat_moments_add(&sm->all, weight_over_pdf(r, w, p));
    return st == MCSTAT_ENONFINITE ? fail(r, "a weight overflowed (weight = value/pdf is infinite)") : st;
}

/* ---- stage 1: pilot and cells -------------------------------------------- */

static int pilot_and_cells(run *r)
{
    const plan *pl = &r->pl;
    uint64_t got = 0;
    for (uint64_t first = 0; first < pl->n_pilot; first += pl->batch) {
        size_t k = (size_t)((pl->n_pilot - first) < pl->batch ? (pl->n_pilot - first) : pl->batch);
        int st = call_sample(r, r->key_pilot, "pilot", first, k);
        if (st)
            return st;
        for (size_t i = 0; i < k; i++)
            if (r->s.p[i] > 0.0 && (r->n_lobes == 0 || lobe_of(r, r->s.x + i * pl->d.dims) < 0)) {
                double w = weight_over_pdf(r, r->s.w[i], r->s.p[i]);
                if (w > r->w_envelope)
                    r->w_envelope = w;
                r->s.st[2 * got] = r->s.sb[2 * i];
                r->s.st[2 * got + 1] = r->s.sb[2 * i + 1];
                got++;
            }
    }
    r->out->n_pilot = pl->n_pilot;
    r->w_envelope *= ENVELOPE_MARGIN;
    r->tr.nodes = r->s.nodes;
    r->tr.cells = r->s.cells;
    r->tr.max_nodes = (int32_t)(2 * pl->max_cells);
    r->tr.max_cells = (int32_t)pl->max_cells;
    int leaf = (int)(pl->n_pilot / pl->cells_target);
    if (leaf < 4)
        leaf = 4;
    mcstat__tree_build(&r->tr, &pl->d, r->s.st, got, leaf, pl->d.kind == MCSTAT_CHECK_DOMAIN_SPHERE);
    size_t used = 0;
    int st = mcstat__cells_integrate(&r->tr, &pl->d, pdf_for_cubature, r, CUBATURE_SHARE / sqrt((double)pl->n),
                                     r->s.rects, pl->max_rects, r->s.xs, r->s.f, pl->batch, &used);
    if (st)
        return st;
    r->n_rects = used;
    double mass = 0.0, err = 0.0;
    for (int32_t c = 0; c < r->tr.n_cells; c++) {
        mass += r->tr.cells[c].prob;
        err += r->tr.cells[c].err;
    }
    r->out->cells = (uint64_t)r->tr.n_cells;
    r->out->mass = mass;
    r->out->mass_error = err;
    int groups = region_count(r);
    for (int32_t c = 0; c < r->tr.n_cells; c++)
        r->tr.cells[c].group = (int32_t)(((int64_t)c * groups) / r->tr.n_cells);
    return MCSTAT_OK;
}

/* ---- stage 2: the tested sample ------------------------------------------ */

static int tested_sample(run *r, sums *sm)
{
    const plan *pl = &r->pl;
    int dims = pl->d.dims;
    int deterministic = !r->o.stochastic;
    for (uint64_t first = 0; first < pl->n; first += pl->batch) {
        size_t k = (size_t)((pl->n - first) < pl->batch ? (pl->n - first) : pl->batch);
        int st = call_sample(r, r->key_test, "tested sample", first, k);
        if (st)
            return st;
        size_t ns = 0, nl = 0;
        for (size_t i = 0; i < k; i++) {
            const double *x = r->s.x + i * dims;
            double p = r->s.p[i], w = r->s.w[i];
            if (pl->reports && p == 0.0) {
                /* a failed sample contributes a zero weight; an escape the weight it carries on */
                if (r->o.escape_transmittance >= 0.0) {
                    int s1 = mcstat_moments_add(&sm->escapes, w);
                    if (s1)
                        return s1;
                    sm->n_escape += w > 0.0;
                } else if (w != 0.0 && deterministic) {
                    compare(r, MCSTAT_CHECK_ROUTE_WEIGHT, x, w, 0.0);
                }
                continue;
            }
            int lobe = r->n_lobes ? lobe_of(r, x) : -1;
            if (lobe >= 0) {
                int s1 = lobe_sample(r, sm, lobe, x, w, p);
                if (s1)
                    return s1;
                nl++;
                continue;
            }
            int32_t c = mcstat__tree_locate(&r->tr, r->s.sb[2 * i], r->s.sb[2 * i + 1]);
            r->s.counts[c] += 1.0;
            r->s.cellb[ns] = c;
            /* compacted in place (ns <= i): the KS route keys the kept ones */
            r->s.sb[2 * ns] = r->s.sb[2 * i];
            r->s.sb[2 * ns + 1] = r->s.sb[2 * i + 1];
            memcpy(r->s.xs + ns * dims, x, (size_t)dims * sizeof(double));
            r->s.ws[ns] = weight_over_pdf(r, w, p);
            r->s.ps[ns] = p;
            ns++;
        }
        sm->n_succ += ns;
        /* zeros of the failed samples enter the mean weight */
        if (pl->has_eval && k > ns + nl) {
            mcstat_moments zeros;
            int s2 = mcstat_moments_from_summary(k - ns - nl, 0.0, 0.0, &zeros);
            if (s2 == MCSTAT_OK)
                s2 = mcstat_moments_merge(&sm->all, &zeros);
            if (s2)
                return s2;
        }
        if (ns == 0)
            continue;
        int st2 = call_density(r, r->m->pdf, "pdf", r->s.xs, ns, r->s.p2);
        if (st2)
            return st2;
        if (pl->has_eval) {
            st2 = call_density(r, r->m->eval, "eval", r->s.xs, ns, r->s.f);
            if (st2)
                return st2;
        }
        for (size_t i = 0; i < ns; i++) {
            const double *x = r->s.xs + i * dims;
            double w = r->s.ws[i], ps = r->s.ps[i], p = r->s.p2[i];
            if (pl->reports && deterministic) {
                double ref;
                int s4 = rounding_nearest(r, x, ps, p, -1.0, &ref);
                if (s4)
                    return s4;
                compare(r, MCSTAT_CHECK_ROUTE_PDF_VALUE, x, ps, ref);
            }
            if (!pl->has_eval)
                continue;
            double f = r->s.f[i];
            if (deterministic) {
                double ref;
                int s4 = ps > 0.0 ? rounding_nearest(r, x, w, f / ps, ps, &ref) : (ref = f / ps, 0);
                if (s4)
                    return s4;
                compare(r, MCSTAT_CHECK_ROUTE_WEIGHT, x, w, ref);
            }
            r->zero_weight += w == 0.0 && f > 0.0;
            compare(r, MCSTAT_CHECK_ROUTE_SUPPORT, x, f > 0.0 && p == 0.0 ? f : 0.0, 0.0);
            if (p > 0.0 && f == 0.0)
                r->pdf_without_eval++;
            int g = r->tr.cells[r->s.cellb[i]].group;
            sm->a[g] += w;
            sm->a2[g] += w * w;
            r->s.wsave[sm->n_w] = w;
            /* KS: keep the point with probability w / W (importance resampling) */
            if (w > r->w_envelope && !r->w_breach) {
                r->w_breach = 1;
                memcpy(r->breach_x, x, (size_t)dims * sizeof(double));
                r->breach_v[0] = w;
                r->breach_v[1] = r->w_envelope;
            }
            if (r->n_keys_a < KS_MAX && mcstat__uniform(r->key_keep_sample, sm->n_w) * r->w_envelope < w)
                r->s.keys_a[r->n_keys_a++] =
                    (double)(mcstat__domain_key(&pl->d, r->s.sb[2 * i], r->s.sb[2 * i + 1]) >> 11);
            sm->n_w++;
            if (sm->n_recip < RECIPROCITY_POINTS && f > 0.0 && dims == 3 && fabs(x[2]) > 1e-6) {
                double *q = r->s.recip + 4 * sm->n_recip++;
                q[0] = x[0];
                q[1] = x[1];
                q[2] = x[2];
                q[3] = f;
            }
        }
        if (pl->has_eval) {
            int s3 = mcstat_moments_add_array(&sm->all, r->s.ws, ns);
            if (s3)
                return s3 == MCSTAT_ENONFINITE ? fail(r, "a weight overflowed (weight = value/pdf is infinite)") : s3;
        }
    }
    return MCSTAT_OK;
}

/* ---- stage 3: the eval-only estimator ------------------------------------ */

/* The share of the pilot a rectangle's cell holds beyond what its integral
 * and error predict, when significant (beyond 3 Poisson sds and 3 points),
 * split over the cell's rectangles by their pilot points; else 0. */
static double pilot_excess(const run *r, const mcstat__rect *rect)
{
    double np = (double)r->tr.n_points;
    if (!(np > 0.0) || rect->p1 == rect->p0)
        return 0.0;
    const mcstat__cell *c = &r->tr.cells[rect->cell];
    double k = (double)c->p_count, e = np * (fmax(c->prob, 0.0) + c->err);
    if (!(k > e + 3.0 * sqrt(e) + 3.0))
        return 0.0;
    return (k - e) / np * (double)(rect->p1 - rect->p0) / k;
}

static int eval_only(run *r, sums *sm)
{
    const plan *pl = &r->pl;
    int dims = pl->d.dims;
    /* The table: the cubature's rectangles (a partition of the domain,
     * finer where pdf varies), each drawn with probability proportional to
     * pdf's integral over it, mixed 9:1 with its area, and uniform inside.
     * Following pdf closely keeps eval/table close to the sample weights,
     * so the estimator is nearly as tight as the sampler's and its mean
     * close to normal at moderate n.  Each rectangle weighs its integral
     * plus its error, plus, in a cell holding significantly more pilot
     * points than its integral predicts (support the cubature missed), the
     * excess in proportion to the rectangle's pilot points: where the
     * cubature is unsure or blind, the table must not fall far below pdf,
     * or pdf/table grows a heavy tail and its mean, though unbiased, is
     * mostly short with a standard error that says otherwise.  Only a
     * significant excess counts: the pilot's counts are noisy (32 points
     * a cell), and following them everywhere would cost the estimator the
     * precision of following pdf. */
    size_t nr = r->n_rects;
    const mcstat__rect *rects = r->s.rects;
    double mass = 0.0, acc = 0.0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < nr; i++) {
            double weight = fmax(rects[i].est, 0.0) + rects[i].err + pilot_excess(r, &rects[i]);
            if (pass == 0) {
                mass += weight;
                continue;
            }
            double area = (rects[i].s1 - rects[i].s0) * (rects[i].t1 - rects[i].t0);
            acc += mass > 0.0 ? (1.0 - DEFENSIVE) * weight / mass + DEFENSIVE * area : area;
            r->s.cdf[i] = acc;
        }
    }
    double total = acc;
    for (uint64_t first = 0; first < pl->n_eval; first += pl->batch) {
        size_t k = (size_t)((pl->n_eval - first) < pl->batch ? (pl->n_eval - first) : pl->batch);
        for (size_t i = 0; i < k; i++) {
            uint64_t idx = (first + i) * 3;
            double u = mcstat__uniform(r->key_eval, idx) * total;
            size_t lo = 0, hi = nr - 1;
            while (lo < hi) {
                size_t mid = lo + (hi - lo) / 2;
                if (r->s.cdf[mid] > u)
                    hi = mid;
                else
                    lo = mid + 1;
            }
            const mcstat__rect *rc = &rects[lo];
            double s = rc->s0 + mcstat__uniform(r->key_eval, idx + 1) * (rc->s1 - rc->s0);
            double t = rc->t0 + mcstat__uniform(r->key_eval, idx + 2) * (rc->t1 - rc->t0);
            mcstat__domain_point(&pl->d, s, t, r->s.xs + i * dims);
            r->s.sb[2 * i] = s;
            r->s.sb[2 * i + 1] = t;
            double pi = (r->s.cdf[lo] - (lo ? r->s.cdf[lo - 1] : 0.0)) / total;
            double area = (rc->s1 - rc->s0) * (rc->t1 - rc->t0);
            r->s.ps[i] = pi / (area * pl->d.jacobian); /* the table's density */
            r->s.cellb[i] = rc->cell;
        }
        int st = call_density(r, r->m->pdf, "pdf", r->s.xs, k, r->s.p2);
        if (st)
            return st;
        for (size_t i = 0; i < k; i++) {
            /* pdf / table: its mean estimates the mass of pdf() without the
             * cubature's bias (the table only needs to be positive where pdf is) */
            double ratio = r->s.p2[i] / r->s.ps[i];
            sm->r += ratio;
            sm->r2 += ratio * ratio;
            r->s.cell_r[r->s.cellb[i]] += ratio;
            r->s.cell_r2[r->s.cellb[i]] += ratio * ratio;
            r->s.rsave[i + first] = ratio;
        }
        if (!pl->has_eval)
            continue;
        st = call_density(r, r->m->eval, "eval", r->s.xs, k, r->s.f);
        if (st)
            return st;
        for (size_t i = 0; i < k; i++) {
            double f = r->s.f[i], v = f / r->s.ps[i];
            int g = r->tr.cells[r->s.cellb[i]].group;
            sm->b[g] += v;
            sm->b2[g] += v * v;
            /* KS: the first half sets the envelope, the second half are
             * the rejection sampler's proposals */
            uint64_t j = first + i, half = pl->n_eval / 2;
            if (j < half) {
                if (v > r->v_largest)
                    r->v_largest = v;
            } else {
                if (j == half)
                    r->v_envelope = ENVELOPE_MARGIN * r->v_largest;
                if (v > r->v_envelope && !r->v_breach) {
                    r->v_breach = 1;
                    memcpy(r->breach_x + 0, r->s.xs + i * dims, (size_t)dims * sizeof(double));
                    r->breach_v[0] = v;
                    r->breach_v[1] = r->v_envelope;
                }
                if (r->n_keys_b < KS_MAX && mcstat__uniform(r->key_keep_eval, j) * r->v_envelope < v)
                    r->s.keys_b[r->n_keys_b++] =
                        (double)(mcstat__domain_key(&pl->d, r->s.sb[2 * i], r->s.sb[2 * i + 1]) >> 11);
            }
            r->s.vsave[sm->n_v++] = v;
            compare(r, MCSTAT_CHECK_ROUTE_SUPPORT, r->s.xs + i * dims, f > 0.0 && r->s.p2[i] == 0.0 ? f : 0.0, 0.0);
            if (r->s.p2[i] > 0.0 && f == 0.0)
                r->pdf_without_eval++;
        }
    }
    return MCSTAT_OK;
}

/* ---- stage 4: reciprocity --------------------------------------------------- */

static int reciprocity(run *r, const sums *sm)
{
    double wi_z = fabs(r->wi[2]);
    /* eval at wi: off the domain */
    if ((wi_z < 1e-6 && r->pl.kind != MCSTAT_CHECK_KIND_PHASE) ||
        (r->pl.d.kind == MCSTAT_CHECK_DOMAIN_HEMISPHERE && r->wi[2] < 0.0))
        return MCSTAT_OK;
    for (uint64_t i = 0; i < sm->n_recip; i++) {
        const double *q = r->s.recip + 4 * i;
        double back = NAN;
        r->out->calls++;
        int st = r->m->eval(r->m->user, q, r->wi, 1, &back);
        if (st)
            return fail(r, "eval() returned status %d (reciprocity: wi and the point swapped)", st);
        if (!isfinite(back) || back < 0.0)
            return fail(r, "eval() returned %.17g with wi = (%.9g, %.9g, %.9g) and the point wi of the check: "
                        "the integrand must be finite and >= 0", back, q[0], q[1], q[2]);
        if (r->pl.kind == MCSTAT_CHECK_KIND_PHASE) /* p(wi, wo) = p(wo, wi): no cosines */
            compare(r, MCSTAT_CHECK_ROUTE_RECIPROCITY, q, q[3], back);
        else
            compare(r, MCSTAT_CHECK_ROUTE_RECIPROCITY, q, q[3] / fabs(q[2]), back / wi_z);
    }
    return MCSTAT_OK;
}

/* ---- the check ---------------------------------------------------------------- */

/* ---- distances: the caller's t in [0, inf), the check's x = 1 - exp(-sigma t) in [0, 1] -- */

typedef struct medium_map {
    const mcstat_check_model *m;
    double sigma;    /* the reference coefficient of the map */
    int not_float32; /* a value the caller's callbacks returned is not a float32 (before the map) */
} medium_map;

#define MEDIUM_CHUNK 256 /* distances converted at a time, on the stack */

static double medium_t(double sigma, double x) { return x >= 1.0 ? INFINITY : -log1p(-x) / sigma; }

/* dx/dt = sigma (1 - x): a density in t is one in x divided by it */
static double medium_jacobian(double sigma, double x) { return sigma * (1.0 - x); }

static int medium_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                         double *pdf)
{
    const medium_map *mm = (const medium_map *)user;
    int st = mm->m->sample(mm->m->user, wi, u, n, x, weight, pdf); /* writes t into x */
    if (st)
        return st;
    for (size_t k = 0; k < n; k++) {
        double t = x[k];
        if (!(is_float32(weight[k]) && is_float32(pdf[k])))
            ((medium_map *)user)->not_float32 = 1;
        if (!(pdf[k] > 0.0))
            continue; /* passed the surface (or failed): x ignored */
        if (!(t >= 0.0) || !isfinite(t)) {
            x[k] = t < 0.0 ? -1.0 : NAN; /* off the domain: named by the caller's check */
            continue;
        }
        double xx = -expm1(-mm->sigma * t);
        x[k] = xx;
        double j = medium_jacobian(mm->sigma, xx);
        pdf[k] = j > 0.0 ? pdf[k] / j : INFINITY;
        if (mm->m->weight == MCSTAT_CHECK_WEIGHT_VALUE) /* a value is a density in t, as eval */
            weight[k] = j > 0.0 ? weight[k] / j : INFINITY;
    }
    return 0;
}

static int medium_density(medium_map *mm, mcstat_check_density_fn fn, const double *wi, const double *x,
                          size_t n, double *out)
{
    double t[MEDIUM_CHUNK];
    for (size_t a = 0; a < n; a += MEDIUM_CHUNK) {
        size_t k = n - a < MEDIUM_CHUNK ? n - a : MEDIUM_CHUNK;
        for (size_t i = 0; i < k; i++)
            t[i] = medium_t(mm->sigma, x[a + i]);
        int st = fn(mm->m->user, wi, t, k, out + a);
        if (st)
            return st;
        for (size_t i = 0; i < k; i++) {
            double j = medium_jacobian(mm->sigma, x[a + i]);
            if (!is_float32(out[a + i]))
                mm->not_float32 = 1;
            /* at x = 1 (t = inf) a density that vanishes there stays 0 */
            out[a + i] = out[a + i] == 0.0 ? 0.0 : (j > 0.0 ? out[a + i] / j : INFINITY);
        }
    }
    return 0;
}

static int medium_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    medium_map *mm = (medium_map *)user;
    return medium_density(mm, mm->m->pdf, wi, x, n, out);
}

static int medium_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    medium_map *mm = (medium_map *)user;
    return medium_density(mm, mm->m->eval, wi, x, n, out);
}

static int run_check(int kind, const mcstat_check_model *model, const double *wi_in, double sigma_ref, size_t n,
                     uint64_t seed, double alpha, const mcstat_check_options *opt, void *work, size_t work_bytes,
                     mcstat_check_report *out)
{
    if (!out)
        REFUSE("out (the report) is NULL");
    if (!valid_alpha(alpha))
        REFUSE("alpha must be in (0, 1), got %g", alpha);
    run r;
    memset(&r, 0, sizeof r);
    int st = read_options(opt, &r.o);
    if (st)
        return st;
    st = make_plan(model, kind, n, &r.o, &r.pl);
    if (st)
        return st;
    double wi[3] = {NAN, NAN, NAN};
    int has_wi = kind == MCSTAT_CHECK_KIND_BSDF || kind == MCSTAT_CHECK_KIND_PHASE;
    if (has_wi) {
        if (!wi_in)
            REFUSE("wi is NULL");
        if (!isfinite(wi_in[0]) || !isfinite(wi_in[1]) || !isfinite(wi_in[2]))
            REFUSE("wi must be a finite, non-zero direction, got (%g, %g, %g)", wi_in[0], wi_in[1], wi_in[2]);
        double len = sqrt(wi_in[0] * wi_in[0] + wi_in[1] * wi_in[1] + wi_in[2] * wi_in[2]);
        if (!(len > 0.0) || !isfinite(len))
            REFUSE("wi must be a finite, non-zero direction, got (%g, %g, %g)", wi_in[0], wi_in[1], wi_in[2]);
        for (int c = 0; c < 3; c++)
            wi[c] = wi_in[c] / len;
    }
    size_t need;
    st = carve(&r.pl, NULL, &r.s, &need);
    if (st)
        return st;
    void *owned = NULL;
    if (!work) {
        owned = malloc(need ? need : 1);
        if (!owned)
            return MCSTAT_ENOMEM;
        work = owned;
    } else if (work_bytes < need) {
        REFUSE("work holds %zu bytes; the check needs %zu (mcstat_check_work_size)", work_bytes, need);
    } else if ((uintptr_t)work & 15u) {
        REFUSE("work must be 16-byte aligned");
    }
    carve(&r.pl, work, &r.s, &need);

    memset(out, 0, sizeof *out);
    medium_map mm = {model, sigma_ref, 0};
    mcstat_check_model mapped;
    r.m = model;
    if (kind == MCSTAT_CHECK_KIND_MEDIUM) {
        mapped = *model;
        mapped.user = &mm;
        mapped.sample = medium_sample;
        mapped.pdf = medium_pdf;
        mapped.eval = medium_eval;
        r.m = &mapped;
    }
    r.wi = has_wi ? wi : NULL;
    r.out = out;
    r.rtol = r.o.rtol;
    /* every point may need it (a float32 lobe at grazing incidence puts most
     * of them beyond rtol); a wrong model pays two small calls per point */
    r.rounding_cap = 2 * (uint64_t)n; /* pdf_value's and weight's */
    r.key_pilot = mcstat__stream_key(seed, STREAM_PILOT);
    r.key_test = mcstat__stream_key(seed, STREAM_TEST);
    r.key_eval = mcstat__stream_key(seed, STREAM_EVAL);
    r.key_keep_sample = mcstat__stream_key(seed, STREAM_KEEP_SAMPLE);
    r.key_keep_eval = mcstat__stream_key(seed, STREAM_KEEP_EVAL);
    r.seed = seed;
    out->kind = kind;
    out->domain = model->domain;
    out->alpha = alpha;
    for (int c = 0; c < 3; c++)
        out->wi[c] = wi[c];
    out->n = n;
    out->n_eval = r.pl.n_eval;
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        mcstat__check_route_init(&out->route[i]);

    sums sm;
    memset(&sm, 0, sizeof sm);
    mcstat_moments_init(&sm.all);
    mcstat_moments_init(&sm.escapes);
    out->escape_weight = out->escape_weight_se = NAN;
    st = model->lobes ? fetch_lobes(&r) : MCSTAT_OK;
    if (st == MCSTAT_OK)
        st = pilot_and_cells(&r);
    if (st == MCSTAT_OK) {
        memset(r.s.counts, 0, (size_t)r.tr.n_cells * sizeof(double));
        memset(r.s.cell_r, 0, (size_t)r.tr.n_cells * sizeof(double));
        memset(r.s.cell_r2, 0, (size_t)r.tr.n_cells * sizeof(double));
        st = tested_sample(&r, &sm);
    }
    if (st == MCSTAT_OK)
        st = eval_only(&r, &sm);
    uint32_t want = r.o.routes;
    int bsdf = kind == MCSTAT_CHECK_KIND_BSDF || kind == MCSTAT_CHECK_KIND_PHASE;
    if (st == MCSTAT_OK && bsdf && r.o.reciprocal && (want & (1u << MCSTAT_CHECK_ROUTE_RECIPROCITY)))
        st = reciprocity(&r, &sm);
    if (st != MCSTAT_OK) {
        char keep[sizeof out->message];
        memcpy(keep, out->message, sizeof keep);
        memset(out, 0, sizeof *out);
        if (st == MCSTAT_ECALLBACK)
            memcpy(out->message, keep, sizeof keep);
        free(owned);
        return st;
    }
    out->n_failed = n - sm.n_succ - sm.n_lobe;
    out->n_lobe = sm.n_lobe;

    /* a medium's values are judged as the caller returned them, not as mapped */
    int not_float32 = kind == MCSTAT_CHECK_KIND_MEDIUM ? mm.not_float32 : r.not_float32;
    r.resolution = r.o.resolution > 0.0 ? r.o.resolution
                   : (not_float32 ? MCSTAT_RESOLUTION_FLOAT64 : MCSTAT_RESOLUTION_FLOAT32);

    /* heavy tails first: they decide which mean-based routes can answer */
    out->tail_index[0] = out->tail_index[1] = NAN;
    if (r.pl.has_eval) {
        out->tail_index[0] = mcstat__check_hill_upper(r.s.wsave, sm.n_w);
        out->tail_index[1] = mcstat__check_hill_upper(r.s.vsave, sm.n_v);
        out->heavy_tailed = out->tail_index[0] < 2.0 || out->tail_index[1] < 2.0;
    }

    /* which routes apply */
    int applies[MCSTAT_CHECK_ROUTE_COUNT] = {0};
    applies[MCSTAT_CHECK_ROUTE_CELLS] = 1;
    applies[MCSTAT_CHECK_ROUTE_MASS] = 1;
    applies[MCSTAT_CHECK_ROUTE_PDF_VALUE] = r.pl.reports && !r.o.stochastic;
    applies[MCSTAT_CHECK_ROUTE_WEIGHT] = r.pl.has_eval && !r.o.stochastic;
    applies[MCSTAT_CHECK_ROUTE_SUPPORT] = r.pl.has_eval;
    applies[MCSTAT_CHECK_ROUTE_INTEGRALS] = r.pl.has_eval;
    applies[MCSTAT_CHECK_ROUTE_ENERGY] = bsdf || kind == MCSTAT_CHECK_KIND_MEDIUM;
    applies[MCSTAT_CHECK_ROUTE_RECIPROCITY] = bsdf && r.o.reciprocal;
    applies[MCSTAT_CHECK_ROUTE_KS] = r.pl.has_eval;
    enum { N_STATISTICAL = 5 };
    int statistical[N_STATISTICAL] = {MCSTAT_CHECK_ROUTE_CELLS, MCSTAT_CHECK_ROUTE_MASS, MCSTAT_CHECK_ROUTE_INTEGRALS,
                                      MCSTAT_CHECK_ROUTE_ENERGY, MCSTAT_CHECK_ROUTE_KS};
    int n_stat = 0;
    for (int i = 0; i < N_STATISTICAL; i++)
        if (applies[statistical[i]] && (want & (1u << statistical[i])))
            n_stat++;
    /* the level each statistical route is held to in the worst case of
     * Holm's procedure: what `detectable` is computed at */
    double level = alpha / (n_stat > 0 ? n_stat : 1);
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++) {
        if (!applies[i] || !(want & (1u << i)))
            continue;
        mcstat__check_route(&r, &sm, i, level);
    }
    if (r.pl.has_eval)
        mcstat__check_report_albedos(&r, &sm);

    /* Holm across the statistical routes that ran */
    double p[N_STATISTICAL], adj[N_STATISTICAL];
    int idx[N_STATISTICAL], k = 0;
    for (int i = 0; i < N_STATISTICAL; i++) {
        mcstat_check_route_result *rr = &out->route[statistical[i]];
        if (rr->state == MCSTAT_CHECK_STATE_RAN && !rr->deterministic) {
            p[k] = rr->p_value;
            idx[k++] = statistical[i];
        }
    }
    out->p_value = 1.0;
    if (k > 0) {
        double work_holm[N_STATISTICAL * 8];
        st = mcstat_p_adjust(p, (size_t)k, MCSTAT_P_ADJUST_HOLM, work_holm, sizeof work_holm, adj);
        if (st) {
            free(owned);
            return st;
        }
        for (int i = 0; i < k; i++) {
            mcstat_check_route_result *rr = &out->route[idx[i]];
            rr->p_adjusted = adj[i];
            rr->reject = adj[i] <= alpha;
            if (adj[i] < out->p_value)
                out->p_value = adj[i];
        }
    }
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        if (out->route[i].state == MCSTAT_CHECK_STATE_RAN && out->route[i].reject) {
            out->reject = 1;
            if (out->route[i].deterministic)
                out->p_value = 0.0;
        }
    out->pdf_without_eval = r.pdf_without_eval;
    out->sigma_ref = kind == MCSTAT_CHECK_KIND_MEDIUM ? sigma_ref : 0.0;
    out->zero_weight = r.zero_weight;
    free(owned);
    return MCSTAT_OK;
}

int mcstat_check_bsdf(const mcstat_check_model *model, const double wi[3], size_t n, uint64_t seed, double alpha,
                      const mcstat_check_options *opt, void *work, size_t work_bytes, mcstat_check_report *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    return run_check(MCSTAT_CHECK_KIND_BSDF, model, wi, 0.0, n, seed, alpha, opt, work, work_bytes, out);
}

int mcstat_check_emitter(const mcstat_check_model *model, size_t n, uint64_t seed, double alpha,
                         const mcstat_check_options *opt, void *work, size_t work_bytes, mcstat_check_report *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    return run_check(MCSTAT_CHECK_KIND_EMITTER, model, NULL, 0.0, n, seed, alpha, opt, work, work_bytes, out);
}

int mcstat_check_warp(const mcstat_check_model *model, size_t n, uint64_t seed, double alpha,
                      const mcstat_check_options *opt, void *work, size_t work_bytes, mcstat_check_report *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    return run_check(MCSTAT_CHECK_KIND_WARP, model, NULL, 0.0, n, seed, alpha, opt, work, work_bytes, out);
}

int mcstat_check_phase(const mcstat_check_model *model, const double wi[3], size_t n, uint64_t seed, double alpha,
                       const mcstat_check_options *opt, void *work, size_t work_bytes, mcstat_check_report *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    return run_check(MCSTAT_CHECK_KIND_PHASE, model, wi, 0.0, n, seed, alpha, opt, work, work_bytes, out);
}

int mcstat_check_medium(const mcstat_check_model *model, double sigma_ref, size_t n, uint64_t seed, double alpha,
                        const mcstat_check_options *opt, void *work, size_t work_bytes, mcstat_check_report *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    if (!(sigma_ref > 0.0) || !isfinite(sigma_ref))
        REFUSE("sigma_ref must be finite and > 0, got %g", sigma_ref);
    return run_check(MCSTAT_CHECK_KIND_MEDIUM, model, NULL, sigma_ref, n, seed, alpha, opt, work, work_bytes, out);
}
