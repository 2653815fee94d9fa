/*
 * p_adjust.c - adjusted p-values for multiple testing, as R's p.adjust.
 *
 * Methods: Bonferroni, Holm (1979), Hochberg (1988), Hommel (1988),
 * Benjamini & Hochberg (1995, "BH", false discovery rate) and Benjamini &
 * Yekutieli (2001, "BY"); and e-BH (Wang & Ramdas 2022), BH's analogue for
 * e-values, valid under any dependence.  NaN entries are R's NA: they stay
 * NaN and n is the number of the others; with n <= 1 the p-values come back
 * unchanged.
 *
 * e-BH on e-values e_(1) >= ... >= e_(n) rejects the k* largest, k* = max{k :
 * k e_(k) / n >= 1/alpha}.  Hypothesis i (descending rank) is rejected iff
 * k* >= i, iff some k >= i has n / (k e_(k)) <= alpha: its adjusted value
 * is min_{k >= i} n / (k e_(k)), capped at 1.  That is BH's step-up
 * cumulative minimum on u = 1/e (u ascending as e descends), so e-BH runs
 * BH's loop on u; ties get equal values as in BH (for tied e at ranks
 * i..j, k e_(k) grows with k, so the minimum over [i, j] is at j).
 *
 * The p-value method "e-BH" first calibrates each p into an e-value, e =
 * kappa p^(kappa - 1) (Vovk & Wang 2021; Shafer et al. 2011): for p
 * uniform, E[e] = 1, and for any valid p, E[e] <= 1, so the e-values are
 * valid under the same dependence the p-values have, whatever it is.  The
 * k-th rejection then needs p_(k) <= (kappa k alpha / n)^(1 / (1 - kappa)).
 * For x = k alpha / n from 1e-8 (a first rejection among 10^6 pixels) to
 * 1e-3, the kappa maximising that threshold runs from about 0.04 to 0.1;
 * kappa = 1/10 stays within a factor 1.7 of the best over that range,
 * where kappa = 1/2 squares x/2 (1e-10 instead of about 5e-7 for x = 2e-5:
 * hopeless for per-pixel tests).  u = 1/e = p^(9/10) / (1/10).
 *
 * Every method but Bonferroni works on the sorted p-values.  They are sorted
 * with their positions by an LSD radix sort on their bits (non-negative
 * doubles order as their bit patterns), 8-bit digits, skipping digits that
 * no two keys differ in (as sort.c).  Tied p-values get equal adjusted
 * values in every method (the cumulative max / min absorbs the order among
 * ties), so the order among ties does not matter.
 *
 * Hommel: R's loop over m = n-1 .. 2 is O(n^2).  Written out, with p_1 <=
 * ... <= p_n sorted, s = n - m,
 *   d_m = m * min_{j > s} p_j / (j - s)        (Simes over the m largest)
 *   c_m = m * min_{j > s+1} p_j / (j - s)
 *   adj_i = max(p_i, max_{m >= max(2, n-i+2)} d_m,
 *               max_{2 <= m <= min(n-i+1, n-1)} min(m p_i, c_m)).
 * min_j p_j / (j - s) is the smallest slope from (s, 0) to the points
 * (j, p_j): a tangent to their lower convex hull, which grows one point to
 * the left as s decreases (a stack; the tangent by binary search).  c_m / m
 * is non-increasing in m, so for each i the m with c_m > m p_i form a prefix
 * [2, m*) (max m p_i at its end) and the rest a window [m*, M_i] whose max
 * of c_m is taken with a monotone deque, both ends moving one way as i
 * falls.  O(n log n) in all (Meijer, Krebs & Goeman 2019 give an O(n)
 * algorithm for the same values; this one is simpler and sorting dominates
 * anyway).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <stdlib.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

/* The sort's workspace at image scale (32 bytes a value: 265 MB for a 4K
 * image) is touched once, page by page; with 4 KiB pages the first touches
 * cost as much as the sort (measured: 0.3 s of 0.7 s at 8.3 M values), so
 * where Linux offers transparent huge pages on request, request them.  An
 * advice: nothing changes where it is refused. */
static void *work_alloc(size_t bytes)
{
    void *w = malloc(bytes ? bytes : 1);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const uintptr_t huge = (uintptr_t)2 << 20;
    if (w && bytes >= 8 * huge) {
        uintptr_t a = ((uintptr_t)w + huge - 1) & ~(huge - 1), e = ((uintptr_t)w + bytes) & ~(huge - 1);
        if (e > a)
            madvise((void *)a, e - a, MADV_HUGEPAGE);
    }
#endif
    return w;
}

typedef struct {
    uint64_t key; /* the bits of p (p >= 0), then its adjusted value's */
    uint64_t idx; /* position in the input */
} pa_item;

/* The calibrator's kappa (see the top of the file). */
#define EBH_KAPPA 0.1

#define PA_BITS 8
#define PA_SIZE (1u << PA_BITS)
#define PA_SMALL 32

static double item_p(const pa_item *it)
{
    double v;
    memcpy(&v, &it->key, sizeof v);
    return v;
}

static void item_set(pa_item *it, double v)
{
    memcpy(&it->key, &v, sizeof v);
}

/* fmin and fmax of values that cannot be NaN: a compare, where the library
 * calls (kept by their NaN rules) cost a quarter of a 4K image's BH. */
static double min_nn(double x, double y)
{
    return y < x ? y : x;
}

static double max_nn(double x, double y)
{
    return y > x ? y : x;
}

static void insertion_sort(pa_item *a, size_t n)
{
    for (size_t i = 1; i < n; i++) {
        pa_item v = a[i];
        size_t j = i;
        while (j > 0 && a[j - 1].key > v.key) {
            a[j] = a[j - 1];
            j--;
        }
        a[j] = v;
    }
}

/* LSD radix sort of a[0..n) by key; tmp has room for n items. */
static void radix_sort(pa_item *a, size_t n, pa_item *tmp)
{
    if (n <= PA_SMALL) {
        insertion_sort(a, n);
        return;
    }
    uint64_t all = ~UINT64_C(0), any = 0;
    for (size_t i = 0; i < n; i++) {
        all &= a[i].key;
        any |= a[i].key;
    }
    uint64_t diff = all ^ any;
    pa_item *src = a, *dst = tmp;
    for (int pass = 0; pass < 64 / PA_BITS; pass++) {
        const int shift = pass * PA_BITS;
        if (!((diff >> shift) & (PA_SIZE - 1)))
            continue;
        size_t h[PA_SIZE] = {0};
        for (size_t i = 0; i < n; i++)
            h[(src[i].key >> shift) & (PA_SIZE - 1)]++;
        size_t sum = 0;
        for (unsigned b = 0; b < PA_SIZE; b++) {
            size_t c = h[b];
            h[b] = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; i++)
            dst[h[(src[i].key >> shift) & (PA_SIZE - 1)]++] = src[i];
        pa_item *t = src;
        src = dst;
        dst = t;
    }
    if (src != a)
        memcpy(a, src, n * sizeof *a);
}

/* Distributes src[0..n) into dst[0..n) by value, in PA_FAN buckets of
 * equal width between lo and hi: bucket floor((v - lo) / (hi - lo) * PA_FAN),
 * monotone in v because rounding is.  start[0..PA_FAN] <- the buckets'
 * bounds.  Returns 0 when the values do not spread (one value, or an
 * infinite one: u = 1/e of e = 0), with nothing moved. */
#define PA_FAN 2048

static int distribute(const pa_item *src, size_t n, pa_item *dst, size_t *start)
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        double v = item_p(&src[i]);
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    double scale = (double)PA_FAN / (hi - lo);
    if (!(hi > lo) || !(hi < INFINITY) || !(scale < INFINITY))
        return 0;
    const double top = (double)(PA_FAN - 1);
    size_t h[PA_FAN + 1] = {0};
#define PA_BUCKET(it) ((size_t)min_nn((item_p(it) - lo) * scale, top))
    for (size_t i = 0; i < n; i++)
        h[PA_BUCKET(&src[i]) + 1]++;
    for (size_t b = 0; b < PA_FAN; b++)
        h[b + 1] += h[b];
    memcpy(start, h, sizeof h);
    for (size_t i = 0; i < n; i++)
        dst[h[PA_BUCKET(&src[i])]++] = src[i];
#undef PA_BUCKET
    return 1;
}

/* Sorts a[0..n) by key; tmp has room for n items.
 *
 * The LSD radix sort alone makes up to 8 passes over the 16-byte items, each
 * reading and scattering all of them (about 1 s of BH over a 4K image's 8.3
 * M p-values).  Two passes of distribution by value come first: the first
 * splits the items into 2048 buckets (writes stream to 2048 places, which
 * the caches hold), the second splits each bucket, now small enough to sort
 * in cache, into up to 2048 more.  Per-pixel p-values are mostly uniform
 * (the unchanged pixels), so the final buckets hold a few items each: an
 * insertion sort.  A crowded final bucket (clustered values) gets the radix
 * sort on its own items. */
static void sort_items(pa_item *a, size_t n, pa_item *tmp)
{
    size_t s1[PA_FAN + 1], s2[PA_FAN + 1];
    if (n <= 4 * PA_FAN || !distribute(a, n, tmp, s1)) {
        radix_sort(a, n, tmp);
        return;
    }
    for (size_t b = 0; b < PA_FAN; b++) { /* bucket b is tmp[s1[b] .. s1[b + 1]) */
        size_t off = s1[b], len = s1[b + 1] - off;
        pa_item *src = tmp + off, *dst = a + off;
        if (len <= PA_SMALL || !distribute(src, len, dst, s2)) {
            memcpy(dst, src, len * sizeof *src);
            if (len <= PA_SMALL)
                insertion_sort(dst, len);
            else
                radix_sort(dst, len, src);
            continue;
        }
        for (size_t c = 0; c < PA_FAN; c++) {
            size_t o2 = s2[c], l2 = s2[c + 1] - o2;
            if (l2 <= PA_SMALL)
                insertion_sort(dst + o2, l2);
            else
                radix_sort(dst + o2, l2, src + o2);
        }
    }
}

/* Points (j, p_j), j = 1..n, of the sorted p-values a[j-1]. */
#define PX(j) ((double)(j))
#define PY(j) item_p(&a[(j) - 1])

/* The j on the hull (stack h[0..top], h[0] rightmost) minimising
 * p_j / (j - s), for s left of every hull point. */
static size_t hull_tangent(const pa_item *a, const size_t *h, size_t top, double s)
{
    /* Predicate on stack index k >= 1: moving right from h[k] to h[k-1] does
     * not lower the slope from (s, 0): (pB - pA)(xA - s) >= pA (xB - xA).
     * False left of the tangent, true from it on; find the largest true k. */
    size_t lo = 0, hi = top; /* h[lo] satisfies it (k = 0 by convention) */
    while (lo < hi) {
        size_t k = lo + (hi - lo + 1) / 2;
        size_t A = h[k], B = h[k - 1];
        double pA = PY(A), pB = PY(B);
        if ((pB - pA) * (PX(A) - s) >= pA * (PX(B) - PX(A)))
            lo = k;
        else
            hi = k - 1;
    }
    return h[lo];
}

/* Adds P, left of every point held, to the hull h[0..*cnt). */
static void hull_push(const pa_item *a, size_t *h, size_t *cnt, size_t P)
{
    double xP = PX(P), pP = PY(P);
    size_t k = *cnt;
    /* Keep edge slopes increasing from left to right (a lower hull): drop
     * A = h[k-1] while slope(P, A) >= slope(A, B), B = h[k-2]. */
    while (k >= 2) {
        size_t A = h[k - 1], B = h[k - 2];
        double pA = PY(A), pB = PY(B);
        if ((pA - pP) * (PX(B) - PX(A)) >= (pB - pA) * (PX(A) - xP))
            k--;
        else
            break;
    }
    h[k++] = P;
    *cnt = k;
}

/* Hommel's adjusted values of the sorted a[0..n) (n >= 3), written into
 * a[].key in place; c, d: n doubles each; h, dq: n indices each (h and dq
 * may share storage). */
static void hommel(pa_item *a, size_t n, double *c, double *d, size_t *h, size_t *dq)
{
    /* c[m], d[m] for m = 1..n stored at index m - 1. */
    size_t cnt = 0;
    for (size_t s1 = n; s1-- > 0;) { /* s = s1, m = n - s */
        double s = (double)s1;
        double m = (double)(n - s1);
        if (n - s1 >= 2) {
            size_t j = hull_tangent(a, h, cnt - 1, s);
            c[n - s1 - 1] = m * PY(j) / (PX(j) - s);
        } else {
            c[n - s1 - 1] = NAN; /* m = 1: unused */
        }
        hull_push(a, h, &cnt, s1 + 1);
        size_t j = hull_tangent(a, h, cnt - 1, s);
        d[n - s1 - 1] = m * PY(j) / (PX(j) - s);
    }
    /* d[m-1] <- max_{m' >= m} d_{m'}. */
    for (size_t m = n - 1; m >= 1; m--)
        d[m - 1] = fmax(d[m - 1], d[m]);
    /* i from n down to 1: window [mstar, M] of m over c, both non-decreasing. */
    size_t mstar = 2, M = 1, head = 0, tail = 0; /* deque dq[head..tail) of m, c decreasing */
    for (size_t i = n; i >= 1; i--) {
        double p = PY(i);
        size_t Mi = n - i + 1 < n - 1 ? n - i + 1 : n - 1;
        while (mstar <= n - 1 && c[mstar - 1] > (double)mstar * p)
            mstar++;
        while (M < Mi) {
            M++;
            while (tail > head && c[dq[tail - 1] - 1] <= c[M - 1])
                tail--;
            dq[tail++] = M;
        }
        while (tail > head && dq[head] < mstar)
            head++;
        size_t m1 = n - i + 2 < n ? n - i + 2 : n;
        if (m1 < 2)
            m1 = 2;
        double v = d[m1 - 1];
        if (Mi >= 2) {
            size_t last = mstar - 1 < Mi ? mstar - 1 : Mi; /* m p_i on [2, last] */
            if (last >= 2)
                v = fmax(v, (double)last * p);
            if (tail > head && mstar <= Mi)
                v = fmax(v, c[dq[head] - 1]);
        }
        item_set(&a[i - 1], fmax(v, p));
    }
}

/* ASCII case-insensitive equality (strcasecmp is POSIX, not C11, and must
 * not depend on the locale). */
static int name_eq(const char *a, const char *b)
{
    for (;; a++, b++) {
        int ca = (unsigned char)*a, cb = (unsigned char)*b;
        if (ca >= 'A' && ca <= 'Z')
            ca += 'a' - 'A';
        if (cb >= 'A' && cb <= 'Z')
            cb += 'a' - 'A';
        if (ca != cb)
            return 0;
        if (!ca)
            return 1;
    }
}

int mcstat_p_adjust_method_parse(const char *name, int *method)
{
    /* R's p.adjust names, then statsmodels' multipletests names and their
     * aliases for the same methods (statsmodels compares lower-cased names;
     * so does this, which also takes R's "BH" and "BY" as "bh", "by").
     * statsmodels' "h" is Holm, its "sh" ("simes-hochberg") Hochberg. */
    static const struct {
        const char *name;
        int method;
    } names[] = {{"none", MCSTAT_P_ADJUST_NONE},
                 {"bonferroni", MCSTAT_P_ADJUST_BONFERRONI},
                 {"holm", MCSTAT_P_ADJUST_HOLM},
                 {"hochberg", MCSTAT_P_ADJUST_HOCHBERG},
                 {"hommel", MCSTAT_P_ADJUST_HOMMEL},
                 {"BH", MCSTAT_P_ADJUST_BH},
                 {"fdr", MCSTAT_P_ADJUST_BH},
                 {"BY", MCSTAT_P_ADJUST_BY},
                 {"e-BH", MCSTAT_P_ADJUST_E_BH},
                 {"ebh", MCSTAT_P_ADJUST_E_BH},
                 {"e_bh", MCSTAT_P_ADJUST_E_BH},
                 /* statsmodels */
                 {"b", MCSTAT_P_ADJUST_BONFERRONI},
                 {"bonf", MCSTAT_P_ADJUST_BONFERRONI},
                 {"h", MCSTAT_P_ADJUST_HOLM},
                 {"sh", MCSTAT_P_ADJUST_HOCHBERG},
                 {"simes-hochberg", MCSTAT_P_ADJUST_HOCHBERG},
                 {"ho", MCSTAT_P_ADJUST_HOMMEL},
                 {"fdr_bh", MCSTAT_P_ADJUST_BH},
                 {"fdr_i", MCSTAT_P_ADJUST_BH},
                 {"fdr_p", MCSTAT_P_ADJUST_BH},
                 {"fdri", MCSTAT_P_ADJUST_BH},
                 {"fdrp", MCSTAT_P_ADJUST_BH},
                 {"fdr_by", MCSTAT_P_ADJUST_BY},
                 {"fdr_n", MCSTAT_P_ADJUST_BY},
                 {"fdr_c", MCSTAT_P_ADJUST_BY},
                 {"fdrn", MCSTAT_P_ADJUST_BY},
                 {"fdrcorr", MCSTAT_P_ADJUST_BY}};
    if (!name || !method)
        return MCSTAT_EINVAL;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (name_eq(name, names[i].name)) {
            *method = names[i].method;
            return MCSTAT_OK;
        }
    }
    return MCSTAT_EINVAL;
}

const char *mcstat_p_adjust_method_name(int method)
{
    switch (method) {
    case MCSTAT_P_ADJUST_NONE: return "none";
    case MCSTAT_P_ADJUST_BONFERRONI: return "bonferroni";
    case MCSTAT_P_ADJUST_HOLM: return "holm";
    case MCSTAT_P_ADJUST_HOCHBERG: return "hochberg";
    case MCSTAT_P_ADJUST_HOMMEL: return "hommel";
    case MCSTAT_P_ADJUST_BH: return "BH";
    case MCSTAT_P_ADJUST_BY: return "BY";
    case MCSTAT_P_ADJUST_E_BH: return "e-BH";
    default: return NULL;
    }
}

int mcstat_p_adjust_work_size(size_t n, int method, size_t *bytes)
{
    if (!bytes || !mcstat_p_adjust_method_name(method))
        return MCSTAT_EINVAL;
    size_t per;
    switch (method) {
    case MCSTAT_P_ADJUST_NONE:
    case MCSTAT_P_ADJUST_BONFERRONI: per = 0; break;
    case MCSTAT_P_ADJUST_HOMMEL: per = 2 * sizeof(pa_item) + sizeof(size_t); break;
    default: per = 2 * sizeof(pa_item); break;
    }
    if (per && n > SIZE_MAX / per)
        return MCSTAT_ETOOBIG;
    *bytes = n * per;
    return MCSTAT_OK;
}

/* mcstat_p_adjust's body; evalues: p holds e-values (method is E_BH). */
static int adjust(const double *p, size_t n, int method, int evalues, void *work, size_t work_bytes,
                  double *adjusted)
{
    MCSTAT_IEEE_SCOPE();
    size_t need;
    int st = mcstat_p_adjust_work_size(n, method, &need);
    if (st)
        return st;
    if (n > 0 && (!p || !adjusted))
        return MCSTAT_EINVAL;
    if (work && ((uintptr_t)work % sizeof(double) != 0))
        return MCSTAT_EINVAL;
    if (work && work_bytes < need)
        return MCSTAT_EBUFSIZE;
    /* Validate first, so that nothing is written on failure. */
    size_t m = 0;
    for (size_t k = 0; k < n; k++) {
        double v = p[k];
        if (isnan(v))
            continue;
        if (!(v >= 0.0 && (evalues || v <= 1.0)))
            return MCSTAT_EINVAL;
        m++;
    }
    /* e-values are never returned as they are: even one is turned into
     * min(1, 1/e). */
    if (m == 0 || (!evalues && (m <= 1 || method == MCSTAT_P_ADJUST_NONE))) {
        if (adjusted != p)
            memcpy(adjusted, p, n * sizeof *p);
        return MCSTAT_OK;
    }
    const double nd = (double)m;
    if (method == MCSTAT_P_ADJUST_BONFERRONI) {
        for (size_t k = 0; k < n; k++)
            adjusted[k] = isnan(p[k]) ? p[k] : fmin(1.0, nd * p[k]);
        return MCSTAT_OK;
    }
    if (m == 2 && method == MCSTAT_P_ADJUST_HOMMEL)
        method = MCSTAT_P_ADJUST_HOCHBERG; /* as R: Hommel and Hochberg agree for two */
    void *own = NULL;
    if (!work) {
        own = work_alloc(need);
        if (!own)
            return MCSTAT_ENOMEM;
        work = own;
    }
    pa_item *a = (pa_item *)work, *tmp = a + n;
    size_t j = 0;
    for (size_t k = 0; k < n; k++) {
        double v = p[k];
        if (isnan(v)) {
            adjusted[k] = v;
            continue;
        }
        if (evalues)
            v = v > 0.0 ? 1.0 / v : INFINITY; /* u = 1/e; e = -0 too */
        else if (method == MCSTAT_P_ADJUST_E_BH)
            v = pow(v, 1.0 - EBH_KAPPA) / EBH_KAPPA; /* 1/e of the calibrated p, increasing in p */
        item_set(&a[j], v + 0.0); /* -0 -> +0: the keys of equal values are equal */
        a[j].idx = k;
        j++;
    }
    sort_items(a, m, tmp);

    switch (method) {
    case MCSTAT_P_ADJUST_HOLM: { /* cummax((n - i + 1) p_(i)), i ascending */
        double run = 0.0;
        for (size_t i = 0; i < m; i++) {
            run = max_nn(run, (nd - (double)i) * item_p(&a[i]));
            item_set(&a[i], min_nn(1.0, run));
        }
        break;
    }
    case MCSTAT_P_ADJUST_HOCHBERG: { /* cummin((n - i + 1) p_(i)), i descending */
        double run = INFINITY;
        for (size_t i = m; i-- > 0;) {
            run = min_nn(run, (nd - (double)i) * item_p(&a[i]));
            item_set(&a[i], min_nn(1.0, run));
        }
        break;
    }
    case MCSTAT_P_ADJUST_BH:
    case MCSTAT_P_ADJUST_BY:
    case MCSTAT_P_ADJUST_E_BH: { /* cummin(q n / i p_(i)), i descending; q = 1 or sum 1/k */
        double q = 1.0;
        if (method == MCSTAT_P_ADJUST_BY) {
            /* R sums in long double; Kahan summation from the small end
             * gives the harmonic number to about 1 ulp. */
            double s = 0.0, comp = 0.0;
            for (size_t k = m; k >= 1; k--) {
                double y = 1.0 / (double)k - comp;
                double t = s + y;
                comp = (t - s) - y;
                s = t;
            }
            q = s;
        }
        double run = INFINITY;
        for (size_t i = m; i-- > 0;) {
            run = min_nn(run, q * nd / (double)(i + 1) * item_p(&a[i]));
            item_set(&a[i], min_nn(1.0, run));
        }
        break;
    }
    case MCSTAT_P_ADJUST_HOMMEL: {
        /* tmp (2m doubles, free after the sort) holds c and d; the index
         * stack and the deque share the m size_t after it. */
        double *c = (double *)tmp, *d = c + m;
        size_t *h = (size_t *)(tmp + n);
        hommel(a, m, c, d, h, h);
        break;
    }
    default: break;
    }
    for (size_t i = 0; i < m; i++)
        adjusted[a[i].idx] = item_p(&a[i]);
    free(own);
    return MCSTAT_OK;
}

int mcstat_p_adjust(const double *p, size_t n, int method, void *work, size_t work_bytes,
                    double *adjusted)
{
    return adjust(p, n, method, 0, work, work_bytes, adjusted);
}

int mcstat_e_bh(const double *e, size_t n, void *work, size_t work_bytes, double *adjusted)
{
    return adjust(e, n, MCSTAT_P_ADJUST_E_BH, 1, work, work_bytes, adjusted);
}
