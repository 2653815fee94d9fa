/*
 * mcstat.h - statistical hypothesis tests for Monte Carlo estimators.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 *
 * Introduction
 *
 * mcstat decides, with a stated error rate, whether a Monte Carlo estimator
 * is right: whether its mean is a reference value (t tests), whether its
 * variance is within a bound (chi-squared and F tests), whether two
 * renderers agree (Welch's t, F, Kolmogorov-Smirnov), per pixel over whole
 * images, and whether a battery of such tests rejects more often than its
 * level allows.  The tests are those of Subr & Arvo, "Statistical
 * Hypothesis Testing for Assessing Monte Carlo Estimators"; the text blocks
 * they print are R's.
 *
 * Example: is an estimator of the integral of 3x^2 over [0, 1], which is 1,
 * unbiased?  (cc example.c $(pkg-config --cflags --libs mcstat))
 *
 *     #include <stdio.h>
 *     #include <stdlib.h>
 *     #include <mcstat.h>
 *     int main(void)
 *     {
 *         mcstat_moments m;
 *         mcstat_result r;
 *         char text[2048];
 *         mcstat_moments_init(&m);
 *         for (int i = 0; i < 100000; i++) {
 *             double u = (rand() + 0.5) / ((double)RAND_MAX + 1.0);
 *             mcstat_moments_add(&m, 3 * u * u);
 *         }
 *         if (mcstat_t_test_1_moments(&m, 1.0, MCSTAT_TWO_SIDED, 0.05, &r) != MCSTAT_OK) return 1;
 *         mcstat_result_format(&r, "estimates", NULL, text, sizeof text, NULL);
 *         fputs(text, stdout);  // R's block: statistic, p-value, interval, decision
 *         return 0;
 *     }
 *
 * The header reads in the order a user meets things, the stable API first:
 *   1. Conventions: statuses, alternatives, options that grow.
 *   2. Accumulators: mcstat_moments (one sample, streaming and mergeable),
 *      its serialized bytes, arrays of accumulators (one per pixel), and
 *      mcstat_stream (a per-thread buffer for checks inside a renderer).
 *   3. The tests and their result: mcstat_result, then t, chi-squared, F
 *      (each on arrays and on accumulators), the efficiency ratio of two
 *      estimators and Kolmogorov-Smirnov.
 *   4. Per-pixel tests: the same tests once per pixel of an image stack
 *      (mcstat_pixels_test), per row of a matrix or of an array of
 *      accumulators.
 *   5. Multiple testing: adjusted p-values (R's p.adjust) for the millions
 *      of per-pixel tests.
 *   6. Equivalence: TOST, "the bias is below eps".
 *   7. Distributions: t, chi-squared and F tails and quantiles.
 *   8. Sizes, versions and GSL's handler.
 * then, in one block, the experimental sections:
 *   9. Power and sample size.
 *  10. Estimator diagnostics: shape, tails, batch size.
 *  11. Goodness of fit: chi-squared GOF of cell counts, the exact binomial
 *      test and the battery meta-test.
 *  12. Renderer checks: do a BSDF's, an emitter's or a warp's sample(),
 *      pdf(), eval() and sample weight agree?
 *  13. Sequential tests: look after every batch, stop as soon as the
 *      evidence decides, the error rate still alpha.
 * and last
 *  14. Deprecated names, kept so that older code still builds and links.
 * Where a new function goes: in the section of its concept, named
 * mcstat_<family>_<verb> (mcstat_moments_add, mcstat_diag_compute) or
 * mcstat_<test>_test_<k>[_moments|_matrix|_moments_rows] for the tests.
 *
 * Experimental sections (9-13) are as tested and as ABI-stable as the rest,
 * but their names and options may change before 1.0; a renamed function
 * stays as a deprecated alias for the next release (and its symbol for as
 * long as the SOVERSION).  They are compiled in by default; define
 * MCSTAT_NO_EXPERIMENTAL to leave them out.
 *
 * Conventions, for every function in this header:
 *   - Fallible calls return an int status: MCSTAT_OK (0) or one of the
 *     MCSTAT_E* codes below; mcstat_strerror() gives a sentence for it.
 *     Outputs are written through the pointers given last.  A call that
 *     gives one answer (a result, a value, a struct, an accumulator it adds
 *     to) writes it only on success: on failure its outputs keep their bytes
 *     (tests/c/test_outputs_on_failure.c holds every such call to it).  The
 *     exceptions, each stated at its call: the element-wise calls (the
 *     _matrix, _moments_rows and per-pixel tests, mcstat_t_quantiles) write
 *     every element, failed ones marked by a status or NaN; the text calls
 *     (*_format) write a NUL-terminated prefix with MCSTAT_EBUFSIZE and the
 *     full length through *length; a renderer check's report carries its
 *     message with MCSTAT_ECALLBACK; mcstat_seq_finish writes the test's
 *     state with MCSTAT_EHEAVYTAIL (a sequential test never allowed to
 *     decide: its result says how far it got).
 *   - Arguments come in one order: the data (arrays and their sizes),
 *     the null value, the alternative, alpha, an options struct (NULL for
 *     the defaults), scratch memory, then the outputs.  A call on an object
 *     the caller keeps (an accumulator, a stream, a sequential test) takes
 *     the object first, as the target of what it does (mcstat_moments_add,
 *     _merge: dst then src; mcstat_stream_merge; mcstat_seq_push_*); the
 *     per-pixel tests take the test first, then the two sides and the range
 *     of pixels.  One call breaks the order otherwise, mcstat_gof_chisq_test
 *     (options before alpha, as 0.1.0's mcstat_chisq_gof it replaced): a
 *     swap there does not compile.
 *   - Nothing here calls abort() or exit(), nothing touches GSL's process-wide
 *     error handler (see mcstat_gsl_handler_off), and no call changes any
 *     global state: every function is thread-safe on distinct objects.  (The
 *     one process-wide value, whether the per-pixel loops may use AVX2, is
 *     read once, at the first per-pixel call: the CPU and MCSTAT_NO_AVX2.)
 *   - No function allocates on the accumulator path.
 *   - Results do not depend on the caller's floating-point environment:
 *     each call computes with IEEE defaults (round to nearest, subnormals
 *     kept, even under flush-to-zero) and restores the caller's mode.  The
 *     library itself must be built without -ffast-math (its sources refuse
 *     it); code including this header may use any flags.
 */

#ifndef MCSTAT_H
#define MCSTAT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* mcstat_result's anonymous unions of anonymous structs are standard C11,
 * an extension in C99 and C++: marked, so that callers building with
 * -Wpedantic get no warning (tests/c/check_header.sh). */
#if defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_ANONYMOUS __extension__
#else
#  define MCSTAT_ANONYMOUS
#endif

#if defined(_WIN32) && defined(MCSTAT_SHARED_BUILD)
#  define MCSTAT_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_API __attribute__((visibility("default")))
#else
#  define MCSTAT_API
#endif
/* MCSTAT_NODISCARD marks the calls that return a status: the compiler warns
 * when one is ignored ([[nodiscard]] in C23 and C++17, where a (void) cast
 * says it was meant; Clang's warn_unused_result before them; nothing for
 * GCC before C23, whose attribute a (void) cast cannot silence).  Define
 * MCSTAT_NO_NODISCARD before including this header to turn it off. */
#if defined(MCSTAT_NO_NODISCARD)
#  define MCSTAT_NODISCARD
#elif defined(__cplusplus) && __cplusplus >= 201703L
#  define MCSTAT_NODISCARD [[nodiscard]]
#elif !defined(__cplusplus) && defined(__STDC_VERSION__) && __STDC_VERSION__ > 201710L
#  define MCSTAT_NODISCARD [[nodiscard]]
#elif defined(__clang__)
#  define MCSTAT_NODISCARD __attribute__((warn_unused_result))
#else
#  define MCSTAT_NODISCARD
#endif
/* MCSTAT_DEPRECATED marks a name this release replaced (section "Deprecated names"): it
 * still links and gives the same results, and the compiler names the
 * replacement.  Define MCSTAT_DISABLE_DEPRECATE_WARNINGS before including
 * this header to silence the warnings. */
#if defined(MCSTAT_DISABLE_DEPRECATE_WARNINGS)
#  define MCSTAT_DEPRECATED(replacement)
#elif defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_DEPRECATED(replacement) __attribute__((deprecated("use " replacement)))
#elif defined(_MSC_VER)
#  define MCSTAT_DEPRECATED(replacement) __declspec(deprecated("use " replacement))
#else
#  define MCSTAT_DEPRECATED(replacement)
#endif

/* ======================================================================== */
/* 1. Conventions.                                                          */
/* Statuses (every fallible call returns one), alternatives (every test     */
/* takes one), and how the options structs grow and the results do not.     */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Compatibility of options and results.                                    */
/* Options structs grow.  Each starts with `uint32_t size`, which its        */
/* initialiser sets to the struct's sizeof as the caller compiled it; new    */
/* fields are only appended.  The library accepts the size of every release */
/* (MCSTAT_<NAME>_OPTIONS_SIZE_<release>), reads only that many bytes and    */
/* gives the fields the caller's version lacks their defaults: a program     */
/* built against an older header runs unchanged against a newer library.    */
/* Any other size is MCSTAT_EINVAL (a header newer than the library, or a   */
/* struct cut short).  mcstat_<name>_options_init(opt) is a macro passing   */
/* sizeof *opt to mcstat_<name>_options_init_size(opt, size), which writes  */
/* only `size` bytes; FFI callers call the latter with their struct's size. */
/*                                                                           */
/* Results do not grow.  mcstat_result (and mcstat_diagnostics) are written */
/* in full by the library, in arrays by the row-wise calls, and carry no    */
/* size field: 0.1.0 binaries allocate them without one, so the library     */
/* could not trust it.  Their size is fixed for this SOVERSION; new outputs */
/* use the per-test storage (the named unions in mcstat_result), or a new   */
/* function with its own struct.                                             */
/* ------------------------------------------------------------------------ */

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
    MCSTAT_ETOOBIG = 9,     /* the sizes are too large for the requested method (e.g. an exact
                               K-S p-value whose lattice would not fit): choose another method;
                               also an observation count that would pass 2^64 - 1 */
    MCSTAT_ECALLBACK = 10,  /* a caller's callback failed or returned invalid values (section "Renderer checks") */
    MCSTAT_EHEAVYTAIL = 11  /* the data's tails are too heavy for the method within the samples
                               seen (section "Sequential, anytime-valid tests": a sequential test never allowed to decide) */
};

/* A sentence describing status (static storage; never NULL). */
MCSTAT_API const char *mcstat_strerror(int status);

/* Why the last call on this thread refused its arguments, naming the
 * argument and its value ("options.cells must be 0 (automatic) or
 * 2..1048576, got 1"), or "" when it gave no reason.  Functions that give
 * reasons clear it when they start, so after one of them it belongs to
 * that call: in 0.3.0 the renderer checks (mcstat_check_bsdf, _emitter,
 * _warp, _phase, _medium, mcstat_check_work_size), for every MCSTAT_EINVAL
 * and MCSTAT_ETOOBIG they return.  Thread-local storage, valid until the
 * thread's next call of such a function; never NULL.  (Since 0.3.) */
MCSTAT_API const char *mcstat_last_error(void);

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
MCSTAT_NODISCARD MCSTAT_API int mcstat_alternative_parse(const char *name, int *alternative);
/* "two-sided", "less", "greater", or NULL for an invalid value. */
MCSTAT_API const char *mcstat_alternative_name(int alternative);

/* ------------------------------------------------------------------------ */
/* The numerical floor.                                                      */
/* Differences at the resolution of the caller's arithmetic are rounding,   */
/* not evidence.  The calls that take data a renderer computed (the renderer */
/* checks' options and the per-pixel options, field `resolution`) add it as */
/* a relative error of what they compare; by default it is derived from the  */
/* data: 64 units in the last place of float32 when every value is a float32 */
/* (a float formula of a few dozen operations, a normalisation rounded once, */
/* is off by up to tens of ulps), else of float64.                          */
/* ------------------------------------------------------------------------ */
#define MCSTAT_RESOLUTION_FLOAT32 0x1p-18 /* 64 * 2^-24 */
#define MCSTAT_RESOLUTION_FLOAT64 0x1p-47 /* 64 * 2^-53 */

/* Every test writes an mcstat_result ("The tests and their result"); the stream checks of
 * "Accumulators" do too. */
typedef struct mcstat_result mcstat_result;

/* ======================================================================== */
/* 2. Accumulators.                                                         */
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

/* ======================================================================== */
/* 3. The tests and their result.                                           */
/* Every test writes an mcstat_result: statistic, p-value, confidence       */
/* interval, critical values, the reject flag and the paper's three-way     */
/* decision; mcstat_result_format prints R's block.  The t, chi-squared and */
/* F tests come on arrays and on accumulators (_moments); the               */
/* Kolmogorov-Smirnov test needs the values themselves.  The sections      */
/* "Equivalence" and "Goodness of fit" fill the same struct.                */
/* ======================================================================== */

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
    MCSTAT_TEST_KS_2 = 5,  /* two-sample Kolmogorov-Smirnov, unweighted or with Canner's weight */
    MCSTAT_TEST_EQUIV_1 = 6, /* one-sample equivalence (TOST), mcstat_equivalence_test_1 */
    MCSTAT_TEST_EQUIV_2 = 7, /* Welch two-sample equivalence (TOST), mcstat_equivalence_test_2 */
    MCSTAT_TEST_BINOM = 8,   /* exact binomial test (also the battery meta-test) */
    MCSTAT_TEST_CHISQ_GOF = 9, /* Pearson's chi-squared goodness of fit of cell counts */
    MCSTAT_TEST_T_2_POOLED = 10, /* Student's two-sample t, pooled variance */
    MCSTAT_TEST_T_PAIRED = 11,   /* paired t (one-sample t on the differences) */
    MCSTAT_TEST_EFFICIENCY = 12, /* ratio of two estimators' efficiencies, mcstat_efficiency_test */
    MCSTAT_TEST_SEQ_MEAN_1 = 13, /* sequential (anytime-valid) tests, section "Sequential, anytime-valid tests" */
    MCSTAT_TEST_SEQ_MEAN_2 = 14,
    MCSTAT_TEST_SEQ_VAR_1 = 15,
    MCSTAT_TEST_SEQ_VAR_2 = 16
};

enum mcstat_method {
    MCSTAT_METHOD_ANALYTIC = 0,  /* p-value from the statistic's exact null distribution (t, chi^2, F) */
    MCSTAT_METHOD_AUTO = 1,      /* (K-S option only) let the test choose; results never carry it */
    MCSTAT_METHOD_EXACT = 2,     /* exact permutation distribution (K-S: lattice paths) */
    MCSTAT_METHOD_SIMULATE = 3,  /* Monte Carlo: p_value_se > 0 */
    MCSTAT_METHOD_ASYMPTOTIC = 4 /* a large-sample approximation */
};

struct mcstat_result {
    int32_t test;          /* enum mcstat_test */
    int32_t method;        /* enum mcstat_method: how the p-value was obtained */
    int32_t alternative;   /* enum mcstat_alternative */
    int32_t reject;        /* 1 if H0 is rejected at level alpha against `alternative` */
    int32_t decision;      /* the paper's three-way outcome: MCSTAT_DECISION_LESS (-1),
                              _EQUAL (0), _GREATER (+1) */
    /* Per-test integer outputs, 0 for tests that set none; read only those of
     * `test`.  reserved_i is 0.1.0's name of the same storage. */
    MCSTAT_ANONYMOUS union {
        int32_t reserved_i[3];
        struct {
            int32_t ks_weight;         /* KS_2: enum mcstat_ks_weight */
            int32_t chisq_cells;       /* CHISQ_GOF: cells after pooling */
            int32_t chisq_n_estimated; /* CHISQ_GOF: parameters estimated (n_estimated) */
        };
        struct {
            int32_t seq_state;         /* SEQ_*: MCSTAT_SEQ_CONTINUE or MCSTAT_SEQ_DECIDED */
            int32_t seq_hold;          /* SEQ_*: why no decision is allowed yet (MCSTAT_SEQ_HOLD_*) */
            int32_t seq_unused_;
        };
        struct {
            int32_t eff_batches_x;     /* EFFICIENCY: timed batches of x (saturates at INT32_MAX) */
            int32_t eff_batches_y;     /* EFFICIENCY: timed batches of y */
        };
    };
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
    /* Per-test outputs (described with each test below), 0 for tests that set
     * none.  The structs share storage: read only those of `test`.  reserved
     * is 0.1.0's name of the same storage. */
    MCSTAT_ANONYMOUS union {
        double reserved[7];
        struct {                      /* KS_2 */
            double ks_critical_se;    /* Monte Carlo standard error of critical[1] */
            double ks_n_sim;          /* replicates simulated (0 unless simulated) */
        };
        struct {                      /* EQUIV_1, EQUIV_2 */
            double tost_t_lower;      /* t for H1: mean > lower bound */
            double tost_t_upper;      /* t for H1: mean < upper bound */
            double tost_p_lower;      /* their one-sided p-values */
            double tost_p_upper;
            double tost_lower;        /* the bounds tested */
            double tost_upper;
        };
        struct {                      /* BINOM */
            double binom_unused_[2];
            double binom_log_p_value; /* log(p_value), finite where p_value underflows */
        };
        struct {                      /* CHISQ_GOF */
            double chisq_unused_[2];
            double chisq_cells_given;  /* k */
            double chisq_min_expected; /* smallest expected count after pooling */
            double chisq_pool_below;   /* min_expected, 0 when pooling was off */
        };
        struct {                       /* SEQ_* (section "Sequential, anytime-valid tests") */
            double seq_looks;          /* pushes so far */
            double seq_n_decided;      /* n (of x) at the look that decided; 0 while continuing */
            double seq_log_e;          /* log of the e-value (test martingale) at the last look */
            double seq_log_e_max;      /* its running maximum: p_value = min(1, exp(-seq_log_e_max)) */
            double seq_eps;            /* equivalence margin (0: none) */
            double seq_t_opt;          /* the n where the confidence sequence is tightest */
            double seq_n_gate;         /* the n the kurtosis gate asks for (0 when open) */
        };
        struct {                       /* EFFICIENCY */
            double eff_var_ratio;      /* s_y^2 / s_x^2 (x's advantage in variance) */
            double eff_time_ratio;     /* mean time y / mean time x (x's advantage in time) */
            double eff_se_log_var_x;   /* delta-method standard errors of the four logs */
            double eff_se_log_var_y;
            double eff_se_log_time_x;
            double eff_se_log_time_y;
        };
    };
};

/* Values of mcstat_result.decision. */
#define MCSTAT_DECISION_LESS (-1)
#define MCSTAT_DECISION_EQUAL 0
#define MCSTAT_DECISION_GREATER 1

/* Deprecated (0.1.0) accessors of the per-test outputs, kept so that old
 * code compiles: use the named fields (MCSTAT_RESULT_KS_WEIGHT(r) is
 * r->ks_weight, MCSTAT_RESULT_N_SIM(r) r->ks_n_sim, ...). */
#define MCSTAT_RESULT_TOST_T_LOWER(r) ((r)->tost_t_lower)
#define MCSTAT_RESULT_TOST_T_UPPER(r) ((r)->tost_t_upper)
#define MCSTAT_RESULT_TOST_P_LOWER(r) ((r)->tost_p_lower)
#define MCSTAT_RESULT_TOST_P_UPPER(r) ((r)->tost_p_upper)
#define MCSTAT_RESULT_TOST_LOWER(r) ((r)->tost_lower)
#define MCSTAT_RESULT_TOST_UPPER(r) ((r)->tost_upper)
#define MCSTAT_RESULT_KS_WEIGHT(r) ((r)->ks_weight)
#define MCSTAT_RESULT_CRITICAL_SE(r) ((r)->ks_critical_se)
#define MCSTAT_RESULT_N_SIM(r) ((r)->ks_n_sim)
#define MCSTAT_RESULT_LOG_P_VALUE(r) ((r)->binom_log_p_value)
#define MCSTAT_RESULT_CHISQ_CELLS(r) ((r)->chisq_cells)
#define MCSTAT_RESULT_CHISQ_ESTIMATED(r) ((r)->chisq_n_estimated)
#define MCSTAT_RESULT_CHISQ_CELLS_GIVEN(r) ((r)->chisq_cells_given)
#define MCSTAT_RESULT_CHISQ_MIN_EXPECTED(r) ((r)->chisq_min_expected)
#define MCSTAT_RESULT_CHISQ_POOL_BELOW(r) ((r)->chisq_pool_below)

/* The decision rule (the paper's three-way outcome, its figure 4): `reject`
 * is the test against the chosen alternative at level alpha; `decision` is
 * 0 (MCSTAT_DECISION_EQUAL) when H0 is not rejected, else the sign of the
 * estimate's deviation from the null value (MCSTAT_DECISION_LESS or
 * _GREATER).  With the two-sided alternative this is the paper's less /
 * equal / greater outcome. */

/* Writes the R-style block (the layout and number formatting of R's
 * print.htest, plus a final "decision at alpha = ...: ..." line) into buf.
 * x_name and y_name name the data ("x" and "y" when NULL).  *length (may be
 * NULL) receives the length of the full text, without the terminating NUL;
 * MCSTAT_EBUFSIZE when it does not fit in size bytes (buf then holds a
 * NUL-terminated prefix). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_result_format(const mcstat_result *r, const char *x_name,
                                    const char *y_name, char *buf, size_t size,
                                    size_t *length);

/* "less", "equal" or "greater" for a decision value, NULL otherwise. */
MCSTAT_API const char *mcstat_decision_name(int decision);

/* *log_p <- the natural log of r's p-value, finite wherever the tail is
 * representable in log even when p_value underflows to 0: t, chi-squared
 * and F tests from the statistic and df through the log tails of section
 * 11 (two-sided: log 2 + the smaller log tail, capped at 0; the
 * efficiency test's t likewise); TOST the
 * larger of its two one-sided log p's; the binomial test its
 * binom_log_p_value; K-S the log of Kolmogorov's limit when asymptotic
 * (unweighted), else log(p_value) (exact and simulated p-values carry no
 * more).  MCSTAT_EINVAL for NULL, an unknown test or a result whose fields
 * are NaN (a failed row). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_result_log_p_value(const mcstat_result *r, double *log_p);

/* conf_int <- r's confidence interval at confidence_level in (0, 1) in
 * place of 1 - alpha, for the same alternative (one-sided ones keep their
 * infinite end, or 0 for a variance):
 *   t tests   estimate +- t quantile * std_error on the result's df, the
 *             estimate (the difference for two samples) taken from the
 *             stored estimates or as null_value + statistic * std_error,
 *             whichever rounds less (so a 1e9 offset keeps its digits);
 *   TOST      the two-sided t interval at that level (the result's own
 *             conf_int is the one at 1 - 2 alpha that TOST amounts to);
 *   variance  [X^2 sigma0^2 / c1, X^2 sigma0^2 / c0], chi-squared quantiles;
 *   F         [F ratio0 / c1, F ratio0 / c0], F quantiles;
 *   binomial  Clopper-Pearson, as the test's.
 *   efficiency exp(log rho_hat +- t quantile * std_error) (log rho_hat =
 *             log null_value + statistic * std_error).
 * At level 1 - alpha it reproduces r->conf_int to rounding.  MCSTAT_EINVAL
 * for NULL, a level outside (0, 1) (or NaN), a test with no parameter
 * interval (K-S, chi-squared goodness of fit) or a result whose fields are
 * NaN; MCSTAT_ENUMERIC if a bound cannot be formed. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_result_conf_int(const mcstat_result *r, double confidence_level, double conf_int[2]);

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
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_1(const double *x, size_t n, double mu0, int alternative,
                               double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_1_moments(const mcstat_moments *x, double mu0, int alternative,
                                       double alpha, mcstat_result *out);

/* Welch's two-sample t test of mean(x) - mean(y) against mu0 (section 2.3,
 * eq. 3, Welch-Satterthwaite degrees of freedom). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2(const double *x, size_t nx, const double *y, size_t ny,
                               double mu0, int alternative, double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_moments(const mcstat_moments *x, const mcstat_moments *y,
                                       double mu0, int alternative, double alpha,
                                       mcstat_result *out);

/* Student's two-sample t test with pooled variance (R's t.test(var.equal =
 * TRUE), SciPy's ttest_ind default): s_p^2 = (M2_x + M2_y)/(nx + ny - 2),
 * standard error s_p sqrt(1/nx + 1/ny), df = nx + ny - 2; test
 * MCSTAT_TEST_T_2_POOLED, estimates as Welch's.  MCSTAT_EDEGENERATE only
 * when both samples are constant (as Welch). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_pooled(const double *x, size_t nx, const double *y, size_t ny,
                                      double mu0, int alternative, double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_pooled_moments(const mcstat_moments *x, const mcstat_moments *y,
                                              double mu0, int alternative, double alpha,
                                              mcstat_result *out);

/* Paired t test of mean(x - y) against mu0 (R's t.test(paired = TRUE),
 * SciPy's ttest_rel): the one-sample t on the n differences x_i - y_i, each
 * one rounding of the exact difference, accumulated as mcstat_moments (a
 * difference that overflows is taken halved, with mu0 halved: t, df and p
 * are unchanged).  Test MCSTAT_TEST_T_PAIRED; n[0] = n[1] = n pairs;
 * estimate[0] the mean difference; df = n - 1.  MCSTAT_ENONFINITE for NaN
 * or +-Inf in x or y, MCSTAT_ETOOFEW for n < 2, MCSTAT_EDEGENERATE when the
 * differences are constant. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_paired(const double *x, const double *y, size_t n, double mu0,
                                    int alternative, double alpha, mcstat_result *out);

/* One-sample chi-squared test of var(x) against sigma2 > 0: statistic
 * (n-1) s^2 / sigma2 on n-1 degrees of freedom (section 2.2, eq. 2). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_1(const double *x, size_t n, double sigma2, int alternative,
                                 double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_1_moments(const mcstat_moments *x, double sigma2,
                                         int alternative, double alpha, mcstat_result *out);

/* Two-sample F test of var(x)/var(y) against ratio > 0: statistic
 * (s_x^2 / s_y^2) / ratio on (nx-1, ny-1) degrees of freedom (section 2.4). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_2(const double *x, size_t nx, const double *y, size_t ny,
                                 double ratio, int alternative, double alpha,
                                 mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_2_moments(const mcstat_moments *x, const mcstat_moments *y,
                                         double ratio, int alternative, double alpha,
                                         mcstat_result *out);

/* ------------------------------------------------------------------------ */
/* Efficiency ratio of two estimators.                                       */
/* "B converges 2x faster than A" is a claim about efficiency, 1 / (variance */
/* per sample x time per sample) (Kalos & Whitlock), both factors measured   */
/* with error. The parameter is rho = eff(x) / eff(y) = (var_y tau_y) /      */
/* (var_x tau_x); MCSTAT_GREATER means x is the more efficient. x and y      */
/* accumulate the estimators' samples; time_x and time_y the time per sample */
/* of k >= 2 timed batches each (a batch's wall time / its size), timed      */
/* interleaved so that machine load affects both. log rho_hat = log s_y^2 -  */
/* log s_x^2 + log tau_y - log tau_x; its standard error adds the delta      */
/* method's (beta2 - (n-3)/(n-1))/n for each log s^2 (beta2 = n M4/M2^2, the */
/* exact variance of s^2 without assuming normal data) and s_tau^2/(k tau^2) */
/* for each log mean time; the statistic (log rho_hat - log ratio) / se is   */
/* referred to a t on Satterthwaite's df (k - 1 per time part, 2/Var per     */
/* variance part). Assumptions: independent samples and batches, finite      */
/* fourth moments; asymptotic in the samples and the batches.                */
/* Calibration (tests/c/test_efficiency.c holds it to binomial bounds): the */
/* rejection rate under H0 is alpha for exponential data (n = 1000, 5 or 10  */
/* timed batches) and for 99%-zero data with ~500 non-zero values per        */
/* sample; with ~20 non-zero values the sample kurtosis underestimates the   */
/* tail and the rate is up to twice alpha: a claim needs hundreds of         */
/* non-zero samples, and a p-value near alpha is weaker evidence than it     */
/* reads.                                                                    */
/* Result: test MCSTAT_TEST_EFFICIENCY, method MCSTAT_METHOD_ASYMPTOTIC;     */
/* statistic and critical values on the t scale, df[0]; conf_int the         */
/* interval for rho (exp of the log interval; 0 and +Inf the open ends);     */
/* estimate[0] rho_hat, estimate[1] s_y^2 / s_x^2; null_value ratio;         */
/* std_error the standard error of log rho_hat; decision the sign of log     */
/* rho_hat - log ratio when rejected; n[] the sample sizes; per-test fields  */
/* eff_var_ratio, eff_time_ratio, the four standard errors eff_se_log_*,     */
/* eff_batches_x/_y. An estimate or bound beyond the doubles is +Inf or 0;   */
/* statistic and p-value, formed in logs, stay exact.                        */
/* Statuses: MCSTAT_EINVAL (NULL, alpha outside (0, 1), ratio <= 0 or not    */
/* finite, a bad alternative, an uninitialised accumulator, a negative       */
/* time), MCSTAT_ETOOFEW (n < 2 in x or y, fewer than 2 timed batches),      */
/* MCSTAT_EDEGENERATE (x or y constant, or every batch timed as 0: a timer   */
/* too coarse), MCSTAT_ENUMERIC (not expected: a guard against NaN). Equal   */
/* batch times are accepted: an exact cost (operation counts) contributes no */
/* error.                                                                    */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_API int mcstat_efficiency_test(const mcstat_moments *x, const mcstat_moments *y,
                                      const mcstat_moments *time_x, const mcstat_moments *time_y,
                                      double ratio, int alternative, double alpha, mcstat_result *out);

/* ------------------------------------------------------------------------ */
/* Two-sample Kolmogorov-Smirnov test (the paper's section 2.5).            */
/* F and G are the empirical CDFs #{x_i <= t}/nx and #{y_j <= t}/ny, z =     */
/* (nx F + ny G)/(nx + ny) the pooled one.  They are compared at the pooled  */
/* jump points only, and where values are tied only after the last of a run */
/* of equal values.  The statistic is                                        */
/*   weight NONE:   D  = sup |F - G|                     (as R and SciPy)    */
/*   weight CANNER: D2 = sqrt(nx ny/(nx+ny)) sup |F - G| / sqrt(z (1 - z)),  */
/*                  the sup over jump points with 0 < z < 1.                 */
/* Alternatives are claims about the first sample, as for every mcstat test */
/* (the paper's section 3 words one of them the other way): MCSTAT_LESS =  */
/* x tends to be smaller than y, i.e. its CDF lies above, sup (F - G);      */
/* MCSTAT_GREATER = x tends to be larger, sup (G - F).                      */
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
/*              per AVX2 kernel step; O(N) per replicate, costs in          */
/*              bench/RESULTS_ks.md); optionally cached (mcstat_ks_cache).   */
/*   ASYMPTOTIC weight NONE only: Kolmogorov's limit at sqrt(ne) D (ne =    */
/*              nx ny/N), one-sided exp(-2 ne D^2); conservative, p within  */
/*              2% at 300+300 and beyond (bench/RESULTS_ks.md; Stephens'     */
/*              correction was measured and is anti-conservative here).      */
/*              Canner's statistic has no usable limit (it grows like       */
/*              sqrt(2 log log n)):                                          */
/*              MCSTAT_EINVAL.                                               */
/*   AUTO       EXACT when (min+1)(N+1) <= MCSTAT_KS_AUTO_EXACT_WORK, else   */
/*              SIMULATE (Canner, or NONE with ties) or ASYMPTOTIC (NONE     */
/*              without ties).                                               */
/* Result fields: statistic D or D2; critical[1] is the value above which H0 */
/* is rejected at alpha (reject == statistic > critical[1] == p <= alpha),   */
/* critical[0] = -Inf; decision is 0, or -1 ("less": x tends to be smaller, */
/* its CDF lies above where the (weighted) deviation is largest) or +1.  df, */
/* estimate, conf_int, null_value, std_error are NaN.  Per-test fields:     */
/*   ks_weight       enum mcstat_ks_weight                                   */
/*   ks_critical_se  Monte Carlo standard error of critical[1] (0 unless     */
/*                   simulated)                                              */
/*   ks_n_sim        replicates simulated                                    */
/* ------------------------------------------------------------------------ */
enum mcstat_ks_weight {
    MCSTAT_KS_WEIGHT_NONE = 0,  /* the classical (Smirnov) statistic */
    MCSTAT_KS_WEIGHT_CANNER = 1 /* Canner's [z(1-z)]^(-1/2) (the paper's) */
};

/* Size limits of the exact method, in lattice cells (min(nx,ny)+1)(nx+ny+1).
 * The recursion only visits the band of points that the threshold has not
 * absorbed and whose probability is above 2^-1000, O(sqrt(N)) wide, so its
 * time grows like N^1.5; the critical value (a search) costs 10-40
 * p-values (figures: bench/RESULTS_ks.md). */
#define MCSTAT_KS_EXACT_MAX_WORK 2e11  /* ~3.2e5 + 3.2e5, seconds: beyond, MCSTAT_ETOOBIG */
#define MCSTAT_KS_AUTO_EXACT_WORK 1.6e7 /* ~2800 + 2800 (costs: bench/RESULTS_ks.md) */
#define MCSTAT_KS_DEFAULT_N_SIM 10000

/* A cache of simulated null distributions, owned by the caller and shared by
 * any number of threads (it has its own lock).  Entries are keyed by (nx, ny,
 * weight, alternative, n_sim, seed, tie pattern), so a battery of tests at
 * the same sizes simulates once.  When adding an entry would exceed
 * max_bytes, the least recently used entries are dropped. */
typedef struct mcstat_ks_cache mcstat_ks_cache;
/* MCSTAT_EINVAL (cache NULL), MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_ks_cache_new(size_t max_bytes, mcstat_ks_cache **cache);
/* Frees the cache (NULL is a no-op); no test may be using it. */
MCSTAT_API void mcstat_ks_cache_free(mcstat_ks_cache *cache);
/* Lookups that found an entry, lookups that did not, entries held (any may be NULL). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_ks_cache_stats(const mcstat_ks_cache *cache, uint64_t *hits,
                                     uint64_t *misses, uint64_t *entries);

/* Options; grows by appending fields ("Conventions", compatibility), so
 * always start from the initialiser. */
typedef struct mcstat_ks_options {
    uint32_t size;          /* sizeof(mcstat_ks_options): set by the initialiser */
    int32_t weight;         /* enum mcstat_ks_weight; default CANNER */
    int32_t method;         /* MCSTAT_METHOD_AUTO (default), _EXACT, _SIMULATE, _ASYMPTOTIC */
    int32_t threads;        /* threads for simulation and sorting, 1..64; default 1:
                               no thread is started unless the caller asks */
    int64_t n_sim;          /* replicates when simulating, >= 1; default 10000 */
    uint64_t seed;          /* simulation seed; default 0 */
    mcstat_ks_cache *cache; /* simulated distributions to reuse; NULL: none */
    int32_t critical;       /* 1: compute critical[1] (exact: a search costing 10-40
                               p-value computations); 0: leave it NaN; default 1 */
    int32_t reserved;       /* zero */
} mcstat_ks_options;

#define MCSTAT_KS_OPTIONS_INIT \
    {sizeof(mcstat_ks_options), MCSTAT_KS_WEIGHT_CANNER, MCSTAT_METHOD_AUTO, 1, \
     MCSTAT_KS_DEFAULT_N_SIM, 0u, NULL, 1, 0}

/* sizeof(mcstat_ks_options) in each release that changed it. */
#define MCSTAT_KS_OPTIONS_SIZE_0_1 48u
/* Sets the first `size` bytes of *opt to MCSTAT_KS_OPTIONS_INIT, with
 * opt->size = size: `size` is sizeof(mcstat_ks_options) as the caller
 * compiled it (FFI callers: their struct's size), so nothing beyond the
 * caller's struct is written.  MCSTAT_EINVAL (nothing written) for NULL or
 * a size no release had. */
MCSTAT_API int mcstat_ks_options_init_size(mcstat_ks_options *opt, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_KS_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_ks_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_API int(mcstat_ks_options_init)(mcstat_ks_options *opt);
#define mcstat_ks_options_init(opt) mcstat_ks_options_init_size((opt), sizeof *(opt))
MCSTAT_API size_t mcstat_sizeof_ks_options(void);

/* The two-sample K-S test of x against y.  opt may be NULL (the defaults).
 * Statuses: MCSTAT_EINVAL (NULL data or out, bad enum, alpha outside (0,1),
 * n_sim < 1, threads outside 1..64, an options size this library does not
 * know, ASYMPTOTIC with Canner's weight), MCSTAT_ETOOFEW (an empty sample),
 * MCSTAT_ENONFINITE (NaN in the data; +-Inf are ordinary, ordered values),
 * MCSTAT_ETOOBIG (nx*ny >= 2^62, or EXACT beyond MCSTAT_KS_EXACT_MAX_WORK),
 * MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_ks_test_2(const double *x, size_t nx, const double *y, size_t ny,
                                int alternative, double alpha, const mcstat_ks_options *opt,
                                mcstat_result *out);

/* ======================================================================== */
/* 4. Per-pixel tests.                                                      */
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
/* two-sample ones: section "Deprecated names").  out[i] receives row i's   */
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

/* ======================================================================== */
/* 5. Multiple testing.                                                     */
/* A per-pixel comparison makes millions of tests: adjust their p-values    */
/* before reading the map.                                                  */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Multiple testing: adjusted p-values, as R's p.adjust.                     */
/* A per-pixel comparison makes millions of tests; at level alpha each, a    */
/* fraction alpha of the unchanged pixels is rejected by chance.  Adjusted   */
/* p-values compared with alpha control the family-wise error rate          */
/* (Bonferroni, Holm, Hochberg, Hommel) or the false discovery rate (BH:     */
/* Benjamini & Hochberg; BY: Benjamini & Yekutieli, valid under any          */
/* dependence; e-BH, mcstat_e_bh below, too).  The values are R's          */
/* p.adjust's, to rounding (R has no e-BH): NaN entries are R's NA (they     */
/* stay NaN, and n, the number of tests, counts the others);                 */
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
    MCSTAT_P_ADJUST_BY = 6,         /* Benjamini-Yekutieli (FDR, any dependence) */
    MCSTAT_P_ADJUST_E_BH = 7        /* e-BH on calibrated p-values (FDR, any dependence) */
};

/* Parses R's names: "none", "bonferroni", "holm", "hochberg", "hommel", "BH"
 * (also "fdr"), "BY"; and statsmodels' multipletests names for the same
 * methods: "b", "bonf"; "h" (Holm); "sh", "simes-hochberg"; "ho";
 * "fdr_bh", "fdr_i", "fdr_p", "fdri", "fdrp"; "fdr_by", "fdr_n", "fdr_c",
 * "fdrn", "fdrcorr"; "e-BH" (also "ebh", "e_bh").  Case is ignored (ASCII).  MCSTAT_EINVAL for anything
 * else, statsmodels' methods this library lacks included ("sidak",
 * "holm-sidak", "fdr_tsbh", "fdr_tsbky", "fdr_gbs", ...). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_p_adjust_method_parse(const char *name, int *method);
/* R's name of a method ("BH", "holm", ...), or NULL for an invalid value. */
MCSTAT_API const char *mcstat_p_adjust_method_name(int method);
/* *bytes <- the workspace mcstat_p_adjust needs for n p-values: 0 for none
 * and bonferroni, 32 n for holm, hochberg, BH, BY and e-BH (and
 * mcstat_e_bh), 40 n for hommel (on
 * 64-bit machines).  MCSTAT_EINVAL (bad method, bytes NULL), MCSTAT_ETOOBIG
 * (the size does not fit in a size_t). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_p_adjust_work_size(size_t n, int method, size_t *bytes);
/* adjusted[0..n) <- the adjusted p[0..n) (adjusted may equal p: in place).
 * work: work_bytes of scratch aligned for double (mcstat_p_adjust_work_size),
 * or NULL, in which case the call allocates it with malloc and frees it
 * before returning.  Statuses: MCSTAT_EINVAL (p or adjusted NULL with n > 0,
 * a bad method, a p-value outside [0, 1] other than NaN, misaligned work;
 * nothing written), MCSTAT_EBUFSIZE (work_bytes too small), MCSTAT_ENOMEM
 * (work NULL and the allocation failed), MCSTAT_ETOOBIG. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_p_adjust(const double *p, size_t n, int method, void *work, size_t work_bytes,
                               double *adjusted);
/* e-BH (Wang & Ramdas 2022): FDR control from e-values, valid under any
 * dependence among them.  With e_(1) >= ... >= e_(n) it rejects the k*
 * largest, k* = max{k : k e_(k) / n >= 1/alpha}; adjusted[i] <- the
 * value of e[i], min over k >= its rank of n / (k e_(k)), capped at 1, so
 * that "reject iff adjusted <= alpha" is that rule at every alpha.  e[i] in
 * [0, +inf]; NaN entries stay NaN and are not counted in n; one e-value
 * gives min(1, 1/e).  Workspace and statuses as mcstat_p_adjust's with
 * method MCSTAT_P_ADJUST_E_BH (MCSTAT_EINVAL: an e-value < 0).
 * MCSTAT_P_ADJUST_E_BH in mcstat_p_adjust is this on the e-values e =
 * kappa p^(kappa - 1), kappa = 1/10, of the p-values (E[e] <= 1 for a valid
 * p): valid under any dependence among the p-values, but less powerful
 * than BY on the same p-values (the k-th rejection needs p_(k) <= (k alpha
 * / (10 n))^(10/9), BY's p_(k) <= k alpha / (n H_n), H_n = 1 + ... + 1/n;
 * about 5 times smaller for a first rejection among 2304 tests at 0.05).
 * Up to n = 12366 (H_n <= 10: H_n p <= 10 p^(9/10) term by term) BY's
 * adjusted values are never larger.
 * On p-values BY is the more powerful of the two; mcstat_e_bh is for
 * e-values proper (likelihood ratios, sequential tests' betting wealth). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_e_bh(const double *e, size_t n, void *work, size_t work_bytes, double *adjusted);

/* ------------------------------------------------------------------------ */
/* Escalation instead of reruns: a two-stage test (Bauer & Koehne 1994).     */
/* A test suite that reruns a failed statistical test until it passes has   */
/* no error rate left.  Escalation keeps it: stage 1 tests n samples and     */
/* gives p1; p1 <= alpha1 rejects, p1 > alpha0 passes, and in between the   */
/* test continues on fresh samples (an independent stage 2, of any size     */
/* chosen after seeing stage 1) giving p2, and rejects when p1 p2 <= c     */
/* (Fisher's product).  With c = (alpha - alpha1) / ln(alpha0 / alpha1) the  */
/* probability of a rejection under H0 is alpha1 + c ln(alpha0 / alpha1) =   */
/* alpha exactly for uniform p-values, at most alpha for valid (super-      */
/* uniform) ones such as discrete tests' or a Holm battery's smallest       */
/* adjusted p-value; the stages must be independent (fresh random numbers). */
/* A correct test escalates with probability alpha0 - alpha1, so it costs    */
/* on average n1 + (alpha0 - alpha1) n2 samples; a borderline error, whose   */
/* p1 falls between the bounds, is judged on n1 + n2.                        */
/* ------------------------------------------------------------------------ */
typedef struct mcstat_escalation {
    double alpha;  /* the level of the whole two-stage test */
    double alpha1; /* stage 1 rejects when p1 <= alpha1 */
    double alpha0; /* stage 1 passes when p1 > alpha0, escalates when alpha1 < p1 <= alpha0 */
    double c;      /* stage 2 rejects when p1 p2 <= c (c <= alpha1) */
} mcstat_escalation;

/* The decisions of mcstat_escalation_decide. */
enum mcstat_escalation_decision {
    MCSTAT_ESCALATION_PASS = 0,     /* no evidence against H0 at alpha */
    MCSTAT_ESCALATION_REJECT = 1,   /* H0 rejected at alpha */
    MCSTAT_ESCALATION_CONTINUE = 2  /* stage 1 was inconclusive: run stage 2 */
};

/* *out <- the design of level alpha in (0, 1) that spends alpha1 = share1
 * alpha at stage 1 (share1 in (0, 1); 1/2 is a good default) and escalates
 * up to alpha0 in (alpha1, 1].  MCSTAT_EINVAL for arguments outside those
 * ranges, NaN included, or when alpha0 is so close to alpha1 that stage 2
 * could not spend the rest (c > alpha1, i.e. alpha0 < alpha1
 * e^((1 - share1) / share1)); nothing written then. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_escalation_design(double alpha, double share1, double alpha0, mcstat_escalation *out);
/* *decision <- the design's decision (enum mcstat_escalation_decision) on
 * stage 1's p1 alone (p2 NaN), or on both stages (p2 in [0, 1]: valid only
 * when stage 1 said MCSTAT_ESCALATION_CONTINUE, MCSTAT_EINVAL otherwise).
 * MCSTAT_EINVAL: design or decision NULL, a design mcstat_escalation_design
 * would not make, p1 outside [0, 1] (NaN included), p2 neither NaN nor in
 * [0, 1]. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_escalation_decide(const mcstat_escalation *design, double p1, double p2, int *decision);

/* ======================================================================== */
/* 6. Equivalence.                                                          */
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

/* ======================================================================== */
/* 7. Distributions.                                                        */
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

/* ======================================================================== */
/* 8. Sizes, versions and GSL's handler.                                    */
/* Constants as functions for FFI callers (every size is                    */
/* mcstat_sizeof_<thing>), the release and ABI numbers, and the opt-in to   */
/* GSL's error handler off.                                                 */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Sizes and constants as functions, for FFI callers that cannot read       */
/* macros or sizeof.  (Each options struct's size sits beside it.)          */
/* ------------------------------------------------------------------------ */
MCSTAT_API size_t mcstat_sizeof_moments(void);
MCSTAT_API size_t mcstat_sizeof_result(void);
/* MCSTAT_MOMENTS_BYTES: the size of the serialized form of one accumulator. */
MCSTAT_API size_t mcstat_sizeof_moments_bytes(void);

/* ------------------------------------------------------------------------ */
/* Versions.                                                                 */
/* MCSTAT_VERSION_MAJOR/MINOR/PATCH is the release, written here only: the   */
/* build (CMakeLists.txt), the Python package (pyproject.toml) read it from  */
/* this header, and the Rust and Go bindings' tests check theirs against it. */
/* MCSTAT_SOVERSION is the ABI: the shared library is libmcstat.so.N.  It    */
/* changes only with an incompatible change, one that breaks a binary built  */
/* against an earlier release with this SOVERSION (a function removed or its */
/* signature changed, a public struct's size or layout changed, an enum     */
/* value renumbered), never with the release number alone; additions keep   */
/* it.  libmcstat/abi/ holds the ABI (abidw) of every release of this      */
/* SOVERSION and `make abi-check` compares every build against each.        */
/* ------------------------------------------------------------------------ */
#define MCSTAT_VERSION_MAJOR 0
#define MCSTAT_VERSION_MINOR 2
#define MCSTAT_VERSION_PATCH 0
/* The shared library's ABI version (its SOVERSION; see above). */
#define MCSTAT_SOVERSION 0
#define MCSTAT_VERSION_NUMBER \
    (MCSTAT_VERSION_MAJOR * 10000 + MCSTAT_VERSION_MINOR * 100 + MCSTAT_VERSION_PATCH)

/* MCSTAT_VERSION_NUMBER of the library actually linked. */
MCSTAT_API unsigned mcstat_version_number(void);
/* "MAJOR.MINOR.PATCH" of the library actually linked (static storage). */
MCSTAT_API const char *mcstat_version(void);

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

/* ======================================================================== */
/* EXPERIMENTAL: every section from here to "Deprecated names".             */
/* Power and sample size, estimator diagnostics, goodness of fit, the       */
/* renderer checks and the sequential tests: tested and held to the ABI     */
/* like the rest, but their names and options may change before 1.0 (a      */
/* renamed function stays as a deprecated alias for the next release, as    */
/* in "Deprecated names").                                                  */
/* ======================================================================== */
/* Compiled in by default.  A program that wants to be sure it uses no
 * experimental name defines MCSTAT_NO_EXPERIMENTAL before including this
 * header: the experimental sections (and the deprecated names of their
 * families) are then left out, and any use is a compile error.  The library exports them
 * either way. */
#ifndef MCSTAT_NO_EXPERIMENTAL

/* ------------------------------------------------------------------------ */
/* 9. Power and sample size.                                 (experimental) */
/* Given all but one of n, effect, alpha and power, mcstat_power_solve finds */
/* the missing one (as R's power.t.test and statsmodels' solve_power); n is */
/* the smallest integer whose power reaches the target.  The tests and what */
/* `effect` means (the statistic's distribution under the alternative):     */
/*   T_1    one-sample t: d = (mean - mu0)/sd; noncentral t, df n-1,         */
/*          ncp sqrt(n) d                                                    */
/*   T_2    two-sample t with n per group and a common sd (R's               */
/*          power.t.test type = "two.sample"): d = (mean_x - mean_y)/sd;     */
/*          noncentral t, df 2(n-1), ncp sqrt(n/2) d                          */
/*   WELCH  Welch's t with nx = n, ny = n_ratio n, sd_y = sd_ratio sd_x:     */
/*          d = (mean_x - mean_y)/sd_x; noncentral t with the Welch-         */
/*          Satterthwaite df of the true variances, ncp d/sqrt(1/nx +        */
/*          sd_ratio^2/ny) (an approximation, checked by simulation in the  */
/*          tests; ny may be fractional: round it up)                        */
/*   VAR_1  chi-squared test: rho = sigma^2/sigma0^2 > 0; exact, the         */
/*          statistic is rho chi^2(n-1)                                      */
/*   VAR_2  F test with nx = n, ny = n_ratio n: rho = (var_x/var_y)/ratio0;  */
/*          exact, the statistic is rho F(nx-1, ny-1)                        */
/* alternative as in the tests (LESS: the effect is negative, rho < 1).     */
/* Two-sided: strict = 1 (default) counts rejections in both tails, the     */
/* true rejection probability (R's strict = TRUE); strict = 0 only the tail */
/* the effect points to (R's default).  Solving for the effect gives the    */
/* solution on the side the alternative names (d > 0, rho > 1 when two-    */
/* sided).  Accuracy: chi-squared and F power to ~1e-13 relative; the      */
/* noncentral t is R's pnt (libRmath), about 1e-12 absolute (not relative:  */
/* a power below 1e-12 is noise), and for |ncp| > 37.62 or df > 4e5 it is  */
/* Abramowitz & Stegun 26.7.10's normal approximation, whose error is      */
/* O(1/df): negligible at df > 4e5; at |ncp| > 37.62 the power is 1 to     */
/* double precision from df = 2 on (SciPy's nct: 1 - 2.5e-31 at df 2, ncp */
/* 38), but at df = 1 (n = 2) it is off by 2e-3 (0.99918 for 0.99713).    */
/* pnt is called so that it never prints (see                               */
/* src/noncentral.c).                                                        */
/* ------------------------------------------------------------------------ */
/* The power enum names the designs, not the tests: it has the pooled
 * two-sample t (T_2) that mcstat_test lacks, so its values differ from
 * enum mcstat_test's (MCSTAT_POWER_VAR_1 is 4, MCSTAT_TEST_VAR_1 is 3).
 * Both numberings are ABI and stay; never pass one enum's value as the
 * other's. */
enum mcstat_power_test {
    MCSTAT_POWER_T_1 = 1,
    MCSTAT_POWER_T_2 = 2,
    MCSTAT_POWER_WELCH = 3,
    MCSTAT_POWER_VAR_1 = 4,
    MCSTAT_POWER_VAR_2 = 5
};
enum mcstat_power_unknown {
    MCSTAT_POWER_SOLVE_POWER = 0,
    MCSTAT_POWER_SOLVE_N = 1,
    MCSTAT_POWER_SOLVE_EFFECT = 2,
    MCSTAT_POWER_SOLVE_ALPHA = 3,
    /* n as a real number, the root of power(n) = target (R's power.t.test's
     * n; SOLVE_N gives the smallest integer reaching the target, this
     * rounded up when it is not one); out->power is left at the target */
    MCSTAT_POWER_SOLVE_N_EXACT = 4
};

/* Grows by appending fields ("Conventions", compatibility): always start
 * from the initialiser (n, effect and power start at 0: unset, invalid
 * until given). */
typedef struct mcstat_power_options {
    uint32_t size;       /* sizeof(mcstat_power_options): set by the initialiser */
    int32_t test;        /* enum mcstat_power_test; default T_1 */
    int32_t alternative; /* enum mcstat_alternative; default TWO_SIDED */
    int32_t strict;      /* two-sided: 1 both tails (default), 0 the effect's tail */
    double n;            /* observations (per group for T_2, of x for WELCH and VAR_2), >= 2 */
    double n_ratio;      /* WELCH, VAR_2: ny = n_ratio n (ny >= 2); default 1 */
    double sd_ratio;     /* WELCH: sd_y / sd_x > 0; default 1 */
    double effect;       /* d (t tests, finite) or rho (variance tests, > 0) */
    double alpha;        /* significance level in (0, 1); default 0.05 */
    double power;        /* in (0, 1) */
    double reserved[4];  /* zero */
} mcstat_power_options;

#define MCSTAT_POWER_OPTIONS_INIT \
    {sizeof(mcstat_power_options), MCSTAT_POWER_T_1, MCSTAT_TWO_SIDED, 1, 0.0, 1.0, 1.0, 0.0, \
     0.05, 0.0, {0.0, 0.0, 0.0, 0.0}}

/* sizeof(mcstat_power_options) in each release that changed it. */
#define MCSTAT_POWER_OPTIONS_SIZE_0_1 96u
/* Sets the first `size` bytes of *o to MCSTAT_POWER_OPTIONS_INIT, with
 * o->size = size: `size` is sizeof(mcstat_power_options) as the caller
 * compiled it (FFI callers: their struct's size), so nothing beyond the
 * caller's struct is written.  MCSTAT_EINVAL (nothing written) for NULL or
 * a size no release had. */
MCSTAT_API int mcstat_power_options_init_size(mcstat_power_options *o, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_POWER_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_power_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_API int(mcstat_power_options_init)(mcstat_power_options *o);
#define mcstat_power_options_init(o) mcstat_power_options_init_size((o), sizeof *(o))
MCSTAT_API size_t mcstat_sizeof_power_options(void);
/* *power <- the power at o->n, o->effect, o->alpha (o->power is ignored).
 * MCSTAT_EINVAL (NULL, bad enum or size, n < 2, ny < 2, an effect out of
 * its domain, alpha outside (0, 1)), MCSTAT_ENUMERIC. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_power_compute(const mcstat_power_options *o, double *power);
/* *out <- *o with the field named by `unknown` (enum mcstat_power_unknown)
 * solved for; the other three must be valid (the unknown's field is
 * ignored); out receives o->size bytes, the caller's version of the
 * struct (out may equal o).  Solving for n also sets out->power to the
 * power at that n (>= the target).  MCSTAT_EINVAL as above, and when no
 * value reaches the power (an effect of 0; a power at or below what alpha
 * alone gives; n beyond 1e15); MCSTAT_ENUMERIC. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_power_solve(const mcstat_power_options *o, int unknown,
                                  mcstat_power_options *out);
/* R's print.power.htest block ("Two-sample t test power calculation", the
 * named values aligned, NOTE lines) for a solved *o, into buf as
 * mcstat_result_format does.  MCSTAT_EINVAL, MCSTAT_EBUFSIZE. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_power_format(const mcstat_power_options *o, char *buf, size_t size,
                                   size_t *length);

/* ------------------------------------------------------------------------ */
/* 10. Estimator diagnostics, mcstat_diag_*.                 (experimental) */
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
MCSTAT_API int mcstat_diag_options_init_size(mcstat_diag_options *opt, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_DIAG_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_diag_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_API int(mcstat_diag_options_init)(mcstat_diag_options *opt);
#define mcstat_diag_options_init(opt) mcstat_diag_options_init_size((opt), sizeof *(opt))
MCSTAT_API size_t mcstat_sizeof_diag_options(void);
MCSTAT_API size_t mcstat_sizeof_diagnostics(void);

/* All diagnostics of n primary estimates x; opt may be NULL (defaults).
 * Allocates 16 n bytes (a radix sort: ~0.15 s per 1e6 values).  Statuses:
 * MCSTAT_EINVAL (NULL x or out, an options size this library does not know,
 * alpha outside (0,1),
 * tolerance outside (0,1), tail_threshold <= 0, k > n), MCSTAT_ETOOFEW
 * (n < 8, n < 2 tail_k + 2, or fewer than 2 batch means), MCSTAT_ENONFINITE,
 * MCSTAT_EDEGENERATE (constant data), MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_diag_compute(const double *x, size_t n, const mcstat_diag_options *opt,
                                   mcstat_diagnostics *out);
/* Hill's tail index of each tail (index[0] lower, index[1] upper) from
 * tail_k order statistics (0: the default), as above.  Statuses:
 * MCSTAT_EINVAL, MCSTAT_ETOOFEW (n < 2 tail_k + 2), MCSTAT_ENONFINITE,
 * MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_diag_tail_index(const double *x, size_t n, size_t tail_k, double index[2]);
/* The Edgeworth-predicted rejection rates size[0] (lower tail: "less") and
 * size[1] (upper: "greater") of the two-sided t test at alpha on m batch
 * means of k values whose skewness and excess kurtosis are given.
 * MCSTAT_EINVAL (non-finite shape, kurtosis < -2, alpha, k == 0),
 * MCSTAT_ETOOFEW (m < 2). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_diag_t_size(double skewness, double kurtosis, uint64_t k, uint64_t m, double alpha,
                                  double size[2]);
/* The batch size rule: the smallest k whose predicted tail rates are within
 * tolerance * alpha/2 of alpha/2 for m batch means.  MCSTAT_EINVAL,
 * MCSTAT_ETOOFEW (m < 2), MCSTAT_ETOOBIG (k beyond 2^53). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_diag_batch_size(double skewness, double kurtosis, uint64_t m, double alpha,
                                      double tolerance, uint64_t *k);

/* ======================================================================== */
/* 11. Goodness of fit.                                      (experimental) */
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
typedef struct mcstat_chisq_options {
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
MCSTAT_API int mcstat_gof_options_init_size(mcstat_gof_options *opt, size_t size);
#define mcstat_gof_options_init(opt) mcstat_gof_options_init_size((opt), sizeof *(opt))
MCSTAT_API size_t mcstat_sizeof_gof_options(void);
MCSTAT_API double mcstat_gof_default_min_expected(void);

/* Pearson's test of observed[0..k) against expected[0..k) as above.  opt may
 * be NULL (the defaults). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_gof_chisq_test(const double *observed, const double *expected, size_t k,
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
MCSTAT_NODISCARD MCSTAT_API int mcstat_binom_test(uint64_t x, uint64_t n, double p, int alternative, double alpha,
                                 mcstat_result *out);
/* The battery meta-test: `rejections` among k tests each at level `level`
 * in (0, 1), tested against the rate `level` (mcstat_binom_test(rejections,
 * k, level, ...)); reject == 1 means the count is not consistent with the
 * level (GREATER: too many rejections, the usual question).  Statuses as
 * mcstat_binom_test, plus MCSTAT_EINVAL for level outside (0, 1). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_battery_test(uint64_t rejections, uint64_t k, double level, int alternative,
                                   double alpha, mcstat_result *out);
/* The same from the battery's k p-values: a test rejects when its p-value
 * is <= level.  MCSTAT_ENONFINITE for a NaN p-value, MCSTAT_EINVAL for one
 * outside [0, 1] (or p_values NULL with k > 0), MCSTAT_ETOOFEW for k == 0. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_battery_test_pvalues(const double *p_values, size_t k, double level, int alternative,
                                           double alpha, mcstat_result *out);


/* ======================================================================== */
/* 12. Renderer checks.                                      (experimental) */
/* Do a BSDF's sample(), pdf(), eval() and sample weight agree?  The        */
/* renderer hands over its routines as callbacks; mcstat feeds them its own  */
/* uniform numbers, runs a battery of checks ("routes") and controls the     */
/* battery's error rate.  Emitters (sampling directions from a reference    */
/* point) and warps (square, disk, interval) are checked the same way.      */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* The model a renderer hands over.                                          */
/* Points live in a domain:                                                  */
/*   SPHERE       unit directions (x, y, z): BSDFs with transmission,        */
/*                emitters;                                                  */
/*   HEMISPHERE   unit directions with z >= 0 (the shading normal is +z):    */
/*                reflection-only BSDFs;                                     */
/*   SQUARE       (x, y) in [0, 1]^2;  DISK  (x, y), x^2 + y^2 <= 1;         */
/*   INTERVAL     x in [0, 1].                                               */
/* Densities are with respect to solid angle (directions) or area/length.   */
/* Callbacks (each returns 0 on success, anything else to stop the check:   */
/* MCSTAT_ECALLBACK then names it), called only from the calling thread,    */
/* n points at a time (n <= the options' batch):                             */
/*   sample(user, wi, u, n, x, weight, pdf): for k < n, from the uniforms    */
/*     u[k*n_uniforms ..] in [0, 1) (multiples of 2^-53: a float renderer    */
/*     that converts them must clamp, as those above 1 - 2^-25 round to      */
/*     1.0f, outside [0, 1): min(u, nextafterf(1, 0)) keeps its contract),   */
/*     point x[k*dims ..], the sample weight                                 */
/*     weight[k] and the density pdf[k] the renderer's sampler reports.  A   */
/*     sample that failed (the renderer's "invalid sample") has pdf 0 and    */
/*     weight 0; x is then ignored.  With MCSTAT_WEIGHT_OVER_PDF (Mitsuba's  */
/*     BSDFSample weight) weight = eval/pdf; with MCSTAT_WEIGHT_VALUE (pbrt's */
/*     Sample_f times |cos|) weight = eval.                                  */
/*   pdf(user, wi, x, n, out): out[k] the density at x[k*dims ..].           */
/*   eval(user, wi, x, n, out): out[k] the integrand the sampler is built    */
/*     for: f(wi, x) |cos(x)| for a BSDF (Mitsuba's eval includes the        */
/*     cosine), the radiance arriving along x for an emitter.  NULL for a   */
/*     warp (no integrand: only the sampler and its density are checked).   */
/* wi is the fixed direction given to mcstat_check_bsdf (NULL for emitters   */
/* and warps; an emitter's reference point lives in `user`).  Callbacks run */
/* under IEEE defaults (see the conventions above): a renderer built to     */
/* flush subnormals sees them kept inside the check.                         */
/* ------------------------------------------------------------------------ */
enum mcstat_check_domain {
    MCSTAT_DOMAIN_SPHERE = 0,
    MCSTAT_DOMAIN_HEMISPHERE = 1,
    MCSTAT_DOMAIN_SQUARE = 2,
    MCSTAT_DOMAIN_DISK = 3,
    MCSTAT_DOMAIN_INTERVAL = 4
};

enum mcstat_check_weight {
    MCSTAT_WEIGHT_OVER_PDF = 0, /* weight = eval / pdf (Mitsuba, most path tracers) */
    MCSTAT_WEIGHT_VALUE = 1     /* weight = eval (the sampled value, not divided) */
};

#define MCSTAT_CHECK_MAX_UNIFORMS 8

typedef int (*mcstat_check_sample_fn)(void *user, const double *wi, const double *u, size_t n, double *x,
                                      double *weight, double *pdf);
typedef int (*mcstat_check_density_fn)(void *user, const double *wi, const double *x, size_t n,
                                       double *out);

/* Discrete lobes (specular reflection and refraction: a BSDF whose sample()
 * returns a direction with a probability, not a density).  pdf() and
 * eval() then describe the smooth part only (as Mitsuba's and pbrt's do),
 * and lobes(user, wi, x, mass, value, count) describes the rest for the
 * check's wi: *count <= MCSTAT_CHECK_MAX_LOBES lobes (x, mass and value
 * have room for that many, no more), lobe k with its
 * direction x[3k ..] (unit length, in the domain), the probability
 * mass[k] in [0, 1] with which sample() returns it (what sample()
 * reports as its pdf there), and value[k] >= 0, the integral of
 * f |cos| over the lobe (its albedo: Fresnel's R for a mirror-like
 * reflection), so that its weight is value/mass (MCSTAT_WEIGHT_VALUE:
 * value).  A sample within MCSTAT_CHECK_LOBE_TOLERANCE (chord length) of
 * a lobe's direction is that lobe's sample; lobes must lie further apart
 * than twice that.  Called once per check (mcstat_check_bsdf only). */
#define MCSTAT_CHECK_MAX_LOBES 4
#define MCSTAT_CHECK_LOBE_TOLERANCE 1e-4
typedef int (*mcstat_check_lobes_fn)(void *user, const double *wi, double *x, double *mass, double *value,
                                     size_t *count);

typedef struct mcstat_check_model {
    int32_t domain;            /* enum mcstat_check_domain */
    int32_t n_uniforms;        /* uniforms per sample, 1..MCSTAT_CHECK_MAX_UNIFORMS (Mitsuba's BSDFs: 3) */
    int32_t weight;            /* enum mcstat_check_weight */
    int32_t sample_reports;    /* 1: sample() writes weight and pdf (BSDFs, emitters); 0: only x
                                  (warps: every sample succeeds, pdf() gives its density) */
    void *user;                /* passed to every callback */
    mcstat_check_sample_fn sample;
    mcstat_check_density_fn pdf;
    mcstat_check_density_fn eval; /* NULL: no integrand (warps) */
    MCSTAT_ANONYMOUS union {
        double reserved[4];    /* zero */
        MCSTAT_ANONYMOUS struct {
            mcstat_check_lobes_fn lobes; /* NULL: no discrete lobes (0.2.0's zeros) */
            double reserved_rest[3];     /* zero */
        };
    };
} mcstat_check_model;

/* Coordinates per point of a domain (3, 3, 2, 2, 1); 0 for a bad domain. */
MCSTAT_API int mcstat_check_domain_dims(int domain);
/* "sphere", "hemisphere", "square", "disk", "interval" and back. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_domain_parse(const char *name, int *domain);
MCSTAT_API const char *mcstat_check_domain_name(int domain); /* NULL if invalid */

/* ------------------------------------------------------------------------ */
/* The routes.                                                               */
/* Each route checks one claim, and names what it cannot see:              */
/*   CELLS        sample() draws from the density pdf() claims: Pearson's    */
/*                chi-squared of the successful samples' counts in cells of  */
/*                (nearly) equal probability.  Cells: a k-d tree over the    */
/*                domain's equal-area square (directions: s = (1 - z)/2,     */
/*                t = phi/(2 pi)), split at medians of an independent pilot  */
/*                sample until each leaf holds 32 pilot points (the sphere   */
/*                is cut at the horizon first); each cell's probability is   */
/*                the integral of pdf() over it by adaptive cubature (Genz-  */
/*                Malik 7/5, splitting where the rules disagree) to 5% of    */
/*                the cell count's sampling sd.  A rectangle where pdf() is  */
/*                0 at some of its 17 points and 4 corner probes and not at  */
/*                others holds the support's edge: its error is then bounded */
/*                by the estimate's distance to area times the least or the  */
/*                largest value seen, and it is halved across the edge; when */
/*                the rectangles run out, the largest errors are halved      */
/*                first.  Rectangles on a pole of the sphere (the disk's     */
/*                centre: lines of the square) start as layers shrinking by  */
/*                4 toward it, so that a narrow peak there is integrated.    */
/*                Consecutive cells are pooled until the expected            */
/*                count is 5, and the remaining cubature error enters each   */
/*                cell's variance, so an integration that falls short costs  */
/*                power, never the level.                                    */
/*                df = pooled cells - 1.  Blind to: pdf() scaled by a        */
/*                constant, everything about weights and eval.              */
/*   MASS         the fraction of samples that succeed equals the integral   */
/*                of pdf() over the domain.  Two estimates: the cubature's  */
/*                integral C (error e) and the mean M of pdf/table at the   */
/*                n_eval points of a table of the cubature's rectangles     */
/*                (each weighing its integral and its error, plus its share */
/*                of a cell's significant excess of pilot points over the   */
/*                cell's integral; unbiased, standard error s).  When M's   */
/*                values                                                    */
/*                are not heavy-tailed (Hill index >= 2.5) and either the   */
/*                two disagree (|C - M| > 4e + 3s) or M is the more precise  */
/*                (3s < 4e), a two-sided z test against M; otherwise the    */
/*                exact binomial test, conservative over the interval that  */
/*                spans both C +- 4e and M +- 3s (it holds the true integral */
/*                when either error statement does); p = 0 only when both   */
/*                ends are above 1.  With discrete lobes, the                */
/*                smooth successes are tested so, and each lobe's count by  */
/*                the exact binomial test against n mass[k]; the route's    */
/*                p-value is the smallest times (lobes + 1) (Bonferroni),   */
/*                where/value the lobe furthest off (its direction, share    */
/*                and mass).  mcstat_check_medium with escape_transmittance */
/*                adds the escapes' weights (a t test, in the same         */
/*                Bonferroni; value: their mean and T(tmax)).  Catches      */
/*                pdf() scaled by a constant, samples                        */
/*                lost, a lobe chosen at a rate other than its pdf says.    */
/*   PDF_VALUE    the pdf sample() reports equals pdf() at the sampled point */
/*                (deterministic: relative tolerance rtol at every sample); */
/*                on a discrete lobe, its mass.  A point whose coordinates  */
/*                are float32 values (a float renderer's) passes when the   */
/*                difference is within rtol plus 4 ulps' worth of pdf()'s   */
/*                change at the point's float32 neighbours: rounding where  */
/*                pdf() is ill-conditioned (grazing half vectors).  WEIGHT   */
/*                likewise.                                                  */
/*   WEIGHT       the weight equals eval/pdf (deterministic, as PDF_VALUE);  */
/*                a failed sample has weight 0; on a discrete lobe, value/   */
/*                mass.                                                      */
/*   SUPPORT      eval > 0 only where pdf > 0, at the sampled points and at  */
/*                the eval-only estimator's points (a region the sampler     */
/*                never reaches biases every estimate using it); a discrete */
/*                lobe with value > 0 has mass > 0.  pdf > 0 where eval = 0  */
/*                is counted (wasted samples), not a failure.                */
/*   INTEGRALS    eval against the sampler, end to end: the integrals of     */
/*                eval over up to 16 regions (consecutive runs of cells),    */
/*                estimated from the sample weights and from an estimator    */
/*                that uses only eval (points from a table of the cells'     */
/*                probabilities, mixed 9:1 with uniform points so that every */
/*                region is reached), compared by a Wald test (chi-squared   */
/*                on the regions, covariances estimated).  The statistical   */
/*                form of WEIGHT: it is what checks a stochastic BSDF.       */
/*   ENERGY       albedo <= 1: one-sided t test of the mean weight (BSDFs;   */
/*                discrete lobes' weights included).                        */
/* CELLS, INTEGRALS, KS and RECIPROCITY see the smooth part only: samples   */
/* on a discrete lobe are left out of them (INTEGRALS: weight 0 there).    */
/*   RECIPROCITY  eval(wi, x)/|x.z| == eval(x, wi)/|wi.z| at up to 1000     */
/*                sampled points (deterministic; only when asked: BSDFs      */
/*                with refraction are not reciprocal in radiance).           */
/*   KS           the sampler's weighted distribution against eval's, point  */
/*                by point rather than by region: the sampled points kept    */
/*                with probability weight/W (W twice the pilot's largest    */
/*                weight: importance resampling, so that the kept points     */
/*                follow eval if the weights are right) against points drawn */
/*                from eval by rejection from the eval-only estimator's      */
/*                table (the envelope twice the largest eval/table of the   */
/*                first half of its points; the second half are proposals), */
/*                by the two-sample K-S test with Canner's weight on Morton     */
/*                keys of the equal-area square, at most 20000 points a     */
/*                side (the exact p-value's cost).  An envelope exceeded    */
/*                makes the route INVALID (the report says which).          */
/* Heavy tails: INTEGRALS and ENERGY need finite variance.  When the Hill   */
/* tail index of the weights (or of the eval-only estimates) is below 2,    */
/* those routes are INVALID (not run) and the report says why.              */
/* The verdict: deterministic routes reject when more than the tolerated    */
/* share of points (option `tolerated`) differ beyond rtol;                 */
/* the statistical routes' p-values are adjusted across routes (Holm), and  */
/* the check rejects when any adjusted p-value is <= alpha: a correct model */
/* is rejected with probability at most alpha (the cubature and the         */
/* asymptotic tests being approximations; measured: tests/python/           */
/* test_check_calibration.py and bench/).  A check that did not reject but  */
/* needed a route that could not answer is inconclusive, not consistent    */
/* (mcstat_check_verdict, below the report).                                */
/* The numerical floor: differences at the resolution of the caller's       */
/* arithmetic are not evidence.  The statistical routes add the options'    */
/* resolution (derived from the values by default: float32 or float64) as a */
/* relative error of what they compare (CELLS: of each cell's probability; */
/* MASS: of the mass; INTEGRALS: a common and a per-region error; ENERGY: */
/* of the albedo), and report it.                                           */
/* ------------------------------------------------------------------------ */
enum mcstat_check_route {
    MCSTAT_CHECK_ROUTE_CELLS = 0,
    MCSTAT_CHECK_ROUTE_MASS = 1,
    MCSTAT_CHECK_ROUTE_PDF_VALUE = 2,
    MCSTAT_CHECK_ROUTE_WEIGHT = 3,
    MCSTAT_CHECK_ROUTE_SUPPORT = 4,
    MCSTAT_CHECK_ROUTE_INTEGRALS = 5,
    MCSTAT_CHECK_ROUTE_ENERGY = 6,
    MCSTAT_CHECK_ROUTE_RECIPROCITY = 7,
    MCSTAT_CHECK_ROUTE_KS = 8,
    MCSTAT_CHECK_ROUTE_COUNT = 9 /* number of routes */
};

/* "cells", "mass", "pdf_value", "weight", "support", "integrals", "energy",
 * "reciprocity", "ks" and back. */
MCSTAT_API const char *mcstat_check_route_name(int route); /* NULL if invalid */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_route_parse(const char *name, int *route);

enum mcstat_check_state {
    MCSTAT_ROUTE_RAN = 0,
    MCSTAT_ROUTE_SKIPPED = 1, /* not asked for, or not applicable to this model */
    MCSTAT_ROUTE_INVALID = 2  /* an assumption failed (heavy tails, too few samples): no answer */
};

/* Why a route could not answer (its state INVALID): the report's `why`.
 * mcstat_check_why_text gives the reason and what would let it answer. */
enum mcstat_check_why {
    MCSTAT_CHECK_WHY_NONE = 0,        /* it answered (or was skipped) */
    MCSTAT_CHECK_WHY_HEAVY_TAIL = 1,  /* a tail index below 2: the mean it tests has no finite variance */
    MCSTAT_CHECK_WHY_TOO_FEW = 2,     /* too few samples, cells, regions or kept points */
    MCSTAT_CHECK_WHY_ENVELOPE = 3,    /* KS: a ratio beyond the resampling envelope */
    MCSTAT_CHECK_WHY_NOTHING = 4,     /* nothing to compare: eval() and the weights are 0 wherever looked,
                                         or no smooth part is claimed or sampled (a purely discrete BSDF) */
    MCSTAT_CHECK_WHY_NUMERIC = 5,     /* a numerical step failed */
    MCSTAT_CHECK_WHY_INTEGRATION = 6  /* the integral of pdf() is not known well enough to test against */
};
/* A sentence: the reason a route could not answer and what would let it
 * answer; "" for MCSTAT_CHECK_WHY_NONE, NULL for an invalid value. */
MCSTAT_API const char *mcstat_check_why_text(int why);


/* ------------------------------------------------------------------------ */
/* Options; grows by appending fields ("Conventions"), so always start     */
/* from the initialiser.                                                    */
/* ------------------------------------------------------------------------ */
typedef struct mcstat_check_options {
    uint32_t size;         /* sizeof(mcstat_check_options): set by the initialiser */
    uint32_t routes;       /* bit (1u << route) for each route to run; default all
                              (routes that do not apply to the model are skipped) */
    int32_t stochastic;    /* 1: weight and pdf are estimates (layered BSDFs): PDF_VALUE and
                              WEIGHT are skipped, INTEGRALS checks them; default 0 */
    int32_t reciprocal;    /* 1: run RECIPROCITY; default 0 */
    int32_t cells;         /* target cells for CELLS, 0 or 2..2^20; 0 (default): 2 n^0.4 within
                              [8, 8192]; the tree gives within a factor 1.4 of it */
    int32_t reserved_i;    /* zero */
    uint64_t n_pilot;      /* pilot samples for the cells, 0 or >= 64 (at most 2^40); 0
                              (default): 32 per target cell */
    uint64_t n_eval;       /* points of the eval-only estimator, 0 or >= 1000; 0 (default): n */
    uint64_t batch;        /* points per callback call, 64..2^32; default 65536 */
    double rtol;           /* relative tolerance of the deterministic routes, in (0, 1); default
                              1e-3 (renderers computing in float32 differ at ~1e-6) */
    double tolerated;      /* share of checked points a deterministic route lets differ beyond
                              rtol, in [0, 1); default 1e-4: float32 renderers miss a light's rim
                              on a retraced point, or lose digits at grazing angles, in about 1e-5
                              of samples (measured on Mitsuba 3); a real bug of a region of
                              probability 1e-3 is still seen at n = 1e5 */
    double reserved[4];    /* zero */
    /* since 0.3 (MCSTAT_CHECK_OPTIONS_SIZE_0_3): */
    double escape_transmittance; /* mcstat_check_medium: < 0 (default -1): a flight that passes the
                              surface is a failed sample, weight 0, its weight not checked; in
                              [0, 1]: T(tmax), the transmittance to the surface, and such a flight
                              reports pdf 0 and the weight it carries on (1 for analog tracking,
                              T(tmax)/P(escape) when the distances follow another density): MASS
                              also tests that the mean over the n flights of the escapes' weights
                              (0 for a scattering) equals T(tmax), by a two-sided t test.  Needs
                              MCSTAT_WEIGHT_OVER_PDF */
    double resolution;     /* the relative resolution of the caller's arithmetic: differences of
                              integrals at that scale are rounding, not evidence.  The statistical
                              routes add it as an error of what they compare (INTEGRALS: a
                              relative error common to all regions and one of each region, of
                              this size each, in the variance of the difference; ENERGY: one of
                              the albedo; MASS and CELLS: one of the mass and of each cell's
                              probability), and each route reports it.  0 (default): derived from the values the callbacks return,
                              MCSTAT_RESOLUTION_FLOAT32 when every pdf, weight and eval value
                              is a float32 (a renderer computing in float), else
                              MCSTAT_RESOLUTION_FLOAT64; > 0: that value, below 0.01 */
    /* routes must not be 0; reserved fields and the model's must be zero
     * (later releases may give them a meaning): MCSTAT_EINVAL otherwise. */
} mcstat_check_options;

#define MCSTAT_CHECK_ROUTE_ALL ((1u << MCSTAT_CHECK_ROUTE_COUNT) - 1u)
#define MCSTAT_CHECK_OPTIONS_INIT \
    {sizeof(mcstat_check_options), MCSTAT_CHECK_ROUTE_ALL, 0, 0, 0, 0, 0, 0, 65536, 1e-3, 1e-4, {0, 0, 0, 0}, -1.0, 0.0}


/* sizeof(mcstat_check_options) in each release that changed it. */
#define MCSTAT_CHECK_OPTIONS_SIZE_0_2 96u
#define MCSTAT_CHECK_OPTIONS_SIZE_0_3 112u
/* Sets the first `size` bytes of *opt to MCSTAT_CHECK_OPTIONS_INIT, with
 * opt->size = size (as mcstat_gof_options_init_size). */
MCSTAT_API int mcstat_check_options_init_size(mcstat_check_options *opt, size_t size);
#define mcstat_check_options_init(opt) mcstat_check_options_init_size((opt), sizeof *(opt))
MCSTAT_API size_t mcstat_sizeof_check_options(void);
MCSTAT_API size_t mcstat_sizeof_check_model(void);
MCSTAT_API size_t mcstat_sizeof_check_report(void);

/* ------------------------------------------------------------------------ */
/* The report.                                                               */
/* Per route: its state, whether it is deterministic, its verdict, and      */
/*   statistic, df, p_value, p_adjusted   (statistical routes; NaN otherwise) */
/*   effect       the departure measured: CELLS Cohen's w = sqrt(X^2/N);     */
/*                MASS and INTEGRALS and ENERGY the relative difference of   */
/*                the two sides; deterministic routes the largest relative   */
/*                difference seen                                            */
/*   detectable   the smallest departure of the same kind this run detects  */
/*                with probability 0.8 at alpha (normal approximations);    */
/*                deterministic routes: the smallest probability of a       */
/*                region where any error above rtol is caught with          */
/*                probability 0.8, -ln(0.2)/checked                         */
/*   n_for_1pct   samples the route needs to detect a 1% departure with     */
/*                probability 0.8 (CELLS: w = 0.01; MASS, INTEGRALS, ENERGY: */
/*                1% relative; deterministic: a region of probability 1%)   */
/*   checked, count  points checked and points beyond tolerance (CELLS:      */
/*                samples and pooled cells)                                  */
/*   where, value[2]  deterministic routes: the point of the largest         */
/*                difference and the two values that differ there           */
/* ------------------------------------------------------------------------ */
typedef struct mcstat_check_route_result {
    int32_t state;         /* enum mcstat_check_state */
    int32_t deterministic; /* 1: a tolerance check, not a test */
    int32_t reject;
    MCSTAT_ANONYMOUS union {
        int32_t reserved_i; /* 0.2.0's name of this storage */
        int32_t why;        /* state INVALID: enum mcstat_check_why; else 0 */
    };
    double statistic, df, p_value, p_adjusted;
    double effect, detectable, n_for_1pct;
    uint64_t checked, count;
    double where[3];
    double value[2];
    MCSTAT_ANONYMOUS union {
        double reserved[3]; /* 0.2.0's name of this storage */
        MCSTAT_ANONYMOUS struct {
            /* statistical routes: the numerical floor they applied, relative
               (options' resolution); NaN for the deterministic ones */
            double resolution;
            double reserved_2[2]; /* zero */
        };
    };
} mcstat_check_route_result;

enum mcstat_check_kind {
    MCSTAT_CHECK_KIND_BSDF = 0,
    MCSTAT_CHECK_KIND_EMITTER = 1,
    MCSTAT_CHECK_KIND_WARP = 2,
    MCSTAT_CHECK_KIND_PHASE = 3, /* mcstat_check_phase */
    MCSTAT_CHECK_KIND_MEDIUM = 4 /* mcstat_check_medium */
};

typedef struct mcstat_check_report {
    int32_t kind;          /* enum mcstat_check_kind */
    int32_t domain;
    int32_t reject;        /* 1: some route rejected */
    int32_t heavy_tailed;  /* 1: a tail index below 2 made routes INVALID */
    double alpha;
    double p_value;        /* smallest adjusted p-value (0 when a deterministic route failed) */
    double wi[3];          /* BSDFs: the direction checked (NaN otherwise) */
    uint64_t n, n_failed;  /* samples drawn for the test, and how many failed */
    uint64_t n_pilot, n_eval;
    uint64_t cells;        /* cells of the tree (before pooling) */
    uint64_t calls;        /* callback calls */
    uint64_t pdf_without_eval; /* points where pdf() > 0 but eval() = 0: samples wasted, not an error */
    double mass;           /* integral of pdf() over the domain (cubature) */
    double mass_error;     /* its estimated absolute error: sum over the cells */
    double mass_sampled, mass_sampled_se; /* the same by Monte Carlo at the table points */
    double albedo, albedo_se;        /* mean weight and its standard error */
    double albedo_eval, albedo_eval_se; /* the eval-only estimate of the same integral */
    double tail_index[2];  /* Hill's upper tail index of the weights, of the eval-only estimates */
    MCSTAT_ANONYMOUS union {
        double reserved[8];
        MCSTAT_ANONYMOUS struct {
            /* samples with weight 0 where the reported pdf and eval() are > 0: counted
               as successes.  A sampler that marks a failed sample by its weight alone
               (Mitsuba and pbrt mark it by pdf 0) shows here; the text says so when
               they are 1% of n or more */
            uint64_t zero_weight;
            /* mcstat_check_medium: the sigma_ref of the map of distances (0 otherwise) */
            double sigma_ref;
            MCSTAT_ANONYMOUS union {
                double reserved_rest[6];
                MCSTAT_ANONYMOUS struct {
                    /* discrete lobes (model->lobes): how many, the samples on them, the
                       sum of their masses and of their values (the discrete part of the
                       albedo; the albedo fields above are the smooth part's); 0 without */
                    uint64_t lobes, n_lobe;
                    double lobe_mass, lobe_albedo;
                    /* mcstat_check_medium with escape_transmittance >= 0: the mean over
                       the n flights of the escapes' weights and its standard error (NaN
                       otherwise, and the se with fewer than 2 escapes) */
                    double escape_weight, escape_weight_se;
                };
            };
        };
    };
    mcstat_check_route_result route[MCSTAT_CHECK_ROUTE_COUNT];
    char message[256];     /* MCSTAT_ECALLBACK: what went wrong, naming the callback, the point
                              and the value; otherwise empty */
} mcstat_check_report;

/* The three verdicts of a check.  INCONCLUSIVE: no route rejected, but a
 * route the check needed could not answer (state INVALID for a reason other
 * than MCSTAT_CHECK_WHY_NOTHING; KS only when INTEGRALS did not answer
 * either, as both check eval() against the sampler), so "consistent" would
 * claim an error rate the battery did not have. */
enum mcstat_check_verdict {
    MCSTAT_CHECK_CONSISTENT = 0,
    MCSTAT_CHECK_INCONSISTENT = 1, /* report->reject */
    MCSTAT_CHECK_INCONCLUSIVE = 2
};
/* *verdict <- the report's verdict; *unanswered (may be NULL) <- bit
 * (1u << route) for each route that could not answer and counts toward
 * INCONCLUSIVE.  MCSTAT_EINVAL for NULL report or verdict, or a report
 * whose states are not those of a check. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_verdict(const mcstat_check_report *report, int *verdict, uint32_t *unanswered);
MCSTAT_API const char *mcstat_check_verdict_name(int verdict); /* "consistent", ...; NULL if invalid */

/* ------------------------------------------------------------------------ */
/* The checks.                                                               */
/* n samples from model->sample (n >= 1000), the uniforms a pure function of */
/* (seed, stream, index), so a check is reproducible and its stream of       */
/* uniforms does not depend on batch; alpha in (0, 1) is the level of the   */
/* whole battery; opt may be NULL (the defaults).                            */
/* Scratch: work of work_bytes >= mcstat_check_work_size(...) bytes, aligned */
/* to 16, or work NULL (allocated and freed inside the call).  About 16 n + */
/* 12 n_eval + 16 n_pilot + 12 KB per target cell + (76 + 16 dims +         */
/* 8 n_uniforms) per batch point: 15 MB at n = 1e5 with the defaults, 44 MB */
/* at 1e6 (most of it the batch and the cubature's rectangles).             */
/*   mcstat_check_bsdf     wi a direction (normalised inside; wi.z may be   */
/*                         negative: light arriving from below); ENERGY,     */
/*                         RECIPROCITY apply; model->lobes may be given;     */
/*   mcstat_check_emitter  directions from a reference point: domain SPHERE */
/*                         or HEMISPHERE, no ENERGY, no RECIPROCITY;         */
/*   mcstat_check_warp     eval ignored (CELLS, MASS, and PDF_VALUE when     */
/*                         sample_reports);                                  */
/*   mcstat_check_phase    a phase function p(wi, wo) of a medium: as       */
/*                         mcstat_check_bsdf on domain SPHERE (required),    */
/*                         eval = p itself (no cosine), weight p/pdf; ENERGY */
/*                         tests albedo == 1 (two-sided: a phase function    */
/*                         integrates to 1 over the sphere; constant weights */
/*                         within rtol), RECIPROCITY (when asked) p(wi, wo)  */
/*                         == p(wo, wi).  mcstat_check_bsdf on the same      */
/*                         model runs the same routes but only sees albedo   */
/*                         above 1, and divides reciprocity by cosines;      */
/*   mcstat_check_medium   distance sampling along a ray: the callbacks'     */
/*                         points are distances t >= 0 (domain INTERVAL,     */
/*                         one coordinate, n_uniforms as the sampler needs), */
/*                         mapped inside to x = 1 - exp(-sigma_ref t) in     */
/*                         [0, 1] (pdf and eval divided by dx/dt, so that    */
/*                         weights are unchanged; pdf() and eval() may be    */
/*                         asked at t = +inf, x = 1).  sample() reports the  */
/*                         density in t of a scattering at t, e.g. sigma_t   */
/*                         exp(-sigma_t t); a flight that passes the surface */
/*                         at tmax is a failed sample (pdf 0, weight 0), so  */
/*                         MASS compares the share of flights stopping       */
/*                         before tmax with the integral of pdf() (1 -       */
/*                         exp(-sigma_t tmax)): pdf() must be 0 beyond tmax; */
/*                         with options' escape_transmittance, an escape's  */
/*                         weight is checked too.                            */
/*                         eval(t) is the integrand the weight estimates,    */
/*                         sigma_s T(t) (the weight sigma_s T / pdf);        */
/*                         ENERGY: albedo <= 1.  sigma_ref >                 */
/*                         0 finite (MCSTAT_EINVAL otherwise): near the      */
/*                         medium's sigma_t the points are nearly uniform;   */
/*                         far below it they crowd at x = 0 (cells still     */
/*                         adapt), above it pdf(x) is unbounded at x = 1.    */
/*                         The report's points (where) are x, not t.         */
/* Cost: the callbacks are called about n + n_pilot times for samples,      */
/* n + n_eval times each for eval and pdf, and pdf 21 times per cubature    */
/* rectangle (2 to 40 per cell); the check's own work is O(1) per sample   */
/* besides sorting for KS (figures: bench/RESULTS.md).                      */
/* Statuses: MCSTAT_EINVAL (NULL model, callbacks or out, a bad domain,      */
/* n_uniforms or weight, lobes given to a check other than mcstat_check_bsdf, */
/* escape_transmittance NaN or above 1, or at least 0 for a check other     */
/* than mcstat_check_medium or with MCSTAT_WEIGHT_VALUE,                     */
/* a BSDF, emitter, phase function or medium without */
/* eval or with sample_reports 0, a phase function off SPHERE, a medium    */
/* off INTERVAL or sigma_ref not > 0 finite, n < 1000, alpha outside       */
/* (0, 1), an options size this library does not know, a bad option, work too small or misaligned,  */
/* wi zero or not finite), MCSTAT_ETOOBIG (n beyond 2^48 or sizes whose     */
/* scratch overflows), MCSTAT_ENOMEM, MCSTAT_ECALLBACK (a callback returned */
/* non-zero, or NaN, Inf, a negative density or weight, a point outside the */
/* domain or a direction not of unit length within 1e-4, lobes() giving     */
/* more than MCSTAT_CHECK_MAX_LOBES lobes, a mass outside [0, 1] or lobes  */
/* closer than twice MCSTAT_CHECK_LOBE_TOLERANCE: out->message says       */
/* which callback, the index, point and value; nothing else in *out is      */
/* meaningful).  A sampler whose samples all fail is not an error: the      */
/* report's routes that need samples say "no answer", and MASS compares     */
/* the failures with the mass of pdf().                                     */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_work_size(const mcstat_check_model *model, size_t n, const mcstat_check_options *opt,
                                      size_t *bytes);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_bsdf(const mcstat_check_model *model, const double wi[3], size_t n, uint64_t seed,
                                 double alpha, const mcstat_check_options *opt, void *work, size_t work_bytes,
                                 mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_emitter(const mcstat_check_model *model, size_t n, uint64_t seed, double alpha,
                                    const mcstat_check_options *opt, void *work, size_t work_bytes,
                                    mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_warp(const mcstat_check_model *model, size_t n, uint64_t seed, double alpha,
                                 const mcstat_check_options *opt, void *work, size_t work_bytes,
                                 mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_phase(const mcstat_check_model *model, const double wi[3], size_t n, uint64_t seed,
                                  double alpha, const mcstat_check_options *opt, void *work, size_t work_bytes,
                                  mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_medium(const mcstat_check_model *model, double sigma_ref, size_t n, uint64_t seed,
                                   double alpha, const mcstat_check_options *opt, void *work, size_t work_bytes,
                                   mcstat_check_report *out);

/* Writes the report as a text block (R's layout: one line per route with
 * its statistic, df and p-values, then what a pass means and the budget a
 * 1% error needs) into buf; *length (may be NULL) receives the full
 * length.  MCSTAT_EINVAL, MCSTAT_EBUFSIZE (buf holds a NUL-terminated
 * prefix). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_format(const mcstat_check_report *r, char *buf, size_t size, size_t *length);
/* One sentence saying what route `route` checks (static storage; NULL if
 * invalid), and one saying what it cannot see. */
MCSTAT_API const char *mcstat_check_route_meaning(int route);
MCSTAT_API const char *mcstat_check_route_blind_spot(int route);

/* ======================================================================== */
/* 13. Sequential, anytime-valid tests.                      (experimental) */
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

#endif /* MCSTAT_NO_EXPERIMENTAL */

/* ======================================================================== */
/* 14. Deprecated names.                                                    */
/* The names this release replaced, one form per family: old -> new.        */
/* They still link (the ABI keeps every exported symbol of its SOVERSION)   */
/* and give bit-identical results; MCSTAT_DEPRECATED names the replacement. */
/* ======================================================================== */
/* sizes: mcstat_sizeof_<thing> */
MCSTAT_DEPRECATED("mcstat_sizeof_moments_bytes") MCSTAT_API size_t mcstat_moments_bytes(void);
MCSTAT_DEPRECATED("mcstat_sizeof_gof_options") MCSTAT_API size_t mcstat_sizeof_chisq_options(void);

#ifndef MCSTAT_NO_EXPERIMENTAL
/* diagnostics: the mcstat_diag_ stem */
MCSTAT_DEPRECATED("mcstat_diag_compute")
MCSTAT_API int mcstat_diagnose(const double *x, size_t n, const mcstat_diag_options *opt, mcstat_diagnostics *out);
MCSTAT_DEPRECATED("mcstat_diag_tail_index")
MCSTAT_API int mcstat_tail_index(const double *x, size_t n, size_t tail_k, double index[2]);
MCSTAT_DEPRECATED("mcstat_diag_t_size")
MCSTAT_API int mcstat_t_size_edgeworth(double skewness, double kurtosis, uint64_t k, uint64_t m, double alpha,
                                       double size[2]);
MCSTAT_DEPRECATED("mcstat_diag_batch_size")
MCSTAT_API int mcstat_batch_size_recommend(double skewness, double kurtosis, uint64_t m, double alpha,
                                           double tolerance, uint64_t *k);

/* goodness of fit: the mcstat_gof_ stem (mcstat_chisq_ is the distribution) */
typedef struct mcstat_chisq_options mcstat_chisq_options;
#define mcstat_chisq_expected mcstat_gof_expected
#define MCSTAT_CHISQ_PROBABILITIES MCSTAT_GOF_PROBABILITIES
#define MCSTAT_CHISQ_COUNTS MCSTAT_GOF_COUNTS
#define MCSTAT_CHISQ_DEFAULT_MIN_EXPECTED MCSTAT_GOF_DEFAULT_MIN_EXPECTED
#define MCSTAT_CHISQ_OPTIONS_INIT MCSTAT_GOF_OPTIONS_INIT
#define MCSTAT_CHISQ_OPTIONS_SIZE_0_1 MCSTAT_GOF_OPTIONS_SIZE_0_1
MCSTAT_DEPRECATED("mcstat_gof_options_init_size")
MCSTAT_API int mcstat_chisq_options_init_size(mcstat_chisq_options *opt, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_GOF_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_chisq_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_DEPRECATED("mcstat_gof_options_init")
MCSTAT_API int(mcstat_chisq_options_init)(mcstat_chisq_options *opt);
#define mcstat_chisq_options_init(opt) mcstat_chisq_options_init_size((opt), sizeof *(opt))
MCSTAT_DEPRECATED("mcstat_gof_default_min_expected") MCSTAT_API double mcstat_chisq_default_min_expected(void);
MCSTAT_DEPRECATED("mcstat_gof_chisq_test")
MCSTAT_API int mcstat_chisq_gof(const double *observed, const double *expected, size_t k,
                                const mcstat_chisq_options *opt, double alpha, mcstat_result *out);

/* sequential tests, two samples: mcstat_seq_push_2_<form>, as the tests'
 * mcstat_<test>_test_2_<form> */
MCSTAT_DEPRECATED("mcstat_seq_push_2_moments")
MCSTAT_API int mcstat_seq_push_moments_2(mcstat_seq *s, const mcstat_moments *bx, const mcstat_moments *by);
MCSTAT_DEPRECATED("mcstat_seq_push_2_array")
MCSTAT_API int mcstat_seq_push_array_2(mcstat_seq *s, const double *x, size_t nx, const double *y, size_t ny);
#endif /* MCSTAT_NO_EXPERIMENTAL */

/* row-wise tests: mcstat_<test>_test_<k>_matrix, each matrix (x, n, stride)
 * then rows.  The one-sample _rows calls put rows before n: swapping the
 * two compiles and answers for another matrix. */
MCSTAT_DEPRECATED("mcstat_t_test_1_matrix (rows moves after x_stride)")
MCSTAT_API int mcstat_t_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride, double mu0,
                                    int alternative, double alpha, unsigned flags, mcstat_result *out,
                                    int32_t *status);
MCSTAT_DEPRECATED("mcstat_t_test_2_matrix (same arguments)")
MCSTAT_API int mcstat_t_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y,
                                    size_t ny, size_t y_stride, size_t rows, double mu0, int alternative,
                                    double alpha, unsigned flags, mcstat_result *out, int32_t *status);
MCSTAT_DEPRECATED("mcstat_var_test_1_matrix (rows moves after x_stride)")
MCSTAT_API int mcstat_var_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride,
                                      double sigma2, int alternative, double alpha, unsigned flags,
                                      mcstat_result *out, int32_t *status);
MCSTAT_DEPRECATED("mcstat_var_test_2_matrix (same arguments)")
MCSTAT_API int mcstat_var_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y,
                                      size_t ny, size_t y_stride, size_t rows, double ratio,
                                      int alternative, double alpha, unsigned flags, mcstat_result *out,
                                      int32_t *status);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_H */
