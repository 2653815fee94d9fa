"""The accuracy mcstat.h promises for the block paths of the per-pixel
tests (mcstat_pixels_test: Welch's and the variance tests) against the
single call; the other per-pixel tests are the single call bit for bit."""
import math

import numpy as np


def p_tol(p, factor=2.0):
    """How far the block paths' p-values may be from the single call's
    (mcstat.h, mcstat_pixels_test): each of Welch's is within 3e-14 +
    4e-16 |log p| relative of the exact tail, as the single call's is, so
    they agree to twice that; the variance tests' to twice that too."""
    return factor * (3e-14 + 4e-16 * np.abs(np.log(np.maximum(p, np.finfo(float).tiny))))


def assert_pvalues_close(got, want, factor=2.0):
    got, want = np.asarray(got, float), np.asarray(want, float)
    assert np.array_equal(np.isnan(got), np.isnan(want))
    ok = ~np.isnan(want)
    err = np.abs(got[ok] - want[ok])
    assert (err <= p_tol(want[ok], factor) * np.abs(want[ok])).all(), float(np.max(err / np.abs(want[ok])))


def _close(got, want, rtol, scale=0.0):
    if isinstance(want, tuple):
        return all(_close(g, w, rtol, scale) for g, w in zip(got, want))
    if math.isnan(want) or math.isinf(want):
        return got == want or (math.isnan(got) and math.isnan(want))
    return abs(got - want) <= rtol * max(abs(want), scale)


def assert_welch_close(got, want):
    """One pixel's TestResult (got) against the single call's (want)."""
    assert got.method == want.method and got.alternative == want.alternative
    assert_pvalues_close(got.pvalue, want.pvalue)
    assert _close(got.statistic, want.statistic, 1e-14, 1.0)
    assert _close(got.df, want.df, 1e-14)
    assert _close(got.std_error, want.std_error, 1e-14)
    scale = 4.0 * want.std_error * math.sqrt(max(want.nobs))
    assert _close(tuple(got.estimate), tuple(want.estimate), 8 * np.finfo(float).eps, scale)
    hw = abs(want.conf_int[1] - want.conf_int[0])
    hw = hw if math.isfinite(hw) else want.std_error
    assert _close(tuple(got.conf_int), tuple(want.conf_int), 1e-14, hw)
    assert _close(tuple(got.critical_values), tuple(want.critical_values), 3e-13)
    assert tuple(got.nobs) == tuple(want.nobs)
    if abs(want.pvalue - want.alpha) > 1e-12:
        assert got.decision == want.decision and got.reject == want.reject


def assert_var_close(got, want):
    """One pixel's variance-test TestResult (block path) against the single call's."""
    assert got.method == want.method and got.alternative == want.alternative
    assert_pvalues_close(got.pvalue, want.pvalue)
    assert _close(got.statistic, want.statistic, 1e-14)
    assert tuple(np.atleast_1d(got.df)) == tuple(np.atleast_1d(want.df))
    assert _close(tuple(got.conf_int), tuple(want.conf_int), 1e-14)
    assert tuple(got.critical_values) == tuple(want.critical_values)
    assert tuple(np.atleast_1d(got.nobs)) == tuple(np.atleast_1d(want.nobs))
    if abs(want.pvalue - want.alpha) > 1e-12:
        assert got.decision == want.decision and got.reject == want.reject
