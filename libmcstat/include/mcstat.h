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
 * mcstat.h includes one header per family, in the order a user meets
 * things (a program may include a family alone, <mcstat/tests.h>):
 *   1. mcstat/base.h          Conventions: statuses, alternatives, options
 *                             that grow, the export and attribute macros.
 *   2. mcstat/moments.h       Accumulators: mcstat_moments (one sample,
 *                             streaming and mergeable), its serialized
 *                             bytes, arrays of accumulators (one per
 *                             pixel), and mcstat_stream (a per-thread
 *                             buffer for checks inside a renderer).
 *   3. mcstat/tests.h         The tests and their result: mcstat_result,
 *                             then t, chi-squared, F (each on arrays and on
 *                             accumulators), the efficiency ratio of two
 *                             estimators and Kolmogorov-Smirnov.
 *   4. mcstat/pixels.h        Per-pixel tests: the same tests once per
 *                             pixel of an image stack (mcstat_pixels_test),
 *                             per row of a matrix or of an array of
 *                             accumulators.
 *   5. mcstat/adjust.h        Multiple testing: adjusted p-values (R's
 *                             p.adjust) for the millions of per-pixel tests.
 *   6. mcstat/equivalence.h   Equivalence: TOST, "the bias is below eps".
 *   7. mcstat/distributions.h t, chi-squared and F tails and quantiles.
 *   8. mcstat/version.h       Sizes, versions and GSL's handler.
 *   9. mcstat/check.h         Renderer checks: do a BSDF's, an emitter's or
 *                             a warp's sample(), pdf(), eval() and sample
 *                             weight agree?
 *  10. mcstat/sequential.h    Sequential tests: look after every batch,
 *                             stop as soon as the evidence decides, the
 *                             error rate still alpha.
 * then the experimental families:
 *  11. mcstat/power.h         Power and sample size.
 *  12. mcstat/diagnostics.h   Estimator diagnostics: shape, tails, batch size.
 *  13. mcstat/gof.h           Goodness of fit: chi-squared GOF of cell
 *                             counts, the exact binomial test and the
 *                             battery meta-test.
 * and last
 *  14. mcstat/deprecated.h    Deprecated names, kept so that older code
 *                             still builds and links.
 * Beside them, not included here: mcstat/embedded.h, the checks embedded in
 * a renderer's loop (MCSTAT_CHECK_ADD, MCSTAT_CHECK_MEAN; mcstat_check.h is
 * its old name), and the C++ headers mcstat_testing.h (test-framework
 * assertions) and mcstat_pbrt.h (pbrt BxDFs to the renderer checks).
 * Where a new function goes: in the family of its concept, named
 * mcstat_<family>_<verb> (mcstat_moments_add, mcstat_diag_compute) or
 * mcstat_<test>_test_<k>[_moments|_matrix|_moments_rows] for the tests.
 *
 * Experimental families (11-13) are as tested and as ABI-stable as the
 * rest, but their names and options may change before 1.0; a renamed
 * function stays as a deprecated alias for the next release (and its
 * symbol for as long as the SOVERSION).  A program opts in by defining
 * MCSTAT_EXPERIMENTAL before including mcstat.h; without it their calls
 * still compile in 0.3, each use warning with the opt-in, and from 0.4
 * mcstat.h declares them only with it.  MCSTAT_NO_EXPERIMENTAL leaves them
 * out.  The renderer checks and the sequential tests, experimental until
 * 0.2, are stable from 0.3: used on Mitsuba 3's, pbrt-v3's and Blender
 * Cycles' code and renders by people who did not write them.
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

/* The stable families, in the order a user meets them. */
#include "mcstat/base.h"
#include "mcstat/moments.h"
#include "mcstat/tests.h"
#include "mcstat/pixels.h"
#include "mcstat/adjust.h"
#include "mcstat/equivalence.h"
#include "mcstat/distributions.h"
#include "mcstat/version.h"
#include "mcstat/check.h"
#include "mcstat/sequential.h"
/* The experimental families (base.h, MCSTAT_EXPERIMENTAL_API). */
#ifndef MCSTAT_NO_EXPERIMENTAL
#include "mcstat/power.h"
#include "mcstat/diagnostics.h"
#include "mcstat/gof.h"
#endif
#include "mcstat/deprecated.h"

#endif /* MCSTAT_H */
