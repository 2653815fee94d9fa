/*
 * mcstat/distributions.h - t, chi-squared and F tails and quantiles.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_DISTRIBUTIONS_FAMILY_H
#define MCSTAT_DISTRIBUTIONS_FAMILY_H

#include "base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 7. Distributions.                                                      */
/* The t, chi-squared and F distributions the tests use, as functions.      */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Distributions.                                                           */
/* Tail probabilities are computed from whichever tail is small (never as   */
/* 1 - P); log versions stay finite where the probability underflows.       */
/* Quantiles invert these by safeguarded Newton iteration.  `upper`        */
/* selects the tail: 0 gives P[X <= x], 1 gives P[X > x]; a quantile solves */
/* that tail's probability = p.                                             */
/* Accuracy: relative error against 50-digit references, the bounds the     */
/* tests enforce (2-3 times the measured peak; per-domain tables, rms and   */
/* worst cases in libmcstat/ACCURACY.md), by tail probability p:            */
/*                                      p >= 1e-30   1e-300 <= p < 1e-30    */
/*   t cdf, df in [1e-3, 1e13]             3e-14          6e-13             */
/*   chi^2 cdf, df in [1e-3, 1e9]        1.5e-13          5e-13             */
/*   F cdf, df1, df2 in [1e-3, 1e9]        4e-14          6e-13             */
/*   quantiles                             3e-13          3e-13             */
/*   p-values of the t, Welch, chi^2 tests 1e-13          4e-13             */
/*   p-values of the F test                1e-13          3e-12             */
/*   log cdf where p < 1e-30: 8e-16 (t), 5e-15 (chi^2), 8e-15 (F) relative  */
/*   error of log p.  Where p >= 1e-30 the log cdf carries the cdf's error: */
/*   an absolute error of log p within the cdf's bound above (the relative  */
/*   error of p; |log p| times less relative to log p).                     */
/*   chi^2 beyond df 1e9: cdf 4e-13, log 2e-13.                             */
/* Small p lose more because p = exp(log p) inherits |log p| times the      */
/* rounding of log p.  The range promised: df in [1e-3, 1e15] (F: both),    */
/* x anywhere (F with one df in [1e-4, 1e-3) too: ACCURACY.md's rows).      */
/* Statuses: MCSTAT_EINVAL for NaN or out-of-domain arguments,               */
/* MCSTAT_ENUMERIC if an iteration fails (never in the range above: the      */
/* fuzz harness treats it as a failure there).                               */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_cdf(double x, double df, int upper, double *p);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_logcdf(double x, double df, int upper, double *logp);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_quantile(double p, double df, int upper, double *x);
/* ------------------------------------------------------------------------ */
/* mcstat_t_quantiles: x[i] = mcstat_t_quantile(p, df[i], upper, ...) for   */
/* n values of df at one level, to the same accuracy, fast where many df    */
/* differ (critical values or detectable differences per pixel): for p in   */
/* [1e-100, 1/4] a per-call table of quantiles in 1/df (denser as p is     */
/* smaller: 1024 to 65536 nodes), interpolated where that is good to        */
/* rounding and finished by Halley's method elsewhere: O(1) a value, far   */
/* below a single call's solve (figures: bench/RESULTS.md).                 */
/* Where an element fails (df NaN or not positive) x[i] is NaN and the      */
/* others are still computed; the status is that of the first failing      */
/* element, MCSTAT_OK if none.                                              */
/* MCSTAT_EINVAL for p NaN or outside [0, 1], or NULL arrays with n > 0.    */
/* Reentrant: callers split large arrays over their own threads.            */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_quantiles(double p, const double *df, size_t n, int upper, double *x);
MCSTAT_NODISCARD MCSTAT_API int mcstat_chisq_cdf(double x, double df, int upper, double *p);
MCSTAT_NODISCARD MCSTAT_API int mcstat_chisq_logcdf(double x, double df, int upper, double *logp);
MCSTAT_NODISCARD MCSTAT_API int mcstat_chisq_quantile(double p, double df, int upper, double *x);
MCSTAT_NODISCARD MCSTAT_API int mcstat_f_cdf(double x, double df1, double df2, int upper, double *p);
MCSTAT_NODISCARD MCSTAT_API int mcstat_f_logcdf(double x, double df1, double df2, int upper, double *logp);
MCSTAT_NODISCARD MCSTAT_API int mcstat_f_quantile(double p, double df1, double df2, int upper, double *x);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_DISTRIBUTIONS_FAMILY_H */
