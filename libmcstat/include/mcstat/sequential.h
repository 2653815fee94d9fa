/*
 * mcstat/sequential.h - sequential, anytime-valid tests.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_SEQUENTIAL_FAMILY_H
#define MCSTAT_SEQUENTIAL_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 10. Sequential, anytime-valid tests.                                   */
/* A fixed-n test looked at after every batch, stopped when its p-value is  */
/* small, rejects a true H0 far more often than alpha (0.5-0.8 at alpha =   */
/* 0.05 over 1000 looks).  These tests may be looked at after every batch   */
/* and stopped at any time, in either direction, their error rate still at  */
/* most alpha: "render until decided".                                      */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Method: the asymptotic Gaussian-mixture confidence sequence (Robbins'    */
/* normal mixture with the variance estimated; Waudby-Smith, Arbour, Sinha, */
/* Kennedy and Ramdas, "Time-uniform central limit theory"), on a working   */
/* parameter theta with estimate theta_hat and standard error se:           */
/*   MEAN_1  theta = mean of x                 se^2 = v_x / n_x              */
/*   MEAN_2  theta = mean of x - mean of y     se^2 = v_x / n_x + v_y / n_y  */
/*   VAR_1   theta = log variance of x         se^2 = (b2_x - 1) / n_x       */
/*   VAR_2   theta = log var(x) - log var(y)   se^2 = (b2_x-1)/n_x + (b2_y-1)/n_y */
/* where b2 = n M4 / M2^2 is the sample kurtosis and v the variance made    */
/* an upper confidence bound, v = s^2 + var_ucb_z sqrt((M4/n - (M2/n)^2)/n) */
/* (a sample that has not yet met its rare large values has a small mean   */
/* and a smaller variance at once; the bound keeps it from deciding).  With */
/* z = (theta_hat - theta0)/se, t_eff = n (the weighted n for two samples,  */
/* sum of per-observation variances over se^2) and a = t_eff c / t_opt,     */
/* c = -2 log(alpha') + log(1 - 2 log(alpha')), the test martingale is      */
/*   two-sided  log E = z^2 a / (2 (1 + a)) - log(1 + a) / 2,  alpha' = alpha */
/*   one-sided  log E = that + log 2 + log Phi(+-z sqrt(a / (1 + a))),       */
/*              alpha' = 2 alpha (Howard et al. 2021's one-sided mixture)   */
/* H0 is rejected at the first look where E >= 1/alpha; the p-value is      */
/* min(1, 1/max E over the looks), valid at any stopping time; the          */
/* confidence sequence is the running intersection of theta_hat +- b se     */
/* over the looks (b the z at which E = 1/alpha), mapped back by exp for    */
/* the variances.  t_opt (default 1e4 observations) is where it is tightest;*/
/* at t_opt its half-width is 1.55 times the fixed-n interval's at alpha =  */
/* 0.05, at 100 observations 4.6 times.                                      */
/*                                                                           */
/* Assumptions, to be read before trusting a decision: independent,        */
/* identically distributed values with finite variance (finite fourth      */
/* moment for VAR_*); the coverage is asymptotic, exact only as n grows.    */
/* For the estimators renderers have (heavy right tails, mostly exact       */
/* zeros) small n is where it fails: a batch of only zeros has zero         */
/* variance and would "prove" any mean wrong.  So a test holds (continues   */
/* without deciding, its p-value 1 and its sequence unbounded) until        */
/*   n >= min_n, M2 > 0, and n >= kurtosis_gate * b2 for every sample       */
/* (about ten non-zero values when they are rare; kurtosis_gate * b2^2 for  */
/* VAR_*, whose standard error rests on b2 itself).  Measured             */
/* (tests/python/test_sequential_calibration.py to 1e4,                     */
/* bench/RESULTS_sequential.md to 1e6, 2000 runs each): the rate of ever    */
/* rejecting a true mean, looked at                                          */
/* every 100 values, stays below alpha (at most 0.041 at alpha = 0.05) for  */
/* normal, exponential, uniform, lognormal (sigma 1.5), 99%-zeros data and  */
/* the paper's irradiance estimators, where the same method without hold   */
/* and bound reaches 0.51 on 99%-zeros data.  Data whose kurtosis keeps    */
/* growing (infinite variance) keep the gate closed: mcstat_seq_finish      */
/* then says MCSTAT_EHEAVYTAIL.                                              */
/*                                                                           */
/* Equivalence (MEAN_1, MEAN_2, two-sided): with eps > 0 the test also      */
/* stops with "equal" (decision 0, reject 0) once the confidence sequence   */
/* lies inside (theta0 - eps, theta0 + eps): the bias is shown below eps,   */
/* with the same error rate (one sequence covers both decisions).           */
/*                                                                           */
/* Pushing: each push is one look; a batch is any accumulator, e.g. the     */
/* per-thread mcstat_moments of a frame merged by the caller (pushing       */
/* batches or their merge gives the same accumulators, bit for bit; the     */
/* looks differ).  The first decision is final (state DECIDED, at           */
/* seq_n_decided); later pushes still narrow the sequence and update the    */
/* p-value.  Cost per look: O(1), no allocation (a Newton root-find of a    */
/* few steps for one-sided tests).  The struct is the caller's, fixed size, no        */
/* pointers: copy it to keep a state, one per thread of control.            */
/* ------------------------------------------------------------------------ */
enum mcstat_seq_kind {
    MCSTAT_SEQ_MEAN_1 = 1, /* mean of x against null_value (mu0) */
    MCSTAT_SEQ_MEAN_2 = 2, /* mean of x - mean of y against null_value (a difference) */
    MCSTAT_SEQ_VAR_1 = 3,  /* variance of x against null_value (sigma0^2 > 0) */
    MCSTAT_SEQ_VAR_2 = 4   /* var(x) / var(y) against null_value (a ratio > 0) */
};
/* mcstat_result.seq_state and mcstat_seq.state */
#define MCSTAT_SEQ_CONTINUE 0
#define MCSTAT_SEQ_DECIDED 1
/* Bits of mcstat_seq.hold: why no decision is allowed at the last look. */
#define MCSTAT_SEQ_HOLD_FEW 1u        /* n < min_n (a sample) */
#define MCSTAT_SEQ_HOLD_DEGENERATE 2u /* a sample has no spread yet (M2 == 0) */
#define MCSTAT_SEQ_HOLD_KURTOSIS 4u   /* n < kurtosis_gate * b2 (b2^2 for VAR_*) (a sample) */

/* Grows by appending fields ("Conventions", compatibility). */
typedef struct mcstat_seq_options {
    uint32_t size;         /* sizeof(mcstat_seq_options): set by the initialiser */
    int32_t alternative;   /* enum mcstat_alternative; default TWO_SIDED */
    double alpha;          /* in (0, 1); default 0.05 */
    double eps;            /* equivalence margin >= 0 on the mean (MEAN_*, two-sided); default 0: none */
    double t_opt;          /* observations (per sample) where the sequence is tightest, > 0; default 1e4 */
    double kurtosis_gate;  /* hold while n < kurtosis_gate * b2, >= 0 (0: off); default 10 */
    double var_ucb_z;      /* the variance's upper-bound factor, >= 0 (0: plain s^2); default 3 */
    uint64_t min_n;        /* hold while a sample has fewer values, >= 2; default 100 */
} mcstat_seq_options;

#define MCSTAT_SEQ_OPTIONS_INIT \
    {sizeof(mcstat_seq_options), MCSTAT_TWO_SIDED, 0.05, 0.0, 1e4, 10.0, 3.0, 100u}
/* sizeof(mcstat_seq_options) in each release that changed it. */
#define MCSTAT_SEQ_OPTIONS_SIZE_0_2 56u
/* As mcstat_ks_options_init_size. */
MCSTAT_API int mcstat_seq_options_init_size(mcstat_seq_options *opt, size_t size);
#define mcstat_seq_options_init(opt) mcstat_seq_options_init_size((opt), sizeof *(opt))
MCSTAT_API size_t mcstat_sizeof_seq_options(void);

/* The state of one sequential test: plain data the caller owns (no
 * pointers; 448 bytes), written only by these functions. */
typedef struct mcstat_seq {
    uint32_t version;      /* MCSTAT_SEQ_VERSION once initialised */
    int32_t kind;          /* enum mcstat_seq_kind */
    int32_t alternative;
    int32_t state;         /* MCSTAT_SEQ_CONTINUE or MCSTAT_SEQ_DECIDED */
    int32_t decision;      /* once decided: MCSTAT_DECISION_LESS, _EQUAL or _GREATER */
    uint32_t hold;         /* MCSTAT_SEQ_HOLD_* bits at the last look */
    mcstat_moments x, y;   /* everything pushed so far (y unused for one sample) */
    double null_value, alpha, eps, t_opt, kurtosis_gate, var_ucb_z;
    uint64_t min_n;
    uint64_t looks;        /* pushes so far */
    uint64_t n_decided;    /* n of x at the deciding look (0 while continuing) */
    double log_e;          /* log e-value at the last look (-Inf while held) */
    double log_e_max;      /* its running maximum */
    double cs[2];          /* confidence sequence on the working scale (running intersection) */
    double reserved[8];    /* zero */
} mcstat_seq;
#define MCSTAT_SEQ_VERSION 1u

/* *s <- an empty test of `kind` against null_value, options opt (NULL:
 * the defaults).  MCSTAT_EINVAL (s untouched) for NULL s, a bad kind or
 * alternative, an options size no release had, alpha outside (0, 1),
 * eps < 0 or not finite, eps > 0 with VAR_* or a one-sided alternative,
 * t_opt <= 0 or not finite, kurtosis_gate or var_ucb_z negative or not
 * finite, min_n < 2, null_value not finite (and <= 0 for VAR_*). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_init(mcstat_seq *s, int kind, double null_value, const mcstat_seq_options *opt);
/* One look after adding a batch of x (MEAN_1, VAR_1): an accumulator, an
 * array, or a stream's values (mcstat_stream_moments; MCSTAT_ENONFINITE if
 * the stream has seen NaN or Inf).  The two-sample kinds take a batch of
 * each (either may be empty).  Statuses, s unchanged on any: MCSTAT_EINVAL
 * (NULL, an uninitialised s or batch, the wrong kind for the call),
 * MCSTAT_ENONFINITE (NaN or +-Inf in a batch), MCSTAT_ETOOBIG (a count
 * would pass 2^64 - 1). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_push_moments(mcstat_seq *s, const mcstat_moments *batch);
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_push_array(mcstat_seq *s, const double *x, size_t n);
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_push_stream(mcstat_seq *s, const mcstat_stream *frame);
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_push_2_moments(mcstat_seq *s, const mcstat_moments *bx, const mcstat_moments *by);
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_push_2_array(mcstat_seq *s, const double *x, size_t nx, const double *y, size_t ny);
/* *out <- the test at the last look (test MCSTAT_TEST_SEQ_*, method
 * MCSTAT_METHOD_ASYMPTOTIC): statistic the z of the last look, p_value the
 * anytime p-value, conf_int the confidence sequence (on the parameter's
 * scale: a mean, a difference, a variance or a ratio), critical[] +-b, the
 * z bounds of the last look (+-Inf while held), estimate[] the means (the
 * variances for VAR_*), std_error se (of the log for VAR_*), df NaN, n[]
 * the counts; reject 1 once decided "less"/"greater"; decision the final
 * one once decided, else 0 (read seq_state: 0 with CONTINUE is "not yet");
 * seq_* fields as in mcstat_result.  mcstat_result_format prints R's
 * layout with the looks, the sequence and "continue" or the decision.
 * MCSTAT_EINVAL for NULL or an uninitialised s. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_result(const mcstat_seq *s, mcstat_result *out);
/* The test at the end of the caller's budget: *out as mcstat_seq_result;
 * returns MCSTAT_OK when decided, or undecided with the data allowing a
 * decision (not enough evidence yet: more samples may decide), and
 * MCSTAT_EHEAVYTAIL (out still written) when the kurtosis gate was closed
 * at the last look: the tails never allowed a decision in this budget. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_seq_finish(const mcstat_seq *s, mcstat_result *out);
/* The name of a kind ("mean", "mean2", "var", "var2"), NULL if invalid. */
MCSTAT_API const char *mcstat_seq_kind_name(int kind);
MCSTAT_API size_t mcstat_sizeof_seq(void);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_SEQUENTIAL_FAMILY_H */
