# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Deprecated: ``python -m mcstat`` runs the mcstat command; use ``mcstat`` or
``python -m mcstat_app`` (kept for one release)."""
import sys
import warnings

warnings.warn("python -m mcstat is deprecated: run mcstat or python -m mcstat_app", DeprecationWarning)

from mcstat_app.cli import main  # noqa: E402

sys.exit(main())
