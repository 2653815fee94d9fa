/*
 * mcstat.h - statistical hypothesis tests for Monte Carlo estimators.
 *
 * The tests of Subr & Arvo, "Statistical Hypothesis Testing for Assessing
 * Monte Carlo Estimators": one-sample t (mean vs mu0), one-sample chi-squared
 * (variance vs sigma0^2), Welch's two-sample t, and the two-sample F test,
 * on arrays or on streaming, mergeable accumulators.
 *
 * Conventions, for every function in this header:
 *   - Fallible calls return an int status: MCSTAT_OK (0) or one of the
 *     MCSTAT_E* codes below; mcstat_strerror() gives a sentence for it.
 *     Outputs are written through the pointer given last, and only on success.
 *   - Nothing here calls abort() or exit(), nothing touches GSL's process-wide
 *     error handler (see mcstat_gsl_handler_off), there is no global state:
 *     every function is thread-safe on distinct objects.
 *   - No function allocates on the accumulator path.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_H
#define MCSTAT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32) && defined(MCSTAT_SHARED_BUILD)
#  define MCSTAT_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_API __attribute__((visibility("default")))
#else
#  define MCSTAT_API
#endif

/* ------------------------------------------------------------------------ */
/* Versions.                                                                 */
/* The release number (MAJOR.MINOR.PATCH) is separate from the shared        */
/* library's SOVERSION, which changes only when the ABI breaks.              */
/* ------------------------------------------------------------------------ */
#define MCSTAT_VERSION_MAJOR 0
#define MCSTAT_VERSION_MINOR 1
#define MCSTAT_VERSION_PATCH 0
#define MCSTAT_VERSION_NUMBER \
    (MCSTAT_VERSION_MAJOR * 10000 + MCSTAT_VERSION_MINOR * 100 + MCSTAT_VERSION_PATCH)

/* MCSTAT_VERSION_NUMBER of the library actually linked. */
MCSTAT_API unsigned mcstat_version_number(void);
/* "MAJOR.MINOR.PATCH" of the library actually linked (static storage). */
MCSTAT_API const char *mcstat_version(void);

/* ------------------------------------------------------------------------ */
/* Status codes.                                                             */
/* ------------------------------------------------------------------------ */
enum mcstat_status {
    MCSTAT_OK = 0,
    MCSTAT_EINVAL = 1,      /* invalid argument: NULL, bad enum, alpha outside (0,1), ... */
    MCSTAT_ETOOFEW = 2,     /* too few observations (fewer than 2 per sample) */
    MCSTAT_ENONFINITE = 3,  /* the data contain NaN or +-Inf */
    MCSTAT_EDEGENERATE = 4, /* the data have (essentially) zero spread */
    MCSTAT_ENOMEM = 5,      /* out of memory */
    MCSTAT_ENUMERIC = 6,    /* a numerical method failed to converge */
    MCSTAT_EBUFSIZE = 7,    /* the caller's buffer is too small */
    MCSTAT_ECORRUPT = 8,    /* serialized bytes are corrupt, truncated or of an unknown version */
    MCSTAT_ETOOBIG = 9      /* the sizes are too large for the requested method (e.g. an exact
                               K-S p-value whose lattice would not fit): choose another method */
};

/* A sentence describing status (static storage; never NULL). */
MCSTAT_API const char *mcstat_strerror(int status);

/* ------------------------------------------------------------------------ */
/* Alternatives and tails.                                                   */
/* An alternative is a claim about the first sample: MCSTAT_LESS means       */
/* mean(x) < mu0 (or mean(x) < mean(y), var(x) < sigma0^2, var(x)/var(y) <   */
/* ratio).  Values match across versions; FFI callers may use the integers. */
/* ------------------------------------------------------------------------ */
enum mcstat_alternative {
    MCSTAT_TWO_SIDED = 0,
    MCSTAT_LESS = 1,
    MCSTAT_GREATER = 2
};

/* Parses "two-sided" (also "two.sided", "two_sided"), "less", "greater". */
MCSTAT_API int mcstat_alternative_parse(const char *name, int *alternative);
/* "two-sided", "less", "greater", or NULL for an invalid value. */
MCSTAT_API const char *mcstat_alternative_name(int alternative);

/* ------------------------------------------------------------------------ */
/* Streaming moments.                                                        */
/* A fixed-size plain struct the caller owns (128 bytes): count, mean, the   */
/* second to fourth central sums, min and max.  Data are added one value or  */
/* one array at a time; two accumulators merge exactly (Chan et al., Pebay), */
/* so per-thread accumulators can be combined at the end of a frame.         */
/*                                                                           */
/* Accuracy: arrays are processed in cache-sized blocks, two passes each     */
/* (shifted sums), blocks merged in a pairwise tree.  The mean is kept as a  */
/* double-double (mean + mean_lo), so data like 1e9 + 1e-3 noise keep their  */
/* digits in differences of means.  Central sums are stored divided by a     */
/* power of two (m2 = M2 / 2^(2*scale), m3 = M3 / 2^(3*scale), m4 likewise)  */
/* so that data near 1e+-300 neither overflow nor underflow; use the         */
/* accessors below rather than the raw fields.                               */
/* ------------------------------------------------------------------------ */
typedef struct mcstat_moments {
    uint64_t n;        /* number of observations */
    int32_t scale;     /* binary exponent of the central sums (see above) */
    uint32_t version;  /* MCSTAT_MOMENTS_VERSION once initialised */
    double mean;       /* the mean, rounded to double */
    double mean_lo;    /* mean + mean_lo is the mean to about 32 digits */
    double m2;         /* sum (x - mean)^2, divided by 2^(2*scale) */
    double m3;         /* sum (x - mean)^3, divided by 2^(3*scale) */
    double m4;         /* sum (x - mean)^4, divided by 2^(4*scale) */
    double min;        /* smallest value added (+Inf when n == 0) */
    double max;        /* largest value added (-Inf when n == 0) */
    double reserved[7];/* zero; room to grow without changing the size */
} mcstat_moments;

#define MCSTAT_MOMENTS_VERSION 1u
/* Size of the serialized form written by mcstat_moments_to_bytes. */
#define MCSTAT_MOMENTS_BYTES 96u

/* Empties m. */
MCSTAT_API int mcstat_moments_init(mcstat_moments *m);
/* Adds one value. MCSTAT_ENONFINITE (m unchanged) for NaN or +-Inf. */
MCSTAT_API int mcstat_moments_add(mcstat_moments *m, double x);
/* Adds n values. MCSTAT_ENONFINITE (m unchanged) if any is NaN or +-Inf. */
MCSTAT_API int mcstat_moments_add_array(mcstat_moments *m, const double *x, size_t n);
/* Like mcstat_moments_add_array, but NaN values are skipped (+-Inf is still
 * an error).  *n_omitted (may be NULL) receives the number skipped. */
MCSTAT_API int mcstat_moments_add_array_omit_nan(mcstat_moments *m, const double *x,
                                                 size_t n, size_t *n_omitted);
/* dst <- dst merged with src (src may equal dst). */
MCSTAT_API int mcstat_moments_merge(mcstat_moments *dst, const mcstat_moments *src);

/* Derived quantities; each returns NaN when undefined (e.g. n < 2). */
MCSTAT_API double mcstat_moments_mean(const mcstat_moments *m);
MCSTAT_API double mcstat_moments_var(const mcstat_moments *m);      /* M2/(n-1); may overflow to Inf */
MCSTAT_API double mcstat_moments_sd(const mcstat_moments *m);       /* sqrt(var), computed without overflow */
MCSTAT_API double mcstat_moments_skewness(const mcstat_moments *m); /* g1 = sqrt(n) M3 / M2^1.5 */
MCSTAT_API double mcstat_moments_kurtosis(const mcstat_moments *m); /* excess g2 = n M4 / M2^2 - 3 */

/* Versioned, little-endian serialization (MCSTAT_MOMENTS_BYTES bytes, with a
 * magic number and a checksum).  from_bytes returns MCSTAT_ECORRUPT for bytes
 * that are truncated, corrupt, of another version or internally inconsistent. */
MCSTAT_API int mcstat_moments_to_bytes(const mcstat_moments *m, unsigned char *buf, size_t size);
MCSTAT_API int mcstat_moments_from_bytes(const unsigned char *buf, size_t size, mcstat_moments *m);

/* ------------------------------------------------------------------------ */
/* Test results.                                                             */
/* A plain struct filled by every test.  Fields that do not apply are NaN    */
/* (df[1] of a t test) or +-Inf (the open end of a one-sided confidence      */
/* interval or the missing critical value of a one-sided test).              */
/* ------------------------------------------------------------------------ */
enum mcstat_test {
    MCSTAT_TEST_T_1 = 1,   /* one-sample t */
    MCSTAT_TEST_T_2 = 2,   /* Welch two-sample t */
    MCSTAT_TEST_VAR_1 = 3, /* one-sample chi-squared test on the variance */
    MCSTAT_TEST_VAR_2 = 4, /* two-sample F test on the ratio of variances */
    MCSTAT_TEST_KS_2 = 5   /* two-sample Kolmogorov-Smirnov, unweighted or with Canner's weight */
};

enum mcstat_method {
    MCSTAT_METHOD_ANALYTIC = 0,  /* p-value from the statistic's exact null distribution (t, chi^2, F) */
    MCSTAT_METHOD_AUTO = 1,      /* (K-S option only) let the test choose; results never carry it */
    MCSTAT_METHOD_EXACT = 2,     /* exact permutation distribution (K-S: lattice paths) */
    MCSTAT_METHOD_SIMULATE = 3,  /* Monte Carlo: p_value_se > 0 */
    MCSTAT_METHOD_ASYMPTOTIC = 4 /* a large-sample approximation */
};

typedef struct mcstat_result {
    int32_t test;          /* enum mcstat_test */
    int32_t method;        /* enum mcstat_method: how the p-value was obtained */
    int32_t alternative;   /* enum mcstat_alternative */
    int32_t reject;        /* 1 if H0 is rejected at level alpha against `alternative` */
    int32_t decision;      /* the paper's three-way outcome: -1 less, 0 equal, +1 greater */
    int32_t reserved_i[3];
    uint64_t n[2];         /* sample sizes (n[1] = 0 for one-sample tests) */
    double statistic;      /* t, X-squared or F */
    double df[2];          /* degrees of freedom (df[1] NaN unless F) */
    double p_value;        /* for `alternative` */
    double p_value_se;     /* Monte Carlo standard error of p_value; 0 when exact */
    double conf_int[2];    /* (1 - alpha) confidence interval for the tested parameter */
    double estimate[2];    /* mean of x (,mean of y); variance of x; ratio of variances */
    double null_value;     /* mu0, mu0 (difference), sigma0^2 or ratio under H0 */
    double alpha;          /* significance level used for reject/decision/critical/conf_int */
    double critical[2];    /* reject when statistic < critical[0] or > critical[1] */
    double std_error;      /* standard error of the estimate (t tests); NaN otherwise */
    double reserved[7];
} mcstat_result;

/* The decision rule (ERRATA 6): `reject` is the test against the chosen
 * alternative at level alpha; `decision` is 0 when H0 is not rejected, else
 * the sign of the estimate's deviation from the null value.  With the
 * two-sided alternative this is the paper's less / equal / greater outcome. */

/* Writes the R-style block (the layout and number formatting of R's
 * print.htest, plus a final "decision at alpha = ...: ..." line) into buf.
 * x_name and y_name name the data ("x" and "y" when NULL).  *length (may be
 * NULL) receives the length of the full text, without the terminating NUL;
 * MCSTAT_EBUFSIZE when it does not fit in size bytes (buf then holds a
 * NUL-terminated prefix). */
MCSTAT_API int mcstat_result_format(const mcstat_result *r, const char *x_name,
                                    const char *y_name, char *buf, size_t size,
                                    size_t *length);

/* "less", "equal" or "greater" for a decision value, NULL otherwise. */
MCSTAT_API const char *mcstat_decision_name(int decision);

/* ------------------------------------------------------------------------ */
/* The tests.                                                                */
/* Each comes on arrays and on accumulators.  Common arguments:              */
/*   alternative  enum mcstat_alternative                                    */
/*   alpha        significance level in (0, 1); conf_int has level 1-alpha   */
/* Statuses: MCSTAT_EINVAL (NULL pointer, bad enum, alpha or a null value    */
/* out of range or non-finite), MCSTAT_ETOOFEW (n < 2 in a sample),          */
/* MCSTAT_ENONFINITE (NaN/Inf in data), MCSTAT_EDEGENERATE (a sample is      */
/* constant to within rounding: its standard deviation is zero or below      */
/* 10*DBL_EPSILON*|mean|; Welch needs this of only one of its samples),      */
/* MCSTAT_ENUMERIC.  (R's t.test applies 10*eps*|mean| to the standard       */
/* error instead, which refuses large samples at large offsets.)             */
/* ------------------------------------------------------------------------ */

/* One-sample t test of mean(x) against mu0 (section 2.1, eq. 1). */
MCSTAT_API int mcstat_t_test_1(const double *x, size_t n, double mu0, int alternative,
                               double alpha, mcstat_result *out);
MCSTAT_API int mcstat_t_test_1_moments(const mcstat_moments *x, double mu0, int alternative,
                                       double alpha, mcstat_result *out);

/* Welch's two-sample t test of mean(x) - mean(y) against mu0 (section 2.3,
 * eq. 3, Welch-Satterthwaite degrees of freedom). */
MCSTAT_API int mcstat_t_test_2(const double *x, size_t nx, const double *y, size_t ny,
                               double mu0, int alternative, double alpha, mcstat_result *out);
MCSTAT_API int mcstat_t_test_2_moments(const mcstat_moments *x, const mcstat_moments *y,
                                       double mu0, int alternative, double alpha,
                                       mcstat_result *out);

/* One-sample chi-squared test of var(x) against sigma2 > 0: statistic
 * (n-1) s^2 / sigma2 on n-1 degrees of freedom (section 2.2, eq. 2). */
MCSTAT_API int mcstat_var_test_1(const double *x, size_t n, double sigma2, int alternative,
                                 double alpha, mcstat_result *out);
MCSTAT_API int mcstat_var_test_1_moments(const mcstat_moments *x, double sigma2,
                                         int alternative, double alpha, mcstat_result *out);

/* Two-sample F test of var(x)/var(y) against ratio > 0: statistic
 * (s_x^2 / s_y^2) / ratio on (nx-1, ny-1) degrees of freedom (section 2.4). */
MCSTAT_API int mcstat_var_test_2(const double *x, size_t nx, const double *y, size_t ny,
                                 double ratio, int alternative, double alpha,
                                 mcstat_result *out);
MCSTAT_API int mcstat_var_test_2_moments(const mcstat_moments *x, const mcstat_moments *y,
                                         double ratio, int alternative, double alpha,
                                         mcstat_result *out);

/* ------------------------------------------------------------------------ */
/* Two-sample Kolmogorov-Smirnov test (section 2.5, ERRATA 1-3, 7).          */
/* F and G are the empirical CDFs #{x_i <= t}/nx and #{y_j <= t}/ny, z =     */
/* (nx F + ny G)/(nx + ny) the pooled one.  They are compared at the pooled  */
/* jump points only, and where values are tied only after the last of a run */
/* of equal values.  The statistic is                                        */
/*   weight NONE:   D  = sup |F - G|                     (as R and SciPy)    */
/*   weight CANNER: D2 = sqrt(nx ny/(nx+ny)) sup |F - G| / sqrt(z (1 - z)),  */
/*                  the sup over jump points with 0 < z < 1.                 */
/* Alternatives are claims about the first sample, as for every mcstat test */
/* (ERRATA 4): MCSTAT_LESS = x tends to be smaller than y, i.e. its CDF lies */
/* above, sup (F - G); MCSTAT_GREATER = x tends to be larger, sup (G - F).   */
/* NOTE: R's ks.test and SciPy's ks_2samp name one-sided alternatives by the */
/* CDF, the other way round: mcstat's LESS is their "greater".  The printed */
/* block uses R's wording ("the CDF of x lies above that of y").  One-sided  */
/* statistics include the end point where F = G, so they are >= 0.          */
/* Under H0 only the order of the labels matters; p-values are conditional  */
/* on the tie pattern.  Methods:                                             */
/*   EXACT      the permutation distribution by a lattice-path recursion in */
/*              probability scale (O(nx ny) time at most, O(N^1.5) in        */
/*              practice, O(min(nx, ny)) memory),                            */
/*              exact integer comparisons, ties handled; relative error      */
/*              about 1e-13, absolute error below 1e-290.  MCSTAT_ETOOBIG    */
/*              when (min(nx,ny)+1)(nx+ny+1) > MCSTAT_KS_EXACT_MAX_WORK.     */
/*   SIMULATE   n_sim random label arrangements (over the fixed tie blocks): */
/*              p = (1 + #{D* >= D})/(n_sim + 1), p_value_se its Monte Carlo */
/*              standard error sqrt(p(1-p)/n_sim); bit-identical for any     */
/*              number of threads and with or without AVX2 (8 replicates    */
/*              per AVX2 kernel step: ~0.55 us per replicate at 1000 + 1000 */
/*              on 2 threads); optionally cached (mcstat_ks_cache).          */
/*   ASYMPTOTIC weight NONE only: Kolmogorov's limit at sqrt(ne) D (ne =    */
/*              nx ny/N), one-sided exp(-2 ne D^2); conservative, p within  */
/*              2% at 300+300 and beyond (bench/RESULTS_ks.md; Stephens'     */
/*              correction was measured and is anti-conservative here).      */
/*              Canner's statistic has no usable limit (ERRATA 3):           */
/*              MCSTAT_EINVAL.                                               */
/*   AUTO       EXACT when (min+1)(N+1) <= MCSTAT_KS_AUTO_EXACT_WORK, else   */
/*              SIMULATE (Canner, or NONE with ties) or ASYMPTOTIC (NONE     */
/*              without ties).                                               */
/* Result fields: statistic D or D2; critical[1] is the value above which H0 */
/* is rejected at alpha (reject == statistic > critical[1] == p <= alpha),   */
/* critical[0] = -Inf; decision is 0, or -1 ("less": x tends to be smaller, */
/* its CDF lies above where the (weighted) deviation is largest) or +1.  df, */
/* estimate, conf_int, null_value, std_error are NaN.  Reserved fields used: */
/*   MCSTAT_RESULT_KS_WEIGHT(r)     reserved_i[0]: enum mcstat_ks_weight     */
/*   MCSTAT_RESULT_CRITICAL_SE(r)   reserved[0]: Monte Carlo standard error  */
/*                                  of critical[1] (0 unless simulated)      */
/*   MCSTAT_RESULT_N_SIM(r)         reserved[1]: replicates simulated        */
/* ------------------------------------------------------------------------ */
enum mcstat_ks_weight {
    MCSTAT_KS_WEIGHT_NONE = 0,  /* the classical (Smirnov) statistic */
    MCSTAT_KS_WEIGHT_CANNER = 1 /* Canner's [z(1-z)]^(-1/2) (the paper's) */
};

#define MCSTAT_RESULT_KS_WEIGHT(r) ((r)->reserved_i[0])
#define MCSTAT_RESULT_CRITICAL_SE(r) ((r)->reserved[0])
#define MCSTAT_RESULT_N_SIM(r) ((r)->reserved[1])

/* Size limits of the exact method, in lattice cells (min(nx,ny)+1)(nx+ny+1).
 * The recursion only visits the band of points that the threshold has not
 * absorbed and whose probability is above 2^-1000, O(sqrt(N)) wide, so its
 * time grows like N^1.5: 0.16 ms for a Canner p-value at 1000 + 1000, 0.8 ms
 * at 4000 + 4000; the critical value (a search) costs 10-40 p-values
 * (bench/RESULTS_ks.md). */
#define MCSTAT_KS_EXACT_MAX_WORK 2e11  /* ~3.2e5 + 3.2e5, seconds: beyond, MCSTAT_ETOOBIG */
#define MCSTAT_KS_AUTO_EXACT_WORK 1.6e7 /* ~2800 + 2800: p-value ~0.5 ms, critical value ~20 ms */
#define MCSTAT_KS_DEFAULT_N_SIM 10000

/* A cache of simulated null distributions, owned by the caller and shared by
 * any number of threads (it has its own lock).  Entries are keyed by (nx, ny,
 * weight, alternative, n_sim, seed, tie pattern), so a battery of tests at
 * the same sizes simulates once.  When adding an entry would exceed
 * max_bytes, the least recently used entries are dropped. */
typedef struct mcstat_ks_cache mcstat_ks_cache;
/* MCSTAT_EINVAL (cache NULL), MCSTAT_ENOMEM. */
MCSTAT_API int mcstat_ks_cache_new(size_t max_bytes, mcstat_ks_cache **cache);
/* Frees the cache (NULL is a no-op); no test may be using it. */
MCSTAT_API void mcstat_ks_cache_free(mcstat_ks_cache *cache);
/* Lookups that found an entry, lookups that did not, entries held (any may be NULL). */
MCSTAT_API int mcstat_ks_cache_stats(const mcstat_ks_cache *cache, uint64_t *hits,
                                     uint64_t *misses, uint64_t *entries);

/* Options; grows by appending fields, so always start from the initialiser. */
typedef struct mcstat_ks_options {
    uint32_t size;          /* sizeof(mcstat_ks_options): set by the initialiser */
    int32_t weight;         /* enum mcstat_ks_weight; default CANNER */
    int32_t method;         /* MCSTAT_METHOD_AUTO (default), _EXACT, _SIMULATE, _ASYMPTOTIC */
    int32_t threads;        /* simulation threads, 1..64; default 2 */
    int64_t n_sim;          /* replicates when simulating, >= 1; default 10000 */
    uint64_t seed;          /* simulation seed; default 0 */
    mcstat_ks_cache *cache; /* simulated distributions to reuse; NULL: none */
    int32_t critical;       /* 1: compute critical[1] (exact: a search costing 10-40
                               p-value computations); 0: leave it NaN; default 1 */
    int32_t reserved;       /* zero */
} mcstat_ks_options;

#define MCSTAT_KS_OPTIONS_INIT \
    {sizeof(mcstat_ks_options), MCSTAT_KS_WEIGHT_CANNER, MCSTAT_METHOD_AUTO, 2, \
     MCSTAT_KS_DEFAULT_N_SIM, 0u, NULL, 1, 0}

/* Sets *opt to MCSTAT_KS_OPTIONS_INIT (for callers that cannot use macros). */
MCSTAT_API int mcstat_ks_options_init(mcstat_ks_options *opt);
MCSTAT_API size_t mcstat_sizeof_ks_options(void);

/* The two-sample K-S test of x against y.  opt may be NULL (the defaults).
 * Statuses: MCSTAT_EINVAL (NULL data or out, bad enum, alpha outside (0,1),
 * n_sim < 1, threads outside 1..64, an options size this library does not
 * know, ASYMPTOTIC with Canner's weight), MCSTAT_ETOOFEW (an empty sample),
 * MCSTAT_ENONFINITE (NaN in the data; +-Inf are ordinary, ordered values),
 * MCSTAT_ETOOBIG (nx*ny >= 2^62, or EXACT beyond MCSTAT_KS_EXACT_MAX_WORK),
 * MCSTAT_ENOMEM. */
MCSTAT_API int mcstat_ks_test_2(const double *x, size_t nx, const double *y, size_t ny,
                                int alternative, double alpha, const mcstat_ks_options *opt,
                                mcstat_result *out);

/* ------------------------------------------------------------------------ */
/* Distributions.                                                            */
/* Tail probabilities accurate to about 1e-13 relative down to the smallest  */
/* normal double, computed from whichever tail is small (never as 1 - P);    */
/* log versions stay finite where the probability underflows.  Quantiles     */
/* invert these by safeguarded Newton iteration, for any degrees of freedom  */
/* from 1e-3 to 1e12 or more.  `upper` selects the tail: 0 gives P[X <= x],  */
/* 1 gives P[X > x]; a quantile solves that tail's probability = p.          */
/* Statuses: MCSTAT_EINVAL for NaN or out-of-domain arguments,               */
/* MCSTAT_ENUMERIC if an iteration fails (not expected).                     */
/* ------------------------------------------------------------------------ */
MCSTAT_API int mcstat_t_cdf(double x, double df, int upper, double *p);
MCSTAT_API int mcstat_t_logcdf(double x, double df, int upper, double *logp);
MCSTAT_API int mcstat_t_quantile(double p, double df, int upper, double *x);
MCSTAT_API int mcstat_chisq_cdf(double x, double df, int upper, double *p);
MCSTAT_API int mcstat_chisq_logcdf(double x, double df, int upper, double *logp);
MCSTAT_API int mcstat_chisq_quantile(double p, double df, int upper, double *x);
MCSTAT_API int mcstat_f_cdf(double x, double df1, double df2, int upper, double *p);
MCSTAT_API int mcstat_f_logcdf(double x, double df1, double df2, int upper, double *logp);
MCSTAT_API int mcstat_f_quantile(double p, double df1, double df2, int upper, double *x);

/* ------------------------------------------------------------------------ */
/* Sizes and constants as functions, for FFI callers that cannot read       */
/* macros or sizeof.                                                         */
/* ------------------------------------------------------------------------ */
MCSTAT_API size_t mcstat_sizeof_moments(void);
MCSTAT_API size_t mcstat_sizeof_result(void);
MCSTAT_API size_t mcstat_moments_bytes(void);

/* ------------------------------------------------------------------------ */
/* GSL's error handler.                                                      */
/* GSL's default handler aborts the process.  mcstat validates every         */
/* argument before calling GSL, so the handler is never reached through      */
/* mcstat, and mcstat never changes it: it is one global shared by every     */
/* library in the process.  A program that wants GSL's own calls to return   */
/* error codes instead of aborting may opt in here.                          */
/* ------------------------------------------------------------------------ */
/* Turns GSL's error handler off (gsl_set_error_handler_off). */
MCSTAT_API void mcstat_gsl_handler_off(void);
/* Turns it off only if no handler has been installed (GSL's default is in
 * force); returns 1 if it did so, 0 if a caller's handler was left alone. */
MCSTAT_API int mcstat_gsl_handler_off_if_default(void);

/* ------------------------------------------------------------------------ */
/* Row-wise tests: the per-pixel case.                                       */
/* One test per row of a matrix (an image whose every pixel holds k          */
/* secondary estimates): row i of x starts at x + i * x_stride (strides in   */
/* elements) and holds n contiguous values; row i of y pairs with row i of   */
/* x.  out[i] receives row i's result, bit for bit what the single-sample    */
/* call on that row returns, and status[i] (may be NULL) its status; a row   */
/* that fails gets NaN fields and the other rows are still computed.         */
/* Critical values are solved once for rows of equal degrees of freedom.     */
/* flags: MCSTAT_ROWS_NO_INTERVALS skips critical values and confidence      */
/* intervals (left NaN; p-value, reject and decision remain): the cheap path */
/* when only the decision map is wanted.  MCSTAT_ROWS_OMIT_NAN skips NaN     */
/* values in each row (+-Inf remains an error).                              */
/* Returns MCSTAT_OK when every row succeeded, else the status of the first  */
/* row that failed; MCSTAT_EINVAL (nothing written) for NULL pointers or     */
/* unknown flags.  No allocation; disjoint row ranges may run on different   */
/* threads (out + start, status + start).                                    */
/* ------------------------------------------------------------------------ */
#define MCSTAT_ROWS_NO_INTERVALS 1u
#define MCSTAT_ROWS_OMIT_NAN 2u

MCSTAT_API int mcstat_t_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride, double mu0,
                                    int alternative, double alpha, unsigned flags, mcstat_result *out,
                                    int32_t *status);
MCSTAT_API int mcstat_t_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y,
                                    size_t ny, size_t y_stride, size_t rows, double mu0, int alternative,
                                    double alpha, unsigned flags, mcstat_result *out, int32_t *status);
MCSTAT_API int mcstat_var_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride,
                                      double sigma2, int alternative, double alpha, unsigned flags,
                                      mcstat_result *out, int32_t *status);
MCSTAT_API int mcstat_var_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y,
                                      size_t ny, size_t y_stride, size_t rows, double ratio,
                                      int alternative, double alpha, unsigned flags, mcstat_result *out,
                                      int32_t *status);


/* ------------------------------------------------------------------------ */
/* Multiple testing: adjusted p-values, as R's p.adjust.                     */
/* A per-pixel comparison makes millions of tests; at level alpha each, a    */
/* fraction alpha of the unchanged pixels is rejected by chance.  Adjusted   */
/* p-values compared with alpha control the family-wise error rate          */
/* (Bonferroni, Holm, Hochberg, Hommel) or the false discovery rate (BH:     */
/* Benjamini & Hochberg; BY: Benjamini & Yekutieli, valid under any          */
/* dependence).  The values are R's p.adjust's, to rounding: NaN entries are */
/* R's NA (they stay NaN, and n, the number of tests, counts the others);    */
/* with n <= 1 the p-values come back unchanged.  O(n log n) (Hommel too).   */
/* Values match across versions; FFI callers may use the integers.          */
/* ------------------------------------------------------------------------ */
enum mcstat_p_adjust_method {
    MCSTAT_P_ADJUST_NONE = 0,       /* unchanged */
    MCSTAT_P_ADJUST_BONFERRONI = 1, /* min(1, n p) */
    MCSTAT_P_ADJUST_HOLM = 2,       /* step-down Bonferroni (FWER, any dependence) */
    MCSTAT_P_ADJUST_HOCHBERG = 3,   /* step-up (FWER, independent or positively dependent tests) */
    MCSTAT_P_ADJUST_HOMMEL = 4,     /* Simes closed testing (FWER, as Hochberg; more powerful) */
    MCSTAT_P_ADJUST_BH = 5,         /* Benjamini-Hochberg (FDR, independent or positively dependent) */
    MCSTAT_P_ADJUST_BY = 6          /* Benjamini-Yekutieli (FDR, any dependence) */
};

/* Parses R's names: "none", "bonferroni", "holm", "hochberg", "hommel", "BH"
 * (also "bh", "fdr"), "BY" (also "by").  MCSTAT_EINVAL for anything else. */
MCSTAT_API int mcstat_p_adjust_method_parse(const char *name, int *method);
/* R's name of a method ("BH", "holm", ...), or NULL for an invalid value. */
MCSTAT_API const char *mcstat_p_adjust_method_name(int method);
/* *bytes <- the workspace mcstat_p_adjust needs for n p-values: 0 for none
 * and bonferroni, 32 n for holm, hochberg, BH and BY, 40 n for hommel (on
 * 64-bit machines).  MCSTAT_EINVAL (bad method, bytes NULL), MCSTAT_ETOOBIG
 * (the size does not fit in a size_t). */
MCSTAT_API int mcstat_p_adjust_work_size(size_t n, int method, size_t *bytes);
/* adjusted[0..n) <- the adjusted p[0..n) (adjusted may equal p: in place).
 * work: work_bytes of scratch aligned for double (mcstat_p_adjust_work_size),
 * or NULL, in which case the call allocates it with malloc and frees it
 * before returning.  Statuses: MCSTAT_EINVAL (p or adjusted NULL with n > 0,
 * a bad method, a p-value outside [0, 1] other than NaN, misaligned work;
 * nothing written), MCSTAT_EBUFSIZE (work_bytes too small), MCSTAT_ENOMEM
 * (work NULL and the allocation failed), MCSTAT_ETOOBIG. */
MCSTAT_API int mcstat_p_adjust(const double *p, size_t n, int method, void *work, size_t work_bytes,
                               double *adjusted);

/* ------------------------------------------------------------------------ */
/* Buffered per-thread accumulator: checks inside a renderer.                */
/* mcstat_moments_add merges one value exactly (double-double mean), which   */
/* costs tens of ns.  A renderer that checks its estimates in production    */
/* keeps one mcstat_stream per thread instead: a fixed-size plain struct of  */
/* MCSTAT_STREAM_BYTES (4096) bytes the caller owns, holding an             */
/* mcstat_moments and an inline buffer of MCSTAT_STREAM_CAPACITY doubles.   */
/* mcstat_stream_add (inline, below) stores the value and bumps a counter;   */
/* when the buffer is full it is flushed into the moments with               */
/* mcstat_moments_add_array, so the moments are exactly what add_array      */
/* gives on the same values (about 0.5 ns per value; bench/RESULTS_check.md)*/
/* No allocation, no lock, no global state: one stream per thread, merged   */
/* (mcstat_stream_merge) by one thread at the end of a frame, then checked. */
/* NaN and +-Inf values are not added: they are counted in n_nonfinite, and */
/* a check on a stream that has seen one returns MCSTAT_ENONFINITE.          */
/* mcstat_check.h wraps all this in macros that compile to nothing when     */
/* checks are off.                                                           */
/* ------------------------------------------------------------------------ */
#define MCSTAT_STREAM_VERSION 1u
#define MCSTAT_STREAM_BYTES 4096u
#define MCSTAT_STREAM_CAPACITY 492u /* (4096 - 128 - 32) / 8 */

typedef struct mcstat_stream {
    mcstat_moments moments;  /* every value flushed so far */
    uint32_t count;          /* values waiting in buf (< MCSTAT_STREAM_CAPACITY) */
    uint32_t version;        /* MCSTAT_STREAM_VERSION once initialised */
    uint64_t n_nonfinite;    /* NaN and +-Inf values seen (and left out) */
    uint64_t reserved[2];    /* zero */
    double buf[MCSTAT_STREAM_CAPACITY];
} mcstat_stream;

/* Empties s.  MCSTAT_EINVAL for NULL. */
MCSTAT_API int mcstat_stream_init(mcstat_stream *s);
/* Adds the buffered values to s->moments and empties the buffer (non-finite
 * values are counted in n_nonfinite instead).  MCSTAT_EINVAL for NULL or an
 * uninitialised stream. */
MCSTAT_API int mcstat_stream_flush(mcstat_stream *s);
/* dst <- dst merged with src: its moments, its buffered values and its
 * non-finite count; src is not modified (it may equal dst).  Merging a
 * thread's stream into a frame total and re-initialising the thread's
 * stream is the end-of-frame step.  MCSTAT_EINVAL. */
MCSTAT_API int mcstat_stream_merge(mcstat_stream *dst, const mcstat_stream *src);
/* *out <- the moments of every value s has seen (flushed or buffered),
 * without modifying s.  MCSTAT_EINVAL. */
MCSTAT_API int mcstat_stream_moments(const mcstat_stream *s, mcstat_moments *out);

/* Adds one value: a store and a counter in the common case, a flush once
 * every MCSTAT_STREAM_CAPACITY values.  s must have been initialised.  FFI
 * callers that cannot inline this may do the same through the struct. */
static inline void mcstat_stream_add(mcstat_stream *s, double x)
{
    s->buf[s->count] = x;
    if (++s->count == MCSTAT_STREAM_CAPACITY)
        (void)mcstat_stream_flush(s);
}

/* Check that the mean of the values is `reference` to within `tolerance`
 * (>= 0, finite), at level alpha, without storing the values.
 *   tolerance == 0: the two-sided one-sample t test of mean == reference.
 *   tolerance > 0: H0 |mean - reference| <= tolerance against H1 |mean -
 *   reference| > tolerance, as two one-sided t tests at alpha/2 each (mean >
 *   reference + tolerance, mean < reference - tolerance); *out is the one
 *   with the smaller p-value (its alpha field is alpha/2), so its R-style
 *   block names the bound that was crossed.  A tolerance covers a reference
 *   that is itself approximate, which enough samples would otherwise detect.
 * out->reject == 1 means the check failed.  Statuses as mcstat_t_test_1,
 * plus MCSTAT_ENONFINITE when the stream has seen a NaN or an infinity. */
MCSTAT_API int mcstat_stream_check_mean(const mcstat_stream *s, double reference, double tolerance,
                                        double alpha, mcstat_result *out);
/* Check that the variance of the values is below `bound` (> 0): the
 * one-sample chi-squared test of var == bound against var > bound at level
 * alpha; out->reject == 1 (the variance is significantly above the bound)
 * means the check failed.  Statuses as mcstat_var_test_1, plus
 * MCSTAT_ENONFINITE as above. */
MCSTAT_API int mcstat_stream_check_var(const mcstat_stream *s, double bound, double alpha,
                                       mcstat_result *out);
MCSTAT_API size_t mcstat_sizeof_stream(void);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_H */
