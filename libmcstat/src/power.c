/*
 * power.c - power and sample size of the t, chi-squared and F tests, the
 * way R's power.t.test and statsmodels' solve_power pose the question: give
 * all but one of n, effect, alpha and power, solve for the missing one.
 *
 * Distributions of the statistics under the alternative:
 *   T_1    t = sqrt(n) (mean - mu0)/s        noncentral t, df n-1, ncp sqrt(n) d
 *   T_2    pooled two-sample t, n per group  noncentral t, df 2(n-1), ncp sqrt(n/2) d
 *   WELCH  Welch's t, nx = n, ny = k n,      approximately noncentral t with the
 *          sd_y = r sd_x                     Welch-Satterthwaite df of the true
 *                                            variances, ncp d / sqrt(1/nx + r^2/ny)
 *   VAR_1  (n-1) s^2 / sigma0^2              rho chi^2(n-1), rho = sigma^2/sigma0^2
 *   VAR_2  (s_x^2/s_y^2) / ratio0            rho F(nx-1, ny-1), rho = true ratio / ratio0
 * so the power of the chi-squared and F tests is a central tail at the
 * critical value divided by rho (closed form), and that of the t tests a
 * noncentral t tail (noncentral.c, R's pnt).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>
#include <stdio.h>

#define N_MAX 1e15 /* solving for n gives up beyond this (MCSTAT_EINVAL) */

/* Every size mcstat_power_options has had, oldest first (options.c). */
static const uint32_t POWER_SIZES[] = {MCSTAT_POWER_OPTIONS_SIZE_0_1};
_Static_assert(sizeof(mcstat_power_options) == MCSTAT_POWER_OPTIONS_SIZE_0_1,
               "a grown mcstat_power_options needs its size appended to POWER_SIZES");

int mcstat_power_options_init_size(mcstat_power_options *o, size_t size)
{
    const mcstat_power_options d = MCSTAT_POWER_OPTIONS_INIT;
    return mcstat__options_init(o, size, &d, sizeof d, POWER_SIZES, sizeof POWER_SIZES / sizeof *POWER_SIZES);
}

/* 0.1.0's entry point: its callers' structs are 0.1.0's size (the name is
 * parenthesised against the header's macro). */
int(mcstat_power_options_init)(mcstat_power_options *o)
{
    return mcstat_power_options_init_size(o, MCSTAT_POWER_OPTIONS_SIZE_0_1);
}

int mcstat__power_options_read(const mcstat_power_options *o, mcstat_power_options *r)
{
    const mcstat_power_options d = MCSTAT_POWER_OPTIONS_INIT;
    *r = d;
    return mcstat__options_read(r, sizeof *r, o, POWER_SIZES, sizeof POWER_SIZES / sizeof *POWER_SIZES);
}


static int valid_test(int t) { return t >= MCSTAT_POWER_T_1 && t <= MCSTAT_POWER_VAR_2; }
static int is_t(int t) { return t <= MCSTAT_POWER_WELCH; }
static int two_sizes(int t) { return t == MCSTAT_POWER_WELCH || t == MCSTAT_POWER_VAR_2; }

/* Sample sizes below 2 (either group) are outside every test's domain. */
static int valid_n(const mcstat_power_options *o, double n)
{
    if (!(n >= 2.0) || !isfinite(n))
        return 0;
    return !two_sizes(o->test) || n * o->n_ratio >= 2.0;
}

/* Options every computation needs, whatever is being solved for. */
static int check_common(const mcstat_power_options *o)
{
    if (!valid_test(o->test) ||
        !valid_alternative(o->alternative) || (o->strict != 0 && o->strict != 1))
        return MCSTAT_EINVAL;
    if (two_sizes(o->test) && !(o->n_ratio > 0.0 && isfinite(o->n_ratio)))
        return MCSTAT_EINVAL;
    if (o->test == MCSTAT_POWER_WELCH && !(o->sd_ratio > 0.0 && isfinite(o->sd_ratio)))
        return MCSTAT_EINVAL;
    return MCSTAT_OK;
}

static int valid_effect(const mcstat_power_options *o, double e)
{
    return is_t(o->test) ? isfinite(e) : (e > 0.0 && isfinite(e));
}

/* The power for n, effect, alpha (validated by the callers). */
static int power_at(const mcstat_power_options *o, double n, double effect, double alpha, double *out)
{
    const int alt = o->alternative;
    /* Which tails count: two-sided strict both, non-strict only the tail the
     * effect points to (R's power.t.test default), one-sided its own. */
    int use_low = alt == MCSTAT_LESS, use_high = alt == MCSTAT_GREATER;
    double a = alt == MCSTAT_TWO_SIDED ? 0.5 * alpha : alpha;
    int st;
    if (is_t(o->test)) {
        double df, ncp;
        if (o->test == MCSTAT_POWER_T_1) {
            df = n - 1.0;
            ncp = sqrt(n) * effect;
        } else if (o->test == MCSTAT_POWER_T_2) {
            df = 2.0 * (n - 1.0);
            ncp = sqrt(0.5 * n) * effect;
        } else {
            double ny = o->n_ratio * n, va = 1.0 / n, vb = o->sd_ratio * o->sd_ratio / ny;
            double m = fmax(va, vb), ra = va / m, rb = vb / m;
            df = (ra + rb) * (ra + rb) / (ra * ra / (n - 1.0) + rb * rb / (ny - 1.0));
            ncp = effect / sqrt(va + vb);
        }
        if (alt == MCSTAT_TWO_SIDED) {
            use_low = o->strict || effect < 0.0;
            use_high = o->strict || effect >= 0.0;
        }
        double c, lo, hi, p = 0.0;
        if ((st = mcstat_t_quantile(a, df, 1, &c)))
            return st;
        if (use_high) {
            if ((st = mcstat__nct_tails(c, df, ncp, &lo, &hi)))
                return st;
            p += hi;
        }
        if (use_low) {
            if ((st = mcstat__nct_tails(-c, df, ncp, &lo, &hi)))
                return st;
            p += lo;
        }
        *out = fmin(1.0, p);
        return MCSTAT_OK;
    }
    double df1 = n - 1.0, df2 = o->n_ratio * n - 1.0, rho = effect;
    if (alt == MCSTAT_TWO_SIDED) {
        use_low = o->strict || rho < 1.0;
        use_high = o->strict || rho >= 1.0;
    }
    double c, t, p = 0.0;
    if (use_high) {
        st = o->test == MCSTAT_POWER_VAR_1 ? mcstat_chisq_quantile(a, df1, 1, &c) : mcstat_f_quantile(a, df1, df2, 1, &c);
        if (st)
            return st;
        st = o->test == MCSTAT_POWER_VAR_1 ? mcstat_chisq_cdf(c / rho, df1, 1, &t) : mcstat_f_cdf(c / rho, df1, df2, 1, &t);
        if (st)
            return st;
        p += t;
    }
    if (use_low) {
        st = o->test == MCSTAT_POWER_VAR_1 ? mcstat_chisq_quantile(a, df1, 0, &c) : mcstat_f_quantile(a, df1, df2, 0, &c);
        if (st)
            return st;
        st = o->test == MCSTAT_POWER_VAR_1 ? mcstat_chisq_cdf(c / rho, df1, 0, &t) : mcstat_f_cdf(c / rho, df1, df2, 0, &t);
        if (st)
            return st;
        p += t;
    }
    *out = fmin(1.0, p);
    return MCSTAT_OK;
}

int mcstat_power_compute(const mcstat_power_options *opt, double *power)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_power_options full, *o = &full;
    int st = mcstat__power_options_read(opt, o);
    if (st || (st = check_common(o)))
        return st;
    if (!power || !valid_n(o, o->n) || !valid_effect(o, o->effect) || !valid_alpha(o->alpha))
        return MCSTAT_EINVAL;
    return power_at(o, o->n, o->effect, o->alpha, power);
}

/* ---- solving ---------------------------------------------------------------
 * Power grows with n, with alpha and with the effect's distance from the null
 * (in the direction the alternative names), so each unknown is found by
 * bracketing and bisection on a monotone function: robust, and the cost
 * (~100 power evaluations, a few microseconds each) does not matter here. */

/* The effect as a function of a search variable u > 0: the t tests' d = s u,
 * the variance tests' rho = exp(s u), s = -1 for LESS, else +1 (the
 * two-sided solution is the one on the "greater" side). */
static double effect_of(const mcstat_power_options *o, double u)
{
    double s = o->alternative == MCSTAT_LESS ? -1.0 : 1.0;
    return is_t(o->test) ? s * u : exp(s * u);
}

static int solve_effect(const mcstat_power_options *o, double *effect)
{
    double lo = 0.0, hi = 1.0, p;
    int st;
    /* at the null (d = 0, rho = 1) the power is what alpha alone gives: a
     * target at or below it needs no effect, and none is the answer */
    if ((st = power_at(o, o->n, effect_of(o, 0.0), o->alpha, &p)))
        return st;
    if (p >= o->power)
        return MCSTAT_EINVAL;
    for (;;) { /* bracket: power(hi) >= target */
        if ((st = power_at(o, o->n, effect_of(o, hi), o->alpha, &p)))
            return st;
        if (p >= o->power)
            break;
        lo = hi;
        hi *= 2.0;
        if (hi > 1e6)
            return MCSTAT_EINVAL; /* no effect reaches this power */
    }
    for (int i = 0; i < 200 && hi - lo > 4.0 * DBL_EPSILON * hi; i++) {
        double mid = 0.5 * (lo + hi);
        if ((st = power_at(o, o->n, effect_of(o, mid), o->alpha, &p)))
            return st;
        if (p >= o->power)
            hi = mid;
        else
            lo = mid;
    }
    *effect = effect_of(o, 0.5 * (lo + hi));
    return MCSTAT_OK;
}

static int solve_alpha(const mcstat_power_options *o, double *alpha)
{
    /* bisection on log(alpha) over [1e-300, 1 - 1e-12] */
    double lo = log(1e-300), hi = log1p(-1e-12), p;
    int st;
    if ((st = power_at(o, o->n, o->effect, exp(hi), &p)))
        return st;
    if (p < o->power)
        return MCSTAT_EINVAL;
    if ((st = power_at(o, o->n, o->effect, exp(lo), &p)))
        return st;
    if (p >= o->power) {
        *alpha = exp(lo);
        return MCSTAT_OK;
    }
    for (int i = 0; i < 200 && hi - lo > 1e-14; i++) {
        double mid = 0.5 * (lo + hi);
        if ((st = power_at(o, o->n, o->effect, exp(mid), &p)))
            return st;
        if (p >= o->power)
            hi = mid;
        else
            lo = mid;
    }
    *alpha = exp(0.5 * (lo + hi));
    return MCSTAT_OK;
}

/* The doubling search both solvers start from: from the smallest n allowed,
 * lo, to [*lo_out, *hi_out] with power(lo) < target <= power(hi) = *p_hi;
 * *hi_out == *lo_out when the smallest n already reaches the target. */
static int bracket_n(const mcstat_power_options *o, double lo, double *lo_out, double *hi_out, double *p_hi)
{
    double p, hi = lo;
    int st = power_at(o, lo, o->effect, o->alpha, &p);
    if (st)
        return st;
    while (p < o->power) {
        lo = hi;
        hi = 2.0 * hi;
        if (hi > N_MAX)
            return MCSTAT_EINVAL; /* effect too small (or zero) for any n */
        if ((st = power_at(o, hi, o->effect, o->alpha, &p)))
            return st;
    }
    *lo_out = lo;
    *hi_out = hi;
    *p_hi = p;
    return MCSTAT_OK;
}

/* The smallest n (an integer; ny = n_ratio n) whose power reaches the target. */
static int solve_n(const mcstat_power_options *o, double *n, double *achieved)
{
    double lo, hi, phi, p;
    int st = bracket_n(o, two_sizes(o->test) && o->n_ratio < 1.0 ? ceil(2.0 / o->n_ratio) : 2.0, &lo, &hi, &phi);
    if (st)
        return st;
    while (hi - lo > 1.0) {
        double mid = floor(0.5 * (lo + hi));
        if ((st = power_at(o, mid, o->effect, o->alpha, &p)))
            return st;
        if (p >= o->power) {
            hi = mid;
            phi = p;
        } else {
            lo = mid;
        }
    }
    *n = hi;
    *achieved = phi;
    return MCSTAT_OK;
}

/* The real n (ny = n_ratio n) at which the power equals the target, as R's
 * power.t.test reports it: bisection on the continuous n.  The smallest n
 * allowed (ny >= 2 too) when the power there already reaches the target. */
static int solve_n_exact(const mcstat_power_options *o, double *n)
{
    double lo, hi, p;
    int st = bracket_n(o, two_sizes(o->test) && o->n_ratio < 1.0 ? 2.0 / o->n_ratio : 2.0, &lo, &hi, &p);
    if (st)
        return st;
    for (int i = 0; i < 200 && hi - lo > 4.0 * DBL_EPSILON * hi; i++) {
        double mid = 0.5 * (lo + hi);
        if ((st = power_at(o, mid, o->effect, o->alpha, &p)))
            return st;
        if (p >= o->power)
            hi = mid;
        else
            lo = mid;
    }
    *n = 0.5 * (lo + hi);
    return MCSTAT_OK;
}

int mcstat_power_solve(const mcstat_power_options *opt, int unknown, mcstat_power_options *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_power_options full, *o = &full;
    int st = mcstat__power_options_read(opt, o);
    if (st || (st = check_common(o)))
        return st;
    if (!out)
        return MCSTAT_EINVAL;
    int need_n = unknown != MCSTAT_POWER_SOLVE_N && unknown != MCSTAT_POWER_SOLVE_N_EXACT;
    int need_e = unknown != MCSTAT_POWER_SOLVE_EFFECT;
    int need_a = unknown != MCSTAT_POWER_SOLVE_ALPHA, need_p = unknown != MCSTAT_POWER_SOLVE_POWER;
    if (unknown < MCSTAT_POWER_SOLVE_POWER || unknown > MCSTAT_POWER_SOLVE_N_EXACT)
        return MCSTAT_EINVAL;
    if ((need_n && !valid_n(o, o->n)) || (need_e && !valid_effect(o, o->effect)) ||
        (need_a && !valid_alpha(o->alpha)) || (need_p && !(o->power > 0.0 && o->power < 1.0)))
        return MCSTAT_EINVAL;
    mcstat_power_options r = *o;
    switch (unknown) {
    case MCSTAT_POWER_SOLVE_POWER:
        st = power_at(o, o->n, o->effect, o->alpha, &r.power);
        break;
    case MCSTAT_POWER_SOLVE_N:
        st = solve_n(o, &r.n, &r.power);
        break;
    case MCSTAT_POWER_SOLVE_N_EXACT:
        st = solve_n_exact(o, &r.n);
        break;
    case MCSTAT_POWER_SOLVE_EFFECT:
        st = solve_effect(o, &r.effect);
        break;
    default:
        st = solve_alpha(o, &r.alpha);
        break;
    }
    if (st)
        return st;
    memcpy(out, &r, r.size); /* the caller's version of the struct: o->size bytes */
    return MCSTAT_OK;
}
