"""For the tests of the scalar_rgb example scripts (delta_lobes.py,
phase_medium.py): import such a script without leaving its variant set for
the other test modules, and a fixture that sets scalar_rgb around each test
and restores the variant before it."""
import importlib

import pytest

import mitsuba as mi


def import_scalar(name):
    """Imports the example module `name` (which sets scalar_rgb when it
    loads) and restores the variant that was set before."""
    before = mi.variant()
    module = importlib.import_module(name)
    if before is not None:
        mi.set_variant(before)
    return module


@pytest.fixture(autouse=True)
def scalar_rgb():
    before = mi.variant()
    mi.set_variant("scalar_rgb")
    yield
    if before is not None and before != "scalar_rgb":
        mi.set_variant(before)


def rejected(report):
    """The names of the routes that ran and rejected."""
    return {x.name for x in report.routes if x.state == "ran" and x.reject}
