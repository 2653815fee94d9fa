"""mcstat.ks_test: against SciPy, R's printed blocks, a direct computation of
Canner's statistic, the exact p-values, and its own promises (reproducible
simulation, the cache, calibration under H0, every bad input).

R's cases are tests/data/ref_ks.h (tools/refgen/make_ks_ref.R, R 4.2.2),
their exact p-values tests/data/ref_ks_exact.h (tools/refgen/make_ks_exact.py,
big-integer path counts), read from the headers so that the C and the
Python tests check against the very same numbers.
"""
import os
import pickle
import re
import threading
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from scipy import stats

import mcstat
from conftest import ROOT, rel_err

MCSTAT_OF_R = {0: "two-sided", 1: "greater", 2: "less"}  # R's alternative -> mcstat's (ERRATA 4)


def _load_r_cases():
    text = open(os.path.join(ROOT, "tests", "data", "ref_ks.h")).read()
    arrays = {m.group(1): [float.fromhex(v.strip()) for v in m.group(2).split(",") if v.strip()]
              for m in re.finditer(r"static const double (ks_[xy]\d+)\[\] = \{(.*?)\};", text, re.S)}
    cases = []
    for m in re.finditer(r'\{(ks_x\d+), (\d+), (ks_y\d+), (\d+), (\d), (\S+), (\S+),\s*"(.*?)"\},', text, re.S):
        x, y = np.array(arrays[m.group(1)]), np.array(arrays[m.group(3)])
        assert len(x) == int(m.group(2)) and len(y) == int(m.group(4))
        r_text = m.group(8).encode().decode("unicode_escape")
        cases.append(dict(x=x, y=y, r_alt=int(m.group(5)), statistic=float.fromhex(m.group(6)),
                          p=float.fromhex(m.group(7)), text=r_text))
    exact_text = open(os.path.join(ROOT, "tests", "data", "ref_ks_exact.h")).read()
    pairs = re.findall(r"\{(\S+), (\S+)\},", exact_text)
    assert len(pairs) == len(cases) > 50
    for c, (a, b) in zip(cases, pairs):
        c["exact_none"], c["exact_canner"] = float.fromhex(a), float.fromhex(b)
    return cases


R_CASES = _load_r_cases()


def has_ties(x, y):
    z = np.concatenate([x, y])
    return np.unique(z).size < z.size


def direct_statistic(x, y, weight, alternative):
    """The statistic straight from its definition (ERRATA 1-2): ECDFs at
    each distinct pooled value, the last (z = 1) left out for Canner."""
    x, y = np.sort(x), np.sort(y)
    nx, ny = x.size, y.size
    t = np.unique(np.concatenate([x, y]))
    F = np.searchsorted(x, t, side="right") / nx
    G = np.searchsorted(y, t, side="right") / ny
    d = {"two-sided": np.abs(F - G), "less": F - G, "greater": G - F}[alternative]
    d = np.concatenate([d, [0.0]])  # one-sided statistics are >= 0
    if weight == "none":
        return d.max()
    z = (nx * F + ny * G) / (nx + ny)
    keep = (z > 0) & (z < 1)
    w = np.concatenate([d[:-1][keep] / np.sqrt(z[keep] * (1 - z[keep])), [0.0]])
    return np.sqrt(nx * ny / (nx + ny)) * w.max()


def strip_decision(text):
    lines = text.split("\n")
    idx = [i for i, l in enumerate(lines) if l.startswith("decision at alpha = ")]
    assert len(idx) == 1, text
    del lines[idx[0]]
    return "\n".join(lines)


# ---------------------------------------------------------------------------
# against SciPy
# ---------------------------------------------------------------------------

SIZES = [(10, 10), (25, 40), (50, 50), (60, 37), (100, 120), (7, 90)]


@pytest.mark.parametrize("nx,ny", SIZES)
@pytest.mark.parametrize("shift", [0.0, 0.6])
def test_exact_unweighted_against_scipy(nx, ny, shift):
    """Statistic and exact p-value against ks_2samp(method="exact") on
    tie-free data; mcstat's "less" is SciPy's "greater" and vice versa."""
    rng = np.random.default_rng(nx * 1000 + ny + int(10 * shift))
    x, y = rng.standard_normal(nx) + shift, rng.standard_normal(ny)
    for ours, theirs in [("two-sided", "two-sided"), ("less", "greater"), ("greater", "less")]:
        r = mcstat.ks_test(x, y, weight="none", method="exact", alternative=ours)
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # SciPy falls back to asymp with a warning: fail instead
            s = stats.ks_2samp(x, y, method="exact", alternative=theirs)
        assert r.pvalue_method == "exact"
        assert rel_err(r.statistic, s.statistic) < 1e-12, (ours, r.statistic, s.statistic)
        assert rel_err(r.pvalue, s.pvalue) < 1e-9, (ours, r.pvalue, s.pvalue)


def test_less_is_scipys_greater():
    """The naming trap, spelled out: x clearly smaller than y."""
    rng = np.random.default_rng(7)
    x, y = rng.standard_normal(40) - 0.8, rng.standard_normal(45)
    less = mcstat.ks_test(x, y, weight="none", method="exact", alternative="less")
    greater = mcstat.ks_test(x, y, weight="none", method="exact", alternative="greater")
    s_greater = stats.ks_2samp(x, y, method="exact", alternative="greater")
    s_less = stats.ks_2samp(x, y, method="exact", alternative="less")
    assert less.pvalue < 1e-3 and less.decision == "less" and less.reject
    assert greater.pvalue > 0.5 and greater.decision == "equal"
    assert rel_err(less.pvalue, s_greater.pvalue) < 1e-9
    assert rel_err(greater.pvalue, s_less.pvalue) < 1e-9
    # two-sided: the decision names the direction in mcstat's sense
    assert mcstat.ks_test(x, y, weight="none").decision == "less"
    assert mcstat.ks_test(y, x, weight="none").decision == "greater"


@pytest.mark.parametrize("nx,ny", [(3000, 3000), (5000, 7000)])
def test_asymptotic_against_scipy(nx, ny):
    """Statistic equal to SciPy's; p-value = Kolmogorov's limit at
    sqrt(ne) D (SciPy's kstwobign) two-sided and exp(-2 ne D^2) one-sided;
    and near ks_2samp's own asymptotic p-value (which uses another
    approximation, kstwo at round(ne))."""
    rng = np.random.default_rng(nx + ny)
    x, y = rng.standard_normal(nx) + 0.06, rng.standard_normal(ny)
    ne = nx * ny / (nx + ny)
    for ours, theirs in [("two-sided", "two-sided"), ("less", "greater"), ("greater", "less")]:
        r = mcstat.ks_test(x, y, weight="none", method="asymptotic", alternative=ours)
        s = stats.ks_2samp(x, y, method="asymp", alternative=theirs)
        # SciPy's ECDF differences carry ~N eps of rounding; ours is the exact fraction k / (nx ny)
        assert rel_err(r.statistic, s.statistic) < 1e-11
        k = r.statistic * nx * ny
        assert k == round(k)
        if ours == "two-sided":
            assert rel_err(r.pvalue, stats.kstwobign.sf(np.sqrt(ne) * r.statistic)) < 1e-10
            assert rel_err(r.pvalue, s.pvalue) < 0.05, (r.pvalue, s.pvalue)
            c = r.critical_values[1]
            assert abs(stats.kstwobign.sf(np.sqrt(ne) * c) - 0.05) < 1e-12
        else:
            assert rel_err(r.pvalue, np.exp(-2 * ne * r.statistic ** 2)) < 1e-12
        assert r.pvalue_method == "asymptotic" and r.pvalue_se == 0 and r.n_sim == 0
    # auto goes to the limit only beyond the exact method's range, without ties
    assert mcstat.ks_test(x, y, weight="none").pvalue_method == "asymptotic"
    assert mcstat.ks_test(x[:500], y[:500], weight="none").pvalue_method == "exact"


def test_big_unweighted_threads_and_direct():
    """Above 65536 values the samples are sorted, and the merged pass made,
    on two threads: the same bits as one thread, the statistic and the
    direction of the supremum as the definition gives them (with and
    without ties)."""
    rng = np.random.default_rng(77)
    x, y = rng.standard_normal(120001), rng.standard_normal(99999) + 0.01
    for xx, yy in [(x, y), (np.round(x, 2), np.round(y, 2)), (y, x)]:
        for alt in ("two-sided", "less", "greater"):
            kw = dict(weight="none", alternative=alt, method="simulate", n_sim=50, seed=1) if has_ties(xx, yy) \
                else dict(weight="none", alternative=alt, method="asymptotic")
            one, two = mcstat.ks_test(xx, yy, threads=1, **kw), mcstat.ks_test(xx, yy, threads=2, **kw)
            assert one._raw() == two._raw()
            assert rel_err(one.statistic, direct_statistic(xx, yy, "none", alt)) < 1e-12
            if one.reject and alt == "two-sided":
                xs, ys = np.sort(xx), np.sort(yy)
                t = np.unique(np.concatenate([xs, ys]))
                dev = np.searchsorted(xs, t, side="right") / xs.size - np.searchsorted(ys, t, side="right") / ys.size
                first = dev[np.argmax(np.abs(dev) == np.abs(dev).max())]
                assert one.decision == ("less" if first > 0 else "greater")


# ---------------------------------------------------------------------------
# R's cases, the exact values, the direct statistic
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("i", range(len(R_CASES)))
def test_r_cases(i):
    c = R_CASES[i]
    alt = MCSTAT_OF_R[c["r_alt"]]
    r = mcstat.ks_test(c["x"], c["y"], weight="none", method="exact", alternative=alt)
    rc = mcstat.ks_test(c["x"], c["y"], weight="canner", method="exact", alternative=alt)
    # exact p-values from big-integer path counts
    assert rel_err(r.pvalue, c["exact_none"]) < 1e-12
    assert rel_err(rc.pvalue, c["exact_canner"]) < 1e-12
    # statistics: R's (a float cumulative sum: ulps of noise) and the definition
    assert abs(r.statistic - c["statistic"]) <= 1e-13 * max(abs(c["statistic"]), 1.0)
    assert rel_err(r.statistic, direct_statistic(c["x"], c["y"], "none", alt)) < 1e-13
    assert rel_err(rc.statistic, direct_statistic(c["x"], c["y"], "canner", alt)) < 1e-13
    # the printed block is R's plus the decision line, except where R is off
    # (as in tests/c/test_ks.c): its "less" with ties uses the wrong tail,
    # it prints rounding noise for a zero statistic, and its 1 - P has other
    # digits than the exact value below ~1e-11
    ties = has_ties(c["x"], c["y"])
    if (c["r_alt"] == 1 and ties) or (abs(c["statistic"]) < 1e-12 and r.statistic == 0.0) \
            or rel_err(c["p"], c["exact_none"]) > 1e-6:
        return  # the exact values are checked above; R's printed one is off here
    assert abs(r.pvalue - c["p"]) <= 1e-9 * c["p"] + 1e-12
    want = re.sub(r"data:  [^\n]*\n", "data:  x and y\n", c["text"])
    assert strip_decision(str(r)) == want
    assert f"decision at alpha = 0.05: {r.decision}\n\n" in str(r)
    assert r.format("new", "trusted") == str(r).replace("data:  x and y", "data:  new and trusted")


def test_r_blocks_cover_enough():
    """The skips above leave most of R's blocks compared."""
    compared = 0
    for c in R_CASES:
        ties = has_ties(c["x"], c["y"])
        if not ((c["r_alt"] == 1 and ties) or abs(c["statistic"]) < 1e-12
                or rel_err(c["p"], c["exact_none"]) > 1e-6):
            compared += 1
    assert compared >= 50


@pytest.mark.parametrize("ties", [False, True])
def test_canner_statistic_direct(ties):
    rng = np.random.default_rng(11 + ties)
    for k in range(40):
        nx, ny = rng.integers(1, 60, size=2)
        x, y = rng.standard_normal(nx) + 0.3 * rng.standard_normal(), rng.standard_normal(ny)
        if ties:
            x, y = np.round(2 * x) / 2, np.round(2 * y) / 2
        for alt in ("two-sided", "less", "greater"):
            for w in ("none", "canner"):
                r = mcstat.ks_test(x, y, weight=w, alternative=alt, method="exact", critical=False)
                d = direct_statistic(x, y, w, alt)
                assert abs(r.statistic - d) <= 1e-13 * max(d, 1.0), (k, alt, w, r.statistic, d)
                assert r.weight == w and r.nobs == (nx, ny)


def test_blocks_of_canner_and_simulation():
    rng = np.random.default_rng(3)
    x, y = rng.standard_normal(20) + 0.5, rng.standard_normal(25)
    r = mcstat.ks_test(x, y, alternative="less", alpha=0.01, method="simulate", n_sim=999, seed=5)
    t = r.format("new", "trusted")
    assert t.startswith("\n\tMonte-Carlo two-sample Kolmogorov-Smirnov test with Canner's weight\n\n")
    assert "data:  new and trusted\nD2^+ = " in t  # mcstat's less is R's "greater": D^+
    assert f"Monte Carlo standard error of the p-value: " in t and " (999 replicates)\n" in t
    assert "alternative hypothesis: the CDF of x lies above that of y\n" in t
    assert t.endswith(f"decision at alpha = 0.01: {r.decision}\n\n")
    assert r.method == "Monte-Carlo two-sample Kolmogorov-Smirnov test with Canner's weight"
    e = mcstat.ks_test(x, y, method="exact")
    assert str(e).startswith("\n\tExact two-sample Kolmogorov-Smirnov test with Canner's weight\n\ndata:  x and y\nD2 = ")
    assert e.method == "Exact two-sample Kolmogorov-Smirnov test with Canner's weight"
    a = mcstat.ks_test(x, y, weight="none", method="asymptotic", alternative="greater")
    assert str(a).startswith("\n\tAsymptotic two-sample Kolmogorov-Smirnov test\n\ndata:  x and y\nD^- = ")
    assert "KSCache" not in repr(r) and "pvalue=" in repr(r) and "n_sim=999" in repr(r)
    for res in (r, e, a):
        assert np.isnan(res.df) and np.isnan(res.null_value) and np.isnan(res.std_error)
        back = pickle.loads(pickle.dumps(res))
        assert str(back) == str(res) and back.seed == res.seed and back._raw() == res._raw()
    assert r.seed == 5 and e.seed is None and a.seed is None


# ---------------------------------------------------------------------------
# the simulation
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("nx,ny", [(8, 11), (30, 25), (100, 80)])
@pytest.mark.parametrize("weight", ["none", "canner"])
def test_simulated_within_error_of_exact(nx, ny, weight):
    rng = np.random.default_rng(nx * ny)
    x, y = rng.standard_normal(nx) + 0.4, rng.standard_normal(ny)
    for k, alt in enumerate(("two-sided", "less", "greater")):
        e = mcstat.ks_test(x, y, weight=weight, alternative=alt, method="exact")
        s = mcstat.ks_test(x, y, weight=weight, alternative=alt, method="simulate", n_sim=20000, seed=k)
        se = np.sqrt(e.pvalue * (1 - e.pvalue) / 20000)
        assert s.pvalue_method == "simulate" and s.n_sim == 20000
        assert s.statistic == e.statistic
        assert abs(s.pvalue - e.pvalue) <= 4.5 * se + 1 / 20001, (alt, s.pvalue, e.pvalue, se)
        assert abs(s.pvalue_se - se) <= 0.2 * se + 1e-4
        # decisions and critical values agree with each other
        for r in (e, s):
            assert r.reject == (r.pvalue <= r.alpha) == (r.statistic > r.critical_values[1])
            assert r.critical_values[0] == -np.inf
        assert e.critical_se == 0.0 and s.critical_se >= 0.0
        tol = max(5 * s.critical_se, 0.05 * e.critical_values[1])
        assert abs(s.critical_values[1] - e.critical_values[1]) <= tol, (s.critical_values, e.critical_values)


def test_simulated_pvalue_never_zero():
    x, y = np.arange(50.0), np.arange(50.0) + 100  # the most extreme arrangement
    r = mcstat.ks_test(x, y, method="simulate", n_sim=500, seed=1)
    assert r.pvalue == 1 / 501 and r.pvalue > 0 and r.pvalue_se > 0
    assert mcstat.ks_test(x, y, method="exact").pvalue < 1e-20


def test_simulated_with_ties_against_exact():
    rng = np.random.default_rng(5)
    x, y = np.round(rng.standard_normal(60) + 0.3), np.round(rng.standard_normal(70))
    assert has_ties(x, y)
    for w in ("none", "canner"):
        e = mcstat.ks_test(x, y, weight=w, method="exact")
        s = mcstat.ks_test(x, y, weight=w, method="simulate", n_sim=20000, seed=9)
        se = np.sqrt(e.pvalue * (1 - e.pvalue) / 20000)
        assert abs(s.pvalue - e.pvalue) <= 4.5 * se + 1 / 20001
    # auto simulates unweighted data with ties beyond the exact range
    big_x, big_y = np.round(rng.standard_normal(3000)), np.round(rng.standard_normal(3000))
    assert mcstat.ks_test(big_x, big_y, weight="none", n_sim=200).pvalue_method == "simulate"


def test_reproducible_from_seed():
    rng = np.random.default_rng(8)
    x, y = rng.standard_normal(300), rng.standard_normal(280) + 0.1
    runs = [mcstat.ks_test(x, y, method="simulate", n_sim=3000, seed=123, threads=t) for t in (1, 2, 3, 7)]
    assert len({r._raw() for r in runs}) == 1  # bit-identical for any number of threads
    other = mcstat.ks_test(x, y, method="simulate", n_sim=3000, seed=124)
    assert other.pvalue != runs[0].pvalue or other.critical_values != runs[0].critical_values
    # no seed: a fresh one, reported, and it repeats the run
    a = mcstat.ks_test(x, y, method="simulate", n_sim=3000)
    b = mcstat.ks_test(x, y, method="simulate", n_sim=3000)
    assert isinstance(a.seed, int) and 0 <= a.seed < 2 ** 64 and a.seed != b.seed
    assert mcstat.ks_test(x, y, method="simulate", n_sim=3000, seed=a.seed)._raw() == a._raw()
    assert mcstat.ks_test(x, y, method="simulate", n_sim=3000, seed=np.uint64(2 ** 64 - 1)).seed == 2 ** 64 - 1


# ---------------------------------------------------------------------------
# the cache
# ---------------------------------------------------------------------------

def test_cache_hits_and_identical_results():
    rng = np.random.default_rng(9)
    cache = mcstat.KSCache(seed=42)
    assert (cache.hits, cache.misses, cache.entries, cache.seed) == (0, 0, 0, 42)
    pairs = [(rng.standard_normal(200), rng.standard_normal(150)) for _ in range(12)]
    cached = [mcstat.ks_test(x, y, method="simulate", n_sim=2000, cache=cache) for x, y in pairs]
    assert (cache.misses, cache.hits, cache.entries) == (1, 11, 1)
    plain = [mcstat.ks_test(x, y, method="simulate", n_sim=2000, seed=42) for x, y in pairs]
    assert [r._raw() for r in cached] == [r._raw() for r in plain]
    assert all(r.seed == 42 for r in cached)
    # another size, weight, alternative, n_sim or seed is another entry
    x, y = pairs[0]
    mcstat.ks_test(x[:100], y, method="simulate", n_sim=2000, cache=cache)
    mcstat.ks_test(x, y, weight="none", method="simulate", n_sim=2000, cache=cache)
    mcstat.ks_test(x, y, alternative="less", method="simulate", n_sim=2000, cache=cache)
    mcstat.ks_test(x, y, method="simulate", n_sim=2001, cache=cache)
    mcstat.ks_test(x, y, method="simulate", n_sim=2000, cache=cache, seed=1)
    mcstat.ks_test(np.round(x), y, method="simulate", n_sim=2000, cache=cache)  # a tie pattern
    assert (cache.misses, cache.entries) == (7, 7)
    # exact tests never touch it
    mcstat.ks_test(x, y, method="exact", cache=cache)
    assert cache.misses + cache.hits == 18
    assert "7 entries" in repr(cache)


def test_cache_eviction():
    cache = mcstat.KSCache(max_bytes=3 * 1000 * 8 + 100, seed=1)  # room for three entries of 1000 keys
    rng = np.random.default_rng(1)
    for n in range(10, 16):
        mcstat.ks_test(rng.standard_normal(n), rng.standard_normal(12), method="simulate", n_sim=1000, cache=cache)
    assert cache.entries <= 3 and cache.misses == 6


def test_cache_shared_by_threads():
    rng = np.random.default_rng(10)
    pairs = [(rng.standard_normal(400), rng.standard_normal(400)) for _ in range(16)]
    cache = mcstat.KSCache(seed=7)
    with ThreadPoolExecutor(4) as ex:
        got = list(ex.map(lambda p: mcstat.ks_test(*p, method="simulate", n_sim=4000, cache=cache, threads=1),
                          pairs))
    want = [mcstat.ks_test(*p, method="simulate", n_sim=4000, seed=7) for p in pairs]
    assert [r._raw() for r in got] == [r._raw() for r in want]
    assert cache.hits + cache.misses == 16 and cache.entries == 1


def test_gil_released():
    """A long simulation lets another Python thread run meanwhile."""
    x, y = np.random.default_rng(1).standard_normal((2, 2000))
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            stop.wait(0.001)

    t = threading.Thread(target=tick)
    t.start()
    try:
        mcstat.ks_test(x, y, method="simulate", n_sim=100000, seed=1, threads=1)  # ~0.1 s
    finally:
        stop.set()
        t.join()
    assert len(ticks) >= 5


# ---------------------------------------------------------------------------
# calibration under H0
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("weight", ["none", "canner"])
def test_calibration_exact(weight):
    """Rejection rate at alpha = 0.05 over 2000 tests of same-distribution
    samples: at most alpha (the exact test is conservative only through the
    discreteness of the statistic), and not far below."""
    rng = np.random.default_rng(100 + (weight == "canner"))
    alpha, m = 0.05, 2000
    rej = sum(mcstat.ks_test(rng.standard_normal(25), rng.standard_normal(35), weight=weight, alpha=alpha,
                             critical=False).reject for _ in range(m))
    se = np.sqrt(alpha * (1 - alpha) / m)
    assert alpha - 0.015 - 4.5 * se <= rej / m <= alpha + 4.5 * se, rej / m


def test_calibration_with_ties_and_simulation():
    """Heavy ties (p conditional on the tie pattern) and simulated p-values:
    still at most alpha."""
    rng = np.random.default_rng(200)
    alpha, m = 0.1, 800
    rej_exact = rej_sim = 0
    for _ in range(m):
        x, y = np.round(rng.standard_normal(30)), np.round(rng.standard_normal(30))
        rej_exact += mcstat.ks_test(x, y, alpha=alpha, method="exact", critical=False).reject
        rej_sim += mcstat.ks_test(x, y, alpha=alpha, method="simulate", n_sim=199, seed=1, critical=False).reject
    se = np.sqrt(alpha * (1 - alpha) / m)
    assert rej_exact / m <= alpha + 4.5 * se
    assert rej_sim / m <= alpha + 4.5 * se + 0.02  # plus the simulation's own error


# ---------------------------------------------------------------------------
# bad inputs
# ---------------------------------------------------------------------------

GOOD = np.array([0.3, 1.2, -0.5, 2.2])


def test_bad_data():
    with pytest.raises(mcstat.TooFewObservationsError, match=r"x has 0 values, y has 4"):
        mcstat.ks_test([], GOOD)
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.ks_test(GOOD, np.array([]))
    with pytest.raises(mcstat.NonFiniteError, match="NaN"):
        mcstat.ks_test(GOOD, [1.0, np.nan])
    neg_nan = np.copysign(np.nan, -1.0)
    big = np.random.default_rng(1).standard_normal(70000)
    for bad in ([neg_nan, 1.0], np.append(big, np.nan), np.append(big, neg_nan)):  # small and radix-sorted
        with pytest.raises(mcstat.NonFiniteError):
            mcstat.ks_test(bad, GOOD, weight="none")
        with pytest.raises(mcstat.NonFiniteError):
            mcstat.ks_test(GOOD, bad)
    r = mcstat.ks_test([1.0], [np.inf, -np.inf, 0.5])  # infinities are ordinary values; one value is enough
    assert 0 < r.pvalue <= 1
    r = mcstat.ks_test([np.inf, np.inf, 1.0], [-np.inf, 0.0, -0.0, np.inf], weight="none", method="exact")
    assert r.statistic == direct_statistic(np.array([np.inf, np.inf, 1.0]), np.array([-np.inf, 0.0, -0.0, np.inf]),
                                           "none", "two-sided")
    with pytest.raises(mcstat.InvalidArgumentError, match="1-D"):
        mcstat.ks_test(np.ones((2, 3)), GOOD)
    with pytest.raises(mcstat.InvalidArgumentError, match="1-D"):
        mcstat.ks_test(GOOD, 3.0)
    with pytest.raises(TypeError, match="not None"):
        mcstat.ks_test(GOOD, None)
    with pytest.raises(TypeError, match="missing required argument 'y'"):
        mcstat.ks_test(GOOD)
    with pytest.raises((TypeError, ValueError)):
        mcstat.ks_test(["a"], GOOD)


def test_bad_options():
    bad = [
        (dict(weight="Canner"), mcstat.InvalidArgumentError, "weight must be"),
        (dict(method="permutation"), mcstat.InvalidArgumentError, "method must be"),
        (dict(alternative="two.tailed"), mcstat.InvalidArgumentError, "alternative must be"),
        (dict(alpha=0.0), mcstat.InvalidArgumentError, r"alpha must be in \(0, 1\)"),
        (dict(alpha=np.nan), mcstat.InvalidArgumentError, "alpha"),
        (dict(method="asymptotic"), mcstat.InvalidArgumentError, "weight='none'"),  # Canner is the default
        (dict(method="asymptotic", weight="canner"), mcstat.InvalidArgumentError, "no usable limit"),
        (dict(n_sim=0), mcstat.InvalidArgumentError, "n_sim must be a positive int"),
        (dict(n_sim=-5), mcstat.InvalidArgumentError, "n_sim"),
        (dict(n_sim=100.0), TypeError, "n_sim must be an int"),
        (dict(n_sim=True), TypeError, "n_sim must be an int"),
        (dict(threads=0), mcstat.InvalidArgumentError, r"threads must be in 1\.\.64"),
        (dict(threads=65), mcstat.InvalidArgumentError, "threads"),
        (dict(seed=-1), mcstat.InvalidArgumentError, "seed must be a non-negative int"),
        (dict(seed=2 ** 64), mcstat.InvalidArgumentError, "seed"),
        (dict(seed=1.5), TypeError, "seed must be an int"),
        (dict(cache="yes"), TypeError, "cache must be an mcstat.KSCache"),
        (dict(weight=1), TypeError, "weight must be a str"),
        (dict(alternatve="less"), TypeError, "unexpected keyword argument 'alternatve'"),
    ]
    for kw, exc, msg in bad:
        with pytest.raises(exc, match=msg):
            mcstat.ks_test(GOOD, GOOD + 0.1, **kw)
    with pytest.raises(TypeError, match="multiple values"):
        mcstat.ks_test(GOOD, GOOD, x=GOOD)
    with pytest.raises(TypeError, match="at most 2 positional"):
        mcstat.ks_test(GOOD, GOOD, GOOD)
    # all errors are ValueErrors worded in Python's terms (no C prefix)
    with pytest.raises(ValueError, match=r"^n_sim must be a positive int, got 0$"):
        mcstat.ks_test(GOOD, GOOD, n_sim=0)


def test_exact_too_big():
    x = np.arange(400000.0)
    with pytest.raises(mcstat.TooBigError, match="method='simulate'"):
        mcstat.ks_test(x, x + 0.5, method="exact")
    assert issubclass(mcstat.TooBigError, ValueError) and mcstat.TooBigError.status == 9


def test_cache_bad_arguments():
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.KSCache(seed=-3)
    with pytest.raises(TypeError):
        mcstat.KSCache(max_bytes="big")


@pytest.mark.parametrize("method", ["exact", "asymptotic"])
@pytest.mark.parametrize("kw", [dict(n_sim=500), dict(seed=3)])
def test_simulation_arguments_without_simulation_raise(method, kw):
    x, y = np.arange(10.0), np.arange(12.0) + 0.5
    name = next(iter(kw))
    with pytest.raises(mcstat.InvalidArgumentError, match=rf"^{name} applies to method='simulate'"):
        mcstat.ks_test(x, y, weight="none", method=method, **kw)
    mcstat.ks_test(x, y, weight="none", method="simulate", **kw)  # where they apply
