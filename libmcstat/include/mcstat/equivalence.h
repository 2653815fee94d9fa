/*
 * mcstat/equivalence.h - equivalence tests (TOST).
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_EQUIVALENCE_FAMILY_H
#define MCSTAT_EQUIVALENCE_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 6. Equivalence.                                                        */
/* Not "is it different?" but "is the difference below eps?": the TOST      */
/* fills an mcstat_result like those of "The tests and their result".       */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Equivalence: two one-sided tests (TOST, Schuirmann 1987).                 */
/* H0: the mean lies outside the bounds, mean <= mu0 + lower or mean >=      */
/* mu0 + upper (two-sample: the difference of means outside [lower, upper]); */
/* H1: it lies strictly inside.  Each bound is tested by a one-sided t test */
/* at level alpha (the one-sample t, or Welch's t with Welch-Satterthwaite  */
/* df); equivalence is shown when both reject, i.e. when the 1 - 2 alpha    */
/* confidence interval lies inside the bounds.  With lower = -eps, upper =  */
/* eps and mu0 the exact value, "equivalent" is the evidence that the       */
/* estimator's bias is smaller than eps in magnitude.                        */
/* Result fields: statistic and p_value are those of the one-sided test     */
/* with the larger p-value (the TOST p-value is max(p_lower, p_upper));      */
/* df[0] the t's degrees of freedom; conf_int the 1 - 2 alpha interval;      */
/* estimate, std_error, n as the t tests; null_value mu0 (0 for two         */
/* samples); alternative MCSTAT_TWO_SIDED (unused); critical[1] = t(1-alpha, */
/* df), critical[0] = -critical[1]: equivalent when t_lower > critical[1]   */
/* and t_upper < critical[0].  reject == 1 means EQUIVALENT (H0 of a        */
/* difference at least as large as the bounds is rejected); decision is 0   */
/* then, else -1 when the lower bound's test is the one that failed (the   */
/* mean may lie at or below the lower bound), +1 when the upper bound's did. */
/* Per-test fields:                                                          */
/*   tost_t_lower, tost_t_upper  t for H1: mean > lower bound, mean < upper  */
/*   tost_p_lower, tost_p_upper  their one-sided p-values                    */
/*   tost_lower, tost_upper      the bounds: mu0 + lower and mu0 + upper (or */
/*                               lower, upper)                               */
/* mcstat_result_format prints both one-sided tests and "equivalent" or     */
/* "not equivalent" as the decision.                                         */
/* Statuses: MCSTAT_EINVAL (NULL, alpha outside (0, 0.5), bounds not finite */
/* or lower >= upper, mu0 not finite), then those of mcstat_t_test_1 / _2.  */
/* ------------------------------------------------------------------------ */
/* Is mean(x) within [mu0 + lower, mu0 + upper]?  (lower < upper; typically
 * lower = -margin < 0 < upper = margin.) */
MCSTAT_NODISCARD MCSTAT_API int mcstat_equivalence_test_1(const double *x, size_t n, double mu0, double lower,
                                         double upper, double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_equivalence_test_1_moments(const mcstat_moments *x, double mu0,
                                                 double lower, double upper, double alpha,
                                                 mcstat_result *out);
/* Is mean(x) - mean(y) within [lower, upper]?  (Welch: unequal variances.) */
MCSTAT_NODISCARD MCSTAT_API int mcstat_equivalence_test_2(const double *x, size_t nx, const double *y, size_t ny,
                                         double lower, double upper, double alpha,
                                         mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_equivalence_test_2_moments(const mcstat_moments *x, const mcstat_moments *y,
                                                 double lower, double upper, double alpha,
                                                 mcstat_result *out);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_EQUIVALENCE_FAMILY_H */
