# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""``mcstat reproduce``: plan the scene, run the studies, write the outputs."""
from __future__ import annotations

import os
import time
from typing import Any, Dict, List, Optional, TextIO

import numpy as np

import mcstat
from mcstat import estimators as est
from . import results
from .context import Context
from .plan import Plan
from .scene import load_scene
from .studies import STUDIES


def missing_report_packages() -> List[str]:
    """The report's optional dependencies that cannot be imported."""
    missing = []
    for name in ("matplotlib", "tqdm"):
        try:
            __import__(name)
        except ImportError:
            missing.append(name)
    return missing


def wall_clock_findings(res: Dict[str, Any]) -> List[str]:
    """The findings of the wall-clock studies that ran (after the reproducible ones)."""
    return [f for s in STUDIES if s.wall_clock for f in res.get(s.key, {}).get("findings", [])]


def command_line(scene: Optional[str], seed: int, quick: bool) -> str:
    """The command as recorded (without --out, so that two output folders compare equal)."""
    return ("mcstat reproduce" + (f" --scene {scene}" if scene else "") + f" --seed {seed}"
            + (" --quick" if quick else ""))


def reproduce(scene_path: Optional[str], out_dir: str, seed: int, quick: bool = False,
              threads: Optional[int] = None, progress: Optional[bool] = None, report: bool = True,
              out: Optional[TextIO] = None) -> Dict[str, Any]:
    """Run everything the scene calls for; write results.json (and report.md with PNGs)."""
    t_start = time.perf_counter()
    started = time.strftime("%Y-%m-%dT%H:%M:%S%z")
    scene = load_scene(scene_path)
    plan = Plan(scene, quick)
    ctx = Context(seed, threads=threads, progress=progress, out=out)
    os.makedirs(out_dir, exist_ok=True)
    cmd = command_line(scene_path, seed, quick)
    ctx.print(f"{cmd}: mcstat {mcstat.__version__}, seed {seed}" + (" (quick mode)" if quick else ""))
    ctx.print(plan.text())
    res: Dict[str, Any] = dict(
        command=cmd, seed=seed, quick=quick, scene_source=scene.source,
        versions=dict(mcstat=mcstat.__version__, libmcstat=mcstat.__libmcstat_version__,
                      libmcest=est.__libmcest_version__, numpy=np.__version__),
        scene=scene.data, plan=plan.to_dict(), studies={}, findings=[])
    transcripts: Dict[str, str] = {}
    findings: List[str] = []
    for study in STUDIES:
        if not plan.runs(study.key):
            continue
        module = study.module()
        t0, m0 = time.perf_counter(), ctx.mark()
        r = module.run(ctx, plan)
        r["wall_seconds"] = time.perf_counter() - t0
        transcripts[study.key] = ctx.since(m0)
        if study.wall_clock:
            # wall-clock results and findings stay apart from the reproducible part
            res[study.key] = r
            r["findings"] = module.findings(r)
        else:
            res["studies"][study.key] = r
            findings += module.findings(r)
    res["findings"] = findings
    res["seeds"] = dict(ctx.seeds)
    res["wall_started"] = started
    res["wall_threads"] = threads or mcstat.get_num_threads()
    res["wall_seconds"] = time.perf_counter() - t_start
    if report:
        from . import report as report_mod  # imports matplotlib: only when a report is wanted

        report_mod.write(out_dir, res, transcripts)
        res["wall_seconds"] = time.perf_counter() - t_start
    results.write(os.path.join(out_dir, "results.json"), res)
    ctx.print("\n== Findings")
    for f in findings + wall_clock_findings(res):
        ctx.print(f"- {f}")
    ctx.print(f"\nwrote {os.path.join(out_dir, 'results.json')}"
              + (f" and {os.path.join(out_dir, 'report.md')}" if report else "")
              + f" in {res['wall_seconds']:.1f} s")
    return res
