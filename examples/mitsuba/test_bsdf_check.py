"""mcstat.check_bsdf / check_emitter on Mitsuba 3's own BSDFs and area lights.

The BSDF is Mitsuba's anisotropic rough conductor (GGX, alpha_u = 0.2,
alpha_v = 0.05, visible-normal sampling, wi = (1, 1, 1)/sqrt 3: its
test_rough_conductor.py test05), through mitsuba_adapters:
  - unmodified, the check does not reject at seed 0.  This is a fixed-seed
    regression test of the adapters and of the check on this BSDF, not a
    calibration claim: a correct BSDF is rejected with probability up to alpha
    at any one seed (compare_chi2.py measures the rate over seeds: RESULTS.md);
  - each planted bug of mitsuba_adapters.PLANTED_BUGS (roughness * 1.1 in the
    sampler, in pdf(), in eval(), or the sample weight * 1.1) is rejected, by
    the route that sees that kind of bug.
The emitter is a rectangular area light seen from a point below it: correct,
it passes at seed 0; with a sampler that draws its first uniform as u^1.2
(while reporting pdf() and eval()/pdf() at the drawn direction) it is rejected.

Variant: llvm_ad_rgb when it runs here, else scalar_rgb (mitsuba_adapters.
pick_variant; MCSTAT_MITSUBA_VARIANT forces one).  The variant is set for this
module only and restored afterwards (test_mitsuba.py uses scalar_rgb).
Skips as test_mitsuba.py: only when `make mitsuba-test` could not install the
wheel (MCSTAT_MITSUBA_UNAVAILABLE); a missing or broken Mitsuba fails.
"""
import os
import sys

import pytest

_unavailable = os.environ.get("MCSTAT_MITSUBA_UNAVAILABLE")
if _unavailable:
    pytest.skip("the mitsuba wheel could not be installed here: " + _unavailable, allow_module_level=True)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba as mi  # noqa: E402
import mcstat  # noqa: E402

import mitsuba_adapters as ma  # noqa: E402

ALPHA = 0.01
BSDF = "conductor_ggx_aniso"
EMITTER_REF = (0.2, -0.1, 0.8)  # 0.2 below the rectangle's centre: it fills much of the sky


@pytest.fixture(scope="module", autouse=True)
def variant():
    before = mi.variant()
    v = ma.use_variant()
    print("\nMitsuba variant", v)
    yield v
    if before is not None and mi.variant() != before:
        mi.set_variant(before)


def check(bug, **kw):
    s, e, p, wi, domain = ma.config_callables(BSDF, bug)
    r = mcstat.check_bsdf(s, e, p, wi, domain=domain, seed=0, alpha=ALPHA, **kw)
    print(r)
    return r


def rejected_routes(r):
    return {x.name for x in r.routes if x.reject}


def test_correct_rough_conductor_passes_at_seed_0():
    r = check(None)
    assert not r.reject, rejected_routes(r)
    ran = {x.name for x in r.routes if x.state == "ran"}
    assert {"cells", "mass", "pdf_value", "weight", "support"} <= ran
    assert r.n_failed < 0.05 * r.n  # the sampler's own below-horizon losses, reported as failed


# bug -> the route that must see it
EXPECTED = {"sampler": "cells", "pdf": "pdf_value", "eval": "weight", "weight": "weight"}


@pytest.mark.parametrize("bug", ma.PLANTED_BUGS)
def test_planted_bug_is_rejected(bug):
    r = check(bug)
    assert r.reject and r.pvalue <= ALPHA
    assert EXPECTED[bug] in rejected_routes(r), rejected_routes(r)


def emitter_check(bug, ref=EMITTER_REF):
    s, e, p = ma.emitter_callables("rectangle", ref=ref, bug=bug)
    r = mcstat.check_emitter(s, e, p, seed=0, alpha=ALPHA)
    print(r)
    return r


def test_area_light_passes_and_planted_sampler_bug_is_rejected():
    ok = emitter_check(None)
    assert not ok.reject, rejected_routes(ok)
    bad = emitter_check("sampler")
    assert bad.reject and "cells" in rejected_routes(bad), rejected_routes(bad)


def test_small_area_light_passes():
    """The same light seen from the origin covers 8.7% of the sphere of
    directions: its pdf() (which integrates to 1 by construction) must be
    integrated over a small, sharp-edged support: a cubature that misses part
    of it finds a mass below 1 (0.99 is enough for mass and cells to reject)."""
    r = emitter_check(None, ref=(0.0, 0.0, 0.0))
    assert not r.reject, rejected_routes(r)
    assert abs(r.mass - 1.0) < 1e-3
