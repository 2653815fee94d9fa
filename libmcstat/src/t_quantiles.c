/*
 * t_quantiles.c - t quantiles on the fast tail (pixels_dist.c): Halley's
 * method for one df, the per-call table of quantiles in 1/df that the
 * per-pixel tests' critical values are interpolated from (pixels.c), and
 * mcstat_t_quantiles, that table as a function of its own.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "pixels.h"

#include <stdlib.h>

/* ---- one quantile ---------------------------------------------------------- */

/* The upper p-quantile of t(df) (0 < p < 1/2) by Halley's method in
 * z = log t on the fast tail: with g = log P[T > t] - log p,
 *   g' = -K/P,  g'' = g' (1 - (df+1) y + K/P),  y = t^2/(df+t^2),
 * (K = t f(t), d log K/dz = 1 - (df+1) y).  Started from Cornish-Fisher
 * (A&S 26.7.5, three terms), whose error of 1e-3..1e-5 at df >= 3 the cubic
 * convergence takes to rounding in two steps; it stops after a step below
 * 1e-6 (the error left is of the order of its cube).  pf is df's prefactor,
 * NULL to compute it.  Falls back to mcstat_t_quantile where the fast tail
 * does not apply or the iteration wanders. */
/* Near the centre (p -> 1/2) the quantile is the tail's absolute error
 * over the density, no longer small relative to itself: there, and for
 * p below 1e-100, mcstat_t_quantile answers. */
static int quantile_ok(double p, double df)
{
    return p >= 1e-100 && p <= 0.25 && df >= 1.0 && df <= 1000.0;
}

/* start: a starting value, NaN for Cornish-Fisher's. */
static int t_upper_quantile(double p, double df, const t_prefactor *pf, double start, double *q)
{
    if (quantile_ok(p, df)) {
        t_prefactor own;
        if (!pf) {
            t_prefactor_init(df, &own);
            pf = &own;
        }
        double t = start;
        if (!(t > 0.0)) {
            double g = mcstat__norm_quantile(p, 1), g2 = g * g, v = 1.0 / df;
            t = g + v * (g * (g2 + 1.0) / 4.0 +
                         v * (g * ((5.0 * g2 + 16.0) * g2 + 3.0) / 96.0 +
                              v * (g * (((3.0 * g2 + 19.0) * g2 + 17.0) * g2 - 15.0) / 384.0)));
        }
        double lp = log(p);
        if (t > 0.0 && isfinite(t)) {
            double z = log(t);
            for (int it = 0; it < 30; it++) {
                double u, o, k, at = exp(z);
                if (!fast_range(at, df) || !mcstat__t_tail_core(at, pf, &u, &o, &k) || !(u > 0.0))
                    break;
                double h = log(u) - lp, kp = k / u, y = at * at / (df + at * at);
                double d1 = -kp, d2 = d1 * (1.0 - (df + 1.0) * y + kp);
                double step = -h / d1;
                double den = 1.0 + 0.5 * step * d2 / d1; /* Halley: -h / (d1 - h d2 / (2 d1)) */
                if (den > 0.5)
                    step /= den;
                if (!isfinite(step))
                    break;
                step = fmax(-2.0, fmin(2.0, step));
                z += step;
                if (fabs(step) < 1e-6) {
                    *q = exp(z);
                    return MCSTAT_OK;
                }
            }
        }
    }
    return mcstat_t_quantile(p, df, 1, q);
}

int mcstat__t_upper_quantile_fast(double p, double df, double *q)
{
    return t_upper_quantile(p, df, NULL, NAN, q);
}

/* ---- the critical values' table ---------------------------------------------- */

/* The per-call table of critical values at level p in qt[0..n], empty
 * (NaN: solved when first needed). */
void mcstat__qt_table_init(mcstat__qt_table *c, double p, double *qt, int n)
{
    c->qt_p = p;
    c->qt = qt;
    c->qt_n = n;
    for (int j = 0; j <= n; j++)
        qt[j] = NAN;
}

/* Node j of the table: the quantile at df = qt_n / j, solved once per
 * call when first needed (node 0 is df = Inf, the normal quantile); the
 * same numbers whichever pixels ask, so pixel ranges do not change results. */
static double qt_node(mcstat__qt_table *c, int j)
{
    if (isnan(c->qt[j])) {
        double q = NAN;
        if (j == 0)
            q = mcstat__norm_quantile(c->qt_p, 1);
        else if (t_upper_quantile(c->qt_p, (double)c->qt_n / j, NULL, NAN, &q))
            q = NAN;
        c->qt[j] = q;
    }
    return c->qt[j];
}

/* The quantile at df from the table: Lagrange through the six nearest
 * nodes in u = qt_n/df (the quantile is smooth in 1/df: its
 * Cornish-Fisher series is one in 1/df).  *exact is set where the five- and
 * six-point values agree to 1e-13, i.e. where the six-point one is good to
 * rounding (measured against SciPy over df in [1, 1000]: within 1.4e-15 at
 * p = 0.025, 0.005, 1e-4, 5e-7); elsewhere it is only Halley's starting
 * value.  NaN where a node failed (Cornish-Fisher starts then). */
static double qt_interp(mcstat__qt_table *c, double df, int *exact)
{
    *exact = 0;
    if (!quantile_ok(c->qt_p, df))
        return NAN;
    const int n = c->qt_n;
    double u = n / df;
    int k = (int)u - 2;
    k = k < 0 ? 0 : k > n - 5 ? n - 5 : k;
    double q[6], v5, v6;
    for (int i = 0; i < 6; i++)
        q[i] = qt_node(c, k + i);
    lagrange56(q, u - k, &v5, &v6);
    *exact = fabs(v6 - v5) < 1e-13 * fabs(v6);
    return v6;
}

/* The critical values (c0, c1) of t(df) for the alternative, as
 * mcstat__finish asks them: two-sided -+q(alpha/2); "less" -q(alpha), +Inf;
 * "greater" -Inf, q(alpha). */
int mcstat__qt_criticals(mcstat__qt_table *c, double df, const t_prefactor *pf, double *c0, double *c1)
{
    double q;
    int st;
    if (c->alternative == MCSTAT_TWO_SIDED) {
        if (df != c->crit_df) { /* equal df (equal variances' ratio) repeat in flat regions */
            int exact;
            q = qt_interp(c, df, &exact);
            if (!exact && (st = t_upper_quantile(c->qt_p, df, pf, q, &q)))
                return st;
            c->crit_two = q;
            c->crit_df = df;
        }
        *c0 = -c->crit_two;
        *c1 = c->crit_two;
        return MCSTAT_OK;
    }
    int exact;
    q = qt_interp(c, df, &exact);
    if (!exact && (st = t_upper_quantile(c->qt_p, df, pf, q, &q)))
        return st;
    if (c->alternative == MCSTAT_LESS) {
        *c0 = -q;
        *c1 = INFINITY;
    } else {
        *c0 = -INFINITY;
        *c1 = q;
    }
    return MCSTAT_OK;
}

/* The table's nodes each pixel needs (solved lazily, one pixel at a time),
 * for pixels.c's block bounds and mcstat_t_quantiles' interpolation. */
void mcstat__qt_table_nodes(mcstat__qt_table *c, size_t k, const double *df, const unsigned char *want,
                            double (*qn)[PIX_BLOCK], double *qs)
{
    const int n = c->qt_n;
    for (size_t j = 0; j < k; j++) {
        int have = (!want || want[j]) && quantile_ok(c->qt_p, df[j]);
        int n0 = have ? (int)(n / df[j]) - 2 : 0;
        n0 = n0 < 0 ? 0 : n0 > n - 5 ? n - 5 : n0;
        for (int i = 0; i < 6; i++)
            qn[i][j] = have ? qt_node(c, n0 + i) : NAN; /* NaN: no value here */
        qs[j] = have ? n / df[j] - n0 : 0.0;
    }
}

/* ---- t quantiles for many df ------------------------------------------
 * The pixel path's critical values as a function of their own: the same
 * kind of per-call table (mcstat__qt_criticals with the alternative "greater" gives
 * the upper p-quantile), interpolated PIX_BLOCK values at a time in a loop
 * that vectorises, Halley (mcstat__qt_criticals) where the five- and six-point values
 * disagree; levels outside the table's range go to mcstat_t_quantile one
 * value at a time.
 *
 * The table's density follows the level: the quantile grows like
 * p^(-1/df), so its derivatives in u = 1/df grow with a = log(1/p), and the
 * interpolation holds to rounding while the step h keeps h a below ~0.005
 * (measured against mcstat_t_quantile over df in [1, 1000]: at 1024 nodes
 * every df interpolates at p = 0.025 but 37-80% of df below 30 need Halley
 * at 1e-4 and all do at 3e-9; at 4096 none do at 3e-9, at 8192 none at
 * 1e-20).  So: the power of two >= 200 a, at least QT_NODES. */
#define QT_MANY_MAX 65536 /* a = 327: p = 1e-142, below quantile_ok's 1e-100 */

static int many_nodes(double p)
{
    double a = -log(p);
    int n = QT_NODES;
    while (n < QT_MANY_MAX && n < 200.0 * a)
        n *= 2;
    return n;
}

typedef struct {
    mcstat__qt_table c;
    double qn[6][PIX_BLOCK], qs[PIX_BLOCK], v[PIX_BLOCK];
    long long exact[PIX_BLOCK]; /* 64 bits, as the doubles: the loop vectorises */
    double qt[];
} many_work;

static PIX_INLINE void many_interp(size_t k, many_work *w)
{
    for (size_t j = 0; j < k; j++) {
        double q[6], v5, v6;
        for (int i = 0; i < 6; i++)
            q[i] = w->qn[i][j];
        lagrange56(q, w->qs[j], &v5, &v6);
        w->v[j] = v6;
        w->exact[j] = fabs(v6 - v5) < 1e-13 * fabs(v6); /* false where a node is NaN */
    }
}

static void many_interp_pass(size_t k, many_work *w)
{
    many_interp(k, w);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void many_interp_pass_avx2(size_t k, many_work *w)
{
    many_interp(k, w);
}
#endif

int mcstat_t_quantiles(double p, const double *df, size_t n, int upper, double *x)
{
    MCSTAT_IEEE_SCOPE();
    if (!(p >= 0.0 && p <= 1.0) || (n > 0 && (!df || !x)))
        return MCSTAT_EINVAL;
    many_work *w = NULL;
    if (quantile_ok(p, 1.0) && n > 16) { /* a short array does not pay for the table */
        int nodes = many_nodes(p);
        w = malloc(sizeof *w + (size_t)(nodes + 1) * sizeof(double));
        if (w) {
            w->c.alternative = MCSTAT_GREATER;
            mcstat__qt_table_init(&w->c, p, w->qt, nodes);
        }
    }
#if PIX_AVX2
    int avx2 = mcstat__pixels_avx2();
#endif
    int first = MCSTAT_OK;
    for (size_t i0 = 0; i0 < n; i0 += PIX_BLOCK) {
        size_t k = n - i0 < PIX_BLOCK ? n - i0 : PIX_BLOCK;
        if (w) {
            mcstat__qt_table_nodes(&w->c, k, df + i0, NULL, w->qn, w->qs);
#if PIX_AVX2
            if (avx2)
                many_interp_pass_avx2(k, w);
            else
#endif
                many_interp_pass(k, w);
        }
        for (size_t j = 0; j < k; j++) {
            double q = NAN, c0, c1;
            int st = MCSTAT_OK;
            if (w && w->exact[j]) {
                q = upper ? w->v[j] : -w->v[j];
            } else if (w) {
                st = mcstat__qt_criticals(&w->c, df[i0 + j], NULL, &c0, &c1);
                q = upper ? c1 : -c1; /* t is symmetric: the lower p-quantile is minus the upper */
            } else {
                st = mcstat_t_quantile(p, df[i0 + j], upper, &q);
            }
            if (st) {
                q = NAN;
                if (first == MCSTAT_OK)
                    first = st;
            }
            x[i0 + j] = q;
        }
    }
    free(w);
    return first;
}
