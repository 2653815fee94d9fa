/*
 * mcstat/pixels.h - per-pixel and row-wise tests.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_PIXELS_FAMILY_H
#define MCSTAT_PIXELS_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 4. Per-pixel tests.                                                    */
/* The tests of "The tests and their result" once per pixel of a stack:    */
/* mcstat_pixels_test takes any layout (seeds-major stacks as renderers     */
/* write them, or rows of values per pixel), float32 or double, channels    */
/* weighted into one value, and writes arrays; the _matrix calls take rows  */
/* of doubles and write an mcstat_result per row; _moments_rows calls take  */
/* arrays of accumulators.                                                  */
/* ======================================================================== */

/* Flags of the per-pixel and row-wise tests.
 *   MCSTAT_ROWS_NO_INTERVALS  no critical values and confidence intervals
 *                             (left NaN; p-value, reject and decision
 *                             remain): the cheap path when only the
 *                             decision map is wanted.
 *   MCSTAT_ROWS_OMIT_NAN      NaN values are left out of each pixel's
 *                             sample (the paired test leaves out the pairs
 *                             with a NaN on either side); +-Inf remains an
 *                             error. */
#define MCSTAT_ROWS_NO_INTERVALS 1u
#define MCSTAT_ROWS_OMIT_NAN 2u
/*   MCSTAT_PIXELS_RENDER      Welch's test (MCSTAT_TEST_T_2 of
 *                             mcstat_pixels_test and the _pixels calls;
 *                             the paired test below; MCSTAT_EINVAL
 *                             elsewhere) made valid on
 *                             renders, whose pixels are often constant on
 *                             a side (all zeros: lit only by rare paths),
 *                             zero-inflated or spiky, at a few seeds.  With
 *                             M = max(|mean x|, |mean y|), d = mean x -
 *                             mean y - null value, eps the numerical
 *                             floor (mcstat_pixels_options.resolution):
 *                             - the numerical floor: each side's variance
 *                               is at least (eps M)^2; a side whose
 *                               variance is at most that is constant;
 *                             - a side that is constant, or shows at most
 *                               one nonzero value, while the other varies,
 *                               may hide a rare value (no test of a mean
 *                               has power against that without
 *                               assumptions: Bahadur and Savage).  If it
 *                               hid one at rate pi = 1 - 0.05^(1/n) (the
 *                               95% upper bound from n draws without it:
 *                               the rule of three), under H0 its variance
 *                               would be at least d^2 (1 - pi) / pi, which
 *                               becomes its variance.  Then |t| <= sqrt(n
 *                               pi / (1 - pi)), which falls from 2.64 at
 *                               n = 2 towards sqrt(-ln 0.05) = 1.73: such
 *                               a pixel cannot be significant alone; it is
 *                               untestable per pixel and needs block tests
 *                               (means of blocks of pixels) or more seeds;
 *                             - the degrees of freedom are Hsu's, min(nx,
 *                               ny) - 1, where a side with zeros and h >= 2
 *                               nonzero values counts h - 1 (its spread
 *                               comes from them): Satterthwaite's
 *                               estimated df makes the far tails that an
 *                               image's adjustment reaches too light at a
 *                               few seeds;
 *                             - both sides constant: equal within eps M,
 *                               MCSTAT_EDEGENERATE (untested, as without
 *                               the flag); different beyond it, both take
 *                               the rule-of-three variance: at a few
 *                               samples per pixel each seed's count of hits
 *                               on a light's edge can be the same by
 *                               chance (a correct pair of Cycles renders
 *                               at 4 spp shows 300 against 400 in every
 *                               seed), so constancy is not determinism.
 *                             Pixels that would be tested without it are
 *                             tested, with these variances and df; the
 *                             plain Welch test (R's t.test) is the
 *                             default.
 *                             The paired test (MCSTAT_TEST_T_PAIRED of
 *                             mcstat_pixels_test; same-seed renders)
 *                             takes the same guards on the differences
 *                             d_s = x_s - y_s: their variance is at
 *                             least (eps M)^2; differences within that
 *                             and equal within eps M are
 *                             MCSTAT_EDEGENERATE; when the differences
 *                             or either side are constant or show at
 *                             most one nonzero value, or a side is zero
 *                             in a seed where the other is not (it may
 *                             hide what the other shows there), the
 *                             variance is at least d^2 (1 - pi) / pi
 *                             (not significant alone); the degrees of
 *                             freedom are the fewest of n - 1 and, for a
 *                             side or the differences with zeros and h >=
 *                             2 nonzero values, h - 1. */
#define MCSTAT_PIXELS_RENDER 4u

/* ------------------------------------------------------------------------ */
/* Per-pixel tests on image stacks.                                          */
/* A pixel's sample is n values (seeds, or the batch means of one pixel);    */
/* an mcstat_pixels_in says where they are: value s of pixel i starts at     */
/* element s * value_stride + i * pixel_stride of data, and is the weighted */
/* sum of `channels` consecutive elements there (formed in double: the      */
/* luminance of RGB without a copy), or the element itself when channels is */
/* 1 and weights NULL.  A seeds-major stack (seeds, height, width[,         */
/* channels]) is value_stride = height * width * channels, pixel_stride =   */
/* channels; rows of values per pixel (height, width, seeds) are            */
/* value_stride = 1, pixel_stride = seeds.                                  */
/* The input grows by appending fields ("Conventions"): start from          */
/* MCSTAT_PIXELS_IN_INIT, which sets size.                                   */
/* ------------------------------------------------------------------------ */
enum mcstat_value_type {
    MCSTAT_VALUE_FLOAT64 = 0, /* double */
    MCSTAT_VALUE_FLOAT32 = 1  /* float, each value converted to double exactly */
};

typedef struct mcstat_pixels_in {
    uint32_t size;          /* sizeof(mcstat_pixels_in): set by the initialiser */
    int32_t type;           /* enum mcstat_value_type */
    const void *data;       /* value 0 of pixel 0 (its first channel) */
    size_t n;               /* values per pixel */
    size_t value_stride;    /* elements from one value of a pixel to the next */
    size_t pixel_stride;    /* elements from one pixel to the next */
    size_t channels;        /* elements per value (consecutive), >= 1 */
    const double *weights;  /* `channels` finite weights; NULL when channels is 1 */
} mcstat_pixels_in;

#define MCSTAT_PIXELS_IN_INIT {sizeof(mcstat_pixels_in), MCSTAT_VALUE_FLOAT64, NULL, 0, 0, 0, 1, NULL}

/* Options of mcstat_pixels_test; grows by appending fields ("Conventions"):
 * start from MCSTAT_PIXELS_OPTIONS_INIT. */
typedef struct mcstat_pixels_options {
    uint32_t size;    /* sizeof(mcstat_pixels_options): set by the initialiser */
    uint32_t flags;   /* MCSTAT_ROWS_NO_INTERVALS, MCSTAT_ROWS_OMIT_NAN; default 0 */
    int32_t threads;  /* threads the call may use, 1..64; default 1: no thread is
                         started unless the caller asks.  Results do not depend
                         on it. */
    int32_t reserved; /* zero */
    /* (0.3) MCSTAT_PIXELS_RENDER's numerical floor ("The numerical
       floor"), relative to the larger |mean| of a pixel's sides:
       differences and spreads below it are rounding, not evidence.  0 (the
       default): from the inputs' type, MCSTAT_RESOLUTION_FLOAT32 for
       float32 and MCSTAT_RESOLUTION_FLOAT64 for double; else a finite
       value in [0, 1).  Ignored without the flag. */
    double resolution;
} mcstat_pixels_options;

#define MCSTAT_PIXELS_OPTIONS_INIT {sizeof(mcstat_pixels_options), 0u, 1, 0, 0.0}

/* Per-pixel results: arrays of the caller's, indexed by pixel (element i is
 * pixel i, whatever range was asked for); any may be NULL, and only what is
 * not NULL is computed and written.  Grows by appending fields ("Conventions"):
 * start from MCSTAT_PIXELS_OUT_INIT (size set, every array NULL). */
typedef struct mcstat_pixels_out {
    uint32_t size;       /* sizeof(mcstat_pixels_out): set by the initialiser */
    uint32_t reserved;   /* zero */
    double *p_value;     /* for the alternative */
    double *statistic;   /* t, X-squared or F */
    double *df;          /* degrees of freedom (F: the numerator's) */
    double *df2;         /* F: the denominator's degrees of freedom (NaN for the others) */
    double *estimate;    /* mcstat_result.estimate[0]: the mean of x (t tests; paired: of
                            the differences), the variance of x (chi-squared), the
                            ratio of the variances (F) */
    double *estimate2;   /* estimate[1]: the mean of y (two-sample t; NaN for the others) */
    double *std_error;   /* t tests: the estimate's (the difference's) standard error */
    double *conf_lo;     /* the 1 - alpha confidence interval of the tested parameter */
    double *conf_hi;
    double *critical_lo; /* mcstat_result.critical[0] and [1] */
    double *critical_hi;
    int32_t *status;     /* MCSTAT_OK or the pixel's error */
    int8_t *decision;    /* MCSTAT_DECISION_*; reject is decision != 0 (0 where failed) */
    uint64_t *n_x;       /* values used from x (the pairs, paired), after NaN left out */
    uint64_t *n_y;       /* values used from y (0 for one-sample tests) */
} mcstat_pixels_out;

#define MCSTAT_PIXELS_OUT_INIT \
    {sizeof(mcstat_pixels_out), 0u, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, \
     NULL, NULL, NULL}

/* sizeof of each struct in each release that changed it. */
#define MCSTAT_PIXELS_IN_SIZE_0_2 56u
#define MCSTAT_PIXELS_OPTIONS_SIZE_0_2 16u
#define MCSTAT_PIXELS_OPTIONS_SIZE_0_3 24u
#define MCSTAT_PIXELS_OUT_SIZE_0_2 128u
MCSTAT_API size_t mcstat_sizeof_pixels_in(void);
MCSTAT_API size_t mcstat_sizeof_pixels_options(void);
MCSTAT_API size_t mcstat_sizeof_pixels_out(void);
/* The initialisers for FFI callers (the first `size` bytes, as the
 * options' _init_size; MCSTAT_EINVAL for NULL or a size no release had). */
MCSTAT_API int mcstat_pixels_in_init_size(mcstat_pixels_in *in, size_t size);
MCSTAT_API int mcstat_pixels_options_init_size(mcstat_pixels_options *opt, size_t size);
MCSTAT_API int mcstat_pixels_out_init_size(mcstat_pixels_out *out, size_t size);

/* The test `test` once per pixel i in [begin, end):
 *   MCSTAT_TEST_T_1         one-sample t of x's mean against null_value (y NULL)
 *   MCSTAT_TEST_T_2         Welch's t of mean(x) - mean(y) against null_value
 *   MCSTAT_TEST_T_2_POOLED  Student's pooled t, likewise
 *   MCSTAT_TEST_T_PAIRED    paired t of mean(x - y) (x and y of equal n)
 *   MCSTAT_TEST_VAR_1       chi-squared test of x's variance against null_value (y NULL)
 *   MCSTAT_TEST_VAR_2       F test of var(x)/var(y) against null_value
 * Each pixel's results are those of the single call on its sample(s)
 * (mcstat_t_test_1, ..._2, ..._2_pooled, mcstat_t_test_paired,
 * mcstat_var_test_1, ..._2): bit for bit for the pooled and paired t and
 * the one-sample t; Welch's and the variance tests run by blocks of pixels
 * and agree to within: Welch's p-value is within 3e-14 + 4e-16 |log p|
 * relative of the exact tail at its statistic, as the single call's is
 * (3e-13 where it underflows), so the two agree to twice that; the
 * variance tests' p-values (from a per-call table of the general routine's
 * log tails, interpolated) agree with the single call's to twice that
 * too; the statistic, df, estimates, standard
 * error and interval about 1e-14 relative (the moments are two passes over
 * the values, the single call's its shifted sums), Welch's critical values
 * 3e-13 (from a per-call table of the t quantile in 1/df; the variance
 * tests' are the single call's).  A pixel the block paths do not cover
 * (a NaN or Inf, extreme magnitudes, too few values, samples constant to
 * within rounding or nearly so, degrees of freedom beyond 1000, a p-value
 * too steep in the statistic for the moments' rounding) is computed by the single call's own code: its status and outputs are
 * then the single call's, bit for bit.  A pixel that fails gets its
 * status, NaN outputs, decision 0 and n_x, n_y 0; the others are still
 * computed.  opt may be NULL (the defaults).
 * Returns MCSTAT_OK when every pixel succeeded, else the status of the
 * first failing pixel (the lowest index); MCSTAT_EINVAL (nothing written)
 * for NULL pointers (x, out; y for two-sample tests), an unknown test,
 * type, flag or struct size, no channels, channels > 1 without weights,
 * non-finite weights, end < begin, alpha outside (0, 1), a null value
 * outside its domain (finite; positive for the variance tests), an unknown
 * alternative, two samples of different types, channels or weights,
 * paired samples of unequal n; MCSTAT_ETOOBIG when the addresses overflow
 * size_t.  The block paths work in about 100 KiB (Welch) or 330 KiB (the
 * variance tests) a thread, off the caller's stack (if it cannot be
 * allocated every pixel takes the single call's code, with the same
 * results, slower); the single call's code takes a buffer of n values a
 * thread (MCSTAT_ENOMEM for the pixels of a thread that could not have
 * it).  opt->threads > 1 runs that many threads (at most one per 4096
 * pixels), the first the caller's, which take the pixels by chunks in
 * turn, so that a core the machine slows down holds up no more than its
 * last chunk.  On x86-64 the
 * block loops run as AVX2 code where the CPU has it (bit for bit the
 * results of the SSE2 code); MCSTAT_NO_AVX2=1 in the environment when the
 * library first runs them keeps them to SSE2 (for tools that do not decode
 * every AVX2 instruction, such as valgrind 3.19). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_pixels_test(int test, const mcstat_pixels_in *x, const mcstat_pixels_in *y, size_t begin,
                                  size_t end, double null_value, int alternative, double alpha,
                                  const mcstat_pixels_options *opt, const mcstat_pixels_out *out);

/* Welch's test per pixel on seeds-major stacks: mcstat_pixels_test(
 * MCSTAT_TEST_T_2, ...) with value s of pixel i at x[s * x_seed_stride +
 * i * channels + c], one thread, flags as in mcstat_pixels_options. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_pixels(const double *x, size_t nx, size_t x_seed_stride, const double *y,
                                      size_t ny, size_t y_seed_stride, size_t channels, const double *weights,
                                      size_t begin, size_t end, double mu0, int alternative, double alpha,
                                      unsigned flags, const mcstat_pixels_out *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_pixels_f32(const float *x, size_t nx, size_t x_seed_stride, const float *y,
                                          size_t ny, size_t y_seed_stride, size_t channels,
                                          const double *weights, size_t begin, size_t end, double mu0,
                                          int alternative, double alpha, unsigned flags,
                                          const mcstat_pixels_out *out);

/* ------------------------------------------------------------------------ */
/* Row-wise tests with one result struct per row.                            */
/* Row i of x starts at x + i * x_stride (strides in elements) and holds n   */
/* contiguous values; row i of y pairs with row i of x.  Arguments in one    */
/* order: each matrix as (data, n, stride), then the number of rows (0.1.0's */
/* *_rows names put rows second in the one-sample calls, seventh in the     */
/* two-sample ones: mcstat/deprecated.h).  out[i] receives row i's   */
/* result, bit for bit the single call on that row, and status[i] (may be   */
/* NULL) its status;                                                        */
/* a row that fails gets NaN fields and the other rows are still computed.  */
/* Critical values are solved once for rows of equal degrees of freedom.    */
/* flags: MCSTAT_ROWS_*.  Returns MCSTAT_OK when every row succeeded, else  */
/* the status of the first row that failed; MCSTAT_EINVAL (nothing written) */
/* for NULL pointers or unknown flags.  No allocation; disjoint row ranges  */
/* may run on different threads (x + start * x_stride, out + start, status  */
/* + start).  The same rows as an mcstat_pixels_in (value_stride 1,         */
/* pixel_stride the row stride) go through mcstat_pixels_test, which        */
/* writes arrays instead of structs and runs Welch's test by blocks of      */
/* pixels: several times faster, within the bounds given there.             */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_1_matrix(const double *x, size_t n, size_t x_stride, size_t rows, double mu0,
                                      int alternative, double alpha, unsigned flags, mcstat_result *out,
                                      int32_t *status);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_matrix(const double *x, size_t nx, size_t x_stride, const double *y,
                                      size_t ny, size_t y_stride, size_t rows, double mu0, int alternative,
                                      double alpha, unsigned flags, mcstat_result *out, int32_t *status);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_1_matrix(const double *x, size_t n, size_t x_stride, size_t rows,
                                        double sigma2, int alternative, double alpha, unsigned flags,
                                        mcstat_result *out, int32_t *status);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_2_matrix(const double *x, size_t nx, size_t x_stride, const double *y,
                                        size_t ny, size_t y_stride, size_t rows, double ratio,
                                        int alternative, double alpha, unsigned flags, mcstat_result *out,
                                        int32_t *status);

/* The tests on arrays of accumulators: out[i] is bit for bit the
 * mcstat_*_moments call on x[i] (and y[i]), status[i] (may be NULL) its
 * status, with the conventions of the row-wise tests above: a failed row
 * gets NaN fields and the others are still computed, critical values are
 * solved once for rows of equal degrees of freedom, MCSTAT_ROWS_NO_INTERVALS
 * skips critical values and confidence intervals.  MCSTAT_ROWS_OMIT_NAN has
 * no meaning here and is MCSTAT_EINVAL.  Returns MCSTAT_OK when every row
 * succeeded, else the first failing row's status; MCSTAT_EINVAL (nothing
 * written) for NULL pointers or unknown flags. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_1_moments_rows(const mcstat_moments *x, size_t rows, double mu0, int alternative,
                                            double alpha, unsigned flags, mcstat_result *out, int32_t *status);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_moments_rows(const mcstat_moments *x, const mcstat_moments *y, size_t rows,
                                            double mu0, int alternative, double alpha, unsigned flags,
                                            mcstat_result *out, int32_t *status);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_1_moments_rows(const mcstat_moments *x, size_t rows, double sigma2,
                                              int alternative, double alpha, unsigned flags, mcstat_result *out,
                                              int32_t *status);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_2_moments_rows(const mcstat_moments *x, const mcstat_moments *y, size_t rows,
                                              double ratio, int alternative, double alpha, unsigned flags,
                                              mcstat_result *out, int32_t *status);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_PIXELS_FAMILY_H */
