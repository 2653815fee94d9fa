/*
 * noncentral.c - the noncentral t distribution, from R's standalone math
 * library (Debian's r-mathlib: libRmath, pnt = AS 243 by Lenth 1989 with
 * R's corrections).  GSL has none; writing one by hand is what we avoid.
 *
 * libRmath is built with MATHLIB_STANDALONE, where a warning is a printf to
 * the caller's stdout and an error an exit(1).  pnt itself never reaches an
 * error; its warnings are avoided here, not silenced:
 *   - domain ("argument out of domain") is silent in R's ML_WARNING, and the
 *     arguments are validated before the call anyway;
 *   - "full precision may not have been achieved in pnt{final}" is printed
 *     when the lower tail is asked for and the series sum exceeds 1 - 1e-10.
 *     The series sums P(|T| <= |t|)-like terms for |t| and |ncp|; asking for
 *     the tail on the far side of t (upper for t >= 0, lower for t < 0, after
 *     pnt's own reflection) never takes that branch, and the other tail is
 *     its complement, which only costs relative accuracy where it is below
 *     about 1e-12 anyway (pnt's accuracy is absolute, not relative);
 *   - the iteration limit (1000 terms) needs ncp^2/2 + ~7 sqrt(ncp^2/2)
 *     terms, below 1000 wherever the series is used (|ncp| <= 37.62 and
 *     df <= 4e5; beyond, pnt returns the normal approximation of Abramowitz
 *     & Stegun 26.7.10 without iterating);
 *   - "underflow occurred" needs exp(-ncp^2/2) == 0, unreachable after the
 *     37.62 switch above.
 * tests/c/test_power.c calls pnt over a grid of t, df and ncp with stdout
 * redirected and checks that nothing was printed.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#define MATHLIB_STANDALONE 1
#include <Rmath.h>

#include "internal.h"

static double clamp01(double p)
{
    if (p < 0.0 && p > -1e-9)
        return 0.0;
    if (p > 1.0 && p < 1.0 + 1e-9)
        return 1.0;
    return p; /* NaN or far out: the caller reports MCSTAT_ENUMERIC */
}

int mcstat__nct_tails(double t, double df, double ncp, double *lower, double *upper)
{
    if (!(df > 0.0) || isnan(t) || !isfinite(ncp) || !lower || !upper)
        return MCSTAT_EINVAL;
    if (isinf(t)) {
        *lower = t > 0 ? 1.0 : 0.0;
        *upper = 1.0 - *lower;
        return MCSTAT_OK;
    }
    if (ncp == 0.0) { /* central: mcstat's own t, accurate in both tails */
        mcstat_tails tt;
        int st = mcstat__t_tails(t, df, &tt);
        if (st)
            return st;
        *lower = tt.p;
        *upper = tt.q;
        return MCSTAT_OK;
    }
    /* pnt reflects t < 0 to (-t, -ncp) and flips the tail; after the flip the
     * tail asked for must be the upper one: so ask for the upper tail of
     * t >= 0 and for the lower tail of t < 0 (see the comment above). */
    /* pnt's sum can land a little outside [0, 1] (R's power.t.test reports
     * powers of 1 + 6e-11): clamp within its 1e-12-level accuracy, with
     * room, and call anything further out a failure. */
    double p;
    if (t >= 0.0) {
        p = clamp01(pnt(t, df, ncp, 0, 0));
        if (!(p >= 0.0 && p <= 1.0))
            return MCSTAT_ENUMERIC;
        *upper = p;
        *lower = 1.0 - p;
    } else {
        p = clamp01(pnt(t, df, ncp, 1, 0));
        if (!(p >= 0.0 && p <= 1.0))
            return MCSTAT_ENUMERIC;
        *lower = p;
        *upper = 1.0 - p;
    }
    return MCSTAT_OK;
}
