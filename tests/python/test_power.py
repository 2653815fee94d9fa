"""mcstat.power against R (tests/data/power_ref.tsv: power.t.test and the
chi-squared / F closed forms, written by tools/refgen/make_power_ref.R),
statsmodels' TTestPower / TTestIndPower, SciPy's central chi^2 and F, a
simulation of Welch's test; mcstat.ks_power against SciPy's ks_2samp on the
same samples."""
import math
import os

import numpy as np
import pytest
from scipy import stats

import mcstat
from conftest import ROOT, rel_err

REF = os.path.join(ROOT, "tests", "data", "power_ref.tsv")
TESTS = {"t_1": "t", "t_2": "t2", "var_1": "var", "var_2": "f"}


def _rows():
    rows = []
    for line in open(REF):
        if line.startswith("#"):
            continue
        f = line.rstrip("\n").split("\t")
        rows.append((f[0], TESTS[f[1]], f[2], f[3] == "1", *map(float, f[4:])))
    return rows


ROWS = _rows()


def test_against_r():
    counts = dict.fromkeys(["power", "n", "effect", "alpha"], 0)
    for solve, test, alt, strict, n, n_ratio, sd_ratio, effect, alpha, pw in ROWS:
        counts[solve] += 1
        kw = dict(n=n, effect=effect, alpha=alpha, power=pw, alternative=alt)
        if alt == "two-sided":
            kw["strict"] = strict
        if test in ("welch", "f"):
            kw["n_ratio"] = n_ratio
        kw[solve] = None
        r = mcstat.power(test, **kw)
        assert r.solved_for == solve
        if solve == "power":
            assert abs(r.power - pw) <= 1e-10 + 1e-9 * pw, (test, alt, n, effect, alpha)
        elif solve == "n":
            assert type(r.n) is int and r.n - 1 < r.n_exact <= r.n
            if test in ("t", "t2"):  # R's n is continuous: ours is the next integer
                assert r.n == math.ceil(n - 1e-7) or (abs(n - round(n)) < 1e-6 and r.n == round(n) + 1)
                assert abs(r.n_exact - n) <= 1e-3 * n  # R's uniroot tolerance is eps^(1/4)
            else:
                assert r.n == n
            assert r.power >= pw
        elif solve == "effect":
            assert rel_err(r.effect, effect) < 1e-8
        else:
            assert abs(r.alpha - alpha) <= 1e-11 + 1e-7 * alpha
    assert min(counts.values()) > 10 and sum(counts.values()) > 1500


def test_statsmodels():
    smp = pytest.importorskip("statsmodels.stats.power")
    one, ind = smp.TTestPower(), smp.TTestIndPower()
    alt = {"two-sided": "two-sided", "less": "smaller", "greater": "larger"}
    for a in alt:
        # (SciPy's nct, under statsmodels, returns NaN far in the tail, e.g.
        # ncp 13 at df 498: the grid stays where it answers)
        for n in (3, 8, 30, 120):
            for d in (0.1, 0.4, 0.8):
                dd = -d if a == "less" else d
                # statsmodels counts both tails two-sided: strict=True
                p = mcstat.power("t", n=n, effect=dd, alternative=a).power
                assert abs(p - one.power(dd, n, 0.05, alternative=alt[a])) < 1e-9
                p = mcstat.power("t2", n=n, effect=dd, alternative=a).power
                assert abs(p - ind.power(dd, n, 0.05, ratio=1, alternative=alt[a])) < 1e-9
        n_sm = one.solve_power(0.3, power=0.8, alpha=0.05, alternative=alt["greater"])
        r = mcstat.power("t", effect=0.3, power=0.8, alternative="greater")
        assert r.n == math.ceil(n_sm) and abs(r.n_exact - n_sm) < 1e-6 * n_sm


def test_variance_tests_closed_form():
    """rho * chi^2(n-1) and rho * F(n-1, k n - 1), written again with SciPy."""
    for n in (3, 12, 80):
        for rho in (0.5, 1.7):
            c_hi, c_lo = stats.chi2.isf(0.025, n - 1), stats.chi2.ppf(0.025, n - 1)
            want = stats.chi2.sf(c_hi / rho, n - 1) + stats.chi2.cdf(c_lo / rho, n - 1)
            assert rel_err(mcstat.power("var", n=n, effect=rho).power, want) < 1e-10
            d1, d2 = n - 1, 2 * n - 1
            want = stats.f.sf(stats.f.isf(0.05, d1, d2) / rho, d1, d2)
            got = mcstat.power("f", n=n, n_ratio=2, effect=rho, alternative="greater").power
            assert rel_err(got, want) < 1e-10


def test_welch_by_simulation():
    """The Welch-Satterthwaite noncentral-t approximation against the
    rejection rate of mcstat.t_test on 40000 simulated pairs (row-wise)."""
    rng = np.random.default_rng(99)
    reps = 40000
    for nx, ny, sdr, d in ((12, 30, 2.0, 0.9), (25, 10, 0.5, 0.6), (6, 6, 3.0, 1.5)):
        x = rng.normal(d, 1.0, (reps, nx))
        y = rng.normal(0.0, sdr, (reps, ny))
        rate = float(np.mean(mcstat.t_test(x, y, axis=-1, intervals=False).reject))
        p = mcstat.power("welch", n=nx, n_ratio=ny / nx, sd_ratio=sdr, effect=d).power
        se = math.sqrt(p * (1 - p) / reps)
        # sampling error plus the approximation's own (small) error
        assert abs(rate - p) < 4 * se + 0.01, (nx, ny, sdr, d, rate, p)


def test_bias_example():
    """How many samples to detect a 0.1% bias at power 0.9?  With primary
    estimates of mean E and sd s, d = 0.001 E / s; at s = E that is d = 1e-3
    and n ~ (z_0.975 + z_0.9)^2 / d^2 = 1.0507e7."""
    r = mcstat.power("t", effect=1e-3, power=0.9)
    z = stats.norm.isf(0.025) + stats.norm.isf(0.1)
    assert abs(r.n - z * z / 1e-6) < 10
    assert r.power >= 0.9
    r2 = mcstat.power("t", delta=0.001 * 2.0, sd=2.0, power=0.9)
    assert r2.n == r.n


def test_str_and_fields():
    r = mcstat.power("t2", effect=1, power=0.9)
    text = str(r)
    assert text.startswith("\n     Two-sample t test power calculation \n\n")
    assert "              n = 23\n" in text
    assert "NOTE: n is number in *each* group" in text
    assert r.n == 23 and r.n_y is None and r.solved_for == "n"
    w = mcstat.power("welch", n=10, n_ratio=2, effect=1)
    assert w.n_y == 20 and "n.y = 20" in str(w)


def test_errors():
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", n=10, effect=0.5, power=0.9)  # nothing to solve
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", effect=0.5)  # two unknowns
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("z", n=10, effect=0.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", n=1, effect=0.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", n=10, effect=0.5, alpha=1.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", n=10, effect=float("nan"))
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("var", n=10, effect=-2)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", effect=0.0, power=0.9)  # no n detects nothing
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", n=20, effect=None, power=0.03)  # alpha alone gives more
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("t", n=10, effect=0.5, alternative="sideways")
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("var", n=10, delta=0.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.power("welch", n=10, effect=0.5, sd_ratio=0)
    with pytest.raises(TypeError):
        mcstat.power("t", n="ten", effect=0.5)


def test_ks_power():
    # under H0 the exact unweighted test rejects at most alpha (conservative)
    r0 = mcstat.ks_power(20, weight="none", n_rep=1500, seed=5)
    assert r0.power <= 0.05 + 4 * math.sqrt(0.05 * 0.95 / 1500)
    # against SciPy's exact ks_2samp on the very same samples
    r = mcstat.ks_power(25, 30, shift=0.7, weight="none", n_rep=300, seed=11)
    rng = np.random.default_rng(11)
    rej = 0
    for _ in range(300):
        x = 0.7 + rng.standard_normal(25)
        y = rng.standard_normal(30)
        rej += stats.ks_2samp(x, y, method="exact").pvalue <= 0.05
    assert abs(r.power - rej / 300) <= 2 / 300  # p-values at the threshold may round apart
    assert r.se == pytest.approx(math.sqrt(r.power * (1 - r.power) / 300))
    assert "power" in str(r)
    # samplers: exponential with a scale change
    e = mcstat.ks_power(40, sampler=lambda g, k: g.exponential(1.0, k), scale=2.0, n_rep=200, seed=1)
    assert e.power > 0.5
    # the smallest n reaching the power, for these seeds
    s = mcstat.ks_sample_size(0.8, shift=1.0, n_rep=200, seed=3)
    assert s.power >= 0.8
    below = mcstat.ks_power(s.n - 1, shift=1.0, n_rep=200, seed=3)
    assert below.power < 0.8
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.ks_power(0)
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.ks_power(10, scale=-1)


def test_solved_n_is_an_int_with_the_exact_root_beside_it():
    r = mcstat.power("t", effect=0.5, power=0.8)
    assert type(r.n) is int and r.n == 34
    assert 33.3 < r.n_exact < 33.4  # R: power.t.test(delta=.5, power=.8, type="one.sample")$n = 33.367
    assert mcstat.power("t", n=r.n_exact, effect=0.5).power == pytest.approx(0.8, abs=1e-9)
    given = mcstat.power("t", n=20, effect=0.5)
    assert given.n == given.n_exact == 20


@pytest.mark.parametrize("test, kw, name", [
    ("t2", dict(n_ratio=1.5), "n_ratio"),
    ("t", dict(n_ratio=2), "n_ratio"),
    ("var", dict(n_ratio=2), "n_ratio"),
    ("t2", dict(sd_ratio=2), "sd_ratio"),
    ("f", dict(sd_ratio=2), "sd_ratio"),
    ("t", dict(alternative="greater", strict=False), "strict"),
])
def test_arguments_that_do_not_apply_raise(test, kw, name):
    base = dict(effect=0.5 if test.startswith("t") else 2.0, power=0.8)
    with pytest.raises(mcstat.InvalidArgumentError, match=rf"^{name} applies to"):
        mcstat.power(test, **base, **kw)
    # the defaults, passed explicitly where they apply, change nothing
    mcstat.power("welch", n_ratio=1.0, sd_ratio=1.0, **base)
    mcstat.power("t", strict=True, **base)
