"""check_gradient: a gradient estimator against central differences (or a
reference) of the same loss, over seeds with common random numbers.

Oracle numbers against SciPy on fixed data; analytic Monte Carlo gradient
problems in NumPy with a planted missing term (caught at >= 18 of 20
seeds) and the correct gradient's rejection rate judged by the battery
meta-test; bad input for every argument.  Deterministic (fixed seeds)."""
import math

import numpy as np
import pytest

import mcstat

scipy_stats = pytest.importorskip("scipy.stats")


# ---- analytic problems ----------------------------------------------------------------
# A. Product rule through a reparameterised sampler: X = theta + SIG Z,
#    loss theta cos X, E = theta cos(theta) exp(-SIG^2/2).  The planted
#    gradient drops the derivative of the explicit factor theta (cos X).
SIG, M_A = 0.5, 8


def _z(seed, m=M_A):
    return np.random.default_rng(seed).standard_normal(m)


def loss_a(theta, seed):
    x = theta + SIG * _z(seed)
    return float(np.mean(theta * np.cos(x)))


def grad_a(theta, planted=False):
    def grad(seed):
        x = theta + SIG * _z(seed)
        g = -theta * np.sin(x)
        return float(np.mean(g if planted else np.cos(x) + g))
    return grad


# B. A discontinuity: loss 1{U < theta} (1 + U) + theta U, U uniform,
#    E = theta + theta^2/2 + theta/2, derivative 1.5 + theta.  The pathwise
#    gradient (U) misses the boundary term (1 + theta), which the correct
#    estimator adds (as edge sampling does).  The finite differences are
#    noisy (the indicator jumps inside [theta - h, theta + h]).
M_B = 16


def _u(seed, m=M_B):
    return np.random.default_rng(seed).random(m)


def loss_b(theta, seed):
    u = _u(seed)
    return float(np.mean((u < theta) * (1 + u) + theta * u))


def grad_b(theta, planted=False):
    def grad(seed):
        u = _u(seed)
        return float(np.mean(u)) + (0.0 if planted else 1.0 + theta)
    return grad


# C. Two parameters: X = a + b Z, loss a cos X; d/da = cos X - a sin X,
#    d/db = -a Z sin X.  The planted gradient drops cos X from d/da only.
def loss_c(theta, seed):
    a, b = theta
    x = a + b * _z(seed)
    return float(np.mean(a * np.cos(x)))


def grad_c(theta, planted=False):
    a, b = theta

    def grad(seed):
        z = _z(seed)
        x = a + b * z
        da = -a * np.sin(x) + (0.0 if planted else np.cos(x))
        return [float(np.mean(da)), float(np.mean(-a * z * np.sin(x)))]
    return grad


THETA_C = np.array([0.7, 0.5])


# ---- oracle ---------------------------------------------------------------------------------


def _oracle(d, margin, alpha):
    n = d.size
    mean, se = d.mean(), d.std(ddof=1) / math.sqrt(n)
    t = scipy_stats.t(n - 1)
    p_plus = t.sf((mean - margin) / se)
    p_minus = t.cdf((mean + margin) / se)
    q = t.ppf(1 - alpha / 2)
    return mean, se, (mean - q * se, mean + q * se), min(1.0, 2 * min(p_plus, p_minus)), (p_plus, p_minus)


def test_oracle_interval_and_pvalues_match_scipy():
    rng = np.random.default_rng(7)
    g = rng.normal(1.0, 0.3, size=40)
    r = g - rng.normal(0.08, 0.1, size=40)  # differences of mean about 0.08
    for margin in (0.0, 0.02, 0.05, 0.2):
        rep = mcstat.check_gradient(g, reference=r, margin=margin, alpha=0.05)
        p = rep.parameters[0]
        mean, se, ci, pv, pvs = _oracle(g - r, margin, 0.05)
        assert p.mean_diff == pytest.approx(mean, rel=1e-12)
        assert p.std_error == pytest.approx(se, rel=1e-10)
        assert p.conf_int == pytest.approx(ci, rel=1e-10)
        assert p.pvalue == pytest.approx(pv, rel=1e-9, abs=1e-300)
        assert p.pvalues == pytest.approx(pvs, rel=1e-9, abs=1e-300)
        assert p.pvalue_adjusted == p.pvalue and rep.alpha_test == 0.05 and rep.n_bounds == 0
        # reject exactly when the interval lies outside the margin
        assert rep.reject == (ci[0] > margin or ci[1] < -margin)
        assert p.margin == margin and p.bias is None
        # detectable: margin + (t(1 - alpha/2) + t(0.8)) se
        t = scipy_stats.t(39)
        assert p.detectable == pytest.approx(margin + (t.ppf(0.975) + t.ppf(0.8)) * se, rel=1e-9)
    assert mcstat.check_gradient(g, reference=r, margin=0.0).reject
    assert not mcstat.check_gradient(g, reference=r, margin=0.2).reject


def test_oracle_richardson_and_rtol_bounds_match_scipy():
    rng = np.random.default_rng(11)
    n = 30
    g = rng.normal(2.0, 0.2, size=(n, 2))
    r = g + rng.normal(0.0, 0.05, size=(n, 2))
    r2 = r + 3 * rng.normal(0.01, 0.02, size=(n, 2))  # Richardson term of mean about 0.01
    rep = mcstat.check_gradient(g, reference=r, reference_2h=r2, margin=[0.01, 0.0], rtol=0.01,
                                alpha=0.1, bound_share=0.25, adjust="bonferroni")
    assert rep.richardson and rep.n_bounds == 4 and rep.richardson_factor == 2.0
    assert rep.alpha_bounds == pytest.approx(0.025) and rep.alpha_test == pytest.approx(0.075)
    a_b = 0.025 / 4
    t = scipy_stats.t(n - 1)
    ps = []
    for j, p in enumerate(rep.parameters):
        rr = (r2[:, j] - r[:, j]) / 3
        q = t.ppf(1 - a_b / 2)
        se_r = rr.std(ddof=1) / math.sqrt(n)
        bias_bound = 2 * max(abs(rr.mean() - q * se_r), abs(rr.mean() + q * se_r))
        se_ref = r[:, j].std(ddof=1) / math.sqrt(n)
        ref_bound = abs(r[:, j].mean()) + q * se_ref
        assert p.bias == pytest.approx(rr.mean(), rel=1e-12)
        assert p.bias_bound == pytest.approx(bias_bound, rel=1e-9)
        assert p.ref_bound == pytest.approx(ref_bound, rel=1e-9)
        m = [0.01, 0.0][j] + 0.01 * ref_bound + bias_bound
        assert p.margin == pytest.approx(m, rel=1e-12)
        mean, se, ci, pv, _ = _oracle(g[:, j] - r[:, j], m, 0.075)
        assert p.conf_int == pytest.approx(ci, rel=1e-9) and p.pvalue == pytest.approx(pv, rel=1e-9)
        ps.append(pv)
        t_b = scipy_stats.t(n - 1)
        assert p.detectable == pytest.approx(m + (t_b.ppf(1 - 0.075 / 4) + t_b.ppf(0.8)) * se, rel=1e-9)
    for p, pv in zip(rep.parameters, ps):
        assert p.pvalue_adjusted == pytest.approx(min(1.0, 2 * pv), rel=1e-12)


def test_holm_across_parameters():
    rng = np.random.default_rng(3)
    g = rng.normal(0, 1, size=(50, 3))
    r = g - rng.normal([0.0, 0.4, 1.0], 0.5, size=(50, 3))
    rep = mcstat.check_gradient(g, reference=r, names=["x", "y", "z"])
    raw = np.array([p.pvalue for p in rep])
    want = np.minimum(1, np.maximum.accumulate(np.sort(raw) * [3, 2, 1]))[np.argsort(np.argsort(raw))]
    assert [p.pvalue_adjusted for p in rep] == pytest.approx(list(want), rel=1e-12)
    assert rep.reject and rep.parameter("z").reject and not rep.parameter("x").reject
    assert rep.parameter(2) is rep.parameter("z") and len(rep) == 3
    text = str(rep)
    assert "Holm-adjusted" in text and "inconsistent" in text and "z" in text.splitlines()[-1]


def test_constant_differences_are_decided_exactly():
    g = np.linspace(0, 1, 10)
    rep = mcstat.check_gradient(g, reference=g - 0.5, margin=0.1)
    assert rep.reject and rep.parameters[0].exact and rep.pvalue == 0.0 and "decided exactly" in str(rep)
    rep = mcstat.check_gradient(g, reference=g - 0.05, margin=0.1)
    assert not rep.reject and rep.parameters[0].exact and rep.pvalue == 1.0
    # a linear loss: FD equals the gradient up to rounding, FD(2h) too
    rep = mcstat.check_gradient(lambda s: 2.0, lambda th, s: 2.0 * th + s, 0.3, h=1e-3, n=5)
    assert not rep.reject


# ---- analytic problems: power and calibration --------------------------------------------------


def test_product_rule_planted_caught_correct_passes():
    caught = sum(mcstat.check_gradient(grad_a(0.7, True), loss_a, 0.7, h=1e-2, n=16, seed=100 * c).reject
                 for c in range(20))
    assert caught >= 18
    rep = mcstat.check_gradient(grad_a(0.7), loss_a, 0.7, h=1e-2, n=16)
    assert not rep.reject and rep.richardson
    # the FD bias is resolved: Richardson's estimate about -(E d)
    p = rep.parameters[0]
    assert p.bias == pytest.approx(-p.mean_diff, rel=0.2) and abs(p.mean_diff) <= p.margin


def test_without_richardson_the_fd_bias_itself_is_detected():
    """Common random numbers make the differences nearly deterministic, so
    the central difference's O(h^2) bias is resolved: margin 0 without the
    Richardson bound rejects the correct gradient (why the bound is on by
    default with f)."""
    rejected = sum(mcstat.check_gradient(grad_a(0.7), loss_a, 0.7, h=1e-2, n=8, seed=8 * c,
                                         richardson=False).reject for c in range(20))
    assert rejected == 20


def test_boundary_term_planted_caught():
    caught = sum(mcstat.check_gradient(grad_b(0.5, True), loss_b, 0.5, h=0.05, n=64, seed=1000 * c).reject
                 for c in range(20))
    assert caught >= 18


def test_two_parameters_planted_names_the_parameter():
    reps = [mcstat.check_gradient(grad_c(THETA_C, True), loss_c, THETA_C, h=[1e-2, 1e-2], n=16,
                                  seed=100 * c, names=["a", "b"]) for c in range(20)]
    assert sum(r.reject for r in reps) >= 18
    assert sum(r.parameter("b").reject for r in reps) <= 2
    rep = mcstat.check_gradient(grad_c(THETA_C), loss_c, THETA_C, h=1e-2, n=16, adjust="bonferroni")
    assert not rep.reject and rep.n_bounds == 2 and "Bonferroni-adjusted" in str(rep)


def _battery_ok(rejected, runs, alpha):
    meta = mcstat.battery_test(rejected, alpha, n=runs, alternative="greater", meta_alpha=0.001)
    return not meta.reject


def test_calibration_correct_gradients():
    """400 checks of each correct gradient at alpha = 0.05 (product rule,
    boundary term, two parameters): rejections not significantly above 5%
    (battery meta-test at 0.001)."""
    runs, counts = 400, {}
    counts["A"] = sum(mcstat.check_gradient(grad_a(0.7), loss_a, 0.7, h=1e-2, n=8, seed=10_000 + 8 * c).reject
                      for c in range(runs))
    counts["B"] = sum(mcstat.check_gradient(grad_b(0.5), loss_b, 0.5, h=0.05, n=16, seed=20_000 + 16 * c).reject
                      for c in range(runs))
    counts["C"] = sum(mcstat.check_gradient(grad_c(THETA_C), loss_c, THETA_C, h=1e-2, n=8,
                                            seed=40_000 + 8 * c).reject for c in range(runs))
    for name, rejected in counts.items():
        assert _battery_ok(rejected, runs, 0.05), (name, rejected, runs)


def test_calibration_at_the_margin_is_alpha_over_two():
    """Normal differences whose mean is exactly the margin: one side rejects
    at rate alpha/2 (the size is attained, not just bounded), judged
    two-sided against alpha/2."""
    rng = np.random.default_rng(5)
    runs, n, margin = 2000, 12, 0.3
    d = rng.normal(margin, 1.0, size=(runs, n))
    rejected = sum(mcstat.check_gradient(d[c], reference=np.zeros(n), margin=margin).reject for c in range(runs))
    meta = mcstat.battery_test(rejected, 0.025, n=runs, meta_alpha=0.001)
    assert not meta.reject, rejected


# ---- the report ------------------------------------------------------------------------------


def test_report_text_and_fields():
    rep = mcstat.check_gradient(grad_a(0.7, True), loss_a, 0.7, h=1e-2, n=16)
    text = str(rep)
    for want in ("Gradient check", "n = 16 seeds", "h = 0.01", "Richardson bias", "96 percent CI",
                 "p-value", "probability 0.8", "decision at alpha = 0.05: inconsistent"):
        assert want in text, want
    assert rep.grad.shape == (16, 1) and rep.ref.shape == (16, 1) and rep.ref_2h.shape == (16, 1)
    assert rep.method == "finite difference" and rep.h == (0.01,) and rep.n == 16
    assert "GradientReport(reject=True" in repr(rep) and "GradientParameter(" in repr(rep.parameters[0])
    assert isinstance(rep, mcstat.GradientReport) and isinstance(rep.parameters[0], mcstat.GradientParameter)
    assert {"check_gradient", "GradientReport", "GradientParameter"} <= set(mcstat.__all__)


def test_callable_reference_and_seeds():
    # reference: the same derivative by another estimator (independent per seed)
    def ref(seed):
        return float(np.mean(np.cos(0.7 + SIG * _z(seed + 10**6)) - 0.7 * np.sin(0.7 + SIG * _z(seed + 10**6))))
    rep = mcstat.check_gradient(grad_a(0.7), reference=ref, seeds=range(5, 45))
    assert rep.n == 40 and rep.method == "reference" and not rep.richardson and not rep.reject
    seen = []
    mcstat.check_gradient(lambda s: seen.append(s) or 1.0, reference=lambda s: 1.0 + 0.01 * (s % 3), n=4, seed=9)
    assert seen == [9, 10, 11, 12]
    # theta as an array goes to f as an array, a float as a float
    types = set()
    mcstat.check_gradient(lambda s: [1.0], lambda th, s: types.add(type(th)) or float(np.sum(th)) + 0.1 * s,
                          [0.5], h=0.1, n=3)
    mcstat.check_gradient(lambda s: 1.0, lambda th, s: types.add(type(th)) or th + 0.1 * s, 0.5, h=0.1, n=3)
    assert types == {np.ndarray, float}


# ---- bad input ----------------------------------------------------------------------------------


GOOD = dict(grad=grad_a(0.7), f=loss_a, theta=0.7)


def call(**kw):
    args = dict(GOOD, h=1e-2, n=4)
    args.update(kw)
    return mcstat.check_gradient(args.pop("grad"), **args)


@pytest.mark.parametrize("bad", [0.0, 1.0, -0.1, float("nan"), 2])
def test_bad_alpha(bad):
    with pytest.raises(mcstat.InvalidArgumentError, match="alpha must be in"):
        call(alpha=bad)


def test_bad_arguments():
    E = mcstat.InvalidArgumentError
    with pytest.raises(TypeError, match="alpha must be a real"):
        call(alpha="0.05")
    for bad in (0.0, 1.0, float("nan")):
        with pytest.raises(E, match="bound_share"):
            call(bound_share=bad)
    for bad in (0.0, -1e-3, float("inf"), float("nan")):
        with pytest.raises(E, match="h must be finite and > 0"):
            call(h=bad)
    with pytest.raises(E, match="h must be a scalar or have 1"):
        call(h=[0.1, 0.1])
    with pytest.raises(TypeError, match="h must be a real"):
        call(h="x")
    with pytest.raises(E, match=r"h\[0\] = 1e-30 vanishes"):
        call(h=1e-30)
    for bad in (-0.1, float("inf"), float("nan")):
        with pytest.raises(E, match="margin must be finite and >= 0"):
            call(margin=bad)
    with pytest.raises(E, match="margin must be a scalar or have 1"):
        call(margin=[0.1, 0.2])
    for bad in (-0.1, float("nan")):
        with pytest.raises(E, match="rtol must be finite"):
            call(rtol=bad)
    for bad in (0.5, float("inf")):
        with pytest.raises(E, match="richardson_factor must be finite and >= 1"):
            call(richardson_factor=bad)
    with pytest.raises(E, match="adjust must be 'holm' or 'bonferroni'"):
        call(adjust="BH")
    with pytest.raises(TypeError, match="adjust must be a string"):
        call(adjust=1)
    with pytest.raises(TypeError, match="richardson must be"):
        call(richardson="yes")
    with pytest.raises(E, match="names has 2 entries"):
        call(names=["a", "b"])


def test_bad_n_and_seeds():
    for n in (0, 1):
        with pytest.raises(mcstat.TooFewObservationsError, match="at least 2 seeds"):
            call(n=n)
    with pytest.raises(TypeError, match="n must be an integer"):
        call(n=4.0)
    with pytest.raises(TypeError, match="seed must be an integer"):
        call(seed=0.5)
    with pytest.raises(TypeError, match="seeds must be integers"):
        call(seeds=[1, 2.5])
    with pytest.raises(mcstat.InvalidArgumentError, match="seeds must be distinct"):
        call(seeds=[1, 2, 2])
    with pytest.raises(mcstat.TooFewObservationsError):
        call(seeds=[3])


def test_bad_f_theta_reference_combinations():
    E = mcstat.InvalidArgumentError
    with pytest.raises(E, match="either f .* or reference, not neither"):
        mcstat.check_gradient(grad_a(0.7))
    with pytest.raises(E, match="not both"):
        mcstat.check_gradient(grad_a(0.7), loss_a, 0.7, h=0.1, reference=lambda s: 1.0)
    with pytest.raises(E, match="f needs theta and h"):
        mcstat.check_gradient(grad_a(0.7), loss_a, 0.7)
    with pytest.raises(E, match="theta and h are for f"):
        mcstat.check_gradient(grad_a(0.7), reference=lambda s: 1.0, h=0.1)
    with pytest.raises(E, match="reference_2h is for a reference"):
        call(reference_2h=lambda s: 1.0)
    with pytest.raises(TypeError, match="f must be a callable"):
        call(f=3.0)
    with pytest.raises(TypeError, match="theta must be a real"):
        call(theta="abc")
    with pytest.raises(TypeError, match="theta must be a real"):
        call(theta=True)
    with pytest.raises(E, match="theta must be finite"):
        call(theta=float("nan"))
    with pytest.raises(E, match="theta must be a scalar or 1-D"):
        call(theta=np.zeros((2, 2)))
    with pytest.raises(E, match="theta is empty"):
        call(theta=[])
    with pytest.raises(E, match="reference must be a callable"):
        mcstat.check_gradient(grad_a(0.7), reference=np.ones(4))
    with pytest.raises(E, match="richardson=True needs reference_2h"):
        mcstat.check_gradient(grad_a(0.7), reference=lambda s: 1.0, richardson=True)
    with pytest.raises(TypeError, match="grad must be a callable"):
        mcstat.check_gradient(None, reference=np.ones(4))


def test_bad_arrays():
    E = mcstat.InvalidArgumentError
    g = np.ones(5) + np.arange(5)
    with pytest.raises(E, match="reference has shape"):
        mcstat.check_gradient(g, reference=np.ones(4))
    with pytest.raises(E, match="reference_2h has shape"):
        mcstat.check_gradient(g, reference=g, reference_2h=np.ones((5, 2)))
    with pytest.raises(mcstat.NonFiniteError, match="grad holds a non-finite"):
        mcstat.check_gradient(np.r_[g[:4], np.nan], reference=g)
    with pytest.raises(mcstat.NonFiniteError, match="reference holds a non-finite"):
        mcstat.check_gradient(g, reference=np.r_[g[:4], np.inf])
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.check_gradient(g[:1], reference=g[:1])
    with pytest.raises(E, match=r"shape \(n,\) or \(n, k\)"):
        mcstat.check_gradient(np.ones((2, 2, 2)), reference=np.ones((2, 2, 2)))
    with pytest.raises(TypeError, match="grad must be an array"):
        mcstat.check_gradient("abc", reference=g)
    with pytest.raises(TypeError, match="reference must be an array"):
        mcstat.check_gradient(g, reference=[object()] * 5)
    with pytest.raises(E, match="reference must be an array too"):
        mcstat.check_gradient(g, reference=lambda s: 1.0)
    with pytest.raises(E, match="not f"):
        mcstat.check_gradient(g, loss_a, 0.7, h=0.1)
    with pytest.raises(E, match="seeds are for callables"):
        mcstat.check_gradient(g, reference=g, seeds=range(5))
    with pytest.raises(E, match="richardson=True needs reference_2h"):
        mcstat.check_gradient(g, reference=g, richardson=True)


def test_callbacks_returning_garbage():
    C = mcstat.CallbackError
    with pytest.raises(C, match=r"grad\(0\) returned a non-finite"):
        call(grad=lambda s: float("nan"))
    with pytest.raises(C, match=r"grad\(0\) returned str"):
        call(grad=lambda s: "x")
    with pytest.raises(C, match=r"grad\(0\) returned 2 value\(s\); expected 1"):
        call(grad=lambda s: [1.0, 2.0])
    with pytest.raises(C, match=r"grad\(0\) returned an array of shape \(2, 2\)"):
        call(grad=lambda s: np.ones((2, 2)))
    with pytest.raises(C, match=r"grad\(0\) returned no values"):
        mcstat.check_gradient(lambda s: [], reference=lambda s: [], n=3)
    with pytest.raises(C, match=r"f\(theta=0.71, seed=0\) returned a non-finite"):
        call(f=lambda th, s: float("inf"))
    with pytest.raises(C, match="returned 3 values .* one real number"):
        call(f=lambda th, s: [1.0, 2.0, 3.0])
    with pytest.raises(C, match=r"f\(theta=0.71, seed=0\) returned NoneType"):
        call(f=lambda th, s: None)
    with pytest.raises(C, match=r"reference\(1\) returned a non-finite"):
        mcstat.check_gradient(lambda s: 1.0, reference=lambda s: float("nan") if s == 1 else 1.0, n=3)
    with pytest.raises(C, match=r"reference\(0\) returned 2 value"):
        mcstat.check_gradient(lambda s: 1.0, reference=lambda s: [1.0, 1.0], n=3)
    with pytest.raises(C, match="overflowed"):
        call(f=lambda th, s: 1e308 * (1 if th > 0.7 else -1), h=1e-3)

    def boom(seed):
        raise RuntimeError("renderer failed")
    with pytest.raises(RuntimeError, match="renderer failed"):
        call(grad=boom)


def test_richardson_factor_covers_an_opposing_next_term():
    """sin: the central difference's bias is -cos h^2/6 + cos h^4/120, so
    Richardson's term (c2 h^2 + 5 c4 h^4) underestimates it by about h^2/5;
    common random numbers resolve that, and factor 1 rejects the correct
    gradient at every seed while the default 2 covers it."""
    def loss(theta, seed):
        return math.sin(theta + 0.01 * _z(seed, 1)[0])

    def grad(seed):
        return math.cos(0.4 + 0.01 * _z(seed, 1)[0])
    one = sum(mcstat.check_gradient(grad, loss, 0.4, h=0.3, n=16, seed=16 * c, richardson_factor=1.0).reject
              for c in range(20))
    two = sum(mcstat.check_gradient(grad, loss, 0.4, h=0.3, n=16, seed=16 * c).reject for c in range(20))
    assert one == 20 and two == 0
