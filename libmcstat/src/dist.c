/*
 * dist.c - Student t, chi-squared and F: both tails, their logarithms, and
 * quantiles, for any positive degrees of freedom.
 *
 * Tails come from the incomplete beta and gamma functions of special.c (never
 * 1 - P for a small upper tail).  GSL's own versions are not used because
 * gsl_cdf_tdist_P/Q switch to a Cornish-Fisher expansion for df > 30 that is
 * only ~2e-7 relative in the tails, and the GSL inverses fail at Monte Carlo
 * sizes (gsl_cdf_chisq_Qinv is wrong by tens of percent for df >= 1e5,
 * gsl_cdf_fdist_Pinv returns NaN for df >= 1e5, gsl_cdf_tdist_Pinv NaN for
 * p <= 1e-100 at small df).
 *
 * Each density is simple in terms of the incomplete functions' prefactor K:
 *   t:    f(t) = K / |t|,  K = x^(df/2) y^(1/2) / B(df/2, 1/2), x = df/(df+t^2)
 *   F:    f(F) = K / F,    K = x^a y^b / B(a, b), a = df1/2, b = df2/2
 *   chi2: f(x) = a K / x,  K = (x/2)^a e^(-x/2) / Gamma(a+1), a = df/2
 * so the quantile solver works with z = log x, where Newton's derivative is
 * d log T / dz = -+ x f(x) / T(x): smooth, and exact in the power-law tails.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>

#define LOG_HALF (-0.69314718055994530942)
#define Z_MIN (-708.39) /* log of DBL_MIN: a quantile below the smallest normal is returned as 0 */
#define Z_MAX (709.78) /* log of DBL_MAX */

static int valid_df(double df)
{
    return df > 0.0 && isfinite(df);
}

/* ---- Student t ---------------------------------------------------------- */

/* x = df/(df+t^2) and y = t^2/(df+t^2), each to a few ulps (|t| < 1e150). */
static void t_xy(double at, double df, double *x, double *y)
{
    double t2 = at * at, s = df + t2;
    *x = df / s;
    *y = t2 / s;
}

/* log P[T > u] for u >= 1e150, where P = u^-df df^(df/2-1) / B(df/2, 1/2)
 * to relative O(df/u^2), i.e. exactly in double precision. */
static double t_log_upper_far(double u, double df)
{
    double a = 0.5 * df, b = 0.5;
    /* log B(a, b) by Stirling with remainders (no cancellation concerns: the
     * result is only needed to relative accuracy, and it is dwarfed by df log u).
     * (a - 1/2) log a - (a + b - 1/2) log(a + b) is written as
     * -(a - 1/2) log1p(b/a) - b log(a + b), and -df log u + (a - 1) log df as
     * -df log(u / sqrt(df)) - log df: the plain forms overflow to Inf - Inf = NaN
     * for df near DBL_MAX (found by tests/fuzz/fuzz_dist). */
    double lb = 0.5 * log(2.0 * M_PI) - (a - 0.5) * log1p(b / a) + (b - 0.5) * log(b) - b * log(a + b)
              + mcstat__log_gammastar(a) + mcstat__log_gammastar(b) - mcstat__log_gammastar(a + b);
    return -df * (log(u) - 0.5 * log(df)) - log(df) - lb;
}

/* log P[T > u] for u >= 1e150 but df > (u / 1e10)^2, so large (> 1e280) that
 * T is normal to far below the probability's underflow: the t density's
 * exponent -(df+1)/2 log1p(r^2), r = u/sqrt(df), over Mills' ratio r sqrt(2 pi).
 * Only the logarithm is meaningful here (P itself is 0 in double); it keeps
 * the leading terms, so its relative error is O(1/r^2 + 1/df). */
static double t_log_upper_huge_df(double u, double df)
{
    double r = u / sqrt(df);
    return -0.5 * (df + 1.0) * log1p(r * r) - log(r) - 0.5 * log(2.0 * M_PI);
}

/* P[|T| <= u] = I_y(1/2, df/2), y = u^2/(df+u^2), by the hypergeometric
 * series I_y(p,q) = y^p x^q / (p B(p,q)) * sum_j c_j, c_0 = 1,
 * c_{j+1} = c_j (p+q+j)/(p+1+j) y (DLMF 8.17.8).  Every term is positive, so
 * the sum is accurate to a few ulps; for y <= 1/2 it converges in at most ~60
 * terms (about 20 at Monte Carlo df), where the continued fraction near the
 * centre needs O(sqrt df) costly steps.  Returns 0 if it did not converge. */
static int t_central(double df, double x, double y, double *s, double *logk)
{
    const double A = 0.5 * df + 0.5;
    double term = 1.0, sum = 1.0;
    for (int j = 0; j < 200; j++) {
        term *= (A + j) / (1.5 + j) * y;
        sum += term;
        if (term <= 0.25 * DBL_EPSILON * sum) {
            *logk = mcstat__log_beta_prefactor(0.5, 0.5 * df, y, x);
            *s = exp(*logk + M_LN2) * sum;
            return 1;
        }
    }
    return 0;
}

/* Both tails of T at t; logk = log(|t| f(t)), the incomplete beta's
 * prefactor, for the quantile solver. */
int mcstat__t_tails(double t, double df, mcstat_tails *out)
{
    if (isnan(t) || !(df > 0.0)) /* a caller's statistic gone wrong: never a NaN p-value with OK */
        return MCSTAT_ENUMERIC;
    if (t == 0.0) {
        out->p = out->q = 0.5;
        out->logp = out->logq = LOG_HALF;
        out->logk = -INFINITY;
        return MCSTAT_OK;
    }
    double at = fabs(t), up, logup, other, logother, logk;
    if (isinf(at)) {
        up = 0.0; logup = -INFINITY; other = 1.0; logother = 0.0; logk = -INFINITY;
    } else if (at < 1e150) {
        double x, y, c;
        mcstat_tails b;
        t_xy(at, df, &x, &y);
        /* The bulk (|t| below ~2, where every test under H0 spends most of
         * its time, and the critical values at alpha = 0.05): the central
         * probability c by its series; the upper tail (1 - c)/2 >= 0.02 then
         * carries at most c/(1-c) <= 24 times c's few-ulp relative error
         * (about 1e-14). */
        if (y <= 0.5 && at <= 2.5 && t_central(df, x, y, &c, &logk) && c <= 0.96) {
            up = 0.5 - 0.5 * c;
            logup = log(up);
            other = 0.5 + 0.5 * c;
            logother = log(other);
            goto done;
        }
        /* P[T > |t|] = I_x(df/2, 1/2) / 2;  P[T <= |t|] = 1/2 + I_y(1/2, df/2) / 2 */
        int st = mcstat__beta_inc(0.5 * df, 0.5, x, y, &b);
        if (st)
            return st;
        up = 0.5 * b.p;
        logup = LOG_HALF + b.logp;
        other = 0.5 + 0.5 * b.q;
        logother = log1p(-up);
        logk = b.logk;
    } else {
        logup = at / sqrt(df) >= 1e10 ? t_log_upper_far(at, df) : t_log_upper_huge_df(at, df);
        up = exp(logup);
        other = 1.0 - up;
        logother = log1p(-up);
        logk = log(df) + logup; /* u f(u) = df P[T > u] in the power-law tail */
    }
done:
    out->logk = logk;
    if (t > 0.0) {
        out->q = up; out->logq = logup; out->p = other; out->logp = logother;
    } else {
        out->p = up; out->logp = logup; out->q = other; out->logq = logother;
    }
    return MCSTAT_OK;
}

/* ---- chi-squared ------------------------------------------------------- */

/* Both tails of chi-squared at x; logk = log(x f(x)) = log(a) + the
 * incomplete gamma's prefactor. */
int mcstat__chisq_tails(double x, double df, mcstat_tails *out)
{
    if (x <= 0.0) {
        out->p = 0.0; out->logp = -INFINITY; out->q = 1.0; out->logq = 0.0; out->logk = -INFINITY;
        return MCSTAT_OK;
    }
    int st = mcstat__gamma_inc(0.5 * df, 0.5 * x, out);
    out->logk += log(0.5 * df);
    return st;
}

/* ---- F ----------------------------------------------------------------- */

/* The incomplete beta's arguments for F at f: x = df1 f / (df1 f + df2),
 * y = df2 / (df1 f + df2), and the deviations u_x = df2 (f-1)/(df1 f + df2),
 * u_y = df1 (1-f)/(df1 f + df2), all without overflow.  The deviations are
 * formed from f - 1 (exact near 1): at large df F lives within 1e-7 of 1, and
 * going through x would round away the digits that matter. */
typedef struct {
    double x, y, ux, uy;
} f_args;

static f_args f_xy(double f, double df1, double df2)
{
    f_args a;
    double r = (df1 / df2) * f; /* may overflow to Inf or underflow to 0 */
    double fm1 = f - 1.0;
    if (r <= 1.0) {
        a.x = r / (1.0 + r);
        a.y = 1.0 / (1.0 + r);
        a.ux = fm1 / (1.0 + r);
        a.uy = -(df1 / df2) * fm1 / (1.0 + r);
    } else {
        double s = (df2 / df1) / f;
        a.x = 1.0 / (1.0 + s);
        a.y = s / (1.0 + s);
        a.ux = s * fm1 / (1.0 + s);
        a.uy = -(fm1 / f) / (1.0 + s);
    }
    return a;
}

/* When one df exceeds the other by F_LIMIT, F is a scaled chi-squared to
 * double precision (the tails change by a relative O(z^2 d_small/d_large)):
 * F -> chi2(df1)/df1 as df2 -> Inf, F -> df2/chi2(df2) as df1 -> Inf.  The
 * incomplete beta's fraction does not converge usefully there. */
#define F_LIMIT 1e20

/* The far tails of F by the leading term of DLMF 8.17.8 (see below): the
 * upper tail (upper = 1, lf = -log f) where y ~ (df2/df1)/f < 1e-300, the
 * lower one (lf = log f) where x ~ (df1/df2) f < 1e-300. */
static int f_far(double a, double b, int upper, double lf, mcstat_tails *out)
{
    double c = a + b, small = upper ? b : a, big = upper ? a : b;
    double lc = mcstat__log_beta_prefactor_u(a, b, a / c, b / c, 0.0, 0.0);
    double lv = c * log1p(small / big) + small * lf - log(small) + lc;
    if (!(lv < 0.0))
        lv = 0.0; /* only by rounding, where the other tail is below an ulp */
    double v = exp(lv), other = -expm1(lv);
    double lother = other < 0.5 ? log(other) : log1p(-v);
    if (upper) {
        out->q = v; out->logq = lv; out->p = other; out->logp = lother;
    } else {
        out->p = v; out->logp = lv; out->q = other; out->logq = lother;
    }
    out->logk = lv + log(small); /* x f(x) = K = small * tail, to O(y) */
    return MCSTAT_OK;
}

int mcstat__f_tails(double f, double df1, double df2, mcstat_tails *out)
{
    if (f <= 0.0) {
        out->p = 0.0; out->logp = -INFINITY; out->q = 1.0; out->logq = 0.0; out->logk = -INFINITY;
        return MCSTAT_OK;
    }
    if (isinf(f)) {
        out->p = 1.0; out->logp = 0.0; out->q = 0.0; out->logq = -INFINITY; out->logk = -INFINITY;
        return MCSTAT_OK;
    }
    if (df2 >= F_LIMIT * df1)
        return mcstat__chisq_tails(df1 * f, df1, out);
    if (df1 >= F_LIMIT * df2) {
        mcstat_tails c; /* P[F <= f] = P[chi2(df2) >= df2 / f]; x f(x) carries over */
        int st = mcstat__chisq_tails(df2 / f, df2, &c);
        out->p = c.q; out->logp = c.logq; out->q = c.p; out->logq = c.logp; out->logk = c.logk;
        return st;
    }
    /* Far out the beta argument on the small side leaves the normal range:
     * F(3.5e13, 0.001) at f = 1.2e307 has y = 2e-324, rounded to 0, and P
     * came out 1 where it is 0.3.  There I_y(b, a) = y^b x^a / (b B(a, b))
     * (1 + O((a+b) y)) (DLMF 8.17.8) with x^a = 1 to double precision, and
     * log y = log(b/a) - log f - O(y): from the prefactor at the centre
     * (x, y) = (a, b)/(a+b),
     *   log Q = (a+b) log1p(b/a) - b log f - log b + log K(centre),
     * and likewise log P as f -> 0. */
    double a = 0.5 * df1, b = 0.5 * df2;
    double s_up = (df2 / df1) / f, r_lo = (df1 / df2) * f; /* y ~ s_up, x ~ r_lo there */
    if (s_up < 1e-300 || r_lo < 1e-300) {
        int upper = s_up < 1e-300;
        return f_far(a, b, upper, upper ? -log(f) : log(f), out);
    }
    f_args g = f_xy(f, df1, df2);
    return mcstat__beta_inc_u(a, b, g.x, g.y, g.ux, g.uy, out);
}

/* ---- the quantile solver ------------------------------------------------ */

typedef struct {
    int kind; /* 0 t (on u > 0, upper tail of T), 1 chi-squared, 2 F */
    double df1, df2;
} dist_ctx;

static int eval_tails(const dist_ctx *d, double x, mcstat_tails *t)
{
    switch (d->kind) {
    case 0: return mcstat__t_tails(x, d->df1, t);
    case 1: return mcstat__chisq_tails(x, d->df1, t);
    default: return mcstat__f_tails(x, d->df1, d->df2, t);
    }
}

/* L(z) = log T(e^z) - log p, T the chosen tail; also returns L'(z). */
static double log_gamma(double a);

/* Chi-squared tails at x = e^z where x is not a normal double: the leading
 * terms in log x, exact to double precision there (x < DBL_MIN: P(a, x/2) =
 * K (1 + O(x)); x > DBL_MAX: Q(a, x/2) = K a / (x/2) (1 + O(a/x)), with K =
 * (x/2)^a e^(-x/2) / Gamma(a+1)). */
static int chisq_tails_z(double z, double df, mcstat_tails *t)
{
    if (z >= Z_MIN && z <= Z_MAX)
        return mcstat__chisq_tails(exp(z), df, t);
    double a = 0.5 * df, lh = z - M_LN2, h = exp(lh);
    double lk = a * lh - h - log_gamma(a + 1.0);
    if (z < 0.0) {
        t->logp = lk;
        t->p = exp(lk);
        t->q = 1.0 - t->p;
        t->logq = log1p(-t->p);
    } else {
        t->logq = lk + log(a) - lh;
        t->q = exp(t->logq);
        t->p = 1.0 - t->q;
        t->logp = log1p(-t->q);
    }
    t->logk = log(a) + lk;
    return MCSTAT_OK;
}

/* F tails at f = e^z where f is not a normal double (z < Z_MIN or > Z_MAX),
 * as mcstat__f_tails would compute them with f - 1 = -1 or f, from log f. */
static int f_tails_z(double z, double df1, double df2, mcstat_tails *out)
{
    if (z >= Z_MIN && z <= Z_MAX)
        return mcstat__f_tails(exp(z), df1, df2, out);
    if (df2 >= F_LIMIT * df1)
        return chisq_tails_z(log(df1) + z, df1, out);
    if (df1 >= F_LIMIT * df2) {
        mcstat_tails c;
        int st = chisq_tails_z(log(df2) - z, df2, &c);
        out->p = c.q; out->logp = c.logq; out->q = c.p; out->logq = c.logp; out->logk = c.logk;
        return st;
    }
    double a = 0.5 * df1, b = 0.5 * df2;
    double lr = log(df1 / df2) + z; /* log of r = (df1/df2) f; y ~ 1/r, x ~ r */
    const double l300 = -690.77552789821368; /* log 1e-300, as in mcstat__f_tails */
    if (-lr < l300)
        return f_far(a, b, 1, -z, out);
    if (lr < l300)
        return f_far(a, b, 0, z, out);
    double r = exp(lr);
    f_args g;
    if (r <= 1.0) { /* f tiny: f - 1 = -1 */
        g.x = r / (1.0 + r);
        g.y = 1.0 / (1.0 + r);
        g.ux = -1.0 / (1.0 + r);
        g.uy = (df1 / df2) / (1.0 + r);
    } else { /* f huge: (f - 1)/f = 1 */
        double sv = 1.0 / r;
        g.x = 1.0 / (1.0 + sv);
        g.y = sv / (1.0 + sv);
        g.ux = (df2 / df1) / (1.0 + sv);
        g.uy = -1.0 / (1.0 + sv);
    }
    return mcstat__beta_inc_u(a, b, g.x, g.y, g.ux, g.uy, out);
}

static int eval_L(const dist_ctx *d, double z, int upper, double logp, double *L, double *dL)
{
    mcstat_tails t;
    int st;
    if (z >= Z_MIN && z <= Z_MAX)
        st = eval_tails(d, exp(z), &t);
    else if (d->kind == 1) /* only the log quantiles go here */
        st = chisq_tails_z(z, d->df1, &t);
    else if (d->kind == 2)
        st = f_tails_z(z, d->df1, d->df2, &t);
    else
        st = MCSTAT_ENUMERIC;
    if (st)
        return st;
    double logT = upper ? t.logq : t.logp;
    *L = logT - logp;
    double slope = exp(t.logk - logT); /* x f(x) / T(x) */
    *dL = upper ? -slope : slope;
    return MCSTAT_OK;
}

/* Solves T(x) = p for x > 0, T the upper (decreasing) or lower (increasing)
 * tail, by Newton's method in z = log x inside a bracket that is widened
 * geometrically until it holds the root.  A Newton step is taken when it
 * stays inside the bracket and the previous one at least halved |L|;
 * otherwise the bracket is bisected (far out on a steep log-tail Newton
 * alone would crawl).  *out is log x, -Inf for roots below e^zmin, +Inf
 * above e^zmax. */
static int solve_z(const dist_ctx *d, double logp, int upper, double x0, double zmin, double zmax, double *out)
{
    const double sgn = upper ? -1.0 : 1.0; /* sgn * L is increasing in z */
    double lo = zmin, hi = zmax;            /* sgn*L(lo) < 0 < sgn*L(hi) once known */
    int lo_known = 0, hi_known = 0;
    double z = log(x0), step = 1.0, prev_abs_L = INFINITY;
    if (!(z > zmin && z < zmax))
        z = 0.0;
    for (int it = 0; it < 400; it++) {
        double L, dL;
        int st = eval_L(d, z, upper, logp, &L, &dL);
        if (st)
            return st;
        if (L == 0.0) {
            *out = z;
            return MCSTAT_OK;
        }
        if (sgn * L > 0.0) {
            hi = z;
            hi_known = 1;
        } else {
            lo = z;
            lo_known = 1;
        }
        double tol = 4.0 * DBL_EPSILON * fmax(1.0, fabs(z));
        double newton = L / dL;
        if (fabs(newton) <= tol) { /* converged: the step is below z's resolution */
            *out = z - newton;
            return MCSTAT_OK;
        }
        double zn = z - newton;
        int newton_ok = zn > lo && zn < hi && fabs(L) <= 0.5 * prev_abs_L;
        prev_abs_L = fabs(L);
        if (!newton_ok) {
            if (lo_known && hi_known) {
                zn = 0.5 * (lo + hi);
                prev_abs_L = INFINITY; /* let Newton try again from the midpoint */
            } else if (!hi_known) { /* root lies above: expand upwards */
                zn = z + step;
                step *= 2.0;
                if (zn >= zmax) {
                    if (z >= zmax - 1e-9) {
                        *out = INFINITY;
                        return MCSTAT_OK;
                    }
                    zn = zmax;
                }
            } else {
                zn = z - step;
                step *= 2.0;
                if (zn <= zmin) {
                    if (z <= zmin + 1e-9) {
                        *out = -INFINITY;
                        return MCSTAT_OK;
                    }
                    zn = zmin;
                }
            }
        }
        z = zn;
        if (lo_known && hi_known && hi - lo <= tol) {
            *out = z;
            return MCSTAT_OK;
        }
    }
    return MCSTAT_ENUMERIC;
}

/* The root as x, within the normal doubles (0 below, +Inf above). */
static int solve_positive(const dist_ctx *d, double logp, int upper, double x0, double *out)
{
    double z;
    int st = solve_z(d, logp, upper, x0, Z_MIN, Z_MAX, &z);
    if (!st)
        *out = exp(z); /* exp(-Inf) = 0, exp(Inf) = Inf */
    return st;
}

/* The root as log x, unclamped: the far tails are then evaluated from log x
 * (chisq_tails_z, f_tails_z).  +-1e7 bounds log x for any df >= 1e-3 and
 * p >= 2^-1074; beyond, -+Inf. */
#define ZL_LIMIT 1e7
static int solve_log(const dist_ctx *d, double logp, int upper, double x0, double *out)
{
    return solve_z(d, logp, upper, x0, -ZL_LIMIT, ZL_LIMIT, out);
}


/* Picks the better of two starting points (the one with smaller |L|). */
static double better_start(const dist_ctx *d, double logp, int upper, double x1, double x2)
{
    if (!(x1 > 0.0 && isfinite(x1)))
        return x2;
    if (!(x2 > 0.0 && isfinite(x2)))
        return x1;
    double L1, L2, dL;
    if (eval_L(d, log(x1), upper, logp, &L1, &dL) || eval_L(d, log(x2), upper, logp, &L2, &dL))
        return x1;
    return fabs(L1) <= fabs(L2) ? x1 : x2;
}

/* log Gamma(a) by Stirling with GSL's remainder; a > 0. */
static double log_gamma(double a)
{
    return 0.5 * log(2.0 * M_PI) + (a - 0.5) * log(a) - a + mcstat__log_gammastar(a);
}

/* Hill's approximation (CACM algorithm 396, 1970, as in R's qt) to u > 0
 * with P[T > u] = p, p < 1/2, df > 1: about 6 digits or better. */
static double t_hill(double p, double df)
{
    double P = 2.0 * p; /* Hill works with the two-sided probability */
    double a = 1.0 / (df - 0.5), b = 48.0 / (a * a);
    double c = ((20700.0 * a / b - 98.0) * a - 16.0) * a + 96.36;
    double d = ((94.5 / (b + c) - 3.0) / b + 1.0) * sqrt(a * M_PI_2) * df;
    double y = pow(d * P, 2.0 / df);
    if (y > 0.05 + a) { /* Cornish-Fisher-like expansion about the normal */
        double x = mcstat__norm_quantile(p, 0); /* negative */
        y = x * x;
        if (df < 5.0)
            c += 0.3 * (df - 4.5) * (x + 0.6);
        c = (((0.05 * d * x - 5.0) * x - 7.0) * x - 2.0) * x + b + c;
        y = (((((0.4 * y + 6.3) * y + 36.0) * y + 94.5) / c - y - 3.0) / b + 1.0) * x;
        y = expm1(a * y * y);
    } else {            /* the power-law tail */
        y = ((1.0 / (((df + 6.0) / (df * y) - 0.089 * d - 0.822) * (df + 2.0) * 3.0) + 0.5 / (df + 4.0)) * y - 1.0) *
                (df + 1.0) / (df + 2.0) + 1.0 / y;
    }
    return sqrt(df * y);
}

/* u > 0 with P[T > u] = p, p in (0, 1/2). */
static int t_upper_quantile(double p, double df, double *u)
{
    dist_ctx d = {0, df, 0.0};
    double logp = log(p);
    /* Fast path: Hill's start and one Halley step on L(z) = log T(e^z) - log p
     * (cubic convergence: a step below 1e-6 leaves an error near 1e-18),
     * with L' = -s, s = x f(x) / T, and L'' = -s (g' + s), g' = d log(x f)/dz
     * = 1 - (df+1) x^2/(df+x^2).  One tail and one density instead of the
     * ~6 of the general solver; anything else falls through to it. */
    if (df >= 1.0) {
        double h = t_hill(p, df);
        if (h > 1e-8 && h < 1e150) {
            double z = log(h), L, dL;
            if (eval_L(&d, z, 1, logp, &L, &dL) == MCSTAT_OK && isfinite(L) && isfinite(dL) && dL < 0.0) {
                double h2 = h * h, g1 = 1.0 - (df + 1.0) * h2 / (df + h2);
                double d2L = dL * (g1 - dL);
                double step = 2.0 * L * dL / (2.0 * dL * dL - L * d2L);
                if (fabs(step) <= 1e-6) {
                    *u = h * exp(-step);
                    return MCSTAT_OK;
                }
            }
        }
    }
    /* Cornish-Fisher about the normal quantile, and the power-law tail. */
    double z = mcstat__norm_quantile(p, 1), z2 = z * z;
    double cf = z + z * (z2 + 1.0) / (4.0 * df) + z * ((5.0 * z2 + 16.0) * z2 + 3.0) / (96.0 * df * df);
    double a = 0.5 * df;
    double lb = log_gamma(a) + log_gamma(0.5) - log_gamma(a + 0.5);
    double tail = exp(((a - 1.0) * log(df) - lb - logp) / df);
    return solve_positive(&d, logp, 1, better_start(&d, logp, 1, cf, tail), u);
}

/* ---- public API ---------------------------------------------------------- */

static int store_tail(const mcstat_tails *t, int upper, int logscale, double *out)
{
    double v = upper ? (logscale ? t->logq : t->q) : (logscale ? t->logp : t->p);
    /* A NaN is a failed method, never an answer (t at df = 5e-324, where
     * df/2 rounds to 0, gave NaN with status OK: tests/fuzz/fuzz_dist). */
    if (isnan(v))
        return MCSTAT_ENUMERIC;
    *out = v;
    return MCSTAT_OK;
}

static int t_cdf(double x, double df, int upper, int logscale, double *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out || isnan(x) || !valid_df(df) || (upper != 0 && upper != 1))
        return MCSTAT_EINVAL;
    mcstat_tails t;
    int st = mcstat__t_tails(x, df, &t);
    return st ? st : store_tail(&t, upper, logscale, out);
}

int mcstat_t_cdf(double x, double df, int upper, double *p) { return t_cdf(x, df, upper, 0, p); }
int mcstat_t_logcdf(double x, double df, int upper, double *p) { return t_cdf(x, df, upper, 1, p); }

static int chisq_cdf(double x, double df, int upper, int logscale, double *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out || isnan(x) || !valid_df(df) || (upper != 0 && upper != 1))
        return MCSTAT_EINVAL;
    mcstat_tails t;
    int st = mcstat__chisq_tails(x, df, &t);
    return st ? st : store_tail(&t, upper, logscale, out);
}

int mcstat_chisq_cdf(double x, double df, int upper, double *p) { return chisq_cdf(x, df, upper, 0, p); }
int mcstat_chisq_logcdf(double x, double df, int upper, double *p) { return chisq_cdf(x, df, upper, 1, p); }

static int f_cdf(double x, double df1, double df2, int upper, int logscale, double *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out || isnan(x) || !valid_df(df1) || !valid_df(df2) || (upper != 0 && upper != 1))
        return MCSTAT_EINVAL;
    mcstat_tails t;
    int st = mcstat__f_tails(x, df1, df2, &t);
    return st ? st : store_tail(&t, upper, logscale, out);
}

int mcstat_f_cdf(double x, double df1, double df2, int upper, double *p) { return f_cdf(x, df1, df2, upper, 0, p); }
int mcstat_f_logcdf(double x, double df1, double df2, int upper, double *p) { return f_cdf(x, df1, df2, upper, 1, p); }

int mcstat_t_quantile(double p, double df, int upper, double *x)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !(p >= 0.0 && p <= 1.0) || !valid_df(df) || (upper != 0 && upper != 1))
        return MCSTAT_EINVAL;
    /* Work with the lower-tail probability pl; T is symmetric. */
    double pl = upper ? 1.0 - p : p; /* exact when it matters: small p is handled below */
    if (p == 0.0) {
        *x = upper ? INFINITY : -INFINITY;
        return MCSTAT_OK;
    }
    if (p == 1.0) {
        *x = upper ? -INFINITY : INFINITY;
        return MCSTAT_OK;
    }
    if (pl == 0.5) {
        *x = 0.0;
        return MCSTAT_OK;
    }
    double u;
    int st;
    if (p < 0.5) { /* the requested tail itself is small: solve P[T > u] = p */
        st = t_upper_quantile(p, df, &u);
        if (st)
            return st;
        *x = upper ? u : -u;
    } else {
        st = t_upper_quantile(1.0 - p, df, &u);
        if (st)
            return st;
        *x = upper ? -u : u;
    }
    return MCSTAT_OK;
}

/* The chi-squared and F quantiles for p in (0, 1): x, or log x (logscale,
 * unclamped) for the variance tests' intervals. */
static int chisq_quantile(double p, double df, int upper, int logscale, double *x)
{
    dist_ctx d = {1, df, 0.0};
    /* Solve in whichever tail is smaller, so log p keeps its digits. */
    int up = upper;
    double q = p;
    if (p > 0.5) {
        up = !upper;
        q = 1.0 - p;
    }
    double logq = log(q);
    /* Wilson-Hilferty, and the small-x limit P ~ (x/2)^a / Gamma(a+1). */
    double z = mcstat__norm_quantile(q, up), c = 2.0 / (9.0 * df);
    double wh = 1.0 - c + z * sqrt(c);
    wh = wh > 0.0 ? df * wh * wh * wh : NAN;
    double a = 0.5 * df;
    double small = up ? NAN : 2.0 * exp((logq + log_gamma(a + 1.0)) / a);
    double x0 = better_start(&d, logq, up, wh, small);
    return logscale ? solve_log(&d, logq, up, x0, x) : solve_positive(&d, logq, up, x0, x);
}

int mcstat_chisq_quantile(double p, double df, int upper, double *x)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !(p >= 0.0 && p <= 1.0) || !valid_df(df) || (upper != 0 && upper != 1))
        return MCSTAT_EINVAL;
    if (p == 0.0 || p == 1.0) {
        *x = ((p == 0.0) == (upper == 0)) ? 0.0 : INFINITY;
        return MCSTAT_OK;
    }
    return chisq_quantile(p, df, upper, 0, x);
}

int mcstat__chisq_log_quantile(double p, double df, int upper, double *z)
{
    if (p == 0.0 || p == 1.0) {
        *z = ((p == 0.0) == (upper == 0)) ? -INFINITY : INFINITY;
        return MCSTAT_OK;
    }
    return chisq_quantile(p, df, upper, 1, z);
}

static int f_quantile(double p, double df1, double df2, int upper, int logscale, double *x)
{
    dist_ctx d = {2, df1, df2};
    int up = upper;
    double q = p;
    if (p > 0.5) {
        up = !upper;
        q = 1.0 - p;
    }
    double logq = log(q);
    /* log F is roughly normal with variance 2 (1/df1 + 1/df2) for large df. */
    double z = mcstat__norm_quantile(q, up);
    double g = exp(z * sqrt(2.0 / df1 + 2.0 / df2));
    double x0 = better_start(&d, logq, up, g, 1.0);
    return logscale ? solve_log(&d, logq, up, x0, x) : solve_positive(&d, logq, up, x0, x);
}

int mcstat_f_quantile(double p, double df1, double df2, int upper, double *x)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !(p >= 0.0 && p <= 1.0) || !valid_df(df1) || !valid_df(df2) || (upper != 0 && upper != 1))
        return MCSTAT_EINVAL;
    if (p == 0.0 || p == 1.0) {
        *x = ((p == 0.0) == (upper == 0)) ? 0.0 : INFINITY;
        return MCSTAT_OK;
    }
    return f_quantile(p, df1, df2, upper, 0, x);
}

int mcstat__f_log_quantile(double p, double df1, double df2, int upper, double *z)
{
    if (p == 0.0 || p == 1.0) {
        *z = ((p == 0.0) == (upper == 0)) ? -INFINITY : INFINITY;
        return MCSTAT_OK;
    }
    return f_quantile(p, df1, df2, upper, 1, z);
}
