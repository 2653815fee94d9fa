/*
 * harness.h - a minimal test harness: checks count and report, main returns
 * the number of failures (ctest treats non-zero as failure).
 */
#ifndef MCSTAT_TEST_HARNESS_H
#define MCSTAT_TEST_HARNESS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int h_checks, h_failures;

#define CHECK(cond)                                                               \
    do {                                                                          \
        h_checks++;                                                               \
        if (!(cond)) {                                                            \
            h_failures++;                                                         \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                         \
    } while (0)

#define CHECK_MSG(cond, ...)                                                      \
    do {                                                                          \
        h_checks++;                                                               \
        if (!(cond)) {                                                            \
            h_failures++;                                                         \
            fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                         \
            fputc('\n', stderr);                                                  \
        }                                                                         \
    } while (0)

/* Relative error, treating equal infinities/NaNs as exact and a zero
 * reference by absolute error. */
static inline double rel_err(double got, double want)
{
    if (got == want || (isnan(got) && isnan(want)))
        return 0.0;
    if (isnan(got) || isnan(want) || isinf(got) || isinf(want))
        return INFINITY;
    if (want == 0.0)
        return fabs(got);
    return fabs(got - want) / fabs(want);
}

#define CHECK_REL(got, want, tol, ...)                                            \
    do {                                                                          \
        double g_ = (got), w_ = (want), e_ = rel_err(g_, w_);                     \
        h_checks++;                                                               \
        if (!(e_ <= (tol))) {                                                     \
            h_failures++;                                                         \
            fprintf(stderr, "%s:%d: %s = %.17g, want %.17g (rel err %.3g > %.3g): ", \
                    __FILE__, __LINE__, #got, g_, w_, e_, (double)(tol));         \
            fprintf(stderr, __VA_ARGS__);                                         \
            fputc('\n', stderr);                                                  \
        }                                                                         \
    } while (0)

#define CHECK_INT(got, want)                                                      \
    do {                                                                          \
        long g_ = (long)(got), w_ = (long)(want);                                 \
        h_checks++;                                                               \
        if (g_ != w_) {                                                           \
            h_failures++;                                                         \
            fprintf(stderr, "%s:%d: %s = %ld, want %ld\n", __FILE__, __LINE__, #got, g_, w_); \
        }                                                                         \
    } while (0)

/* The size knob of the slow tests: n divided by the integer in the
 * environment variable MCSTAT_TEST_SCALE (default 1), but not below lo.
 * make asan-test / valgrind-test set it so that a test does the same work on
 * smaller sizes under the sanitizers and valgrind. */
static inline size_t h_scaled(size_t n, size_t lo)
{
    const char *s = getenv("MCSTAT_TEST_SCALE");
    long d = s ? strtol(s, NULL, 10) : 1;
    size_t m = d > 1 ? n / (size_t)d : n;
    return m < lo ? (lo < n ? lo : n) : m;
}

static inline int h_report(const char *name)
{
    printf("%s: %d checks, %d failures\n", name, h_checks, h_failures);
    return h_failures > 255 ? 255 : h_failures;
}

#endif
