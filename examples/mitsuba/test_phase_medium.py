"""check_phase and check_medium on Mitsuba 3 (phase_medium.py's models,
scalar_rgb): hg, the homogeneous medium and delta tracking through a
heterogeneous grid pass at seed 0 (a fixed-seed regression test of the
adapters; the rates over seeds are RESULTS.md's "Phase functions and
distance sampling"), and one planted bug of each is rejected by the route
that sees it (the media's escapes weighed against T(tmax) too).  Skips as
test_mitsuba.py."""
import os
import sys

import pytest

_unavailable = os.environ.get("MCSTAT_MITSUBA_UNAVAILABLE")
if _unavailable:
    pytest.skip("the mitsuba wheel could not be installed here: " + _unavailable, allow_module_level=True)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scalar_scripts import import_scalar, rejected, scalar_rgb  # noqa: E402,F401  (the fixture: autouse)

pm = import_scalar("phase_medium")


def make(name, bug=None):
    if name == "hg":
        return pm.MitsubaPhase({"type": "hg", "g": 0.7}, bug)
    return pm.MitsubaMedium(bug) if name == "homogeneous" else pm.MitsubaHeterogeneous(bug)


@pytest.mark.parametrize("name", ["hg", "homogeneous", "heterogeneous"])
def test_correct_models_pass_at_seed_0(name):
    r = make(name).check(10000, 0)
    assert not r.reject, str(r)


@pytest.mark.parametrize("name,bug,route", [("hg", "pdf_g", "pdf_value"), ("homogeneous", "sampler", "mass"),
                                            ("heterogeneous", "restart", "cells"),
                                            ("heterogeneous", "accept", "mass"),
                                            ("homogeneous", "escape", "mass"), ("heterogeneous", "escape", "mass")])
def test_planted_bugs_are_rejected(name, bug, route):
    r = make(name, bug).check(10000, 0)
    assert r.reject and route in rejected(r), rejected(r)
