/*
 * pixels.c - Welch's test per pixel on image stacks of any layout (float32
 * or double, optionally a weighted sum of channels), with a Student t tail
 * specialised to the t distribution; pixels_test.c checks the arguments,
 * splits the pixels over threads and each thread runs mcstat__pixels_welch
 * on the chunks it takes.
 *
 * The row-wise tests (rows.c) run every pixel through the single call:
 * an accumulator per sample, the general incomplete beta, a full
 * mcstat_result.  Here, for a block of pixels that fits in L1:
 *   - the moments are two passes over the seeds with the pixels inner
 *     (contiguous, vectorised): the sum, then the deviations d from its
 *     mean, M2 = sum d^2 - (sum d)^2 / n (the corrected two-pass
 *     algorithm) and the mean as the double-double mean + sum d / n, so
 *     1e8 + small noise keeps its digits as in moments.c;
 *   - t, df, the standard errors and the t prefactors in branch-free loops
 *     over the block;
 *   - the tails (mcstat__t_tail_core's series, specialised to b = 1/2: the
 *     cost does not depend on the variety of df) for the whole block: exp
 *     and log1p four pixels at a time (vmath.h), the central series eight
 *     pixels a step (pixels_dist.c);
 *   - the critical values from a per-call table of t quantiles in 1/df
 *     (t_quantiles.c: solved lazily, the same whichever pixels ask),
 *     interpolated, and the intervals' bounds, again for the whole block;
 *     where the interpolation is not good to rounding, Halley's method in
 *     log t on the fast tail finishes that pixel's.
 * The block loops are compiled for SSE2 and for AVX2 (chosen at run time,
 * the same results bit for bit).
 * A pixel outside the fast path's proven ground (a NaN or Inf, extreme
 * magnitudes, too few seeds, nearly constant samples, df or t outside the
 * fast tail's range) is computed by the single call's own code, so its
 * status and outputs are the row path's.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "pixels.h"
#include "vmath.h"

#include <float.h>
#include <pthread.h>
#include <stdlib.h>

#define GATHER 256        /* the slow path's bounce buffer (2 KiB of stack) */
/* (PIX_BLOCK and GATHER are also pixels_test.c's) */
#define FAST_LO 0x1p-200  /* moments.c's unscaled range */
#define FAST_HI 0x1p+200

/* ---- one pixel's outputs --------------------------------------------------- */

typedef struct {
    mcstat__qt_table tab; /* the critical values (t_quantiles.c) */
    const mcstat_pixels_out *out;
    int alternative, intervals;
    double mu0, alpha;
    mcstat_qcache qc; /* the slow path's */
    uint64_t nx, ny;  /* the sample sizes of the fast path */
    int first;        /* status of the first failing pixel */
    size_t first_i;   /* and its index */
    int render;       /* MCSTAT_PIXELS_RENDER */
    double eps;       /* and its resolution */
} pix_ctx;

static void put(const pix_ctx *c, size_t i, int st, double p, double t, double df, double se, double mx,
                double my, double lo, double hi, double c0, double c1, int dec, uint64_t nx, uint64_t ny)
{
    const mcstat_pixels_out *o = c->out;
    if (o->df2)
        o->df2[i] = NAN;
    if (o->critical_lo)
        o->critical_lo[i] = c0;
    if (o->critical_hi)
        o->critical_hi[i] = c1;
    if (o->decision)
        o->decision[i] = (int8_t)dec;
    if (o->n_x)
        o->n_x[i] = nx;
    if (o->n_y)
        o->n_y[i] = ny;
    if (o->std_error)
        o->std_error[i] = se;
    if (o->p_value)
        o->p_value[i] = p;
    if (o->statistic)
        o->statistic[i] = t;
    if (o->df)
        o->df[i] = df;
    if (o->estimate)
        o->estimate[i] = mx;
    if (o->estimate2)
        o->estimate2[i] = my;
    if (o->conf_lo)
        o->conf_lo[i] = lo;
    if (o->conf_hi)
        o->conf_hi[i] = hi;
    if (o->status)
        o->status[i] = st;
}

static void fail(pix_ctx *c, size_t i, int st)
{
    put(c, i, st, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, 0, 0, 0);
    if (c->first == MCSTAT_OK) {
        c->first = st;
        c->first_i = i;
    }
}

/* ---- the slow path: the single call's code ---------------------------------- */

typedef struct {
    const float *f;
    const double *d;
    size_t stride, ps, channels; /* value and pixel strides, elements per value */
    const double *w;
} plane;

static double value(const plane *pl, size_t s, size_t i)
{
    size_t k = s * pl->stride + i * pl->ps;
    if (pl->channels == 1 && !pl->w)
        return pl->f ? (double)pl->f[k] : pl->d[k];
    double v = 0.0;
    for (size_t c = 0; c < pl->channels; c++)
        v += pl->w[c] * (pl->f ? (double)pl->f[k + c] : pl->d[k + c]);
    return v;
}

/* One pixel's sample into m, GATHER values at a time. */
/* *nonzero: the values neither 0 nor NaN. */
static int pixel_moments(const plane *pl, size_t n, size_t i, unsigned flags, mcstat_moments *m, uint64_t *nonzero)
{
    double buf[GATHER];
    mcstat_moments_init(m);
    *nonzero = 0;
    for (size_t s0 = 0; s0 < n; s0 += GATHER) {
        size_t k = n - s0 < GATHER ? n - s0 : GATHER;
        for (size_t j = 0; j < k; j++) {
            buf[j] = value(pl, s0 + j, i);
            *nonzero += buf[j] != 0.0 && !isnan(buf[j]);
        }
        int st = (flags & MCSTAT_ROWS_OMIT_NAN) ? mcstat_moments_add_array_omit_nan(m, buf, k, NULL)
                                                : mcstat_moments_add_array(m, buf, k);
        if (st)
            return st;
    }
    return MCSTAT_OK;
}

static void slow_pixel(pix_ctx *c, const plane *px, size_t nx, const plane *py, size_t ny, size_t i,
                       unsigned flags)
{
    mcstat_moments mx, my;
    mcstat_result r;
    mcstat__render_guard rg = {c->eps, 0, 0};
    int st = pixel_moments(px, nx, i, flags, &mx, &rg.hx);
    if (!st)
        st = pixel_moments(py, ny, i, flags, &my, &rg.hy);
    if (!st && c->render)
        st = mcstat__t_test_2_render(&mx, &my, &rg, c->mu0, c->alternative, c->alpha, c->intervals ? &c->qc : NULL,
                                     &r);
    else if (!st)
        st = mcstat__t_test_2(&mx, &my, c->mu0, c->alternative, c->alpha, c->intervals ? &c->qc : NULL, &r);
    if (st) {
        fail(c, i, st);
        return;
    }
    put(c, i, MCSTAT_OK, r.p_value, r.statistic, r.df[0], r.std_error, r.estimate[0], r.estimate[1], r.conf_int[0],
        r.conf_int[1], r.critical[0], r.critical[1], r.decision, r.n[0], r.n[1]);
}

/* ---- the fast path ------------------------------------------------------------ */

/* fmin/fmax are library calls without -ffinite-math-only; nothing here is NaN */
static inline double dmin(double u, double v) { return u < v ? u : v; }
static inline double dmax(double u, double v) { return u > v ? u : v; }

/* x / d, by a multiplication where d is a power of two (x * (1/d) is then
 * x / d exactly): the divider bounds the block loops, and seed counts are
 * often powers of two.  inv = 1/d; pow2 is the same for a whole loop,
 * which the compiler then unswitches. */
static PIX_INLINE double div_by(double x, double d, double inv, int pow2)
{
    return pow2 ? x * inv : x / d;
}

static int pow2_count(size_t n)
{
    return n > 0 && (n & (n - 1)) == 0;
}

/* A block's statistics, computed pixel by pixel in straight-line loops the
 * compiler vectorises (no branches, no calls, no floating-point operation
 * done conditionally, which -ftrapping-math forbids it to speculate): the
 * moments in; t, df, the standard error, the difference of the means, the
 * t prefactor and each pixel's fate out. */
enum { PIX_FAST, PIX_SLOW, PIX_DEGENERATE };

typedef struct {
    double t[PIX_BLOCK], df[PIX_BLOCK], se[PIX_BLOCK], dhi[PIX_BLOCK], dlo[PIX_BLOCK];
    double sdmax[PIX_BLOCK], lim[PIX_BLOCK]; /* with the render guards; squared without */
    double pa[PIX_BLOCK], pf[PIX_BLOCK], plc[PIX_BLOCK]; /* t_prefactor's a, f, lc */
    double lower[PIX_BLOCK], upper[PIX_BLOCK]; /* the tails, where tail_ok */
    double conf_lo[PIX_BLOCK], conf_hi[PIX_BLOCK]; /* the interval, where bound_ok, then the outputs' */
    double crit_lo[PIX_BLOCK], crit_hi[PIX_BLOCK]; /* the critical values, likewise */
    signed char dec[PIX_BLOCK];                    /* MCSTAT_DECISION_*, where done */
    double p[PIX_BLOCK];                           /* the p-value, where done */
    unsigned char done[PIX_BLOCK];                 /* fast_values answered */
    double qn[6][PIX_BLOCK], qs[PIX_BLOCK]; /* the critical values' six table nodes and the offset in them */
    long long bound_ok[PIX_BLOCK]; /* 64 bits, as the doubles: the loop vectorises */
    unsigned char kind[PIX_BLOCK], tail_ok[PIX_BLOCK];
} block_stats;

/* render: the guards of MCSTAT_PIXELS_RENDER (eps, the rule-of-three
 * ratios rx, ry, the nonzero counts hx, hy), the single call's
 * mcstat__render_adjust; a pixel both of whose sides are constant goes to
 * the single call. */
static PIX_INLINE void block_statistics(size_t k, double nx, const mcstat_dd *mx, const double *m2x, const unsigned char *bx,
                             double ny, const mcstat_dd *my, const double *m2y, const unsigned char *by, double mu0,
                             int render, double eps, double rx, double ry, const double *hx, const double *hy,
                             block_stats *bs)
{
    const int px = pow2_count((size_t)nx), py = pow2_count((size_t)ny);
    const double ix = 1.0 / nx, iy = 1.0 / ny;
    unsigned char both[PIX_BLOCK];
    if (render) {
        for (size_t j = 0; j < k; j++) {
            double vx = m2x[j] / (nx - 1.0), vy = m2y[j] / (ny - 1.0);
            mcstat_dd diff = dd_add(mx[j], dd_neg(my[j]));
            mcstat_dd sh = dd_add(diff, (mcstat_dd){-mu0, 0.0});
            mcstat__render_guard rg = {eps, (uint64_t)hx[j], (uint64_t)hy[j]};
            mcstat__render_welch g;
            mcstat__render_adjust(&rg, nx, ny, rx, ry, vx, vy, dmax(fabs(mx[j].hi), fabs(my[j].hi)), sh.hi + sh.lo,
                                  &g);
            double num = eps * dmax(fabs(mx[j].hi), fabs(my[j].hi));
            num *= num;
            /* near the numerical floor the two paths' moments may judge
             * constancy differently: the single call's decides */
            int near = (vx > num * (1.0 - 1e-6) && vx < num * (1.0 + 1e-6)) ||
                       (vy > num * (1.0 - 1e-6) && vy < num * (1.0 + 1e-6));
            both[j] = (unsigned char)(g.both_constant || near);
            double a = div_by(g.vx, nx, ix, px), b = div_by(g.vy, ny, iy, py), se = sqrt(a + b);
            bs->df[j] = g.df;
            bs->t[j] = (sh.hi + sh.lo) / se;
            bs->se[j] = se;
            bs->dhi[j] = diff.hi;
            bs->dlo[j] = diff.lo;
            bs->sdmax[j] = sqrt(dmax(g.vx, g.vy));
            bs->lim[j] = 10.0 * DBL_EPSILON * dmax(fabs(mx[j].hi), fabs(my[j].hi));
        }
    } else {
        /* the same numbers without the guards, in a loop with no branch
         * (it vectorises: its divisions, one at a time, were a quarter of
         * the kernel's time), and with fewer divisions, the vector unit's
         * slowest operation.  Of ra = a/m and rb = b/m (m = max(a, b) > 0
         * on the fast path) one is m/m = 1 exactly and the other r =
         * min/max, so df = (1+r)^2 / (1/(n1-1) + r^2/(n2-1)) with the
         * sides ordered: the same bits as the single call's formula, with
         * 1/(nx-1), 1/(ny-1) the divisions of 1*1 it makes.  And sdmax is
         * kept squared (sd2max, against lim^2). */
        const double cx = 1.0 / (nx - 1.0), cy = 1.0 / (ny - 1.0);
        for (size_t j = 0; j < k; j++) {
            double vx = m2x[j] / (nx - 1.0), vy = m2y[j] / (ny - 1.0);
            mcstat_dd diff = dd_add(mx[j], dd_neg(my[j]));
            mcstat_dd sh = dd_add(diff, (mcstat_dd){-mu0, 0.0});
            double a = div_by(vx, nx, ix, px), b = div_by(vy, ny, iy, py), se = sqrt(a + b);
            int xbig = a >= b;
            double r = (xbig ? b : a) / (xbig ? a : b), r2 = r * r / (xbig ? ny - 1.0 : nx - 1.0);
            bs->df[j] = (1.0 + r) * (1.0 + r) / (xbig ? cx + r2 : r2 + cy);
            bs->t[j] = (sh.hi + sh.lo) / se;
            bs->se[j] = se;
            bs->dhi[j] = diff.hi;
            bs->dlo[j] = diff.lo;
            bs->sdmax[j] = dmax(vx, vy);
            double lim = 10.0 * DBL_EPSILON * dmax(fabs(mx[j].hi), fabs(my[j].hi));
            bs->lim[j] = lim * lim;
        }
    }
    /* The classification compares sdmax with lim (the render loop) or
     * their squares (the other), with margins of 1e-6 around the single
     * call's threshold, far wider than the squares' rounding. */
    const double lo_margin = render ? 1.0 - 1e-6 : (1.0 - 1e-6) * (1.0 - 1e-6),
                 hi_margin = render ? 1.0 + 1e-6 : (1.0 + 1e-6) * (1.0 + 1e-6);
    for (size_t j = 0; j < k; j++) {
        double m2a = m2x[j], m2b = m2y[j], sdmax = bs->sdmax[j], lim = bs->lim[j], se = bs->se[j];
        /* moments.c's var_scaled moves exponents beyond 2^+-500 out of m2;
         * (bitwise & and |: the loop has no branch) */
        int extreme = ((m2a > 0.0) & ((m2a < 0x1p-500) | (m2a > 0x1p+500))) |
                      ((m2b > 0.0) & ((m2b < 0x1p-500) | (m2b > 0x1p+500)));
        /* t_test.c's "constant to within rounding"; near its edge, where the
         * two accumulations of M2 might decide differently, the slow path
         * decides */
        int degenerate = (render == 0) & (!(se > 0.0) | (sdmax < lim * lo_margin));
        /* with the guards, both sides constant (their tests' own), no
         * spread at all or a floor that overflowed (a shift beyond 2^512
         * squared) go to the single call, which scales */
        int edge = render ? (both[j] != 0) | !((se > 0.0) & (se < INFINITY)) : sdmax < lim * hi_margin;
        int slow = (bx[j] != 0) | (by[j] != 0) | extreme;
        bs->kind[j] = (unsigned char)(slow ? PIX_SLOW : degenerate ? PIX_DEGENERATE : edge ? PIX_SLOW : PIX_FAST);
    }
    /* the t prefactor (t_prefactor_init), where the fast tail can use it */
    for (size_t j = 0; j < k; j++) {
        double a = 0.5 * bs->df[j]; /* used only where df is in [1, 1000] */
        bs->pa[j] = a;
        t_prefactor_parts(a, &bs->pf[j], &bs->plc[j]);
    }
}

/* ---- the intervals of a block -------------------------------------------
 * The critical values by the table's weights (t_quantiles.c) and the bounds
 * by mcstat__ci_bound's double-double arithmetic, for all pixels of a block
 * in one branch-free loop; where the interpolation is not good to rounding, or
 * a bound needs ci_bound's guard against overflow, bound_ok is 0 and the
 * pixel's own path (mcstat__qt_criticals, Halley, ci_bound) decides.  First
 * the table's nodes each pixel needs (mcstat__qt_table_nodes: solved
 * lazily, one pixel at a time). */
static void block_nodes(pix_ctx *c, size_t k, block_stats *st)
{
    unsigned char fast[PIX_BLOCK];
    for (size_t j = 0; j < k; j++)
        fast[j] = st->kind[j] == PIX_FAST;
    mcstat__qt_table_nodes(&c->tab, k, st->df, fast, st->qn, st->qs);
}

static PIX_INLINE void block_bounds(size_t k, int alternative, block_stats *st)
{
    for (size_t j = 0; j < k; j++) {
        double q[6], v5, v6, se = st->se[j];
        for (int i = 0; i < 6; i++)
            q[i] = st->qn[i][j];
        lagrange56(q, st->qs[j], &v5, &v6);
        double aq = fabs(v6);
        /* false where a node is NaN */
        long long ok = (fabs(v6 - v5) < 1e-13 * aq) & (aq <= 0x1p900) & (aq * se <= 0x1p900);
        mcstat_dd est = {st->dhi[j], st->dlo[j]}, p = dd_two_prod(v6, se);
        mcstat_dd lo = dd_add(est, dd_neg(p)), hi = dd_add(est, p); /* est -+ q se */
        st->conf_lo[j] = alternative == MCSTAT_LESS ? -INFINITY : lo.hi + lo.lo;
        st->conf_hi[j] = alternative == MCSTAT_GREATER ? INFINITY : hi.hi + hi.lo;
        st->crit_lo[j] = alternative == MCSTAT_GREATER ? -INFINITY : -v6;
        st->crit_hi[j] = alternative == MCSTAT_LESS ? INFINITY : v6;
        st->bound_ok[j] = ok;
    }
}

static void block_bounds_pass(size_t k, int alternative, block_stats *st)
{
    block_bounds(k, alternative, st);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void block_bounds_pass_avx2(size_t k, int alternative, block_stats *st)
{
    block_bounds(k, alternative, st);
}
#endif

/* Pixel i's outputs from its statistics; returns 0 where the slow path must
 * decide. */
static int fast_values(pix_ctx *c, block_stats *bs, size_t j)
{
    double t = bs->t[j], df = bs->df[j], se = bs->se[j];
    double up, other, kk, lo_tail, hi_tail;
    t_prefactor pf, *ppf = NULL;
    if (df >= 1.0 && df <= 1000.0) { /* shared by the tail and the quantile */
        pf.a = bs->pa[j];
        pf.A = pf.a + 0.5;
        pf.f = bs->pf[j];
        pf.lc = bs->plc[j];
        ppf = &pf;
    }
    if (bs->tail_ok[j] == TAIL_DONE) {
        lo_tail = bs->lower[j];
        hi_tail = bs->upper[j];
    } else if (t == 0.0) {
        lo_tail = hi_tail = 0.5;
    } else if (bs->tail_ok[j] == TAIL_SCALAR && ppf && fast_range(fabs(t), df) &&
               mcstat__t_tail_core(fabs(t), ppf, &up, &other, &kk)) {
        lo_tail = t > 0.0 ? other : up;
        hi_tail = t > 0.0 ? up : other;
    } else {
        mcstat_tails tt;
        if (mcstat__t_tails(t, df, &tt))
            return 0;
        lo_tail = tt.p;
        hi_tail = tt.q;
    }
    double p = c->alternative == MCSTAT_LESS      ? lo_tail
               : c->alternative == MCSTAT_GREATER ? hi_tail
                                                  : dmin(1.0, 2.0 * dmin(lo_tail, hi_tail));
    double lo = NAN, hi = NAN, c0 = NAN, c1 = NAN;
    if (c->intervals && bs->bound_ok[j]) {
        lo = bs->conf_lo[j];
        hi = bs->conf_hi[j];
        c0 = bs->crit_lo[j];
        c1 = bs->crit_hi[j];
    } else if (c->intervals) {
        if (mcstat__qt_criticals(&c->tab, df, ppf, &c0, &c1))
            return 0;
        mcstat_dd diff = {bs->dhi[j], bs->dlo[j]};
        lo = mcstat__ci_bound(diff, c1, se, 0);
        hi = mcstat__ci_bound(diff, c0, se, 0);
    }
    /* mcstat__finish's rule: the side of the smaller tail (two-sided) */
    int low_side = c->alternative == MCSTAT_LESS || (c->alternative == MCSTAT_TWO_SIDED && lo_tail < hi_tail);
    bs->dec[j] = (signed char)(p <= c->alpha ? (low_side ? MCSTAT_DECISION_LESS : MCSTAT_DECISION_GREATER)
                                             : MCSTAT_DECISION_EQUAL);
    bs->p[j] = p;
    bs->conf_lo[j] = lo;
    bs->conf_hi[j] = hi;
    bs->crit_lo[j] = c0;
    bs->crit_hi[j] = c1;
    return 1;
}

/* done[j] and p[j] for the block: where the block passes answered the
 * tails (and the bounds, with intervals), the p-value in a loop that
 * vectorises (lower and upper elsewhere hold a previous block's numbers or
 * the zeros of calloc, and are not used); fast_values for the other fast
 * pixels. */
static void block_values(pix_ctx *c, size_t k, block_stats *bs)
{
    const int alt = c->alternative, iv = c->intervals;
    for (size_t j = 0; j < k; j++) {
        double lo = bs->lower[j], up = bs->upper[j];
        double two = dmin(1.0, 2.0 * dmin(lo, up));
        bs->p[j] = alt == MCSTAT_LESS ? lo : alt == MCSTAT_GREATER ? up : two;
        bs->done[j] = bs->kind[j] == PIX_FAST && bs->tail_ok[j] == TAIL_DONE && (!iv || bs->bound_ok[j]);
    }
    /* the decisions where the block answered (in a loop of its own: the one
     * above vectorises); fast_values sets the others' */
    const int less = alt == MCSTAT_LESS, two_sided = alt == MCSTAT_TWO_SIDED;
    for (size_t j = 0; c->out->decision && j < k; j++) {
        int low_side = less | (two_sided & (bs->lower[j] < bs->upper[j]));
        int reject = bs->p[j] <= c->alpha;
        bs->dec[j] = (signed char)(reject * (1 - 2 * low_side)); /* MCSTAT_DECISION_* */
    }
    for (size_t j = 0; j < k; j++)
        if (!bs->done[j] && bs->kind[j] == PIX_FAST)
            bs->done[j] = (unsigned char)fast_values(c, bs, j);
}

/* The block's outputs, array by array, as if every pixel were a fast one
 * (done[j] = 1); the others are then overwritten, each by its own path. */
static void put_block(const pix_ctx *c, size_t i0, size_t k, const block_stats *bs, const mcstat_dd *mx,
                      const mcstat_dd *my)
{
    const mcstat_pixels_out *o = c->out;
    for (size_t j = 0; o->p_value && j < k; j++)
        o->p_value[i0 + j] = bs->p[j];
    for (size_t j = 0; o->statistic && j < k; j++)
        o->statistic[i0 + j] = bs->t[j];
    for (size_t j = 0; o->df && j < k; j++)
        o->df[i0 + j] = bs->df[j];
    for (size_t j = 0; o->std_error && j < k; j++)
        o->std_error[i0 + j] = bs->se[j];
    for (size_t j = 0; o->estimate && j < k; j++)
        o->estimate[i0 + j] = mx[j].hi;
    for (size_t j = 0; o->estimate2 && j < k; j++)
        o->estimate2[i0 + j] = my[j].hi;
    for (size_t j = 0; o->df2 && j < k; j++)
        o->df2[i0 + j] = NAN;
    for (size_t j = 0; o->conf_lo && j < k; j++)
        o->conf_lo[i0 + j] = c->intervals ? bs->conf_lo[j] : NAN;
    for (size_t j = 0; o->conf_hi && j < k; j++)
        o->conf_hi[i0 + j] = c->intervals ? bs->conf_hi[j] : NAN;
    for (size_t j = 0; o->critical_lo && j < k; j++)
        o->critical_lo[i0 + j] = c->intervals ? bs->crit_lo[j] : NAN;
    for (size_t j = 0; o->critical_hi && j < k; j++)
        o->critical_hi[i0 + j] = c->intervals ? bs->crit_hi[j] : NAN;
    for (size_t j = 0; o->decision && j < k; j++)
        o->decision[i0 + j] = (int8_t)bs->dec[j];
    for (size_t j = 0; o->n_x && j < k; j++)
        o->n_x[i0 + j] = c->nx;
    for (size_t j = 0; o->n_y && j < k; j++)
        o->n_y[i0 + j] = c->ny;
    for (size_t j = 0; o->status && j < k; j++)
        o->status[i0 + j] = MCSTAT_OK;
}

/* The unweighted single-channel case (the usual one) goes MOMENT_TILE
 * pixels at a time with the seeds inside, so that the sums stay in
 * registers instead of being loaded and stored once per seed; the
 * additions are the same, in the same order. */
#define MOMENT_TILE 8
#define ROWS_TILE_MAX 256 /* longest rows transposed for the tile loop */
#define DEFINE_MOMENT_TILE(NAME, T, RANGE)                                                                 \
    static PIX_INLINE void NAME(const T *x, size_t n, size_t stride, size_t j0, size_t len, double dn,     \
                                double inv, int p2, double *sum, double *s1, double *s2, double *amax)     \
    {                                                                                                      \
        double a[MOMENT_TILE], b[MOMENT_TILE], q[MOMENT_TILE], mx[MOMENT_TILE];                            \
        for (size_t l = 0; l < len; l++)                                                                   \
            a[l] = b[l] = q[l] = mx[l] = 0.0;                                                              \
        for (size_t s = 0; s < n; s++) {                                                                   \
            const T *row = x + s * stride + j0;                                                            \
            for (size_t l = 0; l < len; l++) {                                                             \
                double v = (double)row[l];                                                                 \
                a[l] += v;                                                                                 \
                if (RANGE) {                                                                               \
                    double av = fabs(v);                                                                   \
                    mx[l] = av > mx[l] ? av : mx[l];                                                       \
                }                                                                                          \
            }                                                                                              \
        }                                                                                                  \
        for (size_t l = 0; l < len; l++)                                                                   \
            a[l] = div_by(a[l], dn, inv, p2);                                                              \
        for (size_t s = 0; s < n; s++) {                                                                   \
            const T *row = x + s * stride + j0;                                                            \
            for (size_t l = 0; l < len; l++) {                                                             \
                double d = (double)row[l] - a[l];                                                          \
                b[l] += d;                                                                                 \
                q[l] += d * d;                                                                             \
            }                                                                                              \
        }                                                                                                  \
        for (size_t l = 0; l < len; l++) {                                                                 \
            sum[j0 + l] = a[l];                                                                            \
            s1[j0 + l] = b[l];                                                                             \
            s2[j0 + l] = q[l];                                                                             \
            amax[j0 + l] = mx[l];                                                                          \
        }                                                                                                  \
    }

DEFINE_MOMENT_TILE(moment_tile_f32, float, 0)
DEFINE_MOMENT_TILE(moment_tile_f64_any, double, 1)

/* The doubles' full tile in explicit vectors of four: GCC left the loop
 * above scalar for doubles (the |v| maximum defeated its vectoriser: a
 * third of the kernel's time on seeds-major float64 stacks).  Lane l is
 * pixel j0 + l with the loop's own operations in its order, the maximum
 * as its |v| > m ? |v| : m: the same bits. */
static PIX_INLINE void moment_tile_f64(const double *x, size_t n, size_t stride, size_t j0, size_t len, double dn,
                                       double inv, int p2, double *sum, double *s1, double *s2, double *amax)
{
    if (len != MOMENT_TILE) {
        moment_tile_f64_any(x, n, stride, j0, len, dn, inv, p2, sum, s1, s2, amax);
        return;
    }
    const mcs_v4d zero = vm_splat(0.0);
    mcs_v4d a0 = zero, a1 = zero, m0 = zero, m1 = zero, v0, v1;
    for (size_t s = 0; s < n; s++) {
        const double *row = x + s * stride + j0;
        memcpy(&v0, row, sizeof v0);
        memcpy(&v1, row + 4, sizeof v1);
        a0 += v0;
        a1 += v1;
        mcs_v4d av0 = vm_fabs(v0), av1 = vm_fabs(v1);
        m0 = vm_select((mcs_v4i)(av0 > m0), av0, m0);
        m1 = vm_select((mcs_v4i)(av1 > m1), av1, m1);
    }
    if (p2) {
        a0 *= inv;
        a1 *= inv;
    } else {
        a0 /= dn;
        a1 /= dn;
    }
    mcs_v4d b0 = zero, b1 = zero, q0 = zero, q1 = zero;
    for (size_t s = 0; s < n; s++) {
        const double *row = x + s * stride + j0;
        memcpy(&v0, row, sizeof v0);
        memcpy(&v1, row + 4, sizeof v1);
        mcs_v4d d0 = v0 - a0, d1 = v1 - a1;
        b0 += d0;
        b1 += d1;
        q0 += d0 * d0;
        q1 += d1 * d1;
    }
    memcpy(sum + j0, &a0, sizeof a0);
    memcpy(sum + j0 + 4, &a1, sizeof a1);
    memcpy(s1 + j0, &b0, sizeof b0);
    memcpy(s1 + j0 + 4, &b1, sizeof b1);
    memcpy(s2 + j0, &q0, sizeof q0);
    memcpy(s2 + j0 + 4, &q1, sizeof q1);
    memcpy(amax + j0, &m0, sizeof m0);
    memcpy(amax + j0 + 4, &m1, sizeof m1);
}

/* Moments of pixels i0..i0+k-1 of one side into the block's arrays.
 * bad[j] is set where the fast path cannot use the sums (non-finite,
 * extreme). */
/* RANGE: whether an unweighted value can lie outside [FAST_LO, FAST_HI]: a
 * double can; a float cannot (its magnitudes span 2^-149 to 2^128), so its
 * loop skips the |v| maximum and its checks are the sum's finiteness only.
 * A weighted sum of channels is checked whatever the type. */
/* Rows of values per pixel: MOMENT_TILE pixels' rows transposed into a
 * small buffer, then the tile loop as for seeds-major stacks (the same
 * additions in the same order: the same bits).  Not inlined: its buffer
 * would otherwise widen the block loops' frame (measured: 10 ns a pixel
 * on seeds-major stacks). */
#define DEFINE_ROWS_TILES(NAME, TILE, T)                                                                   \
    static __attribute__((noinline)) void NAME(const T *x, size_t n, size_t ps, size_t i0, size_t k,       \
                                               double dn, double inv, int p2, double *sum, double *s1,     \
                                               double *s2, double *amax)                                   \
    {                                                                                                      \
        T buf[MOMENT_TILE * ROWS_TILE_MAX];                                                                \
        for (size_t j = 0; j < k; j += MOMENT_TILE) {                                                      \
            size_t len = k - j < MOMENT_TILE ? k - j : MOMENT_TILE;                                        \
            for (size_t l = 0; l < len; l++) {                                                             \
                const T *r = x + (i0 + j + l) * ps;                                                        \
                for (size_t s = 0; s < n; s++)                                                             \
                    buf[s * MOMENT_TILE + l] = r[s];                                                       \
            }                                                                                              \
            TILE(buf, n, MOMENT_TILE, 0, len, dn, inv, p2, sum + j, s1 + j, s2 + j, amax + j);             \
        }                                                                                                  \
    }

DEFINE_ROWS_TILES(rows_tiles_f32, moment_tile_f32, float)
DEFINE_ROWS_TILES(rows_tiles_f64, moment_tile_f64, double)

#if PIX_AVX2
/* The AVX2 build's rows: eight rows at a time, read four values of four
 * rows at once and transposed in registers, so that each lane of a vector
 * is one row and its sums are the tile loop's, addition for addition (the
 * copy through a buffer was most of the per-row call's time). */
#define ROWS_LOAD4_F64(r, ps, v0, v1, v2, v3)                                                              \
    do {                                                                                                   \
        v0 = _mm256_loadu_pd(r);                                                                           \
        v1 = _mm256_loadu_pd((r) + (ps));                                                                  \
        v2 = _mm256_loadu_pd((r) + 2 * (ps));                                                              \
        v3 = _mm256_loadu_pd((r) + 3 * (ps));                                                              \
    } while (0)
#define ROWS_LOAD4_F32(r, ps, v0, v1, v2, v3)                                                              \
    do {                                                                                                   \
        v0 = _mm256_cvtps_pd(_mm_loadu_ps(r));                                                             \
        v1 = _mm256_cvtps_pd(_mm_loadu_ps((r) + (ps)));                                                    \
        v2 = _mm256_cvtps_pd(_mm_loadu_ps((r) + 2 * (ps)));                                                \
        v3 = _mm256_cvtps_pd(_mm_loadu_ps((r) + 3 * (ps)));                                                \
    } while (0)
/* vj: values s..s+3 of row j -> vj: value s+j of rows 0..3 */
#define ROWS_T4(v0, v1, v2, v3)                                                                            \
    do {                                                                                                   \
        __m256d t0_ = _mm256_unpacklo_pd(v0, v1), t1_ = _mm256_unpackhi_pd(v0, v1);                       \
        __m256d t2_ = _mm256_unpacklo_pd(v2, v3), t3_ = _mm256_unpackhi_pd(v2, v3);                       \
        v0 = _mm256_permute2f128_pd(t0_, t2_, 0x20);                                                       \
        v1 = _mm256_permute2f128_pd(t1_, t3_, 0x20);                                                       \
        v2 = _mm256_permute2f128_pd(t0_, t2_, 0x31);                                                       \
        v3 = _mm256_permute2f128_pd(t1_, t3_, 0x31);                                                       \
    } while (0)
/* value s of rows r..r+3 (the last values, when n is not a multiple of 4) */
#define ROWS_COL4(r, ps, s) _mm256_set_pd((r)[3 * (ps) + (s)], (r)[2 * (ps) + (s)], (r)[(ps) + (s)], (r)[s])

#define DEFINE_ROWS_TILE8(NAME, T, LOAD4, RANGE)                                                           \
    __attribute__((target("avx2"))) static void NAME(const T *x, size_t n, size_t ps, double dn, double inv, \
                                                     int p2, double *sum, double *s1, double *s2,          \
                                                     double *amax)                                         \
    {                                                                                                      \
        const T *x4 = x + 4 * ps;                                                                          \
        const __m256d sign = _mm256_set1_pd(-0.0);                                                         \
        __m256d a0 = _mm256_setzero_pd(), a1 = a0, m0 = a0, m1 = a0;                                       \
        __m256d u0, u1, u2, u3, w0, w1, w2, w3;                                                            \
        size_t s = 0;                                                                                      \
        for (; s + 4 <= n; s += 4) {                                                                       \
            LOAD4(x + s, ps, u0, u1, u2, u3);                                                              \
            LOAD4(x4 + s, ps, w0, w1, w2, w3);                                                             \
            ROWS_T4(u0, u1, u2, u3);                                                                       \
            ROWS_T4(w0, w1, w2, w3);                                                                       \
            a0 = _mm256_add_pd(a0, u0);                                                                    \
            a1 = _mm256_add_pd(a1, w0);                                                                    \
            a0 = _mm256_add_pd(a0, u1);                                                                    \
            a1 = _mm256_add_pd(a1, w1);                                                                    \
            a0 = _mm256_add_pd(a0, u2);                                                                    \
            a1 = _mm256_add_pd(a1, w2);                                                                    \
            a0 = _mm256_add_pd(a0, u3);                                                                    \
            a1 = _mm256_add_pd(a1, w3);                                                                    \
            if (RANGE) { /* max(|v|, m): |v| > m ? |v| : m, as the tile loop's */                         \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u0), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w0), m1);                                        \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u1), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w1), m1);                                        \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u2), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w2), m1);                                        \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u3), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w3), m1);                                        \
            }                                                                                              \
        }                                                                                                  \
        for (size_t t = s; t < n; t++) {                                                                   \
            u0 = ROWS_COL4(x, ps, t);                                                                      \
            w0 = ROWS_COL4(x4, ps, t);                                                                     \
            a0 = _mm256_add_pd(a0, u0);                                                                    \
            a1 = _mm256_add_pd(a1, w0);                                                                    \
            if (RANGE) {                                                                                   \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u0), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w0), m1);                                        \
            }                                                                                              \
        }                                                                                                  \
        if (p2) {                                                                                          \
            a0 = _mm256_mul_pd(a0, _mm256_set1_pd(inv));                                                   \
            a1 = _mm256_mul_pd(a1, _mm256_set1_pd(inv));                                                   \
        } else {                                                                                           \
            a0 = _mm256_div_pd(a0, _mm256_set1_pd(dn));                                                    \
            a1 = _mm256_div_pd(a1, _mm256_set1_pd(dn));                                                    \
        }                                                                                                  \
        __m256d b0 = _mm256_setzero_pd(), b1 = b0, q0 = b0, q1 = b0;                                       \
        for (s = 0; s + 4 <= n; s += 4) {                                                                  \
            LOAD4(x + s, ps, u0, u1, u2, u3);                                                              \
            LOAD4(x4 + s, ps, w0, w1, w2, w3);                                                             \
            ROWS_T4(u0, u1, u2, u3);                                                                       \
            ROWS_T4(w0, w1, w2, w3);                                                                       \
            ROWS_STEP2(u0, w0);                                                                            \
            ROWS_STEP2(u1, w1);                                                                            \
            ROWS_STEP2(u2, w2);                                                                            \
            ROWS_STEP2(u3, w3);                                                                            \
        }                                                                                                  \
        for (size_t t = s; t < n; t++) {                                                                   \
            u0 = ROWS_COL4(x, ps, t);                                                                      \
            w0 = ROWS_COL4(x4, ps, t);                                                                     \
            ROWS_STEP2(u0, w0);                                                                            \
        }                                                                                                  \
        _mm256_storeu_pd(sum, a0);                                                                         \
        _mm256_storeu_pd(sum + 4, a1);                                                                     \
        _mm256_storeu_pd(s1, b0);                                                                          \
        _mm256_storeu_pd(s1 + 4, b1);                                                                      \
        _mm256_storeu_pd(s2, q0);                                                                          \
        _mm256_storeu_pd(s2 + 4, q1);                                                                      \
        _mm256_storeu_pd(amax, m0);                                                                        \
        _mm256_storeu_pd(amax + 4, m1);                                                                    \
    }
/* the second pass's step: d = v - mean; s1 += d; s2 += d * d */
#define ROWS_STEP2(u, w)                                                                                   \
    do {                                                                                                   \
        __m256d du_ = _mm256_sub_pd(u, a0), dw_ = _mm256_sub_pd(w, a1);                                    \
        b0 = _mm256_add_pd(b0, du_);                                                                       \
        b1 = _mm256_add_pd(b1, dw_);                                                                       \
        q0 = _mm256_add_pd(q0, _mm256_mul_pd(du_, du_));                                                   \
        q1 = _mm256_add_pd(q1, _mm256_mul_pd(dw_, dw_));                                                   \
    } while (0)

DEFINE_ROWS_TILE8(rows_tile8_f32, float, ROWS_LOAD4_F32, 0)
DEFINE_ROWS_TILE8(rows_tile8_f64, double, ROWS_LOAD4_F64, 1)

#define DEFINE_ROWS_TILES_AVX2(NAME, TILE8, REST, T)                                                       \
    __attribute__((target("avx2"))) static void NAME(const T *x, size_t n, size_t ps, size_t i0, size_t k,  \
                                                     double dn, double inv, int p2, double *sum,           \
                                                     double *s1, double *s2, double *amax)                 \
    {                                                                                                      \
        size_t j = 0;                                                                                      \
        for (; j + MOMENT_TILE <= k; j += MOMENT_TILE)                                                     \
            TILE8(x + (i0 + j) * ps, n, ps, dn, inv, p2, sum + j, s1 + j, s2 + j, amax + j);               \
        if (j < k)                                                                                         \
            REST(x, n, ps, i0 + j, k - j, dn, inv, p2, sum + j, s1 + j, s2 + j, amax + j);                 \
    }

DEFINE_ROWS_TILES_AVX2(rows_tiles_f32_avx2, rows_tile8_f32, rows_tiles_f32, float)
DEFINE_ROWS_TILES_AVX2(rows_tiles_f64_avx2, rows_tile8_f64, rows_tiles_f64, double)
#else
#define rows_tiles_f32_avx2 rows_tiles_f32
#define rows_tiles_f64_avx2 rows_tiles_f64
#endif

/* wide: called from the AVX2 build (a constant once inlined) */
#define DEFINE_BLOCK_MOMENTS(NAME, TILE, ROWS, T, RANGE)                                                   \
    static PIX_INLINE void NAME(const T *x, size_t n, size_t stride, size_t ps, size_t ch, const double *w,        \
                                size_t i0, size_t k, mcstat_dd *mean, double *m2, unsigned char *bad, int wide)    \
    {                                                                                                      \
        double sum[PIX_BLOCK], amax[PIX_BLOCK], s1[PIX_BLOCK], s2[PIX_BLOCK];                              \
        const double dn = (double)n, inv = 1.0 / dn;                                                       \
        const int p2 = pow2_count(n);                                                                      \
        if (ch == 1 && !w && ps == 1) {                                                                    \
            size_t j = 0;                                                                                  \
            for (; j + MOMENT_TILE <= k; j += MOMENT_TILE)                                                 \
                TILE(x + i0, n, stride, j, MOMENT_TILE, dn, inv, p2, sum, s1, s2, amax);                   \
            for (; j < k; j++)                                                                             \
                TILE(x + i0, n, stride, j, 1, dn, inv, p2, sum, s1, s2, amax);                             \
        } else if (ch == 1 && !w && stride == 1 && n <= ROWS_TILE_MAX) {                                   \
            if (wide)                                                                                      \
                ROWS##_avx2(x, n, ps, i0, k, dn, inv, p2, sum, s1, s2, amax);                              \
            else                                                                                           \
                ROWS(x, n, ps, i0, k, dn, inv, p2, sum, s1, s2, amax);                                     \
        } else {                                                                                           \
            for (size_t j = 0; j < k; j++)                                                                 \
                sum[j] = amax[j] = s1[j] = s2[j] = 0.0;                                                    \
            for (size_t s = 0; s < n; s++) {                                                               \
                const T *row = x + s * stride + i0 * ps;                                                   \
                for (size_t j = 0; j < k; j++) {                                                           \
                    double v = w ? 0.0 : (double)row[j * ps];                                              \
                    for (size_t c = 0; w && c < ch; c++)                                                   \
                        v += w[c] * (double)row[j * ps + c];                                               \
                    sum[j] += v;                                                                           \
                    double av = fabs(v);                                                                   \
                    amax[j] = av > amax[j] ? av : amax[j];                                                 \
                }                                                                                          \
            }                                                                                              \
            for (size_t j = 0; j < k; j++)                                                                 \
                sum[j] = div_by(sum[j], dn, inv, p2); /* the mean to a few ulps; the second pass corrects it */ \
            for (size_t s = 0; s < n; s++) {                                                               \
                const T *row = x + s * stride + i0 * ps;                                                   \
                for (size_t j = 0; j < k; j++) {                                                           \
                    double v = w ? 0.0 : (double)row[j * ps];                                              \
                    for (size_t c = 0; w && c < ch; c++)                                                   \
                        v += w[c] * (double)row[j * ps + c];                                               \
                    double d = v - sum[j];                                                                 \
                    s1[j] += d;                                                                            \
                    s2[j] += d * d;                                                                        \
                }                                                                                          \
            }                                                                                              \
        }                                                                                                  \
        for (size_t j = 0; j < k; j++) {                                                                   \
            double c1 = div_by(s1[j], dn, inv, p2);                                                        \
            mean[j] = dd_two_sum(sum[j], c1);                                                              \
            double v2 = s2[j] - s1[j] * c1;                                                                \
            m2[j] = v2 > 0.0 ? v2 : 0.0;                                                                   \
        }                                                                                                  \
        /* a NaN or Inf among the values makes the sum NaN or Inf; a float's */                            \
        /* squares cannot overflow, a double's or a weighted sum's can */                                  \
        const int range = RANGE || w || ch != 1;                                                           \
        for (size_t j = 0; j < k; j++)                                                                     \
            bad[j] = !(fabs(sum[j]) <= DBL_MAX) ||                                                         \
                     (range && (!(fabs(s2[j]) <= DBL_MAX) || !(fabs(s1[j]) <= DBL_MAX) ||                  \
                                (amax[j] != 0.0 && (amax[j] < FAST_LO || amax[j] > FAST_HI))));            \
    }

DEFINE_BLOCK_MOMENTS(block_moments_f32, moment_tile_f32, rows_tiles_f32, float, 0)
DEFINE_BLOCK_MOMENTS(block_moments_f64, moment_tile_f64, rows_tiles_f64, double, 1)

/* One side's block moments for the other per-pixel tests (pixels_var.c),
 * in the SSE2 and AVX2 builds: the same numbers as Welch's. */
static PIX_INLINE void side_moments_body(const mcstat_pixels_in *p, size_t i0, size_t k, mcstat_dd *mean, double *m2,
                                         unsigned char *bad, int wide)
{
    if (p->type == MCSTAT_VALUE_FLOAT32)
        block_moments_f32(p->data, p->n, p->value_stride, p->pixel_stride, p->channels, p->weights, i0, k, mean, m2,
                          bad, wide);
    else
        block_moments_f64(p->data, p->n, p->value_stride, p->pixel_stride, p->channels, p->weights, i0, k, mean, m2,
                          bad, wide);
}

static void side_moments(const mcstat_pixels_in *p, size_t i0, size_t k, mcstat_dd *mean, double *m2,
                         unsigned char *bad)
{
    side_moments_body(p, i0, k, mean, m2, bad, 0);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void side_moments_avx2(const mcstat_pixels_in *p, size_t i0, size_t k,
                                                               mcstat_dd *mean, double *m2, unsigned char *bad)
{
    side_moments_body(p, i0, k, mean, m2, bad, 1);
}
#endif

#if PIX_AVX2
static int use_avx2(void);
#endif

void mcstat__pixels_block_moments(const mcstat_pixels_in *p, size_t i0, size_t k, mcstat_dd *mean, double *m2,
                                  unsigned char *bad)
{
#if PIX_AVX2
    if (use_avx2()) {
        side_moments_avx2(p, i0, k, mean, m2, bad);
        return;
    }
#endif
    side_moments(p, i0, k, mean, m2, bad);
}

/* Set by the tests, on their own thread, to compare the baseline loops
 * with the AVX2 ones (thread-local: no other thread's calls see it). */
static _Thread_local int pixels_baseline_only;

void mcstat__pixels_baseline_only(int on)
{
    pixels_baseline_only = on;
}

#if PIX_AVX2
/* Whether the AVX2 loops may run: the CPU has AVX2 and MCSTAT_NO_AVX2 is
 * not set (or "0") in the environment (mcstat.h: for valgrind 3.19, which
 * stops at some AVX2 encodings).  Read once, at the first call that asks,
 * and never written again: the library's only process-wide value. */
static pthread_once_t avx2_once = PTHREAD_ONCE_INIT;
static int avx2_allowed;

static void avx2_probe(void)
{
    const char *e = getenv("MCSTAT_NO_AVX2");
    int no = e && *e && strcmp(e, "0") != 0;
    avx2_allowed = !no && __builtin_cpu_supports("avx2");
}

/* Whether this call runs the AVX2 loops (per pixel and per quantile). */
static int use_avx2(void)
{
    pthread_once(&avx2_once, avx2_probe);
    return avx2_allowed && !pixels_baseline_only;
}
#endif

int mcstat__pixels_avx2(void)
{
#if PIX_AVX2
    return use_avx2();
#else
    return 0;
#endif
}

/* One block: both sides' moments, then the statistics. */
typedef struct {
    mcstat_dd mx[PIX_BLOCK], my[PIX_BLOCK];
    double m2x[PIX_BLOCK], m2y[PIX_BLOCK];
    double hx[PIX_BLOCK], hy[PIX_BLOCK]; /* nonzero values, with the render guards */
    unsigned char bx[PIX_BLOCK], by[PIX_BLOCK];
    block_stats st;
} block_work;

typedef struct {
    const float *xf, *yf;
    const double *xd, *yd, *w;
    size_t nx, xs, xps, ny, ys, yps, ch;
    double mu0;
    int render;
    double eps, rx, ry;
} block_input;

/* The nonzero values of pixels i0..i0+k-1 of one side (a value formed as
 * the moments' loops and the single call's form it; NaN counts, but such a
 * pixel is the single call's). */
#define DEFINE_BLOCK_NONZERO(NAME, T)                                                                      \
    static PIX_INLINE void NAME(const T *x, size_t n, size_t stride, size_t ps, size_t ch, const double *w, \
                                size_t i0, size_t k, double *h)                                            \
    {                                                                                                      \
        for (size_t j = 0; j < k; j++)                                                                     \
            h[j] = 0.0;                                                                                    \
        for (size_t s = 0; s < n; s++) {                                                                   \
            const T *row = x + s * stride + i0 * ps;                                                       \
            for (size_t j = 0; j < k; j++) {                                                               \
                double v = w ? 0.0 : (double)row[j * ps];                                                  \
                for (size_t c = 0; w && c < ch; c++)                                                       \
                    v += w[c] * (double)row[j * ps + c];                                                   \
                h[j] += v != 0.0 ? 1.0 : 0.0;                                                              \
            }                                                                                              \
        }                                                                                                  \
    }
DEFINE_BLOCK_NONZERO(block_nonzero_f32, float)
DEFINE_BLOCK_NONZERO(block_nonzero_f64, double)

/* joint: the AVX2 build's central series (central_series8) */
static PIX_INLINE void block_pass_body(const block_input *in, size_t i0, size_t k, block_work *b, int joint)
{
    if (in->xf) {
        block_moments_f32(in->xf, in->nx, in->xs, in->xps, in->ch, in->w, i0, k, b->mx, b->m2x, b->bx, joint);
        block_moments_f32(in->yf, in->ny, in->ys, in->yps, in->ch, in->w, i0, k, b->my, b->m2y, b->by, joint);
    } else {
        block_moments_f64(in->xd, in->nx, in->xs, in->xps, in->ch, in->w, i0, k, b->mx, b->m2x, b->bx, joint);
        block_moments_f64(in->yd, in->ny, in->ys, in->yps, in->ch, in->w, i0, k, b->my, b->m2y, b->by, joint);
    }
    if (in->render && in->xf) {
        block_nonzero_f32(in->xf, in->nx, in->xs, in->xps, in->ch, in->w, i0, k, b->hx);
        block_nonzero_f32(in->yf, in->ny, in->ys, in->yps, in->ch, in->w, i0, k, b->hy);
    } else if (in->render) {
        block_nonzero_f64(in->xd, in->nx, in->xs, in->xps, in->ch, in->w, i0, k, b->hx);
        block_nonzero_f64(in->yd, in->ny, in->ys, in->yps, in->ch, in->w, i0, k, b->hy);
    }
    block_statistics(k, (double)in->nx, b->mx, b->m2x, b->bx, (double)in->ny, b->my, b->m2y, b->by, in->mu0,
                     in->render, in->eps, in->rx, in->ry, b->hx, b->hy, &b->st);
    unsigned char want[PIX_BLOCK];
    for (size_t j = 0; j < k; j++)
        want[j] = b->st.kind[j] == PIX_FAST;
#if PIX_AVX2
    if (joint)
        mcstat__t_block_tails_avx2(k, b->st.t, b->st.df, b->st.pa, b->st.pf, b->st.plc, want, b->st.lower,
                                   b->st.upper, b->st.tail_ok);
    else
#endif
        mcstat__t_block_tails(k, b->st.t, b->st.df, b->st.pa, b->st.pf, b->st.plc, want, b->st.lower,
                              b->st.upper, b->st.tail_ok);
}

static void block_pass(const block_input *in, size_t i0, size_t k, block_work *b)
{
    block_pass_body(in, i0, k, b, 0);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void block_pass_avx2(const block_input *in, size_t i0, size_t k,
                                                             block_work *b)
{
    block_pass_body(in, i0, k, b, 1);
}
#endif

/* Welch's test for pixels [begin, end) of x and y (pixels_test.c has
 * checked the arguments; x and y are of one type and channel weighting).
 * Returns the status of the first pixel that failed. */
int mcstat__pixels_welch(const mcstat_pixels_in *x, const mcstat_pixels_in *y, mcstat__work *wk, size_t *first_index,
                         double mu0, int alternative, double alpha, unsigned flags, double eps,
                         const mcstat_pixels_out *out)
{
    const int f32 = x->type == MCSTAT_VALUE_FLOAT32;
    const float *xf = f32 ? x->data : NULL, *yf = f32 ? y->data : NULL;
    const double *xd = f32 ? NULL : x->data, *yd = f32 ? NULL : y->data;
    const size_t nx = x->n, ny = y->n, channels = x->channels;
    const double *w = x->weights;
    pix_ctx c;
    c.out = out;
    c.alternative = alternative;
    c.intervals = !(flags & MCSTAT_ROWS_NO_INTERVALS);
    c.mu0 = mu0;
    c.alpha = alpha;
    c.tab.alternative = alternative;
    c.tab.crit_two = NAN;
    c.tab.crit_df = NAN;
    c.tab.qt_p = alternative == MCSTAT_TWO_SIDED ? 0.5 * alpha : alpha;
    c.nx = nx;
    c.ny = ny;
    double qt[QT_NODES + 1];
    if (c.intervals)
        mcstat__qt_table_init(&c.tab, c.tab.qt_p, qt, QT_NODES);
    mcstat__qcache_init(&c.qc);
    c.first = MCSTAT_OK;
    c.first_i = 0;
    c.render = (flags & MCSTAT_PIXELS_RENDER) != 0;
    c.eps = eps;
    plane px = {xf, xd, x->value_stride, x->pixel_stride, channels, w},
          py = {yf, yd, y->value_stride, y->pixel_stride, channels, w};
    block_input in = {xf, yf, xd, yd, w, nx, x->value_stride, x->pixel_stride, ny, y->value_stride, y->pixel_stride,
                      channels, mu0, c.render, eps, NAN, NAN};
    if (c.render && nx >= 2 && ny >= 2) {
        in.rx = mcstat__rule3_ratio((double)nx);
        in.ry = mcstat__rule3_ratio((double)ny);
    }
    block_work *b = calloc(1, sizeof *b); /* tens of KiB: not on a caller's thread stack */
    int fast_ok = nx >= 2 && ny >= 2 && b;
#if PIX_AVX2
    int avx2 = use_avx2();
#endif
    size_t begin, end;
    while (mcstat__work_take(wk, &begin, &end))
    for (size_t i0 = begin; i0 < end; i0 += PIX_BLOCK) {
        size_t k = end - i0 < PIX_BLOCK ? end - i0 : PIX_BLOCK;
        if (fast_ok) {
#if PIX_AVX2
            if (avx2)
                block_pass_avx2(&in, i0, k, b);
            else
#endif
                block_pass(&in, i0, k, b);
            if (c.intervals) {
                block_nodes(&c, k, &b->st);
#if PIX_AVX2
                if (avx2)
                    block_bounds_pass_avx2(k, alternative, &b->st);
                else
#endif
                    block_bounds_pass(k, alternative, &b->st);
            }
            block_values(&c, k, &b->st);
            put_block(&c, i0, k, &b->st, b->mx, b->my);
        }
        for (size_t j = 0; j < k; j++) {
            size_t i = i0 + j;
            if (fast_ok && b->st.done[j])
                continue;
            if (fast_ok && b->st.kind[j] == PIX_DEGENERATE)
                fail(&c, i, MCSTAT_EDEGENERATE);
            else
                slow_pixel(&c, &px, nx, &py, ny, i, flags);
        }
    }
    free(b);
    *first_index = c.first_i;
    return c.first;
}

