# mcstat.chisq_gof against R's chisq.test (tests/data/chisq_ref.json,
# written by tools/refgen/make_chisq_ref.R) and SciPy's chisquare.
import json
import os

import numpy as np
import pytest
from scipy import stats

import mcstat
from conftest import HERE, rel_err

with open(os.path.join(HERE, "..", "data", "chisq_ref.json")) as f:
    CASES = json.load(f)


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_against_r(case):
    pooling = dict(min_expected=case["min_expected"]) if case["pool"] else {}
    r = mcstat.chisq_gof(case["x"], case["p"], expected_kind="counts" if case["counts"] else "probabilities",
                         pool=bool(case["pool"]), n_estimated=case["n_estimated"], **pooling)
    assert rel_err(r.statistic, case["statistic"]) < 1e-12
    assert r.df == case["df"]
    assert r.cells == case["cells"]
    if case["pvalue"] == 0.0:  # R underflowed
        assert r.pvalue < 1e-300
    else:
        assert rel_err(r.pvalue, case["pvalue"]) < 1e-11
    assert r.reject == (r.pvalue <= 0.05)
    assert r.decision == ("greater" if r.reject else "equal")
    assert r.nobs == round(sum(case["x"]))
    assert r.method == "Chi-squared test for given probabilities"
    assert r.pvalue_method == "asymptotic"


def test_against_scipy(rng):
    for k in (2, 5, 30, 300):
        for ddof in ((0,) if k == 2 else (0, 1)):
            p = rng.gamma(2.0, size=k)
            p /= p.sum()
            x = rng.multinomial(50 * k, p).astype(float)
            r = mcstat.chisq_gof(x, p, pool=False, n_estimated=ddof)
            s = stats.chisquare(x, x.sum() * p, ddof=ddof)
            assert rel_err(r.statistic, s.statistic) < 1e-12
            assert rel_err(r.pvalue, s.pvalue) < 1e-10
            assert r.critical_values[0] == -np.inf
            assert rel_err(r.critical_values[1], stats.chi2.isf(0.05, k - 1 - ddof)) < 1e-10


def test_deep_tail_against_scipy():
    # p-values far below R's print threshold keep their relative accuracy
    x = np.array([700.0, 100, 100, 100, 100, 100, 100, 100, 100, 600])
    p = np.full(10, 0.1)
    r = mcstat.chisq_gof(x, p)
    s = stats.chisquare(x, x.sum() * p)
    assert s.pvalue < 1e-200
    assert rel_err(r.pvalue, s.pvalue) < 1e-10


def test_pooling_rule():
    # cells 0-2 pool (expected 0.1+1+0.9 = 2 < 5 ... then with cell 3: 32), the
    # rest stand alone
    x = np.array([0.0, 1, 0, 30, 40, 29])
    p = np.array([0.001, 0.01, 0.009, 0.3, 0.4, 0.28])
    r = mcstat.chisq_gof(x, p)
    o = np.array([31.0, 40, 29])
    e = 100 * np.array([0.32, 0.4, 0.28])
    assert r.cells == 3
    assert rel_err(r.statistic, ((o - e) ** 2 / e).sum()) < 1e-14
    assert r.df == 2
    assert "3 after pooling" in str(r)
    # the short tail joins the group before it
    r2 = mcstat.chisq_gof(x[::-1], p[::-1])
    o2 = np.array([29.0, 40, 31])
    e2 = 100 * np.array([0.28, 0.4, 0.32])
    assert rel_err(r2.statistic, ((o2 - e2) ** 2 / e2).sum()) < 1e-14


def test_format_matches_r():
    r = mcstat.chisq_gof([22, 21, 22, 27, 22, 36], np.full(6, 1 / 6))
    # R 4.2.2: print(chisq.test(c(22, 21, 22, 27, 22, 36), p = rep(1/6, 6)))
    assert str(r).startswith("\n\tChi-squared test for given probabilities\n\ndata:  x\n"
                             "X-squared = 6.72, df = 5, p-value = 0.2423\n")
    assert r.format("counts").splitlines()[3] == "data:  counts"


def test_calibration(rng):
    # rejection rate under H0 within binomial bounds (4 sd) of alpha
    p = rng.gamma(1.0, size=25)
    p /= p.sum()
    runs = 2000
    rej = sum(mcstat.chisq_gof(rng.multinomial(400, p), p).reject for _ in range(runs))
    sd = np.sqrt(0.05 * 0.95 / runs)
    assert abs(rej / runs - 0.05) < 4 * sd


@pytest.mark.parametrize("kwargs, exc", [
    (dict(observed=[1, 2, 3], expected=[0.5, 0.5]), mcstat.InvalidArgumentError),
    (dict(observed=[1, np.nan, 3], expected=[0.2, 0.3, 0.5]), mcstat.NonFiniteError),
    (dict(observed=[1, 2, 3], expected=[0.2, np.inf, 0.5]), mcstat.NonFiniteError),
    (dict(observed=[1, -2, 3], expected=[0.2, 0.3, 0.5]), mcstat.InvalidArgumentError),
    (dict(observed=[1, 2, 3], expected=[0.2, 0.3, 0.6]), mcstat.InvalidArgumentError),
    (dict(observed=[1, 2, 3], expected=[0.5, 0.0, 0.5], pool=False), mcstat.InvalidArgumentError),
    (dict(observed=[4], expected=[1.0]), mcstat.TooFewObservationsError),
    (dict(observed=[], expected=[]), mcstat.TooFewObservationsError),
    (dict(observed=[0, 0, 0], expected=[0.2, 0.3, 0.5]), mcstat.TooFewObservationsError),
    (dict(observed=[3, 4, 5], expected=[0.2, 0.3, 0.5], n_estimated=1), mcstat.TooFewObservationsError),
    (dict(observed=[3, 4, 5], expected=[0.2, 0.3, 0.5], alpha=1.0), mcstat.InvalidArgumentError),
    (dict(observed=[3, 4, 5], expected=[0.2, 0.3, 0.5], alpha=0.0), mcstat.InvalidArgumentError),
    (dict(observed=[3, 4, 5], expected=[0.2, 0.3, 0.5], expected_kind="odds"), mcstat.InvalidArgumentError),
    (dict(observed=[3, 4, 5], expected=[0.2, 0.3, 0.5], min_expected=-1), mcstat.InvalidArgumentError),
    (dict(observed=[3, 4, 5], expected=[0.2, 0.3, 0.5], n_estimated=-1), mcstat.InvalidArgumentError),
    (dict(observed=[[3, 4], [5, 6]], expected=[[0.25, 0.25], [0.25, 0.25]]), mcstat.InvalidArgumentError),
])
def test_bad_input(kwargs, exc):
    with pytest.raises(exc):
        mcstat.chisq_gof(**kwargs)
    assert issubclass(exc, ValueError)


def test_rescale_and_counts():
    x = np.array([10.0, 20, 30])
    r1 = mcstat.chisq_gof(x, [2.0, 3.0, 5.0], rescale=True, pool=False)
    r2 = mcstat.chisq_gof(x, [0.2, 0.3, 0.5], pool=False)
    r3 = mcstat.chisq_gof(x, [12.0, 18.0, 30.0], expected_kind="counts", pool=False)
    assert r1.statistic == pytest.approx(r2.statistic, rel=1e-14)
    assert r3.statistic == pytest.approx(r2.statistic, rel=1e-14)


def test_scipy_expected_counts():
    # SciPy's chisquare(f_obs, f_exp) takes expected counts summing to the
    # observed total; R's chisq.test(x, p=) probabilities.  Both are accepted.
    from scipy import stats

    x = np.array([18.0, 22.0, 35.0, 25.0])
    f_exp = np.array([25.0, 25.0, 25.0, 25.0])
    want = stats.chisquare(x, f_exp)
    r = mcstat.chisq_gof(x, f_exp, pool=False)
    assert r.statistic == pytest.approx(want.statistic, rel=1e-13)
    assert r.pvalue == pytest.approx(want.pvalue, rel=1e-12)
    rp = mcstat.chisq_gof(x, f_exp / 100.0, pool=False)
    assert rp.statistic == pytest.approx(r.statistic, rel=1e-14)
    # explicit kinds stay strict
    with pytest.raises(mcstat.InvalidArgumentError, match="expected_kind='counts'"):
        mcstat.chisq_gof(x, f_exp, expected_kind="probabilities")


def test_mismatched_sums_say_what_is_wrong():
    with pytest.raises(mcstat.InvalidArgumentError,
                       match=r"^expected sums to 6\.0 and observed to 60\.0: .*rescale=True") as e:
        mcstat.chisq_gof([10, 20, 30], [1, 2, 3])
    assert "NULL" not in str(e.value)
    with pytest.raises(mcstat.InvalidArgumentError, match=r"observed counts must be >= 0, got -1\.0 at index 1"):
        mcstat.chisq_gof([10, -1, 30], [0.2, 0.3, 0.5])
    with pytest.raises(mcstat.InvalidArgumentError, match=r"expected is 0 at index 1: without pooling"):
        mcstat.chisq_gof([10, 1, 30], [0.5, 0.0, 0.5], pool=False)
    r = mcstat.chisq_gof([10, 20, 30], [1, 2, 3], rescale=True)
    assert r.statistic == pytest.approx(0.0, abs=1e-12)


def test_min_expected_without_pooling_raises():
    with pytest.raises(mcstat.InvalidArgumentError, match="^min_expected applies to pooling"):
        mcstat.chisq_gof([10, 20, 30], [0.2, 0.3, 0.5], pool=False, min_expected=1.0)
    a = mcstat.chisq_gof([10, 20, 30], [0.2, 0.3, 0.5], min_expected=1.0)
    b = mcstat.chisq_gof([10, 20, 30], [0.2, 0.3, 0.5], pool=False)
    assert a.statistic == pytest.approx(b.statistic)


def test_expected_left_out_is_uniform_as_scipy():
    x = np.array([16.0, 18.0, 16.0, 14.0, 12.0, 12.0])
    want = stats.chisquare(x)
    r = mcstat.chisq_gof(x, pool=False)
    assert r.statistic == pytest.approx(want.statistic, rel=1e-13)
    assert r.pvalue == pytest.approx(want.pvalue, rel=1e-12)
    with pytest.raises(mcstat.InvalidArgumentError, match="expected_kind='counts' needs expected counts"):
        mcstat.chisq_gof(x, expected_kind="counts")
