# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The table of studies: one entry per study, from which the rest derives.

A new study is one `Study` below plus its module (``run`` and
``findings``), its report part and its ``$defs`` entry in schema.json
(``tests/python/test_reproduce_studies.py`` checks that the table and
the schema agree).  The planner's rule for it goes in `plan.Plan`.

The table's order is the order in which the studies run and appear in
results.json and report.md.  This module imports nothing of the studies,
so that the scene, the plan and the seed streams can read it cheaply.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any, Callable, Dict, List


@dataclass(frozen=True)
class Study:
    key: str       # its name in scene files (studies.KEY), the plan and results.json
    stream: int    # fixed number in its seed streams' keys: never change or reuse one
    section: str   # the paper's section, as the plan shows it
    title: str
    runner: str    # module of this package with run(ctx, plan) -> dict and findings(result) -> [str]
    report: str    # "module:function" of its report.md part: function(result, fig, transcript) -> [lines]
    schema: str    # its parameters' entry in schema.json's $defs
    # Wall-clock results (not reproducible): kept at results["KEY"] with
    # their own findings, out of results["studies"] and the main findings.
    wall_clock: bool = False

    def module(self) -> Any:
        return importlib.import_module(f"{__package__}.{self.runner}")

    def report_part(self) -> Callable[..., List[str]]:
        mod, fn = self.report.split(":")
        return getattr(importlib.import_module(f"{__package__}.{mod}"), fn)


STUDIES: List[Study] = [
    Study("irradiance", 1, "3.1", "Irradiance estimators (3.1)", "irradiance", "report:irradiance",
          "irradiance_study"),
    Study("sampling", 2, "3.2", "BRDF sampling (3.2)", "sampling", "report:sampling", "sampling_study"),
    Study("radiance", 3, "3.3", "Reflected radiance (3.3)", "radiance", "report:radiance", "radiance_study"),
    Study("bugs", 4, "3.4", "Planted bugs (3.4)", "bugs", "report:bugs", "bugs_study"),
    Study("diagnostics", 6, "diag", "Estimator diagnostics", "diagnose", "diagnose:report", "diagnostics_study"),
    # beyond the paper: chi-squared against Morton-key K-S on planted sampler bugs
    Study("sampler_bugs", 7, "3.2+", "Planted sampler bugs: chi-squared against K-S (3.2+)", "sampler_bugs",
          "report:sampler_bugs", "sampler_bugs_study"),
    # beyond the paper: the renderer's test kit (mcstat.check_bsdf) on the scene's BRDFs with planted bugs
    Study("renderer_check", 8, "kit", "The renderer's test kit on planted bugs", "renderer_check",
          "report:renderer_check", "renderer_check_study"),
    # beyond the paper: anytime-valid sequential tests on the planted bugs of 3.4 ("render until decided")
    Study("sequential", 9, "3.4+", "Sequential tests on the planted bugs (3.4+)", "sequential",
          "sequential:report", "sequential_study"),
    Study("timing", 5, "time", "Error against run time", "timing", "report:timing", "timing_study",
          wall_clock=True),
]

BY_KEY: Dict[str, Study] = {s.key: s for s in STUDIES}
