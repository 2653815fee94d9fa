/*
 * test_pixels.c - Welch's test per pixel on seeds-major images
 * (mcstat_t_test_2_pixels, pixels.c): its fast t tail and quantile
 * (pixels_dist.c, t_quantiles.c) against
 * mpmath (tests/data/t_tail_ref.tsv, tools/refgen/make_t_tail_ref.py),
 * every pixel against mcstat_t_test_2 on its two samples, float32 and
 * double, channel weights, degenerate pixels, NaN omission, pixel ranges,
 * bad arguments.
 */
#include "harness.h"
#include "internal.h"
#include "ref_tsv.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* The accuracy claimed (mcstat.h, pixels.c): the tails where they are
 * normal doubles, relative; the quantile; the pixel p-value against the
 * single call (which is itself within its own bound of the truth). */
#define QUANT_TOL 2e-14

/* A tail p computed from an exponent of size |log p| carries that
 * exponent's rounding, so the bound grows with |log p|: 3e-14 near the
 * centre (where the upper tail is (1 - c)/2, c's error times up to 24),
 * 1e-13 at p = 1e-100, 3.1e-13 at the underflow; the general routine's
 * errors on the same points stay within it too (printed). */
static double p_tol(double p)
{
    return 3e-14 + 4e-16 * fabs(log(fmax(p, DBL_MIN)));
}
#define TAIL_TOL(p) p_tol(p)
#define P_TOL(p) p_tol(p)

static double urand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1p-53;
}

static double nrand(unsigned long long *s)
{
    double u = urand(s) + 0x1p-60, v = urand(s);
    return sqrt(-2.0 * log(u)) * cos(6.283185307179586 * v);
}

/* ---- the tail and quantile against mpmath -------------------------------- */

#define REF_MAX 4096

typedef struct {
    int tails, fast, quantiles;
    double max_fast, max_general, max_q;
    size_t n; /* the tail rows, for the block tails */
    double t[REF_MAX], df[REF_MAX], lo[REF_MAX], up[REF_MAX];
} ref_stats;

/* err of got against want, where want is a normal double; below the
 * normal range the value must only be tiny too */
static double tail_err(double got, double want)
{
    if (want < 1e-300)
        return got < 1e-290 ? 0.0 : INFINITY;
    return rel_err(got, want);
}

static void ref_row(char **f, int nf, void *ctx)
{
    ref_stats *r = ctx;
    if (nf < 5)
        return;
    double a = strtod(f[1], NULL), df = strtod(f[2], NULL), lo = strtod(f[3], NULL), up = strtod(f[4], NULL);
    if (!strcmp(f[0], "quantile")) {
        double q = NAN;
        CHECK_INT(mcstat__t_upper_quantile_fast(a, df, &q), MCSTAT_OK);
        double e = rel_err(q, lo);
        r->max_q = fmax(r->max_q, e);
        CHECK_REL(q, lo, QUANT_TOL, "upper quantile at p = %g, df = %.17g", a, df);
        r->quantiles++;
        return;
    }
    r->tails++;
    if (r->n < REF_MAX) {
        r->t[r->n] = a;
        r->df[r->n] = df;
        r->lo[r->n] = lo;
        r->up[r->n] = up;
        r->n++;
    }
    mcstat_tails g;
    CHECK_INT(mcstat__t_tails(a, df, &g), MCSTAT_OK);
    double m = fmin(lo, up);
    r->max_general = fmax(r->max_general, fmax(tail_err(g.p, lo), tail_err(g.q, up)) / p_tol(m));
    double u, o, lk;
    if (!mcstat__t_tail_fast(a, df, &u, &o, &lk))
        return;
    r->fast++;
    double gp = a > 0 ? o : u, gq = a > 0 ? u : o;
    double e = fmax(tail_err(gp, lo), tail_err(gq, up));
    r->max_fast = fmax(r->max_fast, e / p_tol(m));
    CHECK_MSG(e <= TAIL_TOL(m), "t = %.17g, df = %.17g: tails %.17g %.17g, want %.17g %.17g (err %.3g)", a, df, gp,
              gq, lo, up, e);
    /* log(|t| f(t)) is the general routine's */
    if (g.logk > -700.0)
        CHECK_MSG(fabs(lk - g.logk) <= 1e-13 * fmax(1.0, fabs(g.logk)), "logk %.17g vs %.17g", lk, g.logk);
}

/* The per-pixel path's block tails (vector exp and log1p, eight central
 * series at a time) on the same points, to the same bound. */
static void check_block_tails(const ref_stats *r)
{
    static double lo[REF_MAX], up[REF_MAX];
    static unsigned char done[REF_MAX];
    CHECK_INT(mcstat__t_tails_block(r->n, r->t, r->df, lo, up, done), MCSTAT_OK);
    size_t answered = 0;
    double worst = 0.0;
    for (size_t i = 0; i < r->n; i++) {
        if (!done[i])
            continue;
        answered++;
        double m = fmin(r->lo[i], r->up[i]), e = fmax(tail_err(lo[i], r->lo[i]), tail_err(up[i], r->up[i]));
        worst = fmax(worst, e / p_tol(m));
        CHECK_MSG(e <= TAIL_TOL(m), "block tails at t = %.17g, df = %.17g: %.17g %.17g, want %.17g %.17g (err %.3g)",
                  r->t[i], r->df[i], lo[i], up[i], r->lo[i], r->up[i], e);
    }
    /* all but the far tails where K underflows (the scalar path's logarithmic form) */
    CHECK_MSG(answered * 3 > r->n * 2, "block tails answered %zu of %zu points", answered, r->n);
    printf("block tails: %zu of %zu points, max rel err / bound %.3g\n", answered, r->n, worst);
}

static void test_reference(void)
{
    static ref_stats r;
    int n = tsv_read(MCSTAT_TEST_DATA_DIR "/t_tail_ref.tsv", ref_row, &r);
    CHECK_MSG(n > 2000, "t_tail_ref.tsv: %d rows", n);
    /* the fast tail covers most of the table (not only its easy corner) */
    CHECK_MSG(r.fast > r.tails * 3 / 4, "fast tail took %d of %d points", r.fast, r.tails);
    CHECK(r.quantiles >= 50);
    printf("t tails: fast %d of %d points, max rel err / bound %.3g (general routine %.3g); quantiles %d, max rel err %.3g\n",
           r.fast, r.tails, r.max_fast, r.max_general, r.quantiles, r.max_q);
    CHECK((size_t)r.tails <= REF_MAX);
    check_block_tails(&r);
}

/* The per-pixel critical values as mcstat_t_quantiles gives them (a table
 * in 1/df, interpolated, Halley where the interpolation is not good to
 * rounding) against mcstat_t_quantile over df in [1, 1000], at levels from
 * 0.025 to 1e-12 to QUANT_TOL; the table's density grows with log(1/p)
 * (1024 nodes at 0.025, 8192 at 1e-12, 65536 at 1e-100).  Below 1e-12 the
 * quantile is p^(-1/df)-like and carries the tail's relative error divided
 * by df: the two agree to mcstat.h's 3e-13 for quantiles (measured to 8e-14
 * at 1e-100, df near 1; test_distributions.py holds the table to mpmath). */
static void test_quantile_table(void)
{
    enum { N = 3000 };
    static double df[N], q[N];
    const double ps[] = {0.025, 0.005, 1e-4, 5e-7, 3e-9, 1e-12, 1e-20, 1e-50, 1e-100};
    unsigned long long s = 4242;
    for (int i = 0; i < N; i++)
        df[i] = i < N / 2 ? exp(log(1000.0) * i / (N / 2 - 1)) : exp(log(1000.0) * urand(&s));
    for (size_t k = 0; k < sizeof ps / sizeof ps[0]; k++) {
        CHECK_INT(mcstat_t_quantiles(ps[k], df, N, 1, q), MCSTAT_OK); /* N > 16: the table */
        double worst = 0.0, tol = ps[k] >= 1e-12 ? QUANT_TOL : 3e-13;
        for (int i = 0; i < N; i++) {
            double want;
            CHECK_INT(mcstat_t_quantile(ps[k], df[i], 1, &want), MCSTAT_OK);
            worst = fmax(worst, rel_err(q[i], want));
            CHECK_REL(q[i], want, tol, "p = %g, df = %.17g", ps[k], df[i]);
        }
        printf("critical values at p = %g: max rel err %.3g against mcstat_t_quantile\n", ps[k], worst);
    }
}

/* ---- pixels against the single call -------------------------------------- */

#define P 700     /* pixels: more than two blocks */
#define NX 8
#define NY 11
#define CH 3

static double xd[NX * P * CH], yd[NY * P * CH];
static float xf[NX * P * CH], yf[NY * P * CH];
static const double W[CH] = {0.2126, 0.7152, 0.0722};

/* Images whose pixels run through the cases: plain noise of varied scale and
 * offset, 1e8 + noise (ill-conditioned), equal means, large t (tiny
 * p-values), a NaN, an Inf, constant in one sample, constant in both. */
static void fill(void)
{
    unsigned long long s = 777;
    for (int i = 0; i < P; i++) {
        int kind = i % 10;
        double off = kind == 1 ? 1e8 : (double)(i % 7) - 3.0, sd = kind == 1 ? 1e-3 : 0.1 + (i % 5);
        double shift = kind == 2 ? 0.0 : kind == 3 ? 50.0 * sd : 0.3 * sd * nrand(&s);
        for (int c = 0; c < CH; c++) {
            for (int k = 0; k < NX; k++)
                xd[(size_t)k * P * CH + (size_t)i * CH + c] = off + shift + sd * nrand(&s);
            for (int k = 0; k < NY; k++)
                yd[(size_t)k * P * CH + (size_t)i * CH + c] = off + sd * (1.0 + 0.5 * (i % 3)) * nrand(&s);
        }
        if (kind == 8) /* constant in x only: still tested */
            for (int c = 0; c < CH; c++)
                for (int k = 0; k < NX; k++)
                    xd[(size_t)k * P * CH + (size_t)i * CH + c] = 2.5;
        if (kind == 9 && i % 20 == 9) /* constant in both */
            for (int c = 0; c < CH; c++) {
                for (int k = 0; k < NX; k++)
                    xd[(size_t)k * P * CH + (size_t)i * CH + c] = 4.0;
                for (int k = 0; k < NY; k++)
                    yd[(size_t)k * P * CH + (size_t)i * CH + c] = 4.0;
            }
    }
    xd[3 * P * CH + 4 * CH + 1] = NAN; /* pixel 4 */
    yd[5 * P * CH + 6 * CH + 0] = INFINITY; /* pixel 6 */
    xd[1 * P * CH + 14 * CH + 2] = NAN; /* pixel 14 */
    for (size_t k = 0; k < sizeof xd / sizeof xd[0]; k++)
        xf[k] = (float)xd[k];
    for (size_t k = 0; k < sizeof yd / sizeof yd[0]; k++)
        yf[k] = (float)yd[k];
}

typedef struct {
    double p[P], t[P], df[P], mx[P], my[P], lo[P], hi[P], se[P];
    int32_t st[P];
} outs;

static mcstat_pixels_out view(outs *o)
{
    mcstat_pixels_out v = MCSTAT_PIXELS_OUT_INIT;
    v.p_value = o->p;
    v.statistic = o->t;
    v.df = o->df;
    v.estimate = o->mx;
    v.estimate2 = o->my;
    v.conf_lo = o->lo;
    v.conf_hi = o->hi;
    v.status = o->st;
    v.std_error = o->se;
    return v;
}

/* pixel i's sample of one side, as the function forms it */
static size_t sample(int f32, const void *data, size_t n, size_t ch, const double *w, size_t i, unsigned flags,
                     double *out)
{
    size_t m = 0;
    for (size_t k = 0; k < n; k++) {
        size_t base = k * P * ch + i * ch;
        double v = 0.0;
        if (ch == 1 && !w)
            v = f32 ? (double)((const float *)data)[base] : ((const double *)data)[base];
        else
            for (size_t c = 0; c < ch; c++)
                v += w[c] * (f32 ? (double)((const float *)data)[base + c] : ((const double *)data)[base + c]);
        if ((flags & MCSTAT_ROWS_OMIT_NAN) && isnan(v))
            continue;
        out[m++] = v;
    }
    return m;
}

/* every pixel against mcstat_t_test_2 on its samples */
static void check_pixels(int f32, size_t ch, const double *w, int alternative, unsigned flags, double mu0)
{
    static outs o;
    mcstat_pixels_out v = view(&o);
    const void *x = f32 ? (const void *)xf : (const void *)xd, *y = f32 ? (const void *)yf : (const void *)yd;
    /* ch = 1 reads the first channel of an image whose pixels are CH apart:
     * the "pixel" stride is then CH, so run it as channels = CH, weights e0 */
    static const double e0[CH] = {1.0, 0.0, 0.0};
    size_t c = ch == 1 ? CH : ch;
    const double *ww = ch == 1 ? e0 : w;
    int st = f32 ? mcstat_t_test_2_pixels_f32(xf, NX, P * CH, yf, NY, P * CH, c, ww, 0, P, mu0, alternative, 0.05,
                                              flags, &v)
                 : mcstat_t_test_2_pixels(xd, NX, P * CH, yd, NY, P * CH, c, ww, 0, P, mu0, alternative, 0.05,
                                          flags, &v);
    int first = MCSTAT_OK, fails = 0;
    double maxe = 0.0;
    for (size_t i = 0; i < P; i++) {
        double sx[NX], sy[NY];
        size_t mx = sample(f32, x, NX, c, ww, i, flags, sx), my = sample(f32, y, NY, c, ww, i, flags, sy);
        mcstat_result r;
        int want = mcstat_t_test_2(sx, mx, sy, my, mu0, alternative, 0.05, &r);
        if (want == MCSTAT_OK && (flags & MCSTAT_ROWS_OMIT_NAN) == 0) {
            for (size_t k = 0; k < mx; k++)
                if (isnan(sx[k]))
                    want = MCSTAT_ENONFINITE;
        }
        CHECK_MSG(o.st[i] == want, "pixel %zu: status %d, want %d (f32 %d, ch %zu)", i, (int)o.st[i], want, f32,
                  ch);
        if (want != MCSTAT_OK) {
            if (first == MCSTAT_OK)
                first = want;
            fails++;
            CHECK(isnan(o.p[i]) && isnan(o.t[i]) && isnan(o.df[i]) && isnan(o.mx[i]) && isnan(o.my[i]) &&
                  isnan(o.lo[i]) && isnan(o.hi[i]) && isnan(o.se[i]));
            continue;
        }
        double e = rel_err(o.p[i], r.p_value);
        maxe = fmax(maxe, e);
        CHECK_REL(o.p[i], r.p_value, P_TOL(r.p_value), "pixel %zu p-value (f32 %d, ch %zu, alt %d)", i, f32, ch, alternative);
        /* the means to a few ulps of the data's scale (a mean near 0 has no
         * relative accuracy of its own), t to a few ulps of max(1, |t|) */
        double scale = 4.0 * r.std_error * sqrt((double)NY);
        CHECK_MSG(fabs(o.mx[i] - r.estimate[0]) <= 8 * DBL_EPSILON * (fabs(r.estimate[0]) + scale),
                  "pixel %zu mean x %.17g vs %.17g", i, o.mx[i], r.estimate[0]);
        CHECK_MSG(fabs(o.my[i] - r.estimate[1]) <= 8 * DBL_EPSILON * (fabs(r.estimate[1]) + scale),
                  "pixel %zu mean y %.17g vs %.17g", i, o.my[i], r.estimate[1]);
        CHECK_MSG(fabs(o.t[i] - r.statistic) <= 1e-14 * fmax(1.0, fabs(r.statistic)), "pixel %zu t %.17g vs %.17g",
                  i, o.t[i], r.statistic);
        CHECK_REL(o.df[i], r.df[0], 1e-14, "pixel %zu df", i);
        CHECK_REL(o.se[i], r.std_error, 1e-14, "pixel %zu standard error", i);
        if (flags & MCSTAT_ROWS_NO_INTERVALS) {
            CHECK(isnan(o.lo[i]) && isnan(o.hi[i]));
        } else {
            /* relative to the interval's half-width: the bounds of an
             * interval around 0 have no relative scale of their own */
            double hw = fabs(r.conf_int[1] - r.conf_int[0]);
            if (!isfinite(hw))
                hw = fabs(r.std_error);

            CHECK_MSG(r.conf_int[0] == o.lo[i] || fabs(o.lo[i] - r.conf_int[0]) <= 1e-14 * fmax(hw, fabs(r.conf_int[0])),
                      "pixel %zu lower bound %.17g vs %.17g", i, o.lo[i], r.conf_int[0]);
            CHECK_MSG(r.conf_int[1] == o.hi[i] || fabs(o.hi[i] - r.conf_int[1]) <= 1e-14 * fmax(hw, fabs(r.conf_int[1])),
                      "pixel %zu upper bound %.17g vs %.17g", i, o.hi[i], r.conf_int[1]);
        }
    }
    CHECK_INT(st, first);
    CHECK(fails > 0 && fails < P / 4);
    (void)maxe;
}

static void test_against_single_calls(void)
{
    const int alts[3] = {MCSTAT_TWO_SIDED, MCSTAT_LESS, MCSTAT_GREATER};
    for (int f32 = 0; f32 < 2; f32++)
        for (int a = 0; a < 3; a++) {
            check_pixels(f32, CH, W, alts[a], 0, 0.0);
            check_pixels(f32, 1, NULL, alts[a], MCSTAT_ROWS_NO_INTERVALS, 0.0);
        }
    check_pixels(0, CH, W, MCSTAT_TWO_SIDED, MCSTAT_ROWS_OMIT_NAN, 0.0);
    check_pixels(1, 1, NULL, MCSTAT_GREATER, MCSTAT_ROWS_OMIT_NAN, 0.25);
}

/* channels = 1, weights NULL on a one-channel image; a range split into
 * pieces gives the whole call's outputs, bit for bit */
static void test_ranges(void)
{
    static double x1[NX * P], y1[NY * P];
    static outs a, b;
    for (size_t k = 0; k < NX; k++)
        for (size_t i = 0; i < P; i++)
            x1[k * P + i] = xd[k * P * CH + i * CH + 1];
    for (size_t k = 0; k < NY; k++)
        for (size_t i = 0; i < P; i++)
            y1[k * P + i] = yd[k * P * CH + i * CH + 1];
    mcstat_pixels_out va = view(&a), vb = view(&b);
    int st = mcstat_t_test_2_pixels(x1, NX, P, y1, NY, P, 1, NULL, 0, P, 0.0, MCSTAT_TWO_SIDED, 0.01, 0, &va);
    CHECK_INT(st, MCSTAT_ENONFINITE); /* pixel 4's NaN comes first */
    const size_t cuts[] = {0, 1, 255, 256, 300, 513, P};
    for (int k = 0; k + 1 < 7; k++)
        mcstat_t_test_2_pixels(x1, NX, P, y1, NY, P, 1, NULL, cuts[k], cuts[k + 1], 0.0, MCSTAT_TWO_SIDED, 0.01, 0,
                               &vb);
    CHECK(!memcmp(&a, &b, sizeof a));
    /* NULL outputs are skipped; what is asked for is the same */
    static double p[P];
    mcstat_pixels_out vp = MCSTAT_PIXELS_OUT_INIT;
    vp.p_value = p;
    mcstat_t_test_2_pixels(x1, NX, P, y1, NY, P, 1, NULL, 0, P, 0.0, MCSTAT_TWO_SIDED, 0.01, 0, &vp);
    CHECK(!memcmp(p, a.p, sizeof p));
}

/* ill-conditioned data: 1e8 + noise of 1e-4, in double */
static void test_ill_conditioned(void)
{
    enum { N = 16, Q = 64 };
    static double x[N * Q], y[N * Q];
    unsigned long long s = 99;
    for (int k = 0; k < N * Q; k++) {
        x[k] = 1e8 + 1e-4 * nrand(&s);
        y[k] = 1e8 + 1e-4 * nrand(&s) + 2e-5;
    }
    double p[Q], t[Q], df[Q];
    mcstat_pixels_out o = MCSTAT_PIXELS_OUT_INIT;
    o.p_value = p;
    o.statistic = t;
    o.df = df;
    CHECK_INT(mcstat_t_test_2_pixels(x, N, Q, y, N, Q, 1, NULL, 0, Q, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_OK);
    for (int i = 0; i < Q; i++) {
        double sx[N], sy[N];
        for (int k = 0; k < N; k++) {
            sx[k] = x[k * Q + i];
            sy[k] = y[k * Q + i];
        }
        mcstat_result r;
        CHECK_INT(mcstat_t_test_2(sx, N, sy, N, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
        CHECK_REL(t[i], r.statistic, 1e-13, "pixel %d", i);
        CHECK_REL(df[i], r.df[0], 1e-13, "pixel %d", i);
        CHECK_REL(p[i], r.p_value, P_TOL(r.p_value), "pixel %d", i);
    }
}

static void test_bad_arguments(void)
{
    double x[4] = {1, 2, 3, 4}, y[4] = {2, 3, 4, 6}, p[2] = {-1.0, -1.0};
    float f[4] = {1, 2, 3, 4};
    int32_t st[2] = {-1, -1};
    mcstat_pixels_out o = MCSTAT_PIXELS_OUT_INIT;
    o.p_value = p;
    o.status = st;
    const double w2[2] = {0.5, 0.5}, wbad[2] = {0.5, NAN};
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, NULL),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(NULL, 2, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels_f32(f, 2, 2, NULL, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 0, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 2, NULL, 0, 1, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 2, wbad, 0, 1, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 2, 1, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 0, 2, NAN, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, 7, 0.05, 0, &o), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 1.0, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.0, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, NAN, 0, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, 8u, &o),
              MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pixels(x, 3, SIZE_MAX / 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, 0,
                                     &o),
              MCSTAT_ETOOBIG);
    CHECK_INT(mcstat_t_test_2_pixels(x, 2, 2, y, 2, 2, 2, w2, 0, SIZE_MAX / 2 + 1, 0.0, MCSTAT_TWO_SIDED, 0.05, 0,
                                     &o),
              MCSTAT_ETOOBIG); /* end * channels overflows */
    /* nothing was written */
    CHECK(p[0] == -1.0 && st[0] == -1);
    /* too few seeds: every pixel ETOOFEW, NaN outputs */
    CHECK_INT(mcstat_t_test_2_pixels(x, 1, 2, y, 2, 2, 1, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_ETOOFEW);
    CHECK(st[0] == MCSTAT_ETOOFEW && st[1] == MCSTAT_ETOOFEW && isnan(p[0]) && isnan(p[1]));
    /* an empty range is fine, even with NULL data */
    CHECK_INT(mcstat_t_test_2_pixels(NULL, 2, 2, NULL, 2, 2, 1, NULL, 3, 3, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, &o),
              MCSTAT_OK);
}

/* mcstat_t_quantiles against mcstat_t_quantile value by value: the same
 * numbers to QUANT_TOL, the same failures (NaN there, the first one's
 * status returned), on and off the table's range of levels and df. */
static void test_t_quantiles(void)
{
    enum { N = 3000 };
    static double df[N], x[N];
    unsigned long long s = 99;
    const double special[] = {NAN, -1.0, 0.0, 1e-3, 0.5, 1.0, 1000.0, 1001.0, 1e6, INFINITY, 2.5, 7.25};
    const size_t ns = sizeof special / sizeof special[0];
    for (size_t i = 0; i < N; i++)
        df[i] = i < ns ? special[i] : i % 3 ? 1.0 + 999.0 * urand(&s) : exp(-3.0 + 20.0 * urand(&s));
    const double ps[] = {0.0, 1e-300, 1e-101, 1e-12, 5e-7, 0.025, 0.25, 0.3, 0.5, 0.975, 1.0};
    for (size_t k = 0; k < sizeof ps / sizeof ps[0]; k++)
        for (int upper = 0; upper < 2; upper++) {
            int st = mcstat_t_quantiles(ps[k], df, N, upper, x), first = MCSTAT_OK;
            for (size_t i = 0; i < N; i++) {
                double want = NAN;
                int sw = mcstat_t_quantile(ps[k], df[i], upper, &want);
                if (sw) {
                    CHECK_MSG(isnan(x[i]), "p = %g, df = %g: %g where mcstat_t_quantile fails", ps[k], df[i], x[i]);
                    if (first == MCSTAT_OK)
                        first = sw;
                } else if (isinf(want) || want == 0.0) {
                    CHECK_MSG(x[i] == want, "p = %g, df = %g: %g, want %g", ps[k], df[i], x[i], want);
                } else {
                    CHECK_REL(x[i], want, QUANT_TOL, "p = %g, df = %.17g, upper %d", ps[k], df[i], upper);
                }
            }
            CHECK_INT(st, first);
        }
    CHECK_INT(mcstat_t_quantiles(NAN, df, N, 1, x), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_quantiles(1.5, df, N, 1, x), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_quantiles(0.05, NULL, 3, 1, x), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_quantiles(0.05, df, 3, 1, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_quantiles(0.05, NULL, 0, 1, NULL), MCSTAT_OK);
}

/* The per-block loops compiled for AVX2 and for the baseline give the same
 * outputs bit for bit (on a machine without AVX2 both runs take the
 * baseline), across the battery's kinds of pixels and both element types. */
static void test_simd_paths_agree(void)
{
    static outs a, b;
    for (int f32 = 0; f32 < 2; f32++)
        for (int ch = 1; ch <= CH; ch += CH - 1) {
            const double *w = ch == 1 ? NULL : W;
            mcstat_pixels_out va = view(&a), vb = view(&b);
            int sa = f32 ? mcstat_t_test_2_pixels_f32(xf, NX, P * CH, yf, NY, P * CH, (size_t)ch, w, 0, P, 0.0,
                                                      MCSTAT_TWO_SIDED, 0.05, 0, &va)
                         : mcstat_t_test_2_pixels(xd, NX, P * CH, yd, NY, P * CH, (size_t)ch, w, 0, P, 0.0,
                                                  MCSTAT_TWO_SIDED, 0.05, 0, &va);
            mcstat__pixels_baseline_only(1);
            int sb = f32 ? mcstat_t_test_2_pixels_f32(xf, NX, P * CH, yf, NY, P * CH, (size_t)ch, w, 0, P, 0.0,
                                                      MCSTAT_TWO_SIDED, 0.05, 0, &vb)
                         : mcstat_t_test_2_pixels(xd, NX, P * CH, yd, NY, P * CH, (size_t)ch, w, 0, P, 0.0,
                                                  MCSTAT_TWO_SIDED, 0.05, 0, &vb);
            mcstat__pixels_baseline_only(0);
            CHECK_INT(sa, sb);
            CHECK_MSG(memcmp(&a, &b, sizeof a) == 0, "AVX2 and baseline outputs differ (f32 %d, channels %d)", f32, ch);
        }
}

int main(void)
{
    test_reference();
    test_quantile_table();
    test_t_quantiles();
    fill();
    test_against_single_calls();
    test_simd_paths_agree();
    test_ranges();
    test_ill_conditioned();
    test_bad_arguments();
    return h_report("test_pixels");
}
