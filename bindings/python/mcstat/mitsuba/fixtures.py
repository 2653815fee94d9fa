# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""pytest fixtures for Mitsuba checks: in a conftest.py,

    pytest_plugins = ["mcstat.mitsuba.fixtures"]

then a test (or a module's autouse fixture) asks for ``mitsuba_variant``:
the variant set for the test module (``MCSTAT_MITSUBA_VARIANT``, else
`mcstat.mitsuba.pick_variant`'s choice: llvm_ad_rgb when it runs here,
else scalar_rgb), its name the fixture's value, the variant set before
restored after the module.  Mitsuba is imported when the fixture first
runs, not when the plugin loads.
"""
from __future__ import annotations

from typing import Iterator

import pytest

from . import _env


@pytest.fixture(scope="module")
def mitsuba_variant() -> Iterator[str]:
    """The Mitsuba variant set for this module (see the module's docstring)."""
    mi, _ = _env.modules()
    before = mi.variant()
    variant = _env.ensure_variant(_env.pick_variant())
    yield variant
    if before is not None and mi.variant() != before:
        mi.set_variant(before)
