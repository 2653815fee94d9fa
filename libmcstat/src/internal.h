/*
 * internal.h - what libmcstat's sources share; nothing here is exported.
 * The umbrella every source includes: the visibility macro and argument
 * checks here, the rest in one header per concern (listed at the end).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_INTERNAL_H
#define MCSTAT_INTERNAL_H

#define MCSTAT_EXPERIMENTAL /* the library implements the experimental families */
#include "mcstat.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define MCSTAT_HIDDEN __attribute__((visibility("hidden")))

/* ---- argument checks ---------------------------------------------------- */
static inline int valid_alternative(int alt)
{
    return alt == MCSTAT_TWO_SIDED || alt == MCSTAT_LESS || alt == MCSTAT_GREATER;
}

static inline int valid_alpha(double alpha)
{
    return alpha > 0.0 && alpha < 1.0; /* false for NaN */
}

/* ---- reasons for refusals (status.c) --------------------------------------
 * mcstat__refuse writes the reason mcstat_last_error() returns and returns
 * status: `return mcstat__refuse(MCSTAT_EINVAL, "alpha must be in (0, 1),
 * got %g", alpha);`.  A function that gives reasons clears the last one
 * when it starts (mcstat__error_clear), so no earlier call's shows. */
MCSTAT_HIDDEN int mcstat__refuse(int status, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
MCSTAT_HIDDEN void mcstat__error_clear(void);
/* The tests' common arguments, refused with their reason: alternative,
 * alpha and the result pointer; MCSTAT_OK when they are fine. */
MCSTAT_HIDDEN int mcstat__refuse_test_args(int alternative, double alpha, const void *out);

/* One header per concern, in dependency order. */
#include "fpenv.h"      /* IEEE semantics and the caller's FP mode */
#include "dd.h"         /* double-double arithmetic */
#include "special.h"    /* tails, special functions, distributions */
#include "tests_core.h" /* moments, results, quantile cache, tests on accumulators */
#include "options.h"    /* options structs that grow */
#include "sort.h"       /* radix sort of doubles */
#include "ks.h"         /* Kolmogorov-Smirnov internals */

#endif /* MCSTAT_INTERNAL_H */
