"""t_test against SciPy, the 50-digit references and its own contract."""
import numpy as np
import pytest
import scipy
import scipy.stats as st

import mcstat
from conftest import rel_err
from refdata import (CASES, STIFF_DOMAIN, TOL_CONF_INT, TOL_CRITICAL, TOL_DF, TOL_ESTIMATE, TOL_STATISTIC,
                     accuracy_bound, values)

ALTS = ["two-sided", "less", "greater"]
SCIPY_CI = tuple(int(v) for v in scipy.__version__.split(".")[:2]) >= (1, 11)


def close(got, want, tol=1e-12):
    assert rel_err(got, want) <= tol, (got, want, rel_err(got, want))


@pytest.mark.parametrize("alternative", ALTS)
@pytest.mark.parametrize("n", [2, 3, 7, 50, 333, 4096])
def test_one_sample_agrees_with_scipy(rng, n, alternative):
    for rep in range(3):
        x = rng.normal(rng.uniform(-1, 1), rng.uniform(0.1, 3), size=n)
        mu = float(rng.uniform(-0.5, 0.5))
        alpha = [0.05, 0.01, 0.2][rep]
        r = mcstat.t_test(x, mu=mu, alternative=alternative, alpha=alpha)
        s = st.ttest_1samp(x, mu, alternative=alternative)
        close(r.statistic, s.statistic)
        close(r.pvalue, s.pvalue)
        close(r.df, n - 1)
        assert r.estimate == pytest.approx(x.mean(), rel=1e-14)
        if SCIPY_CI:
            ci = s.confidence_interval(confidence_level=1 - alpha)
            close(r.conf_int[0], ci.low)
            close(r.conf_int[1], ci.high)
        assert r.reject == (r.pvalue <= alpha)
        assert r.nobs == n


@pytest.mark.parametrize("alternative", ALTS)
@pytest.mark.parametrize("nx,ny", [(2, 2), (2, 40), (5, 9), (50, 50), (200, 31), (3000, 2500)])
def test_welch_agrees_with_scipy(rng, nx, ny, alternative):
    for rep in range(3):
        x = rng.normal(rng.uniform(-1, 1), rng.uniform(0.1, 3), size=nx)
        y = rng.normal(rng.uniform(-1, 1), rng.uniform(0.1, 3), size=ny)
        alpha = [0.05, 0.01, 0.2][rep]
        r = mcstat.t_test(x, y, alternative=alternative, alpha=alpha)
        s = st.ttest_ind(x, y, equal_var=False, alternative=alternative)
        close(r.statistic, s.statistic)
        close(r.pvalue, s.pvalue)
        vx, vy = x.var(ddof=1) / nx, y.var(ddof=1) / ny
        close(r.df, (vx + vy) ** 2 / (vx ** 2 / (nx - 1) + vy ** 2 / (ny - 1)))
        assert r.estimate == pytest.approx((x.mean(), y.mean()), rel=1e-14)
        if SCIPY_CI:
            ci = s.confidence_interval(confidence_level=1 - alpha)
            close(r.conf_int[0], ci.low)
            close(r.conf_int[1], ci.high)
        assert r.nobs == (nx, ny)


def test_welch_with_mu_matches_shifted_data(rng):
    x, y = rng.normal(size=30), rng.normal(size=40)
    r = mcstat.t_test(x, y, mu=0.7)
    s = st.ttest_ind(x - 0.7, y, equal_var=False)
    close(r.statistic, s.statistic, 1e-11)
    close(r.pvalue, s.pvalue, 1e-11)
    assert r.null_value == 0.7


def test_critical_values_and_decision(rng):
    x = rng.normal(0.5, 1, size=40)
    r = mcstat.t_test(x, alpha=0.05)
    c = st.t.ppf(0.975, 39)
    close(r.critical_values[1], c, 1e-12)
    assert r.critical_values[0] == -r.critical_values[1]
    assert r.reject == (abs(r.statistic) > c)
    assert r.decision == ("greater" if r.reject else "equal")
    less = mcstat.t_test(x, alternative="less")
    assert less.critical_values[1] == np.inf and less.conf_int[0] == -np.inf
    greater = mcstat.t_test(x, alternative="greater")
    assert greater.critical_values[0] == -np.inf and greater.conf_int[1] == np.inf
    assert r.pvalue_se == 0.0
    assert r.alternative == "two-sided" and r.method == "One Sample t-test"
    close(r.std_error, x.std(ddof=1) / np.sqrt(40), 1e-13)


def test_three_way_decision(rng):
    x = rng.normal(0, 1, size=100)
    assert mcstat.t_test(x - 1, x).decision == "less"
    assert mcstat.t_test(x + 1, x).decision == "greater"
    assert mcstat.t_test(x + 1e-3, x).decision == "equal"


def test_intervals_false_skips_only_intervals(rng):
    x, y = rng.normal(size=30), rng.normal(size=20)
    full = mcstat.t_test(x, y)
    cheap = mcstat.t_test(x, y, intervals=False)
    assert (cheap.statistic, cheap.pvalue, cheap.df, cheap.decision) == (full.statistic, full.pvalue, full.df, full.decision)
    assert all(np.isnan(cheap.conf_int)) and all(np.isnan(cheap.critical_values))


def test_nan_policy_omit(rng):
    x = rng.normal(size=30)
    xn = x.copy()
    xn[[3, 17]] = np.nan
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.t_test(xn)
    r = mcstat.t_test(xn, nan_policy="omit")
    s = mcstat.t_test(x[~np.isnan(xn)])
    assert r._raw() == s._raw() and r.nobs == 28
    xi = x.copy()
    xi[0] = np.inf
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.t_test(xi, nan_policy="omit")


def test_moments_in_place_of_arrays(rng):
    x, y = rng.normal(size=300), rng.normal(0.1, 2, size=200)
    mx = mcstat.Moments(x)
    my = mcstat.Moments()
    my.push(y[:77]).push(y[77:])
    a = mcstat.t_test(x, y)
    for args in [(mx, my), (mx, y), (x, my)]:
        b = mcstat.t_test(*args)
        close(b.statistic, a.statistic, 1e-13)
        close(b.pvalue, a.pvalue, 1e-13)
    assert mcstat.t_test(mx, mu=0.2)._raw() == mcstat.t_test(x, mu=0.2)._raw()


def test_input_types_give_the_same_result(rng):
    x = rng.normal(size=64)
    ref = mcstat.t_test(x)._raw()
    assert mcstat.t_test(list(x))._raw() == ref
    assert mcstat.t_test(tuple(x))._raw() == ref
    strided = np.empty(128)
    strided[::2] = x
    assert mcstat.t_test(strided[::2])._raw() == ref
    ints = np.arange(20)
    assert mcstat.t_test(ints)._raw() == mcstat.t_test(ints.astype(float))._raw()
    assert mcstat.t_test(x.astype(np.float32)).statistic == pytest.approx(mcstat.t_test(x.astype(np.float32).astype(float)).statistic, rel=0)
    assert mcstat.t_test(x=x)._raw() == ref


@pytest.mark.parametrize("case", [c for c in CASES if c["kind"] in ("T_1", "T_2")],
                         ids=lambda c: f'{c["kind"]}-{c["x"]}-{c["y"]}')
def test_stiff_references(case):
    """The 50-digit references of the C tests (tests/data/ref_data.h) through Python."""
    x = values(case["x"])
    alt = ALTS[case["alternative"]]
    if case["kind"] == "T_1":
        r = mcstat.t_test(x, mu=case["null_value"], alternative=alt, alpha=case["alpha"])
        est = (r.estimate,)
    else:
        r = mcstat.t_test(x, values(case["y"]), mu=case["null_value"], alternative=alt, alpha=case["alpha"])
        est = r.estimate
    # the p-value to the accuracy table's bound, the rest as test_reference.c
    p_tol = accuracy_bound("t_test_1" if case["kind"] == "T_1" else "t_test_2", STIFF_DOMAIN)
    assert rel_err(r.statistic, case["statistic"]) <= TOL_STATISTIC
    assert rel_err(r.df, case["df0"]) <= TOL_DF
    assert rel_err(r.pvalue, case["p"]) <= p_tol
    assert rel_err(r.critical_values[0], case["c0"]) <= TOL_CRITICAL
    assert rel_err(r.critical_values[1], case["c1"]) <= TOL_CRITICAL
    assert rel_err(r.conf_int[0], case["ci0"]) <= TOL_CONF_INT
    assert rel_err(r.conf_int[1], case["ci1"]) <= TOL_CONF_INT
    assert rel_err(est[0], case["e0"]) <= TOL_ESTIMATE
    if case["kind"] == "T_2":
        assert rel_err(est[1], case["e1"]) <= TOL_ESTIMATE
    assert r.reject == (case["p"] <= case["alpha"])
