/*
 * special.c - regularized incomplete beta and gamma functions, both tails,
 * accurate deep into the tails and at Monte Carlo sized parameters.
 *
 * Why not gsl_sf_beta_inc / gsl_sf_gamma_inc_P: their prefactor
 * x^a y^b / B(a,b) is formed as exp(a log x + b log y - log B(a,b)), which
 * cancels terms of size a+b (losing ~log10(a+b) digits at Monte Carlo sample
 * sizes), they report the underflow of a deep tail through GSL's error
 * handler (which aborts by default), and they cannot return a tail's log.
 *
 * Here the prefactor is written around the distribution's centre,
 *     x^a y^b / B(a,b) = sqrt(ab / (2 pi (a+b))) * G*(a+b) / (G*(a) G*(b))
 *                        * exp(-a dev(u_x) - b dev(u_y)),
 * with G* the Stirling remainder of the gamma function, u the relative
 * distance from the centre and dev(u) = u - log(1+u) >= 0, so no large terms
 * cancel (Didonato & Morris, ACM TOMS 708, use the same idea).  The rest is a
 * continued fraction: Didonato & Morris's form for I_x(a,b), whose terms stay
 * exact for large a with x near 1 where the classical (Numerical Recipes)
 * form loses log10(a) digits; the series and Legendre's fraction for P, Q.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sf_gamma.h>
#include "log_gammastar_cheb.h"

#define LENTZ_TINY 1e-300

double mcstat__dev(double a, double u, double log1pu)
{
    if (fabs(u) < 0.3) {
        /* log1p(u) = 2 atanh(s), s = u/(2+u): u - log1p(u) = u s - 2 (s^3/3 + s^5/5 + ...) */
        double s = u / (2.0 + u), s2 = s * s, term = s * s2, sum = 0.0;
        for (int k = 3; k < 80; k += 2) {
            double t = term / k;
            sum += t;
            if (fabs(t) <= 1e-17 * fabs(sum))
                break;
            term *= s2;
        }
        return a * (u * s - 2.0 * sum);
    }
    return a * (u - log1pu);
}

double mcstat__log_gammastar(double a)
{
    /* Stirling's series, log G*(a) = sum B_2k / (2k (2k-1) a^(2k-1)); for
     * a >= 10 the terms through a^-13 leave an error below 3e-17 of the
     * result (the next term is 3617/(122400 a^15)). */
    if (a >= 10.0) {
        double r = 1.0 / a, r2 = r * r;
        return r * (1.0 / 12 + r2 * (-1.0 / 360 + r2 * (1.0 / 1260 + r2 * (-1.0 / 1680 +
                    r2 * (1.0 / 1188 + r2 * (-691.0 / 360360 + r2 * (1.0 / 156)))))));
    }
    /* The t distribution's b = 1/2 on every call: G*(1/2) = sqrt(e/2), so
     * log G*(1/2) = (1 - log 2)/2, correctly rounded here (GSL's is 6e-16 off,
     * and costs as much as the rest of a t tail's prefactor). */
    if (a == 0.5)
        return 0.15342640972002736;
    /* GSL's handler must not fire: its domain is a > 0.  Callers check df > 0,
     * but a = df/2 of the smallest subnormal df rounds to 0 (found by
     * tests/fuzz/fuzz_dist: mcstat_t_cdf(5e-324, 5e-324) aborted in GSL). */
    if (!(a > 0.0) || !isfinite(a))
        return NAN;
    /* Below 1e-300 GSL's gammastar overflows inside and calls the handler
     * (mcstat_chisq_cdf(5e-324, 2.2e-308) aborted: tests/fuzz/fuzz_dist).
     * There G*(a) = G(a) e^a a^(1/2 - a) / sqrt(2 pi) with G(a) = 1/a - gamma
     * + O(a): log G*(a) = -(log a + log 2 pi)/2 + O(a log a), exact in double. */
    if (a < 1e-300)
        return -0.5 * (log(a) + log(2.0 * M_PI));
    /* [1/2, 10): Chebyshev pieces fitted at 60 digits (log_gammastar_cheb.h,
     * absolute error below 1e-18 before rounding): GSL's series with its
     * error estimate was a quarter of a small per-pixel Welch test. */
    if (a >= lgs_edge[0]) {
        int i = 0;
        while (a >= lgs_edge[i + 1])
            i++;
        double lo = lgs_edge[i], hi = lgs_edge[i + 1];
        double t = ((a - lo) - (hi - a)) / (hi - lo), t2 = 2.0 * t;
        const double *c = lgs_coef[i];
        double b1 = 0.0, b2 = 0.0;
        for (int j = lgs_terms[i] - 1; j >= 1; j--) {
            double b0 = t2 * b1 - b2 + c[j];
            b2 = b1;
            b1 = b0;
        }
        return t * b1 - b2 + c[0];
    }
    /* a in [1e-300, 1/2): inside GSL's domain (checked above). */
    gsl_sf_result g;
    if (gsl_sf_gammastar_e(a, &g) != 0 || !(g.val > 0.0))
        return NAN;
    return log(g.val);
}

double mcstat__norm_quantile(double p, int upper)
{
    /* Wichura's AS 241 in GSL, accurate to about 1e-16; p in (0, 1). */
    return upper ? gsl_cdf_ugaussian_Qinv(p) : gsl_cdf_ugaussian_Pinv(p);
}

/* Fills both tails from the one computed directly (the lower tail when
 * lower != 0), given its value and logarithm. */
static void tails_from(mcstat_tails *t, int lower, double v, double logv, double logk)
{
    t->logk = logk;
    if (!(v <= 1.0) || !(logv <= 0.0)) { /* a few ulps above 1 at degenerate parameters */
        v = 1.0;
        logv = 0.0;
    }
    double other = 1.0 - v, logother = log1p(-v);
    if (lower) {
        t->p = v; t->logp = logv; t->q = other; t->logq = logother;
    } else {
        t->q = v; t->logq = logv; t->p = other; t->logp = logother;
    }
}

/* Iteration caps grow like sqrt of the parameters (the fractions and series
 * need O(sqrt a) terms near the centre); computed in double, then clamped. */
static long iteration_cap(double a)
{
    double m = 1000.0 + 60.0 * sqrt(a);
    return m < 1e8 ? (long)m : 100000000L;
}

/* erfcx(z) = exp(z^2) erfc(z) for z >= 0, to a few ulps. */
static double erfcx(double z)
{
    if (z < 26.0) {
        mcstat_dd z2 = dd_two_prod(z, z); /* exp of the exact square */
        return exp(z2.hi) * (1.0 + z2.lo) * erfc(z);
    }
    /* 1/(z sqrt(pi)) * sum_k (-1)^k (2k-1)!! / (2 z^2)^k, asymptotic */
    double w = 1.0 / (2.0 * z * z), term = 1.0, sum = 1.0;
    for (int k = 1; k < 30; k++) {
        term *= -(2.0 * k - 1.0) * w;
        sum += term;
        if (fabs(term) < 1e-17 * sum)
            break;
    }
    return sum / (z * 1.7724538509055160273);
}

/* ---- incomplete beta ----------------------------------------------------- */

/* The deviations from the centre, u_x = x (a+b)/a - 1 = x b/a - y and
 * u_y = y (a+b)/b - 1 = y a/b - x, formed from x and y themselves (1 - x
 * would cancel).  Callers who know them more precisely (the F distribution
 * near f = 1) pass them to the _u functions instead. */
static void deviations(double a, double b, double x, double y, double *ux, double *uy)
{
    *ux = x * (b / a) - y;
    *uy = y * (a / b) - x;
}

/* log(1 + u) where 1 + u = v (1 + r), v in (0, 1] known to a few ulps.
 * Below u = -1/2 log1p would carry u's absolute error divided by 1 + u, so
 * the product is formed instead (a few ulps relative, so its log is right
 * to a few 1e-16 absolute).  log v + log1p(r), used before, lost the digits
 * of log v where the two cancel: F(1e15, 562) at f = 3 has log y = -29.3
 * against log1p(a/b) = 28.2, and b = 281 times that error put the tail 8e-13
 * off.  The sum remains where the product leaves the normal range. */
static double log1p_dev(double u, double v, double r)
{
    if (u > -0.5)
        return log1p(u);
    double w = v * (1.0 + r);
    if (w >= DBL_MIN && w <= 1.0)
        return log(w);
    return log(v) + log1p(r);
}

/* a dev(u_x) + b dev(u_y): minus the log of the prefactor's exponential. */
static double dev_sum(double a, double b, double x, double y, double ux, double uy)
{
    double lx = log1p_dev(ux, x, b / a);
    double ly = log1p_dev(uy, y, a / b);
    return mcstat__dev(a, ux, lx) + mcstat__dev(b, uy, ly);
}

/* log of x^a y^b / B(a, b). */
double mcstat__log_beta_prefactor_u(double a, double b, double x, double y, double ux, double uy)
{
    double c = a + b;
    double lg = mcstat__log_gammastar(c) - mcstat__log_gammastar(a) - mcstat__log_gammastar(b);
    /* log sqrt(ab / (2 pi c)), pairing the larger parameter with c: log(a/2pi)
     * + log(b/c) would cancel (690 - 690 at a/b = 1e300) */
    double lead = 0.5 * (log(fmin(a, b) / (2.0 * M_PI)) + log(fmax(a, b) / c));
    return lead + lg - dev_sum(a, b, x, y, ux, uy);
}

double mcstat__log_beta_prefactor(double a, double b, double x, double y)
{
    double ux, uy;
    deviations(a, b, x, y, &ux, &uy);
    return mcstat__log_beta_prefactor_u(a, b, x, y, ux, uy);
}

/* Didonato & Morris's continued fraction (TOMS 708, "bfrac") for
 * I_x(a, b) / prefactor, for lambda = a - (a+b) x >= 0, evaluated by the
 * forward recurrence with rescaling.  The caller forms lambda from x or y so
 * that it does not cancel. */
static int beta_frac(double a, double b, double x, double y, double lambda, double *out)
{
    const double c = 1.0 + lambda, c0 = b / a, c1 = 1.0 + 1.0 / a, yp1 = y + 1.0;
    double n = 0.0, p = 1.0, s = a + 1.0;
    double an = 0.0, bn = 1.0, anp1 = 1.0, bnp1 = c / c1, r = c1 / c;
    /* Iterations grow like sqrt(min(a, b)) near the mean (measured: 0.7 ms at
     * min 5e12 whatever the other); the cap is generous and turns a would-be
     * endless loop into a prompt MCSTAT_ENUMERIC.  It follows max(a, b): with
     * a = 1/16 and b = 2.7e8 (F with df 0.125 and 5.4e8) the fraction creeps
     * by ~7e-16 per step for thousands of steps, and a cap from min(a, b)
     * (1030) failed 1.2% of such calls (found by tests/fuzz/fuzz_dist). */
    long maxit = iteration_cap(4.0 * fmax(a, b));
    for (long it = 0; it < maxit; it++) {
        n += 1.0;
        double t = n / a, w = n * (b - n) * x, e = a / s;
        double alpha = p * (p + c0) * e * e * (w * x);
        e = (t + 1.0) / (c1 + t + t);
        double beta = n + w / s + e * (c + n * yp1);
        p = t + 1.0;
        s += 2.0;
        double tt = alpha * an + beta * anp1;
        an = anp1;
        anp1 = tt;
        tt = alpha * bn + beta * bnp1;
        bn = bnp1;
        bnp1 = tt;
        double r0 = r;
        r = anp1 / bnp1;
        if (fabs(r - r0) <= 1.5 * DBL_EPSILON * r) {
            *out = r;
            return MCSTAT_OK;
        }
        an /= bnp1;
        bn /= bnp1;
        anp1 = r;
        bnp1 = 1.0;
    }
    return MCSTAT_ENUMERIC;
}

/* The leading term of Temme's uniform expansion for large a and b, derived
 * by the substitution -eta^2/2 = xi log(t/xi) + (1-xi) log((1-t)/(1-xi)),
 * xi = a/(a+b), r = a+b, in the beta integral, then one integration by parts:
 *   I_x(a,b) = erfc(-eta sqrt(r/2))/2 - exp(-r eta^2/2)/sqrt(2 pi r) C0(eta),
 *   C0 = sqrt(xi(1-xi))/(x - xi) - 1/eta,   C0(0) = -(1-2xi)/(3 sqrt(xi(1-xi))),
 * relative error O(1/r) (measured against 40-digit values: 1e-11 at
 * r = 1e6, 4e-12 at 6e7).  Used where min(a,b) >= BETA_TEMME, i.e. r >= 1e14,
 * where it is exact in double precision and the continued fraction would
 * need O(sqrt(min(a,b))) terms.  r eta^2/2 is the prefactor's deviation sum. */
#define BETA_TEMME 5e13

static void beta_temme(double a, double b, double x, double y, double ux, double uy, mcstat_tails *t)
{
    double r = a + b, xi = a / r, sig = sqrt(a) * sqrt(b) / r;
    double d = dev_sum(a, b, x, y, ux, uy); /* r eta^2 / 2 */
    double delta = xi * ux;                                     /* x - xi, without cancellation */
    double eta = copysign(sqrt(2.0 * d / r), delta);
    /* near eta = 0 the closed form cancels; C0's slope there only moves the
     * result by |eta| / sqrt(r) < 1e-14 relative */
    double c0 = fabs(eta) > 1e-7 ? sig / delta - 1.0 / eta : -((b - a) / r) / (3.0 * sig);
    double rr = c0 / sqrt(2.0 * M_PI * r);
    double s = 0.5 * erfcx(sqrt(d)) + (eta >= 0.0 ? rr : -rr); /* small tail / exp(-d) */
    double logv = -d + log(s);
    double lg = mcstat__log_gammastar(r) - mcstat__log_gammastar(a) - mcstat__log_gammastar(b);
    double lead = 0.5 * (log(fmin(a, b) / (2.0 * M_PI)) + log(fmax(a, b) / r));
    tails_from(t, eta < 0.0, exp(logv), logv, lead + lg - d);
}

/* ---- one small parameter ------------------------------------------------ */

/* With one parameter s small, the continued fraction needs thousands of
 * terms or fails to converge where the other parameter l is large (F with
 * df 0.001 and 100 at f = 1.5 gave MCSTAT_ENUMERIC; at df 0.00103 and
 * 630784 it stopped early, 2e-10 off, and the two tails' fractions met
 * non-monotonically at f = 1).  There the power series in the small
 * parameter's argument xs (DLMF 8.17.7, as TOMS 708's bpser/apser) is cheap
 * and exact:
 *   I_xs(s, l) = xs^s Gamma(s+l) / (Gamma(s+1) Gamma(l)) (1 + s S),
 *   S = sum_{j>=1} (1-l)_j xs^j / (j! (s+j)),
 * so log I = E = s log xs + lnpoch(l, s) - lnGamma(1+s) + log1p(s S), and the
 * other tail is -expm1(E), each to a few ulps relative: every part of E is
 * formed as O(s) (none is 1 + O(s) rounded first).  The terms of S shrink
 * by l xs / j, and their alternating sum cancels by at most e^(2 l xs): used
 * where l xs <= SMALL_LX and xs <= 1/2. */
#define SMALL_S 0.25
#define SMALL_LX 1.0

/* log Gamma(1+s) for 0 < s <= SMALL_S: -gamma s + (s - log1p(s))
 * + sum_{k>=2} (zeta(k) - 1) (-s)^k / k, the terms below (s/2)^k. */
static double log_gamma1p_small(double s)
{
    static const double zm1[] = {
        0.6449340668482264, 0.2020569031595943, 0.08232323371113819, 0.03692775514336993,
        0.01734306198444914, 0.008349277381922827, 0.00407735619794434, 0.0020083928260822143,
        0.0009945751278180853, 0.0004941886041194645, 0.0002460865533080483, 0.00012271334757848915,
        6.124813505870483e-05, 3.058823630702049e-05, 1.528225940865187e-05, 7.637197637899763e-06,
        3.81729326499984e-06, 1.908212716553939e-06, 9.539620338727962e-07, 4.769329867878064e-07,
        2.38450502727733e-07, 1.1921992596531106e-07, 5.960818905125948e-08, 2.980350351465228e-08};
    double sum = 0.0, pw = -s;
    for (int k = 2; k < 26; k++) { /* (1/8)^26 < 1e-23; pw = (-s)^k */
        pw *= -s;
        sum += zm1[k - 2] * pw / k;
    }
    return -0.57721566490153286061 * s + (s - log1p(s)) + sum;
}

/* log Gamma(l+s) - log Gamma(l) for 0 < s <= SMALL_S, l > 0: Stirling's
 * form at l >= 10, where the difference is s log l + (l+s-1/2) log1p(s/l)
 * - s plus that of the remainders; below, shifted up by the recurrence. */
static double lnpoch_small(double l, double s)
{
    double shift = 0.0;
    while (l < 10.0) {
        shift += log1p(s / l);
        l += 1.0;
    }
    double d = s * (log(l) - 1.0) + (l + s - 0.5) * log1p(s / l) +
               (mcstat__log_gammastar(l + s) - mcstat__log_gammastar(l));
    return d - shift;
}

/* log I_xs(s, l) by the series above; 0 if it did not converge. */
static int beta_small_series(double s, double l, double xs, double *logv)
{
    double term = 1.0, sum = 0.0;
    for (int j = 1; j < 400; j++) {
        term *= (j - l) * xs / j; /* (1-l)_j xs^j / j! */
        double t = term / (s + j);
        sum += t;
        if (fabs(t) <= 1e-17 * fmax(1.0, fabs(sum))) {
            *logv = s * log(xs) + lnpoch_small(l, s) - log_gamma1p_small(s) + log1p(s * sum);
            return 1;
        }
    }
    return 0;
}

/* Both tails when one parameter is small and the series applies; returns 0
 * (leaving t alone) otherwise. */
static int beta_small(double a, double b, double x, double y, double lpre, mcstat_tails *t)
{
    double logv;
    if (a <= SMALL_S && x <= 0.5 && b * x <= SMALL_LX && beta_small_series(a, b, x, &logv)) {
        double q = -expm1(logv); /* I_x(a,b) = e^logv, the other tail 1 - e^logv */
        if (!(q > 0.0)) { /* only by rounding, where 1 - I is below an ulp of 1 */
            q = 0.0;
            logv = 0.0;
        }
        tails_from(t, q >= 0.5, q >= 0.5 ? exp(logv) : q, q >= 0.5 ? logv : log(q), lpre);
        return 1;
    }
    if (b <= SMALL_S && y <= 0.5 && a * y <= SMALL_LX && beta_small_series(b, a, y, &logv)) {
        double p = -expm1(logv); /* I_y(b,a) = 1 - I_x(a,b) = e^logv */
        if (!(p > 0.0)) {
            p = 0.0;
            logv = 0.0;
        }
        tails_from(t, p < 0.5, p < 0.5 ? p : exp(logv), p < 0.5 ? log(p) : logv, lpre);
        return 1;
    }
    return 0;
}

int mcstat__beta_inc(double a, double b, double x, double y, mcstat_tails *t)
{
    double ux, uy;
    deviations(a, b, x, y, &ux, &uy);
    return mcstat__beta_inc_u(a, b, x, y, ux, uy, t);
}

int mcstat__beta_inc_u(double a, double b, double x, double y, double ux, double uy, mcstat_tails *t)
{
    if (!(a > 0.0) || !(b > 0.0) || !isfinite(a) || !isfinite(b) || !(x >= 0.0) || !(y >= 0.0))
        return MCSTAT_EINVAL;
    if (x == 0.0) {
        t->p = 0.0; t->logp = -INFINITY; t->q = 1.0; t->logq = 0.0; t->logk = -INFINITY;
        return MCSTAT_OK;
    }
    if (y == 0.0) {
        t->p = 1.0; t->logp = 0.0; t->q = 0.0; t->logq = -INFINITY; t->logk = -INFINITY;
        return MCSTAT_OK;
    }
    if (a >= BETA_TEMME && b >= BETA_TEMME && fabs(ux) < 0.3 && fabs(uy) < 0.3) { /* as for gamma */
        beta_temme(a, b, x, y, ux, uy, t);
        return MCSTAT_OK;
    }
    double lpre = mcstat__log_beta_prefactor_u(a, b, x, y, ux, uy);
    if (isnan(lpre))
        return MCSTAT_ENUMERIC;
    if ((a <= SMALL_S || b <= SMALL_S) && beta_small(a, b, x, y, lpre, t))
        return MCSTAT_OK;
    /* lambda = a - (a+b) x = b u_y = -a u_x, from the deviation of the
     * smaller parameter (the other product could cancel less precisely) */
    double lambda = (a > b) ? b * uy : -a * ux;
    double r;
    int st;
    if (lambda >= 0.0) { /* x at or below the mean: compute the lower tail */
        if ((st = beta_frac(a, b, x, y, lambda, &r)))
            return st;
        double logv = lpre + log(r);
        tails_from(t, 1, exp(logv), logv, lpre);
    } else {             /* above the mean: the upper tail, I_y(b, a) */
        if ((st = beta_frac(b, a, y, x, -lambda, &r)))
            return st;
        double logv = lpre + log(r);
        tails_from(t, 0, exp(logv), logv, lpre);
    }
    return MCSTAT_OK;
}

/* ---- incomplete gamma ---------------------------------------------------- */

/* Temme's uniform asymptotic expansion (DLMF 8.12.3-8.12.9):
 *   Q(a,x) = erfc(eta sqrt(a/2))/2 + R,  P(a,x) = erfc(-eta sqrt(a/2))/2 - R,
 *   R = exp(-a eta^2/2) / sqrt(2 pi a) * (C0(eta) + C1(eta)/a + O(a^-2)),
 * eta = sign(x-a) sqrt(2 (x/a - 1 - log(x/a))).  Used for a >= TEMME_A, where
 * the truncation is below 1e-18 relative and the series would need O(sqrt a)
 * terms.  The Taylor coefficients of C0 and C1 at eta = 0 (where their closed
 * forms cancel) come from reverting u - log(1+u) = eta^2/2 exactly in
 * rational arithmetic; they agree with Temme's. */
#define TEMME_A 1e8

static double temme_c0(double eta, double u)
{
    static const double c[] = {-1.0 / 3, 1.0 / 12, -2.0 / 135, 1.0 / 864, 1.0 / 2835, -139.0 / 777600,
                               1.0 / 25515, -571.0 / 261273600, -281.0 / 151559100};
    if (fabs(eta) >= 0.3)
        return 1.0 / u - 1.0 / eta;
    double r = 0.0;
    for (int k = 8; k >= 0; k--)
        r = r * eta + c[k];
    return r;
}

static double temme_c1(double eta, double u)
{
    static const double c[] = {-1.0 / 540, -1.0 / 288, 1.0 / 378, -77.0 / 77760, 1.0 / 4860,
                               -1.0 / 2488320, -2743.0 / 151559100, 41969.0 / 5486745600.0, -11.0 / 6823440};
    if (fabs(eta) >= 0.3)
        return 1.0 / (eta * eta * eta) - 1.0 / (u * u * u) - 1.0 / (u * u) - 1.0 / (12.0 * u);
    double r = 0.0;
    for (int k = 8; k >= 0; k--)
        r = r * eta + c[k];
    return r;
}

static void gamma_temme(double a, double x, mcstat_tails *t)
{
    double u = (x - a) / a;
    double l1u = u > -0.5 ? log1p(u) : log(x) - log(a);
    double d = mcstat__dev(a, u, l1u); /* a eta^2 / 2 */
    double eta = copysign(sqrt(2.0 * d / a), u);
    double z = fabs(eta) * sqrt(0.5 * a);
    double r = (temme_c0(eta, u) + temme_c1(eta, u) / a) / sqrt(2.0 * M_PI * a);
    /* the small tail, over exp(-a eta^2/2): Q above the centre, P below */
    double s = 0.5 * erfcx(z) + (eta >= 0.0 ? r : -r);
    double logv = -d + log(s);
    tails_from(t, eta < 0.0, exp(logv), logv, -d - 0.5 * log(2.0 * M_PI * a) - mcstat__log_gammastar(a));
}

/* log of x^a e^-x / Gamma(a+1) = -a dev((x-a)/a) - log(sqrt(2 pi a) G*(a)). */
double mcstat__log_gamma_prefactor(double a, double x)
{
    double u = (x - a) / a; /* x - a is exact near the centre (Sterbenz) */
    double tail = -0.5 * log(2.0 * M_PI * a) - mcstat__log_gammastar(a);
    /* u overflows for a < 1 and x near DBL_MAX (chi-squared at df 1/32,
     * x = DBL_MAX: Inf - log1p(Inf) = NaN, MCSTAT_ENUMERIC; found by
     * tests/fuzz/fuzz_dist): a dev(u) = (x - a) - a log(x/a), formed apart */
    if (!(u < 1e300))
        return -((x - a) - a * (log(x) - log(a))) + tail;
    double l1u = u > -0.5 ? log1p(u) : log(x) - log(a);
    return -mcstat__dev(a, u, l1u) + tail;
}

int mcstat__gamma_inc(double a, double x, mcstat_tails *t)
{
    if (!(a > 0.0) || !isfinite(a) || !(x >= 0.0))
        return MCSTAT_EINVAL;
    if (x == 0.0) {
        t->p = 0.0; t->logp = -INFINITY; t->q = 1.0; t->logq = 0.0; t->logk = -INFINITY;
        return MCSTAT_OK;
    }
    if (isinf(x)) {
        t->p = 1.0; t->logp = 0.0; t->q = 0.0; t->logq = -INFINITY; t->logk = -INFINITY;
        return MCSTAT_OK;
    }
    /* Temme near the centre only: far out, its two leading terms (both about
     * 1/eta) cancel to leave 1/u, and there the series or fraction converges
     * in a few terms anyway. */
    if (a >= TEMME_A && fabs(x - a) < 0.3 * a) {
        gamma_temme(a, x, t);
        return MCSTAT_OK;
    }
    double lpre = mcstat__log_gamma_prefactor(a, x);
    if (isnan(lpre))
        return MCSTAT_ENUMERIC;
    long maxit = iteration_cap(a);
    if (x < a + 1.0) {
        /* P = prefactor * sum_{n>=0} x^n / ((a+1)...(a+n)) */
        double sum = 1.0, term = 1.0;
        long n;
        for (n = 1; n <= maxit; n++) {
            term *= x / (a + n);
            sum += term;
            if (term <= sum * DBL_EPSILON * 0.5)
                break;
        }
        if (n > maxit)
            return MCSTAT_ENUMERIC;
        double logv = lpre + log(sum);
        tails_from(t, 1, exp(logv), logv, lpre);
    } else {
        /* Q = a * prefactor * (Legendre's continued fraction, modified Lentz);
         * (x - a) + 1 keeps the first term exact for large a. */
        double bb = (x - a) + 1.0, c = 1.0 / LENTZ_TINY, d = 1.0 / bb, h = d;
        long i;
        for (i = 1; i <= maxit; i++) {
            double an = -i * (i - a);
            bb += 2.0;
            d = an * d + bb;
            if (fabs(d) < LENTZ_TINY)
                d = LENTZ_TINY;
            c = bb + an / c;
            if (fabs(c) < LENTZ_TINY)
                c = LENTZ_TINY;
            d = 1.0 / d;
            double del = d * c;
            h *= del;
            if (fabs(del - 1.0) <= 2.0 * DBL_EPSILON)
                break;
        }
        if (i > maxit)
            return MCSTAT_ENUMERIC;
        double logv = lpre + log(a * h);
        tails_from(t, 0, exp(logv), logv, lpre);
    }
    return MCSTAT_OK;
}
