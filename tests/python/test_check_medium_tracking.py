"""check_medium on a heterogeneous medium sampled by delta tracking: a ray
through four slabs of different sigma_t and albedo up to a surface,
tentative collisions drawn against a majorant and accepted with
probability sigma_t(t)/majorant.  The claims are exact: the density of the
first real collision is sigma_t(t) T(t) with T from the slabs' optical
depths, the weight sigma_s/sigma_t at it.  Correct, it passes (and the
calibration meta-test holds it to alpha over 200 seeds); the classic
tracking bugs are caught: a majorant below the largest sigma_t (the
acceptance clipped at 1), the weight divided by the majorant instead of
sigma_t, a tracker that restarts each tentative flight from the ray's
origin, and one that forgets the null collisions' count and uses the
homogeneous majorant's transmittance in its pdf
(reported and pdf() alike: only the sampled distances disagree).

sample() needs a random number of uniforms (about 2 majorant * tmax
per flight); it gets two from mcstat and derives the rest from them by
splitmix64: each flight is a pure function of its two uniforms, so the
flights stay independent and the check reproducible."""
import numpy as np
import pytest

import mcstat

EDGES = np.array([0.0, 0.3, 0.5, 0.8, 1.0])  # the last edge is the surface (tmax)
SIGMA_T = np.array([0.5, 4.0, 1.0, 2.5])
ALBEDO = np.array([0.9, 0.5, 0.8, 0.7])
TMAX = EDGES[-1]
MAJORANT = SIGMA_T.max()

_M1, _M2, _GOLDEN = np.uint64(0xBF58476D1CE4E5B9), np.uint64(0x94D049BB133111EB), np.uint64(0x9E3779B97F4A7C15)


def _splitmix(x):
    x = x + _GOLDEN
    x = (x ^ (x >> np.uint64(30))) * _M1
    x = (x ^ (x >> np.uint64(27))) * _M2
    return x ^ (x >> np.uint64(31))


def _stream(u):
    """Per flight, a function j -> the j-th derived uniform in [0, 1)."""
    key = (np.floor(u[:, 0] * 2.0**32).astype(np.uint64) << np.uint64(32)) | np.floor(u[:, 1] * 2.0**32).astype(
        np.uint64)

    def draw(j):
        with np.errstate(over="ignore"):
            return (_splitmix(key ^ _splitmix(np.full(len(key), j, dtype=np.uint64))) >> np.uint64(11)) * 2.0**-53

    return draw


def slab(t):
    return np.clip(np.searchsorted(EDGES, t, side="right") - 1, 0, len(SIGMA_T) - 1)


def optical_depth(t, sigma=SIGMA_T):
    t = np.minimum(np.asarray(t, float), TMAX)
    full = np.concatenate([[0.0], np.cumsum(sigma * np.diff(EDGES))])
    i = slab(t)
    return full[i] + sigma[i] * (t - EDGES[i])


class DeltaTracking:
    def __init__(self, bug=None):
        self.bug = bug

    def _density(self, t):
        t = np.asarray(t, float)
        inside = t < TMAX
        tt = np.where(inside, t, 0.0)
        st = SIGMA_T[slab(tt)]
        if self.bug == "pdf_majorant":  # T of the majorant's homogeneous medium
            d = st * np.exp(-MAJORANT * tt)
        else:
            d = st * np.exp(-optical_depth(tt))
        return np.where(inside, d, 0.0)

    def sample(self, u):
        draw = _stream(u)
        k = len(u)
        majorant = 0.8 * MAJORANT if self.bug == "majorant" else MAJORANT
        t = np.zeros(k)
        done = np.zeros(k, dtype=bool)
        hit = np.zeros(k, dtype=bool)
        j = 0
        while not done.all():
            step = -np.log1p(-draw(2 * j)) / majorant
            t = np.where(done, t, (step if self.bug == "restart" else t + step))
            if self.bug == "restart":  # each tentative flight from the origin, a running maximum kept
                t = np.where(done, t, np.maximum(t, step))
            out = ~done & (t >= TMAX)
            done |= out
            st = SIGMA_T[slab(np.minimum(t, TMAX))]
            real = ~done & (draw(2 * j + 1) < np.minimum(st / majorant, 1.0))
            hit |= real
            done |= real
            j += 1
        ti = np.where(hit, t, 0.0)
        s = slab(ti)
        p = np.where(hit, self._density(ti), 0.0)
        w = ALBEDO[s] * (SIGMA_T[s] / MAJORANT if self.bug == "weight" else 1.0)
        return ti, np.where(hit, w, 0.0), p

    def pdf(self, t):
        return self._density(t)

    def eval(self, t):
        """sigma_s T: the integrand of a scattering's contribution."""
        t = np.asarray(t, float)
        inside = t < TMAX
        tt = np.where(inside, t, 0.0)
        s = slab(tt)
        return np.where(inside, ALBEDO[s] * SIGMA_T[s] * np.exp(-optical_depth(tt)), 0.0)


def check(m, **kw):
    return mcstat.check_medium(m.sample, m.eval, m.pdf, sigma_ref=2.0, n_uniforms=2, **kw)


def test_correct_delta_tracking_passes():
    r = check(DeltaTracking(), n=20000, seed=1)
    assert not r.reject, str(r)
    escape = np.exp(-optical_depth(TMAX))
    assert r.mass == pytest.approx(1 - escape, abs=1e-4)
    assert abs(r.n_failed / r.n - escape) < 5 * np.sqrt(escape * (1 - escape) / r.n)
    # the albedo of the ray: the integral of sigma_s T over [0, tmax], closed form per slab
    tau = optical_depth(EDGES)
    albedo = np.sum(ALBEDO * (np.exp(-tau[:-1]) - np.exp(-tau[1:])))
    assert r.albedo == pytest.approx(albedo, rel=0.02)
    assert r.albedo_eval == pytest.approx(albedo, rel=0.01)


@pytest.mark.parametrize("bug, route", [("majorant", "cells"), ("weight", "weight"), ("restart", "cells"),
                                        ("pdf_majorant", "cells")])
def test_tracking_bugs_are_caught(bug, route):
    for seed in range(5):
        r = check(DeltaTracking(bug), n=20000, seed=seed)
        assert r.reject and r.route(route).reject, (seed, str(r))


@pytest.mark.stats
def test_delta_tracking_rejected_at_rate_alpha():
    """200 seeds at n = 4000, alpha = 0.05: the rejections not significantly
    above 5% (battery meta-test at 0.001)."""
    rejected = sum(check(DeltaTracking(), n=4000, seed=s, alpha=0.05).reject for s in range(200))
    meta = mcstat.battery_test(rejected, 0.05, n=200, alternative="greater", meta_alpha=0.001)
    assert not meta.reject, rejected
