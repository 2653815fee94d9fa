/*
 * pixels.h - what the per-pixel Welch kernel (pixels.c), the fast t tail
 * (pixels_dist.c) and the t quantiles' tables (t_quantiles.c) share: the
 * block size, the baseline and AVX2 builds of the block loops, the t
 * prefactor, Lagrange's six-point weights and the per-call table of
 * critical values.
 * Included by those three files; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_PIXELS_H
#define MCSTAT_PIXELS_H

#include "internal.h"

#define PIX_BLOCK 256     /* pixels per block: their sums stay in L1 */
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
#if PIX_AVX2
#include <immintrin.h>
#endif

/* ---- the t prefactor (pixels_dist.c's tail) --------------------------------
 * With a = df/2, r = t^2/df, the tail's prefactor K = |t| f(t) (the density
 * at t times |t|) is |t| f exp(lc - (a+1/2) log1p(r)); pixels_dist.c's
 * section comment derives it.  Inline: the block loops that form it over
 * a block of pixels vectorise. */
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

static inline void t_prefactor_init(double df, t_prefactor *pf)
{
    pf->a = 0.5 * df;
    pf->A = pf->a + 0.5;
    t_prefactor_parts(pf->a, &pf->f, &pf->lc);
}

/* The fast tail's ground: df in [1, 1000], 1e-100 <= |t| < 1e100. */
static inline int fast_range(double at, double df)
{
    return df >= 1.0 && df <= 1000.0 && at >= 1e-100 && at < 1e100;
}

/* ---- the fast t tail (pixels_dist.c) ----------------------------------------
 * The tails at |t| = at; *kk = K.  Returns 0 where the caller must use
 * mcstat__t_tails. */
MCSTAT_HIDDEN int mcstat__t_tail_core(double at, const t_prefactor *pf, double *upper, double *other, double *kk);

/* Both tails of t(df) at t[j] for the k pixels with want[j] (prefactors
 * pa, pf, plc as block_statistics leaves them): lower[j], upper[j] where
 * ok[j] = TAIL_DONE; TAIL_GENERAL where mcstat__t_tail_core would return 0 too (the
 * general mcstat__t_tails answers), TAIL_SCALAR where the scalar path
 * decides (K underflows, df or t outside the fast range). */
enum { TAIL_SCALAR, TAIL_DONE, TAIL_GENERAL };
/* (k <= PIX_BLOCK) */
MCSTAT_HIDDEN void mcstat__t_block_tails(size_t k, const double *t, const double *df, const double *pa,
                                         const double *pf, const double *plc, const unsigned char *want,
                                         double *lower, double *upper, unsigned char *ok);
#if PIX_AVX2
/* The same compiled for AVX2 (the central series' two vectors of four side
 * by side): the same results, bit for bit. */
__attribute__((target("avx2"))) MCSTAT_HIDDEN void mcstat__t_block_tails_avx2(
    size_t k, const double *t, const double *df, const double *pa, const double *pf, const double *plc,
    const unsigned char *want, double *lower, double *upper, unsigned char *ok);
#endif

/* ---- the critical values' table (t_quantiles.c) ---------------------------- */
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

/* The per-call table of t quantiles at one level, in u = 1/df, and the
 * critical values from it for an alternative: the per-pixel Welch tests'
 * (pixels.c) and mcstat_t_quantiles' (with "greater": the upper quantile). */
typedef struct {
    int alternative;
    double crit_two; /* the two-sided critical value at the last df, and that df */
    double crit_df;
    double qt_p; /* the level of the critical values: alpha/2 or alpha */
    double *qt;  /* their quantiles at df = qt_n / j, j = 0..qt_n, NaN until needed */
    int qt_n;
} mcstat__qt_table;

/* The table at level p in qt[0..n], empty (NaN: each node solved when first
 * needed). */
MCSTAT_HIDDEN void mcstat__qt_table_init(mcstat__qt_table *c, double p, double *qt, int n);
/* The critical values (c0, c1) of t(df) for the table's alternative, as
 * mcstat__finish asks them; pf is df's prefactor, NULL to compute it. */
MCSTAT_HIDDEN int mcstat__qt_criticals(mcstat__qt_table *c, double df, const t_prefactor *pf, double *c0,
                                       double *c1);
/* For each of k df (those with want[j], all if want is NULL), the six table
 * nodes qn[0..5][j] Lagrange's weights take and the offset qs[j] in them;
 * NaN nodes where the table does not answer. */
MCSTAT_HIDDEN void mcstat__qt_table_nodes(mcstat__qt_table *c, size_t k, const double *df, const unsigned char *want,
                                          double (*qn)[PIX_BLOCK], double *qs);

#endif /* MCSTAT_PIXELS_H */
