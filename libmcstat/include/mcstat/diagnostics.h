/*
 * mcstat/diagnostics.h - estimator diagnostics, mcstat_diag_* (experimental).
 *
 * Included by mcstat.h (unless MCSTAT_NO_EXPERIMENTAL); an experimental
 * family: define MCSTAT_EXPERIMENTAL before including it (base.h,
 * MCSTAT_EXPERIMENTAL_API).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_DIAGNOSTICS_FAMILY_H
#define MCSTAT_DIAGNOSTICS_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* 12. Estimator diagnostics, mcstat_diag_*.               (experimental) */
/* Before testing, look at the primary estimates themselves:                 */
/*   shape   skewness g1 and excess kurtosis g2 (mcstat_moments) with their  */
/*           standard errors under normality;                               */
/*   tails   Hill's tail index of each tail, from the tail_k largest        */
/*           excesses over the median (default max(10, min(4 sqrt(n),       */
/*           n/25)); fewer when fewer values lie beyond the median, as for  */
/*           an estimator that is mostly 0): P[X > t] ~ t^-index, the       */
/*           variance is infinite when index <= 2 ("fireflies": rare huge   */
/*           estimates that the sample variance misses until one arrives). */
/*           heavy_tail = 1 when the smaller index is below tail_threshold  */
/*           (default 2.2: index-2 tails scatter about 2).  Measured        */
/*           (tools/refgen/diagnose_rates.py; 200 samples each at n = 1e3 */
/*           / 1e4): flagged U^-1/2 (index 2) 99.5% / 100%, Pareto 1.5 and  */
/*           Cauchy 100% / 100%, t_2 95.5% / 100%, 99% zeros + 1% U^-1/2     */
/*           (10 or 100 nonzero values) 22% / 81.5%; false alarms: uniform,  */
/*           normal, exponential, t_5 0 / 0, gamma(1/2) 0.5% / 0, the paper's */
/*           irradiance estimators U, C, A, S 0 / 0, reflected radiance off */
/*           Ward's and Ashikhmin-Shirley's BRDFs (sampling and rejection,   */
/*           3 outgoing directions) at most 4% / 0.  Tails in between       */
/*           (lognormal(0,1) 55% / 66%, Pareto 3 70% / 98.5%: finite         */
/*           variance, infinite or huge fourth moment) are flagged often:   */
/*           their variance estimates are unreliable too.                   */
/*   batch   the batch size k that makes the two-sided t test at alpha on m */
/*           batch means of k primaries keep its level: the smallest k with */
/*           each tail's rejection rate, by Hall's Edgeworth expansion of   */
/*           the Studentized mean (see diagnose.c), within tolerance *      */
/*           alpha/2 of alpha/2.  The rate's error falls like 1/sqrt(k m), */
/*           so it is m, the number of secondary estimates the test sees,   */
/*           that fixes k.  The rule uses the sample skewness and kurtosis, */
/*           which understate heavy tails: trust it only without heavy_tail.*/
/* ------------------------------------------------------------------------ */
#define MCSTAT_DIAG_DEFAULT_M 30u /* batch means when neither k nor m is given */

/* Options; grows by appending fields ("Conventions", compatibility), so
 * always start from the initialiser. */
typedef struct mcstat_diag_options {
    uint32_t size;         /* sizeof(mcstat_diag_options): set by the initialiser */
    int32_t reserved_i;    /* zero */
    uint64_t k;            /* the batch size in use (0: none; t_size is then for k = 1) */
    uint64_t m;            /* batch means the t test sees (0: n / k, or MCSTAT_DIAG_DEFAULT_M without k) */
    uint64_t tail_k;       /* order statistics per tail in Hill's estimate (0: max(10, min(4 sqrt(n), n/25))) */
    double alpha;          /* the t test's level; default 0.05 */
    double tolerance;      /* allowed relative error of each tail's rate, in (0, 1); default 0.2 */
    double tail_threshold; /* heavy_tail when a tail index is below this (> 0); default 2.2 */
    double reserved[4];    /* zero */
} mcstat_diag_options;

#define MCSTAT_DIAG_OPTIONS_INIT \
    {sizeof(mcstat_diag_options), 0, 0u, 0u, 0u, 0.05, 0.2, 2.2, {0.0, 0.0, 0.0, 0.0}}

typedef struct mcstat_diagnostics {
    uint64_t n;              /* primary estimates */
    uint64_t tail_k;         /* order statistics per tail asked for (see tail_index_se) */
    uint64_t k, m;           /* batch size and number of batch means t_size is for */
    uint64_t recommended_k;  /* the batch size rule's k for m batch means */
    int32_t heavy_tail;      /* 1: a tail index is below tail_threshold */
    int32_t reserved_i;
    double mean, sd;
    double skewness, skewness_se;  /* g1 and sqrt(6n(n-1)/((n-2)(n+1)(n+3))) */
    double kurtosis, kurtosis_se;  /* excess g2 and its standard error under normality */
    double tail_index[2];    /* Hill: [0] lower tail, [1] upper tail (+Inf: no Pareto tail) */
    double tail_index_se[2]; /* index / sqrt(k) with the k actually used (NaN: none) */
    double max_share;        /* max_i (x_i - mean)^2 / sum_i (x_i - mean)^2 */
    double t_size[2];        /* predicted rejection rates of the lower / upper tail of the
                                two-sided t test at alpha on m batch means of k (alpha/2 each
                                when the batch means are normal) */
    double alpha, tolerance; /* as used */
    double reserved[4];
} mcstat_diagnostics;

/* sizeof(mcstat_diag_options) in each release that changed it. */
#define MCSTAT_DIAG_OPTIONS_SIZE_0_1 88u
/* Sets the first `size` bytes of *opt to MCSTAT_DIAG_OPTIONS_INIT, with
 * opt->size = size: `size` is sizeof(mcstat_diag_options) as the caller
 * compiled it (FFI callers: their struct's size), so nothing beyond the
 * caller's struct is written.  MCSTAT_EINVAL (nothing written) for NULL or
 * a size no release had. */
MCSTAT_EXPERIMENTAL_API int mcstat_diag_options_init_size(mcstat_diag_options *opt, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_DIAG_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_diag_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_EXPERIMENTAL_API int(mcstat_diag_options_init)(mcstat_diag_options *opt);
#define mcstat_diag_options_init(opt) mcstat_diag_options_init_size((opt), sizeof *(opt))
MCSTAT_EXPERIMENTAL_API size_t mcstat_sizeof_diag_options(void);
MCSTAT_EXPERIMENTAL_API size_t mcstat_sizeof_diagnostics(void);

/* All diagnostics of n primary estimates x; opt may be NULL (defaults).
 * Allocates 16 n bytes (a radix sort: ~0.15 s per 1e6 values).  Statuses:
 * MCSTAT_EINVAL (NULL x or out, an options size this library does not know,
 * alpha outside (0,1),
 * tolerance outside (0,1), tail_threshold <= 0, k > n), MCSTAT_ETOOFEW
 * (n < 8, n < 2 tail_k + 2, or fewer than 2 batch means), MCSTAT_ENONFINITE,
 * MCSTAT_EDEGENERATE (constant data), MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_diag_compute(const double *x, size_t n, const mcstat_diag_options *opt,
                                   mcstat_diagnostics *out);
/* Hill's tail index of each tail (index[0] lower, index[1] upper) from
 * tail_k order statistics (0: the default), as above.  Statuses:
 * MCSTAT_EINVAL, MCSTAT_ETOOFEW (n < 2 tail_k + 2), MCSTAT_ENONFINITE,
 * MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_diag_tail_index(const double *x, size_t n, size_t tail_k, double index[2]);
/* The Edgeworth-predicted rejection rates size[0] (lower tail: "less") and
 * size[1] (upper: "greater") of the two-sided t test at alpha on m batch
 * means of k values whose skewness and excess kurtosis are given.
 * MCSTAT_EINVAL (non-finite shape, kurtosis < -2, alpha, k == 0),
 * MCSTAT_ETOOFEW (m < 2). */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_diag_t_size(double skewness, double kurtosis, uint64_t k, uint64_t m, double alpha,
                                  double size[2]);
/* The batch size rule: the smallest k whose predicted tail rates are within
 * tolerance * alpha/2 of alpha/2 for m batch means.  MCSTAT_EINVAL,
 * MCSTAT_ETOOFEW (m < 2), MCSTAT_ETOOBIG (k beyond 2^53). */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_diag_batch_size(double skewness, double kurtosis, uint64_t m, double alpha,
                                      double tolerance, uint64_t *k);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_DIAGNOSTICS_FAMILY_H */
