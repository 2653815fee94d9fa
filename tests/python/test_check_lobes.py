"""Discrete (delta) lobes in check_bsdf: a smooth dielectric (reflection and
refraction, both discrete; pdf() and eval() zero), a coated diffuse BSDF
(a specular lobe over a Lambertian base), their planted bugs (the lobe's
weight 5% off, the lobe picked more often than its pdf says, the
refraction's index 1% off, the base's weight off), the callable's bad
returns, and the calibration meta-test: 200 seeds of each correct model at
alpha = 0.05 within the binomial bounds of alpha.
"""
import numpy as np
import pytest

import mcstat


def fresnel(cos_i, eta):
    """Unpolarised Fresnel reflectance of a dielectric of relative index eta
    (cos_i > 0: from outside), the cosine of refraction and eta_it."""
    eta_it = eta if cos_i > 0 else 1.0 / eta
    c = abs(cos_i)
    s2t = (1.0 - c * c) / (eta_it * eta_it)
    if s2t >= 1.0:
        return 1.0, 0.0, eta_it
    ct = np.sqrt(1.0 - s2t)
    rs = (c - eta_it * ct) / (c + eta_it * ct)
    rp = (eta_it * c - ct) / (eta_it * c + ct)
    return 0.5 * (rs * rs + rp * rp), ct, eta_it


class Dielectric:
    """Mitsuba's smooth dielectric in radiance mode: reflection with
    probability F (weight 1), refraction with 1 - F (weight eta_ti^2)."""

    def __init__(self, eta=1.5, weight=1.0, pick=1.0, eta_bug=1.0):
        self.eta, self.weight, self.pick, self.eta_bug = eta, weight, pick, eta_bug

    def _geometry(self, wi, eta):
        F, ct, eta_it = fresnel(wi[2], eta)
        r = np.array([-wi[0], -wi[1], wi[2]])
        t = np.array([-wi[0] / eta_it, -wi[1] / eta_it, -np.sign(wi[2]) * ct])
        return F, r, t, 1.0 / eta_it

    def lobes(self, wi):
        F, r, t, eta_ti = self._geometry(wi, self.eta)
        if F >= 1.0:  # total internal reflection
            return np.array([r]), np.array([1.0]), np.array([1.0])
        return np.array([r, t]), np.array([F, 1.0 - F]), np.array([F, (1.0 - F) * eta_ti ** 2])

    def sample(self, wi, u):
        F, r, t, eta_ti = self._geometry(wi, self.eta * self.eta_bug)
        refl = u[:, 0] < min(F * self.pick, 1.0)
        x = np.where(refl[:, None], r, t)
        return x, np.where(refl, 1.0, eta_ti ** 2) * self.weight, np.where(refl, F, 1.0 - F)

    def eval(self, wi, x):
        return np.zeros(len(x))

    pdf = eval


class Coated:
    """A specular coat (Schlick, R0 = 0.04) over a Lambertian base of albedo
    rho: the coat's reflection picked with probability q."""

    def __init__(self, q=0.3, rho=0.6, weight=1.0, pick=1.0, base=1.0):
        self.q, self.rho, self.weight, self.pick, self.base = q, rho, weight, pick, base

    @staticmethod
    def F(c):
        return 0.04 + 0.96 * (1.0 - c) ** 5

    def lobes(self, wi):
        return np.array([[-wi[0], -wi[1], wi[2]]]), np.array([self.q]), np.array([self.F(wi[2])])

    def sample(self, wi, u):
        F = self.F(wi[2])
        spec = u[:, 0] < self.q * self.pick
        st, phi = np.sqrt(u[:, 1]), 2 * np.pi * u[:, 2]
        d = np.stack([st * np.cos(phi), st * np.sin(phi), np.sqrt(1 - u[:, 1])], axis=1)
        x = np.where(spec[:, None], np.array([-wi[0], -wi[1], wi[2]]), d)
        pdf = np.where(spec, self.q, (1 - self.q) * d[:, 2] / np.pi)
        w = np.where(spec, F / self.q * self.weight, (1 - F) * self.rho / (1 - self.q) * self.base)
        return x, w, pdf

    def eval(self, wi, x):
        return (1 - self.F(wi[2])) * self.rho * np.maximum(x[:, 2], 0) / np.pi

    def pdf(self, wi, x):
        return (1 - self.q) * np.maximum(x[:, 2], 0) / np.pi


def unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


ABOVE, BELOW, GRAZING_INSIDE = unit([0.4, 0.1, 0.9]), unit([0.3, -0.2, -0.8]), unit([0.9, 0.0, -0.2])


def check(m, wi, **kw):
    kw.setdefault("domain", "hemisphere" if isinstance(m, Coated) else "sphere")
    kw.setdefault("energy", wi[2] > 0)  # refraction into the thinner side scales radiance up
    return mcstat.check_bsdf(m.sample, m.eval, m.pdf, wi, lobes=m.lobes, **kw)


@pytest.mark.parametrize("m,wi", [(Dielectric(), ABOVE), (Dielectric(), BELOW), (Dielectric(), GRAZING_INSIDE),
                                  (Coated(), ABOVE)])
def test_correct_lobes_pass(m, wi):
    r = check(m, wi, n=20000, seed=3)
    assert not r.reject, str(r)
    dirs, mass, value = m.lobes(wi)
    assert r.lobes == len(mass)
    assert r.lobe_mass == pytest.approx(mass.sum(), rel=1e-15)
    assert r.lobe_albedo == pytest.approx(value.sum(), rel=1e-15)
    assert r.n_lobe + r.n_failed + r.route("mass").count == r.n
    # each sample is checked by pdf_value and weight, discrete or not
    assert r.route("pdf_value").checked == r.n
    assert "discrete lobes: %d" % len(mass) in str(r)


def test_total_internal_reflection_is_one_lobe_of_mass_one():
    r = check(Dielectric(), GRAZING_INSIDE, n=5000, seed=1)
    assert r.lobes == 1 and r.n_lobe == r.n and r.lobe_mass == 1.0
    assert r.route("mass").pvalue == 1.0


def test_pure_delta_leaves_the_smooth_routes_without_an_answer():
    r = check(Dielectric(), ABOVE, n=5000, seed=1)
    for name in ("cells", "integrals", "ks"):
        assert r.route(name).state == "invalid"
    for name in ("mass", "pdf_value", "weight", "support", "energy"):
        assert r.route(name).state == "ran"
    # the budget of the weakest lobe (the reflection, F = 0.04), closed form:
    # z = z(level / 2 / (lobes + 1)) + z(0.8), level = alpha / 5 routes (Holm's worst case)
    from scipy.stats import norm
    F = fresnel(ABOVE[2], 1.5)[0]
    z = norm.isf(0.01 / 5 / 2 / 3) + norm.isf(0.2)
    assert r.route("mass").detectable == pytest.approx(z * np.sqrt(F * (1 - F) / 5000) / F, rel=1e-6)


@pytest.mark.parametrize("make,route", [
    (lambda: Dielectric(weight=1.05), "weight"),
    (lambda: Dielectric(pick=1.2), "mass"),
    (lambda: Dielectric(eta_bug=1.01), "pdf_value"),
    (lambda: Coated(weight=1.05), "weight"),
    (lambda: Coated(pick=1.1), "mass"),
    (lambda: Coated(base=1.05), "weight"),
])
def test_planted_lobe_bugs_are_caught_on_every_seed(make, route):
    """The issue's bar: a 5% error in a discrete weight caught 20/20."""
    m = make()
    for seed in range(20):  # a 10% error in a lobe of mass 0.04 needs about 2e4 samples
        r = check(m, ABOVE, n=20000 if route == "mass" else 5000, seed=seed)
        assert r.reject and r.route(route).reject, (seed, str(r))


def test_mass_route_names_the_lobe_furthest_off():
    r = check(Dielectric(pick=1.5), ABOVE, n=20000, seed=2)
    where, (share, mass) = r.route("mass").where, r.route("mass").values
    assert where == pytest.approx(tuple(Dielectric().lobes(ABOVE)[0][0]), abs=1e-15)  # reflection
    assert mass == pytest.approx(fresnel(ABOVE[2], 1.5)[0], rel=1e-15)
    assert share == pytest.approx(1.5 * mass, rel=0.15)


def test_without_lobes_the_discrete_samples_fail_pdf_value():
    m = Coated()
    r = mcstat.check_bsdf(m.sample, m.eval, m.pdf, ABOVE, domain="hemisphere", n=5000, seed=1)
    assert r.reject and r.route("pdf_value").reject and r.lobes == 0


def test_a_lobe_with_energy_that_is_never_sampled_fails_support():
    m = Dielectric()

    def lobes(wi):
        d, mass, value = m.lobes(wi)
        return np.vstack([d, [[0.0, 0.0, 1.0]]]), np.append(mass, 0.0), np.append(value, 0.1)

    r = mcstat.check_bsdf(m.sample, m.eval, m.pdf, ABOVE, lobes=lobes, n=5000, seed=1)
    assert r.reject and r.route("support").reject


@pytest.mark.parametrize("ret,match", [
    (lambda wi: None, "expected a tuple"),
    (lambda wi: (np.zeros((1, 2)), [1.0], [1.0]), r"shape \(1, 2\)"),
    (lambda wi: (np.zeros((5, 3)), np.zeros(5), np.zeros(5)), "at most 4"),
    (lambda wi: ([[0, 0, 1]], [1.5], [1.0]), "mass 1.5"),
    (lambda wi: ([[0, 0, 1]], [0.5], [np.nan]), "value nan"),
    (lambda wi: ([[0, 0, 2]], [0.5], [0.5]), "unit length"),
    (lambda wi: ([[0, 0, 1], [0, 0, 1]], [0.5, 0.1], [0.5, 0.1]), "same direction"),
    (lambda wi: ([[0, 0, 1]], [0.5, 0.2], [0.5]), "mass of shape"),
])
def test_lobes_bad_returns_raise_callback_error(ret, match):
    m = Dielectric()
    with pytest.raises(mcstat.CallbackError, match=match):
        mcstat.check_bsdf(m.sample, m.eval, m.pdf, ABOVE, lobes=ret, n=2000)


def test_lobes_argument_errors():
    m = Dielectric()
    with pytest.raises(TypeError, match="lobes must be callable"):
        mcstat.check_bsdf(m.sample, m.eval, m.pdf, ABOVE, lobes=3, n=2000)
    with pytest.raises(TypeError, match="unexpected keyword argument 'lobes'"):
        mcstat.check_phase(m.sample, m.eval, m.pdf, ABOVE, lobes=m.lobes, n=2000)
    with pytest.raises(TypeError, match="unexpected keyword argument 'lobes'"):
        mcstat.check_emitter(lambda u: None, m.eval, m.pdf, lobes=m.lobes, n=2000)

    def boom(wi):
        raise RuntimeError("boom")

    with pytest.raises(RuntimeError, match="boom"):
        mcstat.check_bsdf(m.sample, m.eval, m.pdf, ABOVE, lobes=boom, n=2000)


@pytest.mark.stats
def test_lobes_reject_correct_models_at_rate_alpha():
    """200 seeds x 3 correct models (the dielectric from above and below,
    the coated diffuse) at n = 5000, alpha = 0.05: not significantly more
    than 5% rejected (battery meta-test at 0.001).  About 1 s."""
    rejected = runs = 0
    for seed in range(200):
        for m, wi in ((Dielectric(), ABOVE), (Dielectric(), BELOW), (Coated(), ABOVE)):
            rejected += check(m, wi, n=5000, seed=seed, alpha=0.05).reject
            runs += 1
    meta = mcstat.battery_test(rejected, 0.05, n=runs, alternative="greater", meta_alpha=0.001)
    assert not meta.reject, (rejected, runs)
