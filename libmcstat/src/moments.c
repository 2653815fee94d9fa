/*
 * moments.c - streaming, mergeable moments that stay exact on stiff data.
 *
 * Arrays are cut into blocks of BLOCK values (16 KiB, resident in L1).  Each
 * block is summed once from memory as shifted power sums S_k = sum (x - c)^k,
 * with c the previous block's mean (the "pilot"); the central sums follow by
 * the shift formulas.  Their rounding error grows with rho = n (mean - c)^2 /
 * M2, so a block whose pilot was poor (rho > 1/16: the first block, or data
 * that drift) is summed again about its own mean, which costs an L1 pass, not
 * a memory pass.  This is the two-pass algorithm where it matters and a
 * one-pass one where it does not.
 *
 * Blocks are merged by Chan et al.'s / Pebay's formulas in a pairwise tree,
 * so errors grow like log(n) and not n.  The mean is a double-double, so
 * 1e9 + 1e-3 noise keeps its digits in differences of means.
 *
 * Magnitudes: a block whose largest |x| lies outside [2^-200, 2^200] is
 * summed scaled by 2^-e (e from its largest |x|), and the accumulator keeps
 * m_k = M_k / 2^(k e): no fourth power overflows at 1e300 or underflows at
 * 1e-300.  Accumulators of different scales are rescaled exactly on merge.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <float.h>
#include <string.h>

#define BLOCK 2048
#define FAST_LO 0x1p-200
#define FAST_HI 0x1p+200
#define TREE_DEPTH 56 /* > log2(2^64 / BLOCK) levels of the pairwise tree */
#define OMIT_BLOCK 512 /* bounce buffer for NaN omission: 4 KiB of stack */

/* ---- the block kernel ------------------------------------------------------
 * Eight independent lanes (GCC/Clang vector extension); on x86-64 Linux the
 * function is also compiled for AVX2 and AVX-512 and picked at load time.
 * Lanes are reduced in a fixed order, and -ffp-contract=off keeps FMA out,
 * so every variant returns bit-identical sums. */
typedef double v8d __attribute__((vector_size(64)));
typedef long long v8l __attribute__((vector_size(64)));

#if defined(__x86_64__) && defined(__linux__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(MCSTAT_NO_TARGET_CLONES)
#define KERNEL_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define KERNEL_CLONES
#endif

typedef struct {
    double s1, s2, s3, s4, min, max;
} block_sums;

static inline double lanes_sum(v8d v)
{
    return ((v[0] + v[4]) + (v[2] + v[6])) + ((v[1] + v[5]) + (v[3] + v[7]));
}

KERNEL_CLONES
static void kernel(const double *x, size_t n, double c, block_sums *out)
{
    const v8d vc = {c, c, c, c, c, c, c, c};
    v8d s1 = {0}, s2 = {0}, s3 = {0}, s4 = {0};
    v8d vmin = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
    v8d vmax = -vmin;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        v8d xv;
        memcpy(&xv, x + i, sizeof xv);
        v8d d = xv - vc, d2 = d * d;
        s1 += d;
        s2 += d2;
        s3 += d2 * d;
        s4 += d2 * d2;
        v8l lt = xv < vmin, gt = xv > vmax; /* NaN compares false: caught by the sums */
        vmin = (v8d)((lt & (v8l)xv) | (~lt & (v8l)vmin));
        vmax = (v8d)((gt & (v8l)xv) | (~gt & (v8l)vmax));
    }
    double t1 = 0, t2 = 0, t3 = 0, t4 = 0, mn = INFINITY, mx = -INFINITY;
    for (; i < n; i++) {
        double d = x[i] - c, d2 = d * d;
        t1 += d;
        t2 += d2;
        t3 += d2 * d;
        t4 += d2 * d2;
        mn = x[i] < mn ? x[i] : mn;
        mx = x[i] > mx ? x[i] : mx;
    }
    for (int k = 0; k < 8; k++) {
        mn = vmin[k] < mn ? vmin[k] : mn;
        mx = vmax[k] > mx ? vmax[k] : mx;
    }
    out->s1 = lanes_sum(s1) + t1;
    out->s2 = lanes_sum(s2) + t2;
    out->s3 = lanes_sum(s3) + t3;
    out->s4 = lanes_sum(s4) + t4;
    out->min = mn;
    out->max = mx;
}

/* The scaled variant for extreme magnitudes: d = x 2^-e - c. Rare; scalar. */
static void kernel_scaled(const double *x, size_t n, int e, double c, block_sums *out)
{
    double t1 = 0, t2 = 0, t3 = 0, t4 = 0, mn = INFINITY, mx = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        double d = ldexp(x[i], -e) - c, d2 = d * d;
        t1 += d;
        t2 += d2;
        t3 += d2 * d;
        t4 += d2 * d2;
        mn = x[i] < mn ? x[i] : mn;
        mx = x[i] > mx ? x[i] : mx;
    }
    out->s1 = t1; out->s2 = t2; out->s3 = t3; out->s4 = t4;
    out->min = mn; out->max = mx;
}

/* The scale exponent for data whose largest magnitude is amax. */
static int scale_for(double amax)
{
    if (amax == 0.0 || (amax >= FAST_LO && amax <= FAST_HI))
        return 0;
    return ilogb(amax) + 1;
}

/* Central sums from shifted sums about c (all in units of 2^e). Returns rho. */
static double central_from_shifted(const block_sums *s, double n, double c, int e, mcstat_moments *m)
{
    double delta = s->s1 / n;
    double m2 = s->s2 - delta * s->s1;
    double m3 = s->s3 - 3.0 * delta * s->s2 + 2.0 * n * delta * delta * delta;
    double d2 = delta * delta;
    double m4 = s->s4 - 4.0 * delta * s->s3 + 6.0 * d2 * s->s2 - 3.0 * n * d2 * d2;
    mcstat_dd mean = dd_two_sum(c, delta);
    m->mean = ldexp(mean.hi, e);
    m->mean_lo = ldexp(mean.lo, e);
    m->m2 = m2 > 0.0 ? m2 : 0.0;
    m->m3 = m3;
    m->m4 = m4 > 0.0 ? m4 : 0.0;
    m->scale = e;
    m->min = s->min;
    m->max = s->max;
    if (m2 > 0.0)
        return n * d2 / m2;
    return delta == 0.0 ? 0.0 : INFINITY;
}

static int has_nonfinite(const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 1;
    return 0;
}

/* Moments of one block (n >= 1) into *m, given a pilot shift. */
static int block_moments(const double *x, size_t n, double pilot, mcstat_moments *m)
{
    block_sums s;
    double dn = (double)n;
    memset(m, 0, sizeof *m);
    m->version = MCSTAT_MOMENTS_VERSION;
    m->n = n;
    if (!(fabs(pilot) <= FAST_HI))
        pilot = x[0];
    if (!(fabs(pilot) <= FAST_HI))
        pilot = 0.0;
    kernel(x, n, pilot, &s);
    double amax = fmax(fabs(s.min), fabs(s.max));
    if (isfinite(s.s1) && isfinite(s.s2) && isfinite(s.s3) && isfinite(s.s4) &&
        (amax == 0.0 || (amax >= FAST_LO && amax <= FAST_HI))) {
        double rho = central_from_shifted(&s, dn, pilot, 0, m);
        if (rho > 0.0625) { /* poor pilot: sum again about this block's mean */
            double c = m->mean;
            kernel(x, n, c, &s);
            central_from_shifted(&s, dn, c, 0, m);
        }
        return MCSTAT_OK;
    }
    if (has_nonfinite(x, n))
        return MCSTAT_ENONFINITE;
    /* Extreme magnitudes: scaled two-pass (mean first, then about it). */
    int e = scale_for(amax);
    double c = 0.0;
    for (size_t i = 0; i < n; i++)
        c += ldexp(x[i], -e);
    c /= dn;
    kernel_scaled(x, n, e, c, &s);
    double rho = central_from_shifted(&s, dn, c, e, m);
    if (rho > 0.0625) {
        c = ldexp(m->mean, -e) + ldexp(m->mean_lo, -e);
        kernel_scaled(x, n, e, c, &s);
        central_from_shifted(&s, dn, c, e, m);
    }
    return MCSTAT_OK;
}

/* ---- merging ------------------------------------------------------------ */

static void rescale(mcstat_moments *m, int e)
{
    int k = m->scale - e;
    if (k == 0)
        return;
    m->m2 = ldexp(m->m2, 2 * k);
    m->m3 = ldexp(m->m3, 3 * k);
    m->m4 = ldexp(m->m4, 4 * k);
    m->scale = e;
}

/* a <- a merged with b; both valid, b->n > 0. Pebay (2008), eqs. 2.1-2.3. */
static void merge_into(mcstat_moments *a, const mcstat_moments *b)
{
    if (a->n == 0) {
        *a = *b;
        return;
    }
    mcstat_moments B = *b;
    double mn = a->min < B.min ? a->min : B.min;
    double mx = a->max > B.max ? a->max : B.max;
    int e = scale_for(fmax(fabs(mn), fabs(mx)));
    rescale(a, e);
    rescale(&B, e);
    double na = (double)a->n, nb = (double)B.n, n = na + nb;
    double fa = na / n, fb = nb / n;
    mcstat_dd ma = {a->mean, a->mean_lo}, mb = {B.mean, B.mean_lo};
    mcstat_dd delta = dd_add(mb, dd_neg(ma));
    double ds = ldexp(delta.hi, -e) + ldexp(delta.lo, -e);
    double ds2 = ds * ds;
    double m2 = a->m2 + B.m2 + ds2 * n * fa * fb;
    double m3 = a->m3 + B.m3 + ds2 * ds * n * fa * fb * (fa - fb) + 3.0 * ds * (fa * B.m2 - fb * a->m2);
    double m4 = a->m4 + B.m4 + ds2 * ds2 * n * fa * fb * (fa * fa - fa * fb + fb * fb) +
                6.0 * ds2 * (fa * fa * B.m2 + fb * fb * a->m2) + 4.0 * ds * (fa * B.m3 - fb * a->m3);
    mcstat_dd mean = dd_add(ma, dd_div_d(dd_mul_d(delta, nb), n)); /* delta nb / n, unrounded */
    a->n += B.n;
    a->mean = mean.hi;
    a->mean_lo = mean.lo;
    a->m2 = m2;
    a->m3 = m3;
    a->m4 = m4;
    a->min = mn;
    a->max = mx;
    a->version = MCSTAT_MOMENTS_VERSION;
}

static int is_valid(const mcstat_moments *m)
{
    return m && (m->n == 0 || m->version == MCSTAT_MOMENTS_VERSION);
}

/* ---- public API ---------------------------------------------------------- */

int mcstat_moments_init(mcstat_moments *m)
{
    if (!m)
        return MCSTAT_EINVAL;
    memset(m, 0, sizeof *m);
    m->version = MCSTAT_MOMENTS_VERSION;
    m->min = INFINITY;
    m->max = -INFINITY;
    return MCSTAT_OK;
}

int mcstat_moments_merge(mcstat_moments *dst, const mcstat_moments *src)
{
    if (!is_valid(dst) || !is_valid(src))
        return MCSTAT_EINVAL;
    if (src->n == 0)
        return MCSTAT_OK;
    mcstat_moments copy = *src; /* src may alias dst */
    merge_into(dst, &copy);
    return MCSTAT_OK;
}

int mcstat_moments_add(mcstat_moments *m, double x)
{
    if (!is_valid(m))
        return MCSTAT_EINVAL;
    if (!isfinite(x))
        return MCSTAT_ENONFINITE;
    mcstat_moments one;
    memset(&one, 0, sizeof one);
    one.version = MCSTAT_MOMENTS_VERSION;
    one.n = 1;
    one.mean = x;
    one.min = one.max = x;
    one.scale = scale_for(fabs(x));
    merge_into(m, &one);
    return MCSTAT_OK;
}

/* Adds x[0..n) to m through a pairwise tree of blocks; m is only touched on
 * success.  With omit_nan, NaNs are skipped (copied around in a bounce
 * buffer per block) and counted. */
static int add_array(mcstat_moments *m, const double *x, size_t n, int omit_nan, size_t *n_omitted)
{
    if (!is_valid(m) || (!x && n > 0))
        return MCSTAT_EINVAL;
    mcstat_moments stack[TREE_DEPTH];
    uint64_t count[TREE_DEPTH]; /* blocks merged into stack[k] */
    int top = 0;
    size_t omitted = 0;
    double pilot = m->n > 0 ? m->mean : NAN;
    double buf[OMIT_BLOCK];
    const size_t step = omit_nan ? OMIT_BLOCK : BLOCK;
    for (size_t start = 0; start < n; start += step) {
        size_t len = n - start < step ? n - start : step;
        const double *p = x + start;
        if (omit_nan) {
            size_t k = 0;
            for (size_t i = 0; i < len; i++) {
                if (isnan(p[i]))
                    omitted++;
                else
                    buf[k++] = p[i];
            }
            p = buf;
            len = k;
            if (len == 0)
                continue;
        }
        mcstat_moments b;
        int st = block_moments(p, len, pilot, &b);
        if (st)
            return st;
        pilot = b.mean;
        /* binary-counter pairwise merging: equal-sized partial results merge */
        uint64_t c = 1;
        while (top > 0 && count[top - 1] == c) {
            merge_into(&stack[top - 1], &b);
            b = stack[--top];
            c *= 2;
        }
        stack[top] = b;
        count[top] = c;
        top++;
    }
    if (top > 0) {
        mcstat_moments total = stack[top - 1];
        for (int k = top - 2; k >= 0; k--)
            merge_into(&stack[k], &total), total = stack[k];
        merge_into(m, &total);
    }
    if (n_omitted)
        *n_omitted = omitted;
    return MCSTAT_OK;
}

int mcstat_moments_add_array(mcstat_moments *m, const double *x, size_t n)
{
    return add_array(m, x, n, 0, NULL);
}

int mcstat_moments_add_array_omit_nan(mcstat_moments *m, const double *x, size_t n, size_t *n_omitted)
{
    return add_array(m, x, n, 1, n_omitted);
}

/* ---- derived quantities -------------------------------------------------- */

double mcstat_moments_mean(const mcstat_moments *m)
{
    return (is_valid(m) && m->n > 0) ? m->mean : NAN;
}

double mcstat_moments_var(const mcstat_moments *m)
{
    if (!is_valid(m) || m->n < 2)
        return NAN;
    return ldexp(m->m2 / (double)(m->n - 1), 2 * m->scale);
}

double mcstat_moments_sd(const mcstat_moments *m)
{
    if (!is_valid(m) || m->n < 2)
        return NAN;
    return ldexp(sqrt(m->m2 / (double)(m->n - 1)), m->scale);
}

double mcstat_moments_skewness(const mcstat_moments *m)
{
    if (!is_valid(m) || m->n < 2 || !(m->m2 > 0.0))
        return NAN;
    return sqrt((double)m->n) * m->m3 / (m->m2 * sqrt(m->m2));
}

double mcstat_moments_kurtosis(const mcstat_moments *m)
{
    if (!is_valid(m) || m->n < 2 || !(m->m2 > 0.0))
        return NAN;
    return (double)m->n * m->m4 / (m->m2 * m->m2) - 3.0;
}

/* ---- for the tests -------------------------------------------------------- */

void mcstat__moments_var_scaled(const mcstat_moments *m, double *v, int *e)
{
    *v = m->m2 / (double)(m->n - 1);
    *e = m->scale;
}

mcstat_dd mcstat__moments_mean_dd(const mcstat_moments *m)
{
    mcstat_dd r = {m->mean, m->mean_lo};
    return r;
}

int mcstat__moments_check(const mcstat_moments *m)
{
    if (!is_valid(m))
        return MCSTAT_EINVAL;
    if (m->n < 2)
        return MCSTAT_ETOOFEW;
    if (!isfinite(m->mean) || !isfinite(m->m2) || !(m->m2 >= 0.0))
        return MCSTAT_EINVAL;
    /* "Equal to within rounding": the standard deviation is below 10 eps |mean|
     * (compared in scaled units).  R's t.test tests the standard error
     * instead, which rejects legitimate large samples (1e6 values at
     * 1e9 +- 3e-4 have se < 10 eps 1e9); the spread is what says whether
     * the values differ by more than their last digits. */
    double sd = sqrt(m->m2 / (double)(m->n - 1));
    if (!(sd > 0.0) || sd < 10.0 * DBL_EPSILON * ldexp(fabs(m->mean), -m->scale))
        return MCSTAT_EDEGENERATE;
    return MCSTAT_OK;
}
