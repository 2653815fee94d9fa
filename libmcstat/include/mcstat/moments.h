/*
 * mcstat/moments.h - accumulators: mcstat_moments, its bytes, arrays of
 * accumulators, mcstat_stream.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_MOMENTS_FAMILY_H
#define MCSTAT_MOMENTS_FAMILY_H

#include "base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 2. Accumulators.                                                       */
/* A sample is kept as an mcstat_moments: count, mean and central sums,     */
/* added a value or an array at a time and merged exactly, so the data      */
/* need never be stored.  Accumulators serialize to 96 bytes; arrays of     */
/* them hold one per pixel; mcstat_stream buffers a renderer thread's       */
/* values in front of one.  The t, chi-squared and F tests take them.       */
/* ======================================================================== */

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
/* Adding and merging refuse with MCSTAT_ETOOBIG (m unchanged) when the
 * count n would pass 2^64 - 1. */
/* Adds one value. MCSTAT_ENONFINITE (m unchanged) for NaN or +-Inf. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_add(mcstat_moments *m, double x);
/* Adds n values. MCSTAT_ENONFINITE (m unchanged) if any is NaN or +-Inf. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_add_array(mcstat_moments *m, const double *x, size_t n);
/* Like mcstat_moments_add_array, but NaN values are skipped (+-Inf is still
 * an error).  *n_omitted (may be NULL) receives the number skipped. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_add_array_omit_nan(mcstat_moments *m, const double *x,
                                                 size_t n, size_t *n_omitted);
/* dst <- dst merged with src (src may equal dst). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_merge(mcstat_moments *dst, const mcstat_moments *src);

/* Derived quantities; each returns NaN when undefined (e.g. n < 2). */
MCSTAT_API double mcstat_moments_mean(const mcstat_moments *m);
MCSTAT_API double mcstat_moments_var(const mcstat_moments *m);      /* M2/(n-1); may overflow to Inf */
MCSTAT_API double mcstat_moments_sd(const mcstat_moments *m);       /* sqrt(var), computed without overflow */
MCSTAT_API double mcstat_moments_skewness(const mcstat_moments *m); /* g1 = sqrt(n) M3 / M2^1.5 */
MCSTAT_API double mcstat_moments_kurtosis(const mcstat_moments *m); /* excess g2 = n M4 / M2^2 - 3 */

/* Versioned, little-endian serialization (MCSTAT_MOMENTS_BYTES bytes, with a
 * magic number and a checksum).  from_bytes returns MCSTAT_ECORRUPT for bytes
 * that are truncated, corrupt, of another version or internally inconsistent. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_to_bytes(const mcstat_moments *m, unsigned char *buf, size_t size);
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_from_bytes(const unsigned char *buf, size_t size, mcstat_moments *m);

/* *out <- an accumulator holding a summary: n values whose mean is `mean`
 * and whose sum of squared deviations is m2 (M2 = (n-1) var), as read from
 * a file of per-pixel summaries.  Only n, the mean and M2 are known: the
 * accumulator is that of the symmetric two-point sample mean +- sqrt(M2/n)
 * (M3 = 0, M4 = M2^2/n, min and max those two points), so it keeps every
 * invariant of an accumulator (it merges, serializes and tests like any
 * other), and the t and variance tests, which read only n, mean and M2,
 * give exactly the summary's results; its skewness, kurtosis, min and max
 * describe the stand-in, not the data.  Statuses, in this order:
 * MCSTAT_EINVAL (out NULL), MCSTAT_ENONFINITE (mean or m2 NaN or +-Inf),
 * MCSTAT_EINVAL (m2 < 0), MCSTAT_ETOOFEW (n == 0: an empty summary is
 * mcstat_moments_init; or n == 1 with m2 != 0), MCSTAT_ETOOBIG (mean +-
 * sqrt(M2/n) overflows). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_from_summary(uint64_t n, double mean, double m2, mcstat_moments *out);

/* ------------------------------------------------------------------------ */
/* Arrays of accumulators: one mcstat_moments per pixel.                     */
/* A render farm keeps one accumulator per pixel (an array of `rows` structs */
/* the caller owns, row i = pixel i), adds every rendered image or batch of  */
/* images into it, ships it as bytes, merges arrays element-wise, and tests  */
/* every pixel.  Adding a batch is "add_array on a fresh accumulator, then   */
/* merge", so pushing batches A then B on one machine gives bit for bit what */
/* pushing A and B on two machines and merging the second into the first    */
/* gives: a fixed merge order reproduces a single-machine run exactly.      */
/* No allocation; disjoint row ranges may run on different threads.          */
/* ------------------------------------------------------------------------ */

/* Empties m[0..rows).  MCSTAT_EINVAL for m NULL with rows > 0. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_init_rows(mcstat_moments *m, size_t rows);

/* Adds n values to each of rows accumulators: row i's values are the n
 * contiguous doubles at x + i * x_stride (strides in elements), and m[i]
 * becomes exactly mcstat_moments_merge(m[i], A) where A is
 * mcstat_moments_add_array on a fresh accumulator of those values.  One
 * image with one value per pixel is n = 1, x_stride = 1; a stack of k
 * images stored pixel-major (k values per pixel) is n = k, x_stride = k.
 * flags: MCSTAT_ROWS_OMIT_NAN skips NaN values (+-Inf remains an error).
 * status[i] (may be NULL) receives row i's status; a row that fails
 * (MCSTAT_ENONFINITE, or MCSTAT_ETOOBIG when its count would pass 2^64 - 1)
 * is left unchanged and the other rows are still added.
 * Returns MCSTAT_OK, the status of the first row that failed, or
 * MCSTAT_EINVAL (nothing changed) for NULL pointers, unknown flags or an
 * uninitialised accumulator. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_add_rows(mcstat_moments *m, size_t rows, const double *x, size_t n,
                                       size_t x_stride, unsigned flags, int32_t *status);

/* dst[i] <- dst[i] merged with src[i], for i < rows (mcstat_moments_merge
 * element-wise).  src may equal dst; the arrays must not otherwise overlap.
 * MCSTAT_EINVAL (nothing changed) for NULL pointers or an uninitialised
 * accumulator in either array, MCSTAT_ETOOBIG (nothing changed) when a
 * row's count would pass 2^64 - 1. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_merge_rows(mcstat_moments *dst, const mcstat_moments *src, size_t rows);

/* The array as rows * MCSTAT_MOMENTS_BYTES bytes: the records of
 * mcstat_moments_to_bytes concatenated in row order, no header (each record
 * carries its own magic, version and checksum; the count is size / 96; the
 * image's shape is the caller's).  MCSTAT_EBUFSIZE when size is smaller,
 * MCSTAT_EINVAL for NULL pointers or an uninitialised accumulator. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_to_bytes_rows(const mcstat_moments *m, size_t rows, unsigned char *buf,
                                            size_t size);
/* Reads rows accumulators from exactly rows * MCSTAT_MOMENTS_BYTES bytes.
 * MCSTAT_ECORRUPT (m unchanged) when size differs or any record is corrupt
 * (see mcstat_moments_from_bytes); MCSTAT_EINVAL for NULL pointers. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_moments_from_bytes_rows(const unsigned char *buf, size_t size, size_t rows,
                                              mcstat_moments *m);

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
/* gives on the same values (O(1) per value; bench/RESULTS_check.md).      */
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
    /* reserved is 0.1.0's name of this storage */
    MCSTAT_ANONYMOUS union {
        uint64_t reserved[2];
        struct {
            uint64_t n_overflow; /* values left out because the count would pass 2^64 - 1 */
            uint64_t reserved_1; /* zero */
        };
    };
    double buf[MCSTAT_STREAM_CAPACITY];
} mcstat_stream;

/* Empties s.  MCSTAT_EINVAL for NULL. */
MCSTAT_API int mcstat_stream_init(mcstat_stream *s);
/* Adds the buffered values to s->moments and empties the buffer (non-finite
 * values are counted in n_nonfinite instead).  MCSTAT_EINVAL for NULL or an
 * uninitialised stream.  MCSTAT_ETOOBIG when the count would pass 2^64 - 1:
 * the buffered values are then left out and counted in n_overflow, and every
 * check on the stream returns MCSTAT_ETOOBIG. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_stream_flush(mcstat_stream *s);
/* dst <- dst merged with src: its moments, its buffered values and its
 * non-finite count; src is not modified (it may equal dst).  Merging a
 * thread's stream into a frame total and re-initialising the thread's
 * stream is the end-of-frame step.  MCSTAT_EINVAL; MCSTAT_ETOOBIG (dst
 * unchanged) when a count would pass 2^64 - 1. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_stream_merge(mcstat_stream *dst, const mcstat_stream *src);
/* *out <- the moments of every value s has seen (flushed or buffered),
 * without modifying s.  MCSTAT_EINVAL. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_stream_moments(const mcstat_stream *s, mcstat_moments *out);

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
MCSTAT_NODISCARD MCSTAT_API int mcstat_stream_check_mean(const mcstat_stream *s, double reference, double tolerance,
                                        double alpha, mcstat_result *out);
/* Check that the variance of the values is below `bound` (> 0): the
 * one-sample chi-squared test of var == bound against var > bound at level
 * alpha; out->reject == 1 (the variance is significantly above the bound)
 * means the check failed.  Statuses as mcstat_var_test_1, plus
 * MCSTAT_ENONFINITE as above. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_stream_check_var(const mcstat_stream *s, double bound, double alpha,
                                       mcstat_result *out);
MCSTAT_API size_t mcstat_sizeof_stream(void);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_MOMENTS_FAMILY_H */
