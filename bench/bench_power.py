#!/usr/bin/env python3
"""Power of the renderer checks against the statistical limit and the peers
(make bench-power): for each planted bug, the sample count n90 at which a
test detects it with probability 0.9 at alpha = 0.01.

Tests compared, per (model, bug) case:
  - mcstat: the check a renderer would call (check_bsdf, check_phase,
    check_warp; t_test for an estimator), its defaults, alpha = 0.01;
    "stochastic" rows pass stochastic=True, which leaves out the
    deterministic routes (pdf_value, weight), as for a layered BSDF whose
    weight is not eval/pdf pointwise;
  - the oracle: the most powerful test that knows both the claimed model
    (H0) and the planted one (H1).  Sampler bugs: the Neyman-Pearson
    likelihood-ratio test of the drawn directions' density against the
    claimed one (failed samples included as an atom), critical value
    n*mu0 + z_0.99*sqrt(n)*sd0 from the exact-model moments of the
    log-ratio under H0 (normal approximation; its level is measured by
    simulation at the oracle's n90).  Weight and eval bugs: a one-sided z
    test of the mean weight against its known H0 mean and sd.  Estimator
    bias: the NP test of the known family (z on the mean for Gaussian
    estimates, z on the mean log for log-normal ones);
  - Mitsuba's chi2 (re-implemented from the published description of
    Mitsuba 3's chi2.py: SphericalDomain (phi, -cos theta), 50 x 101
    cells, the pdf integrated per cell by the trapezoid rule on 4 x 4
    points, cells sorted by expected count and pooled below 5, p-value of
    chi2(dof), reject at 0.01 or on samples in a cell of expectation 0);
    1e6 samples by default;
  - pbrt-v4's chi2 (bsdfs_test.cpp: 10 x 20 cells in (theta, phi), the pdf
    integrated over each cell (here 8 x 8 Gauss-Legendre points instead of
    adaptive Simpson), pooling below 5, 5 runs of n samples each at the
    Sidak-corrected level 1 - 0.99^(1/5), a failure in any run fails).
    pbrt's runs use 5 random incident directions; here all 5 use the
    checked one, the strongest version of that test for this case.

n90: the smallest n of a geometric grid (factor sqrt 2 from 1000) at which
the test rejects at >= 90% of the seeds (0..S-1, the same at every n;
every draw seeded).  A grid point stops early once more than 10% of the
seeds have missed (its rate is then known to be below 90%); the n90 point
and the point below it run all S seeds and are reported with their
Clopper-Pearson 95% intervals.

  python bench/bench_power.py [--seeds 40] [--only PATTERN] [--quick] [--write]
  python bench/bench_power.py --diagnose    # single routes, fixed cell counts
  python bench/bench_power.py --analytic    # the peers' n90 from their cells' noncentrality

Writes bench/RESULTS_power.md with --write (a --quick run never writes
it), keeping everything from its "<!-- diagnosis -->" marker on: the
diagnosis is written by hand from --diagnose and --analytic, which only
print.  One core: mcstat.set_num_threads(1), no worker processes.  No
timing is asserted; run times are written down.
"""
import argparse
import fnmatch
import math
import os
import platform
import sys
import time

import numpy as np
from scipy import special, stats

import mcstat

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from common import machine  # noqa: E402

ALPHA = 0.01
Z_A = stats.norm.isf(ALPHA)      # one-sided oracle tests
Z_B = stats.norm.isf(0.10)       # power 0.9 (analytic n90 of the oracle)
N_MIN = 1000                     # the checks refuse n < 1000
TWO_PI = 2 * np.pi


def grid(n_max, n_min=N_MIN, k0=0):
    """n_min * sqrt(2)^k for k >= k0 up to n_max (the oracles start below the
    checks' smallest n, k0 = -6: 125)."""
    g, k = [], k0
    while True:
        n = int(round(n_min * 2 ** (k / 2)))
        if n > n_max:
            return g
        g.append(n)
        k += 1


def direction(theta_deg, phi_deg=0.0):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def frame(d):
    s = math.copysign(1.0, d[2])
    a = -1.0 / (s + d[2])
    b = d[0] * d[1] * a
    return np.array([1 + s * d[0] ** 2 * a, s * b, -s * d[0]]), np.array([b, s + d[1] ** 2 * a, -d[1]])


def around(d, mu, phi):
    t1, t2 = frame(d)
    s = np.sqrt(np.maximum(0.0, 1 - mu * mu))
    return mu[:, None] * d + s[:, None] * (np.cos(phi)[:, None] * t1 + np.sin(phi)[:, None] * t2)


# ---- direction densities: draw(u) -> (x, ok), density(x) ------------------------------
# ok False marks a failed sample (no direction); density integrates to the
# success probability.

class GGX:
    """Isotropic GGX reflection (perfect conductor, F = 1), normals drawn
    from D(h) cos(theta_h), wi fixed; wo below the horizon fails."""

    def __init__(self, alpha, wi):
        self.a, self.wi = alpha, wi

    def D(self, c):
        a2 = self.a ** 2
        return a2 / (np.pi * ((a2 - 1) * c * c + 1) ** 2)

    def G1(self, z):
        t2 = np.maximum(1 - z * z, 0) / np.maximum(z * z, 1e-300)
        return 2 / (1 + np.sqrt(1 + self.a ** 2 * t2))

    def draw(self, u):
        u0 = u[:, 0]
        t2 = self.a ** 2 * u0 / np.maximum(1 - u0, 1e-300)
        ch = 1 / np.sqrt(1 + t2)
        sh = np.sqrt(np.maximum(0, 1 - ch * ch))
        ph = TWO_PI * u[:, 1]
        h = np.stack([sh * np.cos(ph), sh * np.sin(ph), ch], axis=1)
        d = h @ self.wi
        x = 2 * d[:, None] * h - self.wi
        ok = (x[:, 2] > 0) & (d > 0)
        return x, ok

    def density(self, x):
        h = x + self.wi
        h = h / np.maximum(np.linalg.norm(h, axis=1), 1e-300)[:, None]
        oh = np.einsum("ij,ij->i", x, h)
        good = (x[:, 2] > 0) & (oh > 0) & (h[:, 2] > 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            p = self.D(h[:, 2]) * h[:, 2] / (4 * oh)
        return np.where(good, p, 0.0)

    def value(self, x):
        """f * cos(theta_o)."""
        h = x + self.wi
        h = h / np.maximum(np.linalg.norm(h, axis=1), 1e-300)[:, None]
        good = (x[:, 2] > 0) & (h[:, 2] > 0)
        f = self.D(h[:, 2]) * self.G1(self.wi[2]) * self.G1(x[:, 2]) / (4 * self.wi[2])
        return np.where(good, f, 0.0)


class Lambert:
    def __init__(self, rho=0.8):
        self.rho = rho

    def draw(self, u):
        r, ph = np.sqrt(u[:, 0]), TWO_PI * u[:, 1]
        z = np.sqrt(np.maximum(0, 1 - u[:, 0]))
        return np.stack([r * np.cos(ph), r * np.sin(ph), z], axis=1), z > 0

    def density(self, x):
        return np.where(x[:, 2] > 0, x[:, 2] / np.pi, 0.0)

    def value(self, x):
        return self.rho * self.density(x)


class Mixture:
    """A lobe picked with probability s by u[:, 2]: s GGX + (1 - s) Lambert."""

    def __init__(self, s, a, b):
        self.s, self.a, self.b = s, a, b

    def draw(self, u):
        xa, oka = self.a.draw(u)
        xb, okb = self.b.draw(u)
        pick = u[:, 2] < self.s
        return np.where(pick[:, None], xa, xb), np.where(pick, oka, okb)

    def density(self, x):
        return self.s * self.a.density(x) + (1 - self.s) * self.b.density(x)

    def value(self, x):
        return 0.5 * self.a.value(x) + 0.5 * self.b.value(x)


class HG:
    """Henyey-Greenstein of mu = wo . (-wi) (g > 0 forward), eval = pdf."""

    def __init__(self, g, wi):
        self.g, self.wi = g, wi

    def draw(self, u):
        g = self.g
        q = (1 - g * g) / (1 - g + 2 * g * u[:, 0])
        mu = np.clip((1 + g * g - q * q) / (2 * g), -1.0, 1.0)
        return around(-self.wi, mu, TWO_PI * u[:, 1]), np.ones(len(u), bool)

    def density(self, x):
        g, mu = self.g, x @ (-self.wi)
        return (1 - g * g) / (4 * np.pi * (1 + g * g - 2 * g * mu) ** 1.5)

    value = density


class CosPow:
    """The warp cos^e on the hemisphere around +z (e = 1: cosine hemisphere)."""

    def __init__(self, e):
        self.e = e

    def draw(self, u):
        z = u[:, 0] ** (1 / (self.e + 1))
        r = np.sqrt(np.maximum(0, 1 - z * z))
        ph = TWO_PI * u[:, 1]
        return np.stack([r * np.cos(ph), r * np.sin(ph), z], axis=1), z > 0

    def density(self, x):
        return np.where(x[:, 2] > 0, (self.e + 1) / TWO_PI * np.maximum(x[:, 2], 0) ** self.e, 0.0)


class Scaled:
    """pdf() of `base` times `factor` where x[:, 1] > 0, divided by `norm`
    (a density that is `factor` high on half the domain)."""

    def __init__(self, base, factor, norm=1.0):
        self.base, self.factor, self.norm = base, factor, norm

    def density(self, x):
        return self.base.density(x) * np.where(x[:, 1] > 0, self.factor, 1.0) / self.norm


# ---- cases ---------------------------------------------------------------------------------

class Case:
    """One (model, bug): `truth` draws (sampler of H1), `claim` is pdf(),
    `eval_claim` eval(), `wfac` multiplies the weight eval_true/pdf_claim;
    kind: bsdf / phase / warp / estimator; oracle: "lr", "z", "na" or the
    estimator's; chi2: whether sample() and pdf() disagree (the chi2 tests
    see only that)."""

    def __init__(self, model, bug, kind, truth=None, claim=None, eval_true=None, eval_claim=None, wfac=1.0,
                 oracle="lr", chi2=True, wi=None, domain="hemisphere", stochastic=False, note="",
                 estimator=None):
        self.model, self.bug, self.kind = model, bug, kind
        self.truth, self.claim = truth, claim
        self.eval_true, self.eval_claim = eval_true, eval_claim
        self.wfac, self.oracle, self.chi2 = wfac, oracle, chi2
        self.wi, self.domain, self.stochastic, self.note = wi, domain, stochastic, note
        self.estimator = estimator

    @property
    def name(self):
        return f"{self.model} / {self.bug}" + (" (stochastic)" if self.stochastic else "")

    # the callables mcstat gets
    def callables(self):
        truth, claim = self.truth, self.claim
        et, ec, wf = self.eval_true, self.eval_claim, self.wfac

        def sample(*args):
            u = args[-1]
            x, ok = truth.draw(u)
            x = np.where(ok[:, None], x, np.array([0.0, 0.0, 1.0]))
            p = np.where(ok, claim.density(x), 0.0)
            if et is None:
                return x
            with np.errstate(divide="ignore", invalid="ignore"):
                w = np.where(p > 0, wf * et(x) / p, 0.0)
            return x, w, p

        def pdf(*args):
            return claim.density(args[-1])

        def eval_(wi, x):
            return ec(x)

        return sample, eval_, pdf

    def mcstat_run(self, n, seed):
        if self.kind == "estimator":
            x = self.estimator.draw(n, seed, biased=True)
            r = mcstat.t_test(x, mu=self.estimator.mean, alpha=ALPHA)
            return bool(r.pvalue <= ALPHA), ["t"]
        s, e, p = self.callables()
        kw = dict(n=n, seed=seed, alpha=ALPHA)
        if self.kind == "warp":
            r = mcstat.check_warp(s, p, domain=self.domain, **kw)
        elif self.kind == "phase":
            r = mcstat.check_phase(s, e, p, self.wi, stochastic=self.stochastic, **kw)
        else:
            r = mcstat.check_bsdf(s, e, p, self.wi, domain=self.domain, stochastic=self.stochastic, **kw)
        return bool(r.reject), [x.name for x in r.routes if x.reject]


# ---- the oracle ---------------------------------------------------------------------------

class LROracle:
    """NP test of H0: draws follow `claim` (success mass m0) against H1:
    they follow `truth` (m1).  l(x) = log truth/claim, failures log((1-m1)/(1-m0)).
    H0 moments of l by importance weighting draws of H1 (weight claim/truth),
    from `pool` fixed-seed draws."""

    def __init__(self, truth, claim, pool, seed=987_654):
        self.truth, self.claim = truth, claim
        u = np.random.default_rng(seed).random((pool, 3))
        x, ok = truth.draw(u)
        p1, p0 = truth.density(x), claim.density(x)
        m1 = ok.mean()
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(ok, p0 / p1, 0.0)
        m0 = float(np.mean(r))  # the claim's success mass, E1[claim/truth on successes]
        self.m0, self.m1 = m0, m1
        self.fail = math.log((1 - m1) / (1 - m0)) if m1 < 1 and m0 < 1 else 0.0
        lv = self._l(x, ok, p1, p0)
        w = np.where(ok, r, (1 - m0) / (1 - m1) if m1 < 1 else 0.0)
        self.mu1, self.sd1 = float(lv.mean()), float(lv.std())
        self.mu0 = float(np.sum(w * lv) / np.sum(w))
        self.sd0 = float(np.sqrt(np.sum(w * (lv - self.mu0) ** 2) / np.sum(w)))

    def _l(self, x, ok, p1, p0):
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(ok, np.log(p1 / p0), self.fail)

    def statistic(self, n, seed, null=False):
        rng = np.random.default_rng([seed, 77])
        src = self.claim_sampler if null else self.truth
        x, ok = src.draw(rng.random((n, 3)))
        return float(self._l(x, ok, self.truth.density(x), self.claim.density(x)).sum())

    def reject(self, n, seed, null=False):
        return self.statistic(n, seed, null) > n * self.mu0 + Z_A * math.sqrt(n) * self.sd0

    def n90(self):
        d = self.mu1 - self.mu0
        return ((Z_A * self.sd0 + Z_B * self.sd1) / d) ** 2 if d > 0 else math.inf

    claim_sampler = None  # set where the claim has a sampler of its own (level check)


class ZOracle:
    """One-sided z test of the mean weight against its H0 mean and sd (known):
    H0 weights eval_claim/pdf_claim, H1 the weights sample() returns; both at
    the sampler's draws (failures weigh 0)."""

    def __init__(self, case, pool, seed=987_655):
        self.case = case
        u = np.random.default_rng(seed).random((pool, 3))
        w0, w1 = self._weights(u)
        self.mu0, self.sd0 = float(w0.mean()), float(w0.std())
        self.mu1, self.sd1 = float(w1.mean()), float(w1.std())
        self.sign = 1.0 if self.mu1 >= self.mu0 else -1.0

    def _weights(self, u):
        c = self.case
        x, ok = c.truth.draw(u)
        p = c.claim.density(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            w0 = np.where(ok & (p > 0), c.eval_claim(x) / p, 0.0)
            w1 = np.where(ok & (p > 0), c.wfac * c.eval_true(x) / p, 0.0)
        return w0, w1

    def reject(self, n, seed, null=False):
        u = np.random.default_rng([seed, 78]).random((n, 3))
        w = self._weights(u)[0 if null else 1]
        if self.sd0 == 0:
            return bool(np.any(w != self.mu0)) if not null else False
        z = (w.mean() - self.mu0) / (self.sd0 / math.sqrt(n))
        return bool(self.sign * z > Z_A)

    def n90(self):
        d = abs(self.mu1 - self.mu0)
        if self.sd0 == 0:
            return 1.0
        return ((Z_A * self.sd0 + Z_B * self.sd1) / d) ** 2 if d > 0 else math.inf


class Estimator:
    """Per-sample estimates of a quantity whose value is 1: "gauss" N(1, 1);
    "lognormal" exp(s Z - s^2/2), s = 1.  biased: times 1.01 (lognormal) or
    plus 0.01 (gauss): bias 1%."""

    def __init__(self, kind):
        self.kind, self.mean, self.s = kind, 1.0, 1.0

    def draw(self, n, seed, biased):
        z = np.random.default_rng([seed, 79]).standard_normal(n)
        if self.kind == "gauss":
            return 1.0 + z + (0.01 if biased else 0.0)
        return np.exp(self.s * z - self.s ** 2 / 2) * (1.01 if biased else 1.0)

    # the NP oracle: z on the mean (gauss) or on the mean log (lognormal), known sd
    def oracle_reject(self, n, seed, null=False):
        x = self.draw(n, seed, biased=not null)
        if self.kind == "gauss":
            t = (x.mean() - 1.0) * math.sqrt(n)
        else:
            t = (np.log(x).mean() + self.s ** 2 / 2) / self.s * math.sqrt(n)
        return t > Z_A

    def oracle_n90(self):
        d = 0.01 if self.kind == "gauss" else math.log(1.01) / self.s
        return ((Z_A + Z_B) / d) ** 2


# ---- chi2 tests of the peers ----------------------------------------------------------------

def _pool_mitsuba(obs, exp, thr=5.0):
    """Mitsuba's chi2(): cells sorted by expectation, low ones pooled in order."""
    keep = ~((exp == 0) & (obs == 0))
    obs, exp = obs[keep], exp[keep]
    high = exp >= thr
    chsq = float(np.sum((obs[high] - exp[high]) ** 2 / exp[high]))
    dof = int(high.sum())
    lo_o, lo_e = obs[~high], exp[~high]
    if lo_e.size:
        ce = np.cumsum(lo_e)
        co = np.cumsum(lo_o)
        # close a pool each time the running expectation exceeds thr
        start_e, start_o = 0.0, 0.0
        i = 0
        while i < lo_e.size:
            j = int(np.searchsorted(ce, start_e + thr, side="right"))
            if j >= lo_e.size:
                break
            pe, po = ce[j] - start_e, co[j] - start_o
            chsq += (po - pe) ** 2 / pe
            dof += 1
            start_e, start_o = ce[j], co[j]
            i = j + 1
    return chsq, dof - 1


class MitsubaChi2:
    RES_X, RES_Y, IRES = 50, 101, 4  # int(101 / aspect 2) x 101 cells in (phi, -cos theta)

    def __init__(self, claim):
        rx, ry, k = self.RES_X, self.RES_Y, self.IRES
        cw, ch = TWO_PI / rx, 2.0 / ry
        t = (np.arange(k) + 1e-4) * (1 - 2e-4) / (k - 1)  # Mitsuba's points, in cell units
        wt = np.where((np.arange(k) == 0) | (np.arange(k) == k - 1), 0.5, 1.0)
        ix, iy = np.meshgrid(np.arange(rx), np.arange(ry), indexing="xy")
        px = -np.pi + (ix.ravel()[:, None] + t[None, :]) * cw            # (cells, k)
        py = -1.0 + (iy.ravel()[:, None] + t[None, :]) * ch
        PX = np.repeat(px[:, None, :], k, axis=1)                          # (cells, ky, kx)
        PY = np.repeat(py[:, :, None], k, axis=2)
        ct = -PY
        st = np.sqrt(np.maximum(0, 1 - ct * ct))
        x = np.stack([np.cos(PX) * st, np.sin(PX) * st, ct], axis=-1).reshape(-1, 3)
        f = claim.density(x).reshape(PX.shape)
        W = wt[:, None] * wt[None, :] * (cw / (k - 1)) * (ch / (k - 1))
        self.table = (f * W).sum(axis=(1, 2))                               # cell index ix + iy * rx

    def reject(self, x, ok, n):
        rx, ry = self.RES_X, self.RES_Y
        ph = np.arctan2(x[:, 1], x[:, 0])
        y = -x[:, 2]
        ix = np.clip(((ph + np.pi) / TWO_PI * rx).astype(np.int64), 0, rx - 1)
        iy = np.clip(((y + 1) / 2 * ry).astype(np.int64), 0, ry - 1)
        hist = np.bincount((ix + iy * rx)[ok], minlength=rx * ry).astype(float)
        exp = self.table * n
        if np.any((exp == 0) & (hist > 0)):
            return True
        order = np.argsort(exp, kind="stable")
        chsq, dof = _pool_mitsuba(hist[order], exp[order])
        if dof < 1:
            return True
        p = special.gammaincc(dof / 2, chsq / 2)
        return not (p >= ALPHA)


class PbrtChi2:
    TH, PH, RUNS, Q = 10, 20, 5, 8

    def __init__(self, claim):
        g, gw = np.polynomial.legendre.leggauss(self.Q)
        dt, dp = np.pi / self.TH, TWO_PI / self.PH
        it, ip = np.meshgrid(np.arange(self.TH), np.arange(self.PH), indexing="ij")
        th = (it.ravel()[:, None] + (g[None, :] + 1) / 2) * dt           # (cells, q)
        ph = (ip.ravel()[:, None] + (g[None, :] + 1) / 2) * dp
        TH = np.repeat(th[:, :, None], self.Q, axis=2)
        PH = np.repeat(ph[:, None, :], self.Q, axis=1)
        x = np.stack([np.sin(TH) * np.cos(PH), np.sin(TH) * np.sin(PH), np.cos(TH)], axis=-1).reshape(-1, 3)
        f = claim.density(x).reshape(TH.shape) * np.sin(TH)
        W = (gw[:, None] * gw[None, :]) * (dt / 2) * (dp / 2)
        self.table = (f * W).sum(axis=(1, 2))                               # cell it * PH + ip
        self.level = 1 - (1 - ALPHA) ** (1 / self.RUNS)

    def reject_run(self, x, ok, n):
        th = np.arccos(np.clip(x[:, 2], -1, 1))
        ph = np.arctan2(x[:, 1], x[:, 0])
        ph = np.where(ph < 0, ph + TWO_PI, ph)
        it = np.clip(np.floor(th * self.TH / np.pi).astype(np.int64), 0, self.TH - 1)
        ip = np.clip(np.floor(ph * self.PH / TWO_PI).astype(np.int64), 0, self.PH - 1)
        obs = np.bincount((it * self.PH + ip)[ok], minlength=self.TH * self.PH).astype(float)
        exp = self.table * n
        order = np.argsort(exp, kind="stable")
        chsq, dof, po, pe = 0.0, 0, 0.0, 0.0
        for i in order:
            e, o = exp[i], obs[i]
            if e == 0:
                if o > n * 1e-5:
                    return True
            elif e < 5 or (0 < pe < 5):
                po += o
                pe += e
            else:
                chsq += (o - e) ** 2 / e
                dof += 1
        if pe > 0 or po > 0:
            chsq += (po - pe) ** 2 / pe
            dof += 1
        dof -= 1
        if dof <= 0:
            return True
        p = 1 - special.gammainc(0.5 * dof, 0.5 * chsq)
        return not (p >= self.level)


# ---- the cases -----------------------------------------------------------------------------

def cases(pool):
    out = []
    wi_b = direction(40.0)
    a = 0.3
    ggx = GGX(a, wi_b)

    def bsdf(bug, truth, claim, **kw):
        kw.setdefault("eval_true", ggx.value)
        kw.setdefault("eval_claim", ggx.value)
        return Case("GGX a=0.3, wi 40deg", bug, "bsdf", truth=truth, claim=claim, wi=wi_b, **kw)

    out.append(bsdf("sampler alpha x1.02", GGX(a * 1.02, wi_b), ggx))
    out.append(bsdf("sampler alpha x1.05", GGX(a * 1.05, wi_b), ggx))
    out.append(bsdf("pdf 3% high on y>0, renormalised", ggx, Scaled(ggx, 1.03, 1.015)))
    # pdf() integrates to 1.015 x 0.879 < 1 here (12% of the samples fail): a claim an NP test can face
    out.append(bsdf("pdf 3% high on y>0", ggx, Scaled(ggx, 1.03)))
    for st in (False, True):
        out.append(bsdf("weight 3% high", ggx, ggx, wfac=1.03, oracle="z" if st else "det", chi2=False,
                        stochastic=st))
        out.append(bsdf("eval missing cos", ggx, ggx, eval_claim=lambda x: ggx.value(x) / np.maximum(x[:, 2], 1e-12),
                        oracle="z" if st else "det", chi2=False, stochastic=st))
    lam = Lambert(0.8)
    mix, mix_bug = Mixture(0.5, ggx, lam), Mixture(0.5 * 1.05, ggx, lam)
    out.append(Case("GGX 0.3 + Lambert 0.8, s=0.5", "lobe pick x1.05", "bsdf", truth=mix_bug, claim=mix,
                    eval_true=mix.value, eval_claim=mix.value, wi=wi_b))
    wi_p = direction(30.0)
    hg = HG(0.7, wi_p)

    def phase(bug, truth, claim, **kw):
        kw.setdefault("eval_true", hg.value)
        kw.setdefault("eval_claim", hg.value)
        return Case("HG g=0.7", bug, "phase", truth=truth, claim=claim, wi=wi_p, domain="sphere", **kw)

    out.append(phase("sampler g x1.02", HG(0.7 * 1.02, wi_p), hg))
    out.append(phase("sampler g x1.05", HG(0.7 * 1.05, wi_p), hg))
    # a phase function's eval() is its pdf(): the bug sits in the routine both share
    q, q_lit = Scaled(hg, 1.03, 1.015), Scaled(hg, 1.03)
    out.append(phase("pdf 3% high on y>0, renormalised", hg, q, eval_true=q.density, eval_claim=q.density))
    out.append(phase("pdf 3% high on y>0", hg, q_lit, eval_true=q_lit.density, eval_claim=q_lit.density,
                     oracle="na"))
    for st in (False, True):
        out.append(phase("weight 3% high", hg, hg, wfac=1.03, oracle="z" if st else "det", chi2=False,
                         stochastic=st))
    cw = CosPow(1.0)

    def warp(bug, truth, claim, **kw):
        return Case("cosine hemisphere warp", bug, "warp", truth=truth, claim=claim, **kw)

    out.append(warp("sampler exponent x1.02", CosPow(1.02), cw))
    out.append(warp("sampler exponent x1.05", CosPow(1.05), cw))
    out.append(warp("pdf 3% high on y>0, renormalised", cw, Scaled(cw, 1.03, 1.015)))
    out.append(warp("pdf 3% high on y>0", cw, Scaled(cw, 1.03), oracle="na"))
    for kind, label in (("gauss", "estimator N(1,1)"), ("lognormal", "estimator lognormal s=1")):
        out.append(Case(label, "bias 1%", "estimator", oracle="est", chi2=False, estimator=Estimator(kind)))
    return out


# ---- the search -------------------------------------------------------------------------------

def cp_interval(k, n, level=0.95):
    a = (1 - level) / 2
    lo = stats.beta.ppf(a, k, n - k + 1) if k > 0 else 0.0
    hi = stats.beta.ppf(1 - a, k + 1, n - k) if k < n else 1.0
    return lo, hi


def rate_at(run, n, seeds, early=True):
    """Rejections over seeds at n; with early, stop once > 10% missed."""
    k, miss, done, extra = 0, 0, 0, {}
    allowed = seeds - math.ceil(0.9 * seeds)
    for s in range(seeds):
        res = run(n, s)
        rej, info = res if isinstance(res, tuple) else (res, None)
        done += 1
        if rej:
            k += 1
            for r in info or ():
                extra[r] = extra.get(r, 0) + 1
        else:
            miss += 1
            if early and miss > allowed:
                break
    return k, done, extra


def search(run, ns, seeds, log=None):
    """The smallest n of ns at which run rejects at >= 90% of seeds."""
    prev = None
    for i, n in enumerate(ns):
        k, done, extra = rate_at(run, n, seeds)
        if log:
            log(f"    n={n}: {k}/{done}")
        if done == seeds and k >= math.ceil(0.9 * seeds):
            below = None
            if i > 0:
                kb, db, _ = rate_at(run, ns[i - 1], seeds, early=False)
                below = (ns[i - 1], kb, db)
            return dict(n90=n, k=k, seeds=seeds, routes=extra, below=below)
        prev = (n, k, done)
    return dict(n90=None, last=prev, seeds=seeds)


# ---- formatting ---------------------------------------------------------------------------------

def fmt_n(n):
    if n is None:
        return "-"
    if n >= 1e6:
        return f"{n / 1e6:.3g}M"
    if n >= 1e4:
        return f"{n / 1e3:.0f}k"
    if n >= 1e3:
        return f"{n / 1e3:.3g}k"
    return f"{n:.3g}"


def fmt_search(r, n_max, scale=1):
    if r is None:
        return "-"
    if r.get("det"):
        return r["det"]
    if r["n90"] is None:
        last = r["last"]
        tail = f" ({last[1]}/{last[2]} at {fmt_n(last[0] * scale)})" if last else ""
        return f"> {fmt_n(n_max * scale)}{tail}"
    lo, hi = cp_interval(r["k"], r["seeds"])
    floor = "<= " if not r.get("below") else ""
    s = f"{floor}{fmt_n(r['n90'] * scale)} ({r['k']}/{r['seeds']}, CI {lo:.2f}-{hi:.2f}"
    if r.get("below"):
        nb, kb, db = r["below"]
        lo2, hi2 = cp_interval(kb, db)
        s += f"; {kb}/{db} at {fmt_n(nb * scale)}, CI {lo2:.2f}-{hi2:.2f}"
    return s + ")"


def ratio(a, b):
    """n90 ratio a/b with the censoring written out."""
    if a is None or b is None:
        return "-"
    if len(a) > 2 and a[2]:
        # a at the checks' smallest n: an upper bound only, none when b is there too
        return "- (floor)" if len(b) > 2 and b[2] else "<= %.3g" % (a[0] / b[0])
    if len(b) > 2 and b[2]:
        return ">= %.3g" % (a[0] / b[0])
    (va, ca), (vb, cb) = a[:2], b[:2]
    if ca and cb:
        return "?"
    r = va / vb
    if ca:
        return f"> {r:.3g}"
    if cb:
        return f"< {r:.3g}"
    return f"{r:.3g}"


def n90_value(r, n_max):
    """(value, censored) for a search result; None when blind."""
    if r is None:
        return None
    if r.get("det"):
        return (r["value"], False, True)
    if r["n90"] is None:
        return (n_max, True)
    return (r["n90"], False, not r.get("below"))


def environment():
    import scipy
    return (f"{machine()}; Python {platform.python_version()}, NumPy {np.__version__}, SciPy {scipy.__version__}, "
            f"mcstat {mcstat.__version__}")


# ---- diagnosis: which route, which alpha split, which cell layout ------------------------------

DIAG_CASES = ("cosine hemisphere warp / sampler exponent x1.05", "HG g=0.7 / pdf 3% high on y>0, renormalised",
              "GGX a=0.3, wi 40deg / sampler alpha x1.05", "GGX 0.3 + Lambert 0.8, s=0.5 / lobe pick x1.05",
              "cosine hemisphere warp / sampler exponent x1.02")


def diagnose(a, log):
    """n90 of mcstat's check restricted to one route and to a fixed cell
    count (options routes= and cells=; the library is not changed)."""
    ns = grid(a.n_max)
    L = ["| case | configuration | n90 | cells at n90 | n90 / oracle n90 |", "|---|---|---|---:|---:|"]
    by_name = {c.name: c for c in cases(a.pool)}
    for name in DIAG_CASES:
        if not fnmatch.fnmatch(name, a.only):
            continue
        c = by_name[name]
        o = LROracle(c.truth, c.claim, a.pool)
        orc = search(lambda n, s: o.reject(n, s), grid(a.n_max, k0=-6), a.seeds)
        configs = [("full check (default)", {}), ("cells route alone, automatic cells", dict(routes=["cells"]))]
        for k in (16, 64, 256):
            configs.append((f"cells route alone, cells={k}", dict(routes=["cells"], cells=k)))
        configs.append(("full check, cells=16", dict(cells=16)))
        if c.kind != "warp":
            configs.append(("integrals route alone", dict(routes=["integrals"])))
        s_, e_, p_ = c.callables()
        for label, kw in configs:
            cells_seen = {}

            def run(n, seed, kw=kw):
                base = dict(n=n, seed=seed, alpha=ALPHA, **kw)
                if c.kind == "warp":
                    r = mcstat.check_warp(s_, p_, domain=c.domain, **base)
                elif c.kind == "phase":
                    r = mcstat.check_phase(s_, e_, p_, c.wi, **base)
                else:
                    r = mcstat.check_bsdf(s_, e_, p_, c.wi, domain=c.domain, **base)
                cells_seen[n] = r.cells
                return bool(r.reject), [x.name for x in r.routes if x.reject]

            log(f"  {name}: {label}")
            r = search(run, ns, a.seeds, log)
            mv, ov = n90_value(r, ns[-1]), n90_value(orc, ns[-1])
            L.append(f"| {name} | {label} | {fmt_search(r, ns[-1])} | "
                     f"{cells_seen.get(r['n90'], '-') if r['n90'] else '-'} | {ratio(mv, ov)} |")
            print(L[-1], flush=True)
    return L


def noncentrality(df, alpha, power=0.9):
    """The noncentrality a chi2(df) test at alpha needs for the given power."""
    from scipy import optimize
    c = stats.chi2.isf(alpha, df)
    return optimize.brentq(lambda lam: stats.ncx2.sf(c, df, lam) - power, 1e-6, 1e7)


def analytic(a):
    """Predicted n90 of the chi2 peers: lambda(df) / D, D = sum (p1 - p0)^2 / p0
    over their cells (pooling ignored), against the oracle's 13.0 / Var(l)."""
    L = ["| case | oracle: Var(l) under H1, 13.0 / Var(l) | Mitsuba: df, D, lambda(df), n90 | "
         "pbrt: df, D, 5 x lambda / D at 1 - 0.99^(1/5), power 1 - 0.1^(1/5) a run |", "|---|---|---|---|"]
    for c in cases(a.pool):
        if not c.chi2 or c.oracle != "lr" or not fnmatch.fnmatch(c.name, a.only):
            continue
        o = LROracle(c.truth, c.claim, a.pool)
        cells = []
        for T, alpha, pw, runs in ((MitsubaChi2, ALPHA, 0.9, 1),
                                   (PbrtChi2, 1 - (1 - ALPHA) ** 0.2, 1 - 0.1 ** 0.2, 5)):
            t0, t1 = T(c.claim).table, T(c.truth).table
            keep = t0 > 1e-7
            d = float(np.sum((t1[keep] - t0[keep]) ** 2 / t0[keep]))
            df = int(keep.sum()) - 1
            lam = noncentrality(df, alpha, pw)
            cells.append(f"{df}, {d:.3g}, {lam:.0f}, {fmt_n(runs * lam / d)}")
        L.append(f"| {c.name} | {o.sd1 ** 2:.3g}, {fmt_n(13.0 / o.sd1 ** 2)} | {cells[0]} | {cells[1]} |")
    L += ["", "Noncentrality a chi2 test needs for power 0.9 (the one-sided z / NP test: 13.0):", "",
          "| df | alpha 0.01 | alpha 0.005 | alpha 0.0025 |", "|---:|---:|---:|---:|"]
    for df in (1, 15, 31, 63, 127, 255, 511, 1023, 5049):
        L.append(f"| {df} | " + " | ".join(f"{noncentrality(df, x):.1f}" for x in (0.01, 0.005, 0.0025)) + " |")
    return L


# ---- main ---------------------------------------------------------------------------------------

def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=40)
    ap.add_argument("--n-max", type=float, default=1.5e6, help="largest n of mcstat's and the oracle's grid")
    ap.add_argument("--chi2-n-max", type=float, default=8.5e6, help="largest sample count of the chi2 grids")
    ap.add_argument("--pool", type=int, default=4_000_000, help="fixed-seed draws for the oracles' moments")
    ap.add_argument("--only", default="*", help="fnmatch pattern on 'model / bug'")
    ap.add_argument("--quick", action="store_true", help="smoke run: 6 seeds, small grids, a few cases")
    ap.add_argument("--no-chi2", action="store_true")
    ap.add_argument("--write", action="store_true", help="write bench/RESULTS_power.md")
    ap.add_argument("--diagnose", action="store_true",
                    help="instead: n90 of single routes and fixed cell counts on the worst cases (markdown)")
    ap.add_argument("--analytic", action="store_true",
                    help="instead: the chi2 peers' n90 predicted from their cells' noncentrality (markdown)")
    a = ap.parse_args(argv)
    if a.quick:
        a.seeds, a.n_max, a.chi2_n_max, a.pool = 6, 1.7e4, 1.7e4, 200_000
        if a.only == "*":
            a.only = "*sampler*x1.05*"
    mcstat.set_num_threads(1)
    t_start = time.time()
    log = (lambda s: print(s, file=sys.stderr, flush=True))
    if a.analytic:
        L = analytic(a)
        print(f"\n`bench/bench_power.py --analytic`, {time.time() - t_start:.0f} s\n")
        print("\n".join(L))
        return L
    if a.diagnose:
        L = diagnose(a, log)
        print(f"\n`bench/bench_power.py --diagnose --seeds {a.seeds}`, {time.time() - t_start:.0f} s; "
              f"{environment()}\n")
        print("\n".join(L))
        return L
    env0 = environment()
    ns, ns_chi2 = grid(a.n_max), grid(a.chi2_n_max)
    ns_o = grid(a.n_max, k0=-6)
    rows, details = [], []
    for c in cases(a.pool):
        if not fnmatch.fnmatch(c.name, a.only):
            continue
        t0 = time.time()
        log(f"{c.name}")
        res = {}
        # mcstat
        log("  mcstat")
        res["mcstat"] = search(c.mcstat_run, ns, a.seeds, log)
        # oracle
        oracle_text, o_an, level = "", None, None
        if c.oracle == "lr":
            o = LROracle(c.truth, c.claim, a.pool)
            o_an = o.n90()
            log(f"  oracle LR (analytic n90 {o_an:.4g})")
            res["oracle"] = search(lambda n, s: o.reject(n, s), ns_o, a.seeds, log)
            oracle_text = "NP likelihood ratio" + (f" (failures an atom: mass {o.m0:.3f} claimed, {o.m1:.3f} drawn)"
                                                   if o.m1 < 1 else "")
            if res["oracle"]["n90"] and isinstance(c.claim, (GGX, HG, CosPow, Mixture)):
                o.claim_sampler = c.claim
                nn = res["oracle"]["n90"]
                reps = 200
                level = (sum(o.reject(nn, 10_000 + s, null=True) for s in range(reps)), reps, nn)
        elif c.oracle == "z":
            o = ZOracle(c, a.pool)
            o_an = o.n90()
            log(f"  oracle z (analytic n90 {o_an:.4g})")
            if o.sd0 == 0:
                res["oracle"] = dict(det="1 (H0 weights constant)", value=1)
            else:
                res["oracle"] = search(lambda n, s: o.reject(n, s), ns_o, a.seeds, log)
                if res["oracle"]["n90"] is None:
                    pass
            oracle_text = "z on the mean weight"
        elif c.oracle == "det":
            res["oracle"] = dict(det="1 (compare weight with eval/pdf at one sample)", value=1)
            oracle_text = "pointwise"
        elif c.oracle == "est":
            e = c.estimator
            o_an = e.oracle_n90()
            log(f"  oracle estimator (analytic n90 {o_an:.4g})")
            res["oracle"] = search(lambda n, s: e.oracle_reject(n, s), ns_o, a.seeds, log)
            oracle_text = "z on the mean" if e.kind == "gauss" else "z on the mean log"
            nn = res["oracle"]["n90"]
            if nn:
                reps = 400
                level = (sum(e.oracle_reject(nn, 10_000 + s, null=True) for s in range(reps)), reps, nn)
        else:
            res["oracle"] = None
            oracle_text = "n/a: pdf() integrates to 1.015 > 1, no density to face (decided without samples)"
        # chi2 peers
        res["mitsuba"] = res["pbrt"] = None
        mi_default = None
        if c.chi2 and not a.no_chi2:
            mt = MitsubaChi2(c.claim)

            def mi_run(n, s, mt=mt, c=c):
                u = np.random.default_rng([s, 91]).random((n, 3))
                x, ok = c.truth.draw(u)
                return mt.reject(x, ok, n)

            log("  mitsuba chi2")
            res["mitsuba"] = search(mi_run, ns_chi2, a.seeds, log)
            if not a.quick:
                k, d, _ = rate_at(mi_run, 1_000_000, a.seeds, early=False)
                mi_default = (k, d)
            pt = PbrtChi2(c.claim)

            def pb_run(n, s, pt=pt, c=c):
                for run in range(PbrtChi2.RUNS):
                    u = np.random.default_rng([s, 92, run]).random((n, 3))
                    x, ok = c.truth.draw(u)
                    if pt.reject_run(x, ok, n):
                        return True
                return False

            log("  pbrt chi2")
            res["pbrt"] = search(pb_run, grid(a.chi2_n_max / 5), a.seeds, log)
        dt = time.time() - t0
        log(f"  {dt:.0f} s")
        rows.append((c, res, oracle_text, o_an, level, mi_default, dt))

    # ---- the tables
    L = []
    p = L.append
    p("# Renderer checks: how far from the best test?")
    p("")
    p(f"`bench/bench_power.py --seeds {a.seeds}{' --quick' if a.quick else ''}` (`make bench-power`), "
      f"{len(rows)} cases, wall time {time.time() - t_start:.0f} s on one core.")
    p("")
    p(f"Environment: {env0}; at the end: load average {os.getloadavg()[0]:.2f} / {os.getloadavg()[1]:.2f} / "
      f"{os.getloadavg()[2]:.2f}.")
    p("")
    p("n90: the smallest n of the grid 1000 x sqrt(2)^k at which the test rejects at >= 90% of the seeds "
      f"0..{a.seeds - 1} (alpha = 0.01 for every test), with the rejections there and at the grid point below, "
      "each with its Clopper-Pearson 95% interval (with 40 seeds, 36/40 has the interval 0.76-0.97: a "
      "single n90 is known to within a grid step or two, and ratios to within a factor of about 2). "
      f"mcstat's and the oracle's grids stop at {fmt_n(ns[-1])}, the chi2 grids at {fmt_n(ns_chi2[-1])} samples "
      f"(pbrt: {fmt_n(grid(a.chi2_n_max / 5)[-1])} a run, 5 runs). '> n' : not reached.")
    p("")
    p("| model | bug | mcstat n90 | routes that rejected at n90 | oracle | oracle n90 (analytic) | "
      "Mitsuba chi2 n90 (rate at 1e6) | pbrt chi2 n90, 5 runs x | mcstat / oracle | Mitsuba chi2 / mcstat | "
      "pbrt total / mcstat | s |")
    p("|---|---|---|---|---|---|---|---|---:|---:|---:|---:|")
    for c, res, otext, o_an, level, mi_def, dt in rows:
        m = res["mcstat"]
        routes = ", ".join(f"{k} {v}" for k, v in sorted(m.get("routes", {}).items(), key=lambda kv: -kv[1])) \
            if m.get("n90") else "-"
        if c.kind == "estimator":
            routes = "t test (two-sided)" if m.get("n90") else "-"
        mv = n90_value(m, ns[-1])
        ov = n90_value(res["oracle"], ns[-1])
        miv = n90_value(res["mitsuba"], ns_chi2[-1])
        pbv = n90_value(res["pbrt"], grid(a.chi2_n_max / 5)[-1])
        pbv_tot = (pbv[0] * 5, pbv[1]) if pbv else None
        an = f" ({fmt_n(o_an)})" if o_an and math.isfinite(o_an) and not (res["oracle"] or {}).get("det") else ""
        mi_txt = fmt_search(res["mitsuba"], ns_chi2[-1]) if c.chi2 else "blind"
        if c.chi2 and res["mitsuba"] is None:
            mi_txt = "not run"
        if mi_def:
            mi_txt += f" [{mi_def[0]}/{mi_def[1]} at 1M]"
        pb_txt = fmt_search(res["pbrt"], grid(a.chi2_n_max / 5)[-1]) if c.chi2 else "blind"
        if c.chi2 and res["pbrt"] is None:
            pb_txt = "not run"
        mname = c.model + (" (stochastic=True)" if c.stochastic else "")
        p(f"| {mname} | {c.bug} | {fmt_search(m, ns[-1])} | {routes} | {otext} | "
          f"{fmt_search(res['oracle'], ns[-1]) if res['oracle'] else '-'}{an} | {mi_txt} | {pb_txt} | "
          f"{ratio(mv, ov)} | {ratio(miv, mv) if c.chi2 else 'blind'} | {ratio(pbv_tot, mv) if c.chi2 else 'blind'} | "
          f"{dt:.0f} |")
    levels = [(c, lv) for c, _, _, _, lv, _, _ in rows if lv]
    if levels:
        p("")
        p("Level of the oracles' normal-approximation critical values, simulated under H0 at their n90 "
          "(expected 1% of the replicates):")
        p("")
        for c, (k, reps, nn) in levels:
            p(f"- {c.name}: {k}/{reps} at n = {fmt_n(nn)}")
    text = "\n".join(L) + "\n"
    print(text)
    if a.write and not a.quick:
        path = os.path.join(HERE, "RESULTS_power.md")
        old = open(path).read() if os.path.exists(path) else ""
        marker = "<!-- diagnosis -->"
        keep = old[old.index(marker):] if marker in old else ""
        with open(path, "w") as f:
            f.write(text + ("\n" + keep if keep else ""))
    return rows


if __name__ == "__main__":
    main()
