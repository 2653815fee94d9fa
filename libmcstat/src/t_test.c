/*
 * t_test.c - one-sample t (section 2.1, eq. 1) and Welch's two-sample t
 * (section 2.3, eq. 3), on arrays and on accumulators.
 *
 * Differences of means are formed in double-double from the accumulators'
 * double-double means, then scaled by the accumulators' power of two, so
 * neither a 1e9 offset nor a 1e300 magnitude costs digits.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>

/* (a + b) 2^-e, rounded to double.  The sum is formed unscaled, as always;
 * only if it overflows (a mean of 1e300 minus a null value of 1.8e308: the
 * double-double became (-Inf, NaN) and the statistic NaN; found by
 * tests/fuzz/fuzz_bytes) is it formed again in the data's units, where it
 * cannot (both terms are then large, so e > 0 and scaling shrinks them).
 * Scaling first in every case would overflow the other way: mu0 = -50 with
 * subnormal data (e = -1026) scales to Inf, and Inf + x is (Inf, NaN). */
static double dd_add_scaled(mcstat_dd a, double b, int e)
{
    mcstat_dd s = dd_add(a, (mcstat_dd){b, 0.0});
    if (isfinite(s.hi))
        return scale2(s.hi, -e) + scale2(s.lo, -e);
    mcstat_dd as = {scale2(a.hi, -e), scale2(a.lo, -e)}, bs = {scale2(b, -e), 0.0};
    s = dd_add(as, bs);
    return s.hi + s.lo;
}

/* est - c * se in units of 2^e, est a double-double already in those units. */
double mcstat__ci_bound(mcstat_dd est, double c, double se, int e)
{
    if (isinf(c))
        return c > 0 ? -INFINITY : INFINITY;
    /* A critical value beyond 2^900 (df = 1 at alpha = 1e-308 gives -1.4e307)
     * would overflow Dekker's split in dd_two_prod into NaN (found by
     * tests/fuzz/fuzz_rows), and so does a product c se beyond 2^900 in these
     * units (t_test_1({0, 1e47}) at alpha = 1e-268: c = 6.4e267, se = 5e46:
     * the product's error term was Inf - Inf, a NaN interval with status
     * OK).  The estimate is then far below the product's rounding, so plain
     * doubles, scaled, suffice; a bound beyond DBL_MAX is -+Inf. */
    if (fabs(c) > 0x1p900 || !(fabs(c) * se <= 0x1p900))
        return scale2(scale2(-c, -900) * se + scale2(est.hi + est.lo, -900), e + 900);
    mcstat_dd p = dd_two_prod(-c, se);
    mcstat_dd b = dd_add(est, p);
    return scale2(b.hi + b.lo, e);
}

/* The t tests' arguments but the data's values, refused with a reason
 * (mcstat_last_error): y NULL only where the test has one sample. */
static int check_args(const void *x, const void *y, int two, double mu0, int alternative, double alpha,
                      const mcstat_result *out)
{
    if (!x)
        return mcstat__refuse(MCSTAT_EINVAL, "x is NULL");
    if (two && !y)
        return mcstat__refuse(MCSTAT_EINVAL, "y is NULL");
    if (!isfinite(mu0))
        return mcstat__refuse(MCSTAT_EINVAL, "mu0 must be finite, got %g", mu0);
    return mcstat__refuse_test_args(alternative, alpha, out);
}

/* The paired test's render guards (mcstat__t_test_paired_render): eps, the
 * larger |mean| of the two sides (in the differences' units), whether a
 * side or the differences may hide a rare value, the degrees of freedom. */
typedef struct {
    double eps, mmax, df;
    int hides;
} paired_guard;

static int t_test_1(const mcstat_moments *x, double mu0, int alternative, double alpha, const paired_guard *g,
                    mcstat_qcache *qc, mcstat_result *out)
{
    int st_args = check_args(x, NULL, 0, mu0, alternative, alpha, out);
    if (st_args)
        return st_args;
    int st = mcstat__moments_check(x);
    if (st == MCSTAT_EDEGENERATE && g) /* the guards decide what constant means */
        st = MCSTAT_OK;
    if (st)
        return st;
    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = MCSTAT_TEST_T_1;
    r.method = MCSTAT_METHOD_ANALYTIC;
    r.alternative = alternative;
    r.alpha = alpha;
    r.null_value = mu0;
    r.n[0] = x->n;

    double n = (double)x->n, df = n - 1.0, v;
    int e;
    mcstat__moments_var_scaled(x, &v, &e);
    if (g) { /* units in which the shift squares without overflow (Welch's) */
        double big = fmax(fmax(g->mmax, fabs(x->mean)), fabs(mu0));
        int eb = big > 0.0 ? ilogb(big) - 480 : e;
        if (eb > e) {
            v = scale2(v, 2 * (e - eb));
            e = eb;
        }
    }
    mcstat_dd mean = mcstat__moments_mean_dd(x);
    double diff = dd_add_scaled(mean, -mu0, e);
    if (g) {
        double lim = g->eps * scale2(g->mmax, -e), floor2 = lim * lim;
        int constant = v <= floor2;
        if (constant && !(fabs(diff) > lim))
            return MCSTAT_EDEGENERATE;
        v = fmax(v, floor2);
        if (constant || g->hides)
            v = fmax(v, diff * diff * mcstat__rule3_ratio(n));
        df = g->df;
    }
    double se = sqrt(v / n); /* units of 2^e */
    r.statistic = diff / se;
    r.df[0] = df;
    r.estimate[0] = x->mean;
    r.std_error = scale2(se, e);

    mcstat_tails t;
    if (qc)
        mcstat__qcache_use(qc, MCSTAT_Q_T, df, 0.0);
    if ((st = mcstat__t_tails(r.statistic, df, &t)) ||
        (st = mcstat__finish(&r, &t, qc ? mcstat__qcache_quantile : NULL, qc)))
        return st;
    if (!qc) { /* no intervals asked for */
        *out = r;
        return MCSTAT_OK;
    }
    mcstat_dd ms = {scale2(mean.hi, -e), scale2(mean.lo, -e)};
    r.conf_int[0] = mcstat__ci_bound(ms, r.critical[1], se, e);
    r.conf_int[1] = mcstat__ci_bound(ms, r.critical[0], se, e);
    *out = r;
    return MCSTAT_OK;
}

int mcstat__t_test_1(const mcstat_moments *x, double mu0, int alternative, double alpha, mcstat_qcache *qc,
                     mcstat_result *out)
{
    return t_test_1(x, mu0, alternative, alpha, NULL, qc, out);
}

/* ---- the render guards (mcstat.h, MCSTAT_PIXELS_RENDER) ----------------------
 * One formula for the per-pixel block path (pixels.c) and the single call
 * here, in the units the caller's numbers are in (a scale common to both
 * sides: it cancels from every comparison and ratio below). */
double mcstat__rule3_ratio(double n)
{
    /* pi = 1 - 0.05^(1/n), the one-sided 95% upper bound on the rate of a
     * value never seen in n draws; (1 - pi) / pi, pi from expm1 so that
     * large n keeps its digits */
    double pi = -expm1(log(0.05) / n);
    return (1.0 - pi) / pi;
}

static int t_test_2(const mcstat_moments *x, const mcstat_moments *y, double mu0, int alternative, double alpha,
                    int pooled, const mcstat__render_guard *rg, mcstat_qcache *qc, mcstat_result *out)
{
    int st_args = check_args(x, y, 1, mu0, alternative, alpha, out);
    if (st_args)
        return st_args;
    int st = mcstat__moments_check(x);
    if (st == MCSTAT_EDEGENERATE) /* both tests need spread only in the pair (R's rule) */
        st = MCSTAT_OK;
    if (st)
        return st;
    st = mcstat__moments_check(y);
    if (st == MCSTAT_EDEGENERATE)
        st = MCSTAT_OK;
    if (st)
        return st;
    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = pooled ? MCSTAT_TEST_T_2_POOLED : MCSTAT_TEST_T_2;
    r.method = MCSTAT_METHOD_ANALYTIC;
    r.alternative = alternative;
    r.alpha = alpha;
    r.null_value = mu0;
    r.n[0] = x->n;
    r.n[1] = y->n;

    double nx = (double)x->n, ny = (double)y->n, vx, vy;
    int ex, ey;
    mcstat__moments_var_scaled(x, &vx, &ex);
    mcstat__moments_var_scaled(y, &vy, &ey);
    int e = ex > ey ? ex : ey;
    if (rg) {
        /* The guards floor a side's variance at the squared shift: in units
         * of 2^e, |mean_x - mean_y - mu0| must square without overflow even
         * when the spread is far below the means or mu0 (constant sides of
         * 1e-296 against mu0 = -2e303 made the statistic inf/inf). */
        double big = fmax(fmax(fabs(x->mean), fabs(y->mean)), fabs(mu0));
        int eb = big > 0.0 ? ilogb(big) - 480 : e;
        e = eb > e ? eb : e;
    }
    double a = scale2(vx / nx, 2 * (ex - e)), b = scale2(vy / ny, 2 * (ey - e));
    double se = sqrt(a + b); /* units of 2^e */
    if (pooled) {
        /* Student: the pooled variance (M2x + M2y)/(nx + ny - 2), as R's
         * t.test(var.equal = TRUE) forms it from the two variances */
        double df = nx + ny - 2.0;
        double sp2 = scale2(vx * (nx - 1.0), 2 * (ex - e)) / df + scale2(vy * (ny - 1.0), 2 * (ey - e)) / df;
        se = sqrt(sp2 * (1.0 / nx + 1.0 / ny));
    }
    mcstat_dd mx = mcstat__moments_mean_dd(x), my = mcstat__moments_mean_dd(y);
    mcstat_dd diff = dd_add(mx, dd_neg(my)), ds;
    if (isfinite(diff.hi)) {
        ds = (mcstat_dd){scale2(diff.hi, -e), scale2(diff.lo, -e)};
        ds = dd_fast_two_sum(ds.hi, ds.lo);
    } else { /* means near -+DBL_MAX: the difference overflows unscaled (the
              * statistic was NaN; found by tests/fuzz/fuzz_rows), not in
              * the units of the data, where e is then near 1024 */
        mcstat_dd a = {scale2(mx.hi, -e), scale2(mx.lo, -e)}, b = {scale2(my.hi, -e), scale2(my.lo, -e)};
        ds = dd_add(a, dd_neg(b));
    }
    double mmax = fmax(fabs(x->mean), fabs(y->mean));
    double dfr = NAN; /* the render guards' degrees of freedom */
    if (rg) {
        double vxs = scale2(vx, 2 * (ex - e)), vys = scale2(vy, 2 * (ey - e)), sh;
        if (isfinite(diff.hi))
            sh = dd_add_scaled(diff, -mu0, e);
        else {
            mcstat_dd t0 = dd_add(ds, (mcstat_dd){scale2(-mu0, -e), 0.0});
            sh = t0.hi + t0.lo;
        }
        mcstat__render_welch g;
        mcstat__render_adjust(rg, nx, ny, mcstat__rule3_ratio(nx), mcstat__rule3_ratio(ny), vxs, vys,
                              scale2(mmax, -e), sh, &g);
        if (g.both_constant && !g.differ)
            return MCSTAT_EDEGENERATE;
        a = g.vx / nx;
        b = g.vy / ny;
        se = sqrt(a + b);
        dfr = g.df;
    } else {
        /* Both samples constant to within rounding (one constant sample is
         * fine, as in R): the larger standard deviation below 10 eps
         * max|mean|. */
        double sdmax = sqrt(fmax(scale2(vx, 2 * (ex - e)), scale2(vy, 2 * (ey - e))));
        if (!(se > 0.0) || sdmax < 10.0 * DBL_EPSILON * scale2(mmax, -e))
            return MCSTAT_EDEGENERATE;
    }
    if (isfinite(diff.hi)) {
        r.statistic = dd_add_scaled(diff, -mu0, e) / se;
    } else {
        mcstat_dd t0 = dd_add(ds, (mcstat_dd){scale2(-mu0, -e), 0.0});
        r.statistic = (t0.hi + t0.lo) / se;
    }
    /* Welch-Satterthwaite, normalised by the larger term so nothing over- or
     * underflows: df = (a + b)^2 / (a^2/(nx-1) + b^2/(ny-1)). */
    double m = fmax(a, b), ra = a / m, rb = b / m;
    double df = pooled ? nx + ny - 2.0
                : rg       ? dfr
                           : (ra + rb) * (ra + rb) / (ra * ra / (nx - 1.0) + rb * rb / (ny - 1.0));
    r.df[0] = df;
    r.estimate[0] = x->mean;
    r.estimate[1] = y->mean;
    r.std_error = scale2(se, e);

    mcstat_tails t;
    if (qc)
        mcstat__qcache_use(qc, MCSTAT_Q_T, df, 0.0);
    if ((st = mcstat__t_tails(r.statistic, df, &t)) ||
        (st = mcstat__finish(&r, &t, qc ? mcstat__qcache_quantile : NULL, qc)))
        return st;
    if (!qc) {
        *out = r;
        return MCSTAT_OK;
    }
    r.conf_int[0] = mcstat__ci_bound(ds, r.critical[1], se, e);
    r.conf_int[1] = mcstat__ci_bound(ds, r.critical[0], se, e);
    *out = r;
    return MCSTAT_OK;
}

int mcstat__t_test_2(const mcstat_moments *x, const mcstat_moments *y, double mu0, int alternative,
                     double alpha, mcstat_qcache *qc, mcstat_result *out)
{
    return t_test_2(x, y, mu0, alternative, alpha, 0, NULL, qc, out);
}

int mcstat__t_test_2_pooled(const mcstat_moments *x, const mcstat_moments *y, double mu0, int alternative,
                            double alpha, mcstat_qcache *qc, mcstat_result *out)
{
    return t_test_2(x, y, mu0, alternative, alpha, 1, NULL, qc, out);
}

int mcstat__t_test_2_render(const mcstat_moments *x, const mcstat_moments *y, const mcstat__render_guard *rg,
                            double mu0, int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out)
{
    return t_test_2(x, y, mu0, alternative, alpha, 0, rg, qc, out);
}

/* The public calls: a fresh cache, which still answers the second
 * two-sided critical value of a t from the first (c and -c). */
int mcstat_t_test_1_moments(const mcstat_moments *x, double mu0, int alternative, double alpha,
                            mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__t_test_1(x, mu0, alternative, alpha, &qc, out);
}

int mcstat_t_test_2_moments(const mcstat_moments *x, const mcstat_moments *y, double mu0,
                            int alternative, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__t_test_2(x, y, mu0, alternative, alpha, &qc, out);
}

int mcstat_t_test_1(const double *x, size_t n, double mu0, int alternative, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    int st_args = check_args(x, NULL, 0, mu0, alternative, alpha, out);
    if (st_args)
        return st_args;
    mcstat_moments m;
    mcstat_moments_init(&m);
    int st = mcstat_moments_add_array(&m, x, n);
    return st ? st : mcstat_t_test_1_moments(&m, mu0, alternative, alpha, out);
}

int mcstat_t_test_2(const double *x, size_t nx, const double *y, size_t ny, double mu0, int alternative,
                    double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    int st_args = check_args(x, y, 1, mu0, alternative, alpha, out);
    if (st_args)
        return st_args;
    mcstat_moments mx, my;
    int st = mcstat__moments_of_two(x, nx, y, ny, &mx, &my);
    return st ? st : mcstat_t_test_2_moments(&mx, &my, mu0, alternative, alpha, out);
}

int mcstat_t_test_2_pooled_moments(const mcstat_moments *x, const mcstat_moments *y, double mu0, int alternative,
                                   double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__t_test_2_pooled(x, y, mu0, alternative, alpha, &qc, out);
}

int mcstat_t_test_2_pooled(const double *x, size_t nx, const double *y, size_t ny, double mu0, int alternative,
                           double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    int st_args = check_args(x, y, 1, mu0, alternative, alpha, out);
    if (st_args)
        return st_args;
    mcstat_moments mx, my;
    int st = mcstat__moments_of_two(x, nx, y, ny, &mx, &my);
    return st ? st : mcstat_t_test_2_pooled_moments(&mx, &my, mu0, alternative, alpha, out);
}

/* The differences (x_i - y_i) * 2^-s into m, a block at a time (no
 * allocation).  MCSTAT_ENONFINITE when a difference overflows. */
static int add_differences(mcstat_moments *m, const double *x, const double *y, size_t n, int s)
{
    double d[256];
    mcstat_moments_init(m);
    for (size_t i = 0; i < n;) {
        size_t k = n - i < 256 ? n - i : 256;
        for (size_t j = 0; j < k; j++)
            d[j] = s ? scale2(x[i + j], -s) - scale2(y[i + j], -s) : x[i + j] - y[i + j];
        int st = mcstat_moments_add_array(m, d, k);
        if (st)
            return st;
        i += k;
    }
    return MCSTAT_OK;
}

/* A side whose standard deviation is at most lim (unscaled). */
static int spread_at_most(const mcstat_moments *m, double lim)
{
    double v;
    int e;
    mcstat__moments_var_scaled(m, &v, &e);
    return !(scale2(sqrt(v), e) > lim);
}

/* The paired test, with the render guards when eps >= 0 (eps < 0: none). */
static int t_test_paired(const double *x, const double *y, size_t n, double mu0, int alternative, double alpha,
                         double eps, mcstat_qcache *qc, mcstat_result *out)
{
    for (size_t i = 0; i < n; i++) /* NaN or Inf in the data, not an overflowing difference */
        if (!isfinite(x[i]) || !isfinite(y[i]))
            return MCSTAT_ENONFINITE;
    if (n < 2)
        return MCSTAT_ETOOFEW;
    paired_guard guard, *g = NULL;
    /* Each difference is one rounding of the exact x_i - y_i.  Where one
     * overflows (x near DBL_MAX, y near -DBL_MAX) the test runs on the
     * differences halved, against mu0 halved: t, df and p are unchanged,
     * the estimate, standard error and interval are doubled back. */
    int s = 0;
    mcstat_moments m;
    int st = add_differences(&m, x, y, n, 0);
    if (st == MCSTAT_ENONFINITE) {
        s = 1;
        st = add_differences(&m, x, y, n, s);
    }
    if (st)
        return st;
    if (eps >= 0.0) {
        /* Welch's guards carried to the differences: a side that is
         * constant or shows at most one value besides zeros may hide a rare
         * value, and so may differences that do */
        mcstat_moments mx, my;
        uint64_t hx = 0, hy = 0, hd = 0, lone = 0;
        for (size_t i = 0; i < n; i++) {
            hx += x[i] != 0.0;
            hy += y[i] != 0.0;
            hd += x[i] != y[i];
            lone += (x[i] == 0.0) != (y[i] == 0.0);
        }
        mcstat_moments_init(&mx);
        mcstat_moments_init(&my);
        if ((st = mcstat_moments_add_array(&mx, x, n)) || (st = mcstat_moments_add_array(&my, y, n)))
            return st;
        double mmax = fmax(fabs(mx.mean), fabs(my.mean)), lim = eps * mmax;
        guard.eps = eps;
        guard.mmax = scale2(mmax, -s);
        int cx = spread_at_most(&mx, lim), cy = spread_at_most(&my, lim);
        /* ... and so may a side that is zero in a seed where the other is
         * not: the pair's difference is then all the other side's value,
         * and a sampler that reaches a light through rare paths shows
         * zeros and small values while its mean is carried by spikes it has
         * not drawn (light tree off against on, same seeds: the paired
         * test's smaller variance found them in half the comparisons at
         * 16 seeds; bench/RESULTS_cycles_paired.md).  Zeros in the same
         * seeds on both sides (paths the change left alone) are not. */
        guard.hides = hx <= 1 || hy <= 1 || hd <= 1 || cx || cy || lone > 0;
        /* Hsu's rule as Welch's guards take it: a sample with zeros has its
         * spread from its h nonzero values, h - 1 degrees of freedom; the
         * fewest among the sides and the differences.  The t of a side that
         * shows few of the rare values making up its mean is far from
         * Student's at the nominal n - 1 (light tree off against on, same
         * seeds, bench/RESULTS_cycles_paired.md). */
        double nn = (double)n, nu = nn - 1.0;
        const uint64_t h[3] = {cx ? n : hx, cy ? n : hy, hd};
        for (int k = 0; k < 3; k++)
            if (h[k] >= 2 && h[k] < n && (double)h[k] - 1.0 < nu)
                nu = (double)h[k] - 1.0;
        guard.df = nu;
        g = &guard;
    }
    mcstat_result r;
    if ((st = t_test_1(&m, scale2(mu0, -s), alternative, alpha, g, qc, &r)))
        return st;
    r.test = MCSTAT_TEST_T_PAIRED;
    r.n[1] = r.n[0];
    r.null_value = mu0;
    r.estimate[0] = scale2(r.estimate[0], s);
    r.std_error = scale2(r.std_error, s);
    r.conf_int[0] = scale2(r.conf_int[0], s);
    r.conf_int[1] = scale2(r.conf_int[1], s);
    *out = r;
    return MCSTAT_OK;
}

int mcstat__t_test_paired(const double *x, const double *y, size_t n, double mu0, int alternative, double alpha,
                          mcstat_qcache *qc, mcstat_result *out)
{
    return t_test_paired(x, y, n, mu0, alternative, alpha, -1.0, qc, out);
}

int mcstat__t_test_paired_render(const double *x, const double *y, size_t n, double eps, double mu0,
                                 int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out)
{
    return t_test_paired(x, y, n, mu0, alternative, alpha, eps, qc, out);
}

int mcstat_t_test_paired(const double *x, const double *y, size_t n, double mu0, int alternative, double alpha,
                         mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat__error_clear();
    int st_args = check_args(x, y, 1, mu0, alternative, alpha, out);
    if (st_args)
        return st_args;
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    return mcstat__t_test_paired(x, y, n, mu0, alternative, alpha, &qc, out);
}
