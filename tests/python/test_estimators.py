"""mcstat.estimators: Lambert's formula against the 60-digit references of
the C tests (tests/data/ref_irradiance.h, written by
tools/refgen/make_irradiance_reference.py and read from the
header here), the estimators' means against it, the planted bugs caught
by mcstat.t_test, determinism over seeds / first_index / threads, the BRDF
samplers and reflected radiance, bad inputs, and a NumPy re-implementation
of estimator A agreeing in distribution.
"""
import os
import re

import numpy as np
import pytest

import mcstat
from conftest import ROOT, rel_err
from mcstat import estimators as est

EPS = np.finfo(float).eps


def _load_scenes():
    text = open(os.path.join(ROOT, "tests", "data", "ref_irradiance.h")).read()
    pat = (r'\{"(\w+)",\s*\{([^}]*)\},\s*\{([^}]*)\}, \{([^}]*)\}, (\S+),\s*(\S+), (\S+), (\S+),\s*"([^"]*)"\}')
    scenes = {}
    for m in re.finditer(pat, text):
        vec = lambda s: np.array([float.fromhex(v.strip()) for v in s.split(",")])
        scenes[m.group(1)] = dict(triangle=vec(m.group(2)).reshape(3, 3), point=vec(m.group(3)),
                                  normal=vec(m.group(4)), radiance=float.fromhex(m.group(5).rstrip(",")),
                                  E=float(m.group(9)), omega=float.fromhex(m.group(7).rstrip(",")))
    assert len(scenes) == int(re.search(r"#define N_REF_SCENES (\d+)", text).group(1))
    return scenes


SCENES = _load_scenes()


def geometry(s):
    return {k: s[k] for k in ("triangle", "point", "normal", "radiance")}


def kappa(s):
    """Cancellation in Lambert's sum (as tests/test_irradiance_exact.c)."""
    v = s["triangle"] - s["point"]
    terms = []
    for k in range(3):
        c = np.cross(v[k], v[(k + 1) % 3])
        th = np.arctan2(np.linalg.norm(c), v[k] @ v[(k + 1) % 3])
        terms.append(th * c[2] / np.linalg.norm(c))
    return sum(abs(t) for t in terms) / abs(sum(terms))


def tolerance(name, s):
    if name == "edge_on":  # E is proportional to a distance of 7e-9 carried to ~eps
        return 64 * EPS / 7e-9
    if name in ("sliver", "grazing"):
        return 8 * EPS * kappa(s)
    return 2e-14


# ---------------------------------------------------------------------------
# Lambert's formula and the plan
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("name", sorted(SCENES))
def test_irradiance_exact_against_references(name):
    s = SCENES[name]
    E = est.irradiance_exact(**geometry(s))
    assert rel_err(E, s["E"]) <= tolerance(name, s), (E, s["E"])
    plan = est.IrradiancePlan(**geometry(s))
    assert plan.exact == E
    assert rel_err(plan.solid_angle, s["omega"]) <= (tolerance(name, s) if name == "edge_on" else 1e-13)
    if s["E"] == 0.0:
        assert E == 0.0 and (est.irradiance("S", 10, **geometry(s)) == 0).all()


def test_paper_scene():
    sc = est.paper_scene()
    assert set(sc) == {"triangle", "point", "normal", "radiance"}
    ref = SCENES["paper"]
    assert np.array_equal(sc["triangle"], ref["triangle"]) and np.array_equal(sc["point"], ref["point"])
    assert np.array_equal(sc["normal"], ref["normal"]) and sc["radiance"] == 1.0
    assert sc["triangle"].shape == (3, 3) and sc["triangle"].dtype == np.float64
    sc["triangle"][0, 0] = 99.0  # a fresh copy each call
    assert est.paper_scene()["triangle"][0, 0] == -0.6
    plan = est.IrradiancePlan(**est.paper_scene())
    assert abs(plan.exact - 0.664537151664300) < 1e-14 and not plan.straddles and plan.n_fan == 1
    assert plan.n_poly == 3 and abs(plan.area - 0.995) < 1e-3 and plan.radiance == 1.0
    assert "IrradiancePlan" in repr(plan)


def test_geometry_forms():
    """triangle as nested lists or 9 numbers, normals of any length."""
    sc = est.paper_scene()
    E = est.irradiance_exact(**sc)
    assert est.irradiance_exact(triangle=sc["triangle"].tolist(), point=[0, 0, 0], normal=[0, 0, 1]) == E
    for length in (1e-300, 1e-100, 1e200, 1e300):
        assert est.irradiance_exact(triangle=sc["triangle"].ravel(), point=(0, 0, 0), normal=(0, 0, length)) == E
    assert est.irradiance_exact(**dict(sc, radiance=2.5)) == pytest.approx(2.5 * E, rel=1e-15)


# ---------------------------------------------------------------------------
# the estimators
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("scene", ["paper", "straddle", "far_paper", "tilted"])
def test_estimators_unbiased(scene):
    g = geometry(SCENES[scene])
    E = est.irradiance_exact(**g)
    sds = {}
    for k, m in enumerate(est.METHODS):
        e = est.irradiance(m, 400000, **g, seed=11 + k)
        assert e.shape == (400000,) and e.dtype == np.float64
        se = e.std(ddof=1) / np.sqrt(e.size)
        assert abs(e.mean() - E) < 5 * se, (scene, m, e.mean(), E, se)
        sds[m] = e.std()
    if scene == "paper":  # ERRATA 10: sigma_U > sigma_C > sigma_A > sigma_S
        assert sds["U"] > sds["C"] > sds["A"] > sds["S"], sds
        for m, want in zip("UCAS", (1.86, 1.28, 0.202, 0.042)):
            assert abs(sds[m] - want) < 0.02 * want


def test_planted_bugs_detected():
    """Each bug in A is caught by Welch's test against S on batch means at
    alpha = 0.01; the correct A is not."""
    sc = est.paper_scene()
    s = mcstat.batch_means(est.irradiance("S", 50000, **sc, seed=2), 100)
    right = mcstat.t_test(mcstat.batch_means(est.irradiance("A", 50000, **sc, seed=2), 100), s, alpha=0.01)
    assert right.decision == "equal"
    want = {"no_cosine": "greater", "barycentric": "less", "no_jacobian": "greater"}
    for bug in est.BUGS[1:]:
        a = mcstat.batch_means(est.irradiance("A", 50000, **sc, seed=2, bug=bug), 100)
        r = mcstat.t_test(a, s, alpha=0.01)
        assert r.reject and r.decision == want[bug], (bug, r.pvalue)


def test_determinism():
    sc = est.paper_scene()
    for m in est.METHODS:
        one = est.irradiance(m, 100000, **sc, seed=5, threads=1)
        assert np.array_equal(one, est.irradiance(m, 100000, **sc, seed=5))
        for t in (2, 3, 5):
            assert np.array_equal(one, est.irradiance(m, 100000, **sc, seed=5, threads=t)), (m, t)
        parts = [est.irradiance(m, b - a, **sc, seed=5, first_index=a) for a, b in
                 [(0, 1), (1, 777), (777, 50000), (50000, 100000)]]
        assert np.array_equal(one, np.concatenate(parts))
        assert not np.array_equal(one, est.irradiance(m, 100000, **sc, seed=6))
    plan = est.IrradiancePlan(**sc)
    assert np.array_equal(plan.estimates("A", 1000, seed=5, bug="barycentric"),
                          est.irradiance("A", 1000, **sc, seed=5, bug="barycentric"))
    # each bug and method draws from its own stream: with shared uniforms A
    # and A without the Jacobian would be strongly correlated
    a = est.irradiance("A", 4000, **sc, seed=5)
    for other in (est.irradiance("A", 4000, **sc, seed=5, bug="no_jacobian"), est.irradiance("S", 4000, **sc, seed=5)):
        assert abs(np.corrcoef(a, other)[0, 1]) < 0.08
    assert est.irradiance("S", 0, **sc).shape == (0,)
    big = 2 ** 64 - 10
    assert est.irradiance("C", 10, **sc, seed=2 ** 64 - 1, first_index=big).shape == (10,)


def numpy_estimator_A(triangle, n, rng):
    """Estimator A written from the paper (eq. 6) in vectorised NumPy, with
    NumPy's own generator: uniform point y = v0 + b1 e01 + b2 e02 on the
    triangle, L area cos cos' / r^2 (receiver at 0 facing +z)."""
    v0, v1, v2 = triangle
    e01, e02 = v1 - v0, v2 - v0
    nt = np.cross(e01, e02)
    area = 0.5 * np.linalg.norm(nt)
    nt /= np.linalg.norm(nt)
    u1, u2 = rng.random(n), rng.random(n)
    su = np.sqrt(u1)
    y = v0 + (1 - su)[:, None] * e01 + (u2 * su)[:, None] * e02
    r = np.linalg.norm(y, axis=1)
    cos_r = np.maximum(y[:, 2], 0) / r
    cos_e = np.abs(y @ nt) / r
    return area * cos_r * cos_e / r ** 2


def test_numpy_twin_of_A_agrees_in_distribution():
    sc = est.paper_scene()
    ours = est.irradiance("A", 20000, **sc, seed=9)
    theirs = numpy_estimator_A(sc["triangle"], 20000, np.random.default_rng(9))
    ks = mcstat.ks_test(ours, theirs, weight="none")
    assert ks.pvalue > 0.001, ks
    assert mcstat.ks_test(ours, theirs, method="simulate", n_sim=2000, seed=1).pvalue > 0.001
    assert mcstat.t_test(ours, theirs, alpha=0.001).decision == "equal"
    assert mcstat.var_test(ours, theirs, alpha=0.001).decision == "equal"
    # and the same test does see a planted bug
    bad = est.irradiance("A", 20000, **sc, seed=9, bug="barycentric")
    assert mcstat.ks_test(bad, theirs, weight="none").pvalue < 1e-6
    # same range, not the same numbers
    assert not np.allclose(np.sort(ours), np.sort(theirs), rtol=1e-12)
    assert abs(ours.min() - theirs.min()) < 0.05 and abs(ours.max() - theirs.max()) < 0.2


# ---------------------------------------------------------------------------
# BRDFs, Morton keys, reflected radiance
# ---------------------------------------------------------------------------

WO = np.array([0.3, 0.2, 0.9])
BRDFS = {"ward": lambda: est.ward(0.0, 0.6, 0.15, 0.05),
         "ward_diffuse": lambda: est.ward(0.2, 0.5, 0.1, 0.3),
         "as": lambda: est.ashikhmin_shirley(0.0, 0.2, 50, 500),
         "as_diffuse": lambda: est.ashikhmin_shirley(0.5, 0.05, 20, 20)}


@pytest.mark.parametrize("name", sorted(BRDFS))
def test_samplers(name):
    b = BRDFS[name]()
    assert b.model == ("ward" if name.startswith("ward") else "ashikhmin_shirley")
    plan = b.plan(WO)
    assert np.allclose(plan.wo, WO / np.linalg.norm(WO)) and not plan.has_albedo and np.isnan(plan.albedo)
    s = plan.sample(50000, seed=3)
    assert s.directions.shape == (50000, 3) and s.pdf.shape == (50000,) and s.keys.dtype == np.uint64
    assert s.trials == 50000
    assert np.allclose(np.linalg.norm(s.directions, axis=1), 1, atol=1e-12)
    assert np.allclose(s.pdf, plan.pdf(s.directions), rtol=1e-12, atol=0)  # pdf() renormalises its input
    assert np.array_equal(s.keys, est.direction_keys(s.directions))
    # the true density: E_p[f cos / p] over the upper hemisphere is the albedo
    up = s.directions[:, 2] > 0
    f = b.eval(s.directions, WO)
    ratio = np.where(up, f * s.directions[:, 2] / s.pdf, 0.0)
    albedo = plan.compute_albedo(1e-6, strict=False)
    assert plan.has_albedo and plan.albedo == albedo and 0 < albedo < 1
    assert abs(ratio.mean() - albedo) < 5 * ratio.std() / np.sqrt(ratio.size)
    # the exact sampler: upper hemisphere, acceptance = albedo / bound
    x = plan.sample_exact(20000, seed=4)
    assert x.pdf is None and (x.directions[:, 2] > 0).all() and x.trials >= 20000
    acc = plan.acceptance
    assert acc == pytest.approx(albedo / plan.bound)
    se = np.sqrt(20000 * (1 - acc)) / acc  # s.d. of the total number of trials (negative binomial)
    assert abs(x.trials - 20000 / acc) < 5 * se, (x.trials, 20000 / acc, se)


def test_sampler_determinism_and_threads():
    plan = BRDFS["as_diffuse"]().plan(WO)
    a = plan.sample(60000, seed=1, threads=1)
    for t in (2, 3):
        b = plan.sample(60000, seed=1, threads=t)
        assert np.array_equal(a.directions, b.directions) and np.array_equal(a.keys, b.keys)
    c = plan.sample(10000, seed=1, first_index=50000)
    assert np.array_equal(c.directions, a.directions[50000:])
    x1 = plan.sample_exact(60000, seed=2, threads=1)
    x3 = plan.sample_exact(60000, seed=2, threads=3)
    assert np.array_equal(x1.directions, x3.directions) and x1.trials == x3.trials
    h = plan.sample_exact(30000, seed=2, first_index=30000)
    assert np.array_equal(h.directions, x1.directions[30000:])
    plan.compute_albedo(strict=False)
    for m in est.RR_METHODS:
        assert np.array_equal(plan.reflected_radiance(m, 40000, seed=3, threads=1),
                              plan.reflected_radiance(m, 40000, seed=3, threads=4))


def test_ward_sampler_is_not_f_cos():
    """Section 3.2's finding, with these tools: Ward's own sampler does not
    draw from f cos / albedo, and a K-S test on Morton keys sees it."""
    plan = BRDFS["ward"]().plan(WO)
    a = plan.sample(100000, seed=1)
    up = a.directions[:, 2] > 0
    b = plan.sample_exact(100000, seed=1)
    r = mcstat.ks_test(a.keys[up].astype(float), b.keys.astype(float), weight="none")
    assert r.pvalue < 1e-3 and r.reject
    # two exact samples agree
    c = plan.sample_exact(100000, seed=2)
    assert mcstat.ks_test(b.keys.astype(float), c.keys.astype(float), weight="none").pvalue > 1e-3


@pytest.mark.parametrize("name", ["ward_diffuse", "as"])
def test_reflected_radiance_unbiased(name):
    plan = BRDFS[name]().plan(WO, albedo=True)
    assert plan.has_albedo
    Lr = plan.reflected_radiance_reference(1e-6, strict=False)
    for k, m in enumerate(est.RR_METHODS):
        e = plan.reflected_radiance(m, 100000, seed=k)
        assert abs(e.mean() - Lr) < 5 * e.std() / np.sqrt(e.size), (m, e.mean(), Lr)


def test_direction_helpers_against_numpy():
    w = np.random.default_rng(1).standard_normal((1000, 3)) * 3
    u = w / np.linalg.norm(w, axis=1, keepdims=True)
    st = est.direction_square(w)
    assert st.shape == (1000, 2)
    assert np.allclose(st[:, 0], (1 - u[:, 2]) / 2, atol=1e-15)
    assert np.allclose(st[:, 1], np.mod(np.arctan2(u[:, 1], u[:, 0]) / (2 * np.pi), 1.0), atol=1e-15)
    keys = est.direction_keys(w)
    q = np.minimum(np.floor(st * 2.0 ** 32), 2 ** 32 - 1).astype(np.uint64)
    want = np.zeros(1000, dtype=np.uint64)
    for bit in range(32):
        one = np.uint64(1)
        want |= ((q[:, 0] >> np.uint64(bit)) & one) << np.uint64(2 * bit + 1)
        want |= ((q[:, 1] >> np.uint64(bit)) & one) << np.uint64(2 * bit)
    assert np.array_equal(keys, want)
    assert est.direction_keys(w.reshape(10, 100, 3)).shape == (10, 100)
    x, y = u[:, 0], u[:, 1]
    d = np.array([0.3, -0.4, np.sqrt(0.75)])
    L = 1 + 0.5 * (x ** 3 - 3 * x * y ** 2) + 0.3 * np.cos(12 * y) + 4 * np.exp(20 * (u @ d - 1))
    assert np.allclose(est.environment_radiance(w), L, rtol=1e-13)


# ---------------------------------------------------------------------------
# bad inputs
# ---------------------------------------------------------------------------

def test_bad_inputs():
    sc = est.paper_scene()
    E = est.InvalidEstimatorArgument
    cases = [
        (lambda: est.irradiance("X", 10, **sc), E, "method must be 'U', 'C', 'A' or 'S'"),
        (lambda: est.irradiance("A", 10, **sc, bug="typo"), E, "bug must be None"),
        (lambda: est.irradiance("S", 10, **sc, bug="no_cosine"), est.UnsupportedError, "planted bugs"),
        (lambda: est.irradiance("A", -1, **sc), E, "n must be a non-negative int"),
        (lambda: est.irradiance("A", 10, **sc, seed=-1), E, "seed"),
        (lambda: est.irradiance("A", 10, **sc, threads=0), E, "threads"),
        (lambda: est.irradiance("A", 10, **sc, first_index=2 ** 64 - 5), E, "exceeds 2\\*\\*64"),
        (lambda: est.irradiance("A", 10, **dict(sc, triangle=np.zeros((2, 3)))), E, "shape"),
        (lambda: est.irradiance("A", 10, **dict(sc, normal=[0, 0, 0])), E, "normal non-zero"),
        (lambda: est.irradiance("A", 10, **dict(sc, radiance=-1.0)), E, "radiance"),
        (lambda: est.irradiance_exact(**dict(sc, point=[np.nan, 0, 0])), E, "finite"),
        (lambda: est.irradiance(3, 10, **sc), TypeError, "method must be a str"),
        (lambda: est.irradiance("A", 1.5, **sc), TypeError, "n must be an int"),
        (lambda: est.irradiance("A", 10, triangle=sc["triangle"]), TypeError, "incompatible function arguments"),
        (lambda: est.ward(0.0, 0.6, 0.0, 0.1), E, "alpha in"),
        (lambda: est.ashikhmin_shirley(0.0, 1.5, 10, 10), E, "Rs in"),
        (lambda: est.ward(0.0, 0.6, 0.1, 0.1).plan([0.3, 0.2, -0.9]), E, "wo.z > 0"),
        (lambda: est.ward(0.0, 0.6, 0.1, 0.1).plan(WO).reflected_radiance("rejection", 10), est.NotReadyError,
         "albedo"),
        (lambda: est.ward(0.0, 0.6, 0.1, 0.1).plan(WO).reflected_radiance("importance", 10), E, "method must be"),
        (lambda: est.ward(0.0, 0.6, 0.1, 0.1).plan(WO).compute_albedo(0.5), E, "rel_tol"),
        (lambda: est.direction_keys([[0.0, 0.0, 0.0]]), E, "non-zero"),
        (lambda: est.direction_keys([1.0, 2.0]), E, "shape"),
        (lambda: est.ward(0.0, 0.6, 0.1, 0.1).eval([[0, 0, 1.0]], [0, 0, 0]), E, "wo"),
    ]
    for f, exc, msg in cases:
        with pytest.raises(exc, match=msg):
            f()
    # a message naming the argument comes alone, without the C sentence
    with pytest.raises(E, match=r"^method must be 'U', 'C', 'A' or 'S'") as e:
        est.irradiance("X", 10, **sc)
    assert "NULL pointer" not in str(e.value)
    # a trial cap that the sampler must hit (acceptance ~0.9, 2000 directions)
    with pytest.raises(est.TrialLimitError, match="max_trials=1"):
        est.ward(0.0, 0.6, 0.15, 0.05).plan(WO).sample_exact(2000, max_trials=1)
    assert est.ward(0.0, 0.6, 0.15, 0.05).plan(WO).sample_exact(2000, max_trials=100).trials >= 2000
    for cls in (est.InvalidEstimatorArgument, est.UnsupportedError, est.TrialLimitError, est.NotReadyError,
                est.EstimatorNumericalError):
        assert issubclass(cls, est.EstimatorError) and issubclass(cls, ValueError)
    try:
        est.irradiance("A", 10, **dict(sc, normal=[0, 0, 0]))
    except est.EstimatorError as e:
        assert e.status == 1 and str(e).startswith("invalid argument")
