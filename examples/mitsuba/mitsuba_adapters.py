"""The examples' Mitsuba 3 set-up over the shipped adapters (mcstat.mitsuba):
the BSDF configurations of Mitsuba's own tests, BSDFs and area lights with
planted bugs, and Mitsuba's own chi2 test on the same objects.

The adapting itself (variant choice, float32 uniforms, the failed-sample
convention, the callables of check_bsdf and check_emitter) is
mcstat.mitsuba's, installed with ``pip install 'mcstat[mitsuba]'``; this
file re-exports what the examples use of it (pick_variant, bsdf_callables,
emitter_callables), so that there is one implementation.

Variants.  In a JIT variant (llvm_ad_rgb) each callable evaluates a whole
batch in one Dr.Jit kernel; in scalar_rgb it loops in Python (sample() 10 to
80 times slower per sample, a whole check_bsdf 6 to 17 times: RESULTS.md).
pick_variant() chooses llvm_ad_rgb when it works here and scalar_rgb
otherwise (mcstat.mitsuba.pick_variant: Dr.Jit's LLVM backend needs a
libLLVM it can generate code with; LLVM 15 aborts on some CPUs, so llvm is
probed in a subprocess, and DRJIT_LIBLLVM_PATH points at Debian's libllvm19
when it is installed and the variable is unset).

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
  weight   sample()'s weight is 1.1 * eval/pdf; everything else correct (also
           on a BSDF without roughness: a dielectric's discrete samples).
(1.1 is BUG_FACTOR, planted_dict's factor argument.)
"""
import numpy as np

import mcstat.mitsuba as mm
from mcstat.mitsuba import _env

LLVM_VARIANT = _env.LLVM_VARIANT
SCALAR_VARIANT = _env.SCALAR_VARIANT
mi, dr = _env.modules()  # DRJIT_LIBLLVM_PATH set before Dr.Jit loads

PLANTED_BUGS = ("sampler", "pdf", "eval", "weight")
BUG_FACTOR = 1.1
_ROUGHNESS_KEYS = ("alpha", "alpha_u", "alpha_v", "roughness")
pick_variant = mm.pick_variant


def loaded_libllvm():
    """The libLLVM this process has mapped (None before the first LLVM kernel)."""
    with open("/proc/self/maps") as f:
        for line in f:
            if "libLLVM" in line:
                return line.split()[-1]
    return None


def use_variant(variant=None):
    """Sets the Mitsuba variant (pick_variant() if None) and registers the planted-bug plugin for it."""
    variant = _env.ensure_variant(variant or pick_variant())
    _register_planted()
    return variant


def is_jit():
    return _env.is_jit(mi.variant())


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
            self.wrong = None if bug == "weight" else mi.load_dict(rougher(base_dict, factor))
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


# ---- phase functions and media with planted bugs --------------------------------------

# Python plugins ("mcstat_planted_phase", "mcstat_planted_medium") wrapping a
# correct Mitsuba object, loadable by load_dict like any plugin, so that the
# shipped one-liners (mcstat.mitsuba.check_phase / check_medium) see them:
#   phase   pdf      eval_pdf()'s pdf from the phase function with g * factor
#                    (hg); sample() correct
#           weight   sample()'s weight * factor
#   medium  sampler  sample_interaction() from the medium with sigma_t * factor;
#                    the coefficients (get_scattering_coefficients) correct
#           accept   sample_interaction()'s sigma_t * factor: delta tracking then
#                    takes a tentative collision for a real one too often (a
#                    heterogeneous medium: in a homogeneous one every tentative
#                    collision is real)
PHASE_BUGS = ("pdf", "weight")
MEDIUM_BUGS = ("sampler", "accept")
_registered_other = set()


def _make_planted_phase():
    class PlantedPhase(mi.PhaseFunction):
        def __init__(self, props):
            mi.PhaseFunction.__init__(self, props)
            base_dict, bug, factor = _PLANTED_REGISTRY[props["key"]]
            self.bug, self.factor = bug, factor
            self.base = mi.load_dict(base_dict)
            self.wrong = mi.load_dict(dict(base_dict, g=base_dict["g"] * factor)) if bug == "pdf" else self.base
            self.m_flags = self.base.flags()

        def sample(self, ctx, mei, sample1, sample2, active=True):
            wo, w, pdf = self.base.sample(ctx, mei, sample1, sample2, active)
            return wo, (w * self.factor if self.bug == "weight" else w), pdf

        def eval_pdf(self, ctx, mei, wo, active=True):
            value, _ = self.base.eval_pdf(ctx, mei, wo, active)
            return value, self.wrong.eval_pdf(ctx, mei, wo, active)[1]

        def to_string(self):
            return "PlantedPhase[%s]" % self.bug

    return PlantedPhase


def _make_planted_medium():
    class PlantedMedium(mi.Medium):
        def __init__(self, props):
            mi.Medium.__init__(self, props)
            base_dict, bug, factor = _PLANTED_REGISTRY[props["key"]]
            self.bug, self.factor = bug, factor
            self.base = mi.load_dict(base_dict)
            self.wrong = mi.load_dict(dict(base_dict, sigma_t=base_dict["sigma_t"] * factor)) \
                if bug == "sampler" else self.base

        def sample_interaction(self, ray, sample, channel, active=True):
            mei = self.wrong.sample_interaction(ray, sample, channel, active)
            if self.bug == "accept":
                mei.sigma_t = mei.sigma_t * self.factor
            return mei

        def get_scattering_coefficients(self, mei, active=True):
            return self.base.get_scattering_coefficients(mei, active)

        def is_homogeneous(self):
            return self.base.is_homogeneous()

        def to_string(self):
            return "PlantedMedium[%s]" % self.bug

    return PlantedMedium


def _planted_other(kind, base_dict, bug, factor, bugs):
    if bug not in bugs:
        raise ValueError("bug must be one of %s, not %r" % (", ".join(bugs), bug))
    name = "mcstat_planted_" + kind
    if (name, mi.variant()) not in _registered_other:
        if kind == "phase":
            register = getattr(mi, "register_phase", None) or mi.register_phasefunction  # 3.6's name
            register(name, lambda props: _make_planted_phase()(props))
        else:
            mi.register_medium(name, lambda props: _make_planted_medium()(props))
        _registered_other.add((name, mi.variant()))
    key = "%s/%s/%d" % (kind, bug, len(_PLANTED_REGISTRY))
    _PLANTED_REGISTRY[key] = (base_dict, bug, float(factor))
    return {"type": name, "key": key}


def planted_phase_dict(phase_dict, bug, factor=BUG_FACTOR):
    """A load_dict dictionary of a phase function (hg for "pdf") with a planted bug (PHASE_BUGS)."""
    return _planted_other("phase", phase_dict, bug, factor, PHASE_BUGS)


def planted_medium_dict(medium_dict, bug, factor=BUG_FACTOR):
    """A load_dict dictionary of a medium (homogeneous for "sampler") with a planted bug (MEDIUM_BUGS)."""
    return _planted_other("medium", medium_dict, bug, factor, MEDIUM_BUGS)


# ---- BSDF -> mcstat callables: mcstat.mitsuba's -------------------------------------

def _u32(u):
    """mcstat's uniforms as Mitsuba's float32 variants take them (float32, below 1)."""
    return _env.uniforms(u, mi.variant()).astype(np.float32)


def bsdf_callables(bsdf, channel=0):
    """(sample, eval, pdf) for mcstat.check_bsdf from a Mitsuba BSDF object (or a
    load_dict dictionary) of the current variant: mcstat.mitsuba.bsdf_model's.
    `channel`: which colour channel of eval() and of the weight is checked."""
    m = mm.bsdf_model(bsdf, channel=channel, lobes=None, variant=mi.variant())
    return m.sample, m.eval, m.pdf


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
    emitter_scene(shape) sampled by direction from the point ref
    (mcstat.mitsuba.emitter_model's callables).  eval(d) is
    the radiance arriving at ref along d (0 where the ray misses the light),
    pdf(d) Mitsuba's pdf_direction for the point the ray hits.  Planted bugs
    (EMITTER_BUGS), as plain wrappers: sampler (the first uniform u0 replaced by
    u0^1.2 before Mitsuba's sampler: directions off, pdf and weight reported as
    pdf() and eval()/pdf() there), pdf (pdf() * 1.1 where d.x > 0.2), eval
    (eval() * 1.1), weight (sample weight * 1.1); `factor` replaces 1.1, and
    1 + 2 (factor - 1) replaces the sampler's exponent 1.2."""
    if bug not in (None, "none") and bug not in EMITTER_BUGS:
        raise ValueError("bug must be one of %s or None, not %r" % (", ".join(EMITTER_BUGS), bug))
    model = mm.emitter_model(emitter_scene(shape), ref, channel=channel, variant=mi.variant())
    exponent = np.float32(1.0 + 2.0 * (factor - 1.0))

    def raw_sample(u):
        if bug == "sampler":
            u = _u32(u)
            u[:, 0] = u[:, 0] ** exponent
        return model.sample(u)

    raw_eval, raw_pdf = model.eval, model.pdf

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
