/*
 * diagnose.c - diagnostics of an estimator's primary estimates: shape
 * (skewness, excess kurtosis and their standard errors), tails (Hill's
 * tail index: "fireflies", infinite variance), and the batch size that
 * makes the t test on batch means keep its level (an Edgeworth rule).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>
#include <stdlib.h>

/* ---- tails ---------------------------------------------------------------
 * Hill's estimator of the tail index alpha (P[X > t] ~ t^-alpha; the
 * variance is infinite when alpha <= 2) on each tail, from the k largest
 * excesses over the median:
 *     1/alpha = (1/k) sum_{i<k} log(y_(i) / y_(k)),
 * y_(0) >= y_(1) >= ... the excesses x - median (upper tail) or median - x
 * (lower tail), in decreasing order.  The median makes it invariant under a
 * shift of the data (an estimator's offset says nothing about its tail);
 * it biases the estimate of a pure Pareto tail downwards (about 1.6 for
 * U^-1/2, whose index is 2, at the default k), on the safe side.  k: the
 * default max(10, min(4 sqrt(n), n/25)) balances the estimate's scatter
 * (alpha/sqrt(k)) against the bias of light tails, which look heavier the
 * deeper k reaches (tools/refgen/diagnose_rates.py measured both).  An
 * estimator that is mostly constant (0 off the light source) with rare
 * large values - the firefly pattern - has fewer than k + 1 values beyond
 * its median: k is then reduced to their number minus one, if that leaves
 * at least 10; a tail with fewer has no Pareto part to speak of: +Inf. */
static double hill(const uint64_t *keys, size_t n, size_t k, double med, int upper, size_t *k_used)
{
    /* values strictly beyond the median */
    size_t beyond = 0;
    while (beyond < n && (upper ? mcstat__key_double(keys[n - 1 - beyond]) > med
                                : mcstat__key_double(keys[beyond]) < med))
        beyond++;
    if (beyond < k + 1)
        k = beyond >= 11 ? beyond - 1 : 0;
    *k_used = k;
    if (k == 0)
        return INFINITY;
    double ref = upper ? mcstat__key_double(keys[n - 1 - k]) - med : med - mcstat__key_double(keys[k]);
    double s = 0.0;
    for (size_t i = 0; i < k; i++) {
        double y = upper ? mcstat__key_double(keys[n - 1 - i]) - med : med - mcstat__key_double(keys[i]);
        s += log(y / ref);
    }
    return s > 0.0 ? (double)k / s : INFINITY;
}

static size_t default_tail_k(size_t n)
{
    double k = fmin(floor(4.0 * sqrt((double)n)), floor((double)n / 25.0));
    return k < 10.0 ? 10 : (size_t)k;
}

static int tail_index(const double *x, size_t n, size_t k, double index[2], size_t k_used[2])
{
    if (!x || !index)
        return MCSTAT_EINVAL;
    if (k == 0)
        k = default_tail_k(n);
    if (n < 2 * k + 2) /* each tail needs k + 1 values beyond the median */
        return MCSTAT_ETOOFEW;
    uint64_t *keys = malloc(2 * n * sizeof *keys);
    if (!keys)
        return MCSTAT_ENOMEM;
    int st = mcstat__sort_double_keys(x, n, keys, keys + n);
    if (st == MCSTAT_OK) {
        for (size_t i = 0; i < n; i += n - 1) /* +-Inf sort to the ends */
            if (isinf(mcstat__key_double(keys[i])))
                st = MCSTAT_ENONFINITE;
    }
    if (st == MCSTAT_OK) {
        double med = n % 2 ? mcstat__key_double(keys[n / 2])
                           : 0.5 * mcstat__key_double(keys[n / 2 - 1]) + 0.5 * mcstat__key_double(keys[n / 2]);
        size_t ku[2];
        index[0] = hill(keys, n, k, med, 0, &ku[0]);
        index[1] = hill(keys, n, k, med, 1, &ku[1]);
        if (k_used)
            k_used[0] = ku[0], k_used[1] = ku[1];
    }
    free(keys);
    return st;
}

int mcstat_diag_tail_index(const double *x, size_t n, size_t tail_k, double index[2])
{
    MCSTAT_IEEE_SCOPE();
    return tail_index(x, n, tail_k, index, NULL);
}

/* ---- the t test's level under skewness and kurtosis ----------------------
 * Hall's (1987) Edgeworth expansion of the Studentized mean of m values of
 * skewness g and excess kurtosis c:
 *   P[T <= x] = Phi(x) + m^-1/2 q1(x) phi(x) + m^-1 q2(x) phi(x) + O(m^-3/2),
 *   q1(x) = g (2x^2 + 1) / 6,
 *   q2(x) = x [c (x^2 - 3) / 12 - g^2 (x^4 + 2x^2 - 3) / 18 - (x^2 + 1) / 4].
 * The last term of q2 is the normal-to-t correction, which the t test's own
 * quantiles take care of, so it is left out.  Batch means of k values have
 * g / sqrt(k) and c / k.  With z the normal quantile 1 - alpha/2, the
 * two-sided test's tails reject with probability
 *   lower  alpha/2 + a - b,   upper  alpha/2 - a - b,
 *   a = m^-1/2 q1(z) phi(z),  b = m^-1 q2(z) phi(z).
 * Right-skewed estimates (g > 0) make the t statistic left-skewed: too many
 * "less" decisions, too few "greater".  The first-order term depends on k
 * and m only through k m: at a fixed total it is the number of batch means
 * m that the user fixes and k that makes them normal enough. */
static void edgeworth_terms(double g, double c, double m, double z, double *a, double *b)
{
    double phi = exp(-0.5 * z * z) / sqrt(2.0 * M_PI), z2 = z * z;
    *a = g * (2.0 * z2 + 1.0) / 6.0 * phi / sqrt(m);
    *b = z * (c * (z2 - 3.0) / 12.0 - g * g * (z2 * z2 + 2.0 * z2 - 3.0) / 18.0) * phi / m;
}

static int valid_shape(double g, double c)
{
    return isfinite(g) && isfinite(c) && c >= -2.0; /* excess kurtosis >= g^2 - 2 >= -2 */
}

int mcstat_diag_t_size(double skewness, double kurtosis, uint64_t k, uint64_t m, double alpha,
                            double size[2])
{
    MCSTAT_IEEE_SCOPE();
    if (!size || !valid_shape(skewness, kurtosis) || !valid_alpha(alpha) || k == 0)
        return MCSTAT_EINVAL;
    if (m < 2)
        return MCSTAT_ETOOFEW;
    double z = mcstat__norm_quantile(0.5 * alpha, 1), a, b;
    edgeworth_terms(skewness / sqrt((double)k), kurtosis / (double)k, (double)m, z, &a, &b);
    size[0] = fmin(1.0, fmax(0.0, 0.5 * alpha + a - b));
    size[1] = fmin(1.0, fmax(0.0, 0.5 * alpha - a - b));
    return MCSTAT_OK;
}

/* The rule: the smallest k for which both tails are within tolerance *
 * alpha/2 of alpha/2, i.e. |a| + |b| <= tolerance alpha / 2.  With s =
 * 1/sqrt(k), |a| = A s and |b| = B s^2 (A, B those of k = 1), so s is the
 * positive root of B s^2 + A s = e. */
int mcstat_diag_batch_size(double skewness, double kurtosis, uint64_t m, double alpha, double tolerance,
                                uint64_t *k)
{
    MCSTAT_IEEE_SCOPE();
    if (!k || !valid_shape(skewness, kurtosis) || !valid_alpha(alpha) || !(tolerance > 0.0 && tolerance < 1.0))
        return MCSTAT_EINVAL;
    if (m < 2)
        return MCSTAT_ETOOFEW;
    double z = mcstat__norm_quantile(0.5 * alpha, 1), A, B;
    edgeworth_terms(skewness, kurtosis, (double)m, z, &A, &B);
    A = fabs(A);
    B = fabs(B);
    double e = tolerance * 0.5 * alpha;
    if (A + B <= e) {
        *k = 1;
        return MCSTAT_OK;
    }
    /* s = 2e / (A + sqrt(A^2 + 4 B e)): the root without cancellation */
    double s = 2.0 * e / (A + sqrt(A * A + 4.0 * B * e));
    double kk = ceil(1.0 / (s * s) * (1.0 - 4.0 * DBL_EPSILON));
    if (!(kk < 9007199254740992.0))
        return MCSTAT_ETOOBIG;
    *k = kk < 1.0 ? 1 : (uint64_t)kk;
    return MCSTAT_OK;
}

/* ---- everything at once ---------------------------------------------------- */
/* Every size mcstat_diag_options has had, oldest first (options.c). */
static const uint32_t DIAG_SIZES[] = {MCSTAT_DIAG_OPTIONS_SIZE_0_1};
_Static_assert(sizeof(mcstat_diag_options) == MCSTAT_DIAG_OPTIONS_SIZE_0_1,
               "a grown mcstat_diag_options needs its size appended to DIAG_SIZES");

int mcstat_diag_options_init_size(mcstat_diag_options *opt, size_t size)
{
    const mcstat_diag_options d = MCSTAT_DIAG_OPTIONS_INIT;
    return mcstat__options_init(opt, size, &d, sizeof d, DIAG_SIZES, sizeof DIAG_SIZES / sizeof *DIAG_SIZES);
}

int mcstat_diag_compute(const double *x, size_t n, const mcstat_diag_options *opt, mcstat_diagnostics *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_diag_options o = MCSTAT_DIAG_OPTIONS_INIT;
    if (opt && mcstat__options_read(&o, sizeof o, opt, DIAG_SIZES, sizeof DIAG_SIZES / sizeof *DIAG_SIZES))
        return MCSTAT_EINVAL;
    if (!x || !out || !valid_alpha(o.alpha) || !(o.tolerance > 0.0 && o.tolerance < 1.0) ||
        !(o.tail_threshold > 0.0) || (o.k > 0 && o.k > n))
        return MCSTAT_EINVAL;
    size_t tk = o.tail_k ? (size_t)o.tail_k : default_tail_k(n);
    if (n < 2 * tk + 2 || n < 8)
        return MCSTAT_ETOOFEW;
    mcstat_moments mo;
    mcstat_moments_init(&mo);
    int st = mcstat_moments_add_array(&mo, x, n);
    if (st)
        return st;
    double sd = mcstat_moments_sd(&mo), mean = mcstat_moments_mean(&mo);
    if (!(sd > 10.0 * DBL_EPSILON * fabs(mean)))
        return MCSTAT_EDEGENERATE;

    mcstat_diagnostics d;
    memset(&d, 0, sizeof d);
    d.n = n;
    d.mean = mean;
    d.sd = sd;
    d.skewness = mcstat_moments_skewness(&mo);
    d.kurtosis = mcstat_moments_kurtosis(&mo);
    /* the standard errors of G1 and G2 under normality (Joanes & Gill 1998;
     * what SPSS and SAS print) */
    double nn = (double)n;
    d.skewness_se = sqrt(6.0 * nn * (nn - 1.0) / ((nn - 2.0) * (nn + 1.0) * (nn + 3.0)));
    d.kurtosis_se = 2.0 * d.skewness_se * sqrt((nn * nn - 1.0) / ((nn - 3.0) * (nn + 5.0)));
    /* the largest single share of the sum of squares: -> 0 like log(n)/n
     * for finite-variance data, stays O(1) for infinite variance */
    double dev = fmax(mo.max - mean, mean - mo.min) / sd;
    d.max_share = dev * dev / (nn - 1.0);

    d.tail_k = tk;
    size_t ku[2];
    if ((st = tail_index(x, n, tk, d.tail_index, ku)))
        return st;
    for (int i = 0; i < 2; i++)
        d.tail_index_se[i] = ku[i] ? d.tail_index[i] / sqrt((double)ku[i]) : NAN;
    d.heavy_tail = fmin(d.tail_index[0], d.tail_index[1]) < o.tail_threshold;

    d.k = o.k ? o.k : 1;
    d.m = o.m ? o.m : (o.k ? n / o.k : MCSTAT_DIAG_DEFAULT_M);
    if (d.m < 2)
        return MCSTAT_ETOOFEW;
    if ((st = mcstat_diag_t_size(d.skewness, d.kurtosis, d.k, d.m, o.alpha, d.t_size)) ||
        (st = mcstat_diag_batch_size(d.skewness, d.kurtosis, d.m, o.alpha, o.tolerance, &d.recommended_k)))
        return st;
    d.alpha = o.alpha;
    d.tolerance = o.tolerance;
    *out = d;
    return MCSTAT_OK;
}
