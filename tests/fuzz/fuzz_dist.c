/*
 * fuzz_dist.c - the t, chi-squared and F distribution functions and their
 * quantiles, on arguments decoded from bytes (fz_double: extreme, subnormal,
 * infinite and NaN values included).
 *
 * Input: a family byte (t, chi-squared, F), x, a second point x2, df1, df2,
 * p, the tail.  Invariants, where the call returns OK: probabilities in
 * [0, 1], log-probabilities <= 0 and exp(log P) = P; the two tails sum to 1;
 * the lower tail does not decrease from min(x, x2) to max(x, x2); the t
 * distribution is symmetric; for degrees of freedom in [1e-3, 1e15] (the
 * documented range) every call with valid arguments answers (MCSTAT_ENUMERIC
 * is a failure there: the header promises an answer), and a quantile is a
 * point whose tail probability brackets p between q (1 -+ 1e-13) (or its
 * neighbouring doubles), to 1e-9 relative: the quantile is right to 1e-13
 * relative wherever the tail is steep.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

typedef struct {
    int family;
    double df1, df2;
} dist;

static int cdf(const dist *d, double x, int upper, double *p)
{
    switch (d->family) {
    case 0: return mcstat_t_cdf(x, d->df1, upper, p);
    case 1: return mcstat_chisq_cdf(x, d->df1, upper, p);
    default: return mcstat_f_cdf(x, d->df1, d->df2, upper, p);
    }
}

static int logcdf(const dist *d, double x, int upper, double *p)
{
    switch (d->family) {
    case 0: return mcstat_t_logcdf(x, d->df1, upper, p);
    case 1: return mcstat_chisq_logcdf(x, d->df1, upper, p);
    default: return mcstat_f_logcdf(x, d->df1, d->df2, upper, p);
    }
}

static int quantile(const dist *d, double p, int upper, double *x)
{
    switch (d->family) {
    case 0: return mcstat_t_quantile(p, d->df1, upper, x);
    case 1: return mcstat_chisq_quantile(p, d->df1, upper, x);
    default: return mcstat_f_quantile(p, d->df1, d->df2, upper, x);
    }
}

static const char *NAME[3] = {"t", "chisq", "F"};

/* The tail probability at x, which must succeed. */
static double tail(const dist *d, double x, int upper)
{
    double p = NAN;
    int st = cdf(d, x, upper, &p);
    FZ_ASSERT(st == MCSTAT_OK, "%s cdf(%.17g; %.17g, %.17g) status %d", NAME[d->family], x, d->df1, d->df2, st);
    return p;
}

/* Degrees of freedom in the documented range [1e-3, 1e15]. */
static int df_documented(const dist *d)
{
    return d->df1 >= 1e-3 && d->df1 <= 1e15 && (d->family != 2 || (d->df2 >= 1e-3 && d->df2 <= 1e15));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    dist d;
    d.family = fz_u8(&in) % 3;
    double x = fz_double(&in), x2 = fz_double(&in);
    d.df1 = fz_double(&in);
    d.df2 = fz_double(&in);
    double p = fz_double(&in);
    uint8_t ub = fz_u8(&in);
    int upper = ub < 250 ? ub & 1 : (int)(int8_t)fz_u8(&in);
    const char *nm = NAME[d.family];
    if (fz_verbose())
        fprintf(stderr, "%s: x %a x2 %a df1 %a df2 %a p %a upper %d\n", nm, x, x2, d.df1, d.df2, p, upper);

    double P = -1.0, Q = -1.0, lp = 1.0, q;
    int st = cdf(&d, x, upper, &P);
    fz_check_status(st);
    if (st == MCSTAT_OK) {
        FZ_ASSERT(P >= 0.0 && P <= 1.0, "%s cdf(%.17g; %.17g, %.17g, upper %d) = %.17g", nm, x, d.df1, d.df2, upper,
                  P);
        FZ_ASSERT(!isnan(x) && !isnan(d.df1), "%s cdf OK on NaN", nm);
        /* log version */
        st = logcdf(&d, x, upper, &lp);
        FZ_ASSERT(st == MCSTAT_OK, "%s logcdf status %d where cdf is OK", nm, st);
        FZ_ASSERT(lp <= 0.0 && !isnan(lp), "%s logcdf = %.17g", nm, lp);
        if (P >= 1e-300)
            FZ_ASSERT(fabs(exp(lp) - P) <= 1e-10 * P, "%s exp(logcdf(%.17g; %.17g, %.17g)) = %.17g, cdf %.17g", nm, x,
                      d.df1, d.df2, exp(lp), P);
        /* Accuracy (monotonicity, symmetry, quantiles below) is promised for
         * degrees of freedom from 1e-3 up ("to 1e12 or more": checked to
         * 1e15).  Outside, e.g. t at df = 4.5e-308 gave P[T <= -3.4e91] = 0
         * and P[T <= -5e291] = 0.5 (the latter right): README.md. */
        int in_range = df_documented(&d);
        /* the other tail */
        if (upper == 0 || upper == 1) {
            st = cdf(&d, x, !upper, &Q);
            FZ_ASSERT(st == MCSTAT_OK, "%s other tail status %d", nm, st);
            FZ_ASSERT(fabs(P + Q - 1.0) <= 1e-12, "%s tails at %.17g (df %.17g, %.17g): %.17g + %.17g = 1 %+.3g", nm,
                      x, d.df1, d.df2, P, Q, P + Q - 1.0);
            /* monotone lower tail */
            double lo_x = fmin(x, x2), hi_x = fmax(x, x2), a, b;
            if (in_range && !isnan(x2) && cdf(&d, lo_x, 0, &a) == MCSTAT_OK && cdf(&d, hi_x, 0, &b) == MCSTAT_OK)
                FZ_ASSERT(a <= b * (1.0 + 1e-12), "%s cdf not monotone: F(%.17g) = %.17g > F(%.17g) = %.17g", nm,
                          lo_x, a, hi_x, b);
            if (d.family == 0 && in_range) {
                double r = tail(&d, -x, !upper);
                FZ_ASSERT(fabs(r - P) <= 1e-13 * P, "t not symmetric at %.17g (df %.17g): %.17g vs %.17g", x, d.df1,
                          P, r);
            }
        }
    } else {
        /* MCSTAT_ENUMERIC is "not expected" (mcstat.h): in the documented
         * range every valid call answers (F with a df of 0.001 gave it for
         * 1 in 1000 points until the small-parameter series). */
        int valid = !isnan(x) && (upper == 0 || upper == 1);
        FZ_ASSERT(st == MCSTAT_EINVAL || (st == MCSTAT_ENUMERIC && !(valid && df_documented(&d))),
                  "%s cdf(%.17g; %.17g, %.17g, upper %d) status %d", nm, x, d.df1, d.df2, upper, st);
        FZ_ASSERT(P == -1.0, "%s cdf wrote its output with status %d", nm, st);
    }

    q = -12345.0;
    st = quantile(&d, p, upper, &q);
    fz_check_status(st);
    if (st != MCSTAT_OK) {
        FZ_ASSERT(q == -12345.0, "%s quantile wrote its output with status %d", nm, st);
        int valid = p >= 0.0 && p <= 1.0 && (upper == 0 || upper == 1);
        FZ_ASSERT(st == MCSTAT_EINVAL || (st == MCSTAT_ENUMERIC && !(valid && df_documented(&d))),
                  "%s quantile(%.17g; %.17g, %.17g, upper %d) status %d", nm, p, d.df1, d.df2, upper, st);
        return 0;
    }
    FZ_ASSERT(p >= 0.0 && p <= 1.0, "%s quantile OK at p %.17g", nm, p);
    FZ_ASSERT(!isnan(q), "%s quantile(%.17g; %.17g, %.17g, upper %d) NaN", nm, p, d.df1, d.df2, upper);
    if (d.family > 0)
        FZ_ASSERT(q >= 0.0, "%s quantile %.17g < 0", nm, q);
    /* Not checked below DBL_MIN: there the chi-squared and F tails are
     * evaluated at x/2 or df1 x, which round in the subnormal range (the
     * answer at 5e-324 is that at 0); see README.md, what is left out. */
    if (!isfinite(q) || p < 1e-300 || (upper != 0 && upper != 1) || fabs(q) < 0x1p-1020)
        return 0;
    /* Only in the documented range (above); outside, e.g. F with df2 = 6e-152
     * (median near 10^(1/df2)), quantile and tail disagree: README.md. */
    if (!df_documented(&d))
        return 0;
    /* p lies between the tail probabilities at q (1 -+ 1e-13); where the tail
     * is steep (chi-squared at df 2.6e10: 1 ulp of q is 2.4e-10 of p) Newton
     * stops a few ulps away, which is still 1e-15 relative in q. */
    double below = fmin(nextafter(q, -INFINITY), q - 1e-13 * fabs(q));
    double above = fmax(nextafter(q, INFINITY), q + 1e-13 * fabs(q));
    double pb = tail(&d, below, upper), pa = tail(&d, above, upper);
    double lo = fmin(pb, pa), hi = fmax(pb, pa);
    FZ_ASSERT(lo <= p * (1.0 + 1e-9) && p <= hi * (1.0 + 1e-9) + 1e-300,
              "%s quantile(%.17g; %.17g, %.17g, upper %d) = %.17g: tail %.17g .. %.17g", nm, p, d.df1, d.df2, upper,
              q, lo, hi);
    return 0;
}
