/*
 * ks.h - the two-sample Kolmogorov-Smirnov test's internals (ks_*.c).
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_KS_H
#define MCSTAT_KS_H

/* ---- two-sample Kolmogorov-Smirnov (ks_*.c) --------------------------------
 * mcstat's alternatives are claims about the first sample (API.md, ERRATA 4):
 * LESS = x tends to be smaller = its CDF lies above.  R, SciPy and the
 * internals of ks_*.c name them by the CDF instead (greater = sup (F - G));
 * mcstat__ks_cdf_alternative maps one to the other (its own inverse).

 * A lattice point after s = i + j pooled values (i of x, j of y) is
 * u = i*ny - j*nx = (F - G) nx ny and q = s (N - s) = z (1 - z) N^2.  The
 * test works with a monotone "key" of the statistic: |u| for weight NONE,
 * u^2 / q for Canner's; D = key / (nx ny), D2 = sqrt(key N / (nx ny)).
 * Comparisons that decide p-values are made on (u, q) in exact integer
 * arithmetic, so no threshold needs nudging. */
typedef struct {
    uint64_t u, q; /* the value u^2/q (Canner) or u (NONE, q unused); u >= 0 */
} mcstat__ks_point;

static inline int mcstat__ks_cdf_alternative(int alternative)
{
    return alternative == MCSTAT_LESS ? MCSTAT_GREATER : alternative == MCSTAT_GREATER ? MCSTAT_LESS : alternative;
}

typedef struct {
    uint64_t n1, n2, N;
    int weight, alternative;
    size_t nblocks;        /* distinct pooled values */
    const uint64_t *ends;  /* s at the end of each block (ascending, last N); NULL: no ties */
    mcstat__ks_point obs;  /* the observed sup */
    double key;            /* its key */
    int sign;              /* sign of F - G there (+1, -1; 0 when the statistic is 0) */
} mcstat__ks_data;

static inline double mcstat__ks_key(int weight, uint64_t u, uint64_t q)
{
    double du = (double)u;
    return weight == MCSTAT_KS_WEIGHT_NONE ? du : du * du / (double)q;
}
MCSTAT_HIDDEN double mcstat__ks_key_statistic(const mcstat__ks_data *d, double key);
/* -1, 0, +1 as a < b, a == b, a > b exactly (the cross products u^2 q,
 * below 2^192, in integers). */
MCSTAT_HIDDEN int mcstat__ks_point_cmp(int weight, mcstat__ks_point a, mcstat__ks_point b);

/* Exact (ks_exact.c).  MCSTAT_ETOOBIG beyond the work limit. */
MCSTAT_HIDDEN int mcstat__ks_exact_check(const mcstat__ks_data *d);
/* P(statistic >= the value of t) under H0, given the tie pattern. */
MCSTAT_HIDDEN int mcstat__ks_exact_sf(const mcstat__ks_data *d, mcstat__ks_point t, double *p);
/* The largest attainable key c with P(key >= c) > alpha (+ its statistic). */
MCSTAT_HIDDEN int mcstat__ks_exact_critical(const mcstat__ks_data *d, double alpha, double *key);

/* Simulation (ks_simulate.c): n_sim keys of the null distribution, sorted. */
MCSTAT_HIDDEN int mcstat__ks_simulate(const mcstat__ks_data *d, int64_t n_sim, uint64_t seed,
                                      int threads, double *keys);
/* The same with a chosen generator and kernel (the benchmark compares them;
 * the tests check that the two xoshiro kernels give bit-identical keys):
 * TAUS2 GSL's taus2, scalar, only in the benchmark's own build of
 * ks_simulate.c (MCSTAT_KS_BENCH_TAUS2; the library refuses it: EINVAL);
 * XOSHIRO xoshiro256++, the AVX2 kernel where it applies; XOSHIRO_SCALAR
 * the same numbers by the scalar kernel. */
enum {
    MCSTAT__KS_RNG_TAUS2 = 0,
    MCSTAT__KS_RNG_XOSHIRO = 1,
    MCSTAT__KS_RNG_XOSHIRO_SCALAR = 2,
    MCSTAT__KS_RNG_DEFAULT = 1
};
MCSTAT_HIDDEN int mcstat__ks_simulate_rng(const mcstat__ks_data *d, int64_t n_sim, uint64_t seed,
                                          int threads, int rng, double *keys);

/* Cache (ks_cache.c): copies of sorted simulated keys. */
MCSTAT_HIDDEN int mcstat__ks_cache_get(mcstat_ks_cache *c, const mcstat__ks_data *d, int64_t n_sim,
                                       uint64_t seed, double *keys);
MCSTAT_HIDDEN int mcstat__ks_cache_put(mcstat_ks_cache *c, const mcstat__ks_data *d, int64_t n_sim,
                                       uint64_t seed, const double *keys);

/* Asymptotic (ks_asymptotic.c), weight NONE: upper tail at statistic D and
 * the critical value at alpha. */
MCSTAT_HIDDEN double mcstat__ks_asymp_sf(uint64_t n1, uint64_t n2, int two_sided, double d);
MCSTAT_HIDDEN double mcstat__ks_asymp_critical(uint64_t n1, uint64_t n2, int two_sided, double alpha);
/* log of mcstat__ks_asymp_sf, finite where that underflows to 0. */
MCSTAT_HIDDEN double mcstat__ks_asymp_log_sf(uint64_t n1, uint64_t n2, int two_sided, double d);
/* Kolmogorov's limit P(K > t). */
MCSTAT_HIDDEN double mcstat__kolmogorov_sf(double t);

#endif /* MCSTAT_KS_H */
