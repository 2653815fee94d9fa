/*
 * moments.c - streaming, mergeable moments that stay exact on stiff data.
 *
 * Arrays are cut into blocks of BLOCK values (16 KiB, resident in L1).  Each
 * block is summed once from memory as shifted power sums S_k = sum (x - c)^k,
 * with c the previous block's mean (the "pilot"; for the first block the mean
 * of 8 spread samples); the central sums follow by the shift formulas.  Their
 * rounding error is about (1 + 2 rho) eps with rho = n (mean - c)^2 / M2, so
 * a block whose pilot was poor (rho > 1: data that drift, outliers among the
 * samples) is summed again about its own mean, which costs an L1 pass, not a
 * memory pass.  This is the two-pass algorithm where it matters and a
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
 * Shifted power sums, min and max in eight independent lanes (lane k takes
 * x[i] with i = k mod 8), reduced in a fixed order.  The AVX2 version (two
 * 4-wide registers per sum) and the portable one perform the same IEEE
 * operations lane by lane, and -ffp-contract=off keeps FMA out, so every
 * machine returns bit-identical sums.  min/max ignore NaN (x < m ? x : m,
 * vminpd(x, m)); a NaN or Inf shows up in the sums instead. */
typedef struct {
    double s1, s2, s3, s4, min, max;
} block_sums;

static void reduce_lanes(const double l1[8], const double l2[8], const double l3[8], const double l4[8],
                         const double mn[8], const double mx[8], double t1, double t2, double t3, double t4,
                         double tmin, double tmax, block_sums *out)
{
#define LANES_SUM(v) ((((v)[0] + (v)[4]) + ((v)[2] + (v)[6])) + (((v)[1] + (v)[5]) + ((v)[3] + (v)[7])))
    out->s1 = LANES_SUM(l1) + t1;
    out->s2 = LANES_SUM(l2) + t2;
    out->s3 = LANES_SUM(l3) + t3;
    out->s4 = LANES_SUM(l4) + t4;
#undef LANES_SUM
    for (int k = 0; k < 8; k++) {
        tmin = mn[k] < tmin ? mn[k] : tmin;
        tmax = mx[k] > tmax ? mx[k] : tmax;
    }
    out->min = tmin;
    out->max = tmax;
}

/* The scalar tail (n mod 8 values), the same in every variant. */
static void kernel_tail(const double *x, size_t i, size_t n, double c, double t[6])
{
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
    t[0] = t1; t[1] = t2; t[2] = t3; t[3] = t4; t[4] = mn; t[5] = mx;
}

static void kernel_portable(const double *x, size_t n, double c, block_sums *out)
{
    double l1[8] = {0}, l2[8] = {0}, l3[8] = {0}, l4[8] = {0}, mn[8], mx[8], t[6];
    for (int k = 0; k < 8; k++) {
        mn[k] = INFINITY;
        mx[k] = -INFINITY;
    }
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        for (int k = 0; k < 8; k++) {
            double v = x[i + k], d = v - c, d2 = d * d;
            l1[k] += d;
            l2[k] += d2;
            l3[k] += d2 * d;
            l4[k] += d2 * d2;
            mn[k] = v < mn[k] ? v : mn[k];
            mx[k] = v > mx[k] ? v : mx[k];
        }
    }
    kernel_tail(x, i, n, c, t);
    reduce_lanes(l1, l2, l3, l4, mn, mx, t[0], t[1], t[2], t[3], t[4], t[5], out);
}

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__)) && \
    !defined(MCSTAT_NO_AVX2)
#include <immintrin.h>
#define MCSTAT_HAVE_AVX2_KERNEL 1

__attribute__((target("avx2"))) static void kernel_avx2(const double *x, size_t n, double c, block_sums *out)
{
    const __m256d vc = _mm256_set1_pd(c);
    __m256d s1a = _mm256_setzero_pd(), s1b = s1a, s2a = s1a, s2b = s1a, s3a = s1a, s3b = s1a, s4a = s1a, s4b = s1a;
    __m256d mna = _mm256_set1_pd(INFINITY), mnb = mna, mxa = _mm256_set1_pd(-INFINITY), mxb = mxa;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        __m256d xa = _mm256_loadu_pd(x + i), xb = _mm256_loadu_pd(x + i + 4);
        __m256d da = _mm256_sub_pd(xa, vc), db = _mm256_sub_pd(xb, vc);
        __m256d qa = _mm256_mul_pd(da, da), qb = _mm256_mul_pd(db, db);
        s1a = _mm256_add_pd(s1a, da);
        s1b = _mm256_add_pd(s1b, db);
        s2a = _mm256_add_pd(s2a, qa);
        s2b = _mm256_add_pd(s2b, qb);
        s3a = _mm256_add_pd(s3a, _mm256_mul_pd(qa, da));
        s3b = _mm256_add_pd(s3b, _mm256_mul_pd(qb, db));
        s4a = _mm256_add_pd(s4a, _mm256_mul_pd(qa, qa));
        s4b = _mm256_add_pd(s4b, _mm256_mul_pd(qb, qb));
        mna = _mm256_min_pd(xa, mna); /* NaN in x: keeps mna, like x < m ? x : m */
        mnb = _mm256_min_pd(xb, mnb);
        mxa = _mm256_max_pd(xa, mxa);
        mxb = _mm256_max_pd(xb, mxb);
    }
    double l1[8], l2[8], l3[8], l4[8], mn[8], mx[8], t[6];
    _mm256_storeu_pd(l1, s1a); _mm256_storeu_pd(l1 + 4, s1b);
    _mm256_storeu_pd(l2, s2a); _mm256_storeu_pd(l2 + 4, s2b);
    _mm256_storeu_pd(l3, s3a); _mm256_storeu_pd(l3 + 4, s3b);
    _mm256_storeu_pd(l4, s4a); _mm256_storeu_pd(l4 + 4, s4b);
    _mm256_storeu_pd(mn, mna); _mm256_storeu_pd(mn + 4, mnb);
    _mm256_storeu_pd(mx, mxa); _mm256_storeu_pd(mx + 4, mxb);
    /* GCC does not emit vzeroupper for this target("avx2") function: left
     * dirty, the upper halves of the ymm registers make the caller's legacy
     * SSE code (sqrtsd, cvtsi2sd, ...) depend on them, serialising a
     * renderer's loop after every mcstat_moments_add_array (measured: 1.9 ->
     * 10 ns per sample in examples/check/integrator.c). */
    _mm256_zeroupper();
    kernel_tail(x, i, n, c, t);
    reduce_lanes(l1, l2, l3, l4, mn, mx, t[0], t[1], t[2], t[3], t[4], t[5], out);
}
#endif

static void kernel(const double *x, size_t n, double c, block_sums *out)
{
#ifdef MCSTAT_HAVE_AVX2_KERNEL
    if (n >= 16 && __builtin_cpu_supports("avx2")) {
        kernel_avx2(x, n, c, out);
        return;
    }
#endif
    kernel_portable(x, n, c, out);
}

/* The scaled variant for extreme magnitudes: d = x 2^-e - c. Rare; scalar. */
static void kernel_scaled(const double *x, size_t n, int e, double c, block_sums *out)
{
    double t1 = 0, t2 = 0, t3 = 0, t4 = 0, mn = INFINITY, mx = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        double d = scale2(x[i], -e) - c, d2 = d * d;
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
    /* delta = S1/n in double-double: the mean is c + delta, and rounding the
     * division would cost eps |delta| (delta ~ sd unless c was the mean) */
    mcstat_dd delta_dd = dd_div_d((mcstat_dd){s->s1, 0.0}, n);
    double delta = delta_dd.hi;
    double m2 = s->s2 - delta * s->s1;
    double m3 = s->s3 - 3.0 * delta * s->s2 + 2.0 * n * delta * delta * delta;
    double d2 = delta * delta;
    double m4 = s->s4 - 4.0 * delta * s->s3 + 6.0 * d2 * s->s2 - 3.0 * n * d2 * d2;
    mcstat_dd cc = {c, 0.0};
    mcstat_dd mean = dd_add(cc, delta_dd);
    m->mean = e ? scale2(mean.hi, e) : mean.hi;
    m->mean_lo = e ? scale2(mean.lo, e) : mean.lo;
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
    if (!(fabs(pilot) <= FAST_HI)) { /* no previous block: the mean of 8 spread samples */
        size_t step = n >= 8 ? n / 8 : 1, k = 0;
        double sum = 0.0;
        for (size_t i = 0; i < n && k < 8; i += step, k++)
            sum += x[i];
        pilot = sum / (double)k;
    }
    if (!(fabs(pilot) <= FAST_HI))
        pilot = 0.0;
    kernel(x, n, pilot, &s);
    double amax = fmax(fabs(s.min), fabs(s.max));
    if (isfinite(s.s1) && isfinite(s.s2) && isfinite(s.s3) && isfinite(s.s4) &&
        (amax == 0.0 || (amax >= FAST_LO && amax <= FAST_HI))) {
        double rho = central_from_shifted(&s, dn, pilot, 0, m);
        if (rho > 1.0) { /* poor pilot: sum again about this block's mean */
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
        c += scale2(x[i], -e);
    c /= dn;
    kernel_scaled(x, n, e, c, &s);
    double rho = central_from_shifted(&s, dn, c, e, m);
    if (rho > 0.0625) {
        c = scale2(m->mean, -e) + scale2(m->mean_lo, -e);
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
    m->m2 = scale2(m->m2, 2 * k);
    m->m3 = scale2(m->m3, 3 * k);
    m->m4 = scale2(m->m4, 4 * k);
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
    /* The difference of the means and its share nb/n are formed in units of
     * 2^e: unscaled, means of +-1e308 overflowed to Inf and Dekker's split
     * in dd_mul_d overflowed for |delta| above 1e300, and the mean came out
     * NaN (found by tests/fuzz/fuzz_moments).  Powers of two scale exactly,
     * so for all other data nothing changes, bit for bit. */
    mcstat_dd mas = {scale2(a->mean, -e), scale2(a->mean_lo, -e)}, mbs = {scale2(B.mean, -e), scale2(B.mean_lo, -e)};
    mcstat_dd delta = dd_add(mbs, dd_neg(mas)); /* units of 2^e */
    double ds = delta.hi + delta.lo;
    double ds2 = ds * ds;
    double m2 = a->m2 + B.m2 + ds2 * n * fa * fb;
    double m3 = a->m3 + B.m3 + ds2 * ds * n * fa * fb * (fa - fb) + 3.0 * ds * (fa * B.m2 - fb * a->m2);
    double m4 = a->m4 + B.m4 + ds2 * ds2 * n * fa * fb * (fa * fa - fa * fb + fb * fb) +
                6.0 * ds2 * (fa * fa * B.m2 + fb * fb * a->m2) + 4.0 * ds * (fa * B.m3 - fb * a->m3);
    mcstat_dd inc = dd_div_d(dd_mul_d(delta, nb), n); /* delta nb / n, unrounded */
    /* the new mean in units of 2^e too: the increment alone may exceed
     * DBL_MAX (from -DBL_MAX towards +DBL_MAX) where the mean does not */
    mcstat_dd ms = dd_add(mas, inc);
    mcstat_dd mean = {scale2(ms.hi, e), scale2(ms.lo, e)};
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

int mcstat_moments_from_summary(uint64_t n, double mean, double m2, mcstat_moments *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out)
        return MCSTAT_EINVAL;
    if (!isfinite(mean) || !isfinite(m2))
        return MCSTAT_ENONFINITE;
    if (m2 < 0.0)
        return MCSTAT_EINVAL;
    /* no values, or one value with a spread: too few for what the summary
     * claims (the status a test on such a sample gives) */
    if (n == 0 || (n == 1 && m2 != 0.0))
        return MCSTAT_ETOOFEW;
    /* The summary says nothing of the third and fourth sums or the extremes;
     * the stand-in is the symmetric two-point sample mean +- h, h =
     * sqrt(M2/n), which has this n, mean and M2, M3 = 0 and M4 = M2^2/n, the
     * least M4 can be, so the accumulator keeps every invariant that
     * mcstat_moments_from_bytes checks and merges like any other. */
    double h = sqrt(m2 / (double)n);
    mcstat_moments m;
    mcstat_moments_init(&m);
    m.n = n;
    m.mean = mean;
    m.min = mean - h;
    m.max = mean + h;
    if (!isfinite(m.min) || !isfinite(m.max))
        return MCSTAT_ETOOBIG;
    m.scale = scale_for(fmax(fabs(m.min), fabs(m.max)));
    m.m2 = ldexp(m2, -2 * m.scale);
    m.m4 = (m.m2 / (double)n) * m.m2;
    *out = m;
    return MCSTAT_OK;
}

int mcstat_moments_merge(mcstat_moments *dst, const mcstat_moments *src)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(dst) || !is_valid(src))
        return MCSTAT_EINVAL;
    if (src->n == 0)
        return MCSTAT_OK;
    if (src->n > UINT64_MAX - dst->n) /* the count would wrap */
        return MCSTAT_ETOOBIG;
    mcstat_moments copy = *src; /* src may alias dst */
    merge_into(dst, &copy);
    return MCSTAT_OK;
}

int mcstat_moments_add(mcstat_moments *m, double x)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(m))
        return MCSTAT_EINVAL;
    if (!isfinite(x))
        return MCSTAT_ENONFINITE;
    if (m->n == UINT64_MAX)
        return MCSTAT_ETOOBIG;
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
    /* Counts must not wrap: refused before any work when even the values
     * kept would not fit; with omit_nan the exact count is checked below. */
    if (!omit_nan && (uint64_t)n > UINT64_MAX - m->n)
        return MCSTAT_ETOOBIG;
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
        if (total.n > UINT64_MAX - m->n)
            return MCSTAT_ETOOBIG;
        merge_into(m, &total);
    }
    if (n_omitted)
        *n_omitted = omitted;
    return MCSTAT_OK;
}

int mcstat_moments_add_array(mcstat_moments *m, const double *x, size_t n)
{
    MCSTAT_IEEE_SCOPE();
    return add_array(m, x, n, 0, NULL);
}

int mcstat_moments_add_array_omit_nan(mcstat_moments *m, const double *x, size_t n, size_t *n_omitted)
{
    MCSTAT_IEEE_SCOPE();
    return add_array(m, x, n, 1, n_omitted);
}

/* ---- derived quantities -------------------------------------------------- */

double mcstat_moments_mean(const mcstat_moments *m)
{
    MCSTAT_IEEE_SCOPE();
    return (is_valid(m) && m->n > 0) ? m->mean : NAN;
}

double mcstat_moments_var(const mcstat_moments *m)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(m) || m->n < 2)
        return NAN;
    return scale2(m->m2 / (double)(m->n - 1), 2 * m->scale);
}

double mcstat_moments_sd(const mcstat_moments *m)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(m) || m->n < 2)
        return NAN;
    return scale2(sqrt(m->m2 / (double)(m->n - 1)), m->scale);
}

double mcstat_moments_skewness(const mcstat_moments *m)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(m) || m->n < 2 || !(m->m2 > 0.0))
        return NAN;
    return sqrt((double)m->n) * m->m3 / (m->m2 * sqrt(m->m2));
}

double mcstat_moments_kurtosis(const mcstat_moments *m)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(m) || m->n < 2 || !(m->m2 > 0.0))
        return NAN;
    return (double)m->n * m->m4 / (m->m2 * m->m2) - 3.0;
}

/* ---- for the tests -------------------------------------------------------- */

int mcstat__moments_scale_for(double amax)
{
    return scale_for(amax);
}

void mcstat__moments_var_scaled(const mcstat_moments *m, double *v, int *e)
{
    /* Accumulators built by adds keep m2 far from under- and overflow (the
     * scale follows the data's magnitude), but deserialized or merged ones
     * may not: m2 = 1e-305 at n = 4e10 made v / n underflow to 0 and the t
     * statistic 0/0 (found by tests/fuzz/fuzz_bytes).  There the exponent is
     * moved into e, exactly; elsewhere nothing changes, bit for bit. */
    int k = 0;
    if (m->m2 > 0.0 && isfinite(m->m2) && (m->m2 < 0x1p-500 || m->m2 > 0x1p+500))
        k = ilogb(m->m2) / 2;
    *v = scale2(m->m2, -2 * k) / (double)(m->n - 1);
    *e = m->scale + k;
}

mcstat_dd mcstat__moments_mean_dd(const mcstat_moments *m)
{
    mcstat_dd r = {m->mean, m->mean_lo};
    return r;
}

int mcstat__moments_check(const mcstat_moments *m)
{
    if (!is_valid(m))
        return mcstat__refuse(MCSTAT_EINVAL, "an accumulator is not valid (not set up by mcstat_moments_init, "
                                             "or its fields were changed)");
    if (m->n < 2)
        return MCSTAT_ETOOFEW;
    if (!isfinite(m->mean) || !isfinite(m->m2) || !(m->m2 >= 0.0))
        return mcstat__refuse(MCSTAT_EINVAL, "an accumulator's mean or M2 is not finite (mean %g, M2 %g)", m->mean,
                              m->m2);
    /* "Equal to within rounding": the standard deviation is below 10 eps |mean|
     * (compared in scaled units).  R's t.test tests the standard error
     * instead, which rejects legitimate large samples (1e6 values at
     * 1e9 +- 3e-4 have se < 10 eps 1e9); the spread is what says whether
     * the values differ by more than their last digits. */
    double sd = sqrt(m->m2 / (double)(m->n - 1));
    if (!(sd > 0.0) || sd < 10.0 * DBL_EPSILON * scale2(fabs(m->mean), -m->scale))
        return MCSTAT_EDEGENERATE;
    return MCSTAT_OK;
}

int mcstat__moments_of_two(const double *x, size_t nx, const double *y, size_t ny, mcstat_moments *mx,
                           mcstat_moments *my)
{
    mcstat_moments_init(mx);
    mcstat_moments_init(my);
    int st = mcstat_moments_add_array(mx, x, nx);
    return st ? st : mcstat_moments_add_array(my, y, ny);
}
