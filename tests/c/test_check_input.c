/*
 * test_check_input.c - the renderer checks (mcstat_check_*) on bad input,
 * through the public C API only: every case the header's statuses list
 * gives its documented status (MCSTAT_EINVAL, MCSTAT_ETOOBIG,
 * MCSTAT_ECALLBACK), and a callback's failure or invalid
 * values give MCSTAT_ECALLBACK with a message naming the callback.
 *
 * The model is a small valid one (cosine-weighted directions, uniform
 * points on the square, disk and interval) into which one fault at a time
 * is planted, at the fault_at-th point the callback sees (counted over
 * its calls, so a fault can sit inside a batch or in a later call).
 */
#include "mcstat.h"
#include "harness.h"

#include <stdint.h>
#include <string.h>

#define PI 3.14159265358979323846

enum fault {
    F_NONE,
    /* sample() */
    F_SAMPLE_RETURNS,
    F_SAMPLE_NAN_WEIGHT,
    F_SAMPLE_INF_PDF,
    F_SAMPLE_NEG_PDF,
    F_SAMPLE_NEG_WEIGHT,
    F_SAMPLE_NAN_X,
    F_SAMPLE_LONG,       /* a direction of length 1.001 */
    F_SAMPLE_SLIGHTLY,   /* length 1 + 2e-5: within the 1e-4 allowed */
    F_SAMPLE_BELOW,      /* z < 0 on the hemisphere */
    F_SAMPLE_OUTSIDE,    /* square, disk, interval: a point outside */
    F_SAMPLE_FAILED_JUNK, /* a failed sample (pdf 0, weight 0) with a NaN point: ignored */
    F_SAMPLE_ALL_FAIL,   /* every sample fails */
    /* pdf() */
    F_PDF_RETURNS,
    F_PDF_NAN,
    F_PDF_INF,
    F_PDF_NEG,
    /* eval() */
    F_EVAL_RETURNS,
    F_EVAL_NAN,
    F_EVAL_INF,
    F_EVAL_NEG
};

typedef struct mock {
    int domain;
    int fault;
    size_t fault_at;
    size_t seen_sample, seen_pdf, seen_eval; /* points each callback has seen */
    /* what the callbacks were given, against the header's promises */
    size_t max_n;        /* the largest batch */
    size_t bad_u;        /* uniforms outside [0, 1) */
    size_t bad_x;        /* points given to pdf() or eval() outside the domain */
    size_t bad_wi;       /* wi not the normalised direction (BSDFs), not NULL (the others) */
    const double *want_wi;
} mock;

static int in_domain(int domain, const double *x)
{
    switch (domain) {
    case MCSTAT_CHECK_DOMAIN_SPHERE:
    case MCSTAT_CHECK_DOMAIN_HEMISPHERE:
        return fabs(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 1) <= 1e-4 &&
               (domain == MCSTAT_CHECK_DOMAIN_SPHERE || x[2] >= 0);
    case MCSTAT_CHECK_DOMAIN_SQUARE:
        return x[0] >= 0 && x[0] <= 1 && x[1] >= 0 && x[1] <= 1;
    case MCSTAT_CHECK_DOMAIN_DISK:
        return x[0] * x[0] + x[1] * x[1] <= 1 + 1e-12;
    default:
        return x[0] >= 0 && x[0] <= 1;
    }
}

static void observe(mock *m, const double *wi, size_t n, const double *x)
{
    if (n > m->max_n)
        m->max_n = n;
    if (m->want_wi ? !(wi && fabs(wi[0] - m->want_wi[0]) < 1e-12 && fabs(wi[1] - m->want_wi[1]) < 1e-12 &&
                       fabs(wi[2] - m->want_wi[2]) < 1e-12)
                   : wi != NULL)
        m->bad_wi++;
    int dims = mcstat_check_domain_dims(m->domain);
    for (size_t k = 0; x && k < n; k++)
        m->bad_x += !in_domain(m->domain, x + (size_t)dims * k);
}

/* The valid model's density at x (cosine-weighted on the upper hemisphere,
 * uniform on the others). */
static double density(int domain, const double *x)
{
    switch (domain) {
    case MCSTAT_CHECK_DOMAIN_SPHERE:
    case MCSTAT_CHECK_DOMAIN_HEMISPHERE:
        return x[2] > 0 ? x[2] / PI : 0.0;
    case MCSTAT_CHECK_DOMAIN_DISK:
        return 1.0 / PI;
    default:
        return 1.0;
    }
}

/* the integrand: albedo 0.5 on the directions, 0.5 elsewhere */
static double integrand(int domain, const double *x) { return 0.5 * density(domain, x); }

static int hit(mock *m, size_t seen, size_t k, int fault) { return m->fault == fault && seen + k == m->fault_at; }

static int mock_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                       double *pdf)
{
    mock *m = user;
    int dims = mcstat_check_domain_dims(m->domain);
    observe(m, wi, n, NULL);
    for (size_t k = 0; k < 2 * n; k++)
        m->bad_u += !(u[k] >= 0 && u[k] < 1);
    if (m->fault == F_SAMPLE_RETURNS && m->seen_sample <= m->fault_at && m->fault_at < m->seen_sample + n)
        return -1;
    for (size_t k = 0; k < n; k++) {
        const double *uk = u + 2 * k;
        double *xk = x + (size_t)dims * k;
        switch (m->domain) {
        case MCSTAT_CHECK_DOMAIN_SPHERE:
        case MCSTAT_CHECK_DOMAIN_HEMISPHERE: {
            double r = sqrt(uk[0]), phi = 2 * PI * uk[1];
            xk[0] = r * cos(phi), xk[1] = r * sin(phi), xk[2] = sqrt(fmax(0.0, 1 - uk[0]));
            break;
        }
        case MCSTAT_CHECK_DOMAIN_SQUARE:
            xk[0] = uk[0], xk[1] = uk[1];
            break;
        case MCSTAT_CHECK_DOMAIN_DISK: {
            double r = sqrt(uk[0]), phi = 2 * PI * uk[1];
            xk[0] = r * cos(phi), xk[1] = r * sin(phi);
            break;
        }
        default:
            xk[0] = uk[0];
        }
        pdf[k] = density(m->domain, xk);
        if (m->fault == F_SAMPLE_FAILED_JUNK)
            pdf[k] *= 0.9; /* one sample in ten fails, so the others have density 0.9 pdf */
        weight[k] = pdf[k] > 0 ? integrand(m->domain, xk) / pdf[k] : 0.0;
        size_t s = m->seen_sample;
        if (hit(m, s, k, F_SAMPLE_NAN_WEIGHT))
            weight[k] = NAN;
        if (hit(m, s, k, F_SAMPLE_INF_PDF))
            pdf[k] = INFINITY;
        if (hit(m, s, k, F_SAMPLE_NEG_PDF))
            pdf[k] = -pdf[k];
        if (hit(m, s, k, F_SAMPLE_NEG_WEIGHT))
            weight[k] = -weight[k];
        if (hit(m, s, k, F_SAMPLE_NAN_X))
            xk[0] = NAN;
        if (hit(m, s, k, F_SAMPLE_LONG) || hit(m, s, k, F_SAMPLE_SLIGHTLY)) {
            double c = m->fault == F_SAMPLE_LONG ? 1.001 : 1 + 2e-5;
            for (int j = 0; j < dims; j++)
                xk[j] *= c;
        }
        if (hit(m, s, k, F_SAMPLE_BELOW))
            xk[0] = 0.6, xk[1] = 0.0, xk[2] = -0.8;
        if (hit(m, s, k, F_SAMPLE_OUTSIDE)) {
            if (m->domain == MCSTAT_CHECK_DOMAIN_DISK)
                xk[0] = 0.8, xk[1] = 0.8;
            else
                xk[0] = m->domain == MCSTAT_CHECK_DOMAIN_SQUARE ? 1.25 : -0.25;
        }
        if (m->fault == F_SAMPLE_ALL_FAIL || (m->fault == F_SAMPLE_FAILED_JUNK && (s + k) % 10 == 3)) {
            pdf[k] = weight[k] = 0.0;
            if (m->fault == F_SAMPLE_FAILED_JUNK)
                for (int j = 0; j < dims; j++)
                    xk[j] = NAN;
        }
    }
    m->seen_sample += n;
    return 0;
}

static int mock_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    mock *m = user;
    int dims = mcstat_check_domain_dims(m->domain);
    observe(m, wi, n, x);
    if (m->fault == F_PDF_RETURNS && m->seen_pdf <= m->fault_at && m->fault_at < m->seen_pdf + n)
        return 3;
    for (size_t k = 0; k < n; k++) {
        out[k] = density(m->domain, x + (size_t)dims * k);
        if (m->fault == F_SAMPLE_FAILED_JUNK)
            out[k] *= 0.9; /* as sample() reports */
        if (hit(m, m->seen_pdf, k, F_PDF_NAN))
            out[k] = NAN;
        if (hit(m, m->seen_pdf, k, F_PDF_INF))
            out[k] = INFINITY;
        if (hit(m, m->seen_pdf, k, F_PDF_NEG))
            out[k] = -1.0;
    }
    m->seen_pdf += n;
    return 0;
}

static int mock_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    mock *m = user;
    int dims = mcstat_check_domain_dims(m->domain);
    observe(m, wi, n, x);
    if (m->fault == F_EVAL_RETURNS && m->seen_eval <= m->fault_at && m->fault_at < m->seen_eval + n)
        return 1;
    for (size_t k = 0; k < n; k++) {
        out[k] = integrand(m->domain, x + (size_t)dims * k);
        if (hit(m, m->seen_eval, k, F_EVAL_NAN))
            out[k] = NAN;
        if (hit(m, m->seen_eval, k, F_EVAL_INF))
            out[k] = INFINITY;
        if (hit(m, m->seen_eval, k, F_EVAL_NEG))
            out[k] = -1.0;
    }
    m->seen_eval += n;
    return 0;
}

static mcstat_check_model make_model(mock *m, int domain, int fault)
{
    memset(m, 0, sizeof *m);
    m->domain = domain;
    m->fault = fault;
    m->fault_at = 777;
    mcstat_check_model model;
    memset(&model, 0, sizeof model);
    model.domain = domain;
    model.n_uniforms = 2;
    model.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    model.sample_reports = 1;
    model.user = m;
    model.sample = mock_sample;
    model.pdf = mock_pdf;
    model.eval = mock_eval;
    return model;
}

static const double WI[3] = {0.3, -0.2, 0.9};
#define N 2000
#define SEED 20261203u
#define ALPHA 0.01

/* *out is written only on success (or its message on MCSTAT_ECALLBACK):
 * filled with a pattern before each failing call, and compared after. */
static mcstat_check_report sentinel;

static void fill(mcstat_check_report *r) { memset(r, 0xA5, sizeof *r); }

static int untouched(const mcstat_check_report *r) { return memcmp(r, &sentinel, sizeof *r) == 0; }

#define CHECK_EINVAL(call, what)                                                                  \
    do {                                                                                          \
        fill(&rep);                                                                               \
        int st_ = (call);                                                                         \
        CHECK_MSG(st_ == MCSTAT_EINVAL, "%s: status %d (%s), want MCSTAT_EINVAL", what, st_,      \
                  mcstat_strerror(st_));                                                          \
        CHECK_MSG(untouched(&rep), "%s: *out written on failure", what);                          \
        CHECK_MSG(mcstat_last_error()[0] != '\0', "%s: no reason (mcstat_last_error() is empty)", what); \
    } while (0)

/* ... and the reason names `word` (the argument, as a C caller spells it) */
#define CHECK_EINVAL_WHY(call, what, word)                                                        \
    do {                                                                                          \
        CHECK_EINVAL(call, what);                                                                 \
        CHECK_MSG(strstr(mcstat_last_error(), word) != NULL, "%s: reason '%s' does not name %s", what, \
                  mcstat_last_error(), word);                                                     \
    } while (0)

static void test_einval_arguments(void)
{
    mcstat_check_report rep;
    mock m;
    mcstat_check_model model = make_model(&m, MCSTAT_CHECK_DOMAIN_HEMISPHERE, F_NONE);

    /* the valid call passes, so that each case below differs in one thing */
    int st = mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep);
    CHECK_MSG(st == MCSTAT_OK, "valid model: %s (%s)", mcstat_strerror(st), rep.message);

    CHECK_EINVAL_WHY(mcstat_check_bsdf(NULL, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "NULL model", "model is NULL");
    CHECK_INT(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, NULL, NULL, 0, NULL), MCSTAT_EINVAL);
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, NULL, N, SEED, ALPHA, NULL, NULL, 0, &rep), "NULL wi", "wi is NULL");

    mcstat_check_model bad = model;
    bad.sample = NULL;
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "NULL sample", "model.sample");
    bad = model;
    bad.pdf = NULL;
    CHECK_EINVAL(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "NULL pdf");
    bad = model;
    bad.eval = NULL; /* a BSDF has an integrand */
    CHECK_EINVAL(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "NULL eval (BSDF)");
    CHECK_EINVAL_WHY(mcstat_check_emitter(&bad, N, SEED, ALPHA, NULL, NULL, 0, &rep), "NULL eval (emitter)", "model.eval");

    const int domains[] = {-1, 5, 1000};
    for (size_t i = 0; i < sizeof domains / sizeof domains[0]; i++) {
        bad = model;
        bad.domain = domains[i];
        CHECK_EINVAL(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "bad domain");
        CHECK_EINVAL(mcstat_check_warp(&bad, N, SEED, ALPHA, NULL, NULL, 0, &rep), "bad domain (warp)");
    }
    /* an emitter's points are directions */
    mock mw;
    mcstat_check_model square = make_model(&mw, MCSTAT_CHECK_DOMAIN_SQUARE, F_NONE);
    CHECK_EINVAL_WHY(mcstat_check_emitter(&square, N, SEED, ALPHA, NULL, NULL, 0, &rep), "emitter on the square", "model.domain");

    const int uniforms[] = {0, -1, MCSTAT_CHECK_MAX_UNIFORMS + 1};
    for (size_t i = 0; i < sizeof uniforms / sizeof uniforms[0]; i++) {
        bad = model;
        bad.n_uniforms = uniforms[i];
        CHECK_EINVAL_WHY(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "bad n_uniforms", "model.n_uniforms");
    }
    const int weights[] = {-1, 2};
    for (size_t i = 0; i < sizeof weights / sizeof weights[0]; i++) {
        bad = model;
        bad.weight = weights[i];
        CHECK_EINVAL_WHY(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "bad weight enum", "model.weight");
    }
    bad = model;
    bad.sample_reports = 0; /* a BSDF's sampler reports its weight and pdf */
    CHECK_EINVAL(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "sample_reports 0 (BSDF)");
    CHECK_EINVAL(mcstat_check_bsdf(&square, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "BSDF on the square");
    bad = model;
    bad.sample_reports = 2;
    CHECK_EINVAL(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, NULL, NULL, 0, &rep), "sample_reports 2");

    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, 999, SEED, ALPHA, NULL, NULL, 0, &rep), "n = 999", "n must be at least 1000, got 999");
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, 0, SEED, ALPHA, NULL, NULL, 0, &rep), "n = 0");
    CHECK_EINVAL(mcstat_check_warp(&square, 999, SEED, ALPHA, NULL, NULL, 0, &rep), "n = 999 (warp)");
    fill(&rep);
    st = mcstat_check_bsdf(&model, WI, ((size_t)1 << 48) + 1, SEED, ALPHA, NULL, NULL, 0, &rep);
    CHECK_MSG(st == MCSTAT_ETOOBIG, "n = 2^48 + 1: %s", mcstat_strerror(st));

    const double alphas[] = {0.0, 1.0, -0.5, 1.5, NAN, INFINITY};
    for (size_t i = 0; i < sizeof alphas / sizeof alphas[0]; i++)
        CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, alphas[i], NULL, NULL, 0, &rep), "bad alpha");

    const double wis[][3] = {{0, 0, 0}, {NAN, 0, 1}, {0, INFINITY, 1}, {0, 0, -INFINITY}};
    for (size_t i = 0; i < sizeof wis / sizeof wis[0]; i++)
        CHECK_EINVAL(mcstat_check_bsdf(&model, wis[i], N, SEED, ALPHA, NULL, NULL, 0, &rep), "bad wi");
}

static void test_einval_options_and_work(void)
{
    mcstat_check_report rep;
    mock m;
    mcstat_check_model model = make_model(&m, MCSTAT_CHECK_DOMAIN_HEMISPHERE, F_NONE);
    mcstat_check_options opt, o;
    CHECK_INT(mcstat_check_options_init(&opt), MCSTAT_OK);
    CHECK_INT(opt.size, sizeof opt);
    CHECK_INT(mcstat_check_options_init_size(NULL, sizeof opt), MCSTAT_EINVAL);
    CHECK_INT(mcstat_check_options_init_size(&o, 13), MCSTAT_EINVAL);

    /* sizes this library does not know */
    const uint32_t sizes[] = {0, 4, MCSTAT_CHECK_OPTIONS_SIZE_0_2 - 8, MCSTAT_CHECK_OPTIONS_SIZE_0_2 + 4,
                              (uint32_t)sizeof opt + 8, 0xFFFFFFFFu};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        o = opt;
        o.size = sizes[i];
        CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "unknown options size", "options.size");
    }
    /* every released size is read */
    o = opt;
    o.size = MCSTAT_CHECK_OPTIONS_SIZE_0_2;
    CHECK_INT(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), MCSTAT_OK);
    /* bad options */
    o = opt;
    o.batch = 0;
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "batch 0", "options.batch");
    o = opt;
    o.rtol = -1e-3;
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "rtol < 0");
    o = opt;
    o.rtol = NAN;
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "rtol NaN", "options.rtol");
    o = opt;
    o.cells = -1;
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "cells < 0", "options.cells");
    o = opt;
    o.routes = 1u << MCSTAT_CHECK_ROUTE_COUNT;
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "an unknown route bit");
    o = opt;
    o.routes = 0;
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "no route at all", "options.routes");
    o = opt;
    o.reserved[2] = 1.0;
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "options reserved not zero");
    o = opt;
    o.reserved_i = 1;
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "options reserved_i not zero");
    {
        mcstat_check_model bad = model;
        bad.reserved_rest[0] = 1.0;
        CHECK_EINVAL(mcstat_check_bsdf(&bad, WI, N, SEED, ALPHA, &opt, NULL, 0, &rep), "model reserved not zero");
    }
    o = opt;
    o.stochastic = 2;
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "stochastic 2");
    o = opt;
    o.reciprocal = -1;
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &o, NULL, 0, &rep), "reciprocal -1");

    /* scratch: the size mcstat_check_work_size gives works; one byte less
     * or a misaligned pointer does not */
    size_t bytes = 0;
    CHECK_INT(mcstat_check_work_size(NULL, N, &opt, &bytes), MCSTAT_EINVAL);
    CHECK_INT(mcstat_check_work_size(&model, N, &opt, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_check_work_size(&model, N, &opt, &bytes), MCSTAT_OK);
    CHECK(bytes > 0);
    unsigned char *buf = malloc(bytes + 32);
    CHECK(buf != NULL);
    if (!buf)
        return;
    unsigned char *aligned = buf + ((16 - (uintptr_t)buf % 16) % 16);
    int st = mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &opt, aligned, bytes, &rep);
    CHECK_MSG(st == MCSTAT_OK, "work of mcstat_check_work_size bytes: %s", mcstat_strerror(st));
    CHECK_MSG(mcstat_last_error()[0] == '\0', "a check that succeeded left the reason '%s'", mcstat_last_error());
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &opt, aligned, bytes - 1, &rep), "work too small", "work holds");
    CHECK_EINVAL_WHY(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &opt, aligned + 8, bytes, &rep), "work misaligned", "aligned");
    CHECK_EINVAL(mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, &opt, aligned, 0, &rep), "work of 0 bytes");
    free(buf);
}

/* One planted fault: the status, and for MCSTAT_ECALLBACK a message naming
 * the callback. */
static void expect_fault(int kind, int domain, int fault, const mcstat_check_options *opt, int want,
                         const char *callback, const char *what)
{
    mcstat_check_report rep;
    mock m;
    mcstat_check_model model = make_model(&m, domain, fault);
    if (kind == MCSTAT_CHECK_KIND_WARP)
        model.eval = NULL;
    fill(&rep);
    int st = kind == MCSTAT_CHECK_KIND_BSDF      ? mcstat_check_bsdf(&model, WI, N, SEED, ALPHA, opt, NULL, 0, &rep)
             : kind == MCSTAT_CHECK_KIND_EMITTER ? mcstat_check_emitter(&model, N, SEED, ALPHA, opt, NULL, 0, &rep)
                                                 : mcstat_check_warp(&model, N, SEED, ALPHA, opt, NULL, 0, &rep);
    CHECK_MSG(st == want, "%s: status %d (%s), want %d (%s); message \"%.200s\"", what, st, mcstat_strerror(st),
              want, mcstat_strerror(want), st == MCSTAT_ECALLBACK || st == MCSTAT_OK ? rep.message : "");
    if (want == MCSTAT_ECALLBACK && st == MCSTAT_ECALLBACK) {
        const char *nul = memchr(rep.message, '\0', sizeof rep.message);
        size_t len = nul ? (size_t)(nul - rep.message) : sizeof rep.message;
        CHECK_MSG(len > 0 && len < sizeof rep.message, "%s: message empty or not terminated", what);
        CHECK_MSG(len < sizeof rep.message && strstr(rep.message, callback) != NULL,
                  "%s: message \"%.200s\" does not name %s", what, rep.message, callback);
    }
    if (want == MCSTAT_OK && st == MCSTAT_OK)
        CHECK_MSG(rep.message[0] == '\0', "%s: message \"%.200s\" on success", what, rep.message);
}

static void test_callback_faults(void)
{
    const int B = MCSTAT_CHECK_KIND_BSDF, E = MCSTAT_CHECK_KIND_EMITTER, W = MCSTAT_CHECK_KIND_WARP;
    const int H = MCSTAT_CHECK_DOMAIN_HEMISPHERE, S = MCSTAT_CHECK_DOMAIN_SPHERE;
    const int EC = MCSTAT_ECALLBACK;

    expect_fault(B, H, F_SAMPLE_RETURNS, NULL, EC, "sample", "sample() returns -1");
    expect_fault(B, H, F_SAMPLE_NAN_WEIGHT, NULL, EC, "sample", "sample(): NaN weight");
    expect_fault(B, H, F_SAMPLE_INF_PDF, NULL, EC, "sample", "sample(): Inf pdf");
    expect_fault(B, H, F_SAMPLE_NEG_PDF, NULL, EC, "sample", "sample(): negative pdf");
    expect_fault(B, H, F_SAMPLE_NEG_WEIGHT, NULL, EC, "sample", "sample(): negative weight");
    expect_fault(B, H, F_SAMPLE_NAN_X, NULL, EC, "sample", "sample(): NaN point");
    expect_fault(B, H, F_SAMPLE_LONG, NULL, EC, "sample", "sample(): direction of length 1.001");
    expect_fault(B, S, F_SAMPLE_LONG, NULL, EC, "sample", "sample(): direction of length 1.001 (sphere)");
    expect_fault(E, S, F_SAMPLE_LONG, NULL, EC, "sample", "emitter sample(): direction of length 1.001");
    expect_fault(B, H, F_SAMPLE_SLIGHTLY, NULL, MCSTAT_OK, "", "sample(): direction of length 1 + 2e-5");
    expect_fault(B, H, F_SAMPLE_BELOW, NULL, EC, "sample", "sample(): z < 0 on the hemisphere");
    expect_fault(E, H, F_SAMPLE_BELOW, NULL, EC, "sample", "emitter sample(): z < 0 on the hemisphere");
    expect_fault(W, MCSTAT_CHECK_DOMAIN_SQUARE, F_SAMPLE_OUTSIDE, NULL, EC, "sample", "warp: x = 1.25 on the square");
    expect_fault(W, MCSTAT_CHECK_DOMAIN_DISK, F_SAMPLE_OUTSIDE, NULL, EC, "sample", "warp: (0.8, 0.8) on the disk");
    expect_fault(W, MCSTAT_CHECK_DOMAIN_INTERVAL, F_SAMPLE_OUTSIDE, NULL, EC, "sample", "warp: x = -0.25 on the interval");
    /* a failed sample's point is ignored, even NaN */
    expect_fault(B, H, F_SAMPLE_FAILED_JUNK, NULL, MCSTAT_OK, "", "failed samples with NaN points");
    /* not an error: a report whose mass route sees pdf() claim samples that never succeed */
    expect_fault(B, H, F_SAMPLE_ALL_FAIL, NULL, MCSTAT_OK, "", "every sample fails");

    expect_fault(B, H, F_PDF_RETURNS, NULL, EC, "pdf", "pdf() returns 3");
    expect_fault(B, H, F_PDF_NAN, NULL, EC, "pdf", "pdf(): NaN");
    expect_fault(B, H, F_PDF_INF, NULL, EC, "pdf", "pdf(): Inf");
    expect_fault(B, H, F_PDF_NEG, NULL, EC, "pdf", "pdf(): negative");
    expect_fault(W, MCSTAT_CHECK_DOMAIN_SQUARE, F_PDF_NAN, NULL, EC, "pdf", "warp pdf(): NaN");

    expect_fault(B, H, F_EVAL_RETURNS, NULL, EC, "eval", "eval() returns 1");
    expect_fault(B, H, F_EVAL_NAN, NULL, EC, "eval", "eval(): NaN");
    expect_fault(B, H, F_EVAL_INF, NULL, EC, "eval", "eval(): Inf");
    expect_fault(B, H, F_EVAL_NEG, NULL, EC, "eval", "eval(): negative");
    expect_fault(E, S, F_EVAL_NAN, NULL, EC, "eval", "emitter eval(): NaN");

    /* the same faults in a later call: batches of 100 points */
    mcstat_check_options opt;
    mcstat_check_options_init(&opt);
    opt.batch = 100;
    expect_fault(B, H, F_SAMPLE_RETURNS, &opt, EC, "sample", "sample() returns -1 (batch 100)");
    expect_fault(B, H, F_SAMPLE_NAN_WEIGHT, &opt, EC, "sample", "sample(): NaN weight (batch 100)");
    expect_fault(B, H, F_PDF_NEG, &opt, EC, "pdf", "pdf(): negative (batch 100)");
    expect_fault(B, H, F_EVAL_INF, &opt, EC, "eval", "eval(): Inf (batch 100)");
    expect_fault(B, H, F_NONE, &opt, MCSTAT_OK, "", "no fault (batch 100)");
}

/* What the callbacks are given: uniforms in [0, 1), at most `batch`
 * points a call, points of the domain, wi the normalised direction for a
 * BSDF (light from below too) and NULL otherwise. */
static void check_inputs(int kind, int domain, const double *wi, size_t batch)
{
    mcstat_check_report rep;
    mock m;
    mcstat_check_model model = make_model(&m, domain, F_NONE);
    mcstat_check_options opt;
    mcstat_check_options_init(&opt);
    opt.batch = batch;
    double unit[3];
    if (kind == MCSTAT_CHECK_KIND_BSDF) {
        double len = sqrt(wi[0] * wi[0] + wi[1] * wi[1] + wi[2] * wi[2]);
        for (int j = 0; j < 3; j++)
            unit[j] = wi[j] / len;
        m.want_wi = unit;
    }
    if (kind == MCSTAT_CHECK_KIND_WARP)
        model.eval = NULL;
    int st = kind == MCSTAT_CHECK_KIND_BSDF      ? mcstat_check_bsdf(&model, wi, N, SEED, ALPHA, &opt, NULL, 0, &rep)
             : kind == MCSTAT_CHECK_KIND_EMITTER ? mcstat_check_emitter(&model, N, SEED, ALPHA, &opt, NULL, 0, &rep)
                                                 : mcstat_check_warp(&model, N, SEED, ALPHA, &opt, NULL, 0, &rep);
    CHECK_MSG(st == MCSTAT_OK, "kind %d domain %d batch %zu: %s (%s)", kind, domain, batch, mcstat_strerror(st),
              rep.message);
    if (st != MCSTAT_OK)
        return;
    CHECK_MSG(m.max_n >= 1 && m.max_n <= batch, "kind %d domain %d: a call with %zu points, batch %zu", kind, domain,
              m.max_n, batch);
    CHECK_MSG(m.bad_u == 0, "kind %d domain %d: %zu uniforms outside [0, 1)", kind, domain, m.bad_u);
    CHECK_MSG(m.bad_x == 0, "kind %d domain %d: %zu points outside the domain given to pdf()/eval()", kind, domain,
              m.bad_x);
    CHECK_MSG(m.bad_wi == 0, "kind %d domain %d: %zu calls with the wrong wi", kind, domain, m.bad_wi);
    CHECK_INT(rep.kind, kind);
    CHECK_INT(rep.domain, domain);
    CHECK_INT(rep.n, N);
    if (kind == MCSTAT_CHECK_KIND_BSDF)
        CHECK(fabs(rep.wi[0] - unit[0]) < 1e-12 && fabs(rep.wi[1] - unit[1]) < 1e-12 &&
              fabs(rep.wi[2] - unit[2]) < 1e-12);
    else
        CHECK(isnan(rep.wi[0]) && isnan(rep.wi[1]) && isnan(rep.wi[2]));
}

static void test_callback_inputs(void)
{
    const double longer[3] = {0, 3, 4}, below[3] = {0.3, -0.2, -0.9};
    const size_t batches[] = {65536, 100, 64};
    for (size_t b = 0; b < sizeof batches / sizeof batches[0]; b++) {
        check_inputs(MCSTAT_CHECK_KIND_BSDF, MCSTAT_CHECK_DOMAIN_HEMISPHERE, WI, batches[b]);
        check_inputs(MCSTAT_CHECK_KIND_BSDF, MCSTAT_CHECK_DOMAIN_SPHERE, longer, batches[b]);
        check_inputs(MCSTAT_CHECK_KIND_BSDF, MCSTAT_CHECK_DOMAIN_SPHERE, below, batches[b]);
        check_inputs(MCSTAT_CHECK_KIND_EMITTER, MCSTAT_CHECK_DOMAIN_SPHERE, NULL, batches[b]);
        check_inputs(MCSTAT_CHECK_KIND_EMITTER, MCSTAT_CHECK_DOMAIN_HEMISPHERE, NULL, batches[b]);
        for (int d = MCSTAT_CHECK_DOMAIN_SQUARE; d <= MCSTAT_CHECK_DOMAIN_INTERVAL; d++)
            check_inputs(MCSTAT_CHECK_KIND_WARP, d, NULL, batches[b]);
    }
}

int main(void)
{
    fill(&sentinel);
    test_einval_arguments();
    test_einval_options_and_work();
    test_callback_faults();
    test_callback_inputs();
    printf("test_check_input: %d checks, %d failures\n", h_checks, h_failures);
    return h_failures != 0;
}
