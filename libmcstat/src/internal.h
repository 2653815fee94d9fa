/*
 * internal.h - helpers shared by libmcstat's sources; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_INTERNAL_H
#define MCSTAT_INTERNAL_H

#include "mcstat.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define MCSTAT_HIDDEN __attribute__((visibility("hidden")))

/* The algorithms rely on IEEE arithmetic as written, so the library refuses
 * to be built without it rather than give wrong numbers quietly (built with
 * -ffast-math, every variance came out 0):
 * - compensated sums and the double-double helpers below are exact only if
 *   the compiler does not reassociate them (-fassociative-math turns
 *   (a + b) - a into b);
 * - NaN and infinity checks on the caller's data are how bad input gets its
 *   status code (-ffinite-math-only deletes them);
 * - divisions are correctly rounded (-freciprocal-math is not).
 * Code that includes mcstat.h may use any flags: this is libmcstat's own. */
#if defined(__FAST_MATH__) || (defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__) || \
    defined(__ASSOCIATIVE_MATH__) || defined(__RECIPROCAL_MATH__)
#error "libmcstat must be compiled with IEEE floating-point semantics: remove -ffast-math / -Ofast (or -ffinite-math-only, -fassociative-math, -freciprocal-math, -funsafe-math-optimizations) from the flags for libmcstat; its compensated sums, double-double arithmetic and NaN checks depend on them (see src/internal.h)"
#endif

/* ---- the caller's floating-point environment ------------------------------
 * No result may depend on it.  A renderer may run with subnormals flushed to
 * zero and read as zero (x86 MXCSR FTZ/DAZ, ARM FPCR.FZ: what -ffast-math's
 * crtfastmath.o sets at start-up), another rounding direction or trapping
 * exceptions; the scaled moments, the double-double helpers and the tails
 * that underflow gracefully all assume IEEE defaults.  Every public function
 * that computes in floating point starts with MCSTAT_IEEE_SCOPE(): inside, the
 * defaults (round to nearest, subnormals kept, exceptions masked); on return,
 * by any path, the caller's mode again (exception flags raised inside are not
 * kept).  In the default environment the cost is one register read.  Threads
 * started inside inherit the defaults. */
#if defined(__x86_64__) || (defined(__i386__) && defined(__SSE2__))
#include <fenv.h>
#include <xmmintrin.h>
typedef struct {
    unsigned csr; /* MXCSR */
    int round;    /* fegetround(): the x87 control word's, which printf reads */
} mcstat__fpenv;
/* MXCSR: FTZ (bit 15), rounding (13-14), exception masks (7-12), DAZ (6);
 * the default is 0x1f80 plus whatever exception flags (0-5) are set.
 * fesetround() sets the rounding of SSE and x87 together, so a caller's
 * rounding direction shows in MXCSR. */
static inline mcstat__fpenv mcstat__fpenv_enter(void)
{
    mcstat__fpenv e = {_mm_getcsr(), FE_TONEAREST};
    if (__builtin_expect((e.csr & ~0x3fu) != 0x1f80u, 0)) {
        e.round = fegetround();
        if (e.round != FE_TONEAREST)
            fesetround(FE_TONEAREST);
        _mm_setcsr((e.csr & 0x3fu) | 0x1f80u);
    }
    return e;
}
static inline void mcstat__fpenv_leave(const mcstat__fpenv *e)
{
    if (__builtin_expect((e->csr & ~0x3fu) != 0x1f80u, 0)) {
        if (e->round != FE_TONEAREST)
            fesetround(e->round);
        _mm_setcsr(e->csr);
    }
}
#elif defined(__aarch64__)
typedef uint64_t mcstat__fpenv;
/* FPCR: rounding (bits 22-23), FZ (24), DN (25), trap enables (8-12, 15) */
#define MCSTAT__FPCR_MODES 0x03c09f00ull
static inline mcstat__fpenv mcstat__fpenv_enter(void)
{
    uint64_t c;
    __asm__ __volatile__("mrs %0, fpcr" : "=r"(c) : : "memory");
    if (__builtin_expect((c & MCSTAT__FPCR_MODES) != 0, 0)) {
        uint64_t d = c & ~MCSTAT__FPCR_MODES;
        __asm__ __volatile__("msr fpcr, %0" : : "r"(d) : "memory");
    }
    return c;
}
static inline void mcstat__fpenv_leave(const mcstat__fpenv *c)
{
    if (__builtin_expect((*c & MCSTAT__FPCR_MODES) != 0, 0))
        __asm__ __volatile__("msr fpcr, %0" : : "r"(*c) : "memory");
}
#else
/* elsewhere the rounding direction only (no portable flush-to-zero control) */
#include <fenv.h>
typedef int mcstat__fpenv;
static inline mcstat__fpenv mcstat__fpenv_enter(void)
{
    int r = fegetround();
    if (r != FE_TONEAREST)
        fesetround(FE_TONEAREST);
    return r;
}
static inline void mcstat__fpenv_leave(const mcstat__fpenv *r)
{
    if (*r != FE_TONEAREST)
        fesetround(*r);
}
#endif
#define MCSTAT_IEEE_SCOPE() \
    __attribute__((cleanup(mcstat__fpenv_leave), unused)) const mcstat__fpenv mcstat__fpenv_saved = mcstat__fpenv_enter()

/* ---- double-double arithmetic (Dekker, Knuth) ----------------------------
 * Exact when the compiler neither reorders nor contracts these operations;
 * the build passes -ffp-contract=off, and -ffast-math is refused above. */
typedef struct {
    double hi, lo;
} mcstat_dd;

static inline mcstat_dd dd_two_sum(double a, double b)
{
    double s = a + b;
    double bb = s - a;
    double e = (a - (s - bb)) + (b - bb);
    mcstat_dd r = {s, e};
    return r;
}

static inline mcstat_dd dd_fast_two_sum(double a, double b) /* |a| >= |b| */
{
    double s = a + b;
    mcstat_dd r = {s, b - (s - a)};
    return r;
}

static inline mcstat_dd dd_add(mcstat_dd a, mcstat_dd b)
{
    mcstat_dd s = dd_two_sum(a.hi, b.hi);
    mcstat_dd t = dd_two_sum(a.lo, b.lo);
    s.lo += t.hi;
    s = dd_fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return dd_fast_two_sum(s.hi, s.lo);
}

static inline mcstat_dd dd_neg(mcstat_dd a)
{
    mcstat_dd r = {-a.hi, -a.lo};
    return r;
}

/* a * b for doubles, exactly, by Dekker's splitting (no FMA needed). */
static inline mcstat_dd dd_two_prod(double a, double b)
{
    const double split = 134217729.0; /* 2^27 + 1 */
    double p = a * b;
    double ta = split * a, ah = ta - (ta - a), al = a - ah;
    double tb = split * b, bh = tb - (tb - b), bl = b - bh;
    double e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    mcstat_dd r = {p, e};
    return r;
}

static inline mcstat_dd dd_mul_d(mcstat_dd a, double b)
{
    mcstat_dd p = dd_two_prod(a.hi, b);
    p.lo += a.lo * b;
    return dd_fast_two_sum(p.hi, p.lo);
}

/* a / b for a double-double and a double, to about 2^-104 relative. */
static inline mcstat_dd dd_div_d(mcstat_dd a, double b)
{
    double q1 = a.hi / b;
    mcstat_dd p = dd_two_prod(q1, b);
    mcstat_dd r = dd_two_sum(a.hi, -p.hi);
    r.lo += a.lo - p.lo;
    double q2 = (r.hi + r.lo) / b;
    return dd_fast_two_sum(q1, q2);
}

/* x * 2^e; the common e == 0 costs nothing (ldexp is a libm call). */
static inline double scale2(double x, int e)
{
    return e ? ldexp(x, e) : x;
}

/* ---- argument checks ---------------------------------------------------- */
static inline int valid_alternative(int alt)
{
    return alt == MCSTAT_TWO_SIDED || alt == MCSTAT_LESS || alt == MCSTAT_GREATER;
}

static inline int valid_alpha(double alpha)
{
    return alpha > 0.0 && alpha < 1.0; /* false for NaN */
}

/* ---- special functions (special.c) --------------------------------------
 * Both tails of a distribution function and their logarithms, each computed
 * from the side where it is small, so neither loses relative accuracy. */
typedef struct {
    double p, q;       /* lower and upper tail, p + q = 1 */
    double logp, logq; /* their logarithms, finite where p or q underflow */
    double logk;       /* special.c: log of the prefactor x^a y^b / B(a,b) or
                        * x^a e^-x / Gamma(a+1); dist.c: log(x f(x)), the density
                        * at x times x, which is that prefactor (times a for chi2) */
} mcstat_tails;

/* Regularized incomplete beta I_x(a, b) for a, b > 0, with x + y = 1 both
 * given so that neither needs to be formed as 1 - the other. */
MCSTAT_HIDDEN int mcstat__beta_inc(double a, double b, double x, double y, mcstat_tails *t);
/* The same with the deviations from the centre given by the caller:
 * ux = x (a+b)/a - 1, uy = y (a+b)/b - 1 (see special.c). */
MCSTAT_HIDDEN int mcstat__beta_inc_u(double a, double b, double x, double y, double ux, double uy,
                                     mcstat_tails *t);
/* Regularized incomplete gamma P(a, x), Q(a, x) for a > 0, x >= 0. */
MCSTAT_HIDDEN int mcstat__gamma_inc(double a, double x, mcstat_tails *t);
/* log of x^a y^b / B(a, b) (x + y = 1) and of x^a e^-x / Gamma(a+1): the
 * densities below are these over x (see dist.c). */
MCSTAT_HIDDEN double mcstat__log_beta_prefactor(double a, double b, double x, double y);
MCSTAT_HIDDEN double mcstat__log_beta_prefactor_u(double a, double b, double x, double y, double ux, double uy);
MCSTAT_HIDDEN double mcstat__log_gamma_prefactor(double a, double x);
/* log of the Stirling remainder Gamma*(a) = Gamma(a) / (sqrt(2 pi) a^(a-1/2) e^-a). */
MCSTAT_HIDDEN double mcstat__log_gammastar(double a);
/* a * (u - log1p(u)) >= 0 without cancellation near u = 0; the caller gives
 * log1pu = log(1 + u), computed from its inputs where 1 + u would lose digits. */
MCSTAT_HIDDEN double mcstat__dev(double a, double u, double log1pu);

/* Standard normal quantile (a starting value for the iterations). */
MCSTAT_HIDDEN double mcstat__norm_quantile(double p, int upper);

/* ---- distributions (dist.c), with validated arguments ------------------- */
MCSTAT_HIDDEN int mcstat__t_tails(double x, double df, mcstat_tails *t);
MCSTAT_HIDDEN int mcstat__chisq_tails(double x, double df, mcstat_tails *t);
MCSTAT_HIDDEN int mcstat__f_tails(double x, double df1, double df2, mcstat_tails *t);
/* log of mcstat_chisq_quantile / mcstat_f_quantile (p in [0, 1], arguments
 * valid), not clamped to the normal doubles: where the quantile itself is 0
 * or Inf in double its logarithm is still finite (-Inf, +Inf only for p at
 * 0 or 1).  Same solver and starting points, so within the normal range
 * exp(*z) is the public function's result. */
MCSTAT_HIDDEN int mcstat__chisq_log_quantile(double p, double df, int upper, double *z);
MCSTAT_HIDDEN int mcstat__f_log_quantile(double p, double df1, double df2, int upper, double *z);

/* ---- moments (moments.c) ------------------------------------------------ */
/* The variance as v * 2^(2*e) with v finite: *v = m2/(n-1) in scaled units. */
/* The scale exponent an accumulator holding values up to amax in magnitude has. */
MCSTAT_HIDDEN int mcstat__moments_scale_for(double amax);
MCSTAT_HIDDEN void mcstat__moments_var_scaled(const mcstat_moments *m, double *v, int *e);
MCSTAT_HIDDEN mcstat_dd mcstat__moments_mean_dd(const mcstat_moments *m);
/* MCSTAT_ETOOFEW / MCSTAT_EDEGENERATE / MCSTAT_EINVAL checks of a sample. */
MCSTAT_HIDDEN int mcstat__moments_check(const mcstat_moments *m);

/* ---- results (result.c) -------------------------------------------------- */
/* Fills p_value, critical[], reject, decision from the statistic's tails.
 * `quantile(p, upper, ctx, &x)` inverts the null distribution. */
typedef int (*mcstat_quantile_fn)(double p, int upper, const void *ctx, double *x);
MCSTAT_HIDDEN int mcstat__finish(mcstat_result *r, const mcstat_tails *tails,
                                 mcstat_quantile_fn quantile, const void *ctx);
MCSTAT_HIDDEN void mcstat__result_clear(mcstat_result *r);
/* ---- options structs that grow (options.c) --------------------------------
 * known[0..n_known) are the sizes of every released version of a struct
 * (MCSTAT_*_OPTIONS_SIZE_*), the last its current sizeof.
 * _read: *dst holds the defaults (dst_size bytes, the current struct); the
 *   caller's struct src (starting with its uint32_t size) is copied over its
 *   first `size` bytes, so fields src's version lacks keep their defaults;
 *   dst's size field is then the caller's.  MCSTAT_EINVAL (nothing copied)
 *   for src NULL or a size not in known.
 * _init: writes the first `size` bytes of `defaults` (a current struct) to
 *   dst, with size in its size field; MCSTAT_EINVAL for an unknown size. */
MCSTAT_HIDDEN int mcstat__options_size_known(size_t size, const uint32_t *known, size_t n_known);
MCSTAT_HIDDEN int mcstat__options_read(void *dst, size_t dst_size, const void *src, const uint32_t *known,
                                       size_t n_known);
MCSTAT_HIDDEN int mcstat__options_init(void *dst, size_t size, const void *defaults, size_t defaults_size,
                                       const uint32_t *known, size_t n_known);
/* *r <- the caller's power options o read as above (power.c); used by
 * format.c too.  MCSTAT_EINVAL for NULL or an unknown size. */
MCSTAT_HIDDEN int mcstat__power_options_read(const mcstat_power_options *o, mcstat_power_options *r);


/* ---- quantile reuse (t_test.c, var_test.c, batch.c) -----------------------
 * The critical values depend only on alpha, the alternative and the degrees
 * of freedom, so rows of equal sizes share them.  A cache holds the last two
 * quantiles of one distribution; mcstat__qcache_quantile is a
 * mcstat_quantile_fn over it.  Results are bit for bit those of a fresh
 * solve (the solvers are deterministic; the t is symmetric bit for bit). */
enum { MCSTAT_Q_T = 1, MCSTAT_Q_CHISQ = 2, MCSTAT_Q_F = 3 };
typedef struct {
    int kind, n, next;
    double df1, df2;
    struct { double p, x; int upper; } e[2];
} mcstat_qcache;
MCSTAT_HIDDEN void mcstat__qcache_init(mcstat_qcache *c);
/* Selects the distribution; forgets the entries when it changed. */
MCSTAT_HIDDEN void mcstat__qcache_use(mcstat_qcache *c, int kind, double df1, double df2);
MCSTAT_HIDDEN int mcstat__qcache_quantile(double p, int upper, const void *ctx, double *x);

/* The tests on accumulators with a caller's cache; qc == NULL skips the
 * critical values and the confidence interval (left NaN). */
MCSTAT_HIDDEN int mcstat__t_test_1(const mcstat_moments *x, double mu0, int alternative, double alpha,
                                   mcstat_qcache *qc, mcstat_result *out);
MCSTAT_HIDDEN int mcstat__t_test_2(const mcstat_moments *x, const mcstat_moments *y, double mu0,
                                   int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out);
MCSTAT_HIDDEN int mcstat__var_test_1(const mcstat_moments *x, double sigma2, int alternative, double alpha,
                                     mcstat_qcache *qc, mcstat_result *out);
MCSTAT_HIDDEN int mcstat__var_test_2(const mcstat_moments *x, const mcstat_moments *y, double ratio,
                                     int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out);


/* ---- sorting (sort.c) ------------------------------------------------------
 * Doubles as order-preserving unsigned keys (NaN excluded, -0 made +0 so
 * that equal values have equal keys), sorted by an LSD radix sort. */
static inline uint64_t mcstat__order_key(double x)
{
    uint64_t k;
    x = x == 0.0 ? 0.0 : x;
    memcpy(&k, &x, sizeof k);
    return (k >> 63) ? ~k : k | 0x8000000000000000ull;
}
static inline double mcstat__key_double(uint64_t k)
{
    k = (k >> 63) ? k & 0x7fffffffffffffffull : ~k;
    double x;
    memcpy(&x, &k, sizeof x);
    return x;
}
/* Sorts a[0..n) ascending; tmp has room for n keys.  MCSTAT_ENOMEM. */
MCSTAT_HIDDEN int mcstat__radix_sort_u64(uint64_t *a, size_t n, uint64_t *tmp);
/* keys[0..n) <- the order keys of x, sorted; tmp has room for n keys.
 * MCSTAT_ENONFINITE (keys unspecified) if x holds a NaN. */
MCSTAT_HIDDEN int mcstat__sort_double_keys(const double *x, size_t n, uint64_t *keys, uint64_t *tmp);

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
 * TAUS2 GSL's taus2, scalar; XOSHIRO xoshiro256++, the AVX2 kernel where it
 * applies; XOSHIRO_SCALAR the same numbers by the scalar kernel. */
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
/* Jaeschke's (1979) limit for Canner's statistic (measured in bench/, not used). */
MCSTAT_HIDDEN double mcstat__ks_jaeschke_sf(double n, int two_sided, double d2);
/* Kolmogorov's limit P(K > t). */
MCSTAT_HIDDEN double mcstat__kolmogorov_sf(double t);

/* ---- noncentral t (noncentral.c, R's pnt from libRmath) ------------------
 * Both tails of the noncentral t at t (df > 0, finite ncp; t may be +-Inf);
 * never prints (see noncentral.c).  MCSTAT_EINVAL, MCSTAT_ENUMERIC. */
MCSTAT_HIDDEN int mcstat__nct_tails(double t, double df, double ncp, double *lower, double *upper);

#endif /* MCSTAT_INTERNAL_H */
