# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""``python -m mcstat_app``: the mcstat command (see mcstat_app.cli)."""
import sys

from .cli import main

sys.exit(main())
