"""The renderer checks on float32 data, and verdicts that admit "no answer".

NumPy reproductions of two failure classes seen on real renderers:
- float32 constants: an isotropic phase function whose eval and pdf are the
  float32 1/(4 pi) (which integrates to 0.99999996) was rejected at every
  seed by the integrals route (a 4e-8 rounding difference against a
  variance of ~1e-18 along the total); float32 weights that round a ratio
  to 1 +- an ulp were rejected by the energy route.  The numerical floor
  (options' resolution, derived from the values) makes rounding no
  evidence, while a 1% error is still caught.
- a BSDF whose eval() puts the cosine in the wrong place (divides by it)
  and whose sample() reuses it: heavy-tailed weights, so the integrals and
  energy routes cannot answer; the verdict is "inconclusive", not
  "consistent", and the assertion fails unless told to allow it.
Every check has a fixed seed: nothing here passes or fails by chance.
"""
import numpy as np
import pytest
from scipy import stats

import mcstat
import mcstat.testing as mt

F32 = np.float32
INV4PI_F32 = F32(1.0) / F32(4.0 * np.pi)
WI = np.array([0.0, 0.0, 1.0])


def _sphere(u, dtype):
    u = u.astype(dtype)
    z = dtype(1) - dtype(2) * u[:, 0]
    r = np.sqrt(np.maximum(dtype(0), dtype(1) - z * z))
    phi = dtype(2 * np.pi) * u[:, 1]
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1).astype(np.float64)


class Isotropic:
    """The isotropic phase function as a float32 renderer computes it.
    eval_scale: eval() that factor times the density (the weights stay 1:
    a 1% bug of eval alone); ulp_weights: each weight eval/pdf rounded to 1
    or to the next float32 above, depending on the direction (the weight
    and eval agree, as a float renderer's ratio does)."""

    def __init__(self, eval_scale=1.0, ulp_weights=False, dtype=F32):
        self.scale, self.ulp, self.dtype = eval_scale, ulp_weights, dtype
        self.density = dtype(1.0) / dtype(4.0 * np.pi)

    def _ratio(self, wo):
        if not self.ulp:
            return np.full(len(wo), self.dtype(self.scale), self.dtype)
        up = (np.floor(wo[:, 2] * 1e4).astype(np.int64) & 1).astype(bool)
        return np.where(up, np.nextafter(F32(1), F32(2)), F32(1)).astype(self.dtype)

    def sample(self, wi, u):
        wo = _sphere(u, self.dtype)
        w = self._ratio(wo) if self.ulp else np.ones(len(u), self.dtype)
        return wo, w, np.full(len(u), self.density, self.dtype)

    def eval(self, wi, wo):
        return (self.density * self._ratio(wo)).astype(self.dtype)

    def pdf(self, wi, wo):
        return np.full(len(wo), self.density, self.dtype)


def _check(model, seed, n=20_000, **kw):
    return mcstat.check_phase(model.sample, model.eval, model.pdf, WI, n=n, seed=seed, alpha=0.01, **kw)


def _binomial_bound(runs, alpha, meta=0.001):
    """The largest rejection count of `runs` checks at `alpha` that a
    calibrated check reaches with probability above `meta`."""
    return int(stats.binom.ppf(1 - meta, runs, alpha))


def test_float32_isotropic_is_not_rejected():
    reps = [_check(Isotropic(), seed, n=100_000) for seed in range(20)]
    assert sum(r.reject for r in reps) <= _binomial_bound(20, 0.01)
    r = reps[0]
    assert r.route("integrals").resolution == mcstat_float32_resolution()
    assert "every value a float32" in str(r)
    # the rounding is there (the mass of pdf() is not 1 in float32) and
    # still not evidence
    assert r.mass != 1.0 and abs(r.mass - 1.0) < 1e-7


def test_without_the_floor_the_rounding_is_significant():
    """The same data with the floor taken down to float64's: the old
    failure, which shows that the test above can fail."""
    reps = [_check(Isotropic(), seed, n=100_000, resolution=2.0 ** -47) for seed in range(5)]
    assert all(r.route("integrals").reject for r in reps)


def test_float32_ulp_weights_pass_energy():
    reps = [_check(Isotropic(ulp_weights=True), seed) for seed in range(20)]
    assert sum(r.reject for r in reps) <= _binomial_bound(20, 0.01)
    assert all(r.route("energy").state == "ran" and not r.route("energy").deterministic for r in reps)
    # without the floor the energy route sees the half-ulp bias of the mean
    low = _check(Isotropic(ulp_weights=True), 0, resolution=2.0 ** -47)
    assert low.route("energy").reject


def test_a_one_percent_error_is_still_caught_in_float32():
    reps = [_check(Isotropic(eval_scale=1.01), seed) for seed in range(20)]
    assert all(r.reject and r.route("integrals").reject for r in reps)


def test_resolution_is_derived_from_the_values():
    r64 = _check(Isotropic(dtype=np.float64), 0)
    assert r64.route("integrals").resolution == 2.0 ** -47
    assert "float64 values" in str(r64)
    r = _check(Isotropic(), 0, resolution=1e-5)
    assert r.route("integrals").resolution == 1e-5
    assert r.route("energy").resolution == 1e-5
    assert r.route("pdf_value").resolution is None  # deterministic: rtol is its tolerance


def mcstat_float32_resolution():
    return 2.0 ** -18


def mcstat_float64_resolution():
    return 2.0 ** -47


@pytest.mark.parametrize("bad", [-1e-6, 0.01, 0.5, float("nan"), float("inf")])
def test_resolution_out_of_range_is_refused(bad):
    with pytest.raises(mcstat.InvalidArgumentError, match="resolution"):
        _check(Isotropic(), 0, resolution=bad)


# ---- verdicts: consistent, inconsistent, inconclusive ------------------------------------

class CosineBsdf:
    """f |cos| = rho cos^2 * 3 / (2 pi) sampled exactly (pdf = 3 cos^2/(2 pi)
    on the hemisphere), weights rho.  wrong_cosine: eval() divides by the
    cosine where it should multiply, and sample() reuses it: weights
    rho / cos^2, heavy-tailed (tail index 1.5 under this pdf)."""

    def __init__(self, rho=0.8, wrong_cosine=False):
        self.rho, self.bug = rho, wrong_cosine

    def _pdf(self, wo):
        return np.where(wo[:, 2] > 0, 3.0 * wo[:, 2] ** 2 / (2 * np.pi), 0.0)

    def eval(self, wi, wo):
        c = np.maximum(wo[:, 2], 0.0)
        with np.errstate(divide="ignore"):
            return np.where(c > 0, self.rho * 3.0 / (2 * np.pi) * (1.0 if self.bug else c * c), 0.0)

    def pdf(self, wi, wo):
        return self._pdf(wo)

    def sample(self, wi, u):
        c = np.cbrt(1.0 - u[:, 0])  # cos^3 uniform: density 3 cos^2 in cos... times 1/(2 pi) in phi
        c = np.clip(c, 1e-12, 1.0)
        s = np.sqrt(np.maximum(0.0, 1.0 - c * c))
        phi = 2 * np.pi * u[:, 1]
        wo = np.stack([s * np.cos(phi), s * np.sin(phi), c], axis=1)
        p = self._pdf(wo)
        return wo, self.eval(wi, wo) / p, p


def test_heavy_tailed_weights_are_inconclusive_not_consistent():
    m = CosineBsdf(wrong_cosine=True)
    for seed in range(5):
        r = mcstat.check_bsdf(m.sample, m.eval, m.pdf, WI, n=20_000, seed=seed, alpha=0.01, domain="hemisphere")
        assert r.heavy_tailed
        assert not r.reject
        assert r.verdict == "inconclusive"
        assert {"integrals", "energy"} <= set(r.unanswered)
        assert "heavy-tailed" in r.route("energy").why
        text = str(r)
        assert "INCONCLUSIVE" in text and "consistent (no route rejected" not in text
        assert repr(r).startswith("<CheckReport inconclusive")


def test_correct_models_are_consistent_not_inconclusive():
    m = CosineBsdf()
    reps = [mcstat.check_bsdf(m.sample, m.eval, m.pdf, WI, n=10_000, seed=s, alpha=0.01, domain="hemisphere")
            for s in range(40)]
    verdicts = [r.verdict for r in reps]
    assert verdicts.count("inconclusive") == 0
    assert verdicts.count("inconsistent") <= _binomial_bound(40, 0.01)
    assert all(r.unanswered == [] for r in reps if r.verdict == "consistent")


def test_assertion_fails_on_inconclusive_unless_allowed():
    m = CosineBsdf(wrong_cosine=True)
    kw = dict(n=20_000, alpha=0.01, seed=3, escalate=0, domain="hemisphere")
    with pytest.raises(mt.StatisticalAssertionError, match=r"(?s)inconclusive at alpha.*could not answer:.*energy "):
        mt.assert_bsdf_consistent(m.sample, m.eval, m.pdf, WI, **kw)
    rep = mt.assert_bsdf_consistent(m.sample, m.eval, m.pdf, WI, allow_inconclusive=True, **kw)
    assert rep.verdict == "inconclusive"


# ---- a float32 peak through a caller's float64 renormalisation ---------------------

class HenyeyGreenstein32:
    """Henyey-Greenstein at g = 0.99 as a float32 renderer computes it (the
    sample's pdf from the cosine it drew; pdf() from the float32 dot product
    of the direction it is given), behind an adapter that renormalises the
    returned directions in float64, as examples/mitsuba's phase adapter
    did.  Near the forward peak the pdf changes by ~0.2% per float32 ulp of
    the cosine, so the two pdfs differ by 0.35% at a correct sample, and
    pdf_value and weight rejected at every seed (Mitsuba's hg, g = 0.99,
    20 of 20 in the null zoo).  pdf_g: pdf() and eval() with another g
    (the sampler then no longer draws what they claim)."""

    def __init__(self, g=0.99, pdf_g=None):
        self.g, self.pg = F32(g), F32(g if pdf_g is None else pdf_g)

    @staticmethod
    def _hg(c, g):
        t = F32(1) + g * g - F32(2) * g * c
        return (F32(1) - g * g) / (F32(4 * np.pi) * t * np.sqrt(t))

    @staticmethod
    def _frame(d):
        a = np.array([1, 0, 0], F32) if abs(d[0]) < 0.9 else np.array([0, 1, 0], F32)
        t1 = np.cross(d, a).astype(F32)
        t1 /= np.sqrt(np.sum(t1 * t1, dtype=F32))
        return t1, np.cross(d, t1).astype(F32)

    def sample(self, wi, u):
        u = np.minimum(u.astype(F32), np.nextafter(F32(1), F32(0)))
        g = self.g
        s = (F32(1) - g * g) / (F32(1) - g + F32(2) * g * u[:, 0])
        c = np.clip((F32(1) + g * g - s * s) / (F32(2) * g), F32(-1), F32(1)).astype(F32)
        r = np.sqrt(np.maximum(F32(0), F32(1) - c * c))
        phi = F32(2 * np.pi) * u[:, 1]
        d = (-np.asarray(wi, F32)).astype(F32)  # forward scattering continues along -wi
        t1, t2 = self._frame(d)
        wo = ((r * np.cos(phi))[:, None] * t1 + (r * np.sin(phi))[:, None] * t2 + c[:, None] * d).astype(F32)
        wo = wo.astype(np.float64)
        wo /= np.linalg.norm(wo, axis=1)[:, None]  # the adapter's renormalisation, in float64
        return wo, np.ones(len(u)), self._hg(c, g).astype(np.float64)

    def pdf(self, wi, wo):
        wo = np.asarray(wo).astype(F32)
        c = np.sum(-np.asarray(wi, F32) * wo, axis=1, dtype=F32)
        return self._hg(np.clip(c, F32(-1), F32(1)), self.pg).astype(np.float64)

    def eval(self, wi, wo):
        return self.pdf(wi, wo)


HG_WI = np.array([0.604023, 0.219846, 0.766044]) / np.linalg.norm([0.604023, 0.219846, 0.766044])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_float32_hg_peak_renormalised_in_float64_is_not_rejected(seed):
    m = HenyeyGreenstein32()
    r = mcstat.check_phase(m.sample, m.eval, m.pdf, HG_WI, n=20_000, seed=seed, alpha=0.01)
    assert not r.route("pdf_value").reject and not r.route("weight").reject, str(r)


def test_float32_hg_peak_with_the_float64_floor_is_rejected():
    """The control: the same model judged at float64's resolution (no
    float32 rounding allowed) is rejected, so the allowance is what passes it."""
    m = HenyeyGreenstein32()
    r = mcstat.check_phase(m.sample, m.eval, m.pdf, HG_WI, n=20_000, seed=0, alpha=0.01,
                           resolution=mcstat_float64_resolution())
    assert r.route("pdf_value").reject, str(r)


def test_float32_hg_with_a_wrong_g_is_still_caught():
    m = HenyeyGreenstein32(pdf_g=0.985)
    r = mcstat.check_phase(m.sample, m.eval, m.pdf, HG_WI, n=20_000, seed=0, alpha=0.01)
    assert r.reject and r.route("pdf_value").reject, str(r)
