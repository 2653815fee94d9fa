"""mcstat.equivalence_test (TOST) against R (tests/data/equivalence_ref.tsv,
written by tools/refgen/make_power_ref.R), statsmodels' ttost_paired /
ttost_ind(usevar="unequal") and, at a large offset, mpmath."""
import math
import os

import mpmath
import numpy as np
import pytest

import mcstat
from conftest import ROOT, rel_err

REF = os.path.join(ROOT, "tests", "data", "equivalence_ref.tsv")


def _cases():
    out = []
    for line in open(REF):
        if line.startswith("#"):
            continue
        f = line.rstrip("\n").split("\t")
        x = [float.fromhex(v) for v in f[0].split(",")]
        y = None if f[1] == "-" else [float.fromhex(v) for v in f[1].split(",")]
        out.append((np.array(x), None if y is None else np.array(y), *map(float, f[2:6]),
                    [float(v) if v != "NA" else math.nan for v in f[6:]]))
    return out


CASES = _cases()


def _run(x, y, mu0, lower, upper, alpha):
    if y is None:
        return mcstat.equivalence_test(x, mu=mu0, margin=(lower, upper), alpha=alpha)
    return mcstat.equivalence_test(x, y, margin=(lower, upper), alpha=alpha)


@pytest.mark.parametrize("case", range(len(CASES)))
def test_against_r(case):
    x, y, mu0, lower, upper, alpha, ref = CASES[case]
    tl, pl, tu, pu, df, ci0, ci1, ex, ey = ref
    r = _run(x, y, mu0, lower, upper, alpha)
    # R forms mean(x) - mu in double; at the 1e6 offset that costs it digits
    cond = 1 + abs(np.mean(x)) / (r.std_error * min(abs(tl), abs(tu)))
    ttol = 1e-11 + 8 * 2.2e-16 * cond
    assert rel_err(r.statistics[0], tl) <= ttol
    assert rel_err(r.statistics[1], tu) <= ttol
    assert rel_err(r.pvalues[0], pl) <= 1e-9 + 30 * ttol
    assert rel_err(r.pvalues[1], pu) <= 1e-9 + 30 * ttol
    assert r.pvalue == max(r.pvalues)
    assert rel_err(r.df, df) <= 1e-12
    tol = 1e-10 * (ci1 - ci0) + 4 * 2.2e-16 * abs(np.mean(x))
    assert abs(r.conf_int[0] - ci0) <= tol and abs(r.conf_int[1] - ci1) <= tol
    assert r.bounds == pytest.approx((mu0 + lower, mu0 + upper), rel=1e-15)
    assert r.equivalent == (max(pl, pu) <= alpha)
    assert r.equivalent == (r.bounds[0] < r.conf_int[0] and r.conf_int[1] < r.bounds[1])
    assert r.decision == ("equivalent" if r.equivalent else "not equivalent")
    assert str(r).rstrip().endswith(r.decision)


def test_large_offset_against_mpmath():
    """The 1e6-offset case at 50 digits: exact mean and variance of the
    stored doubles, t, and the t distribution's tail by mpmath."""
    x, y, mu0, lower, upper, alpha, _ = next(c for c in CASES if abs(c[2]) > 1e5)
    mpmath.mp.dps = 50
    xs = [mpmath.mpf(v) for v in x]
    n = len(xs)
    m = sum(xs) / n
    s2 = sum((v - m) ** 2 for v in xs) / (n - 1)
    se = mpmath.sqrt(s2 / n)
    nu = n - 1

    def sf(t):  # P(T > t), T ~ t(nu)
        return mpmath.betainc(nu / 2, 0.5, 0, nu / (nu + t * t), regularized=True) / 2 if t > 0 else \
            1 - mpmath.betainc(nu / 2, 0.5, 0, nu / (nu + t * t), regularized=True) / 2

    tl = (m - (mpmath.mpf(mu0) + mpmath.mpf(lower))) / se
    tu = (m - (mpmath.mpf(mu0) + mpmath.mpf(upper))) / se
    r = mcstat.equivalence_test(x, mu=mu0, margin=(lower, upper), alpha=alpha)
    # the bounds are mu0 + lower rounded to double, as mcstat uses them
    tl_d = (m - mpmath.mpf(r.bounds[0])) / se
    tu_d = (m - mpmath.mpf(r.bounds[1])) / se
    assert abs(tl_d - tl) < 1e-6 and abs(tu_d - tu) < 1e-6
    assert rel_err(r.statistics[0], float(tl_d)) < 1e-13
    assert rel_err(r.statistics[1], float(tu_d)) < 1e-13
    assert rel_err(r.pvalues[0], float(sf(tl_d))) < 1e-11
    assert rel_err(r.pvalues[1], float(1 - sf(tu_d))) < 1e-11


def test_statsmodels(rng):
    sm = pytest.importorskip("statsmodels.stats.weightstats")
    for i in range(30):
        n = int(rng.integers(3, 200))
        x = rng.normal(rng.uniform(-0.3, 0.3), rng.uniform(0.2, 2), n)
        m = float(rng.uniform(0.05, 1.0))
        mu0 = float(rng.uniform(-1, 1))
        # one sample: statsmodels' paired TOST on x against the constant mu0
        p, lo, hi = sm.ttost_paired(x, np.full(n, mu0), -m, m)
        r = mcstat.equivalence_test(x, mu=mu0, margin=m)
        assert rel_err(r.pvalue, p) < 1e-9
        assert rel_err(r.statistics[0], lo[0]) < 1e-10 and rel_err(r.statistics[1], hi[0]) < 1e-10
        # Welch
        ny = int(rng.integers(3, 150))
        y = rng.normal(0, rng.uniform(0.2, 2), ny)
        lower, upper = -m, m * rng.uniform(0.5, 2)
        p, lo, hi = sm.ttost_ind(x, y, lower, upper, usevar="unequal")
        r = mcstat.equivalence_test(x, y, margin=(lower, upper))
        assert rel_err(r.pvalue, p) < 1e-9
        assert rel_err(r.pvalues[0], lo[1]) < 1e-9 and rel_err(r.pvalues[1], hi[1]) < 1e-9
        assert rel_err(r.df, lo[2]) < 1e-12


def test_moments_and_nan_policy(rng):
    x = rng.normal(1.0, 1.0, 300)
    y = rng.normal(1.05, 2.0, 200)
    a = mcstat.equivalence_test(x, y, margin=0.5)
    mx, my = mcstat.Moments(), mcstat.Moments()
    mx.push(x[:100]); mx.push(x[100:]); my.push(y)
    b = mcstat.equivalence_test(mx, my, margin=0.5)
    c = mcstat.equivalence_test(x, my, margin=0.5)
    for k in ("statistic", "pvalue", "df", "conf_int", "estimate", "statistics"):
        assert getattr(b, k) == pytest.approx(getattr(a, k), rel=1e-13)
        assert getattr(c, k) == pytest.approx(getattr(a, k), rel=1e-13)
    xn = np.concatenate([x, [np.nan]])
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.equivalence_test(xn, margin=0.5)
    d = mcstat.equivalence_test(xn, margin=0.5, nan_policy="omit")
    e = mcstat.equivalence_test(x, margin=0.5)
    assert d.pvalue == e.pvalue and d.nobs == 300


def test_errors():
    x = [1.0, 2.0, 3.0, 4.0]
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, margin=-1)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, margin=0)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, margin=float("nan"))
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, margin=(1, -1))
    with pytest.raises(TypeError):
        mcstat.equivalence_test(x)
    with pytest.raises(TypeError):
        mcstat.equivalence_test(x, margin="wide")
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, margin=1, alpha=0.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, margin=1, alpha=0)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, margin=1, nan_policy="ignore")
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.equivalence_test([1.0], margin=1)
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.equivalence_test([], margin=1)
    with pytest.raises(mcstat.DegenerateDataError):
        mcstat.equivalence_test([2.0, 2.0, 2.0], margin=1)
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.equivalence_test(x, [1.0, np.inf], margin=1)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(x, x, mu=1.0, margin=1)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.equivalence_test(np.ones((2, 3)), margin=1)
    with pytest.raises(TypeError):
        mcstat.equivalence_test(None, margin=1)
