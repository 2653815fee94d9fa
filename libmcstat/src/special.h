/*
 * special.h - the tails of a distribution (mcstat_tails), the special functions
 * (special.c), the t, chi-squared and F tails (dist.c) and the noncentral t
 * (noncentral.c).
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_SPECIAL_H
#define MCSTAT_SPECIAL_H

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
/* The t tails specialised to the incomplete beta's b = 1/2 (pixels_dist.c): the
 * upper tail P[T > |t|], the other one and log(|t| f(t)); 0 (nothing
 * written) outside its range, 1 <= df <= 1000 and 0 < |t| < 1e100. */
MCSTAT_HIDDEN int mcstat__t_tail_fast(double t, double df, double *upper, double *other, double *logk);
/* The upper p-quantile of t(df) by Newton's method on that tail (t_quantiles.c),
 * mcstat_t_quantile where it does not apply; 0 < p < 1. */
MCSTAT_HIDDEN int mcstat__t_upper_quantile_fast(double p, double df, double *q);
/* pixels.c: nonzero runs the per-block loops' baseline (SSE2) code even
 * where AVX2 is there; for the tests, which compare the two bit for bit. */
MCSTAT_HIDDEN void mcstat__pixels_baseline_only(int on);
/* threads.c's queue of chunks (below) */
typedef struct mcstat__work mcstat__work;
/* pixels.c: Welch's test on the chunks of wk this thread takes, for
 * arguments pixels_test.c has checked (x and y of one type and weighting);
 * the status of its first failed pixel, that pixel's index in *first_index. */
MCSTAT_HIDDEN int mcstat__pixels_welch(const mcstat_pixels_in *x, const mcstat_pixels_in *y, mcstat__work *wk,
                                       size_t *first_index, double mu0, int alternative, double alpha, unsigned flags,
                                       double eps, const mcstat_pixels_out *out);
/* pixels.c: the two-pass moments of pixels i0..i0+k-1 (k <= 256) of one
 * side, as Welch's block path forms them: mean[j] a double-double, m2[j]
 * the sum of squared deviations, bad[j] = 1 where they are not to be used
 * (a NaN or Inf, magnitudes outside [2^-200, 2^200], overflow). */
MCSTAT_HIDDEN void mcstat__pixels_block_moments(const mcstat_pixels_in *p, size_t i0, size_t k, mcstat_dd *mean,
                                                double *m2, unsigned char *bad);
/* pixels.c: whether this call's block loops run as AVX2 code (the CPU has
 * it, and neither MCSTAT_NO_AVX2 nor the tests' baseline switch is set). */
MCSTAT_HIDDEN int mcstat__pixels_avx2(void);
/* pixels_var.c: the variance tests on the chunks of wk this thread takes
 * (arguments checked; y NULL for MCSTAT_TEST_VAR_1), as Welch's above;
 * pixels its block path does not cover go through the single call's code
 * by single(ctx, i). */
typedef int (*mcstat__pixel_fn)(void *ctx, size_t i); /* returns the pixel's status */
MCSTAT_HIDDEN int mcstat__pixels_var(int test, const mcstat_pixels_in *x, const mcstat_pixels_in *y,
                                     mcstat__work *wk, size_t *first_index, double null_value, int alternative,
                                     double alpha, unsigned flags, const mcstat_pixels_out *out,
                                     mcstat__pixel_fn single, void *ctx);
/* threads.c: [begin, end) as a queue of chunks that threads take in turn,
 * so that a thread slowed by the machine takes fewer (the split never
 * changes a result: each item's work is a function of its own index).  A
 * worker keeps its state across the chunks it takes. */
/* The next chunk [*b, *e), in increasing order; 0 when none is left. */
MCSTAT_HIDDEN int mcstat__work_take(mcstat__work *w, size_t *b, size_t *e);
/* A worker: takes chunks until none is left; returns the status of the
 * first item it failed, that item's index in *first_index. */
typedef int (*mcstat__work_fn)(void *ctx, mcstat__work *w, size_t *first_index);
/* f on up to `threads` threads (at most one per min_per_thread items; the
 * first is the caller's), in chunks of a multiple of `granule` items.
 * Returns the status of the failed item of lowest index, MCSTAT_OK if none. */
MCSTAT_HIDDEN int mcstat__run_work(size_t begin, size_t end, int threads, size_t min_per_thread, size_t granule,
                                   mcstat__work_fn f, void *ctx);
/* pixels_dist.c: the per-pixel path's block tails (vector exp and log1p, the
 * central series eight at a time) for n pairs; done[i] where they answered. */
MCSTAT_HIDDEN int mcstat__t_tails_block(size_t n, const double *t, const double *df, double *lower, double *upper,
                                        unsigned char *done);
MCSTAT_HIDDEN int mcstat__chisq_tails(double x, double df, mcstat_tails *t);
MCSTAT_HIDDEN int mcstat__f_tails(double x, double df1, double df2, mcstat_tails *t);
/* log of mcstat_chisq_quantile / mcstat_f_quantile (p in [0, 1], arguments
 * valid), not clamped to the normal doubles: where the quantile itself is 0
 * or Inf in double its logarithm is still finite (-Inf, +Inf only for p at
 * 0 or 1).  Same solver and starting points, so within the normal range
 * exp(*z) is the public function's result. */
MCSTAT_HIDDEN int mcstat__chisq_log_quantile(double p, double df, int upper, double *z);
MCSTAT_HIDDEN int mcstat__f_log_quantile(double p, double df1, double df2, int upper, double *z);

/* ---- noncentral t (noncentral.c, R's pnt from libRmath) ------------------
 * Both tails of the noncentral t at t (df > 0, finite ncp; t may be +-Inf);
 * never prints (see noncentral.c).  MCSTAT_EINVAL, MCSTAT_ENUMERIC. */
MCSTAT_HIDDEN int mcstat__nct_tails(double t, double df, double ncp, double *lower, double *upper);

#endif /* MCSTAT_SPECIAL_H */
