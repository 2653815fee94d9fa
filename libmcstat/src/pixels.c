/*
 * pixels.c - Welch's test per pixel on image stacks of any layout (float32
 * or double, optionally a weighted sum of channels), with a Student t tail
 * specialised to the t distribution; pixels_test.c checks the arguments,
 * splits the pixels over threads and each thread runs mcstat__pixels_welch
 * on the chunks it takes.
 *
 * The row-wise tests (rows.c) run every pixel through the single call:
 * an accumulator per sample, the general incomplete beta, a full
 * mcstat_result.  Here, for a block of pixels that fits in L1:
 *   - the moments are two passes over the seeds with the pixels inner
 *     (contiguous, vectorised): the sum, then the deviations d from its
 *     mean, M2 = sum d^2 - (sum d)^2 / n (the corrected two-pass
 *     algorithm) and the mean as the double-double mean + sum d / n, so
 *     1e8 + small noise keeps its digits as in moments.c;
 *   - t, df, the standard errors and the t prefactors in branch-free loops
 *     over the block;
 *   - the tails (t_tail_core's series, specialised to b = 1/2: the cost
 *     does not depend on the variety of df) for the whole block: exp and
 *     log1p four pixels at a time (vmath.h), the central series eight
 *     pixels a step;
 *   - the critical values from a per-call table of t quantiles in 1/df
 *     (solved lazily, the same whichever pixels ask), interpolated, and the
 *     intervals' bounds, again for the whole block; where the interpolation
 *     is not good to rounding, Halley's method in log t on the fast tail
 *     finishes that pixel's.
 * The block loops are compiled for SSE2 and for AVX2 (chosen at run time,
 * the same results bit for bit).
 * A pixel outside the fast path's proven ground (a NaN or Inf, extreme
 * magnitudes, too few seeds, nearly constant samples, df or t outside the
 * fast tail's range) is computed by the single call's own code, so its
 * status and outputs are the row path's.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"
#include "vmath.h"

#include <float.h>
#include <pthread.h>
#include <stdlib.h>

#define PIX_BLOCK 256     /* pixels per block: their sums stay in L1 */
#define GATHER 256        /* the slow path's bounce buffer (2 KiB of stack) */
/* (PIX_BLOCK and GATHER are also pixels_test.c's) */
#define FAST_LO 0x1p-200  /* moments.c's unscaled range */
#define FAST_HI 0x1p+200
#define QT_NODES 1024      /* the critical values' table: u = 1/df in steps of 1/1024 */
#define LOG_2PI_HALF 0.91893853320467274178 /* log(2 pi) / 2 */

/* The per-block loops (moments, statistics, prefactors) are compiled twice
 * on x86-64, for the baseline (SSE2: two doubles a vector) and for AVX2
 * (four), and chosen at run time.  Each pixel's arithmetic is the same
 * sequence of IEEE operations in both (no FMA: -ffp-contract=off, and AVX2
 * does not imply FMA), so the results are bit for bit the same. */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PIX_AVX2 1
#define PIX_INLINE inline __attribute__((always_inline))
#else
#define PIX_AVX2 0
#define PIX_INLINE inline
#endif

/* ---- the t tail with b = 1/2 --------------------------------------------
 * a = df/2, r = t^2/df, x = 1/(1+r), y = r/(1+r).  The prefactor
 *   K = x^a y^(1/2) / B(a, 1/2) = |t| f(t)
 *     = |t| / sqrt(2) (1+r)^-(a+1/2) Gamma(a+1/2) / (Gamma(a) sqrt(pi) sqrt(a)),
 * with Gamma(a+1/2)/(Gamma(a) sqrt(a)) = exp(L(z)) sqrt(z/a) prod_{i<k} (a+i)/(a+i+1/2)
 * for z = a + k >= 10 (L below), so
 *   K = |t| f exp(e),  f = sqrt(z/a) prod (a+i)/(a+i+1/2),
 *                      e = L(z) - log(2 pi)/2 - (a+1/2) log1p(r).
 * Nothing there cancels beyond the size of the result, and e's rounding,
 * relative to K, is that of log p, not of log |t|.  Then
 *   r >= 1: P[T > |t|] = I_x(a, 1/2)/2 = K/(2a) sum_j c_j,
 *           c_{j+1} = c_j (a+1/2+j)/(a+1+j) x, ratio below x <= 1/2;
 *   r < 1:  P[|T| <= |t|] = I_y(1/2, a) = 2K sum_j c_j,
 *           c_{j+1} = c_j (a+1/2+j)/(3/2+j) y (dist.c's t_central),
 *           used while that central probability is at most 0.96, so the
 *           upper tail (1 - c)/2 carries at most 24 times its error.
 * Both sums have positive terms (a few ulps each).  Outside (df beyond
 * [1, 1000], the centre of a large df, |t| >= 1e100) it returns 0 and the
 * caller uses mcstat__t_tails. */
/* L(z) = log Gamma(z+1/2) - log Gamma(z) - log(z)/2 for z >= 10: the
 * asymptotic series sum_{n even} (2^(1-n) - 2) B_n / (n (n-1) z^(n-1)),
 * n = 2..16; the first term left out is below 4e-18 at z = 10 (mpmath). */
static PIX_INLINE double gamma_half_ratio(double z)
{
    double w = 1.0 / z, w2 = w * w;
    return w * (-1.0 / 8 + w2 * (1.0 / 192 + w2 * (-1.0 / 640 + w2 * (17.0 / 14336 +
           w2 * (-31.0 / 18432 + w2 * (691.0 / 180224 + w2 * (-5461.0 / 425984 +
           w2 * (929569.0 / 15728640))))))));
}

/* The df-dependent part of K: with a = df/2 shifted to z = a + k >= 10,
 *   Gamma(a+1/2)/(Gamma(a) sqrt(a)) = exp(L(z)) sqrt(z/a) prod_{i<k} (a+i)/(a+i+1/2),
 * kept as lc = L(z) - log(2 pi)/2 (for the exponent) and the factor f
 * (multiplying |t|), so K = |t| f exp(lc - (a+1/2) log1p(r)). */
typedef struct {
    double a, A, lc, f;
} t_prefactor;

/* f and lc at a = df/2 >= 1/2, with a fixed trip count and no branches, so
 * that a loop over pixels calling it vectorises: below 10, a is shifted by
 * k = 10 whatever it is (z in [10.5, 20): the series only gains), the
 * product taken unconditionally and chosen at the end, which costs fewer
 * operations than testing z < 10 at each of ten steps. */
static PIX_INLINE void t_prefactor_parts(double a, double *f, double *lc)
{
    double z = a, num = 1.0, den = 1.0;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 10
#endif
    for (int i = 0; i < 10; i++) {
        num *= z;
        den *= z + 0.5;
        z += 1.0;
    }
    int below = isless(a, 10.0); /* quiet: a trapping compare would not vectorise */
    z = below ? z : a;
    num = below ? num : 1.0;
    den = below ? den : 1.0;
    *f = sqrt((z * num * num) / (a * den * den));
    *lc = gamma_half_ratio(z) - LOG_2PI_HALF;
}

static void t_prefactor_init(double df, t_prefactor *pf)
{
    pf->a = 0.5 * df;
    pf->A = pf->a + 0.5;
    t_prefactor_parts(pf->a, &pf->f, &pf->lc);
}

/* 1/(3/2 + j): the central series' divisors, so its terms need no division. */
#define RCP1(j) 1.0 / (1.5 + (j))
#define RCP4(j) RCP1(j), RCP1((j) + 1), RCP1((j) + 2), RCP1((j) + 3)
#define RCP16(j) RCP4(j), RCP4((j) + 4), RCP4((j) + 8), RCP4((j) + 12)
#define RCP64(j) RCP16(j), RCP16((j) + 16), RCP16((j) + 32), RCP16((j) + 48)
#define CENTRAL_TERMS 448
static const double rcp_central[CENTRAL_TERMS] = {
    RCP64(0), RCP64(64), RCP64(128), RCP64(192), RCP64(256), RCP64(320), RCP64(384),
};

/* The upper tail's series sum_j c_j (c_0 = 1, ratio below x <= 1/2);
 * 0 if it has not converged in 200 terms. */
static PIX_INLINE int upper_series(double a, double A, double x, double *sum)
{
    double term = 1.0, s = 1.0;
    for (int j = 0;; j++) {
        if (j == 200)
            return 0;
        term *= (A + j) / (a + 1.0 + j) * x;
        s += term;
        if (term <= 1e-17 * s)
            break;
    }
    *sum = s;
    return 1;
}

/* The upper tail K h / (2a) where the central probability c is too close
 * to 1 for (1 - c)/2 (c > 0.96, |t| below sqrt(df)): h the continued
 * fraction of I_x(a, 1/2) = K h / a (DLMF 8.17.22, a + 1 > (a + 5/2) x
 * for the x = 1/(1+r) in (1/2, 1) met here at df >= 1: it converges),
 * evaluated by Lentz's method.  Its terms d_{2m} = m (1/2 - m) x /
 * ((a + 2m - 1)(a + 2m)), d_{2m+1} = -(a + m)(a + 1/2 + m) x / ((a + 2m)
 * (a + 2m + 1)).  The ratio of successive values goes to 1 within
 * DBL_EPSILON in 10 to 30 steps at the per-pixel df; each step's rounding
 * adds up, so beyond CF_STEPS (large df, x near 1) it returns 0 and the
 * general routine answers. */
#define CF_STEPS 40
/* h of four pixels (a[l], x[l]) at once; ok[l] = 0 where a lane has not
 * converged in CF_STEPS.  A lane's h stops changing when it converges, so
 * every lane gets what it would alone, bit for bit. */
static PIX_INLINE void upper_cf4(const double *a4, const double *x4, double *h4, int *ok)
{
    const mcs_v4d tiny = vm_splat(0x1p-1000), one = vm_splat(1.0);
    mcs_v4d a = {a4[0], a4[1], a4[2], a4[3]}, x = {x4[0], x4[1], x4[2], x4[3]};
    mcs_v4d c = one, d = one - (a + 0.5) * x / (a + 1.0);
    d = one / vm_select((mcs_v4i)(vm_fabs(d) < tiny), tiny, d);
    mcs_v4d h = d;
    mcs_v4i live = {-1, -1, -1, -1};
    for (int m = 1; m <= CF_STEPS; m++) {
        double m2 = 2.0 * m;
        for (int odd = 0; odd < 2; odd++) {
            mcs_v4d dm = odd ? -(a + (double)m) * (a + 0.5 + (double)m) * x / ((a + m2) * (a + 1.0 + m2))
                             : (double)m * (0.5 - m) * x / ((a - 1.0 + m2) * (a + m2));
            d = one + dm * d;
            c = one + dm / c;
            d = one / vm_select((mcs_v4i)(vm_fabs(d) < tiny), tiny, d);
            c = vm_select((mcs_v4i)(vm_fabs(c) < tiny), tiny, c);
            mcs_v4d step = c * d;
            h = vm_select(live, h * step, h);
            if (odd)
                live &= ~(mcs_v4i)(vm_fabs(step - 1.0) <= DBL_EPSILON);
        }
        if (!(live[0] | live[1] | live[2] | live[3]))
            break;
    }
    for (int l = 0; l < 4; l++) {
        h4[l] = h[l];
        ok[l] = !live[l];
    }
}

static int upper_cf(double a, double x, double k, double *upper)
{
    double a4[4] = {a, a, a, a}, x4[4] = {x, x, x, x}, h[4];
    int ok[4];
    upper_cf4(a4, x4, h, ok);
    if (!ok[0])
        return 0;
    *upper = k * h[0] / (2.0 * a);
    return 1;
}

/* The tails at |t| = at; *kk = K.  Returns 0 where the caller must use
 * mcstat__t_tails. */
static int t_tail_core(double at, const t_prefactor *pf, double *upper, double *other, double *kk)
{
    double a = pf->a, A = pf->A, df = 2.0 * a;
    double r = at * at / df;
    double y = r / (1.0 + r), x = 1.0 / (1.0 + r);
    if (r < 1.0 && A * y > 40.0) /* the central series would be long and c near 1 */
        return 0;
    /* |t| f exp(e), not exp(log(|t| f) + e): one logarithm fewer, and
     * the exponent's rounding (relative to K) does not grow with log |t| */
    double e = pf->lc - A * log1p(r);
    double k = e > -700.0 ? at * pf->f * exp(e) : exp(log(at * pf->f) + e);
    double term = 1.0, sum = 1.0;
    if (r >= 1.0) {
        if (!upper_series(a, A, x, &sum))
            return 0;
        double u = k * sum / (2.0 * a);
        *upper = u;
        *other = 1.0 - u;
    } else {
        /* two terms a step: the second from the first term's predecessor,
         * so the loop-carried chain is one multiplication per two terms */
        for (int j = 0;; j += 2) {
            if (j == CENTRAL_TERMS)
                return 0;
            double q0 = (A + j) * rcp_central[j] * y, q1 = (A + (j + 1)) * rcp_central[j + 1] * y;
            double t1 = term * q0;
            term *= q0 * q1;
            sum += t1 + term;
            if (term <= 0.25 * DBL_EPSILON * sum)
                break;
        }
        double c = 2.0 * k * sum, u;
        if (c <= 0.96) {
            *upper = 0.5 - 0.5 * c;
            *other = 0.5 + 0.5 * c;
        } else if (upper_cf(a, x, k, &u)) {
            *upper = u;
            *other = 1.0 - u;
        } else {
            return 0;
        }
    }
    *kk = k;
    return 1;
}

static int fast_range(double at, double df)
{
    return df >= 1.0 && df <= 1000.0 && at >= 1e-100 && at < 1e100;
}

int mcstat__t_tail_fast(double t, double df, double *upper, double *other, double *logk)
{
    double at = fabs(t);
    if (!fast_range(at, df))
        return 0;
    t_prefactor pf;
    double k;
    t_prefactor_init(df, &pf);
    if (!t_tail_core(at, &pf, upper, other, &k))
        return 0;
    *logk = log(at * pf.f) + pf.lc - pf.A * log1p(at * at / df); /* finite where K underflows */
    return 1;
}

/* The upper p-quantile of t(df) (0 < p < 1/2) by Halley's method in
 * z = log t on the fast tail: with g = log P[T > t] - log p,
 *   g' = -K/P,  g'' = g' (1 - (df+1) y + K/P),  y = t^2/(df+t^2),
 * (K = t f(t), d log K/dz = 1 - (df+1) y).  Started from Cornish-Fisher
 * (A&S 26.7.5, three terms), whose error of 1e-3..1e-5 at df >= 3 the cubic
 * convergence takes to rounding in two steps; it stops after a step below
 * 1e-6 (the error left is of the order of its cube).  pf is df's prefactor,
 * NULL to compute it.  Falls back to mcstat_t_quantile where the fast tail
 * does not apply or the iteration wanders. */
/* Near the centre (p -> 1/2) the quantile is the tail's absolute error
 * over the density, no longer small relative to itself: there, and for
 * p below 1e-100, mcstat_t_quantile answers. */
static int quantile_ok(double p, double df)
{
    return p >= 1e-100 && p <= 0.25 && df >= 1.0 && df <= 1000.0;
}

/* start: a starting value, NaN for Cornish-Fisher's. */
static int t_upper_quantile(double p, double df, const t_prefactor *pf, double start, double *q)
{
    if (quantile_ok(p, df)) {
        t_prefactor own;
        if (!pf) {
            t_prefactor_init(df, &own);
            pf = &own;
        }
        double t = start;
        if (!(t > 0.0)) {
            double g = mcstat__norm_quantile(p, 1), g2 = g * g, v = 1.0 / df;
            t = g + v * (g * (g2 + 1.0) / 4.0 +
                         v * (g * ((5.0 * g2 + 16.0) * g2 + 3.0) / 96.0 +
                              v * (g * (((3.0 * g2 + 19.0) * g2 + 17.0) * g2 - 15.0) / 384.0)));
        }
        double lp = log(p);
        if (t > 0.0 && isfinite(t)) {
            double z = log(t);
            for (int it = 0; it < 30; it++) {
                double u, o, k, at = exp(z);
                if (!fast_range(at, df) || !t_tail_core(at, pf, &u, &o, &k) || !(u > 0.0))
                    break;
                double h = log(u) - lp, kp = k / u, y = at * at / (df + at * at);
                double d1 = -kp, d2 = d1 * (1.0 - (df + 1.0) * y + kp);
                double step = -h / d1;
                double den = 1.0 + 0.5 * step * d2 / d1; /* Halley: -h / (d1 - h d2 / (2 d1)) */
                if (den > 0.5)
                    step /= den;
                if (!isfinite(step))
                    break;
                step = fmax(-2.0, fmin(2.0, step));
                z += step;
                if (fabs(step) < 1e-6) {
                    *q = exp(z);
                    return MCSTAT_OK;
                }
            }
        }
    }
    return mcstat_t_quantile(p, df, 1, q);
}

int mcstat__t_upper_quantile_fast(double p, double df, double *q)
{
    return t_upper_quantile(p, df, NULL, NAN, q);
}

/* ---- one pixel's outputs --------------------------------------------------- */

typedef struct {
    const mcstat_pixels_out *out;
    int alternative, intervals;
    double mu0, alpha;
    double crit_two; /* the two-sided critical value at the last df, and that df */
    double crit_df;
    double qt_p; /* the level of the critical values: alpha/2 or alpha */
    double *qt;  /* their quantiles at df = qt_n / j, j = 0..qt_n, NaN until needed */
    int qt_n;
    mcstat_qcache qc; /* the slow path's */
    uint64_t nx, ny;  /* the sample sizes of the fast path */
    int first;        /* status of the first failing pixel */
    size_t first_i;   /* and its index */
} pix_ctx;

static void put(const pix_ctx *c, size_t i, int st, double p, double t, double df, double se, double mx,
                double my, double lo, double hi, double c0, double c1, int dec, uint64_t nx, uint64_t ny)
{
    const mcstat_pixels_out *o = c->out;
    if (o->df2)
        o->df2[i] = NAN;
    if (o->critical_lo)
        o->critical_lo[i] = c0;
    if (o->critical_hi)
        o->critical_hi[i] = c1;
    if (o->decision)
        o->decision[i] = (int8_t)dec;
    if (o->n_x)
        o->n_x[i] = nx;
    if (o->n_y)
        o->n_y[i] = ny;
    if (o->std_error)
        o->std_error[i] = se;
    if (o->p_value)
        o->p_value[i] = p;
    if (o->statistic)
        o->statistic[i] = t;
    if (o->df)
        o->df[i] = df;
    if (o->estimate)
        o->estimate[i] = mx;
    if (o->estimate2)
        o->estimate2[i] = my;
    if (o->conf_lo)
        o->conf_lo[i] = lo;
    if (o->conf_hi)
        o->conf_hi[i] = hi;
    if (o->status)
        o->status[i] = st;
}

static void fail(pix_ctx *c, size_t i, int st)
{
    put(c, i, st, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, 0, 0, 0);
    if (c->first == MCSTAT_OK) {
        c->first = st;
        c->first_i = i;
    }
}

/* ---- the slow path: the single call's code ---------------------------------- */

typedef struct {
    const float *f;
    const double *d;
    size_t stride, ps, channels; /* value and pixel strides, elements per value */
    const double *w;
} plane;

static double value(const plane *pl, size_t s, size_t i)
{
    size_t k = s * pl->stride + i * pl->ps;
    if (pl->channels == 1 && !pl->w)
        return pl->f ? (double)pl->f[k] : pl->d[k];
    double v = 0.0;
    for (size_t c = 0; c < pl->channels; c++)
        v += pl->w[c] * (pl->f ? (double)pl->f[k + c] : pl->d[k + c]);
    return v;
}

/* One pixel's sample into m, GATHER values at a time. */
static int pixel_moments(const plane *pl, size_t n, size_t i, unsigned flags, mcstat_moments *m)
{
    double buf[GATHER];
    mcstat_moments_init(m);
    for (size_t s0 = 0; s0 < n; s0 += GATHER) {
        size_t k = n - s0 < GATHER ? n - s0 : GATHER;
        for (size_t j = 0; j < k; j++)
            buf[j] = value(pl, s0 + j, i);
        int st = (flags & MCSTAT_ROWS_OMIT_NAN) ? mcstat_moments_add_array_omit_nan(m, buf, k, NULL)
                                                : mcstat_moments_add_array(m, buf, k);
        if (st)
            return st;
    }
    return MCSTAT_OK;
}

static void slow_pixel(pix_ctx *c, const plane *px, size_t nx, const plane *py, size_t ny, size_t i,
                       unsigned flags)
{
    mcstat_moments mx, my;
    mcstat_result r;
    int st = pixel_moments(px, nx, i, flags, &mx);
    if (!st)
        st = pixel_moments(py, ny, i, flags, &my);
    if (!st)
        st = mcstat__t_test_2(&mx, &my, c->mu0, c->alternative, c->alpha, c->intervals ? &c->qc : NULL, &r);
    if (st) {
        fail(c, i, st);
        return;
    }
    put(c, i, MCSTAT_OK, r.p_value, r.statistic, r.df[0], r.std_error, r.estimate[0], r.estimate[1], r.conf_int[0],
        r.conf_int[1], r.critical[0], r.critical[1], r.decision, r.n[0], r.n[1]);
}

/* ---- the fast path ------------------------------------------------------------ */

/* Lagrange's values through nodes 0..4 (v5) and 0..5 (v6) at s: the
 * weights prod_{m != i} (s - m) / prod_{m != i} (i - m), their numerators
 * from prefix and suffix products, their denominators constants (six
 * nodes: -+120, 24, 12; five: 24, 6, 4): no division, no branch. */
static PIX_INLINE void lagrange56(const double *q, double s, double *v5, double *v6)
{
    double d0 = s, d1 = s - 1.0, d2 = s - 2.0, d3 = s - 3.0, d4 = s - 4.0, d5 = s - 5.0;
    double p01 = d0 * d1, p012 = p01 * d2, p0123 = p012 * d3;
    double s45 = d4 * d5, s345 = d3 * s45, s2345 = d2 * s345;
    double s34 = d3 * d4, s234 = d2 * s34;
    *v6 = d1 * s2345 * (-1.0 / 120) * q[0] + d0 * s2345 * (1.0 / 24) * q[1] + p01 * s345 * (-1.0 / 12) * q[2] +
          p012 * s45 * (1.0 / 12) * q[3] + p0123 * d5 * (-1.0 / 24) * q[4] + p0123 * d4 * (1.0 / 120) * q[5];
    *v5 = d1 * s234 * (1.0 / 24) * q[0] + d0 * s234 * (-1.0 / 6) * q[1] + p01 * s34 * (1.0 / 4) * q[2] +
          p012 * d4 * (-1.0 / 6) * q[3] + p0123 * (1.0 / 24) * q[4];
}

/* The per-call table of critical values at level p in qt[0..n], empty
 * (NaN: solved when first needed). */
static void qt_table_init(pix_ctx *c, double p, double *qt, int n)
{
    c->qt_p = p;
    c->qt = qt;
    c->qt_n = n;
    for (int j = 0; j <= n; j++)
        qt[j] = NAN;
}

/* Node j of the table: the quantile at df = qt_n / j, solved once per
 * call when first needed (node 0 is df = Inf, the normal quantile); the
 * same numbers whichever pixels ask, so pixel ranges do not change results. */
static double qt_node(pix_ctx *c, int j)
{
    if (isnan(c->qt[j])) {
        double q = NAN;
        if (j == 0)
            q = mcstat__norm_quantile(c->qt_p, 1);
        else if (t_upper_quantile(c->qt_p, (double)c->qt_n / j, NULL, NAN, &q))
            q = NAN;
        c->qt[j] = q;
    }
    return c->qt[j];
}

/* The quantile at df from the table: Lagrange through the six nearest
 * nodes in u = qt_n/df (the quantile is smooth in 1/df: its
 * Cornish-Fisher series is one in 1/df).  *exact is set where the five- and
 * six-point values agree to 1e-13, i.e. where the six-point one is good to
 * rounding (measured against SciPy over df in [1, 1000]: within 1.4e-15 at
 * p = 0.025, 0.005, 1e-4, 5e-7); elsewhere it is only Halley's starting
 * value.  NaN where a node failed (Cornish-Fisher starts then). */
static double qt_interp(pix_ctx *c, double df, int *exact)
{
    *exact = 0;
    if (!quantile_ok(c->qt_p, df))
        return NAN;
    const int n = c->qt_n;
    double u = n / df;
    int k = (int)u - 2;
    k = k < 0 ? 0 : k > n - 5 ? n - 5 : k;
    double q[6], v5, v6;
    for (int i = 0; i < 6; i++)
        q[i] = qt_node(c, k + i);
    lagrange56(q, u - k, &v5, &v6);
    *exact = fabs(v6 - v5) < 1e-13 * fabs(v6);
    return v6;
}

/* The critical values (c0, c1) of t(df) for the alternative, as
 * mcstat__finish asks them: two-sided -+q(alpha/2); "less" -q(alpha), +Inf;
 * "greater" -Inf, q(alpha). */
static int criticals(pix_ctx *c, double df, const t_prefactor *pf, double *c0, double *c1)
{
    double q;
    int st;
    if (c->alternative == MCSTAT_TWO_SIDED) {
        if (df != c->crit_df) { /* equal df (equal variances' ratio) repeat in flat regions */
            int exact;
            q = qt_interp(c, df, &exact);
            if (!exact && (st = t_upper_quantile(c->qt_p, df, pf, q, &q)))
                return st;
            c->crit_two = q;
            c->crit_df = df;
        }
        *c0 = -c->crit_two;
        *c1 = c->crit_two;
        return MCSTAT_OK;
    }
    int exact;
    q = qt_interp(c, df, &exact);
    if (!exact && (st = t_upper_quantile(c->qt_p, df, pf, q, &q)))
        return st;
    if (c->alternative == MCSTAT_LESS) {
        *c0 = -q;
        *c1 = INFINITY;
    } else {
        *c0 = -INFINITY;
        *c1 = q;
    }
    return MCSTAT_OK;
}

/* fmin/fmax are library calls without -ffinite-math-only; nothing here is NaN */
static inline double dmin(double u, double v) { return u < v ? u : v; }
static inline double dmax(double u, double v) { return u > v ? u : v; }

/* x / d, by a multiplication where d is a power of two (x * (1/d) is then
 * x / d exactly): the divider bounds the block loops, and seed counts are
 * often powers of two.  inv = 1/d; pow2 is the same for a whole loop,
 * which the compiler then unswitches. */
static PIX_INLINE double div_by(double x, double d, double inv, int pow2)
{
    return pow2 ? x * inv : x / d;
}

static int pow2_count(size_t n)
{
    return n > 0 && (n & (n - 1)) == 0;
}

/* A block's statistics, computed pixel by pixel in straight-line loops the
 * compiler vectorises (no branches, no calls, no floating-point operation
 * done conditionally, which -ftrapping-math forbids it to speculate): the
 * moments in; t, df, the standard error, the difference of the means, the
 * t prefactor and each pixel's fate out. */
enum { PIX_FAST, PIX_SLOW, PIX_DEGENERATE };

typedef struct {
    double t[PIX_BLOCK], df[PIX_BLOCK], se[PIX_BLOCK], dhi[PIX_BLOCK], dlo[PIX_BLOCK];
    double sdmax[PIX_BLOCK], lim[PIX_BLOCK];
    double pa[PIX_BLOCK], pf[PIX_BLOCK], plc[PIX_BLOCK]; /* t_prefactor's a, f, lc */
    double lower[PIX_BLOCK], upper[PIX_BLOCK]; /* the tails, where tail_ok */
    double conf_lo[PIX_BLOCK], conf_hi[PIX_BLOCK]; /* the interval, where bound_ok, then the outputs' */
    double crit_lo[PIX_BLOCK], crit_hi[PIX_BLOCK]; /* the critical values, likewise */
    signed char dec[PIX_BLOCK];                    /* MCSTAT_DECISION_*, where done */
    double p[PIX_BLOCK];                           /* the p-value, where done */
    unsigned char done[PIX_BLOCK];                 /* fast_values answered */
    double qn[6][PIX_BLOCK], qs[PIX_BLOCK]; /* the critical values' six table nodes and the offset in them */
    long long bound_ok[PIX_BLOCK]; /* 64 bits, as the doubles: the loop vectorises */
    unsigned char kind[PIX_BLOCK], tail_ok[PIX_BLOCK];
} block_stats;

static PIX_INLINE void block_statistics(size_t k, double nx, const mcstat_dd *mx, const double *m2x, const unsigned char *bx,
                             double ny, const mcstat_dd *my, const double *m2y, const unsigned char *by, double mu0,
                             block_stats *bs)
{
    const int px = pow2_count((size_t)nx), py = pow2_count((size_t)ny);
    const double ix = 1.0 / nx, iy = 1.0 / ny;
    for (size_t j = 0; j < k; j++) {
        double vx = m2x[j] / (nx - 1.0), vy = m2y[j] / (ny - 1.0);
        double a = div_by(vx, nx, ix, px), b = div_by(vy, ny, iy, py), se = sqrt(a + b);
        mcstat_dd diff = dd_add(mx[j], dd_neg(my[j]));
        mcstat_dd sh = dd_add(diff, (mcstat_dd){-mu0, 0.0});
        double m = dmax(a, b), ra = a / m, rb = b / m;
        bs->df[j] = (ra + rb) * (ra + rb) / (ra * ra / (nx - 1.0) + rb * rb / (ny - 1.0));
        bs->t[j] = (sh.hi + sh.lo) / se;
        bs->se[j] = se;
        bs->dhi[j] = diff.hi;
        bs->dlo[j] = diff.lo;
        bs->sdmax[j] = sqrt(dmax(vx, vy));
        bs->lim[j] = 10.0 * DBL_EPSILON * dmax(fabs(mx[j].hi), fabs(my[j].hi));
    }
    for (size_t j = 0; j < k; j++) {
        double m2a = m2x[j], m2b = m2y[j], sdmax = bs->sdmax[j], lim = bs->lim[j];
        /* moments.c's var_scaled moves exponents beyond 2^+-500 out of m2 */
        int extreme = (m2a > 0.0 && (m2a < 0x1p-500 || m2a > 0x1p+500)) ||
                      (m2b > 0.0 && (m2b < 0x1p-500 || m2b > 0x1p+500));
        /* t_test.c's "constant to within rounding"; near its edge, where the
         * two accumulations of M2 might decide differently, the slow path
         * decides */
        int degenerate = !(bs->se[j] > 0.0) || sdmax < lim * (1.0 - 1e-6);
        int edge = sdmax < lim * (1.0 + 1e-6);
        bs->kind[j] = (unsigned char)(bx[j] || by[j] || extreme ? PIX_SLOW
                                      : degenerate              ? PIX_DEGENERATE
                                      : edge                    ? PIX_SLOW
                                                                : PIX_FAST);
    }
    /* the t prefactor (t_prefactor_init), where the fast tail can use it */
    for (size_t j = 0; j < k; j++) {
        double a = 0.5 * bs->df[j]; /* used only where df is in [1, 1000] */
        bs->pa[j] = a;
        t_prefactor_parts(a, &bs->pf[j], &bs->plc[j]);
    }
}

/* ---- the tails of a block ----------------------------------------------
 * t_tail_core for many pixels: the prefactors four pixels at a time, the
 * upper series pixel by pixel (few pixels), the central series (most
 * pixels under the null) eight at a time, so its loop runs as long as the
 * slowest of eight and its exit is taken once per eight pixels instead of
 * mispredicted once per pixel; the continued fraction four at a time.  A
 * lane that has converged goes on adding terms below its rounding; the
 * sums are those of t_tail_core to a few ulps. */
/* Two terms of the central series of four pixels: term <- term q0 q1 and
 * s <- s + term q0 + term q0 q1, q_i = (A + j + i) / (3/2 + j + i) y; the
 * loop-carried chain is one multiplication per two terms. */
#define CENTRAL_STEP2(va, vy, j, term, s)                                                                   \
    do {                                                                                                     \
        mcs_v4d q0_ = ((va) + (double)(j)) * rcp_central[j] * (vy);                                          \
        mcs_v4d q1_ = ((va) + (double)((j) + 1)) * rcp_central[(j) + 1] * (vy);                              \
        mcs_v4d t1_ = (term) * q0_;                                                                          \
        (term) = (term) * (q0_ * q1_);                                                                       \
        (s) = (s) + (t1_ + (term));                                                                          \
    } while (0)

/* Four pixels' central series from term j on, four terms a step, until
 * all four have converged (until_done) or up to term jend; returns the
 * term it stopped at.  A converged lane stays converged (its terms only
 * fall from there on). */
static PIX_INLINE int central_run4(mcs_v4d va, mcs_v4d vy, mcs_v4d *term, mcs_v4d *s, int j, int jend, int until_done)
{
    for (; j < jend; j += 4) { /* four terms between the tests of convergence */
        CENTRAL_STEP2(va, vy, j, *term, *s);
        CENTRAL_STEP2(va, vy, j + 2, *term, *s);
        if (until_done) {
            mcs_v4i done = (mcs_v4i)(*term <= 0.25 * DBL_EPSILON * *s);
            if (done[0] & done[1] & done[2] & done[3])
                return j + 4;
        }
    }
    return j;
}

#if PIX_AVX2
#include <immintrin.h>
/* central_series8's AVX2 loop: both vectors of four side by side, the
 * test of convergence of all eight lanes by one movemask (extracting the
 * lanes took 5% of the kernel).  Pointers in and out, and the step as a
 * macro: no 32-byte vector crosses a call between AVX2 and baseline code
 * (clang refuses that ABI change even where the call is never taken). */
__attribute__((target("avx2"))) static inline int central_joint8(const double *A, const double *y, double *sum)
{
    mcs_v4d va0 = {A[0], A[1], A[2], A[3]}, vy0 = {y[0], y[1], y[2], y[3]};
    mcs_v4d va1 = {A[4], A[5], A[6], A[7]}, vy1 = {y[4], y[5], y[6], y[7]};
    mcs_v4d t0 = {1.0, 1.0, 1.0, 1.0}, s0 = t0, t1 = t0, s1 = t0;
    for (int j = 0; j < CENTRAL_TERMS; j += 4) { /* four terms between the tests of convergence */
        CENTRAL_STEP2(va0, vy0, j, t0, s0);
        CENTRAL_STEP2(va1, vy1, j, t1, s1);
        CENTRAL_STEP2(va0, vy0, j + 2, t0, s0);
        CENTRAL_STEP2(va1, vy1, j + 2, t1, s1);
        mcs_v4i done = (mcs_v4i)(t0 <= 0.25 * DBL_EPSILON * s0) & (mcs_v4i)(t1 <= 0.25 * DBL_EPSILON * s1);
        if (_mm256_movemask_pd((__m256d)done) == 15) {
            for (int l = 0; l < 4; l++) {
                sum[l] = s0[l];
                sum[l + 4] = s1[l];
            }
            return 1;
        }
    }
    return 0;
}
#endif

/* The central sums of eight pixels (A = a + 1/2, y), as many terms for all
 * eight as the slowest needs; 0 if one has not converged in CENTRAL_TERMS
 * terms.  joint (AVX2): the two vectors of four side by side, so that
 * their chains overlap in the pipeline; else (SSE2, whose sixteen
 * registers the side-by-side loop overflows) one after the other, the one
 * that stopped first taken on to where the other stopped: the same terms,
 * the same sums, bit for bit. */
static PIX_INLINE int central_series8(const double *A, const double *y, double *sum, int joint)
{
#if PIX_AVX2
    if (joint)
        return central_joint8(A, y, sum);
#endif
    (void)joint;
    mcs_v4d va0 = {A[0], A[1], A[2], A[3]}, vy0 = {y[0], y[1], y[2], y[3]};
    mcs_v4d va1 = {A[4], A[5], A[6], A[7]}, vy1 = {y[4], y[5], y[6], y[7]};
    mcs_v4d t0 = vm_splat(1.0), s0 = t0, t1 = t0, s1 = t0;
    int j0 = central_run4(va0, vy0, &t0, &s0, 0, CENTRAL_TERMS, 1);
    int j1 = central_run4(va1, vy1, &t1, &s1, 0, CENTRAL_TERMS, 1);
    mcs_v4i done = (mcs_v4i)(t0 <= 0.25 * DBL_EPSILON * s0) & (mcs_v4i)(t1 <= 0.25 * DBL_EPSILON * s1);
    int ok = done[0] & done[1] & done[2] & done[3] ? 1 : 0;
    if (j0 < j1)
        central_run4(va0, vy0, &t0, &s0, j0, j1, 0);
    else if (j1 < j0)
        central_run4(va1, vy1, &t1, &s1, j1, j0, 0);
    if (!ok)
        return 0;
    for (int l = 0; l < 4; l++) {
        sum[l] = s0[l];
        sum[l + 4] = s1[l];
    }
    return 1;
}

/* Both tails of t(df) at t[j] for the k pixels with want[j] (prefactors
 * pa, pf, plc as block_statistics leaves them): lower[j], upper[j] where
 * ok[j] = TAIL_DONE; TAIL_GENERAL where t_tail_core would return 0 too (the
 * general mcstat__t_tails answers), TAIL_SCALAR where the scalar path
 * decides (K underflows, df or t outside the fast range). */
enum { TAIL_SCALAR, TAIL_DONE, TAIL_GENERAL };

/* Four pixels' e = lc - A log1p(r), K = |t| f exp(e) and y = r/(1+r) from
 * r, a, lc, f and t (vmath.h); lanes with r = 0 (no fast tail) compute
 * with harmless stand-ins, and K only where exp(e) stays normal. */
static PIX_INLINE void tails_k4(mcs_v4d r, mcs_v4d a, mcs_v4d lc, mcs_v4d f, mcs_v4d t, double *e4, double *k4,
                                double *y4)
{
    mcs_v4i pos = (mcs_v4i)(r > 0.0);
    a = vm_select(pos, a, vm_splat(1.0));
    lc = vm_select(pos, lc, vm_splat(0.0));
    f = vm_select(pos, f, vm_splat(1.0));
    mcs_v4d at = vm_fabs(t);
    mcs_v4d e = lc - (a + 0.5) * vm_log1p4(r);
    mcs_v4i low = (mcs_v4i)(e < -700.0);
    mcs_v4d x = vm_exp4(vm_select(low, vm_splat(-700.0), e));
    mcs_v4d kv = at * f * x, y = r / (1.0 + r);
    memcpy(e4, &e, sizeof e);
    memcpy(k4, &kv, sizeof kv);
    memcpy(y4, &y, sizeof y);
}
static PIX_INLINE void block_tails(size_t k, const double *t, const double *df, const double *pa, const double *pf,
                                   const double *plc, const unsigned char *want, double *lower, double *upper,
                                   unsigned char *ok, int joint)
{
    size_t idx[PIX_BLOCK + 3], nc = 0;
    double cA[PIX_BLOCK + 3], cy[PIX_BLOCK + 3], ck[PIX_BLOCK + 3], cs[8];
    /* Four lanes of the central series run as long as the slowest: grouped
     * by the binary exponent of y (which sets the series' length), lanes of
     * a kind run together.  A counting sort, into sidx, sA, sy, sk; the
     * bins counted as the lanes are found. */
    enum { Y_BINS = 8 };
    size_t cnt[Y_BINS + 1] = {0}, sidx[PIX_BLOCK + 7];
    double sA[PIX_BLOCK + 7], sy[PIX_BLOCK + 7], sk[PIX_BLOCK + 7];
    unsigned char bin[PIX_BLOCK];
    double rr[PIX_BLOCK], ee[PIX_BLOCK], kk[PIX_BLOCK], yy[PIX_BLOCK];
    double uu[PIX_BLOCK]; /* the upper tail at |t| where ok = TAIL_DONE */
    /* r, then e, K and y four pixels at a time (tails_k4); r = 0 where the
     * fast tail has nothing to do */
    for (size_t j = 0; j < k; j++) {
        double at = fabs(t[j]);
        rr[j] = want[j] && t[j] != 0.0 && fast_range(at, df[j]) ? at * at / df[j] : 0.0;
        uu[j] = 0.5; /* t = 0's */
    }
    size_t j = 0;
    for (; j + 4 <= k; j += 4) {
        mcs_v4d r, a, lc, f, at;
        memcpy(&r, rr + j, sizeof r);
        memcpy(&a, pa + j, sizeof a);
        memcpy(&lc, plc + j, sizeof lc);
        memcpy(&f, pf + j, sizeof f);
        memcpy(&at, t + j, sizeof at);
        tails_k4(r, a, lc, f, at, ee + j, kk + j, yy + j);
    }
    if (j < k) {
        mcs_v4d r, a, lc, f, at;
        double e4[4], k4[4], y4[4];
        for (int l = 0; l < 4; l++) {
            size_t i = j + l < k ? j + l : j; /* past k: a copy of pixel j */
            r[l] = rr[i];
            a[l] = pa[i];
            lc[l] = plc[i];
            f[l] = pf[i];
            at[l] = t[i];
        }
        tails_k4(r, a, lc, f, at, e4, k4, y4);
        for (int l = 0; j + l < k; l++) {
            ee[j + l] = e4[l];
            kk[j + l] = k4[l];
            yy[j + l] = y4[l];
        }
    }
    for (size_t j = 0; j < k; j++) {
        double tj = t[j];
        ok[j] = TAIL_SCALAR;
        if (!want[j])
            continue;
        if (tj == 0.0) {
            ok[j] = TAIL_DONE;
            continue;
        }
        if (!(rr[j] > 0.0)) /* outside the fast range (rr's first loop) */
            continue;
        ok[j] = TAIL_GENERAL; /* unless answered below, as for t_tail_core */
        double a = pa[j], A = a + 0.5, r = rr[j], y = yy[j];
        if (r < 1.0 && A * y > 40.0)
            continue;
        if (!(ee[j] > -700.0)) {
            ok[j] = TAIL_SCALAR; /* K underflows here: t_tail_core's logarithmic form */
            continue;
        }
        double kj = kk[j];
        if (r >= 1.0) {
            double sum;
            if (!upper_series(a, A, 1.0 / (1.0 + r), &sum))
                continue;
            uu[j] = kj * sum / (2.0 * a);
            ok[j] = TAIL_DONE;
        } else {
            uint64_t bits;
            memcpy(&bits, &y, sizeof bits);
            int e = 1021 - (int)(bits >> 52); /* y in [2^-(e+2), 2^-(e+1)), as 0 < y < 1/2 here */
            bin[nc] = (unsigned char)(e < Y_BINS - 1 ? e : Y_BINS - 1);
            cnt[bin[nc] + 1]++;
            idx[nc] = j;
            cA[nc] = A;
            cy[nc] = y;
            ck[nc] = kj;
            nc++;
        }
    }
    /* the counting sort: bin b's lanes to sidx[cnt[b]] on, in their order */
    for (int b = 0; b < Y_BINS; b++)
        cnt[b + 1] += cnt[b];
    for (size_t g = 0; g < nc; g++) {
        size_t o = cnt[bin[g]]++;
        sidx[o] = idx[g];
        sA[o] = cA[g];
        sy[o] = cy[g];
        sk[o] = ck[g];
    }
    for (size_t g = nc; g % 8; g++) { /* padding lanes: converged at once */
        sA[g] = 1.0;
        sy[g] = 0.0;
    }
    /* the pixels whose central probability is too close to 1 wait for the
     * continued fraction, four at a time too (a, x, K in cA, cy, ck; their
     * index in idx) */
    size_t nf = 0;
    for (size_t g = 0; g < nc; g += 8) {
        if (!central_series8(sA + g, sy + g, cs, joint))
            continue;
        for (size_t l = 0; l < 8 && g + l < nc; l++) {
            size_t j = sidx[g + l];
            double c = 2.0 * sk[g + l] * cs[l], u = 0.5 - 0.5 * c;
            if (!(c <= 0.96)) {
                idx[nf] = j;
                cA[nf] = sA[g + l] - 0.5; /* a */
                cy[nf] = 1.0 / (1.0 + rr[j]); /* x */
                ck[nf] = sk[g + l];
                nf++;
                continue;
            }
            uu[j] = u;
            ok[j] = TAIL_DONE;
        }
    }
    for (size_t g = nf; g % 4; g++) { /* padding lanes: converge at once */
        cA[g] = 1.0;
        cy[g] = 0.0;
    }
    for (size_t g = 0; g < nf; g += 4) {
        double h[4];
        int hok[4];
        upper_cf4(cA + g, cy + g, h, hok);
        for (size_t l = 0; l < 4 && g + l < nf; l++) {
            if (!hok[l])
                continue;
            size_t j = idx[g + l];
            uu[j] = ck[g + l] * h[l] / (2.0 * cA[g + l]);
            ok[j] = TAIL_DONE;
        }
    }
    /* lower, upper <- 1 - u, u for t > 0, else u, 1 - u, in a loop that
     * vectorises (a branch on t's sign, a coin toss under the null, was
     * mispredicted for every other pixel; and the lanes' scattered stores
     * were twice as many) */
    for (size_t j = 0; j < k; j++) {
        double u = uu[j], v = 1.0 - u;
        int pos = t[j] > 0.0;
        lower[j] = pos ? v : u;
        upper[j] = pos ? u : v;
    }
}

/* Both tails for n (t, df) pairs through block_tails, PIX_BLOCK at a time;
 * done[i] = 1 where it answered (elsewhere the pixels take the scalar
 * path).  For the tests, which hold it to the same reference as the
 * scalar tail. */
int mcstat__t_tails_block(size_t n, const double *t, const double *df, double *lower, double *upper,
                          unsigned char *done)
{
    MCSTAT_IEEE_SCOPE();
    double pa[PIX_BLOCK], pf[PIX_BLOCK], plc[PIX_BLOCK];
    unsigned char want[PIX_BLOCK], ok[PIX_BLOCK];
    for (size_t i0 = 0; i0 < n; i0 += PIX_BLOCK) {
        size_t k = n - i0 < PIX_BLOCK ? n - i0 : PIX_BLOCK;
        for (size_t j = 0; j < k; j++) {
            double d = df[i0 + j];
            want[j] = d >= 1.0 && d <= 1000.0;
            pa[j] = 0.5 * (want[j] ? d : 1.0);
            t_prefactor_parts(pa[j], &pf[j], &plc[j]);
        }
        block_tails(k, t + i0, df + i0, pa, pf, plc, want, lower + i0, upper + i0, ok, 0);
        for (size_t j = 0; j < k; j++)
            done[i0 + j] = ok[j] == TAIL_DONE;
    }
    return MCSTAT_OK;
}

/* ---- the intervals of a block -------------------------------------------
 * The critical values by qt_interp's table and weights and the bounds by
 * mcstat__ci_bound's double-double arithmetic, for all pixels of a block in
 * one branch-free loop; where the interpolation is not good to rounding, or
 * a bound needs ci_bound's guard against overflow, bound_ok is 0 and the
 * pixel's own path (criticals, Halley, ci_bound) decides.  First the
 * table's nodes each pixel needs (solved lazily, one pixel at a time). */
static void table_nodes(pix_ctx *c, size_t k, const double *df, const unsigned char *want, double (*qn)[PIX_BLOCK],
                        double *qs)
{
    const int n = c->qt_n;
    for (size_t j = 0; j < k; j++) {
        int have = (!want || want[j]) && quantile_ok(c->qt_p, df[j]);
        int n0 = have ? (int)(n / df[j]) - 2 : 0;
        n0 = n0 < 0 ? 0 : n0 > n - 5 ? n - 5 : n0;
        for (int i = 0; i < 6; i++)
            qn[i][j] = have ? qt_node(c, n0 + i) : NAN; /* NaN: no value here */
        qs[j] = have ? n / df[j] - n0 : 0.0;
    }
}

static void block_nodes(pix_ctx *c, size_t k, block_stats *st)
{
    unsigned char fast[PIX_BLOCK];
    for (size_t j = 0; j < k; j++)
        fast[j] = st->kind[j] == PIX_FAST;
    table_nodes(c, k, st->df, fast, st->qn, st->qs);
}

static PIX_INLINE void block_bounds(size_t k, int alternative, block_stats *st)
{
    for (size_t j = 0; j < k; j++) {
        double q[6], v5, v6, se = st->se[j];
        for (int i = 0; i < 6; i++)
            q[i] = st->qn[i][j];
        lagrange56(q, st->qs[j], &v5, &v6);
        double aq = fabs(v6);
        /* false where a node is NaN */
        long long ok = (fabs(v6 - v5) < 1e-13 * aq) & (aq <= 0x1p900) & (aq * se <= 0x1p900);
        mcstat_dd est = {st->dhi[j], st->dlo[j]}, p = dd_two_prod(v6, se);
        mcstat_dd lo = dd_add(est, dd_neg(p)), hi = dd_add(est, p); /* est -+ q se */
        st->conf_lo[j] = alternative == MCSTAT_LESS ? -INFINITY : lo.hi + lo.lo;
        st->conf_hi[j] = alternative == MCSTAT_GREATER ? INFINITY : hi.hi + hi.lo;
        st->crit_lo[j] = alternative == MCSTAT_GREATER ? -INFINITY : -v6;
        st->crit_hi[j] = alternative == MCSTAT_LESS ? INFINITY : v6;
        st->bound_ok[j] = ok;
    }
}

static void block_bounds_pass(size_t k, int alternative, block_stats *st)
{
    block_bounds(k, alternative, st);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void block_bounds_pass_avx2(size_t k, int alternative, block_stats *st)
{
    block_bounds(k, alternative, st);
}
#endif

/* Pixel i's outputs from its statistics; returns 0 where the slow path must
 * decide. */
static int fast_values(pix_ctx *c, block_stats *bs, size_t j)
{
    double t = bs->t[j], df = bs->df[j], se = bs->se[j];
    double up, other, kk, lo_tail, hi_tail;
    t_prefactor pf, *ppf = NULL;
    if (df >= 1.0 && df <= 1000.0) { /* shared by the tail and the quantile */
        pf.a = bs->pa[j];
        pf.A = pf.a + 0.5;
        pf.f = bs->pf[j];
        pf.lc = bs->plc[j];
        ppf = &pf;
    }
    if (bs->tail_ok[j] == TAIL_DONE) {
        lo_tail = bs->lower[j];
        hi_tail = bs->upper[j];
    } else if (t == 0.0) {
        lo_tail = hi_tail = 0.5;
    } else if (bs->tail_ok[j] == TAIL_SCALAR && ppf && fast_range(fabs(t), df) &&
               t_tail_core(fabs(t), ppf, &up, &other, &kk)) {
        lo_tail = t > 0.0 ? other : up;
        hi_tail = t > 0.0 ? up : other;
    } else {
        mcstat_tails tt;
        if (mcstat__t_tails(t, df, &tt))
            return 0;
        lo_tail = tt.p;
        hi_tail = tt.q;
    }
    double p = c->alternative == MCSTAT_LESS      ? lo_tail
               : c->alternative == MCSTAT_GREATER ? hi_tail
                                                  : dmin(1.0, 2.0 * dmin(lo_tail, hi_tail));
    double lo = NAN, hi = NAN, c0 = NAN, c1 = NAN;
    if (c->intervals && bs->bound_ok[j]) {
        lo = bs->conf_lo[j];
        hi = bs->conf_hi[j];
        c0 = bs->crit_lo[j];
        c1 = bs->crit_hi[j];
    } else if (c->intervals) {
        if (criticals(c, df, ppf, &c0, &c1))
            return 0;
        mcstat_dd diff = {bs->dhi[j], bs->dlo[j]};
        lo = mcstat__ci_bound(diff, c1, se, 0);
        hi = mcstat__ci_bound(diff, c0, se, 0);
    }
    /* mcstat__finish's rule: the side of the smaller tail (two-sided) */
    int low_side = c->alternative == MCSTAT_LESS || (c->alternative == MCSTAT_TWO_SIDED && lo_tail < hi_tail);
    bs->dec[j] = (signed char)(p <= c->alpha ? (low_side ? MCSTAT_DECISION_LESS : MCSTAT_DECISION_GREATER)
                                             : MCSTAT_DECISION_EQUAL);
    bs->p[j] = p;
    bs->conf_lo[j] = lo;
    bs->conf_hi[j] = hi;
    bs->crit_lo[j] = c0;
    bs->crit_hi[j] = c1;
    return 1;
}

/* done[j] and p[j] for the block: where the block passes answered the
 * tails (and the bounds, with intervals), the p-value in a loop that
 * vectorises (lower and upper elsewhere hold a previous block's numbers or
 * the zeros of calloc, and are not used); fast_values for the other fast
 * pixels. */
static void block_values(pix_ctx *c, size_t k, block_stats *bs)
{
    const int alt = c->alternative, iv = c->intervals;
    for (size_t j = 0; j < k; j++) {
        double lo = bs->lower[j], up = bs->upper[j];
        double two = dmin(1.0, 2.0 * dmin(lo, up));
        bs->p[j] = alt == MCSTAT_LESS ? lo : alt == MCSTAT_GREATER ? up : two;
        bs->done[j] = bs->kind[j] == PIX_FAST && bs->tail_ok[j] == TAIL_DONE && (!iv || bs->bound_ok[j]);
    }
    /* the decisions where the block answered (in a loop of its own: the one
     * above vectorises); fast_values sets the others' */
    const int less = alt == MCSTAT_LESS, two_sided = alt == MCSTAT_TWO_SIDED;
    for (size_t j = 0; c->out->decision && j < k; j++) {
        int low_side = less | (two_sided & (bs->lower[j] < bs->upper[j]));
        int reject = bs->p[j] <= c->alpha;
        bs->dec[j] = (signed char)(reject * (1 - 2 * low_side)); /* MCSTAT_DECISION_* */
    }
    for (size_t j = 0; j < k; j++)
        if (!bs->done[j] && bs->kind[j] == PIX_FAST)
            bs->done[j] = (unsigned char)fast_values(c, bs, j);
}

/* The block's outputs, array by array, as if every pixel were a fast one
 * (done[j] = 1); the others are then overwritten, each by its own path. */
static void put_block(const pix_ctx *c, size_t i0, size_t k, const block_stats *bs, const mcstat_dd *mx,
                      const mcstat_dd *my)
{
    const mcstat_pixels_out *o = c->out;
    for (size_t j = 0; o->p_value && j < k; j++)
        o->p_value[i0 + j] = bs->p[j];
    for (size_t j = 0; o->statistic && j < k; j++)
        o->statistic[i0 + j] = bs->t[j];
    for (size_t j = 0; o->df && j < k; j++)
        o->df[i0 + j] = bs->df[j];
    for (size_t j = 0; o->std_error && j < k; j++)
        o->std_error[i0 + j] = bs->se[j];
    for (size_t j = 0; o->estimate && j < k; j++)
        o->estimate[i0 + j] = mx[j].hi;
    for (size_t j = 0; o->estimate2 && j < k; j++)
        o->estimate2[i0 + j] = my[j].hi;
    for (size_t j = 0; o->df2 && j < k; j++)
        o->df2[i0 + j] = NAN;
    for (size_t j = 0; o->conf_lo && j < k; j++)
        o->conf_lo[i0 + j] = c->intervals ? bs->conf_lo[j] : NAN;
    for (size_t j = 0; o->conf_hi && j < k; j++)
        o->conf_hi[i0 + j] = c->intervals ? bs->conf_hi[j] : NAN;
    for (size_t j = 0; o->critical_lo && j < k; j++)
        o->critical_lo[i0 + j] = c->intervals ? bs->crit_lo[j] : NAN;
    for (size_t j = 0; o->critical_hi && j < k; j++)
        o->critical_hi[i0 + j] = c->intervals ? bs->crit_hi[j] : NAN;
    for (size_t j = 0; o->decision && j < k; j++)
        o->decision[i0 + j] = (int8_t)bs->dec[j];
    for (size_t j = 0; o->n_x && j < k; j++)
        o->n_x[i0 + j] = c->nx;
    for (size_t j = 0; o->n_y && j < k; j++)
        o->n_y[i0 + j] = c->ny;
    for (size_t j = 0; o->status && j < k; j++)
        o->status[i0 + j] = MCSTAT_OK;
}

/* The unweighted single-channel case (the usual one) goes MOMENT_TILE
 * pixels at a time with the seeds inside, so that the sums stay in
 * registers instead of being loaded and stored once per seed; the
 * additions are the same, in the same order. */
#define MOMENT_TILE 8
#define ROWS_TILE_MAX 256 /* longest rows transposed for the tile loop */
#define DEFINE_MOMENT_TILE(NAME, T, RANGE)                                                                 \
    static PIX_INLINE void NAME(const T *x, size_t n, size_t stride, size_t j0, size_t len, double dn,     \
                                double inv, int p2, double *sum, double *s1, double *s2, double *amax)     \
    {                                                                                                      \
        double a[MOMENT_TILE], b[MOMENT_TILE], q[MOMENT_TILE], mx[MOMENT_TILE];                            \
        for (size_t l = 0; l < len; l++)                                                                   \
            a[l] = b[l] = q[l] = mx[l] = 0.0;                                                              \
        for (size_t s = 0; s < n; s++) {                                                                   \
            const T *row = x + s * stride + j0;                                                            \
            for (size_t l = 0; l < len; l++) {                                                             \
                double v = (double)row[l];                                                                 \
                a[l] += v;                                                                                 \
                if (RANGE) {                                                                               \
                    double av = fabs(v);                                                                   \
                    mx[l] = av > mx[l] ? av : mx[l];                                                       \
                }                                                                                          \
            }                                                                                              \
        }                                                                                                  \
        for (size_t l = 0; l < len; l++)                                                                   \
            a[l] = div_by(a[l], dn, inv, p2);                                                              \
        for (size_t s = 0; s < n; s++) {                                                                   \
            const T *row = x + s * stride + j0;                                                            \
            for (size_t l = 0; l < len; l++) {                                                             \
                double d = (double)row[l] - a[l];                                                          \
                b[l] += d;                                                                                 \
                q[l] += d * d;                                                                             \
            }                                                                                              \
        }                                                                                                  \
        for (size_t l = 0; l < len; l++) {                                                                 \
            sum[j0 + l] = a[l];                                                                            \
            s1[j0 + l] = b[l];                                                                             \
            s2[j0 + l] = q[l];                                                                             \
            amax[j0 + l] = mx[l];                                                                          \
        }                                                                                                  \
    }

DEFINE_MOMENT_TILE(moment_tile_f32, float, 0)
DEFINE_MOMENT_TILE(moment_tile_f64, double, 1)

/* Moments of pixels i0..i0+k-1 of one side into the block's arrays.
 * bad[j] is set where the fast path cannot use the sums (non-finite,
 * extreme). */
/* RANGE: whether an unweighted value can lie outside [FAST_LO, FAST_HI]: a
 * double can; a float cannot (its magnitudes span 2^-149 to 2^128), so its
 * loop skips the |v| maximum and its checks are the sum's finiteness only.
 * A weighted sum of channels is checked whatever the type. */
/* Rows of values per pixel: MOMENT_TILE pixels' rows transposed into a
 * small buffer, then the tile loop as for seeds-major stacks (the same
 * additions in the same order: the same bits).  Not inlined: its buffer
 * would otherwise widen the block loops' frame (measured: 10 ns a pixel
 * on seeds-major stacks). */
#define DEFINE_ROWS_TILES(NAME, TILE, T)                                                                   \
    static __attribute__((noinline)) void NAME(const T *x, size_t n, size_t ps, size_t i0, size_t k,       \
                                               double dn, double inv, int p2, double *sum, double *s1,     \
                                               double *s2, double *amax)                                   \
    {                                                                                                      \
        T buf[MOMENT_TILE * ROWS_TILE_MAX];                                                                \
        for (size_t j = 0; j < k; j += MOMENT_TILE) {                                                      \
            size_t len = k - j < MOMENT_TILE ? k - j : MOMENT_TILE;                                        \
            for (size_t l = 0; l < len; l++) {                                                             \
                const T *r = x + (i0 + j + l) * ps;                                                        \
                for (size_t s = 0; s < n; s++)                                                             \
                    buf[s * MOMENT_TILE + l] = r[s];                                                       \
            }                                                                                              \
            TILE(buf, n, MOMENT_TILE, 0, len, dn, inv, p2, sum + j, s1 + j, s2 + j, amax + j);             \
        }                                                                                                  \
    }

DEFINE_ROWS_TILES(rows_tiles_f32, moment_tile_f32, float)
DEFINE_ROWS_TILES(rows_tiles_f64, moment_tile_f64, double)

#if PIX_AVX2
/* The AVX2 build's rows: eight rows at a time, read four values of four
 * rows at once and transposed in registers, so that each lane of a vector
 * is one row and its sums are the tile loop's, addition for addition (the
 * copy through a buffer was most of the per-row call's time). */
#define ROWS_LOAD4_F64(r, ps, v0, v1, v2, v3)                                                              \
    do {                                                                                                   \
        v0 = _mm256_loadu_pd(r);                                                                           \
        v1 = _mm256_loadu_pd((r) + (ps));                                                                  \
        v2 = _mm256_loadu_pd((r) + 2 * (ps));                                                              \
        v3 = _mm256_loadu_pd((r) + 3 * (ps));                                                              \
    } while (0)
#define ROWS_LOAD4_F32(r, ps, v0, v1, v2, v3)                                                              \
    do {                                                                                                   \
        v0 = _mm256_cvtps_pd(_mm_loadu_ps(r));                                                             \
        v1 = _mm256_cvtps_pd(_mm_loadu_ps((r) + (ps)));                                                    \
        v2 = _mm256_cvtps_pd(_mm_loadu_ps((r) + 2 * (ps)));                                                \
        v3 = _mm256_cvtps_pd(_mm_loadu_ps((r) + 3 * (ps)));                                                \
    } while (0)
/* vj: values s..s+3 of row j -> vj: value s+j of rows 0..3 */
#define ROWS_T4(v0, v1, v2, v3)                                                                            \
    do {                                                                                                   \
        __m256d t0_ = _mm256_unpacklo_pd(v0, v1), t1_ = _mm256_unpackhi_pd(v0, v1);                       \
        __m256d t2_ = _mm256_unpacklo_pd(v2, v3), t3_ = _mm256_unpackhi_pd(v2, v3);                       \
        v0 = _mm256_permute2f128_pd(t0_, t2_, 0x20);                                                       \
        v1 = _mm256_permute2f128_pd(t1_, t3_, 0x20);                                                       \
        v2 = _mm256_permute2f128_pd(t0_, t2_, 0x31);                                                       \
        v3 = _mm256_permute2f128_pd(t1_, t3_, 0x31);                                                       \
    } while (0)
/* value s of rows r..r+3 (the last values, when n is not a multiple of 4) */
#define ROWS_COL4(r, ps, s) _mm256_set_pd((r)[3 * (ps) + (s)], (r)[2 * (ps) + (s)], (r)[(ps) + (s)], (r)[s])

#define DEFINE_ROWS_TILE8(NAME, T, LOAD4, RANGE)                                                           \
    __attribute__((target("avx2"))) static void NAME(const T *x, size_t n, size_t ps, double dn, double inv, \
                                                     int p2, double *sum, double *s1, double *s2,          \
                                                     double *amax)                                         \
    {                                                                                                      \
        const T *x4 = x + 4 * ps;                                                                          \
        const __m256d sign = _mm256_set1_pd(-0.0);                                                         \
        __m256d a0 = _mm256_setzero_pd(), a1 = a0, m0 = a0, m1 = a0;                                       \
        __m256d u0, u1, u2, u3, w0, w1, w2, w3;                                                            \
        size_t s = 0;                                                                                      \
        for (; s + 4 <= n; s += 4) {                                                                       \
            LOAD4(x + s, ps, u0, u1, u2, u3);                                                              \
            LOAD4(x4 + s, ps, w0, w1, w2, w3);                                                             \
            ROWS_T4(u0, u1, u2, u3);                                                                       \
            ROWS_T4(w0, w1, w2, w3);                                                                       \
            a0 = _mm256_add_pd(a0, u0);                                                                    \
            a1 = _mm256_add_pd(a1, w0);                                                                    \
            a0 = _mm256_add_pd(a0, u1);                                                                    \
            a1 = _mm256_add_pd(a1, w1);                                                                    \
            a0 = _mm256_add_pd(a0, u2);                                                                    \
            a1 = _mm256_add_pd(a1, w2);                                                                    \
            a0 = _mm256_add_pd(a0, u3);                                                                    \
            a1 = _mm256_add_pd(a1, w3);                                                                    \
            if (RANGE) { /* max(|v|, m): |v| > m ? |v| : m, as the tile loop's */                         \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u0), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w0), m1);                                        \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u1), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w1), m1);                                        \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u2), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w2), m1);                                        \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u3), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w3), m1);                                        \
            }                                                                                              \
        }                                                                                                  \
        for (size_t t = s; t < n; t++) {                                                                   \
            u0 = ROWS_COL4(x, ps, t);                                                                      \
            w0 = ROWS_COL4(x4, ps, t);                                                                     \
            a0 = _mm256_add_pd(a0, u0);                                                                    \
            a1 = _mm256_add_pd(a1, w0);                                                                    \
            if (RANGE) {                                                                                   \
                m0 = _mm256_max_pd(_mm256_andnot_pd(sign, u0), m0);                                        \
                m1 = _mm256_max_pd(_mm256_andnot_pd(sign, w0), m1);                                        \
            }                                                                                              \
        }                                                                                                  \
        if (p2) {                                                                                          \
            a0 = _mm256_mul_pd(a0, _mm256_set1_pd(inv));                                                   \
            a1 = _mm256_mul_pd(a1, _mm256_set1_pd(inv));                                                   \
        } else {                                                                                           \
            a0 = _mm256_div_pd(a0, _mm256_set1_pd(dn));                                                    \
            a1 = _mm256_div_pd(a1, _mm256_set1_pd(dn));                                                    \
        }                                                                                                  \
        __m256d b0 = _mm256_setzero_pd(), b1 = b0, q0 = b0, q1 = b0;                                       \
        for (s = 0; s + 4 <= n; s += 4) {                                                                  \
            LOAD4(x + s, ps, u0, u1, u2, u3);                                                              \
            LOAD4(x4 + s, ps, w0, w1, w2, w3);                                                             \
            ROWS_T4(u0, u1, u2, u3);                                                                       \
            ROWS_T4(w0, w1, w2, w3);                                                                       \
            ROWS_STEP2(u0, w0);                                                                            \
            ROWS_STEP2(u1, w1);                                                                            \
            ROWS_STEP2(u2, w2);                                                                            \
            ROWS_STEP2(u3, w3);                                                                            \
        }                                                                                                  \
        for (size_t t = s; t < n; t++) {                                                                   \
            u0 = ROWS_COL4(x, ps, t);                                                                      \
            w0 = ROWS_COL4(x4, ps, t);                                                                     \
            ROWS_STEP2(u0, w0);                                                                            \
        }                                                                                                  \
        _mm256_storeu_pd(sum, a0);                                                                         \
        _mm256_storeu_pd(sum + 4, a1);                                                                     \
        _mm256_storeu_pd(s1, b0);                                                                          \
        _mm256_storeu_pd(s1 + 4, b1);                                                                      \
        _mm256_storeu_pd(s2, q0);                                                                          \
        _mm256_storeu_pd(s2 + 4, q1);                                                                      \
        _mm256_storeu_pd(amax, m0);                                                                        \
        _mm256_storeu_pd(amax + 4, m1);                                                                    \
    }
/* the second pass's step: d = v - mean; s1 += d; s2 += d * d */
#define ROWS_STEP2(u, w)                                                                                   \
    do {                                                                                                   \
        __m256d du_ = _mm256_sub_pd(u, a0), dw_ = _mm256_sub_pd(w, a1);                                    \
        b0 = _mm256_add_pd(b0, du_);                                                                       \
        b1 = _mm256_add_pd(b1, dw_);                                                                       \
        q0 = _mm256_add_pd(q0, _mm256_mul_pd(du_, du_));                                                   \
        q1 = _mm256_add_pd(q1, _mm256_mul_pd(dw_, dw_));                                                   \
    } while (0)

DEFINE_ROWS_TILE8(rows_tile8_f32, float, ROWS_LOAD4_F32, 0)
DEFINE_ROWS_TILE8(rows_tile8_f64, double, ROWS_LOAD4_F64, 1)

#define DEFINE_ROWS_TILES_AVX2(NAME, TILE8, REST, T)                                                       \
    __attribute__((target("avx2"))) static void NAME(const T *x, size_t n, size_t ps, size_t i0, size_t k,  \
                                                     double dn, double inv, int p2, double *sum,           \
                                                     double *s1, double *s2, double *amax)                 \
    {                                                                                                      \
        size_t j = 0;                                                                                      \
        for (; j + MOMENT_TILE <= k; j += MOMENT_TILE)                                                     \
            TILE8(x + (i0 + j) * ps, n, ps, dn, inv, p2, sum + j, s1 + j, s2 + j, amax + j);               \
        if (j < k)                                                                                         \
            REST(x, n, ps, i0 + j, k - j, dn, inv, p2, sum + j, s1 + j, s2 + j, amax + j);                 \
    }

DEFINE_ROWS_TILES_AVX2(rows_tiles_f32_avx2, rows_tile8_f32, rows_tiles_f32, float)
DEFINE_ROWS_TILES_AVX2(rows_tiles_f64_avx2, rows_tile8_f64, rows_tiles_f64, double)
#else
#define rows_tiles_f32_avx2 rows_tiles_f32
#define rows_tiles_f64_avx2 rows_tiles_f64
#endif

/* wide: called from the AVX2 build (a constant once inlined) */
#define DEFINE_BLOCK_MOMENTS(NAME, TILE, ROWS, T, RANGE)                                                   \
    static PIX_INLINE void NAME(const T *x, size_t n, size_t stride, size_t ps, size_t ch, const double *w,        \
                                size_t i0, size_t k, mcstat_dd *mean, double *m2, unsigned char *bad, int wide)    \
    {                                                                                                      \
        double sum[PIX_BLOCK], amax[PIX_BLOCK], s1[PIX_BLOCK], s2[PIX_BLOCK];                              \
        const double dn = (double)n, inv = 1.0 / dn;                                                       \
        const int p2 = pow2_count(n);                                                                      \
        if (ch == 1 && !w && ps == 1) {                                                                    \
            size_t j = 0;                                                                                  \
            for (; j + MOMENT_TILE <= k; j += MOMENT_TILE)                                                 \
                TILE(x + i0, n, stride, j, MOMENT_TILE, dn, inv, p2, sum, s1, s2, amax);                   \
            for (; j < k; j++)                                                                             \
                TILE(x + i0, n, stride, j, 1, dn, inv, p2, sum, s1, s2, amax);                             \
        } else if (ch == 1 && !w && stride == 1 && n <= ROWS_TILE_MAX) {                                   \
            if (wide)                                                                                      \
                ROWS##_avx2(x, n, ps, i0, k, dn, inv, p2, sum, s1, s2, amax);                              \
            else                                                                                           \
                ROWS(x, n, ps, i0, k, dn, inv, p2, sum, s1, s2, amax);                                     \
        } else {                                                                                           \
            for (size_t j = 0; j < k; j++)                                                                 \
                sum[j] = amax[j] = s1[j] = s2[j] = 0.0;                                                    \
            for (size_t s = 0; s < n; s++) {                                                               \
                const T *row = x + s * stride + i0 * ps;                                                   \
                for (size_t j = 0; j < k; j++) {                                                           \
                    double v = w ? 0.0 : (double)row[j * ps];                                              \
                    for (size_t c = 0; w && c < ch; c++)                                                   \
                        v += w[c] * (double)row[j * ps + c];                                               \
                    sum[j] += v;                                                                           \
                    double av = fabs(v);                                                                   \
                    amax[j] = av > amax[j] ? av : amax[j];                                                 \
                }                                                                                          \
            }                                                                                              \
            for (size_t j = 0; j < k; j++)                                                                 \
                sum[j] = div_by(sum[j], dn, inv, p2); /* the mean to a few ulps; the second pass corrects it */ \
            for (size_t s = 0; s < n; s++) {                                                               \
                const T *row = x + s * stride + i0 * ps;                                                   \
                for (size_t j = 0; j < k; j++) {                                                           \
                    double v = w ? 0.0 : (double)row[j * ps];                                              \
                    for (size_t c = 0; w && c < ch; c++)                                                   \
                        v += w[c] * (double)row[j * ps + c];                                               \
                    double d = v - sum[j];                                                                 \
                    s1[j] += d;                                                                            \
                    s2[j] += d * d;                                                                        \
                }                                                                                          \
            }                                                                                              \
        }                                                                                                  \
        for (size_t j = 0; j < k; j++) {                                                                   \
            double c1 = div_by(s1[j], dn, inv, p2);                                                        \
            mean[j] = dd_two_sum(sum[j], c1);                                                              \
            double v2 = s2[j] - s1[j] * c1;                                                                \
            m2[j] = v2 > 0.0 ? v2 : 0.0;                                                                   \
        }                                                                                                  \
        /* a NaN or Inf among the values makes the sum NaN or Inf; a float's */                            \
        /* squares cannot overflow, a double's or a weighted sum's can */                                  \
        const int range = RANGE || w || ch != 1;                                                           \
        for (size_t j = 0; j < k; j++)                                                                     \
            bad[j] = !(fabs(sum[j]) <= DBL_MAX) ||                                                         \
                     (range && (!(fabs(s2[j]) <= DBL_MAX) || !(fabs(s1[j]) <= DBL_MAX) ||                  \
                                (amax[j] != 0.0 && (amax[j] < FAST_LO || amax[j] > FAST_HI))));            \
    }

DEFINE_BLOCK_MOMENTS(block_moments_f32, moment_tile_f32, rows_tiles_f32, float, 0)
DEFINE_BLOCK_MOMENTS(block_moments_f64, moment_tile_f64, rows_tiles_f64, double, 1)

/* One side's block moments for the other per-pixel tests (pixels_var.c),
 * in the SSE2 and AVX2 builds: the same numbers as Welch's. */
static PIX_INLINE void side_moments_body(const mcstat_pixels_in *p, size_t i0, size_t k, mcstat_dd *mean, double *m2,
                                         unsigned char *bad, int wide)
{
    if (p->type == MCSTAT_VALUE_FLOAT32)
        block_moments_f32(p->data, p->n, p->value_stride, p->pixel_stride, p->channels, p->weights, i0, k, mean, m2,
                          bad, wide);
    else
        block_moments_f64(p->data, p->n, p->value_stride, p->pixel_stride, p->channels, p->weights, i0, k, mean, m2,
                          bad, wide);
}

static void side_moments(const mcstat_pixels_in *p, size_t i0, size_t k, mcstat_dd *mean, double *m2,
                         unsigned char *bad)
{
    side_moments_body(p, i0, k, mean, m2, bad, 0);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void side_moments_avx2(const mcstat_pixels_in *p, size_t i0, size_t k,
                                                               mcstat_dd *mean, double *m2, unsigned char *bad)
{
    side_moments_body(p, i0, k, mean, m2, bad, 1);
}
#endif

#if PIX_AVX2
static int use_avx2(void);
#endif

void mcstat__pixels_block_moments(const mcstat_pixels_in *p, size_t i0, size_t k, mcstat_dd *mean, double *m2,
                                  unsigned char *bad)
{
#if PIX_AVX2
    if (use_avx2()) {
        side_moments_avx2(p, i0, k, mean, m2, bad);
        return;
    }
#endif
    side_moments(p, i0, k, mean, m2, bad);
}

/* Set by the tests, on their own thread, to compare the baseline loops
 * with the AVX2 ones (thread-local: no other thread's calls see it). */
static _Thread_local int pixels_baseline_only;

void mcstat__pixels_baseline_only(int on)
{
    pixels_baseline_only = on;
}

#if PIX_AVX2
/* Whether the AVX2 loops may run: the CPU has AVX2 and MCSTAT_NO_AVX2 is
 * not set (or "0") in the environment (mcstat.h: for valgrind 3.19, which
 * stops at some AVX2 encodings).  Read once, at the first call that asks,
 * and never written again: the library's only process-wide value. */
static pthread_once_t avx2_once = PTHREAD_ONCE_INIT;
static int avx2_allowed;

static void avx2_probe(void)
{
    const char *e = getenv("MCSTAT_NO_AVX2");
    int no = e && *e && strcmp(e, "0") != 0;
    avx2_allowed = !no && __builtin_cpu_supports("avx2");
}

/* Whether this call runs the AVX2 loops (per pixel and per quantile). */
static int use_avx2(void)
{
    pthread_once(&avx2_once, avx2_probe);
    return avx2_allowed && !pixels_baseline_only;
}
#endif

int mcstat__pixels_avx2(void)
{
#if PIX_AVX2
    return use_avx2();
#else
    return 0;
#endif
}

/* One block: both sides' moments, then the statistics. */
typedef struct {
    mcstat_dd mx[PIX_BLOCK], my[PIX_BLOCK];
    double m2x[PIX_BLOCK], m2y[PIX_BLOCK];
    unsigned char bx[PIX_BLOCK], by[PIX_BLOCK];
    block_stats st;
} block_work;

typedef struct {
    const float *xf, *yf;
    const double *xd, *yd, *w;
    size_t nx, xs, xps, ny, ys, yps, ch;
    double mu0;
} block_input;

/* joint: the AVX2 build's central series (central_series8) */
static PIX_INLINE void block_pass_body(const block_input *in, size_t i0, size_t k, block_work *b, int joint)
{
    if (in->xf) {
        block_moments_f32(in->xf, in->nx, in->xs, in->xps, in->ch, in->w, i0, k, b->mx, b->m2x, b->bx, joint);
        block_moments_f32(in->yf, in->ny, in->ys, in->yps, in->ch, in->w, i0, k, b->my, b->m2y, b->by, joint);
    } else {
        block_moments_f64(in->xd, in->nx, in->xs, in->xps, in->ch, in->w, i0, k, b->mx, b->m2x, b->bx, joint);
        block_moments_f64(in->yd, in->ny, in->ys, in->yps, in->ch, in->w, i0, k, b->my, b->m2y, b->by, joint);
    }
    block_statistics(k, (double)in->nx, b->mx, b->m2x, b->bx, (double)in->ny, b->my, b->m2y, b->by, in->mu0, &b->st);
    unsigned char want[PIX_BLOCK];
    for (size_t j = 0; j < k; j++)
        want[j] = b->st.kind[j] == PIX_FAST;
    block_tails(k, b->st.t, b->st.df, b->st.pa, b->st.pf, b->st.plc, want, b->st.lower, b->st.upper, b->st.tail_ok,
                joint);
}

static void block_pass(const block_input *in, size_t i0, size_t k, block_work *b)
{
    block_pass_body(in, i0, k, b, 0);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void block_pass_avx2(const block_input *in, size_t i0, size_t k,
                                                             block_work *b)
{
    block_pass_body(in, i0, k, b, 1);
}
#endif

/* Welch's test for pixels [begin, end) of x and y (pixels_test.c has
 * checked the arguments; x and y are of one type and channel weighting).
 * Returns the status of the first pixel that failed. */
int mcstat__pixels_welch(const mcstat_pixels_in *x, const mcstat_pixels_in *y, mcstat__work *wk, size_t *first_index,
                         double mu0, int alternative, double alpha, unsigned flags, const mcstat_pixels_out *out)
{
    const int f32 = x->type == MCSTAT_VALUE_FLOAT32;
    const float *xf = f32 ? x->data : NULL, *yf = f32 ? y->data : NULL;
    const double *xd = f32 ? NULL : x->data, *yd = f32 ? NULL : y->data;
    const size_t nx = x->n, ny = y->n, channels = x->channels;
    const double *w = x->weights;
    pix_ctx c;
    c.out = out;
    c.alternative = alternative;
    c.intervals = !(flags & MCSTAT_ROWS_NO_INTERVALS);
    c.mu0 = mu0;
    c.alpha = alpha;
    c.crit_two = NAN;
    c.crit_df = NAN;
    c.qt_p = alternative == MCSTAT_TWO_SIDED ? 0.5 * alpha : alpha;
    c.nx = nx;
    c.ny = ny;
    double qt[QT_NODES + 1];
    if (c.intervals)
        qt_table_init(&c, c.qt_p, qt, QT_NODES);
    mcstat__qcache_init(&c.qc);
    c.first = MCSTAT_OK;
    c.first_i = 0;
    plane px = {xf, xd, x->value_stride, x->pixel_stride, channels, w},
          py = {yf, yd, y->value_stride, y->pixel_stride, channels, w};
    block_input in = {xf, yf, xd, yd, w, nx, x->value_stride, x->pixel_stride, ny, y->value_stride, y->pixel_stride,
                      channels, mu0};
    block_work *b = calloc(1, sizeof *b); /* tens of KiB: not on a caller's thread stack */
    int fast_ok = nx >= 2 && ny >= 2 && b;
#if PIX_AVX2
    int avx2 = use_avx2();
#endif
    size_t begin, end;
    while (mcstat__work_take(wk, &begin, &end))
    for (size_t i0 = begin; i0 < end; i0 += PIX_BLOCK) {
        size_t k = end - i0 < PIX_BLOCK ? end - i0 : PIX_BLOCK;
        if (fast_ok) {
#if PIX_AVX2
            if (avx2)
                block_pass_avx2(&in, i0, k, b);
            else
#endif
                block_pass(&in, i0, k, b);
            if (c.intervals) {
                block_nodes(&c, k, &b->st);
#if PIX_AVX2
                if (avx2)
                    block_bounds_pass_avx2(k, alternative, &b->st);
                else
#endif
                    block_bounds_pass(k, alternative, &b->st);
            }
            block_values(&c, k, &b->st);
            put_block(&c, i0, k, &b->st, b->mx, b->my);
        }
        for (size_t j = 0; j < k; j++) {
            size_t i = i0 + j;
            if (fast_ok && b->st.done[j])
                continue;
            if (fast_ok && b->st.kind[j] == PIX_DEGENERATE)
                fail(&c, i, MCSTAT_EDEGENERATE);
            else
                slow_pixel(&c, &px, nx, &py, ny, i, flags);
        }
    }
    free(b);
    *first_index = c.first_i;
    return c.first;
}

/* ---- t quantiles for many df ------------------------------------------
 * The pixel path's critical values as a function of their own: the same
 * kind of per-call table (criticals with the alternative "greater" gives
 * the upper p-quantile), interpolated PIX_BLOCK values at a time in a loop
 * that vectorises, Halley (criticals) where the five- and six-point values
 * disagree; levels outside the table's range go to mcstat_t_quantile one
 * value at a time.
 *
 * The table's density follows the level: the quantile grows like
 * p^(-1/df), so its derivatives in u = 1/df grow with a = log(1/p), and the
 * interpolation holds to rounding while the step h keeps h a below ~0.005
 * (measured against mcstat_t_quantile over df in [1, 1000]: at 1024 nodes
 * every df interpolates at p = 0.025 but 37-80% of df below 30 need Halley
 * at 1e-4 and all do at 3e-9; at 4096 none do at 3e-9, at 8192 none at
 * 1e-20).  So: the power of two >= 200 a, at least QT_NODES. */
#define QT_MANY_MAX 65536 /* a = 327: p = 1e-142, below quantile_ok's 1e-100 */

static int many_nodes(double p)
{
    double a = -log(p);
    int n = QT_NODES;
    while (n < QT_MANY_MAX && n < 200.0 * a)
        n *= 2;
    return n;
}

typedef struct {
    pix_ctx c;
    double qn[6][PIX_BLOCK], qs[PIX_BLOCK], v[PIX_BLOCK];
    long long exact[PIX_BLOCK]; /* 64 bits, as the doubles: the loop vectorises */
    double qt[];
} many_work;

static PIX_INLINE void many_interp(size_t k, many_work *w)
{
    for (size_t j = 0; j < k; j++) {
        double q[6], v5, v6;
        for (int i = 0; i < 6; i++)
            q[i] = w->qn[i][j];
        lagrange56(q, w->qs[j], &v5, &v6);
        w->v[j] = v6;
        w->exact[j] = fabs(v6 - v5) < 1e-13 * fabs(v6); /* false where a node is NaN */
    }
}

static void many_interp_pass(size_t k, many_work *w)
{
    many_interp(k, w);
}

#if PIX_AVX2
__attribute__((target("avx2"))) static void many_interp_pass_avx2(size_t k, many_work *w)
{
    many_interp(k, w);
}
#endif

int mcstat_t_quantiles(double p, const double *df, size_t n, int upper, double *x)
{
    MCSTAT_IEEE_SCOPE();
    if (!(p >= 0.0 && p <= 1.0) || (n > 0 && (!df || !x)))
        return MCSTAT_EINVAL;
    many_work *w = NULL;
    if (quantile_ok(p, 1.0) && n > 16) { /* a short array does not pay for the table */
        int nodes = many_nodes(p);
        w = malloc(sizeof *w + (size_t)(nodes + 1) * sizeof(double));
        if (w) {
            w->c.alternative = MCSTAT_GREATER;
            qt_table_init(&w->c, p, w->qt, nodes);
        }
    }
#if PIX_AVX2
    int avx2 = use_avx2();
#endif
    int first = MCSTAT_OK;
    for (size_t i0 = 0; i0 < n; i0 += PIX_BLOCK) {
        size_t k = n - i0 < PIX_BLOCK ? n - i0 : PIX_BLOCK;
        if (w) {
            table_nodes(&w->c, k, df + i0, NULL, w->qn, w->qs);
#if PIX_AVX2
            if (avx2)
                many_interp_pass_avx2(k, w);
            else
#endif
                many_interp_pass(k, w);
        }
        for (size_t j = 0; j < k; j++) {
            double q = NAN, c0, c1;
            int st = MCSTAT_OK;
            if (w && w->exact[j]) {
                q = upper ? w->v[j] : -w->v[j];
            } else if (w) {
                st = criticals(&w->c, df[i0 + j], NULL, &c0, &c1);
                q = upper ? c1 : -c1; /* t is symmetric: the lower p-quantile is minus the upper */
            } else {
                st = mcstat_t_quantile(p, df[i0 + j], upper, &q);
            }
            if (st) {
                q = NAN;
                if (first == MCSTAT_OK)
                    first = st;
            }
            x[i0 + j] = q;
        }
    }
    free(w);
    return first;
}
