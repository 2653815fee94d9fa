"""check_bsdf's discrete lobes on Mitsuba 3's dielectric, thin dielectric
and plastic (delta_lobes.py's models, scalar_rgb): correct ones pass at
seed 0 (a fixed-seed regression test; the rate over seeds is RESULTS.md's
"Delta and mixed lobes"), and a 5% error in the discrete weight, a
refraction index 1% off and (plastic) the diffuse weight off are rejected
by the route that sees them.  Skips as test_mitsuba.py."""
import os
import sys

import pytest

_unavailable = os.environ.get("MCSTAT_MITSUBA_UNAVAILABLE")
if _unavailable:
    pytest.skip("the mitsuba wheel could not be installed here: " + _unavailable, allow_module_level=True)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scalar_scripts import import_scalar, rejected, scalar_rgb  # noqa: E402,F401  (the fixture: autouse)

dl = import_scalar("delta_lobes")


MODELS = {
    "dielectric": (dl.DIEL, dl.lobes_dielectric),
    "thindielectric": (dl.THIN, dl.lobes_thin),
    "plastic": (dl.PLASTIC, dl.lobes_plastic),
}


@pytest.mark.parametrize("name,wi", [("dielectric", dl.ABOVE), ("dielectric", dl.BELOW),
                                     ("thindielectric", dl.ABOVE), ("plastic", dl.ABOVE)])
def test_correct_delta_lobes_pass_at_seed_0(name, wi):
    r = dl.MitsubaDelta(*MODELS[name]).check(wi, 10000, 0)
    assert not r.reject, str(r)
    assert r.n_lobe > 0 and r.route("weight").checked == r.n


@pytest.mark.parametrize("name,bug,route", [
    ("dielectric", "weight", "weight"), ("dielectric", "eta", "pdf_value"),
    ("thindielectric", "weight", "weight"),
    ("plastic", "weight", "weight"), ("plastic", "eta", "pdf_value"), ("plastic", "base", "weight"),
])
def test_planted_delta_bugs_are_rejected(name, bug, route):
    r = dl.MitsubaDelta(*MODELS[name], bug=bug).check(dl.ABOVE, 10000, 0)
    assert r.reject and route in rejected(r), rejected(r)
