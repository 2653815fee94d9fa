/*
 * pixels_var.c - the chi-squared and F tests per pixel (mcstat_pixels_test's
 * MCSTAT_TEST_VAR_1 and _2) by blocks of pixels.
 *
 * Every pixel of a call has the same number of values, so the same degrees
 * of freedom: the tails are a function of the statistic alone.  They come
 * from a per-call table of both log tails at equally spaced points of
 * u = log(statistic / centre) (the centre df for chi-squared, 1 for F; 512
 * points per standard deviation of u, 20 of them each side), each point
 * solved by the general routine when a pixel first needs it (the same
 * numbers whichever pixels ask, so results do not depend on threads), and
 * interpolated by Lagrange through six points.  Where the five- and
 * six-point values disagree beyond TAB_TOL, or the tail is below
 * e^-MAX_LOG_P, or where the p-value is so steep in the statistic that the
 * moments' rounding (about (nx + ny) eps of the statistic, at worst) could
 * take it past the bound of mcstat.h, the pixel takes the single call's
 * code, as do pixels with a
 * NaN or Inf, extreme magnitudes, zero or nearly zero variance, df beyond
 * 1000, all pixels of a call whose critical values leave the normal
 * doubles.  Which path a pixel takes depends on its values and the call's
 * constants only, never on the range or the threads: a small call pays for
 * the few points it needs (each about as costly as one pixel's single
 * call).  The moments are pixels.c's two passes (the single call's are
 * shifted sums): statistics agree to a few ulps, and the p-value to the
 * bound of mcstat.h.  Critical values are the single call's, solved once.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"
#include "vmath.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* the vector passes compiled for the baseline and for AVX2, as pixels.c's */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PIX_VAR_AVX2 1
#define PIX_INLINE inline __attribute__((always_inline))
#else
#define PIX_VAR_AVX2 0
#define PIX_INLINE inline
#endif

#define VBLOCK 256   /* pixels per block (mcstat__pixels_block_moments' limit) */
#define STEPS 512    /* table points per standard deviation of u */
#define SPAN 20      /* standard deviations each side of the centre */
#define MID (STEPS * SPAN)
#define N_NODES (2 * MID + 1)
#define MAX_DF 1000.0
#define MAX_LOG_P 200.0 /* |log| of the smaller tail the table answers */
#define TAB_TOL 2e-15   /* largest |v6 - v5| of a log tail taken from the table */
#define NODE_USABLE 1
#define NODE_UNUSABLE 2

typedef struct {
    int chisq;
    double df1, df2, centre, h, inv_h;
    double *lt;           /* log lower tail at 2j, log upper at 2j + 1; +Inf: unusable */
    unsigned char *known; /* known[j]: 0 until point j is solved, then NODE_USABLE or NODE_UNUSABLE
                             (calloc'd: untouched pages cost nothing) */
} tail_table;

/* Solves node j if it is not yet known; whether it is usable. */
static int table_node(tail_table *tb, int j)
{
    if (!tb->known[j]) {
        double *v = tb->lt + 2 * j;
        double s = tb->centre * exp((double)(j - MID) * tb->h);
        mcstat_tails t;
        int st = tb->chisq ? mcstat__chisq_tails(s, tb->df1, &t) : mcstat__f_tails(s, tb->df1, tb->df2, &t);
        int usable = !st && isfinite(t.logp) && isfinite(t.logq) && s > 0.0 && isfinite(s);
        v[0] = usable ? t.logp : INFINITY;
        v[1] = usable ? t.logq : INFINITY;
        tb->known[j] = usable ? NODE_USABLE : NODE_UNUSABLE;
    }
    return tb->known[j] == NODE_USABLE;
}

/* Whether nodes n0..n0+5 are all solved and usable (the usual case, without
 * a branch per node), else solves the ones not yet known. */
static int table_nodes6(tail_table *tb, int n0)
{
    const unsigned char *k = tb->known + n0;
    if ((k[0] == NODE_USABLE) & (k[1] == NODE_USABLE) & (k[2] == NODE_USABLE) & (k[3] == NODE_USABLE) &
        (k[4] == NODE_USABLE) & (k[5] == NODE_USABLE))
        return 1;
    int ok = 1;
    for (int i = 0; i < 6 && ok; i++)
        ok = table_node(tb, n0 + i);
    return ok;
}

/* A block's pixels between its passes: the statistics, then what the
 * table's vector pass makes of them. */
typedef struct {
    double stat[VBLOCK], est[VBLOCK]; /* the statistic and estimate (pixels not ok: anything) */
    double v[VBLOCK];                 /* the table's coordinate of the statistic (not ok: 2) */
    double p[VBLOCK];                 /* the p-value */
    double lo[VBLOCK], hi[VBLOCK];    /* the interval */
    int8_t dec[VBLOCK];
    int32_t n0[VBLOCK];               /* the first of the six nodes (not ok: 0) */
    long long ok[VBLOCK], low[VBLOCK]; /* all ones: the block path answers; the lower tail's side */
} var_block;

typedef struct {
    double centre, inv_h, steep; /* steep: (nx + ny + 4) eps, the statistic's rounding */
    int alternative;
    const double *lt;
} var_consts;

/* The table's coordinate of every statistic of the block, v = log(stat /
 * centre) / h + MID, four at a time (k rounded up to 4: the arrays' tails
 * hold the centre). */
static PIX_INLINE void block_coords(size_t k4, const var_consts *vc, var_block *bk)
{
    const double inv_c = 1.0 / vc->centre;
    for (size_t j = 0; j < k4; j += 4) {
        mcs_v4d st;
        memcpy(&st, bk->stat + j, sizeof st);
        mcs_v4d v = vm_log4(st * inv_c) * vc->inv_h + (double)MID;
        memcpy(bk->v + j, &v, sizeof v);
    }
}

#define GATHER4(lt, n0, off)                                                                               \
    ((mcs_v4d){(lt)[2 * (n0)[0] + (off)], (lt)[2 * (n0)[1] + (off)], (lt)[2 * (n0)[2] + (off)],              \
               (lt)[2 * (n0)[3] + (off)]})

/* Both log tails by Lagrange through five and six nodes, four pixels at a
 * time: the pixels where the two agree to TAB_TOL, the smaller tail is
 * above e^-MAX_LOG_P and the statistic's rounding cannot move log p past
 * the bound of mcstat.h keep ok; p the p-value of the alternative, from
 * the exp of one log tail. */
static PIX_INLINE void block_interp(size_t k4, const var_consts *vc, var_block *bk)
{
    const double *lt = vc->lt;
    const mcs_v4d zero = vm_splat(0.0);
    for (size_t j = 0; j < k4; j += 4) {
        mcs_v4d v;
        mcs_v4i ok;
        memcpy(&v, bk->v + j, sizeof v);
        memcpy(&ok, bk->ok + j, sizeof ok);
        const int32_t *n0 = bk->n0 + j;
        mcs_v4d s = v - (mcs_v4d){(double)n0[0], (double)n0[1], (double)n0[2], (double)n0[3]};
        /* Lagrange's weights through nodes 0..5 (w6) and 0..4 (w5) at s */
        mcs_v4d d0 = s, d1 = s - 1.0, d2 = s - 2.0, d3 = s - 3.0, d4 = s - 4.0, d5 = s - 5.0;
        mcs_v4d p01 = d0 * d1, p012 = p01 * d2, p0123 = p012 * d3;
        mcs_v4d s45 = d4 * d5, s345 = d3 * s45, s2345 = d2 * s345, s34 = d3 * d4, s234 = d2 * s34;
        mcs_v4d w60 = d1 * s2345 * (-1.0 / 120), w61 = d0 * s2345 * (1.0 / 24), w62 = p01 * s345 * (-1.0 / 12);
        mcs_v4d w63 = p012 * s45 * (1.0 / 12), w64 = p0123 * d5 * (-1.0 / 24), w65 = p0123 * d4 * (1.0 / 120);
        mcs_v4d w50 = d1 * s234 * (1.0 / 24), w51 = d0 * s234 * (-1.0 / 6), w52 = p01 * s34 * (1.0 / 4);
        mcs_v4d w53 = p012 * d4 * (-1.0 / 6), w54 = p0123 * (1.0 / 24);
        mcs_v4d a0 = GATHER4(lt, n0, 0), a1 = GATHER4(lt + 2, n0, 0), a2 = GATHER4(lt + 4, n0, 0),
                a3 = GATHER4(lt + 6, n0, 0), a4 = GATHER4(lt + 8, n0, 0), a5 = GATHER4(lt + 10, n0, 0);
        mcs_v4d b0 = GATHER4(lt, n0, 1), b1 = GATHER4(lt + 2, n0, 1), b2 = GATHER4(lt + 4, n0, 1),
                b3 = GATHER4(lt + 6, n0, 1), b4 = GATHER4(lt + 8, n0, 1), b5 = GATHER4(lt + 10, n0, 1);
        mcs_v4d lp5 = w50 * a0 + w51 * a1 + w52 * a2 + w53 * a3 + w54 * a4;
        mcs_v4d lq5 = w50 * b0 + w51 * b1 + w52 * b2 + w53 * b3 + w54 * b4;
        mcs_v4d lp = w60 * a0 + w61 * a1 + w62 * a2 + w63 * a3 + w64 * a4 + w65 * a5;
        mcs_v4d lq = w60 * b0 + w61 * b1 + w62 * b2 + w63 * b3 + w64 * b4 + w65 * b5;
        mcs_v4i good = ok & (vm_fabs(lp - lp5) <= TAB_TOL) & (vm_fabs(lq - lq5) <= TAB_TOL);
        lp = vm_select(lp < 0.0, lp, zero);
        lq = vm_select(lq < 0.0, lq, zero);
        good &= (lp >= -MAX_LOG_P) & (lq >= -MAX_LOG_P);
        /* the side of the smaller tail: exp is increasing, so the logs
         * order the tails as their values do (where exp rounds two
         * different logs to one value, p is that value either way) */
        mcs_v4i low = vc->alternative == MCSTAT_LESS      ? (mcs_v4i){-1, -1, -1, -1}
                      : vc->alternative == MCSTAT_GREATER ? (mcs_v4i){0, 0, 0, 0}
                                                          : (mcs_v4i)(lp < lq);
        mcs_v4d logp = vm_select(low, lp, lq);
        mcs_v4d slope = vm_select(low, vm_fabs(a3 - a2), vm_fabs(b3 - b2)) * vc->inv_h;
        /* the statistic's own rounding moves log p by slope times it: it
         * must stay within the bound (mcstat.h), or the single call */
        good &= vc->steep * slope <= 0.5 * (3e-14 - 4e-16 * logp);
        mcs_v4d p = vm_exp4(vm_select(good, logp, zero));
        if (vc->alternative == MCSTAT_TWO_SIDED) {
            p = p + p;
            p = vm_select(p < 1.0, p, vm_splat(1.0));
        }
        memcpy(bk->p + j, &p, sizeof p);
        memcpy(bk->ok + j, &good, sizeof good);
        memcpy(bk->low + j, &low, sizeof low);
    }
}

/* The two vector passes, in the baseline and AVX2 builds (the same
 * operations in both: the same bits). */
static void block_vector_pass(size_t k4, const var_consts *vc, var_block *bk, int interp)
{
    if (interp)
        block_interp(k4, vc, bk);
    else
        block_coords(k4, vc, bk);
}

#if PIX_VAR_AVX2
__attribute__((target("avx2"))) static void block_vector_pass_avx2(size_t k4, const var_consts *vc, var_block *bk,
                                                                    int interp)
{
    if (interp)
        block_interp(k4, vc, bk);
    else
        block_coords(k4, vc, bk);
}
#endif

static void vector_pass(size_t k, const var_consts *vc, var_block *bk, int interp)
{
    size_t k4 = (k + 3) & ~(size_t)3;
#if PIX_VAR_AVX2
    if (mcstat__pixels_avx2()) {
        block_vector_pass_avx2(k4, vc, bk, interp);
        return;
    }
#endif
    block_vector_pass(k4, vc, bk, interp);
}

typedef struct {
    mcstat_dd mx[VBLOCK], my[VBLOCK];
    double m2x[VBLOCK], m2y[VBLOCK];
    unsigned char bx[VBLOCK], by[VBLOCK];
    var_block bk;
    double lt[2 * N_NODES];
    unsigned char known[N_NODES];
} var_work;

/* Whether the two-pass M2 of n values about `mean` keeps ~1e-15 of relative
 * accuracy: its rounding error is about n eps M2 + n^3 eps^2 mean^2. */
static int well_spread(double m2, mcstat_dd mean, size_t n)
{
    double dn = (double)n;
    return m2 > 0.0 && m2 * 0x1p50 >= dn * dn * dn * mean.hi * mean.hi;
}

int mcstat__pixels_var(int test, const mcstat_pixels_in *x, const mcstat_pixels_in *y, mcstat__work *wk,
                       size_t *first_index, double null_value, int alternative, double alpha, unsigned flags,
                       const mcstat_pixels_out *out, mcstat__pixel_fn single, void *ctx)
{
    const int two = test == MCSTAT_TEST_VAR_2, intervals = !(flags & MCSTAT_ROWS_NO_INTERVALS);
    const size_t nx = x->n, ny = two ? y->n : 0;
    const double df1 = (double)nx - 1.0, df2 = two ? (double)ny - 1.0 : 0.0;
    int first = MCSTAT_OK;
    size_t first_i = 0;
    int fast = nx >= 2 && (!two || ny >= 2) && df1 <= MAX_DF && df2 <= MAX_DF;
    double c0 = NAN, c1 = NAN;
    if (fast && intervals) { /* the single call's critical values, once */
        mcstat_qcache qc;
        mcstat__qcache_init(&qc);
        mcstat__qcache_use(&qc, two ? MCSTAT_Q_F : MCSTAT_Q_CHISQ, df1, df2);
        mcstat_result r;
        mcstat__result_clear(&r);
        r.test = test;
        r.alternative = alternative;
        r.alpha = alpha;
        mcstat_tails half = {0.5, 0.5, -M_LN2, -M_LN2, 0.0};
        if (mcstat__finish(&r, &half, mcstat__qcache_quantile, &qc))
            fast = 0;
        c0 = r.critical[0];
        c1 = r.critical[1];
        /* var_test.c's bounds are M2 / c for c normal or at the support's
         * end (0 or Inf); elsewhere it takes logarithms: the single call */
        int ends0 = alternative == MCSTAT_GREATER, ends1 = alternative == MCSTAT_LESS;
        if (!(ends0 || (c0 >= DBL_MIN && c0 <= DBL_MAX)) || !(ends1 || (c1 >= DBL_MIN && c1 <= DBL_MAX)))
            fast = 0;
    }
    var_work *w = fast ? calloc(1, sizeof *w) : NULL; /* ~350 KiB: not on a caller's thread stack */
    tail_table tb = {!two, df1, df2, two ? 1.0 : df1, 0.0, 0.0, NULL, NULL};
    if (w) {
        tb.h = sqrt(two ? 2.0 / df1 + 2.0 / df2 : 2.0 / df1) / STEPS;
        tb.inv_h = 1.0 / tb.h;
        tb.lt = w->lt;
        tb.known = w->known;
    }
    const var_consts vc = {tb.centre, tb.inv_h, (double)(nx + ny + 4) * DBL_EPSILON, alternative, tb.lt};
    const mcstat_pixels_out *o = out;
    size_t begin, end;
    while (mcstat__work_take(wk, &begin, &end))
    for (size_t i0 = begin; i0 < end; i0 += VBLOCK) {
        size_t k = end - i0 < VBLOCK ? end - i0 : VBLOCK;
        var_block *bk = w ? &w->bk : NULL;
        if (w) {
            mcstat__pixels_block_moments(x, i0, k, w->mx, w->m2x, w->bx);
            if (two)
                mcstat__pixels_block_moments(y, i0, k, w->my, w->m2y, w->by);
            for (size_t j = 0; j < k; j++) {
                int ok = !w->bx[j] && well_spread(w->m2x[j], w->mx[j], nx) &&
                         (!two || (!w->by[j] && well_spread(w->m2y[j], w->my[j], ny)));
                double est, stat;
                if (two) {
                    est = (w->m2x[j] / df1) / (w->m2y[j] / df2);
                    stat = est / null_value;
                } else {
                    est = w->m2x[j] / df1;
                    stat = w->m2x[j] / null_value;
                }
                ok = ok && stat >= DBL_MIN && stat <= DBL_MAX;
                bk->est[j] = est;
                bk->stat[j] = ok ? stat : tb.centre;
                bk->ok[j] = ok ? -1 : 0;
            }
            for (size_t j = k; j < VBLOCK && (j & 3); j++) {
                bk->stat[j] = tb.centre;
                bk->ok[j] = 0;
            }
            vector_pass(k, &vc, bk, 0);
            /* the six nodes about each coordinate, solved where first needed */
            for (size_t j = 0; j < k || (j < VBLOCK && (j & 3)); j++) {
                int ok = j < k && bk->ok[j];
                int n0 = 0;
                double v = bk->v[j];
                if (ok && v >= 2.0 && v < (double)(N_NODES - 4)) {
                    n0 = (int)v - 2;
                    ok = table_nodes6(&tb, n0);
                } else {
                    ok = 0;
                }
                if (!ok) {
                    n0 = 0;
                    bk->v[j] = 2.0;
                }
                bk->n0[j] = n0;
                bk->ok[j] = ok ? -1 : 0;
            }
            vector_pass(k, &vc, bk, 1);
        }
        if (bk) { /* every pixel's outputs, field by field; single() then rewrites those not ok */
            for (size_t j = 0; j < k; j++) {
                int ok = bk->ok[j] != 0;
                double num = two ? bk->est[j] : w->m2x[j];
                double lo = intervals && ok ? num / c1 : NAN, hi = intervals && ok ? num / c0 : NAN;
                if (ok && intervals && !((lo == 0.0 && c1 == INFINITY) || (lo >= DBL_MIN && lo <= DBL_MAX)))
                    ok = 0;
                if (ok && intervals && !((hi == INFINITY && c0 == 0.0) || (hi >= DBL_MIN && hi <= DBL_MAX)))
                    ok = 0;
                bk->ok[j] = ok;
                bk->lo[j] = lo;
                bk->hi[j] = hi;
                bk->dec[j] = (int8_t)(bk->p[j] <= alpha ? (bk->low[j] ? MCSTAT_DECISION_LESS : MCSTAT_DECISION_GREATER)
                                                        : MCSTAT_DECISION_EQUAL);
            }
#define FILL(field, v)                                                                                             \
    do {                                                                                                           \
        if (o->field)                                                                                              \
            for (size_t j = 0; j < k; j++)                                                                         \
                o->field[i0 + j] = (v);                                                                            \
    } while (0)
            FILL(p_value, bk->p[j]);
            FILL(statistic, bk->stat[j]);
            FILL(df, df1);
            FILL(df2, two ? df2 : NAN);
            FILL(estimate, bk->est[j]);
            FILL(estimate2, NAN);
            FILL(std_error, NAN);
            FILL(conf_lo, bk->lo[j]);
            FILL(conf_hi, bk->hi[j]);
            FILL(critical_lo, intervals ? c0 : NAN);
            FILL(critical_hi, intervals ? c1 : NAN);
            FILL(status, MCSTAT_OK);
            FILL(decision, bk->dec[j]);
            FILL(n_x, (uint64_t)nx);
            FILL(n_y, (uint64_t)ny);
#undef FILL
        }
        for (size_t j = 0; j < k; j++)
            if (!bk || !bk->ok[j]) {
                int st = single(ctx, i0 + j);
                if (st && first == MCSTAT_OK) {
                    first = st;
                    first_i = i0 + j;
                }
            }
    }
    free(w);
    *first_index = first_i;
    return first;
}
