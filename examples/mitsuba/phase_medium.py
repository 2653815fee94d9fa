"""Mitsuba 3's phase functions (hg, rayleigh) and a homogeneous medium's
free-flight sampling through mcstat.check_phase and mcstat.check_medium,
correct and with planted 10% bugs wrapped around Mitsuba's own objects.

    .venv/bin/python examples/mitsuba/phase_medium.py [--seeds 20] [--n 10000] [--only NAME] [--null-seeds N]

prints the Markdown table of RESULTS.md's section "Phase functions and
distance sampling": for each model, in how many of the seeds the check
rejected at alpha = 0.01 (correct models: false rejections, expected about
alpha * seeds; planted bugs: detections), and the routes that rejected.

Variant scalar_rgb (no LLVM needed): every callable loops in Python over
its points, float32 inside Mitsuba (uniforms rounded to float32 and clamped
below 1, as in mitsuba_adapters.py).

Conventions.  Phase functions (mcstat.mitsuba.PhaseModel's callables):
mcstat's wi is Mitsuba's mei.wi (pointing back along the ray), wo what
sample() returns; eval is the value of eval_pdf, the weight sample()'s (1
for hg and rayleigh), pdf sample()'s.
The medium: a ray from the origin along +z with a surface at TMAX inside a
homogeneous medium (sigma_t 2, albedo 0.75); sample() is
sample_interaction, an interaction at t < TMAX a scattering with the
weight sigma_s T / pdf from transmittance_eval_pdf and
get_scattering_coefficients (what Mitsuba's volumetric path tracer
multiplies by), one that passes TMAX an escape (pdf 0) with the weight 1
it carries on, checked against T(TMAX) (check_medium's escape_transmittance=);
pdf(t) and eval(t) (sigma_s T) come from transmittance_eval_pdf at an
interaction moved to t.

Planted bugs (BUG = 1.1):
  phase  pdf_g    pdf() from the same phase function with g * 1.1 (hg only);
                  sample() correct
         pdf      pdf() * 1.1 (rayleigh: it has no g)
         weight   sample()'s weight * 1.1
         norm     eval() and the weight / 1.1: consistent with each other,
                  the phase function not normalised
  medium pdf      pdf() with sigma_t * 1.1 (sample() and its reported pdf correct)
         weight   the scattering weight * 1.1
         sampler  distances drawn by a medium with sigma_t * 1.1, pdf and
                  weight those of the correct one
  delta   accept   a tentative collision accepted with probability 1.1
  tracking         sigma_t / majorant
         weight   the scattering weight * 1.1
         sampler  tracked through the medium scaled by 1.1, claims the
                  correct one's
         restart  the distance of the last tentative flight alone (the
                  null collisions' distances dropped)
  both   escape   an escape's weight times the albedo (0.75, 0.8), as if
  media           it had scattered
"""
import argparse
import sys

import numpy as np

import mitsuba as mi

mi.set_variant("scalar_rgb")

import mcstat  # noqa: E402
import mcstat.mitsuba as mm  # noqa: E402

BUG = 1.1
ALPHA = 0.01
SIGMA_T, ALBEDO, TMAX = 2.0, 0.75, 1.0
WI = np.array([0.3, -0.4, 0.866])
_ONE_MINUS = float(np.nextafter(np.float32(1), np.float32(0)))


def _u32(u):
    return np.minimum(np.asarray(u, dtype=np.float64).astype(np.float32), np.float32(_ONE_MINUS)).astype(float)


class MitsubaPhase:
    """A Mitsuba phase function as check_phase's callables: the shipped
    mcstat.mitsuba.PhaseModel's (scalar_rgb), with the planted bugs around
    them."""

    def __init__(self, spec, bug=None):
        self.model = mm.phase_model(spec, variant="scalar_rgb")
        self.pdf_model = mm.phase_model(dict(spec, g=spec["g"] * BUG), variant="scalar_rgb") \
            if bug == "pdf_g" else self.model
        self.bug = bug

    def sample(self, wi, u):
        wo, w, p = self.model.sample(wi, u)
        return wo, w * {"weight": BUG, "norm": 1 / BUG}.get(self.bug, 1.0), p

    def eval(self, wi, wo):
        return self.model.eval(wi, wo) / (BUG if self.bug == "norm" else 1.0)

    def pdf(self, wi, wo):
        return self.pdf_model.pdf(wi, wo) * (BUG if self.bug == "pdf" else 1.0)

    def check(self, n, seed):
        return mcstat.check_phase(self.sample, self.eval, self.pdf, WI, n=n, seed=seed, alpha=ALPHA, n_uniforms=3)


class MitsubaMedium:
    """A homogeneous Mitsuba medium's free flights along a ray as
    check_medium's callables."""

    def __init__(self, bug=None):
        self.med = mi.load_dict({"type": "homogeneous", "sigma_t": SIGMA_T, "albedo": ALBEDO})
        self.sampler_med = self.med
        if bug == "sampler":
            self.sampler_med = mi.load_dict({"type": "homogeneous", "sigma_t": SIGMA_T * BUG, "albedo": ALBEDO})
        self.bug = bug
        self.ray = mi.Ray3f(mi.Point3f(0, 0, 0), mi.Vector3f(0, 0, 1))
        self.ray.maxt = TMAX
        self.si = mi.SurfaceInteraction3f()
        self.si.t = TMAX
        self.template = self.med.sample_interaction(self.ray, 0.5, 0, True)

    def _tr_pdf(self, mei, extinction_scale=1.0):
        if extinction_scale != 1.0:
            mei.combined_extinction = mei.combined_extinction * extinction_scale
        tr, pdf = self.med.transmittance_eval_pdf(mei, self.si, True)
        sigma_s = self.med.get_scattering_coefficients(mei, True)[0]
        return tr[0], pdf[0], sigma_s[0]

    def sample(self, u):
        u = _u32(u[:, 0])
        t = np.zeros(len(u))
        w = np.zeros(len(u))
        p = np.zeros(len(u))
        for k in range(len(u)):
            mei = self.sampler_med.sample_interaction(self.ray, float(u[k]), 0, True)
            if not (mei.is_valid() and mei.t < TMAX):
                # passed the surface: pdf 0 and the throughput it carries on (analog: 1)
                w[k] = HET_ALBEDO if self.bug == "escape" else 1.0
                continue
            if self.bug == "sampler":  # the correct medium's values at the wrongly drawn distance
                m = mi.MediumInteraction3f(self.template)
                m.t = mei.t
                mei = m
            tr, pdf, sigma_s = self._tr_pdf(mei)
            t[k], p[k], w[k] = mei.t, pdf, sigma_s * tr / pdf
        if self.bug == "weight":
            w = np.where(p > 0, w * BUG, w)
        return t, w, p

    def _at(self, t, which):
        out = np.zeros(len(t))
        for k in range(len(t)):
            if not t[k] < TMAX:
                continue
            mei = mi.MediumInteraction3f(self.template)
            mei.t = float(t[k])
            tr, pdf, sigma_s = self._tr_pdf(mei, BUG if (which == "pdf" and self.bug == "pdf") else 1.0)
            out[k] = pdf if which == "pdf" else sigma_s * tr
        return out

    def pdf(self, t):
        return self._at(t, "pdf")

    def eval(self, t):
        return self._at(t, "eval")

    def check(self, n, seed):
        return mcstat.check_medium(self.sample, self.eval, self.pdf, sigma_ref=SIGMA_T, n=n, seed=seed, alpha=ALPHA,
                                   escape_transmittance=float(np.exp(-SIGMA_T * TMAX)))


# A heterogeneous medium: a random 8 x 4 x 4 grid of densities in [0.2, 1]
# scaled by 3 (sigma_t up to 2.9) in the unit cube, albedo 0.8; the ray from
# (0.37, 0.61, 0) along +z, a surface at HET_TMAX.  Its distances are drawn
# by delta tracking as a volumetric path tracer does: tentative collisions
# from Mitsuba's sample_interaction (against its majorant), each real with
# probability sigma_t / majorant, the ray restarted at a null collision.
HET_SCALE, HET_ALBEDO, HET_TMAX = 3.0, 0.8, 0.9
HET_ORIGIN = (0.37, 0.61, 0.0)
HET_TABLE = 40001  # points of the optical-depth table along the ray


def _splitmix(x):
    x = (x + 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
    return x ^ (x >> 31)


class MitsubaHeterogeneous:
    """Delta tracking through a heterogeneous Mitsuba medium as
    check_medium's callables.  A flight needs a random number of uniforms:
    it gets two from mcstat and derives the rest by splitmix64, so each
    flight is a pure function of its two uniforms.  The claims: pdf(t) =
    sigma_t(t) T(t) and eval(t) = sigma_s(t) T(t), T from an optical-depth
    table of Mitsuba's own sigma_t along the ray (trilinear: piecewise
    linear along the ray, so the table's trapezoids are within ~1e-8);
    sample() reports that pdf at its distance and the weight sigma_s /
    sigma_t of the collision Mitsuba returns."""

    def __init__(self, bug=None):
        grid = np.random.default_rng(3).uniform(0.2, 1.0, size=(8, 4, 4, 1)).astype(np.float32)
        self.spec = {"type": "heterogeneous", "sigma_t": {"type": "gridvolume", "grid": mi.VolumeGrid(grid)},
                     "albedo": HET_ALBEDO, "scale": HET_SCALE}
        self.med = mi.load_dict(self.spec)
        self.tracker = mi.load_dict(dict(self.spec, scale=HET_SCALE * BUG)) if bug == "sampler" else self.med
        self.bug = bug
        vol = mi.load_dict(self.spec["sigma_t"])
        it = mi.Interaction3f()
        z = np.linspace(0.0, HET_TMAX, HET_TABLE)
        sig = np.empty(HET_TABLE)
        for i, zz in enumerate(z):
            it.p = mi.Point3f(HET_ORIGIN[0], HET_ORIGIN[1], float(zz))
            sig[i] = HET_SCALE * vol.eval(it)[0]
        self.z, self.sig = z, sig
        self.tau = np.concatenate([[0.0], np.cumsum(0.5 * (sig[1:] + sig[:-1]) * np.diff(z))])

    def _sigma_tau(self, t):
        i = np.clip(np.searchsorted(self.z, t, side="right") - 1, 0, HET_TABLE - 2)
        f = (t - self.z[i]) / (self.z[i + 1] - self.z[i])
        s = self.sig[i] + f * (self.sig[i + 1] - self.sig[i])
        tau = self.tau[i] + (t - self.z[i]) * 0.5 * (self.sig[i] + s)
        return s, tau

    def _flight(self, u0, u1):
        key = (int(u0 * 2.0**32) << 32) | int(u1 * 2.0**32)
        ray = mi.Ray3f(mi.Point3f(*HET_ORIGIN), mi.Vector3f(0, 0, 1))
        t, j = 0.0, 0
        while True:
            ray.maxt = HET_TMAX - t
            xi = (_splitmix(key ^ _splitmix(2 * j)) >> 11) * 2.0**-53
            mei = self.tracker.sample_interaction(ray, float(np.float32(min(xi, _ONE_MINUS))), 0, True)
            if not (mei.is_valid() and mei.t < ray.maxt):
                return None, (HET_ALBEDO if self.bug == "escape" else 1.0)  # passed the surface (analog: 1)
            t_new = mei.t if self.bug == "restart" else t + mei.t
            st, maj, ss = mei.sigma_t[0], mei.combined_extinction[0], mei.sigma_s[0]
            accept = st / maj * (BUG if self.bug == "accept" else 1.0)
            xi2 = (_splitmix(key ^ _splitmix(2 * j + 1)) >> 11) * 2.0**-53
            if xi2 < accept:
                return t_new, ss / st
            t = t + mei.t  # a null collision: on from there
            ray = mi.Ray3f(mei.p, mi.Vector3f(0, 0, 1))
            j += 1

    def sample(self, u):
        t, w, p = np.zeros(len(u)), np.zeros(len(u)), np.zeros(len(u))
        for k in range(len(u)):
            tk, w[k] = self._flight(u[k, 0], u[k, 1])
            if tk is None:  # passed the surface: pdf 0, the throughput it carries on
                continue
            t[k] = tk
            s, tau = self._sigma_tau(tk)
            p[k] = s * np.exp(-tau)
        if self.bug == "weight":
            w = np.where(p > 0, w * BUG, w)
        return t, w, p

    def pdf(self, t):
        t = np.asarray(t, float)
        inside = t < HET_TMAX
        s, tau = self._sigma_tau(np.where(inside, t, 0.0))
        return np.where(inside, s * np.exp(-tau), 0.0)

    def eval(self, t):
        return HET_ALBEDO * self.pdf(t)  # albedo constant: sigma_s T = albedo sigma_t T

    def check(self, n, seed):
        return mcstat.check_medium(self.sample, self.eval, self.pdf, sigma_ref=2.0, n=n, seed=seed, alpha=ALPHA,
                                   n_uniforms=2, escape_transmittance=float(np.exp(-self.tau[-1])))


CASES = [
    ("hg g=0.7", lambda bug: MitsubaPhase({"type": "hg", "g": 0.7}, bug), (None, "pdf_g", "weight", "norm")),
    ("hg g=-0.3", lambda bug: MitsubaPhase({"type": "hg", "g": -0.3}, bug), (None, "pdf_g", "weight", "norm")),
    ("rayleigh", lambda bug: MitsubaPhase({"type": "rayleigh"}, bug), (None, "pdf", "weight", "norm")),
    ("homogeneous (sigma_t 2, albedo 0.75, tmax 1)", MitsubaMedium, (None, "pdf", "weight", "sampler", "escape")),
    ("heterogeneous grid, delta tracking (sigma_t 0.6..2.9, tmax 0.9)", MitsubaHeterogeneous,
     (None, "accept", "weight", "sampler", "restart", "escape")),
]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--n", type=int, default=10000)
    ap.add_argument("--only", default="", help="only the models whose name contains this")
    ap.add_argument("--null-seeds", type=int, default=None, help="seeds of the correct models (default --seeds)")
    a = ap.parse_args(argv)
    null_seeds = a.null_seeds or a.seeds
    print(f"Mitsuba {mi.__version__} ({mi.variant()}), mcstat {mcstat.__version__}: n = {a.n}, alpha = {ALPHA}, "
          f"seeds 0..{a.seeds - 1}, planted factor {BUG}\n")
    print("| model | planted bug | rejected | routes that rejected (runs) |")
    print("|---|---|---|---|")
    for name, make, bugs in CASES:
        if a.only not in name:
            continue
        for bug in bugs:
            model = make(bug)
            rejected, routes = 0, {}
            seeds = null_seeds if bug is None else a.seeds
            for seed in range(seeds):
                r = model.check(a.n, seed)
                rejected += r.reject
                for x in r.routes:
                    if x.state == "ran" and x.reject:
                        routes[x.name] = routes.get(x.name, 0) + 1
            which = ", ".join(f"{k} ({v})" for k, v in sorted(routes.items(), key=lambda kv: -kv[1])) or "-"
            print(f"| {name} | {bug or 'none (correct)'} | {rejected}/{seeds} | {which} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
