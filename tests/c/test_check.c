/*
 * test_check.c - the renderer checks (mcstat_check_*): the domains' maps
 * at their extremes, the cell cubature against closed-form integrals,
 * planted bugs of each class caught by the route meant for them, and the
 * battery's calibration: rejection rates of correct models over 500 fixed
 * seeds each, within binomial bounds of alpha.
 */
#include "check.h"
#include "harness.h"

#include <string.h>

#define PI 3.14159265358979323846

/* ---- the domains' maps -------------------------------------------------- */

static void test_domains(void)
{
    const double ss[] = {0.0, 1e-300, 1e-17, 1e-9, 0.25, 0.5, 0.75, 1 - 1e-9, 1.0};
    const double ts[] = {0.0, 1e-12, 0.3, 0.5, 0.999999};
    for (int kind = 0; kind <= MCSTAT_CHECK_DOMAIN_INTERVAL; kind++) {
        mcstat__domain d;
        CHECK(mcstat__domain_get(kind, &d) == MCSTAT_OK);
        for (size_t i = 0; i < sizeof ss / sizeof ss[0]; i++)
            for (size_t j = 0; j < sizeof ts / sizeof ts[0]; j++) {
                double x[3], s, t;
                mcstat__domain_point(&d, ss[i], ts[j], x);
                CHECK_MSG(mcstat__domain_coords(&d, x, &s, &t) == 0, "domain %d s %g t %g", kind, ss[i], ts[j]);
                /* s keeps its relative precision near the pole (1 - z computed
                 * from x^2 + y^2, never as a difference) */
                double es = ss[i] > 0 ? fabs(s - ss[i]) / ss[i] : fabs(s);
                CHECK_MSG(es < 1e-13 || (ss[i] > 1e-300 && ss[i] < 1e-30), "domain %d s %.17g -> %.17g", kind,
                          ss[i], s);
                int has_t = d.two_d && !(kind == MCSTAT_CHECK_DOMAIN_SPHERE && (ss[i] == 0 || ss[i] == 1)) &&
                            !(kind != MCSTAT_CHECK_DOMAIN_SQUARE && ss[i] < 1e-30);
                if (has_t)
                    CHECK_MSG(fabs(t - ts[j]) < 1e-12 || fabs(fabs(t - ts[j]) - 1) < 1e-12, "domain %d t %.17g -> %.17g",
                              kind, ts[j], t);
            }
    }
    /* points off the domain */
    mcstat__domain d;
    double s, t;
    mcstat__domain_get(MCSTAT_CHECK_DOMAIN_SPHERE, &d);
    double longer[3] = {0, 0, 1.001}, nan3[3] = {NAN, 0, 1}, below[3] = {0, 0.6, -0.8};
    CHECK(mcstat__domain_coords(&d, longer, &s, &t) == 1);
    CHECK(mcstat__domain_coords(&d, nan3, &s, &t) == 1);
    CHECK(mcstat__domain_coords(&d, below, &s, &t) == 0 && fabs(s - 0.9) < 1e-15);
    mcstat__domain_get(MCSTAT_CHECK_DOMAIN_HEMISPHERE, &d);
    CHECK(mcstat__domain_coords(&d, below, &s, &t) == 1);
    mcstat__domain_get(MCSTAT_CHECK_DOMAIN_SQUARE, &d);
    double out2[2] = {1.5, 0.5};
    CHECK(mcstat__domain_coords(&d, out2, &s, &t) == 1);
    CHECK(mcstat_check_domain_dims(7) == 0 && mcstat_check_domain_dims(MCSTAT_CHECK_DOMAIN_DISK) == 2);
    int k;
    CHECK(mcstat_check_domain_parse("hemisphere", &k) == MCSTAT_OK && k == MCSTAT_CHECK_DOMAIN_HEMISPHERE);
    CHECK(mcstat_check_domain_parse("cube", &k) == MCSTAT_EINVAL);
}

/* ---- Morton keys and the cubature against closed forms ----------------------- */

static void test_keys(void)
{
    mcstat__domain d;
    mcstat__domain_get(MCSTAT_CHECK_DOMAIN_SPHERE, &d);
    CHECK(mcstat__domain_key(&d, 0.0, 0.0) == 0);
    CHECK(mcstat__domain_key(&d, 1.0, 1.0) == UINT64_MAX);
    CHECK(mcstat__domain_key(&d, 0.5, 0.0) == (1ull << 63)); /* s is the more significant */
    CHECK(mcstat__domain_key(&d, 0.0, 0.5) == (1ull << 62));
    CHECK(mcstat__domain_key(&d, 0.75, 0.25) == ((1ull << 63) | (1ull << 61) | (1ull << 60)));
    mcstat__domain_get(MCSTAT_CHECK_DOMAIN_INTERVAL, &d);
    CHECK(mcstat__domain_key(&d, 0.5, 0.9) == (1ull << 63));
    CHECK(mcstat__domain_key(&d, 1.0, 0.0) == UINT64_MAX - 2047);
}

static int uniform_sphere(void *ctx, const double *x, size_t n, double *out)
{
    (void)ctx, (void)x;
    for (size_t k = 0; k < n; k++)
        out[k] = 1.0 / (4 * PI);
    return 0;
}

/* 3 z^2 / (2 pi) on the hemisphere: 3 (1 - s)^2 per unit of the square, a
 * polynomial the degree-7 rule integrates exactly */
static int z_squared(void *ctx, const double *x, size_t n, double *out)
{
    (void)ctx;
    for (size_t k = 0; k < n; k++)
        out[k] = 3 * x[3 * k + 2] * x[3 * k + 2] / (2 * PI);
    return 0;
}

static void test_cubature(void)
{
    enum { M = 4096, LEAF = 32 };
    static double st[2 * M], xbuf[3 * 4096], fbuf[4096];
    static mcstat__node nodes[2 * 400];
    static mcstat__cell cells[400];
    static mcstat__rect rects[20000];
    for (int dom = MCSTAT_CHECK_DOMAIN_SPHERE; dom <= MCSTAT_CHECK_DOMAIN_HEMISPHERE; dom++) {
        mcstat__domain d;
        mcstat__domain_get(dom, &d);
        uint64_t key = mcstat__stream_key(7, 1);
        for (int i = 0; i < 2 * M; i++) /* a pilot crowded towards s = 0, like a lobe */
            st[i] = (i & 1) ? mcstat__uniform(key, (uint64_t)i) : pow(mcstat__uniform(key, (uint64_t)i), 3.0);
        mcstat__tree tr = {nodes, cells, 0, 0, 800, 400, NULL, 0};
        CHECK(mcstat__tree_max_cells(M, LEAF) <= 400);
        mcstat__tree_build(&tr, &d, st, M, LEAF, dom == MCSTAT_CHECK_DOMAIN_SPHERE);
        CHECK_MSG(tr.n_cells >= M / LEAF / 2 && tr.n_cells <= 2 * M / LEAF, "%d cells", tr.n_cells);
        size_t used = 0;
        int st_ = mcstat__cells_integrate(&tr, &d, dom == MCSTAT_CHECK_DOMAIN_SPHERE ? uniform_sphere : z_squared, NULL,
                                          1e-6, rects, 20000, xbuf, fbuf, 4096, &used);
        CHECK(st_ == 0);
        double sum = 0, worst = 0;
        for (int c = 0; c < tr.n_cells; c++) {
            const mcstat__cell *cl = &tr.cells[c];
            double exact = dom == MCSTAT_CHECK_DOMAIN_SPHERE
                               ? (cl->s1 - cl->s0) * (cl->t1 - cl->t0)
                               /* a^3 - b^3 = (a - b)(a^2 + ab + b^2), a - b = s1 - s0 exactly */
                               : (cl->s1 - cl->s0) *
                                     ((1 - cl->s0) * (1 - cl->s0) + (1 - cl->s0) * (1 - cl->s1) +
                                      (1 - cl->s1) * (1 - cl->s1)) *
                                     (cl->t1 - cl->t0);
            worst = fmax(worst, rel_err(cl->prob, exact));
            sum += cl->prob;
        }
        CHECK_MSG(worst < 1e-13, "domain %d: worst relative error of a cell %.3g", dom, worst);
        CHECK_MSG(fabs(sum - 1) < 1e-13, "domain %d: sum %.17g", dom, sum);
        /* cells are numbered along the leaves and tile the square */
        double area = 0;
        for (int c = 0; c < tr.n_cells; c++)
            area += (tr.cells[c].s1 - tr.cells[c].s0) * (tr.cells[c].t1 - tr.cells[c].t0);
        CHECK(fabs(area - 1) < 1e-14);
        for (int i = 0; i < 1000; i++) {
            double s = mcstat__uniform(key, 100000 + (uint64_t)i), t = mcstat__uniform(key, 200000 + (uint64_t)i);
            const mcstat__cell *cl = &tr.cells[mcstat__tree_locate(&tr, s, t)];
            CHECK(s >= cl->s0 && s <= cl->s1 && t >= cl->t0 && t <= cl->t1);
        }
    }
}

/* ---- a lobe model: cos^e around the mirror direction of wi ------------------
 * eval = rho (e+1)/(2 pi) max(0, r.x)^e on the upper hemisphere, r the
 * mirror direction; the sampler draws the whole lobe and fails (pdf 0)
 * below the horizon, pdf() is the lobe's density on the upper hemisphere.
 * Planted bugs, about 10% each, one per class. */
enum bug { NONE, SAMPLER, PDF, EVAL, WEIGHT, NOISY, NOISY_BIASED };

typedef struct lobe {
    double e, rho, r[3];
    int bug;
} lobe;

static void frame(const double r[3], double t1[3], double t2[3])
{
    /* Duff et al.'s branchless orthonormal basis */
    double sign = copysign(1.0, r[2]), a = -1.0 / (sign + r[2]), b = r[0] * r[1] * a;
    t1[0] = 1.0 + sign * r[0] * r[0] * a;
    t1[1] = sign * b;
    t1[2] = -sign * r[0];
    t2[0] = b;
    t2[1] = sign + r[1] * r[1] * a;
    t2[2] = -r[1];
}

static double lobe_density(double e, const double r[3], const double *x)
{
    double c = r[0] * x[0] + r[1] * x[1] + r[2] * x[2];
    return x[2] > 0 && c > 0 ? (e + 1) / (2 * PI) * pow(c, e) : 0.0;
}

static int lobe_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    const lobe *L = user;
    (void)wi;
    for (size_t k = 0; k < n; k++)
        out[k] = lobe_density(L->bug == PDF ? L->e * 1.1 : L->e, L->r, x + 3 * k);
    return 0;
}

static int lobe_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    const lobe *L = user;
    (void)wi;
    for (size_t k = 0; k < n; k++) {
        out[k] = L->rho * lobe_density(L->e, L->r, x + 3 * k);
        if (L->bug == EVAL && x[3 * k] > 0)
            out[k] *= 1.1;
    }
    return 0;
}

static int lobe_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                       double *pdf)
{
    const lobe *L = user;
    (void)wi;
    double t1[3], t2[3];
    frame(L->r, t1, t2);
    double e = L->bug == SAMPLER ? L->e / 1.1 : L->e;
    for (size_t k = 0; k < n; k++) {
        double c = pow(u[3 * k], 1.0 / (e + 1)), sn = sqrt(fmax(0.0, 1 - c * c)), phi = 2 * PI * u[3 * k + 1];
        double *w = x + 3 * k;
        for (int i = 0; i < 3; i++)
            w[i] = c * L->r[i] + sn * (cos(phi) * t1[i] + sin(phi) * t2[i]);
        double p = lobe_density(L->e, L->r, w); /* what the sampler claims: the correct lobe */
        if (p == 0.0) {
            weight[k] = pdf[k] = 0.0; /* below the horizon: failed */
            continue;
        }
        pdf[k] = p;
        weight[k] = L->rho; /* eval / pdf */
        if (L->bug == WEIGHT)
            weight[k] *= 1.1;
        if (L->bug == NOISY || L->bug == NOISY_BIASED) /* a stochastic weight: mean rho */
            weight[k] = L->rho * 2.0 * u[3 * k + 2] * (L->bug == NOISY_BIASED ? 1.05 : 1.0);
    }
    return 0;
}

static lobe make_lobe(double e, const double wi[3], int bug)
{
    lobe L = {e, 0.8, {-wi[0], -wi[1], wi[2]}, bug};
    double len = sqrt(L.r[0] * L.r[0] + L.r[1] * L.r[1] + L.r[2] * L.r[2]);
    for (int i = 0; i < 3; i++)
        L.r[i] /= len;
    return L;
}

static mcstat_check_model lobe_model(lobe *L)
{
    mcstat_check_model m;
    memset(&m, 0, sizeof m);
    m.domain = MCSTAT_CHECK_DOMAIN_SPHERE;
    m.n_uniforms = 3;
    m.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    m.sample_reports = 1;
    m.user = L;
    m.sample = lobe_sample;
    m.pdf = lobe_pdf;
    m.eval = lobe_eval;
    return m;
}

/* On the square: 1/BAND on the strip s < BAND, 0 elsewhere.  The strip
 * lies in the margin the rule's points never reach (beyond 0.949 of the
 * half-width): all 17 of them see 0. */
#define BAND 0.02
static int edge_strip(void *ctx, const double *x, size_t n, double *out)
{
    (void)ctx;
    for (size_t k = 0; k < n; k++)
        out[k] = x[2 * k] < BAND ? 1.0 / BAND : 0.0;
    return 0;
}

static void test_cubature_edge(void)
{
    static double xbuf[2 * 4096], fbuf[4096];
    static mcstat__node nodes[4];
    static mcstat__cell cells[2];
    static mcstat__rect rects[2000];
    double st[2] = {0.01, 0.5}; /* one pilot point: one cell, the square */
    mcstat__domain d;
    mcstat__domain_get(MCSTAT_CHECK_DOMAIN_SQUARE, &d);
    mcstat__tree tr = {nodes, cells, 0, 0, 4, 2, NULL, 0};
    mcstat__tree_build(&tr, &d, st, 1, 32, 0);
    CHECK(tr.n_cells == 1);
    tr.n_points = 0; /* the rule and its probes alone, no pilot to guide them */
    size_t used = 0;
    CHECK(mcstat__cells_integrate(&tr, &d, edge_strip, NULL, 1e-4, rects, 2000, xbuf, fbuf, 4096, &used) == 0);
    const mcstat__cell *c = &tr.cells[0];
    /* the edge is seen, resolved to tolerance, and the error bounds the error */
    CHECK_MSG(fabs(c->prob - 1.0) <= c->err, "integral %.17g, error %.3g", c->prob, c->err);
    CHECK_MSG(c->err < 1e-3, "error %.3g after %zu rectangles", c->err, used);
    /* with too few rectangles to resolve it, the error is honest, not 0 */
    CHECK(mcstat__cells_integrate(&tr, &d, edge_strip, NULL, 1e-4, rects, 3, xbuf, fbuf, 4096, &used) == 0);
    CHECK(used == 3);
    CHECK_MSG(fabs(c->prob - 1.0) <= c->err, "3 rectangles: integral %.17g, error %.3g", c->prob, c->err);
}

static void test_lobe_bugs(void)
{
    const double wi[3] = {0.5, 0.1, 0.86};
    struct {
        int bug;
        int route; /* the route that must catch it (-1: none may) */
        int stochastic;
    } cases[] = {
        {NONE, -1, 0},
        {SAMPLER, MCSTAT_CHECK_ROUTE_CELLS, 0},
        {PDF, MCSTAT_CHECK_ROUTE_PDF_VALUE, 0},
        {EVAL, MCSTAT_CHECK_ROUTE_WEIGHT, 0},
        {WEIGHT, MCSTAT_CHECK_ROUTE_WEIGHT, 0},
        {NOISY, -1, 1},
        {NOISY_BIASED, MCSTAT_CHECK_ROUTE_INTEGRALS, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        lobe L = make_lobe(40.0, wi, cases[i].bug);
        mcstat_check_model m = lobe_model(&L);
        mcstat_check_options o;
        mcstat_check_options_init(&o);
        o.stochastic = cases[i].stochastic;
        mcstat_check_report r;
        /* a 5% bias of a noisy weight needs the full size */
        size_t n = cases[i].stochastic ? 100000 : h_scaled(100000, 20000);
        int st = mcstat_check_bsdf(&m, wi, n, 1, 0.01, &o, NULL, 0, &r);
        CHECK_MSG(st == MCSTAT_OK, "bug %d: status %d %s", cases[i].bug, st, r.message);
        if (st)
            continue;
        if (cases[i].route < 0) {
            CHECK_MSG(!r.reject, "bug %d rejected (p %g)", cases[i].bug, r.p_value);
        } else {
            CHECK_MSG(r.reject && r.route[cases[i].route].reject, "bug %d not caught by route %s", cases[i].bug,
                      mcstat_check_route_name(cases[i].route));
        }
        if (!!r.reject != (cases[i].route >= 0) || getenv("MCSTAT_TEST_VERBOSE")) {
            char text[4096];
            mcstat_check_format(&r, text, sizeof text, NULL);
            fprintf(stderr, "bug %d:%s", cases[i].bug, text);
        }
    }
}

/* A lobe around a grazing mirror direction loses samples below the horizon:
 * pdf() integrates to the probability of success, and the mass route
 * agrees; the cubature's error estimate bounds its actual error. */
static void test_lobe_mass(void)
{
    const double wi[3] = {0.9, 0.1, 0.42};
    lobe L = make_lobe(10.0, wi, NONE);
    mcstat_check_model m = lobe_model(&L);
    mcstat_check_report r;
    int st = mcstat_check_bsdf(&m, wi, 100000, 5, 0.01, NULL, NULL, 0, &r);
    CHECK_MSG(st == MCSTAT_OK, "status %d %s", st, r.message);
    if (st)
        return;
    double share = 1.0 - (double)r.n_failed / 1e5;
    CHECK(r.n_failed > 1000);
    CHECK_MSG(fabs(r.mass - share) < 4 * sqrt(r.mass * (1 - r.mass) / 1e5) + r.mass_error, "mass %.9g, success share %.9g",
              r.mass, share);
    CHECK_MSG(r.mass_error < 1e-3, "cubature error %g", r.mass_error);
    CHECK(!r.reject);
}

/* ---- warps -------------------------------------------------------------------- */

/* x = u^2 on [0, 1]: pdf 1/(2 sqrt x), singular at 0; the bug forgets the 2 */
static int warp_sq_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                          double *pdf)
{
    (void)user, (void)wi, (void)weight, (void)pdf;
    for (size_t k = 0; k < n; k++)
        x[k] = u[k] * u[k];
    return 0;
}
static int warp_sq_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    int bug = *(const int *)user;
    (void)wi;
    for (size_t k = 0; k < n; k++)
        out[k] = x[k] > 0 ? (bug ? 0.55 : 0.5) / sqrt(x[k]) : 0.0;
    return 0;
}
/* the square to the disk by polar coordinates r = sqrt(u1); the bug uses r = u1 */
static int warp_disk_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                            double *pdf)
{
    int bug = *(const int *)user;
    (void)wi, (void)weight, (void)pdf;
    for (size_t k = 0; k < n; k++) {
        double r = bug ? pow(u[2 * k], 0.45) : sqrt(u[2 * k]), phi = 2 * PI * u[2 * k + 1];
        x[2 * k] = r * cos(phi);
        x[2 * k + 1] = r * sin(phi);
    }
    return 0;
}
static int warp_disk_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++)
        out[k] = x[2 * k] * x[2 * k] + x[2 * k + 1] * x[2 * k + 1] <= 1.0 ? 1.0 / PI : 0.0;
    return 0;
}

static mcstat_check_model warp_model(int domain, int nu, mcstat_check_sample_fn s, mcstat_check_density_fn p,
                                     int *bug)
{
    mcstat_check_model m;
    memset(&m, 0, sizeof m);
    m.domain = domain;
    m.n_uniforms = nu;
    m.sample = s;
    m.pdf = p;
    m.user = bug;
    return m;
}

static void test_warps(void)
{
    for (int bug = 0; bug <= 1; bug++) {
        mcstat_check_report r;
        mcstat_check_model m = warp_model(MCSTAT_CHECK_DOMAIN_INTERVAL, 1, warp_sq_sample, warp_sq_pdf, &bug);
        int st = mcstat_check_warp(&m, 20000, 3, 0.01, NULL, NULL, 0, &r);
        CHECK_MSG(st == MCSTAT_OK && r.reject == bug, "interval warp bug %d: status %d reject %d", bug, st, r.reject);
        if (st == MCSTAT_OK && !bug)
            CHECK_MSG(fabs(r.mass - 1.0) <= r.mass_error && r.mass_error < 1e-3,
                      "singular pdf integrates to %.12g, error estimate %g", r.mass, r.mass_error);
        if (st == MCSTAT_OK && bug)
            CHECK(r.route[MCSTAT_CHECK_ROUTE_MASS].reject);
        m = warp_model(MCSTAT_CHECK_DOMAIN_DISK, 2, warp_disk_sample, warp_disk_pdf, &bug);
        st = mcstat_check_warp(&m, 20000, 3, 0.01, NULL, NULL, 0, &r);
        CHECK_MSG(st == MCSTAT_OK && r.reject == bug, "disk warp bug %d: status %d reject %d", bug, st, r.reject);
        if (st == MCSTAT_OK && bug)
            CHECK(r.route[MCSTAT_CHECK_ROUTE_CELLS].reject);
        if (st == MCSTAT_OK && !bug)
            CHECK_MSG(fabs(r.mass - 1.0) < 1e-9, "disk mass %.15g", r.mass);
    }
}

/* ---- calibration ---------------------------------------------------------------
 * A correct model must be rejected at rate at most alpha: 500 seeds at
 * alpha = 0.05, expected 25 rejections; the battery meta-test (binomial,
 * one-sided) must not reject at 0.001: at most 41 rejections (R:
 * binom.test(41, 500, 0.05, "greater")$p.value = 0.0015, 42: 0.00086). */
static void calibrate(const char *what, mcstat_check_model *m, const double *wi, int kind, size_t n)
{
    int rejections = 0, per_route[MCSTAT_CHECK_ROUTE_COUNT] = {0};
    uint64_t runs = h_scaled(500, 25); /* fewer under the sanitizers: the meta-test stays valid */
    for (uint64_t seed = 1000; seed < 1000 + runs; seed++) {
        mcstat_check_report r;
        int st = kind == MCSTAT_CHECK_KIND_BSDF ? mcstat_check_bsdf(m, wi, n, seed, 0.05, NULL, NULL, 0, &r)
                                                : mcstat_check_warp(m, n, seed, 0.05, NULL, NULL, 0, &r);
        if (st) {
            CHECK_MSG(0, "%s seed %llu: status %d %s", what, (unsigned long long)seed, st, r.message);
            return;
        }
        rejections += r.reject;
        for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
            per_route[i] += r.route[i].reject;
    }
    fprintf(stderr, "calibration %s: %d of %llu rejected at alpha 0.05 (routes:", what, rejections,
            (unsigned long long)runs);
    for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
        fprintf(stderr, " %s %d", mcstat_check_route_name(i), per_route[i]);
    fprintf(stderr, ")\n");
    /* the meta-test: too many rejections for the level? (one-sided: a
     * conservative battery is allowed) */
    mcstat_result meta;
    CHECK(mcstat_battery_test((uint64_t)rejections, runs, 0.05, MCSTAT_GREATER, 0.001, &meta) == MCSTAT_OK);
    CHECK_MSG(!meta.reject, "%s: %d rejections of %llu (p %g)", what, rejections, (unsigned long long)runs,
              meta.p_value);
}

static void test_calibration(void)
{
    const double wi[3] = {0.3, -0.2, 0.93};
    lobe L = make_lobe(10.0, wi, NONE);
    mcstat_check_model m = lobe_model(&L);
    calibrate("lobe e=10", &m, wi, MCSTAT_CHECK_KIND_BSDF, 4000);
    int bug = 0;
    m = warp_model(MCSTAT_CHECK_DOMAIN_INTERVAL, 1, warp_sq_sample, warp_sq_pdf, &bug);
    calibrate("interval u^2", &m, NULL, MCSTAT_CHECK_KIND_WARP, 4000);
    m = warp_model(MCSTAT_CHECK_DOMAIN_DISK, 2, warp_disk_sample, warp_disk_pdf, &bug);
    calibrate("disk", &m, NULL, MCSTAT_CHECK_KIND_WARP, 4000);
}

int main(void)
{
    test_domains();
    test_keys();
    test_cubature();
    test_cubature_edge();
    test_lobe_bugs();
    test_lobe_mass();
    test_warps();
    test_calibration();
    return h_report("test_check");
}
