# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""``python -m mcstat``: the mcstat command (see mcstat.cli)."""
import sys

from .cli import main

sys.exit(main())
