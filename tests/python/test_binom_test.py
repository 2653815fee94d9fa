"""mcstat.binom_test and mcstat.battery_test against R's binom.test
(tests/data/binom_ref.csv, from tools/refgen/make_binom_ref.R),
SciPy's binomtest, and mpmath for tails far below what doubles hold."""
import csv
import math
import os

import mpmath
import numpy as np
import pytest
from scipy import stats

import mcstat

HERE = os.path.dirname(__file__)


def _ref_rows():
    with open(os.path.join(HERE, "..", "data", "binom_ref.csv")) as f:
        return list(csv.DictReader(f))


REF = _ref_rows()


@pytest.mark.parametrize("row", REF, ids=[f"{r['x']}/{r['n']}@{r['p']}-{r['alternative']}" for r in REF])
def test_against_r(row):
    x, n, p = int(float(row["x"])), int(float(row["n"])), float(row["p"])
    alt = row["alternative"].replace(".", "-")
    r = mcstat.binom_test(x, n, p, alternative=alt, alpha=float(row["alpha"]))
    want = float(row["pvalue"])
    if want > 1e-300:
        assert r.pvalue == pytest.approx(want, rel=1e-10)
    lp = float(row["log_pvalue"])
    if math.isfinite(lp) and lp < -1e-3 and (alt != "two-sided" or want > 1e-300):
        assert r.log_pvalue == pytest.approx(lp, rel=1e-10)
    assert r.conf_int[0] == pytest.approx(float(row["lo"]), rel=1e-9, abs=1e-300)
    assert r.conf_int[1] == pytest.approx(float(row["hi"]), rel=1e-9)
    assert r.statistic == x and r.estimate == x / n and r.nobs == n and r.null_value == p


def _scipy_cases():
    rng = np.random.default_rng(20261123)
    out = []
    for _ in range(150):
        n = int(rng.choice([1, 2, 5, 13, 40, 100, 777, 5000, 20000]))
        p = float(rng.choice([rng.random(), 0.5, 0.01, 0.3, 0.99]))
        x = int(np.clip(round(n * p + rng.normal() * math.sqrt(n * p * (1 - p) + 1) * rng.uniform(0, 5)), 0, n))
        out.append((x, n, p, str(rng.choice(["two-sided", "less", "greater"]))))
    return out


@pytest.mark.parametrize("x,n,p,alt", _scipy_cases())
def test_against_scipy(x, n, p, alt):
    ours = mcstat.binom_test(x, n, p, alternative=alt)
    ref = stats.binomtest(x, n, p, alternative=alt)
    ci = ref.proportion_ci(confidence_level=0.95, method="exact")
    assert ours.pvalue == pytest.approx(ref.pvalue, rel=1e-9, abs=1e-300)
    assert ours.conf_int[0] == pytest.approx(ci.low, rel=1e-9, abs=1e-12)
    assert ours.conf_int[1] == pytest.approx(ci.high, rel=1e-9, abs=1e-12)
    assert ours.reject == (ours.pvalue <= 0.05)


def _mp_pmf(k, n, p):
    return mpmath.binomial(n, k) * mpmath.mpf(p) ** k * (1 - mpmath.mpf(p)) ** (n - k)


def _mp_two_sided(x, n, p):
    """R's rule, summed exactly in mpmath (the tails are short: terms fall
    geometrically far from the mode)."""
    mpmath.mp.dps = 40
    m = n * p
    d = _mp_pmf(x, n, p) * (1 + mpmath.mpf("1e-7"))

    def tail_sum(start, step):
        s, k = mpmath.mpf(0), start
        while 0 <= k <= n:
            t = _mp_pmf(k, n, p)
            s += t
            if t < s * mpmath.mpf("1e-30"):
                break
            k += step
        return s

    if x < m:
        j = math.ceil(m)
        while j <= n and _mp_pmf(j, n, p) > d:
            j += 1
        return tail_sum(x, -1) + (tail_sum(j, 1) if j <= n else 0)
    j = math.floor(m)
    while j >= 0 and _mp_pmf(j, n, p) > d:
        j -= 1
    return (tail_sum(j, -1) if j >= 0 else 0) + tail_sum(x, 1)


@pytest.mark.parametrize("x,n,p", [(800, 10**9, 1e-6), (1150, 10**9, 1e-6), (5000, 10**9, 1e-6),
                                   (0, 10**9, 1e-6), (30, 10**7, 1e-4), (2, 10**9, 1e-8), (60, 10**9, 1e-8)])
def test_two_sided_large_n_mpmath(x, n, p):
    """Beyond R (whose rule enumerates O(n) densities): n = 1e9, p-values to
    e^-3000, against R's rule evaluated exactly."""
    want = _mp_two_sided(x, n, p)
    r = mcstat.binom_test(x, n, p)
    assert r.log_pvalue == pytest.approx(float(mpmath.log(want)), rel=1e-10)
    if want > mpmath.mpf("1e-300"):
        assert r.pvalue == pytest.approx(float(want), rel=1e-10)


def test_deep_one_sided_tails_mpmath():
    mpmath.mp.dps = 40
    # P[X >= 200] for n = 1e6, p = 1e-5 (mean 10): ~1e-240
    want = mpmath.fsum(_mp_pmf(k, 10**6, 1e-5) for k in range(200, 400))
    r = mcstat.binom_test(200, 10**6, 1e-5, alternative="greater")
    assert r.pvalue == pytest.approx(float(want), rel=1e-10)
    # P[X >= 900] for n = 1e6, p = 1e-5: ~1e-1200, only as a log
    want = mpmath.fsum(_mp_pmf(k, 10**6, 1e-5) for k in range(900, 1100))
    r = mcstat.binom_test(900, 10**6, 1e-5, alternative="greater")
    assert r.pvalue == 0.0
    assert r.log_pvalue == pytest.approx(float(mpmath.log(want)), rel=1e-11)


def test_block_like_r():
    text = mcstat.binom_test(14, 1000, 0.01).format("14", "1000")
    assert text == ("\n\tExact binomial test\n\ndata:  14 and 1000\n"
                    "number of successes = 14, number of trials = 1000, p-value = 0.2006\n"
                    "alternative hypothesis: true probability of success is not equal to 0.01\n"
                    "95 percent confidence interval:\n 0.007674502 0.023378156\n"
                    "sample estimates:\nprobability of success \n                 0.014 \n"
                    "decision at alpha = 0.05: equal\n\n")


def test_critical_values_are_the_acceptance_region():
    for n, p, alt in [(50, 0.1, "two-sided"), (333, 0.5, "less"), (80, 0.02, "greater"), (7, 0.9, "two-sided")]:
        r0 = mcstat.binom_test(0, n, p, alternative=alt)
        lo, hi = r0.critical_values
        for x in range(n + 1):
            r = mcstat.binom_test(x, n, p, alternative=alt)
            assert r.reject == (x < lo or x > hi)


def test_errors():
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.binom_test(5, 4, 0.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.binom_test(-1, 4, 0.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.binom_test(1, 4, float("nan"))
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.binom_test(1, 4, 1.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.binom_test(1, 4, 0.5, alpha=0.0)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.binom_test(1, 4, 0.5, alternative="bigger")
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.binom_test(0, 0, 0.5)
    with pytest.raises(mcstat.TooBigError):
        mcstat.binom_test(0, 2**60, 0.5)
    with pytest.raises(TypeError):
        mcstat.binom_test(1.5, 4, 0.5)
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.battery_test([0.1, float("nan")], 0.05)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.battery_test([0.1, 1.2], 0.05)
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.battery_test(np.array([], dtype=float), 0.05)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.battery_test([0.1, 0.2], 1.0)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.battery_test(np.array([True, False]), 0.0)
    with pytest.raises(TypeError):
        mcstat.battery_test(3)
    with pytest.raises(TypeError):
        mcstat.battery_test(np.array([0, 1, 1]), 0.05)  # flags or p-values?


def test_battery_forms_agree():
    rng = np.random.default_rng(3)
    pv = rng.random(500)
    a = mcstat.battery_test(pv, 0.05)
    b = mcstat.battery_test(pv <= 0.05, 0.05)
    c = mcstat.battery_test(int((pv <= 0.05).sum()), 0.05, n=500)
    ref = stats.binomtest(int((pv <= 0.05).sum()), 500, 0.05)
    assert a.pvalue == b.pvalue == c.pvalue == pytest.approx(ref.pvalue, rel=1e-9)


def test_battery_calibration_and_power():
    """Under H0 (uniform p-values) the meta-test rejects at most meta_alpha
    (it is exact and discrete, so conservative), within binomial bounds;
    against an anti-conservative battery (p-values Beta(0.8, 1)) it rejects
    nearly always."""
    rng = np.random.default_rng(11)
    B, k = 2000, 400
    rej0 = sum(mcstat.battery_test(rng.random(k), 0.05).reject for _ in range(B))
    # binomial upper bound: B * 0.05 + 4 sd
    assert rej0 <= B * 0.05 + 4 * math.sqrt(B * 0.05 * 0.95)
    assert rej0 >= 0.3 * B * 0.05  # not degenerate
    rej1 = sum(mcstat.battery_test(rng.beta(0.8, 1.0, k), 0.05).reject for _ in range(200))
    assert rej1 >= 0.6 * 200
