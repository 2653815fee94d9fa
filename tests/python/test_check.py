"""The renderer checks from Python: mcstat.check_bsdf, check_emitter,
check_warp.  The statistics themselves are libmcstat's (tests/c/test_check.c
checks them and their calibration); here: the binding's contract, planted
bugs through vectorised NumPy callables, bad callables and arguments, and
(stats suite) the battery's rejection rate on correct models against alpha.
"""
import math

import numpy as np
import pytest

import mcstat


def _frame(r):
    s = math.copysign(1.0, r[2])
    a = -1.0 / (s + r[2])
    b = r[0] * r[1] * a
    return np.array([1 + s * r[0] ** 2 * a, s * b, -s * r[0]]), np.array([b, s + r[1] ** 2 * a, -r[1]])


class Lobe:
    """cos^e lobe around the mirror direction of wi, albedo 0.8 where it is
    above the horizon; the sampler fails (pdf 0, weight 0) below it.  One
    planted ~10% bug per class."""

    def __init__(self, e, wi, bug=None):
        self.e, self.bug = e, bug
        r = np.array([-wi[0], -wi[1], wi[2]], dtype=float)
        self.r = r / np.linalg.norm(r)
        self.t1, self.t2 = _frame(self.r)

    def density(self, e, x):
        c = x @ self.r
        return np.where((x[:, 2] > 0) & (c > 0), (e + 1) / (2 * np.pi) * np.maximum(c, 0.0) ** e, 0.0)

    def sample(self, wi, u):
        e = self.e / 1.1 if self.bug == "sampler" else self.e
        c = u[:, 0] ** (1 / (e + 1))
        s = np.sqrt(np.maximum(0.0, 1 - c * c))
        phi = 2 * np.pi * u[:, 1]
        x = c[:, None] * self.r + s[:, None] * (np.cos(phi)[:, None] * self.t1 + np.sin(phi)[:, None] * self.t2)
        p = self.density(self.e, x)
        w = np.where(p > 0, 0.8, 0.0) * (1.1 if self.bug == "weight" else 1.0)
        return x, w, p

    def pdf(self, wi, x):
        return self.density(self.e * 1.1 if self.bug == "pdf" else self.e, x)

    def eval(self, wi, x):
        v = 0.8 * self.density(self.e, x)
        return v * np.where(x[:, 0] > 0, 1.1, 1.0) if self.bug == "eval" else v


WI = np.array([0.5, 0.1, 0.86])


def check(model, **kw):
    return mcstat.check_bsdf(model.sample, model.eval, model.pdf, WI, **kw)


def test_correct_lobe_passes_and_reports():
    r = check(Lobe(40, WI), seed=1)
    assert not r.reject
    assert r.kind == "bsdf" and r.domain == "sphere" and r.n == 100_000
    assert [x.name for x in r.routes] == ["cells", "mass", "pdf_value", "weight", "support", "integrals",
                                          "energy", "reciprocity", "ks"]
    cells = r.route("cells")
    assert cells.state == "ran" and cells.df > 8 and 0 < cells.pvalue <= 1
    assert cells.p_adjusted >= cells.pvalue
    assert r.route("reciprocity").state == "skipped"
    assert r.route("weight").deterministic and r.route("weight").count == 0
    assert abs(r.mass - 1) < 1e-3 and r.mass_error < 1e-3
    assert r.albedo == pytest.approx(0.8, abs=1e-12)
    assert abs(r.albedo_eval - 0.8) < 5 * r.albedo_eval_se
    text = str(r)
    assert "BSDF check" in text and "decision at alpha = 0.01: consistent" in text
    for name in ("cells", "mass", "integrals"):
        assert name in text
    assert r.route("cells").meaning.startswith("sample() draws")
    assert "constant factor" in r.route("cells").blind_spot
    with pytest.raises(TypeError, match="truth value"):
        bool(r)


@pytest.mark.parametrize(
    "bug, route",
    [("sampler", "cells"), ("pdf", "pdf_value"), ("eval", "weight"), ("weight", "weight")],
)
def test_planted_bugs_are_caught_by_their_route(bug, route):
    r = check(Lobe(40, WI, bug), seed=1)
    assert r.reject and r.route(route).reject, str(r)
    if r.route(route).deterministic:
        assert r.pvalue == 0.0
        assert "INCONSISTENT" in str(r) and route in str(r)


def test_results_do_not_depend_on_the_batch():
    a, b = check(Lobe(20, WI), seed=3, n=5000), check(Lobe(20, WI), seed=3, n=5000, batch=64)
    assert str(a) == str(b)
    assert b.calls > a.calls


def test_weight_value_convention():
    m = Lobe(20, WI)

    def sample_value(wi, u):
        x, w, p = m.sample(wi, u)
        return x, w * p, p  # the value f|cos|, pbrt's convention

    value = mcstat.check_bsdf(sample_value, m.eval, m.pdf, WI, weight="value", n=5000)
    over = mcstat.check_bsdf(m.sample, m.eval, m.pdf, WI, n=5000)
    assert value.route("weight").state == "ran" and value.route("weight").count == 0
    assert value.albedo == pytest.approx(over.albedo, rel=1e-14)
    assert value.route("integrals").statistic == pytest.approx(over.route("integrals").statistic, rel=1e-9)


def test_stochastic_weights_use_the_integrals_route():
    m = Lobe(40, WI)

    def noisy(bias):
        def sample(wi, u):
            x, w, p = m.sample(wi, u)
            return x, w * 2 * u[:, 2] * bias, p

        return sample

    ok = mcstat.check_bsdf(noisy(1.0), m.eval, m.pdf, WI, stochastic=True, seed=1)
    assert not ok.reject
    assert ok.route("weight").state == "skipped" and ok.route("pdf_value").state == "skipped"
    bad = mcstat.check_bsdf(noisy(1.05), m.eval, m.pdf, WI, stochastic=True, seed=1)
    assert bad.reject and bad.route("integrals").reject


def test_routes_and_energy_selection():
    r = check(Lobe(20, WI), n=5000, routes=["cells", "mass"])
    assert [x.name for x in r.routes if x.state == "ran"] == ["cells", "mass"]
    with pytest.raises(mcstat.InvalidArgumentError):
        check(Lobe(20, WI), n=5000, routes=[])
    r = check(Lobe(20, WI), n=5000, energy=False)
    assert r.route("energy").state == "skipped"
    # a route asked for by its flag but left out of routes is refused, not silently skipped
    with pytest.raises(mcstat.InvalidArgumentError, match=r"^reciprocal=True asks for the 'reciprocity' route"):
        check(Lobe(20, WI), n=5000, routes=["cells"], reciprocal=True)
    with pytest.raises(mcstat.InvalidArgumentError, match=r"^energy=True asks for the 'energy' route"):
        check(Lobe(20, WI), n=5000, routes=["cells"], energy=True)
    r = check(Lobe(20, WI), n=5000, routes=["cells", "energy"], energy=True)
    assert r.route("energy").state == "ran"


def test_reciprocity():
    # a Lambertian BSDF is reciprocal; one whose eval depends on wi.z alone is not
    def sample(wi, u):
        r = np.sqrt(u[:, 0])
        phi = 2 * np.pi * u[:, 1]
        x = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(1 - u[:, 0])], axis=1)
        return x, np.full(len(u), 0.7), x[:, 2] / np.pi

    def pdf(wi, x):
        return np.maximum(x[:, 2], 0) / np.pi

    def eval_ok(wi, x):
        return 0.7 / np.pi * np.maximum(x[:, 2], 0)

    def eval_bad(wi, x):
        return 0.7 / np.pi * np.maximum(x[:, 2], 0) * (1 + 0.2 * (wi[2] - 0.6))

    wi = np.array([0.0, 0.8, 0.6])
    r = mcstat.check_bsdf(sample, eval_ok, pdf, wi, domain="hemisphere", reciprocal=True, n=5000)
    assert not r.reject and r.route("reciprocity").state == "ran" and r.route("reciprocity").checked == 1000
    r = mcstat.check_bsdf(sample, eval_bad, pdf, wi, domain="hemisphere", reciprocal=True, n=5000)
    assert r.route("reciprocity").reject


# ---- warps and emitters ----------------------------------------------------------


def test_warps():
    disk = lambda u: np.stack([np.sqrt(u[:, 0]) * np.cos(2 * np.pi * u[:, 1]),
                               np.sqrt(u[:, 0]) * np.sin(2 * np.pi * u[:, 1])], axis=1)  # noqa: E731
    disk_bad = lambda u: disk(np.stack([u[:, 0] ** 1.1, u[:, 1]], axis=1))  # noqa: E731
    disk_pdf = lambda x: np.where((x ** 2).sum(axis=1) <= 1, 1 / np.pi, 0.0)  # noqa: E731
    r = mcstat.check_warp(disk, disk_pdf, domain="disk", n=20000)
    assert r.kind == "warp" and not r.reject and abs(r.mass - 1) < 1e-9
    assert mcstat.check_warp(disk_bad, disk_pdf, domain="disk", n=20000).route("cells").reject
    # the interval: (k,) arrays in and out; a pdf that does not integrate to 1
    r = mcstat.check_warp(lambda u: u[:, 0] ** 2, lambda x: 0.5 / np.sqrt(x), domain="interval", n=20000)
    assert not r.reject
    r = mcstat.check_warp(lambda u: u[:, 0] ** 2, lambda x: 0.55 / np.sqrt(x), domain="interval", n=20000)
    assert r.reject and r.route("mass").reject


def test_emitter_spherical_cap():
    # a light of radiance 2 seen as a cone of half-angle 0.3 around +z: uniform cone sampling
    cos_max = math.cos(0.3)
    solid = 2 * np.pi * (1 - cos_max)

    def sample(u, pdf_scale=1.0):
        z = 1 - u[:, 0] * (1 - cos_max)
        s = np.sqrt(np.maximum(0, 1 - z * z))
        phi = 2 * np.pi * u[:, 1]
        d = np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=1)
        return d, np.full(len(u), 2.0 * solid), np.full(len(u), pdf_scale / solid)

    # inside the cap up to round-off: sampled points on its rim must count as inside
    def eval_(d):
        return np.where(d[:, 2] >= cos_max - 1e-12, 2.0, 0.0)

    def pdf(d):
        return np.where(d[:, 2] >= cos_max - 1e-12, 1 / solid, 0.0)

    r = mcstat.check_emitter(sample, eval_, pdf, n=20000)
    assert r.kind == "emitter" and not r.reject and r.wi is None
    assert r.route("energy").state == "skipped"
    r = mcstat.check_emitter(lambda u: sample(u, 1.1), eval_, pdf, n=20000)
    assert r.reject and r.route("pdf_value").reject


# ---- bad callables and arguments -------------------------------------------------


def test_callable_that_raises_propagates_with_a_note():
    m = Lobe(20, WI)

    def boom(wi, x):
        raise ZeroDivisionError("renderer bug")

    with pytest.raises(ZeroDivisionError, match="renderer bug") as info:
        mcstat.check_bsdf(m.sample, boom, m.pdf, WI, n=2000)
    notes = getattr(info.value, "__notes__", None)
    if notes is not None:
        assert "eval" in notes[0]


@pytest.mark.parametrize(
    "mutate, pattern",
    [
        (lambda x, w, p: (x[:, :2], w, p), r"sample returned points of shape \(\d+, 2\), expected \(\d+, 3\)"),
        (lambda x, w, p: (x, w[:-1], p), r"sample returned weight of shape"),
        (lambda x, w, p: (x, np.where(np.arange(len(w)) == 7, np.nan, w), p), r"sample\(\) returned weight nan"),
        (lambda x, w, p: (x, w, -p), r"sample\(\) returned pdf -"),
        (lambda x, w, p: (2 * x, w, p), r"not in the sphere domain.*unit length"),
        (lambda x, w, p: [x, w, p], r"expected a tuple"),
        (lambda x, w, p: (x, "weights", p), r"weight"),
    ],
)
def test_bad_sample_output_is_a_callback_error(mutate, pattern):
    m = Lobe(20, WI)

    def sample(wi, u):
        return mutate(*m.sample(wi, u))

    with pytest.raises(mcstat.CallbackError, match=pattern):
        mcstat.check_bsdf(sample, m.eval, m.pdf, WI, n=2000)


def test_bad_density_output_is_a_callback_error():
    m = Lobe(20, WI)
    with pytest.raises(mcstat.CallbackError, match=r"pdf\(\) returned -1 at the point \("):
        mcstat.check_bsdf(m.sample, m.eval, lambda wi, x: -np.ones(len(x)), WI, n=2000)
    with pytest.raises(mcstat.CallbackError, match=r"eval\(\) returned inf"):
        mcstat.check_bsdf(m.sample, lambda wi, x: np.full(len(x), np.inf), m.pdf, WI, n=2000)
    with pytest.raises(mcstat.CallbackError, match=r"eval returned values of shape \(3,\)"):
        mcstat.check_bsdf(m.sample, lambda wi, x: np.ones(3), m.pdf, WI, n=2000)
    # a reflection-only domain given a direction below the horizon
    with pytest.raises(mcstat.CallbackError, match="hemisphere"):
        mcstat.check_bsdf(lambda wi, u: (np.tile([0.0, 0.6, -0.8], (len(u), 1)), np.ones(len(u)), np.ones(len(u))),
                          m.eval, m.pdf, WI, domain="hemisphere", n=2000)


def test_bad_arguments():
    m = Lobe(20, WI)
    args = (m.sample, m.eval, m.pdf)
    with pytest.raises(mcstat.InvalidArgumentError, match="n must be at least 1000"):
        mcstat.check_bsdf(*args, WI, n=10)
    with pytest.raises(mcstat.InvalidArgumentError, match="alpha"):
        mcstat.check_bsdf(*args, WI, alpha=1.5)
    with pytest.raises(mcstat.InvalidArgumentError, match=r"wi must be a finite, non-zero direction, got \(0, 0, 0\)"):
        mcstat.check_bsdf(*args, [0, 0, 0])
    with pytest.raises(mcstat.InvalidArgumentError, match="wi must be a direction of 3 numbers"):
        mcstat.check_bsdf(*args, [0, 1])
    with pytest.raises(mcstat.InvalidArgumentError, match="domain"):
        mcstat.check_bsdf(*args, WI, domain="cube")
    with pytest.raises(mcstat.InvalidArgumentError, match="domain of a BSDF"):
        mcstat.check_bsdf(*args, WI, domain="disk")
    with pytest.raises(mcstat.InvalidArgumentError, match="routes"):
        mcstat.check_bsdf(*args, WI, routes=["cells", "colour"])
    with pytest.raises(TypeError, match="routes must be an iterable"):
        mcstat.check_bsdf(*args, WI, routes="cells")
    with pytest.raises(TypeError, match="unexpected keyword argument 'sample_count'"):
        mcstat.check_bsdf(*args, WI, sample_count=10)
    with pytest.raises(TypeError, match="eval must be callable"):
        mcstat.check_bsdf(m.sample, 3, m.pdf, WI)
    with pytest.raises(TypeError, match="n must be an int"):
        mcstat.check_bsdf(*args, WI, n=1e5)
    with pytest.raises(mcstat.InvalidArgumentError, match="n_uniforms"):
        mcstat.check_bsdf(*args, WI, n_uniforms=9)
    with pytest.raises(mcstat.InvalidArgumentError, match="batch"):
        mcstat.check_bsdf(*args, WI, batch=3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'energy'"):
        mcstat.check_warp(lambda u: u, lambda x: np.ones(len(x)), energy=True)


def test_a_sampler_that_always_fails():
    # not an error: a report, whose mass route sees pdf() claim samples that never succeed
    m = Lobe(20, WI)
    r = mcstat.check_bsdf(lambda wi, u: (np.zeros((len(u), 3)), np.zeros(len(u)), np.zeros(len(u))), m.eval, m.pdf,
                          WI, n=2000)
    assert r.n_failed == 2000 and r.reject and r.route("mass").reject
    assert r.route("cells").state == "invalid"
    # a BSDF that reflects nothing from this side: nothing succeeds and pdf() is 0: consistent
    r = mcstat.check_bsdf(lambda wi, u: (np.zeros((len(u), 3)), np.zeros(len(u)), np.zeros(len(u))),
                          lambda wi, x: np.zeros(len(x)), lambda wi, x: np.zeros(len(x)), WI, n=2000)
    assert not r.reject and r.mass == 0 and r.route("mass").pvalue == 1


# ---- calibration (stats suite) ---------------------------------------------------


@pytest.mark.stats
def test_battery_rejects_correct_models_at_rate_alpha():
    """600 checks of correct models (two lobes, a warp) at alpha = 0.05:
    the number rejected must not be significantly above 5% (the battery
    meta-test at 0.001), and the planted sampler bug (the lobe's exponent
    10% off) caught in at least 45 of 50 runs at n = 10000 (power; measured:
    50 of 50, and about half at n = 4000)."""
    rejected = runs = caught = 0
    for seed in range(200):
        for model in (Lobe(5, WI), Lobe(60, [0.8, 0.0, 0.6])):
            r = check(model, n=4000, seed=seed, alpha=0.05)
            rejected += r.reject
            runs += 1
        w = mcstat.check_warp(lambda u: u[:, 0] ** 2, lambda x: 0.5 / np.sqrt(x), domain="interval", n=4000,
                              seed=seed, alpha=0.05)
        rejected += w.reject
        runs += 1
        if seed < 50:
            caught += check(Lobe(60, [0.8, 0.0, 0.6], "sampler"), n=10000, seed=seed, alpha=0.05).reject
    meta = mcstat.battery_test(rejected, 0.05, n=runs, alternative="greater", meta_alpha=0.001)
    assert not meta.reject, (rejected, runs)
    assert caught >= 45, caught


def test_pdf_where_eval_is_zero_is_counted_not_rejected():
    # a cosine sampler for a BSDF that reflects only towards y > 0: samples elsewhere carry weight 0
    def sample(wi, u):
        r = np.sqrt(u[:, 0])
        phi = 2 * np.pi * u[:, 1]
        x = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(1 - u[:, 0])], axis=1)
        return x, np.where(x[:, 1] > 0, 0.5, 0.0), x[:, 2] / np.pi

    def pdf(wi, x):
        return np.maximum(x[:, 2], 0) / np.pi

    def eval_(wi, x):
        return np.where(x[:, 1] > 0, 0.5 * np.maximum(x[:, 2], 0) / np.pi, 0.0)

    r = mcstat.check_bsdf(sample, eval_, pdf, [0, 0, 1], domain="hemisphere", n=5000)
    assert not r.reject, str(r)
    assert r.pdf_without_eval > 2000
    assert "pdf() > 0 where eval() = 0 at" in str(r)
    assert abs(r.mass_sampled - 1) < 5 * r.mass_sampled_se + 1e-12


def test_tolerated_share_of_points_beyond_rtol():
    # a handful of points (u0 < 3e-5: about 3 of 1e5) with a weight off, as float32 round-off at grazing
    # angles gives: within the default tolerated share (1e-4), not with tolerated=0
    m = Lobe(20, WI)

    def sample(wi, u):
        x, w, p = m.sample(wi, u)
        return x, np.where(u[:, 0] < 3e-5, w * 1.01, w), p

    r = mcstat.check_bsdf(sample, m.eval, m.pdf, WI, seed=4)
    weight = r.route("weight")
    assert 1 <= weight.count <= 10 and not weight.reject
    strict = mcstat.check_bsdf(sample, m.eval, m.pdf, WI, seed=4, tolerated=0.0)
    assert strict.route("weight").reject and strict.reject
    with pytest.raises(mcstat.InvalidArgumentError, match="tolerated"):
        mcstat.check_bsdf(sample, m.eval, m.pdf, WI, tolerated=1.0)


def test_failures_marked_by_the_weight_alone_are_named():
    """A sampler that marks a failed sample by weight 0 (keeping a direction
    and its pdf) is rejected by the weight route, and the report says how a
    failed sample is marked; a correct one carries no such line."""
    m = Lobe(20, WI)

    def sample(wi, u):
        x, w, p = m.sample(wi, u)
        failed = u[:, 2] < 0.2  # a fifth of the samples "fail", pdf kept
        return x, np.where(failed, 0.0, w), p

    r = mcstat.check_bsdf(sample, m.eval, m.pdf, WI, n=5000)
    assert r.reject and r.route("weight").reject
    frac = r.zero_weight / r.n
    assert 0.17 < frac < 0.23, frac
    assert "weight 0 where pdf and eval() are > 0" in str(r) and "must return pdf 0" in str(r)
    good = mcstat.check_bsdf(m.sample, m.eval, m.pdf, WI, n=5000)
    assert good.zero_weight == 0 and "must return pdf 0" not in str(good)
