/*
 * binom_test.c - the exact binomial test (R's binom.test) and the battery
 * meta-test: is a count of rejections consistent with the tests' level?
 *
 * Everything comes from the library's own incomplete beta (special.c):
 *   P[X >= k] = I_p(k, n-k+1),   P[X <= k] = I_q(n-k, k+1)  (q = 1-p),
 * both tails of one evaluation, each computed from the side where it is
 * small and with its logarithm, so p-values far below 1e-300 keep their
 * digits in log scale; the density is the beta prefactor,
 *   C(n,k) p^k q^(n-k) = n / (k (n-k)) * p^k q^(n-k) / B(k, n-k),
 * written around the centre (no lgamma cancellation at n = 1e9).
 *
 * R's two-sided rule sums the probabilities of all outcomes no more likely
 * than the observed one, with the relative tolerance 1 + 1e-7.  R counts
 * them one by one (O(n)); the density is monotone on each side of m = n p
 * (it decreases from ceil(m) upwards, increases up to floor(m)), so the set
 * on the other side is a tail whose end a bisection finds in O(log n)
 * density evaluations.  Comparisons are made on log densities, so they do
 * not underflow where R's dbinom does.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>

#define REL_ERR_LOG 9.9999995e-08 /* log(1 + 1e-7): R's relErr */
#define MAX_TRIALS 9007199254740992.0 /* 2^53: counts stay exact in double */

typedef struct {
    double n, p, q; /* trials, probability and 1 - p (given, not formed) */
} binom;

/* log P[X = k], 0 <= k <= n. */
static double logpmf(const binom *b, double k)
{
    if (b->p == 0.0)
        return k == 0.0 ? 0.0 : -INFINITY;
    if (b->q == 0.0)
        return k == b->n ? 0.0 : -INFINITY;
    if (k == 0.0)
        return b->n * log1p(-b->p);
    if (k == b->n)
        return b->n * log(b->p);
    return mcstat__log_beta_prefactor(k, b->n - k, b->p, b->q) + log(b->n / (k * (b->n - k)));
}

/* P[X <= k] (upper = 0) or P[X >= k] (upper = 1), value and log. */
static int tail(const binom *b, double k, int upper, double *v, double *logv)
{
    /* the trivial ends */
    int all = upper ? k <= 0.0 : k >= b->n;
    int none = upper ? k > b->n : k < 0.0;
    if (!all && !none) {
        if (b->p == 0.0)
            all = !upper, none = upper;
        else if (b->q == 0.0)
            all = upper, none = !upper;
    }
    if (all || none) {
        *v = all ? 1.0 : 0.0;
        *logv = all ? 0.0 : -INFINITY;
        return MCSTAT_OK;
    }
    mcstat_tails t;
    /* I_p(a, n-a+1) with a = k (upper) or k+1 (lower): its lower tail is
     * P[X >= a], its upper tail P[X <= a-1] */
    double a = upper ? k : k + 1.0;
    int st = mcstat__beta_inc(a, b->n - a + 1.0, b->p, b->q, &t);
    if (st)
        return st;
    *v = upper ? t.p : t.q;
    *logv = upper ? t.logp : t.logq;
    return MCSTAT_OK;
}

static double log_add(double a, double b)
{
    double hi = fmax(a, b), lo = fmin(a, b);
    if (hi == -INFINITY)
        return -INFINITY;
    return hi + log1p(exp(lo - hi));
}

/* The p-value of x against the alternative, and its log. */
static int pvalue(const binom *b, double x, int alternative, double *pv, double *logpv)
{
    int st;
    if (alternative == MCSTAT_LESS)
        return tail(b, x, 0, pv, logpv);
    if (alternative == MCSTAT_GREATER)
        return tail(b, x, 1, pv, logpv);
    const double m = b->n * b->p;
    if (x == m) {
        *pv = 1.0;
        *logpv = 0.0;
        return MCSTAT_OK;
    }
    const double thr = logpmf(b, x) + REL_ERR_LOG;
    double v1, l1, v2, l2;
    if (x < m) {
        /* the first j >= ceil(m) with pmf(j) <= d relErr (n+1 if none) */
        double lo = ceil(m), hi = b->n + 1.0;
        while (lo < hi) {
            double mid = floor(lo + 0.5 * (hi - lo));
            if (logpmf(b, mid) <= thr)
                hi = mid;
            else
                lo = mid + 1.0;
        }
        if ((st = tail(b, x, 0, &v1, &l1)) || (st = tail(b, lo, 1, &v2, &l2)))
            return st;
    } else {
        /* the last j <= floor(m) with pmf(j) <= d relErr (-1 if none) */
        double lo = -1.0, hi = floor(m);
        while (lo < hi) {
            double mid = ceil(hi - 0.5 * (hi - lo));
            if (logpmf(b, mid) <= thr)
                lo = mid;
            else
                hi = mid - 1.0;
        }
        if ((st = tail(b, lo, 0, &v1, &l1)) || (st = tail(b, x, 1, &v2, &l2)))
            return st;
    }
    *logpv = fmin(0.0, log_add(l1, l2));
    *pv = fmin(1.0, v1 + v2);
    return MCSTAT_OK;
}

/* The Clopper-Pearson bounds, R's p.L and p.U: quantiles of beta
 * distributions, from the F quantile (B ~ Beta(a, b) <=> (B/a)/((1-B)/b) ~
 * F(2a, 2b)), so B = a F / (a F + b). */
static int beta_quantile(double prob, double a, double b, int upper, double *out)
{
    double f;
    int st = mcstat_f_quantile(prob, 2.0 * a, 2.0 * b, upper, &f);
    if (st)
        return st;
    *out = isinf(f) ? 1.0 : a * f / (a * f + b);
    return MCSTAT_OK;
}

static int conf_int(const binom *b, double x, int alternative, double alpha, double ci[2])
{
    int st;
    double tail_alpha = alternative == MCSTAT_TWO_SIDED ? 0.5 * alpha : alpha;
    ci[0] = 0.0;
    ci[1] = 1.0;
    if (alternative != MCSTAT_LESS && x > 0.0 && (st = beta_quantile(tail_alpha, x, b->n - x + 1.0, 0, &ci[0])))
        return st;
    if (alternative != MCSTAT_GREATER && x < b->n &&
        (st = beta_quantile(tail_alpha, x + 1.0, b->n - x, 1, &ci[1])))
        return st;
    return MCSTAT_OK;
}

int mcstat__binom_conf_int(double x, double n, int alternative, double alpha, double ci[2])
{
    binom b = {n, 0.5, 0.5}; /* the interval does not depend on p */
    return conf_int(&b, x, alternative, alpha, ci);
}

/* The acceptance region [c0, c1] of counts whose p-value is above alpha
 * (reject iff x < c0 or x > c1), by bisection: the p-value is monotone on
 * each side of n p (nondecreasing below it, nonincreasing above). */
static int critical(const binom *b, int alternative, double alpha, double c[2])
{
    int st;
    double pv, lpv;
    const double m = b->n * b->p;
    c[0] = -INFINITY;
    c[1] = INFINITY;
    if (alternative != MCSTAT_GREATER) {
        /* smallest x with p(x) > alpha; p is nondecreasing on [0, ceil(m)]
         * (LESS: on [0, n], and P[X <= n] = 1) */
        double lo = 0.0, hi = alternative == MCSTAT_LESS ? b->n : fmin(ceil(m), b->n);
        while (lo < hi) {
            double mid = floor(lo + 0.5 * (hi - lo));
            if ((st = pvalue(b, mid, alternative, &pv, &lpv)))
                return st;
            if (pv > alpha)
                hi = mid;
            else
                lo = mid + 1.0;
        }
        c[0] = lo;
    }
    if (alternative != MCSTAT_LESS) {
        /* largest x with p(x) > alpha; p is nonincreasing on [floor(m), n] */
        double lo = alternative == MCSTAT_GREATER ? 0.0 : fmax(floor(m), 0.0), hi = b->n;
        while (lo < hi) {
            double mid = ceil(hi - 0.5 * (hi - lo));
            if ((st = pvalue(b, mid, alternative, &pv, &lpv)))
                return st;
            if (pv > alpha)
                lo = mid;
            else
                hi = mid - 1.0;
        }
        c[1] = lo;
    }
    return MCSTAT_OK;
}

int mcstat_binom_test(uint64_t x, uint64_t n, double p, int alternative, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out || !valid_alternative(alternative) || !valid_alpha(alpha) || !(p >= 0.0 && p <= 1.0) || x > n)
        return MCSTAT_EINVAL;
    if (n == 0)
        return MCSTAT_ETOOFEW;
    if ((double)n > MAX_TRIALS)
        return MCSTAT_ETOOBIG;
    binom b = {(double)n, p, 1.0 - p};
    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = MCSTAT_TEST_BINOM;
    r.method = MCSTAT_METHOD_EXACT;
    r.alternative = alternative;
    r.alpha = alpha;
    r.n[0] = n;
    r.statistic = (double)x;
    r.estimate[0] = (double)x / (double)n;
    r.null_value = p;
    r.p_value_se = 0.0;
    double logp;
    int st;
    if ((st = pvalue(&b, (double)x, alternative, &r.p_value, &logp)) ||
        (st = conf_int(&b, (double)x, alternative, alpha, r.conf_int)) ||
        (st = critical(&b, alternative, alpha, r.critical)))
        return st;
    r.binom_log_p_value = logp;
    r.reject = r.p_value <= alpha;
    double dev = (double)x - b.n * p;
    r.decision = r.reject ? (dev < 0.0 ? -1 : 1) : 0;
    *out = r;
    return MCSTAT_OK;
}

int mcstat_battery_test(uint64_t rejections, uint64_t k, double level, int alternative, double alpha,
                        mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!(level > 0.0 && level < 1.0))
        return MCSTAT_EINVAL;
    return mcstat_binom_test(rejections, k, level, alternative, alpha, out);
}

int mcstat_battery_test_pvalues(const double *p_values, size_t k, double level, int alternative, double alpha,
                                mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if ((!p_values && k > 0) || !out || !(level > 0.0 && level < 1.0))
        return MCSTAT_EINVAL;
    uint64_t rejections = 0;
    for (size_t i = 0; i < k; i++) {
        if (!(p_values[i] >= 0.0 && p_values[i] <= 1.0))
            return isnan(p_values[i]) ? MCSTAT_ENONFINITE : MCSTAT_EINVAL;
        rejections += p_values[i] <= level;
    }
    return mcstat_binom_test(rejections, (uint64_t)k, level, alternative, alpha, out);
}
