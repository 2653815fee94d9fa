"""t_test as SciPy and R users expect it: equal_var=True (Student's pooled
test), paired=True, unpacking, confidence_interval, nan_policy="propagate"
and log_pvalue, against SciPy and against R (tests/data/t_ref.tsv, written
by tools/refgen/make_t_ref.R)."""
import math
import os

import mpmath
import numpy as np
import pytest
import scipy
import scipy.stats as st

import mcstat
from conftest import ROOT, rel_err

REF = os.path.join(ROOT, "tests", "data", "t_ref.tsv")
ALTS = ["two-sided", "less", "greater"]
SCIPY_CI = tuple(int(v) for v in scipy.__version__.split(".")[:2]) >= (1, 11)


SPECIAL = {"NA": math.nan, "NaN": math.nan, "Inf": math.inf, "-Inf": -math.inf}


def num(s):
    return SPECIAL[s] if s in SPECIAL else float.fromhex(s)


def _rows():
    out = []
    for line in open(REF):
        if line.startswith("#"):
            continue
        f = line.rstrip("\n").split("\t")
        vals = lambda s: None if s == "-" else np.array([float.fromhex(v) for v in s.split(",")])
        out.append(dict(kind=f[0], alt=ALTS[int(f[1])], null=num(f[2]), alpha=num(f[3]), x=vals(f[4]),
                        y=vals(f[5]), stat=num(f[6]), df=num(f[7]), p=num(f[8]), logp=num(f[9]), lo=num(f[10]),
                        hi=num(f[11]), est=num(f[12]), est2=num(f[13]), se=num(f[14]), conf2=num(f[15]),
                        lo2=num(f[16]), hi2=num(f[17]),
                        block=None if f[18] == "-" else f[18].replace("\\n", "\n").replace("\\t", "\t")))
    return out


ROWS = _rows()
T_ROWS = [i for i, r in enumerate(ROWS) if r["kind"] in ("pooled", "paired", "welch", "one")]
VAR_ROWS = [i for i, r in enumerate(ROWS) if r["kind"] in ("var1", "var2")]


def near(got, want, scale, tol):
    """|got - want| <= tol * scale, plus a few of want's ulps."""
    assert got == want or abs(got - want) <= tol * scale + 8 * np.finfo(float).eps * abs(want), (got, want, scale)


def strip_decision(text):
    return "".join(line for line in text.splitlines(True) if not line.startswith("decision at alpha"))


def test_reference_covers_the_cases():
    kinds = [r["kind"] for r in ROWS]
    for k in ("pooled", "paired", "welch", "one", "var1", "var2", "tsyn"):
        assert kinds.count(k) >= 3, k
    assert any(r["p"] == 0.0 and r["kind"] in ("pooled", "paired") for r in ROWS)  # p underflows in R too


@pytest.mark.parametrize("i", T_ROWS)
def test_t_against_r(i):
    c = ROWS[i]
    kw = dict(mu=c["null"], alternative=c["alt"], alpha=c["alpha"])
    if c["kind"] == "one":
        r = mcstat.t_test(c["x"], **kw)
    else:
        r = mcstat.t_test(c["x"], c["y"], equal_var=c["kind"] == "pooled", paired=c["kind"] == "paired", **kw)
    assert r.method == {"pooled": "Two Sample t-test", "paired": "Paired t-test",
                        "welch": "Welch Two Sample t-test", "one": "One Sample t-test"}[c["kind"]]
    assert rel_err(r.statistic, c["stat"]) <= 1e-11
    assert rel_err(r.df, c["df"]) <= 1e-13
    if c["p"] > 1e-300:
        assert rel_err(r.pvalue, c["p"]) <= 1e-11
    else:
        assert r.pvalue < 1e-290
    # the log p-value: finite where R's p-value underflowed to 0
    near(r.log_pvalue, c["logp"], max(1.0, abs(c["logp"])), 1e-12)
    assert math.isfinite(r.log_pvalue)
    width = c["hi"] - c["lo"] if math.isfinite(c["hi"] - c["lo"]) else c["se"]
    near(r.conf_int[0], c["lo"], width, 1e-10)
    near(r.conf_int[1], c["hi"], width, 1e-10)
    assert rel_err(r.std_error, c["se"]) <= 1e-11
    est = r.estimate if isinstance(r.estimate, tuple) else (r.estimate,)
    assert rel_err(est[0], c["est"]) <= 1e-12
    if not math.isnan(c["est2"]):
        assert rel_err(est[1], c["est2"]) <= 1e-12
    # the interval at R's second level (0.5 ... 0.999999)
    ci = r.confidence_interval(c["conf2"])
    width2 = c["hi2"] - c["lo2"] if math.isfinite(c["hi2"] - c["lo2"]) else c["se"]
    near(ci.low, c["lo2"], width2, 1e-10)
    near(ci.high, c["hi2"], width2, 1e-10)
    if c["block"] is not None and c["kind"] in ("pooled", "paired"):
        assert strip_decision(r.format("x", "y")) == c["block"]


@pytest.mark.parametrize("i", VAR_ROWS)
def test_var_interval_and_log_p_against_r(i):
    c = ROWS[i]
    if c["kind"] == "var2":
        r = mcstat.var_test(c["x"], c["y"], ratio=c["null"], alternative=c["alt"], alpha=c["alpha"])
    else:
        r = mcstat.var_test(c["x"], sigma2=c["null"], alternative=c["alt"], alpha=c["alpha"])
    assert rel_err(r.pvalue, c["p"]) <= 1e-11
    near(r.log_pvalue, c["logp"], max(1.0, abs(c["logp"])), 1e-12)
    ci = r.confidence_interval(c["conf2"])
    assert rel_err(ci.low, c["lo2"]) <= 1e-11 and rel_err(ci.high, c["hi2"]) <= 1e-11
    own = r.confidence_interval(1 - c["alpha"])
    assert rel_err(own[0], r.conf_int[0]) <= 1e-13 and rel_err(own[1], r.conf_int[1]) <= 1e-13


# ---- against SciPy ---------------------------------------------------------------


@pytest.mark.parametrize("alternative", ALTS)
@pytest.mark.parametrize("sizes", [(2, 2), (3, 7), (30, 12), (400, 350)])
def test_pooled_agrees_with_scipy(rng, sizes, alternative):
    for rep in range(3):
        x = rng.normal(1.0, rng.uniform(0.3, 3), size=sizes[0])
        y = rng.normal(1.0 + rng.normal(), rng.uniform(0.3, 3), size=sizes[1])
        r = mcstat.t_test(x, y, equal_var=True, alternative=alternative)
        s = st.ttest_ind(x, y, equal_var=True, alternative=alternative)
        assert rel_err(r.statistic, s.statistic) <= 1e-12
        assert rel_err(r.pvalue, s.pvalue) <= 1e-11
        assert r.df == sizes[0] + sizes[1] - 2
        t, p = r
        assert (t, p) == (r.statistic, r.pvalue)
        # (SciPy's interval evaluates t.ppf at 1 - alpha/2, which loses
        # digits at 0.999999: that level is checked against R above)
        if SCIPY_CI:
            for level in (0.5, 0.95, 0.99):
                a, b = r.confidence_interval(level), s.confidence_interval(level)
                w = r.std_error
                for g, want in ((a.low, b.low), (a.high, b.high)):
                    assert g == want or abs(g - want) <= 1e-10 * w
        # SciPy's default is this test
        assert rel_err(st.ttest_ind(x, y).statistic, r.statistic) <= 1e-12


@pytest.mark.parametrize("alternative", ALTS)
@pytest.mark.parametrize("n", [2, 3, 10, 500])
def test_paired_agrees_with_scipy(rng, n, alternative):
    for rep in range(3):
        x = rng.normal(5, 2, size=n)
        y = x + rng.normal(rng.normal() * 0.3, 0.5, size=n)
        r = mcstat.t_test(x, y, paired=True, alternative=alternative, mu=0.1 * rep)
        s = st.ttest_rel(x - 0.1 * rep, y, alternative=alternative)
        assert rel_err(r.statistic, s.statistic) <= 1e-11
        assert rel_err(r.pvalue, s.pvalue) <= 1e-10
        assert r.df == n - 1 and r.nobs == n
        assert rel_err(r.estimate, np.mean(x - y)) <= 1e-12
        if SCIPY_CI and rep == 0:
            for level in (0.5, 0.9, 0.99):
                a, b = r.confidence_interval(level), s.confidence_interval(level)
                for g, want in ((a.low, b.low), (a.high, b.high)):
                    assert g == want or abs(g - want) <= 1e-10 * r.std_error


def test_confidence_interval_is_a_named_tuple():
    r = mcstat.t_test([1.0, 2.0, 3.5, 4.0], [2.0, 2.5, 3.0, 6.1], paired=True)
    ci = r.confidence_interval()
    assert type(ci).__name__ == "ConfidenceInterval" and ci._fields == ("low", "high")
    low, high = ci
    assert (low, high) == (ci.low, ci.high)
    # the default level is SciPy's 0.95; at 1 - alpha it is conf_int
    assert ci == r.confidence_interval(0.95)
    assert all(abs(a - b) <= 1e-14 * abs(b) for a, b in zip(r.confidence_interval(1 - r.alpha), r.conf_int))
    # one-sided: an infinite end
    g = mcstat.t_test([1.0, 2.0, 3.5, 4.0], alternative="greater").confidence_interval(0.9)
    assert g.high == math.inf and math.isfinite(g.low)
    for bad in (0.0, 1.0, -0.2, 1.5, math.nan):
        with pytest.raises(mcstat.InvalidArgumentError, match="confidence_level"):
            r.confidence_interval(bad)
    with pytest.raises(TypeError, match="confidence_level"):
        r.confidence_interval("0.9")
    ks = mcstat.ks_test([0.1, 0.5, 0.7], [0.2, 0.9, 1.3], weight="none")
    with pytest.raises(mcstat.InvalidArgumentError, match="no confidence interval"):
        ks.confidence_interval()


def test_unpacking_and_indexing():
    r = mcstat.t_test([1.0, 2.0, 3.5, 4.0], [2.0, 2.5, 3.0, 6.1], equal_var=True)
    t, p = r
    assert len(r) == 2 and list(r) == [t, p]
    assert r[0] == r[-2] == r.statistic and r[1] == r[-1] == r.pvalue
    with pytest.raises(IndexError):
        r[2]
    # BatchResult is not a pair: its rows stay what len() and [i] say
    b = mcstat.t_test(np.arange(12.0).reshape(3, 4) ** 1.5, np.ones((3, 4)) + np.arange(4.0), equal_var=True)
    assert len(b) == 3 and b[1].statistic == b.statistic[1]


def test_scipy_default_equal_var_documented():
    assert "SciPy's ``ttest_ind`` defaults to the pooled test" in mcstat.t_test.__doc__


# ---- nan_policy ------------------------------------------------------------------


@pytest.mark.parametrize("kw,scipy_fn", [({}, lambda x, y: st.ttest_ind(x, y, equal_var=False)),
                                         ({"equal_var": True}, st.ttest_ind),
                                         ({"paired": True}, st.ttest_rel)])
def test_nan_policy_like_scipy(kw, scipy_fn):
    x = np.array([1.0, 2.0, np.nan, 4.0, 2.5, 3.3])
    y = np.array([2.0, 2.5, 3.0, 6.1, np.nan, 4.0])
    r = mcstat.t_test(x, y, nan_policy="propagate", **kw)
    s = scipy_fn(x, y)
    assert math.isnan(s.statistic) and math.isnan(s.pvalue)
    assert math.isnan(r.statistic) and math.isnan(r.pvalue) and math.isnan(r.df) and math.isnan(r.log_pvalue)
    assert not r.reject and r.decision == ""
    t, p = r
    assert math.isnan(t) and math.isnan(p)
    assert all(math.isnan(v) for v in r.confidence_interval())
    assert "NaN in the data" in str(r) and "decision=''" in repr(r)
    # omit: as SciPy's (ttest_rel drops the pairs)
    ro = mcstat.t_test(x, y, nan_policy="omit", **kw)
    if kw.get("paired"):
        so = st.ttest_rel(x, y, nan_policy="omit")
    elif kw.get("equal_var"):
        so = st.ttest_ind(x, y, nan_policy="omit")
    else:
        so = st.ttest_ind(x, y, equal_var=False, nan_policy="omit")
    assert rel_err(ro.statistic, so.statistic) <= 1e-12 and rel_err(ro.pvalue, so.pvalue) <= 1e-11
    # raise: the default
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.t_test(x, y, **kw)
    # no NaN: propagate changes nothing
    clean = mcstat.t_test(x[[0, 1, 3, 5]], y[[0, 1, 3, 5]], nan_policy="propagate", **kw)
    assert clean.pvalue == mcstat.t_test(x[[0, 1, 3, 5]], y[[0, 1, 3, 5]], **kw).pvalue


def test_nan_policy_propagate_rows_like_scipy():
    x = np.array([[1.0, 2.0, np.nan, 4.0], [1.0, 2.0, 3.0, 4.0], [0.5, 1.5, 2.0, 9.0]])
    y = np.array([[2.0, 3.0, 4.0, 5.5], [2.0, 3.0, 4.0, 5.5], [1.0, np.nan, 2.0, 3.0]])
    for kw, fn in (({}, lambda a, b: st.ttest_ind(a, b, axis=1, equal_var=False)),
                   ({"equal_var": True}, lambda a, b: st.ttest_ind(a, b, axis=1)),
                   ({"paired": True}, lambda a, b: st.ttest_rel(a, b, axis=1))):
        b = mcstat.t_test(x, y, nan_policy="propagate", **kw)
        s = fn(x, y)
        np.testing.assert_array_equal(np.isnan(b.statistic), np.isnan(s.statistic))
        np.testing.assert_allclose(b.pvalue[1], s.pvalue[1], rtol=1e-11)
        assert list(b.ok) == [False, True, False]
        with pytest.raises(mcstat.NonFiniteError):
            mcstat.t_test(x, y, **kw)  # raise: the default


def test_nan_policy_everywhere_and_checked():
    x = [1.0, np.nan, 3.0, 4.5]
    assert math.isnan(mcstat.t_test(x, nan_policy="propagate").pvalue)
    assert math.isnan(mcstat.var_test(x, sigma2=1.0, nan_policy="propagate").pvalue)
    assert math.isnan(mcstat.var_test(x, [1.0, 2.0, 2.5], nan_policy="propagate").pvalue)
    m = mcstat.Moments([1.0, 2.0, 3.0])
    assert math.isnan(mcstat.t_test(x, m, nan_policy="propagate").pvalue)
    assert math.isnan(mcstat.t_test(m, x, nan_policy="propagate", equal_var=True).pvalue)
    with pytest.raises(mcstat.InvalidArgumentError, match="'propagate'"):
        mcstat.t_test(x, nan_policy="ignore")


# ---- argument checks -------------------------------------------------------------


def test_paired_and_equal_var_arguments():
    x, y = [1.0, 2.0, 3.5, 4.0], [2.0, 2.5, 3.0]
    with pytest.raises(ValueError, match="paired=True needs x and y of the same length.*x with 4.*y with 3"):
        mcstat.t_test(x, y, paired=True)
    with pytest.raises(mcstat.InvalidArgumentError, match="exclude each other"):
        mcstat.t_test(x, x, paired=True, equal_var=True)
    with pytest.raises(mcstat.InvalidArgumentError, match="paired=True needs y"):
        mcstat.t_test(x, paired=True)
    with pytest.raises(mcstat.InvalidArgumentError, match="equal_var=True needs y"):
        mcstat.t_test(x, equal_var=True)
    with pytest.raises(mcstat.InvalidArgumentError, match="not mcstat.Moments"):
        mcstat.t_test(mcstat.Moments(x), x, paired=True)
    with pytest.raises(ValueError, match="same length along axis"):
        mcstat.t_test(np.ones((2, 4)), np.ones((2, 3)), paired=True)
    with pytest.raises(mcstat.DegenerateDataError):
        mcstat.t_test([1.0, 2.0, 3.0], [0.5, 1.5, 2.5], paired=True)  # constant differences
    with pytest.raises(mcstat.DegenerateDataError):
        mcstat.t_test([3.0, 3.0, 3.0], [2.0, 2.0], equal_var=True)
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.t_test([1.0], [2.0], paired=True)
    # one constant sample is fine (as R)
    assert math.isfinite(mcstat.t_test([3.0, 3.0, 3.0], [2.0, 2.5, 4.0], equal_var=True).pvalue)


def test_pooled_on_accumulators_and_rows_match_the_single_call(rng):
    x, y = rng.normal(size=(5, 9)), rng.normal(0.3, 2.0, size=(5, 7))
    b = mcstat.t_test(x, y, equal_var=True, alternative="less")
    for i in range(5):
        r = mcstat.t_test(x[i], y[i], equal_var=True, alternative="less")
        assert (b.statistic[i], b.pvalue[i]) == (r.statistic, r.pvalue)
        assert tuple(b.conf_int[i]) == r.conf_int and tuple(b.estimate[i]) == r.estimate
        m = mcstat.t_test(mcstat.Moments(x[i]), mcstat.Moments(y[i]), equal_var=True, alternative="less")
        assert m.pvalue == r.pvalue
        assert b[i].method == "Two Sample t-test"
    assert b.method == "Two Sample t-test"
    # per-pixel accumulators
    ax, ay = mcstat.MomentsArray(5), mcstat.MomentsArray(5)
    for k in range(9):
        ax.push(x[:, k])
    for k in range(7):
        ay.push(y[:, k])
    bm = mcstat.t_test(ax, ay, equal_var=True, alternative="less")
    np.testing.assert_allclose(bm.pvalue, b.pvalue, rtol=1e-13)  # pushed a column at a time: other roundings
    with pytest.raises(mcstat.InvalidArgumentError, match="MomentsArray"):
        mcstat.t_test(ax, ax, paired=True)
    # paired rows, along another axis
    z = x[:, :7] + rng.normal(0.1, 0.2, size=(5, 7))
    bp = mcstat.t_test(x[:, :7].T, z.T, paired=True, axis=0)
    for i in range(5):
        r = mcstat.t_test(x[i, :7], z[i], paired=True)
        assert (bp.statistic[i], bp.pvalue[i]) == (r.statistic, r.pvalue)
    assert bp[2].method == "Paired t-test" and bp.nobs[0] == 7


def t_logsf(t, df):
    """log P(T > t), t > 0, to 40 digits (SciPy's t.logsf is -inf out here)."""
    mpmath.mp.dps = 40
    t, df = mpmath.mpf(t), mpmath.mpf(df)
    return float(mpmath.log(mpmath.betainc(df / 2, 0.5, 0, df / (df + t * t), regularized=True) / 2))


def test_log_pvalue_where_pvalue_underflows():
    x = np.linspace(0.0, 1.0, 200)
    r = mcstat.t_test(x + 1000.0, x, equal_var=True)
    assert r.pvalue == 0.0
    want = math.log(2) + t_logsf(abs(r.statistic), r.df)
    assert math.isfinite(r.log_pvalue) and abs(r.log_pvalue - want) <= 1e-12 * abs(want)
    # greater: the upper tail; less: the lower tail, log(1 - tiny) = 0
    g = mcstat.t_test(x + 1000.0, x, equal_var=True, alternative="greater")
    assert abs(g.log_pvalue - t_logsf(g.statistic, g.df)) <= 1e-12 * abs(g.log_pvalue)
    assert mcstat.t_test(x + 1000.0, x, equal_var=True, alternative="less").log_pvalue == 0.0
    # paired, and where p is an ordinary double: its log
    p = mcstat.t_test(x + 1000.0 + np.sin(x), x, paired=True)
    assert p.pvalue == 0.0 and math.isfinite(p.log_pvalue)
    o = mcstat.t_test(x[:20] + 0.2, x[:20] + 0.05 * np.cos(x[:20] * 40), paired=True)
    assert 0 < o.pvalue < 1 and abs(o.log_pvalue - math.log(o.pvalue)) <= 1e-12 * abs(o.log_pvalue)
    # other tests: the binomial test's own, the variance tests' tails
    b = mcstat.binom_test(3, 10**9, 0.5, alternative="less")
    assert b.pvalue == 0.0 and math.isfinite(b.log_pvalue)
    v = mcstat.var_test(x * 1e3, sigma2=1e-6, alternative="greater")
    assert v.pvalue == 0.0 and math.isfinite(v.log_pvalue) and v.log_pvalue < -708


def test_ks_nan_policy_like_scipy():
    x = np.array([0.1, 0.5, np.nan, 0.7, 1.9, 0.3])
    y = np.array([0.2, 0.9, 1.3, 2.2, 0.8])
    r = mcstat.ks_test(x, y, weight="none", nan_policy="propagate")
    s = st.ks_2samp(x, y)
    assert math.isnan(s.statistic) and math.isnan(r.statistic) and math.isnan(r.pvalue)
    assert r.decision == "" and not r.reject and math.isnan(r.log_pvalue)
    assert "decision=''" in repr(r) and "NaN in the data" in str(r)
    o = mcstat.ks_test(x, y, weight="none", nan_policy="omit")
    so = st.ks_2samp(x, y, nan_policy="omit")
    assert o.statistic == so.statistic and rel_err(o.pvalue, so.pvalue) <= 1e-12
    assert o.nobs == (5, 5)
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.ks_test(x, y, weight="none")
    with pytest.raises(mcstat.InvalidArgumentError, match="nan_policy must be"):
        mcstat.ks_test(x, y, nan_policy="drop")
