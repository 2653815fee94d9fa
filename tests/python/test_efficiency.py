"""mcstat.efficiency_test and mcstat.compare_efficiency: the numbers
against a NumPy/SciPy oracle of the delta method, accumulators and arrays
alike, the R-style block, errors naming their argument, the timing driver."""
import math

import numpy as np
import pytest
from scipy import stats

import mcstat


def oracle(x, y, tx, ty, ratio=1.0, alternative="two-sided", alpha=0.05):
    """The efficiency test from the data, in NumPy and SciPy."""

    def var_part(v):
        v = np.asarray(v, float)
        n = v.size
        d = v - v.mean()
        m2, m4 = np.sum(d**2), np.sum(d**4)
        beta2 = max(n * m4 / m2**2, 1.0)
        V = (beta2 - (n - 3) / (n - 1)) / n
        return math.log(m2 / (n - 1)), V, min(2 / V, n - 1)

    def time_part(t):
        t = np.asarray(t, float)
        k = t.size
        return math.log(t.mean()), t.var(ddof=1) / (k * t.mean() ** 2), k - 1

    parts = [var_part(x), var_part(y), time_part(tx), time_part(ty)]
    lrho = parts[1][0] - parts[0][0] + parts[3][0] - parts[2][0]
    V = sum(p[1] for p in parts)
    df = V**2 / sum(p[1] ** 2 / p[2] for p in parts if p[1] > 0)
    se = math.sqrt(V)
    t = (lrho - math.log(ratio)) / se
    if alternative == "two-sided":
        p = 2 * stats.t.sf(abs(t), df)
        c = stats.t.isf(alpha / 2, df)
        ci = (math.exp(lrho - c * se), math.exp(lrho + c * se))
    elif alternative == "greater":
        p = stats.t.sf(t, df)
        ci = (math.exp(lrho - stats.t.isf(alpha, df) * se), math.inf)
    else:
        p = stats.t.cdf(t, df)
        ci = (0.0, math.exp(lrho + stats.t.isf(alpha, df) * se))
    return dict(statistic=t, df=df, pvalue=p, conf_int=ci, estimate=math.exp(lrho), std_error=se,
                var_ratio=math.exp(parts[1][0] - parts[0][0]), time_ratio=math.exp(parts[3][0] - parts[2][0]))


def data(seed=7, n=400):
    rng = np.random.default_rng(seed)
    x = rng.exponential(1.0, n)
    y = rng.exponential(1.0, n + 37) * (rng.random(n + 37) < 0.3)  # mostly zeros, heavier tailed
    tx = rng.lognormal(np.log(2e-7), 0.2, 15)
    ty = rng.lognormal(np.log(1e-7), 0.2, 11)
    return x, y, tx, ty


@pytest.mark.parametrize("alternative", ["two-sided", "less", "greater"])
@pytest.mark.parametrize("ratio", [1.0, 0.5, 3.0])
def test_against_numpy_scipy(alternative, ratio):
    x, y, tx, ty = data()
    r = mcstat.efficiency_test(x, y, tx, ty, ratio=ratio, alternative=alternative, alpha=0.1)
    want = oracle(x, y, tx, ty, ratio, alternative, 0.1)
    for f in ("statistic", "df", "pvalue", "estimate", "std_error"):
        assert getattr(r, f) == pytest.approx(want[f], rel=1e-9), f
    assert r.conf_int == pytest.approx(want["conf_int"], rel=1e-9)
    assert r.efficiency["var_ratio"] == pytest.approx(want["var_ratio"], rel=1e-12)
    assert r.efficiency["time_ratio"] == pytest.approx(want["time_ratio"], rel=1e-12)
    assert (r.efficiency["batches_x"], r.efficiency["batches_y"]) == (15, 11)
    assert r.nobs == (400, 437)
    assert r.null_value == ratio and r.alternative == alternative and r.alpha == 0.1
    assert r.pvalue_method == "asymptotic"
    assert r.reject == (want["pvalue"] <= 0.1)
    assert r.decision == ("equal" if not r.reject else "greater" if want["statistic"] > 0 else "less")
    assert r.confidence_interval(0.9) == pytest.approx(r.conf_int, rel=1e-12)


def test_moments_and_arrays_agree():
    x, y, tx, ty = data(11)
    a = mcstat.efficiency_test(x, y, tx, ty)
    b = mcstat.efficiency_test(mcstat.Moments(x), mcstat.Moments(y), mcstat.Moments(tx), ty)
    assert a._raw() == b._raw()
    # lists work too
    c = mcstat.efficiency_test(list(x), list(y), list(tx), list(ty))
    assert c.statistic == a.statistic


def test_block_and_repr():
    x, y, tx, ty = data(3)
    r = mcstat.efficiency_test(x, y, tx, ty)
    s = str(r)
    assert "\tEfficiency ratio test (delta method)\n" in s
    assert "alternative hypothesis: true ratio of efficiencies is not equal to 1\n" in s
    assert "timed batches: 15 of x, 11 of y" in s
    assert "ratio of efficiencies" in s and "decision at alpha = 0.05:" in s
    assert "data:  new and old" in r.format("new", "old")
    assert r.method == "Efficiency ratio test (delta method)"
    assert "Efficiency ratio test" in repr(r)
    assert mcstat.t_test(x, y).efficiency is None


def test_x_more_efficient_is_greater():
    rng = np.random.default_rng(5)
    x = rng.normal(0, 1, 5000)
    y = rng.normal(0, 3, 5000)  # nine times the variance
    t = rng.lognormal(0, 0.05, 20)
    r = mcstat.efficiency_test(x, y, t, t * 1.0)
    assert r.decision == "greater" and r.conf_int[0] > 5 and r.conf_int[1] < 15
    r = mcstat.efficiency_test(y, x, t, t)
    assert r.decision == "less"


def test_exact_costs_are_accepted():
    x, y, _, _ = data(4)
    r = mcstat.efficiency_test(x, y, [2.0, 2.0], [1.0, 1.0, 1.0])
    assert r.efficiency["se_log_time_x"] == 0 and r.efficiency["time_ratio"] == 0.5


def test_errors_name_their_argument():
    x, y, tx, ty = data(9)
    with pytest.raises(mcstat.TooFewObservationsError, match="time_y has 1 timed batch"):
        mcstat.efficiency_test(x, y, tx, [1.0])
    with pytest.raises(mcstat.TooFewObservationsError, match="x has 1 value"):
        mcstat.efficiency_test([1.0], y, tx, ty)
    with pytest.raises(mcstat.InvalidArgumentError, match="time_x contains a negative time"):
        mcstat.efficiency_test(x, y, [1.0, -2.0, 3.0], ty)
    with pytest.raises(mcstat.DegenerateDataError, match="y is constant"):
        mcstat.efficiency_test(x, [2.0] * 10, tx, ty)
    with pytest.raises(mcstat.DegenerateDataError, match="every batch of time_x was timed as 0"):
        mcstat.efficiency_test(x, y, [0.0, 0.0], ty)
    with pytest.raises(mcstat.InvalidArgumentError, match="ratio must be finite and > 0"):
        mcstat.efficiency_test(x, y, tx, ty, ratio=0)
    with pytest.raises(mcstat.InvalidArgumentError, match="ratio"):
        mcstat.efficiency_test(x, y, tx, ty, ratio=math.inf)
    with pytest.raises(mcstat.InvalidArgumentError, match="alpha must be in"):
        mcstat.efficiency_test(x, y, tx, ty, alpha=1.5)
    with pytest.raises(mcstat.InvalidArgumentError, match="sideways"):
        mcstat.efficiency_test(x, y, tx, ty, alternative="sideways")
    with pytest.raises(mcstat.NonFiniteError, match="time_y"):
        mcstat.efficiency_test(x, y, tx, [1.0, math.nan])
    with pytest.raises(mcstat.InvalidArgumentError, match="y must be 1-D"):
        mcstat.efficiency_test(x, np.ones((3, 3)), tx, ty)
    with pytest.raises(TypeError, match="time_x must be array-like"):
        mcstat.efficiency_test(x, y, None, ty)
    with pytest.raises(TypeError, match="ratio"):
        mcstat.efficiency_test(x, y, tx, ty, ratio="one")
    with pytest.raises(TypeError, match="not an mcstat.MomentsArray"):
        mcstat.efficiency_test(mcstat.MomentsArray(3), y, tx, ty)


def test_pickle_and_one_sided_intervals():
    import pickle

    x, y, tx, ty = data(13)
    r = mcstat.efficiency_test(x, y, tx, ty, alternative="less", alpha=0.2)
    assert pickle.loads(pickle.dumps(r))._raw() == r._raw()
    assert r.conf_int[0] == 0.0 and r.confidence_interval(0.8) == pytest.approx(r.conf_int, rel=1e-12)
    lo, hi = r.confidence_interval(0.95)
    assert lo == 0.0 and hi > r.conf_int[1]
    r = mcstat.efficiency_test(x, y, tx, ty, alternative="greater")
    assert r.conf_int[1] == math.inf and 0 < r.conf_int[0] < r.estimate


def test_compare_efficiency_times_interleaved_batches():
    rng = np.random.default_rng(1)
    calls = []

    def draw_x(m):
        calls.append("x")
        return rng.normal(0, 1, m)

    def draw_y(m):
        calls.append("y")
        return rng.normal(0, 2, m)

    r = mcstat.compare_efficiency(draw_x, draw_y, n=1000, batches=10, warmup=False)
    assert calls == ["x", "y", "y", "x"] * 5  # alternating, each first half the time
    calls.clear()
    mcstat.compare_efficiency(draw_x, draw_y, n=1000, batches=10)
    assert calls == ["x", "y"] + ["x", "y", "y", "x"] * 5  # a warm-up call each, untimed
    assert r.nobs == (1000, 1000)
    assert (r.efficiency["batches_x"], r.efficiency["batches_y"]) == (10, 10)
    # the variance factor does not depend on the clock: s_y^2 / s_x^2 near 4
    assert 2.5 < r.efficiency["var_ratio"] < 6.5
    assert "Efficiency ratio test" in str(r)
    # n not a multiple of batches: the remainder is left out
    r = mcstat.compare_efficiency(draw_x, draw_y, n=1005, batches=10, alternative="greater", alpha=0.01)
    assert r.nobs == (1000, 1000) and r.alternative == "greater" and r.alpha == 0.01


def test_compare_efficiency_errors():
    ok = lambda m: np.arange(m, dtype=float)  # noqa: E731
    with pytest.raises(mcstat.InvalidArgumentError, match=r"draw_y\(10\) returned 9 values"):
        mcstat.compare_efficiency(ok, lambda m: np.zeros(m - 1), n=100, batches=10)
    with pytest.raises(mcstat.InvalidArgumentError, match="batches must be at least 2"):
        mcstat.compare_efficiency(ok, ok, n=100, batches=1)
    with pytest.raises(mcstat.InvalidArgumentError, match="n must be at least 40"):
        mcstat.compare_efficiency(ok, ok, n=39, batches=20)
    with pytest.raises(TypeError, match="draw_x must be callable"):
        mcstat.compare_efficiency(None, ok, n=100)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="batches must be an int"):
        mcstat.compare_efficiency(ok, ok, n=100, batches=2.5)  # type: ignore[arg-type]
