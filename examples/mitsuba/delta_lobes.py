"""Mitsuba 3's BSDFs with discrete (delta) lobes through mcstat.check_bsdf's
lobes=: the smooth dielectric (reflection and refraction, both discrete),
the thin dielectric (reflection and straight transmission) and the smooth
plastic (a discrete specular coat over a diffuse base: a smooth and a delta
lobe), correct and with planted bugs wrapped around Mitsuba's own objects.

    .venv/bin/python examples/mitsuba/delta_lobes.py [--seeds 20] [--null-seeds 200] [--n 20000]

prints the Markdown table of RESULTS.md's section "Delta and mixed lobes":
for each model and incident direction, in how many of the seeds the check
rejected at alpha = 0.01 (correct models: false rejections, expected about
alpha * seeds; planted bugs: detections), and the routes that rejected.

Variant scalar_rgb (no LLVM needed), channel 0, float32 inside Mitsuba
(uniforms rounded to float32 and clamped below 1).  The lobes are this
file's own claim, written from the physics, not from Mitsuba's code: the
unpolarised Fresnel reflectance of a dielectric (the thin sheet's with its
internal reflections summed), the mirror direction, Snell's refraction;
a refraction's value is (1 - F) / eta^2 (radiance mode: Mitsuba's
transport mode here).  For the plastic the probability of the specular lobe
is Mitsuba's documented choice, F w / (F w + (1 - F)(1 - w)) with w =
s / (s + d) from the mean specular and diffuse reflectances.  A sample is
a discrete one when Mitsuba's sampled_type has a delta flag.

Planted bugs:
  weight  a discrete sample's weight * 1.05 (the smooth ones correct)
  pick    sample1 / 1.2 before Mitsuba sees it: the reflection is picked
          more often than the pdf it reports says
  eta     sampled by the same BSDF with an index 1% higher: the refracted
          direction and the Fresnel terms off (lobes() from the right one)
  base    (plastic) the diffuse samples' weight * 1.05
"""
import argparse
import sys
import time

import numpy as np

import mitsuba as mi

mi.set_variant("scalar_rgb")

import mcstat  # noqa: E402

ALPHA = 0.01
ETA = 1.5
_ONE_MINUS = float(np.nextafter(np.float32(1), np.float32(0)))


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


ABOVE, BELOW = unit([0.4, 0.1, 0.9]), unit([0.3, -0.2, -0.8])


def fresnel(cos_i, eta):
    """Unpolarised Fresnel reflectance, the refracted cosine, eta_it."""
    eta_it = eta if cos_i > 0 else 1.0 / eta
    c = abs(cos_i)
    s2t = (1.0 - c * c) / (eta_it * eta_it)
    if s2t >= 1.0:
        return 1.0, 0.0, eta_it
    ct = np.sqrt(1.0 - s2t)
    rs = (c - eta_it * ct) / (c + eta_it * ct)
    rp = (eta_it * c - ct) / (eta_it * c + ct)
    return 0.5 * (rs * rs + rp * rp), ct, eta_it


def mirror(wi):
    return np.array([-wi[0], -wi[1], wi[2]])


def lobes_dielectric(wi):
    F, ct, eta_it = fresnel(wi[2], ETA)
    if F >= 1.0:
        return np.array([mirror(wi)]), np.array([1.0]), np.array([1.0])
    t = np.array([-wi[0] / eta_it, -wi[1] / eta_it, -np.sign(wi[2]) * ct])
    return np.array([mirror(wi), t]), np.array([F, 1 - F]), np.array([F, (1 - F) / eta_it ** 2])


def lobes_thin(wi):
    R = fresnel(abs(wi[2]), ETA)[0]
    R += (1 - R) ** 2 * R / (1 - R * R)  # the sheet's internal reflections
    return np.array([mirror(wi), -wi]), np.array([R, 1 - R]), np.array([R, 1 - R])


DIFFUSE = 0.5


def lobes_plastic(wi):
    F = fresnel(wi[2], ETA)[0]
    w = 1.0 / (1.0 + DIFFUSE)  # specular reflectance 1 against the diffuse one
    p = F * w / (F * w + (1 - F) * (1 - w))
    return np.array([mirror(wi)]), np.array([p]), np.array([F])


class MitsubaDelta:
    """A Mitsuba BSDF with delta lobes as check_bsdf's callables."""

    def __init__(self, spec, lobes, bug=None):
        self.bsdf = mi.load_dict(spec)
        self.sampler = mi.load_dict(dict(spec, int_ior=ETA * 1.01)) if bug == "eta" else self.bsdf
        self.lobes, self.bug = lobes, bug
        self.ctx = mi.BSDFContext()
        self.domain = "hemisphere" if spec["type"] == "plastic" else "sphere"

    def _si(self, wi):
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*[float(c) for c in wi])
        return si

    def sample(self, wi, u):
        u = np.minimum(np.asarray(u, dtype=np.float64).astype(np.float32), np.float32(_ONE_MINUS))
        if self.bug == "pick":
            u[:, 0] /= 1.2
        si = self._si(wi)
        k = len(u)
        wo, weight, pdf = np.zeros((k, 3)), np.zeros(k), np.zeros(k)
        for i in range(k):
            bs, w = self.sampler.sample(self.ctx, si, float(u[i, 0]), mi.Point2f(float(u[i, 1]), float(u[i, 2])))
            if all(w[c] == 0.0 for c in range(3)) or not bs.pdf > 0:
                continue  # a failed sample
            delta = mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
            wo[i] = (bs.wo[0], bs.wo[1], bs.wo[2])
            weight[i] = w[0] * (1.05 if (self.bug == "weight" and delta) or (self.bug == "base" and not delta)
                                else 1.0)
            pdf[i] = bs.pdf
        n = np.linalg.norm(wo, axis=1)
        wo[n > 0] /= n[n > 0, None]  # float32 directions, renormalised in float64
        return wo, weight, pdf

    def eval(self, wi, wo):
        si = self._si(wi)
        return np.array([self.bsdf.eval(self.ctx, si, mi.Vector3f(*map(float, d)))[0] for d in np.asarray(wo)])

    def pdf(self, wi, wo):
        si = self._si(wi)
        return np.array([self.bsdf.pdf(self.ctx, si, mi.Vector3f(*map(float, d))) for d in np.asarray(wo)])

    def check(self, wi, n, seed):
        # refraction into the denser side scales radiance by 1/eta^2 < 1, out of it by eta^2 > 1:
        # the albedo may exceed 1 from below, so energy is only asked from above
        return mcstat.check_bsdf(self.sample, self.eval, self.pdf, wi, lobes=self.lobes, n=n, seed=seed,
                                 alpha=ALPHA, domain=self.domain, energy=bool(wi[2] > 0))


DIEL = {"type": "dielectric", "int_ior": ETA, "ext_ior": 1.0}
THIN = {"type": "thindielectric", "int_ior": ETA, "ext_ior": 1.0}
PLASTIC = {"type": "plastic", "int_ior": ETA, "ext_ior": 1.0, "diffuse_reflectance": {"type": "rgb", "value": DIFFUSE},
           "nonlinear": False}

CASES = [
    ("dielectric", DIEL, lobes_dielectric, ABOVE, (None, "weight", "pick", "eta")),
    ("dielectric", DIEL, lobes_dielectric, BELOW, (None, "weight", "pick", "eta")),
    ("thindielectric", THIN, lobes_thin, ABOVE, (None, "weight", "pick")),
    ("plastic (delta coat + diffuse)", PLASTIC, lobes_plastic, ABOVE, (None, "weight", "pick", "eta", "base")),
]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--null-seeds", type=int, default=None, help="seeds of the correct models (default --seeds)")
    ap.add_argument("--n", type=int, default=20000)
    a = ap.parse_args(argv)
    null_seeds = a.null_seeds or a.seeds
    print(f"Mitsuba {mi.__version__} ({mi.variant()}), mcstat {mcstat.__version__}: n = {a.n}, alpha = {ALPHA}, "
          f"seeds 0..{a.seeds - 1} (correct models: 0..{null_seeds - 1})\n")
    print("| model | wi | planted bug | rejected | routes that rejected (runs) | s per check |")
    print("|---|---|---|---|---|---|")
    for name, spec, lobes, wi, bugs in CASES:
        for bug in bugs:
            model = MitsubaDelta(spec, lobes, bug)
            rejected, routes = 0, {}
            t0 = time.perf_counter()
            seeds = null_seeds if bug is None else a.seeds
            for seed in range(seeds):
                r = model.check(wi, a.n, seed)
                rejected += r.reject
                for x in r.routes:
                    if x.state == "ran" and x.reject:
                        routes[x.name] = routes.get(x.name, 0) + 1
            dt = (time.perf_counter() - t0) / seeds
            which = ", ".join(f"{k} ({v})" for k, v in sorted(routes.items(), key=lambda kv: -kv[1])) or "-"
            side = "above" if wi[2] > 0 else "below"
            print(f"| {name} | {side} | {bug or 'none (correct)'} | {rejected}/{seeds} | {which} | {dt:.2f} |",
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
