"""The demo suite runs under mcstat's pytest plugin: without --mcstat-alpha
(or the ini option) its tests are skipped, saying so."""
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

_unavailable = os.environ.get("MCSTAT_MITSUBA_UNAVAILABLE")


def pytest_collection_modifyitems(config, items):
    here = os.path.dirname(os.path.abspath(__file__))
    mine = [i for i in items if str(i.fspath).startswith(here)]
    if _unavailable:
        why = "the mitsuba wheel could not be installed here: " + _unavailable
    elif config.getoption("--mcstat-alpha") is None and not config.getini("mcstat_alpha"):
        why = "the demo suite runs under mcstat's budget: pass --mcstat-alpha (e.g. 1e-2)"
    else:
        return
    for i in mine:
        i.add_marker(pytest.mark.skip(reason=why))
