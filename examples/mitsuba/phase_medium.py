"""Mitsuba 3's phase functions (hg, rayleigh) and a homogeneous medium's
free-flight sampling through mcstat.check_phase and mcstat.check_medium,
correct and with planted 10% bugs wrapped around Mitsuba's own objects.

    .venv/bin/python examples/mitsuba/phase_medium.py [--seeds 20] [--n 10000]

prints the Markdown table of RESULTS.md's section "Phase functions and
distance sampling": for each model, in how many of the seeds the check
rejected at alpha = 0.01 (correct models: false rejections, expected about
alpha * seeds; planted bugs: detections), and the routes that rejected.

Variant scalar_rgb (no LLVM needed): every callable loops in Python over
its points, float32 inside Mitsuba (uniforms rounded to float32 and clamped
below 1, as in mitsuba_adapters.py).

Conventions.  Phase functions: mcstat's wi is Mitsuba's mei.wi (pointing
back along the ray), wo what sample() returns; eval is the value of
eval_pdf, the weight sample()'s (1 for hg and rayleigh), pdf sample()'s.
The medium: a ray from the origin along +z with a surface at TMAX inside a
homogeneous medium (sigma_t 2, albedo 0.75); sample() is
sample_interaction, an interaction at t < TMAX a scattering with the
weight sigma_s T / pdf from transmittance_eval_pdf and
get_scattering_coefficients (what Mitsuba's volumetric path tracer
multiplies by), one that passes TMAX a failed sample; pdf(t) and eval(t)
(sigma_s T) come from transmittance_eval_pdf at an interaction moved to t.

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
"""
import argparse
import sys

import numpy as np

import mitsuba as mi

mi.set_variant("scalar_rgb")

import mcstat  # noqa: E402

BUG = 1.1
ALPHA = 0.01
SIGMA_T, ALBEDO, TMAX = 2.0, 0.75, 1.0
WI = np.array([0.3, -0.4, 0.866])
_ONE_MINUS = float(np.nextafter(np.float32(1), np.float32(0)))


def _u32(u):
    return np.minimum(np.asarray(u, dtype=np.float64).astype(np.float32), np.float32(_ONE_MINUS)).astype(float)


class MitsubaPhase:
    """A Mitsuba phase function as check_phase's callables."""

    def __init__(self, spec, bug=None):
        self.pf = mi.load_dict(spec)
        self.bug = bug
        self.pdf_pf = self.pf
        if bug == "pdf_g":
            self.pdf_pf = mi.load_dict(dict(spec, g=spec["g"] * BUG))
        self.ctx = mi.PhaseFunctionContext(None)

    def _mei(self, wi):
        mei = mi.MediumInteraction3f()
        mei.wi = mi.Vector3f(*[float(c) for c in wi])
        mei.sh_frame = mi.Frame3f(mei.wi)  # as sample_interaction sets it
        return mei

    def sample(self, wi, u):
        u = _u32(u)
        mei = self._mei(wi)
        wo = np.empty((len(u), 3))
        w = np.empty(len(u))
        p = np.empty(len(u))
        for k in range(len(u)):
            d, weight, pdf = self.pf.sample(self.ctx, mei, float(u[k, 0]), mi.Point2f(u[k, 1], u[k, 2]))
            wo[k] = (d[0], d[1], d[2])
            w[k] = weight[0]
            p[k] = pdf
        wo /= np.linalg.norm(wo, axis=1)[:, None]  # float32 directions, renormalised in float64
        w *= {"weight": BUG, "norm": 1 / BUG}.get(self.bug, 1.0)
        return wo, np.where(p > 0, w, 0.0), p

    def _eval_pdf(self, pf, wi, wo, which):
        mei = self._mei(wi)
        out = np.empty(len(wo))
        for k in range(len(wo)):
            v, p = pf.eval_pdf(self.ctx, mei, mi.Vector3f(*[float(c) for c in wo[k]]))
            out[k] = v[0] if which == 0 else p
        return out

    def eval(self, wi, wo):
        return self._eval_pdf(self.pf, wi, wo, 0) / (BUG if self.bug == "norm" else 1.0)

    def pdf(self, wi, wo):
        return self._eval_pdf(self.pdf_pf, wi, wo, 1) * (BUG if self.bug == "pdf" else 1.0)

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
                continue  # passed the surface: a failed sample for mcstat
            if self.bug == "sampler":  # the correct medium's values at the wrongly drawn distance
                m = mi.MediumInteraction3f(self.template)
                m.t = mei.t
                mei = m
            tr, pdf, sigma_s = self._tr_pdf(mei)
            t[k], p[k], w[k] = mei.t, pdf, sigma_s * tr / pdf
        if self.bug == "weight":
            w *= BUG
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
        return mcstat.check_medium(self.sample, self.eval, self.pdf, sigma_ref=SIGMA_T, n=n, seed=seed, alpha=ALPHA)


CASES = [
    ("hg g=0.7", lambda bug: MitsubaPhase({"type": "hg", "g": 0.7}, bug), (None, "pdf_g", "weight", "norm")),
    ("hg g=-0.3", lambda bug: MitsubaPhase({"type": "hg", "g": -0.3}, bug), (None, "pdf_g", "weight", "norm")),
    ("rayleigh", lambda bug: MitsubaPhase({"type": "rayleigh"}, bug), (None, "pdf", "weight", "norm")),
    ("homogeneous (sigma_t 2, albedo 0.75, tmax 1)", MitsubaMedium, (None, "pdf", "weight", "sampler")),
]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--n", type=int, default=10000)
    a = ap.parse_args(argv)
    print(f"Mitsuba {mi.__version__} ({mi.variant()}), mcstat {mcstat.__version__}: n = {a.n}, alpha = {ALPHA}, "
          f"seeds 0..{a.seeds - 1}, planted factor {BUG}\n")
    print("| model | planted bug | rejected | routes that rejected (runs) |")
    print("|---|---|---|---|")
    for name, make, bugs in CASES:
        for bug in bugs:
            model = make(bug)
            rejected, routes = 0, {}
            for seed in range(a.seeds):
                r = model.check(a.n, seed)
                rejected += r.reject
                for x in r.routes:
                    if x.state == "ran" and x.reject:
                        routes[x.name] = routes.get(x.name, 0) + 1
            which = ", ".join(f"{k} ({v})" for k, v in sorted(routes.items(), key=lambda kv: -kv[1])) or "-"
            print(f"| {name} | {bug or 'none (correct)'} | {rejected}/{a.seeds} | {which} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
