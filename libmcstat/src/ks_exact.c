/*
 * ks_exact.c - the exact permutation distribution of the two-sample K-S
 * statistic, unweighted or with Canner's weight, conditional on ties.
 *
 * Under H0 every arrangement of the nx + ny labels over the pooled order is
 * equally likely.  Read left to right, the arrangement is a lattice path
 * from (0, 0) to (m, n) (m the smaller sample, indexed by i, so memory is
 * O(min(nx, ny))), and the labels are drawn without replacement: from a
 * point with i of m and s - i of n used, the next label is from the smaller
 * sample with probability (m - i)/(N - s).  The recursion therefore carries
 * probabilities, not path counts, and cannot overflow (R's path counts with
 * ties overflow past N ~ 1030 and fall back to simulation).
 *
 * The statistic is looked at only at the end of a tie block (every step when
 * there are no ties), and only where 0 < s < N.  There the points whose
 * value reaches the threshold are absorbed: their probability is added to
 * the p-value and removed from the chain.  The p-value is thus a sum of
 * positive first-passage probabilities, never 1 - P, and keeps its relative
 * accuracy (about N * 2^-52) however small it is, down to the 2^-1000 below
 * which the band's edges are trimmed.  On each anti-diagonal the points that
 * reach the threshold are two tails of i (both convex conditions in u =
 * i N - s m), found from a floating-point guess corrected by exact integer
 * comparisons of u^2 q_t against u_t^2 q (128-bit), so a path through a
 * point equal in value to the observed one is always counted.
 *
 * Work: (m + 1)(N + 1) multiply-adds at most, fewer as the band of live
 * points narrows; vectorised, about 1 ns per cell (bench/RESULTS_ks.md).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <stdlib.h>

#define TRIM 0x1p-1000 /* live probabilities below this are dropped (no subnormals) */

typedef struct {
    const mcstat__ks_data *d;
    uint64_t m, n, N;
    int weight;
    int hi_side, lo_side; /* reject u >= t (hi) and u <= -t (lo), u = i N - s m */
    double *a;            /* a[i] = m - i + 1 */
    double *idx;          /* idx[i] = i */
    double *buf;          /* two vectors of m + 3 */
} dp_ctx;

int mcstat__ks_exact_check(const mcstat__ks_data *d)
{
    uint64_t m = d->n1 < d->n2 ? d->n1 : d->n2, n = d->n1 + d->n2 - m;
    double work = ((double)m + 1.0) * ((double)d->N + 1.0);
    /* the exact comparisons need (m n)^2 * N^2/4 < 2^127 */
    double lb = 2.0 * log2((double)m * (double)n) + 2.0 * log2((double)d->N) - 2.0;
    if (work > MCSTAT_KS_EXACT_MAX_WORK || lb > 126.0)
        return MCSTAT_ETOOBIG;
    return MCSTAT_OK;
}

static void ctx_free(dp_ctx *c)
{
    free(c->a);
    c->a = NULL;
}

static int ctx_init(dp_ctx *c, const mcstat__ks_data *d)
{
    c->d = d;
    c->weight = d->weight;
    int swapped = d->n1 > d->n2;
    c->m = swapped ? d->n2 : d->n1;
    c->n = swapped ? d->n1 : d->n2;
    c->N = d->N;
    /* u in DP coordinates is -u of the data when the samples are swapped */
    int want_hi = d->alternative != MCSTAT_LESS, want_lo = d->alternative != MCSTAT_GREATER;
    c->hi_side = swapped ? want_lo : want_hi;
    c->lo_side = swapped ? want_hi : want_lo;
    size_t len = (size_t)c->m + 3;
    c->a = malloc(4 * len * sizeof(double));
    if (!c->a)
        return MCSTAT_ENOMEM;
    c->idx = c->a + len;
    c->buf = c->idx + len;
    for (size_t i = 0; i < len; i++) {
        c->a[i] = (double)c->m - (double)i + 1.0;
        c->idx[i] = (double)i;
    }
    return MCSTAT_OK;
}

/* Does point i of anti-diagonal s reach t on the given side? */
static int reaches(const dp_ctx *c, uint64_t s, int64_t i, int side, mcstat__ks_point t)
{
    int64_t u = i * (int64_t)c->N - (int64_t)(s * c->m);
    if (side > 0 ? u <= 0 : u >= 0)
        return 0;
    mcstat__ks_point p = {(uint64_t)(u < 0 ? -u : u), s * (c->N - s)};
    return mcstat__ks_point_cmp(c->weight, p, t) >= 0;
}

/* On anti-diagonal s (points imin..imax), the points reaching t are i <= *ilo
 * and i >= *ihi (*ilo = imin - 1, *ihi = imax + 1 when there are none). */
static void tails(const dp_ctx *c, uint64_t s, mcstat__ks_point t, int64_t imin, int64_t imax, int64_t *ilo,
                  int64_t *ihi)
{
    double R = c->weight == MCSTAT_KS_WEIGHT_NONE ? (double)t.u
                                                  : (double)t.u * sqrt((double)(s * (c->N - s)) / (double)t.q);
    double centre = (double)s * (double)c->m, N = (double)c->N;
    int64_t i;
    if (c->hi_side) {
        double g = ceil((centre + R) / N);
        i = g < (double)imin ? imin : g > (double)(imax + 1) ? imax + 1 : (int64_t)g;
        while (i > imin && reaches(c, s, i - 1, 1, t))
            i--;
        while (i <= imax && !reaches(c, s, i, 1, t))
            i++;
        *ihi = i;
    } else {
        *ihi = imax + 1;
    }
    if (c->lo_side) {
        double g = floor((centre - R) / N);
        i = g < (double)(imin - 1) ? imin - 1 : g > (double)imax ? imax : (int64_t)g;
        while (i < imax && reaches(c, s, i + 1, -1, t))
            i++;
        while (i >= imin && !reaches(c, s, i, -1, t))
            i--;
        *ilo = i;
    } else {
        *ilo = imin - 1;
    }
}

static double sf(const dp_ctx *c, mcstat__ks_point t)
{
    if (t.u == 0)
        return 1.0;
    const uint64_t m = c->m, n = c->n, N = c->N;
    const uint64_t *ends = c->d->ends;
    const size_t len = (size_t)m + 3;
    double *restrict cur = c->buf + 1, *restrict nxt = c->buf + len + 1;
    const double *restrict a = c->a, *restrict idx = c->idx;
    cur[-1] = 0.0;
    cur[0] = 1.0;
    cur[1] = 0.0;
    int64_t lo = 0, hi = 0;
    double absorbed = 0.0;
    size_t k = 0;
    for (uint64_t s = 0; s < N; s++) {
        /* step s -> s + 1: into i from (i-1, s) by a label of the smaller
         * sample, w.p. (m - i + 1)/(N - s), or from (i, s) by one of the
         * larger, w.p. (n - (s - i))/(N - s) */
        const double inv = 1.0 / (double)(N - s), cn = (double)n - (double)s;
        int64_t nlo = lo, nhi = hi + 1 > (int64_t)m ? (int64_t)m : hi + 1;
        if ((int64_t)(s + 1) - (int64_t)n > nlo)
            nlo = (int64_t)(s + 1) - (int64_t)n;
        for (int64_t i = nlo; i <= nhi; i++)
            nxt[i] = (cur[i - 1] * a[i] + cur[i] * (idx[i] + cn)) * inv;
        nxt[nlo - 1] = 0.0;
        nxt[nhi + 1] = 0.0;
        double *t_ = cur;
        cur = nxt;
        nxt = t_;
        lo = nlo;
        hi = nhi;
        const uint64_t s1 = s + 1;
        int end = 1;
        if (ends) {
            end = ends[k] == s1;
            k += end;
        }
        if (end && s1 < N) {
            int64_t imin = s1 > n ? (int64_t)(s1 - n) : 0, imax = s1 < m ? (int64_t)s1 : (int64_t)m;
            int64_t ilo, ihi;
            tails(c, s1, t, imin, imax, &ilo, &ihi);
            for (; lo <= hi && lo <= ilo; lo++) {
                absorbed += cur[lo];
                cur[lo] = 0.0;
            }
            for (; hi >= lo && hi >= ihi; hi--) {
                absorbed += cur[hi];
                cur[hi] = 0.0;
            }
        }
        while (lo <= hi && cur[lo] < TRIM)
            cur[lo++] = 0.0;
        while (hi >= lo && cur[hi] < TRIM)
            cur[hi--] = 0.0;
        if (lo > hi)
            break; /* every path has reached t */
    }
    return absorbed > 1.0 ? 1.0 : absorbed;
}

int mcstat__ks_exact_sf(const mcstat__ks_data *d, mcstat__ks_point t, double *p)
{
    dp_ctx c;
    int st = ctx_init(&c, d);
    if (st)
        return st;
    *p = sf(&c, t);
    ctx_free(&c);
    return MCSTAT_OK;
}

/* ---- critical value: the largest attainable c with P(key >= c) > alpha ---- */

static int is_end(const mcstat__ks_data *d, uint64_t s, size_t *k)
{
    if (!d->ends)
        return 1;
    while (d->ends[*k] < s)
        (*k)++;
    return d->ends[*k] == s;
}

/* The smallest attainable point >= t (> t when strict) on the tested sides;
 * returns 0 when there is none. */
static int next_point(const dp_ctx *c, mcstat__ks_point t, int strict, mcstat__ks_point *out)
{
    const uint64_t m = c->m, n = c->n, N = c->N;
    int found = 0;
    size_t k = 0;
    mcstat__ks_point best = {0, 1};
    for (uint64_t s = 1; s < N; s++) {
        if (!is_end(c->d, s, &k))
            continue;
        int64_t imin = s > n ? (int64_t)(s - n) : 0, imax = s < m ? (int64_t)s : (int64_t)m;
        int64_t ilo, ihi;
        tails(c, s, t, imin, imax, &ilo, &ihi);
        uint64_t q = s * (N - s);
        for (int side = 0; side < 2; side++) {
            int64_t i = side ? ihi : ilo;
            if (side ? i > imax : i < imin)
                continue;
            int64_t u = i * (int64_t)N - (int64_t)(s * m);
            mcstat__ks_point p = {(uint64_t)(u < 0 ? -u : u), c->weight == MCSTAT_KS_WEIGHT_NONE ? 1 : q};
            if (strict && mcstat__ks_point_cmp(c->weight, p, t) == 0) {
                /* the next point outwards is strictly larger */
                i += side ? 1 : -1;
                if (side ? i > imax : i < imin)
                    continue;
                u = i * (int64_t)N - (int64_t)(s * m);
                p.u = (uint64_t)(u < 0 ? -u : u);
            }
            if (!found || mcstat__ks_point_cmp(c->weight, p, best) < 0) {
                best = p;
                found = 1;
            }
        }
    }
    *out = best;
    return found;
}

/* The largest attainable point (on the tested sides). */
static mcstat__ks_point max_point(const dp_ctx *c)
{
    const uint64_t m = c->m, n = c->n, N = c->N;
    size_t k = 0;
    mcstat__ks_point best = {0, 1};
    for (uint64_t s = 1; s < N; s++) {
        if (!is_end(c->d, s, &k))
            continue;
        int64_t imin = s > n ? (int64_t)(s - n) : 0, imax = s < m ? (int64_t)s : (int64_t)m;
        uint64_t q = c->weight == MCSTAT_KS_WEIGHT_NONE ? 1 : s * (N - s);
        int64_t uh = imax * (int64_t)N - (int64_t)(s * m), ul = imin * (int64_t)N - (int64_t)(s * m);
        if (c->hi_side && uh > 0) {
            mcstat__ks_point p = {(uint64_t)uh, q};
            if (mcstat__ks_point_cmp(c->weight, p, best) > 0)
                best = p;
        }
        if (c->lo_side && ul < 0) {
            mcstat__ks_point p = {(uint64_t)-ul, q};
            if (mcstat__ks_point_cmp(c->weight, p, best) > 0)
                best = p;
        }
    }
    return best;
}

/* A point of value near v (a guide only; exactness comes from snapping). */
static mcstat__ks_point near_value(const dp_ctx *c, double v)
{
    /* Converting a double outside [0, 2^64) to uint64_t is undefined: a NaN
     * or negative guess becomes 0, a huge one 2^62 (points have u < 2^63). */
    mcstat__ks_point r;
    double u;
    if (c->weight == MCSTAT_KS_WEIGHT_NONE) {
        u = ceil(v);
        r.q = 1;
    } else {
        u = sqrt(v) * 0x1p20;
        r.q = UINT64_C(1) << 40;
    }
    r.u = !(u > 0.0) ? 0 : u >= 0x1p62 ? UINT64_C(1) << 62 : (uint64_t)u;
    return r;
}

/* The search keeps P(>= lo) > alpha >= P(>= hi) and stops when no attainable
 * value lies between them.  It steps by regula falsi on log p against the
 * key (p falls off smoothly, like exp(-c key) for Canner's u^2/q and like
 * exp(-c u^2) unweighted, where it uses sqrt(key)), snapped to attainable
 * values, with bisection whenever one side has been kept twice (Illinois'
 * safeguard); about 8 p-value evaluations instead of the ~40 of bisection. */
int mcstat__ks_exact_critical(const mcstat__ks_data *d, double alpha, double *key)
{
    dp_ctx c;
    int st = ctx_init(&c, d);
    if (st)
        return st;
    const int none = c.weight == MCSTAT_KS_WEIGHT_NONE;
    /* A first bracket around a guess (Kolmogorov's limit or
     * Jaeschke's limit, good to ~10% in the statistic), widened by 30% steps;
     * the largest attainable value, whose band would be the whole lattice,
     * is evaluated only if the guesses run into it. */
    mcstat__ks_point lo = {0, 1}, hi = max_point(&c);
    double p_lo = 1.0, p_hi = -1.0;
    const uint64_t n1 = d->n1, n2 = d->n2, N = d->N;
    double g = none ? mcstat__ks_asymp_critical(n1, n2, d->alternative == MCSTAT_TWO_SIDED, alpha) * n1 * n2 : 0;
    if (!none) {
        double ll = log(log((double)N)), a = sqrt(2.0 * ll), b = 2.0 * ll + 0.5 * log(ll) - 0.5 * log(M_PI);
        double x = -log(-log1p(-alpha) / (d->alternative == MCSTAT_TWO_SIDED ? 2.0 : 1.0));
        double d2 = (x + b) / a;
        g = d2 * d2 * (double)n1 * (double)n2 / (double)N;
        /* Jaeschke's limit needs log log N > 0: for N <= 2 it is NaN (found
         * by UBSan as a NaN converted to an integer); start small and let
         * the 69% steps find the bracket. */
        if (!(g > 0.0) || !isfinite(g))
            g = 1.0;
    }
    /* Jaeschke's constants need log log N > 0: at N = 2 (1 + 1 values) the
     * guess was NaN and near_value converted it to an integer, undefined
     * behaviour (found by tests/fuzz/fuzz_ks).  The guess only guides. */
    if (!(g > 0.0) || !isfinite(g))
        g = 1.0;
    if (d->obs.u > 0) { /* the observed point is one more free bracket */
        double po = sf(&c, d->obs);
        if (po > alpha)
            lo = d->obs, p_lo = po;
        else
            hi = d->obs, p_hi = po;
    }
    for (int k = 0; k < 60 && p_hi < 0.0; k++, g *= none ? 1.3 : 1.69) {
        mcstat__ks_point cand;
        if (!next_point(&c, near_value(&c, g), 0, &cand) || mcstat__ks_point_cmp(c.weight, cand, hi) >= 0) {
            p_hi = hi.u ? sf(&c, hi) : 1.0; /* the largest value */
            break;
        }
        if (mcstat__ks_point_cmp(c.weight, cand, lo) <= 0)
            continue;
        double pc = sf(&c, cand);
        if (pc > alpha)
            lo = cand, p_lo = pc;
        else
            hi = cand, p_hi = pc;
    }
    if (hi.u == 0 || p_hi > alpha) { /* H0 cannot be rejected at this alpha */
        *key = mcstat__ks_key(d->weight, hi.u, hi.q);
        ctx_free(&c);
        return MCSTAT_OK;
    }
    int side = 0, same = 0;
    const double la = log(alpha);
    for (int iter = 0; iter < 400; iter++) {
        mcstat__ks_point succ, cand;
        if (!next_point(&c, lo, 1, &succ) || mcstat__ks_point_cmp(c.weight, succ, hi) >= 0)
            break;
        double klo = mcstat__ks_key(c.weight, lo.u, lo.q), khi = mcstat__ks_key(c.weight, hi.u, hi.q);
        double xlo = none ? klo * klo : klo, xhi = none ? khi * khi : khi, x;
        if (same >= 2 || !(p_hi > 0.0)) {
            x = 0.5 * (xlo + xhi);
            same = 0;
        } else {
            double f = (log(p_lo) - la) / (log(p_lo) - log(p_hi));
            x = xlo + f * (xhi - xlo);
        }
        double v = none ? sqrt(x) : x;
        if (!next_point(&c, near_value(&c, v), 0, &cand) || mcstat__ks_point_cmp(c.weight, cand, lo) <= 0 ||
            mcstat__ks_point_cmp(c.weight, cand, hi) >= 0)
            cand = succ;
        double pc = sf(&c, cand);
        int now = pc > alpha ? -1 : 1;
        same = now == side ? same + 1 : 1;
        side = now;
        if (pc > alpha) {
            lo = cand;
            p_lo = pc;
        } else {
            hi = cand;
            p_hi = pc;
        }
    }
    *key = mcstat__ks_key(d->weight, lo.u, lo.q);
    ctx_free(&c);
    return MCSTAT_OK;
}
