"""Regressions of mcstat's renderer check found on Mitsuba 3 (fixed seeds).

The uniform cone warp (cos_cutoff -0.5, pdf masked to the cone) at the seed
the demo suite gave it at master seed 19: the cubature of pdf() came out
1.00081 with an error estimate of 6e-5 (short at the rim, a discontinuity),
and the mass route declared "pdf() integrates above 1" (p = 0) although the
unbiased Monte Carlo estimate was 1.0001 +- 0.0011 and every sample
succeeded.  That verdict now needs both estimates above 1; a pdf() that is
5% high still gets it.

The rough plastic (Beckmann, alpha 0.1, diffuse 1) at wi 89.9 degrees from
the normal: the null zoo's cells route rejected it at 19 of 20 seeds.  Its
pdf() integrates to 0.99930 (pdf_quadrature.py, an independent composite
quadrature), mcstat's cubature said 0.9842 +- 0.00035: the pilot's cells
there are slabs 0.01 rad by 3.5 rad, and a rule's points along 3.5 rad
missed the lobe that gathers around the mirror direction.  Rectangles are
now cut toward equal sides first.
"""
import os
import sys

import numpy as np
import pytest

_unavailable = os.environ.get("MCSTAT_MITSUBA_UNAVAILABLE")
if _unavailable:
    pytest.skip("the mitsuba wheel could not be installed here: " + _unavailable, allow_module_level=True)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba as mi  # noqa: E402

import mcstat  # noqa: E402
import mitsuba_adapters as ma  # noqa: E402

SEED = 1440543215812043827  # mcstat.testing.check_seed(19, <the cone's node id>, 0)
COS_CUTOFF = -0.5


@pytest.fixture(scope="module", autouse=True)
def variant():
    before = mi.variant()
    yield ma.use_variant()
    if before is not None and mi.variant() != before:
        mi.set_variant(before)


def cone(scale=1.0):
    def sample(u):
        u = ma._u32(u)
        return np.array(mi.warp.square_to_uniform_cone(mi.Point2f(u[:, 0], u[:, 1]), COS_CUTOFF),
                        dtype=np.float64).T

    def pdf(x):
        v = mi.Vector3f(*[np.asarray(x[:, i], dtype=np.float32) for i in range(3)])
        p = np.broadcast_to(np.array(mi.warp.square_to_uniform_cone_pdf(v, COS_CUTOFF), dtype=np.float64),
                            (len(x),))
        return scale * p * (x[:, 2] >= COS_CUTOFF - 1e-6)
    return sample, pdf


def test_cubature_short_at_the_rim_is_not_a_pdf_above_one():
    r = mcstat.check_warp(*cone(), domain="sphere", n=20000, seed=SEED, alpha=0.005)
    m = r.route("mass")
    # the finding (llvm_ad_rgb's float32 rounding of the rim made the old
    # cubature integrate above 1 beyond its error): the edge-aware cubature's
    # interval now holds 1
    assert r.mass - 4 * r.mass_error <= 1.0, (r.mass, r.mass_error)
    assert abs(r.mass_sampled - 1.0) < 3 * r.mass_sampled_se
    assert m.pvalue > 0.01 and not r.reject, str(r)


def test_a_pdf_five_percent_high_still_integrates_above_one():
    r = mcstat.check_warp(*cone(1.05), domain="sphere", n=20000, seed=SEED, alpha=0.005)
    assert r.route("mass").reject and r.route("mass").pvalue == 0.0, str(r)


PLASTIC_MASS = 0.99930  # pdf_quadrature.py 0.1 89.9 (both refinements 0.9993044)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_grazing_rough_plastic_cubature_holds_its_integral(seed):
    import pdf_quadrature as pq
    sample, eval_, pdf = ma.bsdf_callables(pq.plastic(0.1))
    r = mcstat.check_bsdf(sample, eval_, pdf, pq.direction(89.9), n=20000, seed=seed, alpha=0.01,
                          domain="hemisphere")
    assert abs(r.mass - PLASTIC_MASS) <= 4 * r.mass_error + 2e-4, (r.mass, r.mass_error)
    assert not r.route("cells").reject, str(r)
