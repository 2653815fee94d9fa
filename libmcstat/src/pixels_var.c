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

#include <float.h>
#include <stdlib.h>

#define VBLOCK 256   /* pixels per block (mcstat__pixels_block_moments' limit) */
#define STEPS 512    /* table points per standard deviation of u */
#define SPAN 20      /* standard deviations each side of the centre */
#define MID (STEPS * SPAN)
#define N_NODES (2 * MID + 1)
#define MAX_DF 1000.0
#define MAX_LOG_P 200.0 /* |log| of the smaller tail the table answers */
#define TAB_TOL 2e-15   /* largest |v6 - v5| of a log tail taken from the table */

typedef struct {
    int chisq;
    double df1, df2, centre, h, inv_h;
    double *lt;           /* log lower tail at 2j, log upper at 2j + 1; +Inf: unusable */
    unsigned char *known; /* known[j]: point j solved (calloc'd: untouched pages cost nothing) */
} tail_table;

static int table_node(tail_table *tb, int j, double *lp, double *lq)
{
    double *v = tb->lt + 2 * j;
    if (!tb->known[j]) {
        tb->known[j] = 1;
        double s = tb->centre * exp((double)(j - MID) * tb->h);
        mcstat_tails t;
        int st = tb->chisq ? mcstat__chisq_tails(s, tb->df1, &t) : mcstat__f_tails(s, tb->df1, tb->df2, &t);
        if (st || !isfinite(t.logp) || !isfinite(t.logq) || !(s > 0.0) || !isfinite(s)) {
            v[0] = v[1] = INFINITY;
        } else {
            v[0] = t.logp;
            v[1] = t.logq;
        }
    }
    *lp = v[0];
    *lq = v[1];
    return isfinite(v[0]);
}

/* Lagrange's weights through points 0..4 (w5) and 0..5 (w6) at s, as
 * pixels.c's lagrange56 forms them: both tails share them. */
static void weights56(double s, double *w5, double *w6)
{
    double d0 = s, d1 = s - 1.0, d2 = s - 2.0, d3 = s - 3.0, d4 = s - 4.0, d5 = s - 5.0;
    double p01 = d0 * d1, p012 = p01 * d2, p0123 = p012 * d3;
    double s45 = d4 * d5, s345 = d3 * s45, s2345 = d2 * s345, s34 = d3 * d4, s234 = d2 * s34;
    w6[0] = d1 * s2345 * (-1.0 / 120);
    w6[1] = d0 * s2345 * (1.0 / 24);
    w6[2] = p01 * s345 * (-1.0 / 12);
    w6[3] = p012 * s45 * (1.0 / 12);
    w6[4] = p0123 * d5 * (-1.0 / 24);
    w6[5] = p0123 * d4 * (1.0 / 120);
    w5[0] = d1 * s234 * (1.0 / 24);
    w5[1] = d0 * s234 * (-1.0 / 6);
    w5[2] = p01 * s34 * (1.0 / 4);
    w5[3] = p012 * d4 * (-1.0 / 6);
    w5[4] = p0123 * (1.0 / 24);
}

/* Both tails at statistic s from the table, their logs, and the slopes of
 * the logs in log s; 0 where it does not answer. */
static int table_tails(tail_table *tb, double s, double *lower, double *upper, double *log_lower,
                       double *log_upper, double *slope_lower, double *slope_upper)
{
    if (!(s >= DBL_MIN && s <= DBL_MAX))
        return 0;
    double v = log(s / tb->centre) * tb->inv_h + MID;
    if (!(v >= 2.0 && v < (double)(N_NODES - 4)))
        return 0;
    int n0 = (int)v - 2;
    double qp[6], qq[6];
    for (int i = 0; i < 6; i++)
        if (!table_node(tb, n0 + i, &qp[i], &qq[i]))
            return 0;
    double w5[5], w6[6], p5 = 0.0, q5 = 0.0, p6 = 0.0, q6 = 0.0;
    weights56(v - n0, w5, w6);
    for (int i = 0; i < 5; i++) {
        p5 += w5[i] * qp[i];
        q5 += w5[i] * qq[i];
    }
    for (int i = 0; i < 6; i++) {
        p6 += w6[i] * qp[i];
        q6 += w6[i] * qq[i];
    }
    if (!(fabs(p6 - p5) <= TAB_TOL && fabs(q6 - q5) <= TAB_TOL))
        return 0;
    p6 = p6 < 0.0 ? p6 : 0.0;
    q6 = q6 < 0.0 ? q6 : 0.0;
    if (!(p6 >= -MAX_LOG_P && q6 >= -MAX_LOG_P))
        return 0;
    *lower = exp(p6);
    *upper = exp(q6);
    *log_lower = p6;
    *log_upper = q6;
    *slope_lower = fabs(qp[3] - qp[2]) * tb->inv_h;
    *slope_upper = fabs(qq[3] - qq[2]) * tb->inv_h;
    return 1;
}

typedef struct {
    mcstat_dd mx[VBLOCK], my[VBLOCK];
    double m2x[VBLOCK], m2y[VBLOCK];
    unsigned char bx[VBLOCK], by[VBLOCK];
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

int mcstat__pixels_var(int test, const mcstat_pixels_in *x, const mcstat_pixels_in *y, size_t begin, size_t end,
                       double null_value, int alternative, double alpha, unsigned flags,
                       const mcstat_pixels_out *out, mcstat__pixel_fn single, void *ctx)
{
    const int two = test == MCSTAT_TEST_VAR_2, intervals = !(flags & MCSTAT_ROWS_NO_INTERVALS);
    const size_t nx = x->n, ny = two ? y->n : 0;
    const double df1 = (double)nx - 1.0, df2 = two ? (double)ny - 1.0 : 0.0;
    int first = MCSTAT_OK;
    int fast = nx >= 2 && (!two || ny >= 2) && df1 <= MAX_DF && df2 <= MAX_DF && end > begin;
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
    const mcstat_pixels_out *o = out;
    for (size_t i0 = begin; i0 < end; i0 += VBLOCK) {
        size_t k = end - i0 < VBLOCK ? end - i0 : VBLOCK;
        if (w) {
            mcstat__pixels_block_moments(x, i0, k, w->mx, w->m2x, w->bx);
            if (two)
                mcstat__pixels_block_moments(y, i0, k, w->my, w->m2y, w->by);
        }
        for (size_t j = 0; j < k; j++) {
            const size_t i = i0 + j;
            double est = NAN, stat = NAN, lower = NAN, upper = NAN;
            int ok = w && !w->bx[j] && well_spread(w->m2x[j], w->mx[j], nx) &&
                     (!two || (!w->by[j] && well_spread(w->m2y[j], w->my[j], ny)));
            if (ok) {
                if (two) {
                    est = (w->m2x[j] / df1) / (w->m2y[j] / df2);
                    stat = est / null_value;
                } else {
                    est = w->m2x[j] / df1;
                    stat = w->m2x[j] / null_value;
                }
                double sl, su, ll, lu;
                ok = table_tails(&tb, stat, &lower, &upper, &ll, &lu, &sl, &su);
                /* the statistic's own rounding, up to (nx + ny + 4) eps relative
                 * from the two-pass moments, moves log p by slope times that:
                 * it must stay within the bound (mcstat.h), or the single call */
                int low = alternative == MCSTAT_LESS || (alternative == MCSTAT_TWO_SIDED && lower < upper);
                double slope = low ? sl : su, logp = low ? ll : lu;
                if (ok && (double)(nx + ny + 4) * DBL_EPSILON * slope > 0.5 * (3e-14 - 4e-16 * logp))
                    ok = 0;
            }
            double num = two ? est : ok ? w->m2x[j] : NAN;
            double lo = intervals && ok ? num / c1 : NAN, hi = intervals && ok ? num / c0 : NAN;
            if (ok && intervals && !((lo == 0.0 && c1 == INFINITY) || (lo >= DBL_MIN && lo <= DBL_MAX)))
                ok = 0;
            if (ok && intervals && !((hi == INFINITY && c0 == 0.0) || (hi >= DBL_MIN && hi <= DBL_MAX)))
                ok = 0;
            if (!ok) {
                int st = single(ctx, i);
                if (st && first == MCSTAT_OK)
                    first = st;
                continue;
            }
            int low_side = alternative == MCSTAT_LESS || (alternative == MCSTAT_TWO_SIDED && lower < upper);
            double p = alternative == MCSTAT_LESS      ? lower
                       : alternative == MCSTAT_GREATER ? upper
                                                       : fmin(1.0, 2.0 * (low_side ? lower : upper));
            int dec = p <= alpha ? (low_side ? MCSTAT_DECISION_LESS : MCSTAT_DECISION_GREATER) : MCSTAT_DECISION_EQUAL;
#define PUT(field, v)                                                                                              \
    do {                                                                                                           \
        if (o->field)                                                                                              \
            o->field[i] = (v);                                                                                     \
    } while (0)
            PUT(p_value, p);
            PUT(statistic, stat);
            PUT(df, df1);
            PUT(df2, two ? df2 : NAN);
            PUT(estimate, est);
            PUT(estimate2, NAN);
            PUT(std_error, NAN);
            PUT(conf_lo, lo);
            PUT(conf_hi, hi);
            PUT(critical_lo, intervals ? c0 : NAN);
            PUT(critical_hi, intervals ? c1 : NAN);
            PUT(status, MCSTAT_OK);
            PUT(decision, (int8_t)dec);
            PUT(n_x, (uint64_t)nx);
            PUT(n_y, (uint64_t)ny);
#undef PUT
        }
    }
    free(w);
    return first;
}
