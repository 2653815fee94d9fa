/*
 * fuzz_check.h - invariants every answer of mcstat must satisfy, checked by
 * the harnesses after every call.  A violation prints what was wrong and
 * traps, so the fuzzer reports wrong answers as it reports crashes.
 *
 * The checks hold for any input whatsoever; where floating point makes an
 * identity approximate (a statistic against its critical value) the
 * tolerance is stated and far above the library's documented accuracy.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_FUZZ_CHECK_H
#define MCSTAT_FUZZ_CHECK_H

#include "mcstat.h"

#include <float.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* The library computes in IEEE defaults whatever the caller's mode (its
 * MCSTAT_IEEE_SCOPE); make portability-test runs the harnesses with
 * flush-to-zero and denormals-are-zero set.  A harness's own reference
 * arithmetic (a weighted channel sum, a comparison with 0) done in that mode
 * flushes the subnormals the library keeps and disagrees with it: after the
 * call under test, FZ_IEEE_SCOPE() puts the rest of the harness's scope in
 * the library's mode. */
#include "../../libmcstat/src/fpenv.h"
#define FZ_IEEE_SCOPE() MCSTAT_IEEE_SCOPE()

#define FZ_ASSERT(cond, ...)                                                              \
    do {                                                                                  \
        if (!(cond)) {                                                                    \
            fprintf(stderr, "\nmcstat fuzz: invariant violated at %s:%d: %s\n  ", __FILE__, \
                    __LINE__, #cond);                                                     \
            fprintf(stderr, __VA_ARGS__);                                                 \
            fputc('\n', stderr);                                                          \
            __builtin_trap();                                                             \
        }                                                                                 \
    } while (0)

/* A status is one of the documented codes and has a sentence. */
static inline void fz_check_status(int st)
{
    FZ_ASSERT(st >= MCSTAT_OK && st <= MCSTAT_ETOOBIG, "status %d", st);
    const char *s = mcstat_strerror(st);
    FZ_ASSERT(s && *s, "strerror(%d)", st);
}

/* MCSTAT_ENUMERIC ("an iteration fails (not expected)", mcstat.h) is a
 * failure wherever the header promises an answer.  The distribution
 * functions answer for df in [1e-3, 1e15] (fuzz_dist checks them), and an
 * analytic test's degrees of freedom lie in [1, n_total - 2] (Welch's between
 * min(nx, ny) - 1 and nx + ny - 2): a test over at most 1e15 values must not
 * return it. */
static inline void fz_check_not_enumeric(int st, double n_total, const char *what)
{
    FZ_ASSERT(!(st == MCSTAT_ENUMERIC && n_total <= 1e15), "%s: MCSTAT_ENUMERIC with %.17g values", what, n_total);
}

/* The R-style block of a result the library produced always fits a 4 KiB
 * buffer, and its reported length is the string's. */
static inline void fz_check_format(const mcstat_result *r)
{
    char buf[4096];
    size_t len = 0;
    int st = mcstat_result_format(r, NULL, NULL, buf, sizeof buf, &len);
    FZ_ASSERT(st == MCSTAT_OK, "format status %d", st);
    FZ_ASSERT(strlen(buf) == len, "format length %zu, strlen %zu", len, strlen(buf));
}

/* x <= y up to a relative slack. */
static inline int fz_le(double x, double y, double rel)
{
    return x <= y || x - y <= rel * fmax(fabs(x), fabs(y));
}

enum {
    FZ_NO_INTERVALS = 1 /* critical values and intervals were not asked for */
};

/* Whether alpha lies in (0, 1) as the library sees it: by its bits, since
 * a harness run with denormals-are-zero (make portability-test) compares a
 * subnormal alpha as 0, while the library validates in its own IEEE scope. */
static inline int fz_alpha_valid(double alpha)
{
    uint64_t b;
    memcpy(&b, &alpha, sizeof b);
    return !(b >> 63) && (b << 1) != 0 && alpha < 1.0; /* positive (NaN: alpha < 1 fails) */
}

/* The invariants of a result returned with status st by a test of kind
 * `test` called with `alternative` and `alpha` (nothing to check unless OK). */
static inline void fz_check_result(int st, const mcstat_result *r, int test, int alternative, double alpha,
                                   unsigned flags)
{
    fz_check_status(st);
    if (st != MCSTAT_OK)
        return;
    FZ_ASSERT(r->test == test, "test %d, want %d", r->test, test);
    FZ_ASSERT(r->alternative == alternative, "alternative %d, want %d", r->alternative, alternative);
    FZ_ASSERT(r->alpha == alpha, "alpha %.17g, want %.17g", r->alpha, alpha);
    FZ_ASSERT(fz_alpha_valid(alpha), "OK with alpha %.17g", alpha);
    FZ_ASSERT(r->p_value >= 0.0 && r->p_value <= 1.0, "p_value %.17g", r->p_value);
    FZ_ASSERT(r->p_value_se >= 0.0 && r->p_value_se <= 0.5, "p_value_se %.17g", r->p_value_se);
    FZ_ASSERT(r->reject == 0 || r->reject == 1, "reject %d", r->reject);
    FZ_ASSERT(r->reject == (r->p_value <= alpha), "reject %d with p %.17g, alpha %.17g", r->reject, r->p_value,
              alpha);
    FZ_ASSERT(r->decision >= -1 && r->decision <= 1, "decision %d", r->decision);
    FZ_ASSERT((r->decision != 0) == (r->reject != 0), "decision %d, reject %d", r->decision, r->reject);
    FZ_ASSERT(mcstat_decision_name(r->decision) != NULL, "decision name %d", r->decision);
    FZ_ASSERT(!isnan(r->statistic), "statistic NaN");
    if (alternative == MCSTAT_LESS)
        FZ_ASSERT(r->decision <= 0, "decision %d against 'less'", r->decision);
    if (alternative == MCSTAT_GREATER)
        FZ_ASSERT(r->decision >= 0, "decision %d against 'greater'", r->decision);
    fz_check_format(r);

    if (test == MCSTAT_TEST_KS_2) {
        FZ_ASSERT(r->n[0] >= 1 && r->n[1] >= 1, "n %llu %llu", (unsigned long long)r->n[0],
                  (unsigned long long)r->n[1]);
        FZ_ASSERT(r->statistic >= 0.0, "K-S statistic %.17g", r->statistic);
        if (r->ks_weight == MCSTAT_KS_WEIGHT_NONE)
            FZ_ASSERT(r->statistic <= 1.0, "K-S D %.17g", r->statistic);
        FZ_ASSERT(r->method == MCSTAT_METHOD_EXACT || r->method == MCSTAT_METHOD_SIMULATE ||
                      r->method == MCSTAT_METHOD_ASYMPTOTIC,
                  "K-S method %d", r->method);
        if (r->method != MCSTAT_METHOD_SIMULATE)
            FZ_ASSERT(r->p_value_se == 0.0, "p_value_se %.17g (method %d)", r->p_value_se, r->method);
        if (!isnan(r->critical[1])) {
            FZ_ASSERT(r->critical[0] == -INFINITY, "critical[0] %.17g", r->critical[0]);
            /* documented: reject == statistic > critical[1] == p <= alpha */
            FZ_ASSERT(r->reject == (r->statistic > r->critical[1]), "reject %d, D %.17g, critical %.17g (method %d)",
                      r->reject, r->statistic, r->critical[1], r->method);
        }
        return;
    }

    FZ_ASSERT(r->method == (test == MCSTAT_TEST_EFFICIENCY ? MCSTAT_METHOD_ASYMPTOTIC : MCSTAT_METHOD_ANALYTIC),
              "method %d", r->method);
    FZ_ASSERT(r->p_value_se == 0.0, "p_value_se %.17g", r->p_value_se);
    FZ_ASSERT(r->n[0] >= 2, "n %llu", (unsigned long long)r->n[0]);
    int two = test == MCSTAT_TEST_T_2 || test == MCSTAT_TEST_VAR_2 || test == MCSTAT_TEST_T_2_POOLED ||
              test == MCSTAT_TEST_T_PAIRED || test == MCSTAT_TEST_EFFICIENCY;
    FZ_ASSERT(two ? r->n[1] >= 2 : r->n[1] == 0, "n[1] %llu", (unsigned long long)r->n[1]);
    if (test == MCSTAT_TEST_T_PAIRED) /* the pairs */
        FZ_ASSERT(r->n[0] == r->n[1], "paired n %llu %llu", (unsigned long long)r->n[0], (unsigned long long)r->n[1]);
    if (test == MCSTAT_TEST_T_2_POOLED)
        FZ_ASSERT(r->df[0] == (double)r->n[0] + (double)r->n[1] - 2.0, "pooled df %.17g", r->df[0]);
    FZ_ASSERT(r->df[0] > 0.0, "df %.17g", r->df[0]);
    if (test == MCSTAT_TEST_T_2) {
        /* Welch-Satterthwaite lies between min(nx, ny) - 1 and nx + ny - 2 */
        double lo = (double)(r->n[0] < r->n[1] ? r->n[0] : r->n[1]) - 1.0;
        double hi = (double)r->n[0] + (double)r->n[1] - 2.0;
        FZ_ASSERT(fz_le(lo, r->df[0], 1e-12) && fz_le(r->df[0], hi, 1e-12), "Welch df %.17g outside [%g, %g]",
                  r->df[0], lo, hi);
    }
    if (test == MCSTAT_TEST_EFFICIENCY) /* a ratio, its log's standard error, a t */
        FZ_ASSERT(r->estimate[0] >= 0.0 && r->std_error > 0.0 && r->df[0] <= 1e15, "estimate %.17g, se %.17g, "
                  "df %.17g", r->estimate[0], r->std_error, r->df[0]);
    else if (test == MCSTAT_TEST_T_1 || test == MCSTAT_TEST_T_2 || test == MCSTAT_TEST_T_2_POOLED ||
             test == MCSTAT_TEST_T_PAIRED)
        FZ_ASSERT(r->std_error >= 0.0, "std_error %.17g", r->std_error);
    else
        FZ_ASSERT(r->estimate[0] >= 0.0 && r->statistic >= 0.0, "estimate %.17g, statistic %.17g", r->estimate[0],
                  r->statistic);
    if (flags & FZ_NO_INTERVALS)
        return;

    double c0 = r->critical[0], c1 = r->critical[1], s = r->statistic;
    /* ordered, up to rounding: at alpha = 1 - 2^-53 both two-sided critical
     * values are the median, and they may come out 1 ulp apart either way */
    FZ_ASSERT(!isnan(c0) && !isnan(c1) && fz_le(c0, c1, 4 * DBL_EPSILON), "critical %.17g %.17g", c0, c1);
    FZ_ASSERT(!isnan(r->conf_int[0]) && !isnan(r->conf_int[1]) &&
                  fz_le(r->conf_int[0], r->conf_int[1], 4 * DBL_EPSILON),
              "conf_int %.17g %.17g", r->conf_int[0], r->conf_int[1]);
    /* The statistic clearly beyond a critical value rejects; clearly inside
     * does not (p-values and quantiles agree to ~1e-13; we allow 1e-6).  Only
     * where alpha is a normal number: below, quantiles are not promised. */
    /* Where p rounds to within 1e-12 of alpha (p = 0.5 + 4e-126 is 0.5 in
     * double) the rule p <= alpha decides on the rounded value: skipped. */
    int clear = fabs(r->p_value - alpha) > 1e-12 * alpha;
    if (alpha >= 1e-300 && isfinite(s) && clear) {
        double m = 1e-6;
        int out_hi = alternative != MCSTAT_LESS && s > c1 + m * fabs(c1) + 1e-300;
        int out_lo = alternative != MCSTAT_GREATER && s < c0 - m * fabs(c0) - 1e-300;
        int in = (alternative == MCSTAT_GREATER || s > c0 + m * fabs(c0) + 1e-300) &&
                 (alternative == MCSTAT_LESS || s < c1 - m * fabs(c1) - 1e-300);
        if (out_hi || out_lo)
            FZ_ASSERT(r->reject, "statistic %.17g beyond critical [%.17g, %.17g] but p %.17g > alpha %.17g", s, c0, c1,
                      r->p_value, alpha);
        if (in)
            FZ_ASSERT(!r->reject, "statistic %.17g inside critical [%.17g, %.17g] but p %.17g <= alpha %.17g", s, c0,
                      c1, r->p_value, alpha);
    }
    /* Duality: the null value clearly inside the interval is not rejected,
     * clearly outside it is (slack: 1e-6 of the interval's half-width, 1e-12
     * of the bound: far above the rounding of either). */
    double c = test == MCSTAT_TEST_T_2 ? r->estimate[0] - r->estimate[1] : r->estimate[0];
    double lo = r->conf_int[0], hi = r->conf_int[1], nv = r->null_value;
    /* A variance interval is exact wherever its bound is a double, also where
     * the critical value is not (0 below DBL_MIN, Inf above DBL_MAX); a bound
     * of 0 or Inf then means the true bound under- or overflows, which
     * decides duality the same way.  But p is that of the statistic as a
     * double: where it is subnormal it carries a relative error up to
     * 2^-1074 / s, added to the slack; where it is 0 or Inf (or has fewer than
     * ~10 bits) the test decides on the saturated value (p = 0): not checked. */
    double s_rel = 0.0;
    if (test == MCSTAT_TEST_VAR_1 || test == MCSTAT_TEST_VAR_2)
        s_rel = s >= DBL_MIN && s <= DBL_MAX ? 0.0 : s > 0.0 && s < DBL_MIN ? 0x1p-1074 / s : INFINITY;
    if (alpha >= 1e-300 && isfinite(c) && isfinite(nv) && clear && s_rel < 1e-3) {
        double m = 1e-12 + 2.0 * s_rel;
        double tl = 1e-6 * fabs(lo - c) + m * fabs(lo), th = 1e-6 * fabs(hi - c) + m * fabs(hi);
        int outside = (isfinite(lo) && nv < lo - tl) || (isfinite(hi) && nv > hi + th);
        /* hi = Inf: the true bound may be DBL_MAX rounded up */
        int inside = (lo == -INFINITY || nv > lo + tl) && (hi == INFINITY ? nv <= 0x1p1023 : nv < hi - th);
        if (outside)
            FZ_ASSERT(r->reject, "null %.17g outside conf_int [%.17g, %.17g] but p %.17g > alpha %.17g", nv, lo, hi,
                      r->p_value, alpha);
        if (inside)
            FZ_ASSERT(!r->reject, "null %.17g inside conf_int [%.17g, %.17g] but p %.17g <= alpha %.17g", nv, lo, hi,
                      r->p_value, alpha);
    }
    /* A t interval holds the mean of x, unless a one-sided interval has level
     * 1 - alpha below 1/2.  (Not so for variances: chi-squared is skewed.) */
    if (test == MCSTAT_TEST_T_1 && isfinite(r->estimate[0]) && (alternative == MCSTAT_TWO_SIDED || alpha <= 0.5)) {
        double e = r->estimate[0];
        FZ_ASSERT(fz_le(r->conf_int[0], e, 1e-9) && fz_le(e, r->conf_int[1], 1e-9),
                  "estimate %.17g outside conf_int [%.17g, %.17g]", e, r->conf_int[0], r->conf_int[1]);
    }
}

/* Per-pixel outputs under MCSTAT_PIXELS_RENDER, whose numbers are not the
 * plain Welch reference's (their closed forms: tests/c/test_pixels_test.c):
 * pixels outside [begin, end) untouched (-7 sentinels), every status a known
 * one, every successful pixel's p-value in [0, 1]. */
static inline void fz_check_render_pixels(const int32_t *status, const double *p, size_t count, size_t begin,
                                          size_t end)
{
    for (size_t i = 0; i < count; i++) {
        if (i < begin || i >= end) {
            FZ_ASSERT(status[i] == -7 && p[i] == -7.0, "render: pixel %zu outside the range written", i);
            continue;
        }
        FZ_ASSERT(status[i] >= 0 && status[i] <= MCSTAT_EHEAVYTAIL, "render: pixel %zu status %d", i, (int)status[i]);
        FZ_ASSERT(status[i] != MCSTAT_OK || (p[i] >= 0.0 && p[i] <= 1.0), "render: pixel %zu p %g", i, p[i]);
    }
}

#endif /* MCSTAT_FUZZ_CHECK_H */
