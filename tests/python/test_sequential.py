"""mcstat.SequentialTest and run_until_decided.

The numbers are checked against an independent implementation of mcstat.h's
section "Sequential, anytime-valid tests" written here from the raw values with NumPy and SciPy (two-pass
moments, SciPy's normal log cdf and brentq for the one-sided boundary), at
every look of runs of each kind; then the hold, merges, errors naming
their argument, and the driver.  Calibration (the error rate under H0 over
2000 runs) is test_sequential_calibration.py's (marker ``stats``).
"""
import copy
import math

import numpy as np
import pytest
from scipy import optimize, stats

import mcstat

# ---- the oracle ---------------------------------------------------------------


def _sample(x, gate, z_ucb, min_n, on_var):
    """hold bits, n, variance UCB, n var(log s^2), n_gate from raw values."""
    n = x.size
    hold = 1 if n < min_n else 0
    if n < 2:
        return hold | 2, n, None, None
    d = x - x.mean()
    m2, m4 = float(np.sum(d * d)), float(np.sum(d ** 4))
    var = m2 / (n - 1)
    if m2 == 0 or math.sqrt(var) < 10 * np.finfo(float).eps * abs(x.mean()):
        return hold | 2, n, None, None
    b2 = n * m4 / m2 ** 2
    if gate > 0 and n < gate * b2 * (b2 if on_var else 1):
        hold |= 4
    v = var + z_ucb * math.sqrt(max(m4 / n - (m2 / n) ** 2, 0.0) / n)
    return hold, n, v, b2 - (n - 3) / (n - 1)


def _log_e(z, a, alt):
    base = 0.5 * z * z * a / (1 + a) - 0.5 * math.log1p(a)
    if alt == "two-sided":
        return base
    zz = z if alt == "greater" else -z
    return base + math.log(2) + stats.norm.logcdf(zz * math.sqrt(a / (1 + a)))


def _boundary(a, alpha, alt):
    two = math.sqrt((1 + a) / a * (-2 * math.log(alpha) + math.log1p(a)))
    if alt == "two-sided":
        return two
    return optimize.brentq(lambda z: _log_e(z, a, "greater") + math.log(alpha), 0.0, two, xtol=1e-15, rtol=1e-15)


class Oracle:
    def __init__(self, kind, null, alpha=0.05, alt="two-sided", eps=0.0, t_opt=1e4, gate=10.0, z_ucb=3.0, min_n=100):
        self.kind, self.null, self.alpha, self.alt, self.eps = kind, null, alpha, alt, eps
        self.t_opt, self.gate, self.z_ucb, self.min_n = t_opt, gate, z_ucb, min_n
        self.x, self.y = np.empty(0), np.empty(0)
        self.cs = [-math.inf, math.inf]
        self.log_e_max = -math.inf
        self.decision = "continue"

    def push(self, x, y=None):
        self.x = np.concatenate([self.x, x])
        if y is not None:
            self.y = np.concatenate([self.y, y])
        on_var = self.kind in ("var", "var2")
        hx, nx, vx, wx = _sample(self.x, self.gate, self.z_ucb, self.min_n, on_var)
        two = self.kind in ("mean2", "var2")
        hy, ny, vy, wy = _sample(self.y, self.gate, self.z_ucb, self.min_n, on_var) if two else (0, 0, 0, 0)
        self.hold = hx | hy
        if self.hold:
            self.z = math.nan
            return
        if self.kind == "mean":
            th, se, t_eff, t0 = self.x.mean(), math.sqrt(vx / nx), nx, self.null
        elif self.kind == "mean2":
            se2 = vx / nx + vy / ny
            th, se, t_eff, t0 = self.x.mean() - self.y.mean(), math.sqrt(se2), (vx + vy) / se2, self.null
        elif self.kind == "var":
            th, se, t_eff, t0 = math.log(np.var(self.x, ddof=1)), math.sqrt(wx / nx), nx, math.log(self.null)
        else:
            se2 = wx / nx + wy / ny
            th = math.log(np.var(self.x, ddof=1)) - math.log(np.var(self.y, ddof=1))
            se, t_eff, t0 = math.sqrt(se2), (wx + wy) / se2, math.log(self.null)
        a1 = self.alpha if self.alt == "two-sided" else 2 * self.alpha
        c = -2 * math.log(a1) + math.log1p(-2 * math.log(a1))
        a = t_eff * c / self.t_opt
        b = _boundary(a, self.alpha, self.alt)
        self.z = (th - t0) / se
        self.log_e = _log_e(self.z, a, self.alt)
        self.log_e_max = max(self.log_e_max, self.log_e)
        lo = th - b * se if self.alt != "less" else -math.inf
        hi = th + b * se if self.alt != "greater" else math.inf
        self.cs = [max(self.cs[0], lo), min(self.cs[1], hi)]
        if self.decision == "continue":
            if self.log_e_max >= -math.log(self.alpha):
                self.decision = {"less": "less", "greater": "greater"}.get(
                    self.alt, "less" if self.z < 0 else "greater")
            elif self.eps > 0 and t0 - self.eps < self.cs[0] and self.cs[1] < t0 + self.eps:
                self.decision = "equal"

    @property
    def conf_seq(self):
        f = math.exp if self.kind in ("var", "var2") else (lambda v: v)
        return tuple(f(v) for v in self.cs)  # a variance's open lower end is exp(-inf) = 0

    @property
    def pvalue(self):
        return math.exp(-self.log_e_max) if self.log_e_max > 0 else 1.0


CASES = [
    # kind, null, options, x law, y law
    ("mean", 0.05, dict(), lambda g, k: g.normal(0.0, 1.0, k), None),
    ("mean", 1.0, dict(alternative="greater", alpha=0.01), lambda g, k: g.exponential(1.15, k), None),
    ("mean", 1.0, dict(alternative="less", t_opt=1e3), lambda g, k: g.exponential(0.9, k), None),
    ("mean", 0.5, dict(eps=0.03), lambda g, k: g.uniform(0, 1, k), None),
    ("mean", 3.0, dict(), lambda g, k: np.where(g.uniform(size=k) < 0.05, g.exponential(60.0, k), 0.0), None),
    ("mean2", 0.0, dict(), lambda g, k: g.normal(0.1, 1.0, k), lambda g, k: g.exponential(1.0, k) - 1.0),
    ("mean2", 0.0, dict(eps=0.1, kurtosis_gate=5.0, var_ucb_z=1.0, min_n=50), lambda g, k: g.normal(0, 1, k),
     lambda g, k: g.normal(0, 2, k)),
    ("var", 1.0, dict(), lambda g, k: g.normal(0.0, 1.1, k), None),
    ("var", 1.0 / 12, dict(alternative="less"), lambda g, k: g.uniform(0, 0.95, k), None),
    ("var2", 1.0, dict(), lambda g, k: g.normal(0, 1, k), lambda g, k: g.normal(0, 1.15, k)),
    ("var2", 2.0, dict(alternative="greater"), lambda g, k: g.exponential(1.0, k), lambda g, k: g.normal(0, 1, k)),
]
_ORACLE_KW = dict(alpha="alpha", alternative="alt", eps="eps", t_opt="t_opt", kurtosis_gate="gate",
                  var_ucb_z="z_ucb", min_n="min_n")


@pytest.mark.parametrize("case", range(len(CASES)))
def test_against_oracle(case):
    kind, null, opt, gx, gy = CASES[case]
    g = np.random.default_rng(1000 + case)
    key = {"mean": "mu", "mean2": "mu", "var": "sigma2", "var2": "ratio"}[kind]
    s = mcstat.SequentialTest(kind, **{key: null}, **opt)
    o = Oracle(kind, null, **{_ORACLE_KW[k]: v for k, v in opt.items()})
    decided_at = None
    for look in range(1, 61):
        x = gx(g, 150)
        y = gy(g, 120) if gy else None
        s.push(x, y) if y is not None else s.push(x)
        o.push(x, y)
        assert s.looks == look and s.n == o.x.size
        assert s.hold == (None if s.decided or not o.hold else s.hold)
        if o.hold:
            assert math.isnan(s.statistic)
        else:
            assert s.statistic == pytest.approx(o.z, rel=1e-9, abs=1e-12)
        assert s.pvalue == pytest.approx(o.pvalue, rel=1e-8, abs=1e-300)
        assert s.conf_seq == pytest.approx(o.conf_seq, rel=1e-9, abs=1e-12)
        assert s.decision == o.decision, f"look {look}"
        if s.decided and decided_at is None:
            decided_at = s.n
    assert s.n_decided == decided_at
    # the decision stays, and reject says whether it rejected H0
    assert s.reject == (s.decision in ("less", "greater"))


def test_decides_each_way_and_equal():
    g = np.random.default_rng(7)
    for shift, want in ((0.3, "greater"), (-0.3, "less")):
        s = mcstat.SequentialTest("mean", mu=0.0)
        mcstat.run_until_decided(lambda k: g.normal(shift, 1.0, k), s, budget=100_000, batch=100)
        assert s.decision == want and s.reject and s.n < 3000
        assert s.pvalue <= 0.05 and s.result().reject
    s = mcstat.SequentialTest("mean", mu=0.0, eps=0.1)
    mcstat.run_until_decided(lambda k: g.normal(0.0, 1.0, k), s, budget=100_000, batch=100)
    assert s.decision == "equal" and not s.reject
    lo, hi = s.conf_seq
    assert -0.1 < lo < hi < 0.1


def test_hold_on_zeros_and_heavy_tails():
    s = mcstat.SequentialTest("mean", mu=1.0)
    s.push(np.zeros(100))
    assert s.hold == "no spread yet" and s.decision == "continue" and s.pvalue == 1.0
    assert s.conf_seq == (-math.inf, math.inf)
    x = np.zeros(200)
    x[[3, 150]] = 1.0  # two small values: the mean of 1 has not shown itself yet
    s.push(x)
    assert s.hold.startswith("heavy tails: the kurtosis asks for n >= ")
    with pytest.raises(mcstat.HeavyTailError, match=r"undecided after n = 300: the kurtosis asks for n >= \d+"):
        s.finish()
    # the same data without the hold and the bound: a false "less" at once
    p = mcstat.SequentialTest("mean", mu=1.0, kurtosis_gate=0.0, var_ucb_z=0.0)
    p.push(np.concatenate([np.zeros(100), x]))
    assert p.decision == "less"
    assert p.finish().decision == "less"


def test_moments_and_arrays_agree():
    g = np.random.default_rng(3)
    xs = [g.gamma(0.5, 2.0, 500) for _ in range(4)]
    a = mcstat.SequentialTest("mean", mu=1.0)
    b = mcstat.SequentialTest("mean", mu=1.0)
    for x in xs:
        a.push(x)
        halves = mcstat.Moments().push(x[:250]).merge(mcstat.Moments().push(x[250:]))
        b.push(halves)
    assert a.n == b.n == 2000 and a.looks == b.looks == 4
    assert a.statistic == pytest.approx(b.statistic, rel=1e-13)
    assert a.pvalue == pytest.approx(b.pvalue, rel=1e-12)
    st = mcstat.SequentialTest("mean", mu=1.0)
    frame = mcstat.Stream()
    for x in xs:
        frame.push(x)
    st.push(frame)  # a renderer's frame: its merged per-thread streams
    assert st.n == 2000 and st.looks == 1
    one = mcstat.SequentialTest("mean", mu=1.0).push(np.concatenate(xs))
    assert st.statistic == pytest.approx(one.statistic, rel=1e-13)
    frame.push(np.nan)
    with pytest.raises(mcstat.NonFiniteError, match="the stream x has seen NaN"):
        st.push(frame)
    assert st.n == 2000
    c = copy.copy(a)
    c.push(xs[0])
    assert c.n == 2500 and a.n == 2000


def test_result_and_text():
    s = mcstat.SequentialTest("mean2", mu=0.0, alpha=0.01)
    g = np.random.default_rng(5)
    s.push(g.normal(0, 1, 50), g.normal(0, 1, 60))
    r = s.result()
    assert r.decision == "continue" and not r.reject and r.nobs == (50, 60)
    assert r.method.startswith("Anytime-valid sequential test of the difference in means")
    assert r.pvalue_method == "asymptotic"
    text = str(s)
    assert "data:  x and y, n = 50 and 60 after 1 look\n" in text
    assert "99 percent confidence sequence:" in text
    assert "decision at alpha = 0.01: continue (held: too few values)" in text
    assert repr(s).startswith("<SequentialTest mean2: n=50, looks=1, decision=continue")
    with pytest.raises(mcstat.InvalidArgumentError):
        r.confidence_interval(0.9)  # a sequence exists only at its own level
    assert s.log_pvalue == 0.0


def test_log_pvalue_beyond_underflow():
    s = mcstat.SequentialTest("mean", mu=0.0)
    s.push(np.random.default_rng(2).normal(10.0, 1.0, 5000))
    assert s.pvalue == 0.0 and math.isfinite(s.log_pvalue) and s.log_pvalue < -1000


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(kind="median"), "kind must be"),
        (dict(kind="var"), "kind \"var\" needs sigma2"),
        (dict(kind="var", sigma2=-1.0), "sigma2 must be > 0"),
        (dict(kind="var2", ratio=0.0), "ratio must be > 0"),
        (dict(kind="var", sigma2=1.0, mu=0.0), "mu does not apply"),
        (dict(kind="mean", ratio=2.0), "ratio does not apply"),
        (dict(mu=math.nan), "mu must be finite"),
        (dict(alpha=1.5), r"alpha must be in \(0, 1\)"),
        (dict(alpha=0.0), r"alpha must be in \(0, 1\)"),
        (dict(eps=-0.1), "eps must be >= 0"),
        (dict(eps=0.1, alternative="less"), "eps needs alternative"),
        (dict(kind="var", sigma2=1.0, eps=0.1), "eps .* does not apply"),
        (dict(t_opt=0.0), "t_opt must be > 0"),
        (dict(t_opt=math.inf), "t_opt must be finite"),
        (dict(kurtosis_gate=-1.0), "kurtosis_gate must be >= 0"),
        (dict(var_ucb_z=math.nan), "var_ucb_z must be finite"),
        (dict(min_n=1), "min_n must be >= 2"),
        (dict(min_n=-(2 ** 70)), "min_n must be >= 2"),
        (dict(alternative="bigger"), "alternative"),
    ],
)
def test_bad_arguments(kwargs, match):
    with pytest.raises(mcstat.InvalidArgumentError, match=match):
        mcstat.SequentialTest(**kwargs)


def test_bad_types_and_pushes():
    with pytest.raises(TypeError, match="kind must be a str"):
        mcstat.SequentialTest(3)
    with pytest.raises(TypeError, match="min_n must be an int"):
        mcstat.SequentialTest(min_n=2.5)
    s = mcstat.SequentialTest("mean")
    s.push([1.0, 2.0, 3.0])
    with pytest.raises(mcstat.NonFiniteError, match="x contains NaN"):
        s.push([1.0, math.nan])
    with pytest.raises(mcstat.NonFiniteError):
        s.push([math.inf])
    assert s.n == 3 and s.looks == 1  # refused batches are not added
    with pytest.raises(mcstat.InvalidArgumentError, match="takes one batch"):
        s.push([1.0], [2.0])
    t = mcstat.SequentialTest("mean2")
    with pytest.raises(mcstat.InvalidArgumentError, match=r"push\(x, y\)"):
        t.push([1.0])
    with pytest.raises(mcstat.NonFiniteError, match="y contains NaN"):
        t.push([1.0], [math.nan])
    t.push([], [1.0, 2.0])  # an empty batch is a look with nothing new
    assert t.n == 0 and t.n_y == 2 and t.looks == 1


def test_run_until_decided_budget_and_errors(capsys):
    g = np.random.default_rng(11)
    s = mcstat.SequentialTest("mean", mu=0.0)
    out = mcstat.run_until_decided(lambda k: g.normal(0.0, 1.0, k), s, budget=1050, batch=100, progress=True)
    assert out is s and s.n == 1050 and s.looks == 11 and not s.decided  # the last batch is cut to the budget
    assert capsys.readouterr().err  # tqdm's bar or the plain line, on stderr
    assert s.finish().decision == "continue"
    t = mcstat.SequentialTest("var2")
    mcstat.run_until_decided(lambda k: (g.normal(0, 1, k), g.normal(0, 1.5, k)), t, budget=200_000, batch=500)
    assert t.decision == "less"
    with pytest.raises(TypeError, match=r"must return a pair \(x, y\)"):
        mcstat.run_until_decided(lambda k: g.normal(size=k), mcstat.SequentialTest("mean2"), budget=10)
    with pytest.raises(TypeError, match="test must be a mcstat.SequentialTest"):
        mcstat.run_until_decided(lambda k: g.normal(size=k), "mean", budget=10)
    with pytest.raises(TypeError, match="budget must be an int"):
        mcstat.run_until_decided(lambda k: g.normal(size=k), mcstat.SequentialTest(), budget=1e6)
    with pytest.raises(mcstat.InvalidArgumentError, match="batch must be >= 1"):
        mcstat.run_until_decided(lambda k: g.normal(size=k), mcstat.SequentialTest(), budget=10, batch=0)
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.run_until_decided(lambda k: np.full(k, np.nan), mcstat.SequentialTest(), budget=10)
