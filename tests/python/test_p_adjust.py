"""mcstat.p_adjust against R's p.adjust (tests/data/p_adjust_ref.txt, made
by tools/refgen/make_p_adjust_ref.R) and statsmodels' multipletests;
shapes, NaN, and bad input."""
import os
import zlib

import numpy as np
import pytest
from statsmodels.stats.multitest import multipletests

import mcstat
from conftest import ROOT

REF = os.path.join(ROOT, "tests", "data", "p_adjust_ref.txt")
METHODS = ["bonferroni", "holm", "hochberg", "hommel", "BH", "BY"]
SM = {"bonferroni": "bonferroni", "holm": "holm", "hochberg": "simes-hochberg", "hommel": "hommel",
      "BH": "fdr_bh", "BY": "fdr_by"}


def _read_ref():
    cases, large = [], []
    with open(REF) as f:
        lines = iter(f.read().splitlines())
    for line in lines:
        t = line.split()
        if t[0] == "case":
            p = np.array([float(v) for v in next(lines).split()[1:]])
            adj = np.array([float(v) for v in next(lines).split()[1:]])
            cases.append((t[1], t[2], p, adj))
        elif t[0] == "large":
            large.append({"method": t[1], "n": int(t[2]), "at": []})
        elif t[0] == "at":
            large[-1]["at"].append((int(t[1]), float(t[2])))
        elif t[0] == "sum":
            large[-1]["sum"], large[-1]["count05"] = float(t[1]), int(t[2])
    return cases, large


CASES, LARGE = _read_ref()


def gen(n):
    """The p-values of the R script's gen(N), bit for bit."""
    k = np.arange(n, dtype=np.int64)
    u = ((k * 7919 + 12345) % 1000003) / 1000003.0
    p = u.copy()
    r = k % 7 == 0
    p[r] = np.floor(u[r] * 1000) / 1000
    s = k % 10 == 0
    p[s] = u[s] * u[s] * u[s] * u[s] * 1e-3
    p[k % 5000 == 1] = 0
    p[k % 5000 == 2] = 1
    p[k % 1000 == 999] = np.nan
    return p


def test_reference_file_complete():
    assert len(CASES) == 12 * 6 and len(LARGE) == 6


@pytest.mark.parametrize("name,method,p,want", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_against_r(name, method, p, want):
    got = mcstat.p_adjust(p, method=method)
    np.testing.assert_array_equal(np.isnan(got), np.isnan(want))
    ok = ~np.isnan(want)
    np.testing.assert_allclose(got[ok], want[ok], rtol=1e-14, atol=0)


@pytest.mark.parametrize("rec", LARGE, ids=[r["method"] for r in LARGE])
def test_against_r_large(rec):
    got = mcstat.p_adjust(gen(rec["n"]), method=rec["method"])
    idx = np.array([i for i, _ in rec["at"]])
    want = np.array([v for _, v in rec["at"]])
    np.testing.assert_array_equal(np.isnan(got[idx]), np.isnan(want))
    ok = ~np.isnan(want)
    np.testing.assert_allclose(got[idx][ok], want[ok], rtol=1e-13, atol=0)
    assert np.nansum(got) == pytest.approx(rec["sum"], rel=1e-11)
    assert int(np.count_nonzero(got <= 0.05)) == rec["count05"]


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("kind", ["uniform", "signals", "ties"])
def test_against_statsmodels(method, kind):
    rng = np.random.default_rng(zlib.crc32(f"{method}-{kind}".encode()))
    n = 3000 if method != "hommel" else 600
    p = rng.uniform(size=n)
    if kind == "signals":
        p[: n // 5] = rng.beta(0.1, 8, size=n // 5)
    elif kind == "ties":
        p = np.round(p, 2)
    want = multipletests(p, method=SM[method])[1]
    got = mcstat.p_adjust(p, method=method)
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-15)


def test_any_shape_and_nan():
    rng = np.random.default_rng(3)
    p = rng.uniform(size=(7, 11, 3)) ** 3
    p[2, 4, 1] = np.nan
    got = mcstat.p_adjust(p, method="BH")
    assert got.shape == p.shape and got.dtype == np.float64
    assert np.isnan(got[2, 4, 1]) and np.isnan(got).sum() == 1
    ok = ~np.isnan(p)
    # n counts the non-NaN values only: the same as adjusting them alone
    np.testing.assert_array_equal(got[ok], mcstat.p_adjust(p[ok], method="BH"))
    # non-contiguous and float32 input, input left alone
    q = np.asfortranarray(p)
    before = q.copy()
    np.testing.assert_array_equal(mcstat.p_adjust(q, method="BH"), got)
    np.testing.assert_array_equal(q, before)
    f32 = rng.uniform(size=20).astype(np.float32)
    np.testing.assert_array_equal(mcstat.p_adjust(f32, method="holm"),
                                  mcstat.p_adjust(f32.astype(np.float64), method="holm"))


def test_aliases_and_trivial():
    p = np.array([0.01, 0.04, 0.03])
    np.testing.assert_array_equal(mcstat.p_adjust(p, method="fdr"), mcstat.p_adjust(p, method="BH"))
    np.testing.assert_array_equal(mcstat.p_adjust(p, method="bh"), mcstat.p_adjust(p, method="BH"))
    np.testing.assert_array_equal(mcstat.p_adjust(p, method="by"), mcstat.p_adjust(p, method="BY"))
    np.testing.assert_array_equal(mcstat.p_adjust(p, method="none"), p)
    np.testing.assert_array_equal(mcstat.p_adjust(p), mcstat.p_adjust(p, method="holm"))
    assert mcstat.p_adjust([], method="BH").shape == (0,)
    assert mcstat.p_adjust(0.2, method="BH") == 0.2  # one test: unchanged, as R


@pytest.mark.parametrize("bad", [1.5, -0.01, np.inf, -np.inf])
def test_out_of_range(bad):
    with pytest.raises(mcstat.InvalidArgumentError, match=r"\[0, 1\].*flat index 2"):
        mcstat.p_adjust([0.1, 0.2, bad, 0.3], method="BH")


def test_bad_method_and_type():
    with pytest.raises(mcstat.InvalidArgumentError, match="method"):
        mcstat.p_adjust([0.1, 0.2], method="sidak")
    with pytest.raises(TypeError):
        mcstat.p_adjust(None)
    with pytest.raises((TypeError, ValueError)):
        mcstat.p_adjust(["a", "b"])


# statsmodels' multipletests spellings of the methods mcstat implements
# (its own alias table, case-insensitive as statsmodels compares them).
SM_ALIASES = ["b", "bonf", "bonferroni", "h", "holm", "sh", "simes-hochberg", "ho", "hommel",
              "fdr_bh", "fdr_i", "fdr_p", "fdri", "fdrp", "fdr_by", "fdr_n", "fdr_c", "fdrn", "fdrcorr",
              "FDR_BH", "Holm", "Bonferroni"]


@pytest.mark.parametrize("name", SM_ALIASES)
def test_statsmodels_method_names(name):
    rng = np.random.default_rng(zlib.crc32(name.encode()))
    p = rng.uniform(size=200) ** 3
    want = multipletests(p, method=name.lower())[1]
    np.testing.assert_allclose(mcstat.p_adjust(p, method=name), want, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("name", ["sidak", "s", "holm-sidak", "hs", "fdr_tsbh", "fdr_tsbky", "fdr_gbs"])
def test_statsmodels_methods_not_implemented(name):
    # a ValueError that lists what is accepted and says this one is missing
    with pytest.raises(ValueError, match=r"'fdr_bh'.*'BH'|'BH'.*'fdr_bh'") as e:
        mcstat.p_adjust([0.1, 0.2], method=name)
    assert "does not implement" in str(e.value)
    assert repr(name) in str(e.value)


def test_work_size():
    assert mcstat.p_adjust_work_size(1000, "BH") == 32 * 1000
    assert mcstat.p_adjust_work_size(1000, "fdr_by") == 32 * 1000
    assert mcstat.p_adjust_work_size(1000, "hommel") == 40 * 1000
    assert mcstat.p_adjust_work_size(1000, "bonferroni") == 0
    assert mcstat.p_adjust_work_size(1000, "none") == 0
    assert mcstat.p_adjust_work_size(0, "holm") == 0
    with pytest.raises(mcstat.InvalidArgumentError, match="unknown p_adjust method 'nope'"):
        mcstat.p_adjust_work_size(10, "nope")
    with pytest.raises(mcstat.InvalidArgumentError, match="n must be >= 0"):
        mcstat.p_adjust_work_size(-1, "BH")
    with pytest.raises(mcstat.TooBigError):
        mcstat.p_adjust_work_size(2**63 - 1, "BH")


@pytest.mark.parametrize("method", ["holm", "hochberg", "hommel", "BH", "BY", "e-BH", "bonferroni", "none"])
def test_caller_workspace_gives_the_same_values(method):
    rng = np.random.default_rng(11)
    p = rng.random(5000) ** 3
    p[::97] = np.nan
    p[5:40] = p[4]  # ties
    need = mcstat.p_adjust_work_size(p.size, method)
    work = np.full(need // 8 + 3, 7.0)  # dirty scratch: nothing may depend on its contents
    np.testing.assert_array_equal(mcstat.p_adjust(p, method=method, work=work), mcstat.p_adjust(p, method=method))
    # any dtype and shape will do as long as the bytes are there
    w8 = np.zeros((need + 64) // 2, dtype=np.uint16).reshape(-1, 1)
    np.testing.assert_array_equal(mcstat.p_adjust(p, method=method, work=w8), mcstat.p_adjust(p, method=method))


def test_caller_workspace_refused():
    p = np.linspace(0.0, 1.0, 100)
    need = mcstat.p_adjust_work_size(p.size, "BH")
    with pytest.raises(mcstat.InvalidArgumentError, match=f"work holds {need - 8} bytes; this call needs {need}"):
        mcstat.p_adjust(p, method="BH", work=np.zeros(need // 8 - 1))
    with pytest.raises(mcstat.InvalidArgumentError, match="C-contiguous"):
        mcstat.p_adjust(p, method="BH", work=np.zeros(need // 4)[::2])
    ro = np.zeros(need // 8)
    ro.flags.writeable = False
    with pytest.raises(mcstat.InvalidArgumentError, match="writable buffer"):
        mcstat.p_adjust(p, method="BH", work=ro)
    with pytest.raises(mcstat.InvalidArgumentError, match="writable buffer"):
        mcstat.p_adjust(p, method="BH", work="not a buffer")
    with pytest.raises(mcstat.InvalidArgumentError, match="aligned for float64"):
        mcstat.p_adjust(p, method="BH", work=np.zeros(need + 16, dtype=np.uint8)[1:need + 1])
    # a bad p-value is named as it is without a workspace
    with pytest.raises(mcstat.InvalidArgumentError, match="at flat index 3"):
        mcstat.p_adjust(np.array([0.1, 0.2, 0.3, 1.5]), method="BH", work=np.zeros(16))
