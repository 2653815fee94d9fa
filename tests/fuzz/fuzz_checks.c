/*
 * fuzz_checks.c - the renderer checks (mcstat_check_bsdf, _emitter, _warp),
 * their scratch size, the report's formatting and the name functions,
 * driven by callbacks whose behaviour the input programs.
 *
 * Input: the model (kind, domain, n_uniforms, weight convention,
 * sample_reports, eval NULL or not, reserved fields, which correct density
 * the callbacks implement and the albedo), the options (NULL or set; routes,
 * stochastic, reciprocal, cells, n_pilot, n_eval, batch, rtol, reserved,
 * invalid values too; values that pass the argument checks are kept small so
 * that one input runs in milliseconds), n (1000..4000, or invalid), alpha,
 * seed, wi, how the scratch is passed; then up to MAXFAULTS faults, each
 * corrupting what one callback returns on its k-th call (or every call) at
 * one point, every point or the points of a region: a non-zero status, a
 * value set to anything fz_double gives (NaN, Inf, negative, huge,
 * subnormal), scaled, zeroed (pdf 0 where eval > 0, failed samples), a point
 * moved off the domain or slightly off unit length, below the horizon.
 *
 * The callbacks classify what they return as the library must (a non-zero
 * status, NaN, Inf or a negative density or weight, a point clearly off the
 * domain: MCSTAT_ECALLBACK from that call; a point within rounding of the
 * domain's tolerance: either).  Invariants: the status is a documented
 * code; MCSTAT_ECALLBACK exactly when a callback returned something invalid
 * (or a value/pdf weight overflowed), its message naming the callback, no
 * callback called after the failing one; the callbacks get at most `batch`
 * points, uniforms in [0, 1), points inside the domain (the library's
 * tolerance), wi as documented, eval never for a warp; on MCSTAT_OK each
 * route SKIPPED when not asked for, RAN/SKIPPED/INVALID, a RAN statistical
 * route has p in [0, 1], p_adjusted in [p, 1] and rejects iff p_adjusted <=
 * alpha, a deterministic route rejects iff points were beyond tolerance,
 * report.reject iff some RAN route rejects, report.p_value the smallest
 * adjusted p-value (0 after a deterministic failure, 1 with none), `calls`
 * the callbacks' count, the text block formats into 16 KiB with its length
 * and into 0..64-byte buffers (malloc'ed exactly) as MCSTAT_EBUFSIZE with a
 * NUL-terminated prefix.  The same input run again, with the scratch
 * NULL or caller-owned of exactly mcstat_check_work_size bytes, gives the
 * same status and the same report byte for byte; one byte less is
 * MCSTAT_EINVAL.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#include <stdlib.h>

#define MAXFAULTS 8
#define PI 3.14159265358979323846

enum { CB_SAMPLE, CB_PDF, CB_EVAL, CB_COUNT };
static const char *const cb_names[CB_COUNT] = {"sample", "pdf", "eval"};

enum { SEL_ONE, SEL_ALL, SEL_REGION };
enum { F_STATUS, F_SET, F_SCALE, F_LENGTH, F_ZERO, F_FLIP, F_SUBNORMAL, F_HUGE, F_KINDS };

typedef struct fault {
    int cb, every, sel, what, field;
    uint32_t call, point;
    double value, threshold;
    int status;
} fault;

typedef struct model_state {
    int kind, domain, dims, nu, variant, reports, weight;
    double albedo;
    fault faults[MAXFAULTS];
    int n_faults;
    uint64_t batch;       /* the batch the options ask for (default 65536) */
    double wi[3];         /* the normalised wi (BSDFs) */
    /* counted by the callbacks */
    uint64_t calls, calls_cb[CB_COUNT];
    int invalid;          /* a callback returned something the library must refuse */
    int ambiguous;        /* ... or a point within rounding of the domain's tolerance */
    int overflow;         /* a value/pdf weight that overflows */
    int last_flagged;     /* the last call returned something invalid or ambiguous */
    int called_after;     /* a callback was called after an invalid return */
} model_state;

/* ---- the domains ----------------------------------------------------------- */

/* How far x is beyond the library's rule for the domain (mcstat.h: a
 * direction of unit length within 1e-4, checked as |len^2 - 1| <= 2e-4, with
 * z >= -1e-4 on the hemisphere; the square, disk and interval within 1e-6):
 * positive outside, negative inside (how far inside), +Inf for a
 * non-finite coordinate. */
static double off_domain(int domain, const double *x)
{
    int dims = mcstat_check_domain_dims(domain);
    for (int c = 0; c < dims; c++)
        if (!isfinite(x[c]))
            return INFINITY;
    if (dims == 3) {
        double len2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        double e = fabs(len2 - 1.0) - 2e-4;
        if (domain == MCSTAT_CHECK_DOMAIN_HEMISPHERE && len2 > 0.0)
            e = fmax(e, -1e-4 - x[2] / sqrt(len2));
        return e;
    }
    if (domain == MCSTAT_CHECK_DOMAIN_DISK)
        return x[0] * x[0] + x[1] * x[1] - 1.0 - 1e-6;
    double e = -INFINITY;
    for (int c = 0; c < dims; c++)
        e = fmax(e, fmax(-1e-6 - x[c], x[c] - 1.0 - 1e-6));
    return e;
}

/* Within this of the rule the library may decide either way (rounding). */
#define AMBIGUOUS 1e-9

/* The correct model: a density on the domain, its sampler, eval = albedo
 * times the density (a BSDF whose sampler is exact).  Variant 0 uniform,
 * 1 cosine-like (on the sphere: a clamped cosine on each hemisphere). */
static double density(const model_state *m, const double *x)
{
    switch (m->domain) {
    case MCSTAT_CHECK_DOMAIN_SPHERE: return m->variant ? fabs(x[2]) / (2 * PI) : 1.0 / (4 * PI);
    case MCSTAT_CHECK_DOMAIN_HEMISPHERE: return m->variant ? fmax(x[2], 0.0) / PI : 1.0 / (2 * PI);
    case MCSTAT_CHECK_DOMAIN_SQUARE: return m->variant ? 2.0 * fmin(fmax(x[0], 0.0), 1.0) : 1.0;
    case MCSTAT_CHECK_DOMAIN_DISK: return m->variant ? 3.0 * sqrt(fmin(x[0] * x[0] + x[1] * x[1], 1.0)) / (2 * PI) : 1.0 / PI;
    default: return m->variant ? 2.0 * fmin(fmax(x[0], 0.0), 1.0) : 1.0;
    }
}

static void draw(const model_state *m, const double *u, double *x)
{
    double u0 = u[0], u1 = m->nu >= 2 ? u[1] : fmod(u0 * 65536.0, 1.0);
    double phi = 2 * PI * u1, z, r;
    switch (m->domain) {
    case MCSTAT_CHECK_DOMAIN_SPHERE:
        if (m->variant)
            z = u0 < 0.5 ? sqrt(2 * u0) : -sqrt(2 * u0 - 1);
        else
            z = 1 - 2 * u0;
        r = sqrt(fmax(0.0, 1 - z * z));
        x[0] = r * cos(phi), x[1] = r * sin(phi), x[2] = z;
        break;
    case MCSTAT_CHECK_DOMAIN_HEMISPHERE:
        z = m->variant ? sqrt(u0) : u0;
        r = sqrt(fmax(0.0, 1 - z * z));
        x[0] = r * cos(phi), x[1] = r * sin(phi), x[2] = z;
        break;
    case MCSTAT_CHECK_DOMAIN_SQUARE: x[0] = m->variant ? sqrt(u0) : u0, x[1] = u1; break;
    case MCSTAT_CHECK_DOMAIN_DISK:
        r = m->variant ? cbrt(u0) : sqrt(u0);
        x[0] = r * cos(phi), x[1] = r * sin(phi);
        break;
    default: x[0] = m->variant ? sqrt(u0) : u0; break;
    }
}

/* ---- faults ---------------------------------------------------------------- */

static int fault_applies(const fault *f, int cb, uint64_t call, size_t k, const double *x)
{
    if (f->cb != cb || (!f->every && f->call != call))
        return 0;
    switch (f->sel) {
    case SEL_ONE: return k == f->point;
    case SEL_ALL: return 1;
    default: return x[0] > f->threshold;
    }
}

static double corrupt_value(const fault *f, double v)
{
    switch (f->what) {
    case F_SET: return f->value;
    case F_SCALE: return v * f->value;
    case F_ZERO: return 0.0;
    case F_SUBNORMAL: return 4.9406564584124654e-324 * (1 + f->point % 7);
    case F_HUGE: return f->point & 1 ? DBL_MAX / (1 + f->point % 5) : 1e300;
    default: return v;
    }
}

static void corrupt_point(const fault *f, int dims, double *x)
{
    if (f->what == F_LENGTH) {
        for (int c = 0; c < dims; c++)
            x[c] *= 1.0 + f->value;
    } else if (f->what == F_FLIP) {
        x[dims - 1] = -x[dims - 1];
    } else if (f->what == F_SET) {
        x[f->point % (uint32_t)dims] = f->value;
    } else if (f->what == F_SCALE) {
        x[f->point % (uint32_t)dims] *= f->value;
    }
}

/* ---- the callbacks --------------------------------------------------------- */

/* Counts a call and checks what the library may pass: wi, n <= batch. */
static uint64_t enter(model_state *m, int cb, const double *wi, size_t n)
{
    if (m->invalid)
        m->called_after = 1;
    m->calls++;
    uint64_t call = m->calls_cb[cb]++;
    FZ_ASSERT(n <= m->batch, "%s() called with %zu points, batch %llu", cb_names[cb], n,
              (unsigned long long)m->batch);
    FZ_ASSERT(!(m->kind == MCSTAT_CHECK_KIND_WARP && cb == CB_EVAL), "eval() called for a warp");
    if (m->kind == MCSTAT_CHECK_KIND_BSDF) {
        FZ_ASSERT(wi != NULL, "%s() got wi NULL", cb_names[cb]);
        int same = wi[0] == m->wi[0] && wi[1] == m->wi[1] && wi[2] == m->wi[2];
        /* reciprocity: eval(x, wi) one point at a time, x a sampled direction */
        int swapped = cb == CB_EVAL && n == 1 && off_domain(MCSTAT_CHECK_DOMAIN_SPHERE, wi) <= AMBIGUOUS;
        FZ_ASSERT(same || swapped, "%s() got wi (%a, %a, %a), the check's is (%a, %a, %a)", cb_names[cb], wi[0],
                  wi[1], wi[2], m->wi[0], m->wi[1], m->wi[2]);
    } else {
        FZ_ASSERT(wi == NULL, "%s() got wi non-NULL for kind %d", cb_names[cb], m->kind);
    }
    return call;
}

static void mark(model_state *m, int invalid, int ambiguous)
{
    m->last_flagged = invalid || ambiguous;
    m->invalid |= invalid;
    m->ambiguous |= ambiguous;
}

static int status_fault(model_state *m, int cb, uint64_t call)
{
    for (int i = 0; i < m->n_faults; i++) {
        const fault *f = &m->faults[i];
        if (f->what == F_STATUS && f->cb == cb && (f->every || f->call == call) && f->status != 0)
            return f->status;
    }
    return 0;
}

static int cb_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                     double *pdf)
{
    model_state *m = user;
    uint64_t call = enter(m, CB_SAMPLE, wi, n);
    int dims = m->dims, bad = 0, amb = 0;
    for (size_t k = 0; k < n; k++) {
        for (int j = 0; j < m->nu; j++)
            FZ_ASSERT(u[k * m->nu + j] >= 0.0 && u[k * m->nu + j] < 1.0, "uniform %a", u[k * m->nu + j]);
        double *xk = x + k * dims;
        draw(m, u + k * m->nu, xk);
        double p = density(m, xk), w = m->weight == MCSTAT_CHECK_WEIGHT_VALUE ? m->albedo * p : m->albedo;
        for (int i = 0; i < m->n_faults; i++) {
            const fault *f = &m->faults[i];
            if (f->what == F_STATUS || !fault_applies(f, CB_SAMPLE, call, k, xk))
                continue;
            if (f->field == 0 || f->what == F_LENGTH || f->what == F_FLIP)
                corrupt_point(f, dims, xk);
            else if (f->field == 1)
                w = corrupt_value(f, w);
            else if (f->what == F_ZERO)
                p = w = 0.0; /* a failed sample */
            else
                p = corrupt_value(f, p);
        }
        if (m->reports) {
            weight[k] = w;
            pdf[k] = p;
        } else {
            p = 1.0, w = 0.0; /* what the library assumes */
        }
        /* the library's rule (mcstat.h): pdf and weight finite and >= 0, the
         * point in the domain unless pdf = 0 */
        if (!isfinite(p) || p < 0.0 || !isfinite(w) || w < 0.0) {
            bad = 1;
        } else if (p > 0.0) {
            double e = off_domain(m->domain, xk);
            if (e > AMBIGUOUS)
                bad = 1;
            else if (e >= -AMBIGUOUS)
                amb = 1; /* at the rule's edge rounding decides */
            if (m->reports && m->weight == MCSTAT_CHECK_WEIGHT_VALUE && isinf(w / p))
                m->overflow = 1;
        }
    }
    int st = status_fault(m, CB_SAMPLE, call);
    mark(m, bad || st != 0, amb);
    return st;
}

/* A point the library passes to pdf() or eval(): one a sampler returned and
 * the library accepted, or one of its own (cubature, table): in the domain
 * within the library's tolerance. */
static void check_point(const model_state *m, int cb, const double *x)
{
    double e = off_domain(m->domain, x);
    FZ_ASSERT(e <= AMBIGUOUS, "%s() got a point off the %s domain by %a: (%a, %a, %a)", cb_names[cb],
              mcstat_check_domain_name(m->domain), e, x[0], m->dims > 1 ? x[1] : 0.0, m->dims > 2 ? x[2] : 0.0);
}

static int cb_density(model_state *m, int cb, const double *wi, const double *x, size_t n, double *out)
{
    uint64_t call = enter(m, cb, wi, n);
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        const double *xk = x + k * m->dims;
        check_point(m, cb, xk);
        double v = density(m, xk) * (cb == CB_EVAL ? m->albedo : 1.0);
        for (int i = 0; i < m->n_faults; i++) {
            const fault *f = &m->faults[i];
            if (f->what != F_STATUS && fault_applies(f, cb, call, k, xk))
                v = corrupt_value(f, v);
        }
        out[k] = v;
        if (!isfinite(v) || v < 0.0)
            bad = 1;
    }
    int st = status_fault(m, cb, call);
    mark(m, bad || st != 0, 0);
    return st;
}

static int cb_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    return cb_density(user, CB_PDF, wi, x, n, out);
}

static int cb_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    return cb_density(user, CB_EVAL, wi, x, n, out);
}

/* ---- decoding ---------------------------------------------------------------- */

static int32_t pick(fz_input *in, int32_t valid_count)
{
    uint8_t b = fz_u8(in);
    return b < 240 ? b % valid_count : (int32_t)fz_u32(in);
}

static void decode_fault(fz_input *in, fault *f)
{
    f->cb = fz_u8(in) % CB_COUNT;
    uint8_t when = fz_u8(in);
    f->every = when == 255;
    f->call = when % 16;
    uint8_t sel = fz_u8(in);
    f->sel = sel % 4 == 0 ? SEL_ALL : sel % 4 == 1 ? SEL_REGION : SEL_ONE;
    f->point = fz_u16(in);
    f->threshold = (int8_t)fz_u8(in) / 128.0;
    f->what = fz_u8(in) % F_KINDS;
    f->field = fz_u8(in) % 3; /* sample(): the point, the weight, the pdf */
    f->status = 0;
    f->value = 0.0;
    if (f->what == F_STATUS) {
        uint8_t s = fz_u8(in);
        f->status = s < 200 ? 1 + s % 16 : (int)fz_u32(in);
        if (f->status == 0)
            f->status = -1;
    } else if (f->what == F_LENGTH) {
        static const double eps[] = {1e-7, 4e-5, 9.9e-5, 1.0001e-4, 1.5e-4, 1e-3, 0.1, -0.5, -1e-5, -1.2e-4};
        uint8_t e = fz_u8(in);
        f->value = e < 200 ? eps[e % 10] : fz_double(in);
    } else if (f->what == F_SET || f->what == F_SCALE) {
        f->value = fz_double(in);
    }
}

typedef struct decoded {
    mcstat_check_model model;
    mcstat_check_options opt;
    int opt_null, work_mode;
    size_t n;
    double alpha, wi[3];
    uint64_t seed;
} decoded;

/* A value that passes the argument check is kept small (one input in
 * milliseconds); invalid ones reach the checks. */
static uint64_t pilot_or_eval(fz_input *in, uint64_t lo, uint64_t span)
{
    uint8_t b = fz_u8(in);
    if (b < 128)
        return 0;
    if (b < 200)
        return lo + fz_u16(in) % span;
    if (b < 230)
        return fz_u16(in) % lo; /* below the minimum */
    return (uint64_t)1 << 50 | fz_u32(in); /* beyond the maximum */
}

static void decode(fz_input *in, decoded *d, model_state *m)
{
    memset(d, 0, sizeof *d);
    memset(m, 0, sizeof *m);
    m->kind = fz_u8(in) % 3;
    mcstat_check_model *md = &d->model;
    md->domain = pick(in, 5);
    uint8_t b = fz_u8(in);
    md->n_uniforms = b < 240 ? 1 + b % MCSTAT_CHECK_MAX_UNIFORMS : (int32_t)fz_u32(in);
    md->weight = pick(in, 2);
    b = fz_u8(in);
    md->sample_reports = b < 240 ? (m->kind != MCSTAT_CHECK_KIND_WARP || (b & 1)) : (int32_t)fz_u32(in);
    uint8_t mflags = fz_u8(in);
    m->variant = mflags & 1;
    m->albedo = (fz_u8(in) + 1) / 240.0; /* up to 1.07: ENERGY may reject */
    md->user = m;
    md->sample = cb_sample;
    md->pdf = cb_pdf;
    md->eval = (mflags & 2) && m->kind == MCSTAT_CHECK_KIND_WARP ? NULL : cb_eval;
    if ((mflags & 0x1c) == 0x1c) /* rarely: no eval for a BSDF, NULL callbacks, reserved */
        switch ((mflags >> 5) % 4) {
        case 0: md->eval = NULL; break;
        case 1: md->sample = NULL; break;
        case 2: md->pdf = NULL; break;
        default: md->reserved[mflags % 4] = 1.0; break;
        }

    uint8_t oflags = fz_u8(in);
    d->opt_null = oflags & 1;
    FZ_ASSERT(mcstat_check_options_init(&d->opt) == MCSTAT_OK, "options_init");
    mcstat_check_options *o = &d->opt;
    uint16_t r16 = fz_u16(in);
    if (r16 & 0x8000)
        o->routes = fz_u32(in);
    else if (r16 & 0x4000)
        o->routes = MCSTAT_CHECK_ROUTE_ALL;
    else
        o->routes = r16 & MCSTAT_CHECK_ROUTE_ALL;
    b = fz_u8(in);
    o->stochastic = b < 250 ? b & 1 : (int32_t)fz_u32(in);
    b = fz_u8(in);
    o->reciprocal = b < 250 ? b & 1 : (int32_t)fz_u32(in);
    b = fz_u8(in);
    o->cells = b < 128 ? 0 : b < 224 ? 2 + b % 64 : (int32_t)fz_u32(in);
    o->n_pilot = pilot_or_eval(in, 64, 6000);
    o->n_eval = pilot_or_eval(in, 1000, 4000);
    b = fz_u8(in);
    o->batch = b < 100 ? 65536u : b < 200 ? 64u + fz_u16(in) % 4000u : b < 230 ? (uint64_t)fz_u8(in) : fz_u64(in);
    b = fz_u8(in);
    o->rtol = b < 200 ? 1e-3 : b < 230 ? pow(10.0, -(b - 199) / 3.0) : fz_double(in);
    if (oflags & 2)
        o->size = (uint32_t)fz_range(in, 0, 2 * sizeof *o);
    if ((oflags & 0x0c) == 0x0c) {
        if (oflags & 0x10)
            o->reserved_i = 1;
        else
            o->reserved[(oflags >> 5) % 4] = 1e-300;
    }
    /* keep what passes the checks small: target cells beyond 256 need an
     * explicit small pilot (32 pilot points per cell otherwise) */
    if (o->cells > 256 && o->cells <= (1 << 20) && (o->n_pilot == 0 || o->n_pilot > (1ull << 40)))
        o->n_pilot = 64 + (uint64_t)o->cells % 6000;

    b = fz_u8(in);
    d->n = b < 240 ? (size_t)fz_range(in, 1000, 4000) : b < 248 ? fz_u16(in) % 1000 : ((size_t)1 << 48) + 1 + fz_u8(in);
    d->alpha = fz_alpha(in);
    d->seed = fz_u64(in);
    b = fz_u8(in);
    if (b < 200) {
        /* a direction from two angles, below the horizon too */
        double th = PI * fz_u8(in) / 255.0, ph = 2 * PI * fz_u8(in) / 256.0;
        double len = b < 100 ? 1.0 : 0.5 + b / 50.0;
        d->wi[0] = len * sin(th) * cos(ph), d->wi[1] = len * sin(th) * sin(ph), d->wi[2] = len * cos(th);
    } else {
        for (int c = 0; c < 3; c++)
            d->wi[c] = fz_double(in);
    }
    d->work_mode = fz_u8(in) % 4;

    m->domain = md->domain;
    m->dims = mcstat_check_domain_dims(md->domain);
    m->nu = md->n_uniforms;
    m->reports = md->sample_reports;
    m->weight = md->weight;
    m->batch = d->opt_null ? 65536 : o->batch;
    m->n_faults = (int)fz_range(in, 0, MAXFAULTS);
    for (int i = 0; i < m->n_faults; i++)
        decode_fault(in, &m->faults[i]);
}

/* ---- one run and its invariants ------------------------------------------- */

static void reset_counts(model_state *m)
{
    m->calls = 0;
    memset(m->calls_cb, 0, sizeof m->calls_cb);
    m->invalid = m->ambiguous = m->overflow = m->called_after = 0;
    m->last_flagged = 0;
}

static int run_once(const decoded *d, model_state *m, void *work, size_t work_bytes, mcstat_check_report *rep)
{
    reset_counts(m);
    memset(rep, 0, sizeof *rep);
    const mcstat_check_options *opt = d->opt_null ? NULL : &d->opt;
    switch (m->kind) {
    case MCSTAT_CHECK_KIND_BSDF:
        return mcstat_check_bsdf(&d->model, d->wi, d->n, d->seed, d->alpha, opt, work, work_bytes, rep);
    case MCSTAT_CHECK_KIND_EMITTER:
        return mcstat_check_emitter(&d->model, d->n, d->seed, d->alpha, opt, work, work_bytes, rep);
    default: return mcstat_check_warp(&d->model, d->n, d->seed, d->alpha, opt, work, work_bytes, rep);
    }
}

static void check_format(const mcstat_check_report *r)
{
    static char big[16384];
    size_t len = 0;
    int st = mcstat_check_format(r, big, sizeof big, &len);
    FZ_ASSERT(st == MCSTAT_OK, "check_format status %d", st);
    FZ_ASSERT(strlen(big) == len, "check_format length %zu, strlen %zu", len, strlen(big));
    for (size_t size = 0; size <= 64; size++) {
        char *small = malloc(size ? size : 1);
        size_t l2 = 0;
        st = mcstat_check_format(r, size ? small : NULL, size, &l2);
        FZ_ASSERT(st == MCSTAT_EBUFSIZE, "check_format into %zu bytes: status %d", size, st);
        FZ_ASSERT(l2 == len, "check_format into %zu bytes: length %zu, want %zu", size, l2, len);
        if (size) {
            FZ_ASSERT(memchr(small, 0, size) != NULL, "check_format into %zu bytes: not NUL-terminated", size);
            size_t k = strlen(small);
            FZ_ASSERT(k < size && memcmp(small, big, k) == 0, "check_format into %zu bytes: not a prefix", size);
        }
        free(small);
    }
}

static void check_report(int st, const decoded *d, const model_state *m, const mcstat_check_report *r)
{
    FZ_ASSERT(st == MCSTAT_OK || st == MCSTAT_EINVAL || st == MCSTAT_ETOOBIG || st == MCSTAT_ENOMEM ||
                  st == MCSTAT_ECALLBACK,
              "status %d (%s)", st, mcstat_strerror(st));
    FZ_ASSERT(!m->called_after, "a callback was called after one returned an invalid value (status %d)", st);
    if (st == MCSTAT_ECALLBACK) {
        FZ_ASSERT(memchr(r->message, 0, sizeof r->message) && r->message[0], "ECALLBACK without a message");
        FZ_ASSERT(strstr(r->message, "sample") || strstr(r->message, "pdf") || strstr(r->message, "eval"),
                  "message names no callback: %s", r->message);
        int weight_overflow = m->overflow && strstr(r->message, "overflowed") != NULL;
        FZ_ASSERT(m->invalid || m->ambiguous || weight_overflow, "ECALLBACK, yet every callback was valid: %s",
                  r->message);
        if (!weight_overflow)
            FZ_ASSERT(m->last_flagged, "ECALLBACK after call %llu, which returned nothing invalid: %s",
                      (unsigned long long)m->calls, r->message);
        return;
    }
    FZ_ASSERT(!m->invalid, "status %d although a callback returned an invalid value or status", st);
    FZ_ASSERT(r->message[0] == 0, "status %d with a message: %.255s", st, r->message);
    if (st != MCSTAT_OK)
        return;

    FZ_ASSERT(r->kind == m->kind && r->domain == d->model.domain, "kind %d domain %d", r->kind, r->domain);
    FZ_ASSERT(r->alpha == d->alpha && r->n == d->n, "alpha %a n %llu", r->alpha, (unsigned long long)r->n);
    FZ_ASSERT(r->calls == m->calls, "report counts %llu calls, the callbacks %llu", (unsigned long long)r->calls,
              (unsigned long long)m->calls);
    FZ_ASSERT(r->n_failed <= r->n, "n_failed %llu of %llu",
              (unsigned long long)r->n_failed, (unsigned long long)r->n);
    FZ_ASSERT(r->reject == 0 || r->reject == 1, "reject %d", r->reject);
    FZ_ASSERT(r->heavy_tailed == 0 || r->heavy_tailed == 1, "heavy_tailed %d", r->heavy_tailed);
    FZ_ASSERT(r->p_value >= 0.0 && r->p_value <= 1.0, "report p_value %a", r->p_value);
    if (m->kind == MCSTAT_CHECK_KIND_BSDF)
        FZ_ASSERT(fabs(r->wi[0] * r->wi[0] + r->wi[1] * r->wi[1] + r->wi[2] * r->wi[2] - 1.0) < 1e-12,
                  "wi (%a, %a, %a)", r->wi[0], r->wi[1], r->wi[2]);
    else
        FZ_ASSERT(isnan(r->wi[0]) && isnan(r->wi[1]) && isnan(r->wi[2]), "wi set for kind %d", m->kind);

    uint32_t want = d->opt_null ? MCSTAT_CHECK_ROUTE_ALL : d->opt.routes;
    int any_reject = 0, det_reject = 0;
    double min_adj = 1.0;
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++) {
        const mcstat_check_route_result *rr = &r->route[i];
        FZ_ASSERT(rr->state == MCSTAT_CHECK_STATE_RAN || rr->state == MCSTAT_CHECK_STATE_SKIPPED ||
                      rr->state == MCSTAT_CHECK_STATE_INVALID,
                  "route %d state %d", i, rr->state);
        FZ_ASSERT(rr->reject == 0 || rr->reject == 1, "route %d reject %d", i, rr->reject);
        FZ_ASSERT(rr->deterministic == 0 || rr->deterministic == 1, "route %d deterministic %d", i,
                  rr->deterministic);
        if (!(want & (1u << i)))
            FZ_ASSERT(rr->state == MCSTAT_CHECK_STATE_SKIPPED, "route %d not asked for, state %d", i, rr->state);
        if (rr->state != MCSTAT_CHECK_STATE_RAN) {
            FZ_ASSERT(!rr->reject, "route %d rejects in state %d", i, rr->state);
            continue;
        }
        if (rr->deterministic) {
            if (i != MCSTAT_CHECK_ROUTE_ENERGY)
                FZ_ASSERT(rr->reject == (rr->count > 0) && rr->count <= rr->checked,
                          "route %d: reject %d with %llu of %llu beyond tolerance", i, rr->reject,
                          (unsigned long long)rr->count, (unsigned long long)rr->checked);
            det_reject |= rr->reject;
        } else {
            FZ_ASSERT(rr->p_value >= 0.0 && rr->p_value <= 1.0, "route %d p_value %a", i, rr->p_value);
            FZ_ASSERT(rr->p_adjusted >= rr->p_value && rr->p_adjusted <= 1.0, "route %d p %a, adjusted %a", i,
                      rr->p_value, rr->p_adjusted);
            FZ_ASSERT(rr->reject == (rr->p_adjusted <= d->alpha), "route %d reject %d, adjusted %a, alpha %a", i,
                      rr->reject, rr->p_adjusted, d->alpha);
            FZ_ASSERT(!isnan(rr->statistic), "route %d RAN with a NaN statistic", i);
            min_adj = fmin(min_adj, rr->p_adjusted);
        }
        any_reject |= rr->reject;
    }
    FZ_ASSERT(r->reject == any_reject, "report reject %d, routes %d", r->reject, any_reject);
    FZ_ASSERT(r->p_value == (det_reject ? 0.0 : min_adj), "report p_value %a, smallest adjusted %a%s", r->p_value,
              min_adj, det_reject ? " (a deterministic route failed)" : "");
    check_format(r);
}

/* The names: every valid value round-trips, every other gives NULL. */
static void check_names(int v)
{
    const char *s = mcstat_check_route_name(v);
    int valid = v >= 0 && v < MCSTAT_CHECK_ROUTE_COUNT, back = -1;
    FZ_ASSERT((s != NULL) == valid, "route_name(%d)", v);
    FZ_ASSERT((mcstat_check_route_meaning(v) != NULL) == valid && (mcstat_check_route_blind_spot(v) != NULL) == valid,
              "route_meaning/blind_spot(%d)", v);
    if (s)
        FZ_ASSERT(mcstat_check_route_parse(s, &back) == MCSTAT_OK && back == v, "route_parse(%s)", s);
    s = mcstat_check_domain_name(v);
    valid = v >= 0 && v <= MCSTAT_CHECK_DOMAIN_INTERVAL;
    FZ_ASSERT((s != NULL) == valid && (mcstat_check_domain_dims(v) != 0) == valid, "domain_name(%d)", v);
    if (s)
        FZ_ASSERT(mcstat_check_domain_parse(s, &back) == MCSTAT_OK && back == v, "domain_parse(%s)", s);
    FZ_ASSERT(mcstat_check_route_parse("cellz", &back) == MCSTAT_EINVAL, "route_parse of a bad name");
    FZ_ASSERT(mcstat_check_domain_parse(NULL, &back) == MCSTAT_EINVAL, "domain_parse(NULL)");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    static decoded d;
    static model_state m;
    decode(&in, &d, &m);
    check_names((int)(int8_t)(data && size ? data[size - 1] : 0) % 12);

    /* the direction the BSDF's callbacks must see */
    double len = sqrt(d.wi[0] * d.wi[0] + d.wi[1] * d.wi[1] + d.wi[2] * d.wi[2]);
    for (int c = 0; c < 3; c++)
        m.wi[c] = d.wi[c] / len;

    if (fz_verbose()) {
        const mcstat_check_options *o = &d.opt;
        fprintf(stderr,
                "kind %d domain %d n_uniforms %d weight %d sample_reports %d variant %d albedo %a eval %s\n"
                "opt %s size %u routes 0x%x stochastic %d reciprocal %d cells %d n_pilot %llu n_eval %llu batch %llu "
                "rtol %a\nn %zu alpha %a seed %llu wi (%a, %a, %a) work mode %d\n",
                m.kind, d.model.domain, d.model.n_uniforms, d.model.weight, d.model.sample_reports, m.variant,
                m.albedo, d.model.eval ? "set" : "NULL", d.opt_null ? "NULL" : "set", o->size, o->routes,
                o->stochastic, o->reciprocal, o->cells, (unsigned long long)o->n_pilot,
                (unsigned long long)o->n_eval, (unsigned long long)o->batch, o->rtol, d.n, d.alpha,
                (unsigned long long)d.seed, d.wi[0], d.wi[1], d.wi[2], d.work_mode);
        for (int i = 0; i < m.n_faults; i++) {
            const fault *f = &m.faults[i];
            fprintf(stderr,
                    "fault %d: %s() call %s%u sel %d point %u threshold %g what %d field %d value %a status %d\n", i,
                    cb_names[f->cb], f->every ? "every " : "", f->call, f->sel, f->point, f->threshold, f->what,
                    f->field, f->value, f->status);
        }
    }

    static mcstat_check_report r1, r2;
    int st1 = run_once(&d, &m, NULL, 0, &r1);
    if (fz_verbose()) {
        static char text[16384];
        fprintf(stderr, "status %d, %llu calls, message: %s\n", st1, (unsigned long long)m.calls, r1.message);
        if (st1 == MCSTAT_OK && mcstat_check_format(&r1, text, sizeof text, NULL) == MCSTAT_OK)
            fprintf(stderr, "%s\nmass %a mass_error %a mass_sampled %a se %a tail_index %a %a\n", text, r1.mass,
                    r1.mass_error, r1.mass_sampled, r1.mass_sampled_se, r1.tail_index[0], r1.tail_index[1]);
    }
    check_report(st1, &d, &m, &r1);
    if (st1 != MCSTAT_OK && st1 != MCSTAT_ECALLBACK) {
        /* whatever failed: the zeroed or untouched report still formats or is refused */
        char buf[256];
        int sf = mcstat_check_format(&r1, buf, sizeof buf, NULL);
        FZ_ASSERT(sf == MCSTAT_OK || sf == MCSTAT_EINVAL || sf == MCSTAT_EBUFSIZE, "format status %d", sf);
    }

    size_t bytes = 0;
    const mcstat_check_options *opt = d.opt_null ? NULL : &d.opt;
    int sw = mcstat_check_work_size(&d.model, d.n, opt, &bytes);
    FZ_ASSERT(sw == MCSTAT_OK || sw == MCSTAT_EINVAL || sw == MCSTAT_ETOOBIG, "work_size status %d", sw);
    FZ_ASSERT(mcstat_check_work_size(&d.model, d.n, opt, NULL) == MCSTAT_EINVAL, "work_size with bytes NULL");
    if (sw == MCSTAT_OK)
        FZ_ASSERT(bytes > 0, "work_size 0");
    /* the call's own checks come first: a refused call is refused either way */
    if (sw != MCSTAT_OK && st1 != MCSTAT_EINVAL && st1 != MCSTAT_ETOOBIG)
        FZ_ASSERT(0, "work_size status %d, but the check ran (status %d)", sw, st1);

    /* Again, with the scratch NULL or exactly work_size bytes: the same. */
    void *work = NULL;
    size_t work_bytes = 0;
    if (sw == MCSTAT_OK && d.work_mode != 0) {
        work = malloc(bytes);
        work_bytes = bytes;
        FZ_ASSERT(work && ((uintptr_t)work & 15u) == 0, "malloc");
    }
    if (work || d.work_mode == 0) {
        int st2 = run_once(&d, &m, work, work_bytes, &r2);
        FZ_ASSERT(st2 == st1 || st1 == MCSTAT_ENOMEM || st2 == MCSTAT_ENOMEM, "status %d, then %d (work %s)", st1,
                  st2, work ? "given" : "NULL");
        FZ_ASSERT(memcmp(&r1, &r2, sizeof r1) == 0, "the same input gave different reports (status %d, work %s)",
                  st1, work ? "given" : "NULL");
        check_report(st2, &d, &m, &r2);
    }
    if (sw == MCSTAT_OK && d.work_mode >= 2) {
        /* one byte short (or misaligned): refused before any callback */
        char *w = work;
        size_t wb = bytes - 1;
        if (d.work_mode == 3) {
            w = (char *)work + 1;
            wb = bytes - 1;
        }
        int st3 = run_once(&d, &m, w, wb, &r2);
        FZ_ASSERT(st3 == MCSTAT_EINVAL || (st3 == MCSTAT_ETOOBIG && st1 == MCSTAT_ETOOBIG),
                  "work of %zu bytes (needs %zu)%s: status %d", wb, bytes, d.work_mode == 3 ? ", misaligned" : "",
                  st3);
        FZ_ASSERT(m.calls == 0, "%llu callbacks with too small a scratch", (unsigned long long)m.calls);
    }
    free(work);
    return 0;
}
