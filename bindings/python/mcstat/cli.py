# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Deprecated: the ``mcstat`` command is ``mcstat_app.cli`` (kept for one release)."""
import warnings

from mcstat_app.cli import DEFAULT_SEED, build_parser, main  # noqa: F401

warnings.warn("mcstat.cli is deprecated: the mcstat command is mcstat_app.cli", DeprecationWarning, stacklevel=2)
