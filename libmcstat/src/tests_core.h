/*
 * tests_core.h - what the tests share: the moments a test reads (moments.c),
 * filling a result (result.c), the quantile cache (quantile_cache.c) and
 * the tests on accumulators that the row-wise calls drive (rows.c).
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_TESTS_CORE_H
#define MCSTAT_TESTS_CORE_H

/* ---- moments (moments.c) ------------------------------------------------ */
/* The variance as v * 2^(2*e) with v finite: *v = m2/(n-1) in scaled units. */
/* The scale exponent an accumulator holding values up to amax in magnitude has. */
MCSTAT_HIDDEN int mcstat__moments_scale_for(double amax);
MCSTAT_HIDDEN void mcstat__moments_var_scaled(const mcstat_moments *m, double *v, int *e);
MCSTAT_HIDDEN mcstat_dd mcstat__moments_mean_dd(const mcstat_moments *m);
/* MCSTAT_ETOOFEW / MCSTAT_EDEGENERATE / MCSTAT_EINVAL checks of a sample. */
MCSTAT_HIDDEN int mcstat__moments_check(const mcstat_moments *m);
/* The moments of two samples, for the two-sample tests on arrays: mx and my
 * initialised and filled; the first failing status otherwise. */
MCSTAT_HIDDEN int mcstat__moments_of_two(const double *x, size_t nx, const double *y, size_t ny, mcstat_moments *mx,
                                         mcstat_moments *my);

/* *m <- every value of the stream; MCSTAT_ETOOBIG or MCSTAT_ENONFINITE when
 * it has left values out or holds NaN or +-Inf (stream.c). */
MCSTAT_HIDDEN int mcstat__stream_moments_checked(const mcstat_stream *s, mcstat_moments *m);

/* ---- results (result.c) -------------------------------------------------- */
/* Fills p_value, critical[], reject, decision from the statistic's tails.
 * `quantile(p, upper, ctx, &x)` inverts the null distribution. */
typedef int (*mcstat_quantile_fn)(double p, int upper, const void *ctx, double *x);
MCSTAT_HIDDEN int mcstat__finish(mcstat_result *r, const mcstat_tails *tails,
                                 mcstat_quantile_fn quantile, const void *ctx);
MCSTAT_HIDDEN void mcstat__result_clear(mcstat_result *r);

/* ---- quantile reuse (t_test.c, var_test.c, rows.c; quantile_cache.c) -----------------------
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
/* An interval's bound est - c se, scaled by 2^e, in double-double (the
 * t tests' and the per-pixel path's; safe for |c| or c se beyond 2^900). */
MCSTAT_HIDDEN double mcstat__ci_bound(mcstat_dd est, double c, double se, int e);
/* Student's pooled-variance two-sample t (Welch's code with the pooled
 * standard error and nx + ny - 2 degrees of freedom). */
MCSTAT_HIDDEN int mcstat__t_test_2_pooled(const mcstat_moments *x, const mcstat_moments *y, double mu0,
                                          int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out);
/* The paired t test on x - y (arguments checked but the data; qc as above). */
MCSTAT_HIDDEN int mcstat__t_test_paired(const double *x, const double *y, size_t n, double mu0, int alternative,
                                        double alpha, mcstat_qcache *qc, mcstat_result *out);
MCSTAT_HIDDEN int mcstat__var_test_1(const mcstat_moments *x, double sigma2, int alternative, double alpha,
                                     mcstat_qcache *qc, mcstat_result *out);
MCSTAT_HIDDEN int mcstat__var_test_2(const mcstat_moments *x, const mcstat_moments *y, double ratio,
                                     int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out);

/* The Clopper-Pearson interval of binom_test.c for x successes in n trials
 * at level 1 - alpha (one-sided alternatives keep the end 0 or 1). */
MCSTAT_HIDDEN int mcstat__binom_conf_int(double x, double n, int alternative, double alpha, double ci[2]);

#endif /* MCSTAT_TESTS_CORE_H */
