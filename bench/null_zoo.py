"""The null zoo: correct Mitsuba 3 models through mcstat's renderer kit, as
a calibration benchmark.

    .venv/bin/python bench/null_zoo.py [--seeds 20] [--n 20000] [--n-emitter 10000]
                                      [--only PATTERN] [--out bench/RESULTS_null_zoo.md]

Every Mitsuba 3 scalar_rgb BSDF, phase function, area (and infinite)
emitter and medium the kit applies to, over a grid of parameters (roughness
1e-3 to 1, incident angles to 89.9 degrees, albedo 0 and 1, indices of
refraction near 1, thin and near-pole triangles), each run at the fixed
seeds 0..S-1 at alpha = 0.01.  Each model's rejection count is judged by the
battery meta-test (mcstat.battery_test, alternative "greater") at
meta_alpha 0.001 / (number of models run): Bonferroni over the models, so
a zoo of correct, correctly checked models shows a model OUTSIDE with
probability at most 0.001.

Writes the Markdown table (model, parameters, rejections / seeds,
inconclusive, the routes that rejected, the meta-test's p-value, the
verdict) between the markers "<!-- zoo:begin -->" and "<!-- zoo:end -->" of
--out (the rest of the file, the diagnoses, is kept), and the models the
kit does not apply to with the reason.  Progress and the text of every
rejecting report go to stderr.

The callables are the examples' (examples/mitsuba/): mitsuba_adapters.py
(BSDFs, area lights), delta_lobes.py (delta lobes through lobes=),
phase_medium.py (phase functions, media); what they do not cover (further
emitter shapes, infinite emitters, delta lobes of other indices, the hair
BSDF's fibre offset, albedo 0) is added here on the same conventions:
float32 inside Mitsuba, uniforms rounded to float32 and clamped below 1.

Albedo 0.  Mitsuba marks a failed BSDF sample by a zero weight, and the
adapters map every zero weight to a failed sample (pdf 0); with albedo 0
every weight is 0 and a correct model would look as if every sample
failed.  The albedo-0 models here decide failure by pdf() at the sampled
direction instead (0 there: failed), which is what the kit's convention
means.
"""
import argparse
import fnmatch
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

os.environ.setdefault("MCSTAT_MITSUBA_VARIANT", "scalar_rgb")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "examples", "mitsuba"))

import mitsuba_adapters as ma  # noqa: E402

VARIANT = ma.use_variant("scalar_rgb")
import mitsuba as mi  # noqa: E402

import delta_lobes as dl  # noqa: E402
import mcstat  # noqa: E402
import phase_medium as pm  # noqa: E402

ALPHA = 0.01
META_ALPHA = 0.001
_ONE_MINUS = float(np.nextafter(np.float32(1), np.float32(0)))


def u32(u):
    return np.minimum(np.asarray(u, dtype=np.float64).astype(np.float32), np.float32(_ONE_MINUS))


def direction(theta, phi=30.0):
    t, p = math.radians(theta), math.radians(phi)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


# ---- models ---------------------------------------------------------------------------

class Model:
    """One zoo entry: family, name, parameters, and run(n, seed) -> CheckReport
    (None: not applicable, `why` says why)."""

    def __init__(self, family, name, params, run=None, why=None, n_key="n"):
        self.family, self.name, self.params, self.run, self.why, self.n_key = family, name, params, run, why, n_key

    @property
    def key(self):
        return f"{self.family}/{self.name} {self.params}"


def bsdf_model(name, spec, theta, *, domain, energy=True, params="", albedo0=False, phi=30.0):
    wi = direction(theta, phi)

    def run(n, seed):
        if albedo0:
            s, e, p = zero_albedo_callables(spec)
        else:
            s, e, p = ma.bsdf_callables(spec)
        return mcstat.check_bsdf(s, e, p, wi, n=n, seed=seed, alpha=ALPHA, domain=domain,
                                 energy=energy and bool(wi[2] > 0))
    return Model("bsdf", name, (params + " " if params else "") + f"theta {theta:g}", run)


def zero_albedo_callables(spec):
    """ma.bsdf_callables with failure decided by pdf() at the sampled
    direction (0: failed), not by a zero weight (module docstring)."""
    s, e, p = ma.bsdf_callables(spec)
    bsdf = mi.load_dict(spec)
    ctx = mi.BSDFContext()

    def sample(wi, u):
        u = u32(u)
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*[float(c) for c in wi])
        k = len(u)
        wo, weight, pdf = np.zeros((k, 3)), np.zeros(k), np.zeros(k)
        for i in range(k):
            bs, w = bsdf.sample(ctx, si, float(u[i, 0]), mi.Point2f(float(u[i, 1]), float(u[i, 2])))
            wo[i] = (bs.wo[0], bs.wo[1], bs.wo[2])
            if bs.pdf > 0 and bsdf.pdf(ctx, si, bs.wo) > 0:
                weight[i], pdf[i] = w[0], bs.pdf
        return wo, weight, pdf
    return sample, e, p


def delta_model(name, spec, lobes, theta, *, domain, params="", energy=None):
    wi = direction(theta)

    def run(n, seed):
        m = dl.MitsubaDelta(spec, lobes)
        m.domain = domain
        return mcstat.check_bsdf(m.sample, m.eval, m.pdf, wi, lobes=lobes, n=n, seed=seed, alpha=ALPHA,
                                 domain=domain, energy=bool(wi[2] > 0) if energy is None else energy)
    return Model("bsdf", name, (params + " " if params else "") + f"theta {theta:g}", run)


# lobes written from the physics (delta_lobes.py's functions, with the index a parameter)

def lobes_dielectric(eta):
    def lobes(wi):
        F, ct, eta_it = dl.fresnel(wi[2], eta)
        if F >= 1.0:
            return np.array([dl.mirror(wi)]), np.array([1.0]), np.array([1.0])
        t = np.array([-wi[0] / eta_it, -wi[1] / eta_it, -np.sign(wi[2]) * ct])
        return np.array([dl.mirror(wi), t]), np.array([F, 1 - F]), np.array([F, (1 - F) / eta_it ** 2])
    return lobes


def lobes_thin(eta):
    def lobes(wi):
        R = dl.fresnel(abs(wi[2]), eta)[0]
        R += (1 - R) ** 2 * R / (1 - R * R)  # the sheet's internal reflections
        return np.array([dl.mirror(wi), -wi]), np.array([R, 1 - R]), np.array([R, 1 - R])
    return lobes


def fresnel_conductor(c, eta, k):
    """Unpolarised reflectance of a conductor of complex index eta + i k (exact)."""
    n = complex(eta, k)
    s = 1 - c * c
    ct = np.sqrt(1 - s / (n * n))
    rs = (c - n * ct) / (c + n * ct)
    rp = (n * c - ct) / (n * c + ct)
    return 0.5 * (abs(rs) ** 2 + abs(rp) ** 2)


def lobes_conductor(eta, k):
    def lobes(wi):
        F = 1.0 if eta is None else fresnel_conductor(abs(wi[2]), eta, k)
        return np.array([dl.mirror(wi)]), np.array([1.0]), np.array([F])
    return lobes


def lobes_plastic(eta, diffuse):
    def lobes(wi):
        F = dl.fresnel(wi[2], eta)[0]
        w = 1.0 / (1.0 + diffuse)  # Mitsuba's specular sampling weight: s / (s + d), s = 1
        p = F * w / (F * w + (1 - F) * (1 - w))
        return np.array([dl.mirror(wi)]), np.array([p]), np.array([F])
    return lobes


def lobes_mask(opacity):
    def lobes(wi):
        return np.array([-np.asarray(wi)]), np.array([1 - opacity]), np.array([1 - opacity])
    return lobes


class Hair:
    """Mitsuba's hair BSDF at the fibre offset h = -1 + 2 v (si.uv = (0, v)), as
    check_bsdf's callables (mcstat.mitsuba.BSDFModel's in scalar_rgb, with uv set)."""

    def __init__(self, spec, v):
        self.bsdf, self.v, self.ctx = mi.load_dict(spec), v, mi.BSDFContext()

    def _si(self, wi):
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*[float(c) for c in wi])
        si.uv = mi.Point2f(0.0, self.v)
        return si

    def sample(self, wi, u):
        u = u32(u)
        si = self._si(wi)
        k = len(u)
        wo, weight, pdf = np.zeros((k, 3)), np.zeros(k), np.zeros(k)
        for i in range(k):
            bs, w = self.bsdf.sample(self.ctx, si, float(u[i, 0]), mi.Point2f(float(u[i, 1]), float(u[i, 2])))
            wo[i] = (bs.wo[0], bs.wo[1], bs.wo[2])
            weight[i] = w[0]
            pdf[i] = 0.0 if all(w[c] == 0.0 for c in range(3)) else bs.pdf
        return wo, weight, pdf

    def eval(self, wi, wo):
        si = self._si(wi)
        return np.array([self.bsdf.eval(self.ctx, si, mi.Vector3f(*map(float, d)))[0] for d in np.asarray(wo)])

    def pdf(self, wi, wo):
        si = self._si(wi)
        return np.array([self.bsdf.pdf(self.ctx, si, mi.Vector3f(*map(float, d))) for d in np.asarray(wo)])


def hair_model(v, theta, phi):
    wi = direction(theta, phi)

    def run(n, seed):
        h = Hair({"type": "hair"}, v)
        return mcstat.check_bsdf(h.sample, h.eval, h.pdf, wi, n=n, seed=seed, alpha=ALPHA, domain="sphere")
    return Model("bsdf", "hair", f"h {-1 + 2 * v:g} theta {theta:g} phi {phi:g}", run)


def rgb(v):
    return {"type": "rgb", "value": v}


def bsdf_models():
    M = []
    # diffuse: albedo 0 and 1
    for refl in (0.0, 1.0):
        for th in (0, 45, 89.9):
            M.append(bsdf_model("diffuse", {"type": "diffuse", "reflectance": rgb(refl)}, th, domain="hemisphere",
                                params=f"albedo {refl:g}", albedo0=refl == 0))
    # rough conductors (Mitsuba's default material: a perfect reflector's Fresnel term)
    for dist in ("ggx", "beckmann"):
        alphas = (1e-3, 1e-2, 0.1, 0.5, 1.0) if dist == "ggx" else (1e-3, 0.1, 1.0)
        thetas = (0, 45, 89.9) if dist == "ggx" else (0, 75, 89.9)
        for a in alphas:
            for th in thetas:
                M.append(bsdf_model("roughconductor", {"type": "roughconductor", "distribution": dist, "alpha": a},
                                    th, domain="hemisphere", params=f"{dist} alpha {a:g}"))
        for au, av in ((0.05, 0.5), (0.5, 0.01)) if dist == "ggx" else ():
            for th in (45, 89.9):
                M.append(bsdf_model("roughconductor", {"type": "roughconductor", "distribution": dist,
                                                       "alpha_u": au, "alpha_v": av}, th, domain="hemisphere",
                                    params=f"{dist} alpha_u {au:g} alpha_v {av:g}"))
    M.append(bsdf_model("roughconductor", {"type": "roughconductor", "distribution": "ggx", "alpha": 0.3,
                                           "material": "Au"}, 60, domain="hemisphere", params="ggx alpha 0.3 Au"))
    for th in (45, 89.9):
        M.append(bsdf_model("roughconductor", {"type": "roughconductor", "distribution": "ggx", "alpha": 0.3,
                                               "sample_visible": False}, th, domain="hemisphere",
                            params="ggx alpha 0.3 sample_visible false"))
    # rough dielectrics: from outside (theta < 90) and inside (theta > 90); indices near 1
    for dist, alphas in (("ggx", (1e-3, 1e-2, 0.1, 0.5, 1.0)), ("beckmann", (1e-2, 0.5))):
        for a in alphas:
            for th in (0, 45, 89.9, 135):
                M.append(bsdf_model("roughdielectric", {"type": "roughdielectric", "distribution": dist, "alpha": a},
                                    th, domain="sphere", energy=False, params=f"{dist} alpha {a:g} eta 1.5"))
    for eta in (1.01, 1.0001):
        for a in (0.01, 0.3):
            for th in (45, 135):
                M.append(bsdf_model("roughdielectric", {"type": "roughdielectric", "alpha": a, "int_ior": eta,
                                                        "ext_ior": 1.0}, th, domain="sphere", energy=False,
                                    params=f"beckmann alpha {a:g} eta {eta:g}"))
    # rough plastic: diffuse albedo 0 and 1
    for dist in ("beckmann", "ggx"):
        for a in ((1e-3, 0.1, 1.0) if dist == "beckmann" else (0.1,)):
            for dif in (0.0, 1.0):
                for th in (0, 89.9):
                    M.append(bsdf_model("roughplastic", {"type": "roughplastic", "distribution": dist, "alpha": a,
                                                         "diffuse_reflectance": rgb(dif)}, th, domain="hemisphere",
                                        params=f"{dist} alpha {a:g} diffuse {dif:g}"))
    M.append(bsdf_model("roughplastic", {"type": "roughplastic", "alpha": 0.3, "nonlinear": True,
                                         "diffuse_reflectance": rgb(0.8)}, 45, domain="hemisphere",
                        params="beckmann alpha 0.3 diffuse 0.8 nonlinear"))
    # principled and principledthin
    for rough in (0.01, 0.3, 1.0):
        for th in (45, 89.9):
            M.append(bsdf_model("principled", {"type": "principled", "roughness": rough, "metallic": 0.4,
                                               "spec_trans": 0.3, "anisotropic": 0.3,
                                               "clearcoat": 0.5, "sheen": 0.3, "eta": 1.33}, th, domain="sphere",
                                energy=False, params=f"roughness {rough:g} metallic 0.4 spec_trans 0.3"))
    for th in (0, 89.9):
        M.append(bsdf_model("principled", {"type": "principled", "roughness": 0.5, "metallic": 1.0}, th,
                            domain="hemisphere", params="roughness 0.5 metallic 1"))
    for rough in (0.1, 0.6):
        M.append(bsdf_model("principledthin", {"type": "principledthin", "roughness": rough, "diff_trans": 0.3,
                                               "spec_trans": 0.4, "eta": 1.33}, 45, domain="sphere",
                            energy=False, params=f"roughness {rough:g} diff_trans 0.3 spec_trans 0.4"))
    # combinations
    for th in (45, 89.9):
        M.append(bsdf_model("blendbsdf", {"type": "blendbsdf", "weight": 0.3, "a": {"type": "diffuse"},
                                          "b": {"type": "roughconductor", "distribution": "ggx", "alpha": 0.05}},
                            th, domain="hemisphere", params="0.7 diffuse + 0.3 ggx conductor alpha 0.05"))
    M.append(bsdf_model("twosided", {"type": "twosided",
                                     "bsdf": {"type": "roughconductor", "distribution": "ggx", "alpha": 0.2}},
                        135, domain="sphere", params="ggx conductor alpha 0.2, seen from the back"))
    M.append(bsdf_model("pplastic", {"type": "pplastic", "alpha": 0.2}, 45, domain="hemisphere",
                        params="alpha 0.2 (unpolarised variant)"))
    # delta lobes through lobes=
    for eta in (1.5, 1.01):
        for th in ((0, 45, 89.9, 120, 150) if eta == 1.5 else (45, 135)):
            M.append(delta_model("dielectric", {"type": "dielectric", "int_ior": eta, "ext_ior": 1.0},
                                 lobes_dielectric(eta), th, domain="sphere", params=f"eta {eta:g}"))
    for th in (0, 45, 89.9):
        M.append(delta_model("thindielectric", {"type": "thindielectric", "int_ior": 1.5, "ext_ior": 1.0},
                             lobes_thin(1.5), th, domain="sphere", params="eta 1.5"))
    M.append(delta_model("conductor", {"type": "conductor", "material": "none"}, lobes_conductor(None, None), 45,
                         domain="hemisphere", params="material none (F = 1)"))
    for th in (45, 89.9):
        M.append(delta_model("conductor", {"type": "conductor", "eta": 0.2, "k": 3.0}, lobes_conductor(0.2, 3.0), th,
                             domain="hemisphere", params="eta 0.2 k 3"))
    for dif in (0.0, 1.0):
        for th in (0, 89.9):
            M.append(delta_model("plastic", {"type": "plastic", "int_ior": 1.5, "ext_ior": 1.0, "nonlinear": False,
                                             "diffuse_reflectance": rgb(dif)}, lobes_plastic(1.5, dif), th,
                                 domain="hemisphere", params=f"diffuse {dif:g}"))
    for op in (0.3, 0.9):
        M.append(delta_model("mask", {"type": "mask", "opacity": op, "bsdf": {"type": "diffuse"}}, lobes_mask(op),
                             45, domain="sphere", energy=True, params=f"opacity {op:g} over diffuse"))
    for v, th, ph in ((0.5, 60, 30), (0.85, 89.9, 120)):
        M.append(hair_model(v, th, ph))
    na = [
        ("bsdf", "null", "no scattering: sample() always fails and pdf(), eval() are 0; nothing to check"),
        ("bsdf", "bumpmap, normalmap", "a shading-frame perturbation from a texture over a nested BSDF (in the zoo): "
         "needs a surface interaction with differentials, not a direction pair"),
        ("bsdf", "measured", "needs an RGL measurement file (none ships with Mitsuba)"),
        ("bsdf", "polarizer, retarder, circular, measured_polarized",
         "polarised variants only (a Mueller matrix, not a scalar)"),
    ]
    return M, na


def phase_models():
    M = []

    def ph(name, spec, params, theta=40.0):
        wi = direction(theta, 20.0)

        def run(n, seed):
            m = pm.MitsubaPhase(spec)
            return mcstat.check_phase(m.sample, m.eval, m.pdf, wi, n=n, seed=seed, alpha=ALPHA, n_uniforms=3)
        return Model("phase", name, params, run)

    M.append(ph("isotropic", {"type": "isotropic"}, "-"))
    for g in (-0.9, -0.3, 0.0, 0.5, 0.9, 0.99):
        M.append(ph("hg", {"type": "hg", "g": g}, f"g {g:g}"))
    M.append(ph("rayleigh", {"type": "rayleigh"}, "-"))
    for label, S in (("surface-like (S_zz 0.01)", (1, 1, 0.01, 0, 0, 0)),
                     ("fibre-like (S_zz 1, S_xx = S_yy 0.01)", (0.01, 0.01, 1, 0, 0, 0)),
                     ("tilted, off-diagonal", (0.6, 0.3, 0.2, 0.2, 0.1, -0.05))):
        for th in (10, 80):
            grid = mi.VolumeGrid(np.array(S, dtype=np.float32).reshape(1, 1, 1, 6))
            M.append(ph("sggx", {"type": "sggx", "S": {"type": "gridvolume", "grid": grid, "raw": True,
                                                       "filter_type": "nearest"}}, f"{label}, wi theta {th:g}", th))
    for label, values in (("flat", "1, 1"), ("forward peak", "0.1, 0.2, 0.5, 1, 3, 20"),
                          ("backward, 3 nodes", "4, 0.5, 0.1")):
        M.append(ph("tabphase", {"type": "tabphase", "values": values}, f"{label}: {values}"))
    M.append(ph("blendphase", {"type": "blendphase", "weight": 0.3, "phase1": {"type": "isotropic"},
                               "phase2": {"type": "hg", "g": 0.8}}, "0.7 isotropic + 0.3 hg g 0.8"))
    return M, []


class Homogeneous(pm.MitsubaMedium):
    """phase_medium.MitsubaMedium with sigma_t, albedo and tmax as parameters."""

    def __init__(self, sigma_t, albedo, tmax):
        self.sigma_t, self.albedo, self.tmax = sigma_t, albedo, tmax
        self.med = mi.load_dict({"type": "homogeneous", "sigma_t": sigma_t, "albedo": albedo})
        self.sampler_med, self.bug = self.med, None
        self.ray = mi.Ray3f(mi.Point3f(0, 0, 0), mi.Vector3f(0, 0, 1))
        self.ray.maxt = tmax
        self.si = mi.SurfaceInteraction3f()
        self.si.t = tmax
        self.template = self.med.sample_interaction(self.ray, 0.5, 0, True)

    def sample(self, u):
        # MitsubaMedium.sample with this medium's tmax (the module's TMAX there)
        u = u32(u[:, 0])
        t, w, p = np.zeros(len(u)), np.zeros(len(u)), np.zeros(len(u))
        for k in range(len(u)):
            mei = self.med.sample_interaction(self.ray, float(u[k]), 0, True)
            if not (mei.is_valid() and mei.t < self.tmax):
                w[k] = 1.0
                continue
            tr, pdf, sigma_s = self._tr_pdf(mei)
            t[k], p[k], w[k] = mei.t, pdf, sigma_s * tr / pdf
        return t, w, p

    def _at(self, t, which):
        out = np.zeros(len(t))
        for k in range(len(t)):
            if not t[k] < self.tmax:
                continue
            mei = mi.MediumInteraction3f(self.template)
            mei.t = float(t[k])
            tr, pdf, sigma_s = self._tr_pdf(mei)
            out[k] = pdf if which == "pdf" else sigma_s * tr
        return out

    def check(self, n, seed):
        return mcstat.check_medium(self.sample, self.eval, self.pdf, sigma_ref=self.sigma_t, n=n, seed=seed,
                                   alpha=ALPHA, escape_transmittance=float(np.exp(-self.sigma_t * self.tmax)))


def medium_models():
    M = []
    for sigma_t, tmax in ((0.1, 1.0), (2.0, 1.0), (50.0, 1.0)):
        for albedo in (0.0, 0.75, 1.0):
            if sigma_t != 2.0 and albedo == 0.75:
                continue
            M.append(Model("medium", "homogeneous", f"sigma_t {sigma_t:g} albedo {albedo:g} tmax {tmax:g}",
                           lambda n, seed, a=(sigma_t, albedo, tmax): Homogeneous(*a).check(n, seed)))
    M.append(Model("medium", "heterogeneous", "8x4x4 grid, sigma_t 0.6..2.9, albedo 0.8, delta tracking, tmax 0.9",
                   lambda n, seed: pm.MitsubaHeterogeneous().check(n, seed)))
    return M, []


# ---- emitters -------------------------------------------------------------------------

_OBJ_DIR = tempfile.mkdtemp(prefix="mcstat_zoo_")


def _triangle(name, verts):
    path = os.path.join(_OBJ_DIR, name + ".obj")
    with open(path, "w") as f:
        for v in verts:
            f.write("v %.9g %.9g %.9g\n" % tuple(v))
        f.write("f 1 3 2\n")  # wound so that the emitting side faces the reference points
    return {"type": "obj", "filename": path, "face_normals": True}


T = mi.ScalarTransform4f
SHAPES = {
    # a triangle seen from the origin at a slant
    "triangle": lambda: _triangle("tri", [(-0.6, -0.4, 1.0), (0.7, -0.2, 1.3), (0.1, 0.8, 0.9)]),
    # a sliver: 1.2 long, 0.004 wide
    "thin triangle": lambda: _triangle("thin", [(-0.6, 0.1, 1.0), (0.6, 0.1, 1.1), (0.0, 0.104, 1.05)]),
    # straight above the reference point: its directions crowd the pole of mcstat's sphere map
    "near-pole triangle": lambda: _triangle("pole", [(-0.02, -0.02, 1.0), (0.03, -0.01, 1.0), (0.0, 0.03, 1.0)]),
    "disk": lambda: {"type": "disk", "to_world": T().translate([0.1, 0.2, 1.0]) @ T().rotate([1, 0, 0], 160.0)
                     @ T().scale([0.6, 0.6, 1.0])},
}


def _zoo_scene(shape):
    if shape not in SHAPES:
        return _original_scene(shape)
    light = SHAPES[shape]()
    light["emitter"] = {"type": "area", "radiance": rgb(2.0)}
    return mi.load_dict({"type": "scene", "light": light})


# mitsuba_adapters.emitter_callables builds its scene by emitter_scene(shape): the
# zoo's shapes are added to it, its callables reused as they are
_original_scene = ma.emitter_scene
ma.emitter_scene = _zoo_scene


def area_model(shape, ref, params):
    def run(n, seed):
        s, e, p = ma.emitter_callables(shape, ref=ref)
        return mcstat.check_emitter(s, e, p, n=n, seed=seed, alpha=ALPHA)
    return Model("emitter", "area " + shape, params + " from (%g, %g, %g)" % tuple(ref), run, n_key="n_emitter")


def infinite_callables(spec):
    """(sample, eval, pdf) of an infinite emitter (envmap, constant) from the
    origin: sample_direction, eval at the escaping direction, pdf_direction."""
    scene = mi.load_dict({"type": "scene", "env": spec,
                          "probe": {"type": "sphere", "center": [0, 0, 0], "radius": 0.01}})
    em = scene.emitters()[0]
    it = mi.Interaction3f()
    it.p = mi.Point3f(0, 0, 0)

    def sample(u):
        u = u32(u)
        k = len(u)
        d, w, p = np.zeros((k, 3)), np.zeros(k), np.zeros(k)
        for i in range(k):
            ds, spec_ = em.sample_direction(it, mi.Point2f(float(u[i, 0]), float(u[i, 1])))
            d[i] = (ds.d[0], ds.d[1], ds.d[2])
            w[i], p[i] = spec_[0], ds.pdf
        n = np.linalg.norm(d, axis=1)
        d[n > 0] /= n[n > 0, None]
        return d, np.where(p > 0, w, 0.0), p

    def eval_(d):
        out = np.zeros(len(d))
        si = mi.SurfaceInteraction3f()
        for i, di in enumerate(np.asarray(d, dtype=np.float32)):
            si.wi = mi.Vector3f(*[-float(c) for c in di])
            out[i] = em.eval(si)[0]
        return out

    def pdf(d):
        out = np.zeros(len(d))
        ds = mi.DirectionSample3f()
        for i, di in enumerate(np.asarray(d, dtype=np.float32)):
            ds.d = mi.Vector3f(*map(float, di))
            out[i] = em.pdf_direction(it, ds)
        return out
    return sample, eval_, pdf


def _envmap_bitmap(kind):
    h, w = 32, 64
    th = (np.arange(h) + 0.5) / h * np.pi
    ph = (np.arange(w) + 0.5) / w * 2 * np.pi
    TH, PH = np.meshgrid(th, ph, indexing="ij")
    if kind == "smooth":
        v = 0.2 + np.sin(TH) ** 2 * (1 + 0.5 * np.cos(PH))
    else:  # a sun: one bright texel block on a dim sky
        v = np.full((h, w), 0.05)
        v[6:8, 20:22] = 500.0
    img = np.repeat(v[:, :, None], 3, axis=2).astype(np.float32)
    return mi.Bitmap(img)


def infinite_model(name, spec_fn, params):
    def run(n, seed):
        s, e, p = infinite_callables(spec_fn())
        return mcstat.check_emitter(s, e, p, n=n, seed=seed, alpha=ALPHA)
    return Model("emitter", name, params, run, n_key="n_emitter")


def emitter_models():
    M = []
    for ref in ((0.2, -0.1, 0.8), (0.0, 0.0, 0.0), (1.03, -0.1, 0.645)):
        M.append(area_model("rectangle", ref, "1 x 1.6, tilted 20 deg,"))
    for ref in ((0.0, 0.0, 0.0), (0.3, 0.0, 1.95), (0.3, 0.0, -30.0)):
        M.append(area_model("sphere", ref, "radius 1 at (0.3, 0, 3),"))
    for ref in ((0.0, 0.0, 0.0), (0.6, -0.5, 0.9)):
        M.append(area_model("disk", ref, "radius 0.6, tilted 20 deg,"))
    for ref in ((0.0, 0.0, 0.0), (0.05, 0.1, 0.95)):
        M.append(area_model("triangle", ref, ""))
    M.append(area_model("thin triangle", (0.0, 0.0, 0.0), "1.2 x 0.004,"))
    M.append(area_model("near-pole triangle", (0.0, 0.0, 0.0), "0.05 across, straight above,"))
    M.append(infinite_model("envmap", lambda: {"type": "envmap", "bitmap": _envmap_bitmap("smooth")},
                            "32 x 64 smooth sky"))
    M.append(infinite_model("envmap", lambda: {"type": "envmap", "bitmap": _envmap_bitmap("sun")},
                            "32 x 64, a 2 x 2 texel sun 1e4 times the sky"))
    M.append(infinite_model("constant", lambda: {"type": "constant", "radiance": rgb(1.5)}, "radiance 1.5"))
    na = [
        ("emitter", "point, spot, projector", "a delta position: from a reference point the light arrives along one "
         "direction with no density (sample_direction's pdf is a probability)"),
        ("emitter", "directional, directionalarea", "a delta direction: no density over directions"),
        ("emitter", "area on curves, meshes of many faces", "the same area emitter as the shapes here "
         "(triangle, rectangle, disk, sphere)"),
    ]
    return M, na


FAMILIES = (("bsdf", bsdf_models), ("phase", phase_models), ("emitter", emitter_models), ("medium", medium_models))


# ---- running and the table ------------------------------------------------------------

def run_model(m, seeds, n, log):
    rejected, inconclusive, routes, rejecting = 0, 0, {}, []
    t0 = time.perf_counter()
    for seed in range(seeds):
        r = m.run(n, seed)
        if r.reject:
            rejected += 1
            rejecting.append(seed)
            for x in r.routes:
                if x.state == "ran" and x.reject:
                    routes[x.name] = routes.get(x.name, 0) + 1
            print(f"--- {m.key}: seed {seed} rejected\n{r}", file=log, flush=True)
        elif r.verdict == "inconclusive":
            inconclusive += 1
            print(f"--- {m.key}: seed {seed} inconclusive ({', '.join(r.unanswered)}): "
                  + "; ".join(f"{x.name}: {x.why}" for x in r.routes if x.name in r.unanswered), file=log, flush=True)
    return rejected, inconclusive, routes, rejecting, time.perf_counter() - t0


def environment():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    try:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        commit += " (with uncommitted changes)" if dirty else ""
    except OSError:
        commit = "unknown"
    return cpu, commit


def write(out, text):
    begin, end = "<!-- zoo:begin -->", "<!-- zoo:end -->"
    old = open(out).read() if os.path.exists(out) else ""
    if begin in old and end in old:
        new = old[:old.index(begin)] + begin + "\n" + text + end + old[old.index(end) + len(end):]
    else:
        new = "# The null zoo: correct Mitsuba 3 models through the renderer kit\n\n" + begin + "\n" + text + end + "\n"
    with open(out, "w") as f:
        f.write(new)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--n", type=int, default=20000, help="samples per check (BSDFs, phase functions, media)")
    ap.add_argument("--n-emitter", type=int, default=5000, help="samples per emitter check")
    ap.add_argument("--only", action="append", default=[],
                    help="only the models whose 'family/name params' matches this (a glob, or a substring; "
                         "repeat for several)")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "RESULTS_null_zoo.md"))
    ap.add_argument("--list", action="store_true", help="list the models and exit")
    a = ap.parse_args(argv)

    models, na = [], []
    for _, make in FAMILIES:
        m, x = make()
        models += m
        na += x
    if a.only:
        pats = [p if any(c in p for c in "*?[") else f"*{p}*" for p in a.only]
        models = [m for m in models if any(fnmatch.fnmatch(m.key, p) for p in pats)]
    if a.list:
        for m in models:
            print(m.key)
        return 0
    meta = META_ALPHA / max(1, len(models))
    cpu, commit = environment()
    sizes = {"n": a.n, "n_emitter": a.n_emitter}
    rows, outside, t_all = [], [], time.perf_counter()
    for i, m in enumerate(models):
        rej, inc, routes, seeds_rej, dt = run_model(m, a.seeds, sizes[m.n_key], sys.stderr)
        bt = mcstat.battery_test(rej, ALPHA, n=a.seeds, alternative="greater", meta_alpha=meta)
        verdict = "OUTSIDE" if bt.pvalue <= meta else "calibrated"
        if verdict == "OUTSIDE":
            outside.append(m.key)
        which = ", ".join(f"{k} ({v})" for k, v in sorted(routes.items(), key=lambda kv: -kv[1])) or "-"
        rows.append(f"| {m.family} | {m.name} | {m.params} | {sizes[m.n_key]} | {rej}/{a.seeds} | {inc} | {which} "
                    f"| {bt.pvalue:.3g} | {verdict} | {dt / a.seeds:.2f} |")
        print(f"[{i + 1}/{len(models)} {time.perf_counter() - t_all:.0f}s] {m.key}: {rej}/{a.seeds} rejected "
              f"(seeds {seeds_rej}), {inc} inconclusive, {which}, meta p {bt.pvalue:.3g} {verdict}",
              file=sys.stderr, flush=True)
    total = time.perf_counter() - t_all
    fam = {}
    for m in models:
        fam[m.family] = fam.get(m.family, 0) + 1
    cmd = "    .venv/bin/python bench/null_zoo.py " + " ".join(argv if argv is not None else sys.argv[1:])
    text = [
        "Made by\n", cmd.rstrip(), "",
        f"- CPU: {cpu} ({os.cpu_count()} cores, shared; one process, one thread)",
        f"- Mitsuba {mi.__version__}, variant {mi.variant()}; mcstat {mcstat.__version__}, commit {commit}",
        f"- n = {a.n} samples per check ({a.n_emitter} for emitters), alpha = {ALPHA}, seeds 0..{a.seeds - 1}",
        f"- models: {len(models)} (" + ", ".join(f"{k} {v}" for k, v in fam.items())
        + f"); wall time {total / 60:.1f} min",
        f"- meta-test: battery_test(rejections, {ALPHA}, n={a.seeds}, alternative=\"greater\"), meta_alpha "
        f"{META_ALPHA} / {len(models)} models = {meta:.3g} (Bonferroni): a model is OUTSIDE when its p-value "
        "is at most that",
        f"- OUTSIDE: {len(outside)}" + (": " + "; ".join(outside) if outside else ""), "",
        "| family | model | parameters | n | rejected | inconclusive | routes that rejected (runs) | meta p "
        "| verdict | s per check |",
        "|---|---|---|---|---|---|---|---|---|---|",
        *rows, "",
        "Not applicable (the kit checks densities over directions or distances):", "",
        *[f"- {f} `{name}`: {why}" for f, name, why in na], "",
    ]
    write(a.out, "\n".join(text) + "\n")
    print(f"wrote {a.out}: {len(models)} models, {len(outside)} outside, {total / 60:.1f} min", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
