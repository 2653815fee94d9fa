"""mcstat.distributions: libmcstat's t, chi-squared and F functions over
arrays, against mpmath at 50 digits (the accuracy mcstat.h promises) and
SciPy (names, broadcasting), and their errors."""
import math

import mpmath
import numpy as np
import pytest
from scipy import stats

import mcstat
from mcstat import _core
from mcstat import distributions as D

from conftest import rel_err



@pytest.fixture(autouse=True)
def fifty_digits():
    # other test modules set mpmath's precision too: 50 digits for each test here
    with mpmath.workdps(50):
        yield


def _t_tails(x, df):
    x, df = mpmath.mpf(x), mpmath.mpf(df)
    half = mpmath.betainc(df / 2, mpmath.mpf(1) / 2, 0, df / (df + x * x), regularized=True) / 2
    return (half, 1 - half) if x <= 0 else (1 - half, half)


def _chisq_tails(x, df):
    a, h = mpmath.mpf(df) / 2, mpmath.mpf(x) / 2
    if x <= 0:
        return mpmath.mpf(0), mpmath.mpf(1)
    return (mpmath.gammainc(a, 0, h, regularized=True), mpmath.gammainc(a, h, mpmath.inf, regularized=True))


def _f_tails(x, d1, d2):
    x, d1, d2 = mpmath.mpf(x), mpmath.mpf(d1), mpmath.mpf(d2)
    if x <= 0:
        return mpmath.mpf(0), mpmath.mpf(1)
    # each tail as a lower integral: betainc(..., z, 1) would cancel near z = 1
    return (mpmath.betainc(d1 / 2, d2 / 2, 0, d1 * x / (d1 * x + d2), regularized=True),
            mpmath.betainc(d2 / 2, d1 / 2, 0, d2 / (d1 * x + d2), regularized=True))


def _log_ok(lg, ref, bound):
    # mcstat.h: relative error of log p, or of p where |log p| < 1
    log_ref = mpmath.log(ref)
    if abs(log_ref) < 1:
        return rel_err(math.exp(lg), ref) <= bound
    return rel_err(lg, log_ref) <= bound


def _bound(p, near):
    # mcstat.h: the cdf's bound for p >= 1e-30, 6e-13 below
    return near if p >= 1e-30 else 6e-13


T_POINTS = [(-3.0, 2.5), (0.3, 1.0), (1.96, 30.0), (-40.0, 4.0), (12.0, 0.5), (1e5, 3.0), (2.0, 1e9), (-8.0, 200.0)]
CHISQ_POINTS = [(0.5, 1.0), (3.84, 1.0), (100.0, 10.0), (1e-6, 2.0), (2000.0, 30.0), (1.05e4, 1e4), (0.2, 0.01)]
F_POINTS = [(1.0, 2.0, 3.0), (4.1, 2.0, 10.0), (0.01, 5.0, 50.0), (300.0, 3.0, 40.0), (1.1, 300.0, 500.0),
            (2.0, 0.5, 7.0)]


@pytest.mark.parametrize("x,df", T_POINTS)
def test_t_against_mpmath(x, df):
    lo, up = _t_tails(x, df)
    for upper, ref in ((False, lo), (True, up)):
        got = D.t_cdf(x, df, upper=upper)
        assert isinstance(got, float)
        assert rel_err(got, ref) <= _bound(float(ref), 3e-14), (x, df, upper, got, ref)
        lg = D.t_logcdf(x, df, upper=upper)
        # 8e-16 as promised in the far tails; near the centre only as good
        # as the log of the cdf (test_t_logcdf_promise_near_the_centre)
        assert _log_ok(lg, ref, 8e-16 if abs(mpmath.log(ref)) >= 20 else 5e-15), (x, df, upper, lg)


@pytest.mark.parametrize("x,df", CHISQ_POINTS)
def test_chisq_against_mpmath(x, df):
    lo, up = _chisq_tails(x, df)
    for upper, ref in ((False, lo), (True, up)):
        got = D.chisq_cdf(x, df, upper=upper)
        assert rel_err(got, ref) <= _bound(float(ref), 1.5e-13), (x, df, upper, got, ref)
        lg = D.chisq_logcdf(x, df, upper=upper)
        assert _log_ok(lg, ref, 5e-15), (x, df, upper, lg)


@pytest.mark.parametrize("x,d1,d2", F_POINTS)
def test_f_against_mpmath(x, d1, d2):
    lo, up = _f_tails(x, d1, d2)
    for upper, ref in ((False, lo), (True, up)):
        got = D.f_cdf(x, d1, d2, upper=upper)
        assert rel_err(got, ref) <= _bound(float(ref), 4e-14), (x, d1, d2, upper, got, ref)
        lg = D.f_logcdf(x, d1, d2, upper=upper)
        assert _log_ok(lg, ref, 8e-15), (x, d1, d2, upper, lg)


@pytest.mark.parametrize("df", [0.5, 1.0, 3.0, 10.0, 30.0, 300.0])
def test_log_cdf_near_the_centre_carries_the_cdf_error(df):
    # mcstat.h: where p >= 1e-30 the log cdf's absolute error is within the
    # cdf's relative bound (3e-14 for t; the relative error of log p is
    # |log p| times smaller, not the 8e-16 of the far tails: 3.6e-15 was
    # measured at x = 2.35, df = 10)
    for x in np.linspace(-6.0, 6.0, 49):
        for upper in (False, True):
            ref = _t_tails(x, df)[1 if upper else 0]
            lg = D.t_logcdf(float(x), df, upper=upper)
            assert abs(lg - mpmath.log(ref)) <= 3e-14, (x, df, upper, lg)
            x2 = float(D.chisq_quantile(float(ref), df, upper=upper))
            ref2 = _chisq_tails(x2, df)[1 if upper else 0]
            assert abs(D.chisq_logcdf(x2, df, upper=upper) - mpmath.log(ref2)) <= 1.5e-13, (x2, df, upper)


def test_log_stays_finite_where_the_probability_underflows():
    # P[T > 1e200] with df = 3 is about 1e-600: 0 as a double, finite as a log
    assert D.t_cdf(1e200, 3.0, upper=True) == 0.0
    lg = D.t_logcdf(1e200, 3.0, upper=True)
    ref = mpmath.log(_t_tails(1e200, 3.0)[1])
    assert math.isfinite(lg) and rel_err(lg, ref) <= 8e-16
    lg = D.chisq_logcdf(5000.0, 2.0, upper=True)  # exp(-2500)
    assert rel_err(lg, -2500.0) <= 5e-15


def test_the_small_tail_is_not_one_minus_the_large_one():
    # 1 - P would give 0 here; SciPy's sf agrees with mpmath
    ref = _chisq_tails(400.0, 3.0)[1]
    got = D.chisq_cdf(400.0, 3.0, upper=True)
    assert got > 0 and rel_err(got, ref) <= 6e-13


def _exact_quantile(tails, side, p, x, *df):
    # the root near x at 50 digits (secant steps from libmcstat's x)
    p = mpmath.mpf(p)
    return mpmath.findroot(lambda z: tails(z, *df)[side] / p - 1, (mpmath.mpf(x), mpmath.mpf(x) * (1 + 1e-9)),
                           verify=False)


@pytest.mark.parametrize("p", [1e-200, 1e-40, 1e-5, 0.025, 0.5, 0.975, 1 - 1e-12])
def test_quantiles_against_mpmath(p):
    # mcstat.h: quantiles to 3e-13 relative
    for df in (1.5, 4.0, 1e4):
        for upper in (False, True):
            side = 1 if upper else 0
            x = D.t_quantile(p, df, upper=upper)
            assert rel_err(x, _exact_quantile(_t_tails, side, p, x, df)) <= 3e-13, (p, df, upper, x)
            x = D.chisq_quantile(p, df, upper=upper)
            assert rel_err(x, _exact_quantile(_chisq_tails, side, p, x, df)) <= 3e-13, (p, df, upper, x)
    for upper in (False, True):
        x = D.f_quantile(p, 3.0, 12.0, upper=upper)
        assert rel_err(x, _exact_quantile(_f_tails, 1 if upper else 0, p, x, 3.0, 12.0)) <= 3e-13, (p, upper, x)
    assert rel_err(D.f_quantile(0.95, 2.0, 10.0), stats.f.ppf(0.95, 2.0, 10.0)) <= 1e-12


def test_quantile_endpoints():
    assert D.t_quantile(0.0, 3.0) == -math.inf and D.t_quantile(1.0, 3.0) == math.inf
    assert D.t_quantile(0.5, 3.0) == 0.0
    assert D.chisq_quantile(0.0, 3.0) == 0.0 and D.chisq_quantile(0.0, 3.0, upper=True) == math.inf


def test_scipy_names_and_broadcasting():
    x = np.linspace(-4, 4, 9)
    df = np.array([[1.5], [7.0], [60.0]])
    np.testing.assert_allclose(D.t_cdf(x, df), stats.t.cdf(x, df), rtol=1e-12, atol=0)
    np.testing.assert_allclose(D.t_cdf(x, df, upper=True), stats.t.sf(x, df), rtol=1e-12, atol=0)
    np.testing.assert_allclose(D.t_logcdf(x, df), stats.t.logcdf(x, df), rtol=1e-12, atol=0)
    q = np.array([0.01, 0.5, 0.99])
    np.testing.assert_allclose(D.t_quantile(q, df), stats.t.ppf(q, df), rtol=1e-11, atol=1e-15)
    np.testing.assert_allclose(D.t_quantile(q, df, upper=True), stats.t.isf(q, df), rtol=1e-11, atol=1e-15)
    xs = np.array([0.1, 1.0, 10.0])
    np.testing.assert_allclose(D.chisq_cdf(xs, df), stats.chi2.cdf(xs, df), rtol=1e-12)
    np.testing.assert_allclose(D.chisq_logcdf(xs, df, upper=True), stats.chi2.logsf(xs, df), rtol=1e-12)
    np.testing.assert_allclose(D.chisq_quantile(q, df), stats.chi2.ppf(q, df), rtol=1e-11)
    d2 = np.array([3.0, 30.0])[:, None, None]
    out = D.f_cdf(xs, df, d2)
    assert out.shape == (2, 3, 3) and out.dtype == np.float64
    np.testing.assert_allclose(out, stats.f.cdf(xs, df, d2), rtol=1e-12)
    np.testing.assert_allclose(D.f_logcdf(xs, df, d2, upper=True), stats.f.logsf(xs, df, d2), rtol=1e-12)
    np.testing.assert_allclose(D.f_quantile(q, df, d2, upper=True), stats.f.isf(q, df, d2), rtol=1e-11)


def test_layouts_and_dtypes():
    # strided, reversed, integer and 0-d inputs are read as NumPy reads them
    x = np.arange(24.0).reshape(4, 6)[:, ::-2] - 10
    df = np.arange(1, 5, dtype=np.int32)[:, None]
    got = D.t_cdf(x, df)
    want = np.array([[D.t_cdf(float(v), float(d)) for v in row] for row, d in zip(x, df[:, 0])])
    assert np.array_equal(got, want)
    assert isinstance(D.chisq_cdf(np.float64(2.0), np.array(3)), float)
    assert D.t_cdf([], 3.0).shape == (0,)
    assert D.t_cdf(np.zeros((0, 3)), [1.0, 2.0, 3.0]).shape == (0, 3)


def test_the_tests_use_these_distributions():
    r = mcstat.t_test(np.array([0.3, -1.2, 0.8, 2.0, 0.1, 0.9]), mu=0.0)
    assert r.pvalue == pytest.approx(2 * D.t_cdf(abs(r.statistic), r.df, upper=True), rel=1e-15)
    assert r.critical_values[1] == pytest.approx(D.t_quantile(0.025, r.df, upper=True), rel=1e-14)


@pytest.mark.parametrize("call,message", [
    (lambda: D.t_cdf([0.0, np.nan], 3.0), r"t_cdf: x must not be NaN at index \(1,\)"),
    (lambda: D.t_quantile(1.5, 3.0), r"t_quantile: p must be a probability in \[0, 1\], got 1\.5"),
    (lambda: D.chisq_quantile([0.5, -0.1], 3.0), r"chisq_quantile: p must be .* got -0\.1 at index \(1,\)"),
    (lambda: D.t_cdf(1.0, [[3.0, 0.0]]), r"t_cdf: df must be positive and finite, got 0\.0 at index \(0, 1\)"),
    (lambda: D.chisq_cdf(1.0, math.inf), r"chisq_cdf: df must be positive and finite, got inf"),
    (lambda: D.f_cdf(1.0, 2.0, -1.0), r"f_cdf: df2 must be positive and finite, got -1\.0"),
    (lambda: D.f_quantile(0.5, np.nan, 2.0), r"f_quantile: df1 must be positive and finite, got nan"),
    (lambda: D.t_quantile(1.5, np.linspace(1.0, 50.0, 200)),
     r"t_quantile: p must be a probability in \[0, 1\], got 1\.5 at index \(0,\)"),
    (lambda: D.t_quantile(0.025, np.r_[np.linspace(1.0, 50.0, 200), 0.0]),  # one level, many df: the table
     r"t_quantile: df must be positive and finite, got 0\.0 at index \(200,\)"),
    (lambda: D.t_cdf([1.0, 2.0], [1.0, 2.0, 3.0]),
     r"t_cdf: the arguments do not broadcast together: x has shape \(2,\), df has shape \(3,\)"),
])
def test_bad_values_name_the_argument(call, message):
    with pytest.raises(mcstat.InvalidArgumentError, match=message):
        call()


@pytest.mark.parametrize("p,upper", [(0.025, True), (1e-9, False), (0.7, True), (0.3, False)])
def test_t_quantile_at_one_level_for_many_df(p, upper):
    """One p and an array of df take mcstat_t_quantiles (a table in 1/df,
    over the threads): the single calls' values to rounding."""
    rng = np.random.default_rng(11)
    df = np.concatenate([rng.uniform(1.0, 1000.0, 3000), np.exp(rng.uniform(-6.0, 25.0, 2000))]).reshape(50, 100)
    mcstat.set_num_threads(2)
    try:
        got = D.t_quantile(p, df, upper=upper)
    finally:
        mcstat.set_num_threads(0)
    one = np.array([D.t_quantile(p, float(d), upper=upper) for d in df.ravel()]).reshape(df.shape)
    assert got.shape == df.shape
    np.testing.assert_allclose(got, one, rtol=2e-14, atol=0)
    ok = df > 0.1  # below, the quantile overflows to inf (SciPy's is finite and wrong)
    want = stats.t.isf(p, df[ok]) if upper else stats.t.ppf(p, df[ok])
    np.testing.assert_allclose(got[ok], want, rtol=1e-11)


@pytest.mark.parametrize("p", [3e-9, 1e-20, 1e-50, 1e-100])
def test_t_quantiles_table_at_extreme_levels_against_mpmath(p):
    """mcstat_t_quantiles' table at levels where the quantile grows like
    p^(-1/df) (its density follows log(1/p)): mcstat.h's 3e-13 against
    50-digit roots, df from 1 to 1000 between the table's nodes."""
    df = np.array([1.0092590872715874, 1.1642440560403042, 1.6832457875510582, 2.9, 7.25, 13.7, 101.3, 999.5])
    got = _core._t_quantiles(p, np.tile(df, 4), True)[:df.size]  # more than 16 values: the table
    for d, x in zip(df, got):
        assert rel_err(x, _exact_quantile(_t_tails, 1, p, x, d)) <= 3e-13, (p, d, x)


def test_bad_types():
    with pytest.raises(TypeError, match="x must hold real numbers"):
        D.t_cdf(1 + 2j, 3.0)
    with pytest.raises(TypeError, match="df must hold real numbers"):
        D.chisq_cdf(1.0, ["a"])
    with pytest.raises(TypeError, match="upper must be a bool"):
        D.t_cdf(1.0, 3.0, upper=1)
    with pytest.raises(TypeError, match="df2 must be a real number or an array"):
        D.f_cdf(1.0, 2.0, None)
    with pytest.raises(TypeError):
        D.t_cdf(1.0, 3.0, True)  # upper is keyword-only
