"""mcstat on a real renderer: Mitsuba 3 (the `mitsuba` wheel, variant scalar_rgb).

(a) Section 3.2's BSDF test on Mitsuba's anisotropic rough conductor (GGX,
    alpha_u = 0.2, alpha_v = 0.5).  Two independent sets of directions:
      - Mitsuba's bsdf.sample(), each direction kept with probability w / w_max,
        w = eval*cos / pdf the weight the renderer would use (importance
        resampling): if sample() really draws from pdf(), the kept directions
        follow eval*cos, whatever pdf() is;
      - directions drawn by rejection from bsdf.eval() (which includes the
        cosine) with a uniform-hemisphere proposal, independent of the sampler.
    Both are mapped to Morton keys (libmcest's mcest_direction_key: equal-area
    map, 32 bits per coordinate) and compared with mcstat's two-sample K-S test
    (Canner's weight, exact p-value) at alpha = 0.01.  The planted bug draws
    directions with a wrong sampling parameter (alpha_u = 0.3) while weighting
    them as if they came from the right material's pdf() - the situation of
    Ward's sampler in the paper (ERRATA 9) - and must be detected.
(b) Section 3.1's scene: one Lambertian triangle light above a receiver,
    rendered by Mitsuba (irradiancemeter on a 2e-3-wide receiver, `direct`
    integrator) at 64 seeds; the one-sample t test of the pixel's irradiance
    against Lambert's formula (libmcest's mcest_irradiance_exact, for the
    float32 vertices Mitsuba stores) must not reject at alpha = 0.01, and the
    same renders must reject a reference 1% off.

libmcstat and libmcest are called through ctypes (examples/ctypes), i.e. the
C ABI only.  Needs the `mitsuba` wheel (examples/mitsuba/requirements.txt).
If `make mitsuba-test` could not install it, it sets
MCSTAT_MITSUBA_UNAVAILABLE to pip's reason and these tests skip with it; in
every other case a missing or broken Mitsuba fails.
"""
import ctypes
import math
import os
import struct
import sys
import tempfile

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "examples", "ctypes"))
import mcstat_ctypes as mc  # noqa: E402

_unavailable = os.environ.get("MCSTAT_MITSUBA_UNAVAILABLE")
if _unavailable:
    pytest.skip("the mitsuba wheel could not be installed here: " + _unavailable, allow_module_level=True)
import mitsuba as mi  # noqa: E402  (a missing wheel fails here unless declared unavailable above)

mi.set_variant("scalar_rgb")

LIBDIR = os.environ.get("MCSTAT_LIBDIR", os.path.join(ROOT, "build", "stage", "lib"))
ALPHA = 0.01


class McestScene(ctypes.Structure):
    _fields_ = [("triangle", ctypes.c_double * 9), ("point", ctypes.c_double * 3),
                ("normal", ctypes.c_double * 3), ("radiance", ctypes.c_double)]


@pytest.fixture(scope="module")
def libs():
    lib = mc.load(os.path.join(LIBDIR, "libmcstat.so"))
    est = ctypes.CDLL(os.path.join(LIBDIR, "libmcest.so"))
    est.mcest_sizeof_scene.restype = ctypes.c_size_t
    assert est.mcest_sizeof_scene() == ctypes.sizeof(McestScene)
    est.mcest_irradiance_exact.argtypes = [ctypes.POINTER(McestScene), ctypes.POINTER(ctypes.c_double)]
    est.mcest_direction_key.argtypes = [ctypes.POINTER(ctypes.c_double), ctypes.c_size_t,
                                        ctypes.POINTER(ctypes.c_uint64)]
    return lib, est


def morton_keys(est, dirs):
    w = np.ascontiguousarray(dirs, dtype=np.float64)
    w /= np.linalg.norm(w, axis=1, keepdims=True)
    keys = np.zeros(len(w), dtype=np.uint64)
    st = est.mcest_direction_key(w.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), len(w),
                                 keys.ctypes.data_as(ctypes.POINTER(ctypes.c_uint64)))
    assert st == 0
    return keys.astype(np.float64)  # 53 of 64 bits: ties only within ~2^-26 in both coordinates


# ---- (a) the rough conductor ------------------------------------------------------

def conductor(alpha_u, alpha_v):
    return mi.load_dict({"type": "roughconductor", "distribution": "ggx", "alpha_u": alpha_u,
                         "alpha_v": alpha_v})


def interaction():
    si = mi.SurfaceInteraction3f()
    wi = np.array([0.35, -0.25, 0.9])
    si.wi = mi.Vector3f(*(wi / np.linalg.norm(wi)))  # local shading frame: n = +z, alpha_u along +x
    return si


def resampled_directions(true_bsdf, sampler_bsdf, n, seed):
    """n directions from sampler_bsdf.sample(), kept with probability w / 1 where
    w = true eval*cos / true pdf (<= 1 for a conductor: F G2 / G1)."""
    ctx, si = mi.BSDFContext(), interaction()
    rng = np.random.default_rng(seed)
    out, consistent = [], 0
    while len(out) < n:
        u = rng.random(4)
        bs, weight = sampler_bsdf.sample(ctx, si, u[0], mi.Point2f(u[1], u[2]))
        wo = bs.wo
        if not (weight[0] > 0.0 and wo[2] > 0.0):
            continue  # Mitsuba's invalid samples: no direction, weight 0
        pdf = true_bsdf.pdf(ctx, si, wo)
        w = true_bsdf.eval(ctx, si, wo)[0] / pdf
        if sampler_bsdf is true_bsdf and consistent < 200:  # sample()'s weight is eval/pdf
            assert abs(w - weight[0]) <= 1e-4 * max(1.0, w)
            consistent += 1
        assert w <= 1.0 + 1e-4, w
        if u[3] * 1.0 < w:
            out.append((wo[0], wo[1], wo[2]))
    return np.array(out)


def envelope(bsdf):
    """max over a fine grid of 2 pi eval(wo) (eval includes the cosine), times 1.25;
    the sampler below checks the bound on every proposal."""
    ctx, si = mi.BSDFContext(), interaction()
    best = 0.0
    for mu in np.linspace(0.0025, 0.9975, 200):
        s = math.sqrt(1 - mu * mu)
        for phi in np.linspace(0, 2 * math.pi, 400, endpoint=False):
            best = max(best, bsdf.eval(ctx, si, mi.Vector3f(s * math.cos(phi), s * math.sin(phi), mu))[0])
    return 1.25 * 2 * math.pi * best


def rejection_directions(bsdf, n, seed):
    """Directions with density eval*cos / albedo: uniform proposals on the upper
    hemisphere (density 1/2pi), accepted with probability 2pi eval / M."""
    ctx, si = mi.BSDFContext(), interaction()
    m = envelope(bsdf)
    rng = np.random.default_rng(seed)
    out, trials = [], 0
    while len(out) < n:
        u = rng.random(3)
        mu, phi = u[0], 2 * math.pi * u[1]
        s = math.sqrt(max(0.0, 1 - mu * mu))
        wo = mi.Vector3f(s * math.cos(phi), s * math.sin(phi), mu)
        ratio = 2 * math.pi * bsdf.eval(ctx, si, wo)[0]
        assert ratio <= m, "envelope too low: %g > %g" % (ratio, m)
        trials += 1
        if u[2] * m < ratio:
            out.append((wo[0], wo[1], wo[2]))
    return np.array(out), trials


N_DIRS = 5000


@pytest.fixture(scope="module")
def reference_keys(libs):
    _, est = libs
    dirs, trials = rejection_directions(conductor(0.2, 0.5), N_DIRS, seed=101)
    print("\nrejection sampler: %d directions from %d proposals" % (len(dirs), trials))
    return morton_keys(est, dirs)


def ks(lib, a, b):
    return mc.ks_test_2(lib, a, b, "two-sided", ALPHA, weight=mc.KS_WEIGHT_CANNER, method=mc.METHOD_EXACT)


def test_roughconductor_sampler_matches_eval(libs, reference_keys):
    lib, est = libs
    true = conductor(0.2, 0.5)
    keys = morton_keys(est, resampled_directions(true, true, N_DIRS, seed=202))
    r = ks(lib, keys, reference_keys)
    print(mc.format_result(lib, r, "sample()", "eval_rejection"))
    assert not r.reject, "Mitsuba's sampler disagrees with its eval() at alpha = %g" % ALPHA


def test_wrong_sampling_parameter_is_detected(libs, reference_keys):
    lib, est = libs
    true, wrong = conductor(0.2, 0.5), conductor(0.3, 0.5)  # alpha_u off by 50% in the sampler only
    keys = morton_keys(est, resampled_directions(true, wrong, N_DIRS, seed=303))
    r = ks(lib, keys, reference_keys)
    print(mc.format_result(lib, r, "buggy_sample()", "eval_rejection"))
    assert r.reject and r.p_value < 1e-6, "a sampler with the wrong alpha_u was not detected"


# ---- (b) one triangle light, rendered --------------------------------------------

# The paper-like scene of mcest_scene_paper, wound so that Mitsuba's one-sided
# area light faces the receiver (the paper's emitter emits from both sides).
TRIANGLE = [(-0.6, -0.4, 1.0), (0.1, 0.9, 0.8), (0.9, -0.3, 1.3)]


def f32(v):
    return struct.unpack("f", struct.pack("f", v))[0]


def exact_irradiance(est, triangle, radiance=1.0):
    s = McestScene()
    for k, v in enumerate(triangle):
        for j in range(3):
            s.triangle[3 * k + j] = v[j]
    s.point[:] = (0.0, 0.0, 0.0)
    s.normal[:] = (0.0, 0.0, 1.0)
    s.radiance = radiance
    e = ctypes.c_double()
    assert est.mcest_irradiance_exact(ctypes.byref(s), ctypes.byref(e)) == 0
    return e.value


def triangle_scene(path):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n")
        for v in TRIANGLE:
            f.write("%.9g %.9g %.9g\n" % v)
        f.write("3 0 1 2\n")
    return mi.load_dict({
        "type": "scene",
        "integrator": {"type": "direct"},
        "light": {"type": "ply", "filename": path, "face_normals": True,
                  "emitter": {"type": "area", "radiance": {"type": "rgb", "value": 1.0}}},
        # a 2e-3-wide receiver at the origin facing +z: its mean irradiance is the
        # point's to O(1e-6) relative (the linear variation averages out)
        "receiver": {"type": "rectangle", "to_world": mi.ScalarTransform4f.scale([1e-3, 1e-3, 1.0]),
                     "sensor": {"type": "irradiancemeter",
                                "film": {"type": "hdrfilm", "width": 1, "height": 1,
                                         "rfilter": {"type": "box"}}}},
    })


def test_rendered_irradiance_matches_lambert(libs):
    lib, est = libs
    with tempfile.TemporaryDirectory() as d:
        scene = triangle_scene(os.path.join(d, "triangle.ply"))
        renders = [float(np.array(mi.render(scene, seed=s, spp=16384))[0, 0, 0]) for s in range(64)]
    exact = exact_irradiance(est, [tuple(f32(c) for c in v) for v in TRIANGLE])
    assert abs(exact - 0.664537151664300) < 1e-6  # mcest_scene_paper's E, up to float32 vertices
    r = mc.t_test_1(lib, renders, exact, "two-sided", ALPHA)
    print("\n" + mc.format_result(lib, r, "mitsuba_pixel"))
    assert not r.reject, "Mitsuba's irradiance disagrees with Lambert's formula"
    # the same renders against a reference 1% off: the test has the power to see it
    off = mc.t_test_1(lib, renders, 1.01 * exact, "two-sided", ALPHA)
    assert off.reject and off.decision == -1
