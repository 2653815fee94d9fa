/*
 * mcstat/gof.h - goodness of fit: chi-squared GOF, the exact binomial test
 * and the battery meta-test (experimental).
 *
 * Included by mcstat.h (unless MCSTAT_NO_EXPERIMENTAL); an experimental
 * family: define MCSTAT_EXPERIMENTAL before including it (base.h,
 * MCSTAT_EXPERIMENTAL_API).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_GOF_FAMILY_H
#define MCSTAT_GOF_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 13. Goodness of fit.                                    (experimental) */
/* Are counts consistent with expected probabilities?  Pearson's            */
/* chi-squared test of cell counts (mcstat_gof_*), and the exact binomial   */
/* test of a count, with the battery meta-test built on it: does a battery  */
/* of k tests reject more often than its level allows?                      */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Chi-squared goodness of fit (Pearson), mcstat_gof_*.                     */
/* Counts observed[i] of k cells against expected[i], given as probabilities */
/* (summing to 1) or as counts (summing to the total N = sum observed), both */
/* to within sqrt(DBL_EPSILON) relative as R's chisq.test requires, unless   */
/* rescale = 1 (expected is then scaled to the right total).                 */
/* Pooling (pool = 1, the default): walking the cells in the given order,    */
/* consecutive cells are pooled into one until its expected count N p        */
/* reaches min_expected (default 5, Cochran's rule); a short last group is   */
/* pooled into the group before it.  Order the cells so that neighbours in   */
/* the array are neighbours in space (mcest_brdf_cells does).  Cells of zero */
/* expectation are allowed only with pooling.  pool = 0 is R's chisq.test.   */
/*   X^2 = sum over pooled cells (O - E)^2 / E,                              */
/*   df  = (cells after pooling) - 1 - n_estimated,                          */
/* n_estimated the number of parameters of the expected probabilities that  */
/* were estimated from these counts.  p = P[chi^2(df) > X^2], the upper tail */
/* computed directly (relative error below 1.5e-13, and 5e-13 for p below  */
/* 1e-30 down to 1e-300: libmcstat/ACCURACY.md; log p below that).          */
/* Result: test MCSTAT_TEST_CHISQ_GOF, method MCSTAT_METHOD_ASYMPTOTIC (X^2 */
/* is chi^2 only asymptotically), alternative MCSTAT_GREATER, n[0] = N      */
/* (rounded), df[0]; critical[1] the upper alpha quantile of chi^2(df),      */
/* critical[0] = -Inf; reject = p <= alpha; decision +1 when rejected (the   */
/* counts stray further from expectation than chance allows), else 0.       */
/* conf_int, estimate, null_value, std_error are NaN.  Per-test fields:     */
/*   chisq_cells         cells after pooling                                 */
/*   chisq_n_estimated   n_estimated                                         */
/*   chisq_cells_given   k                                                   */
/*   chisq_min_expected  smallest expected count after pooling               */
/*   chisq_pool_below    min_expected, 0 when pooling was off                */
/* Statuses: MCSTAT_EINVAL (NULL, alpha outside (0,1), bad option, an        */
/* options size this library does not know, a negative count or            */
/* expectation, a zero expectation without pooling, sums that do not match */
/* without rescale, totals that overflow), MCSTAT_ENONFINITE (NaN or Inf   */
/* in either array),                                                         */
/* MCSTAT_ETOOFEW (k < 2, N = 0, or df < 1 after pooling).                   */
/* ------------------------------------------------------------------------ */
enum mcstat_gof_expected {
    MCSTAT_GOF_PROBABILITIES = 0, /* expected[i] are cell probabilities */
    MCSTAT_GOF_COUNTS = 1,        /* expected[i] are expected counts */
    MCSTAT_GOF_AUTO = 2           /* probabilities if they sum to 1, else counts
                                     (SciPy's chisquare takes counts, R's
                                     chisq.test probabilities) */
};

#define MCSTAT_GOF_DEFAULT_MIN_EXPECTED 5.0

/* Options; grows by appending fields ("Conventions", compatibility), so
 * always start from the initialiser. */
/* (The struct keeps 0.1.0's tag, mcstat_chisq_options, for the ABI.) */
typedef struct mcstat_gof_options {
    uint32_t size;        /* sizeof(mcstat_gof_options): set by the initialiser */
    int32_t expected;     /* enum mcstat_gof_expected; default PROBABILITIES */
    int32_t pool;         /* 1 (default): pool cells of low expectation (above); 0: never */
    int32_t rescale;      /* 1: scale expected to the right total; 0 (default): it must sum to it */
    double min_expected;  /* pooling threshold on expected counts, >= 0; default 5 */
    int32_t n_estimated;  /* parameters estimated from the counts, >= 0; default 0 */
    int32_t reserved;     /* zero */
} mcstat_gof_options;

#define MCSTAT_GOF_OPTIONS_INIT \
    {sizeof(mcstat_gof_options), MCSTAT_GOF_PROBABILITIES, 1, 0, \
     MCSTAT_GOF_DEFAULT_MIN_EXPECTED, 0, 0}

/* sizeof(mcstat_gof_options) in each release that changed it. */
#define MCSTAT_GOF_OPTIONS_SIZE_0_1 32u
/* Sets the first `size` bytes of *opt to MCSTAT_GOF_OPTIONS_INIT, with
 * opt->size = size: `size` is sizeof(mcstat_gof_options) as the caller
 * compiled it (FFI callers: their struct's size), so nothing beyond the
 * caller's struct is written.  MCSTAT_EINVAL (nothing written) for NULL or
 * a size no release had. */
MCSTAT_EXPERIMENTAL_API int mcstat_gof_options_init_size(mcstat_gof_options *opt, size_t size);
#define mcstat_gof_options_init(opt) mcstat_gof_options_init_size((opt), sizeof *(opt))
MCSTAT_EXPERIMENTAL_API size_t mcstat_sizeof_gof_options(void);
MCSTAT_EXPERIMENTAL_API double mcstat_gof_default_min_expected(void);

/* Pearson's test of observed[0..k) against expected[0..k) as above.  opt may
 * be NULL (the defaults). */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_gof_chisq_test(const double *observed, const double *expected, size_t k,
                                     const mcstat_gof_options *opt, double alpha, mcstat_result *out);

/* ------------------------------------------------------------------------ */
/* Exact binomial test and the battery meta-test.                            */
/* A battery of k tests at level `level` rejects about level * k times when  */
/* every null hypothesis holds; whether an observed count is consistent with */
/* that is R's binom.test of the count against level.  x successes in n     */
/* trials against P(success) = p, p in [0, 1]:                               */
/*   LESS       p-value P[X <= x];  GREATER  P[X >= x];                       */
/*   TWO_SIDED  R's rule: the sum of P[X = i] over every i with P[X = i] <=   */
/*              P[X = x] (1 + 1e-7); 1 when x == n p.                        */
/* Tails come from the library's incomplete beta (p-values to 3e-14        */
/* relative for n <= 2000 and p >= 1e-30, libmcstat/ACCURACY.md) down to   */
/* the smallest normal double and, in log scale, far below it; the          */
/* densities are compared in log scale (R's dbinom underflows).             */
/* Result fields: statistic = x, estimate[0] = x/n, null_value = p, n[0] =   */
/* n, method EXACT, conf_int the Clopper-Pearson interval at level 1-alpha  */
/* (one-sided for one-sided alternatives, as R), critical = the acceptance  */
/* region of counts [critical[0], critical[1]] (reject iff x < critical[0]  */
/* or x > critical[1]; -Inf / +Inf for the open side), decision the sign of */
/* x - n p when rejected; df and std_error NaN.  Per-test field:           */
/*   binom_log_p_value  log(p_value), finite where p_value underflows to 0   */
/* Statuses: MCSTAT_EINVAL (out NULL, bad enum, alpha outside (0,1), p      */
/* outside [0,1] or NaN, x > n), MCSTAT_ETOOFEW (n == 0), MCSTAT_ETOOBIG     */
/* (n > 2^53), MCSTAT_ENUMERIC.  Cost: O(log^2 n) incomplete-beta and       */
/* density evaluations (the critical counts are bisections).                */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_binom_test(uint64_t x, uint64_t n, double p, int alternative, double alpha,
                                 mcstat_result *out);
/* The battery meta-test: `rejections` among k tests each at level `level`
 * in (0, 1), tested against the rate `level` (mcstat_binom_test(rejections,
 * k, level, ...)); reject == 1 means the count is not consistent with the
 * level (GREATER: too many rejections, the usual question).  Statuses as
 * mcstat_binom_test, plus MCSTAT_EINVAL for level outside (0, 1). */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_battery_test(uint64_t rejections, uint64_t k, double level, int alternative,
                                   double alpha, mcstat_result *out);
/* The same from the battery's k p-values: a test rejects when its p-value
 * is <= level.  MCSTAT_ENONFINITE for a NaN p-value, MCSTAT_EINVAL for one
 * outside [0, 1] (or p_values NULL with k > 0), MCSTAT_ETOOFEW for k == 0. */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_battery_test_pvalues(const double *p_values, size_t k, double level, int alternative,
                                           double alpha, mcstat_result *out);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_GOF_FAMILY_H */
