"""Phase functions and distance sampling: mcstat.check_phase and
mcstat.check_medium (mcstat_check_phase, mcstat_check_medium).  Analytic
Henyey-Greenstein (g = 0.7, -0.3) and Rayleigh phase functions and a
homogeneous medium with a surface at tmax: the correct ones pass, each
planted ~10% bug is caught by the route meant for it, bad arguments are
refused by name; (stats suite) the rejection rate of correct models over
200 seeds within the binomial bounds of alpha.
"""
import math

import numpy as np
import pytest

import mcstat


def _frame(d):
    s = math.copysign(1.0, d[2])
    a = -1.0 / (s + d[2])
    b = d[0] * d[1] * a
    return np.array([1 + s * d[0] ** 2 * a, s * b, -s * d[0]]), np.array([b, s + d[1] ** 2 * a, -d[1]])


def _around(d, mu, phi):
    """Directions at cosine mu from the unit vector d, azimuth phi."""
    t1, t2 = _frame(d)
    s = np.sqrt(np.maximum(0.0, 1 - mu * mu))
    return mu[:, None] * d + s[:, None] * (np.cos(phi)[:, None] * t1 + np.sin(phi)[:, None] * t2)


class Phase:
    """A phase function of mu = wo . (-wi) (wi points back along the ray, as
    in Mitsuba: g > 0 scatters forward).  bug: "pdf_g" (pdf() with g 10%
    off, the sampler right), "weight" (weight 10% high), "norm" (eval and
    weight 0.9 times the phase function: consistent with each other, not
    normalised), "pdf_norm" (pdf() and the reported pdf 1.1 times the
    density drawn)."""

    def __init__(self, kind, g=0.0, bug=None):
        self.kind, self.g, self.bug = kind, g, bug

    def density(self, mu, g):
        if self.kind == "rayleigh":
            return 3 / (16 * np.pi) * (1 + mu * mu)
        if g == 0.0:
            return np.full_like(mu, 1 / (4 * np.pi))
        return (1 - g * g) / (4 * np.pi * (1 + g * g - 2 * g * mu) ** 1.5)

    def mu_of(self, u):
        if self.kind == "rayleigh":
            z = 2 * (2 * u - 1)
            r = np.sqrt(z * z + 1)
            return np.clip(np.cbrt(z + r) + np.cbrt(z - r), -1.0, 1.0)
        g = self.g
        if g == 0.0:
            return 1 - 2 * u
        q = (1 - g * g) / (1 - g + 2 * g * u)
        return np.clip((1 + g * g - q * q) / (2 * g), -1.0, 1.0)

    def _mu(self, wi, wo):
        return np.clip(wo @ (-np.asarray(wi, dtype=float)), -1.0, 1.0)

    def sample(self, wi, u):
        d = -np.asarray(wi, dtype=float)
        wo = _around(d, self.mu_of(u[:, 0]), 2 * np.pi * u[:, 1])
        wo /= np.linalg.norm(wo, axis=1)[:, None]
        p = self.density(self._mu(wi, wo), self.g)
        scale = 1.1 if self.bug == "pdf_norm" else 1.0
        w = {"weight": 1.1, "norm": 0.9}.get(self.bug, 1.0)
        return wo, np.full(len(u), w), scale * p

    def pdf(self, wi, wo):
        g = self.g * 1.1 if self.bug == "pdf_g" else self.g
        return (1.1 if self.bug == "pdf_norm" else 1.0) * self.density(self._mu(wi, wo), g)

    def eval(self, wi, wo):
        return (0.9 if self.bug == "norm" else 1.0) * self.density(self._mu(wi, wo), self.g)


WI = np.array([0.3, -0.4, 0.866])
MODELS = [("hg", 0.7), ("hg", -0.3), ("rayleigh", 0.0)]


def phase_check(model, **kw):
    return mcstat.check_phase(model.sample, model.eval, model.pdf, WI, **kw)


@pytest.mark.parametrize("kind, g", MODELS)
def test_correct_phase_functions_pass(kind, g):
    r = phase_check(Phase(kind, g), n=20000, seed=1, reciprocal=True)
    assert not r.reject, str(r)
    assert r.kind == "phase" and r.domain == "sphere" and r.wi == pytest.approx(tuple(WI / np.linalg.norm(WI)))
    assert abs(r.mass - 1) < 1e-3 and r.n_failed == 0
    assert r.albedo == pytest.approx(1.0, abs=1e-12)
    energy = r.route("energy")
    assert energy.state == "ran" and energy.deterministic and not energy.reject
    assert r.route("reciprocity").state == "ran" and r.route("reciprocity").count == 0
    assert "Phase function check" in str(r) and "albedo 1" in str(r)


@pytest.mark.parametrize("kind, g", MODELS)
@pytest.mark.parametrize("bug, route", [("pdf_g", "pdf_value"), ("weight", "weight"), ("norm", "energy"),
                                        ("pdf_norm", "mass")])
def test_planted_phase_bugs_are_caught(kind, g, bug, route):
    if bug == "pdf_g" and kind == "rayleigh":
        pytest.skip("Rayleigh has no g")
    r = phase_check(Phase(kind, g, bug), n=20000, seed=2)
    assert r.reject and r.route(route).reject, str(r)


def test_check_bsdf_misses_what_check_phase_adds():
    """The same model through check_bsdf: a phase function 10% short
    (eval and weight 0.9 p) passes there, since a BSDF may absorb; and
    reciprocity divided by cosines rejects a reciprocal phase function."""
    m = Phase("hg", 0.7, "norm")
    assert not mcstat.check_bsdf(m.sample, m.eval, m.pdf, WI, n=20000, seed=2).reject
    assert phase_check(m, n=20000, seed=2).route("energy").reject
    ok = Phase("hg", 0.7)
    r = mcstat.check_bsdf(ok.sample, ok.eval, ok.pdf, WI, n=20000, seed=2, reciprocal=True)
    assert r.route("reciprocity").reject
    assert not phase_check(ok, n=20000, seed=2, reciprocal=True).reject


def test_phase_with_spread_weights_tests_albedo_two_sided():
    """A phase function sampled uniformly on the sphere (weights p/pdf not
    constant): the energy route is a two-sided t test, rejecting 0.9 p."""
    hg = Phase("hg", 0.3)

    def sample(wi, u, c=1.0):
        z = 1 - 2 * u[:, 0]
        s = np.sqrt(np.maximum(0, 1 - z * z))
        phi = 2 * np.pi * u[:, 1]
        wo = np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=1)
        return wo, c * hg.eval(wi, wo) * 4 * np.pi, np.full(len(u), 1 / (4 * np.pi))

    pdf = lambda wi, wo: np.full(len(wo), 1 / (4 * np.pi))  # noqa: E731
    r = mcstat.check_phase(sample, hg.eval, pdf, WI, n=20000, seed=3)
    assert not r.reject and not r.route("energy").deterministic and r.route("energy").pvalue > 0.01, str(r)
    short = lambda wi, x: 0.9 * hg.eval(wi, x)  # noqa: E731
    r = mcstat.check_phase(lambda wi, u: sample(wi, u, 0.9), short, pdf, WI, n=20000, seed=3)
    assert r.reject and r.route("energy").reject and r.route("energy").pvalue < 1e-6, str(r)


def test_phase_bad_arguments():
    m = Phase("hg", 0.7)
    with pytest.raises(TypeError, match="unexpected keyword argument 'domain'"):
        mcstat.check_phase(m.sample, m.eval, m.pdf, WI, domain="hemisphere")
    with pytest.raises(mcstat.InvalidArgumentError, match=r"wi must be a finite, non-zero direction, got \(0, 0, 0\)"):
        mcstat.check_phase(m.sample, m.eval, m.pdf, [0, 0, 0])
    with pytest.raises(TypeError, match="unexpected keyword argument 'sigma_ref'"):
        mcstat.check_phase(m.sample, m.eval, m.pdf, WI, sigma_ref=1.0)
    with pytest.raises(mcstat.CallbackError, match="unit length"):
        mcstat.check_phase(lambda wi, u: (2 * m.sample(wi, u)[0], *m.sample(wi, u)[1:]), m.eval, m.pdf, WI, n=2000)


# ---- distance sampling ------------------------------------------------------------


class Homogeneous:
    """Free flights in a homogeneous medium (sigma_t, sigma_s) up to a
    surface at tmax (inf: none).  bug: "pdf_sigma" (pdf() with sigma_t 10%
    off, the sampler and its reported pdf right), "pdf_both" (pdf() and the
    reported pdf with sigma_t 10% off: the sampler disagrees with both),
    "weight" (weight 10% high), "sampler" (flights drawn with sigma_t 10%
    off, everything else right)."""

    def __init__(self, sigma_t=2.0, sigma_s=1.5, tmax=1.0, bug=None):
        self.st, self.ss, self.tmax, self.bug = sigma_t, sigma_s, tmax, bug

    def _density(self, t, st):
        with np.errstate(invalid="ignore"):
            return np.where(t < self.tmax, st * np.exp(-st * np.minimum(t, 1e300)), 0.0)

    def sample(self, u):
        st = self.st * 1.1 if self.bug == "sampler" else self.st
        t = -np.log1p(-u[:, 0]) / st
        inside = t < self.tmax
        p = self._density(t, self.st * 1.1 if self.bug == "pdf_both" else self.st)
        w = np.where(inside, self.ss * np.exp(-self.st * np.where(inside, t, 0)), 0.0)
        w = np.where(p > 0, w / np.where(p > 0, p, 1), 0.0) * (1.1 if self.bug == "weight" else 1.0)
        return np.where(inside, t, 0.0), w, np.where(inside, p, 0.0)

    def pdf(self, t):
        return self._density(t, self.st * 1.1 if self.bug in ("pdf_sigma", "pdf_both") else self.st)

    def eval(self, t):
        return self.ss / self.st * self._density(t, self.st)


def medium_check(model, sigma_ref=2.0, **kw):
    return mcstat.check_medium(model.sample, model.eval, model.pdf, sigma_ref=sigma_ref, **kw)


@pytest.mark.parametrize("tmax, sigma_ref", [(1.0, 2.0), (1.0, 0.5), (np.inf, 2.0), (0.3, 5.0)])
def test_correct_distance_sampling_passes(tmax, sigma_ref):
    m = Homogeneous(tmax=tmax)
    r = medium_check(m, sigma_ref=sigma_ref, n=20000, seed=1)
    assert not r.reject, str(r)
    assert r.kind == "medium" and r.domain == "interval" and r.sigma_ref == sigma_ref and r.wi is None
    escape = math.exp(-m.st * tmax)
    assert r.mass == pytest.approx(1 - escape, abs=1e-3)
    assert abs(r.n_failed / r.n - escape) < 5 * math.sqrt(escape * (1 - escape) / r.n) + 1e-12
    assert r.albedo == pytest.approx(m.ss / m.st * (1 - escape), rel=0.02)
    assert "x = 1 - exp(-" in str(r)


@pytest.mark.parametrize("bug, route", [("pdf_sigma", "pdf_value"), ("pdf_both", "mass"), ("weight", "weight"),
                                        ("sampler", "cells")])
def test_planted_distance_bugs_are_caught(bug, route):
    r = medium_check(Homogeneous(bug=bug), n=20000, seed=2)
    assert r.reject and r.route(route).reject, str(r)


def test_escape_probability_is_what_mass_tests():
    """A sampler that lets 10% of its scatterings escape (they should have
    stopped): only the share of escapes changes, and mass sees it."""
    m = Homogeneous(tmax=2.0)

    def leaky(u):
        t, w, p = m.sample(u)
        lost = u[:, 0] * 1e4 % 1.0 < 0.1
        return t, np.where(lost, 0.0, w), np.where(lost, 0.0, p)

    r = mcstat.check_medium(leaky, m.eval, m.pdf, sigma_ref=2.0, n=20000, seed=4)
    assert r.reject and r.route("mass").reject, str(r)


class Weighted:
    """Distances drawn from exp(sigma_d) rather than from the medium's
    sigma_t, and weighted: a scattering at t carries sigma_s T(t) / pdf(t),
    an escape T(tmax) / P(escape) (analog: sigma_d = sigma_t, escape weight
    1).  bug: "escape" (the escape's weight T(tmax), the division by
    P(escape) forgotten), "claim" (the transmittance claimed 10% high)."""

    def __init__(self, sigma_d=1.2, sigma_t=2.0, sigma_s=1.5, tmax=1.0, bug=None):
        self.sd, self.st, self.ss, self.tmax, self.bug = sigma_d, sigma_t, sigma_s, tmax, bug
        self.T = math.exp(-sigma_t * tmax)

    def claim(self):
        return min(self.T * (1.1 if self.bug == "claim" else 1.0), 1.0)

    def sample(self, u):
        t = -np.log1p(-u[:, 0]) / self.sd
        inside = t < self.tmax
        ti = np.where(inside, t, 0.0)
        p = np.where(inside, self.sd * np.exp(-self.sd * ti), 0.0)
        w_in = self.ss * np.exp(-self.st * ti) / np.where(inside, p, 1.0)
        escape = self.T if self.bug == "escape" else self.T / math.exp(-self.sd * self.tmax)
        return ti, np.where(inside, w_in, escape), p

    def pdf(self, t):
        with np.errstate(invalid="ignore"):
            return np.where(t < self.tmax, self.sd * np.exp(-self.sd * np.minimum(t, 1e300)), 0.0)

    def eval(self, t):
        with np.errstate(invalid="ignore"):
            return np.where(t < self.tmax, self.ss * np.exp(-self.st * np.minimum(t, 1e300)), 0.0)


def weighted_check(m, **kw):
    return mcstat.check_medium(m.sample, m.eval, m.pdf, sigma_ref=2.0, escape_transmittance=m.claim(), **kw)


@pytest.mark.parametrize("sigma_d", [2.0, 1.2, 3.0])
def test_escape_weights_pass_when_right(sigma_d):
    m = Weighted(sigma_d=sigma_d)
    r = weighted_check(m, n=20000, seed=1)
    assert not r.reject, str(r)
    assert r.escape_weight == pytest.approx(m.T, rel=5 * r.escape_weight_se / m.T + 1e-12)
    assert r.route("mass").values[1] == m.claim()
    assert "escape weights" in str(r) and "vs T(tmax)" in str(r)


@pytest.mark.parametrize("bug", ["escape", "claim"])
def test_escape_weight_bugs_are_caught_by_mass(bug):
    for seed in range(5):
        r = weighted_check(Weighted(bug=bug), n=20000, seed=seed)
        assert r.reject and r.route("mass").reject, (seed, str(r))


def test_without_transmittance_escape_weights_are_not_looked_at_but_must_be_0():
    m = Weighted()
    r = mcstat.check_medium(m.sample, m.eval, m.pdf, sigma_ref=2.0, n=5000, seed=1)
    assert r.escape_weight is None and r.reject and r.route("weight").reject  # escapes must weigh 0 then
    h = Homogeneous()
    r = mcstat.check_medium(h.sample, h.eval, h.pdf, sigma_ref=2.0, n=5000, seed=1)
    assert not r.reject and r.escape_weight is None


def test_analog_escapes_weigh_one():
    """Analog tracking (distances from sigma_t itself): an escape carries
    weight 1, and its mean over the flights is the escape share."""
    m = Weighted(sigma_d=2.0)
    r = weighted_check(m, n=20000, seed=3)
    assert not r.reject
    assert r.escape_weight == pytest.approx(r.n_failed / r.n, rel=1e-12)


def test_escape_transmittance_bad_arguments():
    m = Weighted()
    for bad, shown in ((1.5, "1.5"), (float("nan"), "nan")):
        with pytest.raises(mcstat.InvalidArgumentError) as e:
            mcstat.check_medium(m.sample, m.eval, m.pdf, sigma_ref=2.0, escape_transmittance=bad, n=2000)
        assert str(e.value) == f"escape_transmittance must be negative (off) or in [0, 1], got {shown}"
    with pytest.raises(mcstat.InvalidArgumentError, match="MCSTAT_CHECK_WEIGHT_OVER_PDF"):
        mcstat.check_medium(m.sample, m.eval, m.pdf, sigma_ref=2.0, escape_transmittance=0.5, weight="value",
                            n=2000)
    ph = Phase("hg", 0.3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'escape_transmittance'"):
        mcstat.check_phase(ph.sample, ph.eval, ph.pdf, WI, escape_transmittance=0.5, n=2000)


def test_transmittance_is_a_deprecated_alias():
    """0.3's Python name: the same check, with a DeprecationWarning; both names at once are refused."""
    m = Weighted()
    with pytest.warns(DeprecationWarning, match="escape_transmittance"):
        old = mcstat.check_medium(m.sample, m.eval, m.pdf, sigma_ref=2.0, transmittance=m.claim(), n=5000, seed=2)
    new = weighted_check(m, n=5000, seed=2)
    assert old.escape_weight == new.escape_weight and old.route("mass").pvalue == new.route("mass").pvalue
    with pytest.raises(TypeError, match="both escape_transmittance and its old name"):
        mcstat.check_medium(m.sample, m.eval, m.pdf, sigma_ref=2.0, transmittance=0.5, escape_transmittance=0.5)


def test_medium_bad_arguments():
    m = Homogeneous()
    args = (m.sample, m.eval, m.pdf)
    with pytest.raises(TypeError, match="missing required keyword argument 'sigma_ref'"):
        mcstat.check_medium(*args)
    for bad in (0.0, -1.0, float("inf"), float("nan")):
        with pytest.raises(mcstat.InvalidArgumentError, match="sigma_ref must be finite and > 0"):
            mcstat.check_medium(*args, sigma_ref=bad)
    with pytest.raises(TypeError, match="unexpected keyword argument 'domain'"):
        mcstat.check_medium(*args, sigma_ref=1.0, domain="square")
    with pytest.raises(mcstat.CallbackError, match="interval"):
        mcstat.check_medium(lambda u: (-np.ones(len(u)), np.ones(len(u)), np.ones(len(u))), m.eval, m.pdf,
                            sigma_ref=1.0, n=2000)
    with pytest.raises(mcstat.CallbackError, match="pdf"):
        mcstat.check_medium(m.sample, m.eval, lambda t: -np.ones(len(t)), sigma_ref=1.0, n=2000)


# ---- calibration (stats suite) -----------------------------------------------------


@pytest.mark.stats
def test_phase_and_medium_reject_correct_models_at_rate_alpha():
    """200 seeds x 5 correct models (HG 0.7, HG -0.3, Rayleigh, the
    homogeneous medium, the weighted one with its escape weights) at n = 4000, alpha = 0.05: the rejections must not
    be significantly above 5% (battery meta-test at 0.001).  About 10 s."""
    rejected = runs = 0
    for seed in range(200):
        for kind, g in MODELS:
            rejected += phase_check(Phase(kind, g), n=4000, seed=seed, alpha=0.05).reject
            runs += 1
        rejected += medium_check(Homogeneous(), n=4000, seed=seed, alpha=0.05).reject
        rejected += weighted_check(Weighted(), n=4000, seed=seed, alpha=0.05).reject
        runs += 2
    meta = mcstat.battery_test(rejected, 0.05, n=runs, alternative="greater", meta_alpha=0.001)
    assert not meta.reject, (rejected, runs)


# ---- as assertions of mcstat.testing ---------------------------------------------------
def test_phase_and_medium_assertions():
    import mcstat.testing as mt
    wi = np.array([0.3, -0.4, 0.866])
    good, bad = Phase("hg", 0.7), Phase("hg", 0.7, "norm")
    with mt.scope("phase", 0.01):
        r = mt.assert_phase_consistent(good.sample, good.eval, good.pdf, wi, n=20000)
        assert r.kind == "phase"
    with mt.scope("phase-bad", 0.01), pytest.raises(mt.StatisticalAssertionError, match="check_phase at wi"):
        mt.assert_phase_consistent(bad.sample, bad.eval, bad.pdf, wi, n=20000)
    m, wrong = Homogeneous(), Homogeneous(bug="weight")
    with mt.scope("medium", 0.01):
        r = mt.assert_medium_consistent(m.sample, m.eval, m.pdf, sigma_ref=2.0, n=20000)
        assert r.kind == "medium"
    with mt.scope("medium-bad", 0.01), pytest.raises(mt.StatisticalAssertionError, match="check_medium"):
        mt.assert_medium_consistent(wrong.sample, wrong.eval, wrong.pdf, sigma_ref=2.0, n=20000)
