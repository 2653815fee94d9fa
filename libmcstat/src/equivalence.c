/*
 * equivalence.c - equivalence by two one-sided tests (TOST; Schuirmann
 * 1987): the mean (or the difference of means) lies inside [lower, upper]
 * when both "mean > lower" and "mean < upper" are shown at level alpha.
 * The p-value is the larger of the two one-sided p-values; the procedure
 * is the same as asking whether the 1 - 2 alpha confidence interval lies
 * inside the bounds, and that interval is reported.
 *
 * The one-sided tests are mcstat's own t tests (t_test.c), so the
 * double-double handling of large offsets carries over.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

static int valid_bounds(double lower, double upper)
{
    return isfinite(lower) && isfinite(upper) && lower < upper;
}

/* Combines the lower test (H1: > lower bound), the upper test (H1: < upper
 * bound) and the two-sided test at level 2 alpha (its interval) into *out. */
static void combine(int test, const mcstat_result *lo, const mcstat_result *hi, const mcstat_result *ci,
                    double null_value, double lbound, double ubound, double alpha, mcstat_result *out)
{
    mcstat_result r = *ci;
    r.test = test;
    r.alternative = MCSTAT_TWO_SIDED;
    r.alpha = alpha;
    r.null_value = null_value;
    int upper_binds = hi->p_value >= lo->p_value;
    const mcstat_result *b = upper_binds ? hi : lo;
    r.statistic = b->statistic;
    r.p_value = b->p_value;
    r.critical[0] = hi->critical[0]; /* -t(1-alpha, df) */
    r.critical[1] = lo->critical[1]; /* +t(1-alpha, df) */
    r.reject = r.p_value <= alpha;
    r.decision = r.reject ? 0 : upper_binds ? 1 : -1;
    r.tost_t_lower = lo->statistic;
    r.tost_t_upper = hi->statistic;
    r.tost_p_lower = lo->p_value;
    r.tost_p_upper = hi->p_value;
    r.tost_lower = lbound;
    r.tost_upper = ubound;
    *out = r;
}

int mcstat_equivalence_test_1_moments(const mcstat_moments *x, double mu0, double lower, double upper,
                                      double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !out || !isfinite(mu0) || !valid_bounds(lower, upper) || !(alpha > 0.0 && alpha < 0.5))
        return MCSTAT_EINVAL;
    double lb = mu0 + lower, ub = mu0 + upper;
    if (!isfinite(lb) || !isfinite(ub) || !(lb < ub))
        return MCSTAT_EINVAL;
    mcstat_result lo, hi, ci;
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    int st;
    if ((st = mcstat__t_test_1(x, lb, MCSTAT_GREATER, alpha, &qc, &lo)) ||
        (st = mcstat__t_test_1(x, ub, MCSTAT_LESS, alpha, &qc, &hi)) ||
        (st = mcstat__t_test_1(x, mu0, MCSTAT_TWO_SIDED, 2.0 * alpha, &qc, &ci)))
        return st;
    combine(MCSTAT_TEST_EQUIV_1, &lo, &hi, &ci, mu0, lb, ub, alpha, out);
    return MCSTAT_OK;
}

int mcstat_equivalence_test_2_moments(const mcstat_moments *x, const mcstat_moments *y, double lower,
                                      double upper, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !y || !out || !valid_bounds(lower, upper) || !(alpha > 0.0 && alpha < 0.5))
        return MCSTAT_EINVAL;
    mcstat_result lo, hi, ci;
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    int st;
    if ((st = mcstat__t_test_2(x, y, lower, MCSTAT_GREATER, alpha, &qc, &lo)) ||
        (st = mcstat__t_test_2(x, y, upper, MCSTAT_LESS, alpha, &qc, &hi)) ||
        (st = mcstat__t_test_2(x, y, 0.0, MCSTAT_TWO_SIDED, 2.0 * alpha, &qc, &ci)))
        return st;
    combine(MCSTAT_TEST_EQUIV_2, &lo, &hi, &ci, 0.0, lower, upper, alpha, out);
    return MCSTAT_OK;
}

int mcstat_equivalence_test_1(const double *x, size_t n, double mu0, double lower, double upper, double alpha,
                              mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !out)
        return MCSTAT_EINVAL;
    mcstat_moments m;
    mcstat_moments_init(&m);
    int st = mcstat_moments_add_array(&m, x, n);
    return st ? st : mcstat_equivalence_test_1_moments(&m, mu0, lower, upper, alpha, out);
}

int mcstat_equivalence_test_2(const double *x, size_t nx, const double *y, size_t ny, double lower, double upper,
                              double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!x || !y || !out)
        return MCSTAT_EINVAL;
    mcstat_moments mx, my;
    int st = mcstat__moments_of_two(x, nx, y, ny, &mx, &my);
    return st ? st : mcstat_equivalence_test_2_moments(&mx, &my, lower, upper, alpha, out);
}
