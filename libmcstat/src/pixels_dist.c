/*
 * pixels_dist.c - the t distribution kernel of the per-pixel tests: the
 * Student t tail specialised to the incomplete beta's b = 1/2, for one
 * (t, df) (mcstat__t_tail_core, mcstat__t_tail_fast) and for a block of
 * pixels (mcstat__t_block_tails: the prefactors four pixels at a time with
 * vector exp and log1p, the central series eight at a time, compiled for
 * the baseline and for AVX2).  pixels.c's Welch kernel and t_quantiles.c's
 * Halley iteration read it; pixels.h holds the prefactor they share.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "pixels.h"
#include "vmath.h"

#include <float.h>

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

/* The tails at |t| = at (pixels.h). */
int mcstat__t_tail_core(double at, const t_prefactor *pf, double *upper, double *other, double *kk)
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

int mcstat__t_tail_fast(double t, double df, double *upper, double *other, double *logk)
{
    double at = fabs(t);
    if (!fast_range(at, df))
        return 0;
    t_prefactor pf;
    double k;
    t_prefactor_init(df, &pf);
    if (!mcstat__t_tail_core(at, &pf, upper, other, &k))
        return 0;
    *logk = log(at * pf.f) + pf.lc - pf.A * log1p(at * at / df); /* finite where K underflows */
    return 1;
}

/* ---- the tails of a block ----------------------------------------------
 * mcstat__t_tail_core for many pixels: the prefactors four pixels at a time, the
 * upper series pixel by pixel (few pixels), the central series (most
 * pixels under the null) eight at a time, so its loop runs as long as the
 * slowest of eight and its exit is taken once per eight pixels instead of
 * mispredicted once per pixel; the continued fraction four at a time.  A
 * lane that has converged goes on adding terms below its rounding; the
 * sums are those of mcstat__t_tail_core to a few ulps. */
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
        ok[j] = TAIL_GENERAL; /* unless answered below, as for mcstat__t_tail_core */
        double a = pa[j], A = a + 0.5, r = rr[j], y = yy[j];
        if (r < 1.0 && A * y > 40.0)
            continue;
        if (!(ee[j] > -700.0)) {
            ok[j] = TAIL_SCALAR; /* K underflows here: mcstat__t_tail_core's logarithmic form */
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
            idx[nc] = j; /* A, y, K are read from their arrays by the sort */
            nc++;
        }
    }
    /* the counting sort: bin b's lanes to sidx[cnt[b]] on, in their order */
    for (int b = 0; b < Y_BINS; b++)
        cnt[b + 1] += cnt[b];
    for (size_t g = 0; g < nc; g++) {
        size_t o = cnt[bin[g]]++, j = idx[g];
        sidx[o] = j;
        sA[o] = pa[j] + 0.5;
        sy[o] = yy[j];
        sk[o] = kk[j];
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

void mcstat__t_block_tails(size_t k, const double *t, const double *df, const double *pa, const double *pf,
                           const double *plc, const unsigned char *want, double *lower, double *upper,
                           unsigned char *ok)
{
    block_tails(k, t, df, pa, pf, plc, want, lower, upper, ok, 0);
}

#if PIX_AVX2
__attribute__((target("avx2"))) void mcstat__t_block_tails_avx2(size_t k, const double *t, const double *df,
                                                                const double *pa, const double *pf,
                                                                const double *plc, const unsigned char *want,
                                                                double *lower, double *upper, unsigned char *ok)
{
    block_tails(k, t, df, pa, pf, plc, want, lower, upper, ok, 1);
}
#endif

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
