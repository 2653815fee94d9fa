/*
 * mcstat/embedded.h - statistical checks embedded in a renderer, compiled in
 * or out with one switch, like assert().  (Until 0.3 it was mcstat_check.h,
 * a name that read as the renderer checks' of mcstat/check.h; that name
 * still includes this header.)
 *
 * A renderer keeps one mcstat_stream per thread (a 4 KiB plain struct: no
 * allocation, no lock), adds each estimate to it in its hot loop (a store and
 * a counter), merges the threads' streams at the end of a frame and checks
 * expectations on the merged one, without storing samples:
 *
 *     #define MCSTAT_CHECKS 1          // or -DMCSTAT_CHECKS=1; default 0: off
 *     #include <mcstat/embedded.h>
 *
 *     MCSTAT_CHECK_ONLY(mcstat_stream acc[NTHREADS]; mcstat_stream frame;)
 *     ...  MCSTAT_CHECK_INIT(acc[t]);                   // each thread
 *     ...  MCSTAT_CHECK_ADD(acc[t], estimate);          // per sample
 *     ...  MCSTAT_CHECK_MERGE(frame, acc[t]);           // end of frame
 *     if (MCSTAT_CHECK_MEAN(frame, reference, tolerance, 0.001)) ...  // failed
 *     if (MCSTAT_CHECK_VAR_BELOW(frame, bound, 0.001)) ...            // failed
 *
 * With MCSTAT_CHECKS undefined or 0 every macro expands to nothing (the
 * checks to 0) and NONE OF ITS ARGUMENTS IS EVALUATED, as
 * with assert(): keep side effects out of them.  MCSTAT_CHECK_ONLY(...)
 * keeps its argument (declarations, statements) only when checks are on.
 *
 * A check macro evaluates to 1 when the check failed (the test rejected its
 * H0 at level alpha, or the stream saw a NaN or an infinity, or the check
 * could not be computed, e.g. fewer than two values) and 0 when it passed.
 * On failure it first calls MCSTAT_CHECK_ON_FAILURE(what, file, line, status,
 * result), which by default prints the location, the status and the R-style
 * block of the test to stderr; define it before including this header to log,
 * count or abort instead (result is NULL when status != MCSTAT_OK).
 *
 * Continuous checking (sequential mode).  A check at one frame's end tests
 * that frame alone; tested again every frame, a fixed-n test raises false
 * alarms far more often than alpha.  The sequential check instead keeps an
 * anytime-valid test of the mean over every frame so far (an mcstat_seq,
 * 448 bytes of plain data, mcstat/sequential.h): it may be looked at after
 * every frame, its false-alarm rate over the whole run stays at most alpha,
 * and it reports as soon as a bias is certain:
 *
 *     MCSTAT_CHECK_ONLY(mcstat_stream acc[NTHREADS]; mcstat_stream frame; mcstat_seq bias;)
 *     MCSTAT_CHECK_SEQ_MEAN_INIT(bias, reference, 0.001);        // once
 *     for (;;) {                                                  // frames
 *         MCSTAT_CHECK_INIT(frame);
 *         ...  MCSTAT_CHECK_INIT(acc[t]);                         // each thread
 *         ...  MCSTAT_CHECK_ADD(acc[t], estimate);                // per sample
 *         ...  MCSTAT_CHECK_MERGE(frame, acc[t]);                 // end of frame
 *         if (MCSTAT_CHECK_SEQ_PUSH(bias, frame)) ...             // biased
 *     }
 *     if (MCSTAT_CHECK_SEQ_FINISH(bias)) ...                      // end of run
 *
 * MCSTAT_CHECK_SEQ_MEAN_INIT(seq, reference, alpha) starts a two-sided test
 * of mean == reference at level alpha (the library's other defaults: the
 * tests hold while fewer than 100 values, no spread, or too few of a
 * heavy tail's rare large values have been seen);
 * MCSTAT_CHECK_SEQ_MEAN_INIT_EPS(seq, reference, eps, alpha) also stops,
 * passed for good, once the mean is shown within reference +- eps (the
 * same error rate covers both).  A failed initialisation (alpha outside
 * (0, 1), eps < 0, a reference not finite) leaves seq empty, and every push
 * then reports MCSTAT_EINVAL.
 *
 * MCSTAT_CHECK_SEQ_PUSH(seq, frame) adds the frame's stream as one look
 * (O(1) per look; the per-sample cost is MCSTAT_CHECK_ADD's alone) and
 * evaluates to 1 from the look at which the test decided "less" or
 * "greater" on (a decision is final), else 0.  It calls
 * MCSTAT_CHECK_ON_FAILURE once, at the deciding look, with the test's
 * R-style block (the n it decided at on its last line); also at every push
 * that fails (the frame saw a NaN or an infinity: status
 * MCSTAT_ENONFINITE, result NULL, the test unchanged; the push evaluates
 * to 1).  MCSTAT_CHECK_SEQ_FINISH(seq), at the end of a run, evaluates to 1
 * when the test decided a bias (already reported) or when its kurtosis
 * gate was still closed at the last look: the tails never allowed a
 * verdict, reported now with status MCSTAT_EHEAVYTAIL.  Undecided with
 * data that allowed a decision, it evaluates to 0: no bias was found (none
 * larger than the sequence's width, mcstat_seq_result's conf_int).
 *
 * The functions behind the macros are mcstat_stream_* (mcstat/moments.h)
 * and mcstat_seq_* (mcstat/sequential.h); use them directly to keep the
 * mcstat_result.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_EMBEDDED_H
#define MCSTAT_EMBEDDED_H

#ifndef MCSTAT_CHECKS
#define MCSTAT_CHECKS 0
#endif

#if MCSTAT_CHECKS

#include "moments.h"
#include "tests.h"
#include "sequential.h"

#include <stdio.h>
#include <string.h>

#ifndef MCSTAT_CHECK_ON_FAILURE
#define MCSTAT_CHECK_ON_FAILURE(what, file, line, status, result) \
    mcstat_check_print_failure_((what), (file), (line), (status), (result))
#endif

/* C++ callers may build with -Wzero-as-null-pointer-constant, which NULL trips. */
#if defined(__cplusplus) && __cplusplus >= 201103L
#define MCSTAT_CHECK_NULL_ nullptr
#else
#define MCSTAT_CHECK_NULL_ NULL
#endif

/* The default failure report (static inline: the header needs no extra
 * library symbol). */
static inline void mcstat_check_print_failure_(const char *what, const char *file, int line, int status,
                                               const mcstat_result *r)
{
    fprintf(stderr, "%s:%d: mcstat check failed: %s\n", file, line, what);
    if (status != MCSTAT_OK) {
        fprintf(stderr, "  %s\n", mcstat_strerror(status));
        return;
    }
    char text[2048];
    if (mcstat_result_format(r, "samples", MCSTAT_CHECK_NULL_, text, sizeof text, MCSTAT_CHECK_NULL_) == MCSTAT_OK)
        fputs(text, stderr);
}

static inline int mcstat_check_mean_at_(const mcstat_stream *s, double reference, double tolerance,
                                        double alpha, const char *what, const char *file, int line)
{
    mcstat_result r;
    int st = mcstat_stream_check_mean(s, reference, tolerance, alpha, &r);
    if (st == MCSTAT_OK && !r.reject)
        return 0;
    const mcstat_result *shown = MCSTAT_CHECK_NULL_; /* no result to show when the test could not run */
    if (st == MCSTAT_OK)
        shown = &r;
    MCSTAT_CHECK_ON_FAILURE(what, file, line, st, shown);
    return 1;
}

static inline int mcstat_check_var_at_(const mcstat_stream *s, double bound, double alpha, const char *what,
                                       const char *file, int line)
{
    mcstat_result r;
    int st = mcstat_stream_check_var(s, bound, alpha, &r);
    if (st == MCSTAT_OK && !r.reject)
        return 0;
    const mcstat_result *shown = MCSTAT_CHECK_NULL_; /* no result to show when the test could not run */
    if (st == MCSTAT_OK)
        shown = &r;
    MCSTAT_CHECK_ON_FAILURE(what, file, line, st, shown);
    return 1;
}

/* ---- the sequential mode (mcstat/sequential.h) ---- */

/* A failed initialisation leaves *q empty (version 0), so that every push
 * reports MCSTAT_EINVAL instead of reading an uninitialised struct. */
static inline void mcstat_check_seq_init_(mcstat_seq *q, double reference, double eps, double alpha)
{
    mcstat_seq_options o;
    mcstat_seq_options_init(&o);
    o.alpha = alpha;
    o.eps = eps;
    if (mcstat_seq_init(q, MCSTAT_SEQ_MEAN_1, reference, &o) != MCSTAT_OK)
        memset(q, 0, sizeof *q);
}

/* A bias: decided, and not "equal". */
static inline int mcstat_check_seq_biased_(const mcstat_seq *q)
{
    return q->state == MCSTAT_SEQ_DECIDED && q->decision != MCSTAT_DECISION_EQUAL;
}

static inline int mcstat_check_seq_push_at_(mcstat_seq *q, const mcstat_stream *frame, const char *what,
                                            const char *file, int line)
{
    int before = mcstat_check_seq_biased_(q);
    int st = mcstat_seq_push_stream(q, frame);
    if (st != MCSTAT_OK) {
        MCSTAT_CHECK_ON_FAILURE(what, file, line, st, MCSTAT_CHECK_NULL_);
        return 1;
    }
    if (!mcstat_check_seq_biased_(q))
        return 0;
    if (!before) { /* the deciding look: reported once */
        mcstat_result r;
        const mcstat_result *shown = MCSTAT_CHECK_NULL_;
        st = mcstat_seq_result(q, &r);
        if (st == MCSTAT_OK)
            shown = &r;
        MCSTAT_CHECK_ON_FAILURE(what, file, line, st, shown);
    }
    return 1;
}

static inline int mcstat_check_seq_finish_at_(const mcstat_seq *q, const char *what, const char *file, int line)
{
    mcstat_result r;
    int st = mcstat_seq_finish(q, &r);
    if (st == MCSTAT_OK)
        return r.reject != 0; /* a bias was reported at its deciding look */
    MCSTAT_CHECK_ON_FAILURE(what, file, line, st, MCSTAT_CHECK_NULL_);
    return 1;
}

#define MCSTAT_CHECK_SEQ_MEAN_INIT(seq, reference, alpha) \
    mcstat_check_seq_init_(&(seq), (reference), 0.0, (alpha))
#define MCSTAT_CHECK_SEQ_MEAN_INIT_EPS(seq, reference, eps, alpha) \
    mcstat_check_seq_init_(&(seq), (reference), (eps), (alpha))
#define MCSTAT_CHECK_SEQ_PUSH(seq, frame) \
    mcstat_check_seq_push_at_(&(seq), &(frame), "sequential mean of " #seq " (pushed " #frame ")", __FILE__, __LINE__)
#define MCSTAT_CHECK_SEQ_FINISH(seq) \
    mcstat_check_seq_finish_at_(&(seq), "sequential mean of " #seq " (finished)", __FILE__, __LINE__)

#define MCSTAT_CHECK_ONLY(...) __VA_ARGS__
#define MCSTAT_CHECK_INIT(s) ((void)mcstat_stream_init(&(s)))
#define MCSTAT_CHECK_ADD(s, x) mcstat_stream_add(&(s), (x))
#define MCSTAT_CHECK_MERGE(dst, src) ((void)mcstat_stream_merge(&(dst), &(src)))
#define MCSTAT_CHECK_MEAN(s, reference, tolerance, alpha)                                       \
    mcstat_check_mean_at_(&(s), (reference), (tolerance), (alpha),                              \
                          "mean of " #s " == " #reference " +- " #tolerance, __FILE__, __LINE__)
#define MCSTAT_CHECK_VAR_BELOW(s, bound, alpha) \
    mcstat_check_var_at_(&(s), (bound), (alpha), "variance of " #s " <= " #bound, __FILE__, __LINE__)

#else /* checks off: nothing at all, arguments not evaluated */

#include <stddef.h>

/* The value arguments are named inside sizeof, which never evaluates them:
 * a variable the caller keeps only for a check is then not "unused" under
 * -Wall.  The stream and sequential-test arguments are not named: they may
 * be declared only inside MCSTAT_CHECK_ONLY.  The checks are a function call rather than the bare
 * constant 0, so that a check used as a statement, its value ignored, is not
 * a "statement with no effect". */
static inline int mcstat_check_off_(size_t unused)
{
    (void)unused;
    return 0;
}

#define MCSTAT_CHECK_ONLY(...)
#define MCSTAT_CHECK_INIT(s) ((void)0)
#define MCSTAT_CHECK_ADD(s, x) ((void)sizeof(x))
#define MCSTAT_CHECK_MERGE(dst, src) ((void)0)
#define MCSTAT_CHECK_MEAN(s, reference, tolerance, alpha) \
    mcstat_check_off_(sizeof(reference) + sizeof(tolerance) + sizeof(alpha))
#define MCSTAT_CHECK_VAR_BELOW(s, bound, alpha) mcstat_check_off_(sizeof(bound) + sizeof(alpha))
#define MCSTAT_CHECK_SEQ_MEAN_INIT(seq, reference, alpha) ((void)(sizeof(reference) + sizeof(alpha)))
#define MCSTAT_CHECK_SEQ_MEAN_INIT_EPS(seq, reference, eps, alpha) \
    ((void)(sizeof(reference) + sizeof(eps) + sizeof(alpha)))
#define MCSTAT_CHECK_SEQ_PUSH(seq, frame) mcstat_check_off_(0u)
#define MCSTAT_CHECK_SEQ_FINISH(seq) mcstat_check_off_(0u)

#endif
#endif /* MCSTAT_EMBEDDED_H */
