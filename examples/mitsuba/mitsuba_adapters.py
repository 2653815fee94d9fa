"""Mitsuba 3 BSDFs and emitters as the callables of mcstat.check_bsdf / check_emitter,
and BSDFs with planted bugs that Mitsuba's own chi2 test sees too.

Variants.  In a JIT variant (llvm_ad_rgb) each callable evaluates a whole
batch in one Dr.Jit kernel; in scalar_rgb it loops in Python (sample() 10 to
80 times slower per sample, a whole check_bsdf 6 to 17 times: RESULTS.md).
pick_variant() chooses llvm_ad_rgb when it works here and scalar_rgb
otherwise.  Dr.Jit's LLVM backend needs a
libLLVM it can generate code with: LLVM 15 aborts in code generation on some
CPUs (a process abort, not an exception), so pick_variant() probes llvm in a
subprocess, and points DRJIT_LIBLLVM_PATH at Debian's libllvm19 when it is
installed and the variable is unset.

Float32.  Mitsuba's rgb variants compute in float32: the uniforms mcstat
supplies (float64 in [0, 1)) are rounded to float32 and clamped below 1 (a
float64 just below 1 rounds to 1.0f, outside Mitsuba's [0, 1) contract), and
directions and values come back as float32 values widened to float64.

Failed samples.  Mitsuba marks a failed BSDF sample by a zero weight and may
leave bs.pdf > 0 (e.g. a rough conductor's microfacet sample reflected below
the horizon); mcstat wants pdf 0 and weight 0.  The adapters report pdf 0
wherever every colour channel of the weight is 0, which is also how
Mitsuba's own chi2 BSDFAdapter decides that a sample failed.

Planted bugs (PLANTED_BUGS), each a Python BSDF plugin ("mcstat_planted",
registered with mi.register_bsdf) wrapping a correct Mitsuba BSDF, so that
mcstat.check_bsdf and Mitsuba's mitsuba.chi2.ChiSquareTest (via BSDFAdapter
and a load_dict dictionary) test the same object:
  sampler  sample() draws its direction from the BSDF with roughness * 1.1 but
           reports the correct BSDF's pdf() and eval()/pdf() at that direction
           (a sampler that does not draw from the density it claims);
  pdf      pdf() is the pdf of the BSDF with roughness * 1.1; sample() correct;
  eval     eval() is the eval of the BSDF with roughness * 1.1; sample() (its
           direction, pdf and weight) correct;
  weight   sample()'s weight is 1.1 * eval/pdf; everything else correct.
(1.1 is BUG_FACTOR, planted_dict's factor argument.)
"""
import os
import subprocess
import sys

import numpy as np

LLVM_VARIANT = "llvm_ad_rgb"
SCALAR_VARIANT = "scalar_rgb"
_LIBLLVM_CANDIDATES = ("/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so",
                       "/usr/lib/llvm-19/lib/libLLVM.so.1", "/usr/lib/llvm-19/lib/libLLVM-19.so")

if "DRJIT_LIBLLVM_PATH" not in os.environ:
    for _p in _LIBLLVM_CANDIDATES:
        if os.path.exists(_p):
            os.environ["DRJIT_LIBLLVM_PATH"] = _p
            break

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402

PLANTED_BUGS = ("sampler", "pdf", "eval", "weight")
BUG_FACTOR = 1.1
_ROUGHNESS_KEYS = ("alpha", "alpha_u", "alpha_v", "roughness")
# the largest float32 below 1: uniforms are clamped to it after rounding
_ONE_MINUS = float(np.nextafter(np.float32(1), np.float32(0)))

_PROBE = """
import mitsuba as mi, drjit as dr
mi.set_variant('%s')
b = mi.load_dict({'type': 'roughconductor'})
si = dr.zeros(mi.SurfaceInteraction3f, 16); si.wi = mi.Vector3f(0, 0, 1)
bs, w = b.sample(mi.BSDFContext(), si, dr.full(mi.Float, 0.3, 16), mi.Point2f(0.2, 0.7))
dr.eval(w); print('ok', w[0][0] > 0)
"""

_variant_choice = None


def loaded_libllvm():
    """The libLLVM this process has mapped (None before the first LLVM kernel)."""
    with open("/proc/self/maps") as f:
        for line in f:
            if "libLLVM" in line:
                return line.split()[-1]
    return None


def pick_variant():
    """llvm_ad_rgb when it runs here (probed once per process in a subprocess:
    a broken LLVM aborts the process), else scalar_rgb.  MCSTAT_MITSUBA_VARIANT
    overrides the choice."""
    global _variant_choice
    forced = os.environ.get("MCSTAT_MITSUBA_VARIANT")
    if forced:
        return forced
    if _variant_choice is None:
        _variant_choice = SCALAR_VARIANT
        if LLVM_VARIANT in mi.variants():
            try:
                r = subprocess.run([sys.executable, "-c", _PROBE % LLVM_VARIANT], capture_output=True,
                                   text=True, timeout=120, env=os.environ.copy())
                if r.returncode == 0 and "ok True" in r.stdout:
                    _variant_choice = LLVM_VARIANT
            except (OSError, subprocess.SubprocessError):
                pass
    return _variant_choice


def use_variant(variant=None):
    """Sets the Mitsuba variant (pick_variant() if None) and registers the planted-bug plugin for it."""
    variant = variant or pick_variant()
    if mi.variant() != variant:
        mi.set_variant(variant)
    _register_planted()
    return variant


def is_jit():
    return not mi.variant().startswith("scalar")


# ---- BSDF configurations: as Mitsuba's own test suite sets them up ---------------

# name -> (load_dict dictionary, wi (unnormalised), mcstat domain, ChiSquareTest keyword arguments)
# from src/bsdfs/tests/test_rough_conductor.py (test05, test03), test_rough_plastic.py
# (test02), test_rough_dielectric.py (test04 with ggx; test05) and test_principled.py
# (test01) of mitsuba-renderer/mitsuba3.
BSDF_CONFIGS = {
    "conductor_ggx_aniso": (
        {"type": "roughconductor", "alpha_u": 0.2, "alpha_v": 0.05, "distribution": "ggx",
         "sample_visible": True},
        (1.0, 1.0, 1.0), "hemisphere", {"ires": 8}),
    "conductor_beckmann_aniso": (
        {"type": "roughconductor", "alpha_u": 0.2, "alpha_v": 0.05, "distribution": "beckmann",
         "sample_visible": True},
        (1.0, 1.0, 1.0), "hemisphere", {"ires": 16}),
    "plastic": (
        {"type": "roughplastic", "alpha": 0.25,
         "specular_reflectance": {"type": "rgb", "value": 0.7},
         "diffuse_reflectance": {"type": "rgb", "value": 0.1}},
        (0.0, 0.0, 1.0), "hemisphere", {}),
    "dielectric": (
        {"type": "roughdielectric", "alpha": 0.5, "distribution": "ggx", "sample_visible": True},
        (0.5, 0.0, 0.5), "sphere", {}),
    # sample_visible = false: Mitsuba's sampler widens alpha by 1.2 - 0.2 sqrt|cos theta_i|
    # and reports that distribution's pdf, but its weight omits D(m) / D_sampled(m), so
    # weight != eval / pdf (ratio 0.94 at this wi, 0.75 at grazing wi): mcstat rejects the
    # unmodified BSDF; Mitsuba's chi2 (directions vs pdf only) cannot see it.
    "dielectric_ggx_all": (
        {"type": "roughdielectric", "alpha": 0.5, "distribution": "ggx", "sample_visible": False},
        (0.5, 0.0, 0.5), "sphere", {"res": 201}),
    "principled": (
        {"type": "principled", "roughness": 0.6, "metallic": 0.4, "anisotropic": 0.4,
         "clearcoat": 0.8, "eta": 1.33},
        (1.0, 0.0, 1.0), "sphere", {}),
}


def normalized(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def rougher(bsdf_dict, factor=BUG_FACTOR):
    """The dictionary with every roughness parameter times factor."""
    d = dict(bsdf_dict)
    hit = False
    for k in _ROUGHNESS_KEYS:
        if k in d:
            d[k] = d[k] * factor
            hit = True
    if not hit:
        raise ValueError("bsdf_dict has no roughness parameter (%s)" % ", ".join(_ROUGHNESS_KEYS))
    return d


# ---- the planted-bug plugin -------------------------------------------------------

# load_dict hands a Python plugin its parameters as Properties; the two
# dictionaries it wraps live here, under the string key it receives.
_PLANTED_REGISTRY = {}
_registered_for = set()


def _make_planted_class():
    class PlantedBug(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            key = props["key"]
            base_dict, bug, factor = _PLANTED_REGISTRY[key]
            self.bug, self.factor = bug, factor
            self.base = mi.load_dict(base_dict)
            self.wrong = mi.load_dict(rougher(base_dict, factor))
            self.m_flags = self.base.flags()
            self.m_components = [self.base.flags(i) for i in range(self.base.component_count())]

        def sample(self, ctx, si, sample1, sample2, active=True):
            if self.bug == "sampler":
                bs, _ = self.wrong.sample(ctx, si, sample1, sample2, active)
                ok = active & (bs.pdf > 0)
                pdf = self.base.pdf(ctx, si, bs.wo, ok)
                value = self.base.eval(ctx, si, bs.wo, ok)
                ok &= pdf > 0
                bs.pdf = dr.select(ok, pdf, 0.0)
                return bs, dr.select(ok, value / dr.select(ok, pdf, 1.0), 0.0)
            bs, weight = self.base.sample(ctx, si, sample1, sample2, active)
            if self.bug == "weight":
                weight = weight * self.factor
            return bs, weight

        def eval(self, ctx, si, wo, active=True):
            return (self.wrong if self.bug == "eval" else self.base).eval(ctx, si, wo, active)

        def pdf(self, ctx, si, wo, active=True):
            return (self.wrong if self.bug == "pdf" else self.base).pdf(ctx, si, wo, active)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self.eval(ctx, si, wo, active), self.pdf(ctx, si, wo, active)

        def to_string(self):
            return "PlantedBug[%s]" % self.bug

    return PlantedBug


def _register_planted():
    v = mi.variant()
    if v not in _registered_for:
        mi.register_bsdf("mcstat_planted", lambda props: _make_planted_class()(props))
        _registered_for.add(v)


def planted_dict(bsdf_dict, bug, factor=BUG_FACTOR):
    """A load_dict dictionary of bsdf_dict with a planted bug (one of
    PLANTED_BUGS; factor replaces 1.1), or bsdf_dict itself for bug None / "none"."""
    if bug in (None, "none"):
        return bsdf_dict
    if bug not in PLANTED_BUGS:
        raise ValueError("bug must be one of %s or None, not %r" % (", ".join(PLANTED_BUGS), bug))
    _register_planted()
    key = "%s/%d" % (bug, len(_PLANTED_REGISTRY))
    _PLANTED_REGISTRY[key] = (bsdf_dict, bug, float(factor))
    return {"type": "mcstat_planted", "key": key}


# ---- BSDF -> mcstat callables -------------------------------------------------------

def _u32(u):
    u = np.asarray(u, dtype=np.float64).astype(np.float32)
    return np.minimum(u, np.float32(_ONE_MINUS))


def bsdf_callables(bsdf, channel=0):
    """(sample, eval, pdf) for mcstat.check_bsdf from a Mitsuba BSDF object (or a
    load_dict dictionary) of the current variant.  `channel`: which colour
    channel of eval() and of the weight is checked (each channel's weight is
    that channel's eval / pdf)."""
    if isinstance(bsdf, dict):
        bsdf = mi.load_dict(bsdf)
    ctx = mi.BSDFContext()
    return (_jit_bsdf if is_jit() else _scalar_bsdf)(bsdf, ctx, channel)


def _jit_bsdf(bsdf, ctx, ch):
    def interaction(wi, k):
        si = dr.zeros(mi.SurfaceInteraction3f, k)
        si.wi = mi.Vector3f(*[float(c) for c in wi])
        return si

    def vec(x):
        x = np.asarray(x, dtype=np.float32)
        return mi.Vector3f(x[:, 0], x[:, 1], x[:, 2])

    def sample(wi, u):
        u = _u32(u)
        k = len(u)
        bs, w = bsdf.sample(ctx, interaction(wi, k), mi.Float(u[:, 0]), mi.Point2f(u[:, 1], u[:, 2]))
        wo = np.array(bs.wo, dtype=np.float64).reshape(3, k).T
        weight = np.array(w[ch], dtype=np.float64)
        failed = np.array(dr.all(w == 0.0), dtype=bool)
        pdf = np.where(failed, 0.0, np.array(bs.pdf, dtype=np.float64))
        return wo, weight, pdf

    def eval_(wi, wo):
        wo = np.asarray(wo)
        return np.array(bsdf.eval(ctx, interaction(wi, len(wo)), vec(wo))[ch], dtype=np.float64)

    def pdf(wi, wo):
        wo = np.asarray(wo)
        return np.array(bsdf.pdf(ctx, interaction(wi, len(wo)), vec(wo)), dtype=np.float64)

    return sample, eval_, pdf


def _scalar_bsdf(bsdf, ctx, ch):
    def interaction(wi):
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*[float(c) for c in wi])
        return si

    def sample(wi, u):
        u = _u32(u)
        si = interaction(wi)
        k = len(u)
        wo, weight, pdf = np.zeros((k, 3)), np.zeros(k), np.zeros(k)
        for i in range(k):
            bs, w = bsdf.sample(ctx, si, float(u[i, 0]), mi.Point2f(float(u[i, 1]), float(u[i, 2])))
            wo[i] = (bs.wo[0], bs.wo[1], bs.wo[2])
            weight[i] = w[ch]
            pdf[i] = 0.0 if all(w[c] == 0.0 for c in range(len(w))) else bs.pdf
        return wo, weight, pdf

    def eval_(wi, wo):
        si = interaction(wi)
        return np.array([bsdf.eval(ctx, si, mi.Vector3f(*map(float, d)))[ch] for d in np.asarray(wo)])

    def pdf(wi, wo):
        si = interaction(wi)
        return np.array([bsdf.pdf(ctx, si, mi.Vector3f(*map(float, d))) for d in np.asarray(wo)])

    return sample, eval_, pdf


def config_callables(name, bug=None, channel=0, factor=BUG_FACTOR):
    """(sample, eval, pdf, wi, domain) of BSDF_CONFIGS[name] with a planted bug
    (or None), in the current variant."""
    d, wi, domain, _ = BSDF_CONFIGS[name]
    s, e, p = bsdf_callables(planted_dict(d, bug, factor), channel)
    return s, e, p, normalized(wi), domain


# ---- emitters -----------------------------------------------------------------------

EMITTER_BUGS = PLANTED_BUGS


def emitter_scene(shape="rectangle"):
    """A scene holding one area light, seen from the origin: a 1 x 1.6 rectangle
    at height 1 facing down (tilted 20 degrees), or a unit sphere 3 above."""
    T = mi.ScalarTransform4f
    if shape == "rectangle":
        to_world = (T().translate([0.2, -0.1, 1.0]) @ T().rotate([0, 1, 0], 20.0) @ T().rotate([1, 0, 0], 180.0)
                    @ T().scale([0.5, 0.8, 1.0]))
        light = {"type": "rectangle", "to_world": to_world}
    elif shape == "sphere":
        light = {"type": "sphere", "center": [0.3, 0.0, 3.0], "radius": 1.0}
    else:
        raise ValueError("shape must be 'rectangle' or 'sphere', not %r" % (shape,))
    light["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": 2.0}}
    return mi.load_dict({"type": "scene", "light": light})


def emitter_callables(shape="rectangle", ref=(0.0, 0.0, 0.0), bug=None, channel=0, factor=BUG_FACTOR):
    """(sample, eval, pdf) for mcstat.check_emitter: the area light of
    emitter_scene(shape) sampled by direction from the point ref.  eval(d) is
    the radiance arriving at ref along d (0 where the ray misses the light),
    pdf(d) Mitsuba's pdf_direction for the point the ray hits.  Planted bugs
    (EMITTER_BUGS), as plain wrappers: sampler (the first uniform u0 replaced by
    u0^1.2 before Mitsuba's sampler: directions off, pdf and weight reported as
    pdf() and eval()/pdf() there), pdf (pdf() * 1.1 where d.x > 0.2), eval
    (eval() * 1.1), weight (sample weight * 1.1); `factor` replaces 1.1, and
    1 + 2 (factor - 1) replaces the sampler's exponent 1.2."""
    if bug not in (None, "none") and bug not in EMITTER_BUGS:
        raise ValueError("bug must be one of %s or None, not %r" % (", ".join(EMITTER_BUGS), bug))
    scene = emitter_scene(shape)
    emitter = scene.emitters()[0]
    ref = [float(c) for c in ref]
    jit = is_jit()

    def raw_sample(u):
        u = _u32(u)
        if bug == "sampler":
            u[:, 0] = u[:, 0] ** np.float32(1.0 + 2.0 * (factor - 1.0))
        k = len(u)
        if jit:
            it = dr.zeros(mi.Interaction3f, k)
            it.p = mi.Point3f(*ref)
            ds, spec = emitter.sample_direction(it, mi.Point2f(u[:, 0], u[:, 1]))
            d = np.array(ds.d, dtype=np.float64).reshape(3, k).T
            return d, np.array(spec[channel], dtype=np.float64), np.array(ds.pdf, dtype=np.float64)
        it = mi.Interaction3f()
        it.p = mi.Point3f(*ref)
        d, w, p = np.zeros((k, 3)), np.zeros(k), np.zeros(k)
        for i in range(k):
            ds, spec = emitter.sample_direction(it, mi.Point2f(float(u[i, 0]), float(u[i, 1])))
            d[i] = (ds.d[0], ds.d[1], ds.d[2])
            w[i], p[i] = spec[channel], ds.pdf
        return d, w, p

    def hit(d):
        """(si, it): the rays from ref along the directions d (JIT variants)."""
        d = np.asarray(d, dtype=np.float32)
        it = dr.zeros(mi.Interaction3f, len(d))
        it.p = mi.Point3f(*ref)
        return scene.ray_intersect(mi.Ray3f(mi.Point3f(*ref), mi.Vector3f(d[:, 0], d[:, 1], d[:, 2]))), it

    def raw_eval(d):
        if jit:
            si, _ = hit(d)
            valid = si.is_valid()  # a masked-off lane is not zeroed by eval(): select
            return np.array(dr.select(valid, emitter.eval(si, valid)[channel], 0.0), dtype=np.float64)
        out = np.zeros(len(d))
        for i, di in enumerate(np.asarray(d, dtype=np.float32)):
            si = scene.ray_intersect(mi.Ray3f(mi.Point3f(*ref), mi.Vector3f(*map(float, di))))
            if si.is_valid():
                out[i] = emitter.eval(si)[channel]
        return out

    def raw_pdf(d):
        if jit:
            si, it = hit(d)
            ds = mi.DirectionSample3f(scene, si, it)
            valid = si.is_valid()
            return np.array(dr.select(valid, emitter.pdf_direction(it, ds, valid), 0.0), dtype=np.float64)
        out = np.zeros(len(d))
        it = mi.Interaction3f()
        it.p = mi.Point3f(*ref)
        for i, di in enumerate(np.asarray(d, dtype=np.float32)):
            si = scene.ray_intersect(mi.Ray3f(mi.Point3f(*ref), mi.Vector3f(*map(float, di))))
            if si.is_valid():
                out[i] = emitter.pdf_direction(it, mi.DirectionSample3f(scene, si, it))
        return out

    def sample(u):
        d, w, p = raw_sample(u)
        if bug == "weight":
            w = w * factor
        return d, w, p

    def eval_(d):
        v = raw_eval(d)
        return v * factor if bug == "eval" else v

    def pdf(d):
        p = raw_pdf(d)
        if bug == "pdf":
            p = np.where(np.asarray(d)[:, 0] > 0.2, p * factor, p)
        return p

    return sample, eval_, pdf


# ---- Mitsuba's own chi2 test on the same objects -------------------------------------

def mitsuba_chi2(name, bug=None, seed=0, sample_count=1_000_000, factor=BUG_FACTOR, **overrides):
    """Runs mitsuba.chi2.ChiSquareTest as Mitsuba's suite calls it for
    BSDF_CONFIGS[name] (its res/ires, SphericalDomain, sample_dim 3), on the BSDF
    with the planted bug, with the given seed.  Needs a JIT variant (the test
    tabulates with Dr.Jit arrays).  Returns (accepted, p_value, test)."""
    from mitsuba import chi2 as mchi2
    d, wi, _, kw = BSDF_CONFIGS[name]
    pd = planted_dict(d, bug, factor)
    kw = dict(kw, **overrides)
    sample_func, pdf_func = mchi2.BSDFAdapter(pd["type"], pd, wi=dr.normalize(mi.ScalarVector3f(*wi)))
    test = mchi2.ChiSquareTest(domain=mchi2.SphericalDomain(), sample_func=sample_func, pdf_func=pdf_func,
                               sample_dim=3, sample_count=sample_count, seed=seed, **kw)
    ok = test.run(quiet=True)
    return bool(ok), float(test.p_value[0] if hasattr(test.p_value, "__len__") else test.p_value), test
