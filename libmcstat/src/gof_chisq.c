/*
 * gof_chisq.c - Pearson's chi-squared goodness-of-fit test on the counts of
 * k cells against their expected probabilities or counts, with the pooling
 * of cells of low expectation (documented in mcstat.h).
 *
 * Why pooling is a documented, ordered rule: Pearson's X^2 is chi^2(k-1)
 * only asymptotically, and the approximation fails first where expected
 * counts are small (Cochran's rule: all >= 5, or most).  Cells are pooled
 * with their successors in the caller's order, so a caller who orders cells
 * spatially (the direction cells of libmcest are in k-d tree order) pools
 * neighbours.  One pass, no allocation: a closed group is kept pending
 * until the next one closes, so that a short last group can be merged into
 * it.
 *
 * The p-value is the upper tail of chi^2(df) from the incomplete gamma
 * function Q(df/2, X^2/2) computed directly (never 1 - P), so it keeps its
 * relative accuracy deep in the tail (p = 1e-300 and below).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>

/* R's chisq.test: |sum(p) - 1| > sqrt(.Machine$double.eps) is an error. */
#define SUM_TOL 1.4901161193847656e-08

/* Every size mcstat_gof_options has had, oldest first (options.c). */
static const uint32_t GOF_SIZES[] = {MCSTAT_GOF_OPTIONS_SIZE_0_1};
_Static_assert(sizeof(mcstat_gof_options) == MCSTAT_GOF_OPTIONS_SIZE_0_1,
               "a grown mcstat_gof_options needs its size appended to GOF_SIZES");

int mcstat_gof_options_init_size(mcstat_gof_options *opt, size_t size)
{
    const mcstat_gof_options d = MCSTAT_GOF_OPTIONS_INIT;
    return mcstat__options_init(opt, size, &d, sizeof d, GOF_SIZES, sizeof GOF_SIZES / sizeof *GOF_SIZES);
}

double mcstat_gof_default_min_expected(void) { return MCSTAT_GOF_DEFAULT_MIN_EXPECTED; }

/* Neumaier's compensated sum: k may be 1e6 cells of very unequal terms. */
typedef struct {
    double s, c;
} ksum;

static inline void ksum_add(ksum *a, double x)
{
    double t = a->s + x;
    if (fabs(a->s) >= fabs(x))
        a->c += (a->s - t) + x;
    else
        a->c += (x - t) + a->s;
    a->s = t;
}

static inline double ksum_get(const ksum *a) { return a->s + a->c; }

/* (o - e)^2 / e for one (pooled) cell; e > 0. */
static inline double pearson_term(double o, double e)
{
    double d = o - e;
    return (d / e) * d; /* not d * d / e: counts near 1e300 would overflow */
}

int mcstat_gof_chisq_test(const double *observed, const double *expected, size_t k,
                     const mcstat_gof_options *opt, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_gof_options o = MCSTAT_GOF_OPTIONS_INIT;
    if (opt && mcstat__options_read(&o, sizeof o, opt, GOF_SIZES, sizeof GOF_SIZES / sizeof *GOF_SIZES))
        return MCSTAT_EINVAL;
    if (!out || (k > 0 && (!observed || !expected)) || !valid_alpha(alpha))
        return MCSTAT_EINVAL;
    if ((o.expected != MCSTAT_GOF_PROBABILITIES && o.expected != MCSTAT_GOF_COUNTS &&
         o.expected != MCSTAT_GOF_AUTO) ||
        (o.pool != 0 && o.pool != 1) || (o.rescale != 0 && o.rescale != 1) || o.n_estimated < 0 ||
        !(o.min_expected >= 0.0) || !isfinite(o.min_expected) || o.reserved != 0)
        return MCSTAT_EINVAL;
    if (k < 2)
        return MCSTAT_ETOOFEW;

    ksum sn = {0, 0}, se = {0, 0};
    for (size_t i = 0; i < k; i++) {
        if (!isfinite(observed[i]) || !isfinite(expected[i]))
            return MCSTAT_ENONFINITE;
        if (observed[i] < 0.0 || expected[i] < 0.0)
            return MCSTAT_EINVAL;
        if (!o.pool && !(expected[i] > 0.0))
            return MCSTAT_EINVAL; /* without pooling every cell needs a positive expectation */
        ksum_add(&sn, observed[i]);
        ksum_add(&se, expected[i]);
    }
    const double n = ksum_get(&sn), esum = ksum_get(&se);
    if (!isfinite(esum) || !isfinite(n))
        return MCSTAT_EINVAL; /* the totals overflow */
    if (!(n > 0.0))
        return MCSTAT_ETOOFEW;
    if (!(esum > 0.0))
        return MCSTAT_EINVAL;
    /* AUTO: probabilities when they sum to 1, else counts (when N = 1 the
     * two readings give the same expected counts) */
    const int as_p = o.expected == MCSTAT_GOF_PROBABILITIES ||
                     (o.expected == MCSTAT_GOF_AUTO && fabs(esum - 1.0) <= SUM_TOL);
    const double target = as_p ? 1.0 : n;
    if (!o.rescale && fabs(esum - target) > SUM_TOL * target)
        return MCSTAT_EINVAL;
    /* expected count of cell i: expected[i] * scale */
    const double scale = n / esum;

    /* One pass: close a group once its expected count reaches min_expected;
     * keep the last closed group pending so that a short tail can join it. */
    ksum stat = {0, 0};
    double go = 0.0, ge = 0.0;      /* the open group */
    double po = 0.0, pe = 0.0;      /* the pending (closed) group */
    int have_pending = 0;
    uint64_t groups = 0;
    double emin = INFINITY;
    for (size_t i = 0; i < k; i++) {
        go += observed[i];
        ge += expected[i] * scale;
        if (!o.pool || ge >= o.min_expected) {
            if (have_pending) {
                ksum_add(&stat, pearson_term(po, pe));
                emin = fmin(emin, pe);
                groups++;
            }
            po = go, pe = ge, have_pending = 1;
            go = ge = 0.0;
        }
    }
    if (ge > 0.0 || go > 0.0) { /* a short last group joins the pending one */
        if (have_pending)
            po += go, pe += ge;
        else
            po = go, pe = ge, have_pending = 1;
    }
    if (have_pending) {
        if (pe > 0.0)
            ksum_add(&stat, pearson_term(po, pe));
        emin = fmin(emin, pe);
        groups++;
    }
    const double df = (double)groups - 1.0 - (double)o.n_estimated;
    if (!(df >= 1.0))
        return MCSTAT_ETOOFEW;

    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = MCSTAT_TEST_CHISQ_GOF;
    r.method = MCSTAT_METHOD_ASYMPTOTIC;
    r.alternative = MCSTAT_GREATER;
    r.alpha = alpha;
    r.n[0] = n < 0x1p63 ? (uint64_t)llround(n) : UINT64_MAX; /* llround overflows beyond */
    r.statistic = ksum_get(&stat);
    r.df[0] = df;
    r.chisq_cells = groups > INT32_MAX ? INT32_MAX : (int32_t)groups;
    r.chisq_n_estimated = o.n_estimated;
    r.chisq_cells_given = (double)k;
    r.chisq_min_expected = emin;
    r.chisq_pool_below = o.pool ? o.min_expected : 0.0;

    mcstat_tails t;
    int st = mcstat__chisq_tails(r.statistic, df, &t);
    if (st)
        return st;
    /* the upper tail only: X^2 measures distance from the expected counts */
    r.p_value = t.q;
    double c1;
    if ((st = mcstat_chisq_quantile(alpha, df, 1, &c1)))
        return st;
    r.critical[0] = -INFINITY;
    r.critical[1] = c1;
    r.reject = r.p_value <= alpha;
    r.decision = r.reject ? 1 : 0;
    *out = r;
    return MCSTAT_OK;
}
